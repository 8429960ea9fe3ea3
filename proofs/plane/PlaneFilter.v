(** * Stage 1: the binary64 sign filter (kernel/src/core/dot3_filter.hpp).

    Main theorems: [den_filter_sound] (the sign of den = d·n) and [num_filter_sound] (the sign of
    num = (p − o)·n, with the rounded differences p_i ⊖ o_i), both for every binary64 input;
    [den_filter_lanes_sound] and [num_filter_lanes_sound]: the same for [dot3_filter_lanes] alone (no
    [exactly_zero] flag), as the fast path calls it. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model.
Open Scope R_scope.

(** ** The C++ code, operation by operation. *)

(** [Dot3Rounded] and [dot3_rounded(a, b)]: q_i = a_i ⊗ b_i, s = (q_0 ⊕ q_1) ⊕ q_2,
    m = (|q_0| ⊕ |q_1|) ⊕ |q_2|. *)
Record Dot3Rounded := {
  product0 : R; product1 : R; product2 : R;
  value : R;
  magnitude : R }.

Definition dot3_rounded (a0 a1 a2 b0 b1 b2 : R) : Dot3Rounded :=
  let q0 := RN (a0 * b0) in
  let q1 := RN (a1 * b1) in
  let q2 := RN (a2 * b2) in
  {| product0 := q0; product1 := q1; product2 := q2;
     value := RN (RN (q0 + q1) + q2);
     magnitude := RN (RN (Rabs q0 + Rabs q1) + Rabs q2) |}.

(** [dot3_filter_lanes(r, relative_constant)], branch-free as in the C++ (one lane of it for Lanes8):
    bound = (C ⊗ m) ⊕ 3μ, then [sign_lanes(value > bound, value < −bound)] (Model.v): +1, −1, or 2 for
    uncertain. *)
Definition filter_bound (r : Dot3Rounded) (relative_constant : R) : R :=
  RN (RN (relative_constant * magnitude r) + filter_absolute).

Definition dot3_filter_lanes (r : Dot3Rounded) (relative_constant : R) : Z :=
  let bound := filter_bound r relative_constant in
  sign_lanes (Rlt_bool bound (value r)) (Rlt_bool (value r) (- bound)).

(** [dot3_filter(r, relative_constant, exactly_zero)]: zero when [exactly_zero], else
    [static_cast<Sign>(dot3_filter_lanes(r, relative_constant))]. *)
Definition dot3_filter (r : Dot3Rounded) (relative_constant : R) (exactly_zero : bool) : sign :=
  if exactly_zero then Zero else sign_from_Z (dot3_filter_lanes r relative_constant).

(** The two calls in intersect_certified.cpp, with the [*_trivially_zero] flags computed there. *)
Definition den_trivially_zero (d0 d1 d2 n0 n1 n2 : R) : bool :=
  (Req_bool d0 0 || Req_bool n0 0) && (Req_bool d1 0 || Req_bool n1 0) && (Req_bool d2 0 || Req_bool n2 0).

Definition num_trivially_zero (p0 p1 p2 o0 o1 o2 n0 n1 n2 : R) : bool :=
  (Req_bool p0 o0 || Req_bool n0 0) && (Req_bool p1 o1 || Req_bool n1 0) && (Req_bool p2 o2 || Req_bool n2 0).

Definition den_filter (d0 d1 d2 n0 n1 n2 : R) : sign :=
  dot3_filter (dot3_rounded d0 d1 d2 n0 n1 n2) filter_den_relative (den_trivially_zero d0 d1 d2 n0 n1 n2).

Definition num_filter (p0 p1 p2 o0 o1 o2 n0 n1 n2 : R) : sign :=
  dot3_filter (dot3_rounded (RN (p0 - o0)) (RN (p1 - o1)) (RN (p2 - o2)) n0 n1 n2)
    filter_num_relative (num_trivially_zero p0 p1 p2 o0 o1 o2 n0 n1 n2).

(** ** Facts about the stage-1 evaluation that stage 2 reuses. *)

Lemma filter_absolute_eta : filter_absolute = 6 * eta.
Proof. unfold filter_absolute. rewrite min_subnormal_eta. ring. Qed.

Lemma binary64_filter_absolute : binary64 filter_absolute.
Proof.
  unfold filter_absolute, min_subnormal.
  apply generic_format_FLT. exists (Float radix2 3 (-1074)); simpl; try lia.
  unfold F2R; simpl. ring.
Qed.

(** m ≥ 0 and Σ|q_i| ≤ (1 + u)² m: the magnitude dominates the products it sums. *)
Lemma magnitude_bound : forall a0 a1 a2 b0 b1 b2,
  let r := dot3_rounded a0 a1 a2 b0 b1 b2 in
  0 <= magnitude r /\
  Rabs (product0 r) + Rabs (product1 r) + Rabs (product2 r) <= (1 + u) * (1 + u) * magnitude r.
Proof.
  intros. subst r. simpl.
  set (q0 := RN (a0 * b0)). set (q1 := RN (a1 * b1)). set (q2 := RN (a2 * b2)).
  set (m2 := RN (Rabs q0 + Rabs q1)). set (m := RN (m2 + Rabs q2)).
  pose proof u_pos as Hu. rewrite u_val in Hu |- *.
  assert (B0 : binary64 (Rabs q0)) by apply binary64_abs, binary64_RN.
  assert (B1 : binary64 (Rabs q1)) by apply binary64_abs, binary64_RN.
  assert (B2 : binary64 (Rabs q2)) by apply binary64_abs, binary64_RN.
  pose proof (Rabs_pos q0). pose proof (Rabs_pos q1). pose proof (Rabs_pos q2).
  assert (P2 : 0 <= m2) by (apply RN_nonneg; lra).
  assert (P : 0 <= m) by (apply RN_nonneg; lra).
  pose proof (RN_plus_err_round _ _ B0 B1) as E2. fold m2 in E2.
  assert (Bm2 : binary64 m2) by apply binary64_RN.
  pose proof (RN_plus_err_round _ _ Bm2 B2) as E3. fold m in E3.
  rewrite u_val in E2, E3.
  rewrite (Rabs_nonneg_eq m2) in E2 by exact P2. rewrite (Rabs_nonneg_eq m) in E3 by exact P.
  apply Rabs_bounds in E2. apply Rabs_bounds in E3.
  split; [exact P | nra].
Qed.

(** Every other intermediate is at most m in magnitude (used in proofs/README.md, "Overflow"). *)
Lemma dot3_rounded_dominated : forall a0 a1 a2 b0 b1 b2,
  let r := dot3_rounded a0 a1 a2 b0 b1 b2 in
  Rabs (product0 r) <= magnitude r /\ Rabs (product1 r) <= magnitude r /\
  Rabs (product2 r) <= magnitude r /\
  Rabs (RN (product0 r + product1 r)) <= RN (Rabs (product0 r) + Rabs (product1 r)) /\
  Rabs (value r) <= magnitude r.
Proof.
  intros. subst r. simpl.
  set (q0 := RN (a0 * b0)). set (q1 := RN (a1 * b1)). set (q2 := RN (a2 * b2)).
  pose proof (Rabs_pos q0). pose proof (Rabs_pos q1). pose proof (Rabs_pos q2).
  assert (Bq0 : binary64 (Rabs q0)) by apply binary64_abs, binary64_RN.
  assert (Bq1 : binary64 (Rabs q1)) by apply binary64_abs, binary64_RN.
  assert (Bq2 : binary64 (Rabs q2)) by apply binary64_abs, binary64_RN.
  assert (M2 : Rabs (RN (q0 + q1)) <= RN (Rabs q0 + Rabs q1)).
  { rewrite <- RN_abs. apply RN_le. apply Rabs_triang. }
  assert (M : Rabs (RN (RN (q0 + q1) + q2)) <= RN (RN (Rabs q0 + Rabs q1) + Rabs q2)).
  { rewrite <- RN_abs. apply RN_le. eapply Rle_trans; [apply Rabs_triang|]. lra. }
  assert (N2 : 0 <= RN (Rabs q0 + Rabs q1)) by (apply RN_nonneg; lra).
  assert (L0 : Rabs q0 <= RN (Rabs q0 + Rabs q1)).
  { rewrite <- (RN_binary64 _ Bq0) at 1. apply RN_le. lra. }
  assert (L1 : Rabs q1 <= RN (Rabs q0 + Rabs q1)).
  { rewrite <- (RN_binary64 _ Bq1) at 1. apply RN_le. lra. }
  assert (L2 : Rabs q2 <= RN (RN (Rabs q0 + Rabs q1) + Rabs q2)).
  { rewrite <- (RN_binary64 _ Bq2) at 1. apply RN_le. lra. }
  assert (L3 : RN (Rabs q0 + Rabs q1) <= RN (RN (Rabs q0 + Rabs q1) + Rabs q2)).
  { rewrite <- (RN_binary64 (RN (Rabs q0 + Rabs q1))) at 1 by apply binary64_RN. apply RN_le. lra. }
  repeat split; lra.
Qed.

(** ** The computed bound encloses [value] whenever its constant covers the error of [value]:
    |s − V| ≤ (C ⊗ m) ⊕ 3μ.  (The comparison of two quotients, issue 5, uses this enclosure.) *)

Lemma dot3_filter_bound_encloses : forall a0 a1 a2 b0 b1 b2 V C K,
  0 <= K -> K * ((1 + u) * (1 + u) * (1 + u)) <= C * (1 - u) ->
  let r := dot3_rounded a0 a1 a2 b0 b1 b2 in
  Rabs (value r - V) <= K * (Rabs (product0 r) + Rabs (product1 r) + Rabs (product2 r)) + 3 * (1 + u) * eta ->
  Rabs (value r - V) <= filter_bound r C.
Proof.
  intros a0 a1 a2 b0 b1 b2 V C K HK HC r Herr.
  destruct (magnitude_bound a0 a1 a2 b0 b1 b2) as [Pm Qm]. fold r in Pm, Qm.
  set (Q := Rabs (product0 r) + Rabs (product1 r) + Rabs (product2 r)) in *.
  set (m := magnitude r) in *.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (HC0 : 0 <= C).
  { rewrite u_val in HC. nra. }
  (* RN(C·m) ≥ C·m − u·C·m − η *)
  set (Cm := RN (C * m)).
  assert (E1 : Rabs (Cm - C * m) <= u * (C * m) + eta).
  { pose proof (RN_err (C * m)) as H. rewrite (Rabs_nonneg_eq (C * m)) in H by nra. exact H. }
  assert (PCm : 0 <= Cm) by (apply RN_nonneg; nra).
  unfold filter_bound. fold m Cm.
  set (B := RN (Cm + filter_absolute)).
  assert (E2 : Rabs (B - (Cm + filter_absolute)) <= u * Rabs B).
  { apply RN_plus_err_round; [apply binary64_RN | apply binary64_filter_absolute]. }
  assert (PB : 0 <= B).
  { apply RN_nonneg. rewrite filter_absolute_eta. lra. }
  rewrite (Rabs_nonneg_eq B PB) in E2.
  rewrite filter_absolute_eta in E2.
  (* K Q ≤ K (1+u)² m and K (1+u)³ m ≤ C (1−u) m *)
  assert (F1 : K * Q <= K * ((1 + u) * (1 + u) * m)) by (apply Rmult_le_compat_l; lra).
  assert (F2 : K * ((1 + u) * (1 + u) * (1 + u)) * m <= C * (1 - u) * m)
    by (apply Rmult_le_compat_r; lra).
  apply Rabs_bounds in E1. apply Rabs_bounds in E2.
  rewrite u_val in *. nra.
Qed.

(** ** The filter is sound whenever its constant covers the error of [value]. *)
Lemma dot3_filter_sound_gen : forall a0 a1 a2 b0 b1 b2 V C K,
  0 <= K -> K * ((1 + u) * (1 + u) * (1 + u)) <= C * (1 - u) ->
  let r := dot3_rounded a0 a1 a2 b0 b1 b2 in
  Rabs (value r - V) <= K * (Rabs (product0 r) + Rabs (product1 r) + Rabs (product2 r)) + 3 * (1 + u) * eta ->
  certifies (dot3_filter r C false) V.
Proof.
  intros a0 a1 a2 b0 b1 b2 V C K HK HC r Herr.
  pose proof (dot3_filter_bound_encloses a0 a1 a2 b0 b1 b2 V C K HK HC Herr) as Enc. fold r in Enc.
  apply Rabs_bounds in Enc.
  unfold dot3_filter, dot3_filter_lanes, sign_lanes. set (B := filter_bound r C) in *.
  destruct (Rlt_bool_spec B (value r)) as [L|L];
    destruct (Rlt_bool_spec (value r) (- B)) as [L'|L']; simpl; try exact I; lra.
Qed.

(** A 5-term triangle inequality. *)
Lemma Rabs_sum5 : forall x1 x2 x3 x4 x5,
  Rabs (x1 + x2 + x3 + x4 + x5) <= Rabs x1 + Rabs x2 + Rabs x3 + Rabs x4 + Rabs x5.
Proof.
  intros.
  repeat (eapply Rle_trans; [apply Rabs_triang | apply Rplus_le_compat_r]).
  apply Rle_refl.
Qed.

(** The error of [value] against any reals V_i that the products q_i approximate:
    |s − Σ V_i| ≤ u|s_2 + q_2| + u|q_0 + q_1| + Σ |q_i − V_i| ≤ (2u + u²) Σ|q_i| + Σ |q_i − V_i|. *)
Lemma dot3_value_error : forall a0 a1 a2 b0 b1 b2 V0 V1 V2 e0 e1 e2,
  let r := dot3_rounded a0 a1 a2 b0 b1 b2 in
  Rabs (product0 r - V0) <= e0 -> Rabs (product1 r - V1) <= e1 -> Rabs (product2 r - V2) <= e2 ->
  Rabs (value r - (V0 + V1 + V2)) <=
    (2 * u + u * u) * (Rabs (product0 r) + Rabs (product1 r) + Rabs (product2 r)) + e0 + e1 + e2.
Proof.
  intros a0 a1 a2 b0 b1 b2 V0 V1 V2 e0 e1 e2 r H0 H1 H2. subst r. simpl in *.
  set (q0 := RN (a0 * b0)) in *. set (q1 := RN (a1 * b1)) in *. set (q2 := RN (a2 * b2)) in *.
  assert (Bq0 : binary64 q0) by apply binary64_RN.
  assert (Bq1 : binary64 q1) by apply binary64_RN.
  assert (Bq2 : binary64 q2) by apply binary64_RN.
  set (s2 := RN (q0 + q1)). set (s := RN (s2 + q2)).
  assert (Bs2 : binary64 s2) by apply binary64_RN.
  pose proof (RN_plus_err _ _ Bq0 Bq1) as E2. fold s2 in E2.
  pose proof (RN_plus_err _ _ Bs2 Bq2) as E3. fold s in E3.
  pose proof (Rabs_triang q0 q1) as T1. pose proof (Rabs_triang s2 q2) as T2.
  pose proof u_pos as Hu.
  assert (S2 : Rabs s2 <= Rabs (q0 + q1) + u * Rabs (q0 + q1)) by (apply Rabs_close; exact E2).
  pose proof (Rabs_sum5 (s - (s2 + q2)) (s2 - (q0 + q1)) (q0 - V0) (q1 - V1) (q2 - V2)) as T.
  replace (s - (s2 + q2) + (s2 - (q0 + q1)) + (q0 - V0) + (q1 - V1) + (q2 - V2))
    with (s - (V0 + V1 + V2)) in T by ring.
  pose proof (Rabs_pos (q0 + q1)). pose proof (Rabs_pos q2).
  rewrite u_val in *. nra.
Qed.

(** ** The error of stage 1's value for den and for num. *)

(** den: |s − d·n| ≤ (3u + u²)·Σ|q_i| + 3(1 + u)η. *)
Lemma den_value_error : forall d0 d1 d2 n0 n1 n2,
  let r := dot3_rounded d0 d1 d2 n0 n1 n2 in
  Rabs (value r - (d0 * n0 + d1 * n1 + d2 * n2)) <=
    (3 * u + u * u) * (Rabs (product0 r) + Rabs (product1 r) + Rabs (product2 r)) + 3 * (1 + u) * eta.
Proof.
  intros d0 d1 d2 n0 n1 n2 r. pose proof u_pos as Hu. pose proof eta_pos as He.
  pose proof (RN_err_round (d0 * n0)) as E0. pose proof (RN_err_round (d1 * n1)) as E1.
  pose proof (RN_err_round (d2 * n2)) as E2.
  pose proof (dot3_value_error d0 d1 d2 n0 n1 n2 _ _ _ _ _ _ E0 E1 E2) as H. fold r in H.
  subst r. simpl in H |- *. rewrite u_val in *. lra.
Qed.

(** num, from the rounded differences a_i = p_i ⊖ o_i:
    |s − (p − o)·n| ≤ (4u + 2u²)·Σ|q_i| + 3(1 + u)η. *)
Lemma num_value_error : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  binary64 p0 -> binary64 p1 -> binary64 p2 -> binary64 o0 -> binary64 o1 -> binary64 o2 ->
  let r := dot3_rounded (RN (p0 - o0)) (RN (p1 - o1)) (RN (p2 - o2)) n0 n1 n2 in
  Rabs (value r - ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2)) <=
    (4 * u + 2 * (u * u)) * (Rabs (product0 r) + Rabs (product1 r) + Rabs (product2 r)) + 3 * (1 + u) * eta.
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 Bp0 Bp1 Bp2 Bo0 Bo1 Bo2 r.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  (* one product term: |RN(a n) − (p − o) n| ≤ (2u + u²)|q| + (1 + u)η *)
  assert (Term : forall p o n, binary64 p -> binary64 o ->
    Rabs (RN (RN (p - o) * n) - (p - o) * n) <=
      (2 * u + u * u) * Rabs (RN (RN (p - o) * n)) + (1 + u) * eta).
  { intros p o n Bp Bo.
    set (a := RN (p - o)). set (q := RN (a * n)).
    pose proof (RN_minus_err_round p o Bp Bo) as Ea. fold a in Ea.
    pose proof (RN_err_round (a * n)) as Eq. fold q in Eq.
    assert (D : Rabs ((a - (p - o)) * n) <= u * Rabs (a * n)).
    { rewrite Rabs_mult, (Rabs_mult a n), <- Rmult_assoc.
      apply Rmult_le_compat_r; [apply Rabs_pos | exact Ea]. }
    assert (An : Rabs (a * n) <= Rabs q + (u * Rabs q + eta)).
    { apply Rabs_close'. exact Eq. }
    replace (q - (p - o) * n) with ((q - a * n) + (a - (p - o)) * n) by ring.
    eapply Rle_trans; [apply Rabs_triang|].
    rewrite u_val in *. pose proof (Rabs_pos q). nra. }
  pose proof (Term p0 o0 n0 Bp0 Bo0) as E0. pose proof (Term p1 o1 n1 Bp1 Bo1) as E1.
  pose proof (Term p2 o2 n2 Bp2 Bo2) as E2.
  pose proof (dot3_value_error _ _ _ n0 n1 n2 _ _ _ _ _ _ E0 E1 E2) as H. fold r in H.
  subst r. simpl in H |- *. rewrite u_val in *. lra.
Qed.

(** The constants cover the errors: K(1 + u)³ ≤ C(1 − u) for K = 3u + u², C = (3 + 16u)u and for
    K = 4u + 2u², C = (4 + 32u)u. *)
Lemma filter_den_relative_covers :
  (3 * u + u * u) * ((1 + u) * (1 + u) * (1 + u)) <= filter_den_relative * (1 - u).
Proof. unfold filter_den_relative. rewrite u_val. lra. Qed.

Lemma filter_num_relative_covers :
  (4 * u + 2 * (u * u)) * ((1 + u) * (1 + u) * (1 + u)) <= filter_num_relative * (1 - u).
Proof. unfold filter_num_relative. rewrite u_val. lra. Qed.

(** ** The stage-1 enclosures: |s − V| ≤ (C ⊗ m) ⊕ 3μ for den and for num (what the comparison of two
    quotients, issue 5, starts from). *)
Corollary den_filter_encloses : forall d0 d1 d2 n0 n1 n2,
  let r := dot3_rounded d0 d1 d2 n0 n1 n2 in
  Rabs (value r - (d0 * n0 + d1 * n1 + d2 * n2)) <= filter_bound r filter_den_relative.
Proof.
  intros. pose proof u_pos. apply dot3_filter_bound_encloses with (K := 3 * u + u * u).
  - nra.
  - apply filter_den_relative_covers.
  - apply den_value_error.
Qed.

Corollary num_filter_encloses : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  binary64 p0 -> binary64 p1 -> binary64 p2 -> binary64 o0 -> binary64 o1 -> binary64 o2 ->
  let r := dot3_rounded (RN (p0 - o0)) (RN (p1 - o1)) (RN (p2 - o2)) n0 n1 n2 in
  Rabs (value r - ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2)) <= filter_bound r filter_num_relative.
Proof.
  intros. pose proof u_pos. apply dot3_filter_bound_encloses with (K := 4 * u + 2 * (u * u)).
  - nra.
  - apply filter_num_relative_covers.
  - now apply num_value_error.
Qed.

(** ** Main theorems. *)

(** den = d·n with exact inputs: the certified sign is the sign of the exact value (zero only when
    every term has a zero factor). *)
Theorem den_filter_sound : forall d0 d1 d2 n0 n1 n2,
  certifies (den_filter d0 d1 d2 n0 n1 n2) (d0 * n0 + d1 * n1 + d2 * n2).
Proof.
  intros d0 d1 d2 n0 n1 n2.
  unfold den_filter.
  destruct (den_trivially_zero d0 d1 d2 n0 n1 n2) eqn:Z.
  - (* every term has a zero factor *)
    simpl. unfold den_trivially_zero in Z.
    repeat rewrite Bool.andb_true_iff in Z. repeat rewrite Bool.orb_true_iff in Z.
    destruct Z as [[Z0 Z1] Z2].
    assert (T : forall x y, Req_bool x 0 = true \/ Req_bool y 0 = true -> x * y = 0).
    { intros x y [H|H]; apply Req_bool_true_iff in H; subst; ring. }
    rewrite (T _ _ Z0), (T _ _ Z1), (T _ _ Z2). ring.
  - pose proof u_pos.
    apply dot3_filter_sound_gen with (K := 3 * u + u * u).
    + nra.
    + apply filter_den_relative_covers.
    + apply den_value_error.
Qed.

(** num = (p − o)·n where the code multiplies the rounded differences p_i ⊖ o_i. *)
Theorem num_filter_sound : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  binary64 p0 -> binary64 p1 -> binary64 p2 -> binary64 o0 -> binary64 o1 -> binary64 o2 ->
  certifies (num_filter p0 p1 p2 o0 o1 o2 n0 n1 n2)
    ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 Bp0 Bp1 Bp2 Bo0 Bo1 Bo2.
  unfold num_filter.
  destruct (num_trivially_zero p0 p1 p2 o0 o1 o2 n0 n1 n2) eqn:Z.
  - simpl. unfold num_trivially_zero in Z.
    repeat rewrite Bool.andb_true_iff in Z. repeat rewrite Bool.orb_true_iff in Z.
    destruct Z as [[Z0 Z1] Z2].
    assert (T : forall p o n, Req_bool p o = true \/ Req_bool n 0 = true -> (p - o) * n = 0).
    { intros p o n [H|H]; apply Req_bool_true_iff in H; subst; ring. }
    rewrite (T _ _ _ Z0), (T _ _ _ Z1), (T _ _ _ Z2). ring.
  - pose proof u_pos.
    apply dot3_filter_sound_gen with (K := 4 * u + 2 * (u * u)).
    + nra.
    + apply filter_num_relative_covers.
    + now apply num_value_error.
Qed.

(** The fast path (fast_path.hpp) calls the filter without the [exactly_zero] flag, per lane:
    [static_cast<Sign>(dot3_filter_lanes(r, C))], which is [dot3_filter r C false]. *)
Corollary den_filter_lanes_sound : forall d0 d1 d2 n0 n1 n2,
  certifies (sign_from_Z (dot3_filter_lanes (dot3_rounded d0 d1 d2 n0 n1 n2) filter_den_relative))
    (d0 * n0 + d1 * n1 + d2 * n2).
Proof.
  intros. pose proof u_pos.
  apply (dot3_filter_sound_gen d0 d1 d2 n0 n1 n2 _ filter_den_relative (3 * u + u * u)).
  - nra.
  - apply filter_den_relative_covers.
  - apply den_value_error.
Qed.

Corollary num_filter_lanes_sound : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  binary64 p0 -> binary64 p1 -> binary64 p2 -> binary64 o0 -> binary64 o1 -> binary64 o2 ->
  certifies (sign_from_Z (dot3_filter_lanes
               (dot3_rounded (RN (p0 - o0)) (RN (p1 - o1)) (RN (p2 - o2)) n0 n1 n2) filter_num_relative))
    ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2).
Proof.
  intros. pose proof u_pos.
  apply (dot3_filter_sound_gen _ _ _ n0 n1 n2 _ filter_num_relative (4 * u + 2 * (u * u))).
  - nra.
  - apply filter_num_relative_covers.
  - now apply num_value_error.
Qed.

(** A lane sign of the filter is −1, +1 or 2 (uncertain): the fast path never certifies zero. *)
Lemma dot3_filter_lanes_range : forall r C, lane_sign (dot3_filter_lanes r C).
Proof. intros. apply sign_lanes_range. Qed.
