#include "my_ray_code.hpp"

#include <cmath>
#include <limits>

namespace my {
namespace {
double dot(const raykernel::Vec3& a, const raykernel::Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
raykernel::Vec3 minus(const raykernel::Vec3& a, const raykernel::Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr double epsilon = 1e-12;
}  // namespace

raykernel::Intersection ray_plane(const raykernel::Ray& ray, const raykernel::Plane& plane) {
  using raykernel::Relation;
  const double den = dot(ray.direction, plane.normal);
  const double num = dot(minus(plane.point, ray.origin), plane.normal);
  if (std::fabs(den) < epsilon) {
    return {std::fabs(num) < epsilon ? Relation::in_plane : Relation::parallel,
            std::numeric_limits<double>::quiet_NaN()};
  }
  const double t = num / den;
  return {t >= 0 ? Relation::hit : Relation::behind, t};
}

int nearest_hit(const raykernel::Ray& ray, std::span<const raykernel::Plane> planes) {
  int best = -1;
  double best_t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const raykernel::Intersection x = ray_plane(ray, planes[i]);
    if (x.relation == raykernel::Relation::hit && (best < 0 || x.t < best_t)) {
      best = static_cast<int>(i);
      best_t = x.t;
    }
  }
  return best;
}

}  // namespace my
