// spawn and spawn_to (<raykernel/spawn.hpp>, docs/contract.md §9): the certified fast path first
// (spawn/spawn_certified.cpp), then, for what it leaves, the exact path here — spawn_exact and spawn_to_exact alone,
// the reference the fast path is tested against. The exact path decides exactly: the hit point P, the
// sides and the threshold along the stepping axis are exact rationals (GMP), the roundings to the origin's
// format one correct rounding each (MPFR, core/binary64_rounding.hpp).
//
// Why the steps are found without stepping: only coordinate i moves, and σ((x_1, x_2, x_3)) is the sign of
// N_i·x_i + C with C = Σ_{j≠i} N_j·(P̂_j − a_j) − N_i·a_i, linear in x_i. Moving x_i in the direction
// δ = sign(N_i)·s moves N_i·x_i towards s's side: the values of F at or before the threshold x* = −C/N_i (in
// direction δ) have σ ≠ s, those strictly beyond it σ = s. So the origin's coordinate is v, the first value of
// F strictly beyond x* (x* rounded towards δ, one more step when that is x* itself), and k is the number of
// values of F from P̂_i to v: the difference of their ordinals (spawn/format_steps.hpp). σ(P̂) ≠ s puts P̂_i at or
// before x*, so k ≥ 1 and every value before v has σ ≠ s: k is the smallest.
#include <raykernel/spawn.hpp>

#include "core/binary64_rounding.hpp"
#include "core/fp_environment.hpp"
#include "core/rational_from_double.hpp"
#include "spawn/exact_point.hpp"
#include "spawn/format_steps.hpp"
#include "spawn/spawn_certified.hpp"

#include <gmpxx.h>

#include <array>
#include <bit>
#include <cmath>
#include <string>

namespace raykernel {
namespace {

using detail::exact::cross;
using detail::exact::dot;
using detail::exact::exact;
using detail::exact::minus;
using detail::exact::Q3;
using detail::exact::rational_from_double;
using Q = mpq_class;
using detail::spawn_steps::axis_name;
using detail::spawn_steps::format_of;
using detail::spawn_steps::invalid;
using detail::spawn_steps::require_finite;
using detail::spawn_steps::steps_between;

// The source's a and N and the hit point P, exactly, after the checks every entry point makes, in the order
// the reasons are reported: non-finite values (the hit, the triangle, then `extra`: w or q), a zero ray
// direction, a zero w (`zero_extra`), a degenerate triangle, a ray parallel to the plane.
struct ExactHit {
  Q3 a, normal, p;
};
ExactHit exact_hit(const HitPoint& hit, const Triangle& source, const Vec3* extra = nullptr,
                   const char* extra_name = nullptr, bool zero_extra = false) {
  if (hit.kind == HitPoint::Kind::ray_crossing) {
    require_finite(hit.ray.origin, "ray origin");
    require_finite(hit.ray.direction, "ray direction");
  } else {
    require_finite(hit.point, "point");
  }
  require_finite(source.a, "triangle a");
  require_finite(source.b, "triangle b");
  require_finite(source.c, "triangle c");
  if (extra != nullptr) require_finite(*extra, extra_name);
  if (hit.kind == HitPoint::Kind::ray_crossing && hit.ray.direction.x == 0 && hit.ray.direction.y == 0 &&
      hit.ray.direction.z == 0)
    invalid("ray direction is the zero vector");
  if (zero_extra && extra->x == 0 && extra->y == 0 && extra->z == 0) invalid("direction w is the zero vector");

  ExactHit h;
  h.a = exact(source.a);
  h.normal = cross(minus(exact(source.b), h.a), minus(exact(source.c), h.a));
  if (sgn(h.normal[0]) == 0 && sgn(h.normal[1]) == 0 && sgn(h.normal[2]) == 0)
    invalid("the triangle is degenerate (N = (b - a) x (c - a) = 0)");
  std::optional<Q3> p = detail::exact::hit_point(hit, h.a, h.normal);
  if (!p) invalid("the ray is parallel to the triangle's plane (den = d.N = 0)");
  h.p = std::move(*p);
  return h;
}

SpawnedOrigin spawn_on_side(const HitPoint& hit, const Triangle& source, int side_of, const Vec3& w_or_q,
                            OriginFormat format) {
  // side_of: 0 for spawn (s = sign(w·N)), 1 for spawn_to (s = σ(q)).
  const ExactHit h = exact_hit(hit, source, &w_or_q, side_of == 0 ? "direction w" : "target q", side_of == 0);
  const Q3& a = h.a;
  const Q3& normal = h.normal;
  const Q3* const p = &h.p;

  // The side s.
  const int s = side_of == 0 ? sgn(dot(exact(w_or_q), normal)) : sgn(dot(minus(exact(w_or_q), a), normal));
  if (s == 0)
    invalid(side_of == 0 ? "direction w is parallel to the triangle's plane (w.N = 0)"
                         : "target q lies in the triangle's plane (sigma(q) = 0)");

  // P̂.
  const detail::exact::BinaryFormat& f = format_of(format);
  Vec3 rounded{};
  double* r = &rounded.x;
  Q3 rounded_exact;
  for (int k = 0; k < 3; ++k) {
    r[k] = detail::exact::round_rational((*p)[k], f, MPFR_RNDN);
    if (!std::isfinite(r[k]))
      invalid(std::string("the rounded hit point overflows ") + std::string(to_string(format)) + " (coordinate " +
              axis_name(k) + ")");
    rounded_exact[k] = rational_from_double(r[k]);
  }
  const int sigma = sgn(dot(minus(rounded_exact, a), normal));
  if (sigma == s) return {rounded, 0};

  // The axis of the largest |N_i| (the smallest i on an exact tie) and the direction of the steps.
  int i = 0;
  for (int k = 1; k < 3; ++k)
    if (abs(normal[k]) > abs(normal[i])) i = k;
  const int delta = sgn(normal[i]) * s;
  // The threshold x* on axis i, and v, the first value of the format strictly beyond it in direction δ.
  Q rest = 0;
  for (int k = 0; k < 3; ++k)
    if (k != i) rest += normal[k] * (rounded_exact[k] - a[k]);
  const Q threshold = a[i] - rest / normal[i];
  bool on_threshold = false;
  double v = detail::exact::round_rational(threshold, f, delta > 0 ? MPFR_RNDU : MPFR_RNDD, &on_threshold);
  if (on_threshold) v = detail::spawn_steps::step(v, delta, format);  // x* itself has σ = 0: one more
  if (!std::isfinite(v))
    invalid(std::string("no origin in ") + std::string(to_string(format)) + " on the side of w along axis " +
            axis_name(i) + " (beyond the largest finite value)");
  const std::uint64_t steps = steps_between(r[i], v, format);
  r[i] = v;
  return {rounded, steps};
}

// Every zero coordinate of an origin as +0: §9 leaves a zero's sign unspecified, and the two paths reach a zero
// differently (a step from −2^-1074 up is +0; MPFR rounds a negative value up to −0), so one sign is chosen, for
// answers that are the same bits whichever path decided them (tests/spawn_test.cpp, fuzz/fuzz_spawn.cpp).
SpawnedOrigin with_positive_zeros(SpawnedOrigin o) noexcept {
  for (double* c : {&o.origin.x, &o.origin.y, &o.origin.z})
    if (*c == 0) *c = 0;
  return o;
}
}  // namespace

SpawnedOrigin spawn(const HitPoint& hit, const Triangle& source, const Vec3& direction, OriginFormat format) {
  return detail::in_default_fp_environment([&] {
    if (const auto fast = detail::spawn_certified(hit, source, false, direction, format))
      return with_positive_zeros(*fast);
    return with_positive_zeros(spawn_on_side(hit, source, 0, direction, format));
  });
}

SpawnedOrigin spawn_to(const HitPoint& hit, const Triangle& source, const Vec3& target, OriginFormat format) {
  return detail::in_default_fp_environment([&] {
    if (const auto fast = detail::spawn_certified(hit, source, true, target, format)) return with_positive_zeros(*fast);
    return with_positive_zeros(spawn_on_side(hit, source, 1, target, format));
  });
}

SpawnedOrigin spawn_exact(const HitPoint& hit, const Triangle& source, const Vec3& direction, OriginFormat format) {
  return detail::in_default_fp_environment(
      [&] { return with_positive_zeros(spawn_on_side(hit, source, 0, direction, format)); });
}

SpawnedOrigin spawn_to_exact(const HitPoint& hit, const Triangle& source, const Vec3& target, OriginFormat format) {
  return detail::in_default_fp_environment(
      [&] { return with_positive_zeros(spawn_on_side(hit, source, 1, target, format)); });
}

Vec3 rounded_hit_point(const HitPoint& hit, const Triangle& source, OriginFormat format) {
  return detail::in_default_fp_environment([&] {
    const ExactHit h = exact_hit(hit, source);
    Vec3 r{};
    double* c = &r.x;
    for (std::size_t k = 0; k < 3; ++k) c[k] = detail::exact::round_rational(h.p[k], format_of(format), MPFR_RNDN);
    return r;
  });
}

namespace {
// sign(v·N), v = x − a for a point (`point`), or x itself for a direction; exactly, after the finiteness checks.
int side_of(const Vec3& x, bool point, const Triangle& triangle) {
  return detail::in_default_fp_environment([&] {
    require_finite(x, point ? "point" : "direction");
    require_finite(triangle.a, "triangle a");
    require_finite(triangle.b, "triangle b");
    require_finite(triangle.c, "triangle c");
    const Q3 a = exact(triangle.a);
    const Q3 v = point ? minus(exact(x), a) : exact(x);
    return sgn(dot(v, cross(minus(exact(triangle.b), a), minus(exact(triangle.c), a))));
  });
}
}  // namespace

int plane_side(const Vec3& point, const Triangle& triangle) { return side_of(point, true, triangle); }
int direction_side(const Vec3& direction, const Triangle& triangle) { return side_of(direction, false, triangle); }

std::string_view to_string(OriginFormat format) noexcept {
  return format == OriginFormat::binary32 ? "binary32" : "binary64";
}

}  // namespace raykernel
