(** * Liveness of stage 2 of nearest_hit's comparison (issue 16): the second half.

    Stage 2 of [compare_hit_distances] (nearest/nearest_hit.cpp) is [enclosure_sign] of
    [compare_quotients_compensated] (nearest/compare_quotients.hpp), modelled in CompareQuotients.v, twin
    [compare_quotients_compensated_b] (CompareTwins.v, tied by [compare_quotients_compensated_twin] and the
    runner's [nearest_compare]).  CompareStage2Radius.v bounds its radius E from above; here:

    - [compare_compensated_error_model]: hi + lo is within 2^-100·S' + 64η of the cross difference V of the
      four inputs' double-double values (E computed with zero input radii bounds the true error: hi and lo do
      not read the radii);
    - [compare_compensated_live_model] (model) and [compare_compensated_live] (twin, every input part a finite
      double of magnitude ≤ 2^400, radii ≥ 0): the sign is certain whenever

        |V| > k_1·S' + k_2·ρ' + k_3,   k_1 = 13·2^-102, k_2 = 2 + 2^-38, k_3 = 2^-1067 (= 256η),

      V = (h_1 + l_1)(h'_2 + l'_2) − (h_2 + l_2)(h'_1 + l'_1) (n_i = (h_i, l_i, e_i), d_i = (h'_i, l'_i, f_i)),
      S' and ρ' as in CompareStage2Radius.v over the heads a_i, b_i = fst (two_sum h l).  [enclosure_sign] is
      certain when |V| > (1 + 4u)·(err + 2E) for any err ≥ |V − (hi + lo)| ([enclosure_sign_live_err], the form
      of PlaneRefinedLiveness.v's [enclosure_sign_live3] with the error apart from E), and
      (1 + 4u)·(3·2^-100·S' + 2c_2·ρ' + 192η) is below the class bound.  The certain sign is the sign of Δ
      for any reals the inputs enclose (PlaneStageTwoFinite.v's [compare_compensated_twin_sound_total]); [compare_compensated_live_exact]: the same class for the exact
      cross difference |N_1·D_2 − N_2·D_1| of any reals the inputs enclose, with 3 + 2^-37 in place of k_2;
    - [compare_hit_distances_stage2_live]: in nearest_hit's [compare_hit_distances_b], the order is returned
      by stage 1 or stage 2 (stage ≤ 1) when the four stage-2 enclosures are in the class;
      [compare_hit_distances_stage2_live_exact]: the same with the exact Δ = num_a·den_b − num_b·den_a of the ray
      and the planes;
    - not vacuous: [compare_compensated_live_example] (a near tie of relative size 2^-60: in the class, stage 2
      certain, stage 1 on the heads uncertain) and [compare_hit_distances_stage2_example] (a ray and two planes
      with t_a = 1, t_b = 1 + 2^-60: [compare_hit_distances_b] returns from stage 2, stage 1 being uncertain;
      [compare_hit_distances_stage2_example_in_class]: its stage-2 enclosures are in the class);
    - how sharp: [compare_compensated_k1_fails] (k_1 replaced by 7·2^-103 the statement is false: so k_1 is
      within a factor 26/7 < 3.8 of the best constant) and [compare_compensated_k2_fails] (k_2 replaced by
      2 − 2^-19 it is false: k_2 is within a factor 1 + 2^-19 of the best). *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins CompareTwins PlaneLiveness PlaneQueryTwins PlaneStageTwoFinite NearestTwins CompareStage1Liveness CompareStage2Radius.
From Raykernel Require PlaneRefinedLiveness.
Open Scope R_scope.

(** ** The model *)

Definition dd (e : Enclosure) : R := hi e + lo e.
Definition head (e : Enclosure) : R := fst (two_sum (hi e) (lo e)).
Definition cross_dd (n1 d1 n2 d2 : Enclosure) : R := dd n1 * dd d2 - dd n2 * dd d1.
Definition zero_radius (e : Enclosure) : Enclosure := {| hi := hi e; lo := lo e; radius := 0 |}.

Definition k1 : R := 13 * bpow radix2 (-102).
Definition k2 : R := 2 + bpow radix2 (-38).
Definition k3 : R := bpow radix2 (-1067).

Lemma k1_u : k1 = 208 * (u * u).
Proof. unfold k1. rewrite u_val. simpl bpow. lra. Qed.
Lemma k2_val : k2 = 2 + / 274877906944.
Proof. unfold k2. simpl bpow. lra. Qed.
Lemma k3_eta : k3 = 256 * eta.
Proof. unfold k3, eta. replace (-1067)%Z with (8 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. Qed.

(** hi and lo do not read the radii. *)
Lemma compensated_radius_free : forall n1 d1 n2 d2,
  let e0 := compare_quotients_compensated (zero_radius n1) (zero_radius d1) (zero_radius n2) (zero_radius d2) in
  let e := compare_quotients_compensated n1 d1 n2 d2 in
  hi e0 = hi e /\ lo e0 = lo e.
Proof. intros [] [] [] []. split; reflexivity. Qed.

Lemma encloses_dd : forall e, 0 <= radius e -> encloses e (dd e).
Proof. intros e H. unfold encloses, dd. replace (hi e + lo e - (hi e + lo e)) with 0 by ring. rewrite Rabs_R0. exact H. Qed.

Lemma cross_magnitude_nonneg : forall a b c d, 0 <= cross_magnitude a b c d.
Proof. intros. unfold cross_magnitude. pose proof (Rabs_pos (a * d)). pose proof (Rabs_pos (c * b)). lra. Qed.

(** (a) The error of hi + lo: E with zero input radii, hence ≤ 2^-100·S' + 64η. *)
Theorem compare_compensated_error_model : forall n1 d1 n2 d2,
  binary64 (hi n1) -> binary64 (lo n1) -> binary64 (hi d1) -> binary64 (lo d1) ->
  binary64 (hi n2) -> binary64 (lo n2) -> binary64 (hi d2) -> binary64 (lo d2) ->
  let e := compare_quotients_compensated n1 d1 n2 d2 in
  Rabs (cross_dd n1 d1 n2 d2 - (hi e + lo e)) <=
    64 * (u * u) * cross_magnitude (head n1) (head d1) (head n2) (head d2) + 64 * eta.
Proof.
  intros n1 d1 n2 d2 Hn1 Ln1 Hd1 Ld1 Hn2 Ln2 Hd2 Ld2 e.
  destruct (compensated_radius_free n1 d1 n2 d2) as [Eh El]. fold e in Eh, El.
  pose proof (compare_quotients_compensated_enclosure (zero_radius n1) (zero_radius d1) (zero_radius n2)
                (zero_radius d2) (dd n1) (dd d1) (dd n2) (dd d2) Hn1 Ln1 Hd1 Ld1 binary64_0 Hn2 Ln2 Hd2 Ld2
                binary64_0 (encloses_dd (zero_radius n1) (Rle_refl 0)) (encloses_dd (zero_radius d1) (Rle_refl 0))
                (encloses_dd (zero_radius n2) (Rle_refl 0)) (encloses_dd (zero_radius d2) (Rle_refl 0))) as Z.
  pose proof (compare_compensated_radius_upper (zero_radius n1) (zero_radius d1) (zero_radius n2)
                (zero_radius d2) (head n1) (head d1) (head n2) (head d2) eq_refl eq_refl eq_refl eq_refl
                binary64_0 binary64_0 (Rle_refl 0) (Rle_refl 0) (Rle_refl 0) (Rle_refl 0)) as U.
  unfold encloses in Z. rewrite Eh, El in Z.
  replace (propagated_exact (head n1) (radius (zero_radius n1)) (head d1) (radius (zero_radius d1))
             (head n2) (radius (zero_radius n2)) (head d2) (radius (zero_radius d2))) with 0 in U
    by (unfold propagated_exact; cbn [radius zero_radius]; ring).
  unfold cross_dd. eapply Rle_trans; [exact Z|]. lra.
Qed.

(** [enclosure_sign] is certain when |V| > (1 + 4u)·(err + 2·radius) for any err bounding |V − (hi + lo)|
    (v = hi ⊕ lo ≥ (1 − u)(hi + lo), radius ⊕ radius ≤ 2(1 + u)·radius): PlaneRefinedLiveness.v's
    [enclosure_sign_live3_model] with the error apart from the radius; an instance of PlaneLiveness.v's
    [enclosure_sign_live_gen_model]. *)
Lemma enclosure_sign_live_err_model : forall e V err, binary64 (hi e) -> binary64 (lo e) -> binary64 (radius e) ->
  0 <= radius e -> Rabs (V - (hi e + lo e)) <= err -> (1 + 4 * u) * (err + 2 * radius e) < Rabs V ->
  enclosure_sign_lanes e <> uncertain_lane.
Proof.
  intros e V err Bh Bl Br Pr E L.
  apply (enclosure_sign_live_gen_model e V err Bh Bl Br Pr E).
  assert (P0 : 0 <= err) by (eapply Rle_trans; [apply Rabs_pos | exact E]).
  pose proof u_pos. rewrite u_val in *. lra.
Qed.

Lemma enclosure_sign_live_err : forall e V err, fbnd 1000 (hib e) -> fbnd 1000 (lob e) -> fbnd 1000 (radiusb e) ->
  0 <= B2R (radiusb e) -> Rabs (V - (B2R (hib e) + B2R (lob e))) <= err ->
  (1 + 4 * u) * (err + 2 * B2R (radiusb e)) < Rabs V -> enclosure_sign_lanes_b e <> uncertain_lane.
Proof.
  intros e V err Hh Hl Hr P E L.
  rewrite enclosure_sign_b_model.
  - apply (enclosure_sign_live_err_model (enc_R e) V err); try apply binary64_B2R; assumption.
  - destruct (fbnd_add _ _ _ _ Hh Hl ltac:(lia) ltac:(lia) ltac:(lia)) as [F _]. exact F.
  - destruct (fbnd_add _ _ _ _ Hr Hr ltac:(lia) ltac:(lia) ltac:(lia)) as [F _]. exact F.
Qed.

(** The class bound dominates (1 + 4u)·(err + 2E), err = 2^-100·S' + 64η. *)
Lemma compare_compensated_live_bound : forall n1 d1 n2 d2,
  binary64 (hi n1) -> binary64 (lo n1) -> binary64 (hi d1) -> binary64 (lo d1) -> binary64 (radius d1) ->
  binary64 (hi n2) -> binary64 (lo n2) -> binary64 (hi d2) -> binary64 (lo d2) -> binary64 (radius d2) ->
  0 <= radius n1 -> 0 <= radius d1 -> 0 <= radius n2 -> 0 <= radius d2 ->
  k1 * cross_magnitude (head n1) (head d1) (head n2) (head d2) +
    k2 * propagated_exact (head n1) (radius n1) (head d1) (radius d1) (head n2) (radius n2) (head d2) (radius d2)
    + k3 < Rabs (cross_dd n1 d1 n2 d2) ->
  let e := compare_quotients_compensated n1 d1 n2 d2 in
  0 <= radius e /\
  Rabs (cross_dd n1 d1 n2 d2 - (hi e + lo e)) <=
    64 * (u * u) * cross_magnitude (head n1) (head d1) (head n2) (head d2) + 64 * eta /\
  (1 + 4 * u) * ((64 * (u * u) * cross_magnitude (head n1) (head d1) (head n2) (head d2) + 64 * eta) +
                 2 * radius e) < Rabs (cross_dd n1 d1 n2 d2).
Proof.
  intros n1 d1 n2 d2 Hn1 Ln1 Hd1 Ld1 Bf1 Hn2 Ln2 Hd2 Ld2 Bf2 He1 Hf1 He2 Hf2 L e.
  assert (Enc : encloses e (cross_dd n1 d1 n2 d2)).
  { apply compare_quotients_compensated_enclosure; try assumption; apply encloses_dd; assumption. }
  split; [eapply Rle_trans; [apply Rabs_pos | exact Enc]|].
  split; [exact (compare_compensated_error_model n1 d1 n2 d2 Hn1 Ln1 Hd1 Ld1 Hn2 Ln2 Hd2 Ld2)|].
  pose proof (compare_compensated_radius_upper n1 d1 n2 d2 (head n1) (head d1) (head n2) (head d2)
                eq_refl eq_refl eq_refl eq_refl Bf1 Bf2 He1 Hf1 He2 Hf2) as U. fold e in U.
  pose proof (cross_magnitude_nonneg (head n1) (head d1) (head n2) (head d2)) as S0.
  assert (R0 : 0 <= propagated_exact (head n1) (radius n1) (head d1) (radius d1) (head n2) (radius n2)
                                     (head d2) (radius d2)).
  { unfold propagated_exact. pose proof (propagated_nonneg (head n1) (radius n1) (head d2) (radius d2) He1 Hf2).
    pose proof (propagated_nonneg (head n2) (radius n2) (head d1) (radius d1) He2 Hf1). lra. }
  set (r := radius e) in *.
  set (S := cross_magnitude (head n1) (head d1) (head n2) (head d2)) in *.
  set (rho := propagated_exact (head n1) (radius n1) (head d1) (radius d1) (head n2) (radius n2)
                               (head d2) (radius d2)) in *.
  set (V := cross_dd n1 d1 n2 d2) in *.
  clearbody r S rho V. pose proof u_pos. pose proof eta_pos.
  assert (Mu : (1 + 4 * u) * (64 * (u * u) * S + 64 * eta + 2 * r) <=
               (1 + 4 * u) * (64 * (u * u) * S + 64 * eta + 2 * (64 * (u * u) * S + c2 * rho + 64 * eta)))
    by (apply Rmult_le_compat_l; lra).
  rewrite k1_u, k2_val, k3_eta in L. unfold c2 in Mu. simpl bpow in Mu.
  assert (A : (1 + 4 * u) * (192 * (u * u) * S) <= 208 * (u * u) * S).
  { replace ((1 + 4 * u) * (192 * (u * u) * S)) with ((192 + 768 * u) * ((u * u) * S)) by ring.
    replace (208 * (u * u) * S) with (208 * ((u * u) * S)) by ring.
    apply Rmult_le_compat_r; [apply Rmult_le_pos; [nra | lra] | rewrite u_val; lra]. }
  assert (B : (1 + 4 * u) * (2 * ((1 + / 1099511627776) * rho)) <= (2 + / 274877906944) * rho).
  { replace ((1 + 4 * u) * (2 * ((1 + / 1099511627776) * rho))) with
      (((1 + 4 * u) * (2 * (1 + / 1099511627776))) * rho) by ring.
    apply Rmult_le_compat_r; [lra | rewrite u_val; lra]. }
  assert (C : (1 + 4 * u) * (192 * eta) <= 256 * eta) by (rewrite u_val; lra).
  lra.
Qed.

Theorem compare_compensated_live_model : forall n1 d1 n2 d2,
  binary64 (hi n1) -> binary64 (lo n1) -> binary64 (hi d1) -> binary64 (lo d1) -> binary64 (radius d1) ->
  binary64 (hi n2) -> binary64 (lo n2) -> binary64 (hi d2) -> binary64 (lo d2) -> binary64 (radius d2) ->
  0 <= radius n1 -> 0 <= radius d1 -> 0 <= radius n2 -> 0 <= radius d2 ->
  k1 * cross_magnitude (head n1) (head d1) (head n2) (head d2) +
    k2 * propagated_exact (head n1) (radius n1) (head d1) (radius d1) (head n2) (radius n2) (head d2) (radius d2)
    + k3 < Rabs (cross_dd n1 d1 n2 d2) ->
  enclosure_sign_lanes (compare_quotients_compensated n1 d1 n2 d2) <> uncertain_lane.
Proof.
  intros n1 d1 n2 d2 Hn1 Ln1 Hd1 Ld1 Bf1 Hn2 Ln2 Hd2 Ld2 Bf2 He1 Hf1 He2 Hf2 L.
  destruct (compare_compensated_live_bound n1 d1 n2 d2 Hn1 Ln1 Hd1 Ld1 Bf1 Hn2 Ln2 Hd2 Ld2 Bf2 He1 Hf1 He2 Hf2 L)
    as [P [E B]].
  apply (enclosure_sign_live_err_model _ (cross_dd n1 d1 n2 d2)
           (64 * (u * u) * cross_magnitude (head n1) (head d1) (head n2) (head d2) + 64 * eta)); try assumption;
    unfold compare_quotients_compensated; cbn [hi lo radius];
    first [apply binary64_two_sum_hi | apply binary64_RN].
Qed.

(** ** The twin *)

(** Every part of the four inputs of magnitude at most 2^400: hi, lo and the radius stay below 2^1000. *)
Lemma compare_compensated_b_bounded : forall n1 d1 n2 d2,
  fbnd 400 (hib n1) -> fbnd 400 (lob n1) -> fbnd 400 (radiusb n1) ->
  fbnd 400 (hib d1) -> fbnd 400 (lob d1) -> fbnd 400 (radiusb d1) ->
  fbnd 400 (hib n2) -> fbnd 400 (lob n2) -> fbnd 400 (radiusb n2) ->
  fbnd 400 (hib d2) -> fbnd 400 (lob d2) -> fbnd 400 (radiusb d2) ->
  let e := compare_quotients_compensated_b n1 d1 n2 d2 in
  fbnd 1000 (hib e) /\ fbnd 1000 (lob e) /\ fbnd 1000 (radiusb e).
Proof.
  intros [hn1 ln1 e1] [hd1 ld1 f1] [hn2 ln2 e2] [hd2 ld2 f2]. cbn [hib lob radiusb].
  intros Hn1 Ln1 En1 Hd1 Ld1 Fd1 Hn2 Ln2 En2 Hd2 Ld2 Fd2.
  unfold compare_quotients_compensated_b, compare_propagated_error_b, two_prod_b. cbv zeta.
  cbn [hib lob radiusb fst snd].
  split; [|split]; (eapply fbnd_le; [fbnd_tac | zle]).
Qed.

(** Stage 2 of the comparison is certain on the class, on the twin. *)
Theorem compare_compensated_live : forall n1 d1 n2 d2,
  fbnd 400 (hib n1) -> fbnd 400 (lob n1) -> fbnd 400 (radiusb n1) ->
  fbnd 400 (hib d1) -> fbnd 400 (lob d1) -> fbnd 400 (radiusb d1) ->
  fbnd 400 (hib n2) -> fbnd 400 (lob n2) -> fbnd 400 (radiusb n2) ->
  fbnd 400 (hib d2) -> fbnd 400 (lob d2) -> fbnd 400 (radiusb d2) ->
  0 <= B2R (radiusb n1) -> 0 <= B2R (radiusb d1) -> 0 <= B2R (radiusb n2) -> 0 <= B2R (radiusb d2) ->
  k1 * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    k2 * propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                          (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (cross_dd (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)) ->
  enclosure_sign_lanes_b (compare_quotients_compensated_b n1 d1 n2 d2) <> uncertain_lane.
Proof.
  intros n1 d1 n2 d2 Hn1 Ln1 En1 Hd1 Ld1 Fd1 Hn2 Ln2 En2 Hd2 Ld2 Fd2 Pe1 Pf1 Pe2 Pf2 L.
  destruct (compare_compensated_b_bounded n1 d1 n2 d2 Hn1 Ln1 En1 Hd1 Ld1 Fd1 Hn2 Ln2 En2 Hd2 Ld2 Fd2)
    as [BH [BL BR]].
  generalize (compare_quotients_compensated_twin n1 d1 n2 d2). cbv zeta.
  generalize BH BL BR.
  generalize (compare_quotients_compensated_b n1 d1 n2 d2) as e.
  intros e BH' BL' BR' Tw.
  destruct (Tw (proj1 BR') (proj1 BH') (proj1 BL'))
    as [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ Eq]]]]]]]]]]]]]].
  destruct (compare_compensated_live_bound (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)
              (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
              (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
              Pe1 Pf1 Pe2 Pf2 L) as [P [E B]].
  rewrite <- Eq in P, E, B. cbn [enc_R hi lo radius] in P, E, B.
  exact (enclosure_sign_live_err e (cross_dd (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)) _ BH' BL' BR' P E B).
Qed.

(** ** In nearest_hit: [compare_hit_distances] returns by stage 2 at the latest *)

Lemma is_certain_lane : forall e, enclosure_sign_lanes_b e <> uncertain_lane ->
  is_certain_b (sign_from_Z (enclosure_sign_lanes_b e)) = true.
Proof.
  intros e U. assert (Se : lane_sign (enclosure_sign_lanes_b e)) by (unfold enclosure_sign_lanes_b; apply sign_lanes_range).
  destruct Se as [H | [H | H]]; rewrite H; [reflexivity | reflexivity | now elim U].
Qed.

(** When the four stage-2 enclosures of [RayPlaneCascade] that [compare_hit_distances] passes to
    [compare_quotients_compensated] are in the class of [compare_compensated_live] (their radii are ≥ 0
    by construction), the order is returned by stage 1 or stage 2 (stage 0 or 1), never by the exact stage. *)
Theorem compare_hit_distances_stage2_live : forall o d pa na pb nb nsa dsa nsb dsb,
  let n1 := stage2_num_b o pa na in let d1 := stage2_den_b d na in
  let n2 := stage2_num_b o pb nb in let d2 := stage2_den_b d nb in
  fbnd 400 (hib n1) -> fbnd 400 (lob n1) -> fbnd 400 (radiusb n1) ->
  fbnd 400 (hib d1) -> fbnd 400 (lob d1) -> fbnd 400 (radiusb d1) ->
  fbnd 400 (hib n2) -> fbnd 400 (lob n2) -> fbnd 400 (radiusb n2) ->
  fbnd 400 (hib d2) -> fbnd 400 (lob d2) -> fbnd 400 (radiusb d2) ->
  k1 * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    k2 * propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                          (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (cross_dd (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)) ->
  (snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <= 1)%Z.
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb n1 d1 n2 d2 Hn1 Ln1 En1 Hd1 Ld1 Fd1 Hn2 Ln2 En2 Hd2 Ld2 Fd2 L.
  assert (Pe1 : 0 <= B2R (radiusb n1)).
  { apply nonneg_fin_B2R; [unfold n1, stage2_num_b; apply num_radius_nonneg | exact (proj1 En1)]. }
  assert (Pf1 : 0 <= B2R (radiusb d1)).
  { apply nonneg_fin_B2R; [unfold d1, stage2_den_b; apply den_radius_nonneg | exact (proj1 Fd1)]. }
  assert (Pe2 : 0 <= B2R (radiusb n2)).
  { apply nonneg_fin_B2R; [unfold n2, stage2_num_b; apply num_radius_nonneg | exact (proj1 En2)]. }
  assert (Pf2 : 0 <= B2R (radiusb d2)).
  { apply nonneg_fin_B2R; [unfold d2, stage2_den_b; apply den_radius_nonneg | exact (proj1 Fd2)]. }
  pose proof (is_certain_lane _ (compare_compensated_live n1 d1 n2 d2 Hn1 Ln1 En1 Hd1 Ld1 Fd1 Hn2 Ln2 En2
                                   Hd2 Ld2 Fd2 Pe1 Pf1 Pe2 Pf2 L)) as C.
  unfold n1, d1, n2, d2 in C.
  unfold compare_hit_distances_b. cbv zeta. destruct (_ || _)%bool; [cbn [snd]; lia|].
  destruct (is_certain_b (compare_quotients_filter_b _ _ _ _)); [cbn [snd]; lia|].
  rewrite C. cbn [snd]. lia.
Qed.

(** ** Not vacuous, and how sharp *)

Definition w_one : float := PlaneRefinedLiveness.f_one.                                       (* 1 *)
Definition w_zero : float := f_zero.                                                     (* +0 *)
Definition w_2m60 : float := PlaneRefinedLiveness.f_2m60.                                     (* 2^-60 *)
Definition w_m15 : float := @B754_finite 53 1024 true 8444249301319680 (-152) eq_refl.  (* −15·2^-103 *)
Definition w_half : float := @B754_finite 53 1024 false 4503599627370496 (-53) eq_refl. (* 1/2 *)

Lemma w_one_val : B2R w_one = 1.
Proof. exact PlaneRefinedLiveness.f_one_val. Qed.
Lemma w_zero_val : B2R w_zero = 0.
Proof. reflexivity. Qed.
Lemma w_2m60_val : B2R w_2m60 = bpow radix2 (-60).
Proof. exact PlaneRefinedLiveness.f_2m60_val. Qed.
Lemma w_m15_val : B2R w_m15 = - (15 * bpow radix2 (-103)).
Proof.
  change (B2R w_m15) with (IZR (-8444249301319680) * bpow radix2 (-152)).
  replace (IZR (-8444249301319680)) with (- (15 * bpow radix2 49)) by (simpl bpow; lra).
  replace (-103)%Z with (49 + -152)%Z by reflexivity. rewrite bpow_plus. ring.
Qed.
Lemma w_half_val : B2R w_half = / 2.
Proof.
  change (B2R w_half) with (IZR 4503599627370496 * bpow radix2 (-53)).
  change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. simpl bpow. lra.
Qed.

Definition wenc (h l r : float) : EnclosureB := {| hib := h; lob := l; radiusb := r |}.

(** The head of a computed enclosure, through the twin's sum: its mantissa and exponent, checked by
    [vm_compute] (comparing the floats themselves would normalise Flocq's proof terms). *)
Lemma head_const : forall x c, fin (fadd (hib x) (lob x)) = true ->
  mant (fadd (hib x) (lob x)) = mant c -> expo (fadd (hib x) (lob x)) = expo c -> head (enc_R x) = B2R c.
Proof.
  intros x c F M E. unfold head, enc_R, two_sum. cbv zeta. cbn [fst hi lo].
  rewrite <- fadd_val by exact F. rewrite !B2R_mant_expo, M, E. reflexivity.
Qed.

Lemma head_one_zero : head (enc_R (wenc w_one w_zero w_zero)) = 1.
Proof. rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]. Qed.
Lemma head_one_2m60 : head (enc_R (wenc w_one w_2m60 w_zero)) = 1.
Proof. rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]. Qed.
Lemma head_one_m15 : head (enc_R (wenc w_one w_m15 w_zero)) = 1.
Proof. rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]. Qed.
Lemma head_zero : head (enc_R (wenc w_zero w_zero w_zero)) = 0.
Proof. rewrite (head_const _ w_zero); [exact w_zero_val | vm_compute; reflexivity ..]. Qed.
Lemma head_one_half : head (enc_R (wenc w_one w_zero w_half)) = 1.
Proof. rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]. Qed.

Lemma k3_small : k3 <= u * (u * u).
Proof.
  unfold k3. apply Rle_trans with (bpow radix2 (-159)); [apply bpow_le; lia|].
  rewrite u_val. simpl bpow. lra.
Qed.

Ltac w_vals := rewrite ?w_one_val, ?w_zero_val, ?w_2m60_val, ?w_m15_val, ?w_half_val.

Ltac w_class :=
  rewrite ?head_one_zero, ?head_one_2m60, ?head_one_m15, ?head_zero, ?head_one_half;
  unfold cross_dd, dd, cross_magnitude, propagated_exact; cbn [enc_R hi lo radius hib lob radiusb wenc];
  w_vals; rewrite ?k1_u, ?k2_val; pose proof k3_small; pose proof u_pos;
  rewrite ?Rmult_1_l, ?Rmult_1_r, ?Rmult_0_l, ?Rmult_0_r, ?Rplus_0_r, ?Rplus_0_l, ?Rminus_0_r, ?Rabs_R0, ?Rabs_R1;
  rewrite ?Rabs_R0, ?Rabs_R1.

(** A near tie, t_1 − t_2 of relative size 2^-60 (n_1 = d_1 = d_2 = (1, 0, 0), n_2 = (1, 2^-60, 0)): in the class
    of [compare_compensated_live] (|V| = 2^-60 > 13·2^-102·2 + 2^-1067), stage 2 is certain (negative), and stage 1
    on the heads (the one-double enclosures (1, 0)) is uncertain. *)
Example compare_compensated_live_example :
  let n1 := wenc w_one w_zero w_zero in let d1 := wenc w_one w_zero w_zero in
  let n2 := wenc w_one w_2m60 w_zero in let d2 := wenc w_one w_zero w_zero in
  k1 * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    k2 * propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                          (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (cross_dd (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)) /\
  enclosure_sign_lanes_b (compare_quotients_compensated_b n1 d1 n2 d2) = (-1)%Z /\
  compare_quotients_filter_b (renc w_one w_zero) (renc w_one w_zero) (renc w_one w_zero) (renc w_one w_zero)
    = Uncertain.
Proof.
  intros n1 d1 n2 d2. split; [| split; vm_compute; reflexivity].
  unfold n1, d1, n2, d2. w_class.
  match goal with |- _ < Rabs ?V => replace V with (- bpow radix2 (-60)) by ring end.
  rewrite Rabs_Ropp, Rabs_pos_eq by apply bpow_ge_0.
  rewrite u_val in *. simpl bpow. lra.
Qed.

(** In nearest_hit: the ray o = 0, d = (1, 0, 0) and the planes p_a = n_a = (1, 0, 0) (t_a = 1) and
    p_b = (1, 2^-60, 0), n_b = (1, 1, 0) (t_b = 1 + 2^-60): stage 1's num_b rounds to 1, so it is uncertain;
    [compare_hit_distances_b] returns from stage 2 (stage 1) with the order −1 (a first), both ways round. *)
Example compare_hit_distances_stage2_example :
  let o := V3 w_zero w_zero w_zero in let d := V3 w_one w_zero w_zero in
  let pa := V3 w_one w_zero w_zero in let na := V3 w_one w_zero w_zero in
  let pb := V3 w_one w_2m60 w_zero in let nb := V3 w_one w_one w_zero in
  compare_quotients_filter_b
    (filter_enclosure_b (stage1_num_b o pa na) Cpp.filter_num_relative)
    (filter_enclosure_b (stage1_den_b d na) Cpp.filter_den_relative)
    (filter_enclosure_b (stage1_num_b o pb nb) Cpp.filter_num_relative)
    (filter_enclosure_b (stage1_den_b d nb) Cpp.filter_den_relative) = Uncertain /\
  compare_hit_distances_b o d pa na pb nb Positive Positive Positive Positive = ((-1)%Z, 1%Z) /\
  compare_hit_distances_b o d pb nb pa na Positive Positive Positive Positive = (1%Z, 1%Z).
Proof. vm_compute. repeat split; reflexivity. Qed.

Lemma w_fbnd : forall x, fin x = true -> Rabs (B2R x) <= 1 -> fbnd 400 x.
Proof. exact PlaneRefinedLiveness.fbnd_small. Qed.

Ltac w_small := apply w_fbnd; [vm_compute; reflexivity | w_vals;
  first [rewrite Rabs_R0; lra | rewrite Rabs_R1; lra | rewrite Rabs_pos_eq; lra |
         rewrite Rabs_Ropp, Rabs_pos_eq; [| pose proof (bpow_ge_0 radix2 (-103)); lra];
         simpl bpow; lra]].

(** k_1 cannot be replaced by 7·2^-103 (= k_1·7/26): n_1 = d_1 = d_2 = (1, 0, 0), n_2 = (1, −15·2^-103, 0) give
    V = 15·2^-103 > 7·2^-103·S' + k_3 (S' = 2), and stage 2 is uncertain on them (hi ⊕ lo = 15·2^-103 while
    E ⊕ E = 2·(2^-101 ⊗ 2) = 2^-99 = 16·2^-103).  So k_1 is within a factor 26/7 < 3.8 of the best constant. *)
Theorem compare_compensated_k1_fails : ~ (forall n1 d1 n2 d2,
  fbnd 400 (hib n1) -> fbnd 400 (lob n1) -> fbnd 400 (radiusb n1) ->
  fbnd 400 (hib d1) -> fbnd 400 (lob d1) -> fbnd 400 (radiusb d1) ->
  fbnd 400 (hib n2) -> fbnd 400 (lob n2) -> fbnd 400 (radiusb n2) ->
  fbnd 400 (hib d2) -> fbnd 400 (lob d2) -> fbnd 400 (radiusb d2) ->
  0 <= B2R (radiusb n1) -> 0 <= B2R (radiusb d1) -> 0 <= B2R (radiusb n2) -> 0 <= B2R (radiusb d2) ->
  7 * bpow radix2 (-103) * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    k2 * propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                          (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (cross_dd (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)) ->
  enclosure_sign_lanes_b (compare_quotients_compensated_b n1 d1 n2 d2) <> uncertain_lane).
Proof.
  intros H. apply (H (wenc w_one w_zero w_zero) (wenc w_one w_zero w_zero) (wenc w_one w_m15 w_zero)
                    (wenc w_one w_zero w_zero)); cbn [hib lob radiusb wenc];
    try w_small; try (rewrite w_zero_val; lra).
  - w_class.
    match goal with |- _ < Rabs ?V => replace V with (15 * bpow radix2 (-103)) by ring end.
    rewrite Rabs_pos_eq by (pose proof (bpow_ge_0 radix2 (-103)); lra).
    rewrite u_val in *. simpl bpow. lra.
  - vm_compute. reflexivity.
Qed.

(** k_2 cannot be replaced by 2 − 2^-19: n_1 = (1, 0, 0), d_1 = n_2 = (0, 0, 0), d_2 = (1, 0, 1/2) give V = 1,
    S' = 1, ρ' = 1/2, so V > k_1 + (2 − 2^-19)/2 + k_3, and stage 2 is uncertain (E ⊕ E ≈ 2·C_p·R > 1).
    So k_2 is within a factor (2 + 2^-38)/(2 − 2^-19) < 1 + 2^-19 of the best constant. *)
Theorem compare_compensated_k2_fails : ~ (forall n1 d1 n2 d2,
  fbnd 400 (hib n1) -> fbnd 400 (lob n1) -> fbnd 400 (radiusb n1) ->
  fbnd 400 (hib d1) -> fbnd 400 (lob d1) -> fbnd 400 (radiusb d1) ->
  fbnd 400 (hib n2) -> fbnd 400 (lob n2) -> fbnd 400 (radiusb n2) ->
  fbnd 400 (hib d2) -> fbnd 400 (lob d2) -> fbnd 400 (radiusb d2) ->
  0 <= B2R (radiusb n1) -> 0 <= B2R (radiusb d1) -> 0 <= B2R (radiusb n2) -> 0 <= B2R (radiusb d2) ->
  k1 * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    (2 - bpow radix2 (-19)) *
      propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                       (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (cross_dd (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)) ->
  enclosure_sign_lanes_b (compare_quotients_compensated_b n1 d1 n2 d2) <> uncertain_lane).
Proof.
  intros H. apply (H (wenc w_one w_zero w_zero) (wenc w_zero w_zero w_zero) (wenc w_zero w_zero w_zero)
                    (wenc w_one w_zero w_half)); cbn [hib lob radiusb wenc];
    try w_small; try (rewrite ?w_zero_val, ?w_half_val; lra).
  - w_class. match goal with |- _ < Rabs ?V => replace V with 1 by ring end. rewrite Rabs_R1.
    rewrite u_val in *. simpl bpow. lra.
  - vm_compute. reflexivity.
Qed.

(** The ray and planes of [compare_hit_distances_stage2_example] are in the class of
    [compare_hit_distances_stage2_live]: their stage-2 enclosures (hi, lo, radius) are (1, 0, 2^-101) for
    num_a, den_a, den_b and (1, 2^-60, 2^-101) for num_b (mantissas and exponents by [vm_compute]), so
    S' = 2, ρ' = 4·2^-101 + 2·2^-202 and |V| = 2^-60. *)
Definition wo : Vec3B := V3 w_zero w_zero w_zero.
Definition wd : Vec3B := V3 w_one w_zero w_zero.
Definition wpa : Vec3B := V3 w_one w_zero w_zero.
Definition wna : Vec3B := V3 w_one w_zero w_zero.
Definition wpb : Vec3B := V3 w_one w_2m60 w_zero.
Definition wnb : Vec3B := V3 w_one w_one w_zero.

Lemma float_val : forall x m e, mant x = m -> expo x = e -> B2R x = IZR m * bpow radix2 e.
Proof. intros x m e M E. rewrite B2R_mant_expo, M, E. reflexivity. Qed.

Lemma val_one : IZR 4503599627370496 * bpow radix2 (-52) = 1.
Proof. change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. reflexivity. Qed.
Lemma val_2m60 : IZR 4503599627370496 * bpow radix2 (-112) = bpow radix2 (-60).
Proof. change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. reflexivity. Qed.
Lemma val_2m101 : IZR 4503599627370496 * bpow radix2 (-153) = bpow radix2 (-101).
Proof. change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. reflexivity. Qed.
Lemma val_zero : IZR 0 * bpow radix2 0 = 0.
Proof. ring. Qed.

Ltac wfield v := rewrite (float_val _ _ _ eq_refl eq_refl); apply v.
Ltac w_disj := first [left; assumption | right; left; assumption | right; right; left; assumption |
                      right; right; right; assumption].

Example compare_hit_distances_stage2_example_in_class :
  let n1 := stage2_num_b wo wpa wna in let d1 := stage2_den_b wd wna in
  let n2 := stage2_num_b wo wpb wnb in let d2 := stage2_den_b wd wnb in
  (fbnd 400 (hib n1) /\ fbnd 400 (lob n1) /\ fbnd 400 (radiusb n1) /\
   fbnd 400 (hib d1) /\ fbnd 400 (lob d1) /\ fbnd 400 (radiusb d1) /\
   fbnd 400 (hib n2) /\ fbnd 400 (lob n2) /\ fbnd 400 (radiusb n2) /\
   fbnd 400 (hib d2) /\ fbnd 400 (lob d2) /\ fbnd 400 (radiusb d2)) /\
  k1 * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    k2 * propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                          (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (cross_dd (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2)).
Proof.
  intros n1 d1 n2 d2.
  assert (Hn1 : B2R (hib n1) = 1) by wfield val_one.
  assert (Ln1 : B2R (lob n1) = 0) by wfield val_zero.
  assert (En1 : B2R (radiusb n1) = bpow radix2 (-101)) by wfield val_2m101.
  assert (Hd1 : B2R (hib d1) = 1) by wfield val_one.
  assert (Ld1 : B2R (lob d1) = 0) by wfield val_zero.
  assert (Fd1 : B2R (radiusb d1) = bpow radix2 (-101)) by wfield val_2m101.
  assert (Hn2 : B2R (hib n2) = 1) by wfield val_one.
  assert (Ln2 : B2R (lob n2) = bpow radix2 (-60)) by wfield val_2m60.
  assert (En2 : B2R (radiusb n2) = bpow radix2 (-101)) by wfield val_2m101.
  assert (Hd2 : B2R (hib d2) = 1) by wfield val_one.
  assert (Ld2 : B2R (lob d2) = 0) by wfield val_zero.
  assert (Fd2 : B2R (radiusb d2) = bpow radix2 (-101)) by wfield val_2m101.
  assert (A1 : head (enc_R n1) = 1) by (rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]).
  assert (A2 : head (enc_R d1) = 1) by (rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]).
  assert (A3 : head (enc_R n2) = 1) by (rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]).
  assert (A4 : head (enc_R d2) = 1) by (rewrite (head_const _ w_one); [exact w_one_val | vm_compute; reflexivity ..]).
  pose proof (bpow_gt_0 radix2 (-101)) as P101. pose proof (bpow_gt_0 radix2 (-60)) as P60.
  assert (B101 : bpow radix2 (-101) <= 1) by (simpl bpow; lra).
  assert (B60 : bpow radix2 (-60) <= 1) by (simpl bpow; lra).
  assert (Fb : forall x, fin x = true -> B2R x = 0 \/ B2R x = 1 \/ B2R x = bpow radix2 (-101) \/
                         B2R x = bpow radix2 (-60) -> fbnd 400 x).
  { intros x F V. apply w_fbnd; [exact F|].
    destruct V as [V | [V | [V | V]]]; rewrite V; [rewrite Rabs_R0 | rewrite Rabs_R1 |
      rewrite Rabs_pos_eq | rewrite Rabs_pos_eq]; lra. }
  split.
  { do 11 (split; [apply Fb; [vm_compute; reflexivity | w_disj] |]).
    apply Fb; [vm_compute; reflexivity | w_disj]. }
  unfold cross_dd, dd, cross_magnitude, propagated_exact. rewrite A1, A2, A3, A4.
  unfold enc_R. cbn [hi lo]. rewrite Hn1, Ln1, Hd1, Ld1, Hn2, Ln2, Hd2, Ld2, En1, Fd1, En2, Fd2.
  match goal with |- _ < Rabs ?V => replace V with (- bpow radix2 (-60)) by ring end.
  rewrite Rabs_Ropp, (Rabs_pos_eq (bpow radix2 (-60))) by lra.
  rewrite ?Rmult_1_l, ?Rabs_R1, k1_u, k2_val. pose proof k3_small. pose proof u_pos.
  clear Fb. rewrite u_val in *. simpl bpow in *. pow_vals.
  lra.
Qed.

(** ** In the words of the exact values *)

(** The cross difference of any reals the four enclosures enclose is within (1 + u)·ρ' of V. *)
Lemma cross_dd_close : forall n1 d1 n2 d2 N1 D1 N2 D2,
  binary64 (hi n1) -> binary64 (lo n1) -> binary64 (hi d1) -> binary64 (lo d1) ->
  binary64 (hi n2) -> binary64 (lo n2) -> binary64 (hi d2) -> binary64 (lo d2) ->
  encloses n1 N1 -> encloses d1 D1 -> encloses n2 N2 -> encloses d2 D2 ->
  Rabs (N1 * D2 - N2 * D1 - cross_dd n1 d1 n2 d2) <=
    (1 + u) * propagated_exact (head n1) (radius n1) (head d1) (radius d1) (head n2) (radius n2)
                               (head d2) (radius d2).
Proof.
  intros n1 d1 n2 d2 N1 D1 N2 D2 Hn1 Ln1 Hd1 Ld1 Hn2 Ln2 Hd2 Ld2 E1 F1 E2 F2.
  assert (Norm : forall e V, binary64 (hi e) -> binary64 (lo e) -> encloses e V ->
            Rabs (snd (two_sum (hi e) (lo e))) <= u * Rabs (head e) /\
            Rabs (head e + snd (two_sum (hi e) (lo e)) - V) <= radius e /\
            head e + snd (two_sum (hi e) (lo e)) = dd e).
  { intros e V Bh Bl HV. unfold head, dd. pose proof (two_sum_exact (hi e) (lo e) Bh Bl) as X.
    split; [apply (two_sum_lo_bound (hi e) (lo e) Bh Bl)|].
    rewrite X, Rabs_minus_sym. split; [exact HV | reflexivity]. }
  destruct (Norm n1 N1 Hn1 Ln1 E1) as [La1 [Ea1 Xa1]]. destruct (Norm d1 D1 Hd1 Ld1 F1) as [Lb1 [Eb1 Xb1]].
  destruct (Norm n2 N2 Hn2 Ln2 E2) as [La2 [Ea2 Xa2]]. destruct (Norm d2 D2 Hd2 Ld2 F2) as [Lb2 [Eb2 Xb2]].
  pose proof (input_error_dd N1 D2 _ _ _ _ _ _ La1 Lb2 Ea1 Eb2) as I1.
  pose proof (input_error_dd N2 D1 _ _ _ _ _ _ La2 Lb1 Ea2 Eb1) as I2.
  rewrite Xa1, Xb2 in I1. rewrite Xa2, Xb1 in I2.
  unfold cross_dd, propagated_exact.
  replace (N1 * D2 - N2 * D1 - (dd n1 * dd d2 - dd n2 * dd d1))
    with ((N1 * D2 - dd n1 * dd d2) - (N2 * D1 - dd n2 * dd d1)) by ring.
  unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra.
Qed.

Definition k2_exact : R := 3 + bpow radix2 (-37).

(** For any reals N_i, D_i the four stage-2 enclosures enclose (num and den of the two planes along the ray),
    stage 2 is certain whenever the exact cross difference |N_1·D_2 − N_2·D_1| exceeds k_1·S' + (3 + 2^-37)·ρ' + k_3
    (k_2 + 1 + u ≤ 3 + 2^-37: the input error adds (1 + u)·ρ'). *)
Corollary compare_compensated_live_exact : forall n1 d1 n2 d2 N1 D1 N2 D2,
  fbnd 400 (hib n1) -> fbnd 400 (lob n1) -> fbnd 400 (radiusb n1) ->
  fbnd 400 (hib d1) -> fbnd 400 (lob d1) -> fbnd 400 (radiusb d1) ->
  fbnd 400 (hib n2) -> fbnd 400 (lob n2) -> fbnd 400 (radiusb n2) ->
  fbnd 400 (hib d2) -> fbnd 400 (lob d2) -> fbnd 400 (radiusb d2) ->
  encloses (enc_R n1) N1 -> encloses (enc_R d1) D1 -> encloses (enc_R n2) N2 -> encloses (enc_R d2) D2 ->
  k1 * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    k2_exact * propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                                (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (N1 * D2 - N2 * D1) ->
  enclosure_sign_lanes_b (compare_quotients_compensated_b n1 d1 n2 d2) <> uncertain_lane.
Proof.
  intros n1 d1 n2 d2 N1 D1 N2 D2 Hn1 Ln1 En1 Hd1 Ld1 Fd1 Hn2 Ln2 En2 Hd2 Ld2 Fd2 E1 F1 E2 F2 L.
  assert (P : forall e V, encloses e V -> 0 <= radius e) by
    (intros e V H; eapply Rle_trans; [apply Rabs_pos | exact H]).
  pose proof (P _ _ E1) as Pe1. pose proof (P _ _ F1) as Pf1. pose proof (P _ _ E2) as Pe2. pose proof (P _ _ F2) as Pf2.
  cbn [enc_R radius] in Pe1, Pf1, Pe2, Pf2.
  apply compare_compensated_live; try assumption.
  pose proof (cross_dd_close (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2) N1 D1 N2 D2
                (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
                (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) E1 F1 E2 F2) as C.
  cbn [enc_R radius] in C.
  assert (R0 : 0 <= propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                                     (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2))).
  { unfold propagated_exact.
    pose proof (propagated_nonneg (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d2)) (B2R (radiusb d2)) Pe1 Pf2).
    pose proof (propagated_nonneg (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d1)) (B2R (radiusb d1)) Pe2 Pf1).
    lra. }
  set (rho := propagated_exact _ _ _ _ _ _ _ _) in *.
  set (S := cross_magnitude _ _ _ _) in *.
  set (V := cross_dd _ _ _ _) in *.
  set (X := N1 * D2 - N2 * D1) in *.
  clearbody rho S V X.
  assert (T : Rabs X <= Rabs V + (1 + u) * rho).
  { replace X with (V + (X - V)) by ring. eapply Rle_trans; [apply Rabs_triang|]. lra. }
  unfold k2_exact in L. rewrite k2_val. pose proof u_pos. rewrite u_val in *. simpl bpow in L. lra.
Qed.

(** In nearest_hit, with the exact values: when the four stage-2 enclosures are finite of magnitude ≤ 2^400
    and the exact Δ = num_a·den_b − num_b·den_a of the ray and the two planes exceeds k_1·S' + (3 + 2^-37)·ρ'
    + k_3 (S', ρ' of the enclosures), [compare_hit_distances_b] returns by stage 2 at the latest. *)
Corollary compare_hit_distances_stage2_live_exact : forall o d pa na pb nb nsa dsa nsb dsb,
  let n1 := stage2_num_b o pa na in let d1 := stage2_den_b d na in
  let n2 := stage2_num_b o pb nb in let d2 := stage2_den_b d nb in
  fbnd 400 (hib n1) -> fbnd 400 (lob n1) -> fbnd 400 (radiusb n1) ->
  fbnd 400 (hib d1) -> fbnd 400 (lob d1) -> fbnd 400 (radiusb d1) ->
  fbnd 400 (hib n2) -> fbnd 400 (lob n2) -> fbnd 400 (radiusb n2) ->
  fbnd 400 (hib d2) -> fbnd 400 (lob d2) -> fbnd 400 (radiusb d2) ->
  k1 * cross_magnitude (head (enc_R n1)) (head (enc_R d1)) (head (enc_R n2)) (head (enc_R d2)) +
    k2_exact * propagated_exact (head (enc_R n1)) (B2R (radiusb n1)) (head (enc_R d1)) (B2R (radiusb d1))
                                (head (enc_R n2)) (B2R (radiusb n2)) (head (enc_R d2)) (B2R (radiusb d2)) + k3 <
    Rabs (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
          ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)) ->
  (snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <= 1)%Z.
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb n1 d1 n2 d2 Hn1 Ln1 En1 Hd1 Ld1 Fd1 Hn2 Ln2 En2 Hd2 Ld2 Fd2 L.
  rewrite !ray_num_bits, !ray_den_bits in L.
  pose proof (num_compensated_encloses_b (vxb pa) (vyb pa) (vzb pa) (vxb o) (vyb o) (vzb o) (vxb na) (vyb na)
                (vzb na) (proj1 Hn1) (proj1 Ln1) (proj1 En1)) as E1.
  pose proof (den_compensated_encloses_b (vxb d) (vyb d) (vzb d) (vxb na) (vyb na) (vzb na)
                (proj1 Hd1) (proj1 Ld1) (proj1 Fd1)) as F1.
  pose proof (num_compensated_encloses_b (vxb pb) (vyb pb) (vzb pb) (vxb o) (vyb o) (vzb o) (vxb nb) (vyb nb)
                (vzb nb) (proj1 Hn2) (proj1 Ln2) (proj1 En2)) as E2.
  pose proof (den_compensated_encloses_b (vxb d) (vyb d) (vzb d) (vxb nb) (vyb nb) (vzb nb)
                (proj1 Hd2) (proj1 Ld2) (proj1 Fd2)) as F2.
  pose proof (is_certain_lane _ (compare_compensated_live_exact n1 d1 n2 d2 _ _ _ _ Hn1 Ln1 En1 Hd1 Ld1 Fd1
                                   Hn2 Ln2 En2 Hd2 Ld2 Fd2 E1 F1 E2 F2 L)) as C.
  unfold n1, d1, n2, d2 in C.
  unfold compare_hit_distances_b. cbv zeta. destruct (_ || _)%bool; [cbn [snd]; lia|].
  destruct (is_certain_b (compare_quotients_filter_b _ _ _ _)); [cbn [snd]; lia|].
  rewrite C. cbn [snd]. lia.
Qed.
