(** * What a certified quotient says about its divisor (kernel/src/core/quotient_rounding.hpp).

    [round_quotient_certain_divisor]: whenever [round_quotient n (prepare_divisor d)] says certain, the
    divisor's radius is at most u·|D| (D = hi ⊕ lo, the rounded divisor), 2^-1000 ≤ |D| ≤ 2^1000, and any
    real den that d encloses has |den| ≥ (1 − 2u)|D|.  The test's left side holds (1 + 2^-9)·|q0|·E_d and its
    right side is h·|D| ≤ u·|q|·|D| ≤ u(1 + 7u)|q0|·|D| (QuotientRounding.v's [quotient_test_certifies],
    which [round_quotient_sound] uses too): a quotient is certified only
    over a divisor far from zero compared with its radius. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core Relative Pff2Flocq.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated QuotientRounding.
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
  unfold encloses in Hd. cbn [hi lo radius] in *. cbv zeta.
  pose proof (prepare_divisor_spec dd Bdh Bdl) as Sd.
  set (dv := prepare_divisor dd) in *.
  unfold round_quotient in H. cbn [hi lo radius qr_t qr_certain] in H.
  open_certified_quotient nh nl En dd dv Bnh Bnl Sd H.
  change (fst (two_sum (hi dd) (lo dd))) with D.
  destruct (quotient_test_certifies En Ed q0 q w D Dlo (hi dd + lo dd) den BEn Bw PEn Hd XD LD DP AP
              Eta_aD Eta_A Gq Hq1 Test) as [_ [EdD Hden]].
  repeat split; assumption.
Qed.
