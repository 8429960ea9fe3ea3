(** * The fast paths' lanes are the scalar forms, so they certify where the scalar forms do (liveness).

    The lane forms of kernel/src/triangle/ray_triangle_stages.hpp and ray_triangle_cascade.cpp differ from
    the scalar [triangle_filter_values] / [triangle_compensated_values] in three ways only, each twinned in
    TriangleTwins.v:
    - [triangle_relation_lanes] broadcasts d ([bcast]: +0 ⊕ x, which turns −0 into +0), lane 3 being the
      π form seen from a;
    - [triangle_compensated_lanes] broadcasts o for ê_b, ê_c (lanes 0–2 and num's lane 3,
      [num_stage2_lane_b]); den is summed from the lanes;
    - fast_triangle_intersection takes its stage-1 signs from stage 2's high parts ([filter_view]: [fview]),
      where a difference is TwoSum(a, −b).hi = a ⊕ (−b) and stage 1 has a ⊖ b.

    None of them changes anything but the sign of a zero: [zn] forgets a zero's sign, every IEEE operation
    the twins use maps [zn]-equal operands to [zn]-equal results (the [zn_*] lemmas, by the cases of Flocq's
    [Bplus], [Bminus], [Bmult], [Bfma], [Babs], [Bopp]), a ⊖ b and a ⊕ (−b) are [zn]-equal, and the
    comparisons [flt], [fle] do not see a zero's sign.  So, for every 64-bit pattern of every input:
    - [triangle_pi_relation_lane_is_scalar]: a lane of [triangle_relation_lanes] decides as the scalar stage 1;
    - [triangle_pi_compensated_lane_is_scalar], [triangle_num_compensated_lane_is_scalar],
      [triangle_den_compensated_lane_is_scalar]: a lane of [triangle_compensated_lanes] (and den from them)
      gives the scalar stage 2's enclosure up to zero signs, hence the same [enclosure_sign];
    - [triangle_pi_view_lane_is_scalar], [triangle_num_view_lane_is_scalar], [triangle_den_view_lane_is_scalar]:
      the filter sign of a lane's stage-1 view is the scalar stage 1's.
    The liveness of the lane forms is then TriangleLiveness.v's, unchanged ([triangle_*_lane_live]). *)

From Coq Require Import Reals ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model FloatCore ConstantsCpp PlaneTwins TriangleFilter TriangleTwins TriangleLiveness.

(** ** Zeros without their sign *)

Definition zn (x : float) : float := match x with B754_zero _ => B754_zero false | _ => x end.

Lemma zn_fadd : forall x y, zn (fadd x y) = zn (fadd (zn x) (zn y)).
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; try reflexivity; destruct sx; try destruct sy; reflexivity.
Qed.

Lemma zn_fsub : forall x y, zn (fsub x y) = zn (fsub (zn x) (zn y)).
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; try reflexivity; destruct sx; try destruct sy; reflexivity.
Qed.

Lemma zn_fmul : forall x y, zn (fmul x y) = zn (fmul (zn x) (zn y)).
Proof. intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; reflexivity. Qed.

Lemma zn_fabs : forall x, fabs x = fabs (zn x).
Proof. intros [s|s| |s m e H]; reflexivity. Qed.

Lemma zn_fneg : forall x, zn (fneg x) = zn (fneg (zn x)).
Proof. intros [s|s| |s m e H]; reflexivity. Qed.

Lemma zn_ffma : forall x y z, zn (ffma x y z) = zn (ffma (zn x) (zn y) (zn z)).
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy] [sz|sz| |sz mz ez Hz]; cbn [zn];
    try reflexivity; destruct sx; destruct sy; destruct sz; reflexivity.
Qed.

(** a ⊖ b and a ⊕ (−b): the same bits up to a zero's sign (in fact the same bits). *)
Lemma zn_fsub_fadd : forall x y, zn (fsub x y) = zn (fadd x (fneg y)).
Proof. intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; reflexivity. Qed.

Lemma zn_flt : forall x y, flt x y = flt (zn x) (zn y).
Proof. intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; reflexivity. Qed.

Lemma zn_fle : forall x y, fle x y = fle (zn x) (zn y).
Proof. intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; reflexivity. Qed.

(** Congruence: [zn]-equal operands give [zn]-equal results. *)
Lemma fadd_z : forall x x' y y', zn x = zn x' -> zn y = zn y' -> zn (fadd x y) = zn (fadd x' y').
Proof. intros x x' y y' X Y. rewrite (zn_fadd x y), (zn_fadd x' y'), X, Y. reflexivity. Qed.
Lemma fsub_z : forall x x' y y', zn x = zn x' -> zn y = zn y' -> zn (fsub x y) = zn (fsub x' y').
Proof. intros x x' y y' X Y. rewrite (zn_fsub x y), (zn_fsub x' y'), X, Y. reflexivity. Qed.
Lemma fmul_z : forall x x' y y', zn x = zn x' -> zn y = zn y' -> zn (fmul x y) = zn (fmul x' y').
Proof. intros x x' y y' X Y. rewrite (zn_fmul x y), (zn_fmul x' y'), X, Y. reflexivity. Qed.
Lemma fabs_z : forall x x', zn x = zn x' -> zn (fabs x) = zn (fabs x').
Proof. intros x x' X. rewrite (zn_fabs x), (zn_fabs x'), X. reflexivity. Qed.
Lemma fneg_z : forall x x', zn x = zn x' -> zn (fneg x) = zn (fneg x').
Proof. intros x x' X. rewrite (zn_fneg x), (zn_fneg x'), X. reflexivity. Qed.
Lemma ffma_z : forall x x' y y' z z', zn x = zn x' -> zn y = zn y' -> zn z = zn z' ->
  zn (ffma x y z) = zn (ffma x' y' z').
Proof. intros x x' y y' z z' X Y Z. rewrite (zn_ffma x y z), (zn_ffma x' y' z'), X, Y, Z. reflexivity. Qed.
Lemma flt_z : forall x x' y y', zn x = zn x' -> zn y = zn y' -> flt x y = flt x' y'.
Proof. intros x x' y y' X Y. rewrite (zn_flt x y), (zn_flt x' y'), X, Y. reflexivity. Qed.
Lemma fle_z : forall x x' y y', zn x = zn x' -> zn y = zn y' -> fle x y = fle x' y'.
Proof. intros x x' y y' X Y. rewrite (zn_fle x y), (zn_fle x' y'), X, Y. reflexivity. Qed.
Lemma fsub_fadd_z : forall x x' y y', zn x = zn x' -> zn y = zn y' -> zn (fsub x y) = zn (fadd x' (fneg y')).
Proof. intros x x' y y' X Y. rewrite zn_fsub_fadd. apply fadd_z; [exact X | apply fneg_z; exact Y]. Qed.

(** Only syntactically equal sides are closed by [reflexivity] (no conversion of twin terms). *)
Ltac zstep :=
  first [ assumption
        | match goal with |- ?a = ?a => reflexivity end
        | apply fadd_z | apply fsub_z | apply fmul_z | apply ffma_z | apply fabs_z | apply fneg_z ].
Ltac zauto := repeat zstep.

(** ** Stage 1: [FilterTerm]s *)

Definition zF (t t' : FTermB) : Prop := zn (fvb t) = zn (fvb t') /\ zn (fmb t) = zn (fmb t').

Lemma leaf_mul_z : forall y y' z z', zn y = zn y' -> zn z = zn z' -> zF (leaf_mul_b y z) (leaf_mul_b y' z').
Proof. intros. unfold zF, leaf_mul_b. cbn [fvb fmb]. split; zauto. Qed.
Lemma leaf_scale_z : forall x x' c c', zn x = zn x' -> zF c c' -> zF (leaf_scale_b x c) (leaf_scale_b x' c').
Proof. intros x x' c c' X [V M]. unfold zF, leaf_scale_b. cbn [fvb fmb]. split; zauto. Qed.
Lemma term_add_z : forall a a' b b', zF a a' -> zF b b' -> zF (term_add_b a b) (term_add_b a' b').
Proof. intros a a' b b' [Va Ma] [Vb Mb]. unfold zF, term_add_b. cbn [fvb fmb]. split; zauto. Qed.
Lemma term_sub_z : forall a a' b b', zF a a' -> zF b b' -> zF (term_sub_b a b) (term_sub_b a' b').
Proof. intros a a' b b' [Va Ma] [Vb Mb]. unfold zF, term_sub_b. cbn [fvb fmb]. split; zauto. Qed.
(** Stage 2's difference of high parts against stage 1's. *)
Lemma term_subn_z : forall a a' b b', zF a a' -> zF b b' -> zF (term_subn_b a b) (term_sub_b a' b').
Proof.
  intros a a' b b' [Va Ma] [Vb Mb]. unfold zF, term_subn_b, term_sub_b. cbn [fvb fmb].
  split; [symmetry; apply fsub_fadd_z; symmetry; assumption | zauto].
Qed.

Ltac fstep := first [ apply term_add_z | apply term_sub_z | apply term_subn_z | apply leaf_scale_z | apply leaf_mul_z
                    | assumption ].

Lemma det3_z : forall x0 x1 x2 y0 y1 y2 z0 z1 z2 x0' x1' x2' y0' y1' y2' z0' z1' z2',
  zn x0 = zn x0' -> zn x1 = zn x1' -> zn x2 = zn x2' -> zn y0 = zn y0' -> zn y1 = zn y1' -> zn y2 = zn y2' ->
  zn z0 = zn z0' -> zn z1 = zn z1' -> zn z2 = zn z2' ->
  zF (det3_b x0 x1 x2 y0 y1 y2 z0 z1 z2) (det3_b x0' x1' x2' y0' y1' y2' z0' z1' z2').
Proof. intros. unfold det3_b. repeat fstep. Qed.

Lemma det3n_z : forall x0 x1 x2 y0 y1 y2 z0 z1 z2 x0' x1' x2' y0' y1' y2' z0' z1' z2',
  zn x0 = zn x0' -> zn x1 = zn x1' -> zn x2 = zn x2' -> zn y0 = zn y0' -> zn y1 = zn y1' -> zn y2 = zn y2' ->
  zn z0 = zn z0' -> zn z1 = zn z1' -> zn z2 = zn z2' ->
  zF (det3n_b x0 x1 x2 y0 y1 y2 z0 z1 z2) (det3_b x0' x1' x2' y0' y1' y2' z0' z1' z2').
Proof. intros. unfold det3n_b, det3_b. repeat fstep. Qed.

(** The filter's decision reads its operands up to a zero's sign. *)
Lemma det3_filter_lanes_z : forall t t' C A A', zF t t' -> zn A = zn A' ->
  det3_filter_lanes_b t C A = det3_filter_lanes_b t' C A'.
Proof.
  intros t t' C A A' [V M] HA. unfold det3_filter_lanes_b.
  assert (B : zn (fadd (fmul C (fmb t)) A) = zn (fadd (fmul C (fmb t')) A')) by zauto.
  f_equal; apply flt_z; zauto.
Qed.

(** ** The query's vectors *)

Definition zV (v v' : TVec) : Prop := zn (tx v) = zn (tx v') /\ zn (ty v) = zn (ty v') /\ zn (tz v) = zn (tz v').

Lemma zV_refl : forall v, zV v v.
Proof. intros. repeat split. Qed.

(** [broadcast]: +0 ⊕ x is x up to a zero's sign. *)
Lemma bcast_f_zn : forall x, zn (fadd fzero x) = zn x.
Proof. intros [s|s| |s m e H]; try destruct s; reflexivity. Qed.

Lemma bcast_z : forall v, zV (bcast v) v.
Proof. intros [x y z]. unfold zV, bcast. cbn [tx ty tz]. repeat split; apply bcast_f_zn. Qed.

Lemma tsub_z : forall v v' o o', zV v v' -> zV o o' -> zV (tsub v o) (tsub v' o').
Proof. intros v v' o o' [X [Y Z]] [X' [Y' Z']]. unfold zV, tsub. cbn [tx ty tz]. repeat split; zauto. Qed.

Lemma absolute_bv_z : forall x x', zV x x' -> zn (absolute_bv x) = zn (absolute_bv x').
Proof. intros x x' [X [Y Z]]. unfold absolute_bv, absolute_term_b. zauto. Qed.

Lemma det3_bv_z : forall x y z x' y' z', zV x x' -> zV y y' -> zV z z' -> zF (det3_bv x y z) (det3_bv x' y' z').
Proof.
  intros x y z x' y' z' [X0 [X1 X2]] [Y0 [Y1 Y2]] [Z0 [Z1 Z2]]. unfold det3_bv. apply det3_z; assumption.
Qed.

Lemma pi_stage1_z : forall o d p q o' d' p' q', zV o o' -> zV d d' -> zV p p' -> zV q q' ->
  zF (pi_stage1_b o d p q) (pi_stage1_b o' d' p' q').
Proof. intros. unfold pi_stage1_b. apply det3_bv_z; try apply tsub_z; assumption. Qed.

(** ** [triangle_relation_lanes]: d broadcast *)

(** Lanes 0–2 (and lane 3, the instance o := a, (p, q) := (b, c)): the scalar stage 1's decision, for every
    bit pattern and every constant C. *)
Theorem triangle_pi_relation_lane_is_scalar : forall (o d p q : TVec) (C : float),
  det3_filter_lanes_b (pi_stage1_b o (bcast d) p q) C (absolute_bv (bcast d)) =
  det3_filter_lanes_b (pi_stage1_b o d p q) C (absolute_bv d).
Proof.
  intros. apply det3_filter_lanes_z.
  - apply pi_stage1_z; first [apply bcast_z | apply zV_refl].
  - apply absolute_bv_z, bcast_z.
Qed.

(** ** Stage 2: [CompensatedTerm]s *)

Definition zC (t t' : CTermB) : Prop :=
  zn (chb t) = zn (chb t') /\ zn (clb t) = zn (clb t') /\ zn (cmb t) = zn (cmb t').

Lemma two_sum_z : forall a a' b b', zn a = zn a' -> zn b = zn b' ->
  zn (fst (two_sum_b a b)) = zn (fst (two_sum_b a' b')) /\ zn (snd (two_sum_b a b)) = zn (snd (two_sum_b a' b')).
Proof. intros. unfold two_sum_b. cbn [fst snd]. split; zauto. Qed.

Lemma cleaf_mul_z : forall yh yl zh zl yh' yl' zh' zl', zn yh = zn yh' -> zn yl = zn yl' -> zn zh = zn zh' ->
  zn zl = zn zl' -> zC (cleaf_mul_b yh yl zh zl) (cleaf_mul_b yh' yl' zh' zl').
Proof. intros. unfold zC, cleaf_mul_b, product_low_part_b. cbn [chb clb cmb]. repeat split; zauto. Qed.

Lemma cleaf_scale_z : forall xh xl c xh' xl' c', zn xh = zn xh' -> zn xl = zn xl' -> zC c c' ->
  zC (cleaf_scale_b xh xl c) (cleaf_scale_b xh' xl' c').
Proof.
  intros xh xl c xh' xl' c' X L [H [Lc M]]. unfold zC, cleaf_scale_b, product_low_part_b. cbn [chb clb cmb].
  repeat split; zauto.
Qed.

Lemma cterm_add_z : forall a a' b b', zC a a' -> zC b b' -> zC (cterm_add_b a b) (cterm_add_b a' b').
Proof.
  intros a a' b b' [Ha [La Ma]] [Hb [Lb Mb]]. destruct (two_sum_z _ _ _ _ Ha Hb) as [S1 S2].
  unfold zC, cterm_add_b. cbn [chb clb cmb]. repeat split; zauto.
Qed.

Lemma cterm_sub_z : forall a a' b b', zC a a' -> zC b b' -> zC (cterm_sub_b a b) (cterm_sub_b a' b').
Proof.
  intros a a' b b' [Ha [La Ma]] [Hb [Lb Mb]].
  destruct (two_sum_z (chb a) (chb a') (fneg (chb b)) (fneg (chb b')) Ha (fneg_z _ _ Hb)) as [S1 S2].
  unfold zC, cterm_sub_b. cbn [chb clb cmb]. repeat split; zauto.
Qed.

Ltac cstep := first [ apply cterm_add_z | apply cterm_sub_z | apply cleaf_scale_z | apply cleaf_mul_z | assumption ].

Lemma cdet3_z : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2
                       xh0' xl0' xh1' xl1' xh2' xl2' yh0' yl0' yh1' yl1' yh2' yl2' zh0' zl0' zh1' zl1' zh2' zl2',
  zn xh0 = zn xh0' -> zn xl0 = zn xl0' -> zn xh1 = zn xh1' -> zn xl1 = zn xl1' -> zn xh2 = zn xh2' ->
  zn xl2 = zn xl2' -> zn yh0 = zn yh0' -> zn yl0 = zn yl0' -> zn yh1 = zn yh1' -> zn yl1 = zn yl1' ->
  zn yh2 = zn yh2' -> zn yl2 = zn yl2' -> zn zh0 = zn zh0' -> zn zl0 = zn zl0' -> zn zh1 = zn zh1' ->
  zn zl1 = zn zl1' -> zn zh2 = zn zh2' -> zn zl2 = zn zl2' ->
  zC (cdet3_b xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2)
     (cdet3_b xh0' xl0' xh1' xl1' xh2' xl2' yh0' yl0' yh1' yl1' yh2' yl2' zh0' zl0' zh1' zl1' zh2' zl2').
Proof. intros. unfold cdet3_b. repeat cstep. Qed.

Lemma two_diff_z : forall v v' o o', zn v = zn v' -> zn o = zn o' ->
  zn (fst (two_diff_b v o)) = zn (fst (two_diff_b v' o')) /\ zn (snd (two_diff_b v o)) = zn (snd (two_diff_b v' o')).
Proof. intros. unfold two_diff_b. apply two_sum_z; [assumption | apply fneg_z; assumption]. Qed.

Ltac zleaf := first [ match goal with |- ?a = ?a => reflexivity end | assumption ].

Ltac leaves_z :=
  repeat match goal with
  | |- zn (fst (two_diff_b _ _)) = zn (fst (two_diff_b _ _)) => apply two_diff_z; zleaf
  | |- zn (snd (two_diff_b _ _)) = zn (snd (two_diff_b _ _)) => apply two_diff_z; zleaf
  | |- zn ?a = zn ?a => reflexivity
  | |- _ => assumption
  end.

Lemma pi_stage2_z : forall o d p q o' d' p' q', zV o o' -> zV d d' -> zV p p' -> zV q q' ->
  zC (pi_stage2_b o d p q) (pi_stage2_b o' d' p' q').
Proof.
  intros o d p q o' d' p' q' [O0 [O1 O2]] [D0 [D1 D2]] [P0 [P1 P2]] [Q0 [Q1 Q2]].
  unfold pi_stage2_b. cbv zeta. apply cdet3_z; leaves_z.
Qed.

Lemma den_stage2_z : forall o d a b c o' d' a' b' c', zV o o' -> zV d d' -> zV a a' -> zV b b' -> zV c c' ->
  zC (den_stage2_b o d a b c) (den_stage2_b o' d' a' b' c').
Proof.
  intros. unfold den_stage2_b. apply cterm_add_z; [apply cterm_add_z|]; apply pi_stage2_z; assumption.
Qed.

(** Lane 3: TwoDiff(a, o) with the query's o, TwoDiff(b, o'), TwoDiff(c, o') with o' = broadcast(o). *)
Lemma num_stage2_lane_z : forall o a b c, zC (num_stage2_lane_b o a b c) (num_stage2_b o a b c).
Proof.
  intros [ox oy oz] a b c. destruct (bcast_z (TV ox oy oz)) as [O0 [O1 O2]].
  unfold num_stage2_lane_b, num_stage2_b. cbv zeta. apply cdet3_z; leaves_z.
Qed.

Definition zE (e e' : EnclosureB) : Prop :=
  zn (hib e) = zn (hib e') /\ zn (lob e) = zn (lob e') /\ zn (radiusb e) = zn (radiusb e').

Lemma det3_enclosure_z : forall t t' K A A', zC t t' -> zn A = zn A' ->
  zE (det3_enclosure_b t K A) (det3_enclosure_b t' K A').
Proof.
  intros t t' K A A' [H [L M]] HA. unfold zE, det3_enclosure_b. cbn [hib lob radiusb].
  assert (G1 : fle (fabs (chb t)) largest_finite_f = fle (fabs (chb t')) largest_finite_f)
    by (apply fle_z; zauto).
  assert (G2 : fle (fabs (clb t)) largest_finite_f = fle (fabs (clb t')) largest_finite_f)
    by (apply fle_z; zauto).
  rewrite G1, G2. repeat split; try assumption.
  destruct (fle (fabs (chb t')) largest_finite_f && fle (fabs (clb t')) largest_finite_f)%bool; zauto.
Qed.

Lemma enclosure_sign_z : forall e e', zE e e' -> enclosure_sign_lanes_b e = enclosure_sign_lanes_b e'.
Proof.
  intros e e' [H [L R]]. unfold enclosure_sign_lanes_b.
  assert (V : zn (fadd (hib e) (lob e)) = zn (fadd (hib e') (lob e'))) by zauto.
  assert (T : zn (fadd (radiusb e) (radiusb e)) = zn (fadd (radiusb e') (radiusb e'))) by zauto.
  f_equal; apply flt_z; zauto.
Qed.

(** ** [triangle_compensated_lanes]: o broadcast *)

(** Lanes 0–2: the scalar stage 2's enclosure up to zero signs, hence its sign, for every bit pattern. *)
Theorem triangle_pi_compensated_lane_is_scalar : forall (o d p q : TVec) (K A : float),
  zE (det3_enclosure_b (pi_stage2_b (bcast o) d p q) K A) (det3_enclosure_b (pi_stage2_b o d p q) K A) /\
  enclosure_sign_lanes_b (det3_enclosure_b (pi_stage2_b (bcast o) d p q) K A) =
  enclosure_sign_lanes_b (det3_enclosure_b (pi_stage2_b o d p q) K A).
Proof.
  intros. assert (E : zE (det3_enclosure_b (pi_stage2_b (bcast o) d p q) K A) (det3_enclosure_b (pi_stage2_b o d p q) K A)).
  { apply det3_enclosure_z; [apply pi_stage2_z; first [apply bcast_z | apply zV_refl] | reflexivity]. }
  split; [exact E | apply enclosure_sign_z, E].
Qed.

(** den = (lane 0 + lane 1) + lane 2. *)
Theorem triangle_den_compensated_lane_is_scalar : forall (o d a b c : TVec) (K A : float),
  zE (det3_enclosure_b (den_stage2_b (bcast o) d a b c) K A) (det3_enclosure_b (den_stage2_b o d a b c) K A) /\
  enclosure_sign_lanes_b (det3_enclosure_b (den_stage2_b (bcast o) d a b c) K A) =
  enclosure_sign_lanes_b (det3_enclosure_b (den_stage2_b o d a b c) K A).
Proof.
  intros. assert (E : zE (det3_enclosure_b (den_stage2_b (bcast o) d a b c) K A)
                         (det3_enclosure_b (den_stage2_b o d a b c) K A)).
  { apply det3_enclosure_z; [apply den_stage2_z; first [apply bcast_z | apply zV_refl] | reflexivity]. }
  split; [exact E | apply enclosure_sign_z, E].
Qed.

(** Lane 3 (num). *)
Theorem triangle_num_compensated_lane_is_scalar : forall (o a b c : TVec) (K A : float),
  zE (det3_enclosure_b (num_stage2_lane_b o a b c) K A) (det3_enclosure_b (num_stage2_b o a b c) K A) /\
  enclosure_sign_lanes_b (det3_enclosure_b (num_stage2_lane_b o a b c) K A) =
  enclosure_sign_lanes_b (det3_enclosure_b (num_stage2_b o a b c) K A).
Proof.
  intros. assert (E : zE (det3_enclosure_b (num_stage2_lane_b o a b c) K A) (det3_enclosure_b (num_stage2_b o a b c) K A)).
  { apply det3_enclosure_z; [apply num_stage2_lane_z | reflexivity]. }
  split; [exact E | apply enclosure_sign_z, E].
Qed.

(** ** [filter_view]: stage 1 from stage 2's high parts *)

Lemma two_diff_fst_sub_z : forall v v' o o', zn v = zn v' -> zn o = zn o' ->
  zn (fst (two_diff_b v o)) = zn (fsub v' o').
Proof.
  intros v v' o o' V O. change (fst (two_diff_b v o)) with (fadd v (fneg o)).
  symmetry. apply fsub_fadd_z; symmetry; assumption.
Qed.

Lemma pi_view_z : forall o d p q o' d' p' q', zV o o' -> zV d d' -> zV p p' -> zV q q' ->
  zF (fview (pi_stage2_b o d p q)) (pi_stage1_b o' d' p' q').
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [qx qy qz] o' d' p' q' [O0 [O1 O2]] [D0 [D1 D2]] [P0 [P1 P2]] [Q0 [Q1 Q2]].
  unfold pi_stage2_b, pi_stage1_b, det3_bv, tsub. cbn [tx ty tz] in *. rewrite cdet3_view.
  apply det3n_z; first [assumption | apply two_diff_fst_sub_z; assumption].
Qed.

Lemma num_lane_view_z : forall o a b c, zF (fview (num_stage2_lane_b o a b c)) (num_stage1_b o a b c).
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz]. destruct (bcast_z (TV ox oy oz)) as [O0 [O1 O2]].
  unfold num_stage2_lane_b, num_stage1_b, det3_bv, tsub. cbn [tx ty tz] in *. rewrite cdet3_view.
  apply det3n_z; apply two_diff_fst_sub_z; first [assumption | reflexivity].
Qed.

Lemma ehigh_z : forall a o, zn (absolute_bv (ehigh a o)) = zn (absolute_bv (tsub a o)).
Proof.
  intros. apply absolute_bv_z. unfold zV, ehigh, tsub. cbn [tx ty tz].
  repeat split; apply two_diff_fst_sub_z; reflexivity.
Qed.

(** Lanes 0–2 of [triangle_compensated_lanes], their stage-1 view: the scalar stage 1's decision. *)
Theorem triangle_pi_view_lane_is_scalar : forall (o d p q : TVec) (C A : float),
  det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d p q)) C A = det3_filter_lanes_b (pi_stage1_b o d p q) C A.
Proof.
  intros. apply det3_filter_lanes_z; [| reflexivity].
  apply pi_view_z; first [apply bcast_z | apply zV_refl].
Qed.

(** Lane 3 (num) with its absolute term (of the high parts of TwoDiff(a, o)). *)
Theorem triangle_num_view_lane_is_scalar : forall (o a b c : TVec) (C : float),
  det3_filter_lanes_b (fview (num_stage2_lane_b o a b c)) C (absolute_bv (ehigh a o)) =
  det3_filter_lanes_b (num_stage1_b o a b c) C (absolute_bv (tsub a o)).
Proof. intros. apply det3_filter_lanes_z; [apply num_lane_view_z | apply ehigh_z]. Qed.

(** den = (lane 0 + lane 1) + lane 2, its view. *)
Theorem triangle_den_view_lane_is_scalar : forall (o d a b c : TVec) (C A : float),
  det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) C A = det3_filter_lanes_b (den_stage1_b o d a b c) C A.
Proof.
  intros. apply det3_filter_lanes_z; [| reflexivity].
  assert (V : fview (den_stage2_b (bcast o) d a b c) =
              term_add_b (term_add_b (fview (pi_stage2_b (bcast o) d b c)) (fview (pi_stage2_b (bcast o) d c a)))
                         (fview (pi_stage2_b (bcast o) d a b))) by reflexivity.
  rewrite V. unfold den_stage1_b.
  apply term_add_z; [apply term_add_z|]; apply pi_view_z; first [apply bcast_z | apply zV_refl].
Qed.

(** ** Liveness of the lane forms: TriangleLiveness.v's classes, unchanged *)

Open Scope R_scope.

(** [triangle_relation_lanes], lanes 0–2 (lane 3: o := a, (p, q) := (b, c)). *)
Corollary triangle_pi_relation_lane_live : forall o d p q : TVec,
  tbnd 300 o -> tbnd 300 d -> tbnd 300 p -> tbnd 300 q ->
  bpow radix2 (-48) * perm3v (tvec_R d) (rsub (tvec_R p) (tvec_R o)) (rsub (tvec_R q) (tvec_R o)) +
    bpow radix2 (-1068) * sumabs (tvec_R d) + bpow radix2 (-1067) <
    Rabs (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) ->
  det3_filter_lanes_b (pi_stage1_b o (bcast d) p q) Cpp.triangle_filter_pi_relative (absolute_bv (bcast d))
    <> uncertain_lane.
Proof. intros. rewrite triangle_pi_relation_lane_is_scalar. apply triangle_pi_filter_live; assumption. Qed.

(** [triangle_compensated_lanes], lanes 0–2. *)
Corollary triangle_pi_compensated_lane_live : pi_compensated_live_for (fun o => pi_stage2_b (bcast o)).
Proof.
  intros o **. cbv beta. rewrite (proj2 (triangle_pi_compensated_lane_is_scalar _ _ _ _ _ _)).
  apply triangle_pi_compensated_live; assumption.
Qed.

(** Lane 3 (num). *)
Corollary triangle_num_compensated_lane_live : num_compensated_live_for num_stage2_lane_b.
Proof.
  intros o **. rewrite (proj2 (triangle_num_compensated_lane_is_scalar _ _ _ _ _ _)).
  apply triangle_num_compensated_live; assumption.
Qed.

(** den from the lanes. *)
Corollary triangle_den_compensated_lane_live : den_compensated_live_for (fun o => den_stage2_b (bcast o)).
Proof.
  intros o **. cbv beta. rewrite (proj2 (triangle_den_compensated_lane_is_scalar _ _ _ _ _ _ _)).
  apply triangle_den_compensated_live; assumption.
Qed.

(** The stage-1 views fast_triangle_intersection filters (constants π, num, den). *)
Corollary triangle_pi_view_lane_live : forall o d p q : TVec,
  tbnd 300 o -> tbnd 300 d -> tbnd 300 p -> tbnd 300 q ->
  bpow radix2 (-48) * perm3v (tvec_R d) (rsub (tvec_R p) (tvec_R o)) (rsub (tvec_R q) (tvec_R o)) +
    bpow radix2 (-1068) * sumabs (tvec_R d) + bpow radix2 (-1067) <
    Rabs (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) ->
  det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d p q)) Cpp.triangle_filter_pi_relative (absolute_bv d)
    <> uncertain_lane.
Proof. intros. rewrite triangle_pi_view_lane_is_scalar. apply triangle_pi_filter_live; assumption. Qed.

Corollary triangle_num_view_lane_live : forall o a b c : TVec,
  tbnd 300 o -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  bpow radix2 (-48) * perm3v (rsub (tvec_R a) (tvec_R o)) (rsub (tvec_R b) (tvec_R o)) (rsub (tvec_R c) (tvec_R o)) +
    bpow radix2 (-1068) * sumabs (rsub (tvec_R a) (tvec_R o)) + bpow radix2 (-1067) <
    Rabs (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) ->
  det3_filter_lanes_b (fview (num_stage2_lane_b o a b c)) Cpp.triangle_filter_num_relative (absolute_bv (ehigh a o))
    <> uncertain_lane.
Proof. intros. rewrite triangle_num_view_lane_is_scalar. apply triangle_num_filter_live; assumption. Qed.

Corollary triangle_den_view_lane_live : forall o d a b c : TVec,
  tbnd 300 o -> tbnd 300 d -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  bpow radix2 (-48) * den_perm (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) +
    bpow radix2 (-1068) * sumabs (tvec_R d) + bpow radix2 (-1067) <
    Rabs (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) ->
  det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative (absolute_bv d)
    <> uncertain_lane.
Proof. intros. rewrite triangle_den_view_lane_is_scalar. apply triangle_den_filter_live; assumption. Qed.
