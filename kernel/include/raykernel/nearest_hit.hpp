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
// through the same point of the ray) tie. The same nearest-hit module answers for meshes
// (raykernel/mesh_queries.hpp) and for scenes of planes and a mesh (raykernel/nearest_scene.hpp).
#pragma once

#include <raykernel/interval.hpp>
#include <raykernel/raykernel.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace raykernel {
namespace detail {
struct PlaneSetColumns;
}

// The nearest plane hit: its index in the span, and its t (RN of the exact num/den, docs/contract.md §1).
struct NearestHit {
  std::size_t plane;
  double t;

  friend bool operator==(const NearestHit&, const NearestHit&) = default;
};

// A set of planes prepared for many nearest-hit queries: validated once, and each plane that coincides
// exactly with an earlier one (the same geometric plane: parallel normals and a common point, decided in
// exact arithmetic; identical bits included) set aside once, since for every ray it has the same t as the
// earlier plane and so never wins (ties go to the smallest index). Building costs O(k log k) exact
// operations for k planes; queries then cost a binary64 filter per plane in the common case.
class PlaneSet {
 public:
  // Throws invalid_input naming the first invalid plane ("plane 3: plane normal is the zero vector").
  explicit PlaneSet(std::span<const Plane> planes);

  [[nodiscard]] std::size_t size() const noexcept { return planes_.size(); }
  [[nodiscard]] std::span<const Plane> planes() const noexcept { return planes_; }
  // The indices of the planes that can win, ascending: each plane not coinciding with an earlier one.
  [[nodiscard]] std::span<const std::uint32_t> candidates() const noexcept { return candidates_; }

 private:
  friend struct detail::PlaneSetColumns;
  std::vector<Plane> planes_;
  std::vector<std::uint32_t> candidates_;
  std::vector<double> columns_;  // the candidates as structure of arrays (kernel/src/nearest/nearest_screen.hpp)
};

// The certified nearest hit (docs/contract.md §4), or nothing when no plane is hit (no planes, or every
// plane parallel, in-plane or behind). Throws invalid_input when the ray is invalid (a non-finite
// component, a zero direction). Thread-safe; right in any floating-point environment (as `intersect`).
[[nodiscard]] std::optional<NearestHit> nearest_hit(const Ray& ray, const PlaneSet& planes);

// The same for planes given as a span: prepares a PlaneSet for the call (so it also throws invalid_input
// for an invalid plane: "plane 3: plane normal is the zero vector"). For many rays, prepare the set once.
[[nodiscard]] std::optional<NearestHit> nearest_hit(const Ray& ray, std::span<const Plane> planes);

// The reference: every num and den in exact rationals, the minimum t taken exactly, the winner's t rounded
// with MPFR. Slow (microseconds per plane) and obviously right. Throws invalid_input.
[[nodiscard]] std::optional<NearestHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes);

// docs/contract.md §8 on a plane set: the nearest hit among the planes whose exact t lies in `interval`
// ([t_min, t_max], closed, compared exactly: the rational t against the doubles, never a rounded t), ties to the
// smallest index, t rounded as `intersect` rounds it. Throws invalid_input for an invalid ray or interval. The
// whole ray [0, +inf] is nearest_hit(ray, planes); another interval is searched plane by plane (the screen that
// sets planes aside by comparison with one the ray hits holds only for the whole ray). The reference:
// nearest_hit_exact with an interval (every t in rationals).
[[nodiscard]] std::optional<NearestHit> nearest_hit(const Ray& ray, const RayInterval& interval, const PlaneSet& planes);
[[nodiscard]] std::optional<NearestHit> nearest_hit_exact(const Ray& ray, const RayInterval& interval,
                                                          std::span<const Plane> planes);

// The seed's loop in plain doubles: intersect_naive for each plane, keep the hit with the smallest rounded
// t (strictly smaller: ties to the smallest index). No validation, no guarantee: the baseline that
// `raykernel render --compare-naive` measures against the certified answer.
[[nodiscard]] std::optional<NearestHit> nearest_hit_naive(const Ray& ray, std::span<const Plane> planes) noexcept;

// `nearest_hit` plus which stages it needed: the slowest stage that decided a plane's relation, the
// slowest stage that ordered two t values, how many comparisons each stage decided, and the stage that
// rounded the winner's t. Every hit after the first counts one comparison: with the best so far, or, in a
// set of 8 candidate planes or more, for a hit that the vectorized filter finds certainly farther than the
// t of a reference plane the ray hits, that filter comparison. So the total is that of one comparison per
// hit with the best so far; the stages are those of the comparisons actually made.
struct TracedNearestHit {
  std::optional<NearestHit> hit;
  Stage relation_stage = Stage::filter;    // slowest over all planes
  Stage comparison_stage = Stage::filter;  // slowest over all comparisons (filter when there were none)
  Stage t_stage = Stage::filter;           // winner's t (its relation stage when t = 0 exactly; filter on a miss)
  std::array<std::uint32_t, stage_count> comparisons{};  // comparisons decided by each stage
};
[[nodiscard]] TracedNearestHit nearest_hit_traced(const Ray& ray, const PlaneSet& planes);
[[nodiscard]] TracedNearestHit nearest_hit_traced(const Ray& ray, std::span<const Plane> planes);

}  // namespace raykernel
