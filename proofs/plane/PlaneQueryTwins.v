(** * Twins of one ray–plane query (plane/ray_plane_stages.hpp, core/quotient_rounding.hpp)

    The routines of PlaneTwins.v and Expansions.v as the query calls them, and the lean rounding, so that the
    differential runner also checks the call sites (a den constant passed for num, a wrong low part, the
    α = 0 form for num) and the quotient:
    - [prepare_divisor_b], [half_gap_b], [round_quotient_b]: prepare_divisor, half_gap_to_nearer_neighbour
      (on the bits, through Flocq's Bits), round_quotient;
    - [fast_answer_b]: fast_answer(RayPlaneTermsT<V>) (the form the batch lanes run), and
      [fast_answer_pair_b]: fast_answer(o, d, p, n), den and num as the two lanes of a Lanes2 (den's
      a_i = d_i ⊖ 0 with its TwoDiff error, through compensated_dot3, not the α = 0 form);
    - [fast_relation_b], [fast_relation_pair_b]: fast_relation (|s| > B), both forms;
    - [ray_plane_expansions_b]: ray_plane_expansions (stage 3), the C++ as it is.

    These Definitions are checked against the C++ by the runner, and tied to the real-number models at the
    end of this file: [half_gap_twin] and [round_quotient_twin] (every intermediate of a certified rounding
    finite and equal to QuotientRounding.v's), [round_quotient_twin_sound] (t = RN(num/den), from
    [round_quotient_sound]); [fast_relation_twin_correct] and [fast_answer_twin_correct] (the twins of
    PlaneCascade.v's [fast_relation_correct] and [fast_answer_correct], end to end for every bit pattern of
    o, d, p, n).  Not tied yet: [fast_answer_pair_b], [fast_relation_pair_b] (the Lanes2 forms) and
    [ray_plane_expansions_b] (proofs/README.md, "What remains"). *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Flocq Require IEEE754.Binary IEEE754.Bits.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification QuotientRounding PlaneCascade FloatCore
  ConstantsCpp PlaneTwins Expansions.
Import ListNotations.
Open Scope R_scope.

Record Vec3B := V3 { vxb : float; vyb : float; vzb : float }.

(** [p - o] (ray_plane_terms) and [two_diff(p, o).hi] are the same operation. *)
Lemma fsub_two_diff_hi : forall x y, fsub x y = fst (two_diff_b x y).
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; unfold fsub, two_diff_b, two_sum_b, fadd, fneg; cbn;
    try reflexivity; destruct sx, sy; reflexivity.
Qed.

(** ** quotient_rounding.hpp *)

Record DivisorB := { dhib : float; dlob : float; dradiusb : float; dreciprocalb : float; din_rangeb : bool }.

Definition one_f : float := of_bits 4607182418800017408.  (* 1.0 *)

(** [prepare_divisor(den)]: the guard 2^-1000 ≤ |D| ≤ 2^1000 ([abs_D >= min] is [min <= abs_D]: the same
    comparison, false on NaN), and 1 ⊘ D, or 1 ⊘ 1 out of range. *)
Definition prepare_divisor_b (den : EnclosureB) : DivisorB :=
  let D := two_sum_b (hib den) (lob den) in
  let abs_D := fabs (fst D) in
  let in_range := (fle Cpp.divisor_min_magnitude abs_D && fle abs_D Cpp.divisor_max_magnitude)%bool in
  {| dhib := fst D; dlob := snd D; dradiusb := radiusb den;
     dreciprocalb := fdiv one_f (if in_range then fst D else one_f); din_rangeb := in_range |}.

(** [half_gap_to_nearer_neighbour(q)] on the 64-bit pattern: ((|q|'s biased exponent − (53 or 54)) << 52),
    in unsigned 64-bit arithmetic (wrapping, as the C++). *)
Definition word (z : Z) : Z := Z.land z (2 ^ 64 - 1).
Definition half_gap_b (q : float) : float :=
  let bits := to_bits (fabs q) in
  let biased_exponent := Z.shiftr bits 52 in
  let shift := (53 + (if Z.eqb (Z.land bits (2 ^ 52 - 1)) 0 then 1 else 0))%Z in
  of_bits (word (Z.shiftl (word (biased_exponent - shift)) 52)).

(** [round_quotient(num, den)]: (t, certain). *)
Definition round_quotient_b (num : EnclosureB) (den : DivisorB) : float * bool :=
  let N := two_sum_b (hib num) (lob num) in
  let q0 := fmul (fst N) (dreciprocalb den) in
  let r1 := ffma (fneg q0) (dhib den) (fst N) in
  let r2 := ffma (fneg q0) (dlob den) (snd N) in
  let c := fmul (fadd r1 r2) (dreciprocalb den) in
  let q := fadd q0 c in
  let w := fsub c (fsub q q0) in
  let abs_q0 := fabs q0 in
  let abs_D := fabs (dhib den) in
  let abs_q := fabs q in
  let in_range := ((fle Cpp.quotient_min_magnitude (fabs (fst N)) && din_rangeb den) &&
                   (fle Cpp.quotient_min_magnitude abs_q && fle abs_q Cpp.largest_finite))%bool in
  let x := fmul (fadd (fmul abs_q0 (dradiusb den)) (radiusb num)) Cpp.quotient_enclosure_factor in
  let y := fmul (fadd (fmul abs_q0 Cpp.quotient_relative) (fabs w)) abs_D in
  let h := half_gap_b q in
  (q, (in_range && flt (fmul (fadd x y) Cpp.quotient_test_factor) (fmul h abs_D))%bool).

(** ** plane/ray_plane_stages.hpp *)

Definition certain_lane (s : Z) : bool := negb (Z.eqb s uncertain_lane).
Definition first_certain_lanes_b (first second : Z) : Z := if Z.eqb first uncertain_lane then second else first.

(** [fast_answer_from(den_filter, num_filter, den, num)]: (t, behind, certain, relation_by_filter). *)
Definition fast_answer_from_b (den_filter num_filter : Z) (den num : EnclosureB) : float * bool * bool * bool :=
  let den_sign := first_certain_lanes_b den_filter (enclosure_sign_lanes_b den) in
  let num_sign := first_certain_lanes_b num_filter (enclosure_sign_lanes_b num) in
  let t := round_quotient_b num (prepare_divisor_b den) in
  (fst t, Z.ltb (num_sign * den_sign) 0,
   (certain_lane den_sign && certain_lane num_sign && snd t)%bool,
   (certain_lane den_filter && certain_lane num_filter)%bool).

(** [fast_answer(RayPlaneTermsT<V>)]: the terms (diff_i = p_i ⊖ o_i, stage 1 of den and num), den through
    the α = 0 form, num with the TwoDiff low parts. *)
Definition fast_answer_b (o d p n : Vec3B) : float * bool * bool * bool :=
  let diff0 := fsub (vxb p) (vxb o) in let diff1 := fsub (vyb p) (vyb o) in let diff2 := fsub (vzb p) (vzb o) in
  let den1 := dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n) in
  let num1 := dot3_rounded_b diff0 diff1 diff2 (vxb n) (vyb n) (vzb n) in
  let den2 := compensated_dot3_exact_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n) den1 in
  let num2 := compensated_dot3_b diff0 diff1 diff2
                (snd (two_diff_b (vxb p) (vxb o))) (snd (two_diff_b (vyb p) (vyb o))) (snd (two_diff_b (vzb p) (vzb o)))
                (vxb n) (vyb n) (vzb n) num1 in
  fast_answer_from_b (dot3_filter_lanes_b den1 Cpp.filter_den_relative)
    (dot3_filter_lanes_b num1 Cpp.filter_num_relative) den2 num2.

(** [fast_answer(o, d, p, n)]: lane 0 den from a_i = TwoDiff(d_i, +0), lane 1 num from TwoDiff(p_i, o_i),
    both through [compensated_dot3]. *)
Definition lane_enclosure_b (x0 y0 x1 y1 x2 y2 : float) (n : Vec3B) : Dot3B * EnclosureB :=
  let a0 := two_diff_b x0 y0 in let a1 := two_diff_b x1 y1 in let a2 := two_diff_b x2 y2 in
  let s1 := dot3_rounded_b (fst a0) (fst a1) (fst a2) (vxb n) (vyb n) (vzb n) in
  (s1, compensated_dot3_b (fst a0) (fst a1) (fst a2) (snd a0) (snd a1) (snd a2) (vxb n) (vyb n) (vzb n) s1).

Definition fast_answer_pair_b (o d p n : Vec3B) : float * bool * bool * bool :=
  let den := lane_enclosure_b (vxb d) fzero (vyb d) fzero (vzb d) fzero n in
  let num := lane_enclosure_b (vxb p) (vxb o) (vyb p) (vyb o) (vzb p) (vzb o) n in
  fast_answer_from_b (dot3_filter_lanes_b (fst den) Cpp.filter_den_relative)
    (dot3_filter_lanes_b (fst num) Cpp.filter_num_relative) (snd den) (snd num).

(** [fast_relation]: (behind, certain), |s| > B for both. *)
Definition fast_relation_from_b (den num : Dot3B) : bool * bool :=
  let den_bound := fadd (fmul Cpp.filter_den_relative (magnitudeb den)) Cpp.filter_absolute in
  let num_bound := fadd (fmul Cpp.filter_num_relative (magnitudeb num)) Cpp.filter_absolute in
  (xorb (flt (valueb num) fzero) (flt (valueb den) fzero),
   (flt den_bound (fabs (valueb den)) && flt num_bound (fabs (valueb num)))%bool).

Definition fast_relation_b (o d p n : Vec3B) : bool * bool :=
  fast_relation_from_b (dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n))
    (dot3_rounded_b (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o)) (vxb n) (vyb n) (vzb n)).

(** The Lanes2 form: den's a_i = d_i ⊖ 0. *)
Definition fast_relation_pair_b (o d p n : Vec3B) : bool * bool :=
  fast_relation_from_b
    (dot3_rounded_b (fsub (vxb d) fzero) (fsub (vyb d) fzero) (fsub (vzb d) fzero) (vxb n) (vyb n) (vzb n))
    (dot3_rounded_b (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o)) (vxb n) (vyb n) (vzb n)).

(** [ray_plane_expansions(q)] (stage 3): (num, den, exact). *)
Definition ray_plane_expansions_b (fts : float -> float -> float * float) (o d p n : Vec3B) :=
  build_expansions_gen fts (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d) (vxb p) (vyb p) (vzb p)
    (vxb n) (vyb n) (vzb n).

(** ** The twins tied to the models: quotient_rounding.hpp

    [half_gap_twin]: for a double q with |q| ≥ 2^-968, the bit manipulation [half_gap_b] is finite and is
    QuotientRounding.v's [half_gap] (the rounding's test reads the gap from q's bits).
    [round_quotient_twin]: when [round_quotient_b num (prepare_divisor_b den)] certifies (radii non-negative
    or NaN, as every producer's are), every input and every intermediate is finite and t is the model's
    [round_quotient (enc_R num) (prepare_divisor (enc_R den))], which certifies too; the test's right side
    h ⊗ |D| may overflow to +inf, where the model's RN(h·|D|) ≥ 2^1024 exceeds the finite left side just as
    well.  [round_quotient_twin_sound]: with [round_quotient_sound], t = RN(num/den) for the reals the
    enclosures enclose. *)

Lemma normal_mantissa : forall s m e (H : SpecFloat.bounded 53 1024 m e = true),
  bpow radix2 (-1021) <= Rabs (B2R (B754_finite s m e H)) ->
  (2 ^ 52 <= Zpos m < 2 ^ 53)%Z /\ (-1074 < e)%Z.
Proof.
  intros s m e H R. cbn [BinarySingleNaN.B2R] in R. rewrite <- F2R_Zabs, abs_cond_Zopp in R. simpl Z.abs in R.
  pose proof H as H'. unfold SpecFloat.bounded in H'. apply andb_prop in H'. destruct H' as [C _].
  unfold SpecFloat.canonical_mantissa in C. apply Zeq_bool_eq in C.
  rewrite Zpos_digits2_pos in C.
  pose proof (Zdigits_correct radix2 (Zpos m)) as [D1 D2].
  simpl Z.abs in D1, D2.
  unfold SpecFloat.fexp, SpecFloat.emin in C.
  assert (E : (-1074 < e)%Z).
  { destruct (Z.lt_ge_cases (-1074) e) as [L|L]; [exact L|].
    exfalso. assert (Ee : e = (-1074)%Z) by lia. subst e.
    assert (Dle : (Zdigits radix2 (Zpos m) <= 53)%Z) by lia.
    assert (M : IZR (Zpos m) < bpow radix2 53).
    { rewrite <- IZR_Zpower by lia. apply IZR_lt. eapply Z.lt_le_trans; [exact D2|].
      apply Zpower_le. exact Dle. }
    unfold F2R in R. simpl Fnum in R. simpl Fexp in R.
    assert (L2 : IZR (Zpos m) * bpow radix2 (-1074) < bpow radix2 53 * bpow radix2 (-1074))
      by (apply Rmult_lt_compat_r; [apply bpow_gt_0 | exact M]).
    rewrite <- bpow_plus in L2. simpl (53 + -1074)%Z in L2. lra. }
  split; [|exact E].
  assert (Dg : Zdigits radix2 (Zpos m) = 53%Z) by lia.
  rewrite Dg in D1, D2. split.
  - change (2 ^ 52)%Z with (Zpower radix2 (53 - 1)). exact D1.
  - change (2 ^ 53)%Z with (Zpower radix2 53). exact D2.
Qed.

Lemma of_bits_normal : forall E, (0 < E < 2047)%Z ->
  fin (of_bits (E * 2 ^ 52)) = true /\ B2R (of_bits (E * 2 ^ 52)) = bpow radix2 (E - 1023).
Proof.
  intros E HE. unfold of_bits, Bits.b64_of_bits, Bits.binary_float_of_bits.
  assert (J : (E * 2 ^ 52)%Z = Bits.join_bits 52 11 false 0 E).
  { unfold Bits.join_bits. rewrite Z.shiftl_mul_pow2 by lia. lia. }
  rewrite J.
  split.
  - unfold fin. rewrite Binary.is_finite_B2BSN. rewrite Binary.is_finite_FF2B.
    unfold Bits.binary_float_of_bits_aux. rewrite Bits.split_join_bits by (cbn; lia).
    rewrite Zeq_bool_false by lia. rewrite Zeq_bool_false by (cbn; lia). reflexivity.
  - rewrite Binary.B2R_B2BSN. rewrite Binary.B2R_FF2B.
    unfold Bits.binary_float_of_bits_aux. rewrite Bits.split_join_bits by (cbn; lia).
    rewrite Zeq_bool_false by lia. rewrite Zeq_bool_false by (cbn; lia).
    cbn [Z.add]. simpl Binary.FF2R. unfold F2R. simpl Fnum. simpl Fexp.
    change (IZR 4503599627370496) with (bpow radix2 52). rewrite <- bpow_plus. f_equal.
    replace (SpecFloat.emin 53 (Z.pow_pos 2 10)) with (-1074)%Z by reflexivity. lia.
Qed.

Lemma to_bits_normal : forall m e (H : SpecFloat.bounded 53 1024 m e = true), (2 ^ 52 <= Zpos m)%Z ->
  to_bits (B754_finite false m e H) = ((e + 1075) * 2 ^ 52 + (Zpos m - 2 ^ 52))%Z.
Proof.
  intros m e H M. unfold to_bits, Bits.bits_of_b64, Bits.bits_of_binary_float. cbn [Binary.BSN2B].
  rewrite Zle_bool_true by lia. unfold Bits.join_bits. rewrite Z.shiftl_mul_pow2 by lia.
  replace (SpecFloat.emin (52 + 1) (2 ^ (11 - 1))) with (-1074)%Z by reflexivity. lia.
Qed.

Lemma word_small : forall z, (0 <= z < 2 ^ 64)%Z -> word z = z.
Proof.
  intros z Z. unfold word. replace (2 ^ 64 - 1)%Z with (Z.ones 64) by reflexivity.
  rewrite Z.land_ones by lia. apply Z.mod_small. exact Z.
Qed.

(** For a double q with |q| ≥ 2^-968, [half_gap_b] (the bit manipulation of
    half_gap_to_nearer_neighbour) is finite and is the model's [half_gap]. *)
Theorem half_gap_twin : forall q, fin q = true -> half_gap_min_magnitude <= Rabs (B2R q) ->
  fin (half_gap_b q) = true /\ B2R (half_gap_b q) = half_gap (B2R q).
Proof.
  intros [s|s| |s m e H] F G; try discriminate.
  { exfalso. simpl in G. rewrite Rabs_R0 in G. unfold half_gap_min_magnitude in G.
    pose proof (bpow_gt_0 radix2 (-968)). lra. }
  assert (G' : bpow radix2 (-1021) <= Rabs (B2R (B754_finite s m e H))).
  { eapply Rle_trans; [|exact G]. apply bpow_le. lia. }
  destruct (normal_mantissa s m e H G') as [M E].
  pose proof (bounded_le_emax_minus_prec 53 1024 _ m e H) as Up.
  (* the real value and its exponent *)
  assert (V : Rabs (B2R (B754_finite s m e H)) = IZR (Zpos m) * bpow radix2 e).
  { cbn [BinarySingleNaN.B2R]. rewrite <- F2R_Zabs, abs_cond_Zopp. reflexivity. }
  assert (Mag : (mag radix2 (B2R (B754_finite s m e H)) : Z) = (53 + e)%Z).
  { cbn [BinarySingleNaN.B2R]. rewrite mag_F2R_Zdigits by (destruct s; discriminate).
    assert (D : Zdigits radix2 (cond_Zopp s (Zpos m)) = 53%Z).
    { destruct s; cbn [cond_Zopp]; [rewrite Zdigits_opp|];
      apply Zdigits_unique; simpl Z.abs; change (radix2 ^ (53 - 1))%Z with (2 ^ 52)%Z;
      change (radix2 ^ 53)%Z with (2 ^ 53)%Z; lia. }
    simpl Fnum. simpl Fexp. rewrite D. reflexivity. }
  assert (Ee : (-1020 <= e)%Z).
  { assert (L : (-967 <= mag radix2 (B2R (B754_finite s m e H)))%Z).
    { apply mag_ge_bpow. eapply Rle_trans; [|exact G]. unfold half_gap_min_magnitude. apply bpow_le. lia. }
    lia. }
  assert (Eu : (e <= 971)%Z).
  { unfold F2R in Up. cbn [Fnum Fexp] in Up. pose proof (bpow_gt_0 radix2 (1024 - 53)).
    assert (Pm : bpow radix2 52 <= IZR (Zpos m)).
    { rewrite <- IZR_Zpower by lia. apply IZR_le. exact (proj1 M). }
    assert (bpow radix2 52 * bpow radix2 e <= IZR (Zpos m) * bpow radix2 e)
      by (apply Rmult_le_compat_r; [apply bpow_ge_0 | exact Pm]).
    rewrite <- bpow_plus in H1.
    assert (L : bpow radix2 (52 + e) < bpow radix2 1024) by lra.
    apply lt_bpow in L. lia. }
  rewrite (half_gap_bits _ (binary64_B2R _) G), V, Mag.
  unfold half_gap_b. change (fabs (B754_finite s m e H)) with (B754_finite false m e H).
  rewrite (to_bits_normal m e H (proj1 M)).
  set (mm := (Zpos m - 2 ^ 52)%Z).
  assert (Hi : Z.shiftr ((e + 1075) * 2 ^ 52 + mm) 52 = (e + 1075)%Z).
  { rewrite Z.shiftr_div_pow2 by lia. rewrite Z.div_add_l by lia. rewrite Z.div_small by (unfold mm; lia). lia. }
  assert (Lo : Z.land ((e + 1075) * 2 ^ 52 + mm) (2 ^ 52 - 1) = mm).
  { replace (2 ^ 52 - 1)%Z with (Z.ones 52) by reflexivity. rewrite Z.land_ones by lia.
    rewrite Z.add_comm, Z_mod_plus_full. apply Z.mod_small. unfold mm. lia. }
  rewrite Hi, Lo.
  destruct (Z.eqb_spec mm 0) as [Z0|Z0].
  - assert (Em : Zpos m = (2 ^ 52)%Z) by (unfold mm in Z0; lia).
    rewrite (word_small (e + 1075 - (53 + 1))) by lia. rewrite Z.shiftl_mul_pow2 by lia.
    rewrite word_small by lia.
    destruct (of_bits_normal (e + 1075 - (53 + 1)) ltac:(lia)) as [Fh Vh].
    split; [exact Fh|]. rewrite Vh.
    rewrite Req_bool_true.
    + f_equal. lia.
    + rewrite Em. change (IZR (2 ^ 52)) with (bpow radix2 52). rewrite <- bpow_plus. f_equal. lia.
  - rewrite (word_small (e + 1075 - (53 + 0))) by lia. rewrite Z.shiftl_mul_pow2 by lia.
    rewrite word_small by lia.
    destruct (of_bits_normal (e + 1075 - (53 + 0)) ltac:(lia)) as [Fh Vh].
    split; [exact Fh|]. rewrite Vh.
    rewrite Req_bool_false.
    + f_equal. lia.
    + intros Eq. replace (53 + e - 1)%Z with (52 + e)%Z in Eq by lia. rewrite bpow_plus in Eq.
      apply Rmult_eq_reg_r in Eq; [|apply Rgt_not_eq, bpow_gt_0].
      rewrite <- IZR_Zpower in Eq by lia. apply eq_IZR in Eq. change (Zpower radix2 52) with (2 ^ 52)%Z in Eq. unfold mm in Z0. lia.
Qed.

(** The lemmas [cpp_NAME] : B2R Cpp.NAME = NAME, one per constant, are generated with the constants into
    ConstantsCpp.v (twins/emit_constants.cmake; FloatCore.v's [tie]). *)
Lemma one_f_val : B2R one_f = 1.
Proof. float_value one_f. simpl. lra. Qed.

Global Hint Rewrite cpp_quotient_min_magnitude cpp_divisor_min_magnitude cpp_divisor_max_magnitude
  cpp_quotient_relative cpp_quotient_enclosure_factor cpp_quotient_test_factor cpp_largest_finite
  cpp_half_gap_min_magnitude one_f_val : cpp_constants.

Lemma cpp_quotient_constants_finite :
  fin Cpp.quotient_min_magnitude = true /\ fin Cpp.divisor_min_magnitude = true /\
  fin Cpp.divisor_max_magnitude = true /\ fin Cpp.quotient_relative = true /\
  fin Cpp.quotient_enclosure_factor = true /\ fin Cpp.quotient_test_factor = true /\
  fin Cpp.largest_finite = true /\ fin one_f = true.
Proof. vm_compute. repeat split. Qed.

Ltac qfin := let H := fresh "Fq" in pose proof cpp_quotient_constants_finite as H;
  repeat match type of H with _ /\ _ => let H' := fresh "Fq" in destruct H as [H' H] end.

Theorem round_quotient_twin : forall num den : EnclosureB,
  nonneg (radiusb num) -> nonneg (radiusb den) ->
  snd (round_quotient_b num (prepare_divisor_b den)) = true ->
  fin (hib num) = true /\ fin (lob num) = true /\ fin (radiusb num) = true /\
  fin (hib den) = true /\ fin (lob den) = true /\ fin (radiusb den) = true /\
  fin (fst (round_quotient_b num (prepare_divisor_b den))) = true /\
  B2R (fst (round_quotient_b num (prepare_divisor_b den))) =
    qr_t (round_quotient (enc_R num) (prepare_divisor (enc_R den))) /\
  qr_certain (round_quotient (enc_R num) (prepare_divisor (enc_R den))) = true.
Proof.
  intros [nh nl nr] [dh dl dr] Nn Nd C. cbn [hib lob radiusb] in *.
  unfold round_quotient_b, prepare_divisor_b in C |- *. cbn [dhib dlob dradiusb dreciprocalb din_rangeb hib lob radiusb fst snd] in C |- *.
  cbv zeta in C |- *.
  set (ir := (fle Cpp.divisor_min_magnitude (fabs (fst (two_sum_b dh dl))) &&
              fle (fabs (fst (two_sum_b dh dl))) Cpp.divisor_max_magnitude)%bool) in *.
  apply andb_prop in C. destruct C as [C C5].
  apply andb_prop in C. destruct C as [C C34]. apply andb_prop in C34. destruct C34 as [C3 C4].
  apply andb_prop in C. destruct C as [C1 Ir].
  rewrite Ir in C5, C3, C4 |- *.
  set (R := fdiv one_f (fst (two_sum_b dh dl))) in *.
  (* the left side of the test is non-negative or NaN, so it is finite *)
  match type of C5 with flt ?L ?Rh = true =>
    assert (FL : fin L = true);
    [ apply (certifying_bound_finite L Rh); [|left; exact C5];
      repeat first [ apply fmul_nonneg | apply fadd_nonneg | apply fabs_nonneg | assumption | const_nonneg ]
    | ] end.
  qfin. cpp_fin. fin_down2.
  assert (FR : fin R = true) by assumption.
  assert (Fqq : fin (fadd (fmul (fst (two_sum_b nh nl)) R)
              (fmul (fadd (ffma (fneg (fmul (fst (two_sum_b nh nl)) R)) (fst (two_sum_b dh dl)) (fst (two_sum_b nh nl)))
                 (ffma (fneg (fmul (fst (two_sum_b nh nl)) R)) (snd (two_sum_b dh dl)) (snd (two_sum_b nh nl)))) R)) = true)
    by (rewrite <- fle_largest_finite; exact C4).
  unfold round_quotient, prepare_divisor, enc_R. cbn [hi lo radius div_hi div_lo div_radius div_reciprocal div_in_range qr_t qr_certain].
  cbv zeta. cbn [hib lob radiusb].
  set (q := fadd (fmul (fst (two_sum_b nh nl)) R)
              (fmul (fadd (ffma (fneg (fmul (fst (two_sum_b nh nl)) R)) (fst (two_sum_b dh dl)) (fst (two_sum_b nh nl)))
                 (ffma (fneg (fmul (fst (two_sum_b nh nl)) R)) (snd (two_sum_b dh dl)) (snd (two_sum_b nh nl)))) R)) in *.
  assert (IrM : (Rle_bool divisor_min_magnitude (Rabs (fst (two_sum (B2R dh) (B2R dl)))) &&
                 Rle_bool (Rabs (fst (two_sum (B2R dh) (B2R dl)))) divisor_max_magnitude)%bool = true).
  { rewrite <- Ir. unfold ir. to_model2. reflexivity. }
  rewrite IrM.
  assert (Dpos : 0 < Rabs (fst (two_sum (B2R dh) (B2R dl)))).
  { apply andb_prop in IrM. destruct IrM as [G _].
    destruct (Rle_bool_spec divisor_min_magnitude (Rabs (fst (two_sum (B2R dh) (B2R dl))))) as [G'|_]; [|discriminate].
    eapply Rlt_le_trans; [apply bpow_gt_0 | exact G']. }
  assert (VR : B2R R = RN (1 / fst (two_sum (B2R dh) (B2R dl)))).
  { unfold R. rewrite fdiv_val by (try assumption; rewrite (proj2 (proj2 (two_sum_b_fst dh dl ltac:(assumption))));
      intros Z; rewrite Z, Rabs_R0 in Dpos; lra).
    rewrite one_f_val, (proj2 (proj2 (two_sum_b_fst dh dl ltac:(assumption)))). reflexivity. }
  assert (VQ : B2R q = RN
    (RN (fst (two_sum (B2R nh) (B2R nl)) * B2R R) +
     RN (RN (fma (- RN (fst (two_sum (B2R nh) (B2R nl)) * B2R R)) (fst (two_sum (B2R dh) (B2R dl)))
                 (fst (two_sum (B2R nh) (B2R nl))) +
             fma (- RN (fst (two_sum (B2R nh) (B2R nl)) * B2R R)) (snd (two_sum (B2R dh) (B2R dl)))
                 (snd (two_sum (B2R nh) (B2R nl)))) * B2R R))).
  { unfold q. unfold fma. to_model2. reflexivity. }
  rewrite <- VR, <- VQ.
  clearbody R q.
  revert C1 C3 C4. to_model2. intros C1 C3 C4.
  assert (FD : fin (fst (two_sum_b dh dl)) = true) by assumption.
  assert (VD := proj2 (proj2 (two_sum_b_fst dh dl FD))).
  repeat split; try assumption.
  rewrite C1, C3, C4. cbn [andb].
  assert (G : half_gap_min_magnitude <= Rabs (B2R q)).
  { destruct (Rle_bool_spec Q900 (Rabs (B2R q))) as [G|_]; [|discriminate].
    eapply Rle_trans; [|exact G]. apply bpow_le. lia. }
  destruct (half_gap_twin q ltac:(assumption) G) as [Fh Vh].
  match type of C5 with flt ?L ?Rh = true =>
    set (LL := L) in C5; assert (VL : B2R LL = B2R L) by reflexivity;
    assert (FLL : fin LL = true) by exact FL end.
  revert VL. to_model2. intros VL. unfold fma, Rminus. rewrite <- VL.
  clearbody LL. clear VL VQ VR FL.
  destruct (fin (fmul (half_gap_b q) (fabs (fst (two_sum_b dh dl))))) eqn:FRR.
  - rewrite (flt_val _ _ FLL FRR) in C5. rewrite (fmul_val _ _ FRR), fabs_val, Vh, VD in C5. exact C5.
  - apply Rlt_bool_true.
    pose proof (Bmult_correct 53 1024 _ _ mode_NE (half_gap_b q) (fabs (fst (two_sum_b dh dl)))) as M.
    destruct Rlt_bool eqn:O in M.
    + destruct M as [_ [M _]]. rewrite <- fabs_fin in FD. unfold fmul, fin in FRR, Fh, FD.
      rewrite M, Fh, FD in FRR. discriminate.
    + destruct (Rlt_bool_spec (Rabs (round radix2 (SpecFloat.fexp 53 1024) (round_mode mode_NE)
          (B2R (half_gap_b q) * B2R (fabs (fst (two_sum_b dh dl)))))) (bpow radix2 1024)) as [_|O']; [discriminate|].
      clear O. rename O' into O. rewrite RN_flocq in O. rewrite Vh, fabs_val, VD in O.
      assert (P : 0 <= RN (half_gap (B2R q) * Rabs (fst (two_sum (B2R dh) (B2R dl))))).
      { rewrite <- RN_0. apply RN_le. apply Rmult_le_pos; [apply half_gap_bounds | apply Rabs_pos]. }
      rewrite Rabs_pos_eq in O by exact P.
      pose proof (B2R_lt_overflow LL) as B. apply Rabs_lt_inv in B. clear - O B P. lra.
Qed.

(** End to end: when the twin certifies, for any reals num, den that the enclosures enclose (as soon as
    their parts are finite, which is how the stage-2 twins state it), den ≠ 0 and t = RN(num/den). *)
Corollary round_quotient_twin_sound : forall (num den : EnclosureB) (vn vd : R),
  nonneg (radiusb num) -> nonneg (radiusb den) ->
  (fin (hib num) = true -> fin (lob num) = true -> fin (radiusb num) = true -> encloses (enc_R num) vn) ->
  (fin (hib den) = true -> fin (lob den) = true -> fin (radiusb den) = true -> encloses (enc_R den) vd) ->
  snd (round_quotient_b num (prepare_divisor_b den)) = true ->
  vd <> 0 /\ fin (fst (round_quotient_b num (prepare_divisor_b den))) = true /\
  B2R (fst (round_quotient_b num (prepare_divisor_b den))) = RN (vn / vd).
Proof.
  intros num den vn vd Nn Nd En Ed C.
  destruct (round_quotient_twin num den Nn Nd C) as [F1 [F2 [F3 [F4 [F5 [F6 [Ft [Vt Ct]]]]]]]].
  destruct (round_quotient_sound (enc_R num) (enc_R den) vn vd) as [Nz T];
    try apply binary64_B2R; auto.
  split; [exact Nz | split; [exact Ft | rewrite Vt; exact T]].
Qed.

(** ** The twins tied to the models: plane/ray_plane_stages.hpp *)

Definition vec_R (v : Vec3B) : vec3 := Vec3 (B2R (vxb v)) (B2R (vyb v)) (B2R (vzb v)).
Definition vec_fin (v : Vec3B) : Prop := fin (vxb v) = true /\ fin (vyb v) = true /\ fin (vzb v) = true.

(** One side of [fast_relation_from_b]: |s| > B with B = C ⊗ m ⊕ 3μ (non-negative or NaN, so finite
    when the test passes) means a finite stage 1, equal to the model's, whose enclosure gives V ≠ 0 and
    the sign of V. *)
Lemma relation_side_twin : forall a0 a1 a2 b0 b1 b2 C V,
  fin C = true -> nonneg C ->
  let r := dot3_rounded_b a0 a1 a2 b0 b1 b2 in
  (fin a0 = true -> fin a1 = true -> fin a2 = true ->
   let m := dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2) in
   Rabs (value m - V) <= filter_bound m (B2R C)) ->
  flt (fadd (fmul C (magnitudeb r)) Cpp.filter_absolute) (fabs (valueb r)) = true ->
  fin a0 = true /\ fin a1 = true /\ fin a2 = true /\ fin b0 = true /\ fin b1 = true /\ fin b2 = true /\
  V <> 0 /\ flt (valueb r) fzero = Rlt_bool V 0.
Proof.
  intros a0 a1 a2 b0 b1 b2 C V FC NC r Enc T.
  assert (NB : nonneg (fadd (fmul C (magnitudeb r)) Cpp.filter_absolute)).
  { apply fadd_nonneg; [apply fmul_nonneg; [exact NC|] | const_nonneg].
    subst r. unfold dot3_rounded_b. cbn [magnitudeb].
    apply fadd_nonneg; [apply fadd_nonneg|]; apply fabs_nonneg. }
  assert (FB := certifying_bound_finite _ _ NB (or_introl T)).
  assert (Fm : fin (magnitudeb r) = true).
  { destruct (fadd_fin _ _ FB) as [F _]. now destruct (fmul_fin _ _ F). }
  destruct (dot3_rounded_twin a0 a1 a2 b0 b1 b2 Fm) as [F0 [F1 [F2 [G0 [G1 [G2 [_ [_ [_ [Fv E]]]]]]]]]].
  fold r in Fv, E. specialize (Enc F0 F1 F2). cbv zeta in Enc. rewrite <- E in Enc.
  assert (VB : B2R (fadd (fmul C (magnitudeb r)) Cpp.filter_absolute) = filter_bound (dot3_R r) (B2R C)).
  { unfold filter_bound. cbn [dot3_R magnitude]. cpp_fin. to_model. reflexivity. }
  assert (Ff : fin (fabs (valueb r)) = true) by (now rewrite fabs_fin).
  rewrite (flt_val _ _ FB Ff), VB, fabs_val in T.
  destruct (Rlt_bool_spec (filter_bound (dot3_R r) (B2R C)) (Rabs (B2R (valueb r)))) as [T'|_]; [|discriminate].
  destruct (abs_above_bound _ _ _ Enc T') as [Nz S].
  repeat split; try assumption.
  rewrite (flt_val (valueb r) fzero Fv (eq_refl true)). exact S.
Qed.

(** [fast_relation] (what [relation] and the relation batch run), end to end for every bit pattern of
    o, d, p, n: when it says certain, every input is finite, [behind ? behind : hit] is the relation of
    docs/contract.md §1 for the exact values, num ≠ 0, den ≠ 0, d ≠ 0 and n ≠ 0 (the twin of PlaneCascade.v's
    [fast_relation_correct]; no validation before it is needed). *)
Theorem fast_relation_twin_correct : forall o d p n : Vec3B,
  snd (fast_relation_b o d p n) = true ->
  vec_fin o /\ vec_fin d /\ vec_fin p /\ vec_fin n /\
  (if fst (fast_relation_b o d p n) then Behind else Hit) = classify (vec_R o) (vec_R d) (vec_R p) (vec_R n) /\
  ray_num (vec_R o) (vec_R p) (vec_R n) <> 0 /\ ray_den (vec_R d) (vec_R n) <> 0 /\
  vec_R d <> zero3 /\ vec_R n <> zero3.
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [nx ny nz].
  unfold fast_relation_b, fast_relation_from_b. cbn [fst snd vxb vyb vzb]. intros C.
  apply andb_prop in C. destruct C as [Cd Cn].
  destruct cpp_filter_constants as [Fd [Nd [Fn Nn]]].
  destruct (relation_side_twin dx dy dz nx ny nz Cpp.filter_den_relative
              (ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz))) Fd Nd) as
    [Fdx [Fdy [Fdz [Fnx [Fny [Fnz [Zd Sd]]]]]]].
  { intros _ _ _. cbv zeta. rewrite cpp_filter_den_relative. apply den_filter_encloses. }
  { exact Cd. }
  destruct (relation_side_twin (fsub px ox) (fsub py oy) (fsub pz oz) nx ny nz Cpp.filter_num_relative
              (ray_num (vec_R (V3 ox oy oz)) (vec_R (V3 px py pz)) (vec_R (V3 nx ny nz))) Fn Nn) as
    [F0 [F1 [F2 [_ [_ [_ [Zn Sn]]]]]]].
  { intros F0 F1 F2. cbv zeta. rewrite cpp_filter_num_relative.
    destruct (fsub_inv _ _ F0) as [_ [_ V0]]. destruct (fsub_inv _ _ F1) as [_ [_ V1]].
    destruct (fsub_inv _ _ F2) as [_ [_ V2]]. rewrite V0, V1, V2.
    apply num_filter_encloses; apply binary64_B2R. }
  { exact Cn. }
  destruct (fsub_fin _ _ F0) as [Fpx Fox]. destruct (fsub_fin _ _ F1) as [Fpy Foy].
  destruct (fsub_fin _ _ F2) as [Fpz Foz].
  destruct (den_nonzero_valid _ _ Zd) as [Vd Vn].
  unfold vec_fin. cbn [vxb vyb vzb].
  repeat split; try assumption.
  rewrite Sd, Sn, (relation_of_nonzero _ _ _ _ Zn Zd).
  destruct (Rlt_bool _ 0), (Rlt_bool _ 0); reflexivity.
Qed.

(** [fast_answer_b] as [fast_answer_from_b] of the stage-1 signs and the stage-2 enclosures of PlaneTwins.v
    ([den_compensated_b], [num_compensated_b]; p_i ⊖ o_i is two_diff(p_i, o_i).hi), and the three outputs
    [fast_answer_from_b] computes. *)
Lemma fast_answer_b_eq : forall ox oy oz dx dy dz px py pz nx ny nz,
  fast_answer_b (V3 ox oy oz) (V3 dx dy dz) (V3 px py pz) (V3 nx ny nz) =
  fast_answer_from_b (dot3_filter_lanes_b (dot3_rounded_b dx dy dz nx ny nz) Cpp.filter_den_relative)
    (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b px ox)) (fst (two_diff_b py oy)) (fst (two_diff_b pz oz))
       nx ny nz) Cpp.filter_num_relative)
    (den_compensated_b dx dy dz nx ny nz) (num_compensated_b px py pz ox oy oz nx ny nz).
Proof. intros. unfold fast_answer_b. cbn [vxb vyb vzb]. rewrite !fsub_two_diff_hi. reflexivity. Qed.

Lemma fast_answer_from_b_parts : forall df nf den num,
  let a := fast_answer_from_b df nf den num in
  fst (fst (fst a)) = fst (round_quotient_b num (prepare_divisor_b den)) /\
  snd (fst (fst a)) = Z.ltb (first_certain_lanes_b nf (enclosure_sign_lanes_b num) *
                             first_certain_lanes_b df (enclosure_sign_lanes_b den))%Z 0 /\
  snd (fst a) = (certain_lane (first_certain_lanes_b df (enclosure_sign_lanes_b den)) &&
                 certain_lane (first_certain_lanes_b nf (enclosure_sign_lanes_b num)) &&
                 snd (round_quotient_b num (prepare_divisor_b den)))%bool.
Proof. intros. repeat split. Qed.

Lemma first_certain_lanes_b_eq : forall x y, first_certain_lanes_b x y = first_certain_lanes x y.
Proof. reflexivity. Qed.

Lemma certain_lane_true : forall s, certain_lane s = true -> s <> uncertain_lane.
Proof. intros s H. unfold certain_lane in H. apply negb_true_iff, Z.eqb_neq in H. exact H. Qed.

(** What a certain fast answer (t, behind) of the query o, d, p, n means: every input is finite,
    [behind ? behind : hit] is the relation of docs/contract.md §1 for the exact values, num ≠ 0, den ≠ 0,
    d ≠ 0, n ≠ 0, and t is finite and RN(num/den).  The conclusion of every fast-answer theorem below
    and of PlaneQueryPairTwins.v. *)
Definition fast_answer_means (o d p n : Vec3B) (t : float) (behind : bool) : Prop :=
  vec_fin o /\ vec_fin d /\ vec_fin p /\ vec_fin n /\
  (if behind then Behind else Hit) = classify (vec_R o) (vec_R d) (vec_R p) (vec_R n) /\
  ray_num (vec_R o) (vec_R p) (vec_R n) <> 0 /\ ray_den (vec_R d) (vec_R n) <> 0 /\
  vec_R d <> zero3 /\ vec_R n <> zero3 /\
  fin t = true /\
  B2R t = RN (ray_num (vec_R o) (vec_R p) (vec_R n) / ray_den (vec_R d) (vec_R n)).

(** [fast_answer_from_b] with the stage-1 signs and num's stage-2 enclosure of a query and any enclosure
    [den2] of den that is non-negative-or-NaN in its radius, encloses den (with d, n finite) once its parts
    are finite, and whose certain sign is den's: the argument of [fast_answer_twin_correct] below, shared by
    the Lanes2 form (PlaneQueryPairTwins.v, where den2 is computed like num with o = 0). *)
Lemma fast_answer_from_twin_correct : forall ox oy oz dx dy dz px py pz nx ny nz (den2 : EnclosureB),
  let VD := ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz)) in
  nonneg (radiusb den2) ->
  (fin (hib den2) = true -> fin (lob den2) = true -> fin (radiusb den2) = true ->
   encloses (enc_R den2) VD /\ vec_fin (V3 dx dy dz) /\ vec_fin (V3 nx ny nz)) ->
  (fin (hib den2) = true -> fin (lob den2) = true -> certifies (sign_from_Z (enclosure_sign_lanes_b den2)) VD) ->
  let o := V3 ox oy oz in let d := V3 dx dy dz in let p := V3 px py pz in let n := V3 nx ny nz in
  let a := fast_answer_from_b (dot3_filter_lanes_b (dot3_rounded_b dx dy dz nx ny nz) Cpp.filter_den_relative)
    (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b px ox)) (fst (two_diff_b py oy)) (fst (two_diff_b pz oz))
       nx ny nz) Cpp.filter_num_relative)
    den2 (num_compensated_b px py pz ox oy oz nx ny nz) in
  snd (fst a) = true -> fast_answer_means o d p n (fst (fst (fst a))) (snd (fst (fst a))).
Proof.
  intros ox oy oz dx dy dz px py pz nx ny nz den2 VD Nden HE HS o d p n a. subst o d p n a.
  destruct (fast_answer_from_b_parts (dot3_filter_lanes_b (dot3_rounded_b dx dy dz nx ny nz) Cpp.filter_den_relative)
    (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b px ox)) (fst (two_diff_b py oy)) (fst (two_diff_b pz oz))
       nx ny nz) Cpp.filter_num_relative)
    den2 (num_compensated_b px py pz ox oy oz nx ny nz)) as [P1 [P2 P3]].
  rewrite P1, P2, P3. clear P1 P2 P3.
  set (num2 := num_compensated_b px py pz ox oy oz nx ny nz).
  set (VN := ray_num (vec_R (V3 ox oy oz)) (vec_R (V3 px py pz)) (vec_R (V3 nx ny nz))).
  intros C. apply andb_prop in C. destruct C as [C Ct]. apply andb_prop in C. destruct C as [Cd Cn].
  (* the quotient *)
  assert (Nnum : nonneg (radiusb num2)) by apply compensated_radius_nonneg.
  destruct (round_quotient_twin num2 den2 Nnum Nden Ct) as [Fnh [Fnl [Fnr [Fdh [Fdl [Fdr _]]]]]].
  destruct (HE Fdh Fdl Fdr) as [Ed [Fd Fn]].
  assert (En : encloses (enc_R num2) VN /\ vec_fin (V3 px py pz) /\ vec_fin (V3 ox oy oz)).
  { destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fnr Fnh Fnl) as [? [? [? [A0 [A1 [A2 [? [? [? [_ [_ E]]]]]]]]]]].
    destruct (two_diff_b_parts _ _ A0) as [? [? [X0 Y0]]]. destruct (two_diff_b_parts _ _ A1) as [? [? [X1 Y1]]].
    destruct (two_diff_b_parts _ _ A2) as [? [? [X2 Y2]]].
    unfold vec_fin. cbn [vxb vyb vzb]. repeat split; try assumption.
    unfold num2, num_compensated_b. cbv zeta. rewrite E, X0, X1, X2, Y0, Y1, Y2.
    apply compensated_num_enclosure; apply binary64_B2R. }
  destruct En as [En [Fp Fo]].
  destruct (round_quotient_twin_sound num2 den2 VN VD Nnum Nden (fun _ _ _ => En) (fun _ _ _ => Ed) Ct)
    as [Zd [Ft Vt]].
  (* the signs *)
  destruct (den_filter_twin_sound dx dy dz nx ny nz) as [Sdf _].
  destruct (num_filter_twin_sound px py pz ox oy oz nx ny nz) as [Snf _].
  pose proof (HS Fdh Fdl) as Sdc.
  destruct (num_compensated_twin_sound px py pz ox oy oz nx ny nz Fnh Fnl) as [Snc _].
  fold num2 in Snc.
  set (sdf := dot3_filter_lanes_b (dot3_rounded_b dx dy dz nx ny nz) Cpp.filter_den_relative) in *.
  set (snf := dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b px ox)) (fst (two_diff_b py oy))
                (fst (two_diff_b pz oz)) nx ny nz) Cpp.filter_num_relative) in *.
  set (sdc := enclosure_sign_lanes_b den2) in *. set (snc := enclosure_sign_lanes_b num2) in *.
  assert (L1 : lane_sign sdf) by (unfold sdf, dot3_filter_lanes_b; apply sign_lanes_range).
  assert (L2 : lane_sign snf) by (unfold snf, dot3_filter_lanes_b; apply sign_lanes_range).
  assert (L3 : lane_sign sdc) by (unfold sdc, enclosure_sign_lanes_b; apply sign_lanes_range).
  assert (L4 : lane_sign snc) by (unfold snc, enclosure_sign_lanes_b; apply sign_lanes_range).
  clearbody sdf snf sdc snc.
  change VD with (ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz))) in Sdc.
  assert (Sdf' : certifies (sign_from_Z sdf) VD) by exact Sdf.
  assert (Snf' : certifies (sign_from_Z snf) VN) by exact Snf.
  clear Sdf Snf.
  destruct (first_certain_lanes_sound _ _ VD L1 L3 Sdf' Sdc) as [Ld Cd'].
  destruct (first_certain_lanes_sound _ _ VN L2 L4 Snf' Snc) as [Ln Cn'].
  rewrite !first_certain_lanes_b_eq in Cd, Cn |- *.
  destruct (lanes_relation _ _ (vec_R (V3 ox oy oz)) (vec_R (V3 dx dy dz)) (vec_R (V3 px py pz)) (vec_R (V3 nx ny nz))
              Ln Ld (certain_lane_true _ Cn) (certain_lane_true _ Cd) Cn' Cd') as [Rel [Zn Zd']].
  destruct (den_nonzero_valid _ _ Zd') as [Vd Vn].
  exact (conj Fo (conj Fd (conj Fp (conj Fn (conj Rel (conj Zn (conj Zd' (conj Vd (conj Vn (conj Ft Vt)))))))))).
Qed.

(** The opening of [fast_answer_twin_correct] and of PlaneQueryPairTwins.v's [fast_answer_pair_twin_correct]:
    the query's form as a [fast_answer_from_b] (its equation [eq_lemma]), then [fast_answer_from_twin_correct],
    given the three facts it asks of den's first level: [nonneg] (its radius), [encl] (a finite enclosure
    holds den, d and n finite), [sound] (its certified sign). *)
Ltac fast_answer_from_intro eq_lemma nonneg encl sound :=
  intros [ox oy oz] [dx dy dz] [px py pz] [nx ny nz] a; subst a;
  rewrite eq_lemma; apply fast_answer_from_twin_correct; [apply nonneg | apply encl | apply sound].

(** den's first level, what [fast_answer_from_twin_correct] asks of it on the batch lanes' path. *)
Lemma den_compensated_encloses_fin : forall dx dy dz nx ny nz,
  let e := den_compensated_b dx dy dz nx ny nz in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  encloses (enc_R e) (ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz))) /\ vec_fin (V3 dx dy dz) /\
  vec_fin (V3 nx ny nz).
Proof.
  intros dx dy dz nx ny nz e Fdh Fdl Fdr.
  destruct (compensated_dot3_exact_twin _ _ _ _ _ _ Fdr Fdh Fdl) as [X0 [X1 [X2 [X3 [X4 [X5 _]]]]]].
  split; [exact (den_compensated_encloses_b dx dy dz nx ny nz Fdh Fdl Fdr) |].
  exact (conj (conj X0 (conj X1 X2)) (conj X3 (conj X4 X5))).
Qed.

Lemma den_compensated_certifies : forall dx dy dz nx ny nz,
  let e := den_compensated_b dx dy dz nx ny nz in fin (hib e) = true -> fin (lob e) = true ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) (ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz))).
Proof. intros dx dy dz nx ny nz e Fdh Fdl. exact (proj1 (den_compensated_twin_sound dx dy dz nx ny nz Fdh Fdl)). Qed.

(** [fast_answer] (the batch lanes' form: what [intersect] and the intersection batch run), end to end for
    every bit pattern of o, d, p, n: when it says certain, every input is finite, [behind ? behind : hit]
    is the relation of docs/contract.md §1 for the exact values, num ≠ 0, den ≠ 0, d ≠ 0, n ≠ 0, and t is
    finite and RN(num/den) (the twin of PlaneCascade.v's [fast_answer_correct]).  The stage-2 enclosures are
    finite because round_quotient certified them ([round_quotient_twin]), which discharges the
    "hi and lo finite" hypothesis of the stage-2 twin theorems on this path. *)
Theorem fast_answer_twin_correct : forall o d p n : Vec3B,
  let a := fast_answer_b o d p n in
  snd (fst a) = true -> fast_answer_means o d p n (fst (fst (fst a))) (snd (fst (fst a))).
Proof.
  fast_answer_from_intro fast_answer_b_eq den_radius_nonneg den_compensated_encloses_fin den_compensated_certifies.
Qed.
