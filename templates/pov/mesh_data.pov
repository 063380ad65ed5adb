// Mesh {{o}}: its corners' positions and normals, read from {{file}} (beside this scene: run POV-Ray in
// its folder).
// Texel K of the image (row 0 at the top, as POV-Ray maps it), each channel as the 16-bit integer it
// holds.
#declare Facet_Mesh{{o}}_Image = function { pigment { image_map { ppm "{{file}}" gamma 1.0 } } }
#declare Facet_Mesh{{o}}_Col = function(K) { (mod(K, {{width}}) + 0.5)/{{width}} }
#declare Facet_Mesh{{o}}_Row = function(K) { ({{height}} - floor(K/{{width}}) - 0.5)/{{height}} }
#declare Facet_Mesh{{o}}_R = function(K) {
  floor(Facet_Mesh{{o}}_Image(Facet_Mesh{{o}}_Col(K), Facet_Mesh{{o}}_Row(K), 0).red*65535 + 0.5)
}
#declare Facet_Mesh{{o}}_G = function(K) {
  floor(Facet_Mesh{{o}}_Image(Facet_Mesh{{o}}_Col(K), Facet_Mesh{{o}}_Row(K), 0).green*65535 + 0.5)
}
#declare Facet_Mesh{{o}}_B = function(K) {
  floor(Facet_Mesh{{o}}_Image(Facet_Mesh{{o}}_Col(K), Facet_Mesh{{o}}_Row(K), 0).blue*65535 + 0.5)
}
// Value I (0 … 17: the corners' positions, then their normals) of triangle Tri, 24 bits: two a texel of 9.
#declare Facet_Mesh{{o}}_Q = function(Tri, I) {
  select(mod(I, 2) - 0.5,
         Facet_Mesh{{o}}_R(9*Tri + floor(I/2))*256 + floor(Facet_Mesh{{o}}_G(9*Tri + floor(I/2))/256),
         mod(Facet_Mesh{{o}}_G(9*Tri + floor(I/2)), 256)*65536 + Facet_Mesh{{o}}_B(9*Tri + floor(I/2)))
}
// Value I of the three corners blended with the barycentrics A, B of corners 1 and 2.
#declare Facet_Mesh{{o}}_Blend = function(Tri, A, B, I) {
  (1 - A - B)*Facet_Mesh{{o}}_Q(Tri, I) + A*Facet_Mesh{{o}}_Q(Tri, I + 3) + B*Facet_Mesh{{o}}_Q(Tri, I + 6)
}
// The hit point and the interpolated (unnormalized) normal.
#declare Facet_Mesh{{o}}_PX = function(Tri, A, B) {
  {{lo_x}} + {{step_x}}*Facet_Mesh{{o}}_Blend(Tri, A, B, 0)
}
#declare Facet_Mesh{{o}}_PY = function(Tri, A, B) {
  {{lo_y}} + {{step_y}}*Facet_Mesh{{o}}_Blend(Tri, A, B, 1)
}
#declare Facet_Mesh{{o}}_PZ = function(Tri, A, B) {
  {{lo_z}} + {{step_z}}*Facet_Mesh{{o}}_Blend(Tri, A, B, 2)
}
#declare Facet_Mesh{{o}}_MX = function(Tri, A, B) {
  {{step_n}}*Facet_Mesh{{o}}_Blend(Tri, A, B, 9) - 1
}
#declare Facet_Mesh{{o}}_MY = function(Tri, A, B) {
  {{step_n}}*Facet_Mesh{{o}}_Blend(Tri, A, B, 10) - 1
}
#declare Facet_Mesh{{o}}_MZ = function(Tri, A, B) {
  {{step_n}}*Facet_Mesh{{o}}_Blend(Tri, A, B, 11) - 1
}
// uv_mapping's (u, v): triangle 2048·⌊v/4⌋ + ⌊u/4⌋, and the barycentric u − 4⌊u/4⌋ − 1 (likewise v).
#declare Facet_Mesh{{o}}_Tri = function(U, V) { 2048*floor(V/4) + floor(U/4) }
#declare Facet_Mesh{{o}}_Bary = function(U) { U - 4*floor(U/4) - 1 }
