// The exact ground truth of a secondary ray (<raykernel/spawn.hpp>: hits_exact, first_hits_exact): rays from a
// rational start point, decided in GMP rationals by the ray–triangle formula of triangle/ray_triangle_formula.hpp
// (the leaves e_v = v − X taken exactly from the rational X), after a box test in doubles that only sets
// triangles aside when no point of their box can be met.
#include <raykernel/spawn.hpp>

#include "core/binary64_rounding.hpp"
#include "core/exact_value.hpp"
#include "core/fp_environment.hpp"
#include "core/validation.hpp"
#include "spawn/exact_point.hpp"
#include "triangle/ray_triangle_formula.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace raykernel {
namespace {

using detail::exact::Exact;
using detail::exact::Q3;

[[noreturn]] void invalid(const std::string& reason) { throw invalid_input(reason); }

void require(const std::optional<std::string>& reason) {
  if (reason) invalid(*reason);
}

// The validated start point X, exactly.
Q3 start_point(const HitPoint& from, const Triangle& source, const Vec3& direction, const SecondaryInterval& interval) {
  if (from.kind == HitPoint::Kind::ray_crossing) {
    require(validate(from.ray));
    require(detail::non_finite_reason("triangle a", source.a));
    require(detail::non_finite_reason("triangle b", source.b));
    require(detail::non_finite_reason("triangle c", source.c));
  } else {
    require(detail::non_finite_reason("start point", from.point));
  }
  require(detail::non_finite_reason("direction", direction));
  if (detail::is_zero(direction)) invalid("direction is the zero vector");
  if (!detail::is_finite(interval.t_min) || interval.t_min < 0)
    invalid("t_min must be finite and at least 0");
  if (from.kind == HitPoint::Kind::point) return detail::exact::exact(from.point);
  const Q3 a = detail::exact::exact(source.a);
  const Q3 normal = detail::exact::cross(detail::exact::minus(detail::exact::exact(source.b), a),
                                         detail::exact::minus(detail::exact::exact(source.c), a));
  const std::optional<Q3> p = detail::exact::hit_point(from, a, normal);
  if (!p) invalid("the ray is parallel to the plane of the source triangle (or the triangle is degenerate)");
  return *p;
}

// The exact t at which the ray from X along w meets the closed triangle, or nothing (a miss, a coplanar or
// degenerate triangle: den = 0).
std::optional<mpq_class> exact_t(const Q3& x, const std::array<Exact, 3>& w, const Triangle& tri) {
  using detail::exact::rational_from_double;
  const auto e = [&](const Vec3& v) {
    return std::array<Exact, 3>{Exact{rational_from_double(v.x) - x[0]}, Exact{rational_from_double(v.y) - x[1]},
                                Exact{rational_from_double(v.z) - x[2]}};
  };
  const detail::RayTriangleLeaves<Exact> leaves{w, {e(tri.a), e(tri.b), e(tri.c)}};
  const auto terms = detail::ray_triangle_terms(leaves);
  const int sden = sgn(terms.den);
  if (sden == 0) return std::nullopt;
  if (detail::triangle_location(sgn(terms.pi[0]), sgn(terms.pi[1]), sgn(terms.pi[2]), sden) ==
      TriangleLocation::outside)
    return std::nullopt;
  return mpq_class(terms.num.q / terms.den.q);
}

bool in_interval(const mpq_class& t, const mpq_class& t_min, bool included) {
  const int c = cmp(t, t_min);
  return included ? c >= 0 : c > 0;
}

// ---- The box test ----------------------------------------------------------------------------------------
// A bound computed in binary64 round-to-nearest (one subtraction, one division) is within 2^-51.9 of the exact
// value relatively, plus 2^-1075 absolutely (a subtraction of doubles with a subnormal result is exact; a
// division's error is at most half an ulp). Eight steps of nextafter outwards move it by more than that (each
// step is at least 2^-1074, and at least 2^-53 of the value relatively), so the widened bounds enclose the
// exact ones. Infinite results stay infinite (an overflow is conservative); no NaN arises (every operand is
// finite, apart from the start box's bounds, which are subtracted from finite values).
double down(double v) {
  for (int k = 0; k < 8; ++k) v = std::nextafter(v, -std::numeric_limits<double>::infinity());
  return v;
}
double up(double v) {
  for (int k = 0; k < 8; ++k) v = std::nextafter(v, std::numeric_limits<double>::infinity());
  return v;
}

struct StartBox {
  std::array<double, 3> lo, hi;  // RD and RU of X's coordinates (X itself for a point of doubles)
};

StartBox start_box(const Q3& x) {
  StartBox b{};
  for (std::size_t k = 0; k < 3; ++k) {
    b.lo[k] = detail::exact::round_rational(x[k], detail::exact::binary64_format, MPFR_RNDD);
    b.hi[k] = detail::exact::round_rational(x[k], detail::exact::binary64_format, MPFR_RNDU);
  }
  return b;
}

// False only when no point X' + s·w with X' in the start box and s ≥ 0 lies in the triangle's box.
bool may_meet(const StartBox& x, const std::array<double, 3>& w, const Triangle& tri) {
  const std::array<double, 3> va{tri.a.x, tri.a.y, tri.a.z}, vb{tri.b.x, tri.b.y, tri.b.z}, vc{tri.c.x, tri.c.y, tri.c.z};
  double s_lo = 0, s_hi = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < 3; ++k) {
    const double lo = std::min({va[k], vb[k], vc[k]}), hi = std::max({va[k], vb[k], vc[k]});
    if (w[k] == 0) {
      if (x.hi[k] < lo || x.lo[k] > hi) return false;
      continue;
    }
    // s with X'_k + s·w_k in [lo, hi] for some X'_k in [x.lo, x.hi].
    double from = (lo - x.hi[k]) / w[k], to = (hi - x.lo[k]) / w[k];
    if (w[k] < 0) from = (hi - x.lo[k]) / w[k], to = (lo - x.hi[k]) / w[k];
    s_lo = std::max(s_lo, down(from));
    s_hi = std::min(s_hi, up(to));
    if (s_lo > s_hi) return false;
  }
  return true;
}

std::array<Exact, 3> exact_direction(const Vec3& w) {
  return {detail::exact::lift(w.x), detail::exact::lift(w.y), detail::exact::lift(w.z)};
}

}  // namespace

bool hits_exact(const HitPoint& from, const Triangle& source, const Vec3& direction, const Triangle& triangle,
                const SecondaryInterval& interval) {
  return detail::in_default_fp_environment([&] {
    const Q3 x = start_point(from, source, direction, interval);
    require(detail::non_finite_reason("triangle a", triangle.a));
    require(detail::non_finite_reason("triangle b", triangle.b));
    require(detail::non_finite_reason("triangle c", triangle.c));
    const std::optional<mpq_class> t = exact_t(x, exact_direction(direction), triangle);
    return t && in_interval(*t, detail::exact::rational_from_double(interval.t_min), interval.t_min_included);
  });
}

std::vector<std::uint32_t> first_hits_exact(const HitPoint& from, const Triangle& source, const Vec3& direction,
                                            const Mesh& mesh, const SecondaryInterval& interval,
                                            std::optional<std::uint32_t> skip) {
  return detail::in_default_fp_environment([&] {
    const Q3 x = start_point(from, source, direction, interval);
    require(validate(mesh));
    const StartBox box = start_box(x);
    const std::array<double, 3> w{direction.x, direction.y, direction.z};
    const std::array<Exact, 3> w_exact = exact_direction(direction);
    const mpq_class t_min = detail::exact::rational_from_double(interval.t_min);
    std::vector<std::uint32_t> first;
    mpq_class best;
    for (std::uint32_t k = 0; k < mesh.triangles.size(); ++k) {
      if (skip && *skip == k) continue;
      const Triangle tri = mesh.triangle(k);
      if (!may_meet(box, w, tri)) continue;
      const std::optional<mpq_class> t = exact_t(x, w_exact, tri);
      if (!t || !in_interval(*t, t_min, interval.t_min_included)) continue;
      const int c = first.empty() ? -1 : cmp(*t, best);
      if (c < 0) {
        first.assign(1, k);
        best = *t;
      } else if (c == 0) {
        first.push_back(k);
      }
    }
    return first;
  });
}

}  // namespace raykernel
