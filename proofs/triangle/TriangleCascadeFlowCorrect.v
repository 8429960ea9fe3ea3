(** * What an answer of the ray–triangle cascade's twin before the exact stage means
    (TriangleCascadeFlowTwins.v; kernel/src/triangle/ray_triangle_cascade.cpp, [TriangleCascade]).

    For every 64-bit pattern of o, d, a, b, c:
    - [tc_sign_b_correct] (the signs part): a sign [TriangleCascade::sign(v)] returns without setting
      [needs_exact_] is the exact sign of determinant v (πa, πb, πc, den, num: [value_model]), whichever
      stage decided it (stage 1: TriangleTwins.v's filter theorems; stage 2: a certain enclosure sign needs
      finite h and l, [det3_enclosure_certain_finite], then the enclosure theorems; stage 3:
      [triangle_expansion_sign_sound]);
    - [tc_tie_break_b_correct] (the tie-break part): the three signs [tie_break(k)] returns without
      [needs_exact_] are the exact signs of the components of d × (q − p) (TriangleRule.v's [tie_break]);
      [tc_normal_b_correct]: [normal_is_zero()] is whether N = (b − a) × (c − a) is the zero vector;
    - [tc_classify_b_correct]: when [classify] answers (no [needs_exact_]), its classification is
      docs/contract.md §6's ([contract_class], TriangleCascadeTwins.v) for the exact values under the rule;
    - [tc_relation_b_correct]: the same for [triangle_relation_cascade]'s answer before the exact stage, and
      [tc_intersect_b_class_correct] for [triangle_intersection_cascade]'s classification;
    - of the quotients: [tc_zero_quotient_correct] (an exactly zero numerator's +0 is RN(0/den)) and
      [tc_stage3_quotient_correct] (stage 3's [round_quotient] on the tail enclosures, over den's tail
      enclosure or stage 2's: when certain, den ≠ 0 and the value is RN(value/den)).  Stage 2's rounding over
      the broadcast divisor ([shared_divisor_b]) and the whole answer are proved in
      TriangleCascadeQuotients.v ([tc_intersect_b_correct]).
    Lemmas of the same kind as TriangleIntersectTheorem.v's (another file, written in parallel) carry
    other names here ([tcf_*]). *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification PlaneCascade FloatCore ConstantsCpp PlaneTwins
  Expansions PlaneQueryTwins TriangleFilter TriangleRule TriangleTwins TriangleStage3Twins TriangleCascadeTwins TriangleIntersectTwins
  TriangleCascadeFlowTwins TriangleIntegerSign.
From Raykernel Require PlaneCascadeTwins.
Import ListNotations.
Open Scope R_scope.

(** ** Stage 2: a certain sign of [det3_enclosure] needs finite h and l. *)

Lemma tcf_twice_inf : fadd finf finf = finf.
Proof. reflexivity. Qed.

Lemma det3_enclosure_certain_finite : forall t K A,
  enclosure_sign_lanes_b (det3_enclosure_b t K A) <> uncertain_lane -> fin (chb t) = true /\ fin (clb t) = true.
Proof.
  intros t K A U. unfold det3_enclosure_b in U. rewrite !fle_largest_finite in U.
  destruct (fin (chb t)) eqn:Fh; destruct (fin (clb t)) eqn:Fl; try (split; reflexivity); exfalso; apply U;
    unfold enclosure_sign_lanes_b; cbn [hib lob radiusb andb]; rewrite tcf_twice_inf;
    change (fneg finf) with (@B754_infinity 53 1024 true); unfold finf;
    rewrite flt_pinf_l, flt_ninf_r; reflexivity.
Qed.

Lemma det3_enclosure_nonneg : forall t K A, nonneg K -> nonneg (cmb t) -> nonneg A ->
  nonneg (radiusb (det3_enclosure_b t K A)).
Proof.
  intros t K A NK Nm NA. unfold det3_enclosure_b. cbn [radiusb].
  destruct (_ && _)%bool; [apply fadd_nonneg; [apply fmul_nonneg|]; assumption|].
  right. reflexivity.
Qed.

Lemma tcf_cdet3_nonneg : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  nonneg (cmb (cdet3_b xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2)).
Proof. intros. exact (cdet3_b_nonneg xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2). Qed.

Lemma tcf_pi2_nonneg : forall o d p q, nonneg (cmb (pi_stage2_b o d p q)).
Proof. intros. unfold pi_stage2_b. apply tcf_cdet3_nonneg. Qed.
Lemma tcf_num2_nonneg : forall o a b c, nonneg (cmb (num_stage2_b o a b c)).
Proof. intros. unfold num_stage2_b. apply tcf_cdet3_nonneg. Qed.

Lemma tcf_value2_nonneg : forall o d a b c v, nonneg (cmb (tc_value2_b o d a b c v)).
Proof.
  intros. unfold tc_value2_b.
  destruct (Z.eqb v 0); [apply tcf_pi2_nonneg|]. destruct (Z.eqb v 1); [apply tcf_pi2_nonneg|].
  destruct (Z.eqb v 2); [apply tcf_pi2_nonneg|].
  destruct (Z.eqb v 3); [|apply tcf_num2_nonneg].
  unfold den_stage2_b. change (nonneg (fadd (fadd (cmb (pi_stage2_b o d b c)) (cmb (pi_stage2_b o d c a)))
                                               (cmb (pi_stage2_b o d a b)))).
  apply fadd_nonneg; [apply fadd_nonneg|]; apply tcf_pi2_nonneg.
Qed.

(** The determinants' indices 0..4 (πa, πb, πc, den, num): the only ones the cascade asks for. *)
Definition tc_index (v : Z) : Prop := (0 <= v <= 4)%Z.

Lemma tc_index_cases : forall v, tc_index v -> v = 0%Z \/ v = 1%Z \/ v = 2%Z \/ v = 3%Z \/ v = 4%Z.
Proof. unfold tc_index. intros v H. lia. Qed.

(** The enclosure of determinant v encloses the model's value whenever its radius is finite. *)
Lemma tc_enclosure2_encloses : forall o d a b c v, tc_index v -> fin (radiusb (tc_enclosure2_b o d a b c v)) = true ->
  encloses (enc_R (tc_enclosure2_b o d a b c v)) (value_model o d a b c v).
Proof.
  intros o d a b c v I F. unfold tc_enclosure2_b, tc_value2_b, tc_compensated_relative, tc_absolute2_b, value_model in *.
  cbv zeta in *.
  destruct (tc_index_cases v I) as [->|[->|[->|[->| ->]]]]; cbn [Z.eqb Pos.eqb] in *.
  - exact (proj2 (proj2 (proj2 (proj2 (triangle_pi_compensated_twin_sound o d b c F))))).
  - exact (proj2 (proj2 (proj2 (proj2 (triangle_pi_compensated_twin_sound o d c a F))))).
  - exact (proj2 (proj2 (proj2 (proj2 (triangle_pi_compensated_twin_sound o d a b F))))).
  - exact (proj2 (proj2 (proj2 (proj2 (proj2 (triangle_den_compensated_twin_sound o d a b c F)))))).
  - exact (proj2 (proj2 (proj2 (proj2 (triangle_num_compensated_twin_sound o a b c F))))).
Qed.

Lemma tc_enclosure2_sign_sound : forall o d a b c v, tc_index v ->
  certifies (PlaneCascadeTwins.enclosure_sign_b (tc_enclosure2_b o d a b c v)) (value_model o d a b c v).
Proof.
  intros o d a b c v I. destruct cpp_triangle_constants as [_ [_ [_ [NA [_ [_ [_ [_ [_ [_ [_ [NK [_ NKd]]]]]]]]]]]]].
  apply PlaneCascadeTwins.enclosure_sign_b_certifies.
  - unfold tc_enclosure2_b. apply det3_enclosure_nonneg; [| apply tcf_value2_nonneg |].
    + unfold tc_compensated_relative. destruct (Z.eqb v 3); assumption.
    + unfold tc_absolute2_b. destruct (Z.eqb v 4); apply absolute_bv_nonneg.
  - intros U. unfold tc_enclosure2_b in *. exact (det3_enclosure_certain_finite _ _ _ U).
  - intros _ _ F. exact (tc_enclosure2_encloses o d a b c v I F).
Qed.

(** Stage 1 of determinant v. *)
Lemma tc_filter_sound : forall o d a b c v, tc_index v ->
  certifies (sign_from_Z (tc_filter_b o d a b c v)) (value_model o d a b c v).
Proof.
  intros o d a b c v I. unfold tc_filter_b, tc_value1_b, tc_filter_relative, tc_absolute1_b, value_model. cbv zeta.
  destruct (tc_index_cases v I) as [->|[->|[->|[->| ->]]]]; cbn [Z.eqb Pos.eqb].
  - exact (proj1 (triangle_pi_filter_twin_sound o d b c)).
  - exact (proj1 (triangle_pi_filter_twin_sound o d c a)).
  - exact (proj1 (triangle_pi_filter_twin_sound o d a b)).
  - exact (proj1 (triangle_den_filter_twin_sound o d a b c)).
  - exact (proj1 (triangle_num_filter_twin_sound o a b c)).
Qed.

Lemma tcf_certain_sign : forall s x, certifies s x -> is_certain s = true -> sign_to_Z s = sign_of x.
Proof. intros s x C I. apply certified_sign; [exact C|]. intros E. subst s. discriminate I. Qed.

(** ** The signs part *)

(** Stage 3's sign: the integer sign, else the expansion's; a certain one is the exact sign. *)
Lemma tc_stage3_sign_sound : forall o d a b c v, is_certain (tc_stage3_sign_b o d a b c v) = true ->
  sign_to_Z (tc_stage3_sign_b o d a b c v) = sign_of (value_model o d a b c v).
Proof.
  intros o d a b c v. unfold tc_stage3_sign_b. cbv zeta.
  destruct (is_certain (integer_value_sign_b o d a b c v)) eqn:Ci.
  - intros _. exact (integer_value_sign_sound o d a b c v Ci).
  - intros C3. exact (tcf_certain_sign _ _ (triangle_expansion_sign_sound o d a b c v) C3).
Qed.

(** Stage 3's value for the roundings: finite doubles summing exactly to determinant v. *)
Lemma tc_stage3_components_sound : forall o d a b c v l, tc_stage3_components_b o d a b c v = Some l ->
  all_fin l /\ sumR l = value_model o d a b c v.
Proof.
  intros o d a b c v l. unfold tc_stage3_components_b.
  destruct (integer_value_components_b o d a b c v) as [l'|] eqn:I.
  - intros H. injection H as <-. destruct (integer_value_components_sound o d a b c v l' I) as [F [_ S]].
    split; assumption.
  - cbv zeta. destruct (eexact (value_ev o d a b c v)) eqn:X; [|discriminate].
    intros H. injection H as <-. exact (value_ev_exact o d a b c v X).
Qed.

Theorem tc_sign_b_correct : forall o d a b c v f, tc_index v ->
  tf_exact (snd (tc_sign_b o d a b c v f)) = false ->
  fst (tc_sign_b o d a b c v f) = sign_of (value_model o d a b c v).
Proof.
  intros o d a b c v f I. unfold tc_sign_b.
  destruct (Z.eqb_spec (tc_filter_b o d a b c v) uncertain_lane) as [U|U]; cbn [negb].
  - destruct (is_certain (PlaneCascadeTwins.enclosure_sign_b (tc_enclosure2_b o d a b c v))) eqn:C2.
    + intros _. cbn [fst]. exact (tcf_certain_sign _ _ (tc_enclosure2_sign_sound o d a b c v I) C2).
    + destruct (is_certain (tc_stage3_sign_b o d a b c v)) eqn:C3.
      * intros _. cbn [fst]. exact (tc_stage3_sign_sound o d a b c v C3).
      * cbn. discriminate.
  - intros _. cbn [fst].
    exact (proj1 (lane_sign_exact _ _ (det3_filter_lanes_b_range _ _ _) U (tc_filter_sound o d a b c v I))).
Qed.

(** [needs_exact_] is never reset. *)
Lemma tc_sign_b_exact_mono : forall o d a b c v f, tf_exact f = true -> tf_exact (snd (tc_sign_b o d a b c v f)) = true.
Proof.
  intros o d a b c v f E. unfold tc_sign_b.
  destruct (negb _); [exact E|]. destruct (is_certain _); [cbn [snd tf_reach tf_exact]; exact E|].
  destruct (is_certain _); cbn [snd tf_reach tf_exact tf_give_up]; [exact E | reflexivity].
Qed.

(** ** The tie-break and normal parts *)

Lemma tcf_ev_sign_certain : forall e V n, ev_ok e V n -> (Z.of_nat n <= 1048576)%Z -> is_certain (ev_sign e) = true ->
  sign_to_Z (ev_sign e) = sign_of V.
Proof.
  intros e V n [L Ex] Ln C. unfold ev_sign in *. destruct (eexact e) eqn:X; [|discriminate C].
  destruct (Ex eq_refl) as [F S]. rewrite <- S. apply tcf_certain_sign; [|exact C].
  apply expansion_sign_sound; [exact F | lia].
Qed.

Lemma tcf_e3_signs : forall x V n, e3_ok x V n -> (Z.of_nat n <= 1048576)%Z ->
  (is_certain (ev_sign (e0 x)) && is_certain (ev_sign (e1 x)) && is_certain (ev_sign (e2 x)))%bool = true ->
  sign_to_Z (ev_sign (e0 x)) = sign_of (vx V) /\ sign_to_Z (ev_sign (e1 x)) = sign_of (vy V) /\
  sign_to_Z (ev_sign (e2 x)) = sign_of (vz V).
Proof.
  intros x V n [O0 [O1 O2]] Ln C. apply andb_prop in C. destruct C as [C C2]. apply andb_prop in C.
  destruct C as [C0 C1].
  split; [|split]; eapply tcf_ev_sign_certain; eassumption.
Qed.

(** The edge p → q of π k (0: b → c, 1: c → a, 2: a → b), as [tie_break(k)] takes it. *)
Definition tc_edge_p (a b c : TVec) (k : Z) : TVec := if Z.eqb k 0 then b else if Z.eqb k 1 then c else a.
Definition tc_edge_q (a b c : TVec) (k : Z) : TVec := if Z.eqb k 0 then c else if Z.eqb k 1 then a else b.

Lemma tc_tie_vector_ok : forall d a b c k,
  e3_ok (tc_tie_vector d a b c k)
        (tie_break (tvec_R d) (tvec_R (tc_edge_p a b c k)) (tvec_R (tc_edge_q a b c k))) 16.
Proof.
  intros. unfold tc_tie_vector, tie_break, tc_edge_p, tc_edge_q. cbv zeta.
  apply ev_cross_ok; [apply lift3_ok | apply diff3_ok].
Qed.

(** [tie_break(k)] without [needs_exact_]: the exact signs of the components of d × (q − p). *)
Theorem tc_tie_break_b_correct : forall d a b c k f,
  tf_exact (snd (tc_tie_break_b d a b c k f)) = false ->
  let T := tie_break (tvec_R d) (tvec_R (tc_edge_p a b c k)) (tvec_R (tc_edge_q a b c k)) in
  fst (tc_tie_break_b d a b c k f) = (sign_of (vx T), sign_of (vy T), sign_of (vz T)).
Proof.
  intros d a b c k f. unfold tc_tie_break_b. cbv zeta.
  destruct (is_certain (ev_sign (e0 (tc_tie_vector d a b c k))) &&
            is_certain (ev_sign (e1 (tc_tie_vector d a b c k))) &&
            is_certain (ev_sign (e2 (tc_tie_vector d a b c k))))%bool eqn:C; [|cbn; discriminate].
  intros _. cbn [fst]. destruct (tcf_e3_signs _ _ _ (tc_tie_vector_ok d a b c k) ltac:(lia) C) as [E0 [E1 E2]].
  rewrite E0, E1, E2. reflexivity.
Qed.

Lemma tc_tie_break_b_exact_mono : forall d a b c k f, tf_exact f = true ->
  tf_exact (snd (tc_tie_break_b d a b c k f)) = true.
Proof.
  intros d a b c k f E. unfold tc_tie_break_b. cbv zeta.
  destruct (_ && _ && _)%bool; cbn [snd tf_reach tf_exact tf_give_up]; [exact E | reflexivity].
Qed.

Lemma tcf_vec_zero : forall v : vec3, (sign_of (vx v) = 0%Z /\ sign_of (vy v) = 0%Z /\ sign_of (vz v) = 0%Z) <->
  v = Vec3 0 0 0.
Proof.
  intros [x y z]. cbn [vx vy vz]. rewrite !sign_of_zero_iff. split.
  - intros [-> [-> ->]]. reflexivity.
  - intros E. injection E. intros -> -> ->. auto.
Qed.

(** [normal_is_zero()] without [needs_exact_]: whether N = (b − a) × (c − a) is the zero vector. *)
Theorem tc_normal_b_correct : forall a b c f,
  tf_exact (snd (tc_normal_b a b c f)) = false ->
  (fst (tc_normal_b a b c f) = true <-> normal_is_zero (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros a b c f. unfold tc_normal_b. cbv zeta.
  destruct (is_certain (ev_sign (e0 (tc_normal_vector a b c))) &&
            is_certain (ev_sign (e1 (tc_normal_vector a b c))) &&
            is_certain (ev_sign (e2 (tc_normal_vector a b c))))%bool eqn:C; [|cbn; discriminate].
  intros _. cbn [fst].
  assert (Ok : e3_ok (tc_normal_vector a b c) (cross (sub (tvec_R b) (tvec_R a)) (sub (tvec_R c) (tvec_R a))) 16)
    by (unfold tc_normal_vector; apply ev_cross_ok; apply diff3_ok).
  destruct (tcf_e3_signs _ _ _ Ok ltac:(lia) C) as [E0 [E1 E2]]. rewrite E0, E1, E2.
  unfold normal_is_zero. rewrite <- tcf_vec_zero.
  rewrite !andb_true_iff, !Z.eqb_eq. tauto.
Qed.

Lemma tc_normal_b_exact_mono : forall a b c f, tf_exact f = true -> tf_exact (snd (tc_normal_b a b c f)) = true.
Proof.
  intros a b c f E. unfold tc_normal_b. cbv zeta.
  destruct (_ && _ && _)%bool; cbn [snd tf_reach tf_exact tf_give_up]; [exact E | reflexivity].
Qed.

(** ** The classification *)

Lemma tcf_before : forall (g : TFlow -> TFlow) f, (tf_exact f = true -> tf_exact (g f) = true) ->
  tf_exact (g f) = false -> tf_exact f = false.
Proof. intros g f M E. destruct (tf_exact f) eqn:X; [rewrite (M eq_refl) in E; discriminate | reflexivity]. Qed.

Lemma tc_owned_step_mono : forall d a b c sden k sk st, tf_exact (snd st) = true ->
  tf_exact (snd (tc_owned_step d a b c sden k sk st)) = true.
Proof.
  intros d a b c sden k sk [owned f] E. unfold tc_owned_step. cbn [snd] in E.
  destruct (owned && Z.eqb sk 0)%bool; [|exact E].
  pose proof (tc_tie_break_b_exact_mono d a b c k f E) as M.
  destruct (tc_tie_break_b d a b c k f) as [[[tx ty] tz] f'] eqn:T. exact M.
Qed.

Lemma tcf_sign_pm : forall s, sign3 s -> s <> 0%Z -> s = (-1)%Z \/ s = 1%Z.
Proof. intros s [H|[H|H]] N; [left | contradiction | right]; assumption. Qed.

(** One step of the loop: with p → q the edge of π k, sk its exact sign (not −sden while owned). *)
Lemma tc_owned_step_correct : forall d a b c o sden k owned f,
  sign3 sden -> sden <> 0%Z ->
  let P := tvec_R (tc_edge_p a b c k) in let Q := tvec_R (tc_edge_q a b c k) in
  let sk := sign_of (edge_value (tvec_R o) (tvec_R d) P Q) in
  (owned = true -> sk <> (- sden)%Z) ->
  tf_exact (snd (tc_owned_step d a b c sden k sk (owned, f))) = false ->
  fst (tc_owned_step d a b c sden k sk (owned, f)) =
  (owned && Z.eqb (owned_sign_of (tvec_R o) (tvec_R d) P Q) sden)%bool.
Proof.
  intros d a b c o sden k owned f S3 Nd P Q sk Opp. unfold tc_owned_step.
  destruct owned; [|cbn; reflexivity]. cbn [andb].
  unfold owned_sign_of. cbv zeta. fold sk.
  destruct (Z.eqb_spec sk 0) as [Z0|Z0].
  - destruct (tc_tie_break_b d a b c k f) as [[[tx ty] tz] f'] eqn:T. intros X. cbn [fst snd] in X |- *.
    pose proof (tc_tie_break_b_correct d a b c k f) as C. rewrite T in C. cbn [fst snd] in C.
    specialize (C X). injection C. intros -> -> ->. rewrite Z0. reflexivity.
  - intros _. cbn [fst]. unfold owned_sign. rewrite (proj2 (Z.eqb_neq sk 0) Z0). cbn [negb].
    symmetry. apply Z.eqb_eq.
    pose proof (Opp eq_refl) as H. destruct (tcf_sign_pm sk (sign3_of _) Z0) as [E|E];
      destruct (tcf_sign_pm sden S3 Nd) as [E'|E']; rewrite E, E' in *; cbn in H |- *; congruence.
Qed.

Lemma tcf_not_outside : forall sa sb sc sden, triangle_location sa sb sc sden <> Outside ->
  sa <> (- sden)%Z /\ sb <> (- sden)%Z /\ sc <> (- sden)%Z.
Proof.
  intros sa sb sc sden L. unfold triangle_location in L.
  destruct (Z.eqb_spec sa (- sden)); [cbn in L; contradiction|].
  destruct (Z.eqb_spec sb (- sden)); [cbn in L; contradiction|].
  destruct (Z.eqb_spec sc (- sden)); [cbn in L; contradiction|]. auto.
Qed.

Lemma value_model_0 : forall o d a b c, value_model o d a b c 0 = edge_value (tvec_R o) (tvec_R d) (tvec_R b) (tvec_R c).
Proof. reflexivity. Qed.
Lemma value_model_1 : forall o d a b c, value_model o d a b c 1 = edge_value (tvec_R o) (tvec_R d) (tvec_R c) (tvec_R a).
Proof. reflexivity. Qed.
Lemma value_model_2 : forall o d a b c, value_model o d a b c 2 = edge_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b).
Proof. reflexivity. Qed.
Lemma value_model_3 : forall o d a b c, value_model o d a b c 3 = den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c).
Proof. reflexivity. Qed.
Lemma value_model_4 : forall o d a b c, value_model o d a b c 4 = num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c).
Proof. reflexivity. Qed.

(** A sign call that leaves the state not exact gives the exact sign, and the state before was not exact. *)
Lemma tcf_sign_step : forall o d a b c v f s f', tc_index v -> tc_sign_b o d a b c v f = (s, f') ->
  tf_exact f' = false -> s = sign_of (value_model o d a b c v) /\ tf_exact f = false.
Proof.
  intros o d a b c v f s f' I E X. pose proof (tc_sign_b_correct o d a b c v f I) as C.
  pose proof (tc_sign_b_exact_mono o d a b c v f) as M. rewrite E in C, M. cbn [fst snd] in C, M.
  split; [exact (C X)|]. destruct (tf_exact f); [rewrite (M eq_refl) in X; discriminate | reflexivity].
Qed.

(** [classify] (no [needs_exact_]): §6's classification of the exact values under the rule. *)
Theorem tc_classify_b_correct : forall o d a b c owned_rule,
  tf_exact (snd (tc_classify_b o d a b c owned_rule)) = false ->
  contract_class owned_rule (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)
                 (fst (tc_classify_b o d a b c owned_rule)).
Proof.
  intros o d a b c rule. unfold tc_classify_b.
  destruct (tc_sign_b o d a b c 3 tf_start) as [sden f1] eqn:S3.
  unfold contract_class. cbv zeta.
  destruct (Z.eqb_spec sden 0) as [Z0|Z0].
  - destruct (tc_normal_b a b c f1) as [z f2] eqn:N.
    pose proof (tc_normal_b_correct a b c f1) as NC. pose proof (tc_normal_b_exact_mono a b c f1) as NM.
    rewrite N in NC, NM. cbn [fst snd] in NC, NM.
    destruct z.
    + intros X. cbn [fst snd] in X |- *.
      destruct (tcf_sign_step _ _ _ _ _ 3 _ _ _ ltac:(unfold tc_index; lia) S3 (tcf_before (fun _ => f2) f1 NM X))
        as [Ed _].
      rewrite value_model_3 in Ed. rewrite <- Ed, Z0. cbn [Z.eqb tloc towned trel].
      split; [reflexivity | split; [reflexivity|]]. left. split; [apply (proj1 (NC X)); reflexivity | reflexivity].
    + destruct (tc_sign_b o d a b c 4 f2) as [sn f3] eqn:S4. intros X. cbn [fst snd] in X |- *.
      destruct (tcf_sign_step _ _ _ _ _ 4 _ _ _ ltac:(unfold tc_index; lia) S4 X) as [En X2].
      destruct (tcf_sign_step _ _ _ _ _ 3 _ _ _ ltac:(unfold tc_index; lia) S3 (tcf_before (fun _ => f2) f1 NM X2))
        as [Ed _].
      rewrite value_model_3 in Ed. rewrite value_model_4 in En. rewrite <- Ed, <- En, Z0.
      cbn [Z.eqb tloc towned trel].
      assert (NZ : ~ normal_is_zero (tvec_R a) (tvec_R b) (tvec_R c)) by (intros H; pose proof (proj2 (NC X2) H) as F; discriminate F).
      split; [reflexivity | split; [reflexivity|]]. right.
      destruct (Z.eqb_spec sn 0) as [E0|E0]; [left | right]; auto.
  - destruct (tc_sign_b o d a b c 0 f1) as [sa f2] eqn:Sa.
    destruct (tc_sign_b o d a b c 1 f2) as [sb f3] eqn:Sb.
    destruct (tc_sign_b o d a b c 2 f3) as [sc f4] eqn:Sc.
    set (loc := triangle_location sa sb sc sden).
    set (st0 := (negb (is_outside (Some loc)), f4)).
    set (st1 := tc_owned_step d a b c sden 0 sa st0).
    set (st2 := tc_owned_step d a b c sden 1 sb st1).
    destruct (tc_owned_step d a b c sden 2 sc st2) as [owned f7] eqn:O3.
    (* the state after the loop is not exact whenever the final one is not *)
    assert (Fin : tf_exact f7 = false -> tf_exact f4 = false /\ tf_exact (snd st1) = false /\
                                        tf_exact (snd st2) = false).
    { intros X7.
      assert (X2 : tf_exact (snd st2) = false).
      { destruct (tf_exact (snd st2)) eqn:E; [|reflexivity].
        pose proof (tc_owned_step_mono d a b c sden 2 sc st2 E) as M. rewrite O3 in M. cbn in M. congruence. }
      assert (X1 : tf_exact (snd st1) = false).
      { destruct (tf_exact (snd st1)) eqn:E; [|reflexivity].
        pose proof (tc_owned_step_mono d a b c sden 1 sb st1 E) as M. fold st2 in M. congruence. }
      split; [|split; assumption].
      destruct (tf_exact f4) eqn:E; [|reflexivity].
      pose proof (tc_owned_step_mono d a b c sden 0 sa st0 E) as M. fold st1 in M. congruence. }
    assert (Signs : tf_exact f4 = false ->
                    sa = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R b) (tvec_R c)) /\
                    sb = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R c) (tvec_R a)) /\
                    sc = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b)) /\
                    sden = sign_of (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c))).
    { intros X4.
      destruct (tcf_sign_step _ _ _ _ _ 2 _ _ _ ltac:(unfold tc_index; lia) Sc X4) as [Ec X3].
      destruct (tcf_sign_step _ _ _ _ _ 1 _ _ _ ltac:(unfold tc_index; lia) Sb X3) as [Eb X2].
      destruct (tcf_sign_step _ _ _ _ _ 0 _ _ _ ltac:(unfold tc_index; lia) Sa X2) as [Ea X1].
      destruct (tcf_sign_step _ _ _ _ _ 3 _ _ _ ltac:(unfold tc_index; lia) S3 X1) as [Ed _].
      rewrite value_model_0 in Ea. rewrite value_model_1 in Eb. rewrite value_model_2 in Ec.
      rewrite value_model_3 in Ed. auto. }
    (* the owned flag *)
    assert (Owned : tf_exact f7 = false -> sden <> 0%Z -> sign3 sden ->
              sa = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R b) (tvec_R c)) ->
              sb = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R c) (tvec_R a)) ->
              sc = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b)) ->
              owned = (negb (is_outside (Some loc)) &&
                       Z.eqb (owned_sign_of (tvec_R o) (tvec_R d) (tvec_R b) (tvec_R c)) sden &&
                       Z.eqb (owned_sign_of (tvec_R o) (tvec_R d) (tvec_R c) (tvec_R a)) sden &&
                       Z.eqb (owned_sign_of (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b)) sden)%bool).
    { intros X7 N S Ea Eb Ec. destruct (Fin X7) as [X4 [X1 X2]].
      assert (Opp : negb (is_outside (Some loc)) = true -> sa <> (- sden)%Z /\ sb <> (- sden)%Z /\ sc <> (- sden)%Z).
      { intros H. apply tcf_not_outside. fold loc. intros E. rewrite E in H. discriminate H. }
      destruct st1 as [o1 g1] eqn:E1. destruct st2 as [o2 g2] eqn:E2.
      pose proof (tc_owned_step_correct d a b c o sden 0 (negb (is_outside (Some loc))) f4 S N) as C0.
      pose proof (tc_owned_step_correct d a b c o sden 1 o1 g1 S N) as C1.
      pose proof (tc_owned_step_correct d a b c o sden 2 o2 g2 S N) as C2.
      cbv zeta in C0, C1, C2. cbn [tc_edge_p tc_edge_q Z.eqb Pos.eqb] in C0, C1, C2.
      rewrite <- Ea in C0. rewrite <- Eb in C1. rewrite <- Ec in C2.
      unfold st1, st0 in E1. rewrite E1 in C0. cbn [fst snd] in C0.
      unfold st2 in E2. rewrite E2 in C1. cbn [fst snd] in C1.
      rewrite O3 in C2. cbn [fst snd] in C2.
      cbn [snd] in X1, X2.
      assert (H0 : o1 = (negb (is_outside (Some loc)) &&
                         Z.eqb (owned_sign_of (tvec_R o) (tvec_R d) (tvec_R b) (tvec_R c)) sden)%bool)
        by (apply C0; [intros H; exact (proj1 (Opp H)) | exact X1]).
      assert (H1 : o2 = (o1 && Z.eqb (owned_sign_of (tvec_R o) (tvec_R d) (tvec_R c) (tvec_R a)) sden)%bool).
      { apply C1; [|exact X2]. intros H. rewrite H0 in H. apply andb_prop in H. exact (proj1 (proj2 (Opp (proj1 H)))). }
      assert (H2 : owned = (o2 && Z.eqb (owned_sign_of (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b)) sden)%bool).
      { apply C2; [|exact X7]. intros H. rewrite H1, H0 in H. apply andb_prop in H. destruct H as [H _].
        apply andb_prop in H. destruct H as [H _]. exact (proj2 (proj2 (Opp H))). }
      rewrite H2, H1, H0. reflexivity. }
    destruct (if rule then owned else negb (is_outside (Some loc))) eqn:Through.
    + destruct (tc_sign_b o d a b c 4 f7) as [sn f8] eqn:S4. intros X. cbn [fst snd] in X |- *.
      destruct (tcf_sign_step _ _ _ _ _ 4 _ _ _ ltac:(unfold tc_index; lia) S4 X) as [En X7].
      rewrite value_model_4 in En.
      destruct (Fin X7) as [X4 _]. destruct (Signs X4) as [Ea [Eb [Ec Ed]]].
      pose proof (Owned X7 Z0 ltac:(rewrite Ed; apply sign3_of) Ea Eb Ec) as Ow.
      rewrite <- Ea, <- Eb, <- Ec, <- Ed, <- En. rewrite (proj2 (Z.eqb_neq sden 0) Z0).
      fold loc. unfold is_outside in Ow, Through. rewrite <- Ow. cbn [tloc towned trel].
      split; [reflexivity | split; [reflexivity|]]. rewrite Through. reflexivity.
    + intros X. cbn [fst snd] in X |- *.
      destruct (Fin X) as [X4 _]. destruct (Signs X4) as [Ea [Eb [Ec Ed]]].
      pose proof (Owned X Z0 ltac:(rewrite Ed; apply sign3_of) Ea Eb Ec) as Ow.
      rewrite <- Ea, <- Eb, <- Ec, <- Ed. rewrite (proj2 (Z.eqb_neq sden 0) Z0).
      fold loc. unfold is_outside in Ow, Through. rewrite <- Ow. cbn [tloc towned trel].
      split; [reflexivity | split; [reflexivity|]]. rewrite Through. reflexivity.
Qed.

(** ** The cascade's answers before the exact stage *)

(** [triangle_relation_cascade]: an answer before the exact stage is §6's under the rule. *)
Theorem tc_relation_b_correct : forall owned_rule o d a b c cl rs t ua ub uc ts,
  tc_relation_b owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  contract_class owned_rule (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) cl.
Proof.
  intros rule o d a b c cl rs t ua ub uc ts. unfold tc_relation_b.
  pose proof (tc_classify_b_correct o d a b c rule) as C.
  destruct (tc_classify_b o d a b c rule) as [cl' f] eqn:E. cbn [fst snd] in C.
  destruct (tf_exact f) eqn:X; [discriminate|]. intros H. injection H. intros _ _ _ _ _ _ <-. exact (C eq_refl).
Qed.

(** [triangle_intersection_cascade]: the classification of an answer before the exact stage is §6's. *)
(** The class an answer of [tc_intersect_b] carries: every [TCDecided] is built with the classification's [cl].
    Walked once over the definition's tree ([answer_class_if], [answer_class_pair]), not case by case. *)
Definition answer_class_is (x : tc_answer) (cl : TClass) : Prop :=
  match x with TCDecided c _ _ _ _ _ _ => c = cl | TCExact => True end.
Lemma answer_class_if : forall (b : bool) x y cl,
  answer_class_is x cl -> answer_class_is y cl -> answer_class_is (if b then x else y) cl.
Proof. intros [|] x y cl X Y; assumption. Qed.
Lemma answer_class_pair : forall {A B : Type} (p : A * B) (k : A -> B -> tc_answer) cl,
  (forall a b, answer_class_is (k a b) cl) -> answer_class_is (let '(a, b) := p in k a b) cl.
Proof. intros A B [a b] k cl K. apply K. Qed.

Theorem tc_intersect_b_class_correct : forall want_t want_u owned_rule o d a b c cl rs t ua ub uc ts,
  tc_intersect_b want_t want_u owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  contract_class owned_rule (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) cl.
Proof.
  intros wt wu rule o d a b c cl rs t ua ub uc ts H.
  pose proof (tc_classify_b_correct o d a b c rule) as C.
  assert (A : answer_class_is (tc_intersect_b wt wu rule o d a b c) (fst (tc_classify_b o d a b c rule))).
  { unfold tc_intersect_b. destruct (tc_classify_b o d a b c rule) as [cl' f]. cbn [fst].
    cbv zeta.
    repeat match goal with
    | |- answer_class_is (if _ then _ else _) _ => apply answer_class_if
    | |- answer_class_is (let '(_, _) := _ in _) _ => apply answer_class_pair; intros ? ?
    | |- answer_class_is (TCDecided _ _ _ _ _ _ _) _ => reflexivity
    | |- answer_class_is TCExact _ => exact I
    end. }
  rewrite H in A. cbn [answer_class_is] in A. subst cl.
  destruct (tc_classify_b o d a b c rule) as [cl' f] eqn:E. cbn [fst snd] in C |- *.
  apply C. revert H. unfold tc_intersect_b. rewrite E. destruct (tf_exact f); [discriminate | reflexivity].
Qed.

(** ** The quotients' parts that are proved: a zero numerator, and stage 3 *)

(** An exactly zero numerator gives +0, which is RN(0/den). *)
Lemma tc_zero_quotient_correct : forall x y, sign_of x = 0%Z -> B2R fzero = RN (x / y).
Proof.
  intros x y Z0. apply sign_of_zero_iff in Z0. subst x. unfold Rdiv. rewrite Rmult_0_l, RN_0. reflexivity.
Qed.

Lemma tc_enclosure2_nonneg : forall o d a b c v, nonneg (radiusb (tc_enclosure2_b o d a b c v)).
Proof.
  intros o d a b c v. destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [NK [_ NKd]]]]]]]]]]]]].
  unfold tc_enclosure2_b. apply det3_enclosure_nonneg; [| apply tcf_value2_nonneg |].
  - unfold tc_compensated_relative. destruct (Z.eqb v 3); assumption.
  - unfold tc_absolute2_b. destruct (Z.eqb v 4); apply absolute_bv_nonneg.
Qed.

(** [expansion_enclosure(v)]: when it exists, it encloses the model's value. *)
Lemma tc_expansion_enclosure_ok : forall o d a b c v e, tc_expansion_enclosure_b o d a b c v = Some e ->
  nonneg (radiusb e) /\
  (fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true -> encloses (enc_R e) (value_model o d a b c v)).
Proof.
  intros o d a b c v e. unfold tc_expansion_enclosure_b.
  destruct (tc_stage3_components_b o d a b c v) as [l|] eqn:C3; [|discriminate].
  destruct (Z.leb (Z.of_nat (length l)) Cpp.tail_sum_max_terms) eqn:L; [|discriminate].
  intros H. injection H. intros <-. apply Z.leb_le in L.
  unfold Cpp.tail_sum_max_terms in L.
  destruct (tc_stage3_components_sound o d a b c v l C3) as [F S].
  split; [apply PlaneCascadeTwins.tail_b_nonneg|]. intros Fh Fl Fr.
  rewrite <- S. apply PlaneCascadeTwins.tail_b_encloses; [lia | assumption ..].
Qed.

(** Stage 3's rounding of quotient v (t: v = 4; u_k: v = k) over den's divisor (its tail enclosure, or stage
    2's enclosure when den's expansion is not usable): when certain, den ≠ 0 and the value is RN(value/den). *)
Theorem tc_stage3_quotient_correct : forall o d a b c v n,
  tc_expansion_enclosure_b o d a b c v = Some n ->
  let dd := match tc_expansion_enclosure_b o d a b c 3 with Some e => e | None => tc_enclosure2_b o d a b c 3 end in
  snd (round_quotient_b n (prepare_divisor_b dd)) = true ->
  den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) <> 0 /\
  fin (fst (round_quotient_b n (prepare_divisor_b dd))) = true /\
  B2R (fst (round_quotient_b n (prepare_divisor_b dd))) =
    RN (value_model o d a b c v / den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c v n En dd C. rewrite <- value_model_3.
  destruct (tc_expansion_enclosure_ok o d a b c v n En) as [Nn Encn].
  assert (Dd : nonneg (radiusb dd) /\
               (fin (hib dd) = true -> fin (lob dd) = true -> fin (radiusb dd) = true ->
                encloses (enc_R dd) (value_model o d a b c 3))).
  { unfold dd. destruct (tc_expansion_enclosure_b o d a b c 3) as [e|] eqn:Ed.
    - exact (tc_expansion_enclosure_ok o d a b c 3 e Ed).
    - split; [apply tc_enclosure2_nonneg|]. intros _ _ F.
      apply tc_enclosure2_encloses; [unfold tc_index; lia | exact F]. }
  destruct Dd as [Nd Encd].
  exact (round_quotient_twin_sound n dd _ _ Nn Nd Encn Encd C).
Qed.
