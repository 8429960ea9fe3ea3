// Every error constant in kernel/src/core/error_bounds.hpp, recomputed from its formula in exact
// rational arithmetic, and checked against the inequality its derivation needs. A constant edited by one
// ulp, or a derivation that no longer covers its constant, fails here. (The proofs check the same numbers:
// proofs/README.md.)
#include "core/error_bounds.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

namespace raykernel {
namespace {

namespace b = detail::bounds;

mpq_class pow2(int e) {
  mpq_class q(1);
  if (e >= 0) q *= mpq_class(mpz_class(1) << static_cast<mp_bitcnt_t>(e));
  else q /= mpq_class(mpz_class(1) << static_cast<mp_bitcnt_t>(-e));
  return q;
}
const mpq_class u = pow2(-53);
const mpq_class mu = pow2(-1074);  // smallest subnormal
const mpq_class eta = pow2(-1075);
mpq_class power(const mpq_class& x, int n) {
  mpq_class r(1);
  for (int i = 0; i < n; ++i) r *= x;
  return r;
}
mpq_class gamma(int n) { return n * u / (1 - n * u); }
mpq_class exact(double x) { return mpq_class(x); }

TEST(ErrorConstants, UnitsAreTheBinary64Ones) {
  EXPECT_EQ(exact(b::unit_roundoff), u);
  EXPECT_EQ(exact(b::min_subnormal), mu);
}

TEST(ErrorConstants, FilterDen) {
  EXPECT_EQ(exact(b::filter_den_relative), (3 + 16 * u) * u);
  // Needed: C ≥ (3u + u²)(1+u)^4.
  EXPECT_GE(exact(b::filter_den_relative), (3 * u + u * u) * power(1 + u, 4));
}

TEST(ErrorConstants, FilterNum) {
  EXPECT_EQ(exact(b::filter_num_relative), (4 + 32 * u) * u);
  // Needed: C ≥ (4u + 2u²)(1+u)^4.
  EXPECT_GE(exact(b::filter_num_relative), (4 * u + 2 * u * u) * power(1 + u, 4));
}

TEST(ErrorConstants, FilterAbsolute) {
  EXPECT_EQ(exact(b::filter_absolute), 3 * mu);
  // Needed: (U − η)/(1+u) ≥ 3(1+u)η (num's absolute term, the larger).
  EXPECT_GE((exact(b::filter_absolute) - eta) / (1 + u), 3 * (1 + u) * (1 + u) * eta);
}

TEST(ErrorConstants, Compensated) {
  EXPECT_EQ(exact(b::compensated_relative), 32 * u * u);
  EXPECT_EQ(exact(b::compensated_absolute), 16 * mu);
  // Needed: K ≥ (γ_4(4u + 6u²) + 2u²)(1+u)^4 and (U − η)/(1+u) ≥ 6.1η.
  EXPECT_GE(exact(b::compensated_relative), (gamma(4) * (4 * u + 6 * u * u) + 2 * u * u) * power(1 + u, 4));
  EXPECT_GE((exact(b::compensated_absolute) - eta) / (1 + u), mpq_class(61, 10) * eta);
}

TEST(ErrorConstants, CompensatedRefined) {
  EXPECT_EQ(exact(b::refined_relative), 512 * u * u * u);
  EXPECT_EQ(exact(b::refined_low_relative), 2 * u);
  EXPECT_EQ(exact(b::refined_absolute), 8 * mu);
  // Needed: K_2 ≥ 262.1u³(1+u)^4 (γ_9 times the first-order and second-order terms), 2^-52 ≥ u(1+u)², and
  // (U_2 − 2η)/(1+u) ≥ 6.1η.
  EXPECT_GE(exact(b::refined_relative), mpq_class(2621, 10) * u * u * u * power(1 + u, 4));
  EXPECT_LE(gamma(9) * (mpq_class(2911, 100) * u * u), mpq_class(2621, 10) * u * u * u);  // the 262.1 itself
  EXPECT_GE(exact(b::refined_low_relative), u * power(1 + u, 2));
  EXPECT_GE((exact(b::refined_absolute) - 2 * eta) / (1 + u), mpq_class(61, 10) * eta);
}

TEST(ErrorConstants, TailSum) {
  EXPECT_EQ(exact(b::tail_sum_relative), pow2(-48));
  EXPECT_EQ(exact(b::tail_sum_absolute), 2 * mu);
  // Summing k − 1 ≤ 31 terms: γ_30·(1+u)^30 < 2^-48.
  EXPECT_EQ(b::tail_sum_max_terms, 32);
  EXPECT_LT(gamma(b::tail_sum_max_terms - 2) * power(1 + u, b::tail_sum_max_terms - 2), exact(b::tail_sum_relative));
}

TEST(ErrorConstants, RoundQuotient) {
  EXPECT_EQ(exact(b::quotient_min_magnitude), pow2(-900));
  EXPECT_EQ(exact(b::quotient_relative), pow2(-101));
  EXPECT_EQ(exact(b::quotient_enclosure_factor), 1 + pow2(-9));
  EXPECT_EQ(exact(b::quotient_test_factor), 1 + pow2(-45));
  // The |q0|-proportional part of rad: 3.02u(u + ρ_d)ϕ + 3.01u² + 6.02u²ϕ with ρ_d ≤ 2^-50,
  // ϕ = 1/(1 − u − 2^-50); the ρ_d-proportional part must fit the enclosure factor.
  const mpq_class phi = 1 / (1 - u - pow2(-50));
  const mpq_class constant_part = mpq_class(302, 100) * u * u * phi + mpq_class(301, 100) * u * u +
                                  mpq_class(602, 100) * u * u * phi + pow2(-170);
  EXPECT_LE(constant_part, exact(b::quotient_relative));
  EXPECT_LE(phi * (1 + mpq_class(302, 100) * u), exact(b::quotient_enclosure_factor));
  // Six roundings on the left side of the test: (1+u)^6 ≤ 1 + 2^-45.
  EXPECT_LE(power(1 + u, 6), exact(b::quotient_test_factor));
}

// The comparison of two quotients (error_bounds.hpp, "Comparing two quotients").
TEST(ErrorConstants, CompareQuotientsFilter) {
  EXPECT_EQ(exact(b::compare_filter_relative), (2 + 16 * u) * u);
  EXPECT_EQ(exact(b::compare_propagation_factor), 1 + 16 * u);
  EXPECT_EQ(exact(b::compare_absolute), 8 * mu);
  const mpq_class cf = exact(b::compare_filter_relative), cp = exact(b::compare_propagation_factor);
  const mpq_class uc = exact(b::compare_absolute);
  // Needed: C_f ≥ 2u(1+u)^4, C_p ≥ (1+u)^7, U_c/(1+u) ≥ 2η + (2η + 4C_p·η/(1+u)^3)/(1+u)^2.
  EXPECT_GE(cf, 2 * u * power(1 + u, 4));
  EXPECT_GE(cp, power(1 + u, 7));
  EXPECT_GE(uc / (1 + u), 2 * eta + (2 * eta + 4 * cp * eta / power(1 + u, 3)) / power(1 + u, 2));
}

TEST(ErrorConstants, CompareQuotientsCompensated) {
  EXPECT_EQ(exact(b::compare_compensated_relative), 32 * u * u);
  const mpq_class kc = exact(b::compare_compensated_relative), cp = exact(b::compare_propagation_factor);
  const mpq_class uc = exact(b::compare_absolute);
  // The steps of the derivation, each as the inequality it claims (H, η and ρ factored out):
  // the five terms of lo: u + (2u + 3u² + u³)(1+u) + u(1+u) ≤ 4u + 7u²;
  EXPECT_LE(u + (2 * u + 3 * u * u + u * u * u) * (1 + u) + u * (1 + u), 4 * u + 7 * u * u);
  // their three roundings: (3u + 3u² + u³)(4u + 7u²) ≤ 12.01u², and on the η part (3u + ...)·8.01η ≤ 0.01η;
  EXPECT_LE((3 * u + 3 * u * u + u * u * u) * (4 * u + 7 * u * u), mpq_class(1201, 100) * u * u);
  EXPECT_LE((3 * u + 3 * u * u + u * u * u) * mpq_class(801, 100), mpq_class(1, 100));
  // in all: (4u² + u³)(1+u) + 12.01u² ≤ 16.02u² (the cross terms and α_iβ_j, π_i ≤ (1+u)|P| + η);
  EXPECT_LE((4 * u * u + u * u * u) * (1 + u) + mpq_class(1201, 100) * u * u, mpq_class(1602, 100) * u * u);
  // and (6.01 + 2u)η + 2(4u² + u³)η ≤ 6.02η.
  EXPECT_LE(mpq_class(601, 100) + 2 * u + 2 * (4 * u * u + u * u * u), mpq_class(602, 100));
  // Needed: K_c ≥ 16.02u²(1+u)^4, C_p ≥ (1+u)^8, U_c/(1+u) ≥ 6.02η + (2η + 4C_p·η/(1+u)^3)/(1+u)^2.
  EXPECT_GE(kc, mpq_class(1602, 100) * u * u * power(1 + u, 4));
  EXPECT_GE(cp, power(1 + u, 8));
  EXPECT_GE(uc / (1 + u), mpq_class(602, 100) * eta + (2 * eta + 4 * cp * eta / power(1 + u, 3)) / power(1 + u, 2));
}

}  // namespace
}  // namespace raykernel
