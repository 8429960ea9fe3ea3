// The ray–plane cascade beyond the fast path, for one valid query: its state (the terms of
// plane/ray_plane_stages.hpp, with stages 2 and 3 computed once asked for and then kept) and the
// decisions of ray_plane_cascade.cpp. `intersect`, `relation` and `nearest_hit` continue here with the
// queries their fast paths leave open; `intersect_traced` runs it from the start to report its stages.
#pragma once

#include "plane/ray_plane_stages.hpp"

#include <optional>
#include <utility>

namespace raykernel::detail {

class RayPlaneCascade {
 public:
  RayPlaneCascade(const Ray& ray, const Plane& plane) noexcept : RayPlaneCascade(ray, plane, ray_plane_terms(ray, plane)) {}
  RayPlaneCascade(const Ray& ray, const Plane& plane, const RayPlaneTerms& terms) noexcept
      : ray_(ray), plane_(plane), q_(terms) {}

  [[nodiscard]] const Ray& ray() const noexcept { return ray_; }
  [[nodiscard]] const Plane& plane() const noexcept { return plane_; }
  [[nodiscard]] const RayPlaneTerms& terms() const noexcept { return q_; }

  // Stage 1, with the one way it certifies zero: every term has a zero factor, so the exact sum is 0
  // whatever the rounding.
  [[nodiscard]] Sign den_filter() const noexcept {
    const bool zero = (q_.d[0] == 0 || q_.n[0] == 0) && (q_.d[1] == 0 || q_.n[1] == 0) && (q_.d[2] == 0 || q_.n[2] == 0);
    return dot3_filter(q_.den, bounds::filter_den_relative, zero);
  }
  [[nodiscard]] Sign num_filter() const noexcept {
    // p_i ⊖ o_i is 0 exactly when p_i = o_i (gradual underflow): then the term's exact value is 0.
    const bool zero = (q_.diff[0] == 0 || q_.n[0] == 0) && (q_.diff[1] == 0 || q_.n[1] == 0) &&
                      (q_.diff[2] == 0 || q_.n[2] == 0);
    return dot3_filter(q_.num, bounds::filter_num_relative, zero);
  }

  [[nodiscard]] const Enclosure& den_compensated() noexcept { return once(den2_, [&] { return detail::den_compensated(q_); }); }
  [[nodiscard]] const Enclosure& num_compensated() noexcept { return once(num2_, [&] { return detail::num_compensated(q_); }); }
  [[nodiscard]] const Enclosure& den_refined() noexcept { return once(den2r_, [&] { return detail::den_refined(q_); }); }
  [[nodiscard]] const Enclosure& num_refined() noexcept { return once(num2r_, [&] { return detail::num_refined(q_); }); }
  [[nodiscard]] const ExactExpansions& expansions() noexcept { return once(exp3_, [&] { return ray_plane_expansions(q_); }); }

 private:
  template <class T, class F>
  static const T& once(std::optional<T>& slot, F compute) noexcept {
    if (!slot) slot = compute();
    return *slot;
  }

  Ray ray_;
  Plane plane_;
  RayPlaneTerms q_;
  std::optional<Enclosure> den2_, num2_, den2r_, num2r_;
  std::optional<ExactExpansions> exp3_;
};

// The functions below are multiversioned (core/multiversion.hpp) and noexcept: an exception must not
// pass through a target_clones function, whose callers GCC 12 compiles without cleanups.

// The exact signs of num and den, and the stage that certified the later of the two.
struct CertifiedSigns {
  Sign num;  // never `uncertain`
  Sign den;  // never `uncertain`
  Stage stage;
};

// Stages 1–3 of the relation: the signs of num and den, each stage asked only for the signs the cheaper
// ones left uncertain, then the exact stage (plane/exact_plane.hpp) for both when either is left uncertain
// (stage 3 not exact: a TwoProduct underflowed or a value overflowed; or its checked sign uncertain).
// Each sign escalated by core/escalation.hpp's policy.
//   Certified by: proofs/plane/PlaneCascade.v, `cascade_signs_correct` (stages 1 and 2); proofs/core/Expansions.v,
//   `certified_signs_expansion_sound` (stage 3);
//   each sign escalated as core/escalation.hpp: proofs/plane/PlaneCascadeTwins.v, `certified_signs_b_escalate`, `certified_signs_twin_sound`.
[[nodiscard]] CertifiedSigns certified_signs(RayPlaneCascade& query) noexcept;

// t = RN(num/den) for num ≠ 0 ≠ den (hit or behind): round_quotient on the stage-2 enclosures, on the
// second level's, on the stage-3 tail enclosures, then the exact stage. Returns t and the stage that
// rounded it.
//   Certified by: proofs/plane/PlaneCascade.v, `cascade_quotient_correct`, `expansion_t_correct`.
[[nodiscard]] std::pair<double, Stage> certified_quotient(RayPlaneCascade& query) noexcept;

// The whole cascade for a valid query (relation, then t), with the stages that decided them.
[[nodiscard]] TracedIntersection intersect_cascade(RayPlaneCascade& query) noexcept;

}  // namespace raykernel::detail
