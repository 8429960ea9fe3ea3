(** * Liveness of stage 3 of the ray–triangle cascade (the checked sign of [ExpansionValue]).

    Stage 3 of [TriangleCascade::sign(v)] (kernel/src/triangle/ray_triangle_cascade.cpp) is
    [value_expansion(ray, triangle, v).sign()] (core/expansion_value.hpp composed by
    ray_triangle_stages.hpp's [expansion_leaf] and [determinant_leaves]), twinned by TriangleStage3Twins.v's
    [ev_sign (value_ev o d a b c v)] and, in the cascade, by TriangleCascadeFlowTwins.v's [tc_sign_b] (the
    runner ties them to the C++: [tri_expansion], [tri_cascade_relation], [tri_cascade_intersect]).  Its
    soundness is [triangle_expansion_sign_sound]; this file proves that it does certify, on the analogue of
    PlaneStage3Liveness.v's class, reusing that file's lemmas ([expansion_sign_single_certain], [two_prod_small],
    [sum_single], [scale_single], [diff_step], [fint]):

    - the class: every component of o, d, a, b, c an integer of magnitude ≤ 2^15 ([tvec_int_le 15]).  Then
      every difference (p − o) is an integer ≤ 2^16, every cross component y_i·z_j − y_j·z_i ≤ 2·2^32 = 2^33,
      every leaf·cross product ≤ 2^16·2^33 = 2^49 and the dot's partial sums ≤ 2·2^49, 3·2^49 < 2^52: every
      intermediate is an integer ≤ 2^52, exactly a double, so every TwoDiff/TwoSum/TwoProduct low part is 0,
      zero elimination drops it, and each [ExpansionValue] is exact with ONE finite component.  The binding
      determinant is num = (a − o)·((b − o) × (c − o)) (three differences; the π's and den have the leaf d
      ≤ 2^15 outside).  With k = 16 this triangle-inequality bound gives 2·2^52 for the partial sum, above
      2^52, so 15 is the largest k this derivation gives (see the sharpness item below for k = 16, 17);
    - [value_ev_int_single]: on the class, [value_ev o d a b c v] is exact and one finite component for
      every v (πa, πb, πc, den, num); [value_ev_int_certain]: its checked sign [ev_sign] is certain, and it
      is the exact sign of the model's value ([triangle_expansion_sign_sound]);
    - [tie_vector_int_certain], [normal_vector_int_certain]: the same for the tie-break's d × (q − p) and
      the normal (b − a) × (c − a) that the cascade's stage 3 also evaluates as expansions;
    - [tc_sign_int_live]: [tc_sign_b] never gives up ([needs_exact_] unchanged) on the class, whatever
      stages 1 and 2 did; [tc_classify_int_live]: [tc_classify_b] (both rules) ends with [needs_exact_]
      false; [tc_relation_int_live], [tc_intersect_int_live]: the twin relation and intersection cascades
      do not answer [TCExact] (the classification is decided before the exact stage; that the intersection's
      quotients are then rounded before the exact stage is not stated here: it is the quotient rounding's
      liveness, QuotientLiveness.v);
    - [tri_stage3_live_edge], [tri_stage3_live_vertex]: non-vacuity, by [vm_compute] on the twin: a ray
      through the edge ab (π(a, b) exactly 0) and a ray through the vertex a (π(a, b) = π(c, a) = 0) of an
      integer triangle: stage 1 ([tc_filter_b]) and stage 2 ([enclosure_sign_b] of [tc_enclosure2_b]) leave
      each zero π uncertain (they never certify an exact zero), stage 3 certifies it Zero, and
      [tc_relation_b] decides (a hit on the edge / at the vertex, owned or not by the tie-break) at
      [StExpansion] with both rules.
    - sharpness: [tri_stage3_k17_two_components]: with components ≤ 2^17 (k = 17) a num expansion has two
      components (a product 2^55-sized and odd is not a double: TwoProduct's low part is nonzero); its
      checked sign is still certain there (the class is sufficient, not necessary).  k = 16 is between and not
      claimed: the dot's partial sum c_0·x_0 + c_1·x_1 reaches 4·(2^17)^3 = 2^53 (still a double), and the full
      sum needs the bound |c_0| + |c_1| + |c_2| ≤ 4·M² for a cross product of vectors with entries ≤ M (true at
      the vertices of the box, by parity, not proved here) to stay within 2^53. *)

From Coq Require Import Reals ZArith List Lia Lra Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification PlaneCascade FloatCore ConstantsCpp PlaneTwins Expansions PlaneQueryTwins
  PlaneStage3Liveness.
From Raykernel Require Import TriangleFilter TriangleRule TriangleTwins TriangleStage3Twins TriangleCascadeTwins
  TriangleIntersectTwins TriangleCascadeFlowTwins TriangleIntegerSign.
From Raykernel Require PlaneCascadeTwins.
Import ListNotations.
Open Scope R_scope.

(** ** One-component exact [ExpansionValue]s *)

(** [e] is exact, of one finite component, and that component is the integer z, |z| ≤ 2^52. *)
Definition sev (e : EVal) (z : Z) : Prop :=
  eexact e = true /\ (Z.abs z <= 2 ^ 52)%Z /\ exists x, ecomp e = [x] /\ fin x = true /\ B2R x = IZR z.

Lemma sev_single : forall e z, sev e z -> single (ecomp e) (IZR z).
Proof. intros e z [_ [B [x [E [F V]]]]]. exists x. repeat split; auto. now apply small_int. Qed.

Lemma sev_certain : forall e z, sev e z -> is_certain (ev_sign e) = true.
Proof.
  intros e z [X [_ [x [E [F _]]]]]. unfold ev_sign. rewrite X, E.
  destruct (expansion_sign_b [x]) eqn:S; try reflexivity. exfalso; now apply (expansion_sign_single_certain x).
Qed.

Lemma ev_of_sev : forall x z, fin x = true -> B2R x = IZR z -> (Z.abs z <= 2 ^ 52)%Z -> sev (ev_of x) z.
Proof. intros x z F V B. split; [exact F|]. split; [exact B|]. exists x. auto. Qed.

Lemma ev_diff_sev : forall v w zv zw, fin v = true -> fin w = true -> B2R v = IZR zv -> B2R w = IZR zw ->
  (Z.abs zv <= 2 ^ 24)%Z -> (Z.abs zw <= 2 ^ 24)%Z -> sev (ev_diff v w) (zv - zw).
Proof.
  intros v w zv zw Fv Fw Vv Vw Bv Bw.
  destruct (diff_step v w zv zw Fv Fw Vv Vw Bv Bw) as [x [E [F [V _]]]].
  unfold ev_diff; cbv zeta. split; [|split; [clear - Bv Bw; lia|]]; cbn [eexact ecomp]; rewrite E.
  - cbn [hd last]. now rewrite F.
  - exists x. auto.
Qed.

Lemma ev_neg_sev : forall a z, sev a z -> sev (ev_neg a) (- z).
Proof.
  intros a z [X [B [x [E [F V]]]]]. unfold ev_neg. split; [exact X|]. split; [clear - B; lia|].
  cbn [ecomp]. rewrite E. exists (fneg x). cbn [map]. rewrite fneg_fin, fneg_val, V, opp_IZR. auto.
Qed.

Lemma check_finite_single : forall x, fin x = true -> check_finite true [x] = true.
Proof. intros x F. unfold check_finite. cbn [forallb]. now rewrite F. Qed.

Lemma ev_add_sev : forall a b za zb, sev a za -> sev b zb -> (Z.abs (za + zb) <= 2 ^ 52)%Z ->
  sev (ev_add a b) (za + zb).
Proof.
  intros a b za zb Sa Sb B.
  pose proof (sum_single _ _ _ _ (sev_single a za Sa) (sev_single b zb Sb)) as S.
  rewrite <- plus_IZR in S. specialize (S (small_int _ B)). destruct S as [x [E [F [V _]]]].
  destruct Sa as [Xa _]. destruct Sb as [Xb _].
  unfold ev_add; cbv zeta. split; [|split; [exact B|]]; cbn [eexact ecomp]; rewrite E.
  - now rewrite Xa, Xb, check_finite_single.
  - exists x. auto.
Qed.

Lemma ev_sub_sev : forall a b za zb, sev a za -> sev b zb -> (Z.abs (za - zb) <= 2 ^ 52)%Z ->
  sev (ev_sub a b) (za - zb).
Proof.
  intros a b za zb Sa Sb B. unfold ev_sub. replace (za - zb)%Z with (za + - zb)%Z by ring.
  apply ev_add_sev; [exact Sa | now apply ev_neg_sev | clear - B; lia].
Qed.

(** [a * b], b one component (a leaf or a difference): one [scale], exact. *)
Lemma ev_mul_sev : forall a b za zb, sev a za -> sev b zb -> (Z.abs (za * zb) <= 2 ^ 52)%Z ->
  sev (ev_mul a b) (za * zb).
Proof.
  intros a b za zb Sa Sb B. pose proof (sev_single a za Sa) as Ua.
  destruct Sa as [Xa _]. destruct Sb as [Xb [_ [y [Eb [Fy Vy]]]]].
  destruct (scale_single true (ecomp a) (IZR za) y zb Ua Fy Vy (ex_intro _ za eq_refl)) as [C U];
    [rewrite Vy, <- mult_IZR; now apply small_int|].
  rewrite Vy, <- mult_IZR in U. destruct U as [x [E [F [V _]]]].
  unfold ev_mul; cbv zeta. rewrite Eb. cbn [length hd Nat.eqb].
  split; [|split; [exact B|]]; cbn [eexact ecomp].
  - rewrite Xa, Xb, C, E. cbn [andb]. now apply check_finite_single.
  - exists x. auto.
Qed.

Definition sev3 (x : E3) (z0 z1 z2 : Z) : Prop := sev (e0 x) z0 /\ sev (e1 x) z1 /\ sev (e2 x) z2.

(** Interval steps, each by [lia] on two hypotheses (lia's case splits on [Z.abs] grow with the context). *)
Lemma le_15_16 : forall z, (Z.abs z <= 2 ^ 15)%Z -> (Z.abs z <= 2 ^ 16)%Z. Proof. intros; lia. Qed.
Lemma le_15_24 : forall z, (Z.abs z <= 2 ^ 15)%Z -> (Z.abs z <= 2 ^ 24)%Z. Proof. intros; lia. Qed.
Lemma le_15_52 : forall z, (Z.abs z <= 2 ^ 15)%Z -> (Z.abs z <= 2 ^ 52)%Z. Proof. intros; lia. Qed.
Lemma le_32_52 : forall z, (Z.abs z <= 2 ^ 32)%Z -> (Z.abs z <= 2 ^ 52)%Z. Proof. intros; lia. Qed.
Lemma le_33_52 : forall z, (Z.abs z <= 2 ^ 33)%Z -> (Z.abs z <= 2 ^ 52)%Z. Proof. intros; lia. Qed.
Lemma le_49_52 : forall z, (Z.abs z <= 2 ^ 49)%Z -> (Z.abs z <= 2 ^ 52)%Z. Proof. intros; lia. Qed.
Lemma le_50_52 : forall z, (Z.abs z <= 2 ^ 50)%Z -> (Z.abs z <= 2 ^ 52)%Z. Proof. intros; lia. Qed.
Lemma le_51_52 : forall z, (Z.abs z <= 2 ^ 51)%Z -> (Z.abs z <= 2 ^ 52)%Z. Proof. intros; lia. Qed.
Lemma sub_15 : forall a b, (Z.abs a <= 2 ^ 15)%Z -> (Z.abs b <= 2 ^ 15)%Z -> (Z.abs (a - b) <= 2 ^ 16)%Z.
Proof. intros; lia. Qed.
Lemma sub_32 : forall a b, (Z.abs a <= 2 ^ 32)%Z -> (Z.abs b <= 2 ^ 32)%Z -> (Z.abs (a - b) <= 2 ^ 33)%Z.
Proof. intros; lia. Qed.
Lemma add_49 : forall a b, (Z.abs a <= 2 ^ 49)%Z -> (Z.abs b <= 2 ^ 49)%Z -> (Z.abs (a + b) <= 2 ^ 50)%Z.
Proof. intros; lia. Qed.
Lemma add_50_49 : forall a b, (Z.abs a <= 2 ^ 50)%Z -> (Z.abs b <= 2 ^ 49)%Z -> (Z.abs (a + b) <= 2 ^ 51)%Z.
Proof. intros; lia. Qed.

Lemma prod_le : forall a b, (Z.abs a <= 2 ^ 16)%Z -> (Z.abs b <= 2 ^ 16)%Z -> (Z.abs (a * b) <= 2 ^ 32)%Z.
Proof. intros a b A B. exact (zmul_bound a b 16 16 A B ltac:(lia) ltac:(lia)). Qed.

(** [cross_terms(y, z)] on one-component leaves ≤ 2^16: components ≤ 2^33. *)
Lemma ev_cross_sev : forall y z y0 y1 y2 z0 z1 z2, sev3 y y0 y1 y2 -> sev3 z z0 z1 z2 ->
  (Z.abs y0 <= 2 ^ 16)%Z -> (Z.abs y1 <= 2 ^ 16)%Z -> (Z.abs y2 <= 2 ^ 16)%Z ->
  (Z.abs z0 <= 2 ^ 16)%Z -> (Z.abs z1 <= 2 ^ 16)%Z -> (Z.abs z2 <= 2 ^ 16)%Z ->
  sev3 (ev_cross y z) (y1 * z2 - y2 * z1) (y2 * z0 - y0 * z2) (y0 * z1 - y1 * z0) /\
  (Z.abs (y1 * z2 - y2 * z1) <= 2 ^ 33)%Z /\ (Z.abs (y2 * z0 - y0 * z2) <= 2 ^ 33)%Z /\
  (Z.abs (y0 * z1 - y1 * z0) <= 2 ^ 33)%Z.
Proof.
  intros y z y0 y1 y2 z0 z1 z2 [Y0 [Y1 Y2]] [Z0 [Z1 Z2]] B0 B1 B2 C0 C1 C2.
  pose proof (prod_le _ _ B1 C2) as P0. pose proof (prod_le _ _ B2 C1) as Q0.
  pose proof (prod_le _ _ B2 C0) as P1. pose proof (prod_le _ _ B0 C2) as Q1.
  pose proof (prod_le _ _ B0 C1) as P2. pose proof (prod_le _ _ B1 C0) as Q2.
  pose proof (sub_32 _ _ P0 Q0) as D0. pose proof (sub_32 _ _ P1 Q1) as D1. pose proof (sub_32 _ _ P2 Q2) as D2.
  unfold ev_cross, sev3; cbn [e0 e1 e2].
  refine (conj (conj _ (conj _ _)) (conj D0 (conj D1 D2)));
  (apply ev_sub_sev; [apply ev_mul_sev; [assumption | assumption | now apply le_32_52]
                     |apply ev_mul_sev; [assumption | assumption | now apply le_32_52]
                     |now apply le_33_52]).
Qed.

(** [dot_terms(x, c)], x ≤ 2^16, c ≤ 2^33: partial sums ≤ 2^50, 3·2^49. *)
Lemma ev_dot3_sev : forall x c x0 x1 x2 c0 c1 c2, sev3 x x0 x1 x2 -> sev3 c c0 c1 c2 ->
  (Z.abs x0 <= 2 ^ 16)%Z -> (Z.abs x1 <= 2 ^ 16)%Z -> (Z.abs x2 <= 2 ^ 16)%Z ->
  (Z.abs c0 <= 2 ^ 33)%Z -> (Z.abs c1 <= 2 ^ 33)%Z -> (Z.abs c2 <= 2 ^ 33)%Z ->
  sev (ev_dot3 x c) (c0 * x0 + c1 * x1 + c2 * x2).
Proof.
  intros x c x0 x1 x2 c0 c1 c2 [X0 [X1 X2]] [K0 [K1 K2]] B0 B1 B2 C0 C1 C2.
  pose proof (zmul_bound c0 x0 33 16 C0 B0 ltac:(lia) ltac:(lia)) as M0.
  pose proof (zmul_bound c1 x1 33 16 C1 B1 ltac:(lia) ltac:(lia)) as M1.
  pose proof (zmul_bound c2 x2 33 16 C2 B2 ltac:(lia) ltac:(lia)) as M2.
  cbn [Z.add] in M0, M1, M2. unfold ev_dot3.
  apply ev_add_sev; [apply ev_add_sev; [| | exact (le_50_52 _ (add_49 _ _ M0 M1))] |
                     | exact (le_51_52 _ (add_50_49 _ _ (add_49 _ _ M0 M1) M2))];
    apply ev_mul_sev; try assumption; now apply le_49_52.
Qed.

(** ** The class *)

Definition tvec_int_le (k : Z) (v : TVec) : Prop := int_le k (tx v) /\ int_le k (ty v) /\ int_le k (tz v).

Definition e3_small (x : E3) : Prop :=
  exists z0 z1 z2, sev3 x z0 z1 z2 /\ (Z.abs z0 <= 2 ^ 16)%Z /\ (Z.abs z1 <= 2 ^ 16)%Z /\ (Z.abs z2 <= 2 ^ 16)%Z.

Definition e3_cross (x : E3) : Prop :=
  exists z0 z1 z2, sev3 x z0 z1 z2 /\ (Z.abs z0 <= 2 ^ 33)%Z /\ (Z.abs z1 <= 2 ^ 33)%Z /\ (Z.abs z2 <= 2 ^ 33)%Z.

Lemma lift3_small : forall d, tvec_int_le 15 d -> e3_small (lift3 d).
Proof.
  intros d [[F0 [z0 [V0 B0]]] [[F1 [z1 [V1 B1]]] [F2 [z2 [V2 B2]]]]].
  exists z0, z1, z2. unfold lift3, sev3; cbn [e0 e1 e2].
  split; [split; [|split] | split; [|split]]; try (now apply le_15_16);
    apply ev_of_sev; auto; now apply le_15_52.
Qed.

Lemma diff3_small : forall v o, tvec_int_le 15 v -> tvec_int_le 15 o -> e3_small (diff3 v o).
Proof.
  intros v o [[F0 [z0 [V0 B0]]] [[F1 [z1 [V1 B1]]] [F2 [z2 [V2 B2]]]]]
             [[G0 [w0 [W0 C0]]] [[G1 [w1 [W1 C1]]] [G2 [w2 [W2 C2]]]]].
  exists (z0 - w0)%Z, (z1 - w1)%Z, (z2 - w2)%Z. unfold diff3, sev3; cbn [e0 e1 e2].
  split; [split; [|split] | split; [|split]]; try (now apply sub_15);
    apply ev_diff_sev; auto; now apply le_15_24.
Qed.

Lemma cross_small : forall y z, e3_small y -> e3_small z -> e3_cross (ev_cross y z).
Proof.
  intros y z [y0 [y1 [y2 [Y [B0 [B1 B2]]]]]] [z0 [z1 [z2 [Z [C0 [C1 C2]]]]]].
  destruct (ev_cross_sev y z y0 y1 y2 z0 z1 z2 Y Z B0 B1 B2 C0 C1 C2) as [S [D0 [D1 D2]]].
  eexists _, _, _. split; [exact S | auto].
Qed.

Lemma dot_small : forall x c, e3_small x -> e3_cross c -> exists z, sev (ev_dot3 x c) z.
Proof.
  intros x c [x0 [x1 [x2 [X [B0 [B1 B2]]]]]] [c0 [c1 [c2 [C [D0 [D1 D2]]]]]].
  eexists. exact (ev_dot3_sev x c x0 x1 x2 c0 c1 c2 X C B0 B1 B2 D0 D1 D2).
Qed.

Lemma e3_cross_certain : forall x, e3_cross x ->
  is_certain (ev_sign (e0 x)) = true /\ is_certain (ev_sign (e1 x)) = true /\ is_certain (ev_sign (e2 x)) = true.
Proof.
  intros x [z0 [z1 [z2 [[S0 [S1 S2]] _]]]]. repeat split; eapply sev_certain; eassumption.
Qed.

(** Every input an integer of magnitude ≤ 2^15: each of the five stage-3 expansions (πa, πb, πc, den, num)
    is exact with one finite component. *)
Theorem value_ev_int_single : forall o d a b c v,
  tvec_int_le 15 o -> tvec_int_le 15 d -> tvec_int_le 15 a -> tvec_int_le 15 b -> tvec_int_le 15 c ->
  exists z x, sev (value_ev o d a b c v) z /\ ecomp (value_ev o d a b c v) = [x] /\ fin x = true /\
    B2R x = value_model o d a b c v.
Proof.
  intros o d a b c v Io Id Ia Ib Ic.
  assert (Edge : forall o p q, tvec_int_le 15 o -> tvec_int_le 15 p -> tvec_int_le 15 q ->
                 exists z, sev (edge_ev o d p q) z).
  { intros o' p q Io' Ip Iq. unfold edge_ev. apply dot_small; [now apply lift3_small|].
    apply cross_small; now apply diff3_small. }
  assert (S : exists z, sev (value_ev o d a b c v) z).
  { unfold value_ev. destruct (Z.eqb v 0); [now apply Edge|]. destruct (Z.eqb v 1); [now apply Edge|].
    destruct (Z.eqb v 2); [now apply Edge|]. destruct (Z.eqb v 3); [now apply Edge|].
    unfold num_ev. apply dot_small; [now apply diff3_small|]. apply cross_small; now apply diff3_small. }
  destruct S as [z Sz]. exists z. pose proof Sz as [X [_ [x [E [F _]]]]]. exists x.
  split; [exact Sz|]. split; [exact E|]. split; [exact F|].
  destruct (value_ev_exact o d a b c v X) as [_ Sum]. rewrite E in Sum. unfold sumR in Sum. cbn in Sum. lra.
Qed.

(** On the class, stage 3's checked sign of every determinant is certain, and it is the exact sign. *)
Theorem value_ev_int_certain : forall o d a b c v,
  tvec_int_le 15 o -> tvec_int_le 15 d -> tvec_int_le 15 a -> tvec_int_le 15 b -> tvec_int_le 15 c ->
  is_certain (ev_sign (value_ev o d a b c v)) = true /\
  certifies (ev_sign (value_ev o d a b c v)) (value_model o d a b c v).
Proof.
  intros o d a b c v Io Id Ia Ib Ic. destruct (value_ev_int_single o d a b c v Io Id Ia Ib Ic) as [z [_ [S _]]].
  split; [exact (sev_certain _ _ S) | apply triangle_expansion_sign_sound].
Qed.

(** The tie-break's d × (q − p) and the normal (b − a) × (c − a): three certain signs each. *)
Theorem tie_vector_int_certain : forall d a b c k,
  tvec_int_le 15 d -> tvec_int_le 15 a -> tvec_int_le 15 b -> tvec_int_le 15 c ->
  let v := tc_tie_vector d a b c k in
  is_certain (ev_sign (e0 v)) = true /\ is_certain (ev_sign (e1 v)) = true /\ is_certain (ev_sign (e2 v)) = true.
Proof.
  intros d a b c k Id Ia Ib Ic. cbv zeta. apply e3_cross_certain. unfold tc_tie_vector; cbv zeta.
  apply cross_small; [now apply lift3_small|].
  destruct (Z.eqb k 0); [|destruct (Z.eqb k 1)]; now apply diff3_small.
Qed.

Theorem normal_vector_int_certain : forall a b c,
  tvec_int_le 15 a -> tvec_int_le 15 b -> tvec_int_le 15 c ->
  let v := tc_normal_vector a b c in
  is_certain (ev_sign (e0 v)) = true /\ is_certain (ev_sign (e1 v)) = true /\ is_certain (ev_sign (e2 v)) = true.
Proof.
  intros a b c Ia Ib Ic. cbv zeta. apply e3_cross_certain. unfold tc_normal_vector.
  apply cross_small; now apply diff3_small.
Qed.

(** ** The cascade decides before the exact stage *)

Section Cascade.
Variables o d a b c : TVec.
Hypothesis Hsign : forall v, is_certain (ev_sign (value_ev o d a b c v)) = true.
Hypothesis Htie : forall k, let v := tc_tie_vector d a b c k in
  is_certain (ev_sign (e0 v)) = true /\ is_certain (ev_sign (e1 v)) = true /\ is_certain (ev_sign (e2 v)) = true.
Hypothesis Hnormal : let v := tc_normal_vector a b c in
  is_certain (ev_sign (e0 v)) = true /\ is_certain (ev_sign (e1 v)) = true /\ is_certain (ev_sign (e2 v)) = true.

Lemma tc_sign_keeps : forall v f, tf_exact (snd (tc_sign_b o d a b c v f)) = tf_exact f.
Proof.
  intros v f. unfold tc_sign_b; cbv zeta.
  destruct (negb _); [reflexivity|]. destruct (is_certain _); [reflexivity|].
  unfold tc_stage3_sign_b. cbv zeta.
  destruct (is_certain (integer_value_sign_b o d a b c v)) eqn:I; [rewrite I; reflexivity|].
  rewrite (Hsign v). reflexivity.
Qed.

Lemma tc_tie_break_keeps : forall k f, tf_exact (snd (tc_tie_break_b d a b c k f)) = tf_exact f.
Proof.
  intros k f. unfold tc_tie_break_b; cbv zeta. destruct (Htie k) as [T0 [T1 T2]]. cbv zeta in T0, T1, T2.
  rewrite T0, T1, T2. reflexivity.
Qed.

Lemma tc_normal_keeps : forall f, tf_exact (snd (tc_normal_b a b c f)) = tf_exact f.
Proof.
  intros f. unfold tc_normal_b; cbv zeta. destruct Hnormal as [T0 [T1 T2]].
  rewrite T0, T1, T2. reflexivity.
Qed.

Lemma tc_owned_step_keeps : forall sden k sk st,
  tf_exact (snd (tc_owned_step d a b c sden k sk st)) = tf_exact (snd st).
Proof.
  intros sden k sk [owned f]. unfold tc_owned_step. destruct (owned && Z.eqb sk 0)%bool; [|reflexivity].
  pose proof (tc_tie_break_keeps k f) as K. destruct (tc_tie_break_b d a b c k f) as [[[tx ty] tz] f'].
  exact K.
Qed.

Lemma tc_classify_keeps : forall rule, tf_exact (snd (tc_classify_b o d a b c rule)) = false.
Proof.
  intros rule. unfold tc_classify_b.
  pose proof (tc_sign_keeps 3 tf_start) as K3. destruct (tc_sign_b o d a b c 3 tf_start) as [sden f1].
  cbn [snd tf_start tf_exact] in K3.
  destruct (Z.eqb sden 0).
  - pose proof (tc_normal_keeps f1) as KN. destruct (tc_normal_b a b c f1) as [deg f2].
    destruct deg; [cbn [snd] in *; congruence|].
    pose proof (tc_sign_keeps 4 f2) as K4. destruct (tc_sign_b o d a b c 4 f2) as [sn f3].
    cbn [snd] in *. congruence.
  - pose proof (tc_sign_keeps 0 f1) as Ka. destruct (tc_sign_b o d a b c 0 f1) as [sa f2].
    pose proof (tc_sign_keeps 1 f2) as Kb. destruct (tc_sign_b o d a b c 1 f2) as [sb f3].
    pose proof (tc_sign_keeps 2 f3) as Kc. destruct (tc_sign_b o d a b c 2 f3) as [sc f4].
    cbn [snd] in Ka, Kb, Kc.
    match goal with |- context [tc_owned_step d a b c sden 2 sc (tc_owned_step d a b c sden 1 sb
                                  (tc_owned_step d a b c sden 0 sa ?st))] =>
      pose proof (tc_owned_step_keeps sden 0 sa st) as O0;
      pose proof (tc_owned_step_keeps sden 1 sb (tc_owned_step d a b c sden 0 sa st)) as O1;
      pose proof (tc_owned_step_keeps sden 2 sc (tc_owned_step d a b c sden 1 sb
                                                   (tc_owned_step d a b c sden 0 sa st))) as O2 end.
    destruct (tc_owned_step d a b c sden 2 sc _) as [owned f5]. cbn [snd] in O0, O1, O2.
    destruct (if rule then owned else _); [|cbn [snd]; congruence].
    pose proof (tc_sign_keeps 4 f5) as K4. destruct (tc_sign_b o d a b c 4 f5) as [sn f6].
    cbn [snd] in *. congruence.
Qed.

Lemma tc_relation_keeps : forall rule, tc_relation_b rule o d a b c <> TCExact.
Proof.
  intros rule. unfold tc_relation_b. pose proof (tc_classify_keeps rule) as K.
  destruct (tc_classify_b o d a b c rule) as [cl f]. cbn [snd] in K. rewrite K. discriminate.
Qed.

Lemma tc_intersect_keeps : forall want_t want_u rule, tc_intersect_b want_t want_u rule o d a b c <> TCExact.
Proof.
  intros want_t want_u rule. unfold tc_intersect_b. pose proof (tc_classify_keeps rule) as K.
  destruct (tc_classify_b o d a b c rule) as [cl f]. cbn [snd] in K. rewrite K.
  destruct (_ || _)%bool; [discriminate|].
  destruct (if want_t then _ else _) as [n0 f1]. destruct (if want_u then _ else _) as [n1 f2].
  destruct (if want_u then _ else _) as [n2 f3]. destruct (if want_u then _ else _) as [n3 f4].
  destruct (tf_exact f4); [discriminate|]. cbv zeta.
  repeat match goal with |- (if ?x then _ else _) <> TCExact => destruct x end; discriminate.
Qed.

End Cascade.

(** On the class, the twin cascade's stage 3 leaves nothing to the exact stage: [tc_sign_b] never sets
    [needs_exact_], [tc_classify_b] ends with it false under both rules, and the relation and intersection
    cascades do not answer [TCExact]. *)
Section IntClass.
Variables o d a b c : TVec.
Hypotheses (Io : tvec_int_le 15 o) (Id : tvec_int_le 15 d) (Ia : tvec_int_le 15 a) (Ib : tvec_int_le 15 b)
           (Ic : tvec_int_le 15 c).

Let Hs : forall v, is_certain (ev_sign (value_ev o d a b c v)) = true.
Proof. intros v. exact (proj1 (value_ev_int_certain o d a b c v Io Id Ia Ib Ic)). Qed.
Let Ht := fun k => tie_vector_int_certain d a b c k Id Ia Ib Ic.
Let Hn := normal_vector_int_certain a b c Ia Ib Ic.

Theorem tc_sign_int_live : forall v f, tf_exact (snd (tc_sign_b o d a b c v f)) = tf_exact f.
Proof. exact (tc_sign_keeps o d a b c Hs). Qed.

Theorem tc_classify_int_live : forall rule, tf_exact (snd (tc_classify_b o d a b c rule)) = false.
Proof. exact (tc_classify_keeps o d a b c Hs Ht Hn). Qed.

Theorem tc_relation_int_live : forall rule, tc_relation_b rule o d a b c <> TCExact.
Proof. exact (tc_relation_keeps o d a b c Hs Ht Hn). Qed.

Theorem tc_intersect_int_live : forall want_t want_u rule, tc_intersect_b want_t want_u rule o d a b c <> TCExact.
Proof. exact (tc_intersect_keeps o d a b c Hs Ht Hn). Qed.

End IntClass.

(** ** Not vacuous: rays through an edge and through a vertex *)

Definition tvi (x y z : Z) : TVec := TV (fint x) (fint y) (fint z).

Lemma tvi_int : forall k x y z, (0 <= k <= 52)%Z -> (Z.abs x <= 2 ^ k)%Z -> (Z.abs y <= 2 ^ k)%Z ->
  (Z.abs z <= 2 ^ k)%Z -> tvec_int_le k (tvi x y z).
Proof.
  intros k x y z K X Y Z. unfold tvec_int_le, tvi; cbn [tx ty tz].
  refine (conj _ (conj _ _)); apply fint_int; assumption.
Qed.

(** The triangle a = (0,0,0), b = (2,0,0), c = (0,2,0) in z = 0; the ray d = (0,0,−1) from (1,0,1) meets it
    at (1,0,0) on the edge ab (π(a, b), v = 2, exactly 0), from (0,0,1) at the vertex a (π(c, a), v = 1,
    and π(a, b) exactly 0). *)
Definition live_ta := tvi 0 0 0.
Definition live_tb := tvi 2 0 0.
Definition live_tc := tvi 0 2 0.
Definition live_td := tvi 0 0 (-1).
Definition live_edge_o := tvi 1 0 1.
Definition live_vertex_o := tvi 0 0 1.

Lemma live_inputs_in_class :
  tvec_int_le 15 live_ta /\ tvec_int_le 15 live_tb /\ tvec_int_le 15 live_tc /\ tvec_int_le 15 live_td /\
  tvec_int_le 15 live_edge_o /\ tvec_int_le 15 live_vertex_o.
Proof. repeat split; apply tvi_int; lia. Qed.

(** Value v's three twin stages (v: 0, 1, 2 πa, πb, πc; 3 den; 4 num, as [value_ev]): stage 1's lanes,
    stage 2's sign, stage 3's checked sign. *)
Definition tri_stages_b (o d a b c : TVec) (k : Z) :=
  (tc_filter_b o d a b c k, PlaneCascadeTwins.enclosure_sign_b (tc_enclosure2_b o d a b c k), ev_sign (value_ev o d a b c k)).

(** Stage 1 and stage 2 leave the zero π uncertain, stage 3 certifies it Zero; the relation cascade decides
    (a hit on the edge ab, owned by the tie-break) at [StExpansion], under both rules. *)
Theorem tri_stage3_live_edge :
  tri_stages_b live_edge_o live_td live_ta live_tb live_tc 2 = (uncertain_lane, Uncertain, Zero) /\
  tc_relation_b true live_edge_o live_td live_ta live_tb live_tc =
    TCDecided (TC THit (Some EdgeAB) true) StExpansion QNaN QNaN QNaN QNaN StExpansion /\
  tc_relation_b false live_edge_o live_td live_ta live_tb live_tc =
    TCDecided (TC THit (Some EdgeAB) true) StExpansion QNaN QNaN QNaN QNaN StExpansion.
Proof. vm_compute. repeat split; reflexivity. Qed.

Theorem tri_stage3_live_vertex :
  tri_stages_b live_vertex_o live_td live_ta live_tb live_tc 1 = (uncertain_lane, Uncertain, Zero) /\
  tri_stages_b live_vertex_o live_td live_ta live_tb live_tc 2 = (uncertain_lane, Uncertain, Zero) /\
  tc_relation_b true live_vertex_o live_td live_ta live_tb live_tc =
    TCDecided (TC THit (Some VertexA) true) StExpansion QNaN QNaN QNaN QNaN StExpansion /\
  tc_relation_b false live_vertex_o live_td live_ta live_tb live_tc =
    TCDecided (TC THit (Some VertexA) true) StExpansion QNaN QNaN QNaN QNaN StExpansion.
Proof. vm_compute. repeat split; reflexivity. Qed.

(** ** Sharpness of the class's derivation *)

(** k = 17: o = (−2^17, −2^17, −2^17), a = o + (0, 0, 2^18 − 1), b = o + (2^18 − 1, 0, 0), c = o + (0, 2^18 − 1, 0),
    every component of magnitude ≤ 2^17: num = (2^18 − 1)^3, odd and above 2^53, is not a double, so the
    leaf·cross TwoProduct has a nonzero low part and num's expansion has two components (it is still exact
    and its checked sign still certain: the class is sufficient, not necessary). *)
Definition sharp_o := tvi (- 2 ^ 17) (- 2 ^ 17) (- 2 ^ 17).
Definition sharp_a := tvi (- 2 ^ 17) (- 2 ^ 17) (2 ^ 17 - 1).
Definition sharp_b := tvi (2 ^ 17 - 1) (- 2 ^ 17) (- 2 ^ 17).
Definition sharp_c := tvi (- 2 ^ 17) (2 ^ 17 - 1) (- 2 ^ 17).

Theorem tri_stage3_k17_two_components :
  tvec_int_le 17 sharp_o /\ tvec_int_le 17 sharp_a /\ tvec_int_le 17 sharp_b /\ tvec_int_le 17 sharp_c /\
  length (ecomp (value_ev sharp_o live_td sharp_a sharp_b sharp_c 4)) = 2%nat /\
  eexact (value_ev sharp_o live_td sharp_a sharp_b sharp_c 4) = true /\
  ev_sign (value_ev sharp_o live_td sharp_a sharp_b sharp_c 4) = Positive.
Proof.
  split; [apply tvi_int; lia|]. split; [apply tvi_int; lia|]. split; [apply tvi_int; lia|].
  split; [apply tvi_int; lia|]. vm_compute. repeat split; reflexivity.
Qed.
