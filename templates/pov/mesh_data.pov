// Mesh {{o}}: its corners' positions and normals, read from {{file}} (beside this scene: run POV-Ray in
// its folder). Triangle Tri has texels 0 … 8 of row ⌊Tri/455⌋ (from the top), from column 9·(Tri mod 455).
#declare Facet_Mesh{{o}}_Image = function { pigment { image_map { ppm "{{file}}" gamma 1.0 } } }
#declare Facet_Mesh{{o}}_X = function(Tri) { 9*mod(Tri, 455) + 0.5 }
#declare Facet_Mesh{{o}}_Y = function(Tri) { ({{height}} - floor(Tri/455) - 0.5)/{{height}} }
// Texel J's channels as the 16-bit integers they hold.
#declare Facet_Mesh{{o}}_R = function(X, Y, J) { floor(Facet_Mesh{{o}}_Image((X + J)/4095, Y, 0).red*65535 + 0.5) }
#declare Facet_Mesh{{o}}_G = function(X, Y, J) { floor(Facet_Mesh{{o}}_Image((X + J)/4095, Y, 0).green*65535 + 0.5) }
#declare Facet_Mesh{{o}}_B = function(X, Y, J) { floor(Facet_Mesh{{o}}_Image((X + J)/4095, Y, 0).blue*65535 + 0.5) }
// A texel holds two 24-bit values: the first in R and the high byte of G, the second in the rest.
#declare Facet_Mesh{{o}}_QA = function(X, Y, J) {
  Facet_Mesh{{o}}_R(X, Y, J)*256 + floor(Facet_Mesh{{o}}_G(X, Y, J)/256)
}
#declare Facet_Mesh{{o}}_QB = function(X, Y, J) {
  mod(Facet_Mesh{{o}}_G(X, Y, J), 256)*65536 + Facet_Mesh{{o}}_B(X, Y, J)
}
// The hit point and the interpolated (unnormalized) normal: values 0 … 8 are the corners' positions,
// 9 … 17 their normals, value I in texel ⌊I/2⌋; corners 1 and 2 weigh A and B, corner 0 the rest.
{{components}}// uv_mapping's (u, v): triangle 2048·⌊v/4⌋ + ⌊u/4⌋, and the barycentric u − 4⌊u/4⌋ − 1 (likewise v).
#declare Facet_Mesh{{o}}_Tri = function(U, V) { 2048*floor(V/4) + floor(U/4) }
#declare Facet_Mesh{{o}}_Bary = function(U) { U - 4*floor(U/4) - 1 }
