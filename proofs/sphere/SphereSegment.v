(** * Whether a sphere meets an open segment (kernel/src/sphere/ray_sphere_formula.hpp, [segment_root_inside];
    kernel/src/sphere/ray_sphere_cascade.cpp, [segment_meets_sphere]'s two shortcuts).

    The open segment from p to q is the line p + t·e, 0 < t < 1, with the exact direction e = q − p.  With
    A = e·e > 0, B = e·(p − c), C = C_p = |p − c|² − r² and D = B² − A·C, the point at t is on the closed sphere
    exactly when q(t) = A·t² + 2B·t + C = 0, and at the ends
      q(0) = C,  slope(0) = A·0 + B = B,  q(1) = C_q = A + 2B + C,  slope(1) = A·1 + B = A + B
    ([segment_q_at_zero], [segment_slope_at_zero], [segment_q_at_one], [segment_slope_at_one]).  The segment meets
    the sphere iff some real root of q lies in (0, 1) (a double, tangent root counts; a root at an end does not).
    - [segment_root_inside_correct]: the C++'s [segment_root_inside] on the exact signs of D, C, B, C_q and A + B
      is true exactly when some t with 0 < t < 1 has A·t² + 2B·t + C = 0.  D < 0: no real root; D ≥ 0: the real
      roots are t1 and t2 of SphereRoots.v ([segment_root_cases], from [sphere_roots_product]), and
      root_side_of(k, sign q(m), sign slope(m)) = sign(t_k − m) at m = 0 and m = 1
      ([root_side_of_smaller_correct], [root_side_of_larger_correct]), so the test of root k is 0 < t_k < 1
      ([segment_smaller_inside], [segment_larger_inside]).
    - [segment_ends_opposite_meet]: C·C_q < 0 gives a root in (0, 1) (the filter's shortcut "the signs of C_p
      and C_q are certain and differ").
    - [segment_ends_inside_clear]: C < 0 and C_q < 0 give q(t) < 0 on all of [0, 1], so no root there (the
      shortcut "both negative"; convexity, q(t) = (1 − t)·q(0) + t·q(1) − A·t·(1 − t)).
    Over the reals, for all A > 0 (p ≠ q) and all B, C; nothing is assumed about doubles.

    Tied to the C++ by being the same case analysis: [segment_root_inside] below is the constexpr function on
    ints, line by line (the loop over root ∈ {−1, 1} unrolled in that order), on [root_side_of] of SphereRoots.v,
    with the signs as the ints −1, 0, 1 ([Rsign]); sphere/exact_sphere.cpp's [segment_meets_sphere] calls it on
    the exact signs of the rational terms.  The cascade's shortcuts read the filter's signs of C_p and C_q, which
    SphereFilter.v's [sphere_filter_c_sound] makes the exact signs when certain.  tests/sphere_segment_test.cpp
    checks the certified answer against the exact one on every hard kind. *)

From Coq Require Import Reals Lra Psatz ZArith Bool.
From Raykernel.Sphere Require Import SphereRoots.
Open Scope R_scope.

(** [segment_root_inside(sign_d, sign_c_p, sign_b_p, sign_c_q, sign_b_q)], line by line:
    if (sign_d < 0) return false;
    for (int root : {-1, 1})
      if (root_side_of(root, sign_c_p, sign_b_p) > 0 && root_side_of(root, sign_c_q, sign_b_q) < 0) return true;
    return false; *)
Definition segment_root_inside (sign_d sign_c_p sign_b_p sign_c_q sign_b_q : Z) : bool :=
  if Z.ltb sign_d 0 then false
  else if Z.ltb 0 (root_side_of (-1) sign_c_p sign_b_p) && Z.ltb (root_side_of (-1) sign_c_q sign_b_q) 0
  then true
  else if Z.ltb 0 (root_side_of 1 sign_c_p sign_b_p) && Z.ltb (root_side_of 1 sign_c_q sign_b_q) 0
  then true
  else false.

(** The ends of the segment: q and its slope at t = 0 and t = 1. *)
Lemma segment_q_at_zero : forall A B C, sphere_q A B C 0 = C.
Proof. intros A B C. unfold sphere_q. ring. Qed.

Lemma segment_slope_at_zero : forall A B, sphere_slope A B 0 = B.
Proof. intros A B. unfold sphere_slope. ring. Qed.

Lemma segment_q_at_one : forall A B C, sphere_q A B C 1 = A + 2 * B + C.
Proof. intros A B C. unfold sphere_q. ring. Qed.

Lemma segment_slope_at_one : forall A B, sphere_slope A B 1 = A + B.
Proof. intros A B. unfold sphere_slope. ring. Qed.

(** The int comparisons of the C++ on [Rsign]. *)
Lemma segment_sign_pos : forall x, Z.ltb 0 (Rsign x) = true <-> 0 < x.
Proof.
  intros x. destruct (Rsign_cases x) as [[L E]|[[L E]|[L E]]]; rewrite E; cbn;
    split; intro H; first [lra | discriminate | reflexivity].
Qed.

Lemma segment_sign_neg : forall x, Z.ltb (Rsign x) 0 = true <-> x < 0.
Proof.
  intros x. destruct (Rsign_cases x) as [[L E]|[[L E]|[L E]]]; rewrite E; cbn;
    split; intro H; first [lra | discriminate | reflexivity].
Qed.

(** A·q(t) = (A·t + B)² − D. *)
Lemma segment_q_complete_square : forall A B C t,
  A * (A * t * t + 2 * B * t + C) = (A * t + B) * (A * t + B) - (B * B - A * C).
Proof. intros A B C t. ring. Qed.

(** A real root makes D ≥ 0. *)
Lemma segment_root_disc : forall A B C t, 0 < A -> A * t * t + 2 * B * t + C = 0 -> 0 <= B * B - A * C.
Proof.
  intros A B C t HA Ht.
  pose proof (segment_q_complete_square A B C t) as E. rewrite Ht, Rmult_0_r in E.
  pose proof (Rle_0_sqr (A * t + B)) as S. unfold Rsqr in S. lra.
Qed.

(** Every real root is t1 or t2. *)
Lemma segment_root_cases : forall A B C t, 0 < A -> A * t * t + 2 * B * t + C = 0 ->
  t = sphere_t1 A B C \/ t = sphere_t2 A B C.
Proof.
  intros A B C t HA Ht.
  pose proof (segment_root_disc A B C t HA Ht) as HD.
  pose proof (sphere_roots_product A B C t HA HD) as P.
  unfold sphere_q in P. rewrite Ht in P.
  assert (Z : (t - sphere_t1 A B C) * (t - sphere_t2 A B C) = 0).
  { apply (Rmult_eq_reg_l A); [|lra]. rewrite Rmult_0_r, <- Rmult_assoc. exact P. }
  destruct (Rmult_integral _ _ Z) as [Z1|Z2]; [left|right]; lra.
Qed.

(** t1 and t2 are roots when D ≥ 0. *)
Lemma segment_t1_root : forall A B C, 0 < A -> 0 <= B * B - A * C ->
  let t := sphere_t1 A B C in A * t * t + 2 * B * t + C = 0.
Proof.
  intros A B C HA HD t.
  pose proof (sphere_roots_product A B C t HA HD) as P.
  unfold sphere_q in P. rewrite <- P. unfold t. ring.
Qed.

Lemma segment_t2_root : forall A B C, 0 < A -> 0 <= B * B - A * C ->
  let t := sphere_t2 A B C in A * t * t + 2 * B * t + C = 0.
Proof.
  intros A B C HA HD t.
  pose proof (sphere_roots_product A B C t HA HD) as P.
  unfold sphere_q in P. rewrite <- P. unfold t. ring.
Qed.

(** The test of root k at both ends is 0 < t_k < 1. *)
Lemma segment_smaller_inside : forall A B C, 0 < A -> 0 <= B * B - A * C ->
  (Z.ltb 0 (root_side_of (-1) (Rsign C) (Rsign B)) &&
   Z.ltb (root_side_of (-1) (Rsign (A + 2 * B + C)) (Rsign (A + B))) 0 = true)%bool <->
  0 < sphere_t1 A B C < 1.
Proof.
  intros A B C HA HD.
  pose proof (root_side_of_smaller_correct A B C 0 HA HD) as S0.
  pose proof (root_side_of_smaller_correct A B C 1 HA HD) as S1.
  rewrite segment_q_at_zero, segment_slope_at_zero in S0.
  rewrite segment_q_at_one, segment_slope_at_one in S1.
  rewrite <- S0, <- S1, andb_true_iff, segment_sign_pos, segment_sign_neg.
  split; intros [H0 H1]; split; lra.
Qed.

Lemma segment_larger_inside : forall A B C, 0 < A -> 0 <= B * B - A * C ->
  (Z.ltb 0 (root_side_of 1 (Rsign C) (Rsign B)) &&
   Z.ltb (root_side_of 1 (Rsign (A + 2 * B + C)) (Rsign (A + B))) 0 = true)%bool <->
  0 < sphere_t2 A B C < 1.
Proof.
  intros A B C HA HD.
  pose proof (root_side_of_larger_correct A B C 0 HA HD) as S0.
  pose proof (root_side_of_larger_correct A B C 1 HA HD) as S1.
  rewrite segment_q_at_zero, segment_slope_at_zero in S0.
  rewrite segment_q_at_one, segment_slope_at_one in S1.
  rewrite <- S0, <- S1, andb_true_iff, segment_sign_pos, segment_sign_neg.
  split; intros [H0 H1]; split; lra.
Qed.

(** [segment_root_inside] on the exact signs is true exactly when a root of q lies in (0, 1). *)
Theorem segment_root_inside_correct : forall A B C, 0 < A ->
  segment_root_inside (Rsign (B * B - A * C)) (Rsign C) (Rsign B) (Rsign (A + 2 * B + C)) (Rsign (A + B)) = true
  <-> exists t, 0 < t < 1 /\ A * t * t + 2 * B * t + C = 0.
Proof.
  intros A B C HA. unfold segment_root_inside.
  destruct (Z.ltb (Rsign (B * B - A * C)) 0) eqn:Ed.
  - (* D < 0: false, and no real root *)
    apply segment_sign_neg in Ed. split; [discriminate|].
    intros [t [_ Ht]]. pose proof (segment_root_disc A B C t HA Ht). lra.
  - assert (HD : 0 <= B * B - A * C).
    { destruct (Rle_or_lt 0 (B * B - A * C)) as [L|L]; [exact L|].
      apply segment_sign_neg in L. congruence. }
    pose proof (segment_smaller_inside A B C HA HD) as I1.
    pose proof (segment_larger_inside A B C HA HD) as I2.
    destruct (Z.ltb 0 (root_side_of (-1) (Rsign C) (Rsign B)) &&
              Z.ltb (root_side_of (-1) (Rsign (A + 2 * B + C)) (Rsign (A + B))) 0)%bool eqn:E1.
    + split; [intros _|reflexivity].
      exists (sphere_t1 A B C). split; [apply I1; reflexivity | apply segment_t1_root; assumption].
    + destruct (Z.ltb 0 (root_side_of 1 (Rsign C) (Rsign B)) &&
                Z.ltb (root_side_of 1 (Rsign (A + 2 * B + C)) (Rsign (A + B))) 0)%bool eqn:E2.
      * split; [intros _|reflexivity].
        exists (sphere_t2 A B C). split; [apply I2; reflexivity | apply segment_t2_root; assumption].
      * split; [discriminate|].
        intros [t [Hin Ht]].
        destruct (segment_root_cases A B C t HA Ht) as [->| ->].
        -- apply I1 in Hin. congruence.
        -- apply I2 in Hin. congruence.
Qed.

Lemma segment_mult_nonneg_nonpos : forall u v, 0 <= u -> v <= 0 -> u * v <= 0.
Proof. intros u v Hu Hv. nra. Qed.

(** A·(m − x)·(m − y) < 0 with A > 0 and x ≤ y puts m strictly between x and y. *)
Lemma segment_product_negative_between : forall A x y m, 0 < A -> x <= y -> A * (m - x) * (m - y) < 0 -> x < m < y.
Proof.
  intros A x y m HA Hxy Hp.
  destruct (Rlt_or_le x m) as [Lx|Lx]; destruct (Rlt_or_le m y) as [Ly|Ly]; try (split; assumption); exfalso.
  - assert (0 <= A * (m - x)) by (apply Rmult_le_pos; lra).
    assert (0 <= A * (m - x) * (m - y)) by (apply Rmult_le_pos; lra). lra.
  - assert (A * (m - x) <= 0) by (apply segment_mult_nonneg_nonpos; lra).
    assert (0 <= A * (m - x) * (m - y)).
    { replace (A * (m - x) * (m - y)) with ((- (A * (m - x))) * (- (m - y))) by ring.
      apply Rmult_le_pos; lra. }
    lra.
  - replace (m - x) with 0 in Hp by lra. rewrite Rmult_0_r, Rmult_0_l in Hp. lra.
Qed.

(** The filter's first shortcut: C_p and C_q of opposite signs give a root in (0, 1). *)
Theorem segment_ends_opposite_meet : forall A B C, 0 < A -> C * (A + 2 * B + C) < 0 ->
  exists t, 0 < t < 1 /\ A * t * t + 2 * B * t + C = 0.
Proof.
  intros A B C HA Hs.
  assert (HD : 0 <= B * B - A * C).
  { destruct (Rlt_or_le C 0) as [Hc|Hc].
    - nra.
    - assert (Hq : A + 2 * B + C < 0) by nra.
      pose proof (segment_q_complete_square A B C 1) as E.
      replace (A * 1 * 1 + 2 * B * 1 + C) with (A + 2 * B + C) in E by ring.
      assert (Neg : A * (A + 2 * B + C) < 0) by nra.
      pose proof (Rle_0_sqr (A * 1 + B)) as S. unfold Rsqr in S. lra. }
  pose proof (sphere_roots_order A B C HA HD) as Ho.
  pose proof (sphere_roots_product A B C 0 HA HD) as P0.
  pose proof (sphere_roots_product A B C 1 HA HD) as P1.
  rewrite segment_q_at_zero in P0. rewrite segment_q_at_one in P1.
  set (x := sphere_t1 A B C) in *. set (y := sphere_t2 A B C) in *.
  destruct (Rlt_or_le C 0) as [Hc|Hc].
  - (* q(0) < 0 < q(1): t1 < 0 < t2 < 1 *)
    assert (Hq : 0 < A + 2 * B + C) by nra.
    assert (Hxy : x < 0 < y) by (apply (segment_product_negative_between A); lra).
    assert (Hy1 : y < 1).
    { destruct (Rlt_or_le y 1) as [L|L]; [exact L|exfalso].
      assert (0 < A * (1 - x)) by (apply Rmult_lt_0_compat; lra).
      assert (A * (1 - x) * (1 - y) <= 0) by (apply segment_mult_nonneg_nonpos; lra). lra. }
    exists y. split; [lra|]. apply segment_t2_root; assumption.
  - (* q(0) > 0 > q(1): 0 < t1 < 1 < t2 *)
    assert (Hc' : 0 < C) by (destruct Hc as [Hc|Hc]; [exact Hc|rewrite <- Hc, Rmult_0_l in Hs; lra]).
    assert (Hq : A + 2 * B + C < 0) by nra.
    assert (Hxy : x < 1 < y) by (apply (segment_product_negative_between A); lra).
    assert (Hx0 : 0 < x).
    { destruct (Rlt_or_le 0 x) as [L|L]; [exact L|exfalso].
      assert (0 <= A * (0 - x)) by (apply Rmult_le_pos; lra).
      assert (A * (0 - x) * (0 - y) <= 0) by (apply segment_mult_nonneg_nonpos; lra). lra. }
    exists x. split; [lra|]. apply segment_t1_root; assumption.
Qed.

(** The filter's second shortcut: C_p < 0 and C_q < 0 make q negative on all of [0, 1]. *)
Theorem segment_ends_inside_clear : forall A B C, 0 < A -> C < 0 -> A + 2 * B + C < 0 ->
  forall t, 0 <= t <= 1 -> A * t * t + 2 * B * t + C < 0.
Proof.
  intros A B C HA Hc Hq t [H0 H1].
  assert (E : A * t * t + 2 * B * t + C = (1 - t) * C + t * (A + 2 * B + C) - A * t * (1 - t)) by ring.
  rewrite E.
  assert (Ht : 0 <= A * t * (1 - t)) by (apply Rmult_le_pos; [apply Rmult_le_pos|]; lra).
  destruct (Rlt_or_le 0 t) as [Lt|Lt]; nra.
Qed.
