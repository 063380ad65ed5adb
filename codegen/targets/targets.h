// facet — the code generators: one material, equivalent code for each target.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "catalog/program.h"
#include "scene/scene.h"

namespace facet {

enum class Target { Glsl, Glsl450, Essl, Osl, Pov, Hlsl, Wgsl };
std::optional<Target> parse_target(const std::string& name);
const char* target_name(Target t);
const std::vector<Target>& all_targets();

// How POV-Ray draws a scene (facet generate --pov-route). auto: POV-Ray's own
// finish where every material is one exactly (meshes included: POV-Ray blends
// their normals barycentrically, as facet does), else function pigments
// everywhere; native: the finish, or an error saying why not; exact: function
// pigments everywhere; fast: as auto, but a mesh with an isotropic material
// gets slope tables (approximate, measured; docs/povray-meshes.md).
enum class PovRoute { Auto, Native, Exact, Fast };
std::optional<PovRoute> parse_pov_route(const std::string& name);

struct GenerateOptions {
  Target target = Target::Glsl;
  PovRoute pov_route = PovRoute::Auto;
  bool library = false;        // just the functions (GLSL, OSL) / an include file (POV-Ray)
  std::optional<Scene> scene;  // OSL: its lights; POV-Ray: the whole scene. Default: default_scene()
  std::string source;          // named in the header comment
  // OSL: the material of the scene's objects that name none (default: the material generated),
  // whose cut-outs the shader's shadow rays must see too.
  const Material* fallback = nullptr;
  // OSL: the file the shader reads an image's colour from (by the image's path, Texels::path)
  // instead of the image: Cycles' image reader premultiplies a PNG's colour by its alpha, so
  // facet's Cycles renderer hands it a copy without alpha (its alpha it reads from the image).
  std::map<std::string, std::string> image_files;
};

std::string generate(const Material& m, const GenerateOptions& options);

// ---- Parts the renderers assemble themselves.

// Where the light loop (facet_shade) reads its lights: every light through FacetLight
// facet_light(int i), i below the light count. Uniforms: what `facet generate` writes for an
// engine, a uniform array of FACET_MAX_LIGHTS (8; GLSL and HLSL: in the FacetScene block or
// cbuffer at set 0, binding 0; WGSL: its uniform buffer). Buffer: any number, as facet's own
// renderers pass them (targets/glsl_lights.h): GLSL 3.30 a samplerBuffer facet_light_buffer
// (4 texels a light), ES 3.00 a sampler2D facet_light_texture (kLightsPerRow lights a row),
// glsl450 a storage buffer, HLSL a StructuredBuffer and WGSL a storage buffer at set (group)
// kLightSet, binding 0; the FacetScene block, cbuffer or uniform buffer keeps the camera, the
// ambient colour and the count.
enum class LightSource { Uniforms, Buffer };

// GLSL in pieces: the library (constants, terms, facet_reflect), the light loop
// (the lights' declarations, facet_shade) and the standalone main.
struct GlslParts {
  std::string header, library, lights, main;
};
GlslParts glsl_parts(const MaterialProgram& p, Target dialect, const std::string& source,
                     LightSource lights = LightSource::Uniforms);

// The G-buffer shading pass (renderers/gbuffer.h) in `dialect` (Glsl, Glsl450, Essl):
// the material's library and light loop (LightSource::Buffer) under
// templates/glsl/gbuffer_shade.glsl's main, which reads the seven G-buffer images at its pixel
// (samplers facet_gbuffer_position … facet_gbuffer_color0, and facet_gbuffer_visibility, a 2D
// array; Vulkan: set 1, bindings 0-6) and writes facet_color.
std::string glsl_gbuffer_shading_source(const Material& m, Target dialect);

// HLSL in the same pieces (templates/hlsl): the library, the light loop (the FacetScene
// cbuffer, facet_shade, which asks facet_visibility(p, l, d, i) for light i) and the
// standalone Shader Model 5 main.
struct HlslParts {
  std::string header, library, lights, main;
};
HlslParts hlsl_parts(const MaterialProgram& p, const std::string& source, LightSource lights = LightSource::Uniforms);
// WGSL in pieces, as GLSL: the library (constants, textures, terms, facet_reflect), the
// lights (the FacetScene uniform buffer, facet_shade, which calls facet_visibility(p, l,
// d, light) that the code around defines) and the standalone @fragment entry point.
struct WgslParts {
  std::string header, library, lights, main;
};
WgslParts wgsl_parts(const MaterialProgram& p, const std::string& source, LightSource lights = LightSource::Uniforms);
// The G-buffer shading pass in WGSL (the wgpu renderer's): the material's library and
// light loop (LightSource::Buffer) under templates/wgsl/gbuffer_shade.wgsl, whose
// facet_vertex draws one full-screen triangle and whose facet_gbuffer_shade reads the seven
// G-buffer images (@group(1), bindings 0–6; 6 a 2D array) at its pixel; the material's
// images are @group(0) from binding 1.
std::string wgsl_gbuffer_shading_source(const Material& m);

// The robustness sweep's programs (facet/sweep.h): the material's functions
// under a main that evaluates the sweep grid. GLSL's in `dialect` Glsl (uniform vec2
// facet_resolution; Essl the same) or Glsl450 (Vulkan: the grid's side from the push constants, ivec2).
std::string glsl_sweep_source(const Material& m, Target dialect = Target::Glsl);
std::string hlsl_sweep_source(const Material& m);  // a pixel shader: one direction set per pixel
// WGSL's: facet_vertex and facet_sweep (templates/wgsl/sweep.wgsl), the grid's side in the
// uniform buffer at @group(0) @binding(0).
std::string wgsl_sweep_source(const Material& m);
std::string osl_sweep_source(const Material& m);
std::string generate_pov_sweep(const Material& m);

// How POV-Ray evaluates this material in this scene.
struct PovPlan {
  bool native = false;  // POV's own finish reproduces the model exactly
  std::string reason;   // why not, when not
  // Renders to sum for the exact image (Declare=Facet_Light=i, i < passes);
  // one render with Facet_Light=-1 is exact when passes == 1.
  int passes = 1;
  // One line per object: how it is drawn and how exactly (generate_pov_files
  // adds what it measured, e.g. a mesh's data precision).
  std::vector<std::string> routes;
};
// Throws std::invalid_argument when `route` is native and a material is not.
PovPlan pov_plan(const Material& m, const Scene& s, PovRoute route = PovRoute::Auto);
// Objects without a material of their own use `fallback` (may be null when every object has one).
PovPlan pov_plan(const Scene& s, const Material* fallback, PovRoute route = PovRoute::Auto);

// A POV-Ray scene and the files it reads, which go beside it: a mesh on the
// function route reads its geometry from an image (targets/pov_mesh.h).
struct PovFile {
  std::string name;                          // relative to the scene's folder
  std::function<void(std::ostream&)> write;  // writes it (a mesh's lists or data: hundreds of MB)
};
struct PovOutput {
  std::string code;
  std::vector<PovFile> files;
  PovPlan plan;
};
// `stem` starts the files' names (the scene file's own stem, say).
PovOutput generate_pov_files(const Scene& s, const Material* fallback, const std::string& source, PovRoute route,
                             const std::string& stem);
// The POV-Ray library (--library) of `m` and the files it reads beside it (a textured
// material's images), named from `stem`.
PovOutput generate_pov_library(const Material& m, const std::string& source, PovRoute route, const std::string& stem);
// The POV-Ray scene of a whole scene with its objects' own materials; throws
// std::invalid_argument when it needs files beside it (use generate_pov_files).
std::string generate_pov_scene(const Scene& s, const Material* fallback, const std::string& source);

}  // namespace facet
