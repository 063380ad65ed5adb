// glTF metallic–roughness onto the catalog, with its textures (scene/gltf_images.h).
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "core/text.h"
#include "scene/gltf_images.h"

namespace facet::gltf_detail {

using nlohmann::json;

namespace {

RGB rgb3(const std::vector<double>& v, double fallback) {
  return {v.size() > 0 ? v[0] : fallback, v.size() > 1 ? v[1] : fallback, v.size() > 2 ? v[2] : fallback};
}

uint16_t unorm16(double v) { return uint16_t(std::lround(std::clamp(v, 0.0, 1.0) * 65535)); }

// What a metallic–roughness material is made of, its maps resolved.
struct Pbr {
  RGB base{1, 1, 1};
  double metal = 1, rough = 1;
  std::optional<TextureUse> base_map, mr_map;  // baseColorTexture (sRGB), metallicRoughnessTexture (linear)
  std::optional<TextureUse> occlusion_map;     // occlusionTexture (linear, R)
  double occlusion = 1;                        // occlusionTexture.strength
  std::string name;                            // the facet material's key, for baked images' names
  bool vertex_colors = false;                  // COLOR_0 multiplies the base colour
};

// `j` (a value's JSON: a number, a colour or a texture object) times the vertex colour where
// the material's primitives have COLOR_0: a colour becomes {"vertex_color": true, "factor": …}.
json times_vertex_color(const Pbr& p, json j) {
  if (!p.vertex_colors) return j;
  if (!j.is_object()) j = {{"factor", j}};
  j["vertex_color"] = true;
  return j;
}

// The linear base colour at texel (i, j) of the grid the bake runs on.
RGB base_at(const Pbr& p, int i, int j) {
  if (!p.base_map) return p.base;
  const float* t = p.base_map->texels->at(i, j);
  RGB c;
  for (size_t k = 0; k < 3; ++k) c[k] = p.base[k] * srgb_to_linear(t[k]);
  return c;
}

// The metallic value at texel (i, j) of a grid of `w`×`h` (the base colour map's, where
// there is one): the B channel at the texel itself when the grids are one, else sampled
// at the grid texel's centre by glTF's rule (both maps read the same coordinates).
double metal_at(const Pbr& p, int i, int j, int w, int h) {
  if (!p.mr_map) return p.metal;
  const Texels& t = *p.mr_map->texels;
  if (t.width == w && t.height == h) return p.metal * t.at(i, j)[2];
  return p.metal * sample(t, p.mr_map->sampler, (i + 0.5) / w, (j + 0.5) / h)[2];
}

// glTF's occluded colour, lerp(1, occlusion, strength) (glTF 2.0 §3.9.3), at texel (i, j)
// of a grid of `w`×`h`: the R channel at the texel itself when the grids are one, else
// sampled at the grid texel's centre.
double occlusion_at(const Pbr& p, int i, int j, int w, int h) {
  const Texels& t = *p.occlusion_map->texels;
  const double r = t.width == w && t.height == h ? t.at(i, j)[0]
                                                  : sample(t, p.occlusion_map->sampler, (i + 0.5) / w, (j + 0.5) / h)[0];
  return 1 + p.occlusion * (r - 1);
}

// The ambient term m_a: the diffuse albedo the ambient light meets, base·(1 − metallic),
// times glTF's occlusion (docs/textures.md, "glTF import"): the occlusion map times the
// albedo as a factor where the albedo is a number and the strength 1, else baked texel by
// texel on the base colour (or metallic–roughness) map's grid, which the occlusion map
// must share the coordinates of.
json ambient_term(const Pbr& p, const RGB& kd, GltfImages& images, const std::string& mpath,
                  std::vector<std::string>& notes) {
  const TextureUse& o = *p.occlusion_map;
  // k_d·lerp(1, R, s) = k_d·s·R + k_d·(1 − s): the map itself, its offset k_d·(1 − s) (which
  // COLOR_0 would have to multiply too: there, s = 1 only).
  if (!p.base_map && !(p.mr_map && p.metal > 0) && (p.occlusion == 1 || !p.vertex_colors)) {
    json a = o.spec;
    a["colorspace"] = "linear";
    a["channel"] = "r";
    a["factor"] = RGB{kd[0] * p.occlusion, kd[1] * p.occlusion, kd[2] * p.occlusion};
    if (p.occlusion < 1) a["offset"] = RGB{kd[0] * (1 - p.occlusion), kd[1] * (1 - p.occlusion), kd[2] * (1 - p.occlusion)};
    return times_vertex_color(p, a);
  }
  const TextureUse& g = p.base_map ? *p.base_map : p.mr_map && p.metal > 0 ? *p.mr_map : o;
  if (!g.same_mapping(o))
    images.fail(o.key + ".texCoord",
                fmt::format("reads other texture coordinates (set or KHR_texture_transform) than {}; facet bakes the "
                            "ambient term texel by texel from both and needs them to agree",
                            g.key));
  const int w = g.texels->width, h = g.texels->height;
  std::vector<uint16_t> v(size_t(w) * size_t(h) * 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const RGB b = base_at(p, i, j);
      const double keep = (1 - metal_at(p, i, j, w, h)) * occlusion_at(p, i, j, w, h);
      for (size_t k = 0; k < 3; ++k) v[(size_t(j) * size_t(w) + size_t(i)) * 3 + k] = unorm16(b[k] * keep);
    }
  const std::string file = images.bake(p.name + "_ambient", w, h, 3, v);
  notes.push_back(fmt::format("{}: baked the ambient term base·(1 − metallic)·lerp(1, occlusion, {}) texel by texel "
                              "({}×{}, 16-bit linear) into {}",
                              mpath, p.occlusion, w, h, file));
  json a = g.spec;
  a["texture"] = file;
  a["colorspace"] = "linear";
  return times_vertex_color(p, a);  // the baked term times COLOR_0: exact
}

// glTF 2.0 §3.9.4, alphaMode: MASK is facet's cut-out, the base colour's alpha (baseColorFactor's
// times baseColorTexture's A, linear) against alphaCutoff; BLEND, which facet does not blend, is
// drawn opaque, with a note. COLOR_0's alpha, which glTF multiplies in too, is left out of the
// cut-out, with a note: Cycles' shadow rays cannot read another mesh's vertex colour where they
// meet it (docs/textures.md, Cut-outs), so no renderer cuts by it.
void cut_out(const tinygltf::Material& g, const Pbr& p, const std::string& mpath, json& m,
             std::vector<std::string>& notes) {
  const double alpha = g.pbrMetallicRoughness.baseColorFactor.size() > 3 ? g.pbrMetallicRoughness.baseColorFactor[3] : 1;
  if (g.alphaMode == "BLEND")
    notes.push_back(mpath + ": alphaMode BLEND is drawn opaque (facet does not blend surfaces; MASK it cuts out)");
  if (g.alphaMode != "MASK") return;
  m["alpha_cutoff"] = g.alphaCutoff;
  if (p.base_map) {
    m["alpha"] = p.base_map->spec;
    m["alpha"]["channel"] = "a";
    m["alpha"]["colorspace"] = "linear";  // glTF's alpha is linear; only the base colour's rgb is sRGB
    m["alpha"]["factor"] = alpha;
  } else {
    m["alpha"] = alpha;
  }
  if (p.vertex_colors)
    notes.push_back(mpath + " (COLOR_0): alphaMode MASK cuts by the base colour's alpha alone; COLOR_0's alpha is "
                            "left out of the cut-out (approximated: facet's renderers do not cut by a vertex alpha)");
}

// The material's extensions facet does not implement, named in one note (the file's
// required ones were refused before any material was read).
void note_unimplemented_extensions(const tinygltf::Material& g, const std::string& mpath, std::vector<std::string>& notes) {
  if (g.extensions_json_string.empty()) return;
  const json ext = json::parse(g.extensions_json_string, nullptr, false);
  if (!ext.is_object()) return;
  std::string names;
  for (const auto& [name, value] : ext.items())
    if (std::find(material_extensions_read().begin(), material_extensions_read().end(), name) ==
        material_extensions_read().end())
      names += (names.empty() ? "" : ", ") + name;
  if (!names.empty())
    notes.push_back(fmt::format("{}{}: {} ignored: facet does not implement {} yet; the material renders as its "
                                "metallic–roughness core",
                                mpath, g.name.empty() ? "" : " (\"" + one_line(g.name) + "\")", one_line(names),
                                names.find(',') == std::string::npos ? "it" : "them"));
}

// A texture's value: `use`'s image (its sampler, coordinates and transform), channel `channel`
// in `colorspace`, times `factor`.
json texture_value(const TextureUse& use, const char* channel, const char* colorspace, const json& factor) {
  json t = use.spec;
  if (std::string(channel) != "rgb") t["channel"] = channel;
  t["colorspace"] = colorspace;
  t["factor"] = factor;
  return t;
}

// A textureInfo inside a material extension (tinygltf leaves extensions as JSON): its index,
// texCoord and own extensions (KHR_texture_transform) read as the core's are.
TextureUse extension_texture(GltfImages& images, const json& info, const std::string& key) {
  if (!info.is_object() || !info.contains("index") || !info["index"].is_number_integer())
    images.fail(key + ".index", "expected a textureInfo object with a whole-number index");
  const json tex_coord = info.value("texCoord", json(0));
  if (!tex_coord.is_number_integer()) images.fail(key + ".texCoord", "expected a whole number");
  return images.texture(info["index"].get<int>(), tex_coord.get<int>(),
                        info.contains("extensions") ? info["extensions"].dump() : "", key);
}

// The number `name` of extension object `ext` (`fallback` where absent), in [lo, hi]: else
// InputError naming `key`.name.
double extension_number(GltfImages& images, const json& ext, const char* name, double fallback, double lo, double hi,
                        const std::string& key) {
  if (!ext.contains(name)) return fallback;
  const json& v = ext[name];
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
    images.fail(key + "." + name, fmt::format("expected a number in [{:g}, {:g}], found {}", lo, hi, v.dump()));
  return v.get<double>();
}

// A factor of extension `ext` times channel `channel` of its texture `texture` (linear), into
// the lobe's `param`: the README's "factor × texture.channel" (a texture without its factor
// is scaled by the factor's default).
void factor_and_texture(const json& ext, const char* factor, double fallback, const char* texture, const char* channel,
                        const char* param, json& lobe, GltfImages& images, const std::string& key,
                        std::vector<std::pair<int, std::string>>& sets) {
  const double f = extension_number(images, ext, factor, fallback, 0, 1, key);
  lobe[param] = f;
  if (!ext.contains(texture)) return;
  const TextureUse t = extension_texture(images, ext[texture], key + "." + texture);
  sets.emplace_back(t.uv, t.key + ".texCoord");
  lobe[param] = texture_value(t, channel, "linear", f);
}

// The colour `name` of extension object `ext` (`fallback` where absent), each number in [0, hi]:
// else InputError naming `key`.name[k].
RGB extension_color(GltfImages& images, const json& ext, const char* name, RGB fallback, double hi,
                    const std::string& key) {
  if (!ext.contains(name)) return fallback;
  const json& c = ext[name];
  if (!c.is_array() || c.size() != 3) images.fail(key + "." + name, "expected three numbers, found " + c.dump());
  RGB out;
  for (size_t k = 0; k < 3; ++k) {
    if (!c[k].is_number() || !(c[k].get<double>() >= 0 && c[k].get<double>() <= hi))
      images.fail(fmt::format("{}.{}[{}]", key, name, k),
                  fmt::format("expected a number in [0, {:g}], found {}", hi, c[k].dump()));
    out[k] = c[k].get<double>();
  }
  return out;
}

// A colour factor of extension `ext` times its texture `texture`'s rgb in sRGB (the READMEs'
// "factor * sampleLinear(texture).rgb", the texture "encoded in sRGB"), into the lobe's `param`.
void color_and_texture(const json& ext, const char* factor, RGB fallback, double hi, const char* texture,
                       const char* param, json& lobe, GltfImages& images, const std::string& key,
                       std::vector<std::pair<int, std::string>>& sets) {
  const RGB f = extension_color(images, ext, factor, fallback, hi, key);
  lobe[param] = f;
  if (!ext.contains(texture)) return;
  const TextureUse t = extension_texture(images, ext[texture], key + "." + texture);
  sets.emplace_back(t.uv, t.key + ".texCoord");
  lobe[param] = texture_value(t, "rgb", "srgb", f);
}

// KHR_materials_specular: specular = specularFactor × specularTexture's A; specular_color =
// specularColorFactor × specularColorTexture's rgb ("Implementation": specularColor =
// specularColorFactor * sampleLinear(specularColorTexture).rgb).
void specular_extension(const json& spec, json& lobe, GltfImages& images, const std::string& key,
                        std::vector<std::pair<int, std::string>>& sets) {
  factor_and_texture(spec, "specularFactor", 1, "specularTexture", "a", "specular", lobe, images, key, sets);
  color_and_texture(spec, "specularColorFactor", {1, 1, 1}, kColorMax, "specularColorTexture", "specular_color", lobe,
                    images, key, sets);
}

// KHR_materials_sheen ("Sheen"): sheen_color = sheenColorFactor × sheenColorTexture's rgb (sRGB),
// sheen_roughness = sheenRoughnessFactor × sheenRoughnessTexture's A ("sheenRoughness =
// sheenRoughnessFactor * sample(sheenRoughnessTexture).a").
void sheen_extension(const json& sheen, json& lobe, GltfImages& images, const std::string& key,
                     std::vector<std::pair<int, std::string>>& sets) {
  color_and_texture(sheen, "sheenColorFactor", {0, 0, 0}, 1, "sheenColorTexture", "sheen_color", lobe, images, key,
                    sets);
  factor_and_texture(sheen, "sheenRoughnessFactor", 0, "sheenRoughnessTexture", "a", "sheen_roughness", lobe, images,
                     key, sets);
}

// KHR_materials_clearcoat ("Clearcoat"): clearcoat = clearcoatFactor × clearcoatTexture's R,
// clearcoat_roughness = clearcoatRoughnessFactor × clearcoatRoughnessTexture's G. The coat's
// normal is the material's (coat_normal_map: pbr_material reads clearcoatNormalTexture).
void clearcoat_extension(const json& coat, json& lobe, GltfImages& images, const std::string& key,
                         std::vector<std::pair<int, std::string>>& sets) {
  factor_and_texture(coat, "clearcoatFactor", 0, "clearcoatTexture", "r", "clearcoat", lobe, images, key, sets);
  factor_and_texture(coat, "clearcoatRoughnessFactor", 0, "clearcoatRoughnessTexture", "g", "clearcoat_roughness",
                     lobe, images, key, sets);
}

// A normalTextureInfo's texture `t` as facet's normal map object: tangent-space, linear, +Y up
// (glTF 2.0 §3.9.3), its scale facet's strength.
json normal_map_of(const TextureUse& t, double scale) {
  json j = t.spec;
  j["green"] = "up";
  j["strength"] = scale;
  return j;
}

// KHR_materials_clearcoat's clearcoatNormalTexture (a normalTextureInfo: its scale is the map's
// strength) as the material's "coat_normal_map", on the base's tangent frame: "If
// clearcoatNormalTexture is not given, no normal mapping is applied to the clear coat layer"
// (the coat then takes the surface's own normal, which gltf_pbr does without a key). Not read,
// with a note, where the coat is disabled (clearcoatFactor 0) or where it reads other texture
// coordinates than normalTexture (the README: "these textures SHOULD use the same texture
// coordinates because they operate in the same tangent space"; facet turns both on one frame).
void coat_normal_map(const json& coat, const std::optional<TextureUse>& normal_map, json& m, GltfImages& images,
                     const std::string& key, std::vector<std::pair<int, std::string>>& sets,
                     std::vector<std::string>& notes) {
  if (!coat.contains("clearcoatNormalTexture")) return;
  const std::string at = key + ".clearcoatNormalTexture";
  const TextureUse t = extension_texture(images, coat["clearcoatNormalTexture"], at);
  const double scale = extension_number(images, coat["clearcoatNormalTexture"], "scale", 1, -kScalarMax, kScalarMax, at);
  if (extension_number(images, coat, "clearcoatFactor", 0, 0, 1, key) == 0) {
    notes.push_back(at + ": not read: the clear coat is disabled (clearcoatFactor 0)");
    return;
  }
  if (normal_map && normal_map->uv != t.uv) {
    notes.push_back(fmt::format("{}: approximate: not read: it reads TEXCOORD_{} where normalTexture reads TEXCOORD_{}, "
                                "and facet turns both maps on one tangent frame; the coat takes the surface's own "
                                "normal",
                                at, t.uv, normal_map->uv));
    return;
  }
  sets.emplace_back(t.uv, t.key + ".texCoord");
  m["coat_normal_map"] = normal_map_of(t, scale);
}

// KHR_materials_anisotropy ("Anisotropy"): anisotropy_strength = anisotropyStrength (times
// anisotropyTexture's B), anisotropy_rotation = anisotropyRotation (radians from the tangent
// towards the bitangent), and with the texture the direction anisotropy_direction_x, _y = its R and
// G (which the lobe maps as "red [0, 1] to X [−1, 1], green [0, 1] to Y [−1, 1]"), all linear. The direction
// turns from the mesh's tangent frame (ModelDef::uv_tangent: TANGENT, else MikkTSpace on the
// normal texture's coordinates, else on the anisotropy texture's, else on TEXCOORD_0), whose
// coordinates the mesh must have: `sets` names them (a mesh without them is refused there).
void anisotropy_extension(const json& aniso, bool normal_mapped, json& lobe, GltfImages& images, const std::string& key,
                          std::vector<std::pair<int, std::string>>& sets) {
  const double strength = extension_number(images, aniso, "anisotropyStrength", 0, 0, 1, key);
  lobe["anisotropy_strength"] = strength;
  lobe["anisotropy_rotation"] = extension_number(images, aniso, "anisotropyRotation", 0, -kScalarMax, kScalarMax, key);
  if (aniso.contains("anisotropyTexture")) {
    const TextureUse t = extension_texture(images, aniso["anisotropyTexture"], key + ".anisotropyTexture");
    sets.emplace_back(t.uv, t.key + ".texCoord");
    lobe["anisotropy_strength"] = texture_value(t, "b", "linear", strength);
    lobe["anisotropy_direction_x"] = texture_value(t, "r", "linear", 1);
    lobe["anisotropy_direction_y"] = texture_value(t, "g", "linear", 1);
  } else if (strength > 0 && !normal_mapped) {
    sets.emplace_back(0, key + " (its tangent frame: TEXCOORD_0)");
  }
}

// The glTF material as the catalog's gltf_pbr lobe, every input as the file gives it: glTF 2.0
// §3.9.2 (pbrMetallicRoughness: the base colour map's RGB in sRGB times baseColorFactor and
// COLOR_0, the metallic–roughness map's B and G, linear, times their factors), KHR_materials_ior
// (ior), KHR_materials_specular (specularFactor times specularTexture's A; specularColorFactor),
// KHR_materials_sheen (its factors and textures), KHR_materials_anisotropy and
// KHR_materials_clearcoat.
json gltf_pbr_lobe(const tinygltf::Material& g, const Pbr& p, GltfImages& images, const std::string& mpath,
                   std::vector<std::pair<int, std::string>>& sets) {
  json lobe = {{"model", "gltf_pbr"}};
  lobe["base_color"] = times_vertex_color(p, p.base_map ? texture_value(*p.base_map, "rgb", "srgb", p.base) : json(p.base));
  lobe["metallic"] = p.mr_map ? texture_value(*p.mr_map, "b", "linear", p.metal) : json(p.metal);
  lobe["roughness"] = p.mr_map ? texture_value(*p.mr_map, "g", "linear", p.rough) : json(p.rough);
  const json ior = extension_of(g.extensions_json_string, "KHR_materials_ior");
  if (ior.is_object()) {
    // The extension's schema: 0, or at least 1 (the catalog holds up to 1e4).
    const std::string key = mpath + ".extensions.KHR_materials_ior";
    const double eta = extension_number(images, ior, "ior", 1.5, 0, kScalarMax, key);
    if (eta > 0 && eta < 1) images.fail(key + ".ior", fmt::format("{:g} is neither 0 nor at least 1", eta));
    lobe["ior"] = eta;
  }
  const json spec = extension_of(g.extensions_json_string, "KHR_materials_specular");
  if (spec.is_object()) specular_extension(spec, lobe, images, mpath + ".extensions.KHR_materials_specular", sets);
  const json aniso = extension_of(g.extensions_json_string, "KHR_materials_anisotropy");
  if (aniso.is_object())
    anisotropy_extension(aniso, g.normalTexture.index >= 0, lobe, images, mpath + ".extensions.KHR_materials_anisotropy",
                         sets);
  const json sheen = extension_of(g.extensions_json_string, "KHR_materials_sheen");
  if (sheen.is_object()) sheen_extension(sheen, lobe, images, mpath + ".extensions.KHR_materials_sheen", sets);
  const json coat = extension_of(g.extensions_json_string, "KHR_materials_clearcoat");
  if (coat.is_object())
    clearcoat_extension(coat, lobe, images, mpath + ".extensions.KHR_materials_clearcoat", sets);
  return lobe;
}

}  // namespace

const std::vector<std::string>& material_extensions_read() {
  static const std::vector<std::string> read = {"KHR_materials_emissive_strength", "KHR_materials_ior",
                                                "KHR_materials_specular", "KHR_materials_sheen",
                                                "KHR_materials_clearcoat", "KHR_materials_anisotropy",
                                                "FACET_material"};
  return read;
}

json pbr_material(const tinygltf::Material& g, const std::string& mpath, GltfImages& images,
                  std::vector<std::pair<int, std::string>>& sets, std::vector<std::string>& notes, bool vertex_colors) {
  const auto& pbr = g.pbrMetallicRoughness;
  Pbr p;
  p.vertex_colors = vertex_colors;
  p.base = rgb3(pbr.baseColorFactor, 1);
  p.metal = pbr.metallicFactor;
  p.rough = pbr.roughnessFactor;
  p.name = identifier(g.name.empty() ? mpath : g.name) + (vertex_colors ? "_vertex_colors" : "");
  const std::string pm = mpath + ".pbrMetallicRoughness";
  if (pbr.baseColorTexture.index >= 0)
    p.base_map = images.texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                pbr.baseColorTexture.extensions_json_string, pm + ".baseColorTexture");
  if (pbr.metallicRoughnessTexture.index >= 0)
    p.mr_map = images.texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                              pbr.metallicRoughnessTexture.extensions_json_string, pm + ".metallicRoughnessTexture");
  if (g.occlusionTexture.index >= 0) {
    p.occlusion_map = images.texture(g.occlusionTexture.index, g.occlusionTexture.texCoord,
                                     g.occlusionTexture.extensions_json_string, mpath + ".occlusionTexture");
    p.occlusion = std::clamp(g.occlusionTexture.strength, 0.0, 1.0);
    if (p.occlusion != g.occlusionTexture.strength)
      notes.push_back(fmt::format("{}.occlusionTexture.strength: {} taken as {} (glTF allows 0 to 1)", mpath,
                                  g.occlusionTexture.strength, p.occlusion));
  }
  std::optional<TextureUse> normal_map, emission_map;
  if (g.normalTexture.index >= 0)
    normal_map = images.texture(g.normalTexture.index, g.normalTexture.texCoord, g.normalTexture.extensions_json_string,
                                mpath + ".normalTexture");
  if (g.emissiveTexture.index >= 0)
    emission_map = images.texture(g.emissiveTexture.index, g.emissiveTexture.texCoord,
                                  g.emissiveTexture.extensions_json_string, mpath + ".emissiveTexture");
  for (const auto* map : {&p.base_map, &p.mr_map, &p.occlusion_map, &normal_map, &emission_map})
    if (*map) sets.emplace_back((*map)->uv, (*map)->key + ".texCoord");
  if (auto b = line_break(g.name))  // names go into generated code's comments (core/text.h)
    notes.push_back(fmt::format("{}.name \"{}\" {}: made one line, a stand-in for each such character", mpath,
                                one_line(g.name), describe(*b)));
  json m = {{"name", one_line(g.name.empty() ? mpath : g.name) + (vertex_colors ? " (COLOR_0)" : "")}};
  m["specular"] = gltf_pbr_lobe(g, p, images, mpath, sets);
  auto e = rgb3(g.emissiveFactor, 0);
  json strength = extension_of(g.extensions_json_string, "KHR_materials_emissive_strength");
  double k = strength.is_object() ? strength.value("emissiveStrength", 1.0) : 1.0;
  const RGB emitted = {e[0] * k, e[1] * k, e[2] * k};
  if (emission_map && e[0] + e[1] + e[2] > 0) {  // emissiveTexture (sRGB) × emissiveFactor × emissiveStrength
    m["emission"] = emission_map->spec;
    m["emission"]["colorspace"] = "srgb";
    m["emission"]["factor"] = emitted;
  } else if (e[0] + e[1] + e[2] > 0) {
    m["emission"] = emitted;
  } else if (emission_map) {
    notes.push_back(mpath + ".emissiveTexture: emissiveFactor is 0, so the map emits nothing (glTF multiplies them)");
  }
  // KHR_materials_clearcoat, "Emission": gltf_pbr dims the emission by 1 − clearcoat · Fc(n·v)
  // itself (ModelDef::emission_weight), clearcoat the texel times the factor where it is textured.
  if (normal_map) m["normal_map"] = normal_map_of(*normal_map, g.normalTexture.scale);
  if (const json coat = extension_of(g.extensions_json_string, "KHR_materials_clearcoat"); coat.is_object())
    coat_normal_map(coat, normal_map, m, images, mpath + ".extensions.KHR_materials_clearcoat", sets, notes);
  if (p.occlusion_map) {
    const RGB kd_c = {p.base[0] * (1 - p.metal), p.base[1] * (1 - p.metal), p.base[2] * (1 - p.metal)};
    if (p.base_map || (p.mr_map && p.metal > 0) || kd_c[0] + kd_c[1] + kd_c[2] > 0)
      m["ambient"] = ambient_term(p, kd_c, images, mpath, notes);
    else
      notes.push_back(mpath + ".occlusionTexture: the material has no diffuse albedo (metallic 1), so nothing to occlude");
  }
  note_unimplemented_extensions(g, mpath, notes);
  cut_out(g, p, mpath, m, notes);
  return m;
}

}  // namespace facet::gltf_detail
