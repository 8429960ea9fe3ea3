(** * What a certified quotient says about its divisor (kernel/src/certified/quotient_rounding.hpp).

    [round_quotient_certain_divisor]: whenever [round_quotient n (prepare_divisor d)] says certain, the
    divisor's radius is at most u·|D| (D = hi ⊕ lo, the rounded divisor), 2^-1000 ≤ |D| ≤ 2^1000, and any
    real den that d encloses has |den| ≥ (1 − 2u)|D|.  The test's left side holds (1 + 2^-9)·|q0|·E_d and its
    right side is h·|D| ≤ u·|q|·|D| ≤ u(1 + 7u)|q0|·|D| (QuotientRounding.v's [quotient_test_certifies],
    which [round_quotient_sound] uses too): a quotient is certified only
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
  destruct (quotient_test_certifies En Ed q0 q w D Dlo (hi dd + lo dd) den BEn Bw PEn Hd XD LD DP AP
              Eta_aD Eta_A Gq Hq1 Test) as [_ [EdD Hden]].
  repeat split; assumption.
Qed.
