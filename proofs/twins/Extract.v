(** * Extraction of the twins to OCaml, for the differential runner (proofs/twins/README in
    proofs/README.md, "The twins and the differential runner").

    Every entry point takes the inputs of one call as 64-bit patterns (the runner reads them as decimal
    integers) and returns the outputs: doubles as bit patterns (every NaN as 0x7ff8000000000000, the
    runner compares NaNs as a class), signs and flags as small integers.  The functions called are the
    twins the theorems are about; the only code between them and the numbers the C++ prints is
    [of_bits]/[to_bits] (Flocq's Bits) and the OCaml main (twins/runner.ml), which parses and prints.

    Integers are extracted to zarith (ExtrOcamlZBigInt, exact); Fast.v replaces four of Coq's and
    Flocq's bit-by-bit loops by the equivalent zarith primitives (shifts, bit length, power), which
    makes the extracted arithmetic about 60 times faster.  The runner checks those replacements too: a
    wrong one would show as a mismatch against the compiled C++. *)

From Coq Require Import ZArith List.
From Raykernel Require Import Model PlaneClassification CompareQuotients FloatCore ConstantsCpp PlaneTwins CompareTwins
  Expansions PlaneQueryTwins.
From Raykernel Require TriangleTwins TriangleStage3Twins TriangleCascadeTwins TriangleRule.
From Raykernel Require TriangleIntersectTwins.
From Raykernel Require NearestTwins.
From Raykernel Require PlaneCascadeTwins.
From Raykernel Require TriangleCascadeFlowTwins.
From Raykernel Require TriangleIntersectPublic.
From Raykernel Require OrientTwins.
From Raykernel Require QuotientBoundary.
From Raykernel Require SphereStages.
From Raykernel Require SpawnTwins.
From Raykernel Require Escalation.
From Raykernel Require RayBoxTwins.
Require Import ExtrOcamlBasic ExtrOcamlZBigInt.
From Raykernel Require Import Fast.
Import ListNotations.
Open Scope Z_scope.

Definition b := to_bits.
Definition f := of_bits.

Definition enc_bits (e : EnclosureB) : list Z := [b (hib e); b (lob e); b (radiusb e)].
Definition dot3_bits (r : Dot3B) : list Z := [b (qb0 r); b (qb1 r); b (qb2 r); b (valueb r); b (magnitudeb r)].

(** eft.hpp *)
Definition run_two_sum (x : list Z) : list Z :=
  match x with [a; c] => let r := two_sum_b (f a) (f c) in [b (fst r); b (snd r)] | _ => [] end.
Definition run_two_diff (x : list Z) : list Z :=
  match x with [a; c] => let r := two_diff_b (f a) (f c) in [b (fst r); b (snd r)] | _ => [] end.
Definition run_two_prod (x : list Z) : list Z :=
  match x with [a; c] => let r := two_prod_b (f a) (f c) in [b (fst r); b (snd r)] | _ => [] end.

(** dot3_filter.hpp: the rounded dot product and the filter with each constant. *)
Definition run_dot3_rounded (x : list Z) : list Z :=
  match x with [a0; a1; a2; b0; b1; b2] => dot3_bits (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2))
  | _ => [] end.
Definition run_filter (C : float) (x : list Z) : list Z :=
  match x with [a0; a1; a2; b0; b1; b2] =>
    [dot3_filter_lanes_b (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2)) C] | _ => [] end.
Definition run_filter_den := run_filter Cpp.filter_den_relative.
Definition run_filter_num := run_filter Cpp.filter_num_relative.

(** dot3_compensated.hpp: stage 1 computed from a and b, as every caller does. *)
Definition run_compensated (x : list Z) : list Z :=
  match x with [a0; a1; a2; l0; l1; l2; b0; b1; b2] =>
    enc_bits (compensated_dot3_b (f a0) (f a1) (f a2) (f l0) (f l1) (f l2) (f b0) (f b1) (f b2)
                (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2))) | _ => [] end.
Definition run_compensated_exact (x : list Z) : list Z :=
  match x with [a0; a1; a2; b0; b1; b2] =>
    enc_bits (compensated_dot3_exact_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2)
                (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2))) | _ => [] end.
Definition run_refined (x : list Z) : list Z :=
  match x with [a0; a1; a2; l0; l1; l2; b0; b1; b2] =>
    enc_bits (compensated_dot3_refined_b (f a0) (f a1) (f a2) (f l0) (f l1) (f l2) (f b0) (f b1) (f b2)
                (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2))) | _ => [] end.

(** enclosure.hpp *)
Definition run_enclosure_sign (x : list Z) : list Z :=
  match x with [h; l; r] => [enclosure_sign_lanes_b {| hib := f h; lob := f l; radiusb := f r |}] | _ => [] end.

(** expansion.hpp: the components e_0 .. e_k. *)
Definition run_tail_enclosure (x : list Z) : list Z :=
  match x with e0 :: rest => enc_bits (expansion_tail_enclosure_b (f e0) (map f rest)) | [] => [] end.

(** The values of [enum class Sign] (−1, 0, +1, 2 for uncertain) and [Stage] (0..3). *)
Definition sign_code (s : sign) : Z := match s with Negative => -1 | Zero => 0 | Positive => 1 | Uncertain => 2 end.
Definition bool_code (x : bool) : Z := if x then 1 else 0.
Definition list_bits (l : list float) : list Z := Z.of_nat (length l) :: map b l.

(** compare_quotients.hpp *)
Definition run_filter_enclosure (C : float) (x : list Z) : list Z :=
  match x with [a0; a1; a2; b0; b1; b2] =>
    let e := filter_enclosure_b (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2)) C in
    [b (rvalueb e); b (rradiusb e)] | _ => [] end.
Definition run_filter_enclosure_den := run_filter_enclosure Cpp.filter_den_relative.
Definition run_filter_enclosure_num := run_filter_enclosure Cpp.filter_num_relative.
Definition run_propagated (x : list Z) : list Z :=
  match x with [x1; e1; y1; f1; x2; e2; y2; f2] =>
    [b (compare_propagated_error_b (f x1) (f e1) (f y1) (f f1) (f x2) (f e2) (f y2) (f f2))] | _ => [] end.
Definition renc (v r : Z) : RoundedEnclosureB := {| rvalueb := f v; rradiusb := f r |}.
Definition run_compare_filter (x : list Z) : list Z :=
  match x with [x1; e1; y1; f1; x2; e2; y2; f2] =>
    [sign_code (compare_quotients_filter_b (renc x1 e1) (renc y1 f1) (renc x2 e2) (renc y2 f2))] | _ => [] end.
Definition enc (h l r : Z) : EnclosureB := {| hib := f h; lob := f l; radiusb := f r |}.
Definition run_compare_compensated (x : list Z) : list Z :=
  match x with [h1; l1; r1; h2; l2; r2; h3; l3; r3; h4; l4; r4] =>
    enc_bits (compare_quotients_compensated_b (enc h1 l1 r1) (enc h2 l2 r2) (enc h3 l3 r3) (enc h4 l4 r4))
  | _ => [] end.

(** expansion.hpp: "k e_1 .. e_k f_1 .." for two lists, "b e_1 .." for a scale. *)
Definition split_at (x : list Z) : list float * list float :=
  match x with k :: rest => (map f (firstn (Z.to_nat k) rest), map f (skipn (Z.to_nat k) rest)) | [] => ([], []) end.
Definition run_exp_sum_gen fts (x : list Z) : list Z :=
  let '(e, g) := split_at x in list_bits (sum_gen fts e g).
Definition run_exp_scale_gen fts (x : list Z) : list Z :=
  match x with bb :: e => let r := scale_gen fts true (map f e) (f bb) in bool_code (fst r) :: list_bits (snd r)
  | [] => [] end.
Definition run_exp_sum := run_exp_sum_gen two_sum_b.
Definition run_exp_scale := run_exp_scale_gen two_sum_b.
Definition run_exp_sign (x : list Z) : list Z := [sign_code (expansion_sign_b (map f x))].

(** quotient_rounding.hpp: "num.hi num.lo num.radius den.hi den.lo den.radius" → t, certain, and the
    prepared divisor's fields. *)
Definition run_round_quotient (x : list Z) : list Z :=
  match x with [h1; l1; r1; h2; l2; r2] =>
    let dv := prepare_divisor_b (enc h2 l2 r2) in
    let t := round_quotient_b (enc h1 l1 r1) dv in
    [b (fst t); bool_code (snd t); b (dhib dv); b (dlob dv); b (dreciprocalb dv); bool_code (din_rangeb dv)]
  | _ => [] end.
Definition run_half_gap (x : list Z) : list Z :=
  match x with [q] => [b (half_gap_b (f q))] | _ => [] end.

(** Queries "ox oy oz dx dy dz px py pz nx ny nz". *)
Definition v3 (x y z : Z) : Vec3B := V3 (f x) (f y) (f z).
Definition answer_code (a : float * bool * bool * bool) : list Z :=
  let '(t, behind, certain, by_filter) := a in [b t; bool_code behind; bool_code certain; bool_code by_filter].
Definition run_fast_answer (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; px; py; pz; nx; ny; nz] =>
    answer_code (fast_answer_b (v3 ox oy oz) (v3 dx dy dz) (v3 px py pz) (v3 nx ny nz)) | _ => [] end.
Definition run_fast_answer_pair (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; px; py; pz; nx; ny; nz] =>
    answer_code (fast_answer_pair_b (v3 ox oy oz) (v3 dx dy dz) (v3 px py pz) (v3 nx ny nz)) | _ => [] end.
Definition relation_code (r : bool * bool) : list Z := [bool_code (fst r); bool_code (snd r)].
Definition run_fast_relation (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; px; py; pz; nx; ny; nz] =>
    relation_code (fast_relation_b (v3 ox oy oz) (v3 dx dy dz) (v3 px py pz) (v3 nx ny nz)) | _ => [] end.
Definition run_fast_relation_pair (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; px; py; pz; nx; ny; nz] =>
    relation_code (fast_relation_pair_b (v3 ox oy oz) (v3 dx dy dz) (v3 px py pz) (v3 nx ny nz)) | _ => [] end.
Definition run_build_expansions_gen fts (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; px; py; pz; nx; ny; nz] =>
    let '(num, den, ex) := ray_plane_expansions_b fts (v3 ox oy oz) (v3 dx dy dz) (v3 px py pz) (v3 nx ny nz) in
    list_bits num ++ list_bits den ++ [bool_code ex] | _ => [] end.
Definition run_build_expansions := run_build_expansions_gen two_sum_b.
Definition run_compare_expansion_gen fts sgn (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; pax; pay; paz; nax; nay; naz; pbx; pby; pbz; nbx; nby; nbz] =>
    let o := v3 ox oy oz in let d := v3 dx dy dz in
    let '(na, da, xa) := ray_plane_expansions_b fts o d (v3 pax pay paz) (v3 nax nay naz) in
    let '(nb, db, xb) := ray_plane_expansions_b fts o d (v3 pbx pby pbz) (v3 nbx nby nbz) in
    [sign_code (compare_quotients_expansion_gen fts sgn na da xa nb db xb)] | _ => [] end.
Definition run_compare_expansion := run_compare_expansion_gen two_sum_b expansion_sign_b.

(** quotient_boundary.hpp's [round_quotient_at_boundaries] (QuotientBoundary.v): "s q k num_1 .. num_k den_1 .."
    (s = 0: den_sign = +1, else −1) → 1 and RN's bits, or 0 when it does not decide. *)
Definition run_quotient_boundary (x : list Z) : list Z :=
  match x with s :: q :: k :: rest =>
    let num := map f (firstn (Z.to_nat k) rest) in
    let den := map f (skipn (Z.to_nat k) rest) in
    let ds := if Z.eqb s 0 then 1 else (-1) in
    match QuotientBoundary.round_quotient_at_boundaries_b num den ds (f q) with
    | Some r => [1; b r] | None => [0] end
  | _ => [] end.

(** nearest_hit.cpp's [compare_hit_distances] (NearestTwins.v): a ray, two planes and the four signs the
    candidates carry (num_a, den_a, num_b, den_b, each as the double −1, 0, +1) → order, stage (order 0
    when the exact stage decides: it is not a twin). *)
Definition sign_of_word (z : Z) : sign :=
  if Z.eqb z 4607182418800017408 then Positive else if Z.eqb z 13830554455654793216 then Negative
  else if Z.eqb z 0 then Zero else Uncertain.
Definition run_nearest_compare (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; pax; pay; paz; nax; nay; naz; pbx; pby; pbz; nbx; nby; nbz; s1; s2; s3; s4] =>
    let r := NearestTwins.compare_hit_distances_b (v3 ox oy oz) (v3 dx dy dz) (v3 pax pay paz) (v3 nax nay naz)
               (v3 pbx pby pbz) (v3 nbx nby nbz) (sign_of_word s1) (sign_of_word s2) (sign_of_word s3) (sign_of_word s4) in
    [fst r; snd r] | _ => [] end.

(** Ray–triangle stages 1 and 2 (TriangleTwins.v): queries "ox oy oz dx dy dz ax ay az bx by bz cx cy cz". *)
Module Tri.
Import TriangleTwins.
Definition tv (x y z : Z) : TVec := TV (f x) (f y) (f z).
Definition fterm_bits (t : FTermB) : list Z := [b (fvb t); b (fmb t)].
Definition cterm_bits (t : CTermB) : list Z := [b (chb t); b (clb t); b (cmb t)].

(** [triangle_filter_values]: the five values (πa, πb, πc, den, num) with their magnitudes, absolute_d,
    absolute_e, and [det3_filter_lanes] of each with its constant (the full cascade's [det3_filter_sign]).
    den is [den_stage1_b], written with the π's computed once. *)
Definition tri_filter (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let o := tv ox oy oz in let d := tv dx dy dz in let a := tv ax ay az in let bb := tv bx by_ bz in
    let c := tv cx cy cz in
    let pa := pi_stage1_b o d bb c in let pb := pi_stage1_b o d c a in let pc := pi_stage1_b o d a bb in
    let den := term_add_b (term_add_b pa pb) pc in let num := num_stage1_b o a bb c in
    let ad := absolute_bv d in let ae := absolute_bv (tsub a o) in
    fterm_bits pa ++ fterm_bits pb ++ fterm_bits pc ++ fterm_bits den ++ fterm_bits num ++
    [b ad; b ae;
     det3_filter_lanes_b pa Cpp.triangle_filter_pi_relative ad; det3_filter_lanes_b pb Cpp.triangle_filter_pi_relative ad;
     det3_filter_lanes_b pc Cpp.triangle_filter_pi_relative ad; det3_filter_lanes_b den Cpp.triangle_filter_den_relative ad;
     det3_filter_lanes_b num Cpp.triangle_filter_num_relative ae]
  | _ => [] end.

(** [triangle_relation_lanes] (lanes πa, πb, πc, and π(b, c) seen from a; d broadcast, [bcast]) with its
    absolute lanes (of the broadcast d) and the π constant on every lane, then [triangle_num_filter] and
    num's sign. *)
Definition tri_relation_lanes (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let o := tv ox oy oz in let d := tv dx dy dz in let a := tv ax ay az in let bb := tv bx by_ bz in
    let c := tv cx cy cz in
    let d' := bcast d in
    let l := [pi_stage1_b o d' bb c; pi_stage1_b o d' c a; pi_stage1_b o d' a bb; pi_stage1_b a d' bb c] in
    let ad := absolute_bv d' in let num := num_stage1_b o a bb c in let ae := absolute_bv (tsub a o) in
    flat_map fterm_bits l ++ [b ad] ++ map (fun t => det3_filter_lanes_b t Cpp.triangle_filter_pi_relative ad) l ++
    fterm_bits num ++ [b ae; det3_filter_lanes_b num Cpp.triangle_filter_num_relative ae]
  | _ => [] end.

(** [triangle_compensated_values]: the five values (h, l, m), absolute_d, absolute_e, and each value's
    [enclosure] (det3_enclosure with its constant). *)
Definition tri_compensated (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let o := tv ox oy oz in let d := tv dx dy dz in let a := tv ax ay az in let bb := tv bx by_ bz in
    let c := tv cx cy cz in
    let pa := pi_stage2_b o d bb c in let pb := pi_stage2_b o d c a in let pc := pi_stage2_b o d a bb in
    let den := cterm_add_b (cterm_add_b pa pb) pc in let num := num_stage2_b o a bb c in
    let ad := absolute_bv d in let ae := absolute_bv (ehigh a o) in
    let K := Cpp.triangle_compensated_relative in
    cterm_bits pa ++ cterm_bits pb ++ cterm_bits pc ++ cterm_bits den ++ cterm_bits num ++ [b ad; b ae] ++
    enc_bits (det3_enclosure_b pa K ad) ++ enc_bits (det3_enclosure_b pb K ad) ++ enc_bits (det3_enclosure_b pc K ad) ++
    enc_bits (det3_enclosure_b den Cpp.triangle_compensated_den_relative ad) ++ enc_bits (det3_enclosure_b num K ae)
  | _ => [] end.

(** [triangle_compensated_lanes] (lanes πa, πb, πc, num; o broadcast for ê_b, ê_c, [bcast]) as
    fast_triangle_intersection uses it: the lanes,
    their absolute terms, the filter signs of their stage-1 views (constants π, π, π, num), their enclosures
    (K_π), and den = (lane 0 + lane 1) + lane 2 with its filter sign and enclosure. *)
Definition tri_compensated_lanes (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let o := tv ox oy oz in let d := tv dx dy dz in let a := tv ax ay az in let bb := tv bx by_ bz in
    let c := tv cx cy cz in
    let ad := absolute_bv d in let ae := absolute_bv (ehigh a o) in let o' := bcast o in
    let pa := pi_stage2_b o' d bb c in let pb := pi_stage2_b o' d c a in let pc := pi_stage2_b o' d a bb in
    let l := [(pa, Cpp.triangle_filter_pi_relative, ad); (pb, Cpp.triangle_filter_pi_relative, ad);
              (pc, Cpp.triangle_filter_pi_relative, ad);
              (num_stage2_lane_b o a bb c, Cpp.triangle_filter_num_relative, ae)] in
    let K := Cpp.triangle_compensated_relative in
    let den := cterm_add_b (cterm_add_b pa pb) pc in
    flat_map (fun '(t, _, _) => cterm_bits t) l ++ map (fun '(_, _, A) => b A) l ++
    map (fun '(t, C, A) => det3_filter_lanes_b (fview t) C A) l ++
    flat_map (fun '(t, _, A) => enc_bits (det3_enclosure_b t K A)) l ++
    cterm_bits den ++ [det3_filter_lanes_b (fview den) Cpp.triangle_filter_den_relative ad] ++
    enc_bits (det3_enclosure_b den Cpp.triangle_compensated_den_relative ad)
  | _ => [] end.
End Tri.

(** Ray–triangle stage 3 (TriangleStage3Twins.v): "v ox oy oz dx dy dz ax ay az bx by bz cx cy cz", v the
    determinant's index (0..4: πa, πb, πc, den, num) as an integer word; [value_expansion]'s components,
    its flag [exact] and its sign ([ExpansionValue::sign]). *)
Module Tri3.
Import TriangleTwins TriangleStage3Twins.
Definition tri_expansion (x : list Z) : list Z :=
  match x with [v; ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let e := value_ev (Tri.tv ox oy oz) (Tri.tv dx dy dz) (Tri.tv ax ay az) (Tri.tv bx by_ bz) (Tri.tv cx cy cz) v in
    list_bits (ecomp e) ++ [bool_code (eexact e); sign_code (ev_sign e)]
  | _ => [] end.
End Tri3.
Definition run_tri_expansion := Tri3.tri_expansion.

(** [fast_triangle_relation] (TriangleCascadeTwins.v): queries "o d a b c"; "0" when the fast path does not
    answer, else "1 relation location owned stage" ([enum class] values; the stage is the filter, 0) and the
    public [relation]'s "relation location owned", for the owned rule and then the closed one (the fast path
    answers only where no π is 0, so the rules agree). *)
Module Tri4.
Import TriangleTwins TriangleRule TriangleCascadeTwins.
Definition relation_code (r : tri_relation) : Z :=
  match r with THit => 0 | TBehind => 1 | TMiss => 2 | TDegenerate => 3 | TParallel => 4 | TCoplanar => 5 end.
Definition location_code (l : option location) : Z :=
  match l with
  | Some Inside => 0 | Some EdgeAB => 1 | Some EdgeBC => 2 | Some EdgeCA => 3 | Some VertexA => 4
  | Some VertexB => 5 | Some VertexC => 6 | Some Outside => 7 | None => 8
  end.
Definition class_code (c : option TClass) : list Z :=
  match c with
  | None => [0]
  | Some k => let a := [relation_code (trel k); location_code (tloc k); bool_code (towned k)] in 1 :: a ++ [0] ++ a
  end.
Definition tri_fast_relation (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let c := fast_relation_tri_b (Tri.tv ox oy oz) (Tri.tv dx dy dz) (Tri.tv ax ay az) (Tri.tv bx by_ bz)
                                 (Tri.tv cx cy cz) in
    class_code c ++ class_code c
  | _ => [] end.
End Tri4.
Definition run_tri_fast_relation := Tri4.tri_fast_relation.

(** The mesh leaves' screen [triangle_screen] (triangle/ray_triangle_stages.hpp) and the decision of a screened
    triangle (nearest/triangle_candidate.hpp, classify_screened: [inside_relation] from the screen's lane of den):
    "o d" and four triangles "a b c" (42 words); per triangle what [fast_relation_tri_b] answers — 1 a miss (its
    first decision, the four stage-1 signs certain and not all den's, which the screen decides for four triangles
    at once), 2 a hit and 3 behind (its inside branch: the signs certain and all den's, then num's sign), 0 no
    answer.  Correct by [fast_relation_tri_correct]: each answer is §6's under both rules. *)
Module TriScreen.
Import TriangleTwins TriangleCascadeTwins.
Definition screen_bit (o d a b c : TVec) : Z :=
  match fast_relation_tri_b o d a b c with
  | Some k => match trel k with TMiss => 1%Z | THit => 2%Z | TBehind => 3%Z | _ => 0%Z end
  | None => 0%Z
  end.
Fixpoint screen_bits (o d : TVec) (n : nat) (x : list Z) : list Z :=
  match n, x with
  | S n', ax :: ay :: az :: bx :: by_ :: bz :: cx :: cy :: cz :: rest =>
      screen_bit o d (Tri.tv ax ay az) (Tri.tv bx by_ bz) (Tri.tv cx cy cz) :: screen_bits o d n' rest
  | _, _ => []
  end.
Definition tri_leaf_screen (x : list Z) : list Z :=
  match x with
  | ox :: oy :: oz :: dx :: dy :: dz :: rest =>
      if Nat.eqb (length rest) 36 then screen_bits (Tri.tv ox oy oz) (Tri.tv dx dy dz) 4 rest else []
  | _ => []
  end.
End TriScreen.
Definition run_tri_leaf_screen := TriScreen.tri_leaf_screen.

(** [fast_triangle_intersection] (TriangleIntersectTwins.v): "mode o d a b c", mode = t + 2 · barycentric (the
    options asked, 0..3, an integer word).  For the owned rule and then the closed one: "0" when the fast path
    does not answer, else "1", the answer (relation, location, owned, t, ua, ub, uc, relation stage, rounding
    stage), the public [intersect_traced]'s (the same fields) and the public [intersect]'s (relation,
    location, owned, t, ua, ub, uc): the fast path does not read the rule, and the public entry points return
    its answer. *)
Module Tri5.
Import TriangleTwins TriangleRule TriangleCascadeTwins TriangleIntersectTwins.
Definition answer_code (r : option TAnswerB) : list Z :=
  match r with
  | None => [0]
  | Some k =>
    let c := tab_class k in
    let i := [Tri4.relation_code (trel c); Tri4.location_code (tloc c); bool_code (towned c);
              b (tab_t k); b (tab_ua k); b (tab_ub k); b (tab_uc k)] in
    let s := [tab_relation_stage k; tab_rounding_stage k] in
    1 :: i ++ s ++ i ++ s ++ i
  end.
Definition tri_fast_intersect (x : list Z) : list Z :=
  match x with [mode; ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let r := fast_intersection_tri_b (Z.odd mode) (Z.odd (Z.div2 mode)) (Tri.tv ox oy oz) (Tri.tv dx dy dz)
                                     (Tri.tv ax ay az) (Tri.tv bx by_ bz) (Tri.tv cx cy cz) in
    answer_code r ++ answer_code r
  | _ => [] end.
End Tri5.
Definition run_tri_fast_intersect := Tri5.tri_fast_intersect.
Definition run_tri_filter := Tri.tri_filter.
Definition run_tri_relation_lanes := Tri.tri_relation_lanes.
Definition run_tri_compensated := Tri.tri_compensated.
Definition run_tri_compensated_lanes := Tri.tri_compensated_lanes.

(** The cascade's control flow (PlaneCascadeTwins.v): [intersect_traced] and [relation] on "o d p n".
    cascade_intersect: kind (0 invalid, 1 exact stage, 2 decided), the invalid code or the relation, the
    relation's stage, t's bits and t's stage, then the public [intersect]'s relation and t (the same answer,
    which its fast path must give too); what the exact stage decides is not the twin's (0, stage 3).
    cascade_relation: kind, code or relation, stage, and the signs of num and den. *)
Module Casc.
Import PlaneCascadeTwins.
From Flocq Require IEEE754.BinarySingleNaN.
Definition stage_code (s : stage) : Z := match s with StFilter => 0 | StCompensated => 1 | StExpansion => 2 | StExact => 3 end.
Definition rel_code (r : PlaneClassification.relation) : Z :=
  match r with
  | PlaneClassification.Hit => 0 | PlaneClassification.Behind => 1
  | PlaneClassification.Parallel => 2 | PlaneClassification.InPlane => 3
  end.
Definition nan_bits : Z := b (IEEE754.BinarySingleNaN.B754_nan).
Definition cascade_intersect (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; px; py; pz; nx; ny; nz] =>
    match intersect_traced_b (v3 ox oy oz) (v3 dx dy dz) (v3 px py pz) (v3 nx ny nz) with
    | CInvalid c => [0; c; 0; 0; 0; 0; 0]
    | CExact => [1; 0; 3; 0; 3; 0; 0]
    | CDecided r s t =>
      let rc := rel_code r in let sc := stage_code s in
      match t with
      | TNaN => [2; rc; sc; nan_bits; sc; rc; nan_bits]
      | TZero => [2; rc; sc; 0; sc; rc; 0]
      | TRounded q ts => [2; rc; sc; b q; stage_code ts; rc; b q]
      | TExact => [2; rc; sc; 0; 3; rc; 0]
      end
    end
  | _ => [] end.
Definition cascade_relation (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; px; py; pz; nx; ny; nz] =>
    let o := v3 ox oy oz in let d := v3 dx dy dz in let p := v3 px py pz in let n := v3 nx ny nz in
    match relation_b o d p n with
    | CInvalid c => [0; c; 0; 0; 0]
    | CExact => [1; 0; 3; 0; 0]
    | CDecided r s _ =>
      let '(ns, ds, _) := certified_signs_b o d p n in
      [2; rel_code r; stage_code s; sign_code ns; sign_code ds]
    end
  | _ => [] end.
End Casc.
Definition run_cascade_intersect := Casc.cascade_intersect.
Definition run_cascade_relation := Casc.cascade_relation.

(** The ray–triangle cascade's control flow (TriangleCascadeFlowTwins.v).  An answer is coded as: 0 (the
    input is invalid: the public entry points throw invalid_input, the cascade is not run), 1 (the exact stage
    decided the classification: no answer from the twin), or 2, relation, location, owned, the relation's
    stage, the rounding's stage and the bits of t, ua, ub, uc (0 for all four when the rounding stage is the
    exact one, whose values the twin does not compute).
    tri_cascade_intersect: "mode o d a b c" (mode = t + 2 · barycentric + 4 · closed, an integer word 0..7):
    [triangle_intersection_cascade]'s answer and the public [intersect_traced]'s (the fast path's answer
    when its twin answers, else the cascade's: TriangleIntersectPublic.v's [tri_public_intersect_b], the
    subject of [intersect_public_correct]).
    tri_cascade_relation: "mode o d a b c" (mode = 1 for the closed rule, 0 for the owned one):
    [triangle_relation_cascade]'s answer (relation, location, owned, stage) and the public [relation]'s (relation, location, owned: the fast path's when its
    twin answers, else the cascade's; 1 when that is the exact stage's: TriangleIntersectPublic.v's
    [tri_public_relation_b], the subject of [relation_public_correct]). *)
Module TriFlow.
Import TriangleTwins TriangleCascadeTwins TriangleIntersectTwins TriangleCascadeFlowTwins.
Definition qbits (q : qval) : Z := match q with QNaN => Casc.nan_bits | QVal x => b x | QExact => 0 end.
Definition answer_code (r : tc_answer) : list Z :=
  match r with
  | TCExact => [1]
  | TCDecided cl rs t ua ub uc ts =>
    [2; Tri4.relation_code (trel cl); Tri4.location_code (tloc cl); bool_code (towned cl);
     Casc.stage_code rs; Casc.stage_code ts] ++
    (match ts with StExact => [0; 0; 0; 0] | _ => [qbits t; qbits ua; qbits ub; qbits uc] end)
  end.
Definition tri_cascade_intersect (x : list Z) : list Z :=
  match x with [mode; ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let o := Tri.tv ox oy oz in let d := Tri.tv dx dy dz in let a := Tri.tv ax ay az in
    let bb := Tri.tv bx by_ bz in let c := Tri.tv cx cy cz in
    let wt := Z.odd mode in let wu := Z.odd (Z.div2 mode) in let rule := negb (Z.odd (Z.div2 (Z.div2 mode))) in
    if tri_valid_b o d a bb c then
      let cascade := tc_intersect_b wt wu rule o d a bb c in
      (* TriangleIntersectPublic.v's [tri_public_intersect_b] (of [intersect_public_correct]), sharing the
         cascade's answer computed above. *)
      let public := TriangleIntersectPublic.tri_public_of (fast_intersection_tri_b wt wu o d a bb c) cascade in
      answer_code cascade ++ answer_code public
    else [0; 0]
  | _ => [] end.
Definition tri_cascade_relation (x : list Z) : list Z :=
  match x with [mode; ox; oy; oz; dx; dy; dz; ax; ay; az; bx; by_; bz; cx; cy; cz] =>
    let o := Tri.tv ox oy oz in let d := Tri.tv dx dy dz in let a := Tri.tv ax ay az in
    let bb := Tri.tv bx by_ bz in let c := Tri.tv cx cy cz in
    let rule := negb (Z.odd mode) in
    let code (r : tc_answer) := match r with
      | TCExact => [1]
      | TCDecided cl rs _ _ _ _ _ =>
        [2; Tri4.relation_code (trel cl); Tri4.location_code (tloc cl); bool_code (towned cl); Casc.stage_code rs]
      end in
    if tri_valid_b o d a bb c then
      let cascade := tc_relation_b rule o d a bb c in
      (* TriangleIntersectPublic.v's [tri_public_relation_b] (of [relation_public_correct]), sharing the
         cascade's answer computed above. *)
      let public := TriangleIntersectPublic.tri_public_relation_of (fast_relation_tri_b o d a bb c) cascade in
      let public_code := match code public with 2 :: r => 2 :: firstn 3 r | other => other end in
      code cascade ++ public_code
    else [0; 0]
  | _ => [] end.
End TriFlow.
Definition run_tri_cascade_intersect := TriFlow.tri_cascade_intersect.
Definition run_tri_cascade_relation := TriFlow.tri_cascade_relation.

(** mesh_predicates.hpp: the orientation filters of the point-in-mesh query (OrientTwins.v).  [orient2d]:
    "k p q r" (k the ray's axis 0..2 as an integer word, p, q, r three points), the filter in the plane of the
    axes i = (k + 1) mod 3, j = (k + 2) mod 3 as [inside] calls it, each coordinate read as [coordinate(v,
    axis)] reads it; [orient3d]: "o a b c". Output: the filter's answer, +1, −1 or 0. *)
Definition coordinate (v0 v1 v2 axis : Z) : Z := if axis =? 0 then v0 else if axis =? 1 then v1 else v2.
Definition run_orient2d (x : list Z) : list Z :=
  match x with [k; px; py; pz; qx; qy; qz; rx; ry; rz] =>
    let i := (k + 1) mod 3 in let j := (k + 2) mod 3 in
    [OrientTwins.orient2d_filter_b (f (coordinate px py pz i)) (f (coordinate px py pz j))
       (f (coordinate qx qy qz i)) (f (coordinate qx qy qz j)) (f (coordinate rx ry rz i)) (f (coordinate rx ry rz j))]
  | _ => [] end.
Definition run_orient3d (x : list Z) : list Z :=
  match x with [o0; o1; o2; a0; a1; a2; b0; b1; b2; c0; c1; c2] =>
    [OrientTwins.orient3d_filter_b (f o0) (f o1) (f o2) (f a0) (f a1) (f a2) (f b0) (f b1) (f b2) (f c0) (f c1) (f c2)]
  | _ => [] end.

(** sphere/ray_sphere_stages.hpp (SphereStages.v): [sphere_expansions] on "ox oy oz dx dy dz cx cy cz r" — the
    builder's flag, then s.a, s.b, s.c, s.d (each its length and components); [sphere_abc_expansions] on the same
    — the flag, then s.a, s.b, s.c; [sphere_root_side] on the same query, the root (−1 or +1, as a signed integer
    word: 0 reads as −1, anything else as +1) and the boundary's doubles x, y — the expansions built by
    [sphere_abc_expansions] first, as the cascade and sphere_root_side_of call it — the side as a sign code
    (2: uncertain). *)
Definition sphere_query (ox oy oz dx dy dz cx cy cz r : Z) :=
  SphereStages.sphere_expansions_b (f ox, f oy, f oz) (f dx, f dy, f dz) (f cx, f cy, f cz) (f r).
Definition sphere_abc_query (ox oy oz dx dy dz cx cy cz r : Z) :=
  SphereStages.sphere_abc_expansions_b (f ox, f oy, f oz) (f dx, f dy, f dz) (f cx, f cy, f cz) (f r).
Definition run_sphere_expansions (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; cx; cy; cz; r] =>
    let '(ex, a, b, c, d) := sphere_query ox oy oz dx dy dz cx cy cz r in
    bool_code ex :: list_bits a ++ list_bits b ++ list_bits c ++ list_bits d | _ => [] end.
Definition run_sphere_abc_expansions (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; cx; cy; cz; r] =>
    let '(ex, a, b, c) := sphere_abc_query ox oy oz dx dy dz cx cy cz r in
    bool_code ex :: list_bits a ++ list_bits b ++ list_bits c | _ => [] end.
Definition run_sphere_root_side (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; cx; cy; cz; r; root; mx; my] =>
    let '(_, a, b, c) := sphere_abc_query ox oy oz dx dy dz cx cy cz r in
    [sign_code (SphereStages.sphere_root_side_b a b c (if root =? 0 then (-1) else 1) (f mx) (f my))]
  | _ => [] end.

(** spawn/spawn_certified.hpp (SpawnTwins.v): [midpoint_offset] on "x y o" and [affine_enclosure] on
    "o D.hi D.lo D.radius d N.hi N.lo N.radius" (the C++ argument order); each returns its enclosure (hi, lo,
    radius). *)
Definition run_midpoint_offset (x : list Z) : list Z :=
  match x with [x0; y0; o0] => enc_bits (SpawnTwins.midpoint_offset_b (f x0) (f y0) (f o0)) | _ => [] end.
Definition run_affine_enclosure (x : list Z) : list Z :=
  match x with [o; dh; dl; dr; d; nh; nl; nr] =>
    enc_bits (SpawnTwins.affine_enclosure_b (f o) (enc dh dl dr) (f d) (enc nh nl nr)) | _ => [] end.

(** core/escalation.hpp (Escalation.v): [Escalation(start).sign(SignStage{stage_k, decide_k}...)] on "start
    stage_1 sign_1 ... stage_m sign_m" (m ≤ 6 steps; a stage as its code 0..3, a sign as its code −1, 0, +1, 2
    in a 64-bit two's-complement word, so −1 is 2^64 − 1): the answer's sign code, the trace's stage code and
    the number of stages asked. *)
Definition escalation_stage (w : Z) : option Escalation.stage :=
  if w =? 0 then Some Escalation.StFilter else if w =? 1 then Some Escalation.StCompensated
  else if w =? 2 then Some Escalation.StExpansion else if w =? 3 then Some Escalation.StExact else None.
Definition escalation_sign (w : Z) : option sign :=
  if w =? 18446744073709551615 then Some Negative else if w =? 0 then Some Zero
  else if w =? 1 then Some Positive else if w =? 2 then Some Uncertain else None.
Fixpoint escalation_steps (x : list Z) : option (list (Escalation.stage * sign)) :=
  match x with
  | [] => Some []
  | st :: sg :: rest =>
    match escalation_stage st, escalation_sign sg, escalation_steps rest with
    | Some a, Some c, Some r => Some ((a, c) :: r)
    | _, _, _ => None
    end
  | _ => None
  end.
Definition run_escalate (x : list Z) : list Z :=
  match x with
  | start :: rest =>
    match escalation_stage start, escalation_steps rest with
    | Some s, Some steps =>
      if Nat.leb (length steps) 6 then
        let '(a, t, k) := Escalation.escalate s steps in [sign_code a; Casc.stage_code t; Z.of_nat k]
      else []
    | _, _ => []
    end
  | [] => []
  end.

(** box/ray_box.hpp (RayBoxTwins.v): [ray_box_setup] on "ox oy oz dx dy dz Mx My Mz" — [make_slabs] of the ray
    with the magnitudes M: per axis the inverse and enters_at_hi ([make_slab_b]).  [ray_box_entry] and
    [ray_box_node] on "o0 o1 o2 inv0 inv1 inv2 h0 h1 h2 t_min t_max" (a ray's slabs: h_k a word, non-zero when the
    ray enters axis k at the upper face) and the 48 words of a node's face rows, BvhNode::bounds[f][s] at 8·f + s
    (faces lo.x lo.y lo.z hi.x hi.y hi.z, each a binary32 value as the double it converts to): per slot s the
    entry bound and whether the box may be met — the scalar test on box s ([ray_box_entry_b]), and the eight
    lanes of [ray_box_entries8] ([ray_box_entries8_b]: the ray and t_min, t_max broadcast, −0 becoming +0). *)
Definition run_ray_box_setup (x : list Z) : list Z :=
  match x with [ox; oy; oz; dx; dy; dz; mx; my; mz] =>
    flat_map (fun a => let '(d, o, m) := a in
                       let r := RayBoxTwins.make_slab_b (f d) (f o) (f m) in [b (fst r); bool_code (snd r)])
      [(dx, ox, mx); (dy, oy, my); (dz, oz, mz)]
  | _ => [] end.
Definition run_ray_box_boxes (test : list (float * float * bool * float * float) -> float -> float -> float * bool)
    (x : list Z) : list Z :=
  match x with o0 :: o1 :: o2 :: i0 :: i1 :: i2 :: h0 :: h1 :: h2 :: tmin :: tmax :: rows =>
    if Nat.eqb (length rows) 48 then
      let face (k s : nat) := f (nth (8 * k + s)%nat rows 0) in
      flat_map (fun s =>
        let axes := [(f o0, f i0, negb (h0 =? 0), face 0%nat s, face 3%nat s);
                     (f o1, f i1, negb (h1 =? 0), face 1%nat s, face 4%nat s);
                     (f o2, f i2, negb (h2 =? 0), face 2%nat s, face 5%nat s)] in
        let r := test axes (f tmin) (f tmax) in [b (fst r); bool_code (snd r)])
        (seq 0 8)
    else []
  | _ => [] end.
Definition run_ray_box_entry := run_ray_box_boxes RayBoxTwins.ray_box_entry_b.
Definition run_ray_box_node := run_ray_box_boxes RayBoxTwins.ray_box_entries8_b.

Extraction "twins.ml" run_two_sum run_two_diff run_two_prod run_dot3_rounded run_filter_den
  run_filter_num run_compensated run_compensated_exact run_refined run_enclosure_sign run_tail_enclosure
  run_filter_enclosure_den run_filter_enclosure_num run_propagated run_compare_filter run_compare_compensated
  run_exp_sum run_exp_scale run_exp_sign run_round_quotient
  run_half_gap run_fast_answer run_fast_answer_pair run_fast_relation run_fast_relation_pair
  run_build_expansions run_compare_expansion run_quotient_boundary run_nearest_compare
  run_tri_filter run_tri_relation_lanes run_tri_compensated run_tri_compensated_lanes run_tri_expansion
  run_tri_fast_relation run_tri_leaf_screen run_tri_fast_intersect
  run_cascade_intersect run_cascade_relation
  run_tri_cascade_intersect run_tri_cascade_relation
  run_orient2d run_orient3d
  run_sphere_expansions run_sphere_abc_expansions run_sphere_root_side
  run_midpoint_offset run_affine_enclosure
  run_escalate
  run_ray_box_setup run_ray_box_entry run_ray_box_node.
