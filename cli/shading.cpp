#include "shading.hpp"

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
  const double facing = std::fabs(dot(unit, p.unit_normal));  // cos of the angle to the normal
  Linear c = base * (0.22 + 0.78 * facing);
  if (scene_.fog_distance > 0) {
    const double visible = std::exp2(-(t * length) / scene_.fog_distance);
    c = c * visible + horizon_ * (1 - visible);
  }
  return c;
}

}  // namespace raykernel::cli
