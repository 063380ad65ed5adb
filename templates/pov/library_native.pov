{{header}}// POV-Ray's own finish is this model exactly. Use the texture with plain light sources;
// attenuation: fade_distance 0 fade_power 2 is 1/d² (facet's inverse_square).
#declare Facet_{{name}}_Texture = {{texture}}{{emission}}