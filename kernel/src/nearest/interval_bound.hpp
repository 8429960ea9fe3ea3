// A ray's interval bound as a quotient candidate (docs/contract.md §8): the double b as t = b/1, so that a hit's
// exact t = num/den is ordered against it by the nearest-hit module's own certified comparison
// (nearest_candidates.hpp, compare_candidates), stage by stage — never by a rounded t:
//
//     sign(t − b) = sign(num·1 − b·den)·sign(den)·sign(1)
//
//   stage 1  compare_quotients_filter on the hit's stage-1 enclosures and {b, 0}, {1, 0} (exact enclosures: radius 0)
//   stage 2  compare_quotients_compensated on its stage-2 enclosures and {b, 0, 0}, {1, 0, 0}
//   stage 3  compare_quotients_expansion on its expansions and the one-component expansions {b}, {1}
//   stage 4  exact_order: rationals (exact::compare_triangle_t_with, occlusion/exact_occlusion.hpp; for a plane
//            exact::compare_plane_t_with, nearest/exact_nearest.hpp)
//
// Each stage is proved for any enclosures (resp. expansions) of the four values (compare_quotients.hpp:
// proofs/compare/CompareQuotients.v, `compare_quotients_filter_sound`, `compare_quotients_compensated_enclosure`;
// proofs/core/Expansions.v, `compare_quotients_expansion_sound`); a double with radius 0 is an enclosure of
// itself. A bound b = 0 has num_sign zero: the comparison's first step (t = 0 first) orders it without arithmetic.
#pragma once

#include "core/enclosure.hpp"
#include "core/expansion.hpp"
#include "core/sign.hpp"
#include "nearest/compare_quotients.hpp"
#include "nearest/exact_nearest.hpp"
#include "nearest/nearest_candidates.hpp"
#include "nearest/plane_candidate.hpp"
#include "nearest/triangle_candidate.hpp"
#include "occlusion/exact_occlusion.hpp"

#include <raykernel/interval.hpp>

#include <cstddef>
#include <optional>

namespace raykernel::detail {

class BoundQuotient {
 public:
  // b ≥ 0 finite (a valid interval's t_min, or its t_max when finite).
  explicit BoundQuotient(double b) noexcept : b_(b) {
    num_sign = b == 0 ? Sign::zero : Sign::positive;
    expansions_.exact = true;
    expansions_.num.component[0] = b;
    expansions_.num.size = 1;
    expansions_.den.component[0] = 1;
    expansions_.den.size = 1;
  }

  Sign num_sign;
  Sign den_sign = Sign::positive;

  [[nodiscard]] double value() const noexcept { return b_; }
  [[nodiscard]] RoundedEnclosure num_filter() const noexcept { return {b_, 0}; }
  [[nodiscard]] RoundedEnclosure den_filter() const noexcept { return {1, 0}; }
  [[nodiscard]] Enclosure num_compensated() const noexcept { return {b_, 0, 0}; }
  [[nodiscard]] Enclosure den_compensated() const noexcept { return {1, 0, 0}; }
  struct Expansions {
    bool exact;
    Expansion<16> num, den;  // one component each (the capacity of the triangle candidates' short expansions)
  };
  [[nodiscard]] const Expansions& expansions() const noexcept { return expansions_; }

 private:
  double b_;
  Expansions expansions_;
};

[[nodiscard]] inline int exact_order(const Ray& ray, const TriangleCandidate& a, const BoundQuotient& b) {
  return exact::compare_triangle_t_with(ray, *a.source, b.value());
}
[[nodiscard]] inline int exact_order(const Ray& ray, const HitCandidate& a, const BoundQuotient& b) {
  return exact::compare_plane_t_with(ray, *a.plane, b.value());
}

// Whether a hit candidate's exact t lies in the valid interval [t_min, t_max]: t ≥ t_min is asked only when
// t_min > 0 (a hit has t ≥ 0), t ≤ t_max only when t_max is finite.
template <class Candidate>
[[nodiscard]] inline bool within_interval(const Ray& ray, Candidate& c, const RayInterval& interval) noexcept {
  if (interval.t_min > 0) {
    BoundQuotient lower(interval.t_min);
    if (compare_candidates(ray, c, lower).sign < 0) return false;
  }
  if (interval.t_max < std::numeric_limits<double>::infinity()) {
    BoundQuotient upper(interval.t_max);
    if (compare_candidates(ray, c, upper).sign > 0) return false;
  }
  return true;
}

// The same for one plane or triangle on its own (the single-primitive queries of docs/contract.md §8: plane_api.cpp,
// triangle_api.cpp): whether the ray hits it with its exact t in the valid `interval` — for a plane, RN(t) then,
// rounded by the same candidate. Classified by the nearest-hit module's candidates, so the hit and its t against
// the bounds are decided as in every scene.
[[nodiscard]] std::optional<double> hit_t_within_interval(const Ray& ray, const RayInterval& interval,
                                                          const Plane& plane);
[[nodiscard]] bool hits_within_interval(const Ray& ray, const RayInterval& interval, const Triangle& triangle,
                                        TriangleRule rule);
// The exact references: rationals (exact::compare_plane_t_with, exact::compare_triangle_t_with) for a hit's t.
[[nodiscard]] bool exact_t_within_interval(const Ray& ray, const RayInterval& interval, const Plane& plane);
[[nodiscard]] bool exact_t_within_interval(const Ray& ray, const RayInterval& interval, const Triangle& triangle);

}  // namespace raykernel::detail
