
// ---- Standalone entry point: world-space position and normal from the vertex shader
{{inputs}}
void main()
{
    vec3 n = normalize(facet_normal);
    vec3 v = normalize(facet_camera_position.xyz - facet_position);
#ifdef FACET_VERTEX_TANGENT
    vec3 t = normalize(facet_vertex_tangent - n * dot(n, facet_vertex_tangent));
#else
    vec3 t = facet_tangent(n);
#endif
{{sample}}    facet_color = vec4(facet_shade(facet_position, n, v, t), 1.0);
}

// This standalone shader casts no shadows; an engine puts its shadow lookup here.
float facet_visibility(vec3 p, vec3 l, float d, int light)
{
    return 1.0;
}
