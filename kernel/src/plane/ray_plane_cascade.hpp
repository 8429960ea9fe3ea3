// The ray–plane cascade beyond the fast path, for one valid query: its state (the terms of
// plane/ray_plane_stages.hpp, with stages 2 and 3 computed once asked for and then kept) and the
// decisions of ray_plane_cascade.cpp. `intersect`, `relation` and `nearest_hit` continue here with the
// queries their fast paths leave open; `intersect_traced` runs it from the start to report its stages.
#pragma once

#include "core/on_first_use.hpp"
#include "plane/ray_plane_stages.hpp"

#include <array>
#include <utility>

namespace raykernel::detail {

class RayPlaneCascade {
 public:
  RayPlaneCascade(const Ray& ray, const Plane& plane) noexcept : RayPlaneCascade(ray, plane, ray_plane_terms(ray, plane)) {}
  RayPlaneCascade(const Ray& ray, const Plane& plane, const RayPlaneTerms& terms) noexcept
      : ray_(ray), plane_(plane), q_(terms) {}
  // For a query the one-query fast path (plane/ray_plane_stages.hpp, fast_answer) left open, once validated:
  // stage 1 and stage 2's first level as the fast path computed them (RayPlaneFastValues: RayPlanePair's
  // operations, the terms' and the scalar levels' bits), and the fast path's rounding of t from that level (the
  // same operation on the same bits) kept instead of repeated.
  // Inline: its caller is multiversioned (core/multiversion.hpp), and so is this code with it.
  [[gnu::always_inline]] RayPlaneCascade(const Ray& ray, const Plane& plane, const RayPlaneFastValues& fast_path_values,
                                         const QuotientRounding& fast_path_rounding) noexcept;

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

  // Stage 2, each level for den and num at once (RayPlanePair): den_compensated … num_refined of
  // plane/ray_plane_stages.hpp, bit for bit.
  [[nodiscard]] const Enclosure& den_compensated() noexcept { return compensated()[0]; }
  [[nodiscard]] const Enclosure& num_compensated() noexcept { return compensated()[1]; }
  [[nodiscard]] const Enclosure& den_refined() noexcept { return refined()[0]; }
  [[nodiscard]] const Enclosure& num_refined() noexcept { return refined()[1]; }
  [[nodiscard]] const ExactExpansions& expansions() noexcept {
    return expansions_.get(0, [&] { return ray_plane_expansions(q_); });
  }
  // round_quotient on the first level's enclosures (certified_quotient's first step), or the same rounding made
  // before the cascade was built (the fast path's, a nearest-hit candidate's: `keep_compensated_rounding`).
  [[nodiscard]] const QuotientRounding& compensated_rounding() noexcept {
    return rounding_.get(0, [&] { return round_quotient(num_compensated(), prepare_divisor(den_compensated())); });
  }
  void keep_compensated_rounding(const QuotientRounding& r) noexcept { static_cast<void>(rounding_.get(0, [&] { return r; })); }

 private:
  using EnclosurePair = std::array<Enclosure, 2>;  // {den, num}
  [[nodiscard]] static EnclosurePair lanes_of(const EnclosureT<Lanes2>& e) noexcept {
    return {enclosure_lane(e, 0), enclosure_lane(e, 1)};
  }
  [[nodiscard]] const EnclosurePair& compensated() noexcept {
    return levels_.get(0, [&] { return lanes_of(compensated_pair(ray_plane_pair(q_))); });
  }
  [[nodiscard]] const EnclosurePair& refined() noexcept {
    return levels_.get(1, [&] { return lanes_of(refined_pair(ray_plane_pair(q_))); });
  }

  Ray ray_;
  Plane plane_;
  RayPlaneTerms q_;
  OnFirstUse<EnclosurePair, 2> levels_;  // stage 2's first and second level
  OnFirstUse<QuotientRounding, 1> rounding_;
  OnFirstUse<ExactExpansions, 1> expansions_;
};

inline RayPlaneCascade::RayPlaneCascade(const Ray& ray, const Plane& plane, const RayPlaneFastValues& fast_path_values,
                                        const QuotientRounding& fast_path_rounding) noexcept
    : ray_(ray), plane_(plane) {
  RAYKERNEL_QUERY_ARRAYS(ray, plane);
  const RayPlaneFastValues& v = fast_path_values;
  for (int i = 0; i < 3; ++i) {
    q_.o[i] = o[i], q_.d[i] = d[i], q_.p[i] = p[i], q_.n[i] = n[i];
    q_.diff[i] = v.a[i][1];  // p_i ⊖ o_i
    q_.den.product[i] = v.stage1.product[i][0];
    q_.num.product[i] = v.stage1.product[i][1];
  }
  q_.den.value = v.stage1.value[0], q_.num.value = v.stage1.value[1];
  q_.den.magnitude = v.stage1.magnitude[0], q_.num.magnitude = v.stage1.magnitude[1];
  static_cast<void>(levels_.get(0, [&] { return lanes_of(v.compensated); }));
  keep_compensated_rounding(fast_path_rounding);
}

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
