(** * The certified fast path of [spawn] (kernel/src/spawn/spawn_certified.cpp): three roundings.

    [spawn] (docs/contract.md §9) decides the side of the hit point P = o + (num/den)·d against a rounding
    boundary (x + y)/2 of the origin's format, and rounds coordinates to binary32 through binary64.  Its fast
    path needs:
    - [midpoint_offset_encloses] (C++ [midpoint_offset]): for doubles x, y, o, the C++
      (s, e) = TwoSum(x, y), (h, l) = TwoSum(s, −(2·o)), lo = RN(l + e), radius = RN(2^-52·|lo|) gives
      |(x + y − 2·o) − (h + lo)| ≤ radius.  TwoSum is exact (Model.v's [two_sum_exact]), 2·o is exact, so the
      only error is the rounding of l + e, a sum of two doubles: exact below 2^-1022 (Flocq's
      [FLT_format_plus_small], Model.v's [RN_plus_exact_or_normal]), else at most 2^-53·|lo|, which
      RN(2^-52·|lo|) covers (a rounding into the subnormal range loses at most 2^-1075 = 2^-53·2^-1022);
    - [midpoint_side_sign] (the side function of the hit point's coordinates): over the reals, with
      Δ = num·(2·d) − (x + y − 2·o)·den and den ≠ 0, P − (x + y)/2 = Δ/(2·den), so
      sign(P − (x + y)/2) = sign(den·Δ) = sign(den)·sign(Δ);
    - [binary32_through_binary64], [binary32_midpoint_side] (C++ [round_binary32_from_binary64]): with
      r = RN64(x) (ties to even), RN32(x) = RN32(r) unless r is the midpoint of two consecutive binary32
      values f < succ32 f, and at such a midpoint the side of x against r decides: x > r gives succ32 f,
      x < r gives f.  Every binary32 midpoint is a binary64 value (25 significant bits, exponent ≥ −150:
      [midpoint32_binary64]), so none lies strictly between x and its nearest double r, and RN32 is constant
      strictly between two consecutive midpoints ([rn32_below_midpoint], [rn32_above_midpoint]).

    Model: Model.v's [RN] (binary64, ties to even, gradual underflow, no largest exponent: the C++ computation
    while no result overflows) and, for binary32, [round radix2 (FLT_exp (-149) 24) ZnearestE], likewise
    without a largest exponent (binary32 overflow, |x| ≥ 2^128 after rounding, is the C++'s to exclude). *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core Mult_error Relative.
From Raykernel Require Import Constants Model MidpointRounding.
Open Scope R_scope.

(** ** 1. The enclosure of x + y − 2·o (C++ [midpoint_offset]). *)

(** The C++ operation by operation: [two_sum(x, y)], [two_sum(s.hi, -(2 * o))] (RN(2·o) is the C++'s [2 * o],
    exact: [RN_double]), [lo = h.lo + s.lo], [midpoint_offset_relative * std::fabs(lo)] (Constants.v's
    [midpoint_offset_relative] = 2^-52, bounds::midpoint_offset_relative of spawn_certified.hpp). *)
Definition midpoint_offset (x y o : R) : R * R * R :=
  let s := two_sum x y in
  let h := two_sum (fst s) (- RN (2 * o)) in
  let lo := RN (snd h + snd s) in
  (fst h, lo, RN (midpoint_offset_relative * Rabs lo)).

Lemma binary64_double : forall o, binary64 o -> binary64 (2 * o).
Proof.
  intros o Fo. replace (2 * o) with (o * bpow radix2 1) by (change (bpow radix2 1) with 2; ring).
  apply mult_bpow_pos_exact_FLT; [exact Fo | lia].
Qed.

Lemma RN_double : forall o, binary64 o -> RN (2 * o) = 2 * o.
Proof. intros o Fo. apply RN_binary64, binary64_double, Fo. Qed.

(** RN(2^-52·|lo|) ≥ 2^-53·|lo| when |lo| ≥ 2^-1022: relative error 2^-53 in the normal range, absolute
    error 2^-1075 = 2^-53·2^-1022 below it. *)
Lemma radius_covers : forall lo, bpow radix2 (-1022) <= Rabs lo ->
  u * Rabs lo <= RN (bpow radix2 (-52) * Rabs lo).
Proof.
  intros lo Hlo. pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (B : bpow radix2 (-52) = 2 * u) by (rewrite u_val; simpl bpow; lra).
  assert (Eta : u * bpow radix2 (-1022) = eta)
    by (unfold unit_roundoff, eta; rewrite <- bpow_plus; reflexivity).
  assert (Ul : u <= / 2) by (rewrite u_val; lra).
  set (z := bpow radix2 (-52) * Rabs lo).
  assert (Z0 : 0 <= z) by (unfold z; pose proof (bpow_gt_0 radix2 (-52)); pose proof (Rabs_pos lo); nra).
  assert (Zv : z = 2 * u * Rabs lo) by (unfold z; rewrite B; ring).
  destruct (Rle_or_lt (bpow radix2 (-1022)) (Rabs z)) as [N|S].
  - pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) z N) as H1.
    rewrite half_bpow_52 in H1. rewrite (Rabs_pos_eq z Z0) in H1.
    apply Rabs_bounds in H1. pose proof (Rabs_pos lo). nra.
  - pose proof (small_error z S) as H1. apply Rabs_bounds in H1.
    assert (eta <= u * Rabs lo) by (rewrite <- Eta; apply Rmult_le_compat_l; lra).
    lra.
Qed.

(** The enclosure from the exactness of the two TwoSums alone: any doubles s, e, h, l with s + e = x + y and
    h + l = s − 2·o. *)
Lemma midpoint_offset_encloses_gen : forall x y o s e h l,
  binary64 e -> binary64 l -> s + e = x + y -> h + l = s - 2 * o ->
  Rabs ((x + y - 2 * o) - (h + RN (l + e))) <= RN (bpow radix2 (-52) * Rabs (RN (l + e))).
Proof.
  intros x y o s e h l Fe Fl Es Eh.
  replace ((x + y - 2 * o) - (h + RN (l + e))) with (- (RN (l + e) - (l + e))) by lra.
  rewrite Rabs_Ropp.
  destruct (RN_plus_exact_or_normal l e Fl Fe) as [X|N].
  - rewrite X. unfold Rminus. rewrite Rplus_opp_r, Rabs_R0.
    apply RN_nonneg, Rmult_le_pos; [apply bpow_ge_0 | apply Rabs_pos].
  - eapply Rle_trans; [apply RN_plus_err_round; assumption|].
    apply radius_covers.
    assert (F : binary64 (bpow radix2 (-1022))) by (apply binary64_bpow; lia).
    rewrite <- RN_abs, <- (RN_binary64 _ F). now apply RN_le.
Qed.

(** [midpoint_offset] encloses x + y − 2·o for all doubles x, y, o. *)
Theorem midpoint_offset_encloses : forall x y o, binary64 x -> binary64 y -> binary64 o ->
  let '(h, lo, radius) := midpoint_offset x y o in
  Rabs ((x + y - 2 * o) - (h + lo)) <= radius.
Proof.
  intros x y o Fx Fy Fo. unfold midpoint_offset, midpoint_offset_relative.
  apply midpoint_offset_encloses_gen with (s := fst (two_sum x y)).
  - apply binary64_two_sum_lo.
  - apply binary64_two_sum_lo.
  - now apply two_sum_exact.
  - rewrite two_sum_exact.
    + rewrite RN_double by exact Fo. ring.
    + apply binary64_two_sum_hi.
    + apply binary64_opp, binary64_RN.
Qed.

(** ** 2. The side of P = o + (num/den)·d against (x + y)/2 (over the reals). *)

(** P − (x + y)/2 = den·Δ / (2·den²): its sign is sign(den·Δ) = sign(den)·sign(Δ), as [Rcompare], and in
    three implications.  (d ≠ 0 is not needed.) *)
Theorem midpoint_side_sign : forall num den o d x y, den <> 0 ->
  Rcompare (o + num / den * d) ((x + y) / 2)
    = Rcompare (den * (num * (2 * d) - (x + y - 2 * o) * den)) 0 /\
  (0 < den * (num * (2 * d) - (x + y - 2 * o) * den) -> (x + y) / 2 < o + num / den * d) /\
  (den * (num * (2 * d) - (x + y - 2 * o) * den) < 0 -> o + num / den * d < (x + y) / 2) /\
  (num * (2 * d) - (x + y - 2 * o) * den = 0 -> o + num / den * d = (x + y) / 2).
Proof.
  intros num den o d x y Nz.
  set (D := num * (2 * d) - (x + y - 2 * o) * den).
  set (k := / (2 * (den * den))).
  assert (K : 0 < k).
  { unfold k. apply Rinv_0_lt_compat. assert (0 < den * den) by (apply Rsqr_pos_lt; exact Nz). lra. }
  assert (E : o + num / den * d - (x + y) / 2 = den * D * k) by (unfold D, k; field; exact Nz).
  assert (Gt : 0 < den * D -> (x + y) / 2 < o + num / den * d).
  { intros H. assert (0 < den * D * k) by (apply Rmult_lt_0_compat; assumption). lra. }
  assert (Lt : den * D < 0 -> o + num / den * d < (x + y) / 2).
  { intros H. assert (0 < - (den * D) * k) by (apply Rmult_lt_0_compat; lra). lra. }
  assert (Eq : D = 0 -> o + num / den * d = (x + y) / 2).
  { intros H. rewrite H, Rmult_0_r, Rmult_0_l in E. lra. }
  split; [|split; [exact Gt | split; [exact Lt | exact Eq]]].
  destruct (Rcompare_spec (den * D) 0) as [L|Z|G].
  - apply Rcompare_Lt. now apply Lt.
  - apply Rcompare_Eq. rewrite Z, Rmult_0_l in E. lra.
  - apply Rcompare_Gt. now apply Gt.
Qed.

(** ** 3. binary32 through binary64 (C++ [round_binary32_from_binary64]). *)

Notation RN32 := (round radix2 (FLT_exp (-149) 24) ZnearestE).
Notation succ32 := (succ radix2 (FLT_exp (-149) 24)).
Notation pred32 := (pred radix2 (FLT_exp (-149) 24)).

(** [binary32], [binary32_prec_gt_0] and [binary32_binary64] (every binary32 value is a binary64 value) are
    Model.v's. *)

Lemma lt_succ32 : forall f, f < succ32 f.
Proof.
  intros f. destruct (Req_dec f 0) as [Z|NZ].
  - rewrite Z, succ_0, ulp_FLT_0; [apply bpow_gt_0|reflexivity].
  - now apply succ_gt_id.
Qed.

(** The midpoint above a non-negative binary32 value p = M·2^e (|M| < 2^24, e ≥ −149) is
    (2M + 1)·2^(e−1): 25 bits, exponent ≥ −150, a binary64 value. *)
Lemma midpoint32_pos : forall p, 0 <= p -> binary32 p -> binary64 ((p + succ32 p) / 2).
Proof.
  intros p P0 Fp. rewrite succ_eq_pos by exact P0.
  destruct (Req_dec p 0) as [Z|NZ].
  - rewrite Z, ulp_FLT_0 by reflexivity.
    replace ((0 + (0 + bpow radix2 (-149))) / 2) with (bpow radix2 (-150)).
    + apply binary64_bpow. lia.
    + replace (-149)%Z with (1 + -150)%Z by lia. rewrite bpow_plus. change (bpow radix2 1) with 2. field.
  - rewrite ulp_neq_0 by exact NZ.
    assert (Sm := scaled_mantissa_lt_bpow radix2 (FLT_exp (-149) 24) p).
    rewrite (scaled_mantissa_generic radix2 (FLT_exp (-149) 24) p Fp) in Sm.
    assert (Ce : (mag radix2 p - cexp radix2 (FLT_exp (-149) 24) p <= 24)%Z)
      by (unfold cexp, FLT_exp; lia).
    assert (He : (-149 <= cexp radix2 (FLT_exp (-149) 24) p)%Z) by (unfold cexp, FLT_exp; lia).
    assert (Ep : p = IZR (Ztrunc (scaled_mantissa radix2 (FLT_exp (-149) 24) p))
                     * bpow radix2 (cexp radix2 (FLT_exp (-149) 24) p)) by exact Fp.
    set (e := cexp radix2 (FLT_exp (-149) 24) p) in *.
    set (M := Ztrunc (scaled_mantissa radix2 (FLT_exp (-149) 24) p)) in *.
    assert (HM : (Z.abs M < 16777216)%Z).
    { apply lt_IZR. rewrite abs_IZR. eapply Rlt_le_trans; [exact Sm|].
      change (IZR 16777216) with (bpow radix2 24). apply bpow_le. exact Ce. }
    assert (B : bpow radix2 e = 2 * bpow radix2 (e - 1)).
    { replace e with (1 + (e - 1))%Z at 1 by ring. rewrite bpow_plus. reflexivity. }
    replace ((p + (p + bpow radix2 e)) / 2) with (IZR (2 * M + 1) * bpow radix2 (e - 1)).
    + apply binary64_dyadic; lia.
    + rewrite Ep at 1 2. rewrite B, plus_IZR, mult_IZR. simpl IZR. field.
Qed.

(** Every binary32 midpoint (f + succ32 f)/2 is a binary64 value (below zero by symmetry:
    (f + succ32 f)/2 = −(p + succ32 p)/2 with p = pred32(−f) ≥ 0). *)
Lemma midpoint32_binary64 : forall f, binary32 f -> binary64 ((f + succ32 f) / 2).
Proof.
  intros f Ff. destruct (Rle_or_lt 0 f) as [P|N].
  - now apply midpoint32_pos.
  - assert (Fg : binary32 (- f)) by now apply generic_format_opp.
    set (p := pred32 (- f)).
    assert (Fp : binary32 p) by (apply generic_format_pred; auto with typeclass_instances).
    assert (P0 : 0 <= p) by (apply pred_ge_0; auto with typeclass_instances; lra).
    assert (S : succ32 p = - f) by (apply succ_pred; auto with typeclass_instances).
    assert (Sf : succ32 f = - p).
    { unfold p. rewrite <- (Ropp_involutive f) at 1. apply succ_opp. }
    replace ((f + succ32 f) / 2) with (- ((p + succ32 p) / 2)) by (rewrite S, Sf; field).
    apply binary64_opp. now apply midpoint32_pos.
Qed.

Lemma RN_binary32 : forall f, binary32 f -> RN f = f.
Proof. intros f Ff. apply RN_binary64, binary32_binary64, Ff. Qed.

Lemma RN32_generic : forall f, binary32 f -> RN32 f = f.
Proof. intros f Ff. apply round_generic; auto with typeclass_instances. Qed.

Lemma RN32_le : forall a b, a <= b -> RN32 a <= RN32 b.
Proof. intros a b H. apply round_le; auto with typeclass_instances. Qed.

(** RN32 is f on [f, (f + succ32 f)/2) and succ32 f on ((f + succ32 f)/2, succ32 f]. *)
Lemma rn32_below_midpoint : forall f v, binary32 f -> f <= v < (f + succ32 f) / 2 -> RN32 v = f.
Proof.
  intros f v Ff [L U]. apply Rle_antisym.
  - apply round_N_le_midp; auto with typeclass_instances.
  - rewrite <- (RN32_generic f Ff) at 1. now apply RN32_le.
Qed.

Lemma rn32_above_midpoint : forall f v, binary32 f -> (f + succ32 f) / 2 < v <= succ32 f ->
  RN32 v = succ32 f.
Proof.
  intros f v Ff [L U].
  assert (Fs : binary32 (succ32 f)) by (apply generic_format_succ; auto with typeclass_instances).
  apply Rle_antisym.
  - rewrite <- (RN32_generic _ Fs). now apply RN32_le.
  - apply round_N_ge_midp; auto with typeclass_instances.
    rewrite pred_succ by (auto with typeclass_instances). lra.
Qed.

(** r = RN64(x) not a binary32 midpoint: RN32(x) = RN32(r). *)
Theorem binary32_through_binary64 : forall x,
  (forall f, binary32 f -> RN x <> (f + succ32 f) / 2) ->
  RN32 x = RN32 (RN x).
Proof.
  intros x NoMid.
  set (a := round radix2 (FLT_exp (-149) 24) Zfloor x).
  assert (Fa : binary32 a) by (apply generic_format_round; auto with typeclass_instances).
  assert (Ax : a <= x) by (apply (round_DN_pt radix2 (FLT_exp (-149) 24) x)).
  assert (Xs : x <= succ32 a).
  { eapply Rle_trans; [apply (round_UP_pt radix2 (FLT_exp (-149) 24) x)|].
    apply UP_le_succ_DN; auto with typeclass_instances. }
  assert (Fs : binary32 (succ32 a)) by (apply generic_format_succ; auto with typeclass_instances).
  set (m := (a + succ32 a) / 2).
  assert (Fm : binary64 m) by (apply midpoint32_binary64, Fa).
  pose proof (NoMid a Fa) as Nm. fold m in Nm.
  destruct (Rtotal_order x m) as [L|[E|G]].
  - (* a ≤ x < m, and a = RN a ≤ RN x < RN m = m *)
    assert (R1 : RN x <= m) by (rewrite <- (RN_binary64 m Fm); apply RN_le; lra).
    assert (R2 : a <= RN x) by (rewrite <- (RN_binary32 a Fa); apply RN_le; exact Ax).
    rewrite (rn32_below_midpoint a x Fa) by (split; assumption).
    rewrite (rn32_below_midpoint a (RN x) Fa) by (split; [exact R2 | fold m; lra]).
    reflexivity.
  - exfalso. apply Nm. rewrite E. now apply RN_binary64.
  - (* m < x ≤ succ a, and m = RN m ≤ RN x ≤ RN (succ a) = succ a *)
    assert (R1 : m <= RN x) by (rewrite <- (RN_binary64 m Fm); apply RN_le; lra).
    assert (R2 : RN x <= succ32 a) by (rewrite <- (RN_binary32 _ Fs); apply RN_le; exact Xs).
    rewrite (rn32_above_midpoint a x Fa) by (split; assumption).
    rewrite (rn32_above_midpoint a (RN x) Fa) by (split; [fold m; lra | exact R2]).
    reflexivity.
Qed.

(** r = RN64(x) the midpoint of f and succ32 f: the side of x against r decides RN32(x) (x = r is RN32(r)). *)
Theorem binary32_midpoint_side : forall x f, binary32 f ->
  RN x = (f + succ32 f) / 2 ->
  (RN x < x -> RN32 x = succ32 f) /\ (x < RN x -> RN32 x = f).
Proof.
  intros x f Ff Mid.
  assert (Fs : binary32 (succ32 f)) by (apply generic_format_succ; auto with typeclass_instances).
  pose proof (lt_succ32 f) as Lt.
  split; intros H.
  - (* x ≤ succ f: otherwise RN x ≥ RN (succ f) = succ f > the midpoint *)
    assert (Xs : x <= succ32 f).
    { destruct (Rle_or_lt x (succ32 f)) as [X|X]; [exact X|].
      assert (succ32 f <= RN x) by (rewrite <- (RN_binary32 _ Fs); apply RN_le; lra). lra. }
    apply rn32_above_midpoint; [exact Ff | lra].
  - (* f ≤ x: otherwise RN x ≤ RN f = f < the midpoint *)
    assert (Fx : f <= x).
    { destruct (Rle_or_lt f x) as [X|X]; [exact X|].
      assert (RN x <= f) by (rewrite <- (RN_binary32 _ Ff); apply RN_le; lra). lra. }
    apply rn32_below_midpoint; [exact Ff | lra].
Qed.
