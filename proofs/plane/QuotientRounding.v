(** * round_quotient: the correctly rounded t = num/den from two enclosures, with one reciprocal of
    the denominator (kernel/src/core/quotient_rounding.hpp).

    Main theorem: [round_quotient_sound]: for all reals num, den and enclosures n, d of doubles with
    |num − (n.hi + n.lo)| ≤ n.radius and |den − (d.hi + d.lo)| ≤ d.radius, whenever
    [round_quotient n (prepare_divisor d)] says certain, den ≠ 0 and its t = RN(num/den), round to
    nearest with ties to even.  [round_quotient_if_certain_sound] is the same for the optional form.
    [round_quotient_candidate_normal]: a certain t has |t| ≥ 2^-900 ≥ 2^-968 = half_gap_min_magnitude, the
    range where the C++ bit manipulation [half_gap_to_nearer_neighbour] computes the model's [half_gap]
    ([half_gap_bits]).

    The derivation of error_bounds.hpp ("round_quotient") is what the proof follows: with A = |q0|·|D|,
    the residual ρ_1 + ρ_2 = (N − q0·D) + (n − q0·d) is computed to within 9u²A, c·D to within 9u²A of
    the computed residual, c·d is at most 5u²A, so |X − (q0 + c)·Y| ≤ 23u²A (X = N + n, Y = D + d), which
    the constant 2^-101 = 32u² covers with the enclosures' errors and every absolute error η (the guard
    |q| ≥ 2^-900 makes η ≤ 2^-170·|q0| and η·|D| ≤ 2^-170·A). *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core Relative Pff2Flocq.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated.
Open Scope R_scope.

Notation succ64 := (succ radix2 (FLT_exp (-1074) 53)).
Notation pred64 := (pred radix2 (FLT_exp (-1074) 53)).

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

(** For |q| ≥ 2^-968 = [half_gap_min_magnitude] (so that the result is normal), the model's half gap is
    the number half_gap_to_nearer_neighbour builds from q's exponent bits: 2^(e−53) for q in
    [2^e, 2^(e+1)), 2^(e−54) when |q| = 2^e (e = mag q − 1). *)
Theorem half_gap_bits : forall q, binary64 q -> half_gap_min_magnitude <= Rabs q ->
  half_gap q = if Req_bool (Rabs q) (bpow radix2 (mag radix2 q - 1)) then bpow radix2 (mag radix2 q - 55)
               else bpow radix2 (mag radix2 q - 54).
Proof.
  unfold half_gap_min_magnitude.
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

(** ** prepare_divisor and round_quotient, operation by operation, branch-free as in the C++: every
    guard and the test are computed, and [certain] is their conjunction.  The model has no infinities
    or NaN (proofs/README.md, "Overflow"); the guard |q| ≤ largest_finite is kept as written. *)

(** [DivisorT]: the renormalized enclosure (hi, lo) = TwoSum of the enclosure's parts, its radius, the
    reciprocal 1 ⊘ hi and the guard 2^-1000 ≤ |hi| ≤ 2^1000. *)
Record Divisor := {
  div_hi : R; div_lo : R; div_radius : R;
  div_reciprocal : R;
  div_in_range : bool }.

(** [prepare_divisor(den)]: out of range, the divisor is replaced by 1 before dividing
    ([select(in_range, D.hi, one)]). *)
Definition prepare_divisor (den : Enclosure) : Divisor :=
  let D := two_sum (hi den) (lo den) in
  let abs_D := Rabs (fst D) in
  let in_range := (Rle_bool divisor_min_magnitude abs_D && Rle_bool abs_D divisor_max_magnitude)%bool in
  {| div_hi := fst D; div_lo := snd D; div_radius := radius den;
     div_reciprocal := RN (1 / (if in_range then fst D else 1));
     div_in_range := in_range |}.

(** [QuotientRoundingT]: t and whether it is certified. *)
Record QuotientRounding := { qr_t : R; qr_certain : bool }.

(** [round_quotient(num, den)]. *)
Definition round_quotient (num : Enclosure) (den : Divisor) : QuotientRounding :=
  let N := fst (two_sum (hi num) (lo num)) in
  let n := snd (two_sum (hi num) (lo num)) in
  let q0 := RN (N * div_reciprocal den) in
  let r1 := fma (- q0) (div_hi den) N in
  let r2 := fma (- q0) (div_lo den) n in
  let c := RN (RN (r1 + r2) * div_reciprocal den) in
  let q := RN (q0 + c) in
  let w := RN (c - RN (q - q0)) in
  let abs_q0 := Rabs q0 in
  let abs_D := Rabs (div_hi den) in
  let abs_q := Rabs q in
  let in_range := (Rle_bool quotient_min_magnitude (Rabs N) && div_in_range den &&
                   (Rle_bool quotient_min_magnitude abs_q && Rle_bool abs_q largest_finite))%bool in
  let x := RN (RN (RN (abs_q0 * div_radius den) + radius num) * quotient_enclosure_factor) in
  let y := RN (RN (RN (abs_q0 * quotient_relative) + Rabs w) * abs_D) in
  let h := half_gap q in
  {| qr_t := q;
     qr_certain := (in_range && Rlt_bool (RN (RN (x + y) * quotient_test_factor)) (RN (h * abs_D)))%bool |}.

(** [round_quotient_if_certain(num, den)]: the same decision as an optional. *)
Definition round_quotient_if_certain (num : Enclosure) (den : Divisor) : option R :=
  let r := round_quotient num den in
  if qr_certain r then Some (qr_t r) else None.

(** ** Constants. *)

Notation Q900 := quotient_min_magnitude.

Lemma Q900_pos : 0 < Q900.
Proof. apply bpow_gt_0. Qed.

Lemma eta_Q900 : eta = / 2 ^ 175 * Q900.
Proof.
  unfold eta, quotient_min_magnitude. replace (-1075)%Z with (-175 + -900)%Z by lia.
  rewrite bpow_plus. f_equal. simpl. lra.
Qed.

Lemma Q900_normal : bpow radix2 (-1022) <= Q900.
Proof. apply bpow_le. lia. Qed.

Lemma quotient_relative_val : quotient_relative = 32 * (u * u).
Proof. unfold quotient_relative. rewrite u_val. simpl bpow. lra. Qed.

Lemma quotient_enclosure_factor_val : quotient_enclosure_factor = 1 + / 512.
Proof. unfold quotient_enclosure_factor. simpl bpow. lra. Qed.

Lemma quotient_test_factor_val : quotient_test_factor = 1 + / 35184372088832.
Proof. unfold quotient_test_factor. simpl bpow. lra. Qed.

(** The constants of this file are doubles, as the C++ literals of the same names are. *)
Lemma quotient_constants_binary64 :
  binary64 quotient_min_magnitude /\ binary64 divisor_min_magnitude /\ binary64 divisor_max_magnitude /\
  binary64 half_gap_min_magnitude /\ binary64 largest_finite /\ binary64 exact_product_threshold.
Proof.
  repeat split; try (apply binary64_bpow; lia).
  replace largest_finite with (IZR 9007199254740991 * bpow radix2 971).
  - apply binary64_dyadic; [reflexivity | lia].
  - reflexivity.
Qed.

(** ** The divisor: in range, D = hi ⊕ lo and d = the TwoSum error are doubles with D + d = hi + lo,
    |d| ≤ u|D|, and R = RN(1/D) with |R·D − 1| ≤ u (1/D is normal: 2^-1000 ≤ |1/D| ≤ 2^1000). *)
Lemma prepare_divisor_spec : forall den, binary64 (hi den) -> binary64 (lo den) ->
  let dv := prepare_divisor den in
  div_in_range dv = true ->
  binary64 (div_hi dv) /\ binary64 (div_lo dv) /\ div_hi dv + div_lo dv = hi den + lo den /\
  Rabs (div_lo dv) <= u * Rabs (div_hi dv) /\ div_radius dv = radius den /\
  divisor_min_magnitude <= Rabs (div_hi dv) <= divisor_max_magnitude /\
  Rabs (div_reciprocal dv * div_hi dv - 1) <= u.
Proof.
  intros [h l e] Bh Bl dv G. cbn [hi lo radius] in *.
  pose proof (two_sum_exact h l Bh Bl) as X.
  destruct (two_sum_lo_bound h l Bh Bl) as [_ L].
  unfold dv, prepare_divisor in G |- *. cbn [div_hi div_lo div_radius div_reciprocal div_in_range] in G |- *.
  cbn [hi lo radius] in G |- *. rewrite G.
  set (D := fst (two_sum h l)) in *.
  revert G.
  destruct (Rle_bool_spec divisor_min_magnitude (Rabs D)) as [G1|G1]; [|discriminate].
  destruct (Rle_bool_spec (Rabs D) divisor_max_magnitude) as [G2|G2]; [|discriminate].
  intros _.
  assert (DP : 0 < Rabs D) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact G1]).
  assert (Dnz : D <> 0) by (intros Z; rewrite Z, Rabs_R0 in DP; lra).
  repeat split; try assumption; [apply binary64_two_sum_hi | apply binary64_two_sum_lo |].
  (* |1/D| ≥ 2^-1000 is normal *)
  assert (Inv : bpow radix2 (-1022) <= Rabs (1 / D)).
  { unfold Rdiv. rewrite Rmult_1_l, Rabs_inv.
    apply Rle_trans with (/ divisor_max_magnitude).
    - unfold divisor_max_magnitude. rewrite <- bpow_opp. apply bpow_le. lia.
    - apply Rinv_le_contravar; assumption. }
  pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) _ Inv) as E.
  rewrite half_bpow_52 in E.
  replace (RN (1 / D) * D - 1) with ((RN (1 / D) - 1 / D) * D) by (field; exact Dnz).
  rewrite Rabs_mult.
  apply Rle_trans with (u * Rabs (1 / D) * Rabs D); [apply Rmult_le_compat_r; [apply Rabs_pos | exact E]|].
  rewrite Rmult_assoc, <- Rabs_mult. replace (1 / D * D) with 1 by (field; exact Dnz).
  rewrite Rabs_R1. lra.
Qed.

(** What the residual analysis gives for q0, the residual rr and the correction c, with A = |q0|·|D|. *)
Definition residual_facts (N n D d q0 rr c : R) : Prop :=
  let A := Rabs q0 * Rabs D in
  0 < A /\ eta * Rabs D <= / 2 ^ 170 * A /\ eta <= / 2 ^ 170 * A /\
  Rabs ((N - q0 * D) + (n - q0 * d) - rr) <= 9 * (u * u) * A /\
  Rabs (c * D - rr) <= 9 * (u * u) * A /\
  Rabs c <= 5 * u * Rabs q0 /\
  Rabs (c * d) <= 5 * (u * u) * A.

(** ** The residuals, once the guards pass (the derivation of error_bounds.hpp): with A = |q0|·|D|,
    the guard |q| ≥ 2^-900 (with |N| ≥ 2^-900) makes η and η·|D| at most 2^-170·A; the computed residual
    rr is within 9u²A of ρ_1 + ρ_2 = (N − q0 D) + (n − q0 d); c·D is within 9u²A of rr; |c| ≤ 5u|q0|
    (so the Fast2Sum is exact) and |c·d| ≤ 5u²A.  R is any real with |R·D − 1| ≤ u. *)
(** [quotient_residuals_gen] is stated with the guard Q900·|D| ≤ 2(|q0| + |c|)·|D|, which both callers' guards
    imply: |q| ≥ 2^-900 for the candidate q = RN(q0 + c) ([quotient_residuals], here) and |q0| ≥ 2^-901
    (QuotientLiveness.v's [quotient_residuals_q0]). *)
Lemma quotient_residuals_gen : forall N n D d R,
  binary64 N -> binary64 n -> binary64 D -> binary64 d ->
  Rabs n <= u * Rabs N -> Rabs d <= u * Rabs D ->
  Q900 <= Rabs N -> D <> 0 -> Rabs (R * D - 1) <= u ->
  let q0 := RN (N * R) in
  let rr := RN (fma (- q0) D N + fma (- q0) d n) in
  let c := RN (rr * R) in
  Q900 * Rabs D <= 2 * (Rabs q0 * Rabs D + Rabs c * Rabs D) ->
  residual_facts N n D d q0 rr c.
Proof.
  intros N n D d R BN Bn BD Bd Ln Ld GN Dnz RD q0 rr c Gq. unfold residual_facts. set (A := Rabs q0 * Rabs D).
  pose proof Q900_pos as HQ. pose proof eta_Q900 as EQ. pose proof u_pos as Hu. pose proof eta_pos as He.
  set (aD := Rabs D) in *. set (aq := Rabs q0) in *.
  assert (DP : 0 < aD) by (apply Rabs_pos_lt; exact Dnz).
  assert (Paq : 0 <= aq) by apply Rabs_pos.
  assert (RDb : Rabs (R * D) <= 1 + u) by (pose proof (Rabs_close _ _ _ RD); rewrite Rabs_R1 in *; lra).
  (* q0 = RN(N R) *)
  assert (E0D : Rabs (q0 * D - N * R * D) <= u * A + eta * aD).
  { pose proof (RN_err_round (N * R)) as E. fold q0 in E. fold aq in E.
    replace (q0 * D - N * R * D) with ((q0 - N * R) * D) by ring.
    rewrite Rabs_mult. fold aD. unfold A.
    replace (u * (aq * aD) + eta * aD) with ((u * aq + eta) * aD) by ring.
    apply Rmult_le_compat_r; lra. }
  assert (ENRD : Rabs (N * R * D - N) <= u * Rabs N).
  { replace (N * R * D - N) with (N * (R * D - 1)) by ring. rewrite Rabs_mult.
    rewrite Rmult_comm. apply Rmult_le_compat_r; [apply Rabs_pos | exact RD]. }
  assert (Aq : Rabs (q0 * D) = A) by (unfold A, aq, aD; apply Rabs_mult).
  set (rho1 := N - q0 * D).
  assert (HN : Rabs N <= A + Rabs rho1).
  { replace N with (q0 * D + rho1) by (unfold rho1; ring). rewrite <- Aq. apply Rabs_triang. }
  assert (R1 : Rabs rho1 <= u * Rabs N + (u * A + eta * aD)).
  { unfold rho1. replace (N - q0 * D) with (- (N * R * D - N) - (q0 * D - N * R * D)) by ring.
    unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp, Rabs_Ropp. lra. }
  set (rho2 := n - q0 * d).
  assert (QD : Rabs (q0 * d) <= u * A).
  { rewrite Rabs_mult. fold aq. unfold A.
    replace (u * (aq * aD)) with (aq * (u * aD)) by ring.
    apply Rmult_le_compat_l; [lra | exact Ld]. }
  assert (R2 : Rabs rho2 <= u * Rabs N + u * A).
  { unfold rho2. unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  (* the two FMAs and their sum *)
  assert (Er1 : Rabs (fma (- q0) D N - rho1) <= u * Rabs rho1 + eta).
  { unfold fma. replace (- q0 * D + N) with rho1 by (unfold rho1; ring). apply RN_err. }
  assert (Er2 : Rabs (fma (- q0) d n - rho2) <= u * Rabs rho2 + eta).
  { unfold fma. replace (- q0 * d + n) with rho2 by (unfold rho2; ring). apply RN_err. }
  set (r1 := fma (- q0) D N) in *. set (r2 := fma (- q0) d n) in *.
  pose proof (RN_plus_err r1 r2 ltac:(apply binary64_RN) ltac:(apply binary64_RN)) as Err. fold rr in Err.
  assert (T12 : Rabs (r1 + r2) <= Rabs r1 + Rabs r2) by apply Rabs_triang.
  assert (Hr1 : Rabs r1 <= Rabs rho1 + (u * Rabs rho1 + eta)) by (apply Rabs_close; exact Er1).
  assert (Hr2 : Rabs r2 <= Rabs rho2 + (u * Rabs rho2 + eta)) by (apply Rabs_close; exact Er2).
  assert (Hrr : Rabs rr <= Rabs (r1 + r2) + u * Rabs (r1 + r2)) by (apply Rabs_close; exact Err).
  assert (Tr : Rabs (rho1 + rho2 - rr) <= Rabs (r1 - rho1) + Rabs (r2 - rho2) + Rabs (rr - (r1 + r2))).
  { replace (rho1 + rho2 - rr) with (- (r1 - rho1) + - (r2 - rho2) + - (rr - (r1 + r2))) by ring.
    eapply Rle_trans; [apply Rabs_triang|].
    pose proof (Rabs_triang (- (r1 - rho1)) (- (r2 - rho2))). rewrite !Rabs_Ropp in *. lra. }
  (* c = RN(rr R) *)
  assert (EcD : Rabs (c * D - rr * R * D) <= u * (1 + u) * Rabs rr + eta * aD).
  { pose proof (RN_err (rr * R)) as E. fold c in E.
    replace (c * D - rr * R * D) with ((c - rr * R) * D) by ring.
    rewrite Rabs_mult. fold aD.
    apply Rle_trans with ((u * Rabs (rr * R) + eta) * aD); [apply Rmult_le_compat_r; lra|].
    replace ((u * Rabs (rr * R) + eta) * aD) with (u * (Rabs rr * Rabs (R * D)) + eta * aD)
      by (unfold aD; rewrite !Rabs_mult; ring).
    assert (Rabs rr * Rabs (R * D) <= Rabs rr * (1 + u)) by (apply Rmult_le_compat_l; [apply Rabs_pos | exact RDb]).
    apply Rplus_le_compat_r. replace (u * (1 + u) * Rabs rr) with (u * (Rabs rr * (1 + u))) by ring.
    apply Rmult_le_compat_l; lra. }
  assert (ErrRD : Rabs (rr * R * D - rr) <= u * Rabs rr).
  { replace (rr * R * D - rr) with (rr * (R * D - 1)) by ring. rewrite Rabs_mult.
    rewrite Rmult_comm. apply Rmult_le_compat_r; [apply Rabs_pos | exact RD]. }
  assert (EC : Rabs (c * D - rr) <= u * (1 + u) * Rabs rr + eta * aD + u * Rabs rr).
  { replace (c * D - rr) with ((c * D - rr * R * D) + (rr * R * D - rr)) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. lra. }
  assert (cD : Rabs c * aD <= Rabs rr + (u * (1 + u) * Rabs rr + eta * aD + u * Rabs rr)).
  { unfold aD. rewrite <- Rabs_mult. apply Rabs_close. exact EC. }
  assert (HqD : Q900 * aD <= 2 * (A + Rabs c * aD)) by (unfold A; exact Gq).
  assert (EtaN : eta <= / 2 ^ 175 * Rabs N) by (rewrite EQ; lra).
  assert (EtaD : eta * aD = / 2 ^ 175 * (Q900 * aD)) by (rewrite EQ; ring).
  assert (QDP : 0 < Q900 * aD) by (apply Rmult_lt_0_compat; lra).
  pose proof (Rabs_pos rho1) as P1. pose proof (Rabs_pos rho2) as P2. pose proof (Rabs_pos (r1 + r2)) as P3.
  pose proof (Rabs_pos r1) as P4. pose proof (Rabs_pos r2) as P5. pose proof (Rabs_pos rr) as P6.
  pose proof (Rabs_pos c) as P7.
  assert (Ccd : Rabs (c * d) <= u * (Rabs c * aD)).
  { rewrite Rabs_mult. replace (u * (Rabs c * aD)) with (Rabs c * (u * aD)) by ring.
    apply Rmult_le_compat_l; [lra | exact Ld]. }
  set (E1 := eta * aD) in *. set (QD0 := Q900 * aD) in *. set (cD0 := Rabs c * aD) in *.
  assert (cD0_def : cD0 = Rabs c * aD) by reflexivity.
  clearbody E1 QD0 cD0.
  rewrite u_val in *.
  assert (AP : 0 < A) by (simpl in *; lra).
  assert (S1 : E1 <= / 2 ^ 170 * A) by (simpl in *; lra).
  assert (S0 : eta <= / 2 ^ 170 * A) by (simpl in *; lra).
  assert (Brr : Rabs rr <= 401 / 100 * / 9007199254740992 * A).
  { clear -Hr1 Hr2 T12 Hrr HN R1 R2 S0 S1 AP He Hu P1 P2 P3 P4 P5 P6. simpl in *. lra. }
  assert (Bc : cD0 <= 41 / 10 * / 9007199254740992 * A) by (simpl in *; lra).
  repeat split; try assumption.
  - simpl in *. lra.
  - simpl in *. lra.
  - apply Rmult_le_reg_r with aD; [exact DP|]. rewrite <- cD0_def. unfold A in Bc, AP. lra.
  - simpl in *. lra.
Qed.

Lemma quotient_residuals : forall N n D d R,
  binary64 N -> binary64 n -> binary64 D -> binary64 d ->
  Rabs n <= u * Rabs N -> Rabs d <= u * Rabs D ->
  Q900 <= Rabs N -> D <> 0 -> Rabs (R * D - 1) <= u ->
  let q0 := RN (N * R) in
  let rr := RN (fma (- q0) D N + fma (- q0) d n) in
  let c := RN (rr * R) in
  Q900 <= Rabs (RN (q0 + c)) ->
  residual_facts N n D d q0 rr c.
Proof.
  intros N n D d R BN Bn BD Bd Ln Ld GN Dnz RD.
  pose proof (quotient_residuals_gen N n D d R BN Bn BD Bd Ln Ld GN Dnz RD) as G. cbv zeta in G |- *.
  intros Gq. apply G.
  (* the candidate q = RN(q0 + c): |q| ≤ (1 + u)(|q0| + |c|) *)
  pose proof (binary64_RN (N * R)) as Bq0.
  pose proof (binary64_RN (RN (fma (- RN (N * R)) D N + fma (- RN (N * R)) d n) * R)) as Bc.
  revert Gq Bq0 Bc. generalize (RN (N * R)) (RN (RN (fma (- RN (N * R)) D N + fma (- RN (N * R)) d n) * R)).
  intros q0 c Gq' Bq0 Bc. pose proof u_pos as Hu. pose proof (Rabs_pos D) as PD.
  pose proof (RN_plus_err q0 c Bq0 Bc) as Eq.
  pose proof (Rabs_close _ _ _ Eq) as H1. pose proof (Rabs_triang q0 c) as H2. pose proof (Rabs_pos (q0 + c)).
  assert (Hq : Rabs (RN (q0 + c)) <= 2 * (Rabs q0 + Rabs c)) by (rewrite u_val in *; lra).
  apply Rle_trans with (Rabs (RN (q0 + c)) * Rabs D); [apply Rmult_le_compat_r; lra|].
  replace (2 * (Rabs q0 * Rabs D + Rabs c * Rabs D)) with (2 * (Rabs q0 + Rabs c) * Rabs D) by ring.
  apply Rmult_le_compat_r; lra.
Qed.

(** The candidate q = q0 ⊕ c and w = c ⊖ (q ⊖ q0) (Fast2Sum, Flocq [Fast2Sum_correct], exact since
    |c| ≤ |q0|): q + w = q0 + c, |q| ≤ (1 + 7u)|q0| and |q0| ≤ 2|q|. *)
Lemma quotient_candidate : forall q0 c, binary64 q0 -> binary64 c -> Rabs c <= 5 * u * Rabs q0 ->
  let q := RN (q0 + c) in let w := RN (c - RN (q - q0)) in
  q + w = q0 + c /\ Rabs q <= (1 + 7 * u) * Rabs q0 /\ Rabs q0 <= 2 * Rabs q.
Proof.
  intros q0 c Bq0 Bc Hc q w.
  pose proof u_pos as Hu. pose proof (Rabs_pos q0) as P0.
  assert (X : q + w = q0 + c).
  { unfold w. replace (RN (q - q0)) with (- RN (q0 - q)) by (rewrite <- RN_opp; f_equal; ring).
    replace (c - - RN (q0 - q)) with (c + RN (q0 - q)) by ring.
    unfold q. apply (Fast2Sum_correct (-1074) 53 (fun t => negb (Z.even t))); try easy.
    - exact ZnearestE_sym.
    - rewrite u_val in Hc. lra. }
  pose proof (RN_plus_err q0 c Bq0 Bc) as E. fold q in E.
  pose proof (Rabs_triang q0 c) as T1.
  assert (T2 : Rabs q0 <= Rabs (q0 + c) + Rabs c).
  { replace q0 with ((q0 + c) + - c) at 1 by ring. eapply Rle_trans; [apply Rabs_triang|].
    rewrite Rabs_Ropp. lra. }
  pose proof (Rabs_close _ _ _ E) as H1. pose proof (Rabs_close' _ _ _ E) as H2.
  pose proof (Rabs_pos (q0 + c)).
  repeat split; [exact X | rewrite u_val in *; nra | rewrite u_val in *; nra].
Qed.

(** The certifying test, read back (used by [round_quotient_sound] and QuotientDivisorBound.v's
    [round_quotient_certain_divisor]): with q0 the first quotient, q the candidate, w its Fast2Sum tail,
    D the divisor's high part and Dlo its low part (D + Dlo = s, the divisor's double-double), a passed test
    RN((x ⊕ y)·(1 + 2^-45)) < RN(h·|D|) bounds the real left side Z by h·|D|; hence E_d ≤ u·|D| and any
    den within E_d of s has |den| ≥ (1 − 2u)|D|. *)
Lemma quotient_test_certifies : forall (En Ed q0 q w D Dlo s den : R),
  binary64 En -> binary64 w -> 0 <= En -> Rabs (den - s) <= Ed -> D + Dlo = s -> Rabs Dlo <= u * Rabs D ->
  0 < Rabs D -> 0 < Rabs q0 * Rabs D -> eta * Rabs D <= / 2 ^ 170 * (Rabs q0 * Rabs D) ->
  eta <= / 2 ^ 170 * (Rabs q0 * Rabs D) -> Q900 <= Rabs q -> Rabs q <= (1 + 7 * u) * Rabs q0 ->
  let h := half_gap q in
  let x := RN (RN (RN (Rabs q0 * Ed) + En) * (1 + / 512)) in
  let y := RN (RN (RN (Rabs q0 * (32 * (u * u))) + Rabs w) * Rabs D) in
  RN (RN (x + y) * (1 + / 35184372088832)) < RN (h * Rabs D) ->
  (1 + / 512) * (En + Rabs q0 * Ed) + 32 * (u * u) * (Rabs q0 * Rabs D) + Rabs w * Rabs D < h * Rabs D /\
  Ed <= u * Rabs D /\ (1 - 2 * u) * Rabs D <= Rabs den.
Proof.
  intros En Ed q0 q w D Dlo s den BEn Bw PEn Hd XD LD DP AP Eta_aD Eta_A Gq Hq1 h x y Test.
  set (xb := RN (Rabs q0 * Ed)) in *. set (xs := RN (xb + En)) in *.
  set (yb := RN (Rabs q0 * (32 * (u * u)))) in *. set (ys := RN (yb + Rabs w)) in *.
  set (xy := RN (x + y)) in *.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof Q900_normal as QN.
  assert (PEd : 0 <= Ed) by (eapply Rle_trans; [apply Rabs_pos | exact Hd]).
  set (aD := Rabs D) in *. set (aq := Rabs q0) in *.
  destruct (half_gap_bounds q) as [Ph _]. fold h in Ph.
  assert (Hh : h <= u * Rabs q) by (apply half_gap_le_u; lra).
  set (B := aq * Ed).
  assert (PB : 0 <= B) by (unfold B; apply Rmult_le_pos; [apply Rabs_pos | lra]).
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
  assert (Paq : 0 <= aq) by apply Rabs_pos.
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
  set (Z := (1 + / 512) * (En + B) + 32 * (u * u) * (aq * aD) + Rabs w * aD).
  assert (PwD : 0 <= Rabs w * aD) by (apply Rmult_le_pos; lra).
  assert (Eta_aD' : eta * aD <= / 2 ^ 170 * (aq * aD)) by exact Eta_aD.
  assert (TZ : Z < h * aD).
  { apply Rabs_bounds in Exb. apply Rabs_bounds in Exs. apply Rabs_bounds in Ex.
    apply Rabs_bounds in Eyb. apply Rabs_bounds in Eys. apply Rabs_bounds in Ey.
    apply Rabs_bounds in Exy. apply Rabs_bounds in EL. apply Rabs_bounds in ER.
    unfold Z. rewrite u_val in *. simpl in *. lra. }
  assert (HhD : h * aD <= u * Rabs q * aD) by (apply Rmult_le_compat_r; lra).
  assert (HqD : Rabs q * aD <= (1 + 7 * u) * (aq * aD)).
  { rewrite <- Rmult_assoc. apply Rmult_le_compat_r; lra. }
  assert (EdD : Ed <= u * aD).
  { assert (aq * ((1 + / 512) * Ed) < aq * (u * (1 + 7 * u) * aD)).
    { unfold Z, B in TZ, HqD. rewrite u_val in *. lra. }
    assert (aqP : 0 < aq) by (apply Rmult_lt_reg_r with aD; [exact DP | rewrite Rmult_0_l; exact AP]).
    apply Rmult_lt_reg_l in H; [|exact aqP]. rewrite u_val in *. lra. }
  assert (Hden : (1 - 2 * u) * aD <= Rabs den).
  { assert (aD <= Rabs den + Rabs (den - s) + Rabs Dlo).
    { unfold aD. replace D with (den - (den - s) - Dlo) by lra.
      unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
      pose proof (Rabs_triang den (- (den + - s))). rewrite Rabs_Ropp in *. lra. }
    lra. }
  split; [exact TZ | split; assumption].
Qed.

(** The opening that [round_quotient_sound] and QuotientDivisorBound.v's [round_quotient_certain_divisor]
    share: with the numerator [nh + nl ± En] and the divisor [dd] introduced, [Sd] the divisor's
    [prepare_divisor_spec] and [H] the hypothesis that [round_quotient] certifies (unfolded), it passes the
    guards, names every intermediate of round_quotient (N, Nlo, D, Dlo, R, Ed, q0, rr, c, q, w, h, x, y, xy)
    with their facts ([quotient_residuals], [quotient_candidate]) and leaves the passed test as [Test]. *)
Ltac open_certified_quotient nh nl En dd dv Bnh Bnl Sd H :=
  pose proof (two_sum_exact nh nl Bnh Bnl) as XN;
  destruct (two_sum_lo_bound nh nl Bnh Bnl) as [_ LN];
  pose proof (binary64_two_sum_hi nh nl) as BN;
  pose proof (binary64_two_sum_lo nh nl) as BNlo;
  set (N := fst (two_sum nh nl)) in *;
  set (Nlo := snd (two_sum nh nl)) in *;
  revert H;
  destruct (Rle_bool_spec Q900 (Rabs N)) as [GN|GN]; [|discriminate];
  destruct (div_in_range dv) eqn:Gd; [|discriminate];
  destruct (Sd Gd) as [BD [BDlo [XD [LD [ED [[GD1 GD2] RD]]]]]];
  rewrite ED;
  clear Sd ED;
  set (D := div_hi dv) in *;
  set (Dlo := div_lo dv) in *;
  set (R := div_reciprocal dv) in *;
  set (Ed := radius dd) in *;
  assert (DP : 0 < Rabs D) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact GD1]);
  assert (Dnz : D <> 0) by (intros Z; rewrite Z, Rabs_R0 in DP; lra);
  set (q0 := RN (N * R));
  set (rr := RN (fma (- q0) D N + fma (- q0) Dlo Nlo));
  set (c := RN (rr * R));
  set (q := RN (q0 + c));
  destruct (Rle_bool_spec Q900 (Rabs q)) as [Gq|Gq]; [|discriminate];
  destruct (Rle_bool_spec (Rabs q) largest_finite) as [_|_]; [|discriminate];
  cbn [andb];
  rewrite quotient_enclosure_factor_val, quotient_relative_val, quotient_test_factor_val;
  destruct (quotient_residuals N Nlo D Dlo R BN BNlo BD BDlo LN LD GN Dnz RD Gq)
      as [AP [Eta_aD [Eta_A [RR [Ec [Hc HcD]]]]]];
  fold q0 rr c in AP, Eta_aD, Eta_A, RR, Ec, Hc, HcD;
  destruct (quotient_candidate q0 c ltac:(apply binary64_RN) ltac:(apply binary64_RN) Hc)
      as [X [Hq1 Hq2]];
  fold q in X, Hq1, Hq2;
  set (w := RN (c - RN (q - q0))) in *;
  assert (Bq : binary64 q) by apply binary64_RN;
  assert (Bw : binary64 w) by apply binary64_RN;
  set (h := half_gap q);
  set (xb := RN (Rabs q0 * Ed));
  set (xs := RN (xb + En));
  set (x := RN (xs * (1 + / 512)));
  set (yb := RN (Rabs q0 * (32 * (u * u))));
  set (ys := RN (yb + Rabs w));
  set (y := RN (ys * Rabs D));
  set (xy := RN (x + y));
  destruct (Rlt_bool_spec (RN (xy * (1 + / 35184372088832))) (RN (h * Rabs D))) as [Test|Test];
      [|discriminate];
  intros _.

(** ** Main theorem: whenever round_quotient says certain, den ≠ 0 and t = RN(num/den). *)
Theorem round_quotient_sound : forall (n d : Enclosure) (num den : R),
  binary64 (hi n) -> binary64 (lo n) -> binary64 (radius n) ->
  binary64 (hi d) -> binary64 (lo d) -> binary64 (radius d) ->
  encloses n num -> encloses d den ->
  qr_certain (round_quotient n (prepare_divisor d)) = true ->
  den <> 0 /\ qr_t (round_quotient n (prepare_divisor d)) = RN (num / den).
Proof.
  intros [nh nl En] dd num den Bnh Bnl BEn Bdh Bdl BEd Hn Hd H.
  unfold encloses in Hn, Hd. cbn [hi lo radius] in *.
  pose proof (prepare_divisor_spec dd Bdh Bdl) as Sd.
  set (dv := prepare_divisor dd) in *.
  unfold round_quotient in H |- *. cbn [hi lo radius qr_t qr_certain] in H |- *.
  open_certified_quotient nh nl En dd dv Bnh Bnl Sd H.
  (* constants and signs *)
  pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (PEn : 0 <= En) by (eapply Rle_trans; [apply Rabs_pos | exact Hn]).
  assert (PEd : 0 <= Ed) by (eapply Rle_trans; [apply Rabs_pos | exact Hd]).
  (* the test bounds Z below h |D|, hence |den| ≥ (1 − 2u)|D| *)
  destruct (quotient_test_certifies En Ed q0 q w D Dlo (hi dd + lo dd) den BEn Bw PEn Hd XD LD DP AP
              Eta_aD Eta_A Gq Hq1 Test) as [TZ [_ Hden]].
  fold h in TZ.
  set (aD := Rabs D) in *. set (aq := Rabs q0) in *.
  set (B := aq * Ed) in *.
  assert (PB : 0 <= B) by (unfold B; apply Rmult_le_pos; [apply Rabs_pos | lra]).
  set (Z := (1 + / 512) * (En + B) + 32 * (u * u) * (aq * aD) + Rabs w * aD) in *.
  assert (den_nz : den <> 0).
  { intros Z0. rewrite Z0, Rabs_R0 in Hden. rewrite u_val in Hden. lra. }
  split; [exact den_nz|].
  (* the error of q0 + c *)
  set (en := num - (nh + nl)). set (ed := den - (hi dd + lo dd)).
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
  assert (M : Rabs (num - (q0 + c) * den) <= 23 * (u * u) * (aq * aD) + En + (1 + 5 * u) * B).
  { rewrite Ident.
    pose proof (Rabs_sum5 ((N - q0 * D) + (Nlo - q0 * Dlo) - rr) (rr - c * D) (- (c * Dlo)) en
                          (- ((q0 + c) * ed))) as T5.
    rewrite !Rabs_Ropp in T5. rewrite (Rabs_minus_sym rr) in T5.
    replace (N - q0 * D + (Nlo - q0 * Dlo) - rr + (rr - c * D) + - (c * Dlo) + en + - ((q0 + c) * ed))
      with (N - q0 * D + (Nlo - q0 * Dlo) - rr + (rr - c * D) - c * Dlo + en - (q0 + c) * ed) in T5 by ring.
    unfold en at 2 in T5. lra. }
  (* |num/den − (q0 + c)|·|D| ≤ (1 + 2^-9)(En + B) + 2^-101 (aq * aD) *)
  set (tq := num / den - (q0 + c)).
  assert (Etq : Rabs tq * Rabs den = Rabs (num - (q0 + c) * den)).
  { rewrite <- Rabs_mult. f_equal. unfold tq. field. exact den_nz. }
  assert (Ftq : Rabs tq * ((1 - 2 * u) * aD) <= Rabs tq * Rabs den).
  { apply Rmult_le_compat_l; [apply Rabs_pos | exact Hden]. }
  assert (Close : (Rabs tq + Rabs w) * aD < h * aD).
  { unfold Z, B in TZ. unfold B in M, PB. rewrite u_val in *. simpl in *. lra. }
  apply Rmult_lt_reg_r in Close; [|exact DP].
  symmetry. apply RN_of_close; [exact Bq|].
  replace (num / den - q) with (tq + w) by (unfold tq; lra).
  eapply Rle_lt_trans; [apply Rabs_triang | exact Close].
Qed.

(** [round_quotient_if_certain] (the optional form that the cascade in ray_plane_cascade.cpp uses). *)
Corollary round_quotient_if_certain_sound : forall (n d : Enclosure) (num den t : R),
  binary64 (hi n) -> binary64 (lo n) -> binary64 (radius n) ->
  binary64 (hi d) -> binary64 (lo d) -> binary64 (radius d) ->
  encloses n num -> encloses d den ->
  round_quotient_if_certain n (prepare_divisor d) = Some t ->
  den <> 0 /\ t = RN (num / den).
Proof.
  intros n d num den t Bnh Bnl BEn Bdh Bdl BEd Hn Hd H.
  pose proof (round_quotient_sound n d num den Bnh Bnl BEn Bdh Bdl BEd Hn Hd) as S.
  unfold round_quotient_if_certain in H.
  destruct (round_quotient n (prepare_divisor d)) as [q certain]. cbn [qr_t qr_certain] in H, S.
  destruct certain; [|discriminate]. injection H as <-. now apply S.
Qed.

(** ** Whenever round_quotient certifies, its candidate is a double with |q| ≥ 2^-900 ≥ 2^-968 =
    [half_gap_min_magnitude], so the half gap its test uses is the one half_gap_to_nearer_neighbour
    computes from q's bits ([half_gap_bits]). *)
Theorem round_quotient_candidate_normal : forall (num : Enclosure) (den : Divisor),
  let r := round_quotient num den in
  qr_certain r = true ->
  binary64 (qr_t r) /\ half_gap_min_magnitude <= Rabs (qr_t r) /\
  half_gap (qr_t r) =
    if Req_bool (Rabs (qr_t r)) (bpow radix2 (mag radix2 (qr_t r) - 1))
    then bpow radix2 (mag radix2 (qr_t r) - 55) else bpow radix2 (mag radix2 (qr_t r) - 54).
Proof.
  intros num den r H. unfold r, round_quotient in H |- *. cbn [qr_t qr_certain] in H |- *.
  set (q := RN (_ + _)) in *.
  assert (Bq : binary64 q) by apply binary64_RN.
  assert (G : half_gap_min_magnitude <= Rabs q).
  { revert H. destruct (Rle_bool_spec Q900 (Rabs q)) as [Gq|Gq].
    - intros _. eapply Rle_trans; [|exact Gq]. apply bpow_le. lia.
    - cbn [andb]. rewrite Bool.andb_false_r. discriminate. }
  split; [exact Bq | split; [exact G | now apply half_gap_bits]].
Qed.
