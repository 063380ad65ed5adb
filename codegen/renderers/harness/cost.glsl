out vec4 facet_color;

void main()
{
    vec3 dir, p, n;
    if (!facet_camera_hit(dir, p, n)) {
        facet_color = vec4(0.0);
        return;
    }
    vec3 l = normalize(facet_light_position - p);
    vec3 radiance = material_ambient * facet_ambient + material_emission
                  + facet_light_color * facet_reflect(n, l, -dir, facet_tangent(n));
    facet_color = vec4(radiance, 1.0);
}
