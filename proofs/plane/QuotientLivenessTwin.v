(** * Liveness of the quotient rounding over the twin (kernel/src/core/quotient_rounding.hpp:
    [prepare_divisor], [round_quotient]; PlaneQueryTwins.v: [prepare_divisor_b], [round_quotient_b]).

    QuotientLiveness.v's [round_quotient_live] states the liveness over the model ([round_quotient],
    [prepare_divisor], where RN has no overflow).  Here the same class over the twin, the Flocq binary64
    definitions the differential runner checks bit for bit against the C++:

    - [prepare_divisor_b_fwd]: for finite dh, dl of magnitude ≤ 2^1000 with the model's divisor in range,
      [prepare_divisor_b] is finite field by field and is the model's [prepare_divisor] (1 ⊘ D finite and
      RN(1/D), by FloatCore.v's [fdiv_fwd]);
    - [round_quotient_b_fwd]: on such a divisor and a numerator with finite parts of magnitude ≤ 2^1000, a
      quotient |RN(X)| ≤ 2^1001·|D| and radii 0 ≤ E_n ≤ 2^1005, 0 ≤ E_d ≤ |D|, every operation of
      [round_quotient_b] is finite (each below 2^1020: no overflow) and the twin's (t, certain) is the
      model's [round_quotient] — forwards, where PlaneQueryTwins.v's [round_quotient_twin] goes backwards from a
      certified answer;
    - [round_quotient_live_b]: the twin certifies, with t = RN(X/Y) finite, on [round_quotient_live]'s class
      (finite parts of magnitude ≤ 2^1000, E_n, E_d finite and ≥ 0, 2^-1000 ≤ |Y| ≤ 2^1000,
      2^-900 ≤ |X|, 2^-900 ≤ |X/Y| ≤ 2^1000, and
      |Q − RN(Q)| + (1 + 2^-8)(E_n + |Q|E_d)/|Y| + 2^-97|Q| < half_gap(RN(Q)));
      [round_quotient_live_exact_b]: radius 0.
    - [round_quotient_b_third_live], [round_quotient_b_near_midpoint_live]: the computed examples of
      QuotientLiveness.v (1/3, and the near-midpoint X = 1 + 2^-53 + k·2^-106 at k = 513) are in the class,
      shown by real arithmetic, so the theorem is not vacuous and its threshold is the one
      [near_midpoint_threshold] brackets (the twin certifies from k = 290 on);
    - [fast_answer_from_live_b]: at the call site (plane/ray_plane_stages.hpp's [fast_answer_from]), on
      stage-2 enclosures in the class, t = RN(X/Y) and the answer is certain exactly when both signs are.

    The extra hypothesis |hi|, |lo| ≤ 2^1000 is needed: TwoSum of two finite doubles can overflow in its
    intermediate s − a (PlaneStageTwoFinite.v), and X itself must not overflow. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated QuotientRounding FloatCore ConstantsCpp PlaneTwins
  PlaneQueryTwins PlaneLiveness QuotientLiveness.
Open Scope R_scope.

Lemma RN_abs_up : forall x, Rabs (RN x) <= (1 + u) * Rabs x + eta.
Proof.
  intros x. pose proof (RN_err x) as E. pose proof (Rabs_close _ _ _ E). lra.
Qed.

Lemma RN_abs_up' : forall v x, v = RN x -> Rabs v <= (1 + u) * Rabs x + eta.
Proof. intros v x ->. apply RN_abs_up. Qed.

Lemma RN_below : forall x, Rabs x <= bpow radix2 1020 -> Rabs (RN x) < bpow radix2 1024.
Proof.
  intros x H. eapply Rle_lt_trans; [apply (RN_bpow_bound 1020); [lia | exact H]|]. apply bpow_lt. lia.
Qed.

(** ** The model's intermediates are below 2^1020.  V = |N| + 2^-70·|D| is the scale of the numerator;
    a quotient-like value v (q0, c, q, w) has |v|·|D| ≤ k·V, hence |v| ≤ k·(2^1001 + 2^-70). *)
Lemma rq_model_bounds : forall N n D d r En Ed : R,
  bpow radix2 (-1000) <= Rabs D <= bpow radix2 1000 -> Rabs d <= u * Rabs D ->
  Rabs (r * D - 1) <= u -> Rabs N <= bpow radix2 1005 -> Rabs N <= bpow radix2 1001 * Rabs D ->
  Rabs n <= u * Rabs N -> 0 <= En <= bpow radix2 1005 -> 0 <= Ed <= Rabs D ->
  let q0 := RN (N * r) in
  let r1 := RN (- q0 * D + N) in
  let r2 := RN (- q0 * d + n) in
  let s := RN (r1 + r2) in
  let c := RN (s * r) in
  let q := RN (q0 + c) in
  let qq := RN (q - q0) in
  let w := RN (c - qq) in
  let xb := RN (Rabs q0 * Ed) in
  let xs := RN (xb + En) in
  let x := RN (xs * quotient_enclosure_factor) in
  let yb := RN (Rabs q0 * quotient_relative) in
  let ys := RN (yb + Rabs w) in
  let y := RN (ys * Rabs D) in
  let K := bpow radix2 1020 in
  Rabs (N * r) <= K /\ Rabs (- q0 * D + N) <= K /\ Rabs (- q0 * d + n) <= K /\ Rabs (r1 + r2) <= K /\
  Rabs (s * r) <= K /\ Rabs (q0 + c) <= K /\ Rabs (q - q0) <= K /\ Rabs (c - qq) <= K /\
  Rabs (Rabs q0 * Ed) <= K /\ Rabs (xb + En) <= K /\ Rabs (xs * quotient_enclosure_factor) <= K /\
  Rabs (Rabs q0 * quotient_relative) <= K /\ Rabs (yb + Rabs w) <= K /\ Rabs (ys * Rabs D) <= K /\
  Rabs (x + y) <= K /\ Rabs (RN (x + y) * quotient_test_factor) <= K /\
  Rabs q * Rabs D <= K.
Proof.
  intros N n D d r En Ed [GD1 GD2] Ld RD BN NQ Ln [PEn BEn] [PEd BEd].
  intros q0 r1 r2 s c q qq w xb xs x yb ys y K.
  set (aD := Rabs D) in *.
  set (e := bpow radix2 (-70)).
  set (M := bpow radix2 1001) in *.
  set (V := Rabs N + e * aD).
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof (Rabs_pos N) as PN.
  assert (Hu1 : u = / 9007199254740992) by exact u_val.
  assert (PaD : 0 < aD) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact GD1]).
  assert (Pe : 0 < e) by apply bpow_gt_0.
  assert (HK : K = bpow radix2 1020) by reflexivity.
  assert (BK : bpow radix2 1012 * 256 = K).
  { rewrite HK. replace 1020%Z with (1012 + 8)%Z by lia. rewrite bpow_plus. reflexivity. }
  assert (B1005 : bpow radix2 1005 * 128 = bpow radix2 1012).
  { replace 1012%Z with (1005 + 7)%Z by lia. rewrite bpow_plus. reflexivity. }
  assert (BM : M * 16 = bpow radix2 1005).
  { unfold M. replace 1005%Z with (1001 + 4)%Z by lia. rewrite bpow_plus. reflexivity. }
  assert (PM : 0 < M) by apply bpow_gt_0.
  assert (eM : e <= M) by (apply bpow_le; lia).
  (* e·|D| ≤ 2^930 ≤ M, η ≤ e·|D| / 32, η·|D| ≤ e·|D| *)
  assert (eD : e * aD <= M).
  { unfold e, M. eapply Rle_trans; [apply Rmult_le_compat_l; [apply bpow_ge_0 | exact GD2]|].
    rewrite <- bpow_plus. apply bpow_le. lia. }
  assert (etaD : eta <= / 32 * (e * aD)).
  { eapply Rle_trans; [|apply Rmult_le_compat_l; [lra | apply Rmult_le_compat_l; [lra | exact GD1]]].
    unfold eta, e. rewrite <- bpow_plus. replace (/ 32) with (bpow radix2 (-5)) by (simpl; lra).
    rewrite <- bpow_plus. apply bpow_le. lia. }
  assert (etaaD : eta * aD <= / 32 * (e * aD)).
  { assert (eta <= / 32 * e) by (unfold eta, e; replace (/ 32) with (bpow radix2 (-5)) by (simpl; lra);
      rewrite <- bpow_plus; apply bpow_le; lia).
    assert (eta * aD <= / 32 * e * aD) by (apply Rmult_le_compat_r; lra). lra. }
  assert (VM : V <= (M + e) * aD) by (unfold V; lra).
  assert (VB : V <= bpow radix2 1005 + M) by (unfold V; lra).
  assert (PV : e * aD <= V) by (unfold V; lra).
  (* a quotient-like value: |v|·|D| ≤ k·V gives |v| ≤ k·(M + e) *)
  assert (Quot : forall v k, 0 <= k -> Rabs v * aD <= k * V -> Rabs v <= k * (M + e)).
  { intros v k Pk H. apply Rmult_le_reg_r with aD; [exact PaD|].
    assert (k * V <= k * ((M + e) * aD)) by (apply Rmult_le_compat_l; lra). lra. }
  (* |v| ≤ a gives |v|·|D| ≤ a·|D| *)
  assert (Sc : forall v a, Rabs v <= a -> Rabs v * aD <= a * aD) by (intros v a H; apply Rmult_le_compat_r; lra).
  assert (rD : Rabs r * aD <= 1 + u).
  { unfold aD. rewrite <- Rabs_mult. pose proof (Rabs_close _ _ _ RD). rewrite Rabs_R1 in H. lra. }
  assert (Mul_r : forall v, Rabs (v * r) * aD <= (1 + u) * Rabs v).
  { intros v. rewrite Rabs_mult. replace (Rabs v * Rabs r * aD) with (Rabs v * (Rabs r * aD)) by ring.
    rewrite (Rmult_comm (1 + u)). apply Rmult_le_compat_l; [apply Rabs_pos | exact rD]. }
  assert (RNs : forall v z, v = RN z -> Rabs v * aD <= (1 + u) * (Rabs z * aD) + / 32 * (e * aD)).
  { intros v z ->. pose proof (Sc _ _ (RN_abs_up z)). lra. }
  assert (Tri : forall a b, Rabs (a + b) <= Rabs a + Rabs b) by apply Rabs_triang.
  assert (Tri' : forall a b, Rabs (a - b) <= Rabs a + Rabs b).
  { intros a b. unfold Rminus. rewrite <- (Rabs_Ropp b). apply Rabs_triang. }
  assert (Neg : forall a b c', Rabs (- a * b + c') <= Rabs a * Rabs b + Rabs c').
  { intros a b c'. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_mult, Rabs_Ropp. lra. }
  assert (PMe : 0 <= M + e) by lra.
  (* q0 *)
  assert (T0 : Rabs (N * r) * aD <= (1 + u) * Rabs N) by apply Mul_r.
  assert (T0' : Rabs (N * r) <= 2 * (M + e)).
  { apply Quot; [lra|]. unfold V. rewrite Hu1 in T0. lra. }
  assert (Q0 : Rabs q0 * aD <= 2 * V).
  { pose proof (RNs q0 (N * r) eq_refl). unfold V. rewrite Hu1 in *. lra. }
  assert (Q0' : Rabs q0 <= 2 * (M + e)) by (apply Quot; lra).
  (* r1, r2, s *)
  assert (R1e : Rabs (- q0 * D + N) <= 3 * V).
  { pose proof (Neg q0 D N). fold aD in H. unfold V in *. lra. }
  assert (R1 : Rabs r1 <= 4 * V) by (pose proof (RN_abs_up' r1 (- q0 * D + N) eq_refl); rewrite Hu1 in *; lra).
  assert (q0d : Rabs q0 * Rabs d <= u * (Rabs q0 * aD)).
  { replace (u * (Rabs q0 * aD)) with (Rabs q0 * (u * aD)) by ring. apply Rmult_le_compat_l; [apply Rabs_pos | exact Ld]. }
  assert (R2e : Rabs (- q0 * d + n) <= / 2 * V).
  { pose proof (Neg q0 d n). unfold V in *. rewrite Hu1 in *. lra. }
  assert (R2 : Rabs r2 <= V) by (pose proof (RN_abs_up' r2 (- q0 * d + n) eq_refl); rewrite Hu1 in *; lra).
  assert (Se : Rabs (r1 + r2) <= 5 * V) by (pose proof (Tri r1 r2); lra).
  assert (S : Rabs s <= 6 * V) by (pose proof (RN_abs_up' s (r1 + r2) eq_refl); rewrite Hu1 in *; lra).
  (* c, q, qq, w *)
  assert (Ce : Rabs (s * r) * aD <= 7 * V) by (pose proof (Mul_r s); rewrite Hu1 in *; lra).
  assert (C : Rabs c * aD <= 8 * V) by (pose proof (RNs c (s * r) eq_refl); rewrite Hu1 in *; lra).
  assert (Qe : Rabs (q0 + c) * aD <= 10 * V) by (pose proof (Sc _ _ (Tri q0 c)); lra).
  assert (Q : Rabs q * aD <= 11 * V) by (pose proof (RNs q (q0 + c) eq_refl); rewrite Hu1 in *; lra).
  assert (QQe : Rabs (q - q0) * aD <= 13 * V) by (pose proof (Sc _ _ (Tri' q q0)); lra).
  assert (QQ : Rabs qq * aD <= 14 * V) by (pose proof (RNs qq (q - q0) eq_refl); rewrite Hu1 in *; lra).
  assert (We : Rabs (c - qq) * aD <= 22 * V) by (pose proof (Sc _ _ (Tri' c qq)); lra).
  assert (W : Rabs w * aD <= 23 * V) by (pose proof (RNs w (c - qq) eq_refl); rewrite Hu1 in *; lra).
  (* x *)
  assert (XBe : Rabs (Rabs q0 * Ed) <= 2 * V).
  { rewrite Rabs_mult, Rabs_Rabsolu, (Rabs_pos_eq Ed) by lra.
    assert (Rabs q0 * Ed <= Rabs q0 * aD) by (apply Rmult_le_compat_l; [apply Rabs_pos | lra]). lra. }
  assert (XB : Rabs xb <= 3 * V) by (pose proof (RN_abs_up' xb (Rabs q0 * Ed) eq_refl); rewrite Hu1 in *; lra).
  assert (XSe : Rabs (xb + En) <= 3 * V + bpow radix2 1005).
  { pose proof (Tri xb En). rewrite (Rabs_pos_eq En) in H by lra. lra. }
  assert (XS : Rabs xs <= 4 * V + 2 * bpow radix2 1005)
    by (pose proof (RN_abs_up' xs (xb + En) eq_refl); rewrite Hu1 in *; lra).
  assert (F1 : Rabs quotient_enclosure_factor <= 2).
  { rewrite quotient_enclosure_factor_val, Rabs_pos_eq; lra. }
  assert (Xe : Rabs (xs * quotient_enclosure_factor) <= 8 * V + 4 * bpow radix2 1005).
  { rewrite Rabs_mult. pose proof (Rabs_pos xs).
    assert (Rabs xs * Rabs quotient_enclosure_factor <= Rabs xs * 2) by (apply Rmult_le_compat_l; lra). lra. }
  assert (X : Rabs x <= 9 * V + 5 * bpow radix2 1005)
    by (pose proof (RN_abs_up' x (xs * quotient_enclosure_factor) eq_refl); rewrite Hu1 in *; lra).
  (* y *)
  assert (Rel : 0 <= quotient_relative <= / 1024) by (rewrite quotient_relative_val, Hu1; lra).
  assert (YBe' : Rabs (Rabs q0 * quotient_relative) <= Rabs q0 * / 1024).
  { rewrite Rabs_mult, Rabs_Rabsolu, (Rabs_pos_eq quotient_relative) by lra.
    apply Rmult_le_compat_l; [apply Rabs_pos | lra]. }
  assert (YB : Rabs yb * aD <= V).
  { pose proof (RNs yb (Rabs q0 * quotient_relative) eq_refl). pose proof (Sc _ _ YBe'). rewrite Hu1 in *. lra. }
  assert (YSe : Rabs (yb + Rabs w) * aD <= 24 * V).
  { pose proof (Sc _ _ (Tri yb (Rabs w))). rewrite Rabs_Rabsolu in H. lra. }
  assert (YS : Rabs ys * aD <= 25 * V) by (pose proof (RNs ys (yb + Rabs w) eq_refl); rewrite Hu1 in *; lra).
  assert (Ye : Rabs (ys * aD) <= 25 * V) by (rewrite Rabs_mult, (Rabs_pos_eq aD) by lra; exact YS).
  assert (Y : Rabs y <= 26 * V) by (pose proof (RN_abs_up' y (ys * aD) eq_refl); rewrite Hu1 in *; lra).
  assert (XYe : Rabs (x + y) <= 35 * V + 5 * bpow radix2 1005) by (pose proof (Tri x y); lra).
  assert (XY : Rabs (RN (x + y)) <= 36 * V + 6 * bpow radix2 1005)
    by (pose proof (RN_abs_up (x + y)); rewrite Hu1 in *; lra).
  assert (F2 : Rabs quotient_test_factor <= 2).
  { rewrite quotient_test_factor_val, Rabs_pos_eq; lra. }
  assert (Le : Rabs (RN (x + y) * quotient_test_factor) <= 2 * (36 * V + 6 * bpow radix2 1005)).
  { rewrite Rabs_mult. pose proof (Rabs_pos (RN (x + y))).
    assert (Rabs (RN (x + y)) * Rabs quotient_test_factor <= Rabs (RN (x + y)) * 2)
      by (apply Rmult_le_compat_l; [apply Rabs_pos | lra]). lra. }
  pose proof (bpow_ge_0 radix2 1005).
  repeat split; try lra.
  - pose proof (Quot _ 7 ltac:(lra) Ce). lra.
  - pose proof (Quot _ 10 ltac:(lra) Qe). lra.
  - pose proof (Quot _ 13 ltac:(lra) QQe). lra.
  - pose proof (Quot _ 22 ltac:(lra) We). lra.
  - pose proof (Quot _ 24 ltac:(lra) YSe). lra.
Qed.

(** ** The twin computes the model's rounding: forwards, on bounded finite inputs. *)

(** A twin divisor read as the model's. *)
Definition divisor_R (dv : DivisorB) : Divisor :=
  {| div_hi := B2R (dhib dv); div_lo := B2R (dlob dv); div_radius := B2R (dradiusb dv);
     div_reciprocal := B2R (dreciprocalb dv); div_in_range := din_rangeb dv |}.

(** The bound of an operation's exact result, from [rq_model_bounds] (in [MB]). *)
Ltac bnd MB := apply RN_below; rewrite ?fneg_val, ?fabs_val; autorewrite with cpp_constants; clear - MB; tauto.

Lemma round_quotient_b_fwd : forall (num : EnclosureB) (dv : DivisorB),
  fin (hib num) = true -> fin (lob num) = true -> fin (radiusb num) = true ->
  fin (dhib dv) = true -> fin (dlob dv) = true -> fin (dradiusb dv) = true -> fin (dreciprocalb dv) = true ->
  Rabs (B2R (hib num)) <= bpow radix2 1000 -> Rabs (B2R (lob num)) <= bpow radix2 1000 ->
  bpow radix2 (-1000) <= Rabs (B2R (dhib dv)) <= bpow radix2 1000 ->
  Rabs (B2R (dlob dv)) <= u * Rabs (B2R (dhib dv)) ->
  Rabs (B2R (dreciprocalb dv) * B2R (dhib dv) - 1) <= u ->
  Rabs (RN (B2R (hib num) + B2R (lob num))) <= bpow radix2 1001 * Rabs (B2R (dhib dv)) ->
  0 <= B2R (radiusb num) <= bpow radix2 1005 ->
  0 <= B2R (dradiusb dv) <= Rabs (B2R (dhib dv)) ->
  fin (fst (round_quotient_b num dv)) = true /\
  B2R (fst (round_quotient_b num dv)) = qr_t (round_quotient (enc_R num) (divisor_R dv)) /\
  snd (round_quotient_b num dv) = qr_certain (round_quotient (enc_R num) (divisor_R dv)).
Proof.
  intros [nh nl En] [D d Ed R ir] Fnh Fnl FEn FD Fd FEd FR Bnh Bnl GD Ld RD NQ BEn BEd.
  cbn [hib lob radiusb dhib dlob dradiusb dreciprocalb din_rangeb] in *.
  pose proof (fbnd_two_sum 1000 1000 nh nl (conj Fnh Bnh) (conj Fnl Bnl) ltac:(zle) ltac:(zle) ltac:(zle))
    as [[FN BN] [Fn _]].
  change (Z.max 1000 1000 + 5)%Z with 1005%Z in BN.
  destruct (two_sum_b_inv nh nl Fn) as [_ [_ [_ [VN Vn]]]].
  pose proof (two_sum_lo_bound (B2R nh) (B2R nl) (binary64_B2R nh) (binary64_B2R nl)) as [_ Ln].
  rewrite <- VN, <- Vn in Ln.
  rewrite <- two_sum_hi, <- VN in NQ.
  unfold round_quotient_b, round_quotient, enc_R, divisor_R.
  cbn [hib lob radiusb dhib dlob dradiusb dreciprocalb din_rangeb hi lo radius div_hi div_lo div_radius
       div_reciprocal div_in_range].
  cbv zeta. cbn [fst snd qr_t qr_certain].
  rewrite <- VN, <- Vn. clear VN Vn.
  remember (fst (two_sum_b nh nl)) as NB eqn:ENB in *. remember (snd (two_sum_b nh nl)) as nB eqn:EnB in *.
  clear ENB EnB.
  pose proof (rq_model_bounds (B2R NB) (B2R nB) (B2R D) (B2R d) (B2R R) (B2R En) (B2R Ed) GD Ld RD BN NQ Ln BEn BEd)
    as MB.
  cbv zeta in MB.
  qfin.
  unfold fma.
  destruct (fmul_fwd NB R FN FR ltac:(bnd MB)) as [Kq0 Vq0].
  set (tq0 := fmul NB R) in *. rewrite <- Vq0 in MB |- *.
  destruct (ffma_fwd (fneg tq0) D NB ltac:(rewrite fneg_fin; exact Kq0) FD FN ltac:(bnd MB)) as [Kr1 Vr1].
  set (tr1 := ffma (fneg tq0) D NB) in *. rewrite fneg_val in Vr1. rewrite <- Vr1 in MB |- *.
  destruct (ffma_fwd (fneg tq0) d nB ltac:(rewrite fneg_fin; exact Kq0) Fd Fn ltac:(bnd MB)) as [Kr2 Vr2].
  set (tr2 := ffma (fneg tq0) d nB) in *. rewrite fneg_val in Vr2. rewrite <- Vr2 in MB |- *.
  destruct (fadd_fwd tr1 tr2 Kr1 Kr2 ltac:(bnd MB)) as [Ks Vs].
  set (ts := fadd tr1 tr2) in *. rewrite <- Vs in MB |- *.
  destruct (fmul_fwd ts R Ks FR ltac:(bnd MB)) as [Kc Vc].
  set (tc := fmul ts R) in *. rewrite <- Vc in MB |- *.
  destruct (fadd_fwd tq0 tc Kq0 Kc ltac:(bnd MB)) as [Kq Vq].
  set (tq := fadd tq0 tc) in *. rewrite <- Vq in MB |- *.
  destruct (fsub_fwd tq tq0 Kq Kq0 ltac:(bnd MB)) as [Kqq Vqq].
  set (tqq := fsub tq tq0) in *. rewrite <- Vqq in MB |- *.
  destruct (fsub_fwd tc tqq Kc Kqq ltac:(bnd MB)) as [Kw Vw].
  set (tw := fsub tc tqq) in *. rewrite <- Vw in MB |- *.
  destruct (fmul_fwd (fabs tq0) Ed ltac:(rewrite fabs_fin; exact Kq0) FEd ltac:(bnd MB)) as [Kxb Vxb].
  set (txb := fmul (fabs tq0) Ed) in *. rewrite fabs_val in Vxb. rewrite <- Vxb in MB |- *.
  destruct (fadd_fwd txb En Kxb FEn ltac:(bnd MB)) as [Kxs Vxs].
  set (txs := fadd txb En) in *. rewrite <- Vxs in MB |- *.
  destruct (fmul_fwd txs Cpp.quotient_enclosure_factor Kxs ltac:(assumption) ltac:(bnd MB)) as [Kx Vx].
  set (tx := fmul txs Cpp.quotient_enclosure_factor) in *. autorewrite with cpp_constants in Vx.
  rewrite <- Vx in MB |- *.
  destruct (fmul_fwd (fabs tq0) Cpp.quotient_relative ltac:(rewrite fabs_fin; exact Kq0) ltac:(assumption)
              ltac:(bnd MB)) as [Kyb Vyb].
  set (tyb := fmul (fabs tq0) Cpp.quotient_relative) in *. rewrite fabs_val in Vyb.
  autorewrite with cpp_constants in Vyb. rewrite <- Vyb in MB |- *.
  destruct (fadd_fwd tyb (fabs tw) Kyb ltac:(rewrite fabs_fin; exact Kw) ltac:(bnd MB)) as [Kys Vys].
  set (tys := fadd tyb (fabs tw)) in *. rewrite fabs_val in Vys. rewrite <- Vys in MB |- *.
  destruct (fmul_fwd tys (fabs D) Kys ltac:(rewrite fabs_fin; exact FD) ltac:(bnd MB)) as [Ky Vy].
  set (ty := fmul tys (fabs D)) in *. rewrite fabs_val in Vy. rewrite <- Vy in MB |- *.
  destruct (fadd_fwd tx ty Kx Ky ltac:(bnd MB)) as [Kxy Vxy].
  set (txy := fadd tx ty) in *. rewrite <- Vxy in MB |- *.
  destruct (fmul_fwd txy Cpp.quotient_test_factor Kxy ltac:(assumption) ltac:(bnd MB)) as [KL VL].
  set (tL := fmul txy Cpp.quotient_test_factor) in *. autorewrite with cpp_constants in VL.
  rewrite <- VL.
  split; [exact Kq | split; [reflexivity|]].
  rewrite (fle_val Cpp.quotient_min_magnitude (fabs NB) ltac:(assumption) ltac:(rewrite fabs_fin; exact FN)),
    (fle_val Cpp.quotient_min_magnitude (fabs tq) ltac:(assumption) ltac:(rewrite fabs_fin; exact Kq)),
    (fle_val (fabs tq) Cpp.largest_finite ltac:(rewrite fabs_fin; exact Kq) ltac:(assumption)), !fabs_val.
  autorewrite with cpp_constants.
  destruct (Rle_bool_spec Q900 (Rabs (B2R tq))) as [G|G].
  - assert (G' : half_gap_min_magnitude <= Rabs (B2R tq)) by (eapply Rle_trans; [|exact G]; apply bpow_le; lia).
    destruct (half_gap_twin tq Kq G') as [Fh Vh].
    assert (Bh : Rabs (RN (B2R (half_gap_b tq) * B2R (fabs D))) < bpow radix2 1024).
    { apply RN_below. rewrite Vh, fabs_val, Rabs_mult, Rabs_Rabsolu.
      rewrite (Rabs_pos_eq (half_gap _)) by apply half_gap_bounds.
      assert (Nq : bpow radix2 (-1022) <= Rabs (B2R tq)) by (eapply Rle_trans; [|exact G]; apply bpow_le; lia).
      pose proof (half_gap_le_u (B2R tq) Nq) as Hh.
      assert (half_gap (B2R tq) * Rabs (B2R D) <= u * Rabs (B2R tq) * Rabs (B2R D))
        by (apply Rmult_le_compat_r; [apply Rabs_pos | exact Hh]).
      assert (Rabs (B2R tq) * Rabs (B2R D) <= bpow radix2 1020) by (clear - MB; tauto).
      pose proof (Rmult_le_pos _ _ (Rabs_pos (B2R tq)) (Rabs_pos (B2R D))).
      rewrite u_val in *. lra. }
    destruct (fmul_fwd _ _ Fh ltac:(rewrite fabs_fin; exact FD) Bh) as [Fr Vr].
    rewrite (flt_val _ _ KL Fr), Vr, Vh, fabs_val. reflexivity.
  - destruct (Rle_bool Q900 (Rabs (B2R NB))), ir; reflexivity.
Qed.

(** [prepare_divisor_b] on finite parts of magnitude ≤ 2^1000 with the model's divisor in range: finite
    field by field, and the model's [prepare_divisor] (the reciprocal 1 ⊘ D is RN(1/D), finite). *)
Lemma prepare_divisor_b_fwd : forall den : EnclosureB,
  fin (hib den) = true -> fin (lob den) = true -> fin (radiusb den) = true ->
  Rabs (B2R (hib den)) <= bpow radix2 1000 -> Rabs (B2R (lob den)) <= bpow radix2 1000 ->
  div_in_range (prepare_divisor (enc_R den)) = true ->
  fin (dhib (prepare_divisor_b den)) = true /\ fin (dlob (prepare_divisor_b den)) = true /\
  fin (dradiusb (prepare_divisor_b den)) = true /\ fin (dreciprocalb (prepare_divisor_b den)) = true /\
  divisor_R (prepare_divisor_b den) = prepare_divisor (enc_R den).
Proof.
  intros [dh dl Ed] Fh Fl FE Bh Bl G. cbn [hib lob radiusb] in *.
  pose proof (fbnd_two_sum 1000 1000 dh dl (conj Fh Bh) (conj Fl Bl) ltac:(zle) ltac:(zle) ltac:(zle))
    as [[FD _] [Fd _]].
  destruct (two_sum_b_inv dh dl Fd) as [_ [_ [_ [VD Vd]]]].
  unfold prepare_divisor, enc_R in G. cbn [div_in_range hi lo radius hib lob radiusb] in G.
  qfin.
  assert (Ir : (fle Cpp.divisor_min_magnitude (fabs (fst (two_sum_b dh dl))) &&
                fle (fabs (fst (two_sum_b dh dl))) Cpp.divisor_max_magnitude)%bool = true).
  { rewrite (fle_val Cpp.divisor_min_magnitude _ ltac:(assumption) ltac:(rewrite fabs_fin; exact FD)),
      (fle_val _ Cpp.divisor_max_magnitude ltac:(rewrite fabs_fin; exact FD) ltac:(assumption)), fabs_val, VD.
    autorewrite with cpp_constants. exact G. }
  assert (GD : divisor_min_magnitude <= Rabs (fst (two_sum (B2R dh) (B2R dl))) <= divisor_max_magnitude).
  { apply andb_prop in G. destruct G as [G1 G2]. revert G1 G2.
    destruct (Rle_bool_spec divisor_min_magnitude (Rabs (fst (two_sum (B2R dh) (B2R dl))))); [|intros; discriminate].
    destruct (Rle_bool_spec (Rabs (fst (two_sum (B2R dh) (B2R dl)))) divisor_max_magnitude); [|intros; discriminate].
    intros _ _. split; assumption. }
  assert (DP : 0 < Rabs (fst (two_sum (B2R dh) (B2R dl)))) by (apply Rlt_le_trans with divisor_min_magnitude; [unfold divisor_min_magnitude; apply bpow_gt_0 | exact (proj1 GD)]).
  assert (Dnz : B2R (fst (two_sum_b dh dl)) <> 0) by (rewrite VD; intros Z; rewrite Z, Rabs_R0 in DP; lra).
  assert (BR : Rabs (RN (B2R one_f / B2R (fst (two_sum_b dh dl)))) < bpow radix2 1024).
  { apply RN_below. rewrite one_f_val, VD. unfold Rdiv. rewrite Rmult_1_l, Rabs_inv.
    apply Rle_trans with (/ divisor_min_magnitude); [apply Rinv_le_contravar; [unfold divisor_min_magnitude; apply bpow_gt_0 | exact (proj1 GD)]|].
    unfold divisor_min_magnitude. rewrite <- bpow_opp. apply bpow_le. lia. }
  destruct (fdiv_fwd one_f (fst (two_sum_b dh dl)) ltac:(assumption) Dnz BR) as [FR VR].
  unfold prepare_divisor_b, prepare_divisor, divisor_R, enc_R. cbv zeta.
  cbn [hib lob radiusb hi lo radius dhib dlob dradiusb dreciprocalb din_rangeb].
  rewrite Ir, G. repeat split; try assumption.
  rewrite VR, one_f_val, VD, Vd. reflexivity.
Qed.

(** ** Main theorem: the twin certifies on [round_quotient_live]'s class, with t = RN(X/Y). *)

(** The centres X = num.hi + num.lo, Y = den.hi + den.lo and Q = X/Y. *)
Definition rq_center (e : EnclosureB) : R := B2R (hib e) + B2R (lob e).
Definition rq_quotient (num den : EnclosureB) : R := rq_center num / rq_center den.

(** The class: finite parts, hi and lo of magnitude ≤ 2^1000, radii ≥ 0, and [round_quotient_live]'s class
    on Q = X/Y (the divisor's range, 2^-900 ≤ |X|, 2^-900 ≤ |Q| ≤ 2^1000, and Q's distance from the
    midpoints' test). *)
Definition quotient_live_class (num den : EnclosureB) : Prop :=
  fin (hib num) = true /\ fin (lob num) = true /\ fin (radiusb num) = true /\
  fin (hib den) = true /\ fin (lob den) = true /\ fin (radiusb den) = true /\
  Rabs (B2R (hib num)) <= bpow radix2 1000 /\ Rabs (B2R (lob num)) <= bpow radix2 1000 /\
  Rabs (B2R (hib den)) <= bpow radix2 1000 /\ Rabs (B2R (lob den)) <= bpow radix2 1000 /\
  0 <= B2R (radiusb num) /\ 0 <= B2R (radiusb den) /\
  divisor_min_magnitude <= Rabs (rq_center den) <= divisor_max_magnitude /\
  Q900 <= Rabs (rq_center num) /\
  Q900 <= Rabs (rq_quotient num den) <= bpow radix2 1000 /\
  Rabs (rq_quotient num den - RN (rq_quotient num den)) +
    (1 + / 256) * ((B2R (radiusb num) + Rabs (rq_quotient num den) * B2R (radiusb den)) / Rabs (rq_center den)) +
    / 2 ^ 97 * Rabs (rq_quotient num den)
    < half_gap (RN (rq_quotient num den)).

Theorem round_quotient_live_b : forall num den : EnclosureB, quotient_live_class num den ->
  snd (round_quotient_b num (prepare_divisor_b den)) = true /\
  fin (fst (round_quotient_b num (prepare_divisor_b den))) = true /\
  B2R (fst (round_quotient_b num (prepare_divisor_b den))) = RN (rq_quotient num den).
Proof.
  intros num den C. unfold quotient_live_class, rq_quotient, rq_center in *.
  destruct C as [Fnh [Fnl [FEn [Fdh [Fdl [FEd [Bnh [Bnl [Bdh [Bdl [PEn [PEd [GY [GX [GQ Hyp]]]]]]]]]]]]]]].
  set (X := B2R (hib num) + B2R (lob num)) in *. set (Y := B2R (hib den) + B2R (lob den)) in *.
  destruct (round_quotient_live (enc_R num) (enc_R den) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _)
              (binary64_B2R _) (binary64_B2R _) (binary64_B2R _) PEn PEd GY GX GQ Hyp) as [MC MT].
  assert (Gd : div_in_range (prepare_divisor (enc_R den)) = true).
  { unfold prepare_divisor. cbn [div_in_range hi lo enc_R]. rewrite two_sum_hi. fold Y.
    rewrite Rle_bool_true by (apply RN_abs_ge; [lia | apply GY]).
    rewrite Rle_bool_true by (apply RN_abs_le; [lia | apply GY]). reflexivity. }
  destruct (prepare_divisor_b_fwd den Fdh Fdl FEd Bdh Bdl Gd) as [FD [Fd [FE [FR ED]]]].
  destruct (prepare_divisor_spec (enc_R den) (binary64_B2R _) (binary64_B2R _) Gd)
    as [_ [_ [_ [LD [RE [GD RD]]]]]].
  set (dv := prepare_divisor_b den) in *.
  assert (DY : div_hi (prepare_divisor (enc_R den)) = RN Y) by reflexivity.
  rewrite <- ED in LD, RE, GD, RD, DY, MC, MT. cbn [div_hi div_lo div_radius div_reciprocal divisor_R] in LD, RE, GD, RD, DY.
  cbn [radius enc_R] in RE.
  set (D := B2R (dhib dv)) in *.
  (* the quotient's scale and the radii, from the class *)
  pose proof u_pos as Hu. assert (Hu1 : u = / 9007199254740992) by exact u_val.
  assert (YP : 0 < Rabs Y)
    by (apply Rlt_le_trans with divisor_min_magnitude; [unfold divisor_min_magnitude; apply bpow_gt_0 | exact (proj1 GY)]).
  assert (Ynz : Y <> 0) by (intros Z; rewrite Z, Rabs_R0 in YP; lra).
  assert (AX : Rabs X = Rabs (X / Y) * Rabs Y) by (rewrite <- Rabs_mult; f_equal; field; exact Ynz).
  assert (NormY : bpow radix2 (-1022) <= Rabs Y)
    by (apply Rle_trans with divisor_min_magnitude; [unfold divisor_min_magnitude; apply bpow_le; lia | exact (proj1 GY)]).
  assert (NormX : bpow radix2 (-1022) <= Rabs X) by exact (Rle_trans _ _ _ Q900_normal GX).
  assert (NormQ : bpow radix2 (-1022) <= Rabs (X / Y)) by exact (Rle_trans _ _ _ Q900_normal (proj1 GQ)).
  pose proof (Rabs_close' _ _ _ (RN_rel Y NormY)) as DY1. rewrite <- DY in DY1. fold D in DY1.
  pose proof (Rabs_close _ _ _ (RN_rel X NormX)) as NX1.
  assert (QY : Rabs (X / Y) * Rabs Y <= bpow radix2 1000 * Rabs Y) by (apply Rmult_le_compat_r; [lra | apply GQ]).
  set (P := bpow radix2 1000) in *.
  assert (PP : 0 <= P) by apply bpow_ge_0.
  assert (YD : Rabs Y <= (1 + 2 * u) * Rabs D) by (rewrite Hu1 in *; lra).
  assert (NQ : Rabs (RN X) <= bpow radix2 1001 * Rabs D).
  { assert (E1001 : bpow radix2 1001 = 2 * P)
      by (unfold P; replace 1001%Z with (1 + 1000)%Z by lia; rewrite bpow_plus; reflexivity).
    assert (P * Rabs Y <= P * ((1 + 2 * u) * Rabs D)) by (apply Rmult_le_compat_l; [exact PP | exact YD]).
    pose proof (Rmult_le_pos _ _ PP (Rabs_pos D)).
    rewrite E1001. rewrite Hu1 in *. lra. }
  assert (NRQ : bpow radix2 (-1022) <= Rabs (RN (X / Y))).
  { apply RN_abs_ge; [lia | exact NormQ]. }
  pose proof (half_gap_le_u _ NRQ) as Hh.
  pose proof (Rabs_close _ _ _ (RN_rel (X / Y) NormQ)) as RQ.
  set (Kr := (B2R (radiusb num) + Rabs (X / Y) * B2R (radiusb den)) / Rabs Y) in Hyp.
  assert (KrY : Kr * Rabs Y = B2R (radiusb num) + Rabs (X / Y) * B2R (radiusb den)) by (unfold Kr; field; lra).
  assert (RN0 : 0 <= Rabs (X / Y) * B2R (radiusb den)) by (apply Rmult_le_pos; [apply Rabs_pos | exact PEd]).
  assert (KrP : 0 <= Kr).
  { unfold Kr. apply Rmult_le_pos; [lra | apply Rlt_le, Rinv_0_lt_compat; exact YP]. }
  pose proof (Rabs_pos (X / Y - RN (X / Y))).
  assert (0 <= / 2 ^ 97 * Rabs (X / Y))
    by (apply Rmult_le_pos; [apply Rlt_le, Rinv_0_lt_compat, pow_lt; lra | apply Rabs_pos]).
  assert (Kr2 : Kr <= 2 * u * Rabs (X / Y)).
  { pose proof (Rabs_pos (X / Y)). rewrite Hu1 in *. lra. }
  assert (KrY2 : Kr * Rabs Y <= 2 * u * Rabs (X / Y) * Rabs Y) by (apply Rmult_le_compat_r; lra).
  assert (BX : Rabs X <= 2 * P).
  { unfold X. eapply Rle_trans; [apply Rabs_triang | lra]. }
  assert (BEn : 0 <= B2R (radiusb num) <= bpow radix2 1005).
  { split; [exact PEn|]. replace 1005%Z with (5 + 1000)%Z by lia. rewrite bpow_plus. fold P.
    change (bpow radix2 5) with 32. rewrite Hu1 in *. lra. }
  assert (BEd : 0 <= B2R (radiusb den) <= Rabs D).
  { split; [exact PEd|]. apply Rmult_le_reg_l with (Rabs (X / Y)); [pose proof Q900_pos; destruct GQ; lra|].
    assert (Rabs (X / Y) * (2 * u * Rabs Y) <= Rabs (X / Y) * Rabs D)
      by (apply Rmult_le_compat_l; [apply Rabs_pos | rewrite Hu1 in *; lra]).
    rewrite Hu1 in *. lra. }
  rewrite <- RE in BEd.
  destruct (round_quotient_b_fwd num dv Fnh Fnl FEn FD Fd FE FR Bnh Bnl GD LD RD NQ BEn BEd) as [Ft [Vt Ct]].
  rewrite Ct, Vt. split; [exact MC | split; [exact Ft | exact MT]].
Qed.

(** ** Exact enclosures (radius 0): the twin certifies whenever X/Y is not within 2^-97|X/Y| of the points
    RN(X/Y) ± half_gap(RN(X/Y)). *)
Corollary round_quotient_live_exact_b : forall nh nl dh dl : float,
  fin nh = true -> fin nl = true -> fin dh = true -> fin dl = true ->
  Rabs (B2R nh) <= bpow radix2 1000 -> Rabs (B2R nl) <= bpow radix2 1000 ->
  Rabs (B2R dh) <= bpow radix2 1000 -> Rabs (B2R dl) <= bpow radix2 1000 ->
  let X := B2R nh + B2R nl in
  let Y := B2R dh + B2R dl in
  divisor_min_magnitude <= Rabs Y <= divisor_max_magnitude ->
  Q900 <= Rabs X ->
  Q900 <= Rabs (X / Y) <= bpow radix2 1000 ->
  Rabs (X / Y - RN (X / Y)) + / 2 ^ 97 * Rabs (X / Y) < half_gap (RN (X / Y)) ->
  let r := round_quotient_b {| hib := nh; lob := nl; radiusb := fzero |}
                            (prepare_divisor_b {| hib := dh; lob := dl; radiusb := fzero |}) in
  snd r = true /\ fin (fst r) = true /\ B2R (fst r) = RN (X / Y).
Proof.
  intros nh nl dh dl Fnh Fnl Fdh Fdl Bnh Bnl Bdh Bdl X Y GY GX GQ H r.
  apply (round_quotient_live_b {| hib := nh; lob := nl; radiusb := fzero |}
                               {| hib := dh; lob := dl; radiusb := fzero |}).
  unfold quotient_live_class, rq_quotient, rq_center; cbn [hib lob radiusb]; change (B2R fzero) with 0.
  repeat match goal with |- _ /\ _ => split; [first [assumption | reflexivity | lra] |] end.
  unfold Rdiv. rewrite Rmult_0_r, Rplus_0_l, Rmult_0_l, Rmult_0_r, Rplus_0_r. exact H.
Qed.

(** ** The class is not empty: QuotientLiveness.v's computed example 1/3 ([round_quotient_b_third]) is in it,
    so the twin's certification there follows from [round_quotient_live_exact_b], not only from computation.
    RN(1/3) = 6004799503160661·2^-54 = (2^54 − 1)/(3·2^54) is 2^-54/3 below 1/3 and half_gap = 2^-55 (read from
    the twin's [half_gap_b] through [half_gap_twin]): 2^-54/3 + 2^-97/3 < 2^-55. *)

Lemma small_in_range : forall x, bpow radix2 (-2) <= Rabs x <= 4 ->
  Q900 <= Rabs x /\ divisor_min_magnitude <= Rabs x <= divisor_max_magnitude /\ Rabs x <= bpow radix2 1000.
Proof.
  intros x [L H].
  assert (Q900 <= bpow radix2 (-2)) by (apply bpow_le; lia).
  assert (divisor_min_magnitude <= bpow radix2 (-2)) by (apply bpow_le; lia).
  assert (4 <= bpow radix2 1000) by (change 4 with (bpow radix2 2); apply bpow_le; lia).
  unfold divisor_max_magnitude. repeat split; lra.
Qed.

(** RN(1/3) = (2^54 − 1)/(3·2^54) (the double below 1/3, of bits 0x3fd5555555555555) and its half gap 2^-55. *)
Lemma rn_third : RN (1 / 3) = 18014398509481983 / 54043195528445952 /\ half_gap (RN (1 / 3)) = / 36028797018963968.
Proof.
  set (q3 := of_bits 4599676419421066581).
  assert (Fq3 : fin q3 = true) by (vm_compute; reflexivity).
  assert (Vq3 : B2R q3 = 18014398509481983 / 54043195528445952) by (unfold q3; float_real (of_bits 4599676419421066581); lra).
  assert (Gq3 : half_gap_min_magnitude <= Rabs (B2R q3)).
  { rewrite Vq3, Rabs_pos_eq by lra. apply Rle_trans with (bpow radix2 (-2)); [apply bpow_le; lia|].
    simpl bpow. lra. }
  destruct (half_gap_twin q3 Fq3 Gq3) as [_ Hg].
  assert (Hg' : half_gap (B2R q3) = / 36028797018963968).
  { rewrite <- Hg. unfold q3. float_real (half_gap_b (of_bits 4599676419421066581)). lra. }
  assert (RQ : RN (1 / 3) = B2R q3).
  { apply RN_of_close; [apply binary64_B2R|]. rewrite Hg', Vq3, Rabs_pos_eq; lra. }
  rewrite RQ, Hg'. split; [exact Vq3 | reflexivity].
Qed.

Lemma round_quotient_b_third_live :
  let r := round_quotient_b {| hib := of_bits 4607182418800017408; lob := fzero; radiusb := fzero |}
             (prepare_divisor_b {| hib := of_bits 4613937818241073152; lob := fzero; radiusb := fzero |}) in
  snd r = true /\ fin (fst r) = true /\ B2R (fst r) = RN (1 / 3).
Proof.
  assert (V1 : B2R (of_bits 4607182418800017408) = 1) by (float_real (of_bits 4607182418800017408); lra).
  assert (V3 : B2R (of_bits 4613937818241073152) = 3) by (float_real (of_bits 4613937818241073152); lra).
  destruct rn_third as [RQ3 HG3].
  assert (X3 : (B2R (of_bits 4607182418800017408) + B2R fzero) / (B2R (of_bits 4613937818241073152) + B2R fzero) = 1 / 3)
    by (rewrite V1, V3; change (B2R fzero) with 0; field).
  destruct (small_in_range 1) as [GX _]; [rewrite Rabs_R1; simpl bpow; lra|].
  destruct (small_in_range 3) as [_ [GY _]]; [rewrite Rabs_pos_eq by lra; simpl bpow; lra|].
  destruct (small_in_range (1 / 3)) as [GQ1 [_ GQ2]]; [rewrite Rabs_pos_eq by lra; simpl bpow; lra|].
  assert (B : forall x, Rabs x <= 4 -> Rabs x <= bpow radix2 1000).
  { intros x Hx. eapply Rle_trans; [exact Hx|]. change 4 with (bpow radix2 2). apply bpow_le. lia. }
  pose proof (round_quotient_live_exact_b (of_bits 4607182418800017408) fzero (of_bits 4613937818241073152) fzero
    ltac:(vm_compute; reflexivity) eq_refl ltac:(vm_compute; reflexivity) eq_refl
    ltac:(apply B; rewrite V1, Rabs_R1; lra) ltac:(apply B; change (B2R fzero) with 0; rewrite Rabs_R0; lra)
    ltac:(apply B; rewrite V3, Rabs_pos_eq; lra) ltac:(apply B; change (B2R fzero) with 0; rewrite Rabs_R0; lra))
    as L.
  cbv zeta in L |- *. rewrite X3 in L.
  apply L; clear L.
  - rewrite V3. change (B2R fzero) with 0. rewrite Rplus_0_r. exact GY.
  - rewrite V1. change (B2R fzero) with 0. rewrite Rplus_0_r. exact GX.
  - split; assumption.
  - rewrite HG3, RQ3, Rabs_pos_eq, (Rabs_pos_eq (1 / 3)) by lra. lra.
Qed.

(** The near-midpoint example of [near_midpoint_threshold] at k = 513: X = (1 + 2^-52) + (−(2^53 − 513)·2^-106),
    Y = 1, RN(X) = 1 + 2^-52 with half_gap 2^-53; X is 513·2^-106 above the midpoint and 2^-97·|X| < 513·2^-106,
    so it is in the class (the twin certifies from k = 290 on: the theorem's slack is within a factor 1.8). *)
Lemma round_quotient_b_near_midpoint_live :
  let nh := of_bits 4607182418800017409 in
  let nl := of_bits (13591863675404156928 - 513) in
  let r := round_quotient_b {| hib := nh; lob := nl; radiusb := fzero |}
             (prepare_divisor_b {| hib := of_bits 4607182418800017408; lob := fzero; radiusb := fzero |}) in
  snd r = true /\ fin (fst r) = true /\ B2R (fst r) = B2R nh.
Proof.
  cbv zeta.
  assert (V1 : B2R (of_bits 4607182418800017408) = 1) by (float_real (of_bits 4607182418800017408); lra).
  set (nh := of_bits 4607182418800017409). set (nl := of_bits (13591863675404156928 - 513)).
  assert (Fh : fin nh = true) by (vm_compute; reflexivity).
  assert (Fl : fin nl = true) by (vm_compute; reflexivity).
  assert (Vh : B2R nh = 4503599627370497 / 4503599627370496) by (unfold nh; float_real (of_bits 4607182418800017409); lra).
  assert (Vl : B2R nl = - (9007199254740992 - 513) / 81129638414606681695789005144064).
  { unfold nl. float_real (of_bits (13591863675404156928 - 513)). lra. }
  assert (Gh : half_gap_min_magnitude <= Rabs (B2R nh)).
  { rewrite Vh, Rabs_pos_eq by lra. apply Rle_trans with (bpow radix2 (-2)); [apply bpow_le; lia|].
    simpl bpow. lra. }
  destruct (half_gap_twin nh Fh Gh) as [_ Hg].
  assert (Hg' : half_gap (B2R nh) = / 9007199254740992).
  { rewrite <- Hg. unfold nh. float_real (half_gap_b (of_bits 4607182418800017409)). lra. }
  set (X := B2R nh + B2R nl).
  assert (XV : X = 4503599627370497 / 4503599627370496 - (9007199254740992 - 513) / 81129638414606681695789005144064)
    by (unfold X; rewrite Vh, Vl; field).
  assert (RQ : RN X = B2R nh).
  { apply RN_of_close; [apply binary64_B2R|]. rewrite Hg'.
    replace (X - B2R nh) with (B2R nl) by (unfold X; ring). rewrite Vl, Rabs_left by lra. lra. }
  assert (XY : (B2R nh + B2R nl) / (B2R (of_bits 4607182418800017408) + B2R fzero) = X)
    by (rewrite V1; change (B2R fzero) with 0; unfold X; field).
  destruct (small_in_range X) as [GX [_ GQ2]]; [rewrite XV, Rabs_pos_eq by lra; simpl bpow; lra|].
  destruct (small_in_range 1) as [_ [GY _]]; [rewrite Rabs_R1; simpl bpow; lra|].
  assert (B : forall x, Rabs x <= 4 -> Rabs x <= bpow radix2 1000).
  { intros x Hx. eapply Rle_trans; [exact Hx|]. change 4 with (bpow radix2 2). apply bpow_le. lia. }
  pose proof (round_quotient_live_exact_b nh nl (of_bits 4607182418800017408) fzero
    Fh Fl ltac:(vm_compute; reflexivity) eq_refl
    ltac:(apply B; rewrite Vh, Rabs_pos_eq; lra) ltac:(apply B; rewrite Vl, Rabs_left; lra)
    ltac:(apply B; rewrite V1, Rabs_R1; lra) ltac:(apply B; change (B2R fzero) with 0; rewrite Rabs_R0; lra))
    as L.
  cbv zeta in L. rewrite XY, RQ in L.
  apply L; clear L.
  - rewrite V1. change (B2R fzero) with 0. rewrite Rplus_0_r. exact GY.
  - exact GX.
  - split; assumption.
  - rewrite Hg'. replace (X - B2R nh) with (B2R nl) by (unfold X; ring). rewrite Vl, Rabs_left by lra.
    rewrite XV, Rabs_pos_eq by lra. lra.
Qed.

(** ** At the call site: [fast_answer_from_b] (plane/ray_plane_stages.hpp's [fast_answer_from], the stage-2
    answer of the ray–plane query, which rounds t by [round_quotient(num, prepare_divisor(den))]) on stage-2
    enclosures in the class: its t is RN(X/Y), finite, and it is certain exactly when both signs are — the
    quotient rounding never makes the answer uncertain there. *)
Corollary fast_answer_from_live_b : forall (df nf : Z) (den num : EnclosureB),
  quotient_live_class num den ->
  let a := fast_answer_from_b df nf den num in
  fin (fst (fst (fst a))) = true /\ B2R (fst (fst (fst a))) = RN (rq_quotient num den) /\
  snd (fst a) = (certain_lane (first_certain_lanes_b df (enclosure_sign_lanes_b den)) &&
                 certain_lane (first_certain_lanes_b nf (enclosure_sign_lanes_b num)))%bool.
Proof.
  intros df nf den num L a. destruct (round_quotient_live_b num den L) as [C [F T]].
  destruct (fast_answer_from_b_parts df nf den num) as [E1 [_ E3]].
  fold a in E1, E3. rewrite E1, E3, C, andb_true_r. split; [exact F | split; [exact T | reflexivity]].
Qed.
