// Exact points and vectors of the spawn folder: a Vec3 as three GMP rationals, their arithmetic, and the hit
// point P of a HitPoint (docs/contract.md §9) — written once, for spawn/spawn_to and for the exact ground truth
// of secondary rays (secondary_exact.cpp).
#pragma once

#include <raykernel/spawn.hpp>

#include "core/rational_from_double.hpp"

#include <gmpxx.h>

#include <array>
#include <optional>

namespace raykernel::detail::exact {

using Q3 = std::array<mpq_class, 3>;

[[nodiscard]] inline Q3 exact(const Vec3& v) {
  return {rational_from_double(v.x), rational_from_double(v.y), rational_from_double(v.z)};
}
[[nodiscard]] inline mpq_class dot(const Q3& u, const Q3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
[[nodiscard]] inline Q3 minus(const Q3& u, const Q3& v) { return {u[0] - v[0], u[1] - v[1], u[2] - v[2]}; }
[[nodiscard]] inline Q3 cross(const Q3& u, const Q3& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

// P exactly: where the ray's line crosses the plane through `a` with normal `normal` (P = o + (num/den)·d,
// num = (a − o)·N, den = d·N), or the given point. Nothing when the line is parallel to the plane (den = 0).
[[nodiscard]] inline std::optional<Q3> hit_point(const HitPoint& hit, const Q3& a, const Q3& normal) {
  if (hit.kind == HitPoint::Kind::point) return exact(hit.point);
  const Q3 o = exact(hit.ray.origin), d = exact(hit.ray.direction);
  const mpq_class den = dot(d, normal);
  if (sgn(den) == 0) return std::nullopt;
  const mpq_class t = dot(minus(a, o), normal) / den;
  return Q3{o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
}

}  // namespace raykernel::detail::exact
