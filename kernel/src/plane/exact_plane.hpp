// The exact stage: CGAL's exact rationals for num and den, MPFR for the rounding of t. Used by
// `intersect_exact` (the reference) and as the last stage of `intersect`. This header exposes no CGAL or
// GMP type; exact_rational.cpp is the only translation unit that includes CGAL.
#pragma once

#include <raykernel/raykernel.hpp>

namespace raykernel::detail::exact {

// Both assume valid input (validated by the caller).
[[nodiscard]] Intersection intersect(const Ray& ray, const Plane& plane);
[[nodiscard]] ExactIntersection intersect_rational(const Ray& ray, const Plane& plane);

}  // namespace raykernel::detail::exact
