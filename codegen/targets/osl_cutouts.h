// facet — OSL's cut-outs (glTF's alphaMode MASK, Material::masked()) and the image reads they
// share with the textured parameters. Private to codegen/targets (osl.cpp, osl_cutouts.cpp).
//
// Cycles draws a cut-out in two halves. Camera rays: where the shaded surface's alpha is below
// its cutoff the shader returns a Transparent BSDF alone, and Cycles' path goes on through it
// (transparent bounces, which max bounces 0 does not stop). Shadow rays: the shader casts its
// own with trace(), which meets the nearest surface whatever its shader; the shader therefore
// knows the scene's cut-out objects (their shapes, their materials' alpha, told apart by their
// pass index) and goes on past each surface met that is cut out there (facet_blocked).
#pragma once

#include <string>

#include "scene/scene.h"
#include "targets/cfamily.h"
#include "targets/targets.h"
#include "targets/texture_code.h"

namespace facet::targets {

// Image `c` sampled at the enclosing code's s0, t0, s1, t1 (glTF's coordinates): the
// statements, whose locals start with `c.name`, and the value's expression (texture_value_code():
// factor, channel, the vertex colour's facet_color0/facet_alpha0 where `c` reads it, offset,
// clamp). `file` is the OSL string the image is read from (unused where `c` has no image).
struct OslSample {
  std::string statements, value;
};
OslSample osl_sample(const CPrinter& pr, const TextureCall& c, const std::string& file);

// The file a shader reads image `c` from, as an OSL string literal: the image itself, or the
// copy GenerateOptions::image_files names for it where `c` reads colour (Cycles' image reader,
// OpenImageIO, premultiplies a PNG's colour by its alpha; the alpha itself it keeps).
std::string osl_image_file(const TextureCall& c, const GenerateOptions& o);
// Whether image `c`'s colour, as Cycles reads it, is premultiplied: it has a texel of alpha
// below 1 and the shader reads its colour from the image itself.
bool osl_premultiplied(const TextureCall& c, const GenerateOptions& o);

struct OslCutouts {
  bool any = false;       // the scene has a cut-out object: shadow rays go through facet_blocked()
  bool images = false;    // some cut-out samples an image: the shader needs templates/osl/textures.osl
  bool own_uv = false;    // the shaded material's alpha comes from an image: it takes facet_uv0, facet_uv1
  std::string functions;  // the alpha functions, facet_kept_hit(), facet_blocked(), facet_far_side()
  std::string test;       // the shader's statements: the shaded surface's own cut-out
};

// Material `m`'s shader on `scene` (its objects without a material of their own drawn with
// `fallback`): what it needs for the scene's cut-outs.
OslCutouts osl_cutouts(const CPrinter& pr, const Material& m, const Scene& scene, const Material& fallback,
                       const GenerateOptions& o);

// facet's y-up world in Blender's z-up one: (x, y, z) → (x, −z, y).
Vec3 osl_blender(const Vec3& p);

}  // namespace facet::targets
