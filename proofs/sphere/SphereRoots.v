(** * The side of a ray–sphere root against a rounding boundary (kernel/src/sphere/ray_sphere_formula.hpp,
    [root_side_of]).

    The ray–sphere query of docs/contract.md §10 has, with f = o − c, A = d·d, B = d·f, C = f·f − r² and
    D = B² − A·C, the roots t1 = (−B − √D)/A ≤ t2 = (−B + √D)/A of q(t) = A·t² + 2B·t + C (t1 = t2 = −B/A when
    D = 0).  To round a root the C++ compares it with a rounding boundary m (a midpoint of two doubles), but it
    never computes √D: it reads the exact signs of q(m) and of the slope A·m + B, and [root_side_of] turns them
    into sign(t_k − m), for the smaller root (root = −1) or the larger (root = +1):
    - [sphere_roots_product]: A·(m − t1)·(m − t2) = q(m), so q(m) < 0 exactly when t1 < m < t2;
    - [sphere_roots_slope]: A·(m − U) = A·m + B with U = (t1 + t2)/2, so the slope's sign is that of m − U;
      [sphere_roots_order]: t1 ≤ t2; [sphere_roots_tangent]: t1 = t2 = −B/A when D = 0;
    - [root_side_of_smaller_correct], [root_side_of_larger_correct]: for every real m,
      sign(t1 − m) = root_side_of(−1, sign q(m), sign(A·m + B)) and
      sign(t2 − m) = root_side_of(+1, sign q(m), sign(A·m + B)).
    Over the reals, for all A > 0 and D ≥ 0 (the C++ asks only when the ray meets the sphere, D ≥ 0, and A > 0
    for a nonzero direction); m is any real, not only a midpoint, and nothing is assumed about doubles.

    Tied to the C++ by being the same case analysis: [root_side_of] below is the constexpr function on ints,
    branch by branch in the C++'s order (sign_q < 0, sign_q > 0, then root < 0), with the signs as the ints
    −1, 0, 1 ([Rsign]); tests/sphere_test.cpp checks the C++ exhaustively against the exact roots.  Its
    callers: sphere/ray_sphere_stages.hpp's [sphere_root_side] (on the checked signs of the expansions of q(m)
    and the slope) and sphere/exact_sphere.cpp's [root_side_of_midpoint] (on the exact rationals). *)

From Coq Require Import Reals Lra Psatz ZArith.
Open Scope R_scope.

(** The exact sign of a real as the C++ int −1, 0, 1. *)
Definition Rsign (x : R) : Z :=
  if Rlt_dec x 0 then (-1)%Z else if Req_EM_T x 0 then 0%Z else 1%Z.

(** [root_side_of(root, sign_q, sign_slope)], line by line:
    if (sign_q < 0) return root < 0 ? -1 : 1;
    if (sign_q > 0) return sign_slope < 0 ? 1 : -1;
    if (root < 0) return sign_slope <= 0 ? 0 : -1;
    return sign_slope >= 0 ? 0 : 1; *)
Definition root_side_of (root sign_q sign_slope : Z) : Z :=
  if Z.ltb sign_q 0 then (if Z.ltb root 0 then (-1)%Z else 1%Z)
  else if Z.ltb 0 sign_q then (if Z.ltb sign_slope 0 then 1%Z else (-1)%Z)
  else if Z.ltb root 0 then (if Z.leb sign_slope 0 then 0%Z else (-1)%Z)
  else (if Z.leb 0 sign_slope then 0%Z else 1%Z).

(** The quantities of the query, over the reals. *)
Definition sphere_disc (A B C : R) : R := B * B - A * C.
Definition sphere_t1 (A B C : R) : R := (- B - sqrt (sphere_disc A B C)) / A.
Definition sphere_t2 (A B C : R) : R := (- B + sqrt (sphere_disc A B C)) / A.
Definition sphere_q (A B C m : R) : R := A * m * m + 2 * B * m + C.
Definition sphere_slope (A B m : R) : R := A * m + B.

Lemma Rsign_cases : forall x,
  (x < 0 /\ Rsign x = (-1)%Z) \/ (x = 0 /\ Rsign x = 0%Z) \/ (0 < x /\ Rsign x = 1%Z).
Proof.
  intros x. unfold Rsign. destruct (Rlt_dec x 0) as [L|NL].
  - left. split; [exact L|reflexivity].
  - destruct (Req_EM_T x 0) as [E|NE].
    + right; left. split; [exact E|reflexivity].
    + right; right. split; [lra|reflexivity].
Qed.

Lemma Rsign_div_pos : forall x a, 0 < a -> Rsign (x / a) = Rsign x.
Proof.
  intros x a Ha.
  assert (Pi : 0 < / a) by (apply Rinv_0_lt_compat; exact Ha).
  destruct (Rsign_cases x) as [[L E]|[[L E]|[L E]]]; rewrite E;
    destruct (Rsign_cases (x / a)) as [[L' E']|[[L' E']|[L' E']]]; rewrite E'; try reflexivity;
    exfalso; unfold Rdiv in L'; nra.
Qed.

(** With y = A·m + B and s = √D: t1 − m = (−y − s)/A, t2 − m = (s − y)/A, q(m) = (y² − s²)/A. *)
Lemma sphere_shifted : forall A B C m, 0 < A -> 0 <= B * B - A * C ->
  sphere_t1 A B C - m = (- sphere_slope A B m - sqrt (sphere_disc A B C)) / A /\
  sphere_t2 A B C - m = (sqrt (sphere_disc A B C) - sphere_slope A B m) / A /\
  sphere_q A B C m =
    (sphere_slope A B m * sphere_slope A B m - sqrt (sphere_disc A B C) * sqrt (sphere_disc A B C)) / A.
Proof.
  intros A B C m HA HD.
  assert (NZ : A <> 0) by lra.
  rewrite (sqrt_sqrt (sphere_disc A B C) HD).
  unfold sphere_t1, sphere_t2, sphere_q, sphere_slope, sphere_disc.
  repeat split; field; exact NZ.
Qed.

(** q(m) = A·(m − t1)·(m − t2). *)
Theorem sphere_roots_product : forall A B C m, 0 < A -> 0 <= B * B - A * C ->
  A * (m - sphere_t1 A B C) * (m - sphere_t2 A B C) = sphere_q A B C m.
Proof.
  intros A B C m HA HD.
  destruct (sphere_shifted A B C m HA HD) as [E1 [E2 Eq]].
  replace (m - sphere_t1 A B C) with (- (sphere_t1 A B C - m)) by ring.
  replace (m - sphere_t2 A B C) with (- (sphere_t2 A B C - m)) by ring.
  rewrite E1, E2, Eq. field. lra.
Qed.

(** A·m + B = A·(m − U), U = (t1 + t2)/2 = −B/A. *)
Theorem sphere_roots_slope : forall A B C m, 0 < A -> 0 <= B * B - A * C ->
  A * (m - (sphere_t1 A B C + sphere_t2 A B C) / 2) = sphere_slope A B m.
Proof.
  intros A B C m HA HD.
  unfold sphere_t1, sphere_t2, sphere_slope. field. lra.
Qed.

Theorem sphere_roots_order : forall A B C, 0 < A -> 0 <= B * B - A * C ->
  sphere_t1 A B C <= sphere_t2 A B C.
Proof.
  intros A B C HA HD.
  pose proof (sqrt_pos (sphere_disc A B C)) as Hs.
  unfold sphere_t1, sphere_t2, Rdiv.
  apply Rmult_le_compat_r; [left; apply Rinv_0_lt_compat; exact HA | lra].
Qed.

Theorem sphere_roots_tangent : forall A B C, 0 < A -> sphere_disc A B C = 0 ->
  sphere_t1 A B C = - B / A /\ sphere_t2 A B C = - B / A.
Proof.
  intros A B C HA HD.
  unfold sphere_t1, sphere_t2. rewrite HD, sqrt_0.
  split; field; lra.
Qed.

(** The case analysis over y = A·m + B and s = √D ≥ 0. *)
Ltac sign_cases x :=
  let H := fresh "H" in let E := fresh "E" in
  destruct (Rsign_cases x) as [[H E]|[[H E]|[H E]]]; rewrite E.

Lemma root_side_smaller_yz : forall y s, 0 <= s ->
  Rsign (- y - s) = root_side_of (-1) (Rsign (y * y - s * s)) (Rsign y).
Proof.
  intros y s Hs.
  sign_cases (- y - s); sign_cases (y * y - s * s); sign_cases y; cbn;
    first [reflexivity | exfalso; nra].
Qed.

Lemma root_side_larger_yz : forall y s, 0 <= s ->
  Rsign (s - y) = root_side_of 1 (Rsign (y * y - s * s)) (Rsign y).
Proof.
  intros y s Hs.
  sign_cases (s - y); sign_cases (y * y - s * s); sign_cases y; cbn;
    first [reflexivity | exfalso; nra].
Qed.

(** sign(t1 − m) = root_side_of(−1, sign q(m), sign(A·m + B)), for every real m. *)
Theorem root_side_of_smaller_correct : forall A B C m, 0 < A -> 0 <= B * B - A * C ->
  Rsign (sphere_t1 A B C - m) = root_side_of (-1) (Rsign (sphere_q A B C m)) (Rsign (sphere_slope A B m)).
Proof.
  intros A B C m HA HD.
  destruct (sphere_shifted A B C m HA HD) as [E1 [_ Eq]].
  rewrite E1, Eq, !Rsign_div_pos by exact HA.
  apply root_side_smaller_yz, sqrt_pos.
Qed.

(** sign(t2 − m) = root_side_of(+1, sign q(m), sign(A·m + B)), for every real m. *)
Theorem root_side_of_larger_correct : forall A B C m, 0 < A -> 0 <= B * B - A * C ->
  Rsign (sphere_t2 A B C - m) = root_side_of 1 (Rsign (sphere_q A B C m)) (Rsign (sphere_slope A B m)).
Proof.
  intros A B C m HA HD.
  destruct (sphere_shifted A B C m HA HD) as [_ [E2 Eq]].
  rewrite E2, Eq, !Rsign_div_pos by exact HA.
  apply root_side_larger_yz, sqrt_pos.
Qed.
