(** * The classification of docs/contract.md §1 (kernel/src/plane/ray_plane_formula.hpp, [relation_from_signs]).

    Over the reals, the seed's definition — a point o + t·d with t ≥ 0 on the plane (x − p)·n = 0 — is
    equivalent to the relation the code returns from the exact signs of num = (p − o)·n and den = d·n.
    Main theorem: [relation_correct]; the four [relation_*_iff] corollaries state it relation by
    relation.  [certified_sign] connects the stages' answers ([certifies], Model.v) to the signs
    [relation_from_signs] consumes. *)

From Coq Require Import Reals Lra ZArith.
From Flocq Require Import Core.
From Raykernel Require Import Model.
Open Scope R_scope.

Record vec3 := Vec3 { vx : R; vy : R; vz : R }.

Definition dot (a b : vec3) : R := vx a * vx b + vy a * vy b + vz a * vz b.
Definition sub (a b : vec3) : vec3 := Vec3 (vx a - vx b) (vy a - vy b) (vz a - vz b).
Definition point_on_ray (o d : vec3) (t : R) : vec3 :=
  Vec3 (vx o + t * vx d) (vy o + t * vy d) (vz o + t * vz d).

(** The plane through p with normal n: the points x with (x − p)·n = 0. *)
Definition on_plane (p n x : vec3) : Prop := dot (sub x p) n = 0.

(** [enum class Relation]. *)
Inductive relation := Hit | Behind | Parallel | InPlane.

(** [relation_from_signs(num_sign, den_sign)], signs as the C++ ints −1, 0, +1: for den ≠ 0, hit unless
    num_sign · den_sign < 0 (the C++ computes hit + (behind − hit)·[num_sign·den_sign < 0]). *)
Definition relation_from_signs (num_sign den_sign : Z) : relation :=
  if Z.eqb den_sign 0 then (if Z.eqb num_sign 0 then InPlane else Parallel)
  else if Z.ltb (num_sign * den_sign) 0 then Behind else Hit.

(** The exact sign of a real, as [static_cast<int>(Sign)] encodes it. *)
Definition sign_of (x : R) : Z :=
  match Rcompare x 0 with Lt => (-1)%Z | Eq => 0%Z | Gt => 1%Z end.

Definition sign_to_Z (s : sign) : Z :=
  match s with Negative => -1 | Zero => 0 | Positive => 1 | Uncertain => 2 end.

(** A certain answer of any stage is the exact sign. *)
Theorem certified_sign : forall s x, certifies s x -> s <> Uncertain -> sign_to_Z s = sign_of x.
Proof.
  intros [| | |] x H N; simpl in H; unfold sign_of.
  - now rewrite Rcompare_Lt.
  - now rewrite H, Rcompare_Eq.
  - now rewrite Rcompare_Gt.
  - now elim N.
Qed.

Definition ray_num (o p n : vec3) : R := dot (sub p o) n.
Definition ray_den (d n : vec3) : R := dot d n.

(** The point o + t·d is on the plane exactly when t·den = num. *)
Lemma on_plane_iff : forall o d p n t,
  on_plane p n (point_on_ray o d t) <-> t * ray_den d n = ray_num o p n.
Proof.
  intros. unfold on_plane, ray_num, ray_den, dot, sub, point_on_ray. simpl.
  split; intros H; lra.
Qed.

(** ** Main theorem. *)
Theorem relation_correct : forall o d p n : vec3,
  let num := ray_num o p n in
  let den := ray_den d n in
  match relation_from_signs (sign_of num) (sign_of den) with
  | Hit => den <> 0 /\ 0 <= num / den /\ (forall t, on_plane p n (point_on_ray o d t) <-> t = num / den)
  | Behind => den <> 0 /\ num / den < 0 /\ (forall t, on_plane p n (point_on_ray o d t) <-> t = num / den)
  | Parallel => den = 0 /\ forall t, ~ on_plane p n (point_on_ray o d t)
  | InPlane => den = 0 /\ forall t, on_plane p n (point_on_ray o d t)
  end.
Proof.
  intros o d p n num den.
  assert (Unique : den <> 0 -> forall t, on_plane p n (point_on_ray o d t) <-> t = num / den).
  { intros Nz t. rewrite on_plane_iff. fold num den. split; intros H.
    - rewrite <- H. field. exact Nz.
    - rewrite H. field. exact Nz. }
  unfold relation_from_signs, sign_of.
  destruct (Rcompare_spec den 0) as [Dn|Dz|Dp]; destruct (Rcompare_spec num 0) as [Nn|Nz|Np]; simpl.
  (* den < 0 *)
  - split; [lra|]. split; [|apply Unique; lra].
    unfold Rdiv. replace (num * / den) with ((- num) * / (- den)) by (field; lra).
    apply Rmult_le_pos; [lra|]. left. apply Rinv_0_lt_compat. lra.
  - split; [lra|]. split; [|apply Unique; lra]. rewrite Nz. unfold Rdiv. rewrite Rmult_0_l. lra.
  - split; [lra|]. split; [|apply Unique; lra].
    unfold Rdiv. replace (num * / den) with (- (num * / (- den))) by (field; lra).
    assert (0 < num * / - den) by (apply Rmult_lt_0_compat; [lra | apply Rinv_0_lt_compat; lra]). lra.
  (* den = 0 *)
  - split; [exact Dz|]. intros t H. apply on_plane_iff in H. fold num den in H. rewrite Dz in H. lra.
  - split; [exact Dz|]. intros t. apply on_plane_iff. fold num den. rewrite Dz, Nz. ring.
  - split; [exact Dz|]. intros t H. apply on_plane_iff in H. fold num den in H. rewrite Dz in H. lra.
  (* den > 0 *)
  - split; [lra|]. split; [|apply Unique; lra].
    assert (0 < - num / den) by (apply Rdiv_lt_0_compat; lra).
    unfold Rdiv in *. lra.
  - split; [lra|]. split; [|apply Unique; lra]. rewrite Nz. unfold Rdiv. rewrite Rmult_0_l. lra.
  - split; [lra|]. split; [|apply Unique; lra]. left. apply Rdiv_lt_0_compat; lra.
Qed.

(** ** The same, relation by relation, in the seed's words. *)

Definition meets (o d p n : vec3) (t : R) : Prop := on_plane p n (point_on_ray o d t).

Definition classify (o d p n : vec3) : relation :=
  relation_from_signs (sign_of (ray_num o p n)) (sign_of (ray_den d n)).

(** hit: exactly one point of the line is on the plane, and its parameter t is ≥ 0. *)
Corollary relation_hit_iff : forall o d p n,
  classify o d p n = Hit <-> (exists t, meets o d p n t /\ 0 <= t /\ forall t', meets o d p n t' -> t' = t).
Proof.
  intros o d p n. unfold classify, meets.
  pose proof (relation_correct o d p n) as H. cbv zeta in H.
  destruct (relation_from_signs _ _); split; intros K; try discriminate.
  - destruct H as [Nz [Pos U]]. exists (ray_num o p n / ray_den d n).
    split; [now apply U|]. split; [exact Pos|]. intros t' M. now apply U.
  - reflexivity.
  - destruct H as [Nz [Neg U]]. destruct K as [t [M [Pt _]]]. apply U in M. lra.
  - destruct H as [Z N]. destruct K as [t [M _]]. now apply N in M.
  - destruct H as [Z A]. destruct K as [t [M [_ U]]].
    pose proof (U (t + 1) (A (t + 1))). lra.
Qed.

(** behind: exactly one point of the line is on the plane, and its parameter t is < 0. *)
Corollary relation_behind_iff : forall o d p n,
  classify o d p n = Behind <-> (exists t, meets o d p n t /\ t < 0 /\ forall t', meets o d p n t' -> t' = t).
Proof.
  intros o d p n. unfold classify, meets.
  pose proof (relation_correct o d p n) as H. cbv zeta in H.
  destruct (relation_from_signs _ _); split; intros K; try discriminate.
  - destruct H as [Nz [Pos U]]. destruct K as [t [M [Nt _]]]. apply U in M. lra.
  - destruct H as [Nz [Neg U]]. exists (ray_num o p n / ray_den d n).
    split; [now apply U|]. split; [exact Neg|]. intros t' M. now apply U.
  - reflexivity.
  - destruct H as [Z N]. destruct K as [t [M _]]. now apply N in M.
  - destruct H as [Z A]. destruct K as [t [M [_ U]]].
    pose proof (U (t + 1) (A (t + 1))). lra.
Qed.

(** parallel: no point of the line is on the plane. *)
Corollary relation_parallel_iff : forall o d p n,
  classify o d p n = Parallel <-> (forall t, ~ meets o d p n t).
Proof.
  intros o d p n. unfold classify, meets.
  pose proof (relation_correct o d p n) as H. cbv zeta in H.
  destruct (relation_from_signs _ _); split; intros K; try discriminate.
  - destruct H as [_ [_ U]]. elim (K (ray_num o p n / ray_den d n)). now apply U.
  - destruct H as [_ [_ U]]. elim (K (ray_num o p n / ray_den d n)). now apply U.
  - destruct H as [_ N]. exact N.
  - reflexivity.
  - destruct H as [_ A]. elim (K 0). apply A.
Qed.

(** in-plane: every point of the line (so of the ray) is on the plane. *)
Corollary relation_in_plane_iff : forall o d p n,
  classify o d p n = InPlane <-> (forall t, meets o d p n t).
Proof.
  intros o d p n. unfold classify, meets.
  pose proof (relation_correct o d p n) as H. cbv zeta in H.
  destruct (relation_from_signs _ _); split; intros K; try discriminate.
  - destruct H as [_ [_ U]]. pose proof (proj1 (U _) (K (ray_num o p n / ray_den d n + 1))). lra.
  - destruct H as [_ [_ U]]. pose proof (proj1 (U _) (K (ray_num o p n / ray_den d n + 1))). lra.
  - destruct H as [_ N]. elim (N 0). apply K.
  - destruct H as [_ A]. exact A.
  - reflexivity.
Qed.

(** The seed's "the ray meets the plane": some t ≥ 0 puts o + t·d on the plane, exactly for hit and
    in-plane. *)
Corollary ray_meets_plane_iff : forall o d p n,
  (exists t, 0 <= t /\ meets o d p n t) <-> classify o d p n = Hit \/ classify o d p n = InPlane.
Proof.
  intros o d p n. unfold classify, meets.
  pose proof (relation_correct o d p n) as H. cbv zeta in H.
  destruct (relation_from_signs _ _); split; intros K.
  - now left.
  - destruct H as [Nz [Pos U]]. exists (ray_num o p n / ray_den d n). split; [exact Pos | now apply U].
  - destruct H as [Nz [Neg U]]. destruct K as [t [Pt M]]. apply U in M. lra.
  - destruct K as [K|K]; discriminate.
  - destruct H as [_ N]. destruct K as [t [_ M]]. now apply N in M.
  - destruct K as [K|K]; discriminate.
  - now right.
  - destruct H as [_ A]. exists 0. split; [lra | apply A].
Qed.

(** docs/contract.md §1: t = 0 when the origin lies on the plane. *)
Corollary hit_at_origin : forall o d p n,
  ray_num o p n = 0 -> ray_den d n <> 0 -> classify o d p n = Hit /\ ray_num o p n / ray_den d n = 0.
Proof.
  intros o d p n Z Nz. split.
  - unfold classify, relation_from_signs, sign_of. rewrite Z, (Rcompare_Eq 0 0 eq_refl).
    destruct (Rcompare_spec (ray_den d n) 0); simpl; try reflexivity. contradiction.
  - rewrite Z. unfold Rdiv. ring.
Qed.
