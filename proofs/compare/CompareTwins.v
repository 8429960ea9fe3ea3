(** * Twins of the nearest-hit comparison (kernel/src/nearest/compare_quotients.hpp) and of the
    per-query stage results it consumes (ray_plane_stages.hpp), tied to CompareQuotients.v.

    - [filter_enclosure_b], [compare_propagated_error_b], [compare_quotients_filter_b]
      ([compare_quotients_filter_twin]);
    - [compare_quotients_compensated_b] ([compare_quotients_compensated_twin]);
    - end to end, for every bit pattern of a ray and two planes, as nearest_hit.cpp's
      [compare_hit_distances] calls them: PlaneStageTwoFinite.v's [hit_order_compensated_twin_sound_total]
      (stage 2) and NearestTwins.v's [compare_hit_distances_twin_correct] (the whole comparison): a
      certain sign is the sign of Δ = num_a·den_b − num_b·den_a of the exact values. *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins.
Open Scope R_scope.

(** [RoundedEnclosure]: value, radius. *)
Record RoundedEnclosureB := { rvalueb : float; rradiusb : float }.

Definition renc_R (e : RoundedEnclosureB) : RoundedEnclosure :=
  {| rounded_value := B2R (rvalueb e); rounded_radius := B2R (rradiusb e) |}.

(** [filter_enclosure(r, C)]: {value, C·m + 3μ}. *)
Definition filter_enclosure_b (r : Dot3B) (C : float) : RoundedEnclosureB :=
  {| rvalueb := valueb r; rradiusb := fadd (fmul C (magnitudeb r)) Cpp.filter_absolute |}.

(** [compare_propagated_error(x1, e1, y1, f1, x2, e2, y2, f2)]. *)
Definition compare_propagated_error_b (x1 e1 y1 f1 x2 e2 y2 f2 : float) : float :=
  fadd (fadd (fmul (fabs x1) f2) (fmul e1 (fadd (fabs y2) f2)))
       (fadd (fmul (fabs x2) f1) (fmul e2 (fadd (fabs y1) f1))).

(** [compare_quotients_filter(n1, d1, n2, d2)]. *)
Definition compare_quotients_filter_b (n1 d1 n2 d2 : RoundedEnclosureB) : sign :=
  let p := fmul (rvalueb n1) (rvalueb d2) in
  let q := fmul (rvalueb n2) (rvalueb d1) in
  let delta := fsub p q in
  let magnitude := fadd (fabs p) (fabs q) in
  let propagated := compare_propagated_error_b (rvalueb n1) (rradiusb n1) (rvalueb d1) (rradiusb d1)
                      (rvalueb n2) (rradiusb n2) (rvalueb d2) (rradiusb d2) in
  let bound := fadd (fadd (fmul Cpp.compare_filter_relative magnitude)
                          (fmul Cpp.compare_propagation_factor propagated)) Cpp.compare_absolute in
  if flt bound delta then Positive else if flt delta (fneg bound) then Negative else Uncertain.

(** [compare_quotients_compensated(n1, d1, n2, d2)] (no finiteness test: the radius is not finite when
    an input or M is not). *)
Definition compare_quotients_compensated_b (n1 d1 n2 d2 : EnclosureB) : EnclosureB :=
  let a1 := two_sum_b (hib n1) (lob n1) in
  let b1 := two_sum_b (hib d1) (lob d1) in
  let a2 := two_sum_b (hib n2) (lob n2) in
  let b2 := two_sum_b (hib d2) (lob d2) in
  let p := two_prod_b (fst a1) (fst b2) in
  let q := two_prod_b (fst a2) (fst b1) in
  let c1 := ffma (fst a1) (snd b2) (fmul (snd a1) (fst b2)) in
  let c2 := ffma (fst a2) (snd b1) (fmul (snd a2) (fst b1)) in
  let s := two_sum_b (fst p) (fneg (fst q)) in
  let lo := fadd (fadd (fsub (snd p) (snd q)) (fsub c1 c2)) (snd s) in
  let magnitude := fadd (fabs (fst p)) (fabs (fst q)) in
  let propagated := compare_propagated_error_b (fst a1) (radiusb n1) (fst b1) (radiusb d1)
                      (fst a2) (radiusb n2) (fst b2) (radiusb d2) in
  let radius := fadd (fadd (fmul Cpp.compare_compensated_relative magnitude)
                           (fmul Cpp.compare_propagation_factor propagated)) Cpp.compare_absolute in
  {| hib := fst s; lob := lo; radiusb := radius |}.

Lemma propagated_nonneg_b : forall x1 e1 y1 f1 x2 e2 y2 f2,
  nonneg e1 -> nonneg f1 -> nonneg e2 -> nonneg f2 ->
  nonneg (compare_propagated_error_b x1 e1 y1 f1 x2 e2 y2 f2).
Proof.
  intros. unfold compare_propagated_error_b.
  repeat first [apply fadd_nonneg | apply fmul_nonneg | apply fabs_nonneg | assumption].
Qed.

(** A certain order of two quotients (radii non-negative or NaN, as [filter_enclosure] makes them) means a
    finite bound, hence finite inputs and a finite computation: the model's decision. *)
Theorem compare_quotients_filter_twin : forall n1 d1 n2 d2,
  nonneg (rradiusb n1) -> nonneg (rradiusb d1) -> nonneg (rradiusb n2) -> nonneg (rradiusb d2) ->
  compare_quotients_filter_b n1 d1 n2 d2 <> Uncertain ->
  fin (rvalueb n1) = true /\ fin (rradiusb n1) = true /\ fin (rvalueb d1) = true /\ fin (rradiusb d1) = true /\
  fin (rvalueb n2) = true /\ fin (rradiusb n2) = true /\ fin (rvalueb d2) = true /\ fin (rradiusb d2) = true /\
  compare_quotients_filter_b n1 d1 n2 d2 = compare_quotients_filter (renc_R n1) (renc_R d1) (renc_R n2) (renc_R d2).
Proof.
  intros [x1 e1] [y1 f1] [x2 e2] [y2 f2] N1 M1 N2 M2 U. cbn [rradiusb rvalueb] in *.
  unfold compare_quotients_filter_b in *. cbn [rradiusb rvalueb] in *.
  set (bound := fadd (fadd (fmul Cpp.compare_filter_relative (fadd (fabs (fmul x1 y2)) (fabs (fmul x2 y1))))
                  (fmul Cpp.compare_propagation_factor (compare_propagated_error_b x1 e1 y1 f1 x2 e2 y2 f2)))
                  Cpp.compare_absolute) in *.
  assert (NB : nonneg bound).
  { unfold bound. apply fadd_nonneg; [apply fadd_nonneg; apply fmul_nonneg|]; try const_nonneg.
    - apply fadd_nonneg; apply fabs_nonneg.
    - now apply propagated_nonneg_b. }
  assert (FB : fin bound = true).
  { apply (certifying_bound_finite bound (fsub (fmul x1 y2) (fmul x2 y1)) NB).
    destruct (flt bound (fsub (fmul x1 y2) (fmul x2 y1))); [now left|].
    destruct (flt (fsub (fmul x1 y2) (fmul x2 y1)) (fneg bound)); [now right | now elim U]. }
  unfold bound, compare_propagated_error_b in FB. cpp_fin. fin_down.
  (* δ is dominated by M = |P| + |Q| *)
  assert (Fd : fin (fsub (fmul x1 y2) (fmul x2 y1)) = true).
  { assert (FP : fin (fmul x1 y2) = true) by assumption. assert (FQ : fin (fmul x2 y1) = true) by assumption.
    assert (FM : fin (fadd (fabs (fmul x1 y2)) (fabs (fmul x2 y1))) = true) by assumption.
    apply (fsub_fwd _ _ FP FQ).
    eapply Rle_lt_trans; [| apply (B2R_lt_overflow (fadd (fabs (fmul x1 y2)) (fabs (fmul x2 y1))))].
    rewrite (fadd_val _ _ FM), !fabs_val, <- !RN_abs. apply RN_le.
    rewrite (Rabs_pos_eq (Rabs _ + Rabs _)) by
      (pose proof (Rabs_pos (B2R (fmul x1 y2))); pose proof (Rabs_pos (B2R (fmul x2 y1))); lra).
    unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  repeat split; try assumption.
  unfold compare_quotients_filter, renc_R, compare_propagated_error. cbn [rounded_value rounded_radius].
  fold bound. unfold bound, compare_propagated_error_b. to_model. reflexivity.
Qed.

(** The radius, hi and lo being finite, every operation is finite and the model's. *)
Theorem compare_quotients_compensated_twin : forall n1 d1 n2 d2,
  let e := compare_quotients_compensated_b n1 d1 n2 d2 in
  fin (radiusb e) = true -> fin (hib e) = true -> fin (lob e) = true ->
  fin (hib n1) = true /\ fin (lob n1) = true /\ fin (radiusb n1) = true /\
  fin (hib d1) = true /\ fin (lob d1) = true /\ fin (radiusb d1) = true /\
  fin (hib n2) = true /\ fin (lob n2) = true /\ fin (radiusb n2) = true /\
  fin (hib d2) = true /\ fin (lob d2) = true /\ fin (radiusb d2) = true /\
  fin (hib e) = true /\ fin (lob e) = true /\
  enc_R e = compare_quotients_compensated (enc_R n1) (enc_R d1) (enc_R n2) (enc_R d2).
Proof.
  intros [hn1 ln1 e1] [hd1 ld1 f1] [hn2 ln2 e2] [hd2 ld2 f2] e H Fs Flo. subst e.
  unfold compare_quotients_compensated_b in *. cbv zeta in *. cbn [hib lob radiusb] in *.
  unfold compare_propagated_error_b in H. cpp_fin. fin_down2.
  repeat split; try assumption.
  unfold enc_R, compare_quotients_compensated, compare_propagated_error, compare_propagated_error_b, fma.
  cbv zeta.
  cbn [hib lob radiusb hi lo radius]. cbv iota. to_model2. reflexivity.
Qed.
