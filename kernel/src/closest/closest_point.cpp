// closest_point(query, mesh) (docs/contract.md §11): the BVH searched nearest box first, each candidate triangle
// measured in intervals (closest_formula.hpp over core/interval.hpp) or, when an interval sign is uncertain or the
// triangle is degenerate, in rationals; the near-tied candidates ordered exactly; the winner evaluated once in
// rationals and rounded (core/binary64_rounding.hpp, core/root_rounding.hpp). The reference closest_point_exact
// and the binary64 baseline closest_point_naive share the formula.
#include <raykernel/closest_point.hpp>

#include "closest/closest_formula.hpp"
#include "core/binary64_rounding.hpp"
#include "core/exact_value.hpp"
#include "core/fp_environment.hpp"
#include "core/interval.hpp"
#include "core/rational_from_double.hpp"
#include "core/root_rounding.hpp"
#include "core/validation.hpp"

#include <gmpxx.h>
#include <mpfr.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <string>
#include <vector>

namespace raykernel {

std::string_view to_string(ClosestFeature feature) noexcept {
  switch (feature) {
    case ClosestFeature::vertex: return "vertex";
    case ClosestFeature::edge: return "edge";
    case ClosestFeature::face: return "face";
  }
  return "?";
}

namespace {

using detail::ClosestRegion;
using detail::ClosestTerms;
using detail::Interval;
using detail::Vec3Of;
using Q = mpq_class;
using detail::exact::MpfrNumber;

constexpr double inf = std::numeric_limits<double>::infinity();

void throw_if_invalid(const Vec3& query) {
  if (const auto reason = detail::non_finite_reason("query point", query)) throw invalid_input(*reason);
}

// ---- exact arithmetic -------------------------------------------------------------------------------------------
//
// Every double is an integer times a power of two, so the query and a triangle's vertices are integers times 2^e,
// e the smallest exponent among their twelve coordinates: the formula runs on integers (GMP's mpz, no gcd), and
// the closest point is N_i·2^e / D per coordinate, its squared distance S·2^(2e) / D², S = |D·p − N|² (scaled).

using Z = mpz_class;

// The twelve coordinates as integers of one scale 2^exponent.
struct Scaled {
  Vec3Of<Z> p, a, b, c;
  long exponent = 0;
};

Scaled scale(const Vec3& query, const Triangle& tri) {
  const double values[12] = {query.x, query.y, query.z, tri.a.x, tri.a.y, tri.a.z,
                             tri.b.x, tri.b.y, tri.b.z, tri.c.x, tri.c.y, tri.c.z};
  std::uint64_t significand[12];
  long exponent[12];
  long smallest = 0;
  bool any = false;
  for (int k = 0; k < 12; ++k) {
    const auto bits = std::bit_cast<std::uint64_t>(values[k]);
    const auto biased = static_cast<long>((bits >> 52) & 0x7ff);
    significand[k] = bits & ((std::uint64_t{1} << 52) - 1);
    exponent[k] = -1074;  // subnormal or zero
    if (biased != 0) {
      significand[k] |= std::uint64_t{1} << 52;
      exponent[k] = biased - 1075;
    }
    if (significand[k] != 0 && (!any || exponent[k] < smallest)) {
      smallest = exponent[k];
      any = true;
    }
  }
  Z z[12];
  static_assert(sizeof(unsigned long) >= sizeof(std::uint64_t));
  for (int k = 0; k < 12; ++k) {
    z[k] = static_cast<unsigned long>(significand[k]);
    if (significand[k] != 0) mpz_mul_2exp(z[k].get_mpz_t(), z[k].get_mpz_t(), static_cast<mp_bitcnt_t>(exponent[k] - smallest));
    if (std::signbit(values[k])) z[k] = -z[k];
  }
  return {{z[0], z[1], z[2]}, {z[3], z[4], z[5]}, {z[6], z[7], z[8]}, {z[9], z[10], z[11]}, smallest};
}

// The exact closest point of one triangle, scaled: point_i = numerator_i·2^exponent / denominator (denominator > 0),
// squared distance = squared·2^(2·exponent) / denominator².
struct ExactMeasure {
  Vec3Of<Z> numerator;
  Z denominator;
  Z squared;
  long exponent = 0;
  ClosestFeature feature = ClosestFeature::face;
  std::uint8_t corner = 0;

  [[nodiscard]] Q squared_distance() const {  // in lowest terms
    Q d2(squared, denominator * denominator);
    if (exponent >= 0) mpq_mul_2exp(d2.get_mpq_t(), d2.get_mpq_t(), static_cast<mp_bitcnt_t>(2 * exponent));
    else mpq_div_2exp(d2.get_mpq_t(), d2.get_mpq_t(), static_cast<mp_bitcnt_t>(-2 * exponent));
    d2.canonicalize();
    return d2;
  }
};

bool is_zero(const Vec3Of<Z>& v) { return sgn(v.x) == 0 && sgn(v.y) == 0 && sgn(v.z) == 0; }
Vec3Of<Z> cross(const Vec3Of<Z>& u, const Vec3Of<Z>& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}

// The measure of the point `numerator / denominator` (scaled) from p.
ExactMeasure measured(const Scaled& s, Vec3Of<Z> numerator, Z denominator, ClosestFeature feature, std::uint8_t corner) {
  const Vec3Of<Z> r{s.p.x * denominator - numerator.x, s.p.y * denominator - numerator.y,
                    s.p.z * denominator - numerator.z};
  return {std::move(numerator), std::move(denominator), dot(r, r), s.exponent, feature, corner};
}

// A degenerate triangle (a, b, c on a line, or one point) is the union of its three segments, itself a segment:
// its closest point is the nearest of the segments' (the first of them on a tie: the same point). A vertex when
// that point is one, else inside the edge it was found on.
ExactMeasure measure_degenerate(const Scaled& s) {
  const std::array<const Vec3Of<Z>*, 3> v{&s.a, &s.b, &s.c};
  std::optional<ExactMeasure> best;
  for (std::uint8_t k = 0; k < 3; ++k) {
    const Vec3Of<Z>& s0 = *v[k];
    const Vec3Of<Z>& s1 = *v[(k + 1) % 3];
    const Vec3Of<Z> e = s1 - s0;
    const Z length2 = dot(e, e), along = dot(s.p - s0, e);  // t = along / length2, clamped to [0, 1]
    ExactMeasure m = sgn(length2) == 0 || sgn(along) <= 0 ? measured(s, s0, Z(1), ClosestFeature::vertex, k)
                     : along >= length2 ? measured(s, s1, Z(1), ClosestFeature::vertex, static_cast<std::uint8_t>((k + 1) % 3))
                                        : measured(s, {s0.x * length2 + along * e.x, s0.y * length2 + along * e.y,
                                                       s0.z * length2 + along * e.z},
                                                   length2, ClosestFeature::edge, k);
    // d² = squared / denominator²: compare across segments without division.
    if (!best || m.squared * best->denominator * best->denominator < best->squared * m.denominator * m.denominator)
      best = std::move(m);
  }
  // The vertex found along one segment may be the same point as a vertex of smaller index: name the first.
  if (best->feature == ClosestFeature::vertex)
    for (std::uint8_t k = 0; k < 3; ++k)
      if (v[k]->x == v[best->corner]->x && v[k]->y == v[best->corner]->y && v[k]->z == v[best->corner]->z) {
        best->corner = k;
        break;
      }
  return std::move(*best);
}

ExactMeasure measure_exact(const Vec3& query, const Triangle& tri) {
  const Scaled s = scale(query, tri);
  const Vec3Of<Z> ab = s.b - s.a, ac = s.c - s.a;
  if (is_zero(cross(ab, ac))) return measure_degenerate(s);
  const ClosestTerms<Z> t = detail::closest_terms<Z>(s.p, s.a, s.b, s.c, Z(0), Z(1), [](const Z& x) { return sgn(x); });
  // Where the point lies, from its barycentric coordinates (u, v, w) = (den − num_v − num_w, num_v, num_w)/den.
  const bool u0 = t.den == t.num_v + t.num_w, v0 = sgn(t.num_v) == 0, w0 = sgn(t.num_w) == 0;
  ClosestFeature feature = ClosestFeature::face;
  std::uint8_t corner = 0;
  if (v0 && w0) feature = ClosestFeature::vertex, corner = 0;
  else if (u0 && w0) feature = ClosestFeature::vertex, corner = 1;
  else if (u0 && v0) feature = ClosestFeature::vertex, corner = 2;
  else if (w0) feature = ClosestFeature::edge, corner = 0;
  else if (u0) feature = ClosestFeature::edge, corner = 1;
  else if (v0) feature = ClosestFeature::edge, corner = 2;
  return measured(s,
                  {s.a.x * t.den + t.num_v * ab.x + t.num_w * ac.x, s.a.y * t.den + t.num_v * ab.y + t.num_w * ac.y,
                   s.a.z * t.den + t.num_v * ab.z + t.num_w * ac.z},
                  t.den, feature, corner);
}


mpfr_prec_t bits_of(const Z& z) { return std::max<mpfr_prec_t>(2, static_cast<mpfr_prec_t>(mpz_sizeinbase(z.get_mpz_t(), 2))); }

// x (an MPFR value) rounded to binary64 when that is one rounding: x normal in binary64 (no subnormal, no overflow);
// else nothing.
std::optional<double> to_binary64(mpfr_ptr x) {
  if (mpfr_zero_p(x)) return 0.0;
  const mpfr_exp_t e = mpfr_get_exp(x);  // |x| in [2^(e−1), 2^e): normal for e in [−1021, 1024]
  if (e < -1021 || e > 1024) return std::nullopt;
  return mpfr_get_d(x, MPFR_RNDN);
}

// RN(n·2^e / d), d > 0: one MPFR division of exact values at 53 bits, in MPFR's wide exponent range; where the
// quotient is subnormal or overflows (a second rounding would follow), the rational's rounding to binary64.
double round_scaled_quotient(const Z& n, const Z& d, long e) {
  MpfrNumber num(bits_of(n)), den(bits_of(d)), x(53);
  mpfr_set_z(num.get(), n.get_mpz_t(), MPFR_RNDN);  // exact: precision of n
  mpfr_mul_2si(num.get(), num.get(), e, MPFR_RNDN);  // exact
  mpfr_set_z(den.get(), d.get_mpz_t(), MPFR_RNDN);
  mpfr_div(x.get(), num.get(), den.get(), MPFR_RNDN);
  if (const std::optional<double> r = to_binary64(x.get())) return *r;
  Q q(n, d);
  if (e >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  q.canonicalize();
  return detail::exact::round_rational_to_nearest_even(q);
}

// RN(√S·2^e / D): an enclosure by MPFR with directed roundings whose ends round alike (√S irrational is never a
// double nor a midpoint, so a precise enough enclosure decides); √S an integer makes it a quotient; a value
// outside binary64's normal range goes to core/root_rounding.hpp.
double round_distance(const ExactMeasure& m) {
  if (mpz_perfect_square_p(m.squared.get_mpz_t())) {
    Z root;
    mpz_sqrt(root.get_mpz_t(), m.squared.get_mpz_t());
    return round_scaled_quotient(root, m.denominator, m.exponent);
  }
  for (mpfr_prec_t precision = 96; precision <= 4096; precision *= 2) {
    MpfrNumber s(bits_of(m.squared)), den(bits_of(m.denominator)), lo(precision), hi(precision), lo53(53), hi53(53);
    mpfr_set_z(s.get(), m.squared.get_mpz_t(), MPFR_RNDN);  // exact
    mpfr_set_z(den.get(), m.denominator.get_mpz_t(), MPFR_RNDN);
    mpfr_sqrt(lo.get(), s.get(), MPFR_RNDD);
    mpfr_sqrt(hi.get(), s.get(), MPFR_RNDU);
    mpfr_div(lo.get(), lo.get(), den.get(), MPFR_RNDD);
    mpfr_div(hi.get(), hi.get(), den.get(), MPFR_RNDU);
    mpfr_mul_2si(lo.get(), lo.get(), m.exponent, MPFR_RNDD);  // exact
    mpfr_mul_2si(hi.get(), hi.get(), m.exponent, MPFR_RNDU);
    mpfr_set(lo53.get(), lo.get(), MPFR_RNDN);
    mpfr_set(hi53.get(), hi.get(), MPFR_RNDN);
    const std::optional<double> a = to_binary64(lo53.get()), b = to_binary64(hi53.get());
    if (!a || !b) break;
    if (*a == *b) return *a;
  }
  return detail::exact::round_root(Q(0), m.squared_distance(), +1, detail::exact::binary64_format, MPFR_RNDN);
}

ClosestPoint rounded(std::uint32_t triangle, const ExactMeasure& m) {
  ClosestPoint r;
  r.triangle = triangle;
  r.feature = m.feature;
  r.corner = m.corner;
  r.point = {round_scaled_quotient(m.numerator.x, m.denominator, m.exponent),
             round_scaled_quotient(m.numerator.y, m.denominator, m.exponent),
             round_scaled_quotient(m.numerator.z, m.denominator, m.exponent)};
  r.squared_distance_exact = detail::exact::to_public(m.squared_distance());
  r.squared_distance = round_scaled_quotient(m.squared, m.denominator * m.denominator, 2 * m.exponent);
  r.distance = round_distance(m);
  return r;
}

// Whether x is nearer than y, exactly: S_x·4^e_x / D_x² < S_y·4^e_y / D_y².
bool nearer(const ExactMeasure& x, const ExactMeasure& y) { return x.squared_distance() < y.squared_distance(); }

// ---- intervals --------------------------------------------------------------------------------------------------

Vec3Of<Interval> point_interval(const Vec3& v) {
  return {Interval::point(v.x), Interval::point(v.y), Interval::point(v.z)};
}

bool surely_nonzero(const Interval& x) { return x.lo > 0 || x.hi < 0; }

// A candidate's measure: an interval holding its exact squared distance, and what its closest feature is when the
// intervals decided it (vertex or edge regions give a key shared by every triangle with the same vertex or edge).
struct Candidate {
  std::uint32_t triangle;
  std::uint32_t position;  // in leaf order
  Interval squared_distance;
  ClosestRegion region;    // uncertain: measured in rationals (its measure in the search's `exact` list)
  std::int32_t exact;      // index into that list, or −1
};

// The interval measure, or nothing when a sign is uncertain or the triangle may be degenerate.
// `farther` when the distance to the triangle's plane — a lower bound of the distance to the triangle — is provably
// above `best`: the candidate cannot win, and its closest point is not computed.
struct IntervalMeasure {
  enum Kind : std::uint8_t { measured, farther, uncertain } kind;
  ClosestRegion region;
  Interval squared_distance;
};

IntervalMeasure measure_interval(const Vec3& query, const Triangle& tri, double best) {
  const Vec3Of<Interval> p = point_interval(query), a = point_interval(tri.a), b = point_interval(tri.b),
                         c = point_interval(tri.c);
  const Vec3Of<Interval> ab = b - a, ac = c - a;
  const Vec3Of<Interval> n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z, ab.x * ac.y - ab.y * ac.x};
  if (!surely_nonzero(n.x) && !surely_nonzero(n.y) && !surely_nonzero(n.z))
    return {IntervalMeasure::uncertain, ClosestRegion::uncertain, {}};
  // The squared distance to the plane, ((p − a)·n)² / |n|²: a lower bound of the distance to the triangle, and
  // the distance itself in the face region.
  const Interval n2 = detail::square(n.x) + detail::square(n.y) + detail::square(n.z);
  if (!(n2.lo > 0)) return {IntervalMeasure::uncertain, ClosestRegion::uncertain, {}};
  const Interval plane = detail::divide_nonnegative(detail::square(dot(p - a, n)), n2);
  if (plane.lo > best) return {IntervalMeasure::farther, ClosestRegion::uncertain, {}};
  const ClosestTerms<Interval> t = detail::closest_terms<Interval>(
      p, a, b, c, Interval::point(0), Interval::point(1), [](const Interval& x) { return detail::interval_sign(x); });
  const auto squared_length = [](const Vec3Of<Interval>& v) {
    return detail::square(v.x) + detail::square(v.y) + detail::square(v.z);
  };
  switch (t.region) {
    case ClosestRegion::uncertain: return {IntervalMeasure::uncertain, t.region, {}};
    case ClosestRegion::face: return {IntervalMeasure::measured, t.region, plane};
    case ClosestRegion::vertex_a: return {IntervalMeasure::measured, t.region, squared_length(p - a)};
    case ClosestRegion::vertex_b: return {IntervalMeasure::measured, t.region, squared_length(p - b)};
    case ClosestRegion::vertex_c: return {IntervalMeasure::measured, t.region, squared_length(p - c)};
    default: break;  // an edge: |den·ap − num_v·ab − num_w·ac|² / den²
  }
  const Interval den2 = detail::square(t.den);
  if (!(den2.lo > 0)) return {IntervalMeasure::uncertain, t.region, {}};
  return {IntervalMeasure::measured, t.region,
          detail::divide_nonnegative(squared_length(detail::scaled_offset(t, p, a, b, c)), den2)};
}

// A lower bound of the squared distance from p to the box lo ≤ x ≤ hi (closed): per axis the gap, rounded to nearest
// then lowered by one ulp (a lower bound of the exact gap), squared and summed the same way.
double box_lower_bound(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  // below(x) for x = RN(v), v ≥ 0 exact: the double under x, or 0 — a lower bound of v (x ≥ 0, never NaN here).
  const auto below = [](double x) {
    return x > 0 ? std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) - 1) : 0.0;
  };
  const auto gap2 = [&](double x, double l, double h) {
    const double gap = below(std::max({l - x, x - h, 0.0}));  // l − x > 0 or x − h > 0 or neither, exactly
    return below(gap * gap);
  };
  return below(below(gap2(p.x, lo.x, hi.x) + gap2(p.y, lo.y, hi.y)) + gap2(p.z, lo.z, hi.z));
}

double box_lower_bound(const Vec3& p, const BvhNode& node, int slot) {
  const Box3 b = node.box(slot);
  return box_lower_bound(p, b.lo, b.hi);
}

// The same for a triangle's box: a cheap test before the intervals.
double triangle_lower_bound(const Vec3& p, const Triangle& t) {
  return box_lower_bound(p, {std::min({t.a.x, t.b.x, t.c.x}), std::min({t.a.y, t.b.y, t.c.y}), std::min({t.a.z, t.b.z, t.c.z})},
                         {std::max({t.a.x, t.b.x, t.c.x}), std::max({t.a.y, t.b.y, t.c.y}), std::max({t.a.z, t.b.z, t.c.z})});
}

bool same_bits(const Vec3& u, const Vec3& v) {
  return std::bit_cast<std::uint64_t>(u.x) == std::bit_cast<std::uint64_t>(v.x) &&
         std::bit_cast<std::uint64_t>(u.y) == std::bit_cast<std::uint64_t>(v.y) &&
         std::bit_cast<std::uint64_t>(u.z) == std::bit_cast<std::uint64_t>(v.z);
}

// Whether two candidates' closest points are provably the same point without arithmetic: the same vertex (the
// same doubles), or the inside of the same edge (the same two vertices, either order).
bool same_feature(const Candidate& x, const Triangle& tx, const Candidate& y, const Triangle& ty) {
  const auto vertex = [](const Triangle& t, ClosestRegion r) -> const Vec3& {
    return r == ClosestRegion::vertex_a ? t.a : r == ClosestRegion::vertex_b ? t.b : t.c;
  };
  const auto edge = [](const Triangle& t, ClosestRegion r) -> std::pair<const Vec3&, const Vec3&> {
    if (r == ClosestRegion::edge_ab) return {t.a, t.b};
    if (r == ClosestRegion::edge_bc) return {t.b, t.c};
    return {t.c, t.a};
  };
  const auto is_vertex = [](ClosestRegion r) {
    return r == ClosestRegion::vertex_a || r == ClosestRegion::vertex_b || r == ClosestRegion::vertex_c;
  };
  const auto is_edge = [](ClosestRegion r) {
    return r == ClosestRegion::edge_ab || r == ClosestRegion::edge_bc || r == ClosestRegion::edge_ca;
  };
  if (is_vertex(x.region) && is_vertex(y.region)) return same_bits(vertex(tx, x.region), vertex(ty, y.region));
  if (is_edge(x.region) && is_edge(y.region)) {
    const auto [x0, x1] = edge(tx, x.region);
    const auto [y0, y1] = edge(ty, y.region);
    return (same_bits(x0, y0) && same_bits(x1, y1)) || (same_bits(x0, y1) && same_bits(x1, y0));
  }
  return false;
}

struct Counts {
  std::uint64_t candidates = 0, exact_features = 0, exact_comparisons = 0;
};

// The search's working memory, kept per thread between queries (no allocation per query once warm).
struct Pending {
  double lower;
  std::uint32_t first, count;  // a node (count 0) or a leaf range
  bool operator>(const Pending& o) const { return lower > o.lower; }
};
struct SearchBuffers {
  std::vector<Pending> heap;
  std::vector<Candidate> candidates;
  std::vector<ExactMeasure> exact;
  std::vector<std::uint32_t> representatives;
};

ClosestPoint search(const Vec3& query, const PreparedMesh& mesh, Counts& counts) {
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) throw invalid_input("mesh has no triangles: no closest point");
  const std::span<const Triangle> leaf = mesh.leaf_triangles();
  const std::span<const std::uint32_t> order = bvh.triangle_order();
  thread_local SearchBuffers buffers;
  std::vector<Pending>& heap = buffers.heap;
  std::vector<Candidate>& candidates = buffers.candidates;
  std::vector<ExactMeasure>& exact = buffers.exact;
  heap.clear();
  candidates.clear();
  exact.clear();
  const auto push = [&](const Pending& p) {
    heap.push_back(p);
    std::push_heap(heap.begin(), heap.end(), std::greater<>{});
  };
  push({0, 0, 0});
  double best = inf;  // ≥ the smallest exact squared distance measured so far
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), std::greater<>{});
    const Pending next = heap.back();
    heap.pop_back();
    if (next.lower > best) break;  // every box left is farther than a point already found
    if (next.count == 0) {
      const BvhNode& node = bvh.nodes()[next.first];
      for (int s = 0; s < BvhNode::width && !node.empty_slot(s); ++s) {
        const double lower = box_lower_bound(query, node, s);
        if (lower > best) continue;
        push({lower, node.first[static_cast<std::size_t>(s)], node.count[static_cast<std::size_t>(s)]});
      }
      continue;
    }
    for (std::uint32_t position = next.first; position < next.first + next.count; ++position) {
      if (triangle_lower_bound(query, leaf[position]) > best) continue;
      ++counts.candidates;
      Candidate c{order[position], position, {}, ClosestRegion::uncertain, -1};
      const IntervalMeasure m = measure_interval(query, leaf[position], best);
      if (m.kind == IntervalMeasure::farther) continue;
      if (m.kind == IntervalMeasure::measured) {
        c.region = m.region;
        c.squared_distance = m.squared_distance;
      } else {
        ++counts.exact_features;
        c.exact = static_cast<std::int32_t>(exact.size());
        exact.push_back(measure_exact(query, leaf[position]));
        const Q d2 = exact.back().squared_distance();
        c.squared_distance = {detail::exact::round_rational(d2, detail::exact::binary64_format, MPFR_RNDD),
                              detail::exact::round_rational(d2, detail::exact::binary64_format, MPFR_RNDU)};
      }
      if (c.squared_distance.lo > best) continue;
      best = std::min(best, c.squared_distance.hi);
      candidates.push_back(c);
    }
  }
  // The candidates that may be the nearest, by triangle index; one representative per shared vertex or edge.
  std::erase_if(candidates, [&](const Candidate& c) { return c.squared_distance.lo > best; });
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) { return x.triangle < y.triangle; });
  std::vector<std::uint32_t>& representatives = buffers.representatives;
  representatives.clear();
  for (std::uint32_t k = 0; k < candidates.size(); ++k) {
    const Candidate& c = candidates[k];
    const bool repeated = std::any_of(representatives.begin(), representatives.end(), [&](std::uint32_t r) {
      const Candidate& o = candidates[r];
      return c.region != ClosestRegion::uncertain && o.region != ClosestRegion::uncertain &&
             same_feature(o, leaf[o.position], c, leaf[c.position]);
    });
    if (!repeated) representatives.push_back(k);
  }
  const auto measure = [&](Candidate& c) -> const ExactMeasure& {
    if (c.exact < 0) {
      c.exact = static_cast<std::int32_t>(exact.size());
      exact.push_back(measure_exact(query, leaf[c.position]));
    }
    return exact[static_cast<std::size_t>(c.exact)];
  };
  Candidate* winner = &candidates[representatives.front()];
  if (representatives.size() > 1) {
    counts.exact_comparisons += representatives.size();
    for (const std::uint32_t r : representatives) (void)measure(candidates[r]);
    for (const std::uint32_t r : representatives)  // in index order: a strictly smaller distance replaces
      if (nearer(exact[static_cast<std::size_t>(candidates[r].exact)], exact[static_cast<std::size_t>(winner->exact)]))
        winner = &candidates[r];
  }
  return rounded(winner->triangle, measure(*winner));
}

// The binary64 baseline: the same formula in doubles.
struct NaiveMeasure {
  Vec3 point;
  double squared_distance;
  ClosestRegion region;
};
NaiveMeasure measure_naive(const Vec3& query, const Triangle& tri) {
  const auto v = [](const Vec3& x) { return Vec3Of<double>{x.x, x.y, x.z}; };
  const Vec3Of<double> p = v(query), a = v(tri.a), b = v(tri.b), c = v(tri.c);
  const ClosestTerms<double> t = detail::closest_terms<double>(p, a, b, c, 0.0, 1.0, [](double x) {
    return x > 0 ? 1 : x < 0 ? -1 : 0;
  });
  const double sv = t.num_v / t.den, sw = t.num_w / t.den;
  const Vec3 q{a.x + sv * (b.x - a.x) + sw * (c.x - a.x), a.y + sv * (b.y - a.y) + sw * (c.y - a.y),
               a.z + sv * (b.z - a.z) + sw * (c.z - a.z)};
  const double dx = query.x - q.x, dy = query.y - q.y, dz = query.z - q.z;
  return {q, dx * dx + dy * dy + dz * dz, t.region};
}

}  // namespace

ClosestPoint closest_point(const Vec3& query, const PreparedMesh& mesh) {
  throw_if_invalid(query);
  const detail::FpEnvironmentScope environment;
  Counts counts;
  return search(query, mesh, counts);
}

ClosestPoint closest_point(const Vec3& query, const Mesh& mesh) {
  throw_if_invalid(query);
  return closest_point(query, PreparedMesh(mesh));
}

TracedClosestPoint closest_point_traced(const Vec3& query, const PreparedMesh& mesh) {
  throw_if_invalid(query);
  const detail::FpEnvironmentScope environment;
  Counts counts;
  TracedClosestPoint traced;
  traced.closest = search(query, mesh, counts);
  traced.candidates = counts.candidates;
  traced.exact_features = counts.exact_features;
  traced.exact_comparisons = counts.exact_comparisons;
  return traced;
}

double signed_distance(const Vec3& query, const PreparedMesh& mesh, const ClosestPoint& closest) {
  if (closest.squared_distance_exact.numerator == "0") return 0.0;  // on the surface
  return inside(query, mesh) == PointLocation::inside ? -closest.distance : closest.distance;
}

double signed_distance(const Vec3& query, const PreparedMesh& mesh) {
  return signed_distance(query, mesh, closest_point(query, mesh));
}

ClosestPoint closest_point_exact(const Vec3& query, const Mesh& mesh) {
  throw_if_invalid(query);
  if (const auto reason = validate(mesh)) throw invalid_input("mesh: " + *reason);
  if (mesh.triangles.empty()) throw invalid_input("mesh has no triangles: no closest point");
  std::optional<ExactMeasure> best;
  std::uint32_t best_index = 0;
  for (std::uint32_t k = 0; k < mesh.triangles.size(); ++k) {
    ExactMeasure m = measure_exact(query, mesh.triangle(k));
    if (!best || nearer(m, *best)) {
      best = std::move(m);
      best_index = k;
    }
  }
  return rounded(best_index, *best);
}

ClosestPoint closest_point_naive(const Vec3& query, const PreparedMesh& mesh) {
  throw_if_invalid(query);
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) throw invalid_input("mesh has no triangles: no closest point");
  std::priority_queue<Pending, std::vector<Pending>, std::greater<>> queue;
  queue.push({0, 0, 0});
  ClosestPoint best;
  best.squared_distance = inf;
  while (!queue.empty()) {
    const Pending next = queue.top();
    queue.pop();
    if (next.lower > best.squared_distance) break;
    if (next.count == 0) {
      const BvhNode& node = bvh.nodes()[next.first];
      for (int s = 0; s < BvhNode::width && !node.empty_slot(s); ++s) {
        const Box3 box = node.box(s);
        const double gx = std::max({box.lo.x - query.x, 0.0, query.x - box.hi.x}),
                     gy = std::max({box.lo.y - query.y, 0.0, query.y - box.hi.y}),
                     gz = std::max({box.lo.z - query.z, 0.0, query.z - box.hi.z});
        const double lower = gx * gx + gy * gy + gz * gz;
        if (lower <= best.squared_distance)
          queue.push({lower, node.first[static_cast<std::size_t>(s)], node.count[static_cast<std::size_t>(s)]});
      }
      continue;
    }
    for (std::uint32_t position = next.first; position < next.first + next.count; ++position) {
      const NaiveMeasure m = measure_naive(query, mesh.leaf_triangles()[position]);
      const std::uint32_t k = bvh.triangle_order()[position];
      if (m.squared_distance < best.squared_distance ||
          (m.squared_distance == best.squared_distance && k < best.triangle)) {
        best.triangle = k;
        best.point = m.point;
        best.squared_distance = m.squared_distance;
        best.feature = m.region <= ClosestRegion::vertex_c ? ClosestFeature::vertex
                       : m.region == ClosestRegion::face   ? ClosestFeature::face
                                                           : ClosestFeature::edge;
        best.corner = m.region == ClosestRegion::vertex_b || m.region == ClosestRegion::edge_bc ? 1
                      : m.region == ClosestRegion::vertex_c || m.region == ClosestRegion::edge_ca ? 2
                                                                                                  : 0;
      }
    }
  }
  best.distance = std::sqrt(best.squared_distance);
  return best;
}

}  // namespace raykernel
