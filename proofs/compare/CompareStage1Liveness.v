(** * Liveness of stage 1 of the nearest-hit comparison ([compare_quotients_filter],
    kernel/src/nearest/compare_quotients.hpp, as nearest_hit.cpp's [compare_hit_distances] calls it).

    The soundness theorem ([compare_quotients_filter_sound], [compare_hit_distances_twin_correct]) says a
    certain order is right; a filter that never certified would satisfy it.  Here, on the twin
    [compare_quotients_filter_b] (CompareTwins.v, the Flocq binary64 definition the runner checks against
    the C++): for four one-double enclosures (x_i, e_i) of num_i and (y_i, f_i) of den_i, every value and
    radius a finite double of magnitude at most 2^400 (radii ≥ 0), with

      S = |x_1·y_2| + |x_2·y_1|,
      ρ = |x_1|·f_2 + e_1·(|y_2| + f_2) + |x_2|·f_1 + e_2·(|y_1| + f_1)   (the propagated input error),

    - [compare_filter_live]: certain whenever |x_1·y_2 − x_2·y_1| > c_1·S + c_2·ρ + c_3;
    - [compare_filter_live_exact]: certain whenever the exact cross difference of any enclosed reals,
      |N_1·D_2 − N_2·D_1|, exceeds c_1·S + (c_2 + 1)·ρ + c_3;

    c_1 = 2^-51 + 2^-96 (= 4u + 1024u²: 2u from the filter constant C_f = (2 + 16u)u, 2u from the rounding of
    P = x_1 ⊗ y_2 and Q = x_2 ⊗ y_1), c_2 = 1 + 2^-40 (C_p = 1 + 16u and the roundings of R), c_3 = 2^-1060.

    Not vacuous and how sharp ([compare_filter_live_example], [compare_filter_half_c1_fails],
    [compare_filter_half_c2_fails]): the near tie x_1 = y_1 = y_2 = 1, x_2 = 1 − 2^-49, radii 0, is in the
    class and certified; with c_1 halved (2^-52), x_2 = 1 − 2^-51 would be in the class and the filter is
    uncertain on it; with c_2 halved, x_1 = y_2 = 1, x_2 = y_1 = 0, f_2 = 1 would be in the class and the
    filter is uncertain on it.  So c_1 is within a factor 2 of the best constant and c_2 within 2^-40.

    - [compare_hit_distances_stage1_live]: in nearest_hit's [compare_hit_distances] (its twin
      [compare_hit_distances_b], NearestTwins.v), the order of two hits is returned by stage 1 (stage 0,
      Stage::filter) whenever the four stage-1 enclosures are in the class. *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins CompareTwins PlaneLiveness NearestTwins.
Open Scope R_scope.

(** ** Upper bounds of the computed quantities (model) *)

Lemma RN_abs_upper : forall z, Rabs (RN z) <= (1 + u) * Rabs z + eta.
Proof. intros z. pose proof (RN_err z). pose proof (Rabs_triang_inv (RN z) z). lra. Qed.

(** One half of R: RN(RN(|x|·f) + RN(e·RN(|y| + f))) ≤ (1+u)^3·(|x|·f + e·(|y| + f)) + 3η. *)
Lemma propagated_half_upper : forall x e y f, binary64 y -> binary64 f -> 0 <= e -> 0 <= f ->
  RN (RN (Rabs x * f) + RN (e * RN (Rabs y + f))) <=
    (1 + u) * (1 + u) * (1 + u) * (Rabs x * f + e * (Rabs y + f)) + 3 * eta.
Proof.
  intros x e y f By Bf He Hf. pose proof u_pos as U0. pose proof eta_pos as E0.
  assert (U1 : u <= 1 / 1024) by (rewrite u_val; lra).
  pose proof (Rabs_pos x). pose proof (Rabs_pos y).
  assert (Ayf : 0 <= Rabs y + f) by lra.
  pose proof (RN_sum_upper (Rabs y) f (binary64_abs _ By) Bf Ayf) as S1.
  pose proof (RN_nonneg _ Ayf) as S0.
  set (s := RN (Rabs y + f)) in *.
  assert (Es : e * s <= e * ((1 + u) * (Rabs y + f))) by (apply Rmult_le_compat_l; lra).
  assert (Pes : 0 <= e * s) by nra.
  pose proof (RN_upper (e * s) Pes) as T1. pose proof (RN_nonneg _ Pes) as T0.
  assert (Pxf : 0 <= Rabs x * f) by nra.
  pose proof (RN_upper _ Pxf) as R1. pose proof (RN_nonneg _ Pxf) as R0.
  set (t := RN (e * s)) in *. set (r := RN (Rabs x * f)) in *.
  pose proof (RN_sum_upper r t (binary64_RN _) (binary64_RN _) ltac:(lra)) as O.
  set (A := Rabs x * f) in *. set (E := e * (Rabs y + f)) in *.
  assert (PE : 0 <= E) by (unfold E; nra).
  assert (Ee : e * ((1 + u) * (Rabs y + f)) = (1 + u) * E) by (unfold E; ring).
  rewrite Ee in Es. clearbody A E s t r.
  assert (Hrt : r + t <= (1 + u) * A + (1 + u) * ((1 + u) * E) + 2 * eta) by nra.
  assert (H' : (1 + u) * (r + t) <= (1 + u) * ((1 + u) * A + (1 + u) * ((1 + u) * E) + 2 * eta))
    by (apply Rmult_le_compat_l; lra).
  assert (A1 : (1 + u) * A <= (1 + u) * (1 + u) * A) by nra.
  nra.
Qed.

(** R ≤ (1+u)^4·ρ + 7η. *)
Lemma propagated_upper : forall x1 e1 y1 f1 x2 e2 y2 f2,
  binary64 y1 -> binary64 f1 -> binary64 y2 -> binary64 f2 -> 0 <= e1 -> 0 <= f1 -> 0 <= e2 -> 0 <= f2 ->
  compare_propagated_error x1 e1 y1 f1 x2 e2 y2 f2 <=
    (1 + u) * (1 + u) * (1 + u) * (1 + u) *
      (Rabs x1 * f2 + e1 * (Rabs y2 + f2) + (Rabs x2 * f1 + e2 * (Rabs y1 + f1))) + 7 * eta.
Proof.
  intros x1 e1 y1 f1 x2 e2 y2 f2 By1 Bf1 By2 Bf2 He1 Hf1 He2 Hf2. unfold compare_propagated_error.
  pose proof u_pos as U0. pose proof eta_pos as E0.
  pose proof (propagated_half_upper x1 e1 y2 f2 By2 Bf2 He1 Hf2) as H1.
  pose proof (propagated_half_upper x2 e2 y1 f1 By1 Bf1 He2 Hf1) as H2.
  pose proof (Rabs_pos x1). pose proof (Rabs_pos x2).
  assert (P1 : 0 <= Rabs x1 * f2 + e1 * (Rabs y2 + f2)) by (apply propagated_nonneg; assumption).
  assert (P2 : 0 <= Rabs x2 * f1 + e2 * (Rabs y1 + f1)) by (apply propagated_nonneg; assumption).
  assert (N1 : 0 <= RN (RN (Rabs x1 * f2) + RN (e1 * RN (Rabs y2 + f2)))).
  { apply RN_nonneg. apply Rplus_le_le_0_compat; apply RN_nonneg; [nra|].
    apply Rmult_le_pos; [lra | apply RN_nonneg; pose proof (Rabs_pos y2); lra]. }
  assert (N2 : 0 <= RN (RN (Rabs x2 * f1) + RN (e2 * RN (Rabs y1 + f1)))).
  { apply RN_nonneg. apply Rplus_le_le_0_compat; apply RN_nonneg; [nra|].
    apply Rmult_le_pos; [lra | apply RN_nonneg; pose proof (Rabs_pos y1); lra]. }
  pose proof (RN_sum_upper _ _ (binary64_RN (RN (Rabs x1 * f2) + RN (e1 * RN (Rabs y2 + f2))))
                (binary64_RN (RN (Rabs x2 * f1) + RN (e2 * RN (Rabs y1 + f1)))) ltac:(lra)) as O.
  set (h1 := RN (RN (Rabs x1 * f2) + RN (e1 * RN (Rabs y2 + f2)))) in *.
  set (h2 := RN (RN (Rabs x2 * f1) + RN (e2 * RN (Rabs y1 + f1)))) in *.
  set (a := Rabs x1 * f2 + e1 * (Rabs y2 + f2)) in *. set (b := Rabs x2 * f1 + e2 * (Rabs y1 + f1)) in *.
  clearbody h1 h2 a b. rewrite u_val in *. nra.
Qed.

(** ** The model is certain on the class *)

Definition c1 : R := bpow radix2 (-51) + bpow radix2 (-96).
Definition c2 : R := 1 + bpow radix2 (-40).
Definition c3 : R := bpow radix2 (-1060).

Definition cross_magnitude (x1 y1 x2 y2 : R) : R := Rabs (x1 * y2) + Rabs (x2 * y1).
Definition propagated_exact (x1 e1 y1 f1 x2 e2 y2 f2 : R) : R :=
  Rabs x1 * f2 + e1 * (Rabs y2 + f2) + (Rabs x2 * f1 + e2 * (Rabs y1 + f1)).

Lemma c3_eta : c3 = 32768 * eta.
Proof. unfold c3, eta. replace (-1060)%Z with (15 + -1075)%Z by reflexivity. rewrite bpow_plus. simpl bpow. lra. Qed.

Theorem compare_filter_live_model : forall x1 e1 y1 f1 x2 e2 y2 f2,
  binary64 y1 -> binary64 f1 -> binary64 y2 -> binary64 f2 -> 0 <= e1 -> 0 <= f1 -> 0 <= e2 -> 0 <= f2 ->
  c1 * cross_magnitude x1 y1 x2 y2 + c2 * propagated_exact x1 e1 y1 f1 x2 e2 y2 f2 + c3 <
    Rabs (x1 * y2 - x2 * y1) ->
  compare_quotients_filter {| rounded_value := x1; rounded_radius := e1 |}
    {| rounded_value := y1; rounded_radius := f1 |} {| rounded_value := x2; rounded_radius := e2 |}
    {| rounded_value := y2; rounded_radius := f2 |} <> Uncertain.
Proof.
  intros x1 e1 y1 f1 x2 e2 y2 f2 By1 Bf1 By2 Bf2 He1 Hf1 He2 Hf2 L.
  unfold compare_quotients_filter. cbn [rounded_value rounded_radius].
  pose proof u_pos as U0. pose proof eta_pos as E0.
  assert (Z : forall z, Rabs (z - z) <= 0) by (intros z; replace (z - z) with 0 by ring; rewrite Rabs_R0; lra).
  pose proof (filter_delta_error x1 y1 x2 y2 x1 0 y1 0 x2 0 y2 0 (Z _) (Z _) (Z _) (Z _)) as D. cbv zeta in D.
  rewrite !Rmult_0_r, !Rmult_0_l, !Rplus_0_r in D.
  pose proof (propagated_upper x1 e1 y1 f1 x2 e2 y2 f2 By1 Bf1 By2 Bf2 He1 Hf1 He2 Hf2) as RU.
  destruct (compare_propagated_error_lower x1 e1 y1 f1 x2 e2 y2 f2 By1 Bf1 By2 Bf2 He1 Hf1 He2 Hf2)
    as [PR _].
  set (R := compare_propagated_error x1 e1 y1 f1 x2 e2 y2 f2) in *.
  pose proof (RN_abs_upper (x1 * y2)) as AP. pose proof (RN_abs_upper (x2 * y1)) as AQ.
  set (P := RN (x1 * y2)) in *. set (Q := RN (x2 * y1)) in *.
  pose proof (Rabs_pos P). pose proof (Rabs_pos Q).
  assert (MU : RN (Rabs P + Rabs Q) <= (1 + u) * (Rabs P + Rabs Q))
    by (apply RN_sum_upper; [apply binary64_abs, binary64_RN | apply binary64_abs, binary64_RN | lra]).
  pose proof (RN_nonneg (Rabs P + Rabs Q) ltac:(lra)) as M0.
  set (M := RN (Rabs P + Rabs Q)) in *.
  assert (CF : compare_filter_relative = (2 + 16 * u) * u) by reflexivity.
  assert (CP : compare_propagation_factor = 1 + 16 * u) by reflexivity.
  assert (KM : 0 <= compare_filter_relative * M) by (rewrite CF; nra).
  assert (KR : 0 <= compare_propagation_factor * R) by (rewrite CP; nra).
  pose proof (RN_upper _ KM) as B1. pose proof (RN_upper _ KR) as B2.
  pose proof (RN_nonneg _ KM). pose proof (RN_nonneg _ KR).
  pose proof (RN_sum_upper _ _ (binary64_RN (compare_filter_relative * M))
                (binary64_RN (compare_propagation_factor * R)) ltac:(lra)) as B3.
  pose proof (RN_nonneg (RN (compare_filter_relative * M) + RN (compare_propagation_factor * R)) ltac:(lra)) as B30.
  pose proof binary64_compare_absolute as BA. pose proof compare_absolute_eta as EA.
  pose proof (RN_sum_upper _ _ (binary64_RN (RN (compare_filter_relative * M) + RN (compare_propagation_factor * R)))
                BA ltac:(lra)) as B4.
  set (B := RN (RN (RN (compare_filter_relative * M) + RN (compare_propagation_factor * R)) + compare_absolute))
    in *.
  set (b3 := RN (RN (compare_filter_relative * M) + RN (compare_propagation_factor * R))) in *.
  set (b1 := RN (compare_filter_relative * M)) in *. set (b2 := RN (compare_propagation_factor * R)) in *.
  set (delta := RN (P - Q)) in *.
  unfold cross_magnitude, propagated_exact in L. rewrite c3_eta in L. unfold c1, c2 in L. simpl bpow in L.
  pose proof (Rabs_pos (x1 * y2)). pose proof (Rabs_pos (x2 * y1)).
  assert (Pr : 0 <= Rabs x1 * f2 + e1 * (Rabs y2 + f2) + (Rabs x2 * f1 + e2 * (Rabs y1 + f1))).
  { apply Rplus_le_le_0_compat; apply propagated_nonneg; assumption. }
  set (rho := Rabs x1 * f2 + e1 * (Rabs y2 + f2) + (Rabs x2 * f1 + e2 * (Rabs y1 + f1))) in *.
  set (S1 := Rabs (x1 * y2)) in *. set (S2 := Rabs (x2 * y1)) in *.
  set (V := x1 * y2 - x2 * y1) in *.
  rewrite CF in B1. rewrite CP in B2.
  assert (Bup : B <= 2 * ((2 + 16 * u) * u) * (S1 + S2) + (1 + 16 * u) * (1 + u) * (1 + u) * (1 + u) *
                  ((1 + u) * (1 + u) * (1 + u) * (1 + u) * rho) + 64 * eta).
  { clearbody B b3 b1 b2 delta M P Q R rho S1 S2 V. rewrite u_val in *. lra. }
  apply Rabs_le_inv in D.
  clearbody B b3 b1 b2 delta M P Q R rho S1 S2 V.
  destruct (Rlt_bool_spec B delta); [discriminate|].
  destruct (Rlt_bool_spec delta (- B)); [discriminate|].
  exfalso. destruct (Rle_or_lt 0 V).
  - rewrite Rabs_pos_eq in L by assumption. rewrite u_val in *. lra.
  - rewrite Rabs_left in L by assumption. rewrite u_val in *. lra.
Qed.

(** ** The twin *)

Definition renc (v r : float) : RoundedEnclosureB := {| rvalueb := v; rradiusb := r |}.

(** Values and radii of magnitude at most 2^400: nothing overflows, the twin computes the model's sign. *)
Lemma compare_filter_b_model : forall x1 e1 y1 f1 x2 e2 y2 f2,
  fbnd 400 x1 -> fbnd 400 e1 -> fbnd 400 y1 -> fbnd 400 f1 ->
  fbnd 400 x2 -> fbnd 400 e2 -> fbnd 400 y2 -> fbnd 400 f2 ->
  compare_quotients_filter_b (renc x1 e1) (renc y1 f1) (renc x2 e2) (renc y2 f2) =
  compare_quotients_filter (renc_R (renc x1 e1)) (renc_R (renc y1 f1)) (renc_R (renc x2 e2))
    (renc_R (renc y2 f2)).
Proof.
  intros x1 e1 y1 f1 x2 e2 y2 f2 X1 E1 Y1 F1 X2 E2 Y2 F2.
  assert (FB : fbnd 1000 (fadd (fadd (fmul Cpp.compare_filter_relative (fadd (fabs (fmul x1 y2)) (fabs (fmul x2 y1))))
                  (fmul Cpp.compare_propagation_factor (compare_propagated_error_b x1 e1 y1 f1 x2 e2 y2 f2)))
                  Cpp.compare_absolute)).
  { unfold compare_propagated_error_b. eapply fbnd_le; [fbnd_tac | lia]. }
  assert (FD : fbnd 1000 (fsub (fmul x1 y2) (fmul x2 y1))) by (eapply fbnd_le; [fbnd_tac | lia]).
  destruct FB as [FB _]. destruct FD as [FD _].
  unfold compare_quotients_filter_b, compare_quotients_filter, renc_R, renc, compare_propagated_error.
  cbn [rvalueb rradiusb rounded_value rounded_radius].
  unfold compare_propagated_error_b in *. cpp_fin. to_model. reflexivity.
Qed.

(** Stage 1 of the comparison is certain when the cross difference of the enclosures' values exceeds
    c_1·S + c_2·ρ + c_3. *)
Theorem compare_filter_live : forall x1 e1 y1 f1 x2 e2 y2 f2,
  fbnd 400 x1 -> fbnd 400 e1 -> fbnd 400 y1 -> fbnd 400 f1 ->
  fbnd 400 x2 -> fbnd 400 e2 -> fbnd 400 y2 -> fbnd 400 f2 ->
  0 <= B2R e1 -> 0 <= B2R f1 -> 0 <= B2R e2 -> 0 <= B2R f2 ->
  c1 * cross_magnitude (B2R x1) (B2R y1) (B2R x2) (B2R y2) +
    c2 * propagated_exact (B2R x1) (B2R e1) (B2R y1) (B2R f1) (B2R x2) (B2R e2) (B2R y2) (B2R f2) + c3 <
    Rabs (B2R x1 * B2R y2 - B2R x2 * B2R y1) ->
  compare_quotients_filter_b (renc x1 e1) (renc y1 f1) (renc x2 e2) (renc y2 f2) <> Uncertain.
Proof.
  intros x1 e1 y1 f1 x2 e2 y2 f2 X1 E1 Y1 F1 X2 E2 Y2 F2 P1 Q1 P2 Q2 L.
  rewrite compare_filter_b_model by assumption.
  apply compare_filter_live_model; try apply binary64_B2R; assumption.
Qed.

(** The same in the words of the exact values: any N_i, D_i the enclosures enclose (|x_i − N_i| ≤ e_i,
    |y_i − D_i| ≤ f_i: num and den of the two planes along the ray, through PlaneFilter.v's
    [num_filter_encloses], [den_filter_encloses]) whose exact cross difference |N_1·D_2 − N_2·D_1| exceeds
    c_1·S + (c_2 + 1)·ρ + c_3. *)
Corollary compare_filter_live_exact : forall x1 e1 y1 f1 x2 e2 y2 f2 N1 D1 N2 D2,
  fbnd 400 x1 -> fbnd 400 e1 -> fbnd 400 y1 -> fbnd 400 f1 ->
  fbnd 400 x2 -> fbnd 400 e2 -> fbnd 400 y2 -> fbnd 400 f2 ->
  Rabs (B2R x1 - N1) <= B2R e1 -> Rabs (B2R y1 - D1) <= B2R f1 ->
  Rabs (B2R x2 - N2) <= B2R e2 -> Rabs (B2R y2 - D2) <= B2R f2 ->
  c1 * cross_magnitude (B2R x1) (B2R y1) (B2R x2) (B2R y2) +
    (c2 + 1) * propagated_exact (B2R x1) (B2R e1) (B2R y1) (B2R f1) (B2R x2) (B2R e2) (B2R y2) (B2R f2) + c3 <
    Rabs (N1 * D2 - N2 * D1) ->
  compare_quotients_filter_b (renc x1 e1) (renc y1 f1) (renc x2 e2) (renc y2 f2) <> Uncertain.
Proof.
  intros x1 e1 y1 f1 x2 e2 y2 f2 N1 D1 N2 D2 X1 E1 Y1 F1 X2 E2 Y2 F2 H1 G1 H2 G2 L.
  pose proof (input_error N1 D2 _ _ _ _ H1 G2) as I1. pose proof (input_error N2 D1 _ _ _ _ H2 G1) as I2.
  assert (P1 : 0 <= B2R e1) by (eapply Rle_trans; [apply Rabs_pos | exact H1]).
  assert (P2 : 0 <= B2R e2) by (eapply Rle_trans; [apply Rabs_pos | exact H2]).
  assert (Q1 : 0 <= B2R f1) by (eapply Rle_trans; [apply Rabs_pos | exact G1]).
  assert (Q2 : 0 <= B2R f2) by (eapply Rle_trans; [apply Rabs_pos | exact G2]).
  apply compare_filter_live; try assumption.
  unfold propagated_exact in *.
  set (rho := Rabs (B2R x1) * B2R f2 + B2R e1 * (Rabs (B2R y2) + B2R f2) +
              (Rabs (B2R x2) * B2R f1 + B2R e2 * (Rabs (B2R y1) + B2R f1))) in *.
  set (K := c1 * cross_magnitude (B2R x1) (B2R y1) (B2R x2) (B2R y2)) in *.
  assert (Rabs (N1 * D2 - N2 * D1) <= Rabs (B2R x1 * B2R y2 - B2R x2 * B2R y1) + rho).
  { replace (N1 * D2 - N2 * D1) with ((B2R x1 * B2R y2 - B2R x2 * B2R y1) + (N1 * D2 - B2R x1 * B2R y2)
                                       - (N2 * D1 - B2R x2 * B2R y1)) by ring.
    unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
    eapply Rle_trans; [apply Rplus_le_compat_r, Rabs_triang|]. unfold rho. lra. }
  lra.
Qed.

(** ** Not vacuous, and how sharp *)

Definition f_one : float := of_bits 4607182418800017408.     (* 1 *)
Definition f_zero : float := of_bits 0.                      (* +0 *)
Definition f_near49 : float := of_bits 4607182418800017392.  (* 1 − 2^-49 *)
Definition f_near51 : float := of_bits 4607182418800017404.  (* 1 − 2^-51 *)

Lemma f_one_val : B2R f_one = 1.
Proof. float_real f_one. lra. Qed.
Lemma f_zero_val : B2R f_zero = 0.
Proof. reflexivity. Qed.
Lemma f_near49_val : B2R f_near49 = 1 - / 562949953421312.
Proof. float_real f_near49. lra. Qed.
Lemma f_near51_val : B2R f_near51 = 1 - / 2251799813685248.
Proof. float_real f_near51. lra. Qed.

Lemma fbnd_small : forall x, fin x = true -> 0 <= B2R x <= 1 -> fbnd 400 x.
Proof.
  intros x F B. apply (fbnd_mono 1 400); [lia|]. apply fbnd_const; [exact F|].
  rewrite Rabs_pos_eq by lra. lra.
Qed.

Ltac small_input := apply fbnd_small; [vm_compute; reflexivity |
  rewrite ?f_one_val, ?f_zero_val, ?f_near49_val, ?f_near51_val; split; lra].

Ltac class_arith := unfold cross_magnitude, propagated_exact, c1, c2, c3;
  rewrite ?f_one_val, ?f_zero_val, ?f_near49_val, ?f_near51_val;
  repeat (rewrite Rabs_pos_eq by lra); pow_vals; lra.

(** A near tie, t_1 − t_2 of relative size 2^-49 (x_1 = y_1 = y_2 = 1, x_2 = 1 − 2^-49, radii 0): in the
    class of [compare_filter_live], and stage 1 certifies it (by computation on the twin). *)
Example compare_filter_live_example :
  c1 * cross_magnitude (B2R f_one) (B2R f_one) (B2R f_near49) (B2R f_one) +
    c2 * propagated_exact (B2R f_one) (B2R f_zero) (B2R f_one) (B2R f_zero) (B2R f_near49) (B2R f_zero)
           (B2R f_one) (B2R f_zero) + c3 <
    Rabs (B2R f_one * B2R f_one - B2R f_near49 * B2R f_one) /\
  compare_quotients_filter_b (renc f_one f_zero) (renc f_one f_zero) (renc f_near49 f_zero) (renc f_one f_zero)
    = Positive.
Proof. split; [class_arith | vm_compute; reflexivity]. Qed.

(** c_1 cannot be halved: with 2^-52 = 2u (the leading term of C_f) in its place, x_2 = 1 − 2^-51 would be in
    the class (|V| = 2^-51 > 2^-52·(2 − 2^-51)), and stage 1 is uncertain on it (B ≈ C_f·M > 2^-51 = δ). *)
Theorem compare_filter_half_c1_fails : ~ (forall x1 e1 y1 f1 x2 e2 y2 f2,
  fbnd 400 x1 -> fbnd 400 e1 -> fbnd 400 y1 -> fbnd 400 f1 ->
  fbnd 400 x2 -> fbnd 400 e2 -> fbnd 400 y2 -> fbnd 400 f2 ->
  0 <= B2R e1 -> 0 <= B2R f1 -> 0 <= B2R e2 -> 0 <= B2R f2 ->
  bpow radix2 (-52) * cross_magnitude (B2R x1) (B2R y1) (B2R x2) (B2R y2) +
    c2 * propagated_exact (B2R x1) (B2R e1) (B2R y1) (B2R f1) (B2R x2) (B2R e2) (B2R y2) (B2R f2) + c3 <
    Rabs (B2R x1 * B2R y2 - B2R x2 * B2R y1) ->
  compare_quotients_filter_b (renc x1 e1) (renc y1 f1) (renc x2 e2) (renc y2 f2) <> Uncertain).
Proof.
  intros H. apply (H f_one f_zero f_one f_zero f_near51 f_zero f_one f_zero);
    try small_input; try (rewrite f_zero_val; lra).
  - class_arith.
  - vm_compute. reflexivity.
Qed.

(** c_2 cannot be halved: with x_1 = y_2 = 1, x_2 = y_1 = 0 and the radius f_2 = 1 (ρ = 1, |V| = 1), the
    input would be in the class with c_2/2, and stage 1 is uncertain on it (B ≥ C_p·R > 1 = δ). *)
Theorem compare_filter_half_c2_fails : ~ (forall x1 e1 y1 f1 x2 e2 y2 f2,
  fbnd 400 x1 -> fbnd 400 e1 -> fbnd 400 y1 -> fbnd 400 f1 ->
  fbnd 400 x2 -> fbnd 400 e2 -> fbnd 400 y2 -> fbnd 400 f2 ->
  0 <= B2R e1 -> 0 <= B2R f1 -> 0 <= B2R e2 -> 0 <= B2R f2 ->
  c1 * cross_magnitude (B2R x1) (B2R y1) (B2R x2) (B2R y2) +
    c2 / 2 * propagated_exact (B2R x1) (B2R e1) (B2R y1) (B2R f1) (B2R x2) (B2R e2) (B2R y2) (B2R f2) + c3 <
    Rabs (B2R x1 * B2R y2 - B2R x2 * B2R y1) ->
  compare_quotients_filter_b (renc x1 e1) (renc y1 f1) (renc x2 e2) (renc y2 f2) <> Uncertain).
Proof.
  intros H. apply (H f_one f_zero f_zero f_zero f_zero f_zero f_one f_one);
    try small_input; try (rewrite ?f_zero_val, ?f_one_val; lra).
  - class_arith.
  - vm_compute. reflexivity.
Qed.

(** ** In nearest_hit: [compare_hit_distances] returns from stage 1 *)

Lemma nonneg_fin_B2R : forall x, nonneg x -> fin x = true -> 0 <= B2R x.
Proof. intros x [N|S] F; [destruct x; discriminate | now apply Bsign_false_nonneg]. Qed.

Theorem compare_hit_distances_stage1_live : forall o d pa na pb nb nsa dsa nsb dsb x1 e1 y1 f1 x2 e2 y2 f2,
  filter_enclosure_b (stage1_num_b o pa na) Cpp.filter_num_relative = renc x1 e1 ->
  filter_enclosure_b (stage1_den_b d na) Cpp.filter_den_relative = renc y1 f1 ->
  filter_enclosure_b (stage1_num_b o pb nb) Cpp.filter_num_relative = renc x2 e2 ->
  filter_enclosure_b (stage1_den_b d nb) Cpp.filter_den_relative = renc y2 f2 ->
  fbnd 400 x1 -> fbnd 400 e1 -> fbnd 400 y1 -> fbnd 400 f1 ->
  fbnd 400 x2 -> fbnd 400 e2 -> fbnd 400 y2 -> fbnd 400 f2 ->
  c1 * cross_magnitude (B2R x1) (B2R y1) (B2R x2) (B2R y2) +
    c2 * propagated_exact (B2R x1) (B2R e1) (B2R y1) (B2R f1) (B2R x2) (B2R e2) (B2R y2) (B2R f2) + c3 <
    Rabs (B2R x1 * B2R y2 - B2R x2 * B2R y1) ->
  snd (compare_hit_distances_b o d pa na pb nb nsa dsa nsb dsb) = 0%Z.
Proof.
  intros o d pa na pb nb nsa dsa nsb dsb x1 e1 y1 f1 x2 e2 y2 f2 En1 Ed1 En2 Ed2
    X1 E1 Y1 F1 X2 E2 Y2 F2 L.
  assert (Pe1 : 0 <= B2R e1).
  { change e1 with (rradiusb (renc x1 e1)). rewrite <- En1. apply nonneg_fin_B2R; [| rewrite En1; exact (proj1 E1)].
    apply filter_radius_nonneg; [const_nonneg | unfold stage1_num_b; apply stage1_magnitude_nonneg]. }
  assert (Pf1 : 0 <= B2R f1).
  { change f1 with (rradiusb (renc y1 f1)). rewrite <- Ed1. apply nonneg_fin_B2R; [| rewrite Ed1; exact (proj1 F1)].
    apply filter_radius_nonneg; [const_nonneg | unfold stage1_den_b; apply stage1_magnitude_nonneg]. }
  assert (Pe2 : 0 <= B2R e2).
  { change e2 with (rradiusb (renc x2 e2)). rewrite <- En2. apply nonneg_fin_B2R; [| rewrite En2; exact (proj1 E2)].
    apply filter_radius_nonneg; [const_nonneg | unfold stage1_num_b; apply stage1_magnitude_nonneg]. }
  assert (Pf2 : 0 <= B2R f2).
  { change f2 with (rradiusb (renc y2 f2)). rewrite <- Ed2. apply nonneg_fin_B2R; [| rewrite Ed2; exact (proj1 F2)].
    apply filter_radius_nonneg; [const_nonneg | unfold stage1_den_b; apply stage1_magnitude_nonneg]. }
  pose proof (compare_filter_live x1 e1 y1 f1 x2 e2 y2 f2 X1 E1 Y1 F1 X2 E2 Y2 F2 Pe1 Pf1 Pe2 Pf2 L) as C.
  unfold compare_hit_distances_b. cbv zeta. destruct (_ || _)%bool; [reflexivity|].
  rewrite En1, Ed1, En2, Ed2.
  destruct (compare_quotients_filter_b (renc x1 e1) (renc y1 f1) (renc x2 e2) (renc y2 f2)) eqn:Es;
    try reflexivity. exfalso. exact (C eq_refl).
Qed.
