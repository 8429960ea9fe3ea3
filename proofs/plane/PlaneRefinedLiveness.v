(** * Liveness of the second level of stage 2: [compensated_dot3_refined] does certify, on a stated class.

    PlaneRefinedTwins.v and PlaneRefinedFinite.v prove that what the second level certifies is true; a level that
    never certified would satisfy them.  This file proves the converse on a class of inputs, on the twin
    ([compensated_dot3_refined_b], PlaneTwins.v, checked bit for bit against kernel/src/certified/
    dot3_compensated.hpp's [compensated_dot3_refined] by the runner's routine [refined]; the cascade's calls
    [den_refined_b], [num_refined_b] as ray_plane_cascade.cpp makes them through [query.den_refined()],
    [query.num_refined()]), followed by [enclosure_sign]: with every input a finite double of magnitude at
    most 2^410 (2^400 for num's p, o, n), S = Σ|a_i·b_i| the terms' magnitude (the sum the radius's m
    approximates), V the exact value:

    - [refined_radius_upper] (model): radius ≤ 571u³·S + 3u²·|V| + 20η (512u³ from the C++'s
      2^-150 ⊗ m; the rest is 2^-52 ⊗ |lo|, |lo| ≤ u|V| + 29u²S: the TwoSum chain's errors, PlaneCompensated.v's
      [two_sum_chain_invariant], and the second-order products);
    - [enclosure_sign_live3]: [enclosure_sign] is certain when |V| > (3 + 8u)·radius;
    - [refined_live]: certain when |V| > 1714u³·S + 2^-1068, for V = Σ(a_i + α_i)·b_i, |α_i| ≤ u|a_i|;
    - [refined_den_live] (den = d·n, α = +0) and [refined_num_live] (num = (p − o)·n, a_i = p_i ⊖ o_i,
      α_i its TwoDiff low part, S = Σ|(p_i ⊖ o_i)·n_i|).

    Not vacuous: [refined_den_live_witness] and [refined_num_live_witness] are queries (d·n and (p − o)·n
    cancelling to 2^-120 = 2^-15·u²·S, the kind of the runner's [refined_zone_query]) on which stage 1 and
    the first level are uncertain and the second level certain ([vm_compute] of the twins), the first one
    shown in the class.  Sharp within a factor 1.2: [refined_den_live_half_false] is an input with
    |den| = 1792u³ > 857u³·S + 2^-1068 (half the constant) on which the second level is uncertain, since
    its test needs |v| > 2·radius ≈ 1024u³·m = 2048u³ there.  Likewise the C++'s constant doubled (2^-149)
    would make [refined_den_live] false: the test would then need |v| > 2048u³·m, above its class bound
    1714u³·S for m ≈ S. *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneCascade FloatCore ConstantsCpp PlaneTwins PlaneRefinedTwins
  PlaneLiveness.
Import ListNotations.
Open Scope R_scope.

(** ** The model: an upper bound of the radius *)

(** The radius from the inputs: the proof of [compensated_dot3_refined_enclosure] read for |lo|:
    lo = Y ⊕ τ', |Y| ≤ u|X|, V = X + Y + E + Σw'_i + Σδ_i (E the chain's exact errors, |E| ≤ 28u²·Σ|h_i|,
    w'_i the second-order products, |δ_i| ≤ 2η), and τ' within (1 + u)^3 of |τ| + Σ|w'_i|. *)


Lemma refined_radius_upper : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  binary64 a0 -> binary64 a1 -> binary64 a2 -> binary64 al0 -> binary64 al1 -> binary64 al2 ->
  binary64 b0 -> binary64 b1 -> binary64 b2 ->
  Rabs al0 <= u * Rabs a0 -> Rabs al1 <= u * Rabs a1 -> Rabs al2 <= u * Rabs a2 ->
  radius (compensated_dot3_refined a0 a1 a2 al0 al1 al2 b0 b1 b2) <=
    571 * (u * (u * u)) * (Rabs (a0 * b0) + Rabs (a1 * b1) + Rabs (a2 * b2)) +
    3 * (u * u) * Rabs ((a0 + al0) * b0 + (a1 + al1) * b1 + (a2 + al2) * b2) + 20 * eta.
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 Ba0 Ba1 Ba2 Bal0 Bal1 Bal2 Bb0 Bb1 Bb2 H0 H1 H2.
  pose proof (magnitude_upper a0 a1 a2 b0 b1 b2) as MU.
  destruct (magnitude_bound a0 a1 a2 b0 b1 b2) as [Pm Qm].
  unfold compensated_dot3_refined. cbn [hi lo radius].
  set (stage1 := dot3_rounded a0 a1 a2 b0 b1 b2) in *.
  set (m := magnitude stage1) in *.
  assert (Eh0 : product0 stage1 = RN (a0 * b0)) by reflexivity.
  assert (Eh1 : product1 stage1 = RN (a1 * b1)) by reflexivity.
  assert (Eh2 : product2 stage1 = RN (a2 * b2)) by reflexivity.
  set (h0 := product0 stage1) in *. set (h1 := product1 stage1) in *. set (h2 := product2 stage1) in *.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (HS : Rabs h0 + Rabs h1 + Rabs h2 <= (1 + u) * (Rabs (a0 * b0) + Rabs (a1 * b1) + Rabs (a2 * b2)) + 3 * eta).
  { assert (Q : forall x, Rabs (RN x) <= (1 + u) * Rabs x + eta).
    { intros x. pose proof (RN_err x). pose proof (Rabs_triang_inv (RN x) x). rewrite Rabs_minus_sym in *. lra. }
    rewrite Eh0, Eh1, Eh2. pose proof (Q (a0 * b0)). pose proof (Q (a1 * b1)). pose proof (Q (a2 * b2)). lra. }
  set (S := Rabs (a0 * b0) + Rabs (a1 * b1) + Rabs (a2 * b2)) in *.
  set (V := (a0 + al0) * b0 + (a1 + al1) * b1 + (a2 + al2) * b2).
  destruct (refined_term a0 al0 b0 Ba0 Bal0 Bb0 H0) as [D0 [L0 [W0 W0']]]. rewrite <- Eh0 in D0, L0, W0, W0'.
  destruct (refined_term a1 al1 b1 Ba1 Bal1 Bb1 H1) as [D1 [L1 [W1 W1']]]. rewrite <- Eh1 in D1, L1, W1, W1'.
  destruct (refined_term a2 al2 b2 Ba2 Bal2 Bb2 H2) as [D2 [L2 [W2 W2']]]. rewrite <- Eh2 in D2, L2, W2, W2'.
  set (l0 := fma a0 b0 (- h0)) in *. set (l1 := fma a1 b1 (- h1)) in *. set (l2 := fma a2 b2 (- h2)) in *.
  set (w0 := fst (two_prod al0 b0)) in *. set (w0' := snd (two_prod al0 b0)) in *.
  set (w1 := fst (two_prod al1 b1)) in *. set (w1' := snd (two_prod al1 b1)) in *.
  set (w2 := fst (two_prod al2 b2)) in *. set (w2' := snd (two_prod al2 b2)) in *.
  assert (Bh0 : binary64 h0) by (rewrite Eh0; apply binary64_RN).
  assert (Bh1 : binary64 h1) by (rewrite Eh1; apply binary64_RN).
  assert (Bh2 : binary64 h2) by (rewrite Eh2; apply binary64_RN).
  set (s2 := fst (two_sum h0 h1)) in *. set (c2 := snd (two_sum h0 h1)) in *.
  pose proof (two_sum_exact h0 h1 Bh0 Bh1) as X2. fold s2 c2 in X2.
  destruct (two_sum_lo_bound h0 h1 Bh0 Bh1) as [C2 _]. fold c2 in C2.
  assert (S2 : Rabs (s2 - (h0 + h1)) <= u * Rabs (h0 + h1)) by (apply RN_plus_err; assumption).
  assert (Bs2 : binary64 s2) by apply binary64_two_sum_hi.
  set (s3 := fst (two_sum s2 h2)) in *. set (c3 := snd (two_sum s2 h2)) in *.
  pose proof (two_sum_exact s2 h2 Bs2 Bh2) as X3. fold s3 c3 in X3.
  destruct (two_sum_lo_bound s2 h2 Bs2 Bh2) as [C3 _]. fold c3 in C3.
  pose proof (Rabs_pos h0). pose proof (Rabs_pos h1). pose proof (Rabs_pos h2).
  set (HH := Rabs h0 + Rabs h1 + Rabs h2) in *.
  set (F := c3 :: l0 :: l1 :: l2 :: w0 :: w1 :: w2 :: nil).
  assert (A : Rabs c2 + sum_abs F <= (4 * u + 3 * (u * u) + u * (u * u)) * HH + 12 * eta).
  { unfold F. cbn [sum_abs].
    pose proof (Rabs_triang h0 h1). pose proof (Rabs_triang s2 h2).
    apply Rabs_close in S2. pose proof (Rabs_pos (h0 + h1)).
    assert (u * Rabs (s2 + h2) <= u * (Rabs s2 + Rabs h2)) by (apply Rmult_le_compat_l; lra).
    unfold HH. rewrite u_val in *. lra. }
  assert (Wsum : Rabs w0' + Rabs w1' + Rabs w2' <= u * u * ((1 + u) * (1 + u)) * HH + 9 * eta).
  { unfold HH. lra. }
  assert (BF : Forall (fun x => binary64 x) F).
  { unfold F. repeat constructor; first [apply binary64_two_sum_lo | apply binary64_RN]. }
  assert (Bc2 : binary64 c2) by apply binary64_two_sum_lo.
  pose proof (Rabs_pos c2) as Pc2.
  destruct (two_sum_chain_invariant F c2 0 0 0 (Rabs c2) 0 Bc2 binary64_0 BF
              ltac:(simpl; lra) ltac:(simpl; lra) ltac:(rewrite Rabs_R0; lra)
              ltac:(rewrite Rminus_0_r, Rabs_R0; simpl; lra))
    as [E [B [XC [Bsig [Btau [HB [HE Htau]]]]]]].
  change (0 + length F)%nat with 7%nat in HB, Htau.
  set (sigma := fst (two_sum_chain c2 0 F)) in *. set (tau := snd (two_sum_chain c2 0 F)) in *.
  destruct growth_7 as [G0 G7].
  set (k := (1 + u) ^ 7 - 1) in *.
  assert (PA : 0 <= Rabs c2 + sum_abs F).
  { unfold F. cbn [sum_abs]. pose proof (Rabs_pos c3). pose proof (Rabs_pos l0). pose proof (Rabs_pos l1).
    pose proof (Rabs_pos l2). pose proof (Rabs_pos w0). pose proof (Rabs_pos w1). pose proof (Rabs_pos w2). lra. }
  assert (PB : 0 <= B) by (eapply Rle_trans; [apply Rabs_pos | exact HE]).
  assert (HB7 : B <= (7 * u + 22 * (u * u)) * (Rabs c2 + sum_abs F)).
  { eapply Rle_trans; [exact HB|]. apply Rmult_le_compat_r; lra. }
  assert (Ht7 : Rabs (tau - E) <= (7 * u + 22 * (u * u)) * B).
  { eapply Rle_trans; [exact Htau|]. apply Rmult_le_compat_r; lra. }
  clear HB Htau G0 G7. clearbody k. clear k.
  set (t1 := RN (tau + w0')). set (t2 := RN (t1 + w1')). set (tail := RN (t2 + w2')).
  assert (E1 : Rabs (t1 - (tau + w0')) <= u * Rabs (tau + w0')) by (apply RN_plus_err; [exact Btau | apply binary64_RN]).
  assert (E2 : Rabs (t2 - (t1 + w1')) <= u * Rabs (t1 + w1')) by (apply RN_plus_err; apply binary64_RN).
  assert (E3 : Rabs (tail - (t2 + w2')) <= u * Rabs (t2 + w2')) by (apply RN_plus_err; apply binary64_RN).
  (* |tail| ≤ (1+u)^3 (|τ| + Σ|w'|) *)
  assert (Tt : Rabs tail <= (1 + u) * ((1 + u) * ((1 + u) * (Rabs tau + Rabs w0') + Rabs w1') + Rabs w2')).
  { apply Rabs_close in E1. apply Rabs_close in E2. apply Rabs_close in E3.
    pose proof (Rabs_triang tau w0'). pose proof (Rabs_triang t1 w1'). pose proof (Rabs_triang t2 w2').
    pose proof (Rabs_pos (tau + w0')). pose proof (Rabs_pos (t1 + w1')). pose proof (Rabs_pos (t2 + w2')).
    pose proof (Rabs_pos w0'). pose proof (Rabs_pos w1'). pose proof (Rabs_pos w2'). pose proof (Rabs_pos tau).
    rewrite u_val in *. lra. }
  assert (Tau : Rabs tau <= Rabs (tau - E) + Rabs E).
  { replace tau with ((tau - E) + E) at 1 by ring. apply Rabs_triang. }
  (* (X, Y) = TwoSum(s_3, σ), lo = Y ⊕ τ' *)
  assert (Bs3 : binary64 s3) by apply binary64_two_sum_hi.
  pose proof (two_sum_exact s3 sigma Bs3 Bsig) as XX.
  destruct (two_sum_lo_bound s3 sigma Bs3 Bsig) as [_ LY].
  set (X := fst (two_sum s3 sigma)) in *. set (Y := snd (two_sum s3 sigma)) in *.
  assert (Elo : Rabs (RN (Y + tail) - (Y + tail)) <= u * Rabs (Y + tail)).
  { apply RN_plus_err; [apply binary64_two_sum_lo | apply binary64_RN]. }
  set (lo := RN (Y + tail)) in *.
  assert (Lo : Rabs lo <= (1 + u) * (Rabs Y + Rabs tail)).
  { apply Rabs_close in Elo. pose proof (Rabs_triang Y tail). pose proof (Rabs_pos (Y + tail)).
    rewrite u_val in *. lra. }
  (* V = X + Y + E + Σw' + Σδ *)
  assert (Vd : V - (X + Y + E + w0' + w1' + w2') =
               ((a0 + al0) * b0 - (h0 + l0 + w0 + w0')) + ((a1 + al1) * b1 - (h1 + l1 + w1 + w1')) +
               ((a2 + al2) * b2 - (h2 + l2 + w2 + w2'))).
  { unfold F in XC. cbn [sum_list] in XC. unfold V. lra. }
  assert (Xb : Rabs X <= Rabs V + Rabs Y + Rabs E + Rabs w0' + Rabs w1' + Rabs w2' + 6 * eta).
  { apply Rabs_bounds in D0. apply Rabs_bounds in D1. apply Rabs_bounds in D2.
    pose proof (Rle_abs V). pose proof (Rle_abs (- V)). rewrite Rabs_Ropp in *.
    pose proof (Rle_abs Y). pose proof (Rle_abs (- Y)). pose proof (Rle_abs E). pose proof (Rle_abs (- E)).
    pose proof (Rle_abs w0'). pose proof (Rle_abs (- w0')). pose proof (Rle_abs w1'). pose proof (Rle_abs (- w1')).
    pose proof (Rle_abs w2'). pose proof (Rle_abs (- w2')). rewrite !Rabs_Ropp in *.
    destruct (Rle_or_lt 0 X) as [PX|NX]; [rewrite (Rabs_pos_eq X PX) | rewrite (Rabs_left X NX)]; lra. }
  clear Vd XX XC X2 X3.
  (* the radius *)
  rewrite refined_relative_val, refined_low_relative_val, refined_absolute_eta.
  assert (PK : 0 <= 512 * (u * (u * u)) * m) by (apply Rmult_le_pos; [rewrite u_val; lra | exact Pm]).
  assert (PL : 0 <= 2 * u * Rabs lo) by (apply Rmult_le_pos; [rewrite u_val; lra | apply Rabs_pos]).
  pose proof (RN_upper _ PK) as R0. pose proof (RN_upper _ PL) as R1.
  pose proof (RN_nonneg _ PK) as P0. pose proof (RN_nonneg _ PL) as P1.
  pose proof (RN_sum_upper _ _ (binary64_RN (512 * (u * (u * u)) * m)) (binary64_RN (2 * u * Rabs lo))
                ltac:(lra)) as R2.
  set (r2 := RN (RN (512 * (u * (u * u)) * m) + RN (2 * u * Rabs lo))) in *.
  assert (P2 : 0 <= r2) by (apply RN_nonneg; lra).
  assert (B16 : binary64 (16 * eta)) by (rewrite <- refined_absolute_eta; exact binary64_refined_absolute).
  assert (Br2 : binary64 r2) by apply binary64_RN.
  pose proof (RN_sum_upper r2 (16 * eta) Br2 B16 ltac:(lra)) as R3.
  assert (Km : 512 * (u * (u * u)) * m <= 512 * (u * (u * u)) * ((1 + u) * (1 + u) * ((1 + u) * S + 3 * eta))).
  { apply Rmult_le_compat_l; [rewrite u_val; lra | exact MU]. }
  assert (Ll : 2 * u * Rabs lo <= 2 * u * ((1 + u) * (Rabs Y + Rabs tail))).
  { apply Rmult_le_compat_l; [lra | exact Lo]. }
  pose proof (Rabs_pos w0'). pose proof (Rabs_pos w1'). pose proof (Rabs_pos w2'). pose proof (Rabs_pos V).
  pose proof (Rabs_pos Y). pose proof (Rabs_pos X). pose proof (Rabs_pos tau). pose proof (Rabs_pos tail).
  clearbody r2 lo m tail X Y.
  set (R := RN (r2 + 16 * eta)) in *. clearbody R.
  set (K3 := 512 * (u * (u * u)) * m) in *. clearbody K3.
  set (L3 := 2 * u * Rabs lo) in *. clearbody L3.
  rewrite u_val in *. lra.
Qed.

(** ** The twin: bounded inputs, nothing overflows *)

Lemma fbnd_forall_mono : forall k j l, (k <= j)%Z -> Forall (fbnd k) l -> Forall (fbnd j) l.
Proof. intros k j l L H. induction H; constructor; [exact (fbnd_mono k j x L H) | exact IHForall]. Qed.

(** The C++ loop of TwoSums: each step adds at most 6 to the exponent of the bound. *)
Lemma fbnd_chain : forall rest k sigma tail, fbnd k sigma -> fbnd k tail -> Forall (fbnd k) rest -> (0 <= k)%Z ->
  (k + 6 * Z.of_nat (length rest) <= 1023)%Z ->
  fbnd (k + 6 * Z.of_nat (length rest)) (fst (two_sum_chain_b sigma tail rest)) /\
  fbnd (k + 6 * Z.of_nat (length rest)) (snd (two_sum_chain_b sigma tail rest)).
Proof.
  induction rest as [|f rest IH]; intros k sigma tail Hs Ht Hr Hk Hl.
  - cbn [two_sum_chain_b length fst snd]. rewrite Z.add_0_r. split; assumption.
  - cbn [two_sum_chain_b length] in *. inversion Hr as [|x l Hf Hr']. subst x l.
    rewrite Nat2Z.inj_succ in *.
    destruct (fbnd_two_sum k k sigma f Hs Hf Hk Hk ltac:(lia)) as [S1 S2]. rewrite Z.max_id in S1, S2.
    pose proof (fbnd_add _ _ _ _ Ht S2 Hk ltac:(lia) ltac:(lia)) as T. rewrite Z.max_r in T by lia.
    replace (k + 6 * Z.succ (Z.of_nat (length rest)))%Z with ((k + 6) + 6 * Z.of_nat (length rest))%Z by lia.
    apply IH; [apply (fbnd_mono (k + 5)); [lia | exact S1] | apply (fbnd_mono (k + 5 + 1)); [lia | exact T] |
               exact (fbnd_forall_mono k (k + 6) rest ltac:(lia) Hr') | lia | lia].
Qed.

(** With inputs of magnitude at most 2^410, hi, lo and the radius are below 2^1000. *)
Lemma refined_b_bounded : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  fbnd 410 a0 -> fbnd 410 a1 -> fbnd 410 a2 -> fbnd 410 al0 -> fbnd 410 al1 -> fbnd 410 al2 ->
  fbnd 410 b0 -> fbnd 410 b1 -> fbnd 410 b2 ->
  let e := compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2) in
  fbnd 1000 (hib e) /\ fbnd 1000 (lob e) /\ fbnd 1000 (radiusb e).
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 A0 A1 A2 L0 L1 L2 B0 B1 B2 e.
  unfold e, compensated_dot3_refined_b, dot3_rounded_b. cbv zeta. cbn [qb0 qb1 qb2 magnitudeb hib lob radiusb].
  cbn [two_prod_b fst snd].
  match goal with |- context [two_sum_chain_b ?s ?t ?l] =>
    destruct (fbnd_chain l 830 s t) as [C1 C2];
    [eapply fbnd_le; [fbnd_tac | zle] | exact (fbnd_mono 0 830 _ ltac:(lia) fbnd_zero) |
     repeat (apply Forall_cons; [eapply fbnd_le; [fbnd_tac | zle] |]); apply Forall_nil | lia | cbn [length]; lia | ]
  end.
  cbn [length] in C1, C2. change (830 + 6 * Z.of_nat 7)%Z with 872%Z in C1, C2.
  split; [|split]; (eapply fbnd_le; [fbnd_tac | zle]).
Qed.

(** ** enclosure_sign: certain when |V| > (3 + 8u)·radius *)

(** In the model, for any enclosure of V by doubles (sharper than PlaneLiveness.v's 4·radius): PlaneLiveness.v's
    [enclosure_sign_live_encl_model]. *)
Lemma enclosure_sign_live3_model : forall e V, binary64 (hi e) -> binary64 (lo e) -> binary64 (radius e) ->
  encloses e V -> (3 + 8 * u) * radius e < Rabs V -> enclosure_sign_lanes e <> uncertain_lane.
Proof. exact enclosure_sign_live_encl_model. Qed.

Lemma enclosure_sign_live3 : forall e V, fbnd 1000 (hib e) -> fbnd 1000 (lob e) -> fbnd 1000 (radiusb e) ->
  encloses (enc_R e) V -> (3 + 8 * u) * B2R (radiusb e) < Rabs V -> enclosure_sign_lanes_b e <> uncertain_lane.
Proof.
  intros e V Hh Hl Hr E L.
  rewrite enclosure_sign_b_model.
  - apply (enclosure_sign_live3_model _ V); try apply binary64_B2R; assumption.
  - destruct (fbnd_add _ _ _ _ Hh Hl ltac:(lia) ltac:(lia) ltac:(lia)) as [F _]. exact F.
  - destruct (fbnd_add _ _ _ _ Hr Hr ltac:(lia) ltac:(lia) ltac:(lia)) as [F _]. exact F.
Qed.

(** ** The second level of stage 2 does certify *)

(** The twin, for the values V = Σ (a_i + α_i)·b_i it encloses: finite inputs of magnitude at most 2^410
    with |α_i| ≤ u|a_i|, and |V| > 1714u³·S + 2^-1068 (S = Σ|a_i·b_i|) ⇒ certain. *)
Theorem refined_live : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  fbnd 410 a0 -> fbnd 410 a1 -> fbnd 410 a2 -> fbnd 410 al0 -> fbnd 410 al1 -> fbnd 410 al2 ->
  fbnd 410 b0 -> fbnd 410 b1 -> fbnd 410 b2 ->
  Rabs (B2R al0) <= u * Rabs (B2R a0) -> Rabs (B2R al1) <= u * Rabs (B2R a1) -> Rabs (B2R al2) <= u * Rabs (B2R a2) ->
  1714 * (u * (u * u)) * (Rabs (B2R a0 * B2R b0) + Rabs (B2R a1 * B2R b1) + Rabs (B2R a2 * B2R b2)) +
    bpow radix2 (-1068) <
    Rabs ((B2R a0 + B2R al0) * B2R b0 + (B2R a1 + B2R al1) * B2R b1 + (B2R a2 + B2R al2) * B2R b2) ->
  enclosure_sign_lanes_b
    (compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2))
    <> uncertain_lane.
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 A0 A1 A2 L0 L1 L2 B0 B1 B2 Al0 Al1 Al2 L.
  destruct (refined_b_bounded a0 a1 a2 al0 al1 al2 b0 b1 b2 A0 A1 A2 L0 L1 L2 B0 B1 B2) as [BH [BL BR]].
  generalize (compensated_dot3_refined_twin a0 a1 a2 al0 al1 al2 b0 b1 b2). cbv zeta.
  generalize BH BL BR.
  generalize (compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2)) as e.
  intros e BH' BL' BR' Tw.
  destruct (Tw (proj1 BR') (proj1 BH') (proj1 BL')) as [_ [_ [_ [_ [_ [_ [_ [_ [_ E]]]]]]]]].
  apply (enclosure_sign_live3 e ((B2R a0 + B2R al0) * B2R b0 + (B2R a1 + B2R al1) * B2R b1 +
                                 (B2R a2 + B2R al2) * B2R b2) BH' BL' BR').
  - rewrite E. apply compensated_dot3_refined_enclosure; try apply binary64_B2R; assumption.
  - change (B2R (radiusb e)) with (radius (enc_R e)). rewrite E.
    pose proof (refined_radius_upper (B2R a0) (B2R a1) (B2R a2) (B2R al0) (B2R al1) (B2R al2)
                  (B2R b0) (B2R b1) (B2R b2) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
                  (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
                  (binary64_B2R _) Al0 Al1 Al2) as U.
    set (r := radius _) in *. clearbody r.
    set (S := Rabs (B2R a0 * B2R b0) + Rabs (B2R a1 * B2R b1) + Rabs (B2R a2 * B2R b2)) in *.
    set (V := (B2R a0 + B2R al0) * B2R b0 + (B2R a1 + B2R al1) * B2R b1 + (B2R a2 + B2R al2) * B2R b2) in *.
    assert (PS : 0 <= S) by (unfold S; pose proof (Rabs_pos (B2R a0 * B2R b0));
                             pose proof (Rabs_pos (B2R a1 * B2R b1)); pose proof (Rabs_pos (B2R a2 * B2R b2)); lra).
    clearbody S V.
    assert (E1068 : bpow radix2 (-1068) = 128 * eta).
    { unfold eta. replace (-1068)%Z with (7 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. }
    rewrite E1068 in L. pose proof eta_pos. pose proof (Rabs_pos V).
    assert (Mu : (3 + 8 * u) * r <= (3 + 8 * u) * (571 * (u * (u * u)) * S + 3 * (u * u) * Rabs V + 20 * eta)).
    { apply Rmult_le_compat_l; [pose proof u_pos; lra | exact U]. }
    clear U. rewrite u_val in *. lra.
Qed.

(** den = d·n (the cascade's [den_refined]: α = +0): certain when |den| > 1714u³·Σ|d_i·n_i| + 2^-1068. *)
Theorem refined_den_live : forall d0 d1 d2 n0 n1 n2,
  fbnd 410 d0 -> fbnd 410 d1 -> fbnd 410 d2 -> fbnd 410 n0 -> fbnd 410 n1 -> fbnd 410 n2 ->
  1714 * (u * (u * u)) * (Rabs (B2R d0 * B2R n0) + Rabs (B2R d1 * B2R n1) + Rabs (B2R d2 * B2R n2)) +
    bpow radix2 (-1068) < Rabs (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) ->
  enclosure_sign_lanes_b (den_refined_b d0 d1 d2 n0 n1 n2) <> uncertain_lane.
Proof.
  intros d0 d1 d2 n0 n1 n2 D0 D1 D2 N0 N1 N2 L. unfold den_refined_b.
  assert (Z : fbnd 410 fzero) by exact (fbnd_mono 0 410 _ ltac:(lia) fbnd_zero).
  assert (Zu : forall x, Rabs (B2R fzero) <= u * Rabs x).
  { intros x. change (B2R fzero) with 0. rewrite Rabs_R0. pose proof u_pos. pose proof (Rabs_pos x). nra. }
  apply refined_live; try assumption; try apply Zu.
  change (B2R fzero) with 0. rewrite !Rplus_0_r. exact L.
Qed.

(** A TwoDiff of bounded doubles: its parts are bounded, a = RN(p − o), |α| ≤ u|a|, a + α = p − o. *)
Lemma two_diff_b_live : forall p o, fbnd 400 p -> fbnd 400 o ->
  fbnd 410 (fst (two_diff_b p o)) /\ fbnd 410 (snd (two_diff_b p o)) /\
  B2R (fst (two_diff_b p o)) = RN (B2R p - B2R o) /\
  Rabs (B2R (snd (two_diff_b p o))) <= u * Rabs (B2R (fst (two_diff_b p o))) /\
  B2R (fst (two_diff_b p o)) + B2R (snd (two_diff_b p o)) = B2R p - B2R o.
Proof.
  intros p o P O.
  destruct (fbnd_two_sum 400 400 p (fneg o) P (fbnd_neg _ _ O) ltac:(lia) ltac:(lia) ltac:(lia)) as [F1 F2].
  change (two_sum_b p (fneg o)) with (two_diff_b p o) in F1, F2.
  destruct (two_diff_b_parts p o (proj1 F2)) as [_ [_ [E1 E2]]].
  destruct (two_diff_low_part (B2R p) (B2R o) (binary64_B2R _) (binary64_B2R _)) as [X [A _]].
  rewrite <- E1, <- E2 in X, A.
  split; [apply (fbnd_mono (Z.max 400 400 + 5)); [lia | exact F1]|].
  split; [apply (fbnd_mono (Z.max 400 400 + 5)); [lia | exact F2]|].
  split; [exact E1|]. split; [exact A | exact X].
Qed.

(** num = (p − o)·n (the cascade's [num_refined]: a_i = p_i ⊖ o_i, α_i its TwoDiff low part): certain
    when |num| > 1714u³·Σ|(p_i ⊖ o_i)·n_i| + 2^-1068. *)
Theorem refined_num_live : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  fbnd 400 p0 -> fbnd 400 p1 -> fbnd 400 p2 -> fbnd 400 o0 -> fbnd 400 o1 -> fbnd 400 o2 ->
  fbnd 400 n0 -> fbnd 400 n1 -> fbnd 400 n2 ->
  1714 * (u * (u * u)) * (Rabs (RN (B2R p0 - B2R o0) * B2R n0) + Rabs (RN (B2R p1 - B2R o1) * B2R n1) +
                          Rabs (RN (B2R p2 - B2R o2) * B2R n2)) + bpow radix2 (-1068) <
    Rabs ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2) ->
  enclosure_sign_lanes_b (num_refined_b p0 p1 p2 o0 o1 o2 n0 n1 n2) <> uncertain_lane.
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 P0 P1 P2 O0 O1 O2 N0 N1 N2 L. unfold num_refined_b. cbv zeta.
  destruct (two_diff_b_live p0 o0 P0 O0) as [F0 [G0 [E0 [A0 X0]]]].
  destruct (two_diff_b_live p1 o1 P1 O1) as [F1 [G1 [E1 [A1 X1]]]].
  destruct (two_diff_b_live p2 o2 P2 O2) as [F2 [G2 [E2 [A2 X2]]]].
  assert (M0 : fbnd 410 n0) by (apply (fbnd_mono 400); [lia | exact N0]).
  assert (M1 : fbnd 410 n1) by (apply (fbnd_mono 400); [lia | exact N1]).
  assert (M2 : fbnd 410 n2) by (apply (fbnd_mono 400); [lia | exact N2]).
  apply refined_live; try assumption.
  rewrite X0, X1, X2, E0, E1, E2. exact L.
Qed.

(** ** Not vacuous, and sharp within a factor 2 *)

(** Doubles as the C++ writes them: 1, 2^-60, 7·2^-76, 2^-75 (positive significand, exponent). *)
Definition f_one : float := @B754_finite 53 1024 false 4503599627370496 (-52) eq_refl.
Definition f_2m60 : float := @B754_finite 53 1024 false 4503599627370496 (-112) eq_refl.
Definition f_7_2m76 : float := @B754_finite 53 1024 false 7881299347898368 (-126) eq_refl.
Definition f_2m75 : float := @B754_finite 53 1024 false 4503599627370496 (-127) eq_refl.

Lemma f_one_val : B2R f_one = 1.
Proof.
  change (B2R f_one) with (IZR 4503599627370496 * bpow radix2 (-52)).
  change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. reflexivity.
Qed.
Lemma f_2m60_val : B2R f_2m60 = bpow radix2 (-60).
Proof.
  change (B2R f_2m60) with (IZR 4503599627370496 * bpow radix2 (-112)).
  change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. reflexivity.
Qed.
Lemma f_7_2m76_val : B2R f_7_2m76 = 7 * bpow radix2 (-76).
Proof.
  change (B2R f_7_2m76) with (IZR 7881299347898368 * bpow radix2 (-126)).
  replace (IZR 7881299347898368) with (7 * bpow radix2 50) by (simpl bpow; lra).
  rewrite Rmult_assoc, <- bpow_plus. reflexivity.
Qed.
Lemma f_2m75_val : B2R f_2m75 = bpow radix2 (-75).
Proof.
  change (B2R f_2m75) with (IZR 4503599627370496 * bpow radix2 (-127)).
  change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. reflexivity.
Qed.

Lemma fbnd_small : forall x, fin x = true -> Rabs (B2R x) <= 1 -> fbnd 400 x.
Proof.
  intros x F B. split; [exact F|]. eapply Rle_trans; [exact B|].
  change 1 with (bpow radix2 0). apply bpow_le. lia.
Qed.

Lemma bpow_pos_le1 : forall e, (e <= 0)%Z -> 0 <= bpow radix2 e <= 1.
Proof. intros e H. split; [apply bpow_ge_0 | change 1 with (bpow radix2 0); apply bpow_le; lia]. Qed.

(** den for d = (1, 1, 2^-60), n = (1, −1, 2^-60): d·n = 2^-120 cancels to 2^-15·u²·Σ|d_i n_i|, far below
    stage 1's and the first level's bounds (≈ 2^-49·2 and 64u²·2 = 2^-99), far above the second level's
    class bound 1714u³·2 ≈ 2^-148.  Stage 1 and the first level are uncertain ([vm_compute] of the twins),
    the second level certain, as [refined_den_live] says it must be. *)
Example refined_den_live_witness :
  let d0 := f_one in let d1 := f_one in let d2 := f_2m60 in
  let n0 := f_one in let n1 := fneg f_one in let n2 := f_2m60 in
  dot3_filter_lanes_b (dot3_rounded_b d0 d1 d2 n0 n1 n2) Cpp.filter_den_relative = uncertain_lane /\
  enclosure_sign_lanes_b (den_compensated_b d0 d1 d2 n0 n1 n2) = uncertain_lane /\
  enclosure_sign_lanes_b (den_refined_b d0 d1 d2 n0 n1 n2) = 1%Z /\
  1714 * (u * (u * u)) * (Rabs (B2R d0 * B2R n0) + Rabs (B2R d1 * B2R n1) + Rabs (B2R d2 * B2R n2)) +
    bpow radix2 (-1068) < Rabs (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2).
Proof.
  cbv zeta. split; [vm_compute; reflexivity|]. split; [vm_compute; reflexivity|]. split; [vm_compute; reflexivity|].
  rewrite fneg_val, f_one_val, f_2m60_val.
  rewrite <- bpow_plus. change (-60 + -60)%Z with (-120)%Z.
  pose proof (bpow_pos_le1 (-120) ltac:(lia)).
  rewrite (Rabs_pos_eq (bpow radix2 (-120))) by lra.
  rewrite Rmult_1_l, Rmult_1_l, Rabs_R1, Rabs_Ropp, Rabs_R1.
  replace (1 + - (1) + bpow radix2 (-120)) with (bpow radix2 (-120)) by ring.
  rewrite (Rabs_pos_eq (bpow radix2 (-120))) by lra.
  pose proof (bpow_pos_le1 (-1068) ltac:(lia)).
  assert (E : bpow radix2 (-120) = 2 ^ 39 * (u * (u * u))).
  { rewrite u_val. simpl bpow. simpl pow. lra. }
  assert (E' : bpow radix2 (-1068) <= bpow radix2 (-120) / 4).
  { unfold Rdiv. change (/ 4) with (bpow radix2 (-2)). rewrite <- bpow_plus. apply bpow_le. lia. }
  rewrite E in *. pose proof u_pos. assert (0 < u * (u * u)) by (apply Rmult_lt_0_compat; nra).
  assert (W : u * (u * u) <= / 1125899906842624) by (rewrite u_val; lra).
  set (w := u * (u * u)) in *. clearbody w.
  assert (w * w <= w * / 1125899906842624) by (apply Rmult_le_compat_l; lra).
  nra.
Qed.

(** The same cancellation as a num: p = (3/2, −1/2, 2^-60), o = (1/2, 1/2, 0), n = (1, 1, 2^-60), so
    p − o = (1, −1, 2^-60) and num = 2^-120: stage 1 and the first level uncertain, the second level
    certain (the twins, [vm_compute]). *)
Definition f_3_2 : float := @B754_finite 53 1024 false 6755399441055744 (-52) eq_refl.
Definition f_1_2 : float := @B754_finite 53 1024 false 4503599627370496 (-53) eq_refl.

Example refined_num_live_witness :
  let p0 := f_3_2 in let p1 := fneg f_1_2 in let p2 := f_2m60 in
  let o0 := f_1_2 in let o1 := f_1_2 in let o2 := fzero in
  let n0 := f_one in let n1 := f_one in let n2 := f_2m60 in
  dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b p0 o0)) (fst (two_diff_b p1 o1)) (fst (two_diff_b p2 o2))
                         n0 n1 n2) Cpp.filter_num_relative = uncertain_lane /\
  enclosure_sign_lanes_b (num_compensated_b p0 p1 p2 o0 o1 o2 n0 n1 n2) = uncertain_lane /\
  enclosure_sign_lanes_b (num_refined_b p0 p1 p2 o0 o1 o2 n0 n1 n2) = 1%Z.
Proof. cbv zeta. split; [vm_compute; reflexivity|]. split; vm_compute; reflexivity. Qed.

(** Sharpness: [refined_den_live] with the constant halved (857u³) is false.  For d = (1, 1, 7·2^-76),
    n = (1, −1, 2^-75), den = 7·2^-151 = 1792u³ exceeds 857u³·Σ|d_i n_i| ≈ 1714u³ + ..., but the second
    level's radius is 512u³·m = 2^-149 (m = 2) and its test needs |hi ⊕ lo| > 2·radius = 2048u³: uncertain
    ([vm_compute]).  So the class's constant is within a factor 2048/1714 < 1.2 of the best constant for
    den, and above the C++'s 4·512u³ = 2048u³ only by the radius's own |lo| and rounding terms. *)
Theorem refined_den_live_half_false : ~ (forall d0 d1 d2 n0 n1 n2,
  fbnd 410 d0 -> fbnd 410 d1 -> fbnd 410 d2 -> fbnd 410 n0 -> fbnd 410 n1 -> fbnd 410 n2 ->
  857 * (u * (u * u)) * (Rabs (B2R d0 * B2R n0) + Rabs (B2R d1 * B2R n1) + Rabs (B2R d2 * B2R n2)) +
    bpow radix2 (-1068) < Rabs (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) ->
  enclosure_sign_lanes_b (den_refined_b d0 d1 d2 n0 n1 n2) <> uncertain_lane).
Proof.
  intros H.
  assert (B1 : fbnd 410 f_one) by (apply (fbnd_mono 400); [lia | apply fbnd_small; [reflexivity | rewrite f_one_val, Rabs_R1; lra]]).
  assert (B1' : fbnd 410 (fneg f_one)) by (apply fbnd_neg; exact B1).
  assert (B7 : fbnd 410 f_7_2m76).
  { apply (fbnd_mono 400); [lia | apply fbnd_small; [reflexivity|]]. rewrite f_7_2m76_val.
    pose proof (bpow_pos_le1 (-76) ltac:(lia)). rewrite Rabs_pos_eq by lra. simpl bpow. lra. }
  assert (B75 : fbnd 410 f_2m75).
  { apply (fbnd_mono 400); [lia | apply fbnd_small; [reflexivity|]]. rewrite f_2m75_val.
    pose proof (bpow_pos_le1 (-75) ltac:(lia)). rewrite Rabs_pos_eq by lra. lra. }
  apply (H f_one f_one f_7_2m76 f_one (fneg f_one) f_2m75 B1 B1 B7 B1 B1' B75).
  - assert (P7 : B2R f_7_2m76 * B2R f_2m75 = 7 * bpow radix2 (-151)).
    { rewrite f_7_2m76_val, f_2m75_val, Rmult_assoc, <- bpow_plus. reflexivity. }
    rewrite P7, fneg_val, f_one_val.
    pose proof (bpow_pos_le1 (-151) ltac:(lia)).
    rewrite Rmult_1_l, Rmult_1_l, Rabs_R1, Rabs_Ropp, Rabs_R1.
    replace (1 + - (1) + 7 * bpow radix2 (-151)) with (7 * bpow radix2 (-151)) by ring.
    assert (E : bpow radix2 (-151) = 256 * (u * (u * u))) by (rewrite u_val; simpl bpow; lra).
    assert (E' : bpow radix2 (-1068) <= bpow radix2 (-151) / 4).
    { unfold Rdiv. change (/ 4) with (bpow radix2 (-2)). rewrite <- bpow_plus. apply bpow_le. lia. }
    rewrite E in *. pose proof u_pos. assert (0 < u * (u * u)) by (apply Rmult_lt_0_compat; nra).
    assert (W : u * (u * u) <= / 1125899906842624) by (rewrite u_val; lra).
    set (w := u * (u * u)) in *. clearbody w.
    rewrite Rabs_pos_eq by lra.
    assert (w * w <= w * / 1125899906842624) by (apply Rmult_le_compat_l; lra).
    nra.
  - vm_compute. reflexivity.
Qed.
