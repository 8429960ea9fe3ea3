// spawn from a sphere and sphere_side (<raykernel/spawn.hpp>; the rule: docs/contract.md, "Decided here":
// spawning from a sphere), decided exactly: the sides, the normal and the thresholds along the stepping axis are
// exact (GMP rationals, and the thresholds' square roots rounded by MPFR, core/root_rounding.hpp), the roundings to the
// origin's format one correct rounding each. The steps and the format's values: spawn/format_steps.hpp, shared
// with the triangle's spawn.
//
// Why the steps are found without stepping. Only coordinate i moves; with K = Σ_{j≠i} (P̂_j − c_j)² and
// V = r² − K, σ is the sign of C'(x) = (x − c_i)² − V and, leaving outward, B'(x) = w_i·(x − c_i) + Σ_{j≠i}
// w_j·(P̂_j − c_j) must be ≥ 0. Both are polynomials in x of degree ≤ 2.
//   - Outward (s = +1, δ = sign(N_i), w_i·δ > 0): B' grows with every step. Let b be the first value beyond P̂_i
//     with B' ≥ 0 (the step after P̂_i, or the first value at or beyond B's root x_B when that is further). The
//     values between P̂_i and b fail B'. If C'(b) > 0, b is accepted; otherwise b lies in [c_i − √V, c_i + √V]
//     (C' ≤ 0 there only), every value beyond b keeps B' ≥ 0, and the first accepted one is the first value
//     strictly beyond the far root c_i + δ·√V.
//   - Inward (s = −1, δ = −sign(N_i)): C' < 0 exactly on the open interval between the roots (none when V ≤ 0).
//     P̂ is not accepted, so P̂_i lies outside it: before it when δ·(P̂_i − c_i) < 0, then the first accepted value
//     is the first one strictly beyond the near root c_i − δ·√V, if it is still inside (C' < 0); past it
//     otherwise, and then no value beyond P̂_i is inside.
// The guarantee each accepted origin carries: proofs/sphere/SphereSpawn.v.
#include <raykernel/spawn.hpp>

#include "core/binary64_rounding.hpp"
#include "core/fp_environment.hpp"
#include "core/rational_from_double.hpp"
#include "spawn/exact_point.hpp"
#include "spawn/format_steps.hpp"
#include "core/root_rounding.hpp"

#include <gmpxx.h>

#include <cmath>
#include <optional>
#include <string>

namespace raykernel {
namespace {

using detail::exact::dot;
using detail::exact::exact;
using detail::exact::minus;
using detail::exact::Q3;
using detail::exact::rational_from_double;
using detail::spawn_steps::axis_name;
using detail::spawn_steps::format_of;
using detail::spawn_steps::invalid;
using detail::spawn_steps::require_finite;
using detail::spawn_steps::step;
using detail::spawn_steps::steps_between;
using Q = mpq_class;

void require_valid(const Sphere& sphere) {
  if (const std::optional<std::string> error = validate(sphere)) invalid(*error);
}

mpfr_rnd_t towards(int delta) { return delta > 0 ? MPFR_RNDU : MPFR_RNDD; }

// The first value of the format strictly beyond U + root·√V (V ≥ 0) in direction δ, or ±inf.
double first_beyond_root(const Q& u, const Q& v, int root, int delta, OriginFormat format) {
  bool on_root = false;
  const double x = detail::exact::round_root(u, v, root, format_of(format), towards(delta), &on_root);
  return on_root ? step(x, delta, format) : x;
}

// The first value of the format at or beyond the rational x in direction δ, or ±inf.
double first_at_or_beyond(const Q& x, int delta, OriginFormat format) {
  return detail::exact::round_rational(x, format_of(format), towards(delta));
}

// δ·(a − b) > 0: a lies beyond b in direction δ.
bool beyond(const Q& a, const Q& b, int delta) { return sgn(a - b) * delta > 0; }

SpawnedOrigin spawn_from_sphere(const Vec3& point, const Sphere& source, const Vec3& w, OriginFormat format) {
  require_finite(point, "point");
  require_valid(source);
  require_finite(w, "direction w");
  if (w.x == 0 && w.y == 0 && w.z == 0) invalid("direction w is the zero vector");
  const Q3 c = exact(source.center), wq = exact(w);
  const Q r_squared = rational_from_double(source.radius) * rational_from_double(source.radius);
  const Q3 normal = minus(exact(point), c);
  if (sgn(normal[0]) == 0 && sgn(normal[1]) == 0 && sgn(normal[2]) == 0)
    invalid("the point is the sphere's center (N = p - c = 0)");
  const int s = sgn(dot(wq, normal));
  if (s == 0) invalid("direction w is tangent to the sphere at the point (w.(p - c) = 0)");

  // P̂, and whether an origin is accepted.
  double r[3];
  Q3 rounded_exact;
  const double p[3] = {point.x, point.y, point.z};
  for (int k = 0; k < 3; ++k) {
    r[k] = detail::exact::round_rational(rational_from_double(p[k]), format_of(format), MPFR_RNDN);
    if (!std::isfinite(r[k]))
      invalid(std::string("the rounded point overflows ") + std::string(to_string(format)) + " (coordinate " +
              axis_name(k) + ")");
    rounded_exact[k] = rational_from_double(r[k]);
  }
  const auto c_prime = [&](const Q3& x) { const Q3 f = minus(x, c); return sgn(dot(f, f) - r_squared); };
  const auto accepted = [&](const Q3& x) {
    return s < 0 ? c_prime(x) < 0 : c_prime(x) > 0 && sgn(dot(wq, minus(x, c))) >= 0;
  };
  if (accepted(rounded_exact)) return {Vec3{r[0], r[1], r[2]}, 0};

  // The axis and the direction of the steps.
  int i = -1;
  for (int k = 0; k < 3; ++k) {
    if (s > 0 && sgn(wq[k]) * sgn(normal[k]) <= 0) continue;  // outward: only axes with w_k·N_k > 0
    if (i < 0 || abs(normal[k]) > abs(normal[i])) i = k;
  }
  const int delta = sgn(normal[i]) * s;
  Q k_rest = 0;  // K = Σ_{j≠i} (P̂_j − c_j)²
  for (int k = 0; k < 3; ++k)
    if (k != i) k_rest += (rounded_exact[k] - c[k]) * (rounded_exact[k] - c[k]);
  const Q v = r_squared - k_rest;
  const auto with_coordinate = [&](double x) {
    Q3 y = rounded_exact;
    y[i] = rational_from_double(x);
    return y;
  };
  const std::string no_origin = std::string("no origin in ") + std::string(to_string(format)) +
                                (s > 0 ? " outside the sphere" : " strictly inside the sphere") + " along axis " +
                                axis_name(i);

  double x = 0;
  if (s > 0) {
    Q b_rest = 0;  // B'(x) = w_i·(x − c_i) + Σ_{j≠i} w_j·(P̂_j − c_j), increasing in direction δ
    for (int k = 0; k < 3; ++k)
      if (k != i) b_rest += wq[k] * (rounded_exact[k] - c[k]);
    const Q x_b = c[i] - b_rest / wq[i];  // B'(x_b) = 0
    x = step(r[i], delta, format);
    if (std::isfinite(x) && beyond(x_b, rational_from_double(x), delta)) x = first_at_or_beyond(x_b, delta, format);
    if (std::isfinite(x) && c_prime(with_coordinate(x)) <= 0) x = first_beyond_root(c[i], v, delta, delta, format);
  } else {
    if (sgn(v) <= 0 || sgn(rounded_exact[i] - c[i]) * delta > 0) invalid(no_origin);
    x = first_beyond_root(c[i], v, -delta, delta, format);
    if (std::isfinite(x) && c_prime(with_coordinate(x)) >= 0) invalid(no_origin);
  }
  if (!std::isfinite(x)) invalid(no_origin + " (beyond the largest finite value)");
  const std::uint64_t steps = steps_between(r[i], x, format);
  r[i] = x;
  return {Vec3{r[0], r[1], r[2]}, steps};
}

}  // namespace

SpawnedOrigin spawn(const Vec3& point, const Sphere& source, const Vec3& direction, OriginFormat format) {
  return detail::in_default_fp_environment([&] { return spawn_from_sphere(point, source, direction, format); });
}

int sphere_side(const Vec3& point, const Sphere& sphere) {
  return detail::in_default_fp_environment([&] {
    require_finite(point, "point");
    require_valid(sphere);
    const Q3 f = minus(exact(point), exact(sphere.center));
    const Q r = rational_from_double(sphere.radius);
    return sgn(dot(f, f) - r * r);
  });
}

}  // namespace raykernel
