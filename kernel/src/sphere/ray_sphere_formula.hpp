// The ray–sphere formula of docs/contract.md §10, written once over any number type T (exact rationals on the
// exact path; the expansion stage builds the same polynomials from error-free transformations), and the
// decisions that read its signs.
//
//     f = o − c,   A = d·d,   B = d·f,   C = f·f − r²,   D = B² − A·C,
//
// and, for a rounding boundary m of a root (a midpoint of two doubles), q(m) = A·m² + 2B·m + C (the quadratic
// whose roots are t1 ≤ t2, times A > 0) and the slope A·m + B (its sign is that of m − U, U = −B/A).
#pragma once

#include <raykernel/sphere.hpp>

namespace raykernel::detail {

template <class T>
struct RaySphereTerms {
  T a, b, c, d;  // A, B, C, D
};

// `lift(x)` is the double x in T, `difference(v, w)` the exact v − w in T.
template <class T, class Lift, class Difference>
[[nodiscard]] RaySphereTerms<T> ray_sphere_terms(const Ray& ray, const Sphere& sphere, Lift lift, Difference difference) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  const Vec3& c = sphere.center;
  const T fx = difference(o.x, c.x), fy = difference(o.y, c.y), fz = difference(o.z, c.z);
  const T dx = lift(d.x), dy = lift(d.y), dz = lift(d.z), r = lift(sphere.radius);
  RaySphereTerms<T> t{dx * dx + dy * dy + dz * dz, dx * fx + dy * fy + dz * fz, fx * fx + fy * fy + fz * fz - r * r,
                      T{}};
  t.d = t.b * t.b - t.a * t.c;
  return t;
}

[[nodiscard]] constexpr SphereOrigin sphere_origin(int sign_c) noexcept {
  return sign_c < 0 ? SphereOrigin::inside : sign_c == 0 ? SphereOrigin::on_surface : SphereOrigin::outside;
}
[[nodiscard]] constexpr SphereRelation sphere_relation(int sign_d) noexcept {
  return sign_d < 0 ? SphereRelation::miss : sign_d == 0 ? SphereRelation::tangent : SphereRelation::cross;
}

// sign(t_k − m) for the smaller root (root = −1: t1, or t0) or the larger (root = +1: t2, or t0), from the signs
// of q(m) = A·(m − t1)·(m − t2) and of the slope A·m + B = A·(m − U), U = (t1 + t2)/2, for D ≥ 0:
//   q(m) < 0: t1 < m < t2;
//   q(m) > 0: m lies outside [t1, t2], below both when m < U (slope < 0), above both when m > U;
//   q(m) = 0: m is t1 when m ≤ U, t2 when m ≥ U (both, the tangent root, when m = U).
//   Certified by: proofs/sphere/SphereRoots.v, `root_side_of_smaller_correct` and `root_side_of_larger_correct`
//   (for every real m, A > 0 and D ≥ 0; the Coq definition is this case analysis, line by line).
[[nodiscard]] constexpr int root_side_of(int root, int sign_q, int sign_slope) noexcept {
  if (sign_q < 0) return root < 0 ? -1 : 1;
  if (sign_q > 0) return sign_slope < 0 ? 1 : -1;
  if (root < 0) return sign_slope <= 0 ? 0 : -1;
  return sign_slope >= 0 ? 0 : 1;
}

}  // namespace raykernel::detail
