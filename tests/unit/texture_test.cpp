// docs/textures.md: the sampling rule, written out once more by hand on small images
// whose texels are known, and every way a texture can be given wrong.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "catalog/material.h"
#include "catalog/program.h"
#include "catalog/texture.h"
#include "core/diagnostics.h"
#include "core/io.h"
#include "core/texture.h"
#include "reference/interpreter.h"
#include "targets/texture_code.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = FACET_SOURCE_DIR;

// A 3×2 image, texel (i, j) = ((i + 1)/4, (j + 1)/4, (i + j)/8, 1): every texel distinct.
Texels three_by_two() {
  Texels t;
  t.width = 3;
  t.height = 2;
  t.channels = 4;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) t.rgba.insert(t.rgba.end(), {(i + 1) / 4.0f, (j + 1) / 4.0f, (i + j) / 8.0f, 1.0f});
  return t;
}

TEST(Texture, WrapModesOnTexelIndices) {
  // repeat: i mod 3; clamp: [0, 2]; mirror: 0 1 2 2 1 0 0 1 2 …
  const int repeat[] = {1, 2, 0, 1, 2, 0, 1};  // i = −2 … 4
  const int clamp[] = {0, 0, 0, 1, 2, 2, 2};
  const int mirror[] = {1, 0, 0, 1, 2, 2, 1};
  for (int i = -2; i <= 4; ++i) {
    EXPECT_EQ(wrap_index(i, 3, TextureWrap::Repeat), repeat[i + 2]) << i;
    EXPECT_EQ(wrap_index(i, 3, TextureWrap::Clamp), clamp[i + 2]) << i;
    EXPECT_EQ(wrap_index(i, 3, TextureWrap::Mirror), mirror[i + 2]) << i;
  }
}

TEST(Texture, NearestReadsTheTexelUnderTheCoordinateRowZeroAtTheTop) {
  Texels t = three_by_two();
  Sampler s;
  s.filter = TextureFilter::Nearest;
  // (u, v) = (0.5, 0.25): column 1, row 0 (the top row: v grows down the picture).
  auto c = sample(t, s, 0.5, 0.25);
  EXPECT_DOUBLE_EQ(c[0], 0.5);
  EXPECT_DOUBLE_EQ(c[1], 0.25);
  c = sample(t, s, 0.99, 0.99);  // the last texel
  EXPECT_DOUBLE_EQ(c[0], 0.75);
  EXPECT_DOUBLE_EQ(c[1], 0.5);
  c = sample(t, s, 1.0 / 3.0 + 1e-12, 0.0);  // just past the first column's right edge
  EXPECT_DOUBLE_EQ(c[0], 0.5);
}

TEST(Texture, BilinearIsExactAtTexelCentresAndLinearBetweenThem) {
  Texels t = three_by_two();
  Sampler s;
  s.wrap = {TextureWrap::Clamp, TextureWrap::Clamp};
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      auto c = sample(t, s, (i + 0.5) / 3, (j + 0.5) / 2);
      EXPECT_NEAR(c[0], (i + 1) / 4.0, 1e-7) << i << "," << j;
      EXPECT_NEAR(c[1], (j + 1) / 4.0, 1e-7) << i << "," << j;
    }
  // Halfway between the centres of (0, 0) and (1, 1): the mean of the four texels.
  auto c = sample(t, s, 1.0 / 3.0, 0.5);
  EXPECT_NEAR(c[0], (0.25 + 0.5) / 2, 1e-7);
  EXPECT_NEAR(c[1], (0.25 + 0.5) / 2, 1e-7);
  EXPECT_NEAR(c[2], (0 + 1 + 1 + 2) / 32.0, 1e-7);
}

TEST(Texture, SrgbIsDecodedPerTexelBeforeTheBlend) {
  Texels t = three_by_two();
  Sampler s;
  s.srgb = true;
  s.wrap = {TextureWrap::Clamp, TextureWrap::Clamp};
  auto c = sample(t, s, 1.0 / 3.0, 0.25);  // halfway between texels (0, 0) and (1, 0)
  EXPECT_NEAR(c[0], (srgb_to_linear(0.25) + srgb_to_linear(0.5)) / 2, 1e-7);
  EXPECT_NEAR(c[3], 1.0, 0);  // alpha is not decoded
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.04045), 0.04045 / 12.92);
  EXPECT_NEAR(srgb_to_linear(0.5), std::pow(0.555 / 1.055, 2.4), 1e-15);
}

TEST(Texture, TransformFollowsKhrTextureTransformsExample) {
  // KHR_texture_transform's README: offset [0, 1], rotation π/2, scale ½ shows "the lower
  // left quadrant of the source image, rotated clockwise 90°": uv (0, 0) → (0, 1) (the
  // picture's bottom-left), (1, 1) → (½, ½), (1, 0) → (0, ½).
  TextureRef r;
  r.offset = {0, 1};
  r.rotation = M_PI / 2;
  r.scale = {0.5, 0.5};
  auto a = r.transform(0, 0), b = r.transform(1, 1), c = r.transform(1, 0);
  EXPECT_NEAR(a[0], 0, 1e-15);
  EXPECT_NEAR(a[1], 1, 1e-15);
  EXPECT_NEAR(b[0], 0.5, 1e-15);
  EXPECT_NEAR(b[1], 0.5, 1e-15);
  EXPECT_NEAR(c[0], 0, 1e-15);
  EXPECT_NEAR(c[1], 0.5, 1e-15);
}

TEST(Texture, ExamplesDecodeTheirImagesAndBecomeInputs) {
  Material m = load_material((kSource / "examples/textured/textured_ggx.json").string());
  MaterialProgram p = compile(m);
  ASSERT_EQ(p.textured.size(), 2u);
  // The lobes' own parameters first, then the colours k_d, k_s.
  EXPECT_EQ(p.textured[0].key, "specular.alpha");
  EXPECT_EQ(p.textured[1].key, "diffuse.color");
  EXPECT_TRUE(p.uses("specular_alpha"));
  EXPECT_TRUE(p.is_textured("diffuse_color"));
  const Texels& t = *p.textured[0].value.texture->texels;
  EXPECT_EQ(t.bits, 16);
  EXPECT_EQ(t.width, 32);
  // The reference's value is the rule's: clamp(factor ⊗ sample, range).
  Reference ref(m);
  ShadingInputs in;
  ref.sample_textures({{{0.3, 0.6}, {0.3, 0.6}}}, in);
  Sampler s = p.textured[0].value.texture->sampler;
  EXPECT_NEAR(in.textured[0][0], sample(t, s, 0.3, 0.6)[0], 1e-15);
}

TEST(Texture, ValuesAreClampedToTheParametersRange) {
  Range positive = Range::positive(), unit = Range::closed(0, 1);
  EXPECT_DOUBLE_EQ(texture_bounds(positive)[0], kTextureOpenMargin);
  EXPECT_TRUE(std::isinf(texture_bounds(positive)[1]));
  EXPECT_DOUBLE_EQ(texture_bounds(unit)[1], 1.0);
  // A black texel for GGX's α > 0 gives α = 0.001, not 0.
  const std::string dir = test::scratch("texture", "").string();
  std::string png = (fs::path(dir) / "black.png").string();
  // 1×1 black RGB PNG.
  const unsigned char black[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
                                 0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
                                 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x08,
                                 0xd7, 0x63, 0x60, 0x60, 0x60, 0x00, 0x00, 0x00, 0x04, 0x00, 0x01, 0x27, 0x34, 0x27,
                                 0x0a, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  write_file_atomic(png, std::string(reinterpret_cast<const char*>(black), sizeof black));
  Material m = parse_material(nlohmann::json::parse(R"({"specular": {"model": "ggx", "alpha": {"texture": "black.png"}}})"),
                              (fs::path(dir) / "m.json").string());
  Reference ref(m);
  ShadingInputs in;
  ref.sample_textures({{{0.5, 0.5}, {0.5, 0.5}}}, in);
  EXPECT_DOUBLE_EQ(in.textured[0][0], kTextureOpenMargin);
}

// Each bad texture is an InputError naming the material file and the key path.
void expect_error(const std::string& material, const std::string& key, const std::string& words) {
  const std::string dir = test::scratch("texture", "").string();
  const std::string file = (fs::path(dir) / "bad.json").string();
  try {
    parse_material(nlohmann::json::parse(material), file);
    ADD_FAILURE() << "accepted: " << material;
  } catch (const InputError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    bool found = false;
    for (const auto& d : e.diagnostics())
      if (d.path == key && d.file == file && d.message.find(words) != std::string::npos) found = true;
    EXPECT_TRUE(found) << material << " → " << e.what();
  }
}

// A material or scene file names images inside its own folder only (issue 28), like a glTF's
// URIs: "..", an absolute path and a symbolic link leading out are refused, with one message
// whether the file named is there or not; a folder allowed (--allow-path) lets it in.
TEST(Texture, TexturesOutsideTheFilesFolderAreRefused) {
  const fs::path dir = test::scratch("texture_outside", "");
  fs::remove_all(dir);
  fs::create_directories(dir / "inside" / "sub");
  fs::create_directories(dir / "outside");
  const fs::path checker = kSource / "examples/textured/textures/checker.png";
  fs::copy_file(checker, dir / "outside" / "c.png");
  fs::copy_file(checker, dir / "inside" / "sub" / "c.png");
  fs::create_symlink(dir / "outside" / "c.png", dir / "inside" / "link.png");
  const std::string file = (dir / "inside" / "m.json").string();
  auto message = [&](const std::string& texture) {
    const nlohmann::json m = {{"diffuse", {{"model", "lambert"}, {"color", {{"texture", texture}}}}}};
    try {
      parse_material(m, file);
    } catch (const InputError& e) {
      for (const auto& d : e.diagnostics())
        if (d.path == "diffuse.color.texture" && d.file == file) {
          std::string said = d.message;
          for (size_t at; (at = said.find(texture)) != std::string::npos;) said.replace(at, texture.size(), "<name>");
          return said;
        }
      return std::string("another error: ") + e.what();
    }
    return std::string("accepted");
  };
  const std::string refused = message("../outside/c.png");
  EXPECT_NE(refused.find("cannot be used"), std::string::npos) << refused;
  EXPECT_NE(refused.find("--allow-path"), std::string::npos) << refused;
  EXPECT_EQ(message("../outside/missing.png"), refused);
  EXPECT_EQ(message((dir / "outside" / "c.png").string()), refused);
  EXPECT_EQ(message((dir / "outside" / "missing.png").string()), refused);
  EXPECT_EQ(message("link.png"), refused);
  EXPECT_EQ(message("/proc/self/environ"), refused);
  EXPECT_EQ(message("sub/../sub/c.png"), "accepted");  // ".." that stays inside is fine
  allow_folder((dir / "outside").string());
  EXPECT_EQ(message((dir / "outside" / "c.png").string()), "accepted");
  EXPECT_EQ(message("link.png"), "accepted");
}

TEST(Texture, BadTexturesNameTheFileAndKey) {
  const std::string dir = test::scratch("texture", "").string();
  write_file_atomic((fs::path(dir) / "not_an_image.png").string(), "this is text, not a PNG");
  write_file_atomic((fs::path(dir) / "empty.png").string(), "");
  // A truncated PPM (maxval 760) that crashed Debian's stb_image when the fuzzer found it.
  write_file_atomic((fs::path(dir) / "truncated.ppm").string(), "P6\n7661\n760\n");
  // PNG headers claiming 16385×16 and 16000×16000 texels: refused before anything is decoded.
  auto header = [](int w, int h) {
    std::string s("\x89PNG\r\n\x1a\n\0\0\0\x0d" "IHDR", 16);
    for (int x : {w, h}) s += {char(x >> 24), char((x >> 16) & 255), char((x >> 8) & 255), char(x & 255)};
    return s + std::string("\x08\x02\0\0\0\0\0\0\0", 9);
  };
  write_file_atomic((fs::path(dir) / "wide.png").string(), header(16385, 16));
  write_file_atomic((fs::path(dir) / "huge.png").string(), header(16000, 16000));
  auto with = [&](const std::string& value) { return fmt::format(R"({{"diffuse": {{"model": "lambert", "color": {}}}}})", value); };
  expect_error(with(R"({"texture": "missing.png"})"), "diffuse.color.texture", "missing.png");
  expect_error(with(R"({"texture": "not_an_image.png"})"), "diffuse.color.texture", "not an image");
  expect_error(with(R"({"texture": "empty.png"})"), "diffuse.color.texture", "empty");
  expect_error(with(R"({"texture": "truncated.ppm"})"), "diffuse.color.texture", "PNM");
  expect_error(with(R"({"texture": "wide.png"})"), "diffuse.color.texture", "16385×16");
  expect_error(with(R"({"texture": "huge.png"})"), "diffuse.color.texture", "1 GiB");
  expect_error(with(R"({"texture": ""})"), "diffuse.color.texture", "file name");
  expect_error(with(R"({"filter": "nearest"})"), "diffuse.color.texture", "missing");
  expect_error(with(R"({"texture": "a.png", "filter": "trilinear"})"), "diffuse.color.filter", "nearest");
  expect_error(with(R"({"texture": "a.png", "wrap": "border"})"), "diffuse.color.wrap", "mirror");
  expect_error(with(R"({"texture": "a.png", "wrap": ["clamp", 3]})"), "diffuse.color.wrap[1]", "repeat");
  expect_error(with(R"({"texture": "a.png", "uv": 2})"), "diffuse.color.uv", "0 or 1");
  expect_error(with(R"({"texture": "a.png", "factor": -1})"), "diffuse.color.factor", "in [0, 10000]");
  // Numbers float32 targets cannot hold (docs/float32.md): a factor above the colour
  // bound, a transform beyond 1e4.
  expect_error(with(R"({"texture": "a.png", "factor": 1e39})"), "diffuse.color.factor", "in [0, 10000]");
  expect_error(with(R"({"texture": "a.png", "transform": {"scale": [1e39, 1]}})"), "diffuse.color.transform.scale",
               "in [-10000, 10000]");
  expect_error(with(R"({"texture": "a.png", "transform": {"scale": [1]}})"), "diffuse.color.transform.scale", "two");
  expect_error(with(R"({"texture": "a.png", "transform": {"skew": 1}})"), "diffuse.color.transform.skew", "unknown");
  expect_error(with(R"({"texture": "a.png", "colour": "srgb"})"), "diffuse.color.colour", "colorspace");
  expect_error(R"({"specular": {"model": "ggx", "alpha": {"texture": "a.png", "channel": "rgb"}}})",
               "specular.alpha.channel", "\"r\"");
  // Parameters that are not shading parameters take no image.
  expect_error(R"({"diffuse": {"model": "lambert"}, "tangent_axis": {"texture": "a.png"}})", "tangent_axis", "vector");
  // m_a and m_e take an image, checked like any other.
  expect_error(R"({"diffuse": {"model": "lambert"}, "emission": {"texture": "missing.png"}})", "emission.texture",
               "missing.png");
  expect_error(R"({"diffuse": {"model": "lambert"}, "ambient": {"texture": "a.png", "channel": "x"}})",
               "ambient.channel", "\"rgb\"");
}

// m_a and m_e from images: inputs after the lobes', read by the shading, not by the
// reflectance; the reference's emitted light is m_a(u, v) ⊗ A + m_e(u, v); the canonical
// JSON writes the image back.
TEST(Texture, AmbientAndEmissionMapsAreSampledForTheShading) {
  Material m = load_material((kSource / "examples/textured/textured_emission.json").string());
  MaterialProgram p = compile(m);
  ASSERT_EQ(p.textured.size(), 2u);
  EXPECT_EQ(p.textured[0].name, kAmbientInput);
  EXPECT_EQ(p.textured[1].key, "emission");
  EXPECT_FALSE(p.uses(kAmbientInput));
  EXPECT_FALSE(p.uses(kEmissionInput));
  Reference ref(m);
  ShadingInputs in;
  const double u = 0.3, v = 0.6;
  ref.sample_textures({{{u, v}, {u, v}}}, in);
  const RGB A = {0.1, 0.2, 0.3};
  RGB e = ref.emitted(in, A, 1.0);
  for (size_t c = 0; c < 3; ++c) {
    double a = texture_value(p.textured[0].value, Range::non_negative(), u, v)[c];
    double em = texture_value(p.textured[1].value, Range::non_negative(), u, v)[c];
    EXPECT_NEAR(e[c], a * A[c] + em, 1e-15);
    EXPECT_GT(em, 0);
  }
  Material back = parse_material(to_json(m), m.source);
  ASSERT_TRUE(back.emission_texture && back.ambient_texture);
  EXPECT_TRUE(fs::equivalent(back.emission_texture->path, m.emission_texture->path));
  EXPECT_EQ(back.emission, m.emission);
  EXPECT_EQ(back.ambient, m.ambient);
}

// KHR_materials_clearcoat, "Emission": under a coat from an image, m_e(u, v) · (1 − clearcoat(u, v) ·
// Fc(n·v)), clearcoat(u, v) the texel times the factor: the input the reflectance reads, sampled once.
TEST(Texture, EmissionUnderATexturedCoatTakesTheCoatsTexel) {
  Material m = load_material((kSource / "examples/textured/textured_emissive_coat.json").string());
  MaterialProgram p = compile(m);
  ASSERT_TRUE(p.emission_weight);
  ASSERT_EQ(p.emission_weight->params.size(), 2u);
  EXPECT_EQ(p.emission_weight->params[1].name, "specular_clearcoat");
  const auto coat = std::find_if(p.textured.begin(), p.textured.end(),
                                 [](const TexturedInput& t) { return t.name == "specular_clearcoat"; });
  const auto emission = std::find_if(p.textured.begin(), p.textured.end(),
                                     [](const TexturedInput& t) { return t.name == kEmissionInput; });
  ASSERT_TRUE(coat != p.textured.end() && emission != p.textured.end());
  Reference ref(m);
  double lo = 1, hi = 0;  // the coat's values must differ across the samples, or the test proves nothing
  for (const auto& [u, v] : {std::pair{0.1, 0.2}, {0.4, 0.7}, {0.8, 0.35}, {0.55, 0.9}}) {
    ShadingInputs in;
    ref.sample_textures({{{u, v}, {u, v}}}, in);
    const double c = texture_value(coat->value, coat->range, u, v)[0];
    const RGB e = texture_value(emission->value, Range::non_negative(), u, v);
    lo = std::min(lo, c);
    hi = std::max(hi, c);
    for (double NoV : {1.0, 0.4, 0.05}) {
      const RGB got = ref.emitted(in, {0, 0, 0}, NoV);
      const double fc = 0.04 + 0.96 * std::pow(1 - NoV, 5);
      for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(got[k], e[k] * (1 - c * fc), 1e-15) << u << ", " << v << ", n·v " << NoV;
    }
  }
  EXPECT_GT(hi - lo, 0.05);
}

TEST(NormalMap, BadNormalMapsNameTheFileAndKey) {
  const std::string dir = test::scratch("texture", "").string();
  auto with = [&](const std::string& value) {
    return fmt::format(R"({{"diffuse": {{"model": "lambert"}}, "normal_map": {}}})", value);
  };
  expect_error(with(R"({"texture": "missing.png"})"), "normal_map.texture", "missing.png");
  expect_error(with(R"({"uv": 0})"), "normal_map.texture", "missing");
  expect_error(with(R"("normals.png")"), "normal_map", "normal map object");
  expect_error(with(R"({"texture": "a.png", "green": "left"})"), "normal_map.green", "DirectX");
  expect_error(with(R"({"texture": "a.png", "strength": "strong"})"), "normal_map.strength",
               "expected a number in [-10000, 10000]");
  expect_error(with(R"({"texture": "a.png", "colorspace": "srgb"})"), "normal_map.colorspace", "always rgb and linear");
  expect_error(with(R"({"texture": "a.png", "factor": 2})"), "normal_map.factor", "unknown key");
  expect_error(with(R"({"texture": "a.png", "strenght": 2})"), "normal_map.strenght", "\"strength\"");
  expect_error(with(R"({"texture": "a.png", "wrap": "border"})"), "normal_map.wrap", "mirror");
  expect_error(with(R"({"texture": "a.png", "uv": 3})"), "normal_map.uv", "0 or 1");
}

// The coat's own normal map (coat_normal_map, glTF's clearcoatNormalTexture) needs a coat and
// the base map's texture coordinates (one tangent frame); the example writes back the same and
// compiles to a reflectance that reads the coat's normal.
TEST(NormalMap, CoatNormalMapsNeedACoatAndTheBasesCoordinates) {
  const fs::path dir = test::scratch("texture", "");
  fs::copy_file(kSource / "examples/textured/textures/normals.png", dir / "a.png", fs::copy_options::overwrite_existing);
  expect_error(R"({"specular": {"model": "gltf_pbr"}, "coat_normal_map": {"texture": "a.png"}})", "coat_normal_map",
               "needs a clear coat");
  expect_error(R"({"diffuse": {"model": "lambert"}, "coat_normal_map": {"texture": "a.png"}})", "coat_normal_map",
               "needs a clear coat");
  expect_error(R"({"specular": {"model": "gltf_pbr", "clearcoat": 0.5}, "normal_map": {"texture": "a.png"},
                   "coat_normal_map": {"texture": "a.png", "uv": 1}})",
               "coat_normal_map.uv", "one tangent frame");
  expect_error(R"({"specular": {"model": "gltf_pbr", "clearcoat": 0.5}, "coat_normal_map": {"texture": "a.png",
                   "green": "sideways"}})",
               "coat_normal_map.green", "DirectX");
  const Material m = load_material((kSource / "examples/textured/textured_coat_normal.json").string());
  ASSERT_TRUE(m.coat_normal_map && !m.normal_map);
  EXPECT_DOUBLE_EQ(m.coat_normal_map->strength, 0.6);
  const nlohmann::json j = to_json(m);
  EXPECT_EQ(to_json(parse_material(j, m.source)), j);
  const MaterialProgram p = compile(m);
  EXPECT_TRUE(p.uses_coat_normal() && p.has_uv_frame() && p.coat_normal_mapped() && !p.normal_mapped());
}

TEST(NormalMap, ExampleParsesAndWritesBackTheSame) {
  const Material m = load_material((kSource / "examples/textured/textured_normal_cook_torrance.json").string());
  ASSERT_TRUE(m.normal_map);
  EXPECT_DOUBLE_EQ(m.normal_map->strength, 0.8);
  EXPECT_FALSE(m.normal_map->green_down);
  EXPECT_EQ(m.normal_map->texture().colorspace, "linear");
  EXPECT_FALSE(m.normal_map->texture().sampler.srgb);
  const nlohmann::json j = to_json(m);
  EXPECT_EQ(j["normal_map"]["green"], "up");
  EXPECT_EQ(j["normal_map"].count("factor"), 0u);
  const Material back = parse_material(j, m.source);
  ASSERT_TRUE(back.normal_map);
  EXPECT_EQ(to_json(back), j);
  EXPECT_TRUE(compile(m).has_textures());
}

// glTF 2.0 §3.9.3 by hand: rgb → n_t with the strength on x and y, green down negating y,
// and the frame's bitangent B = w·(N × T).
TEST(NormalMap, TangentSpaceNormalFollowsGltf) {
  NormalMap m;
  m.strength = 0.5;
  const std::array<double, 3> rgb = {0.75, 0.25, 1.0};  // (0.5, −0.5, 1) before the strength
  auto n = normal_map_tangent_normal(m, rgb);
  const double len = std::sqrt(0.25 * 0.25 * 2 + 1);
  EXPECT_NEAR(n[0], 0.25 / len, 1e-15);
  EXPECT_NEAR(n[1], -0.25 / len, 1e-15);
  EXPECT_NEAR(n[2], 1 / len, 1e-15);
  m.green_down = true;
  EXPECT_NEAR(normal_map_tangent_normal(m, rgb)[1], 0.25 / len, 1e-15);
  // N = +z, T = +x: B = N × T = +y for w = +1, −y for w = −1.
  const Vec3 N(0, 0, 1), T(1, 0, 0);
  Vec3 up = perturb_normal(N, T, 1, {0, 1, 0}), down = perturb_normal(N, T, -1, {0, 1, 0});
  EXPECT_NEAR(up.y, 1, 1e-15);
  EXPECT_NEAR(down.y, -1, 1e-15);
  // A tangent not ⟂ N is Gram–Schmidt'd first: the flat map gives N back exactly.
  Vec3 flat = perturb_normal(N, normalize(Vec3(1, 0, 1)), 1, {0, 0, 1});
  EXPECT_NEAR(flat.z, 1, 1e-15);
  // The anisotropic tangent follows the mapped normal: ⟂ n′.
  Vec3 mapped = normalize(Vec3(0.3, 0.1, 1));
  EXPECT_NEAR(dot(follow_normal(Vec3(1, 0, 0), mapped), mapped), 0, 1e-15);
}

// docs/textures.md, "Tangent frames": T is the unit ∂p/∂u of the shapes' mappings (a finite
// difference of uv_at), and B = w·(N × T) points towards decreasing v.
TEST(NormalMap, ShapesTangentsAreTheirMappingsDerivatives) {
  const Scene s = load_scene("shadows");
  int checked = 0;
  for (const auto& o : s.objects) {
    if (o.type == Object::Type::Mesh) continue;
    for (const Vec3 dir : {Vec3(0.3, 0.4, 0.8), Vec3(-0.5, 0.2, 0.3), Vec3(0.1, -0.7, -0.2)}) {
      Vec3 p, a, b;
      if (o.type == Object::Type::Sphere) {
        p = o.center + normalize(dir) * o.radius;
      } else {
        o.plane_axes(a, b);
        p = o.point + a * (dir.x * o.size) + b * (dir.y * o.size);
      }
      Hit h;
      Vec3 t;
      double w = 0;
      ASSERT_TRUE(o.tangent_at(p, h, t, w));
      EXPECT_EQ(w, 1);
      const Vec3 n = o.normal_at(p, h);
      EXPECT_NEAR(dot(t, n), 0, 1e-12);
      // Moving along t raises u and leaves v; moving along B lowers v and leaves u.
      const double e = 1e-6;
      auto uv = [&](const Vec3& q) {
        const Vec3 on = o.type == Object::Type::Sphere ? o.center + normalize(q - o.center) * o.radius : q;
        return o.uv_at(on, h)[0];
      };
      const auto at = uv(p), along_t = uv(p + t * e), along_b = uv(p + cross(n, t) * (w * e));
      EXPECT_GT(along_t[0] - at[0], 0);
      EXPECT_NEAR(along_t[1] - at[1], 0, 1e-9);
      EXPECT_LT(along_b[1] - at[1], 0);
      EXPECT_NEAR(along_b[0] - at[0], 0, 1e-9);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);  // two spheres and the square
}


// "vertex_color": true multiplies a value by the surface's vertex colour (glTF's COLOR_0):
// a colour by its rgb, a number by the component its channel names; "offset" is added before
// the clamp; without "texture", the vertex colour alone. The example's values, on a surface of
// vertex colour vc, are what docs/textures.md says; the JSON writes them back; the values of
// the vertex colour alone are inputs to sample but no image to bind.
TEST(VertexColor, ValuesTakeTheVertexColourAndAnOffset) {
  const Material m = load_material((kSource / "examples/textured/textured_vertex_color.json").string());
  const MaterialProgram p = compile(m);
  EXPECT_TRUE(p.uses_vertex_color());
  const VertexColor vc{0.25, 0.5, 0.75, 0.4};
  std::map<std::string, const TexturedInput*> by_key;
  for (const auto& t : p.textured) by_key[t.key] = &t;
  ASSERT_TRUE(by_key.count("diffuse.color") && by_key.count("specular.alpha") && by_key.count("specular.fresnel.f0") &&
              by_key.count("ambient"));
  const double u = 0.3, v = 0.6;
  // A colour from an image: factor ⊗ texel ⊗ rgb.
  const TexturedInput& kd = *by_key["diffuse.color"];
  const TextureRef& t = *kd.value.texture;
  const auto texel = sample(*t.texels, t.sampler, u, v);
  const auto kd_value = texture_value(kd.value, kd.range, u, v, nullptr, vc);
  for (size_t c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(kd_value[c], kd.value.rgb[c] * texel[c] * vc[c]);
  // A number of the vertex colour alone, channel "a": offset + factor · alpha.
  const TexturedInput& alpha = *by_key["specular.alpha"];
  EXPECT_FALSE(alpha.value.texture->has_image());
  for (double x : texture_value(alpha.value, alpha.range, u, v, nullptr, vc)) EXPECT_DOUBLE_EQ(x, 0.1 + 0.4 * 0.4);
  // f0: offset + factor ⊗ texel ⊗ rgb.
  const TexturedInput& f0 = *by_key["specular.fresnel.f0"];
  const auto f0_value = texture_value(f0.value, f0.range, u, v, nullptr, vc);
  for (size_t c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(f0_value[c], 0.024 + f0.value.rgb[c] * texel[c] * vc[c]);
  // m_a, the vertex colour alone: factor ⊗ rgb; white without a vertex colour: the factor.
  const TexturedInput& ambient = *by_key["ambient"];
  const auto a = texture_value(ambient.value, ambient.range, u, v, nullptr, vc);
  const auto white = texture_value(ambient.value, ambient.range, u, v);
  for (size_t c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(a[c], ambient.value.rgb[c] * vc[c]);
    EXPECT_DOUBLE_EQ(white[c], ambient.value.rgb[c]);
  }
  // The reference samples them so.
  Reference ref(m);
  ShadingInputs in;
  ref.sample_textures({{{u, v}, {u, v}}}, in, vc);
  for (size_t i = 0; i < p.textured.size(); ++i)
    EXPECT_EQ(in.textured[i], texture_value(p.textured[i].value, p.textured[i].range, u, v, nullptr, vc)) << i;
  // Two images (k_d's and f0's); four values to sample.
  EXPECT_EQ(image_calls(p).size(), 2u);
  EXPECT_EQ(texture_calls(p).size(), 4u);
  // The canonical JSON reads back the same values.
  const Material back = parse_material(to_json(m), m.source);
  const MaterialProgram q = compile(back);
  ASSERT_EQ(q.textured.size(), p.textured.size());
  for (size_t i = 0; i < p.textured.size(); ++i)
    EXPECT_EQ(texture_value(q.textured[i].value, q.textured[i].range, u, v, nullptr, vc),
              texture_value(p.textured[i].value, p.textured[i].range, u, v, nullptr, vc))
        << p.textured[i].key;
}

TEST(VertexColor, BadValuesNameTheFileAndKey) {
  auto with = [&](const std::string& value) { return fmt::format(R"({{"diffuse": {{"model": "lambert", "color": {}}}}})", value); };
  expect_error(with(R"({"vertex_color": 1})"), "diffuse.color.vertex_color", "true");
  expect_error(with(R"({"vertex_color": false})"), "diffuse.color.texture", "\"vertex_color\": true");
  expect_error(with(R"({"vertex_color": true, "filter": "nearest"})"), "diffuse.color.filter", "no \"texture\"");
  expect_error(with(R"({"vertex_color": true, "uv": 1})"), "diffuse.color.uv", "no \"texture\"");
  expect_error(with(R"({"vertex_color": true, "channel": "a"})"), "diffuse.color.channel", "\"rgb\"");
  expect_error(with(R"({"vertex_color": true, "offset": -0.5})"), "diffuse.color.offset", "in [0, 10000]");
  expect_error(with(R"({"vertex_color": true, "offset": [1, 2]})"), "diffuse.color.offset", "three numbers");
  expect_error(R"({"specular": {"model": "ggx", "alpha": {"vertex_color": true, "offset": [0.1, 0.1, 0.1]}}})",
               "specular.alpha.offset", "a number");
}

}  // namespace
}  // namespace facet
