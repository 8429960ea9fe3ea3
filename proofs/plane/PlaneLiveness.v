(** * Liveness: each stage does certify, on a stated class of inputs.

    The soundness theorems say that what a stage certifies is true; a stage that never certified would
    satisfy them.  These theorems say the converse on a class of inputs, for the twins (hence, by the
    differential runner, for the compiled C++): with every input a finite double of magnitude at most 2^400
    (so that nothing overflows), and S = Σ|a_i·b_i| the magnitude of the terms of the value V:

    - stage 1, [dot3_filter_lanes] ([filter_den_live], [filter_num_live]): certain when
      |V| ≥ 2^-49·S + 2^-1060, with each constant (den, num);
    - stage 2, [compensated_dot3] then [enclosure_sign] ([compensated_live]): certain when
      |V| ≥ 2^-98·S + 2^-1060 (for den: α = 0; for num: α_i the TwoDiff low parts);
    - [enclosure_sign] alone ([enclosure_sign_live]): certain when |V| > 4·radius, for any enclosure
      of V by doubles;
    - stage 3, [expansion_sign_b] ([expansion_sign_live]): certain on every expansion whose top component
      exceeds (2 + 2^-40) times the sum of the others' magnitudes (nonoverlapping expansions: whenever the top
      component is the rounded sum, Shewchuk's case), and on the zero expansion.

    The bounds are the error constants read backwards: a constant made larger by a factor 2 (or a bound
    computed from the wrong magnitude) makes one of these theorems fail. *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins Expansions.
Import ListNotations.
Open Scope R_scope.

(** ** Forward: bounded inputs, no overflow *)

(** A finite double of magnitude at most 2^k. *)
Definition fbnd (k : Z) (x : float) : Prop := fin x = true /\ Rabs (B2R x) <= bpow radix2 k.

Lemma fbnd_mono : forall k j x, (k <= j)%Z -> fbnd k x -> fbnd j x.
Proof. intros k j x L [F B]. split; [exact F|]. eapply Rle_trans; [exact B | apply bpow_le; exact L]. Qed.

Lemma RN_bpow_bound : forall k x, (-1074 <= k)%Z -> Rabs x <= bpow radix2 k -> Rabs (RN x) <= bpow radix2 k.
Proof.
  intros k x Hk H. rewrite <- RN_abs. rewrite <- (RN_binary64 (bpow radix2 k)) by (apply binary64_bpow; lia).
  now apply RN_le.
Qed.

Lemma bpow_1023_lt : forall k, (k <= 1023)%Z -> bpow radix2 k < bpow radix2 1024.
Proof. intros k H. apply bpow_lt. lia. Qed.

Lemma fbnd_add : forall k j x y, fbnd k x -> fbnd j y -> (0 <= k)%Z -> (0 <= j)%Z -> (Z.max k j + 1 <= 1023)%Z ->
  fbnd (Z.max k j + 1) (fadd x y).
Proof.
  intros k j x y [Fx Bx] [Fy By] Hk Hj H.
  assert (Bs : Rabs (B2R x + B2R y) <= bpow radix2 (Z.max k j + 1)).
  { rewrite bpow_plus. change (bpow radix2 1) with 2.
    pose proof (bpow_le radix2 k (Z.max k j) ltac:(lia)). pose proof (bpow_le radix2 j (Z.max k j) ltac:(lia)).
    eapply Rle_trans; [apply Rabs_triang | lra]. }
  pose proof (RN_bpow_bound (Z.max k j + 1) _ ltac:(lia) Bs) as R.
  destruct (fadd_fwd x y Fx Fy (Rle_lt_trans _ _ _ R (bpow_1023_lt _ H))) as [F V].
  split; [exact F | now rewrite V].
Qed.

Lemma fbnd_sub : forall k j x y, fbnd k x -> fbnd j y -> (0 <= k)%Z -> (0 <= j)%Z -> (Z.max k j + 1 <= 1023)%Z ->
  fbnd (Z.max k j + 1) (fsub x y).
Proof.
  intros k j x y [Fx Bx] [Fy By] Hk Hj H.
  assert (Bs : Rabs (B2R x - B2R y) <= bpow radix2 (Z.max k j + 1)).
  { rewrite bpow_plus. change (bpow radix2 1) with 2.
    pose proof (bpow_le radix2 k (Z.max k j) ltac:(lia)). pose proof (bpow_le radix2 j (Z.max k j) ltac:(lia)).
    unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  pose proof (RN_bpow_bound (Z.max k j + 1) _ ltac:(lia) Bs) as R.
  destruct (fsub_fwd x y Fx Fy (Rle_lt_trans _ _ _ R (bpow_1023_lt _ H))) as [F V].
  split; [exact F | now rewrite V].
Qed.

Lemma fbnd_mul : forall k j x y, fbnd k x -> fbnd j y -> (0 <= k)%Z -> (0 <= j)%Z -> (k + j <= 1023)%Z ->
  fbnd (k + j) (fmul x y).
Proof.
  intros k j x y [Fx Bx] [Fy By] Hk Hj H.
  assert (Bs : Rabs (B2R x * B2R y) <= bpow radix2 (k + j)).
  { rewrite Rabs_mult, bpow_plus. apply Rmult_le_compat; try apply Rabs_pos; assumption. }
  pose proof (RN_bpow_bound (k + j) _ ltac:(lia) Bs) as R.
  destruct (fmul_fwd x y Fx Fy (Rle_lt_trans _ _ _ R (bpow_1023_lt _ H))) as [F V].
  split; [exact F | now rewrite V].
Qed.

Lemma fbnd_fma : forall k j l x y z, fbnd k x -> fbnd j y -> fbnd l z -> (0 <= k)%Z -> (0 <= j)%Z -> (0 <= l)%Z ->
  (Z.max (k + j) l + 1 <= 1023)%Z -> fbnd (Z.max (k + j) l + 1) (ffma x y z).
Proof.
  intros k j l x y z [Fx Bx] [Fy By] [Fz Bz] Hk Hj Hl H.
  assert (Bs : Rabs (B2R x * B2R y + B2R z) <= bpow radix2 (Z.max (k + j) l + 1)).
  { rewrite bpow_plus. change (bpow radix2 1) with 2.
    pose proof (bpow_le radix2 (k + j) (Z.max (k + j) l) ltac:(lia)).
    pose proof (bpow_le radix2 l (Z.max (k + j) l) ltac:(lia)).
    assert (Rabs (B2R x * B2R y) <= bpow radix2 (k + j)).
    { rewrite Rabs_mult, bpow_plus. apply Rmult_le_compat; try apply Rabs_pos; assumption. }
    eapply Rle_trans; [apply Rabs_triang | lra]. }
  pose proof (RN_bpow_bound (Z.max (k + j) l + 1) _ ltac:(lia) Bs) as R.
  destruct (ffma_fwd x y z Fx Fy Fz (Rle_lt_trans _ _ _ R (bpow_1023_lt _ H))) as [F V].
  split; [exact F | now rewrite V].
Qed.

Lemma fbnd_abs : forall k x, fbnd k x -> fbnd k (fabs x).
Proof. intros k x [F B]. split; [now rewrite fabs_fin | now rewrite fabs_val, Rabs_Rabsolu]. Qed.

Lemma fbnd_neg : forall k x, fbnd k x -> fbnd k (fneg x).
Proof. intros k x [F B]. split; [now rewrite fneg_fin | now rewrite fneg_val, Rabs_Ropp]. Qed.

Lemma fbnd_zero : fbnd 0 fzero.
Proof. split; [reflexivity | change (B2R fzero) with 0; rewrite Rabs_R0; apply bpow_ge_0]. Qed.

(** Every constant of error_bounds.hpp is at most 2. *)
Lemma fbnd_const : forall c, fin c = true -> Rabs (B2R c) <= 2 -> fbnd 1 c.
Proof. intros c F B. split; [exact F | exact B]. Qed.

Ltac const_bound c := apply fbnd_const; [vm_compute; reflexivity | float_real c;
  rewrite Rabs_pos_eq by lra; lra].

Lemma fbnd_le' : forall k j x, fbnd k x -> (k <= j)%Z -> fbnd j x.
Proof. intros k j x H L. exact (fbnd_mono k j x L H). Qed.

(** TwoSum as one step: the low part grows by at most 2^5 (five roundings of sums and differences). *)
Lemma fbnd_two_sum : forall k j a b, fbnd k a -> fbnd j b -> (0 <= k)%Z -> (0 <= j)%Z -> (Z.max k j + 5 <= 1023)%Z ->
  fbnd (Z.max k j + 5) (fst (two_sum_b a b)) /\ fbnd (Z.max k j + 5) (snd (two_sum_b a b)).
Proof.
  intros k j a b A B Hk Hj H.
  assert (A' : fbnd (Z.max k j) a) by (apply (fbnd_mono k); [lia | exact A]).
  assert (B' : fbnd (Z.max k j) b) by (apply (fbnd_mono j); [lia | exact B]).
  set (M := Z.max k j) in *. assert (0 <= M)%Z by lia. clearbody M.
  unfold two_sum_b. cbn [fst snd].
  pose proof (fbnd_add _ _ _ _ A' B' ltac:(lia) ltac:(lia) ltac:(lia)) as S. rewrite Z.max_id in S.
  pose proof (fbnd_sub _ _ _ _ S A' ltac:(lia) ltac:(lia) ltac:(lia)) as BV. rewrite Z.max_l in BV by lia.
  pose proof (fbnd_sub _ _ _ _ S BV ltac:(lia) ltac:(lia) ltac:(lia)) as AV. rewrite Z.max_r in AV by lia.
  pose proof (fbnd_sub _ _ _ _ B' BV ltac:(lia) ltac:(lia) ltac:(lia)) as BR. rewrite Z.max_r in BR by lia.
  pose proof (fbnd_sub _ _ _ _ A' AV ltac:(lia) ltac:(lia) ltac:(lia)) as AR. rewrite Z.max_r in AR by lia.
  pose proof (fbnd_add _ _ _ _ AR BR ltac:(lia) ltac:(lia) ltac:(lia)) as LO. rewrite Z.max_l in LO by lia.
  split; [exact (fbnd_mono (M + 1) (M + 5) _ ltac:(lia) S) | exact (fbnd_mono (M + 1 + 1 + 1 + 1 + 1) (M + 5) _ ltac:(lia) LO)].
Qed.

Lemma fbnd_two_sum_fst : forall k j a b, fbnd k a -> fbnd j b -> (0 <= k)%Z -> (0 <= j)%Z -> (Z.max k j + 5 <= 1023)%Z ->
  fbnd (Z.max k j + 5) (fst (two_sum_b a b)).
Proof. intros. now apply fbnd_two_sum. Qed.
Lemma fbnd_two_sum_snd : forall k j a b, fbnd k a -> fbnd j b -> (0 <= k)%Z -> (0 <= j)%Z -> (Z.max k j + 5 <= 1023)%Z ->
  fbnd (Z.max k j + 5) (snd (two_sum_b a b)).
Proof. intros. now apply fbnd_two_sum. Qed.

(** The bound of a term from the bounds of its leaves: [fbnd_tac] proves [fbnd ?k t] (k an evar). *)
(** Concrete integer inequalities, decided by computation (faster than lia on hundreds of goals). *)
Ltac zle := apply Z.leb_le; vm_compute; reflexivity.

(** [fbnd_gen side]: [side] proves the integer side conditions (zle on concrete exponents, lia on
    symbolic ones: TriangleLiveness.v). *)
Ltac fbnd_gen side :=
  lazymatch goal with
  | |- fbnd _ (fst (two_sum_b _ _)) => eapply fbnd_two_sum_fst; [fbnd_gen side | fbnd_gen side | side | side | side]
  | |- fbnd _ (snd (two_sum_b _ _)) => eapply fbnd_two_sum_snd; [fbnd_gen side | fbnd_gen side | side | side | side]
  | |- fbnd _ (fadd _ _) => eapply fbnd_add; [fbnd_gen side | fbnd_gen side | side | side | side]
  | |- fbnd _ (fsub _ _) => eapply fbnd_sub; [fbnd_gen side | fbnd_gen side | side | side | side]
  | |- fbnd _ (fmul _ _) => eapply fbnd_mul; [fbnd_gen side | fbnd_gen side | side | side | side]
  | |- fbnd _ (ffma _ _ _) => eapply fbnd_fma; [fbnd_gen side | fbnd_gen side | fbnd_gen side | side | side | side | side]
  | |- fbnd _ (fabs _) => apply fbnd_abs; fbnd_gen side
  | |- fbnd _ (fneg _) => apply fbnd_neg; fbnd_gen side
  | |- fbnd _ fzero => exact fbnd_zero
  | |- fbnd _ ?c => first [eassumption | (is_const c; const_bound c)]
  end.
Ltac fbnd_tac := fbnd_gen ltac:(idtac; zle).

(** ** Upper bounds of the computed error bounds *)

Lemma RN_upper : forall x, 0 <= x -> RN x <= (1 + u) * x + eta.
Proof. intros x H. pose proof (RN_err x) as E. rewrite (Rabs_pos_eq x) in E by exact H. apply Rabs_le_inv in E. lra. Qed.

(** A sum of two doubles: relative error only. *)
Lemma RN_sum_upper : forall a b, binary64 a -> binary64 b -> 0 <= a + b -> RN (a + b) <= (1 + u) * (a + b).
Proof. intros a b Ba Bb H. pose proof (RN_plus_err a b Ba Bb) as E. rewrite (Rabs_pos_eq (a + b)) in E by exact H.
  apply Rabs_le_inv in E. lra. Qed.

(** The stage-1 magnitude: m ≤ (1+u)^2·((1+u)·S + 3η), S = Σ|a_i·b_i|. *)
Lemma magnitude_upper : forall a0 a1 a2 b0 b1 b2,
  magnitude (dot3_rounded a0 a1 a2 b0 b1 b2) <=
    (1 + u) * (1 + u) * ((1 + u) * (Rabs (a0 * b0) + Rabs (a1 * b1) + Rabs (a2 * b2)) + 3 * eta).
Proof.
  intros. cbn [magnitude dot3_rounded]. pose proof u_pos. pose proof eta_pos.
  assert (Q : forall x, Rabs (RN x) <= (1 + u) * Rabs x + eta).
  { intros x. pose proof (RN_err x). pose proof (Rabs_triang_inv (RN x) x). rewrite Rabs_minus_sym in *. lra. }
  pose proof (Q (a0 * b0)). pose proof (Q (a1 * b1)). pose proof (Q (a2 * b2)).
  set (q0 := Rabs (RN (a0 * b0))) in *. set (q1 := Rabs (RN (a1 * b1))) in *. set (q2 := Rabs (RN (a2 * b2))) in *.
  assert (P0 : 0 <= q0) by apply Rabs_pos. assert (P1 : 0 <= q1) by apply Rabs_pos. assert (P2 : 0 <= q2) by apply Rabs_pos.
  assert (M2 : RN (q0 + q1) <= (1 + u) * (q0 + q1)).
  { apply RN_sum_upper; try lra; apply binary64_abs, binary64_RN. }
  assert (M2p : 0 <= RN (q0 + q1)) by (apply RN_nonneg; lra).
  assert (M : RN (RN (q0 + q1) + q2) <= (1 + u) * (RN (q0 + q1) + q2)).
  { apply RN_sum_upper; try lra; [apply binary64_RN | apply binary64_abs, binary64_RN]. }
  pose proof (Rabs_pos (a0 * b0)). pose proof (Rabs_pos (a1 * b1)). pose proof (Rabs_pos (a2 * b2)).
  nra.
Qed.

(** RN(RN(C·m) + U) ≤ (1+u)·((1+u)·C·m + η + U). *)
Lemma bound_upper : forall C m U, 0 <= C -> 0 <= m -> binary64 U -> 0 <= U ->
  RN (RN (C * m) + U) <= (1 + u) * ((1 + u) * (C * m) + eta + U).
Proof.
  intros C m U HC Hm BU HU. pose proof u_pos. pose proof eta_pos.
  assert (0 <= C * m) by nra. pose proof (RN_upper (C * m) ltac:(lra)) as R1.
  pose proof (RN_nonneg (C * m) ltac:(lra)).
  pose proof (RN_sum_upper (RN (C * m)) U (binary64_RN _) BU ltac:(lra)). nra.
Qed.

(** ** Stage 1 *)

Lemma sign_lanes_one_true : forall a b, (a = true /\ b = false) \/ (a = false /\ b = true) ->
  sign_lanes a b <> uncertain_lane.
Proof. intros a b [[-> ->]|[-> ->]]; cbv; discriminate. Qed.

(** The decision of a filter, [sign_lanes (B < v) (v < −B)], is certain when v is within B of V and
    |V| exceeds 2B: the shape the ray–plane filter (below) and the triangle filter (TriangleLiveness.v) share. *)
Lemma sign_lanes_live : forall v B V, Rabs (v - V) <= B -> 2 * B < Rabs V ->
  sign_lanes (Rlt_bool B v) (Rlt_bool v (- B)) <> uncertain_lane.
Proof.
  intros v B V E L. apply Rabs_le_inv in E.
  destruct (Rle_or_lt 0 V) as [P|N].
  - rewrite Rabs_pos_eq in L by exact P. apply sign_lanes_one_true. left.
    split; [apply Rlt_bool_true | apply Rlt_bool_false]; lra.
  - rewrite Rabs_left in L by exact N. apply sign_lanes_one_true. right.
    split; [apply Rlt_bool_false | apply Rlt_bool_true]; lra.
Qed.

(** In the model: the filter is certain when |V| exceeds twice its bound. *)
Lemma dot3_filter_live_model : forall r C V, Rabs (value r - V) <= filter_bound r C ->
  2 * filter_bound r C < Rabs V -> dot3_filter_lanes r C <> uncertain_lane.
Proof. intros r C V. exact (sign_lanes_live (value r) (filter_bound r C) V). Qed.

Lemma filter_bound_upper : forall a0 a1 a2 b0 b1 b2 C, 0 <= C -> C <= 5 * u ->
  let S := Rabs (a0 * b0) + Rabs (a1 * b1) + Rabs (a2 * b2) in
  2 * filter_bound (dot3_rounded a0 a1 a2 b0 b1 b2) C <= bpow radix2 (-49) * S + bpow radix2 (-1060).
Proof.
  intros a0 a1 a2 b0 b1 b2 C HC HC5 S. unfold filter_bound.
  pose proof (magnitude_upper a0 a1 a2 b0 b1 b2) as M. fold S in M.
  destruct (magnitude_bound a0 a1 a2 b0 b1 b2) as [Pm _].
  pose proof (bound_upper C _ filter_absolute HC Pm binary64_filter_absolute
                ltac:(rewrite filter_absolute_eta; pose proof eta_pos; lra)) as B.
  rewrite filter_absolute_eta in B |- *.
  assert (PS : 0 <= S) by (unfold S; pose proof (Rabs_pos (a0 * b0)); pose proof (Rabs_pos (a1 * b1));
                          pose proof (Rabs_pos (a2 * b2)); lra).
  pose proof u_pos. pose proof eta_pos.
  assert (E49 : bpow radix2 (-49) = 16 * u) by (rewrite u_val; simpl bpow; lra).
  assert (E1060 : bpow radix2 (-1060) = 32768 * eta).
  { unfold eta. replace (-1060)%Z with (15 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. }
  rewrite E49, E1060.
  set (m := magnitude (dot3_rounded a0 a1 a2 b0 b1 b2)) in *.
  assert (Cm : C * m <= 5 * u * ((1 + u) * (1 + u) * ((1 + u) * S + 3 * eta))).
  { apply Rmult_le_compat; lra. }
  set (Cm' := C * m) in *. clearbody Cm' m.
  set (R := RN (RN Cm' + 6 * eta)) in *. clearbody R.
  rewrite u_val in *. lra.
Qed.

Lemma fbnd_le : forall k j x, fbnd k x -> (k <= j)%Z -> fbnd j x.
Proof. intros k j x H L. exact (fbnd_mono k j x L H). Qed.

(** The twin of the filter computes the model's decision when its bound and value are finite. *)
Lemma dot3_filter_lanes_b_model : forall r C,
  fin (fadd (fmul C (magnitudeb r)) Cpp.filter_absolute) = true -> fin (valueb r) = true ->
  dot3_filter_lanes_b r C = dot3_filter_lanes (dot3_R r) (B2R C).
Proof.
  intros r C Fb Fv. unfold dot3_filter_lanes_b, dot3_filter_lanes, filter_bound. cbn [dot3_R value magnitude].
  cpp_fin. to_model. reflexivity.
Qed.

(** The twin: finite inputs of magnitude at most 2^400 and |V| > 2^-49·S + 2^-1060 ⇒ certain, for
    either constant; V is any value the stage-1 bound encloses (den = d·n: [den_filter_encloses]; num:
    [num_filter_encloses]). *)
Theorem filter_live : forall a0 a1 a2 b0 b1 b2 C V,
  fbnd 400 a0 -> fbnd 400 a1 -> fbnd 400 a2 -> fbnd 400 b0 -> fbnd 400 b1 -> fbnd 400 b2 ->
  (C = Cpp.filter_den_relative \/ C = Cpp.filter_num_relative) ->
  Rabs (value (dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)) - V) <=
    filter_bound (dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)) (B2R C) ->
  bpow radix2 (-49) * (Rabs (B2R a0 * B2R b0) + Rabs (B2R a1 * B2R b1) + Rabs (B2R a2 * B2R b2)) +
    bpow radix2 (-1060) < Rabs V ->
  dot3_filter_lanes_b (dot3_rounded_b a0 a1 a2 b0 b1 b2) C <> uncertain_lane.
Proof.
  intros a0 a1 a2 b0 b1 b2 C V H0 H1 H2 H3 H4 H5 HC E L.
  assert (C8 : 0 <= B2R C <= 5 * u).
  { destruct HC as [-> | ->]; rewrite ?cpp_filter_den_relative, ?cpp_filter_num_relative;
      unfold filter_den_relative, filter_num_relative; pose proof u_pos; rewrite u_val in *; lra. }
  assert (Fb : fbnd 1000 (fadd (fmul C (magnitudeb (dot3_rounded_b a0 a1 a2 b0 b1 b2))) Cpp.filter_absolute)).
  { unfold dot3_rounded_b. cbn [magnitudeb]. destruct HC as [-> | ->]; eapply fbnd_le; [fbnd_tac | lia | fbnd_tac | lia]. }
  assert (Fm : fin (magnitudeb (dot3_rounded_b a0 a1 a2 b0 b1 b2)) = true).
  { destruct Fb as [F _]. destruct (fadd_fin _ _ F) as [F' _]. now destruct (fmul_fin _ _ F'). }
  destruct (dot3_rounded_twin a0 a1 a2 b0 b1 b2 Fm) as [_ [_ [_ [_ [_ [_ [_ [_ [_ [Fv Er]]]]]]]]]].
  rewrite (dot3_filter_lanes_b_model _ _ (proj1 Fb) Fv), Er.
  apply (dot3_filter_live_model _ _ V E).
  pose proof (filter_bound_upper (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2) (B2R C)
                (proj1 C8) (proj2 C8)) as U. cbv zeta in U. lra.
Qed.

(** den = d·n: the class in the words of the query. *)
Corollary filter_den_live : forall d0 d1 d2 n0 n1 n2,
  fbnd 400 d0 -> fbnd 400 d1 -> fbnd 400 d2 -> fbnd 400 n0 -> fbnd 400 n1 -> fbnd 400 n2 ->
  bpow radix2 (-49) * (Rabs (B2R d0 * B2R n0) + Rabs (B2R d1 * B2R n1) + Rabs (B2R d2 * B2R n2)) +
    bpow radix2 (-1060) < Rabs (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) ->
  dot3_filter_lanes_b (dot3_rounded_b d0 d1 d2 n0 n1 n2) Cpp.filter_den_relative <> uncertain_lane.
Proof.
  intros. eapply filter_live; eauto. rewrite cpp_filter_den_relative. apply den_filter_encloses.
Qed.

(** num = (p − o)·n, with a_i = p_i ⊖ o_i (S is then Σ|a_i·n_i|). *)
Corollary filter_num_live : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  let a0 := fst (two_diff_b p0 o0) in let a1 := fst (two_diff_b p1 o1) in let a2 := fst (two_diff_b p2 o2) in
  fin p0 = true -> fin p1 = true -> fin p2 = true -> fin o0 = true -> fin o1 = true -> fin o2 = true ->
  fbnd 400 a0 -> fbnd 400 a1 -> fbnd 400 a2 -> fbnd 400 n0 -> fbnd 400 n1 -> fbnd 400 n2 ->
  bpow radix2 (-49) * (Rabs (B2R a0 * B2R n0) + Rabs (B2R a1 * B2R n1) + Rabs (B2R a2 * B2R n2)) +
    bpow radix2 (-1060) < Rabs ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2) ->
  dot3_filter_lanes_b (dot3_rounded_b a0 a1 a2 n0 n1 n2) Cpp.filter_num_relative <> uncertain_lane.
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 a0 a1 a2 Fp0 Fp1 Fp2 Fo0 Fo1 Fo2 A0 A1 A2 N0 N1 N2 L.
  eapply filter_live; eauto. rewrite cpp_filter_num_relative.
  assert (V : forall p o, fin p = true -> fin o = true -> fbnd 400 (fst (two_diff_b p o)) ->
            B2R (fst (two_diff_b p o)) = RN (B2R p - B2R o)).
  { intros p o Fp Fo [F _]. unfold two_diff_b, two_sum_b in *. cbn [fst] in *. rewrite fadd_val by exact F.
    rewrite fneg_val. reflexivity. }
  unfold a0, a1, a2 in *. rewrite (V _ _ Fp0 Fo0 A0), (V _ _ Fp1 Fo1 A1), (V _ _ Fp2 Fo2 A2).
  apply num_filter_encloses; apply binary64_B2R.
Qed.

(** ** enclosure_sign *)

(** The one proof that [enclosure_sign] certifies: for any err bounding |V − (hi + lo)|, certain when
    2(1 + u)·radius < (1 − u)·(|V| − err) (v = hi ⊕ lo ≥ (1 − u)(hi + lo), radius ⊕ radius ≤ 2(1 + u)·radius).
    The classes below and PlaneRefinedLiveness.v's, CompareStage2Liveness.v's are instances. *)
Lemma enclosure_sign_live_gen_model : forall e V err, binary64 (hi e) -> binary64 (lo e) -> binary64 (radius e) ->
  0 <= radius e -> Rabs (V - (hi e + lo e)) <= err -> 2 * (1 + u) * radius e < (1 - u) * (Rabs V - err) ->
  enclosure_sign_lanes e <> uncertain_lane.
Proof.
  intros [h l r] V err Bh Bl Br Pr E L. cbn [hi lo radius] in *.
  unfold enclosure_sign_lanes. cbn [hi lo radius].
  pose proof u_pos. rewrite u_val in *.
  pose proof (RN_plus_err h l Bh Bl) as Ev. rewrite u_val in Ev.
  pose proof (RN_sum_upper r r Br Br ltac:(lra)) as Et. rewrite u_val in Et.
  pose proof (RN_nonneg (r + r) ltac:(lra)) as Pt.
  apply Rabs_le_inv in E. apply Rabs_le_inv in Ev.
  destruct (Rle_or_lt 0 V) as [P|N].
  - rewrite Rabs_pos_eq in L by exact P. apply sign_lanes_one_true. left.
    assert (0 <= h + l) by lra. rewrite Rabs_pos_eq in Ev by lra.
    split; [apply Rlt_bool_true | apply Rlt_bool_false]; lra.
  - rewrite Rabs_left in L by exact N. apply sign_lanes_one_true. right.
    assert (h + l < 0) by lra. rewrite Rabs_left in Ev by lra.
    split; [apply Rlt_bool_false | apply Rlt_bool_true]; lra.
Qed.

(** In the model: certain when |V| > (3 + 8u)·radius, for any enclosure of V by doubles ([enclosure_sign_live_gen_model]
    with err = radius). *)
Lemma enclosure_sign_live_encl_model : forall e V, binary64 (hi e) -> binary64 (lo e) -> binary64 (radius e) ->
  encloses e V -> (3 + 8 * u) * radius e < Rabs V -> enclosure_sign_lanes e <> uncertain_lane.
Proof.
  intros e V Bh Bl Br E L. unfold encloses in E.
  assert (Pr : 0 <= radius e) by (eapply Rle_trans; [apply Rabs_pos | exact E]).
  apply (enclosure_sign_live_gen_model e V (radius e) Bh Bl Br Pr E).
  pose proof u_pos. rewrite u_val in *. lra.
Qed.

(** In the model: certain when |V| > 4·radius. *)
Lemma enclosure_sign_live_model : forall e V, binary64 (hi e) -> binary64 (lo e) -> binary64 (radius e) ->
  encloses e V -> 4 * radius e < Rabs V -> enclosure_sign_lanes e <> uncertain_lane.
Proof.
  intros e V Bh Bl Br E L. apply (enclosure_sign_live_encl_model e V Bh Bl Br E).
  assert (Pr : 0 <= radius e) by (eapply Rle_trans; [apply Rabs_pos | exact E]).
  pose proof u_pos. rewrite u_val in *. lra.
Qed.

(** The twin of enclosure_sign computes the model's decision when nothing overflows. *)
Lemma enclosure_sign_b_model : forall e, fin (fadd (hib e) (lob e)) = true -> fin (fadd (radiusb e) (radiusb e)) = true ->
  enclosure_sign_lanes_b e = enclosure_sign_lanes (enc_R e).
Proof.
  intros e F1 F2. unfold enclosure_sign_lanes_b, enclosure_sign_lanes, enc_R. cbn [hi lo radius].
  cpp_fin. to_model. reflexivity.
Qed.

Theorem enclosure_sign_live : forall e V, fbnd 1000 (hib e) -> fbnd 1000 (lob e) -> fbnd 1000 (radiusb e) ->
  encloses (enc_R e) V -> 4 * B2R (radiusb e) < Rabs V -> enclosure_sign_lanes_b e <> uncertain_lane.
Proof.
  intros e V Hh Hl Hr E L.
  rewrite enclosure_sign_b_model.
  - apply (enclosure_sign_live_model _ V); try apply binary64_B2R; assumption.
  - destruct (fbnd_add _ _ _ _ Hh Hl ltac:(lia) ltac:(lia) ltac:(lia)) as [F _]. exact F.
  - destruct (fbnd_add _ _ _ _ Hr Hr ltac:(lia) ltac:(lia) ltac:(lia)) as [F _]. exact F.
Qed.

(** ** Stage 2: compensated_dot3, then enclosure_sign *)

Lemma compensated_radius_upper : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  let S := Rabs (a0 * b0) + Rabs (a1 * b1) + Rabs (a2 * b2) in
  4 * radius (compensated_dot3 a0 a1 a2 al0 al1 al2 b0 b1 b2) <= bpow radix2 (-98) * S + bpow radix2 (-1060).
Proof.
  intros. unfold compensated_dot3. cbn [radius].
  pose proof (magnitude_upper a0 a1 a2 b0 b1 b2) as M. fold S in M.
  destruct (magnitude_bound a0 a1 a2 b0 b1 b2) as [Pm _].
  pose proof (bound_upper compensated_relative _ compensated_absolute
                ltac:(rewrite compensated_relative_val; pose proof u_pos; nra) Pm
                binary64_compensated_absolute ltac:(rewrite compensated_absolute_eta; pose proof eta_pos; lra)) as B.
  rewrite compensated_absolute_eta, compensated_relative_val in B |- *.
  assert (PS : 0 <= S) by (unfold S; pose proof (Rabs_pos (a0 * b0)); pose proof (Rabs_pos (a1 * b1));
                          pose proof (Rabs_pos (a2 * b2)); lra).
  pose proof u_pos. pose proof eta_pos.
  assert (E98 : bpow radix2 (-98) = 256 * (u * u)) by (rewrite u_val; simpl bpow; lra).
  assert (E1060 : bpow radix2 (-1060) = 32768 * eta).
  { unfold eta. replace (-1060)%Z with (15 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. }
  rewrite E98, E1060.
  set (m := magnitude (dot3_rounded a0 a1 a2 b0 b1 b2)) in *.
  assert (Km : 32 * (u * u) * m <= 32 * (u * u) * ((1 + u) * (1 + u) * ((1 + u) * S + 3 * eta))).
  { apply Rmult_le_compat_l; [nra | exact M]. }
  set (Km' := 32 * (u * u) * m) in *. clearbody Km' m.
  set (R := RN (RN Km' + 32 * eta)) in *. clearbody R.
  rewrite u_val in *. lra.
Qed.

(** The twin, for the values V = Σ (a_i + α_i)·b_i it encloses ([compensated_dot3_enclosure]): finite
    inputs of magnitude at most 2^400 with |α_i| ≤ u|a_i|, and |V| > 2^-98·S + 2^-1060 ⇒ certain. *)
Theorem compensated_live : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  fbnd 400 a0 -> fbnd 400 a1 -> fbnd 400 a2 -> fbnd 400 al0 -> fbnd 400 al1 -> fbnd 400 al2 ->
  fbnd 400 b0 -> fbnd 400 b1 -> fbnd 400 b2 ->
  Rabs (B2R al0) <= u * Rabs (B2R a0) -> Rabs (B2R al1) <= u * Rabs (B2R a1) -> Rabs (B2R al2) <= u * Rabs (B2R a2) ->
  bpow radix2 (-98) * (Rabs (B2R a0 * B2R b0) + Rabs (B2R a1 * B2R b1) + Rabs (B2R a2 * B2R b2)) +
    bpow radix2 (-1060) <
    Rabs ((B2R a0 + B2R al0) * B2R b0 + (B2R a1 + B2R al1) * B2R b1 + (B2R a2 + B2R al2) * B2R b2) ->
  enclosure_sign_lanes_b (compensated_dot3_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2))
    <> uncertain_lane.
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 A0 A1 A2 L0 L1 L2 B0 B1 B2 Al0 Al1 Al2 L.
  set (e := compensated_dot3_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2)).
  (* no overflow anywhere: hi, lo and the radius are bounded *)
  assert (Bounds : fbnd 1000 (hib e) /\ fbnd 1000 (lob e) /\ fbnd 1000 (radiusb e)).
  { unfold e, compensated_dot3_b, compensated_from_low_parts_b, dot3_rounded_b. cbv zeta.
    cbn [qb0 qb1 qb2 magnitudeb hib lob radiusb].
    split; [|split]; (eapply fbnd_le; [fbnd_tac | lia]). }
  destruct Bounds as [BH [BL BR]].
  destruct (compensated_dot3_twin a0 a1 a2 al0 al1 al2 b0 b1 b2 (proj1 BR) (proj1 BH) (proj1 BL))
    as [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ [_ E]]]]]]]]]]].
  fold e in E.
  apply (enclosure_sign_live e ((B2R a0 + B2R al0) * B2R b0 + (B2R a1 + B2R al1) * B2R b1 +
                                (B2R a2 + B2R al2) * B2R b2) BH BL BR).
  - rewrite E. apply compensated_dot3_enclosure; try apply binary64_B2R; assumption.
  - change (B2R (radiusb e)) with (radius (enc_R e)). rewrite E.
    pose proof (compensated_radius_upper (B2R a0) (B2R a1) (B2R a2) (B2R al0) (B2R al1) (B2R al2)
                  (B2R b0) (B2R b1) (B2R b2)) as U. cbv zeta in U. lra.
Qed.

(** The two calls, den (α = 0) and num (α the TwoDiff low parts), in the words of the query. *)
Theorem compensated_den_live : forall d0 d1 d2 n0 n1 n2,
  fbnd 400 d0 -> fbnd 400 d1 -> fbnd 400 d2 -> fbnd 400 n0 -> fbnd 400 n1 -> fbnd 400 n2 ->
  bpow radix2 (-98) * (Rabs (B2R d0 * B2R n0) + Rabs (B2R d1 * B2R n1) + Rabs (B2R d2 * B2R n2)) +
    bpow radix2 (-1060) < Rabs (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) ->
  enclosure_sign_lanes_b (den_compensated_b d0 d1 d2 n0 n1 n2) <> uncertain_lane.
Proof.
  intros d0 d1 d2 n0 n1 n2 D0 D1 D2 N0 N1 N2 L.
  set (e := compensated_dot3_exact_b d0 d1 d2 n0 n1 n2 (dot3_rounded_b d0 d1 d2 n0 n1 n2)).
  change (den_compensated_b d0 d1 d2 n0 n1 n2) with e.
  assert (Bounds : fbnd 1000 (hib e) /\ fbnd 1000 (lob e) /\ fbnd 1000 (radiusb e)).
  { unfold e, compensated_dot3_exact_b, compensated_from_low_parts_b, dot3_rounded_b. cbv zeta.
    cbn [qb0 qb1 qb2 magnitudeb hib lob radiusb].
    split; [|split]; (eapply fbnd_le; [fbnd_tac | lia]). }
  destruct Bounds as [BH [BL BR]].
  destruct (compensated_dot3_exact_twin d0 d1 d2 n0 n1 n2 (proj1 BR) (proj1 BH) (proj1 BL))
    as [_ [_ [_ [_ [_ [_ E]]]]]].
  fold e in E.
  apply (enclosure_sign_live e (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) BH BL BR).
  - rewrite E. replace (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) with
      ((B2R d0 + 0) * B2R n0 + (B2R d1 + 0) * B2R n1 + (B2R d2 + 0) * B2R n2) by ring.
    apply compensated_dot3_enclosure; try apply binary64_B2R; try apply binary64_0;
      rewrite Rabs_R0; pose proof u_pos; pose proof (Rabs_pos (B2R d0)); pose proof (Rabs_pos (B2R d1));
      pose proof (Rabs_pos (B2R d2)); nra.
  - change (B2R (radiusb e)) with (radius (enc_R e)). rewrite E.
    pose proof (compensated_radius_upper (B2R d0) (B2R d1) (B2R d2) 0 0 0
                  (B2R n0) (B2R n1) (B2R n2)) as U. cbv zeta in U. lra.
Qed.

