// Test oracles that do not share code with the kernel: exact rationals straight from GMP, and a correct
// rounding of a rational to binary64 by integer division (independent of the MPFR rounding under test).
#pragma once

#include <raykernel/raykernel.hpp>

#include <gmpxx.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace raykernel::test_support {

inline mpq_class to_mpq(const Rational& r) {
  mpq_class q(mpz_class(r.numerator), mpz_class(r.denominator));
  q.canonicalize();
  return q;
}

// Exact value of a double (mpq_set_d is exact in the default floating-point environment).
inline mpq_class to_mpq(double x) { return mpq_class(x); }

// den = d·n and num = (p − o)·n, exactly.
struct ExactTerms {
  mpq_class num, den;
};
inline ExactTerms exact_terms(const Ray& r, const Plane& p) {
  auto q = [](double x) { return mpq_class(x); };
  const Vec3 &o = r.origin, &d = r.direction, &pt = p.point, &n = p.normal;
  return {(q(pt.x) - q(o.x)) * q(n.x) + (q(pt.y) - q(o.y)) * q(n.y) + (q(pt.z) - q(o.z)) * q(n.z),
          q(d.x) * q(n.x) + q(d.y) * q(n.y) + q(d.z) * q(n.z)};
}

// Whether |q| lies in (2^e + ulp/4, 2^e + ulp/2) for the ulp of [2^e, 2^(e+1)): it rounds down to 2^e, where the gap
// below is half the gap above (the testkit's above-power-of-two kinds).
inline bool just_above_power_of_two(mpq_class q) {
  q = abs(q);
  if (q == 0) return false;
  while (q < 1) q *= 2;
  while (q >= 2) q /= 2;
  const mpq_class excess = q - 1;
  return excess > mpq_class(1, mpz_class(1) << 54) && excess < mpq_class(1, mpz_class(1) << 53);
}

// RN(q), ties to even, gradual underflow, overflow to ±inf; a nonzero q that rounds to 0 keeps its sign.
// By integer division: q = I·2^k + rest with the quantum 2^k of q's binade (or 2^-1074 below 2^-1022).
inline double round_by_integer_division(const mpq_class& q) {
  if (q == 0) return 0.0;
  const bool negative = q < 0;
  const mpz_class num = abs(q.get_num()), den = q.get_den();
  // e = floor(log2 |q|): start from the bit lengths and correct by one.
  long e = static_cast<long>(mpz_sizeinbase(num.get_mpz_t(), 2)) - static_cast<long>(mpz_sizeinbase(den.get_mpz_t(), 2));
  auto at_least_power = [&](long k) {  // |q| ≥ 2^k ?
    mpz_class l = num, r = den;
    if (k >= 0) r <<= static_cast<mp_bitcnt_t>(k); else l <<= static_cast<mp_bitcnt_t>(-k);
    return l >= r;
  };
  if (!at_least_power(e)) --e;
  double magnitude;
  if (e >= 1024) {
    magnitude = std::numeric_limits<double>::infinity();
  } else {
    const long k = (e >= -1022 ? e : -1022) - 52;  // quantum exponent
    mpz_class scaled_num = num, scaled_den = den;  // |q| / 2^k
    if (k >= 0) scaled_den <<= static_cast<mp_bitcnt_t>(k); else scaled_num <<= static_cast<mp_bitcnt_t>(-k);
    mpz_class integer, rest;
    mpz_fdiv_qr(integer.get_mpz_t(), rest.get_mpz_t(), scaled_num.get_mpz_t(), scaled_den.get_mpz_t());
    const int half = cmp(2 * rest, scaled_den);
    if (half > 0 || (half == 0 && mpz_odd_p(integer.get_mpz_t()))) ++integer;
    // integer ≤ 2^53: exact as a double; ldexp is exact or overflows to inf as RN would.
    magnitude = std::ldexp(integer.get_d(), static_cast<int>(k));
  }
  return negative ? -magnitude : magnitude;
}

inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// The answer docs/contract.md §1 requires, from the exact oracle above.
inline Intersection contract_answer(const Ray& r, const Plane& p) {
  const ExactTerms e = exact_terms(r, p);
  const int sn = sgn(e.num), sd = sgn(e.den);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (sd == 0) return {sn == 0 ? Relation::in_plane : Relation::parallel, nan};
  const Relation rel = (sn == 0 || sn == sd) ? Relation::hit : Relation::behind;
  return {rel, round_by_integer_division(e.num / e.den)};
}

inline bool same_answer(const Intersection& a, const Intersection& b) {
  if (a.relation != b.relation) return false;
  if (a.relation == Relation::parallel || a.relation == Relation::in_plane) return std::isnan(a.t) && std::isnan(b.t);
  return same_bits(a.t, b.t);
}

inline std::string describe(const Intersection& x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, " %a", x.t);
  return std::string(to_string(x.relation)) + buf;
}

}  // namespace raykernel::test_support
