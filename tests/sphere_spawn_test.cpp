// Spawning from a sphere (raykernel/spawn.hpp; the rule: docs/contract.md, "Decided here"). Hand-derived cases
// (each answer worked out in the comment above it), then properties on points where rays of every hard sphere
// kind hit their sphere, with directions leaving outward, inward and grazing: the origin is accepted (σ = s and,
// outward, w·(x − c) ≥ 0, in rationals written here), one step less is not (k is the smallest), and the guarantee
// holds by an oracle of its own — the exact ray–sphere query from the origin (intersect_exact): outward, no root
// at t ≥ 0; inward, the origin inside.
#include "commands/spawn.hpp"

#include <raykernel/spawn.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/testkit/plane_rapidcheck.hpp>
#include <raykernel/testkit/sphere_queries.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cfenv>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

namespace raykernel {
namespace {

const Sphere unit{{0, 0, 0}, 1};

mpq_class q(double x) {
  mpq_class r(x);  // exact: GMP converts a double exactly
  return r;
}

// sign(|x − c|² − r²) and sign(w·(x − c)), in rationals (the test's own).
int side(const Vec3& x, const Sphere& s) {
  const mpq_class fx = q(x.x) - q(s.center.x), fy = q(x.y) - q(s.center.y), fz = q(x.z) - q(s.center.z);
  return sgn(fx * fx + fy * fy + fz * fz - q(s.radius) * q(s.radius));
}
int leaving(const Vec3& x, const Sphere& s, const Vec3& w) {
  return sgn(q(w.x) * (q(x.x) - q(s.center.x)) + q(w.y) * (q(x.y) - q(s.center.y)) + q(w.z) * (q(x.z) - q(s.center.z)));
}
bool accepted(const Vec3& x, const Sphere& s, const Vec3& w, int direction_side) {
  return direction_side < 0 ? side(x, s) < 0 : side(x, s) > 0 && leaving(x, s, w) >= 0;
}

std::string text(const Vec3& v) {
  return testkit::hex_string(v.x) + " " + testkit::hex_string(v.y) + " " + testkit::hex_string(v.z);
}

TEST(SphereSpawnHandDerived, OnTheSurfaceOutwardAndInward) {
  // p = (1, 0, 0) on the unit sphere, N = (1, 0, 0). Outward along x: σ(p) = 0 ≠ +1, axis x, δ = +1: the first
  // double above 1, 1 + 2^-52, is outside (C' = 2^-51 + 2^-104 > 0) and w·(x − c) > 0: k = 1.
  SpawnedOrigin o = spawn(Vec3{1, 0, 0}, unit, Vec3{1, 0, 0});
  EXPECT_EQ(o.origin.x, 1 + 0x1p-52);
  EXPECT_EQ(o.origin.y, 0);
  EXPECT_EQ(o.steps, 1u);
  // Inward: s = −1, δ = −1: the first double below 1, 1 − 2^-53, is inside: k = 1.
  o = spawn(Vec3{1, 0, 0}, unit, Vec3{-1, 2, 3});
  EXPECT_EQ(o.origin.x, 1 - 0x1p-53);
  EXPECT_EQ(o.steps, 1u);
}

TEST(SphereSpawnHandDerived, AlreadyOnTheSideItLeavesTowards) {
  // p = (2, 0, 0) is outside: leaving outward (w·N = 2 > 0, w·(p − c) ≥ 0) it is the origin, k = 0; leaving
  // inward it must reach inside the sphere: along x, δ = −1, the first double strictly below 1 (the near root
  // c_x + √(1 − 0) = 1): 1 − 2^-53, k = the doubles from 2 down to it = 2^52 + 1.
  EXPECT_EQ(spawn(Vec3{2, 0, 0}, unit, Vec3{1, 5, 0}).steps, 0u);
  const SpawnedOrigin in = spawn(Vec3{2, 0, 0}, unit, Vec3{-1, 0, 0});
  EXPECT_EQ(in.origin.x, 1 - 0x1p-53);
  EXPECT_EQ(in.steps, (std::uint64_t{1} << 52) + 1);
  // p = (0.5, 0, 0) inside leaving inward: the origin, k = 0.
  EXPECT_EQ(spawn(Vec3{0.5, 0, 0}, unit, Vec3{-1, 0, 0}).steps, 0u);
}

TEST(SphereSpawnHandDerived, OutwardPicksAnAxisWhereEachStepLeaves) {
  // p = (0, 1, 0) is on the sphere; w = (1, 1e-300, 0): w·N = 1e-300 > 0, outward. The largest |N_i| is y, and
  // w_y·N_y > 0: axis y, δ = +1: 1 + 2^-52 on y, k = 1 — there w·(x − c) = 1e-300·(1 + 2^-52) > 0.
  SpawnedOrigin o = spawn(Vec3{0, 1, 0}, unit, Vec3{1, 1e-300, 0});
  EXPECT_EQ(o.origin.x, 0);
  EXPECT_EQ(o.origin.y, 1 + 0x1p-52);
  EXPECT_EQ(o.steps, 1u);
  // w = (1, 1, 0) from p = (0.5, −1, 0) outside (C = 1/4): w·N = 0.5 − 1 < 0, inward. Axis y (|N_y| = 1 is
  // the largest), δ = −sign(N_y)·... = +1: towards the centre, K = 0.25, V = 0.75: the first double strictly
  // above −√0.75 is inside. Worked with rationals below rather than by hand: accepted, and one step less not.
  o = spawn(Vec3{0.5, -1, 0}, unit, Vec3{1, 1, 0});
  EXPECT_GT(o.origin.y, -std::sqrt(0.75) - 0x1p-50);
  EXPECT_LT(o.origin.y, -std::sqrt(0.75) + 0x1p-50);
  EXPECT_EQ(side(o.origin, unit), -1);
  EXPECT_EQ(side(Vec3{0.5, std::nextafter(o.origin.y, -2.0), 0}, unit), 1);
}

TEST(SphereSpawnHandDerived, Binary32StartsFromTheFloatRounding) {
  // p = (1 + 2^-40, 0, 0) rounds to the float 1, on the sphere. Outward: the next float, 1 + 2^-23, k = 1.
  const SpawnedOrigin o = spawn(Vec3{1 + 0x1p-40, 0, 0}, unit, Vec3{1, 0, 0}, OriginFormat::binary32);
  EXPECT_EQ(o.origin.x, 1 + 0x1p-23);
  EXPECT_EQ(o.steps, 1u);
  // Inward: the float below 1, 1 − 2^-24.
  EXPECT_EQ(spawn(Vec3{1 + 0x1p-40, 0, 0}, unit, Vec3{-1, 0, 0}, OriginFormat::binary32).origin.x, 1 - 0x1p-24);
}

TEST(SphereSpawnHandDerived, InvalidInputIsNamed) {
  const auto reason = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const invalid_input& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(reason([] { (void)spawn(Vec3{0, 0, 0}, unit, Vec3{1, 0, 0}); }).find("center"), std::string::npos);
  EXPECT_NE(reason([] { (void)spawn(Vec3{1, 0, 0}, unit, Vec3{0, 1, 0}); }).find("tangent"), std::string::npos);
  EXPECT_NE(reason([] { (void)spawn(Vec3{1, 0, 0}, unit, Vec3{0, 0, 0}); }).find("zero"), std::string::npos);
  EXPECT_NE(reason([] { (void)spawn(Vec3{NAN, 0, 0}, unit, Vec3{1, 0, 0}); }).find("point x is NaN"),
            std::string::npos);
  EXPECT_NE(reason([] { (void)spawn(Vec3{1, 0, 0}, Sphere{{0, 0, 0}, -1}, Vec3{1, 0, 0}); }).find("radius"),
            std::string::npos);
  // Inward from (5, 5, 0) along x: K = 25 > r² = 1, the line y = 5 misses the ball: no origin inside on x.
  EXPECT_NE(reason([] { (void)spawn(Vec3{5, 5, 0}, unit, Vec3{-1, -1, 0}); }).find("no origin"), std::string::npos);
  // A float that overflows binary32.
  EXPECT_NE(reason([] { (void)spawn(Vec3{1e300, 0, 0}, unit, Vec3{1, 0, 0}, OriginFormat::binary32); })
                .find("overflows"),
            std::string::npos);
}

TEST(SphereSpawnHandDerived, SphereSide) {
  EXPECT_EQ(sphere_side(Vec3{1, 0, 0}, unit), 0);
  EXPECT_EQ(sphere_side(Vec3{1 + 0x1p-52, 0, 0}, unit), 1);
  EXPECT_EQ(sphere_side(Vec3{0.6, 0.8, 0}, unit), sgn(q(0.6) * q(0.6) + q(0.8) * q(0.8) - 1));
}

// `raykernel spawn --sphere`, through the command's stream code: the hand-derived answers above, a tangent w named,
// and a malformed line answered invalid with the batch going on.
TEST(SphereSpawnCli, LinesOfTenNumbers) {
  std::istringstream in(
      "1 0 0  0 0 0 1  1 0 0\n"
      "# inward\n"
      "1 0 0  0 0 0 1  -1 2 3\n"
      "1 0 0  0 0 0 1  0 1 0\n"
      "1 0 0  0 0 0\n"
      "2 0 0  0 0 0 1  -1 0 0\n");
  std::ostringstream out, err;
  cli::SpawnCommandOptions options;
  options.sphere = true;
  cli::SpawnCounts counts;
  const int status = cli::spawn_stream(in, out, err, options, counts);
  EXPECT_EQ(status, 1);
  // 1 + 2^-52 = 1.0000000000000002, 1 − 2^-53 = 0.9999999999999999 (shortest round-trip decimals); from 2 down to
  // 1 − 2^-53: 2^52 + 1 = 4503599627370497 steps.
  EXPECT_EQ(out.str(),
            "1.0000000000000002 0 0 1\n"
            "0.9999999999999999 0 0 1\n"
            "invalid direction w is tangent to the sphere at the point (w.(p - c) = 0)\n"
            "invalid expected 10 numbers, found 6\n"
            "0.9999999999999999 0 0 4503599627370497\n");
  EXPECT_NE(err.str().find("line 5"), std::string::npos) << err.str();
  EXPECT_EQ(counts.moved, 3u);
}

// The guarantee, by the exact ray–sphere query from the origin.
void expect_guarantee(const Vec3& origin, const Vec3& w, const Sphere& sphere, int s) {
  const SphereIntersection x = intersect_exact(Ray{origin, w}, sphere);
  if (s > 0) {
    EXPECT_EQ(x.origin, SphereOrigin::outside) << text(origin);
    if (x.relation != SphereRelation::miss)  // both roots negative: the larger rounds below 0 or to −0
      EXPECT_TRUE(x.t2 < 0 || (x.t2 == 0 && std::signbit(x.t2))) << text(origin) << " t2 " << x.t2;
  } else {
    EXPECT_EQ(x.origin, SphereOrigin::inside) << text(origin);
  }
}

// x rounded to nearest-even in the format (the conversion to float rounds so in the default environment).
double in_format(double x, OriginFormat format) {
  if (format == OriginFormat::binary64) return x;
  const volatile float f = static_cast<float>(x);
  return f;
}

// One spawn checked: accepted, minimal, the guarantee. Returns false when the input was invalid for a named
// reason the test confirms.
bool check_spawn(const Vec3& p, const Sphere& sphere, const Vec3& w, OriginFormat format) {
  const int s = sgn(q(w.x) * (q(p.x) - q(sphere.center.x)) + q(w.y) * (q(p.y) - q(sphere.center.y)) +
                    q(w.z) * (q(p.z) - q(sphere.center.z)));
  SpawnedOrigin o;
  try {
    o = spawn(p, sphere, w, format);
  } catch (const invalid_input& e) {
    const std::string why = e.what();
    if (s == 0) EXPECT_NE(why.find("tangent"), std::string::npos) << why;
    else EXPECT_NE(why.find("no origin"), std::string::npos) << why << " at " << text(p);
    return false;
  }
  EXPECT_NE(s, 0) << text(p);
  EXPECT_TRUE(accepted(o.origin, sphere, w, s)) << text(p) << " -> " << text(o.origin);
  expect_guarantee(o.origin, w, sphere, s);
  if (o.steps > 0) {  // one step back on the axis that moved is not accepted
    const double p_hat[3] = {in_format(p.x, format), in_format(p.y, format), in_format(p.z, format)};
    double back[3] = {o.origin.x, o.origin.y, o.origin.z};
    int moved = -1;
    for (int i = 0; i < 3; ++i)
      if (back[i] != p_hat[i]) moved = i;
    EXPECT_GE(moved, 0);
    if (moved >= 0) {
      const double a = back[moved], toward = p_hat[moved];
      back[moved] = format == OriginFormat::binary32
                        ? static_cast<double>(std::nextafter(static_cast<float>(a), static_cast<float>(toward)))
                        : std::nextafter(a, toward);
      const Vec3 b{back[0], back[1], back[2]};
      EXPECT_FALSE(accepted(b, sphere, w, s))
          << text(p) << " back " << text(b) << " origin " << text(o.origin) << " k " << o.steps << " s " << s
          << " sphere " << text(sphere.center) << " " << testkit::hex_string(sphere.radius) << " w " << text(w)
          << " moved " << moved << " phat " << testkit::hex_string(p_hat[moved]) << " format " << static_cast<int>(format);
    }
  }
  return true;
}

// The point a ray hits its sphere at, as a renderer computes it (o ⊕ t1 ⊗ d), and three directions: the
// reflection about the rounded normal (often grazing), back along −d (inward or outward, by the side) and on
// along d.
struct Spawns {
  Vec3 p;
  Vec3 w[3];
};
std::optional<Spawns> spawns_of(const testkit::SphereQuery& s) {
  const SphereIntersection x = intersect(s.ray, s.sphere);
  if (x.relation == SphereRelation::miss || !std::isfinite(x.t1)) return std::nullopt;
  const Vec3& o = s.ray.origin;
  const Vec3& d = s.ray.direction;
  const Vec3 p{o.x + x.t1 * d.x, o.y + x.t1 * d.y, o.z + x.t1 * d.z};
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return std::nullopt;
  const Vec3 n{p.x - s.sphere.center.x, p.y - s.sphere.center.y, p.z - s.sphere.center.z};
  const double nn = n.x * n.x + n.y * n.y + n.z * n.z, dn = d.x * n.x + d.y * n.y + d.z * n.z;
  if (!(nn > 0) || !std::isfinite(nn) || !std::isfinite(dn)) return std::nullopt;
  const double k = 2 * dn / nn;
  const Vec3 reflected{d.x - k * n.x, d.y - k * n.y, d.z - k * n.z};
  return Spawns{p, {reflected, {-d.x, -d.y, -d.z}, d}};
}

bool usable(const Vec3& w) {
  return std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z) && (w.x != 0 || w.y != 0 || w.z != 0);
}

RC_GTEST_PROP(SphereSpawn, AcceptedMinimalAndNeverRehits, ()) {
  const auto kind = *rc::gen::elementOf(testkit::all_sphere_query_kinds);
  const testkit::SphereQuery s = *rc::gen::exec([kind] { return make_sphere_query(kind, testkit::rc_bit_source()); });
  const std::optional<Spawns> sp = spawns_of(s);
  RC_PRE(sp.has_value());
  const int which = *rc::gen::inRange(0, 3);
  RC_PRE(usable(sp->w[which]));
  const OriginFormat format = *rc::gen::elementOf(std::vector<OriginFormat>{OriginFormat::binary64, OriginFormat::binary32});
  if (format == OriginFormat::binary32) RC_PRE(std::fabs(sp->p.x) < 1e38 && std::fabs(sp->p.y) < 1e38 && std::fabs(sp->p.z) < 1e38);
  check_spawn(sp->p, s.sphere, sp->w[which], format);
  RC_ASSERT(!::testing::Test::HasFailure());
}

// Every hard kind, deterministic, and in the other rounding modes the same origins.
TEST(SphereSpawn, EveryKindInEveryEnvironment) {
  testkit::SplitMix64 rng(29);
  const testkit::BitSource source = [&rng] { return rng(); };
  int spawned = 0, stepped = 0, outward = 0, inward = 0;
  for (testkit::SphereQueryKind kind : testkit::all_sphere_query_kinds)
    for (int i = 0; i < 60; ++i) {
      const testkit::SphereQuery s = testkit::make_sphere_query(kind, source);
      const std::optional<Spawns> sp = spawns_of(s);
      if (!sp) continue;
      for (const Vec3& w : sp->w) {
        if (!usable(w) || !check_spawn(sp->p, s.sphere, w, OriginFormat::binary64)) continue;
        const SpawnedOrigin want = spawn(sp->p, s.sphere, w);
        ++spawned;
        stepped += want.steps > 0;
        (leaving(sp->p, s.sphere, w) > 0 ? outward : inward) += 1;
        for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
          ASSERT_EQ(std::fesetround(mode), 0);
          const SpawnedOrigin got = spawn(sp->p, s.sphere, w);
          std::fesetround(FE_TONEAREST);
          EXPECT_EQ(got.steps, want.steps);
          EXPECT_EQ(text(got.origin), text(want.origin));
        }
      }
    }
  EXPECT_GT(spawned, 1000);
  EXPECT_GT(stepped, 200);  // the hard kinds put many hit points on the wrong side
  EXPECT_GT(outward, 300);
  EXPECT_GT(inward, 300);
}

}  // namespace
}  // namespace raykernel
