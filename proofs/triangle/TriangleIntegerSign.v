(** * Stage 3's first try of the ray–triangle cascade: the exact sign of a determinant in integers
    (kernel/src/triangle/ray_triangle_stages.hpp, [integer_value_sign]; kernel/src/core/integer_det3.hpp).

    The C++ reads each determinant's leaves as integer vectors over one power of two — d's doubles
    ([direction_vector_b], IntegerDet3.v's [integer_vector]) and each difference p − o as TwoDiff's two parts
    ([difference_vector_b], [integer_vector_sum]: exact whether or not p − o is a double, [difference_vector_ok])
    — and asks [integer_det3_sign] ([det3_Z]).  The twin [integer_value_sign_b] does the same on the fifteen inputs, and
    [integer_value_sign_sound] proves a certain answer the exact sign of the determinant ([value_model]: πa, πb,
    πc, den seen from a, num).  The runner compares it with the C++ through the cascade's routines
    ([tri_cascade_relation], [tri_cascade_intersect]: TriangleCascadeFlowTwins.v's [tc_sign_b] asks it before
    the expansions).

    The same leaves give the roundings' stage-3 value ([integer_value_components], IntegerExpansion.v's
    [integer_components]): [integer_value_components_sound], at most four finite doubles summing exactly to the
    determinant; the twin [integer_value_components_b] is asked by the cascade's twin before the expansions
    ([tc_stage3_components_b]) and compared through [tri_cascade_intersect]. Both are one walk over the leaves
    ([integer_value_b], [integer_value_spec]) with the sign or the components at its end. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification PlaneCascade FloatCore PlaneTwins Expansions IntegerDet3
  IntegerExpansion TriangleFilter TriangleTwins TriangleStage3Twins.
Open Scope R_scope.

(** A vector read as integers over one power of two: (X0, X1, X2, E). [ivec_ok X x]: X is the vector x, each
    integer below 2^62 (what the C++'s fixed widths need: IntegerDet3.v's [det3_range]). *)
Definition ivec := (Z * Z * Z * Z)%type.
Definition ivec_ok (X : ivec) (x : vec3) : Prop :=
  let '(X0, X1, X2, E) := X in
  vx x = IZR X0 * bpow radix2 E /\ vy x = IZR X1 * bpow radix2 E /\ vz x = IZR X2 * bpow radix2 E /\
  (Z.abs X0 < 2 ^ 62 /\ Z.abs X1 < 2 ^ 62 /\ Z.abs X2 < 2 ^ 62)%Z.

(** integer_leaf for d: its three doubles ([integer_vector]). *)
Definition direction_vector_b (d : TVec) : option ivec := integer_vector (tx d) (ty d) (tz d).

Lemma direction_vector_ok : forall d X, direction_vector_b d = Some X -> ivec_ok X (tvec_R d).
Proof.
  intros d [[[X0 X1] X2] E] H. destruct (integer_vector_value _ _ _ _ _ _ _ H) as [V0 [V1 [V2 B]]].
  unfold ivec_ok, tvec_R. cbn [vx vy vz]. auto.
Qed.

(** integer_leaf for p − from: TwoDiff's parts of each component, read together ([integer_vector_sum]). *)
Definition difference_vector_b (p from : TVec) : option ivec :=
  let '(hx, lx) := two_diff_b (tx p) (tx from) in
  let '(hy, ly) := two_diff_b (ty p) (ty from) in
  let '(hz, lz) := two_diff_b (tz p) (tz from) in
  integer_vector_sum hx hy hz lx ly lz.

(** A finite low part makes the two parts the exact difference ([two_sum_b_exact]). *)
Lemma two_diff_parts_exact : forall v w, fin (snd (two_diff_b v w)) = true ->
  B2R (fst (two_diff_b v w)) + B2R (snd (two_diff_b v w)) = B2R v - B2R w.
Proof.
  intros v w F. unfold two_diff_b in *. destruct (two_sum_b_exact v (fneg w) F) as [_ [_ S]].
  rewrite fneg_val in S. lra.
Qed.

Lemma difference_vector_ok : forall p from X, difference_vector_b p from = Some X ->
  ivec_ok X (sub (tvec_R p) (tvec_R from)).
Proof.
  intros p from [[[X0 X1] X2] E] H. unfold difference_vector_b in H.
  destruct (two_diff_b (tx p) (tx from)) as [hx lx] eqn:Tx.
  destruct (two_diff_b (ty p) (ty from)) as [hy ly] eqn:Ty.
  destruct (two_diff_b (tz p) (tz from)) as [hz lz] eqn:Tz.
  destruct (integer_vector_sum_fin _ _ _ _ _ _ _ H) as [Fx [Fy Fz]].
  destruct (integer_vector_sum_value _ _ _ _ _ _ _ _ _ _ H) as [V0 [V1 [V2 B]]].
  pose proof (two_diff_parts_exact (tx p) (tx from)) as Ex. rewrite Tx in Ex.
  pose proof (two_diff_parts_exact (ty p) (ty from)) as Ey. rewrite Ty in Ey.
  pose proof (two_diff_parts_exact (tz p) (tz from)) as Ez. rewrite Tz in Ez.
  cbn [fst snd] in Ex, Ey, Ez.
  unfold ivec_ok, sub, tvec_R. cbn [vx vy vz].
  rewrite <- (Ex Fx), <- (Ey Fy), <- (Ez Fz). auto.
Qed.

(** [integer_det3_sign(X, Y, Z)] and [integer_det3_components(X, Y, Z)] of three integer vectors. *)
Definition integer_det3_sign_b (X Y W : ivec) : sign :=
  let '(X0, X1, X2, _) := X in let '(Y0, Y1, Y2, _) := Y in let '(W0, W1, W2, _) := W in
  match Z.compare (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) 0 with Lt => Negative | Eq => Zero | Gt => Positive end.

Definition integer_det3_components_b (X Y W : ivec) : option (list float) :=
  let '(X0, X1, X2, Ex) := X in let '(Y0, Y1, Y2, Ey) := Y in let '(W0, W1, W2, Ez) := W in
  integer_components (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) (Ex + Ey + Ez).

(** The leaves of determinant v as the C++ forms them ([integer_leaf], [determinant_leaves]): x = d (x = a − o
    for num), y = p − o, z = q − o with (p, q) = (b, c), (c, a), (a, b), and for den (b, c) from a — handed to f
    (the sign or the components), or [none] when a leaf is not an integer vector. *)
Section Leaves.
Context {A : Type} (f : ivec -> ivec -> ivec -> A) (none : A).

Definition integer_leaves_b (X : option ivec) (p q from : TVec) : A :=
  match X, difference_vector_b p from, difference_vector_b q from with
  | Some X, Some Y, Some W => f X Y W
  | _, _, _ => none
  end.

Definition integer_value_b (o d a b c : TVec) (v : Z) : A :=
  if Z.eqb v 0 then integer_leaves_b (direction_vector_b d) b c o
  else if Z.eqb v 1 then integer_leaves_b (direction_vector_b d) c a o
  else if Z.eqb v 2 then integer_leaves_b (direction_vector_b d) a b o
  else if Z.eqb v 3 then integer_leaves_b (direction_vector_b d) b c a
  else integer_leaves_b (difference_vector_b a o) b c o.

(** What f's answer means of the determinant of its integer vectors' values, it means of the determinant v. *)
Variable P : A -> R -> Prop.
Hypothesis P_none : forall r, P none r.
Hypothesis P_f : forall X Y W x y z, ivec_ok X x -> ivec_ok Y y -> ivec_ok W z -> P (f X Y W) (dot x (cross y z)).

Lemma integer_leaves_spec : forall X x p q from, (forall X', X = Some X' -> ivec_ok X' x) ->
  P (integer_leaves_b X p q from) (dot x (cross (sub (tvec_R p) (tvec_R from)) (sub (tvec_R q) (tvec_R from)))).
Proof.
  intros X x p q from HX. unfold integer_leaves_b.
  destruct X as [X'|]; [|apply P_none].
  destruct (difference_vector_b p from) as [Y|] eqn:HY; [|apply P_none].
  destruct (difference_vector_b q from) as [W|] eqn:HW; [|apply P_none].
  apply P_f; [now apply HX | now apply difference_vector_ok | now apply difference_vector_ok].
Qed.

Theorem integer_value_spec : forall o d a b c v, P (integer_value_b o d a b c v) (value_model o d a b c v).
Proof.
  intros o d a b c v. unfold integer_value_b, value_model. cbv zeta.
  destruct (Z.eqb v 0); [apply integer_leaves_spec; intros X' E; now apply direction_vector_ok|].
  destruct (Z.eqb v 1); [apply integer_leaves_spec; intros X' E; now apply direction_vector_ok|].
  destruct (Z.eqb v 2); [apply integer_leaves_spec; intros X' E; now apply direction_vector_ok|].
  destruct (Z.eqb v 3).
  { rewrite <- den_from_a. apply integer_leaves_spec; intros X' E; now apply direction_vector_ok. }
  apply integer_leaves_spec. intros X' E. now apply difference_vector_ok.
Qed.
End Leaves.

(** An integer vector's determinant: the model's, with the C++'s fixed widths ([det3_scaled], [det3_range]). *)
Lemma ivec_det3 : forall X Y W x y z, ivec_ok X x -> ivec_ok Y y -> ivec_ok W z ->
  let '(X0, X1, X2, Ex) := X in let '(Y0, Y1, Y2, Ey) := Y in let '(W0, W1, W2, Ez) := W in
  dot x (cross y z) = IZR (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) * bpow radix2 (Ex + Ey + Ez) /\
  (Z.abs (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) < 2 ^ 189)%Z.
Proof.
  intros [[[X0 X1] X2] Ex] [[[Y0 Y1] Y2] Ey] [[[W0 W1] W2] Ez] x y z
    [Vx0 [Vx1 [Vx2 [Bx0 [Bx1 Bx2]]]]] [Vy0 [Vy1 [Vy2 [By0 [By1 By2]]]]] [Vz0 [Vz1 [Vz2 [Bz0 [Bz1 Bz2]]]]].
  split.
  - rewrite <- det3_scaled, <- Vx0, <- Vx1, <- Vx2, <- Vy0, <- Vy1, <- Vy2, <- Vz0, <- Vz1, <- Vz2.
    unfold det3_R, dot, cross. cbn [vx vy vz]. ring.
  - now apply det3_range.
Qed.

(** [integer_value_sign(ray, triangle, v)]. *)
Definition integer_value_sign_b (o d a b c : TVec) (v : Z) : sign :=
  integer_value_b integer_det3_sign_b Uncertain o d a b c v.

(** A certain answer is the exact sign of determinant v. *)
Theorem integer_value_sign_sound : forall o d a b c v,
  is_certain (integer_value_sign_b o d a b c v) = true ->
  sign_to_Z (integer_value_sign_b o d a b c v) = sign_of (value_model o d a b c v).
Proof.
  intros o d a b c v. unfold integer_value_sign_b.
  apply (integer_value_spec integer_det3_sign_b Uncertain
           (fun s r => is_certain s = true -> sign_to_Z s = sign_of r)).
  - intros r C. discriminate C.
  - intros X Y W x y z HX HY HZ _. pose proof (ivec_det3 X Y W x y z HX HY HZ) as D.
    destruct X as [[[X0 X1] X2] Ex], Y as [[[Y0 Y1] Y2] Ey], W as [[[W0 W1] W2] Ez].
    destruct D as [D _]. unfold integer_det3_sign_b, sign_of. rewrite D.
    set (n := det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2). set (p := bpow radix2 (Ex + Ey + Ez)).
    assert (Pp : 0 < p) by apply bpow_gt_0.
    destruct (Z.compare_spec n 0) as [E|L|G].
    + rewrite E. simpl. rewrite Rmult_0_l, Rcompare_Eq; reflexivity.
    + rewrite Rcompare_Lt; [reflexivity|]. apply IZR_lt in L. simpl in L. nra.
    + rewrite Rcompare_Gt; [reflexivity|]. apply IZR_lt in G. simpl in G. nra.
Qed.

(** [integer_value_components(leaves, v)]. *)
Definition integer_value_components_b (o d a b c : TVec) (v : Z) : option (list float) :=
  integer_value_b integer_det3_components_b None o d a b c v.

(** When it answers: at most four finite doubles whose exact sum is determinant v. *)
Theorem integer_value_components_sound : forall o d a b c v l,
  integer_value_components_b o d a b c v = Some l ->
  all_fin l /\ (length l <= 4)%nat /\ sumR l = value_model o d a b c v.
Proof.
  intros o d a b c v. unfold integer_value_components_b.
  apply (integer_value_spec integer_det3_components_b None
           (fun r x => forall l, r = Some l -> all_fin l /\ (length l <= 4)%nat /\ sumR l = x)).
  - intros x l E. discriminate E.
  - intros X Y W x y z HX HY HZ l H. pose proof (ivec_det3 X Y W x y z HX HY HZ) as D.
    destruct X as [[[X0 X1] X2] Ex], Y as [[[Y0 Y1] Y2] Ey], W as [[[W0 W1] W2] Ez].
    destruct D as [D R]. unfold integer_det3_components_b in H.
    assert (R' : (Z.abs (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) < 2 ^ 212)%Z).
    { apply Z.lt_trans with (2 ^ 189)%Z; [exact R | apply Z.pow_lt_mono_r; lia]. }
    destruct (integer_components_sound _ _ _ R' H) as [F [S L]].
    split; [exact F|]. split; [exact L|]. rewrite S, D. reflexivity.
Qed.
