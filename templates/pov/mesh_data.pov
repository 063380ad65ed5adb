// Mesh {{o}}: its corners' positions and normals, read from {{file}} (beside this scene: run POV-Ray in
// its folder). Triangle t owns the 2 × 2 texels of block (t mod {{blocks}}, ⌊t/{{blocks}}⌋); uv_mapping's (u, v)
// counts texels (column, row from the bottom), and `interpolate 2` blends a block's texels linearly.
#declare Facet_Mesh{{o}}_Image = function { pigment { image_map { ppm {{file}} gamma 1.0 interpolate 2 } } }
// Plane K's channels at (U, V): planes 0 and 1 hold the positions' hi and lo, 2 and 3 the normals'
// (4 and 5, with texture coordinates: u₀, v₀, u₁; 6 and 7: v₁ and, with a normal map's tangents,
// their x, y; 8 and 9: their z, w and, with vertex colours, r; 10 and 11: the colours' g, b, a).
#declare Facet_Mesh{{o}}_R = function(U, V, K) {
  Facet_Mesh{{o}}_Image((U + 0.5)/{{width}}, (V + K*{{plane_rows}} + 0.5)/{{height}}, 0).red
}
#declare Facet_Mesh{{o}}_G = function(U, V, K) {
  Facet_Mesh{{o}}_Image((U + 0.5)/{{width}}, (V + K*{{plane_rows}} + 0.5)/{{height}}, 0).green
}
#declare Facet_Mesh{{o}}_B = function(U, V, K) {
  Facet_Mesh{{o}}_Image((U + 0.5)/{{width}}, (V + K*{{plane_rows}} + 0.5)/{{height}}, 0).blue
}
// The hit point (P) and the interpolated, unnormalized normal (M): offset + step·65535·(32768·hi + lo).
{{components}}
