// facet — scenes: a camera, analytic objects, lights and an ambient colour.
//
// World space is right-handed with +y up (as OpenGL and glTF). Targets with
// other conventions convert: POV-Ray mirrors z (left-handed), Blender swaps to
// +z up.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "catalog/catalog.h"
#include "catalog/material.h"
#include "core/vec.h"

namespace facet {

struct Camera {
  Vec3 position{0, 0, 4};
  Vec3 look_at{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fov = 40;  // vertical field of view, degrees (perspective)
  // Orthographic: parallel rays along the view direction from a rectangle `height` high
  // centred at `position` (glTF's orthographic camera: height = 2·ymag).
  bool orthographic = false;
  double height = 2;

  // The ray through pixel centre (i + 0.5, j + 0.5) of a w×h image, rows from the top.
  struct Basis {
    Vec3 forward, right, up;
    double tan_half;  // tan(fov/2); orthographic: half the height
  };
  Basis basis() const;
  // Its unit direction; `origin` gets where it starts (the eye, or a point of the
  // orthographic camera's image rectangle).
  Vec3 ray(int i, int j, int w, int h, Vec3* origin = nullptr) const;
  // The unit direction from p towards the eye: v of the shading at p.
  Vec3 toward_eye(const Vec3& p) const;
};

struct Attenuation {
  using Law = AttenuationLaw;  // the catalog's: each attenuation model states its law
  Law law = Law::None;
  double constant = 1, linear = 0, quadratic = 0;
  double range = 0;  // InverseSquareRange: the distance at which the light reaches 0
};

struct Light {
  using Type = LightType;  // the catalog's: each light model states its type
  Type type = Type::Point;
  Vec3 position;
  Vec3 direction{0, -1, 0};  // unit: the way the light travels (directional), the cone axis (spot)
  RGB color{1, 1, 1};
  double cutoff = 30;        // degrees (spot)
  double exponent = 0;       // spot
  Attenuation attenuation;

  // From a surface point: the unit direction to the light and its distance
  // (infinite for directional lights). Attenuation and the spot cone are
  // catalog functions (terms::attenuation_*, terms::spot_cone).
  void toward(const Vec3& p, Vec3& l, double& distance) const;
};

// A triangle mesh with a normal per vertex. Shading is smooth: the normal at a
// point is the normalized barycentric blend of its triangle's vertex normals.
struct Mesh {
  std::vector<Vec3> positions, normals;
  std::vector<std::array<uint32_t, 3>> triangles;
  // Texture coordinates per vertex, sets 0 and 1 (glTF's TEXCOORD_0/1: v down the
  // picture); empty where the mesh has no such set.
  std::array<std::vector<std::array<double, 2>>, 2> texcoords;
  // Tangents per vertex, [x, y, z, w], where the mesh brings its own (glTF's TANGENT, the
  // Blender add-on's calc_tangents()): a normal map's ∂p/∂u and B = w·(n × t). Empty: a
  // normal map takes facet's MikkTSpace tangents (scene/tangents.h).
  std::vector<std::array<double, 4>> tangents;
  // Vertex colours, RGBA per vertex (glTF's COLOR_0: linear, alpha 1 where it is RGB): what a
  // material's values with "vertex_color" multiply by (catalog/texture.h), blended across a
  // triangle as the texture coordinates are. Empty: white.
  std::vector<std::array<double, 4>> colors;
  // A bounding volume hierarchy, nodes in depth-first order: an inner node's
  // left child follows it, `right` indexes the other; a leaf holds `count`
  // triangles from `start` in `order`.
  struct Node {
    Vec3 lo, hi;
    uint32_t start = 0, count = 0;
    int32_t right = -1;
  };
  std::vector<Node> nodes;
  std::vector<uint32_t> order;
  void build_bvh();
  // Calls visit(triangle) for every triangle whose box, grown by `margin`
  // (relative), the ray origin + t·dir enters for t < t_max.
  void candidates(const Vec3& origin, const Vec3& dir, double t_max, double margin,
                  const std::function<void(int)>& visit) const;
  // The smooth normal of triangle `t` at barycentrics (u, v) of its vertices 1 and 2.
  Vec3 normal(int t, double u, double v) const;
};

// Where a ray meets an object: distance, and for meshes the triangle and the
// barycentrics (u, v) of its second and third vertices.
struct Hit {
  double t = -1;
  int triangle = -1;
  double u = 0, v = 0;
  bool ok() const { return t > 0; }
};

// Where a mesh object's triangles are when a scene file references them instead of
// holding them: a glTF file's mesh (its coordinates as they are) or node (its mesh
// in the node's world transform), chosen by index or name; one primitive or all.
struct MeshReference {
  std::string file;       // the glTF file, as a path from the working directory (or absolute)
  bool node = true;       // a node, else a mesh
  int64_t index = -1;     // its index, or −1 where `name` names it
  std::string name;
  int64_t primitive = -1;  // −1: every triangle primitive of the mesh
  // The glTF sets TEXCOORD_n read as the mesh's texture coordinate sets 0 and 1.
  std::array<int64_t, 2> texcoords{0, 1};
};

struct Object {
  using Type = ObjectType;  // the catalog's: each object model states its type
  Type type = Type::Sphere;
  std::string name;
  std::string material;  // a key of Scene::materials; "" shades with the material under test
  // sphere
  Vec3 center;
  double radius = 1;
  // plane: a square of half-side `size` through `point`, facing `normal`
  Vec3 point;
  Vec3 normal{0, 1, 0};
  double size = 10;
  // mesh
  std::shared_ptr<const Mesh> mesh;
  std::optional<MeshReference> reference;  // where the mesh is in a glTF file, if the scene says so

  // The square's in-plane axes (unit, with normal forming a right-handed frame).
  void plane_axes(Vec3& u, Vec3& v) const;
  // Nearest hit along origin + t·dir with t > t_min, ignoring triangle `skip` of a mesh.
  Hit hit(const Vec3& origin, const Vec3& dir, double t_min = 0, int skip = -1) const;
  double intersect(const Vec3& origin, const Vec3& dir, double t_min = 0) const { return hit(origin, dir, t_min).t; }
  Vec3 normal_at(const Vec3& p, const Hit& h) const;
  // Texture coordinates sets 0 and 1 at p (docs/textures.md): a sphere's and a square's
  // are their documented mappings (the same in both sets), a mesh's its vertices'
  // blended barycentrically ((0, 0) for a set it lacks).
  std::array<std::array<double, 2>, 2> uv_at(const Vec3& p, const Hit& h) const;
  // The vertex colour at a hit (RGBA): a mesh's colours blended barycentrically, as uv_at
  // blends its coordinates; white on the shapes and on meshes without colours.
  std::array<double, 4> color_at(const Hit& h) const;
  // The tangent frame of texture coordinates at p, for normal maps (docs/textures.md,
  // "Tangent frames"): t the unit ∂p/∂u, and w = ±1 such that B = w·(n × t) points up
  // the picture (towards decreasing v, glTF's bitangent rule). A sphere's t is
  // normalize(d_z, 0, −d_x) (undefined at the poles), a square's its first axis; w = +1
  // on both. Meshes have no tangents yet: false there.
  bool tangent_at(const Vec3& p, const Hit& h, Vec3& t, double& w) const;
  // Spheres and squares are convex: they never shadow themselves where n·l > 0.
  bool convex() const { return type != Type::Mesh; }
  // A sphere around the object (for culling and scene scale).
  void bounds(Vec3& center, double& radius) const;
};

struct Scene {
  std::string name;
  std::string source;  // the file, or "built-in"
  Camera camera;
  RGB ambient{0, 0, 0};
  // How previews show it: radiance × 2^exposure, then the standard view transform (sRGB
  // encoding, clipped to [0, 1]), as Blender's Film exposure and Standard view do. Renderers
  // ignore it: their images are linear radiance.
  double exposure = 0;
  std::map<std::string, Material> materials;  // named materials objects refer to
  std::vector<Object> objects;
  std::vector<Light> lights;
  // Every object names its own material: the scene renders without one given.
  bool has_own_materials() const;
  // The material of object i: its own, else `fallback` (the material under test).
  const Material& material_of(size_t i, const Material* fallback) const;
};

Scene parse_scene(const nlohmann::json& doc, const std::string& file);
// A file path, or the name of a built-in scene ("single", "shadows").
Scene load_scene(const std::string& name_or_path);
const std::vector<std::string>& builtin_scene_names();
nlohmann::json builtin_scene_json(const std::string& name);
// The canonical JSON form; materials and meshes are written inline.
nlohmann::json to_json(const Scene& s);
// The form written to `scene_file`: as to_json, but a mesh with a reference is
// written as that reference, its file's path relative to `scene_file`'s folder, and
// the materials' image paths relative to that folder too.
nlohmann::json to_json(const Scene& s, const std::string& scene_file);
nlohmann::json scene_schema();

// Every mesh whose material reads a texture coordinate set (a textured parameter's "uv")
// has that set; else InputError naming the scene file, the object and the material's key.
// `fallback` shades the objects without a material of their own.
void check_texture_sets(const Scene& s, const Material* fallback);

// The default validation scene: one unit sphere, a camera and one point light.
Scene default_scene();

}  // namespace facet
