// The public ray–triangle entry points (raykernel/triangle.hpp), as api.cpp's ray–plane ones: the default
// floating-point environment for the call (fp_environment.hpp); the fast path on raw input
// (triangle/ray_triangle_cascade.hpp); for what it does not certify, validation at the boundary
// (validation.hpp) and the full cascade; or the exact reference. Möller–Trumbore runs in the caller's
// environment, as the baseline it is.
#include <raykernel/triangle.hpp>

#include "core/fp_requirements.hpp"
#include "triangle/exact_triangle.hpp"
#include "core/fp_environment.hpp"
#include "triangle/ray_triangle_formula.hpp"
#include "triangle/ray_triangle_cascade.hpp"
#include "triangle/ray_triangle_stages.hpp"
#include "core/validation.hpp"
#include "nearest/interval_bound.hpp"

#include <limits>
#include <optional>
#include <string>

namespace raykernel {
namespace {

void throw_if_invalid(const Ray& ray, const Triangle& triangle) {
  if (detail::is_valid(ray) & detail::is_valid(triangle)) [[likely]]
    return;
  throw invalid_input(*validate(ray, triangle));
}

// The certified answer: the fast path (multiversioned, noexcept), then — outside it, since validation
// throws — the full cascade for valid input. In the default environment (the callers install it).
// Certified by: proofs/triangle/TriangleIntersectPublic.v, `intersect_public_correct` (certified's choice on valid
// input, through the twins of both paths: an answer before the exact stage has finite inputs, §6's class,
// den ≠ 0 when located, and each asked quotient RN(·/den) with den ≠ 0; run against this code by the
// differential runner, routine tri_cascade_intersect), and `relation_public_correct` (certified_relation's
// choice on valid input: an answer before the exact stage has finite inputs, §6's class under the rule, den ≠ 0
// exactly when located; routine tri_cascade_relation).
detail::TracedTriangleClassification certified_relation(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  if (const auto c = detail::fast_triangle_relation(ray, triangle, rule)) [[likely]]
    return *c;
  throw_if_invalid(ray, triangle);
  return detail::triangle_relation_cascade(ray, triangle, rule);
}

TracedTriangleIntersection certified(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  detail::TriangleStage2Handover stage2;
  if (const auto a = detail::fast_triangle_intersection(ray, triangle, options, stage2)) [[likely]]
    return *a;
  throw_if_invalid(ray, triangle);
  return detail::triangle_intersection_cascade(ray, triangle, options, stage2);
}

}  // namespace

TriangleIntersection intersect(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  return detail::in_default_fp_environment([&] { return certified(ray, triangle, options).intersection; });
}

TracedTriangleIntersection intersect_traced(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  return detail::in_default_fp_environment([&] { return certified(ray, triangle, options); });
}

TriangleClassification relation(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  return detail::in_default_fp_environment([&] { return certified_relation(ray, triangle, rule).classification; });
}

TriangleIntersection intersect_exact(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, triangle);
    return detail::exact::intersect_triangle(ray, triangle, options);
  });
}

std::optional<TriangleIntersection> intersect(const Ray& ray, const RayInterval& interval, const Triangle& triangle,
                                              const TriangleOptions& options) {
  return detail::in_default_fp_environment([&]() -> std::optional<TriangleIntersection> {
    throw_if_invalid(ray, triangle);
    detail::throw_if_invalid_interval(interval);
    if (!detail::hits_within_interval(ray, interval, triangle, options.rule)) return std::nullopt;
    return certified(ray, triangle, options).intersection;
  });
}

std::optional<TriangleIntersection> intersect_exact(const Ray& ray, const RayInterval& interval,
                                                    const Triangle& triangle, const TriangleOptions& options) {
  return detail::in_default_fp_environment([&]() -> std::optional<TriangleIntersection> {
    throw_if_invalid(ray, triangle);
    detail::throw_if_invalid_interval(interval);
    const TriangleIntersection x = detail::exact::intersect_triangle(ray, triangle, options);
    if (x.relation != TriangleRelation::hit || !detail::exact_t_within_interval(ray, interval, triangle))
      return std::nullopt;
    return x;
  });
}

ExactTriangleIntersection intersect_exact_rational(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, triangle);
    return detail::exact::intersect_triangle_rational(ray, triangle, rule);
  });
}

// Möller–Trumbore in the caller's environment, as the baseline it is (no guarantee, no check).
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
