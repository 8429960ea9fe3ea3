(** * Liveness of the quotient rounding (kernel/src/core/quotient_rounding.hpp: [prepare_divisor],
    [round_quotient]).

    [round_quotient_sound] (QuotientRounding.v) says a certified t is RN(num/den); a rounding that never
    certified would satisfy it.  Here the converse, on a stated class: for enclosures (hi, lo, radius) of
    num and den with centres X = n.hi + n.lo, Y = d.hi + d.lo and Q = X/Y in range
    (2^-1000 ≤ |Y| ≤ 2^1000 as the divisor guard requires, 2^-900 ≤ |X|, 2^-900 ≤ |Q| ≤ 2^1000),
    [round_quotient_live]: the rounding certifies, with t = RN(Q), whenever

        |Q − RN(Q)| + (1 + 2^-8)·(E_n + |Q|·E_d)/|Y| + 2^-97·|Q| < half_gap(RN(Q)),

    i.e. Q is farther than (1 + 2^-8)(E_n + |Q| E_d)/|Y| + 2^-97|Q| from the two points RN(Q) ± half_gap(RN(Q))
    (the midpoints between RN(Q) and its neighbours, except at a power of two, where the midpoint above is
    twice as far as the point the test uses).  2^-97|Q| = 512u²|Q| ≤ 512u·ulp(Q) is the test's own slack
    (its factor 1 + 2^-45, the constant 2^-101 = 32u² and the residual's 23u²).
    [round_quotient_live_exact]: with exact enclosures (radius 0), it certifies whenever Q is not within
    2^-97|Q| of those points.  Both are stated over QuotientRounding.v's [round_quotient]/[prepare_divisor];
    the end of this file runs the twin [round_quotient_b] on concrete enclosures by computation
    ([round_quotient_b_third], [near_midpoint_threshold]: not vacuous, and the constant within a factor 1.8
    of the test's own threshold); QuotientLivenessTwin.v states both theorems over the twin
    ([round_quotient_live_b], [round_quotient_live_exact_b]).

    The proof reads [round_quotient_sound]'s derivation forwards: the residual analysis
    ([quotient_residuals_q0], the same as QuotientRounding.v's [quotient_residuals] with the guard on q0
    instead of q, since here q is the conclusion) puts q0 + c within 25u²|Q| of Q, so q = RN(Q); the
    computed test's left side is at most (1 + 2^-45 + 7u) times its real value and its right side h ⊗ |D| at
    least (1 − u)·h·|D|. *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core Relative Pff2Flocq.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated QuotientRounding FloatCore PlaneTwins PlaneQueryTwins.
Open Scope R_scope.

(** [quotient_residuals] with the guard |q0| ≥ 2^-901 in place of |q| ≥ 2^-900. *)
Lemma quotient_residuals_q0 : forall N n D d R,
  binary64 N -> binary64 n -> binary64 D -> binary64 d ->
  Rabs n <= u * Rabs N -> Rabs d <= u * Rabs D ->
  Q900 <= Rabs N -> D <> 0 -> Rabs (R * D - 1) <= u ->
  let q0 := RN (N * R) in
  Q900 <= 2 * Rabs q0 ->
  let rr := RN (fma (- q0) D N + fma (- q0) d n) in
  let c := RN (rr * R) in
  residual_facts N n D d q0 rr c.
Proof.
  intros N n D d R BN Bn BD Bd Ln Ld GN Dnz RD.
  pose proof (quotient_residuals_gen N n D d R BN Bn BD Bd Ln Ld GN Dnz RD) as G. cbv zeta in G |- *.
  intros Gq0. apply G.
  revert Gq0. generalize (RN (N * R)) (RN (RN (fma (- RN (N * R)) D N + fma (- RN (N * R)) d n) * R)).
  intros q0 c Gq0. pose proof (Rabs_pos D) as PD. pose proof (Rabs_pos c) as PC.
  assert (Q900 * Rabs D <= 2 * Rabs q0 * Rabs D) by (apply Rmult_le_compat_r; lra).
  pose proof (Rmult_le_pos _ _ PC PD). lra.
Qed.

Lemma RN_up : forall x, 0 <= x -> RN x <= (1 + u) * x + eta.
Proof. intros x H. pose proof (RN_err x) as E. rewrite (Rabs_pos_eq x) in E by exact H. apply Rabs_le_inv in E. lra. Qed.

Lemma RN_sum_up : forall a b, binary64 a -> binary64 b -> 0 <= a + b -> RN (a + b) <= (1 + u) * (a + b).
Proof. intros a b Ba Bb H. pose proof (RN_plus_err a b Ba Bb) as E. rewrite (Rabs_pos_eq (a + b)) in E by exact H.
  apply Rabs_le_inv in E. lra. Qed.

Lemma RN_down : forall x, 0 <= x -> (1 - u) * x - eta <= RN x.
Proof. intros x H. pose proof (RN_err x) as E. rewrite (Rabs_pos_eq x) in E by exact H. apply Rabs_le_inv in E. lra. Qed.

(** Relative error without η in the normal range. *)
Lemma RN_rel : forall x, bpow radix2 (-1022) <= Rabs x -> Rabs (RN x - x) <= u * Rabs x.
Proof.
  intros x Hx. pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) _ Hx) as E.
  rewrite half_bpow_52 in E. exact E.
Qed.

Lemma RN_abs_ge : forall x k, (-1074 <= k)%Z -> bpow radix2 k <= Rabs x -> bpow radix2 k <= Rabs (RN x).
Proof.
  intros x k Hk H. rewrite <- RN_abs, <- (RN_binary64 (bpow radix2 k)) by (apply binary64_bpow; lia).
  now apply RN_le.
Qed.

Lemma RN_abs_le : forall x k, (-1074 <= k)%Z -> Rabs x <= bpow radix2 k -> Rabs (RN x) <= bpow radix2 k.
Proof.
  intros x k Hk H. rewrite <- RN_abs, <- (RN_binary64 (bpow radix2 k)) by (apply binary64_bpow; lia).
  now apply RN_le.
Qed.

Lemma bpow_1000_largest : bpow radix2 1000 <= largest_finite.
Proof.
  unfold largest_finite. replace 1000%Z with (29 + 971)%Z by lia. rewrite bpow_plus.
  apply Rmult_le_compat_r; [apply bpow_ge_0|]. simpl. lra.
Qed.

Lemma Rabs_3 : forall a b c, Rabs (a - b - c) <= Rabs a + Rabs b + Rabs c.
Proof.
  intros a b c. unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
  pose proof (Rabs_triang a (- b)) as T. rewrite Rabs_Ropp in T. lra.
Qed.

(** ** Main theorem (the model): the rounding certifies, with t = RN(X/Y), when X/Y is far enough from the
    points RN(X/Y) ± half_gap(RN(X/Y)). *)
Theorem round_quotient_live : forall n d : Enclosure,
  binary64 (hi n) -> binary64 (lo n) -> binary64 (radius n) ->
  binary64 (hi d) -> binary64 (lo d) -> binary64 (radius d) ->
  0 <= radius n -> 0 <= radius d ->
  divisor_min_magnitude <= Rabs (hi d + lo d) <= divisor_max_magnitude ->
  Q900 <= Rabs (hi n + lo n) ->
  Q900 <= Rabs ((hi n + lo n) / (hi d + lo d)) <= bpow radix2 1000 ->
  Rabs ((hi n + lo n) / (hi d + lo d) - RN ((hi n + lo n) / (hi d + lo d))) +
    (1 + / 256) * ((radius n + Rabs ((hi n + lo n) / (hi d + lo d)) * radius d) / Rabs (hi d + lo d)) +
    / 2 ^ 97 * Rabs ((hi n + lo n) / (hi d + lo d))
    < half_gap (RN ((hi n + lo n) / (hi d + lo d))) ->
  qr_certain (round_quotient n (prepare_divisor d)) = true /\
  qr_t (round_quotient n (prepare_divisor d)) = RN ((hi n + lo n) / (hi d + lo d)).
Proof.
  intros [nh nl En] [dh dl Ed] Bnh Bnl BEn Bdh Bdl BEd PEn PEd [GY1 GY2] GX [GQ1 GQ2] Hyp.
  cbn [hi lo radius] in *.
  remember (nh + nl) as X eqn:EX. remember (dh + dl) as Y eqn:EY.
  remember (X / Y) as Q eqn:EQ.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof Q900_pos as HQ9.
  assert (Hu1 : u < / 1024) by (rewrite u_val; lra).
  assert (YP : 0 < Rabs Y) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact GY1]).
  assert (Ynz : Y <> 0) by (intros Z; rewrite Z, Rabs_R0 in YP; lra).
  assert (XQY : X = Q * Y) by (rewrite EQ; field; exact Ynz).
  assert (AX : Rabs X = Rabs Q * Rabs Y) by (rewrite XQY; apply Rabs_mult).
  assert (Norm : forall z, Q900 <= Rabs z -> bpow radix2 (-1022) <= Rabs z).
  { intros z Hz. eapply Rle_trans; [|exact Hz]. apply bpow_le. lia. }
  assert (NormY : bpow radix2 (-1022) <= Rabs Y).
  { eapply Rle_trans; [|exact GY1]. apply bpow_le. lia. }
  (* the numerator's double-double *)
  pose proof (two_sum_exact nh nl Bnh Bnl) as XN.
  destruct (two_sum_lo_bound nh nl Bnh Bnl) as [_ LN].
  pose proof (binary64_two_sum_hi nh nl) as BN.
  pose proof (binary64_two_sum_lo nh nl) as BNlo.
  assert (NX : fst (two_sum nh nl) = RN X) by (rewrite EX; apply two_sum_hi).
  set (N := fst (two_sum nh nl)) in *. set (Nlo := snd (two_sum nh nl)) in *.
  assert (GN : Q900 <= Rabs N) by (rewrite NX; apply RN_abs_ge; [lia | exact GX]).
  pose proof (RN_rel X (Norm X GX)) as EN. rewrite <- NX in EN.
  (* the divisor is in range *)
  assert (Gd : div_in_range (prepare_divisor {| hi := dh; lo := dl; radius := Ed |}) = true).
  { unfold prepare_divisor. cbn [div_in_range hi lo]. rewrite two_sum_hi, <- EY.
    rewrite Rle_bool_true by (apply RN_abs_ge; [lia | exact GY1]).
    rewrite Rle_bool_true by (apply RN_abs_le; [lia | exact GY2]). reflexivity. }
  pose proof (prepare_divisor_spec {| hi := dh; lo := dl; radius := Ed |} Bdh Bdl Gd)
    as [BD [BDlo [XD [LD [ED [[GD1 GD2] RD]]]]]].
  cbn [hi lo radius] in XD, ED.
  assert (DY : div_hi (prepare_divisor {| hi := dh; lo := dl; radius := Ed |}) = RN Y).
  { unfold prepare_divisor. cbn [div_hi hi lo]. rewrite two_sum_hi, <- EY. reflexivity. }
  set (dv := prepare_divisor {| hi := dh; lo := dl; radius := Ed |}) in *.
  unfold round_quotient. cbn [hi lo radius qr_t qr_certain].
  fold N Nlo. rewrite Gd, ED.
  set (D := div_hi dv) in *. set (Dlo := div_lo dv) in *. set (R := div_reciprocal dv) in *.
  rewrite <- EY in XD.
  assert (DP : 0 < Rabs D) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact GD1]).
  assert (Dnz : D <> 0) by (intros Z; rewrite Z, Rabs_R0 in DP; lra).
  pose proof (RN_rel Y NormY) as EDY. rewrite <- DY in EDY.
  set (aD := Rabs D) in *. set (aY := Rabs Y) in *. set (aQ := Rabs Q) in *.
  assert (aD1 : aD <= (1 + u) * aY) by (pose proof (Rabs_close _ _ _ EDY); unfold aD, aY in *; lra).
  assert (aD2 : (1 - u) * aY <= aD) by (pose proof (Rabs_close' _ _ _ EDY); unfold aD, aY in *; lra).
  (* q0 = RN(N R) is at least 2^-901 *)
  set (t0 := N * R).
  assert (T0 : (1 - u) * Rabs N <= Rabs t0 * aD).
  { unfold aD. rewrite <- Rabs_mult.
    assert (Rabs (t0 * D - N) <= u * Rabs N).
    { unfold t0. replace (N * R * D - N) with (N * (R * D - 1)) by ring. rewrite Rabs_mult, Rmult_comm.
      apply Rmult_le_compat_r; [apply Rabs_pos | exact RD]. }
    pose proof (Rabs_close' _ _ _ H). lra. }
  assert (NX1 : (1 - u) * Rabs X <= Rabs N) by (pose proof (Rabs_close' _ _ _ EN); lra).
  assert (QD : aQ * aD <= aQ * ((1 + u) * aY)) by (apply Rmult_le_compat_l; [apply Rabs_pos | exact aD1]).
  assert (T0Q : (1 - u) * (1 - u) / (1 + u) * aQ <= Rabs t0).
  { apply Rmult_le_reg_r with aD; [exact DP|].
    assert (0 < 1 + u) by lra.
    apply Rle_trans with ((1 - u) * (1 - u) * (aQ * aY)); [|rewrite <- AX;
      assert ((1 - u) * ((1 - u) * Rabs X) <= (1 - u) * Rabs N) by (apply Rmult_le_compat_l; lra); lra].
    replace ((1 - u) * (1 - u) / (1 + u) * aQ * aD) with ((1 - u) * (1 - u) / (1 + u) * (aQ * aD)) by ring.
    apply Rle_trans with ((1 - u) * (1 - u) / (1 + u) * (aQ * ((1 + u) * aY))).
    - apply Rmult_le_compat_l; [|exact QD]. apply Rmult_le_pos; [nra | apply Rlt_le, Rinv_0_lt_compat; lra].
    - right. field. lra. }
  assert (K2 : / 2 <= (1 - u) * (1 - u) / (1 + u)).
  { apply Rmult_le_reg_r with (1 + u); [lra|]. unfold Rdiv. rewrite Rmult_assoc, Rinv_l by lra. nra. }
  assert (T0h : / 2 * aQ <= Rabs t0).
  { eapply Rle_trans; [apply Rmult_le_compat_r; [apply Rabs_pos | exact K2] | exact T0Q]. }
  assert (Q9h : bpow radix2 (-1022) <= / 2 * Q900).
  { unfold quotient_min_magnitude.
    replace (/ 2 * bpow radix2 (-900)) with (bpow radix2 (-901))
      by (replace (-900)%Z with (-901 + 1)%Z by lia; rewrite bpow_plus; change (bpow radix2 1) with 2; field).
    apply bpow_le; lia. }
  assert (Nt0 : bpow radix2 (-1022) <= Rabs t0) by lra.
  set (q0 := RN t0).
  pose proof (RN_rel t0 Nt0) as E0. fold q0 in E0.
  assert (Kb : 1 - 4 * u <= (1 - u) * (1 - u) / (1 + u)).
  { apply Rmult_le_reg_r with (1 + u); [lra|]. unfold Rdiv. rewrite Rmult_assoc, Rinv_l by lra. nra. }
  assert (T0Q' : (1 - 4 * u) * aQ <= Rabs t0).
  { eapply Rle_trans; [apply Rmult_le_compat_r; [apply Rabs_pos | exact Kb] | exact T0Q]. }
  assert (Q0L : (1 - 5 * u) * aQ <= Rabs q0).
  { pose proof (Rabs_close' _ _ _ E0). pose proof (Rabs_pos t0). rewrite u_val in *. lra. }
  assert (Gq0 : Q900 <= 2 * Rabs q0) by (rewrite u_val in *; lra).
  destruct (quotient_residuals_q0 N Nlo D Dlo R BN BNlo BD BDlo LN LD GN Dnz RD Gq0)
    as [AP [Eta_aD [Eta_A [RR [Ec [Hc HcD]]]]]].
  fold t0 in AP, Eta_aD, Eta_A, RR, Ec, Hc, HcD. fold q0 in AP, Eta_aD, Eta_A, RR, Ec, Hc, HcD. fold aD in AP, Eta_aD, Eta_A, RR, Ec, Hc, HcD.
  set (rr' := RN (fma (- q0) D N + fma (- q0) Dlo Nlo)) in *.
  set (c := RN (rr' * R)) in *.
  destruct (quotient_candidate q0 c (binary64_RN _) (binary64_RN _) Hc) as [Xq [Hq1 Hq2]].
  set (q := RN (q0 + c)) in *. set (w := RN (c - RN (q - q0))) in *.
  (* q0 + c is within 25u²|Q| of Q *)
  assert (EXY : Rabs (X - (q0 + c) * Y) <= 23 * (u * u) * (Rabs q0 * aD)).
  { replace (X - (q0 + c) * Y) with (((N - q0 * D) + (Nlo - q0 * Dlo) - rr') - (c * D - rr') - c * Dlo)
      by (rewrite EX, <- XN, <- XD; ring).
    pose proof (Rabs_3 ((N - q0 * D) + (Nlo - q0 * Dlo) - rr') (c * D - rr') (c * Dlo)). lra. }
  assert (Ee : Rabs (q0 + c - Q) <= 24 * (u * u) * Rabs q0).
  { apply Rmult_le_reg_r with aY; [exact YP|].
    assert (Rabs (q0 + c - Q) * aY = Rabs (X - (q0 + c) * Y)).
    { unfold aY. rewrite <- Rabs_mult, <- Rabs_Ropp. f_equal. rewrite XQY. ring. }
    assert (Rabs q0 * aD <= Rabs q0 * ((1 + u) * aY)) by (apply Rmult_le_compat_l; [apply Rabs_pos | exact aD1]).
    rewrite u_val in *. lra. }
  assert (Q0U : Rabs q0 <= (1 + 6 * u) * aQ).
  { assert (Rabs q0 <= aQ + Rabs (q0 + c - Q) + Rabs c).
    { replace q0 with (Q + (q0 + c - Q) + - c) at 1 by ring.
      pose proof (Rabs_triang (Q + (q0 + c - Q)) (- c)). pose proof (Rabs_triang Q (q0 + c - Q)).
      rewrite Rabs_Ropp in *. unfold aQ. lra. }
    rewrite u_val in *. lra. }
  assert (Ee' : Rabs (q0 + c - Q) <= 25 * (u * u) * aQ) by (rewrite u_val in *; lra).
  assert (C97 : / 2 ^ 97 = 512 * (u * u)) by (rewrite u_val; field).
  rewrite C97 in Hyp.
  set (Kr := (En + aQ * Ed) / aY) in *.
  assert (KrP : 0 <= Kr) by (unfold Kr; apply Rmult_le_pos; [apply Rplus_le_le_0_compat; [exact PEn | apply Rmult_le_pos; lra] | apply Rlt_le, Rinv_0_lt_compat; exact YP]).
  assert (PaQ : 0 <= aQ) by lra.
  assert (qRN : q = RN Q).
  { unfold q. apply RN_of_close; [apply binary64_RN|].
    replace (q0 + c - RN Q) with ((q0 + c - Q) + (Q - RN Q)) by ring.
    eapply Rle_lt_trans; [apply Rabs_triang|]. rewrite u_val in *. lra. }
  rewrite <- qRN in Hyp.
  assert (Gq1 : Q900 <= Rabs q) by (rewrite qRN; apply RN_abs_ge; [lia | exact GQ1]).
  assert (Gq2 : Rabs q <= largest_finite).
  { eapply Rle_trans; [|apply bpow_1000_largest]. rewrite qRN; apply RN_abs_le; [lia | exact GQ2]. }
  rewrite quotient_enclosure_factor_val, quotient_relative_val, quotient_test_factor_val.
  rewrite (Rle_bool_true _ _ GN), (Rle_bool_true _ _ Gq1), (Rle_bool_true _ _ Gq2). cbn [andb].
  split; [| exact qRN].
  apply Rlt_bool_true.
  (* the test, read forwards *)
  set (h := half_gap q) in *.
  set (dQ := Rabs (Q - q)) in *.
  assert (PdQ : 0 <= dQ) by apply Rabs_pos.
  pose proof (Rabs_pos q0) as Pq0. pose proof (Rabs_pos w) as Pw.
  assert (Hw : Rabs w <= dQ + 25 * (u * u) * aQ).
  { replace w with ((q0 + c - Q) + (Q - q)) by lra.
    eapply Rle_trans; [apply Rabs_triang|]. unfold dQ. lra. }
  assert (KrY : Kr * aY = En + aQ * Ed) by (unfold Kr; field; lra).
  assert (HypD : (dQ + (1 + / 256) * Kr + 512 * (u * u) * aQ) * aD < h * aD)
    by (apply Rmult_lt_compat_r; [exact DP | exact Hyp]).
  assert (Fh : h <= u * Rabs q) by (apply half_gap_le_u; apply Norm; exact Gq1).
  assert (Fq : Rabs q <= (1 + u) * aQ).
  { rewrite qRN. pose proof (RN_rel Q (Norm Q GQ1)) as E. pose proof (Rabs_close _ _ _ E). unfold aQ. lra. }
  assert (FhD : h * aD <= (u * ((1 + u) * aQ)) * aD).
  { apply Rmult_le_compat_r; [lra|]. eapply Rle_trans; [exact Fh|]. apply Rmult_le_compat_l; lra. }
  assert (dQlt : dQ < h).
  { pose proof Hyp as H'. rewrite u_val in H'. assert (0 <= aQ) by lra. lra. }
  assert (dQh : dQ * aD <= h * aD) by (apply Rmult_le_compat_r; lra).
  assert (KrYD : Kr * ((1 - u) * aY) <= Kr * aD) by (apply Rmult_le_compat_l; lra).
  assert (q0Ed : Rabs q0 * Ed <= ((1 + 6 * u) * aQ) * Ed) by (apply Rmult_le_compat_r; lra).
  assert (AQ : Rabs q0 * aD <= ((1 + 6 * u) * aQ) * aD) by (apply Rmult_le_compat_r; lra).
  assert (wD : Rabs w * aD <= (dQ + 25 * (u * u) * aQ) * aD) by (apply Rmult_le_compat_r; lra).
  set (xb := RN (Rabs q0 * Ed)). set (xs := RN (xb + En)). set (x := RN (xs * (1 + / 512))).
  set (yb := RN (Rabs q0 * (32 * (u * u)))). set (ys := RN (yb + Rabs w)). set (y := RN (ys * aD)).
  set (xy := RN (x + y)).
  assert (Pxb : 0 <= xb) by (apply RN_nonneg; apply Rmult_le_pos; [apply Rabs_pos | exact PEd]).
  assert (Bxb : xb <= (1 + u) * (Rabs q0 * Ed) + eta) by (apply RN_up; apply Rmult_le_pos; [apply Rabs_pos | exact PEd]).
  assert (Pxs : 0 <= xs) by (apply RN_nonneg; lra).
  assert (Bxs : xs <= (1 + u) * (xb + En)) by (apply RN_sum_up; [apply binary64_RN | exact BEn | lra]).
  assert (Px : 0 <= x) by (apply RN_nonneg; apply Rmult_le_pos; lra).
  assert (Bx : x <= (1 + u) * (xs * (1 + / 512)) + eta) by (apply RN_up; apply Rmult_le_pos; lra).
  assert (Pyb0 : 0 <= Rabs q0 * (32 * (u * u))).
  { apply Rmult_le_pos; [apply Rabs_pos | apply Rmult_le_pos; [lra | apply Rmult_le_pos; lra]]. }
  assert (Pyb : 0 <= yb) by (apply RN_nonneg; exact Pyb0).
  assert (Byb : yb <= (1 + u) * (Rabs q0 * (32 * (u * u))) + eta) by (apply RN_up; exact Pyb0).
  assert (Pys : 0 <= ys) by (apply RN_nonneg; lra).
  assert (Bys : ys <= (1 + u) * (yb + Rabs w))
    by (apply RN_sum_up; [apply binary64_RN | apply binary64_abs, binary64_RN | lra]).
  assert (BysD : ys * aD <= ((1 + u) * ((1 + u) * (Rabs q0 * (32 * (u * u))) + eta + Rabs w)) * aD)
    by (apply Rmult_le_compat_r; [lra | eapply Rle_trans; [exact Bys | apply Rmult_le_compat_l; lra]]).
  assert (Py : 0 <= y) by (apply RN_nonneg; apply Rmult_le_pos; lra).
  assert (By : y <= (1 + u) * (ys * aD) + eta) by (apply RN_up; apply Rmult_le_pos; lra).
  assert (Pxy : 0 <= xy) by (apply RN_nonneg; lra).
  assert (Bxy : xy <= (1 + u) * (x + y)) by (apply RN_sum_up; [apply binary64_RN | apply binary64_RN | lra]).
  assert (BL : RN (xy * (1 + / 35184372088832)) <= (1 + u) * (xy * (1 + / 35184372088832)) + eta)
    by (apply RN_up; apply Rmult_le_pos; lra).
  assert (BR : (1 - u) * (h * aD) - eta <= RN (h * aD)).
  { apply RN_down. apply Rmult_le_pos; [apply half_gap_bounds | lra]. }
  clear - BL BR Bxy By BysD Bys Byb Bx Bxs Bxb Pxb Pxs Px Pyb Pys Py Pxy KrY HypD FhD dQh KrYD q0Ed AQ wD Eta_aD Eta_A
    Hu Hu1 He PdQ Pq0 Pw KrP PEn PEd.
  rewrite u_val in *. lra.
Qed.

(** ** Exact enclosures (radius 0): certified whenever X/Y is not within 2^-97|X/Y| = 512u²|X/Y| of the points
    RN(X/Y) ± half_gap(RN(X/Y)). *)
Corollary round_quotient_live_exact : forall nh nl dh dl : R,
  binary64 nh -> binary64 nl -> binary64 dh -> binary64 dl ->
  divisor_min_magnitude <= Rabs (dh + dl) <= divisor_max_magnitude ->
  Q900 <= Rabs (nh + nl) ->
  Q900 <= Rabs ((nh + nl) / (dh + dl)) <= bpow radix2 1000 ->
  Rabs ((nh + nl) / (dh + dl) - RN ((nh + nl) / (dh + dl))) + / 2 ^ 97 * Rabs ((nh + nl) / (dh + dl))
    < half_gap (RN ((nh + nl) / (dh + dl))) ->
  let r := round_quotient {| hi := nh; lo := nl; radius := 0 |}
                          (prepare_divisor {| hi := dh; lo := dl; radius := 0 |}) in
  qr_certain r = true /\ qr_t r = RN ((nh + nl) / (dh + dl)).
Proof.
  intros nh nl dh dl Bnh Bnl Bdh Bdl GY GX GQ H r.
  apply (round_quotient_live {| hi := nh; lo := nl; radius := 0 |} {| hi := dh; lo := dl; radius := 0 |});
    cbn [hi lo radius]; try assumption; try apply binary64_0; lra.
Qed.

(** ** Not vacuous, and how sharp: the twin on concrete enclosures, by computation.
    [round_quotient_b] (PlaneQueryTwins.v, checked against the C++ by the runner's quotient routines) on exact
    enclosures: 1/3 is certified (its distance to the nearer midpoint is 2^-55/3, far above 2^-97/3).
    Near a midpoint: X = (1 + 2^-52) + (−2^-53 + k·2^-106), Y = 1, so Q = 1 + 2^-53 + k·u² lies k·u² above
    the midpoint 1 + 2^-53 between 1 and its successor (RN(Q) = 1 + 2^-52, half_gap = 2^-53).
    [round_quotient_live_exact] covers k ≥ 513 (512u²·|Q| < 513u²); the twin certifies from k = 290 on and
    not at k = 288: the theorem's slack 2^-97|Q| is within a factor 1.8 of the test's actual one
    (about 289u²|Q| here: the factor 1 + 2^-45 of the test, 256u², with 32u² of the constant 2^-101). *)
Definition live_enc (h l r : Z) : EnclosureB := {| hib := of_bits h; lob := of_bits l; radiusb := of_bits r |}.

(** bits: 1.0 = 4607182418800017408, 3.0 = 4613937818241073152, RN(1/3) = 4599676419421066581,
    1 + 2^-52 = 4607182418800017409, −(2^53 − k)·2^-106 = 13591863675404156928 − k. *)
Lemma round_quotient_b_third :
  let r := round_quotient_b (live_enc 4607182418800017408 0 0) (prepare_divisor_b (live_enc 4613937818241073152 0 0)) in
  (to_bits (fst r), snd r) = (4599676419421066581%Z, true).
Proof. vm_compute. reflexivity. Qed.

Definition near_midpoint_certified (k : Z) : bool :=
  snd (round_quotient_b (live_enc 4607182418800017409 (13591863675404156928 - k) 0)
                        (prepare_divisor_b (live_enc 4607182418800017408 0 0))).

Lemma near_midpoint_threshold :
  map near_midpoint_certified (256 :: 288 :: 290 :: 512 :: 513 :: 1024 :: nil)%Z =
  (false :: false :: true :: true :: true :: true :: nil).
Proof. vm_compute. reflexivity. Qed.

(** The radii: 1/3 (X = 1, Y = 3) is 2^-55/3 from the point RN(1/3) + 2^-55, so [round_quotient_live] covers
    E_n < (1 + 2^-8)^-1·(2^-55 − 2^-97) and E_d < 3·(that); the twin certifies with E_n = 2^-57 and not with
    E_n = 2^-55, with E_d = 2^-55 and not with E_d = 2^-53 (bits 2^-57 = 4350477240039899136,
    2^-55 = 4359484439294640128, 2^-53 = 4368491638549381120). *)
Lemma third_radius_threshold :
  map (fun r => snd (round_quotient_b (live_enc 4607182418800017408 0 r)
                                      (prepare_divisor_b (live_enc 4613937818241073152 0 0))))
      (4350477240039899136 :: 4359484439294640128 :: nil)%Z = (true :: false :: nil) /\
  map (fun r => snd (round_quotient_b (live_enc 4607182418800017408 0 0)
                                      (prepare_divisor_b (live_enc 4613937818241073152 0 r))))
      (4359484439294640128 :: 4368491638549381120 :: nil)%Z = (true :: false :: nil).
Proof. split; vm_compute; reflexivity. Qed.
