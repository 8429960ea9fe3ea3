(** * The twin of the ray–triangle cascade's control flow (kernel/src/triangle/ray_triangle_cascade.cpp,
    [TriangleCascade], [triangle_relation_cascade], [triangle_intersection_cascade]; the public [relation]
    and [intersect_traced] of triangle_api.cpp), over IEEE-754 binary64, as PlaneCascadeTwins.v is the ray–plane
    one.

    From the fifteen input bit patterns, as the C++ does:
    - [tc_sign_b v]: [TriangleCascade::sign(v)] — stage 1 ([triangle_filter_values], [det3_filter_lanes]
      with v's constants: TriangleTwins.v), then stage 2's enclosure sign ([triangle_compensated_values],
      [det3_enclosure], [enclosure_sign]; the C++ evaluates both stages at once as
      [triangle_compensated_values_by_lanes] and its filter view: the same values up to the sign of a zero,
      which no strict comparison sees — TriangleTwins.v's lane twins, runner routine [tri_compensated_lanes]),
      then stage 3 ([stage3_sign], [tc_stage3_sign_b]): the integer sign when the leaves allow
      ([integer_value_sign]: TriangleIntegerSign.v's [integer_value_sign_b]), else the expansion's checked sign
      ([value_expansion]: TriangleStage3Twins.v's [value_ev], [ev_sign]), else 0 with [needs_exact_] set;
    - [tc_tie_break_b k]: [tie_break(k)] — [tie_break_signs_by_expansion]: the signs of d × (q − p) for
      edge k as expansions ([ev_cross] of [lift3 d] and [diff3 q p]), or {1, 0, 0} with [needs_exact_];
    - [tc_normal_b]: [normal_is_zero()] — [normal_is_zero_by_expansion]: N = (b − a) × (c − a) as
      expansions, or false with [needs_exact_];
    - [tc_classify_b rule]: [classify_triangle] (ray_triangle_formula.hpp) with those callbacks, in the
      C++ order of the calls; the state ([TFlow]) is [stage_] (the latest stage any call reached) and
      [needs_exact_];
    - [tc_intersect_b]: [triangle_intersection_cascade]: the classification; the numerators' signs (an
      exactly zero numerator gives +0); [round_quotients] on the stage-2 enclosures over one divisor (its
      fields broadcast: [shared_divisor_b]); the stage-3 tail enclosures ([expansion_enclosure] of stage 3's
      value, [tc_stage3_components_b]: the integer's components, else the exact expansion; at most
      [tail_sum_max_terms] components, [PlaneCascadeTwins.tail_b]) over den's (or stage 2's) divisor,
      [round_quotient] per quotient; then [round_quotient_near] on the candidates ([qstep_boundary]: num's and
      den's stage-3 values of at most 16 components, den's stage-3 sign ±1); else the exact stage ([QExact]:
      the twin computes no exact answer);
    - [tc_relation_b]: [triangle_relation_cascade];
    - [tri_valid_b]: [is_valid(ray) & is_valid(triangle)] (finite components, d not the zero vector), by
      which the public entry points choose between the fast path's answer, invalid_input and the cascade.

    The differential runner (routines [tri_cascade_intersect], [tri_cascade_relation], group triangles5)
    compares these definitions with the compiled [triangle_intersection_cascade] and
    [triangle_relation_cascade] and with the public [intersect_traced] and [relation] (after the fast
    path's twins, TriangleCascadeTwins.v and TriangleIntersectTwins.v), bit for bit, stages included. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification PlaneCascade FloatCore ConstantsCpp PlaneTwins Expansions PlaneQueryTwins
  TriangleFilter TriangleRule TriangleTwins TriangleStage3Twins TriangleCascadeTwins TriangleIntersectTwins
  QuotientBoundary TriangleIntegerSign.
From Raykernel Require PlaneCascadeTwins.
Import ListNotations.

(** [Stage] and [later] (ray_triangle_cascade.cpp). *)
Notation stage := PlaneCascadeTwins.stage.
Notation StFilter := PlaneCascadeTwins.StFilter.
Notation StCompensated := PlaneCascadeTwins.StCompensated.
Notation StExpansion := PlaneCascadeTwins.StExpansion.
Notation StExact := PlaneCascadeTwins.StExact.

Definition stage_rank (s : stage) : Z :=
  match s with StFilter => 0 | StCompensated => 1 | StExpansion => 2 | StExact => 3 end.
Definition later (s t : stage) : stage := if Z.leb (stage_rank t) (stage_rank s) then s else t.

(** The query's state: [stage_] and [needs_exact_]. *)
Record TFlow := TFl { tf_stage : stage; tf_exact : bool }.
Definition tf_start : TFlow := TFl StFilter false.
Definition tf_reach (f : TFlow) (s : stage) : TFlow := TFl (later (tf_stage f) s) (tf_exact f).
Definition tf_give_up (f : TFlow) : TFlow := TFl (tf_stage f) true.

Section Query.
Variables o d a b c : TVec.

(** Stage 1 of determinant v (0 πa, 1 πb, 2 πc, 3 den, 4 num) as [triangle_filter_values] forms it, and
    [filter_relative(v)], [absolute(v)]. *)
Definition tc_value1_b (v : Z) : FTermB :=
  if Z.eqb v 0 then pi_stage1_b o d b c else if Z.eqb v 1 then pi_stage1_b o d c a
  else if Z.eqb v 2 then pi_stage1_b o d a b else if Z.eqb v 3 then den_stage1_b o d a b c
  else num_stage1_b o a b c.
Definition tc_filter_relative (v : Z) : float :=
  if Z.eqb v 3 then Cpp.triangle_filter_den_relative
  else if Z.eqb v 4 then Cpp.triangle_filter_num_relative else Cpp.triangle_filter_pi_relative.
Definition tc_absolute1_b (v : Z) : float := if Z.eqb v 4 then absolute_bv (tsub a o) else absolute_bv d.
Definition tc_filter_b (v : Z) : Z := det3_filter_lanes_b (tc_value1_b v) (tc_filter_relative v) (tc_absolute1_b v).

(** Stage 2 ([triangle_compensated_values]) and [TriangleCompensatedValues::enclosure(v)]. *)
Definition tc_value2_b (v : Z) : CTermB :=
  if Z.eqb v 0 then pi_stage2_b o d b c else if Z.eqb v 1 then pi_stage2_b o d c a
  else if Z.eqb v 2 then pi_stage2_b o d a b else if Z.eqb v 3 then den_stage2_b o d a b c
  else num_stage2_b o a b c.
Definition tc_compensated_relative (v : Z) : float :=
  if Z.eqb v 3 then Cpp.triangle_compensated_den_relative else Cpp.triangle_compensated_relative.
Definition tc_absolute2_b (v : Z) : float := if Z.eqb v 4 then absolute_bv (ehigh a o) else absolute_bv d.
Definition tc_enclosure2_b (v : Z) : EnclosureB :=
  det3_enclosure_b (tc_value2_b v) (tc_compensated_relative v) (tc_absolute2_b v).

(** [stage3_sign(v)]: the integer sign when the leaves allow, else the expansion's checked sign. *)
Definition tc_stage3_sign_b (v : Z) : sign :=
  let si := integer_value_sign_b o d a b c v in
  if is_certain si then si else ev_sign (value_ev o d a b c v).

(** [sign(v)]. *)
Definition tc_sign_b (v : Z) (f : TFlow) : Z * TFlow :=
  let s1 := tc_filter_b v in
  if negb (Z.eqb s1 uncertain_lane) then (s1, f) else
  let f := tf_reach f StCompensated in
  let s2 := PlaneCascadeTwins.enclosure_sign_b (tc_enclosure2_b v) in
  if is_certain s2 then (sign_to_Z s2, f) else
  let f := tf_reach f StExpansion in
  let s3 := tc_stage3_sign_b v in
  if is_certain s3 then (sign_to_Z s3, f) else (0%Z, tf_give_up f).

(** [tie_break_signs_by_expansion(ray, triangle, k)]: d × (q − p) for b → c, c → a, a → b. *)
Definition tc_tie_vector (k : Z) : E3 :=
  let p := if Z.eqb k 0 then b else if Z.eqb k 1 then c else a in
  let q := if Z.eqb k 0 then c else if Z.eqb k 1 then a else b in
  ev_cross (lift3 d) (diff3 q p).

(** [tie_break(k)]: the stage reaches stage 3; the three signs, or {1, 0, 0} and the exact stage. *)
Definition tc_tie_break_b (k : Z) (f : TFlow) : (Z * Z * Z) * TFlow :=
  let f := tf_reach f StExpansion in
  let v := tc_tie_vector k in
  let s0 := ev_sign (e0 v) in let s1 := ev_sign (e1 v) in let s2 := ev_sign (e2 v) in
  if (is_certain s0 && is_certain s1 && is_certain s2)%bool then ((sign_to_Z s0, sign_to_Z s1, sign_to_Z s2), f)
  else ((1%Z, 0%Z, 0%Z), tf_give_up f).

(** [normal_is_zero_by_expansion(triangle)]: N = (b − a) × (c − a). *)
Definition tc_normal_vector : E3 := ev_cross (diff3 b a) (diff3 c a).

Definition tc_normal_b (f : TFlow) : bool * TFlow :=
  let f := tf_reach f StExpansion in
  let n := tc_normal_vector in
  let s0 := ev_sign (e0 n) in let s1 := ev_sign (e1 n) in let s2 := ev_sign (e2 n) in
  if (is_certain s0 && is_certain s1 && is_certain s2)%bool then
    ((Z.eqb (sign_to_Z s0) 0 && Z.eqb (sign_to_Z s1) 0 && Z.eqb (sign_to_Z s2) 0)%bool, f)
  else (false, tf_give_up f).

(** One step of [classify_triangle]'s loop over k: while owned, a π that is 0 asks its tie-break. *)
Definition tc_owned_step (sden k sk : Z) (st : bool * TFlow) : bool * TFlow :=
  let '(owned, f) := st in
  if (owned && Z.eqb sk 0)%bool then
    let '((tx, ty, tz), f) := tc_tie_break_b k f in (Z.eqb (owned_sign 0 tx ty tz) sden, f)
  else (owned, f).

(** [classify_triangle(rule, ...)] (ray_triangle_formula.hpp) with [TriangleCascade]'s callbacks; [owned_rule]
    true for [TriangleRule::owned]. *)
Definition tc_classify_b (owned_rule : bool) : TClass * TFlow :=
  let '(sden, f) := tc_sign_b 3 tf_start in
  if Z.eqb sden 0 then
    let '(degenerate, f) := tc_normal_b f in
    if degenerate then (TC TDegenerate None false, f)
    else let '(sn, f) := tc_sign_b 4 f in (TC (if Z.eqb sn 0 then TCoplanar else TParallel) None false, f)
  else
    let '(sa, f) := tc_sign_b 0 f in let '(sb, f) := tc_sign_b 1 f in let '(sc, f) := tc_sign_b 2 f in
    let loc := triangle_location sa sb sc sden in
    let '(owned, f) := tc_owned_step sden 2 sc (tc_owned_step sden 1 sb
                         (tc_owned_step sden 0 sa (negb (is_outside (Some loc)), f))) in
    let through := if owned_rule then owned else negb (is_outside (Some loc)) in
    if through then
      let '(sn, f) := tc_sign_b 4 f in
      (TC (if Z.leb 0 (sn * sden) then THit else TBehind) (Some loc) owned, f)
    else (TC TMiss (Some loc) owned, f).

(** Stage 3's exact value of determinant v for the roundings: its integer's components when the leaves allow
    ([integer_value_components]), else its expansion of doubles when that is exact. *)
Definition tc_stage3_components_b (v : Z) : option (list float) :=
  match integer_value_components_b o d a b c v with
  | Some l => Some l
  | None => let e := value_ev o d a b c v in if eexact e then Some (ecomp e) else None
  end.

(** [expansion_enclosure(v)]: stage 3's tail enclosure when that value has at most [tail_sum_max_terms]
    components. *)
Definition tc_expansion_enclosure_b (v : Z) : option EnclosureB :=
  match tc_stage3_components_b v with
  | Some l => if Z.leb (Z.of_nat (length l)) Cpp.tail_sum_max_terms then Some (PlaneCascadeTwins.tail_b l) else None
  | None => None
  end.

(** [short_expansion(v)]: that value when it has at most 16 components (the capacity
    [round_quotient_at_boundaries] is proved for). *)
Definition tc_short_b (v : Z) : option (list float) :=
  match tc_stage3_components_b v with
  | Some l => if Nat.leb (length l) 16 then Some l else None
  | None => None
  end.

End Query.

(** A quotient of the answer: NaN (not asked, or no crossing), a value, or left to the exact stage. *)
Inductive qval := QNaN | QVal (x : float) | QExact.

(** The cascade's answer: the exact stage decided the classification (no answer from the twin), or the
    classification, its stage, t, the three barycentrics and the rounding stage. *)
Inductive tc_answer := TCExact | TCDecided (cl : TClass) (rs : stage) (t ua ub uc : qval) (ts : stage).

(** One quotient's progress: whether it is certain, and its value. *)
Definition qstep (x : bool * qval) (r : float * bool) : bool * qval :=
  if fst x then x else (snd r, QVal (fst r)).

Definition qstep3 (x : bool * qval) (r : option (float * bool)) : bool * qval :=
  if fst x then x else match r with Some r => (snd r, QVal (fst r)) | None => x end.

(** A quotient not yet certain, decided at the rounding boundaries of its candidate when den's sign is ±1 and
    both expansions are short: [round_quotient_near(num, den, den_sign, candidate)] (the boundaries of the candidate, else of its neighbours). *)
Definition qstep_boundary (x : bool * qval) (ds : Z) (den num : option (list float)) : bool * qval :=
  if fst x then x else
  match snd x, den, num with
  | QVal q, Some ed, Some en =>
    if (Z.eqb ds 1 || Z.eqb ds (-1))%bool then
      match round_quotient_near_b en ed ds q with Some r => (true, QVal r) | None => x end
    else x
  | _, _, _ => x
  end.

Definition qfinal (x : bool * qval) : qval := if fst x then snd x else QExact.

(** [triangle_intersection_cascade(ray, triangle, options)]: [want_t], [want_u] the options t and
    barycentric, [owned_rule] the rule. *)
Definition tc_intersect_b (want_t want_u owned_rule : bool) (o d a b c : TVec) : tc_answer :=
  let '(cl, f) := tc_classify_b o d a b c owned_rule in
  if tf_exact f then TCExact else
  let rs := tf_stage f in
  if (match tloc cl with None => true | Some _ => false end || (negb want_t && negb want_u))%bool
  then TCDecided cl rs QNaN QNaN QNaN QNaN rs else
  (* the numerators' signs, for the quotients asked: t (num), then πa, πb, πc *)
  let '(n0, f) := if want_t then tc_sign_b o d a b c 4 f else (0%Z, f) in
  let '(n1, f) := if want_u then tc_sign_b o d a b c 0 f else (0%Z, f) in
  let '(n2, f) := if want_u then tc_sign_b o d a b c 1 f else (0%Z, f) in
  let '(n3, f) := if want_u then tc_sign_b o d a b c 2 f else (0%Z, f) in
  let exact_or_nan (w : bool) := if w then QExact else QNaN in
  if tf_exact f then
    TCDecided cl rs (exact_or_nan want_t) (exact_or_nan want_u) (exact_or_nan want_u) (exact_or_nan want_u) StExact
  else
  let start (w : bool) (n : Z) := (negb w || Z.eqb n 0, if w then QVal fzero else QNaN)%bool in
  let x0 := start want_t n0 in let x1 := start want_u n1 in let x2 := start want_u n2 in
  let x3 := start want_u n3 in
  let all (x0 x1 x2 x3 : bool * qval) := (fst x0 && fst x1 && fst x2 && fst x3)%bool in
  let ts := tf_stage f in
  if all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts else
  (* stage 2: round_quotients over one divisor *)
  let ts := later ts StCompensated in
  let dv := shared_divisor_b (tc_enclosure2_b o d a b c 3) in
  let x0 := qstep x0 (round_quotient_b (tc_enclosure2_b o d a b c 4) dv) in
  let x1 := qstep x1 (round_quotient_b (tc_enclosure2_b o d a b c 0) dv) in
  let x2 := qstep x2 (round_quotient_b (tc_enclosure2_b o d a b c 1) dv) in
  let x3 := qstep x3 (round_quotient_b (tc_enclosure2_b o d a b c 2) dv) in
  if all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts else
  (* stage 3: the tail enclosures over den's (or stage 2's) divisor *)
  let ts := later ts StExpansion in
  let dd := match tc_expansion_enclosure_b o d a b c 3 with Some e => e | None => tc_enclosure2_b o d a b c 3 end in
  let dv3 := prepare_divisor_b dd in
  let r3 (v : Z) := match tc_expansion_enclosure_b o d a b c v with
                    | Some n => Some (round_quotient_b n dv3) | None => None end in
  let x0 := if fst x0 then x0 else qstep3 x0 (r3 4%Z) in
  let x1 := if fst x1 then x1 else qstep3 x1 (r3 0%Z) in
  let x2 := if fst x2 then x2 else qstep3 x2 (r3 1%Z) in
  let x3 := if fst x3 then x3 else qstep3 x3 (r3 2%Z) in
  if all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts else
  (* the rounding boundaries of each candidate, in expansions ([round_quotient_at_boundaries]) *)
  let ds := sign_to_Z (tc_stage3_sign_b o d a b c 3) in
  let rb (v : Z) (x : bool * qval) := qstep_boundary x ds (tc_short_b o d a b c 3) (tc_short_b o d a b c v) in
  let x0 := rb 4%Z x0 in let x1 := rb 0%Z x1 in let x2 := rb 1%Z x2 in let x3 := rb 2%Z x3 in
  if all x0 x1 x2 x3 then TCDecided cl rs (snd x0) (snd x1) (snd x2) (snd x3) ts
  else TCDecided cl rs (qfinal x0) (qfinal x1) (qfinal x2) (qfinal x3) StExact.

(** [triangle_relation_cascade(ray, triangle, rule)]. *)
Definition tc_relation_b (owned_rule : bool) (o d a b c : TVec) : tc_answer :=
  let '(cl, f) := tc_classify_b o d a b c owned_rule in
  if tf_exact f then TCExact else TCDecided cl (tf_stage f) QNaN QNaN QNaN QNaN (tf_stage f).

(** [is_valid(ray) & is_valid(triangle)] (validation.hpp): finite components, d not (±0, ±0, ±0). *)
Definition tfin_b (v : TVec) : bool := (fin (tx v) && fin (ty v) && fin (tz v))%bool.
Definition tri_valid_b (o d a b c : TVec) : bool :=
  (tfin_b o && tfin_b d && negb (PlaneCascadeTwins.is_zero_b (tx d) && PlaneCascadeTwins.is_zero_b (ty d) &&
                                  PlaneCascadeTwins.is_zero_b (tz d)) && tfin_b a && tfin_b b && tfin_b c)%bool.
