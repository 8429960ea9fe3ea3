// raykernel/nearest_hit.hpp: the first plane a ray meets, decided exactly (docs/contract.md §4).
//
// Ray casting's inner loop (docs/ray-casting.md §1.1, "for every object: update the pixel if the object is nearest so far")
// chooses, among the planes a ray hits, the one with the smallest t. `nearest_hit` makes that choice
// exactly for the doubles given: the winner is the plane with the smallest exact t = num/den among those
// whose relation is hit (t ≥ 0; parallel, in-plane and behind planes never win), ties go to the smallest
// index, and the t returned is the winner's exact t rounded to nearest as in docs/contract.md §1.
//
// Comparing two t values is a certified predicate of its own, the sign of num_a·den_b − num_b·den_a:
// a binary64 filter, a double-double stage, exact expansions and exact rationals, each asked only when
// the cheaper ones cannot decide. Rounded t values are never compared, so two planes whose t differ by
// less than an ulp are ordered correctly, and planes whose exact t are equal (coincident planes, planes
// through the same point of the ray) tie.
#pragma once

#include <raykernel/raykernel.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace raykernel {

// The nearest plane hit: its index in the span, and its t (RN of the exact num/den, docs/contract.md §1).
struct NearestHit {
  std::size_t plane;
  double t;

  friend bool operator==(const NearestHit&, const NearestHit&) = default;
};

// The certified nearest hit (docs/contract.md §4), or nothing when no plane is hit (no planes, or every plane
// parallel, in-plane or behind). Throws invalid_input when the ray or a plane is invalid (a non-finite
// component, a zero direction or normal); what() names it, e.g. "plane 3: plane normal is the zero
// vector". Thread-safe; no global state. In a non-default floating-point environment (directed rounding,
// flush-to-zero) it answers through the exact path, like `intersect`.
[[nodiscard]] std::optional<NearestHit> nearest_hit(const Ray& ray, std::span<const Plane> planes);

// The reference: every num and den in exact rationals, the minimum t taken exactly, the winner's t rounded
// with MPFR. Slow (microseconds per plane) and obviously right. Throws invalid_input.
[[nodiscard]] std::optional<NearestHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes);

// The seed's loop in plain doubles: intersect_naive for each plane, keep the hit with the smallest rounded
// t (strictly smaller: ties to the smallest index). No validation, no guarantee: the baseline that
// `raykernel render --compare-naive` measures against the certified answer.
[[nodiscard]] std::optional<NearestHit> nearest_hit_naive(const Ray& ray, std::span<const Plane> planes) noexcept;

// `nearest_hit` plus which stages it needed: the slowest stage that decided a plane's relation, the
// slowest stage that ordered two t values, how many comparisons each stage decided, and the stage that
// rounded the winner's t.
struct TracedNearestHit {
  std::optional<NearestHit> hit;
  Stage relation_stage = Stage::filter;    // slowest over all planes
  Stage comparison_stage = Stage::filter;  // slowest over all comparisons (filter when there were none)
  Stage t_stage = Stage::filter;           // winner's t (its relation stage when t = 0 exactly; filter on a miss)
  std::array<std::uint32_t, stage_count> comparisons{};  // comparisons decided by each stage

  // The slowest stage this answer needed beyond the fast path, what `raykernel render --show-stages` marks:
  // the slower of relation_stage and comparison_stage, or t_stage if that is slower still. Rounding t
  // starts at the compensated stage (the filter only gives signs), so t_stage == compensated is the fast
  // path and counts as filter here; expansion and exact count.
  [[nodiscard]] Stage slowest_stage() const noexcept {
    Stage s = relation_stage;
    if (comparison_stage > s) s = comparison_stage;
    if (t_stage > Stage::compensated && t_stage > s) s = t_stage;
    return s;
  }
};
[[nodiscard]] TracedNearestHit nearest_hit_traced(const Ray& ray, std::span<const Plane> planes);

// The reason `plane` is invalid input (as `validate` words it), or nothing when it is valid.
[[nodiscard]] std::optional<std::string> validate_plane(const Plane& plane);
// The reason `ray` is invalid input, or nothing when it is valid.
[[nodiscard]] std::optional<std::string> validate_ray(const Ray& ray);

}  // namespace raykernel
