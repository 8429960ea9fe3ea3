// Spheres and open segments (docs/contract.md §8 and §10): a sphere meets the segment from p to q when a root of
// the line p + t·(q − p), with q − p exact, lies strictly between 0 and 1 (the tangent root included, an end on
// the sphere not by itself). Hand-derived cases (each answer worked out in the comment above it), then
// properties: the certified answer equals the exact reference on every hard sphere kind, and, where q − p is a
// double and neither end is on the sphere, the closed interval [0, 1] of the ray p → q (nearest_root, §8) says
// the same — an oracle written without the segment's formula.
#include "commands/sphere_set.hpp"

#include <raykernel/occlusion.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/testkit/plane_rapidcheck.hpp>
#include <raykernel/testkit/sphere_queries.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cfenv>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel {
namespace {

const Sphere unit{{0, 0, 0}, 1};

std::string text(const Vec3& v) {
  return testkit::hex_string(v.x) + " " + testkit::hex_string(v.y) + " " + testkit::hex_string(v.z);
}

// Both the certified and the exact answer are `want`, and so is the one-sphere set's.
void expect_both(const Vec3& p, const Vec3& q, const Sphere& sphere, bool want) {
  EXPECT_EQ(segment_meets(p, q, sphere), want) << text(p) << " -> " << text(q);
  EXPECT_EQ(segment_meets_exact(p, q, sphere), want) << text(p) << " -> " << text(q);
  const std::vector<Sphere> one{sphere};
  EXPECT_EQ(occluded(p, q, SphereSet(one)), want) << text(p) << " -> " << text(q);
}

TEST(SphereSegmentHandDerived, ThroughAndShortOf) {
  // Along x through the unit sphere: e = (4, 0, 0), roots where −2 + 4t = ∓1: t = 1/4, 3/4, both inside (0, 1).
  expect_both({-2, 0, 0}, {2, 0, 0}, unit, true);
  // q = (−1, 0, 0) on the sphere: e = (1, 0, 0), roots t = 1 and 3: none strictly inside.
  expect_both({-2, 0, 0}, {-1, 0, 0}, unit, false);
  // Both ends inside: −1/2 + t = ∓1 at t = −1/2 and 3/2.
  expect_both({-0.5, 0, 0}, {0.5, 0, 0}, unit, false);
  // From inside to outside: −1/2 + (5/2)t = ∓1 at t = −1/5 and 3/5.
  expect_both({-0.5, 0, 0}, {2, 0, 0}, unit, true);
}

TEST(SphereSegmentHandDerived, EndsOnTheSphere) {
  // A diameter from surface to surface: −1 + 2t = ∓1 at t = 0 and 1, the ends: the open segment meets nothing.
  expect_both({-1, 0, 0}, {1, 0, 0}, unit, false);
  // From the surface across: 1 − 4t = ∓1 at t = 1/2 and 0: the far side at t = 1/2 counts.
  expect_both({1, 0, 0}, {-3, 0, 0}, unit, true);
  // From the surface away: 1 + 2t = ∓1 at t = −1 and 0: nothing inside.
  expect_both({1, 0, 0}, {3, 0, 0}, unit, false);
}

TEST(SphereSegmentHandDerived, TangentsAndAnUlpOff) {
  // y = 1 touches the sphere at x = 0: −2 + 4t = 0 at t = 1/2, a tangent root inside: the closed sphere blocks.
  expect_both({-2, 1, 0}, {2, 1, 0}, unit, true);
  // The same line from the touching point: t0 = 0, an end: nothing.
  expect_both({0, 1, 0}, {2, 1, 0}, unit, false);
  // y = 1 + 2^-52: |f|² − r² > B² for every t (the line misses by an ulp).
  expect_both({-2, 1 + 0x1p-52, 0}, {2, 1 + 0x1p-52, 0}, unit, false);
  // y = 1 − 2^-53: the line crosses, roots at x = ∓√(1 − (1 − 2^-53)²) ≈ ∓2^-26, t = 1/2 ∓ 2^-28: inside.
  expect_both({-2, 1 - 0x1p-53, 0}, {2, 1 - 0x1p-53, 0}, unit, true);
}

TEST(SphereSegmentHandDerived, DirectionThatIsNotADouble) {
  // p = (1 + 2^-52, 0, 0) just outside, q = (−2^-1074, 0, 0) inside: q − p = −(1 + 2^-52 + 2^-1074) is no double.
  // The line crosses x = 1 at t = 2^-52 / (1 + 2^-52 + 2^-1074), in (0, 1); x = −1 lies beyond q (t > 1).
  expect_both({1 + 0x1p-52, 0, 0}, {-0x1p-1074, 0, 0}, unit, true);
  // q = (1 − 2^-53, 0, 0) inside by half an ulp of 1, p = (3, 0, 0): x = 1 at t = 2/(2 + 2^-53) < 1: inside.
  expect_both({3, 0, 0}, {1 - 0x1p-53, 0, 0}, unit, true);
  // q = (1, 2^-1074, 0): |q|² − 1 = 2^-2148 > 0, just outside; p = (3, 0, 0). The line's closest approach to the
  // centre is below 1 only if it dips inside; it goes from x = 3 to x = 1 with y ≤ 2^-1074, so |point|² ≥ x² > 1
  // for x > 1 and the only candidates are beyond q: nothing inside (0, 1).
  expect_both({3, 0, 0}, {1, 0x1p-1074, 0}, unit, false);
}

TEST(SphereSegmentInvalid, EveryReasonIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)segment_meets({0, 0, 0}, {0, 0, 0}, unit), invalid_input);
  EXPECT_THROW((void)segment_meets({0, 0, 0}, {-0.0, 0, 0}, unit), invalid_input);  // 0 equals −0
  EXPECT_THROW((void)segment_meets({nan, 0, 0}, {1, 0, 0}, unit), invalid_input);
  EXPECT_THROW((void)segment_meets({0, 0, 0}, {1, 0, 0}, Sphere{{0, 0, 0}, 0}), invalid_input);
  EXPECT_THROW((void)occluded(Vec3{0, 0, 0}, Vec3{0, 0, 0}, SphereSet(std::vector<Sphere>{unit})), invalid_input);
  try {
    (void)segment_meets({0, 0, 0}, {0, 0, 0}, unit);
  } catch (const invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("p = q"), std::string::npos) << e.what();
  }
}

// A segment from a hard sphere query: p its origin, and q one of o + d (rounded), the mirror of p through the
// centre (2c − p, rounded) or the centre itself.
struct SegmentCase {
  Vec3 p, q;
  Sphere sphere;
};

SegmentCase segment_case(const testkit::SphereQuery& s, int which) {
  const Vec3& o = s.ray.origin;
  const Vec3& d = s.ray.direction;
  const Vec3& c = s.sphere.center;
  Vec3 q = which == 0 ? Vec3{o.x + d.x, o.y + d.y, o.z + d.z}
           : which == 1 ? Vec3{2 * c.x - o.x, 2 * c.y - o.y, 2 * c.z - o.z}
                        : c;
  return {o, q, s.sphere};
}

bool usable(const SegmentCase& s) { return !validate_segment(s.p, s.q).has_value(); }

RC_GTEST_PROP(SphereSegment, CertifiedAgreesWithExact, ()) {
  const auto kind = *rc::gen::elementOf(testkit::all_sphere_query_kinds);
  const int which = *rc::gen::inRange(0, 3);
  const testkit::SphereQuery s = *rc::gen::exec([kind] { return make_sphere_query(kind, testkit::rc_bit_source()); });
  const SegmentCase c = segment_case(s, which);
  RC_PRE(usable(c));
  RC_TAG(std::string(testkit::to_string(kind)));
  RC_ASSERT(segment_meets(c.p, c.q, c.sphere) == segment_meets_exact(c.p, c.q, c.sphere));
}

// Where e = q − p is a double (small integer coordinates) and neither end is on the sphere, a root lies in the
// open (0, 1) exactly when one lies in the closed [0, 1]: the ray p → e with the interval [0, 1] decides.
TEST(SphereSegment, AgreesWithTheClosedIntervalWhereNoEndIsOnTheSphere) {
  testkit::SplitMix64 rng(17);
  auto coordinate = [&] { return static_cast<double>(static_cast<int>(rng() % 17) - 8); };
  int met = 0, compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p{coordinate(), coordinate(), coordinate()}, q{coordinate(), coordinate(), coordinate()};
    const Sphere sphere{{coordinate(), coordinate(), coordinate()}, static_cast<double>(1 + rng() % 6)};
    if (validate_segment(p, q)) continue;
    const auto on_sphere = [&](const Vec3& x) {
      const double fx = x.x - sphere.center.x, fy = x.y - sphere.center.y, fz = x.z - sphere.center.z;
      return fx * fx + fy * fy + fz * fz == sphere.radius * sphere.radius;  // small integers: exact
    };
    if (on_sphere(p) || on_sphere(q)) continue;
    const Ray ray{p, {q.x - p.x, q.y - p.y, q.z - p.z}};  // integers: exact
    const bool closed = nearest_root(ray, RayInterval{0, 1}, sphere).has_value();
    EXPECT_EQ(segment_meets(p, q, sphere), closed) << text(p) << " -> " << text(q);
    met += closed;
    ++compared;
  }
  EXPECT_GT(compared, 15000);
  EXPECT_GT(met, 2000);
}

// Every hard kind, deterministic: certified == exact, in the default environment and in the others.
TEST(SphereSegment, AgreesWithExactOnEveryKindInEveryEnvironment) {
  testkit::SplitMix64 rng(23);
  const testkit::BitSource source = [&rng] { return rng(); };
  std::vector<SegmentCase> cases;
  for (testkit::SphereQueryKind kind : testkit::all_sphere_query_kinds)
    for (int i = 0; i < 150; ++i) {
      const testkit::SphereQuery s = testkit::make_sphere_query(kind, source);
      for (int which = 0; which < 3; ++which)
        if (const SegmentCase c = segment_case(s, which); usable(c)) cases.push_back(c);
    }
  std::vector<bool> want;
  int met = 0;
  for (const SegmentCase& c : cases) {
    want.push_back(segment_meets_exact(c.p, c.q, c.sphere));
    met += want.back();
    EXPECT_EQ(segment_meets(c.p, c.q, c.sphere), want.back()) << text(c.p) << " -> " << text(c.q);
  }
  EXPECT_GT(met, 500);
  EXPECT_LT(met, static_cast<int>(cases.size()) - 500);
  for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    ASSERT_EQ(std::fesetround(mode), 0);
    for (std::size_t i = 0; i < cases.size(); ++i)
      EXPECT_EQ(segment_meets(cases[i].p, cases[i].q, cases[i].sphere), want[i]) << mode;
    std::fesetround(FE_TONEAREST);
  }
}

// occluded(p, q, SphereSet) walks the set's BVH by the box of the segment's ends: on a set large enough to have one
// (spheres on a coarse dyadic grid, so that segments end on spheres, graze them and pass between them), it says
// what the exact reference says of the spheres one by one — no sphere the segment meets is culled.
TEST(SphereSetSegments, TheBvhWalkMissesNoSphere) {
  std::mt19937_64 rng(20261129);
  const auto grid = [&](int lo, int hi) {
    return static_cast<double>(std::uniform_int_distribution<int>(lo, hi)(rng)) / 4.0;
  };
  std::vector<Sphere> spheres;
  for (int k = 0; k < 60; ++k) spheres.push_back({{grid(-16, 16), grid(-16, 16), grid(-16, 16)}, grid(1, 6)});
  const SphereSet set(spheres);
  ASSERT_NE(set.bvh(), nullptr);
  int met = 0;
  for (int i = 0; i < 4000; ++i) {
    Vec3 p{grid(-20, 20), grid(-20, 20), grid(-20, 20)};
    // Short and long segments, some along an axis (flat boxes), some from a sphere's centre outwards.
    const int span = i % 3 == 0 ? 4 : 40;
    Vec3 q{p.x + grid(-span, span), p.y + (i % 5 == 0 ? 0.0 : grid(-span, span)), p.z + grid(-span, span)};
    if (i % 7 == 0) p = spheres[static_cast<std::size_t>(i) % spheres.size()].center;
    if (p.x == q.x && p.y == q.y && p.z == q.z) q.x += 1;
    bool want = false;
    for (const Sphere& s : spheres) want = want || segment_meets_exact(p, q, s);
    EXPECT_EQ(occluded(p, q, set), want) << text(p) << " -> " << text(q);
    met += want;
  }
  EXPECT_GT(met, 800);
  EXPECT_LT(met, 3200);
}

// The CLI's --spheres streams (docs/contract.md, "Decided here"): answers worked out by hand. The unit sphere and
// one of radius 2 at (10, 0, 0); rays along +x from x = −5 meet the first at t = 4, 6 and the second at 13, 17.
TEST(SphereSetCli, NearestAndOccludedLines) {
  std::istringstream file("# two spheres\n0 0 0 1\n\n10 0 0 2\n");
  const cli::SpheresFile spheres = cli::read_spheres(file);
  ASSERT_TRUE(spheres.ok()) << spheres.error;
  ASSERT_EQ(spheres.items.size(), 2u);
  const SphereSet set(spheres.items);
  const std::string rays =
      "-5 0 0 1 0 0\n"           // t = 4 (sphere 0)
      "-5 0 0 1 0 0 5 inf\n"     // [5, inf]: t = 6 (the unit sphere's far side)
      "-5 0 0 1 0 0 6.5 13\n"    // [6.5, 13]: t = 13 (sphere 1's near side, the closed bound)
      "-5 0 0 1 0 0 6.5 12.5\n"  // nothing in [6.5, 12.5]
      "-5 5 0 1 0 0\n"           // y = 5 misses both
      "0 0 0 0 0 0\n";           // invalid
  for (cli::Method method : {cli::Method::certified, cli::Method::exact}) {
    std::istringstream in(rays);
    std::ostringstream out, err;
    cli::SphereSetCounts counts;
    const cli::SphereSetOptions options{.method = method};
    EXPECT_EQ(cli::sphere_nearest_stream(in, out, err, set, options, counts), cli::exit_invalid_line);
    EXPECT_EQ(out.str(), "hit 0 4\nhit 0 6\nhit 1 13\nmiss\nmiss\ninvalid ray direction is the zero vector\n");
    std::istringstream in2(rays);
    std::ostringstream out2, err2;
    cli::SphereSetCounts counts2;
    EXPECT_EQ(cli::sphere_occluded_stream(in2, out2, err2, set, options, counts2), cli::exit_invalid_line);
    EXPECT_EQ(out2.str(), "occluded\noccluded\noccluded\nclear\nclear\ninvalid ray direction is the zero vector\n");
  }
  const std::string segments =
      "-2 0 0 2 0 0\n"   // through the unit sphere
      "-1 0 0 1 0 0\n"   // surface to surface: roots at the ends only
      "1 0 0 -3 0 0\n"   // from the surface across: the far side at t = 1/2
      "5 0 0 7 0 0\n"    // between the spheres
      "1 1 1 1 1 1\n";   // p = q
  for (cli::Method method : {cli::Method::certified, cli::Method::exact}) {
    std::istringstream in(segments);
    std::ostringstream out, err;
    cli::SphereSetCounts counts;
    const cli::SphereSetOptions options{.method = method, .segment = true};
    EXPECT_EQ(cli::sphere_occluded_stream(in, out, err, set, options, counts), cli::exit_invalid_line);
    EXPECT_EQ(out.str(), "occluded\nclear\noccluded\nclear\ninvalid segment endpoints are equal (p = q)\n");
    EXPECT_EQ(err.str(), "raykernel: line 5: segment endpoints are equal (p = q)\n");
  }
}

TEST(SphereSetCli, AnInvalidSphereLineIsNamed) {
  std::istringstream file("0 0 0 1\n# fine so far\n1 2 3 -1\n4 5 6 1\n");
  const cli::SpheresFile spheres = cli::read_spheres(file);
  EXPECT_FALSE(spheres.ok());
  EXPECT_EQ(spheres.error_line, 3u);
  EXPECT_NE(spheres.error.find("radius"), std::string::npos) << spheres.error;
  EXPECT_TRUE(spheres.items.empty());
  std::istringstream short_line("0 0 0\n");
  EXPECT_EQ(cli::read_spheres(short_line).error_line, 1u);
}

}  // namespace
}  // namespace raykernel
