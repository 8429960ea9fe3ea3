// The exact stage's rounding of a rational to binary64 (MPFR in an emulated binary64) against an
// independent rounding by integer division (tests/support/oracle.hpp), on seeded random rationals that aim
// at the hard spots: ties, near ties, binade boundaries, the subnormal range and the overflow threshold.
#include "support/oracle.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace raykernel {
namespace {

using test_support::round_by_integer_division;
using test_support::same_bits;

double round_with_kernel(const mpq_class& q) {
  return round_rational_to_double(q.get_num().get_str(), q.get_den().get_str());
}

void expect_rounds_alike(const mpq_class& q) {
  const double kernel = round_with_kernel(q);
  const double oracle = round_by_integer_division(q);
  EXPECT_TRUE(same_bits(kernel, oracle)) << q.get_str() << ": kernel " << std::hexfloat << kernel << ", oracle " << oracle;
}

TEST(ExactRounding, MpfrKeepsItsExponentRangePerThread) {
  // The exact stage changes MPFR's exponent range for the duration of one rounding; that is only safe with
  // several threads when MPFR keeps it in thread-local storage.
  EXPECT_TRUE(mpfr_buildopt_tls_p());
}

TEST(ExactRounding, LeavesMpfrsExponentRangeAsItFoundIt) {
  const mpfr_exp_t emin = mpfr_get_emin(), emax = mpfr_get_emax();
  (void)round_rational_to_double("1", "3");
  EXPECT_EQ(mpfr_get_emin(), emin);
  EXPECT_EQ(mpfr_get_emax(), emax);
}

TEST(ExactRounding, HandDerivedValues) {
  EXPECT_EQ(round_rational_to_double("1", "10"), 0x1.999999999999ap-4);  // RN(0.1) rounds up
  EXPECT_EQ(round_rational_to_double("1", "3"), 0x1.5555555555555p-2);
  EXPECT_EQ(round_rational_to_double("-2", "3"), -0x1.5555555555555p-1);
  EXPECT_EQ(round_rational_to_double("0", "7"), 0.0);
  EXPECT_FALSE(std::signbit(round_rational_to_double("0", "7")));
  // 2^-1075 ties to 0 (even); −2^-1075 to −0; 3·2^-1075 ties to 2^-1073 (even).
  const std::string two_1075 = mpz_class(mpz_class(1) << 1075).get_str();
  EXPECT_TRUE(same_bits(round_rational_to_double("1", two_1075), 0.0));
  EXPECT_TRUE(same_bits(round_rational_to_double("-1", two_1075), -0.0));
  EXPECT_EQ(round_rational_to_double("3", two_1075), 0x1p-1073);
  // 2^1024 − 2^970 (halfway above the largest double) → inf; one less → the largest double.
  const mpz_class halfway = (mpz_class(1) << 1024) - (mpz_class(1) << 970);
  EXPECT_EQ(round_rational_to_double(halfway.get_str(), "1"), std::numeric_limits<double>::infinity());
  EXPECT_EQ(round_rational_to_double(mpz_class(halfway - 1).get_str(), "1"), std::numeric_limits<double>::max());
  EXPECT_EQ(round_rational_to_double(mpz_class(-halfway).get_str(), "1"), -std::numeric_limits<double>::infinity());
}

TEST(ExactRounding, TruncatingConversionsWouldBeWrong) {
  // The pitfall the contract warns about: GMP's mpq_get_d truncates.
  const mpq_class tenth(1, 10);
  EXPECT_EQ(tenth.get_d(), 0x1.9999999999999p-4);
  EXPECT_EQ(round_with_kernel(tenth), 0x1.999999999999ap-4);
}

TEST(ExactRounding, RejectsMalformedText) {
  EXPECT_THROW((void)round_rational_to_double("1x", "3"), std::invalid_argument);
  EXPECT_THROW((void)round_rational_to_double("1", "0"), std::invalid_argument);
}

// Random rationals around the hard spots, from a seeded stream (the seed is printed on failure).
TEST(ExactRounding, AgreesWithIntegerDivisionOnHardRationals) {
  const std::uint64_t seed = 20261121;
  testkit::SplitMix64 rng(seed);
  auto random_mpz = [&](int bits) {
    mpz_class z = 0;
    for (int b = 0; b < bits; b += 64) z = (z << 64) + mpz_class(static_cast<unsigned long>(rng()));
    return mpz_class(z >> static_cast<mp_bitcnt_t>((bits + 63) / 64 * 64 - bits));
  };
  SCOPED_TRACE("seed " + std::to_string(seed));
  for (int i = 0; i < 40000; ++i) {
    const int exponent = static_cast<int>(rng() % 2300) - 1150;  // |q| from 2^-1150 to 2^1150
    mpq_class q;
    switch (i % 4) {
      case 0: {  // a random rational with random sizes
        q = mpq_class(random_mpz(1 + static_cast<int>(rng() % 200)) + 1, random_mpz(1 + static_cast<int>(rng() % 200)) + 1);
        break;
      }
      case 1: {  // an exact midpoint: odd 54-bit integer
        q = mpq_class(random_mpz(53) | (mpz_class(1) << 53) | 1);
        break;
      }
      case 2: {  // a near midpoint: odd 54-bit integer ± 2^-k
        const int k = 1 + static_cast<int>(rng() % 100);
        mpq_class delta(1, mpz_class(1) << static_cast<mp_bitcnt_t>(k));
        q = mpq_class(random_mpz(53) | (mpz_class(1) << 53) | 1) + (rng() & 1 ? delta : mpq_class(-delta));
        break;
      }
      default: {  // a 53-bit integer ± tiny: next to a representable value
        const int k = 1 + static_cast<int>(rng() % 100);
        q = mpq_class(random_mpz(53) | (mpz_class(1) << 52)) + mpq_class(rng() & 1 ? 1 : -1, mpz_class(1) << static_cast<mp_bitcnt_t>(k));
        break;
      }
    }
    q.canonicalize();
    if (exponent >= 0) q *= mpq_class(mpz_class(1) << static_cast<mp_bitcnt_t>(exponent));
    else q /= mpq_class(mpz_class(1) << static_cast<mp_bitcnt_t>(-exponent));
    if (rng() & 1) q = -q;
    expect_rounds_alike(q);
    if (HasFailure()) return;
  }
}

}  // namespace
}  // namespace raykernel
