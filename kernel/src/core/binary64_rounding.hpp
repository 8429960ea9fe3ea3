// The rounding of an exact rational to binary64 (docs/contract.md §1): to nearest, ties to even, gradual
// underflow (a nonzero value that rounds to zero keeps its sign), overflow to ±inf. MPFR in an emulated
// binary64 (precision 53, exponent range [-1073, 1024], mpfr_subnormalize): one correct rounding.
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

// Sets MPFR's exponent range to binary64's for the lifetime of the object (MPFR keeps it per thread).
class Binary64ExponentRangeGuard {
 public:
  Binary64ExponentRangeGuard() : emin_(mpfr_get_emin()), emax_(mpfr_get_emax()) {
    // MPFR's significands are in [1/2, 1): binary64's normal range [2^-1022, 2^1024) is exponents
    // [-1021, 1024], and with 53-bit precision the subnormals reach down to 2^-1074 = 1/2 · 2^-1073.
    mpfr_set_emin(-1073);
    mpfr_set_emax(1024);
  }
  ~Binary64ExponentRangeGuard() {
    mpfr_set_emin(emin_);
    mpfr_set_emax(emax_);
  }
  Binary64ExponentRangeGuard(const Binary64ExponentRangeGuard&) = delete;
  Binary64ExponentRangeGuard& operator=(const Binary64ExponentRangeGuard&) = delete;

 private:
  mpfr_exp_t emin_, emax_;
};

// RN(q) in binary64 with ties to even, gradual underflow (sign kept) and overflow to ±inf.
[[nodiscard]] inline double round_rational_to_nearest_even(const mpq_class& q) {
  const Binary64ExponentRangeGuard range;
  mpfr_t x;
  mpfr_init2(x, std::numeric_limits<double>::digits);
  int ternary = mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDN);
  ternary = mpfr_subnormalize(x, ternary, MPFR_RNDN);
  const double rounded = mpfr_get_d(x, MPFR_RNDN);  // exact: x is now a binary64 value or ±0 or ±inf
  mpfr_clear(x);
  return rounded;
}

}  // namespace raykernel::detail::exact
