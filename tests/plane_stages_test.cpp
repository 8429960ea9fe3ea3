// Each certified stage on its own, against exact rational arithmetic, over every kind of hard query:
// a stage may say `uncertain`, but what it certifies must be exactly right, and each enclosure must contain
// the exact value. The cascade test (plane_properties_test.cpp) checks the composition; these check the parts,
// so that a wrong constant fails here even when a later stage would have masked it.
#include "support/oracle.hpp"

#include "core/dot3_compensated.hpp"
#include "core/dot3_filter.hpp"
#include "core/enclosure.hpp"
#include "core/error_bounds.hpp"
#include "core/expansion.hpp"
#include "core/quotient_rounding.hpp"
#include "core/validation.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/ray_plane_stages.hpp"

#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/plane_reference_check.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace raykernel {
namespace {

using detail::Dot3Rounded;
using detail::Enclosure;
using detail::Sign;
using testkit::Query;

int sign_of(const mpq_class& q) { return sgn(q); }

// round_quotient as the cascade calls it: the divisor prepared from den's enclosure.
std::optional<double> round_quotient(const Enclosure& num, const Enclosure& den) {
  return detail::round_quotient_if_certain(num, detail::prepare_divisor(den));
}

// Whether |exact − (hi + lo)| ≤ radius, in exact arithmetic.
bool encloses(const Enclosure& e, const mpq_class& exact) {
  if (!std::isfinite(e.radius)) return true;  // "no information" is always true
  if (!std::isfinite(e.hi) || !std::isfinite(e.lo)) return false;  // a finite radius promises finite values
  const mpq_class error = abs(exact - (mpq_class(e.hi) + mpq_class(e.lo)));
  return error <= mpq_class(e.radius);
}

struct Inputs {
  double d[3], n[3], p[3], o[3], diff[3], diff_lo[3];
};
Inputs inputs_of(const Query& q) {
  Inputs in{{q.ray.direction.x, q.ray.direction.y, q.ray.direction.z},
            {q.plane.normal.x, q.plane.normal.y, q.plane.normal.z},
            {q.plane.point.x, q.plane.point.y, q.plane.point.z},
            {q.ray.origin.x, q.ray.origin.y, q.ray.origin.z},
            {},
            {}};
  for (int i = 0; i < 3; ++i) {
    const detail::DoubleDouble s = detail::two_diff(in.p[i], in.o[i]);
    in.diff[i] = s.hi;
    in.diff_lo[i] = s.lo;
  }
  return in;
}

class StagesOnHardQueries : public ::testing::TestWithParam<testkit::QueryKind> {};

TEST_P(StagesOnHardQueries, EachStageIsRightWhenItDecides) {
  const testkit::QueryKind kind = GetParam();
  const std::uint64_t seed = 0x5eed0000 + static_cast<std::uint64_t>(kind);
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  SCOPED_TRACE(std::string(testkit::to_string(kind)) + ", seed " + std::to_string(seed));
  int decided[4] = {0, 0, 0, 0};  // filter, compensated, round_quotient (compensated), round_quotient (expansion)
  for (int i = 0; i < 3000; ++i) {
    const Query q = testkit::make_query(kind, bits);
    const Inputs in = inputs_of(q);
    const test_support::ExactTerms exact = test_support::exact_terms(q.ray, q.plane);
    constexpr double zero[3] = {0, 0, 0};

    // Stage 1.
    const Dot3Rounded den1 = detail::dot3_rounded(in.d, in.n);
    const Dot3Rounded num1 = detail::dot3_rounded(in.diff, in.n);
    for (const auto& [stage1, constant, value] : {std::tuple{den1, detail::bounds::filter_den_relative, exact.den},
                                                  std::tuple{num1, detail::bounds::filter_num_relative, exact.num}}) {
      const Sign s = detail::dot3_filter(stage1, constant, false);
      if (s != Sign::uncertain) {
        ++decided[0];
        ASSERT_EQ(static_cast<int>(s), sign_of(value)) << "filter certified a wrong sign, query " << i;
      }
    }

    // Stage 2: the enclosures contain the exact values; the signs they certify are right.
    const Enclosure den2 = detail::compensated_dot3(in.d, zero, in.n, den1);
    const Enclosure num2 = detail::compensated_dot3(in.diff, in.diff_lo, in.n, num1);
    // The α = 0 form den uses in the cascade computes the same bits (g_i = l_i = RN(0·b_i + l_i)).
    const Enclosure den2_exact = detail::compensated_dot3_exact(in.d, in.n, den1);
    ASSERT_TRUE(test_support::same_bits(den2.hi, den2_exact.hi) && test_support::same_bits(den2.lo, den2_exact.lo) &&
                test_support::same_bits(den2.radius, den2_exact.radius))
        << "compensated_dot3_exact differs from compensated_dot3 with α = 0, query " << i;
    ASSERT_TRUE(encloses(den2, exact.den)) << "den enclosure, query " << i;
    ASSERT_TRUE(encloses(num2, exact.num)) << "num enclosure, query " << i;
    for (const auto& [e, value] : {std::pair{den2, exact.den}, std::pair{num2, exact.num}}) {
      const Sign s = detail::enclosure_sign(e);
      if (s != Sign::uncertain) {
        ++decided[1];
        ASSERT_EQ(static_cast<int>(s), sign_of(value)) << "compensated sign, query " << i;
      }
    }

    // Stage 3: the expansions are exact when the builder says so, and their tail enclosures hold.
    detail::ExpansionBuilder builder;
    detail::Expansion<2> products[3];
    for (int k = 0; k < 3; ++k) detail::ExpansionBuilder::from_pair(builder.product(in.d[k], in.n[k]), products[k]);
    detail::Expansion<4> partial;
    detail::Expansion<6> den3;
    detail::ExpansionBuilder::sum(products[0], products[1], partial);
    detail::ExpansionBuilder::sum(partial, products[2], den3);
    builder.check_finite(den3);
    if (builder.exact()) {
      mpq_class sum = 0;
      for (std::size_t k = 0; k < den3.size; ++k) sum += mpq_class(den3.component[k]);
      ASSERT_EQ(sum, exact.den) << "den expansion, query " << i;
      ASSERT_EQ(static_cast<int>(den3.sign()), sign_of(exact.den));
      ASSERT_TRUE(encloses(detail::expansion_tail_enclosure(den3), exact.den)) << "tail enclosure, query " << i;
    }

    // round_quotient: whatever it returns is RN(num/den).
    if (exact.num != 0 && exact.den != 0) {
      const double expected = test_support::round_by_integer_division(exact.num / exact.den);
      if (const std::optional<double> t = round_quotient(num2, den2)) {
        ++decided[2];
        ASSERT_TRUE(test_support::same_bits(*t, expected)) << "round_quotient, query " << i << ": " << std::hexfloat << *t
                                                   << " vs " << expected;
      }
      // With exact enclosures (radius 0 after exact expansion), only ties and range guards can fail.
      auto tight = [](const mpq_class& v) -> std::optional<Enclosure> {
        const double hi = v.get_d();  // truncated; fine, the enclosure is checked below
        if (!std::isfinite(hi)) return std::nullopt;
        const double lo = mpq_class(v - mpq_class(hi)).get_d();
        const Enclosure e{hi, lo, 0x1p-1074};
        if (!encloses(e, v)) return std::nullopt;
        return e;
      };
      const std::optional<Enclosure> exact_num = tight(exact.num), exact_den = tight(exact.den);
      if (exact_num && exact_den) {
        if (const std::optional<double> t = round_quotient(*exact_num, *exact_den)) {
          ++decided[3];
          ASSERT_TRUE(test_support::same_bits(*t, expected)) << "round_quotient on tight enclosures, query " << i;
        }
      }
    }
  }
  RecordProperty("filter_decisions", decided[0]);
  RecordProperty("round_quotient_decisions", decided[2]);
}

INSTANTIATE_TEST_SUITE_P(AllKinds, StagesOnHardQueries, ::testing::ValuesIn(testkit::all_query_kinds),
                         [](const auto& info) {
                           std::string name(testkit::to_string(info.param));
                           for (char& c : name) c = (c == '-') ? '_' : c;
                           return name;
                         });

// Each call site passes its own constant (a mutation that filtered num with den's smaller constant left the
// differential runner and the hard queries silent). Hand-derived window: o = 0, p = (1, −1 + 7u, 0),
// n = (1, 1, 0) with u = 2^-53 give num's products 1 and −1 + 7u (exact), value s = 7u (Sterbenz) and magnitude
// m = 2 − 7u. num's bound (4 + 32u)u·m + 3μ ≈ 8u exceeds s, so stage 1 leaves num uncertain and stage 2 decides;
// den's constant (3 + 16u)u would give ≈ 6u < s and certify it at stage 1. d = (1, 0, 0): den = 1, certain.
TEST(Stages, NumIsFilteredWithItsOwnConstant) {
  constexpr double u = 0x1p-53;
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const Plane plane{{1, -1 + 7 * u, 0}, {1, 1, 0}};
  const TracedIntersection traced = intersect_traced(ray, plane);
  EXPECT_EQ(traced.intersection.relation, Relation::hit);
  EXPECT_EQ(traced.relation_stage, Stage::compensated) << "num's stage-1 bound is not (4 + 32u)u·m + 3μ";
  // The same window seen by the fast path: not certain at stage 1, so `intersect` answers through stage 2 too.
  EXPECT_EQ(intersect(ray, plane).t, 7 * u);
}

TEST(RoundQuotient, HalfGapToNearerNeighbour) {
  // For q in [2^e, 2^(e+1)) the gap to either neighbour is 2^(e−52), half of it 2^(e−53); at q = 2^e the
  // gap below is 2^(e−53), half of it 2^(e−54).
  EXPECT_EQ(detail::half_gap_to_nearer_neighbour(1.5), 0x1p-53);
  EXPECT_EQ(detail::half_gap_to_nearer_neighbour(-1.5), 0x1p-53);
  EXPECT_EQ(detail::half_gap_to_nearer_neighbour(1.0), 0x1p-54);
  EXPECT_EQ(detail::half_gap_to_nearer_neighbour(0x1.fffffffffffffp+0), 0x1p-53);
  EXPECT_EQ(detail::half_gap_to_nearer_neighbour(0x1p-900), 0x1p-954);
  EXPECT_EQ(detail::half_gap_to_nearer_neighbour(std::numeric_limits<double>::max()), 0x1p970);
}

TEST(RoundQuotient, DeclinesExactTies) {
  // num = 2^53 + 3, den = 2^53 exactly (radius 0 would be ideal; the smallest radius we can state is μ):
  // t = 1 + 3·2^-53 is a tie, which no enclosure of positive width can decide.
  const Enclosure num{0x1p53, 3, 0x1p-1074};
  const Enclosure den{0x1p53, 0, 0x1p-1074};
  EXPECT_FALSE(round_quotient(num, den).has_value());
}

TEST(RoundQuotient, DecidesAClearCase) {
  // num = 1, den = 3 known to within 2^-200: 1/3 is far from any midpoint.
  const Enclosure num{1, 0, 0x1p-200};
  const Enclosure den{3, 0, 0x1p-200};
  const std::optional<double> t = round_quotient(num, den);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(*t, 0x1.5555555555555p-2);
}

TEST(RoundQuotient, DeclinesWideEnclosures) {
  // den known only to 2^-40 relative: t's rounding cannot be certified.
  const Enclosure num{1, 0, 0};
  const Enclosure den{3, 0, 0x1p-40};
  EXPECT_FALSE(round_quotient(num, den).has_value());
}

TEST(Expansion, ZeroIsTheSingleComponentZero) {
  detail::ExpansionBuilder builder;
  detail::Expansion<2> a, b;
  detail::ExpansionBuilder::from_pair(builder.product(3, 5), a);   // 15
  detail::ExpansionBuilder::from_pair(builder.product(-5, 3), b);  // −15
  detail::Expansion<4> sum;
  detail::ExpansionBuilder::sum(a, b, sum);
  EXPECT_TRUE(builder.exact());
  EXPECT_EQ(sum.size, 1u);
  EXPECT_EQ(sum.component[0], 0.0);
  EXPECT_EQ(sum.sign(), Sign::zero);
}

TEST(Expansion, UnderflowingProductIsFlaggedInexact) {
  detail::ExpansionBuilder builder;
  (void)builder.product(0x1p-600, 0x1p-600);  // 2^-1200: not representable, not exact
  EXPECT_FALSE(builder.exact());
  detail::ExpansionBuilder ok;
  (void)ok.product(0x1p-484, 0x1p-484);  // 2^-968: exact
  EXPECT_TRUE(ok.exact());
}

}  // namespace
}  // namespace raykernel

namespace raykernel {
namespace {

// intersect's and relation's fast paths evaluate den and num side by side as the two lanes of a Lanes2;
// the proofs model each value's own evaluation (fast_answer on RayPlaneTermsT<double>). Every lane must be
// that evaluation, bit for bit: the certification, the relation and t.
TEST(FastPaths, TheTwoLaneFormIsTheScalarFormBitForBit) {
  std::size_t certified = 0, queries = 0;
  for (const testkit::QueryKind kind : testkit::all_query_kinds) {
    testkit::SplitMix64 rng(0x1a2e5 + static_cast<std::uint64_t>(kind));
    const testkit::BitSource bits = [&rng] { return rng(); };
    for (int i = 0; i < 2000; ++i, ++queries) {
      const testkit::Query q = testkit::make_query(kind, bits);
      const detail::RayPlaneTerms terms = detail::ray_plane_terms(q.ray, q.plane);
      const detail::FastAnswer scalar = detail::fast_answer(terms);
      const detail::FastAnswer paired = detail::fast_answer(q.ray, q.plane);
      ASSERT_EQ(scalar.certain, paired.certain) << testkit::to_string(q);
      ASSERT_EQ(scalar.relation_by_filter, paired.relation_by_filter) << testkit::to_string(q);
      const detail::FastRelationT<double> rs = detail::fast_relation(terms), rp = detail::fast_relation(q.ray, q.plane);
      ASSERT_EQ(rs.certain, rp.certain) << testkit::to_string(q);
      if (rs.certain) {
        ASSERT_EQ(rs.behind, rp.behind) << testkit::to_string(q);
      }
      if (!scalar.certain) continue;
      ++certified;
      ASSERT_EQ(scalar.behind, paired.behind) << testkit::to_string(q);
      ASSERT_TRUE(test_support::same_bits(scalar.t, paired.t)) << testkit::to_string(q);
    }
  }
  EXPECT_GT(certified, queries / 5);  // the easy kinds (about a quarter of these): the comparison is not vacuous
}

// The cascade evaluates stage 2's levels of den and num as the two lanes of a RayPlanePair, and continues
// from the fast path's values and rounding of t (RayPlaneCascade's constructor from them); the proofs model each
// value's scalar evaluation (den_compensated … num_refined). Every lane must be that evaluation, bit for bit, and
// the cascade built after the fast path must hold what the cascade built from the inputs holds.
bool same_enclosure(const Enclosure& a, const Enclosure& b) {
  return test_support::same_bits(a.hi, b.hi) && test_support::same_bits(a.lo, b.lo) &&
         test_support::same_bits(a.radius, b.radius);
}
bool same_stage1(const Dot3Rounded& a, const Dot3Rounded& b) {
  for (int i = 0; i < 3; ++i)
    if (!test_support::same_bits(a.product[i], b.product[i])) return false;
  return test_support::same_bits(a.value, b.value) && test_support::same_bits(a.magnitude, b.magnitude);
}

TEST(CascadeLanes, ThePairIsTheScalarStagesBitForBit) {
  std::size_t queries = 0, left_open = 0, refined_certain = 0, signs_certain = 0, second_level_step = 0,
              stage1_left_open = 0;
  for (const testkit::QueryKind kind : testkit::all_query_kinds) {
    testkit::SplitMix64 rng(0xca5cade + static_cast<std::uint64_t>(kind));
    const testkit::BitSource bits = [&rng] { return rng(); };
    for (int i = 0; i < 2000; ++i) {
      const Query q = testkit::make_query(kind, bits);
      if (!detail::is_valid(q.ray) || !detail::is_valid(q.plane)) continue;
      ++queries;
      const detail::RayPlaneTerms terms = detail::ray_plane_terms(q.ray, q.plane);
      const Enclosure den2 = detail::den_compensated(terms), num2 = detail::num_compensated(terms);
      const Enclosure den2r = detail::den_refined(terms), num2r = detail::num_refined(terms);
      const double o[3] = {q.ray.origin.x, q.ray.origin.y, q.ray.origin.z};
      const double d[3] = {q.ray.direction.x, q.ray.direction.y, q.ray.direction.z};
      const double p[3] = {q.plane.point.x, q.plane.point.y, q.plane.point.z};
      const double n[3] = {q.plane.normal.x, q.plane.normal.y, q.plane.normal.z};
      for (const detail::RayPlanePair& pair : {detail::ray_plane_pair(terms), detail::ray_plane_pair(o, d, p, n)}) {
        const auto c = detail::compensated_pair(pair);
        ASSERT_TRUE(same_enclosure(detail::enclosure_lane(c, 0), den2)) << testkit::to_string(q);
        ASSERT_TRUE(same_enclosure(detail::enclosure_lane(c, 1), num2)) << testkit::to_string(q);
        const auto r = detail::refined_pair(pair);
        ASSERT_TRUE(same_enclosure(detail::enclosure_lane(r, 0), den2r)) << testkit::to_string(q);
        ASSERT_TRUE(same_enclosure(detail::enclosure_lane(r, 1), num2r)) << testkit::to_string(q);
      }
      // The cascade from the inputs and the cascade from the fast path's values and rounding (what
      // intersect() hands over): the same terms, levels and rounding.
      detail::RayPlaneFastValues values;
      const detail::FastAnswer fast = detail::fast_answer(q.ray, q.plane, values);
      detail::RayPlaneCascade from_inputs(q.ray, q.plane),
          from_fast(q.ray, q.plane, values, detail::QuotientRounding{fast.t, fast.rounding_certain});
      ASSERT_TRUE(same_stage1(from_fast.terms().den, terms.den) && same_stage1(from_fast.terms().num, terms.num))
          << testkit::to_string(q);
      for (int k = 0; k < 3; ++k) ASSERT_TRUE(test_support::same_bits(from_fast.terms().diff[k], terms.diff[k]));
      ASSERT_TRUE(same_enclosure(from_fast.den_compensated(), den2) && same_enclosure(from_fast.num_compensated(), num2));
      ASSERT_TRUE(same_enclosure(from_inputs.den_refined(), den2r) && same_enclosure(from_inputs.num_refined(), num2r));
      const detail::QuotientRounding a = from_inputs.compensated_rounding(), b = from_fast.compensated_rounding();
      ASSERT_EQ(a.certain, b.certain) << testkit::to_string(q);
      if (a.certain) {
        ASSERT_TRUE(test_support::same_bits(a.t, b.t)) << testkit::to_string(q);
      }
      if (!fast.certain) {
        ++left_open;
        refined_certain += detail::enclosure_sign(from_fast.den_refined()) != Sign::uncertain;
      }
      // The second level from the fast path's stage 1 (intersect's step before the cascade) is the cascade's.
      const auto r = detail::refined_pair(values.stage1, q.ray, q.plane);
      ASSERT_TRUE(same_enclosure(detail::enclosure_lane(r, 0), den2r) && same_enclosure(detail::enclosure_lane(r, 1), num2r))
          << testkit::to_string(q);
      const TracedIntersection x = detail::intersect_cascade(from_inputs), y = detail::intersect_cascade(from_fast);
      ASSERT_EQ(x.intersection.relation, y.intersection.relation) << testkit::to_string(q);
      ASSERT_TRUE(test_support::same_bits(x.intersection.t, y.intersection.t) ||
                  (std::isnan(x.intersection.t) && std::isnan(y.intersection.t)))
          << testkit::to_string(q);
      // The signs of that step (stage 1's where certain, else the second level's), where both are certain, are
      // the cascade's (hit or behind), and then the public intersect (which rounds t on the second level itself
      // when the fast path did not) answers as the cascade does.
      detail::RayPlaneFastValues stage1_values;
      detail::Lanes2 alpha[3], normal[3];
      const detail::Mask2 filter = detail::fast_stage1(o, d, p, n, stage1_values, alpha, normal);
      ASSERT_EQ(fast.relation_by_filter, (filter[0] != detail::uncertain_lane) && (filter[1] != detail::uncertain_lane))
          << testkit::to_string(q);
      const detail::Mask2 signs = detail::filter_or_refined_signs(filter, r);
      if (signs[0] != detail::uncertain_lane && signs[1] != detail::uncertain_lane) {
        ++signs_certain;
        const detail::CertifiedSigns c = detail::certified_signs(from_inputs);
        ASSERT_EQ(static_cast<int>(c.den), signs[0]) << testkit::to_string(q);
        ASSERT_EQ(static_cast<int>(c.num), signs[1]) << testkit::to_string(q);
        if (!fast.certain) ++second_level_step;
        stage1_left_open += (filter[0] == detail::uncertain_lane) | (filter[1] == detail::uncertain_lane);
      }
      const Intersection pub = intersect(q.ray, q.plane);
      ASSERT_EQ(pub.relation, x.intersection.relation) << testkit::to_string(q);
      if (x.t_stage != Stage::exact) {
        ASSERT_TRUE(test_support::same_bits(pub.t, x.intersection.t) || (std::isnan(pub.t) && std::isnan(x.intersection.t)))
            << testkit::to_string(q);
      }
    }
  }
  // Not vacuous: the hard kinds leave many queries to the cascade, and the second level decides many of them;
  // many of those have both signs from the fast path.
  EXPECT_GT(left_open, queries / 4);
  EXPECT_GT(refined_certain, left_open / 4);
  EXPECT_GT(second_level_step, left_open / 8);
  EXPECT_GT(stage1_left_open, second_level_step / 4);  // the step straight after stage 1 is taken too
  EXPECT_GT(signs_certain, queries / 2);
}

// intersect takes the second level's step on raw input, before validation (plane_api.cpp, intersection_rest;
// PlaneCascadeTwins.v, second_level_twin_valid: it answers only for valid input). Every query of every kind
// made invalid in each component in turn (NaN, ±inf), or with d or n the zero vector of either sign, must still
// be reported as invalid input, never answered.
TEST(CascadeLanes, TheStepBeforeValidationNeverAnswersInvalidInput) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(), inf, -inf};
  std::size_t checked = 0, step_taken = 0;
  for (const testkit::QueryKind kind : testkit::all_query_kinds) {
    testkit::SplitMix64 rng(0xba5e + static_cast<std::uint64_t>(kind));
    const testkit::BitSource bits = [&rng] { return rng(); };
    for (int i = 0; i < 200; ++i) {
      const Query q = testkit::make_query(kind, bits);
      if (!detail::is_valid(q.ray) || !detail::is_valid(q.plane)) continue;
      step_taken += !detail::fast_answer(q.ray, q.plane).certain;
      for (int component = 0; component < 12; ++component) {
        for (const double b : bad) {
          Ray r = q.ray;
          Plane pl = q.plane;
          double* field[12] = {&r.origin.x,  &r.origin.y,  &r.origin.z,  &r.direction.x, &r.direction.y, &r.direction.z,
                               &pl.point.x, &pl.point.y, &pl.point.z, &pl.normal.x,    &pl.normal.y,    &pl.normal.z};
          *field[component] = b;
          ASSERT_THROW((void)intersect(r, pl), invalid_input) << testkit::to_string(q) << " component " << component;
          ++checked;
        }
      }
      for (const double zero : {0.0, -0.0}) {
        Ray r = q.ray;
        r.direction = {zero, 0.0, zero};
        ASSERT_THROW((void)intersect(r, q.plane), invalid_input) << testkit::to_string(q);
        Plane pl = q.plane;
        pl.normal = {0.0, zero, zero};
        ASSERT_THROW((void)intersect(q.ray, pl), invalid_input) << testkit::to_string(q);
        checked += 2;
      }
    }
  }
  EXPECT_GT(step_taken, 200u);  // the hard kinds: the queries these were made from reach the step
  EXPECT_GT(checked, 10000u);
}

// TwoSum can overflow inside with finite operands and a finite sum (proofs/plane/PlaneStageTwoFinite.v,
// two_sum_b_nan_or_finite): for p = −(2^1022 + 3·2^970) and o = −(2^1024 − 2^971), the largest double,
// p − o = 3·2^1022 − 5·2^970 is a tie between two doubles 2^971 apart and rounds to the even one,
// s = 3·2^1022 − 2^972; then s − p = 2^1024 − 2^970 is the tie between the largest double and 2^1024, which
// rounds to +inf, so the low part is inf − inf = NaN. Stage 2 of num = (p − o)·n must then say uncertain
// (its lo is NaN), never a sign; the answer comes from a later stage and is still the exact one.
TEST(Stages, ATwoDiffThatOverflowsInsideLeavesStageTwoUncertain) {
  const double p = -(0x1p1022 + 0x3p970), o = -0x1.fffffffffffffp1023;
  const detail::DoubleDouble difference = detail::two_diff(p, o);
  EXPECT_EQ(difference.hi, 0x3p1022 - 0x1p972);
  EXPECT_TRUE(std::isnan(difference.lo));
  // num = p − o > 0 and den = 1: a hit at t = RN(p − o) = difference.hi.
  const Ray ray{{o, 0, 0}, {1, 0, 0}};
  const Plane plane{{p, 0, 0}, {1, 0, 0}};
  const Enclosure num = detail::num_compensated(detail::ray_plane_terms(ray, plane));
  EXPECT_TRUE(std::isnan(num.lo));
  EXPECT_EQ(detail::enclosure_sign(num), Sign::uncertain);
  const TracedIntersection traced = intersect_traced(ray, plane);
  EXPECT_EQ(traced.intersection.relation, Relation::hit);
  EXPECT_EQ(traced.intersection.t, difference.hi);
  EXPECT_GT(traced.t_stage, Stage::compensated);  // round_quotient sees the NaN and says uncertain
  const Intersection exact = intersect_exact(ray, plane);
  EXPECT_EQ(exact.relation, Relation::hit);
  EXPECT_EQ(exact.t, difference.hi);
}

}  // namespace
}  // namespace raykernel
