// The ray–triangle error constants (kernel/src/core/error_bounds.hpp), recomputed from their formulas in
// exact rationals, and checked against the inequalities their derivations (proofs/triangle/TriangleFilter.v,
// proofs/triangle/TriangleCompensated.v) need. A constant edited by one ulp, or a derivation that stops covering its
// constant, fails here. (proofs_constants_match checks the same numbers against proofs/core/Constants.v.)
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
const mpq_class eta = pow2(-1075);
mpq_class exact(double x) { return mpq_class(x); }

TEST(TriangleConstants, AbsoluteTerm) {
  EXPECT_EQ(exact(b::triangle_absolute_scale), 32 * eta);
  EXPECT_EQ(exact(b::triangle_absolute), 64 * eta);
  // (1 − u)(A − η) with A ≥ (1 − u)(K_A(1 − u)³Σ − η + U_A) must cover the largest absolute part, stage 2's
  // den: 25η·Σ + 49η (coefficients of Σ and of 1 separately).
  const mpq_class one_minus = 1 - u;
  const mpq_class sigma_coefficient = one_minus * one_minus * exact(b::triangle_absolute_scale) * one_minus * one_minus * one_minus;
  const mpq_class constant = one_minus * (one_minus * (exact(b::triangle_absolute) - eta) - eta);
  EXPECT_GE(sigma_coefficient, 25 * eta);
  EXPECT_GE(constant, 49 * eta);
}

TEST(TriangleConstants, Filter) {
  EXPECT_EQ(exact(b::triangle_filter_pi_relative), 8 * u);
  EXPECT_EQ(exact(b::triangle_filter_num_relative), 9 * u);
  EXPECT_EQ(exact(b::triangle_filter_den_relative), 10 * u);
  // α ≤ C(1 − u)², with the proofs' α: 7u + 60u² (π), 8u + 60u² (num), (u + (u + 7u + 60u²)(1 + u))(1 + u) (den).
  const mpq_class sq = (1 - u) * (1 - u);
  EXPECT_LE(7 * u + 60 * u * u, exact(b::triangle_filter_pi_relative) * sq);
  EXPECT_LE(8 * u + 60 * u * u, exact(b::triangle_filter_num_relative) * sq);
  EXPECT_LE((u + (u + 7 * u + 60 * u * u) * (1 + u)) * (1 + u), exact(b::triangle_filter_den_relative) * sq);
  // And 7u, 8u, 9u themselves (the first-order terms) would not do: the constants are not much too large.
  EXPECT_GT(7 * u + 60 * u * u, 7 * u * sq);
}

TEST(TriangleConstants, Compensated) {
  EXPECT_EQ(exact(b::triangle_compensated_relative), 128 * u * u);
  EXPECT_EQ(exact(b::triangle_compensated_den_relative), 256 * u * u);
  const mpq_class sq = (1 - u) * (1 - u);
  EXPECT_LE(80 * u * u, exact(b::triangle_compensated_relative) * sq);
  // den: two double-double sums of the π enclosures (α 80u², λ 13u): α' = (α + u² + (u(1+u) + u)λ)(1 + u) twice.
  const mpq_class a1 = (80 * u * u + u * u + (u * (1 + u) + u) * 13 * u) * (1 + u);
  const mpq_class l1 = (1 + u) * ((1 + u) * 13 * u + u) * (1 + u);
  const mpq_class a2 = (a1 + u * u + (u * (1 + u) + u) * l1) * (1 + u);
  EXPECT_LE(a2, exact(b::triangle_compensated_den_relative) * sq);
  EXPECT_GT(a2, exact(b::triangle_compensated_relative) * sq) << "den needs its own, larger constant";
}

}  // namespace
}  // namespace raykernel
