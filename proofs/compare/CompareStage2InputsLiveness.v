(** * Liveness of stage 2 of nearest_hit's comparison, in the words of the ray and the planes (issue 16).

    CompareStage2Liveness.v's [compare_hit_distances_stage2_live_exact] states its class on the four stage-2
    enclosures (S', ρ' over their renormalized heads and radii).  Here the same class is bounded by the inputs:
    for a ray (o, d) and planes (p_a, n_a), (p_b, n_b) whose coordinates are finite doubles of magnitude
    ≤ 2^180, with

      P_x = Σ|(p_i − o_i)·n_i| (num's magnitude), D_x = Σ|d_i·n_i| (den's magnitude),
      R(P) = (2^-100 + 2^-152)·P + 2^-1062 (a stage-2 radius, from PlaneLiveness.v's [compensated_radius_upper]),
      H(P) = (1 + 2^-52)·P + 2^-1061 (a stage-2 head: |head| ≤ (1 + u)(|V| + radius), |V| ≤ P),

    - [stage2_num_bounded], [stage2_den_bounded]: every part of the stage-2 enclosures is below 2^400 (the
      hypothesis of CompareStage2Liveness.v's class);
    - [stage2_num_facts], [stage2_den_facts]: the radius is at most R(P), the head at most H(P);
    - [compare_hit_distances_stage2_live_inputs]: [compare_hit_distances_b] returns by stage 2 at the latest
      whenever the exact Δ = num_a·den_b − num_b·den_a exceeds

        k_1·(H(P_a)·H(D_b) + H(P_b)·H(D_a))
          + k_2'·(H(P_a)·R(D_b) + R(P_a)·(H(D_b) + R(D_b)) + H(P_b)·R(D_a) + R(P_b)·(H(D_a) + R(D_a))) + k_3

      (k_1, k_2' = 3 + 2^-37, k_3 of CompareStage2Liveness.v), a bound of size ≈ 9.25·2^-100·(P_a·D_b + P_b·D_a);
    - [compare_hit_distances_stage2_live_inputs_simple]: the simpler class |Δ| > 2^-96·(P_a·D_b + P_b·D_a) + 2^-600
      ([pnum_le], [pden_le]: P, D ≤ 2^363; [products_upper]: the products of heads and radii are their leading
      terms plus at most 2^-690);
    - not vacuous: [compare_hit_distances_stage2_inputs_example_in_class],
      [compare_hit_distances_stage2_inputs_simple_example]: the ray and planes of CompareStage2Liveness.v's
      [compare_hit_distances_stage2_example] (t_a = 1, t_b = 1 + 2^-60, stage 1 uncertain, stage 2 decides) are in
      both classes.  The bound is in the magnitudes P, D, not in |num|, |den|: it is loose by P/|num| when num's
      dot product cancels. *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins CompareTwins PlaneLiveness PlaneQueryTwins PlaneStageTwoFinite NearestTwins CompareStage1Liveness CompareStage2Radius
  CompareStage2Liveness.
Open Scope R_scope.

Definition vbnd (k : Z) (v : Vec3B) : Prop := fbnd k (vxb v) /\ fbnd k (vyb v) /\ fbnd k (vzb v).

Definition pnum (o p n : Vec3B) : R :=
  Rabs ((B2R (vxb p) - B2R (vxb o)) * B2R (vxb n)) + Rabs ((B2R (vyb p) - B2R (vyb o)) * B2R (vyb n)) +
  Rabs ((B2R (vzb p) - B2R (vzb o)) * B2R (vzb n)).
Definition pden (d n : Vec3B) : R :=
  Rabs (B2R (vxb d) * B2R (vxb n)) + Rabs (B2R (vyb d) * B2R (vyb n)) + Rabs (B2R (vzb d) * B2R (vzb n)).

Definition rad_of (P : R) : R := (bpow radix2 (-100) + bpow radix2 (-152)) * P + bpow radix2 (-1062).
Definition head_of (P : R) : R := (1 + bpow radix2 (-52)) * P + bpow radix2 (-1061).

(** ** No overflow *)

Lemma stage2_num_bounded : forall o p n, vbnd 180 o -> vbnd 180 p -> vbnd 180 n ->
  let e := stage2_num_b o p n in fbnd 400 (hib e) /\ fbnd 400 (lob e) /\ fbnd 400 (radiusb e).
Proof.
  intros [ox oy oz] [px py pz] [nx ny nz] [O0 [O1 O2]] [P0 [P1 P2]] [N0 [N1 N2]]. cbn [vxb vyb vzb] in *.
  unfold stage2_num_b, num_compensated_b, two_diff_b, compensated_dot3_b, compensated_from_low_parts_b,
    dot3_rounded_b. cbv zeta. cbn [vxb vyb vzb qb0 qb1 qb2 magnitudeb hib lob radiusb].
  split; [|split]; (eapply fbnd_le; [fbnd_tac | zle]).
Qed.

Lemma stage2_den_bounded : forall d n, vbnd 180 d -> vbnd 180 n ->
  let e := stage2_den_b d n in fbnd 400 (hib e) /\ fbnd 400 (lob e) /\ fbnd 400 (radiusb e).
Proof.
  intros [dx dy dz] [nx ny nz] [D0 [D1 D2]] [N0 [N1 N2]]. cbn [vxb vyb vzb] in *.
  unfold stage2_den_b, den_compensated_b, compensated_dot3_exact_b, compensated_from_low_parts_b,
    dot3_rounded_b. cbv zeta. cbn [vxb vyb vzb qb0 qb1 qb2 magnitudeb hib lob radiusb].
  split; [|split]; (eapply fbnd_le; [fbnd_tac | zle]).
Qed.

(** ** Radius and head from above *)

(** The head RN(hi + lo) is at most (1 + u)·(|V| + radius) for any V the enclosure encloses. *)
Lemma head_upper : forall e V, binary64 (hi e) -> binary64 (lo e) -> encloses e V ->
  Rabs (head e) <= (1 + u) * (Rabs V + radius e).
Proof.
  intros e V Bh Bl E. unfold head, two_sum. cbv zeta. cbn [fst].
  pose proof (RN_plus_err (hi e) (lo e) Bh Bl) as R. unfold encloses in E.
  pose proof (Rabs_triang_inv (RN (hi e + lo e)) (hi e + lo e)) as T1.
  pose proof (Rabs_triang_inv (hi e + lo e) V) as T2. rewrite Rabs_minus_sym in E.
  pose proof u_pos. pose proof (Rabs_pos (hi e + lo e)).
  assert (Rabs (hi e + lo e) <= Rabs V + radius e) by lra.
  assert (u * Rabs (hi e + lo e) <= u * (Rabs V + radius e)) by (apply Rmult_le_compat_l; lra). lra.
Qed.

Lemma head_of_upper : forall e V P, binary64 (hi e) -> binary64 (lo e) -> encloses e V -> Rabs V <= P ->
  radius e <= rad_of P -> Rabs (head e) <= head_of P.
Proof.
  intros e V P Bh Bl E HV Hr. pose proof (head_upper e V Bh Bl E) as H.
  assert (P0 : 0 <= P) by (pose proof (Rabs_pos V); lra).
  unfold rad_of, head_of in *. pose proof u_pos.
  set (a := bpow radix2 (-100) + bpow radix2 (-152)) in *.
  set (w := bpow radix2 (-1062)) in *.
  assert (A : (1 + u) * (Rabs V + radius e) <= (1 + u) * (P + (a * P + w)))
    by (apply Rmult_le_compat_l; lra).
  assert (B : w * (1 + u) <= bpow radix2 (-1061)).
  { replace (-1061)%Z with (1 + -1062)%Z by reflexivity. rewrite bpow_plus. unfold w.
    pose proof (bpow_gt_0 radix2 (-1062)). rewrite u_val. simpl (bpow radix2 1). simpl (bpow radix2 (-53)). lra. }
  assert (C : P * ((1 + u) * (1 + a)) <= P * (1 + bpow radix2 (-52))).
  { apply Rmult_le_compat_l; [exact P0|]. unfold a. rewrite u_val. simpl bpow. lra. }
  replace ((1 + u) * (P + (a * P + w))) with (P * ((1 + u) * (1 + a)) + w * (1 + u)) in A by ring.
  lra.
Qed.

Lemma ray_num_upper : forall o p n, Rabs (ray_num (vec_R o) (vec_R p) (vec_R n)) <= pnum o p n.
Proof.
  intros. rewrite ray_num_bits. unfold pnum.
  eapply Rle_trans; [apply Rabs_triang|]. apply Rplus_le_compat_r. apply Rabs_triang.
Qed.

Lemma ray_den_upper : forall d n, Rabs (ray_den (vec_R d) (vec_R n)) <= pden d n.
Proof.
  intros. rewrite ray_den_bits. unfold pden.
  eapply Rle_trans; [apply Rabs_triang|]. apply Rplus_le_compat_r. apply Rabs_triang.
Qed.

Lemma stage2_num_facts : forall o p n, vbnd 180 o -> vbnd 180 p -> vbnd 180 n ->
  let e := stage2_num_b o p n in
  B2R (radiusb e) <= rad_of (pnum o p n) /\ Rabs (head (enc_R e)) <= head_of (pnum o p n).
Proof.
  intros o p n Bo Bp Bn e.
  destruct (stage2_num_bounded o p n Bo Bp Bn) as [[Fh _] [[Fl _] [Fr _]]]. fold e in Fh, Fl, Fr.
  pose proof (num_compensated_encloses_b (vxb p) (vyb p) (vzb p) (vxb o) (vyb o) (vzb o) (vxb n) (vyb n) (vzb n)
                Fh Fl Fr) as Enc. rewrite <- ray_num_bits in Enc.
  assert (Rd : B2R (radiusb e) <= rad_of (pnum o p n)).
  { destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [A0 [A1 [A2 [? [? [? [_ [_ E]]]]]]]]]]].
    destruct (two_diff_b_parts _ _ A0) as [Bp0 [Bo0 [X0 _]]]. destruct (two_diff_b_parts _ _ A1) as [Bp1 [Bo1 [X1 _]]].
    destruct (two_diff_b_parts _ _ A2) as [Bp2 [Bo2 [X2 _]]].
    change (B2R (radiusb e)) with (radius (enc_R e)). unfold e, stage2_num_b, num_compensated_b. cbv zeta.
    rewrite E.
    pose proof (compensated_radius_upper (B2R (fst (two_diff_b (vxb p) (vxb o))))
                  (B2R (fst (two_diff_b (vyb p) (vyb o)))) (B2R (fst (two_diff_b (vzb p) (vzb o))))
                  (B2R (snd (two_diff_b (vxb p) (vxb o)))) (B2R (snd (two_diff_b (vyb p) (vyb o))))
                  (B2R (snd (two_diff_b (vzb p) (vzb o)))) (B2R (vxb n)) (B2R (vyb n)) (B2R (vzb n))) as U.
    cbv zeta in U. rewrite X0, X1, X2 in U |- *.
    assert (D : forall a b c, Rabs (RN (B2R a - B2R b) * B2R c) <= (1 + u) * Rabs ((B2R a - B2R b) * B2R c)).
    { intros a b c. rewrite !Rabs_mult. pose proof (RN_minus_err (B2R a) (B2R b) (binary64_B2R _) (binary64_B2R _)).
      pose proof (Rabs_triang_inv (RN (B2R a - B2R b)) (B2R a - B2R b)). pose proof (Rabs_pos (B2R c)).
      assert (Rabs (RN (B2R a - B2R b)) <= (1 + u) * Rabs (B2R a - B2R b)) by lra. nra. }
    pose proof (D (vxb p) (vxb o) (vxb n)). pose proof (D (vyb p) (vyb o) (vyb n)).
    pose proof (D (vzb p) (vzb o) (vzb n)). unfold rad_of. fold (pnum o p n) in *.
    set (Sr := Rabs (RN (B2R (vxb p) - B2R (vxb o)) * B2R (vxb n)) + Rabs (RN (B2R (vyb p) - B2R (vyb o)) * B2R (vyb n))
               + Rabs (RN (B2R (vzb p) - B2R (vzb o)) * B2R (vzb n))) in U.
    assert (Sle : Sr <= (1 + u) * pnum o p n) by (unfold Sr, pnum; lra).
    assert (E98 : bpow radix2 (-98) = 4 * bpow radix2 (-100)) by (simpl bpow; lra).
    assert (E1060 : bpow radix2 (-1060) = 4 * bpow radix2 (-1062)).
    { replace (-1060)%Z with (2 + -1062)%Z by reflexivity. rewrite bpow_plus. simpl (bpow radix2 2). lra. }
    assert (M : bpow radix2 (-100) * Sr <= bpow radix2 (-100) * ((1 + u) * pnum o p n))
      by (apply Rmult_le_compat_l; [apply bpow_ge_0 | exact Sle]).
    assert (K : bpow radix2 (-100) * (1 + u) <= bpow radix2 (-100) + bpow radix2 (-152))
      by (rewrite u_val; simpl bpow; lra).
    assert (P0 : 0 <= pnum o p n) by (unfold pnum; pose proof (Rabs_pos ((B2R (vxb p) - B2R (vxb o)) * B2R (vxb n)));
      pose proof (Rabs_pos ((B2R (vyb p) - B2R (vyb o)) * B2R (vyb n)));
      pose proof (Rabs_pos ((B2R (vzb p) - B2R (vzb o)) * B2R (vzb n))); lra).
    assert (K2 : bpow radix2 (-100) * (1 + u) * pnum o p n <= (bpow radix2 (-100) + bpow radix2 (-152)) * pnum o p n)
      by (apply Rmult_le_compat_r; assumption).
    rewrite E98, E1060 in U. lra. }
  split; [exact Rd|].
  exact (head_of_upper (enc_R e) _ _ (binary64_B2R (hib e)) (binary64_B2R (lob e)) Enc (ray_num_upper o p n) Rd).
Qed.

Lemma stage2_den_facts : forall d n, vbnd 180 d -> vbnd 180 n ->
  let e := stage2_den_b d n in
  B2R (radiusb e) <= rad_of (pden d n) /\ Rabs (head (enc_R e)) <= head_of (pden d n).
Proof.
  intros d n Bd Bn e.
  destruct (stage2_den_bounded d n Bd Bn) as [[Fh _] [[Fl _] [Fr _]]]. fold e in Fh, Fl, Fr.
  pose proof (den_compensated_encloses_b (vxb d) (vyb d) (vzb d) (vxb n) (vyb n) (vzb n) Fh Fl Fr) as Enc.
  rewrite <- ray_den_bits in Enc.
  assert (Rd : B2R (radiusb e) <= rad_of (pden d n)).
  { destruct (compensated_dot3_exact_twin _ _ _ _ _ _ Fr Fh Fl) as [? [? [? [? [? [? E]]]]]].
    change (B2R (radiusb e)) with (radius (enc_R e)). unfold e, stage2_den_b, den_compensated_b. rewrite E.
    pose proof (compensated_radius_upper (B2R (vxb d)) (B2R (vyb d)) (B2R (vzb d)) 0 0 0
                  (B2R (vxb n)) (B2R (vyb n)) (B2R (vzb n))) as U.
    cbv zeta in U. unfold rad_of, pden. pose proof (Rabs_pos (B2R (vxb d) * B2R (vxb n))).
    pose proof (Rabs_pos (B2R (vyb d) * B2R (vyb n))). pose proof (Rabs_pos (B2R (vzb d) * B2R (vzb n))).
    assert (E98 : bpow radix2 (-98) = 4 * bpow radix2 (-100)) by (simpl bpow; lra).
    assert (E1060 : bpow radix2 (-1060) = 4 * bpow radix2 (-1062)).
    { replace (-1060)%Z with (2 + -1062)%Z by reflexivity. rewrite bpow_plus. simpl (bpow radix2 2). lra. }
    pose proof (bpow_ge_0 radix2 (-152)).
    assert (0 <= bpow radix2 (-152) * (Rabs (B2R (vxb d) * B2R (vxb n)) + Rabs (B2R (vyb d) * B2R (vyb n)) +
                                       Rabs (B2R (vzb d) * B2R (vzb n)))) by (apply Rmult_le_pos; lra).
    rewrite E98, E1060 in U. lra. }
  split; [exact Rd|].
  exact (head_of_upper (enc_R e) _ _ (binary64_B2R (hib e)) (binary64_B2R (lob e)) Enc (ray_den_upper d n) Rd).
Qed.

(** ** The class in the inputs *)

(** S' and ρ' grow with the heads' magnitudes and the radii. *)
Lemma class_bound_mono : forall h1 r1 h2 r2 h3 r3 h4 r4 H1 R1 H2 R2 H3 R3 H4 R4,
  0 <= r1 -> 0 <= r2 -> 0 <= r3 -> 0 <= r4 ->
  Rabs h1 <= H1 -> r1 <= R1 -> Rabs h2 <= H2 -> r2 <= R2 -> Rabs h3 <= H3 -> r3 <= R3 -> Rabs h4 <= H4 -> r4 <= R4 ->
  k1 * cross_magnitude h1 h2 h3 h4 + k2_exact * propagated_exact h1 r1 h2 r2 h3 r3 h4 r4 + k3 <=
  k1 * (H1 * H4 + H3 * H2) + k2_exact * (H1 * R4 + R1 * (H4 + R4) + (H3 * R2 + R3 * (H2 + R2))) + k3.
Proof.
  intros h1 r1 h2 r2 h3 r3 h4 r4 H1 R1 H2 R2 H3 R3 H4 R4 P1 P2 P3 P4 A1 B1 A2 B2 A3 B3 A4 B4.
  unfold cross_magnitude, propagated_exact. rewrite !Rabs_mult.
  pose proof (Rabs_pos h1). pose proof (Rabs_pos h2). pose proof (Rabs_pos h3). pose proof (Rabs_pos h4).
  assert (K1 : 0 <= k1) by (unfold k1; pose proof (bpow_ge_0 radix2 (-102)); lra).
  assert (K2 : 0 <= k2_exact) by (unfold k2_exact; pose proof (bpow_ge_0 radix2 (-37)); lra).
  assert (S : Rabs h1 * Rabs h4 + Rabs h3 * Rabs h2 <= H1 * H4 + H3 * H2).
  { apply Rplus_le_compat; apply Rmult_le_compat; lra. }
  assert (Q : Rabs h1 * r4 + r1 * (Rabs h4 + r4) + (Rabs h3 * r2 + r3 * (Rabs h2 + r2)) <=
              H1 * R4 + R1 * (H4 + R4) + (H3 * R2 + R3 * (H2 + R2))).
  { repeat apply Rplus_le_compat; apply Rmult_le_compat; lra. }
  apply Rplus_le_compat_r. apply Rplus_le_compat; apply Rmult_le_compat_l; assumption.
Qed.

(** Stage 2 of nearest_hit's comparison decides, on the twin, for a ray and two planes of coordinates at most
    2^180, whenever the exact Δ = num_a·den_b − num_b·den_a exceeds the bound in P_a, D_a, P_b, D_b. *)
Theorem compare_hit_distances_stage2_live_inputs : forall o d pa na pb nb nsa dsa nsb dsb,
  vbnd 180 o -> vbnd 180 d -> vbnd 180 pa -> vbnd 180 na -> vbnd 180 pb -> vbnd 180 nb ->
  let Pa := pnum o pa na in let Da := pden d na in let Pb := pnum o pb nb in let Db := pden d nb in
  k1 * (head_of Pa * head_of Db + head_of Pb * head_of Da) +
    k2_exact * (head_of Pa * rad_of Db + rad_of Pa * (head_of Db + rad_of Db) +
                (head_of Pb * rad_of Da + rad_of Pb * (head_of Da + rad_of Da))) + k3 <
    Rabs (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
          ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)) ->
  (snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <= 1)%Z.
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb Bo Bd Bpa Bna Bpb Bnb Pa Da Pb Db L.
  destruct (stage2_num_bounded o pa na Bo Bpa Bna) as [Hn1 [Ln1 En1]].
  destruct (stage2_den_bounded d na Bd Bna) as [Hd1 [Ld1 Fd1]].
  destruct (stage2_num_bounded o pb nb Bo Bpb Bnb) as [Hn2 [Ln2 En2]].
  destruct (stage2_den_bounded d nb Bd Bnb) as [Hd2 [Ld2 Fd2]].
  destruct (stage2_num_facts o pa na Bo Bpa Bna) as [Rn1 An1].
  destruct (stage2_den_facts d na Bd Bna) as [Rd1 Ad1].
  destruct (stage2_num_facts o pb nb Bo Bpb Bnb) as [Rn2 An2].
  destruct (stage2_den_facts d nb Bd Bnb) as [Rd2 Ad2].
  assert (Pos : forall e V, fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
                encloses (enc_R e) V -> 0 <= B2R (radiusb e)).
  { intros e V _ _ _ H. eapply Rle_trans; [apply Rabs_pos | exact H]. }
  pose proof (Pos _ _ (proj1 Hn1) (proj1 Ln1) (proj1 En1)
                (num_compensated_encloses_b _ _ _ _ _ _ _ _ _ (proj1 Hn1) (proj1 Ln1) (proj1 En1))) as Pn1.
  pose proof (Pos _ _ (proj1 Hd1) (proj1 Ld1) (proj1 Fd1)
                (den_compensated_encloses_b _ _ _ _ _ _ (proj1 Hd1) (proj1 Ld1) (proj1 Fd1))) as Pd1.
  pose proof (Pos _ _ (proj1 Hn2) (proj1 Ln2) (proj1 En2)
                (num_compensated_encloses_b _ _ _ _ _ _ _ _ _ (proj1 Hn2) (proj1 Ln2) (proj1 En2))) as Pn2.
  pose proof (Pos _ _ (proj1 Hd2) (proj1 Ld2) (proj1 Fd2)
                (den_compensated_encloses_b _ _ _ _ _ _ (proj1 Hd2) (proj1 Ld2) (proj1 Fd2))) as Pd2.
  apply (compare_hit_distances_stage2_live_exact o d pa na pb nb nsa dsa nsb dsb Hn1 Ln1 En1 Hd1 Ld1 Fd1
           Hn2 Ln2 En2 Hd2 Ld2 Fd2).
  eapply Rle_lt_trans; [| exact L].
  apply class_bound_mono; assumption.
Qed.

(** ** Not vacuous *)

Lemma head_of_le2 : forall P, 0 <= P -> P <= 3 / 2 -> 0 <= head_of P <= 2.
Proof.
  intros P P0 P1. unfold head_of.
  assert (A : bpow radix2 (-1061) <= 1 / 4) by (apply Rle_trans with (bpow radix2 (-2)); [apply bpow_le; lia | simpl bpow; lra]).
  pose proof (bpow_ge_0 radix2 (-1061)). simpl (bpow radix2 (-52)). split; [nra | nra].
Qed.

Lemma rad_of_small : forall P, 0 <= P -> P <= 3 / 2 -> 0 <= rad_of P <= bpow radix2 (-97).
Proof.
  intros P P0 P1. unfold rad_of.
  assert (A : bpow radix2 (-1062) <= bpow radix2 (-99)) by (apply bpow_le; lia).
  pose proof (bpow_ge_0 radix2 (-1062)).
  assert (E : bpow radix2 (-97) = 4 * bpow radix2 (-99) /\ bpow radix2 (-100) = bpow radix2 (-99) / 2 /\
              bpow radix2 (-152) <= bpow radix2 (-99) / 4) by (simpl bpow; lra).
  pose proof (bpow_gt_0 radix2 (-99)). destruct E as [E1 [E2 E3]]. rewrite E1, E2.
  pose proof (bpow_ge_0 radix2 (-152)). split; nra.
Qed.

(** The ray and planes of CompareStage2Liveness.v's [compare_hit_distances_stage2_example] (t_a = 1, t_b = 1 + 2^-60;
    stage 1 uncertain, [compare_hit_distances_b] returns from stage 2) are in the class of
    [compare_hit_distances_stage2_live_inputs]: P_a = D_a = D_b = 1, P_b = 1 + 2^-60, |Δ| = 2^-60. *)
Example compare_hit_distances_stage2_inputs_example_in_class :
  (vbnd 180 wo /\ vbnd 180 wd /\ vbnd 180 wpa /\ vbnd 180 wna /\ vbnd 180 wpb /\ vbnd 180 wnb) /\
  let Pa := pnum wo wpa wna in let Da := pden wd wna in let Pb := pnum wo wpb wnb in let Db := pden wd wnb in
  k1 * (head_of Pa * head_of Db + head_of Pb * head_of Da) +
    k2_exact * (head_of Pa * rad_of Db + rad_of Pa * (head_of Db + rad_of Db) +
                (head_of Pb * rad_of Da + rad_of Pb * (head_of Da + rad_of Da))) + k3 <
    Rabs (ray_num (vec_R wo) (vec_R wpa) (vec_R wna) * ray_den (vec_R wd) (vec_R wnb) -
          ray_num (vec_R wo) (vec_R wpb) (vec_R wnb) * ray_den (vec_R wd) (vec_R wna)).
Proof.
  pose proof (bpow_gt_0 radix2 (-60)) as P60.
  assert (B60 : bpow radix2 (-60) <= 1 / 4) by (apply Rle_trans with (bpow radix2 (-2)); [apply bpow_le; lia | simpl bpow; lra]).
  assert (F : forall x, fin x = true -> B2R x = 0 \/ B2R x = 1 \/ B2R x = bpow radix2 (-60) -> fbnd 180 x).
  { intros x Fx V. split; [exact Fx|]. apply Rle_trans with 1; [| apply (bpow_le radix2 0); lia].
    destruct V as [V | [V | V]]; rewrite V; [rewrite Rabs_R0 | rewrite Rabs_R1 | rewrite Rabs_pos_eq]; lra. }
  split.
  { unfold vbnd, wo, wd, wpa, wna, wpb, wnb. cbn [vxb vyb vzb].
    repeat split; try reflexivity; apply F; try reflexivity;
      rewrite ?w_one_val, ?w_zero_val, ?w_2m60_val; auto. }
  intros Pa Da Pb Db.
  assert (Va : Pa = 1 /\ Da = 1 /\ Db = 1 /\ Pb = 1 + bpow radix2 (-60)).
  { unfold Pa, Da, Pb, Db, pnum, pden, wo, wd, wpa, wna, wpb, wnb. cbn [vxb vyb vzb].
    rewrite w_one_val, w_zero_val, w_2m60_val.
    replace (1 - 0) with 1 by ring. replace (0 - 0) with 0 by ring. replace (bpow radix2 (-60) - 0) with (bpow radix2 (-60)) by ring.
    rewrite ?Rmult_1_l, ?Rmult_1_r, ?Rmult_0_l, ?Rmult_0_r, ?Rabs_R0, ?Rabs_R1, (Rabs_pos_eq (bpow radix2 (-60))) by lra.
    repeat split; ring. }
  destruct Va as [Va [Wa [Wb Vb]]].
  rewrite !ray_num_bits, !ray_den_bits. unfold wo, wd, wpa, wna, wpb, wnb. cbn [vxb vyb vzb].
  rewrite w_one_val, w_zero_val, w_2m60_val.
  match goal with |- _ < Rabs ?V => replace V with (- bpow radix2 (-60)) by ring end.
  rewrite Rabs_Ropp, (Rabs_pos_eq (bpow radix2 (-60))) by lra.
  assert (I1 : 0 <= Pa <= 3 / 2) by lra. assert (I2 : 0 <= Da <= 3 / 2) by lra.
  assert (I3 : 0 <= Pb <= 3 / 2) by lra. assert (I4 : 0 <= Db <= 3 / 2) by lra.
  destruct (head_of_le2 Pa (proj1 I1) (proj2 I1)) as [G1 L1]. destruct (rad_of_small Pa (proj1 I1) (proj2 I1)) as [S1 T1].
  destruct (head_of_le2 Da (proj1 I2) (proj2 I2)) as [G2 L2]. destruct (rad_of_small Da (proj1 I2) (proj2 I2)) as [S2 T2].
  destruct (head_of_le2 Pb (proj1 I3) (proj2 I3)) as [G3 L3]. destruct (rad_of_small Pb (proj1 I3) (proj2 I3)) as [S3 T3].
  destruct (head_of_le2 Db (proj1 I4) (proj2 I4)) as [G4 L4]. destruct (rad_of_small Db (proj1 I4) (proj2 I4)) as [S4 T4].
  pose proof (class_bound_mono (head_of Pa) (rad_of Pa) (head_of Da) (rad_of Da) (head_of Pb) (rad_of Pb)
                (head_of Db) (rad_of Db) 2 (bpow radix2 (-97)) 2 (bpow radix2 (-97)) 2 (bpow radix2 (-97))
                2 (bpow radix2 (-97)) S1 S2 S3 S4) as M.
  rewrite !Rabs_pos_eq in M by assumption.
  specialize (M L1 T1 L2 T2 L3 T3 L4 T4).
  unfold cross_magnitude, propagated_exact in M. rewrite !Rabs_mult, !(Rabs_pos_eq (head_of _)) in M by assumption.
  eapply Rle_lt_trans; [exact M|].
  pose proof k3_small. pose proof u_pos. unfold k2_exact. rewrite k1_u. rewrite u_val in *. simpl bpow in *. lra.
Qed.

(** ** A simpler form: |Δ| > 2^-96·(P_a·D_b + P_b·D_a) + 2^-600 *)

Lemma fbnd_abs_le : forall k x, fbnd k x -> Rabs (B2R x) <= bpow radix2 k.
Proof. intros k x [_ H]. exact H. Qed.

Lemma pnum_le : forall o p n, vbnd 180 o -> vbnd 180 p -> vbnd 180 n -> 0 <= pnum o p n <= bpow radix2 363.
Proof.
  intros o p n [O0 [O1 O2]] [P0 [P1 P2]] [N0 [N1 N2]]. unfold pnum.
  assert (T : forall a b c, fbnd 180 a -> fbnd 180 b -> fbnd 180 c ->
            0 <= Rabs ((B2R a - B2R b) * B2R c) <= bpow radix2 361).
  { intros a b c A B C. apply fbnd_abs_le in A, B, C. split; [apply Rabs_pos|]. rewrite Rabs_mult.
    pose proof (Rabs_triang (B2R a) (- B2R b)). rewrite Rabs_Ropp in *.
    assert (E : 2 * bpow radix2 180 * bpow radix2 180 = bpow radix2 361).
    { change 2 with (bpow radix2 1). rewrite Rmult_assoc, <- !bpow_plus. reflexivity. }
    rewrite <- E.
    apply Rmult_le_compat; try apply Rabs_pos; [unfold Rminus; lra | exact C]. }
  pose proof (T _ _ _ P0 O0 N0). pose proof (T _ _ _ P1 O1 N1). pose proof (T _ _ _ P2 O2 N2).
  assert (E : 4 * bpow radix2 361 = bpow radix2 363) by (change 4 with (bpow radix2 2); rewrite <- bpow_plus; reflexivity).
  rewrite <- E.
  pose proof (bpow_ge_0 radix2 361). lra.
Qed.

Lemma pden_le : forall d n, vbnd 180 d -> vbnd 180 n -> 0 <= pden d n <= bpow radix2 363.
Proof.
  intros d n [D0 [D1 D2]] [N0 [N1 N2]]. unfold pden.
  assert (T : forall a c, fbnd 180 a -> fbnd 180 c -> 0 <= Rabs (B2R a * B2R c) <= bpow radix2 360).
  { intros a c A C. apply fbnd_abs_le in A, C. split; [apply Rabs_pos|]. rewrite Rabs_mult.
    replace (bpow radix2 360) with (bpow radix2 180 * bpow radix2 180) by (rewrite <- bpow_plus; reflexivity).
    apply Rmult_le_compat; try apply Rabs_pos; assumption. }
  pose proof (T _ _ D0 N0). pose proof (T _ _ D1 N1). pose proof (T _ _ D2 N2).
  assert (E : 8 * bpow radix2 360 = bpow radix2 363) by (change 8 with (bpow radix2 3); rewrite <- bpow_plus; reflexivity).
  rewrite <- E.
  pose proof (bpow_ge_0 radix2 360). lra.
Qed.

(** With M = 2^363 bounding P and Q, t = 2^-1061 bounding the absolute parts: the products of heads and radii
    are their leading terms plus at most 2^-690. *)
Lemma products_upper : forall P Q, 0 <= P <= bpow radix2 363 -> 0 <= Q <= bpow radix2 363 ->
  head_of P * head_of Q <= (1 + bpow radix2 (-50)) * (P * Q) + bpow radix2 (-690) /\
  head_of P * rad_of Q <= (bpow radix2 (-100) + bpow radix2 (-150)) * (P * Q) + bpow radix2 (-690) /\
  rad_of P * head_of Q <= (bpow radix2 (-100) + bpow radix2 (-150)) * (P * Q) + bpow radix2 (-690) /\
  rad_of P * rad_of Q <= bpow radix2 (-199) * (P * Q) + bpow radix2 (-690).
Proof.
  intros P Q [P0 P1] [Q0 Q1]. unfold head_of, rad_of.
  set (M := bpow radix2 363) in *. set (t := bpow radix2 (-1061)).
  assert (Et : bpow radix2 (-1062) = t / 2) by
    (unfold t; replace (-1061)%Z with (1 + -1062)%Z by reflexivity; rewrite bpow_plus; simpl (bpow radix2 1); lra).
  rewrite Et.
  assert (Tp : 0 < t) by apply bpow_gt_0.
  assert (TM : t * M <= bpow radix2 (-696)) by (unfold t, M; rewrite <- bpow_plus; apply bpow_le; lia).
  assert (TT : t * t <= bpow radix2 (-696)).
  { unfold t. rewrite <- bpow_plus. apply bpow_le. lia. }
  assert (E690 : bpow radix2 (-690) = 64 * bpow radix2 (-696)).
  { replace (-690)%Z with (6 + -696)%Z by reflexivity. rewrite bpow_plus. simpl (bpow radix2 6). lra. }
  rewrite E690.
  assert (tP : t * P <= bpow radix2 (-696)) by (eapply Rle_trans; [apply Rmult_le_compat_l; [lra | exact P1] | exact TM]).
  assert (tQ : t * Q <= bpow radix2 (-696)) by (eapply Rle_trans; [apply Rmult_le_compat_l; [lra | exact Q1] | exact TM]).
  assert (PQ : 0 <= P * Q) by (apply Rmult_le_pos; assumption).
  assert (tP0 : 0 <= t * P) by nra. assert (tQ0 : 0 <= t * Q) by nra.
  simpl (bpow radix2 (-52)). simpl (bpow radix2 (-50)). simpl (bpow radix2 (-150)). simpl (bpow radix2 (-100)).
  simpl (bpow radix2 (-152)). simpl (bpow radix2 (-199)).
  pose proof (bpow_gt_0 radix2 (-696)).
  repeat split; match goal with |- ?l <= ?r =>
    let L := fresh in assert (L : l = l) by reflexivity; ring_simplify end; nra.
Qed.

(** Stage 2 of nearest_hit's comparison decides (the twin returns by stage 2 at the latest) for a ray and two
    planes of coordinates at most 2^180 whenever |num_a·den_b − num_b·den_a| > 2^-96·(P_a·D_b + P_b·D_a) + 2^-600
    (the coefficient of [compare_hit_distances_stage2_live_inputs]'s bound is ≈ 9.25·2^-100 < 2^-96). *)
Corollary compare_hit_distances_stage2_live_inputs_simple : forall o d pa na pb nb nsa dsa nsb dsb,
  vbnd 180 o -> vbnd 180 d -> vbnd 180 pa -> vbnd 180 na -> vbnd 180 pb -> vbnd 180 nb ->
  bpow radix2 (-96) * (pnum o pa na * pden d nb + pnum o pb nb * pden d na) + bpow radix2 (-600) <
    Rabs (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
          ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)) ->
  (snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <= 1)%Z.
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb Bo Bd Bpa Bna Bpb Bnb L.
  apply compare_hit_distances_stage2_live_inputs; try assumption.
  pose proof (pnum_le o pa na Bo Bpa Bna) as Ia. pose proof (pden_le d na Bd Bna) as Ja.
  pose proof (pnum_le o pb nb Bo Bpb Bnb) as Ib. pose proof (pden_le d nb Bd Bnb) as Jb.
  cbv zeta. eapply Rle_lt_trans; [| exact L].
  destruct (products_upper _ _ Ia Jb) as [X1 [X2 [X3 X4]]].
  destruct (products_upper _ _ Ib Ja) as [Y1 [Y2 [Y3 Y4]]].
  set (x := pnum o pa na * pden d nb) in *. set (y := pnum o pb nb * pden d na) in *.
  assert (x0 : 0 <= x) by (apply Rmult_le_pos; lra). assert (y0 : 0 <= y) by (apply Rmult_le_pos; lra).
  set (Ha := head_of (pnum o pa na)) in *. set (Ra := rad_of (pnum o pa na)) in *.
  set (Hb := head_of (pnum o pb nb)) in *. set (Rb := rad_of (pnum o pb nb)) in *.
  set (Hda := head_of (pden d na)) in *. set (Rda := rad_of (pden d na)) in *.
  set (Hdb := head_of (pden d nb)) in *. set (Rdb := rad_of (pden d nb)) in *.
  assert (S : Ha * Hdb + Hb * Hda <= (1 + bpow radix2 (-50)) * (x + y) + 2 * bpow radix2 (-690)).
  { lra. }
  assert (Q : Ha * Rdb + Ra * (Hdb + Rdb) + (Hb * Rda + Rb * (Hda + Rda)) <=
              (2 * (bpow radix2 (-100) + bpow radix2 (-150)) + bpow radix2 (-199)) * (x + y) + 6 * bpow radix2 (-690)).
  { replace (Ra * (Hdb + Rdb)) with (Ra * Hdb + Ra * Rdb) by ring.
    replace (Rb * (Hda + Rda)) with (Rb * Hda + Rb * Rda) by ring. lra. }
  assert (K1 : 0 <= k1) by (unfold k1; pose proof (bpow_ge_0 radix2 (-102)); lra).
  assert (K2 : 0 <= k2_exact) by (unfold k2_exact; pose proof (bpow_ge_0 radix2 (-37)); lra).
  assert (A : k1 * (Ha * Hdb + Hb * Hda) <= k1 * ((1 + bpow radix2 (-50)) * (x + y) + 2 * bpow radix2 (-690)))
    by (apply Rmult_le_compat_l; assumption).
  assert (B : k2_exact * (Ha * Rdb + Ra * (Hdb + Rdb) + (Hb * Rda + Rb * (Hda + Rda))) <=
              k2_exact * ((2 * (bpow radix2 (-100) + bpow radix2 (-150)) + bpow radix2 (-199)) * (x + y) +
                          6 * bpow radix2 (-690)))
    by (apply Rmult_le_compat_l; assumption).
  assert (C : k3 <= bpow radix2 (-690)) by (unfold k3; apply bpow_le; lia).
  assert (D : bpow radix2 (-690) <= bpow radix2 (-600) / 64).
  { apply Rle_trans with (bpow radix2 (-606)); [apply bpow_le; lia|].
    replace (-600)%Z with (6 + -606)%Z by reflexivity. rewrite bpow_plus. simpl (bpow radix2 6).
    pose proof (bpow_ge_0 radix2 (-606)). lra. }
  pose proof (bpow_ge_0 radix2 (-690)).
  set (LHS1 := k1 * (Ha * Hdb + Hb * Hda)) in *. set (LHS2 := k2_exact * (Ha * Rdb + Ra * (Hdb + Rdb) + (Hb * Rda + Rb * (Hda + Rda)))) in *.
  set (w := bpow radix2 (-690)) in *. set (z := bpow radix2 (-600)) in *. clearbody w z LHS1 LHS2.
  unfold k1, k2_exact in *. simpl bpow in *. lra.
Qed.

(** The same ray and planes are in the simpler class: 2^-96·(1·1 + (1 + 2^-60)·1) + 2^-600 < 2^-60. *)
Example compare_hit_distances_stage2_inputs_simple_example :
  bpow radix2 (-96) * (pnum wo wpa wna * pden wd wnb + pnum wo wpb wnb * pden wd wna) + bpow radix2 (-600) <
    Rabs (ray_num (vec_R wo) (vec_R wpa) (vec_R wna) * ray_den (vec_R wd) (vec_R wnb) -
          ray_num (vec_R wo) (vec_R wpb) (vec_R wnb) * ray_den (vec_R wd) (vec_R wna)).
Proof.
  pose proof (bpow_gt_0 radix2 (-60)) as P60.
  unfold pnum, pden. rewrite !ray_num_bits, !ray_den_bits. unfold wo, wd, wpa, wna, wpb, wnb. cbn [vxb vyb vzb].
  rewrite w_one_val, w_zero_val, w_2m60_val.
  match goal with |- _ < Rabs ?V => replace V with (- bpow radix2 (-60)) by ring end.
  rewrite Rabs_Ropp, (Rabs_pos_eq (bpow radix2 (-60))) by lra.
  replace (1 - 0) with 1 by ring. replace (0 - 0) with 0 by ring. replace (bpow radix2 (-60) - 0) with (bpow radix2 (-60)) by ring.
  rewrite ?Rmult_1_l, ?Rmult_1_r, ?Rmult_0_l, ?Rmult_0_r, ?Rabs_R0, ?Rabs_R1, (Rabs_pos_eq (bpow radix2 (-60))) by lra.
  assert (D : bpow radix2 (-600) <= bpow radix2 (-62)) by (apply bpow_le; lia).
  set (z := bpow radix2 (-600)) in *. clearbody z. simpl bpow in *. lra.
Qed.
