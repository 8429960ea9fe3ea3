(** * The error constants of namespace bounds (kernel/src/core/error_bounds.hpp, and the headers that
    reopen it: box/ray_box.hpp, orient/orient_predicates.hpp), as exact reals.

    Every theorem in this directory is stated about the constants defined here, and the ctest test
    [proofs_constants_match] (proofs/check_constants.cpp) evaluates each right-hand side below
    exactly and compares it with the value of the C++ literal of the same name.  Keep every
    right-hand side in the small grammar that test understands: integers, previously defined names,
    [bpow radix2 (k)], [+], [*] and parentheses. *)

From Coq Require Import Reals.
From Flocq Require Import Core.
Open Scope R_scope.

(** Unit roundoff u = 2^-53, smallest positive subnormal mu = 2^-1074 and largest finite number
    (2^53 − 1)·2^971 = 2^1024 − 2^971 of binary64. *)
Definition unit_roundoff : R := bpow radix2 (-53).
Definition min_subnormal : R := bpow radix2 (-1074).
Definition largest_finite : R := 9007199254740991 * bpow radix2 (971).

(** TwoProduct is exact when its rounded product is at least 2^-968 in magnitude (Model.v,
    [two_prod_guard_exact]; PlaneCascade.v, [two_prod_threshold_exact]). *)
Definition exact_product_threshold : R := bpow radix2 (-968).

(** Stage 1, dot3_filter (PlaneFilter.v): B = (C ⊗ m) ⊕ filter_absolute. *)
Definition filter_den_relative : R := (3 + 16 * unit_roundoff) * unit_roundoff.
Definition filter_num_relative : R := (4 + 32 * unit_roundoff) * unit_roundoff.
Definition filter_absolute : R := 3 * min_subnormal.

(** Stage 2, compensated_dot3 (PlaneCompensated.v): E = (K ⊗ m) ⊕ U. *)
Definition compensated_relative : R := bpow radix2 (-101).
Definition compensated_absolute : R := bpow radix2 (-1070).

(** Stage 2, second level, compensated_dot3_refined (PlaneCompensated.v):
    E = ((refined_relative ⊗ m) ⊕ (refined_low_relative ⊗ |lo|)) ⊕ refined_absolute. *)
Definition refined_relative : R := bpow radix2 (-150).
Definition refined_low_relative : R := bpow radix2 (-52).
Definition refined_absolute : R := 8 * min_subnormal.

(** Stage 3, expansion_tail_enclosure (PlaneCompensated.v): E = (A ⊗ 2^-48) ⊕ 2 mu, at most 32 terms. *)
Definition tail_sum_relative : R := bpow radix2 (-48).
Definition tail_sum_absolute : R := 2 * min_subnormal.
Definition tail_sum_max_terms : nat := 32.

(** prepare_divisor and round_quotient (QuotientRounding.v): the guards |N| ≥ 2^-900, 2^-900 ≤ |q|,
    2^-1000 ≤ |D| ≤ 2^1000, and the test's constants; half_gap_to_nearer_neighbour's valid range. *)
Definition quotient_min_magnitude : R := bpow radix2 (-900).
Definition divisor_min_magnitude : R := bpow radix2 (-1000).
Definition divisor_max_magnitude : R := bpow radix2 (1000).
Definition quotient_relative : R := bpow radix2 (-101).
Definition quotient_enclosure_factor : R := 1 + bpow radix2 (-9).
Definition quotient_test_factor : R := 1 + bpow radix2 (-45).
Definition half_gap_min_magnitude : R := bpow radix2 (-968).

(** Comparing two quotients, compare_quotients_filter and compare_quotients_compensated
    (CompareQuotients.v): B = ((C_f ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c and E = ((K_c ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c. *)
Definition compare_filter_relative : R := (2 + 16 * unit_roundoff) * unit_roundoff.
Definition compare_propagation_factor : R := 1 + 16 * unit_roundoff.
Definition compare_absolute : R := 8 * min_subnormal.
Definition compare_compensated_relative : R := bpow radix2 (-101).

(** ** Ray–triangle (kernel/src/triangle/): the determinants' filter and enclosures (TriangleFilter.v,
    TriangleCompensated.v). *)

(** The dynamic absolute term A = (K_A ⊗ S) ⊕ U_A of both stages. *)
Definition triangle_absolute_scale : R := bpow radix2 (-1070).
Definition triangle_absolute : R := bpow radix2 (-1069).

(** Stage 1, det3_filter: B = (C ⊗ m) ⊕ A. *)
Definition triangle_filter_pi_relative : R := 8 * unit_roundoff.
Definition triangle_filter_num_relative : R := 9 * unit_roundoff.
Definition triangle_filter_den_relative : R := 10 * unit_roundoff.

(** Stage 2, det3_compensated: E = (K ⊗ m) ⊕ A. *)
Definition triangle_compensated_relative : R := 128 * (unit_roundoff * unit_roundoff).
Definition triangle_compensated_den_relative : R := 256 * (unit_roundoff * unit_roundoff).

(** ** The BVH's ray–box test (kernel/src/box/ray_box.hpp; box/RayBox.v). *)

(** The outward factors K_lo = 1 − 2^-50 = (2^50 − 1)·2^-50, K_hi = 1 + 2^-50 and the absolute term τ. *)
Definition ray_box_near_factor : R := 1125899906842623 * bpow radix2 (-50).
Definition ray_box_far_factor : R := 1 + bpow radix2 (-50).
Definition ray_box_absolute : R := bpow radix2 (-1022).
(** Case B's range: 2^-1022 ≤ |d| ≤ 2^1022, and the guard's bound 2^1022. *)
Definition ray_box_min_direction : R := bpow radix2 (-1022).
Definition ray_box_max_direction : R := bpow radix2 (1022).
Definition ray_box_max_parameter : R := bpow radix2 (1022).

(** ** The orientation filters of the point-in-mesh query (kernel/src/orient/orient_predicates.hpp;
    orient/OrientFilter.v). *)

(** orient2d_filter: B = (A ⊗ (|L| ⊕ |R|)) ⊕ U. *)
Definition orient2d_filter_relative : R := bpow radix2 (-51).
Definition orient2d_filter_absolute : R := bpow radix2 (-1071).

(** orient3d_filter: B = A ⊗ P, when every rounded difference is 0 or of magnitude in [2^-300, 2^300]. *)
Definition orient3d_filter_relative : R := bpow radix2 (-49).
Definition orient3d_filter_min_difference : R := bpow radix2 (-300).
Definition orient3d_filter_max_difference : R := bpow radix2 (300).

(** midpoint_offset (kernel/src/spawn/spawn_certified.hpp; spawn/SpawnRounding.v): the radius R ⊗ |lo| of the
    enclosure of x + y − 2·o. *)
Definition midpoint_offset_relative : R := bpow radix2 (-52).

(** affine_enclosure (kernel/src/spawn/spawn_certified.hpp; spawn/SpawnAffine.v): radius
    (C ⊗ ((|o| ⊗ D.radius ⊕ |d| ⊗ N.radius) ⊕ E)) ⊕ U. *)
Definition affine_propagation_factor : R := 1 + bpow radix2 (-50).
Definition affine_absolute : R := bpow radix2 (-1060).

(** ** Ray–sphere (kernel/src/sphere/ray_sphere_filter.hpp; sphere/SphereFilter.v): E_C = (κ_C ⊗ P_C) ⊕ μ_C and
    E_D = (κ_D ⊗ ((X ⊗ X) ⊕ (Y ⊗ Z))) ⊕ μ_D with X, Y, Z each a magnitude ⊕ θ, the bounds of stage 1's signs of C and D. *)
Definition sphere_filter_c_relative : R := 8 * unit_roundoff.
Definition sphere_filter_c_absolute : R := 8 * min_subnormal.
Definition sphere_filter_d_relative : R := 32 * unit_roundoff.
Definition sphere_filter_d_floor : R := bpow radix2 (-1018).
Definition sphere_filter_d_absolute : R := 64 * min_subnormal.

(** Ray–sphere roots (kernel/src/sphere/ray_sphere_boundary_filter.hpp): the boundary filter's E_q = (κ_q ⊗ W) ⊕ μ_q,
    W's tail factor τ, and the slope's E_s = (κ_s ⊗ Σ|d_i|(… ⊕ floor)) ⊕ μ_s (proved in sphere/SphereBoundaryFilter.v:
    `sphere_boundary_q_sound`, `sphere_boundary_slope_sound`). *)
Definition sphere_boundary_q_relative : R := bpow radix2 (-96).
Definition sphere_boundary_q_absolute : R := bpow radix2 (-1060).
Definition sphere_boundary_tail : R := bpow radix2 (-45).
Definition sphere_boundary_slope_relative : R := bpow radix2 (-49).
Definition sphere_boundary_slope_floor : R := bpow radix2 (-1000).
Definition sphere_boundary_slope_absolute : R := bpow radix2 (-1070).
