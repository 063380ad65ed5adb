// facet — glTF 2.0 in and out, through tinygltf.
//
// Import: meshes (world space, node transforms applied), the first perspective
// camera, KHR_lights_punctual lights, and materials. A material with facet's
// vendor extension FACET_material is read exactly; otherwise glTF's
// metallic–roughness maps onto the catalog (glTF 2.0 specification, Appendix B):
//   specular: GGX, α = roughness², separable Smith G, Schlick F with
//             f0 = mix(0.04, baseColor, metallic)           — exact
//   diffuse:  Lambert, k_d = baseColor · (1 − metallic)      — exact for metals;
//             glTF weights a dielectric's diffuse by (1 − F), the catalog does not.
// Textures: baseColorTexture and metallicRoughnessTexture as textured parameters, baked
// where the mapping is not a plain factor (scene/gltf_images.h, docs/textures.md); the
// other maps are named in a note. A file without lights gets a headlight.
// Lights: C = colour · intensity / (683 lm/W · π) with inverse-square attenuation
// (kLumensPerWatt below) — exact for point and directional lights; `range` as the
// extension's recommended window (the catalog's inverse_square_range); spot cones are hard
// in facet (exact when inner = outer).
//
// Export: a valid glTF 2.0 file whose materials carry the full facet description
// (FACET_material) beside the nearest metallic–roughness fallback (as the catalog
// states it: each specular lobe's ModelDef::ggx_alpha, and a Fresnel term's
// normal_reflectance as a conductor's base colour); analytic spheres and planes
// become meshes plus FACET_object (their exact definition), lights carry
// FACET_light beside KHR_lights_punctual, the scene's ambient colour FACET_scene;
// the materials' images are copied beside a .gltf or held in a .glb (a diffuse sRGB
// colour map is also the fallback's baseColorTexture).
// None of the extensions is required: other viewers use the fallback.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "core/diagnostics.h"
#include "scene/scene.h"

namespace facet {

// glTF's lights are photometric (KHR_lights_punctual: candela for point and spot lights, lux
// for directional ones); facet's light colour C is radiometric as Blender's lights are (a white
// Lambert surface facing a light of colour C at distance 1 shows C, and a Blender point light
// of P watts is C = P / (4π²)). The two meet at the luminous efficacy glTF-Blender-IO converts
// with both ways (io_scene_gltf2's PBR_WATTS_TO_LUMENS): C = colour · intensity / (683 lm/W · π).
// So a file Blender's exporter wrote imports with the brightness Cycles rendered it with.
inline constexpr double kLumensPerWatt = 683;

struct GltfImportOptions {
  // The luminous efficacy of the import's conversion of candela and lux (kLumensPerWatt); 1
  // keeps photometric units (C = colour · intensity / π: the image in cd/m²).
  double lumens_per_watt = kLumensPerWatt;
  // Shades primitives that have no material; without it they are an error.
  std::optional<Material> default_material;
  // The scene file the import is for: the images the glTF file holds (GLB buffer views,
  // data URIs) and those the import bakes go to `<its stem>.textures/` beside it. Empty:
  // beside the glTF file, as for `<gltf stem>.json`.
  std::string output;
};

// A file an import writes beside its scene: an image the glTF file held, or one it baked.
struct GltfImportFile {
  std::string path, bytes;
};

// Throws InputError naming the file and the glTF path of the problem. `notes`
// receives what was approximate or ignored (alpha modes, spot cones, the default
// light…). The materials' images are decoded and read as the files `files` lists
// (core/texture.h's cache) before those are written: the caller writes them
// (write_import_files), or not at all when it passes none.
Scene import_gltf(const std::string& path, const GltfImportOptions& options, std::vector<std::string>& notes,
                  std::vector<GltfImportFile>* files = nullptr);
// The same from the file's bytes (`binary`: .glb). External buffers and images are read
// from `folder`; with an empty `folder` none is read (an error names it), so bytes
// from anywhere (the fuzzer's, say) touch no file. `path` names the input in errors.
Scene import_gltf_data(const std::string& data, bool binary, const std::string& path, const std::string& folder,
                       const GltfImportOptions& options, std::vector<std::string>& notes,
                       std::vector<GltfImportFile>* files = nullptr);
// Writes every file (its folder created), each atomically, all or none: on a failure the
// files already written are removed (and the folders created, if left empty), and IoError
// names the file.
void write_import_files(const std::vector<GltfImportFile>& files);

// The glTF meshes one scene file's objects reference (MeshReference), each file read
// once. Two steps, so that nothing is allocated for a scene over the limit: `add`
// finds each reference's primitives and counts them against the scene's limit
// (gltf_read.h: 100,000,000 triangles and as many vertices, and the memory
// available), `build` then reads them (identical references share one mesh).
// Problems go to the scene's sink under the object's key path; a problem inside
// a glTF file names that file and its glTF key path.
class GltfReferences {
 public:
  explicit GltfReferences(std::string scene_file);
  ~GltfReferences();
  GltfReferences(const GltfReferences&) = delete;
  GltfReferences& operator=(const GltfReferences&) = delete;
  // Object `object` of the scene, at key path `path`; `ref.file` from the working directory.
  void add(size_t object, const MeshReference& ref, const std::string& path, DiagnosticSink& sink);
  // Sets each referencing object's mesh (with its hierarchy), unless `sink` has problems.
  void build(std::vector<Object>& objects, DiagnosticSink& sink);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes `s` (objects without a material use `fallback`) as .gltf (one file,
// buffer embedded) or .glb, by the path's extension. Written whole or not at all.
void export_gltf(const Scene& s, const Material* fallback, const std::string& path, std::vector<std::string>& notes);

}  // namespace facet
