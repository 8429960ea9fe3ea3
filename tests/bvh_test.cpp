// The BVH (kernel/include/raykernel/bvh.hpp) against exact rational arithmetic.
//
// - The box test alone (RayBox.*): whenever the exact ray meets a box at some t in [t0, t1] — decided in GMP
//   rationals from the doubles — the certified test must accept it with an entry bound ≤ the exact entry t;
//   on hand-picked boxes (faces, edges and corners touched exactly, zero and −0 direction components, tiny
//   and huge directions, coordinates near the overflow threshold, subnormals) and on generated ones.
// - The whole traversal (Bvh.*): for generated rays over the closed test meshes of the testkit and over
//   random triangle soups — rays aimed exactly at vertices, at edge points (testkit::edge_point), at points
//   inside faces and at corners and faces of the hierarchy's boxes, with zero direction components, and
//   random rays — every triangle the exact ray meets under the closed rule (docs/contract.md §6: den ≠ 0,
//   no π of the sign opposite to den's, t = num/den ≥ 0) at t ≤ the bound given to next() lies in a leaf the
//   traversal returns. The signs of den, num and the π are 3×3 determinants (orient3d-like), decided by a
//   floating-point filter with a 32-fold margin over its error bound, and in GMP rationals when the filter
//   is unsure; t ≤ bound is decided in rationals.
// The long run (ctest label `long`, `bvh_traversal_300k`) checks 3·10^5 generated rays; RapidCheck prints its
// seed, RC_PARAMS="seed=N" reproduces a run.
#include <raykernel/bvh.hpp>
#include <raykernel/testkit/meshes.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

namespace raykernel {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

mpq_class q(double x) { return mpq_class(x); }  // exact: the double's bits

// ---- Exact oracles ---------------------------------------------------------------------------------------

// The smallest t in [t0, t1] (t1 = +inf allowed) at which o + t·d is in the closed box, exactly, or nothing.
std::optional<mpq_class> exact_box_entry(const Ray& r, const Box3& b, double t0, double t1) {
  mpq_class lo_t = q(t0);
  std::optional<mpq_class> hi_t;
  if (t1 != inf) hi_t = q(t1);
  const double o[3] = {r.origin.x, r.origin.y, r.origin.z}, d[3] = {r.direction.x, r.direction.y, r.direction.z};
  const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (q(o[i]) < q(lo[i]) || q(o[i]) > q(hi[i])) return std::nullopt;
      continue;
    }
    mpq_class a = (q(lo[i]) - q(o[i])) / q(d[i]), c = (q(hi[i]) - q(o[i])) / q(d[i]);
    if (a > c) std::swap(a, c);
    if (a > lo_t) lo_t = a;
    if (!hi_t || c < *hi_t) hi_t = c;
  }
  if (hi_t && lo_t > *hi_t) return std::nullopt;
  return lo_t;
}

// det(a, b, c) = a·(b × c) for rows given as differences of doubles, exactly.
struct Diff {
  double p, o;  // the component p − o (o = 0 for a plain value)
};
// The exact sign in 128-bit integers when every entry p − o is exact in binary64 and all nine are integer
// multiples of a common power of two below 2^40 in magnitude (then |det| < 6·2^120 < 2^127); else nothing.
std::optional<int> small_integer_det_sign(const std::array<std::array<Diff, 3>, 3>& rows) {
  double v[9];
  int min_exp = std::numeric_limits<int>::max(), max_exp = std::numeric_limits<int>::min();
  for (int k = 0; k < 9; ++k) {
    const Diff& e = rows[static_cast<std::size_t>(k / 3)][static_cast<std::size_t>(k % 3)];
    const double s = e.p - e.o, bb = e.p - s;  // TwoDiff: s is exact iff the error term is 0
    if ((e.p - (s + bb)) + (bb - e.o) != 0 || !std::isfinite(s)) return std::nullopt;
    v[k] = s;
    if (s == 0) continue;
    int ex = 0;
    const double m = std::frexp(s, &ex);
    auto mant = static_cast<std::int64_t>(std::ldexp(m, 53));
    int low = ex - 53;
    while ((mant & 1) == 0) mant >>= 1, ++low;  // s = mant · 2^low with mant odd
    min_exp = std::min(min_exp, low);
    max_exp = std::max(max_exp, ex);
  }
  if (min_exp == std::numeric_limits<int>::max()) return 0;
  if (max_exp - min_exp > 40) return std::nullopt;
  __int128 m[3][3];
  for (int k = 0; k < 9; ++k) m[k / 3][k % 3] = static_cast<__int128>(std::ldexp(v[k], -min_exp));  // exact integers
  const __int128 det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return det > 0 ? 1 : det < 0 ? -1 : 0;
}

int exact_det_sign(const std::array<std::array<Diff, 3>, 3>& rows) {
  if (const auto s = small_integer_det_sign(rows)) return *s;
  mpq_class m[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = q(rows[i][j].p) - q(rows[i][j].o);
  const mpq_class det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return sgn(det);
}

// The same sign, from doubles when a generous filter decides. The computed determinant of rounded differences
// differs from the exact one by at most about 7u times the permanent Σ|a_i||b_j||c_k| (Shewchuk 1997, the
// orient3d bound A = (7 + 56u)u with the input differences rounded); deciding only when |det| exceeds 2^-45
// times the computed permanent leaves a factor 32 over that, and the range checks keep every product and
// sum away from underflow and overflow. Otherwise: rationals.
struct FilteredDet {
  double value = 0, error = 0;  // |exact − value| ≤ error, when tame
  bool tame = false;
  int sign = 0;  // the exact sign (filtered or exact)
};
FilteredDet det_sign_filtered(const std::array<std::array<Diff, 3>, 3>& rows) {
  FilteredDet f;
  double m[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = rows[i][j].p - rows[i][j].o;
  const double c0 = m[1][1] * m[2][2] - m[1][2] * m[2][1], c1 = m[1][0] * m[2][2] - m[1][2] * m[2][0],
               c2 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c0 - m[0][1] * c1 + m[0][2] * c2;
  const double perm = std::fabs(m[0][0]) * (std::fabs(m[1][1] * m[2][2]) + std::fabs(m[1][2] * m[2][1])) +
                      std::fabs(m[0][1]) * (std::fabs(m[1][0] * m[2][2]) + std::fabs(m[1][2] * m[2][0])) +
                      std::fabs(m[0][2]) * (std::fabs(m[1][0] * m[2][1]) + std::fabs(m[1][1] * m[2][0]));
  if (perm > 0x1p-800 && perm < 0x1p800) {
    bool tame = true;
    for (auto& row : m)
      for (double v : row) tame = tame && (v == 0 || (std::fabs(v) > 0x1p-300 && std::fabs(v) < 0x1p300));
    f.tame = tame;
    f.value = det;
    f.error = 0x1p-45 * perm;
    if (tame && std::fabs(det) > f.error) {
      f.sign = det > 0 ? 1 : -1;
      return f;
    }
  }
  f.sign = exact_det_sign(rows);
  return f;
}
int det_sign(const std::array<std::array<Diff, 3>, 3>& rows) { return det_sign_filtered(rows).sign; }

std::array<Diff, 3> diff(const Vec3& p, const Vec3& o) { return {Diff{p.x, o.x}, Diff{p.y, o.y}, Diff{p.z, o.z}}; }
std::array<Diff, 3> plain(const Vec3& v) { return {Diff{v.x, 0}, Diff{v.y, 0}, Diff{v.z, 0}}; }

// Whether the exact ray meets the triangle under the closed rule at some t ≤ bound (bound ≥ 0 or +inf).
bool closed_rule_hit(const Ray& r, const Triangle& t, double bound) {
  const Vec3 &o = r.origin, &d = r.direction;
  const int den = det_sign({diff(t.b, t.a), diff(t.c, t.a), plain(d)});  // d·((b − a) × (c − a))
  if (den == 0) return false;                                            // degenerate, parallel or coplanar
  const int pa = det_sign({diff(t.b, o), diff(t.c, o), plain(d)});       // π(b, c) = d·((b − o) × (c − o))
  const int pb = det_sign({diff(t.c, o), diff(t.a, o), plain(d)});
  const int pc = det_sign({diff(t.a, o), diff(t.b, o), plain(d)});
  if (pa == -den || pb == -den || pc == -den) return false;              // outside
  const FilteredDet num_f = det_sign_filtered({diff(t.b, t.a), diff(t.c, t.a), diff(t.a, o)});  // (a − o)·N
  if (num_f.sign == -den) return false;                                  // t < 0: behind
  if (bound == inf) return true;
  // t = num/den > bound for sure when |num| − e_num > bound·(|den| + e_den) with room for the rounding of
  // these few operations (relative 2^-50 each, against a margin of 2^-40).
  const FilteredDet den_f = det_sign_filtered({diff(t.b, t.a), diff(t.c, t.a), plain(d)});
  if (num_f.tame && den_f.tame && std::fabs(num_f.value) - num_f.error > bound * (std::fabs(den_f.value) + den_f.error) * (1 + 0x1p-40) &&
      bound * (std::fabs(den_f.value) + den_f.error) < 0x1p900)
    return false;
  // t = num/den ≤ bound, exactly
  auto m = [](const Vec3& p, const Vec3& s) { return std::array<mpq_class, 3>{q(p.x) - q(s.x), q(p.y) - q(s.y), q(p.z) - q(s.z)}; };
  const auto e1 = m(t.b, t.a), e2 = m(t.c, t.a), ao = m(t.a, o);
  const std::array<mpq_class, 3> n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const mpq_class num_q = ao[0] * n[0] + ao[1] * n[1] + ao[2] * n[2];
  const mpq_class den_q = q(d.x) * n[0] + q(d.y) * n[1] + q(d.z) * n[2];
  return num_q / den_q <= q(bound);
}

// ---- The box test --------------------------------------------------------------------------------------

// The largest binary32 ≤ x and the smallest ≥ x, by stepping from a conversion (the test's own rounding; the
// BVH's must give the same bits).
float float_down(double x) {
  float f = static_cast<float>(x);
  while (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float float_up(double x) {
  float f = static_cast<float>(x);
  while (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}
// The box rounded outward to binary32 (what a BvhNode stores), as doubles.
Box3 outward(const Box3& b) {
  return {{float_down(b.lo.x), float_down(b.lo.y), float_down(b.lo.z)}, {float_up(b.hi.x), float_up(b.hi.y), float_up(b.hi.z)}};
}

// A node whose child `slot` is `b` and whose other slots in use hold `other`, both rounded outward (empty
// slots: the empty box, first = count = 0).
BvhNode node_with(const Box3& b, int slot, int children, const Box3& other) {
  BvhNode n{};
  for (int s = 0; s < BvhNode::width; ++s) {
    const Box3 x = s == slot ? outward(b) : s < children ? outward(other) : Box3{{inf, inf, inf}, {-inf, -inf, -inf}};
    const double f[6] = {x.lo.x, x.lo.y, x.lo.z, x.hi.x, x.hi.y, x.hi.z};
    for (int k = 0; k < 6; ++k) n.bounds[static_cast<std::size_t>(k)][static_cast<std::size_t>(s)] = static_cast<float>(f[k]);
    n.first[static_cast<std::size_t>(s)] = 0;
    n.count[static_cast<std::size_t>(s)] = s < children ? 1 : 0;
  }
  return n;
}

std::array<double, 3> magnitude_max(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {std::max(a[0], b[0]), std::max(a[1], b[1]), std::max(a[2], b[2])};
}
std::array<double, 3> magnitude_of(const Box3& b);

// Checks the certified test against the exact entry; returns whether the exact ray meets the box. The
// traversal's eight-lane form, with the box rounded outward to binary32 in a random slot of a node, must give
// the scalar test's answer and entry bound on the rounded box bit for bit (each lane performs the scalar
// operations), and — the rounded box containing the exact one — never reject a box the exact ray meets.
bool check_box(const Ray& r, const Box3& b, double t0, double t1, const std::array<double, 3>& magnitude) {
  const auto slabs = ray_box_slabs(r, magnitude);
  const std::optional<double> got = ray_box_entry(slabs, b, t0, t1);
  const std::optional<mpq_class> exact = exact_box_entry(r, b, t0, t1);
  if (exact) {
    RC_ASSERT(got.has_value());
    RC_ASSERT(q(*got) <= *exact);
  }
  const int children = *rc::gen::inRange(1, BvhNode::width + 1);
  const int slot = *rc::gen::inRange(0, children);
  const Box3 other = *rc::gen::element(b, Box3{{-1, -1, -1}, {1, 1, 1}}, Box3{{inf, inf, inf}, {-inf, -inf, -inf}});
  const BvhNode node = node_with(b, slot, children, other);
  const Box3 stored = node.box(slot);
  // The guard's magnitude must bound the stored boxes (MeshBvh's bounds its outward root box).
  const auto node_slabs =
      ray_box_slabs(r, magnitude_max(magnitude, magnitude_max(magnitude_of(stored), magnitude_of(outward(other)))));
  const std::optional<double> scalar = ray_box_entry(node_slabs, stored, t0, t1);
  std::array<double, BvhNode::width> entries{};
  const unsigned met = ray_box_entries(node_slabs, node, t0, t1, entries);
  RC_ASSERT((met >> children) == 0u);
  RC_ASSERT(((met >> slot) & 1u) == static_cast<unsigned>(scalar.has_value()));
  if (scalar) RC_ASSERT(std::bit_cast<std::uint64_t>(entries[static_cast<std::size_t>(slot)]) == std::bit_cast<std::uint64_t>(*scalar));
  if (exact) {
    RC_ASSERT(scalar.has_value());
    RC_ASSERT(q(*scalar) <= *exact);
  }
  return exact.has_value();
}

std::array<double, 3> magnitude_of(const Box3& b) {
  return {std::max(std::fabs(b.lo.x), std::fabs(b.hi.x)), std::max(std::fabs(b.lo.y), std::fabs(b.hi.y)),
          std::max(std::fabs(b.lo.z), std::fabs(b.hi.z))};
}

TEST(RayBox, HandPickedBoundaryCases) {
  const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
  struct Case {
    const char* what;
    Ray ray;
    Box3 box;
    double t0, t1;
    bool meets;  // derived by hand
  };
  const Case cases[] = {
      // The ray (0,0,0) + t(1,1,0) touches the box [1,2]×[1,2]×[0,0] exactly at its corner (1,1,0), t = 1.
      {"corner", {{0, 0, 0}, {1, 1, 0}}, {{1, 1, 0}, {2, 2, 0}}, 0, inf, true},
      // ... and with t1 = 1 exactly: the entry t is 1, still inside [0, 1].
      {"corner at t1", {{0, 0, 0}, {1, 1, 0}}, {{1, 1, 0}, {2, 2, 0}}, 0, 1, true},
      // ... and misses it by one ulp of the box: x-slab from 1 + 2^-52.
      {"corner missed by an ulp", {{0, 0, 0}, {1, 1, 0}}, {{1 + 0x1p-52, 0, 0}, {2, 1, 0}}, 0, inf, false},
      // d = (1, 0, 0) from y = 1 exactly on the box's face y = 1: the slab y holds the whole line.
      {"zero component on the face", {{-5, 1, 0.5}, {1, 0, 0}}, {{0, 0, 0}, {1, 1, 1}}, 0, inf, true},
      {"minus zero component on the face", {{-5, 1, 0.5}, {1, -0.0, 0}}, {{0, 0, 0}, {1, 1, 1}}, 0, inf, true},
      {"zero component off the face", {{-5, 1 + 0x1p-52, 0.5}, {1, 0, 0}}, {{0, 0, 0}, {1, 1, 1}}, 0, inf, false},
      {"minus zero component, below", {{-5, -0x1p-1074, 0.5}, {1, -0.0, 0}}, {{0, 0, 0}, {1, 1, 1}}, 0, inf, false},
      // Subnormal direction along y, box a subnormal distance above: t = 1 exactly.
      {"subnormal direction", {{0, 0, 0}, {0, tiny, 0}}, {{-1, tiny, -1}, {1, 2 * tiny, 1}}, 0, inf, true},
      // d = (1, 2^-1074, 0): the y slab [2^-1074, 1] is entered at t = 1 (x = 1 is in [0, 2]).
      {"mixed exponents", {{0, 0, 0}, {1, tiny, 0}}, {{0, tiny, 0}, {2, 1, 0}}, 0, inf, true},
      // A box near the overflow threshold: the ray from −max along +x reaches x = max at t = 2·max (beyond
      // the double range): met, as t1 = +inf.
      {"beyond the double range", {{-big, 0, 0}, {1, 0, 0}}, {{big, -1, -1}, {big, 1, 1}}, 0, inf, true},
      {"huge box, huge direction", {{0, 0, 0}, {big, big, big}}, {{big / 2, big / 2, big / 2}, {big, big, big}}, 0, inf, true},
      // The box behind the origin: no t ≥ 0.
      {"behind", {{0, 0, 0}, {1, 0, 0}}, {{-2, -1, -1}, {-1, 1, 1}}, 0, inf, false},
      // The origin inside a point box.
      {"point box at the origin", {{0.1, 0.2, 0.3}, {1, 2, 3}}, {{0.1, 0.2, 0.3}, {0.1, 0.2, 0.3}}, 0, inf, true},
      // t range starting after the box: entry t = 1 < t0 = 3 ≤ exit t = 2? No: the box is left at t = 2.
      {"t0 after the box", {{0, 0, 0}, {1, 0, 0}}, {{1, -1, -1}, {2, 1, 1}}, 3, inf, false},
      {"t0 inside the box", {{0, 0, 0}, {1, 0, 0}}, {{1, -1, -1}, {2, 1, 1}}, 1.5, inf, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    EXPECT_EQ(exact_box_entry(c.ray, c.box, c.t0, c.t1).has_value(), c.meets) << "the oracle disagrees with the hand derivation";
    if (c.meets) {
      for (const auto& magnitude : {magnitude_of(c.box), std::array<double, 3>{big, big, big}}) {
        const auto got = ray_box_entry(ray_box_slabs(c.ray, magnitude), c.box, c.t0, c.t1);
        ASSERT_TRUE(got.has_value());
        EXPECT_LE(q(*got), *exact_box_entry(c.ray, c.box, c.t0, c.t1));
      }
    }
  }
}

// A double from a mix of scales: small integers, dyadic grid values, random doubles of any exponent,
// subnormals, zeros of either sign and values near the overflow threshold.
rc::Gen<double> any_double() {
  return rc::gen::oneOf(
      rc::gen::map(rc::gen::inRange(-8, 9), [](int i) { return static_cast<double>(i); }),
      rc::gen::map(rc::gen::inRange(-4096, 4097), [](int i) { return std::ldexp(static_cast<double>(i), -10); }),
      rc::gen::map(rc::gen::pair(rc::gen::inRange<std::int64_t>(-(1LL << 53), 1LL << 53), rc::gen::inRange(-1100, 971)),
                   [](std::pair<std::int64_t, int> p) { return std::ldexp(static_cast<double>(p.first), p.second); }),
      rc::gen::map(rc::gen::inRange<std::int64_t>(-(1LL << 52), 1LL << 52),
                   [](std::int64_t i) { return std::ldexp(static_cast<double>(i), -1074); }),
      rc::gen::element(0.0, -0.0, std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), 0x1p1000, -0x1p1000));
}

rc::Gen<Vec3> any_vec() {
  return rc::gen::map(rc::gen::tuple(any_double(), any_double(), any_double()),
                      [](std::tuple<double, double, double> t) { return Vec3{std::get<0>(t), std::get<1>(t), std::get<2>(t)}; });
}

// Values k·2^e (|k| < 2^20) on one grid: sums and power-of-two multiples of them are mostly exact.
Vec3 grid_vec(int e) {
  auto c = [&] { return std::ldexp(static_cast<double>(*rc::gen::inRange(-(1 << 20), 1 << 20)), e); };
  return {*rc::gen::element(0.0, c()), c(), c()};
}

RC_GTEST_PROP(RayBox, NeverRejectsABoxTheExactRayMeets, ()) {
  const int kind = *rc::gen::inRange(0, 3);
  const int e = *rc::gen::inRange(-1070, 980);
  const Vec3 o = kind == 0 ? *any_vec() : grid_vec(e);
  Vec3 d = kind == 0 ? *any_vec() : grid_vec(e + *rc::gen::inRange(-20, 21));
  RC_PRE(!(d.x == 0 && d.y == 0 && d.z == 0));
  // Either an arbitrary box or one touching a point of the ray: p = o + t·d for a power of two t, when that
  // is exact, as a corner, an edge point or a face point of the box.
  Box3 box;
  const Vec3 a = *any_vec(), b = *any_vec();
  box = {{std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}, {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}};
  double t_hit = 0;
  if (kind > 0) {
    t_hit = std::ldexp(1.0, *rc::gen::inRange(-20, 21));
    const Vec3 p{o.x + t_hit * d.x, o.y + t_hit * d.y, o.z + t_hit * d.z};
    RC_PRE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    const bool exact = q(p.x) == q(o.x) + q(t_hit) * q(d.x) && q(p.y) == q(o.y) + q(t_hit) * q(d.y) &&
                       q(p.z) == q(o.z) + q(t_hit) * q(d.z);
    RC_PRE(exact && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    // extend from p by nonnegative amounts on chosen sides (0 keeps a face, edge or corner through p)
    auto side = [&](double c, bool up) {
      const double e = std::fabs(*any_double());
      const double v = up ? c + e : c - e;
      return std::isfinite(v) ? v : c;
    };
    const int mask = *rc::gen::inRange(0, 64);
    box.lo = {(mask & 1) ? side(p.x, false) : p.x, (mask & 2) ? side(p.y, false) : p.y, (mask & 4) ? side(p.z, false) : p.z};
    box.hi = {(mask & 8) ? side(p.x, true) : p.x, (mask & 16) ? side(p.y, true) : p.y, (mask & 32) ? side(p.z, true) : p.z};
  }
  RC_PRE(std::isfinite(o.x) && std::isfinite(box.lo.x) && std::isfinite(box.hi.z));
  const double t0 = *rc::gen::element(0.0, 0.0, t_hit, std::fabs(*any_double()));
  const double t1 = std::max(t0, *rc::gen::element(inf, inf, t_hit, std::fabs(*any_double())));
  const bool met = check_box({o, d}, box, t0, t1, magnitude_of(box));
  RC_CLASSIFY(met, "exact ray meets the box");
  RC_CLASSIFY(kind > 0, "box touches a point of the ray");
}

// ---- The traversal -------------------------------------------------------------------------------------

struct TestMesh {
  const char* name;
  Mesh mesh;
  MeshBvh bvh;
};

const std::vector<TestMesh>& test_meshes() {
  static const std::vector<TestMesh> meshes = [] {
    std::vector<TestMesh> v;
    auto add = [&](const char* name, Mesh m, BvhBuildOptions o = {}) {
      MeshBvh bvh(m, o);
      v.push_back({name, std::move(m), std::move(bvh)});
    };
    add("octahedron", testkit::make_octahedron());
    add("cube-3", testkit::make_subdivided_cube(3), {.max_leaf_size = 1, .max_leaf_size_hard = 1, .bins = 8});
    add("cube-4", testkit::make_subdivided_cube(4, 0.5));
    add("icosphere-2", testkit::make_icosphere(2), {.max_leaf_size = 2, .max_leaf_size_hard = 4, .bins = 16});
    add("terrain-4", testkit::make_terrain(4));
    return v;
  }();
  return meshes;
}

// A soup of triangles with coordinates of one random scale (exponent e), some sharing vertices, some
// degenerate.
Mesh random_soup() {
  const int e = *rc::gen::element(0, 0, -20, 40, -1000, 1000, -1060);
  const int count = *rc::gen::inRange(1, 25);
  Mesh m;
  for (int k = 0; k < 3 * count; ++k) {
    const int reuse = *rc::gen::inRange(0, 5);
    if (reuse == 0 && !m.vertices.empty()) {
      m.vertices.push_back(m.vertices[static_cast<std::size_t>(*rc::gen::inRange<std::size_t>(0, m.vertices.size()))]);
    } else {
      auto c = [&] {
        return std::ldexp(static_cast<double>(*rc::gen::inRange<std::int64_t>(-(1LL << 20), 1LL << 20)) +
                              (reuse == 1 ? static_cast<double>(*rc::gen::inRange(0, 1 << 20)) * 0x1p-30 : 0.0),
                          e - 20);
      };
      m.vertices.push_back({c(), c(), c()});
    }
    if (k % 3 == 2) {
      const auto i = static_cast<std::uint32_t>(k);
      m.triangles.push_back({i - 2, i - 1, i});
    }
  }
  return m;
}

// A ray aimed exactly at `target` from an origin on a coarse grid around it (scale s), or at least near it
// when the difference is not exact; with some direction components zeroed by sharing the target's.
Ray aimed_ray(const Vec3& target, double s) {
  auto coord = [&](double t) {
    const int share = *rc::gen::inRange(0, 6);
    if (share == 0) return t;
    return std::ldexp(static_cast<double>(*rc::gen::inRange(-64, 65)), -4) * s;
  };
  const Vec3 o{coord(target.x), coord(target.y), coord(target.z)};
  Vec3 d{target.x - o.x, target.y - o.y, target.z - o.z};
  if (d.x == 0 && d.y == 0 && d.z == 0) d = {s, 0, 0};
  return {o, d};
}

void check_traversal(const Mesh& mesh, const MeshBvh& bvh, const Ray& ray, double bound, std::uint64_t& exact_hits) {  // exact_hits: visited triangles
  for (double c : {ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y, ray.direction.z})
    RC_PRE(std::isfinite(c));
  std::vector<char> visited(mesh.triangles.size(), 0);
  BvhRayTraversal walk(bvh, ray);
  while (const auto leaf = walk.next(bound)) {
    RC_ASSERT(leaf->entry_lower_bound <= bound);
    for (std::uint32_t k : leaf->triangles) visited[k] = 1;
  }
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    if (visited[k]) continue;
    const bool hit = closed_rule_hit(ray, mesh.triangle(k), bound);
    if (hit) {
      RC_FAIL("triangle " + std::to_string(k) + " is hit by the exact ray (closed rule, t <= bound) but its leaf was not visited");
    }
  }
  exact_hits += std::count(visited.begin(), visited.end(), 1);
}

RC_GTEST_PROP(Bvh, VisitsEveryTriangleTheExactRayMeets, ()) {
  static std::uint64_t exact_hits = 0;
  const bool soup = *rc::gen::inRange(0, 4) == 0;
  Mesh soup_mesh;
  std::optional<MeshBvh> soup_bvh;
  const Mesh* mesh;
  const MeshBvh* bvh;
  if (soup) {
    soup_mesh = random_soup();
    soup_bvh.emplace(soup_mesh, BvhBuildOptions{.max_leaf_size = 1, .max_leaf_size_hard = 2, .bins = 4});
    mesh = &soup_mesh;
    bvh = &*soup_bvh;
  } else {
    const TestMesh& t = test_meshes()[*rc::gen::inRange<std::size_t>(0, test_meshes().size())];
    mesh = &t.mesh;
    bvh = &t.bvh;
  }
  const Box3& root = bvh->bounds();
  const double s = std::max({bvh->magnitude()[0], bvh->magnitude()[1], bvh->magnitude()[2], 0x1p-1000}) * 2;
  const auto pick_triangle = [&] { return mesh->triangle(*rc::gen::inRange<std::size_t>(0, mesh->triangles.size())); };
  Ray ray;
  const int kind = *rc::gen::inRange(0, 6);
  switch (kind) {
    case 0: {  // a vertex
      const Triangle t = pick_triangle();
      ray = aimed_ray(*rc::gen::element(t.a, t.b, t.c), s);
      break;
    }
    case 1: {  // an edge point
      const Triangle t = pick_triangle();
      const int bits = *rc::gen::inRange(1, 12);
      const auto p = testkit::edge_point(t.a, t.b, *rc::gen::inRange<std::int64_t>(0, (1LL << bits) + 1), bits);
      ray = aimed_ray(p ? *p : t.a, s);
      break;
    }
    case 2: {  // a point inside a face: an edge point of (edge point, third vertex)
      const Triangle t = pick_triangle();
      const auto p = testkit::edge_point(t.a, t.b, *rc::gen::inRange<std::int64_t>(1, 16), 4);
      const auto r = p ? testkit::edge_point(*p, t.c, *rc::gen::inRange<std::int64_t>(1, 16), 4) : std::nullopt;
      ray = aimed_ray(r ? *r : t.c, s);
      break;
    }
    case 3: {  // a corner or a face point of a box of the hierarchy
      const BvhNode& n = bvh->nodes()[*rc::gen::inRange<std::size_t>(0, bvh->nodes().size())];
      const Box3 b = n.box(*rc::gen::inRange(0, n.children()));
      const Vec3 corner{*rc::gen::element(b.lo.x, b.hi.x), *rc::gen::element(b.lo.y, b.hi.y),
                        *rc::gen::element(b.lo.z, b.hi.z)};
      const auto p = testkit::edge_point(corner, b.hi, *rc::gen::inRange<std::int64_t>(0, 3), 1);
      ray = aimed_ray(p && *rc::gen::arbitrary<bool>() ? *p : corner, s);
      break;
    }
    case 4: {  // through the root box, random
      const Vec3 target{*rc::gen::element(root.lo.x, root.hi.x, 0.0), *rc::gen::element(root.lo.y, root.hi.y, 0.0),
                        *rc::gen::element(root.lo.z, root.hi.z, 0.0)};
      ray = aimed_ray(target, s);
      break;
    }
    default:  // anything
      ray = {*any_vec(), *any_vec()};
      RC_PRE(!(ray.direction.x == 0 && ray.direction.y == 0 && ray.direction.z == 0));
      RC_PRE(std::isfinite(ray.origin.x + ray.origin.y + ray.origin.z));
  }
  // The bound: +inf, 1 (the aimed point is at t = 1 when the aim was exact), or a random value.
  const double bound = *rc::gen::element(inf, inf, 1.0, std::ldexp(1.0, *rc::gen::inRange(-3, 4)));
  check_traversal(*mesh, *bvh, ray, bound, exact_hits);
  RC_CLASSIFY(soup, "random soup");
  RC_TAG(kind);
}

TEST(Bvh, StructureIsExactAndComplete) {
  // Every triangle in exactly one leaf; every child's box is the exact min/max of the vertices below it rounded
  // outward to binary32; the root's children cover bounds(); slots beyond children() hold the empty box;
  // depth() is the longest path; magnitude() is the outward root box's.
  for (const TestMesh& t : test_meshes()) {
    SCOPED_TRACE(t.name);
    const auto nodes = t.bvh.nodes();
    std::vector<int> seen(t.mesh.triangles.size(), 0);
    using Six = std::array<double, 6>;
    auto grow = [](Box3& b, const Vec3& v) {
      b.lo = {std::min(b.lo.x, v.x), std::min(b.lo.y, v.y), std::min(b.lo.z, v.z)};
      b.hi = {std::max(b.hi.x, v.x), std::max(b.hi.y, v.y), std::max(b.hi.z, v.z)};
    };
    const Box3 empty{{inf, inf, inf}, {-inf, -inf, -inf}};
    int depth = 0;
    std::function<Box3(std::uint32_t, int)> check = [&](std::uint32_t i, int level) -> Box3 {
      depth = std::max(depth, level);
      const BvhNode& n = nodes[i];
      EXPECT_GE(n.children(), 1);
      Box3 all = empty;
      for (int s = 0; s < BvhNode::width; ++s) {
        if (s >= n.children()) {
          EXPECT_EQ(std::bit_cast<Six>(n.box(s)), std::bit_cast<Six>(empty)) << "node " << i << " slot " << s;
          EXPECT_TRUE(n.empty_slot(s));
          continue;
        }
        Box3 b = empty;
        if (n.is_leaf(s)) {
          const auto slot = static_cast<std::size_t>(s);
          for (std::uint32_t j = n.first[slot]; j < n.first[slot] + n.count[slot]; ++j) {
            const std::uint32_t k = t.bvh.triangle_order()[j];
            ++seen[k];
            const Triangle tr = t.mesh.triangle(k);
            grow(b, tr.a), grow(b, tr.b), grow(b, tr.c);
          }
        } else {
          EXPECT_GT(n.first[static_cast<std::size_t>(s)], i) << "children after their parent";
          b = check(n.first[static_cast<std::size_t>(s)], level + 1);
        }
        // The stored box: the exact min/max rounded outward to binary32, bit for bit.
        EXPECT_EQ(std::bit_cast<Six>(outward(b)), std::bit_cast<Six>(n.box(s))) << "node " << i << " slot " << s;
        grow(all, b.lo), grow(all, b.hi);
      }
      return all;
    };
    const Box3 root = check(0, 1);
    EXPECT_EQ(std::bit_cast<Six>(root), std::bit_cast<Six>(t.bvh.bounds()));
    const auto m = magnitude_of(outward(root));
    using Three = std::array<std::uint64_t, 3>;
    EXPECT_EQ(std::bit_cast<Three>(m), std::bit_cast<Three>(t.bvh.magnitude()));
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
    EXPECT_EQ(t.bvh.depth(), depth);
    EXPECT_LE(t.bvh.depth(), MeshBvh::max_depth);
  }
}

TEST(Bvh, TheSameNodesOnAnyNumberOfThreads) {
  // 81,920 triangles: above the size from which the build splits its top levels and bins its largest nodes on
  // several threads. One thread and two must give the same nodes and order, byte for byte.
  const Mesh mesh = testkit::make_icosphere(6);
  const MeshBvh one(mesh, {.threads = 1});
  const MeshBvh two(mesh, {.threads = 2});
  ASSERT_EQ(one.nodes().size(), two.nodes().size());
  EXPECT_EQ(std::memcmp(one.nodes().data(), two.nodes().data(), one.nodes().size_bytes()), 0);
  ASSERT_EQ(one.triangle_order().size(), two.triangle_order().size());
  EXPECT_TRUE(std::equal(one.triangle_order().begin(), one.triangle_order().end(), two.triangle_order().begin()));
  EXPECT_EQ(one.depth(), two.depth());
  EXPECT_GT(one.nodes().size(), 1000u);
}

TEST(Bvh, RejectsInvalidInput) {
  Mesh m = testkit::make_octahedron();
  m.vertices[0].x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MeshBvh{m}, invalid_input);
  const MeshBvh bvh(testkit::make_octahedron());
  EXPECT_THROW(BvhRayTraversal(bvh, {{0, 0, 0}, {0, 0, 0}}), invalid_input);
  EXPECT_THROW(BvhRayTraversal(bvh, {{0, 0, inf}, {0, 0, 1}}), invalid_input);
  EXPECT_THROW(BvhRayTraversal(bvh, {{0, 0, 0}, {0, 0, 1}}, -1.0), invalid_input);
  const MeshBvh empty{Mesh{}};
  BvhRayTraversal walk(empty, {{0, 0, 0}, {0, 0, 1}});
  EXPECT_FALSE(walk.next().has_value());
}

TEST(Bvh, PrunesByTheBoundButKeepsTies) {
  // Octahedron of radius 1, ray from (0,0,-4) along +z: it enters the lower faces at the vertex (0,0,-1),
  // t = 3 exactly, and leaves through (0,0,1) at t = 5. With the bound 3, the four faces at (0,0,-1) (met at
  // t = 3) must be returned; with 3 − 2^-51 (below 3) none may be needed, and leaves entered after t = 3
  // must not come back.
  const Mesh m = testkit::make_octahedron();
  const MeshBvh bvh(m, {.max_leaf_size = 1, .max_leaf_size_hard = 1, .bins = 8});
  const Ray ray{{0, 0, -4}, {0, 0, 1}};
  std::vector<std::uint32_t> seen;
  BvhRayTraversal walk(bvh, ray);
  while (auto leaf = walk.next(3.0)) {
    EXPECT_LE(leaf->entry_lower_bound, 3.0);
    for (std::uint32_t k : leaf->triangles) seen.push_back(k);
  }
  for (std::uint32_t k = 0; k < 8; ++k) {
    const bool lower = m.vertices[m.triangles[k][2]].z < 0 || m.vertices[m.triangles[k][1]].z < 0 || m.vertices[m.triangles[k][0]].z < 0;
    if (lower) EXPECT_NE(std::find(seen.begin(), seen.end(), k), seen.end()) << "lower face " << k;
    else EXPECT_EQ(std::find(seen.begin(), seen.end(), k), seen.end()) << "upper face " << k << " starts at t = 4 > 3";
  }
}

}  // namespace
}  // namespace raykernel
