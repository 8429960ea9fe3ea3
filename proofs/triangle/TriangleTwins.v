(** * Computable twins of the ray–triangle stages 1 and 2, over IEEE-754 binary64, tied to the models.

    Each [*_b] definition is the C++ of kernel/src/core/det3_stages.hpp and ray_triangle_stages.hpp,
    operation by operation in the C++ order (the order of kernel/src/triangle/ray_triangle_formula.hpp's
    [cross_terms] and [dot_terms]), over Flocq's binary64 (FloatCore.v); the differential runner
    (proofs/twins/, routines [tri_filter], [tri_relation_lanes], [tri_compensated], [tri_compensated_lanes])
    checks them bit for bit against the compiled C++ on every variant.

    - stage 1 ([FilterLeaf], [FilterTerm], their [*], [+], [−]; [det3_absolute_term]; [det3_filter_lanes]):
      [leaf_mul_b], [leaf_scale_b], [term_add_b], [term_sub_b], [det3_b], [absolute_term_b],
      [det3_filter_lanes_b]; the query's values as [triangle_filter_values] forms them: [pi_stage1_b],
      [num_stage1_b], [den_stage1_b] (and lane 3 of [triangle_relation_lanes]: [pi_stage1_b a d b c]);
    - stage 2 ([CompensatedLeaf], [CompensatedTerm], [product_low_part], [det3_enclosure]):
      [cleaf_mul_b], [cleaf_scale_b], [cterm_add_b], [cterm_sub_b], [cdet3_b], [det3_enclosure_b]; the
      query's values as [triangle_compensated_values] and [triangle_compensated_lanes] form them:
      [pi_stage2_b], [num_stage2_b], [den_stage2_b].

    Theorems, for every 64-bit pattern of every input:
    - [det3_twin]: a finite stage-1 magnitude m means every leaf is finite and the twin's value and
      magnitude are the model's ([det3] of TriangleFilter.v); [det3_filter_lanes_twin]: a certain sign
      means m and the absolute term are finite, and the sign is the model's;
    - [triangle_pi_filter_twin_sound], [triangle_num_filter_twin_sound], [triangle_den_filter_twin_sound]: a sign stage 1 certifies is
      the sign of the exact value (TriangleFilter.v's [pi_filter_sound] etc. for the bits), and every
      input it depends on is finite;
    - [cdet3_twin]: finite low part and magnitude mean a finite stage 2 equal to the model's [cdet3];
      [triangle_pi_compensated_twin_sound], [triangle_num_compensated_twin_sound], [triangle_den_compensated_twin_sound]: when the
      enclosure's radius is finite, it encloses the exact value (TriangleCompensated.v's
      [*_compensated_encloses] for the bits; the C++ puts +inf in the radius when h or l is not finite);
    - the fast paths' lanes ([bcast]: the lanes' broadcast maps −0 to +0): [triangle_pi_lane_filter_twin_sound]
      ([triangle_relation_lanes]), [triangle_pi_lane_compensated_twin_sound],
      [triangle_num_lane_compensated_twin_sound], [triangle_den_lane_compensated_twin_sound]
      ([triangle_compensated_lanes] and den summed from it), and the signs fast_triangle_intersection takes
      from the stage-1 view of those lanes ([filter_view]: [fview]): [triangle_pi_lane_view_filter_twin_sound],
      [triangle_num_lane_view_filter_twin_sound], [triangle_den_lane_view_filter_twin_sound]. *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneCascade PlaneClassification FloatCore ConstantsCpp
  PlaneTwins TriangleFilter TriangleCompensated.
Open Scope R_scope.

(** ** Constants: the compiled values are the ones TriangleFilter.v and TriangleCompensated.v use. *)

(** The lemmas [cpp_NAME] : B2R Cpp.NAME = NAME, one per constant, are generated with the constants into
    ConstantsCpp.v (twins/emit_constants.cmake; FloatCore.v's [tie]). *)

Lemma cpp_triangle_constants :
  fin Cpp.triangle_absolute_scale = true /\ nonneg Cpp.triangle_absolute_scale /\
  fin Cpp.triangle_absolute = true /\ nonneg Cpp.triangle_absolute /\
  fin Cpp.triangle_filter_pi_relative = true /\ nonneg Cpp.triangle_filter_pi_relative /\
  fin Cpp.triangle_filter_num_relative = true /\ nonneg Cpp.triangle_filter_num_relative /\
  fin Cpp.triangle_filter_den_relative = true /\ nonneg Cpp.triangle_filter_den_relative /\
  fin Cpp.triangle_compensated_relative = true /\ nonneg Cpp.triangle_compensated_relative /\
  fin Cpp.triangle_compensated_den_relative = true /\ nonneg Cpp.triangle_compensated_den_relative.
Proof. repeat split; first [vm_compute; reflexivity | const_nonneg]. Qed.

(** Split the conjunctions of a goal, not the definitions ([ftw], [ctw], [tfin]) inside it. *)
Ltac tsplit := repeat match goal with |- _ /\ _ => split end.

(** ** Stage 1: [FilterTerm {v, m}] and its operations. *)

Record FTermB := { fvb : float; fmb : float }.

(** [FilterLeaf y * FilterLeaf z]: p = y * z, {p, abs(p)}. *)
Definition leaf_mul_b (y z : float) : FTermB := let p := fmul y z in {| fvb := p; fmb := fabs p |}.
(** [FilterLeaf x * FilterTerm c]: {x.v * c.v, abs(x.v) * c.m}. *)
Definition leaf_scale_b (x : float) (c : FTermB) : FTermB :=
  {| fvb := fmul x (fvb c); fmb := fmul (fabs x) (fmb c) |}.
(** [a + b]: {a.v + b.v, a.m + b.m}; [a − b]: {a.v − b.v, a.m + b.m}. *)
Definition term_add_b (a b : FTermB) : FTermB := {| fvb := fadd (fvb a) (fvb b); fmb := fadd (fmb a) (fmb b) |}.
Definition term_sub_b (a b : FTermB) : FTermB := {| fvb := fsub (fvb a) (fvb b); fmb := fadd (fmb a) (fmb b) |}.

(** [dot_terms(x, cross_terms(y, z))]: (x0·c0 + x1·c1) + x2·c2, c = (y1 z2 − y2 z1, y2 z0 − y0 z2, y0 z1 − y1 z0). *)
Definition det3_b (x0 x1 x2 y0 y1 y2 z0 z1 z2 : float) : FTermB :=
  term_add_b (term_add_b (leaf_scale_b x0 (term_sub_b (leaf_mul_b y1 z2) (leaf_mul_b y2 z1)))
                         (leaf_scale_b x1 (term_sub_b (leaf_mul_b y2 z0) (leaf_mul_b y0 z2))))
             (leaf_scale_b x2 (term_sub_b (leaf_mul_b y0 z1) (leaf_mul_b y1 z0))).

(** [det3_absolute_term(x0, x1, x2)]: s = (abs(x0) + abs(x1)) + abs(x2); K_A * s + U_A. *)
Definition absolute_term_b (x0 x1 x2 : float) : float :=
  fadd (fmul Cpp.triangle_absolute_scale (fadd (fadd (fabs x0) (fabs x1)) (fabs x2))) Cpp.triangle_absolute.

(** [det3_filter_lanes(r, relative, absolute)]: bound = relative * m + absolute;
    [sign_lanes(v > bound, v < −bound)]. *)
Definition det3_filter_lanes_b (t : FTermB) (C A : float) : Z :=
  let bound := fadd (fmul C (fmb t)) A in sign_lanes (flt bound (fvb t)) (flt (fvb t) (fneg bound)).

(** ** The query's vectors and values ([triangle_filter_values]: d lifted, ê_v = v − o rounded once). *)

Record TVec := TV { tx : float; ty : float; tz : float }.
Definition tvec_R (v : TVec) : vec3 := Vec3 (B2R (tx v)) (B2R (ty v)) (B2R (tz v)).
Definition tfin (v : TVec) : Prop := fin (tx v) = true /\ fin (ty v) = true /\ fin (tz v) = true.

Definition tsub (v o : TVec) : TVec := TV (fsub (tx v) (tx o)) (fsub (ty v) (ty o)) (fsub (tz v) (tz o)).
Definition det3_bv (x y z : TVec) : FTermB :=
  det3_b (tx x) (ty x) (tz x) (tx y) (ty y) (tz y) (tx z) (ty z) (tz z).
Definition absolute_bv (x : TVec) : float := absolute_term_b (tx x) (ty x) (tz x).

(** π(p, q) = d·(ê_p × ê_q): πa = π(b, c), πb = π(c, a), πc = π(a, b); num = ê_a·(ê_b × ê_c);
    den = (πa + πb) + πc.  (The relation-only lanes put π(b, c) seen from a, [pi_stage1_b a d b c], in
    lane 3.) *)
Definition pi_stage1_b (o d p q : TVec) : FTermB := det3_bv d (tsub p o) (tsub q o).
Definition num_stage1_b (o a b c : TVec) : FTermB := det3_bv (tsub a o) (tsub b o) (tsub c o).
Definition den_stage1_b (o d a b c : TVec) : FTermB :=
  term_add_b (term_add_b (pi_stage1_b o d b c) (pi_stage1_b o d c a)) (pi_stage1_b o d a b).

(** ** Stage 1: from "m is finite" to "every operation is the model's". *)

(** The twin [t] of the model's [T]: finite, the same values, and |v| ≤ m. *)
Definition ftw (t : FTermB) (T : FTerm) : Prop :=
  fin (fvb t) = true /\ fin (fmb t) = true /\ B2R (fvb t) = fv T /\ B2R (fmb t) = fm T /\
  Rabs (B2R (fvb t)) <= B2R (fmb t).

Lemma fsub_dominated : forall x y z, fin x = true -> fin y = true ->
  Rabs (RN (B2R x - B2R y)) <= B2R z ->
  fin (fsub x y) = true /\ B2R (fsub x y) = RN (B2R x - B2R y).
Proof.
  intros x y z Fx Fy D. apply fsub_fwd; try assumption.
  eapply Rle_lt_trans; [exact D|]. eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow].
Qed.

Lemma leaf_mul_back : forall y z, fin (fmb (leaf_mul_b y z)) = true -> fin y = true /\ fin z = true.
Proof. intros y z H. cbn [fmb leaf_mul_b] in H. rewrite fabs_fin in H. exact (fmul_fin _ _ H). Qed.

Lemma leaf_mul_tw : forall y z, fin (fmb (leaf_mul_b y z)) = true -> ftw (leaf_mul_b y z) (leaf_mul (B2R y) (B2R z)).
Proof.
  intros y z H. cbn [fmb leaf_mul_b] in H. rewrite fabs_fin in H.
  destruct (fmul_inv _ _ H) as [Fy [Fz V]].
  unfold ftw, leaf_mul_b, leaf_mul. cbn [fvb fmb fv fm]. rewrite fabs_fin, fabs_val, V.
  repeat split; try assumption; lra.
Qed.

Lemma leaf_scale_back : forall x c, fin (fmb (leaf_scale_b x c)) = true -> fin x = true /\ fin (fmb c) = true.
Proof.
  intros x c H. cbn [fmb leaf_scale_b] in H. destruct (fmul_fin _ _ H) as [F1 F2]. rewrite fabs_fin in F1. now split.
Qed.

Lemma leaf_scale_tw : forall x c C, fin x = true -> ftw c C -> fin (fmb (leaf_scale_b x c)) = true ->
  ftw (leaf_scale_b x c) (leaf_scale (B2R x) C).
Proof.
  intros x c C Fx [Fv [Fm [Ev [Em D]]]] H. cbn [fmb leaf_scale_b] in H.
  pose proof (fmul_val _ _ H) as Vm. rewrite fabs_val in Vm.
  assert (L : Rabs (RN (B2R x * B2R (fvb c))) <= B2R (fmul (fabs x) (fmb c))).
  { rewrite Vm, <- RN_abs. apply RN_le. rewrite Rabs_mult. apply Rmult_le_compat_l; [apply Rabs_pos | exact D]. }
  destruct (fmul_fwd x (fvb c) Fx Fv) as [Fp Vp].
  { eapply Rle_lt_trans; [exact L|]. eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow]. }
  unfold ftw, leaf_scale_b, leaf_scale. cbn [fvb fmb fv fm].
  rewrite Vp in *. repeat split; try assumption.
  - now rewrite Ev.
  - rewrite Vm, Em. reflexivity.
Qed.

Lemma term_add_back : forall a b, fin (fmb (term_add_b a b)) = true -> fin (fmb a) = true /\ fin (fmb b) = true.
Proof. intros a b H. exact (fadd_fin _ _ H). Qed.
Lemma term_sub_back : forall a b, fin (fmb (term_sub_b a b)) = true -> fin (fmb a) = true /\ fin (fmb b) = true.
Proof. intros a b H. exact (fadd_fin _ _ H). Qed.

Lemma term_add_tw : forall a b A B, ftw a A -> ftw b B -> fin (fmb (term_add_b a b)) = true ->
  ftw (term_add_b a b) (term_add A B).
Proof.
  intros a b A B [Fva [Fma [Eva [Ema Da]]]] [Fvb [Fmb [Evb [Emb Db]]]] H. cbn [fmb term_add_b] in H.
  pose proof (fadd_val _ _ H) as Vm.
  assert (L : Rabs (RN (B2R (fvb a) + B2R (fvb b))) <= B2R (fadd (fmb a) (fmb b))).
  { rewrite Vm, <- RN_abs. apply RN_le. eapply Rle_trans; [apply Rabs_triang | lra]. }
  destruct (fadd_dominated _ _ _ Fva Fvb L) as [Fs Vs].
  unfold ftw, term_add_b, term_add. cbn [fvb fmb fv fm]. rewrite Vs in *.
  repeat split; try assumption.
  - now rewrite Eva, Evb.
  - now rewrite Vm, Ema, Emb.
Qed.

Lemma term_sub_tw : forall a b A B, ftw a A -> ftw b B -> fin (fmb (term_sub_b a b)) = true ->
  ftw (term_sub_b a b) (term_sub A B).
Proof.
  intros a b A B [Fva [Fma [Eva [Ema Da]]]] [Fvb [Fmb [Evb [Emb Db]]]] H. cbn [fmb term_sub_b] in H.
  pose proof (fadd_val _ _ H) as Vm.
  assert (L : Rabs (RN (B2R (fvb a) - B2R (fvb b))) <= B2R (fadd (fmb a) (fmb b))).
  { rewrite Vm, <- RN_abs. apply RN_le. unfold Rminus. eapply Rle_trans; [apply Rabs_triang|].
    rewrite Rabs_Ropp. lra. }
  destruct (fsub_dominated _ _ _ Fva Fvb L) as [Fs Vs].
  unfold ftw, term_sub_b, term_sub. cbn [fvb fmb fv fm]. rewrite Vs in *.
  repeat split; try assumption.
  - now rewrite Eva, Evb.
  - now rewrite Vm, Ema, Emb.
Qed.

Ltac ftw_back :=
  repeat match goal with
  | H : fin (fmb (term_add_b ?a ?b)) = true |- _ =>
      tryif (have_fin (fmb a)) then fail else destruct (term_add_back a b H)
  | H : fin (fmb (term_sub_b ?a ?b)) = true |- _ =>
      tryif (have_fin (fmb a)) then fail else destruct (term_sub_back a b H)
  | H : fin (fmb (leaf_scale_b ?x ?c)) = true |- _ =>
      tryif (have_fin (fmb c)) then fail else destruct (leaf_scale_back x c H)
  | H : fin (fmb (leaf_mul_b ?y ?z)) = true |- _ =>
      tryif (have_fin y; have_fin z) then fail else destruct (leaf_mul_back y z H)
  end.

Ltac ftw_fwd :=
  repeat match goal with
  | |- ftw (term_add_b _ _) _ => apply term_add_tw
  | |- ftw (term_sub_b _ _) _ => apply term_sub_tw
  | |- ftw (leaf_scale_b _ _) _ => apply leaf_scale_tw
  | |- ftw (leaf_mul_b _ _) _ => apply leaf_mul_tw
  | |- _ => assumption
  end.

(** A finite magnitude: every leaf is finite, the value is finite, and both are the model's. *)
Theorem det3_twin : forall x0 x1 x2 y0 y1 y2 z0 z1 z2,
  fin (fmb (det3_b x0 x1 x2 y0 y1 y2 z0 z1 z2)) = true ->
  (fin x0 = true /\ fin x1 = true /\ fin x2 = true /\ fin y0 = true /\ fin y1 = true /\ fin y2 = true /\
   fin z0 = true /\ fin z1 = true /\ fin z2 = true) /\
  ftw (det3_b x0 x1 x2 y0 y1 y2 z0 z1 z2)
      (det3 (B2R x0) (B2R x1) (B2R x2) (B2R y0) (B2R y1) (B2R y2) (B2R z0) (B2R z1) (B2R z2)).
Proof.
  intros x0 x1 x2 y0 y1 y2 z0 z1 z2 H. unfold det3_b in *. ftw_back.
  split; [repeat split; assumption|]. unfold det3. ftw_fwd.
Qed.

Lemma det3_b_nonneg : forall x0 x1 x2 y0 y1 y2 z0 z1 z2, nonneg (fmb (det3_b x0 x1 x2 y0 y1 y2 z0 z1 z2)).
Proof.
  intros. unfold det3_b, term_add_b, term_sub_b, leaf_scale_b, leaf_mul_b. cbn [fmb].
  repeat first [apply fadd_nonneg | apply fmul_nonneg | apply fabs_nonneg].
Qed.

Lemma absolute_term_b_nonneg : forall x0 x1 x2, nonneg (absolute_term_b x0 x1 x2).
Proof.
  intros. destruct cpp_triangle_constants as [_ [N1 [_ [N2 _]]]]. unfold absolute_term_b.
  apply fadd_nonneg; [apply fmul_nonneg; [exact N1|] | exact N2].
  repeat first [apply fadd_nonneg | apply fabs_nonneg].
Qed.

Global Hint Rewrite cpp_triangle_absolute_scale cpp_triangle_absolute cpp_triangle_filter_pi_relative
  cpp_triangle_filter_num_relative cpp_triangle_filter_den_relative cpp_triangle_compensated_relative
  cpp_triangle_compensated_den_relative : cpp_constants.

(** A finite absolute term: finite inputs and the model's [absolute_term]. *)
Lemma absolute_term_twin : forall x0 x1 x2, fin (absolute_term_b x0 x1 x2) = true ->
  fin x0 = true /\ fin x1 = true /\ fin x2 = true /\
  B2R (absolute_term_b x0 x1 x2) = absolute_term (B2R x0) (B2R x1) (B2R x2).
Proof.
  intros x0 x1 x2 H. unfold absolute_term_b in *. fin_down. repeat split; try assumption.
  unfold absolute_term. to_model. reflexivity.
Qed.

(** A certain sign: a finite bound, so a finite magnitude and absolute term, and the model's sign. *)
Theorem det3_filter_lanes_twin : forall t T C A, fin C = true -> nonneg C -> nonneg (fmb t) -> nonneg A ->
  (fin (fmb t) = true -> ftw t T) ->
  det3_filter_lanes_b t C A <> uncertain_lane ->
  fin (fmb t) = true /\ fin A = true /\
  det3_filter_lanes_b t C A = det3_filter_lanes T (B2R C) (B2R A).
Proof.
  intros t T C A FC NC Nm NA Tw U. unfold det3_filter_lanes_b in *.
  set (bound := fadd (fmul C (fmb t)) A) in *.
  assert (NB : nonneg bound) by (apply fadd_nonneg; [apply fmul_nonneg|]; assumption).
  assert (FB : fin bound = true) by (apply (certifying_bound_finite bound (fvb t) NB); now apply sign_lanes_certain).
  destruct (fadd_fin _ _ FB) as [Fp FA]. destruct (fmul_fin _ _ Fp) as [_ Fm].
  destruct (Tw Fm) as [Fv [_ [Ev [Em _]]]].
  repeat split; try assumption.
  unfold det3_filter_lanes, det3_bound. subst bound.
  rewrite (flt_val _ (fvb t)) by assumption.
  rewrite (flt_val (fvb t)) by (rewrite ?fneg_fin; assumption).
  rewrite fneg_val, (fadd_val _ _ FB), (fmul_val _ _ Fp), Ev, Em. reflexivity.
Qed.

(** The shape every end-to-end filter theorem below shares: from the twin's tie [Tw] (which also yields the
    finiteness [Fins] of the inputs) and the model's soundness [S], a certified sign is the exact sign of V,
    and a certain sign implies [Fins]. *)
Lemma filter_twin_sound_gen : forall (t : FTermB) (T : FTerm) (C A : float) (V : R) (Fins : Prop),
  fin C = true -> nonneg C -> nonneg (fmb t) -> nonneg A ->
  (fin (fmb t) = true -> Fins /\ ftw t T) ->
  (fin A = true -> Fins -> certifies (sign_from_Z (det3_filter_lanes T (B2R C) (B2R A))) V) ->
  certifies (sign_from_Z (det3_filter_lanes_b t C A)) V /\ (det3_filter_lanes_b t C A <> uncertain_lane -> Fins).
Proof.
  intros t T C A V Fins FC NC Nm NA Tw S.
  destruct (Z.eq_dec (det3_filter_lanes_b t C A) uncertain_lane) as [U|U].
  - split; [rewrite U; exact I | intros X; contradiction].
  - destruct (det3_filter_lanes_twin t T C A FC NC Nm NA (fun F => proj2 (Tw F)) U) as [Fm [FA E]].
    destruct (Tw Fm) as [Fs _]. split; [rewrite E; exact (S FA Fs) | intros _; exact Fs].
Qed.

(** ** Stage 1 of a query, end to end. *)

Lemma tsub_twin : forall v o, fin (tx (tsub v o)) = true -> fin (ty (tsub v o)) = true -> fin (tz (tsub v o)) = true ->
  tfin v /\ tfin o /\ tvec_R (tsub v o) = rsub (tvec_R v) (tvec_R o).
Proof.
  intros [vx' vy' vz'] [ox oy oz] Hx Hy Hz. unfold tsub, tfin, tvec_R, rsub in *. cbn [tx ty tz vx vy vz] in *.
  destruct (fsub_inv _ _ Hx) as [? [? Vx]]. destruct (fsub_inv _ _ Hy) as [? [? Vy]].
  destruct (fsub_inv _ _ Hz) as [? [? Vz]].
  repeat split; try assumption. now rewrite Vx, Vy, Vz.
Qed.

Lemma tvec_R_doubles : forall v, doubles3 (tvec_R v).
Proof. intros v. repeat split; apply binary64_B2R. Qed.

Lemma det3_bv_twin : forall x y z, fin (fmb (det3_bv x y z)) = true ->
  tfin x /\ tfin y /\ tfin z /\ ftw (det3_bv x y z) (det3v (tvec_R x) (tvec_R y) (tvec_R z)).
Proof.
  intros [x0 x1 x2] [y0 y1 y2] [z0 z1 z2] H. unfold det3_bv, det3v, tfin in *. cbn [tx ty tz vx vy vz tvec_R] in *.
  destruct (det3_twin _ _ _ _ _ _ _ _ _ H) as [[? [? [? [? [? [? [? [? ?]]]]]]]] T].
  tsplit; assumption.
Qed.

Lemma absolute_bv_twin : forall x, fin (absolute_bv x) = true -> tfin x /\ B2R (absolute_bv x) = absolute_v (tvec_R x).
Proof.
  intros [x0 x1 x2] H. unfold absolute_bv, absolute_v, tfin in *. cbn [tx ty tz tvec_R vx vy vz] in *.
  destruct (absolute_term_twin _ _ _ H) as [? [? [? E]]]. repeat split; assumption.
Qed.

Lemma pi_stage1_twin : forall o d p q, fin (fmb (pi_stage1_b o d p q)) = true ->
  tfin o /\ tfin d /\ tfin p /\ tfin q /\ ftw (pi_stage1_b o d p q) (pi_stage1 (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)).
Proof.
  intros o d p q H. unfold pi_stage1_b, pi_stage1 in *.
  destruct (det3_bv_twin _ _ _ H) as [Fd [[F1 [F2 F3]] [[G1 [G2 G3]] T]]].
  destruct (tsub_twin p o F1 F2 F3) as [Fp [Fo Ep]]. destruct (tsub_twin q o G1 G2 G3) as [Fq [_ Eq]].
  rewrite Ep, Eq in T. tsplit; assumption.
Qed.

Lemma num_stage1_twin : forall o a b c, fin (fmb (num_stage1_b o a b c)) = true ->
  tfin o /\ tfin a /\ tfin b /\ tfin c /\ ftw (num_stage1_b o a b c) (num_stage1 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o a b c H. unfold num_stage1_b, num_stage1 in *.
  destruct (det3_bv_twin _ _ _ H) as [[E1 [E2 E3]] [[F1 [F2 F3]] [[G1 [G2 G3]] T]]].
  destruct (tsub_twin a o E1 E2 E3) as [Fa [Fo Ea]].
  destruct (tsub_twin b o F1 F2 F3) as [Fb [_ Eb]]. destruct (tsub_twin c o G1 G2 G3) as [Fc [_ Ec]].
  rewrite Ea, Eb, Ec in T. tsplit; assumption.
Qed.

(** den = (πa + πb) + πc from the ties of its three π terms (stage 1 and stage 2 alike). *)
Ltac pi_sum_leaves T0 T1 T2 :=
  destruct T0 as [? [? [? [? ?]]]]; destruct T1 as [_ [_ [_ [? ?]]]]; destruct T2 as [_ [_ [_ [_ ?]]]].

Lemma den_stage1_twin : forall o d a b c, fin (fmb (den_stage1_b o d a b c)) = true ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  ftw (den_stage1_b o d a b c) (den_stage1 (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c H. unfold den_stage1_b, den_stage1 in *.
  destruct (term_add_back _ _ H) as [H01 H2]. destruct (term_add_back _ _ H01) as [H0 H1].
  pi_sum_leaves (pi_stage1_twin _ _ _ _ H0) (pi_stage1_twin _ _ _ _ H1) (pi_stage1_twin _ _ _ _ H2).
  tsplit; try assumption. ftw_fwd.
Qed.

Lemma absolute_bv_nonneg : forall x, nonneg (absolute_bv x).
Proof. intros. apply absolute_term_b_nonneg. Qed.
Lemma pi_stage1_b_nonneg : forall o d p q, nonneg (fmb (pi_stage1_b o d p q)).
Proof. intros. apply det3_b_nonneg. Qed.
Lemma num_stage1_b_nonneg : forall o a b c, nonneg (fmb (num_stage1_b o a b c)).
Proof. intros. apply det3_b_nonneg. Qed.
Lemma den_stage1_b_nonneg : forall o d a b c, nonneg (fmb (den_stage1_b o d a b c)).
Proof.
  intros. unfold den_stage1_b.
  apply (fadd_nonneg (fmb (term_add_b _ _)) (fmb (pi_stage1_b o d a b))); [apply fadd_nonneg|]; apply det3_b_nonneg.
Qed.

(** End to end, for every 64-bit pattern of o, d, p, q: a sign the stage-1 filter certifies for
    π(p, q) = d·((p − o) × (q − o)) is its exact sign, and then o, d, p, q are finite. *)
Theorem triangle_pi_filter_twin_sound : forall o d p q : TVec,
  let s := det3_filter_lanes_b (pi_stage1_b o d p q) Cpp.triangle_filter_pi_relative (absolute_bv d) in
  certifies (sign_from_Z s) (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) /\
  (s <> uncertain_lane -> tfin o /\ tfin d /\ tfin p /\ tfin q).
Proof.
  intros o d p q. cbv zeta. destruct cpp_triangle_constants as [_ [_ [_ [_ [FC [NC _]]]]]].
  apply (filter_twin_sound_gen _ (pi_stage1 (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) _ _ _ _ FC NC
           (pi_stage1_b_nonneg o d p q) (absolute_bv_nonneg _)).
  - intros F. destruct (pi_stage1_twin o d p q F) as [? [? [? [? T]]]]. split; [tsplit; assumption | exact T].
  - intros FA _. rewrite cpp_triangle_filter_pi_relative, (proj2 (absolute_bv_twin d FA)).
    apply pi_filter_sound; apply tvec_R_doubles.
Qed.

(** num = (a − o)·((b − o) × (c − o)), with the absolute term of ê_a. *)
Theorem triangle_num_filter_twin_sound : forall o a b c : TVec,
  let s := det3_filter_lanes_b (num_stage1_b o a b c) Cpp.triangle_filter_num_relative (absolute_bv (tsub a o)) in
  certifies (sign_from_Z s) (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) /\
  (s <> uncertain_lane -> tfin o /\ tfin a /\ tfin b /\ tfin c).
Proof.
  intros o a b c. cbv zeta. destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [FC [NC _]]]]]]]].
  apply (filter_twin_sound_gen _ (num_stage1 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) _ _ _ _ FC NC
           (num_stage1_b_nonneg o a b c) (absolute_bv_nonneg _)).
  - intros F. destruct (num_stage1_twin o a b c F) as [? [? [? [? T]]]]. split; [tsplit; assumption | exact T].
  - intros FA _. destruct (absolute_bv_twin _ FA) as [[F1 [F2 F3]] EA].
    destruct (tsub_twin a o F1 F2 F3) as [_ [_ Ea]].
    rewrite cpp_triangle_filter_num_relative, EA, Ea. apply num_filter_sound; apply tvec_R_doubles.
Qed.

(** den = (πa ⊕ πb) ⊕ πc: a certified sign is the sign of d·((b − a) × (c − a)) summed as πa + πb + πc. *)
Theorem triangle_den_filter_twin_sound : forall o d a b c : TVec,
  let s := det3_filter_lanes_b (den_stage1_b o d a b c) Cpp.triangle_filter_den_relative (absolute_bv d) in
  certifies (sign_from_Z s) (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) /\
  (s <> uncertain_lane -> tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c).
Proof.
  intros o d a b c. cbv zeta. destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [_ [_ [FC [NC _]]]]]]]]]].
  apply (filter_twin_sound_gen _ (den_stage1 (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) _ _ _ _ FC NC
           (den_stage1_b_nonneg o d a b c) (absolute_bv_nonneg _)).
  - intros F. destruct (den_stage1_twin o d a b c F) as [? [? [? [? [? T]]]]]. split; [tsplit; assumption | exact T].
  - intros FA _. rewrite cpp_triangle_filter_den_relative, (proj2 (absolute_bv_twin d FA)).
    apply den_filter_sound; apply tvec_R_doubles.
Qed.

(** ** Stage 2: [CompensatedTerm {h, l, m}] and its operations. *)

Record CTermB := { chb : float; clb : float; cmb : float }.

(** [product_low_part(ah, al, bh, bl, p)] = fma(ah, bl, fma(al, bh, fma(ah, bh, −p))). *)
Definition product_low_part_b (ah al bh bl p : float) : float := ffma ah bl (ffma al bh (ffma ah bh (fneg p))).

(** [CompensatedLeaf y * CompensatedLeaf z]: p = y.h * z.h, {p, product_low_part(y.h, y.l, z.h, z.l, p), abs(p)}. *)
Definition cleaf_mul_b (yh yl zh zl : float) : CTermB :=
  let p := fmul yh zh in {| chb := p; clb := product_low_part_b yh yl zh zl p; cmb := fabs p |}.
(** [CompensatedLeaf x * CompensatedTerm c]: p = x.h * c.h, {p, product_low_part(x.h, x.l, c.h, c.l, p),
    abs(x.h) * c.m}. *)
Definition cleaf_scale_b (xh xl : float) (c : CTermB) : CTermB :=
  let p := fmul xh (chb c) in
  {| chb := p; clb := product_low_part_b xh xl (chb c) (clb c) p; cmb := fmul (fabs xh) (cmb c) |}.
(** [a + b]: s = two_sum(a.h, b.h), {s.hi, (a.l + b.l) + s.lo, a.m + b.m}; [a − b]: s = two_sum(a.h, −b.h),
    {s.hi, (a.l − b.l) + s.lo, a.m + b.m}. *)
Definition cterm_add_b (a b : CTermB) : CTermB :=
  let s := two_sum_b (chb a) (chb b) in
  {| chb := fst s; clb := fadd (fadd (clb a) (clb b)) (snd s); cmb := fadd (cmb a) (cmb b) |}.
Definition cterm_sub_b (a b : CTermB) : CTermB :=
  let s := two_sum_b (chb a) (fneg (chb b)) in
  {| chb := fst s; clb := fadd (fsub (clb a) (clb b)) (snd s); cmb := fadd (cmb a) (cmb b) |}.

Definition cdet3_b (xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 : float) : CTermB :=
  cterm_add_b (cterm_add_b (cleaf_scale_b xh0 xl0 (cterm_sub_b (cleaf_mul_b yh1 yl1 zh2 zl2) (cleaf_mul_b yh2 yl2 zh1 zl1)))
                           (cleaf_scale_b xh1 xl1 (cterm_sub_b (cleaf_mul_b yh2 yl2 zh0 zl0) (cleaf_mul_b yh0 yl0 zh2 zl2))))
              (cleaf_scale_b xh2 xl2 (cterm_sub_b (cleaf_mul_b yh0 yl0 zh1 zl1) (cleaf_mul_b yh1 yl1 zh0 zl0))).

(** [det3_enclosure(t, relative, absolute)]: radius = relative * m + absolute, replaced by +inf unless
    |h| ≤ largest finite and |l| ≤ largest finite. *)
Definition det3_enclosure_b (t : CTermB) (K A : float) : EnclosureB :=
  let radius := fadd (fmul K (cmb t)) A in
  let finite := andb (fle (fabs (chb t)) largest_finite_f) (fle (fabs (clb t)) largest_finite_f) in
  {| hib := chb t; lob := clb t; radiusb := if finite then radius else finf |}.

(** The leaves of [triangle_compensated_values]: d as (d, 0), ê_v as TwoDiff(v, o). *)
Definition pi_stage2_b (o d p q : TVec) : CTermB :=
  let ex := two_diff_b (tx p) (tx o) in let ey := two_diff_b (ty p) (ty o) in let ez := two_diff_b (tz p) (tz o) in
  let fx := two_diff_b (tx q) (tx o) in let fy := two_diff_b (ty q) (ty o) in let fz := two_diff_b (tz q) (tz o) in
  cdet3_b (tx d) fzero (ty d) fzero (tz d) fzero
          (fst ex) (snd ex) (fst ey) (snd ey) (fst ez) (snd ez) (fst fx) (snd fx) (fst fy) (snd fy) (fst fz) (snd fz).
Definition num_stage2_b (o a b c : TVec) : CTermB :=
  let ax := two_diff_b (tx a) (tx o) in let ay := two_diff_b (ty a) (ty o) in let az := two_diff_b (tz a) (tz o) in
  let bx := two_diff_b (tx b) (tx o) in let by_ := two_diff_b (ty b) (ty o) in let bz := two_diff_b (tz b) (tz o) in
  let cx := two_diff_b (tx c) (tx o) in let cy := two_diff_b (ty c) (ty o) in let cz := two_diff_b (tz c) (tz o) in
  cdet3_b (fst ax) (snd ax) (fst ay) (snd ay) (fst az) (snd az) (fst bx) (snd bx) (fst by_) (snd by_) (fst bz) (snd bz)
          (fst cx) (snd cx) (fst cy) (snd cy) (fst cz) (snd cz).
Definition den_stage2_b (o d a b c : TVec) : CTermB :=
  cterm_add_b (cterm_add_b (pi_stage2_b o d b c) (pi_stage2_b o d c a)) (pi_stage2_b o d a b).
(** The lanes' [broadcast<Lanes4>(x)] is [V{} + x] (lanes.hpp): +0 ⊕ x, which is x except that −0 becomes +0.
    [triangle_relation_lanes] broadcasts d, [triangle_compensated_lanes] broadcasts o (for ê_b, ê_c), so their
    lanes are the values of a query with that vector's −0 components replaced by +0 (the same reals). *)
Definition bcast (v : TVec) : TVec := TV (fadd fzero (tx v)) (fadd fzero (ty v)) (fadd fzero (tz v)).

(** Lane 3 of [triangle_compensated_lanes]: x = TwoDiff(a, o) with the query's o, y = TwoDiff(b, o'),
    z = TwoDiff(c, o') with o' = broadcast(o). *)
Definition num_stage2_lane_b (o a b c : TVec) : CTermB :=
  let o' := bcast o in
  let ax := two_diff_b (tx a) (tx o) in let ay := two_diff_b (ty a) (ty o) in let az := two_diff_b (tz a) (tz o) in
  let bx := two_diff_b (tx b) (tx o') in let by_ := two_diff_b (ty b) (ty o') in let bz := two_diff_b (tz b) (tz o') in
  let cx := two_diff_b (tx c) (tx o') in let cy := two_diff_b (ty c) (ty o') in let cz := two_diff_b (tz c) (tz o') in
  cdet3_b (fst ax) (snd ax) (fst ay) (snd ay) (fst az) (snd az) (fst bx) (snd bx) (fst by_) (snd by_) (fst bz) (snd bz)
          (fst cx) (snd cx) (fst cy) (snd cy) (fst cz) (snd cz).

(** The absolute term of num in stage 2: of the high parts of TwoDiff(a, o). *)
Definition ehigh (v o : TVec) : TVec :=
  TV (fst (two_diff_b (tx v) (tx o))) (fst (two_diff_b (ty v) (ty o))) (fst (two_diff_b (tz v) (tz o))).

(** ** Stage 2: from "l and m are finite" to "every operation is the model's". *)

Definition ctw (t : CTermB) (T : CTerm) : Prop :=
  fin (chb t) = true /\ fin (clb t) = true /\ fin (cmb t) = true /\
  B2R (chb t) = ch T /\ B2R (clb t) = cl T /\ B2R (cmb t) = cm T.

Lemma cleaf_mul_back : forall yh yl zh zl, fin (clb (cleaf_mul_b yh yl zh zl)) = true ->
  fin yh = true /\ fin yl = true /\ fin zh = true /\ fin zl = true.
Proof.
  intros yh yl zh zl H. cbn [clb cleaf_mul_b] in H. unfold product_low_part_b in H. fin_down.
  repeat split; assumption.
Qed.

Lemma cleaf_mul_tw : forall yh yl zh zl, fin (clb (cleaf_mul_b yh yl zh zl)) = true ->
  fin (cmb (cleaf_mul_b yh yl zh zl)) = true ->
  ctw (cleaf_mul_b yh yl zh zl) (cleaf_mul (B2R yh) (B2R yl) (B2R zh) (B2R zl)).
Proof.
  intros yh yl zh zl H Hm. unfold ctw, cleaf_mul_b, cleaf_mul, product_low_part_b, product_low_part in *.
  cbn [chb clb cmb ch cl cm] in *. fin_down.
  repeat split; first [assumption | rewrite fabs_fin; assumption | unfold fma; to_model; reflexivity].
Qed.

Lemma cleaf_scale_back : forall xh xl c, fin (clb (cleaf_scale_b xh xl c)) = true ->
  fin (cmb (cleaf_scale_b xh xl c)) = true ->
  fin xh = true /\ fin xl = true /\ fin (chb c) = true /\ fin (clb c) = true /\ fin (cmb c) = true.
Proof.
  intros xh xl c H Hm. cbn [clb cmb cleaf_scale_b] in H, Hm. unfold product_low_part_b in H. fin_down.
  repeat split; assumption.
Qed.

Lemma cleaf_scale_tw : forall xh xl c C, ctw c C -> fin (clb (cleaf_scale_b xh xl c)) = true ->
  fin (cmb (cleaf_scale_b xh xl c)) = true ->
  ctw (cleaf_scale_b xh xl c) (cleaf_scale (B2R xh) (B2R xl) C).
Proof.
  intros xh xl c C [Fh [Fl [Fm [Eh [El Em]]]]] H Hm.
  unfold ctw, cleaf_scale_b, cleaf_scale, product_low_part_b, product_low_part in *.
  cbn [chb clb cmb ch cl cm] in *. fin_down.
  repeat split; try assumption; unfold fma; to_model; rewrite ?Eh, ?El, ?Em; reflexivity.
Qed.

(** A sum or a difference of two terms (the difference adds −b.h and subtracts the low parts): one proof. *)
Ltac cterm_back_tac :=
  intros a b H Hm; cbn [clb cmb cterm_add_b cterm_sub_b] in H, Hm; fin_down;
  destruct (two_sum_b_inv _ _ ltac:(eassumption)) as [? [F _]]; rewrite ?fneg_fin in F; repeat split; assumption.

Ltac cterm_tw_tac low_inv :=
  intros a b A B [Fha [Fla [Fma [Eha [Ela Ema]]]]] [Fhb [Flb [Fmb [Ehb [Elb Emb]]]]] H Hm;
  cbn [clb cmb cterm_add_b cterm_sub_b] in H, Hm;
  destruct (fadd_inv _ _ H) as [H1 [Hs Vl]];
  destruct (low_inv _ _ H1) as [_ [_ Vl1]];
  destruct (two_sum_b_inv _ _ Hs) as [_ [_ [Fs [Es1 Es2]]]];
  unfold ctw, cterm_add_b, cterm_add, cterm_sub_b, cterm_sub; cbn [chb clb cmb ch cl cm];
  rewrite ?fneg_val in Es1, Es2;
  repeat split; try assumption;
  [ now rewrite Es1, Eha, Ehb | now rewrite Vl, Vl1, Es2, Eha, Ehb, Ela, Elb
  | now rewrite (fadd_val _ _ Hm), Ema, Emb ].

Lemma cterm_add_back : forall a b, fin (clb (cterm_add_b a b)) = true -> fin (cmb (cterm_add_b a b)) = true ->
  fin (chb a) = true /\ fin (clb a) = true /\ fin (cmb a) = true /\
  fin (chb b) = true /\ fin (clb b) = true /\ fin (cmb b) = true.
Proof. cterm_back_tac. Qed.

Lemma cterm_sub_back : forall a b, fin (clb (cterm_sub_b a b)) = true -> fin (cmb (cterm_sub_b a b)) = true ->
  fin (chb a) = true /\ fin (clb a) = true /\ fin (cmb a) = true /\
  fin (chb b) = true /\ fin (clb b) = true /\ fin (cmb b) = true.
Proof. cterm_back_tac. Qed.

Lemma cterm_add_tw : forall a b A B, ctw a A -> ctw b B -> fin (clb (cterm_add_b a b)) = true ->
  fin (cmb (cterm_add_b a b)) = true -> ctw (cterm_add_b a b) (cterm_add A B).
Proof. cterm_tw_tac fadd_inv. Qed.

Lemma cterm_sub_tw : forall a b A B, ctw a A -> ctw b B -> fin (clb (cterm_sub_b a b)) = true ->
  fin (cmb (cterm_sub_b a b)) = true -> ctw (cterm_sub_b a b) (cterm_sub A B).
Proof. cterm_tw_tac fsub_inv. Qed.

Ltac ctw_back :=
  repeat match goal with
  | H : fin (clb (cterm_add_b ?a ?b)) = true, Hm : fin (cmb (cterm_add_b ?a ?b)) = true |- _ =>
      tryif (have_fin (cmb a)) then fail else destruct (cterm_add_back a b H Hm) as [? [? [? [? [? ?]]]]]
  | H : fin (clb (cterm_sub_b ?a ?b)) = true, Hm : fin (cmb (cterm_sub_b ?a ?b)) = true |- _ =>
      tryif (have_fin (cmb a)) then fail else destruct (cterm_sub_back a b H Hm) as [? [? [? [? [? ?]]]]]
  | H : fin (clb (cleaf_scale_b ?x ?l ?c)) = true, Hm : fin (cmb (cleaf_scale_b ?x ?l ?c)) = true |- _ =>
      tryif (have_fin (cmb c)) then fail else destruct (cleaf_scale_back x l c H Hm) as [? [? [? [? ?]]]]
  | H : fin (clb (cleaf_mul_b ?yh ?yl ?zh ?zl)) = true |- _ =>
      tryif (have_fin yh; have_fin yl; have_fin zh; have_fin zl) then fail
      else destruct (cleaf_mul_back yh yl zh zl H) as [? [? [? ?]]]
  end.

Ltac ctw_fwd :=
  repeat match goal with
  | |- ctw (cterm_add_b _ _) _ => apply cterm_add_tw
  | |- ctw (cterm_sub_b _ _) _ => apply cterm_sub_tw
  | |- ctw (cleaf_scale_b _ _ _) _ => apply cleaf_scale_tw
  | |- ctw (cleaf_mul_b _ _ _ _) _ => apply cleaf_mul_tw
  | |- _ => assumption
  end.

(** Finite low part and magnitude: every leaf is finite, and the whole stage 2 is the model's. *)
Theorem cdet3_twin : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  let t := cdet3_b xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 in
  fin (clb t) = true -> fin (cmb t) = true ->
  (fin xh0 = true /\ fin xl0 = true /\ fin xh1 = true /\ fin xl1 = true /\ fin xh2 = true /\ fin xl2 = true /\
   fin yh0 = true /\ fin yl0 = true /\ fin yh1 = true /\ fin yl1 = true /\ fin yh2 = true /\ fin yl2 = true /\
   fin zh0 = true /\ fin zl0 = true /\ fin zh1 = true /\ fin zl1 = true /\ fin zh2 = true /\ fin zl2 = true) /\
  ctw t (cdet3 (B2R xh0) (B2R xl0) (B2R xh1) (B2R xl1) (B2R xh2) (B2R xl2) (B2R yh0) (B2R yl0) (B2R yh1)
               (B2R yl1) (B2R yh2) (B2R yl2) (B2R zh0) (B2R zl0) (B2R zh1) (B2R zl1) (B2R zh2) (B2R zl2)).
Proof.
  intros xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 t H Hm.
  subst t. unfold cdet3_b in *. ctw_back.
  split; [repeat split; assumption|]. unfold cdet3. ctw_fwd.
Qed.

(** A finite radius: h, l, m and the absolute term are finite (the C++ returns +inf otherwise), and the
    enclosure is the model's. *)
Theorem det3_enclosure_twin : forall t K A, fin (radiusb (det3_enclosure_b t K A)) = true ->
  fin (chb t) = true /\ fin (clb t) = true /\ fin (cmb t) = true /\ fin A = true /\
  forall T, ctw t T -> enc_R (det3_enclosure_b t K A) = TriangleCompensated.det3_enclosure T (B2R K) (B2R A).
Proof.
  intros t K A H. unfold det3_enclosure_b in *. cbn [radiusb] in H.
  rewrite !fle_largest_finite in H.
  destruct (fin (chb t)) eqn:Fh; [|discriminate]. destruct (fin (clb t)) eqn:Fl; [|discriminate].
  cbn [andb] in H. destruct (fadd_fin _ _ H) as [Fp FA]. destruct (fmul_fin _ _ Fp) as [FK Fm].
  repeat split; try assumption.
  intros T [_ [_ [_ [Eh [El Em]]]]]. unfold enc_R, TriangleCompensated.det3_enclosure.
  rewrite !fle_largest_finite, Fh, Fl. cbn [andb hib lob radiusb].
  rewrite (fadd_val _ _ H), (fmul_val _ _ Fp), Eh, El, Em. reflexivity.
Qed.

(** ** Stage 2 of a query, end to end. *)

Lemma two_diff_twin : forall v o, fin (snd (two_diff_b v o)) = true ->
  fin v = true /\ fin o = true /\ B2R (fst (two_diff_b v o)) = RN (B2R v - B2R o) /\
  B2R (snd (two_diff_b v o)) = snd (two_diff (B2R v) (B2R o)).
Proof.
  intros v o H. unfold two_diff_b in *. destruct (two_sum_b_inv _ _ H) as [Fv [Fo [_ [E1 E2]]]].
  rewrite fneg_fin in Fo. rewrite fneg_val in E1, E2. rewrite two_sum_hi in E1.
  repeat split; assumption.
Qed.

Lemma two_diff_fst_twin : forall v o, fin (fst (two_diff_b v o)) = true ->
  fin v = true /\ fin o = true /\ B2R (fst (two_diff_b v o)) = RN (B2R v - B2R o).
Proof.
  intros v o H. unfold two_diff_b in *. destruct (two_sum_b_fst _ _ H) as [Fv [Fo E]].
  rewrite fneg_fin in Fo. rewrite fneg_val, two_sum_hi in E. repeat split; assumption.
Qed.

Lemma ehigh_twin : forall a o, fin (absolute_bv (ehigh a o)) = true ->
  tfin a /\ tfin o /\ B2R (absolute_bv (ehigh a o)) = absolute_v (rsub (tvec_R a) (tvec_R o)).
Proof.
  intros a o H. destruct (absolute_bv_twin _ H) as [[F1 [F2 F3]] E]. rewrite E.
  unfold ehigh in *. cbn [tx ty tz] in F1, F2, F3.
  destruct (two_diff_fst_twin _ _ F1) as [? [? E1]]. destruct (two_diff_fst_twin _ _ F2) as [? [? E2]].
  destruct (two_diff_fst_twin _ _ F3) as [? [? E3]].
  repeat split; try assumption. unfold tvec_R, rsub. cbn [tx ty tz vx vy vz]. now rewrite E1, E2, E3.
Qed.

(** The broadcast lane x ↦ +0 ⊕ x: x itself when finite. *)
Lemma bcast_val : forall x, fin (fadd fzero x) = true -> fin x = true /\ B2R (fadd fzero x) = B2R x.
Proof.
  intros x H. destruct (fadd_inv _ _ H) as [_ [Fx V]]. split; [exact Fx|].
  rewrite V. change (B2R fzero) with 0. rewrite Rplus_0_l. apply RN_binary64, binary64_B2R.
Qed.

Ltac two_diff_leaves H :=
  repeat match type of H with
  | context [B2R (snd (two_diff_b ?v ?o))] =>
      let F := fresh in assert (F : fin (snd (two_diff_b v o)) = true) by assumption;
      let E1 := fresh in let E2 := fresh in
      destruct (two_diff_twin v o F) as [? [? [E1 E2]]]; rewrite E1, E2 in H; clear F E1 E2
  end.

(** A stage-2 determinant [cdet3_b] of TwoDiff leaves (and broadcast lanes) whose low part and magnitude are
    finite: its inputs are finite and it is the model's stage 2 (the shape of [pi_stage2_twin],
    [num_stage2_twin], [num_stage2_lane_twin]). *)
Ltac stage2_leaves H Hm :=
  let T := fresh "T" in
  destruct (cdet3_twin _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ H Hm)
    as [[? [? [? [? [? [? [? [? [? [? [? [? [? [? [? [? [? ?]]]]]]]]]]]]]]]]] T];
  two_diff_leaves T; try change (B2R fzero) with 0 in T;
  repeat match goal with
  | F : fin (fadd fzero ?x) = true |- _ =>
      let E := fresh in destruct (bcast_val x F) as [? E]; rewrite E in T; clear F E
  end;
  unfold tfin; cbn [tx ty tz]; tsplit; try assumption.

Lemma pi_stage2_twin : forall o d p q, fin (clb (pi_stage2_b o d p q)) = true -> fin (cmb (pi_stage2_b o d p q)) = true ->
  tfin o /\ tfin d /\ tfin p /\ tfin q /\ ctw (pi_stage2_b o d p q) (pi_stage2 (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)).
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [qx qy qz] H Hm. unfold pi_stage2_b in *. cbn [tx ty tz] in *.
  stage2_leaves H Hm.
Qed.

Lemma num_stage2_twin : forall o a b c, fin (clb (num_stage2_b o a b c)) = true -> fin (cmb (num_stage2_b o a b c)) = true ->
  tfin o /\ tfin a /\ tfin b /\ tfin c /\ ctw (num_stage2_b o a b c) (num_stage2 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz] H Hm. unfold num_stage2_b in *. cbn [tx ty tz] in *.
  stage2_leaves H Hm.
Qed.

Lemma den_stage2_twin : forall o d a b c, fin (clb (den_stage2_b o d a b c)) = true ->
  fin (cmb (den_stage2_b o d a b c)) = true ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  ctw (den_stage2_b o d a b c) (den_stage2 (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c H Hm. unfold den_stage2_b, den_stage2 in *.
  destruct (cterm_add_back _ _ H Hm) as [_ [H01 [Hm01 [_ [H2 Hm2]]]]].
  destruct (cterm_add_back _ _ H01 Hm01) as [_ [H0 [Hm0 [_ [H1 Hm1]]]]].
  pi_sum_leaves (pi_stage2_twin _ _ _ _ H0 Hm0) (pi_stage2_twin _ _ _ _ H1 Hm1) (pi_stage2_twin _ _ _ _ H2 Hm2).
  tsplit; try assumption. ctw_fwd.
Qed.

(** The shape every end-to-end stage-2 theorem below shares: from a finite radius, the twin's tie [Tw] of
    the determinant (which also yields the finiteness [Fins] of the inputs) and the model's enclosure [S],
    the enclosure holds X and [Fins] holds (as [filter_twin_sound_gen] for stage 1). *)
Lemma compensated_twin_sound_gen : forall (t : CTermB) (K A : float), fin (radiusb (det3_enclosure_b t K A)) = true ->
  forall (T : CTerm) (X : R) (Fins : Prop),
  (fin (clb t) = true -> fin (cmb t) = true -> Fins /\ ctw t T) ->
  (fin A = true -> Fins -> encloses (TriangleCompensated.det3_enclosure T (B2R K) (B2R A)) X) ->
  Fins /\ encloses (enc_R (det3_enclosure_b t K A)) X.
Proof.
  intros t K A H T X Fins Tw S. destruct (det3_enclosure_twin _ _ _ H) as [_ [Fl [Fm [FA E]]]].
  destruct (Tw Fl Fm) as [Fs Tt]. split; [exact Fs|]. rewrite (E _ Tt). exact (S FA Fs).
Qed.

(** End to end: when the radius stage 2 returns for π(p, q) is finite, the enclosure holds the exact value
    (TriangleCompensated.v's [pi_compensated_encloses] for the bits), and o, d, p, q are finite. *)
Theorem triangle_pi_compensated_twin_sound : forall o d p q : TVec,
  let e := det3_enclosure_b (pi_stage2_b o d p q) Cpp.triangle_compensated_relative (absolute_bv d) in
  fin (radiusb e) = true ->
  tfin o /\ tfin d /\ tfin p /\ tfin q /\ encloses (enc_R e) (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)).
Proof.
  intros o d p q e H.
  destruct (compensated_twin_sound_gen _ _ _ H (pi_stage2 (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q))
              (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) (tfin o /\ tfin d /\ tfin p /\ tfin q))
    as [[? [? [? ?]]] ?]; [| | tsplit; assumption].
  - intros Fl Fm. destruct (pi_stage2_twin o d p q Fl Fm) as [? [? [? [? T]]]]. split; [tsplit; assumption | exact T].
  - intros FA _. rewrite cpp_triangle_compensated_relative, (proj2 (absolute_bv_twin d FA)).
    apply pi_compensated_encloses; apply tvec_R_doubles.
Qed.

(** num's two stage-2 forms (the query's and lane 3 of the lanes) differ only in how the determinant is
    computed: one proof from the tie [Tw] of either. *)
Lemma num_compensated_twin_gen : forall (t : CTermB) (o a b c : TVec),
  (fin (clb t) = true -> fin (cmb t) = true ->
   tfin o /\ tfin a /\ tfin b /\ tfin c /\ ctw t (num_stage2 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c))) ->
  let e := det3_enclosure_b t Cpp.triangle_compensated_relative (absolute_bv (ehigh a o)) in
  fin (radiusb e) = true ->
  tfin o /\ tfin a /\ tfin b /\ tfin c /\ encloses (enc_R e) (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros t o a b c Tw e H.
  destruct (compensated_twin_sound_gen _ _ _ H (num_stage2 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c))
              (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) (tfin o /\ tfin a /\ tfin b /\ tfin c))
    as [[? [? [? ?]]] ?]; [| | tsplit; assumption].
  - intros Fl Fm. destruct (Tw Fl Fm) as [? [? [? [? T]]]]. split; [tsplit; assumption | exact T].
  - intros FA _. rewrite cpp_triangle_compensated_relative, (proj2 (proj2 (ehigh_twin a o FA))).
    apply num_compensated_encloses; apply tvec_R_doubles.
Qed.

(** num: with the absolute term of the high parts of TwoDiff(a, o). *)
Theorem triangle_num_compensated_twin_sound : forall o a b c : TVec,
  let e := det3_enclosure_b (num_stage2_b o a b c) Cpp.triangle_compensated_relative (absolute_bv (ehigh a o)) in
  fin (radiusb e) = true ->
  tfin o /\ tfin a /\ tfin b /\ tfin c /\ encloses (enc_R e) (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof. intros o a b c. exact (num_compensated_twin_gen _ o a b c (num_stage2_twin o a b c)). Qed.

(** den = (πa + πb) + πc in double-doubles, with K_den. *)
Theorem triangle_den_compensated_twin_sound : forall o d a b c : TVec,
  let e := det3_enclosure_b (den_stage2_b o d a b c) Cpp.triangle_compensated_den_relative (absolute_bv d) in
  fin (radiusb e) = true ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  encloses (enc_R e) (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c e H.
  destruct (compensated_twin_sound_gen _ _ _ H (den_stage2 (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c))
              (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c))
              (tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c))
    as [[? [? [? [? ?]]]] ?]; [| | tsplit; assumption].
  - intros Fl Fm. destruct (den_stage2_twin o d a b c Fl Fm) as [? [? [? [? [? T]]]]].
    split; [tsplit; assumption | exact T].
  - intros FA _. rewrite cpp_triangle_compensated_den_relative, (proj2 (absolute_bv_twin d FA)).
    apply den_compensated_encloses; apply tvec_R_doubles.
Qed.

(** ** The lanes of the fast paths ([triangle_relation_lanes], [triangle_compensated_lanes]). *)

Lemma bcast_twin : forall v, tfin (bcast v) -> tfin v /\ tvec_R (bcast v) = tvec_R v.
Proof.
  intros [x y z] [Fx [Fy Fz]]. unfold bcast, tfin, tvec_R in *. cbn [tx ty tz] in *.
  destruct (bcast_val _ Fx) as [? Ex]. destruct (bcast_val _ Fy) as [? Ey]. destruct (bcast_val _ Fz) as [? Ez].
  rewrite Ex, Ey, Ez. tsplit; auto.
Qed.

(** Lanes 0–2 of [triangle_relation_lanes] (d broadcast): a certified sign is the exact sign of π(p, q);
    lane 3, π(b, c) seen from a, is the instance o := a, (p, q) := (b, c), whose exact value is
    d·((b − a) × (c − a)), den's. *)
Corollary triangle_pi_lane_filter_twin_sound : forall o d p q : TVec,
  let s := det3_filter_lanes_b (pi_stage1_b o (bcast d) p q) Cpp.triangle_filter_pi_relative (absolute_bv (bcast d)) in
  certifies (sign_from_Z s) (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) /\
  (s <> uncertain_lane -> tfin o /\ tfin d /\ tfin p /\ tfin q).
Proof.
  intros o d p q s. destruct (triangle_pi_filter_twin_sound o (bcast d) p q) as [C F]. fold s in C, F.
  destruct (Z.eq_dec s uncertain_lane) as [U|U].
  - split; [rewrite U; exact I | intros X; contradiction].
  - destruct (F U) as [Fo [Fd [Fp Fq]]]. destruct (bcast_twin d Fd) as [Fd' E].
    rewrite E in C. split; [exact C | intros _; tsplit; assumption].
Qed.

(** Lanes 0–2 of [triangle_compensated_lanes] (o broadcast): a finite radius encloses π(p, q). *)
Corollary triangle_pi_lane_compensated_twin_sound : forall o d p q : TVec,
  let e := det3_enclosure_b (pi_stage2_b (bcast o) d p q) Cpp.triangle_compensated_relative (absolute_bv d) in
  fin (radiusb e) = true ->
  tfin o /\ tfin d /\ tfin p /\ tfin q /\ encloses (enc_R e) (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)).
Proof.
  intros o d p q e H. destruct (triangle_pi_compensated_twin_sound (bcast o) d p q H) as [Fo [Fd [Fp [Fq C]]]].
  destruct (bcast_twin o Fo) as [Fo' E]. rewrite E in C. tsplit; assumption.
Qed.

(** den = (lane 0 + lane 1) + lane 2 of [triangle_compensated_lanes]. *)
Corollary triangle_den_lane_compensated_twin_sound : forall o d a b c : TVec,
  let e := det3_enclosure_b (den_stage2_b (bcast o) d a b c) Cpp.triangle_compensated_den_relative (absolute_bv d) in
  fin (radiusb e) = true ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  encloses (enc_R e) (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros o d a b c e H. destruct (triangle_den_compensated_twin_sound (bcast o) d a b c H) as [Fo [Fd [Fa [Fb [Fc C]]]]].
  destruct (bcast_twin o Fo) as [Fo' E]. rewrite E in C. tsplit; assumption.
Qed.

Lemma num_stage2_lane_twin : forall o a b c, fin (clb (num_stage2_lane_b o a b c)) = true ->
  fin (cmb (num_stage2_lane_b o a b c)) = true ->
  tfin o /\ tfin a /\ tfin b /\ tfin c /\
  ctw (num_stage2_lane_b o a b c) (num_stage2 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz] H Hm. unfold num_stage2_lane_b, bcast in *. cbn [tx ty tz] in *.
  stage2_leaves H Hm.
Qed.

(** Lane 3 of [triangle_compensated_lanes]: a finite radius encloses num. *)
Theorem triangle_num_lane_compensated_twin_sound : forall o a b c : TVec,
  let e := det3_enclosure_b (num_stage2_lane_b o a b c) Cpp.triangle_compensated_relative (absolute_bv (ehigh a o)) in
  fin (radiusb e) = true ->
  tfin o /\ tfin a /\ tfin b /\ tfin c /\ encloses (enc_R e) (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof. intros o a b c. exact (num_compensated_twin_gen _ o a b c (num_stage2_lane_twin o a b c)). Qed.

(** ** The fast path's stage-1 signs, taken from stage 2's high parts ([filter_view]). *)

(** [filter_view(t)] = {t.h, t.m}. *)
Definition fview (t : CTermB) : FTermB := {| fvb := chb t; fmb := cmb t |}.

(** Stage 2's high parts are stage 1's operations, except that a difference is TwoSum(a.h, −b.h).hi,
    i.e. a.h ⊕ (−b.h), where stage 1 has a.v ⊖ b.v (the same bits, not the same Flocq term). *)
Definition term_subn_b (a b : FTermB) : FTermB :=
  {| fvb := fadd (fvb a) (fneg (fvb b)); fmb := fadd (fmb a) (fmb b) |}.
Definition det3n_b (x0 x1 x2 y0 y1 y2 z0 z1 z2 : float) : FTermB :=
  term_add_b (term_add_b (leaf_scale_b x0 (term_subn_b (leaf_mul_b y1 z2) (leaf_mul_b y2 z1)))
                         (leaf_scale_b x1 (term_subn_b (leaf_mul_b y2 z0) (leaf_mul_b y0 z2))))
             (leaf_scale_b x2 (term_subn_b (leaf_mul_b y0 z1) (leaf_mul_b y1 z0))).

Lemma cdet3_view : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  fview (cdet3_b xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2) =
  det3n_b xh0 xh1 xh2 yh0 yh1 yh2 zh0 zh1 zh2.
Proof. reflexivity. Qed.

Lemma term_subn_back : forall a b, fin (fmb (term_subn_b a b)) = true -> fin (fmb a) = true /\ fin (fmb b) = true.
Proof. intros a b H. exact (fadd_fin _ _ H). Qed.

Lemma term_subn_tw : forall a b A B, ftw a A -> ftw b B -> fin (fmb (term_subn_b a b)) = true ->
  ftw (term_subn_b a b) (term_sub A B).
Proof.
  intros a b A B [Fva [Fma [Eva [Ema Da]]]] [Fvb [Fmb [Evb [Emb Db]]]] H. cbn [fmb term_subn_b] in H.
  pose proof (fadd_val _ _ H) as Vm.
  assert (Fn : fin (fneg (fvb b)) = true) by (rewrite fneg_fin; exact Fvb).
  assert (L : Rabs (RN (B2R (fvb a) + B2R (fneg (fvb b)))) <= B2R (fadd (fmb a) (fmb b))).
  { rewrite Vm, <- RN_abs, fneg_val. apply RN_le. eapply Rle_trans; [apply Rabs_triang|].
    rewrite Rabs_Ropp. lra. }
  destruct (fadd_dominated _ _ _ Fva Fn L) as [Fs Vs].
  unfold ftw, term_subn_b, term_sub. cbn [fvb fmb fv fm]. rewrite Vs in *.
  repeat split; try assumption.
  - rewrite fneg_val, Eva, Evb. reflexivity.
  - now rewrite Vm, Ema, Emb.
Qed.

Theorem det3n_twin : forall x0 x1 x2 y0 y1 y2 z0 z1 z2,
  fin (fmb (det3n_b x0 x1 x2 y0 y1 y2 z0 z1 z2)) = true ->
  (fin x0 = true /\ fin x1 = true /\ fin x2 = true /\ fin y0 = true /\ fin y1 = true /\ fin y2 = true /\
   fin z0 = true /\ fin z1 = true /\ fin z2 = true) /\
  ftw (det3n_b x0 x1 x2 y0 y1 y2 z0 z1 z2)
      (det3 (B2R x0) (B2R x1) (B2R x2) (B2R y0) (B2R y1) (B2R y2) (B2R z0) (B2R z1) (B2R z2)).
Proof.
  intros x0 x1 x2 y0 y1 y2 z0 z1 z2 H. unfold det3n_b in *.
  repeat match goal with
  | H : fin (fmb (term_subn_b ?a ?b)) = true |- _ =>
      tryif (have_fin (fmb a)) then fail else destruct (term_subn_back a b H)
  | _ => progress ftw_back
  end.
  split; [tsplit; assumption|]. unfold det3.
  repeat match goal with
  | |- ftw (term_add_b _ _) _ => apply term_add_tw
  | |- ftw (term_subn_b _ _) _ => apply term_subn_tw
  | |- ftw (leaf_scale_b _ _) _ => apply leaf_scale_tw
  | |- ftw (leaf_mul_b _ _) _ => apply leaf_mul_tw
  | |- _ => assumption
  end.
Qed.

(** The high parts of the leaves TwoDiff(v, o). *)
Ltac view_leaves T :=
  repeat match goal with
  | F : fin (fst (two_diff_b ?v ?o)) = true |- _ =>
      let E := fresh in destruct (two_diff_fst_twin v o F) as [? [? E]]; rewrite E in T; clear F E
  end.

Lemma pi_view_twin : forall o d p q, fin (fmb (fview (pi_stage2_b o d p q))) = true ->
  tfin o /\ tfin d /\ tfin p /\ tfin q /\
  ftw (fview (pi_stage2_b o d p q)) (pi_stage1 (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)).
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [qx qy qz] H. unfold pi_stage2_b in *. cbn [tx ty tz] in *.
  rewrite cdet3_view in *.
  destruct (det3n_twin _ _ _ _ _ _ _ _ _ H) as [[? [? [? [? [? [? [? [? ?]]]]]]]] T].
  view_leaves T.
  unfold tfin. cbn [tx ty tz]. tsplit; try assumption.
Qed.

Lemma num_lane_view_twin : forall o a b c, fin (fmb (fview (num_stage2_lane_b o a b c))) = true ->
  tfin o /\ tfin a /\ tfin b /\ tfin c /\
  ftw (fview (num_stage2_lane_b o a b c)) (num_stage1 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)).
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz] H. unfold num_stage2_lane_b, bcast in *. cbn [tx ty tz] in *.
  rewrite cdet3_view in *.
  destruct (det3n_twin _ _ _ _ _ _ _ _ _ H) as [[? [? [? [? [? [? [? [? ?]]]]]]]] T].
  view_leaves T.
  repeat match goal with
  | F : fin (fadd fzero ?x) = true |- _ =>
      let E := fresh in destruct (bcast_val x F) as [? E]; rewrite E in T; clear F E
  end.
  unfold tfin. cbn [tx ty tz]. tsplit; try assumption.
Qed.

Lemma fview_nonneg : forall t, nonneg (cmb t) -> nonneg (fmb (fview t)).
Proof. intros t N. exact N. Qed.

Lemma cdet3_b_nonneg : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  nonneg (fmb (fview (cdet3_b xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2))).
Proof.
  intros. rewrite cdet3_view. unfold det3n_b, term_add_b, term_subn_b, leaf_scale_b, leaf_mul_b. cbn [fmb].
  repeat first [apply fadd_nonneg | apply fmul_nonneg | apply fabs_nonneg].
Qed.

Lemma pi_view_nonneg : forall o d p q, nonneg (fmb (fview (pi_stage2_b o d p q))).
Proof. intros. apply cdet3_b_nonneg. Qed.
Lemma num_lane_view_nonneg : forall o a b c, nonneg (fmb (fview (num_stage2_lane_b o a b c))).
Proof. intros. apply cdet3_b_nonneg. Qed.

(** Lanes 0–2 of [triangle_compensated_lanes] (o broadcast), their stage-1 view: a sign certified by
    [det3_filter_lanes(filter_view(lanes), π, A)] is the exact sign of π(p, q). *)
Theorem triangle_pi_lane_view_filter_twin_sound : forall o d p q : TVec,
  let s := det3_filter_lanes_b (fview (pi_stage2_b (bcast o) d p q)) Cpp.triangle_filter_pi_relative (absolute_bv d) in
  certifies (sign_from_Z s) (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) /\
  (s <> uncertain_lane -> tfin o /\ tfin d /\ tfin p /\ tfin q).
Proof.
  intros o d p q. cbv zeta. destruct cpp_triangle_constants as [_ [_ [_ [_ [FC [NC _]]]]]].
  apply (filter_twin_sound_gen _ (pi_stage1 (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) _ _ _ _ FC NC
           (pi_view_nonneg (bcast o) d p q) (absolute_bv_nonneg _)).
  - intros F. destruct (pi_view_twin (bcast o) d p q F) as [Fo [? [? [? T]]]].
    destruct (bcast_twin o Fo) as [? Eo]. rewrite Eo in T. split; [tsplit; assumption | exact T].
  - intros FA _. rewrite cpp_triangle_filter_pi_relative, (proj2 (absolute_bv_twin d FA)).
    apply pi_filter_sound; apply tvec_R_doubles.
Qed.

(** Lane 3 (num), its stage-1 view with the num constant. *)
Theorem triangle_num_lane_view_filter_twin_sound : forall o a b c : TVec,
  let s := det3_filter_lanes_b (fview (num_stage2_lane_b o a b c)) Cpp.triangle_filter_num_relative
                               (absolute_bv (ehigh a o)) in
  certifies (sign_from_Z s) (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) /\
  (s <> uncertain_lane -> tfin o /\ tfin a /\ tfin b /\ tfin c).
Proof.
  intros o a b c. cbv zeta. destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [FC [NC _]]]]]]]].
  apply (filter_twin_sound_gen _ (num_stage1 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) _ _ _ _ FC NC
           (num_lane_view_nonneg o a b c) (absolute_bv_nonneg _)).
  - intros F. destruct (num_lane_view_twin o a b c F) as [? [? [? [? T]]]]. split; [tsplit; assumption | exact T].
  - intros FA _. rewrite cpp_triangle_filter_num_relative, (proj2 (proj2 (ehigh_twin a o FA))).
    apply num_filter_sound; apply tvec_R_doubles.
Qed.

(** den = (lane 0 + lane 1) + lane 2, its stage-1 view with the den constant. *)
Theorem triangle_den_lane_view_filter_twin_sound : forall o d a b c : TVec,
  let s := det3_filter_lanes_b (fview (den_stage2_b (bcast o) d a b c)) Cpp.triangle_filter_den_relative
                               (absolute_bv d) in
  certifies (sign_from_Z s) (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) /\
  (s <> uncertain_lane -> tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c).
Proof.
  intros o d a b c. cbv zeta.
  destruct cpp_triangle_constants as [_ [_ [_ [_ [_ [_ [_ [_ [FC [NC _]]]]]]]]]].
  assert (V : fview (den_stage2_b (bcast o) d a b c) =
              term_add_b (term_add_b (fview (pi_stage2_b (bcast o) d b c)) (fview (pi_stage2_b (bcast o) d c a)))
                         (fview (pi_stage2_b (bcast o) d a b))) by reflexivity.
  assert (N : nonneg (fmb (fview (den_stage2_b (bcast o) d a b c)))).
  { rewrite V. apply (fadd_nonneg (fmb (term_add_b _ _)) (fmb (fview (pi_stage2_b (bcast o) d a b))));
      [apply fadd_nonneg|]; apply pi_view_nonneg. }
  apply (filter_twin_sound_gen _ (den_stage1 (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) _ _ _ _ FC NC
           N (absolute_bv_nonneg _)).
  - intros H. rewrite V in *. unfold den_stage1.
    destruct (term_add_back _ _ H) as [H01 H2]. destruct (term_add_back _ _ H01) as [H0 H1].
    destruct (pi_view_twin _ _ _ _ H0) as [Fo [Fd [Fb [Fc T0]]]].
    destruct (pi_view_twin _ _ _ _ H1) as [_ [_ [_ [Fa T1]]]].
    destruct (pi_view_twin _ _ _ _ H2) as [_ [_ [_ [_ T2]]]].
    destruct (bcast_twin o Fo) as [Fo' Eo]. rewrite Eo in T0, T1, T2.
    split; [tsplit; assumption | ftw_fwd].
  - intros FA _. rewrite cpp_triangle_filter_den_relative, (proj2 (absolute_bv_twin d FA)).
    apply den_filter_sound; apply tvec_R_doubles.
Qed.
