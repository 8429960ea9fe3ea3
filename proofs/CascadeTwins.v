(** * The twin of the ray–plane cascade's control flow (certified/ray_plane_cascade.{hpp,cpp},
    validation.{hpp,cpp}, api.cpp: [intersect_traced], [relation]).

    From the twelve input bit patterns, as the C++ does:
    - [validate_b]: validation.cpp's [validate(ray, plane)] — the first non-finite component in the order
      o, d, p, n (and whether it is NaN, +inf or −inf, decided from the bits), then a zero direction, then
      a zero normal — as a code: 3·i + k for component i (0 … 11) of kind k (0 NaN, 1 +inf, 2 −inf), 36 for
      "ray direction is the zero vector", 37 for "plane normal is the zero vector";
    - [certified_signs_b]: stage 1 with the zero flags of RayPlaneCascade::den_filter/num_filter, then, for
      the signs still open, the first level of stage 2, then its second level, then stage 3 (the checked
      signs of the expansions, when the builder says exact), else the exact stage, which the twin does not
      compute ([StExact], no answer);
    - [certified_quotient_b]: round_quotient on the first level's enclosures, on the second level's, on the
      stage-3 tail enclosures (when exact), else the exact stage ([None]);
    - [intersect_cascade_b]: parallel and in-plane (t = NaN), num = 0 (t = +0), the exact stage when the
      signs came from it, else t from [certified_quotient_b];
    - [intersect_traced_b], [relation_b]: validation first, then the cascade ([intersect_traced], and
      [relation] past its fast path, whose certified answers are the contract's: QueryTwins.v).

    The stage twins are Twins.v's, RefinedTwins.v's, QueryTwins.v's and Expansions.v's, called as
    ray_plane_query.hpp calls them; the differential runner compares the public entry points with these
    definitions bit for bit, the deciding stage included (routines [cascade_intersect],
    [cascade_relation]).  The theorem [cascade_twin_correct] (below) says what an answer before the exact
    stage means. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model Filter Compensated Classification QuotientRounding Cascade FloatCore
  ConstantsCpp Twins Expansions QueryTwins RefinedTwins.
Import ListNotations.
Open Scope R_scope.

(** [Stage] (raykernel.hpp), in its order. *)
Inductive stage := StFilter | StCompensated | StExpansion | StExact.

(** ** validation.cpp *)

(** [non_finite_reason]'s kind, from the bits: NaN when the significand bits are not all zero, else the
    sign of the infinity; nothing for a finite component. *)
Definition nonfinite_kind (x : float) : option Z :=
  match x with
  | B754_nan => Some 0%Z
  | B754_infinity false => Some 1%Z
  | B754_infinity true => Some 2%Z
  | _ => None
  end.

Fixpoint first_nonfinite (i : Z) (xs : list float) : option Z :=
  match xs with
  | [] => None
  | x :: rest => match nonfinite_kind x with
                 | Some k => Some (3 * i + k)%Z
                 | None => first_nonfinite (i + 1)%Z rest
                 end
  end.

(** [is_zero]: the bits shifted left by one are 0, i.e. ±0. *)
Definition is_zero_b (x : float) : bool := match x with B754_zero _ => true | _ => false end.
Definition vec_zero_b (v : Vec3B) : bool := (is_zero_b (vxb v) && is_zero_b (vyb v) && is_zero_b (vzb v))%bool.

Definition components (o d p n : Vec3B) : list float :=
  [vxb o; vyb o; vzb o; vxb d; vyb d; vzb d; vxb p; vyb p; vzb p; vxb n; vyb n; vzb n].

Definition code_zero_direction : Z := 36.
Definition code_zero_normal : Z := 37.

Definition validate_b (o d p n : Vec3B) : option Z :=
  match first_nonfinite 0 (components o d p n) with
  | Some c => Some c
  | None => if vec_zero_b d then Some code_zero_direction
            else if vec_zero_b n then Some code_zero_normal else None
  end.

(** ** ray_plane_cascade.cpp *)

(** RayPlaneCascade's zero flags: [(a_0 == 0 || n_0 == 0) && (a_1 == 0 || n_1 == 0) && (a_2 == 0 || n_2 == 0)]. *)
Definition zero_flag (a0 a1 a2 n0 n1 n2 : float) : bool :=
  ((feq a0 fzero || feq n0 fzero) && (feq a1 fzero || feq n1 fzero) && (feq a2 fzero || feq n2 fzero))%bool.

(** [enclosure_sign(e)] = static_cast<Sign>(enclosure_sign_lanes(e)). *)
Definition enclosure_sign_b (e : EnclosureB) : sign := sign_from_Z (enclosure_sign_lanes_b e).

(** The tail enclosure of an expansion (its first component, then the others). *)
Definition tail_b (l : list float) : EnclosureB :=
  match l with [] => expansion_tail_enclosure_b fzero [] | e0 :: rest => expansion_tail_enclosure_b e0 rest end.

Section Query.
Variables o d p n : Vec3B.

Definition den1_b : Dot3B := dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n).
Definition num1_b : Dot3B :=
  dot3_rounded_b (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o)) (vxb n) (vyb n) (vzb n).
Definition den_filter_b : sign :=
  dot3_filter_b den1_b Cpp.filter_den_relative (zero_flag (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)).
Definition num_filter_b : sign :=
  dot3_filter_b num1_b Cpp.filter_num_relative
    (zero_flag (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o)) (vxb n) (vyb n) (vzb n)).
Definition den2_b : EnclosureB := den_compensated_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n).
Definition num2_b : EnclosureB :=
  num_compensated_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n).
Definition den2r_b : EnclosureB := den_refined_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n).
Definition num2r_b : EnclosureB :=
  num_refined_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n).
Definition expansions_b : list float * list float * bool := ray_plane_expansions_b two_sum_b o d p n.

(** The signs after stage 2: stage 1's where certain, else the first level's, else the second level's. *)
Definition den_sign2_b : sign :=
  first_certain (first_certain den_filter_b (enclosure_sign_b den2_b)) (enclosure_sign_b den2r_b).
Definition num_sign2_b : sign :=
  first_certain (first_certain num_filter_b (enclosure_sign_b num2_b)) (enclosure_sign_b num2r_b).

(** [certified_signs]: (num, den, stage); at the exact stage the twin has no signs ([Uncertain]). *)
Definition certified_signs_b : sign * sign * stage :=
  if (is_certain den_filter_b && is_certain num_filter_b)%bool then (num_filter_b, den_filter_b, StFilter)
  else if (is_certain den_sign2_b && is_certain num_sign2_b)%bool then (num_sign2_b, den_sign2_b, StCompensated)
  else
    let '(en, ed, ex) := expansions_b in
    if (ex && is_certain (expansion_sign_b en) && is_certain (expansion_sign_b ed))%bool
    then (expansion_sign_b en, expansion_sign_b ed, StExpansion)
    else (Uncertain, Uncertain, StExact).

(** [certified_quotient]: t and the stage that rounded it, or [None] for the exact stage. *)
Definition certified_quotient_b : option (float * stage) :=
  let q2 := round_quotient_b num2_b (prepare_divisor_b den2_b) in
  if snd q2 then Some (fst q2, StCompensated) else
  let q2r := round_quotient_b num2r_b (prepare_divisor_b den2r_b) in
  if snd q2r then Some (fst q2r, StCompensated) else
  let '(en, ed, ex) := expansions_b in
  if ex then
    let q3 := round_quotient_b (tail_b en) (prepare_divisor_b (tail_b ed)) in
    if snd q3 then Some (fst q3, StExpansion) else None
  else None.

End Query.

(** The answer: invalid input (the code of the reason), the exact stage (no answer), or the relation, the
    stage that decided it and t: NaN (parallel, in-plane), +0 (num = 0), rounded by a stage, or by the
    exact stage (no t). *)
Inductive t_answer := TNaN | TZero | TRounded (t : float) (s : stage) | TExact.
Inductive cascade_answer := CInvalid (code : Z) | CExact | CDecided (r : relation) (s : stage) (t : t_answer).

(** [intersect_cascade], for a valid query. *)
Definition intersect_cascade_b (o d p n : Vec3B) : cascade_answer :=
  let '(ns, ds, st) := certified_signs_b o d p n in
  match st with
  | StExact => CExact
  | _ =>
    let r := relation_from_signs (sign_to_Z ns) (sign_to_Z ds) in
    match r with
    | Parallel | InPlane => CDecided r st TNaN
    | _ =>
      match ns with
      | Zero => CDecided Hit st TZero
      | _ => match certified_quotient_b o d p n with
             | Some (t, ts) => CDecided r st (TRounded t ts)
             | None => CDecided r st TExact
             end
      end
    end
  end.

(** [intersect_traced]: validation, then the cascade. *)
Definition intersect_traced_b (o d p n : Vec3B) : cascade_answer :=
  match validate_b o d p n with Some c => CInvalid c | None => intersect_cascade_b o d p n end.

(** [relation] past its fast path ([relation_rest]): validation, then [certified_signs]. *)
Definition relation_b (o d p n : Vec3B) : cascade_answer :=
  match validate_b o d p n with
  | Some c => CInvalid c
  | None => let '(ns, ds, st) := certified_signs_b o d p n in
            match st with
            | StExact => CExact
            | _ => CDecided (relation_from_signs (sign_to_Z ns) (sign_to_Z ds)) st TNaN
            end
  end.
