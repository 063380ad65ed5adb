// POV-Ray 3.7 SDL.
//
// POV's own finish is used where it is exactly the catalog's model (the lobes
// whose catalog entry has a PovFinish: Lambert, Phong and Blinn–Phong with a
// grey k_s; POV-compatible attenuation). Every other model is evaluated exactly
// in function pigments (shared/notes/povray.md, recipe A; pov_functions.cpp):
// the function receives the hit point, the generator knows each object's
// analytic normal (a mesh's pigment receives uv_mapping's point in its
// triangle's block of a data image, whose bilinear lookup blends the corners'
// point and normal: pov_mesh.h), and the
// pigment holds the whole per-light radiance. Meshes with a native material are
// POV-Ray's own mesh2, whose smooth normal is facet's (docs/povray-meshes.md).
// `finish { diffuse 1 brilliance 0 }` then multiplies it by the light's colour
// and its shadow test, and nothing else.
//
// A pigment can encode one light. With several lights the scene either renders
// one light per pass (Declare=Facet_Light=i; the passes summed are exact) or,
// by default, puts one inset copy of each object in a light_group per light:
// one run, but the inset (1e-4 of the scene) moves shadow edges by a pixel and
// sharp highlights by up to about 1 % (measured; tests/unit/detection_test.cpp).
//
// The scaffolding is in templates/pov/; every expression is printed by the
// shared writer (targets/writer.h) through PovPrinter, which folds it first.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "core/diagnostics.h"
#include "core/vec.h"
#include "scene/gltf_read.h"
#include "scene/tangents.h"
#include "targets/pov_scene.h"
#include "targets/targets.h"
#include "targets/targets_internal.h"
#include "targets/templates.h"

namespace facet {

using targets::kPovWidth;
using targets::pov_number;
using targets::pov_rgb;
using targets::pov_vector;

namespace {

// ---------------------------------------------------------------- the plan

// POV-Ray's attenuation matches the catalog's law exactly (povray.md §2).
bool native_attenuation(const Light& l) {
  if (l.type == Light::Type::Directional) return true;
  const Attenuation& a = l.attenuation;
  switch (a.law) {
    case Attenuation::Law::None:
    case Attenuation::Law::InverseSquare: return true;
    case Attenuation::Law::Polynomial:
      // min(1, ·) never bites when c1 ≥ 1; fade has one power term.
      return a.constant >= 1 && (a.linear == 0 || a.quadratic == 0);
    case Attenuation::Law::InverseSquareRange: return false;  // no fade has the window
  }
  return false;
}

bool holds(const PovFinishRequirement& r, const ModelSpec& s) {
  auto it = s.values.find(r.param);
  switch (r.kind) {
    case PovFinishRequirement::Kind::Choice: return it != s.values.end() && it->second.choice == r.choice;
    case PovFinishRequirement::Kind::Absent: return it == s.values.end() || !it->second.model;
    case PovFinishRequirement::Kind::Grey: return it != s.values.end() && targets::pov_grey(it->second.rgb);
  }
  return false;
}

// Why a lobe is not a POV-Ray finish, or "" when it is exactly one (the catalog's PovFinish).
std::string lobe_native(const std::optional<ModelSpec>& lobe) {
  if (!lobe) return "";
  const PovFinish& f = lobe->def->pov_finish;
  if (!f.native()) return lobe->def->name + " is not a POV-Ray finish";
  for (const auto& r : f.requirements)
    if (!holds(r, *lobe)) return r.why;
  return "";
}

std::string material_native(const Material& m) {
  const MaterialProgram p = compile(m);
  // A finish's pigment is one colour an object; a vertex colour varies across each triangle.
  if (p.uses_vertex_color()) return "its parameters take the vertex colour, which function pigments blend per triangle";
  if (p.has_textures()) return "its parameters come from images, which function pigments sample";
  // POV-Ray's finish turns a normal towards the ray (trace.cpp), so it would light the inside of a
  // sphere seen through a hole, which facet shades by its own normal, facing away: dark.
  if (alpha_call(m))
    return "its cut-out's alpha comes from an image: function pigments cut it out and shade a surface seen from "
           "behind (a sphere's inside, through a hole) by its own normal, which POV-Ray's finish turns towards the eye";
  std::string why = lobe_native(m.diffuse);
  if (why.empty()) why = lobe_native(m.specular);
  // A finish adds its terms; a layer weights what lies under it by what it reflects itself.
  if (why.empty() && !m.layers.empty())
    why = "layers[0] (" + m.layers[0].def->name + ") weights the lobes under it, which POV-Ray's finish only adds";
  return why;
}

}  // namespace

namespace {

std::string object_kind(const Object& o) {
  switch (o.type) {
    case Object::Type::Sphere: return "sphere";
    case Object::Type::Plane: return "square";
    case Object::Type::Mesh: return fmt::format("mesh of {} triangles", o.mesh->triangles.size());
  }
  return "object";
}

// How object o is drawn, for the header and stderr.
std::string route_line(const Object& o, bool native, bool table) {
  std::string how;
  if (table)
    how = fmt::format("slope tables over n·l and n·v ({0} × {0} nodes a light; approximate)", targets::PovScene::kTableNodes);
  else if (native)
    how = o.type == Object::Type::Mesh
              ? "POV-Ray's finish on mesh2, whose normals POV-Ray blends barycentrically as facet does (exact; "
                "POV-Ray stores the vertices in float32)"
              : "POV-Ray's finish (exact)";
  else
    how = o.type == Object::Type::Mesh ? "function pigments, the geometry read from a data image (exact)"
                                       : "function pigments on the analytic normal (exact)";
  return fmt::format("object \"{}\" ({}): {}", o.name, object_kind(o), how);
}

}  // namespace

PovPlan pov_plan(const Scene& s, const Material* fallback, PovRoute route) {
  PovPlan plan;
  if (route == PovRoute::Exact) plan.reason = "--pov-route exact: function pigments for every object";
  for (size_t i = 0; i < s.objects.size() && plan.reason.empty(); ++i) {
    plan.reason = material_native(s.material_of(i, fallback));
    if (!plan.reason.empty()) plan.reason = "object \"" + s.objects[i].name + "\": " + plan.reason;
  }
  for (const auto& l : s.lights)
    if (plan.reason.empty() && !native_attenuation(l)) plan.reason = "this attenuation law is not a POV-Ray fade";
  plan.native = plan.reason.empty();
  if (route == PovRoute::Native && !plan.native)
    throw std::invalid_argument("--pov-route native: " + plan.reason);
  for (size_t i = 0; i < s.objects.size(); ++i)
    plan.routes.push_back(route_line(s.objects[i], plan.native, targets::pov_table_object(s, i, fallback, route, plan.native)));
  // Function pigments: a pass per light, and one for the emission (m_a ⊗ A + m_e).
  bool emits = false;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Material& m = s.material_of(i, fallback);
    for (int c = 0; c < 3; ++c) emits |= m.ambient[size_t(c)] * s.ambient[size_t(c)] + m.emission[size_t(c)] != 0;
  }
  plan.passes = plan.native ? 1 : std::max(1, int(s.lights.size()) + (emits ? 1 : 0));
  return plan;
}

PovPlan pov_plan(const Material& m, const Scene& s, PovRoute route) { return pov_plan(s, &m, route); }

namespace targets {

bool pov_table_object(const Scene& s, size_t i, const Material* fallback, PovRoute route, bool native) {
  if (native || route != PovRoute::Fast || s.objects[i].type != Object::Type::Mesh) return false;
  const MaterialProgram p = compile(s.material_of(i, fallback));
  // A table's nodes are functions of n·l, n·v and the hit point alone: no texture coordinates,
  // no vertex colour (both come from the data image of the function route), no cut-out image.
  return !p.uses_tangent() && !p.has_textures() && !alpha_call(p.material);
}

bool pov_grey(const RGB& c) { return c[0] == c[1] && c[1] == c[2]; }
bool pov_black(const RGB& c) { return c[0] == 0 && c[1] == 0 && c[2] == 0; }

std::string PovShading::suffix(int ch) const { return dependent ? std::string("_") + "RGB"[ch] : ""; }

RGB PovShading::emission(const Scene& s) const {
  RGB e;
  for (size_t i = 0; i < 3; ++i) e[i] = material->ambient[i] * s.ambient[i] + material->emission[i];
  return e;
}

std::string emission_texture(const RGB& e, double weight, double t) {
  std::string color = t > 0 ? fmt::format("rgbt <{}, {}, {}, {}>", pov_number(weight * e[0]), pov_number(weight * e[1]),
                                          pov_number(weight * e[2]), pov_number(t))
                            : "rgb " + pov_rgb({weight * e[0], weight * e[1], weight * e[2]});
  return "texture {\n  pigment { " + color +
         " }\n  finish { ambient 0 emission Facet_Exposure diffuse 0 specular 0 phong 0 }\n}\n";
}

namespace {

// " keyword value" for each term of the lobe's PovFinish.
std::string finish_terms(const ModelSpec& s, double weight) {
  std::string out;
  for (const PovFinishTerm& t : s.def->pov_finish.terms) {
    double v = t.value;
    switch (t.from) {
      case PovFinishTerm::From::Weight: v = weight; break;
      case PovFinishTerm::From::GreyColor: v = s.at(t.param).rgb[0] * weight; break;
      case PovFinishTerm::From::Number: v = s.at(t.param).number; break;
      case PovFinishTerm::From::Reciprocal: v = 1.0 / s.at(t.param).number; break;
      case PovFinishTerm::From::Fixed: break;
    }
    out.append(" ").append(t.keyword).append(" ").append(pov_number(v));
  }
  return out;
}

}  // namespace

std::string native_texture(const Material& m, double weight) {
  std::string finish = "ambient 0 emission 0";
  finish += m.diffuse ? finish_terms(*m.diffuse, weight) : " diffuse 0";
  finish += m.specular ? finish_terms(*m.specular, weight) : " specular 0 phong 0";
  RGB pigment = {0, 0, 0};
  const std::string pigment_param = m.diffuse ? m.diffuse->def->pov_finish.pigment : "";
  if (!pigment_param.empty()) pigment = m.diffuse->at(pigment_param).rgb;
  return fmt::format("texture {{\n  pigment {{ rgb {} }}\n  finish {{ {} }}\n}}\n", pov_rgb(pigment), finish);
}

// ---------------------------------------------------------------- the scene's frame

PovScene::PovScene(const Scene& s, const Material* fallback, const std::string& source, PovRoute route,
                   const std::string& stem)
    : s_(s), source_(source), plan_(pov_plan(s, fallback, route)), stem_(stem), data_(s.objects.size()),
      routes_(plan_.routes) {
  for (size_t i = 0; i < s.objects.size(); ++i) table_.push_back(pov_table_object(s, i, fallback, route, plan_.native));
  std::vector<const Material*> distinct;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Material* m = &s.material_of(i, fallback);
    auto it = std::find(distinct.begin(), distinct.end(), m);
    shading_of_.push_back(size_t(it - distinct.begin()));
    if (it == distinct.end()) distinct.push_back(m);
  }
  if (distinct.empty() && fallback) distinct.push_back(fallback);
  std::set<std::string> prefixes;
  for (const Material* m : distinct) {
    auto sh = std::make_unique<PovShading>();
    sh->material = m;
    sh->program = compile(*m);
    if (distinct.size() > 1) {
      sh->prefix = capital(identifier(m->name)) + "_";
      while (!prefixes.insert(sh->prefix).second) sh->prefix = "M" + sh->prefix;
    }
    std::set<const ir::Function*> own = {sh->program.reflectance.get()};
    if (sh->program.diffuse) own.insert(sh->program.diffuse.get());
    if (sh->program.specular) own.insert(sh->program.specular.get());
    for (const auto& layer : sh->program.layers) own.insert(layer.get());
    for (const auto& w : sh->program.emission_weights) own.insert(w.get());
    if (sh->program.emission_weight) own.insert(sh->program.emission_weight.get());
    sh->printer = PovPrinter(sh->prefix, own);
    sh->dependent = sh->printer.channel_dependent(sh->program.reflectance);
    shadings_.push_back(std::move(sh));
  }
  register_textures();
  double r = length(s.camera.position);
  for (const auto& o : s.objects) {
    Vec3 c;
    double rad;
    o.bounds(c, rad);
    r = std::max(r, length(c) + rad);
  }
  scale_ = std::max(r, 1.0);
  build_scaffolding();
  register_mesh_files();
}

// Each mesh's include file and, on the function route, its data image: written
// later, straight to their files (generate_pov_files' caller), from the mesh itself.
// POV-Ray's own shading (native finish, slope tables) reads the mesh's normal_vectors;
// the function route reads its normals from the data image and needs none.
void PovScene::register_mesh_files() {
  std::vector<double> insets;  // the one-run file's copies k = 1 … passes − 1 (passes())
  for (int k = 1; !plan_.native && k < plan_.passes; ++k) insets.push_back(1e-4 * double(k) * scale_);
  for (size_t o = 0; o < s_.objects.size(); ++o) {
    const Object& obj = s_.objects[o];
    if (obj.type != Object::Type::Mesh) continue;
    std::shared_ptr<const Mesh> mesh = obj.mesh;
    const bool numbered = !plan_.native && !table_[o];
    files_.push_back({fmt::format("{}_mesh{}.inc", stem_, o),
                      [mesh, o, name = obj.name, numbered, insets](std::ostream& out) {
                        write_pov_mesh_include(out, *mesh, o, name, !numbered, numbered, insets);
                      }});
    if (!numbered) continue;
    const bool textured = shading(o).textured();
    // A normal map's corner tangents (scene/tangents.h): three more planes.
    std::shared_ptr<const std::vector<std::array<double, 4>>> tangents;
    if (const auto set = shading(o).material->frame_uv())
      tangents = std::make_shared<const std::vector<std::array<double, 4>>>(mesh_tangents(*mesh, *set));
    // The vertex colours where the material reads them (object_function() reads the same planes).
    const bool colors = shading(o).program.uses_vertex_color() && !mesh->colors.empty();
    data_[o] = pov_mesh_data(*mesh, fmt::format("{}_mesh{}.ppm", stem_, o), textured, tangents, colors);
    routes_[o] += fmt::format("; POV-Ray reads its positions from {} to within {:.2g} and normals to within {:.2g}",
                              data_[o].file, data_[o].position_error, data_[o].normal_error);
    if (textured) routes_[o] += fmt::format(", texture coordinates to within {:.2g}", data_[o].texcoord_error);
    if (tangents) routes_[o] += ", and the tangent frame's tangents (normal maps', anisotropy's) as its normals";
    if (colors) routes_[o] += fmt::format(", vertex colours to within {:.2g}", data_[o].color_error);
    files_.push_back({data_[o].file, [mesh, d = data_[o]](std::ostream& out) { write_pov_mesh_image(out, *mesh, d); }});
  }
}

// Each textured parameter's image, written beside the scene (pov_texture.h), and its
// sampling function; a colour from an image or the vertex colour makes the material's
// pigments per channel. A value of the vertex colour alone has no image.
void PovScene::register_textures() {
  for (auto& sh : shadings_) {
    std::vector<TextureCall> calls = texture_calls(sh->program);
    for (const auto& n : normal_map_calls(sh->program)) calls.push_back(n);
    if (auto a = alpha_call(*sh->material)) calls.push_back(*a);
    std::map<std::string, PovTexture> sampled;  // the colours a max₃ is derived from
    for (const auto& c : calls) {
      if (!c.max_of.empty()) {  // max₃ of a colour sampled before it (TexturedInput::max_of)
        const PovTexture& colour = sampled.at(c.max_of);
        const std::vector<ir::FunctionPtr> fs = pov_max_sample_functions(colour, c.name);
        for (const auto& f : fs) sh->printer.add_own(f);
        sh->samples[c.name] = {fs.back(), colour.call.uv, colour.call.image, colour.call.vertex_color};
        continue;
      }
      PovTexture t;
      t.call = c;
      t.image = -1;
      if (c.image) {
        t.image = int(textures_.size());
        t.file = fmt::format("{}_texture{}.ppm", stem_, t.image);
        if (c.channel == 3) t.alpha = fmt::format("{}_texture{}_alpha.pgm", stem_, t.image);
        const Texels* texels = c.texels;
        files_.push_back({t.file, [texels](std::ostream& out) { write_pov_texture_image(out, *texels, false); }});
        if (!t.alpha.empty())
          files_.push_back({t.alpha, [texels](std::ostream& out) { write_pov_texture_image(out, *texels, true); }});
        textures_.push_back(t);
      }
      if (c.name == "normal_map" || c.name == "coat_normal_map") {  // three channels as numbers, which the object functions combine
        auto& rgb = c.name == "normal_map" ? sh->normal_map : sh->coat_normal_map;
        for (int k = 0; k < 3; ++k) {
          rgb[size_t(k)] = pov_sample_function(pov_lane(t, k, c.name));
          sh->printer.add_own(rgb[size_t(k)]);
        }
        sh->normal_map_uv = c.uv;
        continue;
      }
      ir::FunctionPtr f = pov_sample_function(t);
      sh->printer.add_own(f);
      sampled[c.name] = t;
      if (c.name == "alpha") {  // the cut-out's: read by its Facet_Kept, not by the reflectance
        sh->alpha = f;
        sh->alpha_uv = c.uv;
        continue;
      }
      sh->samples[c.name] = {f, c.uv, c.image, c.vertex_color};
      if (sh->printer.channel_dependent(f)) sh->dependent = true;
    }
  }
}

std::string PovScene::texture_declarations() const {
  const bool vertex_colors =
      std::any_of(shadings_.begin(), shadings_.end(), [](const auto& sh) { return sh->program.uses_vertex_color(); });
  if (textures_.empty() && !vertex_colors) return "";
  std::string out = textures_.empty() ? "" : render_template("pov/textures.pov", {});
  for (const auto& t : textures_) out += pov_texture_declarations(t);
  if (vertex_colors) out += pov_rgb_declarations();
  return out + "\n";
}

namespace {

// The camera's statements (look_at last: it turns the vectors before it). Perspective: the
// vertical field of view whatever the aspect; orthographic: up and right as long as the
// view is high and wide (POV-Ray's orthographic camera takes their lengths as its extent).
std::string camera_block(const Camera& c) {
  const std::string eye = fmt::format("  location {}\n", pov_vector(c.position));
  const std::string aim = fmt::format("  sky {}\n  look_at {}\n", pov_vector(c.up), pov_vector(c.look_at));
  if (c.orthographic)
    return fmt::format("  orthographic\n{0}  right -x*{1}*image_width/image_height\n  up y*{1}\n{2}", eye,
                       pov_number(c.height), aim);
  return fmt::format("  perspective\n{0}  right -x*image_width/image_height\n  up y\n  sky {1}\n"
                     "  angle 2*degrees(atan(image_width/image_height*tan(radians({2}/2))))  // vertical field of view "
                     "{2}°\n  look_at {3}\n",
                     eye, pov_vector(c.up), pov_number(c.fov), pov_vector(c.look_at));
}

}  // namespace

std::string PovScene::render() {
  const Camera& c = s_.camera;
  const int count = plan_.native ? 1 : plan_.passes;
  size_t triangles = 0;
  for (const auto& o : s_.objects) triangles += o.type == Object::Type::Mesh ? o.mesh->triangles.size() : 0;
  const bool big = triangles >= 250000;  // a second or more: say so
  const auto start = std::chrono::steady_clock::now();
  if (big) progress(fmt::format("writing the POV-Ray scene: {} triangles", gltf_detail::thousands(triangles)));
  std::string body = plan_.native ? native() : functions(true) + lights() + passes();  // before the header: it
  if (big)                                                                             // names what lights() measured
    progress(fmt::format("POV-Ray scene written in {:.1f} s",
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
  // A camera ray goes on through each surface cut out (transmit 1), one trace level each.
  const bool cutouts = std::any_of(kept_.begin(), kept_.end(), [](const ir::FunctionPtr& f) { return f != nullptr; });
  return render_template("pov/scene.pov", {{"header", header()},
                                           {"trace_level", cutouts ? " max_trace_level 64" : ""},
                                           {"passes", std::to_string(count)},
                                           {"last", std::to_string(count - 1)},
                                           {"camera", camera_block(c)},
                                           {"body", body}});
}

std::string PovScene::library() {
  const PovShading& sh = *shadings_.front();
  const Material& m = *sh.material;
  const std::string name = capital(identifier(m.name));
  if (m.frame_uv())  // its pigment macro takes the user's normal and no tangent frame
    throw InputError({{m.source.empty() ? m.name : m.source, m.frame_key(),
                       "POV-Ray's --library does not read texture-coordinate tangent frames (normal maps, glTF's "
                       "anisotropy) yet (a scene does: docs/textures.md)"}});
  if (m.masked())  // its pigment macro holds the radiance, which has no transmit
    throw InputError({{m.source.empty() ? m.name : m.source, "alpha_cutoff",
                       "POV-Ray's --library does not cut out yet (a scene does: docs/textures.md)"}});
  if (plan_.native) {
    RGB e = sh.emission(s_);
    std::string emission;
    if (!pov_black(e))
      emission = "// The emissive part (m_a ⊗ A + m_e) as a layer over it:\n#declare Facet_" + name +
                 "_Emission = " + emission_texture(e, 2, 0.5);
    return render_template("pov/library_native.pov", {{"header", header()},
                                                      {"name", name},
                                                      {"texture", native_texture(m, 1)},
                                                      {"emission", emission}});
  }
  PovPigment p;
  const bool colored = sh.program.uses_vertex_color();
  p.radiance = [&](int ch) {
    std::vector<ir::Expr> args = {var("x"), var("y"), var("z")};
    for (const char* n : {"NX", "NY", "NZ"}) args.push_back(ir::call(declared(n, 3), {var("x"), var("y"), var("z")}));
    for (const char* n : {"Facet_Lx", "Facet_Ly", "Facet_Lz", "Facet_Ex", "Facet_Ey", "Facet_Ez"}) args.push_back(var(n));
    if (sh.textured())
      for (const char* n : {"S0", "T0", "S1", "T1"}) args.push_back(ir::call(declared(n, 3), {var("x"), var("y"), var("z")}));
    if (sh.textured() && colored)
      for (const char* n : {"R0", "G0", "B0", "A0"}) args.push_back(ir::call(declared(n, 3), {var("x"), var("y"), var("z")}));
    return ir::call(declared("Facet_Point_Shade" + sh.suffix(ch), args.size()), args);
  };
  p.factors = [](int) { return std::vector<ir::Expr>{var("Scale")}; };
  return render_template("pov/library_functions.pov",
                         {{"header", header()},
                          {"functions", functions()},
                          {"uv_doc", std::string(sh.textured() ? "//   * its texture coordinates sets 0 and 1 as functions of (x, y, z): S0, T0, S1, T1 "
                                                                 "(glTF's: v down the picture; docs/textures.md);\n"
                                                               : "") +
                                         (colored ? "//   * its vertex colour (glTF's COLOR_0, linear) as functions of (x, y, z): R0, G0, B0, A0 "
                                                    "(1 where the surface has none);\n"
                                                  : "")},
                          {"signature", !sh.textured() ? "NX, NY, NZ, LightPosition, Eye, Scale"
                                        : colored      ? "NX, NY, NZ, S0, T0, S1, T1, R0, G0, B0, A0, LightPosition, Eye, Scale"
                                                       : "NX, NY, NZ, S0, T0, S1, T1, LightPosition, Eye, Scale"},
                          {"shade", point_shade()},
                          {"pigment", indented(pov_pigment(sh.printer, sh.dependent, p, kPovWidth - 2), 2)}});
}

namespace {

// Comment lines (each "// …") word-wrapped to the scene's width.
std::string wrapped_comments(const std::string& lines) {
  std::string out;
  for (size_t start = 0; start < lines.size();) {
    size_t end = lines.find('\n', start);
    if (end == std::string::npos) end = lines.size();
    std::string line = lines.substr(start, end - start);
    if (line.rfind("// ", 0) == 0) comment_to(out, line.substr(3), "", "//", kPovWidth);
    else out.append(line).append("\n");
    start = end + 1;
  }
  return out;
}

}  // namespace

std::string PovScene::header() {
  std::string names, description;
  for (const auto& sh : shadings_) {
    names += (names.empty() ? "" : ", ") + sh->material->name;
    description += describe_material(*sh->material, "//");
  }
  std::string notes;
  if (plan_.native) {
    notes = "POV-Ray's own finish is this model: every light in one render is exact.";
  } else if (plan_.passes > 1) {
    bool meshes = std::any_of(s_.objects.begin(), s_.objects.end(),
                              [](const Object& o) { return o.type == Object::Type::Mesh; });
    notes = fmt::format(
        "Function pigments hold one light each. Exact: render with Declare=Facet_Light=i for i = 0..{} (the lights{}; "
        "Facet_Passes below) and sum the images. Facet_Light=-1 (default) renders everything at once through "
        "light_group copies inset by 1e-4 of the scene's size, and the inset moves what each copy sees: shadow edges "
        "shift by a pixel, and sharp highlights by up to 1 % (facet measured Ward αx = 0.1 at 0.5 % on 1 % of its "
        "pixels){}.",
        plan_.passes - 1, plan_.passes > int(s_.lights.size()) ? ", then the emission" : "",
        meshes ? "; on meshes about 1 % of the pixels are off by up to 15 %. Use the passes for anything you compare"
               : "");
  } else {
    notes = "Function pigments evaluate the model exactly (to 16-bit output precision).";
  }
  if (!plan_.native) notes += "\n(" + plan_.reason + ")";
  std::string note_lines;
  comment_to(note_lines, notes, "", "//", kPovWidth);
  for (const auto& r : routes_) comment_to(note_lines, r, "", "//", kPovWidth);
  return render_template("pov/header.pov", {{"kind", shadings_.size() > 1 ? "materials" : "material"},
                                            {"names", names},
                                            {"route", plan_.native ? "(native finish)" : "(function pigments)"},
                                            {"version", FACET_VERSION},
                                            {"source", source_},
                                            {"description", wrapped_comments(description)},
                                            {"scene", s_.name},
                                            {"notes", note_lines}});
}

// `light_source { … }` on one line, or one clause a line where that is too long.
std::string PovScene::light_source(const Light& l, std::vector<std::string> extra, double scale,
                                   const std::string& comment) {
  bool parallel = l.type == Light::Type::Directional;
  ir::Expr color = pov_grey(l.color) ? ir::Expr(l.color[0]) : var(pov_rgb(l.color));
  std::vector<std::string> clauses = {
      parallel ? pov_vector(Vec3(0, 0, 0) - l.direction * 1e5) : pov_vector(l.position),
      "color rgb " + PovPrinter().expr((color * scale * var("Facet_Exposure")).node(), 0)};
  if (parallel) clauses.push_back("parallel point_at <0, 0, 0>");
  clauses.insert(clauses.end(), extra.begin(), extra.end());
  std::string one = "light_source {";
  for (const auto& c : clauses) one += " " + c;
  one += " }";
  std::string note = comment.empty() ? "" : "  // " + comment;
  if (indent_ + one.size() + note.size() <= kPovWidth) return one + note + "\n";
  CodeWriter w(kPovWidth - indent_);
  if (!comment.empty()) w.comment(comment);
  w.open("light_source {");
  for (const auto& c : clauses) w.line(c);
  w.close("}");
  return w.take();
}

// The geometry of object o with `body` (lines) inside; `shrink` (relative to the scene) insets a copy.
std::string PovScene::object(size_t o, double shrink, const std::string& body, const std::string& modifiers) {
  const Object& obj = s_.objects[o];
  CodeWriter w(kPovWidth - indent_);
  if (obj.type == Object::Type::Sphere) {
    w.open("sphere {");
    w.line(pov_vector(obj.center) + ", " + pov_number(obj.radius - shrink * scale_));
  } else if (obj.type == Object::Type::Plane) {
    Vec3 u, v;
    obj.plane_axes(u, v);
    Vec3 c = obj.point - obj.normal * (shrink * scale_);
    Vec3 p0 = c + (u + v) * obj.size, p1 = c + (v - u) * obj.size, p2 = c - (u + v) * obj.size,
         p3 = c + (u - v) * obj.size;
    w.open("polygon {");
    w.line(fmt::format("5, {}, {}, {}, {}, {}", pov_vector(p0), pov_vector(p1), pov_vector(p2), pov_vector(p3),
                       pov_vector(p0)));
  } else {
    return mesh(o, shrink, body, modifiers);
  }
  w.text(body);
  w.text(modifiers);
  w.close("}");
  return w.take();
}

// A mesh with `body` (its texture) inside: an instance of the mesh2 its include
// file declares (register_mesh_files); copy k of the one-run file, inset by 1e-4·k
// of the scene, has vertices of its own. On the function route the pigment is the
// whole radiance, n·l ≤ 0 included, so POV-Ray must not skip a light by its own
// normal (trace.cpp, ComputeOneDiffuseLight): double_illuminate.
std::string PovScene::mesh(size_t o, double shrink, const std::string& body, const std::string& modifiers) {
  const long copy = std::lround(shrink / 1e-4);
  std::string name = copy == 0 ? fmt::format("Facet_Mesh{}", o) : fmt::format("Facet_Mesh{}_Copy{}", o, copy);
  std::string lit_both = data_[o].file.empty() ? "" : "double_illuminate\n";
  return fmt::format("object {{  // {}\n  {}\n", s_.objects[o].name, name) + indented(body, 2) +
         indented(modifiers + lit_both, 2) + "}\n";
}

// ---------------------------------------------------------------- the native route

std::string PovScene::native_light(size_t i) {
  const Light& l = s_.lights[i];
  if (l.type == Light::Type::Directional) return light_source(l, {}, 1, fmt::format("light {}: directional", i));
  const Attenuation& a = l.attenuation;
  double scale = 1;
  std::vector<std::string> extra;
  // POV-Ray fades only when fade_distance > 1e-10 (point.cpp): 1/d² is C/(2 fd²) · 2/(1 + (d/fd)²) = C/(fd² + d²)
  // with fd = 1e-4, within 1e-8/d² of it (povray.md §2).
  if (a.law == Attenuation::Law::InverseSquare) {
    constexpr double fd = 1e-4;
    scale = 1 / (2 * fd * fd);
    extra.push_back(fmt::format("fade_distance {} fade_power 2", pov_number(fd)));
  }
  if (a.law == Attenuation::Law::Polynomial) {
    if (a.linear == 0 && a.quadratic == 0) {
      scale = 1 / a.constant;
    } else if (a.quadratic == 0) {  // 2/(1 + d/fd) · C/(2 c1) = C/(c1 + c2 d)
      scale = 1 / (2 * a.constant);
      extra.push_back(fmt::format("fade_distance {} fade_power 1", pov_number(a.constant / a.linear)));
    } else {  // 2/(1 + (d/fd)²) · C/(2 c1) = C/(c1 + c3 d²)
      scale = 1 / (2 * a.constant);
      extra.push_back(fmt::format("fade_distance {} fade_power 2", pov_number(std::sqrt(a.constant / a.quadratic))));
    }
  }
  if (l.type == Light::Type::Spot) {
    extra.push_back(fmt::format("spotlight point_at {} radius {} falloff {} tightness {}",
                                pov_vector(l.position + l.direction), pov_number(l.cutoff), pov_number(l.cutoff),
                                pov_number(l.exponent)));
  }
  return light_source(l, extra, scale, fmt::format("light {}", i));
}

std::string PovScene::native() {
  std::string lights, objects;
  for (size_t i = 0; i < s_.lights.size(); ++i) lights += native_light(i);
  for (size_t o = 0; o < s_.objects.size(); ++o)
    if (s_.objects[o].type == Object::Type::Mesh) objects += mesh_declarations(o);
  for (size_t o = 0; o < s_.objects.size(); ++o) {
    if (absent(o)) {
      comment_to(objects, fmt::format("object \"{}\" is cut out everywhere (its alpha is below its cutoff)", s_.objects[o].name),
                 "", "//", kPovWidth);
      continue;
    }
    const PovShading& sh = shading(o);
    RGB e = sh.emission(s_);
    std::string tex = pov_black(e) ? native_texture(*sh.material, 1)
                                   : native_texture(*sh.material, 2) + emission_texture(e, 2, 0.5);
    objects += object(o, 0, tex, "");
  }
  return render_template("pov/native.pov", {{"lights", lights}, {"objects", objects}});
}

}  // namespace targets

std::string generate_pov_sweep(const Material& m) {
  require_no_images(m, "which the POV-Ray sweep target does not sample yet (GLSL does; docs/textures.md)");
  Scene s = default_scene();
  return targets::PovScene(s, &m, m.source).sweep();
}

PovOutput generate_pov_files(const Scene& s, const Material* fallback, const std::string& source, PovRoute route,
                             const std::string& stem) {
  targets::PovScene scene(s, fallback, source, route, stem);
  PovOutput out;
  out.code = scene.render();
  out.files = std::move(scene.files());
  out.plan = scene.plan();
  out.plan.routes = scene.routes();  // with what generation measured
  return out;
}

namespace {

// The code of a scene that reads no file beside it.
std::string pov_code_alone(const PovOutput& out) {
  if (!out.files.empty())
    throw std::invalid_argument("this POV-Ray scene reads " + out.files.front().name +
                                " beside it: write it with generate_pov_files (facet generate -o FILE)");
  return out.code;
}

}  // namespace

PovOutput generate_pov_library(const Material& m, const std::string& source, PovRoute route, const std::string& stem) {
  const Scene s = default_scene();  // PovScene keeps a reference: it must outlive it
  targets::PovScene scene(s, &m, source, route, stem);
  PovOutput out;
  out.code = scene.library();
  out.files = std::move(scene.files());
  out.plan = scene.plan();
  return out;
}

std::string generate_pov_scene(const Scene& s, const Material* fallback, const std::string& source) {
  return pov_code_alone(generate_pov_files(s, fallback, source, PovRoute::Auto, "facet"));
}

std::string generate_pov(const Material& m, const GenerateOptions& o) {
  Scene s = o.scene ? *o.scene : default_scene();
  if (o.library) return pov_code_alone(generate_pov_library(m, o.source, o.pov_route, "facet"));
  return pov_code_alone(generate_pov_files(s, &m, o.source, o.pov_route, "facet"));
}

}  // namespace facet
