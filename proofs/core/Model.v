(** * The floating-point model every proof in this directory uses.

    binary64, round to nearest with ties to even, gradual underflow (subnormals), written as Flocq's
    [round radix2 (FLT_exp (-1074) 53) ZnearestE].  The model has no largest exponent: it is the IEEE-754
    computation for as long as no intermediate result reaches 2^1024 in magnitude.  proofs/README.md
    ("Overflow") explains why every certifying branch of the C++ code implies that.

    Each C++ operation [a + b], [a - b], [a * b], [a / b] on doubles is one [RN] of the exact real
    result; [std::fma(a, b, c)] is [RN (a * b + c)] (one rounding); [std::fabs] and unary minus are
    exact.  This holds because the certified code is compiled with -ffp-contract=off, without
    -ffast-math, with SSE2 (FLT_EVAL_METHOD == 0), and runs only when MXCSR says round-to-nearest and no
    flush-to-zero (kernel/src/plane/plane_api.cpp); see proofs/README.md ("Assumptions").

    This file: the model, the branch-free sign encoding of sign.hpp ([sign_lanes]), the error-free
    transformations of kernel/src/core/eft.hpp with their exactness theorems, and the
    rounding-error lemmas the stage proofs are built from.

    The certified routines are templates over a lane type (double, or Lanes8, eight doubles;
    kernel/src/core/lanes.hpp).  The model is the scalar instantiation; each lane of Lanes8 performs
    the same IEEE operations on its own query (proofs/README.md, "Lanes"). *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core Plus_error Mult_error Relative Pff2Flocq.
From Raykernel Require Import Constants.
Open Scope R_scope.

Notation binary64 := (generic_format radix2 (FLT_exp (-1074) 53)).
Notation RN := (round radix2 (FLT_exp (-1074) 53) ZnearestE).
Notation u := unit_roundoff.

Global Instance binary64_prec_gt_0 : Prec_gt_0 53.
Proof. reflexivity. Qed.

(** binary32 (the BVH's stored boxes, box/RayBox.v; spawned coordinates, spawn/SpawnRounding.v): every binary32
    value is a binary64 value. *)
Notation binary32 := (generic_format radix2 (FLT_exp (-149) 24)).

Global Instance binary32_prec_gt_0 : Prec_gt_0 24.
Proof. reflexivity. Qed.

Lemma binary32_binary64 : forall x, binary32 x -> binary64 x.
Proof.
  intros x Hx. apply generic_inclusion_mag with (fexp1 := FLT_exp (-149) 24); [|exact Hx].
  intros _. unfold FLT_exp. lia.
Qed.

(** Half the smallest subnormal: the largest absolute error of a rounding in the subnormal range. *)
Definition eta : R := bpow radix2 (-1075).

(** ** The C++ operations of eft.hpp, in the source's evaluation order. *)

(** [std::fma(a, b, c)]: one rounding of the exact a·b + c. *)
Definition fma (a b c : R) : R := RN (a * b + c).

(** [two_sum(a, b)] (Knuth): the pair (hi, lo). *)
Definition two_sum (a b : R) : R * R :=
  let s := RN (a + b) in
  let b_virtual := RN (s - a) in
  let a_virtual := RN (s - b_virtual) in
  let b_roundoff := RN (b - b_virtual) in
  let a_roundoff := RN (a - a_virtual) in
  (s, RN (a_roundoff + b_roundoff)).

(** [two_diff(a, b)] is [two_sum(a, -b)]. *)
Definition two_diff (a b : R) : R * R := two_sum a (- b).

(** [two_prod(a, b)]: (a ⊗ b, fma(a, b, -(a ⊗ b))). *)
Definition two_prod (a b : R) : R * R :=
  let p := RN (a * b) in (p, fma a b (- p)).

(** ** The answer of a sign stage (kernel/src/core/sign.hpp). *)
Inductive sign := Negative | Zero | Positive | Uncertain.

(** What a stage's answer claims about the exact real value: [Uncertain] claims nothing. *)
Definition certifies (s : sign) (x : R) : Prop :=
  match s with
  | Negative => x < 0
  | Zero => x = 0
  | Positive => 0 < x
  | Uncertain => True
  end.

(** [sign_lanes(above, below)] (sign.hpp): the branch-free sign of the lane-templated routines
    (dot3_filter_lanes, enclosure_sign_lanes): s = [above] − [below], then s + 2·[s = 0], i.e. the
    values of [enum class Sign] (−1, +1, and 2 for uncertain) as integers.  (For Lanes8 the code
    computes below − above on masks that are −1 where true, which gives the same integers per lane.) *)
Definition uncertain_lane : Z := 2.

Definition sign_lanes (above below : bool) : Z :=
  let s := (Z.b2z above - Z.b2z below)%Z in (s + uncertain_lane * Z.b2z (Z.eqb s 0))%Z.

(** [static_cast<Sign>(i)] for the integers the lane routines produce (−1, 0, +1, 2). *)
Definition sign_from_Z (i : Z) : sign :=
  match i with
  | Zneg xH => Negative
  | Z0 => Zero
  | Zpos xH => Positive
  | _ => Uncertain
  end.

(** The integers sign_lanes can produce: −1, +1 or 2 (never 0: a lane sign never certifies zero). *)
Definition lane_sign (i : Z) : Prop := i = (-1)%Z \/ i = 1%Z \/ i = uncertain_lane.

Lemma sign_lanes_range : forall above below, lane_sign (sign_lanes above below).
Proof. intros [|] [|]; unfold lane_sign; cbv; auto. Qed.

(** A certain lane sign is ±1, the integer of the [sign] it encodes, which is neither zero nor
    uncertain. *)
Lemma lane_sign_certain : forall i, lane_sign i -> i <> uncertain_lane ->
  (i = (-1)%Z /\ sign_from_Z i = Negative) \/ (i = 1%Z /\ sign_from_Z i = Positive).
Proof.
  intros i [ -> | [ -> | -> ] ] N; [left | right | elim N]; split; reflexivity.
Qed.

(** ** Constants as rationals (for [lra]). *)

Lemma u_val : u = / 9007199254740992.
Proof. unfold unit_roundoff. simpl. reflexivity. Qed.

Lemma u_pos : 0 < u.
Proof. rewrite u_val. lra. Qed.

Lemma eta_pos : 0 < eta.
Proof. apply bpow_gt_0. Qed.

Lemma half_bpow_52 : / 2 * bpow radix2 (- (53) + 1) = u.
Proof. rewrite u_val. simpl bpow. lra. Qed.

Lemma half_min_subnormal : / 2 * bpow radix2 (-1074) = eta.
Proof.
  unfold eta. replace (-1075)%Z with (-1 + -1074)%Z by lia.
  rewrite bpow_plus. reflexivity.
Qed.

Lemma min_subnormal_eta : min_subnormal = 2 * eta.
Proof. unfold min_subnormal. rewrite <- half_min_subnormal. field. Qed.

(** ** Basic facts about [RN]. *)

Lemma binary64_RN : forall x, binary64 (RN x).
Proof.
  intros x. apply generic_format_round; [apply FLT_exp_valid; reflexivity | apply valid_rnd_N].
Qed.

Lemma RN_binary64 : forall x, binary64 x -> RN x = x.
Proof. intros x Hx. apply round_generic; auto with typeclass_instances. Qed.

Lemma RN_le : forall x y, x <= y -> RN x <= RN y.
Proof. intros x y H. apply round_le; auto with typeclass_instances. Qed.

Lemma RN_0 : RN 0 = 0.
Proof. apply round_0; auto with typeclass_instances. Qed.

Lemma RN_nonneg : forall x, 0 <= x -> 0 <= RN x.
Proof. intros x H. rewrite <- RN_0. now apply RN_le. Qed.

Lemma RN_abs : forall x, RN (Rabs x) = Rabs (RN x).
Proof. intros x. apply round_NE_abs; auto with typeclass_instances. Qed.

Lemma RN_opp : forall x, RN (- x) = - RN x.
Proof. intros x. apply round_NE_opp. Qed.

Lemma binary64_opp : forall x, binary64 x -> binary64 (- x).
Proof. intros x H. now apply generic_format_opp. Qed.

Lemma binary64_abs : forall x, binary64 x -> binary64 (Rabs x).
Proof. intros x H. now apply generic_format_abs. Qed.

Lemma binary64_0 : binary64 0.
Proof. apply generic_format_0. Qed.

Lemma binary64_bpow : forall e, (-1074 <= e)%Z -> binary64 (bpow radix2 e).
Proof. intros e He. apply generic_format_FLT_bpow; [reflexivity | exact He]. Qed.

(** ** Rounding errors.  Every rounding: |RN(x) − x| ≤ u|x| + η and ≤ u|RN(x)| + η (Flocq
    [relative_error_N_FLT] above 2^-1022, [error_le_half_ulp] with [ulp_FLT_small] below). *)

Lemma small_error : forall x,
  Rabs x < bpow radix2 (-1022) -> Rabs (RN x - x) <= eta.
Proof.
  intros x Hx.
  eapply Rle_trans.
  - apply error_le_half_ulp. apply FLT_exp_valid. reflexivity.
  - rewrite ulp_FLT_small.
    + rewrite half_min_subnormal. apply Rle_refl.
    + reflexivity.
    + eapply Rlt_le_trans; [exact Hx|]. apply bpow_le. lia.
Qed.

Lemma RN_err : forall x, Rabs (RN x - x) <= u * Rabs x + eta.
Proof.
  intros x. pose proof eta_pos. pose proof u_pos.
  destruct (Rle_or_lt (bpow radix2 (-1022)) (Rabs x)) as [Hx|Hx].
  - pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) x Hx) as H1.
    rewrite half_bpow_52 in H1. lra.
  - pose proof (small_error x Hx). pose proof (Rabs_pos x). nra.
Qed.

Lemma RN_err_round : forall x, Rabs (RN x - x) <= u * Rabs (RN x) + eta.
Proof.
  intros x. pose proof eta_pos. pose proof u_pos.
  destruct (Rle_or_lt (bpow radix2 (-1022)) (Rabs x)) as [Hx|Hx].
  - pose proof (relative_error_N_FLT_round radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) x Hx) as H1.
    rewrite half_bpow_52 in H1. lra.
  - pose proof (small_error x Hx). pose proof (Rabs_pos (RN x)). nra.
Qed.

(** A sum of two doubles has a relative error only: below 2^-1022 it is exact (Flocq
    [FLT_format_plus_small], Hauser's theorem). *)
Lemma RN_plus_exact_or_normal : forall a b, binary64 a -> binary64 b ->
  RN (a + b) = a + b \/ bpow radix2 (-1022) <= Rabs (a + b).
Proof.
  intros a b Ha Hb.
  destruct (Rle_or_lt (bpow radix2 (-1022)) (Rabs (a + b))) as [H|H]; [now right|left].
  apply RN_binary64. apply FLT_format_plus_small; try assumption.
  - reflexivity.
  - apply Rlt_le. eapply Rlt_le_trans; [exact H|]. apply bpow_le. lia.
Qed.

Lemma RN_plus_err : forall a b, binary64 a -> binary64 b ->
  Rabs (RN (a + b) - (a + b)) <= u * Rabs (a + b).
Proof.
  intros a b Ha Hb. pose proof u_pos. pose proof (Rabs_pos (a + b)).
  destruct (RN_plus_exact_or_normal a b Ha Hb) as [E|N].
  - rewrite E. unfold Rminus. rewrite Rplus_opp_r, Rabs_R0. nra.
  - pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) _ N) as H1.
    rewrite half_bpow_52 in H1. exact H1.
Qed.

Lemma RN_plus_err_round : forall a b, binary64 a -> binary64 b ->
  Rabs (RN (a + b) - (a + b)) <= u * Rabs (RN (a + b)).
Proof.
  intros a b Ha Hb. pose proof u_pos.
  destruct (RN_plus_exact_or_normal a b Ha Hb) as [E|N].
  - rewrite E. unfold Rminus. rewrite Rplus_opp_r, Rabs_R0.
    pose proof (Rabs_pos (a + b)). nra.
  - pose proof (relative_error_N_FLT_round radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) _ N) as H1.
    rewrite half_bpow_52 in H1. exact H1.
Qed.

Lemma RN_minus_err : forall a b, binary64 a -> binary64 b ->
  Rabs (RN (a - b) - (a - b)) <= u * Rabs (a - b).
Proof. intros a b Ha Hb. apply RN_plus_err; [exact Ha | now apply binary64_opp]. Qed.

Lemma RN_minus_err_round : forall a b, binary64 a -> binary64 b ->
  Rabs (RN (a - b) - (a - b)) <= u * Rabs (RN (a - b)).
Proof. intros a b Ha Hb. apply RN_plus_err_round; [exact Ha | now apply binary64_opp]. Qed.

(** ** Error-free transformations. *)

Lemma ZnearestE_sym : forall x : Z,
  negb (Z.even x) = negb (negb (Z.even (- (x + 1)))).
Proof. intros x. rewrite Z.even_opp, Z.even_add. now destruct (Z.even x). Qed.

(** TwoSum is exact for all doubles (Flocq [TwoSum_correct], whose algorithm is the C++ one operation
    by operation: s, b_virtual, a_virtual, b_roundoff, a_roundoff, lo). *)
Theorem two_sum_exact : forall a b, binary64 a -> binary64 b ->
  fst (two_sum a b) + snd (two_sum a b) = a + b.
Proof.
  intros a b Ha Hb. unfold two_sum; simpl.
  apply (TwoSum_correct (-1074) 53 (fun t => negb (Z.even t))); try easy.
  exact ZnearestE_sym.
Qed.

Lemma two_sum_hi : forall a b, fst (two_sum a b) = RN (a + b).
Proof. reflexivity. Qed.

Lemma binary64_two_sum_hi : forall a b, binary64 (fst (two_sum a b)).
Proof. intros. apply binary64_RN. Qed.

Lemma binary64_two_sum_lo : forall a b, binary64 (snd (two_sum a b)).
Proof. intros. apply binary64_RN. Qed.

(** The low part is the rounding error of the high part: |lo| ≤ u|a + b| and |lo| ≤ u|hi|. *)
Lemma two_sum_lo_bound : forall a b, binary64 a -> binary64 b ->
  Rabs (snd (two_sum a b)) <= u * Rabs (a + b) /\
  Rabs (snd (two_sum a b)) <= u * Rabs (fst (two_sum a b)).
Proof.
  intros a b Ha Hb. pose proof (two_sum_exact a b Ha Hb) as E.
  replace (snd (two_sum a b)) with (- (RN (a + b) - (a + b))) by (simpl in E |- *; lra).
  rewrite Rabs_Ropp. split; [now apply RN_plus_err | now apply RN_plus_err_round].
Qed.

Lemma binary64_two_prod_hi : forall a b, binary64 (fst (two_prod a b)).
Proof. intros. apply binary64_RN. Qed.

Lemma binary64_two_prod_lo : forall a b, binary64 (snd (two_prod a b)).
Proof. intros. apply binary64_RN. Qed.

(** TwoProduct with an FMA is exact when the product does not underflow (Flocq [mult_error_FLT]); the
    guard of expansion.hpp's [note_product] ([p == 0] with a zero factor, or |p| ≥ 2^-968) implies it. *)
Theorem two_prod_exact : forall a b, binary64 a -> binary64 b ->
  (a * b <> 0 -> bpow radix2 (-969) <= Rabs (a * b)) ->
  fst (two_prod a b) + snd (two_prod a b) = a * b.
Proof.
  intros a b Ha Hb H. unfold two_prod, fma; simpl.
  replace (a * b + - RN (a * b)) with (- (RN (a * b) - a * b)) by ring.
  rewrite RN_opp, (RN_binary64 (RN (a * b) - a * b)); [ring|].
  apply mult_error_FLT; auto with typeclass_instances.
Qed.

Theorem two_prod_guard_exact : forall a b, binary64 a -> binary64 b ->
  (RN (a * b) = 0 /\ (a = 0 \/ b = 0)) \/ bpow radix2 (-968) <= Rabs (RN (a * b)) ->
  fst (two_prod a b) + snd (two_prod a b) = a * b.
Proof.
  intros a b Ha Hb G. apply two_prod_exact; try assumption.
  intros Nz. destruct G as [[_ [Z|Z]]|G]; [rewrite Z in Nz; lra | rewrite Z in Nz; lra |].
  destruct (Rle_or_lt (bpow radix2 (-969)) (Rabs (a * b))) as [L|L]; [exact L|].
  exfalso.
  assert (F : binary64 (bpow radix2 (-969))) by (apply binary64_bpow; lia).
  assert (Rabs (RN (a * b)) <= bpow radix2 (-969)).
  { rewrite <- RN_abs, <- (RN_binary64 _ F). apply RN_le. lra. }
  assert (bpow radix2 (-969) < bpow radix2 (-968)) by (apply bpow_lt; lia).
  lra.
Qed.

(** TwoProduct is exact up to η (used by CompareQuotients.v and by the second level of stage 2): exact when |a·b| ≥ 2^-969 ([two_prod_exact]); below, a·b − (a ⊗ b) is
    below 2^-1022 and its rounding (the FMA) errs by at most η. *)
Lemma two_prod_error : forall a b, binary64 a -> binary64 b ->
  Rabs (a * b - (fst (two_prod a b) + snd (two_prod a b))) <= eta.
Proof.
  intros a b Ba Bb. pose proof eta_pos as He.
  destruct (Rle_or_lt (bpow radix2 (-969)) (Rabs (a * b))) as [L|L].
  - rewrite two_prod_exact; [| exact Ba | exact Bb | intros; exact L].
    unfold Rminus. rewrite Rplus_opp_r, Rabs_R0. lra.
  - unfold two_prod, fma. cbn [fst snd].
    set (P := RN (a * b)).
    assert (Z : Rabs (a * b + - P) < bpow radix2 (-1022)).
    { rewrite <- Rabs_Ropp. replace (- (a * b + - P)) with (P - a * b) by ring.
      destruct (Rle_or_lt (bpow radix2 (-1022)) (Rabs (a * b))) as [N|S].
      - pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) (a * b) N) as E.
        rewrite half_bpow_52 in E. fold P in E.
        eapply Rle_lt_trans; [exact E|].
        replace (bpow radix2 (-1022)) with (u * bpow radix2 (-969)).
        + apply Rmult_lt_compat_l; [apply u_pos | exact L].
        + unfold unit_roundoff. rewrite <- bpow_plus. reflexivity.
      - eapply Rle_lt_trans; [apply small_error; exact S|].
        unfold eta. apply bpow_lt. lia. }
    pose proof (small_error _ Z) as E.
    replace (a * b - (P + RN (a * b + - P))) with (- (RN (a * b + - P) - (a * b + - P))) by ring.
    rewrite Rabs_Ropp. exact E.
Qed.

(** ** Small real-arithmetic helpers for the error analyses. *)

(** [Req_bool] models C++'s [==] on doubles. *)
Lemma Req_bool_true_iff : forall x y, Req_bool x y = true <-> x = y.
Proof.
  intros x y. destruct (Req_bool_spec x y) as [E|N]; split; intros H; easy.
Qed.

Lemma Rabs_close : forall x y e, Rabs (x - y) <= e -> Rabs x <= Rabs y + e.
Proof.
  intros x y e H. replace x with (y + (x - y)) by ring.
  eapply Rle_trans; [apply Rabs_triang|]. lra.
Qed.

Lemma Rabs_close' : forall x y e, Rabs (x - y) <= e -> Rabs y <= Rabs x + e.
Proof. intros x y e H. apply Rabs_close. now rewrite Rabs_minus_sym. Qed.

Lemma Rabs_bounds : forall x e, Rabs x <= e -> - e <= x <= e.
Proof. intros x e H. now apply Rabs_le_inv. Qed.

Lemma Rabs_mult_le_l : forall x y z, Rabs x <= y -> Rabs (x * z) <= y * Rabs z.
Proof.
  intros x y z H. rewrite Rabs_mult. apply Rmult_le_compat_r; [apply Rabs_pos | exact H].
Qed.

Lemma Rabs_nonneg_eq : forall x, 0 <= x -> Rabs x = x.
Proof. intros x H. now apply Rabs_pos_eq. Qed.

(** ** Every constant of Constants.v is a binary64 number, as the C++ literal of the same name is. *)
Lemma binary64_dyadic : forall (m e : Z), (Z.abs m < 2 ^ 53)%Z -> (-1074 <= e)%Z ->
  binary64 (IZR m * bpow radix2 e).
Proof.
  intros m e Hm He. apply generic_format_FLT. exists (Float radix2 m e); simpl; try easy.
Qed.

Theorem constants_binary64 :
  binary64 unit_roundoff /\ binary64 min_subnormal /\
  binary64 filter_den_relative /\ binary64 filter_num_relative /\ binary64 filter_absolute /\
  binary64 compensated_relative /\ binary64 compensated_absolute /\
  binary64 tail_sum_relative /\ binary64 tail_sum_absolute /\
  binary64 quotient_min_magnitude /\ binary64 quotient_relative /\
  binary64 quotient_enclosure_factor /\ binary64 quotient_test_factor /\
  binary64 compare_filter_relative /\ binary64 compare_propagation_factor /\
  binary64 compare_absolute /\ binary64 compare_compensated_relative /\
  binary64 refined_relative /\ binary64 refined_low_relative /\ binary64 refined_absolute.
Proof.
  repeat split; try (apply binary64_bpow; lia).
  - (* (3 + 16u)u = (3·2^49 + 1)·2^-102 *)
    replace filter_den_relative with (IZR 1688849860263937 * bpow radix2 (-102)).
    + apply binary64_dyadic; [reflexivity | lia].
    + unfold filter_den_relative. rewrite u_val. simpl bpow. lra.
  - (* (4 + 32u)u = (2^50 + 1)·2^-101 *)
    replace filter_num_relative with (IZR 1125899906842625 * bpow radix2 (-101)).
    + apply binary64_dyadic; [reflexivity | lia].
    + unfold filter_num_relative. rewrite u_val. simpl bpow. lra.
  - replace filter_absolute with (IZR 3 * bpow radix2 (-1074)).
    + apply binary64_dyadic; [reflexivity | lia].
    + reflexivity.
  - replace tail_sum_absolute with (IZR 2 * bpow radix2 (-1074)).
    + apply binary64_dyadic; [reflexivity | lia].
    + reflexivity.
  - replace quotient_enclosure_factor with (IZR 513 * bpow radix2 (-9)).
    + apply binary64_dyadic; [reflexivity | lia].
    + unfold quotient_enclosure_factor. simpl bpow. lra.
  - replace quotient_test_factor with (IZR 35184372088833 * bpow radix2 (-45)).
    + apply binary64_dyadic; [reflexivity | lia].
    + unfold quotient_test_factor. simpl bpow. lra.
  - (* (2 + 16u)u = (2^50 + 1)·2^-102 *)
    replace compare_filter_relative with (IZR 1125899906842625 * bpow radix2 (-102)).
    + apply binary64_dyadic; [reflexivity | lia].
    + unfold compare_filter_relative. rewrite u_val. simpl bpow. lra.
  - (* 1 + 16u = (2^49 + 1)·2^-49 *)
    replace compare_propagation_factor with (IZR 562949953421313 * bpow radix2 (-49)).
    + apply binary64_dyadic; [reflexivity | lia].
    + unfold compare_propagation_factor. rewrite u_val. simpl bpow. lra.
  - replace compare_absolute with (IZR 8 * bpow radix2 (-1074)).
    + apply binary64_dyadic; [reflexivity | lia].
    + reflexivity.
  - replace refined_absolute with (IZR 8 * bpow radix2 (-1074)).
    + apply binary64_dyadic; [reflexivity | lia].
    + reflexivity.
Qed.
