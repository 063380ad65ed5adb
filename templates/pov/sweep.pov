{{header}}#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { orthographic location <0.5, 0.5, -1> direction z right x up y }

{{functions}}
// ---- The sweep grid
{{grid}}
// The reflectance at the grid's direction set (x, y); 1 where it is finite and ≥ 0
// (POV-Ray would render a NaN black, like a 0).
{{reflect}}#declare Facet_Ok = function(V) { (V >= 0) & (V <= 1e300) }
polygon {
  5, <0, 0, 0>, <1, 0, 0>, <1, 1, 0>, <0, 1, 0>, <0, 0, 0>
{{pigment}}  finish { ambient 0 diffuse 0 specular 0 phong 0 emission 1 }
}
