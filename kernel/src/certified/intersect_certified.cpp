// The certified ray–plane query: the cascade filter → compensated → expansion → exact.
//
// The relation needs the exact signs of den = d·n and num = (p − o)·n; each stage is asked only for the
// signs the cheaper ones left uncertain. t needs a correct rounding of num/den: round_quotient decides it
// from the compensated enclosures, then from the (near-exact) expansion enclosures, and the exact stage
// settles what is left (exact ties, values within ~2^-100 of a rounding boundary, extreme exponents).
//
// The file is compiled with -ffp-contract=off and without fast-math (kernel/CMakeLists.txt): the proofs
// model each + − × / as one correctly rounded operation and each std::fma as one rounding.
#include "certified/fp_requirements.hpp"
#include "certified/dot3_compensated.hpp"
#include "certified/dot3_filter.hpp"
#include "certified/enclosure.hpp"
#include "certified/error_bounds.hpp"
#include "certified/expansion.hpp"
#include "certified/intersect_certified.hpp"
#include "certified/round_quotient.hpp"
#include "exact/exact.hpp"
#include "ray_plane_formula.hpp"

#include <cmath>
#include <limits>
#include <optional>

namespace raykernel::detail {
namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

[[nodiscard]] int to_int(Sign s) noexcept { return static_cast<int>(s); }

// The inputs of the two dot products, as the stages consume them.
struct QueryTerms {
  double d[3], n[3], p[3], o[3];
  double diff[3];  // p_i ⊖ o_i, the a_i of num
};

// Stage 3: the exact expansions of num and den. num = Σ (δ_i + ε_i)·n_i with δ_i + ε_i = p_i − o_i exactly:
// each term is a 2-component expansion scaled by n_i (≤ 4 components), three of them ≤ 12. Returns the
// exact signs and the tail enclosures round_quotient needs, or exact = false when a TwoProduct underflowed
// or something overflowed (then only the exact stage can answer). Out of line: it is rarely needed, and
// its buffers would otherwise weigh on every query's stack frame.
struct ExpansionOutcome {
  bool exact;
  Sign den_sign, num_sign;
  Enclosure den, num;
};

[[gnu::noinline]] RAYKERNEL_MULTIVERSION ExpansionOutcome expansion_stage(const QueryTerms& q) noexcept {
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
  if (!builder.exact()) return {false, Sign::uncertain, Sign::uncertain, {}, {}};
  return {true, den.sign(), num.sign(), expansion_tail_enclosure(den), expansion_tail_enclosure(num)};
}

[[gnu::noinline, gnu::cold]] TracedIntersection exact_stage(const Ray& ray, const Plane& plane) {
  return {exact::intersect(ray, plane), Stage::exact, Stage::exact};
}

}  // namespace

// GCC and clang (≥ 14) build an FMA clone and a portable clone of this function and pick one when the
// program loads: std::fma is one instruction in the first and a correctly rounded libm call in the
// second, so both compute the same bits.
RAYKERNEL_MULTIVERSION
TracedIntersection intersect_certified_valid(const Ray& ray, const Plane& plane) {
  const QueryTerms q{
      {ray.direction.x, ray.direction.y, ray.direction.z},
      {plane.normal.x, plane.normal.y, plane.normal.z},
      {plane.point.x, plane.point.y, plane.point.z},
      {ray.origin.x, ray.origin.y, ray.origin.z},
      {plane.point.x - ray.origin.x, plane.point.y - ray.origin.y, plane.point.z - ray.origin.z},
  };

  // Stage 1: binary64 filter. A term with a zero factor is exactly zero whatever the rounding.
  const Dot3Rounded den1 = dot3_rounded(q.d, q.n);
  const Dot3Rounded num1 = dot3_rounded(q.diff, q.n);
  const bool den_trivially_zero =
      (q.d[0] == 0 || q.n[0] == 0) && (q.d[1] == 0 || q.n[1] == 0) && (q.d[2] == 0 || q.n[2] == 0);
  const bool num_trivially_zero =
      (q.p[0] == q.o[0] || q.n[0] == 0) && (q.p[1] == q.o[1] || q.n[1] == 0) && (q.p[2] == q.o[2] || q.n[2] == 0);
  Sign den_sign = dot3_filter(den1, bounds::filter_den_relative, den_trivially_zero);
  Sign num_sign = dot3_filter(num1, bounds::filter_num_relative, num_trivially_zero);
  Stage relation_stage = Stage::filter;

  // Stage 2, computed on demand and shared by the sign and the t decisions.
  std::optional<Enclosure> den2, num2;
  auto compensated = [&] {
    if (den2) return;
    constexpr double exact_low_part[3] = {0, 0, 0};
    double diff_low_part[3];
    for (int i = 0; i < 3; ++i) diff_low_part[i] = two_diff(q.p[i], q.o[i]).lo;
    den2 = compensated_dot3(q.d, exact_low_part, q.n, den1);
    num2 = compensated_dot3(q.diff, diff_low_part, q.n, num1);
  };
  // Stage 3, on demand.
  std::optional<ExpansionOutcome> exp3;
  auto expansions = [&]() -> const ExpansionOutcome& {
    if (!exp3) exp3 = expansion_stage(q);
    return *exp3;
  };

  if (!is_certain(den_sign) || !is_certain(num_sign)) {
    compensated();
    relation_stage = Stage::compensated;
    if (!is_certain(den_sign)) den_sign = enclosure_sign(*den2);
    if (!is_certain(num_sign)) num_sign = enclosure_sign(*num2);
  }
  if (!is_certain(den_sign) || !is_certain(num_sign)) {
    const ExpansionOutcome& e = expansions();
    if (!e.exact) return exact_stage(ray, plane);
    relation_stage = Stage::expansion;
    den_sign = e.den_sign;
    num_sign = e.num_sign;
  }

  const Relation relation = relation_from_signs(to_int(num_sign), to_int(den_sign));
  if (relation == Relation::parallel || relation == Relation::in_plane)
    return {{relation, not_a_number}, relation_stage, relation_stage};
  if (num_sign == Sign::zero) return {{Relation::hit, 0.0}, relation_stage, relation_stage};

  // t = RN(num/den), num ≠ 0 ≠ den.
  compensated();
  if (const std::optional<double> t = round_quotient(*num2, *den2))
    return {{relation, *t}, relation_stage, Stage::compensated};
  const ExpansionOutcome& e = expansions();
  if (e.exact) {
    if (const std::optional<double> t = round_quotient(e.num, e.den))
      return {{relation, *t}, relation_stage, Stage::expansion};
  }
  return {{relation, exact_stage(ray, plane).intersection.t}, relation_stage, Stage::exact};
}

}  // namespace raykernel::detail
