// The exact stage of the nearest-hit module where kinds meet, and the reference of a scene: GMP rationals from
// the doubles' bits (core/rational_from_double.hpp). This header exposes no GMP type; exact_nearest.cpp is the
// only translation unit that sees them. Inputs must be valid (validated by the caller).
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/triangle.hpp>

namespace raykernel::detail::exact {

// The sign of t_plane − t_triangle along `ray` for a plane and a triangle whose den are nonzero (t = num/den of
// docs/contract.md §1 and §6).
[[nodiscard]] int compare_plane_triangle_t(const Ray& ray, const Plane& plane, const Triangle& triangle);

// The sign of t − b for a plane's t = num/den (den ≠ 0) and a double b (an interval's bound).
[[nodiscard]] int compare_plane_t_with(const Ray& ray, const Plane& plane, double b);

// The sign of t_sphere − t_other for a sphere's root (`root` −1: t1 = U − √V, +1: t2 = U + √V, 0: the tangent
// root t0 = U; docs/contract.md §10) against a plane's or a triangle's t = num/den (den ≠ 0), or against another
// sphere's root. The sphere's relation must not be miss.
[[nodiscard]] int compare_sphere_plane_t(const Ray& ray, const Sphere& sphere, int root, const Plane& plane);
[[nodiscard]] int compare_sphere_triangle_t(const Ray& ray, const Sphere& sphere, int root, const Triangle& triangle);
[[nodiscard]] int compare_sphere_sphere_t(const Ray& ray, const Sphere& a, int root_a, const Sphere& b, int root_b);

// The exact signs (−1, 0, +1) of a triangle's num = (a − o)·N and den = d·N, N = (b − a) × (c − a).
struct QuotientSigns {
  int num;
  int den;
};
[[nodiscard]] QuotientSigns triangle_quotient_signs(const Ray& ray, const Triangle& triangle);

}  // namespace raykernel::detail::exact
