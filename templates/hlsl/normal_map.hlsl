
// {{what}} (docs/textures.md, "Normal maps"; glTF 2.0 §3.9.3): n_t = normalize((2·rgb − 1)
// ⊗ (s, s, 1)), y negated first for DirectX's green-down maps; {{whose}} normal is
// normalize(n_t.x·T + n_t.y·B + n_t.z·n), T = t Gram–Schmidt'd against n, B = w·(n × T).
float3 {{function}}(float3 n, float3 t, float w)
{
    float3 c = 2.0 * {{map}} - 1.0;
    float3 nt = normalize(float3({{strength}} * c.x, {{green}}{{strength}} * c.y, c.z));
    float3 T = normalize(t - n * dot(n, t));
    float3 B = w * cross(n, T);
    return normalize(nt.x * T + nt.y * B + nt.z * n);
}
