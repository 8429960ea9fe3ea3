// The exact stage of the interval and segment queries (docs/contract.md §8): GMP rationals from the doubles' bits
// (core/rational_from_double.hpp). This header exposes no GMP type; exact_occlusion.cpp is the only translation
// unit that sees them. Inputs must be valid (validated by the caller).
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

#include <array>

namespace raykernel::detail::exact {

// The sign of t − b for the exact t = num/den of docs/contract.md §6 of `ray` against a triangle whose den is
// nonzero, and a double b: sign(num − b·den)·sign(den), in rationals.
[[nodiscard]] int compare_triangle_t_with(const Ray& ray, const Triangle& triangle, double b);

// The signs of the x, y, z components of the owned rule's tie-break vector (q − p) × (v − u) of the directed
// edge u → v for the segment from p to q (its exact direction d = q − p), in rationals.
[[nodiscard]] std::array<int, 3> segment_tie_break_signs(const Vec3& p, const Vec3& q, const Vec3& u, const Vec3& v);

// The reference of docs/contract.md §8's segment: the §6 values of the line from p along the exact d = q − p
// (ray_triangle_formula.hpp in rationals, d as differences), classified under `rule`, and 0 < num/den < 1 as
// rationals.
[[nodiscard]] bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Triangle& triangle, TriangleRule rule);

}  // namespace raykernel::detail::exact
