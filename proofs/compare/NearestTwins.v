(** * The nearest-hit comparison (kernel/src/nearest/nearest_hit.cpp, [compare_hit_distances]), twin and theorem.

    [compare_hit_distances_b] is the C++ function operation by operation on the bits of a ray (o, d) and two
    planes (p_a, n_a), (p_b, n_b) it hits, given the certified signs of num and den that the candidates
    carry ([HitCandidate::num_sign], [den_sign]): the two shortcuts (t = 0 first), then the cascade of
    [compare_quotients_filter] on the four stage-1 [filter_enclosure]s (num's with num's constant, den's
    with den's: the call site a mutation once got wrong, proofs/mutation/run.py's [call_site_nearest]),
    [enclosure_sign] of [compare_quotients_compensated] on the four stage-2 enclosures of [RayPlaneCascade]
    (den: the α = 0 form; num: with the TwoDiff low parts), and [compare_quotients_expansion] on the stage-3
    expansions.  It returns (order, stage) with stage 0, 1, 2 for the stage that decided (Stage::filter,
    compensated, expansion) and (0, 3) when the C++ falls to the exact stage (exact rationals, not a twin).

    [compare_hit_distances_twin_correct]: for every bit pattern of the ray and planes, when both candidates
    are hits whose carried signs are certain and exact (what nearest_hit gives them: the relation's signs),
    an order decided before the exact stage is sign(t_a − t_b) for the exact t = num/den.  The differential
    runner (routine [nearest_compare], on near-tie plane pairs) checks the twin against the compiled
    [compare_hit_distances] bit for bit (order and stage). *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification QuotientRounding CompareQuotients
  PlaneCascade FloatCore ConstantsCpp PlaneTwins CompareTwins Expansions PlaneQueryTwins PlaneStageTwoFinite.
From Raykernel Require PlaneQueryPairTwins.
Open Scope R_scope.

Definition stage1_num_b (o p n : Vec3B) : Dot3B :=
  dot3_rounded_b (fsub (vxb p) (vxb o)) (fsub (vyb p) (vyb o)) (fsub (vzb p) (vzb o)) (vxb n) (vyb n) (vzb n).
Definition stage1_den_b (d n : Vec3B) : Dot3B :=
  dot3_rounded_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n).
Definition stage2_num_b (o p n : Vec3B) : EnclosureB :=
  num_compensated_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n).
Definition stage2_den_b (d n : Vec3B) : EnclosureB :=
  den_compensated_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n).

Definition is_certain_b (s : sign) : bool := match s with Uncertain => false | _ => true end.

(** [compare_hit_distances(a, b)]: (order, stage). *)
Definition compare_hit_distances_b (o d pa na pb nb : Vec3B) (nsa dsa nsb dsb : sign) : Z * Z :=
  let at_origin s := match s with Zero => true | _ => false end in
  if (at_origin nsa || at_origin nsb)%bool then (origin_order nsa nsb, 0%Z) else
  let delta1 := compare_quotients_filter_b
                  (filter_enclosure_b (stage1_num_b o pa na) Cpp.filter_num_relative)
                  (filter_enclosure_b (stage1_den_b d na) Cpp.filter_den_relative)
                  (filter_enclosure_b (stage1_num_b o pb nb) Cpp.filter_num_relative)
                  (filter_enclosure_b (stage1_den_b d nb) Cpp.filter_den_relative) in
  if is_certain_b delta1 then (hit_distance_order delta1 dsa dsb, 0%Z) else
  let delta2 := sign_from_Z (enclosure_sign_lanes_b
                  (compare_quotients_compensated_b (stage2_num_b o pa na) (stage2_den_b d na)
                                                   (stage2_num_b o pb nb) (stage2_den_b d nb))) in
  if is_certain_b delta2 then (hit_distance_order delta2 dsa dsb, 1%Z) else
  let '(xna, xda, xa) := ray_plane_expansions_b two_sum_b o d pa na in
  let '(xnb, xdb, xb) := ray_plane_expansions_b two_sum_b o d pb nb in
  let delta3 := compare_quotients_expansion_b xna xda xa xnb xdb xb in
  if is_certain_b delta3 then (hit_distance_order delta3 dsa dsb, 2%Z) else (0%Z, 3%Z).

(** ** Each stage's certain sign of Δ is the exact sign *)

Lemma is_certain_b_true : forall s, is_certain_b s = true -> s <> Uncertain.
Proof. intros [] H; try discriminate; congruence. Qed.

Lemma ray_num_bits : forall o p n : Vec3B,
  ray_num (vec_R o) (vec_R p) (vec_R n) =
  (B2R (vxb p) - B2R (vxb o)) * B2R (vxb n) + (B2R (vyb p) - B2R (vyb o)) * B2R (vyb n) +
  (B2R (vzb p) - B2R (vzb o)) * B2R (vzb n).
Proof. intros [] [] []. reflexivity. Qed.

Lemma ray_den_bits : forall d n : Vec3B,
  ray_den (vec_R d) (vec_R n) = B2R (vxb d) * B2R (vxb n) + B2R (vyb d) * B2R (vyb n) + B2R (vzb d) * B2R (vzb n).
Proof. intros [] []. reflexivity. Qed.

Lemma filter_radius_nonneg : forall r C, nonneg C -> nonneg (magnitudeb r) ->
  nonneg (rradiusb (filter_enclosure_b r C)).
Proof. intros r C NC NM. cbn [rradiusb]. apply fadd_nonneg; [now apply fmul_nonneg | const_nonneg]. Qed.

Lemma stage1_magnitude_nonneg : forall a0 a1 a2 b0 b1 b2, nonneg (magnitudeb (dot3_rounded_b a0 a1 a2 b0 b1 b2)).
Proof. intros. cbn [magnitudeb dot3_rounded_b]. apply fadd_nonneg; [apply fadd_nonneg|]; apply fabs_nonneg. Qed.

(** A finite stage-1 enclosure (finite value and radius) encloses its exact value. *)
Lemma filter_enclosure_b_encloses : forall a0 a1 a2 b0 b1 b2 C V,
  let r := dot3_rounded_b a0 a1 a2 b0 b1 b2 in
  fin C = true ->
  (fin a0 = true -> fin a1 = true -> fin a2 = true ->
   Rabs (value (dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)) - V) <=
   filter_bound (dot3_rounded (B2R a0) (B2R a1) (B2R a2) (B2R b0) (B2R b1) (B2R b2)) (B2R C)) ->
  fin (rradiusb (filter_enclosure_b r C)) = true ->
  rounded_encloses (renc_R (filter_enclosure_b r C)) V.
Proof.
  intros a0 a1 a2 b0 b1 b2 C V r FC H Fr. subst r. cbn [rradiusb filter_enclosure_b] in Fr.
  destruct (fadd_fin _ _ Fr) as [F1 _]. destruct (fmul_fin _ _ F1) as [_ Fm].
  destruct (dot3_rounded_twin a0 a1 a2 b0 b1 b2 Fm) as [Fa0 [Fa1 [Fa2 [_ [_ [_ [_ [_ [_ [_ E]]]]]]]]]].
  specialize (H Fa0 Fa1 Fa2). rewrite <- E in H.
  unfold rounded_encloses, renc_R. cbn [rounded_value rounded_radius rvalueb rradiusb filter_enclosure_b].
  unfold filter_bound in H. cbn [dot3_R value magnitude] in H.
  rewrite (fadd_val _ _ Fr), (fmul_val _ _ F1), cpp_filter_absolute. exact H.
Qed.

Lemma filter_num_encloses_b : forall o p n : Vec3B,
  fin (rradiusb (filter_enclosure_b (stage1_num_b o p n) Cpp.filter_num_relative)) = true ->
  rounded_encloses (renc_R (filter_enclosure_b (stage1_num_b o p n) Cpp.filter_num_relative))
    (ray_num (vec_R o) (vec_R p) (vec_R n)).
Proof.
  intros [ox oy oz] [px py pz] [nx ny nz] Fr. unfold stage1_num_b in *. cbn [vxb vyb vzb] in *.
  apply filter_enclosure_b_encloses; [vm_compute; reflexivity | | exact Fr].
  intros F0 F1 F2. rewrite ray_num_bits. cbn [vxb vyb vzb]. rewrite cpp_filter_num_relative.
  destruct (fsub_inv _ _ F0) as [_ [_ V0]]. destruct (fsub_inv _ _ F1) as [_ [_ V1]].
  destruct (fsub_inv _ _ F2) as [_ [_ V2]]. rewrite V0, V1, V2.
  apply num_filter_encloses; apply binary64_B2R.
Qed.

Lemma filter_den_encloses_b : forall d n : Vec3B,
  fin (rradiusb (filter_enclosure_b (stage1_den_b d n) Cpp.filter_den_relative)) = true ->
  rounded_encloses (renc_R (filter_enclosure_b (stage1_den_b d n) Cpp.filter_den_relative))
    (ray_den (vec_R d) (vec_R n)).
Proof.
  intros [dx dy dz] [nx ny nz] Fr. unfold stage1_den_b in *. cbn [vxb vyb vzb] in *.
  apply filter_enclosure_b_encloses; [vm_compute; reflexivity | | exact Fr].
  intros _ _ _. rewrite ray_den_bits. cbn [vxb vyb vzb]. rewrite cpp_filter_den_relative.
  apply den_filter_encloses.
Qed.

Lemma filter_delta_twin_sound : forall o d pa na pb nb : Vec3B,
  certifies (compare_quotients_filter_b
               (filter_enclosure_b (stage1_num_b o pa na) Cpp.filter_num_relative)
               (filter_enclosure_b (stage1_den_b d na) Cpp.filter_den_relative)
               (filter_enclosure_b (stage1_num_b o pb nb) Cpp.filter_num_relative)
               (filter_enclosure_b (stage1_den_b d nb) Cpp.filter_den_relative))
    (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
     ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)).
Proof.
  intros o d pa na pb nb.
  set (e1 := filter_enclosure_b (stage1_num_b o pa na) Cpp.filter_num_relative).
  set (e2 := filter_enclosure_b (stage1_den_b d na) Cpp.filter_den_relative).
  set (e3 := filter_enclosure_b (stage1_num_b o pb nb) Cpp.filter_num_relative).
  set (e4 := filter_enclosure_b (stage1_den_b d nb) Cpp.filter_den_relative).
  assert (NN : forall r C, nonneg C -> r = stage1_num_b o pa na \/ r = stage1_den_b d na \/
                 r = stage1_num_b o pb nb \/ r = stage1_den_b d nb -> nonneg (rradiusb (filter_enclosure_b r C))).
  { intros r C NC Hr. apply filter_radius_nonneg; [exact NC|].
    destruct Hr as [ -> | [ -> | [ -> | -> ]]]; apply stage1_magnitude_nonneg. }
  assert (Cn : nonneg Cpp.filter_num_relative) by const_nonneg.
  assert (Cd : nonneg Cpp.filter_den_relative) by const_nonneg.
  destruct (compare_quotients_filter_b e1 e2 e3 e4) eqn:S; try exact I;
  (destruct (compare_quotients_filter_twin e1 e2 e3 e4 (NN _ _ Cn (or_introl eq_refl))
     (NN _ _ Cd (or_intror (or_introl eq_refl))) (NN _ _ Cn (or_intror (or_intror (or_introl eq_refl))))
     (NN _ _ Cd (or_intror (or_intror (or_intror eq_refl)))) ltac:(rewrite S; discriminate))
     as [_ [F1 [_ [F2 [_ [F3 [_ [F4 E]]]]]]]];
   rewrite S in E; rewrite E;
   apply compare_quotients_filter_sound;
     [apply binary64_B2R .. | apply filter_num_encloses_b; exact F1 | apply filter_den_encloses_b; exact F2
     | apply filter_num_encloses_b; exact F3 | apply filter_den_encloses_b; exact F4]).
Qed.

Lemma compensated_delta_twin_sound : forall o d pa na pb nb : Vec3B,
  certifies (sign_from_Z (enclosure_sign_lanes_b
               (compare_quotients_compensated_b (stage2_num_b o pa na) (stage2_den_b d na)
                                                (stage2_num_b o pb nb) (stage2_den_b d nb))))
    (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
     ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)).
Proof.
  intros [ox oy oz] [dx dy dz] [pax pay paz] [nax nay naz] [pbx pby pbz] [nbx nby nbz].
  rewrite !ray_num_bits, !ray_den_bits. cbn [vxb vyb vzb].
  exact (hit_order_compensated_twin_sound_total ox oy oz dx dy dz pax pay paz nax nay naz pbx pby pbz nbx nby nbz).
Qed.

Lemma expansion_delta_twin_sound : forall o d pa na pb nb : Vec3B,
  let '(xna, xda, xa) := ray_plane_expansions_b two_sum_b o d pa na in
  let '(xnb, xdb, xb) := ray_plane_expansions_b two_sum_b o d pb nb in
  certifies (compare_quotients_expansion_b xna xda xa xnb xdb xb)
    (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
     ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)).
Proof.
  intros o d pa na pb nb.
  pose proof (PlaneQueryPairTwins.ray_plane_expansions_twin_exact o d pa na) as Xa.
  pose proof (PlaneQueryPairTwins.ray_plane_expansions_twin_exact o d pb nb) as Xb.
  destruct o as [ox oy oz], d as [dx dy dz], pa as [pax pay paz], na as [nax nay naz], pb as [pbx pby pbz],
    nb as [nbx nby nbz].
  pose proof (length_build_expansions two_sum_b ox oy oz dx dy dz pax pay paz nax nay naz) as La.
  pose proof (length_build_expansions two_sum_b ox oy oz dx dy dz pbx pby pbz nbx nby nbz) as Lb.
  unfold ray_plane_expansions_b in *. cbn [vxb vyb vzb] in *.
  destruct (build_expansions_gen two_sum_b ox oy oz dx dy dz pax pay paz nax nay naz) as [[xna xda] xa].
  destruct (build_expansions_gen two_sum_b ox oy oz dx dy dz pbx pby pbz nbx nby nbz) as [[xnb xdb] xb].
  destruct La as [La1 La2]. destruct Lb as [Lb1 Lb2].
  pose proof (compare_quotients_expansion_sound xna xda xa xnb xdb xb ltac:(lia) ltac:(lia) ltac:(lia) ltac:(lia)) as S.
  destruct xa; [|exact I]. destruct xb; [|destruct (compare_quotients_expansion_gen _ _ _ _ true _ _ false) eqn:E;
    try exact I; unfold compare_quotients_expansion_gen in E; rewrite andb_false_r in E; discriminate].
  destruct (Xa eq_refl) as [_ [_ [Sna Sda]]]. destruct (Xb eq_refl) as [_ [_ [Snb Sdb]]].
  rewrite <- Sna, <- Sda, <- Snb, <- Sdb. exact S.
Qed.

(** ** The theorem *)

(** For every bit pattern of the ray and the two planes: when both candidates are hits (den ≠ 0,
    t = num/den ≥ 0) whose carried signs are certain and exact (the relation's signs), an order
    [compare_hit_distances] decides before the exact stage is sign(t_a − t_b) of the exact t. *)
Theorem compare_hit_distances_twin_correct : forall (o d pa na pb nb : Vec3B) (nsa dsa nsb dsb : sign),
  let Na := ray_num (vec_R o) (vec_R pa) (vec_R na) in let Da := ray_den (vec_R d) (vec_R na) in
  let Nb := ray_num (vec_R o) (vec_R pb) (vec_R nb) in let Db := ray_den (vec_R d) (vec_R nb) in
  certifies nsa Na -> nsa <> Uncertain -> certifies dsa Da -> dsa <> Uncertain -> Da <> 0 -> 0 <= Na / Da ->
  certifies nsb Nb -> nsb <> Uncertain -> certifies dsb Db -> dsb <> Uncertain -> Db <> 0 -> 0 <= Nb / Db ->
  let r := compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb in
  snd r <> 3%Z -> fst r = sign_of (Na / Da - Nb / Db).
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb Na Da Nb Db Cna Una Cda Uda Zda Pa Cnb Unb Cdb Udb Zdb Pb r Nx.
  subst r. unfold compare_hit_distances_b in *. cbv zeta in Nx |- *.
  destruct ((match nsa with Zero => true | _ => false end || match nsb with Zero => true | _ => false end)%bool)
    eqn:Org.
  { cbn [fst]. apply origin_order_correct; try assumption.
    apply orb_true_iff in Org. destruct Org as [H|H]; [left|right]; destruct nsa; try discriminate; destruct nsb;
      try discriminate; reflexivity. }
  pose proof (filter_delta_twin_sound o d pa na pb nb) as S1.
  destruct (is_certain_b (compare_quotients_filter_b _ _ _ _)) eqn:C1.
  { cbn [fst]. apply hit_distance_order_correct; try assumption. apply is_certain_b_true. exact C1. }
  pose proof (compensated_delta_twin_sound o d pa na pb nb) as S2.
  destruct (is_certain_b (sign_from_Z _)) eqn:C2.
  { cbn [fst]. apply hit_distance_order_correct; try assumption. apply is_certain_b_true. exact C2. }
  pose proof (expansion_delta_twin_sound o d pa na pb nb) as S3.
  destruct (ray_plane_expansions_b two_sum_b o d pa na) as [[xna xda] xa].
  destruct (ray_plane_expansions_b two_sum_b o d pb nb) as [[xnb xdb] xb].
  destruct (is_certain_b (compare_quotients_expansion_gen _ _ _ _ _ _ _ _)) eqn:C3; [|cbn [snd] in Nx; contradiction].
  cbn [fst]. apply hit_distance_order_correct; try assumption. apply is_certain_b_true. exact C3.
Qed.
