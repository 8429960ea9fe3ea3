(** * Stage 1 of the ray–triangle cascade: the binary64 filter of a 3×3 determinant
    (kernel/src/core/det3_stages.hpp, [FilterLeaf], [FilterTerm], [det3_filter_lanes], [det3_absolute_term];
    evaluated in the order of kernel/src/triangle/ray_triangle_formula.hpp).

    Every value of a ray–triangle query is det(x, y, z) = x·(y × z) of leaves: d (an input) and the rounded
    differences ê = v ⊖ o.  Main theorems:
    - [det3_filter_encloses]: |s − V| ≤ (C ⊗ m) ⊕ A for any determinant whose leaves are doubles within
      relative error u of the exact values (and x within ex ∈ {0, u}), with A the dynamic absolute term;
    - [pi_filter_sound], [num_filter_sound], [den_filter_sound]: a sign the filter certifies for
      π(p, q) = d·((p − o) × (q − o)), num = (a − o)·((b − o) × (c − o)), den = πa + πb + πc is the exact sign.

    The proof carries an invariant through each operation ([approx]): the computed value v and magnitude m
    are doubles, |v| ≤ m, and |v − V| ≤ α·m + β for explicit α and β; the absolute parts β of the products
    are scaled by |x_i| in the outer products, which is why the bound needs A = (K_A ⊗ S) ⊕ U_A,
    S = (|x_0| ⊕ |x_1|) ⊕ |x_2|, and not a constant. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model PlaneClassification.
Open Scope R_scope.

(** ** The C++ code, operation by operation. *)

(** [FilterTerm {v, m}]. *)
Record FTerm := { fv : R; fm : R }.

(** [FilterLeaf y * FilterLeaf z]: p = y ⊗ z, m = |p|. *)
Definition leaf_mul (y z : R) : FTerm := let p := RN (y * z) in {| fv := p; fm := Rabs p |}.
(** [FilterTerm a ± FilterTerm b]: v = a.v ⊕ b.v (⊖), m = a.m ⊕ b.m. *)
Definition term_add (a b : FTerm) : FTerm := {| fv := RN (fv a + fv b); fm := RN (fm a + fm b) |}.
Definition term_sub (a b : FTerm) : FTerm := {| fv := RN (fv a - fv b); fm := RN (fm a + fm b) |}.
(** [FilterLeaf x * FilterTerm c]: v = x ⊗ c.v, m = |x| ⊗ c.m. *)
Definition leaf_scale (x : R) (c : FTerm) : FTerm := {| fv := RN (x * fv c); fm := RN (Rabs x * fm c) |}.

(** [cross_terms(y, z)] and [dot_terms(x, c)] of ray_triangle_formula.hpp. *)
Definition det3 (x0 x1 x2 y0 y1 y2 z0 z1 z2 : R) : FTerm :=
  term_add (term_add (leaf_scale x0 (term_sub (leaf_mul y1 z2) (leaf_mul y2 z1)))
                     (leaf_scale x1 (term_sub (leaf_mul y2 z0) (leaf_mul y0 z2))))
           (leaf_scale x2 (term_sub (leaf_mul y0 z1) (leaf_mul y1 z0))).

(** [det3_absolute_term(x0, x1, x2)]: A = (K_A ⊗ S) ⊕ U_A, S = (|x0| ⊕ |x1|) ⊕ |x2|. *)
Definition absolute_term (x0 x1 x2 : R) : R :=
  RN (RN (triangle_absolute_scale * RN (RN (Rabs x0 + Rabs x1) + Rabs x2)) + triangle_absolute).

(** [det3_filter_lanes(r, relative, absolute)]: bound = (C ⊗ m) ⊕ A, then sign_lanes. *)
Definition det3_bound (t : FTerm) (C A : R) : R := RN (RN (C * fm t) + A).
Definition det3_filter_lanes (t : FTerm) (C A : R) : Z :=
  let b := det3_bound t C A in sign_lanes (Rlt_bool b (fv t)) (Rlt_bool (fv t) (- b)).

(** ** Basic facts. *)

Lemma u_small : u <= / 1024.
Proof. rewrite u_val. lra. Qed.

Lemma eta_u : 0 <= eta.
Proof. apply Rlt_le, eta_pos. Qed.

(** From |RN x − x| ≤ u|x| + η: |x| ≤ (1 + 2u)(|RN x| + η). *)
Lemma abs_before_rounding : forall x, Rabs x <= (1 + 2 * u) * (Rabs (RN x) + eta).
Proof.
  intros x. pose proof (RN_err x) as E. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  assert (A : Rabs x <= Rabs (RN x) + (u * Rabs x + eta)).
  { apply Rabs_close'. exact E. }
  pose proof (Rabs_pos x). pose proof (Rabs_pos (RN x)).
  assert (B : Rabs x * (1 - u) <= Rabs (RN x) + eta) by lra.
  assert (C : (1 + 2 * u) * (1 - u) >= 1) by nra.
  nra.
Qed.

Lemma binary64_abs_RN : forall x, binary64 (Rabs (RN x)).
Proof. intros. apply binary64_abs, binary64_RN. Qed.

(** ** The invariant: v and m are doubles, |v| ≤ m, and |v − V| ≤ α·m + β. *)
Definition approx (t : FTerm) (V alpha beta : R) : Prop :=
  binary64 (fv t) /\ binary64 (fm t) /\ 0 <= fm t /\ Rabs (fv t) <= fm t /\
  Rabs (fv t - V) <= alpha * fm t + beta.

Lemma approx_weaken : forall t V a b a' b', approx t V a b -> a <= a' -> b <= b' -> approx t V a' b'.
Proof.
  intros t V a b a' b' [B1 [B2 [P [D E]]]] Ha Hb. repeat split; try assumption.
  assert (a * fm t <= a' * fm t) by (apply Rmult_le_compat_r; assumption). lra.
Qed.

(** A product of two leaves within relative error u of Y and Z. *)
Lemma leaf_mul_approx : forall y z Y Z, binary64 y -> binary64 z ->
  Rabs (Y - y) <= u * Rabs y -> Rabs (Z - z) <= u * Rabs z ->
  approx (leaf_mul y z) (Y * Z) (3 * u + 6 * (u * u)) ((1 + 3 * u) * eta).
Proof.
  intros y z Y Z By Bz HY HZ. unfold approx, leaf_mul. cbn [fv fm].
  set (p := RN (y * z)).
  pose proof u_pos. pose proof u_small. pose proof eta_pos.
  repeat split.
  - apply binary64_RN.
  - apply binary64_abs_RN.
  - apply Rabs_pos.
  - apply Rle_refl.
  - pose proof (RN_err_round (y * z)) as E. fold p in E.
    pose proof (abs_before_rounding (y * z)) as Hyz. fold p in Hyz.
    (* |yz − YZ| ≤ (2u + u²)|yz| *)
    assert (D : Rabs (y * z - Y * Z) <= (2 * u + u * u) * Rabs (y * z)).
    { replace (y * z - Y * Z) with (- ((Y - y) * z) - Y * (Z - z)) by ring.
      eapply Rle_trans; [apply Rabs_triang|]. rewrite !Rabs_Ropp, !Rabs_mult.
      assert (RY : Rabs Y <= (1 + u) * Rabs y) by (apply Rabs_close in HY; lra).
      pose proof (Rabs_pos y). pose proof (Rabs_pos z). pose proof (Rabs_pos (Z - z)). pose proof (Rabs_pos (Y - y)).
      assert (T1 : Rabs (Y - y) * Rabs z <= u * Rabs y * Rabs z) by (apply Rmult_le_compat_r; lra).
      assert (T2 : Rabs Y * Rabs (Z - z) <= (1 + u) * Rabs y * (u * Rabs z)).
      { apply Rmult_le_compat; try lra; apply Rabs_pos. }
      lra. }
    replace (p - Y * Z) with ((p - y * z) + (y * z - Y * Z)) by ring.
    eapply Rle_trans; [apply Rabs_triang|].
    pose proof (Rabs_pos (y * z)). pose proof (Rabs_pos p).
    assert (F : (2 * u + u * u) * Rabs (y * z) <= (2 * u + u * u) * ((1 + 2 * u) * (Rabs p + eta)))
      by (apply Rmult_le_compat_l; nra).
    rewrite u_val in *. nra.
Qed.

(** The sum (difference) of two values: the error of the rounding is u|v_a ± v_b| ≤ u(m_a + m_b), and
    m_a + m_b ≤ (1 + u)·m. *)
Lemma term_addsub_approx : forall (sub : bool) a b A B alpha beta1 beta2,
  approx a A alpha beta1 -> approx b B alpha beta2 -> 0 <= alpha ->
  approx (if sub then term_sub a b else term_add a b) (if sub then A - B else A + B)
         ((u + alpha) * (1 + u)) (beta1 + beta2).
Proof.
  intros sub a b A B alpha beta1 beta2 [Ba [Bma [Pa [Da Ea]]]] [Bb [Bmb [Pb [Db Eb]]]] Halpha.
  pose proof u_pos.
  assert (Bm : binary64 (RN (fm a + fm b))) by apply binary64_RN.
  assert (Pm : 0 <= RN (fm a + fm b)) by (apply RN_nonneg; lra).
  pose proof (RN_plus_err_round (fm a) (fm b) Bma Bmb) as Em.
  rewrite (Rabs_nonneg_eq (RN (fm a + fm b))) in Em by exact Pm.
  assert (Sm : fm a + fm b <= (1 + u) * RN (fm a + fm b)) by (apply Rabs_bounds in Em; lra).
  set (m := RN (fm a + fm b)) in *.
  (* the value: w = v_a + v_b or v_a − v_b, exact W = A ± B *)
  set (w := if sub then fv a - fv b else fv a + fv b).
  set (W := if sub then A - B else A + B).
  assert (Ev : Rabs (RN w - w) <= u * Rabs w).
  { unfold w. destruct sub; [apply RN_minus_err | apply RN_plus_err]; assumption. }
  assert (Hw : Rabs w <= fm a + fm b).
  { unfold w. destruct sub.
    - unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra.
    - eapply Rle_trans; [apply Rabs_triang|]. lra. }
  assert (Ew : Rabs (w - W) <= alpha * fm a + beta1 + (alpha * fm b + beta2)).
  { unfold w, W. destruct sub.
    - replace (fv a - fv b - (A - B)) with ((fv a - A) - (fv b - B)) by ring.
      unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra.
    - replace (fv a + fv b - (A + B)) with ((fv a - A) + (fv b - B)) by ring.
      eapply Rle_trans; [apply Rabs_triang|]. lra. }
  assert (Hv : fv (if sub then term_sub a b else term_add a b) = RN w) by (unfold w; destruct sub; reflexivity).
  assert (Hm : fm (if sub then term_sub a b else term_add a b) = m) by (destruct sub; reflexivity).
  unfold approx. rewrite Hv, Hm. fold W.
  repeat split.
  - apply binary64_RN.
  - exact Bm.
  - exact Pm.
  - rewrite <- RN_abs. unfold m. apply RN_le. exact Hw.
  - replace (RN w - W) with ((RN w - w) + (w - W)) by ring.
    eapply Rle_trans; [apply Rabs_triang|].
    assert (F1 : u * Rabs w <= u * (fm a + fm b)) by (apply Rmult_le_compat_l; lra).
    assert (F2 : (u + alpha) * (fm a + fm b) <= (u + alpha) * ((1 + u) * m)) by (apply Rmult_le_compat_l; lra).
    nra.
Qed.

Lemma term_add_approx : forall a b A B alpha beta1 beta2,
  approx a A alpha beta1 -> approx b B alpha beta2 -> 0 <= alpha ->
  approx (term_add a b) (A + B) ((u + alpha) * (1 + u)) (beta1 + beta2).
Proof. intros. apply (term_addsub_approx false); assumption. Qed.

Lemma term_sub_approx : forall a b A B alpha beta1 beta2,
  approx a A alpha beta1 -> approx b B alpha beta2 -> 0 <= alpha ->
  approx (term_sub a b) (A - B) ((u + alpha) * (1 + u)) (beta1 + beta2).
Proof. intros. apply (term_addsub_approx true); assumption. Qed.

(** A leaf x (within relative error ex ≤ u of X) times a value: the absolute part β of the value is scaled by
    |x| — the dynamic absolute term. *)
Lemma leaf_scale_approx : forall x X c C alpha beta ex,
  binary64 x -> 0 <= ex <= u -> Rabs (X - x) <= ex * Rabs x ->
  approx c C alpha beta -> 0 <= alpha <= 1 -> 0 <= beta ->
  approx (leaf_scale x c) (X * C)
         ((u + alpha + ex * (1 + alpha)) * (1 + 2 * u))
         (Rabs x * ((1 + ex) * beta) + (1 + (u + alpha + ex * (1 + alpha)) * (1 + 2 * u)) * eta).
Proof.
  intros x X c C alpha beta ex Bx Hex HX [Bc [Bmc [Pc [Dc Ec]]]] Ha Hb.
  pose proof u_pos. pose proof u_small. pose proof eta_pos.
  unfold approx, leaf_scale. cbn [fv fm].
  set (mc := fm c) in *. set (vc := fv c) in *.
  set (Q := Rabs x * mc).
  pose proof (Rabs_pos x) as Px.
  assert (PQ : 0 <= Q) by (unfold Q; apply Rmult_le_pos; lra).
  set (m := RN Q).
  assert (Pm : 0 <= m) by (apply RN_nonneg; exact PQ).
  assert (HQ : Q <= (1 + 2 * u) * (m + eta)).
  { pose proof (abs_before_rounding Q) as HH. fold m in HH. rewrite (Rabs_nonneg_eq Q PQ), (Rabs_nonneg_eq m Pm) in HH. exact HH. }
  assert (Hxv : Rabs (x * vc) <= Q) by (rewrite Rabs_mult; apply Rmult_le_compat_l; lra).
  repeat split.
  - apply binary64_RN.
  - apply binary64_RN.
  - exact Pm.
  - rewrite <- RN_abs. apply RN_le. exact Hxv.
  - (* |v − XC| ≤ |v − x·vc| + |x|·|vc − C| + |X − x|·|C| *)
    pose proof (RN_err (x * vc)) as E1.
    assert (RC : Rabs C <= mc + (alpha * mc + beta)).
    { apply Rabs_close' in Ec. lra. }
    assert (T1 : Rabs (x * (vc - C)) <= Rabs x * (alpha * mc + beta))
      by (rewrite Rabs_mult; apply Rmult_le_compat_l; lra).
    assert (T2 : Rabs ((X - x) * C) <= ex * Rabs x * (mc + (alpha * mc + beta))).
    { rewrite Rabs_mult. apply Rmult_le_compat; try apply Rabs_pos; lra. }
    replace (RN (x * vc) - X * C) with ((RN (x * vc) - x * vc) + x * (vc - C) - (X - x) * C) by ring.
    unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
    eapply Rle_trans; [apply Rplus_le_compat_r, Rabs_triang|].
    assert (E1' : Rabs (RN (x * vc) - x * vc) <= u * Q + eta).
    { eapply Rle_trans; [exact E1|]. apply Rplus_le_compat_r, Rmult_le_compat_l; lra. }
    set (K := u + alpha + ex * (1 + alpha)).
    assert (PK : 0 <= K) by (unfold K; nra).
    assert (S : u * Q + Rabs x * (alpha * mc + beta) + ex * Rabs x * (mc + (alpha * mc + beta))
                = K * Q + Rabs x * ((1 + ex) * beta)) by (unfold K, Q; ring).
    assert (KQ : K * Q <= K * ((1 + 2 * u) * (m + eta))) by (apply Rmult_le_compat_l; lra).
    nra.
Qed.

(** ** The determinant. *)

(** One cross component y_j z_k − y_k z_j. *)
Lemma cross_approx : forall yj zk yk zj Yj Zk Yk Zj,
  binary64 yj -> binary64 zk -> binary64 yk -> binary64 zj ->
  Rabs (Yj - yj) <= u * Rabs yj -> Rabs (Zk - zk) <= u * Rabs zk ->
  Rabs (Yk - yk) <= u * Rabs yk -> Rabs (Zj - zj) <= u * Rabs zj ->
  approx (term_sub (leaf_mul yj zk) (leaf_mul yk zj)) (Yj * Zk - Yk * Zj) (4 * u + 11 * (u * u)) ((2 + 6 * u) * eta).
Proof.
  intros. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  eapply approx_weaken.
  - apply term_sub_approx; [apply leaf_mul_approx; assumption | apply leaf_mul_approx; assumption |].
    rewrite u_val. lra.
  - rewrite u_val. nra.
  - lra.
Qed.

(** One outer term x_i·c_i, with x within ex ≤ u of X. *)
Lemma outer_approx : forall x X c C ex,
  binary64 x -> 0 <= ex <= u -> Rabs (X - x) <= ex * Rabs x ->
  approx c C (4 * u + 11 * (u * u)) ((2 + 6 * u) * eta) ->
  approx (leaf_scale x c) (X * C) (5 * u + ex + 40 * (u * u)) (Rabs x * (3 * eta) + 2 * eta).
Proof.
  intros x X c C ex Bx Hex HX Hc. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  eapply approx_weaken.
  - apply leaf_scale_approx; try eassumption; rewrite ?u_val in *; lra.
  - rewrite u_val in *. nra.
  - pose proof (Rabs_pos x).
    assert (F : Rabs x * ((1 + ex) * ((2 + 6 * u) * eta)) <= Rabs x * (3 * eta)).
    { apply Rmult_le_compat_l; [lra|]. rewrite u_val in *. nra. }
    assert (G : (1 + (u + (4 * u + 11 * (u * u)) + ex * (1 + (4 * u + 11 * (u * u)))) * (1 + 2 * u)) * eta <= 2 * eta).
    { apply Rmult_le_compat_r; [lra|]. rewrite u_val in *. nra. }
    lra.
Qed.

(** det(x, y, z) = x·(y × z), the formula's order, with y, z within relative error u and x within ex ≤ u. *)
Definition det3_exact (X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 : R) : R :=
  X0 * (Y1 * Z2 - Y2 * Z1) + X1 * (Y2 * Z0 - Y0 * Z2) + X2 * (Y0 * Z1 - Y1 * Z0).

Definition det3_alpha (ex : R) : R := 7 * u + ex + 60 * (u * u).

Lemma det3_approx : forall x0 x1 x2 y0 y1 y2 z0 z1 z2 X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 ex,
  binary64 x0 -> binary64 x1 -> binary64 x2 -> binary64 y0 -> binary64 y1 -> binary64 y2 ->
  binary64 z0 -> binary64 z1 -> binary64 z2 -> 0 <= ex <= u ->
  Rabs (X0 - x0) <= ex * Rabs x0 -> Rabs (X1 - x1) <= ex * Rabs x1 -> Rabs (X2 - x2) <= ex * Rabs x2 ->
  Rabs (Y0 - y0) <= u * Rabs y0 -> Rabs (Y1 - y1) <= u * Rabs y1 -> Rabs (Y2 - y2) <= u * Rabs y2 ->
  Rabs (Z0 - z0) <= u * Rabs z0 -> Rabs (Z1 - z1) <= u * Rabs z1 -> Rabs (Z2 - z2) <= u * Rabs z2 ->
  approx (det3 x0 x1 x2 y0 y1 y2 z0 z1 z2) (det3_exact X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2)
         (det3_alpha ex) ((Rabs x0 + Rabs x1 + Rabs x2) * (3 * eta) + 6 * eta).
Proof.
  intros. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  unfold det3, det3_exact.
  set (at_ := 5 * u + ex + 40 * (u * u)).
  assert (P0 := outer_approx x0 X0 _ _ ex ltac:(assumption) ltac:(assumption) ltac:(assumption)
                  (cross_approx y1 z2 y2 z1 Y1 Z2 Y2 Z1 ltac:(assumption) ltac:(assumption) ltac:(assumption)
                     ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption))).
  assert (P1 := outer_approx x1 X1 _ _ ex ltac:(assumption) ltac:(assumption) ltac:(assumption)
                  (cross_approx y2 z0 y0 z2 Y2 Z0 Y0 Z2 ltac:(assumption) ltac:(assumption) ltac:(assumption)
                     ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption))).
  assert (P2 := outer_approx x2 X2 _ _ ex ltac:(assumption) ltac:(assumption) ltac:(assumption)
                  (cross_approx y0 z1 y1 z0 Y0 Z1 Y1 Z0 ltac:(assumption) ltac:(assumption) ltac:(assumption)
                     ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption))).
  fold at_ in P0, P1, P2.
  assert (Pat : 0 <= at_) by (unfold at_; nra).
  pose proof (term_add_approx _ _ _ _ _ _ _ P0 P1 Pat) as S01.
  assert (P2' : approx (leaf_scale x2 (term_sub (leaf_mul y0 z1) (leaf_mul y1 z0))) (X2 * (Y0 * Z1 - Y1 * Z0))
                       ((u + at_) * (1 + u)) (Rabs x2 * (3 * eta) + 2 * eta)).
  { eapply approx_weaken; [exact P2| |lra]. nra. }
  assert (Pa : 0 <= (u + at_) * (1 + u)) by nra.
  pose proof (term_add_approx _ _ _ _ _ _ _ S01 P2' Pa) as S.
  eapply approx_weaken; [exact S| |].
  - unfold det3_alpha, at_. rewrite u_val in *. nra.
  - lra.
Qed.

(** ** The bound covers the error. *)

Lemma binary64_triangle_absolute : binary64 triangle_absolute.
Proof. apply binary64_bpow. lia. Qed.

Lemma triangle_absolute_eta : triangle_absolute = 64 * eta.
Proof.
  unfold triangle_absolute, eta. replace (-1069)%Z with (6 + -1075)%Z by lia.
  rewrite bpow_plus. simpl bpow. lra.
Qed.

Lemma triangle_absolute_scale_eta : triangle_absolute_scale = 32 * eta.
Proof.
  unfold triangle_absolute_scale, eta. replace (-1070)%Z with (5 + -1075)%Z by lia.
  rewrite bpow_plus. simpl bpow. lra.
Qed.

(** A = (K_A ⊗ S) ⊕ U_A ≥ (1 − u)(K_A(1 − u)³·Σ|x_i| − η + U_A): S sums doubles (relative errors only). *)
Lemma absolute_term_lower : forall x0 x1 x2, binary64 x0 -> binary64 x1 -> binary64 x2 ->
  binary64 (absolute_term x0 x1 x2) /\
  (1 - u) * (triangle_absolute_scale * ((1 - u) * ((1 - u) * (1 - u))) * (Rabs x0 + Rabs x1 + Rabs x2) - eta +
             triangle_absolute) <= absolute_term x0 x1 x2.
Proof.
  intros x0 x1 x2 B0 B1 B2. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  split; [apply binary64_RN|].
  unfold absolute_term.
  pose proof (Rabs_pos x0). pose proof (Rabs_pos x1). pose proof (Rabs_pos x2).
  assert (A0 := binary64_abs _ B0). assert (A1 := binary64_abs _ B1). assert (A2 := binary64_abs _ B2).
  set (s1 := RN (Rabs x0 + Rabs x1)).
  pose proof (RN_plus_err _ _ A0 A1) as E1. fold s1 in E1.
  rewrite (Rabs_nonneg_eq (Rabs x0 + Rabs x1)) in E1 by lra. apply Rabs_bounds in E1.
  assert (Bs1 : binary64 s1) by apply binary64_RN.
  set (s := RN (s1 + Rabs x2)).
  pose proof (RN_plus_err _ _ Bs1 A2) as E2. fold s in E2.
  assert (Ps1 : 0 <= s1) by (unfold s1; apply RN_nonneg; lra).
  rewrite (Rabs_nonneg_eq (s1 + Rabs x2)) in E2 by lra. apply Rabs_bounds in E2.
  assert (G1 : (1 - u) * ((1 - u) * (Rabs x0 + Rabs x1)) <= (1 - u) * s1) by (apply Rmult_le_compat_l; lra).
  assert (G2 : (1 - u) * ((1 - u) * Rabs x2) <= (1 - u) * Rabs x2).
  { apply Rmult_le_compat_l; [lra|]. assert (0 <= u * Rabs x2) by nra. lra. }
  assert (Hs : (1 - u) * ((1 - u) * (Rabs x0 + Rabs x1 + Rabs x2)) <= s) by lra.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in *.
  set (k := RN (32 * eta * s)).
  assert (Ps : 0 <= s) by nra.
  pose proof (RN_err (32 * eta * s)) as E3. fold k in E3.
  rewrite (Rabs_nonneg_eq (32 * eta * s)) in E3 by nra. apply Rabs_bounds in E3.
  assert (Bk : binary64 k) by apply binary64_RN.
  assert (B64 : binary64 (64 * eta)) by (rewrite <- triangle_absolute_eta; apply binary64_triangle_absolute).
  assert (Pk : 0 <= k) by (unfold k; apply RN_nonneg; nra).
  pose proof (RN_plus_err _ _ Bk B64) as E4.
  rewrite (Rabs_nonneg_eq (k + 64 * eta)) in E4 by lra. apply Rabs_bounds in E4.
  assert (F : 32 * eta * ((1 - u) * ((1 - u) * (1 - u))) * (Rabs x0 + Rabs x1 + Rabs x2) <= 32 * eta * s * (1 - u)).
  { assert (0 <= 32 * eta * (1 - u)) by nra.
    replace (32 * eta * ((1 - u) * ((1 - u) * (1 - u))) * (Rabs x0 + Rabs x1 + Rabs x2))
      with (32 * eta * (1 - u) * ((1 - u) * ((1 - u) * (Rabs x0 + Rabs x1 + Rabs x2)))) by ring.
    replace (32 * eta * s * (1 - u)) with (32 * eta * (1 - u) * s) by ring.
    apply Rmult_le_compat_l; assumption. }
  nra.
Qed.

(** (C ⊗ m) ⊕ A ≥ C(1 − u)²·m + (1 − u)(A − η): it covers α·m + β when α ≤ C(1 − u)² and β ≤ (1 − u)(A − η). *)
Lemma bound_covers : forall t V alpha beta C A,
  approx t V alpha beta -> binary64 A -> 0 <= C -> eta <= A ->
  alpha <= C * ((1 - u) * (1 - u)) -> beta <= (1 - u) * (A - eta) ->
  Rabs (fv t - V) <= det3_bound t C A.
Proof.
  intros t V alpha beta C A [_ [_ [Pm [_ E]]]] BA PC HA Ha Hb.
  pose proof u_pos. pose proof u_small. pose proof eta_pos.
  unfold det3_bound. set (m := fm t) in *.
  set (X := RN (C * m)).
  pose proof (RN_err (C * m)) as E1. fold X in E1.
  rewrite (Rabs_nonneg_eq (C * m)) in E1 by nra. apply Rabs_bounds in E1.
  assert (PX : 0 <= X) by (apply RN_nonneg; nra).
  pose proof (RN_plus_err X A ltac:(apply binary64_RN) BA) as E2.
  rewrite (Rabs_nonneg_eq (X + A)) in E2 by lra. apply Rabs_bounds in E2.
  assert (F : alpha * m <= C * ((1 - u) * (1 - u)) * m) by (apply Rmult_le_compat_r; assumption).
  nra.
Qed.

(** A sign certified from an enclosure by the bound is the exact sign. *)
Lemma det3_filter_sound_gen : forall t V C A, Rabs (fv t - V) <= det3_bound t C A ->
  certifies (sign_from_Z (det3_filter_lanes t C A)) V.
Proof.
  intros t V C A Enc. apply Rabs_bounds in Enc.
  unfold det3_filter_lanes, sign_lanes. set (B := det3_bound t C A) in *.
  destruct (Rlt_bool_spec B (fv t)) as [L|L]; destruct (Rlt_bool_spec (fv t) (- B)) as [L'|L']; simpl;
    try exact I; lra.
Qed.

(** ** The values of a ray–triangle query. *)

Definition doubles3 (v : vec3) : Prop := binary64 (vx v) /\ binary64 (vy v) /\ binary64 (vz v).

(** The leaves ê = v ⊖ o of kernel/src/triangle/ray_triangle_stages.hpp ([triangle_filter_values]). *)
Definition rsub (v o : vec3) : vec3 := Vec3 (RN (vx v - vx o)) (RN (vy v - vy o)) (RN (vz v - vz o)).
Definition det3v (x y z : vec3) : FTerm := det3 (vx x) (vy x) (vz x) (vx y) (vy y) (vz y) (vx z) (vy z) (vz z).
Definition absolute_v (x : vec3) : R := absolute_term (vx x) (vy x) (vz x).

(** π(p, q) = d·(ê_p × ê_q) (πa = π(b, c), πb = π(c, a), πc = π(a, b)), num = ê_a·(ê_b × ê_c),
    den = (πa ⊕ πb) ⊕ πc. *)
Definition pi_stage1 (o d p q : vec3) : FTerm := det3v d (rsub p o) (rsub q o).
Definition num_stage1 (o a b c : vec3) : FTerm := det3v (rsub a o) (rsub b o) (rsub c o).
Definition den_stage1 (o d a b c : vec3) : FTerm :=
  term_add (term_add (pi_stage1 o d b c) (pi_stage1 o d c a)) (pi_stage1 o d a b).

(** The exact values (docs/contract.md §6). *)
Definition cross (y z : vec3) : vec3 :=
  Vec3 (vy y * vz z - vz y * vy z) (vz y * vx z - vx y * vz z) (vx y * vy z - vy y * vx z).
Definition edge_value (o d p q : vec3) : R := dot d (cross (sub p o) (sub q o)).
Definition num_value (o a b c : vec3) : R := dot (sub a o) (cross (sub b o) (sub c o)).
Definition den_value (o d a b c : vec3) : R := edge_value o d b c + edge_value o d c a + edge_value o d a b.

Lemma leaf_error : forall v o, binary64 v -> binary64 o -> Rabs ((v - o) - RN (v - o)) <= u * Rabs (RN (v - o)).
Proof. intros. rewrite Rabs_minus_sym. now apply RN_minus_err_round. Qed.

Lemma exact_leaf : forall x, Rabs (x - x) <= 0 * Rabs x.
Proof. intros. unfold Rminus. rewrite Rplus_opp_r, Rabs_R0. lra. Qed.

Lemma pi_approx : forall o d p q, doubles3 o -> doubles3 d -> doubles3 p -> doubles3 q ->
  approx (pi_stage1 o d p q) (edge_value o d p q) (det3_alpha 0)
         ((Rabs (vx d) + Rabs (vy d) + Rabs (vz d)) * (3 * eta) + 6 * eta).
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [qx qy qz] [Box [Boy Boz]] [Bdx [Bdy Bdz]] [Bpx [Bpy Bpz]] [Bqx [Bqy Bqz]].
  cbn [vx vy vz] in *. pose proof u_pos.
  unfold pi_stage1, det3v, rsub, edge_value, dot, cross, sub. cbn [vx vy vz].
  replace (dx * ((py - oy) * (qz - oz) - (pz - oz) * (qy - oy)) + dy * ((pz - oz) * (qx - ox) - (px - ox) * (qz - oz)) +
           dz * ((px - ox) * (qy - oy) - (py - oy) * (qx - ox)))
    with (det3_exact dx dy dz (px - ox) (py - oy) (pz - oz) (qx - ox) (qy - oy) (qz - oz)) by (unfold det3_exact; ring).
  apply det3_approx; try apply binary64_RN; try assumption; try apply exact_leaf; try apply leaf_error; try assumption;
    lra.
Qed.

Lemma num_approx : forall o a b c, doubles3 o -> doubles3 a -> doubles3 b -> doubles3 c ->
  approx (num_stage1 o a b c) (num_value o a b c) (det3_alpha u)
         ((Rabs (vx (rsub a o)) + Rabs (vy (rsub a o)) + Rabs (vz (rsub a o))) * (3 * eta) + 6 * eta).
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz] [Box [Boy Boz]] [Bax [Bay Baz]] [Bbx [Bby Bbz]] [Bcx [Bcy Bcz]].
  cbn [vx vy vz] in *. pose proof u_pos.
  unfold num_stage1, det3v, rsub, num_value, dot, cross, sub. cbn [vx vy vz].
  replace ((ax - ox) * ((by_ - oy) * (cz - oz) - (bz - oz) * (cy - oy)) +
           (ay - oy) * ((bz - oz) * (cx - ox) - (bx - ox) * (cz - oz)) +
           (az - oz) * ((bx - ox) * (cy - oy) - (by_ - oy) * (cx - ox)))
    with (det3_exact (ax - ox) (ay - oy) (az - oz) (bx - ox) (by_ - oy) (bz - oz) (cx - ox) (cy - oy) (cz - oz))
    by (unfold det3_exact; ring).
  apply det3_approx; try apply binary64_RN; try apply leaf_error; try assumption; lra.
Qed.

(** ** Main theorems: the enclosures, and the signs the filter certifies. *)

Theorem pi_filter_encloses : forall o d p q, doubles3 o -> doubles3 d -> doubles3 p -> doubles3 q ->
  Rabs (fv (pi_stage1 o d p q) - edge_value o d p q) <=
    det3_bound (pi_stage1 o d p q) triangle_filter_pi_relative (absolute_v d).
Proof.
  intros o d p q Bo Bd Bp Bq. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  destruct Bd as [Bdx [Bdy Bdz]].
  destruct (absolute_term_lower (vx d) (vy d) (vz d) Bdx Bdy Bdz) as [BA HA]. fold (absolute_v d) in BA, HA.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  pose proof (Rabs_pos (vx d)). pose proof (Rabs_pos (vy d)). pose proof (Rabs_pos (vz d)).
  apply bound_covers with (alpha := det3_alpha 0)
                          (beta := (Rabs (vx d) + Rabs (vy d) + Rabs (vz d)) * (3 * eta) + 6 * eta).
  - apply pi_approx; [exact Bo | repeat split; assumption | exact Bp | exact Bq].
  - exact BA.
  - unfold triangle_filter_pi_relative. lra.
  - rewrite u_val in *. nra.
  - unfold det3_alpha, triangle_filter_pi_relative. rewrite u_val. lra.
  - rewrite u_val in *. nra.
Qed.

Theorem pi_filter_sound : forall o d p q, doubles3 o -> doubles3 d -> doubles3 p -> doubles3 q ->
  certifies (sign_from_Z (det3_filter_lanes (pi_stage1 o d p q) triangle_filter_pi_relative (absolute_v d)))
            (edge_value o d p q).
Proof. intros. apply det3_filter_sound_gen. now apply pi_filter_encloses. Qed.

Theorem num_filter_encloses : forall o a b c, doubles3 o -> doubles3 a -> doubles3 b -> doubles3 c ->
  Rabs (fv (num_stage1 o a b c) - num_value o a b c) <=
    det3_bound (num_stage1 o a b c) triangle_filter_num_relative (absolute_v (rsub a o)).
Proof.
  intros o a b c Bo Ba Bb Bc. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  destruct (absolute_term_lower (vx (rsub a o)) (vy (rsub a o)) (vz (rsub a o)) ltac:(apply binary64_RN)
              ltac:(apply binary64_RN) ltac:(apply binary64_RN)) as [BA HA].
  fold (absolute_v (rsub a o)) in BA, HA.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  pose proof (Rabs_pos (vx (rsub a o))). pose proof (Rabs_pos (vy (rsub a o))). pose proof (Rabs_pos (vz (rsub a o))).
  apply bound_covers with (alpha := det3_alpha u)
    (beta := (Rabs (vx (rsub a o)) + Rabs (vy (rsub a o)) + Rabs (vz (rsub a o))) * (3 * eta) + 6 * eta).
  - now apply num_approx.
  - exact BA.
  - unfold triangle_filter_num_relative. lra.
  - rewrite u_val in *. nra.
  - unfold det3_alpha, triangle_filter_num_relative. rewrite u_val. lra.
  - rewrite u_val in *. nra.
Qed.

Theorem num_filter_sound : forall o a b c, doubles3 o -> doubles3 a -> doubles3 b -> doubles3 c ->
  certifies (sign_from_Z (det3_filter_lanes (num_stage1 o a b c) triangle_filter_num_relative
                                            (absolute_v (rsub a o))))
            (num_value o a b c).
Proof. intros. apply det3_filter_sound_gen. now apply num_filter_encloses. Qed.

Lemma den_approx : forall o d a b c, doubles3 o -> doubles3 d -> doubles3 a -> doubles3 b -> doubles3 c ->
  approx (den_stage1 o d a b c) (den_value o d a b c) ((u + (u + det3_alpha 0) * (1 + u)) * (1 + u))
         (3 * ((Rabs (vx d) + Rabs (vy d) + Rabs (vz d)) * (3 * eta) + 6 * eta)).
Proof.
  intros o d a b c Bo Bd Ba Bb Bc. pose proof u_pos.
  unfold den_stage1, den_value.
  assert (P0 : 0 <= det3_alpha 0) by (unfold det3_alpha; nra).
  pose proof (term_add_approx _ _ _ _ _ _ _ (pi_approx o d b c Bo Bd Bb Bc) (pi_approx o d c a Bo Bd Bc Ba) P0) as S.
  assert (P2 : approx (pi_stage1 o d a b) (edge_value o d a b) ((u + det3_alpha 0) * (1 + u))
                 ((Rabs (vx d) + Rabs (vy d) + Rabs (vz d)) * (3 * eta) + 6 * eta)).
  { eapply approx_weaken; [apply pi_approx; assumption| |lra]. nra. }
  eapply approx_weaken; [apply (term_add_approx _ _ _ _ _ _ _ S P2); nra | lra | lra].
Qed.

Theorem den_filter_encloses : forall o d a b c, doubles3 o -> doubles3 d -> doubles3 a -> doubles3 b -> doubles3 c ->
  Rabs (fv (den_stage1 o d a b c) - den_value o d a b c) <=
    det3_bound (den_stage1 o d a b c) triangle_filter_den_relative (absolute_v d).
Proof.
  intros o d a b c Bo Bd Ba Bb Bc. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  pose proof Bd as [Bdx [Bdy Bdz]].
  destruct (absolute_term_lower (vx d) (vy d) (vz d) Bdx Bdy Bdz) as [BA HA]. fold (absolute_v d) in BA, HA.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  pose proof (Rabs_pos (vx d)). pose proof (Rabs_pos (vy d)). pose proof (Rabs_pos (vz d)).
  eapply bound_covers.
  - apply den_approx; assumption.
  - exact BA.
  - unfold triangle_filter_den_relative. lra.
  - rewrite u_val in *. nra.
  - unfold det3_alpha, triangle_filter_den_relative. rewrite u_val. nra.
  - rewrite u_val in *. nra.
Qed.

Theorem den_filter_sound : forall o d a b c, doubles3 o -> doubles3 d -> doubles3 a -> doubles3 b -> doubles3 c ->
  certifies (sign_from_Z (det3_filter_lanes (den_stage1 o d a b c) triangle_filter_den_relative (absolute_v d)))
            (den_value o d a b c).
Proof. intros. apply det3_filter_sound_gen. now apply den_filter_encloses. Qed.

(** The general enclosure, for any determinant of leaves within the stated errors (the three above are its
    instances; stated separately for the record). *)
Theorem det3_filter_encloses : forall x0 x1 x2 y0 y1 y2 z0 z1 z2 X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 ex C,
  binary64 x0 -> binary64 x1 -> binary64 x2 -> binary64 y0 -> binary64 y1 -> binary64 y2 ->
  binary64 z0 -> binary64 z1 -> binary64 z2 -> 0 <= ex <= u ->
  Rabs (X0 - x0) <= ex * Rabs x0 -> Rabs (X1 - x1) <= ex * Rabs x1 -> Rabs (X2 - x2) <= ex * Rabs x2 ->
  Rabs (Y0 - y0) <= u * Rabs y0 -> Rabs (Y1 - y1) <= u * Rabs y1 -> Rabs (Y2 - y2) <= u * Rabs y2 ->
  Rabs (Z0 - z0) <= u * Rabs z0 -> Rabs (Z1 - z1) <= u * Rabs z1 -> Rabs (Z2 - z2) <= u * Rabs z2 ->
  det3_alpha ex <= C * ((1 - u) * (1 - u)) ->
  Rabs (fv (det3 x0 x1 x2 y0 y1 y2 z0 z1 z2) - det3_exact X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2) <=
    det3_bound (det3 x0 x1 x2 y0 y1 y2 z0 z1 z2) C (absolute_term x0 x1 x2).
Proof.
  intros. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  destruct (absolute_term_lower x0 x1 x2) as [BA HA]; try assumption.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  pose proof (Rabs_pos x0). pose proof (Rabs_pos x1). pose proof (Rabs_pos x2).
  assert (PC : 0 <= C).
  { assert (0 < det3_alpha ex) by (unfold det3_alpha; nra). assert (0 < (1 - u) * (1 - u)) by nra. nra. }
  eapply bound_covers; [apply det3_approx; eassumption | exact BA | exact PC | | eassumption |];
    rewrite u_val in *; nra.
Qed.
