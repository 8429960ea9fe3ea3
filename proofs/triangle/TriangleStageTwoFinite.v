(** * tri_drop_guard for every bit pattern: stage 2's low parts of the ray–triangle cascade.

    TriangleMutations.v proves [tri_drop_guard_same_unless_infinite_low]: the twin of fast_triangle_intersection
    with det3_enclosure's guard |l| ≤ largest finite dropped (kernel/src/core/det3_stages.hpp, mutation
    [tri_drop_guard] of proofs/mutation/run.py) answers as the twin whenever the five stage-2 terms satisfy
    [no_infinite_low] (never a finite h with l = ±inf and a finite radius).  This file proves [no_infinite_low]
    for the stage-2 terms as TriangleTwins.v computes them, for every 64-bit pattern of every input, and so
    [tri_drop_guard_same]: the mutated twin equals the twin, unconditionally.

    The invariant (PlaneStageTwoFinite.v's approach, [nf k x]: x is NaN, or finite with |x| ≤ 2^k): wherever h and m
    are finite, l is NaN or below 2^987 (2^991 for den).  Step by step:
    - [cleaf_mul_low_rel]: a leaf product y·z with y.h ⊗ z.h finite, leaves whose low parts are NaN or
      |l| ≤ u|h| ([leaf_ok]: d with l = 0, TwoDiff's (ê, err), [two_diff_leaf_ok]): l NaN or |l| ≤ 32u|p| + 32η;
    - [cterm_sub_low_rel]: the cross difference c = y_j z_k − y_k z_j: l NaN or |l| ≤ 512u·|c.m| + 512η (a
      relative bound: the outer product multiplies it by |x.h|, up to 2^1024);
    - [cleaf_scale_low_nf_rel]: x·c with x.h ⊗ c.h and |x.h| ⊗ c.m finite: l NaN or below 2^983 (u·|x.h|·c.m
      < 2^972);
    - [cterm_add_low_nf], [cterm_sub_low_nf]: a sum with a finite high part adds at most 2 to the exponent;
    - [cdet3_low_nf]: any determinant of [leaf_ok] leaves; [pi_no_infinite_low], [num_lane_no_infinite_low],
      [den_no_infinite_low] (through [no_infinite_low_of_nf]: a finite radius needs a finite m);
    - [tri_drop_guard_same]. *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneClassification FloatCore ConstantsCpp PlaneTwins PlaneLiveness PlaneStageTwoFinite
  TriangleTwins TriangleIntersectTwins TriangleMutations.
Open Scope R_scope.

(** ** From "NaN or finite" to [no_infinite_low] *)

Theorem nan_or_finite_low_no_infinite_low : forall t K A,
  is_nan (clb t) = true \/ fin (clb t) = true -> no_infinite_low t K A.
Proof. intros t K A [N|F] _ Fl Nl; congruence. Qed.

Lemma nf_nan_or_finite : forall k x, nf k x -> is_nan x = true \/ fin x = true.
Proof. intros k x [N|[F _]]; auto. Qed.

(** ** Sums and differences *)

Lemma cterm_add_hi_fin : forall a b, fin (chb (cterm_add_b a b)) = true ->
  fin (chb a) = true /\ fin (chb b) = true.
Proof. intros a b F. exact (fadd_fin _ _ F). Qed.

Lemma cterm_sub_hi_fin : forall a b, fin (chb (cterm_sub_b a b)) = true ->
  fin (chb a) = true /\ fin (chb b) = true.
Proof.
  intros a b F. destruct (fadd_fin _ _ F) as [Fa Fb]. rewrite fneg_fin in Fb. now split.
Qed.

Theorem cterm_add_low_nf : forall k a b, (970 <= k)%Z -> (k + 2 <= 1023)%Z ->
  fin (chb (cterm_add_b a b)) = true -> nf k (clb a) -> nf k (clb b) -> nf (k + 2) (clb (cterm_add_b a b)).
Proof.
  intros k a b K1 K2 F A B. destruct (cterm_add_hi_fin a b F) as [Fa Fb].
  change (clb (cterm_add_b a b)) with (fadd (fadd (clb a) (clb b)) (snd (two_sum_b (chb a) (chb b)))).
  replace (k + 2)%Z with ((k + 1) + 1)%Z by lia. apply nf_add; try lia.
  - apply nf_add; assumption || lia.
  - apply (nf_mono 971); [lia|]. apply small_nf; assumption.
Qed.

Theorem cterm_sub_low_nf : forall k a b, (970 <= k)%Z -> (k + 2 <= 1023)%Z ->
  fin (chb (cterm_sub_b a b)) = true -> nf k (clb a) -> nf k (clb b) -> nf (k + 2) (clb (cterm_sub_b a b)).
Proof.
  intros k a b K1 K2 F A B. pose proof (cterm_sub_hi_fin a b F) as [Fa Fb].
  change (clb (cterm_sub_b a b)) with (fadd (fsub (clb a) (clb b)) (snd (two_sum_b (chb a) (fneg (chb b))))).
  replace (k + 2)%Z with ((k + 1) + 1)%Z by lia. apply nf_add; try lia.
  - apply nf_sub; assumption || lia.
  - apply (nf_mono 971); [lia|]. apply small_nf; try assumption. now rewrite fneg_fin.
Qed.

(** ** Products *)

(** fma(x, y, z) with z NaN or below 2^973 and |x·y| ≤ 2^972: NaN or below 2^974. *)
Lemma ffma_nf_974 : forall x y z, fin x = true -> (is_nan y = true \/ (fin y = true /\ Rabs (B2R x * B2R y) <= bpow radix2 972)) ->
  nf 973 z -> nf 974 (ffma x y z).
Proof.
  intros x y z Fx [Ny|[Fy B1]] [Nz|[Fz Bz]]; [left; now apply ffma_nan_2 .. | left; now apply ffma_nan_3 | right].
  assert (B3 : Rabs (B2R x * B2R y + B2R z) <= bpow radix2 974).
  { eapply Rle_trans; [apply Rabs_triang|].
    assert (E3 : bpow radix2 973 = 2 * bpow radix2 972) by (change 973%Z with (1 + 972)%Z; rewrite bpow_plus; reflexivity).
    assert (E4 : bpow radix2 974 = 4 * bpow radix2 972).
    { change 974%Z with (2 + 972)%Z. rewrite bpow_plus. change (bpow radix2 2) with 4. reflexivity. }
    rewrite E4. rewrite E3 in Bz. pose proof (bpow_ge_0 radix2 972). lra. }
  destruct (fbnd_of_RN 974 _ ltac:(lia) B3) as [L3 R3].
  destruct (ffma_fwd _ _ _ Fx Fy Fz L3) as [Ff Vf]. split; [exact Ff | now rewrite Vf].
Qed.

(** A leaf product y·z, y.h ⊗ z.h finite, leaves with low parts NaN or |l| ≤ u|h|. *)
Theorem cleaf_mul_low_nf : forall yh yl zh zl, fin (fmul yh zh) = true -> small_low yh yl -> small_low zh zl ->
  nf 974 (clb (cleaf_mul_b yh yl zh zl)).
Proof.
  intros yh yl zh zl F Sy Sz. change (clb (cleaf_mul_b yh yl zh zl)) with
    (ffma yh zl (ffma yl zh (ffma yh zh (fneg (fmul yh zh))))).
  destruct (fmul_inv yh zh F) as [Fy [Fz _]].
  apply ffma_nf_974; [exact Fy | | apply low_term_nf; assumption].
  destruct Sz as [N|[Fl L]]; [now left | right; split; [exact Fl|]].
  pose proof (product_small yh zh F) as P. rewrite Rmult_comm, (Rmult_comm (B2R yh)) in P.
  rewrite Rmult_comm. exact (low_product_bound zh zl yh Fz Fy Fl L P).
Qed.

(** A scaled term x·c, x.h ⊗ c.h finite: given |x.h · c.l| ≤ 2^972 (or c.l NaN). *)
Theorem cleaf_scale_low_nf : forall xh xl c, fin (fmul xh (chb c)) = true -> small_low xh xl ->
  (is_nan (clb c) = true \/ (fin (clb c) = true /\ Rabs (B2R xh * B2R (clb c)) <= bpow radix2 972)) ->
  nf 974 (clb (cleaf_scale_b xh xl c)).
Proof.
  intros xh xl c F Sx Sc. change (clb (cleaf_scale_b xh xl c)) with
    (ffma xh (clb c) (ffma xl (chb c) (ffma xh (chb c) (fneg (fmul xh (chb c)))))).
  destruct (fmul_inv xh (chb c) F) as [Fx [Fc _]].
  apply ffma_nf_974; [exact Fx | exact Sc | apply low_term_nf; assumption].
Qed.

(** The leaves: d as (d, 0), and TwoDiff's (ê, err). *)
Lemma zero_small_low : forall x, small_low x fzero.
Proof.
  intros x. right. split; [reflexivity|]. change (B2R fzero) with 0. rewrite Rabs_R0.
  apply Rmult_le_pos; [left; apply u_pos | apply Rabs_pos].
Qed.

(** ** A relative bound on the cross differences' low parts *)

Lemma RN_up : forall x, Rabs (RN x) <= 2 * Rabs x + eta.
Proof.
  intros x. pose proof (RN_err x). pose proof (Rabs_close' x (RN x) _ ltac:(rewrite Rabs_minus_sym; eassumption)).
  pose proof u_small. pose proof u_pos. pose proof (Rabs_pos x).
  assert (u * Rabs x <= / 2 * Rabs x) by (apply Rmult_le_compat_r; lra). lra.
Qed.

Lemma RN_down : forall x, Rabs x <= 2 * Rabs (RN x) + eta.
Proof.
  intros x. pose proof (RN_err_round x). pose proof (Rabs_close' (RN x) x _ H).
  pose proof u_small. pose proof u_pos. pose proof (Rabs_pos (RN x)).
  assert (u * Rabs (RN x) <= / 2 * Rabs (RN x)) by (apply Rmult_le_compat_r; lra). lra.
Qed.

Lemma small_low_product : forall x xl y, fin xl = true -> Rabs (B2R xl) <= u * Rabs (B2R x) ->
  Rabs (B2R xl * B2R y) <= u * Rabs (B2R x * B2R y).
Proof.
  intros x xl y _ L. rewrite !Rabs_mult. pose proof (Rabs_pos (B2R y)).
  rewrite <- Rmult_assoc. apply Rmult_le_compat_r; assumption.
Qed.

Definition rel_low (lam kap : R) (l m : float) : Prop :=
  is_nan l = true \/ (fin l = true /\ Rabs (B2R l) <= lam * Rabs (B2R m) + kap).

(** A leaf product: |l| ≤ 32u·|p| + 32η. *)
Theorem cleaf_mul_low_rel : forall yh yl zh zl, fin (fmul yh zh) = true -> small_low yh yl -> small_low zh zl ->
  rel_low (32 * u) (32 * eta) (clb (cleaf_mul_b yh yl zh zl)) (fmul yh zh).
Proof.
  intros yh yl zh zl F Sy Sz.
  pose proof (cleaf_mul_low_nf yh yl zh zl F Sy Sz) as NF.
  change (clb (cleaf_mul_b yh yl zh zl)) with
    (ffma yh zl (ffma yl zh (ffma yh zh (fneg (fmul yh zh))))) in *.
  destruct (fmul_inv yh zh F) as [Fy [Fz Vp]].
  destruct NF as [N|[Fl _]]; [now left | right; split; [exact Fl|]].
  destruct (ffma_fin _ _ _ Fl) as [_ [Fzl FY]]. destruct (ffma_fin _ _ _ FY) as [Fyl [_ Fr]].
  destruct Sy as [Ny|[_ Ly]]; [destruct yl; discriminate|].
  destruct Sz as [Nz|[_ Lz]]; [destruct zl; discriminate|].
  rewrite (ffma_val _ _ _ Fl), (ffma_val _ _ _ FY), (ffma_val _ _ _ Fr), fneg_val, Vp.
  set (P := B2R yh * B2R zh).
  pose proof (small_low_product yh yl zh Fyl Ly) as B1. fold P in B1.
  pose proof (small_low_product zh zl yh Fzl Lz) as B2. rewrite (Rmult_comm (B2R zh)) in B2. fold P in B2.
  rewrite (Rmult_comm (B2R zl)) in B2.
  pose proof (RN_err P) as E0. pose proof (RN_down P) as D.
  pose proof (RN_up (P + - RN P)) as R0. replace (P + - RN P) with (- (RN P - P)) in R0 by ring.
  rewrite Rabs_Ropp in R0.
  pose proof (RN_up (B2R yl * B2R zh + RN (P + - RN P))) as R1.
  pose proof (Rabs_triang (B2R yl * B2R zh) (RN (P + - RN P))) as T1.
  pose proof (RN_up (B2R yh * B2R zl + RN (B2R yl * B2R zh + RN (P + - RN P)))) as R2.
  pose proof (Rabs_triang (B2R yh * B2R zl) (RN (B2R yl * B2R zh + RN (P + - RN P)))) as T2.
  replace (P + - RN P) with (- (RN P - P)) in * by ring.
  pose proof u_pos. pose proof eta_pos. pose proof u_small.
  assert (U : u * Rabs P <= u * (2 * Rabs (RN P) + eta)) by (apply Rmult_le_compat_l; lra).
  assert (u * eta <= eta) by (rewrite <- (Rmult_1_l eta) at 2; apply Rmult_le_compat_r; lra).
  assert (0 <= u * Rabs (RN P)) by (apply Rmult_le_pos; [lra | apply Rabs_pos]). lra.
Qed.

Lemma bpow_971_mul : forall k, (0 <= k)%Z -> bpow radix2 (971 + k) = bpow radix2 k * bpow radix2 971.
Proof. intros k _. rewrite bpow_plus. ring. Qed.

(** A difference of two terms whose magnitudes are |h| (the leaf products): |l| ≤ 512u·|m| + 512η. *)
Theorem cterm_sub_low_rel : forall a b,
  fin (chb (cterm_sub_b a b)) = true -> fin (cmb (cterm_sub_b a b)) = true ->
  B2R (cmb a) = Rabs (B2R (chb a)) -> B2R (cmb b) = Rabs (B2R (chb b)) ->
  rel_low (32 * u) (32 * eta) (clb a) (chb a) -> rel_low (32 * u) (32 * eta) (clb b) (chb b) ->
  rel_low (512 * u) (512 * eta) (clb (cterm_sub_b a b)) (cmb (cterm_sub_b a b)).
Proof.
  intros a b Fh Fm Ma Mb La Lb. unfold rel_low in La, Lb |- *. pose proof (cterm_sub_hi_fin a b Fh) as [Fa Fb].
  change (clb (cterm_sub_b a b)) with (fadd (fsub (clb a) (clb b)) (snd (two_sum_b (chb a) (fneg (chb b))))).
  change (cmb (cterm_sub_b a b)) with (fadd (cmb a) (cmb b)) in *.
  change (chb (cterm_sub_b a b)) with (fst (two_sum_b (chb a) (fneg (chb b)))) in Fh.
  rewrite two_sum_b_fst_eq in Fh.
  destruct La as [Na|[Fla Ba]]; [left; apply PlaneStageTwoFinite.fadd_nan_l, fsub_nan_l; exact Na|].
  destruct Lb as [Nb|[Flb Bb]]; [left; apply PlaneStageTwoFinite.fadd_nan_l, fsub_nan_r; exact Nb|].
  destruct (two_sum_lo_small (chb a) (fneg (chb b)) Fa ltac:(now rewrite fneg_fin) Fh) as [No|[Flo Bo]];
    [left; apply PlaneStageTwoFinite.fadd_nan_r; exact No|].
  set (lo := snd (two_sum_b (chb a) (fneg (chb b)))) in *. clearbody lo.
  rewrite (fadd_val _ _ Fh), fneg_val in Bo. rewrite (fadd_val _ _ Fm), Ma, Mb.
  set (pa := B2R (chb a)) in *. set (pb := B2R (chb b)) in *.
  pose proof (B2R_lt_overflow (chb a)) as Oa. pose proof (B2R_lt_overflow (chb b)) as Ob. fold pa pb in Oa, Ob.
  pose proof u_pos. pose proof eta_pos. pose proof u_small. pose proof eta_small. pose proof u_bpow_1024.
  pose proof (bpow_gt_0 radix2 971).
  assert (Ua : u * Rabs pa <= bpow radix2 971) by (rewrite <- u_bpow_1024; apply Rmult_le_compat_l; lra).
  assert (Ub : u * Rabs pb <= bpow radix2 971) by (rewrite <- u_bpow_1024; apply Rmult_le_compat_l; lra).
  assert (E978 : bpow radix2 978 = 128 * bpow radix2 971).
  { change 978%Z with (971 + 7)%Z. rewrite bpow_971_mul by lia. reflexivity. }
  (* l_a − l_b *)
  assert (D1 : Rabs (B2R (clb a) - B2R (clb b)) <= bpow radix2 978).
  { unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  destruct (fbnd_of_RN 978 _ ltac:(lia) D1) as [L1 _].
  destruct (fsub_fwd _ _ Fla Flb L1) as [Fs Vs].
  (* the TwoSum low part *)
  pose proof (RN_up (pa + - pb)) as R1.
  assert (T1 : Rabs (pa + - pb) <= Rabs pa + Rabs pb) by (eapply Rle_trans; [apply Rabs_triang | rewrite Rabs_Ropp; lra]).
  assert (Uo : u * Rabs (RN (pa + - pb)) <= u * (2 * (Rabs pa + Rabs pb) + eta)) by (apply Rmult_le_compat_l; lra).
  assert (ue : u * eta <= eta) by (rewrite <- (Rmult_1_l eta) at 2; apply Rmult_le_compat_r; lra).
  pose proof (RN_up (B2R (clb a) - B2R (clb b))) as R2.
  assert (D2 : Rabs (B2R (fsub (clb a) (clb b)) + B2R lo) <= bpow radix2 978 * 4).
  { rewrite Vs. eapply Rle_trans; [apply Rabs_triang|]. lra. }
  assert (E980 : bpow radix2 978 * 4 = bpow radix2 980).
  { change 980%Z with (978 + 2)%Z. rewrite bpow_plus. reflexivity. }
  rewrite E980 in D2. destruct (fbnd_of_RN 980 _ ltac:(lia) D2) as [L2 _].
  destruct (fadd_fwd _ _ Fs Flo L2) as [Fl Vl]. right. split; [exact Fl|]. rewrite Vl.
  pose proof (RN_up (B2R (fsub (clb a) (clb b)) + B2R lo)) as R3.
  pose proof (Rabs_triang (B2R (fsub (clb a) (clb b))) (B2R lo)) as T3. rewrite Vs in R3, T3.
  pose proof (RN_down (Rabs pa + Rabs pb)) as R4.
  rewrite (Rabs_pos_eq (Rabs pa + Rabs pb)) in R4 by (pose proof (Rabs_pos pa); pose proof (Rabs_pos pb); lra).
  assert (U4 : u * (Rabs pa + Rabs pb) <= u * (2 * Rabs (RN (Rabs pa + Rabs pb)) + eta)) by (apply Rmult_le_compat_l; lra).
  assert (T2 : Rabs (B2R (clb a) - B2R (clb b)) <= Rabs (B2R (clb a)) + Rabs (B2R (clb b)))
    by (unfold Rminus; eapply Rle_trans; [apply Rabs_triang | rewrite Rabs_Ropp; lra]).
  assert (0 <= u * Rabs (RN (Rabs pa + Rabs pb))) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  rewrite Vs. lra.
Qed.

(** fma(x, y, z) with |x·y| ≤ 2^k and z NaN or below 2^j, j ≤ k: NaN or below 2^(k+1). *)
Lemma ffma_nf_gen : forall k j x y z, (j <= k)%Z -> (-1074 <= j)%Z -> (k + 1 <= 1023)%Z -> fin x = true ->
  (is_nan y = true \/ (fin y = true /\ Rabs (B2R x * B2R y) <= bpow radix2 k)) ->
  nf j z -> nf (k + 1) (ffma x y z).
Proof.
  intros k j x y z Hjk Hj Hk Fx [Ny|[Fy B1]] [Nz|[Fz Bz]]; [left; now apply ffma_nan_2 .. | left; now apply ffma_nan_3 | right].
  assert (B3 : Rabs (B2R x * B2R y + B2R z) <= bpow radix2 (k + 1)).
  { eapply Rle_trans; [apply Rabs_triang|]. rewrite bpow_plus. change (bpow radix2 1) with 2.
    pose proof (bpow_le radix2 j k Hjk). lra. }
  destruct (fbnd_of_RN (k + 1) _ ltac:(lia) B3) as [L3 R3].
  destruct (ffma_fwd _ _ _ Fx Fy Fz L3) as [Ff Vf]. split; [exact Ff | now rewrite Vf].
Qed.

(** A scaled cross difference x·c: with x.h ⊗ c.h and |x.h| ⊗ c.m finite and c's low part within
    512u·|c.m| + 512η, the low part is NaN or below 2^983. *)
Theorem cleaf_scale_low_nf_rel : forall xh xl c, fin (fmul xh (chb c)) = true ->
  fin (fmul (fabs xh) (cmb c)) = true -> small_low xh xl -> rel_low (512 * u) (512 * eta) (clb c) (cmb c) ->
  nf 983 (clb (cleaf_scale_b xh xl c)).
Proof.
  intros xh xl c F Fm Sx Rc. change (clb (cleaf_scale_b xh xl c)) with
    (ffma xh (clb c) (ffma xl (chb c) (ffma xh (chb c) (fneg (fmul xh (chb c)))))).
  destruct (fmul_inv xh (chb c) F) as [Fx [Fc _]].
  replace 983%Z with (982 + 1)%Z by lia.
  apply (ffma_nf_gen 982 973); try lia; [exact Fx | | apply low_term_nf; assumption].
  destruct Rc as [N|[Fl Bl]]; [now left | right; split; [exact Fl|]].
  destruct (fmul_inv _ _ Fm) as [_ [_ Vm]]. rewrite fabs_val in Vm.
  pose proof (B2R_lt_overflow (fmul (fabs xh) (cmb c))) as O. rewrite Vm in O.
  pose proof (RN_down (Rabs (B2R xh) * B2R (cmb c))) as D. rewrite Rabs_mult, Rabs_Rabsolu in D.
  pose proof (B2R_lt_overflow xh) as Ox.
  pose proof u_pos. pose proof eta_pos. pose proof eta_small. pose proof u_bpow_1024.
  pose proof (Rabs_pos (B2R xh)). pose proof (Rabs_pos (B2R (cmb c))).
  rewrite Rabs_mult.
  assert (P1 : Rabs (B2R xh) * Rabs (B2R (clb c)) <= Rabs (B2R xh) * (512 * u * Rabs (B2R (cmb c)) + 512 * eta))
    by (apply Rmult_le_compat_l; assumption).
  assert (P2 : u * (Rabs (B2R xh) * Rabs (B2R (cmb c))) <= u * (2 * bpow radix2 1024 + eta))
    by (apply Rmult_le_compat_l; lra).
  assert (P3 : eta * Rabs (B2R xh) <= eta * bpow radix2 1024) by (apply Rmult_le_compat_l; lra).
  assert (P4 : eta * bpow radix2 1024 <= 1) by (unfold eta; rewrite <- bpow_plus; change 1 with (bpow radix2 0); apply bpow_le; lia).
  assert (E982 : bpow radix2 982 = 2048 * bpow radix2 971).
  { change 982%Z with (971 + 11)%Z. rewrite bpow_971_mul by lia. reflexivity. }
  assert (u * eta <= eta) by (rewrite <- (Rmult_1_l eta) at 2; apply Rmult_le_compat_r; pose proof u_small; lra).
  pose proof (bpow_ge_0 radix2 971).
  assert (1024 <= bpow radix2 971).
  { change 1024 with (bpow radix2 10). apply bpow_le; lia. }
  lra.
Qed.

(** ** The determinant: every low part NaN or below 2^987 when h and m are finite *)

Definition leaf_ok (h l : float) : Prop := fin h = true -> small_low h l.

Lemma zero_leaf_ok : forall x, leaf_ok x fzero.
Proof. intros x _. apply zero_small_low. Qed.

Lemma two_diff_leaf_ok : forall v o, leaf_ok (fst (two_diff_b v o)) (snd (two_diff_b v o)).
Proof.
  intros v o Fa. unfold two_diff_b in *. rewrite two_sum_b_fst_eq in Fa |- *. destruct (fadd_fin _ _ Fa) as [Fp Fo].
  exact (two_sum_lo_small v (fneg o) Fp Fo Fa).
Qed.

Lemma cross_low_rel : forall yh yl zh zl yh' yl' zh' zl', leaf_ok yh yl -> leaf_ok zh zl -> leaf_ok yh' yl' ->
  leaf_ok zh' zl' ->
  let c := cterm_sub_b (cleaf_mul_b yh yl zh zl) (cleaf_mul_b yh' yl' zh' zl') in
  fin (chb c) = true -> fin (cmb c) = true -> rel_low (512 * u) (512 * eta) (clb c) (cmb c).
Proof.
  intros yh yl zh zl yh' yl' zh' zl' Oy Oz Oy' Oz' c Fh Fm.
  destruct (cterm_sub_hi_fin _ _ Fh) as [F1 F2]. cbn [chb cleaf_mul_b] in F1, F2.
  destruct (fmul_fin _ _ F1) as [Fy Fz]. destruct (fmul_fin _ _ F2) as [Fy' Fz'].
  apply cterm_sub_low_rel; try assumption; try (apply fabs_val);
    apply cleaf_mul_low_rel; auto.
Qed.

Lemma scale_low_nf : forall xh xl yh yl zh zl yh' yl' zh' zl', leaf_ok xh xl -> leaf_ok yh yl -> leaf_ok zh zl ->
  leaf_ok yh' yl' -> leaf_ok zh' zl' ->
  let s := cleaf_scale_b xh xl (cterm_sub_b (cleaf_mul_b yh yl zh zl) (cleaf_mul_b yh' yl' zh' zl')) in
  fin (chb s) = true -> fin (cmb s) = true -> nf 983 (clb s).
Proof.
  intros xh xl yh yl zh zl yh' yl' zh' zl' Ox Oy Oz Oy' Oz' s Fh Fm.
  change (fin (fmul xh (chb (cterm_sub_b (cleaf_mul_b yh yl zh zl) (cleaf_mul_b yh' yl' zh' zl')))) = true) in Fh.
  change (fin (fmul (fabs xh) (cmb (cterm_sub_b (cleaf_mul_b yh yl zh zl) (cleaf_mul_b yh' yl' zh' zl')))) = true) in Fm.
  destruct (fmul_fin _ _ Fh) as [Fx Fc]. destruct (fmul_fin _ _ Fm) as [_ Fcm].
  apply cleaf_scale_low_nf_rel; try assumption; [apply Ox; exact Fx|].
  apply cross_low_rel; assumption.
Qed.

Lemma cterm_add_fin : forall a b, fin (chb (cterm_add_b a b)) = true -> fin (cmb (cterm_add_b a b)) = true ->
  fin (chb a) = true /\ fin (cmb a) = true /\ fin (chb b) = true /\ fin (cmb b) = true.
Proof.
  intros a b Fh Fm. destruct (cterm_add_hi_fin a b Fh) as [Ha Hb]. destruct (fadd_fin _ _ Fm) as [Ma Mb]. auto.
Qed.

Theorem cdet3_low_nf : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  leaf_ok xh0 xl0 -> leaf_ok xh1 xl1 -> leaf_ok xh2 xl2 -> leaf_ok yh0 yl0 -> leaf_ok yh1 yl1 -> leaf_ok yh2 yl2 ->
  leaf_ok zh0 zl0 -> leaf_ok zh1 zl1 -> leaf_ok zh2 zl2 ->
  let t := cdet3_b xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 in
  fin (chb t) = true -> fin (cmb t) = true -> nf 987 (clb t).
Proof.
  intros xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 t Fh Fm.
  unfold t, cdet3_b in *.
  destruct (cterm_add_fin _ _ Fh Fm) as [H01 [M01 [H2 M2]]].
  destruct (cterm_add_fin _ _ H01 M01) as [H0 [M0 [H1 M1]]].
  replace 987%Z with (985 + 2)%Z by lia. apply cterm_add_low_nf; try lia; try assumption.
  - replace 985%Z with (983 + 2)%Z by lia. apply cterm_add_low_nf; try lia; try assumption;
      apply scale_low_nf; assumption.
  - apply (nf_mono 983); [lia|]. apply scale_low_nf; assumption.
Qed.

(** ** [no_infinite_low] for the five stage-2 terms *)

Lemma no_infinite_low_of_nf : forall t K A k, (k <= 1023)%Z ->
  (fin (chb t) = true -> fin (cmb t) = true -> nf k (clb t)) -> no_infinite_low t K A.
Proof.
  intros t K A k _ H Fh Fl Nl. destruct (fin (fadd (fmul K (cmb t)) A)) eqn:Fr; [|reflexivity].
  destruct (fadd_fin _ _ Fr) as [Fp _]. destruct (fmul_fin _ _ Fp) as [_ Fm].
  destruct (H Fh Fm) as [N|[F _]]; congruence.
Qed.

Lemma pi_low_nf : forall o d p q, fin (chb (pi_stage2_b o d p q)) = true -> fin (cmb (pi_stage2_b o d p q)) = true ->
  nf 987 (clb (pi_stage2_b o d p q)).
Proof.
  intros o d p q. unfold pi_stage2_b. apply cdet3_low_nf; first [apply zero_leaf_ok | apply two_diff_leaf_ok].
Qed.

Lemma num_lane_low_nf : forall o a b c, fin (chb (num_stage2_lane_b o a b c)) = true ->
  fin (cmb (num_stage2_lane_b o a b c)) = true -> nf 987 (clb (num_stage2_lane_b o a b c)).
Proof.
  intros o a b c. unfold num_stage2_lane_b. apply cdet3_low_nf; apply two_diff_leaf_ok.
Qed.

Theorem pi_no_infinite_low : forall o d p q K A, no_infinite_low (pi_stage2_b o d p q) K A.
Proof. intros. apply (no_infinite_low_of_nf _ _ _ 987); [lia | apply pi_low_nf]. Qed.

Theorem num_lane_no_infinite_low : forall o a b c K A, no_infinite_low (num_stage2_lane_b o a b c) K A.
Proof. intros. apply (no_infinite_low_of_nf _ _ _ 987); [lia | apply num_lane_low_nf]. Qed.

Theorem den_no_infinite_low : forall o d a b c K A,
  no_infinite_low (cterm_add_b (cterm_add_b (pi_stage2_b o d b c) (pi_stage2_b o d c a)) (pi_stage2_b o d a b)) K A.
Proof.
  intros. apply (no_infinite_low_of_nf _ _ _ 991); [lia|]. intros Fh Fm.
  destruct (cterm_add_fin _ _ Fh Fm) as [H01 [M01 [H2 M2]]].
  destruct (cterm_add_fin _ _ H01 M01) as [H0 [M0 [H1 M1]]].
  replace 991%Z with (989 + 2)%Z by lia. apply cterm_add_low_nf; try lia; try assumption.
  - replace 989%Z with (987 + 2)%Z by lia. apply cterm_add_low_nf; try lia; try assumption; apply pi_low_nf; assumption.
  - apply (nf_mono 987); [lia|]. apply pi_low_nf; assumption.
Qed.

(** ** The mutation: the mutated twin equals the twin for every bit pattern *)

Theorem tri_drop_guard_same : forall want_t want_u (o d a b c : TVec),
  fast_intersection_drop_guard_b want_t want_u o d a b c = fast_intersection_tri_b want_t want_u o d a b c.
Proof.
  intros want_t want_u o d a b c. apply tri_drop_guard_same_unless_infinite_low;
    [ exact (pi_no_infinite_low _ _ _ _ _ _) | exact (pi_no_infinite_low _ _ _ _ _ _)
    | exact (pi_no_infinite_low _ _ _ _ _ _) | exact (num_lane_no_infinite_low _ _ _ _ _ _)
    | exact (den_no_infinite_low _ _ _ _ _ _ _) ].
Qed.
