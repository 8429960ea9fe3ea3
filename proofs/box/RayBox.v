(** * The BVH's ray–box test never rejects a box the exact ray meets (kernel/src/box/ray_box.hpp).

    For one axis of the slab test, with d ≠ 0 in the range where 1/d is a normal double (case B of the
    argument in ray_box.hpp), the code computes

      inv = RN(1/d),  p = RN(RN(plane − o) · inv),
      near_lo = RN(RN(p · K_lo) − τ),  far_hi = RN(RN(p · K_hi) + τ)

    with K_lo = 1 − 2^-50, K_hi = 1 + 2^-50, τ = 2^-1022.  Main theorems, for the exact slab parameter
    T = (plane − o)/d:
    - [near_bound_sound]: near_lo ≤ T when T ≥ 0, and near_lo ≤ 0 when T < 0;
    - [far_bound_sound]: far_hi ≥ T when T ≥ 0;
    - [slab_sound]: for every real t* ≥ 0 in the exact slab [T_near, T_far], near_lo ≤ t* ≤ far_hi;
    - [slab_sound_outward]: the same on the box the BVH stores (binary32 bounds rounded outward, lo down and
      hi up, converted exactly to double): near_lo ≤ t* ≤ far_hi for every real t* ≥ 0 in the exact box's
      slab;
    - [ray_box_sound]: the test's t0 = max(t_min, near_lo of each axis) and t1 = min(t_max, far_hi of each
      axis), with an axis left out (NaN, case A's equalities and case C) modelled as [None], satisfy
      t0 ≤ t* ≤ t1 for every t* in [t_min, t_max] that the slab bounds allow: the box is not rejected, and
      t0 is a lower bound of the exact entry.
    Overflow is outside the model (Model.v); the C++ guard G = RN(RN(M + |o|)·|inv|) ≤ 2^1022 keeps every
    value of case B below 2^1023 (ray_box.hpp, B2), and case A's infinities are argued there. *)

From Coq Require Import Reals Lra Lia List.
From Flocq Require Import Core Relative.
From Raykernel Require Import Constants Model.
Open Scope R_scope.
Import ListNotations.

(** The constants of ray_box.hpp ([bounds::ray_box_*]) are Constants.v's: K_lo = [ray_box_near_factor],
    K_hi = [ray_box_far_factor], τ = [ray_box_absolute]. *)

(** ** The C++ operations, in the source's order. *)

Definition slab_parameter (plane o inv : R) : R := RN (RN (plane - o) * inv).
Definition near_bound (p : R) : R := RN (RN (p * ray_box_near_factor) - ray_box_absolute).
Definition far_bound (p : R) : R := RN (RN (p * ray_box_far_factor) + ray_box_absolute).

(** ** Facts about the constants. *)

Lemma tau_eta : ray_box_absolute = 9007199254740992 * eta.
Proof. unfold ray_box_absolute, eta. rewrite (bpow_plus radix2 53 (-1075)) at 1. simpl. lra. Qed.

Lemma factors_u : ray_box_near_factor = 1 - 8 * u /\ ray_box_far_factor = 1 + 8 * u.
Proof. unfold ray_box_near_factor, ray_box_far_factor. rewrite u_val. simpl. split; lra. Qed.

Lemma u_small : 0 < u < / 1000000.
Proof. rewrite u_val. lra. Qed.

Lemma binary64_tau : binary64 ray_box_absolute.
Proof. apply binary64_bpow. lia. Qed.

(** ** Relative-error forms. *)

Lemma rel_form : forall v w, Rabs (w - v) <= u * Rabs v -> exists e, Rabs e <= u /\ w = v * (1 + e).
Proof.
  intros v w H. pose proof u_small.
  destruct (Req_dec v 0) as [Z|NZ].
  - subst v. rewrite Rabs_R0, Rmult_0_r in H. exists 0. split.
    + rewrite Rabs_R0. lra.
    + assert (Rabs (w - 0) = 0) by (pose proof (Rabs_pos (w - 0)); lra).
      destruct (Req_dec (w - 0) 0) as [W|W]; [lra|]. now apply Rabs_no_R0 in W.
  - exists ((w - v) / v). split.
    + unfold Rdiv. rewrite Rabs_mult, Rabs_inv. apply Rmult_le_reg_r with (Rabs v).
      * now apply Rabs_pos_lt.
      * rewrite Rmult_assoc, Rinv_l; [lra|]. now apply Rabs_no_R0.
    + field. exact NZ.
Qed.

(** RN(1/d) has a relative error only, for |1/d| ≥ 2^-1022. *)
Lemma inverse_rel : forall d, bpow radix2 (-1022) <= Rabs (/ d) ->
  exists e, Rabs e <= u /\ RN (/ d) = / d * (1 + e).
Proof.
  intros d H. apply rel_form.
  pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) (/ d) H) as H1.
  rewrite half_bpow_52 in H1. exact H1.
Qed.

(** y = RN(plane − o) · inv = T(1 + e1)(1 + e2). *)
Lemma product_form : forall plane o d, binary64 plane -> binary64 o -> d <> 0 ->
  bpow radix2 (-1022) <= Rabs (/ d) ->
  exists e1 e2, Rabs e1 <= u /\ Rabs e2 <= u /\
    RN (plane - o) * RN (/ d) = (plane - o) / d * ((1 + e1) * (1 + e2)).
Proof.
  intros plane o d Hp Ho Hd Hinv.
  destruct (rel_form (plane - o) (RN (plane - o)) (RN_minus_err plane o Hp Ho)) as [e1 [He1 E1]].
  destruct (inverse_rel d Hinv) as [e2 [He2 E2]].
  exists e1, e2. repeat split; try assumption. rewrite E1, E2. unfold Rdiv. ring.
Qed.

Lemma factor_bounds : forall e1 e2, Rabs e1 <= u -> Rabs e2 <= u ->
  (1 - u) * (1 - u) <= (1 + e1) * (1 + e2) <= (1 + u) * (1 + u).
Proof.
  intros e1 e2 H1 H2. pose proof u_small.
  apply Rabs_bounds in H1. apply Rabs_bounds in H2. split; nra.
Qed.

Lemma mult_nonpos_nonneg : forall a b, a <= 0 -> 0 <= b -> a * b <= 0.
Proof. intros a b Ha Hb. nra. Qed.

(** The margins of the outward factors: K_lo(1 + u)^5 ≤ 1 and K_hi(1 − u)^5 ≥ 1 (u = 2^-53). *)
Lemma near_margin : (1 + u) * (1 + u) * (1 + u) * (1 - 8 * u) * (1 + u) * (1 + u) <= 1.
Proof. rewrite u_val. lra. Qed.

Lemma far_margin : 1 <= (1 - u) * (1 - u) * (1 - u) * (1 + 8 * u) * (1 - u) * (1 - u).
Proof. rewrite u_val. lra. Qed.

(** ** The near bound. *)

Theorem near_bound_sound : forall plane o d, binary64 plane -> binary64 o -> d <> 0 ->
  bpow radix2 (-1022) <= Rabs (/ d) ->
  let T := (plane - o) / d in
  let near := near_bound (slab_parameter plane o (RN (/ d))) in
  (0 <= T -> near <= T) /\ (T < 0 -> near <= 0).
Proof.
  intros plane o d Hp Ho Hd Hinv T near.
  destruct (product_form plane o d Hp Ho Hd Hinv) as [e1 [e2 [He1 [He2 Ey]]]].
  pose proof (factor_bounds e1 e2 He1 He2) as [Flo Fhi].
  set (F := (1 + e1) * (1 + e2)) in *.
  pose proof u_small as Hu. pose proof eta_pos as Heta. pose proof tau_eta as Htau.
  destruct factors_u as [Klo _].
  set (y := RN (plane - o) * RN (/ d)) in *.
  fold T in Ey.
  unfold near, near_bound, slab_parameter. fold y.
  set (K := ray_box_near_factor) in *.
  set (p := RN y). set (a := RN (p * K)).
  assert (HK : 0 <= K) by lra.
  assert (HF : 0 <= F) by (eapply Rle_trans; [|exact Flo]; apply Rmult_le_pos; lra).
  split.
  - intros HT.
    assert (Hy0 : 0 <= y) by (rewrite Ey; apply Rmult_le_pos; assumption).
    assert (Hy1 : y <= T * ((1 + u) * (1 + u))) by (rewrite Ey; apply Rmult_le_compat_l; assumption).
    assert (Hp0 : 0 <= p) by (apply RN_nonneg; exact Hy0).
    assert (Hpy : p <= y * (1 + u) + eta).
    { pose proof (RN_err y) as E. rewrite (Rabs_nonneg_eq y) in E by lra. apply Rabs_bounds in E. unfold p. lra. }
    assert (Hp1 : p <= T * ((1 + u) * (1 + u)) * (1 + u) + eta).
    { assert (y * (1 + u) <= T * ((1 + u) * (1 + u)) * (1 + u)) by (apply Rmult_le_compat_r; lra). lra. }
    assert (Hq : 0 <= p * K) by (apply Rmult_le_pos; assumption).
    assert (Ha : a <= p * K * (1 + u) + eta).
    { pose proof (RN_err (p * K)) as E. rewrite (Rabs_nonneg_eq (p * K)) in E by exact Hq.
      apply Rabs_bounds in E. unfold a. lra. }
    assert (Ha1 : a <= (T * ((1 + u) * (1 + u)) * (1 + u) + eta) * K * (1 + u) + eta).
    { assert (p * K * (1 + u) <= (T * ((1 + u) * (1 + u)) * (1 + u) + eta) * K * (1 + u)).
      { apply Rmult_le_compat_r; [lra|]. apply Rmult_le_compat_r; assumption. }
      lra. }
    destruct (Rle_or_lt (a - ray_box_absolute) 0) as [Neg|Pos].
    + eapply Rle_trans; [apply RN_le; exact Neg|]. rewrite RN_0. exact HT.
    + pose proof (RN_minus_err a ray_box_absolute (binary64_RN _) binary64_tau) as E.
      rewrite (Rabs_nonneg_eq (a - ray_box_absolute)) in E by lra. apply Rabs_bounds in E.
      (* RN(a − τ) ≤ (a − τ)(1 + u) ≤ T·(K(1 + u)^5) + (η·K(1 + u) + η − τ)(1 + u) ≤ T *)
      assert (Hat : (a - ray_box_absolute) * (1 + u) <=
                    ((T * ((1 + u) * (1 + u)) * (1 + u) + eta) * K * (1 + u) + eta - ray_box_absolute) * (1 + u))
        by (apply Rmult_le_compat_r; lra).
      assert (Split : ((T * ((1 + u) * (1 + u)) * (1 + u) + eta) * K * (1 + u) + eta - ray_box_absolute) * (1 + u) =
                      T * ((1 + u) * (1 + u) * (1 + u) * K * (1 + u) * (1 + u)) +
                      (eta * (K * (1 + u)) + eta - ray_box_absolute) * (1 + u)) by ring.
      assert (Hc : T * ((1 + u) * (1 + u) * (1 + u) * K * (1 + u) * (1 + u)) <= T).
      { rewrite Klo. rewrite <- (Rmult_1_r T) at 2. apply Rmult_le_compat_l; [exact HT|]. apply near_margin. }
      assert (HK2 : K * (1 + u) <= 2) by (rewrite Klo, u_val; lra).
      assert (Hconst : eta * (K * (1 + u)) <= eta * 2) by (apply Rmult_le_compat_l; lra).
      assert (Hneg : (eta * (K * (1 + u)) + eta - ray_box_absolute) * (1 + u) <= 0)
        by (apply mult_nonpos_nonneg; lra).
      lra.
  - intros HT.
    assert (Hy : y <= 0) by (rewrite Ey; apply mult_nonpos_nonneg; lra).
    assert (Hp0 : p <= 0) by (unfold p; rewrite <- RN_0; now apply RN_le).
    assert (Hq : p * K <= 0) by (apply mult_nonpos_nonneg; lra).
    assert (Ha : a <= 0) by (unfold a; rewrite <- RN_0; now apply RN_le).
    rewrite <- RN_0. apply RN_le. lra.
Qed.

(** ** The far bound. *)

Theorem far_bound_sound : forall plane o d, binary64 plane -> binary64 o -> d <> 0 ->
  bpow radix2 (-1022) <= Rabs (/ d) ->
  let T := (plane - o) / d in
  0 <= T -> T <= far_bound (slab_parameter plane o (RN (/ d))).
Proof.
  intros plane o d Hp Ho Hd Hinv T HT.
  destruct (product_form plane o d Hp Ho Hd Hinv) as [e1 [e2 [He1 [He2 Ey]]]].
  pose proof (factor_bounds e1 e2 He1 He2) as [Flo Fhi].
  set (F := (1 + e1) * (1 + e2)) in *.
  pose proof u_small as Hu. pose proof eta_pos as Heta. pose proof tau_eta as Htau.
  destruct factors_u as [_ Khi].
  set (y := RN (plane - o) * RN (/ d)) in *.
  fold T in Ey.
  unfold far_bound, slab_parameter. fold y.
  set (K := ray_box_far_factor) in *.
  set (p := RN y). set (b := RN (p * K)).
  assert (HK : 0 <= K) by lra.
  assert (Hy1 : T * ((1 - u) * (1 - u)) <= y) by (rewrite Ey; apply Rmult_le_compat_l; assumption).
  assert (Hy0 : 0 <= y) by (eapply Rle_trans; [|exact Hy1]; apply Rmult_le_pos; [exact HT|]; apply Rmult_le_pos; lra).
  assert (Hp0 : 0 <= p) by (apply RN_nonneg; exact Hy0).
  assert (Hpy : y * (1 - u) - eta <= p).
  { pose proof (RN_err y) as E. rewrite (Rabs_nonneg_eq y) in E by lra. apply Rabs_bounds in E. unfold p. lra. }
  assert (Hp1 : T * ((1 - u) * (1 - u)) * (1 - u) - eta <= p).
  { assert (T * ((1 - u) * (1 - u)) * (1 - u) <= y * (1 - u)) by (apply Rmult_le_compat_r; lra). lra. }
  assert (Hq : 0 <= p * K) by (apply Rmult_le_pos; assumption).
  assert (Hb : p * K * (1 - u) - eta <= b).
  { pose proof (RN_err (p * K)) as E. rewrite (Rabs_nonneg_eq (p * K)) in E by exact Hq.
    apply Rabs_bounds in E. unfold b. lra. }
  assert (Hb1 : (T * ((1 - u) * (1 - u)) * (1 - u) - eta) * K * (1 - u) - eta <= b).
  { assert ((T * ((1 - u) * (1 - u)) * (1 - u) - eta) * K * (1 - u) <= p * K * (1 - u)).
    { apply Rmult_le_compat_r; [lra|]. apply Rmult_le_compat_r; assumption. }
    lra. }
  assert (Hb0 : 0 <= b) by (apply RN_nonneg; exact Hq).
  pose proof (RN_plus_err b ray_box_absolute (binary64_RN _) binary64_tau) as E.
  rewrite (Rabs_nonneg_eq (b + ray_box_absolute)) in E by lra. apply Rabs_bounds in E.
  (* RN(b + τ) ≥ (b + τ)(1 − u) ≥ T·(K(1 − u)^5) + (τ − η·K(1 − u) − η)(1 − u) ≥ T *)
  assert (Hbt : ((T * ((1 - u) * (1 - u)) * (1 - u) - eta) * K * (1 - u) - eta + ray_box_absolute) * (1 - u) <=
                (b + ray_box_absolute) * (1 - u)) by (apply Rmult_le_compat_r; lra).
  assert (Split : ((T * ((1 - u) * (1 - u)) * (1 - u) - eta) * K * (1 - u) - eta + ray_box_absolute) * (1 - u) =
                  T * ((1 - u) * (1 - u) * (1 - u) * K * (1 - u) * (1 - u)) +
                  (ray_box_absolute - eta * (K * (1 - u)) - eta) * (1 - u)) by ring.
  assert (Hc : T <= T * ((1 - u) * (1 - u) * (1 - u) * K * (1 - u) * (1 - u))).
  { rewrite Khi. rewrite <- (Rmult_1_r T) at 1. apply Rmult_le_compat_l; [exact HT|]. apply far_margin. }
  assert (HK2 : K * (1 - u) <= 2) by (rewrite Khi, u_val; lra).
  assert (Hconst : eta * (K * (1 - u)) <= eta * 2) by (apply Rmult_le_compat_l; lra).
  assert (Hpos : 0 <= (ray_box_absolute - eta * (K * (1 - u)) - eta) * (1 - u)) by (apply Rmult_le_pos; lra).
  lra.
Qed.

(** ** One axis: every t* ≥ 0 in the exact slab lies between the two bounds. *)

Theorem slab_sound : forall near_plane far_plane o d t, binary64 near_plane -> binary64 far_plane ->
  binary64 o -> d <> 0 -> bpow radix2 (-1022) <= Rabs (/ d) -> 0 <= t ->
  (near_plane - o) / d <= t <= (far_plane - o) / d ->
  near_bound (slab_parameter near_plane o (RN (/ d))) <= t /\
  t <= far_bound (slab_parameter far_plane o (RN (/ d))).
Proof.
  intros np fp o d t Hn Hf Ho Hd Hinv Ht [Hlo Hhi]. split.
  - destruct (near_bound_sound np o d Hn Ho Hd Hinv) as [Pos Neg].
    destruct (Rle_or_lt 0 ((np - o) / d)) as [H|H].
    + eapply Rle_trans; [apply Pos; exact H | exact Hlo].
    + eapply Rle_trans; [apply Neg; exact H | exact Ht].
  - eapply Rle_trans; [exact Hhi|]. apply far_bound_sound; try assumption. lra.
Qed.

(** ** The three axes together: t0 = max(t_min, the near bounds), t1 = min(t_max, the far bounds), an axis
    left out (its NaN bounds) modelled as [None], which the C++ comparisons ignore. *)

Definition bounded_below_by (t : R) (b : option R) : Prop := match b with Some v => v <= t | None => True end.
Definition bounded_above_by (t : R) (b : option R) : Prop := match b with Some v => t <= v | None => True end.

Definition max_step (t0 : R) (b : option R) : R := match b with Some v => if Rlt_bool t0 v then v else t0 | None => t0 end.
Definition min_step (t1 : R) (b : option R) : R := match b with Some v => if Rlt_bool v t1 then v else t1 | None => t1 end.

Theorem ray_box_sound : forall (near far : list (option R)) t_min t_max t,
  t_min <= t <= t_max -> Forall (bounded_below_by t) near -> Forall (bounded_above_by t) far ->
  fold_left max_step near t_min <= t /\ t <= fold_left min_step far t_max.
Proof.
  intros near far t_min t_max t [Hlo Hhi] Hn Hf. split.
  - revert t_min Hlo Hhi. induction Hn as [|b rest Hb Hrest IH]; intros t_min Hlo Hhi; simpl; [exact Hlo|].
    apply IH; [|exact Hhi].
    destruct b as [v|]; simpl in *; [|exact Hlo].
    destruct (Rlt_bool_spec t_min v); assumption.
  - revert t_max Hlo Hhi. induction Hf as [|b rest Hb Hrest IH]; intros t_max Hlo Hhi; simpl; [exact Hhi|].
    apply IH; [exact Hlo|].
    destruct b as [v|]; simpl in *; [|exact Hhi].
    destruct (Rlt_bool_spec v t_max); assumption.
Qed.

(** ** Boxes stored in binary32, rounded outward.

    The BVH stores each child box in binary32: lo' is a binary32 value ≤ lo and hi' a binary32 value ≥ hi,
    for the exact double box [lo, hi] (the C++ rounds with (float)x, then steps with nextafterf until the
    inequality holds). At query time each bound is converted exactly to double and the slab test above runs
    on it. Every binary32 value is a double ([binary32_binary64], Model.v), and the outward box's slab contains the
    exact box's ([outward_slab_order]), so [slab_sound_outward]: the test on the outward box never rejects a
    t* ≥ 0 in the exact box's slab. The exact faces enter only through the order, so they need not be
    doubles. *)

(** The faces in the ray's crossing order, as the C++ picks them by the sign bit of d: near = lo, far = hi
    when d > 0, near = hi, far = lo when d < 0. Rounding lo down and hi up moves the near face against the
    ray's direction and the far face along it. *)
Definition near_face (d lo hi : R) : R := if Rlt_bool d 0 then hi else lo.
Definition far_face (d lo hi : R) : R := if Rlt_bool d 0 then lo else hi.

Lemma outward_faces : forall d lo hi lo' hi', lo' <= lo -> hi <= hi' ->
  (0 < d -> near_face d lo' hi' <= near_face d lo hi /\ far_face d lo hi <= far_face d lo' hi') /\
  (d < 0 -> near_face d lo hi <= near_face d lo' hi' /\ far_face d lo' hi' <= far_face d lo hi).
Proof.
  intros d lo hi lo' hi' Hlo Hhi. unfold near_face, far_face.
  split; intros Hd; destruct (Rlt_bool_spec d 0); lra.
Qed.

(** Moved outward, the near face's parameter decreases and the far face's increases, for either sign of d. *)
Lemma outward_slab_order : forall near_plane far_plane near' far' o d, d <> 0 ->
  (0 < d -> near' <= near_plane /\ far_plane <= far') ->
  (d < 0 -> near_plane <= near' /\ far' <= far_plane) ->
  (near' - o) / d <= (near_plane - o) / d /\ (far_plane - o) / d <= (far' - o) / d.
Proof.
  intros np fp n' f' o d Hd Hpos Hneg. unfold Rdiv.
  destruct (Rlt_or_le 0 d) as [P|N].
  - destruct (Hpos P) as [H1 H2]. assert (I : 0 < / d) by (apply Rinv_0_lt_compat; exact P). split; nra.
  - assert (N' : d < 0) by lra. destruct (Hneg N') as [H1 H2].
    assert (I : / d < 0) by (apply Rinv_lt_0_compat; exact N'). split; nra.
Qed.

Theorem slab_sound_outward : forall near_plane far_plane near' far' o d t,
  binary32 near' -> binary32 far' -> binary64 o -> d <> 0 -> bpow radix2 (-1022) <= Rabs (/ d) -> 0 <= t ->
  (0 < d -> near' <= near_plane /\ far_plane <= far') ->
  (d < 0 -> near_plane <= near' /\ far' <= far_plane) ->
  (near_plane - o) / d <= t <= (far_plane - o) / d ->
  near_bound (slab_parameter near' o (RN (/ d))) <= t /\
  t <= far_bound (slab_parameter far' o (RN (/ d))).
Proof.
  intros np fp n' f' o d t Hn Hf Ho Hd Hinv Ht Hpos Hneg [Hlo Hhi].
  destruct (outward_slab_order np fp n' f' o d Hd Hpos Hneg) as [On Of].
  apply slab_sound; try assumption; try (apply binary32_binary64; assumption). lra.
Qed.
