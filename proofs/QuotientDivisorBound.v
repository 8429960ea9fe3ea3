(** * What a certified quotient says about its divisor (kernel/src/certified/quotient_rounding.hpp).

    [round_quotient_certain_divisor]: whenever [round_quotient n (prepare_divisor d)] says certain, the
    divisor's radius is at most u·|D| (D = hi ⊕ lo, the rounded divisor), 2^-1000 ≤ |D| ≤ 2^1000, and any
    real den that d encloses has |den| ≥ (1 − 2u)|D|.  The test's left side holds (1 + 2^-9)·|q0|·E_d and its
    right side is h·|D| ≤ u·|q|·|D| ≤ u(1 + 7u)|q0|·|D| (the argument of QuotientRounding.v's
    [round_quotient_sound], whose steps this proof repeats up to that bound): a quotient is certified only
    over a divisor far from zero compared with its radius. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core Relative Pff2Flocq.
From Raykernel Require Import Constants Model Filter Compensated QuotientRounding.
Open Scope R_scope.

Theorem round_quotient_certain_divisor : forall (n d : Enclosure) (den : R),
  binary64 (hi n) -> binary64 (lo n) -> binary64 (radius n) ->
  binary64 (hi d) -> binary64 (lo d) -> binary64 (radius d) ->
  0 <= radius n -> encloses d den ->
  qr_certain (round_quotient n (prepare_divisor d)) = true ->
  let D := fst (two_sum (hi d) (lo d)) in
  radius d <= u * Rabs D /\ divisor_min_magnitude <= Rabs D <= divisor_max_magnitude /\
  (1 - 2 * u) * Rabs D <= Rabs den.
Proof.
  intros [nh nl En] dd den Bnh Bnl BEn Bdh Bdl BEd PEn Hd H.
  unfold encloses in Hd. cbn [hi lo radius] in *.
  pose proof (prepare_divisor_spec dd Bdh Bdl) as Sd.
  set (dv := prepare_divisor dd) in *.
  unfold round_quotient in H. cbn [hi lo radius qr_t qr_certain] in H.
  pose proof (two_sum_exact nh nl Bnh Bnl) as XN.
  destruct (two_sum_lo_bound nh nl Bnh Bnl) as [_ LN].
  pose proof (binary64_two_sum_hi nh nl) as BN. pose proof (binary64_two_sum_lo nh nl) as BNlo.
  set (N := fst (two_sum nh nl)) in *. set (Nlo := snd (two_sum nh nl)) in *.
  revert H.
  destruct (Rle_bool_spec Q900 (Rabs N)) as [GN|GN]; [|discriminate].
  destruct (div_in_range dv) eqn:Gd; [|discriminate].
  destruct (Sd Gd) as [BD [BDlo [XD [LD [ED [[GD1 GD2] RD]]]]]].
  rewrite ED. clear Sd ED.
  assert (DD : div_hi dv = fst (two_sum (hi dd) (lo dd))) by reflexivity.
  cbv zeta. rewrite <- DD.
  set (D := div_hi dv) in *. set (Dlo := div_lo dv) in *. set (R := div_reciprocal dv) in *.
  set (Ed := radius dd) in *.
  assert (DP : 0 < Rabs D) by (eapply Rlt_le_trans; [apply bpow_gt_0 | exact GD1]).
  assert (Dnz : D <> 0) by (intros Z; rewrite Z, Rabs_R0 in DP; lra).
  set (q0 := RN (N * R)).
  set (rr := RN (fma (- q0) D N + fma (- q0) Dlo Nlo)).
  set (c := RN (rr * R)).
  set (q := RN (q0 + c)).
  destruct (Rle_bool_spec Q900 (Rabs q)) as [Gq|Gq]; [|discriminate].
  destruct (Rle_bool_spec (Rabs q) largest_finite) as [_|_]; [|discriminate].
  cbn [andb].
  rewrite quotient_enclosure_factor_val, quotient_relative_val, quotient_test_factor_val.
  destruct (quotient_residuals N Nlo D Dlo R BN BNlo BD BDlo LN LD GN Dnz RD Gq)
    as [AP [Eta_aD [Eta_A [RR [Ec [Hc HcD]]]]]].
  fold q0 rr c in AP, Eta_aD, Eta_A, RR, Ec, Hc, HcD.
  destruct (quotient_candidate q0 c ltac:(apply binary64_RN) ltac:(apply binary64_RN) Hc)
    as [X [Hq1 Hq2]].
  fold q in X, Hq1, Hq2.
  set (w := RN (c - RN (q - q0))) in *.
  assert (Bq : binary64 q) by apply binary64_RN. assert (Bw : binary64 w) by apply binary64_RN.
  set (h := half_gap q).
  set (xb := RN (Rabs q0 * Ed)). set (xs := RN (xb + En)).
  set (x := RN (xs * (1 + / 512))).
  set (yb := RN (Rabs q0 * (32 * (u * u)))). set (ys := RN (yb + Rabs w)).
  set (y := RN (ys * Rabs D)).
  set (xy := RN (x + y)).
  destruct (Rlt_bool_spec (RN (xy * (1 + / 35184372088832))) (RN (h * Rabs D))) as [Test|Test];
    [|discriminate].
  intros _.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof Q900_pos as HQ.
  pose proof Q900_normal as QN.
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
  { assert (aD <= Rabs den + Rabs (den - (hi dd + lo dd)) + Rabs Dlo).
    { unfold aD. replace D with (den - (den - (hi dd + lo dd)) - Dlo) by lra.
      unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
      pose proof (Rabs_triang den (- (den + - (hi dd + lo dd)))). rewrite Rabs_Ropp in *. lra. }
    fold Ed in Hd. lra. }
  repeat split; assumption.
Qed.
