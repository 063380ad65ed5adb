// facet — scenes: a camera, analytic objects, lights and an ambient colour.
//
// World space is right-handed with +y up (as OpenGL and glTF). Targets with
// other conventions convert: POV-Ray mirrors z (left-handed), Blender swaps to
// +z up.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "facet/material.h"
#include "facet/vec.h"

namespace facet {

struct Camera {
  Vec3 position{0, 0, 4};
  Vec3 look_at{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fov = 40;  // vertical field of view, degrees

  // The ray through pixel centre (i + 0.5, j + 0.5) of a w×h image, rows from the top.
  struct Basis {
    Vec3 forward, right, up;
    double tan_half;  // tan(fov/2)
  };
  Basis basis() const;
  Vec3 ray(int i, int j, int w, int h) const;
};

struct Attenuation {
  enum class Law { None, InverseSquare, Polynomial };
  Law law = Law::None;
  double constant = 1, linear = 0, quadratic = 0;
};

struct Light {
  enum class Type { Point, Directional, Spot };
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

struct Object {
  enum class Type { Sphere, Plane };
  Type type = Type::Sphere;
  std::string name;
  // sphere
  Vec3 center;
  double radius = 1;
  // plane: a square of half-side `size` through `point`, facing `normal`
  Vec3 point;
  Vec3 normal{0, 1, 0};
  double size = 10;
  // The square's in-plane axes (unit, with normal forming a right-handed frame).
  void plane_axes(Vec3& u, Vec3& v) const;
  // Nearest hit along origin + t·dir with t > t_min; returns t or a negative number.
  double intersect(const Vec3& origin, const Vec3& dir, double t_min = 0) const;
  Vec3 normal_at(const Vec3& p) const;
};

struct Scene {
  std::string name;
  std::string source;  // the file, or "built-in"
  Camera camera;
  RGB ambient{0, 0, 0};
  std::vector<Object> objects;
  std::vector<Light> lights;
};

Scene parse_scene(const nlohmann::json& doc, const std::string& file);
// A file path, or the name of a built-in scene ("single", "shadows").
Scene load_scene(const std::string& name_or_path);
const std::vector<std::string>& builtin_scene_names();
nlohmann::json builtin_scene_json(const std::string& name);
nlohmann::json to_json(const Scene& s);
nlohmann::json scene_schema();

// The default validation scene: one unit sphere, a camera and one point light.
Scene default_scene();

}  // namespace facet
