// The lecture's ray–plane formula, written once and evaluated in any number type.
//
//     den = d·n,    num = (p − o)·n,    t = num / den
//
// (docs/ray-casting.md §2: (d·n) t = −(o − p)·n). The naive path instantiates it with double, the exact path with
// CGAL::Exact_rational; the certified stages evaluate the same two dot products, term by term in the same
// order, with error-free transformations (certified/).
#pragma once

#include <raykernel/raykernel.hpp>

namespace raykernel::detail {

template <class T>
struct RayPlaneValues {
  T num;  // (p − o)·n
  T den;  // d·n
};

// `lift` maps an input double to T (exactly, for an exact T).
template <class T, class Lift>
[[nodiscard]] RayPlaneValues<T> ray_plane_values(const Ray& ray, const Plane& plane, Lift lift) {
  const Vec3 &o = ray.origin, &d = ray.direction, &p = plane.point, &n = plane.normal;
  const T nx = lift(n.x), ny = lift(n.y), nz = lift(n.z);
  T den = (lift(d.x) * nx + lift(d.y) * ny) + lift(d.z) * nz;
  T num = ((lift(p.x) - lift(o.x)) * nx + (lift(p.y) - lift(o.y)) * ny) + (lift(p.z) - lift(o.z)) * nz;
  return {std::move(num), std::move(den)};
}

// For den ≠ 0: the ray meets the plane behind its origin, num/den < 0, exactly when num·den < 0. Signs are
// −1, 0, +1 (an int, or integer lanes of a vector: then the answer is a lane mask).
template <class SignInteger>
[[nodiscard]] constexpr auto signs_say_behind(SignInteger num_sign, SignInteger den_sign) noexcept {
  return num_sign * den_sign < 0;
}

// The relation of docs/contract.md §1 from the exact signs (−1, 0, +1) of num and den.
[[nodiscard]] constexpr Relation relation_from_signs(int num_sign, int den_sign) noexcept {
  if (den_sign == 0) return num_sign == 0 ? Relation::in_plane : Relation::parallel;
  return signs_say_behind(num_sign, den_sign) ? Relation::behind : Relation::hit;
}

}  // namespace raykernel::detail
