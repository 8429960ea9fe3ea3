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

// The open segment from p to q (docs/contract.md §8 and §10): the line p + t·e with the exact direction
// e = q − p, whose quadratic A·t² + 2B·t + C has at the ends
//   q(0) = C_p = |p − c|² − r²,  q(1) = A + 2B + C = C_q = |q − c|² − r²,
//   slope(0) = B = e·(p − c),     slope(1) = A + B = e·(q − c),
// and D = B² − A·C_p. Every term is a polynomial in the doubles given (no rounded q − p).
template <class T>
struct SegmentSphereTerms {
  T a, c_p, c_q, b_p, b_q, d;
};

template <class T, class Lift, class Difference>
[[nodiscard]] SegmentSphereTerms<T> segment_sphere_terms(const Vec3& p, const Vec3& q, const Sphere& sphere, Lift lift,
                                                         Difference difference) {
  const Vec3& c = sphere.center;
  const T ex = difference(q.x, p.x), ey = difference(q.y, p.y), ez = difference(q.z, p.z);
  const T fx = difference(p.x, c.x), fy = difference(p.y, c.y), fz = difference(p.z, c.z);
  const T gx = difference(q.x, c.x), gy = difference(q.y, c.y), gz = difference(q.z, c.z);
  const T r = lift(sphere.radius);
  const T r2 = r * r;
  SegmentSphereTerms<T> t{ex * ex + ey * ey + ez * ez,
                          fx * fx + fy * fy + fz * fz - r2,
                          gx * gx + gy * gy + gz * gz - r2,
                          ex * fx + ey * fy + ez * fz,
                          ex * gx + ey * gy + ez * gz,
                          T{}};
  t.d = t.b_p * t.b_p - t.a * t.c_p;
  return t;
}

// Whether a root lies strictly between the ends (0 < t_k < 1), from the signs of D, C_p, B at 0, C_q and A + B at
// 1: D ≥ 0 and some root k with sign(t_k − 0) > 0 and sign(t_k − 1) < 0 (root_side_of at m = 0 and m = 1; A > 0
// as p ≠ q). A tangent root counts (the sphere is closed); a root at an end does not (the segment is open).
//   Certified by: proofs/sphere/SphereSegment.v, `segment_root_inside_correct` (for all A > 0, B, C on the exact
//   signs: true exactly when some root of A·t² + 2B·t + C lies in (0, 1); the Coq definition is this case analysis).
[[nodiscard]] constexpr bool segment_root_inside(int sign_d, int sign_c_p, int sign_b_p, int sign_c_q,
                                                 int sign_b_q) noexcept {
  if (sign_d < 0) return false;
  for (int root : {-1, 1})
    if (root_side_of(root, sign_c_p, sign_b_p) > 0 && root_side_of(root, sign_c_q, sign_b_q) < 0) return true;
  return false;
}

}  // namespace raykernel::detail
