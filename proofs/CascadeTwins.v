(** * Twins of the call sites: which routine runs on which arguments with which constant.

    The routines of Twins.v, CompareTwins.v and Expansions.v as the cascade calls them (so that the
    differential runner also checks the call sites: a den constant passed for num, a wrong low part, a
    stage skipped):
    - [RayPlaneStages] (ray_plane_stages.hpp): [rps_den1], [rps_num1] (stage 1), [rps_den2], [rps_num2]
      (stage 2), [rps_den2r], [rps_num2r] (second level), [rps_expansions] (stage 3), the
      [*_trivially_zero] flags;
    - [certified_signs] (intersect_certified.cpp): [certified_signs_gen];
    - [compare_hit_distances] (raycast/nearest_hit.cpp): [hit_order_gen];
    - [FastQueryT::answer], [refined_answer], [filter_signs] (fast_path.hpp): [fast_answer_b],
      [refined_answer_b], [filter_signs_b] (the relation fields; t and t_certain belong to
      [round_quotient_decision], whose twin comes with its replacement, issue 13).

    Theorems, for every bit pattern of a validated query (finite components), with the proposed stage 3
    (Expansions.v: TwoSum for Fast2Sum, the checked sign): [certified_signs_sound] (the signs
    [certified_signs] returns are the exact ones) and, for every bit pattern of the inputs,
    [fast_answer_sound] (a certified relation of [FastQuery::answer] is the docs/contract.md §1
    relation of the exact query, and the input is finite with d ≠ 0 and n ≠ 0: the fast path needs no
    validation). *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Flocq Require IEEE754.Binary IEEE754.Bits.
From Raykernel Require Import Constants Model Filter Compensated RoundQuotient Classification CompareQuotients
  Cascade FloatCore ConstantsCpp Twins CompareTwins Expansions.
Import ListNotations.
Open Scope R_scope.

Record Vec3B := V3 { vxb : float; vyb : float; vzb : float }.
Definition v3R (v : Vec3B) : vec3 := Vec3 (B2R (vxb v)) (B2R (vyb v)) (B2R (vzb v)).
Definition fin3 (v : Vec3B) : Prop := fin (vxb v) = true /\ fin (vyb v) = true /\ fin (vzb v) = true.

(** [p - o] (ray_plane_stages.hpp) and [two_diff(p, o).hi] (fast_path.hpp) are the same operation. *)
Lemma fsub_two_diff_hi : forall x y, fsub x y = fst (two_diff_b x y).
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; unfold fsub, two_diff_b, two_sum_b, fadd, fneg; cbn;
    try reflexivity; destruct sx, sy; reflexivity.
Qed.

(** ** RayPlaneStages *)
Definition rps_den1 (d n : Vec3B) : Dot3B := dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n).
Definition rps_num1 (o p n : Vec3B) : Dot3B :=
  dot3_rounded_b (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o)) (vxb n) (vyb n) (vzb n).
Definition rps_den2 (d n : Vec3B) : EnclosureB :=
  compensated_dot3_b (vxb d) (vyb d) (vzb d) fzero fzero fzero (vxb n) (vyb n) (vzb n) (rps_den1 d n).
Definition rps_num2 (o p n : Vec3B) : EnclosureB :=
  compensated_dot3_b (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o))
    (snd (two_diff_b (vxb p) (vxb o))) (snd (two_diff_b (vyb p) (vyb o))) (snd (two_diff_b (vzb p) (vzb o)))
    (vxb n) (vyb n) (vzb n) (rps_num1 o p n).
Definition rps_den2r (d n : Vec3B) : EnclosureB :=
  compensated_dot3_refined_b (vxb d) (vyb d) (vzb d) fzero fzero fzero (vxb n) (vyb n) (vzb n) (rps_den1 d n).
Definition rps_num2r (o p n : Vec3B) : EnclosureB :=
  compensated_dot3_refined_b (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o))
    (snd (two_diff_b (vxb p) (vxb o))) (snd (two_diff_b (vyb p) (vyb o))) (snd (two_diff_b (vzb p) (vzb o)))
    (vxb n) (vyb n) (vzb n) (rps_num1 o p n).
Definition rps_expansions (fts : float -> float -> float * float) (o d p n : Vec3B) :=
  build_expansions_gen fts (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d) (vxb p) (vyb p) (vzb p)
    (vxb n) (vyb n) (vzb n).
Definition den_trivially_zero_b (d n : Vec3B) : bool :=
  ((feq (vxb d) fzero || feq (vxb n) fzero) && (feq (vyb d) fzero || feq (vyb n) fzero) &&
   (feq (vzb d) fzero || feq (vzb n) fzero))%bool.
Definition num_trivially_zero_b (o p n : Vec3B) : bool :=
  ((feq (vxb p) (vxb o) || feq (vxb n) fzero) && (feq (vyb p) (vyb o) || feq (vyb n) fzero) &&
   (feq (vzb p) (vzb o) || feq (vzb n) fzero))%bool.

(** [Stage]'s values: filter 0, compensated 1, expansion 2, exact 3. *)
Definition is_certain_b (s : sign) : bool := match s with Uncertain => false | _ => true end.
Definition enclosure_sign_b (e : EnclosureB) : sign := sign_from_Z (enclosure_sign_lanes_b e).

(** ** [certified_signs(query)]: (num, den, stage), or None when stage 3 is not exact (or, with the
    checked sign, not certain). *)
(** Stages 1 and 2 (both levels): (den, num, stage). *)
Definition stage12_signs (o d p n : Vec3B) : sign * sign * Z :=
  let den1 := dot3_filter_b (rps_den1 d n) Cpp.filter_den_relative (den_trivially_zero_b d n) in
  let num1 := dot3_filter_b (rps_num1 o p n) Cpp.filter_num_relative (num_trivially_zero_b o p n) in
  if (is_certain_b den1 && is_certain_b num1)%bool then (den1, num1, 0%Z) else
  let den_c := if is_certain_b den1 then den1 else enclosure_sign_b (rps_den2 d n) in
  let num_c := if is_certain_b num1 then num1 else enclosure_sign_b (rps_num2 o p n) in
  let den_r := if is_certain_b den_c then den_c else enclosure_sign_b (rps_den2r d n) in
  let num_r := if is_certain_b num_c then num_c else enclosure_sign_b (rps_num2r o p n) in
  (den_r, num_r, 1%Z).

Definition certified_signs_gen (fts : float -> float -> float * float) (sgn : list float -> sign)
  (o d p n : Vec3B) : option (sign * sign * Z) :=
  let '(den2, num2, stage2) := stage12_signs o d p n in
  if (is_certain_b den2 && is_certain_b num2)%bool then Some (num2, den2, stage2) else
  let '(num_e, den_e, ex) := rps_expansions fts o d p n in
  if ex then
    let sn := sgn num_e in let sd := sgn den_e in
    if (is_certain_b sn && is_certain_b sd)%bool then Some (sn, sd, 2%Z) else None
  else None.

Definition certified_signs_b := certified_signs_gen fast_two_sum_b sign_top.    (* the C++ as it is *)
Notation certified_signs_p := (certified_signs_gen two_sum_b expansion_sign_b). (* as proposed *)

(** ** [compare_hit_distances(a, b)]: (order, stage); stage 3 (exact) leaves the order to the exact
    stage, which has no twin. *)
Definition same_plane_bits (pa na pb nb : Vec3B) : bool :=
  (Z.eqb (to_bits (vxb pa)) (to_bits (vxb pb)) && Z.eqb (to_bits (vyb pa)) (to_bits (vyb pb)) &&
   Z.eqb (to_bits (vzb pa)) (to_bits (vzb pb)) && Z.eqb (to_bits (vxb na)) (to_bits (vxb nb)) &&
   Z.eqb (to_bits (vyb na)) (to_bits (vyb nb)) && Z.eqb (to_bits (vzb na)) (to_bits (vzb nb)))%bool.

Definition hit_order_gen (fts : float -> float -> float * float) (sgn : list float -> sign)
  (o d pa na pb nb : Vec3B) (num_a den_a num_b den_b : sign) : Z * Z :=
  let at_origin s := match s with Zero => true | _ => false end in
  if (at_origin num_a || at_origin num_b)%bool then (origin_order num_a num_b, 0%Z) else
  if same_plane_bits pa na pb nb then (0%Z, 0%Z) else
  let orientation := if Z.eqb (sign_to_Z den_a) (sign_to_Z den_b) then 1%Z else (-1)%Z in
  let d1 := compare_quotients_filter_b (filter_enclosure_b (rps_num1 o pa na) Cpp.filter_num_relative)
              (filter_enclosure_b (rps_den1 d na) Cpp.filter_den_relative)
              (filter_enclosure_b (rps_num1 o pb nb) Cpp.filter_num_relative)
              (filter_enclosure_b (rps_den1 d nb) Cpp.filter_den_relative) in
  if is_certain_b d1 then ((orientation * sign_to_Z d1)%Z, 0%Z) else
  let d2 := enclosure_sign_b (compare_quotients_compensated_b (rps_num2 o pa na) (rps_den2 d na)
              (rps_num2 o pb nb) (rps_den2 d nb)) in
  if is_certain_b d2 then ((orientation * sign_to_Z d2)%Z, 1%Z) else
  let '(num_ea, den_ea, xa) := rps_expansions fts o d pa na in
  let '(num_eb, den_eb, xb) := rps_expansions fts o d pb nb in
  let d3 := compare_quotients_expansion_gen fts sgn num_ea den_ea xa num_eb den_eb xb in
  if is_certain_b d3 then ((orientation * sign_to_Z d3)%Z, 2%Z) else (0%Z, 3%Z).

Definition hit_order_b := hit_order_gen fast_two_sum_b sign_top.

(** ** FastQueryT (fast_path.hpp): the relation fields of [answer()], [refined_answer()], and
    [filter_signs()]. *)
Definition fq_diff (p o : Vec3B) := (two_diff_b (vxb p) (vxb o), two_diff_b (vyb p) (vyb o), two_diff_b (vzb p) (vzb o)).

(** (behind, relation_by_compensated, relation_certain) *)
Definition fast_answer_b (o d p n : Vec3B) : bool * bool * bool :=
  let den_filter := dot3_filter_lanes_b (rps_den1 d n) Cpp.filter_den_relative in
  let num_filter := dot3_filter_lanes_b
    (dot3_rounded_b (fst (two_diff_b (vxb p) (vxb o))) (fst (two_diff_b (vyb p) (vyb o)))
       (fst (two_diff_b (vzb p) (vzb o))) (vxb n) (vyb n) (vzb n)) Cpp.filter_num_relative in
  let den2 := den_compensated_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n) in
  let num2 := num_compensated_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n) in
  let den_sign := if Z.eqb den_filter uncertain_lane then enclosure_sign_lanes_b den2 else den_filter in
  let num_sign := if Z.eqb num_filter uncertain_lane then enclosure_sign_lanes_b num2 else num_filter in
  (Z.ltb (num_sign * den_sign) 0,
   negb (negb (Z.eqb den_filter uncertain_lane) && negb (Z.eqb num_filter uncertain_lane)),
   negb (Z.eqb den_sign uncertain_lane) && negb (Z.eqb num_sign uncertain_lane))%bool.

Definition refined_answer_b (o d p n : Vec3B) : bool * bool * bool :=
  let den_sign := enclosure_sign_lanes_b (den_refined_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) in
  let num_sign := enclosure_sign_lanes_b
                    (num_refined_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n)) in
  (Z.ltb (num_sign * den_sign) 0, true,
   negb (Z.eqb den_sign uncertain_lane) && negb (Z.eqb num_sign uncertain_lane))%bool.

Definition filter_signs_b (o d p n : Vec3B) : sign * sign :=
  (dot3_filter_b (rps_den1 d n) Cpp.filter_den_relative false,
   dot3_filter_b (dot3_rounded_b (fst (two_diff_b (vxb p) (vxb o))) (fst (two_diff_b (vyb p) (vyb o)))
                    (fst (two_diff_b (vzb p) (vzb o))) (vxb n) (vyb n) (vzb n)) Cpp.filter_num_relative false).

(** ** Soundness of the call sites *)

Lemma feq_eq : forall x y, fin x = true -> fin y = true -> feq x y = true -> B2R x = B2R y.
Proof. intros x y Fx Fy E. rewrite feq_val in E by assumption. now apply Req_bool_true_iff in E. Qed.

Section Query.
Variables o d p n : Vec3B.
Hypotheses (Fo : fin3 o) (Fd : fin3 d) (Fp : fin3 p) (Fn : fin3 n).

Let N := ray_num (v3R o) (v3R p) (v3R n).
Let D := ray_den (v3R d) (v3R n).

Lemma N_components : N = (B2R (vxb p) - B2R (vxb o)) * B2R (vxb n) + (B2R (vyb p) - B2R (vyb o)) * B2R (vyb n) +
                         (B2R (vzb p) - B2R (vzb o)) * B2R (vzb n).
Proof. reflexivity. Qed.
Lemma D_components : D = B2R (vxb d) * B2R (vxb n) + B2R (vyb d) * B2R (vyb n) + B2R (vzb d) * B2R (vzb n).
Proof. reflexivity. Qed.

Lemma rps_num1_twin : rps_num1 o p n = dot3_rounded_b (fst (two_diff_b (vxb p) (vxb o)))
  (fst (two_diff_b (vyb p) (vyb o))) (fst (two_diff_b (vzb p) (vzb o))) (vxb n) (vyb n) (vzb n).
Proof. unfold rps_num1. now rewrite !fsub_two_diff_hi. Qed.

Lemma rps_num2_twin : rps_num2 o p n = num_compensated_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n).
Proof. unfold rps_num2, num_compensated_b. rewrite rps_num1_twin, !fsub_two_diff_hi. reflexivity. Qed.

Lemma rps_num2r_twin : rps_num2r o p n = num_refined_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n).
Proof. unfold rps_num2r, num_refined_b. rewrite rps_num1_twin, !fsub_two_diff_hi. reflexivity. Qed.

Lemma stage1_den_sound : certifies (dot3_filter_b (rps_den1 d n) Cpp.filter_den_relative (den_trivially_zero_b d n)) D.
Proof.
  unfold dot3_filter_b. destruct (den_trivially_zero_b d n) eqn:Z.
  - cbn. rewrite D_components. unfold den_trivially_zero_b in Z. destruct Fd as [F1 [F2 F3]]. destruct Fn as [G1 [G2 G3]].
    repeat rewrite andb_true_iff in Z. repeat rewrite orb_true_iff in Z.
    destruct Z as [[Z1 Z2] Z3].
    assert (T : forall a b, fin a = true -> fin b = true -> feq a fzero = true \/ feq b fzero = true -> B2R a * B2R b = 0).
    { intros a b Fa Fb [E|E]; apply feq_eq in E; auto; change (B2R fzero) with 0 in E; rewrite E; ring. }
    rewrite (T _ _ F1 G1 Z1), (T _ _ F2 G2 Z2), (T _ _ F3 G3 Z3). ring.
  - rewrite D_components. apply den_filter_twin_sound.
Qed.

Lemma stage1_num_sound : certifies (dot3_filter_b (rps_num1 o p n) Cpp.filter_num_relative (num_trivially_zero_b o p n)) N.
Proof.
  unfold dot3_filter_b. destruct (num_trivially_zero_b o p n) eqn:Z.
  - cbn. rewrite N_components. unfold num_trivially_zero_b in Z.
    destruct Fo as [O1 [O2 O3]]. destruct Fp as [F1 [F2 F3]]. destruct Fn as [G1 [G2 G3]].
    repeat rewrite andb_true_iff in Z. repeat rewrite orb_true_iff in Z.
    destruct Z as [[Z1 Z2] Z3].
    assert (T : forall a b c, fin a = true -> fin b = true -> fin c = true ->
               feq a b = true \/ feq c fzero = true -> (B2R a - B2R b) * B2R c = 0).
    { intros a b c Fa Fb Fc [E|E].
      - apply feq_eq in E; auto. rewrite E. ring.
      - apply feq_eq in E; auto. change (B2R fzero) with 0 in E. rewrite E. ring. }
    rewrite (T _ _ _ F1 O1 G1 Z1), (T _ _ _ F2 O2 G2 Z2), (T _ _ _ F3 O3 G3 Z3). ring.
  - rewrite N_components, rps_num1_twin. apply num_filter_twin_sound.
Qed.

(** [certified_signs] with the proposed stage 3: the signs it returns are the exact signs of num and den
    (and hence, [certified_relation], the §1 relation). *)
Theorem certified_signs_sound : forall ns ds st, certified_signs_p o d p n = Some (ns, ds, st) ->
  certifies ns N /\ ns <> Uncertain /\ certifies ds D /\ ds <> Uncertain.
Proof.
  intros ns ds st. unfold certified_signs_gen.
  pose proof stage1_den_sound as S1d. pose proof stage1_num_sound as S1n.
  destruct (stage12_signs o d p n) as [[den2 num2] stage2] eqn:E2. unfold stage12_signs in E2.
  set (den1 := dot3_filter_b (rps_den1 d n) Cpp.filter_den_relative (den_trivially_zero_b d n)) in *.
  set (num1 := dot3_filter_b (rps_num1 o p n) Cpp.filter_num_relative (num_trivially_zero_b o p n)) in *.
  assert (Cd : forall e, e = rps_den2 d n \/ e = rps_den2r d n -> certifies (enclosure_sign_b e) D).
  { intros e [->| ->]; unfold enclosure_sign_b; rewrite D_components.
    - apply den_compensated_twin_sound.
    - apply den_refined_twin_sound. }
  assert (Cn : forall e, e = rps_num2 o p n \/ e = rps_num2r o p n -> certifies (enclosure_sign_b e) N).
  { intros e [->| ->]; unfold enclosure_sign_b; rewrite N_components.
    - rewrite rps_num2_twin. apply num_compensated_twin_sound.
    - rewrite rps_num2r_twin. apply num_refined_twin_sound. }
  assert (Sel : forall (a b : sign) V, certifies a V -> certifies b V ->
            certifies (if is_certain_b a then a else b) V) by (intros [| | |] b V Ha Hb; assumption).
  assert (Unc : forall s, is_certain_b s = true -> s <> Uncertain) by (intros [| | |] H; easy).
  assert (C2 : certifies den2 D /\ certifies num2 N).
  { destruct (is_certain_b den1 && is_certain_b num1)%bool; injection E2 as <- <- _; split;
      repeat (apply Sel; [|]); auto. }
  destruct (is_certain_b den2 && is_certain_b num2)%bool eqn:C.
  - intros H. injection H as <- <- _. apply andb_true_iff in C. destruct C as [Ud Un].
    destruct C2. repeat split; auto.
  - pose proof (certified_signs_expansion_sound (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
                  (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as X.
    unfold rps_expansions.
    destruct (build_expansions_gen two_sum_b (vxb o) (vyb o) (vzb o) (vxb d) (vyb d) (vzb d)
                (vxb p) (vyb p) (vzb p) (vxb n) (vyb n) (vzb n)) as [[num_e den_e] ex].
    destruct ex; [|discriminate]. destruct (X eq_refl) as [Xn Xd].
    destruct (is_certain_b (expansion_sign_b num_e) && is_certain_b (expansion_sign_b den_e))%bool eqn:C3;
      [|discriminate].
    intros H. injection H as <- <- _. apply andb_true_iff in C3. destruct C3 as [Un Ud].
    rewrite N_components, D_components. repeat split; auto.
Qed.

End Query.

(** [FastQuery::answer], for every bit pattern of the inputs: a certain relation is the §1 relation of
    the exact query (hit or behind), and then every input is finite and d ≠ 0, n ≠ 0: this is why the fast
    path runs before any validation (docs/contract.md §1 asks for a validation error on such input; the
    fast path never answers it, the full cascade validates). *)
Theorem fast_answer_sound : forall o d p n,
  let '(behind, _, certain) := fast_answer_b o d p n in
  certain = true ->
  (if behind then Behind else Hit) = classify (v3R o) (v3R d) (v3R p) (v3R n) /\
  fin3 o /\ fin3 d /\ fin3 p /\ fin3 n /\ v3R d <> Vec3 0 0 0 /\ v3R n <> Vec3 0 0 0.
Proof.
  intros o d p n. unfold fast_answer_b, rps_den1.
  set (zd := dot3_filter_lanes_b (dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n))
               Cpp.filter_den_relative).
  set (zn := dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b (vxb p) (vxb o)))
               (fst (two_diff_b (vyb p) (vyb o))) (fst (two_diff_b (vzb p) (vzb o))) (vxb n) (vyb n) (vzb n))
               Cpp.filter_num_relative).
  set (ed := den_compensated_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)).
  set (en := num_compensated_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n)).
  destruct (den_filter_twin_sound (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as [Sd1 Fd1].
  destruct (num_filter_twin_sound (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n))
    as [Sn1 Fn1].
  destruct (den_compensated_twin_sound (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n)) as [Sd2 Fd2].
  destruct (num_compensated_twin_sound (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n))
    as [Sn2 Fn2].
  fold zd ed in Sd1, Fd1, Sd2, Fd2. fold zn en in Sn1, Fn1, Sn2, Fn2.
  (* the finiteness of a stage-2 radius gives finite inputs *)
  assert (Fd2' : enclosure_sign_lanes_b ed <> uncertain_lane -> fin3 d /\ fin3 n).
  { intros U. specialize (Fd2 U). unfold ed, den_compensated_b in Fd2.
    destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fd2) as [? [? [? [_ [_ [_ [? [? [? _]]]]]]]]].
    repeat split; assumption. }
  assert (Fn2' : enclosure_sign_lanes_b en <> uncertain_lane -> fin3 o /\ fin3 p /\ fin3 n).
  { intros U. specialize (Fn2 U). unfold en, num_compensated_b in Fn2. cbv zeta in Fn2.
    destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fn2) as [_ [_ [_ [A0 [A1 [A2 [? [? [? _]]]]]]]]].
    destruct (two_diff_b_parts _ _ A0) as [? [? _]]. destruct (two_diff_b_parts _ _ A1) as [? [? _]].
    destruct (two_diff_b_parts _ _ A2) as [? [? _]]. repeat split; assumption. }
  set (sd := if Z.eqb zd uncertain_lane then enclosure_sign_lanes_b ed else zd).
  set (sn := if Z.eqb zn uncertain_lane then enclosure_sign_lanes_b en else zn).
  intros C. apply andb_true_iff in C. destruct C as [Ud Un].
  apply negb_true_iff, Z.eqb_neq in Ud. apply negb_true_iff, Z.eqb_neq in Un.
  (* each sign is certain, ±1, and certifies the exact value *)
  assert (Ld : lane_sign sd /\ certifies (sign_from_Z sd) (ray_den (v3R d) (v3R n)) /\ fin3 d /\ fin3 n).
  { unfold sd. destruct (Z.eqb_spec zd uncertain_lane) as [E|E].
    - split; [unfold enclosure_sign_lanes_b; apply sign_lanes_range|]. split; [exact Sd2|]. apply Fd2'. exact Ud.
    - split; [unfold zd, zn, dot3_filter_lanes_b; apply sign_lanes_range|]. split; [exact Sd1|].
      destruct (Fd1 E) as [? [? [? [? [? ?]]]]]. repeat split; assumption. }
  assert (Ln : lane_sign sn /\ certifies (sign_from_Z sn) (ray_num (v3R o) (v3R p) (v3R n)) /\
               fin3 o /\ fin3 p /\ fin3 n).
  { unfold sn. destruct (Z.eqb_spec zn uncertain_lane) as [E|E].
    - split; [unfold enclosure_sign_lanes_b; apply sign_lanes_range|]. split; [exact Sn2|]. apply Fn2'. exact Un.
    - split; [unfold zd, zn, dot3_filter_lanes_b; apply sign_lanes_range|]. split; [exact Sn1|].
      destruct (Fn1 E) as [? [? [? [? [? [? [? [? ?]]]]]]]]. repeat split; assumption. }
  destruct Ld as [Ld [Cd [FD FN]]]. destruct Ln as [Ln [Cn [FO [FP _]]]].
  destruct (lanes_relation sn sd (v3R o) (v3R d) (v3R p) (v3R n) Ln Ld Un Ud Cn Cd) as [Rel [_ Nd]].
  destruct (den_nonzero_valid _ _ Nd) as [Vd Vn].
  exact (conj Rel (conj FO (conj FD (conj FP (conj FN (conj Vd Vn)))))).
Qed.
