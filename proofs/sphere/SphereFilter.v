(** * Stage 1 of the ray–sphere cascade: the binary64 filter of the signs of C and D
    (kernel/src/sphere/ray_sphere_filter.hpp; the bounds' derivation: kernel/src/core/error_bounds.hpp, ray–sphere).

    Main theorems: [sphere_filter_c_sound] (a certain sign of Ĉ against E_C is the sign of the exact
    C = (o − c)·(o − c) − r²) and [sphere_filter_d_sound] (a certain sign of D̂ against E_D is the sign of the
    exact D = B² − A·C, A = d·d, B = (o − c)·d), for every binary64 input. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model.
From Raykernel.Plane Require Import PlaneFilter.
Open Scope R_scope.

(** ** The C++ code, operation by operation. *)

(** [sphere_filter_sign(value, bound)]: value > bound, value < −bound, else uncertain. *)
Definition filter_sign (v b : R) : sign :=
  if Rlt_bool b v then Positive else if Rlt_bool v (- b) then Negative else Uncertain.

Definition sphere_f (o c : R) : R := RN (o - c).

(** S = dot3_rounded(f, f). *)
Definition sphere_s (o0 o1 o2 c0 c1 c2 : R) : Dot3Rounded :=
  dot3_rounded (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)
               (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2).

(** Ĉ = S.value ⊖ q, q = r ⊗ r. *)
Definition sphere_c_value (o0 o1 o2 c0 c1 c2 r : R) : R :=
  RN (value (sphere_s o0 o1 o2 c0 c1 c2) - RN (r * r)).

(** E_C = (κ_C ⊗ (S.magnitude ⊕ q)) ⊕ μ_C. *)
Definition sphere_c_bound (o0 o1 o2 c0 c1 c2 r : R) : R :=
  RN (RN (sphere_filter_c_relative * RN (magnitude (sphere_s o0 o1 o2 c0 c1 c2) + RN (r * r)))
      + sphere_filter_c_absolute).

Definition sphere_filter_c (o0 o1 o2 c0 c1 c2 r : R) : sign :=
  filter_sign (sphere_c_value o0 o1 o2 c0 c1 c2 r) (sphere_c_bound o0 o1 o2 c0 c1 c2 r).

(** D̂ = (B̂ ⊗ B̂) ⊖ (Â ⊗ Ĉ) and E_D, from the values and bounds of A, B, C. *)
Definition d_value (a b c : R) : R := RN (RN (b * b) - RN (a * c)).

Definition d_bound (a b c ea eb ec : R) : R :=
  let bb := RN (b * b) in
  let ac := RN (a * c) in
  let t1 := RN (sphere_filter_d_relative * RN (Rabs bb + Rabs ac)) in
  let t2 := RN (eb * RN (RN (Rabs b + Rabs b) + eb)) in
  let t3 := RN (ea * Rabs c) in
  let t4 := RN (RN (Rabs a + ea) * ec) in
  RN (RN (RN (RN (t1 + t2) + RN (t3 + t4)) * sphere_filter_d_factor) + sphere_filter_d_absolute).

(** The whole filter of D, as sphere_filter() computes it: Â, E_A by dot3_rounded(d, d) and filter_den_relative,
    B̂, E_B by dot3_rounded(f, d) and filter_num_relative. *)
Definition sphere_filter_d (o0 o1 o2 d0 d1 d2 c0 c1 c2 r : R) : sign :=
  let ra := dot3_rounded d0 d1 d2 d0 d1 d2 in
  let rb := dot3_rounded (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2) d0 d1 d2 in
  let a := value ra in
  let b := value rb in
  let c := sphere_c_value o0 o1 o2 c0 c1 c2 r in
  let ea := filter_bound ra filter_den_relative in
  let eb := filter_bound rb filter_num_relative in
  let ec := sphere_c_bound o0 o1 o2 c0 c1 c2 r in
  filter_sign (d_value a b c) (d_bound a b c ea eb ec).

(** ** Soundness of the sign test from an enclosure. *)

Lemma filter_sign_sound : forall v b X, Rabs (v - X) <= b -> certifies (filter_sign v b) X.
Proof.
  intros v b X H. apply Rabs_bounds in H. unfold filter_sign.
  destruct (Rlt_bool_spec b v) as [L|L]; simpl; [lra|].
  destruct (Rlt_bool_spec v (- b)) as [L'|L']; simpl; [lra | exact I].
Qed.

(** Lower bounds of a rounding of a non-negative real. *)
Lemma RN_lower : forall x, 0 <= x -> x * (1 - u) - eta <= RN x.
Proof.
  intros x Hx. pose proof (RN_err x) as E. rewrite (Rabs_nonneg_eq x Hx) in E.
  apply Rabs_bounds in E. lra.
Qed.

Lemma RN_plus_lower : forall a b, binary64 a -> binary64 b -> 0 <= a + b -> (a + b) * (1 - u) <= RN (a + b).
Proof.
  intros a b Ha Hb H. pose proof (RN_plus_err a b Ha Hb) as E. rewrite (Rabs_nonneg_eq _ H) in E.
  apply Rabs_bounds in E. lra.
Qed.

(** ** C. *)

(** One square of a rounded difference: |f̂ ⊗ f̂ − (o − c)²| ≤ 4u|f̂ ⊗ f̂| + 2η. *)
Lemma square_term_error : forall o c, binary64 o -> binary64 c ->
  Rabs (RN (sphere_f o c * sphere_f o c) - (o - c) * (o - c)) <=
    4 * u * Rabs (RN (sphere_f o c * sphere_f o c)) + 2 * eta.
Proof.
  intros o c Bo Bc. unfold sphere_f.
  set (f := o - c). set (g := RN (o - c)). set (q := RN (g * g)).
  pose proof u_pos as Hu. pose proof eta_pos as He.
  pose proof (RN_minus_err_round o c Bo Bc) as E1. change (Rabs (g - f) <= u * Rabs g) in E1.
  pose proof (RN_err_round (g * g)) as E2. fold q in E2.
  assert (Hgg : Rabs (g * g) <= Rabs q + u * Rabs q + eta).
  { pose proof (Rabs_close' _ _ _ E2). lra. }
  rewrite Rabs_mult in Hgg.
  assert (D : Rabs (g * g - f * f) <= (2 * u + u * u) * (Rabs g * Rabs g)).
  { replace (g * g - f * f) with ((g - f) * (g + f)) by ring. rewrite Rabs_mult.
    assert (S : Rabs (g + f) <= (2 + u) * Rabs g).
    { replace (g + f) with (2 * g - (g - f)) by ring.
      eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp, Rabs_mult, (Rabs_nonneg_eq 2) by lra. lra. }
    pose proof (Rabs_pos (g - f)). pose proof (Rabs_pos (g + f)). pose proof (Rabs_pos g).
    apply Rle_trans with (u * Rabs g * ((2 + u) * Rabs g)).
    - apply Rmult_le_compat; lra.
    - nra. }
  change (Rabs (q - f * f) <= 4 * u * Rabs q + 2 * eta).
  replace (q - f * f) with ((q - g * g) + (g * g - f * f)) by ring.
  eapply Rle_trans; [apply Rabs_triang|].
  pose proof (Rabs_pos q). pose proof (Rabs_pos g).
  assert (G : (2 * u + u * u) * (Rabs g * Rabs g) <= (2 * u + u * u) * (Rabs q + u * Rabs q + eta))
    by (apply Rmult_le_compat_l; nra).
  assert (K : u + (2 * u + u * u) * (1 + u) <= 4 * u) by (rewrite u_val; lra).
  assert (K2 : (u + (2 * u + u * u) * (1 + u)) * Rabs q <= 4 * u * Rabs q) by (apply Rmult_le_compat_r; lra).
  assert (K3 : (1 + (2 * u + u * u)) * eta <= 2 * eta) by (rewrite u_val; lra).
  replace ((2 * u + u * u) * (Rabs q + u * Rabs q + eta))
    with ((u + (2 * u + u * u) * (1 + u)) * Rabs q - u * Rabs q + (1 + (2 * u + u * u)) * eta - eta) in G by ring.
  lra.
Qed.

(** |S − f·f| ≤ (6u + u²)Σ|q_i| + 6η. *)
Lemma sphere_s_error : forall o0 o1 o2 c0 c1 c2,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 c0 -> binary64 c1 -> binary64 c2 ->
  let s := sphere_s o0 o1 o2 c0 c1 c2 in
  Rabs (value s - ((o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2))) <=
    (6 * u + u * u) * (Rabs (product0 s) + Rabs (product1 s) + Rabs (product2 s)) + 6 * eta.
Proof.
  intros o0 o1 o2 c0 c1 c2 B0 B1 B2 C0 C1 C2 s.
  pose proof (square_term_error o0 c0 B0 C0) as E0. pose proof (square_term_error o1 c1 B1 C1) as E1.
  pose proof (square_term_error o2 c2 B2 C2) as E2.
  pose proof (dot3_value_error _ _ _ _ _ _ _ _ _ _ _ _ E0 E1 E2) as H.
  unfold s, sphere_s. simpl in H |- *. lra.
Qed.

Lemma binary64_sphere_filter_c_absolute : binary64 sphere_filter_c_absolute.
Proof.
  unfold sphere_filter_c_absolute, min_subnormal.
  apply generic_format_FLT. exists (Float radix2 8 (-1074)); simpl; try lia.
  unfold F2R; simpl. ring.
Qed.

Lemma binary64_sphere_filter_d_absolute : binary64 sphere_filter_d_absolute.
Proof.
  unfold sphere_filter_d_absolute, min_subnormal.
  apply generic_format_FLT. exists (Float radix2 64 (-1074)); simpl; try lia.
  unfold F2R; simpl. ring.
Qed.

(** Unfinished (not in this file yet): the enclosures |Ĉ − C| ≤ E_C and |D̂ − D| ≤ E_D and the theorems
    [sphere_filter_c_sound] and [sphere_filter_d_sound]; ray_sphere_filter.hpp's filter is therefore not wired
    into the cascade (ray_sphere_cascade.cpp, use_sphere_filter). *)
