(** * The twin of the ray–plane cascade's control flow (plane/ray_plane_cascade.{hpp,cpp},
    core/validation.{hpp,cpp}, plane/plane_api.cpp: [intersect_traced], [relation]).

    From the twelve input bit patterns, as the C++ does:
    - [validate_b]: validation.cpp's [validate(ray, plane)] — the first non-finite component in the order
      o, d, p, n (and whether it is NaN, +inf or −inf, decided from the bits), then a zero direction, then
      a zero normal — as a code: 3·i + k for component i (0 … 11) of kind k (0 NaN, 1 +inf, 2 −inf), 36 for
      "ray direction is the zero vector", 37 for "plane normal is the zero vector";
    - [certified_signs_b]: each sign through its stages (core/escalation.hpp, Escalation.v): stage 1 with the
      zero flags of RayPlaneCascade::den_filter/num_filter, then, while it is open, the first level of stage 2,
      then its second level, then stage 3 (the checked sign of its expansion, when the builder says exact);
      both certain: the signs and the latest stage either was asked of ([certified_signs_b_escalate]); else
      the exact stage, which the twin does not compute ([StExact], no answer);
    - [certified_quotient_b]: round_quotient on the first level's enclosures, on the second level's, on the
      stage-3 tail enclosures (when exact), then [round_quotient_near] (the boundaries of the candidate or a neighbour) on the expansions with the
      last candidate (den's checked sign ±1), else the exact stage ([None]);
    - [intersect_cascade_b]: parallel and in-plane (t = NaN), num = 0 (t = +0), the exact stage when the
      signs came from it, else t from [certified_quotient_b];
    - [intersect_traced_b], [relation_b]: validation first, then the cascade ([intersect_traced], and
      [relation] past its fast path, whose certified answers are the contract's: PlaneQueryTwins.v).

    The stage twins are PlaneTwins.v's, PlaneRefinedTwins.v's, PlaneQueryTwins.v's and Expansions.v's, called as
    plane/ray_plane_stages.hpp calls them; the differential runner compares the public entry points with these
    definitions bit for bit, the deciding stage included (routines [cascade_intersect],
    [cascade_relation]).  The theorem [cascade_twin_correct] (below) says what an answer before the exact
    stage means. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN Plus_error.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification QuotientRounding PlaneCascade FloatCore
  ConstantsCpp PlaneTwins Expansions PlaneQueryTwins PlaneRefinedTwins QuotientBoundary.
From Raykernel Require PlaneStageTwoFinite PlaneRefinedFinite.
From Raykernel Require Escalation.
Import ListNotations.
Open Scope R_scope.

(** [Stage] (raykernel/core.hpp), in its order: Escalation.v's (core/escalation.hpp), named here as before. *)
Notation stage := Escalation.stage.
Notation StFilter := Escalation.StFilter.
Notation StCompensated := Escalation.StCompensated.
Notation StExpansion := Escalation.StExpansion.
Notation StExact := Escalation.StExact.

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

(** Stage 3 of each sign: the checked sign of its expansion when the builder says exact, else uncertain. *)
Definition den_expansion_sign_b : sign := let '(_, ed, ex) := expansions_b in if ex then expansion_sign_b ed else Uncertain.
Definition num_expansion_sign_b : sign := let '(en, _, ex) := expansions_b in if ex then expansion_sign_b en else Uncertain.

(** The signs after stage 3: stage 2's where certain, else stage 3's. *)
Definition den_sign3_b : sign := first_certain den_sign2_b den_expansion_sign_b.
Definition num_sign3_b : sign := first_certain num_sign2_b num_expansion_sign_b.

(** [certified_signs]: (num, den, stage), each sign through its stages (core/escalation.hpp) and the stage the
    later of the two ([certified_signs_b_escalate], below); at the exact stage the twin has no signs
    ([Uncertain]). *)
Definition certified_signs_b : sign * sign * stage :=
  if (is_certain den_filter_b && is_certain num_filter_b)%bool then (num_filter_b, den_filter_b, StFilter)
  else if (is_certain den_sign2_b && is_certain num_sign2_b)%bool then (num_sign2_b, den_sign2_b, StCompensated)
  else if (is_certain den_sign3_b && is_certain num_sign3_b)%bool then (num_sign3_b, den_sign3_b, StExpansion)
  else (Uncertain, Uncertain, StExact).

(** The stages of each sign, as ray_plane_cascade.cpp's [certified_signs] hands them to
    [Escalation::sign]: the filter, stage 2's two levels (both counted as compensated), the expansion. *)
Definition den_steps_b : list (stage * sign) :=
  [(StFilter, den_filter_b); (StCompensated, enclosure_sign_b den2_b); (StCompensated, enclosure_sign_b den2r_b);
   (StExpansion, den_expansion_sign_b)].
Definition num_steps_b : list (stage * sign) :=
  [(StFilter, num_filter_b); (StCompensated, enclosure_sign_b num2_b); (StCompensated, enclosure_sign_b num2r_b);
   (StExpansion, num_expansion_sign_b)].

(** The chain of [certified_signs_b] is the escalation of each sign (den first, then num, one trace, from
    [StFilter]), for any answers of the stages. *)
Lemma two_signs_escalate : forall a1 a2 a3 a4 b1 b2 b3 b4 : sign,
  let a_2 := first_certain (first_certain a1 a2) a3 in let b_2 := first_certain (first_certain b1 b2) b3 in
  let a_3 := first_certain a_2 a4 in let b_3 := first_certain b_2 b4 in
  (if (is_certain a1 && is_certain b1)%bool then (b1, a1, StFilter)
   else if (is_certain a_2 && is_certain b_2)%bool then (b_2, a_2, StCompensated)
   else if (is_certain a_3 && is_certain b_3)%bool then (b_3, a_3, StExpansion)
   else (Uncertain, Uncertain, StExact)) =
  (let '(ds, t, _) := Escalation.escalate StFilter
                        [(StFilter, a1); (StCompensated, a2); (StCompensated, a3); (StExpansion, a4)] in
   let '(ns, t', _) := Escalation.escalate t
                        [(StFilter, b1); (StCompensated, b2); (StCompensated, b3); (StExpansion, b4)] in
   if (Escalation.sign_certain ds && Escalation.sign_certain ns)%bool then (ns, ds, t')
   else (Uncertain, Uncertain, StExact)).
Proof.
  intros a1 a2 a3 a4 b1 b2 b3 b4; cbv zeta.
  (* destruct each answer only while it still matters: 13 cases a sign *)
  destruct a1; cbn; [destruct b1; cbn; try reflexivity .. |].
  all: repeat (match goal with s : sign |- _ => lazymatch goal with |- context [s] => destruct s; cbn end end);
    reflexivity.
Qed.

(** ray_plane_cascade.cpp's [certified_signs]: the escalation of den through [den_steps_b], then of num through
    [num_steps_b] with the same trace, both signs when both are certain with the trace, else the exact stage. *)
Theorem certified_signs_b_escalate :
  certified_signs_b =
  let '(ds, t, _) := Escalation.escalate StFilter den_steps_b in
  let '(ns, t', _) := Escalation.escalate t num_steps_b in
  if (Escalation.sign_certain ds && Escalation.sign_certain ns)%bool then (ns, ds, t')
  else (Uncertain, Uncertain, StExact).
Proof. exact (two_signs_escalate _ _ _ _ _ _ _ _). Qed.

(** [certified_quotient]: t and the stage that rounded it, or [None] for the exact stage. *)
Definition certified_quotient_b : option (float * stage) :=
  let q2 := round_quotient_b num2_b (prepare_divisor_b den2_b) in
  if snd q2 then Some (fst q2, StCompensated) else
  let q2r := round_quotient_b num2r_b (prepare_divisor_b den2r_b) in
  if snd q2r then Some (fst q2r, StCompensated) else
  let '(en, ed, ex) := expansions_b in
  if ex then
    let q3 := round_quotient_b (tail_b en) (prepare_divisor_b (tail_b ed)) in
    if snd q3 then Some (fst q3, StExpansion) else
    (* the rounding boundaries of the candidate, in the expansions *)
    let ds := sign_to_Z (expansion_sign_b ed) in
    if (Z.eqb ds 1 || Z.eqb ds (-1))%bool then
      match round_quotient_near_b en ed ds (fst q3) with
      | Some t => Some (t, StExpansion)
      | None => None
      end
    else None
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

(** ** What an answer before the exact stage means

    A stage-2 sign is used only when it is certain, and a certain sign needs finite hi and lo (with them,
    a finite radius and the twin theorems give the enclosure).  That is proved for every bit pattern, for
    both levels: PlaneStageTwoFinite.v ([den_compensated_certain_finite], [num_compensated_certain_finite]) and
    PlaneRefinedFinite.v ([den_refined_certain_finite], [num_refined_certain_finite]).  (The stronger "a finite
    radius comes with finite hi and lo" is false for the first level of num: a TwoDiff low part can be NaN
    while m, hence the radius, is finite; PlaneStageTwoFinite.v.) *)

(** A certain enclosure sign is the exact sign, given the producer's "certain sign → finite parts". *)
Lemma enclosure_sign_b_certifies : forall (e : EnclosureB) V, nonneg (radiusb e) ->
  (enclosure_sign_lanes_b e <> uncertain_lane -> fin (hib e) = true /\ fin (lob e) = true) ->
  (fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true -> encloses (enc_R e) V) ->
  certifies (enclosure_sign_b e) V.
Proof.
  intros e V N F Enc. unfold enclosure_sign_b.
  destruct (Z.eq_dec (enclosure_sign_lanes_b e) uncertain_lane) as [U|U]; [rewrite U; exact I|].
  destruct (F U) as [Fh Fl].
  destruct (stage2_sign_twin e V N Fh Fl (fun Fr' => Enc Fh Fl Fr')) as [C _]. exact C.
Qed.

Lemma RN_diff_zero : forall a b, binary64 a -> binary64 b -> RN (a - b) = 0 -> a = b.
Proof.
  intros a b Ba Bb H.
  destruct (Rle_or_lt (Rabs (a - b)) (bpow radix2 (53 + -1074))) as [S|L].
  - assert (F : binary64 (a - b)).
    { unfold Rminus. apply FLT_format_plus_small; auto with typeclass_instances.
      now apply binary64_opp. }
    rewrite RN_binary64 in H by exact F. lra.
  - assert (P : bpow radix2 (53 + -1074) <= Rabs (RN (a - b))).
    { rewrite <- RN_abs. rewrite <- (RN_binary64 (bpow radix2 (53 + -1074))) by (apply binary64_bpow; lia).
      apply RN_le. lra. }
    rewrite H, Rabs_R0 in P. pose proof (bpow_gt_0 radix2 (53 + -1074)). lra.
Qed.

Lemma feq_zero_val : forall x, feq x fzero = true -> B2R x = 0.
Proof. intros x H. exact (proj2 (feq_zero x H)). Qed.

Section Signs.
Variables o d p n : Vec3B.
Let VN := ray_num (vec_R o) (vec_R p) (vec_R n).
Let VD := ray_den (vec_R d) (vec_R n).

Lemma VD_eq : VD = B2R (vxb d) * B2R (vxb n) + B2R (vyb d) * B2R (vyb n) + B2R (vzb d) * B2R (vzb n).
Proof. reflexivity. Qed.
Lemma VN_eq : VN = (B2R (vxb p) - B2R (vxb o)) * B2R (vxb n) + (B2R (vyb p) - B2R (vyb o)) * B2R (vyb n) +
                   (B2R (vzb p) - B2R (vzb o)) * B2R (vzb n).
Proof. reflexivity. Qed.

Lemma term_zero : forall a b, (feq a fzero || feq b fzero)%bool = true -> B2R a * B2R b = 0.
Proof.
  intros a b H. apply orb_true_iff in H. destruct H as [H|H]; rewrite (feq_zero_val _ H); ring.
Qed.

Lemma den_filter_b_certifies : certifies (den_filter_b d n) VD.
Proof.
  unfold den_filter_b, dot3_filter_b, zero_flag.
  destruct (((feq (vxb d) fzero || feq (vxb n) fzero) && (feq (vyb d) fzero || feq (vyb n) fzero)) &&
            (feq (vzb d) fzero || feq (vzb n) fzero))%bool eqn:Z.
  - cbn. apply andb_true_iff in Z. destruct Z as [Z Z2]. apply andb_true_iff in Z. destruct Z as [Z0 Z1].
    rewrite VD_eq, (term_zero _ _ Z0), (term_zero _ _ Z1), (term_zero _ _ Z2). ring.
  - rewrite VD_eq. exact (proj1 (den_filter_twin_sound (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n))).
Qed.

Lemma diff_term_zero : forall a c b, (feq (fsub a c) fzero || feq b fzero)%bool = true ->
  (B2R a - B2R c) * B2R b = 0.
Proof.
  intros a c b H. apply orb_true_iff in H. destruct H as [H|H]; [|rewrite (feq_zero_val _ H); ring].
  destruct (feq_zero _ H) as [F V]. destruct (fsub_inv _ _ F) as [_ [_ E]]. rewrite E in V.
  rewrite (RN_diff_zero _ _ (binary64_B2R a) (binary64_B2R c) V). ring.
Qed.

Lemma num_filter_b_certifies : certifies (num_filter_b o p n) VN.
Proof.
  unfold num_filter_b, dot3_filter_b, zero_flag.
  match goal with |- certifies (if ?c then _ else _) _ => destruct c eqn:Z end.
  - cbn. apply andb_true_iff in Z. destruct Z as [Z Z2]. apply andb_true_iff in Z. destruct Z as [Z0 Z1].
    rewrite VN_eq, (diff_term_zero _ _ _ Z0), (diff_term_zero _ _ _ Z1), (diff_term_zero _ _ _ Z2). ring.
  - rewrite VN_eq. unfold num1_b. rewrite !fsub_two_diff_hi.
    exact (proj1 (num_filter_twin_sound (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n))).
Qed.

Lemma den2_nonneg : nonneg (radiusb (den2_b d n)).
Proof. apply den_radius_nonneg. Qed.

Lemma den2_encloses : fin (hib (den2_b d n)) = true -> fin (lob (den2_b d n)) = true ->
  fin (radiusb (den2_b d n)) = true -> encloses (enc_R (den2_b d n)) VD.
Proof.
  intros Fh Fl Fr. unfold den2_b in *.
  destruct (compensated_dot3_exact_twin _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [? [? [? E]]]]]].
  unfold den_compensated_b. rewrite E, VD_eq. apply compensated_den_enclosure; apply binary64_B2R.
Qed.

Lemma num2_encloses : fin (hib (num2_b o p n)) = true -> fin (lob (num2_b o p n)) = true ->
  fin (radiusb (num2_b o p n)) = true -> encloses (enc_R (num2_b o p n)) VN.
Proof.
  intros Fh Fl Fr. unfold num2_b in *.
  destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [A0 [A1 [A2 [? [? [? [_ [_ E]]]]]]]]]]].
  destruct (two_diff_b_parts _ _ A0) as [? [? [X0 Y0]]]. destruct (two_diff_b_parts _ _ A1) as [? [? [X1 Y1]]].
  destruct (two_diff_b_parts _ _ A2) as [? [? [X2 Y2]]].
  unfold num_compensated_b. cbv zeta. rewrite E, X0, X1, X2, Y0, Y1, Y2, VN_eq.
  apply compensated_num_enclosure; apply binary64_B2R.
Qed.

Lemma den2r_encloses : fin (hib (den2r_b d n)) = true -> fin (lob (den2r_b d n)) = true ->
  fin (radiusb (den2r_b d n)) = true -> encloses (enc_R (den2r_b d n)) VD.
Proof.
  intros Fh Fl Fr. rewrite VD_eq.
  exact (proj2 (proj2 (proj2 (proj2 (proj2 (proj2 (proj2 (den_refined_twin_encloses _ _ _ _ _ _ Fh Fl Fr)))))))).
Qed.

Lemma num2r_encloses : fin (hib (num2r_b o p n)) = true -> fin (lob (num2r_b o p n)) = true ->
  fin (radiusb (num2r_b o p n)) = true -> encloses (enc_R (num2r_b o p n)) VN.
Proof.
  intros Fh Fl Fr. rewrite VN_eq.
  destruct (num_refined_twin_encloses _ _ _ _ _ _ _ _ _ Fh Fl Fr) as [_ [_ [_ [_ [_ [_ [_ [_ [_ En]]]]]]]]].
  exact En.
Qed.

Lemma den_sign2_certifies : certifies (den_sign2_b d n) VD.
Proof.
  pose proof (PlaneStageTwoFinite.den_compensated_certain_finite (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as Fd.
  pose proof (PlaneRefinedFinite.den_refined_certain_finite (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as Fdr.
  unfold den_sign2_b. apply first_certain_sound; [apply first_certain_sound|].
  - apply den_filter_b_certifies.
  - exact (enclosure_sign_b_certifies (den2_b d n) VD den2_nonneg Fd den2_encloses).
  - exact (enclosure_sign_b_certifies (den2r_b d n) VD (den_refined_radius_nonneg _ _ _ _ _ _) Fdr den2r_encloses).
Qed.

Lemma num_sign2_certifies : certifies (num_sign2_b o p n) VN.
Proof.
  pose proof (PlaneStageTwoFinite.num_compensated_certain_finite (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o)
                (vxb n) (vyb n) (vzb n)) as Fn.
  pose proof (PlaneRefinedFinite.num_refined_certain_finite (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o)
                (vxb n) (vyb n) (vzb n)) as Fnr.
  unfold num_sign2_b. apply first_certain_sound; [apply first_certain_sound|].
  - apply num_filter_b_certifies.
  - exact (enclosure_sign_b_certifies (num2_b o p n) VN (compensated_radius_nonneg _ _ _ _ _ _ _ _ _) Fn num2_encloses).
  - exact (enclosure_sign_b_certifies (num2r_b o p n) VN (num_refined_radius_nonneg _ _ _ _ _ _ _ _ _) Fnr
             num2r_encloses).
Qed.

Lemma den_expansion_sign_certifies : certifies (den_expansion_sign_b o d p n) VD.
Proof.
  unfold den_expansion_sign_b, expansions_b, ray_plane_expansions_b.
  pose proof (certified_signs_expansion_sound (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
                (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as S.
  destruct (build_expansions_gen two_sum_b (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
              (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as [[en ed] ex].
  destruct ex; [rewrite VD_eq; exact (proj2 (S eq_refl)) | exact I].
Qed.

Lemma num_expansion_sign_certifies : certifies (num_expansion_sign_b o d p n) VN.
Proof.
  unfold num_expansion_sign_b, expansions_b, ray_plane_expansions_b.
  pose proof (certified_signs_expansion_sound (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
                (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as S.
  destruct (build_expansions_gen two_sum_b (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
              (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as [[en ed] ex].
  destruct ex; [rewrite VN_eq; exact (proj1 (S eq_refl)) | exact I].
Qed.

Lemma den_sign3_certifies : certifies (den_sign3_b o d p n) VD.
Proof. apply first_certain_sound; [apply den_sign2_certifies | apply den_expansion_sign_certifies]. Qed.

Lemma num_sign3_certifies : certifies (num_sign3_b o d p n) VN.
Proof. apply first_certain_sound; [apply num_sign2_certifies | apply num_expansion_sign_certifies]. Qed.

(** [certified_signs_b]: before the exact stage, both signs are certain and exact. *)
Theorem certified_signs_twin_sound : forall ns ds st, certified_signs_b o d p n = (ns, ds, st) -> st <> StExact ->
  ns <> Uncertain /\ ds <> Uncertain /\ certifies ns VN /\ certifies ds VD.
Proof.
  intros ns ds st E X. unfold certified_signs_b in E.
  destruct (is_certain (den_filter_b d n) && is_certain (num_filter_b o p n))%bool eqn:C1.
  - injection E as <- <- <-. apply andb_true_iff in C1. destruct C1 as [Cd Cn].
    repeat split; [destruct (num_filter_b o p n); discriminate | destruct (den_filter_b d n); discriminate
                  | apply num_filter_b_certifies | apply den_filter_b_certifies].
  - destruct (is_certain (den_sign2_b d n) && is_certain (num_sign2_b o p n))%bool eqn:C2.
    + injection E as <- <- <-. apply andb_true_iff in C2. destruct C2 as [Cd Cn].
      repeat split; [destruct (num_sign2_b o p n); discriminate | destruct (den_sign2_b d n); discriminate
                    | apply num_sign2_certifies | apply den_sign2_certifies].
    + destruct (is_certain (den_sign3_b o d p n) && is_certain (num_sign3_b o d p n))%bool eqn:C3.
      * injection E as <- <- <-. apply andb_true_iff in C3. destruct C3 as [Cd Cn].
        repeat split; [destruct (num_sign3_b o d p n); discriminate | destruct (den_sign3_b o d p n); discriminate
                      | apply num_sign3_certifies | apply den_sign3_certifies].
      * injection E as _ _ <-. contradiction.
Qed.

End Signs.

(** ** t: [certified_quotient_b] *)

Lemma tail_loop_b_nonneg : forall rest q lo mag, nonneg mag ->
  nonneg (let '(_, _, m) := tail_loop_b q lo mag rest in m).
Proof.
  induction rest as [|e rest IH]; intros q lo mag N; [exact N|].
  cbn [tail_loop_b]. apply IH. apply fadd_nonneg; [exact N | apply fabs_nonneg].
Qed.

Lemma tail_b_nonneg : forall l, nonneg (radiusb (tail_b l)).
Proof.
  intros l. assert (G : forall e0 rest, nonneg (radiusb (expansion_tail_enclosure_b e0 rest))).
  { intros e0 rest. unfold expansion_tail_enclosure_b.
    pose proof (tail_loop_b_nonneg rest e0 fzero fzero fzero_nonneg) as N.
    destruct (tail_loop_b e0 fzero fzero rest) as [[q lo] m]. cbn [radiusb].
    apply fadd_nonneg; [apply fmul_nonneg; [exact N | const_nonneg] | const_nonneg]. }
  destruct l; apply G.
Qed.

Lemma tail_b_encloses : forall l, (length l <= 32)%nat ->
  fin (hib (tail_b l)) = true -> fin (lob (tail_b l)) = true -> fin (radiusb (tail_b l)) = true ->
  encloses (enc_R (tail_b l)) (sumR l).
Proof.
  intros [|e0 rest] L Fh _ Fr; cbn [tail_b] in *.
  - destruct (expansion_tail_enclosure_twin fzero [] Fh Fr) as [_ [_ E]]. rewrite E.
    replace (sumR []) with (B2R fzero + sum_list (map B2R [])) by (cbn; ring).
    apply tail_sum_enclosure; [apply binary64_B2R | constructor | cbn; unfold tail_sum_max_terms; lia].
  - destruct (expansion_tail_enclosure_twin e0 rest Fh Fr) as [_ [_ E]]. rewrite E.
    change (sumR (e0 :: rest)) with (B2R e0 + sum_list (map B2R rest)).
    apply tail_sum_enclosure; [apply binary64_B2R | | rewrite map_length; unfold tail_sum_max_terms; cbn in L; lia].
    apply Forall_forall. intros x Hx. apply in_map_iff in Hx. destruct Hx as [y [<- _]]. apply binary64_B2R.
Qed.

Lemma some_pair_fst : forall (A B : Type) (a c : A) (b e : B), Some (a, b) = Some (c, e) -> c = a.
Proof. intros A B a c b e H. injection H as H1 _. symmetry. exact H1. Qed.

Section Quotient.
Variables o d p n : Vec3B.
Let VN := ray_num (vec_R o) (vec_R p) (vec_R n).
Let VD := ray_den (vec_R d) (vec_R n).

(** A t that [certified_quotient] returns before the exact stage is RN(num/den), den ≠ 0 (no hypothesis:
    round_quotient's certificate implies finite enclosures, [round_quotient_twin]). *)
Theorem certified_quotient_twin_sound : forall q ts, certified_quotient_b o d p n = Some (q, ts) ->
  VD <> 0 /\ fin q = true /\ B2R q = RN (VN / VD).
Proof.
  intros q ts. unfold certified_quotient_b.
  destruct (snd (round_quotient_b (num2_b o p n) (prepare_divisor_b (den2_b d n)))) eqn:C1.
  - intros E. apply some_pair_fst in E. subst q.
    exact (round_quotient_twin_sound (num2_b o p n) (den2_b d n) VN VD (compensated_radius_nonneg _ _ _ _ _ _ _ _ _)
             (den2_nonneg d n) (num2_encloses o p n) (den2_encloses d n) C1).
  - destruct (snd (round_quotient_b (num2r_b o p n) (prepare_divisor_b (den2r_b d n)))) eqn:C2.
    + intros E. apply some_pair_fst in E. subst q.
      exact (round_quotient_twin_sound (num2r_b o p n) (den2r_b d n) VN VD (num_refined_radius_nonneg _ _ _ _ _ _ _ _ _)
               (den_refined_radius_nonneg _ _ _ _ _ _) (num2r_encloses o p n) (den2r_encloses d n) C2).
    + unfold expansions_b, ray_plane_expansions_b.
      pose proof (build_expansions_exact (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
                    (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as X.
      pose proof (length_build_expansions two_sum_b (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
                    (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as L.
      destruct (build_expansions_gen two_sum_b (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
                  (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as [[en ed] ex].
      destruct ex; [|discriminate].
      destruct (X eq_refl) as [_ [_ [Sd Sn]]]. destruct L as [Ln Ld].
      destruct (snd (round_quotient_b (tail_b en) (prepare_divisor_b (tail_b ed)))) eqn:C3.
      * intros E. apply some_pair_fst in E. subst q.
        apply (round_quotient_twin_sound (tail_b en) (tail_b ed) VN VD (tail_b_nonneg _) (tail_b_nonneg _));
          [ | | exact C3].
        -- intros Fh Fl Fr. unfold VN. rewrite (VN_eq o p n), <- Sn. apply tail_b_encloses; [lia | assumption ..].
        -- intros Fh Fl Fr. unfold VD. rewrite (VD_eq d n), <- Sd. apply tail_b_encloses; [lia | assumption ..].
      * (* the rounding boundaries: den's checked sign is ±1, hence den's sign (expansion_sign_sound) *)
        destruct (X eq_refl) as [_ [Fd _]].
        assert (Cd := expansion_sign_sound ed Fd ltac:(lia)).
        assert (VDe : VD = sumR ed) by (unfold VD; rewrite (VD_eq d n), <- Sd; reflexivity).
        assert (VNe : VN = sumR en) by (unfold VN; rewrite (VN_eq o p n), <- Sn; reflexivity).
        destruct (expansion_sign_b ed) eqn:Sg; cbn [sign_to_Z] in *;
          try (cbv [Z.eqb orb]; intros H; discriminate H); cbv [Z.eqb orb].
        -- destruct (round_quotient_near_b en ed (-1) _) as [r|] eqn:B; [|discriminate].
           intros E. injection E as <- _. cbn [certifies] in Cd.
           destruct (round_quotient_near_sound en ed (-1) _ r ltac:(lia) ltac:(lia)
                       ltac:(right; split; [reflexivity | exact Cd]) B) as [Fr Rr].
           rewrite VDe, VNe. repeat split; [lra | exact Fr | exact Rr].
        -- destruct (round_quotient_near_b en ed 1 _) as [r|] eqn:B; [|discriminate].
           intros E. injection E as <- _. cbn [certifies] in Cd.
           destruct (round_quotient_near_sound en ed 1 _ r ltac:(lia) ltac:(lia)
                       ltac:(left; split; [reflexivity | exact Cd]) B) as [Fr Rr].
           rewrite VDe, VNe. repeat split; [lra | exact Fr | exact Rr].
Qed.

End Quotient.

(** ** Validation *)

Lemma nonfinite_kind_none : forall x, nonfinite_kind x = None -> fin x = true.
Proof. intros [s|[|]| |s m e H] K; try reflexivity; discriminate. Qed.

Lemma first_nonfinite_none : forall xs i, first_nonfinite i xs = None -> Forall (fun x => fin x = true) xs.
Proof.
  induction xs as [|x xs IH]; intros i H; [constructor|].
  cbn [first_nonfinite] in H. destruct (nonfinite_kind x) eqn:K; [discriminate|].
  constructor; [now apply nonfinite_kind_none | exact (IH _ H)].
Qed.

Lemma zero_float : forall x, fin x = true -> B2R x = 0 -> is_zero_b x = true.
Proof.
  intros [s|s| |s m e H] F V; try reflexivity; try discriminate.
  exfalso. cbn in V. apply eq_0_F2R in V. destruct s; discriminate.
Qed.

Lemma vec_nonzero : forall v, vec_fin v -> vec_zero_b v = false -> vec_R v <> zero3.
Proof.
  intros [x y z] [Fx [Fy Fz]] Z E. unfold vec_R, zero3 in E. cbn [vxb vyb vzb] in *.
  injection E as Ex Ey Ez. unfold vec_zero_b in Z. cbn [vxb vyb vzb] in Z.
  rewrite (zero_float _ Fx Ex), (zero_float _ Fy Ey), (zero_float _ Fz Ez) in Z. discriminate.
Qed.

(** Validation passes exactly when every component is finite and neither d nor n is the zero vector
    (the "only if" direction; the runner compares the reasons with validation.cpp's). *)
Theorem validate_b_none : forall o d p n, validate_b o d p n = None ->
  vec_fin o /\ vec_fin d /\ vec_fin p /\ vec_fin n /\ vec_R d <> zero3 /\ vec_R n <> zero3.
Proof.
  intros o d p n V. unfold validate_b in V.
  destruct (first_nonfinite 0 (components o d p n)) eqn:F; [discriminate|].
  apply first_nonfinite_none in F. unfold components in F.
  repeat (apply Forall_cons_iff in F; destruct F as [? F]).
  assert (Fo : vec_fin o) by (repeat split; assumption). assert (Fd : vec_fin d) by (repeat split; assumption).
  assert (Fp : vec_fin p) by (repeat split; assumption). assert (Fn : vec_fin n) by (repeat split; assumption).
  destruct (vec_zero_b d) eqn:Zd; [discriminate|]. destruct (vec_zero_b n) eqn:Zn; [discriminate|].
  repeat split; try assumption; now apply vec_nonzero.
Qed.

(** ** The theorem: [intersect_traced_b]

    For every bit pattern of the twelve inputs: an answer before the exact stage comes from valid input
    (every component finite, d ≠ 0, n ≠ 0), its relation is docs/contract.md §1's for the exact values
    ([classify]), and its t is RN(num/den) when a stage rounded it (den ≠ 0), +0 when num = 0 exactly;
    invalid input is reported by [validate_b]'s code, which the runner compares with the C++'s reason.
    No hypothesis: a certain stage-2 sign comes with finite hi and lo for every bit pattern (above). *)
Theorem cascade_twin_correct : forall o d p n : Vec3B,
  match intersect_traced_b o d p n with
  | CInvalid c => validate_b o d p n = Some c
  | CExact => True
  | CDecided r s t =>
      s <> StExact /\ vec_fin o /\ vec_fin d /\ vec_fin p /\ vec_fin n /\ vec_R d <> zero3 /\ vec_R n <> zero3 /\
      r = classify (vec_R o) (vec_R d) (vec_R p) (vec_R n) /\
      match t with
      | TRounded q _ => ray_den (vec_R d) (vec_R n) <> 0 /\ fin q = true /\
          B2R q = RN (ray_num (vec_R o) (vec_R p) (vec_R n) / ray_den (vec_R d) (vec_R n))
      | TZero => ray_num (vec_R o) (vec_R p) (vec_R n) = 0
      | TNaN => r = Parallel \/ r = InPlane
      | TExact => True
      end
  end.
Proof.
  intros o d p n. unfold intersect_traced_b.
  destruct (validate_b o d p n) as [c|] eqn:V; [reflexivity|].
  destruct (validate_b_none o d p n V) as [Fo [Fd [Fp [Fn [Zd Zn]]]]].
  unfold intersect_cascade_b.
  destruct (certified_signs_b o d p n) as [[ns ds] st] eqn:S.
  pose proof (certified_signs_twin_sound o d p n ns ds st S) as G.
  destruct st; cbv beta iota zeta; [| | | exact I].
  all: specialize (G ltac:(discriminate)); destruct G as [Un [Ud [Cn Cd]]];
    pose proof (certified_relation ns ds (vec_R o) (vec_R d) (vec_R p) (vec_R n) Cn Un Cd Ud) as R;
    destruct (relation_from_signs (sign_to_Z ns) (sign_to_Z ds)) eqn:Rel; cbv beta iota.
  Ltac common Fo Fd Fp Fn Zd Zn :=
    split; [discriminate|]; split; [exact Fo|]; split; [exact Fd|]; split; [exact Fp|]; split; [exact Fn|];
    split; [exact Zd|]; split; [exact Zn|]; split.
  (* parallel, in-plane: t is NaN *)
  all: lazymatch goal with
       | |- _ /\ _ => common Fo Fd Fp Fn Zd Zn; [exact R | first [left; reflexivity | right; reflexivity]]
       | |- _ => idtac end.
  (* hit, behind: num = 0 (t = +0), else certified_quotient *)
  all: destruct ns; try contradiction; cbv beta iota.
  all: lazymatch goal with
       | |- _ /\ _ => common Fo Fd Fp Fn Zd Zn;
                      [lazymatch type of Rel with
                       | _ = Behind => exfalso; destruct ds; try contradiction; cbn in Rel; discriminate
                       | _ => exact R end
                      | exact Cn]
       | |- _ => idtac end.
  all: destruct (certified_quotient_b o d p n) as [[q ts]|] eqn:Q; cbv beta iota.
  all: common Fo Fd Fp Fn Zd Zn; [exact R | try exact I].
  all: exact (certified_quotient_twin_sound o d p n q ts Q).
Qed.

(** ** Validation, the other direction: valid input is never rejected, invalid input always gets a code *)

Lemma first_nonfinite_fin : forall xs i, Forall (fun x => fin x = true) xs -> first_nonfinite i xs = None.
Proof.
  induction xs as [|x xs IH]; intros i F; [reflexivity|].
  apply Forall_cons_iff in F. destruct F as [Fx F]. cbn [first_nonfinite].
  destruct x as [s|s| |s m e B]; try discriminate; exact (IH _ F).
Qed.

Lemma vec_zero_b_R : forall v, vec_zero_b v = true -> vec_R v = zero3.
Proof.
  intros [[s0| | |] [s1| | |] [s2| | |]]; unfold vec_zero_b; cbn [vxb vyb vzb is_zero_b andb]; try discriminate.
  intros _. reflexivity.
Qed.

(** Every component finite, d ≠ 0 and n ≠ 0: validation passes (the converse of [validate_b_none]). *)
Theorem validate_b_valid : forall o d p n : Vec3B,
  vec_fin o -> vec_fin d -> vec_fin p -> vec_fin n -> vec_R d <> zero3 -> vec_R n <> zero3 ->
  validate_b o d p n = None.
Proof.
  intros o d p n [? [? ?]] [? [? ?]] [? [? ?]] [? [? ?]] Zd Zn. unfold validate_b.
  rewrite first_nonfinite_fin by (unfold components; repeat constructor; assumption).
  destruct (vec_zero_b d) eqn:D; [exfalso; exact (Zd (vec_zero_b_R d D))|].
  destruct (vec_zero_b n) eqn:N; [exfalso; exact (Zn (vec_zero_b_R n N))|]. reflexivity.
Qed.

(** Invalid input — a non-finite component (NaN, ±inf), d = 0 or n = 0 — always gets a code. *)
Theorem validate_b_some : forall o d p n : Vec3B,
  ~ vec_fin o \/ ~ vec_fin d \/ ~ vec_fin p \/ ~ vec_fin n \/ vec_R d = zero3 \/ vec_R n = zero3 ->
  exists c, validate_b o d p n = Some c.
Proof.
  intros o d p n H. destruct (validate_b o d p n) as [c|] eqn:V; [now exists c|].
  destruct (validate_b_none o d p n V) as [Fo [Fd [Fp [Fn [Zd Zn]]]]]. exfalso. tauto.
Qed.

(** ** [intersect]'s step between its fast path and the cascade (plane/plane_api.cpp, [intersection_rest])

    For a valid query the fast path left open — straight after stage 1 when stage 1 left a sign open, or after
    stage 2's first level when that did not round t (both signs then stage 1's) — the signs of den and num
    from stage 1's filter where certain, else from stage 2's second level ([filter_or_refined_signs]:
    [den_refined_sign_b], [num_refined_sign_b]; the filter per lane as [fast_stage1] computes it, which is
    [den1_b], [num1_b]'s filter bit for bit, with [first_certain_lanes_b_eq] and [fsub_two_diff_hi] for the
    forms); when both are certain, t rounded on stage 2's second level ([den2r_b], [num2r_b]:
    plane/ray_plane_stages.hpp's [refined_pair] from the fast path's stage 1, the cascade's second level bit
    for bit, tests/plane_stages_test.cpp), and the answer when that rounding is certain: t and
    behind = (num_sign · den_sign < 0).  Otherwise ([None]) the cascade runs. *)
Definition den_refined_sign_b (d n : Vec3B) : Z :=
  first_certain_lanes (dot3_filter_lanes_b (dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n))
                         Cpp.filter_den_relative)
    (enclosure_sign_lanes_b (den2r_b d n)).
Definition num_refined_sign_b (o p n : Vec3B) : Z :=
  first_certain_lanes (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b (vxb p) (vxb o)))
                         (fst (two_diff_b (vyb p) (vyb o))) (fst (two_diff_b (vzb p) (vzb o))) (vxb n) (vyb n) (vzb n))
                         Cpp.filter_num_relative)
    (enclosure_sign_lanes_b (num2r_b o p n)).

(** The step from any two lane signs and any two enclosures: t and behind when both signs are certain and
    round_quotient certifies t. *)
Definition second_level_from (ds ns : Z) (num den : EnclosureB) : option (float * bool) :=
  if (certain_lane ds && certain_lane ns)%bool then
    if snd (round_quotient_b num (prepare_divisor_b den))
    then Some (fst (round_quotient_b num (prepare_divisor_b den)), Z.ltb (ns * ds) 0)
    else None
  else None.

Definition second_level_b (o d p n : Vec3B) : option (float * bool) :=
  second_level_from (den_refined_sign_b d n) (num_refined_sign_b o p n) (num2r_b o p n) (den2r_b d n).

(** The step's meaning for any sound signs and enclosures (every fact abstract: no computation on floats). *)
Lemma second_level_from_correct : forall (ds ns : Z) (num den : EnclosureB) (o d p n : Vec3B) t behind,
  vec_fin o -> vec_fin d -> vec_fin p -> vec_fin n -> vec_R d <> zero3 -> vec_R n <> zero3 ->
  lane_sign ds -> certifies (sign_from_Z ds) (ray_den (vec_R d) (vec_R n)) ->
  lane_sign ns -> certifies (sign_from_Z ns) (ray_num (vec_R o) (vec_R p) (vec_R n)) ->
  nonneg (radiusb num) -> nonneg (radiusb den) ->
  (fin (hib num) = true -> fin (lob num) = true -> fin (radiusb num) = true ->
   encloses (enc_R num) (ray_num (vec_R o) (vec_R p) (vec_R n))) ->
  (fin (hib den) = true -> fin (lob den) = true -> fin (radiusb den) = true ->
   encloses (enc_R den) (ray_den (vec_R d) (vec_R n))) ->
  second_level_from ds ns num den = Some (t, behind) -> fast_answer_means o d p n t behind.
Proof.
  intros ds ns num den o d p n t behind Fo Fd Fp Fn Zd Zn Ld Sd Ln Sn Nn Nd En Ed S.
  unfold second_level_from in S.
  destruct (certain_lane ds && certain_lane ns)%bool eqn:C; [|discriminate S].
  apply andb_prop in C. destruct C as [Cd Cn].
  pose proof (round_quotient_twin_sound num den _ _ Nn Nd En Ed) as Q.
  destruct (round_quotient_b num (prepare_divisor_b den)) as [q c] eqn:Eq.
  cbn [fst snd] in S, Q. destruct c; [|discriminate S].
  injection S as <- <-.
  destruct (lanes_relation ns ds _ _ _ _ Ln Ld (certain_lane_true _ Cn) (certain_lane_true _ Cd) Sn Sd)
    as [Rel [Zn' Zd']].
  destruct (Q eq_refl) as [_ [Ft Vt]].
  exact (conj Fo (conj Fd (conj Fp (conj Fn (conj Rel (conj Zn' (conj Zd' (conj Zd (conj Zn (conj Ft Vt)))))))))).
Qed.

Lemma den2r_b_eq : forall d n : Vec3B,
  den2r_b d n = den_refined_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n).
Proof. reflexivity. Qed.
Lemma num2r_b_eq : forall o p n : Vec3B,
  num2r_b o p n = num_refined_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n).
Proof. reflexivity. Qed.

(** Each of the step's signs is a lane sign and, when certain, the exact sign (every bit pattern: the second
    level's by PlaneRefinedFinite.v's total theorems).  Each fact is used in the form its lemma states it, and
    forms are changed only by rewriting with lemmas over abstract terms ([VD_eq], [den2r_b_eq], …): a
    conversion between two forms of a concrete term can make Coq's kernel compute on the floats. *)
Lemma den_refined_sign_sound : forall d n : Vec3B,
  lane_sign (den_refined_sign_b d n) /\ certifies (sign_from_Z (den_refined_sign_b d n)) (ray_den (vec_R d) (vec_R n)).
Proof.
  intros d n.
  destruct (den_filter_twin_sound (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as [Sf _].
  rewrite <- (VD_eq d n) in Sf.
  pose proof (PlaneRefinedFinite.den_refined_twin_sound_total (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as Se.
  cbv zeta in Se. rewrite <- (VD_eq d n), <- den2r_b_eq in Se.
  assert (L1 : lane_sign (dot3_filter_lanes_b (dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n))
                            Cpp.filter_den_relative)) by (unfold dot3_filter_lanes_b; apply sign_lanes_range).
  assert (L2 : lane_sign (enclosure_sign_lanes_b (den2r_b d n))) by (unfold enclosure_sign_lanes_b; apply sign_lanes_range).
  exact (first_certain_lanes_sound _ _ _ L1 L2 Sf Se).
Qed.

Lemma num_refined_sign_sound : forall o p n : Vec3B,
  lane_sign (num_refined_sign_b o p n) /\
  certifies (sign_from_Z (num_refined_sign_b o p n)) (ray_num (vec_R o) (vec_R p) (vec_R n)).
Proof.
  intros o p n.
  destruct (num_filter_twin_sound (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n)) as [Sf _].
  rewrite <- (VN_eq o p n) in Sf.
  pose proof (PlaneRefinedFinite.num_refined_twin_sound_total (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o)
                (vxb n) (vyb n) (vzb n)) as Se.
  cbv zeta in Se. rewrite <- (VN_eq o p n), <- num2r_b_eq in Se.
  assert (L1 : lane_sign (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b (vxb p) (vxb o)))
                            (fst (two_diff_b (vyb p) (vyb o))) (fst (two_diff_b (vzb p) (vzb o))) (vxb n) (vyb n) (vzb n))
                            Cpp.filter_num_relative))
    by (unfold dot3_filter_lanes_b; apply sign_lanes_range).
  assert (L2 : lane_sign (enclosure_sign_lanes_b (num2r_b o p n))) by (unfold enclosure_sign_lanes_b; apply sign_lanes_range).
  exact (first_certain_lanes_sound _ _ _ L1 L2 Sf Se).
Qed.

(** Its answer means what a certain fast answer means ([fast_answer_means]: the relation of
    docs/contract.md §1, num ≠ 0, den ≠ 0, and t finite and RN(num/den)), for every bit pattern that
    passes validation. *)
Lemma second_level_twin_means : forall (o d p n : Vec3B) (t : float) (behind : bool),
  validate_b o d p n = None -> second_level_b o d p n = Some (t, behind) -> fast_answer_means o d p n t behind.
Proof.
  intros o d p n t behind V S.
  destruct (validate_b_none o d p n V) as [Fo [Fd [Fp [Fn [Zd Zn]]]]].
  destruct (den_refined_sign_sound d n) as [Ld Sd]. destruct (num_refined_sign_sound o p n) as [Ln Sn].
  exact (second_level_from_correct _ _ _ _ o d p n t behind Fo Fd Fp Fn Zd Zn Ld Sd Ln Sn
           (num_refined_radius_nonneg _ _ _ _ _ _ _ _ _) (den_refined_radius_nonneg _ _ _ _ _ _)
           (num2r_encloses o p n) (den2r_encloses d n) S).
Qed.

(** And the step answers only for valid input ([validate_b] = None), for every bit pattern: a certain rounding
    has finite enclosures ([round_quotient_twin]), whose radii read stage 1's magnitudes, which are finite only
    when every operand is ([magnitude_operands_fin]; num's operands p_i ⊖ o_i only when p_i and o_i are), and a
    certain sign of den is a nonzero den, so d ≠ 0 and n ≠ 0.  This is why [intersection_rest] validates only
    after the step, for the cascade. *)
Lemma magnitude_operands_fin : forall a0 a1 a2 b0 b1 b2,
  fin (magnitudeb (dot3_rounded_b a0 a1 a2 b0 b1 b2)) = true ->
  fin a0 = true /\ fin a1 = true /\ fin a2 = true /\ fin b0 = true /\ fin b1 = true /\ fin b2 = true.
Proof.
  intros a0 a1 a2 b0 b1 b2 H. unfold dot3_rounded_b in H. cbn [magnitudeb] in H.
  destruct (fadd_fin _ _ H) as [H1 H2]. destruct (fadd_fin _ _ H1) as [H3 H4].
  rewrite fabs_fin in H2, H3, H4.
  destruct (fmul_fin _ _ H2). destruct (fmul_fin _ _ H3). destruct (fmul_fin _ _ H4).
  tauto.
Qed.

Lemma refined_radius_magnitude_fin : forall a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1,
  fin (radiusb (compensated_dot3_refined_b a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1)) = true ->
  fin (magnitudeb stage1) = true.
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1 Fr.
  destruct (PlaneRefinedFinite.refined_shape a0 a1 a2 al0 al1 al2 b0 b1 b2 stage1) as [x [y [tail [_ [_ Er]]]]].
  rewrite Er in Fr.
  destruct (fadd_fin _ _ Fr) as [F1 _]. destruct (fadd_fin _ _ F1) as [F2 _]. exact (proj2 (fmul_fin _ _ F2)).
Qed.

Lemma den2r_fin : forall d n : Vec3B, fin (radiusb (den2r_b d n)) = true -> vec_fin d /\ vec_fin n.
Proof.
  intros d n F. rewrite den2r_b_eq in F. unfold den_refined_b in F.
  pose proof (magnitude_operands_fin _ _ _ _ _ _ (refined_radius_magnitude_fin _ _ _ _ _ _ _ _ _ _ F)) as M.
  unfold vec_fin. tauto.
Qed.

Lemma num2r_fin : forall o p n : Vec3B, fin (radiusb (num2r_b o p n)) = true -> vec_fin o /\ vec_fin p /\ vec_fin n.
Proof.
  intros o p n F. rewrite num2r_b_eq in F. unfold num_refined_b in F. cbv zeta in F.
  destruct (magnitude_operands_fin _ _ _ _ _ _ (refined_radius_magnitude_fin _ _ _ _ _ _ _ _ _ _ F))
    as [A0 [A1 [A2 [N0 [N1 N2]]]]].
  rewrite <- fsub_two_diff_hi in A0, A1, A2.
  destruct (fsub_fin _ _ A0). destruct (fsub_fin _ _ A1). destruct (fsub_fin _ _ A2).
  unfold vec_fin. tauto.
Qed.

Lemma second_level_from_valid : forall (ds ns : Z) (num den : EnclosureB) (o d p n : Vec3B) t behind,
  lane_sign ds -> certifies (sign_from_Z ds) (ray_den (vec_R d) (vec_R n)) ->
  nonneg (radiusb num) -> nonneg (radiusb den) ->
  (fin (radiusb num) = true -> vec_fin o /\ vec_fin p /\ vec_fin n) ->
  (fin (radiusb den) = true -> vec_fin d /\ vec_fin n) ->
  second_level_from ds ns num den = Some (t, behind) ->
  vec_fin o /\ vec_fin d /\ vec_fin p /\ vec_fin n /\ vec_R d <> zero3 /\ vec_R n <> zero3.
Proof.
  intros ds ns num den o d p n t behind Ld Sd Nn Nd Fnum Fden S.
  unfold second_level_from in S.
  destruct (certain_lane ds && certain_lane ns)%bool eqn:C; [|discriminate S].
  apply andb_prop in C. destruct C as [Cd _].
  destruct (snd (round_quotient_b num (prepare_divisor_b den))) eqn:Ct; [|discriminate S].
  destruct (round_quotient_twin num den Nn Nd Ct) as [_ [_ [Fr [_ [_ [Fr' _]]]]]].
  destruct (Fnum Fr) as [Fo [Fp Fn]]. destruct (Fden Fr') as [Fd _].
  destruct (lane_sign_exact _ _ Ld (certain_lane_true _ Cd) Sd) as [_ [_ D]].
  destruct (den_nonzero_valid _ _ D) as [Zd Zn].
  tauto.
Qed.

Theorem second_level_twin_valid : forall (o d p n : Vec3B) (t : float) (behind : bool),
  second_level_b o d p n = Some (t, behind) -> validate_b o d p n = None.
Proof.
  intros o d p n t behind S.
  destruct (den_refined_sign_sound d n) as [Ld Sd].
  destruct (second_level_from_valid _ _ _ _ o d p n t behind Ld Sd
              (num_refined_radius_nonneg _ _ _ _ _ _ _ _ _) (den_refined_radius_nonneg _ _ _ _ _ _)
              (num2r_fin o p n) (den2r_fin d n) S) as [Fo [Fd [Fp [Fn [Zd Zn]]]]].
  exact (validate_b_valid o d p n Fo Fd Fp Fn Zd Zn).
Qed.

(** The step, for every bit pattern of the twelve inputs: when it answers, the input is valid and the answer
    means what a certain fast answer means. *)
Theorem second_level_twin_correct : forall (o d p n : Vec3B) (t : float) (behind : bool),
  second_level_b o d p n = Some (t, behind) -> validate_b o d p n = None /\ fast_answer_means o d p n t behind.
Proof.
  intros o d p n t behind S.
  pose proof (second_level_twin_valid o d p n t behind S) as V.
  exact (conj V (second_level_twin_means o d p n t behind V S)).
Qed.

(** ** The theorem: [relation_b] ([relation] past its fast path)

    For every bit pattern of the twelve inputs: an answer before the exact stage comes from valid input
    (every component finite, d ≠ 0, n ≠ 0), carries no t, and its relation is docs/contract.md §1's for the
    exact values: [classify] = [relation_from_signs] of the exact signs of num and den, whose meaning is
    PlaneClassification.v's [relation_correct]; invalid input is reported by [validate_b]'s code.  No hypothesis
    (as [cascade_twin_correct]). *)
Theorem relation_twin_correct : forall o d p n : Vec3B,
  match relation_b o d p n with
  | CInvalid c => validate_b o d p n = Some c
  | CExact => True
  | CDecided r s t =>
      s <> StExact /\ t = TNaN /\ vec_fin o /\ vec_fin d /\ vec_fin p /\ vec_fin n /\ vec_R d <> zero3 /\
      vec_R n <> zero3 /\ r = classify (vec_R o) (vec_R d) (vec_R p) (vec_R n)
  end.
Proof.
  intros o d p n. unfold relation_b.
  destruct (validate_b o d p n) as [c|] eqn:V; [reflexivity|].
  destruct (validate_b_none o d p n V) as [Fo [Fd [Fp [Fn [Zd Zn]]]]].
  destruct (certified_signs_b o d p n) as [[ns ds] st] eqn:S.
  pose proof (certified_signs_twin_sound o d p n ns ds st S) as G.
  destruct st; cbv beta iota; [| | | exact I].
  all: destruct (G ltac:(discriminate)) as [Un [Ud [Cn Cd]]];
    split; [discriminate|]; split; [reflexivity|]; do 6 (split; [assumption|]);
    exact (certified_relation ns ds (vec_R o) (vec_R d) (vec_R p) (vec_R n) Cn Un Cd Ud).
Qed.

(** ** A mutation that cannot be observed: stage 2 never contradicts a certain filter

    [certified_signs] keeps a certain stage-1 sign and asks stage 2 only for the open ones.  Overwriting a
    certain stage-1 sign by a stage-2 sign whenever the latter is certain (either level, den or num) changes
    nothing: both are sound for the same exact value, and two certain sound signs of one real are equal.
    (Overwriting it by an uncertain stage-2 sign would change the answer; that a certain filter implies a
    certain first level is not proved: proofs/README.md, "What remains".) *)
Lemma certain_signs_agree : forall s1 s2 x, certifies s1 x -> s1 <> Uncertain -> certifies s2 x ->
  s2 <> Uncertain -> s1 = s2.
Proof. intros [| | |] [| | |] x C1 U1 C2 U2; cbn in *; try reflexivity; try congruence; lra. Qed.

Lemma is_certain_not_uncertain : forall s, is_certain s = true -> s <> Uncertain.
Proof. intros [| | |] C; discriminate. Qed.

Theorem den_stage2_agrees_with_filter : forall d n : Vec3B,
  is_certain (den_filter_b d n) = true ->
  (is_certain (enclosure_sign_b (den2_b d n)) = true -> enclosure_sign_b (den2_b d n) = den_filter_b d n) /\
  (is_certain (enclosure_sign_b (den2r_b d n)) = true -> enclosure_sign_b (den2r_b d n) = den_filter_b d n).
Proof.
  intros d n C1. pose proof (den_filter_b_certifies d n) as S1.
  pose proof (PlaneStageTwoFinite.den_compensated_certain_finite (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as Fd.
  pose proof (PlaneRefinedFinite.den_refined_certain_finite (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as Fdr.
  split; intros C2; (eapply certain_signs_agree; [| apply is_certain_not_uncertain; exact C2 | exact S1
                                                 | apply is_certain_not_uncertain; exact C1]).
  - exact (enclosure_sign_b_certifies (den2_b d n) _ (den2_nonneg d n) Fd (den2_encloses d n)).
  - exact (enclosure_sign_b_certifies (den2r_b d n) _ (den_refined_radius_nonneg _ _ _ _ _ _) Fdr
             (den2r_encloses d n)).
Qed.

Theorem num_stage2_agrees_with_filter : forall o p n : Vec3B,
  is_certain (num_filter_b o p n) = true ->
  (is_certain (enclosure_sign_b (num2_b o p n)) = true -> enclosure_sign_b (num2_b o p n) = num_filter_b o p n) /\
  (is_certain (enclosure_sign_b (num2r_b o p n)) = true -> enclosure_sign_b (num2r_b o p n) = num_filter_b o p n).
Proof.
  intros o p n C1. pose proof (num_filter_b_certifies o p n) as S1.
  pose proof (PlaneStageTwoFinite.num_compensated_certain_finite (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o)
                (vxb n) (vyb n) (vzb n)) as Fn.
  pose proof (PlaneRefinedFinite.num_refined_certain_finite (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o)
                (vxb n) (vyb n) (vzb n)) as Fnr.
  split; intros C2; (eapply certain_signs_agree; [| apply is_certain_not_uncertain; exact C2 | exact S1
                                                 | apply is_certain_not_uncertain; exact C1]).
  - exact (enclosure_sign_b_certifies (num2_b o p n) _ (compensated_radius_nonneg _ _ _ _ _ _ _ _ _) Fn
             (num2_encloses o p n)).
  - exact (enclosure_sign_b_certifies (num2r_b o p n) _ (num_refined_radius_nonneg _ _ _ _ _ _ _ _ _) Fnr
             (num2r_encloses o p n)).
Qed.
