#include "targets/osl_cutouts.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>

#include <fmt/format.h>

#include "core/text.h"

namespace facet::targets {

Vec3 osl_blender(const Vec3& p) { return {p.x, -p.z, p.y}; }

OslSample osl_sample(const CPrinter& pr, const TextureCall& c, const std::string& file) {
  OslSample out;
  if (!c.max_of.empty()) {  // max₃ of the colour sampled before it
    out.value = fmt::format("max(max({0}[0], {0}[1]), {0}[2])", c.max_of);
    return out;
  }
  std::string texel;
  if (c.image) {
    std::string s = fmt::format("s{}", c.uv), t = fmt::format("t{}", c.uv);
    if (c.transformed) {
      std::string su = fmt::format("{} * {} + {} * {} + {}", pr.literal(c.a), s, pr.literal(c.b), t, pr.literal(c.ou));
      std::string tv = fmt::format("{} * {} + {} * {} + {}", pr.literal(c.c), s, pr.literal(c.d), t, pr.literal(c.ov));
      s = su;
      t = tv;
    }
    out.statements = fmt::format(
        "    float {0}_alpha;\n    color {0}_texel = facet_texture({1}, {2}, {3}, {4}, {5}, {6}, {7}, {8}, {9}, {0}_alpha);\n",
        c.name, file, c.texels->width, c.texels->height, s, t, c.wrap[0], c.wrap[1], c.bilinear ? 1 : 0, c.srgb ? 1 : 0);
    texel = c.channel < 0   ? c.name + "_texel"
            : c.channel == 3 ? c.name + "_alpha"
                             : fmt::format("{}_texel[{}]", c.name, c.channel);
  }
  // The vertex colour: the shader's facet_color0 (rgb) and facet_alpha0 inputs.
  const std::string vc = c.color || c.channel < 0 ? "facet_color0"
                         : c.channel == 3          ? "facet_alpha0"
                                                   : fmt::format("facet_color0[{}]", c.channel);
  const ValueWords words{[&](double x) { return pr.literal(x); },
                         [&](const std::array<double, 3>& x) { return pr.color_literal(x); },
                         [&](double x) { return "color(" + pr.literal(x) + ")"; }};
  out.value = texture_value_code(c, texel, vc, words);
  return out;
}

namespace {

bool translucent(const Texels& t) {
  for (size_t i = 3; i < t.rgba.size(); i += 4)
    if (t.rgba[i] < 1) return true;
  return false;
}

std::string absolute(const std::string& path) {
  return std::filesystem::absolute(path).lexically_normal().string();
}

}  // namespace

bool osl_premultiplied(const TextureCall& c, const GenerateOptions& o) {
  return c.channel != 3 && !o.image_files.count(c.texels->path) && translucent(*c.texels);
}

std::string osl_image_file(const TextureCall& c, const GenerateOptions& o) {
  auto copy = o.image_files.find(c.texels->path);
  // An absolute path: Cycles opens it from wherever Blender runs.
  return quoted_literal(c.channel != 3 && copy != o.image_files.end() ? copy->second : absolute(c.texels->path));
}

namespace {

// The alpha functions of the scene's cut-out materials, facet_alpha{k}(s0, t0, s1, t1), one per
// distinct material: the shaded one is a copy of the scene's (GenerateOptions), so materials are
// the same where their JSON is.
struct AlphaFunctions {
  std::map<std::string, size_t> index;
  std::string text;
  bool images = false;
  static std::string key(const Material& m) { return to_json(m).dump(); }
  size_t at(const Material& m) const { return index.at(key(m)); }
  bool has(const Material& m) const { return index.count(key(m)) > 0; }
};

std::string alpha_function(const CPrinter& pr, const Material& m, size_t k, const GenerateOptions& o, bool& images) {
  std::string body;
  if (auto c = alpha_call(m)) {
    c->name = "alpha";
    const OslSample sample = osl_sample(pr, *c, osl_image_file(*c, o));
    body = sample.statements + "    return " + sample.value + ";\n";
    images = true;
  } else {
    body = "    return " + pr.literal(m.alpha.number) + ";\n";
  }
  return fmt::format(
      "// \"{}\"'s alpha at texture coordinates (s0, t0), (s1, t1) (glTF's: t down the picture); its cutoff {}.\n"
      "float facet_alpha{}(float s0, float t0, float s1, float t1)\n{{\n{}}}\n\n",
      m.name, pr.literal(*m.alpha_cutoff), k, body);
}

// OSL's `type`(x, y, z) of facet's `v`, in Blender's axes.
std::string blender_literal(const CPrinter& pr, const char* type, const Vec3& v) {
  const Vec3 b = osl_blender(v);
  return fmt::format("{}({}, {}, {})", type, pr.literal(b.x), pr.literal(b.y), pr.literal(b.z));
}

// s, t of point Q of the sphere centred at `center` (docs/textures.md, "Texture coordinates of
// the shapes"), in Blender's axes as FACET_UV_OSL computes them; nq the unit normal there.
std::string sphere_coordinates(const std::string& center, const std::string& indent) {
  return fmt::format(
      "{0}nq = normalize(Q - {1});\n"
      "{0}s = 0.5 + atan2(nq[0], -nq[1]) / M_2PI;  // facet's (x, y, z) is Blender's (x, −z, y)\n"
      "{0}t = acos(clamp(nq[2], -1, 1)) / M_PI;\n",
      indent, center);
}

// s, t of a sphere's or a square's point Q.
std::string shape_coordinates(const CPrinter& pr, const Object& obj, const std::string& indent) {
  if (obj.type == Object::Type::Sphere) return sphere_coordinates(blender_literal(pr, "point", obj.center), indent);
  Vec3 a, b;
  obj.plane_axes(a, b);
  return fmt::format("{0}s = 0.5 + dot(Q - {1}, {2}) / {4};\n{0}t = 0.5 - dot(Q - {1}, {3}) / {4};\n", indent,
                     blender_literal(pr, "point", obj.point), blender_literal(pr, "vector", a),
                     blender_literal(pr, "vector", b), pr.literal(2 * obj.size));
}

// Whether point Q (Blender's axes) lies on object `obj`, a sphere or a square, within `tol`.
std::string on_shape(const CPrinter& pr, const Object& obj, const std::string& tol) {
  if (obj.type == Object::Type::Sphere)
    return fmt::format("abs(distance(Q, {}) - {}) < {}", blender_literal(pr, "point", obj.center),
                       pr.literal(obj.radius), tol);
  Vec3 a, b;
  obj.plane_axes(a, b);
  const std::string o = blender_literal(pr, "point", obj.point), size = pr.literal(obj.size * (1 + 1e-5));
  return fmt::format("abs(dot(Q - {0}, {1})) < {2} && abs(dot(Q - {0}, {3})) <= {5} && abs(dot(Q - {0}, {4})) <= {5}",
                     o, blender_literal(pr, "vector", obj.normal), tol, blender_literal(pr, "vector", a),
                     blender_literal(pr, "vector", b), size);
}

// facet_mesh{i}(Q, …): whether Q lies on a triangle of mesh object i (within `tol` of its
// plane, inside its edges), and there its texture coordinates, blended from the corners'.
// trace() tells the hit's point, not which object or triangle it met (getmessage reads the
// shaded object's attributes, measured in Blender 4.5), so the shader searches the triangles.
std::string mesh_search(const CPrinter& pr, const Object& obj, size_t i, const std::string& tol) {
  const Mesh& mesh = *obj.mesh;
  const size_t n = mesh.triangles.size();
  std::string corners, uv;
  for (const auto& t : mesh.triangles)
    for (uint32_t v : t) {
      corners += (corners.empty() ? "" : ", ") + blender_literal(pr, "point", mesh.positions[v]);
      for (const auto& set : mesh.texcoords)
        for (size_t k = 0; k < 2; ++k) uv += (uv.empty() ? "" : ", ") + pr.literal(set.empty() ? 0.0 : set[v][k]);
    }
  return fmt::format(
      "// Whether Q lies on a triangle of \"{0}\" ({1} triangles), and there its texture coordinates.\n"
      "int facet_mesh{2}(point Q, output float s0, output float t0, output float s1, output float t1)\n{{\n"
      "    point p[{3}] = {{ {4} }};\n"
      "    float uv[{5}] = {{ {6} }};  // per corner: s0, t0, s1, t1 (glTF's)\n"
      "    float best = {7};\n    int found = 0;\n"
      "    for (int k = 0; k < {1}; ++k) {{\n"
      "        vector e1 = p[3 * k + 1] - p[3 * k], e2 = p[3 * k + 2] - p[3 * k], q = Q - p[3 * k];\n"
      "        vector n = cross(e1, e2);\n        float area = dot(n, n);\n"
      "        float off = abs(dot(q, n)) / sqrt(area);\n"
      "        if (area == 0 || off >= best) continue;\n"
      "        float b1 = dot(cross(q, e2), n) / area, b2 = dot(cross(e1, q), n) / area;\n"
      "        if (b1 < -1e-5 || b2 < -1e-5 || b1 + b2 > 1 + 1e-5) continue;\n"
      "        best = off;\n        found = 1;\n        int c = 12 * k;\n"
      "        float b0 = 1 - b1 - b2;\n"
      "        s0 = b0 * uv[c] + b1 * uv[c + 4] + b2 * uv[c + 8];\n"
      "        t0 = b0 * uv[c + 1] + b1 * uv[c + 5] + b2 * uv[c + 9];\n"
      "        s1 = b0 * uv[c + 2] + b1 * uv[c + 6] + b2 * uv[c + 10];\n"
      "        t1 = b0 * uv[c + 3] + b1 * uv[c + 7] + b2 * uv[c + 11];\n"
      "    }}\n    return found;\n}}\n\n",
      obj.name, n, i, 3 * n, corners, 12 * n, uv, tol);
}

// facet_kept_hit(): whether the surface the last trace() met is there. The surface is known by
// where it was met: on a cut-out object (within the scene's size × 1e-4), else opaque.
std::string kept_hit(const CPrinter& pr, const Scene& s, const Material& fallback, const AlphaFunctions& alphas,
                     const std::string& tol) {
  std::string cases, meshes;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& obj = s.objects[i];
    const Material& m = s.material_of(i, &fallback);
    if (!m.masked()) continue;
    const std::string test = fmt::format("facet_alpha{}({{}}) >= {}", alphas.at(m), pr.literal(*m.alpha_cutoff));
    if (obj.type == Object::Type::Mesh) {
      meshes += mesh_search(pr, obj, i, tol);
      cases += fmt::format("    if (facet_mesh{}(Q, s0, t0, s1, t1))  // \"{}\"\n        return {};\n", i, obj.name,
                           fmt::format(fmt::runtime(test), "s0, t0, s1, t1"));
    } else if (obj.type == Object::Type::Plane) {
      cases += fmt::format("    if ({}) {{  // \"{}\"\n", on_shape(pr, obj, tol), obj.name) +
               shape_coordinates(pr, obj, "        ") + "        return " +
               fmt::format(fmt::runtime(test), "s, t, s, t") + ";\n    }\n";
    } else {  // met from outside: its near side, then its far side, which trace() does not meet from inside
      cases += fmt::format("    if ({}) {{  // \"{}\"\n", on_shape(pr, obj, tol), obj.name) +
               shape_coordinates(pr, obj, "        ") + "        if (" +
               fmt::format(fmt::runtime(test), "s, t, s, t") + ") return 1;\n" +
               fmt::format("        float through = 2 * dot({} - Q, L);\n", blender_literal(pr, "point", obj.center)) +
               "        if (along + through >= d) return 0;\n        Q += through * L;\n" +
               shape_coordinates(pr, obj, "        ") + "        return " +
               fmt::format(fmt::runtime(test), "s, t, s, t") + ";\n    }\n";
    }
  }
  return meshes +
         "// Whether the surface the last trace() met, `along` from the shadow ray's start along L (d the\n"
         "// light's distance), is there (alpha ≥ its cutoff). trace() tells where it met it, not what:\n"
         "// the surface is the cut-out object that point lies on, if any; every other object is opaque.\n"
         "// Past a sphere's near side cut out, its far side: trace() never meets a point primitive's\n"
         "// far side from inside (measured in Blender 4.5).\n"
         "int facet_kept_hit(vector L, float along, float d)\n{\n    point Q = 0;\n    getmessage(\"trace\", \"P\", Q);\n"
         "    float s = 0, t = 0, s0 = 0, t0 = 0, s1 = 0, t1 = 0;\n    vector nq = 0;\n" + cases + "    return 1;\n}\n\n";
}

// facet_blocked(Pt, L, d, from): light from L is blocked within d.
std::string blocked(const CPrinter& pr, double step) {
  return fmt::format(
      "// Whether something is there between Pt and Pt + d·L: trace() meets the nearest surface\n"
      "// (skipping the shaded primitive when `from` is 0, Pt being P), and past each one cut out\n"
      "// there the search goes on, {0} beyond it (the scene's size × 1e-5).\n"
      "int facet_blocked(point Pt, vector L, float d, float from)\n{{\n"
      "    float start = from;\n"
      "    for (int k = 0; k < 64; ++k) {{\n"
      "        int hit = 0;\n"
      "        if (start == 0) hit = trace(Pt, L, \"maxdist\", d);\n"
      "        else hit = trace(Pt, L, \"mindist\", start, \"maxdist\", d);\n"
      "        if (!hit) return 0;\n"
      "        float t = 0;\n"
      "        getmessage(\"trace\", \"hitdist\", t);  // from Pt + start·L\n"
      "        if (facet_kept_hit(L, start + t, d)) return 1;\n"
      "        start += t + {0};\n"
      "        if (start >= d) return 0;\n"
      "    }}\n"
      "    return 1;\n}}\n\n",
      pr.literal(step));
}

// facet_far_side(…) for material `m` (facet_alpha{k}) where spheres wear it, else "".
std::string far_side(const CPrinter& pr, const Scene& s, const Material& m, const Material& fallback, size_t k,
                     double step, const std::string& tol) {
  std::string cases;
  const std::string own = AlphaFunctions::key(m);
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& obj = s.objects[i];
    if (obj.type != Object::Type::Sphere || AlphaFunctions::key(s.material_of(i, &fallback)) != own) continue;
    cases += fmt::format("    {}if ({}) c = {};  // \"{}\"\n", cases.empty() ? "" : "else ",
                         std::regex_replace(on_shape(pr, obj, tol), std::regex("\\bQ\\b"), "P"),
                         blender_literal(pr, "point", obj.center), obj.name);
  }
  if (cases.empty()) return "";
  return fmt::format(
      "// Seen through a cut-out sphere's near side at P, the camera ray meets its far side: Cycles'\n"
      "// path goes on past P but never meets a point primitive it left again, so the shader finds\n"
      "// the far side itself. 1 where that is there and nothing lies between: Pt, Nn, the texture\n"
      "// coordinates and the tangent frame are then the far side's, and its shadow rays start\n"
      "// {0} out (`from`), Pt not being P.\n"
      "int facet_far_side(output point Pt, output vector Nn, output float s0, output float t0, output float s1,\n"
      "                   output float t1, output vector tangent, output float handedness, output float from)\n{{\n"
      "    point c = 0;\n{1}    else return 0;\n"
      "    vector D = -normalize(I);\n    float far = 2 * dot(c - P, D);\n    point Q = P + far * D;\n"
      "    float s = 0, t = 0;\n    vector nq = 0;\n{2}"
      "    if (!(facet_alpha{3}(s, t, s, t) >= {4}) || trace(P, D, \"maxdist\", far)) return 0;\n"
      "    Pt = Q;\n    Nn = nq;\n    s0 = s1 = s;\n    t0 = t1 = t;\n"
      "    tangent = normalize(vector(-nq[1], nq[0], 0));  // docs/textures.md: facet's (d_z, 0, −d_x)\n"
      "    handedness = 1;\n    from = {0};\n    return 1;\n}}\n\n",
      pr.literal(step), cases, sphere_coordinates("c", "    "), k, pr.literal(*m.alpha_cutoff));
}

// The scene's size: its objects' and camera's distance from the origin, at least 1.
double scene_size(const Scene& s) {
  double r = std::max(1.0, length(s.camera.position));
  for (const auto& o : s.objects) {
    Vec3 c;
    double rad;
    o.bounds(c, rad);
    r = std::max(r, length(c) + rad);
  }
  return r;
}

// The shaded surface's own cut-out: where alpha < cutoff, the far side (a sphere's) or nothing.
std::string own_test(const CPrinter& pr, const Material& m, size_t k, bool far) {
  std::string test = fmt::format(
      "    // The cut-out (glTF's alphaMode MASK): the surface is there only where alpha ≥ {0}.\n"
      "    if (!(facet_alpha{1}(s0, t0, s1, t1) >= {0})) {{\n", pr.literal(*m.alpha_cutoff), k);
  if (far) test += "        if (!facet_far_side(Pt, Nn, s0, t0, s1, t1, uv_tangent, uv_handedness, shadow_from)) {\n";
  test += std::string(far ? "    " : "") +
          "        Out = transparent();  // Cycles' path goes on past it (transparent bounces)\n" +
          (far ? "            exit();\n        }\n" : "        exit();\n") + "    }\n";
  return test;
}

}  // namespace

OslCutouts osl_cutouts(const CPrinter& pr, const Material& m, const Scene& scene, const Material& fallback,
                       const GenerateOptions& o) {
  OslCutouts out;
  AlphaFunctions alphas;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Material& mi = scene.material_of(i, &fallback);
    if (!mi.masked() || alphas.has(mi)) continue;
    const size_t k = alphas.index.size();
    alphas.index[AlphaFunctions::key(mi)] = k;
    alphas.text += alpha_function(pr, mi, k, o, alphas.images);
  }
  // The shaded material's own, where no object wears it (the material under test, alone).
  if (m.masked() && !alphas.has(m)) {
    const size_t k = alphas.index.size();
    alphas.index[AlphaFunctions::key(m)] = k;
    alphas.text += alpha_function(pr, m, k, o, alphas.images);
  }
  for (size_t i = 0; i < scene.objects.size(); ++i) out.any = out.any || scene.material_of(i, &fallback).masked();
  if (alphas.index.empty()) return out;
  out.images = alphas.images;
  const double step = 1e-5 * scene_size(scene);
  const std::string tol = pr.literal(1e-4 * scene_size(scene));
  out.functions = alphas.text;
  if (out.any) out.functions += kept_hit(pr, scene, fallback, alphas, tol) + blocked(pr, step);
  if (!m.masked()) return out;
  const size_t k = alphas.at(m);
  const std::string far = far_side(pr, scene, m, fallback, k, step, tol);
  out.functions += far;
  out.own_uv = alpha_call(m).has_value();
  out.test = own_test(pr, m, k, !far.empty());
  return out;
}

}  // namespace facet::targets
