// Ray–sphere (docs/contract.md §10): hand-derived cases (each expected value derived in the comment beside it,
// never from the code), the contract's sample through the CLI's stream code, every testkit construction's
// promise checked with exact rationals, the exact reference's roundings against an independent oracle (the side
// of each root at the midpoints beside its rounding), the certified cascade against the exact reference
// (RapidCheck, every hard kind), and the answers in other floating-point environments.
#include "support/answer_lines.hpp"
#include "commands/sphere.hpp"
#include "sphere/ray_sphere_boundary_filter.hpp"
#include "common/exit_status.hpp"

#include "sphere/exact_sphere.hpp"
#include "sphere/ray_sphere_cascade.hpp"
#include "sphere/ray_sphere_filter.hpp"
#include "sphere/ray_sphere_formula.hpp"

#include <raykernel/sphere.hpp>
#include <raykernel/testkit/plane_rapidcheck.hpp>
#include <raykernel/testkit/sphere_queries.hpp>
#include <raykernel/testkit/plane_reference_check.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace raykernel {
namespace {

using testkit::hex_string;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double max_double = std::numeric_limits<double>::max();

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

std::string text(const SphereIntersection& a) {
  std::string s = std::string(to_string(a.origin)) + " " + std::string(to_string(a.relation));
  if (a.relation != SphereRelation::miss) s += " " + hex_string(a.t1) + " " + hex_string(a.t2);
  return s;
}

// Both the certified and the exact answer are `want` (roots bit for bit: the sign of a zero counts).
void expect_both(const Ray& ray, const Sphere& sphere, const SphereIntersection& want) {
  for (const SphereIntersection& got : {intersect(ray, sphere), intersect_exact(ray, sphere)}) {
    EXPECT_EQ(text(got), text(want)) << testkit::hex_string(ray.origin.x);
  }
  const SphereClassification c = relation(ray, sphere);
  EXPECT_EQ(c.origin, want.origin);
  EXPECT_EQ(c.relation, want.relation);
}

const Ray x_axis{{0, 0, 0}, {1, 0, 0}};

TEST(SphereHandDerived, CrossesAlongAnAxis) {
  // f = (−5, 0, 0), A = 1, B = −5, C = 25 − 1 = 24, D = 25 − 24 = 1: roots 5 ∓ 1.
  expect_both(x_axis, Sphere{{5, 0, 0}, 1}, {SphereOrigin::outside, SphereRelation::cross, 4, 6});
  // The direction (2, 0, 0): A = 4, B = −10, C = 24, D = 100 − 96 = 4: roots (10 ∓ 2)/4 = 2, 3.
  expect_both({{0, 0, 0}, {2, 0, 0}}, Sphere{{5, 0, 0}, 1}, {SphereOrigin::outside, SphereRelation::cross, 2, 3});
  // The origin at the centre, r = 2: C = −4 < 0, B = 0, D = 4: roots ∓2.
  expect_both(x_axis, Sphere{{0, 0, 0}, 2}, {SphereOrigin::inside, SphereRelation::cross, -2, 2});
}

TEST(SphereHandDerived, TangentExactlyAndAnUlpOff) {
  // o = (0, 1, 0), d = (1, 0, 0), c = (5, 0, 0), r = 1: f = (−5, 1, 0), B = −5, C = 25 + 1 − 1 = 25,
  // D = 25 − 25 = 0: tangent at t0 = 5.
  const Sphere s{{5, 0, 0}, 1};
  expect_both({{0, 1, 0}, {1, 0, 0}}, s, {SphereOrigin::outside, SphereRelation::tangent, 5, 5});
  // o_y = 1 + 2^-52: C = 25 + (1 + 2^-52)² − 1 > 25 = B²: D < 0, a miss.
  const SphereIntersection miss = intersect(Ray{{0, 1 + 0x1p-52, 0}, {1, 0, 0}}, s);
  EXPECT_EQ(miss.relation, SphereRelation::miss);
  EXPECT_TRUE(std::isnan(miss.t1) && std::isnan(miss.t2));
  EXPECT_EQ(intersect_exact(Ray{{0, 1 + 0x1p-52, 0}, {1, 0, 0}}, s).relation, SphereRelation::miss);
  // o_y = 1 − 2^-53: D = 1 − (1 − 2^-53)² = 2^-52 − 2^-106, √D = 2^-26·√(1 − 2^-54) = 2^-26 − ε with
  // 0 < ε < 2^-80, far below half an ulp of 5 (2^-51): the roots round to 5 ∓ 2^-26, both doubles.
  expect_both({{0, 1 - 0x1p-53, 0}, {1, 0, 0}}, s,
              {SphereOrigin::outside, SphereRelation::cross, 5 - 0x1p-26, 5 + 0x1p-26});
}

TEST(SphereHandDerived, OriginOnTheSurface) {
  // o = (1, 0, 0) on the unit sphere: C = 0. d = (−1, 0, 0): B = −1, D = 1, roots 1 ∓ 1 = +0, 2.
  expect_both({{1, 0, 0}, {-1, 0, 0}}, Sphere{{0, 0, 0}, 1}, {SphereOrigin::on_surface, SphereRelation::cross, 0.0, 2});
  // d = (1, 0, 0): B = 1, roots −1 ∓ 1 = −2 and an exact 0, which is +0.
  const SphereIntersection a = intersect(Ray{{1, 0, 0}, {1, 0, 0}}, Sphere{{0, 0, 0}, 1});
  EXPECT_EQ(bits(a.t2), bits(0.0));
  expect_both({{1, 0, 0}, {1, 0, 0}}, Sphere{{0, 0, 0}, 1}, {SphereOrigin::on_surface, SphereRelation::cross, -2, 0.0});
  // d = (0, 1, 0) at (1, 0, 0): B = 0, C = 0, D = 0: tangent at +0.
  expect_both({{1, 0, 0}, {0, 1, 0}}, Sphere{{0, 0, 0}, 1}, {SphereOrigin::on_surface, SphereRelation::tangent, 0.0, 0.0});
}

TEST(SphereHandDerived, FarAwaySphereWhoseCCancels) {
  // c = (2^52, 0, 0), r = 2^52 − 1: C = 2^104 − (2^52 − 1)² = 2^53 − 1 exactly, D = 2^104 − (2^53 − 1) =
  // (2^52 − 1)², roots 2^52 ∓ (2^52 − 1) = 1 and 2^53 − 1. (In doubles r² rounds to 2^104 − 2^53.)
  expect_both(x_axis, Sphere{{0x1p52, 0, 0}, 0x1p52 - 1},
              {SphereOrigin::outside, SphereRelation::cross, 1, 0x1p53 - 1});
}

TEST(SphereHandDerived, RootsOnRoundingTies) {
  // c = (2^53, 0, 0), r = 1: roots 2^53 ∓ 1. 2^53 − 1 is a double; 2^53 + 1 is the midpoint of 2^53 and
  // 2^53 + 2, whose significands end in 0 and 1: ties to even give 2^53.
  expect_both(x_axis, Sphere{{0x1p53, 0, 0}, 1}, {SphereOrigin::outside, SphereRelation::cross, 0x1p53 - 1, 0x1p53});
  // r = 3: 2^53 − 3 is a double; 2^53 + 3 lies midway between 2^53 + 2 (odd significand) and 2^53 + 4 (even).
  expect_both(x_axis, Sphere{{0x1p53, 0, 0}, 3}, {SphereOrigin::outside, SphereRelation::cross, 0x1p53 - 3, 0x1p53 + 4});
  // c = (2^-1073, 0, 0), r = 2^-1074, d = (2, 0, 0): A = 4, B = −2^-1072, C = 2^-2146 − 2^-2148 = 3·2^-2148,
  // D = 2^-2144 − 12·2^-2148 = 2^-2146, roots (2^-1072 ∓ 2^-1073)/4 = 2^-1075 and 3·2^-1075: the first is the
  // midpoint of +0 and 2^-1074 (to +0, the even one), the second of 2^-1074 and 2^-1073 (to 2^-1073).
  expect_both({{0, 0, 0}, {2, 0, 0}}, Sphere{{0x1p-1073, 0, 0}, 0x1p-1074},
              {SphereOrigin::outside, SphereRelation::cross, 0.0, 0x1p-1073});
  // Mirrored: roots −3·2^-1075 (to −2^-1073) and −2^-1075, which rounds to zero and keeps its sign: −0.
  expect_both({{0, 0, 0}, {2, 0, 0}}, Sphere{{-0x1p-1073, 0, 0}, 0x1p-1074},
              {SphereOrigin::outside, SphereRelation::cross, -0x1p-1073, -0.0});
}

TEST(SphereHandDerived, SubnormalCentreCoordinateBreaksATie) {
  // c = (4, 0, ε) with ε = 3·2^-1074, r = 1 + 3·2^-52: roots 4 ∓ √(r² − ε²). Without ε, t1 = 3 − 3·2^-52 is the
  // midpoint of 3 − 2^-50 (even significand) and 3 − 2^-51 (odd): ties to even would give 3 − 2^-50. With ε > 0,
  // √(r² − ε²) < r, so t1 lies just above the midpoint: 3 − 2^-51. (ε² underflows in binary64: the expansions
  // are not exact here, and must not decide; found by fuzz_sphere.) t2 = 5 + 3·2^-52 − δ with 0 < δ < ε²/r, i.e.
  // 5 + 0.75 ulp(5) minus a hair: 5 + 2^-50.
  expect_both(x_axis, Sphere{{4, 0, 0x3p-1074}, 1 + 0x3p-52},
              {SphereOrigin::outside, SphereRelation::cross, 3 - 0x1p-51, 5 + 0x1p-50});
}

TEST(SphereHandDerived, RootsBeyondTheDoubleRange) {
  // c = (M, 0, 0) with M = 2^1024 − 2^971 the largest double, r = 2^970: roots M ∓ 2^970, each the midpoint of
  // M and a neighbour. M − 2^970 lies between M − 2^971 (even significand) and M (odd): M − 2^971. M + 2^970 =
  // 2^1024 − 2^970, between M (odd) and 2^1024 (even, beyond the range): ties to even overflow to +inf.
  expect_both(x_axis, Sphere{{max_double, 0, 0}, 0x1p970},
              {SphereOrigin::outside, SphereRelation::cross, max_double - 0x1p971, inf});
  // r = 2^969: M + 2^969 is below that midpoint: M. M − 2^969 is above M − 2^970: M.
  expect_both(x_axis, Sphere{{max_double, 0, 0}, 0x1p969},
              {SphereOrigin::outside, SphereRelation::cross, max_double, max_double});
  // d = (−1, 0, 0): the roots are −M ∓ 2^970: −inf and −(M − 2^971).
  expect_both({{0, 0, 0}, {-1, 0, 0}}, Sphere{{max_double, 0, 0}, 0x1p970},
              {SphereOrigin::outside, SphereRelation::cross, -inf, -(max_double - 0x1p971)});
}

TEST(SphereHandDerived, TinyAndHugeDirections) {
  // Scaling d by 2^k divides every root by 2^k exactly (A by 2^2k, B by 2^k, D by 2^2k).
  for (int k : {-500, -300, 300, 500}) {
    const double s = std::ldexp(1.0, k);
    expect_both({{0, 0, 0}, {s, 0, 0}}, Sphere{{5, 0, 0}, 1},
                {SphereOrigin::outside, SphereRelation::cross, std::ldexp(4.0, -k), std::ldexp(6.0, -k)});
  }
  // An irrational pair scaled: o = (0, 1, 0), c = (5, 0, 0), r = 2: D = 4 − 1 = 3, roots 5 ∓ √3 =
  // 3.26794919243112270647... and 6.73205080756887729352..., whose roundings (strtod of those 30-digit decimals:
  // 0x1.a24c28bd3d9abp+1 = 3.267949192431123 and 0x1.aed9eba16132bp+2 = 6.732050807568878) scale exactly by 2^-k.
  const double t1 = 0x1.a24c28bd3d9abp+1, t2 = 0x1.aed9eba16132bp+2;
  EXPECT_EQ(t1, std::strtod("3.267949192431122706472553658494", nullptr));
  EXPECT_EQ(t2, std::strtod("6.732050807568877293527446341506", nullptr));
  for (int k : {0, -400, 400}) {
    const double s = std::ldexp(1.0, k);
    expect_both({{0, 1, 0}, {s, 0, 0}}, Sphere{{5, 0, 0}, 2},
                {SphereOrigin::outside, SphereRelation::cross, std::ldexp(t1, -k), std::ldexp(t2, -k)});
  }
}

TEST(SphereInvalid, EveryReasonIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Sphere unit{{0, 0, 0}, 1};
  EXPECT_EQ(validate(Ray{{nan, 0, 0}, {1, 0, 0}}, unit).value_or(""), "ray origin x is NaN");
  EXPECT_EQ(validate(Ray{{0, 0, 0}, {0, 0, 0}}, unit).value_or(""), "ray direction is the zero vector");
  EXPECT_EQ(validate(x_axis, Sphere{{0, inf, 0}, 1}).value_or(""), "sphere center y is +inf");
  EXPECT_EQ(validate(x_axis, Sphere{{0, 0, 0}, -inf}).value_or(""), "sphere radius is -inf");
  EXPECT_EQ(validate(x_axis, Sphere{{0, 0, 0}, nan}).value_or(""), "sphere radius is NaN");
  for (double r : {0.0, -0.0, -1.0, -0x1p-1074})
    EXPECT_EQ(validate(x_axis, Sphere{{0, 0, 0}, r}).value_or(""), "sphere radius is not positive") << r;
  EXPECT_FALSE(validate(x_axis, Sphere{{0, 0, 0}, 0x1p-1074}).has_value());  // a subnormal radius is valid
  EXPECT_THROW((void)intersect(x_axis, Sphere{{0, 0, 0}, 0.0}), invalid_input);
  EXPECT_THROW((void)intersect_exact(Ray{{0, 0, 0}, {0, 0, 0}}, unit), invalid_input);
  EXPECT_THROW((void)relation(x_axis, Sphere{{0, 0, nan}, 1}), invalid_input);
}

// The fast paths run before validation (ray_sphere_cascade.hpp, fast_sphere_relation for relation() and
// sphere_intersection_filtered for intersect()): they must answer nothing for every invalid input, so that
// validation names it. Each of the ten numbers of otherwise valid
// queries (crossing, missing, tangent-ish, huge and tiny ones, which the filter certifies) replaced by NaN, ±inf,
// and the direction by zero, the radius by 0, −0, negatives: never certified, and relation() and intersect() throw.
TEST(SphereFastPath, InvalidInputIsNeverCertified) {
  SphereIntersection out{};
  const auto filtered = [&out](const Ray& ray, const Sphere& sphere) {
    return detail::sphere_intersection_filtered(ray, sphere, out);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<Ray, Sphere>> bases{
      {Ray{{-5, 0, 0}, {1, 0, 0}}, Sphere{{0, 0, 0}, 1}},        {Ray{{-5, 3, 0}, {1, 0, 0}}, Sphere{{0, 0, 0}, 1}},
      {Ray{{0.25, 0, 0}, {0, 1, 0}}, Sphere{{0, 0, 0}, 1}},       {Ray{{1e70, 0, 0}, {-1e70, 0, 0}}, Sphere{{0, 0, 0}, 5e69}},
      {Ray{{-1e-70, 0, 0}, {1e-70, 0, 0}}, Sphere{{0, 0, 0}, 1e-71}}, {Ray{{2, 2, 2}, {-1, -1, -1}}, Sphere{{0, 0, 0}, 3}}};
  int certified_valid = 0, checked = 0;
  for (const auto& [ray0, sphere0] : bases) {
    ASSERT_TRUE(detail::fast_sphere_relation(ray0, sphere0).has_value()) << certified_valid;  // the filter decides the valid base
    ASSERT_TRUE(filtered(ray0, sphere0)) << certified_valid;
    ++certified_valid;
    for (int k = 0; k < 10; ++k)
      for (double bad : {nan, -nan, inf, -inf}) {
        Ray ray = ray0;
        Sphere sphere = sphere0;
        double* slot[10] = {&ray.origin.x, &ray.origin.y, &ray.origin.z, &ray.direction.x, &ray.direction.y,
                            &ray.direction.z, &sphere.center.x, &sphere.center.y, &sphere.center.z, &sphere.radius};
        *slot[k] = bad;
        EXPECT_FALSE(detail::fast_sphere_relation(ray, sphere).has_value()) << k << " " << bad;
        EXPECT_FALSE(filtered(ray, sphere)) << k << " " << bad;
        EXPECT_THROW((void)relation(ray, sphere), invalid_input) << k << " " << bad;
        EXPECT_THROW((void)intersect(ray, sphere), invalid_input) << k << " " << bad;
        ++checked;
      }
    Ray still = ray0;
    still.direction = {0, 0, 0};
    EXPECT_FALSE(detail::fast_sphere_relation(still, sphere0).has_value());
    EXPECT_FALSE(filtered(still, sphere0));
    EXPECT_THROW((void)relation(still, sphere0), invalid_input);
    EXPECT_THROW((void)intersect(still, sphere0), invalid_input);
    for (double r : {0.0, -0.0, -sphere0.radius, -0x1p-1074, -1e300}) {
      const Sphere bad{sphere0.center, r};
      EXPECT_FALSE(detail::fast_sphere_relation(ray0, bad).has_value()) << r;
      EXPECT_FALSE(filtered(ray0, bad)) << r;
      EXPECT_THROW((void)relation(ray0, bad), invalid_input) << r;
      EXPECT_THROW((void)intersect(ray0, bad), invalid_input) << r;
      ++checked;
    }
  }
  EXPECT_EQ(certified_valid, 6);
  EXPECT_EQ(checked, 6 * (40 + 5));
}

// The contract's sample through the stream code of `raykernel sphere --exact` (check-cases' comparison: the
// word after invalid is free, roots as doubles with the sign of a zero, U V exactly).
TEST(SphereSample, MatchesTheContract) {
  const std::string dir = RAYKERNEL_CASES_DIR;
  std::ifstream in(dir + "/sphere-sample.txt");
  ASSERT_TRUE(in) << "missing sample";
  std::ostringstream out, err;
  cli::SphereCommandOptions options;
  options.exact = true;
  cli::SphereCounts counts;
  EXPECT_EQ(cli::sphere_stream(in, out, err, options, counts), cli::exit_invalid_line);
  std::istringstream got_lines(out.str());
  const std::vector<std::string> want = test_support::read_lines(dir + "/sphere-sample.expected");
  std::size_t line = 0, wrong = 0;
  for (std::string got; std::getline(got_lines, got); ++line) {
    ASSERT_LT(line, want.size());
    const auto g = test_support::words(got), w = test_support::words(want[line]);
    bool same = !g.empty() && !w.empty() && g[0] == w[0];
    if (same && w[0] != "invalid") {
      same = g.size() == w.size() && g[1] == w[1];
      for (std::size_t k = 2; same && k < w.size(); ++k) {
        const bool root = w[1] != "miss" && k + 2 < w.size();
        if (root) {
          const double a = std::strtod(g[k].c_str(), nullptr), b = std::strtod(w[k].c_str(), nullptr);
          same = bits(a) == bits(b);
        } else {
          mpq_class p, q;
          same = test_support::parse_rational(g[k], p) && test_support::parse_rational(w[k], q) && p == q;
        }
      }
    }
    if (!same) {
      ++wrong;
      ADD_FAILURE() << "line " << line + 1 << ": got '" << got << "', want '" << want[line] << "'";
    }
  }
  EXPECT_EQ(line, want.size());
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(counts.relation[static_cast<int>(SphereRelation::tangent)], 0u);
}

// RN(t) = x, checked from the exact sides of t at the midpoints beside x (exact::root_side_of_midpoint): t
// strictly between them, or on one with x's significand even. For normal x below the largest double.
::testing::AssertionResult is_rounding_of_root(const Ray& ray, const Sphere& sphere, int root, double x) {
  if (!(std::fabs(x) >= 0x1p-1021 && std::fabs(x) < max_double)) return ::testing::AssertionSuccess();
  const double up = std::nextafter(x, inf), down = std::nextafter(x, -inf);
  const bool even = (bits(x) & 1) == 0;
  const int above = detail::exact::root_side_of_midpoint(ray, sphere, root, x, up);
  const int below = detail::exact::root_side_of_midpoint(ray, sphere, root, down, x);
  if (above > 0 || below < 0 || (above == 0 && !even) || (below == 0 && !even))
    return ::testing::AssertionFailure() << "root " << root << " rounded to " << hex_string(x) << ": side above "
                                         << above << ", below " << below;
  return ::testing::AssertionSuccess();
}

std::vector<testkit::SphereQuery> queries_of_every_kind(std::size_t per_kind, std::uint64_t seed) {
  std::vector<testkit::SphereQuery> q;
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource source = [&rng] { return rng(); };
  for (testkit::SphereQueryKind kind : testkit::all_sphere_query_kinds)
    for (std::size_t i = 0; i < per_kind; ++i) q.push_back(testkit::make_sphere_query(kind, source));
  return q;
}

TEST(SphereExact, RoundsEveryRootAsTheMidpointOracleSays) {
  std::size_t roots = 0;
  for (const testkit::SphereQuery& q : queries_of_every_kind(300, 11)) {
    const SphereIntersection e = intersect_exact(q.ray, q.sphere);
    if (e.relation == SphereRelation::miss) continue;
    EXPECT_TRUE(is_rounding_of_root(q.ray, q.sphere, -1, e.t1)) << testkit::sphere_line(q);
    EXPECT_TRUE(is_rounding_of_root(q.ray, q.sphere, +1, e.t2)) << testkit::sphere_line(q);
    roots += 2;
  }
  EXPECT_GT(roots, 2000u);
}

// Each construction's promise, exactly.
TEST(SphereQueries, KeepTheirPromises) {
  testkit::SplitMix64 rng(5);
  const testkit::BitSource source = [&rng] { return rng(); };
  int ties = 0;
  for (int i = 0; i < 400; ++i) {
    const testkit::SphereQuery t = testkit::make_sphere_query(testkit::SphereQueryKind::tangent, source);
    EXPECT_EQ(intersect_exact(t.ray, t.sphere).relation, SphereRelation::tangent) << testkit::sphere_line(t);
    const testkit::SphereQuery s = testkit::make_sphere_query(testkit::SphereQueryKind::on_surface, source);
    EXPECT_EQ(intersect_exact(s.ray, s.sphere).origin, SphereOrigin::on_surface) << testkit::sphere_line(s);
    const testkit::SphereQuery r = testkit::make_sphere_query(testkit::SphereQueryKind::rounding_tie, source);
    const SphereIntersection e = intersect_exact(r.ray, r.sphere);
    ASSERT_EQ(e.relation, SphereRelation::cross) << testkit::sphere_line(r);
    for (int root : {-1, 1}) {
      const double x = root < 0 ? e.t1 : e.t2;
      for (const double y : {std::nextafter(x, inf), std::nextafter(x, -inf)})
        ties += detail::exact::root_side_of_midpoint(r.ray, r.sphere, root, std::min(x, y), std::max(x, y)) == 0;
    }
  }
  EXPECT_GT(ties, 300);  // most tie constructions have an odd chord (the rest give exact roots)
  // A subnormal offset breaks every tie: no root lies on a midpoint of its neighbours.
  for (int i = 0; i < 400; ++i) {
    const testkit::SphereQuery o = testkit::make_sphere_query(testkit::SphereQueryKind::subnormal_offset, source);
    const SphereIntersection e = intersect_exact(o.ray, o.sphere);
    ASSERT_EQ(e.relation, SphereRelation::cross) << testkit::sphere_line(o);
    for (int root : {-1, 1}) {
      const double x = root < 0 ? e.t1 : e.t2;
      for (const double y : {std::nextafter(x, inf), std::nextafter(x, -inf)})
        EXPECT_NE(detail::exact::root_side_of_midpoint(o.ray, o.sphere, root, std::min(x, y), std::max(x, y)), 0)
            << testkit::sphere_line(o);
    }
  }
}

// Where the expansion stage is exact (README, "Ray–sphere"): every query of the kinds whose inputs have exponents
// in [−150, 150] and no subnormal component is decided without GMP, relation and roots; a near-tangent query
// reaches GMP only when its nudge made a zero component subnormal (a product below 2^-969). The kinds scaled out
// of range (tiny, huge, and the directions scaled by 2^±400..600) may reach it.
TEST(SphereStages, InRangeKindsNeverReachTheExactStage) {
  testkit::SplitMix64 rng(7);
  const testkit::BitSource source = [&rng] { return rng(); };
  auto has_subnormal = [](const testkit::SphereQuery& q) {
    for (double x : {q.ray.origin.x, q.ray.origin.y, q.ray.origin.z, q.ray.direction.x, q.ray.direction.y,
                     q.ray.direction.z, q.sphere.center.x, q.sphere.center.y, q.sphere.center.z, q.sphere.radius})
      if (x != 0 && std::fabs(x) < 0x1p-1022) return true;
    return false;
  };
  using K = testkit::SphereQueryKind;
  std::size_t with_roots = 0;
  for (K kind : {K::random, K::tangent, K::near_tangent, K::on_surface, K::near_surface, K::rounding_tie,
                 K::far_cancel, K::wide_exponents}) {
    for (int i = 0; i < 1000; ++i) {
      const testkit::SphereQuery q = testkit::make_sphere_query(kind, source);
      const TracedSphereIntersection t = intersect_traced(q.ray, q.sphere);
      with_roots += t.intersection.relation != SphereRelation::miss;
      if (kind == K::near_tangent && has_subnormal(q)) continue;
      EXPECT_NE(t.relation_stage, Stage::exact) << testkit::to_string(kind) << ": " << testkit::sphere_line(q);
      EXPECT_NE(t.rounding_stage, Stage::exact) << testkit::to_string(kind) << ": " << testkit::sphere_line(q);
    }
  }
  EXPECT_GT(with_roots, 4000u);
}

// The filter's bound where Â underflows to 0 (d = (2^-600, 0, 0): A = 2^-1200) and B̂² alone looks certain: with
// f = o − c = (2^500, 2^500, 0) and r = 1, B = 2^-100, B² = 2^-200 and A·C = 2^-1200·(2^1001 − 1), so
// D = 2^-200 − 2^-199 + 2^-1200 = −2^-200 + 2^-1200 < 0: a miss. A bound made of relative terms only (κ·(m_B² + Â·P_C))
// would certify D̂ = 2^-200 positive; E_D's floor θ (SphereFilter.v, `floor_covers`) keeps Â's absolute error in it.
// And the mirror case, B² just above A·C: f = (2^500, 0, 0),
// D = 2^-200 − 2^-1200·(2^1000 − 1) = 2^-1200 > 0, a crossing the filter must not call a miss either.
TEST(SphereHandDerived, FilterBoundCoversAnUnderflowedA) {
  const double tiny = std::ldexp(1.0, -600), big = std::ldexp(1.0, 500);
  {
    const Ray ray{{big, big, 0}, {tiny, 0, 0}};
    const Sphere sphere{{0, 0, 0}, 1};
    const detail::SphereFilterSigns f = detail::sphere_filter(ray, sphere);
    EXPECT_NE(f.d, detail::Sign::positive);
    EXPECT_EQ(relation(ray, sphere).relation, SphereRelation::miss);
    EXPECT_EQ(intersect(ray, sphere).relation, SphereRelation::miss);
  }
  {
    const Ray ray{{big, 0, 0}, {tiny, 0, 0}};
    const Sphere sphere{{0, 0, 0}, 1};
    const detail::SphereFilterSigns f = detail::sphere_filter(ray, sphere);
    EXPECT_NE(f.d, detail::Sign::negative);
    EXPECT_EQ(relation(ray, sphere).relation, SphereRelation::cross);
  }
}

// Stage 1 (sphere/ray_sphere_filter.hpp): the binary64 filter of the signs of C and D decides the relation of nearly
// every random query, each sign it certifies is the exact one, and the cascade takes it (relation_stage filter).
TEST(SphereStages, FilterDecidesRandomQueries) {
  testkit::SplitMix64 rng(11);
  const testkit::BitSource source = [&rng] { return rng(); };
  int filtered = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const testkit::SphereQuery q = testkit::make_sphere_query(testkit::SphereQueryKind::random, source);
    const detail::SphereFilterSigns f = detail::sphere_filter(q.ray, q.sphere);
    const TracedSphereIntersection traced = intersect_traced(q.ray, q.sphere);
    const bool decided = detail::is_certain(f.c) && detail::is_certain(f.d);
    EXPECT_EQ(traced.relation_stage == Stage::filter, decided) << testkit::sphere_line(q);
    if (!decided) continue;
    ++filtered;
    const SphereIntersection exact = detail::exact::intersect_sphere(q.ray, q.sphere);
    EXPECT_EQ(detail::sphere_relation(static_cast<int>(f.d)), exact.relation) << testkit::sphere_line(q);
    EXPECT_EQ(detail::sphere_origin(static_cast<int>(f.c)), exact.origin) << testkit::sphere_line(q);
  }
  std::printf("sphere filter: %d of %d random queries\n", filtered, n);
  EXPECT_GE(filtered, n * 99 / 100);
}

// The roots' filter (sphere/ray_sphere_boundary_filter.hpp): at the midpoints beside each correctly rounded root
// and a few ulps further, on every kind, each side it certifies is the exact side (exact::root_side_of_midpoint),
// an exact tie (a root on a midpoint, q(m) = 0) is never certified, and on random queries it decides every side
// beside the roots, so that the cascade rounds them there (rounding_stage filter).
TEST(SphereStages, BoundaryFilterSidesAreExact) {
  int certified = 0, compared = 0, random_sides = 0, random_decided = 0, ties = 0;
  const std::vector<testkit::SphereQuery> queries = queries_of_every_kind(300, 41);
  for (std::size_t n = 0; n < queries.size(); ++n) {
    const testkit::SphereQuery& q = queries[n];
    const SphereIntersection exact = detail::exact::intersect_sphere(q.ray, q.sphere);
    if (exact.relation == SphereRelation::miss) continue;
    const bool random = n < 300;  // all_sphere_query_kinds starts with random
    for (int root : {-1, 1}) {
      const double t = root < 0 ? exact.t1 : exact.t2;
      if (!std::isfinite(t) || t == 0) continue;
      double x = t;
      for (int k = 0; k < 3; ++k) x = std::nextafter(x, -INFINITY);
      for (int k = 0; k < 6; ++k) {
        const double y = std::nextafter(x, INFINITY);
        const detail::Sign side = detail::sphere_root_side_filtered(q.ray, q.sphere, root, x, y);
        const int want = detail::exact::root_side_of_midpoint(q.ray, q.sphere, root, x, y);
        ++compared;
        ties += want == 0;
        if (random && (x == t || y == t)) {
          ++random_sides;
          random_decided += detail::is_certain(side);
        }
        if (detail::is_certain(side)) {
          ++certified;
          EXPECT_NE(side, detail::Sign::zero);
          EXPECT_EQ(static_cast<int>(side), want) << testkit::sphere_line(q) << " root " << root << " at "
                                                  << testkit::hex_string(x) << " " << testkit::hex_string(y);
        }
        x = y;
      }
    }
  }
  std::printf("boundary filter: %d of %d sides certified, %d of %d beside random roots, %d ties\n", certified,
              compared, random_decided, random_sides, ties);
  EXPECT_GT(ties, 100);  // the rounding-tie kinds put roots on midpoints: never certified (checked above)
  EXPECT_GT(certified, compared / 3);  // the hard kinds sit near ties and tangents
  EXPECT_EQ(random_decided, random_sides);
  EXPECT_GT(random_sides, 100);
}

// The boundary filter's error bound itself, against 4q(m) in rationals: |4q(m) − q̂| ≤ E_q on every kind at the
// midpoints beside the roots (where q(m) is smallest and the cancellation largest), and with room: the largest
// ratio |4q − q̂|/E_q seen is printed and must stay below 1/8 (the derivation's margin is about 1/19).
// The boundary filter's slope sign, checked exactly, where the products d_i ⊗ H_i underflow: the Coq proof
// (proofs/sphere/SphereBoundaryFilter.v) found that with d = (2^-1074, −2^-1074, −2^-1074) — and with every input a
// normal double, d = ±2^-600 and o, r scaled by 2^-474, 2^-480 — the slope 2(A·m + B) = −0.47·2^-1074 was
// certified positive, before the absolute term μ_s = 2^-1070 was added to its bound. A certain slope must now have
// the exact sign.
TEST(SphereStages, BoundaryFilterSlopeIsRightWhereItsProductsUnderflow) {
  const auto check = [](const Ray& ray, const Sphere& sphere, double x, double y) {
    const detail::SphereBoundarySigns b = detail::sphere_boundary_filter(ray, sphere, x, y);
    const mpq_class m_twice = mpq_class(x) + mpq_class(y);
    const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z}, d[3] = {ray.direction.x, ray.direction.y, ray.direction.z},
                 c[3] = {sphere.center.x, sphere.center.y, sphere.center.z};
    mpq_class slope = 0;
    for (int i = 0; i < 3; ++i) slope += mpq_class(d[i]) * (2 * (mpq_class(o[i]) - mpq_class(c[i])) + m_twice * mpq_class(d[i]));
    EXPECT_EQ(b.q, detail::Sign::positive);  // q(m) > 0 here: the slope is read
    if (detail::is_certain(b.slope)) {
      EXPECT_EQ(static_cast<int>(b.slope), sgn(slope));
    }
    EXPECT_LT(sgn(slope), 0);
  };
  const double o1 = 0x1.051eb851eb852p-2, o2 = 0x1.f5c28f5c28f5cp-3;
  check(Ray{{o1, o2, o2}, {0x1p-1074, -0x1p-1074, -0x1p-1074}}, Sphere{{0, 0, 0}, 0.125}, 1, 1);
  check(Ray{{std::ldexp(o1, -474), std::ldexp(o2, -474), std::ldexp(o2, -474)}, {0x1p-600, -0x1p-600, -0x1p-600}},
        Sphere{{0, 0, 0}, 0x1p-480}, 1, 1);
}

TEST(SphereStages, BoundaryFilterErrorBoundHoldsWithRoom) {
  double worst = 0;
  int checked = 0;
  for (const testkit::SphereQuery& q : queries_of_every_kind(200, 43)) {
    const SphereIntersection exact = detail::exact::intersect_sphere(q.ray, q.sphere);
    if (exact.relation == SphereRelation::miss) continue;
    for (double t : {exact.t1, exact.t2}) {
      if (!std::isfinite(t) || t == 0) continue;
      for (double y : {std::nextafter(t, INFINITY), std::nextafter(t, -INFINITY)}) {
        const detail::SphereBoundarySigns b = detail::sphere_boundary_filter(q.ray, q.sphere, t, y);
        if (!std::isfinite(b.q4_bound) || !std::isfinite(b.q4)) continue;
        const mpq_class m_twice = mpq_class(t) + mpq_class(y);
        const double o[3] = {q.ray.origin.x, q.ray.origin.y, q.ray.origin.z};
        const double d[3] = {q.ray.direction.x, q.ray.direction.y, q.ray.direction.z};
        const double c[3] = {q.sphere.center.x, q.sphere.center.y, q.sphere.center.z};
        mpq_class q4 = -4 * mpq_class(q.sphere.radius) * mpq_class(q.sphere.radius);
        for (int i = 0; i < 3; ++i) {
          const mpq_class g = 2 * (mpq_class(o[i]) - mpq_class(c[i])) + m_twice * mpq_class(d[i]);
          q4 += g * g;
        }
        const mpq_class error = abs(q4 - mpq_class(b.q4));
        ASSERT_LE(error, mpq_class(b.q4_bound)) << testkit::sphere_line(q) << " at " << testkit::hex_string(t);
        if (b.q4_bound > 0) worst = std::max(worst, mpq_class(error / mpq_class(b.q4_bound)).get_d());
        ++checked;
      }
    }
  }
  std::printf("boundary filter: %d evaluations, largest error / E_q = %g\n", checked, worst);
  EXPECT_GT(checked, 2000);
  EXPECT_LT(worst, 0.125);
}

// The decision of root_side_of against the roots' order, over exact small cases: for the roots 1 and 3
// (A = 1, B = −2, C = 3) and the tangent root 2 (A = 1, B = −2, C = 4), every m in {0, 1, 2, 3, 4} (exactly on a
// root, between, outside).
TEST(SphereRootSide, AgreesWithTheRootsOrder) {
  auto sign = [](long v) { return (v > 0) - (v < 0); };
  for (long c : {3L, 4L}) {
    const long t1 = c == 3 ? 1 : 2, t2 = c == 3 ? 3 : 2;
    for (long m = 0; m <= 4; ++m) {
      const long q = m * m - 4 * m + c, slope = m - 2;
      EXPECT_EQ(detail::root_side_of(-1, sign(q), sign(slope)), sign(t1 - m)) << c << " " << m;
      EXPECT_EQ(detail::root_side_of(+1, sign(q), sign(slope)), sign(t2 - m)) << c << " " << m;
    }
  }
}

std::string certified_text(const testkit::SphereQuery& q) { return text(intersect(q.ray, q.sphere)); }
std::string exact_text(const testkit::SphereQuery& q) { return text(intersect_exact(q.ray, q.sphere)); }

// The same, deterministic: 300 queries of every kind, so that each kind is tried many times in every run (the
// property above samples a kind about eight times).
TEST(SphereCertified, AgreesWithExactOnEveryKind) {
  for (const testkit::SphereQuery& q : queries_of_every_kind(300, 13))
    EXPECT_EQ(certified_text(q), exact_text(q)) << testkit::sphere_line(q);
}

RC_GTEST_PROP(SphereCertified, AgreesWithExact, ()) {
  const auto kind = *rc::gen::elementOf(testkit::all_sphere_query_kinds);
  const testkit::SphereQuery q = *rc::gen::exec([kind] { return make_sphere_query(kind, testkit::rc_bit_source()); });
  RC_TAG(std::string(testkit::to_string(kind)));
  const std::string certified = certified_text(q), exact = exact_text(q);
  if (certified != exact) RC_FAIL(testkit::sphere_line(q) + ": certified " + certified + ", exact " + exact);
  const SphereClassification c = relation(q.ray, q.sphere);
  const SphereIntersection e = intersect_exact(q.ray, q.sphere);
  RC_ASSERT(c.origin == e.origin);
  RC_ASSERT(c.relation == e.relation);
}

// The answers in other floating-point environments are the default environment's, bit for bit.
TEST(SphereEnvironment, AnswersDoNotDependOnTheCallersEnvironment) {
  const std::vector<testkit::SphereQuery> queries = queries_of_every_kind(40, 3);
  std::vector<std::string> want;
  for (const testkit::SphereQuery& q : queries)
    want.push_back(certified_text(q) + "|" + exact_text(q) + "|" +
                   std::string(to_string(relation(q.ray, q.sphere).relation)));
  for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    ASSERT_EQ(std::fesetround(mode), 0);
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const testkit::SphereQuery& q = queries[i];
      EXPECT_EQ(certified_text(q) + "|" + exact_text(q) + "|" +
                    std::string(to_string(relation(q.ray, q.sphere).relation)),
                want[i])
          << mode << ": " << testkit::sphere_line(q);
    }
    std::fesetround(FE_TONEAREST);
  }
#if defined(__x86_64__)
  const unsigned csr = _mm_getcsr();
  _mm_setcsr(csr | 0x8040);  // flush-to-zero and denormals-are-zero
  std::vector<std::string> got;
  for (const testkit::SphereQuery& q : queries) got.push_back(certified_text(q) + "|" + exact_text(q));
  _mm_setcsr(csr);
  for (std::size_t i = 0; i < queries.size(); ++i)
    EXPECT_EQ(got[i] + "|" + std::string(to_string(relation(queries[i].ray, queries[i].sphere).relation)), want[i])
        << "FTZ/DAZ: " << testkit::sphere_line(queries[i]);
#endif
}

}  // namespace
}  // namespace raykernel
