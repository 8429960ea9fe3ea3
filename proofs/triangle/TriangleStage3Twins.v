(** * Stage 3 of the ray–triangle cascade: the composition of kernel/src/core/expansion_value.hpp, as a
    twin over IEEE-754 binary64, proved to be the exact determinants of TriangleFilter.v.

    [EVal] is [ExpansionValue<N>]: the components (the capacity N is a compile-time bound the C++ never
    reaches, [length_value_ev]) and the flag [exact].  Each operation is the C++ one, operation by operation,
    built on Expansions.v's twins of the [ExpansionBuilder] ([sum_b], [scale_b], [from_pair],
    [check_finite], [expansion_sign_b]):

    - [ev_of] ([expansion_of]), [ev_diff] ([expansion_difference]: TwoDiff, exact when its first and last
      components are finite), [ev_add] ([operator+]: sum, then a fresh builder's [check_finite]), [ev_neg]
      ([operator-], unary), [ev_sub] ([a + (−b)]), [ev_mul] ([operator*(a, leaf b)]: one builder,
      [scale(a, b_0)], and when b has two components [scale(a, b_1)] summed with it, then [check_finite]);
      the formula writes leaf·cross with the leaf first, which the C++ forwards to [cross · leaf];
    - [ev_cross] ([cross_terms] on leaves), [ev_dot3] ([dot_terms] of leaves and cross components);
    - [edge_ev] (d·((p − o) × (q − o)): [value_expansion] of a π, or of den with a in o's place, over the
      leaves [expansion_leaf] reads), [num_ev] ([num_expansion]), [value_ev] ([value_expansion]: πa, πb, πc,
      den = π(b, c) seen from a, num, the leaves of each as [determinant_leaves] names them), [ev_sign]
      ([ExpansionValue::sign]).

    Theorems, for every 64-bit pattern of the inputs:
    - [value_ev_exact]: when [exact] is true, every component is finite and the components sum exactly to
      the model's determinant ([edge_value] for the π's, [den_value] for den, [num_value] for num);
    - [triangle_expansion_sign_sound]: the sign stage 3 certifies ([ev_sign]) is the sign of that exact
      value;
    - [length_value_ev]: at most 192 components (the C++ capacity [ExpansionValue<192>]).

    The differential runner (routine [tri_expansions], proofs/twins/) compares [value_ev] (components, flag,
    sign) with the compiled [value_expansion] bit for bit. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification FloatCore PlaneTwins Expansions TriangleFilter TriangleRule
  TriangleTwins.
Import ListNotations.
Open Scope R_scope.

(** ** The twins *)

Record EVal := EV { ecomp : list float; eexact : bool }.

(** [expansion_of(x)]: {x}, exact when x is finite. *)
Definition ev_of (x : float) : EVal := EV [x] (fin x).

(** [expansion_difference(v, w)]: from_pair(two_diff(v, w)), exact when its first and last components are
    finite. *)
Definition ev_diff (v w : float) : EVal :=
  let e := from_pair (two_diff_b v w) in EV e (fin (hd fzero e) && fin (last e fzero))%bool.

(** [a + b]: sum, then [check_finite] on a fresh builder. *)
Definition ev_add (a b : EVal) : EVal :=
  let r := sum_b (ecomp a) (ecomp b) in EV r (eexact a && eexact b && check_finite true r)%bool.

(** [−a] (exact negation of each component) and [a − b] = [a + (−b)]. *)
Definition ev_neg (a : EVal) : EVal := EV (map fneg (ecomp a)) (eexact a).
Definition ev_sub (a b : EVal) : EVal := ev_add a (ev_neg b).

(** [a * b], b a leaf: one builder; scale(a, b_0), and if b has two components scale(a, b_1) and their
    sum; then check_finite. *)
Definition ev_mul (a b : EVal) : EVal :=
  let first := scale_b true (ecomp a) (hd fzero (ecomp b)) in
  if Nat.eqb (length (ecomp b)) 1 then
    EV (snd first) (eexact a && eexact b && check_finite (fst first) (snd first))%bool
  else
    let second := scale_b (fst first) (ecomp a) (nth 1 (ecomp b) fzero) in
    let r := sum_b (snd first) (snd second) in
    EV r (eexact a && eexact b && check_finite (fst second) r)%bool.

Record E3 := E3v { e0 : EVal; e1 : EVal; e2 : EVal }.

(** [cross_terms(y, z)] on leaves (leaf·leaf: [ev_mul y_i z_j]). *)
Definition ev_cross (y z : E3) : E3 :=
  E3v (ev_sub (ev_mul (e1 y) (e2 z)) (ev_mul (e2 y) (e1 z)))
      (ev_sub (ev_mul (e2 y) (e0 z)) (ev_mul (e0 y) (e2 z)))
      (ev_sub (ev_mul (e0 y) (e1 z)) (ev_mul (e1 y) (e0 z))).

(** [dot_terms(x, c)] = (x_0·c_0 + x_1·c_1) + x_2·c_2, each leaf·cross product computed as c_i·x_i. *)
Definition ev_dot3 (x c : E3) : EVal :=
  ev_add (ev_add (ev_mul (e0 c) (e0 x)) (ev_mul (e1 c) (e1 x))) (ev_mul (e2 c) (e2 x)).

Definition lift3 (d : TVec) : E3 := E3v (ev_of (tx d)) (ev_of (ty d)) (ev_of (tz d)).
Definition diff3 (v o : TVec) : E3 := E3v (ev_diff (tx v) (tx o)) (ev_diff (ty v) (ty o)) (ev_diff (tz v) (tz o)).

(** d·((p − o) × (q − o)) (a π, or den from a); [num_expansion] = (a − o)·((b − o) × (c − o)). *)
Definition edge_ev (o d p q : TVec) : EVal := ev_dot3 (lift3 d) (ev_cross (diff3 p o) (diff3 q o)).
Definition num_ev (o a b c : TVec) : EVal := ev_dot3 (diff3 a o) (ev_cross (diff3 b o) (diff3 c o)).

(** [value_expansion(ray, triangle, v)]: 0 πa, 1 πb, 2 πc, 3 den (π(b, c) seen from a), otherwise num. *)
Definition value_ev (o d a b c : TVec) (v : Z) : EVal :=
  if Z.eqb v 0 then edge_ev o d b c else if Z.eqb v 1 then edge_ev o d c a
  else if Z.eqb v 2 then edge_ev o d a b else if Z.eqb v 3 then edge_ev a d b c else num_ev o a b c.

(** [ExpansionValue::sign()]: the checked sign when exact, else uncertain. *)
Definition ev_sign (e : EVal) : sign := if eexact e then expansion_sign_b (ecomp e) else Uncertain.

(** ** Exactness *)

(** [e] has at most [n] components and, when exact, finite components summing to [V]. *)
Definition ev_ok (e : EVal) (V : R) (n : nat) : Prop :=
  (length (ecomp e) <= n)%nat /\ (eexact e = true -> all_fin (ecomp e) /\ sumR (ecomp e) = V).

Lemma ev_of_ok : forall x, ev_ok (ev_of x) (B2R x) 1.
Proof.
  intros x. split; [cbn; lia|]. cbn [ev_of eexact ecomp]. intros F.
  split; [constructor; [exact F | constructor]|]. unfold sumR. cbn. ring.
Qed.

Lemma all_fin_two : forall l, (length l <= 2)%nat -> fin (hd fzero l) = true -> fin (last l fzero) = true ->
  all_fin l.
Proof.
  intros [|x [|y [|z l]]] L H1 H2; cbn in *; repeat constructor; auto; lia.
Qed.

Lemma ev_diff_ok : forall v w, ev_ok (ev_diff v w) (B2R v - B2R w) 2.
Proof.
  intros v w. unfold ev_diff; cbv zeta. split; [apply length_from_pair|]. cbn [eexact ecomp]. intros F.
  apply andb_prop in F. destruct F as [F1 F2].
  assert (A : all_fin (from_pair (two_diff_b v w))) by (apply all_fin_two; auto; apply length_from_pair).
  split; [exact A|]. destruct (from_pair_exact _ A) as [_ [L E]]. rewrite E.
  pose proof (two_sum_twin_exact _ _ L) as T. unfold two_diff_b in *. rewrite fneg_val in T. lra.
Qed.

Lemma ev_add_ok : forall a b A B n m, ev_ok a A n -> ev_ok b B m -> ev_ok (ev_add a b) (A + B) (n + m).
Proof.
  intros a b A B n m [La Ea] [Lb Eb]. unfold ev_add; cbv zeta. split.
  - cbn [ecomp]. pose proof (length_sum_gen two_sum_b (ecomp a) (ecomp b)). lia.
  - cbn [eexact ecomp]. intros X. apply andb_prop in X. destruct X as [X C]. apply andb_prop in X.
    destruct X as [Xa Xb]. destruct (check_finite_true _ _ C) as [_ F].
    destruct (sum_gen_exact _ _ F) as [_ [_ S]]. destruct (Ea Xa) as [_ Sa]. destruct (Eb Xb) as [_ Sb].
    split; [exact F|]. rewrite S, Sa, Sb. reflexivity.
Qed.

Lemma all_fin_map_neg : forall l, all_fin l -> all_fin (map fneg l).
Proof.
  induction l as [|x l IH]; intros H; [constructor|]. inversion H as [|y k Fx Fl]; subst.
  constructor; [rewrite fneg_fin; exact Fx | apply IH; exact Fl].
Qed.

Lemma ev_neg_ok : forall a A n, ev_ok a A n -> ev_ok (ev_neg a) (- A) n.
Proof.
  intros a A n [La Ea]. unfold ev_neg. split; cbn [ecomp eexact].
  - rewrite map_length. exact La.
  - intros X. destruct (Ea X) as [F S]. split; [now apply all_fin_map_neg|]. rewrite sumR_neg, S. reflexivity.
Qed.

Lemma ev_sub_ok : forall a b A B n m, ev_ok a A n -> ev_ok b B m -> ev_ok (ev_sub a b) (A - B) (n + m).
Proof. intros. unfold ev_sub, Rminus. apply ev_add_ok; [|apply ev_neg_ok]; assumption. Qed.

Lemma ev_mul_ok : forall a b A B n, ev_ok a A n -> ev_ok b B 2 -> ev_ok (ev_mul a b) (A * B) (4 * n).
Proof.
  intros a b A B n [La Ea] [Lb Eb]. unfold ev_mul; cbv zeta.
  destruct (Nat.eqb_spec (length (ecomp b)) 1) as [L1|L1].
  - split; cbn [ecomp].
    + pose proof (length_scale_gen two_sum_b true (ecomp a) (hd fzero (ecomp b))). lia.
    + cbn [eexact]. intros X. apply andb_prop in X. destruct X as [X C]. apply andb_prop in X.
      destruct X as [Xa Xb]. destruct (check_finite_true _ _ C) as [Xs F].
      destruct (scale_gen_exact _ _ _ Xs F) as [_ [_ [_ S]]].
      destruct (Ea Xa) as [_ Sa]. destruct (Eb Xb) as [_ Sb].
      split; [exact F|]. rewrite S, Sa, <- Sb.
      destruct (ecomp b) as [|b0 [|b1 l]]; cbn in L1; try discriminate.
      unfold sumR. cbn. ring.
  - split; cbn [ecomp].
    + pose proof (length_sum_gen two_sum_b (snd (scale_b true (ecomp a) (hd fzero (ecomp b))))
                    (snd (scale_b (fst (scale_b true (ecomp a) (hd fzero (ecomp b)))) (ecomp a)
                                  (nth 1 (ecomp b) fzero)))).
      pose proof (length_scale_gen two_sum_b true (ecomp a) (hd fzero (ecomp b))).
      pose proof (length_scale_gen two_sum_b (fst (scale_b true (ecomp a) (hd fzero (ecomp b)))) (ecomp a)
                    (nth 1 (ecomp b) fzero)).
      lia.
    + cbn [eexact]. intros X. apply andb_prop in X. destruct X as [X C]. apply andb_prop in X.
      destruct X as [Xa Xb]. destruct (check_finite_true _ _ C) as [Xs F].
      destruct (sum_gen_exact _ _ F) as [F1 [F2 S]].
      destruct (scale_gen_exact _ _ _ Xs F2) as [X1 [_ [_ S2]]].
      destruct (scale_gen_exact _ _ _ X1 F1) as [_ [_ [_ S1]]].
      destruct (Ea Xa) as [_ Sa]. destruct (Eb Xb) as [_ Sb].
      split; [exact F|]. rewrite S, S1, S2, Sa, <- Sb.
      destruct (ecomp b) as [|b0 [|b1 [|b2 l]]]; cbn in L1, Lb; try lia; unfold sumR; cbn.
      * change (B2R fzero) with 0. ring.
      * ring.
Qed.

Definition e3_ok (x : E3) (v : vec3) (n : nat) : Prop :=
  ev_ok (e0 x) (vx v) n /\ ev_ok (e1 x) (vy v) n /\ ev_ok (e2 x) (vz v) n.

Lemma ev_cross_ok : forall y z Y Z, e3_ok y Y 2 -> e3_ok z Z 2 -> e3_ok (ev_cross y z) (cross Y Z) 16.
Proof.
  intros y z Y Z [Y0 [Y1 Y2]] [Z0 [Z1 Z2]]. unfold ev_cross, e3_ok, cross. cbn [e0 e1 e2 vx vy vz].
  refine (conj _ (conj _ _));
    match goal with |- ev_ok (ev_sub (ev_mul ?a ?b) (ev_mul ?c ?e)) _ _ =>
      apply (ev_sub_ok _ _ _ _ 8 8); apply (ev_mul_ok _ _ _ _ 2); assumption end.
Qed.

Lemma ev_dot_ok : forall x c X C, e3_ok x X 2 -> e3_ok c C 16 -> ev_ok (ev_dot3 x c) (dot X C) 192.
Proof.
  intros x c X C [X0 [X1 X2]] [C0 [C1 C2]]. unfold ev_dot3, dot.
  replace (vx X * vx C + vy X * vy C + vz X * vz C) with (vx C * vx X + vy C * vy X + vz C * vz X) by ring.
  apply (ev_add_ok _ _ _ _ 128 64); [apply (ev_add_ok _ _ _ _ 64 64)|]; apply (ev_mul_ok _ _ _ _ 16); assumption.
Qed.

Lemma weaken_ok : forall e V n m, (n <= m)%nat -> ev_ok e V n -> ev_ok e V m.
Proof. intros e V n m L [H1 H2]. split; [lia | exact H2]. Qed.

Lemma lift3_ok : forall d, e3_ok (lift3 d) (tvec_R d) 2.
Proof. intros d. unfold lift3, e3_ok. cbn. refine (conj _ (conj _ _)); apply (weaken_ok _ _ 1); auto; apply ev_of_ok. Qed.

Lemma diff3_ok : forall v o, e3_ok (diff3 v o) (sub (tvec_R v) (tvec_R o)) 2.
Proof. intros v o. unfold diff3, e3_ok. cbn. refine (conj _ (conj _ _)); apply ev_diff_ok. Qed.

Lemma edge_ev_ok : forall o d p q,
  ev_ok (edge_ev o d p q) (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) 192.
Proof.
  intros. unfold edge_ev, edge_value. apply ev_dot_ok; [apply lift3_ok|]. apply ev_cross_ok; apply diff3_ok.
Qed.

Lemma num_ev_ok : forall o a b c, ev_ok (num_ev o a b c) (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) 192.
Proof.
  intros. unfold num_ev, num_value. apply ev_dot_ok; [apply diff3_ok|]. apply ev_cross_ok; apply diff3_ok.
Qed.

(** The model's value of determinant v (TriangleFilter.v; den as [den_value], the sum of the three π). *)
Definition value_model (o d a b c : TVec) (v : Z) : R :=
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  if Z.eqb v 0 then edge_value O D B C else if Z.eqb v 1 then edge_value O D C A
  else if Z.eqb v 2 then edge_value O D A B else if Z.eqb v 3 then den_value O D A B C else num_value O A B C.

Lemma den_from_a : forall o d a b c, edge_value a d b c = den_value o d a b c.
Proof. intros. rewrite den_as_edge_values. reflexivity. Qed.

Lemma value_ev_ok : forall o d a b c v, ev_ok (value_ev o d a b c v) (value_model o d a b c v) 192.
Proof.
  intros o d a b c v. unfold value_ev, value_model. cbv zeta.
  destruct (Z.eqb v 0); [exact (edge_ev_ok o d b c)|].
  destruct (Z.eqb v 1); [exact (edge_ev_ok o d c a)|].
  destruct (Z.eqb v 2); [exact (edge_ev_ok o d a b)|].
  destruct (Z.eqb v 3); [|exact (num_ev_ok o a b c)].
  rewrite <- (den_from_a (tvec_R o)). exact (edge_ev_ok a d b c).
Qed.

(** Stage 3 of determinant v, for every bit pattern of o, d, a, b, c: when the expansion is exact, its
    components are finite and sum exactly to the model's πa, πb, πc, den or num. *)
Theorem value_ev_exact : forall o d a b c v,
  eexact (value_ev o d a b c v) = true ->
  all_fin (ecomp (value_ev o d a b c v)) /\ sumR (ecomp (value_ev o d a b c v)) = value_model o d a b c v.
Proof. intros o d a b c v X. exact (proj2 (value_ev_ok o d a b c v) X). Qed.

Theorem length_value_ev : forall o d a b c v, (length (ecomp (value_ev o d a b c v)) <= 192)%nat.
Proof. intros. exact (proj1 (value_ev_ok o d a b c v)). Qed.

(** The sign stage 3 certifies for determinant v is the exact sign of the model's value. *)
Theorem triangle_expansion_sign_sound : forall o d a b c v,
  certifies (ev_sign (value_ev o d a b c v)) (value_model o d a b c v).
Proof.
  intros o d a b c v. unfold ev_sign.
  destruct (eexact (value_ev o d a b c v)) eqn:X; [|exact I].
  destruct (value_ev_exact o d a b c v X) as [F S]. rewrite <- S.
  apply expansion_sign_sound; [exact F|]. pose proof (length_value_ev o d a b c v). lia.
Qed.
