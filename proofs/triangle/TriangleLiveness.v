(** * Liveness of the ray–triangle stages 1 and 2: each does certify, on a stated class of inputs.

    The soundness theorems of TriangleFilter.v, TriangleCompensated.v and TriangleTwins.v say that what a stage
    certifies is true; a stage that never certified would satisfy them.  These theorems say the converse on a
    class of inputs, for the twins of TriangleTwins.v (hence, by the differential runner, for the compiled C++
    of kernel/src/core/det3_stages.hpp and ray_triangle_stages.hpp): with every input a finite double of
    magnitude at most 2^300 (so that nothing overflows), V the exact value (π(p, q), num or den),
    P the permanent of the computed leaves Σ|x_i|·(|y_j z_k| + |y_k z_j|) (for den: the sum of the three π's)
    and X = Σ|x_i| of the outer vector (d for the π's and den, ê_a = a ⊖ o for num):

    - stage 1, [det3_filter_lanes] on the [FilterTerm] twins ([triangle_pi_filter_live],
      [triangle_num_filter_live], [triangle_den_filter_live]): certain when |V| > 2^-48·P + 2^-1068·X + 2^-1067;
    - stage 2, [det3_enclosure] then [enclosure_sign] on the [CompensatedTerm] twins
      ([triangle_pi_compensated_live], [triangle_num_compensated_live], [triangle_den_compensated_live]):
      certain when |V| > 2^-95·P + 2^-1067·X + 2^-1066.

    The bounds are the error constants read backwards: 2^-48 = 32u covers twice the filter's bound C·m for
    C = 8u, 9u, 10u (π, num, den), and 2^-95 = 2048u² four times stage 2's radius K·m for K = 128u², 256u²;
    a constant made twice larger (or a magnitude computed from the wrong products) makes one of them fail.
    The absolute parts: A = (K_A ⊗ S) ⊕ U_A ≈ 32η·X + 64η. *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneCascade PlaneClassification FloatCore ConstantsCpp
  PlaneTwins TriangleFilter TriangleCompensated TriangleTwins PlaneLiveness.
Open Scope R_scope.

(** ** The model: upper bounds of the magnitude and of the absolute term *)

(** The permanent of the leaves, which the computed magnitude m approximates from above. *)
Definition perm3 (x0 x1 x2 y0 y1 y2 z0 z1 z2 : R) : R :=
  Rabs x0 * (Rabs (y1 * z2) + Rabs (y2 * z1)) + Rabs x1 * (Rabs (y2 * z0) + Rabs (y0 * z2)) +
  Rabs x2 * (Rabs (y0 * z1) + Rabs (y1 * z0)).
Definition perm3v (x y z : vec3) : R := perm3 (vx x) (vy x) (vz x) (vx y) (vy y) (vz y) (vx z) (vy z) (vz z).
Definition sumabs (x : vec3) : R := Rabs (vx x) + Rabs (vy x) + Rabs (vz x).

Lemma perm3v_nonneg : forall x y z, 0 <= perm3v x y z.
Proof.
  intros. unfold perm3v, perm3.
  repeat match goal with |- context [Rabs ?a] => pose proof (Rabs_pos a); fail | _ => idtac end.
  assert (forall a b c, 0 <= Rabs a * (Rabs b + Rabs c)).
  { intros. apply Rmult_le_pos; [apply Rabs_pos|]. pose proof (Rabs_pos b). pose proof (Rabs_pos c). lra. }
  repeat apply Rplus_le_le_0_compat; apply H.
Qed.

Lemma sumabs_nonneg : forall x, 0 <= sumabs x.
Proof. intros. unfold sumabs. pose proof (Rabs_pos (vx x)). pose proof (Rabs_pos (vy x)). pose proof (Rabs_pos (vz x)). lra. Qed.

(** A magnitude: a non-negative double. *)
Definition mag (m : R) : Prop := binary64 m /\ 0 <= m.

Lemma leaf_mul_m : forall y z, mag (fm (leaf_mul y z)) /\ fm (leaf_mul y z) <= (1 + u) * Rabs (y * z) + eta.
Proof.
  intros. unfold leaf_mul. cbn [fm]. split; [split; [apply binary64_abs_RN | apply Rabs_pos]|].
  pose proof (RN_err (y * z)). pose proof (Rabs_triang_inv (RN (y * z)) (y * z)). lra.
Qed.

Lemma term_add_m : forall a b, mag (fm a) -> mag (fm b) ->
  mag (fm (term_add a b)) /\ fm (term_add a b) <= (1 + u) * (fm a + fm b).
Proof.
  intros a b [Ba Pa] [Bb Pb]. unfold term_add. cbn [fm].
  split; [split; [apply binary64_RN | apply RN_nonneg; lra] | apply RN_sum_upper; [exact Ba | exact Bb | lra]].
Qed.

(** A difference has a sum's magnitude m = RN(m_a + m_b). *)
Lemma term_sub_m : forall a b, mag (fm a) -> mag (fm b) ->
  mag (fm (term_sub a b)) /\ fm (term_sub a b) <= (1 + u) * (fm a + fm b).
Proof. intros a b. exact (term_add_m a b). Qed.

Lemma leaf_scale_m : forall x c, mag (fm c) ->
  mag (fm (leaf_scale x c)) /\ fm (leaf_scale x c) <= (1 + u) * (Rabs x * fm c) + eta.
Proof.
  intros x c [Bc Pc]. unfold leaf_scale. cbn [fm].
  assert (0 <= Rabs x * fm c) by (apply Rmult_le_pos; [apply Rabs_pos | exact Pc]).
  split; [split; [apply binary64_RN | apply RN_nonneg; lra] | apply RN_upper; lra].
Qed.

(** One outer term |x|·(cross magnitude). *)
Lemma outer_m : forall x yj zk yk zj,
  let o := leaf_scale x (term_sub (leaf_mul yj zk) (leaf_mul yk zj)) in
  mag (fm o) /\
  fm o <= (1 + u) * ((1 + u) * (1 + u)) * (Rabs x * (Rabs (yj * zk) + Rabs (yk * zj))) +
          2 * ((1 + u) * (1 + u)) * (eta * Rabs x) + eta.
Proof.
  intros. subst o. pose proof u_pos. pose proof eta_pos. pose proof (Rabs_pos x).
  destruct (leaf_mul_m yj zk) as [M1 U1]. destruct (leaf_mul_m yk zj) as [M2 U2].
  destruct (term_sub_m _ _ M1 M2) as [M3 U3].
  destruct (leaf_scale_m x _ M3) as [M4 U4]. split; [exact M4|].
  set (c := fm (term_sub (leaf_mul yj zk) (leaf_mul yk zj))) in *.
  assert (Uc : c <= (1 + u) * (1 + u) * (Rabs (yj * zk) + Rabs (yk * zj)) + 2 * (1 + u) * eta) by nra.
  assert (Xc : Rabs x * c <= Rabs x * ((1 + u) * (1 + u) * (Rabs (yj * zk) + Rabs (yk * zj)) + 2 * (1 + u) * eta))
    by (apply Rmult_le_compat_l; lra).
  assert (E : (1 + u) * (Rabs x * ((1 + u) * (1 + u) * (Rabs (yj * zk) + Rabs (yk * zj)) + 2 * (1 + u) * eta)) =
              (1 + u) * ((1 + u) * (1 + u)) * (Rabs x * (Rabs (yj * zk) + Rabs (yk * zj))) +
              2 * ((1 + u) * (1 + u)) * (eta * Rabs x)) by ring.
  assert (0 <= 1 + u) by lra.
  assert ((1 + u) * (Rabs x * c) <= (1 + u) * (Rabs x * ((1 + u) * (1 + u) * (Rabs (yj * zk) + Rabs (yk * zj)) +
            2 * (1 + u) * eta))) by (apply Rmult_le_compat_l; lra).
  lra.
Qed.

(** The stage-1 magnitude of a determinant: m ≤ (1 + 2^-40)·P + 9η·X + 9η. *)
Lemma det3v_magnitude_upper : forall x y z,
  mag (fm (det3v x y z)) /\
  fm (det3v x y z) <= (1 + / 1099511627776) * perm3v x y z + 9 * (eta * sumabs x) + 9 * eta.
Proof.
  intros [x0 x1 x2] [y0 y1 y2] [z0 z1 z2]. unfold det3v, det3, perm3v, perm3, sumabs. cbn [vx vy vz].
  pose proof u_pos. pose proof eta_pos.
  destruct (outer_m x0 y1 z2 y2 z1) as [M0 U0]. destruct (outer_m x1 y2 z0 y0 z2) as [M1 U1].
  destruct (outer_m x2 y0 z1 y1 z0) as [M2 U2].
  destruct (term_add_m _ _ M0 M1) as [M01 U01]. destruct (term_add_m _ _ M01 M2) as [M U].
  split; [exact M|].
  set (o0 := fm (leaf_scale x0 _)) in *. set (o1 := fm (leaf_scale x1 _)) in *. set (o2 := fm (leaf_scale x2 _)) in *.
  set (s := fm (term_add (leaf_scale x0 _) (leaf_scale x1 _))) in *.
  set (Q0 := Rabs x0 * (Rabs (y1 * z2) + Rabs (y2 * z1))) in *.
  set (Q1 := Rabs x1 * (Rabs (y2 * z0) + Rabs (y0 * z2))) in *.
  set (Q2 := Rabs x2 * (Rabs (y0 * z1) + Rabs (y1 * z0))) in *.
  assert (0 <= Q0) by (unfold Q0; apply Rmult_le_pos; [apply Rabs_pos | pose proof (Rabs_pos (y1 * z2)); pose proof (Rabs_pos (y2 * z1)); lra]).
  assert (0 <= Q1) by (unfold Q1; apply Rmult_le_pos; [apply Rabs_pos | pose proof (Rabs_pos (y2 * z0)); pose proof (Rabs_pos (y0 * z2)); lra]).
  assert (0 <= Q2) by (unfold Q2; apply Rmult_le_pos; [apply Rabs_pos | pose proof (Rabs_pos (y0 * z1)); pose proof (Rabs_pos (y1 * z0)); lra]).
  assert (0 <= eta * Rabs x0) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (0 <= eta * Rabs x1) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (0 <= eta * Rabs x2) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  destruct M0 as [_ P0]. destruct M1 as [_ P1]. destruct M2 as [_ P2].
  assert (S : s <= (1 + u) * (o0 + o1)) by exact U01.
  assert (T : fm (term_add (term_add (leaf_scale x0 (term_sub (leaf_mul y1 z2) (leaf_mul y2 z1)))
                                      (leaf_scale x1 (term_sub (leaf_mul y2 z0) (leaf_mul y0 z2))))
                            (leaf_scale x2 (term_sub (leaf_mul y0 z1) (leaf_mul y1 z0))))
              <= (1 + u) * ((1 + u) * (o0 + o1) + o2)).
  { eapply Rle_trans; [exact U|]. apply Rmult_le_compat_l; lra. }
  replace (eta * (Rabs x0 + Rabs x1 + Rabs x2)) with (eta * Rabs x0 + eta * Rabs x1 + eta * Rabs x2) by ring.
  rewrite u_val in *. lra.
Qed.

(** The absolute term: A = (K_A ⊗ S) ⊕ U_A ≤ 33η·X + 66η. *)
Lemma absolute_v_upper : forall x, doubles3 x -> mag (absolute_v x) /\ absolute_v x <= 33 * (eta * sumabs x) + 66 * eta.
Proof.
  intros [x0 x1 x2] [B0 [B1 B2]]. cbn [vx vy vz] in *. unfold absolute_v, absolute_term, sumabs. cbn [vx vy vz].
  pose proof u_pos. pose proof eta_pos.
  pose proof (Rabs_pos x0). pose proof (Rabs_pos x1). pose proof (Rabs_pos x2).
  assert (A0 := binary64_abs _ B0). assert (A1 := binary64_abs _ B1). assert (A2 := binary64_abs _ B2).
  pose proof (RN_sum_upper _ _ A0 A1 ltac:(lra)) as S1.
  set (s1 := RN (Rabs x0 + Rabs x1)) in *.
  assert (Ps1 : 0 <= s1) by (apply RN_nonneg; lra).
  pose proof (RN_sum_upper s1 (Rabs x2) (binary64_RN _) A2 ltac:(lra)) as S2.
  set (s := RN (s1 + Rabs x2)) in *.
  assert (Ps : 0 <= s) by (apply RN_nonneg; lra).
  assert (Hs : s <= (1 + u) * (1 + u) * (Rabs x0 + Rabs x1 + Rabs x2)) by nra.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta.
  assert (Pk : 0 <= 32 * eta * s) by nra.
  pose proof (RN_upper _ Pk) as K1.
  set (k := RN (32 * eta * s)) in *.
  assert (Pk' : 0 <= k) by (apply RN_nonneg; lra).
  assert (B64 : binary64 (64 * eta)) by (rewrite <- triangle_absolute_eta; apply binary64_triangle_absolute).
  pose proof (RN_sum_upper k (64 * eta) (binary64_RN _) B64 ltac:(lra)) as K2.
  split; [split; [apply binary64_RN | apply RN_nonneg; lra]|].
  assert (Es : 32 * eta * s <= 32 * eta * ((1 + u) * (1 + u) * (Rabs x0 + Rabs x1 + Rabs x2)))
    by (apply Rmult_le_compat_l; lra).
  replace (32 * eta * ((1 + u) * (1 + u) * (Rabs x0 + Rabs x1 + Rabs x2)))
    with (32 * ((1 + u) * (1 + u)) * (eta * (Rabs x0 + Rabs x1 + Rabs x2))) in Es by ring.
  assert (0 <= eta * (Rabs x0 + Rabs x1 + Rabs x2)) by (apply Rmult_le_pos; lra).
  rewrite u_val in *. lra.
Qed.

(** Stage 1: twice the bound (C ⊗ m) ⊕ A, for C ≤ 10u and the magnitude and absolute term above. *)
Lemma det3_bound_upper : forall C m A P X, 0 <= C <= 10 * u -> mag m -> mag A -> 0 <= P -> 0 <= X ->
  m <= (1 + / 1073741824) * P + 32 * (eta * X) + 32 * eta -> A <= 33 * (eta * X) + 66 * eta ->
  2 * RN (RN (C * m) + A) <= bpow radix2 (-48) * P + bpow radix2 (-1068) * X + bpow radix2 (-1067).
Proof.
  intros C m A P X [C0 C1] [Bm Pm] [BA PA] PP PX Um UA.
  pose proof u_pos. pose proof eta_pos. assert (0 <= eta * X) by nra.
  pose proof (bound_upper C m A C0 Pm BA PA) as B.
  assert (Cm : C * m <= 10 * u * ((1 + / 1073741824) * P + 32 * (eta * X) + 32 * eta))
    by (apply Rmult_le_compat; lra).
  assert (E48 : bpow radix2 (-48) = 32 * u) by (rewrite u_val; simpl bpow; lra).
  assert (E1068 : bpow radix2 (-1068) * X = 128 * (eta * X)).
  { unfold eta. replace (-1068)%Z with (7 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. }
  assert (E1067 : bpow radix2 (-1067) = 256 * eta).
  { unfold eta. replace (-1067)%Z with (8 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. }
  rewrite E48, E1068, E1067.
  set (R := RN (RN (C * m) + A)) in *. set (Cm' := C * m) in *. clearbody R Cm'.
  rewrite u_val in *. lra.
Qed.

(** Stage 2: four times the radius (K ⊗ m) ⊕ A, for K ≤ 256u². *)
Lemma det3_radius_upper : forall K m A P X, 0 <= K <= 256 * (u * u) -> mag m -> mag A -> 0 <= P -> 0 <= X ->
  m <= (1 + / 1073741824) * P + 32 * (eta * X) + 32 * eta -> A <= 33 * (eta * X) + 66 * eta ->
  4 * RN (RN (K * m) + A) <= bpow radix2 (-95) * P + bpow radix2 (-1067) * X + bpow radix2 (-1066).
Proof.
  intros K m A P X [K0 K1] [Bm Pm] [BA PA] PP PX Um UA.
  pose proof u_pos. pose proof eta_pos. assert (0 <= eta * X) by nra.
  pose proof (bound_upper K m A K0 Pm BA PA) as B.
  assert (Km : K * m <= 256 * (u * u) * ((1 + / 1073741824) * P + 32 * (eta * X) + 32 * eta))
    by (apply Rmult_le_compat; lra).
  assert (E95 : bpow radix2 (-95) = 2048 * (u * u)) by (rewrite u_val; simpl bpow; lra).
  assert (E1067 : bpow radix2 (-1067) * X = 256 * (eta * X)).
  { unfold eta. replace (-1067)%Z with (8 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. }
  assert (E1066 : bpow radix2 (-1066) = 512 * eta).
  { unfold eta. replace (-1066)%Z with (9 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. }
  rewrite E95, E1067, E1066.
  set (R := RN (RN (K * m) + A)) in *. set (Km' := K * m) in *. clearbody R Km'.
  rewrite u_val in *. lra.
Qed.

(** The magnitudes of the query's values (shared by both stages: [stage2_filter_view]). *)
Lemma pi_magnitude_upper : forall o d p q,
  mag (fm (pi_stage1 o d p q)) /\
  fm (pi_stage1 o d p q) <= (1 + / 1073741824) * perm3v d (rsub p o) (rsub q o) + 32 * (eta * sumabs d) + 32 * eta.
Proof.
  intros. unfold pi_stage1. destruct (det3v_magnitude_upper d (rsub p o) (rsub q o)) as [M U]. split; [exact M|].
  pose proof eta_pos. pose proof (sumabs_nonneg d). assert (0 <= eta * sumabs d) by nra.
  pose proof (perm3v_nonneg d (rsub p o) (rsub q o)). lra.
Qed.

Lemma num_magnitude_upper : forall o a b c,
  mag (fm (num_stage1 o a b c)) /\
  fm (num_stage1 o a b c) <= (1 + / 1073741824) * perm3v (rsub a o) (rsub b o) (rsub c o) + 32 * (eta * sumabs (rsub a o)) + 32 * eta.
Proof.
  intros. unfold num_stage1. destruct (det3v_magnitude_upper (rsub a o) (rsub b o) (rsub c o)) as [M U].
  split; [exact M|].
  pose proof eta_pos. pose proof (sumabs_nonneg (rsub a o)). assert (0 <= eta * sumabs (rsub a o)) by nra.
  pose proof (perm3v_nonneg (rsub a o) (rsub b o) (rsub c o)). lra.
Qed.

Definition den_perm (o d a b c : vec3) : R :=
  perm3v d (rsub b o) (rsub c o) + perm3v d (rsub c o) (rsub a o) + perm3v d (rsub a o) (rsub b o).

Lemma den_magnitude_upper : forall o d a b c,
  mag (fm (den_stage1 o d a b c)) /\
  fm (den_stage1 o d a b c) <= (1 + / 1073741824) * den_perm o d a b c + 32 * (eta * sumabs d) + 32 * eta.
Proof.
  intros. unfold den_stage1, den_perm, pi_stage1.
  destruct (det3v_magnitude_upper d (rsub b o) (rsub c o)) as [Ma Ua].
  destruct (det3v_magnitude_upper d (rsub c o) (rsub a o)) as [Mb Ub].
  destruct (det3v_magnitude_upper d (rsub a o) (rsub b o)) as [Mc Uc].
  destruct (term_add_m _ _ Ma Mb) as [Mab Uab]. destruct (term_add_m _ _ Mab Mc) as [M U].
  split; [exact M|].
  pose proof u_pos. pose proof eta_pos. pose proof (sumabs_nonneg d). assert (0 <= eta * sumabs d) by nra.
  pose proof (perm3v_nonneg d (rsub b o) (rsub c o)). pose proof (perm3v_nonneg d (rsub c o) (rsub a o)).
  pose proof (perm3v_nonneg d (rsub a o) (rsub b o)).
  set (ma := fm (det3v d (rsub b o) (rsub c o))) in *. set (mb := fm (det3v d (rsub c o) (rsub a o))) in *.
  set (mc := fm (det3v d (rsub a o) (rsub b o))) in *.
  set (mab := fm (term_add (det3v d (rsub b o) (rsub c o)) (det3v d (rsub c o) (rsub a o)))) in *.
  destruct Mab as [_ Pab]. destruct Mc as [_ Pc].
  assert (T : fm (term_add (term_add (det3v d (rsub b o) (rsub c o)) (det3v d (rsub c o) (rsub a o)))
                           (det3v d (rsub a o) (rsub b o))) <= (1 + u) * ((1 + u) * (ma + mb) + mc)).
  { eapply Rle_trans; [exact U|]. apply Rmult_le_compat_l; lra. }
  rewrite u_val in *. lra.
Qed.

(** ** Stage 1 *)

(** In the model: certain when |V| exceeds twice the bound. *)
Lemma det3_filter_live_model : forall t C A V, Rabs (fv t - V) <= det3_bound t C A ->
  2 * det3_bound t C A < Rabs V -> det3_filter_lanes t C A <> uncertain_lane.
Proof. intros t C A V. exact (sign_lanes_live (fv t) (det3_bound t C A) V). Qed.

(** The twin computes the model's decision when its bound is finite. *)
Lemma det3_filter_lanes_b_model : forall t T C A, fin (fadd (fmul C (fmb t)) A) = true -> ftw t T ->
  det3_filter_lanes_b t C A = det3_filter_lanes T (B2R C) (B2R A).
Proof.
  intros t T C A FB [Fv [_ [Ev [Em _]]]]. unfold det3_filter_lanes_b, det3_filter_lanes, det3_bound. cbv zeta.
  destruct (fadd_fin _ _ FB) as [Fp FA].
  rewrite (flt_val _ (fvb t)) by assumption.
  rewrite (flt_val (fvb t)) by (rewrite ?fneg_fin; assumption).
  rewrite fneg_val, (fadd_val _ _ FB), (fmul_val _ _ Fp), Ev, Em. reflexivity.
Qed.

(** A vector of finite doubles of magnitude at most 2^k. *)
Definition tbnd (k : Z) (v : TVec) : Prop := fbnd k (tx v) /\ fbnd k (ty v) /\ fbnd k (tz v).

Lemma tsub_model : forall v o, tfin v -> tfin o -> fin (tx (tsub v o)) = true -> fin (ty (tsub v o)) = true ->
  fin (tz (tsub v o)) = true -> tvec_R (tsub v o) = rsub (tvec_R v) (tvec_R o).
Proof. intros v o _ _ Fx Fy Fz. exact (proj2 (proj2 (tsub_twin v o Fx Fy Fz))). Qed.

(** The filter's last step, from a finite bound of a twin whose model encloses V. *)
Lemma filter_live_step : forall t T C A V,
  fin (fadd (fmul C (fmb t)) A) = true -> ftw t T ->
  Rabs (fv T - V) <= det3_bound T (B2R C) (B2R A) ->
  2 * det3_bound T (B2R C) (B2R A) < Rabs V ->
  det3_filter_lanes_b t C A <> uncertain_lane.
Proof.
  intros t T C A V FB Tw E L. rewrite (det3_filter_lanes_b_model _ _ _ _ FB Tw).
  exact (det3_filter_live_model _ _ _ V E L).
Qed.

Lemma fin_bound_parts : forall C m A, fbnd 1000 (fadd (fmul C m) A) ->
  fin (fadd (fmul C m) A) = true /\ fin m = true /\ fin A = true.
Proof.
  intros C m A [F _]. destruct (fadd_fin _ _ F) as [Fp FA]. destruct (fmul_fin _ _ Fp) as [_ Fm]. tauto.
Qed.

Ltac unfold_stage1 :=
  unfold den_stage1_b, pi_stage1_b, num_stage1_b, det3_bv, det3_b, absolute_bv, absolute_term_b, tsub,
    term_add_b, term_sub_b, leaf_scale_b, leaf_mul_b; cbn [tx ty tz fmb fvb].

(** π(p, q) = d·((p − o) × (q − o)): for inputs of magnitude at most 2^300, the filter with π's constant is
    certain when |π| > 2^-48·P + 2^-1068·Σ|d_i| + 2^-1067. *)
Theorem triangle_pi_filter_live : forall o d p q : TVec,
  tbnd 300 o -> tbnd 300 d -> tbnd 300 p -> tbnd 300 q ->
  bpow radix2 (-48) * perm3v (tvec_R d) (rsub (tvec_R p) (tvec_R o)) (rsub (tvec_R q) (tvec_R o)) +
    bpow radix2 (-1068) * sumabs (tvec_R d) + bpow radix2 (-1067) <
    Rabs (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) ->
  det3_filter_lanes_b (pi_stage1_b o d p q) Cpp.triangle_filter_pi_relative (absolute_bv d) <> uncertain_lane.
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [qx qy qz] [O0 [O1 O2]] [D0 [D1 D2]] [P0 [P1 P2]] [Q0 [Q1 Q2]] L.
  cbn [tx ty tz] in *.
  set (o := TV ox oy oz) in *. set (d := TV dx dy dz) in *. set (p := TV px py pz) in *. set (q := TV qx qy qz) in *.
  assert (Fb : fbnd 1000 (fadd (fmul Cpp.triangle_filter_pi_relative (fmb (pi_stage1_b o d p q))) (absolute_bv d))).
  { subst o d p q. unfold_stage1. eapply fbnd_le; [fbnd_tac | lia]. }
  destruct (fin_bound_parts _ _ _ Fb) as [FB [Fm FA]].
  destruct (pi_stage1_twin _ _ _ _ Fm) as [_ [_ [_ [_ T]]]].
  apply (filter_live_step _ _ _ _ (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) FB T);
    rewrite cpp_triangle_filter_pi_relative, (proj2 (absolute_bv_twin _ FA)).
  { apply TriangleFilter.pi_filter_encloses; apply tvec_R_doubles. }
  destruct (pi_magnitude_upper (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) as [M U].
  destruct (absolute_v_upper (tvec_R d) (tvec_R_doubles d)) as [MA UA].
  eapply Rle_lt_trans; [| exact L]. unfold det3_bound.
  apply det3_bound_upper; try assumption; try apply perm3v_nonneg; try apply sumabs_nonneg.
  unfold triangle_filter_pi_relative. pose proof u_pos. lra.
Qed.

(** num = ê_a·(ê_b × ê_c), with the absolute term of ê_a = a ⊖ o. *)
Theorem triangle_num_filter_live : forall o a b c : TVec,
  tbnd 300 o -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  bpow radix2 (-48) * perm3v (rsub (tvec_R a) (tvec_R o)) (rsub (tvec_R b) (tvec_R o)) (rsub (tvec_R c) (tvec_R o)) +
    bpow radix2 (-1068) * sumabs (rsub (tvec_R a) (tvec_R o)) + bpow radix2 (-1067) <
    Rabs (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) ->
  det3_filter_lanes_b (num_stage1_b o a b c) Cpp.triangle_filter_num_relative (absolute_bv (tsub a o)) <> uncertain_lane.
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz] [O0 [O1 O2]] [A0 [A1 A2]] [B0 [B1 B2]] [C0 [C1 C2]] L.
  cbn [tx ty tz] in *.
  set (o := TV ox oy oz) in *. set (a := TV ax ay az) in *. set (b := TV bx by_ bz) in *. set (c := TV cx cy cz) in *.
  assert (Fb : fbnd 1000 (fadd (fmul Cpp.triangle_filter_num_relative (fmb (num_stage1_b o a b c)))
                               (absolute_bv (tsub a o)))).
  { subst o a b c. unfold_stage1. eapply fbnd_le; [fbnd_tac | lia]. }
  destruct (fin_bound_parts _ _ _ Fb) as [FB [Fm FA]].
  destruct (num_stage1_twin _ _ _ _ Fm) as [_ [_ [_ [_ T]]]].
  destruct (absolute_bv_twin _ FA) as [[F1 [F2 F3]] EA].
  destruct (tsub_twin a o F1 F2 F3) as [_ [_ Ea]].
  apply (filter_live_step _ _ _ _ (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) FB T);
    rewrite cpp_triangle_filter_num_relative, EA, Ea.
  { apply TriangleFilter.num_filter_encloses; apply tvec_R_doubles. }
  destruct (num_magnitude_upper (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) as [M U].
  assert (Dr : doubles3 (rsub (tvec_R a) (tvec_R o))) by (repeat split; apply binary64_RN).
  destruct (absolute_v_upper _ Dr) as [MA UA].
  eapply Rle_lt_trans; [| exact L]. unfold det3_bound.
  apply det3_bound_upper; try assumption; try apply perm3v_nonneg; try apply sumabs_nonneg.
  unfold triangle_filter_num_relative. pose proof u_pos. lra.
Qed.

(** den = (πa ⊕ πb) ⊕ πc, P the sum of the three π's permanents. *)
Theorem triangle_den_filter_live : forall o d a b c : TVec,
  tbnd 300 o -> tbnd 300 d -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  bpow radix2 (-48) * den_perm (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) +
    bpow radix2 (-1068) * sumabs (tvec_R d) + bpow radix2 (-1067) <
    Rabs (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) ->
  det3_filter_lanes_b (den_stage1_b o d a b c) Cpp.triangle_filter_den_relative (absolute_bv d) <> uncertain_lane.
Proof.
  intros [ox oy oz] [dx dy dz] [ax ay az] [bx by_ bz] [cx cy cz] [O0 [O1 O2]] [D0 [D1 D2]] [A0 [A1 A2]]
    [B0 [B1 B2]] [C0 [C1 C2]] L.
  cbn [tx ty tz] in *.
  set (o := TV ox oy oz) in *. set (d := TV dx dy dz) in *. set (a := TV ax ay az) in *. set (b := TV bx by_ bz) in *.
  set (c := TV cx cy cz) in *.
  assert (Fb : fbnd 1000 (fadd (fmul Cpp.triangle_filter_den_relative (fmb (den_stage1_b o d a b c))) (absolute_bv d))).
  { subst o d a b c. unfold_stage1. eapply fbnd_le; [fbnd_tac | lia]. }
  destruct (fin_bound_parts _ _ _ Fb) as [FB [Fm FA]].
  destruct (den_stage1_twin _ _ _ _ _ Fm) as [_ [_ [_ [_ [_ T]]]]].
  apply (filter_live_step _ _ _ _ (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) FB T);
    rewrite cpp_triangle_filter_den_relative, (proj2 (absolute_bv_twin _ FA)).
  { apply TriangleFilter.den_filter_encloses; apply tvec_R_doubles. }
  destruct (den_magnitude_upper (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) as [M U].
  destruct (absolute_v_upper (tvec_R d) (tvec_R_doubles d)) as [MA UA].
  eapply Rle_lt_trans; [| exact L]. unfold det3_bound.
  apply det3_bound_upper; try assumption; try apply sumabs_nonneg.
  - unfold triangle_filter_den_relative. pose proof u_pos. lra.
  - unfold den_perm. pose proof (perm3v_nonneg (tvec_R d) (rsub (tvec_R b) (tvec_R o)) (rsub (tvec_R c) (tvec_R o))).
    pose proof (perm3v_nonneg (tvec_R d) (rsub (tvec_R c) (tvec_R o)) (rsub (tvec_R a) (tvec_R o))).
    pose proof (perm3v_nonneg (tvec_R d) (rsub (tvec_R a) (tvec_R o)) (rsub (tvec_R b) (tvec_R o))). lra.
Qed.

(** ** Stage 2 *)

(** No overflow: bounds of a [CompensatedTerm] twin's three parts, operation by operation. *)
Definition cbnd (k : Z) (t : CTermB) : Prop := fbnd k (chb t) /\ fbnd k (clb t) /\ fbnd k (cmb t).

(** lia, after Z.max x x = x (lia alone fails on some nested maxima of equal arguments). *)
Ltac zlia := repeat rewrite Z.max_id; lia.

Ltac fbnd_tac_l := fbnd_gen ltac:(idtac; lia).

(** Each part of a leaf or a sum: [fbnd_tac_l] on the operation, then the exponent's slack. *)
Ltac cbnd_tac := split; [|split]; (eapply fbnd_le; [fbnd_tac_l | zlia]).

Lemma cleaf_mul_bnd : forall k yh yl zh zl, (0 <= k)%Z -> (2 * k + 3 <= 1023)%Z ->
  fbnd k yh -> fbnd k yl -> fbnd k zh -> fbnd k zl -> cbnd (2 * k + 3) (cleaf_mul_b yh yl zh zl).
Proof. intros. unfold cbnd, cleaf_mul_b, product_low_part_b. cbn [chb clb cmb]. cbnd_tac. Qed.

Lemma cleaf_scale_bnd : forall j k xh xl c, (0 <= j)%Z -> (0 <= k)%Z -> (j + k + 3 <= 1023)%Z ->
  fbnd j xh -> fbnd j xl -> cbnd k c -> cbnd (j + k + 3) (cleaf_scale_b xh xl c).
Proof.
  intros j k xh xl c Hj Hk H X L [Ch [Cl Cm]]. unfold cbnd, cleaf_scale_b, product_low_part_b. cbn [chb clb cmb].
  cbnd_tac.
Qed.

(** A sum and a difference of two terms: one proof, the difference being the sum of a negated high part. *)
Lemma cterm_add_sub_bnd : forall k a b, (0 <= k)%Z -> (k + 6 <= 1023)%Z -> cbnd k a -> cbnd k b ->
  cbnd (k + 6) (cterm_add_b a b) /\ cbnd (k + 6) (cterm_sub_b a b).
Proof.
  intros k a b Hk H [Ah [Al Am]] [Bh [Bl Bm]]. unfold cbnd, cterm_add_b, cterm_sub_b. cbn [chb clb cmb].
  split; cbnd_tac.
Qed.

Lemma cterm_add_bnd : forall k a b, (0 <= k)%Z -> (k + 6 <= 1023)%Z -> cbnd k a -> cbnd k b ->
  cbnd (k + 6) (cterm_add_b a b).
Proof. intros. now apply cterm_add_sub_bnd. Qed.

Lemma cterm_sub_bnd : forall k a b, (0 <= k)%Z -> (k + 6 <= 1023)%Z -> cbnd k a -> cbnd k b ->
  cbnd (k + 6) (cterm_sub_b a b).
Proof. intros. now apply cterm_add_sub_bnd. Qed.

Lemma cdet3_bnd : forall j xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  (0 <= j)%Z -> (3 * j + 24 <= 1023)%Z ->
  fbnd j xh0 -> fbnd j xl0 -> fbnd j xh1 -> fbnd j xl1 -> fbnd j xh2 -> fbnd j xl2 ->
  fbnd j yh0 -> fbnd j yl0 -> fbnd j yh1 -> fbnd j yl1 -> fbnd j yh2 -> fbnd j yl2 ->
  fbnd j zh0 -> fbnd j zl0 -> fbnd j zh1 -> fbnd j zl1 -> fbnd j zh2 -> fbnd j zl2 ->
  cbnd (3 * j + 24) (cdet3_b xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2).
Proof.
  intros. unfold cdet3_b.
  replace (3 * j + 24)%Z with ((3 * j + 18) + 6)%Z by lia. apply cterm_add_bnd; [lia | lia | |].
  - replace (3 * j + 18)%Z with ((3 * j + 12) + 6)%Z by lia. apply cterm_add_bnd; [lia | lia | |].
    + replace (3 * j + 12)%Z with (j + (2 * j + 9) + 3)%Z by lia. apply cleaf_scale_bnd; try lia; try assumption.
      replace (2 * j + 9)%Z with ((2 * j + 3) + 6)%Z by lia. apply cterm_sub_bnd; try lia; apply cleaf_mul_bnd; assumption || lia.
    + replace (3 * j + 12)%Z with (j + (2 * j + 9) + 3)%Z by lia. apply cleaf_scale_bnd; try lia; try assumption.
      replace (2 * j + 9)%Z with ((2 * j + 3) + 6)%Z by lia. apply cterm_sub_bnd; try lia; apply cleaf_mul_bnd; assumption || lia.
  - replace (3 * j + 18)%Z with (j + (2 * j + 9) + 3 + 6)%Z by lia.
    assert (cbnd (j + (2 * j + 9) + 3) (cleaf_scale_b xh2 xl2 (cterm_sub_b (cleaf_mul_b yh0 yl0 zh1 zl1)
                                                                        (cleaf_mul_b yh1 yl1 zh0 zl0)))) as [X [Y Z]].
    { apply cleaf_scale_bnd; try lia; try assumption.
      replace (2 * j + 9)%Z with ((2 * j + 3) + 6)%Z by lia. apply cterm_sub_bnd; try lia; apply cleaf_mul_bnd; assumption || lia. }
    split; [|split]; (eapply fbnd_le; [eassumption | lia]).
Qed.

Lemma two_diff_bnd : forall v o, fbnd 300 v -> fbnd 300 o ->
  fbnd 305 (fst (two_diff_b v o)) /\ fbnd 305 (snd (two_diff_b v o)).
Proof.
  intros v o V O. unfold two_diff_b.
  destruct (fbnd_two_sum 300 300 v (fneg o) V (fbnd_neg _ _ O) ltac:(lia) ltac:(lia) ltac:(lia)) as [A B].
  split; (eapply fbnd_le; [eassumption | lia]).
Qed.

Lemma fbnd_305 : forall x, fbnd 300 x -> fbnd 305 x.
Proof. intros x H. eapply fbnd_le; [exact H | lia]. Qed.
Lemma fbnd_zero_305 : fbnd 305 fzero.
Proof. eapply fbnd_le; [exact fbnd_zero | lia]. Qed.

Ltac leaves_305 :=
  repeat match goal with
  | H : fbnd 300 ?v, H' : fbnd 300 ?o |- _ =>
      lazymatch goal with
      | _ : fbnd 305 (fst (two_diff_b v o)) |- _ => fail
      | |- _ => destruct (two_diff_bnd v o H H')
      end
  end.

(** A stage-2 determinant of TwoDiff leaves of inputs of magnitude at most 2^300 (and of d's zero low
    parts): each leaf is bounded by 2^305, hence the determinant by 2^939. *)
Ltac stage2_bnd_tac :=
  cbn [tx ty tz] in *; cbv zeta;
  repeat match goal with
  | |- context [two_diff_b ?v ?o] =>
      lazymatch goal with
      | _ : fbnd 305 (fst (two_diff_b v o)) |- _ => fail
      | |- _ => destruct (two_diff_bnd v o ltac:(assumption) ltac:(assumption))
      end
  end;
  replace 939%Z with (3 * 305 + 24)%Z by reflexivity;
  apply cdet3_bnd; try lia; first [assumption | apply fbnd_305; assumption | exact fbnd_zero_305].

Lemma pi_stage2_bnd : forall o d p q, tbnd 300 o -> tbnd 300 d -> tbnd 300 p -> tbnd 300 q ->
  cbnd 939 (pi_stage2_b o d p q).
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [qx qy qz] [O0 [O1 O2]] [D0 [D1 D2]] [P0 [P1 P2]] [Q0 [Q1 Q2]].
  unfold pi_stage2_b. stage2_bnd_tac.
Qed.

Lemma num_stage2_bnd : forall o a b c, tbnd 300 o -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  cbnd 939 (num_stage2_b o a b c).
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz] [O0 [O1 O2]] [A0 [A1 A2]] [B0 [B1 B2]] [C0 [C1 C2]].
  unfold num_stage2_b. stage2_bnd_tac.
Qed.

Lemma den_stage2_bnd : forall o d a b c, tbnd 300 o -> tbnd 300 d -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  cbnd 951 (den_stage2_b o d a b c).
Proof.
  intros o d a b c O D A B C. unfold den_stage2_b.
  replace 951%Z with (945 + 6)%Z by reflexivity. apply cterm_add_bnd; [lia | lia | |].
  - replace 945%Z with (939 + 6)%Z by reflexivity. apply cterm_add_bnd; [lia | lia | |]; apply pi_stage2_bnd; assumption.
  - destruct (pi_stage2_bnd o d a b O D A B) as [X [Y Z]]. split; [|split]; (eapply fbnd_le; [eassumption | lia]).
Qed.

Lemma absolute_bv_bnd : forall x, tbnd 305 x -> fbnd 310 (absolute_bv x).
Proof.
  intros [x0 x1 x2] [X0 [X1 X2]]. cbn [tx ty tz] in *. unfold absolute_bv, absolute_term_b. cbn [tx ty tz].
  eapply fbnd_le; [fbnd_tac | lia].
Qed.

Lemma det3_enclosure_b_parts : forall t K A, fin (chb t) = true -> fin (clb t) = true ->
  hib (det3_enclosure_b t K A) = chb t /\ lob (det3_enclosure_b t K A) = clb t /\
  radiusb (det3_enclosure_b t K A) = fadd (fmul K (cmb t)) A.
Proof.
  intros t K A Fh Fl. unfold det3_enclosure_b. cbn [hib lob radiusb].
  rewrite !fle_largest_finite, Fh, Fl. repeat split.
Qed.

(** From bounded parts of a twin [t] of a model [T] with enclosure (K, A) of V: certain when V exceeds four
    times the radius. *)
Lemma compensated_live_step : forall t T K A V, (K = Cpp.triangle_compensated_relative \/
    K = Cpp.triangle_compensated_den_relative) ->
  cbnd 960 t -> fbnd 310 A -> (fin (clb t) = true -> fin (cmb t) = true -> ctw t T) ->
  encloses (TriangleCompensated.det3_enclosure T (B2R K) (B2R A)) V ->
  4 * RN (RN (B2R K * cm T) + B2R A) < Rabs V ->
  enclosure_sign_lanes_b (det3_enclosure_b t K A) <> uncertain_lane.
Proof.
  intros t T K A V HK [Bh [Bl Bm]] BA Tw E L.
  destruct (det3_enclosure_b_parts t K A (proj1 Bh) (proj1 Bl)) as [Eh [El Er]].
  assert (BR : fbnd 1000 (radiusb (det3_enclosure_b t K A))).
  { rewrite Er. destruct HK as [-> | ->]; eapply fbnd_le; [fbnd_tac | lia | fbnd_tac | lia]. }
  destruct (det3_enclosure_twin t K A (proj1 BR)) as [_ [_ [_ [_ EE]]]].
  pose proof (EE T (Tw (proj1 Bl) (proj1 Bm))) as ER.
  apply (enclosure_sign_live _ V); [rewrite Eh; eapply fbnd_le; [exact Bh | lia] |
                                    rewrite El; eapply fbnd_le; [exact Bl | lia] | exact BR | rewrite ER; exact E |].
  change (B2R (radiusb (det3_enclosure_b t K A))) with (radius (enc_R (det3_enclosure_b t K A))).
  rewrite ER. exact L.
Qed.

(** Stage 2's liveness statements, each over the function [s] that forms the twin's terms from the query: the
    scalar twins here ([pi_stage2_b], [num_stage2_b], [den_stage2_b]), the lane forms in TriangleLaneLiveness.v,
    which so state the same property. *)
Definition pi_compensated_live_for (s : TVec -> TVec -> TVec -> TVec -> CTermB) : Prop := forall o d p q : TVec,
  tbnd 300 o -> tbnd 300 d -> tbnd 300 p -> tbnd 300 q ->
  bpow radix2 (-95) * perm3v (tvec_R d) (rsub (tvec_R p) (tvec_R o)) (rsub (tvec_R q) (tvec_R o)) +
    bpow radix2 (-1067) * sumabs (tvec_R d) + bpow radix2 (-1066) <
    Rabs (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) ->
  enclosure_sign_lanes_b (det3_enclosure_b (s o d p q) Cpp.triangle_compensated_relative (absolute_bv d))
    <> uncertain_lane.
Definition num_compensated_live_for (s : TVec -> TVec -> TVec -> TVec -> CTermB) : Prop := forall o a b c : TVec,
  tbnd 300 o -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  bpow radix2 (-95) * perm3v (rsub (tvec_R a) (tvec_R o)) (rsub (tvec_R b) (tvec_R o)) (rsub (tvec_R c) (tvec_R o)) +
    bpow radix2 (-1067) * sumabs (rsub (tvec_R a) (tvec_R o)) + bpow radix2 (-1066) <
    Rabs (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) ->
  enclosure_sign_lanes_b (det3_enclosure_b (s o a b c) Cpp.triangle_compensated_relative
                                           (absolute_bv (ehigh a o))) <> uncertain_lane.
Definition den_compensated_live_for (s : TVec -> TVec -> TVec -> TVec -> TVec -> CTermB) : Prop :=
  forall o d a b c : TVec,
  tbnd 300 o -> tbnd 300 d -> tbnd 300 a -> tbnd 300 b -> tbnd 300 c ->
  bpow radix2 (-95) * den_perm (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) +
    bpow radix2 (-1067) * sumabs (tvec_R d) + bpow radix2 (-1066) <
    Rabs (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) ->
  enclosure_sign_lanes_b (det3_enclosure_b (s o d a b c) Cpp.triangle_compensated_den_relative
                                           (absolute_bv d)) <> uncertain_lane.

(** π(p, q): stage 2 with K_π is certain when |π| > 2^-95·P + 2^-1067·Σ|d_i| + 2^-1066. *)
Theorem triangle_pi_compensated_live : pi_compensated_live_for pi_stage2_b.
Proof.
  intros o d p q O D P Q L.
  assert (BA : fbnd 310 (absolute_bv d)).
  { apply absolute_bv_bnd. destruct D as [? [? ?]]. repeat split; apply fbnd_305; assumption. }
  destruct (pi_stage2_bnd o d p q O D P Q) as [Bh [Bl Bm]].
  apply (compensated_live_step _ (pi_stage2 (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) _ _
           (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) (or_introl eq_refl)).
  - split; [|split]; (eapply fbnd_le; [eassumption | lia]).
  - exact BA.
  - intros Fl Fm. exact (proj2 (proj2 (proj2 (proj2 (pi_stage2_twin o d p q Fl Fm))))).
  - rewrite cpp_triangle_compensated_relative, (proj2 (absolute_bv_twin _ (proj1 BA))).
    apply pi_compensated_encloses; apply tvec_R_doubles.
  - rewrite cpp_triangle_compensated_relative, (proj2 (absolute_bv_twin _ (proj1 BA))).
    rewrite (proj2 (proj1 (stage2_filter_view (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q) (tvec_R q)) _ _)).
    destruct (pi_magnitude_upper (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) as [M U].
    destruct (absolute_v_upper (tvec_R d) (tvec_R_doubles d)) as [MA UA].
    eapply Rle_lt_trans; [| exact L].
    apply det3_radius_upper; try assumption; try apply perm3v_nonneg; try apply sumabs_nonneg.
    unfold triangle_compensated_relative. pose proof u_pos. nra.
Qed.

(** num: with K_num = K_π and the absolute term of the high parts of TwoDiff(a, o). *)
Theorem triangle_num_compensated_live : num_compensated_live_for num_stage2_b.
Proof.
  intros o a b c O A B C L.
  assert (BA : fbnd 310 (absolute_bv (ehigh a o))).
  { apply absolute_bv_bnd. destruct o as [ox oy oz]. destruct a as [ax ay az].
    destruct O as [O0 [O1 O2]]. destruct A as [A0 [A1 A2]]. cbn [tx ty tz] in *. unfold ehigh. cbn [tx ty tz].
    repeat split; apply two_diff_bnd; assumption. }
  destruct (num_stage2_bnd o a b c O A B C) as [Bh [Bl Bm]].
  apply (compensated_live_step _ (num_stage2 (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) _ _
           (num_value (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) (or_introl eq_refl)).
  - split; [|split]; (eapply fbnd_le; [eassumption | lia]).
  - exact BA.
  - intros Fl Fm. exact (proj2 (proj2 (proj2 (proj2 (num_stage2_twin o a b c Fl Fm))))).
  - rewrite cpp_triangle_compensated_relative, (proj2 (proj2 (ehigh_twin a o (proj1 BA)))).
    apply num_compensated_encloses; apply tvec_R_doubles.
  - rewrite cpp_triangle_compensated_relative, (proj2 (proj2 (ehigh_twin a o (proj1 BA)))).
    rewrite (proj2 (proj1 (proj2 (stage2_filter_view (tvec_R o) (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c))))).
    destruct (num_magnitude_upper (tvec_R o) (tvec_R a) (tvec_R b) (tvec_R c)) as [M U].
    assert (Dr : doubles3 (rsub (tvec_R a) (tvec_R o))) by (repeat split; apply binary64_RN).
    destruct (absolute_v_upper _ Dr) as [MA UA].
    eapply Rle_lt_trans; [| exact L].
    apply det3_radius_upper; try assumption; try apply perm3v_nonneg; try apply sumabs_nonneg.
    unfold triangle_compensated_relative. pose proof u_pos. nra.
Qed.

(** den = (πa + πb) + πc in double-doubles, with K_den. *)
Theorem triangle_den_compensated_live : den_compensated_live_for den_stage2_b.
Proof.
  intros o d a b c O D A B C L.
  assert (BA : fbnd 310 (absolute_bv d)).
  { apply absolute_bv_bnd. destruct D as [? [? ?]]. repeat split; apply fbnd_305; assumption. }
  destruct (den_stage2_bnd o d a b c O D A B C) as [Bh [Bl Bm]].
  apply (compensated_live_step _ (den_stage2 (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) _ _
           (den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) (or_intror eq_refl)).
  - split; [|split]; (eapply fbnd_le; [eassumption | lia]).
  - exact BA.
  - intros Fl Fm. exact (proj2 (proj2 (proj2 (proj2 (proj2 (den_stage2_twin o d a b c Fl Fm)))))).
  - rewrite cpp_triangle_compensated_den_relative, (proj2 (absolute_bv_twin _ (proj1 BA))).
    apply den_compensated_encloses; apply tvec_R_doubles.
  - rewrite cpp_triangle_compensated_den_relative, (proj2 (absolute_bv_twin _ (proj1 BA))).
    rewrite (proj2 (proj2 (proj2 (stage2_filter_view (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c))))).
    destruct (den_magnitude_upper (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c)) as [M U].
    destruct (absolute_v_upper (tvec_R d) (tvec_R_doubles d)) as [MA UA].
    eapply Rle_lt_trans; [| exact L].
    apply det3_radius_upper; try assumption; try apply sumabs_nonneg.
    + unfold triangle_compensated_den_relative. pose proof u_pos. nra.
    + unfold den_perm. pose proof (perm3v_nonneg (tvec_R d) (rsub (tvec_R b) (tvec_R o)) (rsub (tvec_R c) (tvec_R o))).
      pose proof (perm3v_nonneg (tvec_R d) (rsub (tvec_R c) (tvec_R o)) (rsub (tvec_R a) (tvec_R o))).
      pose proof (perm3v_nonneg (tvec_R d) (rsub (tvec_R a) (tvec_R o)) (rsub (tvec_R b) (tvec_R o))). lra.
Qed.
