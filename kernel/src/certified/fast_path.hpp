// The fast path of the certified cascade: stage 1 and the first level of stage 2 for both signs, and
// round_quotient on the stage-2 enclosures for t — on uniformly random queries, every query. Written once
// for V = double (`intersect`) and V = Lanes8 (the batch API, eight queries per step); branch-free either
// way. When a sign is still uncertain, or t needs the second level of stage 2, the caller continues
// (FastQuery::refined_answer, then the full cascade in intersect_certified.cpp).
//
// Every operation is the one the full cascade performs for the same query, in the same order: the same
// stage-1 values, the same stage-2 enclosures, the same round_quotient decisions. The proofs model it for
// one query (the lanes of Lanes8 perform the same IEEE operations, lanes.hpp):
//   answer:          proofs/Cascade.v, `fast_answer_correct`
//   refined_answer:  proofs/Cascade.v, `refined_answer_correct`
//   intersect's use: proofs/Cascade.v, `intersect_fast_correct`
//
// No validation is needed before it: a certified sign implies valid input. A NaN or infinite component
// makes some stage-1 product non-finite (x·0 is NaN for infinite x), hence the magnitude m non-finite, and
// with it the filter's bound and the stage-2 radius (K·m + U): every certifying comparison is then false.
// A zero direction or normal makes every product of d·n exactly 0, so neither stage certifies a nonzero
// sign of den; and neither certifies zero (`exactly_zero` is false here): zeros are the full cascade's.
// In the model (no inf or NaN): proofs/Cascade.v, `fast_path_den_valid` (a den sign certified by stage 1
// or either level of stage 2 implies d ≠ 0 and n ≠ 0); the finiteness half: proofs/README.md.
#pragma once

#include "certified/dot3_compensated.hpp"
#include "certified/dot3_filter.hpp"
#include "certified/eft.hpp"
#include "certified/enclosure.hpp"
#include "certified/error_bounds.hpp"
#include "certified/lanes.hpp"
#include "certified/round_quotient.hpp"
#include "certified/sign.hpp"

#include <raykernel/raykernel.hpp>

#include <type_traits>

namespace raykernel::detail {

// The fast path's answer, per query (V = double) or per lane (V = Lanes8).
template <class V>
struct FastAnswerT {
  V t;
  MaskOf<V> behind;                   // the relation is behind (else hit), where relation_certain
  MaskOf<V> relation_by_compensated;  // the filter left a sign to the first level of stage 2
  MaskOf<V> relation_certain;         // both signs certified nonzero (so the input is valid)
  MaskOf<V> t_certain;                // t = RN(num/den) certified by round_quotient
};
using FastAnswer = FastAnswerT<double>;

// One query's (or eight queries') stage-1 values, kept for the later stages.
template <class V>
class FastQueryT {
 public:
  [[gnu::always_inline]] FastQueryT(const V o[3], const V d[3], const V p[3], const V n[3]) noexcept {
    for (int i = 0; i < 3; ++i) {
      const DD<V> s = two_diff(p[i], o[i]);  // s.hi = p_i ⊖ o_i, s.hi + s.lo = p_i − o_i
      diff_[i] = s.hi;
      diff_low_part_[i] = s.lo;
      d_[i] = d[i];
      n_[i] = n[i];
    }
    den1_ = dot3_rounded(d_, n_);
    num1_ = dot3_rounded(diff_, n_);
  }

  // Stage 1 and the first level of stage 2 for the signs, round_quotient on the first level for t.
  [[nodiscard]] [[gnu::always_inline]] FastAnswerT<V> answer() const noexcept {
    const V exact_low_part[3] = {V{}, V{}, V{}};
    const IntegerOf<V> den_filter = dot3_filter_lanes(den1_, bounds::filter_den_relative);
    const IntegerOf<V> num_filter = dot3_filter_lanes(num1_, bounds::filter_num_relative);
    const EnclosureT<V> den2 = compensated_dot3(d_, exact_low_part, n_, den1_);
    const EnclosureT<V> num2 = compensated_dot3(diff_, diff_low_part_, n_, num1_);
    const IntegerOf<V> den_sign = first_certain_lanes(den_filter, enclosure_sign_lanes(den2));
    const IntegerOf<V> num_sign = first_certain_lanes(num_filter, enclosure_sign_lanes(num2));
    const QuotientRoundingT<V> t = round_quotient_decision(num2, den2);
    return {t.t,
            num_sign * den_sign < 0,  // ±1 each when certain
            mask_not(both(den_filter != uncertain_lane, num_filter != uncertain_lane)),
            both(den_sign != uncertain_lane, num_sign != uncertain_lane),
            t.certain};
  }

  // The scalar path's finer steps (V = double only).
  struct FilterSigns {
    Sign den, num;
    [[nodiscard]] bool decided() const noexcept { return (den != Sign::uncertain) & (num != Sign::uncertain); }
    [[nodiscard]] Relation relation() const noexcept {
      return static_cast<int>(num) * static_cast<int>(den) < 0 ? Relation::behind : Relation::hit;
    }
  };
  [[nodiscard]] [[gnu::always_inline]] FilterSigns filter_signs() const noexcept
    requires std::is_same_v<V, double>
  {
    return {dot3_filter(den1_, bounds::filter_den_relative, false), dot3_filter(num1_, bounds::filter_num_relative, false)};
  }

  // t from the first level of stage 2, when the filter decided the relation.
  [[nodiscard]] [[gnu::always_inline]] QuotientRounding compensated_t() const noexcept
    requires std::is_same_v<V, double>
  {
    constexpr double exact_low_part[3] = {0, 0, 0};
    return round_quotient_decision(compensated_dot3(diff_, diff_low_part_, n_, num1_),
                                   compensated_dot3(d_, exact_low_part, n_, den1_));
  }

  // The second level of stage 2 for both signs and t, for near-degenerate queries. When the filter is
  // uncertain about a value V, |V| ≤ B ≈ 3u·m, so the first level's radius 2^-101·m is at least 2^-49.6·|V|
  // and round_quotient on it cannot succeed: near-degenerate queries come here directly.
  [[nodiscard]] [[gnu::always_inline]] FastAnswer refined_answer() const noexcept
    requires std::is_same_v<V, double>
  {
    constexpr double exact_low_part[3] = {0, 0, 0};
    const Enclosure den = compensated_dot3_refined(d_, exact_low_part, n_, den1_);
    const Enclosure num = compensated_dot3_refined(diff_, diff_low_part_, n_, num1_);
    const std::int64_t den_sign = enclosure_sign_lanes(den);
    const std::int64_t num_sign = enclosure_sign_lanes(num);
    const QuotientRounding t = round_quotient_decision(num, den);
    return {t.t, num_sign * den_sign < 0, true,
            both(den_sign != uncertain_lane, num_sign != uncertain_lane), t.certain};
  }

 private:
  V d_[3], n_[3], diff_[3], diff_low_part_[3];
  Dot3RoundedT<V> den1_, num1_;
};
using FastQuery = FastQueryT<double>;

}  // namespace raykernel::detail
