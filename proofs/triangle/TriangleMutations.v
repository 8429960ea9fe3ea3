(** * The two triangle mutations the mutation check reports as unobservable (proofs/mutation/run.py's
    [UNOBSERVABLE]), on the twin of fast_triangle_intersection (TriangleIntersectTwins.v).

    [fast_intersection_mut_b enc Cden den_in_filter] is [fast_intersection_tri_b] (TriangleIntersectTwins.v) with
    the enclosure routine [enc], den's stage-1 constant [Cden] and whether the stage label [by_filter] reads den's
    filter sign as parameters ([fast_intersection_mut_original]: with [det3_enclosure_b], den's constant and
    [true] it is the twin, by [reflexivity]).  The mutated twins (the third, [by_filter] without den's sign, is
    TriangleDenCertain.v's [fast_intersection_by_filter_den_b]):
    - [fast_intersection_call_site_den_b] (mutation [tri_call_site_den]): den filtered with π's constant;
    - [fast_intersection_drop_guard_b] (mutation [tri_drop_guard]): [det3_enclosure_noguard_b], the radius
      kept finite when only |h| ≤ largest finite holds.

    Theorems, for every 64-bit pattern of every input:
    - [den_filter_constant_monotone]: where the filter certifies with den's constant (10u) it certifies the same
      sign with π's (8u) (the bound is monotone in the constant);
      [tri_call_site_den_same_unless_between]: the mutated twin's answer is the twin's unless den's stage-1 view
      lies strictly between the two bounds (certain with 8u, uncertain with 10u);
    - [drop_guard_consumers_agree]: without the guard, an enclosure gives the same sign ([enclosure_sign]) and the
      same [round_quotient] results (as numerator and as divisor) unless h is finite, l is ±inf and
      (K ⊗ m) ⊕ A is finite ([no_infinite_low]); [tri_drop_guard_same_unless_infinite_low]: the mutated twin's
      answer is the twin's whenever the five stage-2 terms (πa, πb, πc, num, den) satisfy [no_infinite_low].

    Not proved here (proofs/README.md, "What remains"): that a query whose den view lies between the two bounds
    gets no answer (stage 2 cannot round a quotient there), and that a stage-2 term never has a finite h, an
    infinite l and a finite magnitude (|l| stays below a few u·m). *)

From Coq Require Import Reals Lra ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneClassification FloatCore ConstantsCpp PlaneTwins PlaneQueryTwins TriangleRule TriangleTwins
  TriangleCascadeTwins TriangleIntersectTwins.

(** ** The twin with its enclosure routine and den's constant as parameters *)

(** The part after the stage-2 lanes, from the signs and quotients it reads: the five filter signs, the five
    enclosure signs, the four quotients. *)
Definition fast_intersection_core (den_in_filter want_t want_u : bool) (fa fb fc fn fd ga gb gc gn gd : Z)
    (qa qb qc qn : float * bool) : option TAnswerB :=
  let sa := first_certain_lanes_b fa ga in let sb := first_certain_lanes_b fb gb in
  let sc := first_certain_lanes_b fc gc in let sn := first_certain_lanes_b fn gn in
  let sd := first_certain_lanes_b fd gd in
  if negb (certain_lane sa && certain_lane sb && certain_lane sc && certain_lane sd)%bool then None else
  match decide_nonzero_b sa sb sc sd sn with
  | None => None
  | Some cl =>
    if (want_t && negb (certain_lane sn))%bool then None else
    if negb ((negb want_t || snd qn) && (negb want_u || (snd qa && snd qb && snd qc)))%bool then None else
    let by_filter := (certain_lane fa && certain_lane fb && certain_lane fc &&
                      (negb den_in_filter || certain_lane fd) && (is_outside (tloc cl) || certain_lane fn))%bool in
    Some (TAB cl (if want_t then fst qn else fnan) (if want_u then fst qa else fnan)
              (if want_u then fst qb else fnan) (if want_u then fst qc else fnan)
              (if by_filter then 0 else 1) 1)
  end.

Lemma fast_intersection_core_congr : forall den_in_filter want_t want_u fa fb fc fn fd fd' ga gb gc gn gd ga' gb' gc' gn' gd'
    qa qb qc qn qa' qb' qc' qn',
  fd = fd' -> ga = ga' -> gb = gb' -> gc = gc' -> gn = gn' -> gd = gd' -> qa = qa' -> qb = qb' -> qc = qc' ->
  qn = qn' ->
  fast_intersection_core den_in_filter want_t want_u fa fb fc fn fd ga gb gc gn gd qa qb qc qn =
  fast_intersection_core den_in_filter want_t want_u fa fb fc fn fd' ga' gb' gc' gn' gd' qa' qb' qc' qn'.
Proof. intros. subst. reflexivity. Qed.

Definition fast_intersection_mut_b (enc : CTermB -> float -> float -> EnclosureB) (Cden : float)
    (den_in_filter want_t want_u : bool) (o d a b c : TVec) : option TAnswerB :=
  if (negb want_t && negb want_u)%bool then
    match fast_relation_tri_b o d a b c with
    | Some cl => Some (TAB cl fnan fnan fnan fnan 0 0)
    | None => None
    end
  else
    let ad := absolute_bv d in let ae := absolute_bv (ehigh a o) in let o' := bcast o in
    let pa := pi_stage2_b o' d b c in let pb := pi_stage2_b o' d c a in let pc := pi_stage2_b o' d a b in
    let pn := num_stage2_lane_b o a b c in
    let Cpi := Cpp.triangle_filter_pi_relative in let K := Cpp.triangle_compensated_relative in
    let ea := enc pa K ad in let eb := enc pb K ad in
    let ec := enc pc K ad in let en := enc pn K ae in
    let den := cterm_add_b (cterm_add_b pa pb) pc in
    let ed := enc den Cpp.triangle_compensated_den_relative ad in
    let dv := shared_divisor_b ed in
    fast_intersection_core den_in_filter want_t want_u
      (det3_filter_lanes_b (fview pa) Cpi ad) (det3_filter_lanes_b (fview pb) Cpi ad)
      (det3_filter_lanes_b (fview pc) Cpi ad) (det3_filter_lanes_b (fview pn) Cpp.triangle_filter_num_relative ae)
      (det3_filter_lanes_b (fview den) Cden ad)
      (enclosure_sign_lanes_b ea) (enclosure_sign_lanes_b eb) (enclosure_sign_lanes_b ec)
      (enclosure_sign_lanes_b en) (enclosure_sign_lanes_b ed)
      (round_quotient_b ea dv) (round_quotient_b eb dv) (round_quotient_b ec dv) (round_quotient_b en dv).

Lemma fast_intersection_mut_original : forall want_t want_u o d a b c,
  fast_intersection_mut_b det3_enclosure_b Cpp.triangle_filter_den_relative true want_t want_u o d a b c =
  fast_intersection_tri_b want_t want_u o d a b c.
Proof. reflexivity. Qed.

(** ** tri_call_site_den: fast_triangle_intersection filters den with π's constant *)

Open Scope R_scope.

Definition fast_intersection_call_site_den_b := fast_intersection_mut_b det3_enclosure_b Cpp.triangle_filter_pi_relative true.

Lemma nonneg_fin_pos : forall x, nonneg x -> fin x = true -> 0 <= B2R x.
Proof.
  intros [s|s| |s m e H] [N|N] F; try discriminate; cbn in N; try (subst; apply Bsign_false_nonneg; reflexivity);
    cbn; lra.
Qed.

(** A smaller bound certifies whatever a larger one certifies, with the same sign. *)
Lemma sign_lanes_monotone : forall B B' v, fin B = true -> fin B' = true -> 0 <= B2R B <= B2R B' ->
  sign_lanes (flt B' v) (flt v (fneg B')) <> uncertain_lane ->
  sign_lanes (flt B v) (flt v (fneg B)) = sign_lanes (flt B' v) (flt v (fneg B')).
Proof.
  intros B B' v FB FB' [P L] H. destruct (fin v) eqn:Fv.
  - rewrite !flt_val in * by (rewrite ?fneg_fin; assumption). rewrite !fneg_val in *.
    destruct (Rlt_bool_spec (B2R B) (B2R v)), (Rlt_bool_spec (B2R v) (- B2R B)),
             (Rlt_bool_spec (B2R B') (B2R v)), (Rlt_bool_spec (B2R v) (- B2R B'));
      try lra; try reflexivity; exfalso; apply H; reflexivity.
  - destruct v as [sv|sv| |sv mv ev Hv]; try discriminate Fv;
      destruct B as [sb|sb| |sb mb eb Hb]; try discriminate FB;
      destruct B' as [sb'|sb'| |sb' mb' eb' Hb']; try discriminate FB'; try destruct sv; reflexivity.
Qed.

(** Den's stage-1 decision with π's constant (8u) is its decision with den's (10u) wherever the latter is
    certain; [C], [C'] any finite non-negative constants with C ≤ C'. *)
Theorem den_filter_constant_monotone : forall t C C' A, fin C = true -> fin C' = true -> nonneg C -> nonneg C' ->
  B2R C <= B2R C' -> nonneg (fmb t) -> nonneg A ->
  det3_filter_lanes_b t C' A <> uncertain_lane -> det3_filter_lanes_b t C A = det3_filter_lanes_b t C' A.
Proof.
  intros t C C' A FC FC' NC NC' L Nm NA H. unfold det3_filter_lanes_b in *.
  set (B' := fadd (fmul C' (fmb t)) A) in *.
  assert (NB' : nonneg B') by (apply fadd_nonneg; [apply fmul_nonneg|]; assumption).
  assert (FB' : fin B' = true) by (apply (certifying_bound_finite B' (fvb t) NB'); now apply sign_lanes_certain).
  destruct (fadd_fin _ _ FB') as [Fp' FA]. destruct (fmul_fin _ _ Fp') as [_ Fm].
  pose proof (nonneg_fin_pos _ NC FC). pose proof (nonneg_fin_pos _ NC' FC').
  pose proof (nonneg_fin_pos _ Nm Fm) as Pm. pose proof (nonneg_fin_pos _ NA FA) as PA.
  assert (Lp : 0 <= RN (B2R C * B2R (fmb t)) <= B2R (fmul C' (fmb t))).
  { rewrite (fmul_val _ _ Fp'). split; [rewrite <- RN_0; apply RN_le; nra | apply RN_le; nra]. }
  destruct (fmul_fwd C (fmb t) FC Fm) as [Fp Vp].
  { rewrite Rabs_pos_eq by lra. eapply Rle_lt_trans; [apply Lp|].
    eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow]. }
  assert (Ls : 0 <= RN (B2R (fmul C (fmb t)) + B2R A) <= B2R B').
  { unfold B'. rewrite (fadd_val _ _ FB'), Vp. split; [rewrite <- RN_0; apply RN_le; lra | apply RN_le; lra]. }
  destruct (fadd_fwd (fmul C (fmb t)) A Fp FA) as [FB VB].
  { rewrite Rabs_pos_eq by lra. eapply Rle_lt_trans; [apply Ls|].
    eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow]. }
  apply sign_lanes_monotone; try assumption. rewrite VB. exact Ls.
Qed.

Lemma den_view_nonneg : forall o d a b c, nonneg (fmb (fview (den_stage2_b (bcast o) d a b c))).
Proof.
  intros. change (nonneg (fadd (cmb (cterm_add_b (pi_stage2_b (bcast o) d b c) (pi_stage2_b (bcast o) d c a)))
                               (cmb (pi_stage2_b (bcast o) d a b)))).
  apply fadd_nonneg; [apply fadd_nonneg|]; apply pi_view_nonneg.
Qed.

(** The mutated twin answers as the twin (the same classification, t, barycentrics and stages) unless den's
    view is certain with 8u and uncertain with 10u. *)
Theorem tri_call_site_den_same_unless_between : forall want_t want_u (o d a b c : TVec),
  let fd := det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative
                                (absolute_bv d) in
  let fd' := det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_pi_relative
                                 (absolute_bv d) in
  fd <> uncertain_lane \/ fd' = uncertain_lane ->
  fast_intersection_call_site_den_b want_t want_u o d a b c = fast_intersection_tri_b want_t want_u o d a b c.
Proof.
  intros want_t want_u o d a b c fd fd' H.
  destruct cpp_triangle_constants as [_ [_ [_ [_ [FP [NP [_ [_ [FD [ND _]]]]]]]]]].
  assert (E : fd' = fd).
  { assert (M : fd <> uncertain_lane -> fd' = fd).
    { intros U. apply (den_filter_constant_monotone _ _ _ _ FP FD NP ND).
      - rewrite cpp_triangle_filter_pi_relative, cpp_triangle_filter_den_relative.
        unfold triangle_filter_pi_relative, triangle_filter_den_relative. pose proof u_pos. lra.
      - apply den_view_nonneg.
      - apply absolute_bv_nonneg.
      - exact U. }
    destruct (Z.eq_dec fd uncertain_lane) as [V|V]; [| exact (M V)].
    destruct H as [U | U]; [contradiction | transitivity uncertain_lane; [exact U | symmetry; exact V]]. }
  transitivity (fast_intersection_mut_b det3_enclosure_b Cpp.triangle_filter_den_relative true want_t want_u o d a b c);
    [| apply fast_intersection_mut_original].
  unfold fast_intersection_call_site_den_b, fast_intersection_mut_b.
  destruct (negb want_t && negb want_u)%bool; [reflexivity|]. cbv zeta.
  apply fast_intersection_core_congr; first [exact E | match goal with |- ?x = ?x => reflexivity end].
Qed.

(** ** tri_drop_guard: det3_enclosure without the guard |l| ≤ largest finite *)

Definition det3_enclosure_noguard_b (t : CTermB) (K A : float) : EnclosureB :=
  let radius := fadd (fmul K (cmb t)) A in
  let finite := fle (fabs (chb t)) largest_finite_f in
  {| hib := chb t; lob := clb t; radiusb := if finite then radius else finf |}.

Definition fast_intersection_drop_guard_b := fast_intersection_mut_b det3_enclosure_noguard_b Cpp.triangle_filter_den_relative true.

(** The case the guard would matter for and the consumers do not absorb: h finite, l = ±inf, finite radius. *)
Definition no_infinite_low (t : CTermB) (K A : float) : Prop :=
  fin (chb t) = true -> fin (clb t) = false -> is_nan (clb t) = false -> fin (fadd (fmul K (cmb t)) A) = false.

Lemma fabs_nan : fabs B754_nan = B754_nan.
Proof. reflexivity. Qed.
Lemma fle_nan_r : forall x, fle x B754_nan = false.
Proof. intros [s|s| |s m e H]; reflexivity. Qed.
Lemma fadd_nan_r : forall x, fadd x B754_nan = B754_nan.
Proof. intros [s|s| |s m e H]; reflexivity. Qed.
Lemma fadd_inf_r : forall x s, fin x = true -> fadd x (B754_infinity s) = B754_infinity s.
Proof. intros [sx|sx| |sx m e H] s F; try discriminate; reflexivity. Qed.
Lemma fin_fmul_l : forall x y, fin x = false -> fin (fmul x y) = false.
Proof. intros x y F. destruct (fin (fmul x y)) eqn:E; [|reflexivity]. now rewrite (proj1 (fmul_fin _ _ E)) in F. Qed.
Lemma fin_fadd_l : forall x y, fin x = false -> fin (fadd x y) = false.
Proof. intros x y F. destruct (fin (fadd x y)) eqn:E; [|reflexivity]. now rewrite (proj1 (fadd_fin _ _ E)) in F. Qed.
Lemma cpp_largest_finite_bits : Cpp.largest_finite = largest_finite_f.
Proof. reflexivity. Qed.

(** [round_quotient(num, den)]: its value does not read num's radius; when it is not certain, neither is it
    for another radius. *)
Lemma round_quotient_radius_irrelevant : forall e e' dv, hib e = hib e' -> lob e = lob e' ->
  snd (round_quotient_b e dv) = false -> snd (round_quotient_b e' dv) = false ->
  round_quotient_b e dv = round_quotient_b e' dv.
Proof.
  intros e e' dv Hh Hl S S'. rewrite (surjective_pairing (round_quotient_b e dv)),
    (surjective_pairing (round_quotient_b e' dv)), S, S'. f_equal.
  unfold round_quotient_b. cbv zeta. cbn [fst]. rewrite Hh, Hl. reflexivity.
Qed.

Lemma round_quotient_nan_low : forall e dv, lob e = B754_nan -> snd (round_quotient_b e dv) = false.
Proof.
  intros e dv Hl. unfold round_quotient_b. cbv zeta. cbn [snd]. rewrite Hl.
  change (fst (two_sum_b (hib e) B754_nan)) with (fadd (hib e) B754_nan).
  rewrite fadd_nan_r, fabs_nan, fle_nan_r. reflexivity.
Qed.

Lemma round_quotient_inf_low : forall e dv s, fin (hib e) = true -> lob e = B754_infinity s ->
  snd (round_quotient_b e dv) = false.
Proof.
  intros e dv s Fh Hl. unfold round_quotient_b. cbv zeta. cbn [snd]. rewrite Hl.
  change (fst (two_sum_b (hib e) (B754_infinity s))) with (fadd (hib e) (B754_infinity s)).
  rewrite (fadd_inf_r _ _ Fh), cpp_largest_finite_bits, fle_largest_finite.
  rewrite fin_fadd_l by (apply fin_fmul_l; reflexivity).
  rewrite !andb_false_r. reflexivity.
Qed.

(** As a divisor: out of range, its radius is not read. *)
Lemma round_quotient_divisor_radius_irrelevant : forall n e e', hib e = hib e' -> lob e = lob e' ->
  din_rangeb (prepare_divisor_b e) = false ->
  round_quotient_b n (shared_divisor_b e) = round_quotient_b n (shared_divisor_b e').
Proof.
  intros n e e' Hh Hl R. unfold round_quotient_b, shared_divisor_b. cbv zeta.
  cbn [dhib dlob dradiusb dreciprocalb din_rangeb].
  assert (R' : din_rangeb (prepare_divisor_b e') = false) by (unfold prepare_divisor_b in *; rewrite <- Hh, <- Hl; exact R).
  rewrite R, R', !andb_false_r, !andb_false_l.
  unfold prepare_divisor_b. cbv zeta. cbn [dhib dlob dreciprocalb]. rewrite Hh, Hl. reflexivity.
Qed.

Lemma divisor_nan_low : forall e, lob e = B754_nan -> din_rangeb (prepare_divisor_b e) = false.
Proof.
  intros e Hl. unfold prepare_divisor_b. cbv zeta. cbn [din_rangeb]. rewrite Hl.
  change (fst (two_sum_b (hib e) B754_nan)) with (fadd (hib e) B754_nan).
  rewrite fadd_nan_r, fabs_nan, fle_nan_r. reflexivity.
Qed.

Lemma divisor_inf_low : forall e s, fin (hib e) = true -> lob e = B754_infinity s ->
  din_rangeb (prepare_divisor_b e) = false.
Proof.
  intros e s Fh Hl. unfold prepare_divisor_b. cbv zeta. cbn [din_rangeb]. rewrite Hl.
  change (fst (two_sum_b (hib e) (B754_infinity s))) with (fadd (hib e) (B754_infinity s)).
  rewrite (fadd_inf_r _ _ Fh). destruct s; vm_compute; reflexivity.
Qed.

Lemma enclosure_sign_nan_low : forall e, lob e = B754_nan -> enclosure_sign_lanes_b e = uncertain_lane.
Proof.
  intros e Hl. unfold enclosure_sign_lanes_b. cbv zeta. rewrite Hl, fadd_nan_r.
  replace (flt (fadd (radiusb e) (radiusb e)) B754_nan) with false by (destruct (fadd _ _); reflexivity).
  reflexivity.
Qed.

Lemma enclosure_sign_inf_low : forall e s, fin (hib e) = true -> lob e = B754_infinity s ->
  (radiusb e = finf \/ radiusb e = B754_nan) -> enclosure_sign_lanes_b e = uncertain_lane.
Proof.
  intros e s Fh Hl Hr. unfold enclosure_sign_lanes_b. cbv zeta. rewrite Hl, (fadd_inf_r _ _ Fh).
  destruct Hr as [Hr | Hr]; rewrite Hr; destruct s; reflexivity.
Qed.

Lemma nonneg_not_fin : forall x, nonneg x -> fin x = false -> x = finf \/ x = B754_nan.
Proof. intros [s|s| |s m e H] [N|N] F; cbn in *; try discriminate; subst; auto. Qed.

(** Without the guard, the three consumers of an enclosure (its sign; [round_quotient] with it as
    numerator, and as divisor) give what they give with the guard, unless [no_infinite_low] fails. *)
Theorem drop_guard_consumers_agree : forall t K A, nonneg K -> nonneg (cmb t) -> nonneg A -> no_infinite_low t K A ->
  enclosure_sign_lanes_b (det3_enclosure_noguard_b t K A) = enclosure_sign_lanes_b (det3_enclosure_b t K A) /\
  (forall dv, round_quotient_b (det3_enclosure_noguard_b t K A) dv = round_quotient_b (det3_enclosure_b t K A) dv) /\
  (forall n, round_quotient_b n (shared_divisor_b (det3_enclosure_noguard_b t K A)) =
             round_quotient_b n (shared_divisor_b (det3_enclosure_b t K A))).
Proof.
  intros t K A NK Nm NA P.
  destruct (fin (chb t) && fin (clb t))%bool eqn:G.
  - assert (E : det3_enclosure_noguard_b t K A = det3_enclosure_b t K A).
    { unfold det3_enclosure_noguard_b, det3_enclosure_b. rewrite !fle_largest_finite, G.
      apply andb_true_iff in G. destruct G as [G _]. rewrite G. reflexivity. }
    rewrite E. repeat split; reflexivity.
  - destruct (fin (chb t)) eqn:Fh.
    2:{ assert (E : det3_enclosure_noguard_b t K A = det3_enclosure_b t K A).
        { unfold det3_enclosure_noguard_b, det3_enclosure_b. rewrite !fle_largest_finite, Fh. reflexivity. }
        rewrite E. repeat split; reflexivity. }
    cbn [andb] in G. rename G into Fl.
    set (e1 := det3_enclosure_noguard_b t K A). set (e2 := det3_enclosure_b t K A).
    assert (Hh : hib e1 = hib e2) by reflexivity. assert (Hl : lob e1 = lob e2) by reflexivity.
    assert (H1 : hib e1 = chb t) by reflexivity. assert (L1 : lob e1 = clb t) by reflexivity.
    assert (H2 : hib e2 = chb t) by reflexivity. assert (L2 : lob e2 = clb t) by reflexivity.
    assert (R2 : radiusb e2 = finf).
    { unfold e2, det3_enclosure_b. cbn [radiusb]. rewrite !fle_largest_finite, Fh, Fl. reflexivity. }
    destruct (clb t) as [s|s| |s m ex Hx] eqn:Cl; try discriminate Fl.
    + (* l = ±inf: the radius without the guard is +inf or NaN too *)
      assert (Fr : fin (fadd (fmul K (cmb t)) A) = false) by (apply P; [exact Fh | rewrite Cl; reflexivity ..]).
      assert (R1 : radiusb e1 = finf \/ radiusb e1 = B754_nan).
      { unfold e1, det3_enclosure_noguard_b. cbn [radiusb]. rewrite fle_largest_finite, Fh.
        apply nonneg_not_fin; [apply fadd_nonneg; [apply fmul_nonneg|]; assumption | exact Fr]. }
      rewrite <- H1 in Fh. pose proof Fh as Fh2. rewrite Hh in Fh2.
      split; [|split].
      * rewrite (enclosure_sign_inf_low e1 s), (enclosure_sign_inf_low e2 s); auto.
      * intros dv. apply round_quotient_radius_irrelevant; try assumption;
          [apply (round_quotient_inf_low _ _ s) | apply (round_quotient_inf_low _ _ s)]; assumption.
      * intros n. apply round_quotient_divisor_radius_irrelevant; try assumption.
        apply (divisor_inf_low _ s); assumption.
    + (* l = NaN *)
      split; [|split].
      * rewrite (enclosure_sign_nan_low e1), (enclosure_sign_nan_low e2); auto.
      * intros dv. apply round_quotient_radius_irrelevant; try assumption; apply round_quotient_nan_low; assumption.
      * intros n. apply round_quotient_divisor_radius_irrelevant; try assumption. apply divisor_nan_low; assumption.
Qed.

(** The mutated twin answers as the twin whenever the five stage-2 terms satisfy [no_infinite_low]. *)
Theorem tri_drop_guard_same_unless_infinite_low : forall want_t want_u (o d a b c : TVec),
  let ad := absolute_bv d in let ae := absolute_bv (ehigh a o) in let K := Cpp.triangle_compensated_relative in
  let pa := pi_stage2_b (bcast o) d b c in let pb := pi_stage2_b (bcast o) d c a in
  let pc := pi_stage2_b (bcast o) d a b in let pn := num_stage2_lane_b o a b c in
  no_infinite_low pa K ad -> no_infinite_low pb K ad -> no_infinite_low pc K ad -> no_infinite_low pn K ae ->
  no_infinite_low (cterm_add_b (cterm_add_b pa pb) pc) Cpp.triangle_compensated_den_relative ad ->
  fast_intersection_drop_guard_b want_t want_u o d a b c = fast_intersection_tri_b want_t want_u o d a b c.
Proof.
  intros want_t want_u o d a b c ad ae K pa pb pc pn Pa Pb Pc Pn Pd.
  destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [NK [_ NKd]]]]]]]]]]]]].
  assert (NA : nonneg ad) by apply absolute_bv_nonneg. assert (NE : nonneg ae) by apply absolute_bv_nonneg.
  destruct (drop_guard_consumers_agree pa K ad NK (pi_view_nonneg _ _ _ _) NA Pa) as [Sa [Qa _]].
  destruct (drop_guard_consumers_agree pb K ad NK (pi_view_nonneg _ _ _ _) NA Pb) as [Sb [Qb _]].
  destruct (drop_guard_consumers_agree pc K ad NK (pi_view_nonneg _ _ _ _) NA Pc) as [Sc [Qc _]].
  destruct (drop_guard_consumers_agree pn K ae NK (num_lane_view_nonneg _ _ _ _) NE Pn) as [Sn [Qn _]].
  destruct (drop_guard_consumers_agree _ _ ad NKd (den_view_nonneg o d a b c) NA Pd) as [Sd [_ Dd]].
  transitivity (fast_intersection_mut_b det3_enclosure_b Cpp.triangle_filter_den_relative true want_t want_u o d a b c);
    [| apply fast_intersection_mut_original].
  unfold fast_intersection_drop_guard_b, fast_intersection_mut_b.
  destruct (negb want_t && negb want_u)%bool; [reflexivity|]. cbv zeta.
  apply fast_intersection_core_congr;
    [ match goal with |- ?x = ?x => reflexivity end
    | exact Sa | exact Sb | exact Sc | exact Sn | exact Sd
    | etransitivity; [apply Qa | apply Dd] | etransitivity; [apply Qb | apply Dd]
    | etransitivity; [apply Qc | apply Dd] | etransitivity; [apply Qn | apply Dd] ].
Qed.
