// The testkit's ray–triangle tools: the hard-query constructors keep their exact promises (checked in GMP
// rationals by the independent oracle), the fuzz decoder inverts its encoders, and the reference check finds
// and reports what is wrong.
#include "support/triangle_oracle.hpp"

#include <raykernel/testkit/triangle_fuzz_decoder.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/testkit/triangle_reference_check.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <string>

namespace raykernel::testkit {
namespace {

using test_support::triangle_oracle;

int zero_pis(const test_support::TriangleOracle& o) {
  return (sgn(o.pi_a) == 0) + (sgn(o.pi_b) == 0) + (sgn(o.pi_c) == 0);
}

class TriangleKinds : public ::testing::TestWithParam<TriangleQueryKind> {};

TEST_P(TriangleKinds, KeepTheirPromises) {
  const TriangleQueryKind kind = GetParam();
  SplitMix64 rng(0xfeed + static_cast<std::uint64_t>(kind));
  const BitSource bits = [&rng] { return rng(); };
  int special = 0;  // queries with the kind's property
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const TriangleQuery q = make_triangle_query(kind, bits);
    ASSERT_FALSE(validate(q.ray, q.triangle).has_value()) << triangle_line(q);
    const test_support::TriangleOracle o = triangle_oracle(q.ray, q.triangle, TriangleRule::owned);
    const bool degenerate = o.answer.relation == TriangleRelation::degenerate;
    switch (kind) {
      case TriangleQueryKind::through_vertex:
        // The line through a vertex: the two π of its edges are 0 (or den = 0: the line lies in the plane).
        ASSERT_TRUE(zero_pis(o) >= 2 || sgn(o.den) == 0) << triangle_line(q);
        special += zero_pis(o) == 2 && sgn(o.den) != 0;
        break;
      case TriangleQueryKind::through_edge:
        ASSERT_TRUE(zero_pis(o) >= 1 || sgn(o.den) == 0) << triangle_line(q);
        special += o.answer.location >= TriangleLocation::edge_ab && o.answer.location <= TriangleLocation::edge_ca;
        break;
      case TriangleQueryKind::through_interior:
        special += o.answer.location == TriangleLocation::inside;
        break;
      case TriangleQueryKind::origin_on_triangle:
        ASSERT_EQ(sgn(o.num), 0) << triangle_line(q);
        special += sgn(o.den) != 0;
        break;
      case TriangleQueryKind::degenerate:
        ASSERT_TRUE(degenerate) << triangle_line(q);
        ++special;
        break;
      case TriangleQueryKind::parallel:
        ASSERT_EQ(sgn(o.den), 0) << triangle_line(q);
        special += o.answer.relation == TriangleRelation::parallel;
        break;
      case TriangleQueryKind::coplanar:
        ASSERT_EQ(sgn(o.den), 0) << triangle_line(q);
        ASSERT_EQ(sgn(o.num), 0) << triangle_line(q);
        special += o.answer.relation == TriangleRelation::coplanar;
        break;
      case TriangleQueryKind::above_power_of_two:
        // t or one barycentric coordinate just above a power of two (the relabelling moves a's coordinate).
        if (sgn(o.den) == 0) break;
        special += test_support::just_above_power_of_two(o.num / o.den) ||
                   test_support::just_above_power_of_two(o.pi_a / o.den) ||
                   test_support::just_above_power_of_two(o.pi_b / o.den) ||
                   test_support::just_above_power_of_two(o.pi_c / o.den);
        break;
      case TriangleQueryKind::rounding_tie: {
        // t = num/den halfway between two doubles (unless the origin was nudged, a quarter of the time): the
        // two neighbours of RN(t) around t are at equal distance.
        if (sgn(o.den) == 0) break;
        const mpq_class t = o.num / o.den;
        const double r = test_support::round_by_integer_division(t);
        const double other = (mpq_class(r) < t) ? std::nextafter(r, HUGE_VAL) : std::nextafter(r, -HUGE_VAL);
        special += abs(mpq_class(r) - t) == abs(mpq_class(other) - t);
        break;
      }
      case TriangleQueryKind::near_vertex:
      case TriangleQueryKind::near_edge:
        // Near a vertex or an edge but (mostly) not on it.
        special += zero_pis(o) == 0 && sgn(o.den) != 0;
        break;
      case TriangleQueryKind::sliver:
      case TriangleQueryKind::needle: {
        // Not degenerate, but nearly: for a sliver |N| < 2^-40·|b − a|·|c − a| (a vertex near the opposite
        // edge), for a needle one edge shorter than 2^-40 of another (compared squared, exactly). The vertices
        // are relabelled after the construction, so every pair of edges is tried.
        if (degenerate) break;
        const test_support::Q3 a = test_support::q3(q.triangle.a), b = test_support::q3(q.triangle.b),
                               c = test_support::q3(q.triangle.c);
        const mpq_class e[3] = {dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)};
        const mpq_class scale = mpq_class(mpz_class(1) << 80);
        if (kind == TriangleQueryKind::sliver) {
          special += dot(o.normal, o.normal) * scale < e[0] * e[2];
        } else {
          bool short_edge = false;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) short_edge = short_edge || e[i] * scale < e[j];
          special += short_edge;
        }
        break;
      }
      case TriangleQueryKind::tiny:
      case TriangleQueryKind::huge: {
        // Every coordinate scaled far out: some difference of the inputs underflows or overflows in a product.
        const double m = std::fabs(q.triangle.a.x) + std::fabs(q.triangle.b.y) + std::fabs(q.ray.origin.z);
        special += kind == TriangleQueryKind::tiny ? m < 0x1p-900 : m > 0x1p850;
        break;
      }
      default: ++special; break;
    }
  }
  const double share = static_cast<double>(special) / n;
  RecordProperty("share_with_property", std::to_string(share));
  EXPECT_GT(share, kind == TriangleQueryKind::rounding_tie ? 0.5 : 0.6) << to_string(kind);
}

INSTANTIATE_TEST_SUITE_P(All, TriangleKinds, ::testing::ValuesIn(all_triangle_query_kinds),
                         [](const ::testing::TestParamInfo<TriangleQueryKind>& info) {
                           std::string name(to_string(info.param));
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(TriangleFuzzDecoder, EncodersInvertTheDecoder) {
  const TriangleQuery q{{{1, -0.0, std::bit_cast<double>(0x7ff8000000000123ULL)}, {0x1p-1074, 2, 3}},
                        {{4, 5, 6}, {7, 8, 9}, {10, 11, -HUGE_VAL}}};
  const std::vector<std::uint8_t> raw = encode_raw_fuzz_input(q);
  ASSERT_EQ(raw.size(), raw_triangle_fuzz_input_size);
  const FuzzTriangleQuery f = decode_fuzz_triangle_query(raw);
  EXPECT_FALSE(f.kind.has_value());
  EXPECT_EQ(std::memcmp(&f.query, &q, sizeof q), 0);
  const std::uint64_t words[3] = {1, 2, 3};
  const std::vector<std::uint8_t> hard = encode_hard_triangle_fuzz_input(TriangleQueryKind::sliver, words);
  const FuzzTriangleQuery g = decode_fuzz_triangle_query(hard);
  ASSERT_TRUE(g.kind.has_value());
  EXPECT_EQ(*g.kind, TriangleQueryKind::sliver);
  std::size_t i = 0;
  const TriangleQuery expected =
      make_triangle_query(TriangleQueryKind::sliver, [&i] { return i < 3 ? std::uint64_t{++i} : std::uint64_t{0}; });
  EXPECT_EQ(std::memcmp(&g.query, &expected, sizeof expected), 0);
  EXPECT_EQ(decode_fuzz_triangle_query({}).query.ray.direction.x, 0.0);  // empty input: raw zeros
}

TEST(TriangleReferenceCheckTest, ReportsAWrongRelationUnderItsRule) {
  // The unit triangle's edge bc at (1/2, 1/2) (tests/triangle_test.cpp): owned miss, closed hit.
  const TriangleQuery q{{{0.5, 0.5, -1}, {0, 0, 1}}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  const TriangleIntersection closed_hit = intersect_exact(q.ray, q.triangle, {TriangleRule::closed, true, true});
  EXPECT_TRUE(check_against_reference(q, closed_hit, TriangleRule::closed).passed());
  const TriangleReferenceCheck c = check_against_reference(q, closed_hit, TriangleRule::owned);
  EXPECT_FALSE(c.passed());
  EXPECT_FALSE(c.relation_matches);
  const std::string report = c.report();
  EXPECT_NE(report.find("relation is hit, expected miss (owned rule)"), std::string::npos) << report;
  EXPECT_NE(report.find("raykernel triangle --rule=owned --exact --hex"), std::string::npos) << report;
  EXPECT_NE(report.find("t = 1/1"), std::string::npos) << report;
}

TEST(TriangleReferenceCheckTest, MeasuresUlpsAndIgnoresWhatWasNotComputed) {
  // t = 1/3 (d = (0, 0, 3)); an answer one ulp above, and an answer without coordinates (NaN: not judged).
  const TriangleQuery q{{{0.25, 0.25, -1}, {0, 0, 3}}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  TriangleIntersection got = intersect(q.ray, q.triangle);
  got.t = std::nextafter(got.t, 1.0);
  got.barycentric = {std::nan(""), std::nan(""), std::nan("")};
  const TriangleReferenceCheck strict = check_against_reference(q, got, TriangleRule::owned, 0);
  EXPECT_FALSE(strict.passed());
  ASSERT_TRUE(strict.ulps[0].has_value());
  EXPECT_EQ(*strict.ulps[0], 1u);
  EXPECT_FALSE(strict.ulps[1].has_value());
  EXPECT_TRUE(check_against_reference(q, got, TriangleRule::owned, 1).passed());
  // Möller–Trumbore answers are judged without the location and owned flag if asked.
  const TriangleIntersection naive = intersect_naive(q.ray, q.triangle);
  EXPECT_TRUE(check_against_reference(q, naive, TriangleRule::closed, 4, false).relation_matches);
}

}  // namespace
}  // namespace raykernel::testkit
