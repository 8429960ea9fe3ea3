// Constructions of hard ray–triangle queries (triangle_queries.hpp). The exact constructions work on integer
// vectors (|coordinate| < 2^45, so sums, differences and small multiples are exact in int64 and as doubles)
// and turn them into doubles by one power-of-two scaling for the points and one for the direction: exact,
// and the incidence (a line through a vertex, a direction in the plane) is scale-invariant.
#include <raykernel/testkit/triangle_queries.hpp>

#include <raykernel/testkit/plane_reference_check.hpp>

#include "construction.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

namespace raykernel::testkit {
namespace {

using namespace construction;

constexpr std::int64_t grid = std::int64_t{1} << 20;  // vertex and origin coordinates in [−2^20, 2^20]

Vec3 to_vec(IVec v, int e) {
  return {std::ldexp(static_cast<double>(v.x), e), std::ldexp(static_cast<double>(v.y), e),
          std::ldexp(static_cast<double>(v.z), e)};
}

// An exact construction in integers: the triangle, the origin, and the direction.
struct IQuery {
  IVec o, d, a, b, c;
};

// A nonzero direction: `d`, or when it is zero (the origin drawn on the target), a fixed one with the origin
// moved back along it, so that the line still passes through the target.
void ensure_direction(IQuery& q) {
  if (!is_zero(q.d)) return;
  q.d = {1, 2, 3};
  q.o = q.o - q.d;
}

// A point of the triangle with weights (2^m − j − k, j, k)/2^m, all coordinates scaled by 2^m (so exact):
// returns the triangle scaled by 2^m as well.
struct DyadicPoint {
  IVec a, b, c, point;
};
DyadicPoint dyadic_point(const IQuery& q, int m, std::int64_t j, std::int64_t k) {
  const std::int64_t scale = std::int64_t{1} << m;
  const IVec a = scale * q.a, b = scale * q.b, c = scale * q.c;
  return {a, b, c, a + j * (q.b - q.a) + k * (q.c - q.a)};
}

// The line from a random origin through a vertex (where = 0), an edge point (1) or an interior point (2),
// possibly the other way (behind) and with the direction scaled by a power of two separately (returned in
// `direction_exponent`).
IQuery aimed(Draw& draw, int where, int& direction_exponent, IVec* target = nullptr) {
  IQuery q{draw.ivec(grid), {}, draw.ivec(grid), draw.ivec(grid), draw.ivec(grid)};
  const int m = draw.small(1, 20);
  const std::int64_t full = std::int64_t{1} << m;
  std::int64_t j = 0, k = 0;
  if (where == 0) {
    const int v = draw.small(0, 2);
    j = v == 1 ? full : 0;
    k = v == 2 ? full : 0;
  } else if (where == 1) {
    const std::int64_t w = draw.integer(1, full - 1);
    switch (draw.small(0, 2)) {
      case 0: j = w; break;             // edge ab
      case 1: j = w, k = full - w; break;  // edge bc
      default: k = w; break;            // edge ca
    }
  } else {
    if (full < 4) return aimed(draw, 0, direction_exponent, target);
    j = draw.integer(1, full - 2);
    k = draw.integer(1, full - 1 - j);
  }
  const DyadicPoint p = dyadic_point(q, m, j, k);
  q.a = p.a, q.b = p.b, q.c = p.c;
  q.o = (std::int64_t{1} << m) * q.o;
  q.d = p.point - q.o;
  ensure_direction(q);
  if (target != nullptr) *target = p.point;
  if (draw.coin()) q.d = -1 * q.d;  // the point lies behind the origin
  direction_exponent = draw.small(-8, 8);
  return q;
}

TriangleQuery from_integers(const IQuery& q, int point_exponent, int direction_exponent) {
  return {{to_vec(q.o, point_exponent), to_vec(q.d, point_exponent + direction_exponent)},
          {to_vec(q.a, point_exponent), to_vec(q.b, point_exponent), to_vec(q.c, point_exponent)}};
}


int nonzero_steps(Draw& draw) {
  const int k = draw.small(1, 4);
  return draw.coin() ? k : -k;
}

TriangleQuery build(TriangleQueryKind kind, Draw& draw) {
  int de = 0;
  switch (kind) {
    case TriangleQueryKind::random:
      return {{draw.unit_vector(), draw.unit_vector()}, {draw.unit_vector(), draw.unit_vector(), draw.unit_vector()}};
    case TriangleQueryKind::through_vertex: {
      const IQuery q = aimed(draw, 0, de);
      return from_integers(q, draw.small(-60, 40), de);
    }
    case TriangleQueryKind::through_edge: {
      const IQuery q = aimed(draw, 1, de);
      return from_integers(q, draw.small(-60, 40), de);
    }
    case TriangleQueryKind::through_interior: {
      const IQuery q = aimed(draw, 2, de);
      return from_integers(q, draw.small(-60, 40), de);
    }
    case TriangleQueryKind::near_vertex:
    case TriangleQueryKind::near_edge: {
      const IQuery q = aimed(draw, kind == TriangleQueryKind::near_vertex ? 0 : 1, de);
      TriangleQuery t = from_integers(q, draw.small(-60, 40), de);
      Vec3& v = draw.coin() ? t.ray.origin : t.ray.direction;
      double& c = component(v, draw.small(0, 2));
      c = nudge(c, nonzero_steps(draw));
      return t;
    }
    case TriangleQueryKind::origin_on_triangle: {
      IVec target{};
      IQuery q = aimed(draw, draw.small(0, 2), de, &target);
      q.o = target;  // the origin on a vertex, an edge point or an interior point of the triangle
      q.d = draw.ivec(grid);
      ensure_direction(q);
      return from_integers(q, draw.small(-60, 40), draw.small(-8, 8));
    }
    case TriangleQueryKind::sliver: {
      // c on the midpoint of ab, then moved off the line by a few ulps in one coordinate.
      IQuery q = aimed(draw, draw.small(0, 2), de);
      const IVec mid = q.a + q.b;  // 2·midpoint: scale a and b by 2 instead of halving
      q.a = 2 * q.a, q.b = 2 * q.b, q.o = 2 * q.o, q.d = 2 * q.d;
      q.c = mid;
      TriangleQuery t = from_integers(q, draw.small(-60, 40), de);
      double& c = component(t.triangle.c, draw.small(0, 2));
      c = nudge(c, nonzero_steps(draw));
      return t;
    }
    case TriangleQueryKind::needle: {
      // b a few ulps from a (in one or more coordinates); the ray aimed at a, at c or at the middle of ca.
      IQuery q = aimed(draw, draw.small(0, 1), de);
      TriangleQuery t = from_integers(q, draw.small(-60, 40), de);
      t.triangle.b = t.triangle.a;
      for (int i = 0, n = draw.small(1, 3); i < n; ++i) {
        double& c = component(t.triangle.b, draw.small(0, 2));
        c = nudge(c, nonzero_steps(draw));
      }
      return t;
    }
    case TriangleQueryKind::degenerate: {
      IQuery q = aimed(draw, draw.small(0, 2), de);
      const std::int64_t k = draw.integer(-3, 3);
      q.c = q.a + k * (q.b - q.a);  // collinear; k = 0 or 1 repeats a vertex
      if (draw.small(0, 3) == 0) q.b = q.a;
      return from_integers(q, draw.small(-60, 40), de);
    }
    case TriangleQueryKind::parallel:
    case TriangleQueryKind::coplanar: {
      IQuery q{{}, {}, draw.ivec(grid), draw.ivec(grid), draw.ivec(grid)};
      const IVec u = q.b - q.a, v = q.c - q.a;
      q.d = draw.integer(-4, 4) * u + draw.integer(-4, 4) * v;
      if (is_zero(q.d)) q.d = u;
      if (is_zero(q.d)) q.d = {1, 0, 0};
      q.o = q.a + draw.integer(-4, 4) * u + draw.integer(-4, 4) * v;
      if (kind == TriangleQueryKind::parallel) {
        IVec n = cross(u, v);
        // N < 2^43 per coordinate: o + 3N stays below 2^45. (A degenerate triangle has N = 0: o stays in
        // the "plane", and the answer is degenerate anyway.)
        q.o = q.o + (draw.coin() ? 1 : -1) * draw.integer(1, 3) * n;
      }
      return from_integers(q, draw.small(-60, 20), draw.small(-8, 8));
    }
    case TriangleQueryKind::above_power_of_two: {
      // A quotient in (2^e + ulp/4, 2^e + ulp/2), which rounds down to 2^e where the gap below is half the gap
      // above: round_quotient's rule (the half gap to the nearer neighbour) cannot certify it, the rounding
      // boundaries can. j is drawn in (2^(m−54), 2^(m−53)) so that j·2^-m lies in (2^-54, 2^-53).
      const int m = draw.small(56, 100);
      const std::uint64_t low = std::uint64_t{1} << (m - 54);
      const double j = static_cast<double>(low + 1 + draw.word() % (low - 1));
      if (draw.coin()) {
        // t: the triangle in the plane z = 2^(m+s), o_z = −j·2^s, d_z = ±2^(m+u): t = ±(1 + j·2^-m)·2^(s−u).
        const int s = draw.small(-60, 60), u = draw.small(-60, 60), e = draw.small(-30, 10);
        const double Z = std::ldexp(1.0, m + s);
        auto grid_point = [&] { return std::ldexp(static_cast<double>(draw.integer(-grid, grid)), e); };
        auto xy = [&] { return Vec3{grid_point(), grid_point(), Z}; };
        const Vec3 a = xy(), b = xy(), c = xy();
        const Vec3 o{grid_point(), grid_point(), -std::ldexp(j, s)};
        const Vec3 d{grid_point(), grid_point(), std::ldexp(draw.coin() ? 1.0 : -1.0, m + u)};
        return TriangleQuery{{o, d}, {a, b, c}};
      }
      // u_a: a = 0, b = 2^k·x, c = 2^k·y, the ray along z through (−j·2^(k−m−1), −j·2^(k−m−1)):
      // u_a = 1 − x/2^k − y/2^k = 1 + j·2^-m.
      const int k = draw.small(-40, 40);
      const double x = -std::ldexp(j, k - m - 1);
      const Vec3 o{x, x, std::ldexp(static_cast<double>(draw.integer(1, grid)) * (draw.coin() ? 1 : -1), k)};
      const Vec3 d{0, 0, std::ldexp(draw.coin() ? 1.0 : -1.0, draw.small(-40, 40))};
      return TriangleQuery{{o, d}, {Vec3{0, 0, 0}, Vec3{std::ldexp(1.0, k), 0, 0}, Vec3{0, std::ldexp(1.0, k), 0}}};
    }
    case TriangleQueryKind::rounding_tie: {
      // The triangle in the plane z = Z, d = (dx, dy, D·2^g) with D odd: N = (0, 0, N_z) and t = (Z − o_z)/d_z.
      // Z − o_z = D·M·2^(s+g) with M odd in (2^53, 2^54): t = M·2^s lies halfway between two doubles. The
      // 58-bit Z − o_z is held as Z = hi, o_z = −lo (hi + lo exact).
      const std::uint64_t M = (std::uint64_t{1} << 53) + 2 * (draw.word() >> 12) + 1;
      const std::uint64_t D = 2 * static_cast<std::uint64_t>(draw.small(0, 7)) + 1;
      const std::uint64_t X = D * M;  // < 2^58
      const double hi = static_cast<double>(X);
      const double lo = static_cast<double>(static_cast<std::int64_t>(X) - static_cast<std::int64_t>(hi));
      const int s = draw.small(-80, 0), g = draw.small(-20, 20);
      const double Z = std::ldexp(hi, s + g);
      const int e = draw.small(-30, 10);
      auto xy = [&] {
        const IVec v = draw.ivec(grid);
        return Vec3{std::ldexp(static_cast<double>(v.x), e), std::ldexp(static_cast<double>(v.y), e), Z};
      };
      const Vec3 a = xy(), b = xy(), c = xy();
      TriangleQuery t{{{std::ldexp(static_cast<double>(draw.integer(-grid, grid)), e),
                        std::ldexp(static_cast<double>(draw.integer(-grid, grid)), e), -std::ldexp(lo, s + g)},
                       {std::ldexp(static_cast<double>(draw.integer(-grid, grid)), e),
                        std::ldexp(static_cast<double>(draw.integer(-grid, grid)), e),
                        std::ldexp(static_cast<double>(D), g)}},
                      {a, b, c}};
      if (draw.coin()) t.ray.direction.z = -t.ray.direction.z;  // behind
      if (draw.small(0, 3) == 0) t.ray.origin.z = nudge(t.ray.origin.z, nonzero_steps(draw));  // near a tie
      return t;
    }
    case TriangleQueryKind::wide_exponents: {
      auto v = [&] { return Vec3{draw.scaled(-300, 300), draw.scaled(-300, 300), draw.scaled(-300, 300)}; };
      return {{v(), v()}, {v(), v(), v()}};
    }
    case TriangleQueryKind::tiny:
    case TriangleQueryKind::huge: {
      const IQuery q = aimed(draw, draw.small(0, 2), de);  // coordinates below 2^42
      const bool tiny = kind == TriangleQueryKind::tiny;
      const int e = tiny ? draw.small(-1074, -1000) : draw.small(900, 975);  // |coordinates| < 2^44·2^975
      return from_integers(q, e, tiny ? draw.small(0, 8) : draw.small(-8, 0));
    }
  }
  return {{{0, 0, -1}, {0, 0, 1}}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
}

// The same permutation and reflection of the axes for all five vectors, and a relabelling of the vertices:
// every incidence, zero and tie survives exactly (a reflection or a reversal flips N and the π's together).
TriangleQuery shuffle(Draw& draw, TriangleQuery q) {
  permute_and_reflect_axes(draw, {&q.ray.origin, &q.ray.direction, &q.triangle.a, &q.triangle.b, &q.triangle.c});
  Triangle& t = q.triangle;
  switch (draw.small(0, 3)) {
    case 1: t = {t.b, t.c, t.a}; break;
    case 2: t = {t.c, t.a, t.b}; break;
    case 3: t = {t.a, t.c, t.b}; break;
    default: break;
  }
  return q;
}

}  // namespace

std::string_view to_string(TriangleQueryKind kind) noexcept {
  switch (kind) {
    case TriangleQueryKind::random: return "random";
    case TriangleQueryKind::through_vertex: return "through-vertex";
    case TriangleQueryKind::through_edge: return "through-edge";
    case TriangleQueryKind::through_interior: return "through-interior";
    case TriangleQueryKind::near_vertex: return "near-vertex";
    case TriangleQueryKind::near_edge: return "near-edge";
    case TriangleQueryKind::origin_on_triangle: return "origin-on-triangle";
    case TriangleQueryKind::sliver: return "sliver";
    case TriangleQueryKind::needle: return "needle";
    case TriangleQueryKind::degenerate: return "degenerate";
    case TriangleQueryKind::parallel: return "parallel";
    case TriangleQueryKind::coplanar: return "coplanar";
    case TriangleQueryKind::rounding_tie: return "rounding-tie";
    case TriangleQueryKind::above_power_of_two: return "above-power-of-two";
    case TriangleQueryKind::wide_exponents: return "wide-exponents";
    case TriangleQueryKind::tiny: return "tiny";
    case TriangleQueryKind::huge: return "huge";
  }
  return "?";
}

TriangleQuery make_triangle_query(TriangleQueryKind kind, const BitSource& bits) {
  Draw draw(bits);
  TriangleQuery q = shuffle(draw, build(kind, draw));
  Vec3& d = q.ray.direction;
  if (d.x == 0 && d.y == 0 && d.z == 0) d.x = 1;  // only a shrinker's all-zero words reach this
  return q;
}

std::string triangle_line(const TriangleQuery& q) {
  std::string line;
  for (const Vec3* v : {&q.ray.origin, &q.ray.direction, &q.triangle.a, &q.triangle.b, &q.triangle.c}) {
    for (double c : {v->x, v->y, v->z}) {
      if (!line.empty()) line += ' ';
      line += hex_string(c);
    }
  }
  return line;
}

}  // namespace raykernel::testkit
