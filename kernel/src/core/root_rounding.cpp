// U ± √V rounded once (core/root_rounding.hpp).
#include "core/root_rounding.hpp"

#include <gmpxx.h>
#include <mpfr.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <stdexcept>

namespace raykernel::detail::exact {
namespace {

// √v when v ≥ 0 is the square of a rational.
std::optional<mpq_class> rational_sqrt(const mpq_class& v) {
  if (!mpz_perfect_square_p(v.get_num_mpz_t()) || !mpz_perfect_square_p(v.get_den_mpz_t())) return std::nullopt;
  mpz_class n, d;
  mpz_sqrt(n.get_mpz_t(), v.get_num_mpz_t());
  mpz_sqrt(d.get_mpz_t(), v.get_den_mpz_t());
  return mpq_class(n, d);  // lowest terms already: the roots of coprime squares are coprime
}


bool same_double(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// U + root·√V, V > 0 not the square of a rational (the value is irrational), rounded once to the format in the
// mode (MPFR_RNDN, MPFR_RNDU, MPFR_RNDD).
double round_irrational_root(const mpq_class& u, const mpq_class& v, int root, const BinaryFormat& format,
                             mpfr_rnd_t mode) {
  for (mpfr_prec_t precision = 128; precision <= (mpfr_prec_t{1} << 24); precision *= 2) {
    MpfrNumber u_lo(precision), u_hi(precision), v_lo(precision), v_hi(precision), s_lo(precision), s_hi(precision),
        lo(precision), hi(precision);
    mpfr_set_q(u_lo.get(), u.get_mpq_t(), MPFR_RNDD);
    mpfr_set_q(u_hi.get(), u.get_mpq_t(), MPFR_RNDU);
    mpfr_set_q(v_lo.get(), v.get_mpq_t(), MPFR_RNDD);
    mpfr_set_q(v_hi.get(), v.get_mpq_t(), MPFR_RNDU);
    mpfr_sqrt(s_lo.get(), v_lo.get(), MPFR_RNDD);  // s_lo ≤ √V ≤ s_hi
    mpfr_sqrt(s_hi.get(), v_hi.get(), MPFR_RNDU);
    if (root < 0) {
      mpfr_sub(lo.get(), u_lo.get(), s_hi.get(), MPFR_RNDD);
      mpfr_sub(hi.get(), u_hi.get(), s_lo.get(), MPFR_RNDU);
    } else {
      mpfr_add(lo.get(), u_lo.get(), s_lo.get(), MPFR_RNDD);
      mpfr_add(hi.get(), u_hi.get(), s_hi.get(), MPFR_RNDU);
    }
    // lo ≤ root ≤ hi, both finite (the default exponent range holds every value here): rounding is monotonic,
    // so when both ends round to the same value, so does the root.
    mpq_class q_lo, q_hi;
    mpfr_get_q(q_lo.get_mpq_t(), lo.get());
    mpfr_get_q(q_hi.get_mpq_t(), hi.get());
    const double a = round_rational(q_lo, format, mode), b = round_rational(q_hi, format, mode);
    if (same_double(a, b)) return a;
  }
  throw std::logic_error("raykernel: root rounding: no rounding decided at 2^24 bits");  // unreachable
}

}  // namespace

double round_root(const mpq_class& u, const mpq_class& v, int root, const BinaryFormat& format, mpfr_rnd_t mode,
                  bool* exact) {
  if (const std::optional<mpq_class> s = rational_sqrt(v))
    return round_rational(root < 0 ? mpq_class(u - *s) : mpq_class(u + *s), format, mode, exact);  // exact 0: +0
  if (exact != nullptr) *exact = false;
  return round_irrational_root(u, v, root, format, mode);
}

}  // namespace raykernel::detail::exact
