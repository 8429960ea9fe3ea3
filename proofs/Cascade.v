(** * The pieces as intersect_certified.cpp combines them.

    - [certified_relation]: signs certified by any stage give the relation of CONTRACT §1;
    - [filter_relation_correct]: the stage-1 relation, end to end from the binary64 inputs;
    - [compensated_signs_correct]: stage 2's sign decisions ([enclosure_sign] of the compensated
      enclosures);
    - [compensated_t_correct]: the t that round_quotient returns from the compensated enclosures;
    - [expansion_t_correct]: the t that round_quotient returns from the expansion enclosures, given
      that the expansions sum exactly to num and den (Shewchuk's theorems, cited, not proved here). *)

From Coq Require Import Reals Lra Lia List.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model Filter Compensated RoundQuotient Classification.
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
