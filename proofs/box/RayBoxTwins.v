(** * The BVH's ray–box test over IEEE-754 binary64, tied to RayBox.v.

    [make_slab_b], [ray_box_axis_b] and [ray_box_entry_b] are kernel/src/box/ray_box.hpp's [make_slabs] (one
    axis), [ray_box_axis] and [ray_box_entry] (and so, lane by lane, [ray_box_entries8]), operation by operation
    in the C++ order, over FloatCore.v's binary64 and the compiled constants [Cpp.ray_box_near_factor],
    [Cpp.ray_box_far_factor], [Cpp.ray_box_absolute], [Cpp.ray_box_min_direction],
    [Cpp.ray_box_max_direction], [Cpp.ray_box_max_parameter] (ConstantsCpp.v, with the lemmas [cpp_ray_box_*]
    that they are Constants.v's values).  The runner (proofs/twins/, group [box]) compares them with the
    compiled C++ bit for bit: [make_slabs] (routine ray_box_setup), the scalar [ray_box_entry] on each of a
    node's eight boxes (ray_box_entry), and [ray_box_entries8] as each instruction set compiles it
    (ray_box_node: mesh_detail::{portable,avx2,avx512}::node_entries) against [ray_box_entries8_b].

    - [near_bound_twin_model], [far_bound_twin_model]: a finite near_lo (far_hi) has finite operands and is
      RayBox.v's [near_bound (slab_parameter plane o inv)] ([far_bound ...]) on their values: nothing
      overflowed, and every operation is the model's RN.
    - [ray_box_axis_twin_model]: with finite near_lo, far_hi, t0, t1, the axis's new t0 and t1 are
      RayBox.v's [max_step] and [min_step] on those values.
    - [make_slab_case_b]: case B of ray_box.hpp's argument read from the bits — a direction component with
      2^-1022 ≤ |d| ≤ 2^1022, a magnitude M that is a non-negative double (or +inf) and the guard passed (the
      inverse is not NaN) — gives a finite inverse RN(1/d), a finite o and M, and for every finite face with
      |face| ≤ M a finite slab parameter p = RN(RN(face − o)·inv) with |p| ≤ 2^1022 (ray_box.hpp's B2).
    - [near_bound_twin_sound], [far_bound_twin_sound]: in case B, near_lo and far_hi are finite (no operation
      overflows) and satisfy RayBox.v's [near_bound_sound] and [far_bound_sound] for the exact slab parameter
      T = (face − o)/d of the input values.
    - [ray_box_axis_twin_sound]: in case B, one axis of the test keeps every t ≥ 0 of the exact slab between
      its t0 and t1 (t0 finite, t1 finite or +inf), as [slab_sound] does in the model; [ray_box_axis_nan]: an
      axis with a NaN inverse (case C) leaves t0 and t1 as they were.
    - [ray_box_entry_twin_sound]: the whole test, every axis in case B with t in its exact slab or left out:
      the box is met (t0 <= t1) and the entry bound is finite and at most t ([ray_box_sound] over the bits).
    - [ray_box_entries8_twin_sound]: the same for a lane of [ray_box_entries8] ([ray_box_entries8_b]: the
      broadcast of the ray and of t_min, t_max turns −0 into +0, which the runner showed: the scalar entry
      of t_min = −0 is −0, the lanes' +0).
    Cases A (d = ±0: ±inf inverse) and C (an axis left out: NaN inverse) are argued in ray_box.hpp; the twins
    compute them too (IEEE infinities and NaN), and the runner checks the C++ against them bit for bit. *)

From Coq Require Import Reals Lra Lia ZArith Bool List.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model FloatCore ConstantsCpp RayBox.
Open Scope R_scope.
Import ListNotations.

(** ** Constants. *)

Definition one_box : float := of_bits 4607182418800017408.  (* 1.0, the numerator of 1.0 / d *)

Lemma one_box_val : B2R one_box = 1.
Proof. float_value one_box. simpl. lra. Qed.

Lemma cpp_ray_box_constants_finite :
  fin Cpp.ray_box_near_factor = true /\ fin Cpp.ray_box_far_factor = true /\ fin Cpp.ray_box_absolute = true /\
  fin Cpp.ray_box_min_direction = true /\ fin Cpp.ray_box_max_direction = true /\
  fin Cpp.ray_box_max_parameter = true /\ fin one_box = true.
Proof. vm_compute. repeat split. Qed.

(** ** The C++ operations, in the source's order. *)

(** [(plane - origin) * inverse] *)
Definition slab_parameter_b (plane origin inverse : float) : float := fmul (fsub plane origin) inverse.
(** [p * bounds::ray_box_near_factor - bounds::ray_box_absolute] *)
Definition near_bound_b (p : float) : float := fsub (fmul p Cpp.ray_box_near_factor) Cpp.ray_box_absolute.
(** [p * bounds::ray_box_far_factor + bounds::ray_box_absolute] *)
Definition far_bound_b (p : float) : float := fadd (fmul p Cpp.ray_box_far_factor) Cpp.ray_box_absolute.

(** [ray_box_axis<V>(near_plane, far_plane, origin, inverse, t0, t1)]: the new (t0, t1), with
    [select(near_lo > t0, near_lo, t0)] and [select(far_hi < t1, far_hi, t1)] (a NaN bound keeps t0, t1). *)
Definition ray_box_axis_b (near far origin inverse t0 t1 : float) : float * float :=
  let near_lo := near_bound_b (slab_parameter_b near origin inverse) in
  let far_hi := far_bound_b (slab_parameter_b far origin inverse) in
  (if flt t0 near_lo then near_lo else t0, if flt far_hi t1 then far_hi else t1).

(** [make_slabs] on one axis: the inverse (±inf for d = ±0, case A; RN(1/d) when 2^-1022 ≤ |d| ≤ 2^1022 and
    the guard RN(RN(M + |o|)·|inv|) ≤ 2^1022 holds, case B; NaN otherwise, case C) and [enters_at_hi], the
    sign bit of d ([std::signbit]; for d not NaN, as every valid ray's). *)
Definition make_slab_b (d o M : float) : float * bool :=
  let a := fabs d in
  let inv :=
    if feq a fzero then B754_infinity (Bsign d)
    else if fle Cpp.ray_box_min_direction a && fle a Cpp.ray_box_max_direction then
      let inv := fdiv one_box d in
      if fle (fmul (fadd M (fabs o)) (fabs inv)) Cpp.ray_box_max_parameter then inv else B754_nan
    else B754_nan in
  (inv, Bsign d).

(** [ray_box_entry(s, box, t0, t1, entry)]: the axes in order, each (origin, inverse, enters_at_hi, lo, hi);
    the near face is hi when the ray enters at the upper face.  Returns (entry, t0 <= t1). *)
Definition ray_box_step_b (t : float * float) (axis : float * float * bool * float * float) : float * float :=
  let '(o, inv, hi_first, lo, hi) := axis in
  if hi_first then ray_box_axis_b hi lo o inv (fst t) (snd t) else ray_box_axis_b lo hi o inv (fst t) (snd t).

Definition ray_box_entry_b (axes : list (float * float * bool * float * float)) (t0 t1 : float) : float * bool :=
  let r := fold_left ray_box_step_b axes (t0, t1) in (fst r, fle (fst r) (snd r)).

(** ** The twins are the model's operations when nothing overflows. *)

Theorem near_bound_twin_model : forall plane origin inverse,
  fin (near_bound_b (slab_parameter_b plane origin inverse)) = true ->
  fin plane = true /\ fin origin = true /\ fin inverse = true /\
  B2R (near_bound_b (slab_parameter_b plane origin inverse)) =
    near_bound (slab_parameter (B2R plane) (B2R origin) (B2R inverse)).
Proof.
  intros plane origin inverse H. unfold near_bound_b, slab_parameter_b in *.
  fin_down. repeat split; try assumption.
  unfold near_bound, slab_parameter. to_model_ops.
  rewrite cpp_ray_box_near_factor, cpp_ray_box_absolute. reflexivity.
Qed.

Theorem far_bound_twin_model : forall plane origin inverse,
  fin (far_bound_b (slab_parameter_b plane origin inverse)) = true ->
  fin plane = true /\ fin origin = true /\ fin inverse = true /\
  B2R (far_bound_b (slab_parameter_b plane origin inverse)) =
    far_bound (slab_parameter (B2R plane) (B2R origin) (B2R inverse)).
Proof.
  intros plane origin inverse H. unfold far_bound_b, slab_parameter_b in *.
  fin_down. repeat split; try assumption.
  unfold far_bound, slab_parameter. to_model_ops.
  rewrite cpp_ray_box_far_factor, cpp_ray_box_absolute. reflexivity.
Qed.

Lemma select_max_model : forall t0 x, fin t0 = true -> fin x = true ->
  fin (if flt t0 x then x else t0) = true /\ B2R (if flt t0 x then x else t0) = max_step (B2R t0) (Some (B2R x)).
Proof.
  intros t0 x F0 Fx. unfold max_step. rewrite flt_val by assumption.
  destruct (Rlt_bool (B2R t0) (B2R x)); split; auto.
Qed.

Lemma select_min_model : forall t1 x, fin t1 = true -> fin x = true ->
  fin (if flt x t1 then x else t1) = true /\ B2R (if flt x t1 then x else t1) = min_step (B2R t1) (Some (B2R x)).
Proof.
  intros t1 x F1 Fx. unfold min_step. rewrite flt_val by assumption.
  destruct (Rlt_bool (B2R x) (B2R t1)); split; auto.
Qed.

(** One axis: with finite bounds and finite t0, t1, the new t0 and t1 are RayBox.v's [max_step] and
    [min_step] (the fold of [ray_box_sound]) on the model's bounds. *)
Theorem ray_box_axis_twin_model : forall near far origin inverse t0 t1,
  fin (near_bound_b (slab_parameter_b near origin inverse)) = true ->
  fin (far_bound_b (slab_parameter_b far origin inverse)) = true -> fin t0 = true -> fin t1 = true ->
  let r := ray_box_axis_b near far origin inverse t0 t1 in
  fin (fst r) = true /\ fin (snd r) = true /\
  B2R (fst r) = max_step (B2R t0) (Some (near_bound (slab_parameter (B2R near) (B2R origin) (B2R inverse)))) /\
  B2R (snd r) = min_step (B2R t1) (Some (far_bound (slab_parameter (B2R far) (B2R origin) (B2R inverse)))).
Proof.
  intros near far origin inverse t0 t1 Fn Ff F0 F1 r.
  destruct (near_bound_twin_model near origin inverse Fn) as [_ [_ [_ Vn]]].
  destruct (far_bound_twin_model far origin inverse Ff) as [_ [_ [_ Vf]]].
  destruct (select_max_model t0 _ F0 Fn) as [G0 W0]. destruct (select_min_model t1 _ F1 Ff) as [G1 W1].
  unfold r, ray_box_axis_b. cbn [fst snd]. rewrite <- Vn, <- Vf. repeat split; assumption.
Qed.

(** ** Case B from the bits: the set-up's guard keeps every operation below 2^1023. *)

(** The three magnitudes of the argument, as multiples of 2^971 (the spacing of the largest doubles). *)
Lemma case_b_powers :
  bpow radix2 1022 = 2251799813685248 * bpow radix2 971 /\
  bpow radix2 1023 = 4503599627370496 * bpow radix2 971 /\
  bpow radix2 1024 = 9007199254740992 * bpow radix2 971 /\
  0 < bpow radix2 971 /\ bpow radix2 (-1022) <= bpow radix2 971.
Proof.
  repeat split.
  - replace 1022%Z with (51 + 971)%Z by lia. rewrite bpow_plus. reflexivity.
  - replace 1023%Z with (52 + 971)%Z by lia. rewrite bpow_plus. reflexivity.
  - replace 1024%Z with (53 + 971)%Z by lia. rewrite bpow_plus. reflexivity.
  - apply bpow_gt_0.
  - apply bpow_le. lia.
Qed.

(** A rounding of a value at most 3·2^1022 in magnitude does not overflow (it is at most the largest double). *)
Lemma RN_below_overflow : forall x, Rabs x <= 3 * bpow radix2 1022 -> Rabs (RN x) < bpow radix2 1024.
Proof.
  intros x H. destruct case_b_powers as [P2 [_ [P4 [Y _]]]].
  pose proof largest_finite_f_val as V.
  assert (L : Rabs (RN x) <= B2R largest_finite_f).
  { rewrite <- RN_abs. rewrite <- (RN_binary64 (B2R largest_finite_f)) by apply binary64_B2R.
    apply RN_le. rewrite V. lra. }
  rewrite V in L. lra.
Qed.

Lemma RN_abs_le : forall x b, binary64 b -> Rabs x <= b -> Rabs (RN x) <= b.
Proof. intros x b B H. rewrite <- RN_abs, <- (RN_binary64 b B). apply RN_le. exact H. Qed.

(** A non-negative value (or NaN) that compares ≤ a finite constant is finite. *)
Lemma fle_nonneg_fin : forall g c, nonneg g -> fin c = true -> fle g c = true -> fin g = true.
Proof.
  intros [sg|[|]| |sg mg eg Hg] [sc|sc| |sc mc ec Hc] [N|N] Fc H; simpl in N, Fc; try discriminate;
    try reflexivity; unfold fle in H; simpl in H; discriminate.
Qed.

Lemma fin_of_range : forall d : float, bpow radix2 (-1022) <= Rabs (B2R d) -> fin d = true.
Proof.
  intros [s|s| |s m e He] R; try reflexivity; simpl in R; rewrite Rabs_R0 in R;
    pose proof (bpow_gt_0 radix2 (-1022)); lra.
Qed.

(** Case B of ray_box.hpp, as hypotheses on the inputs of [make_slabs]: the direction component in
    [2^-1022, 2^1022], the magnitude a non-negative double or +inf (MeshBvh::magnitude()), and the guard
    passed (the inverse is not NaN). *)
Definition case_b (d o M : float) : Prop :=
  bpow radix2 (-1022) <= Rabs (B2R d) <= bpow radix2 1022 /\ nonneg M /\ is_nan (fst (make_slab_b d o M)) = false.

Theorem make_slab_case_b : forall d o M, case_b d o M ->
  let inv := fst (make_slab_b d o M) in
  fin d = true /\ fin o = true /\ fin M = true /\ fin inv = true /\ B2R inv = RN (/ B2R d) /\
  bpow radix2 (-1022) <= Rabs (/ B2R d) /\
  (forall plane, fin plane = true -> Rabs (B2R plane) <= B2R M ->
     fin (slab_parameter_b plane o inv) = true /\ Rabs (B2R (slab_parameter_b plane o inv)) <= bpow radix2 1022 /\
     B2R (slab_parameter_b plane o inv) = slab_parameter (B2R plane) (B2R o) (RN (/ B2R d))).
Proof.
  intros d o M [[Rlo Rhi] [NM Hnan]] inv.
  pose proof (fin_of_range d Rlo) as Fd.
  destruct cpp_ray_box_constants_finite as [_ [_ [_ [Fmin [Fmax [Fpar F1]]]]]].
  pose proof (bpow_gt_0 radix2 (-1022)) as Pm.
  assert (Dnz : B2R d <> 0) by (intros Z; rewrite Z, Rabs_R0 in Rlo; lra).
  assert (Z : feq (fabs d) fzero = false).
  { rewrite feq_val by (try rewrite fabs_fin; easy). rewrite fabs_val. change (B2R fzero) with 0.
    apply Req_bool_false. intros E. rewrite E in Rlo. lra. }
  assert (Lo : fle Cpp.ray_box_min_direction (fabs d) = true).
  { rewrite fle_val by (try rewrite fabs_fin; easy). rewrite fabs_val, cpp_ray_box_min_direction.
    apply Rle_bool_true. exact Rlo. }
  assert (Hi : fle (fabs d) Cpp.ray_box_max_direction = true).
  { rewrite fle_val by (try rewrite fabs_fin; easy). rewrite fabs_val, cpp_ray_box_max_direction.
    apply Rle_bool_true. exact Rhi. }
  unfold inv, make_slab_b in *. rewrite Z, Lo, Hi in *. cbn [andb fst] in *.
  clear inv. set (i := fdiv one_box d) in *.
  set (S := fadd M (fabs o)) in *. set (G := fmul S (fabs i)) in *.
  destruct (fle G Cpp.ray_box_max_parameter) eqn:HG; [|cbn in Hnan; discriminate].
  assert (NG : nonneg G) by (apply fmul_nonneg; [apply fadd_nonneg; [exact NM | apply fabs_nonneg] | apply fabs_nonneg]).
  pose proof (fle_nonneg_fin G _ NG Fpar HG) as FG.
  assert (FG' := FG). unfold G, S in FG'. fin_down.
  assert (FS : fin S = true) by assumption.
  assert (Fi : fin i = true) by assumption.
  assert (Vi : B2R i = RN (/ B2R d)).
  { unfold i. rewrite fdiv_val by assumption. rewrite one_box_val. unfold Rdiv. rewrite Rmult_1_l. reflexivity. }
  assert (Inv : bpow radix2 (-1022) <= Rabs (/ B2R d)).
  { rewrite Rabs_inv. replace (bpow radix2 (-1022)) with (/ bpow radix2 1022) by (rewrite <- bpow_opp; reflexivity).
    apply Rinv_le_contravar; [apply Rabs_pos_lt; exact Dnz | exact Rhi]. }
  assert (VS : B2R S = RN (B2R M + Rabs (B2R o))) by (unfold S; rewrite fadd_val by assumption; now rewrite fabs_val).
  assert (VG : B2R G = RN (B2R S * Rabs (B2R i))) by (unfold G; rewrite fmul_val by assumption; now rewrite fabs_val).
  assert (BG : B2R G <= bpow radix2 1022).
  { rewrite fle_val in HG by assumption. rewrite cpp_ray_box_max_parameter in HG.
    unfold ray_box_max_parameter in HG.
    destruct (Rle_lt_dec (B2R G) (bpow radix2 1022)) as [L|L]; [exact L|].
    rewrite Rle_bool_false in HG by exact L. discriminate. }
  refine (conj Fd (conj _ (conj _ (conj Fi (conj Vi (conj Inv _)))))); try assumption.
  intros plane Fp Bp.
  assert (Bq : Rabs (RN (B2R plane - B2R o)) <= B2R S).
  { rewrite VS, <- RN_abs. apply RN_le. unfold Rminus. eapply Rle_trans; [apply Rabs_triang|].
    rewrite Rabs_Ropp. lra. }
  destruct (fsub_fwd plane o Fp ltac:(assumption)) as [Fq Vq].
  { eapply Rle_lt_trans; [exact Bq|]. eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow]. }
  set (q := fsub plane o) in *.
  assert (Bp' : Rabs (RN (B2R q * B2R i)) <= bpow radix2 1022).
  { eapply Rle_trans; [|exact BG]. rewrite VG, <- RN_abs. apply RN_le. rewrite Rabs_mult.
    apply Rmult_le_compat_r; [apply Rabs_pos|]. rewrite Vq. exact Bq. }
  destruct (fmul_fwd q i Fq Fi) as [Fpq Vpq].
  { eapply Rle_lt_trans; [exact Bp'|]. apply bpow_lt. lia. }
  unfold slab_parameter_b. fold q. repeat split; try assumption.
  - rewrite Vpq. exact Bp'.
  - rewrite Vpq, Vq, Vi. reflexivity.
Qed.

(** From a slab parameter |p| ≤ 2^1022 (ray_box.hpp's B2), the bounds do not overflow: |RN(p·K)| ≤ 2^1023 and
    |RN(p·K) ∓ τ| ≤ 3·2^1022 (B4's last line), and they are the model's. *)
Lemma near_bound_b_finite : forall p, fin p = true -> Rabs (B2R p) <= bpow radix2 1022 ->
  fin (near_bound_b p) = true /\ B2R (near_bound_b p) = near_bound (B2R p).
Proof.
  intros p Fp Bp. destruct case_b_powers as [P2 [P3 [P4 [Y T]]]].
  destruct cpp_ray_box_constants_finite as [FK [_ [Ft _]]].
  destruct factors_u as [Klo _]. pose proof u_small as Hu. pose proof (Rabs_pos (B2R p)) as Ap.
  assert (Ba : Rabs (RN (B2R p * B2R Cpp.ray_box_near_factor)) <= bpow radix2 1023).
  { apply RN_abs_le; [apply binary64_bpow; lia|]. rewrite Rabs_mult, cpp_ray_box_near_factor.
    rewrite (Rabs_nonneg_eq ray_box_near_factor) by lra.
    assert (Rabs (B2R p) * ray_box_near_factor <= Rabs (B2R p)) by (rewrite Klo; nra). lra. }
  destruct (fmul_fwd p Cpp.ray_box_near_factor Fp FK) as [Fa Va].
  { eapply Rle_lt_trans; [exact Ba|]. apply bpow_lt. lia. }
  set (a := fmul p Cpp.ray_box_near_factor) in *.
  assert (Bt : B2R Cpp.ray_box_absolute = bpow radix2 (-1022)) by (rewrite cpp_ray_box_absolute; reflexivity).
  destruct (fsub_fwd a Cpp.ray_box_absolute Fa Ft) as [Fn Vn].
  { apply RN_below_overflow. unfold Rminus. eapply Rle_trans; [apply Rabs_triang|].
    rewrite Rabs_Ropp, Bt, (Rabs_nonneg_eq (bpow radix2 (-1022))) by (apply bpow_ge_0). rewrite Va. lra. }
  unfold near_bound_b. fold a. split; [exact Fn|].
  rewrite Vn, Va. unfold near_bound. rewrite cpp_ray_box_near_factor, cpp_ray_box_absolute. reflexivity.
Qed.

Lemma far_bound_b_finite : forall p, fin p = true -> Rabs (B2R p) <= bpow radix2 1022 ->
  fin (far_bound_b p) = true /\ B2R (far_bound_b p) = far_bound (B2R p).
Proof.
  intros p Fp Bp. destruct case_b_powers as [P2 [P3 [P4 [Y T]]]].
  destruct cpp_ray_box_constants_finite as [_ [FK [Ft _]]].
  destruct factors_u as [_ Khi]. pose proof u_small as Hu. pose proof (Rabs_pos (B2R p)) as Ap.
  assert (Ba : Rabs (RN (B2R p * B2R Cpp.ray_box_far_factor)) <= bpow radix2 1023).
  { apply RN_abs_le; [apply binary64_bpow; lia|]. rewrite Rabs_mult, cpp_ray_box_far_factor.
    rewrite (Rabs_nonneg_eq ray_box_far_factor) by lra.
    assert (Rabs (B2R p) * ray_box_far_factor <= 2 * Rabs (B2R p)) by (rewrite Khi; nra). lra. }
  destruct (fmul_fwd p Cpp.ray_box_far_factor Fp FK) as [Fa Va].
  { eapply Rle_lt_trans; [exact Ba|]. apply bpow_lt. lia. }
  set (a := fmul p Cpp.ray_box_far_factor) in *.
  assert (Bt : B2R Cpp.ray_box_absolute = bpow radix2 (-1022)) by (rewrite cpp_ray_box_absolute; reflexivity).
  destruct (fadd_fwd a Cpp.ray_box_absolute Fa Ft) as [Fn Vn].
  { apply RN_below_overflow. eapply Rle_trans; [apply Rabs_triang|].
    rewrite Bt, (Rabs_nonneg_eq (bpow radix2 (-1022))) by (apply bpow_ge_0). rewrite Va. lra. }
  unfold far_bound_b. fold a. split; [exact Fn|].
  rewrite Vn, Va. unfold far_bound. rewrite cpp_ray_box_far_factor, cpp_ray_box_absolute. reflexivity.
Qed.

(** ** What the bits certify, in case B: RayBox.v's [near_bound_sound] and [far_bound_sound] for the inverse
    [make_slabs] computed and any finite face within the magnitude M (every face of every box the BVH tests:
    M is the root box's magnitude, rounded outward). *)

Theorem near_bound_twin_sound : forall plane d o M, case_b d o M -> fin plane = true -> Rabs (B2R plane) <= B2R M ->
  let near_lo := near_bound_b (slab_parameter_b plane o (fst (make_slab_b d o M))) in
  let T := (B2R plane - B2R o) / B2R d in
  fin near_lo = true /\ (0 <= T -> B2R near_lo <= T) /\ (T < 0 -> B2R near_lo <= 0).
Proof.
  intros plane d o M C Fp Bp near_lo T.
  assert (Dnz : B2R d <> 0).
  { destruct C as [[Rlo _] _]. intros Z. rewrite Z, Rabs_R0 in Rlo. pose proof (bpow_gt_0 radix2 (-1022)). lra. }
  destruct (make_slab_case_b d o M C) as [Fd [Fo [FM [Fi [Vi [Inv Slab]]]]]].
  destruct (Slab plane Fp Bp) as [Fs [Bs Vs]].
  destruct (near_bound_b_finite _ Fs Bs) as [Fn Vn].
  pose proof (near_bound_sound (B2R plane) (B2R o) (B2R d) (binary64_B2R _) (binary64_B2R _) Dnz Inv) as S.
  cbv zeta in S. unfold near_lo, T. rewrite Vn, Vs. split; [exact Fn | exact S].
Qed.

Theorem far_bound_twin_sound : forall plane d o M, case_b d o M -> fin plane = true -> Rabs (B2R plane) <= B2R M ->
  let far_hi := far_bound_b (slab_parameter_b plane o (fst (make_slab_b d o M))) in
  let T := (B2R plane - B2R o) / B2R d in
  fin far_hi = true /\ (0 <= T -> T <= B2R far_hi).
Proof.
  intros plane d o M C Fp Bp far_hi T.
  assert (Dnz : B2R d <> 0).
  { destruct C as [[Rlo _] _]. intros Z. rewrite Z, Rabs_R0 in Rlo. pose proof (bpow_gt_0 radix2 (-1022)). lra. }
  destruct (make_slab_case_b d o M C) as [Fd [Fo [FM [Fi [Vi [Inv Slab]]]]]].
  destruct (Slab plane Fp Bp) as [Fs [Bs Vs]].
  destruct (far_bound_b_finite _ Fs Bs) as [Fn Vn].
  pose proof (far_bound_sound (B2R plane) (B2R o) (B2R d) (binary64_B2R _) (binary64_B2R _) Dnz Inv) as S.
  cbv zeta in S. unfold far_hi, T. rewrite Vn, Vs. split; [exact Fn | exact S].
Qed.

(** ** One axis of the test, in case B: every t ≥ 0 in the exact slab that the running t0, t1 allow, they
    still allow.  t0 is finite (it starts at t_min); t1 is finite or +inf (t_max may be +inf). *)

Definition allows_from (t : R) (t0 : float) : Prop := fin t0 = true /\ B2R t0 <= t.
Definition allows_to (t : R) (t1 : float) : Prop := t1 = B754_infinity false \/ (fin t1 = true /\ t <= B2R t1).

Theorem ray_box_axis_twin_sound : forall near far d o M t0 t1 t,
  case_b d o M -> fin near = true -> fin far = true -> Rabs (B2R near) <= B2R M -> Rabs (B2R far) <= B2R M ->
  0 <= t -> (B2R near - B2R o) / B2R d <= t <= (B2R far - B2R o) / B2R d ->
  allows_from t t0 -> allows_to t t1 ->
  let r := ray_box_axis_b near far o (fst (make_slab_b d o M)) t0 t1 in
  allows_from t (fst r) /\ allows_to t (snd r).
Proof.
  intros near far d o M t0 t1 t C Fn Ff Bn Bf Ht [Tn Tf] [F0 H0] H1 r.
  destruct (near_bound_twin_sound near d o M C Fn Bn) as [Fl [Lpos Lneg]].
  destruct (far_bound_twin_sound far d o M C Ff Bf) as [Fh Hpos].
  cbv zeta in Lpos, Lneg, Hpos.
  set (near_lo := near_bound_b (slab_parameter_b near o (fst (make_slab_b d o M)))) in *.
  set (far_hi := far_bound_b (slab_parameter_b far o (fst (make_slab_b d o M)))) in *.
  assert (Nl : B2R near_lo <= t).
  { destruct (Rle_or_lt 0 ((B2R near - B2R o) / B2R d)) as [P|N].
    - specialize (Lpos P). lra.
    - specialize (Lneg N). lra. }
  assert (Fh' : t <= B2R far_hi) by (specialize (Hpos ltac:(lra)); lra).
  unfold r, ray_box_axis_b. fold near_lo far_hi. cbn [fst snd]. split.
  - destruct (flt t0 near_lo); split; assumption.
  - destruct (flt far_hi t1); [right; split; assumption | exact H1].
Qed.

(** Case C: an axis whose inverse is NaN is left out (RayBox.v's [None]): t0 and t1 pass unchanged. *)
Lemma ray_box_axis_nan : forall near far origin inverse t0 t1, is_nan inverse = true ->
  ray_box_axis_b near far origin inverse t0 t1 = (t0, t1).
Proof.
  intros near far origin [| | |] t0 t1 N; try discriminate.
  unfold ray_box_axis_b, near_bound_b, far_bound_b, slab_parameter_b, fmul, fsub, fadd.
  destruct (BinarySingleNaN.Bminus mode_NE near origin); destruct (BinarySingleNaN.Bminus mode_NE far origin);
    destruct t0 as [|[|]| |]; destruct t1 as [|[|]| |]; reflexivity.
Qed.

(** ** The whole box: the three axes folded, then [t0 <= t1].  An axis either is left out (NaN inverse) or is
    in case B with both faces finite within M and t in its exact slab. *)

Definition axis_allows (t : R) (axis : float * float * bool * float * float) : Prop :=
  let '(o, inv, hi_first, lo, hi) := axis in
  let near := if hi_first then hi else lo in
  let far := if hi_first then lo else hi in
  is_nan inv = true \/
  exists d M, inv = fst (make_slab_b d o M) /\ case_b d o M /\ fin near = true /\ fin far = true /\
    Rabs (B2R near) <= B2R M /\ Rabs (B2R far) <= B2R M /\
    (B2R near - B2R o) / B2R d <= t <= (B2R far - B2R o) / B2R d.

Lemma ray_box_step_sound : forall t r axis, 0 <= t -> allows_from t (fst r) -> allows_to t (snd r) ->
  axis_allows t axis -> allows_from t (fst (ray_box_step_b r axis)) /\ allows_to t (snd (ray_box_step_b r axis)).
Proof.
  intros t [t0 t1] [[[[o inv] h] lo] hi] Ht H0 H1 A. unfold axis_allows in A. cbn [fst snd] in *.
  unfold ray_box_step_b.
  destruct A as [N | [d [M [E [C [Fn [Ff [Bn [Bf Sl]]]]]]]]].
  - destruct h; rewrite ray_box_axis_nan by exact N; split; assumption.
  - subst inv. destruct h; apply ray_box_axis_twin_sound; assumption.
Qed.

Theorem ray_box_entry_twin_sound : forall axes t0 t1 t, 0 <= t ->
  allows_from t t0 -> allows_to t t1 -> Forall (axis_allows t) axes ->
  let r := ray_box_entry_b axes t0 t1 in
  snd r = true /\ fin (fst r) = true /\ B2R (fst r) <= t.
Proof.
  intros axes t0 t1 t Ht H0 H1 A r.
  assert (Fold : forall axes r0, Forall (axis_allows t) axes -> allows_from t (fst r0) -> allows_to t (snd r0) ->
            allows_from t (fst (fold_left ray_box_step_b axes r0)) /\
            allows_to t (snd (fold_left ray_box_step_b axes r0))).
  { induction axes0 as [|axis rest IH]; intros r0 FA F0 F1; [split; assumption|].
    inversion FA as [|? ? Ax Rest]; subst. cbn [fold_left].
    destruct (ray_box_step_sound t r0 axis Ht F0 F1 Ax). apply IH; assumption. }
  destruct (Fold axes (t0, t1) A H0 H1) as [[Fe Le] U].
  unfold r, ray_box_entry_b. cbn [fst snd].
  set (x := fold_left ray_box_step_b axes (t0, t1)) in *.
  refine (conj _ (conj Fe Le)).
  destruct U as [Inf | [F2 L2]].
  - rewrite Inf. destruct (fst x) as [| | |s m e B]; try discriminate; reflexivity.
  - rewrite fle_val by assumption. apply Rle_bool_true. lra.
Qed.

(** ** The eight lanes: [ray_box_entries8] (one Lanes8, or two Lanes4 or four Lanes2 by instruction set) broadcasts the ray's origin and inverse and t_min, t_max
    to the lanes with [broadcast<V>(x)] = V{} + x, i.e. +0 + x: x itself, except that −0 becomes +0
    (TriangleTwins.v's [bcast] likewise); the faces are converted from binary32 exactly.  So each lane is
    [ray_box_entry_b] on the broadcast values: an entry −0 of the scalar test (t_min = −0 passed through) is +0
    in the lanes, the same real.  [ray_box_entries8_twin_sound]: the lanes keep the guarantee of
    [ray_box_entry_twin_sound]. *)

Definition broadcast_b (x : float) : float := fadd fzero x.

Lemma broadcast_b_eq : forall x, broadcast_b x = match x with B754_zero _ => B754_zero false | _ => x end.
Proof. intros [[|]|[|]| |s m e H]; reflexivity. Qed.

Definition broadcast_axis (axis : float * float * bool * float * float) : float * float * bool * float * float :=
  let '(o, inv, hi_first, lo, hi) := axis in (broadcast_b o, broadcast_b inv, hi_first, lo, hi).

Definition ray_box_entries8_b (axes : list (float * float * bool * float * float)) (t0 t1 : float) : float * bool :=
  ray_box_entry_b (map broadcast_axis axes) (broadcast_b t0) (broadcast_b t1).

Lemma broadcast_b_fin : forall x, fin (broadcast_b x) = fin x.
Proof. intros x. rewrite broadcast_b_eq. destruct x; reflexivity. Qed.

Lemma broadcast_b_val : forall x, B2R (broadcast_b x) = B2R x.
Proof. intros x. rewrite broadcast_b_eq. destruct x; reflexivity. Qed.

Lemma broadcast_b_nan : forall x, is_nan (broadcast_b x) = is_nan x.
Proof. intros x. rewrite broadcast_b_eq. destruct x; reflexivity. Qed.

Lemma broadcast_b_nonzero : forall x, B2R x <> 0 -> broadcast_b x = x.
Proof. intros [s|s| |s m e H] N; try reflexivity. elim N. reflexivity. Qed.

Lemma make_slab_broadcast : forall d o M, make_slab_b d (broadcast_b o) M = make_slab_b d o M.
Proof.
  intros d o M. unfold make_slab_b. replace (fabs (broadcast_b o)) with (fabs o); [reflexivity|].
  rewrite broadcast_b_eq. destruct o as [[|]| | |]; reflexivity.
Qed.

Theorem ray_box_entries8_twin_sound : forall axes t0 t1 t, 0 <= t ->
  allows_from t t0 -> allows_to t t1 -> Forall (axis_allows t) axes ->
  let r := ray_box_entries8_b axes t0 t1 in
  snd r = true /\ fin (fst r) = true /\ B2R (fst r) <= t.
Proof.
  intros axes t0 t1 t Ht [F0 L0] H1 A r. apply ray_box_entry_twin_sound.
  - exact Ht.
  - split; [rewrite broadcast_b_fin; exact F0 | rewrite broadcast_b_val; exact L0].
  - destruct H1 as [E | [F1 L1]]; [left; rewrite E; reflexivity |].
    right. split; [rewrite broadcast_b_fin; exact F1 | rewrite broadcast_b_val; exact L1].
  - apply Forall_map. eapply Forall_impl; [|exact A].
    intros [[[[o inv] h] lo] hi] Ax. unfold axis_allows in *. cbn [broadcast_axis].
    destruct Ax as [N | [d [M [E [C [Fn [Ff [Bn [Bf Sl]]]]]]]]].
    + left. rewrite broadcast_b_nan. exact N.
    + right. exists d, M.
      destruct (make_slab_case_b d o M C) as [_ [_ [_ [Fi [Vi [Inv _]]]]]].
      assert (Nz : B2R inv <> 0).
      { subst inv. rewrite Vi. intros Z.
        assert (P : bpow radix2 (-1022) <= Rabs (RN (/ B2R d))).
        { rewrite <- RN_abs. rewrite <- (RN_binary64 (bpow radix2 (-1022))) by (apply binary64_bpow; lia).
          apply RN_le. exact Inv. }
        rewrite Z, Rabs_R0 in P. pose proof (bpow_gt_0 radix2 (-1022)). lra. }
      rewrite (broadcast_b_nonzero inv Nz), broadcast_b_val, make_slab_broadcast.
      unfold case_b in *. rewrite make_slab_broadcast. repeat split; try tauto.
Qed.
