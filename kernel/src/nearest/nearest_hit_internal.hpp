// The parts of nearest_hit that tests drive directly: a plane the ray hits, with what decided it, and the
// certified order of two such planes' t.
#pragma once

#include "core/dot3_filter.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "core/sign.hpp"
#include "nearest/nearest_screen.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

#include <cstddef>
#include <optional>

namespace raykernel::detail {

// A plane whose relation to the ray is hit: the exact signs of its num and den (den ≠ 0; num is zero or
// has den's sign), the stage-1 values every comparison starts from, and the rest of its cascade, built
// the first time a comparison needs a later stage.
struct HitCandidate {
  HitCandidate(std::size_t plane_index, const Ray& ray, const Plane& plane, const Dot3Rounded& den_stage1,
               const Dot3Rounded& num_stage1) noexcept
      : index(plane_index), ray(&ray), plane(&plane), den(den_stage1), num(num_stage1) {}

  // The cascade of this plane (stage 1 recomputed once, on the rare comparisons the filter cannot decide).
  [[nodiscard]] RayPlaneCascade& cascade() noexcept {
    if (!full) full.emplace(*ray, *plane);
    return *full;
  }

  std::size_t index;
  const Ray* ray;
  const Plane* plane;
  Dot3Rounded den, num;  // stage 1
  Sign num_sign = Sign::uncertain;
  Sign den_sign = Sign::uncertain;
  Stage relation_stage = Stage::filter;  // the stage that certified the two signs
  std::optional<RayPlaneCascade> full;
};

// The sign of t_a − t_b (−1, 0, +1) and the cheapest stage that certified it.
struct DistanceOrder {
  int sign;
  Stage stage;
};

// The exact order of the t of two hit candidates along the same ray: t = 0 (num = 0) first; otherwise
// sign(Δ)·sign(den_a)·sign(den_b) with Δ = num_a·den_b − num_b·den_a decided by compare_quotients_filter,
// compare_quotients_compensated, compare_quotients_expansion, and the exact stage
// (nearest/compare_quotients.hpp), each asked only when the cheaper ones cannot decide.
[[nodiscard]] DistanceOrder compare_hit_distances(HitCandidate& a, HitCandidate& b) noexcept;

// nearest_hit_traced with a given screen (nearest/nearest_screen.hpp; null: the scalar loop) whatever the
// set's size, so that tests run every screen this CPU can run, and the scalar loop, on the same sets.
// Throws invalid_input for an invalid ray.
[[nodiscard]] TracedNearestHit nearest_traced_with_screen(const Ray& ray, const PlaneSet& set,
                                                          nearest_kernel::ScreenFunction screen);
// The screen nearest_hit uses on this CPU.
[[nodiscard]] nearest_kernel::ScreenFunction chosen_screen() noexcept;

}  // namespace raykernel::detail
