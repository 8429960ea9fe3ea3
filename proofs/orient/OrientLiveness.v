(** * Liveness of the orientation filters (kernel/src/orient/orient_predicates.hpp): each does certify, on a stated
    class of inputs.

    The soundness theorems (OrientFilter.v, OrientTwins.v) say that a sign the filters return is the exact
    sign; a filter that always answered 0 would satisfy them.  Here:
    - [orient2d_filter_live] (model): for doubles with |orient2d| > 2^-50·(|X1·Y2| + |Y1·X2|) + 2^-1070, X1 = p_i −
      r_i, Y2 = q_j − r_j, Y1 = p_j − r_j, X2 = q_i − r_i the exact differences, the filter returns the sign
      of orient2d (8u and 32η: twice the filter's 4u and 16η).
    - [orient2d_filter_twin_live]: the same for the twin ([orient2d_filter_b], run against the C++ by the
      runner's [orient2d]), for finite inputs of magnitude ≤ 2^510 (then nothing overflows:
      [orient2d_filter_b_fwd]).
    - [orient3d_filter_live] (model): when every rounded difference passes the range test and |det| >
      2^-47·Σ|Z_k|·(|X_k·Y_k| + |X'_k·Y'_k|) ([orient3d_permanent], the exact permanent of Shewchuk's evaluation
      order: 64u against the filter's 16u), the filter returns the sign of det(a − o, b − o, c − o).
    - Witnesses, by [vm_compute] on the twins: [orient2d_live_witness] (a near-degenerate turn, orient2d =
      2^-40, in the class: the twin certifies +1), [orient2d_uncertain_witness] (three collinear points with one
      nudged by an ulp: the twin answers 0, the exact stage decides), [orient3d_live_witness] (a point 2^-30
      above a triangle's plane: +1) and [orient3d_range_witness] (a difference of 2^-400: out of the range
      test, 0). *)

From Coq Require Import Reals Lra Lia ZArith Bool List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model FloatCore ConstantsCpp OrientFilter OrientTwins.
Open Scope R_scope.
Import ListNotations.

(** ** orient2d, over the model *)

Lemma eta_val : eta = bpow radix2 (-1075).
Proof. reflexivity. Qed.

Lemma bpow_1070_eta : bpow radix2 (-1070) = 32 * eta.
Proof. unfold eta. replace (-1070)%Z with (5 + -1075)%Z by lia. rewrite bpow_plus. simpl. lra. Qed.

Lemma bpow_50_u : bpow radix2 (-50) = 8 * u.
Proof. rewrite u_val. simpl. lra. Qed.

Theorem orient2d_filter_live : forall pi pj qi qj ri rj,
  binary64 pi -> binary64 pj -> binary64 qi -> binary64 qj -> binary64 ri -> binary64 rj ->
  let O := orient2d_exact pi pj qi qj ri rj in
  bpow radix2 (-50) * (Rabs ((pi - ri) * (qj - rj)) + Rabs ((pj - rj) * (qi - ri))) + bpow radix2 (-1070)
    < Rabs O ->
  orient2d_filter pi pj qi qj ri rj = (if Rlt_bool 0 O then 1 else -1)%Z.
Proof.
  intros pi pj qi qj ri rj Hpi Hpj Hqi Hqj Hri Hrj O Hc.
  rewrite bpow_50_u, bpow_1070_eta in Hc.
  pose proof (orient2d_error pi pj qi qj ri rj Hpi Hpj Hqi Hqj Hri Hrj) as Err. cbv zeta in Err.
  fold O in Err.
  assert (EL : Rabs (orient2d_left pi pj qi qj ri rj - (pi - ri) * (qj - rj))
               <= (3 * u + 9 * (u * u)) * Rabs (orient2d_left pi pj qi qj ri rj) + 2 * eta).
  { apply prod_close with (x := RN (pi - ri)) (y := RN (qj - rj));
      [apply RN_minus_err; assumption | apply RN_minus_err; assumption | apply RN_err_round | pose proof eta_pos; lra]. }
  assert (ER : Rabs (orient2d_right pi pj qi qj ri rj - (pj - rj) * (qi - ri))
               <= (3 * u + 9 * (u * u)) * Rabs (orient2d_right pi pj qi qj ri rj) + 2 * eta).
  { apply prod_close with (x := RN (pj - rj)) (y := RN (qi - ri));
      [apply RN_minus_err; assumption | apply RN_minus_err; assumption | apply RN_err_round | pose proof eta_pos; lra]. }
  unfold orient2d_filter, orient2d_det, orient2d_bound.
  set (L := orient2d_left pi pj qi qj ri rj) in *. set (R := orient2d_right pi pj qi qj ri rj) in *.
  set (P := Rabs ((pi - ri) * (qj - rj))) in *. set (Q := Rabs ((pj - rj) * (qi - ri))) in *.
  assert (BL : binary64 L) by apply binary64_RN. assert (BR : binary64 R) by apply binary64_RN.
  assert (CL : Rabs L <= P + Rabs (L - (pi - ri) * (qj - rj))) by (apply Rabs_close; lra).
  assert (CR : Rabs R <= Q + Rabs (R - (pj - rj) * (qi - ri))) by (apply Rabs_close; lra).
  pose proof (RN_minus_err L R BL BR) as ED.
  (* the bound from above *)
  pose proof (Rabs_pos L). pose proof (Rabs_pos R).
  assert (ES : Rabs (RN (Rabs L + Rabs R) - (Rabs L + Rabs R)) <= u * Rabs (Rabs L + Rabs R))
    by (apply RN_plus_err; apply binary64_abs; assumption).
  rewrite (Rabs_nonneg_eq (Rabs L + Rabs R)) in ES by lra. apply Rabs_bounds in ES.
  set (S' := RN (Rabs L + Rabs R)) in *.
  assert (PS : 0 <= S') by (unfold S'; apply RN_nonneg; lra).
  pose proof (RN_err (orient2d_filter_relative * S')) as EM.
  rewrite orient2d_relative_u in EM |- *.
  rewrite (Rabs_nonneg_eq (4 * u * S')) in EM by (pose proof u_pos; nra). apply Rabs_bounds in EM.
  set (M := RN (4 * u * S')) in *.
  assert (PM : 0 <= M) by (unfold M; apply RN_nonneg; pose proof u_pos; nra).
  assert (EB : Rabs (RN (M + orient2d_filter_absolute) - (M + orient2d_filter_absolute))
               <= u * Rabs (M + orient2d_filter_absolute))
    by (apply RN_plus_err; [apply binary64_RN | unfold orient2d_filter_absolute; apply binary64_bpow; lia]).
  rewrite orient2d_absolute_eta in EB |- *. pose proof eta_pos.
  rewrite (Rabs_nonneg_eq (M + 16 * eta)) in EB by lra. apply Rabs_bounds in EB.
  set (B := RN (M + 16 * eta)) in *.
  assert (PB : 0 <= B) by (unfold B; apply RN_nonneg; lra).
  assert (M1 : u * S' <= u * ((1 + u) * (Rabs L + Rabs R))) by (pose proof u_pos; apply Rmult_le_compat_l; lra).
  assert (M2 : u * (4 * u * S') <= u * (4 * u * ((1 + u) * (Rabs L + Rabs R))))
    by (pose proof u_pos; apply Rmult_le_compat_l; [lra | apply Rmult_le_compat_l; lra]).
  assert (M3 : u * (M + 16 * eta) <= u * ((1 + u) * (4 * u * ((1 + u) * (Rabs L + Rabs R))) + eta + 16 * eta))
    by (pose proof u_pos; apply Rmult_le_compat_l; lra).
  apply Rabs_bounds in Err. pose proof u_pos as Up. pose proof u_le as Ul.
  unfold filter_decision.
  destruct (Rlt_bool_spec 0 O) as [Op|On].
  - (* O > 0: L − R > 0 and D > B *)
    rewrite Rabs_nonneg_eq in Hc by lra.
    assert (Pos : 0 < L - R) by (rewrite u_val in *; lra).
    rewrite (Rabs_nonneg_eq (L - R)) in ED by lra. apply Rabs_bounds in ED.
    assert (Hd : B < RN (L - R)) by (clearbody L R S' M B P Q; rewrite u_val in *; lra).
    rewrite (Rlt_bool_true _ _ Hd), Rlt_bool_false by lra. reflexivity.
  - assert (Onz : O < 0).
    { destruct (Rle_lt_or_eq_dec O 0 On) as [N|Z]; [exact N|].
      rewrite Z, Rabs_R0 in Hc. assert (0 <= P) by (unfold P; apply Rabs_pos).
      assert (0 <= Q) by (unfold Q; apply Rabs_pos). rewrite u_val in *. lra. }
    rewrite Rabs_left in Hc by lra.
    assert (Neg : L - R < 0) by (rewrite u_val in *; lra).
    rewrite (Rabs_left (L - R)) in ED by lra. apply Rabs_bounds in ED.
    assert (Hd : RN (L - R) < - B) by (clearbody L R S' M B P Q; rewrite u_val in *; lra).
    rewrite Rlt_bool_false by lra. rewrite (Rlt_bool_true _ _ Hd). reflexivity.
Qed.

(** ** orient3d, over the model *)

Lemma bpow_47_u : bpow radix2 (-47) = 64 * u.
Proof. rewrite u_val. simpl. lra. Qed.

Theorem orient3d_filter_live : forall o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 a0 -> binary64 a1 -> binary64 a2 ->
  binary64 b0 -> binary64 b1 -> binary64 b2 -> binary64 c0 -> binary64 c1 -> binary64 c2 ->
  o3_in_range (orient3d_values o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2) = true ->
  let det := orient3d_exact o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 in
  bpow radix2 (-47) * orient3d_permanent o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 < Rabs det ->
  orient3d_filter o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 = (if Rlt_bool 0 det then 1 else -1)%Z.
Proof.
  intros o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 Bo0 Bo1 Bo2 Ba0 Ba1 Ba2 Bb0 Bb1 Bb2 Bc0 Bc1 Bc2 IR det Hc.
  destruct (orient3d_error_bounds o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 Bo0 Bo1 Bo2 Ba0 Ba1 Ba2 Bb0 Bb1 Bb2 Bc0 Bc1
              Bc2 IR) as [Q [PQ [E [L [U K]]]]].
  fold det in E. rewrite bpow_47_u in Hc.
  unfold orient3d_filter. rewrite IR. unfold filter_decision.
  set (D := o3_det (orient3d_values o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2)) in *.
  set (B := o3_bound (orient3d_values o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2)) in *.
  set (Pe := orient3d_permanent o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2) in *.
  apply Rabs_bounds in E. pose proof u_pos as Up.
  clearbody D B Pe det.
  destruct (Rlt_bool_spec 0 det) as [Op|On].
  - rewrite Rabs_nonneg_eq in Hc by lra.
    rewrite Rlt_bool_true by (rewrite u_val in *; lra). rewrite Rlt_bool_false by (rewrite u_val in *; lra).
    reflexivity.
  - assert (Pe0 : 0 <= Pe) by (rewrite u_val in *; lra).
    assert (Onz : det < 0).
    { destruct (Rle_lt_or_eq_dec det 0 On) as [N|Z]; [exact N|].
      rewrite Z, Rabs_R0 in Hc. rewrite u_val in *. lra. }
    rewrite Rabs_left in Hc by lra.
    rewrite Rlt_bool_false by (rewrite u_val in *; lra). rewrite Rlt_bool_true by (rewrite u_val in *; lra).
    reflexivity.
Qed.

(** ** orient2d over the twin: finite inputs of magnitude ≤ 2^510 do not overflow *)

Lemma bnd_sub : forall x y k, Rabs x <= bpow radix2 k -> Rabs y <= bpow radix2 k ->
  Rabs (x - y) <= bpow radix2 (k + 1).
Proof.
  intros x y k Hx Hy. rewrite bpow_plus. change (bpow radix2 1) with 2.
  unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra.
Qed.

Lemma bnd_add_abs : forall x y k, Rabs x <= bpow radix2 k -> Rabs y <= bpow radix2 k ->
  Rabs (Rabs x + Rabs y) <= bpow radix2 (k + 1).
Proof.
  intros x y k Hx Hy. rewrite bpow_plus. change (bpow radix2 1) with 2.
  pose proof (Rabs_pos x). pose proof (Rabs_pos y). rewrite Rabs_nonneg_eq by lra. lra.
Qed.

Lemma bnd_add : forall x y k, Rabs x <= bpow radix2 k -> Rabs y <= bpow radix2 k ->
  Rabs (x + y) <= bpow radix2 (k + 1).
Proof.
  intros x y k Hx Hy. rewrite bpow_plus. change (bpow radix2 1) with 2.
  eapply Rle_trans; [apply Rabs_triang|]. lra.
Qed.

Lemma bnd_mul : forall x y k l, Rabs x <= bpow radix2 k -> Rabs y <= bpow radix2 l ->
  Rabs (x * y) <= bpow radix2 (k + l).
Proof.
  intros x y k l Hx Hy. rewrite Rabs_mult, bpow_plus.
  apply Rmult_le_compat; try apply Rabs_pos; assumption.
Qed.

Lemma bnd_RN : forall x k, (-1074 <= k)%Z -> Rabs x <= bpow radix2 k -> Rabs (RN x) <= bpow radix2 k.
Proof.
  intros x k Hk H. rewrite <- RN_abs. rewrite <- (RN_binary64 (bpow radix2 k)) by (apply binary64_bpow; exact Hk).
  apply RN_le. exact H.
Qed.

Lemma bnd_ok : forall x k, (-1074 <= k)%Z -> (k < 1024)%Z -> Rabs x <= bpow radix2 k ->
  Rabs (RN x) < bpow radix2 1024.
Proof.
  intros x k Hk Hl H. eapply Rle_lt_trans; [apply (bnd_RN x k Hk H)|]. apply bpow_lt. exact Hl.
Qed.

Theorem orient2d_filter_b_fwd : forall pi pj qi qj ri rj : float,
  fin pi = true -> fin pj = true -> fin qi = true -> fin qj = true -> fin ri = true -> fin rj = true ->
  Rabs (B2R pi) <= bpow radix2 510 -> Rabs (B2R pj) <= bpow radix2 510 -> Rabs (B2R qi) <= bpow radix2 510 ->
  Rabs (B2R qj) <= bpow radix2 510 -> Rabs (B2R ri) <= bpow radix2 510 -> Rabs (B2R rj) <= bpow radix2 510 ->
  orient2d_filter_b pi pj qi qj ri rj = orient2d_filter (B2R pi) (B2R pj) (B2R qi) (B2R qj) (B2R ri) (B2R rj).
Proof.
  intros pi pj qi qj ri rj Fpi Fpj Fqi Fqj Fri Frj Bpi Bpj Bqi Bqj Bri Brj.
  assert (D : forall x y, fin x = true -> fin y = true -> Rabs (B2R x) <= bpow radix2 510 ->
            Rabs (B2R y) <= bpow radix2 510 ->
            fin (fsub x y) = true /\ B2R (fsub x y) = RN (B2R x - B2R y) /\ Rabs (B2R (fsub x y)) <= bpow radix2 511).
  { intros x y Fx Fy Bx By. pose proof (bnd_sub _ _ _ Bx By) as S.
    destruct (fsub_fwd x y Fx Fy (bnd_ok _ 511 ltac:(lia) ltac:(lia) S)) as [F V].
    repeat split; [exact F | exact V | rewrite V; apply bnd_RN; [lia | exact S]]. }
  destruct (D pi ri) as [Fx1 [Vx1 Bx1]]; try assumption. destruct (D qj rj) as [Fy2 [Vy2 By2]]; try assumption.
  destruct (D pj rj) as [Fy1 [Vy1 By1]]; try assumption. destruct (D qi ri) as [Fx2 [Vx2 Bx2]]; try assumption.
  assert (M : forall x y, fin x = true -> fin y = true -> Rabs (B2R x) <= bpow radix2 511 ->
            Rabs (B2R y) <= bpow radix2 511 ->
            fin (fmul x y) = true /\ B2R (fmul x y) = RN (B2R x * B2R y) /\ Rabs (B2R (fmul x y)) <= bpow radix2 1022).
  { intros x y Fx Fy Bx By. pose proof (bnd_mul _ _ _ _ Bx By) as S.
    destruct (fmul_fwd x y Fx Fy (bnd_ok _ 1022 ltac:(lia) ltac:(lia) S)) as [F V].
    repeat split; [exact F | exact V | rewrite V; apply bnd_RN; [lia | exact S]]. }
  destruct (M (fsub pi ri) (fsub qj rj)) as [FL [VL BL]]; try assumption.
  destruct (M (fsub pj rj) (fsub qi ri)) as [FR [VR BR]]; try assumption.
  unfold orient2d_filter_b.
  set (L := fmul (fsub pi ri) (fsub qj rj)) in *. set (R := fmul (fsub pj rj) (fsub qi ri)) in *.
  destruct (fsub_fwd L R FL FR (bnd_ok _ 1023 ltac:(lia) ltac:(lia) (bnd_sub _ _ _ BL BR))) as [Fd Vd].
  assert (BS := bnd_add_abs _ _ _ BL BR).
  destruct (fadd_fwd (fabs L) (fabs R) ltac:(rewrite fabs_fin; exact FL) ltac:(rewrite fabs_fin; exact FR)
              ltac:(rewrite !fabs_val; exact (bnd_ok _ 1023 ltac:(lia) ltac:(lia) BS))) as [FS VS].
  rewrite !fabs_val in VS.
  destruct cpp_orient_constants_finite as [FA [FU _]].
  assert (BA : Rabs (B2R Cpp.orient2d_filter_relative) <= bpow radix2 (-51)).
  { rewrite cpp_orient2d_filter_relative. unfold orient2d_filter_relative. rewrite Rabs_nonneg_eq by apply bpow_ge_0. lra. }
  assert (BS' : Rabs (B2R (fadd (fabs L) (fabs R))) <= bpow radix2 1023) by (rewrite VS; apply bnd_RN; [lia | exact BS]).
  pose proof (bnd_mul _ _ _ _ BA BS') as BAS.
  destruct (fmul_fwd _ _ FA FS (bnd_ok _ (-51 + 1023) ltac:(lia) ltac:(lia) BAS)) as [FAS VAS].
  assert (BAS' : Rabs (B2R (fmul Cpp.orient2d_filter_relative (fadd (fabs L) (fabs R)))) <= bpow radix2 972)
    by (rewrite VAS; apply bnd_RN; [lia | exact BAS]).
  assert (BU : Rabs (B2R Cpp.orient2d_filter_absolute) <= bpow radix2 972).
  { rewrite cpp_orient2d_filter_absolute. unfold orient2d_filter_absolute. rewrite Rabs_nonneg_eq by apply bpow_ge_0.
    apply bpow_le. lia. }
  destruct (fadd_fwd _ _ FAS FU (bnd_ok _ 973 ltac:(lia) ltac:(lia) (bnd_add _ _ _ BAS' BU))) as [FB VB].
  rewrite filter_decision_b_model by assumption.
  unfold orient2d_filter, orient2d_det, orient2d_bound, orient2d_left, orient2d_right.
  rewrite VB, VAS, VS, Vd, VL, VR, Vx1, Vy2, Vy1, Vx2, cpp_orient2d_filter_relative, cpp_orient2d_filter_absolute.
  reflexivity.
Qed.

Theorem orient2d_filter_twin_live : forall pi pj qi qj ri rj : float,
  fin pi = true -> fin pj = true -> fin qi = true -> fin qj = true -> fin ri = true -> fin rj = true ->
  Rabs (B2R pi) <= bpow radix2 510 -> Rabs (B2R pj) <= bpow radix2 510 -> Rabs (B2R qi) <= bpow radix2 510 ->
  Rabs (B2R qj) <= bpow radix2 510 -> Rabs (B2R ri) <= bpow radix2 510 -> Rabs (B2R rj) <= bpow radix2 510 ->
  let O := orient2d_exact (B2R pi) (B2R pj) (B2R qi) (B2R qj) (B2R ri) (B2R rj) in
  bpow radix2 (-50) * (Rabs ((B2R pi - B2R ri) * (B2R qj - B2R rj)) + Rabs ((B2R pj - B2R rj) * (B2R qi - B2R ri)))
    + bpow radix2 (-1070) < Rabs O ->
  orient2d_filter_b pi pj qi qj ri rj = (if Rlt_bool 0 O then 1 else -1)%Z.
Proof.
  intros pi pj qi qj ri rj Fpi Fpj Fqi Fqj Fri Frj Bpi Bpj Bqi Bqj Bri Brj O Hc.
  rewrite orient2d_filter_b_fwd by assumption.
  apply orient2d_filter_live; try apply binary64_B2R. exact Hc.
Qed.

(** ** Witnesses, on the twins *)

Definition w_zero : float := of_bits 0.                        (* 0 *)
Definition w_one : float := of_bits 4607182418800017408.       (* 1 *)
Definition w_two : float := of_bits 4611686018427387904.       (* 2 *)
Definition w_two_40 : float := of_bits 4611686018427389952.    (* 2 + 2^-40 *)
Definition w_three : float := of_bits 4613937818241073152.     (* 3 *)
Definition w_three_51 : float := of_bits 4613937818241073153.  (* 3 + 2^-51 *)

(** p = (1, 1), q = (2, 2 + 2^-40), r = (0, 0): orient2d = 2^-40, in [orient2d_filter_twin_live]'s class; the twin
    certifies +1. *)
Lemma orient2d_live_witness : orient2d_filter_b w_one w_one w_two w_two_40 w_zero w_zero = 1%Z.
Proof. vm_compute. reflexivity. Qed.

Lemma orient2d_live_witness_in_class :
  let O := orient2d_exact (B2R w_one) (B2R w_one) (B2R w_two) (B2R w_two_40) (B2R w_zero) (B2R w_zero) in
  bpow radix2 (-50) * (Rabs ((B2R w_one - B2R w_zero) * (B2R w_two_40 - B2R w_zero)) +
                       Rabs ((B2R w_one - B2R w_zero) * (B2R w_two - B2R w_zero)))
    + bpow radix2 (-1070) < Rabs O /\ 0 < O.
Proof.
  intros O. unfold O, orient2d_exact.
  assert (V0 : B2R w_zero = 0) by reflexivity.
  assert (V1 : B2R w_one = 1) by (float_real w_one; lra).
  assert (V2 : B2R w_two = 2) by (float_real w_two; lra).
  assert (V3 : B2R w_two_40 = 2 + bpow radix2 (-40)) by (float_real w_two_40; simpl bpow; lra).
  rewrite V0, V1, V2, V3. replace ((1 - 0) * (2 + bpow radix2 (-40) - 0) - (1 - 0) * (2 - 0)) with (bpow radix2 (-40)) by ring.
  rewrite !Rabs_nonneg_eq by (pose proof (bpow_ge_0 radix2 (-40)); lra).
  simpl bpow. split; lra.
Qed.

(** p = (1, 1), q = (3, 3 + 2^-51), r = (0, 0): orient2d = 2^-51, below the filter's bound (about 6·2^-51): the
    twin answers 0 and the exact stage decides. *)
Lemma orient2d_uncertain_witness : orient2d_filter_b w_one w_one w_three w_three_51 w_zero w_zero = 0%Z.
Proof. vm_compute. reflexivity. Qed.

Definition w_quarter : float := of_bits 4598175219545276416.    (* 1/4 *)
Definition w_m2_30 : float := of_bits 13695446466833678336.     (* −2^-30 *)
Definition w_m2_400 : float := of_bits 12029114604706594816.    (* −2^-400 *)

(** o = (1/4, 1/4, −2^-30) just below the triangle a = (1, 0, 0), b = (0, 1, 0), c = (0, 0, 0), inside it:
    det(a − o, b − o, c − o) = 2^-30; the twin certifies +1. *)
Lemma orient3d_live_witness :
  orient3d_filter_b w_quarter w_quarter w_m2_30 w_one w_zero w_zero w_zero w_one w_zero w_zero w_zero w_zero = 1%Z.
Proof. vm_compute. reflexivity. Qed.

(** The same with o 2^-400 below the plane: a difference of 2^-400 fails the range test, the twin answers 0 (the
    exact stage decides). *)
Lemma orient3d_range_witness :
  orient3d_filter_b w_quarter w_quarter w_m2_400 w_one w_zero w_zero w_zero w_one w_zero w_zero w_zero w_zero = 0%Z.
Proof. vm_compute. reflexivity. Qed.
