(** * Stage 3's first try of the ray–triangle cascade: the exact sign of a determinant in integers
    (kernel/src/triangle/ray_triangle_stages.hpp, [integer_value_sign]; kernel/src/core/integer_det3.hpp).

    The C++ forms each determinant's leaves as single doubles — d, and each difference p − o by TwoDiff, kept
    only when its low part is 0 (then the difference is exact) — and asks [integer_det3_sign] (IntegerDet3.v's
    [integer_vector] and [det3_Z]).  The twin [integer_value_sign_b] does the same on the fifteen inputs, and
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

(** [two_diff(v, w)] kept when its low part is 0 ([ey.lo == 0]: false on NaN). *)
Definition exact_diff_b (v w : float) : option float :=
  let p := two_diff_b v w in if feq (snd p) fzero then Some (fst p) else None.

Lemma exact_diff_value : forall v w x, exact_diff_b v w = Some x -> B2R x = B2R v - B2R w.
Proof.
  intros v w x E. unfold exact_diff_b in E. destruct (feq (snd (two_diff_b v w)) fzero) eqn:Z; [|discriminate].
  injection E as <-. destruct (feq_zero _ Z) as [F V].
  unfold two_diff_b in *. destruct (two_sum_b_exact v (fneg w) F) as [_ [_ S]].
  rewrite fneg_val in S. change (B2R (fst (two_sum_b v (fneg w))) = B2R v - B2R w). lra.
Qed.

(** [integer_det3_sign(x, y, z)]. *)
Definition integer_det3_sign_b (x0 x1 x2 y0 y1 y2 z0 z1 z2 : float) : sign :=
  match integer_vector x0 x1 x2, integer_vector y0 y1 y2, integer_vector z0 z1 z2 with
  | Some (X0, X1, X2, _), Some (Y0, Y1, Y2, _), Some (W0, W1, W2, _) =>
      match Z.compare (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) 0 with Lt => Negative | Eq => Zero | Gt => Positive end
  | _, _, _ => Uncertain
  end.

Lemma integer_det3_sign_b_sound : forall x0 x1 x2 y0 y1 y2 z0 z1 z2,
  is_certain (integer_det3_sign_b x0 x1 x2 y0 y1 y2 z0 z1 z2) = true ->
  sign_to_Z (integer_det3_sign_b x0 x1 x2 y0 y1 y2 z0 z1 z2) =
  sign_of (det3_R (B2R x0) (B2R x1) (B2R x2) (B2R y0) (B2R y1) (B2R y2) (B2R z0) (B2R z1) (B2R z2)).
Proof.
  intros x0 x1 x2 y0 y1 y2 z0 z1 z2. unfold integer_det3_sign_b.
  destruct (integer_vector x0 x1 x2) as [[[[X0 X1] X2] Ex]|] eqn:HX; [|discriminate].
  destruct (integer_vector y0 y1 y2) as [[[[Y0 Y1] Y2] Ey]|] eqn:HY; [|discriminate].
  destruct (integer_vector z0 z1 z2) as [[[[W0 W1] W2] Ez]|] eqn:HZ; [|discriminate].
  intros _. destruct (integer_det3_sign_correct _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ HX HY HZ) as [S _].
  unfold sign_of. rewrite S. destruct (Z.compare _ 0); reflexivity.
Qed.

(** [integer_det3_components(x, y, z)]: D·2^(Ex+Ey+Ez) as at most four doubles (IntegerExpansion.v). *)
Definition integer_det3_components_b (x0 x1 x2 y0 y1 y2 z0 z1 z2 : float) : option (list float) :=
  match integer_vector x0 x1 x2, integer_vector y0 y1 y2, integer_vector z0 z1 z2 with
  | Some (X0, X1, X2, Ex), Some (Y0, Y1, Y2, Ey), Some (W0, W1, W2, Ez) =>
      integer_components (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) (Ex + Ey + Ez)
  | _, _, _ => None
  end.

Lemma integer_det3_components_b_sound : forall x0 x1 x2 y0 y1 y2 z0 z1 z2 l,
  integer_det3_components_b x0 x1 x2 y0 y1 y2 z0 z1 z2 = Some l ->
  all_fin l /\ (length l <= 4)%nat /\
  sumR l = det3_R (B2R x0) (B2R x1) (B2R x2) (B2R y0) (B2R y1) (B2R y2) (B2R z0) (B2R z1) (B2R z2).
Proof.
  intros x0 x1 x2 y0 y1 y2 z0 z1 z2 l. unfold integer_det3_components_b.
  destruct (integer_vector x0 x1 x2) as [[[[X0 X1] X2] Ex]|] eqn:HX; [|discriminate].
  destruct (integer_vector y0 y1 y2) as [[[[Y0 Y1] Y2] Ey]|] eqn:HY; [|discriminate].
  destruct (integer_vector z0 z1 z2) as [[[[W0 W1] W2] Ez]|] eqn:HZ; [|discriminate].
  intros H.
  destruct (integer_det3_sign_correct _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ HX HY HZ) as [_ [_ [_ [_ R]]]].
  assert (R' : (Z.abs (det3_Z X0 X1 X2 Y0 Y1 Y2 W0 W1 W2) < 2 ^ 212)%Z).
  { apply Z.lt_trans with (2 ^ 189)%Z; [exact R | apply Z.pow_lt_mono_r; lia]. }
  destruct (integer_components_sound _ _ _ R' H) as [F [S L]].
  split; [exact F|]. split; [exact L|]. rewrite S.
  destruct (integer_vector_value _ _ _ _ _ _ _ HX) as [Vx0 [Vx1 [Vx2 _]]].
  destruct (integer_vector_value _ _ _ _ _ _ _ HY) as [Vy0 [Vy1 [Vy2 _]]].
  destruct (integer_vector_value _ _ _ _ _ _ _ HZ) as [Vz0 [Vz1 [Vz2 _]]].
  rewrite Vx0, Vx1, Vx2, Vy0, Vy1, Vy2, Vz0, Vz1, Vz2, det3_scaled. reflexivity.
Qed.

(** The leaves of determinant v as the C++ forms them ([integer_leaf], [determinant_leaves]): x = d (x = a − o
    for num), y = p − o, z = q − o with (p, q) = (b, c), (c, a), (a, b), and for den (b, c) from a — handed to f
    (the sign or the components), or [none] when a difference is not exact. *)
Section Leaves.
Context {A : Type} (f : float -> float -> float -> float -> float -> float -> float -> float -> float -> A) (none : A).

Definition integer_leaves_b (x0 x1 x2 : float) (p q from : TVec) : A :=
  match exact_diff_b (tx p) (tx from), exact_diff_b (ty p) (ty from), exact_diff_b (tz p) (tz from),
        exact_diff_b (tx q) (tx from), exact_diff_b (ty q) (ty from), exact_diff_b (tz q) (tz from) with
  | Some y0, Some y1, Some y2, Some z0, Some z1, Some z2 => f x0 x1 x2 y0 y1 y2 z0 z1 z2
  | _, _, _, _, _, _ => none
  end.

Definition integer_value_b (o d a b c : TVec) (v : Z) : A :=
  if Z.eqb v 0 then integer_leaves_b (tx d) (ty d) (tz d) b c o
  else if Z.eqb v 1 then integer_leaves_b (tx d) (ty d) (tz d) c a o
  else if Z.eqb v 2 then integer_leaves_b (tx d) (ty d) (tz d) a b o
  else if Z.eqb v 3 then integer_leaves_b (tx d) (ty d) (tz d) b c a
  else match exact_diff_b (tx a) (tx o), exact_diff_b (ty a) (ty o), exact_diff_b (tz a) (tz o) with
       | Some x0, Some x1, Some x2 => integer_leaves_b x0 x1 x2 b c o
       | _, _, _ => none
       end.

(** What f's answer means of det3_R of its leaves, it means of the determinant v. *)
Variable P : A -> R -> Prop.
Hypothesis P_none : forall r, P none r.
Hypothesis P_f : forall x0 x1 x2 y0 y1 y2 z0 z1 z2,
  P (f x0 x1 x2 y0 y1 y2 z0 z1 z2) (det3_R (B2R x0) (B2R x1) (B2R x2) (B2R y0) (B2R y1) (B2R y2) (B2R z0) (B2R z1) (B2R z2)).

Lemma integer_leaves_spec : forall x0 x1 x2 p q from,
  P (integer_leaves_b x0 x1 x2 p q from)
    (dot (Vec3 (B2R x0) (B2R x1) (B2R x2)) (cross (sub (tvec_R p) (tvec_R from)) (sub (tvec_R q) (tvec_R from)))).
Proof.
  intros x0 x1 x2 p q from. unfold integer_leaves_b.
  destruct (exact_diff_b (tx p) (tx from)) as [y0|] eqn:Y0; [|apply P_none].
  destruct (exact_diff_b (ty p) (ty from)) as [y1|] eqn:Y1; [|apply P_none].
  destruct (exact_diff_b (tz p) (tz from)) as [y2|] eqn:Y2; [|apply P_none].
  destruct (exact_diff_b (tx q) (tx from)) as [z0|] eqn:W0; [|apply P_none].
  destruct (exact_diff_b (ty q) (ty from)) as [z1|] eqn:W1; [|apply P_none].
  destruct (exact_diff_b (tz q) (tz from)) as [z2|] eqn:W2; [|apply P_none].
  replace (dot _ _) with (det3_R (B2R x0) (B2R x1) (B2R x2) (B2R y0) (B2R y1) (B2R y2) (B2R z0) (B2R z1) (B2R z2));
    [apply P_f|].
  unfold det3_R, dot, cross, sub, tvec_R. cbn [vx vy vz].
  rewrite (exact_diff_value _ _ _ Y0), (exact_diff_value _ _ _ Y1), (exact_diff_value _ _ _ Y2),
    (exact_diff_value _ _ _ W0), (exact_diff_value _ _ _ W1), (exact_diff_value _ _ _ W2). ring.
Qed.

Theorem integer_value_spec : forall o d a b c v, P (integer_value_b o d a b c v) (value_model o d a b c v).
Proof.
  intros o d a b c v. unfold integer_value_b, value_model. cbv zeta.
  destruct (Z.eqb v 0); [apply integer_leaves_spec|].
  destruct (Z.eqb v 1); [apply integer_leaves_spec|].
  destruct (Z.eqb v 2); [apply integer_leaves_spec|].
  destruct (Z.eqb v 3); [rewrite <- den_from_a; apply integer_leaves_spec|].
  destruct (exact_diff_b (tx a) (tx o)) as [x0|] eqn:X0; [|apply P_none].
  destruct (exact_diff_b (ty a) (ty o)) as [x1|] eqn:X1; [|apply P_none].
  destruct (exact_diff_b (tz a) (tz o)) as [x2|] eqn:X2; [|apply P_none].
  replace (num_value _ _ _ _) with
    (dot (Vec3 (B2R x0) (B2R x1) (B2R x2)) (cross (sub (tvec_R b) (tvec_R o)) (sub (tvec_R c) (tvec_R o))));
    [apply integer_leaves_spec|].
  unfold num_value, dot, sub, tvec_R. cbn [vx vy vz].
  rewrite (exact_diff_value _ _ _ X0), (exact_diff_value _ _ _ X1), (exact_diff_value _ _ _ X2). reflexivity.
Qed.
End Leaves.

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
  - intros. now apply integer_det3_sign_b_sound.
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
  - intros x0 x1 x2 y0 y1 y2 z0 z1 z2 l. apply integer_det3_components_b_sound.
Qed.
