(** * tri_drop_guard: stage 2's low parts of the ray–triangle cascade, for every bit pattern (partial).

    TriangleMutations.v proves [tri_drop_guard_same_unless_infinite_low]: the twin of
    fast_triangle_intersection with det3_enclosure's guard |l| ≤ largest finite dropped answers as the twin
    whenever the five stage-2 terms satisfy [no_infinite_low] (never a finite h with l = ±inf and a finite
    radius).  This file proves, for every 64-bit pattern, the steps of that invariant that need no relative
    bound (the approach of StageTwoFinite.v: "NaN, or finite and below 2^k", [nf]):

    - [nan_or_finite_low_no_infinite_low]: a low part that is NaN or finite satisfies [no_infinite_low];
    - [cleaf_mul_low_nf]: a leaf product y·z with y.h ⊗ z.h finite (and leaves whose low parts are NaN or
      |l| ≤ u|h|, as TwoDiff's are: [two_diff_small_low]) has a low part NaN or below 2^974;
    - [cterm_add_low_nf], [cterm_sub_low_nf]: a sum or difference with a finite high part of terms whose low
      parts are NaN or below 2^k has a low part NaN or below 2^(k+2) (k ≥ 970);
    - [cleaf_scale_low_nf]: x·c with x.h ⊗ c.h finite has a low part NaN or below 2^975 when c's low part is
      NaN or |x.h · c.l| ≤ 2^972 (in the reals).

    Not proved here (proofs/README.md, "What remains"): the hypothesis of [cleaf_scale_low_nf] for the cross
    differences c = y_j z_k − y_k z_j of the stage-2 terms — it needs a relative bound |c.l| ≤ λ·c.m + κ
    (with |x.h|·c.m < 2^1025 from a finite magnitude x.h ⊗ c.m), not an absolute one — and hence
    [no_infinite_low] for πa, πb, πc, num, den and the unconditional [tri_drop_guard_same]. *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model Classification FloatCore ConstantsCpp Twins Liveness StageTwoFinite
  TriangleTwins TriangleMutations.
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
