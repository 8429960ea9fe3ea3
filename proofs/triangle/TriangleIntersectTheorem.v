(** * The ray–triangle fast intersection's theorem: every answer of [fast_intersection_tri_b]
    (TriangleIntersectTwins.v, the twin of [fast_triangle_intersection] in
    kernel/src/triangle/ray_triangle_cascade.cpp, tied to the compiled code bit for bit by the runner's
    routine [tri_fast_intersect]) is docs/contract.md §6's.

    - [round_quotient_shared_sound]: [round_quotients]' divisor has its fields broadcast to the lanes
      ([shared_divisor_b]: +0 ⊕ x, which is x except that −0 becomes +0); a quotient rounded over it is
      certified exactly when the one over [prepare_divisor_b] is, with the same value (the relation [zr],
      "equal up to the sign of a zero", is kept by every operation of [round_quotient_b]), so PlaneQueryTwins.v's
      [round_quotient_twin_sound] applies: t = RN(num/den);
    - [tri_lane_sign_exact]: a certain sign of a lane ([first_certain_lanes] of the stage-1 view's filter
      sign and the stage-2 enclosure's sign) is the exact sign, nonzero;
    - [decide_nonzero_contract]: [decide_nonzero] of the exact, nonzero signs is §6's [contract_class] under
      both rules (the argument of TriangleCascade.v's [fast_location_correct]);
    - [fast_intersection_tri_correct]: for every bit pattern of o, d, a, b, c, every option set and both
      rules, an answer of the twin is [contract_class] of the exact values, t (when asked) is RN(num/den) and
      each barycentric (when asked) RN(π_k/den), with πa = π(b, c), πb = π(c, a), πc = π(a, b). *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneCompensated PlaneClassification PlaneCascade FloatCore ConstantsCpp PlaneTwins PlaneQueryTwins TriangleFilter
  TriangleCompensated TriangleRule TriangleTwins TriangleStage3Twins TriangleCascadeTwins TriangleIntersectTwins.
Open Scope R_scope.

(** ** Equal up to the sign of a zero *)

Definition zr (x y : float) : Prop :=
  match x, y with B754_zero _, B754_zero _ => True | _, _ => x = y end.

Lemma zr_refl : forall x, zr x x.
Proof. intros [s|s| |s m e B]; cbn; trivial. Qed.

Lemma zr_cases : forall x y, zr x y -> x = y \/ (exists s s', x = B754_zero s /\ y = B754_zero s').
Proof.
  intros [s|s| |s m e B] [s'|s'| |s' m' e' B'] H; cbn in H;
    first [right; exists s, s'; split; reflexivity | left; exact H].
Qed.

Lemma zr_real : forall x y, zr x y -> fin x = fin y /\ B2R x = B2R y.
Proof. intros x y H. destruct (zr_cases x y H) as [<-|[s [s' [-> ->]]]]; split; reflexivity. Qed.

Ltac zr_finish := repeat match goal with b : bool |- _ => destruct b end; cbn; trivial.

(** Two related pairs of operands, one of them zeros: the operation does not reach its finite case. *)
Ltac zr_op2 :=
  let x := fresh "x" in let x' := fresh "x'" in let y := fresh "y" in let y' := fresh "y'" in
  let Hx := fresh "Hx" in let Hy := fresh "Hy" in
  intros x x' y y' Hx Hy;
  destruct (zr_cases _ _ Hx) as [<-|[? [? [-> ->]]]]; destruct (zr_cases _ _ Hy) as [<-|[? [? [-> ->]]]];
  [apply zr_refl | destruct x as [?|?| |? ? ? ?] | destruct y as [?|?| |? ? ? ?] | ]; zr_finish.

Lemma zr_fadd : forall x x' y y', zr x x' -> zr y y' -> zr (fadd x y) (fadd x' y').
Proof. zr_op2. Qed.
Lemma zr_fsub : forall x x' y y', zr x x' -> zr y y' -> zr (fsub x y) (fsub x' y').
Proof. zr_op2. Qed.
Lemma zr_fmul : forall x x' y y', zr x x' -> zr y y' -> zr (fmul x y) (fmul x' y').
Proof. zr_op2. Qed.

Lemma zr_ffma : forall x x' y y' z, zr x x' -> zr y y' -> zr (ffma x y z) (ffma x' y' z).
Proof.
  intros x x' y y' z Hx Hy.
  destruct (zr_cases _ _ Hx) as [<-|[? [? [-> ->]]]]; destruct (zr_cases _ _ Hy) as [<-|[? [? [-> ->]]]];
  [apply zr_refl | destruct x as [?|?| |? ? ? ?] | destruct y as [?|?| |? ? ? ?] | ];
  destruct z as [?|?| |? ? ? ?]; zr_finish.
Qed.

Lemma zr_fneg : forall x x', zr x x' -> zr (fneg x) (fneg x').
Proof. intros x x' H. destruct (zr_cases _ _ H) as [<-|[? [? [-> ->]]]]; [apply zr_refl | exact I]. Qed.

Lemma zr_fabs : forall x x', zr x x' -> fabs x = fabs x'.
Proof. intros x x' H. destruct (zr_cases _ _ H) as [<-|[? [? [-> ->]]]]; reflexivity. Qed.

Lemma zr_flt_l : forall x x' y, zr x x' -> flt x y = flt x' y.
Proof.
  intros x x' y H. destruct (zr_cases _ _ H) as [<-|[? [? [-> ->]]]]; [reflexivity|].
  destruct y as [?|?| |? ? ? ?]; zr_finish.
Qed.

Lemma zr_bcast : forall x, zr (bcast_f x) x.
Proof. intros [s|s| |s m e B]; unfold bcast_f, fzero; zr_finish. Qed.

(** ** [round_quotient] over related divisors *)

Lemma round_quotient_b_zr : forall num dv dv',
  zr (dhib dv) (dhib dv') -> zr (dlob dv) (dlob dv') -> zr (dradiusb dv) (dradiusb dv') ->
  zr (dreciprocalb dv) (dreciprocalb dv') -> din_rangeb dv = din_rangeb dv' ->
  zr (fst (round_quotient_b num dv)) (fst (round_quotient_b num dv')) /\
  snd (round_quotient_b num dv) = snd (round_quotient_b num dv').
Proof.
  intros num dv dv' Hh Hl Hr HR Hi. unfold round_quotient_b. cbv zeta. cbn [fst snd].
  rewrite Hi.
  set (N := two_sum_b (hib num) (lob num)).
  assert (Q0 : zr (fmul (fst N) (dreciprocalb dv)) (fmul (fst N) (dreciprocalb dv'))) by (apply zr_fmul; [apply zr_refl | exact HR]).
  set (q0 := fmul (fst N) (dreciprocalb dv)) in *. set (q0' := fmul (fst N) (dreciprocalb dv')) in *.
  assert (R1 : zr (ffma (fneg q0) (dhib dv) (fst N)) (ffma (fneg q0') (dhib dv') (fst N)))
    by (apply zr_ffma; [apply zr_fneg, Q0 | exact Hh]).
  assert (R2 : zr (ffma (fneg q0) (dlob dv) (snd N)) (ffma (fneg q0') (dlob dv') (snd N)))
    by (apply zr_ffma; [apply zr_fneg, Q0 | exact Hl]).
  assert (Cc : zr (fmul (fadd (ffma (fneg q0) (dhib dv) (fst N)) (ffma (fneg q0) (dlob dv) (snd N))) (dreciprocalb dv))
                  (fmul (fadd (ffma (fneg q0') (dhib dv') (fst N)) (ffma (fneg q0') (dlob dv') (snd N))) (dreciprocalb dv')))
    by (apply zr_fmul; [apply zr_fadd; assumption | exact HR]).
  set (c := fmul (fadd (ffma (fneg q0) (dhib dv) (fst N)) (ffma (fneg q0) (dlob dv) (snd N))) (dreciprocalb dv)) in *.
  set (c' := fmul (fadd (ffma (fneg q0') (dhib dv') (fst N)) (ffma (fneg q0') (dlob dv') (snd N))) (dreciprocalb dv')) in *.
  assert (Q : zr (fadd q0 c) (fadd q0' c')) by (apply zr_fadd; assumption).
  set (q := fadd q0 c) in *. set (q' := fadd q0' c') in *.
  assert (W : zr (fsub c (fsub q q0)) (fsub c' (fsub q' q0'))) by (apply zr_fsub; [|apply zr_fsub]; assumption).
  split; [exact Q|].
  rewrite (zr_fabs _ _ Q), (zr_fabs _ _ Q0), (zr_fabs _ _ W), (zr_fabs _ _ Hh).
  unfold half_gap_b. rewrite (zr_fabs _ _ Q).
  f_equal. apply zr_flt_l.
  apply zr_fmul; [|apply zr_refl]. apply zr_fadd; [|apply zr_refl].
  apply zr_fmul; [|apply zr_refl]. apply zr_fadd; [|apply zr_refl].
  apply zr_fmul; [apply zr_refl | exact Hr].
Qed.

Lemma shared_divisor_zr : forall num den,
  zr (fst (round_quotient_b num (shared_divisor_b den))) (fst (round_quotient_b num (prepare_divisor_b den))) /\
  snd (round_quotient_b num (shared_divisor_b den)) = snd (round_quotient_b num (prepare_divisor_b den)).
Proof. intros. apply round_quotient_b_zr; first [apply zr_bcast | reflexivity]. Qed.

(** PlaneQueryTwins.v's [round_quotient_twin_sound] over the broadcast divisor. *)
Theorem round_quotient_shared_sound : forall (num den : EnclosureB) (vn vd : R),
  nonneg (radiusb num) -> nonneg (radiusb den) ->
  (fin (hib num) = true -> fin (lob num) = true -> fin (radiusb num) = true -> encloses (enc_R num) vn) ->
  (fin (hib den) = true -> fin (lob den) = true -> fin (radiusb den) = true -> encloses (enc_R den) vd) ->
  snd (round_quotient_b num (shared_divisor_b den)) = true ->
  vd <> 0 /\ fin (fst (round_quotient_b num (shared_divisor_b den))) = true /\
  B2R (fst (round_quotient_b num (shared_divisor_b den))) = RN (vn / vd).
Proof.
  intros num den vn vd Nn Nd En Ed C. destruct (shared_divisor_zr num den) as [Z S].
  rewrite S in C. destruct (zr_real _ _ Z) as [F V]. rewrite F, V.
  exact (round_quotient_twin_sound num den vn vd Nn Nd En Ed C).
Qed.

(** ** The signs of the lanes *)

Lemma det3_enclosure_nonneg : forall t K A, nonneg (cmb t) -> nonneg K -> nonneg A ->
  nonneg (radiusb (det3_enclosure_b t K A)).
Proof.
  intros t K A Nm NK NA. unfold det3_enclosure_b. cbn [radiusb].
  destruct (fle (fabs (chb t)) largest_finite_f && fle (fabs (clb t)) largest_finite_f)%bool;
    [apply fadd_nonneg; [apply fmul_nonneg|] | apply finf_nonneg]; assumption.
Qed.

(** [first_certain_lanes(filter, enclosure_sign_lanes(e))] certain: the exact sign, nonzero, and what the
    certifying stage implies of the inputs ([Fins]). *)
Lemma lane_sign_gen : forall (f : Z) (e : EnclosureB) (V : R) (Fins : Prop),
  lane_sign f -> certifies (sign_from_Z f) V -> (f <> uncertain_lane -> Fins) ->
  nonneg (radiusb e) ->
  (fin (radiusb e) = true -> fin (hib e) = true /\ fin (lob e) = true /\ Fins /\ encloses (enc_R e) V) ->
  certain_lane (first_certain_lanes_b f (enclosure_sign_lanes_b e)) = true ->
  first_certain_lanes_b f (enclosure_sign_lanes_b e) = sign_of V /\ V <> 0 /\ Fins.
Proof.
  intros f e V Fins Lf Cf Ff N He C.
  assert (Se : lane_sign (enclosure_sign_lanes_b e)) by (unfold enclosure_sign_lanes_b; apply sign_lanes_range).
  assert (Ce : certifies (sign_from_Z (enclosure_sign_lanes_b e)) V /\
               (enclosure_sign_lanes_b e <> uncertain_lane -> Fins)).
  { destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U].
    - split; [rewrite U; exact I | intros X; contradiction].
    - pose proof (enclosure_sign_radius_finite e N U) as Fr.
      destruct (He Fr) as [Fh [Fl [Fi E]]].
      split; [exact (proj1 (stage2_sign_twin e V N Fh Fl (fun _ => E))) | intros _; exact Fi]. }
  destruct Ce as [Ce Fe].
  destruct (first_certain_lanes_sound f _ V Lf Se Cf Ce) as [L S].
  rewrite <- first_certain_lanes_b_eq in L, S.
  destruct (lane_sign_exact _ V L (certain_lane_true _ C) S) as [E [_ Nv]].
  split; [exact E | split; [exact Nv|]].
  revert C. unfold first_certain_lanes_b, certain_lane.
  destruct (Z.eqb_spec f uncertain_lane) as [U|U]; intros C.
  - apply Fe. intros X. rewrite X in C. discriminate C.
  - exact (Ff U).
Qed.

Lemma filter_lane_sign : forall t C A, lane_sign (det3_filter_lanes_b t C A).
Proof. intros. unfold det3_filter_lanes_b. apply sign_lanes_range. Qed.

Definition pi_lane_enc (o d p q : TVec) : EnclosureB :=
  det3_enclosure_b (pi_stage2_b (bcast o) d p q) Cpp.triangle_compensated_relative (absolute_bv d).
Definition num_lane_enc (o a b c : TVec) : EnclosureB :=
  det3_enclosure_b (num_stage2_lane_b o a b c) Cpp.triangle_compensated_relative (absolute_bv (ehigh a o)).
Definition den_lane_enc (o d a b c : TVec) : EnclosureB :=
  det3_enclosure_b (den_stage2_b (bcast o) d a b c) Cpp.triangle_compensated_den_relative (absolute_bv d).

(** The shape of the stage-2 lane enclosures' facts ([pi_lane_enc_facts], [num_lane_enc_facts],
    [den_lane_enc_facts]): a [det3_enclosure] of non-negative parts has a non-negative radius, and a finite
    radius gives finite parts plus what the twin's soundness gives ([Fins], the enclosed value V). *)
Lemma det3_lane_enc_facts : forall t K A (Fins : Prop) (V : R),
  nonneg (cmb t) -> nonneg K -> nonneg A ->
  (fin (radiusb (det3_enclosure_b t K A)) = true -> Fins /\ encloses (enc_R (det3_enclosure_b t K A)) V) ->
  let e := det3_enclosure_b t K A in
  nonneg (radiusb e) /\
  (fin (radiusb e) = true -> fin (hib e) = true /\ fin (lob e) = true /\ Fins /\ encloses (enc_R e) V).
Proof.
  intros t K A Fins V Nm NK NA S e. split; [apply det3_enclosure_nonneg; assumption|].
  intros Fr. destruct (det3_enclosure_twin _ _ _ Fr) as [Fh [Fl _]]. destruct (S Fr) as [F E].
  tsplit; assumption.
Qed.

Lemma and_assoc4 : forall A B C D E : Prop, A /\ B /\ C /\ D /\ E -> (A /\ B /\ C /\ D) /\ E.
Proof. tauto. Qed.
Lemma and_assoc5 : forall A B C D E F : Prop, A /\ B /\ C /\ D /\ E /\ F -> (A /\ B /\ C /\ D /\ E) /\ F.
Proof. tauto. Qed.

Lemma compensated_relatives_nonneg :
  nonneg Cpp.triangle_compensated_relative /\ nonneg Cpp.triangle_compensated_den_relative.
Proof.
  destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [NK ND]]]]]]]]]]]]. split; assumption.
Qed.

Lemma pi_lane_enc_facts : forall o d p q, let e := pi_lane_enc o d p q in
  nonneg (radiusb e) /\
  (fin (radiusb e) = true -> fin (hib e) = true /\ fin (lob e) = true /\ (tfin o /\ tfin d /\ tfin p /\ tfin q) /\
                             encloses (enc_R e) (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q))).
Proof.
  intros o d p q. apply det3_lane_enc_facts; [apply pi_view_nonneg | apply compensated_relatives_nonneg |
    apply absolute_bv_nonneg | intros Fr; exact (and_assoc4 _ _ _ _ _ (triangle_pi_lane_compensated_twin_sound o d p q Fr))].
Qed.

Lemma num_lane_enc_facts : forall o a b c, let e := num_lane_enc o a b c in
  nonneg (radiusb e) /\
  (fin (radiusb e) = true -> fin (hib e) = true /\ fin (lob e) = true /\ (tfin o /\ tfin a /\ tfin b /\ tfin c) /\
                             encloses (enc_R e) (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c))).
Proof.
  intros o a b c. apply det3_lane_enc_facts; [apply num_lane_view_nonneg | apply compensated_relatives_nonneg |
    apply absolute_bv_nonneg | intros Fr; exact (and_assoc4 _ _ _ _ _ (triangle_num_lane_compensated_twin_sound o a b c Fr))].
Qed.

Lemma den_lane_cmb_nonneg : forall o d a b c, nonneg (cmb (den_stage2_b o d a b c)).
Proof.
  intros. unfold den_stage2_b, cterm_add_b. cbn [cmb].
  apply fadd_nonneg; [apply fadd_nonneg|]; apply pi_view_nonneg.
Qed.

Lemma den_lane_enc_facts : forall o d a b c, let e := den_lane_enc o d a b c in
  nonneg (radiusb e) /\
  (fin (radiusb e) = true -> fin (hib e) = true /\ fin (lob e) = true /\
                             (tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c) /\
                             encloses (enc_R e) (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c))).
Proof.
  intros o d a b c. apply det3_lane_enc_facts; [apply den_lane_cmb_nonneg | apply compensated_relatives_nonneg |
    apply absolute_bv_nonneg | intros Fr; exact (and_assoc5 _ _ _ _ _ _ (triangle_den_lane_compensated_twin_sound o d a b c Fr))].
Qed.

(** Lanes 0–2 of the fast intersection (o broadcast): a certain sign is the exact sign of π(p, q), nonzero. *)
Lemma pi_lane_sign : forall o d p q,
  certain_lane (first_certain_lanes_b
    (det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d p q)) Cpp.triangle_filter_pi_relative (absolute_bv d))
    (enclosure_sign_lanes_b (pi_lane_enc o d p q))) = true ->
  first_certain_lanes_b
    (det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d p q)) Cpp.triangle_filter_pi_relative (absolute_bv d))
    (enclosure_sign_lanes_b (pi_lane_enc o d p q)) = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) /\
  edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q) <> 0 /\ (tfin o /\ tfin d /\ tfin p /\ tfin q).
Proof.
  intros o d p q. destruct (triangle_pi_lane_view_filter_twin_sound o d p q) as [Cf Ff].
  destruct (pi_lane_enc_facts o d p q) as [N He].
  exact (lane_sign_gen _ _ _ _ (filter_lane_sign _ _ _) Cf Ff N He).
Qed.

(** Lane 3 (num). *)
Lemma num_lane_sign : forall o a b c,
  certain_lane (first_certain_lanes_b
    (det3_filter_lanes_b (fview (num_stage2_lane_b o a b c)) Cpp.triangle_filter_num_relative (absolute_bv (ehigh a o)))
    (enclosure_sign_lanes_b (num_lane_enc o a b c))) = true ->
  first_certain_lanes_b
    (det3_filter_lanes_b (fview (num_stage2_lane_b o a b c)) Cpp.triangle_filter_num_relative (absolute_bv (ehigh a o)))
    (enclosure_sign_lanes_b (num_lane_enc o a b c)) = sign_of (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) /\
  num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c) <> 0 /\ (tfin o /\ tfin a /\ tfin b /\ tfin c).
Proof.
  intros o a b c. destruct (triangle_num_lane_view_filter_twin_sound o a b c) as [Cf Ff].
  destruct (num_lane_enc_facts o a b c) as [N He].
  exact (lane_sign_gen _ _ _ _ (filter_lane_sign _ _ _) Cf Ff N He).
Qed.

(** den = (lane 0 + lane 1) + lane 2. *)
Lemma den_lane_sign : forall o d a b c,
  certain_lane (first_certain_lanes_b
    (det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative (absolute_bv d))
    (enclosure_sign_lanes_b (den_lane_enc o d a b c))) = true ->
  first_certain_lanes_b
    (det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative (absolute_bv d))
    (enclosure_sign_lanes_b (den_lane_enc o d a b c)) =
    sign_of (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) /\
  den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) <> 0 /\
  (tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c).
Proof.
  intros o d a b c. destruct (triangle_den_lane_view_filter_twin_sound o d a b c) as [Cf Ff].
  destruct (den_lane_enc_facts o d a b c) as [N He].
  exact (lane_sign_gen _ _ _ _ (filter_lane_sign _ _ _) Cf Ff N He).
Qed.

(** ** The classification: [decide_nonzero] of the exact, nonzero signs is §6's *)

Lemma decide_nonzero_contract : forall O D A B C sn cl,
  edge_value O D B C <> 0 -> edge_value O D C A <> 0 -> edge_value O D A B <> 0 -> den_value O D A B C <> 0 ->
  (certain_lane sn = true -> sn = sign_of (num_value O A B C) /\ num_value O A B C <> 0) ->
  decide_nonzero_b (sign_of (edge_value O D B C)) (sign_of (edge_value O D C A)) (sign_of (edge_value O D A B))
                   (sign_of (den_value O D A B C)) sn = Some cl ->
  contract_class true O D A B C cl /\ contract_class false O D A B C cl.
Proof.
  intros O D A B C sn cl Na Nb Nc Nd Hn. apply (decided_class_contract O D A B C sn cl Na Nb Nc Nd).
  intros Un. apply Hn. unfold certain_lane. rewrite (proj2 (Z.eqb_neq _ _) Un). reflexivity.
Qed.

(** ** The quotients *)

Lemma lane_quotient : forall (num den : EnclosureB) (V VD : R),
  nonneg (radiusb num) -> (fin (radiusb num) = true -> encloses (enc_R num) V) ->
  nonneg (radiusb den) -> (fin (radiusb den) = true -> encloses (enc_R den) VD) ->
  snd (round_quotient_b num (shared_divisor_b den)) = true ->
  fin (fst (round_quotient_b num (shared_divisor_b den))) = true /\
  B2R (fst (round_quotient_b num (shared_divisor_b den))) = RN (V / VD).
Proof.
  intros num den V VD Nn En Nd Ed C.
  destruct (round_quotient_shared_sound num den V VD Nn Nd (fun _ _ F => En F) (fun _ _ F => Ed F) C) as [_ R].
  exact R.
Qed.

Lemma pi_lane_quotient : forall o d a b c p q,
  snd (round_quotient_b (pi_lane_enc o d p q) (shared_divisor_b (den_lane_enc o d a b c))) = true ->
  fin (fst (round_quotient_b (pi_lane_enc o d p q) (shared_divisor_b (den_lane_enc o d a b c)))) = true /\
  B2R (fst (round_quotient_b (pi_lane_enc o d p q) (shared_divisor_b (den_lane_enc o d a b c)))) =
    RN (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q) /
        den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c p q. destruct (pi_lane_enc_facts o d p q) as [Nn En]. destruct (den_lane_enc_facts o d a b c) as [Nd Ed].
  apply lane_quotient; [exact Nn | intros F; exact (proj2 (proj2 (proj2 (En F)))) |
                        exact Nd | intros F; exact (proj2 (proj2 (proj2 (Ed F))))].
Qed.

Lemma num_lane_quotient : forall o d a b c,
  snd (round_quotient_b (num_lane_enc o a b c) (shared_divisor_b (den_lane_enc o d a b c))) = true ->
  fin (fst (round_quotient_b (num_lane_enc o a b c) (shared_divisor_b (den_lane_enc o d a b c)))) = true /\
  B2R (fst (round_quotient_b (num_lane_enc o a b c) (shared_divisor_b (den_lane_enc o d a b c)))) =
    RN (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c) /
        den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c. destruct (num_lane_enc_facts o a b c) as [Nn En]. destruct (den_lane_enc_facts o d a b c) as [Nd Ed].
  apply lane_quotient; [exact Nn | intros F; exact (proj2 (proj2 (proj2 (En F)))) |
                        exact Nd | intros F; exact (proj2 (proj2 (proj2 (Ed F))))].
Qed.

(** ** The theorem *)

(** What an answer [ans] of the fast intersection means for the query o, d, a, b, c with the options
    [want_t], [want_u]: the inputs are finite, den ≠ 0, the classification is docs/contract.md §6's under the
    owned and the closed rule, t (asked) is finite and RN(num/den), and each barycentric (asked) is finite and
    RN(π_k/den) with πa = π(b, c), πb = π(c, a), πc = π(a, b). *)
Definition intersection_means (want_t want_u : bool) (o d a b c : TVec) (ans : TAnswerB) : Prop :=
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  den_value O D A B C <> 0 /\
  contract_class true O D A B C (tab_class ans) /\ contract_class false O D A B C (tab_class ans) /\
  (want_t = true -> fin (tab_t ans) = true /\ B2R (tab_t ans) = RN (num_value O A B C / den_value O D A B C)) /\
  (want_u = true ->
   (fin (tab_ua ans) = true /\ B2R (tab_ua ans) = RN (edge_value O D B C / den_value O D A B C)) /\
   (fin (tab_ub ans) = true /\ B2R (tab_ub ans) = RN (edge_value O D C A / den_value O D A B C)) /\
   (fin (tab_uc ans) = true /\ B2R (tab_uc ans) = RN (edge_value O D A B / den_value O D A B C))).

(** The twin past its lanes, over names for the lanes' signs and quotients. *)
Definition intersect_tail_b (want_t want_u : bool) (fa fb fc fd fn sa sb sc sd sn : Z) (qa qb qc qn : float * bool) :
  option TAnswerB :=
  if negb (certain_lane sa && certain_lane sb && certain_lane sc && certain_lane sd)%bool then None else
  match decide_nonzero_b sa sb sc sd sn with
  | None => None
  | Some cl =>
    if (want_t && negb (certain_lane sn))%bool then None else
    if negb ((negb want_t || snd qn) && (negb want_u || (snd qa && snd qb && snd qc)))%bool then None else
    let by_filter := (certain_lane fa && certain_lane fb && certain_lane fc && certain_lane fd &&
                      (is_outside (tloc cl) || certain_lane fn))%bool in
    Some (TAB cl (if want_t then fst qn else fnan) (if want_u then fst qa else fnan)
              (if want_u then fst qb else fnan) (if want_u then fst qc else fnan)
              (if by_filter then 0 else 1) 1)
  end%Z.

(** [fast_intersection_tri_b] with an option asked, as [intersect_tail_b] of its lanes (an equation of
    definitions: den summed from the lanes is [den_stage2_b]). *)
Lemma fast_intersection_tri_b_eq : forall want_t want_u o d a b c,
  (negb want_t && negb want_u)%bool = false ->
  let fa := det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d b c)) Cpp.triangle_filter_pi_relative (absolute_bv d) in
  let fb := det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d c a)) Cpp.triangle_filter_pi_relative (absolute_bv d) in
  let fc := det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d a b)) Cpp.triangle_filter_pi_relative (absolute_bv d) in
  let fn := det3_filter_lanes_b (fview (num_stage2_lane_b o a b c)) Cpp.triangle_filter_num_relative
                                (absolute_bv (ehigh a o)) in
  let fd := det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative
                                (absolute_bv d) in
  let dv := shared_divisor_b (den_lane_enc o d a b c) in
  fast_intersection_tri_b want_t want_u o d a b c =
  intersect_tail_b want_t want_u fa fb fc fd fn
    (first_certain_lanes_b fa (enclosure_sign_lanes_b (pi_lane_enc o d b c)))
    (first_certain_lanes_b fb (enclosure_sign_lanes_b (pi_lane_enc o d c a)))
    (first_certain_lanes_b fc (enclosure_sign_lanes_b (pi_lane_enc o d a b)))
    (first_certain_lanes_b fd (enclosure_sign_lanes_b (den_lane_enc o d a b c)))
    (first_certain_lanes_b fn (enclosure_sign_lanes_b (num_lane_enc o a b c)))
    (round_quotient_b (pi_lane_enc o d b c) dv) (round_quotient_b (pi_lane_enc o d c a) dv)
    (round_quotient_b (pi_lane_enc o d a b) dv) (round_quotient_b (num_lane_enc o a b c) dv).
Proof.
  intros want_t want_u o d a b c W.
  unfold fast_intersection_tri_b, intersect_tail_b, pi_lane_enc, num_lane_enc, den_lane_enc, den_stage2_b.
  rewrite W. cbv zeta. reflexivity.
Qed.

Lemma intersect_tail_correct : forall want_t want_u (fa fb fc fd fn sa sb sc sd sn : Z) (qa qb qc qn : float * bool)
  (o d a b c : TVec) ans,
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  (certain_lane sa = true -> sa = sign_of (edge_value O D B C) /\ edge_value O D B C <> 0 /\
                             (tfin o /\ tfin d /\ tfin b /\ tfin c)) ->
  (certain_lane sb = true -> sb = sign_of (edge_value O D C A) /\ edge_value O D C A <> 0 /\
                             (tfin o /\ tfin d /\ tfin c /\ tfin a)) ->
  (certain_lane sc = true -> sc = sign_of (edge_value O D A B) /\ edge_value O D A B <> 0 /\
                             (tfin o /\ tfin d /\ tfin a /\ tfin b)) ->
  (certain_lane sd = true -> sd = sign_of (den_value O D A B C) /\ den_value O D A B C <> 0 /\
                             (tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c)) ->
  (certain_lane sn = true -> sn = sign_of (num_value O A B C) /\ num_value O A B C <> 0 /\
                             (tfin o /\ tfin a /\ tfin b /\ tfin c)) ->
  (snd qa = true -> fin (fst qa) = true /\ B2R (fst qa) = RN (edge_value O D B C / den_value O D A B C)) ->
  (snd qb = true -> fin (fst qb) = true /\ B2R (fst qb) = RN (edge_value O D C A / den_value O D A B C)) ->
  (snd qc = true -> fin (fst qc) = true /\ B2R (fst qc) = RN (edge_value O D A B / den_value O D A B C)) ->
  (snd qn = true -> fin (fst qn) = true /\ B2R (fst qn) = RN (num_value O A B C / den_value O D A B C)) ->
  intersect_tail_b want_t want_u fa fb fc fd fn sa sb sc sd sn qa qb qc qn = Some ans ->
  intersection_means want_t want_u o d a b c ans.
Proof.
  intros want_t want_u fa fb fc fd fn sa sb sc sd sn qa qb qc qn o d a b c ans O D A B C Sa Sb Sc Sd Sn Qa Qb Qc Qn.
  unfold intersect_tail_b.
  destruct (certain_lane sa && certain_lane sb && certain_lane sc && certain_lane sd)%bool eqn:Cert;
    cbn [negb]; [|intros H; discriminate H].
  apply andb_prop in Cert. destruct Cert as [Cert Cd]. apply andb_prop in Cert. destruct Cert as [Cert Cc].
  apply andb_prop in Cert. destruct Cert as [Ca Cb].
  destruct (Sa Ca) as [Ea [Na [Fo [Fd [Fb Fc]]]]]. destruct (Sb Cb) as [Eb [Nb [_ [_ [_ Fa]]]]].
  destruct (Sc Cc) as [Ec [Nc _]]. destruct (Sd Cd) as [Ed [Nd _]].
  rewrite Ea, Eb, Ec, Ed.
  destruct (decide_nonzero_b _ _ _ _ sn) as [cl|] eqn:Dn; [|intros H; discriminate H].
  destruct (decide_nonzero_contract _ _ _ _ _ sn cl Na Nb Nc Nd
              (fun C => conj (proj1 (Sn C)) (proj1 (proj2 (Sn C)))) Dn) as [C1 C2].
  destruct (want_t && negb (certain_lane sn))%bool eqn:Wt; [intros H; discriminate H|].
  destruct ((negb want_t || snd qn) && (negb want_u || (snd qa && snd qb && snd qc)))%bool eqn:Rd;
    cbn [negb]; [|intros H; discriminate H].
  intros H. injection H as <-.
  unfold intersection_means. cbv zeta. cbn [tab_class tab_t tab_ua tab_ub tab_uc].
  apply andb_prop in Rd. destruct Rd as [Rt Ru].
  tsplit; try assumption.
  - intros ->. cbn [negb orb] in Rt. exact (Qn Rt).
  - intros ->. cbn [negb orb] in Ru. apply andb_prop in Ru. destruct Ru as [Ru Rc].
    apply andb_prop in Ru. destruct Ru as [Ra Rb]. exact (conj (Qa Ra) (conj (Qb Rb) (Qc Rc))).
Qed.

(** [fast_triangle_intersection] (kernel/src/triangle/ray_triangle_cascade.cpp), through its twin: for every
    64-bit pattern of o, d, a, b, c and every option set, an answer is docs/contract.md §6's for the exact
    values under both rules, with t = RN(num/den) and the barycentrics RN(π_k/den) when asked. *)
Theorem fast_intersection_tri_correct : forall want_t want_u o d a b c ans,
  fast_intersection_tri_b want_t want_u o d a b c = Some ans -> intersection_means want_t want_u o d a b c ans.
Proof.
  intros want_t want_u o d a b c ans.
  destruct (negb want_t && negb want_u)%bool eqn:W.
  - (* neither t nor the barycentrics: the relation's fast path *)
    unfold fast_intersection_tri_b. rewrite W.
    destruct (fast_relation_tri_b o d a b c) as [cl|] eqn:R; [|intros H; discriminate H].
    intros H. injection H as <-.
    destruct (fast_relation_tri_correct o d a b c cl R) as [Fo [Fd [Fa [Fb [Fc [Nd [C1 C2]]]]]]].
    apply andb_prop in W. destruct W as [Wt Wu]. apply negb_true_iff in Wt, Wu. subst want_t want_u.
    unfold intersection_means. cbn [tab_class]. tsplit; try assumption; intros X; discriminate X.
  - rewrite (fast_intersection_tri_b_eq want_t want_u o d a b c W).
    apply intersect_tail_correct.
    + exact (pi_lane_sign o d b c).
    + exact (pi_lane_sign o d c a).
    + exact (pi_lane_sign o d a b).
    + exact (den_lane_sign o d a b c).
    + exact (num_lane_sign o a b c).
    + exact (pi_lane_quotient o d a b c b c).
    + exact (pi_lane_quotient o d a b c c a).
    + exact (pi_lane_quotient o d a b c a b).
    + exact (num_lane_quotient o d a b c).
Qed.
