(** * Spawning from a sphere: what an accepted origin guarantees (kernel/src/sphere/sphere_spawn.cpp; the rule:
    docs/contract.md, "Decided here": spawning from a sphere; raykernel/spawn.hpp).

    A new ray starts at an origin x (doubles) along w ≠ 0. With f = x − c, its quadratic is
    q(t) = A·t² + 2B·t + C, A = w·w > 0, B = w·f, C = f·f − r² (ray_sphere_formula.hpp's, for the ray x, w), and
    its hits on the sphere are the roots t ≥ 0. spawn accepts an origin when σ(x) = sign(C) is the side s that w
    leaves towards and, leaving outward, also B ≥ 0 ([sphere_spawn.cpp]'s `accepted`, checked there in exact
    rationals). Over the reals:
    - [spawn_outward_never_hits]: C > 0 and B ≥ 0 give q(t) > 0 for every t ≥ 0: leaving outward, the ray never
      meets the sphere;
    - [spawn_inward_one_exit]: C < 0 gives exactly one root t ≥ 0, and it is > 0: leaving inward, the ray meets
      the sphere once, where it leaves it, and never at its origin;
    - [spawn_axis_leaving_grows], [spawn_axis_side]: the steps' two facts (why the C++ finds k without
      stepping): moving coordinate i by h changes B by h·w_i — so along an axis with w_i·N_i > 0 in direction
      δ = sign(N_i), B grows —, and C along axis i is (x_i − c_i)² − V with V = r² − Σ_{j≠i} f_j², so C ≤ 0
      exactly on [c_i − √V, c_i + √V] and C < 0 exactly strictly inside it.
    Tied to the C++ by being its acceptance test and its threshold algebra; tests/sphere_spawn_test.cpp checks the
    accepted origins, the minimality of k and these guarantees (by intersect_exact from the origin). *)

From Coq Require Import Reals Lra.
Open Scope R_scope.

Definition spawn_q (a b c t : R) : R := a * t * t + 2 * b * t + c.

(** Leaving outward: no root at t ≥ 0. *)
Theorem spawn_outward_never_hits : forall a b c, 0 < a -> 0 < c -> 0 <= b ->
  forall t, 0 <= t -> 0 < spawn_q a b c t.
Proof.
  intros a b c Ha Hc Hb t Ht. unfold spawn_q.
  assert (0 <= a * t * t) by (apply Rmult_le_pos; [apply Rmult_le_pos|]; lra).
  assert (0 <= 2 * b * t) by (apply Rmult_le_pos; lra).
  lra.
Qed.

(** Leaving inward: exactly one root t ≥ 0, and it is positive. *)
Theorem spawn_inward_one_exit : forall a b c, 0 < a -> c < 0 ->
  exists t, 0 < t /\ spawn_q a b c t = 0 /\ (forall t', 0 <= t' -> spawn_q a b c t' = 0 -> t' = t).
Proof.
  intros a b c Ha Hc.
  assert (Hdd : b * b < b * b - a * c) by nra.
  assert (Hd0 : 0 <= b * b - a * c) by nra.
  destruct (ex_intro (fun s => 0 <= s /\ s * s = b * b - a * c) (sqrt (b * b - a * c))
              (conj (sqrt_pos _) (sqrt_sqrt _ Hd0))) as [s [Hs0 Hs2]].
  assert (Hbs : b < s).
  { destruct (Rle_or_lt s b) as [L|L]; [exfalso|exact L].
    assert (s * s <= b * b) by (apply Rmult_le_compat; lra). lra. }
  assert (Hqt : spawn_q a b c ((- b + s) / a) = 0).
  { assert (E : spawn_q a b c ((- b + s) / a) = (s * s - (b * b - a * c)) / a) by (unfold spawn_q; field; lra).
    rewrite E, Hs2. unfold Rdiv. ring. }
  assert (Ht : 0 < (- b + s) / a) by (apply Rdiv_lt_0_compat; lra).
  exists ((- b + s) / a). split; [exact Ht|]. split; [exact Hqt|].
  intros t' Ht' Hq. generalize dependent ((- b + s) / a). intros t Hqt Ht.
  destruct (Req_dec t' t) as [E|E]; [exact E|exfalso].
  unfold spawn_q in Hq, Hqt.
  (* q(t') − q(t) = (t' − t)·(a(t' + t) + 2b) = 0, so a(t' + t) = −2b; then a·t'·t = c < 0, but t', t ≥ 0. *)
  assert (Hsum : a * (t' + t) + 2 * b = 0).
  { assert (H0 : (t' - t) * (a * (t' + t) + 2 * b) = 0) by nra.
    apply Rmult_integral in H0. destruct H0 as [H0|H0]; [exfalso; apply E; lra | exact H0]. }
  assert (Hprod : a * t' * t = c) by nra.
  assert (0 <= a * t' * t) by (apply Rmult_le_pos; [apply Rmult_le_pos|]; lra).
  lra.
Qed.

(** Moving coordinate i of the origin by h: B = w·(x − c) changes by h·w_i (written for i = x; the others are the
    same with the coordinates renamed). With δ = sign(N_i) and w_i·N_i > 0, each step h (of sign δ) raises B. *)
Theorem spawn_axis_leaving_grows : forall w0 w1 w2 f0 f1 f2 h,
  w0 * (f0 + h) + w1 * f1 + w2 * f2 = (w0 * f0 + w1 * f1 + w2 * f2) + h * w0.
Proof. intros. ring. Qed.

Theorem spawn_axis_step_sign : forall w0 n0 h, 0 < w0 * n0 -> 0 < h * n0 -> 0 < h * w0.
Proof. intros w0 n0 h H1 H2. nra. Qed.

(** C along axis i: (x_i − c_i)² − V, V = r² − Σ_{j≠i} f_j²; C < 0 exactly when |x_i − c_i| < √V, C ≤ 0 exactly
    when |x_i − c_i| ≤ √V (V ≥ 0). *)
Theorem spawn_axis_side : forall x ci f1 f2 r,
  let v := r * r - (f1 * f1 + f2 * f2) in
  ((x - ci) * (x - ci) + f1 * f1 + f2 * f2 - r * r = (x - ci) * (x - ci) - v) /\
  (0 <= v -> ((x - ci) * (x - ci) - v < 0 <-> Rabs (x - ci) < sqrt v)).
Proof.
  intros x ci f1 f2 r v. split; [unfold v; ring|].
  intros Hv. pose proof (sqrt_pos v) as Hs. pose proof (sqrt_sqrt v Hv) as Hss.
  pose proof (Rabs_pos (x - ci)) as Ha.
  assert (Hsq : Rabs (x - ci) * Rabs (x - ci) = (x - ci) * (x - ci)) by (rewrite <- Rabs_mult; apply Rabs_right; apply Rle_ge; apply Rle_0_sqr).
  split; intros H.
  - destruct (Rlt_or_le (Rabs (x - ci)) (sqrt v)) as [L|L]; [exact L|].
    assert (sqrt v * sqrt v <= Rabs (x - ci) * Rabs (x - ci)) by (apply Rmult_le_compat; lra). lra.
  - assert (Rabs (x - ci) * Rabs (x - ci) < sqrt v * sqrt v) by nra. lra.
Qed.
