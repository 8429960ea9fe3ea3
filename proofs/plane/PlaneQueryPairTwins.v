(** * The Lanes2 forms of one ray–plane query, and stage 3 (plane/ray_plane_stages.hpp), tied to the models.

    PlaneQueryTwins.v's [fast_answer_pair_b] and [fast_relation_pair_b] are the one-query forms [fast_answer(o,
    d, p, n)] and [fast_relation(o, d, p, n)], which put den and num in the two lanes of a Lanes2: den's
    lane computes a_i = d_i ⊖ 0 and its TwoDiff low part, as num's lane computes p_i ⊖ o_i.  This file
    proves the conclusions of [fast_relation_twin_correct] and [fast_answer_twin_correct] for them, by
    reusing those theorems rather than repeating their proofs:
    - [fast_relation_pair_b_eq]: the pair form IS [fast_relation_b] (x ⊖ +0 = x for every bit pattern),
      so [fast_relation_pair_twin_correct] is [fast_relation_twin_correct];
    - [fast_answer_pair_twin_correct]: d_i ⊖ 0's rounded part is d_i for every bit pattern
      ([two_diff_zero_hi]), so stage 1 is the same; den's stage-2 enclosure is num's formula with o = 0,
      whose low parts are fma(0, n_i, l_i) where [fast_answer_b] has l_i (the same real, not always the
      same bits: a zero l_i may differ in sign), so the pair twin is an instance of
      [fast_answer_from_twin_correct] (PlaneQueryTwins.v) with that enclosure, which encloses den and certifies
      den's sign ([num_compensated_encloses_b], [num_compensated_twin_sound] with o = 0);
    - [ray_plane_expansions_twin_exact]: when the builder's flag says exact, the expansions of
      [ray_plane_expansions_b] (the twin of ray_plane_expansions, with TwoSum) are finite and sum exactly
      to num = (p − o)·n and den = d·n of the query (Expansions.v's [build_expansions_exact]).  The flag
      is computed by the code itself (every TwoProduct passed its guard, every component finite), so the
      hypothesis is what the consumers test: the cascade and compare_quotients_expansion use the expansions
      only when it holds. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification QuotientRounding PlaneCascade FloatCore
  ConstantsCpp PlaneTwins Expansions PlaneQueryTwins PlaneStageTwoFinite.
Open Scope R_scope.

(** x ⊖ +0 = x, bit for bit, for every x (−0 ⊖ +0 = −0 in round to nearest). *)
Lemma fsub_zero_r : forall x, fsub x fzero = x.
Proof. intros [[|]|[|]| |s m e H]; reflexivity. Qed.

(** two_diff(x, 0).hi = x ⊕ (−0) = x, bit for bit. *)
Lemma two_diff_zero_hi : forall x, fst (two_diff_b x fzero) = x.
Proof. intros [[|]|[|]| |s m e H]; reflexivity. Qed.

Lemma fast_relation_pair_b_eq : forall o d p n, fast_relation_pair_b o d p n = fast_relation_b o d p n.
Proof. intros o d p n. unfold fast_relation_pair_b, fast_relation_b. rewrite !fsub_zero_r. reflexivity. Qed.

(** [fast_relation(o, d, p, n)] (the Lanes2 form, what [relation] runs for one query): the conclusions of
    [fast_relation_twin_correct], for every bit pattern. *)
Theorem fast_relation_pair_twin_correct : forall o d p n : Vec3B,
  snd (fast_relation_pair_b o d p n) = true ->
  vec_fin o /\ vec_fin d /\ vec_fin p /\ vec_fin n /\
  (if fst (fast_relation_pair_b o d p n) then Behind else Hit) = classify (vec_R o) (vec_R d) (vec_R p) (vec_R n) /\
  ray_num (vec_R o) (vec_R p) (vec_R n) <> 0 /\ ray_den (vec_R d) (vec_R n) <> 0 /\
  vec_R d <> zero3 /\ vec_R n <> zero3.
Proof. intros o d p n. rewrite fast_relation_pair_b_eq. apply fast_relation_twin_correct. Qed.

(** The pair form as [fast_answer_from_b]: den's lane is num's formula with o = 0. *)
Lemma fast_answer_pair_b_eq : forall ox oy oz dx dy dz px py pz nx ny nz,
  fast_answer_pair_b (V3 ox oy oz) (V3 dx dy dz) (V3 px py pz) (V3 nx ny nz) =
  fast_answer_from_b (dot3_filter_lanes_b (dot3_rounded_b dx dy dz nx ny nz) Cpp.filter_den_relative)
    (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b px ox)) (fst (two_diff_b py oy)) (fst (two_diff_b pz oz))
       nx ny nz) Cpp.filter_num_relative)
    (num_compensated_b dx dy dz fzero fzero fzero nx ny nz) (num_compensated_b px py pz ox oy oz nx ny nz).
Proof.
  intros.
  change (fast_answer_pair_b (V3 ox oy oz) (V3 dx dy dz) (V3 px py pz) (V3 nx ny nz)) with
    (fast_answer_from_b (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b dx fzero)) (fst (two_diff_b dy fzero))
         (fst (two_diff_b dz fzero)) nx ny nz) Cpp.filter_den_relative)
      (dot3_filter_lanes_b (dot3_rounded_b (fst (two_diff_b px ox)) (fst (two_diff_b py oy)) (fst (two_diff_b pz oz))
         nx ny nz) Cpp.filter_num_relative)
      (num_compensated_b dx dy dz fzero fzero fzero nx ny nz) (num_compensated_b px py pz ox oy oz nx ny nz)).
  rewrite !two_diff_zero_hi. reflexivity.
Qed.

Lemma den_as_num_value : forall dx dy dz nx ny nz,
  (B2R dx - B2R fzero) * B2R nx + (B2R dy - B2R fzero) * B2R ny + (B2R dz - B2R fzero) * B2R nz =
  ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz)).
Proof. intros. change (B2R fzero) with 0. unfold ray_den, dot, vec_R. cbn. ring. Qed.

(** den as num with o = 0 (the Lanes2 form's den), what [fast_answer_from_twin_correct] asks of it. *)
Lemma den_pair_encloses_fin : forall dx dy dz nx ny nz,
  let e := num_compensated_b dx dy dz fzero fzero fzero nx ny nz in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  encloses (enc_R e) (ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz))) /\ vec_fin (V3 dx dy dz) /\
  vec_fin (V3 nx ny nz).
Proof.
  intros dx dy dz nx ny nz e Fh Fl Fr.
  pose proof (num_compensated_encloses_b dx dy dz fzero fzero fzero nx ny nz Fh Fl Fr) as E.
  rewrite den_as_num_value in E. split; [exact E|].
  destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [A0 [A1 [A2 [? [? [? _]]]]]]]]].
  destruct (two_diff_b_parts _ _ A0) as [? _]. destruct (two_diff_b_parts _ _ A1) as [? _].
  destruct (two_diff_b_parts _ _ A2) as [? _].
  unfold vec_fin. cbn [vxb vyb vzb]. repeat split; assumption.
Qed.

Lemma den_pair_certifies : forall dx dy dz nx ny nz,
  let e := num_compensated_b dx dy dz fzero fzero fzero nx ny nz in fin (hib e) = true -> fin (lob e) = true ->
  certifies (sign_from_Z (enclosure_sign_lanes_b e)) (ray_den (vec_R (V3 dx dy dz)) (vec_R (V3 nx ny nz))).
Proof.
  intros dx dy dz nx ny nz e Fh Fl. rewrite <- den_as_num_value.
  exact (proj1 (num_compensated_twin_sound dx dy dz fzero fzero fzero nx ny nz Fh Fl)).
Qed.

(** [fast_answer(o, d, p, n)] (the Lanes2 form, what [intersect] runs for one query): the conclusions of
    [fast_answer_twin_correct], for every bit pattern of o, d, p, n. *)
Theorem fast_answer_pair_twin_correct : forall o d p n : Vec3B,
  let a := fast_answer_pair_b o d p n in
  snd (fst a) = true -> fast_answer_means o d p n (fst (fst (fst a))) (snd (fst (fst a))).
Proof. fast_answer_from_intro fast_answer_pair_b_eq num_radius_nonneg den_pair_encloses_fin den_pair_certifies. Qed.

(** Stage 3: [ray_plane_expansions] (TwoSum throughout), exact when its flag says so. *)
Theorem ray_plane_expansions_twin_exact : forall o d p n : Vec3B,
  let '(num, den, exact) := ray_plane_expansions_b two_sum_b o d p n in
  exact = true ->
  all_fin num /\ all_fin den /\
  sumR num = ray_num (vec_R o) (vec_R p) (vec_R n) /\ sumR den = ray_den (vec_R d) (vec_R n).
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [nx ny nz].
  unfold ray_plane_expansions_b. cbn [vxb vyb vzb].
  pose proof (build_expansions_exact ox oy oz dx dy dz px py pz nx ny nz) as H.
  destruct (build_expansions_b ox oy oz dx dy dz px py pz nx ny nz) as [[num den] ex].
  intros Ex. destruct (H Ex) as [Fn [Fd [Sd Sn]]].
  split; [exact Fn|]. split; [exact Fd|]. split.
  - rewrite Sn. unfold ray_num, dot, sub, vec_R. cbn. ring.
  - rewrite Sd. unfold ray_den, dot, vec_R. cbn. ring.
Qed.
