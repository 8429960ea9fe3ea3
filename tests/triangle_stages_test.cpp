// Each stage of the certified ray–triangle cascade on its own, against exact rational arithmetic, on every
// kind of hard triangle query: a stage may say `uncertain`, but what it certifies must be exactly right, every
// enclosure must contain the exact value, and every exact expansion must equal the exact value. A wrong
// constant fails here even where a later stage would have masked it. Then the filter alone on subnormal and
// huge inputs, where the dynamic absolute term matters, with a demonstration that a constant absolute term
// (as for the plane's dot products) would certify wrong signs.
#include "core/det3_stages.hpp"
#include "core/error_bounds.hpp"
#include "nearest/triangle_candidate.hpp"
#include "triangle/ray_triangle_cascade.hpp"
#include "triangle/ray_triangle_formula.hpp"
#include "triangle/ray_triangle_stages.hpp"

#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/triangle.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>
#include <random>
#include <bit>
#include <cstring>
#include <string>

namespace raykernel {
namespace {

using detail::Enclosure;
using detail::Sign;
using testkit::TriangleQuery;

struct ExactValues {
  mpq_class value[5];  // πa, πb, πc, den, num
};

// The five values straight from the definitions (not from the kernel's formula template).
ExactValues exact_values(const TriangleQuery& q) {
  auto v = [](const Vec3& p) { return std::array<mpq_class, 3>{mpq_class(p.x), mpq_class(p.y), mpq_class(p.z)}; };
  const auto o = v(q.ray.origin), d = v(q.ray.direction), a = v(q.triangle.a), b = v(q.triangle.b), c = v(q.triangle.c);
  auto sub = [](const std::array<mpq_class, 3>& x, const std::array<mpq_class, 3>& y) {
    return std::array<mpq_class, 3>{x[0] - y[0], x[1] - y[1], x[2] - y[2]};
  };
  auto cross = [](const std::array<mpq_class, 3>& x, const std::array<mpq_class, 3>& y) {
    return std::array<mpq_class, 3>{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
  };
  auto dot = [](const std::array<mpq_class, 3>& x, const std::array<mpq_class, 3>& y) {
    return mpq_class(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]);
  };
  auto pi = [&](const std::array<mpq_class, 3>& p, const std::array<mpq_class, 3>& r) {
    return dot(d, cross(sub(p, o), sub(r, o)));
  };
  const auto n = cross(sub(b, a), sub(c, a));
  return {{pi(b, c), pi(c, a), pi(a, b), dot(d, n), dot(sub(a, o), n)}};
}

bool encloses(const Enclosure& e, const mpq_class& exact) {
  if (!std::isfinite(e.radius)) return true;
  if (!std::isfinite(e.hi) || !std::isfinite(e.lo)) return false;
  return abs(exact - (mpq_class(e.hi) + mpq_class(e.lo))) <= mpq_class(e.radius);
}

class TriangleStagesOnHardQueries : public ::testing::TestWithParam<testkit::TriangleQueryKind> {};

TEST_P(TriangleStagesOnHardQueries, EachStageIsRightWhenItDecides) {
  const testkit::TriangleQueryKind kind = GetParam();
  const std::uint64_t seed = 0x7e1a0000 + static_cast<std::uint64_t>(kind);
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  SCOPED_TRACE(std::string(testkit::to_string(kind)) + ", seed " + std::to_string(seed));
  int decided[3] = {0, 0, 0};  // filter, compensated, expansion
  int integer_decided = 0;
  int handed_over = 0;
  for (int i = 0; i < 1500; ++i) {
    const TriangleQuery q = testkit::make_triangle_query(kind, bits);
    const ExactValues exact = exact_values(q);
    const detail::TriangleFilterValues s1 = detail::triangle_filter_values(q.ray, q.triangle);
    const detail::TriangleCompensatedValues s2 = detail::triangle_compensated_values(q.ray, q.triangle);
    const detail::TriangleExpansions s3 = detail::triangle_expansions(q.ray, q.triangle);
    const detail::TriangleFilterValues s2_as_1 = s2.filter();
    // The full cascade's stage 2, evaluated in lanes: the same five values and absolute terms, bit for bit.
    const detail::TriangleCompensatedValues s2_lanes = detail::triangle_compensated_values_by_lanes(q.ray, q.triangle);
    ASSERT_EQ(std::memcmp(&s2_lanes.value, &s2.value, sizeof s2.value), 0) << testkit::triangle_line(q);
    ASSERT_EQ(s2_lanes.absolute_d, s2.absolute_d);
    ASSERT_EQ(s2_lanes.absolute_e, s2.absolute_e);
    // What the fast path leaves the cascade when it certifies nothing: the same values, bit for bit, and only
    // when it evaluated them (t or barycentrics asked; the relation alone reads stage 1 of other lanes).
    for (const bool t_asked : {true, false}) {
      detail::TriangleStage2Handover handover;
      const TriangleOptions options{.t = t_asked, .barycentric = false};
      if (!detail::fast_triangle_intersection(q.ray, q.triangle, options, handover)) {
        ASSERT_EQ(handover.computed, t_asked) << testkit::triangle_line(q);
        if (handover.computed) {
          ASSERT_EQ(std::memcmp(&handover.values.value, &s2.value, sizeof s2.value), 0) << testkit::triangle_line(q);
          ASSERT_EQ(handover.values.absolute_d, s2.absolute_d);
          ASSERT_EQ(handover.values.absolute_e, s2.absolute_e);
          ++handed_over;
        }
      } else {
        ASSERT_FALSE(handover.computed);
      }
    }
    for (int v = 0; v < 5; ++v) {
      const auto idx = static_cast<std::size_t>(v);
      const int want = sgn(exact.value[v]);
      // Stage 2's high parts and magnitudes are stage 1's values, bit for bit.
      ASSERT_EQ(std::memcmp(&s1.value[idx], &s2_as_1.value[idx], sizeof s1.value[idx]), 0) << "value " << v;
      const auto f = static_cast<Sign>(
          detail::det3_filter_lanes(s1.value[idx], detail::filter_relative(v), s1.absolute(v)));
      if (f != Sign::uncertain) {
        ++decided[0];
        ASSERT_EQ(static_cast<int>(f), want) << "filter, value " << v << ", query " << testkit::triangle_line(q);
      }
      const Enclosure e = s2.enclosure(v);
      ASSERT_TRUE(encloses(e, exact.value[v])) << "enclosure, value " << v << ", query " << testkit::triangle_line(q);
      const Sign es = detail::enclosure_sign(e);
      if (es != Sign::uncertain) {
        ++decided[1];
        ASSERT_EQ(static_cast<int>(es), want) << "enclosure sign, value " << v;
      }
      const Sign xs = s3.sign(v);
      if (xs != Sign::uncertain) {
        ++decided[2];
        ASSERT_EQ(static_cast<int>(xs), want) << "expansion sign, value " << v;
      }
      // Stage 3's integers (core/integer_det3.hpp): the sign when certain, and the components' exact sum.
      const Sign is = detail::integer_value_sign(q.ray, q.triangle, v);
      if (is != Sign::uncertain) {
        ++integer_decided;
        ASSERT_EQ(static_cast<int>(is), want) << "integer sign, value " << v << ", query " << testkit::triangle_line(q);
      }
      detail::IntegerLeaves leaves(q.ray, q.triangle);
      const detail::IntegerValue iv = detail::integer_value_components(leaves, v);
      if (iv.ok) {
        ASSERT_TRUE(is != Sign::uncertain);  // the same integers
        mpq_class total = 0;
        for (std::size_t k = 0; k < iv.e.size; ++k) total += mpq_class(iv.e.component[k]);
        ASSERT_EQ(total, exact.value[v]) << "integer components, value " << v << ", query " << testkit::triangle_line(q);
      }
    }
    // The fast paths' lane layouts compute the same bits as the scalar evaluation the proofs model: lanes
    // πa, πb, πc, num (stage 2, and its stage-1 view), and πa, πb, πc, den = π(b, c) seen from a (the
    // relation-only path's stage 1); num on its own.
    const auto c4 = detail::triangle_compensated_lanes(q.ray, q.triangle);
    const auto f4 = detail::triangle_relation_lanes(q.ray, q.triangle);
    const detail::TriangleFilterValues from_a = detail::triangle_filter_values({q.triangle.a, q.ray.direction}, q.triangle);
    const int scalar_of_lane[4] = {0, 1, 2, 4};
    for (int k = 0; k < 4; ++k) {
      const auto c = detail::lane(c4.lanes, k);
      const auto& want = s2.value[static_cast<std::size_t>(scalar_of_lane[k])];
      ASSERT_TRUE(std::memcmp(&c, &want, sizeof c) == 0) << "compensated lane " << k << ": " << testkit::triangle_line(q);
      ASSERT_EQ(c4.absolute[k], s2.absolute(scalar_of_lane[k]));
      const auto f = detail::lane(f4.lanes, k);
      const auto& fwant = k < 3 ? s1.value[static_cast<std::size_t>(k)] : from_a.value[0];
      ASSERT_TRUE(std::memcmp(&f, &fwant, sizeof f) == 0) << "relation lane " << k << ": " << testkit::triangle_line(q);
      ASSERT_EQ(f4.absolute[k], s1.absolute_d);
    }
    const detail::TriangleNumFilter num1 = detail::triangle_num_filter(q.ray, q.triangle);
    ASSERT_TRUE(std::memcmp(&num1.value, &s1.value[4], sizeof num1.value) == 0);
    ASSERT_EQ(num1.absolute, s1.absolute_e);
    // The exact expansions sum to the exact values.
    auto sum = [](const auto& x) {
      mpq_class s = 0;
      for (std::size_t k = 0; k < x.e.size; ++k) s += mpq_class(x.e.component[k]);
      return s;
    };
    for (std::size_t k = 0; k < 3; ++k) {
      if (s3.pi[k].exact) {
        ASSERT_EQ(sum(s3.pi[k]), exact.value[k]);
      }
    }
    if (s3.den.exact) {
      ASSERT_EQ(sum(s3.den), exact.value[3]);
    }
    if (s3.num.exact) {
      ASSERT_EQ(sum(s3.num), exact.value[4]);
    }
  }
  RecordProperty("filter_decided", decided[0]);
  RecordProperty("compensated_decided", decided[1]);
  RecordProperty("expansion_decided", decided[2]);
  RecordProperty("integer_decided", integer_decided);
  RecordProperty("handed_over", handed_over);
  // The kinds an ulp or a few off a grid (a nudged origin, direction or vertex: differences p − o that are not
  // doubles) keep integer leaves: their points span fewer than 62 bits, so the integers decide 99% of the values
  // and more (7,492–7,496 of 7,500 here; 5,105–6,084 when only the differences that are doubles were read).
  if (kind == testkit::TriangleQueryKind::near_vertex || kind == testkit::TriangleQueryKind::near_edge ||
      kind == testkit::TriangleQueryKind::sliver || kind == testkit::TriangleQueryKind::needle) {
    EXPECT_GE(integer_decided, 1500 * 5 * 99 / 100);
    EXPECT_GT(handed_over, 0);  // these kinds leave the fast path
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, TriangleStagesOnHardQueries, ::testing::ValuesIn(testkit::all_triangle_query_kinds),
                         [](const ::testing::TestParamInfo<testkit::TriangleQueryKind>& info) {
                           std::string name(testkit::to_string(info.param));
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

// The leaf filter's layout (triangle_relation_columns: four triangles, one per lane) computes, lane by lane, the
// bits of the relation-only layout (triangle_relation_lanes: one triangle, πa, πb, πc, den in its lanes), and
// triangle_certain_misses flags exactly the triangles whose fast relation is the filter's "outside" miss. The
// four lanes: the query's triangle, its vertices rotated, another query's triangle, its orientation flipped.
TEST_P(TriangleStagesOnHardQueries, LeafColumnsAreTheRelationLanesOfEachTriangle) {
  const testkit::TriangleQueryKind kind = GetParam();
  const std::uint64_t seed = 0x7e1b0000 + static_cast<std::uint64_t>(kind);
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  SCOPED_TRACE(std::string(testkit::to_string(kind)) + ", seed " + std::to_string(seed));
  int misses = 0, lanes = 0;
  for (int i = 0; i < 1500; ++i) {
    const TriangleQuery q = testkit::make_triangle_query(kind, bits);
    const TriangleQuery other = testkit::make_triangle_query(kind, bits);
    const Triangle& t = q.triangle;
    const Triangle four[4] = {t, {t.b, t.c, t.a}, other.triangle, {t.a, t.c, t.b}};
    const Triangle* const p[4] = {&four[0], &four[1], &four[2], &four[3]};
    const detail::TriangleRelationColumns columns = detail::triangle_relation_columns(q.ray, p);
    const unsigned miss = detail::triangle_certain_misses(q.ray, p);
    for (int k = 0; k < 4; ++k) {
      const auto want = detail::triangle_relation_lanes(q.ray, four[k]);
      for (int j = 0; j < 4; ++j) {
        const auto& column = j < 3 ? columns.pi[j] : columns.den;
        const detail::FilterTerm<double> got{column.v[k], column.m[k]};
        const auto expected = detail::lane(want.lanes, j);
        ASSERT_TRUE(std::memcmp(&got, &expected, sizeof got) == 0)
            << "lane " << k << ", value " << j << ": " << testkit::triangle_line({q.ray, four[k]});
      }
      ASSERT_EQ(std::bit_cast<std::uint64_t>(columns.absolute[k]), std::bit_cast<std::uint64_t>(want.absolute[3]));
      const auto fast = detail::fast_triangle_relation(q.ray, four[k], TriangleRule::owned);
      const bool filter_miss = fast && fast->classification.relation == TriangleRelation::miss;
      ASSERT_EQ(((miss >> k) & 1) != 0, filter_miss) << "lane " << k << ": " << testkit::triangle_line({q.ray, four[k]});
      misses += filter_miss;
      ++lanes;
    }
  }
  RecordProperty("certain_misses", misses);
  RecordProperty("lanes", lanes);
}

// triangle_screen's `inside` flags exactly the triangles whose fast relation takes its inside branch (the four
// stage-1 signs of its lanes certain and all den's), with den's sign; inside_relation from the screen's lane of den
// decides as fast_triangle_relation does and hands over the same stage-1 values; and a nearest-hit candidate
// classified through the screen (classify_screened) is the candidate classify makes, in every field the search
// reads.
TEST_P(TriangleStagesOnHardQueries, TheScreenDecidesInsideAsEachTriangleWould) {
  const testkit::TriangleQueryKind kind = GetParam();
  const std::uint64_t seed = 0x1a5d0000 + static_cast<std::uint64_t>(kind);
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  SCOPED_TRACE(std::string(testkit::to_string(kind)) + ", seed " + std::to_string(seed));
  const auto same_bits = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  int inside = 0;
  for (int i = 0; i < 1500; ++i) {
    const TriangleQuery q = testkit::make_triangle_query(kind, bits);
    const TriangleQuery other = testkit::make_triangle_query(kind, bits);
    const Triangle& t = q.triangle;
    const Triangle four[4] = {t, {t.c, t.a, t.b}, other.triangle, {t.b, t.a, t.c}};
    const Triangle* const p[4] = {&four[0], &four[1], &four[2], &four[3]};
    const detail::TriangleScreen screen = detail::triangle_screen(q.ray, p);
    detail::LeafScreen leaf(q.ray, std::span<const Triangle>(four, 4), 0, 4);
    for (int k = 0; k < 4; ++k) {
      const std::string line = "lane " + std::to_string(k) + ": " + testkit::triangle_line({q.ray, four[k]});
      const auto lanes = detail::triangle_relation_lanes(q.ray, four[k]);
      const detail::Mask4 sign =
          detail::det3_filter_lanes(lanes.lanes, detail::bounds::triangle_filter_pi_relative, lanes.absolute);
      bool certain = true, all_den = true;
      for (int j = 0; j < 4; ++j) certain = certain && sign[j] != detail::uncertain_lane;
      for (int j = 0; j < 3; ++j) all_den = all_den && sign[j] == sign[3];
      ASSERT_EQ(((screen.inside >> k) & 1) != 0, certain && all_den) << line;
      ASSERT_EQ(((screen.missed >> k) & 1) != 0, certain && !all_den) << line;
      if (((screen.inside >> k) & 1) != 0) {
        ++inside;
        ASSERT_EQ(screen.den_sign[k], sign[3]) << line;
        const detail::InsideRelation through =
            detail::inside_relation(q.ray, four[k], detail::lane(screen.den, k), screen.absolute);
        detail::TriangleQuotientStage1 values{};
        const auto fast = detail::fast_triangle_relation(q.ray, four[k], TriangleRule::owned, values);
        ASSERT_EQ(fast.has_value(), through.num_sign != detail::uncertain_lane) << line;
        ASSERT_TRUE(same_bits(values.num, through.values.num) && same_bits(values.den, through.values.den) &&
                    same_bits(values.absolute_e, through.values.absolute_e) &&
                    same_bits(values.absolute_d, through.values.absolute_d))
            << line;
        if (fast) {
          const TriangleClassification c = through.classification(screen.den_sign[k]);
          ASSERT_EQ(fast->classification.relation, c.relation) << line;
          ASSERT_EQ(fast->classification.location, c.location) << line;
          ASSERT_EQ(fast->classification.owned, c.owned) << line;
        }
      }
      const auto n = static_cast<std::size_t>(k);
      if (leaf.certainly_missed(n)) continue;
      for (const TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
        detail::TriangleCandidate a, b;
        a.classify(q.ray, four[k], n, static_cast<std::uint32_t>(k), rule);
        b.classify_screened(q.ray, four[k], n, static_cast<std::uint32_t>(k), rule, leaf, n);
        ASSERT_EQ(a.classification.relation, b.classification.relation) << line;
        ASSERT_EQ(a.classification.location, b.classification.location) << line;
        ASSERT_EQ(a.classification.owned, b.classification.owned) << line;
        ASSERT_EQ(a.relation_stage, b.relation_stage) << line;
        if (a.classification.relation != TriangleRelation::hit) continue;
        ASSERT_EQ(a.num_sign, b.num_sign) << line;
        ASSERT_EQ(a.den_sign, b.den_sign) << line;
        ASSERT_TRUE(same_bits(a.num_filter(), b.num_filter()) && same_bits(a.den_filter(), b.den_filter())) << line;
        ASSERT_EQ(std::bit_cast<std::uint64_t>(a.round_t()), std::bit_cast<std::uint64_t>(b.round_t())) << line;
      }
    }
  }
  RecordProperty("inside_lanes", inside);
  if (kind == testkit::TriangleQueryKind::random || kind == testkit::TriangleQueryKind::through_interior) {
    EXPECT_GT(inside, 300) << "the screen's inside branch was hardly exercised";
  }
}

// ---- The filter at the ends of the exponent range ---------------------------------------------------------

// A filter with the plane's constant absolute term 3μ instead of the dynamic one (the counterfactual).
Sign filter_with_constant_absolute(const detail::FilterTerm<double>& r, double relative) {
  const double bound = relative * r.m + 0x0.0000000000003p-1022;
  return r.v > bound ? Sign::positive : (r.v < -bound ? Sign::negative : Sign::uncertain);
}

TEST(TriangleFilter, SoundOnSubnormalAndHugeInputs) {
  // Vertices and origin ±(1 + f)·2^e with e in [-545, -525]: the products of the cross products land around
  // 2^-1070, in the subnormal range, where each rounding errs by up to η = 2^-1075 absolutely; d has e in
  // [960, 1020], which scales those errors up to about 2^-55. Half of the queries swap the roles (points near
  // 2^500, d subnormal), where the outer products underflow.
  testkit::SplitMix64 rng(0x5b0);
  auto scaled = [&](int emin, int emax) {
    const double significand = 1.0 + static_cast<double>(rng() >> 12) * 0x1p-52;
    const int e = emin + static_cast<int>(rng() % static_cast<std::uint64_t>(emax - emin + 1));
    const double m = std::ldexp(significand, e);
    return (rng() & 1) ? -m : m;
  };
  int certified = 0, wrong_with_constant_term = 0;
  for (int i = 0; i < 30000; ++i) {
    const bool tiny_points = (i & 1) != 0;
    auto point = [&] {
      return tiny_points ? Vec3{scaled(-545, -525), scaled(-545, -525), scaled(-545, -525)}
                         : Vec3{scaled(480, 520), scaled(480, 520), scaled(480, 520)};
    };
    const Vec3 d = tiny_points ? Vec3{scaled(960, 1020), scaled(960, 1020), scaled(960, 1020)}
                               : Vec3{scaled(-1074, -1040), scaled(-1074, -1040), scaled(-1074, -1040)};
    const TriangleQuery q{{point(), d}, {point(), point(), point()}};
    const ExactValues exact = exact_values(q);
    const detail::TriangleFilterValues s1 = detail::triangle_filter_values(q.ray, q.triangle);
    for (int v = 0; v < 5; ++v) {
      const auto idx = static_cast<std::size_t>(v);
      const auto f = static_cast<Sign>(
          detail::det3_filter_lanes(s1.value[idx], detail::filter_relative(v), s1.absolute(v)));
      if (f != Sign::uncertain) {
        ++certified;
        ASSERT_EQ(static_cast<int>(f), sgn(exact.value[v])) << "value " << v << ": " << testkit::triangle_line(q);
      }
      const Sign c = filter_with_constant_absolute(s1.value[idx], detail::filter_relative(v));
      if (c != Sign::uncertain && static_cast<int>(c) != sgn(exact.value[v])) ++wrong_with_constant_term;
    }
  }
  RecordProperty("certified", certified);
  EXPECT_GT(certified, 1000) << "the filter should still decide some of these";
  EXPECT_GT(wrong_with_constant_term, 0) << "the counterfactual filter should be caught wrong at least once";
  std::printf("extreme exponents: the filter certified %d signs, all right; with a constant absolute term it would "
              "have certified %d wrong ones\n",
              certified, wrong_with_constant_term);
}

// The fast paths pass each value's own relative constant (error_bounds.hpp: π 8u, num 9u, den 10u) at their
// call sites in ray_triangle_cascade.cpp, which no twin covers (the runner checks det3_filter_lanes, not who
// passes which constant). Each case below puts one value's stage-1 ratio |v|/m strictly between a smaller
// constant and its own, with every product and sum exact, so that the right constant leaves that value to
// stage 2 (the traced stage is `compensated`) and a smaller one would certify it at the filter. The absolute
// terms A are below 2^-1000 here and do not move any bound (C ⊗ m ≥ 2^-50 in both cases).
TEST(TriangleFilter, FastRelationFiltersNumWithItsOwnConstant) {
  // o = 0, d = (0, 0, 1); a = (1, 0, K + 1), b = (0, 1, K + 1), c = (−1, −1, −2K + 1), on the plane
  // z = Kx + Ky + 1, K = 2^49 + 2^47 + 2^46 (all coordinates and products below are integers < 2^53: exact).
  // π(b, c) = d·(b × c) = b_x c_y − b_y c_x = 1, likewise π(c, a) = π(a, b) = 1, each with m = 1: the filter
  // certifies them (and den, lane 3: d·((b − a) × (c − a)) = 3, m = 3), all positive: inside.
  // num = a·(b × c): b × c = (−K + 2, −K − 1, 1), so num = (−K + 2) + 0 + (K + 1) = 3, and its permanent
  // m = |a_x|·(|b_y c_z| + |b_z c_y|) + |a_y|·(…) + |a_z|·(|b_x c_y| + |b_y c_x|) = 3K + 0 + (K + 1) = 4K + 1
  // = 3096224743817217. num's bound 9u·m ≈ 3.09375 ≥ 3: uncertain, stage 2 decides (num = 3 exactly, radius
  // ≈ 2^-47). With π's constant the bound would be 8u·m ≈ 2.75 < 3: certified by the filter.
  constexpr double K = 0x1p49 + 0x1p47 + 0x1p46;
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  const Triangle triangle{{1, 0, K + 1}, {0, 1, K + 1}, {-1, -1, -2 * K + 1}};
  const TracedTriangleIntersection traced = intersect_traced(ray, triangle, {TriangleRule::owned, false, false});
  EXPECT_EQ(traced.intersection.relation, TriangleRelation::hit);  // num/den = 3/3 = 1 > 0
  EXPECT_EQ(traced.intersection.location, TriangleLocation::inside);
  EXPECT_EQ(traced.relation_stage, Stage::compensated) << "fast_relation: num's bound is not 9u·m + A";
}

TEST(TriangleFilter, CascadeFiltersDenWithItsOwnConstant) {
  // o = (0, 0, 1), d = (0, 0, −1); the triangle in the plane z = 0: a = (−16, −16, 0), b = (1, 1 − 17u, 0),
  // c = (1, 1 + 18u, 0) (u = 2^-53; all doubles). With d = (0, 0, −1) and ê_v = (v_x, v_y, −1), π(p, q) =
  // −(p_x q_y − p_y q_x) and m = |p_x q_y| + |p_y q_x| (the d_x, d_y terms are 0 · …), every product exact:
  //   π(b, c) = −((1 + 18u) − (1 − 17u)) = −35u,      m = 2:          |π|/m = 17.5u
  //   π(c, a) = −(−16 + 16(1 + 18u)) = −288u,         m = 32 + 288u:  |π|/m ≈ 9.0u
  //   π(a, b) = −(−16(1 − 17u) + 16) = −272u,         m = 32 − 272u:  |π|/m ≈ 8.5u
  // all above π's 8u: certified negative by the filter. den = (πa ⊕ πb) ⊕ πc = −595u, m = 66:
  // |den|/m = 9.015u, so den's 10u·m ≈ 660u leaves it uncertain (stage 2 certifies it: exact, radius ≈ 2^-92),
  // where π's 8u·m ≈ 528u would certify it. num = ê_a·(ê_b × ê_c) = −595u and its m = 66 are den's (the z
  // components are all −1): |num|/m = 9.015u > 9u, certified. Stage 2 cannot round t or the barycentrics here
  // (den's radius 256u²·66 is about 28u·|den|, far above the half gap), so the fast path hands the query to the
  // full cascade, whose den is filtered with filter_relative(value_den): hit, t = num/den = 1 (o + 1·d = 0 is
  // on the plane), inside, with den's sign from stage 2.
  // (The same window in fast_triangle_intersection's own den filter is unobservable: whenever stage 2 rounds
  // t, |den| is above about 256u·m, which every constant certifies; proofs/README.md, the triangle mutations.)
  constexpr double u = 0x1p-53;
  const Ray ray{{0, 0, 1}, {0, 0, -1}};
  const Triangle triangle{{-16, -16, 0}, {1, 1 - 17 * u, 0}, {1, 1 + 18 * u, 0}};
  const TracedTriangleIntersection traced = intersect_traced(ray, triangle);
  EXPECT_EQ(traced.intersection.relation, TriangleRelation::hit);
  EXPECT_EQ(traced.intersection.location, TriangleLocation::inside);
  EXPECT_EQ(traced.intersection.t, 1.0);
  EXPECT_EQ(traced.relation_stage, Stage::compensated) << "the cascade: den's bound is not 10u·m + A";
}

// det3_absolute_term computes A = (K_A ⊗ S) ⊕ U_A without subnormal arithmetic (core/det3_stages.hpp); its bits
// must be the formula's, which is what the proofs model: checked here for values on both sides of 2^48, ties of
// 16·S, subnormal, huge and non-finite inputs and random bit patterns, for one value and per lane.
std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
double formula(double x0, double x1, double x2) {
  const double s = (std::fabs(x0) + std::fabs(x1)) + std::fabs(x2);
  return detail::bounds::triangle_absolute_scale * s + detail::bounds::triangle_absolute;
}
TEST(DetAbsoluteTerm, SameBitsAsTheFormula) {
  std::vector<double> values{0.0, -0.0, 1.0, 0x1p48, std::nextafter(0x1p48, 0.0), std::nextafter(0x1p48, 1e300),
                             0x1p47 + 0.03125, 0x1p47 + 0.09375, 0.03125, 0.09375, 3 * 0x1p-5, 0x1p-1074, 0x1p-1022,
                             1e-300, 1e300, 1.7976931348623157e308, HUGE_VAL, -HUGE_VAL, std::nan("")};
  std::mt19937_64 rng(2026);
  for (int k = 0; k < 20000; ++k) {
    const int e = static_cast<int>(rng() % 140) - 60;
    values.push_back(std::ldexp(static_cast<double>(rng() >> 11), e - 53));
    values.push_back(std::bit_cast<double>(rng()));
  }
  for (std::size_t k = 0; k + 2 < values.size(); ++k) {
    const double x0 = values[k], x1 = values[(k * 7 + 1) % values.size()], x2 = k % 3 == 0 ? 0.0 : values[k + 2];
    const double want = formula(x0, x1, x2);
    const double got = detail::det3_absolute_term(x0, x1, x2);
    if (std::isnan(want)) {
      EXPECT_TRUE(std::isnan(got));
    } else {
      EXPECT_EQ(bits(got), bits(want)) << x0 << " " << x1 << " " << x2;
    }
    const detail::Lanes4 l0{x0, x1, x2, x0}, l1{x1, x2, x0, 0.0}, l2{x2, x0, x1, x1};
    const detail::Lanes4 lanes = detail::det3_absolute_term(l0, l1, l2);
    const double per_lane[4] = {formula(x0, x1, x2), formula(x1, x2, x0), formula(x2, x0, x1), formula(x0, 0.0, x1)};
    for (int i = 0; i < 4; ++i) {
      if (std::isnan(per_lane[i])) EXPECT_TRUE(std::isnan(lanes[i]));
      else EXPECT_EQ(bits(lanes[i]), bits(per_lane[i])) << "lane " << i;
    }
  }
}

}  // namespace
}  // namespace raykernel

namespace raykernel {
namespace {

int exact_sign(const mpq_class& x) { return sgn(x); }

// product_difference_sign (triangle/ray_triangle_stages.hpp; proofs/triangle/TieBreakPairs.v,
// `pair_difference_sign`): every sign it gives is the exact sign of a·b − c·e (rationals), including equal rounded
// products that differ in their low parts, zero factors and products of opposite sign; it gives nothing when a
// TwoProduct underflows past its guard.
TEST(TieBreakPairs, ProductDifferenceSignIsExact) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  int decided = 0, equal_highs = 0;
  for (int n = 0; n < 200000; ++n) {
    double a = std::ldexp(unit(rng), exponent(rng)), b = std::ldexp(unit(rng), exponent(rng));
    double c, e;
    switch (n % 4) {
      case 0:  // independent
        c = std::ldexp(unit(rng), exponent(rng)), e = std::ldexp(unit(rng), exponent(rng));
        break;
      case 1:  // the same product, factors scaled by a power of two: a·b − c·e = 0 exactly
        c = a * 2, e = b / 2;
        break;
      case 2:  // c·e an ulp or two from a·b: equal highs, different lows, often
        c = a, e = std::nextafter(b, n % 8 < 4 ? 2.0 : -2.0);
        break;
      default:  // a zero factor
        c = 0, e = unit(rng);
        break;
    }
    const std::optional<int> s = detail::product_difference_sign(a, b, c, e);
    const mpq_class exact = mpq_class(a) * mpq_class(b) - mpq_class(c) * mpq_class(e);
    if (!s) continue;
    ++decided;
    if (a * b == c * e) ++equal_highs;
    ASSERT_EQ(*s, exact_sign(exact)) << a << " " << b << " " << c << " " << e;
  }
  EXPECT_EQ(decided, 200000);  // no product of these magnitudes underflows
  EXPECT_GT(equal_highs, 50000);
  // Hand-derived: (1 + 2^-52)·(1 + 2^-52) = 1 + 2^-51 + 2^-104 rounds to 1 + 2^-51, as does (1 + 2^-51)·1: equal
  // highs, lows 2^-104 and 0, so the difference is +2^-104.
  const double x = 1 + 0x1p-52;
  EXPECT_EQ(x * x, (1 + 0x1p-51) * 1.0);
  EXPECT_EQ(detail::product_difference_sign(x, x, 1 + 0x1p-51, 1.0), 1);
  EXPECT_EQ(detail::product_difference_sign(1 + 0x1p-51, 1.0, x, x), -1);
  EXPECT_EQ(detail::product_difference_sign(x, x, x, x), 0);
  // A product below the guard (2^-600·2^-600 underflows): nothing.
  EXPECT_FALSE(detail::product_difference_sign(0x1p-600, 0x1p-600, 1.0, 1.0).has_value());
}

// The tie-break signs with the pair shortcut equal the expansions' (edge_tie_break in ExpansionValue) on the hard
// triangle queries of every kind, for each edge.
TEST(TieBreakPairs, TieBreakSignsEqualTheExpansions) {
  int compared = 0;
  for (const testkit::TriangleQueryKind kind : testkit::all_triangle_query_kinds) {
    testkit::SplitMix64 rng(static_cast<std::uint64_t>(kind) + 101);
    const testkit::BitSource source = [&rng] { return rng(); };
    for (int n = 0; n < 500; ++n) {
      const TriangleQuery q = testkit::make_triangle_query(kind, source);
      for (int k = 0; k < 3; ++k) {
        const std::optional<std::array<int, 3>> fast = detail::tie_break_signs_by_expansion(q.ray, q.triangle, k);
        const Vec3& p = k == 0 ? q.triangle.b : k == 1 ? q.triangle.c : q.triangle.a;
        const Vec3& w = k == 0 ? q.triangle.c : k == 1 ? q.triangle.a : q.triangle.b;
        const std::array<detail::ExpansionValue<2>, 3> d{detail::expansion_of(q.ray.direction.x),
                                                         detail::expansion_of(q.ray.direction.y),
                                                         detail::expansion_of(q.ray.direction.z)};
        const auto v = detail::edge_tie_break(d, p, w, detail::expansion_difference);
        bool certain = true;
        std::array<int, 3> slow{};
        for (std::size_t i = 0; i < 3; ++i) {
          certain = certain && detail::is_certain(v[i].sign());
          slow[i] = static_cast<int>(v[i].sign());
        }
        if (!certain) continue;
        ASSERT_TRUE(fast.has_value());
        EXPECT_EQ(*fast, slow);
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 10000);
}

}  // namespace
}  // namespace raykernel
