// The error constants of the ray–triangle stages (kernel/src/triangle/), each beside its derivation, its valid
// range and the theorem in proofs/ that certifies it. A new section of bounds:: to be folded into
// error_bounds.hpp; tests/triangle_constants_test.cpp recomputes every constant from its formula and
// proofs/check_constants.cpp compares each with proofs/TriangleConstants.v.
//
// Notation as in error_bounds.hpp: u = 2^-53, η = 2^-1075 (the largest absolute error of a rounding in the
// subnormal range), μ = 2^-1074, ⊕ ⊖ ⊗ rounded operations. Rounding model with gradual underflow:
// RN(x) = x(1+ε) + e, |ε| ≤ u, |e| ≤ η; a sum or difference of two doubles has no absolute error.
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
#pragma once

namespace raykernel::detail::bounds {

// ---------------------------------------------------------------------------------------------------------
// The dynamic absolute term A = (K_A ⊗ S) ⊕ U_A (both stages).
//
// Derivation. Each P, Q errs by at most u|P| + η; the η's reach the value multiplied by |x_i|(1+u)² (stage 1:
// 2 per component, so 2.01η·Σ|x_i|; stage 2: the TwoProduct residual and the three FMAs of each cross
// component, about 6.1η·Σ|x_i|); the outer products add 3η (stage 1) or 9.1η (stage 2). den adds three π's:
// at most 18.3η·Σ|d_i| + 27.3η. With S ≥ Σ|x_i|/(1+u)² and RN(K_A·S) ≥ K_A·S/(1+u) − η:
//   K_A = 32η = 2^-1070 ≥ 18.3(1+u)^3·η,   U_A = 64η = 2^-1069 ≥ 27.3η + η + the η lost by C ⊗ m below.
// Valid for all finite inputs; A = +inf when S overflows (then nothing is certified).
// Certified by: proofs/TriangleFilter.v, `det3_filter_encloses`; proofs/TriangleCompensated.v,
// `det3_compensated_encloses` (both use A as computed here).
inline constexpr double triangle_absolute_scale = 0x1p-1070;  // K_A = 32η = 16μ
inline constexpr double triangle_absolute = 0x1p-1069;        // U_A = 64η = 32μ

// ---------------------------------------------------------------------------------------------------------
// Stage 1: det3_filter (triangle/det3_stages.hpp), B = (C ⊗ m) ⊕ A;  s > B ⇒ V > 0,  s < −B ⇒ V < 0.
//
// Derivation (per term i, Higham §3.1 with the underflow terms kept apart): with M_i = |P_i| + |Q_i|,
//   |Y_j Z_k − ŷ_j ẑ_k| ≤ (2u + u²)|ŷ_j ẑ_k|          (rounded differences; 0 when y, z are inputs)
//   |ŷ_j ẑ_k − P| ≤ u|P| + η,  |P − Q − c| ≤ u·M_i,  |X_i − x̂_i| ≤ u|x̂_i| (num only),
//   |x̂_i c_i − t_i| ≤ u|x̂_i c_i| + η,  the two additions ≤ (2u + u²)Σ|t_i|,
// so |s − V| ≤ k·Σ|x̂_i|M_i + 2.01η·Σ|x̂_i| + 3.01η with k = 7u + O(u²) for a π (x = d exact), 8u + O(u²)
// for num; den = (π̂a ⊕ π̂b) ⊕ π̂c adds (2u + u²)Σ|π̂| ≤ (2u + u²)(1 + u)Σm_k: 9u + O(u²). With
// m ≥ Σ|x̂_i|M_i/(1+u)^4 − 3η, the constants below leave a margin of u·m for the O(u²) terms and roundings.
// Valid for all finite inputs (subnormal included); uncertain (never wrong) when m or A is not finite.
// Certified by: proofs/TriangleFilter.v, `pi_filter_sound`, `num_filter_sound`, `den_filter_sound`.
inline constexpr double triangle_filter_pi_relative = 0x1p-50;     // 8u
inline constexpr double triangle_filter_num_relative = 0x1.2p-50;  // 9u
inline constexpr double triangle_filter_den_relative = 0x1.4p-50;  // 10u

// ---------------------------------------------------------------------------------------------------------
// Stage 2: det3_compensated (triangle/det3_stages.hpp): an enclosure |V − (h + l)| ≤ E, E = (K ⊗ m) ⊕ A.
//
// Double-double leaves (h, l), |l| ≤ u|h|, exact. A product of two leaves (or of a leaf x and a cross
// component (h, l)): P = a_h ⊗ b_h, l = RN(a_h·b_l + RN(a_l·b_h + RN(a_h·b_h − P))) (three FMAs; the
// term a_l·b_l ≤ u²|a_h b_h| is dropped). A sum or difference: (s, σ) = TwoSum(a_h, ±b_h),
// l = (a_l ⊕ ±b_l) ⊕ σ. Per cross component the error is ≤ 19u²·M_i + 6η and its low part ≤ 4u·M_i + 6η;
// per outer term ≤ 31u²·|x_i|M_i + 6.01η|x_i| + 3.01η, low part ≤ 6u·|x_i|M_i + ...; the two sums of the dot
// product add ≤ 4u·(8u)·Σ|x_i|M_i. In all about 63u²·Σ|x_i|M_i (+ the η terms of A); den sums three such
// enclosures with two more double-double additions: about 95u²·Σm_k.
//   K_π = K_num = 128u² = 2^-99,   K_den = 256u² = 2^-98   (m ≥ Σ|x_i|M_i/(1+u)^4 − 3η)
// Valid for all finite inputs; the radius is +inf when a value is not finite. Decides signs unless the value
// is within ~2^-98 of m (exact zeros go on to stage 3), and lets round_quotient_decision round t and the
// barycentric coordinates for condition numbers up to ~2^40.
// Certified by: proofs/TriangleCompensated.v, `pi_compensated_encloses`, `num_compensated_encloses`,
// `den_compensated_encloses`.
inline constexpr double triangle_compensated_relative = 0x1p-99;      // K_π = K_num = 128u²
inline constexpr double triangle_compensated_den_relative = 0x1p-98;  // K_den = 256u²

// Stage 3 (triangle/expansion_value.hpp) computes the five values, the tie-break vectors and N as exact
// expansions (Shewchuk's Theorems 13 and 19) whenever no TwoProduct underflowed and nothing overflowed: no
// constant. Stage 4 (exact rationals) decides the rest.

}  // namespace raykernel::detail::bounds
