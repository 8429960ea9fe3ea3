(** * The ray–triangle fast intersection (kernel/src/triangle/ray_triangle_cascade.cpp,
    [fast_triangle_intersection]) as a twin over IEEE-754 binary64.

    - [fast_intersection_tri_b want_t want_u o d a b c]: [fast_triangle_intersection_body], operation by
      operation on TriangleTwins.v's stage-2 lane twins: with neither t nor the barycentrics asked, the
      relation's fast path ([fast_relation_tri_b], TriangleCascadeTwins.v); otherwise the four lanes of
      [triangle_compensated_lanes] (πa, πb, πc with o broadcast, [bcast]; num), each sign
      [first_certain_lanes] of the filter sign of its stage-1 view ([fview], constants π, π, π, num) and
      the sign of its enclosure (K_π); den = (lane 0 + lane 1) + lane 2 with its own constants;
      [decide_nonzero_b] ([decide_nonzero]); [round_quotients] over the one divisor prepared from den's
      enclosure, its fields broadcast ([V{} + x], −0 becomes +0: [shared_divisor_b]); the stages
      ([by_filter]).  [None] where the C++ returns std::nullopt; NaN ([fnan]) for a value not asked.

    The differential runner (routine [tri_fast_intersect], group triangles3) compares the twin with the
    compiled [fast_triangle_intersection] and, when it answers, the public [intersect_traced] and [intersect],
    for both rules and every combination of the options t and barycentric.  The theorem that an answer of
    this twin is §6's with t = RN(num/den) and the barycentrics RN(π_k/den) is
    [fast_intersection_tri_correct] (TriangleIntersectTheorem.v). *)

From Coq Require Import ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification FloatCore ConstantsCpp PlaneTwins PlaneQueryTwins TriangleRule TriangleTwins TriangleCascadeTwins.
Open Scope Z_scope.

Definition fnan : float := B754_nan.

(** [broadcast<Lanes4>(x)] = [V{} + x]. *)
Definition bcast_f (x : float) : float := fadd fzero x.

(** [round_quotients]' divisor: [prepare_divisor(den)], its fields broadcast to the four lanes. *)
Definition shared_divisor_b (den : EnclosureB) : DivisorB :=
  let dv := prepare_divisor_b den in
  {| dhib := bcast_f (dhib dv); dlob := bcast_f (dlob dv); dradiusb := bcast_f (dradiusb dv);
     dreciprocalb := bcast_f (dreciprocalb dv); din_rangeb := din_rangeb dv |}.

(** [decide_nonzero(sa, sb, sc, sden, snum)]. *)
Definition decide_nonzero_b (sa sb sc sden snum : Z) : option TClass :=
  if (Z.eqb sa sden && Z.eqb sb sden && Z.eqb sc sden)%bool then
    if Z.eqb snum uncertain_lane then None
    else Some (TC (if Z.eqb snum sden then THit else TBehind) (Some Inside) true)
  else Some (TC TMiss (Some Outside) false).

(** The answer: the classification, t, the three barycentrics, the relation's stage and the rounding's
    stage (0 filter, 1 compensated: [Stage]'s values). *)
Record TAnswerB := TAB { tab_class : TClass; tab_t : float; tab_ua : float; tab_ub : float; tab_uc : float;
                         tab_relation_stage : Z; tab_rounding_stage : Z }.

Definition is_outside (l : option location) : bool := match l with Some Outside => true | _ => false end.

Definition fast_intersection_tri_b (want_t want_u : bool) (o d a b c : TVec) : option TAnswerB :=
  if (negb want_t && negb want_u)%bool then
    match fast_relation_tri_b o d a b c with
    | Some cl => Some (TAB cl fnan fnan fnan fnan 0 0)
    | None => None
    end
  else
    let ad := absolute_bv d in let ae := absolute_bv (ehigh a o) in let o' := bcast o in
    let pa := pi_stage2_b o' d b c in let pb := pi_stage2_b o' d c a in let pc := pi_stage2_b o' d a b in
    let pn := num_stage2_lane_b o a b c in
    let Cpi := Cpp.triangle_filter_pi_relative in let K := Cpp.triangle_compensated_relative in
    let fa := det3_filter_lanes_b (fview pa) Cpi ad in let fb := det3_filter_lanes_b (fview pb) Cpi ad in
    let fc := det3_filter_lanes_b (fview pc) Cpi ad in
    let fn := det3_filter_lanes_b (fview pn) Cpp.triangle_filter_num_relative ae in
    let ea := det3_enclosure_b pa K ad in let eb := det3_enclosure_b pb K ad in
    let ec := det3_enclosure_b pc K ad in let en := det3_enclosure_b pn K ae in
    let sa := first_certain_lanes_b fa (enclosure_sign_lanes_b ea) in
    let sb := first_certain_lanes_b fb (enclosure_sign_lanes_b eb) in
    let sc := first_certain_lanes_b fc (enclosure_sign_lanes_b ec) in
    let sn := first_certain_lanes_b fn (enclosure_sign_lanes_b en) in
    let den := cterm_add_b (cterm_add_b pa pb) pc in
    let fd := det3_filter_lanes_b (fview den) Cpp.triangle_filter_den_relative ad in
    let ed := det3_enclosure_b den Cpp.triangle_compensated_den_relative ad in
    let sd := first_certain_lanes_b fd (enclosure_sign_lanes_b ed) in
    if negb (certain_lane sa && certain_lane sb && certain_lane sc && certain_lane sd)%bool then None else
    match decide_nonzero_b sa sb sc sd sn with
    | None => None
    | Some cl =>
      if (want_t && negb (certain_lane sn))%bool then None else
      let dv := shared_divisor_b ed in
      let qa := round_quotient_b ea dv in let qb := round_quotient_b eb dv in
      let qc := round_quotient_b ec dv in let qn := round_quotient_b en dv in
      if negb ((negb want_t || snd qn) && (negb want_u || (snd qa && snd qb && snd qc)))%bool then None else
      let by_filter := (certain_lane fa && certain_lane fb && certain_lane fc && certain_lane fd &&
                        (is_outside (tloc cl) || certain_lane fn))%bool in
      Some (TAB cl (if want_t then fst qn else fnan) (if want_u then fst qa else fnan)
                (if want_u then fst qb else fnan) (if want_u then fst qc else fnan)
                (if by_filter then 0 else 1) 1)
    end.
