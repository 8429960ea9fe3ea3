// The parts of nearest_hit that tests and the proofs' differential runner drive directly: a plane the ray hits,
// with what decided it (nearest/plane_candidate.hpp), and the certified order of two such planes' t.
#pragma once

#include "nearest/nearest_candidates.hpp"
#include "nearest/nearest_screen.hpp"
#include "nearest/plane_candidate.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

namespace raykernel::detail {

// The exact order of the t of two plane hits along the same ray: t = 0 (num = 0) first; otherwise
// sign(Δ)·sign(den_a)·sign(den_b) with Δ = num_a·den_b − num_b·den_a decided by compare_quotients_filter,
// compare_quotients_compensated, compare_quotients_expansion, and the exact stage (nearest/compare_quotients.hpp),
// each asked only when the cheaper ones cannot decide: compare_candidates (nearest/nearest_candidates.hpp) on
// two planes, as nearest_hit compares them.
[[nodiscard]] DistanceOrder compare_hit_distances(HitCandidate& a, HitCandidate& b) noexcept;

// nearest_hit_traced with a given screen (nearest/nearest_screen.hpp; null: the scalar loop) whatever the
// set's size, so that tests run every screen this CPU can run, and the scalar loop, on the same sets.
// Throws invalid_input for an invalid ray.
[[nodiscard]] TracedNearestHit nearest_traced_with_screen(const Ray& ray, const PlaneSet& set,
                                                          nearest_kernel::ScreenFunction screen);
// The screen nearest_hit uses on this CPU.
[[nodiscard]] nearest_kernel::ScreenFunction chosen_screen() noexcept;

}  // namespace raykernel::detail
