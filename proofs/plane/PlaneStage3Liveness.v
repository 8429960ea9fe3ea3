(** * Liveness of stage 3 of the ray–plane cascade (the expansion stage's checked sign).

    [Expansion::sign()] (kernel/src/core/expansion.hpp), twinned by [expansion_sign_b]
    (Expansions.v), returns uncertain unless 2·(rounded Σ|lower components|) < |top| or the expansion is
    the single 0.  Soundness is [expansion_sign_sound]; this file proves that it does certify:
    - [expansion_sign_single_certain]: on every expansion of ONE finite component (what the builder's
      zero elimination leaves whenever every TwoSum/TwoProduct low part is 0, e.g. small integer inputs)
      the twin's checked sign is certain, and ([expansion_sign_single_exact]) it is the sign of the
      component, zero included;
    - [stage3_plane_live_example]: non-vacuity at the cascade level, by computation on the twin the runner
      checks against the C++: o = (0,0,0), d = (1,1,0), p = (1,0,0), n = (1,−1,0) (den = 1 − 1 = 0, a
      parallel ray whose products cancel, num = 1): stage 1 ([den_filter_b]) and stage 2 ([den_sign2_b])
      leave den's sign uncertain, the expansions are exact, den's expansion is the single 0 and num's the
      single 1, and [relation_b] answers Parallel at [StExpansion], before the exact stage;
    - [build_expansions_single], [expansions_int_single]: every input an integer of magnitude ≤ 2^24: every
      TwoSum/TwoDiff/TwoProduct low part is 0, [note_product] holds, zero elimination drops the low parts,
      and each expansion is one finite component; hence [stage3_int_live] (the builder says exact, both
      checked signs are certain, [certified_signs_b] stops before [StExact]) and [relation_int_live].
    The triangle's stage 3 (TriangleStage3Twins.v) is not covered here. *)

From Coq Require Import Reals ZArith List Lia Lra.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneCascade FloatCore PlaneTwins Expansions PlaneQueryTwins PlaneQueryPairTwins PlaneCascadeTwins
  PlaneClassification.
Import ListNotations.
Open Scope R_scope.

(** A one-component expansion: the lower magnitude is +0, so the top decides unless it is ±0, and then
    the expansion is the single zero. *)
Theorem expansion_sign_single_certain : forall x, fin x = true -> expansion_sign_b [x] <> Uncertain.
Proof.
  intros x F. unfold expansion_sign_b.
  change (lower_magnitude [x]) with fzero. change (last [x] fzero) with x.
  destruct x as [s | s | | s m e H]; try discriminate F.
  - destruct s; vm_compute; discriminate.
  - destruct s; cbv [fabs flt fadd fzero Babs Bplus Bltb]; simpl; discriminate.
Qed.

Theorem expansion_sign_single_exact : forall x, fin x = true ->
  expansion_sign_b [x] <> Uncertain /\ certifies (expansion_sign_b [x]) (B2R x).
Proof.
  intros x F. split; [now apply expansion_sign_single_certain |].
  replace (B2R x) with (sumR [x]) by (unfold sumR; simpl; ring).
  apply expansion_sign_sound; [constructor; [exact F | constructor] | simpl; lia].
Qed.

(** The cascade-level consequence: when the builder's expansions are exact and each has one component,
    stage 3 answers ([certified_signs_b]'s stage is not [StExact], so [relation_b] does not hand the query
    to the exact stage) and its signs are the exact signs of num and den. *)
Theorem certified_signs_single_live : forall o d p n x y,
  expansions_b o d p n = ([x], [y], true) ->
  snd (certified_signs_b o d p n) <> StExact.
Proof.
  intros o d p n x y H.
  pose proof (ray_plane_expansions_twin_exact o d p n) as X.
  change (ray_plane_expansions_b two_sum_b o d p n) with (expansions_b o d p n) in X.
  rewrite H in X. destruct (X eq_refl) as [Fn [Fd _]].
  inversion Fn as [| ? ? Fx _]; inversion Fd as [| ? ? Fy _]; subst.
  assert (Cx : is_certain (expansion_sign_b [x]) = true).
  { destruct (expansion_sign_b [x]) eqn:E; try reflexivity. exfalso; now apply (expansion_sign_single_certain x). }
  assert (Cy : is_certain (expansion_sign_b [y]) = true).
  { destruct (expansion_sign_b [y]) eqn:E; try reflexivity. exfalso; now apply (expansion_sign_single_certain y). }
  assert (Dy : is_certain (den_sign3_b o d p n) = true).
  { unfold den_sign3_b, den_expansion_sign_b. rewrite H. destruct (den_sign2_b d n); [reflexivity .. | exact Cy]. }
  assert (Nx : is_certain (num_sign3_b o d p n) = true).
  { unfold num_sign3_b, num_expansion_sign_b. rewrite H. destruct (num_sign2_b o p n); [reflexivity .. | exact Cx]. }
  unfold certified_signs_b.
  destruct (is_certain (den_filter_b d n) && is_certain (num_filter_b o p n))%bool; [discriminate|].
  destruct (is_certain (den_sign2_b d n) && is_certain (num_sign2_b o p n))%bool; [discriminate|].
  rewrite Dy, Nx. discriminate.
Qed.

(** The same for [relation_b] on a valid query: it decides, at a stage before the exact one. *)
Theorem relation_single_live : forall o d p n x y,
  validate_b o d p n = None -> expansions_b o d p n = ([x], [y], true) ->
  relation_b o d p n <> CExact.
Proof.
  intros o d p n x y V H. pose proof (certified_signs_single_live o d p n x y H) as L.
  unfold relation_b. rewrite V.
  destruct (certified_signs_b o d p n) as [[ns ds] st]. simpl in L.
  destruct st; try discriminate. contradiction.
Qed.


(** A real that is an integer below 2^52 in magnitude: exactly a double. *)
Definition small (r : R) : Prop := exists z : Z, r = IZR z /\ (Z.abs z <= 2 ^ 52)%Z.

Lemma small_fmt : forall r, small r -> binary64 r /\ Rabs r < bpow radix2 1024.
Proof.
  intros r [z [-> B]]. split.
  - destruct (Z.eq_dec z 0) as [->|NZ]; [apply binary64_0|].
    apply generic_format_FLT. exists (Float radix2 z 0).
    + unfold F2R; simpl. ring.
    + simpl. apply Z.le_lt_trans with (1 := B). reflexivity.
    + simpl. lia.
  - rewrite <- abs_IZR. apply Rle_lt_trans with (IZR (2 ^ 52)); [now apply IZR_le|].
    replace (IZR (2 ^ 52)) with (bpow radix2 52) by reflexivity. apply bpow_lt. lia.
Qed.

Lemma small_0 : small 0.
Proof. exists 0%Z. split; [reflexivity | lia]. Qed.

(** A real that a finite double can hold; a small one is one. *)
Definition repr (r : R) : Prop := binary64 r /\ Rabs r < bpow radix2 1024.

Lemma small_repr : forall r, small r -> repr r.
Proof. exact small_fmt. Qed.

Lemma repr_B2R : forall x, repr (B2R x).
Proof. intros x. split; [apply binary64_B2R | apply B2R_lt_overflow]. Qed.

Lemma repr_eq : forall r s, repr r -> s = r -> repr s.
Proof. intros r s H ->. exact H. Qed.

Lemma repr_0 : repr 0.
Proof. split; [apply binary64_0 | rewrite Rabs_R0; apply bpow_gt_0]. Qed.

Lemma fadd_repr : forall x y, fin x = true -> fin y = true -> repr (B2R x + B2R y) ->
  fin (fadd x y) = true /\ B2R (fadd x y) = B2R x + B2R y.
Proof.
  intros x y Fx Fy [G L]. destruct (fadd_fwd x y Fx Fy) as [F V]; [now rewrite RN_binary64|].
  split; [exact F|]. now rewrite V, RN_binary64.
Qed.

Lemma fsub_repr : forall x y, fin x = true -> fin y = true -> repr (B2R x - B2R y) ->
  fin (fsub x y) = true /\ B2R (fsub x y) = B2R x - B2R y.
Proof.
  intros x y Fx Fy [G L]. destruct (fsub_fwd x y Fx Fy) as [F V]; [now rewrite RN_binary64|].
  split; [exact F|]. now rewrite V, RN_binary64.
Qed.

Lemma fadd_exact : forall x y, fin x = true -> fin y = true -> small (B2R x + B2R y) ->
  fin (fadd x y) = true /\ B2R (fadd x y) = B2R x + B2R y.
Proof. intros x y Fx Fy S. exact (fadd_repr x y Fx Fy (small_repr _ S)). Qed.

Lemma fsub_exact : forall x y, fin x = true -> fin y = true -> small (B2R x - B2R y) ->
  fin (fsub x y) = true /\ B2R (fsub x y) = B2R x - B2R y.
Proof. intros x y Fx Fy S. exact (fsub_repr x y Fx Fy (small_repr _ S)). Qed.

Lemma fmul_exact : forall x y, fin x = true -> fin y = true -> small (B2R x * B2R y) ->
  fin (fmul x y) = true /\ B2R (fmul x y) = B2R x * B2R y.
Proof.
  intros x y Fx Fy S. destruct (small_fmt _ S) as [G L].
  destruct (fmul_fwd x y Fx Fy) as [F V]; [now rewrite RN_binary64|]. split; [exact F|]. now rewrite V, RN_binary64.
Qed.

Lemma ffma_exact : forall x y z, fin x = true -> fin y = true -> fin z = true -> small (B2R x * B2R y + B2R z) ->
  fin (ffma x y z) = true /\ B2R (ffma x y z) = B2R x * B2R y + B2R z.
Proof.
  intros x y z Fx Fy Fz S. destruct (small_fmt _ S) as [G L].
  destruct (ffma_fwd x y z Fx Fy Fz) as [F V]; [now rewrite RN_binary64|]. split; [exact F|]. now rewrite V, RN_binary64.
Qed.

Lemma small_eq : forall r s, small r -> s = r -> small s.
Proof. intros r s H ->. exact H. Qed.

(** TwoSum whose sum a + b is a double: the sum is exact and the low part is 0 (every intermediate is
    a + b, a, b or 0). *)
Lemma two_sum_repr : forall a b, fin a = true -> fin b = true -> repr (B2R a + B2R b) ->
  fin (fst (two_sum_b a b)) = true /\ B2R (fst (two_sum_b a b)) = B2R a + B2R b /\
  fin (snd (two_sum_b a b)) = true /\ B2R (snd (two_sum_b a b)) = 0.
Proof.
  intros a b Fa Fb S. unfold two_sum_b; cbn [fst snd].
  destruct (fadd_repr a b Fa Fb S) as [F1 V1].
  destruct (fsub_repr (fadd a b) a F1 Fa) as [F2 V2]; [rewrite V1; apply (repr_eq _ _ (repr_B2R b)); ring|].
  destruct (fsub_repr (fadd a b) (fsub (fadd a b) a) F1 F2) as [F3 V3];
    [rewrite V2, V1; apply (repr_eq _ _ (repr_B2R a)); ring|].
  destruct (fsub_repr b (fsub (fadd a b) a) Fb F2) as [F4 V4]; [rewrite V2, V1; apply (repr_eq _ _ repr_0); ring|].
  destruct (fsub_repr a (fsub (fadd a b) (fsub (fadd a b) a)) Fa F3) as [F5 V5];
    [rewrite V3, V2, V1; apply (repr_eq _ _ repr_0); ring|].
  destruct (fadd_repr _ _ F5 F4) as [F6 V6]; [rewrite V5, V4, V3, V2, V1; apply (repr_eq _ _ repr_0); ring|].
  repeat split; auto. rewrite V6, V5, V4, V3, V2, V1. ring.
Qed.

(** TwoSum of small integers whose sum is small: the sum is exact, the low part is zero. *)
Lemma two_sum_small : forall a b, fin a = true -> fin b = true -> small (B2R a) -> small (B2R b) ->
  small (B2R a + B2R b) ->
  fin (fst (two_sum_b a b)) = true /\ B2R (fst (two_sum_b a b)) = B2R a + B2R b /\
  fin (snd (two_sum_b a b)) = true /\ B2R (snd (two_sum_b a b)) = 0.
Proof. intros a b Fa Fb _ _ S. exact (two_sum_repr a b Fa Fb (small_repr _ S)). Qed.

Lemma small_opp : forall r, small r -> small (- r).
Proof. intros r [z [-> B]]. exists (- z)%Z. split; [now rewrite opp_IZR | lia]. Qed.

Lemma two_diff_small : forall a b, fin a = true -> fin b = true -> small (B2R a) -> small (B2R b) ->
  small (B2R a - B2R b) ->
  fin (fst (two_diff_b a b)) = true /\ B2R (fst (two_diff_b a b)) = B2R a - B2R b /\
  fin (snd (two_diff_b a b)) = true /\ B2R (snd (two_diff_b a b)) = 0.
Proof.
  intros a b Fa Fb Sa Sb S. unfold two_diff_b.
  assert (Fn : fin (fneg b) = true) by now rewrite fneg_fin.
  destruct (two_sum_small a (fneg b) Fa Fn Sa) as [F1 [V1 R]].
  - rewrite fneg_val. now apply small_opp.
  - rewrite fneg_val. apply (small_eq _ _ S). ring.
  - rewrite fneg_val in V1. split; [exact F1|]. split; [rewrite V1; ring | exact R].
Qed.

Lemma two_prod_small : forall a b, fin a = true -> fin b = true -> small (B2R a * B2R b) ->
  fin (fst (two_prod_b a b)) = true /\ B2R (fst (two_prod_b a b)) = B2R a * B2R b /\
  fin (snd (two_prod_b a b)) = true /\ B2R (snd (two_prod_b a b)) = 0.
Proof.
  intros a b Fa Fb S. unfold two_prod_b; cbn [fst snd].
  destruct (fmul_exact a b Fa Fb S) as [F1 V1].
  assert (Fn : fin (fneg (fmul a b)) = true) by now rewrite fneg_fin.
  destruct (ffma_exact a b _ Fa Fb Fn) as [F2 V2];
    [rewrite fneg_val, V1; apply (small_eq _ _ small_0); ring|].
  repeat split; auto. rewrite V2, fneg_val, V1. ring.
Qed.

(** An integer-valued double: finite, |x| ≤ 2^k. *)
Definition int_le (k : Z) (x : float) : Prop :=
  fin x = true /\ exists z : Z, B2R x = IZR z /\ (Z.abs z <= 2 ^ k)%Z.

Lemma feq_zero_true : forall x, fin x = true -> B2R x = 0 -> feq x fzero = true.
Proof. intros x F Z. rewrite (feq_val x fzero F eq_refl). apply Req_bool_true_iff. rewrite Z. reflexivity. Qed.

Lemma push_zero : forall h x, fin x = true -> B2R x = 0 -> push h x = h.
Proof. intros h x F Z. unfold push. now rewrite feq_zero_true. Qed.

Lemma finish_nil : forall q, finish nil q = [q].
Proof. intros q. unfold finish. cbn [length Nat.eqb]. now rewrite Bool.orb_true_r. Qed.

(** An expansion of one finite component of value v, v a small integer. *)
Definition single (l : list float) (v : R) : Prop :=
  exists x, l = [x] /\ fin x = true /\ B2R x = v /\ small v.

Lemma single_small : forall l v, single l v -> small v.
Proof. intros l v [x [_ [_ [_ S]]]]. exact S. Qed.

Lemma from_pair_single : forall p, fin (fst p) = true -> fin (snd p) = true -> B2R (snd p) = 0 ->
  small (B2R (fst p)) -> single (from_pair p) (B2R (fst p)).
Proof.
  intros p F1 F2 Z S. unfold from_pair. rewrite push_zero by assumption. rewrite finish_nil.
  exists (fst p). auto.
Qed.

Lemma sum_single : forall e f u v, single e u -> single f v -> small (u + v) ->
  single (sum_gen two_sum_b e f) (u + v).
Proof.
  intros e f u v [x [-> [Fx [Vx Su]]]] [y [-> [Fy [Vy Sv]]]] S. unfold sum_gen. cbn [merge].
  destruct (Bool.eqb (flt x y) (flt (fneg x) y)).
  - destruct (two_sum_small y x Fy Fx) as [F1 [V1 [F2 V2]]];
      [now rewrite Vy | now rewrite Vx | rewrite Vx, Vy; apply (small_eq _ _ S); ring |].
    cbn [sum_loop]. rewrite push_zero by assumption. rewrite finish_nil.
    exists (fst (two_sum_b y x)). repeat split; auto. rewrite V1, Vx, Vy. ring.
  - destruct (two_sum_small x y Fx Fy) as [F1 [V1 [F2 V2]]];
      [now rewrite Vx | now rewrite Vy | rewrite Vx, Vy; exact S |].
    cbn [sum_loop]. rewrite push_zero by assumption. rewrite finish_nil.
    exists (fst (two_sum_b x y)). repeat split; auto. rewrite V1, Vx, Vy. ring.
Qed.

Lemma int_prod : forall a b za zb, B2R a = IZR za -> B2R b = IZR zb -> B2R a * B2R b = IZR (za * zb).
Proof. intros a b za zb -> ->. now rewrite mult_IZR. Qed.

Lemma note_product_int : forall a b za zb, fin a = true -> fin b = true -> B2R a = IZR za -> B2R b = IZR zb ->
  fin (fst (two_prod_b a b)) = true -> B2R (fst (two_prod_b a b)) = B2R a * B2R b ->
  note_product_b a b (fst (two_prod_b a b)) = true.
Proof.
  intros a b za zb Fa Fb Va Vb Fp Vp. unfold note_product_b. rewrite Fp, Bool.andb_true_r.
  rewrite (feq_val _ fzero Fp eq_refl). destruct (Req_bool_spec (B2R (fst (two_prod_b a b))) (B2R fzero)) as [E|E].
  - rewrite Vp in E. change (B2R fzero) with 0 in E. destruct (Rmult_integral _ _ E) as [Z|Z].
    + now rewrite (feq_zero_true a).
    + rewrite (feq_zero_true b) by assumption. apply Bool.orb_true_r.
  - assert (F0 : fin tiny_product = true) by reflexivity.
    rewrite (fle_val _ _ F0) by now rewrite fabs_fin. apply Rle_bool_true.
    rewrite fabs_val, tiny_product_threshold, Vp, (int_prod a b za zb Va Vb). unfold exact_product_threshold.
    rewrite Vp, (int_prod a b za zb Va Vb) in E. change (B2R fzero) with 0 in E.
    assert (NZ : (za * zb <> 0)%Z) by (intros H; apply E; now rewrite H).
    apply Rle_trans with 1; [apply (bpow_le radix2 (-968) 0); lia|].
    rewrite <- abs_IZR. apply IZR_le. lia.
Qed.

(** [builder.scale] of a one-component expansion by a small integer: one component, the product. *)
Lemma scale_single : forall ex e u b zb, single e u -> fin b = true -> B2R b = IZR zb -> (exists zu, u = IZR zu) ->
  small (u * B2R b) ->
  fst (scale_gen two_sum_b ex e b) = ex /\ single (snd (scale_gen two_sum_b ex e b)) (u * B2R b).
Proof.
  intros ex e u b zb [x [-> [Fx [Vx Su]]]] Fb Vb [zu Zu] S. unfold scale_gen, product_b. cbn [fst snd scale_loop].
  destruct (two_prod_small x b Fx Fb) as [F1 [V1 [F2 V2]]]; [now rewrite Vx|].
  rewrite (note_product_int x b zu zb Fx Fb) by (rewrite ?Vx; auto; congruence).
  rewrite Bool.andb_true_r. split; [reflexivity|].
  rewrite push_zero by assumption. rewrite finish_nil. exists (fst (two_prod_b x b)). repeat split; auto.
  now rewrite V1, Vx.
Qed.

Lemma small_int : forall z, (Z.abs z <= 2 ^ 52)%Z -> small (IZR z).
Proof. intros z B. now exists z. Qed.

Lemma zmul_bound : forall a b ka kb, (Z.abs a <= 2 ^ ka)%Z -> (Z.abs b <= 2 ^ kb)%Z -> (0 <= ka)%Z -> (0 <= kb)%Z ->
  (Z.abs (a * b) <= 2 ^ (ka + kb))%Z.
Proof.
  intros a b ka kb A B Ka Kb. rewrite Z.abs_mul, Z.pow_add_r by lia.
  apply Z.mul_le_mono_nonneg; lia.
Qed.

Lemma product_step : forall ex a b za zb, fin a = true -> fin b = true -> B2R a = IZR za -> B2R b = IZR zb ->
  (Z.abs (za * zb) <= 2 ^ 52)%Z ->
  fst (product_b ex a b) = ex /\ single (from_pair (snd (product_b ex a b))) (IZR (za * zb)).
Proof.
  intros ex a b za zb Fa Fb Va Vb B. rewrite mult_IZR.
  destruct (two_prod_small a b Fa Fb) as [F1 [V1 [F2 V2]]];
    [rewrite Va, Vb, <- mult_IZR; now apply small_int|].
  unfold product_b; cbn [fst snd]. rewrite (note_product_int a b za zb) by auto. rewrite Bool.andb_true_r.
  split; [reflexivity|]. rewrite <- Va, <- Vb, <- V1. apply from_pair_single; auto.
  rewrite V1, Va, Vb, <- mult_IZR. now apply small_int.
Qed.

Lemma diff_step : forall a b za zb, fin a = true -> fin b = true -> B2R a = IZR za -> B2R b = IZR zb ->
  (Z.abs za <= 2 ^ 24)%Z -> (Z.abs zb <= 2 ^ 24)%Z ->
  single (from_pair (two_diff_b a b)) (IZR (za - zb)).
Proof.
  intros a b za zb Fa Fb Va Vb A B.
  destruct (two_diff_small a b Fa Fb) as [F1 [V1 [F2 V2]]];
    [rewrite Va; apply small_int; lia | rewrite Vb; apply small_int; lia
    | rewrite Va, Vb, <- minus_IZR; apply small_int; lia |].
  rewrite minus_IZR, <- Va, <- Vb, <- V1. apply from_pair_single; auto.
  rewrite V1, Va, Vb, <- minus_IZR. apply small_int; lia.
Qed.

Ltac int_in H := let F := fresh "F" in let z := fresh "z" in let V := fresh "V" in let B := fresh "B" in
  destruct H as [F [z [V B]]].

(** Every input an integer of magnitude ≤ 2^24: the builder's expansions are exact and have one component
    each (every TwoSum/TwoProduct low part is 0 and zero elimination drops it). *)
Theorem build_expansions_single : forall o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2,
  int_le 24 o0 -> int_le 24 o1 -> int_le 24 o2 -> int_le 24 d0 -> int_le 24 d1 -> int_le 24 d2 ->
  int_le 24 p0 -> int_le 24 p1 -> int_le 24 p2 -> int_le 24 n0 -> int_le 24 n1 -> int_le 24 n2 ->
  exists x y, build_expansions_b o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2 = ([x], [y], true).
Proof.
  intros o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2 Io0 Io1 Io2 Id0 Id1 Id2 Ip0 Ip1 Ip2 In0 In1 In2.
  int_in Io0; int_in Io1; int_in Io2; int_in Id0; int_in Id1; int_in Id2;
  int_in Ip0; int_in Ip1; int_in Ip2; int_in In0; int_in In1; int_in In2.
  pose proof (zmul_bound z2 z8 24 24 B2 B8 ltac:(lia) ltac:(lia)) as M0.
  pose proof (zmul_bound z3 z9 24 24 B3 B9 ltac:(lia) ltac:(lia)) as M1.
  pose proof (zmul_bound z4 z10 24 24 B4 B10 ltac:(lia) ltac:(lia)) as M2.
  assert (D0 : (Z.abs (z5 - z) <= 2 ^ 25)%Z) by (clear - B5 B; lia).
  assert (D1 : (Z.abs (z6 - z0) <= 2 ^ 25)%Z) by (clear - B6 B0; lia).
  assert (D2 : (Z.abs (z7 - z1) <= 2 ^ 25)%Z) by (clear - B7 B1; lia).
  pose proof (zmul_bound _ z8 25 24 D0 B8 ltac:(lia) ltac:(lia)) as N0.
  pose proof (zmul_bound _ z9 25 24 D1 B9 ltac:(lia) ltac:(lia)) as N1.
  pose proof (zmul_bound _ z10 25 24 D2 B10 ltac:(lia) ltac:(lia)) as N2.
  cbn [Z.add] in M0, M1, M2, N0, N1, N2.
  destruct (product_step true d0 n0 z2 z8 F2 F8 V2 V8 ltac:(clear - M0; lia)) as [E0 S0].
  destruct (product_step true d1 n1 z3 z9 F3 F9 V3 V9 ltac:(clear - M1; lia)) as [E1 S1].
  destruct (product_step true d2 n2 z4 z10 F4 F10 V4 V10 ltac:(clear - M2; lia)) as [E2 S2].
  pose proof (diff_step p0 o0 z5 z F5 F V5 V B5 B) as T0.
  pose proof (diff_step p1 o1 z6 z0 F6 F0 V6 V0 B6 B0) as T1.
  pose proof (diff_step p2 o2 z7 z1 F7 F1 V7 V1 B7 B1) as T2.
  destruct (scale_single true _ _ n0 z8 T0 F8 V8 (ex_intro _ _ eq_refl)) as [C0 U0];
    [rewrite V8, <- mult_IZR; apply small_int; clear - N0; lia|].
  destruct (scale_single true _ _ n1 z9 T1 F9 V9 (ex_intro _ _ eq_refl)) as [C1 U1];
    [rewrite V9, <- mult_IZR; apply small_int; clear - N1; lia|].
  destruct (scale_single true _ _ n2 z10 T2 F10 V10 (ex_intro _ _ eq_refl)) as [C2 U2];
    [rewrite V10, <- mult_IZR; apply small_int; clear - N2; lia|].
  rewrite V8, <- mult_IZR in U0. rewrite V9, <- mult_IZR in U1. rewrite V10, <- mult_IZR in U2.
  pose proof (sum_single _ _ _ _ S0 S1 ltac:(rewrite <- plus_IZR; apply small_int; clear - M0 M1; lia)) as S01.
  pose proof (sum_single _ _ _ _ S01 S2 ltac:(rewrite <- !plus_IZR; apply small_int; clear - M0 M1 M2; lia)) as Sden.
  pose proof (sum_single _ _ _ _ U0 U1 ltac:(rewrite <- plus_IZR; apply small_int; clear - N0 N1; lia)) as U01.
  pose proof (sum_single _ _ _ _ U01 U2 ltac:(rewrite <- !plus_IZR; apply small_int; clear - N0 N1 N2; lia)) as Snum.
  unfold build_expansions_gen. cbv zeta. rewrite E0, E1, E2, C0, C1, C2.
  destruct Sden as [y [Ey [Fy _]]]. destruct Snum as [x [Ex [Fx _]]].
  rewrite Ey, Ex. exists x, y. unfold check_finite. cbn [forallb]. now rewrite Fx, Fy.
Qed.

(** The class: every component of o, d, p, n an integer of magnitude ≤ 2^24 (then every intermediate of den =
    d·n and num = (p − o)·n is an integer below 2^52, exactly a double). *)
Definition vec_int_le (k : Z) (v : Vec3B) : Prop := int_le k (vxb v) /\ int_le k (vyb v) /\ int_le k (vzb v).

Theorem expansions_int_single : forall o d p n, vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 p -> vec_int_le 24 n ->
  exists x y, expansions_b o d p n = ([x], [y], true).
Proof.
  intros [o0 o1 o2] [d0 d1 d2] [p0 p1 p2] [n0 n1 n2] [Io0 [Io1 Io2]] [Id0 [Id1 Id2]] [Ip0 [Ip1 Ip2]] [In0 [In1 In2]].
  exact (build_expansions_single o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2 Io0 Io1 Io2 Id0 Id1 Id2 Ip0 Ip1 Ip2 In0 In1 In2).
Qed.

(** On the class, stage 3 certifies both signs (each the exact sign), so the cascade never reaches the exact
    stage: [certified_signs_b]'s stage is not [StExact] and [relation_b] on a valid query is not [CExact].
    Both signs certain also means the mutation "stage 3 returning when ONE expansion sign is certain" (of the
    joint stage 3 before core/escalation.hpp) answers as the code on this class. *)
Theorem stage3_int_live : forall o d p n, vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 p -> vec_int_le 24 n ->
  let '(en, ed, ex) := expansions_b o d p n in
  ex = true /\ is_certain (expansion_sign_b en) = true /\ is_certain (expansion_sign_b ed) = true /\
  snd (certified_signs_b o d p n) <> StExact.
Proof.
  intros o d p n Io Id Ip In. destruct (expansions_int_single o d p n Io Id Ip In) as [x [y E]].
  pose proof (certified_signs_single_live o d p n x y E) as L.
  pose proof (ray_plane_expansions_twin_exact o d p n) as X.
  change (ray_plane_expansions_b two_sum_b o d p n) with (expansions_b o d p n) in X.
  rewrite E in X |- *. destruct (X eq_refl) as [Fn [Fd _]].
  inversion Fn as [| ? ? Fx _]; inversion Fd as [| ? ? Fy _]; subst.
  split; [reflexivity|]. split; [|split; [|exact L]].
  - destruct (expansion_sign_b [x]) eqn:Ex; try reflexivity. exfalso; now apply (expansion_sign_single_certain x).
  - destruct (expansion_sign_b [y]) eqn:Ey; try reflexivity. exfalso; now apply (expansion_sign_single_certain y).
Qed.

Theorem relation_int_live : forall o d p n, vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 p -> vec_int_le 24 n ->
  validate_b o d p n = None -> relation_b o d p n <> CExact.
Proof.
  intros o d p n Io Id Ip In V. destruct (expansions_int_single o d p n Io Id Ip In) as [x [y E]].
  exact (relation_single_live o d p n x y V E).
Qed.

(** The concrete input: small integers as doubles. *)
Definition fint (z : Z) : float := @binary_normalize 53 1024 eq_refl _ mode_NE z 0 false.

(** [fint z] is the double z, for |z| ≤ 2^52. *)
Lemma fint_value : forall z, (Z.abs z <= 2 ^ 52)%Z -> fin (fint z) = true /\ B2R (fint z) = IZR z.
Proof.
  intros z B. destruct (small_fmt _ (small_int z B)) as [G L].
  unfold fint, fin. match goal with |- context [@binary_normalize ?p ?e ?h1 ?h2 ?m z 0 false] =>
    pose proof (binary_normalize_correct p e h1 h2 m z 0 false) as C end. cbv zeta in C.
  replace (F2R {| Fnum := z; Fexp := 0 |}) with (IZR z) in C by (unfold F2R; simpl; ring).
  assert (R : round radix2 (SpecFloat.fexp 53 1024) (round_mode mode_NE) (IZR z) = IZR z)
    by exact (RN_binary64 _ G).
  rewrite R, Rlt_bool_true in C by exact L. destruct C as [V [F _]]. split; [exact F | exact V].
Qed.

(** The same as the class's [int_le k]. *)
Lemma fint_int : forall k z, (0 <= k <= 52)%Z -> (Z.abs z <= 2 ^ k)%Z -> int_le k (fint z).
Proof.
  intros k z K B.
  assert (B52 : (Z.abs z <= 2 ^ 52)%Z) by (apply Z.le_trans with (1 := B); apply Z.pow_le_mono_r; lia).
  destruct (fint_value z B52) as [F V]. split; [exact F|]. exists z. split; [exact V | exact B].
Qed.

Definition live_o := V3 (fint 0) (fint 0) (fint 0).
Definition live_d := V3 (fint 1) (fint 1) (fint 0).
Definition live_p := V3 (fint 1) (fint 0) (fint 0).
Definition live_n := V3 (fint 1) (fint (-1)) (fint 0).

Theorem stage3_plane_live_example :
  den_filter_b live_d live_n = Uncertain /\ den_sign2_b live_d live_n = Uncertain /\
  snd (expansions_b live_o live_d live_p live_n) = true /\
  snd (fst (expansions_b live_o live_d live_p live_n)) = [fzero] /\
  expansion_sign_b (snd (fst (expansions_b live_o live_d live_p live_n))) = Zero /\
  expansion_sign_b (fst (fst (expansions_b live_o live_d live_p live_n))) = Positive /\
  relation_b live_o live_d live_p live_n = CDecided Parallel StExpansion TNaN.
Proof. vm_compute. repeat split; reflexivity. Qed.
