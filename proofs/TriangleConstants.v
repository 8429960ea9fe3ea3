(** * The error constants of kernel/src/certified/triangle_bounds.hpp (the ray–triangle stages), as exact reals.

    Checked like Constants.v by the ctest test [proofs_constants_match] (proofs/check_constants.cpp), which
    reads this file after Constants.v (so [unit_roundoff] is known).  Keep every right-hand side in that
    test's grammar. *)

From Coq Require Import Reals.
From Flocq Require Import Core.
From Raykernel Require Import Constants.
Open Scope R_scope.

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
