(** * Comparing two quotients: the nearest-hit order (kernel/src/nearest/compare_quotients.hpp).

    nearest_hit orders t_1 = N_1/D_1 and t_2 = N_2/D_2 by the sign of Δ = N_1·D_2 − N_2·D_1, each of the
    four values known through an enclosure from the cascade of its own query.

    - [compare_quotients_filter_sound]: [compare_quotients_filter] (stage 1).  If the four one-double
      enclosures |x − V| ≤ e hold, the sign it certifies is the sign of Δ.  The stage-1 enclosures it is
      applied to are PlaneFilter.v's [den_filter_encloses] and [num_filter_encloses] (through
      [filter_enclosure_encloses]).
    - [compare_quotients_compensated_enclosure]: [compare_quotients_compensated] (stage 2).  If the four
      double-double enclosures hold (PlaneCompensated.v's [compensated_den_enclosure] and
      [compensated_num_enclosure]), the result encloses Δ; [enclosure_sign_sound] then gives its sign.
    - [quotient_order_sign]: over the reals, sign(t_1 − t_2) = sign(Δ)·sign(D_1)·sign(D_2);
      [hit_distance_order_correct]: the order nearest_hit.cpp's [compare_hit_distances] derives from a
      certain sign of Δ and the den signs is the order of the exact quotients; [origin_order_correct]:
      the same for its shortcut for a plane through the origin.  PlaneCascade.v composes these with the two
      stages above ([compare_hit_distances_filter_correct], [compare_hit_distances_compensated_correct]).

    The derivation is the one in kernel/src/core/error_bounds.hpp, "Comparing two quotients". *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core Relative.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification.
Open Scope R_scope.

(** ** The C++ code, operation by operation. *)

(** [struct RoundedEnclosure { value, radius }]: the claim |V − value| ≤ radius. *)
Record RoundedEnclosure := { rounded_value : R; rounded_radius : R }.

Definition rounded_encloses (e : RoundedEnclosure) (V : R) : Prop :=
  Rabs (rounded_value e - V) <= rounded_radius e.

(** [filter_enclosure(r, relative_constant)]: {s, (C ⊗ m) ⊕ 3μ}, the bound of [dot3_filter]. *)
Definition filter_enclosure (r : Dot3Rounded) (relative_constant : R) : RoundedEnclosure :=
  {| rounded_value := value r;
     rounded_radius := RN (RN (relative_constant * magnitude r) + filter_absolute) |}.

(** [compare_propagated_error]:
    R = ((|x_1| ⊗ f_2) ⊕ (e_1 ⊗ (|y_2| ⊕ f_2))) ⊕ ((|x_2| ⊗ f_1) ⊕ (e_2 ⊗ (|y_1| ⊕ f_1))). *)
Definition compare_propagated_error (x1 e1 y1 f1 x2 e2 y2 f2 : R) : R :=
  RN (RN (RN (Rabs x1 * f2) + RN (e1 * RN (Rabs y2 + f2))) +
      RN (RN (Rabs x2 * f1) + RN (e2 * RN (Rabs y1 + f1)))).

(** [compare_quotients_filter(n1, d1, n2, d2)]: P = x_1 ⊗ y_2, Q = x_2 ⊗ y_1, δ = P ⊖ Q,
    M = |P| ⊕ |Q|, B = ((C_f ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c; δ > B ⇒ positive, δ < −B ⇒ negative. *)
Definition compare_quotients_filter (n1 d1 n2 d2 : RoundedEnclosure) : sign :=
  let p := RN (rounded_value n1 * rounded_value d2) in
  let q := RN (rounded_value n2 * rounded_value d1) in
  let delta := RN (p - q) in
  let magnitude := RN (Rabs p + Rabs q) in
  let propagated :=
    compare_propagated_error (rounded_value n1) (rounded_radius n1) (rounded_value d1) (rounded_radius d1)
      (rounded_value n2) (rounded_radius n2) (rounded_value d2) (rounded_radius d2) in
  let bound :=
    RN (RN (RN (compare_filter_relative * magnitude) + RN (compare_propagation_factor * propagated)) +
        compare_absolute) in
  if Rlt_bool bound delta then Positive
  else if Rlt_bool delta (- bound) then Negative
  else Uncertain.

(** [compare_quotients_compensated(n1, d1, n2, d2)].  The C++ replaces the radius by +inf when S or lo
    is not finite: in the model nothing overflows, so that branch is not taken (proofs/README.md,
    "Overflow"). *)
Definition compare_quotients_compensated (n1 d1 n2 d2 : Enclosure) : Enclosure :=
  let a1 := two_sum (hi n1) (lo n1) in
  let b1 := two_sum (hi d1) (lo d1) in
  let a2 := two_sum (hi n2) (lo n2) in
  let b2 := two_sum (hi d2) (lo d2) in
  let p := two_prod (fst a1) (fst b2) in
  let q := two_prod (fst a2) (fst b1) in
  let c1 := fma (fst a1) (snd b2) (RN (snd a1 * fst b2)) in
  let c2 := fma (fst a2) (snd b1) (RN (snd a2 * fst b1)) in
  let s := two_sum (fst p) (- fst q) in
  let lo := RN (RN (RN (snd p - snd q) + RN (c1 - c2)) + snd s) in
  let magnitude := RN (Rabs (fst p) + Rabs (fst q)) in
  let propagated :=
    compare_propagated_error (fst a1) (radius n1) (fst b1) (radius d1)
      (fst a2) (radius n2) (fst b2) (radius d2) in
  let radius :=
    RN (RN (RN (compare_compensated_relative * magnitude) + RN (compare_propagation_factor * propagated)) +
        compare_absolute) in
  {| hi := fst s; lo := lo; radius := radius |}.

(** ** Rounding facts: lower bounds of a rounded non-negative value. *)

Lemma binary64_compare_absolute : binary64 compare_absolute.
Proof. apply constants_binary64. Qed.

Lemma compare_absolute_eta : compare_absolute = 16 * eta.
Proof. unfold compare_absolute. rewrite min_subnormal_eta. ring. Qed.

(** z ≤ (1 + u)·RN(z) + η for z ≥ 0. *)
Lemma RN_nonneg_lower : forall z, 0 <= z -> 0 <= RN z /\ z <= (1 + u) * RN z + eta.
Proof.
  intros z Hz. pose proof (RN_err_round z) as E. pose proof (RN_nonneg z Hz) as P.
  rewrite (Rabs_nonneg_eq (RN z) P) in E. apply Rabs_bounds in E. split; [exact P | lra].
Qed.

(** a + b ≤ (1 + u)·RN(a + b) for doubles a, b with a + b ≥ 0 (no η: Hauser). *)
Lemma RN_sum_lower : forall a b, binary64 a -> binary64 b -> 0 <= a + b ->
  0 <= RN (a + b) /\ a + b <= (1 + u) * RN (a + b).
Proof.
  intros a b Ba Bb H. pose proof (RN_plus_err_round a b Ba Bb) as E.
  pose proof (RN_nonneg (a + b) H) as P.
  rewrite (Rabs_nonneg_eq _ P) in E. apply Rabs_bounds in E. split; [exact P | lra].
Qed.

Lemma Rabs_sub3 : forall x y z, Rabs (x - y - z) <= Rabs x + Rabs y + Rabs z.
Proof.
  intros x y z. unfold Rminus.
  pose proof (Rabs_triang (x + - y) (- z)). pose proof (Rabs_triang x (- y)).
  rewrite !Rabs_Ropp in *. lra.
Qed.

(** ** The computed error bound. *)

(** Half of R: t = (|x| ⊗ f) ⊕ (e ⊗ (|y| ⊕ f)) ≥ (|x| f + e (|y| + f) − (2 + u)η)/(1 + u)³. *)
Lemma propagated_half : forall x e y f, binary64 y -> binary64 f -> 0 <= e -> 0 <= f ->
  let t := RN (RN (Rabs x * f) + RN (e * RN (Rabs y + f))) in
  0 <= t /\ Rabs x * f + e * (Rabs y + f) <= (1 + u) * (1 + u) * (1 + u) * t + (2 + u) * eta.
Proof.
  intros x e y f By Bf He Hf t.
  pose proof u_pos as Hu. pose proof eta_pos as Heta. pose proof (Rabs_pos x) as Ax.
  destruct (RN_nonneg_lower (Rabs x * f) ltac:(nra)) as [P1 L1].
  set (t1 := RN (Rabs x * f)) in *.
  destruct (RN_sum_lower (Rabs y) f (binary64_abs y By) Bf ltac:(pose proof (Rabs_pos y); lra)) as [Pw Lw].
  set (w := RN (Rabs y + f)) in *.
  destruct (RN_nonneg_lower (e * w) ltac:(nra)) as [P2 L2].
  set (t2 := RN (e * w)) in *.
  destruct (RN_sum_lower t1 t2 (binary64_RN _) (binary64_RN _) ltac:(lra)) as [Pt Lt].
  fold t in Pt, Lt.
  assert (Ew : e * (Rabs y + f) <= (1 + u) * (e * w)).
  { replace ((1 + u) * (e * w)) with (e * ((1 + u) * w)) by ring. apply Rmult_le_compat_l; lra. }
  split; [exact Pt|].
  rewrite u_val in *. nra.
Qed.

(** R ≥ (ρ − 2(2 + u)η)/(1 + u)⁴ with ρ = |x_1| f_2 + e_1 (|y_2| + f_2) + |x_2| f_1 + e_2 (|y_1| + f_1). *)
Lemma compare_propagated_error_lower : forall x1 e1 y1 f1 x2 e2 y2 f2,
  binary64 y1 -> binary64 f1 -> binary64 y2 -> binary64 f2 ->
  0 <= e1 -> 0 <= f1 -> 0 <= e2 -> 0 <= f2 ->
  let R := compare_propagated_error x1 e1 y1 f1 x2 e2 y2 f2 in
  0 <= R /\
  Rabs x1 * f2 + e1 * (Rabs y2 + f2) + (Rabs x2 * f1 + e2 * (Rabs y1 + f1)) <=
    (1 + u) * (1 + u) * (1 + u) * (1 + u) * R + 2 * (2 + u) * eta.
Proof.
  intros x1 e1 y1 f1 x2 e2 y2 f2 By1 Bf1 By2 Bf2 He1 Hf1 He2 Hf2 R.
  destruct (propagated_half x1 e1 y2 f2 By2 Bf2 He1 Hf2) as [P1 L1].
  destruct (propagated_half x2 e2 y1 f1 By1 Bf1 He2 Hf1) as [P2 L2].
  set (t1 := RN (RN (Rabs x1 * f2) + RN (e1 * RN (Rabs y2 + f2)))) in *.
  set (t2 := RN (RN (Rabs x2 * f1) + RN (e2 * RN (Rabs y1 + f1)))) in *.
  destruct (RN_sum_lower t1 t2 (binary64_RN _) (binary64_RN _) ltac:(lra)) as [P L].
  unfold R, compare_propagated_error. fold t1 t2.
  split; [exact P|].
  pose proof u_pos. rewrite u_val in *. lra.
Qed.

(** The bound of both stages, ((K ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c, is at least
    (K·M + C_p·R + (1 + u)² U_c − 2η)/(1 + u)³. *)
Lemma compare_bound_lower : forall K M R, 0 <= K * M -> 0 <= R ->
  let B := RN (RN (RN (K * M) + RN (compare_propagation_factor * R)) + compare_absolute) in
  K * M + compare_propagation_factor * R + (1 + u) * (1 + u) * compare_absolute <=
    (1 + u) * (1 + u) * (1 + u) * B + 2 * eta.
Proof.
  intros K M R HKM HR B.
  pose proof u_pos. pose proof eta_pos.
  assert (HCp : 0 <= compare_propagation_factor * R).
  { unfold compare_propagation_factor. nra. }
  destruct (RN_nonneg_lower _ HKM) as [P1 L1].
  destruct (RN_nonneg_lower _ HCp) as [P2 L2].
  set (r1 := RN (K * M)) in *. set (r2 := RN (compare_propagation_factor * R)) in *.
  destruct (RN_sum_lower r1 r2 (binary64_RN _) (binary64_RN _) ltac:(lra)) as [P3 L3].
  set (r3 := RN (r1 + r2)) in *.
  assert (PU : 0 <= compare_absolute) by (rewrite compare_absolute_eta; lra).
  destruct (RN_sum_lower r3 compare_absolute (binary64_RN _) binary64_compare_absolute ltac:(lra))
    as [P4 L4].
  fold B in P4, L4.
  rewrite u_val in *. lra.
Qed.

(** ** The propagated input error. *)

Lemma propagated_nonneg : forall x e y f, 0 <= e -> 0 <= f -> 0 <= Rabs x * f + e * (Rabs y + f).
Proof.
  intros x e y f He Hf. pose proof (Rabs_pos x). pose proof (Rabs_pos y).
  apply Rplus_le_le_0_compat; apply Rmult_le_pos; lra.
Qed.

(** |N·D − x·y| ≤ |x|·f + e·(|y| + f) for |x − N| ≤ e, |y − D| ≤ f. *)
Lemma input_error : forall N D x y e f, Rabs (x - N) <= e -> Rabs (y - D) <= f ->
  Rabs (N * D - x * y) <= Rabs x * f + e * (Rabs y + f).
Proof.
  intros N D x y e f HN HD.
  replace (N * D - x * y) with (- (x * (y - D)) - (x - N) * y + (x - N) * (y - D)) by ring.
  set (a := x - N) in *. set (b := y - D) in *.
  eapply Rle_trans; [apply Rabs_triang|].
  unfold Rminus. eapply Rle_trans; [apply Rplus_le_compat_r, Rabs_triang|].
  rewrite !Rabs_Ropp, !Rabs_mult.
  pose proof (Rabs_pos a). pose proof (Rabs_pos b). pose proof (Rabs_pos x). pose proof (Rabs_pos y).
  assert (Rabs x * Rabs b <= Rabs x * f) by (apply Rmult_le_compat_l; lra).
  assert (Rabs a * Rabs y <= e * Rabs y) by (apply Rmult_le_compat_r; lra).
  assert (Rabs a * Rabs b <= e * f) by (apply Rmult_le_compat; lra).
  lra.
Qed.

(** The same around a double-double a + α, b + β with |α| ≤ u|a|, |β| ≤ u|b|:
    |N·D − (a + α)(b + β)| ≤ (1 + u)·(|a|·f + e·(|b| + f)). *)
Lemma input_error_dd : forall N D a al b bl e f,
  Rabs al <= u * Rabs a -> Rabs bl <= u * Rabs b ->
  Rabs (a + al - N) <= e -> Rabs (b + bl - D) <= f ->
  Rabs (N * D - (a + al) * (b + bl)) <= (1 + u) * (Rabs a * f + e * (Rabs b + f)).
Proof.
  intros N D a al b bl e f Hal Hbl HN HD.
  eapply Rle_trans; [exact (input_error N D (a + al) (b + bl) e f HN HD)|].
  pose proof u_pos. pose proof (Rabs_pos a). pose proof (Rabs_pos b).
  assert (He : 0 <= e) by (eapply Rle_trans; [apply Rabs_pos | exact HN]).
  assert (Hf : 0 <= f) by (eapply Rle_trans; [apply Rabs_pos | exact HD]).
  assert (A : Rabs (a + al) <= (1 + u) * Rabs a) by (pose proof (Rabs_triang a al); lra).
  assert (B : Rabs (b + bl) <= (1 + u) * Rabs b) by (pose proof (Rabs_triang b bl); lra).
  assert (Rabs (a + al) * f <= (1 + u) * Rabs a * f) by (apply Rmult_le_compat_r; lra).
  assert (e * (Rabs (b + bl) + f) <= e * ((1 + u) * Rabs b + f)) by (apply Rmult_le_compat_l; lra).
  assert (e * f <= (1 + u) * (e * f)) by (assert (0 <= e * f) by nra; nra).
  lra.
Qed.

(** ** Stage 1. *)

(** The stage-1 enclosure of a dot product (PlaneFilter.v) is a [RoundedEnclosure] of it. *)
Lemma filter_enclosure_encloses : forall r C V,
  Rabs (value r - V) <= filter_bound r C -> rounded_encloses (filter_enclosure r C) V.
Proof. intros r C V H. exact H. Qed.

Lemma filter_enclosure_binary64 : forall a0 a1 a2 b0 b1 b2 C,
  let e := filter_enclosure (dot3_rounded a0 a1 a2 b0 b1 b2) C in
  binary64 (rounded_value e) /\ binary64 (rounded_radius e).
Proof. intros. split; apply binary64_RN. Qed.

(** The error of δ: |Δ − δ| ≤ ρ + 2u(|P| + |Q|) + 2η. *)
Lemma filter_delta_error : forall N1 D1 N2 D2 x1 e1 y1 f1 x2 e2 y2 f2,
  Rabs (x1 - N1) <= e1 -> Rabs (y1 - D1) <= f1 -> Rabs (x2 - N2) <= e2 -> Rabs (y2 - D2) <= f2 ->
  let P := RN (x1 * y2) in let Q := RN (x2 * y1) in
  Rabs (N1 * D2 - N2 * D1 - RN (P - Q)) <=
    Rabs x1 * f2 + e1 * (Rabs y2 + f2) + (Rabs x2 * f1 + e2 * (Rabs y1 + f1)) +
    2 * u * (Rabs P + Rabs Q) + 2 * eta.
Proof.
  intros N1 D1 N2 D2 x1 e1 y1 f1 x2 e2 y2 f2 H1 G1 H2 G2 P Q.
  pose proof (input_error N1 D2 x1 y2 e1 f2 H1 G2) as I1.
  pose proof (input_error N2 D1 x2 y1 e2 f1 H2 G1) as I2.
  pose proof (RN_err_round (x1 * y2)) as EP. fold P in EP.
  pose proof (RN_err_round (x2 * y1)) as EQ. fold Q in EQ.
  pose proof (RN_minus_err P Q (binary64_RN _) (binary64_RN _)) as ED.
  assert (T : u * Rabs (P - Q) <= u * (Rabs P + Rabs Q)).
  { apply Rmult_le_compat_l; [pose proof u_pos; lra|].
    unfold Rminus. rewrite <- (Rabs_Ropp Q). apply Rabs_triang. }
  replace (N1 * D2 - N2 * D1 - RN (P - Q))
    with ((N1 * D2 - x1 * y2) - (N2 * D1 - x2 * y1) - (P - x1 * y2) + (Q - x2 * y1) - (RN (P - Q) - (P - Q)))
    by ring.
  set (z1 := N1 * D2 - x1 * y2) in *. set (z2 := N2 * D1 - x2 * y1) in *.
  set (z3 := P - x1 * y2) in *. set (z4 := Q - x2 * y1) in *. set (z5 := RN (P - Q) - (P - Q)) in *.
  assert (Rabs (z1 - z2 - z3 + z4 - z5) <= Rabs z1 + Rabs z2 + Rabs z3 + Rabs z4 + Rabs z5).
  { pose proof (Rabs_sum5 z1 (- z2) (- z3) z4 (- z5)) as S. rewrite !Rabs_Ropp in S.
    replace (z1 - z2 - z3 + z4 - z5) with (z1 + - z2 + - z3 + z4 + - z5) by ring. exact S. }
  lra.
Qed.

(** ** Main theorem of stage 1: for all reals N_i, D_i enclosed by the four arguments,
    |x_i − N_i| ≤ e_i and |y_i − D_i| ≤ f_i, a sign certified by [compare_quotients_filter] is the sign
    of Δ = N_1·D_2 − N_2·D_1.  Only the y_i and f_i (the den side, added to each other) must be doubles;
    e_i, f_i ≥ 0 follows from the enclosures. *)
Theorem compare_quotients_filter_sound : forall (n1 d1 n2 d2 : RoundedEnclosure) (N1 D1 N2 D2 : R),
  binary64 (rounded_value d1) -> binary64 (rounded_radius d1) ->
  binary64 (rounded_value d2) -> binary64 (rounded_radius d2) ->
  rounded_encloses n1 N1 -> rounded_encloses d1 D1 -> rounded_encloses n2 N2 -> rounded_encloses d2 D2 ->
  certifies (compare_quotients_filter n1 d1 n2 d2) (N1 * D2 - N2 * D1).
Proof.
  intros [x1 e1] [y1 f1] [x2 e2] [y2 f2] N1 D1 N2 D2 By1 Bf1 By2 Bf2 H1 G1 H2 G2.
  unfold rounded_encloses in *. cbn [rounded_value rounded_radius] in *.
  unfold compare_quotients_filter. cbn [rounded_value rounded_radius].
  pose proof (filter_delta_error N1 D1 N2 D2 x1 e1 y1 f1 x2 e2 y2 f2 H1 G1 H2 G2) as Err.
  cbv zeta in Err.
  set (P := RN (x1 * y2)) in *. set (Q := RN (x2 * y1)) in *.
  set (delta := RN (P - Q)) in *.
  assert (He1 : 0 <= e1) by (eapply Rle_trans; [apply Rabs_pos | exact H1]).
  assert (He2 : 0 <= e2) by (eapply Rle_trans; [apply Rabs_pos | exact H2]).
  assert (Hf1 : 0 <= f1) by (eapply Rle_trans; [apply Rabs_pos | exact G1]).
  assert (Hf2 : 0 <= f2) by (eapply Rle_trans; [apply Rabs_pos | exact G2]).
  destruct (compare_propagated_error_lower x1 e1 y1 f1 x2 e2 y2 f2 By1 Bf1 By2 Bf2 He1 Hf1 He2 Hf2)
    as [PR LR].
  set (R := compare_propagated_error x1 e1 y1 f1 x2 e2 y2 f2) in *.
  set (rho := Rabs x1 * f2 + e1 * (Rabs y2 + f2) + (Rabs x2 * f1 + e2 * (Rabs y1 + f1))) in *.
  destruct (RN_sum_lower (Rabs P) (Rabs Q) (binary64_abs _ (binary64_RN _)) (binary64_abs _ (binary64_RN _))
              ltac:(pose proof (Rabs_pos P); pose proof (Rabs_pos Q); lra)) as [PM LM].
  set (M := RN (Rabs P + Rabs Q)) in *.
  pose proof u_pos. pose proof eta_pos.
  assert (HKM : 0 <= compare_filter_relative * M).
  { apply Rmult_le_pos; [unfold compare_filter_relative; rewrite u_val; lra | exact PM]. }
  pose proof (compare_bound_lower compare_filter_relative M R HKM PR) as LB. cbv zeta in LB.
  set (B := RN (RN (RN (compare_filter_relative * M) + RN (compare_propagation_factor * R)) +
                compare_absolute)) in *.
  assert (Hrho : 0 <= rho).
  { apply Rplus_le_le_0_compat; apply propagated_nonneg; assumption. }
  pose proof (Rabs_pos P). pose proof (Rabs_pos Q).
  assert (Enc : Rabs (N1 * D2 - N2 * D1 - delta) <= B).
  { clearbody R rho M B P Q delta.
    unfold compare_filter_relative, compare_propagation_factor in *. rewrite compare_absolute_eta in LB.
    rewrite u_val in *. lra. }
  apply Rabs_bounds in Enc.
  destruct (Rlt_bool_spec B delta) as [L|L]; [simpl; lra|].
  destruct (Rlt_bool_spec delta (- B)) as [L'|L']; simpl; [lra | exact I].
Qed.

(** ** Stage 2.  ([two_prod_error], TwoProduct exact up to η, is in Model.v.) *)

(** The cross terms: c = fma(a, β, α ⊗ b) approximates a·β + α·b, and α·β is dropped:
    |(a + α)(b + β) − a·b − c| ≤ (4u² + u³)|a·b| + (2 + u)η and |c| ≤ (2u + 3u² + u³)|a·b| + (2 + u)η. *)
Lemma cross_terms : forall a al b bl, Rabs al <= u * Rabs a -> Rabs bl <= u * Rabs b ->
  let c := fma a bl (RN (al * b)) in
  Rabs ((a + al) * (b + bl) - a * b - c) <= (4 * (u * u) + u * u * u) * Rabs (a * b) + (2 + u) * eta /\
  Rabs c <= (2 * u + 3 * (u * u) + u * u * u) * Rabs (a * b) + (2 + u) * eta.
Proof.
  intros a al b bl Ha Hb c.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  pose proof (Rabs_pos a). pose proof (Rabs_pos b). pose proof (Rabs_pos al). pose proof (Rabs_pos bl).
  assert (Hpi : Rabs (a * b) = Rabs a * Rabs b) by apply Rabs_mult.
  assert (X1 : Rabs (a * bl) <= u * Rabs (a * b)).
  { rewrite Rabs_mult, Hpi. replace (u * (Rabs a * Rabs b)) with (Rabs a * (u * Rabs b)) by ring.
    apply Rmult_le_compat_l; lra. }
  assert (X2 : Rabs (al * b) <= u * Rabs (a * b)).
  { rewrite Rabs_mult, Hpi, <- Rmult_assoc. apply Rmult_le_compat_r; lra. }
  assert (X3 : Rabs (al * bl) <= u * u * Rabs (a * b)).
  { rewrite Rabs_mult, Hpi. replace (u * u * (Rabs a * Rabs b)) with ((u * Rabs a) * (u * Rabs b)) by ring.
    apply Rmult_le_compat; lra. }
  set (w := RN (al * b)) in c.
  pose proof (RN_err (al * b)) as Ew. fold w in Ew.
  assert (Hw : Rabs w <= Rabs (al * b) + (u * Rabs (al * b) + eta)) by (apply Rabs_close; exact Ew).
  pose proof (Rabs_triang (a * bl) w) as Tw.
  pose proof (RN_err (a * bl + w)) as Ec.
  replace (RN (a * bl + w)) with c in Ec by reflexivity.
  assert (Hc : Rabs c <= Rabs (a * bl + w) + (u * Rabs (a * bl + w) + eta)) by (apply Rabs_close; exact Ec).
  pose proof (Rabs_pos (al * b)). pose proof (Rabs_pos (a * bl + w)). pose proof (Rabs_pos (a * b)).
  split.
  - replace ((a + al) * (b + bl) - a * b - c)
      with (al * bl - (w - al * b) - (c - (a * bl + w))) by ring.
    eapply Rle_trans; [apply Rabs_sub3|].
    rewrite u_val in *. lra.
  - rewrite u_val in *. lra.
Qed.

(** One side of Δ, N·D with N ≈ a + α, D ≈ b + β: (P, p) = TwoProduct(a, b), c the cross terms.
    |N·D − (P + p + c)| ≤ (1 + u)ρ_i + (4u² + u³)((1 + u)|P| + η) + (3 + u)η, and the sizes of p and c. *)
Lemma product_side : forall N D a al b bl e f, binary64 a -> binary64 b ->
  Rabs al <= u * Rabs a -> Rabs bl <= u * Rabs b ->
  Rabs (a + al - N) <= e -> Rabs (b + bl - D) <= f ->
  let P := fst (two_prod a b) in let p := snd (two_prod a b) in
  let c := fma a bl (RN (al * b)) in
  Rabs (N * D - (P + p + c)) <=
    (1 + u) * (Rabs a * f + e * (Rabs b + f)) +
    (4 * (u * u) + u * u * u) * ((1 + u) * Rabs P + eta) + (3 + u) * eta /\
  Rabs p <= u * Rabs P + 2 * eta /\
  Rabs c <= (2 * u + 3 * (u * u) + u * u * u) * ((1 + u) * Rabs P + eta) + (2 + u) * eta.
Proof.
  intros N D a al b bl e f Ba Bb Hal Hbl HN HD P p c.
  pose proof (input_error_dd N D a al b bl e f Hal Hbl HN HD) as I.
  pose proof (two_prod_error a b Ba Bb) as T. fold P p in T.
  destruct (cross_terms a al b bl Hal Hbl) as [C1 C2]. fold c in C1, C2.
  assert (EP : Rabs (P - a * b) <= u * Rabs P + eta) by apply RN_err_round.
  assert (Pi : Rabs (a * b) <= (1 + u) * Rabs P + eta) by (pose proof (Rabs_close' _ _ _ EP); lra).
  pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (Pi' : (4 * (u * u) + u * u * u) * Rabs (a * b) <=
                (4 * (u * u) + u * u * u) * ((1 + u) * Rabs P + eta)) by (apply Rmult_le_compat_l; nra).
  assert (Pi'' : (2 * u + 3 * (u * u) + u * u * u) * Rabs (a * b) <=
                 (2 * u + 3 * (u * u) + u * u * u) * ((1 + u) * Rabs P + eta)) by (apply Rmult_le_compat_l; nra).
  split; [|split].
  - replace (N * D - (P + p + c))
      with ((N * D - (a + al) * (b + bl)) + (a * b - (P + p)) + ((a + al) * (b + bl) - a * b - c)) by ring.
    eapply Rle_trans; [apply Rabs_triang|].
    eapply Rle_trans; [apply Rplus_le_compat_r, Rabs_triang|].
    lra.
  - replace p with ((a * b - P) - (a * b - (P + p))) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp, Rabs_minus_sym. lra.
  - lra.
Qed.

(** The low part: lo = ((p ⊖ q) ⊕ (c_1 ⊖ c_2)) ⊕ s, three roundings of sums of doubles. *)
Lemma lo_sum_error : forall p q c1 c2 s,
  binary64 p -> binary64 q -> binary64 c1 -> binary64 c2 -> binary64 s ->
  Rabs (p - q + (c1 - c2) + s - RN (RN (RN (p - q) + RN (c1 - c2)) + s)) <=
    u * (3 + 3 * u + u * u) * (Rabs p + Rabs q + Rabs c1 + Rabs c2) + u * Rabs s.
Proof.
  intros p q c1 c2 s Bp Bq Bc1 Bc2 Bs.
  set (r1 := RN (p - q)). set (r2 := RN (c1 - c2)). set (r3 := RN (r1 + r2)). set (l := RN (r3 + s)).
  pose proof (RN_minus_err p q Bp Bq) as E1. fold r1 in E1.
  pose proof (RN_minus_err c1 c2 Bc1 Bc2) as E2. fold r2 in E2.
  pose proof (RN_plus_err r1 r2 (binary64_RN _) (binary64_RN _)) as E3. fold r3 in E3.
  pose proof (RN_plus_err r3 s (binary64_RN _) Bs) as E4. fold l in E4.
  assert (A1 : Rabs (p - q) <= Rabs p + Rabs q).
  { unfold Rminus. rewrite <- (Rabs_Ropp q). apply Rabs_triang. }
  assert (A2 : Rabs (c1 - c2) <= Rabs c1 + Rabs c2).
  { unfold Rminus. rewrite <- (Rabs_Ropp c2). apply Rabs_triang. }
  pose proof (Rabs_close _ _ _ E1) as R1. pose proof (Rabs_close _ _ _ E2) as R2.
  pose proof (Rabs_close _ _ _ E3) as R3.
  pose proof (Rabs_triang r1 r2). pose proof (Rabs_triang r3 s).
  replace (p - q + (c1 - c2) + s - l)
    with (- (r1 - (p - q)) - (r2 - (c1 - c2)) - (r3 - (r1 + r2)) - (l - (r3 + s))) by ring.
  assert (T : forall y1 y2 y3 y4, Rabs (- y1 - y2 - y3 - y4) <= Rabs y1 + Rabs y2 + Rabs y3 + Rabs y4).
  { intros. unfold Rminus.
    pose proof (Rabs_triang (- y1 + - y2 + - y3) (- y4)). pose proof (Rabs_triang (- y1 + - y2) (- y3)).
    pose proof (Rabs_triang (- y1) (- y2)). rewrite !Rabs_Ropp in *. lra. }
  eapply Rle_trans; [apply T|].
  pose proof u_pos. pose proof (Rabs_pos (p - q)). pose proof (Rabs_pos (c1 - c2)).
  pose proof (Rabs_pos (r1 + r2)). pose proof (Rabs_pos (r3 + s)).
  rewrite u_val in *. lra.
Qed.

Lemma compare_compensated_relative_val : compare_compensated_relative = 32 * (u * u).
Proof. unfold compare_compensated_relative. rewrite u_val. simpl bpow. lra. Qed.

(** ** Main theorem of stage 2: for all reals N_i, D_i enclosed by the four double-double enclosures
    (|N_i − (hi + lo)| ≤ radius), [compare_quotients_compensated] encloses Δ = N_1·D_2 − N_2·D_1.
    The hi and lo parts must be doubles (TwoSum, TwoProduct), and so must the radii of D_1 and D_2
    (added to |b_i| in R); the radii are ≥ 0 by the enclosures. *)
Theorem compare_quotients_compensated_enclosure : forall (n1 d1 n2 d2 : Enclosure) (N1 D1 N2 D2 : R),
  binary64 (hi n1) -> binary64 (lo n1) -> binary64 (hi d1) -> binary64 (lo d1) -> binary64 (radius d1) ->
  binary64 (hi n2) -> binary64 (lo n2) -> binary64 (hi d2) -> binary64 (lo d2) -> binary64 (radius d2) ->
  encloses n1 N1 -> encloses d1 D1 -> encloses n2 N2 -> encloses d2 D2 ->
  encloses (compare_quotients_compensated n1 d1 n2 d2) (N1 * D2 - N2 * D1).
Proof.
  intros [hn1 ln1 e1] [hd1 ld1 f1] [hn2 ln2 e2] [hd2 ld2 f2] N1 D1 N2 D2
         Bhn1 Bln1 Bhd1 Bld1 Bf1 Bhn2 Bln2 Bhd2 Bld2 Bf2 H1 G1 H2 G2.
  unfold encloses in *. cbn [hi lo radius] in *.
  unfold compare_quotients_compensated. cbn [hi lo radius].
  (* the four renormalized inputs: a + α = hi + lo exactly, |α| ≤ u|a| *)
  assert (Norm : forall h l e V, binary64 h -> binary64 l -> Rabs (V - (h + l)) <= e ->
            Rabs (snd (two_sum h l)) <= u * Rabs (fst (two_sum h l)) /\
            Rabs (fst (two_sum h l) + snd (two_sum h l) - V) <= e /\ binary64 (fst (two_sum h l)) /\
            0 <= e).
  { intros h l e V Bh Bl HV. rewrite (two_sum_exact h l Bh Bl), Rabs_minus_sym.
    split; [apply (two_sum_lo_bound h l Bh Bl)|]. split; [exact HV|]. split; [apply binary64_two_sum_hi|].
    eapply Rle_trans; [apply Rabs_pos | exact HV]. }
  destruct (Norm _ _ _ _ Bhn1 Bln1 H1) as [La1 [Ea1 [Ba1 He1]]].
  destruct (Norm _ _ _ _ Bhd1 Bld1 G1) as [Lb1 [Eb1 [Bb1 Hf1]]].
  destruct (Norm _ _ _ _ Bhn2 Bln2 H2) as [La2 [Ea2 [Ba2 He2]]].
  destruct (Norm _ _ _ _ Bhd2 Bld2 G2) as [Lb2 [Eb2 [Bb2 Hf2]]].
  clear Norm H1 G1 H2 G2.
  set (a1 := fst (two_sum hn1 ln1)) in *. set (al1 := snd (two_sum hn1 ln1)) in *.
  set (b1 := fst (two_sum hd1 ld1)) in *. set (bl1 := snd (two_sum hd1 ld1)) in *.
  set (a2 := fst (two_sum hn2 ln2)) in *. set (al2 := snd (two_sum hn2 ln2)) in *.
  set (b2 := fst (two_sum hd2 ld2)) in *. set (bl2 := snd (two_sum hd2 ld2)) in *.
  (* the two sides *)
  destruct (product_side N1 D2 a1 al1 b2 bl2 e1 f2 Ba1 Bb2 La1 Lb2 Ea1 Eb2) as [S1 [Sp Sc1]].
  destruct (product_side N2 D1 a2 al2 b1 bl1 e2 f1 Ba2 Bb1 La2 Lb1 Ea2 Eb1) as [S2 [Sq Sc2]].
  set (P := fst (two_prod a1 b2)) in *. set (p := snd (two_prod a1 b2)) in *.
  set (Q := fst (two_prod a2 b1)) in *. set (q := snd (two_prod a2 b1)) in *.
  set (c1 := fma a1 bl2 (RN (al1 * b2))) in *. set (c2 := fma a2 bl1 (RN (al2 * b1))) in *.
  assert (BP : binary64 P) by apply binary64_RN. assert (BQ : binary64 Q) by apply binary64_RN.
  (* S + s = P − Q *)
  pose proof (two_sum_exact P (- Q) BP (binary64_opp _ BQ)) as XS.
  destruct (two_sum_lo_bound P (- Q) BP (binary64_opp _ BQ)) as [Ls _].
  set (S := fst (two_sum P (- Q))) in *. set (s := snd (two_sum P (- Q))) in *.
  assert (Ls' : Rabs s <= u * (Rabs P + Rabs Q)).
  { eapply Rle_trans; [exact Ls|]. apply Rmult_le_compat_l; [pose proof u_pos; lra|].
    rewrite <- (Rabs_Ropp Q). apply Rabs_triang. }
  (* the low part *)
  pose proof (lo_sum_error p q c1 c2 s (binary64_RN _) (binary64_RN _) (binary64_RN _) (binary64_RN _)
                (binary64_two_sum_lo _ _)) as Elo.
  set (l := RN (RN (RN (p - q) + RN (c1 - c2)) + s)) in *.
  (* the computed radius *)
  destruct (compare_propagated_error_lower a1 e1 b1 f1 a2 e2 b2 f2 Bb1 Bf1 Bb2 Bf2 He1 Hf1 He2 Hf2)
    as [PR LR].
  set (R := compare_propagated_error a1 e1 b1 f1 a2 e2 b2 f2) in *.
  destruct (RN_sum_lower (Rabs P) (Rabs Q) (binary64_abs _ BP) (binary64_abs _ BQ)
              ltac:(pose proof (Rabs_pos P); pose proof (Rabs_pos Q); lra)) as [PM LM].
  set (M := RN (Rabs P + Rabs Q)) in *.
  pose proof u_pos. pose proof eta_pos.
  assert (HKM : 0 <= compare_compensated_relative * M).
  { apply Rmult_le_pos; [apply bpow_ge_0 | exact PM]. }
  pose proof (compare_bound_lower compare_compensated_relative M R HKM PR) as LB. cbv zeta in LB.
  set (E := RN (RN (RN (compare_compensated_relative * M) + RN (compare_propagation_factor * R)) +
                compare_absolute)) in *.
  (* the decomposition of the error *)
  replace (N1 * D2 - N2 * D1 - (S + l))
    with ((N1 * D2 - (P + p + c1)) - (N2 * D1 - (Q + q + c2)) + (p - q + (c1 - c2) + s - l))
    by (simpl in XS; lra).
  set (z1 := N1 * D2 - (P + p + c1)) in *. set (z2 := N2 * D1 - (Q + q + c2)) in *.
  set (z3 := p - q + (c1 - c2) + s - l) in *.
  assert (T : Rabs (z1 - z2 + z3) <= Rabs z1 + Rabs z2 + Rabs z3).
  { pose proof (Rabs_triang (z1 - z2) z3). pose proof (Rabs_triang z1 (- z2)). rewrite Rabs_Ropp in *.
    unfold Rminus in *. lra. }
  set (rho1 := Rabs a1 * f2 + e1 * (Rabs b2 + f2)) in *.
  set (rho2 := Rabs a2 * f1 + e2 * (Rabs b1 + f1)) in *.
  assert (Hrho : 0 <= rho1 + rho2).
  { apply Rplus_le_le_0_compat; apply propagated_nonneg; assumption. }
  pose proof (Rabs_pos P). pose proof (Rabs_pos Q). pose proof (Rabs_pos p). pose proof (Rabs_pos q).
  pose proof (Rabs_pos c1). pose proof (Rabs_pos c2). pose proof (Rabs_pos s).
  clearbody z1 z2 z3 rho1 rho2 R M E P Q p q c1 c2 s l.
  rewrite compare_compensated_relative_val in LB. unfold compare_propagation_factor in LB.
  rewrite compare_absolute_eta in LB.
  rewrite u_val in *. lra.
Qed.

(** ** The order nearest_hit derives from the signs (kernel/src/nearest/nearest_hit.cpp,
    [compare_hit_distances]). *)

Lemma sign_of_mult : forall x y, sign_of (x * y) = (sign_of x * sign_of y)%Z.
Proof.
  intros x y. unfold sign_of.
  destruct (Rcompare_spec x 0); destruct (Rcompare_spec y 0); destruct (Rcompare_spec (x * y) 0);
    try reflexivity; subst; nra.
Qed.

Lemma sign_of_inv : forall y, sign_of (/ y) = sign_of y.
Proof.
  intros y. unfold sign_of.
  destruct (Rcompare_spec y 0) as [L|E|L].
  - rewrite Rcompare_Lt; [reflexivity | now apply Rinv_lt_0_compat].
  - subst. rewrite Rinv_0, Rcompare_Eq; reflexivity.
  - rewrite Rcompare_Gt; [reflexivity | now apply Rinv_0_lt_compat].
Qed.

(** Over the reals: sign(N_1/D_1 − N_2/D_2) = sign(Δ)·sign(D_1)·sign(D_2), Δ = N_1·D_2 − N_2·D_1. *)
Theorem quotient_order_sign : forall N1 D1 N2 D2, D1 <> 0 -> D2 <> 0 ->
  sign_of (N1 / D1 - N2 / D2) = (sign_of (N1 * D2 - N2 * D1) * sign_of D1 * sign_of D2)%Z.
Proof.
  intros N1 D1 N2 D2 Z1 Z2.
  replace (N1 / D1 - N2 / D2) with ((N1 * D2 - N2 * D1) * / D1 * / D2) by (field; auto).
  rewrite !sign_of_mult, !sign_of_inv. reflexivity.
Qed.

(** [compare_hit_distances] past its two shortcuts: [orientation = a.den_sign == b.den_sign ? 1 : -1]
    times the certified sign of Δ ([static_cast<int>(Sign)] is [sign_to_Z]). *)
Definition hit_distance_order (delta den_sign_a den_sign_b : sign) : Z :=
  ((if Z.eqb (sign_to_Z den_sign_a) (sign_to_Z den_sign_b) then 1 else -1) * sign_to_Z delta)%Z.

(** The order it returns is the exact order of t_a = N_a/D_a and t_b = N_b/D_b, for den signs that are
    certain (as nearest_hit's always are) and nonzero (a hit), whenever the sign of Δ is certain. *)
Theorem hit_distance_order_correct : forall delta den_sign_a den_sign_b Na Da Nb Db,
  certifies den_sign_a Da -> den_sign_a <> Uncertain -> Da <> 0 ->
  certifies den_sign_b Db -> den_sign_b <> Uncertain -> Db <> 0 ->
  certifies delta (Na * Db - Nb * Da) -> delta <> Uncertain ->
  hit_distance_order delta den_sign_a den_sign_b = sign_of (Na / Da - Nb / Db).
Proof.
  intros delta sa sb Na Da Nb Db Ca Ua Za Cb Ub Zb Cd Ud.
  rewrite (quotient_order_sign Na Da Nb Db Za Zb).
  unfold hit_distance_order.
  rewrite (certified_sign sa Da Ca Ua), (certified_sign sb Db Cb Ub), (certified_sign delta _ Cd Ud).
  set (sd := sign_of (Na * Db - Nb * Da)). unfold sign_of.
  destruct (Rcompare_spec Da 0) as [A|A|A]; [| contradiction |];
    destruct (Rcompare_spec Db 0) as [B|B|B]; try contradiction; cbn -[Z.mul]; ring.
Qed.

(** The first shortcut: a plane through the origin (num = 0, certified: t = 0) comes first:
    [!a_at_origin − !b_at_origin].  For two hits (den ≠ 0, t = num/den ≥ 0). *)
Definition origin_order (num_sign_a num_sign_b : sign) : Z :=
  let at_origin s := match s with Zero => true | _ => false end in
  (Z.b2z (negb (at_origin num_sign_a)) - Z.b2z (negb (at_origin num_sign_b)))%Z.

Theorem origin_order_correct : forall num_sign_a num_sign_b Na Da Nb Db,
  certifies num_sign_a Na -> num_sign_a <> Uncertain -> Da <> 0 -> 0 <= Na / Da ->
  certifies num_sign_b Nb -> num_sign_b <> Uncertain -> Db <> 0 -> 0 <= Nb / Db ->
  (num_sign_a = Zero \/ num_sign_b = Zero) ->
  origin_order num_sign_a num_sign_b = sign_of (Na / Da - Nb / Db).
Proof.
  intros sa sb Na Da Nb Db Ca Ua Za Pa Cb Ub Zb Pb Z.
  assert (T : forall s N D, certifies s N -> s <> Uncertain -> D <> 0 -> 0 <= N / D ->
            (s = Zero /\ N / D = 0) \/ (s <> Zero /\ 0 < N / D)).
  { intros s N D C U Nz P. destruct s; simpl in C.
    - right. split; [discriminate|]. destruct P as [P|P]; [exact P|].
      exfalso. assert (N = N / D * D) by (field; exact Nz). rewrite <- P in H. lra.
    - left. split; [reflexivity|]. rewrite C. unfold Rdiv. ring.
    - right. split; [discriminate|]. destruct P as [P|P]; [exact P|].
      exfalso. assert (N = N / D * D) by (field; exact Nz). rewrite <- P in H. lra.
    - now elim U. }
  unfold origin_order, sign_of.
  destruct (T sa Na Da Ca Ua Za Pa) as [[-> Ea]|[Na' Ea]];
    destruct (T sb Nb Db Cb Ub Zb Pb) as [[-> Eb]|[Nb' Eb]].
  - rewrite Ea, Eb, Rminus_0_r, Rcompare_Eq; reflexivity.
  - rewrite Ea, Rcompare_Lt by lra. simpl. destruct sb; try reflexivity; now elim Nb'.
  - rewrite Eb, Rcompare_Gt by lra. simpl. destruct sa; try reflexivity; now elim Na'.
  - destruct Z; contradiction.
Qed.
