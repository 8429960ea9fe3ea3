// Inputs of the differential runner: COUNT lines per routine, "routine x1 x2 ..." with every input a 64-bit
// pattern in unsigned decimal.
//
// Two sources, mixed per routine:
//   * the testkit's hard queries (testkit/include/raykernel/testkit/plane_queries.hpp: near-parallel,
//     near-coplanar, exact degeneracies, ties, subnormal, huge, t overflow/underflow, ...) and near-tie plane
//     pairs (plane_pairs.hpp), turned into each routine's arguments the way the cascade forms them (den from
//     d and n, num from p ⊖ o and n with the TwoDiff low parts, enclosures from stage 2, expansions from
//     stage 3), so that the certifying branches are exercised;
//   * raw bit patterns: uniformly random 64-bit words and special values (±0, ±smallest and largest
//     subnormal, ±smallest normal, ±1, ±largest finite, ±inf, quiet and signalling NaNs with payloads and
//     both signs, extreme exponents), alone or injected into hard queries;
//   * for the BVH's ray–box test, scenes of binary32 boxes and rays aimed at their faces (box_scene, box_ray).
// Deterministic in SEED (SplitMix64), which is printed.
//
// Usage: raykernel_twin_inputs SEED COUNT OUT_FILE [ROUTINE...]
#include "nearest/compare_quotients.hpp"
#include "core/eft.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/ray_plane_stages.hpp"
#include "triangle/ray_triangle_stages.hpp"
#include "box/ray_box.hpp"

#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/plane_pairs.hpp>
#include <raykernel/testkit/sphere_queries.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/sphere.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {

using raykernel::testkit::SplitMix64;
using namespace raykernel;
using detail::DoubleDouble;

class Source {
 public:
  explicit Source(std::uint64_t seed) : rng_(seed) {}
  std::uint64_t word() { return rng_(); }
  std::uint64_t below(std::uint64_t n) { return rng_() % n; }
  bool chance(int one_in) { return below(static_cast<std::uint64_t>(one_in)) == 0; }

  // A raw input: a special value (1 in 4) or a uniformly random word.
  double raw() {
    static constexpr std::array<std::uint64_t, 26> special = {
        0x0000000000000000ULL, 0x8000000000000000ULL,  // ±0
        0x0000000000000001ULL, 0x8000000000000001ULL,  // ±smallest subnormal
        0x000fffffffffffffULL, 0x800fffffffffffffULL,  // ±largest subnormal
        0x0010000000000000ULL, 0x8010000000000000ULL,  // ±smallest normal
        0x3ff0000000000000ULL, 0xbff0000000000000ULL,  // ±1
        0x7fefffffffffffffULL, 0xffefffffffffffffULL,  // ±largest finite
        0x7ff0000000000000ULL, 0xfff0000000000000ULL,  // ±inf
        0x7ff8000000000000ULL, 0xfff8000000000000ULL,  // quiet NaNs
        0x7ff0000000000001ULL, 0x7ff4000000000000ULL,  // signalling NaNs
        0x7ff8dead0000beefULL, 0x7fe0000000000000ULL,  // NaN with payload; 2^1023
        0x0360000000000000ULL, 0x4340000000000000ULL,  // 2^-969 (TwoProduct boundary); 2^53
        0x3ca0000000000000ULL, 0x7fdfffffffffffffULL,  // 2^-53; just below 2^1023
        0x0020000000000000ULL, 0x3fefffffffffffffULL,  // 2^-1021; 1 - 2^-53
    };
    if (chance(4)) return std::bit_cast<double>(special[below(special.size())]);
    if (chance(3)) {  // a random significand at an extreme or a moderate exponent
      const std::uint64_t exponent = chance(2) ? below(40) + (chance(2) ? 0 : 2007) : 1023 - 60 + below(120);
      return std::bit_cast<double>((word() & 0x800fffffffffffffULL) | (exponent << 52));
    }
    return std::bit_cast<double>(word());
  }

  // n raw inputs.
  std::vector<double> raws(int n) {
    std::vector<double> x;
    for (int i = 0; i < n; ++i) x.push_back(raw());
    return x;
  }

  testkit::Query query() {
    const auto kind = testkit::all_query_kinds[below(testkit::all_query_kinds.size())];
    testkit::Query q = testkit::make_query(kind, [this] { return word(); });
    if (chance(8)) {  // a special value in one component (invalid input: the cascade must not certify)
      double* c[12] = {&q.ray.origin.x, &q.ray.origin.y, &q.ray.origin.z, &q.ray.direction.x,
                       &q.ray.direction.y, &q.ray.direction.z, &q.plane.point.x, &q.plane.point.y,
                       &q.plane.point.z, &q.plane.normal.x, &q.plane.normal.y, &q.plane.normal.z};
      *c[below(12)] = raw();
    }
    return q;
  }
  // A hard ray–triangle query (testkit/triangle_queries.hpp: through vertices and edges, ulps beside them,
  // slivers, needles, degenerate, parallel, coplanar, rounding ties, wide, tiny and huge scales), as the 15
  // inputs "o d a b c"; 1 in 8 with a raw special value in one component, 1 in 8 with the signs of its zeros
  // flipped, 1 in 16 wholly raw.
  std::vector<double> triangle_query() {
    if (chance(16)) return raws(15);
    const auto kind = testkit::all_triangle_query_kinds[below(testkit::all_triangle_query_kinds.size())];
    const testkit::TriangleQuery q = testkit::make_triangle_query(kind, [this] { return word(); });
    std::vector<double> x = {q.ray.origin.x,    q.ray.origin.y,    q.ray.origin.z, q.ray.direction.x,
                             q.ray.direction.y, q.ray.direction.z, q.triangle.a.x, q.triangle.a.y,
                             q.triangle.a.z,    q.triangle.b.x,    q.triangle.b.y, q.triangle.b.z,
                             q.triangle.c.x,    q.triangle.c.y,    q.triangle.c.z};
    if (chance(8)) x[below(15)] = raw();
    if (chance(8))  // every zero component's sign flipped: the lanes' broadcast maps −0 to +0 (TriangleTwins.v, bcast)
      for (double& c : x)
        if (c == 0) c = -c;
    return x;
  }
  // A hard ray–sphere query (testkit/sphere_queries.hpp: tangents and an ulp off, origins on the surface,
  // rounding ties, cancelling far-away spheres, extreme exponents), as the 10 inputs "o d c r"; 1 in 8 with a raw
  // special value in one component, 1 in 16 wholly raw.
  std::vector<double> sphere_query() {
    if (chance(16)) return raws(10);
    const auto kind = testkit::all_sphere_query_kinds[below(testkit::all_sphere_query_kinds.size())];
    const testkit::SphereQuery q = testkit::make_sphere_query(kind, [this] { return word(); });
    std::vector<double> x = {q.ray.origin.x,    q.ray.origin.y,    q.ray.origin.z,   q.ray.direction.x,
                             q.ray.direction.y, q.ray.direction.z, q.sphere.center.x, q.sphere.center.y,
                             q.sphere.center.z, q.sphere.radius};
    if (chance(8)) x[below(10)] = raw();
    return x;
  }
  // A sphere query, a root (word 0: t1, 1: t2) and a boundary x, y beside that root: the textbook root and the
  // next double (a rounding boundary), the root twice (a bound of an interval), or raw.
  std::vector<double> sphere_root_side_args() {
    std::vector<double> x = sphere_query();
    const std::uint64_t root = below(2);
    const SphereIntersection r = intersect_naive(Ray{{x[0], x[1], x[2]}, {x[3], x[4], x[5]}},
                                                 Sphere{{x[6], x[7], x[8]}, x[9]});
    double m = root == 0 ? r.t1 : r.t2;
    if (!std::isfinite(m) || chance(8)) m = raw();
    const double n = chance(3) ? m : std::nextafter(m, chance(2) ? INFINITY : -INFINITY);
    x.push_back(std::bit_cast<double>(root));
    x.push_back(m);
    x.push_back(n);
    return x;
  }
  // A ray–triangle query whose origin is just off the plane above a point well inside the triangle, at a
  // distance about 2^-44..2^-73 of the triangle's size: num = det(a − o, b − o, c − o) is then below its
  // stage-1 filter bound (about 8u·m) but within stage 2's reach, while πa, πb, πc and den stay clear of
  // theirs; d random (the line crosses the plane near o, inside).
  std::vector<double> near_plane_triangle_query() {
    auto unit = [this] { return static_cast<double>(word() >> 11) * 0x1p-52 - 1.0; };  // in [−1, 1)
    double v[9];
    for (double& c : v) c = unit();
    double w[3];
    for (double& c : w) c = 0.1 + 0.9 * std::abs(unit());
    const double total = w[0] + w[1] + w[2];
    const double e1[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]};
    const double e2[3] = {v[6] - v[0], v[7] - v[1], v[8] - v[2]};
    const double normal[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                              e1[0] * e2[1] - e1[1] * e2[0]};
    const double offset = std::ldexp(chance(2) ? 1.0 : -1.0, -44 - static_cast<int>(below(30)));
    std::vector<double> x(15);
    for (int i = 0; i < 3; ++i) {
      const double inside = (w[0] * v[i] + w[1] * v[3 + i] + w[2] * v[6 + i]) / total;
      x[i] = inside + normal[i] * offset;
      x[3 + i] = unit();
    }
    for (int i = 0; i < 9; ++i) x[6 + i] = v[i];
    return x;
  }
  // The points of an orientation test (mesh_predicates.hpp, proofs/orient/OrientTwins.v), as "o a b c": those
  // of a hard triangle query (its ray's origin and the triangle's vertices: through vertices and edges,
  // degenerate, coplanar, tiny and huge, raw values), 1 in 4 an origin just off the triangle's plane
  // (near_plane_triangle_query: orient3d near its filter's bound), 1 in 4 with c on the line ab up to its
  // rounding and a nudge of an ulp (orient2d near 0 in every plane), 1 in 8 scaled by 2^s, s in [−1100, 1000]
  // (the range test's bounds 2^±300, underflow and overflow), 1 in 16 wholly raw.
  std::vector<double> orientation_points() {
    std::vector<double> x(12);
    if (chance(16)) {
      for (double& c : x) c = raw();
      return x;
    }
    const std::vector<double> q = chance(4) ? near_plane_triangle_query() : triangle_query();
    for (int i = 0; i < 3; ++i) x[i] = q[i];
    for (int i = 0; i < 9; ++i) x[3 + i] = q[6 + i];
    if (chance(4)) {  // c = a + t·(b − a), rounded, one coordinate nudged by an ulp
      const double t = static_cast<double>(word() >> 11) * 0x1p-53;
      for (int i = 0; i < 3; ++i) x[9 + i] = x[3 + i] + t * (x[6 + i] - x[3 + i]);
      if (chance(2)) {
        double& c = x[9 + below(3)];
        c = std::nextafter(c, chance(2) ? HUGE_VAL : -HUGE_VAL);
      }
    }
    if (chance(8)) {
      const int s = static_cast<int>(below(2101)) - 1100;
      for (double& c : x) c = std::ldexp(c, s);
    }
    return x;
  }
  // A query whose den and num cancel to about u²·m, where stage 2's first level is uncertain and its second
  // level decides (no testkit kind aims there): n random; a_0 random, a_1 = −a_0·n_0/n_1 rounded, so that
  // a_0·n_0 + a_1·n_1 = r is about u·m; a_2 = −r/n_2 rounded, so that the whole sum is about u·|r|. d is such a
  // vector; p − o another (o = 0 or a power of two, which p − o leaves exact), one of the two sometimes random.
  testkit::Query refined_zone_query() {
    auto unit = [this] { return (static_cast<double>(word() >> 11) * 0x1p-53 + 0.5) * (chance(2) ? 1 : -1); };
    double n[3], d[3], e[3];
    for (double& c : n) c = unit();
    auto cancel = [&](double a[3]) {
      a[0] = unit();
      a[1] = -(a[0] * n[0]) / n[1];
      const detail::DoubleDouble p0 = detail::two_prod(a[0], n[0]), p1 = detail::two_prod(a[1], n[1]);
      const double r = (p0.hi + p1.hi) + (p0.lo + p1.lo);
      a[2] = -r / n[2];
    };
    cancel(d), cancel(e);
    if (chance(4)) d[below(3)] = unit();
    else if (chance(4)) e[below(3)] = unit();
    const double shift = chance(2) ? 0.0 : 0x1p3;
    return {{{shift, shift, shift}, {d[0], d[1], d[2]}}, {{e[0] + shift, e[1] + shift, e[2] + shift}, {n[0], n[1], n[2]}}};
  }
  // A query with an exact stage-3 expansion that fails Expansion::sign's check 2·Σ|lower| < |top| while the
  // other expansion's sign is certain and stage 2 leaves a sign open. The shape, from three products
  // h0·1 + r·1 + d3·n3 with d3·n3 = h2 + l2 exactly (TwoProduct), h0 = −h2 an odd multiple of q = ulp(h0),
  // r = ±q/2 − l2: the expansion sum meets l2 + r = ±q/2 first, then h0: the tie rounds to even, away from h0
  // (h0 ± q, low ∓q/2), and h2 cancels h0: the expansion is [∓q/2, ±q] (value ±q/2, the shape of
  // CompareStage3Liveness.v's `compare_stage3_uncertain_example`). n = (1, 1, n3) and
  // p = (−(x·n3).hi, −(x·n3).lo, x), whose terms cancel exactly. Half of the queries put the shape in den:
  // d = (h0, r, d3)·2^k (|k| ≤ 40, exact), o = (0, t, 0), num = −t exactly (p_1 ⊖ t and its TwoDiff low
  // part; t = 0 or ±2^-150..2^-349, below stage 2's reach |num| ≤ 1714u³·S); stage 2 certifies den. The
  // other half put it in num's TwoDiff low parts: o = −(h0, r, d3)·2^-j (150 ≤ j < 450), so p_i − o_i =
  // p_i + low_i with low = (h0, r, d3)·2^-j and num = ±(q/2)·2^-j, far below stage 2's reach; d random, den
  // certain. Either way the cascade must go to the exact stage; stage 3 returning on the certain sign alone
  // would return the other `uncertain` and, half of the time, the wrong relation.
  testkit::Query stage3_tie_query() {
    auto unit = [this] { return (static_cast<double>(word() >> 11) * 0x1p-53 + 0.5) * (chance(2) ? 1 : -1); };
    double d3, n3, h0, q, half;
    detail::DoubleDouble p{};
    do {  // h0 an odd multiple of its ulp (half the draws), r = half − l2 exact (nearly all)
      d3 = unit(), n3 = unit();
      p = detail::two_prod(d3, n3);
      h0 = -p.hi;
      q = std::ldexp(1.0, std::ilogb(h0) - 52);
      half = p.lo > 0 ? q / 2 : -q / 2;
    } while (p.lo == 0 || std::fmod(h0 / q, 2.0) == 0 || detail::two_diff(half, p.lo).lo != 0);
    const double r = half - p.lo;
    const double x = unit();
    const detail::DoubleDouble px = detail::two_prod(x, n3);
    const Vec3 terms_cancel{-px.hi, -px.lo, x}, normal{1, 1, n3};
    if (chance(2)) {  // the shape in num's low parts (px.lo ≠ 0: else p_1 = 0 and the low part moves)
      const double tail = std::ldexp(1.0, -150 - static_cast<int>(below(300)));
      if (px.lo != 0) return {{{-h0 * tail, -r * tail, -d3 * tail}, {unit(), unit(), unit()}}, {terms_cancel, normal}};
    }
    const double t = chance(2) ? 0.0 : std::ldexp(unit(), -149 - static_cast<int>(below(200)));
    const double scale = std::ldexp(1.0, static_cast<int>(below(81)) - 40);
    return {{{0, t, 0}, {h0 * scale, r * scale, d3 * scale}}, {terms_cancel, normal}};
  }
  testkit::PlanePair plane_pair() { return testkit::make_plane_pair_near_tie([this] { return word(); }); }

 private:
  SplitMix64 rng_;
};

struct Terms {
  double o[3], d[3], p[3], n[3], diff[3], diff_lo[3];
};
Terms terms(const testkit::Query& q) {
  Terms t{{q.ray.origin.x, q.ray.origin.y, q.ray.origin.z},
          {q.ray.direction.x, q.ray.direction.y, q.ray.direction.z},
          {q.plane.point.x, q.plane.point.y, q.plane.point.z},
          {q.plane.normal.x, q.plane.normal.y, q.plane.normal.z},
          {},
          {}};
  for (int i = 0; i < 3; ++i) {
    const DoubleDouble s = detail::two_diff(t.p[i], t.o[i]);
    t.diff[i] = s.hi;
    t.diff_lo[i] = s.lo;
  }
  return t;
}

using Args = std::vector<double>;

// The arguments of the dot-product routines from a query: den (a = d, α = 0, b = n) or num (a = p ⊖ o,
// α = the TwoDiff low part, b = n).
Args dot3_args(const Terms& t, bool num, bool with_alpha) {
  Args a;
  for (int i = 0; i < 3; ++i) a.push_back(num ? t.diff[i] : t.d[i]);
  if (with_alpha)
    for (int i = 0; i < 3; ++i) a.push_back(num ? t.diff_lo[i] : 0.0);
  for (int i = 0; i < 3; ++i) a.push_back(t.n[i]);
  return a;
}

Args raw_args(Source& s, int n) {
  Args a;
  for (int i = 0; i < n; ++i) a.push_back(s.raw());
  return a;
}

detail::Enclosure stage2(const testkit::Query& q, bool num, bool refined) {
  const detail::RayPlaneTerms t = detail::ray_plane_terms(q.ray, q.plane);
  if (refined) return num ? detail::num_refined(t) : detail::den_refined(t);
  return num ? detail::num_compensated(t) : detail::den_compensated(t);
}

std::vector<double> expansion_components(const testkit::Query& q, bool num) {
  const detail::ExactExpansions e = detail::ray_plane_expansions(detail::ray_plane_terms(q.ray, q.plane));
  std::vector<double> c;
  if (num)
    c.assign(e.num.component, e.num.component + e.num.size);
  else
    c.assign(e.den.component, e.den.component + e.den.size);
  return c;
}

// A ray and two planes: a near-tie plane pair (testkit/plane_pairs.hpp), or the ray of one hard query with
// the planes of it and of another.
Args pair_args(Source& s) {
  Args a;
  auto push3 = [&](const Vec3& v) { a.push_back(v.x), a.push_back(v.y), a.push_back(v.z); };
  if (s.chance(2)) {
    const testkit::PlanePair pp = s.plane_pair();
    push3(pp.ray.origin), push3(pp.ray.direction);
    for (const Plane& p : pp.planes) push3(p.point), push3(p.normal);
  } else {
    const testkit::Query q1 = s.query(), q2 = s.query();
    push3(q1.ray.origin), push3(q1.ray.direction), push3(q1.plane.point), push3(q1.plane.normal);
    push3(q2.plane.point), push3(q2.plane.normal);
  }
  return a;
}

testkit::Query query_of(const Args& a, int plane) {
  const std::size_t at = 6 + 6 * static_cast<std::size_t>(plane);
  return {{{a[0], a[1], a[2]}, {a[3], a[4], a[5]}}, {{a[at], a[at + 1], a[at + 2]}, {a[at + 3], a[at + 4], a[at + 5]}}};
}

Args query_args(const testkit::Query& q) {
  return {q.ray.origin.x,    q.ray.origin.y,    q.ray.origin.z,    q.ray.direction.x,
          q.ray.direction.y, q.ray.direction.z, q.plane.point.x,   q.plane.point.y,
          q.plane.point.z,   q.plane.normal.x,  q.plane.normal.y,  q.plane.normal.z};
}

// An expansion: the components of a query's num or den expansion, or a raw list.
std::vector<double> some_expansion(Source& s, std::size_t max_raw) {
  if (s.chance(3)) {
    std::vector<double> c;
    const std::size_t n = 1 + static_cast<std::size_t>(s.below(max_raw));
    for (std::size_t i = 0; i < n; ++i) c.push_back(s.raw());
    return c;
  }
  return expansion_components(s.query(), s.chance(2));
}

// A leading integer word (the options, the rule or a determinant's index, as its bit pattern), then a
// ray–triangle query. The word is an argument, so it is drawn before the query (the order the seed fixes).
Args word_then(std::uint64_t word, const std::vector<double>& query) {
  Args a{std::bit_cast<double>(word)};
  a.insert(a.end(), query.begin(), query.end());
  return a;
}
Args word_then_triangle_query(Source& s, std::uint64_t word) { return word_then(word, s.triangle_query()); }

// ---- spawn (spawn/spawn_certified.hpp, proofs/spawn/SpawnTwins.v) ----------------------------------------------

// A double with a random significand and sign and the biased exponent e, clamped to [0, 2046] (0: subnormal or zero).
double with_exponent(Source& s, long e) {
  const auto biased = static_cast<std::uint64_t>(std::clamp(e, 0L, 2046L));
  return std::bit_cast<double>((s.word() & 0x800fffffffffffffULL) | (biased << 52));
}
double any_sign(Source& s, double x) { return s.chance(2) ? x : -x; }
double neighbour(Source& s, double x) { return std::nextafter(x, s.chance(2) ? HUGE_VAL : -HUGE_VAL); }

// A hard ray–triangle query (1 in 4 with its origin just off the plane) and the triangle's stage-2 enclosures of
// num and den, as spawn's rounded_hit gets them (triangle_quotient_compensated).
struct SpawnQuery {
  std::vector<double> q;  // "o d a b c"
  detail::TriangleQuotientStage2 v;
};
SpawnQuery spawn_query(Source& s) {
  SpawnQuery r{s.chance(4) ? s.near_plane_triangle_query() : s.triangle_query(), {}};
  const std::vector<double>& q = r.q;
  const Ray ray{{q[0], q[1], q[2]}, {q[3], q[4], q[5]}};
  const Triangle tri{{q[6], q[7], q[8]}, {q[9], q[10], q[11]}, {q[12], q[13], q[14]}};
  r.v = detail::triangle_quotient_compensated(ray, tri);
  return r;
}

// "x y o" of midpoint_offset, the enclosure of x + y − 2·o ((x + y)/2 a rounding boundary between the doubles x, y
// beside a hit point's coordinate, o the ray origin's coordinate): 1 in 8 raw; else one of
//   uniformly random words;
//   x, y adjacent doubles (1 in 4: x = y, as round_binary32_from_binary64 asks at r = r), o near them: x or y,
//     1–4 ulps from x, x·(1 ± 2^-j), or x·2^k (so that the TwoSums' low parts are nonzero and l + e rounds);
//   the call site: a hard ray–triangle query's coordinate x = o_k + (num.hi/den.hi)·d_k, its neighbour, o_k;
//   three random significands at the exponents E, E − a, E − b (a, b ≤ 120) in any order (l + e inexact);
//   subnormal: x, y, o below or at the smallest normal 2^-1022 (l + e exact);
//   huge: x near 2^1023 with its neighbour (x + y overflows), o huge (2·o overflows) or the largest finite;
// then 1 in 8 with one of the three a raw value.
Args midpoint_offset_args(Source& s) {
  if (s.chance(8)) return raw_args(s, 3);
  Args a(3);
  switch (s.below(6)) {
    case 0:
      for (double& v : a) v = std::bit_cast<double>(s.word());
      break;
    case 1: {
      const double x = with_exponent(s, 1023 - 60 + static_cast<long>(s.below(120)));
      const double y = s.chance(4) ? x : neighbour(s, x);
      double o = x;
      switch (s.below(4)) {
        case 0:
          if (s.chance(2)) o = y;
          break;
        case 1:
          for (std::uint64_t k = 1 + s.below(4); k > 0; --k) o = neighbour(s, o);
          break;
        case 2:
          o = x * (1 + any_sign(s, std::ldexp(1.0, -1 - static_cast<int>(s.below(60)))));
          break;
        default:
          o = any_sign(s, std::ldexp(x, static_cast<int>(s.below(121)) - 60));
      }
      a = {x, y, o};
      break;
    }
    case 2: {
      const SpawnQuery sq = spawn_query(s);
      const std::size_t k = static_cast<std::size_t>(s.below(3));
      const double o = sq.q[k], d = sq.q[3 + k];
      const double x = o + (sq.v.num.hi / sq.v.den.hi) * d;
      a = {x, s.chance(4) ? x : neighbour(s, x), o};
      break;
    }
    case 3: {
      const long e = 200 + static_cast<long>(s.below(1700));
      const long exponents[3] = {e, e - static_cast<long>(s.below(121)), e - static_cast<long>(s.below(121))};
      const std::size_t first = static_cast<std::size_t>(s.below(3));
      for (std::size_t i = 0; i < 3; ++i) a[i] = with_exponent(s, exponents[(first + i) % 3]);
      break;
    }
    case 4: {
      const double x = with_exponent(s, static_cast<long>(s.below(2)));
      a = {x, s.chance(2) ? neighbour(s, x) : with_exponent(s, static_cast<long>(s.below(2))),
           s.chance(3) ? x : with_exponent(s, static_cast<long>(s.below(3)))};
      break;
    }
    default: {
      const double x = with_exponent(s, 2040 + static_cast<long>(s.below(7)));
      const double o = s.chance(4) ? any_sign(s, std::numeric_limits<double>::max())
                                   : with_exponent(s, 2020 + static_cast<long>(s.below(27)));
      a = {x, s.chance(2) ? neighbour(s, x) : with_exponent(s, 2040 + static_cast<long>(s.below(7))), o};
    }
  }
  if (s.chance(8)) a[s.below(3)] = s.raw();
  return a;
}

// An enclosure (hi, lo, radius) as affine_enclosure may get one, not normalized: hi at a moderate exponent (1 in 8:
// ±0); lo ±0, at or below u·|hi| (normalized), between u·|hi| and |hi|, or above |hi|; the radius 0, far below hi,
// of hi's size, up to 2^1000 times it, the largest finite, or subnormal.
std::array<double, 3> loose_enclosure(Source& s) {
  const long e = 1023 - 100 + static_cast<long>(s.below(200));
  const double hi = s.chance(8) ? any_sign(s, 0.0) : with_exponent(s, e);
  double lo = 0;
  switch (s.below(4)) {
    case 0: lo = any_sign(s, 0.0); break;
    case 1: lo = with_exponent(s, e - 53 - static_cast<long>(s.below(20))); break;
    case 2: lo = with_exponent(s, e - static_cast<long>(s.below(53))); break;
    default: lo = with_exponent(s, e + 1 + static_cast<long>(s.below(8)));
  }
  double radius = 0;
  switch (s.below(6)) {
    case 0: break;
    case 1: radius = std::abs(with_exponent(s, e - 60 - static_cast<long>(s.below(60)))); break;
    case 2: radius = std::abs(with_exponent(s, e - 5 + static_cast<long>(s.below(10)))); break;
    case 3: radius = std::abs(with_exponent(s, e + static_cast<long>(s.below(1000)))); break;
    case 4: radius = std::numeric_limits<double>::max(); break;
    default: radius = std::abs(with_exponent(s, 0));
  }
  return {hi, lo, radius};
}

// "o D.hi D.lo D.radius d N.hi N.lo N.radius" of affine_enclosure, the enclosure of o·D + d·N: 1 in 16 wholly raw;
// half the call site (a hard ray–triangle query's o_k, den's stage-2 enclosure, d_k, num's: the numerator
// o_k·den + d_k·num of the hit point's coordinate); half loose enclosures (loose_enclosure) with o and d at moderate
// or extreme exponents (products that underflow or overflow), ±0 or random words; 1 in 8 with one field raw.
Args affine_enclosure_args(Source& s) {
  if (s.chance(16)) return raw_args(s, 8);
  Args a;
  if (s.chance(2)) {
    const SpawnQuery sq = spawn_query(s);
    const std::size_t k = static_cast<std::size_t>(s.below(3));
    const detail::Enclosure& D = sq.v.den;
    const detail::Enclosure& N = sq.v.num;
    a = {sq.q[k], D.hi, D.lo, D.radius, sq.q[3 + k], N.hi, N.lo, N.radius};
  } else {
    auto coordinate = [&s]() -> double {
      switch (s.below(5)) {
        case 0: return with_exponent(s, static_cast<long>(s.below(60)));
        case 1: return with_exponent(s, 1990 + static_cast<long>(s.below(57)));
        case 2: return any_sign(s, 0.0);
        case 3: return std::bit_cast<double>(s.word());
        default: return with_exponent(s, 1023 - 60 + static_cast<long>(s.below(120)));
      }
    };
    const double o = coordinate();
    const std::array<double, 3> D = loose_enclosure(s);
    const double d = coordinate();
    const std::array<double, 3> N = loose_enclosure(s);
    a = {o, D[0], D[1], D[2], d, N[0], N[1], N[2]};
  }
  if (s.chance(8)) a[s.below(8)] = s.raw();
  return a;
}

// A quotient at a rounding boundary (round_quotient_at_boundaries): a candidate q (a few significant bits,
// a power of two, or raw), den = D_1 (+ D_2) and num = (q + δ)·den as TwoProducts, δ = 0, half the gap above
// or below q (t on a midpoint: a tie) or a random offset, sometimes with a tiny extra component (t just off
// the midpoint); den's sign word (mostly the true sign). "s q k num.. den..".
Args boundary_args(Source& s) {
  double q;
  if (s.chance(8)) q = s.raw();
  else {
    const double m = s.chance(3) ? 1.0 : 1.0 + static_cast<double>(s.below(1 << 20)) * 0x1p-20;
    q = std::ldexp(s.chance(2) ? m : -m, static_cast<int>(s.below(200)) - 100);
  }
  std::vector<double> den{std::ldexp(static_cast<double>(2 * s.below(1 << 10) + 1) * (s.chance(2) ? 1 : -1),
                                     static_cast<int>(s.below(60)) - 30)};
  if (s.chance(3)) den.push_back(std::ldexp(den[0], -60 - static_cast<int>(s.below(20))));
  if (s.chance(16)) den[0] = s.raw();
  const int kind = static_cast<int>(s.below(4));
  double delta = 0;
  if (kind == 1) delta = (std::nextafter(q, HUGE_VAL) - q) / 2;
  if (kind == 2) delta = (std::nextafter(q, -HUGE_VAL) - q) / 2;
  if (kind == 3) delta = s.raw();
  std::vector<double> num;
  for (const double d : den) {
    const DoubleDouble a = detail::two_prod(q, d), b = detail::two_prod(delta, d);
    for (const double c : {a.lo, a.hi, b.lo, b.hi})
      if (c != 0) num.push_back(c);
  }
  if (s.chance(4)) num.push_back(std::ldexp(den[0] * q, -70 - static_cast<int>(s.below(40))) * (s.chance(2) ? 1 : -1));
  if (num.empty()) num.push_back(s.raw());
  const double den_sum = den.size() > 1 ? den[0] + den[1] : den[0];
  const std::uint64_t sign_word = s.chance(16) ? s.below(2) : (den_sum < 0 ? 1 : 0);
  Args a{std::bit_cast<double>(sign_word), q, std::bit_cast<double>(static_cast<std::uint64_t>(num.size()))};
  a.insert(a.end(), num.begin(), num.end());
  a.insert(a.end(), den.begin(), den.end());
  return a;
}

// ---- The BVH's ray–box test (box/ray_box.hpp, proofs/box/RayBoxTwins.v) ----------------------------------------

// A binary32 value, as the double it converts to exactly.
double binary32(double x) { return static_cast<double>(static_cast<float>(x)); }

// x moved by k ulps of a double (k may be negative).
double ulps(double x, int k) {
  for (; k > 0; --k) x = std::nextafter(x, HUGE_VAL);
  for (; k < 0; ++k) x = std::nextafter(x, -HUGE_VAL);
  return x;
}

// A BVH node's scene: the root box (binary32 values), its magnitude per axis (max |lo|, |hi|, as MeshBvh's),
// and the eight children's boxes (BvhNode::bounds[f][s], binary32 values as doubles).
struct BoxScene {
  std::array<double, 3> lo{}, hi{}, magnitude{};
  std::array<std::array<double, 8>, 6> bounds{};
};

BoxScene box_scene(Source& s) {
  BoxScene b;
  // the scale: moderate; tiny and huge binary32 (subnormal floats, near FLT_MAX); beyond binary32 (±inf bounds)
  long e = 0;
  switch (s.below(6)) {
    case 0: e = -149 + static_cast<long>(s.below(30)); break;
    case 1: e = 100 + static_cast<long>(s.below(28)); break;
    case 2: e = 120 + static_cast<long>(s.below(20)); break;
    default: e = static_cast<long>(s.below(40)) - 20;
  }
  auto unit = [&s] { return (static_cast<double>(s.word() >> 11) * 0x1p-53) * 2 - 1; };  // [-1, 1)
  for (std::size_t i = 0; i < 3; ++i) {
    const double c = std::ldexp(unit(), static_cast<int>(e)), w = std::ldexp(std::fabs(unit()), static_cast<int>(e));
    b.lo[i] = binary32(c - w), b.hi[i] = binary32(c + w);
    if (s.chance(16)) b.hi[i] = b.lo[i];  // a flat root
    b.magnitude[i] = std::max(std::fabs(b.lo[i]), std::fabs(b.hi[i]));
  }
  for (std::size_t slot = 0; slot < 8; ++slot) {
    const auto kind = s.below(12);
    for (std::size_t i = 0; i < 3; ++i) {
      double l = 0, h = 0;
      const double width = b.hi[i] - b.lo[i];
      if (kind == 0) {  // empty: lo = +inf, hi = −inf (BvhNode's empty slot)
        l = HUGE_VAL, h = -HUGE_VAL;
      } else if (kind == 1) {  // the root's box
        l = b.lo[i], h = b.hi[i];
      } else if (kind == 2) {  // raw binary32 words (NaN, ±inf, subnormal floats)
        l = binary32(static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(s.word())))),
        h = binary32(static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(s.word()))));
      } else {  // a sub-box of the root (a point 1 in 8), a face at ±inf 1 in 16
        const double u = std::fabs(unit()), v = std::fabs(unit());
        l = binary32(b.lo[i] + std::min(u, v) * width), h = binary32(b.lo[i] + std::max(u, v) * width);
        if (s.chance(8)) h = l;
        if (s.chance(16)) l = -HUGE_VAL;
        if (s.chance(16)) h = HUGE_VAL;
      }
      b.bounds[i][slot] = l, b.bounds[3 + i][slot] = h;
    }
  }
  return b;
}

// A ray for a scene: per axis an origin inside or around the root, on a face of a child (a slab plane: 0·inf
// with a zero direction), a few ulps beside one, far away (the guard), or raw; a direction component at a
// moderate exponent, aimed at a child's corner or face, ±0, about 2^-1022 or 2^1022 (the ends of case B),
// subnormal, huge, or raw (not NaN with the sign bit set: std::signbit of a NaN is outside the twin).
raykernel::Ray box_ray(Source& s, const BoxScene& b) {
  auto unit = [&s] { return (static_cast<double>(s.word() >> 11) * 0x1p-53) * 2 - 1; };
  const std::size_t slot = static_cast<std::size_t>(s.below(8));
  std::array<double, 3> o{}, d{};
  for (std::size_t i = 0; i < 3; ++i) {
    const double mid = b.lo[i] / 2 + b.hi[i] / 2, half = b.hi[i] / 2 - b.lo[i] / 2;
    const double face = b.bounds[s.chance(2) ? i : i + 3][slot];
    switch (s.below(8)) {
      case 0: o[i] = face; break;
      case 1: o[i] = ulps(face, static_cast<int>(s.below(7)) - 3); break;
      case 2: o[i] = std::ldexp(unit(), 900 + static_cast<int>(s.below(124))); break;
      case 3: o[i] = s.raw(); break;
      default: o[i] = mid + 3 * half * unit();
    }
    const double target = b.bounds[s.chance(2) ? i : i + 3][slot];
    switch (s.below(12)) {
      case 0: d[i] = s.chance(2) ? 0.0 : -0.0; break;
      case 1: d[i] = (s.chance(2) ? 1 : -1) * ulps(0x1p-1022, static_cast<int>(s.below(5)) - 2); break;
      case 2: d[i] = (s.chance(2) ? 1 : -1) * ulps(0x1p1022, static_cast<int>(s.below(5)) - 2); break;
      case 3: d[i] = std::ldexp(unit(), -1074 + static_cast<int>(s.below(60))); break;
      case 4: d[i] = std::ldexp(unit(), 1000 + static_cast<int>(s.below(24))); break;
      case 5: d[i] = s.raw(); break;
      case 6: case 7: d[i] = target - o[i]; break;  // towards a face of the child: corners, edges
      default: d[i] = std::ldexp(unit(), static_cast<int>(s.below(60)) - 30);
    }
    if (std::isnan(d[i])) d[i] = std::fabs(d[i]);
  }
  return {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
}

// "ox oy oz dx dy dz Mx My Mz" of make_slabs: a scene's ray and magnitudes; 1 in 8 a magnitude +inf (a root
// beyond binary32), 0, or raw.
Args ray_box_setup_args(Source& s) {
  const BoxScene b = box_scene(s);
  const raykernel::Ray r = box_ray(s, b);
  Args a{r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z,
         b.magnitude[0], b.magnitude[1], b.magnitude[2]};
  if (s.chance(8)) {
    const double m[3] = {HUGE_VAL, 0.0, s.raw()};
    a[6 + s.below(3)] = m[s.below(3)];
  }
  return a;
}

// "o0 o1 o2 inv0 inv1 inv2 h0 h1 h2 t_min t_max" and the 48 face words of a node: the slabs make_slabs gives a
// scene's ray (1 in 8 raw origins, inverses and faces instead); t_min 0 (±0), a positive value or a slab
// parameter of a face; t_max +inf, t_min, a slab parameter (t at a face), or a larger value.
Args ray_box_node_args(Source& s) {
  const BoxScene b = box_scene(s);
  const raykernel::Ray r = box_ray(s, b);
  raykernel::BvhRayTraversal::Slabs slabs = raykernel::mesh_detail::make_slabs(r, b.magnitude);
  if (s.chance(8))
    for (std::size_t k = 0; k < 3; ++k) {
      if (s.chance(2)) slabs.origin[k] = s.raw();
      if (s.chance(2)) slabs.inverse_direction[k] = s.raw();
      if (s.chance(2)) slabs.enters_at_hi[k] = !slabs.enters_at_hi[k];
    }
  // a slab parameter of one of the faces of a child, as the test computes it
  auto parameter = [&]() {
    const std::size_t k = static_cast<std::size_t>(s.below(3));
    const double face = b.bounds[s.chance(2) ? k : k + 3][s.below(8)];
    return (face - slabs.origin[k]) * slabs.inverse_direction[k];
  };
  double t_min = 0;
  switch (s.below(6)) {
    case 0: t_min = -0.0; break;
    case 1: t_min = std::fabs(s.raw()); break;
    case 2: t_min = std::fabs(parameter()); break;
    default: t_min = 0.0;
  }
  if (std::isnan(t_min) || std::isinf(t_min)) t_min = 0.0;
  double t_max = HUGE_VAL;
  switch (s.below(6)) {
    case 0: t_max = t_min; break;
    case 1: t_max = std::max(t_min, std::fabs(parameter())); break;
    case 2: t_max = t_min + std::ldexp(static_cast<double>(s.below(1000)), static_cast<int>(s.below(40)) - 20); break;
    default: t_max = HUGE_VAL;
  }
  if (std::isnan(t_max)) t_max = HUGE_VAL;
  Args a;
  for (std::size_t k = 0; k < 3; ++k) a.push_back(slabs.origin[k]);
  for (std::size_t k = 0; k < 3; ++k) a.push_back(slabs.inverse_direction[k]);
  for (std::size_t k = 0; k < 3; ++k) a.push_back(std::bit_cast<double>(std::uint64_t{slabs.enters_at_hi[k] ? 1u : 0u}));
  a.push_back(t_min), a.push_back(t_max);
  for (std::size_t f = 0; f < 6; ++f)
    for (std::size_t slot = 0; slot < 8; ++slot) a.push_back(b.bounds[f][slot]);
  return a;
}

using Generator = std::function<Args(Source&)>;

const std::map<std::string, Generator>& generators() {
  static const std::map<std::string, Generator> table = {
      {"ray_box_setup", ray_box_setup_args},
      {"ray_box_entry", ray_box_node_args},
      {"ray_box_node", ray_box_node_args},
      {"two_sum",
       [](Source& s) {
         if (s.chance(2)) return raw_args(s, 2);
         const Terms t = terms(s.query());
         const int i = static_cast<int>(s.below(3));
         return s.chance(2) ? Args{t.p[i], -t.o[i]} : Args{t.d[i] * t.n[i], t.diff[i] * t.n[i]};
       }},
      {"two_diff",
       [](Source& s) {
         if (s.chance(2)) return raw_args(s, 2);
         const Terms t = terms(s.query());
         const int i = static_cast<int>(s.below(3));
         return Args{t.p[i], t.o[i]};
       }},
      {"two_prod",
       [](Source& s) {
         if (s.chance(2)) return raw_args(s, 2);
         const Terms t = terms(s.query());
         const int i = static_cast<int>(s.below(3));
         return s.chance(2) ? Args{t.d[i], t.n[i]} : Args{t.diff[i], t.n[i]};
       }},
      {"dot3_rounded", [](Source& s) { return s.chance(3) ? raw_args(s, 6) : dot3_args(terms(s.query()), s.chance(2), false); }},
      {"filter_den", [](Source& s) { return s.chance(3) ? raw_args(s, 6) : dot3_args(terms(s.query()), false, false); }},
      {"filter_num", [](Source& s) { return s.chance(3) ? raw_args(s, 6) : dot3_args(terms(s.query()), true, false); }},
      {"compensated", [](Source& s) { return s.chance(3) ? raw_args(s, 9) : dot3_args(terms(s.query()), s.chance(2), true); }},
      {"refined", [](Source& s) { return s.chance(3) ? raw_args(s, 9) : dot3_args(terms(s.query()), s.chance(2), true); }},
      {"enclosure_sign",
       [](Source& s) {
         if (s.chance(4)) return raw_args(s, 3);
         const detail::Enclosure e = stage2(s.query(), s.chance(2), s.chance(2));
         if (s.chance(3)) {  // the radius moved to the decision threshold |hi + lo| = 2·radius
           const double r = std::abs(e.hi + e.lo) / 2;
           return Args{e.hi, e.lo, s.chance(2) ? r : std::nextafter(r, s.chance(2) ? 0.0 : HUGE_VAL)};
         }
         return Args{e.hi, e.lo, e.radius};
       }},
      {"filter_enclosure_den", [](Source& s) { return s.chance(3) ? raw_args(s, 6) : dot3_args(terms(s.query()), false, false); }},
      {"filter_enclosure_num", [](Source& s) { return s.chance(3) ? raw_args(s, 6) : dot3_args(terms(s.query()), true, false); }},
      {"propagated",
       [](Source& s) {
         if (s.chance(3)) return raw_args(s, 8);
         const Args a = pair_args(s);
         Args r;
         for (int k = 0; k < 2; ++k) {
           const detail::RayPlaneTerms st = detail::ray_plane_terms(query_of(a, k).ray, query_of(a, k).plane);
           const detail::RoundedEnclosure n = detail::filter_enclosure(st.num, detail::bounds::filter_num_relative);
           const detail::RoundedEnclosure d = detail::filter_enclosure(st.den, detail::bounds::filter_den_relative);
           r.insert(r.end(), {n.value, n.radius, d.value, d.radius});
         }
         return r;
       }},
      {"compare_filter",
       [](Source& s) {
         if (s.chance(4)) return raw_args(s, 8);
         const Args a = pair_args(s);
         Args r;
         for (int k = 0; k < 2; ++k) {
           const detail::RayPlaneTerms st = detail::ray_plane_terms(query_of(a, k).ray, query_of(a, k).plane);
           const detail::RoundedEnclosure n = detail::filter_enclosure(st.num, detail::bounds::filter_num_relative);
           const detail::RoundedEnclosure d = detail::filter_enclosure(st.den, detail::bounds::filter_den_relative);
           r.insert(r.end(), {n.value, n.radius, d.value, d.radius});
         }
         return r;
       }},
      {"compare_compensated",
       [](Source& s) {
         if (s.chance(4)) return raw_args(s, 12);
         const Args a = pair_args(s);
         Args r;
         for (int k = 0; k < 2; ++k) {
           const detail::RayPlaneTerms st = detail::ray_plane_terms(query_of(a, k).ray, query_of(a, k).plane);
           for (const detail::Enclosure& e : {detail::num_compensated(st), detail::den_compensated(st)})
             r.insert(r.end(), {e.hi, e.lo, e.radius});
         }
         return r;
       }},
      {"exp_sum",
       [](Source& s) {
         const std::vector<double> e = some_expansion(s, 8), f = some_expansion(s, 8);
         Args r{std::bit_cast<double>(static_cast<std::uint64_t>(e.size()))};
         r.insert(r.end(), e.begin(), e.end());
         r.insert(r.end(), f.begin(), f.end());
         return r;
       }},
      {"exp_scale",
       [](Source& s) {
         const std::vector<double> e = some_expansion(s, 8);
         Args r{s.chance(3) ? s.raw() : terms(s.query()).n[s.below(3)]};
         r.insert(r.end(), e.begin(), e.end());
         return r;
       }},
      {"exp_sign", [](Source& s) { return some_expansion(s, 12); }},
      {"build_expansions", [](Source& s) { return query_args(s.query()); }},
      {"compare_expansion", [](Source& s) { return pair_args(s); }},
      {"quotient_boundary", [](Source& s) { return boundary_args(s); }},
      // nearest_hit.cpp's compare_hit_distances: a near-tie plane pair and the signs of num and den each
      // candidate carries (the relation's, certified_signs), as doubles −1, 0, +1. Half of the pairs have
      // the second plane's point scaled by 1 ± j·2^-52 (j < 64, or < 2^20 for 1 in 4 of them), which puts
      // the order's margin across the stage-1 bounds, so that the filter decides some (and a wrong constant
      // at its call site changes some decisions); the near ties themselves go to stages 2 and 3.
      {"nearest_compare",
       [](Source& s) {
         testkit::PlanePair pp = s.plane_pair();
         if (s.chance(2)) {
           const double j = static_cast<double>(1 + s.below(s.chance(4) ? 1u << 20 : 64u));
           const double factor = 1 + (s.chance(2) ? j : -j) * 0x1p-52;
           Vec3& p = pp.planes[1].point;
           p = {p.x * factor, p.y * factor, p.z * factor};
         }
         Args a;
         auto push3 = [&](const Vec3& v) { a.push_back(v.x), a.push_back(v.y), a.push_back(v.z); };
         push3(pp.ray.origin), push3(pp.ray.direction);
         for (const Plane& p : pp.planes) push3(p.point), push3(p.normal);
         for (const Plane& p : pp.planes) {
           detail::RayPlaneCascade cascade(pp.ray, p);
           const detail::CertifiedSigns signs = detail::certified_signs(cascade);
           a.push_back(static_cast<double>(static_cast<int>(signs.num)));
           a.push_back(static_cast<double>(static_cast<int>(signs.den)));
         }
         return a;
       }},
      {"fast_answer", [](Source& s) { return query_args(s.query()); }},
      {"fast_answer_pair", [](Source& s) { return query_args(s.query()); }},
      {"fast_relation", [](Source& s) { return query_args(s.query()); }},
      {"fast_relation_pair", [](Source& s) { return query_args(s.query()); }},
      // the cascade's control flow (PlaneCascadeTwins.v): hard queries (their degenerate kinds reach stage 3 and the
      // exact stage), 1 in 8 with a special value in one component (query()), 1 in 16 wholly raw, 1 in 4 in the
      // second level's zone (refined_zone_query), 1 in 32 with an exact stage-3 expansion whose checked sign is
      // uncertain, num's or den's, and num left open by stage 2 (stage3_tie_query)
      {"cascade_intersect",
       [](Source& s) {
         if (s.chance(32)) return query_args(s.stage3_tie_query());
         return s.chance(16) ? raw_args(s, 12) : query_args(s.chance(4) ? s.refined_zone_query() : s.query());
       }},
      {"cascade_relation",
       [](Source& s) {
         if (s.chance(32)) return query_args(s.stage3_tie_query());
         return s.chance(16) ? raw_args(s, 12) : query_args(s.chance(4) ? s.refined_zone_query() : s.query());
       }},
      {"compensated_exact", [](Source& s) { return s.chance(3) ? raw_args(s, 6) : dot3_args(terms(s.query()), false, false); }},
      // num's and den's stage-2 enclosures of one query (the operands round_quotient gets), sometimes with a
      // raw value in one field.
      {"round_quotient",
       [](Source& s) {
         if (s.chance(8)) return raw_args(s, 6);
         const testkit::Query q = s.query();
         const detail::Enclosure n = stage2(q, true, false), d = stage2(q, false, false);
         Args a{n.hi, n.lo, n.radius, d.hi, d.lo, d.radius};
         if (s.chance(6)) a[s.below(6)] = s.raw();
         return a;
       }},
      // a quotient's bits: raw, or a quotient of two query values.
      {"half_gap",
       [](Source& s) {
         if (s.chance(2)) return raw_args(s, 1);
         const Terms t = terms(s.query());
         return Args{(t.diff[0] * t.n[0]) / (t.d[0] * t.n[0])};
       }},
      // ray–triangle stages 1 and 2 (proofs/triangle/TriangleTwins.v)
      {"tri_filter", [](Source& s) { return s.triangle_query(); }},
      {"tri_relation_lanes", [](Source& s) { return s.triangle_query(); }},
      {"tri_compensated", [](Source& s) { return s.triangle_query(); }},
      {"tri_compensated_lanes", [](Source& s) { return s.triangle_query(); }},
      {"tri_fast_relation", [](Source& s) { return s.triangle_query(); }},
      // the leaves' screen: a query's ray and four triangles, in a random order: the query's own, its vertices
      // rotated, its orientation flipped, and another query's (1 in 8 of all 42 words with one raw word)
      {"tri_leaf_screen",
       [](Source& s) {
         const Args q = s.triangle_query(), other = s.triangle_query();
         const double* a = &q[6];
         const double* b = &q[9];
         const double* c = &q[12];
         const double* triangles[4][3] = {{a, b, c}, {b, c, a}, {a, c, b}, {&other[6], &other[9], &other[12]}};
         for (std::size_t k = 3; k > 0; --k) std::swap(triangles[k], triangles[s.below(k + 1)]);
         Args x(q.begin(), q.begin() + 6);
         for (const auto& t : triangles)
           for (const double* v : t) x.insert(x.end(), v, v + 3);
         if (s.chance(8)) x[s.below(42)] = s.raw();
         return x;
       }},
      // stage 3 (proofs/triangle/TriangleStage3Twins.v): the determinant's index 0..4 as an integer word, then the query
      {"tri_expansion", [](Source& s) { return word_then_triangle_query(s, s.below(5)); }},
      // fast_triangle_intersection (proofs/triangle/TriangleIntersectTwins.v): the options asked, t + 2 · barycentric
      // (0..3) as an integer word, then the query
      // (1 in 4: an origin just off the triangle's plane above an inside point, the barycentrics asked, so that
      // num's filter is uncertain and its stage 2 certain: the stage label depends on num's filter term)
      {"tri_fast_intersect",
       [](Source& s) {
         if (s.chance(4)) {
           const std::uint64_t options = 2 + s.below(2);
           return word_then(options, s.near_plane_triangle_query());
         }
         return word_then_triangle_query(s, s.below(4));
       }},
      // the full cascade's control flow (proofs/triangle/TriangleCascadeFlowTwins.v): the options asked and the rule
      // (t + 2 · barycentric + 4 · closed; for the relation 1 · closed) as an integer word, then a hard query
      // (ties through vertices and edges, where the owned rule's tie-break decides; degenerate, parallel,
      // coplanar; raw patterns)
      {"tri_cascade_intersect", [](Source& s) { return word_then_triangle_query(s, s.below(8)); }},
      {"tri_cascade_relation", [](Source& s) { return word_then_triangle_query(s, s.below(2)); }},
      // the orientation filters (proofs/orient/OrientTwins.v): orient2d on three of the four points in the plane
      // of the axes of a ray's axis k (0..2, an integer word), as inside() calls it: (a, b, o), (b, c, o),
      // (c, a, o) or (b, c, a); orient3d on "o a b c"
      {"orient2d",
       [](Source& s) {
         const std::vector<double> x = s.orientation_points();
         static constexpr int order[4][3] = {{1, 2, 0}, {2, 3, 0}, {3, 1, 0}, {2, 3, 1}};
         const int* pick = order[s.below(4)];
         std::vector<double> points;
         for (int m = 0; m < 3; ++m)
           for (int i = 0; i < 3; ++i) points.push_back(x[static_cast<std::size_t>(3 * pick[m] + i)]);
         return word_then(s.below(3), points);
       }},
      {"orient3d", [](Source& s) { return s.orientation_points(); }},
      // the sphere's expansion stage (proofs/sphere/SphereStages.v): a hard sphere query; and the side of a root
      // at a boundary beside it
      {"sphere_expansions", [](Source& s) { return s.sphere_query(); }},
      {"sphere_abc_expansions", [](Source& s) { return s.sphere_query(); }},
      {"sphere_root_side", [](Source& s) { return s.sphere_root_side_args(); }},
      // spawn's two enclosures (proofs/spawn/SpawnTwins.v): midpoint_offset's "x y o" and affine_enclosure's
      // "o D d N" (above)
      {"midpoint_offset", [](Source& s) { return midpoint_offset_args(s); }},
      {"affine_enclosure", [](Source& s) { return affine_enclosure_args(s); }},
      // the escalation policy (core/escalation.hpp, proofs/core/Escalation.v): a start stage (the filter 1 in 2,
      // else any), then 0..6 steps (stage, sign), each a stage code 0..3 (1 in 2 lists nondecreasing, as the
      // predicates order them) and a sign code −1, 0, +1 or 2 (uncertain: 1 in 2, so that escalations run
      // long and end uncertain), the codes as integer words (−1 in two's complement)
      {"escalate",
       [](Source& s) {
         const std::uint64_t start = s.chance(2) ? 0 : s.below(4);
         const std::size_t m = s.below(7);
         std::vector<std::uint64_t> stages(m);
         for (std::uint64_t& stage : stages) stage = s.below(4);
         if (s.chance(2)) std::sort(stages.begin(), stages.end());
         Args a{std::bit_cast<double>(start)};
         for (const std::uint64_t stage : stages) {
           const std::int64_t sign = s.chance(2) ? 2 : static_cast<std::int64_t>(s.below(3)) - 1;
           a.push_back(std::bit_cast<double>(stage));
           a.push_back(std::bit_cast<double>(static_cast<std::uint64_t>(sign)));
         }
         return a;
       }},
      {"tail_enclosure",
       [](Source& s) {
         if (s.chance(3)) return raw_args(s, 1 + static_cast<int>(s.below(32)));
         std::vector<double> c = expansion_components(s.query(), s.chance(2));
         if (c.size() > 32) c.resize(32);
         return c;
       }},
  };
  return table;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: raykernel_twin_inputs SEED COUNT OUT_FILE [ROUTINE...]\n";
    return 2;
  }
  const std::uint64_t seed = std::stoull(argv[1]);
  const long count = std::stol(argv[2]);
  std::vector<std::string> routines;
  for (int i = 4; i < argc; ++i) routines.emplace_back(argv[i]);
  if (routines.empty())
    for (const auto& [name, _] : generators()) routines.push_back(name);
  std::ofstream out(argv[3]);
  if (!out) {
    std::cerr << "cannot write " << argv[3] << '\n';
    return 1;
  }
  Source source(seed);
  for (const std::string& name : routines) {
    const auto g = generators().find(name);
    if (g == generators().end()) {
      std::cerr << "unknown routine " << name << '\n';
      return 2;
    }
    for (long k = 0; k < count; ++k) {
      const Args args = g->second(source);
      out << name;
      for (double x : args) out << ' ' << std::bit_cast<std::uint64_t>(x);
      out << '\n';
    }
  }
  out.close();
  if (!out) {
    std::cerr << "write failed: " << argv[3] << '\n';
    return 1;
  }
  std::cout << "seed " << seed << ": " << count << " inputs for each of " << routines.size() << " routines\n";
  return 0;
}
