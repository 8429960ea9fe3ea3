// An independent oracle for docs/contract.md §6, sharing no code with the kernel: every value straight from the
// contract's definitions in GMP rationals (π(p, q) = d·((p − o) × (q − o)) literally, N = (b − a) × (c − a),
// den = d·N, num = (a − o)·N), the location, rules and tie-breaks as the contract words them, and each quotient
// rounded by integer division (oracle.hpp), not by MPFR.
#pragma once

#include "support/oracle.hpp"

#include <raykernel/triangle.hpp>

#include <gmpxx.h>

#include <array>
#include <limits>
#include <string>

namespace raykernel::test_support {

struct Q3 {
  mpq_class x, y, z;
};
inline Q3 q3(const Vec3& v) { return {mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)}; }
inline Q3 operator-(const Q3& a, const Q3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Q3 cross(const Q3& a, const Q3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline mpq_class dot(const Q3& a, const Q3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct TriangleOracle {
  mpq_class pi_a, pi_b, pi_c, den, num;
  Q3 normal;
  TriangleIntersection answer;  // under the rule given to the oracle
};

// π(p, q) for the ray (o, d).
inline mpq_class edge_value(const Q3& o, const Q3& d, const Q3& p, const Q3& q) { return dot(d, cross(p - o, q - o)); }

// The owned rule's sign for π(p, q): its sign, or the first nonzero component of d × (q − p).
inline int owned_sign_of(const mpq_class& pi, const Q3& d, const Q3& p, const Q3& q) {
  if (sgn(pi) != 0) return sgn(pi);
  const Q3 t = cross(d, q - p);
  if (sgn(t.x) != 0) return sgn(t.x);
  if (sgn(t.y) != 0) return sgn(t.y);
  return sgn(t.z);
}

inline TriangleOracle triangle_oracle(const Ray& ray, const Triangle& tri, TriangleRule rule) {
  const Q3 o = q3(ray.origin), d = q3(ray.direction), a = q3(tri.a), b = q3(tri.b), c = q3(tri.c);
  TriangleOracle r;
  r.normal = cross(b - a, c - a);
  r.den = dot(d, r.normal);
  r.num = dot(a - o, r.normal);
  r.pi_a = edge_value(o, d, b, c);
  r.pi_b = edge_value(o, d, c, a);
  r.pi_c = edge_value(o, d, a, b);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.answer = {TriangleRelation::miss, TriangleLocation::none, false, nan, {nan, nan, nan}};
  if (sgn(r.den) == 0) {
    const bool degenerate = sgn(r.normal.x) == 0 && sgn(r.normal.y) == 0 && sgn(r.normal.z) == 0;
    r.answer.relation = degenerate             ? TriangleRelation::degenerate
                        : sgn(r.num) == 0      ? TriangleRelation::coplanar
                                               : TriangleRelation::parallel;
    return r;
  }
  const int s = sgn(r.den);
  const int sa = sgn(r.pi_a), sb = sgn(r.pi_b), sc = sgn(r.pi_c);
  TriangleLocation loc;
  if (sa == -s || sb == -s || sc == -s) loc = TriangleLocation::outside;
  else if (sb == 0 && sc == 0) loc = TriangleLocation::vertex_a;
  else if (sc == 0 && sa == 0) loc = TriangleLocation::vertex_b;
  else if (sa == 0 && sb == 0) loc = TriangleLocation::vertex_c;
  else if (sc == 0) loc = TriangleLocation::edge_ab;
  else if (sa == 0) loc = TriangleLocation::edge_bc;
  else if (sb == 0) loc = TriangleLocation::edge_ca;
  else loc = TriangleLocation::inside;
  const bool owned = owned_sign_of(r.pi_a, d, b, c) == s && owned_sign_of(r.pi_b, d, c, a) == s &&
                     owned_sign_of(r.pi_c, d, a, b) == s;
  const bool through = rule == TriangleRule::owned ? owned : loc != TriangleLocation::outside;
  const mpq_class t = r.num / r.den;
  r.answer.location = loc;
  r.answer.owned = owned;
  r.answer.relation = !through ? TriangleRelation::miss : (t >= 0 ? TriangleRelation::hit : TriangleRelation::behind);
  r.answer.t = round_by_integer_division(t);
  r.answer.barycentric = {round_by_integer_division(r.pi_a / r.den), round_by_integer_division(r.pi_b / r.den),
                          round_by_integer_division(r.pi_c / r.den)};
  return r;
}

// The same answer, bit for bit (NaN where NaN).
inline bool same_triangle_answer(const TriangleIntersection& x, const TriangleIntersection& y) {
  auto same = [](double p, double q) { return (std::isnan(p) && std::isnan(q)) || same_bits(p, q); };
  return x.relation == y.relation && x.location == y.location && x.owned == y.owned && same(x.t, y.t) &&
         same(x.barycentric[0], y.barycentric[0]) && same(x.barycentric[1], y.barycentric[1]) &&
         same(x.barycentric[2], y.barycentric[2]);
}

inline std::string describe(const TriangleIntersection& x) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %s owned=%d t=%a u=(%a, %a, %a)", std::string(to_string(x.relation)).c_str(),
                std::string(to_string(x.location)).c_str(), x.owned ? 1 : 0, x.t, x.barycentric[0], x.barycentric[1],
                x.barycentric[2]);
  return buf;
}

}  // namespace raykernel::test_support
