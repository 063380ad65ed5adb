// facet — textured parameters on POV-Ray's function route (docs/textures.md).
// Private to codegen/targets (pov.cpp, pov_functions.cpp).
//
// POV-Ray reads each image through `image_map`, but facet hands it its own decoded
// texels: a binary PPM of 16 bits a channel beside the scene (k/255 and k/65535 are
// both whole multiples of 1/65535, so every texel is exact), its alpha in a PGM where a
// parameter reads it, each with the row of zeros on top that POV-Ray's PPM reader needs
// (pov_mesh.h). Without `interpolate` an image_map returns the nearest texel, so read at
// a texel's centre it returns that texel's value, and the file's row j lies at
// y = 1 − (j + 1 + ½)/(H + 1) (POV-Ray puts the first row at the top, y = 1). The
// texel functions Facet_Texel{k}_R, _G, _B, _A(I, J) wrap the indices and decode sRGB;
// Facet_Sample_<parameter>(S, T) (IR, printed like every function) applies the
// transform, the filter, the factor and the clamp; where the value reads the vertex colour
// it takes its R, G, B, A after S and T (without an image, them alone).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "core/ir.h"
#include "targets/texture_code.h"

namespace facet::targets {

struct PovTexture {
  TextureCall call;
  int image = 0;         // k of Facet_Texel{k}_…: the scene's images, counted from 0 (−1: none, the vertex colour alone)
  std::string file;      // the PPM beside the scene
  std::string alpha;     // the PGM of its alpha, or "" where no parameter reads it
};

// The declarations of texture k's image functions and texel readers.
std::string pov_texture_declarations(const PovTexture& t);
// The PPM (alpha: the PGM of the alpha channel) of t's texels.
void write_pov_texture_image(std::ostream& out, const Texels& t, bool alpha);
// Facet_Sample_<name>(S, T[, R, G, B, A]): the textured parameter's value at texture
// coordinates (S, T) on a surface of vertex colour (R, G, B, A).
ir::FunctionPtr pov_sample_function(const PovTexture& t);
// Lane k (0–2) of colour texture t as a number named `name`_r, _g or _b: the image's channel k (and
// the vertex colour's), lane k of its factor and offset. The normal maps' r, g, b and a colour's
// max₃ are sampled so.
PovTexture pov_lane(const PovTexture& t, int k, const std::string& name);
// Facet_Sample_<name>_r, _g, _b (each lane of colour texture t's value, sampled as a number) and,
// last, Facet_Sample_<name>(S, T[, R, G, B, A]) = their max: max₃ of t's value
// (TexturedInput::max_of), since POV-Ray's functions are scalar.
std::vector<ir::FunctionPtr> pov_max_sample_functions(const PovTexture& t, const std::string& name);
// Facet_Rgb_R, _G, _B(R, G, B): a colour from three numbers, channel by channel (POV-Ray's
// functions are scalar): what a colour's vertex colour is made of. Declared once in a scene
// whose materials read the vertex colour.
std::string pov_rgb_declarations();

}  // namespace facet::targets
