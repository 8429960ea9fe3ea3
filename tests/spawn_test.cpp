// spawn and spawn_to (<raykernel/spawn.hpp>, docs/contract.md §9): hand-derived cases for every branch (k = 0,
// P̂ on the plane, ties of |N_i|, steps across zero, k beyond 2^53, binary32, no origin, overflow, every invalid
// input), the contract's sample in both formats, and a RapidCheck property checking each answer against its
// definition with an oracle of its own (GMP for the signs, MPFR for the roundings, nextafter for the steps).
#include "invalid_reason.hpp"

#include <raykernel/spawn.hpp>

#include "commands/spawn.hpp"
#include "core/fp_environment.hpp"
#include "spawn/spawn_certified.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <mpfr.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel {
namespace {

constexpr double denorm_min = std::numeric_limits<double>::denorm_min();
constexpr double float_denorm_min = static_cast<double>(std::numeric_limits<float>::denorm_min());

const Triangle xy_plane{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // N = (0, 0, 1)
const Triangle yz_plane{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // N = (1, 0, 0)

void expect_origin(const SpawnedOrigin& got, const Vec3& origin, std::uint64_t steps) {
  EXPECT_EQ(got.origin.x, origin.x);
  EXPECT_EQ(got.origin.y, origin.y);
  EXPECT_EQ(got.origin.z, origin.z);
  EXPECT_EQ(got.steps, steps);
}

using test::invalid_reason;

TEST(Spawn, ARoundedPointOnTheSideNeedsNoStep) {
  // N = (3, 0, 1) × ... : the plane −x + 3z = 0 (a = 0, b = (3, 0, 1), c = (0, 1, 0): N = (−1, 0, 3)). The ray
  // down x = 1 crosses it at z = 1/3; RN(1/3) < 1/3, so σ(P̂) = sign(3·RN(1/3) − 1) = −1.
  const Triangle tilted{{0, 0, 0}, {3, 0, 1}, {0, 1, 0}};
  const Ray down{{1, 0.5, 1}, {0, 0, -1}};
  const double third = 1.0 / 3.0;
  // Leaving downwards, s = sign(w·N) = sign(−3) = −1 = σ(P̂): the origin is P̂, k = 0.
  expect_origin(spawn(HitPoint::crossing(down), tilted, {0, 0, -1}), {1, 0.5, third}, 0);
  // Leaving upwards, s = +1: z (|N_z| = 3 is the largest) moves up, δ = sign(3)·1, to the first double above 1/3.
  expect_origin(spawn(HitPoint::crossing(down), tilted, {0, 0, 1}), {1, 0.5, std::nextafter(third, 1.0)}, 1);
}

TEST(Spawn, APointExactlyOnThePlaneMovesOneStepOffIt) {
  const Ray down{{0.25, 0.25, 1}, {0, 0, -1}};  // P = (1/4, 1/4, 0) exactly: σ(P̂) = 0
  expect_origin(spawn(HitPoint::crossing(down), xy_plane, {0, 0, 1}), {0.25, 0.25, denorm_min}, 1);
  expect_origin(spawn(HitPoint::crossing(down), xy_plane, {1, 2, -1}), {0.25, 0.25, -denorm_min}, 1);
  // In binary32 the step is to the smallest float subnormal, 2^-149.
  expect_origin(spawn(HitPoint::crossing(down), xy_plane, {0, 0, 1}, OriginFormat::binary32),
                {0.25, 0.25, float_denorm_min}, 1);
  // A ray from below, any sign of t: the crossing is the same point.
  expect_origin(spawn(HitPoint::crossing({{0.25, 0.25, -3}, {0, 0, -1}}), xy_plane, {0, 0, 1}),
                {0.25, 0.25, denorm_min}, 1);
}

TEST(Spawn, AnExactTieOfTheLargestNormalComponentsStepsTheFirstAxis) {
  // a = 0, b = (0, 0, 1), c = (1, −1, 0): N = (1, 1, 0), |N_x| = |N_y|: x is the axis.
  const Triangle diagonal{{0, 0, 0}, {0, 0, 1}, {1, -1, 0}};
  expect_origin(spawn(HitPoint::at({0, 0, 5}), diagonal, {1, 0, 0}), {denorm_min, 0, 5}, 1);
  expect_origin(spawn(HitPoint::at({0, 0, 5}), diagonal, {0, -1, 0}), {-denorm_min, 0, 5}, 1);
}

TEST(Spawn, StepsAreCountedAcrossZeroAndBeyond2To53) {
  // The plane x = 0, N = (1, 0, 0). From x = −2^-1074 to the first value above 0: −2^-1074 → 0 → 2^-1074.
  expect_origin(spawn(HitPoint::at({-denorm_min, 7, 7}), yz_plane, {1, 0, 0}), {denorm_min, 7, 7}, 2);
  // From x = −1: every double in [−1, 0) (2^62 − 2^52 of them... exactly the bits of 1.0), zero, then 2^-1074.
  const std::uint64_t bits_of_one = 0x3ff0000000000000;
  expect_origin(spawn(HitPoint::at({-1, 0, 0}), yz_plane, {1, 0, 0}), {denorm_min, 0, 0}, bits_of_one + 1);
  expect_origin(spawn(HitPoint::at({-1, 0, 0}), yz_plane, {1, 0, 0}, OriginFormat::binary32),
                {float_denorm_min, 0, 0}, 0x3f800000u + 1);
  // The point need not be on the plane; already on the side: k = 0.
  expect_origin(spawn(HitPoint::at({3, 4, 5}), yz_plane, {2, 1, 1}), {3, 4, 5}, 0);
}

TEST(Spawn, Binary32IsRoundedStraightFromTheExactPoint) {
  // The plane z = 1 + (2^-24 + 2^-60)·x: through a = (0, 0, 1), b = (2^36, 0, 4097 + 2^-24) (37 bits: a double)
  // and c = (0, 1, 1). The ray down x = 1 crosses it at P_z = 1 + 2^-24 + 2^-60 exactly. The double nearest P_z is
  // 1 + 2^-24, a float midpoint, which rounds to 1 in binary32 (ties to even): a rounding through a double would
  // give 1. P_z itself is above the midpoint, so RN32(P_z) = 1 + 2^-23.
  const Triangle t{{0, 0, 1}, {std::ldexp(1, 36), 0, 4097 + std::ldexp(1, -24)}, {0, 1, 1}};
  // Leaving upwards (w·N = 2^36 > 0): RN32(P_z) is above the plane, the origin with k = 0.
  const Ray down{{1, 0, 5}, {0, 0, -1}};
  expect_origin(spawn(HitPoint::crossing(down), t, {0, 0, 1}, OriginFormat::binary32), {1, 0, 1 + std::ldexp(1, -23)}, 0);
  // In binary64, RN(P_z) = 1 + 2^-24 is below P_z: one step up, to the first double above P_z.
  expect_origin(spawn(HitPoint::crossing(down), t, {0, 0, 1}), {1, 0, 1 + std::ldexp(1, -24) + std::ldexp(1, -52)}, 1);
  // Leaving downwards in binary32, RN32(P_z) is on the wrong side: one float down, to 1.
  expect_origin(spawn(HitPoint::crossing(down), t, {0, 0, -1}, OriginFormat::binary32), {1, 0, 1}, 1);
}

TEST(Spawn, MidpointsOfTheFormatAreDecidedExactly) {
  // The ray from (1, 0, 1) along (d_x, 0, −2) crosses z = 0 at t = 1/2: P_x = 1 + d_x/2 exactly (hand-derived).
  const auto from = [](double dx) { return HitPoint::crossing(Ray{{1, 0, 1}, {dx, 0, -2}}); };
  const double u = std::ldexp(1, -52);
  // binary64: P_x = 1 + 2^-53, the midpoint of 1 and 1 + 2^-52: ties to even, 1; an ulp of d_x beside it decides.
  expect_origin(spawn(from(u), xy_plane, {0, 0, 1}), {1, 0, denorm_min}, 1);
  expect_origin(spawn(from(u + std::ldexp(1, -104)), xy_plane, {0, 0, 1}), {1 + u, 0, denorm_min}, 1);
  expect_origin(spawn(from(u - std::ldexp(1, -105)), xy_plane, {0, 0, 1}), {1, 0, denorm_min}, 1);
  // binary32: P_x = 1 + 2^-24 ± 2^-76 rounds to 1 + 2^-24 in binary64, a float midpoint; P_x's side of it decides
  // (above: 1 + 2^-23; below: 1; exactly on it: ties to even, 1).
  const double f = std::ldexp(1, -23);
  expect_origin(spawn(from(f + std::ldexp(1, -75)), xy_plane, {0, 0, 1}, OriginFormat::binary32),
                {1 + f, 0, float_denorm_min}, 1);
  expect_origin(spawn(from(f - std::ldexp(1, -75)), xy_plane, {0, 0, 1}, OriginFormat::binary32),
                {1, 0, float_denorm_min}, 1);
  expect_origin(spawn(from(f), xy_plane, {0, 0, -1}, OriginFormat::binary32), {1, 0, -float_denorm_min}, 1);
  // A direction with d_x = 0: P_x = o_x exactly; in binary32 a double that is a float midpoint ties to even.
  expect_origin(spawn(HitPoint::crossing(Ray{{1 + std::ldexp(1, -24), 0, 1}, {0, 0, -2}}), xy_plane, {0, 0, 1},
                      OriginFormat::binary32),
                {1, 0, float_denorm_min}, 1);
}

TEST(Spawn, ShadowRaysTowardsATargetPoint) {
  // spawn_to: s = σ(q).
  expect_origin(spawn_to(HitPoint::at({0, 0, 0}), yz_plane, {5, 1, 1}), {denorm_min, 0, 0}, 1);
  expect_origin(spawn_to(HitPoint::at({0, 0, 0}), yz_plane, {-5, 1, 1}), {-denorm_min, 0, 0}, 1);
  EXPECT_NE(invalid_reason([] { (void)spawn_to(HitPoint::at({0, 0, 0}), yz_plane, {0, 3, 4}); }).find("lies in the triangle's plane"),
            std::string::npos);
}

TEST(Spawn, NoOriginOrOverflowIsInvalidNamed) {
  constexpr double max = DBL_MAX;
  const Triangle far_plane{{max, 0, 0}, {max, 1, 0}, {max, 0, 1}};  // x = DBL_MAX
  EXPECT_NE(invalid_reason([&] { (void)spawn(HitPoint::at({0, 0, 0}), far_plane, {1, 0, 0}); }).find("no origin in binary64"),
            std::string::npos);
  // Towards −x, σ(0) = −1 = s already.
  expect_origin(spawn(HitPoint::at({0, 0, 0}), far_plane, {-1, 0, 0}), {0, 0, 0}, 0);
  // binary32: a point beyond FLT_MAX overflows, and FLT_MAX itself has no float above it.
  EXPECT_NE(invalid_reason([] { (void)spawn(HitPoint::at({1e39, 0, 0}), yz_plane, {1, 0, 0}, OriginFormat::binary32); })
                .find("overflows binary32"),
            std::string::npos);
  const double fmax = static_cast<double>(FLT_MAX);
  const Triangle float_far{{fmax, 0, 0}, {fmax, 1, 0}, {fmax, 0, 1}};
  EXPECT_NE(invalid_reason([&] { (void)spawn(HitPoint::at({0, 0, 0}), float_far, {1, 0, 0}, OriginFormat::binary32); })
                .find("no origin in binary32"),
            std::string::npos);
  // In binary64 that plane is far from the top: the first double above FLT_MAX.
  expect_origin(spawn(HitPoint::at({0, 0, 0}), float_far, {1, 0, 0}), {std::nextafter(fmax, max), 0, 0},
                0x47efffffe0000000u + 1);
}

TEST(Spawn, InvalidInputIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Ray down{{0.25, 0.25, 1}, {0, 0, -1}};
  const auto reason = [&](const HitPoint& h, const Triangle& t, const Vec3& w) {
    return invalid_reason([&] { (void)spawn(h, t, w); });
  };
  EXPECT_EQ(reason(HitPoint::crossing({{0, 0, 0}, {0, 0, 0}}), xy_plane, {0, 0, 1}), "ray direction is the zero vector");
  EXPECT_EQ(reason(HitPoint::crossing(down), xy_plane, {0, 0, 0}), "direction w is the zero vector");
  EXPECT_EQ(reason(HitPoint::crossing({{nan, 0, 0}, {0, 0, 1}}), xy_plane, {0, 0, 1}), "ray origin x is NaN");
  EXPECT_EQ(reason(HitPoint::at({0, INFINITY, 0}), xy_plane, {0, 0, 1}), "point y is inf");
  EXPECT_EQ(reason(HitPoint::crossing(down), {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {0, 0, 1}),
            "the triangle is degenerate (N = (b - a) x (c - a) = 0)");
  EXPECT_EQ(reason(HitPoint::crossing({{0, 0, 1}, {1, 0, 0}}), xy_plane, {0, 0, 1}),
            "the ray is parallel to the triangle's plane (den = d.N = 0)");
  EXPECT_EQ(reason(HitPoint::crossing(down), xy_plane, {1, 1, 0}),
            "direction w is parallel to the triangle's plane (w.N = 0)");
}

// ---- The contract's sample, both formats (tests/data/contract-cases/spawn-sample.*) ------------------------

std::vector<std::string> lines_of(const std::string& text) {
  std::istringstream s(text);
  std::vector<std::string> out;
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

TEST(SpawnSample, EveryLineIsTheContractsAnswerInBothFormats) {
  const std::string dir = RAYKERNEL_CASES_DIR;
  for (const bool binary32 : {false, true}) {
    std::ifstream in(dir + "/spawn-sample.txt");
    std::ostringstream out, err;
    cli::SpawnCounts counts;
    cli::SpawnCommandOptions options;
    if (binary32) options.format = OriginFormat::binary32;
    EXPECT_EQ(cli::spawn_stream(in, out, err, options, counts), 1);  // the sample has invalid lines
    std::ifstream e(dir + (binary32 ? "/spawn-sample.float.expected" : "/spawn-sample.expected"));
    std::stringstream expected;
    expected << e.rdbuf();
    const std::vector<std::string> got = lines_of(out.str()), want = lines_of(expected.str());
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
      std::istringstream g(got[k]), w(want[k]);
      std::string gw[4], ww[4];
      g >> gw[0] >> gw[1] >> gw[2] >> gw[3];
      w >> ww[0] >> ww[1] >> ww[2] >> ww[3];
      if (ww[0] == "invalid") {
        EXPECT_EQ(gw[0], "invalid") << "line " << k + 1;
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        // Compared as the values they read back to in the format (the sign of a zero is free).
        if (binary32) EXPECT_EQ(std::strtof(gw[c].c_str(), nullptr), std::strtof(ww[c].c_str(), nullptr)) << "line " << k + 1;
        else EXPECT_EQ(std::strtod(gw[c].c_str(), nullptr), std::strtod(ww[c].c_str(), nullptr)) << "line " << k + 1;
      }
      EXPECT_EQ(gw[3], ww[3]) << "line " << k + 1;
    }
  }
}

// ---- The definition, checked by an oracle of its own -----------------------------------------------------

using Q3 = std::array<mpq_class, 3>;
Q3 q3(const Vec3& v) { return {mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)}; }  // exact in the default environment
int side(const Q3& x, const Q3& a, const Q3& n) {
  return sgn((x[0] - a[0]) * n[0] + (x[1] - a[1]) * n[1] + (x[2] - a[2]) * n[2]);
}

// RN of q in the format, by MPFR with the format's precision and exponent range set here.
double oracle_round(const mpq_class& q, bool binary32) {
  const mpfr_exp_t emin = mpfr_get_emin(), emax = mpfr_get_emax();
  mpfr_set_emin(binary32 ? -148 : -1073);
  mpfr_set_emax(binary32 ? 128 : 1024);
  mpfr_t x;
  mpfr_init2(x, binary32 ? 24 : 53);
  const int t = mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDN);
  mpfr_subnormalize(x, t, MPFR_RNDN);
  const double r = mpfr_get_d(x, MPFR_RNDN);
  mpfr_clear(x);
  mpfr_set_emin(emin);
  mpfr_set_emax(emax);
  return r;
}

double step(double x, int direction, bool binary32) {
  if (binary32) return static_cast<double>(std::nextafter(static_cast<float>(x), direction > 0 ? INFINITY : -INFINITY));
  return std::nextafter(x, direction > 0 ? INFINITY : -INFINITY);
}

// A double near `scale`, with random low bits.
rc::Gen<double> coordinate(int scale) {
  return rc::gen::map(rc::gen::inRange<std::int64_t>(-(1 << 20), 1 << 20), [scale](std::int64_t m) {
    return std::ldexp(static_cast<double>(m), scale - 20);
  });
}

RC_GTEST_PROP(SpawnDefinition, TheOriginIsStrictlyOnTheSideWithTheFewestSteps, ()) {
  const int scale = *rc::gen::inRange(-60, 60);
  const bool binary32 = *rc::gen::arbitrary<bool>();
  const bool point_mode = *rc::gen::arbitrary<bool>();
  const auto v = [&] { return Vec3{*coordinate(scale), *coordinate(scale), *coordinate(scale)}; };
  const Triangle t{v(), v(), v()};
  const Ray ray{v(), v()};
  const Vec3 p = v(), w = v();
  const HitPoint hit = point_mode ? HitPoint::at(p) : HitPoint::crossing(ray);
  const OriginFormat format = binary32 ? OriginFormat::binary32 : OriginFormat::binary64;
  const Q3 a = q3(t.a), b = q3(t.b), c = q3(t.c);
  const Q3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const Q3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  // The exact P.
  Q3 P;
  if (point_mode) {
    P = q3(p);
  } else {
    const Q3 o = q3(ray.origin), d = q3(ray.direction);
    const mpq_class den = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    RC_PRE(sgn(den) != 0);
    const mpq_class tq = ((a[0] - o[0]) * n[0] + (a[1] - o[1]) * n[1] + (a[2] - o[2]) * n[2]) / den;
    for (int k = 0; k < 3; ++k) P[k] = o[k] + tq * d[k];
  }
  const Q3 wq = q3(w);
  const int s = sgn(wq[0] * n[0] + wq[1] * n[1] + wq[2] * n[2]);
  RC_PRE(s != 0);  // (N = 0 makes s = 0 too)
  Vec3 rounded{oracle_round(P[0], binary32), oracle_round(P[1], binary32), oracle_round(P[2], binary32)};
  RC_PRE(std::isfinite(rounded.x) && std::isfinite(rounded.y) && std::isfinite(rounded.z));
  const SpawnedOrigin o = spawn(hit, t, w, format);
  const double* got = &o.origin.x;
  const double* r = &rounded.x;
  RC_ASSERT(side(q3(o.origin), a, n) == s);  // strictly on side s
  if (side(q3(rounded), a, n) == s) {
    RC_ASSERT(o.steps == 0u);
    for (int k = 0; k < 3; ++k) RC_ASSERT(got[k] == r[k]);
    return;
  }
  int i = 0;
  for (int k = 1; k < 3; ++k)
    if (abs(n[k]) > abs(n[i])) i = k;
  const int delta = sgn(n[i]) * s;
  for (int k = 0; k < 3; ++k)
    if (k != i) RC_ASSERT(got[k] == r[k]);
  RC_ASSERT(o.steps >= 1u);
  // One step back towards P̂ is not on the side (k is the smallest); small k are also counted step by step.
  Vec3 back = o.origin;
  (&back.x)[i] = step(got[i], -delta, binary32);
  RC_ASSERT(side(q3(back), a, n) != s);
  if (o.steps <= 64) {
    double x = r[i];
    for (std::uint64_t k = 0; k < o.steps; ++k) x = step(x, delta, binary32);
    RC_ASSERT(x == got[i]);
  }
}

// ---- The certified fast path against the exact path ------------------------------------------------------

// A double of `bits` significant bits (1 to 53) near 2^scale, or 0 one time in eight: short significands make
// the hit's coordinates land on midpoints of the format (ties) and on the plane; zeros make axis-aligned rays.
rc::Gen<double> hard_coordinate(int scale, int bits) {
  return rc::gen::map(rc::gen::pair(rc::gen::inRange<std::int64_t>(-(std::int64_t{1} << (bits - 1)),
                                                                    std::int64_t{1} << (bits - 1)),
                                    rc::gen::inRange(0, 8)),
                      [scale, bits](const std::pair<std::int64_t, int>& m) {
                        return m.second == 0 ? 0.0 : std::ldexp(static_cast<double>(m.first), scale - bits);
                      });
}

// The reason spawn throws, or "" with the answer.
std::pair<std::string, SpawnedOrigin> run(const std::function<SpawnedOrigin()>& f) {
  try {
    return {"", f()};
  } catch (const invalid_input& e) {
    return {e.what(), {}};
  }
}

RC_GTEST_PROP(SpawnCertified, EqualsTheExactPathBitForBit, ()) {
  const int scale = *rc::gen::inRange(-80, 80);
  const int bits = *rc::gen::element(1, 2, 3, 5, 12, 24, 25, 53);
  const auto v = [&] {
    return Vec3{*hard_coordinate(scale, bits), *hard_coordinate(scale, bits), *hard_coordinate(scale, bits)};
  };
  const Triangle t{v(), v(), v()};
  const bool point_mode = *rc::gen::inRange(0, 4) == 0;
  const HitPoint hit = point_mode ? HitPoint::at(v()) : HitPoint::crossing(Ray{v(), v()});
  const Vec3 w = v();
  const OriginFormat format = *rc::gen::arbitrary<bool>() ? OriginFormat::binary32 : OriginFormat::binary64;
  const bool to = *rc::gen::arbitrary<bool>();
  const auto fast = run([&] { return to ? spawn_to(hit, t, w, format) : spawn(hit, t, w, format); });
  const auto exact = run([&] { return to ? spawn_to_exact(hit, t, w, format) : spawn_exact(hit, t, w, format); });
  RC_ASSERT(fast.first == exact.first);
  const bool certified = detail::in_default_fp_environment(
      [&] { return detail::spawn_certified(hit, t, to, w, format).has_value(); });
  RC_TAG(exact.first.empty() ? (exact.second.steps == 0 ? "k = 0" : "k >= 1") : "invalid",
         certified ? "certified" : "exact path");
  RC_ASSERT(!(certified && !exact.first.empty()));  // the fast path answers valid input only
  if (!exact.first.empty()) return;
  RC_ASSERT(std::bit_cast<std::uint64_t>(fast.second.origin.x) == std::bit_cast<std::uint64_t>(exact.second.origin.x));
  RC_ASSERT(std::bit_cast<std::uint64_t>(fast.second.origin.y) == std::bit_cast<std::uint64_t>(exact.second.origin.y));
  RC_ASSERT(std::bit_cast<std::uint64_t>(fast.second.origin.z) == std::bit_cast<std::uint64_t>(exact.second.origin.z));
  RC_ASSERT(fast.second.steps == exact.second.steps);
}

}  // namespace
}  // namespace raykernel
