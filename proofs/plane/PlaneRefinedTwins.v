(** * The twin of the second level of stage 2, tied to the model (core/dot3_compensated.hpp,
    [compensated_dot3_refined]; plane/ray_plane_stages.hpp, [den_refined], [num_refined]).

    [compensated_dot3_refined_b] (PlaneTwins.v) is the C++ operation by operation over IEEE binary64; the
    differential runner checks it bit for bit (routine [refined]).  This file proves that whenever its
    hi, lo and radius are finite, every input and every intermediate is finite and the twin's enclosure
    is, as reals, PlaneCompensated.v's [compensated_dot3_refined] of the same inputs, so
    [compensated_dot3_refined_enclosure] (and through it PlaneCascade.v's [refined_signs_correct],
    [refined_t_correct]) applies to the bits:
    - [compensated_dot3_refined_twin]: the tie, for any a, α, b;
    - [den_refined_twin_sound], [num_refined_twin_sound]: end to end for every bit pattern of d, n (p, o),
      the sign [enclosure_sign_lanes] certifies on the second level is the sign of the exact den (num),
      given hi and lo finite (as PlaneTwins.v's first-level [den/num_compensated_twin_sound]);
    - [den_refined_twin_encloses], [num_refined_twin_encloses]: a finite enclosure of the twin encloses
      the exact value (what round_quotient's twin theorem consumes).

    The proof never unfolds the whole twin by [cbn]/[simpl] (a previous version's kernel check took
    minutes): each intermediate of the C++ is named ([set]), its finiteness and its value are derived by
    one small lemma each, and the model's definition is rewritten, innermost operation first, into the
    names. *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneCascade FloatCore ConstantsCpp PlaneTwins.
Import ListNotations.
Open Scope R_scope.

(** The chain's pair of results as reals. *)
Lemma two_sum_chain_b_pair : forall rest sigma tail,
  fin (snd (two_sum_chain_b sigma tail rest)) = true ->
  pair_R (two_sum_chain_b sigma tail rest) = two_sum_chain (B2R sigma) (B2R tail) (map B2R rest).
Proof.
  intros rest sigma tail H. destruct (two_sum_chain_b_inv rest sigma tail H) as [_ [_ [_ [E1 E2]]]].
  unfold pair_R. rewrite E1, E2. symmetry. apply surjective_pairing.
Qed.

Lemma two_sum_b_pair : forall a b, fin (snd (two_sum_b a b)) = true ->
  pair_R (two_sum_b a b) = two_sum (B2R a) (B2R b).
Proof. intros a b H. now destruct (two_sum_twin a b H) as [_ [_ [_ E]]]. Qed.

Lemma two_prod_b_pair : forall a b, fin (snd (two_prod_b a b)) = true ->
  pair_R (two_prod_b a b) = two_prod (B2R a) (B2R b).
Proof. intros a b H. now destruct (two_prod_twin a b H) as [_ [_ [_ E]]]. Qed.

Lemma ffma_neg_val : forall a b q, fin (ffma a b (fneg q)) = true ->
  B2R (ffma a b (fneg q)) = fma (B2R a) (B2R b) (- B2R q).
Proof. intros a b q H. rewrite ffma_val by exact H. rewrite fneg_val. reflexivity. Qed.

Lemma fin_fzero : fin fzero = true.
Proof. reflexivity. Qed.

(** The values, once every intermediate is named: the model's definition rewritten, innermost operation
    first, into the names (no let, no twin in sight: a small term for the kernel). *)
Lemma refined_model_named : forall (r : Dot3B) (a0 a1 a2 al0 al1 al2 b0 b1 b2 : float)
  (s2 s3 w0 w1 w2 ch x : float * float) (l0 l1 l2 tl lo rad : float),
  dot3_R r = dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2) ->
  pair_R s2 = two_sum (B2R (qb0 r)) (B2R (qb1 r)) ->
  pair_R s3 = two_sum (B2R (fst s2)) (B2R (qb2 r)) ->
  B2R l0 = fma (B2R a0) (B2R b0) (- B2R (qb0 r)) ->
  B2R l1 = fma (B2R a1) (B2R b1) (- B2R (qb1 r)) ->
  B2R l2 = fma (B2R a2) (B2R b2) (- B2R (qb2 r)) ->
  pair_R w0 = two_prod (B2R al0) (B2R b0) ->
  pair_R w1 = two_prod (B2R al1) (B2R b1) ->
  pair_R w2 = two_prod (B2R al2) (B2R b2) ->
  pair_R ch = two_sum_chain (B2R (snd s2)) 0
                [B2R (snd s3); B2R l0; B2R l1; B2R l2; B2R (fst w0); B2R (fst w1); B2R (fst w2)] ->
  B2R tl = RN (RN (RN (B2R (snd ch) + B2R (snd w0)) + B2R (snd w1)) + B2R (snd w2)) ->
  pair_R x = two_sum (B2R (fst s3)) (B2R (fst ch)) ->
  B2R lo = RN (B2R (snd x) + B2R tl) ->
  B2R rad = RN (RN (RN (refined_relative * B2R (magnitudeb r)) + RN (refined_low_relative * Rabs (B2R lo))) +
                refined_absolute) ->
  enc_R {| hib := fst x; lob := lo; radiusb := rad |} =
  compensated_dot3_refined (B2R a0) (B2R a1) (B2R a2) (B2R al0) (B2R al1) (B2R al2) (B2R b0) (B2R b1) (B2R b2).
Proof.
  intros r a0 a1 a2 al0 al1 al2 b0 b1 b2 s2 s3 w0 w1 w2 ch x l0 l1 l2 tl lo rad
    E ES2 ES3 EL0 EL1 EL2 EW0 EW1 EW2 ECH ET EX ELO ERAD.
  unfold compensated_dot3_refined. rewrite <- E. cbv zeta. cbn [dot3_R product0 product1 product2 magnitude].
  rewrite <- ES2. cbn [pair_R fst snd]. rewrite <- ES3. cbn [pair_R fst snd].
  rewrite <- EL0, <- EL1, <- EL2, <- EW0, <- EW1, <- EW2. cbn [pair_R fst snd].
  rewrite <- ECH. cbn [pair_R fst snd]. rewrite <- ET, <- EX. cbn [pair_R fst snd].
  rewrite <- ELO, <- ERAD. reflexivity.
Qed.

(** The tie: a finite radius, hi and lo mean every operation was finite and is the model's. *)
Theorem compensated_dot3_refined_twin : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  let e := compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2) in
  fin (radiusb e) = true -> fin (hib e) = true -> fin (lob e) = true ->
  fin a0 = true /\ fin a1 = true /\ fin a2 = true /\ fin al0 = true /\ fin al1 = true /\ fin al2 = true /\
  fin b0 = true /\ fin b1 = true /\ fin b2 = true /\
  enc_R e = compensated_dot3_refined (B2R a0) (B2R a1) (B2R a2) (B2R al0) (B2R al1) (B2R al2)
              (B2R b0) (B2R b1) (B2R b2).
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 e.
  unfold e, compensated_dot3_refined_b. cbv zeta.
  generalize (dot3_rounded_twin a0 a1 a2 b0 b1 b2).
  generalize (dot3_rounded_b a0 a1 a2 b0 b1 b2) as r. intros r Tw. cbv zeta in Tw.
  generalize (two_sum_b_pair (qb0 r) (qb1 r)).
  generalize (two_sum_b (qb0 r) (qb1 r)) as s2. intros s2 ES2.
  generalize (two_sum_b_pair (fst s2) (qb2 r)).
  generalize (two_sum_b (fst s2) (qb2 r)) as s3. intros s3 ES3.
  generalize (ffma_fin a0 b0 (fneg (qb0 r))). generalize (ffma_neg_val a0 b0 (qb0 r)).
  generalize (ffma a0 b0 (fneg (qb0 r))) as l0. intros l0 EL0 FL0.
  generalize (ffma_fin a1 b1 (fneg (qb1 r))). generalize (ffma_neg_val a1 b1 (qb1 r)).
  generalize (ffma a1 b1 (fneg (qb1 r))) as l1. intros l1 EL1 FL1.
  generalize (ffma_fin a2 b2 (fneg (qb2 r))). generalize (ffma_neg_val a2 b2 (qb2 r)).
  generalize (ffma a2 b2 (fneg (qb2 r))) as l2. intros l2 EL2 FL2.
  generalize (two_prod_twin al0 b0). generalize (two_prod_b_pair al0 b0).
  generalize (two_prod_b al0 b0) as w0. intros w0 EW0 TW0.
  generalize (two_prod_twin al1 b1). generalize (two_prod_b_pair al1 b1).
  generalize (two_prod_b al1 b1) as w1. intros w1 EW1 TW1.
  generalize (two_prod_twin al2 b2). generalize (two_prod_b_pair al2 b2).
  generalize (two_prod_b al2 b2) as w2. intros w2 EW2 TW2.
  set (lst := [snd s3; l0; l1; l2; fst w0; fst w1; fst w2]).
  generalize (two_sum_chain_b_inv lst (snd s2) fzero). generalize (two_sum_chain_b_pair lst (snd s2) fzero).
  generalize (two_sum_chain_b (snd s2) fzero lst) as ch. intros ch ECH ICH.
  generalize (two_sum_b_inv (fst s3) (fst ch)). generalize (two_sum_b_pair (fst s3) (fst ch)).
  generalize (two_sum_b (fst s3) (fst ch)) as x. intros x EX IX.
  generalize (fadd_val (fadd (fadd (snd ch) (snd w0)) (snd w1)) (snd w2)). generalize (fadd_fin (fadd (fadd (snd ch) (snd w0)) (snd w1)) (snd w2)).
  generalize (fadd (fadd (fadd (snd ch) (snd w0)) (snd w1)) (snd w2)) as tl. intros tl FT VT.
  generalize (fadd_val (snd x) tl). generalize (fadd_fin (snd x) tl).
  generalize (fadd (snd x) tl) as lo. intros lo FLO VLO.
  cbn [hib lob radiusb]. intros Frad Fhi Flo.
  (* finiteness, from the outputs down *)
  destruct (fadd_fin _ _ Frad) as [Frad1 _]. destruct (fadd_fin _ _ Frad1) as [Fm1 Fl1].
  destruct (fmul_fin _ _ Fm1) as [_ Fm]. destruct (fmul_fin _ _ Fl1) as [_ _].
  destruct (Tw Fm) as [Fa0 [Fa1 [Fa2 [Fb0 [Fb1 [Fb2 [Fq0 [Fq1 [Fq2 [_ E]]]]]]]]]].
  destruct (FLO Flo) as [Fx Ftl].
  destruct (FT Ftl) as [Ft1 Fw2]. destruct (fadd_fin _ _ Ft1) as [Ft2 Fw1].
  destruct (fadd_fin _ _ Ft2) as [Fch Fw0].
  destruct (ICH Fch) as [_ [Fl [Fs2 _]]].
  destruct Fs2 as [Fs2|Fs2]; [discriminate Fs2|].
  unfold lst in Fl.
  apply Forall_cons_iff in Fl; destruct Fl as [Fs3 Fl]. apply Forall_cons_iff in Fl; destruct Fl as [Gl0 Fl].
  apply Forall_cons_iff in Fl; destruct Fl as [Gl1 Fl]. apply Forall_cons_iff in Fl; destruct Fl as [Gl2 _].
  destruct (TW0 Fw0) as [Fal0 _]. destruct (TW1 Fw1) as [Fal1 _]. destruct (TW2 Fw2) as [Fal2 _].
  repeat split; try assumption.
  apply (refined_model_named r a0 a1 a2 al0 al1 al2 b0 b1 b2 s2 s3 w0 w1 w2 ch x l0 l1 l2 tl lo).
  - exact E.
  - exact (ES2 Fs2).
  - exact (ES3 Fs3).
  - exact (EL0 Gl0).
  - exact (EL1 Gl1).
  - exact (EL2 Gl2).
  - exact (EW0 Fw0).
  - exact (EW1 Fw1).
  - exact (EW2 Fw2).
  - exact (ECH Fch).
  - rewrite (VT Ftl), (fadd_val _ _ Ft1), (fadd_val _ _ Ft2). reflexivity.
  - exact (EX Fx).
  - exact (VLO Flo).
  - rewrite (fadd_val _ _ Frad), (fadd_val _ _ Frad1), (fmul_val _ _ Fm1), (fmul_val _ _ Fl1), fabs_val.
    rewrite cpp_refined_relative, cpp_refined_low_relative, cpp_refined_absolute. reflexivity.
Qed.

(** The radius is "non-negative or NaN": sums and products of non-negative constants, m and |lo|. *)
Lemma refined_radius_nonneg : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  nonneg (radiusb (compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 (dot3_rounded_b a0 a1 a2 b0 b1 b2))).
Proof.
  intros. unfold compensated_dot3_refined_b. cbv zeta. cbn [radiusb].
  apply fadd_nonneg; [apply fadd_nonneg; apply fmul_nonneg|]; try const_nonneg; try apply fabs_nonneg.
  unfold dot3_rounded_b. cbn [magnitudeb]. apply fadd_nonneg; [apply fadd_nonneg|]; apply fabs_nonneg.
Qed.

Lemma den_refined_radius_nonneg : forall d0 d1 d2 n0 n1 n2, nonneg (radiusb (den_refined_b d0 d1 d2 n0 n1 n2)).
Proof. intros. apply refined_radius_nonneg. Qed.

Lemma num_refined_radius_nonneg : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  nonneg (radiusb (num_refined_b p0 p1 p2 o0 o1 o2 n0 n1 n2)).
Proof. intros. apply refined_radius_nonneg. Qed.

(** den's second level ([den_refined]: α = +0): a finite enclosure is the model's [refined_den_enclosure]
    of PlaneCascade.v and encloses d·n; d and n are finite. *)
Theorem den_refined_twin_encloses : forall d0 d1 d2 n0 n1 n2 : float,
  let e := den_refined_b d0 d1 d2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  fin d0 = true /\ fin d1 = true /\ fin d2 = true /\ fin n0 = true /\ fin n1 = true /\ fin n2 = true /\
  enc_R e = compensated_dot3_refined (B2R d0) (B2R d1) (B2R d2) 0 0 0 (B2R n0) (B2R n1) (B2R n2) /\
  encloses (enc_R e) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2).
Proof.
  intros d0 d1 d2 n0 n1 n2 e Fh Fl Fr.
  destruct (compensated_dot3_refined_twin d0 d1 d2 fzero fzero fzero n0 n1 n2 Fr Fh Fl)
    as [F0 [F1 [F2 [_ [_ [_ [G0 [G1 [G2 E]]]]]]]]].
  change (B2R fzero) with 0 in E. fold (den_refined_b d0 d1 d2 n0 n1 n2) in E. fold e in E.
  repeat split; try assumption.
  rewrite E. apply compensated_den_refined_enclosure; apply binary64_B2R.
Qed.

(** num's second level ([num_refined]: a_i = p_i ⊖ o_i, α_i its TwoDiff low part). *)
Theorem num_refined_twin_encloses : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let e := num_refined_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  fin p0 = true /\ fin p1 = true /\ fin p2 = true /\ fin o0 = true /\ fin o1 = true /\ fin o2 = true /\
  fin n0 = true /\ fin n1 = true /\ fin n2 = true /\
  encloses (enc_R e) ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 e Fh Fl Fr.
  unfold e, num_refined_b in Fh, Fl, Fr |- *. cbv zeta in Fh, Fl, Fr |- *.
  destruct (compensated_dot3_refined_twin _ _ _ _ _ _ n0 n1 n2 Fr Fh Fl)
    as [_ [_ [_ [A0 [A1 [A2 [G0 [G1 [G2 E]]]]]]]]].
  destruct (two_diff_b_parts _ _ A0) as [? [? [X0 Y0]]]. destruct (two_diff_b_parts _ _ A1) as [? [? [X1 Y1]]].
  destruct (two_diff_b_parts _ _ A2) as [? [? [X2 Y2]]].
  repeat split; try assumption.
  rewrite E, X0, X1, X2, Y0, Y1, Y2. apply compensated_num_refined_enclosure; apply binary64_B2R.
Qed.

(** End to end, for every bit pattern: the sign the second level certifies is the exact sign, given hi and
    lo finite (the hypothesis of the first level's [den/num_compensated_twin_sound]; PlaneRefinedFinite.v
    discharges it: [den_refined_twin_sound_total], [num_refined_twin_sound_total]). *)
Theorem den_refined_twin_sound : forall d0 d1 d2 n0 n1 n2 : float,
  let e := den_refined_b d0 d1 d2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2) /\
  (enclosure_sign_lanes_b e <> uncertain_lane -> fin (radiusb e) = true).
Proof.
  intros. apply stage2_twin_sound_gen; [apply den_refined_radius_nonneg | intros Fh Fl Fr | assumption ..].
  now destruct (den_refined_twin_encloses d0 d1 d2 n0 n1 n2 Fh Fl Fr) as [_ [_ [_ [_ [_ [_ [_ En]]]]]]].
Qed.

Theorem num_refined_twin_sound : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let e := num_refined_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  fin (hib e) = true -> fin (lob e) = true ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e))
    ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2) /\
  (enclosure_sign_lanes_b e <> uncertain_lane -> fin (radiusb e) = true).
Proof.
  intros. apply stage2_twin_sound_gen; [apply num_refined_radius_nonneg | intros Fh Fl Fr | assumption ..].
  now destruct (num_refined_twin_encloses p0 p1 p2 o0 o1 o2 n0 n1 n2 Fh Fl Fr)
    as [_ [_ [_ [_ [_ [_ [_ [_ [_ En]]]]]]]]].
Qed.
