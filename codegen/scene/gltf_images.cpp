#include "scene/gltf_images.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "catalog/material.h"
#include "core/image.h"
#include "core/io.h"

namespace facet::gltf_detail {

using nlohmann::json;
namespace fs = std::filesystem;

// gltf_images.h
json extension_of(const std::string& extensions_json, const char* name) {
  if (extensions_json.empty()) return nullptr;
  json all = json::parse(extensions_json, nullptr, false);
  if (!all.is_object() || !all.contains(name)) return nullptr;
  return all[name];
}

namespace {

// A name safe in any file system: letters, digits, '-' and '_', at most 40 of them.
std::string safe_name(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (out.size() >= 40) break;
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    out.push_back(ok ? c : '_');
  }
  return out;
}

// "image/png" or "image/jpeg" by the file's signature (glTF's core formats), else "".
std::string mime_of(const std::string& bytes) {
  if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n", 8) == 0) return "image/png";
  if (bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xFF && static_cast<unsigned char>(bytes[1]) == 0xD8 &&
      static_cast<unsigned char>(bytes[2]) == 0xFF)
    return "image/jpeg";
  return "";
}

const char* wrap_name(int gl) {
  switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return "clamp";
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return "mirror";
    default: return "repeat";
  }
}

TextureWrap wrap_of(int gl) {
  switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::Clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::Mirror;
    default: return TextureWrap::Repeat;
  }
}

}  // namespace

bool TextureUse::same_mapping(const TextureUse& o) const {
  return uv == o.uv && spec.value("transform", json()) == o.spec.value("transform", json());
}

GltfImages::GltfImages(const tinygltf::Model& model, std::string gltf_path, std::string folder,
                       const std::string& output, std::vector<std::string>& notes)
    : model_(model),
      path_(std::move(gltf_path)),
      source_folder_(std::move(folder)),
      notes_(notes),
      mipmap_noted_(model.samplers.size(), false) {
  fs::path out = output.empty() ? fs::path(path_).replace_extension(".json") : fs::path(output);
  output_folder_ = fs::absolute(out.parent_path().empty() ? fs::path(".") : out.parent_path()).string();
  folder_ = (fs::absolute(out.parent_path().empty() ? fs::path(".") : out.parent_path()) /
             (out.stem().string() + ".textures"))
                .lexically_normal()
                .string();
}

void GltfImages::fail(const std::string& key, const std::string& message) const {
  throw InputError({{path_, key, message, 0, 0}});
}

// glTF's sampler `sampler` (−1: none, glTF's default: repeat, the viewer's filter).
Sampler GltfImages::sampler_of(int sampler, const std::string& key) {
  Sampler s;
  if (sampler < 0) return s;
  if (size_t(sampler) >= model_.samplers.size()) fail(key, fmt::format("its texture's sampler {} names no sampler", sampler));
  const tinygltf::Sampler& g = model_.samplers[size_t(sampler)];
  s.filter = g.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? TextureFilter::Nearest : TextureFilter::Bilinear;
  s.wrap = {wrap_of(g.wrapS), wrap_of(g.wrapT)};
  const bool mipmaps = g.minFilter >= TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST &&
                       g.minFilter <= TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  if (mipmaps && !mipmap_noted_[size_t(sampler)]) {
    mipmap_noted_[size_t(sampler)] = true;
    notes_.push_back(fmt::format("{}: samplers[{}] asks for mipmaps (minFilter {}); facet samples the image itself "
                                 "({}), without mipmaps, as validation does (docs/textures.md)",
                                 path_, sampler, g.minFilter,
                                 s.filter == TextureFilter::Nearest ? "nearest" : "bilinear"));
  }
  return s;
}

TextureUse GltfImages::texture(int index, int tex_coord, const std::string& extensions_json, const std::string& key) {
  if (index < 0 || size_t(index) >= model_.textures.size())
    fail(key + ".index", fmt::format("names no texture ({}; the file has {})", index, model_.textures.size()));
  const tinygltf::Texture& t = model_.textures[size_t(index)];
  if (t.source < 0)
    fail(key + ".index", fmt::format("textures[{}] has no source image facet reads (glTF's core formats: PNG, JPEG; "
                                     "image extensions such as KHR_texture_basisu and EXT_texture_webp are not read)",
                                     index));
  TextureUse use;
  use.key = key;
  use.sampler = sampler_of(t.sampler, key + ".index");
  use.uv = tex_coord;
  use.spec = {{"texture", image_file(t.source, key + ".index")},
              {"filter", use.sampler.filter == TextureFilter::Nearest ? "nearest" : "bilinear"},
              {"wrap", json::array({wrap_name(t.sampler >= 0 ? model_.samplers[size_t(t.sampler)].wrapS
                                                             : TINYGLTF_TEXTURE_WRAP_REPEAT),
                                    wrap_name(t.sampler >= 0 ? model_.samplers[size_t(t.sampler)].wrapT
                                                             : TINYGLTF_TEXTURE_WRAP_REPEAT)})}};
  json tt = extension_of(extensions_json, "KHR_texture_transform");
  if (tt.is_object()) {
    auto pair = [&](const char* k, double d) {
      const json v = tt.value(k, json::array({d, d}));
      if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
        fail(key + ".extensions.KHR_texture_transform." + k, fmt::format("expected [u, v], found {}", v.dump()));
      return v;
    };
    const json rotation = tt.value("rotation", json(0.0));
    if (!rotation.is_number()) fail(key + ".extensions.KHR_texture_transform.rotation", "expected a number");
    use.spec["transform"] = {{"offset", pair("offset", 0)}, {"scale", pair("scale", 1)}, {"rotation", rotation}};
    const json tc = tt.value("texCoord", json(use.uv));
    if (!tc.is_number_integer()) fail(key + ".extensions.KHR_texture_transform.texCoord", "expected an integer");
    use.uv = tc.get<int>();
  }
  if (use.uv < 0) fail(key + ".texCoord", fmt::format("{}: a texture coordinate set is TEXCOORD_n, n ≥ 0", use.uv));
  use.spec["uv"] = use.uv;
  use.texels = load_texels(use.spec["texture"].get<std::string>());  // decoded by image_file
  return use;
}

std::string GltfImages::image_file(int image, const std::string& key) {
  if (image < 0 || size_t(image) >= model_.images.size())
    fail(key, fmt::format("its texture's source {} names no image (the file has {})", image, model_.images.size()));
  auto known = image_paths_.find(image);
  if (known != image_paths_.end()) return known->second;
  const tinygltf::Image& im = model_.images[size_t(image)];
  std::string file;
  if (im.bufferView >= 0) {
    const tinygltf::BufferView& v = model_.bufferViews.at(size_t(im.bufferView));  // checked by load_model
    const auto& data = model_.buffers.at(size_t(v.buffer)).data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
      fail(key, fmt::format("images[{}]: bufferViews[{}] reaches past its buffer", image, im.bufferView));
    file = embedded_file(image, std::string(data.begin() + long(v.byteOffset),
                                            data.begin() + long(v.byteOffset + v.byteLength)), key);
  } else if (!im.image.empty()) {
    file = embedded_file(image, std::string(im.image.begin(), im.image.end()), key);
  } else if (im.uri.rfind("data:", 0) == 0) {
    fail(key, fmt::format("images[{}] is a data URI of type \"{}\"; facet reads image/png and image/jpeg (glTF's "
                          "core formats)",
                          image, im.uri.substr(5, std::min(im.uri.find_first_of(";,"), size_t(40)) - 5)));
  } else if (!im.uri.empty()) {
    file = external_file(image, im.uri, key);
  } else {
    fail(key, fmt::format("images[{}] has neither a uri nor a bufferView", image));
  }
  image_paths_[image] = file;
  return file;
}

// An image held by the glTF file: checked and decoded now, written with the scene.
std::string GltfImages::embedded_file(int image, const std::string& bytes, const std::string& key) {
  const tinygltf::Image& im = model_.images[size_t(image)];
  const std::string ext = im.mimeType == "image/png" ? "png" : im.mimeType == "image/jpeg" ? "jpg" : "";
  if (ext.empty())
    fail(key, fmt::format("images[{}] has mimeType \"{}\"; facet reads image/png and image/jpeg (glTF's core formats)",
                          image, im.mimeType));
  return planned_copy(image, ext, bytes, key);
}

// Image `image`'s bytes, checked and decoded now, planned as `<textures folder>/imageN_<name>.<ext>`.
std::string GltfImages::planned_copy(int image, const std::string& ext, const std::string& bytes,
                                     const std::string& key) {
  const std::string name = safe_name(model_.images[size_t(image)].name);
  const std::string file =
      (fs::path(folder_) / fmt::format("image{}{}.{}", image, name.empty() ? "" : "_" + name, ext)).string();
  try {
    remember_texels(file, decode_texels(bytes, fmt::format("images[{}]", image)));
  } catch (const IoError& e) {
    fail(key, e.what());
  }
  files_.push_back({file, bytes});
  return file;
}

// An image beside the glTF file (its URI relative to the file's folder, percent-decoded).
std::string GltfImages::external_file(int image, const std::string& uri, const std::string& key) {
  if (source_folder_.empty())
    fail(key, fmt::format("images[{}].uri \"{}\" is an external file, and an import from memory reads none", image, uri));
  const std::string abs = uri_file(source_folder_, uri, path_, key);
  if (!fs::is_regular_file(abs))
    fail(key, fmt::format("images[{}].uri \"{}\" is not there ({}); an external image must sit where its URI says, "
                          "relative to the glTF file",
                          image, uri, abs));
  if (inside_folder(abs, output_folder_)) {
    try {
      (void)load_texels(abs);
    } catch (const IoError& e) {
      fail(key, fmt::format("images[{}].uri: {}", image, e.what()));
    }
    return abs;
  }
  // The scene will be read with its images confined to its folder, so one from elsewhere
  // goes beside it, bytes unchanged, like an image the glTF holds.
  std::string bytes;
  try {
    bytes = read_file(abs);
  } catch (const IoError& e) {
    fail(key, fmt::format("images[{}].uri: {}", image, e.what()));
  }
  const std::string mime = mime_of(bytes);
  const std::string ext = mime == "image/png" ? "png" : mime == "image/jpeg" ? "jpg" : "";
  if (ext.empty())
    fail(key, fmt::format("images[{}].uri \"{}\" is neither a PNG nor a JPEG file (glTF's core formats)", image, uri));
  return planned_copy(image, ext, bytes, key);
}

std::string GltfImages::bake(const std::string& name, int width, int height, int channels,
                             const std::vector<uint16_t>& values) {
  // Named from the whole name (identifier(): past 64 characters its start and a hash, never
  // cut short), numbered where two materials' names make one identifier ("a-b", "a b").
  const std::string base = (fs::path(folder_) / identifier(name)).string();
  std::string file = base + ".png";
  auto planned = [&](const std::string& f) {
    return std::any_of(files_.begin(), files_.end(), [&](const GltfImportFile& p) { return p.path == f; });
  };
  for (int k = 2; planned(file); ++k) file = fmt::format("{}_{}.png", base, k);
  std::string bytes = encode_png16(width, height, channels, values, file);
  remember_texels(file, decode_texels(bytes, file));
  files_.push_back({file, std::move(bytes)});
  return file;
}

// ---------------------------------------------------------------- export

namespace {

// A relative URI for `path` (RFC 3986: unreserved characters and '/' as they are).
std::string percent_encoded(const std::string& path) {
  std::string out;
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/')
      out.push_back(char(c));
    else
      out += fmt::format("%{:02X}", c);
  }
  return out;
}

int gl_wrap(TextureWrap w) {
  switch (w) {
    case TextureWrap::Clamp: return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    case TextureWrap::Mirror: return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
    default: return TINYGLTF_TEXTURE_WRAP_REPEAT;
  }
}

}  // namespace

GltfImageWriter::GltfImageWriter(tinygltf::Model& model, const std::string& output, std::vector<std::string>& notes)
    : model_(model),
      folder_(fs::path(output).parent_path().string()),
      stem_(fs::path(output).stem().string()),
      binary_(fs::path(output).extension() == ".glb"),
      notes_(notes) {}

json GltfImageWriter::material_images(json material, json& images) {
  if (material.is_array()) {
    for (auto& e : material) e = material_images(std::move(e), images);
  } else if (material.is_object()) {
    for (auto& [key, e] : material.items())
      if (key == "texture" && e.is_string()) {
        const std::string path = fs::absolute(e.get<std::string>()).lexically_normal().string();
        const int index = image_of(path);
        e = names_.at(path);
        images[names_.at(path)] = index;
      } else {
        e = material_images(std::move(e), images);
      }
  }
  return material;
}

// The glTF image of the file at `path`: a copy beside the output, or the GLB's bytes.
int GltfImageWriter::image_of(const std::string& path) {
  auto known = images_.find(path);
  if (known != images_.end()) return known->second;
  const std::string bytes = read_file(path);
  tinygltf::Image im;
  std::string base = fs::path(path).filename().string();
  im.name = fs::path(path).stem().string();
  const std::string mime = mime_of(bytes);
  if (binary_ && !mime.empty()) {
    std::vector<unsigned char>& bin = model_.buffers[0].data;
    while (bin.size() % 4) bin.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = bin.size();
    v.byteLength = bytes.size();
    bin.insert(bin.end(), bytes.begin(), bytes.end());
    model_.bufferViews.push_back(v);
    im.bufferView = int(model_.bufferViews.size() - 1);
    im.mimeType = mime;
    for (int k = 2; !taken_.insert(base).second; ++k) base = fmt::format("{}_{}", k, fs::path(path).filename().string());
    names_[path] = base;
  } else {
    if (mime.empty())
      notes_.push_back(fmt::format("{}: not PNG or JPEG, glTF's image formats; copied beside the output for facet, "
                                   "other viewers may not read it",
                                   path));
    for (int k = 2; !taken_.insert(base).second; ++k) base = fmt::format("{}_{}", k, fs::path(path).filename().string());
    const std::string rel = stem_ + ".textures/" + base;
    im.uri = percent_encoded(rel);
    names_[path] = rel;
    files_.push_back({(fs::path(folder_) / rel).string(), bytes});
  }
  model_.images.push_back(im);
  images_[path] = int(model_.images.size() - 1);
  return images_[path];
}

int GltfImageWriter::sampler_of(const Sampler& s) {
  const int filter = s.filter == TextureFilter::Nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
  const std::array<int, 3> key{filter, gl_wrap(s.wrap[0]), gl_wrap(s.wrap[1])};
  auto known = samplers_.find(key);
  if (known != samplers_.end()) return known->second;
  tinygltf::Sampler g;
  g.magFilter = g.minFilter = filter;  // no mipmaps: the texture is sampled as facet validates it
  g.wrapS = key[1];
  g.wrapT = key[2];
  model_.samplers.push_back(g);
  return samplers_[key] = int(model_.samplers.size() - 1);
}

void GltfImageWriter::texture_info(const TextureRef& t, tinygltf::TextureInfo& info, std::set<std::string>& used) {
  tinygltf::Texture tex;
  tex.source = image_of(fs::absolute(t.path).lexically_normal().string());
  tex.sampler = sampler_of(t.sampler);
  model_.textures.push_back(tex);
  info.index = int(model_.textures.size() - 1);
  info.texCoord = t.uv;
  if (t.has_transform()) {
    tinygltf::Value::Object tt;
    tt["offset"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(t.offset[0]), tinygltf::Value(t.offset[1])});
    tt["scale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(t.scale[0]), tinygltf::Value(t.scale[1])});
    tt["rotation"] = tinygltf::Value(t.rotation);
    info.extensions["KHR_texture_transform"] = tinygltf::Value(tt);
    used.insert("KHR_texture_transform");
  }
}

}  // namespace facet::gltf_detail
