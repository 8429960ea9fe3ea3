// raykernel.SphereSet from Python (bind_sphere_set.cpp): the spheres of a scene, validated once, with a BVH from
// eight spheres on (raykernel::SphereSet), and the sphere forms of the scene queries of docs/contract.md §8 and §10,
// which nearest_hit, nearest_hit_exact, nearest_hit_batch, occluded, occluded_segment and their batches call when
// their scene is one. `exact` chooses the references (every sphere in rationals) over the certified queries.
#pragma once

#include "convert.hpp"

#include <raykernel/occlusion.hpp>
#include <raykernel/sphere.hpp>

#include <optional>
#include <string>

namespace raykernel::python {

[[nodiscard]] inline bool is_sphere_set(py::handle scene) { return py::isinstance<raykernel::SphereSet>(scene); }

// The nearest sphere within [t_min, t_max]: the SphereHit NamedTuple (sphere, t) or None; SphereHitArrays.
[[nodiscard]] py::object nearest_hit_spheres(py::handle ray, const raykernel::SphereSet& spheres, double t_min,
                                             double t_max, bool exact);
[[nodiscard]] py::object nearest_hit_spheres_batch(py::handle origins, py::handle directions,
                                                   const raykernel::SphereSet& spheres, py::handle t_min,
                                                   py::handle t_max, const std::string& path, const std::string& errors,
                                                   std::optional<unsigned> threads);

// Any-hit within the interval, and on the open segment p → q (no validation: the callers' batches validate).
[[nodiscard]] bool occluded_spheres(const Ray& ray, const RayInterval& interval, const raykernel::SphereSet& spheres,
                                    bool exact);
[[nodiscard]] bool occluded_segment_spheres(const Vec3& p, const Vec3& q, const raykernel::SphereSet& spheres,
                                            bool exact);

}  // namespace raykernel::python
