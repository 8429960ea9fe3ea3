(** * The correctly rounded quotient at its rounding boundaries (kernel/src/core/quotient_boundary.hpp).

    [round_quotient_at_boundaries(num, den, den_sign, q)] decides RN(Σnum/Σden) for a candidate double q from
    the exact signs of t − m⁺ and t − m⁻, m± the midpoints of q and its neighbours (next_up, next_down of
    kernel/src/core/neighbours.hpp: Flocq's [Bsucc], [Bpred]), each sign that of 2·Σnum − (x + y)·Σden
    (compare_quotients_expansion on the expansions num, den, TwoSum(x, y) and {2}) times den's sign.
    This file: its twin over binary64, one Flocq operation per C++ operation ([side_of_midpoint_b],
    [round_quotient_at_boundaries_b]; the parity of q as the parity of its significand field, which is the
    last bit of its pattern: MidpointRounding.v's [b754_canonical]), and
    - [side_of_midpoint_sound]: a certain side is the sign of t − (x + y)/2, for den's sign ±1 as given;
    - [round_quotient_at_boundaries_sound]: a value is finite and RN(Σnum/Σden), for expansions of at most
      16 components (compare_quotients_expansion's range) and den_sign the sign of Σden (nonzero).
    The differential runner runs the twin against the C++ (routine quotient_boundary). *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Flocq Require IEEE754.Binary IEEE754.Bits.
From Raykernel Require Import Constants Model FloatCore ConstantsCpp PlaneTwins Expansions MidpointRounding.
Import ListNotations.
Open Scope R_scope.

Definition two_f : float := of_bits 4611686018427387904.  (* 2.0 *)

Lemma two_f_value : B2R two_f = 2 /\ fin two_f = true.
Proof. split; [vm_compute; lra | reflexivity]. Qed.

(** [static_cast<Sign>(static_cast<int>(s) * den_sign)] for a certain s. *)
Definition sign_z (s : sign) : Z := match s with Negative => -1 | Zero => 0 | Positive => 1 | Uncertain => 0 end.
Definition z_sign (z : Z) : sign := if Z.ltb z 0 then Negative else if Z.eqb z 0 then Zero else Positive.

(** [boundary_internal::side_of_midpoint(num, den, den_sign, x, y)]. *)
Definition side_of_midpoint_b (num den : list float) (den_sign : Z) (x y : float) : sign :=
  let s := two_sum_b x y in
  if negb (fin (snd s)) then Uncertain else
  match compare_quotients_expansion_b num den true (from_pair s) [two_f] true with
  | Uncertain => Uncertain
  | d => z_sign (sign_z d * den_sign)
  end.

(** [boundary_internal::even(q)]: (bits & 1) == 0, as the parity of the significand field. *)
Definition even_b (q : float) : bool :=
  match q with B754_finite _ m _ _ => Z.even (Zpos m) | _ => true end.

(** [round_quotient_at_boundaries(num, den, den_sign, q)]. *)
Definition round_quotient_at_boundaries_b (num den : list float) (den_sign : Z) (q : float) : option float :=
  let magnitude := fabs q in
  if negb (fle Cpp.half_gap_min_magnitude magnitude && flt magnitude Cpp.largest_finite)%bool then None else
  let up := Bsucc q in
  let down := Bpred q in
  match side_of_midpoint_b num den den_sign q up with
  | Zero => Some (if even_b q then q else up)
  | Negative =>
    match side_of_midpoint_b num den den_sign down q with
    | Zero => Some (if even_b q then q else down)
    | Positive => Some q
    | _ => None
    end
  | _ => None
  end.

Lemma all_fin_from_pair : forall p, fin (fst p) = true -> fin (snd p) = true -> all_fin (from_pair p).
Proof.
  intros [h l] Fh Fl. unfold from_pair, finish, push. simpl in *.
  destruct (feq l fzero); destruct (_ || _)%bool; simpl; repeat constructor; auto.
Qed.

Lemma sign_transfer : forall X Y D, X * (2 * D) = Y ->
  (0 < D -> (Y < 0 -> X < 0) /\ (Y = 0 -> X = 0) /\ (0 < Y -> 0 < X)) /\
  (D < 0 -> (Y < 0 -> 0 < X) /\ (Y = 0 -> X = 0) /\ (0 < Y -> X < 0)).
Proof.
  intros X Y D E. subst Y. split; intros P; repeat split; intros H.
  - destruct (Rlt_or_le X 0) as [L|L]; [exact L|]. nra.
  - destruct (Rmult_integral _ _ H) as [Z|Z]; [exact Z|lra].
  - destruct (Rlt_or_le 0 X) as [L|L]; [exact L|]. nra.
  - destruct (Rlt_or_le 0 X) as [L|L]; [exact L|]. nra.
  - destruct (Rmult_integral _ _ H) as [Z|Z]; [exact Z|lra].
  - destruct (Rlt_or_le X 0) as [L|L]; [exact L|]. nra.
Qed.

(** The hypothesis of the theorems below: den_sign is ±1, the sign of Σden (the callers' checked sign of den). *)
Definition den_sign_is (ds : Z) (den : list float) : Prop :=
  (ds = 1%Z /\ 0 < sumR den) \/ (ds = (-1)%Z /\ sumR den < 0).

(** A certain side is the sign of t − (x + y)/2, t = Σnum/Σden, for den_sign ±1 the sign of Σden. *)
Theorem side_of_midpoint_sound : forall num den ds x y,
  (length num <= 16)%nat -> (length den <= 16)%nat ->
  den_sign_is ds den ->
  side_of_midpoint_b num den ds x y <> Uncertain ->
  fin x = true /\ fin y = true /\
  certifies (side_of_midpoint_b num den ds x y) (sumR num / sumR den - (B2R x + B2R y) / 2).
Proof.
  intros num den ds x y Ln Ld Ds NU. unfold den_sign_is in Ds. unfold side_of_midpoint_b in *.
  destruct (fin (snd (two_sum_b x y))) eqn:Fl; [|simpl in NU; congruence]. simpl in *.
  destruct (two_sum_b_inv x y Fl) as [Fx [Fy [Fh _]]].
  destruct (two_sum_b_exact x y Fl) as [_ [_ S]].
  destruct (from_pair_exact _ (all_fin_from_pair _ Fh Fl)) as [_ [_ Sp]].
  assert (Lp : (length (from_pair (two_sum_b x y)) <= 16)%nat) by (pose proof (length_from_pair (two_sum_b x y)); lia).
  assert (L2 : (length [two_f] <= 16)%nat) by (simpl; lia).
  pose proof (compare_quotients_expansion_sound num den true (from_pair (two_sum_b x y)) [two_f] true
                Ln Ld Lp L2) as C.
  assert (T : sumR [two_f] = 2) by (rewrite sumR_cons, (proj1 two_f_value); unfold sumR; simpl; lra).
  rewrite T, Sp in C.
  split; [exact Fx|]. split; [exact Fy|].
  set (N := sumR num) in *. set (D := sumR den) in *.
  assert (Dnz : D <> 0) by (destruct Ds as [[_ P]|[_ P]]; lra).
  assert (K : (N / D - (B2R x + B2R y) / 2) * (2 * D) = N * 2 - (B2R (snd (two_sum_b x y)) + B2R (fst (two_sum_b x y))) * D).
  { replace (B2R (snd (two_sum_b x y)) + B2R (fst (two_sum_b x y))) with (B2R x + B2R y) by lra. field. exact Dnz. }
  destruct (sign_transfer _ _ _ K) as [Pos Neg].
  destruct (compare_quotients_expansion_b num den true (from_pair (two_sum_b x y)) [two_f] true);
    [| | |congruence]; simpl in C;
    destruct Ds as [[E P]|[E P]]; subst ds; simpl; [apply (Pos P)|apply (Neg P)|apply (Pos P)|apply (Neg P)|
                                                    apply (Pos P)|apply (Neg P)]; exact C.
Qed.

Lemma bsucc_value : forall q : float, fin q = true -> fin (Bsucc q) = true -> B2R (Bsucc q) = succ64 (B2R q).
Proof.
  intros q Fq Fs. pose proof (Bsucc_correct 53 1024 _ _ q Fq) as H.
  destruct (Rlt_bool _ _); [now destruct H|]. destruct (Bsucc q); simpl in H; try discriminate; easy.
Qed.

Lemma bpred_value : forall q : float, fin q = true -> fin (Bpred q) = true -> B2R (Bpred q) = pred64 (B2R q).
Proof.
  intros q Fq Fs. pose proof (Bpred_correct 53 1024 _ _ q Fq) as H.
  destruct (Rlt_bool _ _); [now destruct H|]. destruct (Bpred q); simpl in H; try discriminate; easy.
Qed.

(** A value of [round_quotient_at_boundaries] is finite and RN(Σnum/Σden). *)
Theorem round_quotient_at_boundaries_sound : forall num den ds q r,
  (length num <= 16)%nat -> (length den <= 16)%nat ->
  den_sign_is ds den ->
  round_quotient_at_boundaries_b num den ds q = Some r ->
  fin r = true /\ B2R r = RN (sumR num / sumR den).
Proof.
  intros num den ds q r Ln Ld Ds H. unfold round_quotient_at_boundaries_b in H.
  destruct (negb _) eqn:G; [discriminate|].
  set (t := sumR num / sumR den) in *.
  assert (Canon : forall s m e B, even_b (B754_finite s m e B) = Z.even (Fnum (Float radix2 (cond_Zopp s (Zpos m)) e))).
  { intros s m e B. simpl. now destruct s. }
  destruct (side_of_midpoint_b num den ds q (Bsucc q)) eqn:A; try discriminate.
  - (* t below m⁺ *)
    assert (NA : side_of_midpoint_b num den ds q (Bsucc q) <> Uncertain) by (rewrite A; discriminate).
    destruct (side_of_midpoint_sound num den ds q (Bsucc q) Ln Ld Ds NA) as [Fq [Fu Ca]].
    rewrite A in Ca. simpl in Ca. rewrite (bsucc_value q Fq Fu) in Ca. fold t in Ca.
    destruct (side_of_midpoint_b num den ds (Bpred q) q) eqn:B; try discriminate;
      assert (NB : side_of_midpoint_b num den ds (Bpred q) q <> Uncertain) by (rewrite B; discriminate);
      destruct (side_of_midpoint_sound num den ds (Bpred q) q Ln Ld Ds NB) as [Fd [_ Cb]];
      rewrite B in Cb; simpl in Cb; rewrite (bpred_value q Fq Fd) in Cb; fold t in Cb; injection H as <-.
    + (* t = m⁻ *)
      destruct q as [s|s| |s m e Bq]; try discriminate Fq.
      * (* q = ±0: the guard 2^-968 ≤ |q| excluded it *)
        exfalso. destruct s; vm_compute in G; discriminate G.
      * destruct (b754_canonical s m e Bq) as [C [V _]].
        rewrite Canon. destruct (Z.even _) eqn:Ev; split.
        -- exact Fq.
        -- pose proof (rn_at_midpoint_below _ t _ (binary64_B2R _) C (eq_sym V)) as R. rewrite Ev in R. rewrite R; [reflexivity|lra].
        -- exact Fd.
        -- pose proof (rn_at_midpoint_below _ t _ (binary64_B2R _) C (eq_sym V)) as R. rewrite Ev in R.
           rewrite R; [now rewrite (bpred_value _ Fq Fd)|lra].
    + (* strictly between *)
      split; [exact Fq|]. symmetry. apply rn_between_midpoints; [apply binary64_B2R|lra].
  - (* t = m⁺ *)
    assert (NA : side_of_midpoint_b num den ds q (Bsucc q) <> Uncertain) by (rewrite A; discriminate).
    destruct (side_of_midpoint_sound num den ds q (Bsucc q) Ln Ld Ds NA) as [Fq [Fu Ca]].
    rewrite A in Ca. simpl in Ca. rewrite (bsucc_value q Fq Fu) in Ca. fold t in Ca. injection H as <-.
    destruct q as [s|s| |s m e Bq]; try discriminate Fq.
    + exfalso. destruct s; vm_compute in G; discriminate G.
    + destruct (b754_canonical s m e Bq) as [C [V _]].
      rewrite Canon. destruct (Z.even _) eqn:Ev; split.
      * exact Fq.
      * pose proof (rn_at_midpoint_above _ t _ (binary64_B2R _) C (eq_sym V)) as R. rewrite Ev in R. rewrite R; [reflexivity|lra].
      * exact Fu.
      * pose proof (rn_at_midpoint_above _ t _ (binary64_B2R _) C (eq_sym V)) as R. rewrite Ev in R.
        rewrite R; [now rewrite (bsucc_value _ Fq Fu)|lra].
Qed.

(** Liveness: ties are decided (no exact stage). t = (2^-53 + 1)/1 is the midpoint of 1 and its successor:
    RN(t) = 1 (even); t = 3·2^-53 + 1 is the midpoint of 1 + 2^-52 (odd) and 1 + 2^-51: RN(t) = 1 + 2^-51;
    and a t strictly between the midpoints of q = 1, t = 1 + 2^-60, gives q. *)
(** [round_quotient_near(num, den, den_sign, q)]: the candidate, then its neighbours (next_up and next_down,
    kernel/src/core/neighbours.hpp: [Bsucc] and [Bpred]). *)
Definition round_quotient_near_b (num den : list float) (den_sign : Z) (q : float) : option float :=
  match round_quotient_at_boundaries_b num den den_sign q with
  | Some r => Some r
  | None =>
    match round_quotient_at_boundaries_b num den den_sign (Bsucc q) with
    | Some r => Some r
    | None => round_quotient_at_boundaries_b num den den_sign (Bpred q)
    end
  end.

Theorem round_quotient_near_sound : forall num den ds q r,
  (length num <= 16)%nat -> (length den <= 16)%nat ->
  den_sign_is ds den ->
  round_quotient_near_b num den ds q = Some r ->
  fin r = true /\ B2R r = RN (sumR num / sumR den).
Proof.
  intros num den ds q r Ln Ld Ds. unfold round_quotient_near_b.
  destruct (round_quotient_at_boundaries_b num den ds q) as [x|] eqn:A.
  - intros E. injection E as <-. exact (round_quotient_at_boundaries_sound _ _ _ _ _ Ln Ld Ds A).
  - destruct (round_quotient_at_boundaries_b num den ds (Bsucc q)) as [x|] eqn:B.
    + intros E. injection E as <-. exact (round_quotient_at_boundaries_sound _ _ _ _ _ Ln Ld Ds B).
    + intros C. exact (round_quotient_at_boundaries_sound _ _ _ _ _ Ln Ld Ds C).
Qed.

Lemma round_quotient_at_boundaries_tie_even :
  option_map to_bits (round_quotient_at_boundaries_b [of_bits 4368491638549381120; of_bits 4607182418800017408]
                        [of_bits 4607182418800017408] 1 (of_bits 4607182418800017408)) = Some 4607182418800017408%Z.
Proof. vm_compute. reflexivity. Qed.

Lemma round_quotient_at_boundaries_tie_odd :
  option_map to_bits (round_quotient_at_boundaries_b [of_bits 4375247037990436864; of_bits 4607182418800017408]
                        [of_bits 4607182418800017408] 1 (of_bits 4607182418800017409)) = Some 4607182418800017410%Z.
Proof. vm_compute. reflexivity. Qed.

Lemma round_quotient_at_boundaries_between :
  option_map to_bits (round_quotient_at_boundaries_b [of_bits 4336966441157787648; of_bits 4607182418800017408]
                        [of_bits 4607182418800017408] 1 (of_bits 4607182418800017408)) = Some 4607182418800017408%Z.
Proof. vm_compute. reflexivity. Qed.
