(** * Computable twins of the certified routines, over IEEE-754 binary64, tied to the model.

    Each [*_b] definition below is one C++ routine of kernel/src/certified/, operation by operation in
    the C++ order, over Flocq's IEEE binary64 (FloatCore.v): it computes the same bits as the compiled
    C++ for every input, ±0, subnormals, ±inf and NaN included (checked by the differential runner,
    proofs/twins/, on every variant the kernel is compiled to).  Each twin theorem says: when the twin
    certifies (its decision says certain, or the radius it returns is finite), every input and every
    output is finite and equal, as a real number, to what the model of Model.v computes from the same
    inputs, so the soundness theorems of PlaneFilter.v and PlaneCompensated.v apply to the twin's outputs.  The
    corollaries [*_twin_sound] state the result end to end, for every bit pattern of every input: what
    the C++ certifies is true of the exact values — for stage 1 with no hypothesis; for stage 2 given
    that hi and lo are finite (the C++ tests no finiteness since issue 13), a hypothesis that
    PlaneStageTwoFinite.v discharges: a certain stage-2 sign implies finite hi and lo, for every bit pattern
    ([den_compensated_twin_sound_total], [num_compensated_twin_sound_total]).

    - eft.hpp: [two_sum_b], [two_diff_b], [two_prod_b] ([two_sum_twin], [two_prod_twin]);
    - dot3_filter.hpp: [dot3_rounded_b], [dot3_filter_lanes_b], [dot3_filter_b] ([dot3_rounded_twin],
      [dot3_filter_lanes_twin]; [den_filter_twin_sound], [num_filter_twin_sound]);
    - dot3_compensated.hpp: [compensated_dot3_b], [compensated_dot3_exact_b] (α = 0),
      [compensated_dot3_refined_b] ([compensated_dot3_twin], [compensated_dot3_exact_twin]; the refined
      twin's theorem is PlaneRefinedTwins.v's [compensated_dot3_refined_twin]);
    - enclosure.hpp: [enclosure_sign_lanes_b] ([enclosure_sign_twin]; end to end
      [den_compensated_twin_sound], [num_compensated_twin_sound]);
    - expansion.hpp: [expansion_tail_enclosure_b] ([expansion_tail_enclosure_twin]).

    The constants are the compiled ones: [Cpp.NAME] (ConstantsCpp.v, generated from the compiled
    error_bounds.hpp at build time); the lemmas [cpp_NAME] prove each equal to the Constants.v value the
    soundness theorems were proved with. *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneCascade FloatCore ConstantsCpp.
Open Scope R_scope.

(** ** Constants: the compiled values of error_bounds.hpp are the ones the theorems use. *)

(** The lemmas [cpp_NAME] : B2R Cpp.NAME = NAME, one per constant, are generated with the constants into
    ConstantsCpp.v (twins/emit_constants.cmake; FloatCore.v's [tie]). *)

Global Hint Rewrite cpp_filter_den_relative cpp_filter_num_relative cpp_filter_absolute
  cpp_compensated_relative cpp_compensated_absolute cpp_refined_relative cpp_refined_low_relative
  cpp_refined_absolute cpp_tail_sum_relative cpp_tail_sum_absolute cpp_compare_filter_relative
  cpp_compare_propagation_factor cpp_compare_absolute cpp_compare_compensated_relative : cpp_constants.

(** Every constant the twins use is a finite, non-negative double. *)
Lemma cpp_constants_finite :
  fin Cpp.filter_den_relative = true /\ fin Cpp.filter_num_relative = true /\ fin Cpp.filter_absolute = true /\
  fin Cpp.compensated_relative = true /\ fin Cpp.compensated_absolute = true /\
  fin Cpp.refined_relative = true /\ fin Cpp.refined_low_relative = true /\ fin Cpp.refined_absolute = true /\
  fin Cpp.tail_sum_relative = true /\ fin Cpp.tail_sum_absolute = true /\
  fin Cpp.compare_filter_relative = true /\ fin Cpp.compare_propagation_factor = true /\
  fin Cpp.compare_absolute = true /\ fin Cpp.compare_compensated_relative = true.
Proof. vm_compute. repeat split. Qed.

Ltac const_nonneg := lazymatch goal with |- nonneg ?c => is_const c; right; vm_compute; reflexivity end.

(** ** Tactics: from "this result is finite" to "every operation below it is the model's". *)

(** [have_fin], [fin_down], [fin_solve]: FloatCore.v. *)

(** Put the finiteness of every constant in the context. *)
Ltac cpp_fin := let H := fresh "Fcpp" in pose proof cpp_constants_finite as H;
  repeat match type of H with _ /\ _ => let H' := fresh "Fcpp" in destruct H as [H' H] end;
  pose proof largest_finite_f_fin.

(** Rewrite every B2R of an operation, every comparison and every constant into the model's terms (FloatCore.v's
    [to_model_ops], then the constants). *)
Ltac to_model := to_model_ops; autorewrite with cpp_constants.

(** ** eft.hpp *)

(** [two_sum(a, b)]: s = a + b, b_virtual = s − a, a_virtual = s − b_virtual, b_roundoff = b − b_virtual,
    a_roundoff = a − a_virtual, (s, a_roundoff + b_roundoff). *)
Definition two_sum_b (a b : float) : float * float :=
  let s := fadd a b in
  let b_virtual := fsub s a in
  let a_virtual := fsub s b_virtual in
  let b_roundoff := fsub b b_virtual in
  let a_roundoff := fsub a a_virtual in
  (s, fadd a_roundoff b_roundoff).

(** [two_diff(a, b)] is [two_sum(a, -b)]. *)
Definition two_diff_b (a b : float) : float * float := two_sum_b a (fneg b).

(** [two_prod(a, b)]: p = a * b, (p, fma(a, b, −p)). *)
Definition two_prod_b (a b : float) : float * float :=
  let p := fmul a b in (p, ffma a b (fneg p)).

Definition pair_R (x : float * float) : R * R := (B2R (fst x), B2R (snd x)).

(** Every operation of TwoSum flows into its low part: a finite low part means a finite computation,
    which is the model's. *)
Theorem two_sum_twin : forall a b, fin (snd (two_sum_b a b)) = true ->
  fin a = true /\ fin b = true /\ fin (fst (two_sum_b a b)) = true /\
  pair_R (two_sum_b a b) = two_sum (B2R a) (B2R b).
Proof.
  intros a b H. unfold two_sum_b in *. cbn [fst snd] in *. fin_down.
  repeat split; try assumption.
  unfold pair_R, two_sum. cbn [fst snd]. to_model. reflexivity.
Qed.

Corollary two_sum_twin_exact : forall a b, fin (snd (two_sum_b a b)) = true ->
  B2R (fst (two_sum_b a b)) + B2R (snd (two_sum_b a b)) = B2R a + B2R b.
Proof.
  intros a b H. destruct (two_sum_twin a b H) as [Fa [Fb [_ E]]].
  change (fst (pair_R (two_sum_b a b)) + snd (pair_R (two_sum_b a b)) = B2R a + B2R b).
  rewrite E. apply two_sum_exact; apply binary64_B2R.
Qed.

Theorem two_prod_twin : forall a b, fin (snd (two_prod_b a b)) = true ->
  fin a = true /\ fin b = true /\ fin (fst (two_prod_b a b)) = true /\
  pair_R (two_prod_b a b) = two_prod (B2R a) (B2R b).
Proof.
  intros a b H. unfold two_prod_b in *. cbn [fst snd] in *. fin_down.
  repeat split; try assumption.
  unfold pair_R, two_prod, fma. cbn [fst snd]. to_model. reflexivity.
Qed.


(** The low part of TwoSum or TwoProduct being finite, the whole transformation is the model's. *)
Lemma two_sum_b_inv : forall a b, fin (snd (two_sum_b a b)) = true ->
  fin a = true /\ fin b = true /\ fin (fst (two_sum_b a b)) = true /\
  B2R (fst (two_sum_b a b)) = fst (two_sum (B2R a) (B2R b)) /\
  B2R (snd (two_sum_b a b)) = snd (two_sum (B2R a) (B2R b)).
Proof.
  intros a b H. destruct (two_sum_twin a b H) as [Fa [Fb [Fs E]]].
  repeat split; try assumption.
  - change (fst (pair_R (two_sum_b a b)) = fst (two_sum (B2R a) (B2R b))). now rewrite E.
  - change (snd (pair_R (two_sum_b a b)) = snd (two_sum (B2R a) (B2R b))). now rewrite E.
Qed.

Lemma two_sum_b_fst : forall a b, fin (fst (two_sum_b a b)) = true ->
  fin a = true /\ fin b = true /\ B2R (fst (two_sum_b a b)) = fst (two_sum (B2R a) (B2R b)).
Proof. intros a b H. exact (fadd_inv a b H). Qed.

Lemma two_prod_b_inv : forall a b, fin (snd (two_prod_b a b)) = true ->
  fin a = true /\ fin b = true /\ fin (fst (two_prod_b a b)) = true /\
  B2R (fst (two_prod_b a b)) = fst (two_prod (B2R a) (B2R b)) /\
  B2R (snd (two_prod_b a b)) = snd (two_prod (B2R a) (B2R b)).
Proof.
  intros a b H. destruct (two_prod_twin a b H) as [Fa [Fb [Fs E]]].
  repeat split; try assumption.
  - change (fst (pair_R (two_prod_b a b)) = fst (two_prod (B2R a) (B2R b))). now rewrite E.
  - change (snd (pair_R (two_prod_b a b)) = snd (two_prod (B2R a) (B2R b))). now rewrite E.
Qed.

Lemma two_prod_b_fst : forall a b, fin (fst (two_prod_b a b)) = true ->
  fin a = true /\ fin b = true /\ B2R (fst (two_prod_b a b)) = fst (two_prod (B2R a) (B2R b)).
Proof. intros a b H. exact (fmul_inv a b H). Qed.

(** The C++ loop [for (j = 1; j < 8; ++j) { step = two_sum(sigma, first_order[j]); sigma = step.hi;
    tail += step.lo; }]. *)
Fixpoint two_sum_chain_b (sigma tail : float) (rest : list float) : float * float :=
  match rest with
  | nil => (sigma, tail)
  | f :: rest' => let step := two_sum_b sigma f in two_sum_chain_b (fst step) (fadd tail (snd step)) rest'
  end.

(** The chain's final tail being finite, every step is finite and the model's. *)
Lemma two_sum_chain_b_inv : forall rest sigma tail,
  fin (snd (two_sum_chain_b sigma tail rest)) = true ->
  fin tail = true /\ Forall (fun x => fin x = true) rest /\ (rest = nil \/ fin sigma = true) /\
  B2R (fst (two_sum_chain_b sigma tail rest)) = fst (two_sum_chain (B2R sigma) (B2R tail) (map B2R rest)) /\
  B2R (snd (two_sum_chain_b sigma tail rest)) = snd (two_sum_chain (B2R sigma) (B2R tail) (map B2R rest)).
Proof.
  induction rest as [|f rest IH]; intros sigma tail H.
  - simpl in *. repeat split; auto.
  - cbn [two_sum_chain_b] in H. destruct (IH _ _ H) as [Ft [Fr [_ [E1 E2]]]].
    destruct (fadd_inv _ _ Ft) as [Ftail [Fstep Vt]].
    destruct (two_sum_b_inv _ _ Fstep) as [Fs [Ff [Fh [Eh El]]]].
    repeat split; auto.
    + cbn [two_sum_chain_b two_sum_chain map]. rewrite E1, Vt, Eh, El. reflexivity.
    + cbn [two_sum_chain_b two_sum_chain map]. rewrite E2, Vt, Eh, El. reflexivity.
Qed.

(** The same tactics, one level up: TwoSum and TwoProduct as single steps (keeps the terms small). *)
Ltac fin_down2 :=
  repeat first [match goal with
  | H : fin (snd (two_sum_chain_b ?s ?t ?l)) = true |- _ =>
      tryif have_fin t then fail else
      (let HF := fresh in let HS := fresh in destruct (two_sum_chain_b_inv l s t H) as [? [HF [HS _]]];
       repeat (apply Forall_cons_iff in HF; destruct HF as [? HF]);
       destruct HS as [HS|HS]; [discriminate HS|])
  | H : fin (snd (two_sum_b ?x ?y)) = true |- _ =>
      tryif (have_fin (fst (two_sum_b x y))) then fail else destruct (two_sum_b_inv x y H) as [? [? [? _]]]
  | H : fin (fst (two_sum_b ?x ?y)) = true |- _ =>
      tryif (have_fin x; have_fin y) then fail else destruct (two_sum_b_fst x y H) as [? [? _]]
  | H : fin (snd (two_prod_b ?x ?y)) = true |- _ =>
      tryif (have_fin (fst (two_prod_b x y))) then fail else destruct (two_prod_b_inv x y H) as [? [? [? _]]]
  | H : fin (fst (two_prod_b ?x ?y)) = true |- _ =>
      tryif (have_fin x; have_fin y) then fail else destruct (two_prod_b_fst x y H) as [? [? _]]
  end | fin_down_step].

Ltac to_model2 :=
  fin_down2;
  repeat first [match goal with
  | |- context [B2R (fst (two_sum_chain_b ?s ?t ?l))] =>
      rewrite (proj1 (proj2 (proj2 (proj2 (two_sum_chain_b_inv l s t ltac:(fin_solve))))))
  | |- context [B2R (snd (two_sum_chain_b ?s ?t ?l))] =>
      rewrite (proj2 (proj2 (proj2 (proj2 (two_sum_chain_b_inv l s t ltac:(fin_solve))))))
  | |- context [map B2R (?a :: ?l)] => change (map B2R (a :: l)) with (B2R a :: map B2R l)
  | |- context [map B2R nil] => change (map B2R nil) with (@nil R)
  | |- context [B2R (fst (two_sum_b ?x ?y))] =>
      rewrite (proj2 (proj2 (two_sum_b_fst x y ltac:(fin_solve))))
  | |- context [B2R (snd (two_sum_b ?x ?y))] =>
      rewrite (proj2 (proj2 (proj2 (proj2 (two_sum_b_inv x y ltac:(fin_solve))))))
  | |- context [B2R (fst (two_prod_b ?x ?y))] =>
      rewrite (proj2 (proj2 (two_prod_b_fst x y ltac:(fin_solve))))
  | |- context [B2R (snd (two_prod_b ?x ?y))] =>
      rewrite (proj2 (proj2 (proj2 (proj2 (two_prod_b_inv x y ltac:(fin_solve))))))
  end | to_model_step];
  autorewrite with cpp_constants.

(** ** dot3_filter.hpp *)

(** [Dot3RoundedT] and [dot3_rounded(a, b)]. *)
Record Dot3B := { qb0 : float; qb1 : float; qb2 : float; valueb : float; magnitudeb : float }.

Definition dot3_rounded_b (a0 a1 a2 b0 b1 b2 : float) : Dot3B :=
  let q0 := fmul a0 b0 in let q1 := fmul a1 b1 in let q2 := fmul a2 b2 in
  {| qb0 := q0; qb1 := q1; qb2 := q2;
     valueb := fadd (fadd q0 q1) q2;
     magnitudeb := fadd (fadd (fabs q0) (fabs q1)) (fabs q2) |}.

Definition dot3_R (r : Dot3B) : Dot3Rounded :=
  {| product0 := B2R (qb0 r); product1 := B2R (qb1 r); product2 := B2R (qb2 r);
     value := B2R (valueb r); magnitude := B2R (magnitudeb r) |}.

(** [dot3_filter_lanes(r, C)]: bound = C·m + 3μ, [sign_lanes(value > bound, value < −bound)]. *)
Definition dot3_filter_lanes_b (r : Dot3B) (C : float) : Z :=
  let bound := fadd (fmul C (magnitudeb r)) Cpp.filter_absolute in
  sign_lanes (flt bound (valueb r)) (flt (valueb r) (fneg bound)).

(** [dot3_filter(r, C, exactly_zero)]. *)
Definition dot3_filter_b (r : Dot3B) (C : float) (exactly_zero : bool) : sign :=
  if exactly_zero then Zero else sign_from_Z (dot3_filter_lanes_b r C).

(** The magnitude m dominates the products and the value: a finite m means a finite computation. *)
Theorem dot3_rounded_twin : forall a0 a1 a2 b0 b1 b2,
  let r := dot3_rounded_b a0 a1 a2 b0 b1 b2 in
  fin (magnitudeb r) = true ->
  fin a0 = true /\ fin a1 = true /\ fin a2 = true /\ fin b0 = true /\ fin b1 = true /\ fin b2 = true /\
  fin (qb0 r) = true /\ fin (qb1 r) = true /\ fin (qb2 r) = true /\ fin (valueb r) = true /\
  dot3_R r = dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2).
Proof.
  intros a0 a1 a2 b0 b1 b2 r H. subst r. unfold dot3_rounded_b in *. cbn [magnitudeb valueb qb0 qb1 qb2] in *.
  set (q0 := fmul a0 b0) in *. set (q1 := fmul a1 b1) in *. set (q2 := fmul a2 b2) in *.
  set (m2 := fadd (fabs q0) (fabs q1)) in *.
  assert (Fm2 : fin m2 = true) by (destruct (fadd_fin _ _ H); assumption).
  assert (Fq2 : fin q2 = true) by (destruct (fadd_fin _ _ H) as [_ F]; now rewrite fabs_fin in F).
  assert (Fq0 : fin q0 = true) by (destruct (fadd_fin _ _ Fm2) as [F _]; now rewrite fabs_fin in F).
  assert (Fq1 : fin q1 = true) by (destruct (fadd_fin _ _ Fm2) as [_ F]; now rewrite fabs_fin in F).
  destruct (fmul_inv _ _ Fq0) as [Fa0 [Fb0 V0]]. destruct (fmul_inv _ _ Fq1) as [Fa1 [Fb1 V1]].
  destruct (fmul_inv _ _ Fq2) as [Fa2 [Fb2 V2]].
  (* the value is dominated by the magnitude *)
  assert (S2 : fin (fadd q0 q1) = true /\ B2R (fadd q0 q1) = RN (B2R q0 + B2R q1)).
  { apply fadd_dominated with (z := m2); try assumption.
    unfold m2. rewrite fadd_val by assumption. rewrite !fabs_val, <- RN_abs.
    apply RN_le, Rabs_triang. }
  destruct S2 as [Fs2 Vs2].
  assert (S : fin (fadd (fadd q0 q1) q2) = true).
  { apply (fadd_dominated _ _ (fadd m2 (fabs q2))); try assumption.
    rewrite (fadd_val m2 (fabs q2) H). unfold m2. rewrite (fadd_val (fabs q0) (fabs q1) Fm2).
    rewrite !fabs_val, Vs2, <- RN_abs. apply RN_le.
    eapply Rle_trans; [apply Rabs_triang|]. apply Rplus_le_compat_r.
    rewrite <- RN_abs. apply RN_le, Rabs_triang. }
  repeat split; try assumption.
  unfold dot3_R, dot3_rounded. cbn [qb0 qb1 qb2 valueb magnitudeb]. unfold m2, q0, q1, q2 in *.
  to_model. reflexivity.
Qed.

(** A certain filter sign means a finite bound, hence a finite stage 1, equal to the model's. *)
Theorem dot3_filter_lanes_twin : forall a0 a1 a2 b0 b1 b2 C,
  fin C = true -> nonneg C ->
  let r := dot3_rounded_b a0 a1 a2 b0 b1 b2 in
  dot3_filter_lanes_b r C <> uncertain_lane ->
  fin (magnitudeb r) = true /\
  dot3_filter_lanes_b r C = dot3_filter_lanes (dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)) (B2R C).
Proof.
  intros a0 a1 a2 b0 b1 b2 C FC NC r U.
  unfold dot3_filter_lanes_b in U.
  set (bound := fadd (fmul C (magnitudeb r)) Cpp.filter_absolute) in U.
  assert (NB : nonneg bound).
  { apply fadd_nonneg; [apply fmul_nonneg; [exact NC|] | const_nonneg].
    subst r. unfold dot3_rounded_b. cbn [magnitudeb].
    apply fadd_nonneg; [apply fadd_nonneg|]; apply fabs_nonneg. }
  assert (FB : fin bound = true).
  { apply (certifying_bound_finite bound (valueb r) NB). now apply sign_lanes_certain. }
  assert (Fm : fin (magnitudeb r) = true).
  { destruct (fadd_fin _ _ FB) as [F _]. now destruct (fmul_fin _ _ F). }
  destruct (dot3_rounded_twin a0 a1 a2 b0 b1 b2 Fm) as [_ [_ [_ [_ [_ [_ [_ [_ [_ [Fv E]]]]]]]]]].
  fold r in Fv, E. split; [exact Fm|].
  rewrite <- E. unfold dot3_filter_lanes_b, dot3_filter_lanes, filter_bound. fold bound.
  unfold bound in *. cbn [dot3_R value magnitude]. cpp_fin. to_model. reflexivity.
Qed.

Lemma cpp_filter_constants :
  fin Cpp.filter_den_relative = true /\ nonneg Cpp.filter_den_relative /\
  fin Cpp.filter_num_relative = true /\ nonneg Cpp.filter_num_relative.
Proof. repeat split; try fin_solve; const_nonneg. Qed.

(** End to end, for every 64-bit pattern of d and n: a sign stage 1 certifies for den = d·n is the sign
    of the exact value, and then d and n are finite.  ("The fast path needs no validation": NaN and inf
    inputs are never certified; PlaneCascade.v's [fast_path_den_valid] adds d ≠ 0 and n ≠ 0.) *)
Theorem den_filter_twin_sound : forall d0 d1 d2 n0 n1 n2 : float,
  let s := dot3_filter_lanes_b (dot3_rounded_b d0 d1 d2 n0 n1 n2) Cpp.filter_den_relative in
  certifies (sign_from_Z s) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) /\
  (s <> uncertain_lane -> fin d0 = true /\ fin d1 = true /\ fin d2 = true /\
                          fin n0 = true /\ fin n1 = true /\ fin n2 = true).
Proof.
  intros d0 d1 d2 n0 n1 n2 s.
  destruct cpp_filter_constants as [F [N _]].
  destruct (Z.eq_dec s uncertain_lane) as [U|U].
  - split; [rewrite U; exact I | intros C; contradiction].
  - destruct (dot3_filter_lanes_twin d0 d1 d2 n0 n1 n2 _ F N U) as [Fm E].
    destruct (dot3_rounded_twin d0 d1 d2 n0 n1 n2 Fm) as [? [? [? [? [? [? _]]]]]].
    split; [| intros _; repeat split; assumption].
    unfold s. rewrite E, cpp_filter_den_relative. apply den_filter_lanes_sound.
Qed.

(** num = (p − o)·n from the rounded differences p_i ⊖ o_i ([two_diff(p_i, o_i).hi] in fast_path.hpp). *)
Theorem num_filter_twin_sound : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let s := dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b p0 o0)) (fst (two_diff_b p1 o1))
                                  (fst (two_diff_b p2 o2)) n0 n1 n2) Cpp.filter_num_relative in
  certifies (sign_from_Z s)
    ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2) /\
  (s <> uncertain_lane -> fin p0 = true /\ fin p1 = true /\ fin p2 = true /\ fin o0 = true /\
                          fin o1 = true /\ fin o2 = true /\ fin n0 = true /\ fin n1 = true /\ fin n2 = true).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 s.
  destruct cpp_filter_constants as [_ [_ [F N]]].
  destruct (Z.eq_dec s uncertain_lane) as [U|U].
  - split; [rewrite U; exact I | intros C; contradiction].
  - destruct (dot3_filter_lanes_twin _ _ _ n0 n1 n2 _ F N U) as [Fm E].
    destruct (dot3_rounded_twin _ _ _ n0 n1 n2 Fm) as [D0 [D1 [D2 [? [? [? _]]]]]].
    unfold two_diff_b, two_sum_b in D0, D1, D2. cbn [fst] in D0, D1, D2.
    destruct (fadd_inv _ _ D0) as [Fp0 [Fo0 V0]]. destruct (fadd_inv _ _ D1) as [Fp1 [Fo1 V1]].
    destruct (fadd_inv _ _ D2) as [Fp2 [Fo2 V2]].
    rewrite fneg_fin in Fo0, Fo1, Fo2. rewrite fneg_val in V0, V1, V2.
    split; [| intros _; repeat split; assumption].
    unfold s. rewrite E, cpp_filter_num_relative.
    unfold two_diff_b, two_sum_b. cbn [fst]. rewrite V0, V1, V2.
    apply num_filter_lanes_sound; apply binary64_B2R.
Qed.

(** ** dot3_compensated.hpp and enclosure.hpp *)

(** [EnclosureT]: hi, lo, radius. *)
Record EnclosureB := { hib : float; lob : float; radiusb : float }.

Definition enc_R (e : EnclosureB) : Enclosure :=
  {| hi := B2R (hib e); lo := B2R (lob e); radius := B2R (radiusb e) |}.

(** [compensated_dot3_from_low_parts(g, stage1)]: the sums shared by both forms. *)
Definition compensated_from_low_parts_b (g0 g1 g2 : float) (stage1 : Dot3B) : EnclosureB :=
  let s2 := two_sum_b (qb0 stage1) (qb1 stage1) in
  let s3 := two_sum_b (fst s2) (qb2 stage1) in
  let lo := fadd (fadd (fadd g0 g1) g2) (fadd (snd s2) (snd s3)) in
  let radius := fadd (fmul Cpp.compensated_relative (magnitudeb stage1)) Cpp.compensated_absolute in
  {| hib := fst s3; lob := lo; radiusb := radius |}.

(** [compensated_dot3(a, alpha, b, stage1)]: l_i = fma(a_i, b_i, −h_i), g_i = fma(α_i, b_i, l_i). *)
Definition compensated_dot3_b (a0 a1 a2 al0 al1 al2 b0 b1 b2 : float) (stage1 : Dot3B) : EnclosureB :=
  let l0 := ffma a0 b0 (fneg (qb0 stage1)) in let g0 := ffma al0 b0 l0 in
  let l1 := ffma a1 b1 (fneg (qb1 stage1)) in let g1 := ffma al1 b1 l1 in
  let l2 := ffma a2 b2 (fneg (qb2 stage1)) in let g2 := ffma al2 b2 l2 in
  compensated_from_low_parts_b g0 g1 g2 stage1.

(** [compensated_dot3_exact(a, b, stage1)]: the α = 0 form, g_i = l_i (den). *)
Definition compensated_dot3_exact_b (a0 a1 a2 b0 b1 b2 : float) (stage1 : Dot3B) : EnclosureB :=
  compensated_from_low_parts_b (ffma a0 b0 (fneg (qb0 stage1))) (ffma a1 b1 (fneg (qb1 stage1)))
    (ffma a2 b2 (fneg (qb2 stage1))) stage1.


(** [compensated_dot3_refined(a, alpha, b, stage1)]; [double tail = 0] is +0. *)
Definition compensated_dot3_refined_b (a0 a1 a2 al0 al1 al2 b0 b1 b2 : float) (stage1 : Dot3B) : EnclosureB :=
  let s2 := two_sum_b (qb0 stage1) (qb1 stage1) in
  let s3 := two_sum_b (fst s2) (qb2 stage1) in
  let l0 := ffma a0 b0 (fneg (qb0 stage1)) in let w0 := two_prod_b al0 b0 in
  let l1 := ffma a1 b1 (fneg (qb1 stage1)) in let w1 := two_prod_b al1 b1 in
  let l2 := ffma a2 b2 (fneg (qb2 stage1)) in let w2 := two_prod_b al2 b2 in
  let chain := two_sum_chain_b (snd s2) fzero (snd s3 :: l0 :: l1 :: l2 :: fst w0 :: fst w1 :: fst w2 :: nil) in
  let tail := fadd (fadd (fadd (snd chain) (snd w0)) (snd w1)) (snd w2) in
  let x := two_sum_b (fst s3) (fst chain) in
  let lo := fadd (snd x) tail in
  let radius := fadd (fadd (fmul Cpp.refined_relative (magnitudeb stage1))
                           (fmul Cpp.refined_low_relative (fabs lo))) Cpp.refined_absolute in
  {| hib := fst x; lob := lo; radiusb := radius |}.

(** [enclosure_sign_lanes(e)]: v = hi + lo, twice_radius = radius + radius,
    [sign_lanes(v > twice_radius, v < −twice_radius)]. *)
Definition enclosure_sign_lanes_b (e : EnclosureB) : Z :=
  let v := fadd (hib e) (lob e) in
  let twice_radius := fadd (radiusb e) (radiusb e) in
  sign_lanes (flt twice_radius v) (flt v (fneg twice_radius)).


(** The stage-1 fields the stage-2 twins read, as the model's. *)
Lemma dot3_fields : forall a0 a1 a2 b0 b1 b2,
  let r := dot3_rounded_b a0 a1 a2 b0 b1 b2 in
  let m := dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2) in
  dot3_R r = m ->
  B2R (qb0 r) = product0 m /\ B2R (qb1 r) = product1 m /\ B2R (qb2 r) = product2 m /\
  B2R (magnitudeb r) = magnitude m.
Proof. intros a0 a1 a2 b0 b1 b2 r m E. rewrite <- E. repeat split. Qed.

(** A finite hi, lo and radius mean a finite computation equal to the model's: every operation flows into
    one of them.  (The C++ tests no finiteness: these theorems take finite hi and lo as hypotheses, and
    PlaneStageTwoFinite.v proves them whenever the enclosure's sign is certain — not whenever m is finite: a
    TwoDiff low part can be NaN with finite inputs and a finite difference.) *)
Theorem compensated_dot3_twin : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  let e := compensated_dot3_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2) in
  fin (radiusb e) = true -> fin (hib e) = true -> fin (lob e) = true ->
  fin a0 = true /\ fin a1 = true /\ fin a2 = true /\ fin al0 = true /\ fin al1 = true /\ fin al2 = true /\
  fin b0 = true /\ fin b1 = true /\ fin b2 = true /\ fin (hib e) = true /\ fin (lob e) = true /\
  enc_R e = compensated_dot3 (B2R a0) (B2R a1) (B2R a2) (B2R al0) (B2R al1) (B2R al2) (B2R b0) (B2R b1) (B2R b2).
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 e Frad Fhi Flo. subst e.
  unfold compensated_dot3_b, compensated_from_low_parts_b in *. cbv zeta in *. cbn [hib lob radiusb] in *.
  set (r := dot3_rounded_b a0 a1 a2 b0 b1 b2) in *.
  assert (Fm : fin (magnitudeb r) = true) by (fin_down2; assumption).
  destruct (dot3_rounded_twin a0 a1 a2 b0 b1 b2 Fm) as [Fa0 [Fa1 [Fa2 [Fb0 [Fb1 [Fb2 [Fq0 [Fq1 [Fq2 [_ E]]]]]]]]]].
  fold r in Fq0, Fq1, Fq2, E.
  destruct (dot3_fields a0 a1 a2 b0 b1 b2 E) as [E0 [E1 [E2 Em]]]. fold r in E0, E1, E2, Em.
  clearbody r. cpp_fin. fin_down2.
  repeat split; try assumption.
  unfold enc_R, compensated_dot3, fma. cbv zeta. cbn [hib lob radiusb hi lo radius].
  to_model2. rewrite E0, E1, E2, Em. reflexivity.
Qed.

(** The α = 0 form (den), against PlaneCascade.v's [compensated_dot3_exact], which [compensated_dot3_exact_inputs]
    shows is [compensated_dot3] with α = 0. *)
Theorem compensated_dot3_exact_twin : forall a0 a1 a2 b0 b1 b2,
  let e := compensated_dot3_exact_b a0 a1 a2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2) in
  fin (radiusb e) = true -> fin (hib e) = true -> fin (lob e) = true ->
  fin a0 = true /\ fin a1 = true /\ fin a2 = true /\ fin b0 = true /\ fin b1 = true /\ fin b2 = true /\
  enc_R e = compensated_dot3 (B2R a0) (B2R a1) (B2R a2) 0 0 0 (B2R b0) (B2R b1) (B2R b2).
Proof.
  intros a0 a1 a2 b0 b1 b2 e Frad Fhi Flo. subst e. rewrite <- compensated_dot3_exact_inputs.
  unfold compensated_dot3_exact_b, compensated_from_low_parts_b in *. cbv zeta in *. cbn [hib lob radiusb] in *.
  set (r := dot3_rounded_b a0 a1 a2 b0 b1 b2) in *.
  assert (Fm : fin (magnitudeb r) = true) by (fin_down2; assumption).
  destruct (dot3_rounded_twin a0 a1 a2 b0 b1 b2 Fm) as [Fa0 [Fa1 [Fa2 [Fb0 [Fb1 [Fb2 [Fq0 [Fq1 [Fq2 [_ E]]]]]]]]]].
  fold r in Fq0, Fq1, Fq2, E.
  destruct (dot3_fields a0 a1 a2 b0 b1 b2 E) as [E0 [E1 [E2 Em]]]. fold r in E0, E1, E2, Em.
  clearbody r. cpp_fin. fin_down2.
  repeat split; try assumption.
  unfold enc_R, compensated_dot3_exact, fma. cbv zeta. cbn [hib lob radiusb hi lo radius].
  to_model2. rewrite E0, E1, E2, Em. reflexivity.
Qed.


Lemma Bsign_false_nonneg : forall x : float, Bsign x = false -> 0 <= B2R x.
Proof.
  intros [sx|sx| |sx mx ex Hx] S; simpl in S; try (simpl; lra).
  subst. simpl. apply F2R_ge_0. simpl. lia.
Qed.

Lemma Bsign_true_nonpos : forall x : float, Bsign x = true -> B2R x <= 0.
Proof.
  intros [sx|sx| |sx mx ex Hx] S; simpl in S; try (simpl; lra).
  subst. simpl. apply F2R_le_0. simpl. lia.
Qed.

Lemma flt_pinf_r : forall x, fin x = true -> flt x (B754_infinity false) = true.
Proof. intros [sx|sx| |sx mx ex Hx] F; try discriminate; destruct sx; reflexivity. Qed.
Lemma flt_pinf_l : forall y, flt (B754_infinity false) y = false.
Proof. intros [sy|[|]| |sy my ey Hy]; reflexivity. Qed.
Lemma flt_ninf_r : forall x, flt x (B754_infinity true) = false.
Proof. intros [sx|[|]| |[|] mx ex Hx]; reflexivity. Qed.
Lemma flt_ninf_l : forall y, fin y = true -> flt (B754_infinity true) y = true.
Proof. intros [sy|sy| |sy my ey Hy] F; try discriminate; destruct sy; reflexivity. Qed.

(** A certain enclosure sign means a finite radius (the radius is non-negative or NaN, so "twice the
    radius" is a bound [certifying_bound_finite] applies to). *)
Lemma enclosure_sign_radius_finite : forall e, nonneg (radiusb e) ->
  enclosure_sign_lanes_b e <> uncertain_lane -> fin (radiusb e) = true.
Proof.
  intros e N U. unfold enclosure_sign_lanes_b in U.
  assert (F : fin (fadd (radiusb e) (radiusb e)) = true).
  { apply (certifying_bound_finite _ (fadd (hib e) (lob e))); [now apply fadd_nonneg|].
    now apply sign_lanes_certain. }
  now destruct (fadd_fin _ _ F).
Qed.

(** Given finite hi and lo (which every producer's finite radius implies), the twin's certain decision is
    the model's.  When hi + lo overflows, the IEEE sum is ±inf and the model's sum is beyond ±2^1024: both
    are beyond twice the (finite) radius, on the same side. *)
Theorem enclosure_sign_twin : forall e, fin (hib e) = true -> fin (lob e) = true -> nonneg (radiusb e) ->
  enclosure_sign_lanes_b e <> uncertain_lane ->
  fin (radiusb e) = true /\ enclosure_sign_lanes_b e = enclosure_sign_lanes (enc_R e).
Proof.
  intros e Fh Fl N U.
  pose proof (enclosure_sign_radius_finite e N U) as Fr.
  split; [exact Fr|].
  unfold enclosure_sign_lanes_b, enclosure_sign_lanes, enc_R. cbn [hi lo radius].
  destruct (fadd_fwd _ _ Fr Fr ltac:(apply (Rle_lt_trans _ _ _ (Rle_refl _));
    unfold enclosure_sign_lanes_b in U;
    assert (Ft : fin (fadd (radiusb e) (radiusb e)) = true) by
      (apply (certifying_bound_finite _ (fadd (hib e) (lob e))); [now apply fadd_nonneg | now apply sign_lanes_certain]);
    rewrite <- (fadd_val _ _ Ft); apply B2R_lt_overflow)) as [Ft Vt].
  pose proof (Bplus_correct 53 1024 _ _ mode_NE (hib e) (lob e) Fh Fl) as C.
  fold (fadd (hib e) (lob e)) in C. rewrite RN_flocq in C.
  destruct (Rlt_bool_spec (Rabs (RN (B2R (hib e) + B2R (lob e)))) (bpow radix2 1024)) as [L|L].
  - destruct C as [Vv [Fv _]]. rewrite (flt_val _ _ Ft Fv), (flt_val _ _ Fv), fneg_val, Vt, Vv
      by (rewrite fneg_fin; exact Ft). reflexivity.
  - destruct C as [O S]. rewrite (overflow_sign _ _ O). rewrite <- Vt.
    set (T := fadd (radiusb e) (radiusb e)) in *.
    pose proof (B2R_lt_overflow T) as Tb. apply Rabs_lt_inv in Tb.
    destruct (Bsign (hib e)) eqn:Sh.
    + (* both negative: the sum is at most −2^1024 *)
      assert (Neg : RN (B2R (hib e) + B2R (lob e)) <= - bpow radix2 1024).
      { pose proof (Bsign_true_nonpos _ Sh). pose proof (Bsign_true_nonpos (lob e) (eq_sym S)).
        assert (RN (B2R (hib e) + B2R (lob e)) <= 0) by (rewrite <- RN_0; apply RN_le; lra).
        rewrite Rabs_left1 in L by assumption. lra. }
      rewrite flt_ninf_r, (flt_ninf_l _ (ltac:(rewrite fneg_fin; exact Ft))).
      rewrite (Rlt_bool_false (B2R T)) by lra. rewrite (Rlt_bool_true _ (- B2R T)) by lra. reflexivity.
    + assert (Pos : bpow radix2 1024 <= RN (B2R (hib e) + B2R (lob e))).
      { pose proof (Bsign_false_nonneg _ Sh). pose proof (Bsign_false_nonneg (lob e) (eq_sym S)).
        assert (0 <= RN (B2R (hib e) + B2R (lob e))) by (rewrite <- RN_0; apply RN_le; lra).
        rewrite Rabs_pos_eq in L by assumption. lra. }
      rewrite (flt_pinf_r _ Ft), flt_pinf_l.
      rewrite (Rlt_bool_true (B2R T)) by lra. rewrite (Rlt_bool_false _ (- B2R T)) by lra. reflexivity.
Qed.

(** The radii are "non-negative or NaN": sums and products of non-negative constants and magnitudes. *)
Lemma compensated_radius_nonneg : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  nonneg (radiusb (compensated_dot3_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2))).
Proof.
  intros. unfold compensated_dot3_b, compensated_from_low_parts_b, dot3_rounded_b. cbv zeta. cbn [radiusb magnitudeb].
  apply fadd_nonneg; [apply fmul_nonneg|]; try const_nonneg.
  apply fadd_nonneg; [apply fadd_nonneg|]; apply fabs_nonneg.
Qed.


(** ** End to end: the sign the first or second level of stage 2 certifies, for every bit pattern of the
    inputs, is the sign of the exact value (the calls of fast_path.hpp and ray_plane_stages.hpp: den with
    [exact_low_part] = {+0, +0, +0}, num with the rounded differences and their TwoDiff low parts). *)

Definition den_compensated_b (d0 d1 d2 n0 n1 n2 : float) : EnclosureB :=
  compensated_dot3_exact_b d0 d1 d2 n0 n1 n2 (dot3_rounded_b d0 d1 d2 n0 n1 n2).
Definition num_compensated_b (p0 p1 p2 o0 o1 o2 n0 n1 n2 : float) : EnclosureB :=
  let a0 := two_diff_b p0 o0 in let a1 := two_diff_b p1 o1 in let a2 := two_diff_b p2 o2 in
  compensated_dot3_b (fst a0) (fst a1) (fst a2) (snd a0) (snd a1) (snd a2) n0 n1 n2
    (dot3_rounded_b (fst a0) (fst a1) (fst a2) n0 n1 n2).
Definition den_refined_b (d0 d1 d2 n0 n1 n2 : float) : EnclosureB :=
  compensated_dot3_refined_b d0 d1 d2 fzero fzero fzero n0 n1 n2 (dot3_rounded_b d0 d1 d2 n0 n1 n2).
Definition num_refined_b (p0 p1 p2 o0 o1 o2 n0 n1 n2 : float) : EnclosureB :=
  let a0 := two_diff_b p0 o0 in let a1 := two_diff_b p1 o1 in let a2 := two_diff_b p2 o2 in
  compensated_dot3_refined_b (fst a0) (fst a1) (fst a2) (snd a0) (snd a1) (snd a2) n0 n1 n2
    (dot3_rounded_b (fst a0) (fst a1) (fst a2) n0 n1 n2).

(** A stage-2 sign that is certain implies a finite radius, hence a finite computation equal to the
    model's (the two theorems above), whose sign is sound ([enclosure_sign_sound]). *)
Lemma stage2_sign_twin : forall (e : EnclosureB) (V : R),
  nonneg (radiusb e) -> fin (hib e) = true -> fin (lob e) = true ->
  (fin (radiusb e) = true -> encloses (enc_R e) V) ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) V /\
  (enclosure_sign_lanes_b e <> uncertain_lane -> fin (radiusb e) = true).
Proof.
  intros e V N Fh Fl H. destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U].
  - split; [rewrite U; exact I | intros C; contradiction].
  - pose proof (enclosure_sign_radius_finite e N U) as Fr.
    pose proof (H Fr) as Enc.
    destruct (enclosure_sign_twin e Fh Fl N U) as [_ E].
    split; [| intros _; exact Fr].
    rewrite E. apply enclosure_sign_sound; [apply binary64_B2R .. | exact Enc].
Qed.

Lemma two_diff_b_parts : forall p o, fin (snd (two_diff_b p o)) = true ->
  fin p = true /\ fin o = true /\
  B2R (fst (two_diff_b p o)) = RN (B2R p - B2R o) /\ B2R (snd (two_diff_b p o)) = snd (two_diff (B2R p) (B2R o)).
Proof.
  intros p o H. unfold two_diff_b in *. destruct (two_sum_b_inv _ _ H) as [Fp [Fo [_ [E1 E2]]]].
  rewrite fneg_fin in Fo. rewrite fneg_val in E1, E2. repeat split; assumption.
Qed.

Lemma den_radius_nonneg : forall d0 d1 d2 n0 n1 n2, nonneg (radiusb (den_compensated_b d0 d1 d2 n0 n1 n2)).
Proof.
  intros. unfold den_compensated_b, compensated_dot3_exact_b, compensated_from_low_parts_b, dot3_rounded_b.
  cbv zeta. cbn [radiusb magnitudeb]. apply fadd_nonneg; [apply fmul_nonneg|]; try const_nonneg.
  apply fadd_nonneg; [apply fadd_nonneg|]; apply fabs_nonneg.
Qed.

Lemma num_radius_nonneg : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  nonneg (radiusb (num_compensated_b p0 p1 p2 o0 o1 o2 n0 n1 n2)).
Proof. intros. unfold num_compensated_b. apply compensated_radius_nonneg. Qed.

Lemma den_compensated_encloses_b : forall d0 d1 d2 n0 n1 n2,
  let e := den_compensated_b d0 d1 d2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  encloses (enc_R e) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2).
Proof.
  intros d0 d1 d2 n0 n1 n2 e Fh Fl Fr.
  destruct (compensated_dot3_exact_twin _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [? [? [? E]]]]]].
  unfold e, den_compensated_b. rewrite E. apply compensated_den_enclosure; apply binary64_B2R.
Qed.

Lemma num_compensated_encloses_b : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  let e := num_compensated_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  encloses (enc_R e) ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 e Fh Fl Fr.
  destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [A0 [A1 [A2 [? [? [? [_ [_ E]]]]]]]]]]].
  destruct (two_diff_b_parts _ _ A0) as [? [? [X0 Y0]]]. destruct (two_diff_b_parts _ _ A1) as [? [? [X1 Y1]]].
  destruct (two_diff_b_parts _ _ A2) as [? [? [X2 Y2]]].
  unfold e, num_compensated_b. cbv zeta. rewrite E, X0, X1, X2, Y0, Y1, Y2.
  apply compensated_num_enclosure; apply binary64_B2R.
Qed.

(** Every end-to-end stage-2 theorem (first level here, second level in PlaneRefinedTwins.v) has this shape:
    the radius is non-negative or NaN, and a finite computation encloses V. *)
Lemma stage2_twin_sound_gen : forall (e : EnclosureB) (V : R), nonneg (radiusb e) ->
  (fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true -> encloses (enc_R e) V) ->
  fin (hib e) = true -> fin (lob e) = true ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) V /\
  (enclosure_sign_lanes_b e <> uncertain_lane -> fin (radiusb e) = true).
Proof. intros e V N H Fh Fl. exact (stage2_sign_twin e V N Fh Fl (H Fh Fl)). Qed.

Theorem den_compensated_twin_sound : forall d0 d1 d2 n0 n1 n2 : float,
  let e := den_compensated_b d0 d1 d2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) /\
  (enclosure_sign_lanes_b e <> uncertain_lane -> fin (radiusb e) = true).
Proof.
  intros. apply stage2_twin_sound_gen; [apply den_radius_nonneg | apply den_compensated_encloses_b | assumption ..].
Qed.

Theorem num_compensated_twin_sound : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let e := num_compensated_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e))
    ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2) /\
  (enclosure_sign_lanes_b e <> uncertain_lane -> fin (radiusb e) = true).
Proof.
  intros. apply stage2_twin_sound_gen; [apply num_radius_nonneg | apply num_compensated_encloses_b | assumption ..].
Qed.



(** ** expansion.hpp: [expansion_tail_enclosure] *)

(** The C++ loop: [s = two_sum(q, e_i); q = s.hi; lo += s.lo; magnitude += |s.lo|]. *)
Fixpoint tail_loop_b (q lo magnitude : float) (rest : list float) : float * float * float :=
  match rest with
  | nil => (q, lo, magnitude)
  | e :: rest' => let s := two_sum_b q e in
      tail_loop_b (fst s) (fadd lo (snd s)) (fadd magnitude (fabs (snd s))) rest'
  end.

(** [double lo = 0, magnitude = 0]; E = magnitude·2^-48 + 2μ. *)
Definition expansion_tail_enclosure_b (e0 : float) (rest : list float) : EnclosureB :=
  let '(q, lo, magnitude) := tail_loop_b e0 fzero fzero rest in
  {| hib := q; lob := lo; radiusb := fadd (fmul magnitude Cpp.tail_sum_relative) Cpp.tail_sum_absolute |}.

Lemma tail_loop_b_mag : forall rest q lo mag,
  fin (snd (tail_loop_b q lo mag rest)) = true -> fin mag = true.
Proof.
  induction rest as [|e rest IH]; intros q lo mag H; [exact H|].
  cbn [tail_loop_b] in H. apply IH in H. now destruct (fadd_fin _ _ H).
Qed.

(** The loop invariant: lo is dominated by magnitude (|lo| ≤ m, rounding is monotone), so a finite final
    magnitude means every step is finite and the model's. *)
Lemma tail_loop_b_twin : forall rest q lo mag,
  fin q = true -> fin lo = true -> Rabs (B2R lo) <= B2R mag ->
  let '(q', lo', mag') := tail_loop_b q lo mag rest in
  fin mag' = true ->
  Forall (fun x => fin x = true) rest /\ fin q' = true /\ fin lo' = true /\
  tail_loop (B2R q) (B2R lo) (B2R mag) (map B2R rest) = (B2R q', B2R lo', B2R mag').
Proof.
  induction rest as [|e rest IH]; intros q lo mag Fq Flo D.
  - cbn. intros _. auto.
  - cbn [tail_loop_b tail_loop map].
    pose proof (tail_loop_b_mag rest (fst (two_sum_b q e)) (fadd lo (snd (two_sum_b q e)))
                  (fadd mag (fabs (snd (two_sum_b q e))))) as M.
    destruct (tail_loop_b (fst (two_sum_b q e)) (fadd lo (snd (two_sum_b q e)))
                (fadd mag (fabs (snd (two_sum_b q e)))) rest) as [[q' lo'] mag'] eqn:T.
    intros Fm'. specialize (M Fm').
    destruct (fadd_inv _ _ M) as [Fmag [Fr Vm]]. rewrite fabs_fin in Fr.
    destruct (two_sum_b_inv q e Fr) as [_ [Fe [Fs [Es Er]]]].
    assert (Flo1 : fin (fadd lo (snd (two_sum_b q e))) = true /\
                   B2R (fadd lo (snd (two_sum_b q e))) = RN (B2R lo + B2R (snd (two_sum_b q e)))).
    { apply (fadd_dominated _ _ (fadd mag (fabs (snd (two_sum_b q e))))); try assumption.
      rewrite Vm, fabs_val, <- RN_abs. apply RN_le.
      eapply Rle_trans; [apply Rabs_triang | lra]. }
    destruct Flo1 as [Flo1 Vlo1].
    pose proof (IH _ _ (fadd mag (fabs (snd (two_sum_b q e)))) Fs Flo1) as IH'.
    assert (D' : Rabs (B2R (fadd lo (snd (two_sum_b q e)))) <= B2R (fadd mag (fabs (snd (two_sum_b q e))))).
    { rewrite Vlo1, Vm, fabs_val, <- RN_abs. apply RN_le. eapply Rle_trans; [apply Rabs_triang | lra]. }
    specialize (IH' D'). rewrite T in IH'. destruct (IH' Fm') as [Fr' [Fq' [Flo' E]]].
    repeat split; auto.
    rewrite <- E, Es, Vlo1, Vm, fabs_val, Er. reflexivity.
Qed.

(** A finite hi and radius mean a finite computation: the twin's enclosure is the model's, which
    [tail_sum_enclosure] proves encloses the exact sum of the components. *)
Theorem expansion_tail_enclosure_twin : forall e0 rest,
  let E := expansion_tail_enclosure_b e0 rest in
  fin (hib E) = true -> fin (radiusb E) = true ->
  Forall (fun x => fin x = true) (e0 :: rest) /\ fin (lob E) = true /\
  enc_R E = expansion_tail_enclosure (B2R e0) (map B2R rest).
Proof.
  intros e0 rest E Fh Fr. subst E. unfold expansion_tail_enclosure_b, expansion_tail_enclosure in *.
  assert (F0 : fin e0 = true \/ rest <> nil).
  { destruct rest; [left | right; discriminate]. cbn in Fh. exact Fh. }
  pose proof (tail_loop_b_twin rest e0 fzero fzero) as T.
  destruct (tail_loop_b e0 fzero fzero rest) as [[q lo] mag] eqn:L.
  cbn [hib lob radiusb] in *. cpp_fin. fin_down.
  assert (Fe0 : fin e0 = true).
  { destruct F0 as [F0|N]; [exact F0|].
    destruct rest as [|e rest]; [contradiction|].
    cbn [tail_loop_b] in L. pose proof (tail_loop_b_mag rest (fst (two_sum_b e0 e))
      (fadd fzero (snd (two_sum_b e0 e))) (fadd fzero (fabs (snd (two_sum_b e0 e))))) as M.
    rewrite L in M. specialize (M ltac:(assumption)).
    destruct (fadd_fin _ _ M) as [_ Fa]. rewrite fabs_fin in Fa.
    now destruct (two_sum_b_inv _ _ Fa). }
  destruct (T Fe0 eq_refl ltac:(change (B2R fzero) with 0; rewrite Rabs_R0; right; reflexivity) ltac:(assumption))
    as [Fr' [Fq [Flo E]]].
  change (B2R fzero) with 0 in E.
  repeat split; try assumption; [constructor; assumption|].
  rewrite E. unfold enc_R. cbn [hib lob radiusb]. to_model. reflexivity.
Qed.
