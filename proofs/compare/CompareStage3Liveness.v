(** * Liveness of stage 3 of the nearest-hit comparison (compare_quotients.hpp, [compare_quotients_expansion]).

    [compare_quotients_expansion] multiplies the stage-3 expansions of num and den of two planes exactly and
    returns the checked sign ([Expansion::sign], twin [expansion_sign_b]) of the expansion of
    Δ = N_a·D_b − N_b·D_a.  Soundness is Expansions.v's [compare_quotients_expansion_sound]; this file proves
    that it does certify, on the twin [compare_quotients_expansion_b] that the runner checks against the C++:
    - [compare_quotients_expansion_single]: four one-component expansions of integers whose cross products
      are at most 2^51 in magnitude: both products and Δ stay one-component (every TwoProduct/TwoSum low
      part is 0 and zero elimination drops it; PlaneStage3Liveness.v's [scale_single], [sum_single]), every
      flag stays true, and the checked sign is certain and is the sign of Δ;
    - [compare_stage3_int_live_gen]: for two queries (same o, d; planes (p_a, n_a), (p_b, n_b)) whose
      components are integers of magnitude ≤ 2^24 (so num and den are one-component,
      PlaneStage3Liveness.v's [expansions_int_single]) with |N_a·D_b|, |N_b·D_a| ≤ 2^51: the stage answers, with
      the exact sign of Δ;
    - [compare_stage3_int_live]: the same for every component an integer of magnitude ≤ 2^11, the largest k
      for which the crude bounds |N| ≤ 3·2^(2k+1), |D| ≤ 3·2^(2k) keep |Δ| ≤ 2·9·2^(4k+1) below 2^52
      (k = 12 gives 9·2^50 > 2^52);
    - [compare_hit_distances_int_live], [compare_hit_distances_int_correct]: on that class
      [compare_hit_distances_b] (nearest_hit's comparison) decides before the exact (CGAL) stage, and its
      order is sign(t_a − t_b);
    - [compare_stage3_tie_example]: non-vacuity, by [vm_compute] on the twins: an exact tie (t_a = t_b = 2
      from different planes, Δ = 0) on which stages 1 and 2 are uncertain (only an exact stage can certify
      Δ = 0) and stage 3 answers Zero, so [compare_hit_distances_b] returns (0, stage 2 = expansion);
      [compare_stage3_tie_in_class] shows the input is in the class of [compare_stage3_int_live];
    - beyond one-component products, the exact ties: [compare_quotients_expansion_int_tie],
      [compare_stage3_int_tie], [compare_hit_distances_int_tie_live]: every component an integer of magnitude
      ≤ 2^24 and N_a·D_b = N_b·D_a: the products (up to 2^104) are [lo, hi] with hi = RN(P), lo = P − hi
      ([two_prod_int], [multiply_int]), equal on a tie, the merge pairs lo with −lo and hi with −hi
      ([merge_two]), every TwoSum of Δ's sum has a representable sum and a zero low part (PlaneStage3Liveness.v's
      [two_sum_repr], generalised there from its [two_sum_small]; [sum_pairs4]), so Δ's expansion is the single zero and the stage answers Zero; witness
      [compare_stage3_tie2_example] (a tie near 2^72 whose products have two components, stages 1 and 2
      uncertain) and [compare_stage3_tie2_in_class].

    Not covered, and not true in general: Δ ≠ 0 with multi-component products.  The checked sign is certain
    when 2·(rounded Σ|lower components|) < |top|, which a nonoverlapping expansion can fail (top = 2^m, a
    lower part of magnitude 2^(m−1)): [compare_stage3_uncertain_example] is such an input with components
    below 2^24 ([compare_stage3_uncertain_in_class]), Δ = 2^14 and Δ's expansion [−2^14, 2^15]; stage 2
    decides it (proofs/README.md, "What remains"). *)

From Coq Require Import Reals ZArith List Lia Lra Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneClassification CompareQuotients PlaneCascade FloatCore ConstantsCpp PlaneTwins Expansions
  CompareTwins PlaneQueryTwins PlaneQueryPairTwins NearestTwins PlaneStage3Liveness.
From Raykernel Require PlaneCascadeTwins.
Import ListNotations.
Open Scope R_scope.

(** ** Stage 3 on one-component integer expansions *)

Lemma multiply_one : forall fts ex e f0, multiply_gen fts ex e [f0] = scale_gen fts ex e f0.
Proof. intros. unfold multiply_gen. cbn [accumulate]. now destruct (scale_gen fts ex e f0). Qed.

Lemma small_of_le51 : forall z, (Z.abs z <= 2 ^ 51)%Z -> small (IZR z).
Proof. intros z B. apply small_int. apply Z.le_trans with (1 := B). apply Z.pow_le_mono_r; lia. Qed.

Lemma single_int : forall x z, fin x = true -> B2R x = IZR z -> (Z.abs z <= 2 ^ 52)%Z -> single [x] (B2R x).
Proof. intros x z F V B. exists x. repeat split; auto. rewrite V. now apply small_int. Qed.

(** The product [multiply_expansions] of [x] by [y]: one component, the exact product, flag unchanged. *)
Lemma multiply_single : forall ex x y zx zy, fin x = true -> fin y = true -> B2R x = IZR zx -> B2R y = IZR zy ->
  (Z.abs zx <= 2 ^ 52)%Z -> (Z.abs (zx * zy) <= 2 ^ 51)%Z ->
  exists w, multiply_gen two_sum_b ex [x] [y] = (ex, [w]) /\ fin w = true /\ B2R w = IZR (zx * zy).
Proof.
  intros ex x y zx zy Fx Fy Vx Vy Bx B. rewrite multiply_one.
  destruct (scale_single ex [x] (B2R x) y zy (single_int x zx Fx Vx Bx) Fy Vy (ex_intro _ zx Vx))
    as [E [w [L [Fw [Vw _]]]]].
  { rewrite Vx, Vy, <- mult_IZR. now apply small_of_le51. }
  exists w. split; [|split; [exact Fw | rewrite Vw, Vx, Vy, mult_IZR; reflexivity]].
  destruct (scale_gen two_sum_b ex [x] y) as [b l]. cbn [fst snd] in E, L. now rewrite E, L.
Qed.

(** [compare_quotients_expansion] on one-component integer expansions with cross products of magnitude at
    most 2^51: certain, and the sign of Δ = x_1·y_2 − x_2·y_1. *)
Theorem compare_quotients_expansion_single : forall x1 y1 x2 y2 zx1 zy1 zx2 zy2,
  fin x1 = true -> fin y1 = true -> fin x2 = true -> fin y2 = true ->
  B2R x1 = IZR zx1 -> B2R y1 = IZR zy1 -> B2R x2 = IZR zx2 -> B2R y2 = IZR zy2 ->
  (Z.abs zx1 <= 2 ^ 52)%Z -> (Z.abs zx2 <= 2 ^ 52)%Z ->
  (Z.abs (zx1 * zy2) <= 2 ^ 51)%Z -> (Z.abs (zx2 * zy1) <= 2 ^ 51)%Z ->
  compare_quotients_expansion_b [x1] [y1] true [x2] [y2] true <> Uncertain /\
  certifies (compare_quotients_expansion_b [x1] [y1] true [x2] [y2] true) (B2R x1 * B2R y2 - B2R x2 * B2R y1).
Proof.
  intros x1 y1 x2 y2 zx1 zy1 zx2 zy2 F1 G1 F2 G2 V1 W1 V2 W2 B1 B2 P1 P2.
  destruct (multiply_single true x1 y2 zx1 zy2 F1 G2 V1 W2 B1 P1) as [w1 [M1 [Fw1 Vw1]]].
  destruct (multiply_single true x2 y1 zx2 zy1 F2 G1 V2 W1 B2 P2) as [w2 [M2 [Fw2 Vw2]]].
  assert (S1 : single [w1] (B2R w1)) by (exists w1; repeat split; auto; rewrite Vw1; now apply small_of_le51).
  assert (S2 : single [fneg w2] (- B2R w2)).
  { exists (fneg w2). rewrite fneg_fin, fneg_val. repeat split; auto. apply small_opp. rewrite Vw2. now apply small_of_le51. }
  assert (S : small (B2R w1 + - B2R w2)).
  { rewrite Vw1, Vw2, <- opp_IZR, <- plus_IZR. apply small_int.
    assert (2 ^ 52 = 2 ^ 51 + 2 ^ 51)%Z as -> by reflexivity. lia. }
  destruct (sum_single _ _ _ _ S1 S2 S) as [w [Ew [Fw [Vw _]]]].
  assert (Eq : compare_quotients_expansion_b [x1] [y1] true [x2] [y2] true = expansion_sign_b [w]).
  { unfold compare_quotients_expansion_gen. cbn [andb negb]. rewrite M1. cbn [fst snd]. rewrite M2. cbn [fst snd map].
    rewrite Ew. unfold check_finite. cbn [forallb andb]. now rewrite Fw1, fneg_fin, Fw2, Fw. }
  rewrite Eq. destruct (expansion_sign_single_exact w Fw) as [U C]. split; [exact U|].
  rewrite Vw in C. rewrite V1, V2, W1, W2, <- !mult_IZR. rewrite Vw1, Vw2 in C.
  replace (IZR (zx1 * zy2) - IZR (zx2 * zy1)) with (IZR (zx1 * zy2) + - IZR (zx2 * zy1)) by ring. exact C.
Qed.

(** ** Integer queries: num and den are integers, and their expansions are one component each *)

Lemma diff_bound : forall a b k, (0 <= k)%Z -> (Z.abs a <= 2 ^ k)%Z -> (Z.abs b <= 2 ^ k)%Z ->
  (Z.abs (a - b) <= 2 ^ (k + 1))%Z.
Proof. intros a b k K A B. rewrite Z.pow_add_r by lia. change (2 ^ 1)%Z with 2%Z. lia. Qed.

Lemma abs3_le : forall a b c m, (Z.abs a <= m -> Z.abs b <= m -> Z.abs c <= m -> Z.abs (a + b + c) <= 3 * m)%Z.
Proof. intros. lia. Qed.

Lemma sumR_one : forall x, sumR [x] = B2R x.
Proof. intros x. unfold sumR. simpl. ring. Qed.

Lemma num_int : forall k o p n, (0 <= k)%Z -> vec_int_le k o -> vec_int_le k p -> vec_int_le k n ->
  exists z, ray_num (vec_R o) (vec_R p) (vec_R n) = IZR z /\ (Z.abs z <= 3 * 2 ^ (2 * k + 1))%Z.
Proof.
  intros k [o0 o1 o2] [p0 p1 p2] [n0 n1 n2] K [Io0 [Io1 Io2]] [Ip0 [Ip1 Ip2]] [In0 [In1 In2]].
  cbn [vxb vyb vzb] in *.
  destruct Io0 as [_ [a0 [Va0 Ba0]]]; destruct Io1 as [_ [a1 [Va1 Ba1]]]; destruct Io2 as [_ [a2 [Va2 Ba2]]].
  destruct Ip0 as [_ [b0 [Vb0 Bb0]]]; destruct Ip1 as [_ [b1 [Vb1 Bb1]]]; destruct Ip2 as [_ [b2 [Vb2 Bb2]]].
  destruct In0 as [_ [c0 [Vc0 Bc0]]]; destruct In1 as [_ [c1 [Vc1 Bc1]]]; destruct In2 as [_ [c2 [Vc2 Bc2]]].
  exists ((b0 - a0) * c0 + (b1 - a1) * c1 + (b2 - a2) * c2)%Z. split.
  - rewrite ray_num_bits. cbn [vxb vyb vzb]. rewrite Va0, Va1, Va2, Vb0, Vb1, Vb2, Vc0, Vc1, Vc2.
    rewrite !plus_IZR, !mult_IZR, !minus_IZR. ring.
  - pose proof (zmul_bound _ _ _ _ (diff_bound b0 a0 k K Bb0 Ba0) Bc0 ltac:(lia) K) as M0.
    pose proof (zmul_bound _ _ _ _ (diff_bound b1 a1 k K Bb1 Ba1) Bc1 ltac:(lia) K) as M1.
    pose proof (zmul_bound _ _ _ _ (diff_bound b2 a2 k K Bb2 Ba2) Bc2 ltac:(lia) K) as M2.
    replace (k + 1 + k)%Z with (2 * k + 1)%Z in M0, M1, M2 by ring. now apply abs3_le.
Qed.

Lemma den_int : forall k d n, (0 <= k)%Z -> vec_int_le k d -> vec_int_le k n ->
  exists z, ray_den (vec_R d) (vec_R n) = IZR z /\ (Z.abs z <= 3 * 2 ^ (2 * k))%Z.
Proof.
  intros k [d0 d1 d2] [n0 n1 n2] K [Id0 [Id1 Id2]] [In0 [In1 In2]]. cbn [vxb vyb vzb] in *.
  destruct Id0 as [_ [a0 [Va0 Ba0]]]; destruct Id1 as [_ [a1 [Va1 Ba1]]]; destruct Id2 as [_ [a2 [Va2 Ba2]]].
  destruct In0 as [_ [c0 [Vc0 Bc0]]]; destruct In1 as [_ [c1 [Vc1 Bc1]]]; destruct In2 as [_ [c2 [Vc2 Bc2]]].
  exists (a0 * c0 + a1 * c1 + a2 * c2)%Z. split.
  - rewrite ray_den_bits. cbn [vxb vyb vzb]. rewrite Va0, Va1, Va2, Vc0, Vc1, Vc2.
    rewrite !plus_IZR, !mult_IZR. ring.
  - pose proof (zmul_bound _ _ _ _ Ba0 Bc0 K K) as M0. pose proof (zmul_bound _ _ _ _ Ba1 Bc1 K K) as M1.
    pose proof (zmul_bound _ _ _ _ Ba2 Bc2 K K) as M2.
    replace (k + k)%Z with (2 * k)%Z in M0, M1, M2 by ring. now apply abs3_le.
Qed.

Lemma int_le_mono : forall k l x, (0 <= k <= l)%Z -> int_le k x -> int_le l x.
Proof.
  intros k l x K [F [z [V B]]]. split; [exact F|]. exists z. split; [exact V|].
  apply Z.le_trans with (1 := B). apply Z.pow_le_mono_r; lia.
Qed.

Lemma vec_int_le_mono : forall k l v, (0 <= k <= l)%Z -> vec_int_le k v -> vec_int_le l v.
Proof. intros k l v K [X [Y Z]]. split; [|split]; eapply int_le_mono; eauto. Qed.

(** One query with integer components ≤ 2^24: its stage-3 expansions are exact, [num] and [den] one finite
    integer component each, of values num and den. *)
Lemma query_expansions_int : forall o d p n,
  vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 p -> vec_int_le 24 n ->
  exists x y zx zy, ray_plane_expansions_b two_sum_b o d p n = ([x], [y], true) /\
    fin x = true /\ fin y = true /\ B2R x = IZR zx /\ B2R y = IZR zy /\
    ray_num (vec_R o) (vec_R p) (vec_R n) = IZR zx /\ ray_den (vec_R d) (vec_R n) = IZR zy /\
    (Z.abs zx <= 2 ^ 52)%Z /\ (Z.abs zy <= 2 ^ 52)%Z.
Proof.
  intros o d p n Io Id Ip In. destruct (expansions_int_single o d p n Io Id Ip In) as [x [y E]].
  change (PlaneCascadeTwins.expansions_b o d p n) with (ray_plane_expansions_b two_sum_b o d p n) in E.
  pose proof (ray_plane_expansions_twin_exact o d p n) as X. rewrite E in X.
  destruct (X eq_refl) as [Fx [Fy [Sx Sy]]].
  inversion Fx as [| ? ? Fx' _]; inversion Fy as [| ? ? Fy' _]; subst.
  destruct (num_int 24 o p n ltac:(lia) Io Ip In) as [zx [Nx Bx]].
  destruct (den_int 24 d n ltac:(lia) Id In) as [zy [Ny By]].
  rewrite sumR_one in Sx, Sy.
  exists x, y, zx, zy. repeat split; auto; try congruence.
  - apply Z.le_trans with (1 := Bx). change (3 * 2 ^ (2 * 24 + 1) <= 2 ^ 52)%Z. lia.
  - apply Z.le_trans with (1 := By). change (3 * 2 ^ (2 * 24) <= 2 ^ 52)%Z. lia.
Qed.

(** ** The comparison's stage 3 certifies on integer queries *)

(** Integer components ≤ 2^24 whose cross products N_a·D_b, N_b·D_a are at most 2^51 in magnitude:
    [compare_quotients_expansion] on the two queries' stage-3 expansions is certain and is the sign of Δ. *)
Theorem compare_stage3_int_live_gen : forall o d pa na pb nb,
  vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 pa -> vec_int_le 24 na -> vec_int_le 24 pb ->
  vec_int_le 24 nb ->
  Rabs (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb)) <= bpow radix2 51 ->
  Rabs (ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)) <= bpow radix2 51 ->
  let '(xna, xda, xa) := ray_plane_expansions_b two_sum_b o d pa na in
  let '(xnb, xdb, xb) := ray_plane_expansions_b two_sum_b o d pb nb in
  compare_quotients_expansion_b xna xda xa xnb xdb xb <> Uncertain /\
  certifies (compare_quotients_expansion_b xna xda xa xnb xdb xb)
    (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
     ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)).
Proof.
  intros o d pa na pb nb Io Id Ipa Ina Ipb Inb Pa Pb.
  destruct (query_expansions_int o d pa na Io Id Ipa Ina) as [x1 [y1 [zx1 [zy1 [E1 [F1 [G1 [V1 [W1 [N1 [D1 [B1 C1]]]]]]]]]]]].
  destruct (query_expansions_int o d pb nb Io Id Ipb Inb) as [x2 [y2 [zx2 [zy2 [E2 [F2 [G2 [V2 [W2 [N2 [D2 [B2 C2]]]]]]]]]]]].
  rewrite E1, E2, N1, N2, D1, D2. rewrite N1, D2 in Pa. rewrite N2, D1 in Pb.
  rewrite <- mult_IZR, <- abs_IZR in Pa, Pb. change (bpow radix2 51) with (IZR (2 ^ 51)) in Pa, Pb.
  apply le_IZR in Pa, Pb. rewrite Z.abs_mul in Pa, Pb.
  rewrite <- V1, <- W1, <- V2, <- W2.
  apply (compare_quotients_expansion_single x1 y1 x2 y2 zx1 zy1 zx2 zy2); auto; rewrite Z.abs_mul; exact Pa || exact Pb.
Qed.

(** Every component an integer of magnitude ≤ 2^11: |N| ≤ 3·2^23, |D| ≤ 3·2^22, so the cross products are
    at most 9·2^45 ≤ 2^51. *)
Theorem compare_stage3_int_live : forall o d pa na pb nb,
  vec_int_le 11 o -> vec_int_le 11 d -> vec_int_le 11 pa -> vec_int_le 11 na -> vec_int_le 11 pb ->
  vec_int_le 11 nb ->
  let '(xna, xda, xa) := ray_plane_expansions_b two_sum_b o d pa na in
  let '(xnb, xdb, xb) := ray_plane_expansions_b two_sum_b o d pb nb in
  compare_quotients_expansion_b xna xda xa xnb xdb xb <> Uncertain /\
  certifies (compare_quotients_expansion_b xna xda xa xnb xdb xb)
    (ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) -
     ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na)).
Proof.
  intros o d pa na pb nb Io Id Ipa Ina Ipb Inb.
  assert (Cross : forall p1 n1 n2, vec_int_le 11 p1 -> vec_int_le 11 n1 -> vec_int_le 11 n2 ->
            Rabs (ray_num (vec_R o) (vec_R p1) (vec_R n1) * ray_den (vec_R d) (vec_R n2)) <= bpow radix2 51).
  { intros p1 n1 n2 Ip In1 In2.
    destruct (num_int 11 o p1 n1 ltac:(lia) Io Ip In1) as [zn [Vn Bn]].
    destruct (den_int 11 d n2 ltac:(lia) Id In2) as [zd [Vd Bd]].
    rewrite Vn, Vd, <- mult_IZR, <- abs_IZR. change (bpow radix2 51) with (IZR (2 ^ 51)). apply IZR_le.
    rewrite Z.abs_mul. change (2 * 11 + 1)%Z with 23%Z in Bn. change (2 * 11)%Z with 22%Z in Bd.
    apply Z.le_trans with ((3 * 2 ^ 23) * (3 * 2 ^ 22))%Z; [apply Z.mul_le_mono_nonneg; lia | vm_compute; discriminate]. }
  assert (K : (0 <= 11 <= 24)%Z) by lia.
  exact (compare_stage3_int_live_gen o d pa na pb nb (vec_int_le_mono _ _ _ K Io) (vec_int_le_mono _ _ _ K Id)
           (vec_int_le_mono _ _ _ K Ipa) (vec_int_le_mono _ _ _ K Ina) (vec_int_le_mono _ _ _ K Ipb)
           (vec_int_le_mono _ _ _ K Inb) (Cross pa na nb Ipa Ina Inb) (Cross pb nb na Ipb Inb Ina)).
Qed.

(** Hence nearest_hit's comparison never reaches the exact stage on that class (whatever signs the
    candidates carry: the shortcuts and stages 1 and 2 answer at stages 0 and 1). *)
Theorem compare_hit_distances_int_live : forall (o d pa na pb nb : Vec3B) (nsa dsa nsb dsb : sign),
  vec_int_le 11 o -> vec_int_le 11 d -> vec_int_le 11 pa -> vec_int_le 11 na -> vec_int_le 11 pb ->
  vec_int_le 11 nb ->
  snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <> 3%Z.
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb Io Id Ipa Ina Ipb Inb.
  pose proof (compare_stage3_int_live o d pa na pb nb Io Id Ipa Ina Ipb Inb) as L.
  unfold compare_hit_distances_b.
  destruct (ray_plane_expansions_b two_sum_b o d pa na) as [[xna xda] xa].
  destruct (ray_plane_expansions_b two_sum_b o d pb nb) as [[xnb xdb] xb].
  destruct L as [U _]. cbv zeta.
  destruct (_ || _)%bool; [cbn [snd]; discriminate|].
  destruct (is_certain_b (compare_quotients_filter_b _ _ _ _)); [cbn [snd]; discriminate|].
  destruct (is_certain_b (sign_from_Z _)); [cbn [snd]; discriminate|].
  destruct (compare_quotients_expansion_b xna xda xa xnb xdb xb); cbn [is_certain_b snd]; try discriminate.
  contradiction.
Qed.

(** ... and, for two hits with certain carried signs (what nearest_hit gives), its order is sign(t_a − t_b). *)
Theorem compare_hit_distances_int_correct : forall (o d pa na pb nb : Vec3B) (nsa dsa nsb dsb : sign),
  vec_int_le 11 o -> vec_int_le 11 d -> vec_int_le 11 pa -> vec_int_le 11 na -> vec_int_le 11 pb ->
  vec_int_le 11 nb ->
  let Na := ray_num (vec_R o) (vec_R pa) (vec_R na) in let Da := ray_den (vec_R d) (vec_R na) in
  let Nb := ray_num (vec_R o) (vec_R pb) (vec_R nb) in let Db := ray_den (vec_R d) (vec_R nb) in
  certifies nsa Na -> nsa <> Uncertain -> certifies dsa Da -> dsa <> Uncertain -> Da <> 0 -> 0 <= Na / Da ->
  certifies nsb Nb -> nsb <> Uncertain -> certifies dsb Db -> dsb <> Uncertain -> Db <> 0 -> 0 <= Nb / Db ->
  snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <> 3%Z /\
  fst (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) = sign_of (Na / Da - Nb / Db).
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb Io Id Ipa Ina Ipb Inb Na Da Nb Db.
  intros Cna Una Cda Uda Zda Pa Cnb Unb Cdb Udb Zdb Pb.
  pose proof (compare_hit_distances_int_live o d pa na pb nb nsa dsa nsb dsb Io Id Ipa Ina Ipb Inb) as L.
  split; [exact L|].
  exact (compare_hit_distances_twin_correct o d pa na pb nb nsa dsa nsb dsb
           Cna Una Cda Uda Zda Pa Cnb Unb Cdb Udb Zdb Pb L).
Qed.

(** ** Non-vacuity: an exact tie, decided by stage 3 *)

(** The comparison's three twin stages on a ray (o, d) and two planes (pa, na), (pb, nb), and the comparison
    itself: (stage 1's sign, stage 2's sign, (the two queries' exact flags, stage 3's sign),
    [compare_hit_distances_b] for two hits).  The examples below state its value. *)
Definition compare_stages_b (o d pa na pb nb : Vec3B) :=
  (compare_quotients_filter_b
     (filter_enclosure_b (stage1_num_b o pa na) Cpp.filter_num_relative)
     (filter_enclosure_b (stage1_den_b d na) Cpp.filter_den_relative)
     (filter_enclosure_b (stage1_num_b o pb nb) Cpp.filter_num_relative)
     (filter_enclosure_b (stage1_den_b d nb) Cpp.filter_den_relative),
   sign_from_Z (enclosure_sign_lanes_b
     (compare_quotients_compensated_b (stage2_num_b o pa na) (stage2_den_b d na)
                                      (stage2_num_b o pb nb) (stage2_den_b d nb))),
   (let '(xna, xda, xa) := ray_plane_expansions_b two_sum_b o d pa na in
    let '(xnb, xdb, xb) := ray_plane_expansions_b two_sum_b o d pb nb in
    (xa, xb, compare_quotients_expansion_b xna xda xa xnb xdb xb)),
   compare_hit_distances_b o d pa na pb nb Positive Positive Positive Positive).

(** o = (0,0,0), d = (1,0,0); plane a: p = (2,0,0), n = (1,0,0): N_a = 2, D_a = 1, t_a = 2; plane b:
    p = (2,5,0), n = (3,0,0): N_b = 6, D_b = 3, t_b = 2.  Δ = 2·3 − 6·1 = 0: stage 1's δ = 0 lies inside its
    positive bound and stage 2's enclosure of Δ is 0 ± a positive radius, so both are uncertain; the
    expansions are [2], [1], [6], [3], the products [6] and [6], Δ's expansion [0]: Zero. *)
Definition tie_o := V3 (fint 0) (fint 0) (fint 0).
Definition tie_d := V3 (fint 1) (fint 0) (fint 0).
Definition tie_pa := V3 (fint 2) (fint 0) (fint 0).
Definition tie_na := V3 (fint 1) (fint 0) (fint 0).
Definition tie_pb := V3 (fint 2) (fint 5) (fint 0).
Definition tie_nb := V3 (fint 3) (fint 0) (fint 0).

Theorem compare_stage3_tie_example :
  compare_stages_b tie_o tie_d tie_pa tie_na tie_pb tie_nb = (Uncertain, Uncertain, (true, true, Zero), (0%Z, 2%Z)).
Proof. vm_compute. repeat split; reflexivity. Qed.

(** The tie is in the class of [compare_stage3_int_live] (so the theorem is not vacuous there, and the
    class holds inputs on which only stage 3 of the three twin stages certifies). *)
Theorem compare_stage3_tie_in_class :
  vec_int_le 11 tie_o /\ vec_int_le 11 tie_d /\ vec_int_le 11 tie_pa /\ vec_int_le 11 tie_na /\
  vec_int_le 11 tie_pb /\ vec_int_le 11 tie_nb.
Proof. repeat split; cbn [vxb vyb vzb]; apply fint_int; cbn; lia. Qed.

(** ** Exact ties on integer queries up to 2^24: stage 3 answers Zero

    Here the products N_a·D_b and N_b·D_a need two components: TwoProduct of integers gives hi = RN(P) and
    lo = P − hi, an integer, so each product expansion is [lo, hi] (or [hi] when lo = 0).  On a tie the two
    products are equal reals, so their components are equal values; the merge pairs lo with −lo and hi with
    −hi, and every TwoSum of Δ's sum is exact with a zero low part: Δ's expansion is the single zero. *)

Lemma eta_le_u : eta <= u.
Proof. rewrite u_val. unfold eta. replace (/ 9007199254740992) with (bpow radix2 (-53)) by reflexivity.
  apply bpow_le. lia. Qed.

(** TwoProduct of two integer doubles ≤ 2^52 with a nonzero product: the guard of [note_product] holds, both
    parts are finite, hi + lo is the product, hi ≠ 0 and |lo| < |hi|. *)
Lemma two_prod_int : forall a b za zb, fin a = true -> fin b = true -> B2R a = IZR za -> B2R b = IZR zb ->
  (Z.abs za <= 2 ^ 52)%Z -> (Z.abs zb <= 2 ^ 52)%Z -> (za * zb <> 0)%Z ->
  note_product_b a b (fst (two_prod_b a b)) = true /\ fin (fst (two_prod_b a b)) = true /\
  fin (snd (two_prod_b a b)) = true /\
  B2R (fst (two_prod_b a b)) + B2R (snd (two_prod_b a b)) = B2R a * B2R b /\
  B2R (fst (two_prod_b a b)) <> 0 /\ Rabs (B2R (snd (two_prod_b a b))) < Rabs (B2R (fst (two_prod_b a b))).
Proof.
  intros a b za zb Fa Fb Va Vb Ba Bb NZ.
  assert (P1 : 1 <= Rabs (B2R a * B2R b)).
  { rewrite Va, Vb, <- mult_IZR, <- abs_IZR. apply IZR_le. lia. }
  assert (P2 : Rabs (B2R a * B2R b) <= bpow radix2 104).
  { rewrite Va, Vb, <- mult_IZR, <- abs_IZR. change (bpow radix2 104) with (IZR (2 ^ 104)). apply IZR_le.
    rewrite Z.abs_mul. change (2 ^ 104)%Z with (2 ^ 52 * 2 ^ 52)%Z. apply Z.mul_le_mono_nonneg; lia. }
  assert (H1 : 1 <= Rabs (RN (B2R a * B2R b))).
  { rewrite <- RN_abs. rewrite <- (RN_binary64 1) by (apply (binary64_bpow 0); lia). now apply RN_le. }
  assert (H2 : Rabs (RN (B2R a * B2R b)) <= bpow radix2 104).
  { rewrite <- RN_abs. rewrite <- (RN_binary64 (bpow radix2 104)) by (apply binary64_bpow; lia). now apply RN_le. }
  assert (L104 : bpow radix2 104 < bpow radix2 1024) by (apply bpow_lt; lia).
  destruct (fmul_fwd a b Fa Fb ltac:(lra)) as [Fh Vh].
  assert (Ex : RN (B2R a * B2R b + - RN (B2R a * B2R b)) = B2R a * B2R b - RN (B2R a * B2R b)).
  { pose proof (two_prod_exact (B2R a) (B2R b) (binary64_B2R a) (binary64_B2R b)) as T.
    unfold two_prod, fma in T; cbn [fst snd] in T.
    assert (bpow radix2 (-969) <= Rabs (B2R a * B2R b)).
    { apply Rle_trans with 1; [apply (bpow_le radix2 (-969) 0); lia | exact P1]. }
    specialize (T ltac:(intros; assumption)). lra. }
  pose proof (RN_err (B2R a * B2R b)) as Err. pose proof u_pos. pose proof eta_le_u. pose proof eta_pos.
  assert (Uv : u <= / 4) by (rewrite u_val; lra).
  assert (Fn : fin (fneg (fmul a b)) = true) by now rewrite fneg_fin.
  destruct (ffma_fwd a b (fneg (fmul a b)) Fa Fb Fn) as [Fl Vl].
  { rewrite fneg_val, Vh, Ex. rewrite Rabs_minus_sym. eapply Rle_lt_trans; [exact Err|].
    apply Rle_lt_trans with (bpow radix2 104); [|exact L104]. nra. }
  rewrite fneg_val, Vh, Ex in Vl.
  change (fst (two_prod_b a b)) with (fmul a b). change (snd (two_prod_b a b)) with (ffma a b (fneg (fmul a b))).
  assert (Nh : B2R (fmul a b) <> 0) by (intros Z; rewrite Vh in Z; rewrite Z, Rabs_R0 in H1; lra).
  split; [|split; [exact Fh | split; [exact Fl | split; [rewrite Vl, Vh; ring | split; [exact Nh |]]]]].
  - unfold note_product_b. rewrite Fh, Bool.andb_true_r.
    rewrite (feq_val _ fzero Fh eq_refl). destruct (Req_bool_spec (B2R (fmul a b)) (B2R fzero)) as [E|E];
      [change (B2R fzero) with 0 in E; contradiction|].
    assert (F0 : fin tiny_product = true) by reflexivity.
    rewrite (fle_val _ _ F0) by now rewrite fabs_fin. apply Rle_bool_true.
    rewrite fabs_val, tiny_product_threshold, Vh. unfold exact_product_threshold.
    apply Rle_trans with 1; [apply (bpow_le radix2 (-968) 0); lia | exact H1].
  - rewrite Vl, Vh. rewrite Rabs_minus_sym.
    assert (Rabs (B2R a * B2R b) <= Rabs (RN (B2R a * B2R b)) + Rabs (RN (B2R a * B2R b) - B2R a * B2R b)).
    { replace (B2R a * B2R b) with (RN (B2R a * B2R b) - (RN (B2R a * B2R b) - B2R a * B2R b)) at 1 by ring.
      apply Rabs_triang_inv2 || (eapply Rle_trans; [apply Rabs_triang|]; rewrite Rabs_Ropp; lra). }
    nra.
Qed.

(** [multiply_expansions] of [x] by [y], integers with a nonzero product: [lo, hi], or [hi] when lo = 0. *)
Lemma multiply_int : forall ex x y zx zy, fin x = true -> fin y = true -> B2R x = IZR zx -> B2R y = IZR zy ->
  (Z.abs zx <= 2 ^ 52)%Z -> (Z.abs zy <= 2 ^ 52)%Z -> (zx * zy <> 0)%Z ->
  exists h l, multiply_gen two_sum_b ex [x] [y] = (ex, if Req_bool (B2R l) 0 then [h] else [l; h]) /\
    fin h = true /\ fin l = true /\ B2R h = RN (B2R x * B2R y) /\ B2R l = B2R x * B2R y - RN (B2R x * B2R y) /\
    B2R h <> 0 /\ Rabs (B2R l) < Rabs (B2R h).
Proof.
  intros ex x y zx zy Fx Fy Vx Vy Bx By NZ.
  destruct (two_prod_int x y zx zy Fx Fy Vx Vy Bx By NZ) as [N [Fh [Fl [S [Nh L]]]]].
  assert (Vh : B2R (fst (two_prod_b x y)) = RN (B2R x * B2R y)) by (apply fmul_val; exact Fh).
  exists (fst (two_prod_b x y)), (snd (two_prod_b x y)). rewrite multiply_one.
  split; [|repeat split; auto; lra].
  unfold scale_gen, product_b. cbn [fst snd scale_loop]. rewrite N, Bool.andb_true_r.
  unfold push. rewrite (feq_val _ fzero Fl eq_refl). change (B2R fzero) with 0.
  destruct (Req_bool (B2R (snd (two_prod_b x y))) 0).
  - now rewrite finish_nil.
  - unfold finish. rewrite (feq_val _ fzero Fh eq_refl). change (B2R fzero) with 0.
    destruct (Req_bool_spec (B2R (fst (two_prod_b x y))) 0) as [E|E]; [contradiction | reflexivity].
Qed.

(** The merge ([take_smaller]) of [l, h] and [−l, −h] (as values), |l| < |h|: the two l's first, then the
    two h's. *)
Lemma take_lower1 : forall h l', fin h = true -> fin l' = true -> Rabs (B2R l') < Rabs (B2R h) ->
  Bool.eqb (flt h l') (flt (fneg h) l') = false.
Proof.
  intros h l' Fh Fl L. rewrite !flt_val by (rewrite ?fneg_fin; assumption). rewrite fneg_val.
  destruct (Rlt_bool_spec (B2R h) (B2R l')); destruct (Rlt_bool_spec (- B2R h) (B2R l')); try reflexivity;
    exfalso; revert L; unfold Rabs; destruct (Rcase_abs (B2R l')); destruct (Rcase_abs (B2R h)); lra.
Qed.

Lemma take_lower2 : forall l h', fin l = true -> fin h' = true -> Rabs (B2R l) < Rabs (B2R h') ->
  Bool.eqb (flt l h') (flt (fneg l) h') = true.
Proof.
  intros l h' Fl Fh L. rewrite !flt_val by (rewrite ?fneg_fin; assumption). rewrite fneg_val.
  destruct (Rlt_bool_spec (B2R l) (B2R h')); destruct (Rlt_bool_spec (- B2R l) (B2R h')); try reflexivity;
    exfalso; revert L; unfold Rabs; destruct (Rcase_abs (B2R l)); destruct (Rcase_abs (B2R h')); lra.
Qed.

Lemma merge_one : forall a b, merge [a] [b] = [a; b] \/ merge [a] [b] = [b; a].
Proof. intros a b. cbn [merge]. destruct (Bool.eqb _ _); auto. Qed.

Lemma merge_two : forall l h l' h', fin l = true -> fin h = true -> fin l' = true -> fin h' = true ->
  Rabs (B2R l) < Rabs (B2R h) -> Rabs (B2R l') = Rabs (B2R l) -> Rabs (B2R h') = Rabs (B2R h) ->
  exists a b c d, merge [l; h] [l'; h'] = [a; b; c; d] /\
    ((a = l /\ b = l') \/ (a = l' /\ b = l)) /\ ((c = h /\ d = h') \/ (c = h' /\ d = h)).
Proof.
  intros l h l' h' Fl Fh Fl' Fh' L El Eh. cbn [merge].
  destruct (Bool.eqb (flt l l') (flt (fneg l) l')).
  - rewrite (take_lower1 h l' Fh Fl') by lra.
    destruct (Bool.eqb (flt h h') (flt (fneg h) h')); eexists _, _, _, _; split; try reflexivity; tauto.
  - rewrite (take_lower2 l h' Fl Fh') by lra.
    destruct (Bool.eqb (flt h h') (flt (fneg h) h')); eexists _, _, _, _; split; try reflexivity; tauto.
Qed.

(** Δ's sum when its merge is pairs of opposite values: every TwoSum is exact with a zero low part. *)
Lemma sum_pairs2 : forall e f a b, merge e f = [a; b] -> fin a = true -> fin b = true -> B2R a + B2R b = 0 ->
  exists q, sum_gen two_sum_b e f = [q] /\ fin q = true /\ B2R q = 0.
Proof.
  intros e f a b M Fa Fb S. unfold sum_gen. rewrite M. cbn [sum_loop].
  destruct (two_sum_repr b a Fb Fa) as [F1 [V1 [F2 V2]]]; [apply (repr_eq _ _ repr_0); lra|].
  rewrite push_zero by assumption. rewrite finish_nil. exists (fst (two_sum_b b a)). repeat split; auto. lra.
Qed.

Lemma sum_pairs4 : forall e f a b c d, merge e f = [a; b; c; d] -> fin a = true -> fin b = true ->
  fin c = true -> fin d = true -> B2R a + B2R b = 0 -> B2R c + B2R d = 0 ->
  exists q, sum_gen two_sum_b e f = [q] /\ fin q = true /\ B2R q = 0.
Proof.
  intros e f a b c d M Fa Fb Fc Fd S1 S2. unfold sum_gen. rewrite M. cbn [sum_loop].
  destruct (two_sum_repr b a Fb Fa) as [F1 [V1 [F2 V2]]]; [apply (repr_eq _ _ repr_0); lra|].
  destruct (two_sum_repr _ c F1 Fc) as [F3 [V3 [F4 V4]]]; [apply (repr_eq _ _ (repr_B2R c)); lra|].
  destruct (two_sum_repr _ d F3 Fd) as [F5 [V5 [F6 V6]]]; [apply (repr_eq _ _ repr_0); lra|].
  rewrite (push_zero [] _ F2 V2), (push_zero [] _ F4 V4), (push_zero [] _ F6 V6), finish_nil.
  eexists. repeat split; [exact F5 | lra].
Qed.

(** An exact tie N_1·D_2 = N_2·D_1 of one-component integer expansions (each ≤ 2^52, products up to 2^104):
    [compare_quotients_expansion] answers Zero. *)
Theorem compare_quotients_expansion_int_tie : forall x1 y1 x2 y2 zx1 zy1 zx2 zy2,
  fin x1 = true -> fin y1 = true -> fin x2 = true -> fin y2 = true ->
  B2R x1 = IZR zx1 -> B2R y1 = IZR zy1 -> B2R x2 = IZR zx2 -> B2R y2 = IZR zy2 ->
  (Z.abs zx1 <= 2 ^ 52)%Z -> (Z.abs zy1 <= 2 ^ 52)%Z -> (Z.abs zx2 <= 2 ^ 52)%Z -> (Z.abs zy2 <= 2 ^ 52)%Z ->
  (zx1 * zy2 = zx2 * zy1)%Z ->
  compare_quotients_expansion_b [x1] [y1] true [x2] [y2] true = Zero.
Proof.
  intros x1 y1 x2 y2 zx1 zy1 zx2 zy2 F1 G1 F2 G2 V1 W1 V2 W2 B1 C1 B2 C2 T.
  destruct (Z.eq_dec (zx1 * zy2) 0) as [Z0|NZ].
  - destruct (compare_quotients_expansion_single x1 y1 x2 y2 zx1 zy1 zx2 zy2 F1 G1 F2 G2 V1 W1 V2 W2 B1 B2
                ltac:(rewrite Z0; lia) ltac:(rewrite <- T, Z0; lia)) as [U C].
    rewrite V1, V2, W1, W2, <- !mult_IZR, <- T, Rminus_diag_eq in C by reflexivity.
    destruct (compare_quotients_expansion_b _ _ _ _ _ _); cbn in C; try lra; congruence.
  - assert (P : B2R x1 * B2R y2 = B2R x2 * B2R y1) by (rewrite V1, V2, W1, W2, <- !mult_IZR; now rewrite T).
    destruct (multiply_int true x1 y2 zx1 zy2 F1 G2 V1 W2 B1 C2 NZ) as [h1 [l1 [M1 [Fh1 [Fl1 [Vh1 [Vl1 [Nh1 L1]]]]]]]].
    destruct (multiply_int true x2 y1 zx2 zy1 F2 G1 V2 W1 B2 C1 ltac:(rewrite <- T; exact NZ))
      as [h2 [l2 [M2 [Fh2 [Fl2 [Vh2 [Vl2 [Nh2 L2]]]]]]]].
    assert (Eh : B2R h2 = B2R h1) by (rewrite Vh1, Vh2, P; reflexivity).
    assert (El : B2R l2 = B2R l1) by (rewrite Vl1, Vl2, P; reflexivity).
    unfold compare_quotients_expansion_gen. cbn [andb negb]. rewrite M1. cbn [fst snd]. rewrite M2. cbn [fst snd].
    rewrite El. destruct (Req_bool (B2R l1) 0).
    + cbn [map].
      assert (Fn : fin (fneg h2) = true) by now rewrite fneg_fin.
      assert (S : B2R h1 + B2R (fneg h2) = 0) by (rewrite fneg_val, Eh; ring).
      destruct (merge_one h1 (fneg h2)) as [M|M];
        [destruct (sum_pairs2 _ _ _ _ M Fh1 Fn S) as [q [Eq [Fq Vq]]]
        |destruct (sum_pairs2 _ _ _ _ M Fn Fh1 ltac:(lra)) as [q [Eq [Fq Vq]]]];
      rewrite Eq; unfold check_finite; cbn [forallb andb]; rewrite Fh1, Fn, Fq; cbn [andb];
      destruct (expansion_sign_single_exact q Fq) as [U C]; rewrite Vq in C;
      destruct (expansion_sign_b [q]); cbn in C; try lra; congruence.
    + cbn [map].
      assert (Fn1 : fin (fneg l2) = true) by now rewrite fneg_fin.
      assert (Fn2 : fin (fneg h2) = true) by now rewrite fneg_fin.
      destruct (merge_two l1 h1 (fneg l2) (fneg h2) Fl1 Fh1 Fn1 Fn2 L1
                  ltac:(rewrite fneg_val, Rabs_Ropp, El; reflexivity)
                  ltac:(rewrite fneg_val, Rabs_Ropp, Eh; reflexivity)) as [a [b [c [d [M [AB CD]]]]]].
      assert (Sab : B2R a + B2R b = 0) by (destruct AB as [[-> ->]|[-> ->]]; rewrite fneg_val, El; ring).
      assert (Scd : B2R c + B2R d = 0) by (destruct CD as [[-> ->]|[-> ->]]; rewrite fneg_val, Eh; ring).
      assert (Fa : fin a = true) by (destruct AB as [[-> ->]|[-> ->]]; assumption).
      assert (Fb : fin b = true) by (destruct AB as [[-> ->]|[-> ->]]; assumption).
      assert (Fc : fin c = true) by (destruct CD as [[-> ->]|[-> ->]]; assumption).
      assert (Fd : fin d = true) by (destruct CD as [[-> ->]|[-> ->]]; assumption).
      destruct (sum_pairs4 _ _ _ _ _ _ M Fa Fb Fc Fd Sab Scd) as [q [Eq [Fq Vq]]].
      rewrite Eq. unfold check_finite. cbn [forallb andb]. rewrite Fl1, Fh1, Fn1, Fn2, Fq. cbn [andb].
      destruct (expansion_sign_single_exact q Fq) as [U C]. rewrite Vq in C.
      destruct (expansion_sign_b [q]); cbn in C; try lra; congruence.
Qed.

(** Two queries (same o, d) with every component an integer of magnitude ≤ 2^24 and an exact tie
    N_a·D_b = N_b·D_a: stage 3 of the comparison answers Zero (the products need not be one double). *)
Theorem compare_stage3_int_tie : forall o d pa na pb nb,
  vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 pa -> vec_int_le 24 na -> vec_int_le 24 pb ->
  vec_int_le 24 nb ->
  ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) =
  ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na) ->
  let '(xna, xda, xa) := ray_plane_expansions_b two_sum_b o d pa na in
  let '(xnb, xdb, xb) := ray_plane_expansions_b two_sum_b o d pb nb in
  compare_quotients_expansion_b xna xda xa xnb xdb xb = Zero.
Proof.
  intros o d pa na pb nb Io Id Ipa Ina Ipb Inb T.
  destruct (query_expansions_int o d pa na Io Id Ipa Ina) as [x1 [y1 [zx1 [zy1 [E1 [F1 [G1 [V1 [W1 [N1 [D1 [B1 C1]]]]]]]]]]]].
  destruct (query_expansions_int o d pb nb Io Id Ipb Inb) as [x2 [y2 [zx2 [zy2 [E2 [F2 [G2 [V2 [W2 [N2 [D2 [B2 C2]]]]]]]]]]]].
  rewrite E1, E2. rewrite N1, N2, D1, D2, <- !mult_IZR in T. apply eq_IZR in T.
  exact (compare_quotients_expansion_int_tie x1 y1 x2 y2 zx1 zy1 zx2 zy2 F1 G1 F2 G2 V1 W1 V2 W2 B1 C1 B2 C2 T).
Qed.

(** Hence nearest_hit's comparison decides every such tie before the exact stage. *)
Theorem compare_hit_distances_int_tie_live : forall (o d pa na pb nb : Vec3B) (nsa dsa nsb dsb : sign),
  vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 pa -> vec_int_le 24 na -> vec_int_le 24 pb ->
  vec_int_le 24 nb ->
  ray_num (vec_R o) (vec_R pa) (vec_R na) * ray_den (vec_R d) (vec_R nb) =
  ray_num (vec_R o) (vec_R pb) (vec_R nb) * ray_den (vec_R d) (vec_R na) ->
  snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <> 3%Z.
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb Io Id Ipa Ina Ipb Inb T.
  pose proof (compare_stage3_int_tie o d pa na pb nb Io Id Ipa Ina Ipb Inb T) as L.
  unfold compare_hit_distances_b.
  destruct (ray_plane_expansions_b two_sum_b o d pa na) as [[xna xda] xa].
  destruct (ray_plane_expansions_b two_sum_b o d pb nb) as [[xnb xdb] xb].
  cbv zeta.
  destruct (_ || _)%bool; [cbn [snd]; discriminate|].
  destruct (is_certain_b (compare_quotients_filter_b _ _ _ _)); [cbn [snd]; discriminate|].
  destruct (is_certain_b (sign_from_Z _)); [cbn [snd]; discriminate|].
  rewrite L. cbn [is_certain_b snd]. discriminate.
Qed.

(** ... and, for two hits with certain carried signs, its order is sign(t_a − t_b) = 0. *)
Theorem compare_hit_distances_int_tie_correct : forall (o d pa na pb nb : Vec3B) (nsa dsa nsb dsb : sign),
  vec_int_le 24 o -> vec_int_le 24 d -> vec_int_le 24 pa -> vec_int_le 24 na -> vec_int_le 24 pb ->
  vec_int_le 24 nb ->
  let Na := ray_num (vec_R o) (vec_R pa) (vec_R na) in let Da := ray_den (vec_R d) (vec_R na) in
  let Nb := ray_num (vec_R o) (vec_R pb) (vec_R nb) in let Db := ray_den (vec_R d) (vec_R nb) in
  Na * Db = Nb * Da ->
  certifies nsa Na -> nsa <> Uncertain -> certifies dsa Da -> dsa <> Uncertain -> Da <> 0 -> 0 <= Na / Da ->
  certifies nsb Nb -> nsb <> Uncertain -> certifies dsb Db -> dsb <> Uncertain -> Db <> 0 -> 0 <= Nb / Db ->
  snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) <> 3%Z /\
  fst (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) = sign_of (Na / Da - Nb / Db).
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb Io Id Ipa Ina Ipb Inb Na Da Nb Db T.
  intros Cna Una Cda Uda Zda Pa Cnb Unb Cdb Udb Zdb Pb.
  pose proof (compare_hit_distances_int_tie_live o d pa na pb nb nsa dsa nsb dsb Io Id Ipa Ina Ipb Inb T) as L.
  split; [exact L|].
  exact (compare_hit_distances_twin_correct o d pa na pb nb nsa dsa nsb dsb
           Cna Una Cda Uda Zda Pa Cnb Unb Cdb Udb Zdb Pb L).
Qed.

(** Non-vacuity beyond one-component products: o = 0, d = (1,0,0), plane a: p = (2^24 − 1, 0, 0),
    n = (2^24 − 3, 0, 0); plane b: p = (2^24 − 1, 7, 0), n = (2^24 − 5, 0, 0).  t_a = t_b = 2^24 − 1, and
    N_a·D_b = (2^24 − 1)(2^24 − 3)(2^24 − 5), an odd number near 2^72, is not a double: the product
    expansions have two components.  Stages 1 and 2 are uncertain, stage 3 answers Zero. *)
Definition tie2_o := V3 (fint 0) (fint 0) (fint 0).
Definition tie2_d := V3 (fint 1) (fint 0) (fint 0).
Definition tie2_pa := V3 (fint 16777215) (fint 0) (fint 0).
Definition tie2_na := V3 (fint 16777213) (fint 0) (fint 0).
Definition tie2_pb := V3 (fint 16777215) (fint 7) (fint 0).
Definition tie2_nb := V3 (fint 16777211) (fint 0) (fint 0).

Theorem compare_stage3_tie2_example :
  compare_stages_b tie2_o tie2_d tie2_pa tie2_na tie2_pb tie2_nb = (Uncertain, Uncertain, (true, true, Zero), (0%Z, 2%Z)) /\
  (let '(xna, xda, _) := ray_plane_expansions_b two_sum_b tie2_o tie2_d tie2_pa tie2_na in
   let '(xnb, xdb, _) := ray_plane_expansions_b two_sum_b tie2_o tie2_d tie2_pb tie2_nb in
   (length (snd (multiply_gen two_sum_b true xna xdb)), length (snd (multiply_gen two_sum_b true xnb xda))))
    = (2%nat, 2%nat).
Proof. vm_compute. repeat split; reflexivity. Qed.

Theorem compare_stage3_tie2_in_class :
  vec_int_le 24 tie2_o /\ vec_int_le 24 tie2_d /\ vec_int_le 24 tie2_pa /\ vec_int_le 24 tie2_na /\
  vec_int_le 24 tie2_pb /\ vec_int_le 24 tie2_nb.
Proof. repeat split; cbn [vxb vyb vzb]; apply fint_int; cbn; lia. Qed.

(** Why ties: with two-component products stage 3 alone need not certify Δ ≠ 0.  o = 0, d = (1,0,0), plane a:
    p = (4599108, 11152844, 0), n = (11499133, 1, 0); plane b: p = (4599108, 5173596, 0), n = (5334233, 1, 0)
    (every component an integer below 2^24).  N_a·D_b = H + 2^13 and N_b·D_a = H − 2^13 for H an odd multiple
    of 2^15 = ulp(H) in [2^67, 2^68): both products round to H, their low parts are ±2^13, and the sum
    of Δ's expansion rounds H + 2^14 (a midpoint) to the even neighbour H + 2^15, leaving [−2^14, 2^15]: exact
    (Δ = 2^14) but 2·2^14 < 2^15 fails, so the checked sign is uncertain (found by search: it needs the
    midpoint).  Stage 1 is uncertain and stage 2 decides (order 1, t_a > t_b): [compare_hit_distances_b]
    returns at stage 1 (compensated). *)
Definition unc_o := V3 (fint 0) (fint 0) (fint 0).
Definition unc_d := V3 (fint 1) (fint 0) (fint 0).
Definition unc_pa := V3 (fint 4599108) (fint 11152844) (fint 0).
Definition unc_na := V3 (fint 11499133) (fint 1) (fint 0).
Definition unc_pb := V3 (fint 4599108) (fint 5173596) (fint 0).
Definition unc_nb := V3 (fint 5334233) (fint 1) (fint 0).

Theorem compare_stage3_uncertain_example :
  compare_stages_b unc_o unc_d unc_pa unc_na unc_pb unc_nb = (Uncertain, Positive, (true, true, Uncertain), (1%Z, 1%Z)).
Proof. vm_compute. repeat split; reflexivity. Qed.

Theorem compare_stage3_uncertain_in_class :
  vec_int_le 24 unc_o /\ vec_int_le 24 unc_d /\ vec_int_le 24 unc_pa /\ vec_int_le 24 unc_na /\
  vec_int_le 24 unc_pb /\ vec_int_le 24 unc_nb.
Proof. repeat split; cbn [vxb vyb vzb]; apply fint_int; cbn; lia. Qed.
