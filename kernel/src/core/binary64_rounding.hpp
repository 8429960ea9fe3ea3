// The rounding of an exact rational to binary64 (docs/contract.md §1): to nearest, ties to even, gradual
// underflow (a nonzero value that rounds to zero keeps its sign), overflow to ±inf. MPFR in an emulated
// binary64 (precision 53, exponent range [-1073, 1024], mpfr_subnormalize): one correct rounding. The same
// for binary32 (the origins of spawn, §9) and in the directed modes.
// mpq_get_d and CGAL::to_double truncate and are never used.
//
// The one home of that rounding: the exact ray–plane stage and round_rational_to_double (exact_rational.cpp),
// the exact ray–triangle stage (exact_triangle.cpp). MPFR keeps its exponent range per thread
// (mpfr_buildopt_tls_p() is true in Debian's build, checked in tests/exact_rounding_test.cpp).
#pragma once

#include <gmpxx.h>
#include <mpfr.h>

#include <limits>

namespace raykernel::detail::exact {

// A binary interchange format as MPFR emulates it: the precision, and the exponent range of MPFR's
// significands in [1/2, 1). binary64's normal range [2^-1022, 2^1024) is exponents [-1021, 1024], and with 53
// bits the subnormals reach down to 2^-1074 = 1/2 · 2^-1073; binary32's [2^-126, 2^128) is [-125, 128], its
// subnormals down to 2^-149 = 1/2 · 2^-148.
struct BinaryFormat {
  mpfr_prec_t precision;
  mpfr_exp_t emin, emax;
};
inline constexpr BinaryFormat binary64_format{53, -1073, 1024};
inline constexpr BinaryFormat binary32_format{24, -148, 128};

// An MPFR number of a given precision, freed on scope exit.
class MpfrNumber {
 public:
  explicit MpfrNumber(mpfr_prec_t precision) { mpfr_init2(x_, precision); }
  ~MpfrNumber() { mpfr_clear(x_); }
  MpfrNumber(const MpfrNumber&) = delete;
  MpfrNumber& operator=(const MpfrNumber&) = delete;
  [[nodiscard]] mpfr_ptr get() { return x_; }

 private:
  mpfr_t x_;
};

// Sets MPFR's exponent range to a format's for the lifetime of the object (MPFR keeps it per thread).
class ExponentRangeGuard {
 public:
  explicit ExponentRangeGuard(const BinaryFormat& format) : emin_(mpfr_get_emin()), emax_(mpfr_get_emax()) {
    mpfr_set_emin(format.emin);
    mpfr_set_emax(format.emax);
  }
  ~ExponentRangeGuard() {
    mpfr_set_emin(emin_);
    mpfr_set_emax(emax_);
  }
  ExponentRangeGuard(const ExponentRangeGuard&) = delete;
  ExponentRangeGuard& operator=(const ExponentRangeGuard&) = delete;

 private:
  mpfr_exp_t emin_, emax_;
};

// q rounded once to `format` in `mode` (MPFR_RNDN: nearest, ties to even; MPFR_RNDU, MPFR_RNDD: towards +inf,
// −inf), with gradual underflow (a nonzero value that rounds to zero keeps its sign) and IEEE overflow (to ±inf
// when the mode rounds away from zero, else to the largest finite value). Returned as a double, exactly (every
// binary32 value is a double). `exact`, when given, says whether the rounded value is q itself.
[[nodiscard]] inline double round_rational(const mpq_class& q, const BinaryFormat& format, mpfr_rnd_t mode,
                                           bool* exact = nullptr) {
  const ExponentRangeGuard range(format);
  mpfr_t x;
  mpfr_init2(x, format.precision);
  int ternary = mpfr_set_q(x, q.get_mpq_t(), mode);
  ternary = mpfr_subnormalize(x, ternary, mode);
  if (exact != nullptr) *exact = ternary == 0;
  const double rounded = mpfr_get_d(x, MPFR_RNDN);  // exact: x is a value of the format, or ±0 or ±inf
  mpfr_clear(x);
  return rounded;
}

// RN(q) in binary64 with ties to even, gradual underflow (sign kept) and overflow to ±inf.
[[nodiscard]] inline double round_rational_to_nearest_even(const mpq_class& q) {
  return round_rational(q, binary64_format, MPFR_RNDN);
}

}  // namespace raykernel::detail::exact
