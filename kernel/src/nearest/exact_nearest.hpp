// The exact stage of the nearest-hit module where kinds meet, and the reference of a scene: GMP rationals from
// the doubles' bits (core/rational_from_double.hpp). This header exposes no GMP type; exact_nearest.cpp is the
// only translation unit that sees them. Inputs must be valid (validated by the caller).
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

namespace raykernel::detail::exact {

// The sign of t_plane − t_triangle along `ray` for a plane and a triangle whose den are nonzero (t = num/den of
// docs/contract.md §1 and §6).
[[nodiscard]] int compare_plane_triangle_t(const Ray& ray, const Plane& plane, const Triangle& triangle);

// The exact signs (−1, 0, +1) of a triangle's num = (a − o)·N and den = d·N, N = (b − a) × (c − a).
struct QuotientSigns {
  int num;
  int den;
};
[[nodiscard]] QuotientSigns triangle_quotient_signs(const Ray& ray, const Triangle& triangle);

}  // namespace raykernel::detail::exact
