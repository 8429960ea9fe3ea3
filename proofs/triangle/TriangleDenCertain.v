(** * A quotient certified over den's divisor implies den's stage-1 filter sign is certain
    (kernel/src/triangle/ray_triangle_cascade.cpp, [fast_triangle_intersection]).

    - [den_filter_margin] (reals): if the divisor's radius E_d = (256u² ⊗ m) ⊕ A is at most u·|D| with
      2^-1000 ≤ |D| and |den| ≥ (1 − 2u)|D|, then den's stage-1 bound B = (10u ⊗ m) ⊕ A (the same m and A)
      is below |den|/2 — so a stage-1 value h within B of den has |h| > B;
    - [den_quotient_filter_certain]: whenever [round_quotient_b num (shared_divisor_b ed)] certifies (ed den's
      stage-2 enclosure, [den_lane_enc]), den's stage-1 filter sign with den's own constant is certain.  Through
      PlaneQueryTwins.v's [round_quotient_twin] and QuotientDivisorBound.v's [round_quotient_certain_divisor]
      (E_d ≤ u·|D|), TriangleFilter.v's [den_filter_encloses] (|h − den| ≤ B) and the margin above;
    - its consequences for two mutations of run.py, each mutated twin equal to the twin for every bit pattern:
      [tri_call_site_den_same] (den filtered with π's constant) and [tri_by_filter_den_same] (the stage label
      [by_filter] not reading den's filter sign). *)

From Coq Require Import Reals Lra ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated QuotientRounding QuotientDivisorBound FloatCore ConstantsCpp
  PlaneTwins PlaneQueryTwins TriangleFilter TriangleTwins TriangleIntersectTwins TriangleIntersectTheorem TriangleMutations.
Open Scope R_scope.

Theorem den_filter_margin : forall h m A V Dm,
  0 <= m -> 0 <= A -> binary64 A ->
  Rabs (h - V) <= RN (RN (triangle_filter_den_relative * m) + A) ->
  RN (RN (triangle_compensated_den_relative * m) + A) <= u * Dm ->
  divisor_min_magnitude <= Dm -> (1 - 2 * u) * Dm <= Rabs V ->
  RN (RN (triangle_filter_den_relative * m) + A) < Rabs h.
Proof.
  intros h m A V Dm Pm PA BA Hh HE GD HV.
  unfold triangle_filter_den_relative, triangle_compensated_den_relative in *.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  set (r1 := RN (256 * (u * u) * m)) in *. set (b1 := RN (10 * u * m)) in *.
  assert (P1 : 0 <= 256 * (u * u) * m) by (apply Rmult_le_pos; [nra | lra]).
  assert (P2 : 0 <= 10 * u * m) by (apply Rmult_le_pos; [lra | lra]).
  pose proof (RN_err (256 * (u * u) * m)) as E1. fold r1 in E1. rewrite (Rabs_pos_eq (256 * (u * u) * m)) in E1 by exact P1.
  pose proof (RN_err (10 * u * m)) as E2. fold b1 in E2. rewrite (Rabs_pos_eq (10 * u * m)) in E2 by exact P2.
  assert (Pr1 : 0 <= r1) by (apply RN_nonneg; exact P1).
  assert (Pb1 : 0 <= b1) by (apply RN_nonneg; exact P2).
  pose proof (RN_plus_err r1 A ltac:(apply binary64_RN) BA) as E3. rewrite (Rabs_pos_eq (r1 + A)) in E3 by lra.
  pose proof (RN_plus_err b1 A ltac:(apply binary64_RN) BA) as E4. rewrite (Rabs_pos_eq (b1 + A)) in E4 by lra.
  apply Rabs_bounds in E1. apply Rabs_bounds in E2. apply Rabs_bounds in E3. apply Rabs_bounds in E4.
  set (Ed := RN (r1 + A)) in *. set (B := RN (b1 + A)) in *.
  assert (Th : Rabs V - Rabs (h - V) <= Rabs h).
  { pose proof (Rabs_triang h (V - h)) as T. replace (h + (V - h)) with V in T by ring.
    rewrite Rabs_minus_sym in T. lra. }
  assert (Eta : eta <= / 2 ^ 75 * Dm).
  { apply Rle_trans with (/ 2 ^ 75 * divisor_min_magnitude); [|apply Rmult_le_compat_l; [simpl; lra | exact GD]].
    unfold eta, divisor_min_magnitude. replace (-1075)%Z with (-75 + -1000)%Z by reflexivity.
    rewrite bpow_plus. apply Req_le. f_equal. simpl. lra. }
  assert (DmP : 0 < Dm) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact GD]).
  clear GD. rewrite u_val in *. simpl in Eta. lra.
Qed.

(** den's stage-1 view (the hi parts of den's stage-2 term): a finite magnitude makes it the model's. *)
Lemma den_view_twin : forall o d a b c, fin (fmb (fview (den_stage2_b (bcast o) d a b c))) = true ->
  (tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c) /\
  ftw (fview (den_stage2_b (bcast o) d a b c)) (den_stage1 (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c H.
  assert (V : fview (den_stage2_b (bcast o) d a b c) =
              term_add_b (term_add_b (fview (pi_stage2_b (bcast o) d b c)) (fview (pi_stage2_b (bcast o) d c a)))
                         (fview (pi_stage2_b (bcast o) d a b))) by reflexivity.
  rewrite V in *. unfold den_stage1.
  destruct (term_add_back _ _ H) as [H01 H2]. destruct (term_add_back _ _ H01) as [H0 H1].
  destruct (pi_view_twin _ _ _ _ H0) as [Fo [Fd [Fb [Fc T0]]]].
  destruct (pi_view_twin _ _ _ _ H1) as [_ [_ [_ [Fa T1]]]].
  destruct (pi_view_twin _ _ _ _ H2) as [_ [_ [_ [_ T2]]]].
  destruct (bcast_twin o Fo) as [Fo' Eo]. rewrite Eo in T0, T1, T2.
  split; [tsplit; assumption | ftw_fwd].
Qed.

(** A finite radius of den's enclosure is (K_den ⊗ m) ⊕ A, with h, l, m, A finite. *)
Lemma den_lane_enc_radius : forall o d a b c, fin (radiusb (den_lane_enc o d a b c)) = true ->
  let t := den_stage2_b (bcast o) d a b c in
  fin (chb t) = true /\ fin (cmb t) = true /\ fin (absolute_bv d) = true /\
  B2R (radiusb (den_lane_enc o d a b c)) =
    RN (RN (B2R Cpp.triangle_compensated_den_relative * B2R (cmb t)) + B2R (absolute_bv d)).
Proof.
  intros o d a b c F. cbv zeta. unfold den_lane_enc in *. revert F.
  generalize (den_stage2_b (bcast o) d a b c) as t. intros t F. unfold det3_enclosure_b in *. cbn [radiusb] in F |- *.
  rewrite !fle_largest_finite in F |- *.
  destruct (fin (chb t)) eqn:Fh; [|discriminate]. destruct (fin (clb t)) eqn:Fl; [|discriminate].
  cbn [andb] in F |- *. destruct (fadd_fin _ _ F) as [Fp FA]. destruct (fmul_fin _ _ Fp) as [_ Fm].
  repeat split; try assumption. rewrite (fadd_val _ _ F), (fmul_val _ _ Fp). reflexivity.
Qed.

Lemma nonneg_fin_R : forall x, nonneg x -> fin x = true -> 0 <= B2R x.
Proof.
  intros [s|s| |s m e H] [N|N] F; try discriminate; cbn in N; try (subst; apply Bsign_false_nonneg; reflexivity);
    cbn; lra.
Qed.

(** Whenever a quotient is certified over den's divisor ([shared_divisor_b] of den's stage-2 enclosure), den's
    stage-1 filter sign with den's own constant (10u) is certain. *)
Theorem den_quotient_filter_certain : forall (num : EnclosureB) o d a b c,
  nonneg (radiusb num) ->
  snd (round_quotient_b num (shared_divisor_b (den_lane_enc o d a b c))) = true ->
  det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative (absolute_bv d)
    <> uncertain_lane.
Proof.
  intros num o d a b c Nn C.
  destruct (den_lane_enc_facts o d a b c) as [Nd Ed].
  remember (den_lane_enc o d a b c) as ed eqn:Eed in *.
  rewrite (proj2 (shared_divisor_zr num ed)) in C.
  destruct (round_quotient_twin num ed Nn Nd C) as [Fnh [Fnl [Fnr [Fdh [Fdl [Fdr [_ [_ Cm]]]]]]]].
  destruct (Ed Fdr) as [_ [_ [_ Enc]]].
  set (V := den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) in *.
  destruct (round_quotient_certain_divisor (enc_R num) (enc_R ed) V
              (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
              (nonneg_fin_R _ Nn Fnr) Enc Cm) as [RD [[GD1 GD2] HV]].
  set (Dm := Rabs (fst (two_sum (hi (enc_R ed)) (lo (enc_R ed))))) in *.
  destruct (den_lane_enc_radius o d a b c ltac:(rewrite <- Eed; exact Fdr)) as [Fh [Fm [FA Er]]].
  destruct (den_view_twin o d a b c Fm) as [[Fo [Fd [Fa [Fb Fc]]]] [Fv [_ [Ev [Em _]]]]].
  (* [remember], not [set]: a let-bound t makes the kernel compare t with its unfolded body (minutes at Qed) *)
  remember (den_stage2_b (bcast o) d a b c) as t eqn:Et in *.
  change (radius (enc_R ed)) with (B2R (radiusb ed)) in RD. rewrite <- Eed in Er. rewrite Er in RD.
  destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [_ [_ [FC [NC [_ [_ [_ NK]]]]]]]]]]]]].
  assert (PA : 0 <= B2R (absolute_bv d)) by (apply nonneg_fin_R; [apply absolute_bv_nonneg | exact FA]).
  assert (Pm : 0 <= B2R (cmb t)) by (apply nonneg_fin_R; [rewrite Et; apply den_lane_cmb_nonneg | exact Fm]).
  assert (Encl := den_filter_encloses (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)
                    (tvec_R_doubles o) (tvec_R_doubles d) (tvec_R_doubles a) (tvec_R_doubles b) (tvec_R_doubles c)).
  fold V in Encl. unfold det3_bound in Encl.
  rewrite <- (proj2 (absolute_bv_twin d FA)) in Encl.
  change (fmb (fview t)) with (cmb t) in Em. change (fvb (fview t)) with (chb t) in Ev, Fv.
  rewrite <- Em, <- Ev in Encl.
  rewrite cpp_triangle_compensated_den_relative in RD.
  assert (M := den_filter_margin (B2R (chb t)) (B2R (cmb t)) (B2R (absolute_bv d)) V Dm Pm PA (binary64_B2R _)
                 Encl RD GD1 HV).
  (* the float bound is finite and is the model's *)
  pose proof u_pos as Hu.
  assert (Pc : 0 <= triangle_filter_den_relative <= 1)
    by (unfold triangle_filter_den_relative; rewrite u_val; lra).
  assert (Lm : Rabs (RN (B2R Cpp.triangle_filter_den_relative * B2R (cmb t))) < bpow radix2 1024).
  { rewrite cpp_triangle_filter_den_relative. rewrite Rabs_pos_eq by (apply RN_nonneg; nra).
    apply Rle_lt_trans with (RN (B2R (cmb t))); [apply RN_le; nra|].
    rewrite RN_binary64 by apply binary64_B2R. pose proof (B2R_lt_overflow (cmb t)) as O.
    rewrite Rabs_pos_eq in O by exact Pm. exact O. }
  destruct (fmul_fwd _ _ FC Fm Lm) as [Fp Vp].
  assert (Lb : Rabs (RN (B2R (fmul Cpp.triangle_filter_den_relative (cmb t)) + B2R (absolute_bv d))) <
               bpow radix2 1024).
  { rewrite Vp, cpp_triangle_filter_den_relative.
    pose proof (Rabs_pos (B2R (chb t))). pose proof (B2R_lt_overflow (chb t)).
    rewrite Rabs_pos_eq by (apply RN_nonneg; apply Rplus_le_le_0_compat; [apply RN_nonneg; nra | exact PA]).
    lra. }
  destruct (fadd_fwd _ _ Fp FA Lb) as [Fb' Vb].
  rewrite cpp_triangle_filter_den_relative in Vp.
  assert (PB : 0 <= RN (RN (triangle_filter_den_relative * B2R (cmb t)) + B2R (absolute_bv d))).
  { apply RN_nonneg. apply Rplus_le_le_0_compat; [apply RN_nonneg; nra | exact PA]. }
  assert (Fnb : fin (fneg (fadd (fmul Cpp.triangle_filter_den_relative (cmb t)) (absolute_bv d))) = true)
    by (rewrite fneg_fin; exact Fb').
  unfold det3_filter_lanes_b. change (fmb (fview t)) with (cmb t). change (fvb (fview t)) with (chb t).
  rewrite (flt_val _ _ Fb' Fh), (flt_val _ _ Fh Fnb), fneg_val, Vb, Vp.
  destruct (Rle_or_lt 0 (B2R (chb t))) as [S|S].
  - rewrite Rabs_pos_eq in M by exact S. rewrite (Rlt_bool_true _ _ M), Rlt_bool_false by lra.
    intros Y; compute in Y; discriminate Y.
  - rewrite Rabs_left in M by exact S. rewrite Rlt_bool_false by lra. rewrite Rlt_bool_true by lra.
    intros Y; compute in Y; discriminate Y.
Qed.

(** ** tri_call_site_den: the mutated twin answers as the twin for every bit pattern *)

Lemma core_none_uncertified : forall den_in_filter want_t want_u fa fb fc fn fd ga gb gc gn gd qa qb qc qn,
  (negb want_t && negb want_u)%bool = false -> snd qa = false -> snd qn = false ->
  fast_intersection_core den_in_filter want_t want_u fa fb fc fn fd ga gb gc gn gd qa qb qc qn = None.
Proof.
  intros den_in_filter want_t want_u fa fb fc fn fd ga gb gc gn gd qa qb qc qn W Qa Qn. unfold fast_intersection_core. cbv zeta.
  rewrite Qa, Qn. destruct want_t, want_u; try discriminate W; cbn [negb orb andb];
    repeat match goal with
    | |- (if ?b then _ else _) = None => destruct b
    | |- match ?m with Some _ => _ | None => _ end = None => destruct m
    end; reflexivity.
Qed.

(** With den's stage-1 sign uncertain under den's constant, no quotient is certified over den's divisor, so the
    twin with any den constant answers nothing (with t or the barycentrics asked). *)
Lemma mut_none_den_uncertain : forall C f want_t want_u o d a b c,
  (negb want_t && negb want_u)%bool = false ->
  det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative (absolute_bv d)
    = uncertain_lane ->
  fast_intersection_mut_b det3_enclosure_b C f want_t want_u o d a b c = None.
Proof.
  intros C f want_t want_u o d a b c W U.
  assert (NQ : forall num, nonneg (radiusb num) ->
                snd (round_quotient_b num (shared_divisor_b (den_lane_enc o d a b c))) = false).
  { intros num N. apply not_true_is_false. intros S. exact (den_quotient_filter_certain num o d a b c N S U). }
  pose proof (NQ _ (proj1 (pi_lane_enc_facts o d b c))) as Qa.
  pose proof (NQ _ (proj1 (num_lane_enc_facts o a b c))) as Qn.
  unfold fast_intersection_mut_b. rewrite W. cbv zeta.
  apply core_none_uncertified; [exact W | exact Qa | exact Qn].
Qed.

(** [fast_triangle_intersection] with den filtered by π's constant (mutation [tri_call_site_den]) answers as
    [fast_triangle_intersection], for every 64-bit pattern of o, d, a, b, c and every option set: outside the
    window of [tri_call_site_den_same_unless_between] by that theorem; inside it (den's view uncertain with 10u)
    neither answers, since an answer needs a quotient certified over den's divisor
    ([den_quotient_filter_certain]). *)
Theorem tri_call_site_den_same : forall want_t want_u (o d a b c : TVec),
  fast_intersection_call_site_den_b want_t want_u o d a b c = fast_intersection_tri_b want_t want_u o d a b c.
Proof.
  intros want_t want_u o d a b c.
  destruct (Z.eq_dec (det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative
                        (absolute_bv d)) uncertain_lane) as [U|U].
  2:{ apply tri_call_site_den_same_unless_between. left. exact U. }
  transitivity (fast_intersection_mut_b det3_enclosure_b Cpp.triangle_filter_den_relative true want_t want_u o d a b c);
    [| apply fast_intersection_mut_original].
  unfold fast_intersection_call_site_den_b.
  destruct (negb want_t && negb want_u)%bool eqn:W.
  - unfold fast_intersection_mut_b. rewrite W. reflexivity.
  - rewrite !mut_none_den_uncertain by assumption. reflexivity.
Qed.

(** ** tri_by_filter_den: [by_filter] without den's filter sign *)

(** [fast_triangle_intersection] whose stage label [by_filter] does not read den's stage-1 filter sign (mutation
    [tri_by_filter_den] of proofs/mutation/run.py). *)
Definition fast_intersection_by_filter_den_b :=
  fast_intersection_mut_b det3_enclosure_b Cpp.triangle_filter_den_relative false.

Lemma core_den_in_filter_certain : forall want_t want_u fa fb fc fn fd ga gb gc gn gd qa qb qc qn,
  certain_lane fd = true ->
  fast_intersection_core false want_t want_u fa fb fc fn fd ga gb gc gn gd qa qb qc qn =
  fast_intersection_core true want_t want_u fa fb fc fn fd ga gb gc gn gd qa qb qc qn.
Proof. intros until qn. intros D. unfold fast_intersection_core. rewrite D. reflexivity. Qed.

(** The mutated twin answers as [fast_intersection_tri_b], for every 64-bit pattern of o, d, a, b, c and every option
    set: where den's filter sign is certain [by_filter] reads the same; where it is uncertain neither answers
    (with t or the barycentrics asked, an answer needs a quotient certified over den's divisor, which makes den's
    filter sign certain: [den_quotient_filter_certain] through [mut_none_den_uncertain]; with neither asked the
    relation's fast path answers, which has no [by_filter]). *)
Theorem tri_by_filter_den_same : forall want_t want_u (o d a b c : TVec),
  fast_intersection_by_filter_den_b want_t want_u o d a b c = fast_intersection_tri_b want_t want_u o d a b c.
Proof.
  intros want_t want_u o d a b c.
  transitivity (fast_intersection_mut_b det3_enclosure_b Cpp.triangle_filter_den_relative true want_t want_u o d a b c);
    [| apply fast_intersection_mut_original].
  unfold fast_intersection_by_filter_den_b.
  destruct (negb want_t && negb want_u)%bool eqn:W.
  - unfold fast_intersection_mut_b. rewrite W. reflexivity.
  - destruct (Z.eq_dec (det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c))
                          Cpp.triangle_filter_den_relative (absolute_bv d)) uncertain_lane) as [U|U].
    + rewrite !mut_none_den_uncertain by assumption. reflexivity.
    + unfold fast_intersection_mut_b. rewrite W. cbv zeta. apply core_den_in_filter_certain.
      unfold certain_lane. apply negb_true_iff. apply Z.eqb_neq. exact U.
Qed.
