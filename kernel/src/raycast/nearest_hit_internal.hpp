// The parts of nearest_hit that tests drive directly: a plane the ray hits with its cascade state, and the
// certified order of two such planes' t.
#pragma once

#include "certified/ray_plane_stages.hpp"
#include "certified/sign.hpp"

#include <raykernel/raykernel.hpp>

#include <cstddef>

namespace raykernel::detail {

// A plane whose relation to the ray is hit, with the exact signs of its num and den (den ≠ 0; num is zero
// or has den's sign) and the cascade state that decided them.
struct HitCandidate {
  HitCandidate(std::size_t plane_index, const Ray& ray, const Plane& plane) noexcept
      : index(plane_index), stages(ray, plane) {}

  std::size_t index;
  Sign num_sign = Sign::uncertain;
  Sign den_sign = Sign::uncertain;
  Stage relation_stage = Stage::exact;  // the stage that certified the two signs
  RayPlaneStages stages;
};

// The sign of t_a − t_b (−1, 0, +1) and the cheapest stage that certified it.
struct DistanceOrder {
  int sign;
  Stage stage;
};

// The exact order of the t of two hit candidates along the same ray: t = 0 (num = 0) first; identical
// planes tie; otherwise sign(Δ)·sign(den_a)·sign(den_b) with Δ = num_a·den_b − num_b·den_a decided by
// compare_quotients_filter, compare_quotients_compensated, compare_quotients_expansion, and the exact
// stage (certified/compare_quotients.hpp). Computes the stages 2 and 3 of either candidate on demand.
[[nodiscard]] DistanceOrder compare_hit_distances(HitCandidate& a, HitCandidate& b);

}  // namespace raykernel::detail
