// The public ray–triangle entry points (raykernel/triangle.hpp): validation at the boundary, then the
// certified cascade, the exact reference or Möller–Trumbore.
#include <raykernel/triangle.hpp>

#include "certified/fp_requirements.hpp"
#include "entry_checks.hpp"
#include "exact/exact_triangle.hpp"
#include "ray_triangle_formula.hpp"
#include "triangle/ray_triangle_stages.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace raykernel {
namespace detail {

std::optional<std::string> triangle_invalid_reason(const Ray& ray, const Triangle& triangle) {
  struct Field {
    const char* name;
    const Vec3& value;
  };
  const Field fields[] = {{"ray origin", ray.origin},
                          {"ray direction", ray.direction},
                          {"triangle vertex a", triangle.a},
                          {"triangle vertex b", triangle.b},
                          {"triangle vertex c", triangle.c}};
  for (const Field& f : fields) {
    const double component[3] = {f.value.x, f.value.y, f.value.z};
    for (int i = 0; i < 3; ++i) {
      if (std::isnan(component[i])) return std::string(f.name) + " " + "xyz"[i] + " is NaN";
      if (std::isinf(component[i]))
        return std::string(f.name) + " " + "xyz"[i] + " is " + (component[i] > 0 ? "+inf" : "-inf");
    }
  }
  const Vec3& d = ray.direction;
  if (d.x == 0 && d.y == 0 && d.z == 0) return std::string("ray direction is the zero vector");
  return std::nullopt;
}

}  // namespace detail

namespace {

void throw_if_invalid(const Ray& ray, const Triangle& triangle) {
  if (std::optional<std::string> reason = detail::triangle_invalid_reason(ray, triangle)) throw invalid_input(*reason);
}

// The certified answer; the exact stage when the floating-point environment is not the one the bounds assume.
TracedTriangleIntersection certified(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  if (!detail::default_floating_point_environment()) [[unlikely]] {
    throw_if_invalid(ray, triangle);
    return {detail::exact::intersect_triangle(ray, triangle, options), Stage::exact, Stage::exact};
  }
  return detail::intersect_triangle_certified(ray, triangle, options);
}

}  // namespace

std::optional<std::string> validate(const Ray& ray, const Triangle& triangle) {
  return detail::triangle_invalid_reason(ray, triangle);
}

TriangleIntersection intersect(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  return certified(ray, triangle, options).intersection;
}

TracedTriangleIntersection intersect_traced(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  return certified(ray, triangle, options);
}

TriangleClassification relation(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  if (!detail::default_floating_point_environment()) [[unlikely]] {
    throw_if_invalid(ray, triangle);
    return detail::exact::classify_triangle(ray, triangle, rule);
  }
  return detail::triangle_relation_traced(ray, triangle, rule).classification;
}

TriangleIntersection intersect_exact(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  throw_if_invalid(ray, triangle);
  return detail::exact::intersect_triangle(ray, triangle, options);
}

ExactTriangleIntersection intersect_exact_rational(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  throw_if_invalid(ray, triangle);
  return detail::exact::intersect_triangle_rational(ray, triangle, rule);
}

TriangleIntersection intersect_naive(const Ray& ray, const Triangle& triangle) noexcept {
  struct V {
    double x, y, z;
  };
  auto sub = [](const Vec3& p, const Vec3& q) { return V{p.x - q.x, p.y - q.y, p.z - q.z}; };
  auto cross = [](const V& p, const V& q) {
    return V{p.y * q.z - p.z * q.y, p.z * q.x - p.x * q.z, p.x * q.y - p.y * q.x};
  };
  auto dot = [](const V& p, const V& q) { return p.x * q.x + p.y * q.y + p.z * q.z; };
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const V d{ray.direction.x, ray.direction.y, ray.direction.z};
  const V e1 = sub(triangle.b, triangle.a), e2 = sub(triangle.c, triangle.a);
  const V p = cross(d, e2);
  const double det = dot(e1, p);
  const V tvec = sub(ray.origin, triangle.a);
  if (det == 0) {
    const V n = cross(e1, e2);
    const TriangleRelation relation = (n.x == 0 && n.y == 0 && n.z == 0) ? TriangleRelation::degenerate
                                      : dot(tvec, n) == 0                ? TriangleRelation::coplanar
                                                                         : TriangleRelation::parallel;
    return {relation, TriangleLocation::none, false, nan, {nan, nan, nan}};
  }
  const double u = dot(tvec, p) / det;
  const V q = cross(tvec, e1);
  const double v = dot(d, q) / det;
  const double t = dot(e2, q) / det;
  const double w = (1 - u) - v;
  auto sign = [](double x) { return (x > 0) - (x < 0); };
  const TriangleLocation location = detail::triangle_location(sign(w), sign(u), sign(v), 1);
  const bool through = u >= 0 && v >= 0 && u + v <= 1;
  const TriangleRelation relation =
      !through ? TriangleRelation::miss : (t >= 0 ? TriangleRelation::hit : TriangleRelation::behind);
  return {relation, location, through, t, {w, u, v}};
}

std::string_view to_string(TriangleRule rule) noexcept {
  switch (rule) {
    case TriangleRule::owned: return "owned";
    case TriangleRule::closed: return "closed";
  }
  return "?";
}

std::string_view to_string(TriangleRelation relation) noexcept {
  switch (relation) {
    case TriangleRelation::hit: return "hit";
    case TriangleRelation::behind: return "behind";
    case TriangleRelation::miss: return "miss";
    case TriangleRelation::degenerate: return "degenerate";
    case TriangleRelation::parallel: return "parallel";
    case TriangleRelation::coplanar: return "coplanar";
  }
  return "?";
}

std::string_view to_string(TriangleLocation location) noexcept {
  switch (location) {
    case TriangleLocation::inside: return "inside";
    case TriangleLocation::edge_ab: return "edge-ab";
    case TriangleLocation::edge_bc: return "edge-bc";
    case TriangleLocation::edge_ca: return "edge-ca";
    case TriangleLocation::vertex_a: return "vertex-a";
    case TriangleLocation::vertex_b: return "vertex-b";
    case TriangleLocation::vertex_c: return "vertex-c";
    case TriangleLocation::outside: return "outside";
    case TriangleLocation::none: return "none";
  }
  return "?";
}

}  // namespace raykernel
