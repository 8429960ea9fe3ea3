(** * Twins of one ray–plane query (certified/ray_plane_query.hpp, certified/quotient_rounding.hpp)

    The routines of Twins.v and Expansions.v as the query calls them, and the lean rounding, so that the
    differential runner also checks the call sites (a den constant passed for num, a wrong low part, the
    α = 0 form for num) and the quotient:
    - [prepare_divisor_b], [half_gap_b], [round_quotient_b]: prepare_divisor, half_gap_to_nearer_neighbour
      (on the bits, through Flocq's Bits), round_quotient;
    - [fast_answer_b]: fast_answer(RayPlaneTermsT<V>) (the form the batch lanes run), and
      [fast_answer_pair_b]: fast_answer(o, d, p, n), den and num as the two lanes of a Lanes2 (den's
      a_i = d_i ⊖ 0 with its TwoDiff error, through compensated_dot3, not the α = 0 form);
    - [fast_relation_b], [fast_relation_pair_b]: fast_relation (|s| > B), both forms;
    - [ray_plane_expansions_b]: ray_plane_expansions (stage 3), the C++ as it is.

    These Definitions are checked against the C++ by the runner; their tie to the real-number models
    (Cascade.v's [fast_answer_correct], [fast_relation_correct]; QuotientRounding.v's [round_quotient_sound])
    is not yet a theorem about them (proofs/README.md, "What remains"): the stage-1 and stage-2 pieces they
    call are tied (Twins.v), the composition and the quotient are not. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model Filter Compensated Classification Cascade FloatCore ConstantsCpp
  Twins Expansions.
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

(** ** ray_plane_query.hpp *)

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
