#include "rendering/shading.hpp"

#include <raykernel/transform.hpp>

#include <algorithm>
#include <cmath>

namespace raykernel::cli {
namespace {

double dot(const Vec3& a, const Vec3& b) noexcept { return a.x * b.x + a.y * b.y + a.z * b.z; }

}  // namespace

Shader::PreparedPlane Shader::prepare(const ScenePlane& sp) {
  PreparedPlane p;
  p.unit_normal = normalized(sp.plane.normal);
  p.color[0] = p.color[1] = linear(sp.color);
  if (sp.checker) {
    const Vec3& n = p.unit_normal;
    const Vec3& a = sp.checker->u_axis;
    const double k = dot(a, n);
    p.u = normalized({a.x - k * n.x, a.y - k * n.y, a.z - k * n.z});
    p.v = {n.y * p.u.z - n.z * p.u.y, n.z * p.u.x - n.x * p.u.z, n.x * p.u.y - n.y * p.u.x};
    p.color[0] = linear(sp.checker->colors[0]);
    p.color[1] = linear(sp.checker->colors[1]);
    p.checker_size = sp.checker->size;
  }
  return p;
}

Shader::Shader(const Scene& s)
    : scene_(s), horizon_(linear(s.background.horizon)), zenith_(linear(s.background.zenith)) {
  for (const ScenePlane& p : s.planes) planes_.push_back(prepare(p));
  for (const SceneMeshReference& m : s.mesh_files) mesh_colors_.push_back(linear(m.color));
  for (const SceneSphere& sp : s.spheres) sphere_colors_.push_back(linear(sp.color));
}

Linear Shader::sky(const Vec3& unit_direction) const noexcept {
  const double elevation = std::clamp(unit_direction.y, 0.0, 1.0);
  const double k = std::sqrt(elevation);
  return horizon_ * (1 - k) + zenith_ * k;
}

Linear Shader::shade(const Ray& ray, const std::optional<NearestHit>& hit) const noexcept {
  const Vec3& d = ray.direction;
  const double length = std::sqrt(dot(d, d));
  const Vec3 unit{d.x / length, d.y / length, d.z / length};
  if (!hit || !std::isfinite(hit->t)) return sky(unit);
  const PreparedPlane& p = planes_[hit->plane];
  const Vec3& point = scene_.planes[hit->plane].plane.point;
  const double t = hit->t;
  Linear base = p.color[0];
  if (p.checker_size > 0) {
    const Vec3 x{ray.origin.x + t * d.x - point.x, ray.origin.y + t * d.y - point.y, ray.origin.z + t * d.z - point.z};
    const double a = std::floor(dot(x, p.u) / p.checker_size), b = std::floor(dot(x, p.v) / p.checker_size);
    const double parity = std::fabs(std::fmod(a + b, 2.0));
    if (std::isfinite(parity) && parity == 1) base = p.color[1];
  }
  return lit(unit, length, t, base, p.unit_normal);
}

Linear Shader::lit(const Vec3& unit, double length, double t, Linear base, const Vec3& unit_normal) const noexcept {
  const double facing = std::fabs(dot(unit, unit_normal));  // cos of the angle to the normal
  Linear c = base * (0.22 + 0.78 * facing);
  if (scene_.fog_distance > 0) {
    const double visible = std::exp2(-(t * length) / scene_.fog_distance);
    c = c * visible + horizon_ * (1 - visible);
  }
  return c;
}

Linear Shader::shade_triangle(const Ray& ray, std::uint32_t triangle, double t) const noexcept {
  const Vec3& d = ray.direction;
  const double length = std::sqrt(dot(d, d));
  const Vec3 unit{d.x / length, d.y / length, d.z / length};
  if (!std::isfinite(t) || triangle >= scene_.mesh.triangles.size()) return sky(unit);
  const Triangle tri = scene_.mesh.triangle(triangle);
  const Vec3 e1{tri.b.x - tri.a.x, tri.b.y - tri.a.y, tri.b.z - tri.a.z};
  const Vec3 e2{tri.c.x - tri.a.x, tri.c.y - tri.a.y, tri.c.z - tri.a.z};
  const Vec3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const double n_length = std::sqrt(dot(n, n));
  // A hit triangle is not degenerate, but its rounded normal may be 0 or overflow: shade it face-on then.
  const Vec3 unit_normal = n_length > 0 && std::isfinite(n_length) ? Vec3{n.x / n_length, n.y / n_length, n.z / n_length}
                                                                   : Vec3{-unit.x, -unit.y, -unit.z};
  const std::size_t mesh = scene_.mesh_of_triangle(triangle);
  const Linear base = mesh < mesh_colors_.size() ? mesh_colors_[mesh] : linear(scene_defaults::plane_colors[0]);
  return lit(unit, length, t, base, unit_normal);
}

Linear Shader::shade_sphere(const Ray& ray, std::size_t sphere, double t) const noexcept {
  const Vec3& d = ray.direction;
  const double length = std::sqrt(dot(d, d));
  const Vec3 unit{d.x / length, d.y / length, d.z / length};
  if (!std::isfinite(t) || sphere >= scene_.spheres.size()) return sky(unit);
  const Sphere& s = scene_.spheres[sphere].sphere;
  const Vec3 n{ray.origin.x + t * d.x - s.center.x, ray.origin.y + t * d.y - s.center.y, ray.origin.z + t * d.z - s.center.z};
  const double n_length = std::sqrt(dot(n, n));
  const Vec3 unit_normal = n_length > 0 && std::isfinite(n_length) ? Vec3{n.x / n_length, n.y / n_length, n.z / n_length}
                                                                   : Vec3{-unit.x, -unit.y, -unit.z};
  return lit(unit, length, t, sphere_colors_[sphere], unit_normal);
}

}  // namespace raykernel::cli
