#include "facet/render.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "facet/reference.h"

namespace facet {

namespace {

struct Hit {
  double t = -1;
  int object = -1;
};

Hit nearest(const Scene& s, const Vec3& o, const Vec3& d, double t_min) {
  Hit h;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    double t = s.objects[i].intersect(o, d, t_min);
    if (t > 0 && (h.t < 0 || t < h.t)) h = {t, int(i)};
  }
  return h;
}

// Is the segment p + s·l, s ∈ (offset, dist), blocked by an object other than
// `self`? (Objects are convex: none shadows itself where n·l > 0.) Also reports
// whether the segment passes within kGrazing of an occluder's edge.
bool blocked(const Scene& s, size_t self, const Vec3& p, const Vec3& l, double dist, double offset, bool& grazing) {
  bool hit = false;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    if (i == self) continue;
    const Object& o = s.objects[i];
    double t = o.intersect(p, l, offset);
    if (t > 0 && t < dist) hit = true;
    if (o.type == Object::Type::Sphere) {
      // Closest approach of the ray's line to the centre, ahead of p.
      double along = dot(o.center - p, l);
      if (along > offset && along - o.radius < dist) {
        double miss = length(o.center - (p + l * along));
        if (std::fabs(miss - o.radius) < kGrazing * o.radius) grazing = true;
      }
    } else {
      double den = dot(l, o.normal);
      if (den != 0) {
        double u_t = dot(o.point - p, o.normal) / den;
        if (u_t > offset && u_t < dist) {
          Vec3 q = p + l * u_t - o.point, u, v;
          o.plane_axes(u, v);
          double edge = std::max(std::fabs(dot(q, u)), std::fabs(dot(q, v)));
          if (std::fabs(edge - o.size) < kGrazing * o.size) grazing = true;
        }
      }
    }
  }
  return hit;
}

double scene_scale(const Scene& s) {
  double r = length(s.camera.position);
  for (const auto& o : s.objects)
    r = std::max(r, o.type == Object::Type::Sphere ? length(o.center) + o.radius : length(o.point) + o.size);
  return std::max(r, 1.0);
}

}  // namespace

Render render_reference(const Material& m, const Scene& s, int width, int height, int threads) {
  Reference ref(m);
  Render r;
  r.image = Image(width, height);
  r.object.assign(size_t(width) * size_t(height), -1);
  r.grazing.assign(size_t(width) * size_t(height), 0);
  const double offset = kShadowRayOffset * scene_scale(s);
  const Vec3 axis(m.tangent_axis);

  auto shade_rows = [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < width; ++x) {
        Vec3 dir = s.camera.ray(x, y, width, height);
        Hit h = nearest(s, s.camera.position, dir, 0);
        if (h.object < 0) continue;
        size_t idx = size_t(y) * size_t(width) + size_t(x);
        r.object[idx] = h.object;
        const Object& obj = s.objects[size_t(h.object)];
        Vec3 p = s.camera.position + dir * h.t;
        Vec3 n = obj.normal_at(p);
        Vec3 v = -dir;
        Vec3 t = tangent_rule(n, axis);
        RGB L;
        for (int c = 0; c < 3; ++c) L[c] = m.ambient[c] * s.ambient[c] + m.emission[c];
        bool grazing = false;
        for (const auto& light : s.lights) {
          Vec3 l;
          double d;
          light.toward(p, l, d);
          double factor = ref.light_factor(light, l, d);
          if (!(factor > 0) || dot(n, l) <= 0) continue;
          if (blocked(s, size_t(h.object), p, l, d, offset, grazing)) continue;
          RGB f = ref.reflectance(n, l, v, t);
          for (int c = 0; c < 3; ++c) L[c] += factor * light.color[c] * f[c];
        }
        r.grazing[idx] = grazing;
        float* px = r.image.at(x, y);
        for (int c = 0; c < 3; ++c) px[c] = float(L[c]);
      }
    }
  };
  int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  n = std::min(n, height);
  std::vector<std::thread> pool;
  for (int i = 0; i < n; ++i) pool.emplace_back(shade_rows, height * i / n, height * (i + 1) / n);
  for (auto& t : pool) t.join();
  return r;
}

}  // namespace facet
