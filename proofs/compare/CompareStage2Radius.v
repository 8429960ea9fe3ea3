(** * Liveness of stage 2 of nearest_hit's comparison (issue 16): the radius upper bound (model).

    Stage 2 of [compare_hit_distances] (nearest/nearest_hit.cpp) is [enclosure_sign] of
    [compare_quotients_compensated] (nearest/compare_quotients.hpp), modelled in CompareQuotients.v.
    Its sign is certain when the computed |hi| exceeds the radius E (and |lo| is small, PlaneRefinedLiveness.v's
    [enclosure_sign_live3_model]: |V| > (3 + 8u)·E suffices).  This file proves the first half of the
    liveness argument: an UPPER bound of E over the model,

      E ≤ 2^-100·S' + c_2·ρ' + 64η,

    S' = |a_1·b_2| + |a_2·b_1| and ρ' = |a_1|·f_2 + e_1·(|b_2| + f_2) + |a_2|·f_1 + e_2·(|b_1| + f_1), where
    a_i, b_i are the renormalized heads (fst (two_sum hi lo)) of the four inputs, c_2 = 1 + 2^-40
    (CompareStage1Liveness.v).  The second half (the error of hi + lo, the twin-level theorem
    [compare_compensated_live], witnesses and sharpness) is CompareStage2Liveness.v. *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins CompareTwins PlaneLiveness NearestTwins CompareStage1Liveness.
Open Scope R_scope.

Lemma two_prod_fst : forall a b, fst (two_prod a b) = RN (a * b).
Proof. reflexivity. Qed.

Lemma propagated_error_nonneg : forall x1 e1 y1 f1 x2 e2 y2 f2,
  0 <= e1 -> 0 <= f1 -> 0 <= e2 -> 0 <= f2 -> 0 <= compare_propagated_error x1 e1 y1 f1 x2 e2 y2 f2.
Proof.
  intros x1 e1 y1 f1 x2 e2 y2 f2 He1 Hf1 He2 Hf2. unfold compare_propagated_error.
  pose proof (Rabs_pos x1). pose proof (Rabs_pos x2). pose proof (Rabs_pos y1). pose proof (Rabs_pos y2).
  apply RN_nonneg. apply Rplus_le_le_0_compat; apply RN_nonneg; apply Rplus_le_le_0_compat; apply RN_nonneg;
    try nra; apply Rmult_le_pos; try lra; apply RN_nonneg; lra.
Qed.

(** The radius of [compare_quotients_compensated] from above. *)
Theorem compare_compensated_radius_upper : forall (n1 d1 n2 d2 : Enclosure) a1 b1 a2 b2,
  a1 = fst (two_sum (hi n1) (lo n1)) -> b1 = fst (two_sum (hi d1) (lo d1)) ->
  a2 = fst (two_sum (hi n2) (lo n2)) -> b2 = fst (two_sum (hi d2) (lo d2)) ->
  binary64 (radius d1) -> binary64 (radius d2) ->
  0 <= radius n1 -> 0 <= radius d1 -> 0 <= radius n2 -> 0 <= radius d2 ->
  radius (compare_quotients_compensated n1 d1 n2 d2) <=
    64 * (u * u) * cross_magnitude a1 b1 a2 b2 +
    c2 * propagated_exact a1 (radius n1) b1 (radius d1) a2 (radius n2) b2 (radius d2) + 64 * eta.
Proof.
  intros [hn1 ln1 e1] [hd1 ld1 f1] [hn2 ln2 e2] [hd2 ld2 f2] a1 b1 a2 b2 Ha1 Hb1 Ha2 Hb2 Bf1 Bf2 He1 Hf1 He2 Hf2.
  cbn [hi lo radius] in *.
  unfold compare_quotients_compensated. cbn [hi lo radius].
  rewrite !two_prod_fst. rewrite <- Ha1, <- Hb1, <- Ha2, <- Hb2.
  assert (Bb1 : binary64 b1) by (rewrite Hb1; apply binary64_two_sum_hi).
  assert (Bb2 : binary64 b2) by (rewrite Hb2; apply binary64_two_sum_hi).
  pose proof u_pos as U0. pose proof eta_pos as E0.
  assert (U1 : u <= / 1125899906842624) by (rewrite u_val; lra).
  pose proof (propagated_upper a1 e1 b1 f1 a2 e2 b2 f2 Bb1 Bf1 Bb2 Bf2 He1 Hf1 He2 Hf2) as PU.
  pose proof (propagated_error_nonneg a1 e1 b1 f1 a2 e2 b2 f2 He1 Hf1 He2 Hf2) as P0.
  assert (rho0 : 0 <= propagated_exact a1 e1 b1 f1 a2 e2 b2 f2).
  { unfold propagated_exact. pose proof (propagated_nonneg a1 e1 b2 f2 He1 Hf2).
    pose proof (propagated_nonneg a2 e2 b1 f1 He2 Hf1). lra. }
  fold (propagated_exact a1 e1 b1 f1 a2 e2 b2 f2) in PU.
  set (P := compare_propagated_error a1 e1 b1 f1 a2 e2 b2 f2) in *.
  set (rho := propagated_exact a1 e1 b1 f1 a2 e2 b2 f2) in *.
  unfold cross_magnitude.
  pose proof (RN_abs_upper (a1 * b2)) as Q1. pose proof (RN_abs_upper (a2 * b1)) as Q2.
  set (S := Rabs (a1 * b2) + Rabs (a2 * b1)).
  set (Sp := Rabs (RN (a1 * b2)) + Rabs (RN (a2 * b1))).
  assert (Sp0 : 0 <= Sp) by (unfold Sp; pose proof (Rabs_pos (RN (a1 * b2))); pose proof (Rabs_pos (RN (a2 * b1))); lra).
  assert (S0 : 0 <= S) by (unfold S; pose proof (Rabs_pos (a1 * b2)); pose proof (Rabs_pos (a2 * b1)); lra).
  assert (HSp : Sp <= (1 + u) * S + 2 * eta) by (unfold Sp, S; lra).
  clearbody Sp S. clear Q1 Q2.
  pose proof (RN_upper Sp Sp0) as Hm. pose proof (RN_nonneg Sp Sp0) as m0.
  set (m := RN Sp) in *. clearbody m.
  rewrite compare_compensated_relative_val, compare_absolute_eta. unfold compare_propagation_factor.

  set (K := 32 * (u * u)).
  assert (K0 : 0 <= K) by (unfold K; nra).
  assert (K1 : K <= / 1024) by (unfold K; nra).
  assert (Km0 : 0 <= K * m) by nra.
  pose proof (RN_upper (K * m) Km0) as Hr1. pose proof (RN_nonneg (K * m) Km0) as r10.
  set (r1 := RN (K * m)) in *. clearbody r1.
  set (F := 1 + 16 * u) in *.
  assert (FP0 : 0 <= F * P) by (unfold F; nra).
  pose proof (RN_upper (F * P) FP0) as Hr2. pose proof (RN_nonneg (F * P) FP0) as r20.
  set (r2 := RN (F * P)) in *. clearbody r2.
  assert (r30' : 0 <= r1 + r2) by lra.
  pose proof (RN_upper (r1 + r2) r30') as Hr3. pose proof (RN_nonneg (r1 + r2) r30') as r30.
  set (r3 := RN (r1 + r2)) in *. clearbody r3.
  assert (r40' : 0 <= r3 + 16 * eta) by lra.
  pose proof (RN_upper (r3 + 16 * eta) r40') as Hr4.
  set (r4 := RN (r3 + 16 * eta)) in *. clearbody r4.
  set (g := 1 + u) in *.
  assert (g1 : 1 <= g) by (unfold g; lra).
  assert (g2 : g <= 1 + / 1125899906842624) by (unfold g; lra).
  clearbody P rho.
  (* m ≤ g²S + 3η; r1 ≤ g³K·S + 2η *)
  assert (M1 : m <= g * g * S + 4 * eta).
  { assert (T : g * Sp <= g * (g * S + 2 * eta)) by (apply Rmult_le_compat_l; lra).
    assert (T2 : g * (2 * eta) <= 3 * eta) by nra. lra. }
  assert (R1 : r1 <= g * g * g * K * S + 2 * eta).
  { assert (T : g * (K * m) <= g * (K * (g * g * S + 4 * eta))) by
      (apply Rmult_le_compat_l; [lra | apply Rmult_le_compat_l; lra]).
    assert (GK : g * K <= / 256) by nra.
    assert (T2 : g * (K * (4 * eta)) <= eta).
    { replace (g * (K * (4 * eta))) with (4 * (g * K) * eta) by ring.
      apply Rle_trans with (4 * / 256 * eta); [apply Rmult_le_compat_r; lra | lra]. }
    lra. }
  (* r2 ≤ gF·(g⁴ρ + 7η) + η *)
  assert (F0 : 0 <= F) by (unfold F; lra).
  assert (F1 : F <= 1 + / 1024) by (unfold F; lra).
  assert (R2 : r2 <= g * F * (g * g * g * g * rho) + 9 * eta).
  { assert (T : g * (F * P) <= g * (F * (g * g * g * g * rho + 7 * eta))) by
      (apply Rmult_le_compat_l; [lra | apply Rmult_le_compat_l; lra]).
    assert (GF : g * F <= 1 + / 256) by nra.
    assert (T2 : g * (F * (7 * eta)) <= 8 * eta).
    { replace (g * (F * (7 * eta))) with (7 * (g * F) * eta) by ring.
      apply Rle_trans with (7 * (1 + / 256) * eta); [apply Rmult_le_compat_r; lra | lra]. }
    lra. }
  (* the final roundings *)
  assert (R3 : r3 <= g * (g * g * g * K * S + g * F * (g * g * g * g * rho)) + 13 * eta).
  { assert (T : g * (r1 + r2) <= g * (g * g * g * K * S + 2 * eta + (g * F * (g * g * g * g * rho) + 9 * eta)))
      by (apply Rmult_le_compat_l; lra).
    assert (T2 : g * (11 * eta) <= 12 * eta).
    { replace (g * (11 * eta)) with (11 * g * eta) by ring.
      apply Rle_trans with (11 * (1 + / 1125899906842624) * eta); [apply Rmult_le_compat_r; lra | lra]. }
    lra. }
  assert (R4 : r4 <= g * (g * (g * g * g * K * S + g * F * (g * g * g * g * rho))) + 32 * eta).
  { assert (T : g * (r3 + 16 * eta) <=
                g * (g * (g * g * g * K * S + g * F * (g * g * g * g * rho)) + 13 * eta + 16 * eta))
      by (apply Rmult_le_compat_l; lra).
    assert (T2 : g * (29 * eta) <= 30 * eta).
    { replace (g * (29 * eta)) with (29 * g * eta) by ring.
      apply Rle_trans with (29 * (1 + / 1125899906842624) * eta); [apply Rmult_le_compat_r; lra | lra]. }
    lra. }
  (* the constants: g⁵K ≤ 2K, g⁷F ≤ c2 *)
  assert (G5 : g * g * g * g * g <= 2).
  { assert (g * g <= 2) by nra. assert (g * g * g <= 2) by nra. assert (g * g * g * g <= 2) by nra. nra. }
  assert (G7 : g * g * g * g * g * g * g * F <= c2).
  { unfold c2, g, F. rewrite u_val. simpl bpow. lra. }
  assert (KS : g * (g * (g * g * g * K * S)) <= 64 * (u * u) * S).
  { replace (g * (g * (g * g * g * K * S))) with ((g * g * g * g * g) * (K * S)) by ring.
    replace (64 * (u * u) * S) with (2 * (K * S)) by (unfold K; ring).
    apply Rmult_le_compat_r; [nra | exact G5]. }
  assert (FR : g * (g * (g * F * (g * g * g * g * rho))) <= c2 * rho).
  { replace (g * (g * (g * F * (g * g * g * g * rho)))) with ((g * g * g * g * g * g * g * F) * rho) by ring.
    apply Rmult_le_compat_r; [exact rho0 | exact G7]. }
  lra.
Qed.
