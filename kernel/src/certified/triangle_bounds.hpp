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
// Derivation. Each P, Q errs by up to u|P| + η; the η's reach the value multiplied by |x_i| in the outer
// products: stage 1 carries at most 3η·Σ|x_i| + 6η (a determinant) or 9η·Σ|d_i| + 18η (den); stage 2 (the
// TwoProduct residuals and the FMAs of each cross component, then the outer FMAs) at most 8.3η·Σ|x_h| + 16η,
// or 25η·Σ|d_i| + 49η for den. With S ≥ (1−u)²·Σ|x_i| and the two roundings of A,
//   A ≥ (1−u)(K_A(1−u)³·Σ|x_i| − η + U_A)                                     (absolute_term_lower)
// and the bounds below need (1−u)(A − η) ≥ that absolute part: K_A = 32η and U_A = 64η give
// (1−u)(A − η) ≥ 31.9η·Σ|x_i| + 61.9η, which covers all of them.
// Valid for all finite inputs; A = +inf when S overflows (then nothing is certified).
// Certified by: proofs/TriangleFilter.v, `absolute_term_lower`, `det3_filter_encloses`
// Certified by: proofs/TriangleCompensated.v, `det3_compensated_encloses`
inline constexpr double triangle_absolute_scale = 0x1p-1070;  // K_A = 32η = 16μ
inline constexpr double triangle_absolute = 0x1p-1069;        // U_A = 64η = 32μ

// ---------------------------------------------------------------------------------------------------------
// Stage 1: det3_filter (triangle/det3_stages.hpp), B = (C ⊗ m) ⊕ A;  v > B ⇒ V > 0,  v < −B ⇒ V < 0.
//
// Derivation (proofs/TriangleFilter.v carries |v − V| ≤ α·m + β through each operation, m the computed
// permanent, the leaves within relative error u of the exact differences and x within ex ∈ {0, u}):
//   product of two leaves   α = 3u + 6u²,          β = (1 + 3u)η             (leaf_mul_approx)
//   cross component         α = 4u + 11u²,         β = (2 + 6u)η             (cross_approx)
//   outer term x_i·c_i      α = 5u + ex + 40u²,    β = 3η·|x_i| + 2η         (outer_approx)
//   the determinant         α = 7u + ex + 60u²,    β = 3η·Σ|x_i| + 6η        (det3_approx)
//   den = (π̂a ⊕ π̂b) ⊕ π̂c    α ≤ 9u + 80u²,        β = 9η·Σ|d_i| + 18η       (den_approx)
// with ex = 0 for the π's (x = d, exact) and ex = u for num (x = ê_a). The bound covers α·m + β when
// α ≤ C(1−u)² (bound_covers: (C ⊗ m) ⊕ A ≥ C(1−u)²·m + (1−u)(A − η)), so C = 8u, 9u, 10u.
// Valid for all finite inputs (subnormal included); uncertain (never wrong) when m or A is not finite.
// Certified by: proofs/TriangleFilter.v, `pi_filter_sound`, `num_filter_sound`, `den_filter_sound`
inline constexpr double triangle_filter_pi_relative = 0x1p-50;     // 8u
inline constexpr double triangle_filter_num_relative = 0x1.2p-50;  // 9u
inline constexpr double triangle_filter_den_relative = 0x1.4p-50;  // 10u

// ---------------------------------------------------------------------------------------------------------
// Stage 2: det3_compensated (triangle/det3_stages.hpp): an enclosure |V − (h + l)| ≤ E, E = (K ⊗ m) ⊕ A.
//
// Double-double leaves (h, l), |l| ≤ u|h|, exact. A product of two leaves (or of a leaf x and a cross
// component (h, l)): P = a_h ⊗ b_h, l = RN(a_h·b_l + RN(a_l·b_h + RN(a_h·b_h − P))) (three FMAs; the term a_l·b_l
// is dropped). A sum or difference: (s, σ) = TwoSum(a_h, ±b_h), l = (a_l ⊕ ±b_l) ⊕ σ. proofs/TriangleCompensated.v
// carries |h + l − V| ≤ α·m + β and |l| ≤ λ·m + κ through each operation:
//   product of two leaves   α = 7u²,    β = 4η,                 λ = 4u,    κ = 7η       (cleaf_mul_capprox)
//   cross component         α = 17u²,   β = 8.1η,               λ = 6u,    κ = 15η      (ccross_capprox)
//   outer term              α = 35u²,   β = 8.2η·|x_h| + 5η,    λ = 10u,   κ = 16η·|x_h| + 6η (couter_capprox)
//   the determinant         α = 80u²,   β = 8.3η·Σ|x_h| + 16η,  λ = 13u                  (cdet3_capprox)
//   den (two more sums)     α ≤ 136u²,  β ≤ 25η·Σ|d_i| + 49η
// The radius covers α·m + β when α ≤ K(1−u)² (radius_covers), so
//   K_π = K_num = 128u² = 2^-99,   K_den = 256u² = 2^-98.
// Valid for all finite inputs; the radius is +inf when a value is not finite. Decides signs unless the value
// is within ~2^-98 of m (exact zeros go on to stage 3), and lets round_quotient_decision round t and the
// barycentric coordinates for condition numbers up to ~2^40.
// Certified by: proofs/TriangleCompensated.v, `pi_compensated_encloses`, `num_compensated_encloses`
// Certified by: proofs/TriangleCompensated.v, `den_compensated_encloses`, `stage2_filter_view`
inline constexpr double triangle_compensated_relative = 0x1p-99;      // K_π = K_num = 128u²
inline constexpr double triangle_compensated_den_relative = 0x1p-98;  // K_den = 256u²

// Stage 3 (triangle/expansion_value.hpp) computes the five values, the tie-break vectors and N as exact
// expansions (Shewchuk's Theorems 13 and 19) whenever no TwoProduct underflowed and nothing overflowed: no
// constant. Stage 4 (exact rationals) decides the rest.

}  // namespace raykernel::detail::bounds
