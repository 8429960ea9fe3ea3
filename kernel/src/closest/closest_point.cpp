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

constexpr double inf = std::numeric_limits<double>::infinity();

void throw_if_invalid(const Vec3& query) {
  if (const auto reason = detail::non_finite_reason("query point", query)) throw invalid_input(*reason);
}

// ---- exact rationals --------------------------------------------------------------------------------------------

Vec3Of<Q> lift(const Vec3& v) {
  using detail::exact::rational_from_double;
  return {rational_from_double(v.x), rational_from_double(v.y), rational_from_double(v.z)};
}

// The exact closest point of one triangle: the point, its squared distance, where it lies.
struct ExactMeasure {
  Vec3Of<Q> point;
  Q squared_distance;
  ClosestFeature feature = ClosestFeature::face;
  std::uint8_t corner = 0;
};

bool is_zero(const Vec3Of<Q>& v) { return sgn(v.x) == 0 && sgn(v.y) == 0 && sgn(v.z) == 0; }
bool same(const Vec3Of<Q>& u, const Vec3Of<Q>& v) { return u.x == v.x && u.y == v.y && u.z == v.z; }
Vec3Of<Q> cross(const Vec3Of<Q>& u, const Vec3Of<Q>& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}

// A degenerate triangle (a, b, c on a line, or one point) is the union of its three segments, itself a segment:
// its closest point is the nearest of the segments' (the first of them on a tie: the same point).
ExactMeasure measure_degenerate(const Vec3Of<Q>& p, const std::array<Vec3Of<Q>, 3>& v) {
  ExactMeasure best;
  bool found = false;
  for (std::uint8_t k = 0; k < 3; ++k) {
    const Vec3Of<Q>& s0 = v[k];
    const Vec3Of<Q> e = v[(k + 1) % 3] - s0;
    const Q length2 = dot(e, e);
    Q t = 0;
    if (sgn(length2) > 0) {
      t = dot(p - s0, e) / length2;
      if (sgn(t) < 0) t = 0;
      if (t > 1) t = 1;
    }
    const Vec3Of<Q> q{s0.x + t * e.x, s0.y + t * e.y, s0.z + t * e.z};
    const Vec3Of<Q> r = p - q;
    Q d2 = dot(r, r);
    if (!found || d2 < best.squared_distance) {
      best = {q, std::move(d2), ClosestFeature::edge, k};
      found = true;
    }
  }
  for (std::uint8_t k = 0; k < 3; ++k)
    if (same(best.point, v[k])) {
      best.feature = ClosestFeature::vertex;
      best.corner = k;
      break;
    }
  return best;
}

ExactMeasure measure_exact(const Vec3& query, const Triangle& tri) {
  const Vec3Of<Q> p = lift(query), a = lift(tri.a), b = lift(tri.b), c = lift(tri.c);
  if (is_zero(cross(b - a, c - a))) return measure_degenerate(p, {a, b, c});
  const ClosestTerms<Q> t =
      detail::closest_terms<Q>(p, a, b, c, Q(0), Q(1), [](const Q& x) { return sgn(x); });
  const Vec3Of<Q> ab = b - a, ac = c - a;
  ExactMeasure m;
  m.point = {a.x + (t.num_v * ab.x + t.num_w * ac.x) / t.den, a.y + (t.num_v * ab.y + t.num_w * ac.y) / t.den,
             a.z + (t.num_v * ab.z + t.num_w * ac.z) / t.den};
  const Vec3Of<Q> r = p - m.point;
  m.squared_distance = dot(r, r);
  // Where the point lies, from its barycentric coordinates (u, v, w) = (den − num_v − num_w, num_v, num_w)/den.
  const bool u0 = t.den == t.num_v + t.num_w, v0 = sgn(t.num_v) == 0, w0 = sgn(t.num_w) == 0;
  if (v0 && w0) m = {m.point, m.squared_distance, ClosestFeature::vertex, 0};
  else if (u0 && w0) m = {m.point, m.squared_distance, ClosestFeature::vertex, 1};
  else if (u0 && v0) m = {m.point, m.squared_distance, ClosestFeature::vertex, 2};
  else if (w0) m = {m.point, m.squared_distance, ClosestFeature::edge, 0};
  else if (u0) m = {m.point, m.squared_distance, ClosestFeature::edge, 1};
  else if (v0) m = {m.point, m.squared_distance, ClosestFeature::edge, 2};
  return m;
}

ClosestPoint rounded(std::uint32_t triangle, const ExactMeasure& m) {
  using detail::exact::round_rational_to_nearest_even;
  ClosestPoint r;
  r.triangle = triangle;
  r.feature = m.feature;
  r.corner = m.corner;
  r.point = {round_rational_to_nearest_even(m.point.x), round_rational_to_nearest_even(m.point.y),
             round_rational_to_nearest_even(m.point.z)};
  r.squared_distance_exact = detail::exact::to_public(m.squared_distance);
  r.squared_distance = round_rational_to_nearest_even(m.squared_distance);
  r.distance = detail::exact::round_root(Q(0), m.squared_distance, +1, detail::exact::binary64_format, MPFR_RNDN);
  return r;
}

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
  ClosestRegion region;    // uncertain: measured in rationals (exact below)
  std::optional<ExactMeasure> exact;
};

// The interval measure, or nothing when a sign is uncertain or the triangle may be degenerate.
std::optional<std::pair<ClosestRegion, Interval>> measure_interval(const Vec3& query, const Triangle& tri) {
  const Vec3Of<Interval> p = point_interval(query), a = point_interval(tri.a), b = point_interval(tri.b),
                         c = point_interval(tri.c);
  const Vec3Of<Interval> ab = b - a, ac = c - a;
  const Interval nx = ab.y * ac.z - ab.z * ac.y, ny = ab.z * ac.x - ab.x * ac.z, nz = ab.x * ac.y - ab.y * ac.x;
  if (!surely_nonzero(nx) && !surely_nonzero(ny) && !surely_nonzero(nz)) return std::nullopt;
  const ClosestTerms<Interval> t = detail::closest_terms<Interval>(
      p, a, b, c, Interval::point(0), Interval::point(1), [](const Interval& x) { return detail::interval_sign(x); });
  if (t.region == ClosestRegion::uncertain) return std::nullopt;
  const Interval den2 = detail::square(t.den);
  if (!(den2.lo > 0)) return std::nullopt;
  const Vec3Of<Interval> r = detail::scaled_offset(t, p, a, b, c);
  const Interval num = detail::square(r.x) + detail::square(r.y) + detail::square(r.z);
  return std::pair{t.region, detail::divide_nonnegative(num, den2)};
}

// A lower bound of the squared distance from p to the box [lo, hi] (closed).
double box_lower_bound(const Vec3& p, const BvhNode& node, int slot) {
  using detail::next_down;
  const auto s = static_cast<std::size_t>(slot);
  const double coordinates[3] = {p.x, p.y, p.z};
  double sum = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const double x = coordinates[k], lo = node.bounds[k][s], hi = node.bounds[k + 3][s];
    double gap = 0;
    if (x < lo) gap = std::max(0.0, next_down(lo - x));
    else if (x > hi) gap = std::max(0.0, next_down(x - hi));
    sum = std::max(0.0, next_down(sum + std::max(0.0, next_down(gap * gap))));
  }
  return sum;
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

ClosestPoint search(const Vec3& query, const PreparedMesh& mesh, Counts& counts) {
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) throw invalid_input("mesh has no triangles: no closest point");
  const std::span<const Triangle> leaf = mesh.leaf_triangles();
  const std::span<const std::uint32_t> order = bvh.triangle_order();

  struct Pending {
    double lower;
    std::uint32_t first, count;  // a node (count 0) or a leaf range
    bool operator>(const Pending& o) const { return lower > o.lower; }
  };
  std::priority_queue<Pending, std::vector<Pending>, std::greater<>> queue;
  queue.push({0, 0, 0});
  double best = inf;  // ≥ the smallest exact squared distance measured so far
  std::vector<Candidate> candidates;
  while (!queue.empty()) {
    const Pending next = queue.top();
    queue.pop();
    if (next.lower > best) break;  // every box left is farther than a point already found
    if (next.count == 0) {
      const BvhNode& node = bvh.nodes()[next.first];
      for (int s = 0; s < static_cast<int>(node.children); ++s) {
        const double lower = box_lower_bound(query, node, s);
        if (lower <= best)
          queue.push({lower, node.first[static_cast<std::size_t>(s)], node.count[static_cast<std::size_t>(s)]});
      }
      continue;
    }
    for (std::uint32_t position = next.first; position < next.first + next.count; ++position) {
      ++counts.candidates;
      Candidate c{order[position], position, {}, ClosestRegion::uncertain, std::nullopt};
      if (const auto measured = measure_interval(query, leaf[position])) {
        c.region = measured->first;
        c.squared_distance = measured->second;
      } else {
        ++counts.exact_features;
        c.exact = measure_exact(query, leaf[position]);
        c.squared_distance = {
            detail::exact::round_rational(c.exact->squared_distance, detail::exact::binary64_format, MPFR_RNDD),
            detail::exact::round_rational(c.exact->squared_distance, detail::exact::binary64_format, MPFR_RNDU)};
      }
      if (c.squared_distance.lo > best) continue;
      best = std::min(best, c.squared_distance.hi);
      candidates.push_back(std::move(c));
    }
  }
  // The candidates that may be the nearest, by triangle index; one representative per shared vertex or edge.
  std::erase_if(candidates, [&](const Candidate& c) { return c.squared_distance.lo > best; });
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) { return x.triangle < y.triangle; });
  std::vector<Candidate*> representatives;
  for (Candidate& c : candidates) {
    const bool repeated = std::any_of(representatives.begin(), representatives.end(), [&](const Candidate* r) {
      return c.region != ClosestRegion::uncertain && r->region != ClosestRegion::uncertain &&
             same_feature(*r, leaf[r->position], c, leaf[c.position]);
    });
    if (!repeated) representatives.push_back(&c);
  }
  Candidate* winner = representatives.front();
  if (representatives.size() > 1) {
    counts.exact_comparisons += representatives.size();
    for (Candidate* c : representatives)
      if (!c->exact) c->exact = measure_exact(query, leaf[c->position]);
    for (Candidate* c : representatives)  // in index order: a strictly smaller distance replaces
      if (c->exact->squared_distance < winner->exact->squared_distance) winner = c;
  }
  if (!winner->exact) winner->exact = measure_exact(query, leaf[winner->position]);
  return rounded(winner->triangle, *winner->exact);
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
    if (!best || m.squared_distance < best->squared_distance) {
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
  struct Pending {
    double lower;
    std::uint32_t first, count;
    bool operator>(const Pending& o) const { return lower > o.lower; }
  };
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
      for (int s = 0; s < static_cast<int>(node.children); ++s) {
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
