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
struct RayPlaneTerms {
  T num;  // (p − o)·n
  T den;  // d·n
};

// `lift` maps an input double to T (exactly, for an exact T).
template <class T, class Lift>
[[nodiscard]] RayPlaneTerms<T> ray_plane_terms(const Ray& ray, const Plane& plane, Lift lift) {
  const Vec3 &o = ray.origin, &d = ray.direction, &p = plane.point, &n = plane.normal;
  const T nx = lift(n.x), ny = lift(n.y), nz = lift(n.z);
  T den = (lift(d.x) * nx + lift(d.y) * ny) + lift(d.z) * nz;
  T num = ((lift(p.x) - lift(o.x)) * nx + (lift(p.y) - lift(o.y)) * ny) + (lift(p.z) - lift(o.z)) * nz;
  return {std::move(num), std::move(den)};
}

// The relation of docs/contract.md §1 from the exact signs (−1, 0, +1) of num and den.
[[nodiscard]] constexpr Relation relation_from_signs(int num_sign, int den_sign) noexcept {
  if (den_sign == 0) return num_sign == 0 ? Relation::in_plane : Relation::parallel;
  // hit iff num/den ≥ 0 iff num·den ≥ 0 (written without a branch on the unpredictable signs)
  return static_cast<Relation>(static_cast<int>(Relation::hit) +
                               (static_cast<int>(Relation::behind) - static_cast<int>(Relation::hit)) *
                                   static_cast<int>(num_sign * den_sign < 0));
}

}  // namespace raykernel::detail
