(** * The second level of stage 2 for every bit pattern: a certain sign implies finite hi and lo.

    The first level's proof (PlaneStageTwoFinite.v) needs the "NaN or bounded" analysis of lo, because its
    radius depends on m only, and lo can be NaN while m is finite.  The second level
    ([compensated_dot3_refined_b], dot3_compensated.hpp [compensated_dot3_refined]) needs none of it: its
    radius is (2^-150 ⊗ m ⊕ 2^-52 ⊗ |lo|) ⊕ 8μ, so a finite radius means a finite lo (a NaN or infinite
    operand of ⊗ or ⊕ gives a NaN or infinite result), lo = x.lo ⊕ tail with x = TwoSum(s3.hi, σ), and a
    finite TwoSum low part means a finite TwoSum high part, which is hi ([two_sum_b_inv]).  A certain sign
    needs a finite radius ([enclosure_sign_radius_finite]).

    - [refined_radius_finite_parts]: for any inputs and any stage-1 record, a finite radius of the refined
      enclosure comes with finite hi and lo;
    - [den_refined_certain_finite], [num_refined_certain_finite]: a certain [enclosure_sign] of
      [den_refined_b], [num_refined_b] implies finite hi and lo, for every bit pattern of the inputs;
    - [den_refined_twin_sound_total], [num_refined_twin_sound_total]: PlaneRefinedTwins.v's
      [den_refined_twin_sound], [num_refined_twin_sound] without the hypothesis "hi and lo finite".

    Nothing here unfolds a float operation: the proof only reads the shape of the twin's outputs. *)

From Coq Require Import Reals ZArith List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneCascade FloatCore ConstantsCpp PlaneTwins PlaneRefinedTwins.
Open Scope R_scope.

(** The outputs' shape: hi = x.hi and lo = x.lo ⊕ tail for one TwoSum x, and the radius reads |lo|. *)
Lemma refined_shape : forall a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1,
  let e := compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1 in
  exists x y tail, hib e = fst (two_sum_b x y) /\ lob e = fadd (snd (two_sum_b x y)) tail /\
    radiusb e = fadd (fadd (fmul Cpp.refined_relative (magnitudeb stage1))
                           (fmul Cpp.refined_low_relative (fabs (lob e)))) Cpp.refined_absolute.
Proof. intros. do 3 eexists. split; [|split]; reflexivity. Qed.

Lemma refined_radius_finite_parts : forall a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1,
  let e := compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1 in
  fin (radiusb e) = true -> fin (hib e) = true /\ fin (lob e) = true.
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1 e Fr.
  destruct (refined_shape a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1) as [x [y [tail [Eh [El Er]]]]].
  fold e in Eh, El, Er. rewrite Er in Fr.
  destruct (fadd_fin _ _ Fr) as [F1 _]. destruct (fadd_fin _ _ F1) as [_ F2].
  destruct (fmul_fin _ _ F2) as [_ F3]. rewrite fabs_fin in F3.
  split; [|exact F3].
  rewrite El in F3. destruct (fadd_fin _ _ F3) as [F4 _].
  rewrite Eh. exact (proj1 (proj2 (proj2 (two_sum_b_inv x y F4)))).
Qed.

(** den = d·n, second level: a certain sign implies finite hi and lo, for every bit pattern. *)
Theorem den_refined_certain_finite : forall d0 d1 d2 n0 n1 n2 : float,
  let e := den_refined_b d0 d1 d2 n0 n1 n2 in
  enclosure_sign_lanes_b e <> uncertain_lane -> fin (hib e) = true /\ fin (lob e) = true.
Proof.
  intros d0 d1 d2 n0 n1 n2 e U.
  apply refined_radius_finite_parts.
  exact (enclosure_sign_radius_finite e (den_refined_radius_nonneg d0 d1 d2 n0 n1 n2) U).
Qed.

(** num = (p − o)·n, second level (α_i the TwoDiff low parts, which can be NaN: then lo is NaN, the
    radius NaN, the sign uncertain). *)
Theorem num_refined_certain_finite : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let e := num_refined_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  enclosure_sign_lanes_b e <> uncertain_lane -> fin (hib e) = true /\ fin (lob e) = true.
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 e U.
  apply refined_radius_finite_parts.
  exact (enclosure_sign_radius_finite e (num_refined_radius_nonneg p0 p1 p2 o0 o1 o2 n0 n1 n2) U).
Qed.

(** End to end, for every bit pattern, with no hypothesis: the sign the second level certifies is the
    sign of the exact value. *)
Theorem den_refined_twin_sound_total : forall d0 d1 d2 n0 n1 n2 : float,
  let e := den_refined_b d0 d1 d2 n0 n1 n2 in
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2).
Proof.
  intros d0 d1 d2 n0 n1 n2 e.
  destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U]; [rewrite U; exact I|].
  destruct (den_refined_certain_finite d0 d1 d2 n0 n1 n2 U) as [Fh Fl].
  exact (proj1 (den_refined_twin_sound d0 d1 d2 n0 n1 n2 Fh Fl)).
Qed.

Theorem num_refined_twin_sound_total : forall p0 p1 p2 o0 o1 o2 n0 n1 n2 : float,
  let e := num_refined_b p0 p1 p2 o0 o1 o2 n0 n1 n2 in
  certifies (sign_from_Z (enclosure_sign_lanes_b e))
    ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 e.
  destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U]; [rewrite U; exact I|].
  destruct (num_refined_certain_finite p0 p1 p2 o0 o1 o2 n0 n1 n2 U) as [Fh Fl].
  exact (proj1 (num_refined_twin_sound p0 p1 p2 o0 o1 o2 n0 n1 n2 Fh Fl)).
Qed.
