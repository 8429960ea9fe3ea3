(** * round_quotient: the correctly rounded t = num/den from two enclosures
    (kernel/src/certified/round_quotient.hpp).

    Main theorem: [round_quotient_decision_sound]: whenever [round_quotient_decision] says certain, its
    t satisfies den ≠ 0 and t = RN(num / den), round to nearest with ties to even, for every num and den
    enclosed by the two arguments; [round_quotient_sound] is the same for the optional form
    [round_quotient].  [round_quotient_candidate_normal] shows that, once the guards pass, the candidate q has
    |q| ≥ 2^-901, the range where the C++ bit manipulation [half_gap_to_nearer_neighbour] computes the
    model's [half_gap] ([half_gap_bits]). *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model Filter Compensated.
Open Scope R_scope.

Notation succ64 := (succ radix2 (FLT_exp (-1074) 53)).
Notation pred64 := (pred radix2 (FLT_exp (-1074) 53)).
Notation ulp64 := (ulp radix2 (FLT_exp (-1074) 53)).

(** ** Half the distance from q to its nearer neighbour. *)
Definition half_gap (q : R) : R := Rmin (succ64 q - q) (q - pred64 q) / 2.

Lemma half_gap_bounds : forall q,
  0 <= half_gap q /\ half_gap q <= (succ64 q - q) / 2 /\ half_gap q <= (q - pred64 q) / 2.
Proof.
  intros q. unfold half_gap.
  pose proof (succ_ge_id radix2 (FLT_exp (-1074) 53) q).
  pose proof (pred_le_id radix2 (FLT_exp (-1074) 53) q).
  pose proof (Rmin_l (succ64 q - q) (q - pred64 q)).
  pose proof (Rmin_r (succ64 q - q) (q - pred64 q)).
  assert (0 <= Rmin (succ64 q - q) (q - pred64 q)) by (apply Rmin_glb; lra).
  lra.
Qed.

(** A real within half the gap of a double q rounds to q: it lies strictly between the midpoints of
    q and its neighbours, so no tie can arise. *)
Lemma RN_of_close : forall q t, binary64 q -> Rabs (t - q) < half_gap q -> RN t = q.
Proof.
  intros q t Fq H. destruct (half_gap_bounds q) as [_ [H1 H2]].
  apply Rabs_def2 in H. destruct H as [H3 H4].
  apply Rle_antisym.
  - apply (round_N_le_midp radix2 (FLT_exp (-1074) 53)); [exact Fq | lra].
  - apply (round_N_ge_midp radix2 (FLT_exp (-1074) 53)); [exact Fq | lra].
Qed.

Lemma half_gap_le_u : forall q, bpow radix2 (-1022) <= Rabs q -> half_gap q <= u * Rabs q.
Proof.
  intros q Hq. destruct (half_gap_bounds q) as [_ [H1 _]].
  pose proof (succ_le_plus_ulp radix2 (FLT_exp (-1074) 53) q).
  pose proof (ulp_FLT_le radix2 (-1074) 53 q Hq) as U.
  replace (bpow radix2 (1 - 53)) with (2 * u) in U by (rewrite u_val; simpl bpow; lra).
  lra.
Qed.

Lemma half_gap_opp : forall q, half_gap (- q) = half_gap q.
Proof.
  intros q. unfold half_gap.
  rewrite (succ_opp radix2 (FLT_exp (-1074) 53)), (pred_opp radix2 (FLT_exp (-1074) 53)).
  rewrite Rmin_comm. f_equal. f_equal; ring.
Qed.

(** For |q| ≥ 2^-968 (so that the result is normal), the model's half gap is the number
    half_gap_to_nearer_neighbour builds from q's exponent bits: 2^(e−53) for q in [2^e, 2^(e+1)),
    2^(e−54) when |q| = 2^e (e = mag q − 1). *)
Theorem half_gap_bits : forall q, binary64 q -> bpow radix2 (-968) <= Rabs q ->
  half_gap q = if Req_bool (Rabs q) (bpow radix2 (mag radix2 q - 1)) then bpow radix2 (mag radix2 q - 55)
               else bpow radix2 (mag radix2 q - 54).
Proof.
  (* It suffices to prove it for q > 0. *)
  assert (Pos : forall q, binary64 q -> bpow radix2 (-968) <= q ->
    half_gap q = if Req_bool q (bpow radix2 (mag radix2 q - 1)) then bpow radix2 (mag radix2 q - 55)
                 else bpow radix2 (mag radix2 q - 54)).
  { intros q Fq Hq.
    assert (Qp : 0 < q) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact Hq]).
    assert (M : (-967 <= mag radix2 q)%Z).
    { apply mag_ge_bpow. rewrite Rabs_pos_eq by lra. exact Hq. }
    unfold half_gap.
    rewrite (succ_eq_pos radix2 (FLT_exp (-1074) 53)) by lra.
    rewrite (pred_eq_pos radix2 (FLT_exp (-1074) 53)) by lra.
    unfold pred_pos.
    rewrite !(ulp_neq_0 radix2 (FLT_exp (-1074) 53)) by lra.
    unfold cexp, FLT_exp.
    rewrite Z.max_l by lia.
    assert (Half : forall k, bpow radix2 k / 2 = bpow radix2 (k - 1)).
    { intros k. replace (k - 1)%Z with (k + -1)%Z by lia. rewrite bpow_plus. simpl (bpow radix2 (-1)).
      unfold Rdiv. f_equal. }
    destruct (Req_bool_spec q (bpow radix2 (mag radix2 q - 1))) as [E|E].
    - rewrite Z.max_l by lia.
      replace (q + bpow radix2 (mag radix2 q - 53) - q) with (bpow radix2 (mag radix2 q - 53)) by ring.
      replace (q - (q - bpow radix2 (mag radix2 q - 1 - 53))) with (bpow radix2 (mag radix2 q - 54))
        by (replace (mag radix2 q - 1 - 53)%Z with (mag radix2 q - 54)%Z by lia; ring).
      rewrite Rmin_right by (apply bpow_le; lia).
      rewrite Half. f_equal. lia.
    - replace (q + bpow radix2 (mag radix2 q - 53) - q) with (bpow radix2 (mag radix2 q - 53)) by ring.
      replace (q - (q - bpow radix2 (mag radix2 q - 53))) with (bpow radix2 (mag radix2 q - 53)) by ring.
      rewrite Rmin_left by lra.
      rewrite Half. f_equal. lia. }
  intros q Fq Hq.
  destruct (Rle_or_lt 0 q) as [P|N].
  - rewrite Rabs_pos_eq in Hq |- * by exact P. now apply Pos.
  - rewrite Rabs_left in Hq |- * by exact N.
    rewrite <- half_gap_opp, <- (mag_opp radix2 q).
    now apply Pos; [apply binary64_opp|].
Qed.

(** ** round_quotient_decision, operation by operation, branch-free as in the C++: every guard and the
    test are computed, and [certain] is their conjunction ([both(both(in_range, |q| < HUGE_VAL), inside)]).
    The C++ guards also require N, D, q0, q and both radii to be finite ([< HUGE_VAL]); in the model
    every value is finite, so those conjuncts are true and are left out (proofs/README.md, "Overflow").
    Returns (t, certain). *)
Definition round_quotient_decision (n d : Enclosure) : R * bool :=
  let N := fst (two_sum (hi n) (lo n)) in
  let Nlo := snd (two_sum (hi n) (lo n)) in
  let D := fst (two_sum (hi d) (lo d)) in
  let Dlo := snd (two_sum (hi d) (lo d)) in
  let q0 := RN (N / D) in
  let abs_q0 := Rabs q0 in
  let abs_D := Rabs D in
  let abs_N := Rabs N in
  let in_range := (Rle_bool quotient_min_magnitude abs_N && Rle_bool quotient_min_magnitude abs_D &&
                   Rle_bool quotient_min_magnitude abs_q0)%bool in
  let r1 := fma (- q0) D N in
  let r2 := fma (- q0) Dlo Nlo in
  let c := RN (RN (r1 + r2) / D) in
  let q := two_sum q0 c in
  let x := RN (RN (RN (abs_q0 * radius d) + radius n) * quotient_enclosure_factor) in
  let y := RN (RN (RN (abs_q0 * quotient_relative) + Rabs (snd q)) * abs_D) in
  let h := half_gap (fst q) in
  let inside := Rlt_bool (RN (RN (x + y) * quotient_test_factor)) (RN (h * abs_D)) in
  (fst q, (in_range && inside)%bool).

(** [round_quotient(n, d)]: the same decision as an optional. *)
Definition round_quotient (n d : Enclosure) : option R :=
  let r := round_quotient_decision n d in
  if snd r then Some (fst r) else None.

(** ** Constants. *)

Notation Q900 := quotient_min_magnitude.

Lemma Q900_pos : 0 < Q900.
Proof. apply bpow_gt_0. Qed.

Lemma eta_Q900 : eta = / 2 ^ 175 * Q900.
Proof.
  unfold eta, quotient_min_magnitude. replace (-1075)%Z with (-175 + -900)%Z by lia.
  rewrite bpow_plus. f_equal. simpl. lra.
Qed.

Lemma Q900_normal : bpow radix2 (-1022) <= Q900 / 4.
Proof.
  unfold quotient_min_magnitude.
  replace (bpow radix2 (-900) / 4) with (bpow radix2 (-902)).
  - apply bpow_le. lia.
  - replace (-902)%Z with (-900 + -2)%Z by lia. rewrite bpow_plus. simpl (bpow radix2 (-2)). lra.
Qed.

Lemma quotient_relative_val : quotient_relative = 32 * (u * u).
Proof. unfold quotient_relative. rewrite u_val. simpl bpow. lra. Qed.

Lemma quotient_enclosure_factor_val : quotient_enclosure_factor = 1 + / 512.
Proof. unfold quotient_enclosure_factor. simpl bpow. lra. Qed.

Lemma quotient_test_factor_val : quotient_test_factor = 1 + / 35184372088832.
Proof. unfold quotient_test_factor. simpl bpow. lra. Qed.

(** ** The residuals, once the guards pass: with A = |q0|·|D|,
    |R − rr| ≤ 7u²A for R = (N − q0 D) + (n − q0 d), |c D − rr| ≤ 5u²A, |c| ≤ 5u|q0|, |c d| ≤ 5u²A,
    and A ≥ Q900/2 (which makes every absolute error η negligible: η ≤ 2^-174 A). *)
Lemma quotient_residuals : forall N Nlo D Dlo,
  binary64 N -> binary64 Nlo -> binary64 D -> binary64 Dlo ->
  Rabs Nlo <= u * Rabs N -> Rabs Dlo <= u * Rabs D ->
  Q900 <= Rabs N -> Q900 <= Rabs D -> Q900 <= Rabs (RN (N / D)) ->
  let q0 := RN (N / D) in
  let rr := RN (fma (- q0) D N + fma (- q0) Dlo Nlo) in
  let c := RN (rr / D) in
  Q900 <= 2 * (Rabs q0 * Rabs D) /\
  Rabs ((N - q0 * D) + (Nlo - q0 * Dlo) - rr) <= 7 * (u * u) * (Rabs q0 * Rabs D) /\
  Rabs (c * D - rr) <= 5 * (u * u) * (Rabs q0 * Rabs D) /\
  Rabs c <= 5 * u * Rabs q0 /\
  Rabs (c * Dlo) <= 5 * (u * u) * (Rabs q0 * Rabs D).
Proof.
  intros N Nlo D Dlo BN BNlo BD BDlo LN LD GN GD Gq q0 rr c.
  fold q0 in Gq.
  pose proof Q900_pos as HQ. pose proof eta_Q900 as EQ. pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (DP : 0 < Rabs D) by lra.
  assert (Dnz : D <> 0) by (intros Z; rewrite Z, Rabs_R0 in DP; lra).
  assert (q0P : 0 < Rabs q0) by lra.
  set (aD := Rabs D) in *. set (aq := Rabs q0) in *.
  (* q0 = RN(N/D): |q0 D − N| ≤ u A + η |D| *)
  assert (E0 : Rabs (q0 * D - N) <= u * (aq * aD) + eta * aD).
  { pose proof (RN_err_round (N / D)) as E. fold q0 in E.
    replace (q0 * D - N) with ((q0 - N / D) * D) by (field; exact Dnz).
    rewrite Rabs_mult. fold aD. fold aq in E.
    replace (u * (aq * aD) + eta * aD) with ((u * aq + eta) * aD) by ring.
    apply Rmult_le_compat_r; [lra | exact E]. }
  assert (Eta_aq : eta <= / 2 ^ 175 * aq) by (rewrite EQ; simpl; lra).
  assert (Eta_aD : eta * aD <= / 2 ^ 175 * (aq * aD)).
  { rewrite <- Rmult_assoc. apply Rmult_le_compat_r; lra. }
  assert (Aq : Rabs (q0 * D) = aq * aD) by apply Rabs_mult.
  set (A := aq * aD) in *.
  assert (AP : 0 < A) by (unfold A; apply Rmult_lt_0_compat; lra).
  set (rho1 := N - q0 * D).
  assert (R1 : Rabs rho1 <= u * A + / 2 ^ 175 * A).
  { unfold rho1. rewrite Rabs_minus_sym. lra. }
  assert (HN : Rabs N <= A + Rabs rho1).
  { replace N with (q0 * D + rho1) by (unfold rho1; ring). rewrite <- Aq. apply Rabs_triang. }
  assert (A2 : Q900 <= 2 * A) by (simpl in *; rewrite u_val in *; lra).
  assert (Eta_A : eta <= / 2 ^ 174 * A) by (rewrite EQ; simpl in *; lra).
  (* the two FMA residuals *)
  assert (Er1 : Rabs (fma (- q0) D N - rho1) <= u * Rabs rho1 + eta).
  { unfold fma. replace (- q0 * D + N) with rho1 by (unfold rho1; ring). apply RN_err. }
  set (rho2 := Nlo - q0 * Dlo).
  assert (Er2 : Rabs (fma (- q0) Dlo Nlo - rho2) <= u * Rabs rho2 + eta).
  { unfold fma. replace (- q0 * Dlo + Nlo) with rho2 by (unfold rho2; ring). apply RN_err. }
  assert (QD : Rabs (q0 * Dlo) <= u * A).
  { rewrite Rabs_mult. fold aq. unfold A.
    replace (u * (aq * aD)) with (aq * (u * aD)) by ring.
    apply Rmult_le_compat_l; [lra | exact LD]. }
  assert (R2 : Rabs rho2 <= Rabs Nlo + Rabs (q0 * Dlo)).
  { unfold rho2. unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  set (r1 := fma (- q0) D N) in *. set (r2 := fma (- q0) Dlo Nlo) in *.
  assert (Br1 : binary64 r1) by apply binary64_RN.
  assert (Br2 : binary64 r2) by apply binary64_RN.
  pose proof (RN_plus_err r1 r2 Br1 Br2) as Err. fold rr in Err.
  assert (T12 : Rabs (r1 + r2) <= Rabs r1 + Rabs r2) by apply Rabs_triang.
  assert (Hr1 : Rabs r1 <= Rabs rho1 + (u * Rabs rho1 + eta)) by (apply Rabs_close; exact Er1).
  assert (Hr2 : Rabs r2 <= Rabs rho2 + (u * Rabs rho2 + eta)) by (apply Rabs_close; exact Er2).
  assert (Tr : Rabs (rho1 + rho2 - rr) <= Rabs (r1 - rho1) + Rabs (r2 - rho2) + Rabs (rr - (r1 + r2))).
  { replace (rho1 + rho2 - rr) with (- (r1 - rho1) + - (r2 - rho2) + - (rr - (r1 + r2))) by ring.
    eapply Rle_trans; [apply Rabs_triang|].
    pose proof (Rabs_triang (- (r1 - rho1)) (- (r2 - rho2))). rewrite !Rabs_Ropp in *. lra. }
  assert (Hrr : Rabs rr <= Rabs (r1 + r2) + u * Rabs (r1 + r2)) by (apply Rabs_close; exact Err).
  pose proof (Rabs_pos rho1). pose proof (Rabs_pos rho2). pose proof (Rabs_pos (r1 + r2)).
  assert (RR : Rabs (rho1 + rho2 - rr) <= 7 * (u * u) * A) by (rewrite u_val in *; simpl in *; lra).
  assert (Arr : Rabs rr <= 4 * u * A) by (rewrite u_val in *; simpl in *; lra).
  (* c = RN(rr / D) *)
  assert (Ec : Rabs (c * D - rr) <= u * Rabs rr + eta * aD).
  { pose proof (RN_err (rr / D)) as E. fold c in E.
    replace (c * D - rr) with ((c - rr / D) * D) by (field; exact Dnz).
    rewrite Rabs_mult. fold aD.
    replace (Rabs rr) with (Rabs (rr / D) * aD) by (unfold aD; rewrite <- Rabs_mult; f_equal; field; exact Dnz).
    replace (u * (Rabs (rr / D) * aD) + eta * aD) with ((u * Rabs (rr / D) + eta) * aD) by ring.
    apply Rmult_le_compat_r; [lra | exact E]. }
  assert (Ec' : Rabs (c * D - rr) <= 5 * (u * u) * A) by (rewrite u_val in *; simpl in *; lra).
  assert (cD : Rabs c * aD <= 5 * u * A).
  { unfold aD. rewrite <- Rabs_mult. pose proof (Rabs_close _ _ _ Ec'). rewrite u_val in *; simpl in *. lra. }
  assert (Hc : Rabs c <= 5 * u * aq).
  { apply Rmult_le_reg_r with aD; [exact DP|]. unfold A in cD. lra. }
  assert (HcD : Rabs (c * Dlo) <= 5 * (u * u) * A).
  { rewrite Rabs_mult.
    apply Rle_trans with (Rabs c * (u * aD)).
    - apply Rmult_le_compat_l; [apply Rabs_pos | exact LD].
    - unfold A in cD |- *. rewrite u_val in *. lra. }
  repeat split; lra.
Qed.

(** The candidate q = RN(q0 + c) and w = [two_sum(q0, c).lo]: q + w = q0 + c, |w| ≤ u|q|,
    |q| ≤ (1 + 7u)|q0| and |q0| ≤ 2|q|. *)
Lemma quotient_candidate : forall q0 c, binary64 q0 -> binary64 c -> Rabs c <= 5 * u * Rabs q0 ->
  let q := fst (two_sum q0 c) in let w := snd (two_sum q0 c) in
  q + w = q0 + c /\ Rabs w <= u * Rabs q /\ Rabs q <= (1 + 7 * u) * Rabs q0 /\ Rabs q0 <= 2 * Rabs q.
Proof.
  intros q0 c Bq0 Bc Hc q w.
  pose proof (two_sum_exact q0 c Bq0 Bc) as X. fold q w in X.
  destruct (two_sum_lo_bound q0 c Bq0 Bc) as [_ L]. fold q w in L.
  assert (T1 : Rabs q <= Rabs q0 + Rabs c + Rabs w).
  { replace q with (q0 + c - w) by lra. unfold Rminus.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. pose proof (Rabs_triang q0 c). lra. }
  assert (T2 : Rabs q0 <= Rabs q + Rabs c + Rabs w).
  { replace q0 with (q - c + w) by lra. unfold Rminus.
    eapply Rle_trans; [apply Rabs_triang|]. pose proof (Rabs_triang q (- c)). rewrite Rabs_Ropp in *. lra. }
  pose proof (Rabs_pos q). pose proof (Rabs_pos q0).
  repeat split; try easy; rewrite u_val in *; lra.
Qed.

(** ** Once the guards pass, the candidate is a normal number far from the underflow range:
    |q| ≥ 2^-901, so half_gap_to_nearer_neighbour's precondition |q| ≥ 2^-968 holds. *)
Theorem round_quotient_candidate_normal : forall N Nlo D Dlo,
  binary64 N -> binary64 Nlo -> binary64 D -> binary64 Dlo ->
  Rabs Nlo <= u * Rabs N -> Rabs Dlo <= u * Rabs D ->
  Q900 <= Rabs N -> Q900 <= Rabs D -> Q900 <= Rabs (RN (N / D)) ->
  let q0 := RN (N / D) in
  let c := RN (RN (fma (- q0) D N + fma (- q0) Dlo Nlo) / D) in
  bpow radix2 (-901) <= Rabs (fst (two_sum q0 c)).
Proof.
  intros N Nlo D Dlo BN BNlo BD BDlo LN LD GN GD Gq q0 c.
  destruct (quotient_residuals N Nlo D Dlo BN BNlo BD BDlo LN LD GN GD Gq) as [_ [_ [_ [Hc _]]]].
  fold q0 c in Hc.
  destruct (quotient_candidate q0 c ltac:(apply binary64_RN) ltac:(apply binary64_RN) Hc) as [_ [_ [_ Hq]]].
  fold q0 in Gq.
  replace (bpow radix2 (-901)) with (Q900 / 2).
  - lra.
  - unfold quotient_min_magnitude. replace (-901)%Z with (-900 + -1)%Z by lia.
    rewrite bpow_plus. simpl (bpow radix2 (-1)). lra.
Qed.

(** ** Main theorem: whenever the decision is certain, den ≠ 0 and t = RN(num/den). *)
Theorem round_quotient_decision_sound : forall (n d : Enclosure) (num den : R),
  binary64 (hi n) -> binary64 (lo n) -> binary64 (radius n) ->
  binary64 (hi d) -> binary64 (lo d) -> binary64 (radius d) ->
  encloses n num -> encloses d den ->
  snd (round_quotient_decision n d) = true ->
  den <> 0 /\ fst (round_quotient_decision n d) = RN (num / den).
Proof.
  intros [nh nl En] [dh dl Ed] num den Bnh Bnl BEn Bdh Bdl BEd Hn Hd H.
  unfold encloses in Hn, Hd. cbn [hi lo radius] in *.
  unfold round_quotient_decision in H |- *. cbn [hi lo radius fst snd] in H |- *.
  (* the two TwoSums *)
  pose proof (two_sum_exact nh nl Bnh Bnl) as XN.
  destruct (two_sum_lo_bound nh nl Bnh Bnl) as [_ LN].
  pose proof (two_sum_exact dh dl Bdh Bdl) as XD.
  destruct (two_sum_lo_bound dh dl Bdh Bdl) as [_ LD].
  pose proof (binary64_two_sum_hi nh nl) as BN. pose proof (binary64_two_sum_lo nh nl) as BNlo.
  pose proof (binary64_two_sum_hi dh dl) as BD. pose proof (binary64_two_sum_lo dh dl) as BDlo.
  set (N := fst (two_sum nh nl)) in *. set (Nlo := snd (two_sum nh nl)) in *.
  set (D := fst (two_sum dh dl)) in *. set (Dlo := snd (two_sum dh dl)) in *.
  set (q0 := RN (N / D)) in *.
  (* the guards *)
  revert H.
  destruct (Rle_bool_spec Q900 (Rabs N)) as [GN|GN]; [|discriminate].
  destruct (Rle_bool_spec Q900 (Rabs D)) as [GD|GD]; [|discriminate].
  destruct (Rle_bool_spec Q900 (Rabs q0)) as [Gq|Gq]; [|discriminate].
  cbn [andb].
  rewrite quotient_enclosure_factor_val, quotient_relative_val, quotient_test_factor_val.
  destruct (quotient_residuals N Nlo D Dlo BN BNlo BD BDlo LN LD GN GD Gq) as [A2 [RR [Ec [Hc HcD]]]].
  fold q0 in A2, RR, Ec, Hc, HcD.
  set (rr := RN (fma (- q0) D N + fma (- q0) Dlo Nlo)) in *.
  set (c := RN (rr / D)) in *.
  destruct (quotient_candidate q0 c ltac:(apply binary64_RN) ltac:(apply binary64_RN) Hc)
    as [X [Lw [Hq1 Hq2]]].
  pose proof (binary64_two_sum_hi q0 c) as Bq. pose proof (binary64_two_sum_lo q0 c) as Bw.
  set (q := fst (two_sum q0 c)) in *. set (w := snd (two_sum q0 c)) in *.
  set (h := half_gap q).
  (* the test *)
  set (xb := RN (Rabs q0 * Ed)). set (xs := RN (xb + En)).
  set (x := RN (xs * (1 + / 512))).
  set (yb := RN (Rabs q0 * (32 * (u * u)))). set (ys := RN (yb + Rabs w)).
  set (y := RN (ys * Rabs D)).
  set (xy := RN (x + y)).
  destruct (Rlt_bool_spec (RN (xy * (1 + / 35184372088832))) (RN (h * Rabs D))) as [Test|Test];
    [|discriminate].
  intros _.
  (* constants and signs *)
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof Q900_pos as HQ. pose proof eta_Q900 as EQ.
  pose proof Q900_normal as QN.
  assert (PEn : 0 <= En) by (eapply Rle_trans; [apply Rabs_pos | exact Hn]).
  assert (PEd : 0 <= Ed) by (eapply Rle_trans; [apply Rabs_pos | exact Hd]).
  set (aD := Rabs D) in *. set (aq := Rabs q0) in *.
  assert (DP : 0 < aD) by lra.
  assert (Dnz : D <> 0) by (intros Z; unfold aD in DP; rewrite Z, Rabs_R0 in DP; lra).
  assert (AP : 0 < aq * aD) by (apply Rmult_lt_0_compat; lra).
  assert (Eta_A : eta <= / 2 ^ 174 * (aq * aD)) by (rewrite EQ; simpl; lra).
  assert (Eta_aD : eta * aD <= / 2 ^ 175 * (aq * aD)).
  { rewrite <- Rmult_assoc. apply Rmult_le_compat_r; [lra|]. rewrite EQ. simpl. lra. }
  (* the half gap of q *)
  destruct (half_gap_bounds q) as [Ph _]. fold h in Ph.
  assert (Hh : h <= u * Rabs q).
  { apply half_gap_le_u. lra. }
  (* the rounded test, term by term *)
  set (B := aq * Ed).
  assert (PB : 0 <= B) by (unfold B; apply Rmult_le_pos; lra).
  assert (Exb : Rabs (xb - B) <= u * B + eta).
  { pose proof (RN_err B) as E. rewrite (Rabs_nonneg_eq B PB) in E. exact E. }
  assert (Pxb : 0 <= xb) by (apply RN_nonneg; exact PB).
  assert (Exs : Rabs (xs - (xb + En)) <= u * (xb + En)).
  { pose proof (RN_plus_err xb En ltac:(apply binary64_RN) BEn) as E.
    rewrite (Rabs_nonneg_eq (xb + En)) in E by lra. exact E. }
  assert (Pxs : 0 <= xs) by (apply RN_nonneg; lra).
  assert (Ex : Rabs (x - xs * (1 + / 512)) <= u * (xs * (1 + / 512)) + eta).
  { pose proof (RN_err (xs * (1 + / 512))) as E.
    rewrite (Rabs_nonneg_eq (xs * (1 + / 512))) in E by (apply Rmult_le_pos; lra). exact E. }
  assert (Pyb0 : 0 <= aq * (32 * (u * u))) by (rewrite u_val; apply Rmult_le_pos; lra).
  assert (Eyb : Rabs (yb - aq * (32 * (u * u))) <= u * (aq * (32 * (u * u))) + eta).
  { pose proof (RN_err (aq * (32 * (u * u)))) as E. rewrite (Rabs_nonneg_eq _ Pyb0) in E. exact E. }
  assert (Pyb : 0 <= yb) by (apply RN_nonneg; exact Pyb0).
  pose proof (Rabs_pos w) as Pw.
  assert (Eys : Rabs (ys - (yb + Rabs w)) <= u * (yb + Rabs w)).
  { pose proof (RN_plus_err yb (Rabs w) ltac:(apply binary64_RN) (binary64_abs w Bw)) as E.
    rewrite (Rabs_nonneg_eq (yb + Rabs w)) in E by lra. exact E. }
  assert (Pys : 0 <= ys) by (apply RN_nonneg; lra).
  assert (Ey : Rabs (y - ys * aD) <= u * (ys * aD) + eta).
  { pose proof (RN_err (ys * aD)) as E. rewrite (Rabs_nonneg_eq (ys * aD)) in E by (apply Rmult_le_pos; lra). exact E. }
  assert (Fys : (1 - u) * (yb + Rabs w) * aD <= ys * aD).
  { apply Rmult_le_compat_r; [lra|]. apply Rabs_bounds in Eys. lra. }
  assert (Fyb : ((1 - u) * (aq * (32 * (u * u))) - eta) * aD <= yb * aD).
  { apply Rmult_le_compat_r; [lra|]. apply Rabs_bounds in Eyb. lra. }
  assert (Px : 0 <= x) by (apply RN_nonneg, Rmult_le_pos; lra).
  assert (Py : 0 <= y) by (apply RN_nonneg, Rmult_le_pos; lra).
  assert (Exy : Rabs (xy - (x + y)) <= u * (x + y)).
  { pose proof (RN_plus_err x y ltac:(apply binary64_RN) ltac:(apply binary64_RN)) as E.
    rewrite (Rabs_nonneg_eq (x + y)) in E by lra. exact E. }
  assert (Pxy : 0 <= xy) by (apply RN_nonneg; lra).
  assert (EL : Rabs (RN (xy * (1 + / 35184372088832)) - xy * (1 + / 35184372088832)) <=
               u * (xy * (1 + / 35184372088832)) + eta).
  { pose proof (RN_err (xy * (1 + / 35184372088832))) as E.
    rewrite (Rabs_nonneg_eq (xy * (1 + / 35184372088832))) in E by (apply Rmult_le_pos; lra). exact E. }
  assert (ER : Rabs (RN (h * aD) - h * aD) <= u * (h * aD) + eta).
  { pose proof (RN_err (h * aD)) as E. rewrite (Rabs_nonneg_eq (h * aD)) in E by (apply Rmult_le_pos; lra). exact E. }
  (* the test implies Z < h |D| *)
  set (Z := (1 + / 512) * (En + B) + 32 * (u * u) * (aq * aD) + Rabs w * aD).
  assert (PwD : 0 <= Rabs w * aD) by (apply Rmult_le_pos; lra).
  assert (TZ : Z < h * aD).
  { apply Rabs_bounds in Exb. apply Rabs_bounds in Exs. apply Rabs_bounds in Ex.
    apply Rabs_bounds in Eyb. apply Rabs_bounds in Eys. apply Rabs_bounds in Ey.
    apply Rabs_bounds in Exy. apply Rabs_bounds in EL. apply Rabs_bounds in ER.
    unfold Z. rewrite u_val in *. simpl in *. lra. }
  (* hence Ed ≤ u |D|, and den ≠ 0 with |den| ≥ (1 − 2u)|D| *)
  assert (HhD : h * aD <= u * Rabs q * aD) by (apply Rmult_le_compat_r; lra).
  assert (HqD : Rabs q * aD <= (1 + 7 * u) * (aq * aD)).
  { rewrite <- Rmult_assoc. apply Rmult_le_compat_r; lra. }
  assert (EdD : Ed <= u * aD).
  { assert (aq * ((1 + / 512) * Ed) < aq * (u * (1 + 7 * u) * aD)).
    { unfold Z, B in TZ. rewrite u_val in *. lra. }
    apply Rmult_lt_reg_l in H; [|lra]. rewrite u_val in *. lra. }
  assert (Hden : (1 - 2 * u) * aD <= Rabs den).
  { assert (aD <= Rabs den + Rabs (den - (dh + dl)) + Rabs Dlo).
    { unfold aD. replace D with (den - (den - (dh + dl)) - Dlo) by lra.
      unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
      pose proof (Rabs_triang den (- (den + - (dh + dl)))). rewrite Rabs_Ropp in *. lra. }
    lra. }
  assert (den_nz : den <> 0).
  { intros Z0. rewrite Z0, Rabs_R0 in Hden. rewrite u_val in Hden. lra. }
  split; [exact den_nz|].
  (* the error of q0 + c *)
  set (en := num - (nh + nl)). set (ed := den - (dh + dl)).
  assert (Ident : num - (q0 + c) * den =
    ((N - q0 * D) + (Nlo - q0 * Dlo) - rr) + (rr - c * D) - c * Dlo + en - (q0 + c) * ed).
  { unfold en, ed. rewrite <- XN, <- XD. ring. }
  assert (Hqc : Rabs (q0 + c) <= (1 + 5 * u) * aq).
  { eapply Rle_trans; [apply Rabs_triang|]. unfold aq in *. lra. }
  assert (Hqced : Rabs ((q0 + c) * ed) <= (1 + 5 * u) * B).
  { rewrite Rabs_mult. unfold B.
    apply Rle_trans with (Rabs (q0 + c) * Ed).
    - apply Rmult_le_compat_l; [apply Rabs_pos | exact Hd].
    - rewrite <- Rmult_assoc. apply Rmult_le_compat_r; [exact PEd | exact Hqc]. }
  assert (M : Rabs (num - (q0 + c) * den) <= 17 * (u * u) * (aq * aD) + En + (1 + 5 * u) * B).
  { rewrite Ident.
    pose proof (Rabs_sum5 ((N - q0 * D) + (Nlo - q0 * Dlo) - rr) (rr - c * D) (- (c * Dlo)) en
                          (- ((q0 + c) * ed))) as T5.
    rewrite !Rabs_Ropp in T5. rewrite (Rabs_minus_sym rr) in T5.
    replace (N - q0 * D + (Nlo - q0 * Dlo) - rr + (rr - c * D) + - (c * Dlo) + en + - ((q0 + c) * ed))
      with (N - q0 * D + (Nlo - q0 * Dlo) - rr + (rr - c * D) - c * Dlo + en - (q0 + c) * ed) in T5 by ring.
    unfold en at 2 in T5. lra. }
  (* |num/den − (q0 + c)|·|D| ≤ (1 + 2^-9)(En + B) + 2^-101 A *)
  set (tq := num / den - (q0 + c)).
  assert (Etq : Rabs tq * Rabs den = Rabs (num - (q0 + c) * den)).
  { rewrite <- Rabs_mult. f_equal. unfold tq. field. exact den_nz. }
  assert (Ftq : Rabs tq * ((1 - 2 * u) * aD) <= Rabs tq * Rabs den).
  { apply Rmult_le_compat_l; [apply Rabs_pos | exact Hden]. }
  assert (Close : (Rabs tq + Rabs w) * aD < h * aD).
  { unfold Z, B in TZ. unfold B in M, PB. rewrite u_val in *. lra. }
  apply Rmult_lt_reg_r in Close; [|exact DP].
  symmetry. apply RN_of_close; [exact Bq|].
  replace (num / den - q) with (tq + w) by (unfold tq; lra).
  eapply Rle_lt_trans; [apply Rabs_triang | exact Close].
Qed.

(** [round_quotient] (the optional form that the cascade in intersect_certified.cpp uses). *)
Theorem round_quotient_sound : forall (n d : Enclosure) (num den t : R),
  binary64 (hi n) -> binary64 (lo n) -> binary64 (radius n) ->
  binary64 (hi d) -> binary64 (lo d) -> binary64 (radius d) ->
  encloses n num -> encloses d den ->
  round_quotient n d = Some t ->
  den <> 0 /\ t = RN (num / den).
Proof.
  intros n d num den t Bnh Bnl BEn Bdh Bdl BEd Hn Hd H.
  pose proof (round_quotient_decision_sound n d num den Bnh Bnl BEn Bdh Bdl BEd Hn Hd) as S.
  unfold round_quotient in H.
  destruct (round_quotient_decision n d) as [q certain]. cbn [fst snd] in H, S.
  destruct certain; [|discriminate]. injection H as <-. now apply S.
Qed.
