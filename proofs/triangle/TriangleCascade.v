(** * The ray–triangle cascade composed as kernel/src/triangle/ray_triangle_cascade.cpp composes it.

    - [triangle_fast_sign_correct]: the fast path's sign of each value ([first_certain_lanes] of the filter's
      and the enclosure's lane signs) is, when certain, the exact sign (then nonzero);
    - [fast_location_correct]: with the signs of den and the three π certain (so nonzero), the location is
      inside when all three have den's sign and outside otherwise, and the owned rule agrees with the closed
      one (no π is 0, so no tie-break is consulted);
    - [triangle_quotient_correct]: [round_quotient] of the stage-2 enclosure of num (or of a π) over ONE divisor,
      [prepare_divisor] of den's stage-2 enclosure, shared by the four quotients, when certain, returns
      RN(num/den) (RN(π/den)), and den ≠ 0 — the roundings of t and of the barycentric coordinates
      ([round_quotient_sound], QuotientRounding.v, applied to [num_compensated_encloses],
      [pi_compensated_encloses], [den_compensated_encloses]). The fast path computes the four in the lanes of
      a Lanes4 with the scalar divisor broadcast: each lane is this scalar computation (proofs/README.md,
      "Lanes");
    - [triangle_quotient_expansion_correct]: the same from stage 3, the numerator's expansion tail enclosure
      (at most 32 components, [tail_sum_enclosure]) over the divisor prepared from any enclosure of den; that
      the expansions sum to the exact values is Shewchuk's theorem (cited, as in PlaneCascade.v's
      [expansion_t_correct]);
    - [den_nonzero_direction]: a certified den ≠ 0 implies d ≠ 0 (the fast path needs no validation for it). *)

From Coq Require Import Reals Lra Lia ZArith List.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model PlaneClassification PlaneCompensated QuotientRounding PlaneCascade
  TriangleFilter TriangleCompensated TriangleRule.
Open Scope R_scope.

Lemma det3_lane_sign_correct : forall (f : FTerm) (e : Enclosure) C A V,
  binary64 (hi e) -> binary64 (lo e) -> binary64 (radius e) ->
  Rabs (fv f - V) <= det3_bound f C A -> encloses e V ->
  lane_sign (first_certain_lanes (det3_filter_lanes f C A) (enclosure_sign_lanes e)) /\
  certifies (sign_from_Z (first_certain_lanes (det3_filter_lanes f C A) (enclosure_sign_lanes e))) V.
Proof.
  intros f e C A V Bh Bl Br Hf He.
  apply first_certain_lanes_sound.
  - apply sign_lanes_range.
  - apply enclosure_sign_lanes_range.
  - now apply det3_filter_sound_gen.
  - exact (enclosure_sign_sound e V Bh Bl Br He).
Qed.

(** The five values of a query: the fast path's sign, the filter's from stage 2's high parts and magnitudes
    (which are stage 1's values, [stage2_filter_view]), else the enclosure's. *)
Theorem triangle_fast_sign_correct : forall o d a b c,
  doubles3 o -> doubles3 d -> doubles3 a -> doubles3 b -> doubles3 c ->
  (forall p q, doubles3 p -> doubles3 q ->
     certifies (sign_from_Z (first_certain_lanes
        (det3_filter_lanes {| fv := ch (pi_stage2 o d p q); fm := cm (pi_stage2 o d p q) |}
                           triangle_filter_pi_relative (absolute_v d))
        (enclosure_sign_lanes (det3_enclosure (pi_stage2 o d p q) triangle_compensated_relative (absolute_v d)))))
       (edge_value o d p q)) /\
  certifies (sign_from_Z (first_certain_lanes
        (det3_filter_lanes {| fv := ch (num_stage2 o a b c); fm := cm (num_stage2 o a b c) |}
                           triangle_filter_num_relative (absolute_v (rsub a o)))
        (enclosure_sign_lanes (det3_enclosure (num_stage2 o a b c) triangle_compensated_relative
                                              (absolute_v (rsub a o))))))
    (num_value o a b c) /\
  certifies (sign_from_Z (first_certain_lanes
        (det3_filter_lanes {| fv := ch (den_stage2 o d a b c); fm := cm (den_stage2 o d a b c) |}
                           triangle_filter_den_relative (absolute_v d))
        (enclosure_sign_lanes (det3_enclosure (den_stage2 o d a b c) triangle_compensated_den_relative
                                              (absolute_v d)))))
    (den_value o d a b c).
Proof.
  intros o d a b c Bo Bd Ba Bb Bc.
  destruct (stage2_filter_view o d a b c) as [Vpi [[Hn Mn] [Hd Md]]].
  split; [|split].
  - intros p q Bp Bq. destruct (Vpi p q) as [Hp Mp].
    destruct (det3_enclosure_binary64 _ _ _ _ _ _ triangle_compensated_relative (absolute_v d)
                (pi_capprox o d p q Bo Bd Bp Bq)) as [B1 [B2 B3]].
    apply (det3_lane_sign_correct _ _ _ _ _ B1 B2 B3).
    + rewrite Hp, Mp. replace {| fv := fv (pi_stage1 o d p q); fm := fm (pi_stage1 o d p q) |} with (pi_stage1 o d p q)
        by (destruct (pi_stage1 o d p q); reflexivity). now apply pi_filter_encloses.
    + now apply pi_compensated_encloses.
  - destruct (det3_enclosure_binary64 _ _ _ _ _ _ triangle_compensated_relative (absolute_v (rsub a o))
                (num_capprox o a b c Bo Ba Bb Bc)) as [B1 [B2 B3]].
    apply (det3_lane_sign_correct _ _ _ _ _ B1 B2 B3).
    + rewrite Hn, Mn. replace {| fv := fv (num_stage1 o a b c); fm := fm (num_stage1 o a b c) |} with (num_stage1 o a b c)
        by (destruct (num_stage1 o a b c); reflexivity). now apply num_filter_encloses.
    + now apply num_compensated_encloses.
  - assert (B1 : binary64 (hi (det3_enclosure (den_stage2 o d a b c) triangle_compensated_den_relative (absolute_v d))))
      by (unfold det3_enclosure, den_stage2, cterm_add; cbn [hi ch]; apply binary64_two_sum_hi).
    assert (B2 : binary64 (lo (det3_enclosure (den_stage2 o d a b c) triangle_compensated_den_relative (absolute_v d))))
      by (unfold det3_enclosure, den_stage2, cterm_add; cbn [lo cl]; apply binary64_RN).
    assert (B3 : binary64 (radius (det3_enclosure (den_stage2 o d a b c) triangle_compensated_den_relative
                                                  (absolute_v d))))
      by (unfold det3_enclosure; cbn [radius]; apply binary64_RN).
    apply (det3_lane_sign_correct _ _ _ _ _ B1 B2 B3).
    + rewrite Hd, Md. replace {| fv := fv (den_stage1 o d a b c); fm := fm (den_stage1 o d a b c) |}
        with (den_stage1 o d a b c) by (destruct (den_stage1 o d a b c); reflexivity). now apply den_filter_encloses.
    + now apply den_compensated_encloses.
Qed.

(** With certain (nonzero) signs of the three π and of den — [decide_nonzero] of ray_triangle_cascade.cpp. *)
Theorem fast_location_correct : forall pa pb pc, pa + pb + pc <> 0 -> pa <> 0 -> pb <> 0 -> pc <> 0 ->
  let sa := sign_of pa in let sb := sign_of pb in let sc := sign_of pc in let sden := sign_of (pa + pb + pc) in
  (triangle_location sa sb sc sden = Inside <-> (sa = sden /\ sb = sden /\ sc = sden)%Z) /\
  (triangle_location sa sb sc sden = Outside <-> ~ (sa = sden /\ sb = sden /\ sc = sden)%Z) /\
  (forall tx ty tz, owned_sign sa tx ty tz = sa) /\ (forall tx ty tz, owned_sign sb tx ty tz = sb) /\
  (forall tx ty tz, owned_sign sc tx ty tz = sc).
Proof.
  intros pa pb pc Hd Ha Hb Hc. cbv zeta.
  assert (Nz : forall x, x <> 0 -> sign_of x <> 0%Z) by (intros x Hx E; apply sign_of_zero_iff in E; contradiction).
  assert (Own : forall s tx ty tz, s <> 0%Z -> owned_sign s tx ty tz = s).
  { intros s tx ty tz Hs. unfold owned_sign. destruct (Z.eqb_spec s 0); [contradiction | reflexivity]. }
  pose proof (triangle_location_correct pa pb pc Hd) as L. cbv zeta in L.
  destruct L as [LO [LI _]].
  pose proof (Nz _ Ha) as Na. pose proof (Nz _ Hb) as Nb. pose proof (Nz _ Hc) as Nc. pose proof (Nz _ Hd) as Nd.
  pose proof (sign_of_range pa) as Ra. pose proof (sign_of_range pb) as Rb. pose proof (sign_of_range pc) as Rc.
  pose proof (sign_of_range (pa + pb + pc)) as Rd.
  split; [exact LI|]. split.
  - split.
    + intros H [E1 [E2 E3]]. apply LO in H. lia.
    + intros H. apply LO. lia.
  - split; [intros; apply Own; assumption|]. split; intros; apply Own; assumption.
Qed.

(** The roundings of t and of the barycentric coordinates from the stage-2 enclosures, all four over the one
    divisor prepared from den's enclosure (one reciprocal). *)
Theorem triangle_quotient_correct : forall o d a b c, doubles3 o -> doubles3 d -> doubles3 a -> doubles3 b ->
  doubles3 c ->
  let divisor := prepare_divisor (det3_enclosure (den_stage2 o d a b c) triangle_compensated_den_relative
                                                 (absolute_v d)) in
  (forall r, r = round_quotient (det3_enclosure (num_stage2 o a b c) triangle_compensated_relative
                                                (absolute_v (rsub a o))) divisor ->
             qr_certain r = true -> den_value o d a b c <> 0 /\ qr_t r = RN (num_value o a b c / den_value o d a b c)) /\
  (forall p q r, doubles3 p -> doubles3 q ->
             r = round_quotient (det3_enclosure (pi_stage2 o d p q) triangle_compensated_relative (absolute_v d))
                                divisor ->
             qr_certain r = true -> den_value o d a b c <> 0 /\ qr_t r = RN (edge_value o d p q / den_value o d a b c)).
Proof.
  intros o d a b c Bo Bd Ba Bb Bc divisor.
  set (den := det3_enclosure (den_stage2 o d a b c) triangle_compensated_den_relative (absolute_v d)) in divisor.
  (* den's enclosure and its doubles *)
  assert (Hden : encloses den (den_value o d a b c)) by (apply den_compensated_encloses; assumption).
  assert (Bden : binary64 (hi den) /\ binary64 (lo den) /\ binary64 (radius den)).
  { unfold den, det3_enclosure, den_stage2, cterm_add. cbn [hi lo radius ch cl].
    repeat split; try apply binary64_RN; apply binary64_two_sum_hi. }
  destruct Bden as [Dh [Dl Dr]].
  split.
  - intros r -> H.
    destruct (det3_enclosure_binary64 _ _ _ _ _ _ triangle_compensated_relative (absolute_v (rsub a o))
                (num_capprox o a b c Bo Ba Bb Bc)) as [Nh [Nl Nr]].
    apply (round_quotient_sound _ _ _ _ Nh Nl Nr Dh Dl Dr); [apply num_compensated_encloses; assumption | exact Hden | exact H].
  - intros p q r Bp Bq -> H.
    destruct (det3_enclosure_binary64 _ _ _ _ _ _ triangle_compensated_relative (absolute_v d)
                (pi_capprox o d p q Bo Bd Bp Bq)) as [Ph [Pl Pr]].
    apply (round_quotient_sound _ _ _ _ Ph Pl Pr Dh Dl Dr); [apply pi_compensated_encloses; assumption | exact Hden | exact H].
Qed.

(** Stage 3: the numerator's expansion (at most 32 components, summing exactly to the value: Shewchuk,
    cited) through expansion_tail_enclosure, over the divisor prepared from any enclosure of den made of
    doubles (den's tail enclosure, or its stage-2 enclosure when den's expansion is too long). *)
Theorem triangle_quotient_expansion_correct : forall (e0 : R) (rest : list R) (dd : Enclosure) (value den : R),
  binary64 e0 -> Forall (fun x => binary64 x) rest -> (S (length rest) <= tail_sum_max_terms)%nat ->
  e0 + sum_list rest = value ->
  binary64 (hi dd) -> binary64 (lo dd) -> binary64 (radius dd) -> encloses dd den ->
  qr_certain (round_quotient (expansion_tail_enclosure e0 rest) (prepare_divisor dd)) = true ->
  den <> 0 /\ qr_t (round_quotient (expansion_tail_enclosure e0 rest) (prepare_divisor dd)) = RN (value / den).
Proof.
  intros e0 rest dd value den B0 Brest Len Sum Dh Dl Dr Hd H.
  destruct (tail_enclosure_binary64 e0 rest B0) as [Th [Tl Tr]].
  apply (round_quotient_sound _ _ _ _ Th Tl Tr Dh Dl Dr); [|exact Hd|exact H].
  rewrite <- Sum. now apply tail_sum_enclosure.
Qed.

(** den ≠ 0 implies d ≠ 0. *)
Theorem den_nonzero_direction : forall o d a b c, den_value o d a b c <> 0 -> (vx d <> 0 \/ vy d <> 0 \/ vz d <> 0).
Proof.
  intros o d a b c H. rewrite den_as_edge_values in H.
  destruct (Req_dec (vx d) 0) as [X|X]; [|now left].
  destruct (Req_dec (vy d) 0) as [Y|Y]; [|now right; left].
  destruct (Req_dec (vz d) 0) as [Z|Z]; [|now right; right].
  exfalso. apply H. unfold dot. rewrite X, Y, Z. ring.
Qed.
