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

// The grid k_d and f0 are baked on: the base colour map's where there is one, else the
// metallic–roughness map's. Both maps must read the same texture coordinates.
const TextureUse& bake_grid(const Pbr& p, const GltfImages& images, const std::string& mpath,
                           std::vector<std::string>& notes) {
  if (!p.base_map) return *p.mr_map;
  if (p.mr_map && !p.base_map->same_mapping(*p.mr_map))
    images.fail(p.mr_map->key + ".texCoord",
                fmt::format("reads other texture coordinates (set or KHR_texture_transform) than {}; facet bakes k_d "
                            "and f0 texel by texel from both and needs them to agree",
                            p.base_map->key));
  if (p.mr_map && (p.mr_map->sampler.filter != p.base_map->sampler.filter ||
                   p.mr_map->sampler.wrap != p.base_map->sampler.wrap))
    notes.push_back(fmt::format("{}: the metallic–roughness and base colour maps have different samplers; the baked "
                                "k_d and f0 are read with the base colour map's, α with the metallic–roughness map's",
                                mpath));
  if (p.mr_map && (p.mr_map->texels->width != p.base_map->texels->width ||
                   p.mr_map->texels->height != p.base_map->texels->height))
    notes.push_back(fmt::format("{}: the metallic–roughness map ({}×{}) and the base colour map ({}×{}) differ in "
                                "size; k_d and f0 are baked at the base colour map's texels, metallic sampled there",
                                mpath, p.mr_map->texels->width, p.mr_map->texels->height, p.base_map->texels->width,
                                p.base_map->texels->height));
  return *p.base_map;
}

// A linear map of the grid `g` (its sampler, coordinates and transform) holding `file`.
json baked_spec(const TextureUse& g, const std::string& file, bool color) {
  json s = g.spec;
  s["texture"] = file;
  s["colorspace"] = "linear";
  if (!color) s["channel"] = "r";
  return s;
}

// k_d = base·(1 − metallic) and f0 = 0.04·(1 − metallic) + base·metallic, texel by texel.
void bake_kd_f0(const Pbr& p, GltfImages& images, json& kd, json& f0, const std::string& mpath,
                std::vector<std::string>& notes) {
  const TextureUse& g = bake_grid(p, images, mpath, notes);
  const int w = g.texels->width, h = g.texels->height;
  std::vector<uint16_t> kd16(size_t(w) * size_t(h) * 3), f016(kd16.size());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const RGB b = base_at(p, i, j);
      const double m = metal_at(p, i, j, w, h);
      for (size_t k = 0; k < 3; ++k) {
        const size_t at = (size_t(j) * size_t(w) + size_t(i)) * 3 + k;
        kd16[at] = unorm16(b[k] * (1 - m));
        f016[at] = unorm16(0.04 * (1 - m) + b[k] * m);
      }
    }
  const std::string kd_file = images.bake(p.name + "_kd", w, h, 3, kd16);
  const std::string f0_file = images.bake(p.name + "_f0", w, h, 3, f016);
  kd = baked_spec(g, kd_file, true);
  f0 = baked_spec(g, f0_file, true);
  notes.push_back(fmt::format("{}: baked k_d = base·(1 − metallic) and f0 = 0.04·(1 − metallic) + base·metallic "
                              "texel by texel ({}×{}, 16-bit linear) into {} and {}",
                              mpath, w, h, kd_file, f0_file));
}

// GGX α = max((roughness·G)², kRoughnessMin) texel by texel, from the metallic–roughness map.
json bake_alpha(const Pbr& p, GltfImages& images, const std::string& mpath, std::vector<std::string>& notes) {
  const TextureUse& g = *p.mr_map;
  const int w = g.texels->width, h = g.texels->height;
  std::vector<uint16_t> v(size_t(w) * size_t(h));
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double r = p.rough * g.texels->at(i, j)[1];
      v[size_t(j) * size_t(w) + size_t(i)] = unorm16(std::max(r * r, kRoughnessMin));
    }
  const std::string file = images.bake(p.name + "_alpha", w, h, 1, v);
  notes.push_back(fmt::format("{}: baked GGX α = (roughness·G)² texel by texel ({}×{}, 16-bit linear) into {}", mpath,
                              w, h, file));
  return baked_spec(g, file, false);
}

// The diffuse colour and Schlick's f0: numbers, a map times a factor (and the vertex
// colour), or baked maps. With metallic m a number, f0 = 0.04·(1 − m) + base·m is the base
// colour map (and COLOR_0) times base·m plus the offset 0.04·(1 − m): exact, no bake (until
// texture values had offsets f0 was baked texel by texel wherever 0 < m < 1).
void colours(const Pbr& p, GltfImages& images, json& kd, json& f0, const std::string& mpath,
             std::vector<std::string>& notes) {
  RGB kd_c, f0_c, base_m;
  for (size_t c = 0; c < 3; ++c) {
    kd_c[c] = p.base[c] * (1 - p.metal);
    f0_c[c] = 0.04 * (1 - p.metal) + p.base[c] * p.metal;
    base_m[c] = p.base[c] * p.metal;
  }
  kd = kd_c;
  f0 = f0_c;
  if (p.mr_map && p.metal > 0) {
    bake_kd_f0(p, images, kd, f0, mpath, notes);
    kd = times_vertex_color(p, kd);  // the baked k_d times COLOR_0: exact
    if (p.vertex_colors)
      notes.push_back(mpath + ": approximate: f0 = 0.04·(1 − metallic) + base·metallic·COLOR_0 with metallic from a "
                              "map is no image times COLOR_0 plus a number; the baked f0 leaves COLOR_0 out");
    return;
  }
  const bool diffuse = kd_c[0] + kd_c[1] + kd_c[2] > 0, metal = p.metal > 0;
  json f0_offset = p.metal < 1 ? json(0.04 * (1 - p.metal)) : json();
  if (!p.base_map) {
    if (diffuse) kd = times_vertex_color(p, kd_c);
    if (metal && p.vertex_colors) {
      f0 = times_vertex_color(p, base_m);
      if (!f0_offset.is_null()) f0["offset"] = f0_offset;
    }
    return;
  }
  kd = p.base_map->spec;  // base · (1 − metallic): the map times a factor, exact
  kd["colorspace"] = "srgb";
  kd["factor"] = kd_c;
  kd = times_vertex_color(p, kd);
  if (!metal) return;
  f0 = p.base_map->spec;
  f0["colorspace"] = "srgb";
  f0["factor"] = base_m;
  if (!f0_offset.is_null()) f0["offset"] = f0_offset;
  f0 = times_vertex_color(p, f0);
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
    if (name != "KHR_materials_emissive_strength" && name != "FACET_material") names += (names.empty() ? "" : ", ") + name;
  if (!names.empty())
    notes.push_back(fmt::format("{}{}: {} ignored: facet does not implement {} yet; the material renders as its "
                                "metallic–roughness core",
                                mpath, g.name.empty() ? "" : " (\"" + one_line(g.name) + "\")", one_line(names),
                                names.find(',') == std::string::npos ? "it" : "them"));
}

}  // namespace

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
  json kd, f0;
  colours(p, images, kd, f0, mpath, notes);
  const bool diffuse = kd.is_object() || kd[0].get<double>() + kd[1].get<double>() + kd[2].get<double>() > 0;
  if (diffuse) m["diffuse"] = {{"model", "lambert"}, {"color", kd}};
  m["specular"] = {{"model", "ggx"},
                   {"alpha", p.mr_map ? bake_alpha(p, images, mpath, notes) : json(std::max(p.rough * p.rough, kRoughnessMin))},
                   {"geometry", "smith_ggx"},
                   {"fresnel", {{"model", "schlick"}, {"f0", f0}}}};
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
  if (normal_map) {  // tangent-space, linear, +Y up (glTF 2.0 §3.9.3); scale is facet's strength
    m["normal_map"] = normal_map->spec;
    m["normal_map"]["green"] = "up";
    m["normal_map"]["strength"] = g.normalTexture.scale;
  }
  if (p.occlusion_map) {
    const RGB kd_c = {p.base[0] * (1 - p.metal), p.base[1] * (1 - p.metal), p.base[2] * (1 - p.metal)};
    if (p.base_map || (p.mr_map && p.metal > 0) || kd_c[0] + kd_c[1] + kd_c[2] > 0)
      m["ambient"] = ambient_term(p, kd_c, images, mpath, notes);
    else
      notes.push_back(mpath + ".occlusionTexture: the material has no diffuse albedo (metallic 1), so nothing to occlude");
  }
  note_unimplemented_extensions(g, mpath, notes);
  cut_out(g, p, mpath, m, notes);
  if (diffuse && (p.metal < 1 || p.mr_map))
    notes.push_back(mpath + ": approximate: glTF weights a dielectric's diffuse by (1 − F); the catalog's Lambert does not");
  return m;
}

}  // namespace facet::gltf_detail
