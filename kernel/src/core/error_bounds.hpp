// The error constants of the certified stages — ray–plane, the comparison of quotients, ray–triangle — each
// beside its derivation, its valid range and the theorem in proofs/ that certifies it. This file is the only
// place they are written; the stages include it, tests/plane_constants_test.cpp and
// tests/triangle_constants_test.cpp recompute every constant from its formula, and the proofs state their
// theorems about these exact numbers (proofs/core/Constants.v; proofs/README.md
// explains how the two are compared).
//
// Notation. Binary64, round to nearest (ties to even; the bounds hold for any tie rule).
//   u = 2^-53           unit roundoff
//   μ = 2^-1074         smallest positive subnormal
//   η = μ/2 = 2^-1075   largest absolute rounding error of a result in the subnormal range
//   ⊕ ⊖ ⊗ ⊘            rounded operations; RN(x) the rounding of the real x
// Rounding model with gradual underflow (Flocq `error_N_FLT`): RN(x) = x(1+ε) + e with |ε| ≤ u, |e| ≤ η,
// ε·e = 0. Two sharper facts are used: |RN(x) − x| ≤ u·|RN(x)| when |x| ≥ 2^-1022; and a sum or difference
// of two doubles is exact when its result is below 2^-1022 (Hauser 1996, Thm 3.4.1), so additions carry
// relative errors only.
//
// Overflow. Every stage computes its error bound from magnitudes that dominate its intermediate values;
// an overflow anywhere makes that bound or the value ±inf or NaN, and every comparison that certifies a
// result is then false. So "the bound is finite" implies "no intermediate overflowed", which is the
// hypothesis the theorems state (proofs/README.md, "Overflow").
#pragma once

namespace raykernel::detail::bounds {

inline constexpr double unit_roundoff = 0x1p-53;          // u
inline constexpr double min_subnormal = 0x0.0000000000001p-1022;  // μ = 2^-1074
inline constexpr double largest_finite = 0x1.fffffffffffffp+1023;  // |x| ≤ largest_finite ⇔ x is finite

// TwoProduct (core/eft.hpp) is exact when a·b = 0 or |a·b| ≥ 2^-969 = 2^(emin + 2p − 1) (Flocq
// `mult_error_FLT`); |a ⊗ b| ≥ 2^-968 implies |a·b| ≥ 2^-969 (a rounding moves a value by at most half an
// ulp), so the expansion stage checks the rounded product against this threshold.
// Certified by: proofs/core/Model.v, `two_prod_guard_exact`.
inline constexpr double exact_product_threshold = 0x1p-968;

// ---------------------------------------------------------------------------------------------------------
// Stage 1: dot3_filter (core/dot3_filter.hpp)
//
//   q_i = a_i ⊗ b_i,  s = (q_1 ⊕ q_2) ⊕ q_3,  m = (|q_1| ⊕ |q_2|) ⊕ |q_3|,  B = (C ⊗ m) ⊕ U;
//   s > B ⇒ a·b > 0,  s < −B ⇒ a·b < 0.
//
// Derivation (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1, with the underflow term):
// with Q = Σ|q_i|, |q_i − a_i b_i| ≤ u|q_i| + η, |s_2 − (q_1+q_2)| ≤ u|q_1+q_2|, |s − (s_2+q_3)| ≤ u(1+u)Q:
//   den = d·n exactly:            |s − a·b| ≤ (3u + u²)·Q + 3η
//   num, a_i = p_i ⊖ o_i:         |a_i − (p_i−o_i)| ≤ u|a_i| adds u(1+u)Q + 3uη:
//                                 |s − (p−o)·n| ≤ (4u + 2u²)·Q + 3(1+u)η
// and m ≥ Q/(1+u)², (C ⊗ m) ≥ C·m/(1+u) − η, so B ≥ C·m/(1+u)² + (U − η)/(1+u). Hence it suffices that
//   C_den ≥ (3u + u²)(1+u)^4 = 3u + 13u² + O(u³)      → C_den = (3 + 16u)·u  (Shewchuk's ccwerrboundA)
//   C_num ≥ (4u + 2u²)(1+u)^4 = 4u + 18u² + O(u³)     → C_num = (4 + 32u)·u
//   U ≥ η + 3(1+u)²η ≈ 4η                             → U = 3μ = 6η
// Valid for all finite inputs, including subnormal ones; uncertain (never wrong) when m overflows.
// Certified by: proofs/plane/PlaneFilter.v, theorems `den_filter_sound` and `num_filter_sound`.
inline constexpr double filter_den_relative = 0x1.8000000000004p-52;  // (3 + 16u)u
inline constexpr double filter_num_relative = 0x1.0000000000004p-51;  // (4 + 32u)u
inline constexpr double filter_absolute = 0x0.0000000000003p-1022;    // 3μ

// ---------------------------------------------------------------------------------------------------------
// Stage 2: compensated_dot3 (core/dot3_compensated.hpp)
//
// Value V = Σ (a_i + α_i)·b_i with |α_i| ≤ u|a_i| (α = 0 for den; for num a_i + α_i = p_i − o_i exactly,
// by TwoSum). With h_i = a_i ⊗ b_i (the q_i of stage 1), l_i = RN(a_i b_i − h_i) and g_i = RN(α_i b_i + l_i)
// (two FMAs), (s_2, c_2) = TwoSum(h_1, h_2), (s_3, c_3) = TwoSum(s_2, h_3):
//   hi = s_3,  lo = ((g_1 ⊕ g_2) ⊕ g_3) ⊕ (c_2 ⊕ c_3),  E = (K ⊗ m) ⊕ U  (m from stage 1),
// and the claim is |V − (hi + lo)| ≤ E. Exactly, Σ h_i = s_3 + c_2 + c_3 (TwoSum) and
// a_i b_i = h_i + l_i + λ_i with |λ_i| ≤ η (λ_i = 0 when |a_i b_i| ≥ 2^-969, Flocq `mult_error_FLT`;
// otherwise a_i b_i − h_i is subnormal). With H = Σ|h_i|:
//   |l_i| ≤ u|h_i| + η,  |α_i b_i| ≤ u(1+u)|h_i| + uη,  |g_i − (α_i b_i + l_i)| ≤ 2u²|h_i| + 1.01η,
//   |c_2| + |c_3| ≤ 2u(1+u)²H,  Σ|terms of lo| ≤ (4u + 6u²)H + 6.03η,
//   |V − hi − lo| ≤ γ_4·(4u + 6u²)H + 2u²H + 6.1η ≤ 18.1u²·H + 6.1η   (γ_n = nu/(1−nu)).
// With H ≤ (1+u)²m as in stage 1:
//   K ≥ 18.1u²(1+u)^4      → K = 32u² = 2^-101
//   U ≥ η + 6.1(1+u)η      → U = 16μ = 2^-1070
// Valid for all finite inputs; uncertain when a value or E is not finite.
// Certified by: proofs/plane/PlaneCompensated.v, theorem `compensated_dot3_enclosure`.
inline constexpr double compensated_relative = 0x1p-101;
inline constexpr double compensated_absolute = 0x1p-1070;

// Stage 2, second level: compensated_dot3_refined (core/dot3_compensated.hpp), for values that
// cancel to within ~2^-50 of the terms' magnitude (near-parallel rays, origins ulps from the plane), where
// the first level's 2^-101·m is too wide to round t. Same inputs; the low parts are no longer rounded into
// one double but summed with error-free transformations:
//   (s_2, c_2) = TwoSum(h_1, h_2), (s_3, c_3) = TwoSum(s_2, h_3), l_i = RN(a_i b_i − h_i),
//   (w_i, w'_i) = TwoProduct(α_i, b_i);  F = (c_2, c_3, l_1, l_2, l_3, w_1, w_2, w_3) summed by a TwoSum
//   chain σ_1 = F_1, (σ_j, ε_j) = TwoSum(σ_{j−1}, F_j); the errors summed plainly:
//   τ = ((((0 ⊕ ε_2) ⊕ ... ⊕ ε_8) ⊕ w'_1) ⊕ w'_2) ⊕ w'_3;  (X, Y) = TwoSum(s_3, σ_8);
//   hi = X,  lo = Y ⊕ τ,  E = ((K_2 ⊗ m) ⊕ (2^-52 ⊗ |lo|)) ⊕ U_2.
// Exactly, V = X + Y + Σε_j + Σw'_i + Σλ_i + Σλ'_i (λ, λ' the TwoProduct residuals, each ≤ η, zero
// without underflow). With H = Σ|h_i|: Σ|F| ≤ 4.01u·H + 9η; Σ|ε_j| ≤ 7(1+u)^7·u·Σ|F| ≤ 28.11u²H + 63.1uη;
// Σ|w'_i| ≤ 1.001u²H + 3.01η; the 9 roundings of τ cost ≤ γ_9·(29.11u²H + 66.2η) ≤ 262.1u³H + 596uη;
// RN(Y + τ) costs ≤ u|lo|. In all |V − (hi + lo)| ≤ 262.1u³·H + u·|lo| + 6.01η. With H ≤ (1+u)²m and the
// three roundings of E (RN(K_2 ⊗ m) ≥ K_2·m/(1+u) − η, the other two relative):
//   K_2 ≥ 262.1u³(1+u)^4      → K_2 = 512u³ = 2^-150
//   2^-52 = 2u covers u|lo|(1+u)²
//   U_2 ≥ 2η + 6.1(1+u)η      → U_2 = 8μ = 2^-1071
// Valid for all finite inputs; the radius is +inf when anything overflowed. Decides signs unless V is
// within ~2^-148 of the terms' magnitude (exact zeros go on to stage 3), and lets round_quotient decide t
// for condition numbers up to ~2^90.
// Certified by: proofs/plane/PlaneCompensated.v, theorem `compensated_dot3_refined_enclosure` (its bookkeeping is
// coarser, the TwoSum chain bounded step by step with (1+u)^7: about 283u³·H + u·|lo| + 7η, which these
// constants also cover).
inline constexpr double refined_relative = 0x1p-150;
inline constexpr double refined_low_relative = 0x1p-52;
inline constexpr double refined_absolute = 0x0.0000000000008p-1022;  // 8μ

// Sign from an enclosure |V − (hi + lo)| ≤ E: with (v, e) = TwoSum(hi, lo), |V − v| ≤ u|v| + E, so
// |v| > 2E ⇒ sign(V) = sign(v).  Certified by: proofs/plane/PlaneCompensated.v, theorem `enclosure_sign_sound`.

// ---------------------------------------------------------------------------------------------------------
// Stage 3: expansion_tail_enclosure (core/expansion.hpp)
//
// An exact expansion e_1..e_k (expansion.hpp) is condensed by one TwoSum pass (Q, r_j) = TwoSum(Q, e_{j+1}),
// which keeps its exact sum S = Q + Σ r_j. Then hi = Q, lo = RN-sum of the r_j (left to right), and
// A = RN-sum of |r_j|. Summing k−1 ≤ 31 terms: |lo − Σ r_j| ≤ γ_30·Σ|r_j| ≤ γ_30(1+u)^30·A < 2^-48·A, so
//   E = (A ⊗ 2^-48) ⊕ 2μ    (the 2μ covers the underflow of A ⊗ 2^-48, whose error is at most η).
// Certified by: proofs/plane/PlaneCompensated.v, theorem `tail_sum_enclosure`.
inline constexpr double tail_sum_relative = 0x1p-48;
inline constexpr double tail_sum_absolute = 0x0.0000000000002p-1022;  // 2μ
inline constexpr int tail_sum_max_terms = 32;

// ---------------------------------------------------------------------------------------------------------
// round_quotient (core/quotient_rounding.hpp): the correctly rounded t = num/den from enclosures
//   |num − (N + n)| ≤ E_n,  |den − (D + d)| ≤ E_d,
// where (N, n) and (D, d) are normalized pairs (the outputs of TwoSum: |n| ≤ u|N|, |d| ≤ u|D|). One
// reciprocal serves every quotient with the same denominator (prepare_divisor), so a triangle's t and its
// three barycentric coordinates share it.
//
//   R = 1 ⊘ D,  q0 = N ⊗ R,  r = RN(N − q0·D) ⊕ RN(n − q0·d)  (two FMAs),  c = r ⊗ R,
//   q = q0 ⊕ c,  w = c ⊖ (q ⊖ q0)                                (Fast2Sum: q + w = q0 + c exactly).
// Guards: |N| ≥ 2^-900, 2^-1000 ≤ |D| ≤ 2^1000, 2^-900 ≤ |q| ≤ largest_finite. Derivation, with
// X = N + n, Y = D + d, T = X/Y and the exact correction c* = T − q0 = (ρ_1 + ρ_2)/Y, ρ_1 = N − q0·D,
// ρ_2 = n − q0·d:
//   R = (1/D)(1 + δ_R) (R normal by the guard on D), q0 = (N/D)(1 + δ_R)(1 + δ_q) + η_q (N·R alone could
//   underflow under the guards on N and D; the guard |q| ≥ 2^-900 keeps η_q, like every η below, under
//   2^-170·|q0|), so
//   |ρ_1| ≤ (2u + u²)|N|, |ρ_2| ≤ u|N| + u|q0 D| ≤ (2u + 3u²)|N|, |c*| ≤ (4u + 7u²)|N/D|;
//   c = (ρ_1(1+ε_1) + ρ_2(1+ε_2) + η_1 + η_2)(1+ε_3)(1+δ_R)(1+ε_4)/D + η_4, and 1/Y = (1/D)/(1 + d/D), so
//   |c − c*| ≤ |N/D|·((4u + 3u²)(4u + 7u²) + (4u + 3u²)·u(1 + 3u)) + 2.01η/|D| + η ≤ 20.1u²·|q0|
// (the proof, bounding the residual against Y rather than D, gets 23u²·|q0|, still below 32u² = 2^-101; with
// 2^-102 = 16u² it fails),
// the η terms being below 2^-172·|q0| by the guards (|N| ≥ 2^-900 makes η/|D| ≤ 2^-175·|N/D|). With the
// Fast2Sum (exact since |c| ≤ 5u|q0|), |T − q| ≤ |w| + 20.1u²·|q0|. The enclosures add
//   |t − T| ≤ (E_n + |T|·E_d)/(|Y| − E_d) ≤ (1 + 2^-50)·(E_n + |q0|·E_d)/|D|
// once the test below holds (it implies E_d ≤ 2^-52·|D|). So
//   |t − q| ≤ |w| + 2^-101·|q0| + (1 + 2^-9)·(E_n + |q0|·E_d)/|D|                       (32u² ≥ 20.1u²)
// and q = RN(t) when this is below h, half the gap from q to its nearer neighbour: t then lies strictly
// inside q's rounding interval, so no tie can arise. The code tests, without division,
//   ((((|q0| ⊗ E_d) ⊕ E_n) ⊗ ϕ_c) ⊕ (((|q0| ⊗ 2^-101) ⊕ |w|) ⊗ |D|)) ⊗ (1 + 2^-45)  <  h ⊗ |D|,
// ϕ_c = 1 + 2^-9; the factor 1 + 2^-45 absorbs the relative errors of the six roundings of the left side,
// and their absolute (underflow) errors, which can occur when E_n or E_d is tiny, fit in the slack between
// 2^-101 and the 23u² the proof needs; h ⊗ |D| is a power of two times a double.
// Certified by: proofs/plane/QuotientRounding.v, theorem `round_quotient_sound`.
inline constexpr double quotient_min_magnitude = 0x1p-900;   // |N| and |q|
inline constexpr double divisor_min_magnitude = 0x1p-1000;   // |D|: 1/D finite
inline constexpr double divisor_max_magnitude = 0x1p+1000;   // |D|: 1/D normal
inline constexpr double quotient_relative = 0x1p-101;
inline constexpr double quotient_enclosure_factor = 0x1.008p+0;      // 1 + 2^-9
inline constexpr double quotient_test_factor = 0x1.0000000000080p+0;  // 1 + 2^-45
// half_gap_to_nearer_neighbour builds 2^(e−53) (or 2^(e−54) at a power of two) from q's exponent bits; the
// result is normal, as the proofs require, for |q| ≥ 2^-968 (the guard above keeps |q| ≥ 2^-900).
// Certified by: proofs/plane/QuotientRounding.v, `half_gap_bits`, and the test `proofs_half_gap`.
inline constexpr double half_gap_min_magnitude = 0x1p-968;

// ---------------------------------------------------------------------------------------------------------
// Comparing two quotients (nearest/compare_quotients.hpp): the order of t_1 = N_1/D_1 and t_2 = N_2/D_2
// along a ray, for nearest_hit. With D_1, D_2 ≠ 0,
//   sign(t_1 − t_2) = sign(Δ)·sign(D_1)·sign(D_2),    Δ = N_1·D_2 − N_2·D_1,
// so the predicate is the sign of Δ, a degree-2 polynomial in the four values, each known through an
// enclosure from the cascade: |N_i − x_i| ≤ e_i, |D_i − y_i| ≤ f_i. Rounded t values are never compared.
//
// Lower-bound facts used below, for a real z ≥ 0:  RN(z) ≥ z/(1+u) − η,  and RN(z) ≥ z/(1+u) when z is
// a sum of two doubles (exact below 2^-1022). Each ⊕/⊗ of non-negative values below is bounded with them.
// The propagated input error is, for i ≠ j (exactly, from N_i D_j − x_i y_j = x_i(D_j − y_j) +
// (N_i − x_i) y_j + (N_i − x_i)(D_j − y_j)):
//   |N_i D_j − x_i y_j| ≤ ρ_i := |x_i|·f_j + e_i·(|y_j| + f_j),    ρ = ρ_1 + ρ_2,
// and the code computes it as
//   R = ((|x_1| ⊗ f_2) ⊕ (e_1 ⊗ (|y_2| ⊕ f_2))) ⊕ ((|x_2| ⊗ f_1) ⊕ (e_2 ⊗ (|y_1| ⊕ f_1)))
//     ≥ ρ/(1+u)^4 − 4η/(1+u)^2.
//
// Stage 1: compare_quotients_filter, inputs x_i = s (value), e_i, f_i = (C ⊗ m) ⊕ 3μ (the stage-1 values
// and error bounds of num_i and den_i, whose enclosure |s − V| ≤ (C ⊗ m) ⊕ 3μ is proofs/plane/PlaneFilter.v's
// `den_filter_encloses` and `num_filter_encloses`):
//   P = x_1 ⊗ y_2,  Q = x_2 ⊗ y_1,  δ = P ⊖ Q,  M = |P| ⊕ |Q|,
//   B = ((C_f ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c;    δ > B ⇒ Δ > 0,  δ < −B ⇒ Δ < 0,  otherwise uncertain.
// Error: with H = |P| + |Q|, |x_1 y_2 − P| ≤ u|P| + η, |x_2 y_1 − Q| ≤ u|Q| + η, |δ − (P − Q)| ≤ uH:
//   |Δ − δ| ≤ ρ + 2u·H + 2η.
// Computed bound: M ≥ H/(1+u), so
//   B ≥ C_f·H/(1+u)^4 + C_p·ρ/(1+u)^7 + U_c/(1+u) − (2η + 4C_p·η/(1+u)^3)/(1+u)^2.
// Hence it suffices that
//   C_f ≥ 2u(1+u)^4 = 2u + 8u² + O(u³)            → C_f = (2 + 16u)·u
//   C_p ≥ (1+u)^7                                  → C_p = 1 + 16u  (shared with stage 2, which needs (1+u)^8)
//   U_c ≥ (1+u)(2 + 2 + 4C_p)η ≈ 8η                → U_c = 8μ = 16η  (shared with stage 2, which needs ≈ 12η)
// Valid for all finite inputs with e_i, f_i ≥ 0; uncertain (never wrong) when anything overflows: P, Q or
// δ overflowing makes M, hence B, +inf; a non-finite x_i, e_i or f_i makes B +inf or NaN; every
// certifying comparison is then false.
// Certified by: proofs/compare/CompareQuotients.v, theorem `compare_quotients_filter_sound`.
inline constexpr double compare_filter_relative = 0x1.0000000000004p-52;    // C_f = (2 + 16u)u
inline constexpr double compare_propagation_factor = 0x1.0000000000008p+0;  // C_p = 1 + 16u = 1 + 2^-49
inline constexpr double compare_absolute = 0x0.0000000000008p-1022;        // U_c = 8μ = 2^-1071

// Stage 2: compare_quotients_compensated, inputs the stage-2 enclosures (hi, lo, radius) of num_i, den_i.
//   (a_i, α_i) = TwoSum(N_i.hi, N_i.lo),  (b_i, β_i) = TwoSum(D_i.hi, D_i.lo)   (|α_i| ≤ u|a_i|, |β_i| ≤ u|b_i|;
//                                          e_i = N_i.radius, f_i = D_i.radius enclose N_i, D_i around a_i+α_i, b_i+β_i)
//   (P, p) = TwoProduct(a_1, b_2),  (Q, q) = TwoProduct(a_2, b_1)
//   c_1 = fma(a_1, β_2, α_1 ⊗ b_2),  c_2 = fma(a_2, β_1, α_2 ⊗ b_1)     (the cross terms; α_i β_j is dropped)
//   (S, s) = TwoSum(P, −Q),  lo = ((p ⊖ q) ⊕ (c_1 ⊖ c_2)) ⊕ s
//   M = |P| ⊕ |Q|,  R as above with x_i = a_i, y_i = b_i,
//   E = ((K_c ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c,   and the claim is the enclosure |Δ − (S + lo)| ≤ E,
// whose sign enclosure_sign decides (`enclosure_sign_sound`). Derivation, with H = |P| + |Q| and
// π_1 = |a_1 b_2| ≤ (1+u)|P| + η (π_2 likewise with Q):
//   input error: |N_1 D_2 − (a_1+α_1)(b_2+β_2)| ≤ (1+u)ρ_1, both sides: ≤ (1+u)ρ;
//   P + p = a_1 b_2 up to η (TwoProduct; exact unless a_1 b_2 underflows), S + s = P − Q exactly;
//   |α_1 β_2| ≤ u²π_1;  |c_1 − (a_1β_2 + α_1b_2)| ≤ (3u² + u³)π_1 + (2+u)η;
//   the five terms of lo sum to at most T ≤ (4u + 7u²)H + 8.01η, and their three roundings cost
//   ≤ (3u + 3u² + u³)·T ≤ 12.01u²·H + 0.01η;
//   in all |Δ − (S + lo)| ≤ (1+u)ρ + 16.02u²·H + 6.02η.
// The computed bound satisfies E ≥ K_c·H/(1+u)^4 + C_p·ρ/(1+u)^7 + U_c/(1+u) − (2η + 4C_p·η/(1+u)^3)/(1+u)^2,
// so it suffices that
//   K_c ≥ 16.02u²(1+u)^4                           → K_c = 32u² = 2^-101
//   C_p ≥ (1+u)^8 = 1 + 8u + O(u²)                 → C_p = 1 + 16u (above)
//   U_c ≥ (1+u)(6.02 + 2 + 4C_p)η ≈ 12.02η         → U_c = 8μ = 16η (above)
// Valid for all finite inputs; when a value overflows the enclosure's radius is +inf ("no information"),
// and so is E when M or R overflows. Decides the order unless t_1, t_2 agree to about 2^-100 relatively
// (or the inputs' own radii are that wide); exact ties always go on to stage 3.
// Certified by: proofs/compare/CompareQuotients.v, theorem `compare_quotients_compensated_enclosure`.
inline constexpr double compare_compensated_relative = 0x1p-101;  // K_c = 32u²

// Stage 3: compare_quotients_expansion computes Δ exactly as an expansion from the stage-3 expansions of
// num_i and den_i (expansion.hpp; proofs/core/Expansions.v, `compare_quotients_expansion_sound`): exact whenever
// the builder reports no underflowing TwoProduct and nothing non-finite, its sign checked. No constant but
// exact_product_threshold. Stage 4 (exact rationals) decides the rest.

// =========================================================================================================
// Ray–triangle (kernel/src/triangle/, docs/contract.md §6). Notation as above; in particular a sum or
// difference of two doubles has no absolute error.
//
// The values. Every value is a 3×3 determinant det(x, y, z) = x·(y × z) of leaves (ray_triangle_formula.hpp):
//   πa = d·(e_b × e_c), πb = d·(e_c × e_a), πc = d·(e_a × e_b), num = e_a·(e_b × e_c), den = (πa + πb) + πc,
// where d is an input (exact) and e_v = v − o a difference of inputs. The leaves of stage 1 are d and
// ê_v = v ⊖ o (|ê − e| ≤ u|ê|, no absolute error: a difference of doubles); the leaves of stage 2 are d and
// the exact double-doubles (h, l) = TwoDiff(v, o).
//
// Evaluation (both stages, the same operations on the high parts): for a cross component
//   P = y_j ⊗ z_k,  Q = y_k ⊗ z_j,  c = P ⊖ Q,  M = |P| ⊕ |Q|,
// then t_i = x_i ⊗ c_i with magnitude x-term m_i = |x_i| ⊗ M_i, and s = (t_0 ⊕ t_1) ⊕ t_2,
// m = (m_0 ⊕ m_1) ⊕ m_2 (den: the π's and their m's summed the same way). m is the permanent
// Σ|x_i|(|y_j z_k| + |y_k z_j|) as computed, Shewchuk's orient3d "permanent".
//
// Underflow. A product y_j ⊗ z_k that underflows errs by up to η, and the outer product multiplies that error
// by |x_i|, which may be up to 2^1024: no constant absolute term covers it. The bound therefore has a
// dynamic absolute term proportional to S = (|x_0| ⊕ |x_1|) ⊕ |x_2|,
//   A = (K_A ⊗ S) ⊕ U_A,
// computed once per vector x (d for the π's and den, e_a for num) and shared by both stages.
//
// Overflow. m dominates every intermediate in magnitude (|c_i| ≤ M_i, |t_i| ≤ m_i, |s| ≤ m, and stage 2's low
// parts are O(u)·m); an overflow anywhere makes m (or S) +inf or NaN, and then every certifying comparison
// is false. Stage 2 also folds a non-finite high or low part into an infinite radius, as compensated_dot3.
//
// The quotients t = num/den and πk/den are rounded by round_quotient (above) from the stage-2 enclosures
// (or stage 3's tail enclosures), all four over one divisor prepared once from den's enclosure.

// ---------------------------------------------------------------------------------------------------------
// The dynamic absolute term A = (K_A ⊗ S) ⊕ U_A (both stages).
//
// Derivation. Each P, Q errs by up to u|P| + η; the η's reach the value multiplied by |x_i| in the outer
// products: stage 1 carries at most 3η·Σ|x_i| + 6η (a determinant) or 9η·Σ|d_i| + 18η (den); stage 2 (the
// TwoProduct residuals and the FMAs of each cross component, then the outer FMAs) at most 8.3η·Σ|x_h| + 16η,
// or 25η·Σ|d_i| + 49η for den. With S ≥ (1−u)²·Σ|x_i| and the two roundings of A,
//   A ≥ (1−u)(K_A(1−u)³·Σ|x_i| − η + U_A)                                     (absolute_term_lower)
// and the bounds below need (1−u)(A − η) ≥ that absolute part: K_A = 32η and U_A = 64η give
// (1−u)(A − η) ≥ 31.9η·Σ|x_i| + 61.9η, which covers all of them.
// Valid for all finite inputs; A = +inf when S overflows (then nothing is certified).
// Certified by: proofs/triangle/TriangleFilter.v, `absolute_term_lower`, `det3_filter_encloses`
// Certified by: proofs/triangle/TriangleCompensated.v, `det3_compensated_encloses`
inline constexpr double triangle_absolute_scale = 0x1p-1070;  // K_A = 32η = 16μ
inline constexpr double triangle_absolute = 0x1p-1069;        // U_A = 64η = 32μ

// ---------------------------------------------------------------------------------------------------------
// Stage 1: det3_filter (core/det3_stages.hpp), B = (C ⊗ m) ⊕ A;  v > B ⇒ V > 0,  v < −B ⇒ V < 0.
//
// Derivation (proofs/triangle/TriangleFilter.v carries |v − V| ≤ α·m + β through each operation, m the computed
// permanent, the leaves within relative error u of the exact differences and x within ex ∈ {0, u}):
//   product of two leaves   α = 3u + 6u²,          β = (1 + 3u)η             (leaf_mul_approx)
//   cross component         α = 4u + 11u²,         β = (2 + 6u)η             (cross_approx)
//   outer term x_i·c_i      α = 5u + ex + 40u²,    β = 3η·|x_i| + 2η         (outer_approx)
//   the determinant         α = 7u + ex + 60u²,    β = 3η·Σ|x_i| + 6η        (det3_approx)
//   den = (π̂a ⊕ π̂b) ⊕ π̂c    α ≤ 9u + 80u²,        β = 9η·Σ|d_i| + 18η       (den_approx)
// with ex = 0 for the π's (x = d, exact) and ex = u for num (x = ê_a). The bound covers α·m + β when
// α ≤ C(1−u)² (bound_covers: (C ⊗ m) ⊕ A ≥ C(1−u)²·m + (1−u)(A − η)), so C = 8u, 9u, 10u.
// Valid for all finite inputs (subnormal included); uncertain (never wrong) when m or A is not finite.
// Certified by: proofs/triangle/TriangleFilter.v, `pi_filter_sound`, `num_filter_sound`, `den_filter_sound`
inline constexpr double triangle_filter_pi_relative = 0x1p-50;     // 8u
inline constexpr double triangle_filter_num_relative = 0x1.2p-50;  // 9u
inline constexpr double triangle_filter_den_relative = 0x1.4p-50;  // 10u

// ---------------------------------------------------------------------------------------------------------
// Stage 2: det3_compensated (core/det3_stages.hpp): an enclosure |V − (h + l)| ≤ E, E = (K ⊗ m) ⊕ A.
//
// Double-double leaves (h, l), |l| ≤ u|h|, exact. A product of two leaves (or of a leaf x and a cross
// component (h, l)): P = a_h ⊗ b_h, l = RN(a_h·b_l + RN(a_l·b_h + RN(a_h·b_h − P))) (three FMAs; the term a_l·b_l
// is dropped). A sum or difference: (s, σ) = TwoSum(a_h, ±b_h), l = (a_l ⊕ ±b_l) ⊕ σ.
// proofs/triangle/TriangleCompensated.v carries |h + l − V| ≤ α·m + β and |l| ≤ λ·m + κ through each operation:
//   product of two leaves   α = 7u²,    β = 4η,                 λ = 4u,    κ = 7η       (cleaf_mul_capprox)
//   cross component         α = 17u²,   β = 8.1η,               λ = 6u,    κ = 15η      (ccross_capprox)
//   outer term              α = 35u²,   β = 8.2η·|x_h| + 5η,    λ = 10u,   κ = 16η·|x_h| + 6η (couter_capprox)
//   the determinant         α = 80u²,   β = 8.3η·Σ|x_h| + 16η,  λ = 13u                  (cdet3_capprox)
//   den (two more sums)     α ≤ 136u²,  β ≤ 25η·Σ|d_i| + 49η
// The radius covers α·m + β when α ≤ K(1−u)² (radius_covers), so
//   K_π = K_num = 128u² = 2^-99,   K_den = 256u² = 2^-98.
// Valid for all finite inputs; the radius is +inf when a value is not finite. Decides signs unless the value
// is within ~2^-98 of m (exact zeros go on to stage 3), and lets round_quotient round t and the
// barycentric coordinates for condition numbers up to ~2^40.
// Certified by: proofs/triangle/TriangleCompensated.v, `pi_compensated_encloses`, `num_compensated_encloses`
// Certified by: proofs/triangle/TriangleCompensated.v, `den_compensated_encloses`, `stage2_filter_view`
inline constexpr double triangle_compensated_relative = 0x1p-99;      // K_π = K_num = 128u²
inline constexpr double triangle_compensated_den_relative = 0x1p-98;  // K_den = 256u²

// Stage 3 (core/expansion_value.hpp) computes the five values, the tie-break vectors and N as exact
// expansions (expansion.hpp; proofs/core/Expansions.v) whenever no TwoProduct underflowed and nothing overflowed:
// no constant. Stage 4 (exact rationals) decides the rest.

// =========================================================================================================
// Ray–sphere (kernel/src/sphere/, docs/contract.md §10): stage 1, sphere_filter (sphere/ray_sphere_filter.hpp),
// the signs of C = f·f − r² and D = B² − A·C (the origin and the relation; the roots stay in the expansion stage).
//
//   f_i = o_i ⊖ c_i;  Â, E_A: dot3_rounded(d, d) and its dot3_filter_bound (filter_den_relative);
//   B̂, E_B: dot3_rounded(f, d) and its bound (filter_num_relative: B is num's shape (p − o)·n with p = o,
//   o = c, n = d);  S = dot3_rounded(f, f), q = r ⊗ r,  Ĉ = S.value ⊖ q,  P_C = S.magnitude ⊕ q,
//   E_C = (κ_C ⊗ P_C) ⊕ μ_C;
//   D̂ = (B̂ ⊗ B̂) ⊖ (Â ⊗ Ĉ),
//   E_D = (κ_D ⊗ ((X ⊗ X) ⊕ (Y ⊗ Z))) ⊕ μ_D,  X = m_B ⊕ θ, Y = Â ⊕ θ, Z = P_C ⊕ θ (m_B: B̂'s magnitude);
//   Ĉ > E_C ⇒ C > 0,  Ĉ < −E_C ⇒ C < 0;  D̂ > E_D ⇒ D > 0,  D̂ < −E_D ⇒ D < 0;  otherwise uncertain.
//
// Derivation. C: with f̂_i = f_i(1 + δ_i), |δ_i| ≤ u (a difference of doubles: no absolute error),
// |f̂_i² − f_i²| ≤ (2u + u²)f̂_i², so each product q_i = f̂_i ⊗ f̂_i is within (3u + 3u² + u³)|q_i| + (1+u)²η of
// f_i², and (dot3_value_error) |S − f·f| ≤ (5u + 4u² + u³)Σ|q_i| + 3(1+u)²η, Σ|q_i| ≤ (1+u)²·m_S; the
// rounding of r² adds u·q + η and the subtraction u(|S| + q) ≤ u(m_S + q); m_S + q ≤ (1+u)P_C. So
//   |Ĉ − C| ≤ (6u + O(u²))·P_C + 4.1η,  and κ_C = 8u, μ_C = 8μ = 16η cover it with the two roundings of E_C.
// D: exactly D̂ − D = (D̂ − (b − a)) + (b − B̂²) − (a − ÂĈ) + (B̂² − B²) − (ÂĈ − AC), b = B̂ ⊗ B̂, a = Â ⊗ Ĉ:
//   |D̂ − (b − a)| ≤ u(|b| + |a|),  |b − B̂²| + |a − ÂĈ| ≤ u(|b| + |a|) + 2η,
//   |B̂² − B²| ≤ E_B(2|B̂| + E_B),  |ÂĈ − AC| ≤ E_A|Ĉ| + (|Â| + E_A)E_C,
// so |D̂ − D| ≤ 2u(|b| + |a|) + E_B(2|B̂| + E_B) + E_A|Ĉ| + (|Â| + E_A)E_C + 2η, with E_A, E_B as dot3_filter_bound
// computes them (filter_den_relative on Â, filter_num_relative on m_B). That bound is not computed: each of E_A,
// E_B, E_C is (κ ⊗ m) ⊕ μ with u ≤ κ, μ ≤ 16η, hence at most 2κ·(m ⊕ θ) — the floor θ = 2^-1018 has uθ = 16η
// and absorbs the absolute errors (so that a product with an underflowed Â or a tiny m_B is still covered) —
// and |B̂| ≤ m_B ≤ X, Â ≤ Y, |Ĉ| ≤ P_C ≤ Z, |b| ≤ X ⊗ X, |a| ≤ Y ⊗ Z; then the error is at most
// 2u(X⊗X + Y⊗Z) + 4κ_B(1 + κ_B)X² + (2κ_A + 2κ_C(1 + 2κ_A))YZ + 2η ≤ 31u((X ⊗ X) ⊕ (Y ⊗ Z)) + 3η, and E_D's
// three roundings leave at least κ_D(1 − u)³ = 32u(1 − u)³ of it and 127η. Seven operations where the bound of
// the individual enclosures took twenty: the relation's fast path measured 27% faster, the bound at most 2.5×
// wider than that one.
// Valid for all finite inputs (subnormal included); uncertain (never wrong) when anything overflows: every
// intermediate is dominated by P_C, m_A, m_B or the terms of E_D, whose overflow makes a bound +inf or NaN,
// and every certifying comparison (value > bound, value < −bound) is then false. Never certifies a zero.
// Certified by: proofs/sphere/SphereFilter.v, `sphere_c_encloses` and `sphere_d_encloses` (the latter from
// `d_value_error`, `floor_covers` and `d_bound_lower`).
inline constexpr double sphere_filter_c_relative = 0x1p-50;          // κ_C = 8u
inline constexpr double sphere_filter_c_absolute = 0x1p-1071;        // μ_C = 8μ
inline constexpr double sphere_filter_d_relative = 0x1p-48;          // κ_D = 32u
inline constexpr double sphere_filter_d_floor = 0x1p-1018;           // θ = 2^-1018 (uθ = 16η)
inline constexpr double sphere_filter_d_absolute = 0x1p-1068;        // μ_D = 64μ

// =========================================================================================================
// Ray–sphere roots (kernel/src/sphere/ray_sphere_boundary_filter.hpp): the signs of q(m) and of the slope at a
// rounding boundary m = (x + y)/2, in double-double, before any expansion.
//
//   M = x + y = M₁ + M₂ (TwoSum); per axis (f̂, f̌) = TwoDiff(o_i, c_i), P = M₁ ⊗ d_i, π = fma(M₁, d_i, −P),
//   Q = M₂ ⊗ d_i, (H, h) = TwoSum(2f̂, P), L = (h ⊕ 2f̌) ⊕ (π ⊕ Q), T = (|f̂| ⊕ |f̂|) ⊕ |P|;
//   S_i = TwoProduct(H_i, H_i), R = TwoProduct(2r, 2r); a₁ = TwoSum(S₀, S₁), a₂ = TwoSum(a₁, S₂), a₃ = TwoSum(a₂, −R)
//   (heads); k_i = L_i ⊗ ((H_i ⊕ H_i) ⊕ L_i); s = ((σ₀ ⊕ σ₁) ⊕ (σ₂ ⊖ ρ)) ⊕ ((a₁.lo ⊕ a₂.lo) ⊕ a₃.lo) ⊕ ((k₀ ⊕ k₁) ⊕ k₂);
//   value = a₃.hi ⊕ s;  W = ((S₀ ⊕ S₁) ⊕ S₂) ⊕ R ⊕ Σ T_i ⊗ (|H_i| ⊕ τ ⊗ T_i);  E_q = (κ_q ⊗ W) ⊕ μ_q.
//
// Derivation (exact 4q(m) = Σ G_i² − (2r)², G_i = 2f_i + M·d_i). G_i = H + λ exactly, λ = h + 2f̌ + (M₁d_i − P) +
// M₂d_i; |h| ≤ u|H| ≤ u(1+u)T, |2f̌| ≤ u·2|f̂|, |π| ≤ u|P| + η, |Q| ≤ u(1+u)²|P| + 2η, so Λ = |h| + |2f̌| + |π| + |Q|
// ≤ 3.01u·T + 3η; L's three roundings and Q's and π's own errors leave δ = |G_i − (H + L)| ≤ 7.2u²T + 13η, and
// |L| ≤ 3.1u·T + 7η. Then G² = H² + L(2H + L) + δ'(2H + 2L + δ') (|δ'| ≤ δ): the last term ≤ 14.4u²T|H| + O(u³T²)
// + O(η(|H| + T)); k's two roundings ≤ 2.1u·|L|(2|H| + |L|) ≤ 13.1u²T|H| + O(u³T²); H² = S.hi + S.lo and (2r)² =
// R.hi + R.lo exactly up to η each (TwoProduct); Σ S.hi − R.hi = a₃.hi + a₁.lo + a₂.lo + a₃.lo exactly (TwoSum);
// the sum s (depth 4) ≤ 4.01u·Σ|terms| ≤ 16.1u²(ΣS + R) + 25.2u²ΣT|H| + O(u³T²). In all
//   |4q(m) − (a₃.hi + s)| ≤ 53u²·ΣT|H| + 17u²(ΣS + R) + 64u³ΣT² + c·η·(1 + |H| + T),
// and η·X ≤ η(1 + X²) puts the η terms under μ_q and under κ_q·(ΣS + τ·ΣT²) (ηX² ≪ 2^-141·X²). So κ_q = 2^-96 =
// 1024u² (more than 19 times the u² coefficients above, which covers W's own ten roundings, (1 + u)^10 < 1.01),
// τ = 2^-45 (u³T² ≤ u²·2^-45·T² with room), μ_q = 2^-1060 (2^15 η). The final rounding of value = RN(a₃.hi + s)
// keeps its sign and |value| ≤ (1 + u)|a₃.hi + s| + η, which E_q's margin covers: value > E_q implies a₃.hi + s >
// E_q(1 − u) − η > the error, so 4q(m) > 0 (and < −E_q, < 0).
// The slope 2(A·m + B) = Σ d_i·G_i is read from Σ d_i ⊗ H_i: the dropped Σ d_i·λ_i is ≤ 3.1u·Σ|d_i|T_i + 3η·Σ|d_i|,
// the products and sums ≤ 3.01u·Σ|d_i H_i| + 3η; κ_s = 16u, the floor 2^-1000 per |d_i| covers the 3η·|d_i|
// (κ_s·2^-1000 = 2^-1049 ≫ 3η), and the absolute μ_s = 2^-1070 = 32η the three products' own underflow errors,
// which no multiple of |d_i| covers when the d_i are tiny (found by the proof: d = (2^-1074, −2^-1074, −2^-1074)
// once had its slope certified with the wrong sign; tests/sphere_test.cpp keeps the case).
// Valid for all finite inputs; uncertain when W, the value or the slope's magnitude is not finite (overflow: every
// intermediate is below W or the magnitude up to a factor 4, so an overflow anywhere makes one of them +inf or
// NaN). Never certifies a zero.
// Certified by: proofs/sphere/SphereBoundaryFilter.v, `sphere_boundary_q_sound` and `sphere_boundary_slope_sound`
// (proved for every binary64 input).
inline constexpr double sphere_boundary_q_relative = 0x1p-96;      // κ_q = 1024u²
inline constexpr double sphere_boundary_q_absolute = 0x1p-1060;    // μ_q = 2^15·η
inline constexpr double sphere_boundary_tail = 0x1p-45;            // τ
inline constexpr double sphere_boundary_slope_relative = 0x1p-49;  // κ_s = 16u
inline constexpr double sphere_boundary_slope_floor = 0x1p-1000;   // per |d_i|
inline constexpr double sphere_boundary_slope_absolute = 0x1p-1070;  // μ_s = 32η

}  // namespace raykernel::detail::bounds
