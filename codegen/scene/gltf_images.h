// facet — a glTF file's images and its materials' textures, for `facet import-gltf`.
//
// facet's materials name image files (docs/textures.md), so an image a glTF file holds
// (in a GLB's buffer view, or as a data URI) becomes a file beside the scene the import
// writes (`<scene stem>.textures/imageN_<name>.png|jpg`, its bytes as they were); an
// external image is referenced where it is. The images are decoded here, once, by
// core/texture.h, and held in its cache under the path they will be written at, so the
// scene reads them before any file is written; the files are written by the caller,
// all or none (write_import_files in gltf.h).
//
// glTF's metallic–roughness is mapped onto the catalog with textures where the map is
// a plain factor of a texel (k_d = base·(1 − metallic) with a base colour map), and
// baked texel by texel where it is not (α = (roughness·G)², k_d and f0 mixing base
// colour and B = metallic): docs/textures.md, "glTF import".
#pragma once

#include <array>
#include <map>
#include <set>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "catalog/texture.h"
#include "core/texture.h"
#include "scene/gltf.h"
#include "scene/gltf_read.h"

namespace facet::gltf_detail {

// The JSON of extension `name` in a glTF object's extensions (tinygltf's string), or null.
nlohmann::json extension_of(const std::string& extensions_json, const char* name);

// One glTF textureInfo, resolved: facet's texture JSON for it (the image's absolute
// path, filter, wrap, uv, transform; colorspace and factor left to the caller) and the
// decoded image.
struct TextureUse {
  nlohmann::json spec;
  std::shared_ptr<const Texels> texels;
  std::string key;  // the textureInfo's glTF key path
  Sampler sampler;
  int uv = 0;
  // The same texture coordinates (set and transform) as `o`.
  bool same_mapping(const TextureUse& o) const;
};

class GltfImages {
 public:
  // External images are read from `folder` (none with an empty one: an import from
  // memory). `output`: the scene file the import will write (empty: beside the glTF
  // file, as `<gltf stem>.json`); its folder and stem place the extracted and baked images.
  GltfImages(const tinygltf::Model& model, std::string gltf_path, std::string folder, const std::string& output,
             std::vector<std::string>& notes);

  // The textureInfo at glTF key path `key` ("materials[0].pbrMetallicRoughness.baseColorTexture");
  // InputError naming the file and `key` (+ ".index", ".texCoord") when it cannot be read.
  TextureUse texture(int index, int tex_coord, const std::string& extensions_json, const std::string& key);
  // The file of image `image` (named at `key`), as an absolute path: an embedded image's
  // planned file, an external one's own when it lies inside the scene's folder, else its
  // planned copy (a scene names images inside its own folder only: catalog/texture.cpp).
  std::string image_file(int image, const std::string& key);
  // A 16-bit PNG computed by the import, planned as `<textures folder>/<name>.png`; its path.
  std::string bake(const std::string& name, int width, int height, int channels, const std::vector<uint16_t>& values);

  std::vector<GltfImportFile>& files() { return files_; }
  // The folder of the scene the import writes: every image file above lies inside it.
  const std::string& scene_folder() const { return output_folder_; }
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

 private:
  std::string embedded_file(int image, const std::string& bytes, const std::string& key);
  std::string external_file(int image, const std::string& uri, const std::string& key);
  std::string planned_copy(int image, const std::string& ext, const std::string& bytes, const std::string& key);
  Sampler sampler_of(int sampler, const std::string& key);

  const tinygltf::Model& model_;
  std::string path_, source_folder_, folder_;  // the glTF file; its external images' folder; where images are written
  std::string output_folder_;                  // the scene's folder
  std::vector<std::string>& notes_;
  std::map<int, std::string> image_paths_;
  std::vector<GltfImportFile> files_;
  std::vector<bool> mipmap_noted_;
};

// glTF's metallic–roughness material `g` (at `mpath`, "materials[3]") as facet material
// JSON, its textures through `images`. `sets` receives each texture coordinate set a
// texture reads, with its key path. `vertex_colors`: for primitives with COLOR_0, which
// multiplies the base colour (glTF 2.0 §3.9.2): the values made of the base colour take the
// vertex colour ("vertex_color", catalog/texture.h).
nlohmann::json pbr_material(const tinygltf::Material& g, const std::string& mpath, GltfImages& images,
                            std::vector<std::pair<int, std::string>>& sets, std::vector<std::string>& notes,
                            bool vertex_colors = false);

// The material extensions pbr_material reads (glTF's KHR_materials_* it maps, and facet's own
// FACET_material): a file may require them, and a material's others are named in its note.
const std::vector<std::string>& material_extensions_read();

}  // namespace facet::gltf_detail

namespace facet::gltf_detail {

// The images of an export: each image file a material names becomes one glTF image,
// copied beside a .gltf output (`<output stem>.textures/NAME`, a relative URI) or held in
// a GLB's buffer (PNG and JPEG, glTF's core formats; an image of another format is
// copied beside the GLB and referenced by URI, with a note).
class GltfImageWriter {
 public:
  GltfImageWriter(tinygltf::Model& model, const std::string& output, std::vector<std::string>& notes);
  // `material` (facet material JSON, absolute image paths) with each image named as the
  // export writes it; `images` receives {name: glTF image index} (FACET_material's "images").
  nlohmann::json material_images(nlohmann::json material, nlohmann::json& images);
  // A textured colour as `info` (a textureInfo: its texture, texCoord and
  // KHR_texture_transform, which goes into `used`).
  void texture_info(const TextureRef& t, tinygltf::TextureInfo& info, std::set<std::string>& used);
  // The copies to write beside the output.
  std::vector<GltfImportFile>& files() { return files_; }

 private:
  int image_of(const std::string& path);
  int sampler_of(const Sampler& s);

  tinygltf::Model& model_;
  std::string folder_, stem_;  // the output's
  bool binary_;
  std::vector<std::string>& notes_;
  std::map<std::string, int> images_;        // by the source's absolute path
  std::map<std::string, std::string> names_; // the source's absolute path → its name in FACET_material
  std::set<std::string> taken_;              // file names used in the textures folder
  std::map<std::array<int, 3>, int> samplers_;
  std::vector<GltfImportFile> files_;
};

}  // namespace facet::gltf_detail
