(** * The enclosure of an affine combination o·D + d·N (kernel/src/spawn/spawn_certified.cpp, [affine_enclosure]).

    [spawn]'s fast path encloses X = o·D + d·N, for doubles o, d and enclosures (hi, lo, radius) of two reals
    D and N, by the C++

      dd = two_sum(D.hi, D.lo), nn = two_sum(N.hi, N.lo);
      a = {dd.hi, nn.hi, 0}, alpha = {dd.lo, nn.lo, 0}, b = {o, d, 0};
      v = compensated_dot3(a, alpha, b, dot3_rounded(a, b));
      propagated = |o| ⊗ D.radius ⊕ |d| ⊗ N.radius;
      return {v.hi, v.lo, C ⊗ (propagated ⊕ v.radius) ⊕ U}

    with C = [affine_propagation_factor] = 1 + 2^-50 = 1 + 8u and U = [affine_absolute] = 2^-1060 = 2^15·η
    (Constants.v; bounds:: of spawn_certified.hpp).

    - [affine_enclosure_sound]: the result encloses o·X_D + d·X_N for every X_D enclosed by D and X_N enclosed
      by N.  The TwoSum pairs have the sums of the input pairs (Model.v's [two_sum_exact]) and |lo| ≤ u|hi|
      ([two_sum_lo_bound]), so PlaneCompensated.v's [compensated_dot3_enclosure] encloses
      V = o·(D.hi + D.lo) + d·(N.hi + N.lo) within E = v.radius; |o·X_D + d·X_N − V| ≤ |o|·D.radius +
      |d|·N.radius =: P.  The computed radius is at least P + E: each of its six roundings is at least
      (1 − u)·exact, less η for the two products and C ⊗ s (the sums of doubles have no absolute error), so it is
      at least C(1 − u)^4·P + C(1 − u)^3·E − (2C + 1)·η + (1 − u)·U, and C(1 − u)^4 ≥ 1 + 4u − 32u² ≥ 1,
      (1 − u)·U ≥ (2C + 1)·η.

    Model: Model.v's [RN] (binary64, ties to even, gradual underflow, no largest exponent).  As for the other
    theorems of PlaneCompensated.v, no overflow hypothesis is stated: the model is the C++ computation while no
    intermediate overflows (proofs/README.md, "Overflow"); an overflow makes the C++ radius +inf or NaN and the
    comparison that consumes the enclosure (round_quotient) uncertain. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated.
Open Scope R_scope.

(** ** The C++ operation by operation.  [D] and [N] are the enclosures' (hi, lo, radius); compensated_dot3
    computes its [dot3_rounded(a, b)] itself (PlaneCompensated.v). *)
Definition affine_enclosure (o : R) (D : Enclosure) (d : R) (N : Enclosure) : Enclosure :=
  let dd := two_sum (hi D) (lo D) in
  let nn := two_sum (hi N) (lo N) in
  let v := compensated_dot3 (fst dd) (fst nn) 0 (snd dd) (snd nn) 0 o d 0 in
  let propagated := RN (RN (Rabs o * radius D) + RN (Rabs d * radius N)) in
  {| hi := hi v; lo := lo v;
     radius := RN (RN (affine_propagation_factor * RN (propagated + radius v)) + affine_absolute) |}.

Lemma affine_propagation_factor_val : affine_propagation_factor = 1 + 8 * u.
Proof. unfold affine_propagation_factor. rewrite u_val. simpl bpow. lra. Qed.

Lemma affine_absolute_eta : affine_absolute = 32768 * eta.
Proof.
  unfold affine_absolute, eta. replace (-1060)%Z with (15 + -1075)%Z by lia.
  rewrite bpow_plus. simpl bpow. lra.
Qed.

Lemma binary64_affine_absolute : binary64 affine_absolute.
Proof. apply binary64_bpow. lia. Qed.

(** A rounding of a non-negative real x loses at most u·x + η. *)
Lemma RN_lower_nonneg : forall x, 0 <= x -> (1 - u) * x - eta <= RN x.
Proof.
  intros x Hx. pose proof (RN_err x) as H. rewrite (Rabs_nonneg_eq x Hx) in H.
  apply Rabs_bounds in H. lra.
Qed.

(** A rounding of a non-negative sum of two doubles loses at most u·(a + b). *)
Lemma RN_plus_lower_nonneg : forall a b, binary64 a -> binary64 b -> 0 <= a + b ->
  (1 - u) * (a + b) <= RN (a + b).
Proof.
  intros a b Ba Bb H. pose proof (RN_plus_err a b Ba Bb) as E. rewrite (Rabs_nonneg_eq (a + b) H) in E.
  apply Rabs_bounds in E. lra.
Qed.

(** ** The renormalized pair: (hi, lo) = TwoSum(x, y) has hi + lo = x + y and |lo| ≤ u|hi|. *)
Lemma renormalized_pair : forall x y, binary64 x -> binary64 y ->
  fst (two_sum x y) + snd (two_sum x y) = x + y /\
  Rabs (snd (two_sum x y)) <= u * Rabs (fst (two_sum x y)) /\
  binary64 (fst (two_sum x y)) /\ binary64 (snd (two_sum x y)).
Proof.
  intros x y Bx By. repeat split.
  - now apply two_sum_exact.
  - now apply two_sum_lo_bound.
  - apply binary64_two_sum_hi.
  - apply binary64_two_sum_lo.
Qed.

(** ** Main theorem. *)
Theorem affine_enclosure_sound : forall (o d : R) (D N : Enclosure) (XD XN : R),
  binary64 o -> binary64 d ->
  binary64 (hi D) -> binary64 (lo D) -> binary64 (radius D) ->
  binary64 (hi N) -> binary64 (lo N) -> binary64 (radius N) ->
  encloses D XD -> encloses N XN ->
  encloses (affine_enclosure o D d N) (o * XD + d * XN).
Proof.
  intros o d D N XD XN Bo Bd BDh BDl BDr BNh BNl BNr ED EN.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (PDr : 0 <= radius D) by (eapply Rle_trans; [apply Rabs_pos | exact ED]).
  assert (PNr : 0 <= radius N) by (eapply Rle_trans; [apply Rabs_pos | exact EN]).
  destruct (renormalized_pair (hi D) (lo D) BDh BDl) as [XDd [LDd [BDa BDal]]].
  destruct (renormalized_pair (hi N) (lo N) BNh BNl) as [XNn [LNn [BNa BNal]]].
  unfold affine_enclosure.
  set (Da := fst (two_sum (hi D) (lo D))) in *. set (Dal := snd (two_sum (hi D) (lo D))) in *.
  set (Na := fst (two_sum (hi N) (lo N))) in *. set (Nal := snd (two_sum (hi N) (lo N))) in *.
  (* compensated_dot3 encloses V = o·(D.hi + D.lo) + d·(N.hi + N.lo) *)
  assert (Z0 : Rabs 0 <= u * Rabs 0) by (rewrite Rabs_R0; lra).
  pose proof (compensated_dot3_enclosure Da Na 0 Dal Nal 0 o d 0 BDa BNa binary64_0 BDal BNal binary64_0
                Bo Bd binary64_0 LDd LNn Z0) as Ev.
  set (v := compensated_dot3 Da Na 0 Dal Nal 0 o d 0) in *.
  replace ((Da + Dal) * o + (Na + Nal) * d + (0 + 0) * 0) with (o * (hi D + lo D) + d * (hi N + lo N))
    in Ev by (rewrite <- XDd, <- XNn; ring).
  unfold encloses in Ev |- *. cbn [hi lo radius] in Ev |- *.
  set (E := radius v) in *.
  assert (BE : binary64 E) by (unfold E, v, compensated_dot3; cbn [radius]; apply binary64_RN).
  assert (PE : 0 <= E) by (eapply Rle_trans; [apply Rabs_pos | exact Ev]).
  (* |X − V| ≤ |o|·D.radius + |d|·N.radius *)
  set (x1 := Rabs o * radius D). set (x2 := Rabs d * radius N).
  assert (Px1 : 0 <= x1) by (apply Rmult_le_pos; [apply Rabs_pos | exact PDr]).
  assert (Px2 : 0 <= x2) by (apply Rmult_le_pos; [apply Rabs_pos | exact PNr]).
  assert (Prop_ : Rabs (o * XD + d * XN - (o * (hi D + lo D) + d * (hi N + lo N))) <= x1 + x2).
  { replace (o * XD + d * XN - (o * (hi D + lo D) + d * (hi N + lo N)))
      with (o * (XD - (hi D + lo D)) + d * (XN - (hi N + lo N))) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite !Rabs_mult.
    apply Rplus_le_compat; apply Rmult_le_compat_l; try apply Rabs_pos; assumption. }
  (* the computed radius is at least x1 + x2 + E *)
  set (r1 := RN x1). set (r2 := RN x2).
  pose proof (RN_lower_nonneg x1 Px1) as L1. fold r1 in L1.
  pose proof (RN_lower_nonneg x2 Px2) as L2. fold r2 in L2.
  assert (P1 : 0 <= r1) by (apply RN_nonneg; exact Px1).
  assert (P2 : 0 <= r2) by (apply RN_nonneg; exact Px2).
  pose proof (RN_plus_lower_nonneg r1 r2 (binary64_RN _) (binary64_RN _) ltac:(lra)) as L3.
  set (p := RN (r1 + r2)) in *.
  assert (Pp : 0 <= p) by (apply RN_nonneg; lra).
  pose proof (RN_plus_lower_nonneg p E (binary64_RN _) BE ltac:(lra)) as L4.
  set (s := RN (p + E)) in *.
  assert (Ps : 0 <= s) by (apply RN_nonneg; lra).
  rewrite affine_propagation_factor_val.
  assert (PCs : 0 <= (1 + 8 * u) * s) by (apply Rmult_le_pos; lra).
  pose proof (RN_lower_nonneg _ PCs) as L5.
  set (c := RN ((1 + 8 * u) * s)) in *.
  assert (Pc : 0 <= c) by (apply RN_nonneg; exact PCs).
  assert (PU : 0 <= affine_absolute) by (rewrite affine_absolute_eta; lra).
  pose proof (RN_plus_lower_nonneg c affine_absolute (binary64_RN _) binary64_affine_absolute ltac:(lra)) as L6.
  rewrite affine_absolute_eta in L6 |- *.
  (* the triangle inequality, then the chain of lower bounds (linear once u is a numeral) *)
  eapply Rle_trans.
  { replace (o * XD + d * XN - (hi v + lo v))
      with ((o * XD + d * XN - (o * (hi D + lo D) + d * (hi N + lo N))) +
            (o * (hi D + lo D) + d * (hi N + lo N) - (hi v + lo v))) by ring.
    apply Rabs_triang. }
  rewrite u_val in *. lra.
Qed.
