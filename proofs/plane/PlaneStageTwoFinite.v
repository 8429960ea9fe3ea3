(** * Stage 2 for every bit pattern: a certified sign implies finite hi and lo.

    Since issue 13 the C++ stage 2 (dot3_compensated.hpp, compare_quotients.hpp) tests no finiteness of hi
    and lo: a non-finite value must make the decision uncertain by itself.  The twin theorems of PlaneTwins.v
    ([den_compensated_twin_sound], [num_compensated_twin_sound]) and CompareTwins.v
    ([compare_quotients_compensated_twin]) take "hi and lo finite" as a hypothesis; this file discharges
    it, for every 64-bit pattern of every input (NaN, ±inf included), for the consumers that take a sign from
    stage 2 without a certified t (ray_plane_cascade.cpp's [certified_signs], compare_quotients.hpp's
    [compare_quotients_compensated] as nearest_hit.cpp's [compare_hit_distances] uses it):

    - [two_sum_b_nan_or_finite]: TwoSum of two finite doubles whose sum is finite has a low part that is
      NaN or finite, never ±inf.  (Its intermediate a − (s − a') can overflow: for a = −(2^1022 + 3·2^970)
      and b = the largest double, s is finite but s − a rounds to +inf; then the low part is inf − inf =
      NaN.  With a finite b_virtual every other operation stays below 2^1024: [two_sum_inner_bounded].)
    - [den_compensated_certain_finite], [num_compensated_certain_finite]: a certain [enclosure_sign] of
      stage 2's first level implies finite hi and lo; [den_compensated_twin_sound_total],
      [num_compensated_twin_sound_total]: the end-to-end theorems without that hypothesis.
    - [compare_compensated_certain_finite]: a certain [enclosure_sign] of [compare_quotients_compensated]
      (any four input enclosures with radii non-negative or NaN) implies finite inputs, hi and lo;
      [compare_compensated_twin_sound_total]: its sign is then the sign of Δ for any reals the inputs
      enclose.

    The argument is the one proofs/README.md, "Overflow", gave in words: a certain sign needs a finite
    radius, hence a finite magnitude, which bounds hi; lo is a sum of values below 2^973 (rounding errors of
    values below 2^1024) unless one of them is NaN, and a NaN lo makes hi ⊕ lo NaN, which no comparison
    certifies. *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN Sterbenz.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins CompareTwins PlaneLiveness.
Open Scope R_scope.

(** ** The model: TwoSum's intermediates *)

Lemma RN_nearest : forall x g, binary64 g -> Rabs (RN x - x) <= Rabs (g - x).
Proof.
  intros x g Hg.
  destruct (round_N_pt radix2 (FLT_exp (-1074) 53) (fun t => negb (Z.even t)) x) as [_ H].
  now apply H.
Qed.

Lemma RN_abs_le_double : forall x y, binary64 y -> Rabs x <= Rabs y -> Rabs (RN x) <= Rabs y.
Proof.
  intros x y Hy H. rewrite <- RN_abs, <- (RN_binary64 (Rabs y)) by now apply binary64_abs.
  now apply RN_le.
Qed.

Lemma binary64_half_large : forall a, binary64 a -> bpow radix2 1023 < a -> binary64 (a / 2).
Proof.
  intros a Ha L.
  destruct (FLT_format_generic radix2 (-1074) 53 a Ha) as [[m e] E Hm He]. simpl in E, Hm, He.
  unfold F2R in E. simpl in E.
  assert (Ee : (971 <= e)%Z).
  { destruct (Z_lt_le_dec e 971) as [Lt|]; [|lia]. exfalso.
    assert (Hm' : Rabs (IZR m) < bpow radix2 53).
    { rewrite <- abs_IZR. rewrite <- IZR_Zpower by lia. apply IZR_lt. exact Hm. }
    assert (Be : bpow radix2 e <= bpow radix2 970) by (apply bpow_le; lia).
    assert (a <= Rabs (IZR m) * bpow radix2 e).
    { rewrite E. rewrite <- (Rabs_pos_eq (bpow radix2 e)) at 2 by apply bpow_ge_0. rewrite <- Rabs_mult. apply Rle_abs. }
    assert (Rabs (IZR m) * bpow radix2 e <= bpow radix2 53 * bpow radix2 970).
    { apply Rmult_le_compat; try apply Rabs_pos; try apply bpow_ge_0; lra. }
    rewrite <- bpow_plus in H0. change (53 + 970)%Z with 1023%Z in H0. lra. }
  replace (a / 2) with (IZR m * bpow radix2 (e - 1)).
  - apply binary64_dyadic; [exact Hm | lia].
  - rewrite E. replace (e - 1)%Z with (e + -1)%Z by ring. rewrite bpow_plus. change (bpow radix2 (-1)) with (/ 2). field.
Qed.

Lemma bpow_972 : bpow radix2 972 = 2 * bpow radix2 971.
Proof. change 972%Z with (1 + 971)%Z. rewrite bpow_plus. reflexivity. Qed.

Lemma bpow_plus_1' : bpow radix2 1023 = 2 * bpow radix2 1022.
Proof. change 1023%Z with (1 + 1022)%Z. rewrite bpow_plus. reflexivity. Qed.

Lemma bpow_plus_2' : bpow radix2 1024 = 4 * bpow radix2 1022.
Proof. change 1024%Z with (2 + 1022)%Z. rewrite bpow_plus. reflexivity. Qed.

(** a_virtual for a > 2^1023: either a + b is a double (Sterbenz), and then a_virtual = a, or s − a is one
    (Sterbenz on s and a, as in Fast2Sum), and again a_virtual = a; or b ≥ 0 and a_virtual lies in [0, s]. *)
Lemma ts_av_large : forall a b, binary64 a -> binary64 b -> bpow radix2 1023 < a ->
  Rabs a < bpow radix2 1024 -> Rabs b < bpow radix2 1024 -> Rabs (RN (a + b)) < bpow radix2 1024 ->
  Rabs (RN (RN (a + b) - RN (RN (a + b) - a))) < bpow radix2 1024.
Proof.
  intros a b Ha Hb L Fa Fb Fs.
  pose proof (bpow_gt_0 radix2 1023) as P.
  assert (Exact : binary64 (a + b) -> Rabs (RN (RN (a + b) - RN (RN (a + b) - a))) < bpow radix2 1024).
  { intros E. rewrite (RN_binary64 (a + b) E). replace (a + b - a) with b by ring.
    rewrite (RN_binary64 b Hb). replace (a + b - b) with a by ring. now rewrite (RN_binary64 a Ha). }
  assert (Ss : binary64 (RN (a + b))) by apply binary64_RN.
  set (s := RN (a + b)) in *.
  destruct (Rle_or_lt 0 b) as [Pb|Nb].
  - (* b ≥ 0: a ≤ s, 0 ≤ s − a ≤ s, so b_virtual and a_virtual lie in [0, s] *)
    assert (As : a <= s) by (unfold s; rewrite <- (RN_binary64 a Ha) at 1; apply RN_le; lra).
    assert (B0 : 0 <= RN (s - a)) by (apply RN_nonneg; lra).
    assert (B1 : RN (s - a) <= s) by (rewrite <- (RN_binary64 s Ss) at 2; apply RN_le; lra).
    assert (V0 : 0 <= RN (s - RN (s - a))) by (apply RN_nonneg; lra).
    assert (V1 : RN (s - RN (s - a)) <= s) by (rewrite <- (RN_binary64 s Ss) at 3; apply RN_le; lra).
    rewrite Rabs_pos_eq by lra. rewrite Rabs_pos_eq in Fs by lra. lra.
  - destruct (Rle_or_lt (a / 2) (- b)) as [Big|Small].
    + (* |b| ≥ a/2: a + b is a double *)
      apply Exact. replace (a + b) with (a - - b) by ring.
      apply (sterbenz radix2 (FLT_exp (-1074) 53)); [exact Ha | now apply binary64_opp |].
      rewrite Rabs_left in Fb by lra. rewrite Rabs_pos_eq in Fa by lra.
      assert (bpow radix2 1024 = 2 * bpow radix2 1023) by (change 1024%Z with (1 + 1023)%Z; rewrite bpow_plus; reflexivity). lra.
    + (* |b| < a/2: a/2 ≤ s ≤ a, so s − a is a double and a_virtual = a *)
      assert (H2 : binary64 (a / 2)) by now apply binary64_half_large.
      assert (S1 : a / 2 <= s) by (unfold s; rewrite <- (RN_binary64 _ H2); apply RN_le; lra).
      assert (S2 : s <= a) by (unfold s; rewrite <- (RN_binary64 a Ha) at 2; apply RN_le; lra).
      assert (D : binary64 (s - a)).
      { replace (s - a) with (- (a - s)) by ring. apply binary64_opp. apply (sterbenz radix2 (FLT_exp (-1074) 53)); [exact Ha | exact Ss | lra]. }
      rewrite (RN_binary64 _ D). replace (s - (s - a)) with a by ring. now rewrite (RN_binary64 a Ha).
Qed.

(** With a finite b_virtual = RN(s − a), the other four operations of TwoSum stay below 2^1024: each is a
    rounding error of s (at most u·|s| < 2^971), twice one, or a_virtual, which is a itself, or lies between
    0 and s, or is at most 1.5·2^1023. *)
Section TwoSumInner.
Variables a b : R.
Hypothesis Ha : binary64 a.
Hypothesis Hb : binary64 b.
Hypothesis Fa : Rabs a < bpow radix2 1024.
Hypothesis Fs : Rabs (RN (a + b)) < bpow radix2 1024.

Let s := RN (a + b).
Let bv := RN (s - a).
Let av := RN (s - bv).
Let br := RN (b - bv).
Let ar := RN (a - av).

Lemma ts_delta : Rabs (s - (a + b)) <= u * Rabs s.
Proof. unfold s. now apply RN_plus_err_round. Qed.

Lemma ts_eps1 : Rabs (bv - (s - a)) <= Rabs (s - (a + b)).
Proof. unfold bv. eapply Rle_trans; [apply (RN_nearest _ b Hb)|]. right. rewrite <- Rabs_Ropp. f_equal. ring. Qed.

Lemma ts_eps2 : Rabs (av - (s - bv)) <= Rabs (bv - (s - a)).
Proof. unfold av. eapply Rle_trans; [apply (RN_nearest _ a Ha)|]. right. f_equal. ring. Qed.

Lemma ts_small : Rabs (s - (a + b)) <= bpow radix2 971.
Proof.
  pose proof ts_delta. pose proof u_pos. rewrite u_val in *.
  assert (u_val' : / 9007199254740992 * bpow radix2 1024 = bpow radix2 971).
  { change 9007199254740992 with (bpow radix2 53). rewrite <- bpow_opp, <- bpow_plus. reflexivity. }
  assert (Rabs s <= bpow radix2 1024) by (unfold s; lra).
  assert (/ 9007199254740992 * Rabs s <= / 9007199254740992 * bpow radix2 1024) by (apply Rmult_le_compat_l; lra).
  lra.
Qed.

Lemma bpow_971_1024 : bpow radix2 971 + bpow radix2 971 + bpow radix2 971 < bpow radix2 1024.
Proof.
  assert (E : bpow radix2 1024 = bpow radix2 971 * bpow radix2 53) by (rewrite <- bpow_plus; reflexivity).
  pose proof (bpow_gt_0 radix2 971). change (bpow radix2 53) with 9007199254740992 in E. lra.
Qed.

Lemma small_RN : forall x, Rabs x <= bpow radix2 972 -> Rabs (RN x) < bpow radix2 1024.
Proof.
  intros x H. eapply Rle_lt_trans; [apply (RN_bpow_bound 972); [lia | exact H]|]. apply bpow_lt. lia.
Qed.

Lemma ts_br : Rabs br < bpow radix2 1024.
Proof.
  apply small_RN. pose proof ts_eps1. pose proof ts_small.
  replace (b - bv) with (- (bv - (s - a)) - (s - (a + b))) by ring.
  unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp, Rabs_Ropp.
  rewrite bpow_972. lra.
Qed.

Lemma ts_ar : Rabs ar < bpow radix2 1024.
Proof.
  apply small_RN. pose proof ts_eps1. pose proof ts_eps2. pose proof ts_small.
  replace (a - av) with (- (av - (s - bv)) + (bv - (s - a))) by ring.
  eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. rewrite bpow_972. lra.
Qed.

Lemma ts_lo : Rabs (RN (ar + br)) < bpow radix2 1024.
Proof.
  pose proof (two_sum_exact a b Ha Hb) as E. unfold two_sum in E. cbn [fst snd] in E.
  fold s bv av br ar in E. replace (RN (ar + br)) with (- (s - (a + b))) by lra.
  rewrite Rabs_Ropp. pose proof ts_small. pose proof (bpow_lt radix2 971 1024 ltac:(lia)). lra.
Qed.

Hypothesis Fb : Rabs b < bpow radix2 1024.

Lemma ts_av : Rabs av < bpow radix2 1024.
Proof.
  destruct (Rle_or_lt (Rabs a) (bpow radix2 1023)) as [L|L].
  - assert (B3 : binary64 (IZR 3 * bpow radix2 1022)) by (apply binary64_dyadic; lia).
    eapply Rle_lt_trans; [apply (RN_abs_le_double _ _ B3)|].
    + pose proof ts_eps1. pose proof ts_small.
      replace (s - bv) with (a - (bv - (s - a))) by ring.
      unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
      rewrite (Rabs_pos_eq (IZR 3 * bpow radix2 1022)) by (apply Rmult_le_pos; [lra | apply bpow_ge_0]).
      assert (bpow radix2 1023 = 2 * bpow radix2 1022) by (rewrite bpow_plus_1'; reflexivity).
      assert (bpow radix2 971 <= bpow radix2 1022) by (apply bpow_le; lia). lra.
    + rewrite (Rabs_pos_eq (IZR 3 * bpow radix2 1022)) by (apply Rmult_le_pos; [lra | apply bpow_ge_0]).
      assert (bpow radix2 1024 = 4 * bpow radix2 1022) by (rewrite bpow_plus_2'; reflexivity).
      pose proof (bpow_gt_0 radix2 1022). lra.
  - destruct (Rle_or_lt 0 a) as [P|N].
    + rewrite Rabs_pos_eq in L by lra. unfold av, bv, s. apply (ts_av_large a b); assumption.
    + rewrite Rabs_left in L by lra.
      pose proof (ts_av_large (- a) (- b) (binary64_opp a Ha) (binary64_opp b Hb) L
                    ltac:(now rewrite Rabs_Ropp) ltac:(now rewrite Rabs_Ropp)
                    ltac:(replace (- a + - b) with (- (a + b)) by ring; now rewrite RN_opp, Rabs_Ropp)) as H.
      replace (- a + - b) with (- (a + b)) in H by ring. rewrite RN_opp in H.
      replace (- RN (a + b) - - a) with (- (RN (a + b) - a)) in H by ring. rewrite RN_opp in H.
      replace (- RN (a + b) - - RN (RN (a + b) - a)) with (- (RN (a + b) - RN (RN (a + b) - a))) in H by ring.
      rewrite RN_opp, Rabs_Ropp in H. exact H.
Qed.

End TwoSumInner.

(** ** TwoSum on the bits: the low part is NaN or finite *)

Lemma fsub_finite_not_nan : forall x y, fin x = true -> fin y = true -> is_nan (fsub x y) = false.
Proof.
  intros x y Fx Fy. pose proof (Bminus_correct 53 1024 _ _ mode_NE x y Fx Fy) as C.
  unfold fsub. destruct Rlt_bool.
  - destruct C as [_ [F _]]. revert F. destruct (BinarySingleNaN.Bminus mode_NE x y); try reflexivity.
    intros F. discriminate F.
  - revert C. destruct (BinarySingleNaN.Bminus mode_NE x y); try reflexivity.
    intros [C _]. unfold binary_overflow in C. destruct overflow_to_inf; discriminate C.
Qed.

Lemma two_sum_tail_inf : forall s a b sg, fin s = true -> fin a = true -> fin b = true ->
  is_nan (fadd (fsub a (fsub s (B754_infinity sg))) (fsub b (B754_infinity sg))) = true.
Proof.
  intros [ss|ss| |ss ms es Hs] [sa|sa| |sa ma ea Ha] [sb|sb| |sb mb eb Hb] sg Fs Fa Fb;
    try discriminate; destruct sg; reflexivity.
Qed.

Theorem two_sum_b_nan_or_finite : forall a b, fin a = true -> fin b = true -> fin (fadd a b) = true ->
  is_nan (snd (two_sum_b a b)) = true \/ fin (snd (two_sum_b a b)) = true.
Proof.
  intros a b Fa Fb Fs. unfold two_sum_b. cbv zeta. cbn [snd].
  pose proof (fadd_val a b Fs) as Vs.
  set (s := fadd a b) in *. clearbody s.
  destruct (fin (fsub s a)) eqn:Fbv.
  - right.
    pose proof (fsub_val s a Fbv) as Vbv. set (bv := fsub s a) in *. clearbody bv.
    pose proof (B2R_lt_overflow a) as La. pose proof (B2R_lt_overflow b) as Lb.
    pose proof (B2R_lt_overflow s) as Ls. rewrite Vs in Ls.
    pose proof (binary64_B2R a) as Ba. pose proof (binary64_B2R b) as Bb.
    destruct (fsub_fwd s bv Fs Fbv) as [Fav Vav].
    { rewrite Vbv, Vs. apply ts_av; assumption. }
    destruct (fsub_fwd b bv Fb Fbv) as [Fbr Vbr].
    { rewrite Vbv, Vs. apply ts_br; assumption. }
    destruct (fsub_fwd a (fsub s bv) Fa Fav) as [Far Var].
    { rewrite Vav, Vbv, Vs. apply ts_ar; assumption. }
    destruct (fadd_fwd _ _ Far Fbr) as [Flo _]; [|exact Flo].
    rewrite Var, Vbr, Vav, Vbv, Vs. apply ts_lo; assumption.
  - left. destruct (fsub s a) as [sg|sg| |sg m e H] eqn:E; try discriminate.
    + apply two_sum_tail_inf; assumption.
    + pose proof (fsub_finite_not_nan s a Fs Fa) as N. rewrite E in N. discriminate N.
Qed.

(** ** NaN propagates; a comparison with NaN is false *)

Lemma fadd_nan_l : forall x y, is_nan x = true -> is_nan (fadd x y) = true.
Proof. intros [| | |] y H; try discriminate. destruct y; reflexivity. Qed.
Lemma fadd_nan_r : forall x y, is_nan y = true -> is_nan (fadd x y) = true.
Proof. intros x [| | |] H; try discriminate. destruct x; reflexivity. Qed.
Lemma fsub_nan_l : forall x y, is_nan x = true -> is_nan (fsub x y) = true.
Proof. intros [| | |] y H; try discriminate. destruct y; reflexivity. Qed.
Lemma fsub_nan_r : forall x y, is_nan y = true -> is_nan (fsub x y) = true.
Proof. intros x [| | |] H; try discriminate. destruct x; reflexivity. Qed.
Lemma fmul_nan_l : forall x y, is_nan x = true -> is_nan (fmul x y) = true.
Proof. intros [| | |] y H; try discriminate. destruct y; reflexivity. Qed.
Lemma ffma_nan_1 : forall x y z, is_nan x = true -> is_nan (ffma x y z) = true.
Proof. intros [| | |] y z H; try discriminate. destruct y; reflexivity. Qed.
Lemma ffma_nan_2 : forall x y z, is_nan y = true -> is_nan (ffma x y z) = true.
Proof. intros x [| | |] z H; try discriminate. destruct x; reflexivity. Qed.
Lemma ffma_nan_3 : forall x y z, is_nan z = true -> is_nan (ffma x y z) = true.
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy] [| | |] H; try discriminate; reflexivity.
Qed.

Lemma flt_nan_r : forall x y, is_nan y = true -> flt x y = false.
Proof. intros x [| | |] H; try discriminate. destruct x; reflexivity. Qed.
Lemma flt_nan_l : forall x y, is_nan x = true -> flt x y = false.
Proof. intros [| | |] y H; try discriminate. destruct y; reflexivity. Qed.

(** A certain enclosure sign: hi ⊕ lo is not NaN. *)
Lemma enclosure_sign_not_nan : forall e, enclosure_sign_lanes_b e <> uncertain_lane ->
  is_nan (fadd (hib e) (lob e)) = false.
Proof.
  intros e U. unfold enclosure_sign_lanes_b in U. apply sign_lanes_certain in U.
  destruct (is_nan (fadd (hib e) (lob e))) eqn:N; [|reflexivity].
  rewrite flt_nan_r, flt_nan_l in U by exact N. destruct U; discriminate.
Qed.

(** ** "NaN, or finite and below 2^k" *)

Definition nf (k : Z) (x : float) : Prop := is_nan x = true \/ fbnd k x.

Lemma nf_mono : forall k j x, (k <= j)%Z -> nf k x -> nf j x.
Proof. intros k j x L [N|B]; [now left | right; now apply (fbnd_mono k)]. Qed.

(** A sum or a difference: NaN in, NaN out; finite arguments below 2^k give a result below 2^(k+1). *)
Lemma nf_binop : forall (op : float -> float -> float) k x y,
  (forall a b, is_nan a = true -> is_nan (op a b) = true) -> (forall a b, is_nan b = true -> is_nan (op a b) = true) ->
  (fbnd k x -> fbnd k y -> fbnd (k + 1) (op x y)) -> nf k x -> nf k y -> nf (k + 1) (op x y).
Proof.
  intros op k x y NL NR B [Nx|Bx] [Ny|By]; [left; now apply NL .. | left; now apply NR | right; now apply B].
Qed.

Lemma nf_add : forall k x y, nf k x -> nf k y -> (0 <= k)%Z -> (k + 1 <= 1023)%Z -> nf (k + 1) (fadd x y).
Proof.
  intros k x y X Y K L. apply nf_binop; [exact fadd_nan_l | exact fadd_nan_r | | exact X | exact Y].
  intros Bx By. replace (k + 1)%Z with (Z.max k k + 1)%Z by lia. apply fbnd_add; auto; lia.
Qed.

Lemma nf_sub : forall k x y, nf k x -> nf k y -> (0 <= k)%Z -> (k + 1 <= 1023)%Z -> nf (k + 1) (fsub x y).
Proof.
  intros k x y X Y K L. apply nf_binop; [exact fsub_nan_l | exact fsub_nan_r | | exact X | exact Y].
  intros Bx By. replace (k + 1)%Z with (Z.max k k + 1)%Z by lia. apply fbnd_sub; auto; lia.
Qed.

Lemma nf_not_nan : forall k x, nf k x -> is_nan x = false -> fin x = true.
Proof. intros k x [N|[F _]] M; [congruence | exact F]. Qed.

Lemma fadd_not_nan : forall x y, is_nan (fadd x y) = false -> is_nan x = false /\ is_nan y = false.
Proof.
  intros x y H. destruct (is_nan x) eqn:Nx; [rewrite fadd_nan_l in H by exact Nx; discriminate|].
  destruct (is_nan y) eqn:Ny; [rewrite fadd_nan_r in H by exact Ny; discriminate|]. now split.
Qed.

(** ** The numbers: every rounding error of a finite double is below 2^971 *)

Lemma u_bpow_1024 : u * bpow radix2 1024 = bpow radix2 971.
Proof.
  rewrite u_val. change 1024%Z with (53 + 971)%Z. rewrite bpow_plus.
  change (bpow radix2 53) with 9007199254740992. field.
Qed.

Lemma eta_small : eta <= bpow radix2 971.
Proof. unfold eta. apply bpow_le. lia. Qed.

Lemma u_small : u <= / 2.
Proof. rewrite u_val. lra. Qed.

(** |x·y| for x ⊗ y finite: u·|x·y| ≤ 2^972. *)
Lemma product_small : forall x y, fin (fmul x y) = true -> u * Rabs (B2R x * B2R y) <= bpow radix2 972.
Proof.
  intros x y F. destruct (fmul_inv x y F) as [_ [_ V]].
  pose proof (B2R_lt_overflow (fmul x y)) as L. rewrite V in L.
  pose proof (RN_err_round (B2R x * B2R y)) as E.
  assert (A : Rabs (B2R x * B2R y) <= bpow radix2 1024 + u * bpow radix2 1024 + eta).
  { pose proof u_pos. assert (u * Rabs (RN (B2R x * B2R y)) <= u * bpow radix2 1024) by (apply Rmult_le_compat_l; lra).
    pose proof (Rabs_close' _ _ _ E). lra. }
  rewrite u_bpow_1024 in A. rewrite bpow_972.
  pose proof u_pos. pose proof eta_small. pose proof eta_pos. pose proof u_small. pose proof (bpow_gt_0 radix2 971).
  assert (u * Rabs (B2R x * B2R y) <= u * (bpow radix2 1024 + bpow radix2 971 + eta)) by (apply Rmult_le_compat_l; lra).
  rewrite Rmult_plus_distr_l, Rmult_plus_distr_l, u_bpow_1024 in H4.
  assert (u * bpow radix2 971 <= / 2 * bpow radix2 971) by (apply Rmult_le_compat_r; lra).
  assert (u * eta <= / 2 * bpow radix2 971) by (apply Rmult_le_compat; lra).
  lra.
Qed.

Lemma fbnd_of_RN : forall k x, (-1074 <= k <= 1023)%Z -> Rabs x <= bpow radix2 k ->
  Rabs (RN x) < bpow radix2 1024 /\ Rabs (RN x) <= bpow radix2 k.
Proof.
  intros k x K H. pose proof (RN_bpow_bound k x ltac:(lia) H) as R. split; [|exact R].
  eapply Rle_lt_trans; [exact R | apply bpow_lt; lia].
Qed.

(** The TwoProduct residual fma(x, y, −(x ⊗ y)) of a finite product: below 2^972. *)
Lemma fma_residual_fbnd : forall x y, fin (fmul x y) = true -> fbnd 972 (ffma x y (fneg (fmul x y))).
Proof.
  intros x y F. destruct (fmul_inv x y F) as [Fx [Fy V]].
  assert (B : Rabs (B2R x * B2R y + B2R (fneg (fmul x y))) <= bpow radix2 972).
  { rewrite fneg_val, V. pose proof (RN_err_round (B2R x * B2R y)) as E.
    pose proof (B2R_lt_overflow (fmul x y)) as L. rewrite V in L.
    replace (B2R x * B2R y + - RN (B2R x * B2R y)) with (- (RN (B2R x * B2R y) - B2R x * B2R y)) by ring.
    rewrite Rabs_Ropp. pose proof u_pos. pose proof eta_small. rewrite bpow_972.
    assert (u * Rabs (RN (B2R x * B2R y)) <= u * bpow radix2 1024) by (apply Rmult_le_compat_l; lra).
    rewrite u_bpow_1024 in H1. lra. }
  destruct (fbnd_of_RN 972 _ ltac:(lia) B) as [L R].
  destruct (ffma_fwd x y (fneg (fmul x y)) Fx Fy ltac:(now rewrite fneg_fin) L) as [Ff Vf].
  split; [exact Ff | now rewrite Vf].
Qed.

(** A TwoSum low part of finite operands with a finite sum: NaN, or finite with |lo| ≤ u·|a ⊕ b|. *)
Lemma two_sum_lo_small : forall a b, fin a = true -> fin b = true -> fin (fadd a b) = true ->
  is_nan (snd (two_sum_b a b)) = true \/
  (fin (snd (two_sum_b a b)) = true /\ Rabs (B2R (snd (two_sum_b a b))) <= u * Rabs (B2R (fadd a b))).
Proof.
  intros a b Fa Fb Fs. destruct (two_sum_b_nan_or_finite a b Fa Fb Fs) as [N|F]; [now left|right].
  split; [exact F|]. destruct (two_sum_b_inv a b F) as [_ [_ [_ [_ E]]]].
  rewrite E. destruct (two_sum_lo_bound (B2R a) (B2R b) (binary64_B2R a) (binary64_B2R b)) as [_ L].
  rewrite two_sum_hi in L. now rewrite fadd_val by exact Fs.
Qed.

Lemma small_nf : forall a b, fin a = true -> fin b = true -> fin (fadd a b) = true -> nf 971 (snd (two_sum_b a b)).
Proof.
  intros a b Fa Fb Fs. destruct (two_sum_lo_small a b Fa Fb Fs) as [N|[F L]]; [now left|right].
  split; [exact F|]. rewrite <- u_bpow_1024. eapply Rle_trans; [exact L|].
  apply Rmult_le_compat_l; [left; apply u_pos | left; apply B2R_lt_overflow].
Qed.

(** A low part times a finite value, as fma(x, yl, xl ⊗ y) or fma(xl, y, z) uses it. *)
Definition small_low (x xl : float) : Prop :=
  is_nan xl = true \/ (fin xl = true /\ Rabs (B2R xl) <= u * Rabs (B2R x)).

Lemma low_product_bound : forall x xl y, fin x = true -> fin y = true -> fin xl = true ->
  Rabs (B2R xl) <= u * Rabs (B2R x) -> Rabs (B2R x * B2R y) * u <= bpow radix2 972 ->
  Rabs (B2R xl * B2R y) <= bpow radix2 972.
Proof.
  intros x xl y Fx Fy Fl L P. rewrite Rabs_mult. rewrite Rabs_mult in P.
  pose proof (Rabs_pos (B2R y)). pose proof (Rabs_pos (B2R x)). pose proof (Rabs_pos (B2R xl)). pose proof u_pos.
  assert (Rabs (B2R xl) * Rabs (B2R y) <= u * Rabs (B2R x) * Rabs (B2R y)) by (apply Rmult_le_compat_r; lra).
  lra.
Qed.

(** The cross term of [compare_quotients_compensated]: c = fma(x, yl, xl ⊗ y), with x ⊗ y finite. *)
Lemma cross_term_nf : forall x xl y yl, fin (fmul x y) = true -> small_low x xl -> small_low y yl ->
  nf 973 (ffma x yl (fmul xl y)).
Proof.
  intros x xl y yl F [Nx|[Fxl Lx]] [Ny|[Fyl Ly]].
  - left. apply ffma_nan_3. now apply fmul_nan_l.
  - left. apply ffma_nan_3. now apply fmul_nan_l.
  - left. now apply ffma_nan_2.
  - right. destruct (fmul_inv x y F) as [Fx [Fy _]].
    pose proof (product_small x y F) as P. rewrite Rmult_comm in P.
    pose proof (low_product_bound x xl y Fx Fy Fxl Lx P) as B1.
    assert (B2 : Rabs (B2R x * B2R yl) <= bpow radix2 972).
    { rewrite Rmult_comm. apply (low_product_bound y yl x Fy Fx Fyl Ly). replace (B2R y * B2R x) with (B2R x * B2R y) by ring. exact P. }
    destruct (fbnd_of_RN 972 _ ltac:(lia) B1) as [L1 R1].
    destruct (fmul_fwd xl y Fxl Fy L1) as [Fm Vm].
    assert (B3 : Rabs (B2R x * B2R yl + B2R (fmul xl y)) <= bpow radix2 973).
    { rewrite Vm. eapply Rle_trans; [apply Rabs_triang|]. change 973%Z with (1 + 972)%Z. rewrite bpow_plus.
      change (bpow radix2 1) with 2. lra. }
    destruct (fbnd_of_RN 973 _ ltac:(lia) B3) as [L3 R3].
    destruct (ffma_fwd _ _ _ Fx Fyl Fm L3) as [Ff Vf]. split; [exact Ff | now rewrite Vf].
Qed.

(** num's g_i = fma(α, n, l) with α the TwoDiff low part of a = p ⊖ o and l the residual of a ⊗ n. *)
Lemma low_term_nf : forall x xl y, fin (fmul x y) = true -> small_low x xl ->
  nf 973 (ffma xl y (ffma x y (fneg (fmul x y)))).
Proof.
  intros x xl y F [Nx|[Fxl Lx]]; [left; now apply ffma_nan_1 | right].
  destruct (fmul_inv x y F) as [Fx [Fy _]].
  pose proof (product_small x y F) as P. rewrite Rmult_comm in P.
  pose proof (low_product_bound x xl y Fx Fy Fxl Lx P) as B1.
  destruct (fma_residual_fbnd x y F) as [Fr Br].
  assert (B3 : Rabs (B2R xl * B2R y + B2R (ffma x y (fneg (fmul x y)))) <= bpow radix2 973).
  { eapply Rle_trans; [apply Rabs_triang|]. change 973%Z with (1 + 972)%Z. rewrite bpow_plus.
    change (bpow radix2 1) with 2. lra. }
  destruct (fbnd_of_RN 973 _ ltac:(lia) B3) as [L3 R3].
  destruct (ffma_fwd _ _ _ Fxl Fy Fr L3) as [Ff Vf]. split; [exact Ff | now rewrite Vf].
Qed.

(** ** The first level of stage 2 (dot3_compensated.hpp) *)

Lemma two_sum_b_fst_eq : forall a b, fst (two_sum_b a b) = fadd a b.
Proof. reflexivity. Qed.

(** The sums shared by both forms: with a finite stage-1 magnitude and low parts g_i that are NaN or below
    2^973, hi is stage 1's value (finite) and lo is NaN or finite; a hi ⊕ lo that is not NaN leaves finite. *)
Lemma from_low_parts_finite : forall a0 a1 a2 b0 b1 b2 g0 g1 g2,
  fin (magnitudeb (dot3_rounded_b a0 a1 a2 b0 b1 b2)) = true -> nf 973 g0 -> nf 973 g1 -> nf 973 g2 ->
  is_nan (fadd (hib (compensated_from_low_parts_b g0 g1 g2 (dot3_rounded_b a0 a1 a2 b0 b1 b2)))
               (lob (compensated_from_low_parts_b g0 g1 g2 (dot3_rounded_b a0 a1 a2 b0 b1 b2)))) = false ->
  fin (hib (compensated_from_low_parts_b g0 g1 g2 (dot3_rounded_b a0 a1 a2 b0 b1 b2))) = true /\
  fin (lob (compensated_from_low_parts_b g0 g1 g2 (dot3_rounded_b a0 a1 a2 b0 b1 b2))) = true.
Proof.
  intros a0 a1 a2 b0 b1 b2 g0 g1 g2 Fm G0 G1 G2 N.
  destruct (dot3_rounded_twin a0 a1 a2 b0 b1 b2 Fm) as [_ [_ [_ [_ [_ [_ [Fq0 [Fq1 [Fq2 [Fv _]]]]]]]]]].
  unfold compensated_from_low_parts_b in *. cbv zeta in *. cbn [hib lob] in *.
  rewrite !two_sum_b_fst_eq in *.
  unfold dot3_rounded_b in *. cbv zeta in *. cbn [qb0 qb1 qb2 valueb magnitudeb] in *.
  set (q0 := fmul a0 b0) in *. set (q1 := fmul a1 b1) in *. set (q2 := fmul a2 b2) in *.
  destruct (fadd_fin _ _ Fv) as [F01 _].
  apply fadd_not_nan in N. destruct N as [_ N]. split; [exact Fv|].
  apply (nf_not_nan 976); [|exact N].
  replace 976%Z with (975 + 1)%Z by reflexivity. apply nf_add; try lia.
  - replace 975%Z with (974 + 1)%Z by reflexivity. apply nf_add; try lia; [|now apply (nf_mono 973)].
    replace 974%Z with (973 + 1)%Z by reflexivity. apply nf_add; try lia; assumption.
  - apply (nf_mono 972); [lia|]. replace 972%Z with (971 + 1)%Z by reflexivity. apply nf_add; try lia.
    + now apply small_nf.
    + now apply small_nf.
Qed.

Lemma radius_magnitude : forall g0 g1 g2 r, fin (radiusb (compensated_from_low_parts_b g0 g1 g2 r)) = true ->
  fin (magnitudeb r) = true.
Proof.
  intros g0 g1 g2 r F. unfold compensated_from_low_parts_b in F. cbv zeta in F. cbn [radiusb] in F.
  destruct (fadd_fin _ _ F) as [F1 _]. now destruct (fmul_fin _ _ F1).
Qed.

(** den = d·n: a certain sign of the first level implies finite hi and lo, for every bit pattern. *)
Theorem den_compensated_certain_finite : forall d0 d1 d2 n0 n1 n2 : float,
  let e := den_compensated_b d0 d1 d2 n0 n1 n2 in
  enclosure_sign_lanes_b e <> uncertain_lane -> fin (hib e) = true /\ fin (lob e) = true.
Proof.
  intros d0 d1 d2 n0 n1 n2 e U.
  pose proof (enclosure_sign_radius_finite e (den_radius_nonneg d0 d1 d2 n0 n1 n2) U) as Fr.
  pose proof (enclosure_sign_not_nan e U) as N.
  unfold e, den_compensated_b, compensated_dot3_exact_b in *.
  pose proof (radius_magnitude _ _ _ _ Fr) as Fm.
  destruct (dot3_rounded_twin d0 d1 d2 n0 n1 n2 Fm) as [_ [_ [_ [_ [_ [_ [Fq0 [Fq1 [Fq2 _]]]]]]]]].
  apply from_low_parts_finite; try assumption; right; apply (fbnd_mono 972); try lia; apply fma_residual_fbnd; assumption.
Qed.

Lemma two_diff_small_low : forall p o n, fin (fmul (fst (two_diff_b p o)) n) = true ->
  small_low (fst (two_diff_b p o)) (snd (two_diff_b p o)).
Proof.
  intros p o n F. destruct (fmul_fin _ _ F) as [Fa _].
  unfold two_diff_b in *. rewrite two_sum_b_fst_eq in Fa |- *. destruct (fadd_fin _ _ Fa) as [Fp Fo].
  exact (two_sum_lo_small p (fneg o) Fp Fo Fa).
Qed.

(** num = (p − o)·n with the TwoDiff low parts: the same, for every bit pattern (a TwoDiff whose low part
    is NaN makes lo NaN, hence uncertain). *)
Theorem num_compensated_certain_finite : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let e := num_compensated_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  enclosure_sign_lanes_b e <> uncertain_lane -> fin (hib e) = true /\ fin (lob e) = true.
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 e U.
  pose proof (enclosure_sign_radius_finite e (num_radius_nonneg p0 p1 p2 o0 o1 o2 n0 n1 n2) U) as Fr.
  pose proof (enclosure_sign_not_nan e U) as N.
  unfold e, num_compensated_b, compensated_dot3_b in *. cbv zeta in *.
  pose proof (radius_magnitude _ _ _ _ Fr) as Fm.
  destruct (dot3_rounded_twin _ _ _ n0 n1 n2 Fm) as [_ [_ [_ [_ [_ [_ [Fq0 [Fq1 [Fq2 _]]]]]]]]].
  assert (F0 : fin (fmul (fst (two_diff_b p0 o0)) n0) = true) by exact Fq0.
  assert (F1 : fin (fmul (fst (two_diff_b p1 o1)) n1) = true) by exact Fq1.
  assert (F2 : fin (fmul (fst (two_diff_b p2 o2)) n2) = true) by exact Fq2.
  apply from_low_parts_finite; try assumption.
  - exact (low_term_nf _ _ _ F0 (two_diff_small_low _ _ _ F0)).
  - exact (low_term_nf _ _ _ F1 (two_diff_small_low _ _ _ F1)).
  - exact (low_term_nf _ _ _ F2 (two_diff_small_low _ _ _ F2)).
Qed.

(** End to end, for every bit pattern, with no hypothesis: PlaneTwins.v's [den_compensated_twin_sound] and
    [num_compensated_twin_sound] without "hi and lo finite". *)
Theorem den_compensated_twin_sound_total : forall d0 d1 d2 n0 n1 n2 : float,
  let e := den_compensated_b d0 d1 d2 n0 n1 n2 in
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) /\
  (enclosure_sign_lanes_b e <> uncertain_lane ->
   fin (radiusb e) = true /\ fin (hib e) = true /\ fin (lob e) = true /\
   fin d0 = true /\ fin d1 = true /\ fin d2 = true /\ fin n0 = true /\ fin n1 = true /\ fin n2 = true).
Proof.
  intros d0 d1 d2 n0 n1 n2 e.
  destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U].
  - split; [rewrite U; exact I | intros C; contradiction].
  - destruct (den_compensated_certain_finite d0 d1 d2 n0 n1 n2 U) as [Fh Fl].
    destruct (den_compensated_twin_sound d0 d1 d2 n0 n1 n2 Fh Fl) as [S R].
    split; [exact S|]. intros _. pose proof (R U) as Fr.
    destruct (compensated_dot3_exact_twin d0 d1 d2 n0 n1 n2 Fr Fh Fl) as [? [? [? [? [? [? _]]]]]].
    repeat split; assumption.
Qed.

Theorem num_compensated_twin_sound_total : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let e := num_compensated_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  certifies (sign_from_Z (enclosure_sign_lanes_b e))
    ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2) /\
  (enclosure_sign_lanes_b e <> uncertain_lane ->
   fin (radiusb e) = true /\ fin (hib e) = true /\ fin (lob e) = true /\
   fin p0 = true /\ fin p1 = true /\ fin p2 = true /\ fin o0 = true /\ fin o1 = true /\ fin o2 = true /\
   fin n0 = true /\ fin n1 = true /\ fin n2 = true).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 e.
  destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U].
  - split; [rewrite U; exact I | intros C; contradiction].
  - destruct (num_compensated_certain_finite p0 p1 p2 o0 o1 o2 n0 n1 n2 U) as [Fh Fl].
    destruct (num_compensated_twin_sound p0 p1 p2 o0 o1 o2 n0 n1 n2 Fh Fl) as [S R].
    split; [exact S|]. intros _. pose proof (R U) as Fr.
    destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [A0 [A1 [A2 [? [? [? _]]]]]]]]].
    destruct (two_diff_b_parts _ _ A0) as [? [? _]]. destruct (two_diff_b_parts _ _ A1) as [? [? _]].
    destruct (two_diff_b_parts _ _ A2) as [? [? _]].
    repeat split; assumption.
Qed.

(** A finite stage-2 enclosure of den or num encloses the exact value (PlaneTwins.v's theorems, restated). *)
(** ** compare_quotients_compensated (compare_quotients.hpp) *)

Lemma compare_radius_nonneg : forall n1 d1 n2 d2,
  nonneg (radiusb n1) -> nonneg (radiusb d1) -> nonneg (radiusb n2) -> nonneg (radiusb d2) ->
  nonneg (radiusb (compare_quotients_compensated_b n1 d1 n2 d2)).
Proof.
  intros n1 d1 n2 d2 N1 M1 N2 M2. unfold compare_quotients_compensated_b. cbv zeta. cbn [radiusb].
  apply fadd_nonneg; [apply fadd_nonneg; apply fmul_nonneg|]; try const_nonneg.
  - apply fadd_nonneg; apply fabs_nonneg.
  - now apply propagated_nonneg_b.
Qed.

(** Any four input enclosures with radii non-negative or NaN (every producer's are): a certain sign of
    the comparison's enclosure implies finite hi and lo (|S| ≤ M = |P| ⊕ |Q|; lo is a sum of TwoProduct
    residuals, cross terms of low parts and a TwoSum low part, each NaN or below 2^973). *)
Theorem compare_compensated_certain_finite : forall n1 d1 n2 d2,
  nonneg (radiusb n1) -> nonneg (radiusb d1) -> nonneg (radiusb n2) -> nonneg (radiusb d2) ->
  let e := compare_quotients_compensated_b n1 d1 n2 d2 in
  enclosure_sign_lanes_b e <> uncertain_lane -> fin (hib e) = true /\ fin (lob e) = true.
Proof.
  intros n1 d1 n2 d2 N1 M1 N2 M2 e U.
  pose proof (enclosure_sign_radius_finite e (compare_radius_nonneg n1 d1 n2 d2 N1 M1 N2 M2) U) as Fr.
  pose proof (enclosure_sign_not_nan e U) as N.
  unfold e, compare_quotients_compensated_b in *. cbv zeta in *. cbn [hib lob radiusb] in *.
  unfold two_prod_b in *. cbv zeta in *. cbn [fst snd] in *. rewrite !two_sum_b_fst_eq in *.
  set (a1 := fadd (hib n1) (lob n1)) in *. set (b1 := fadd (hib d1) (lob d1)) in *.
  set (a2 := fadd (hib n2) (lob n2)) in *. set (b2 := fadd (hib d2) (lob d2)) in *.
  set (P := fmul a1 b2) in *. set (Q := fmul a2 b1) in *.
  destruct (fadd_fin _ _ Fr) as [Fr1 _]. destruct (fadd_fin _ _ Fr1) as [Fr2 _].
  destruct (fmul_fin _ _ Fr2) as [_ FM].
  destruct (fadd_fin _ _ FM) as [FP FQ]. rewrite fabs_fin in FP, FQ.
  assert (FPQ : fin a1 = true /\ fin b2 = true) by (now apply fmul_fin). destruct FPQ as [Fa1 Fb2].
  assert (FQQ : fin a2 = true /\ fin b1 = true) by (now apply fmul_fin). destruct FQQ as [Fa2 Fb1].
  destruct (fadd_fin _ _ Fa1) as [Fhn1 Fln1]. destruct (fadd_fin _ _ Fb1) as [Fhd1 Fld1].
  destruct (fadd_fin _ _ Fa2) as [Fhn2 Fln2]. destruct (fadd_fin _ _ Fb2) as [Fhd2 Fld2].
  (* S = P ⊖ Q is dominated by M = |P| ⊕ |Q| *)
  assert (FS : fin (fadd P (fneg Q)) = true).
  { destruct (fadd_dominated P (fneg Q) (fadd (fabs P) (fabs Q)) FP ltac:(now rewrite fneg_fin)) as [F _]; [|exact F].
    rewrite (fadd_val _ _ FM), !fabs_val, fneg_val, <- !RN_abs. apply RN_le.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  apply fadd_not_nan in N. destruct N as [_ N]. split; [exact FS|].
  apply (nf_not_nan 976); [|exact N].
  replace 976%Z with (975 + 1)%Z by reflexivity. apply nf_add; try lia.
  - replace 975%Z with (974 + 1)%Z by reflexivity. apply nf_add; try lia.
    + apply (nf_mono 973); [lia|]. replace 973%Z with (972 + 1)%Z by reflexivity. apply nf_sub; try lia;
        right; now apply fma_residual_fbnd.
    + replace 974%Z with (973 + 1)%Z by reflexivity. apply nf_sub; try lia; apply cross_term_nf; try assumption;
        apply two_sum_lo_small; assumption.
  - apply (nf_mono 971); [lia|]. apply small_nf; try assumption. now rewrite fneg_fin.
Qed.

(** End to end, without "hi and lo finite": for any input enclosures with radii non-negative or NaN, a
    certain sign of [compare_quotients_compensated] is the sign of Δ = N_1·D_2 − N_2·D_1 for any reals
    the (then finite) inputs enclose. *)
Theorem compare_compensated_twin_sound_total : forall n1 d1 n2 d2 (N1 D1 N2 D2 : R),
  nonneg (radiusb n1) -> nonneg (radiusb d1) -> nonneg (radiusb n2) -> nonneg (radiusb d2) ->
  let e := compare_quotients_compensated_b n1 d1 n2 d2 in
  (enclosure_sign_lanes_b e <> uncertain_lane ->
   encloses (enc_R n1) N1 /\ encloses (enc_R d1) D1 /\ encloses (enc_R n2) N2 /\ encloses (enc_R d2) D2) ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) (N1 * D2 - N2 * D1).
Proof.
  intros n1 d1 n2 d2 N1 D1 N2 D2 R1 S1 R2 S2 e Enc.
  destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U]; [rewrite U; exact I|].
  destruct (compare_compensated_certain_finite n1 d1 n2 d2 R1 S1 R2 S2 U) as [Fh Fl].
  destruct (Enc U) as [E1 [F1 [E2 F2]]].
  apply stage2_sign_twin; [apply compare_radius_nonneg; assumption | exact Fh | exact Fl | ].
  intros Fr.
  destruct (compare_quotients_compensated_twin n1 d1 n2 d2 Fr Fh Fl)
    as [? [? [? [? [? [? [? [? [? [? [? [? [_ [_ Eq]]]]]]]]]]]]]].
  fold e in Eq. rewrite Eq.
  apply compare_quotients_compensated_enclosure; try assumption; apply binary64_B2R.
Qed.

(** For nearest_hit: the stage-2 enclosures of a ray and two planes, as [compare_hit_distances] passes them
    (num_a, den_a, num_b, den_b from [RayPlaneCascade]'s [num_compensated], [den_compensated]): a certain
    sign is the sign of Δ = num_a·den_b − num_b·den_a of the exact values, for every bit pattern of the ray
    and both planes. *)
Theorem hit_order_compensated_twin_sound_total : forall o0 o1 o2 d0 d1 d2 pa0 pa1 pa2 na0 na1 na2
    pb0 pb1 pb2 nb0 nb1 nb2 : float,
  let num_a := num_compensated_b pa0 pa1 pa2 o0 o1 o2 na0 na1 na2 in
  let den_a := den_compensated_b d0 d1 d2 na0 na1 na2 in
  let num_b := num_compensated_b pb0 pb1 pb2 o0 o1 o2 nb0 nb1 nb2 in
  let den_b := den_compensated_b d0 d1 d2 nb0 nb1 nb2 in
  let Na := (B2R pa0 - B2R o0) * B2R na0 + (B2R pa1 - B2R o1) * B2R na1 + (B2R pa2 - B2R o2) * B2R na2 in
  let Da := B2R d0 * B2R na0 + B2R d1 * B2R na1 + B2R d2 * B2R na2 in
  let Nb := (B2R pb0 - B2R o0) * B2R nb0 + (B2R pb1 - B2R o1) * B2R nb1 + (B2R pb2 - B2R o2) * B2R nb2 in
  let Db := B2R d0 * B2R nb0 + B2R d1 * B2R nb1 + B2R d2 * B2R nb2 in
  certifies (sign_from_Z (enclosure_sign_lanes_b (compare_quotients_compensated_b num_a den_a num_b den_b)))
    (Na * Db - Nb * Da).
Proof.
  intros.
  assert (R1 : nonneg (radiusb num_a)) by exact (num_radius_nonneg pa0 pa1 pa2 o0 o1 o2 na0 na1 na2).
  assert (S1 : nonneg (radiusb den_a)) by exact (den_radius_nonneg d0 d1 d2 na0 na1 na2).
  assert (R2 : nonneg (radiusb num_b)) by exact (num_radius_nonneg pb0 pb1 pb2 o0 o1 o2 nb0 nb1 nb2).
  assert (S2 : nonneg (radiusb den_b)) by exact (den_radius_nonneg d0 d1 d2 nb0 nb1 nb2).
  apply (compare_compensated_twin_sound_total num_a den_a num_b den_b Na Da Nb Db R1 S1 R2 S2).
  intros U.
  destruct (compare_compensated_certain_finite num_a den_a num_b den_b R1 S1 R2 S2 U) as [Fh Fl].
  pose proof (enclosure_sign_radius_finite _ (compare_radius_nonneg num_a den_a num_b den_b R1 S1 R2 S2) U) as Fr.
  destruct (compare_quotients_compensated_twin num_a den_a num_b den_b Fr Fh Fl)
    as [Hn1 [Ln1 [Rn1 [Hd1 [Ld1 [Rd1 [Hn2 [Ln2 [Rn2 [Hd2 [Ld2 [Rd2 _]]]]]]]]]]]].
  split; [|split; [|split]].
  - exact (num_compensated_encloses_b pa0 pa1 pa2 o0 o1 o2 na0 na1 na2 Hn1 Ln1 Rn1).
  - exact (den_compensated_encloses_b d0 d1 d2 na0 na1 na2 Hd1 Ld1 Rd1).
  - exact (num_compensated_encloses_b pb0 pb1 pb2 o0 o1 o2 nb0 nb1 nb2 Hn2 Ln2 Rn2).
  - exact (den_compensated_encloses_b d0 d1 d2 nb0 nb1 nb2 Hd2 Ld2 Rd2).
Qed.
