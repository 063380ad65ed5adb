
// {{what}} (docs/textures.md, "Normal maps"; glTF 2.0 §3.9.3): n_t = normalize((2·rgb − 1)
// ⊗ (s, s, 1)), y negated first for DirectX's green-down maps; {{whose}} normal is
// normalize(n_t.x·T + n_t.y·B + n_t.z·n), T = t Gram–Schmidt'd against n, B = w·(n × T).
vec3 {{function}}(vec3 n, vec3 t, float w)
{
    vec3 c = 2.0 * {{map}} - 1.0;
    vec3 nt = normalize(vec3({{strength}} * c.x, {{green}}{{strength}} * c.y, c.z));
    vec3 T = normalize(t - n * dot(n, t));
    vec3 B = w * cross(n, T);
    return normalize(nt.x * T + nt.y * B + nt.z * n);
}
