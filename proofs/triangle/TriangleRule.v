(** * The decisions of docs/contract.md §6 over the reals (kernel/src/triangle/ray_triangle_formula.hpp:
    [triangle_location], [owned_sign], [crossing_relation], [classify_triangle]).

    - [den_as_edge_values], [den_normal]: den = πa + πb + πc = d·((b − a) × (c − a));
    - [edge_value_antisymmetric], [tie_break_antisymmetric], [owned_sign_antisymmetric]: the owned rule's sign of
      an edge p → q is minus that of q → p, so two triangles sharing an edge with opposite orientations (a
      consistently oriented mesh) give it opposite signs;
    - [owned_sign_nonzero]: when den ≠ 0, every edge's owned sign is ±1 (the tie-break vector d × (q − p) of
      an edge of the triangle vanishes only when den = 0);
    - [edge_value_shift]: moving the origin by δ changes π(p, q) by δ·(d × (q − p)) exactly — for δ = (ε, ε², ε³),
      ε → 0+, the sign of π is the owned sign (the rule's meaning);
    - [triangle_location_correct]: the location function returns each location exactly under the condition
      §6 states for it. *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core.
From Raykernel Require Import Model PlaneClassification TriangleFilter.
Open Scope R_scope.

Definition tie_break (d p q : vec3) : vec3 := cross d (sub q p).

(** [owned_sign(pi_sign, tx, ty, tz)]: the sign of π when nonzero, else the first nonzero component's sign. *)
Definition owned_sign (pi_sign tx ty tz : Z) : Z :=
  if negb (Z.eqb pi_sign 0) then pi_sign
  else if negb (Z.eqb tx 0) then tx else if negb (Z.eqb ty 0) then ty else tz.

Definition owned_sign_of (o d p q : vec3) : Z :=
  let t := tie_break d p q in owned_sign (sign_of (edge_value o d p q)) (sign_of (vx t)) (sign_of (vy t)) (sign_of (vz t)).

Lemma den_as_edge_values : forall o d a b c,
  den_value o d a b c = dot d (cross (sub b a) (sub c a)).
Proof. intros. unfold den_value, edge_value, dot, cross, sub. simpl. ring. Qed.

(** The same den from the other two edges' points of view (a cyclic relabelling). *)
Lemma den_cyclic : forall d a b c,
  dot d (cross (sub b a) (sub c a)) = dot d (cross (sub c b) (sub a b)) /\
  dot d (cross (sub b a) (sub c a)) = dot d (cross (sub a c) (sub b c)).
Proof. intros. unfold dot, cross, sub. simpl. split; ring. Qed.

Lemma edge_value_antisymmetric : forall o d p q, edge_value o d q p = - edge_value o d p q.
Proof. intros. unfold edge_value, dot, cross, sub. simpl. ring. Qed.

Lemma tie_break_antisymmetric : forall d p q,
  vx (tie_break d q p) = - vx (tie_break d p q) /\ vy (tie_break d q p) = - vy (tie_break d p q) /\
  vz (tie_break d q p) = - vz (tie_break d p q).
Proof. intros. unfold tie_break, cross, sub. simpl. repeat split; ring. Qed.

Lemma sign_of_opp : forall x, sign_of (- x) = (- sign_of x)%Z.
Proof.
  intros x. unfold sign_of. destruct (Rcompare_spec x 0) as [L|E|G].
  - rewrite Rcompare_Gt by lra. reflexivity.
  - subst. rewrite Ropp_0, Rcompare_Eq by reflexivity. reflexivity.
  - rewrite Rcompare_Lt by lra. reflexivity.
Qed.

Lemma sign_of_range : forall x, sign_of x = (-1)%Z \/ sign_of x = 0%Z \/ sign_of x = 1%Z.
Proof. intros. unfold sign_of. destruct (Rcompare x 0); auto. Qed.

Lemma sign_of_zero_iff : forall x, sign_of x = 0%Z <-> x = 0.
Proof.
  intros x. unfold sign_of. destruct (Rcompare_spec x 0) as [L|E|G]; split; intros H; try reflexivity;
    try discriminate; lra.
Qed.

Definition sign3 (s : Z) : Prop := s = (-1)%Z \/ s = 0%Z \/ s = 1%Z.

Lemma sign3_of : forall x, sign3 (sign_of x).
Proof. intros. apply sign_of_range. Qed.

Lemma owned_sign_opp : forall s x y z, sign3 s -> sign3 x -> sign3 y -> sign3 z ->
  owned_sign (- s) (- x) (- y) (- z) = (- owned_sign s x y z)%Z.
Proof.
  intros s x y z Hs Hx Hy Hz.
  destruct Hs as [-> | [-> | ->]]; destruct Hx as [-> | [-> | ->]]; destruct Hy as [-> | [-> | ->]];
    destruct Hz as [-> | [-> | ->]]; reflexivity.
Qed.

Theorem owned_sign_antisymmetric : forall o d p q, owned_sign_of o d q p = (- owned_sign_of o d p q)%Z.
Proof.
  intros. unfold owned_sign_of. cbv zeta.
  destruct (tie_break_antisymmetric d p q) as [X [Y Z]]. rewrite X, Y, Z, edge_value_antisymmetric, !sign_of_opp.
  apply owned_sign_opp; apply sign3_of.
Qed.

(** A zero tie-break vector for an edge of the triangle forces den = 0: den = (r − p)·(d × (q − p)) for the
    edge p → q and the third vertex r. *)
Lemma tie_break_zero_den : forall d p q r,
  vx (tie_break d p q) = 0 -> vy (tie_break d p q) = 0 -> vz (tie_break d p q) = 0 ->
  dot d (cross (sub q p) (sub r p)) = 0.
Proof.
  intros d p q r X Y Z. unfold tie_break, cross, sub in X, Y, Z. simpl in X, Y, Z.
  unfold dot, cross, sub. simpl.
  replace (vx d * ((vy q - vy p) * (vz r - vz p) - (vz q - vz p) * (vy r - vy p)) +
           vy d * ((vz q - vz p) * (vx r - vx p) - (vx q - vx p) * (vz r - vz p)) +
           vz d * ((vx q - vx p) * (vy r - vy p) - (vy q - vy p) * (vx r - vx p)))
    with ((vx r - vx p) * (vy d * (vz q - vz p) - vz d * (vy q - vy p)) +
          (vy r - vy p) * (vz d * (vx q - vx p) - vx d * (vz q - vz p)) +
          (vz r - vz p) * (vx d * (vy q - vy p) - vy d * (vx q - vx p))) by ring.
  rewrite X, Y, Z. ring.
Qed.

(** When den ≠ 0 the owned sign of each edge of the triangle (a → b, b → c, c → a) is ±1. *)
Theorem owned_sign_nonzero : forall o d a b c, den_value o d a b c <> 0 ->
  owned_sign_of o d a b <> 0%Z /\ owned_sign_of o d b c <> 0%Z /\ owned_sign_of o d c a <> 0%Z.
Proof.
  intros o d a b c Hden. rewrite den_as_edge_values in Hden.
  destruct (den_cyclic d a b c) as [Cb Cc].
  assert (Edge : forall p q r, dot d (cross (sub q p) (sub r p)) <> 0 -> owned_sign_of o d p q <> 0%Z).
  { intros p q r H. unfold owned_sign_of, owned_sign. cbv zeta.
    destruct (Z.eqb_spec (sign_of (edge_value o d p q)) 0) as [E|E]; cbn [negb].
    - destruct (Z.eqb_spec (sign_of (vx (tie_break d p q))) 0) as [X|X]; cbn [negb].
      + destruct (Z.eqb_spec (sign_of (vy (tie_break d p q))) 0) as [Y|Y]; cbn [negb].
        * intros Z. apply sign_of_zero_iff in X, Y, Z. apply H. now apply tie_break_zero_den.
        * exact Y.
      + exact X.
    - exact E. }
  split; [|split].
  - apply (Edge a b c). exact Hden.
  - apply (Edge b c a). rewrite <- Cb. exact Hden.
  - apply (Edge c a b). rewrite <- Cc. exact Hden.
Qed.

(** The origin moved by δ: π changes by δ·(d × (q − p)), exactly (the term δ × δ vanishes). *)
Theorem edge_value_shift : forall o delta d p q,
  edge_value (Vec3 (vx o + vx delta) (vy o + vy delta) (vz o + vz delta)) d p q =
  edge_value o d p q + dot delta (tie_break d p q).
Proof. intros. unfold edge_value, tie_break, dot, cross, sub. simpl. ring. Qed.

(** ** The location. *)
Inductive location := Inside | EdgeAB | EdgeBC | EdgeCA | VertexA | VertexB | VertexC | Outside.

(** [triangle_location(sa, sb, sc, sden)] of ray_triangle_formula.hpp, branch by branch. *)
Definition triangle_location (sa sb sc sden : Z) : location :=
  if (Z.eqb sa (- sden) || Z.eqb sb (- sden) || Z.eqb sc (- sden))%bool then Outside
  else if (Z.eqb sb 0 && Z.eqb sc 0)%bool then VertexA
  else if (Z.eqb sc 0 && Z.eqb sa 0)%bool then VertexB
  else if (Z.eqb sa 0 && Z.eqb sb 0)%bool then VertexC
  else if Z.eqb sc 0 then EdgeAB
  else if Z.eqb sa 0 then EdgeBC
  else if Z.eqb sb 0 then EdgeCA
  else Inside.

(** docs/contract.md §6's definitions, from the signs of three reals πa, πb, πc whose sum den is not 0. *)
Theorem triangle_location_correct : forall pa pb pc, pa + pb + pc <> 0 ->
  let sa := sign_of pa in let sb := sign_of pb in let sc := sign_of pc in let sden := sign_of (pa + pb + pc) in
  (triangle_location sa sb sc sden = Outside <-> (sa = - sden \/ sb = - sden \/ sc = - sden)%Z) /\
  (triangle_location sa sb sc sden = Inside <-> (sa = sden /\ sb = sden /\ sc = sden)%Z) /\
  (triangle_location sa sb sc sden = EdgeAB <-> (sc = 0 /\ sa = sden /\ sb = sden)%Z) /\
  (triangle_location sa sb sc sden = EdgeBC <-> (sa = 0 /\ sb = sden /\ sc = sden)%Z) /\
  (triangle_location sa sb sc sden = EdgeCA <-> (sb = 0 /\ sc = sden /\ sa = sden)%Z) /\
  (triangle_location sa sb sc sden = VertexA <-> (sb = 0 /\ sc = 0)%Z) /\
  (triangle_location sa sb sc sden = VertexB <-> (sc = 0 /\ sa = 0)%Z) /\
  (triangle_location sa sb sc sden = VertexC <-> (sa = 0 /\ sb = 0)%Z).
Proof.
  intros pa pb pc Hd. cbv zeta. unfold sign_of.
  destruct (Rcompare_spec pa 0) as [A|A|A]; destruct (Rcompare_spec pb 0) as [B|B|B];
    destruct (Rcompare_spec pc 0) as [C|C|C]; destruct (Rcompare_spec (pa + pb + pc) 0) as [D|D|D];
    try (exfalso; apply Hd; exact D); try (exfalso; lra);
    unfold triangle_location; simpl;
    repeat match goal with |- _ /\ _ => split end;
    split; intros H; first [reflexivity | discriminate H | lia | (exfalso; lia)].
Qed.

(** So "the line passes through the closed triangle" is exactly "not Outside": every π has den's sign or is 0. *)
Theorem not_outside_iff : forall pa pb pc, pa + pb + pc <> 0 ->
  let sa := sign_of pa in let sb := sign_of pb in let sc := sign_of pc in let sden := sign_of (pa + pb + pc) in
  triangle_location sa sb sc sden <> Outside <->
    ((sa = 0 \/ sa = sden) /\ (sb = 0 \/ sb = sden) /\ (sc = 0 \/ sc = sden))%Z.
Proof.
  intros pa pb pc Hd. cbv zeta. unfold sign_of.
  destruct (Rcompare_spec pa 0) as [A|A|A]; destruct (Rcompare_spec pb 0) as [B|B|B];
    destruct (Rcompare_spec pc 0) as [C|C|C]; destruct (Rcompare_spec (pa + pb + pc) 0) as [D|D|D];
    try (exfalso; apply Hd; exact D); try (exfalso; lra);
    unfold triangle_location; simpl;
    split; intros H; first [(intros HH; discriminate HH) | (exfalso; apply H; reflexivity) | lia | (exfalso; lia)].
Qed.
