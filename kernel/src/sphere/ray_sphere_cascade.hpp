// The certified ray–sphere cascade (docs/contract.md §10): the expansion stage (ray_sphere_stages.hpp) for the
// signs of C and D and for each root's rounding, the exact stage (exact_sphere.hpp) for whatever it leaves.
// Valid input, the default floating-point environment (the entry points in sphere_api.cpp see to both).
#pragma once

#include <raykernel/sphere.hpp>

namespace raykernel::detail {

[[nodiscard]] TracedSphereIntersection sphere_intersection_cascade(const Ray& ray, const Sphere& sphere);

struct TracedSphereClassification {
  SphereClassification classification;
  Stage stage;
};
[[nodiscard]] TracedSphereClassification sphere_relation_cascade(const Ray& ray, const Sphere& sphere);

}  // namespace raykernel::detail
