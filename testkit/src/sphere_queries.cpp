// Constructions of hard ray–sphere queries (sphere_queries.hpp). The exact ones work on integer vectors and
// become doubles by one power-of-two scaling for the points and the radius and one for the direction: exact,
// and tangency (D = 0), an origin on the surface (C = 0) and a root's value in units of the direction's scale
// are invariant under both.
//
// A line at offset u from the centre (u ⟂ d) with the origin o = c + u + s·d has B = s·|d|², C = |u|² + s²|d|² −
// r² and D = |d|²·(r² − |u|²): tangent when r = |u|, and then t0 = −s; with r² − |u|² = g², the roots are −s ∓ g.
// Integer vectors of integer length come from Pythagorean quadruples.
#include <raykernel/testkit/sphere_queries.hpp>

#include <raykernel/testkit/plane_reference_check.hpp>

#include "construction.hpp"

#include <cmath>
#include <cstdint>
#include <string>

namespace raykernel::testkit {
namespace {

using namespace construction;

constexpr std::int64_t grid = std::int64_t{1} << 20;  // centre coordinates in [−2^20, 2^20]

// a² + b² + c² = n².
struct Quadruple {
  std::int64_t a, b, c, n;
};
constexpr Quadruple quadruples[] = {{0, 3, 4, 5},   {1, 2, 2, 3},   {2, 3, 6, 7},    {1, 4, 8, 9},   {4, 4, 7, 9},
                                    {2, 6, 9, 11},  {6, 6, 7, 11},  {0, 5, 12, 13},  {3, 4, 12, 13}, {2, 5, 14, 15},
                                    {2, 10, 11, 15}, {0, 8, 15, 17}, {1, 12, 12, 17}, {8, 9, 12, 17}, {0, 20, 21, 29}};

Quadruple quadruple(Draw& draw) {
  Quadruple q = quadruples[draw.small(0, static_cast<int>(std::size(quadruples)) - 1)];
  switch (draw.small(0, 2)) {  // which component is the odd one out
    case 1: q = {q.b, q.c, q.a, q.n}; break;
    case 2: q = {q.c, q.a, q.b, q.n}; break;
    default: break;
  }
  return q;
}

Vec3 to_vec(IVec v, int e) {
  return {std::ldexp(static_cast<double>(v.x), e), std::ldexp(static_cast<double>(v.y), e),
          std::ldexp(static_cast<double>(v.z), e)};
}

// An exact construction in integers, before scaling.
struct IQuery {
  IVec o, d, c;
  std::int64_t r;
};

SphereQuery from_integers(const IQuery& q, int point_exponent, int direction_exponent) {
  return {{to_vec(q.o, point_exponent), to_vec(q.d, point_exponent + direction_exponent)},
          {to_vec(q.c, point_exponent), std::ldexp(static_cast<double>(q.r), point_exponent)}};
}

// A direction perpendicular to u (nonzero).
IVec perpendicular(Draw& draw, IVec u) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    const IVec d = cross(u, draw.ivec(16));
    if (!is_zero(d)) return d;
  }
  return is_zero(cross(u, {1, 0, 0})) ? cross(u, {0, 1, 0}) : cross(u, {1, 0, 0});
}

// The line along d from the origin o = c + u + s·d: tangent (u = k·(a, b, c) ⟂ d, r = k·n = |u|: t0 = −s), or
// crossing (d = (1, 0, 0), u = k·(0, b, c), r = k·n: r² − |u|² = (k·a)², roots −s ∓ k·a).
IQuery line_construction(Draw& draw, bool crossing) {
  const Quadruple q = quadruple(draw);
  const std::int64_t k = draw.integer(1, 1 << 10);
  IQuery result{};
  result.c = draw.ivec(grid);
  result.r = k * q.n;
  IVec u{}, d{};
  if (crossing) {
    u = k * IVec{0, q.b, q.c};
    d = {1, 0, 0};
  } else {
    u = k * IVec{q.a, q.b, q.c};
    d = perpendicular(draw, u);
  }
  if (draw.coin()) d = -1 * d;
  const std::int64_t s = draw.integer(-(1 << 12), 1 << 12);
  result.d = d;
  result.o = result.c + u + s * d;
  return result;
}

// The origin exactly on the sphere: o = c + k·(a, b, c), r = k·n; d random.
IQuery surface_construction(Draw& draw) {
  const Quadruple q = quadruple(draw);
  const std::int64_t k = draw.integer(1, 1 << 10);
  IQuery result{};
  result.c = draw.ivec(grid);
  result.o = result.c + IVec{k * (draw.coin() ? q.a : -q.a), k * (draw.coin() ? q.b : -q.b), k * q.c};
  result.r = k * q.n;
  result.d = draw.ivec(1 << 12);
  if (is_zero(result.d)) result.d = {1, 2, 3};
  return result;
}

int nonzero_steps(Draw& draw) {
  const int k = draw.small(1, 4);
  return draw.coin() ? k : -k;
}

// One component of o or d, or the radius, moved by 1–4 ulps.
SphereQuery nudged(Draw& draw, SphereQuery q, bool direction_too) {
  const int which = draw.small(0, direction_too ? 6 : 3);
  if (which == 3) {
    q.sphere.radius = nudge(q.sphere.radius, nonzero_steps(draw));
    if (!(q.sphere.radius > 0)) q.sphere.radius = std::nextafter(0.0, 1.0);
  } else if (which < 3) {
    double& x = component(q.ray.origin, which);
    x = nudge(x, nonzero_steps(draw));
  } else {
    double& x = component(q.ray.direction, which - 4);
    x = nudge(x, nonzero_steps(draw));
  }
  return q;
}

// Along ±x, the foot of the perpendicular s = ±(2^53 + 2j) (even, so exact) before the origin o = 0: the roots
// −s ∓ a are odd integers beyond 2^53 in magnitude, midpoints of two doubles, when a is odd (the quadruple is
// turned so that it is, where it has an odd component).
SphereQuery rounding_tie_construction(Draw& draw) {
  Quadruple q = quadruple(draw);
  for (int turn = 0; turn < 2 && q.a % 2 == 0; ++turn) q = {q.b, q.c, q.a, q.n};
  const std::int64_t s = ((std::int64_t{1} << 53) + 2 * draw.integer(0, 1 << 20)) * (draw.coin() ? 1 : -1);
  IQuery result{};
  result.d = {draw.coin() ? 1 : -1, 0, 0};
  result.o = {0, 0, 0};
  result.c = IVec{-s * result.d.x, -q.b, -q.c};  // o − c = (0, b, c) + s·d
  result.r = q.n;
  return from_integers(result, draw.small(-30, 30), 0);
}

SphereQuery build(SphereQueryKind kind, Draw& draw) {
  switch (kind) {
    case SphereQueryKind::random: {
      const double r = std::fabs(draw.unit());
      return {{draw.unit_vector(), draw.unit_vector()}, {draw.unit_vector(), r > 0 ? r : 0.5}};
    }
    case SphereQueryKind::tangent:
      return from_integers(line_construction(draw, false), draw.small(-20, 20), draw.small(-8, 8));
    case SphereQueryKind::near_tangent:
      return nudged(draw, from_integers(line_construction(draw, false), draw.small(-20, 20), draw.small(-8, 8)), true);
    case SphereQueryKind::on_surface:
      return from_integers(surface_construction(draw), draw.small(-20, 20), draw.small(-8, 8));
    case SphereQueryKind::near_surface:
      return nudged(draw, from_integers(surface_construction(draw), draw.small(-20, 20), draw.small(-8, 8)), false);
    case SphereQueryKind::rounding_tie: return rounding_tie_construction(draw);
    case SphereQueryKind::far_cancel: {
      // The origin near the unit box, the centre up to 2^50 away, r = |o − c| rounded and moved by 0–2 ulps.
      const Vec3 o = draw.unit_vector();
      const IVec f = draw.ivec(std::int64_t{1} << 30);
      const double scale = std::ldexp(1.0, draw.small(0, 20));
      const Vec3 c{o.x - static_cast<double>(f.x) * scale, o.y - static_cast<double>(f.y) * scale,
                   o.z - static_cast<double>(f.z) * scale};
      const double fx = o.x - c.x, fy = o.y - c.y, fz = o.z - c.z;
      double r = std::sqrt(fx * fx + fy * fy + fz * fz);
      r = nudge(r, draw.small(-2, 2));
      if (!(r > 0)) r = 1;
      return {{o, draw.unit_vector()}, {c, r}};
    }
    case SphereQueryKind::wide_exponents: {
      auto v = [&] { return Vec3{draw.scaled(-150, 150), draw.scaled(-150, 150), draw.scaled(-150, 150)}; };
      return {{v(), v()}, {v(), std::fabs(draw.scaled(-150, 150))}};
    }
    case SphereQueryKind::tiny_direction:
    case SphereQueryKind::huge_direction: {
      const bool tiny = kind == SphereQueryKind::tiny_direction;
      const int de = tiny ? draw.small(-600, -400) : draw.small(400, 600);
      return from_integers(line_construction(draw, draw.coin()), draw.small(-20, 20), de);
    }
    case SphereQueryKind::subnormal_offset: {
      // Ties without cancellation: o = 0, d = (±1, 0, 0), c = (X·d_x, 0, 0), r = R with R odd in [2^40, 2^51]
      // and X = 2^53 + R + 1 + 2j even: the roots X ∓ R are odd integers in [2^53, 2^54), midpoints of two
      // doubles, and D = R² is far from B² − A·C's rounding error. Then ε = ±k·2^-1074 goes into one of o_x, o_y,
      // o_z, c_y, c_z: across the ray, C grows by ε² (a square that underflows in binary64) and nothing else
      // changes; along it, the roots move by ε. Either way they leave their midpoints by less than any double.
      const std::int64_t r = 2 * draw.integer(std::int64_t{1} << 39, std::int64_t{1} << 50) + 1;
      const std::int64_t x = (std::int64_t{1} << 53) + r + 1 + 2 * draw.integer(0, std::int64_t{1} << 40);
      IQuery tie{};
      tie.d = {draw.coin() ? 1 : -1, 0, 0};
      tie.c = {x * tie.d.x, 0, 0};
      tie.r = r;
      SphereQuery q = from_integers(tie, draw.small(-30, 30), 0);
      const double offset = static_cast<double>(draw.integer(1, 1 << 20)) * 0x1p-1074 * (draw.coin() ? 1 : -1);
      const int where = draw.small(0, 4);
      if (where < 3) component(q.ray.origin, where) = offset;
      else component(q.sphere.center, where - 2) = offset;
      return q;
    }
    case SphereQueryKind::tiny:
    case SphereQueryKind::huge: {
      const int pe = kind == SphereQueryKind::tiny ? draw.small(-1000, -900) : draw.small(900, 980);
      const IQuery q = draw.coin() ? line_construction(draw, draw.coin()) : surface_construction(draw);
      return from_integers(q, pe, draw.small(-8, 8));
    }
  }
  return {};
}

// The same permutation and reflection of the axes for o, d and c: every distance and dot product survives.
SphereQuery shuffle(Draw& draw, SphereQuery q) {
  permute_and_reflect_axes(draw, {&q.ray.origin, &q.ray.direction, &q.sphere.center});
  return q;
}

}  // namespace

std::string_view to_string(SphereQueryKind kind) noexcept {
  switch (kind) {
    case SphereQueryKind::random: return "random";
    case SphereQueryKind::tangent: return "tangent";
    case SphereQueryKind::near_tangent: return "near-tangent";
    case SphereQueryKind::on_surface: return "on-surface";
    case SphereQueryKind::near_surface: return "near-surface";
    case SphereQueryKind::rounding_tie: return "rounding-tie";
    case SphereQueryKind::far_cancel: return "far-cancel";
    case SphereQueryKind::wide_exponents: return "wide-exponents";
    case SphereQueryKind::tiny_direction: return "tiny-direction";
    case SphereQueryKind::huge_direction: return "huge-direction";
    case SphereQueryKind::tiny: return "tiny";
    case SphereQueryKind::huge: return "huge";
    case SphereQueryKind::subnormal_offset: return "subnormal-offset";
  }
  return "?";
}

SphereQuery make_sphere_query(SphereQueryKind kind, const BitSource& bits) {
  Draw draw(bits);
  SphereQuery q = shuffle(draw, build(kind, draw));
  Vec3& d = q.ray.direction;
  if (d.x == 0 && d.y == 0 && d.z == 0) d.x = 1;  // only a shrinker's all-zero words reach this
  return q;
}

std::string sphere_line(const SphereQuery& q) {
  std::string line;
  for (double x : {q.ray.origin.x, q.ray.origin.y, q.ray.origin.z, q.ray.direction.x, q.ray.direction.y,
                   q.ray.direction.z, q.sphere.center.x, q.sphere.center.y, q.sphere.center.z, q.sphere.radius}) {
    if (!line.empty()) line += ' ';
    line += hex_string(x);
  }
  return line;
}

}  // namespace raykernel::testkit
