#include "catalog/texture.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "core/io.h"
#include "core/text.h"

namespace facet {

using nlohmann::json;

namespace {

const std::vector<std::string> kKeys = {"texture", "channel", "uv", "transform", "colorspace",
                                        "filter", "wrap", "factor", "vertex_color", "offset"};
// The keys that say how an image is sampled: meaningless without one.
const std::vector<std::string> kImageKeys = {"uv", "transform", "colorspace", "filter", "wrap"};
// A normal map's keys: a texture's sampling keys, its convention and strength.
const std::vector<std::string> kNormalMapKeys = {"texture", "uv", "filter", "wrap", "transform", "green", "strength"};
const std::vector<std::string> kTransformKeys = {"offset", "scale", "rotation"};
const std::vector<std::string> kWraps = {"repeat", "clamp", "mirror"};

std::string quoted(const std::vector<std::string>& xs) {
  std::string s;
  for (size_t i = 0; i < xs.size(); ++i) s += (i ? ", \"" : "\"") + xs[i] + "\"";
  return s;
}

// Reads the keys of a texture object one by one, each problem at its key path.
class TextureReader {
 public:
  TextureReader(const json& j, const std::string& path, const ParamDef& p, DiagnosticSink& sink)
      : j_(j), path_(path), p_(p), sink_(sink) {}

  std::optional<Value> read() {
    for (const auto& [key, val] : j_.items())
      if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end()) {
        std::string hint = suggest(key, kKeys);
        error(key, fmt::format("unknown key of a texture{}; allowed keys: {}",
                               hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", quoted(kKeys)));
      }
    const bool color = p_.kind == ParamKind::Color;
    ref_.channel = choice("channel", color ? std::vector<std::string>{"rgb", "r", "g", "b", "a"}
                                           : std::vector<std::string>{"r", "g", "b", "a"},
                          color ? "rgb" : "r");
    ref_.colorspace = choice("colorspace", {"srgb", "linear"}, color ? "srgb" : "linear");
    ref_.sampler.srgb = ref_.colorspace == "srgb";
    ref_.sampler.filter = choice("filter", {"nearest", "bilinear"}, "bilinear") == "nearest" ? TextureFilter::Nearest
                                                                                              : TextureFilter::Bilinear;
    wrap();
    uv_set();
    transform();
    vertex_color();
    Value out;
    out.kind = p_.kind;
    out.rgb = {1, 1, 1};
    out.number = 1;
    factor("factor", out.rgb);
    if (j_.contains("factor") && !j_["factor"].is_array()) out.number = out.rgb[0];
    factor("offset", ref_.bias);
    image();
    if (!ok_) return std::nullopt;
    out.texture = std::make_shared<TextureRef>(ref_);
    return out;
  }

 private:
  void error(const std::string& key, const std::string& message) {
    sink_.error(key.empty() ? path_ : join_path(path_, key), message);
    ok_ = false;
  }

  std::string choice(const std::string& key, const std::vector<std::string>& allowed, const std::string& fallback) {
    auto it = j_.find(key);
    if (it == j_.end()) return fallback;
    if (!it->is_string() || std::find(allowed.begin(), allowed.end(), it->get<std::string>()) == allowed.end()) {
      error(key, fmt::format("expected one of {}, found {}", quoted(allowed), it->dump()));
      return fallback;
    }
    return it->get<std::string>();
  }

  TextureWrap wrap_of(const json& v, const std::string& key) {
    if (v.is_string())
      for (size_t i = 0; i < kWraps.size(); ++i)
        if (v.get<std::string>() == kWraps[i]) return TextureWrap(i);
    error(key, fmt::format("expected one of {} (or [u, v] of them), found {}", quoted(kWraps), v.dump()));
    return TextureWrap::Repeat;
  }

  void wrap() {
    auto it = j_.find("wrap");
    if (it == j_.end()) return;
    if (it->is_array() && it->size() == 2) {
      ref_.sampler.wrap = {wrap_of((*it)[0], "wrap[0]"), wrap_of((*it)[1], "wrap[1]")};
    } else {
      TextureWrap w = wrap_of(*it, "wrap");
      ref_.sampler.wrap = {w, w};
    }
  }

  void uv_set() {
    auto it = j_.find("uv");
    if (it == j_.end()) return;
    if (!it->is_number_integer() || (it->get<int64_t>() != 0 && it->get<int64_t>() != 1)) {
      error("uv", fmt::format("expected the texture coordinate set 0 or 1, found {}", it->dump()));
      return;
    }
    ref_.uv = it->get<int>();
  }

  bool finite(const json& v) { return v.is_number() && std::isfinite(v.get<double>()); }
  // A transform's numbers: |x| ≤ kScalarMax, so that uv·scale + offset stays a float32 number.
  bool bounded(const json& v) { return v.is_number() && std::fabs(v.get<double>()) <= kScalarMax; }

  void pair(const json& t, const std::string& key, std::array<double, 2>& out) {
    auto it = t.find(key);
    if (it == t.end()) return;
    if (!it->is_array() || it->size() != 2 || !bounded((*it)[0]) || !bounded((*it)[1])) {
      error("transform." + key, fmt::format("expected two numbers [u, v] in [-{0}, {0}], found {1}", kScalarMax, it->dump()));
      return;
    }
    out = {(*it)[0].get<double>(), (*it)[1].get<double>()};
  }

  void transform() {
    auto it = j_.find("transform");
    if (it == j_.end()) return;
    if (!it->is_object()) {
      error("transform", fmt::format("expected an object with keys {}, found {}", quoted(kTransformKeys), it->dump()));
      return;
    }
    for (const auto& [key, val] : it->items())
      if (std::find(kTransformKeys.begin(), kTransformKeys.end(), key) == kTransformKeys.end())
        error("transform." + key, "unknown key; allowed keys: " + quoted(kTransformKeys));
    pair(*it, "offset", ref_.offset);
    pair(*it, "scale", ref_.scale);
    auto r = it->find("rotation");
    if (r != it->end()) {
      if (!bounded(*r))
        error("transform.rotation", fmt::format("expected a number in [-{0}, {0}] (radians), found {1}", kScalarMax, r->dump()));
      else ref_.rotation = r->get<double>();
    }
  }

  void vertex_color() {
    auto it = j_.find("vertex_color");
    if (it == j_.end()) return;
    if (!it->is_boolean()) {
      error("vertex_color", fmt::format("expected true (the value times the surface's vertex colour, glTF's COLOR_0) or "
                                        "false, found {}",
                                        it->dump()));
      return;
    }
    ref_.vertex_color = it->get<bool>();
  }

  // "factor" or "offset": a number (any parameter) or a colour (colour parameters), each in
  // [0, texture_factor_max(range)]; a number fills the three lanes.
  void factor(const std::string& key, std::array<double, 3>& out) {
    auto it = j_.find(key);
    if (it == j_.end()) return;
    const double top = texture_factor_max(p_.range);
    auto one = [&](const json& v, const std::string& at, double& into) {
      if (!finite(v) || v.get<double>() < 0 || v.get<double>() > top) {
        error(at, fmt::format("expected a number in [0, {}], found {}", top, v.dump()));
        return;
      }
      into = v.get<double>();
    };
    if (it->is_array() && it->size() == 3 && p_.kind == ParamKind::Color) {
      for (size_t i = 0; i < 3; ++i) one((*it)[i], index_path(key, i), out[i]);
    } else if (it->is_array()) {
      error(key, fmt::format("expected {}, found {}", p_.kind == ParamKind::Color ? "a number or three numbers"
                                                                                  : "a number",
                             it->dump()));
    } else {
      double x = 0;
      one(*it, key, x);
      out = {x, x, x};
    }
  }

  // Without "texture" the value is the vertex colour alone: "vertex_color" must say so, and
  // the keys that describe an image's sampling have nothing to describe.
  bool vertex_color_alone() {
    if (!ref_.vertex_color) {
      error("texture", "missing; a texture names its image file (relative to this file's folder), or "
                       "\"vertex_color\": true takes the surface's vertex colour alone");
      return false;
    }
    for (const auto& key : kImageKeys)
      if (j_.contains(key)) error(key, "describes how an image is sampled, and this value has no \"texture\"; allowed "
                                       "without one: \"vertex_color\", \"channel\", \"factor\", \"offset\"");
    if (p_.kind == ParamKind::Color && ref_.channel != "rgb")
      error("channel", fmt::format("\"{}\": a colour takes the vertex colour's rgb; allowed without a \"texture\": "
                                   "\"rgb\"",
                                   ref_.channel));
    return ok_;
  }

  void image() {
    auto it = j_.find("texture");
    if (it == j_.end()) {
      vertex_color_alone();
      return;
    }
    if (!it->is_string() || it->get<std::string>().empty()) {
      error("texture", fmt::format("expected the image's file name, found {}", it->dump()));
      return;
    }
    ref_.file = it->get<std::string>();
    std::filesystem::path f(ref_.file);
    ref_.path = f.is_absolute() ? f.string() : (std::filesystem::path(sink_.folder()) / f).string();
    if (auto b = line_break(ref_.path)) {  // OSL and POV-Ray name the file in a string literal (core/text.h)
      error("texture", fmt::format("the image's path \"{}\" {}; a texture's path is one line of text (it is "
                                   "printed into the generated code)",
                                   one_line(ref_.path), describe(*b)));
      return;
    }
    if (!ok_) return;  // decode only what is otherwise valid
    // Like a glTF's URIs (core/io.h): a material or scene file, which may come from anywhere,
    // names images inside its own folder, or in one the user allowed with --allow-path.
    if (confined_path(sink_.folder(), ref_.file).empty()) {
      error("texture", outside_folder_message(ref_.file, sink_.folder(), "a material or scene file", "the file's"));
      return;
    }
    try {
      ref_.texels = load_texels(ref_.path);
    } catch (const IoError& e) {
      error("texture", e.what());
    }
  }

  const json& j_;
  std::string path_;
  const ParamDef& p_;
  DiagnosticSink& sink_;
  TextureRef ref_;
  bool ok_ = true;
};

}  // namespace

std::array<double, 2> TextureRef::transform(double u, double v) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double su = scale[0] * u, sv = scale[1] * v;
  return {c * su + s * sv + offset[0], -s * su + c * sv + offset[1]};
}

double texture_factor_max(const Range& r) { return std::isfinite(r.max) ? std::max(r.max, kColorMax) : kColorMax; }

std::array<double, 2> texture_bounds(const Range& r) {
  double lo = std::isfinite(r.min) ? r.min + (r.min_open ? kTextureOpenMargin : 0.0) : -HUGE_VAL;
  double hi = std::isfinite(r.max) ? r.max - (r.max_open ? kTextureOpenMargin : 0.0) : HUGE_VAL;
  return {lo, hi};
}

std::optional<Value> parse_texture_value(const json& j, const std::string& path, const ParamDef& p,
                                         DiagnosticSink& sink) {
  return TextureReader(j, path, p, sink).read();
}

json texture_json(const Value& v) {
  const TextureRef& t = *v.texture;
  static const char* wraps[] = {"repeat", "clamp", "mirror"};
  auto lanes = [&](const std::array<double, 3>& x) {
    const bool grey = x[0] == x[1] && x[1] == x[2];
    return v.kind == ParamKind::Color && !grey ? json(x) : json(x[0]);
  };
  json j = {{"channel", t.channel}};
  if (t.has_image()) {
    // The image's absolute path: the JSON may be written anywhere (a scene, a glTF file's
    // FACET_material) and must read back the same image.
    j["texture"] = std::filesystem::absolute(t.path).lexically_normal().string();
    j["uv"] = t.uv;
    j["colorspace"] = t.colorspace;
    j["filter"] = t.sampler.filter == TextureFilter::Nearest ? "nearest" : "bilinear";
    j["wrap"] = t.sampler.wrap[0] == t.sampler.wrap[1]
                    ? json(wraps[int(t.sampler.wrap[0])])
                    : json::array({wraps[int(t.sampler.wrap[0])], wraps[int(t.sampler.wrap[1])]});
    if (t.has_transform()) j["transform"] = {{"offset", t.offset}, {"scale", t.scale}, {"rotation", t.rotation}};
  }
  j["factor"] = lanes(v.rgb);
  // Written only where set, so that a material without them reads as it always has.
  if (t.vertex_color) j["vertex_color"] = true;
  if (t.bias != std::array<double, 3>{0, 0, 0}) j["offset"] = lanes(t.bias);
  return j;
}

json relative_textures(json j, const std::string& folder) {
  if (j.is_array()) {
    for (auto& e : j) e = relative_textures(std::move(e), folder);
  } else if (j.is_object()) {
    for (auto& [key, e] : j.items())
      if (key == "texture" && e.is_string()) {
        namespace fs = std::filesystem;
        const fs::path base = fs::absolute(folder.empty() ? fs::path(".") : fs::path(folder)).lexically_normal();
        const fs::path rel = fs::absolute(e.get<std::string>()).lexically_normal().lexically_relative(base);
        if (!rel.empty()) e = rel.generic_string();
      } else {
        e = relative_textures(std::move(e), folder);
      }
  }
  return j;
}

static json texture_schema_body(bool color) {
  json wrap = {{"enum", kWraps}};
  json channels = color ? json::array({"rgb", "r", "g", "b", "a"}) : json::array({"r", "g", "b", "a"});
  json factor = {{"type", "number"}, {"minimum", 0}};
  if (color)
    factor = {{"oneOf", json::array({factor, {{"type", "array"}, {"items", factor}, {"minItems", 3}, {"maxItems", 3}}})}};
  json bounded = {{"type", "number"}, {"minimum", -kScalarMax}, {"maximum", kScalarMax}};
  json pair = {{"type", "array"}, {"items", bounded}, {"minItems", 2}, {"maxItems", 2}};
  // An image, or the vertex colour alone: "texture" may be left out only with "vertex_color": true,
  // and then none of the image's sampling keys.
  json image_keys = json::array();
  for (const auto& k : kImageKeys) image_keys.push_back({{"required", json::array({k})}});
  json alone = {{"properties", {{"vertex_color", {{"const", true}}}}},
                {"required", json::array({"vertex_color"})},
                {"not", {{"anyOf", image_keys}}}};
  if (color) alone["properties"]["channel"] = {{"const", "rgb"}};
  return {{"type", "object"},
          {"description", "the value from an image, the vertex colour or both: clamp(offset + factor ⊗ "
                          "channel(sample(image, uv)) ⊗ vertex colour, the parameter's range)"},
          {"anyOf", json::array({{{"required", json::array({"texture"})}}, alone})},
          {"additionalProperties", false},
          {"properties",
           {{"texture", {{"type", "string"}, {"minLength", 1}, {"description", "image file, relative to this file"}}},
            {"channel", {{"enum", channels}, {"default", color ? "rgb" : "r"}}},
            {"uv", {{"enum", json::array({0, 1})}, {"default", 0}}},
            {"colorspace", {{"enum", json::array({"srgb", "linear"})}, {"default", color ? "srgb" : "linear"}}},
            {"filter", {{"enum", json::array({"nearest", "bilinear"})}, {"default", "bilinear"}}},
            {"wrap", {{"oneOf", json::array({wrap, {{"type", "array"}, {"items", wrap}, {"minItems", 2}, {"maxItems", 2}}})}}},
            {"factor", factor},
            {"offset", factor},
            {"vertex_color",
             {{"type", "boolean"},
              {"default", false},
              {"description", "times the surface's vertex colour (glTF's COLOR_0; white without one): its rgb for a "
                              "colour, the component \"channel\" names for a number"}}},
            {"transform",
             {{"type", "object"},
              {"additionalProperties", false},
              {"properties", {{"offset", pair}, {"scale", pair}, {"rotation", bounded}}}}}}}};
}

json texture_schema(bool color, const Range& range) {
  // The shared definition, and this parameter's largest factor.
  json factor = {{"type", "number"}, {"minimum", 0}, {"maximum", texture_factor_max(range)}};
  if (color)
    factor = {{"oneOf", json::array({factor, {{"type", "array"}, {"items", factor}, {"minItems", 3}, {"maxItems", 3}}})}};
  return {{"allOf", json::array({{{"$ref", color ? "#/$defs/texture_color" : "#/$defs/texture_number"}},
                                 {{"properties", {{"factor", factor}, {"offset", factor}}}}})}};
}

json texture_schema_defs() {
  return {{"texture_color", texture_schema_body(true)}, {"texture_number", texture_schema_body(false)}};
}

std::array<double, 3> texture_value(const Value& val, const Range& range, double u, double v, bool* fragile,
                                    const VertexColor& color0) {
  const TextureRef& t = *val.texture;
  const int channel = t.channel_index();
  std::array<double, 4> s{1, 1, 1, 1};  // no image: the factor and the vertex colour alone
  if (t.has_image()) {
    auto uv = t.transform(u, v);
    if (fragile && t.sampler.filter == TextureFilter::Nearest) {
      const int size[2] = {t.texels->width, t.texels->height};
      for (int k = 0; k < 2; ++k) {
        double x = uv[size_t(k)] * size[k];
        double to_edge = std::fabs(x - std::round(x)) / size[k];
        if (to_edge < kTexelEdgeMargin) *fragile = true;
      }
    }
    s = sample(*t.texels, t.sampler, uv[0], uv[1]);
  }
  std::array<double, 3> out{};
  for (size_t k = 0; k < 3; ++k) {
    const double x = channel < 0 ? s[k] : s[size_t(channel)];
    // A colour takes the vertex colour's rgb, a number the component its channel names.
    const double vc = !t.vertex_color ? 1.0 : val.kind == ParamKind::Color ? color0[k] : color0[size_t(std::max(channel, 0))];
    out[k] = t.bias[k] + val.rgb[k] * x * vc;
  }
  auto b = texture_bounds(range);
  for (double& x : out) x = std::min(std::max(x, b[0]), b[1]);
  return out;
}

namespace {

// A colour parameter of range [0, 1]: the normal map's texture is read as one (rgb, linear).
ParamDef normal_map_param() {
  ParamDef p;
  p.name = "normal_map";
  p.kind = ParamKind::Color;
  p.range = Range::closed(0, 1);
  return p;
}

}  // namespace

std::optional<NormalMap> parse_normal_map(const json& j, const std::string& path, DiagnosticSink& sink) {
  if (!j.is_object()) {
    sink.error(path, fmt::format("expected a normal map object with keys {}, found {}", quoted(kNormalMapKeys),
                                 j.dump()));
    return std::nullopt;
  }
  NormalMap m;
  bool ok = true;
  json texture = json::object();
  for (const auto& [key, val] : j.items()) {
    if (key == "green") {
      if (val == "up" || val == "down") m.green_down = val == "down";
      else sink.error(join_path(path, key), "expected \"up\" (OpenGL's, glTF's convention) or \"down\" (DirectX's), found " + val.dump());
      ok = ok && (val == "up" || val == "down");
    } else if (key == "strength") {
      if (val.is_number() && std::fabs(val.get<double>()) <= kScalarMax) {
        m.strength = val.get<double>();
      } else {
        sink.error(join_path(path, key), fmt::format("expected a number in [-{0}, {0}] (glTF's normalTexture.scale), "
                                                     "found {1}", kScalarMax, val.dump()));
        ok = false;
      }
    } else if (std::find(kNormalMapKeys.begin(), kNormalMapKeys.end(), key) != kNormalMapKeys.end()) {
      texture[key] = val;
    } else {
      std::string hint = suggest(key, kNormalMapKeys);
      sink.error(join_path(path, key),
                 fmt::format("unknown key of a normal map{}; allowed keys: {} (a normal map is always rgb and linear)",
                             hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", quoted(kNormalMapKeys)));
      ok = false;
    }
  }
  texture["colorspace"] = "linear";
  static const ParamDef param = normal_map_param();
  std::optional<Value> v = parse_texture_value(texture, path, param, sink);
  if (!v || !ok) return std::nullopt;
  m.value = *v;
  return m;
}

json normal_map_json(const NormalMap& m) {
  json j = texture_json(m.value);
  for (const char* key : {"channel", "colorspace", "factor"}) j.erase(key);
  j["green"] = m.green_down ? "down" : "up";
  j["strength"] = m.strength;
  return j;
}

json normal_map_schema() {
  json s = texture_schema_body(true);
  for (const char* key : {"channel", "colorspace", "factor", "offset", "vertex_color"}) s["properties"].erase(key);
  s.erase("anyOf");
  s["required"] = json::array({"texture"});
  s["description"] = "a tangent-space normal map (glTF 2.0 §3.9.3): n_t = normalize((2·rgb − 1) ⊗ (s, s, 1)), "
                     "rgb linear; the shading normal normalize(n_t.x·T + n_t.y·B + n_t.z·N), B = w·(N × T)";
  s["properties"]["green"] = {{"enum", json::array({"up", "down"})},
                              {"default", "up"},
                              {"description", "+y up the picture (OpenGL, glTF) or down (DirectX: y negated)"}};
  s["properties"]["strength"] = {{"type", "number"},
                                 {"minimum", -kScalarMax},
                                 {"maximum", kScalarMax},
                                 {"default", 1},
                                 {"description", "glTF's normalTexture.scale"}};
  return s;
}

json coat_normal_map_schema() {
  json s = normal_map_schema();
  s["description"] = "the clear coat's own tangent-space normal map (KHR_materials_clearcoat's clearcoatNormalTexture), "
                     "read as normal_map is, on the same tangent frame (the same uv set); it needs a clear coat "
                     "(gltf_pbr's clearcoat). Without it the coat takes the surface's own, unmapped normal";
  s["properties"]["strength"]["description"] = "glTF's clearcoatNormalTexture.scale";
  return s;
}

std::array<double, 3> normal_map_rgb(const NormalMap& m, double u, double v, bool* fragile) {
  static const Range unit = normal_map_param().range;
  return texture_value(m.value, unit, u, v, fragile);
}

std::array<double, 3> normal_map_tangent_normal(const NormalMap& m, const std::array<double, 3>& rgb) {
  const double s = m.strength;
  std::array<double, 3> n = {s * (2 * rgb[0] - 1), s * (2 * rgb[1] - 1) * (m.green_down ? -1 : 1), 2 * rgb[2] - 1};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (len > 0)
    for (double& x : n) x /= len;
  return n;
}

}  // namespace facet
