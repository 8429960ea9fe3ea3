(** * The pieces as intersect_certified.cpp, fast_path.hpp and nearest_hit.cpp combine them.

    - [certified_relation]: signs certified by any stage give the relation of docs/contract.md §1;
    - [filter_relation_correct]: the stage-1 relation, end to end from the binary64 inputs;
    - [compensated_signs_correct]: stage 2's sign decisions ([enclosure_sign] of the compensated
      enclosures); [refined_signs_correct]: the same for the second level ([compensated_dot3_refined]);
    - [compensated_t_correct], [refined_t_correct]: the t that round_quotient returns from the
      enclosures of either level;
    - [cascade_signs_correct], [cascade_quotient_correct]: [certified_signs] through stage 2 (both
      levels) and [certified_quotient] through stage 2, as intersect_certified.cpp chains them;
    - the fast path (fast_path.hpp): [fast_answer_correct] ([FastQuery::answer], the batch API per lane),
      [refined_answer_correct] ([FastQuery::refined_answer]) and [intersect_fast_correct]
      ([intersect_certified] before it falls back to the full cascade): a certified answer is the §1
      relation and t = RN(num/den), and the input has d ≠ 0 and n ≠ 0 ([fast_path_den_valid]: a nonzero
      den sign from stage 1 or either level of stage 2 implies both), which is why the fast path needs no
      validation (the finiteness half is IEEE propagation: proofs/README.md, "The fast path");
    - [expansion_t_correct]: the t that round_quotient returns from the expansion enclosures, given
      that the expansions sum exactly to num and den (Shewchuk's theorems, cited, not proved here);
    - [compare_hit_distances_filter_correct], [compare_hit_distances_compensated_correct]: the order of
      two hits' t that nearest_hit.cpp's [compare_hit_distances] returns from stage 1 or stage 2 of the
      comparison (compare_quotients.hpp) is the order of the exact t = num/den. *)

From Coq Require Import Reals Lra Lia List ZArith.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model Filter Compensated RoundQuotient Classification
  CompareQuotients.
Open Scope R_scope.

(** [first_certain(first, second)] (sign.hpp): [first] where it is certain, else [second]; and its lane
    form [first_certain_lanes] on the integers of [sign_lanes]. *)
Definition first_certain (first second : sign) : sign :=
  match first with Uncertain => second | _ => first end.

Definition first_certain_lanes (first second : Z) : Z :=
  if Z.eqb first uncertain_lane then second else first.

Definition is_certain (s : sign) : bool := match s with Uncertain => false | _ => true end.

Lemma first_certain_sound : forall s1 s2 x, certifies s1 x -> certifies s2 x -> certifies (first_certain s1 s2) x.
Proof. intros [| | |] s2 x H1 H2; simpl; assumption. Qed.

Lemma first_certain_lanes_sound : forall z1 z2 x,
  lane_sign z1 -> lane_sign z2 -> certifies (sign_from_Z z1) x -> certifies (sign_from_Z z2) x ->
  lane_sign (first_certain_lanes z1 z2) /\ certifies (sign_from_Z (first_certain_lanes z1 z2)) x.
Proof.
  intros z1 z2 x L1 L2 C1 C2. unfold first_certain_lanes.
  destruct (Z.eqb_spec z1 uncertain_lane); split; assumption.
Qed.

(** A certain lane sign of a real x is its exact sign, ±1, so x ≠ 0. *)
Lemma lane_sign_exact : forall z x, lane_sign z -> z <> uncertain_lane -> certifies (sign_from_Z z) x ->
  z = sign_of x /\ z <> 0%Z /\ x <> 0.
Proof.
  intros z x L U C. unfold sign_of.
  destruct (lane_sign_certain z L U) as [[-> E]|[-> E]]; rewrite E in C; simpl in C.
  - rewrite Rcompare_Lt by exact C. repeat split; [discriminate | lra].
  - rewrite Rcompare_Gt by exact C. repeat split; [discriminate | lra].
Qed.

(** [num_sign * den_sign < 0 ? behind : hit] (fast_path.hpp, [FastQuery::FilterSigns::relation]), for two
    certain lane signs, is the §1 relation, and num, den ≠ 0. *)
Lemma lanes_relation : forall zn zd o d p n,
  lane_sign zn -> lane_sign zd -> zn <> uncertain_lane -> zd <> uncertain_lane ->
  certifies (sign_from_Z zn) (ray_num o p n) -> certifies (sign_from_Z zd) (ray_den d n) ->
  (if Z.ltb (zn * zd) 0 then Behind else Hit) = classify o d p n /\ ray_num o p n <> 0 /\ ray_den d n <> 0.
Proof.
  intros zn zd o d p n Ln Ld Un Ud Cn Cd.
  destruct (lane_sign_exact zn _ Ln Un Cn) as [En [Nn Xn]].
  destruct (lane_sign_exact zd _ Ld Ud Cd) as [Ed [Nd Xd]].
  split; [|split; assumption].
  unfold classify, relation_from_signs. rewrite <- En, <- Ed.
  destruct (Z.eqb_spec zd 0); [contradiction | reflexivity].
Qed.

(** The zero vector, which validation rejects as a direction or a normal. *)
Definition zero3 : vec3 := Vec3 0 0 0.

Lemma den_nonzero_valid : forall d n, ray_den d n <> 0 -> d <> zero3 /\ n <> zero3.
Proof.
  intros d n H. split; intros E; apply H; unfold ray_den, dot; rewrite E; simpl; ring.
Qed.

Theorem certified_relation : forall (num_sign den_sign : sign) (o d p n : vec3),
  certifies num_sign (ray_num o p n) -> num_sign <> Uncertain ->
  certifies den_sign (ray_den d n) -> den_sign <> Uncertain ->
  relation_from_signs (sign_to_Z num_sign) (sign_to_Z den_sign) = classify o d p n.
Proof.
  intros ns ds o d p n Cn Un Cd Ud. unfold classify.
  now rewrite (certified_sign ns _ Cn Un), (certified_sign ds _ Cd Ud).
Qed.

Section Query.
Variables ox oy oz dx dy dz px py pz nx ny nz : R.
Hypotheses (Box : binary64 ox) (Boy : binary64 oy) (Boz : binary64 oz)
           (Bdx : binary64 dx) (Bdy : binary64 dy) (Bdz : binary64 dz)
           (Bpx : binary64 px) (Bpy : binary64 py) (Bpz : binary64 pz)
           (Bnx : binary64 nx) (Bny : binary64 ny) (Bnz : binary64 nz).

Let o := Vec3 ox oy oz.
Let d := Vec3 dx dy dz.
Let p := Vec3 px py pz.
Let n := Vec3 nx ny nz.

Lemma ray_num_components : ray_num o p n = (px - ox) * nx + (py - oy) * ny + (pz - oz) * nz.
Proof. reflexivity. Qed.

Lemma ray_den_components : ray_den d n = dx * nx + dy * ny + dz * nz.
Proof. reflexivity. Qed.

(** The two calls of stage 2 in intersect_certified.cpp. *)
Definition num_enclosure : Enclosure :=
  compensated_dot3 (RN (px - ox)) (RN (py - oy)) (RN (pz - oz))
    (snd (two_diff px ox)) (snd (two_diff py oy)) (snd (two_diff pz oz)) nx ny nz.
Definition den_enclosure : Enclosure := compensated_dot3 dx dy dz 0 0 0 nx ny nz.

Theorem filter_relation_correct :
  let ns := num_filter px py pz ox oy oz nx ny nz in
  let ds := den_filter dx dy dz nx ny nz in
  ns <> Uncertain -> ds <> Uncertain ->
  relation_from_signs (sign_to_Z ns) (sign_to_Z ds) = classify o d p n.
Proof.
  intros ns ds Un Ud. apply certified_relation; try assumption.
  - rewrite ray_num_components. now apply num_filter_sound.
  - rewrite ray_den_components. now apply den_filter_sound.
Qed.

Theorem compensated_signs_correct :
  certifies (enclosure_sign num_enclosure) (ray_num o p n) /\
  certifies (enclosure_sign den_enclosure) (ray_den d n).
Proof.
  split; apply enclosure_sign_sound; try apply binary64_RN.
  - rewrite ray_num_components. now apply compensated_num_enclosure.
  - rewrite ray_den_components. now apply compensated_den_enclosure.
Qed.

Theorem compensated_t_correct : forall t,
  round_quotient num_enclosure den_enclosure = Some t ->
  ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n).
Proof.
  intros t H. eapply round_quotient_sound; [..|exact H];
    try (unfold num_enclosure, den_enclosure, compensated_dot3; cbn [hi lo radius];
         first [apply binary64_two_sum_hi | apply binary64_RN]).
  - rewrite ray_num_components. now apply compensated_num_enclosure.
  - rewrite ray_den_components. now apply compensated_den_enclosure.
Qed.

(** ** The second level of stage 2, as compute_refined (ray_plane_stages.hpp) and
    FastQuery::refined_answer (fast_path.hpp) call it. *)
Definition refined_num_enclosure : Enclosure :=
  compensated_dot3_refined (RN (px - ox)) (RN (py - oy)) (RN (pz - oz))
    (snd (two_diff px ox)) (snd (two_diff py oy)) (snd (two_diff pz oz)) nx ny nz.
Definition refined_den_enclosure : Enclosure := compensated_dot3_refined dx dy dz 0 0 0 nx ny nz.

Lemma enclosures_correct :
  encloses num_enclosure (ray_num o p n) /\ encloses den_enclosure (ray_den d n) /\
  encloses refined_num_enclosure (ray_num o p n) /\ encloses refined_den_enclosure (ray_den d n).
Proof.
  rewrite ray_num_components, ray_den_components. repeat split.
  - now apply compensated_num_enclosure.
  - now apply compensated_den_enclosure.
  - now apply compensated_num_refined_enclosure.
  - now apply compensated_den_refined_enclosure.
Qed.

Lemma enclosures_binary64 : forall e, e = num_enclosure \/ e = den_enclosure \/
  e = refined_num_enclosure \/ e = refined_den_enclosure ->
  binary64 (hi e) /\ binary64 (lo e) /\ binary64 (radius e).
Proof.
  intros e [ -> | [ -> | [ -> | -> ] ] ]; repeat split;
    unfold num_enclosure, den_enclosure, refined_num_enclosure, refined_den_enclosure,
      compensated_dot3, compensated_dot3_refined; cbn [hi lo radius];
    first [apply binary64_two_sum_hi | apply binary64_RN].
Qed.

Lemma enclosure_sign_correct : forall e V, e = num_enclosure \/ e = den_enclosure \/
  e = refined_num_enclosure \/ e = refined_den_enclosure -> encloses e V ->
  lane_sign (enclosure_sign_lanes e) /\ certifies (sign_from_Z (enclosure_sign_lanes e)) V.
Proof.
  intros e V He Enc. destruct (enclosures_binary64 e He) as [B1 [B2 B3]].
  split; [apply enclosure_sign_lanes_range | now apply enclosure_sign_sound].
Qed.

Theorem refined_signs_correct :
  certifies (enclosure_sign refined_num_enclosure) (ray_num o p n) /\
  certifies (enclosure_sign refined_den_enclosure) (ray_den d n).
Proof.
  destruct enclosures_correct as [_ [_ [Hn Hd]]].
  split; apply enclosure_sign_correct; auto.
Qed.

Lemma round_quotient_decision_correct : forall nE dE,
  (nE = num_enclosure /\ dE = den_enclosure) \/ (nE = refined_num_enclosure /\ dE = refined_den_enclosure) ->
  snd (round_quotient_decision nE dE) = true ->
  ray_den d n <> 0 /\ fst (round_quotient_decision nE dE) = RN (ray_num o p n / ray_den d n).
Proof.
  intros nE dE Hs T. destruct enclosures_correct as [En [Ed [Ern Erd]]].
  destruct Hs as [ [ -> -> ] | [ -> -> ] ].
  - destruct (enclosures_binary64 num_enclosure ltac:(auto)) as [B1 [B2 B3]].
    destruct (enclosures_binary64 den_enclosure ltac:(auto)) as [B4 [B5 B6]].
    now apply round_quotient_decision_sound.
  - destruct (enclosures_binary64 refined_num_enclosure ltac:(auto)) as [B1 [B2 B3]].
    destruct (enclosures_binary64 refined_den_enclosure ltac:(auto)) as [B4 [B5 B6]].
    now apply round_quotient_decision_sound.
Qed.

Theorem refined_t_correct : forall t,
  round_quotient refined_num_enclosure refined_den_enclosure = Some t ->
  ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n).
Proof.
  intros t H. unfold round_quotient in H.
  pose proof (round_quotient_decision_correct refined_num_enclosure refined_den_enclosure
                ltac:(auto)) as R.
  destruct (round_quotient_decision refined_num_enclosure refined_den_enclosure) as [q [|]];
    [|discriminate]. injection H as <-. now apply R.
Qed.

(** ** The full cascade through stage 2 (intersect_certified.cpp, [certified_signs] and
    [certified_quotient]): each sign is stage 1's where certain, else the first level's, else the second
    level's; t is round_quotient on the first level's enclosures, else on the second level's.  Stage 3
    (expansions, cited) and stage 4 (exact) come after. *)
Definition cascade_num_sign : sign :=
  first_certain (num_filter px py pz ox oy oz nx ny nz)
    (first_certain (enclosure_sign num_enclosure) (enclosure_sign refined_num_enclosure)).
Definition cascade_den_sign : sign :=
  first_certain (den_filter dx dy dz nx ny nz)
    (first_certain (enclosure_sign den_enclosure) (enclosure_sign refined_den_enclosure)).

Theorem cascade_signs_correct :
  certifies cascade_num_sign (ray_num o p n) /\ certifies cascade_den_sign (ray_den d n) /\
  (cascade_num_sign <> Uncertain -> cascade_den_sign <> Uncertain ->
   relation_from_signs (sign_to_Z cascade_num_sign) (sign_to_Z cascade_den_sign) = classify o d p n).
Proof.
  destruct compensated_signs_correct as [Cn Cd]. destruct refined_signs_correct as [Rn Rd].
  assert (Sn : certifies cascade_num_sign (ray_num o p n)).
  { apply first_certain_sound; [|now apply first_certain_sound].
    rewrite ray_num_components. now apply num_filter_sound. }
  assert (Sd : certifies cascade_den_sign (ray_den d n)).
  { apply first_certain_sound; [|now apply first_certain_sound].
    rewrite ray_den_components. apply den_filter_sound. }
  split; [exact Sn | split; [exact Sd|]].
  intros Un Ud. now apply certified_relation.
Qed.

Definition cascade_quotient : option R :=
  match round_quotient num_enclosure den_enclosure with
  | Some t => Some t
  | None => round_quotient refined_num_enclosure refined_den_enclosure
  end.

Theorem cascade_quotient_correct : forall t, cascade_quotient = Some t ->
  ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n).
Proof.
  intros t. unfold cascade_quotient.
  destruct (round_quotient num_enclosure den_enclosure) as [t1|] eqn:E.
  - intros H. injection H as <-. now apply compensated_t_correct.
  - apply refined_t_correct.
Qed.

(** ** The fast path (fast_path.hpp), one query; the batch API runs the same operations per lane. *)

(** [FastAnswerT]. *)
Record FastAnswer := {
  fast_t : R;
  fast_behind : bool;
  fast_relation_by_compensated : bool;
  fast_relation_certain : bool;
  fast_t_certain : bool }.

Definition answer_relation (a : FastAnswer) : relation := if fast_behind a then Behind else Hit.

(** The stage-1 values the constructor of [FastQueryT] computes: den1 = dot3_rounded(d, n) and
    num1 = dot3_rounded(diff, n), diff_i = [two_diff(p_i, o_i).hi] = p_i ⊖ o_i. *)
Definition fast_den1 : Dot3Rounded := dot3_rounded dx dy dz nx ny nz.
Definition fast_num1 : Dot3Rounded := dot3_rounded (RN (px - ox)) (RN (py - oy)) (RN (pz - oz)) nx ny nz.

(** [FastQueryT::answer]: stage 1 and the first level of stage 2 for the signs, round_quotient_decision on
    the first level for t. *)
Definition fast_answer : FastAnswer :=
  let den_filter := dot3_filter_lanes fast_den1 filter_den_relative in
  let num_filter := dot3_filter_lanes fast_num1 filter_num_relative in
  let den2 := den_enclosure in
  let num2 := num_enclosure in
  let den_sign := first_certain_lanes den_filter (enclosure_sign_lanes den2) in
  let num_sign := first_certain_lanes num_filter (enclosure_sign_lanes num2) in
  let t := round_quotient_decision num2 den2 in
  {| fast_t := fst t;
     fast_behind := Z.ltb (num_sign * den_sign) 0;
     fast_relation_by_compensated :=
       negb (negb (Z.eqb den_filter uncertain_lane) && negb (Z.eqb num_filter uncertain_lane));
     fast_relation_certain := negb (Z.eqb den_sign uncertain_lane) && negb (Z.eqb num_sign uncertain_lane);
     fast_t_certain := snd t |}.

(** [FastQuery::refined_answer]: the second level of stage 2 for both signs and t. *)
Definition refined_answer : FastAnswer :=
  let den_sign := enclosure_sign_lanes refined_den_enclosure in
  let num_sign := enclosure_sign_lanes refined_num_enclosure in
  let t := round_quotient_decision refined_num_enclosure refined_den_enclosure in
  {| fast_t := fst t;
     fast_behind := Z.ltb (num_sign * den_sign) 0;
     fast_relation_by_compensated := true;
     fast_relation_certain := negb (Z.eqb den_sign uncertain_lane) && negb (Z.eqb num_sign uncertain_lane);
     fast_t_certain := snd t |}.

(** [FastQuery::filter_signs] (dot3_filter without the [exactly_zero] flag) and
    [FilterSigns::relation]. *)
Definition fast_filter_den : sign := dot3_filter fast_den1 filter_den_relative false.
Definition fast_filter_num : sign := dot3_filter fast_num1 filter_num_relative false.
Definition filter_signs_relation (num den : sign) : relation :=
  if Z.ltb (sign_to_Z num * sign_to_Z den) 0 then Behind else Hit.

(** [intersect_certified] up to its call of [full_cascade]: Some (relation, t) when the fast path
    answers. *)
Definition intersect_fast : option (relation * R) :=
  let decided := (is_certain fast_filter_den && is_certain fast_filter_num)%bool in
  let t := round_quotient_decision num_enclosure den_enclosure in
  if (decided && snd t)%bool then Some (filter_signs_relation fast_filter_num fast_filter_den, fst t)
  else if (fast_relation_certain refined_answer && fast_t_certain refined_answer)%bool
  then Some (answer_relation refined_answer, fast_t refined_answer)
  else None.

Lemma fast_filters_correct :
  lane_sign (dot3_filter_lanes fast_den1 filter_den_relative) /\
  certifies (sign_from_Z (dot3_filter_lanes fast_den1 filter_den_relative)) (ray_den d n) /\
  lane_sign (dot3_filter_lanes fast_num1 filter_num_relative) /\
  certifies (sign_from_Z (dot3_filter_lanes fast_num1 filter_num_relative)) (ray_num o p n).
Proof.
  repeat split; try apply dot3_filter_lanes_range.
  - rewrite ray_den_components. apply den_filter_lanes_sound.
  - rewrite ray_num_components. now apply num_filter_lanes_sound.
Qed.

(** The input check the fast path does without: a den sign certified nonzero by stage 1 (as the fast
    path calls it) or by either level of stage 2 implies d ≠ 0 and n ≠ 0. *)
Theorem fast_path_den_valid :
  dot3_filter_lanes fast_den1 filter_den_relative <> uncertain_lane \/
  enclosure_sign_lanes den_enclosure <> uncertain_lane \/
  enclosure_sign_lanes refined_den_enclosure <> uncertain_lane ->
  d <> zero3 /\ n <> zero3.
Proof.
  intros H. apply den_nonzero_valid.
  destruct fast_filters_correct as [L1 [C1 _]]. destruct enclosures_correct as [_ [Ed [_ Erd]]].
  destruct (enclosure_sign_correct den_enclosure _ ltac:(auto) Ed) as [L2 C2].
  destruct (enclosure_sign_correct refined_den_enclosure _ ltac:(auto) Erd) as [L3 C3].
  destruct H as [U|[U|U]]; [apply (lane_sign_exact _ _ L1 U C1) | apply (lane_sign_exact _ _ L2 U C2) |
                            apply (lane_sign_exact _ _ L3 U C3)].
Qed.

(** [FastQuery::answer]: a certain relation is the §1 relation (num, den ≠ 0, so hit or behind), on an
    input with d ≠ 0 and n ≠ 0; a certain t is RN(num/den). *)
Theorem fast_answer_correct :
  (fast_relation_certain fast_answer = true ->
   answer_relation fast_answer = classify o d p n /\ ray_num o p n <> 0 /\ ray_den d n <> 0 /\
   d <> zero3 /\ n <> zero3) /\
  (fast_t_certain fast_answer = true ->
   ray_den d n <> 0 /\ fast_t fast_answer = RN (ray_num o p n / ray_den d n)).
Proof.
  destruct fast_filters_correct as [L1 [C1 [L2 C2]]]. destruct enclosures_correct as [En [Ed _]].
  destruct (enclosure_sign_correct den_enclosure _ ltac:(auto) Ed) as [L3 C3].
  destruct (enclosure_sign_correct num_enclosure _ ltac:(auto) En) as [L4 C4].
  destruct (first_certain_lanes_sound _ _ _ L1 L3 C1 C3) as [Ld Cd].
  destruct (first_certain_lanes_sound _ _ _ L2 L4 C2 C4) as [Ln Cn].
  split.
  - unfold fast_answer, answer_relation. cbn [fast_relation_certain fast_behind].
    intros R. apply andb_prop in R. destruct R as [Rd Rn].
    apply Bool.negb_true_iff, Z.eqb_neq in Rd. apply Bool.negb_true_iff, Z.eqb_neq in Rn.
    destruct (lanes_relation _ _ o d p n Ln Ld Rn Rd Cn Cd) as [Rel [Nn Nd]].
    destruct (den_nonzero_valid d n Nd) as [Vd Vn]. repeat split; assumption.
  - unfold fast_answer. cbn [fast_t_certain fast_t]. apply round_quotient_decision_correct. auto.
Qed.

(** [FastQuery::refined_answer]: the same from the second level of stage 2. *)
Theorem refined_answer_correct :
  (fast_relation_certain refined_answer = true ->
   answer_relation refined_answer = classify o d p n /\ ray_num o p n <> 0 /\ ray_den d n <> 0 /\
   d <> zero3 /\ n <> zero3) /\
  (fast_t_certain refined_answer = true ->
   ray_den d n <> 0 /\ fast_t refined_answer = RN (ray_num o p n / ray_den d n)).
Proof.
  destruct enclosures_correct as [_ [_ [Ern Erd]]].
  destruct (enclosure_sign_correct refined_den_enclosure _ ltac:(auto) Erd) as [Ld Cd].
  destruct (enclosure_sign_correct refined_num_enclosure _ ltac:(auto) Ern) as [Ln Cn].
  split.
  - unfold refined_answer, answer_relation. cbn [fast_relation_certain fast_behind].
    intros R. apply andb_prop in R. destruct R as [Rd Rn].
    apply Bool.negb_true_iff, Z.eqb_neq in Rd. apply Bool.negb_true_iff, Z.eqb_neq in Rn.
    destruct (lanes_relation _ _ o d p n Ln Ld Rn Rd Cn Cd) as [Rel [Nn Nd]].
    destruct (den_nonzero_valid d n Nd) as [Vd Vn]. repeat split; assumption.
  - unfold refined_answer. cbn [fast_t_certain fast_t]. apply round_quotient_decision_correct. auto.
Qed.

(** [intersect_certified] before the full cascade: whatever it returns is the §1 relation (hit or
    behind) with t = RN(num/den), and the input it answered has d ≠ 0 and n ≠ 0. *)
Theorem intersect_fast_correct : forall rel t, intersect_fast = Some (rel, t) ->
  rel = classify o d p n /\ ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n) /\
  d <> zero3 /\ n <> zero3.
Proof.
  intros rel t. unfold intersect_fast, fast_filter_den, fast_filter_num, dot3_filter. cbv zeta.
  destruct fast_filters_correct as [L1 [C1 [L2 C2]]].
  pose proof (round_quotient_decision_correct num_enclosure den_enclosure ltac:(auto)) as Rq.
  destruct refined_answer_correct as [RA RB].
  (* make the computed values opaque: only their properties are used *)
  set (zd := dot3_filter_lanes fast_den1 filter_den_relative) in *. clearbody zd.
  set (zn := dot3_filter_lanes fast_num1 filter_num_relative) in *. clearbody zn.
  set (q := round_quotient_decision num_enclosure den_enclosure) in *. clearbody q.
  set (ra := refined_answer) in *. clearbody ra.
  destruct q as [q certain]. cbn [fst snd] in Rq |- *.
  destruct (is_certain (sign_from_Z zd) && is_certain (sign_from_Z zn) && certain)%bool eqn:Dc.
  - apply andb_prop in Dc. destruct Dc as [Dc Tc]. apply andb_prop in Dc. destruct Dc as [Dd Dn].
    intros H. injection H as <- <-.
    assert (Ud : zd <> uncertain_lane) by (intros E; rewrite E in Dd; discriminate Dd).
    assert (Un : zn <> uncertain_lane) by (intros E; rewrite E in Dn; discriminate Dn).
    destruct (lanes_relation zn zd o d p n L2 L1 Un Ud C2 C1) as [Rel [Nn Nd]].
    destruct (Rq Tc) as [_ T]. destruct (den_nonzero_valid d n Nd) as [Vd Vn].
    split; [|repeat split; assumption].
    destruct (lane_sign_certain zd L1 Ud) as [[E1 S1]|[E1 S1]];
      destruct (lane_sign_certain zn L2 Un) as [[E2 S2]|[E2 S2]];
      unfold filter_signs_relation; rewrite S1, S2; rewrite E1, E2 in Rel; exact Rel.
  - destruct (fast_relation_certain ra && fast_t_certain ra)%bool eqn:Rc; [|discriminate].
    intros H. injection H as <- <-. apply andb_prop in Rc. destruct Rc as [Rr Rt].
    destruct (RA Rr) as [Rel [_ [Nd [Vd Vn]]]]. destruct (RB Rt) as [_ T].
    repeat split; assumption.
Qed.

End Query.

(** The TwoSum pass of [expansion_tail_enclosure] produces doubles. *)
Lemma tail_loop_binary64 : forall rest q lo mag,
  binary64 q -> binary64 lo -> binary64 mag ->
  let '(q', lo', mag') := tail_loop q lo mag rest in binary64 q' /\ binary64 lo' /\ binary64 mag'.
Proof.
  induction rest as [|e rest IH]; intros q lo mag Bq Blo Bmag.
  - simpl. auto.
  - cbn [tail_loop]. apply IH; apply binary64_RN.
Qed.

Lemma tail_enclosure_binary64 : forall e0 rest, binary64 e0 ->
  let E := expansion_tail_enclosure e0 rest in binary64 (hi E) /\ binary64 (lo E) /\ binary64 (radius E).
Proof.
  intros e0 rest B0. unfold expansion_tail_enclosure.
  pose proof (tail_loop_binary64 rest e0 0 0 B0 binary64_0 binary64_0) as H.
  destruct (tail_loop e0 0 0 rest) as [[q lo] mag]. destruct H as [Bq [Blo _]].
  simpl. repeat split; try assumption. apply binary64_RN.
Qed.

(** Stage 3: [num] and [den] are the exact sums of the expansions (Shewchuk's Theorems 13 and 19 with
    the exactness guards of expansion.hpp: cited).  Expansions have at most 12 components here. *)
Theorem expansion_t_correct : forall (num_e0 den_e0 : R) (num_rest den_rest : list R) (num den t : R),
  binary64 num_e0 -> Forall (fun x => binary64 x) num_rest -> (S (length num_rest) <= tail_sum_max_terms)%nat ->
  binary64 den_e0 -> Forall (fun x => binary64 x) den_rest -> (S (length den_rest) <= tail_sum_max_terms)%nat ->
  num_e0 + sum_list num_rest = num -> den_e0 + sum_list den_rest = den ->
  round_quotient (expansion_tail_enclosure num_e0 num_rest) (expansion_tail_enclosure den_e0 den_rest) = Some t ->
  den <> 0 /\ t = RN (num / den).
Proof.
  intros ne0 de0 nr dr num den t Bn Fn Ln Bd Fd Ld Sn Sd H.
  destruct (tail_enclosure_binary64 ne0 nr Bn) as [B1 [B2 B3]].
  destruct (tail_enclosure_binary64 de0 dr Bd) as [B4 [B5 B6]].
  apply round_quotient_sound with (1 := B1) (2 := B2) (3 := B3) (4 := B4) (5 := B5) (6 := B6); [| |exact H].
  - rewrite <- Sn. now apply tail_sum_enclosure.
  - rewrite <- Sd. now apply tail_sum_enclosure.
Qed.

(** ** nearest_hit: the order of two hits along one ray (kernel/src/raycast/nearest_hit.cpp,
    [compare_hit_distances]), from the per-query stage results of certified/ray_plane_stages.hpp. *)

(** [RayPlaneStages]: stage 1 ([num_rounded], [den_rounded]) and stage 2 ([num_compensated],
    [den_compensated]) of one query, with the same arguments as [RayPlaneStages] passes. *)
Definition stage1_num (o p n : vec3) : Dot3Rounded :=
  dot3_rounded (RN (vx p - vx o)) (RN (vy p - vy o)) (RN (vz p - vz o)) (vx n) (vy n) (vz n).
Definition stage1_den (d n : vec3) : Dot3Rounded :=
  dot3_rounded (vx d) (vy d) (vz d) (vx n) (vy n) (vz n).
Definition stage2_num (o p n : vec3) : Enclosure :=
  compensated_dot3 (RN (vx p - vx o)) (RN (vy p - vy o)) (RN (vz p - vz o))
    (snd (two_diff (vx p) (vx o))) (snd (two_diff (vy p) (vy o))) (snd (two_diff (vz p) (vz o)))
    (vx n) (vy n) (vz n).
Definition stage2_den (d n : vec3) : Enclosure :=
  compensated_dot3 (vx d) (vy d) (vz d) 0 0 0 (vx n) (vy n) (vz n).

Definition binary64_vec3 (v : vec3) : Prop := binary64 (vx v) /\ binary64 (vy v) /\ binary64 (vz v).

(** The sign of Δ that [compare_hit_distances] computes by stage 1 and by stage 2, for the ray (o, d) and
    the planes (p_a, n_a) and (p_b, n_b). *)
Definition hit_delta_filter (o d pa na pb nb : vec3) : sign :=
  compare_quotients_filter (filter_enclosure (stage1_num o pa na) filter_num_relative)
    (filter_enclosure (stage1_den d na) filter_den_relative)
    (filter_enclosure (stage1_num o pb nb) filter_num_relative)
    (filter_enclosure (stage1_den d nb) filter_den_relative).
Definition hit_delta_compensated (o d pa na pb nb : vec3) : sign :=
  enclosure_sign (compare_quotients_compensated (stage2_num o pa na) (stage2_den d na)
                    (stage2_num o pb nb) (stage2_den d nb)).

Section NearestHit.
Variables o d pa na pb nb : vec3.
Hypotheses (Bo : binary64_vec3 o) (Bd : binary64_vec3 d) (Bpa : binary64_vec3 pa) (Bna : binary64_vec3 na)
           (Bpb : binary64_vec3 pb) (Bnb : binary64_vec3 nb).

Lemma stage1_num_encloses : forall p n, binary64_vec3 p ->
  rounded_encloses (filter_enclosure (stage1_num o p n) filter_num_relative) (ray_num o p n).
Proof.
  intros p n [B0 [B1 B2]]. destruct Bo as [O0 [O1 O2]].
  apply filter_enclosure_encloses. unfold stage1_num. unfold ray_num, dot, sub; cbn [vx vy vz].
  now apply num_filter_encloses.
Qed.

Lemma stage1_den_encloses : forall n,
  rounded_encloses (filter_enclosure (stage1_den d n) filter_den_relative) (ray_den d n).
Proof.
  intros n. apply filter_enclosure_encloses. unfold stage1_den. unfold ray_den, dot.
  apply den_filter_encloses.
Qed.

Lemma stage2_num_encloses : forall p n, binary64_vec3 p -> binary64_vec3 n ->
  encloses (stage2_num o p n) (ray_num o p n).
Proof.
  intros p n [B0 [B1 B2]] [N0 [N1 N2]]. destruct Bo as [O0 [O1 O2]].
  unfold stage2_num. unfold ray_num, dot, sub; cbn [vx vy vz]. now apply compensated_num_enclosure.
Qed.

Lemma stage2_den_encloses : forall n, binary64_vec3 n -> encloses (stage2_den d n) (ray_den d n).
Proof.
  intros n [N0 [N1 N2]]. destruct Bd as [D0 [D1 D2]].
  unfold stage2_den. unfold ray_den, dot. now apply compensated_den_enclosure.
Qed.

(** The parts of a stage-2 enclosure are doubles. *)
Lemma compensated_dot3_binary64 : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  let e := compensated_dot3 a0 a1 a2 al0 al1 al2 b0 b1 b2 in
  binary64 (hi e) /\ binary64 (lo e) /\ binary64 (radius e).
Proof. intros. repeat split; apply binary64_RN. Qed.

(** Stage 1 of the comparison: whenever it is certain, [compare_hit_distances] returns the sign of
    t_a − t_b, t = num/den exact, for two planes the ray hits (den ≠ 0) with certain den signs. *)
Theorem compare_hit_distances_filter_correct : forall den_sign_a den_sign_b,
  certifies den_sign_a (ray_den d na) -> den_sign_a <> Uncertain -> ray_den d na <> 0 ->
  certifies den_sign_b (ray_den d nb) -> den_sign_b <> Uncertain -> ray_den d nb <> 0 ->
  hit_delta_filter o d pa na pb nb <> Uncertain ->
  hit_distance_order (hit_delta_filter o d pa na pb nb) den_sign_a den_sign_b =
    sign_of (ray_num o pa na / ray_den d na - ray_num o pb nb / ray_den d nb).
Proof.
  intros sa sb Ca Ua Za Cb Ub Zb Ud.
  apply (hit_distance_order_correct _ sa sb _ _ _ _ Ca Ua Za Cb Ub Zb); [|exact Ud].
  destruct (filter_enclosure_binary64 (vx d) (vy d) (vz d) (vx na) (vy na) (vz na) filter_den_relative)
    as [Bya Bfa].
  destruct (filter_enclosure_binary64 (vx d) (vy d) (vz d) (vx nb) (vy nb) (vz nb) filter_den_relative)
    as [Byb Bfb].
  exact (compare_quotients_filter_sound _ _ _ _ _ _ _ _ Bya Bfa Byb Bfb
           (stage1_num_encloses pa na Bpa) (stage1_den_encloses na)
           (stage1_num_encloses pb nb Bpb) (stage1_den_encloses nb)).
Qed.

(** Stage 2 of the comparison, the same from the stage-2 enclosures and [enclosure_sign]. *)
Theorem compare_hit_distances_compensated_correct : forall den_sign_a den_sign_b,
  certifies den_sign_a (ray_den d na) -> den_sign_a <> Uncertain -> ray_den d na <> 0 ->
  certifies den_sign_b (ray_den d nb) -> den_sign_b <> Uncertain -> ray_den d nb <> 0 ->
  hit_delta_compensated o d pa na pb nb <> Uncertain ->
  hit_distance_order (hit_delta_compensated o d pa na pb nb) den_sign_a den_sign_b =
    sign_of (ray_num o pa na / ray_den d na - ray_num o pb nb / ray_den d nb).
Proof.
  intros sa sb Ca Ua Za Cb Ub Zb Ud.
  apply (hit_distance_order_correct _ sa sb _ _ _ _ Ca Ua Za Cb Ub Zb); [|exact Ud].
  unfold hit_delta_compensated.
  apply enclosure_sign_sound; [apply binary64_RN .. |].
  destruct (compensated_dot3_binary64 (RN (vx pa - vx o)) (RN (vy pa - vy o)) (RN (vz pa - vz o))
    (snd (two_diff (vx pa) (vx o))) (snd (two_diff (vy pa) (vy o))) (snd (two_diff (vz pa) (vz o)))
    (vx na) (vy na) (vz na)) as [Bh1 [Bl1 _]].
  destruct (compensated_dot3_binary64 (RN (vx pb - vx o)) (RN (vy pb - vy o)) (RN (vz pb - vz o))
    (snd (two_diff (vx pb) (vx o))) (snd (two_diff (vy pb) (vy o))) (snd (two_diff (vz pb) (vz o)))
    (vx nb) (vy nb) (vz nb)) as [Bh2 [Bl2 _]].
  destruct (compensated_dot3_binary64 (vx d) (vy d) (vz d) 0 0 0 (vx na) (vy na) (vz na))
    as [Bhd1 [Bld1 Brd1]].
  destruct (compensated_dot3_binary64 (vx d) (vy d) (vz d) 0 0 0 (vx nb) (vy nb) (vz nb))
    as [Bhd2 [Bld2 Brd2]].
  exact (compare_quotients_compensated_enclosure _ _ _ _ _ _ _ _
           Bh1 Bl1 Bhd1 Bld1 Brd1 Bh2 Bl2 Bhd2 Bld2 Brd2
           (stage2_num_encloses pa na Bpa Bna) (stage2_den_encloses na Bna)
           (stage2_num_encloses pb nb Bpb Bnb) (stage2_den_encloses nb Bnb)).
Qed.

End NearestHit.
