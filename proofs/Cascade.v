(** * The pieces as intersect_certified.cpp combines them.

    - [certified_relation]: signs certified by any stage give the relation of CONTRACT §1;
    - [filter_relation_correct]: the stage-1 relation, end to end from the binary64 inputs;
    - [compensated_signs_correct]: stage 2's sign decisions ([enclosure_sign] of the compensated
      enclosures);
    - [compensated_t_correct]: the t that round_quotient returns from the compensated enclosures;
    - [expansion_t_correct]: the t that round_quotient returns from the expansion enclosures, given
      that the expansions sum exactly to num and den (Shewchuk's theorems, cited, not proved here);
    - [compare_hit_distances_filter_correct], [compare_hit_distances_compensated_correct]: the order of
      two hits' t that nearest_hit.cpp's [compare_hit_distances] returns from stage 1 or stage 2 of the
      comparison (compare_quotients.hpp) is the order of the exact t = num/den. *)

From Coq Require Import Reals Lra Lia List.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model Filter Compensated RoundQuotient Classification
  CompareQuotients.
Open Scope R_scope.

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
