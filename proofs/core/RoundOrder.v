(** * Rounding to nearest keeps the order (the nearest-hit comparison of a sphere's rounded root).

    The nearest-hit module orders two candidates by their exact t (nearest/nearest_candidates.hpp,
    [compare_candidates]).  A sphere's root t = U ∓ √V is rounded correctly, RN(t), by its own stages
    (sphere/ray_sphere_stages.hpp); against another candidate whose RN(t) is known, the two roundings decide the
    order when they differ, and only equal roundings go on to the exact stage.  That is sound because rounding
    to nearest is monotone (Flocq's [round_le]): RN(a) < RN(b) implies a < b, since b ≤ a would give
    RN(b) ≤ RN(a).

    - [rn_strict_order]: RN(a) < RN(b) → a < b;
    - [rn_equal_or_ordered]: a < b → RN(a) ≤ RN(b) (monotonicity; a < b allows RN(a) = RN(b), so equal
      roundings decide nothing);
    - [rn_compare_distinct]: when RN(a) ≠ RN(b), sign(a − b) = sign(RN(a) − RN(b)) (as [Rcompare]).
    Here RN is binary64 round to nearest with any tie rule [choice] (ties to even, [ZnearestE], is the C++'s and
    Model.v's [RN]: [rne_strict_order], [rne_compare_distinct]), over the reals, without overflow (Model.v).

    With overflow (IEEE-754: a result whose rounding reaches 2^1024 in magnitude is ±inf, the sign of the
    exact value): [ieee_rn x f] says that the double f is the IEEE rounding of the real x (ties to even),
    [binary_normalize_ieee_rn] that Flocq's [binary_normalize] computes one, and [ieee_rn_strict_order] that
    the C++'s [<] on two such doubles (FloatCore.v's [flt], Flocq's [Bltb], −inf < every finite double < +inf)
    implies the order of the exact values. *)

From Coq Require Import Reals Lra ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require FloatCore.
Open Scope R_scope.

(** binary64 round to nearest with the tie rule [choice] (Model.v's [RN] is [choice] = ties to even). *)
Local Notation RN choice := (round radix2 (FLT_exp (-1074) 53) (Znearest choice)).

Local Instance round_order_prec_gt_0 : Prec_gt_0 53.
Proof. reflexivity. Qed.

(** Monotonicity, restated: a < b gives RN(a) ≤ RN(b) (equality possible: both may round to one double). *)
Theorem rn_equal_or_ordered : forall choice a b, a < b -> RN choice a <= RN choice b.
Proof.
  intros choice a b H. apply round_le; auto with typeclass_instances. lra.
Qed.

(** Strict order of the roundings implies strict order of the exact values. *)
Theorem rn_strict_order : forall choice a b, RN choice a < RN choice b -> a < b.
Proof.
  intros choice a b H. destruct (Rlt_or_le a b) as [L|L]; [exact L|].
  exfalso. pose proof (round_le radix2 (FLT_exp (-1074) 53) (Znearest choice) b a L). lra.
Qed.

(** Two exact values whose roundings differ are ordered as their roundings. *)
Theorem rn_compare_distinct : forall choice a b,
  RN choice a <> RN choice b -> Rcompare a b = Rcompare (RN choice a) (RN choice b).
Proof.
  intros choice a b N.
  destruct (Rcompare_spec (RN choice a) (RN choice b)) as [L|E|G].
  - apply Rcompare_Lt. now apply (rn_strict_order choice).
  - contradiction.
  - apply Rcompare_Gt. now apply (rn_strict_order choice).
Qed.

(** The same for ties to even, written as Model.v's [RN]. *)
Theorem rne_strict_order : forall a b,
  round radix2 (FLT_exp (-1074) 53) ZnearestE a < round radix2 (FLT_exp (-1074) 53) ZnearestE b -> a < b.
Proof. intros a b. apply rn_strict_order. Qed.

Theorem rne_compare_distinct : forall a b,
  round radix2 (FLT_exp (-1074) 53) ZnearestE a <> round radix2 (FLT_exp (-1074) 53) ZnearestE b ->
  Rcompare a b = Rcompare (round radix2 (FLT_exp (-1074) 53) ZnearestE a)
                          (round radix2 (FLT_exp (-1074) 53) ZnearestE b).
Proof. intros a b. apply rn_compare_distinct. Qed.

(** ** With overflow to ±inf (IEEE-754 binary64, ties to even). *)

Local Notation RNE := (round radix2 (FLT_exp (-1074) 53) ZnearestE).

(** The double f is the IEEE rounding of the real x: RN(x) when |RN(x)| < 2^1024, else the infinity of x's sign. *)
Definition ieee_rn (x : R) (f : binary_float 53 1024) : Prop :=
  (is_finite f = true /\ B2R f = RNE x) \/
  (bpow radix2 1024 <= Rabs (RNE x) /\ f = B754_infinity (Rlt_bool x 0)).

(** Flocq's [binary_normalize] (the IEEE rounding of m·2^e) is one. *)
Theorem binary_normalize_ieee_rn : forall m e sz,
  ieee_rn (F2R (Float radix2 m e)) (binary_normalize 53 1024 _ _ mode_NE m e sz).
Proof.
  intros m e sz. unfold ieee_rn.
  pose proof (binary_normalize_correct 53 1024 _ _ mode_NE m e sz) as H. cbv zeta in H.
  change (SpecFloat.fexp 53 1024) with (FLT_exp (-1074) 53) in H.
  change (round_mode mode_NE) with ZnearestE in H.
  destruct (Rlt_bool_spec (Rabs (RNE (F2R (Float radix2 m e)))) (bpow radix2 1024)) as [L|L].
  - left. destruct H as [V [F _]]. now split.
  - right. split; [exact L|]. now apply FloatCore.overflow_sign.
Qed.

(** A rounding at least 2^1024 in magnitude has the sign of the exact value. *)
Lemma rne_overflow_neg : forall x, bpow radix2 1024 <= Rabs (RNE x) -> x < 0 -> RNE x <= - bpow radix2 1024.
Proof.
  intros x O N.
  assert (RNE x <= 0).
  { rewrite <- (round_0 radix2 (FLT_exp (-1074) 53) ZnearestE).
    apply round_le; auto with typeclass_instances. lra. }
  rewrite Rabs_left1 in O by exact H. lra.
Qed.

Lemma rne_overflow_pos : forall x, bpow radix2 1024 <= Rabs (RNE x) -> 0 <= x -> bpow radix2 1024 <= RNE x.
Proof.
  intros x O N.
  assert (0 <= RNE x).
  { rewrite <- (round_0 radix2 (FLT_exp (-1074) 53) ZnearestE).
    apply round_le; auto with typeclass_instances. }
  rewrite Rabs_pos_eq in O by exact H. lra.
Qed.

(** The C++'s [fx < fy] on the IEEE roundings of x and y implies x < y (−inf, +inf included). *)
Theorem ieee_rn_strict_order : forall x y fx fy,
  ieee_rn x fx -> ieee_rn y fy -> FloatCore.flt fx fy = true -> x < y.
Proof.
  intros x y fx fy Hx Hy H. unfold FloatCore.flt in H.
  destruct Hx as [[Fx Vx]|[Ox Ix]]; destruct Hy as [[Fy Vy]|[Oy Iy]].
  - rewrite Bltb_correct in H by assumption.
    destruct (Rlt_bool_spec (B2R fx) (B2R fy)) as [L|L]; [|discriminate].
    apply (rn_strict_order (fun t => negb (Z.even t))). now rewrite <- Vx, <- Vy.
  - subst fy. destruct (Rlt_bool_spec y 0) as [N|N].
    + destruct fx as [sx|sx| |sx mx ex Ex]; simpl in Fx, H; try discriminate; destruct sx; discriminate.
    + pose proof (rne_overflow_pos y Oy N).
      pose proof (abs_B2R_lt_emax 53 1024 fx) as A. rewrite Vx in A.
      apply Rabs_def2 in A.
      apply (rn_strict_order (fun t => negb (Z.even t))). lra.
  - subst fx. destruct (Rlt_bool_spec x 0) as [N|N].
    + pose proof (rne_overflow_neg x Ox N).
      pose proof (abs_B2R_lt_emax 53 1024 fy) as A. rewrite Vy in A.
      apply Rabs_def2 in A.
      apply (rn_strict_order (fun t => negb (Z.even t))). lra.
    + destruct fy as [sy|sy| |sy my ey Ey]; simpl in Fy, H; try discriminate; destruct sy; discriminate.
  - subst fx fy.
    destruct (Rlt_bool_spec x 0) as [Nx|Nx]; destruct (Rlt_bool_spec y 0) as [Ny|Ny];
      simpl in H; try discriminate. lra.
Qed.
