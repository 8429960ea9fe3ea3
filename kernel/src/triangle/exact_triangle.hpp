// The exact stage of the ray–triangle query (docs/contract.md §6): every value of ray_triangle_formula.hpp in
// GMP rationals, every rounding by MPFR. `intersect_exact` (the reference) and the last stage of the certified
// cascade. This header exposes no GMP type; exact_triangle.cpp is the only translation unit that sees them.
// All functions assume valid input (validated by the caller).
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

#include <array>

namespace raykernel::detail::exact {

[[nodiscard]] TriangleIntersection intersect_triangle(const Ray& ray, const Triangle& triangle,
                                                      const TriangleOptions& options);
[[nodiscard]] ExactTriangleIntersection intersect_triangle_rational(const Ray& ray, const Triangle& triangle,
                                                                    TriangleRule rule);

// The relation, location and owned flag, every sign exact.
[[nodiscard]] TriangleClassification classify_triangle(const Ray& ray, const Triangle& triangle, TriangleRule rule);

// RN(num/den) and RN(π_k/den) for den ≠ 0, each only where asked for (NaN elsewhere).
struct TriangleRoundings {
  double t;
  Barycentric barycentric;
};
[[nodiscard]] TriangleRoundings round_triangle_quotients(const Ray& ray, const Triangle& triangle, bool t,
                                                         bool barycentric);

}  // namespace raykernel::detail::exact
