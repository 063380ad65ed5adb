
// {{what}} (docs/textures.md, "Normal maps"; glTF 2.0 §3.9.3): n_t = normalize((2·rgb − 1)
// ⊗ (s, s, 1)), y negated first for DirectX's green-down maps; {{whose}} normal is
// normalize(n_t.x·T + n_t.y·B + n_t.z·n), T = t Gram–Schmidt'd against n, B = w·(n × T).
fn {{function}}(n: vec3<f32>, t: vec3<f32>, w: f32) -> vec3<f32> {
    let c = 2.0 * {{map}} - 1.0;
    let nt = normalize(vec3<f32>({{strength}} * c.x, {{green}}{{strength}} * c.y, c.z));
    let T = normalize(t - n * dot(n, t));
    let B = w * cross(n, T);
    return normalize(nt.x * T + nt.y * B + nt.z * n);
}
