(** * The orientation filters of the point-in-mesh query over IEEE-754 binary64, tied to OrientFilter.v.

    [orient2d_filter_b] and [orient3d_filter_b] are kernel/src/orient/orient_predicates.hpp's [orient2d_filter] and
    [orient3d_filter], operation by operation in the C++ order, over FloatCore.v's binary64 and the compiled
    constants [Cpp.orient2d_filter_relative], ... (ConstantsCpp.v).  The runner (proofs/twins/, group
    [orient]) compares them with the compiled C++ bit for bit.

    - [cpp_orient2d_filter_relative] … [cpp_orient3d_filter_max_difference] (generated in ConstantsCpp.v): the
      compiled constants are Constants.v's.
    - [orient2d_filter_twin_sound]: for every bit pattern of the six coordinates, an answer +1 or −1 means every
      input is finite and it is the sign of orient2d of the exact values (OrientFilter.v's
      [orient2d_filter_sound]): a non-finite input or an overflow anywhere makes the bound +inf or NaN, and
      the answer 0.
    - [orient3d_filter_twin_sound]: the same for the twelve coordinates of o, a, b, c and
      det(a − o, b − o, c − o) ([orient3d_filter_sound]).
    - [orient2d_filter_twin_model], [orient3d_filter_twin_model]: a certain answer is the model's answer on the
      same reals (so every theorem about the model's filters holds for the bits). *)

From Coq Require Import Reals Lra Lia ZArith Bool List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model FloatCore ConstantsCpp OrientFilter.
Open Scope R_scope.
Import ListNotations.

(** ** Constants: the compiled values are the ones OrientFilter.v uses.  The lemmas [cpp_NAME] : B2R Cpp.NAME =
    NAME, one per constant, are generated with the constants into ConstantsCpp.v (twins/emit_constants.cmake;
    FloatCore.v's [tie]). *)

Lemma cpp_orient_constants_finite :
  fin Cpp.orient2d_filter_relative = true /\ fin Cpp.orient2d_filter_absolute = true /\
  fin Cpp.orient3d_filter_relative = true /\ fin Cpp.orient3d_filter_min_difference = true /\
  fin Cpp.orient3d_filter_max_difference = true.
Proof. vm_compute. repeat split. Qed.

Lemma cpp_orient_constants_nonneg :
  nonneg Cpp.orient2d_filter_relative /\ nonneg Cpp.orient2d_filter_absolute /\ nonneg Cpp.orient3d_filter_relative.
Proof. unfold nonneg. vm_compute. auto. Qed.

Ltac orient_constants := rewrite ?cpp_orient2d_filter_relative, ?cpp_orient2d_filter_absolute,
  ?cpp_orient3d_filter_relative, ?cpp_orient3d_filter_min_difference, ?cpp_orient3d_filter_max_difference.

(** ** The C++'s decision over the bits: (det > bound) − (det < −bound). *)

Definition filter_decision_b (det bound : float) : Z :=
  ((if flt bound det then 1 else 0) - (if flt det (fneg bound) then 1 else 0))%Z.

(** A certain answer (+1 or −1) means one comparison held, so the bound (non-negative or NaN) is finite. *)
Lemma filter_decision_b_certain : forall det bound, nonneg bound ->
  filter_decision_b det bound <> 0%Z -> fin bound = true.
Proof.
  intros det bound N H. apply (certifying_bound_finite bound det N).
  unfold filter_decision_b in H. destruct (flt bound det); [left; reflexivity|].
  destruct (flt det (fneg bound)); [right; reflexivity | simpl in H; contradiction].
Qed.

Lemma filter_decision_b_model : forall det bound, fin det = true -> fin bound = true ->
  filter_decision_b det bound = filter_decision (B2R det) (B2R bound).
Proof.
  intros det bound Fd Fb. unfold filter_decision_b, filter_decision.
  rewrite (flt_val bound det Fb Fd), (flt_val det (fneg bound) Fd) by (rewrite fneg_fin; exact Fb).
  rewrite fneg_val. reflexivity.
Qed.

(** An operation whose model result is at most a finite double in magnitude does not overflow. *)
Lemma fsub_dominated : forall x y z, fin x = true -> fin y = true -> fin z = true ->
  Rabs (RN (B2R x - B2R y)) <= B2R z ->
  fin (fsub x y) = true /\ B2R (fsub x y) = RN (B2R x - B2R y).
Proof.
  intros x y z Fx Fy Fz D. apply fsub_fwd; try assumption.
  eapply Rle_lt_trans; [exact D|]. eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow].
Qed.

Lemma fmul_dominated : forall x y z, fin x = true -> fin y = true -> fin z = true ->
  Rabs (RN (B2R x * B2R y)) <= B2R z ->
  fin (fmul x y) = true /\ B2R (fmul x y) = RN (B2R x * B2R y).
Proof.
  intros x y z Fx Fy Fz D. apply fmul_fwd; try assumption.
  eapply Rle_lt_trans; [exact D|]. eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow].
Qed.

(** |RN(a − b)| ≤ RN(|a| + |b|), and |RN(a·b)| ≤ RN(|a|·|b|)-style dominations used below. *)
Lemma RN_minus_abs_le : forall a b, Rabs (RN (a - b)) <= RN (Rabs a + Rabs b).
Proof.
  intros a b. rewrite <- RN_abs. apply RN_le.
  unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra.
Qed.

Lemma RN_plus_abs_le : forall a b, Rabs (RN (a + b)) <= RN (Rabs a + Rabs b).
Proof. intros a b. rewrite <- RN_abs. apply RN_le. apply Rabs_triang. Qed.

Lemma RN_mult_abs_le : forall a b c, Rabs b <= c -> Rabs (RN (a * b)) <= RN (c * Rabs a).
Proof.
  intros a b c H. rewrite <- RN_abs. apply RN_le. rewrite Rabs_mult, Rmult_comm.
  apply Rmult_le_compat_r; [apply Rabs_pos | exact H].
Qed.

(** ** orient2d_filter *)

(** [orient2d_filter(p, q, r, i, j)] on the coordinates it reads: p_i, p_j, q_i, q_j, r_i, r_j. *)
Definition orient2d_filter_b (pi pj qi qj ri rj : float) : Z :=
  let x1 := fsub pi ri in let y2 := fsub qj rj in
  let y1 := fsub pj rj in let x2 := fsub qi ri in
  let left := fmul x1 y2 in let right := fmul y1 x2 in
  let det := fsub left right in
  let bound := fadd (fmul Cpp.orient2d_filter_relative (fadd (fabs left) (fabs right))) Cpp.orient2d_filter_absolute in
  filter_decision_b det bound.

Theorem orient2d_filter_twin_model : forall pi pj qi qj ri rj : float,
  orient2d_filter_b pi pj qi qj ri rj <> 0%Z ->
  fin pi = true /\ fin pj = true /\ fin qi = true /\ fin qj = true /\ fin ri = true /\ fin rj = true /\
  orient2d_filter_b pi pj qi qj ri rj = orient2d_filter (B2R pi) (B2R pj) (B2R qi) (B2R qj) (B2R ri) (B2R rj).
Proof.
  intros pi pj qi qj ri rj H. unfold orient2d_filter_b in *.
  set (left := fmul (fsub pi ri) (fsub qj rj)) in *. set (right := fmul (fsub pj rj) (fsub qi ri)) in *.
  set (S := fadd (fabs left) (fabs right)) in *.
  set (bound := fadd (fmul Cpp.orient2d_filter_relative S) Cpp.orient2d_filter_absolute) in *.
  destruct cpp_orient_constants_nonneg as [N1 [N2 _]].
  assert (Nb : nonneg bound) by (apply fadd_nonneg; [apply fmul_nonneg; [exact N1 | apply fadd_nonneg; apply fabs_nonneg] | exact N2]).
  pose proof (filter_decision_b_certain _ _ Nb H) as Fb. unfold bound, S, left, right in Fb.
  fin_down.
  (* det = left ⊖ right is at most S = |left| ⊕ |right|, a finite double *)
  assert (Fl : fin left = true) by assumption. assert (Fr : fin right = true) by assumption.
  assert (FS : fin S = true) by (unfold S; assumption).
  assert (VS : B2R S = RN (Rabs (B2R left) + Rabs (B2R right))).
  { unfold S. rewrite fadd_val by assumption. rewrite !fabs_val. reflexivity. }
  destruct (fsub_dominated left right S Fl Fr FS) as [Fd Vd].
  { rewrite VS. apply RN_minus_abs_le. }
  repeat split; try assumption.
  rewrite filter_decision_b_model by assumption.
  unfold orient2d_filter, orient2d_det, orient2d_bound, orient2d_left, orient2d_right.
  rewrite Vd. unfold bound, S, left, right. to_model_ops. orient_constants. reflexivity.
Qed.

Theorem orient2d_filter_twin_sound : forall pi pj qi qj ri rj : float,
  (orient2d_filter_b pi pj qi qj ri rj = 1%Z ->
     fin pi = true /\ fin pj = true /\ fin qi = true /\ fin qj = true /\ fin ri = true /\ fin rj = true /\
     0 < orient2d_exact (B2R pi) (B2R pj) (B2R qi) (B2R qj) (B2R ri) (B2R rj)) /\
  (orient2d_filter_b pi pj qi qj ri rj = (-1)%Z ->
     fin pi = true /\ fin pj = true /\ fin qi = true /\ fin qj = true /\ fin ri = true /\ fin rj = true /\
     orient2d_exact (B2R pi) (B2R pj) (B2R qi) (B2R qj) (B2R ri) (B2R rj) < 0).
Proof.
  intros pi pj qi qj ri rj.
  pose proof (orient2d_filter_sound (B2R pi) (B2R pj) (B2R qi) (B2R qj) (B2R ri) (B2R rj)
    (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _))
    as [Sp Sn].
  split; intros E;
    (destruct (orient2d_filter_twin_model pi pj qi qj ri rj ltac:(rewrite E; discriminate))
       as [F1 [F2 [F3 [F4 [F5 [F6 M]]]]]];
     repeat split; try assumption; rewrite M in E; auto).
Qed.

(** ** orient3d_filter *)

(** The range test of one difference: m == 0 || (m >= 2^-300 && m <= 2^300), m = |v|. *)
Definition in_difference_range_b (v : float) : bool :=
  let m := fabs v in
  feq m fzero || (fle Cpp.orient3d_filter_min_difference m && fle m Cpp.orient3d_filter_max_difference).

Definition o3_term_b (z x1 y1 x2 y2 : float) : float := fmul z (fsub (fmul x1 y1) (fmul x2 y2)).
Definition o3_perm_b (z x1 y1 x2 y2 : float) : float :=
  fmul (fadd (fabs (fmul x1 y1)) (fabs (fmul x2 y2))) (fabs z).

(** [orient3d_filter(o, a, b, c)]: the C++ names adx = a.x − o.x, …; the products bdxcdy = bdx·cdy, …; det
    = adz·(bdxcdy − cdxbdy) + bdz·(cdxady − adxcdy) + cdz·(adxbdy − bdxady); the permanent likewise. *)
Definition orient3d_filter_b (o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 : float) : Z :=
  let adx := fsub a0 o0 in let ady := fsub a1 o1 in let adz := fsub a2 o2 in
  let bdx := fsub b0 o0 in let bdy := fsub b1 o1 in let bdz := fsub b2 o2 in
  let cdx := fsub c0 o0 in let cdy := fsub c1 o1 in let cdz := fsub c2 o2 in
  if forallb in_difference_range_b [adx; ady; adz; bdx; bdy; bdz; cdx; cdy; cdz] then
    let det := fadd (fadd (o3_term_b adz bdx cdy cdx bdy) (o3_term_b bdz cdx ady adx cdy))
                    (o3_term_b cdz adx bdy bdx ady) in
    let permanent := fadd (fadd (o3_perm_b adz bdx cdy cdx bdy) (o3_perm_b bdz cdx ady adx cdy))
                          (o3_perm_b cdz adx bdy bdx ady) in
    filter_decision_b det (fmul Cpp.orient3d_filter_relative permanent)
  else 0%Z.

Lemma o3_perm_b_nonneg : forall z x1 y1 x2 y2, nonneg (o3_perm_b z x1 y1 x2 y2).
Proof. intros. unfold o3_perm_b. apply fmul_nonneg; [apply fadd_nonneg; apply fabs_nonneg | apply fabs_nonneg]. Qed.

(** A finite permanent term: its operands are finite, and the term's computation is finite and the model's,
    with |t| ≤ p. *)
Lemma o3_term_b_dominated : forall z x1 y1 x2 y2, fin (o3_perm_b z x1 y1 x2 y2) = true ->
  fin z = true /\ fin x1 = true /\ fin y1 = true /\ fin x2 = true /\ fin y2 = true /\
  fin (o3_term_b z x1 y1 x2 y2) = true /\
  B2R (o3_term_b z x1 y1 x2 y2) = o3_term (B2R z) (B2R x1) (B2R y1) (B2R x2) (B2R y2) /\
  B2R (o3_perm_b z x1 y1 x2 y2) = o3_perm (B2R z) (B2R x1) (B2R y1) (B2R x2) (B2R y2) /\
  Rabs (B2R (o3_term_b z x1 y1 x2 y2)) <= B2R (o3_perm_b z x1 y1 x2 y2).
Proof.
  intros z x1 y1 x2 y2 H. unfold o3_perm_b, o3_term_b in *.
  fin_down.
  set (a := fmul x1 y1) in *. set (b := fmul x2 y2) in *.
  set (s := fadd (fabs a) (fabs b)) in *.
  assert (Fs : fin s = true) by (unfold s; assumption).
  assert (Vs : B2R s = RN (Rabs (B2R a) + Rabs (B2R b))) by (unfold s; rewrite fadd_val by assumption; now rewrite !fabs_val).
  destruct (fsub_dominated a b s ltac:(assumption) ltac:(assumption) Fs) as [Fe Ve].
  { rewrite Vs. apply RN_minus_abs_le. }
  assert (Vp : B2R (fmul s (fabs z)) = RN (B2R s * Rabs (B2R z))) by (rewrite fmul_val by assumption; now rewrite fabs_val).
  assert (Bp : Rabs (RN (B2R z * B2R (fsub a b))) <= B2R (fmul s (fabs z))).
  { rewrite Vp. apply RN_mult_abs_le. rewrite Ve, Vs. apply RN_minus_abs_le. }
  destruct (fmul_dominated z (fsub a b) (fmul s (fabs z)) ltac:(assumption) Fe H) as [Ft Vt]; [exact Bp|].
  repeat split; try assumption.
  - rewrite Vt, Ve. unfold o3_term, a, b. rewrite !fmul_val by assumption. reflexivity.
  - rewrite Vp, Vs. unfold o3_perm, a, b. rewrite !fmul_val by assumption. reflexivity.
  - rewrite Vt. exact Bp.
Qed.

Lemma in_difference_range_b_model : forall v, fin v = true ->
  in_difference_range_b v = in_difference_range (B2R v).
Proof.
  intros v F. unfold in_difference_range_b, in_difference_range.
  destruct cpp_orient_constants_finite as [_ [_ [_ [Fmin Fmax]]]].
  rewrite feq_val by (try rewrite fabs_fin; easy).
  rewrite (fle_val Cpp.orient3d_filter_min_difference (fabs v)) by (try rewrite fabs_fin; easy).
  rewrite (fle_val (fabs v) Cpp.orient3d_filter_max_difference) by (try rewrite fabs_fin; easy).
  rewrite fabs_val. change (B2R fzero) with 0. orient_constants. reflexivity.
Qed.

Lemma forallb_range_model : forall L, Forall (fun v => fin v = true) L ->
  forallb in_difference_range_b L = forallb in_difference_range (map B2R L).
Proof.
  induction L as [|v L IH]; intros F; [reflexivity|]. inversion F as [|? ? Fv FL]; subst.
  simpl. rewrite in_difference_range_b_model by exact Fv. rewrite IH by exact FL. reflexivity.
Qed.

Theorem orient3d_filter_twin_model : forall o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 : float,
  orient3d_filter_b o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 <> 0%Z ->
  (fin o0 = true /\ fin o1 = true /\ fin o2 = true /\ fin a0 = true /\ fin a1 = true /\ fin a2 = true /\
   fin b0 = true /\ fin b1 = true /\ fin b2 = true /\ fin c0 = true /\ fin c1 = true /\ fin c2 = true) /\
  orient3d_filter_b o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 =
    orient3d_filter (B2R o0) (B2R o1) (B2R o2) (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)
      (B2R c0) (B2R c1) (B2R c2).
Proof.
  intros o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 H. unfold orient3d_filter_b in *.
  set (adx := fsub a0 o0) in *. set (ady := fsub a1 o1) in *. set (adz := fsub a2 o2) in *.
  set (bdx := fsub b0 o0) in *. set (bdy := fsub b1 o1) in *. set (bdz := fsub b2 o2) in *.
  set (cdx := fsub c0 o0) in *. set (cdy := fsub c1 o1) in *. set (cdz := fsub c2 o2) in *.
  destruct (forallb in_difference_range_b [adx; ady; adz; bdx; bdy; bdz; cdx; cdy; cdz]) eqn:IR;
    [| contradiction H; reflexivity].
  set (p1 := o3_perm_b adz bdx cdy cdx bdy) in *. set (p2 := o3_perm_b bdz cdx ady adx cdy) in *.
  set (p3 := o3_perm_b cdz adx bdy bdx ady) in *.
  set (P := fadd (fadd p1 p2) p3) in *.
  destruct cpp_orient_constants_nonneg as [_ [_ N3]].
  assert (NB : nonneg (fmul Cpp.orient3d_filter_relative P)).
  { apply fmul_nonneg; [exact N3|]. unfold P. apply fadd_nonneg; [apply fadd_nonneg|]; apply o3_perm_b_nonneg. }
  pose proof (filter_decision_b_certain _ _ NB H) as FB.
  destruct (fmul_fin _ _ FB) as [_ FP]. unfold P in FP.
  destruct (fadd_fin _ _ FP) as [FP12 Fp3]. destruct (fadd_fin _ _ FP12) as [Fp1 Fp2].
  destruct (o3_term_b_dominated _ _ _ _ _ Fp1) as [Fadz [Fbdx [Fcdy [Fcdx [Fbdy [Ft1 [Vt1 [Vp1 Bt1]]]]]]]].
  destruct (o3_term_b_dominated _ _ _ _ _ Fp2) as [Fbdz [_ [Fady [Fadx [_ [Ft2 [Vt2 [Vp2 Bt2]]]]]]]].
  destruct (o3_term_b_dominated _ _ _ _ _ Fp3) as [Fcdz [_ [_ [_ [_ [Ft3 [Vt3 [Vp3 Bt3]]]]]]]].
  fold p1 p2 p3 in Vp1, Vp2, Vp3, Bt1, Bt2, Bt3.
  set (t1 := o3_term_b adz bdx cdy cdx bdy) in *. set (t2 := o3_term_b bdz cdx ady adx cdy) in *.
  set (t3 := o3_term_b cdz adx bdy bdx ady) in *.
  (* the sums of the terms are dominated by the sums of the permanent's terms *)
  assert (VP12 : B2R (fadd p1 p2) = RN (B2R p1 + B2R p2)) by (apply fadd_val; exact FP12).
  assert (P1 : 0 <= B2R p1) by (rewrite Vp1; apply RN_nonneg; apply Rmult_le_pos; [apply RN_nonneg; pose proof (Rabs_pos (RN (B2R bdx * B2R cdy))); pose proof (Rabs_pos (RN (B2R cdx * B2R bdy))); lra | apply Rabs_pos]).
  assert (P2 : 0 <= B2R p2) by (rewrite Vp2; apply RN_nonneg; apply Rmult_le_pos; [apply RN_nonneg; pose proof (Rabs_pos (RN (B2R cdx * B2R ady))); pose proof (Rabs_pos (RN (B2R adx * B2R cdy))); lra | apply Rabs_pos]).
  destruct (fadd_dominated t1 t2 (fadd p1 p2) Ft1 Ft2) as [Ft12 Vt12].
  { rewrite VP12. eapply Rle_trans; [apply RN_plus_abs_le|]. apply RN_le. lra. }
  assert (VP : B2R P = RN (B2R (fadd p1 p2) + B2R p3)) by (apply fadd_val; exact FP).
  assert (B12 : Rabs (B2R (fadd t1 t2)) <= B2R (fadd p1 p2)).
  { rewrite Vt12, VP12. eapply Rle_trans; [apply RN_plus_abs_le|]. apply RN_le. lra. }
  destruct (fadd_dominated (fadd t1 t2) t3 P Ft12 Ft3) as [Fdet Vdet].
  { rewrite VP. eapply Rle_trans; [apply RN_plus_abs_le|]. apply RN_le. lra. }
  (* every difference is finite, hence every input *)
  pose proof (fsub_fin _ _ Fadx). pose proof (fsub_fin _ _ Fady). pose proof (fsub_fin _ _ Fadz).
  pose proof (fsub_fin _ _ Fbdx). pose proof (fsub_fin _ _ Fbdy). pose proof (fsub_fin _ _ Fbdz).
  pose proof (fsub_fin _ _ Fcdx). pose proof (fsub_fin _ _ Fcdy). pose proof (fsub_fin _ _ Fcdz).
  split; [tauto|].
  subst adx ady adz bdx bdy bdz cdx cdy cdz t1 t2 t3 p1 p2 p3 P.
  unfold orient3d_filter, orient3d_values.
  rewrite <- (fsub_val a0 o0 Fadx), <- (fsub_val a1 o1 Fady), <- (fsub_val a2 o2 Fadz),
    <- (fsub_val b0 o0 Fbdx), <- (fsub_val b1 o1 Fbdy), <- (fsub_val b2 o2 Fbdz),
    <- (fsub_val c0 o0 Fcdx), <- (fsub_val c1 o1 Fcdy), <- (fsub_val c2 o2 Fcdz).
  cbn [o3_in_range o3_det o3_bound].
  assert (IRm : forallb in_difference_range (map B2R [fsub a0 o0; fsub a1 o1; fsub a2 o2; fsub b0 o0; fsub b1 o1;
                                                      fsub b2 o2; fsub c0 o0; fsub c1 o1; fsub c2 o2]) = true)
    by (rewrite <- forallb_range_model by (repeat constructor; assumption); exact IR).
  cbn [map] in IRm. rewrite IRm. cbv beta iota.
  rewrite filter_decision_b_model by assumption.
  rewrite Vdet, Vt12, Vt1, Vt2, Vt3.
  rewrite fmul_val by exact FB. rewrite VP, VP12, Vp1, Vp2, Vp3. orient_constants. reflexivity.
Qed.

Theorem orient3d_filter_twin_sound : forall o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 : float,
  (orient3d_filter_b o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 = 1%Z ->
     (fin o0 = true /\ fin o1 = true /\ fin o2 = true /\ fin a0 = true /\ fin a1 = true /\ fin a2 = true /\
      fin b0 = true /\ fin b1 = true /\ fin b2 = true /\ fin c0 = true /\ fin c1 = true /\ fin c2 = true) /\
     0 < orient3d_exact (B2R o0) (B2R o1) (B2R o2) (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)
           (B2R c0) (B2R c1) (B2R c2)) /\
  (orient3d_filter_b o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 = (-1)%Z ->
     (fin o0 = true /\ fin o1 = true /\ fin o2 = true /\ fin a0 = true /\ fin a1 = true /\ fin a2 = true /\
      fin b0 = true /\ fin b1 = true /\ fin b2 = true /\ fin c0 = true /\ fin c1 = true /\ fin c2 = true) /\
     orient3d_exact (B2R o0) (B2R o1) (B2R o2) (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)
       (B2R c0) (B2R c1) (B2R c2) < 0).
Proof.
  intros o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2.
  pose proof (orient3d_filter_sound (B2R o0) (B2R o1) (B2R o2) (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1)
    (B2R b2) (B2R c0) (B2R c1) (B2R c2) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
    (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
    (binary64_B2R _) (binary64_B2R _)) as [Sp Sn].
  split; intros E;
    (destruct (orient3d_filter_twin_model o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 ltac:(rewrite E; discriminate))
       as [F M]; split; [exact F | rewrite M in E; auto]).
Qed.
