(** * The pieces as the C++ combines them: the cascade (kernel/src/plane/ray_plane_cascade.cpp), the
    fast paths of kernel/src/plane/ray_plane_stages.hpp ([fast_answer], [fast_relation]) that
    [intersect] and [relation] (kernel/src/plane/plane_api.cpp) and the batch loops (kernel/src/plane/fast_loop.hpp)
    run, and nearest_hit.cpp's comparison.

    - [compensated_dot3_exact_inputs]: [compensated_dot3_exact] (dot3_compensated.hpp), the α = 0 form
      that den = d·n uses, computes what [compensated_dot3] computes with α = 0;
    - [certified_relation]: signs certified by any stage give the relation of docs/contract.md §1;
    - [filter_relation_correct]: the stage-1 relation with the zero flags, end to end from the binary64
      inputs;
    - [compensated_signs_correct]: stage 2's sign decisions ([enclosure_sign] of the compensated
      enclosures); [refined_signs_correct]: the same for the second level ([compensated_dot3_refined]);
    - [compensated_t_correct], [refined_t_correct]: the t that round_quotient returns from the
      enclosures of either level (QuotientRounding.v, one reciprocal of the prepared divisor);
    - [cascade_signs_correct], [cascade_quotient_correct]: [certified_signs] through stage 2 (both
      levels) and [certified_quotient] through stage 2, as ray_plane_cascade.cpp chains them;
    - the fast paths: [fast_answer_correct] ([fast_answer]: what [intersect] and the batch API run, per
      lane), [intersect_fast_correct] ([intersect] before it falls back to validation and the cascade):
      a certified answer is the §1 relation (hit or behind) with t = RN(num/den), on an input with d ≠ 0
      and n ≠ 0; [fast_relation_correct] ([fast_relation], what [relation] and the relation batch run):
      its decision |s| > B for both signs certifies the §1 relation with num ≠ 0 and den ≠ 0;
      [fast_path_den_valid]: a nonzero den sign from stage 1 or either level of stage 2 implies d ≠ 0
      and n ≠ 0, which is why the fast paths need no validation (the finiteness half is IEEE
      propagation: proofs/README.md, "The fast path");
    - [expansion_t_correct]: the t that round_quotient returns from the expansion enclosures, given
      that the expansions sum exactly to num and den (Shewchuk's theorems, cited, not proved here);
      [two_prod_threshold_exact]: the guard |a ⊗ b| ≥ exact_product_threshold of the expansion builder;
    - [compare_hit_distances_filter_correct], [compare_hit_distances_compensated_correct]: the order of
      two hits' t that nearest_hit.cpp's [compare_hit_distances] returns from stage 1 or stage 2 of the
      comparison (compare_quotients.hpp) is the order of the exact t = num/den. *)

From Coq Require Import Reals Lra Lia List ZArith Bool.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated QuotientRounding PlaneClassification
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

(** [signs_say_behind(num_sign, den_sign) ? behind : hit] (ray_plane_formula.hpp, as [fast_answer] uses
    it), for two certain lane signs, is the §1 relation, and num, den ≠ 0. *)
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

(** For num, den ≠ 0 the §1 relation is behind exactly when num < 0 and den < 0 differ, the test
    [(num.value < 0) != (den.value < 0)] of [fast_relation] applied to the exact values. *)
Lemma relation_of_nonzero : forall o d p n, ray_num o p n <> 0 -> ray_den d n <> 0 ->
  classify o d p n =
    if negb (Bool.eqb (Rlt_bool (ray_num o p n) 0) (Rlt_bool (ray_den d n) 0)) then Behind else Hit.
Proof.
  intros o d p n Nn Nd. unfold classify, relation_from_signs, sign_of.
  destruct (Rcompare_spec (ray_num o p n) 0) as [Ln|En|Gn]; [| contradiction |];
    destruct (Rcompare_spec (ray_den d n) 0) as [Ld|Ed|Gd]; try contradiction;
    repeat first [rewrite (Rlt_bool_true _ _ Ln) | rewrite (Rlt_bool_false _ _ (Rlt_le _ _ Gn)) |
                  rewrite (Rlt_bool_true _ _ Ld) | rewrite (Rlt_bool_false _ _ (Rlt_le _ _ Gd))];
    reflexivity.
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

(** ** [compensated_dot3_exact] (dot3_compensated.hpp): [compensated_dot3] for α = 0, which computes
    g_i = l_i instead of g_i = fma(α_i, b_i, l_i) = RN(0·b_i + l_i). *)
Definition compensated_dot3_exact (a0 a1 a2 b0 b1 b2 : R) : Enclosure :=
  let stage1 := dot3_rounded a0 a1 a2 b0 b1 b2 in
  let h0 := product0 stage1 in let h1 := product1 stage1 in let h2 := product2 stage1 in
  let g0 := fma a0 b0 (- h0) in
  let g1 := fma a1 b1 (- h1) in
  let g2 := fma a2 b2 (- h2) in
  let s2 := two_sum h0 h1 in
  let s3 := two_sum (fst s2) h2 in
  let lo := RN (RN (RN (g0 + g1) + g2) + RN (snd s2 + snd s3)) in
  let radius := RN (RN (compensated_relative * magnitude stage1) + compensated_absolute) in
  {| hi := fst s3; lo := lo; radius := radius |}.

(** The same enclosure, bit for bit: RN(0·b + l) = l for the double l = RN(a·b − h). *)
Theorem compensated_dot3_exact_inputs : forall a0 a1 a2 b0 b1 b2,
  compensated_dot3_exact a0 a1 a2 b0 b1 b2 = compensated_dot3 a0 a1 a2 0 0 0 b0 b1 b2.
Proof.
  intros. unfold compensated_dot3_exact, compensated_dot3.
  assert (G : forall b l, binary64 l -> fma 0 b l = l).
  { intros b l Bl. unfold fma. rewrite Rmult_0_l, Rplus_0_l. now apply RN_binary64. }
  rewrite !(G _ (fma _ _ _)) by apply binary64_RN. reflexivity.
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

(** The first level of stage 2 as plane/ray_plane_stages.hpp computes it: [num_compensated]
    ([compensated_dot3] with α_i = [two_diff(p_i, o_i).lo]) and [den_compensated]
    ([compensated_dot3_exact]). *)
Definition num_enclosure : Enclosure :=
  compensated_dot3 (RN (px - ox)) (RN (py - oy)) (RN (pz - oz))
    (snd (two_diff px ox)) (snd (two_diff py oy)) (snd (two_diff pz oz)) nx ny nz.
Definition den_enclosure : Enclosure := compensated_dot3_exact dx dy dz nx ny nz.

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

(** ** The second level of stage 2: [num_refined] and [den_refined] (plane/ray_plane_stages.hpp). *)
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
  - unfold den_enclosure. rewrite compensated_dot3_exact_inputs. now apply compensated_den_enclosure.
  - now apply compensated_num_refined_enclosure.
  - now apply compensated_den_refined_enclosure.
Qed.

Lemma enclosures_binary64 : forall e, e = num_enclosure \/ e = den_enclosure \/
  e = refined_num_enclosure \/ e = refined_den_enclosure ->
  binary64 (hi e) /\ binary64 (lo e) /\ binary64 (radius e).
Proof.
  intros e [ -> | [ -> | [ -> | -> ] ] ]; repeat split;
    unfold num_enclosure, den_enclosure, refined_num_enclosure, refined_den_enclosure,
      compensated_dot3, compensated_dot3_exact, compensated_dot3_refined; cbn [hi lo radius];
    first [apply binary64_two_sum_hi | apply binary64_RN].
Qed.

Lemma enclosure_sign_correct : forall e V, e = num_enclosure \/ e = den_enclosure \/
  e = refined_num_enclosure \/ e = refined_den_enclosure -> encloses e V ->
  lane_sign (enclosure_sign_lanes e) /\ certifies (sign_from_Z (enclosure_sign_lanes e)) V.
Proof.
  intros e V He Enc. destruct (enclosures_binary64 e He) as [B1 [B2 B3]].
  split; [apply enclosure_sign_lanes_range | now apply enclosure_sign_sound].
Qed.

Theorem compensated_signs_correct :
  certifies (enclosure_sign num_enclosure) (ray_num o p n) /\
  certifies (enclosure_sign den_enclosure) (ray_den d n).
Proof.
  destruct enclosures_correct as [Hn [Hd _]].
  split; apply enclosure_sign_correct; auto.
Qed.

Theorem refined_signs_correct :
  certifies (enclosure_sign refined_num_enclosure) (ray_num o p n) /\
  certifies (enclosure_sign refined_den_enclosure) (ray_den d n).
Proof.
  destruct enclosures_correct as [_ [_ [Hn Hd]]].
  split; apply enclosure_sign_correct; auto.
Qed.

(** round_quotient on the enclosures of either level, the divisor prepared from den's. *)
Lemma quotient_rounding_correct : forall nE dE,
  (nE = num_enclosure /\ dE = den_enclosure) \/ (nE = refined_num_enclosure /\ dE = refined_den_enclosure) ->
  qr_certain (round_quotient nE (prepare_divisor dE)) = true ->
  ray_den d n <> 0 /\ qr_t (round_quotient nE (prepare_divisor dE)) = RN (ray_num o p n / ray_den d n).
Proof.
  intros nE dE Hs T. destruct enclosures_correct as [En [Ed [Ern Erd]]].
  destruct Hs as [ [ -> -> ] | [ -> -> ] ].
  - destruct (enclosures_binary64 num_enclosure ltac:(auto)) as [B1 [B2 B3]].
    destruct (enclosures_binary64 den_enclosure ltac:(auto)) as [B4 [B5 B6]].
    now apply round_quotient_sound.
  - destruct (enclosures_binary64 refined_num_enclosure ltac:(auto)) as [B1 [B2 B3]].
    destruct (enclosures_binary64 refined_den_enclosure ltac:(auto)) as [B4 [B5 B6]].
    now apply round_quotient_sound.
Qed.

Lemma quotient_rounding_if_certain_correct : forall nE dE t,
  (nE = num_enclosure /\ dE = den_enclosure) \/ (nE = refined_num_enclosure /\ dE = refined_den_enclosure) ->
  round_quotient_if_certain nE (prepare_divisor dE) = Some t ->
  ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n).
Proof.
  intros nE dE t Hs H. unfold round_quotient_if_certain in H.
  pose proof (quotient_rounding_correct nE dE Hs) as R.
  destruct (round_quotient nE (prepare_divisor dE)) as [q [|]]; [|discriminate].
  injection H as <-. now apply R.
Qed.

Theorem compensated_t_correct : forall t,
  round_quotient_if_certain num_enclosure (prepare_divisor den_enclosure) = Some t ->
  ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n).
Proof. intros t. apply quotient_rounding_if_certain_correct. auto. Qed.

Theorem refined_t_correct : forall t,
  round_quotient_if_certain refined_num_enclosure (prepare_divisor refined_den_enclosure) = Some t ->
  ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n).
Proof. intros t. apply quotient_rounding_if_certain_correct. auto. Qed.

(** ** The cascade through stage 2 (ray_plane_cascade.cpp, [certified_signs] and [certified_quotient]):
    each sign is stage 1's (with the zero flags) where certain, else the first level's, else the second
    level's; t is round_quotient on the first level's enclosures, else on the second level's.  Stage 3
    (expansions, [expansion_t_correct]) and stage 4 (exact) come after. *)
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
  match round_quotient_if_certain num_enclosure (prepare_divisor den_enclosure) with
  | Some t => Some t
  | None => round_quotient_if_certain refined_num_enclosure (prepare_divisor refined_den_enclosure)
  end.

Theorem cascade_quotient_correct : forall t, cascade_quotient = Some t ->
  ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n).
Proof.
  intros t. unfold cascade_quotient.
  destruct (round_quotient_if_certain num_enclosure (prepare_divisor den_enclosure)) as [t1|] eqn:E.
  - intros H. injection H as <-. now apply compensated_t_correct.
  - apply refined_t_correct.
Qed.

(** ** The fast paths (plane/ray_plane_stages.hpp), one query; the batch loops run the same operations per
    lane (proofs/README.md, "Lanes"). *)

(** The stage-1 values of [RayPlaneTermsT] (and of [fast_relation], which computes the same ones as
    locals): den = dot3_rounded(d, n) and num = dot3_rounded(diff, n), diff_i = p_i ⊖ o_i. *)
Definition fast_den1 : Dot3Rounded := dot3_rounded dx dy dz nx ny nz.
Definition fast_num1 : Dot3Rounded := dot3_rounded (RN (px - ox)) (RN (py - oy)) (RN (pz - oz)) nx ny nz.

(** [FastAnswerT]. *)
Record FastAnswer := {
  fast_t : R;
  fast_behind : bool;
  fast_certain : bool;
  fast_relation_by_filter : bool }.

Definition answer_relation (a : FastAnswer) : relation := if fast_behind a then Behind else Hit.

(** [fast_answer]: stage 1 and the first level of stage 2 for the signs, round_quotient on the first
    level's enclosures for t, one flag for all three. *)
Definition fast_answer : FastAnswer :=
  let den_filter := dot3_filter_lanes fast_den1 filter_den_relative in
  let num_filter := dot3_filter_lanes fast_num1 filter_num_relative in
  let den := den_enclosure in
  let num := num_enclosure in
  let den_sign := first_certain_lanes den_filter (enclosure_sign_lanes den) in
  let num_sign := first_certain_lanes num_filter (enclosure_sign_lanes num) in
  let t := round_quotient num (prepare_divisor den) in
  {| fast_t := qr_t t;
     fast_behind := Z.ltb (num_sign * den_sign) 0;
     fast_certain :=
       negb (Z.eqb den_sign uncertain_lane) && negb (Z.eqb num_sign uncertain_lane) && qr_certain t;
     fast_relation_by_filter :=
       negb (Z.eqb den_filter uncertain_lane) && negb (Z.eqb num_filter uncertain_lane) |}.

(** [certified_intersection] (api.cpp) before [intersection_rest]: the fast path's answer where it is
    certain, else None (then the input is validated and the cascade answers). *)
Definition intersect_fast : option (relation * R) :=
  if fast_certain fast_answer then Some (answer_relation fast_answer, fast_t fast_answer) else None.

(** [FastRelationT] and [fast_relation]: stage 1 alone, decided by |s| > B, with behind where the
    rounded values differ in sign. *)
Record FastRelation := { relation_behind : bool; relation_certain : bool }.

Definition fast_relation : FastRelation :=
  let den := fast_den1 in
  let num := fast_num1 in
  let den_bound := filter_bound den filter_den_relative in
  let num_bound := filter_bound num filter_num_relative in
  {| relation_behind := negb (Bool.eqb (Rlt_bool (value num) 0) (Rlt_bool (value den) 0));
     relation_certain := Rlt_bool den_bound (Rabs (value den)) && Rlt_bool num_bound (Rabs (value num)) |}.

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

(** The input check the fast paths do without: a den sign certified nonzero by stage 1 (as the fast
    paths call it) or by either level of stage 2 implies d ≠ 0 and n ≠ 0. *)
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

(** [fast_answer]: when certain, the relation is the §1 relation (num, den ≠ 0, so hit or behind), the
    input has d ≠ 0 and n ≠ 0, and t = RN(num/den). *)
Theorem fast_answer_correct :
  fast_certain fast_answer = true ->
  answer_relation fast_answer = classify o d p n /\ ray_num o p n <> 0 /\ ray_den d n <> 0 /\
  d <> zero3 /\ n <> zero3 /\ fast_t fast_answer = RN (ray_num o p n / ray_den d n).
Proof.
  destruct fast_filters_correct as [L1 [C1 [L2 C2]]]. destruct enclosures_correct as [En [Ed _]].
  destruct (enclosure_sign_correct den_enclosure _ ltac:(auto) Ed) as [L3 C3].
  destruct (enclosure_sign_correct num_enclosure _ ltac:(auto) En) as [L4 C4].
  destruct (first_certain_lanes_sound _ _ _ L1 L3 C1 C3) as [Ld Cd].
  destruct (first_certain_lanes_sound _ _ _ L2 L4 C2 C4) as [Ln Cn].
  pose proof (quotient_rounding_correct num_enclosure den_enclosure ltac:(auto)) as Q.
  unfold fast_answer, answer_relation. cbn [fast_certain fast_behind fast_t].
  intros R. apply andb_prop in R. destruct R as [R Rt]. apply andb_prop in R. destruct R as [Rd Rn].
  apply Bool.negb_true_iff, Z.eqb_neq in Rd. apply Bool.negb_true_iff, Z.eqb_neq in Rn.
  destruct (lanes_relation _ _ o d p n Ln Ld Rn Rd Cn Cd) as [Rel [Nn Nd]].
  destruct (den_nonzero_valid d n Nd) as [Vd Vn]. destruct (Q Rt) as [_ T].
  repeat split; assumption.
Qed.

(** [intersect] before the fallback: whatever the fast path returns is the §1 relation (hit or behind)
    with t = RN(num/den), and the input it answered has d ≠ 0 and n ≠ 0. *)
Theorem intersect_fast_correct : forall rel t, intersect_fast = Some (rel, t) ->
  rel = classify o d p n /\ ray_den d n <> 0 /\ t = RN (ray_num o p n / ray_den d n) /\
  d <> zero3 /\ n <> zero3.
Proof.
  intros rel t. unfold intersect_fast.
  pose proof fast_answer_correct as F.
  (* make the computed answer opaque: only its properties are used *)
  set (a := fast_answer) in *. clearbody a.
  intros H. destruct (fast_certain a) eqn:C; [|discriminate].
  injection H as <- <-.
  destruct (F eq_refl) as [Rel [_ [Nd [Vd [Vn T]]]]].
  repeat split; assumption.
Qed.

(** [fast_relation]: |s| > B (B ≥ 0) decides the sign of the exact value, which is then nonzero and
    negative exactly when s < 0. *)
Lemma abs_above_bound : forall s B V, Rabs (s - V) <= B -> B < Rabs s ->
  V <> 0 /\ Rlt_bool s 0 = Rlt_bool V 0.
Proof.
  intros s B V E A. apply Rabs_bounds in E.
  destruct (Rle_or_lt 0 s) as [Ps|Ns].
  - rewrite Rabs_pos_eq in A by exact Ps.
    split; [lra|]. rewrite (Rlt_bool_false s 0), (Rlt_bool_false V 0) by lra. reflexivity.
  - rewrite Rabs_left in A by exact Ns.
    split; [lra|]. rewrite (Rlt_bool_true s 0), (Rlt_bool_true V 0) by lra. reflexivity.
Qed.

(** [fast_relation] (what [relation] and the relation batch run): when certain, [behind ? behind : hit]
    is the §1 relation, num ≠ 0 and den ≠ 0, and the input has d ≠ 0 and n ≠ 0. *)
Theorem fast_relation_correct :
  relation_certain fast_relation = true ->
  (if relation_behind fast_relation then Behind else Hit) = classify o d p n /\
  ray_num o p n <> 0 /\ ray_den d n <> 0 /\ d <> zero3 /\ n <> zero3.
Proof.
  unfold fast_relation. cbn [relation_certain relation_behind].
  intros C. apply andb_prop in C. destruct C as [Cd Cn].
  destruct (Rlt_bool_spec (filter_bound fast_den1 filter_den_relative) (Rabs (value fast_den1))) as [Gd|_];
    [|discriminate].
  destruct (Rlt_bool_spec (filter_bound fast_num1 filter_num_relative) (Rabs (value fast_num1))) as [Gn|_];
    [|discriminate].
  pose proof (den_filter_encloses dx dy dz nx ny nz) as Ed. fold fast_den1 in Ed.
  pose proof (num_filter_encloses px py pz ox oy oz nx ny nz Bpx Bpy Bpz Box Boy Boz) as En.
  fold fast_num1 in En.
  rewrite <- ray_den_components in Ed. rewrite <- ray_num_components in En.
  destruct (abs_above_bound _ _ _ Ed Gd) as [Nd Sd].
  destruct (abs_above_bound _ _ _ En Gn) as [Nn Sn].
  destruct (den_nonzero_valid d n Nd) as [Vd Vn].
  rewrite Sd, Sn, <- (relation_of_nonzero o d p n Nn Nd).
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
  round_quotient_if_certain (expansion_tail_enclosure num_e0 num_rest)
    (prepare_divisor (expansion_tail_enclosure den_e0 den_rest)) = Some t ->
  den <> 0 /\ t = RN (num / den).
Proof.
  intros ne0 de0 nr dr num den t Bn Fn Ln Bd Fd Ld Sn Sd H.
  destruct (tail_enclosure_binary64 ne0 nr Bn) as [B1 [B2 B3]].
  destruct (tail_enclosure_binary64 de0 dr Bd) as [B4 [B5 B6]].
  apply round_quotient_if_certain_sound with (1 := B1) (2 := B2) (3 := B3) (4 := B4) (5 := B5) (6 := B6); [| |exact H].
  - rewrite <- Sn. now apply tail_sum_enclosure.
  - rewrite <- Sd. now apply tail_sum_enclosure.
Qed.

(** The guard of the expansion builder's [note_product] (expansion.hpp): TwoProduct is exact when the
    rounded product is at least [exact_product_threshold] = 2^-968 in magnitude, or zero with a zero
    factor ([two_prod_guard_exact], Model.v, with the constant of error_bounds.hpp). *)
Corollary two_prod_threshold_exact : forall a b, binary64 a -> binary64 b ->
  (RN (a * b) = 0 /\ (a = 0 \/ b = 0)) \/ exact_product_threshold <= Rabs (RN (a * b)) ->
  fst (two_prod a b) + snd (two_prod a b) = a * b.
Proof. exact two_prod_guard_exact. Qed.

(** ** nearest_hit: the order of two hits along one ray (kernel/src/nearest/nearest_hit.cpp,
    [compare_hit_distances]), from the per-query stage results of plane/ray_plane_stages.hpp. *)

(** [RayPlaneTermsT] and [RayPlaneCascade]: stage 1 ([num], [den] of the terms) and stage 2
    ([num_compensated], [den_compensated]: [compensated_dot3] and [compensated_dot3_exact]) of one query,
    with the same arguments as plane/ray_plane_stages.hpp passes. *)
Definition stage1_num (o p n : vec3) : Dot3Rounded :=
  dot3_rounded (RN (vx p - vx o)) (RN (vy p - vy o)) (RN (vz p - vz o)) (vx n) (vy n) (vz n).
Definition stage1_den (d n : vec3) : Dot3Rounded :=
  dot3_rounded (vx d) (vy d) (vz d) (vx n) (vy n) (vz n).
Definition stage2_num (o p n : vec3) : Enclosure :=
  compensated_dot3 (RN (vx p - vx o)) (RN (vy p - vy o)) (RN (vz p - vz o))
    (snd (two_diff (vx p) (vx o))) (snd (two_diff (vy p) (vy o))) (snd (two_diff (vz p) (vz o)))
    (vx n) (vy n) (vz n).
Definition stage2_den (d n : vec3) : Enclosure :=
  compensated_dot3_exact (vx d) (vy d) (vz d) (vx n) (vy n) (vz n).

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
  unfold stage2_den. rewrite compensated_dot3_exact_inputs. unfold ray_den, dot.
  now apply compensated_den_enclosure.
Qed.

(** The parts of a stage-2 enclosure are doubles. *)
Lemma compensated_dot3_binary64 : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  let e := compensated_dot3 a0 a1 a2 al0 al1 al2 b0 b1 b2 in
  binary64 (hi e) /\ binary64 (lo e) /\ binary64 (radius e).
Proof. intros. repeat split; apply binary64_RN. Qed.

Lemma stage2_den_binary64 : forall d n,
  let e := stage2_den d n in binary64 (hi e) /\ binary64 (lo e) /\ binary64 (radius e).
Proof. intros. repeat split; unfold e, stage2_den, compensated_dot3_exact; apply binary64_RN. Qed.

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
  destruct (stage2_den_binary64 d na) as [Bhd1 [Bld1 Brd1]].
  destruct (stage2_den_binary64 d nb) as [Bhd2 [Bld2 Brd2]].
  exact (compare_quotients_compensated_enclosure _ _ _ _ _ _ _ _
           Bh1 Bl1 Bhd1 Bld1 Brd1 Bh2 Bl2 Bhd2 Bld2 Brd2
           (stage2_num_encloses pa na Bpa Bna) (stage2_den_encloses na Bna)
           (stage2_num_encloses pb nb Bpb Bnb) (stage2_den_encloses nb Bnb)).
Qed.

End NearestHit.
