(** * Rounding to nearest at the midpoints of a double (kernel/src/core/quotient_boundary.hpp's decision).

    [round_quotient_at_boundaries] compares t = num/den with the two midpoints m⁻ = (q⁻ + q)/2 and
    m⁺ = (q + q⁺)/2 of a candidate double q and its neighbours q⁻ = pred q, q⁺ = succ q (next_down, next_up), by
    exact signs (proofs/core/Expansions.v, [compare_quotients_expansion_sound]), and chooses RN(t) from them:
    - m⁻ < t < m⁺: RN(t) = q ([rn_between_midpoints], Flocq's [round_N_le_midp] and [round_N_ge_midp]);
    - t = m⁺: q when q's integral significand is even, else q⁺; t = m⁻: q when it is even, else q⁻ (ties to
      even: [rn_at_midpoint_below], [rn_at_midpoint_above]; at a midpoint both neighbours are nearest, and of
      two consecutive doubles exactly one has an even canonical significand, Flocq's [DN_UP_parity_generic]);
    - [boundary_decision_correct]: the three cases as the C++ decides them from sign(t − m⁺), sign(t − m⁻);
    - [b754_canonical]: a finite double's significand field m is its canonical integral significand up to the
      sign, so "even" is the parity of m, the last bit of the C++'s bit pattern (the stored fraction of a
      normal double is m − 2^52, of a subnormal m itself).
    Over the reals for every double q (no range: the C++'s range 2^-968 ≤ |q| < largest_finite only keeps the
    neighbours finite and normal and the products exact). *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model.
Open Scope R_scope.

Notation succ64 := (succ radix2 (FLT_exp (-1074) 53)).
Notation pred64 := (pred radix2 (FLT_exp (-1074) 53)).
Notation canonical64 := (canonical radix2 (FLT_exp (-1074) 53)).

Lemma lt_succ64 : forall x, x < succ64 x.
Proof.
  intros x. destruct (Req_dec x 0) as [Z|NZ].
  - rewrite Z, succ_0, ulp_FLT_0; [apply bpow_gt_0|reflexivity].
  - now apply succ_gt_id.
Qed.

(** Strictly between the midpoints: RN(t) = q. *)
Theorem rn_between_midpoints : forall q t, binary64 q ->
  (pred64 q + q) / 2 < t < (q + succ64 q) / 2 -> RN t = q.
Proof.
  intros q t Fq [L U]. apply Rle_antisym.
  - now apply round_N_le_midp; auto with typeclass_instances.
  - apply round_N_ge_midp; auto with typeclass_instances. lra.
Qed.

(** At the midpoint t of x and succ x: both are nearest, RN(t) is one of them, the even one. *)
Lemma midpoint_facts : forall x t, binary64 x -> t = (x + succ64 x) / 2 ->
  (forall gx gy, canonical64 gx -> F2R gx = x -> canonical64 gy -> F2R gy = succ64 x ->
     Z.even (Fnum gy) = negb (Z.even (Fnum gx))) /\
  (RN t = x \/ RN t = succ64 x) /\
  (exists g, RN t = F2R g /\ canonical64 g /\ Z.even (Fnum g) = true).
Proof.
  intros x t Fx E.
  pose proof (lt_succ64 x) as Lt.
  assert (Fy : binary64 (succ64 x)) by (apply generic_format_succ; auto with typeclass_instances).
  assert (DN : round radix2 (FLT_exp (-1074) 53) Zfloor t = x).
  { apply round_DN_eq; auto with typeclass_instances. lra. }
  assert (UP : round radix2 (FLT_exp (-1074) 53) Zceil t = succ64 x).
  { apply round_UP_eq; auto with typeclass_instances. rewrite pred_succ; auto with typeclass_instances. lra. }
  assert (NF : ~ binary64 t).
  { intro Ft. rewrite round_generic in DN; auto with typeclass_instances. lra. }
  assert (ENE : Exists_NE radix2 (FLT_exp (-1074) 53)) by (apply exists_NE_FLT; right; reflexivity).
  assert (Par : forall gx gy, canonical64 gx -> F2R gx = x -> canonical64 gy -> F2R gy = succ64 x ->
                  Z.even (Fnum gy) = negb (Z.even (Fnum gx))).
  { intros gx gy Cx Gx Cy Gy. apply (DN_UP_parity_generic radix2 _ t gx gy NF Cx Cy); congruence. }
  pose proof (round_NE_pt radix2 (FLT_exp (-1074) 53) t) as [N Choice].
  assert (Two : RN t = x \/ RN t = succ64 x).
  { pose proof (Rnd_N_pt_DN_or_UP_eq _ _ _ _ _ (round_DN_pt radix2 _ t) (round_UP_pt radix2 _ t) N) as H.
    now rewrite DN, UP in H. }
  split; [exact Par|]. split; [exact Two|].
  destruct Choice as [NE | U]; [exact NE|].
  exfalso.
  assert (Half : Rabs (x - t) = Rabs (succ64 x - t)).
  { rewrite E. rewrite Rabs_left by lra. rewrite Rabs_pos_eq by lra. lra. }
  assert (Nx : Rnd_N_pt binary64 t x).
  { split; [exact Fx|]. intros g Fg. destruct N as [_ N].
    destruct Two as [R|R]; rewrite R in N; [|rewrite Half]; now apply N. }
  assert (Ny : Rnd_N_pt binary64 t (succ64 x)).
  { split; [exact Fy|]. intros g Fg. rewrite <- Half. now apply Nx. }
  pose proof (U _ Nx) as A. pose proof (U _ Ny) as B. lra.
Qed.

(** t = m⁺ of q: RN(t) = q when q's canonical significand is even, else succ q. *)
Theorem rn_at_midpoint_above : forall q t gq, binary64 q -> canonical64 gq -> F2R gq = q ->
  t = (q + succ64 q) / 2 -> RN t = if Z.even (Fnum gq) then q else succ64 q.
Proof.
  intros q t gq Fq Cq Gq E.
  destruct (midpoint_facts q t Fq E) as [Par [Two [g [Gg [Cg Eg]]]]].
  assert (Fy : binary64 (succ64 q)) by (apply generic_format_succ; auto with typeclass_instances).
  destruct (canonical_generic_format radix2 (FLT_exp (-1074) 53) _ Fy) as [gy [Gy Cy]].
  pose proof (lt_succ64 q) as Lt.
  destruct Two as [R|R]; rewrite R in Gg |- *.
  - assert (g = gq) by (apply (canonical_unique radix2 (FLT_exp (-1074) 53)); auto; congruence). subst g. now rewrite Eg.
  - assert (g = gy) by (apply (canonical_unique radix2 (FLT_exp (-1074) 53)); auto; congruence). subst g.
    rewrite (Par gq gy Cq Gq Cy (eq_sym Gy)) in Eg. destruct (Z.even (Fnum gq)); [discriminate|reflexivity].
Qed.

(** t = m⁻ of q: RN(t) = q when q's canonical significand is even, else pred q. *)
Theorem rn_at_midpoint_below : forall q t gq, binary64 q -> canonical64 gq -> F2R gq = q ->
  t = (pred64 q + q) / 2 -> RN t = if Z.even (Fnum gq) then q else pred64 q.
Proof.
  intros q t gq Fq Cq Gq E.
  assert (Fp : binary64 (pred64 q)) by (apply generic_format_pred; auto with typeclass_instances).
  assert (S : succ64 (pred64 q) = q) by (apply succ_pred; auto with typeclass_instances).
  assert (E' : t = (pred64 q + succ64 (pred64 q)) / 2) by (rewrite S; exact E).
  destruct (midpoint_facts (pred64 q) t Fp E') as [Par [Two [g [Gg [Cg Eg]]]]].
  rewrite S in Par, Two.
  destruct (canonical_generic_format radix2 (FLT_exp (-1074) 53) _ Fp) as [gp [Gp Cp]].
  pose proof (lt_succ64 (pred64 q)) as Lt. rewrite S in Lt.
  destruct Two as [R|R]; rewrite R in Gg |- *.
  - assert (g = gp) by (apply (canonical_unique radix2 (FLT_exp (-1074) 53)); auto; congruence). subst g.
    rewrite (Par gp gq Cp (eq_sym Gp) Cq Gq), Eg; reflexivity.
  - assert (g = gq) by (apply (canonical_unique radix2 (FLT_exp (-1074) 53)); auto; congruence). subst g. now rewrite Eg.
Qed.

(** The decision of [round_quotient_at_boundaries] from the signs of t − m⁺ and t − m⁻ (a: t against m⁺,
    b: t against m⁻, as Rcompare): m⁺ tie, then below m⁺ and m⁻ tie, then strictly between. *)
Theorem boundary_decision_correct : forall q t gq, binary64 q -> canonical64 gq -> F2R gq = q ->
  (Rcompare t ((q + succ64 q) / 2) = Eq -> RN t = if Z.even (Fnum gq) then q else succ64 q) /\
  (Rcompare t ((q + succ64 q) / 2) = Lt -> Rcompare t ((pred64 q + q) / 2) = Eq ->
     RN t = if Z.even (Fnum gq) then q else pred64 q) /\
  (Rcompare t ((q + succ64 q) / 2) = Lt -> Rcompare t ((pred64 q + q) / 2) = Gt -> RN t = q).
Proof.
  intros q t gq Fq Cq Gq. split; [|split].
  - intros A. apply Rcompare_Eq_inv in A. now apply rn_at_midpoint_above.
  - intros _ B. apply Rcompare_Eq_inv in B. now apply rn_at_midpoint_below.
  - intros A B. apply Rcompare_Lt_inv in A. apply Rcompare_Gt_inv in B. apply rn_between_midpoints; auto; lra.
Qed.

(** A finite double B754_finite s m e is F2R of the canonical float (±m, e): its canonical integral
    significand is ±m, whose parity is m's. *)
Theorem b754_canonical : forall s m e (B : SpecFloat.bounded 53 1024 m e = true),
  canonical64 (Float radix2 (cond_Zopp s (Zpos m)) e) /\
  B2R (B754_finite s m e B : binary_float 53 1024) = F2R (Float radix2 (cond_Zopp s (Zpos m)) e) /\
  Z.even (cond_Zopp s (Zpos m)) = Z.even (Zpos m).
Proof.
  intros s m e B. split; [|split].
  - apply (canonical_canonical_mantissa 53 1024 s). apply andb_prop in B. now destruct B.
  - reflexivity.
  - destruct s; reflexivity.
Qed.
