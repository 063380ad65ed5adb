// POV-Ray's function route: the shading frame, the lights and the objects as IR
// functions (named Facet_…, printed like the catalog's terms), the pigments
// that hold their radiance, and the passes (shared/notes/povray.md, recipe A).
#include <array>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "catalog/catalog.h"
#include "core/text.h"
#include "targets/pov_mesh.h"
#include "targets/pov_scene.h"
#include "targets/sweep_grid.h"
#include "targets/templates.h"

namespace facet::targets {

using ir::Expr;

namespace {

// Three scalar expressions: POV-Ray functions see vectors component by component.
struct Triple {
  Expr x, y, z;
};
Triple operator+(const Triple& a, const Triple& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Triple operator-(const Vec3& a, const Triple& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Triple operator-(const Triple& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Triple operator/(const Triple& a, const Expr& d) { return {a.x / d, a.y / d, a.z / d}; }
Expr dot3(const Triple& a, const Triple& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Expr length3(const Triple& a) { return ir::sqrt(dot3(a, a)); }
Triple cross3(const Triple& a, const Triple& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Triple constant(const Vec3& v) { return {v.x, v.y, v.z}; }
Triple params(ir::FunctionBuilder& fb, const char* x, const char* y, const char* z) {
  return {fb.param(x), fb.param(y), fb.param(z)};
}
Triple lets(ir::FunctionBuilder& fb, const char* x, const char* y, const char* z, const Triple& v) {
  return {fb.let(x, v.x), fb.let(y, v.y), fb.let(z, v.z)};
}
void append(std::vector<Expr>& out, const Triple& v) { out.insert(out.end(), {v.x, v.y, v.z}); }
std::vector<Expr> args(std::initializer_list<Triple> vs) {
  std::vector<Expr> out;
  for (const auto& v : vs) append(out, v);
  return out;
}

bool reads(const ir::Function& f, std::initializer_list<const char*> inputs) {
  for (const auto& p : f.params)
    for (const char* in : inputs)
      if (p.name == in) return true;
  return false;
}
bool reads_tangent(const ir::Function& f) { return reads(f, {"LoT", "VoT", "LoB", "VoB", "HoT", "HoB"}); }

// `name`(n, l, v[, t]) → `reflectance` (a light of unit colour), its inputs the dot
// products of unit vectors, h = (l + v) / Hl, Hl = max(|l + v|, ε) (catalog.h,
// Input), b = n × t.
// The texture coordinates S0, T0, S1, T1 as parameters of `fb`, where `sh` samples images,
// then the vertex colour R0, G0, B0, A0 where it reads that.
std::vector<Expr> uv_params(ir::FunctionBuilder& fb, const PovShading& sh) {
  if (!sh.textured()) return {};
  std::vector<Expr> out = {fb.param("S0"), fb.param("T0"), fb.param("S1"), fb.param("T1")};
  if (sh.program.uses_vertex_color())
    for (const char* c : {"R0", "G0", "B0", "A0"}) out.push_back(fb.param(c));
  return out;
}

// Textured input `s` at the coordinates and vertex colour `uv` (uv_params()'s order).
Expr sample_call(const PovShading::Sample& s, const std::vector<Expr>& uv) {
  std::vector<Expr> args;
  if (s.image) args = {uv[2 * size_t(s.uv)], uv[2 * size_t(s.uv) + 1]};
  if (s.vertex_color) args.insert(args.end(), uv.begin() + 4, uv.begin() + 8);
  return ir::call(s.f, args);
}
std::vector<Expr> with(std::vector<Expr> a, const std::vector<Expr>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Whether the lights' functions of `sh` take the coat's own normal E after n (and t): the
// surface's own, where the lobes read a normal map's (MaterialProgram::uses_coat_normal).
bool takes_coat(const PovShading& sh) { return sh.program.uses_coat_normal(); }

// Whether they take the texture frame's handedness Tw after T: the lobes' tangent is that frame's
// (MaterialProgram::uv_tangent; KHR_materials_anisotropy), and b = Tw·(n × t).
bool takes_handedness(const PovShading& sh) { return sh.program.uv_tangent(); }

ir::FunctionPtr frame_function(const ir::FunctionPtr& reflectance, const std::string& name, bool tangent,
                               const PovShading& sh) {
  ir::FunctionBuilder fb(name, "");
  Triple N = params(fb, "Nx", "Ny", "Nz"), L = params(fb, "Lx", "Ly", "Lz"), V = params(fb, "Vx", "Vy", "Vz");
  Triple T = tangent ? params(fb, "Tx", "Ty", "Tz") : Triple{0.0, 0.0, 0.0};
  const std::optional<Expr> W = tangent && takes_handedness(sh) ? std::optional<Expr>(fb.param("Tw")) : std::nullopt;
  Triple E = takes_coat(sh) ? params(fb, "Ex", "Ey", "Ez") : Triple{0.0, 0.0, 0.0};
  const std::vector<Expr> uv = uv_params(fb, sh);
  Triple H = L + V, B = cross3(N, T);
  if (W) B = {B.x * *W, B.y * *W, B.z * *W};  // b = w·(n × t) on the texture frame
  Expr Hl = reads(*reflectance, {"NoH", "VoH", "HoT", "HoB"}) ? fb.let("Hl", ir::max(length3(H), kEpsilon)) : Expr(1.0);
  auto input = [&](const std::string& in) -> Expr {
    if (auto t = sh.samples.find(in); t != sh.samples.end()) return sample_call(t->second, uv);
    if (in == "NoL") return dot3(N, L);
    if (in == "NoV") return dot3(N, V);
    if (in == "LoV") return dot3(L, V);
    if (in == "LoT") return dot3(L, T);
    if (in == "VoT") return dot3(V, T);
    if (in == "LoB") return dot3(L, B);
    if (in == "VoB") return dot3(V, B);
    if (in == "NoH") return dot3(N, H) / Hl;
    if (in == "VoH") return dot3(V, H) / Hl;
    if (in == "HoT") return dot3(H, T) / Hl;
    if (in == "HoB") return dot3(H, B) / Hl;
    if (in == "CoL") return dot3(E, L);
    if (in == "CoV") return dot3(E, V);
    if (in == "CoH") return dot3(E, H) / Hl;
    throw std::logic_error("facet: POV-Ray has no input " + in);
  };
  std::vector<Expr> inputs;
  for (const auto& in : reflectance->params) inputs.push_back(input(in.name));
  return fb.returns(ir::call(reflectance, inputs));
}

// The normal maps' frame at a point (docs/textures.md, "Tangent frames"): the object's unit
// normal N and unit tangent T ⟂ N with B = N × T (the shapes': w = +1), or a mesh's blended
// tangent t made ⟂ n (Gram–Schmidt) with B = w·(n × T). Built once for both maps.
struct MapFrame {
  Triple N, T, B;
};
MapFrame map_frame(ir::FunctionBuilder& fb, const Triple& n, const Triple& t, const std::optional<Expr>& w) {
  MapFrame f{lets(fb, "Gx", "Gy", "Gz", n), lets(fb, "Ux", "Uy", "Uz", t), {0.0, 0.0, 0.0}};
  f.B = cross3(f.N, f.T);
  if (w) {
    Expr along = fb.let("Ud", dot3(f.N, f.T));
    const Triple g = lets(fb, "Vx", "Vy", "Vz", {f.T.x - f.N.x * along, f.T.y - f.N.y * along, f.T.z - f.N.z * along});
    Expr gl = fb.let("Vl", length3(g));
    f.T = lets(fb, "Kx", "Ky", "Kz", g / gl);
    const Triple c = cross3(f.N, f.T);
    f.B = {c.x * *w, c.y * *w, c.z * *w};
  }
  return f;
}

// A normal map's normal (catalog/texture.h, NormalMap; glTF 2.0 §3.9.3) on frame `f`: n_t =
// normalize((2·rgb − 1) ⊗ (s, ±s, 1)), normalize(n_t.x·T + n_t.y·B + n_t.z·N): the lobes' map, or
// with `coat` the coat's own (Material::coat_normal_map), its values named apart (Z…) so that
// both can be in one function. `sh` has that map. `frame` gives the frame, built where the first
// map asks for it (after its texel's lets, so that a lone map's chain carries no more values).
Triple mapped_normal(ir::FunctionBuilder& fb, const PovShading& sh, const std::vector<Expr>& uv,
                     const std::function<const MapFrame&()>& frame, bool coat = false) {
  const std::array<ir::FunctionPtr, 3>& rgb = coat ? sh.coat_normal_map : sh.normal_map;
  const NormalMap& m = coat ? *sh.material->coat_normal_map : *sh.material->normal_map;
  const size_t set = size_t(sh.normal_map_uv);
  auto lane = [&](size_t k) { return ir::call(rgb[k], {uv[2 * set], uv[2 * set + 1]}); };
  const std::string tag = coat ? "Z" : "";
  auto named = [&](const char* stem, const Triple& v) {
    return Triple{fb.let(tag + stem + "x", v.x), fb.let(tag + stem + "y", v.y), fb.let(tag + stem + "z", v.z)};
  };
  const double s = m.strength;
  Triple c = named("C", {s * (2.0 * lane(0) - 1.0), (m.green_down ? -s : s) * (2.0 * lane(1) - 1.0), 2.0 * lane(2) - 1.0});
  Expr len = fb.let(tag + "Cl", length3(c));
  const MapFrame& f = frame();
  auto times = [](const Triple& v, const Expr& k) { return Triple{v.x * k, v.y * k, v.z * k}; };
  const Triple mapped = named("Q", times(f.T, c.x / len) + times(f.B, c.y / len) + times(f.N, c.z / len));
  Expr ml = fb.let(tag + "Ql", length3(mapped));
  return mapped / ml;
}

// The normal maps' normals at a point of own normal `own` and frame t, w (w: a mesh's): the
// lobes' map's, or with `coat` the coat's own map's; `own` where the material has no such map.
// The frame is built where the first map asks for it, and shared.
struct PointNormals {
  ir::FunctionBuilder& fb;
  const PovShading& sh;
  const std::vector<Expr>& uv;
  Triple own, t;
  std::optional<Expr> w;
  std::optional<MapFrame> frame{};
  Triple mapped(bool coat) {
    if (!(coat ? sh.coat_normal_map : sh.normal_map)[0]) return own;
    auto shared = [this]() -> const MapFrame& {
      if (!frame) frame = map_frame(fb, own, t, w);
      return *frame;
    };
    return mapped_normal(fb, sh, uv, shared, coat);
  }
};

// Whether the lights' functions of `sh` take the tangent: a normal map under a lobe that reads
// it, whose tangent follows the mapped normal (mapped_tangent) instead of the tangent rule on it,
// or lobes that turn from the texture frame's tangent (frame_tangent; they take Tw too).
bool takes_tangent(const PovShading& sh, const ir::Function& reflectance) {
  return (sh.normal_map[0] || sh.program.uv_tangent()) && reads_tangent(reflectance);
}

Triple frame_tangent(ir::FunctionBuilder& fb, const Triple& t, const Triple& n);
Triple mapped_tangent(ir::FunctionBuilder& fb, const PovShading& sh, const Triple& n, const Triple& m);

// The tangent arguments of a light's function (where it takes them) at a point of own normal
// `own` whose lobes read `n`, on the frame t, w: the texture frame's tangent made ⟂ n and its
// handedness (w, or +1 on the shapes) where the lobes turn from it, else the tangent rule made ⟂ n.
void append_tangent(ir::FunctionBuilder& fb, const PovShading& sh, std::vector<Expr>& a, const Triple& own,
                    const Triple& n, const Triple& t, const std::optional<Expr>& w) {
  if (!takes_tangent(sh, *sh.program.reflectance)) return;
  if (!takes_handedness(sh)) return append(a, mapped_tangent(fb, sh, own, n));
  append(a, frame_tangent(fb, t, n));
  a.push_back(w ? *w : Expr(1.0));  // the shapes' frames are right-handed
}

// The texture frame's tangent t (a mesh's blended corner tangent, a shape's ∂p/∂u) made ⟂ the
// lobes' normal n, normalize(t − n(n·t)): the lobes' tangent where they turn from that frame.
Triple frame_tangent(ir::FunctionBuilder& fb, const Triple& t, const Triple& n) {
  const Triple u = lets(fb, "Ox", "Oy", "Oz", t);
  Expr along = fb.let("Od", dot3(u, n));
  const Triple g = lets(fb, "Yx", "Yy", "Yz", {u.x - n.x * along, u.y - n.y * along, u.z - n.z * along});
  Expr gl = fb.let("Yl", length3(g));
  return g / gl;
}

// The tangent rule on the object's normal n (t = normalize(axis × n), or x̂ × n where
// |axis × n| < ε), then Gram–Schmidt against the mapped normal m: normalize(t − m(m·t)).
Triple mapped_tangent(ir::FunctionBuilder& fb, const PovShading& sh, const Triple& n, const Triple& m) {
  const Triple c = lets(fb, "Ax", "Ay", "Az", cross3(constant(normalize(Vec3(sh.material->tangent_axis))), n));
  Expr len = fb.let("Al", length3(c));
  Expr fallback = fb.let("Fl", ir::sqrt(n.z * n.z + n.y * n.y));
  const Triple t = lets(fb, "Rx", "Ry", "Rz",
                        {ir::select(len < 1e-4, Expr(0.0), c.x / len), ir::select(len < 1e-4, -n.z / fallback, c.y / len),
                         ir::select(len < 1e-4, n.y / fallback, c.z / len)});
  Expr along = fb.let("Ad", dot3(t, m));
  const Triple g = lets(fb, "Wx", "Wy", "Wz", {t.x - m.x * along, t.y - m.y * along, t.z - m.z * along});
  Expr gl = fb.let("Wl", length3(g));
  return g / gl;
}

}  // namespace

// {P}Facet_Reflect{suffix}(n, l, v) → `reflectance`, with the tangent rule where it
// reads t: t = normalize(axis × n), or x̂ × n = (0, −nz, ny) where |axis × n| < ε.
ir::FunctionPtr PovScene::reflect_function(PovShading& sh, const ir::FunctionPtr& reflectance,
                                           const std::string& suffix) {
  // A coat's own normal comes with a normal map, under which the tangent is a parameter too.
  if (takes_coat(sh) && reads_tangent(*reflectance) && !takes_tangent(sh, *reflectance))
    throw std::logic_error("facet: POV-Ray's tangent rule takes no coat normal");
  if (!reads_tangent(*reflectance) || takes_tangent(sh, *reflectance)) {  // the tangent, if any, as a parameter
    ir::FunctionPtr f = frame_function(reflectance, "Facet_Reflect" + suffix, takes_tangent(sh, *reflectance), sh);
    sh.printer.add_own(f);
    return f;
  }
  ir::FunctionPtr frame = frame_function(reflectance, "Facet_Frame" + suffix, true, sh);
  ir::FunctionBuilder unit("Facet_Tangent" + suffix, "");  // t = C / |C|
  Triple N = params(unit, "Nx", "Ny", "Nz"), L = params(unit, "Lx", "Ly", "Lz"), V = params(unit, "Vx", "Vy", "Vz");
  Triple C = params(unit, "Cx", "Cy", "Cz");
  Expr len = unit.param("Len");
  const std::vector<Expr> unit_uv = uv_params(unit, sh);
  ir::FunctionPtr tangent = unit.returns(ir::call(frame, with(args({N, L, V, C / len}), unit_uv)));

  ir::FunctionBuilder fb("Facet_Reflect" + suffix, "");
  N = params(fb, "Nx", "Ny", "Nz"), L = params(fb, "Lx", "Ly", "Lz"), V = params(fb, "Vx", "Vy", "Vz");
  const std::vector<Expr> uv = uv_params(fb, sh);
  // |C| from the cross product itself, so one helper takes C and |C|.
  const Triple axis_x_n = cross3(constant(normalize(Vec3(sh.material->tangent_axis))), N);
  C = lets(fb, "Cx", "Cy", "Cz", axis_x_n);
  Expr c_len = fb.let("Len", length3(axis_x_n));
  std::vector<Expr> fallback = args({N, L, V, {0.0, -N.z, N.y}}), own = args({N, L, V, C});
  fallback.push_back(ir::sqrt(N.z * N.z + N.y * N.y));
  own.push_back(c_len);
  fallback = with(fallback, uv);
  own = with(own, uv);
  ir::FunctionPtr f =
      fb.returns(ir::select(c_len < 1e-4, ir::call(tangent, fallback), ir::call(tangent, own)));
  for (const auto& g : {frame, tangent, f}) sh.printer.add_own(g);
  return f;
}

// {P}Facet_Light{i}{suffix}(x, y, z, n): the radiance of light i of unit colour at a
// point with unit normal n, seen from the camera: att(d) · spot · `reflect`. L and V
// lead to the light and the eye, D and Dv are their lengths.
ir::FunctionPtr PovScene::light_function(PovShading& sh, size_t i, const ir::FunctionPtr& reflect,
                                         const std::string& suffix) {
  const Light& l = s_.lights[i];
  ir::FunctionBuilder fb(fmt::format("Facet_Light{}{}", i, suffix), "");
  Triple P = params(fb, "x", "y", "z"), N = params(fb, "Nx", "Ny", "Nz");
  const bool tangent = takes_tangent(sh, *sh.program.reflectance);
  const Triple T = tangent ? params(fb, "Tx", "Ty", "Tz") : Triple{0.0, 0.0, 0.0};
  const std::optional<Expr> W = tangent && takes_handedness(sh) ? std::optional<Expr>(fb.param("Tw")) : std::nullopt;
  const std::optional<Triple> E = takes_coat(sh) ? std::optional<Triple>(params(fb, "Ex", "Ey", "Ez")) : std::nullopt;
  const std::vector<Expr> uv = uv_params(fb, sh);
  auto frame = [&](const Triple& L, const Triple& V) {
    std::vector<Expr> a = tangent ? args({N, L, V, T}) : args({N, L, V});
    if (W) a.push_back(*W);
    if (E) append(a, *E);
    return with(a, uv);
  };
  // v: towards the eye, or (orthographic) the one direction against the view.
  const Camera& c = s_.camera;
  if (l.type == Light::Type::Directional) {
    Triple V = constant(c.toward_eye(Vec3(0, 0, 0)));
    if (!c.orthographic) {
      V = lets(fb, "Vx", "Vy", "Vz", c.position - P);
      V = V / fb.let("Dv", length3(c.position - P));
    }
    ir::FunctionPtr f = fb.returns(ir::call(reflect, frame(constant(-l.direction), V)));
    sh.printer.add_own(f);
    return f;
  }
  // The lengths from the differences themselves: one helper takes all four.
  Triple L = lets(fb, "Lx", "Ly", "Lz", l.position - P);
  Triple V = c.orthographic ? constant(c.toward_eye(Vec3(0, 0, 0))) : lets(fb, "Vx", "Vy", "Vz", c.position - P);
  Expr d = fb.let("D", length3(l.position - P));
  if (!c.orthographic) V = V / fb.let("Dv", length3(c.position - P));
  std::optional<Expr> factor;
  auto times = [&](const Expr& x) { factor = factor ? *factor * x : x; };
  const Attenuation& a = l.attenuation;
  if (a.law == Attenuation::Law::InverseSquare) times(ir::call(terms::attenuation_inverse_square(), {d}));
  if (a.law == Attenuation::Law::Polynomial)
    times(ir::call(terms::attenuation_polynomial(), {d, a.constant, a.linear, a.quadratic}));
  if (a.law == Attenuation::Law::InverseSquareRange)
    times(ir::call(terms::attenuation_inverse_square_range(), {d, a.range}));
  if (l.type == Light::Type::Spot)
    times(ir::call(terms::spot_cone(),
                   {-dot3(L / d, constant(l.direction)), std::cos(l.cutoff * kPi / 180), l.exponent}));
  Expr reflected = ir::call(reflect, frame(L / d, V));
  ir::FunctionPtr f = fb.returns(factor ? *factor * reflected : reflected);
  sh.printer.add_own(f);
  return f;
}

// {P}Facet_Emission(x, y, z, n, S0, T0, S1, T1[, R0, G0, B0, A0]): m_a ⊗ A + m_e, either from
// its image or vertex colour (the sampling function of its textured input) or its colour, m_e
// times emission_weight(n·v[, its textured parameters]) where layers lie over it (n the coat's
// normal: the surface's own, or the coat's own normal map's; v towards the camera: its position,
// or an orthographic camera's −forward); called like a light function.
ir::FunctionPtr PovScene::emission_function(PovShading& sh) {
  ir::FunctionBuilder fb("Facet_Emission", "");
  const Triple P = params(fb, "x", "y", "z");
  const Triple N = params(fb, "Nx", "Ny", "Nz");
  const std::vector<Expr> uv = uv_params(fb, sh);
  auto term = [&](const char* input, const RGB& c) -> Expr {
    auto t = sh.samples.find(input);
    if (t == sh.samples.end()) return ir::color(c[0], c[1], c[2]);
    return sample_call(t->second, uv);
  };
  const RGB& A = s_.ambient;
  Expr ambient = term(kAmbientInput, sh.material->ambient) * ir::color(A[0], A[1], A[2]);
  Expr emitted = term(kEmissionInput, sh.material->emission);
  if (sh.program.emission_weight) {
    const Camera& cam = s_.camera;
    Triple V = cam.orthographic ? constant(-cam.basis().forward) : cam.position - P;
    if (!cam.orthographic) {
      V = lets(fb, "Vx", "Vy", "Vz", V);
      V = V / fb.let("Vl", length3(V));
    }
    std::vector<Expr> args = {dot3(N, V)};  // then the textured parameters it reads, sampled here
    for (size_t i = 1; i < sh.program.emission_weight->params.size(); ++i)
      args.push_back(sample_call(sh.samples.at(sh.program.emission_weight->params[i].name), uv));
    emitted = emitted * ir::call(sh.program.emission_weight, args);
  }
  ir::FunctionPtr f = fb.returns(ambient + emitted);
  sh.printer.add_own(f);
  return f;
}

// {P}Facet_Kept(x, y, z, n[, t], S0, T0, S1, T1): 1 where the cut-out's alpha (Facet_Sample_alpha)
// is at least its cutoff (glTF 2.0 §3.9.4, alphaMode MASK), 0 where the surface is cut out;
// called like a light's function, so that each object hands it its texture coordinates.
ir::FunctionPtr PovScene::kept_function(PovShading& sh) {
  ir::FunctionBuilder fb("Facet_Kept", "");
  params(fb, "x", "y", "z");
  params(fb, "Nx", "Ny", "Nz");
  if (takes_tangent(sh, *sh.program.reflectance)) {
    params(fb, "Tx", "Ty", "Tz");
    if (takes_handedness(sh)) fb.param("Tw");
  }
  if (takes_coat(sh)) params(fb, "Ex", "Ey", "Ez");
  const std::vector<Expr> uv = uv_params(fb, sh);
  const size_t set = size_t(sh.alpha_uv);
  Expr alpha = ir::call(sh.alpha, {uv[2 * set], uv[2 * set + 1]});
  ir::FunctionPtr f = fb.returns(ir::select(alpha < *sh.material->alpha_cutoff, Expr(0.0), Expr(1.0)));
  sh.printer.add_own(f);
  return f;
}

// `name`: `light` (a light's, or the emission's function) on object o, which takes (x, y, z):
// the hit point on spheres and squares, uv_mapping's point on meshes.
ir::FunctionPtr PovScene::object_function(size_t o, const std::string& name, const ir::FunctionPtr& light,
                                          std::optional<size_t> light_index, bool own_normal) {
  const Object& obj = s_.objects[o];
  ir::FunctionBuilder fb(name, "");
  Triple P = params(fb, "x", "y", "z");
  // docs/textures.md: the shapes' texture coordinates (the same in both sets); their vertex
  // colour is white.
  std::vector<Expr> uv;
  const bool colored = shading(o).program.uses_vertex_color();
  auto coordinates = [&](const Expr& s, const Expr& t) {
    if (!shading(o).textured()) return;
    Expr s0 = fb.let("S0", s), t0 = fb.let("T0", t);
    uv = {s0, t0, s0, t0};
    if (colored) uv.insert(uv.end(), 4, Expr(1.0));
  };
  // The call of `light` at point `at` of own normal `own` and frame t, w (w: a mesh's; the
  // shapes' is +1): its arguments the lobes' normal n (the normal map's), the tangent that follows
  // it where the light takes one, the coat's normal where it takes that (takes_coat: the coat's
  // own map's, else `own`), then the coordinates. Where `own_normal` (the emission's function) the
  // point and the coat's normal alone, which the emission's weight reads.
  const PovShading& sh = shading(o);
  auto shaded = [&](const Triple& at, const Triple& own, const Triple& t, const std::optional<Expr>& w) {
    PointNormals normals{fb, sh, uv, own, t, w};
    const Triple coat = normals.mapped(true);
    if (own_normal) return ir::call(light, with(args({at, coat}), uv));
    const Triple n = normals.mapped(false);
    std::vector<Expr> a = args({at, n});
    append_tangent(fb, sh, a, own, n, t, w);
    if (takes_coat(sh)) append(a, coat);
    return ir::call(light, with(a, uv));
  };
  if (obj.type == Object::Type::Plane) {
    Vec3 a, b;
    obj.plane_axes(a, b);
    const Triple q = P - obj.point;
    coordinates(0.5 + dot3(q, constant(a)) / (2 * obj.size), 0.5 - dot3(q, constant(b)) / (2 * obj.size));
    return fb.returns(shaded(P, constant(obj.normal), constant(a), std::nullopt));
  }
  if (obj.type == Object::Type::Mesh) {
    // (x, y) is uv_mapping's: where in the data image the hit point's block
    // blends its corners' point and normal (pov_mesh.h).
    auto data = [&](const char* f) { return declared(fmt::format("Facet_Mesh{}_{}", o, f), 2); };
    std::vector<Expr> at = {P.x, P.y};
    Triple hit = lets(fb, "Px", "Py", "Pz", {ir::call(data("PX"), at), ir::call(data("PY"), at),
                                             ir::call(data("PZ"), at)});
    Triple M = lets(fb, "Mx", "My", "Mz", {ir::call(data("MX"), at), ir::call(data("MY"), at),
                                           ir::call(data("MZ"), at)});
    Expr len = fb.let("Len", length3(M));
    if (shading(o).textured())
      uv = {fb.let("S0", ir::call(data("S0"), at)), fb.let("T0", ir::call(data("T0"), at)),
            fb.let("S1", ir::call(data("S1"), at)), fb.let("T1", ir::call(data("T1"), at))};
    // The vertex colour: the data image's blend of the corners' (pov_mesh.h), white without colours.
    if (colored)
      for (const char* c : {"CR", "CG", "CB", "CA"})
        uv.push_back(!obj.mesh->colors.empty() ? fb.let(std::string(1, c[1]) + "0", ir::call(data(c), at)) : Expr(1.0));
    // Without a map the frame is not read.
    if (!sh.framed() || (own_normal && !sh.coat_normal_map[0]))
      return fb.returns(ir::call(light, with(args({hit, M / len}), uv)));
    // The blended corner tangents (docs/textures.md, "Tangent frames"), w the sign of the blended w.
    const Triple tangent = {ir::call(data("UX"), at), ir::call(data("UY"), at), ir::call(data("UZ"), at)};
    Expr w = fb.let("W", ir::select(ir::call(data("UW"), at) < 0.0, Expr(-1.0), Expr(1.0)));
    Expr lit = shaded(hit, M / len, tangent, w);
    if (!light_index || own_normal) return fb.returns(lit);
    // The smooth normal decides whether the light is above the surface (the reference's rule,
    // docs/textures.md "Normal maps"); POV-Ray's own lit side is the flat triangle's, which
    // faces the light a little past the smooth normal's terminator, where n′ may still.
    const Light& l = s_.lights[*light_index];
    const Triple toward = l.type == Light::Type::Directional ? constant(-l.direction) : l.position - hit;
    return fb.returns(lit * ir::select(dot3(M, toward) > 0.0, Expr(1.0), Expr(0.0)));
  }
  // Sphere: n = (P − C)/|P − C|, which holds for the shrunken copies too.
  Triple radial = P - obj.center;
  Expr r = fb.let("R", length3(radial));
  const Triple d = radial / r;
  coordinates(0.5 + ir::atan2(d.x, d.z) / (2 * kPi), ir::acos(ir::clamp(d.y, -1.0, 1.0)) / kPi);
  // docs/textures.md, "Tangent frames": the sphere's ∂p/∂u ∝ (d_z, 0, −d_x).
  const Triple t = sh.framed() ? Triple{d.z, 0.0, -d.x} / ir::sqrt(d.z * d.z + d.x * d.x) : Triple{0.0, 0.0, 0.0};
  return fb.returns(shaded(P, d, t, std::nullopt));
}

namespace {

// Whether `sh` is shaded lobe by lobe (PovShading::lobes): its reflectance differs per
// channel only through k_d and k_s.
bool by_lobe(const PovShading& sh) {
  const MaterialProgram& p = sh.program;
  if (!sh.dependent || sh.textured()) return false;  // k_d, k_s from an image are no colour map's
  if (!p.layers.empty()) return false;               // a layer weights k_d ⊗ ρ_d + k_s ⊗ ρ_s as a whole
  for (const auto& lobe : {p.diffuse, p.specular})
    if (lobe && (lobe->result_type() != ir::Type::Float || sh.printer.channel_dependent(lobe))) return false;
  return true;
}

}  // namespace

void PovScene::build_scaffolding() {
  for (auto& sh : shadings_) {
    sh->reflect = reflect_function(*sh, sh->program.reflectance, "");
    for (size_t i = 0; i < s_.lights.size(); ++i) sh->lights.push_back(light_function(*sh, i, sh->reflect, ""));
    if (!by_lobe(*sh)) continue;
    for (bool specular : {false, true}) {
      if (!(specular ? sh->program.specular : sh->program.diffuse)) continue;
      PovShading::Lobe lobe;
      lobe.suffix = specular ? "_Specular" : "_Diffuse";
      lobe.color = (specular ? sh->material->specular : sh->material->diffuse)->at("color").rgb;
      ir::FunctionPtr reflectance = lobe_reflectance(sh->program, specular);
      sh->printer.add_own(reflectance);
      lobe.reflect = reflect_function(*sh, reflectance, lobe.suffix);
      for (size_t i = 0; i < s_.lights.size(); ++i)
        lobe.lights.push_back(light_function(*sh, i, lobe.reflect, lobe.suffix));
      sh->lobes.push_back(std::move(lobe));
    }
  }
  for (size_t o = 0; o < s_.objects.size(); ++o) {
    PovShading& sh = *shadings_[shading_of_[o]];
    if (!table_[o] || !sh.tables.empty()) continue;
    for (size_t i = 0; i < s_.lights.size(); ++i) sh.tables.push_back(table_function(sh, i));
    const TableError e = table_error(*sh.material);
    routes_[o] += fmt::format("; measured at every cell's centre, |Δ|/max(1, |ρ|) is at most {:.2g} and over 2e-3 in "
                              "{:.2g} % of the cells (highlights and grazing angles: docs/povray-meshes.md)",
                              e.worst, 100 * e.share_over);
  }
  for (auto& sh : shadings_) {
    if (sh->material->ambient_texture || sh->material->emission_texture || sh->program.emission_weight)
      sh->emission_function = emission_function(*sh);
    if (sh->alpha) sh->kept = kept_function(*sh);
  }
  for (size_t o = 0; o < s_.objects.size(); ++o) {
    objects_.emplace_back(s_.lights.size());
    const PovShading& sh = shading(o);
    kept_.push_back(sh.kept ? object_function(o, fmt::format("Facet_Object{}_Kept", o), sh.kept) : nullptr);
    emissions_.push_back(sh.emission_function ? object_function(o, fmt::format("Facet_Object{}_Emission", o),
                                                                sh.emission_function, std::nullopt, true)
                                              : nullptr);
    if (table_[o]) continue;  // the table's leaves call Facet_Table{i}
    for (size_t i = 0; i < s_.lights.size(); ++i) {
      const std::string name = fmt::format("Facet_Object{}_Light{}", o, i);
      if (sh.lobes.empty()) objects_[o][i].push_back(object_function(o, name, sh.lights[i], i));
      for (const auto& lobe : sh.lobes)
        objects_[o][i].push_back(object_function(o, name + lobe.suffix, lobe.lights[i], i));
    }
  }
}

// What the objects of `sh` call: its lobes' reflect functions, or its whole one, and the
// whole reflectance where a slope table reads it (`objects` false: the whole one, which the
// library and the sweep call).
std::vector<ir::FunctionPtr> PovScene::reflect_roots(const PovShading& sh, bool objects) const {
  std::vector<ir::FunctionPtr> roots;
  if (sh.program.emission_weight) roots.push_back(sh.program.emission_weight);  // the emission function's
  if (!objects || sh.lobes.empty()) {
    roots.push_back(sh.reflect);
    return roots;
  }
  if (!sh.tables.empty()) roots.push_back(sh.program.reflectance);
  for (const auto& lobe : sh.lobes) roots.push_back(lobe.reflect);
  return roots;
}

std::string PovScene::functions(bool objects) {
  std::string constants, terms, frames;
  for (const auto& sh : shadings_) {
    constants += "// ---- Material constants";
    if (!sh->prefix.empty()) constants += " of \"" + sh->material->name + "\"";
    constants += "\n" + sh->printer.constants(ir::constants(reflect_roots(*sh, objects)));
  }
  std::set<const ir::Function*> printed;
  for (const auto& sh : shadings_) {
    std::vector<ir::FunctionPtr> roots = {terms::attenuation_inverse_square(), terms::attenuation_polynomial(),
                                          terms::spot_cone()};
    for (const auto& l : s_.lights)  // the window only where a light has it: no scene pays for it otherwise
      if (l.attenuation.law == Attenuation::Law::InverseSquareRange) {
        roots.push_back(terms::attenuation_inverse_square_range());
        break;
      }
    for (const auto& r : reflect_roots(*sh, objects)) roots.push_back(r);
    for (const auto& f : ir::dependencies(roots))
      if (!is_scaffold(*f) && printed.insert(f.get()).second) terms += sh->printer.function(f) + "\n";
  }
  for (const auto& sh : shadings_) {
    std::vector<ir::FunctionPtr> roots = reflect_roots(*sh, objects);
    if (objects && sh->emission_function) roots.push_back(sh->emission_function);
    if (objects && sh->kept) roots.push_back(sh->kept);
    for (const auto& f : ir::dependencies(roots))
      if (is_scaffold(*f) && !is_declared(*f)) frames += sh->printer.function(f);
    if (objects)  // the object functions read the normal maps
      for (const auto* map : {&sh->normal_map, &sh->coat_normal_map})
        if ((*map)[0])
          for (const auto& f : *map) frames += sh->printer.function(f);
  }
  return render_template("pov/functions.pov", {{"constants", constants}, {"terms", terms},
                                               {"frames", texture_declarations() + frames}});
}

// Mesh o's data functions (pov_mesh.h, on the function route) and its include
// file, whose mesh2 objects every pass and copy of it instances.
std::string PovScene::mesh_declarations(size_t o) {
  std::string out = data_[o].file.empty() ? "" : pov_mesh_decoder(data_[o], o);  // on the function route
  return out + fmt::format("#include {}  // mesh {} (\"{}\"): its mesh2, declared\n",
                           quoted_literal(fmt::format("{}_mesh{}.inc", stem_, o)), o, s_.objects[o].name);
}

std::string PovScene::lights() {
  std::string functions, objects;
  for (const auto& sh : shadings_) {
    for (const auto& f : sh->lights)
      if (sh->lobes.empty()) functions += sh->printer.function(f);
    for (const auto& lobe : sh->lobes)
      for (const auto& f : lobe.lights) functions += sh->printer.function(f);
    for (const auto& f : sh->tables) functions += sh->printer.function(f);
  }
  for (size_t o = 0; o < s_.objects.size(); ++o)
    if (s_.objects[o].type == Object::Type::Mesh) objects += mesh_declarations(o);  // the data functions first
  for (size_t o = 0; o < s_.objects.size(); ++o) {
    for (const auto& parts : objects_[o])
      for (const auto& f : parts) objects += shading(o).printer.function(f);
    if (emissions_[o]) objects += shading(o).printer.function(emissions_[o]);
    if (kept_[o]) objects += shading(o).printer.function(kept_[o]);
  }
  return render_template("pov/lights.pov", {{"functions", functions}, {"objects", objects}});
}

std::string pov_pigment(const PovPrinter& pr, bool dependent, const PovPigment& p, size_t width) {
  const bool t = p.transmit > 0;
  auto color = [&](const std::string& r, const std::string& g, const std::string& b) {
    if (t) return fmt::format("rgbt <{}, {}, {}, {}>", r, g, b, pov_number(p.transmit));
    return r == g && g == b ? "rgb " + r : fmt::format("rgb <{}, {}, {}>", r, g, b);
  };
  // Each entry holds max(0, min(1, radiance · Π factors)) and its colour map scales it
  // back: the colour at 1 is weight / Π factors (times the entry's colour). The scale is in
  // the colour, not a factor of the pigment: that would scale transmit too. Several entries
  // are averaged, so each colour is also times their count.
  struct Entry {
    Expr held;
    std::array<double, 3> coefficient;  // the colour at 1 is coefficient / denominator (0: black)
    Expr denominator;
    int ch;                             // the channel the printer prints `held` for
  };
  std::vector<Entry> entries;
  for (const auto& part : p.parts) {
    Expr scale = Expr(part.scale) * var("Facet_Exposure");
    Entry e{part.radiance * scale, {}, scale, 0};
    for (size_t c = 0; c < 3; ++c) e.coefficient[c] = p.weight * part.color[c];
    entries.push_back(e);
  }
  for (int ch = 0; p.parts.empty() && ch < (dependent ? 3 : 1); ++ch) {
    std::vector<Expr> factors = p.factors(ch);
    if (factors.empty()) continue;
    Entry e{p.radiance(ch), {}, factors.front(), ch};
    for (const auto& f : factors) e.held = e.held * f;
    for (size_t k = 1; k < factors.size(); ++k) e.denominator = e.denominator * factors[k];
    for (int c = 0; c < 3; ++c) e.coefficient[size_t(c)] = !dependent || c == ch ? p.weight : 0;
    entries.push_back(e);
  }
  if (entries.empty()) return "pigment { " + color("0", "0", "0") + " }\n";
  const double n = double(entries.size());
  auto top = [&](const Entry& e, size_t c) {
    return e.coefficient[c] != 0 ? pr.expr((Expr(n * e.coefficient[c]) / e.denominator).node(), e.ch)
                                 : std::string("0");
  };
  auto held = [&](const Entry& e) {
    return "function { " + pr.expr(ir::max(0.0, ir::min(1.0, e.held)).node(), e.ch) + " }";
  };
  CodeWriter w(width);
  w.open("pigment {");
  if (entries.size() == 1) {
    const Entry& e = entries.front();
    w.line(held(e));
    w.line("color_map { [0 " + color("0", "0", "0") + "] [1 " + color(top(e, 0), top(e, 1), top(e, 2)) + "] }");
    w.close("}");
    return w.take();
  }
  w.line("average");
  w.open("pigment_map {");
  for (const auto& e : entries) {
    w.line("[1 " + held(e));
    w.line("  color_map { [0 " + color("0", "0", "0") + "] [1 " + color(top(e, 0), top(e, 1), top(e, 2)) + "] }]");
  }
  w.close("}");
  w.close("}");
  return w.take();
}

namespace {
const char* kLitFinish = "finish { ambient 0 emission 0 diffuse 1 brilliance 0 specular 0 phong 0 }\n";
}  // namespace

// Object o lit by light i, × weight, with transmit t. The function holds
// min(radiance·S, 1), S = the light's colour × exposure: exact up to the
// radiance at which the 16-bit output saturates anyway.
std::string PovScene::lit(size_t o, size_t i, double weight, double t, double shrink, const std::string& mods) {
  const Object& obj = s_.objects[o];
  const PovShading& sh = shading(o);
  const RGB& c = s_.lights[i].color;
  PovPigment p;
  p.weight = weight;
  p.transmit = t;
  p.factors = [&](int ch) -> std::vector<Expr> {
    double s = sh.dependent ? c[size_t(ch)] : 0;
    if (!sh.dependent)
      for (double x : c)
        if (x > 0 && (s == 0 || x < s)) s = x;  // the dimmest channel that shows
    if (s == 0) return {};
    return {s, var("Facet_Exposure")};
  };
  const size_t width = kPovWidth - indent_ - 4;  // the pigment in the texture in the object
  if (table_[o]) {  // one table per material, light and copy, declared where it is first used
    const std::string name = fmt::format("Facet_{}Table{}{}", shading(o).prefix, i,
                                         weight == 1 && t == 0 ? "" : fmt::format("_{}", int(weight)));
    std::string declaration;
    if (declared_tables_.insert(name).second)
      declaration = "#declare " + name + " = " + table_pigment(o, i, p, kPovWidth - indent_);
    return declaration + object(o, shrink, "texture {\n  pigment { " + name + " }\n  " + kLitFinish + "}\n", mods);
  }
  std::vector<Expr> at = {var("x"), var("y"), var("z")};
  const std::vector<ir::FunctionPtr>& fs = objects_[o][i];
  if (sh.lobes.empty()) {
    p.radiance = [&](int) { return ir::call(fs.front(), at); };
  } else {  // each lobe's pigment is k ⊗ ρ, held to where the dimmest channel that shows saturates
    for (size_t k = 0; k < fs.size(); ++k) {
      double scale = 0;
      for (size_t ch = 0; ch < 3; ++ch) {
        double x = sh.lobes[k].color[ch] * c[ch];
        if (x > 0 && (scale == 0 || x < scale)) scale = x;
      }
      if (scale > 0) p.parts.push_back({ir::call(fs[k], at), sh.lobes[k].color, scale});
    }
  }
  // A mesh's pigment sees uv_mapping's (u, v): its object function reads the rest.
  const char* mapping = obj.type == Object::Type::Mesh ? "  uv_mapping\n" : "";
  return object(o, shrink,
                "texture {\n" + std::string(mapping) + indented(cut(o, pov_pigment(sh.printer, sh.dependent, p, width - 2)), 2) +
                    "  " + kLitFinish + "}\n",
                mods);
}

// Object o with its emission m_a ⊗ A + m_e, × weight, with transmit t: a colour, or where
// m_a or m_e comes from an image a function pigment holding min(E · exposure, 1), which the
// finish's emission scales back.
std::string PovScene::emitting(size_t o, double weight, double t, double shrink, const std::string& mods) {
  const PovShading& sh = shading(o);
  if (!emissions_[o] && kept_[o]) {  // the colour as a pigment that cut() wraps
    const RGB e = sh.emission(s_);
    const char* mapping = s_.objects[o].type == Object::Type::Mesh ? "  uv_mapping\n" : "";
    const std::string color = t > 0 ? fmt::format("rgbt <{}, {}, {}, {}>", pov_number(weight * e[0]),
                                                  pov_number(weight * e[1]), pov_number(weight * e[2]), pov_number(t))
                                    : "rgb " + pov_rgb({weight * e[0], weight * e[1], weight * e[2]});
    return object(o, shrink,
                  "texture {\n" + std::string(mapping) + indented(cut(o, "pigment { " + color + " }\n"), 2) +
                      "  finish { ambient 0 emission Facet_Exposure diffuse 0 specular 0 phong 0 }\n}\n",
                  mods);
  }
  if (!emissions_[o]) return object(o, shrink, emission_texture(sh.emission(s_), weight, t), mods);
  const RGB e = sh.emission(s_);  // the factors: a channel they hold at 0 stays black
  PovPigment p;
  p.weight = weight;
  p.transmit = t;
  p.radiance = [&](int) { return ir::call(emissions_[o], {var("x"), var("y"), var("z")}); };
  p.factors = [&](int ch) -> std::vector<Expr> {
    if (e[size_t(ch)] == 0 && sh.printer.channel_dependent(emissions_[o])) return {};
    return {var("Facet_Exposure")};
  };
  const char* mapping = s_.objects[o].type == Object::Type::Mesh ? "  uv_mapping\n" : "";
  const size_t width = kPovWidth - indent_ - 4;
  return object(o, shrink,
                "texture {\n" + std::string(mapping) +
                    indented(cut(o, pov_pigment(sh.printer, sh.printer.channel_dependent(emissions_[o]), p, width - 2)), 2) +
                    "  finish { ambient 0 emission Facet_Exposure diffuse 0 specular 0 phong 0 }\n}\n",
                mods);
}

bool PovScene::absent(size_t o) const {
  const Material& m = *shading(o).material;
  return m.masked() && !m.alpha.texture && m.alpha.number < *m.alpha_cutoff;
}

// The pigment's own entries under a pigment_map keyed by Facet_Object{o}_Kept: 0 clear, which
// POV-Ray's camera rays go on through (its transmit 1) and its shadow rays pass (light × 1), 1
// the pigment. Kept is 0 or 1, never between, so no entry is ever blended with the other.
std::string PovScene::cut(size_t o, const std::string& pigment) const {
  if (!kept_[o]) return pigment;
  const size_t open = pigment.find('{'), close = pigment.rfind('}');
  std::string body = pigment.substr(open + 1, close - open - 1);
  while (!body.empty() && (body.front() == ' ' || body.front() == '\n')) body.erase(body.begin());
  while (!body.empty() && (body.back() == ' ' || body.back() == '\n')) body.pop_back();
  return fmt::format("pigment {{\n  function {{ {}(x, y, z) }}\n  pigment_map {{\n    [0 rgbt <0, 0, 0, 1>]\n"
                     "    [1\n{}\n    ]\n  }}\n}}\n",
                     shading(o).printer.name(kept_[o], 0), indented(body, 6));
}

// Pass `item`: light `item` alone, or after the lights the emission alone.
std::string PovScene::pass(size_t item) {
  const size_t n = s_.lights.size();
  std::string out = item < n ? light_source(s_.lights[item]) : "";
  for (size_t o = 0; o < s_.objects.size(); ++o)
    if (!absent(o)) out += item < n ? lit(o, item, 1, 0, 0, "") : emitting(o, 1, 0, 0, "");
  return out;
}

std::string PovScene::passes() {
  const size_t n = s_.lights.size();
  bool emits = false;
  for (size_t o = 0; o < s_.objects.size(); ++o) emits |= !pov_black(shading(o).emission(s_));
  const size_t items = n + (emits ? 1 : 0);
  if (items <= 1) return items == 1 ? pass(0) : "";
  std::string cases, copies;
  for (size_t i = 0; i < items; ++i)
    cases += fmt::format("#case ({})  // {}\n", i, i < n ? fmt::format("light {}", i) : "emission") + pass(i) +
             "#break\n";
  // Copy k lets t_k = (items − k − 1)/(items − k) through to the copies inside it
  // and keeps 1 − t_k of its own pigment, so copy k is seen with weight
  // t_0 ⋯ t_(k−1) (1 − t_k) = 1/items: every pigment is scaled by items.
  for (size_t k = 0; k < items; ++k) {
    double t = double(items - 1 - k) / double(items - k);
    double weight = double(items);
    double shrink = 1e-4 * double(k);
    std::string mods = k + 1 == items ? "" : "no_shadow\n";
    if (k >= n) {
      for (size_t o = 0; o < s_.objects.size(); ++o)
        if (!absent(o)) copies += emitting(o, weight, t, shrink, mods);
      continue;
    }
    indent_ = 2;
    std::string group = light_source(s_.lights[k]);
    for (size_t o = 0; o < s_.objects.size(); ++o)
      if (!absent(o)) group += lit(o, k, weight, t, shrink, mods);
    indent_ = 0;
    copies += "light_group {\n" + indented(group, 2) + "  global_lights off\n}\n";
  }
  return render_template("pov/passes.pov", {{"cases", cases}, {"copies", copies}});
}

// Facet_Point_Shade(x, y, z, n, light position, eye) for the library's pigment macro.
std::string PovScene::point_shade() {
  PovShading& sh = *shadings_.front();
  ir::FunctionBuilder fb("Facet_Point_Shade", "");
  Triple P = params(fb, "x", "y", "z"), N = params(fb, "Nx", "Ny", "Nz");
  Triple light = params(fb, "Px", "Py", "Pz"), eye = params(fb, "Ex", "Ey", "Ez");
  Triple to_light = {light.x - P.x, light.y - P.y, light.z - P.z}, to_eye = {eye.x - P.x, eye.y - P.y, eye.z - P.z};
  Triple L = lets(fb, "Lx", "Ly", "Lz", to_light), V = lets(fb, "Vx", "Vy", "Vz", to_eye);
  const std::vector<Expr> uv = uv_params(fb, sh);  // a textured material's coordinates
  Expr d = fb.let("D", length3(to_light)), dv = fb.let("Dv", length3(to_eye));
  ir::FunctionPtr f = fb.returns(ir::call(sh.reflect, with(args({N, L / d, V / dv}), uv)));
  sh.printer.add_own(f);
  return sh.printer.function(f);
}

// The robustness sweep (analysis/sweep.h): each pixel centre of a unit square is a
// direction set of the grid; each channel shows whether that channel of the
// reflectance is finite and ≥ 0 (POV-Ray would render a NaN black, like a 0).
std::string PovScene::sweep() {
  PovShading& sh = *shadings_.front();
  PovPrinter grid_printer;
  std::string grid;
  for (const auto& f : ir::dependencies(sweep_grid())) grid += grid_printer.function(f) + "\n";
  ir::FunctionBuilder fb("Facet_Reflect_grid", "");
  Expr x = fb.param("x"), y = fb.param("y");
  std::vector<Expr> directions;
  for (const auto& component : sweep_grid()) directions.push_back(ir::call(component, {x, y}));
  // Lobes that read the texture frame's tangent take t as a parameter: the sweep's is the
  // tangent rule's on n (as the other targets' sweeps give it), its handedness +1.
  if (takes_tangent(sh, *sh.program.reflectance)) {
    const Triple n = lets(fb, "Nx", "Ny", "Nz", {directions[0], directions[1], directions[2]});
    directions[0] = n.x, directions[1] = n.y, directions[2] = n.z;
    append(directions, mapped_tangent(fb, sh, n, n));
    if (takes_handedness(sh)) directions.push_back(1.0);
  }
  // A frame alone makes the shading take texture coordinates, which no image reads here.
  if (sh.textured()) directions.insert(directions.end(), 4, Expr(0.0));
  ir::FunctionPtr f = fb.returns(ir::call(sh.reflect, directions));
  sh.printer.add_own(f);
  std::string pigment = "  pigment {\n    average\n    pigment_map {\n";
  for (int ch = 0; ch < 3; ++ch) {
    pigment += fmt::format("      [1 function {{ Facet_Ok({}(x, y)) }} color_map {{ [0 rgb 0] [1 rgb {}] }}]\n",
                           sh.printer.name(f, sh.dependent ? ch : 0),
                           ch == 0 ? "<3, 0, 0>" : ch == 1 ? "<0, 3, 0>" : "<0, 0, 3>");
  }
  pigment += "    }\n  }\n";
  return render_template("pov/sweep.pov", {{"header", header()},
                                           {"functions", functions()},
                                           {"grid", grid},
                                           {"reflect", sh.printer.function(f)},
                                           {"pigment", pigment}});
}

}  // namespace facet::targets
