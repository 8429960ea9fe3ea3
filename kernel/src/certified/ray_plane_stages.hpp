// The per-query state of the certified cascade, so that callers other than `intersect` can reuse what a
// query has already computed. `nearest_hit` keeps the stages of the best plane so far and of the candidate,
// and its comparison of two t values (certified/compare_quotients.hpp) consumes the same stage-1 values,
// stage-2 enclosures and stage-3 expansions that decided each plane's relation.
//
// Stage 1 is evaluated when the object is built; stages 2 and 3 on first use, and then kept. The arithmetic
// of every stage is the one in dot3_filter.hpp, dot3_compensated.hpp and expansion.hpp, called with the
// same arguments in the same order as before this state was factored out of intersect_certified.cpp.
#pragma once

#include "certified/dot3_compensated.hpp"
#include "certified/dot3_filter.hpp"
#include "certified/eft.hpp"
#include "certified/enclosure.hpp"
#include "certified/error_bounds.hpp"
#include "certified/expansion.hpp"
#include "certified/sign.hpp"

#include <raykernel/raykernel.hpp>

#include <optional>
#include <utility>

namespace raykernel::detail {

// The inputs of the two dot products, as the stages consume them.
struct QueryTerms {
  double d[3], n[3], p[3], o[3];
  double diff[3];  // p_i ⊖ o_i, the a_i of num
};

// The exact expansions of num and den (stage 3). num = Σ (δ_i + ε_i)·n_i with δ_i + ε_i = p_i − o_i
// exactly: each term is a 2-component expansion scaled by n_i (≤ 4 components), three of them ≤ 12.
struct ExactExpansions {
  Expansion<12> num;
  Expansion<6> den;
  bool exact;  // every TwoProduct was exact and nothing overflowed: num and den are the exact values
};

[[nodiscard]] inline ExactExpansions build_expansions(const QueryTerms& q) noexcept {
  ExpansionBuilder builder;
  Expansion<12> num;
  Expansion<6> den;
  {
    Expansion<2> product[3];
    for (int i = 0; i < 3; ++i) ExpansionBuilder::from_pair(builder.product(q.d[i], q.n[i]), product[i]);
    Expansion<4> partial;
    ExpansionBuilder::sum(product[0], product[1], partial);
    ExpansionBuilder::sum(partial, product[2], den);
  }
  {
    Expansion<4> term[3];
    for (int i = 0; i < 3; ++i) {
      Expansion<2> difference;
      ExpansionBuilder::from_pair(two_diff(q.p[i], q.o[i]), difference);
      builder.scale(difference, q.n[i], term[i]);
    }
    Expansion<8> partial;
    ExpansionBuilder::sum(term[0], term[1], partial);
    ExpansionBuilder::sum(partial, term[2], num);
  }
  builder.check_finite(num);
  builder.check_finite(den);
  return {num, den, builder.exact()};
}

// One ray–plane query inside the cascade: inputs, stage 1, and stages 2 and 3 once asked for.
class RayPlaneStages {
 public:
  RayPlaneStages(const Ray& ray, const Plane& plane) noexcept
      : ray_(ray),
        plane_(plane),
        q_{{ray.direction.x, ray.direction.y, ray.direction.z},
           {plane.normal.x, plane.normal.y, plane.normal.z},
           {plane.point.x, plane.point.y, plane.point.z},
           {ray.origin.x, ray.origin.y, ray.origin.z},
           {plane.point.x - ray.origin.x, plane.point.y - ray.origin.y, plane.point.z - ray.origin.z}},
        den1_(dot3_rounded(q_.d, q_.n)),
        num1_(dot3_rounded(q_.diff, q_.n)) {}

  [[nodiscard]] const Ray& ray() const noexcept { return ray_; }
  [[nodiscard]] const Plane& plane() const noexcept { return plane_; }
  [[nodiscard]] const QueryTerms& terms() const noexcept { return q_; }

  // Stage 1: the rounded dot products (values, products, magnitudes).
  [[nodiscard]] const Dot3Rounded& den_rounded() const noexcept { return den1_; }
  [[nodiscard]] const Dot3Rounded& num_rounded() const noexcept { return num1_; }

  // A term with a zero factor is exactly zero whatever the rounding: every term of den (num) has one.
  [[nodiscard]] bool den_trivially_zero() const noexcept {
    return (q_.d[0] == 0 || q_.n[0] == 0) && (q_.d[1] == 0 || q_.n[1] == 0) && (q_.d[2] == 0 || q_.n[2] == 0);
  }
  [[nodiscard]] bool num_trivially_zero() const noexcept {
    return (q_.p[0] == q_.o[0] || q_.n[0] == 0) && (q_.p[1] == q_.o[1] || q_.n[1] == 0) &&
           (q_.p[2] == q_.o[2] || q_.n[2] == 0);
  }

  // Stage 2: double-double enclosures of den and num, computed together on first use.
  [[nodiscard]] const Enclosure& den_compensated() noexcept {
    compute_compensated();
    return *den2_;
  }
  [[nodiscard]] const Enclosure& num_compensated() noexcept {
    compute_compensated();
    return *num2_;
  }
  [[nodiscard]] bool has_compensated() const noexcept { return den2_.has_value(); }

  // Stage 2, second level: the tighter enclosures of compensated_dot3_refined, on first use.
  [[nodiscard]] const Enclosure& den_refined() noexcept {
    compute_refined();
    return *den2r_;
  }
  [[nodiscard]] const Enclosure& num_refined() noexcept {
    compute_refined();
    return *num2r_;
  }

  // Stage 3: the exact expansions of num and den (use them only when `.exact`).
  [[nodiscard]] const ExactExpansions& expansions() noexcept {
    if (!exp3_) exp3_ = build_expansions(q_);
    return *exp3_;
  }

 private:
  // Both levels of stage 2 take the same arguments: den's exact inputs (no low parts), and num's rounded
  // differences with their exact TwoDiff errors.
  template <class Level>
  void compute_stage2(std::optional<Enclosure>& den, std::optional<Enclosure>& num, Level level) noexcept {
    if (den) return;
    constexpr double exact_low_part[3] = {0, 0, 0};
    double diff_low_part[3];
    for (int i = 0; i < 3; ++i) diff_low_part[i] = two_diff(q_.p[i], q_.o[i]).lo;
    den = level(q_.d, exact_low_part, q_.n, den1_);
    num = level(q_.diff, diff_low_part, q_.n, num1_);
  }
  void compute_compensated() noexcept {
    compute_stage2(den2_, num2_, [](const double* a, const double* alpha, const double* b, const Dot3Rounded& s1) {
      return compensated_dot3(a, alpha, b, s1);
    });
  }
  void compute_refined() noexcept {
    compute_stage2(den2r_, num2r_, [](const double* a, const double* alpha, const double* b, const Dot3Rounded& s1) {
      return compensated_dot3_refined(a, alpha, b, s1);
    });
  }

  Ray ray_;
  Plane plane_;
  QueryTerms q_;
  Dot3Rounded den1_, num1_;
  std::optional<Enclosure> den2_, num2_;
  std::optional<Enclosure> den2r_, num2r_;
  std::optional<ExactExpansions> exp3_;
};

// The exact signs of num and den, and the stage that certified the later of the two.
struct CertifiedSigns {
  Sign num;  // never `uncertain`
  Sign den;  // never `uncertain`
  Stage stage;
};

// Stages 1–3 of the relation: the signs of num and den, each stage asked only for the signs the cheaper
// ones left uncertain. Empty when stage 3 is needed but not exact (a TwoProduct underflowed or a value
// overflowed): then only the exact stage can decide.
[[nodiscard]] std::optional<CertifiedSigns> certified_signs(RayPlaneStages& query) noexcept;

// t = RN(num/den) for num ≠ 0 ≠ den (hit or behind): round_quotient on the stage-2 enclosures, then on the
// stage-3 tail enclosures, then the exact stage. Returns t and the stage that rounded it.
[[nodiscard]] std::pair<double, Stage> certified_quotient(RayPlaneStages& query);

}  // namespace raykernel::detail
