// The exact stage of the ray–sphere query (docs/contract.md §10): A, B, C, D of ray_sphere_formula.hpp in GMP
// rationals, each root rounded by MPFR. `intersect_exact` (the reference) and the last stage of the certified
// cascade. This header exposes no GMP type; exact_sphere.cpp is the only translation unit that sees them. All
// functions assume valid input (validated by the caller).
#pragma once

#include <raykernel/sphere.hpp>

namespace raykernel::detail::exact {

[[nodiscard]] SphereClassification classify_sphere(const Ray& ray, const Sphere& sphere);
[[nodiscard]] SphereIntersection intersect_sphere(const Ray& ray, const Sphere& sphere);
[[nodiscard]] ExactSphereIntersection intersect_sphere_rational(const Ray& ray, const Sphere& sphere);

// sign(t_k − m) for the root k (−1: t1 or t0, +1: t2 or t0) and the rational m = (x + y)/2 of two finite doubles,
// exactly (ray_sphere_formula.hpp, root_side_of on the exact q(m) and slope); D ≥ 0. The test oracle of
// both roundings.
[[nodiscard]] int root_side_of_midpoint(const Ray& ray, const Sphere& sphere, int root, double x, double y);

// Whether the sphere meets the open segment from p to q (ray_sphere_formula.hpp, segment_root_inside on the exact
// signs); p ≠ q.
[[nodiscard]] bool segment_meets_sphere(const Vec3& p, const Vec3& q, const Sphere& sphere);

}  // namespace raykernel::detail::exact
