{{header}}// This model is not a POV-Ray finish: it is evaluated exactly in function pigments, which
// see only the hit point. Your scene must provide, per object and light:
//   * the object's unit normal as three functions of (x, y, z), world space (texture after transforms);
//   * the light: a point light's position (attenuation and spot go into the pigment);
//   * the eye position.
{{uv_doc}}// Facet_Pigment_Point({{signature}}) builds the pigment for one point light;
// light the object with that light alone (light_group) and finish { Facet_Finish }. Scale: the pigment
// is exact up to 1/Scale (use the light's brightest channel).

{{functions}}
// ---- The point light's pigment
{{shade}}
#declare Facet_Finish = finish { ambient 0 emission 0 diffuse 1 brilliance 0 specular 0 phong 0 }
#macro Facet_Pigment_Point({{signature}})
  // Floats: a function may read a float identifier but not a vector's component.
  #local Facet_Lx = LightPosition.x; #local Facet_Ly = LightPosition.y; #local Facet_Lz = LightPosition.z;
  #local Facet_Ex = Eye.x; #local Facet_Ey = Eye.y; #local Facet_Ez = Eye.z;
{{pigment}}#end
