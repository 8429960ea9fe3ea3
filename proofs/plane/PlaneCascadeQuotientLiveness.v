(** * The ray–plane cascade's t is decided by stage 2 on a class (issue 16: liveness at the cascade level).

    PlaneCascadeTwins.v's [certified_quotient_b] (plane/ray_plane_cascade.cpp's [certified_quotient], run by
    [intersect_cascade] / the public [intersect] and [intersect_traced] past the fast path) rounds t by
    [round_quotient(num, prepare_divisor(den))] on the first level of stage 2 ([num2_b], [den2_b]:
    [num_compensated_b], [den_compensated_b]), then on the second level, then on stage 3's tail enclosures,
    else leaves it to the exact stage.  QuotientLivenessTwin.v's [round_quotient_live_b] says when the
    rounding certifies.  Here its consequence for the cascade:

    - [cascade_quotient_live_b]: when the first-level enclosures of the query satisfy
      [round_quotient_live_b]'s class, [certified_quotient_b] answers at the first level of stage 2
      (Some (q, StCompensated), q the first level's rounding: neither the second level, nor stage 3, nor the
      exact stage), with q finite, q = RN(X/Y) for the enclosures' heads X, Y, and q = RN(num/den) for the
      query's exact num = (p − o)·n, den = d·n;
    - [intersect_traced_live_b]: then every answer of [intersect_traced_b] with a t has it rounded by stage 2
      (TRounded q StCompensated, or +0 / NaN where the cascade does not divide), never [TExact];
    - [cascade_quotient_live_third]: the query o = 0, d = (3, 0, 0), p = n = (1, 0, 0) (t = 1/3) is in the
      class (its enclosures' values read from the twin by [vm_compute], the class shown by real arithmetic),
      so the theorem is not vacuous; [intersect_traced_third] shows by [vm_compute] that there the relation is
      decided by stage 1 (the filter) and t by stage 2: the ray–plane cascade has no stage-1 quotient, the
      first level of stage 2 is the first stage that can round t.

    The class is stated on the first-level enclosures (hi, lo, radius of [num2_b] and [den2_b]), not yet on
    the query's own inputs; what that needs is in proofs/README.md, "What remains". *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification QuotientRounding PlaneCascade FloatCore
  ConstantsCpp PlaneTwins Expansions PlaneQueryTwins PlaneRefinedTwins PlaneCascadeTwins PlaneLiveness QuotientLiveness QuotientLivenessTwin.
Open Scope R_scope.

(** [certified_quotient_b] when its first branch certifies (an equation of the definition, without unfolding
    the twins it calls). *)
Lemma certified_quotient_b_first : forall o d p n : Vec3B,
  snd (round_quotient_b (num2_b o p n) (prepare_divisor_b (den2_b d n))) = true ->
  certified_quotient_b o d p n = Some (fst (round_quotient_b (num2_b o p n) (prepare_divisor_b (den2_b d n))), StCompensated).
Proof. intros o d p n H. unfold certified_quotient_b. cbv zeta. rewrite H. reflexivity. Qed.

(** ** Main theorem: on [round_quotient_live_b]'s class for the first-level enclosures, the cascade rounds t at
    the first level of stage 2, to RN(num/den). *)
Theorem cascade_quotient_live_b : forall (o d p n : Vec3B) (num den : EnclosureB),
  num = num2_b o p n -> den = den2_b d n ->
  quotient_live_class num den ->
  let q := fst (round_quotient_b num (prepare_divisor_b den)) in
  certified_quotient_b o d p n = Some (q, StCompensated) /\ fin q = true /\ B2R q = RN (rq_quotient num den) /\
  B2R q = RN (ray_num (vec_R o) (vec_R p) (vec_R n) / ray_den (vec_R d) (vec_R n)) /\
  ray_den (vec_R d) (vec_R n) <> 0.
Proof.
  intros o d p n num den En Ed L q. destruct (round_quotient_live_b num den L) as [C [F T]].
  fold q in F, T.
  assert (Q : certified_quotient_b o d p n = Some (q, StCompensated)).
  { unfold q. rewrite En, Ed in *. apply certified_quotient_b_first. exact C. }
  destruct (certified_quotient_twin_sound o d p n q StCompensated Q) as [Dnz [_ S]].
  repeat split; assumption.
Qed.

(** [intersect_cascade_b]'s t, given [certified_quotient_b]'s answer (the control flow only). *)
Lemma intersect_cascade_t : forall o d p n q, certified_quotient_b o d p n = Some (q, StCompensated) ->
  forall r st tt, intersect_cascade_b o d p n = CDecided r st tt ->
  tt = TNaN \/ tt = TZero \/ tt = TRounded q StCompensated.
Proof.
  intros o d p n q Q r st tt.
  unfold intersect_cascade_b.
  destruct (certified_signs_b o d p n) as [[ns ds] st0].
  destruct st0; [| | | discriminate];
    destruct (relation_from_signs (sign_to_Z ns) (sign_to_Z ds)); destruct ns; try rewrite Q;
    intros E; injection E; intros Et _ _; subst tt;
    first [left; reflexivity | right; left; reflexivity | right; right; reflexivity].
Qed.

(** The answer of the public entry point's twin: any t it gives is stage 2's rounding, RN(num/den) — never the
    exact stage's ([TExact]) nor stage 3's. *)
Corollary intersect_traced_live_b : forall (o d p n : Vec3B) (num den : EnclosureB),
  num = num2_b o p n -> den = den2_b d n ->
  quotient_live_class num den ->
  forall r st tt, intersect_traced_b o d p n = CDecided r st tt ->
  tt = TNaN \/ tt = TZero \/
  (tt = TRounded (fst (round_quotient_b num (prepare_divisor_b den))) StCompensated /\
   B2R (fst (round_quotient_b num (prepare_divisor_b den))) =
     RN (ray_num (vec_R o) (vec_R p) (vec_R n) / ray_den (vec_R d) (vec_R n))).
Proof.
  intros o d p n num den En Ed L r st tt.
  destruct (cascade_quotient_live_b o d p n num den En Ed L) as [Q [_ [_ [S _]]]].
  unfold intersect_traced_b. destruct (validate_b o d p n); [discriminate|].
  intros E. destruct (intersect_cascade_t o d p n _ Q r st tt E) as [H | [H | H]]; auto.
Qed.

(** ** Not vacuous: the query o = 0, d = (3, 0, 0), p = n = (1, 0, 0) (num = 1, den = 3, t = 1/3). *)
Definition one_b : float := of_bits 4607182418800017408.    (* 1.0 *)
Definition three_b : float := of_bits 4613937818241073152.  (* 3.0 *)
Definition third_o : Vec3B := V3 fzero fzero fzero.
Definition third_d : Vec3B := V3 three_b fzero fzero.
Definition third_p : Vec3B := V3 one_b fzero fzero.
Definition third_n : Vec3B := V3 one_b fzero fzero.

(** The twin's answer there, computed (summarized to bits: [vm_compute] of the floats' proof fields is slow):
    the relation (hit) by stage 1, t = RN(1/3) (bits 0x3fd5555555555555) by stage 2. *)
Definition answer_summary (a : cascade_answer) : option (relation * stage * Z * stage) :=
  match a with CDecided r s (TRounded t s') => Some (r, s, to_bits t, s') | _ => None end.

Lemma intersect_traced_third :
  answer_summary (intersect_traced_b third_o third_d third_p third_n) =
    Some (Hit, StFilter, 4599676419421066581%Z, StCompensated).
Proof. vm_compute. reflexivity. Qed.

(** [vval c]: B2R c as IZR m · 2^e for a twin term c, m and e by [vm_compute] (FloatCore.v's [float_value]
    would check them by the kernel's lazy reduction, minutes on a twin). *)
Ltac vval c := rewrite (B2R_mant_expo c);
  let m := eval vm_compute in (mant c) in
  let e := eval vm_compute in (expo c) in
  replace (mant c) with m by (vm_compute; reflexivity); replace (expo c) with e by (vm_compute; reflexivity);
  pow_vals.

(** The query is in [cascade_quotient_live_b]'s class: the first-level enclosures are num = (1, 0, 2^-101) and
    den = (3, 0, 3·2^-101) (read from the twin), RN(1/3) is 2^-54/3 below 1/3 with half_gap 2^-55, and
    2^-54/3 + (1 + 2^-8)·(2^-101 + 2^-101)/3 + 2^-97/3 < 2^-55.  The theorem, not the computation, gives the
    answer: stage 2's t, RN(num/den). *)
Lemma cascade_quotient_live_third :
  let q := fst (round_quotient_b (num2_b third_o third_p third_n) (prepare_divisor_b (den2_b third_d third_n))) in
  certified_quotient_b third_o third_d third_p third_n = Some (q, StCompensated) /\ fin q = true /\
  B2R q = RN (1 / 3).
Proof.
  intros q.
  assert (Vnh : B2R (hib (num2_b third_o third_p third_n)) = 1) by (vval (hib (num2_b third_o third_p third_n)); lra).
  assert (Vnl : B2R (lob (num2_b third_o third_p third_n)) = 0) by (vval (lob (num2_b third_o third_p third_n)); lra).
  assert (Vnr : B2R (radiusb (num2_b third_o third_p third_n)) = / 2535301200456458802993406410752)
    by (vval (radiusb (num2_b third_o third_p third_n)); lra).
  assert (Vdh : B2R (hib (den2_b third_d third_n)) = 3) by (vval (hib (den2_b third_d third_n)); lra).
  assert (Vdl : B2R (lob (den2_b third_d third_n)) = 0) by (vval (lob (den2_b third_d third_n)); lra).
  assert (Vdr : B2R (radiusb (den2_b third_d third_n)) = 3 / 2535301200456458802993406410752)
    by (vval (radiusb (den2_b third_d third_n)); lra).
  destruct rn_third as [RQ3 HG3].
  assert (B : forall x, Rabs x <= 4 -> Rabs x <= bpow radix2 1000).
  { intros x Hx. eapply Rle_trans; [exact Hx|]. change 4 with (bpow radix2 2). apply bpow_le. lia. }
  destruct (small_in_range 1) as [GX _]; [rewrite Rabs_R1; simpl bpow; lra|].
  destruct (small_in_range 3) as [_ [GY _]]; [rewrite Rabs_pos_eq by lra; simpl bpow; lra|].
  destruct (small_in_range (1 / 3)) as [GQ1 [_ GQ2]]; [rewrite Rabs_pos_eq by lra; simpl bpow; lra|].
  assert (XY : (B2R (hib (num2_b third_o third_p third_n)) + B2R (lob (num2_b third_o third_p third_n))) /
          (B2R (hib (den2_b third_d third_n)) + B2R (lob (den2_b third_d third_n))) = 1 / 3)
    by (rewrite Vnh, Vnl, Vdh, Vdl; field).
  assert (L : quotient_live_class (num2_b third_o third_p third_n) (den2_b third_d third_n)).
  { unfold quotient_live_class, rq_quotient, rq_center. rewrite XY, Vnr, Vdr, Vnh, Vnl, Vdh, Vdl, !Rplus_0_r.
    do 6 (split; [vm_compute; reflexivity|]).
    split; [apply B; rewrite Rabs_R1; lra|]. split; [apply B; rewrite Rabs_R0; lra|].
    split; [apply B; rewrite Rabs_pos_eq; lra|]. split; [apply B; rewrite Rabs_R0; lra|].
    split; [lra|]. split; [lra|]. split; [exact GY|]. split; [exact GX|]. split; [split; assumption|].
    rewrite HG3, RQ3, (Rabs_pos_eq 3), (Rabs_pos_eq (1 / 3)) by lra. rewrite Rabs_pos_eq by lra. lra. }
  destruct (cascade_quotient_live_b third_o third_d third_p third_n _ _ eq_refl eq_refl L) as [Q [F [T _]]].
  unfold rq_quotient, rq_center in T. rewrite XY in T.
  split; [exact Q | split; [exact F | exact T]].
Qed.
