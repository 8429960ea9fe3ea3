(** * The ray–triangle cascade's whole answer before the exact stage: classification and quotients
    (TriangleCascadeFlowTwins.v's [tc_intersect_b], the twin of [triangle_intersection_cascade] in
    kernel/src/triangle/ray_triangle_cascade.cpp, tied to the compiled code bit for bit by the runner's
    routine [tri_cascade_intersect]).

    - [tc_stage2_quotient_correct]: stage 2's [round_quotients] over the broadcast divisor
      ([shared_divisor_b] of den's stage-2 enclosure), when certain, is RN(value/den)
      (TriangleIntersectTheorem.v's [round_quotient_shared_sound] on TriangleCascadeFlowCorrect.v's
      enclosure theorems);
    - [tc_quot_tail]: [tc_intersect_b] past its numerators' signs, over names for the quotients' starts, the
      stage-2 roundings and the stage-3 ones; [tc_intersect_b_eq] (an equation of definitions) says the twin
      is that tail; [tc_quot_tail_correct]: every quotient the tail answers with a value has the value its
      rounding certified (the [qstep]/[qstep3] chain keeps the invariant [tc_qinv]);
    - [tc_intersect_b_correct]: for every 64-bit pattern of o, d, a, b, c, every option set and both rules,
      an answer of [tc_intersect_b] before the exact stage has docs/contract.md §6's classification under the
      rule ([tc_intersect_b_class_correct]), and each of t, u_a, u_b, u_c that has a value (asked, and not left
      to the exact stage) is finite and RN(num/den), RN(πa/den), RN(πb/den), RN(πc/den) with
      πa = π(b, c), πb = π(c, a), πc = π(a, b) — the quotient part of TriangleIntersectTheorem.v's
      [intersection_means] for the fast path (which also has den ≠ 0 and finite inputs: the cascade's twin
      is stated for every bit pattern, its callers pass valid inputs only);
    - [tc_intersect_b_unasked]: a quotient not asked is NaN in every answer. *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification PlaneCascade FloatCore ConstantsCpp PlaneTwins Expansions PlaneQueryTwins
  TriangleFilter TriangleRule TriangleTwins TriangleStage3Twins TriangleCascadeTwins TriangleIntersectTwins
  TriangleCascadeFlowTwins QuotientBoundary.
From Raykernel Require TriangleCascadeFlowCorrect TriangleIntersectTheorem.
From Raykernel Require PlaneCascadeTwins.
Open Scope R_scope.

Module F := TriangleCascadeFlowCorrect.

(** What a quotient of the answer means: a value is finite and RN(V/VD). *)
Definition tc_quotient_means (q : qval) (V VD : R) : Prop :=
  forall x, q = QVal x -> fin x = true /\ B2R x = RN (V / VD).

(** ** Stage 2: [round_quotients] over the broadcast divisor *)

Theorem tc_stage2_quotient_correct : forall o d a b c v, F.tc_index v ->
  snd (round_quotient_b (tc_enclosure2_b o d a b c v) (shared_divisor_b (tc_enclosure2_b o d a b c 3))) = true ->
  fin (fst (round_quotient_b (tc_enclosure2_b o d a b c v) (shared_divisor_b (tc_enclosure2_b o d a b c 3)))) = true /\
  B2R (fst (round_quotient_b (tc_enclosure2_b o d a b c v) (shared_divisor_b (tc_enclosure2_b o d a b c 3)))) =
    RN (value_model o d a b c v / value_model o d a b c 3).
Proof.
  intros o d a b c v I C.
  destruct (TriangleIntersectTheorem.round_quotient_shared_sound _ _ (value_model o d a b c v) (value_model o d a b c 3)
              (F.tc_enclosure2_nonneg o d a b c v) (F.tc_enclosure2_nonneg o d a b c 3)
              (fun _ _ Fr => F.tc_enclosure2_encloses o d a b c v I Fr)
              (fun _ _ Fr => F.tc_enclosure2_encloses o d a b c 3 ltac:(unfold F.tc_index; lia) Fr) C)
    as [_ R].
  exact R.
Qed.

(** ** The quotients' chain, over names *)

Definition tc_all (x0 x1 x2 x3 : bool * qval) : bool := (fst x0 && fst x1 && fst x2 && fst x3)%bool.
Definition tc_start (w : bool) (n : Z) : bool * qval := (negb w || Z.eqb n 0, if w then QVal fzero else QNaN)%bool.
Definition tc_qs3 (x : bool * qval) (r : option (float * bool)) : bool * qval := if fst x then x else qstep3 x r.

Definition tc_quot_tail4 (cl : TClass) (rs ts : stage) (x0 x1 x2 x3 : bool * qval) : tc_answer :=
  if tc_all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts
  else TCDecided cl rs (qfinal x0) (qfinal x1) (qfinal x2) (qfinal x3) StExact.

Definition tc_quot_tail3 (cl : TClass) (rs ts : stage) (x0 x1 x2 x3 : bool * qval) (ds : Z)
  (dn b0 b1 b2 b3 : option (list float)) : tc_answer :=
  if tc_all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts
  else tc_quot_tail4 cl rs ts (qstep_boundary x0 ds dn b0) (qstep_boundary x1 ds dn b1)
                     (qstep_boundary x2 ds dn b2) (qstep_boundary x3 ds dn b3).

Definition tc_quot_tail2 (cl : TClass) (rs ts : stage) (x0 x1 x2 x3 : bool * qval)
  (p0 p1 p2 p3 : option (float * bool)) (ds : Z) (dn b0 b1 b2 b3 : option (list float)) : tc_answer :=
  if tc_all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts
  else tc_quot_tail3 cl rs (later ts StExpansion) (tc_qs3 x0 p0) (tc_qs3 x1 p1) (tc_qs3 x2 p2) (tc_qs3 x3 p3)
                     ds dn b0 b1 b2 b3.

Definition tc_quot_tail (cl : TClass) (rs ts : stage) (x0 x1 x2 x3 : bool * qval) (q0 q1 q2 q3 : float * bool)
  (p0 p1 p2 p3 : option (float * bool)) (ds : Z) (dn b0 b1 b2 b3 : option (list float)) : tc_answer :=
  if tc_all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts
  else tc_quot_tail2 cl rs (later ts StCompensated) (qstep x0 q0) (qstep x1 q1) (qstep x2 q2) (qstep x3 q3)
                     p0 p1 p2 p3 ds dn b0 b1 b2 b3.

(** Stage 3's rounding of quotient v, as [tc_intersect_b]'s [r3] forms it. *)
Definition tc_r3 (o d a b c : TVec) (v : Z) : option (float * bool) :=
  let dd := match tc_expansion_enclosure_b o d a b c 3 with Some e => e | None => tc_enclosure2_b o d a b c 3 end in
  match tc_expansion_enclosure_b o d a b c v with
  | Some n => Some (round_quotient_b n (prepare_divisor_b dd)) | None => None end.

Definition tc_q2 (o d a b c : TVec) (v : Z) : float * bool :=
  round_quotient_b (tc_enclosure2_b o d a b c v) (shared_divisor_b (tc_enclosure2_b o d a b c 3)).

(** [tc_intersect_b] with its quotients' chain named (an equation of definitions; the roundings and signs
    kept opaque to unification, so that it compares them by name instead of computing them). *)
Opaque round_quotient_b tc_enclosure2_b tc_sign_b tc_classify_b tc_expansion_enclosure_b shared_divisor_b
  prepare_divisor_b tc_short_b value_ev ev_sign round_quotient_near_b tc_stage3_sign_b.
Lemma tc_intersect_b_eq : forall want_t want_u owned_rule o d a b c,
  tc_intersect_b want_t want_u owned_rule o d a b c =
  let '(cl, f) := tc_classify_b o d a b c owned_rule in
  if tf_exact f then TCExact else
  let rs := tf_stage f in
  if (match tloc cl with None => true | Some _ => false end || (negb want_t && negb want_u))%bool
  then TCDecided cl rs QNaN QNaN QNaN QNaN rs else
  let '(n0, f) := if want_t then tc_sign_b o d a b c 4 f else (0%Z, f) in
  let '(n1, f) := if want_u then tc_sign_b o d a b c 0 f else (0%Z, f) in
  let '(n2, f) := if want_u then tc_sign_b o d a b c 1 f else (0%Z, f) in
  let '(n3, f) := if want_u then tc_sign_b o d a b c 2 f else (0%Z, f) in
  let exact_or_nan (w : bool) := if w then QExact else QNaN in
  if tf_exact f then
    TCDecided cl rs (exact_or_nan want_t) (exact_or_nan want_u) (exact_or_nan want_u) (exact_or_nan want_u) StExact
  else
  tc_quot_tail cl rs (tf_stage f) (tc_start want_t n0) (tc_start want_u n1) (tc_start want_u n2) (tc_start want_u n3)
    (tc_q2 o d a b c 4) (tc_q2 o d a b c 0) (tc_q2 o d a b c 1) (tc_q2 o d a b c 2)
    (tc_r3 o d a b c 4) (tc_r3 o d a b c 0) (tc_r3 o d a b c 1) (tc_r3 o d a b c 2)
    (sign_to_Z (tc_stage3_sign_b o d a b c 3)) (tc_short_b o d a b c 3)
    (tc_short_b o d a b c 4) (tc_short_b o d a b c 0) (tc_short_b o d a b c 1) (tc_short_b o d a b c 2).
Proof.
  intros. unfold tc_intersect_b, tc_quot_tail, tc_quot_tail2, tc_quot_tail3, tc_quot_tail4, tc_all, tc_start, tc_qs3,
    tc_q2, tc_r3.
  reflexivity.
Qed.

Transparent round_quotient_b tc_enclosure2_b tc_sign_b tc_classify_b tc_expansion_enclosure_b shared_divisor_b
  prepare_divisor_b tc_short_b value_ev ev_sign round_quotient_near_b tc_stage3_sign_b.

(** The invariant of a quotient's progress: once certain, a value is RN(V/VD). *)
Definition tc_qinv (x : bool * qval) (V VD : R) : Prop := fst x = true -> tc_quotient_means (snd x) V VD.

Lemma tc_qinv_qstep : forall x r V VD, tc_qinv x V VD ->
  (snd r = true -> fin (fst r) = true /\ B2R (fst r) = RN (V / VD)) -> tc_qinv (qstep x r) V VD.
Proof.
  intros [c q] [y s] V VD I R. unfold qstep, tc_qinv, tc_quotient_means in *. cbn [fst snd] in *.
  destruct c; [exact I|]. cbn [fst snd]. intros S x E. injection E as <-. exact (R S).
Qed.

Lemma tc_qinv_qs3 : forall x p V VD, tc_qinv x V VD ->
  (forall r, p = Some r -> snd r = true -> fin (fst r) = true /\ B2R (fst r) = RN (V / VD)) ->
  tc_qinv (tc_qs3 x p) V VD.
Proof.
  intros [c q] p V VD I R. unfold tc_qs3, qstep3, tc_qinv, tc_quotient_means in *. cbn [fst snd] in *.
  destruct c; [exact I|]. destruct p as [[y s]|]; [|exact I]. cbn [fst snd].
  intros S x E. injection E as <-. exact (R _ eq_refl S).
Qed.

(** The rounding boundaries: a value of [round_quotient_near] is RN(V/VD) when den's sign ds is
    VD's and the expansions sum to VD and V (at most 16 components each). *)
Lemma tc_qinv_boundary : forall x ds dn bn V VD, tc_qinv x V VD ->
  ((ds = 1%Z \/ ds = (-1)%Z) -> (ds = 1%Z /\ 0 < VD) \/ (ds = (-1)%Z /\ VD < 0)) ->
  (forall l, dn = Some l -> (length l <= 16)%nat /\ sumR l = VD) ->
  (forall l, bn = Some l -> (length l <= 16)%nat /\ sumR l = V) ->
  tc_qinv (qstep_boundary x ds dn bn) V VD.
Proof.
  intros [c q] ds dn bn V VD I S D B. unfold qstep_boundary, tc_qinv, tc_quotient_means in *. cbn [fst snd] in *.
  destruct c; [exact I|].
  destruct q as [| y |]; cbn [fst snd]; try (intros H; discriminate H).
  destruct dn as [ed|]; [|intros H; discriminate H].
  destruct bn as [en|]; [|intros H; discriminate H].
  destruct (Z.eqb ds 1 || Z.eqb ds (-1))%bool eqn:Ds; [|intros H; discriminate H].
  destruct (round_quotient_near_b en ed ds y) as [r|] eqn:R; [|intros H; discriminate H].
  intros _ x E. injection E as <-.
  destruct (D ed eq_refl) as [Ld Sd]. destruct (B en eq_refl) as [Ln Sn].
  assert (Dsc : (ds = 1%Z /\ 0 < sumR ed) \/ (ds = (-1)%Z /\ sumR ed < 0)).
  { rewrite Sd. apply S. apply orb_true_iff in Ds. destruct Ds as [Ds|Ds]; apply Z.eqb_eq in Ds; tauto. }
  destruct (round_quotient_near_sound en ed ds y r Ln Ld Dsc R) as [Fr Rr].
  split; [exact Fr|]. rewrite Rr, Sn, Sd. reflexivity.
Qed.

(** [tc_short_b v]: at most 16 components summing to determinant v. *)
Lemma tc_short_means : forall o d a b c v l, tc_short_b o d a b c v = Some l ->
  (length l <= 16)%nat /\ sumR l = value_model o d a b c v.
Proof.
  intros o d a b c v l. unfold tc_short_b.
  destruct (tc_stage3_components_b o d a b c v) as [l'|] eqn:C3; [|intros H; discriminate H].
  destruct (Nat.leb (length l') 16) eqn:L; [|intros H; discriminate H].
  intros H. injection H as <-. apply Nat.leb_le in L.
  split; [exact L | exact (proj2 (F.tc_stage3_components_sound o d a b c v l' C3))].
Qed.

(** den's checked sign in stage 3, when ±1, is den's sign. *)
Lemma tc_den_sign_means : forall o d a b c,
  let ds := sign_to_Z (tc_stage3_sign_b o d a b c 3) in
  (ds = 1%Z \/ ds = (-1)%Z) ->
  (ds = 1%Z /\ 0 < value_model o d a b c 3) \/ (ds = (-1)%Z /\ value_model o d a b c 3 < 0).
Proof.
  intros o d a b c ds H. unfold ds in *.
  assert (C : is_certain (tc_stage3_sign_b o d a b c 3) = true).
  { destruct (tc_stage3_sign_b o d a b c 3); cbn in H |- *; try reflexivity. destruct H as [H|H]; discriminate H. }
  pose proof (F.tc_stage3_sign_sound o d a b c 3 C) as S. rewrite S in H |- *. unfold sign_of in *.
  destruct (Rcompare_spec (value_model o d a b c 3) 0) as [L|E|G].
  - right. split; [reflexivity | exact L].
  - exfalso. destruct H as [H|H]; discriminate H.
  - left. split; [reflexivity | exact G].
Qed.

Lemma tc_qinv_final : forall x V VD, tc_qinv x V VD -> tc_quotient_means (qfinal x) V VD.
Proof.
  intros [c q] V VD I. unfold qfinal, tc_qinv in *. cbn [fst snd] in *.
  destruct c; [exact (I eq_refl)|]. intros x E. discriminate E.
Qed.

Lemma tc_all_fst : forall x0 x1 x2 x3, tc_all x0 x1 x2 x3 = true ->
  fst x0 = true /\ fst x1 = true /\ fst x2 = true /\ fst x3 = true.
Proof. intros x0 x1 x2 x3 H. unfold tc_all in H. rewrite !andb_true_iff in H. tauto. Qed.

(** The chain: every quotient the tail answers with a value is one its rounding certified. *)
Theorem tc_quot_tail_correct : forall cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3
  V0 V1 V2 V3 VD cl' rs' t ua ub uc ts',
  tc_qinv x0 V0 VD -> tc_qinv x1 V1 VD -> tc_qinv x2 V2 VD -> tc_qinv x3 V3 VD ->
  (snd q0 = true -> fin (fst q0) = true /\ B2R (fst q0) = RN (V0 / VD)) ->
  (snd q1 = true -> fin (fst q1) = true /\ B2R (fst q1) = RN (V1 / VD)) ->
  (snd q2 = true -> fin (fst q2) = true /\ B2R (fst q2) = RN (V2 / VD)) ->
  (snd q3 = true -> fin (fst q3) = true /\ B2R (fst q3) = RN (V3 / VD)) ->
  (forall r, p0 = Some r -> snd r = true -> fin (fst r) = true /\ B2R (fst r) = RN (V0 / VD)) ->
  (forall r, p1 = Some r -> snd r = true -> fin (fst r) = true /\ B2R (fst r) = RN (V1 / VD)) ->
  (forall r, p2 = Some r -> snd r = true -> fin (fst r) = true /\ B2R (fst r) = RN (V2 / VD)) ->
  (forall r, p3 = Some r -> snd r = true -> fin (fst r) = true /\ B2R (fst r) = RN (V3 / VD)) ->
  ((ds = 1%Z \/ ds = (-1)%Z) -> (ds = 1%Z /\ 0 < VD) \/ (ds = (-1)%Z /\ VD < 0)) ->
  (forall l, dn = Some l -> (length l <= 16)%nat /\ sumR l = VD) ->
  (forall l, b0 = Some l -> (length l <= 16)%nat /\ sumR l = V0) ->
  (forall l, b1 = Some l -> (length l <= 16)%nat /\ sumR l = V1) ->
  (forall l, b2 = Some l -> (length l <= 16)%nat /\ sumR l = V2) ->
  (forall l, b3 = Some l -> (length l <= 16)%nat /\ sumR l = V3) ->
  tc_quot_tail cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 = TCDecided cl' rs' t ua ub uc ts' ->
  cl' = cl /\ tc_quotient_means t V0 VD /\ tc_quotient_means ua V1 VD /\ tc_quotient_means ub V2 VD /\
  tc_quotient_means uc V3 VD.
Proof.
  intros cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 V0 V1 V2 V3 VD cl' rs' t ua ub uc ts'
    I0 I1 I2 I3 Q0 Q1 Q2 Q3 P0 P1 P2 P3 HS HD B0 B1 B2 B3.
  assert (Done : forall y0 y1 y2 y3 s, tc_qinv y0 V0 VD -> tc_qinv y1 V1 VD -> tc_qinv y2 V2 VD -> tc_qinv y3 V3 VD ->
            tc_all y0 y1 y2 y3 = true ->
            TCDecided cl rs (snd y0) (snd y1) (snd y2) (snd y3) s = TCDecided cl' rs' t ua ub uc ts' ->
            cl' = cl /\ tc_quotient_means t V0 VD /\ tc_quotient_means ua V1 VD /\ tc_quotient_means ub V2 VD /\
            tc_quotient_means uc V3 VD).
  { intros y0 y1 y2 y3 s J0 J1 J2 J3 A E. injection E as <- _ <- <- <- <- _.
    destruct (tc_all_fst _ _ _ _ A) as [A0 [A1 [A2 A3]]].
    exact (conj eq_refl (conj (J0 A0) (conj (J1 A1) (conj (J2 A2) (J3 A3))))). }
  unfold tc_quot_tail. destruct (tc_all x0 x1 x2 x3) eqn:A; [exact (Done _ _ _ _ _ I0 I1 I2 I3 A)|].
  pose proof (tc_qinv_qstep _ _ _ _ I0 Q0) as J0. pose proof (tc_qinv_qstep _ _ _ _ I1 Q1) as J1.
  pose proof (tc_qinv_qstep _ _ _ _ I2 Q2) as J2. pose proof (tc_qinv_qstep _ _ _ _ I3 Q3) as J3.
  unfold tc_quot_tail2.
  destruct (tc_all (qstep x0 q0) (qstep x1 q1) (qstep x2 q2) (qstep x3 q3)) eqn:A2;
    [exact (Done _ _ _ _ _ J0 J1 J2 J3 A2)|].
  pose proof (tc_qinv_qs3 _ _ _ _ J0 P0) as K0. pose proof (tc_qinv_qs3 _ _ _ _ J1 P1) as K1.
  pose proof (tc_qinv_qs3 _ _ _ _ J2 P2) as K2. pose proof (tc_qinv_qs3 _ _ _ _ J3 P3) as K3.
  unfold tc_quot_tail3.
  destruct (tc_all (tc_qs3 (qstep x0 q0) p0) (tc_qs3 (qstep x1 q1) p1) (tc_qs3 (qstep x2 q2) p2)
                   (tc_qs3 (qstep x3 q3) p3)) eqn:A3; [exact (Done _ _ _ _ _ K0 K1 K2 K3 A3)|].
  pose proof (tc_qinv_boundary _ _ _ _ _ _ K0 HS HD B0) as L0. pose proof (tc_qinv_boundary _ _ _ _ _ _ K1 HS HD B1) as L1.
  pose proof (tc_qinv_boundary _ _ _ _ _ _ K2 HS HD B2) as L2. pose proof (tc_qinv_boundary _ _ _ _ _ _ K3 HS HD B3) as L3.
  unfold tc_quot_tail4.
  destruct (tc_all (qstep_boundary (tc_qs3 (qstep x0 q0) p0) ds dn b0) (qstep_boundary (tc_qs3 (qstep x1 q1) p1) ds dn b1)
                   (qstep_boundary (tc_qs3 (qstep x2 q2) p2) ds dn b2) (qstep_boundary (tc_qs3 (qstep x3 q3) p3) ds dn b3))
    eqn:A4; [exact (Done _ _ _ _ _ L0 L1 L2 L3 A4)|].
  intros E. injection E as <- _ <- <- <- <- _.
  exact (conj eq_refl (conj (tc_qinv_final _ _ _ L0) (conj (tc_qinv_final _ _ _ L1)
           (conj (tc_qinv_final _ _ _ L2) (tc_qinv_final _ _ _ L3))))).
Qed.

(** ** The pieces of the cascade *)

Lemma tc_q2_correct : forall o d a b c v, F.tc_index v ->
  snd (tc_q2 o d a b c v) = true ->
  fin (fst (tc_q2 o d a b c v)) = true /\
  B2R (fst (tc_q2 o d a b c v)) = RN (value_model o d a b c v / value_model o d a b c 3).
Proof. intros o d a b c v I. exact (tc_stage2_quotient_correct o d a b c v I). Qed.

Lemma tc_r3_correct : forall o d a b c v r, tc_r3 o d a b c v = Some r -> snd r = true ->
  fin (fst r) = true /\ B2R (fst r) = RN (value_model o d a b c v / value_model o d a b c 3).
Proof.
  intros o d a b c v r. unfold tc_r3. cbv zeta.
  destruct (tc_expansion_enclosure_b o d a b c v) as [n|] eqn:En; [|intros H; discriminate H].
  intros H. injection H as <-. intros S.
  destruct (F.tc_stage3_quotient_correct o d a b c v n En S) as [_ R]. rewrite F.value_model_3. exact R.
Qed.

(** A start: an asked quotient whose numerator's sign is exactly 0 is +0 = RN(0/den). *)
Lemma tc_start_inv : forall w n V VD, (w = true -> n = sign_of V) -> tc_qinv (tc_start w n) V VD.
Proof.
  intros w n V VD H. unfold tc_start, tc_qinv, tc_quotient_means. cbn [fst snd].
  destruct w; cbn [negb orb]; [|intros _ x E; discriminate E].
  intros Z0 x E. injection E as <-. apply Z.eqb_eq in Z0. rewrite (H eq_refl) in Z0.
  split; [reflexivity | exact (F.tc_zero_quotient_correct V VD Z0)].
Qed.

(** A numerator's sign asked or not: without [needs_exact_] after it, the exact sign, and no
    [needs_exact_] before it. *)
Lemma tc_opt_sign_step : forall o d a b c v (w : bool) f n f', F.tc_index v ->
  (if w then tc_sign_b o d a b c v f else (0%Z, f)) = (n, f') -> tf_exact f' = false ->
  (w = true -> n = sign_of (value_model o d a b c v)) /\ tf_exact f = false.
Proof.
  intros o d a b c v w f n f' I E X. destruct w.
  - destruct (F.tcf_sign_step o d a b c v f n f' I E X) as [S X0]. split; [intros _; exact S | exact X0].
  - injection E as <- <-. split; [intros H; discriminate H | exact X].
Qed.

(** ** The theorem *)

(** [triangle_intersection_cascade] (kernel/src/triangle/ray_triangle_cascade.cpp), through its twin: for
    every 64-bit pattern of o, d, a, b, c, every option set and both rules, an answer before the exact stage
    has §6's classification under the rule, and t, u_a, u_b, u_c, when they have a value, are finite and
    RN(num/den), RN(π(b, c)/den), RN(π(c, a)/den), RN(π(a, b)/den). *)
Theorem tc_intersect_b_correct : forall want_t want_u owned_rule o d a b c cl rs t ua ub uc ts,
  tc_intersect_b want_t want_u owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  contract_class owned_rule O D A B C cl /\
  tc_quotient_means t (num_value O A B C) (den_value O D A B C) /\
  tc_quotient_means ua (edge_value O D B C) (den_value O D A B C) /\
  tc_quotient_means ub (edge_value O D C A) (den_value O D A B C) /\
  tc_quotient_means uc (edge_value O D A B) (den_value O D A B C).
Proof.
  intros wt wu rule o d a b c cl rs t ua ub uc ts H.
  pose proof (F.tc_intersect_b_class_correct wt wu rule o d a b c cl rs t ua ub uc ts H) as Cl.
  cbv zeta. split; [exact Cl|]. revert H.
  rewrite tc_intersect_b_eq, <- (F.value_model_0 o d a b c), <- (F.value_model_1 o d a b c),
    <- (F.value_model_2 o d a b c), <- (F.value_model_3 o d a b c), <- (F.value_model_4 o d a b c).
  assert (Nan : forall V, tc_quotient_means QNaN V (value_model o d a b c 3)) by (intros V x E; discriminate E).
  assert (Ex : forall (w : bool) V, tc_quotient_means (if w then QExact else QNaN) V (value_model o d a b c 3))
    by (intros [|] V x E; discriminate E).
  destruct (tc_classify_b o d a b c rule) as [cl0 f0]. destruct (tf_exact f0); [intros E; discriminate E|].
  destruct (_ || _)%bool.
  { intros E. injection E as _ _ <- <- <- <- _. tsplit; apply Nan. }
  destruct (if wt then tc_sign_b o d a b c 4 f0 else (0%Z, f0)) as [n0 f1] eqn:N0.
  destruct (if wu then tc_sign_b o d a b c 0 f1 else (0%Z, f1)) as [n1 f2] eqn:N1.
  destruct (if wu then tc_sign_b o d a b c 1 f2 else (0%Z, f2)) as [n2 f3] eqn:N2.
  destruct (if wu then tc_sign_b o d a b c 2 f3 else (0%Z, f3)) as [n3 f4] eqn:N3.
  destruct (tf_exact f4) eqn:X4.
  { intros E. injection E as _ _ <- <- <- <- _. tsplit; apply Ex. }
  destruct (tc_opt_sign_step o d a b c 2 wu f3 n3 f4 ltac:(unfold F.tc_index; lia) N3 X4) as [S3 X3].
  destruct (tc_opt_sign_step o d a b c 1 wu f2 n2 f3 ltac:(unfold F.tc_index; lia) N2 X3) as [S2 X2].
  destruct (tc_opt_sign_step o d a b c 0 wu f1 n1 f2 ltac:(unfold F.tc_index; lia) N1 X2) as [S1 X1].
  destruct (tc_opt_sign_step o d a b c 4 wt f0 n0 f1 ltac:(unfold F.tc_index; lia) N0 X1) as [S0 _].
  intros E.
  destruct (tc_quot_tail_correct _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _
              (tc_start_inv _ _ _ _ S0) (tc_start_inv _ _ _ _ S1) (tc_start_inv _ _ _ _ S2) (tc_start_inv _ _ _ _ S3)
              (tc_q2_correct o d a b c 4 ltac:(unfold F.tc_index; lia))
              (tc_q2_correct o d a b c 0 ltac:(unfold F.tc_index; lia))
              (tc_q2_correct o d a b c 1 ltac:(unfold F.tc_index; lia))
              (tc_q2_correct o d a b c 2 ltac:(unfold F.tc_index; lia))
              (tc_r3_correct o d a b c 4) (tc_r3_correct o d a b c 0)
              (tc_r3_correct o d a b c 1) (tc_r3_correct o d a b c 2)
              (tc_den_sign_means o d a b c) (tc_short_means o d a b c 3)
              (tc_short_means o d a b c 4) (tc_short_means o d a b c 0)
              (tc_short_means o d a b c 1) (tc_short_means o d a b c 2) E) as [_ R].
  exact R.
Qed.

(** ** A quotient not asked is NaN *)

Lemma tc_certain_qstep : forall x q, fst x = true -> qstep x q = x.
Proof. intros [c v] q F. cbn [fst] in F. subst c. reflexivity. Qed.

Lemma tc_certain_qs3 : forall x p, fst x = true -> tc_qs3 x p = x.
Proof. intros [c v] p F. cbn [fst] in F. subst c. reflexivity. Qed.

Lemma tc_certain_boundary : forall x ds dn bn, fst x = true -> qstep_boundary x ds dn bn = x.
Proof. intros [c v] ds dn bn F. cbn [fst] in F. subst c. reflexivity. Qed.

Lemma tc_certain_chain2 : forall x q p, fst x = true -> tc_qs3 (qstep x q) p = x.
Proof. intros x q p F. rewrite (tc_certain_qstep x q F). exact (tc_certain_qs3 x p F). Qed.

Lemma tc_certain_chain3 : forall x q p ds dn bn, fst x = true -> qstep_boundary (tc_qs3 (qstep x q) p) ds dn bn = x.
Proof. intros x q p ds dn bn F. rewrite (tc_certain_chain2 x q p F). exact (tc_certain_boundary x ds dn bn F). Qed.

Lemma tc_quot_tail_nan : forall cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 cl' rs' t ua ub uc ts',
  tc_quot_tail cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 = TCDecided cl' rs' t ua ub uc ts' ->
  (fst x0 = true /\ snd x0 = QNaN -> t = QNaN) /\ (fst x1 = true /\ snd x1 = QNaN -> ua = QNaN) /\
  (fst x2 = true /\ snd x2 = QNaN -> ub = QNaN) /\ (fst x3 = true /\ snd x3 = QNaN -> uc = QNaN).
Proof.
  intros cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 cl' rs' t ua ub uc ts'.
  unfold tc_quot_tail, tc_quot_tail2, tc_quot_tail3, tc_quot_tail4.
  destruct (tc_all x0 x1 x2 x3).
  { intros E. injection E as _ _ <- <- <- <- _. tsplit; intros [_ S]; exact S. }
  destruct (tc_all (qstep x0 q0) (qstep x1 q1) (qstep x2 q2) (qstep x3 q3)).
  { intros E. injection E as _ _ <- <- <- <- _. tsplit; intros [F S]; rewrite tc_certain_qstep; assumption. }
  destruct (tc_all (tc_qs3 _ _) _ _ _).
  { intros E. injection E as _ _ <- <- <- <- _. tsplit; intros [F S]; rewrite tc_certain_chain2; assumption. }
  destruct (tc_all _ _ _ _).
  - intros E. injection E as _ _ <- <- <- <- _. tsplit; intros [F S]; rewrite tc_certain_chain3; assumption.
  - intros E. injection E as _ _ <- <- <- <- _.
    tsplit; intros [F S]; (rewrite tc_certain_chain3; [unfold qfinal; rewrite F; exact S | exact F]).
Qed.

(** [triangle_intersection_cascade] through its twin: a quotient not asked is NaN, in every answer. *)
Theorem tc_intersect_b_unasked : forall want_t want_u owned_rule o d a b c cl rs t ua ub uc ts,
  tc_intersect_b want_t want_u owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  (want_t = false -> t = QNaN) /\ (want_u = false -> ua = QNaN /\ ub = QNaN /\ uc = QNaN).
Proof.
  intros wt wu rule o d a b c cl rs t ua ub uc ts. rewrite tc_intersect_b_eq.
  destruct (tc_classify_b o d a b c rule) as [cl0 f0]. destruct (tf_exact f0); [intros E; discriminate E|].
  destruct (_ || _)%bool.
  { intros E. injection E as _ _ <- <- <- <- _. split; intros _; tsplit; reflexivity. }
  destruct (if wt then tc_sign_b o d a b c 4 f0 else (0%Z, f0)) as [n0 f1].
  destruct (if wu then tc_sign_b o d a b c 0 f1 else (0%Z, f1)) as [n1 f2].
  destruct (if wu then tc_sign_b o d a b c 1 f2 else (0%Z, f2)) as [n2 f3].
  destruct (if wu then tc_sign_b o d a b c 2 f3 else (0%Z, f3)) as [n3 f4].
  destruct (tf_exact f4).
  { intros E. injection E as _ _ <- <- <- <- _. split; intros ->; tsplit; reflexivity. }
  intros E. destruct (tc_quot_tail_nan _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ E) as [T0 [T1 [T2 T3]]].
  split.
  - intros ->. apply T0. split; reflexivity.
  - intros ->. tsplit; [apply T1 | apply T2 | apply T3]; split; reflexivity.
Qed.
