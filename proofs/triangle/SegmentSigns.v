(** * The open segment from p to q against a triangle a, b, c: the signs it is decided from
    (kernel/src/occlusion/segment_triangle.hpp, [segment_meets_triangle]; docs/contract.md §8).

    The segment is the line p + t·d, d = q − p, 0 < t < 1.  With N = (b − a) × (c − a) and the side
    S(x) = (x − a)·N ([side]), docs/contract.md §6's values of that line, as
    kernel/src/triangle/ray_triangle_formula.hpp writes them for the origin p and the direction d
    ([num_value], [edge_value], [den_value] of TriangleFilter.v), are, exactly and over the reals:
    - [segment_num_is_side]: num = (a − p)·((b − p) × (c − p)) = −S(p);
    - [segment_den_is_difference]: den = d·N = πa + πb + πc = S(q) − S(p);
    - [segment_t_in_open_unit]: for den ≠ 0, t = num/den lies in (0, 1) exactly when S(p)·S(q) < 0;
      [segment_crossing_signs]: S(p)·S(q) < 0 gives den ≠ 0 and num, den both of S(q)'s sign;
      [segment_plane_test_correct]: the C++'s test on the signs (sp ≠ 0 and sq = −sp) holds exactly when
      den ≠ 0 and 0 < num/den < 1 (so den = 0 — parallel, coplanar, degenerate — never passes it);
    - [segment_side_is_orient3d]: S(x) = det(x − a, b − a, c − a) = orient3d(a, x, b, c);
    - [segment_pi_is_orient3d]: π(u, v) = d·((u − p) × (v − p)) = det(q − p, u − p, v − p) = orient3d(p, q, u, v).
    Here [orient3d o a b c] = det(a − o, b − o, c − o) is what kernel/src/orient/orient_predicates.hpp's
    [orient3d_sign(o, a, b, c)] takes the sign of: [orient3d_is_exact] shows it is OrientFilter.v's
    [orient3d_exact] (the filter's value in Shewchuk's order, [orient3d_filter_sound]) and the model's
    [num_value o a b c] (the determinant of [num_expansion(Ray{o, 0}, Triangle{a, b, c})], its stage 2, and of
    [exact::det3_sign(o, a, b, c)], its stage 3).  So the calls [orient3d_sign(t.a, p, t.b, t.c)],
    [orient3d_sign(t.a, q, t.b, t.c)] are the signs of S(p), S(q), and [orient3d_sign(p, q, u, v)] for the
    edges (b, c), (c, a), (a, b) the signs of πa, πb, πc, with the argument orders of the C++ and the signs
    its header comment claims.  No hypothesis on the inputs; nothing about doubles. *)

From Coq Require Import Reals Lra Psatz ZArith.
From Flocq Require Import Core.
From Raykernel Require Import PlaneClassification TriangleFilter.
From Raykernel Require OrientFilter.
Open Scope R_scope.

(** det(u, v, w) = u·(v × w). *)
Definition det3_vec (u v w : vec3) : R := dot u (cross v w).

(** The value [orient3d_sign(o, a, b, c)] takes the sign of: det(a − o, b − o, c − o). *)
Definition orient3d (o a b c : vec3) : R := det3_vec (sub a o) (sub b o) (sub c o).

(** N = (b − a) × (c − a) and S(x) = (x − a)·N. *)
Definition tri_normal (a b c : vec3) : vec3 := cross (sub b a) (sub c a).
Definition side (a b c x : vec3) : R := dot (sub x a) (tri_normal a b c).

(** orient3d is the filter's exact value (OrientFilter.v, Shewchuk's order) and the model's num for a ray
    from o (TriangleFilter.v: the determinant of [num_expansion] and [exact::det3_sign]). *)
Lemma orient3d_is_exact : forall o a b c,
  orient3d o a b c =
    OrientFilter.orient3d_exact (vx o) (vy o) (vz o) (vx a) (vy a) (vz a) (vx b) (vy b) (vz b)
                                (vx c) (vy c) (vz c) /\
  orient3d o a b c = num_value o a b c.
Proof.
  intros [o0 o1 o2] [a0 a1 a2] [b0 b1 b2] [c0 c1 c2].
  unfold orient3d, det3_vec, OrientFilter.orient3d_exact, num_value, dot, cross, sub. cbn [vx vy vz].
  split; ring.
Qed.

(** ** 1. num = −S(p) *)
Theorem segment_num_is_side : forall p a b c, num_value p a b c = - side a b c p.
Proof.
  intros [p0 p1 p2] [a0 a1 a2] [b0 b1 b2] [c0 c1 c2].
  unfold num_value, side, tri_normal, dot, cross, sub. cbn [vx vy vz]. ring.
Qed.

(** ** 2. den = d·N = πa + πb + πc = S(q) − S(p) *)
Theorem segment_den_is_difference : forall p q a b c,
  dot (sub q p) (tri_normal a b c) = side a b c q - side a b c p /\
  den_value p (sub q p) a b c = side a b c q - side a b c p.
Proof.
  intros [p0 p1 p2] [q0 q1 q2] [a0 a1 a2] [b0 b1 b2] [c0 c1 c2].
  unfold den_value, edge_value, side, tri_normal, dot, cross, sub. cbn [vx vy vz].
  split; ring.
Qed.

(** ** 3. t = num/den in (0, 1) exactly when S(p), S(q) have opposite signs *)

(** The same over two reals: with num = −Sp and den = Sq − Sp ≠ 0. *)
Lemma open_unit_iff : forall sp sq, sq - sp <> 0 -> (0 < - sp / (sq - sp) < 1 <-> sp * sq < 0).
Proof.
  intros sp sq D.
  assert (T : - sp = (- sp / (sq - sp)) * (sq - sp)) by (field; exact D).
  set (t := - sp / (sq - sp)) in *.
  split.
  - intros [T0 T1].
    destruct (Rlt_or_le 0 (sq - sp)) as [P | N].
    + (* den > 0: num = t·den ∈ (0, den), so Sp < 0 < Sq *)
      assert (0 < - sp) by (rewrite T; apply Rmult_lt_0_compat; lra).
      assert (- sp < sq - sp) by (rewrite T; rewrite <- (Rmult_1_l (sq - sp)) at 2;
                                  apply Rmult_lt_compat_r; lra).
      nra.
    + assert (Nd : sq - sp < 0) by lra.
      assert (- sp < 0) by (rewrite T; nra).
      assert (sq - sp < - sp) by (rewrite T; nra).
      nra.
  - intros M.
    destruct (Rlt_or_le sp 0) as [Sp | Sp].
    + assert (Sq : 0 < sq) by nra.
      split; unfold t.
      * apply Rdiv_lt_0_compat; lra.
      * apply (Rmult_lt_reg_r (sq - sp)); [lra|]. unfold Rdiv. rewrite Rmult_assoc, Rinv_l by exact D. lra.
    + assert (Sp' : 0 < sp) by nra.
      assert (Sq : sq < 0) by nra.
      assert (E : t = sp / (sp - sq)) by (unfold t; field; split; lra).
      rewrite E. split.
      * apply Rdiv_lt_0_compat; lra.
      * apply (Rmult_lt_reg_r (sp - sq)); [lra|]. unfold Rdiv. rewrite Rmult_assoc, Rinv_l by lra. lra.
Qed.

Theorem segment_t_in_open_unit : forall p q a b c,
  dot (sub q p) (tri_normal a b c) <> 0 ->
  (0 < num_value p a b c / dot (sub q p) (tri_normal a b c) < 1 <-> side a b c p * side a b c q < 0).
Proof.
  intros p q a b c D. destruct (segment_den_is_difference p q a b c) as [E _].
  rewrite segment_num_is_side, E in *. now apply open_unit_iff.
Qed.

(** [Rcompare]'s sign of a real ([sign_of], the C++'s int −1, 0, +1) is that of a real of the same sign. *)
Lemma sign_of_same : forall x y, 0 < x * y -> sign_of x = sign_of y.
Proof.
  intros x y H. unfold sign_of.
  destruct (Rcompare_spec x 0); destruct (Rcompare_spec y 0); try reflexivity; exfalso; subst; nra.
Qed.

Theorem segment_crossing_signs : forall p q a b c,
  side a b c p * side a b c q < 0 ->
  dot (sub q p) (tri_normal a b c) <> 0 /\
  num_value p a b c * side a b c q > 0 /\
  dot (sub q p) (tri_normal a b c) * side a b c q > 0 /\
  sign_of (num_value p a b c) = sign_of (side a b c q) /\
  sign_of (dot (sub q p) (tri_normal a b c)) = sign_of (side a b c q).
Proof.
  intros p q a b c M. destruct (segment_den_is_difference p q a b c) as [E _].
  rewrite segment_num_is_side, E.
  set (sp := side a b c p) in *. set (sq := side a b c q) in *.
  assert (N : - sp * sq > 0) by lra.
  assert (Dq : (sq - sp) * sq > 0) by nra.
  split; [| split; [exact N | split; [exact Dq | split]]].
  - intros Z. rewrite Z in Dq. lra.
  - apply sign_of_same. lra.
  - apply sign_of_same. lra.
Qed.

(** The C++'s test, [sp == 0 → false; sq != −sp → false] on the signs sp = sign S(p), sq = sign S(q): it passes
    exactly when den ≠ 0 and 0 < num/den < 1 (den = 0 never passes). *)
Theorem segment_plane_test_correct : forall p q a b c,
  (sign_of (side a b c p) <> 0%Z /\ sign_of (side a b c q) = (- sign_of (side a b c p))%Z) <->
  (dot (sub q p) (tri_normal a b c) <> 0 /\
   0 < num_value p a b c / dot (sub q p) (tri_normal a b c) < 1).
Proof.
  intros p q a b c.
  assert (Test : (sign_of (side a b c p) <> 0%Z /\ sign_of (side a b c q) = (- sign_of (side a b c p))%Z) <->
                 side a b c p * side a b c q < 0).
  { set (sp := side a b c p). set (sq := side a b c q). unfold sign_of.
    destruct (Rcompare_spec sp 0) as [P | P | P]; destruct (Rcompare_spec sq 0) as [Q | Q | Q]; cbn.
    all: split; [intros [H1 H2] | intros M].
    all: try discriminate; try (exfalso; apply H1; reflexivity); try nra.
    all: split; [discriminate | reflexivity]. }
  rewrite Test. split.
  - intros M. destruct (segment_crossing_signs p q a b c M) as [D _].
    split; [exact D|]. now apply segment_t_in_open_unit.
  - intros [D T]. now apply (segment_t_in_open_unit p q a b c D).
Qed.

(** ** 4. S(x) = det(x − a, b − a, c − a) = orient3d(a, x, b, c): [orient3d_sign(t.a, x, t.b, t.c)] *)
Theorem segment_side_is_orient3d : forall a b c x,
  side a b c x = det3_vec (sub x a) (sub b a) (sub c a) /\
  side a b c x = orient3d a x b c.
Proof. intros. unfold side, tri_normal, orient3d, det3_vec. split; reflexivity. Qed.

(** ** 5. π(u, v) = det(q − p, u − p, v − p) = orient3d(p, q, u, v): [orient3d_sign(p, q, u, v)] *)
Theorem segment_pi_is_orient3d : forall p q u v,
  edge_value p (sub q p) u v = det3_vec (sub q p) (sub u p) (sub v p) /\
  edge_value p (sub q p) u v = orient3d p q u v.
Proof. intros. unfold edge_value, orient3d, det3_vec. split; reflexivity. Qed.
