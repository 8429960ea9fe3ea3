(** * The ray–sphere roots' boundary filter: the signs of q(m) and of the slope at a rounding boundary
    (kernel/src/sphere/ray_sphere_boundary_filter.hpp, [sphere_boundary_filter]; the bounds' derivation:
    kernel/src/core/error_bounds.hpp, "Ray–sphere roots").

    What it certifies: at a boundary m = (x + y)/2, a certain sign of q̂ = 4q(m) against E_q is the sign of the
    exact 4q(m) = Σ_i (2(o_i − c_i) + (x + y)·d_i)² − (2r)², and a certain sign of the slope ŝ against E_s is the
    sign of the exact 2(A·m + B) = Σ_i d_i·(2(o_i − c_i) + (x + y)·d_i), for every binary64 input (subnormal
    included).

    Main theorems:
    - [sphere_boundary_q_encloses]: the value is RN(z) for a real z with |4q(m) − z| ≤ E_q = (κ_q ⊗ W) ⊕ μ_q;
    - [sphere_boundary_q_sound]: a certain sign of q is the sign of the exact 4q(m);
    - [sphere_boundary_slope_encloses]: |ŝ − 2(A·m + B)| ≤ E_s = (κ_s ⊗ Σ_i |d_i| ⊗ ((|H_i| ⊕ T_i) ⊕ 2^-1000)) ⊕ μ_s;
    - [sphere_boundary_slope_sound]: a certain sign of the slope (read only when q's is positive) is the sign of
      the exact 2(A·m + B).

    The model: RN on the reals, no overflow (core/Model.v, as PlaneFilter.v and SphereFilter.v); two_sum,
    two_diff and two_prod are the error-free transformations of core/eft.hpp (two_prod the FMA TwoProduct: one
    rounding), fma one rounding; [boundary] follows the C++ operation by operation (-ffp-contract=off), the slope's
    magnitude summed from 0 as the C++'s loop. The finiteness checks (W, |value|, the slope's magnitude at most the
    largest double) are in [boundary_q_sign] / [boundary_slope_sign], where in the model they only make answers
    uncertain; with IEEE overflow they are what keeps the answer uncertain (error_bounds.hpp's argument).

    The hypotheses: every input (o, d, c, r, x, y) is a binary64 number; nothing else (no range, no normality).

    Found by this proof: the slope's bound once had no absolute term, E_s = κ_s ⊗ Σ_i |d_i| ⊗ (…), and was
    wrong. Each product d_i ⊗ H_i can lose up to η = 2^-1075 to underflow, which the floor 2^-1000 per |d_i| covers
    only when |d_i| is not tiny. Counterexample (checked with the C++ routine and exact rationals): o = (0.255,
    0.245, 0.245) (the nearest doubles), c = (0, 0, 0), r = 0.125, d = (2^-1074, −2^-1074, −2^-1074), x = y = 1:
    q(m) is certified positive (correctly), the slope is computed as 2^-1074 with E_s = 0 and was certified
    positive, but the exact 2(A·m + B) = −0.47·2^-1074 < 0 (the same with normal inputs: o scaled by 2^-474,
    d = (2^-600, −2^-600, −2^-600), r = 2^-480). The fix, in the C++ and here: E_s = (κ_s ⊗ magnitude) ⊕ μ_s with
    μ_s = 2^-1070 = 32η ([sphere_boundary_slope_absolute]), which covers the three products' underflow (3η) and
    the roundings of E_s itself; tests/sphere_test.cpp keeps the case. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core Mult_error.
From Raykernel Require Import Constants Model.
From Raykernel.Sphere Require Import SphereFilter.
Open Scope R_scope.

Record Axis := { axis_h : R; axis_l : R; axis_t : R }.

Definition axis (o c d m1 m2 : R) : Axis :=
  let f := two_diff o c in
  let p := RN (m1 * d) in
  let pi := fma m1 d (- p) in
  let q := RN (m2 * d) in
  let head := two_sum (RN (fst f + fst f)) p in
  {| axis_h := fst head;
     axis_l := RN (RN (snd head + RN (snd f + snd f)) + RN (pi + q));
     axis_t := RN (RN (Rabs (fst f) + Rabs (fst f)) + Rabs p) |}.

Lemma RN_double : forall x, binary64 x -> RN (x + x) = x + x.
Proof.
  intros x Hx. apply RN_binary64.
  replace (x + x) with (x * bpow radix2 1) by (change (bpow radix2 1) with 2; ring).
  apply mult_bpow_pos_exact_FLT; [exact Hx | lia].
Qed.

Lemma abs_iv : forall x, - Rabs x <= x <= Rabs x /\ 0 <= Rabs x.
Proof. intros x. split; [apply Rabs_bounds, Rle_refl | apply Rabs_pos]. Qed.

Lemma RN_err_iv : forall z B, Rabs z <= B -> - (u * B + eta) <= RN z - z <= u * B + eta.
Proof.
  intros z B H. apply Rabs_bounds. eapply Rle_trans; [apply RN_err|].
  pose proof u_pos. apply Rplus_le_compat_r. apply Rmult_le_compat_l; lra.
Qed.

Lemma RN_sum_iv : forall a b B, binary64 a -> binary64 b -> Rabs (a + b) <= B ->
  - (u * B) <= RN (a + b) - (a + b) <= u * B.
Proof.
  intros a b B Ha Hb H. apply Rabs_bounds. eapply Rle_trans; [apply RN_plus_err; assumption|].
  pose proof u_pos. apply Rmult_le_compat_l; lra.
Qed.

Ltac absb x := let h := fresh "AB" in pose proof (abs_iv x) as h.
Ltac rabs := apply Rabs_le; split; lra.

(** Per axis: G = 2(o − c) + (M₁ + M₂)·d = H + L + δ. *)
Lemma axis_bounds : forall o c d m1 m2,
  binary64 o -> binary64 c -> binary64 d -> binary64 m1 -> binary64 m2 -> Rabs m2 <= u * Rabs m1 ->
  let a := axis o c d m1 m2 in
  binary64 (axis_h a) /\ binary64 (axis_l a) /\ 0 <= axis_t a /\
  Rabs (axis_h a) <= (1 + 3 * u) * axis_t a /\
  Rabs (axis_l a) <= 10 * u * axis_t a + 7 * eta /\
  Rabs (2 * (o - c) + (m1 + m2) * d - (axis_h a + axis_l a)) <= 18 * (u * u) * axis_t a + 6 * eta.
Proof.
  intros o c d m1 m2 Bo Bc Bd B1 B2 M2 a.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv.
  unfold a, axis, two_diff, fma. cbv zeta. cbn [axis_h axis_l axis_t].
  set (fh := fst (two_sum o (- c))). set (fl := snd (two_sum o (- c))).
  assert (Bc' : binary64 (- c)) by (apply binary64_opp; exact Bc).
  assert (E0 : fh + fl = o - c) by (unfold fh, fl; rewrite two_sum_exact; [ring | exact Bo | exact Bc']).
  destruct (two_sum_lo_bound o (- c) Bo Bc') as [_ Lf]. fold fh fl in Lf.
  assert (Bfh : binary64 fh) by apply binary64_two_sum_hi.
  assert (Bfl : binary64 fl) by apply binary64_two_sum_lo.
  rewrite (RN_double fh Bfh), (RN_double fl Bfl).
  set (p := RN (m1 * d)).
  assert (Bp : binary64 p) by apply binary64_RN.
  assert (B2fh : binary64 (fh + fh)) by (rewrite <- (RN_double fh Bfh); apply binary64_RN).
  assert (B2fl : binary64 (fl + fl)) by (rewrite <- (RN_double fl Bfl); apply binary64_RN).
  set (H := fst (two_sum (fh + fh) p)). set (h := snd (two_sum (fh + fh) p)).
  assert (EH : H + h = fh + fh + p) by (unfold H, h; apply two_sum_exact; assumption).
  destruct (two_sum_lo_bound (fh + fh) p B2fh Bp) as [Lh _]. fold h in Lh.
  assert (BH : binary64 H) by apply binary64_two_sum_hi.
  assert (Bh : binary64 h) by apply binary64_two_sum_lo.
  absb fh. absb fl. absb p. absb h. absb H. absb m1. absb m2. absb d.
  set (Fh := Rabs fh) in *. set (Pp := Rabs p) in *. set (Tx := Fh + Fh + Pp).
  assert (DTx : Tx = Fh + Fh + Pp) by reflexivity.
  (* T *)
  assert (BFh : binary64 Fh) by (apply binary64_abs; exact Bfh).
  rewrite (RN_double Fh BFh).
  set (T := RN (Fh + Fh + Pp)).
  assert (BFF : binary64 (Fh + Fh)) by (rewrite <- (RN_double Fh BFh); apply binary64_RN).
  assert (BPp : binary64 Pp) by (apply binary64_abs; exact Bp).
  assert (ET := RN_sum_iv (Fh + Fh) Pp Tx BFF BPp ltac:(unfold Tx; rabs)). fold T in ET.
  (* products *)
  assert (Ep : Rabs (p - m1 * d) <= u * Pp + eta) by (apply RN_err_round).
  apply Rabs_bounds in Ep.
  assert (Am1d : Rabs (m1 * d) <= Pp + u * Pp + eta) by rabs.
  assert (Am2d : Rabs (m2 * d) <= u * (Pp + u * Pp + eta)).
  { rewrite Rabs_mult. rewrite Rabs_mult in Am1d. apply Rle_trans with (u * Rabs m1 * Rabs d).
    - apply Rmult_le_compat_r; [apply Rabs_pos | exact M2].
    - rewrite Rmult_assoc. apply Rmult_le_compat_l; lra. }
  set (m1d := m1 * d) in *. set (m2d := m2 * d) in *.
  absb m2d.
  unfold fma.
  set (pi := RN (m1d + - p)).
  assert (Epi := RN_err_iv (m1d + - p) (u * Pp + eta) ltac:(rabs)). fold pi in Epi.
  set (q := RN (m2d)).
  assert (Eq := RN_err_iv m2d (u * (Pp + u * Pp + eta)) Am2d). fold q in Eq.
  assert (Bpi : binary64 pi) by apply binary64_RN.
  assert (Bq : binary64 q) by apply binary64_RN.
  (* the sums of L *)
  assert (Hh2 : Rabs h <= u * Tx).
  { eapply Rle_trans; [exact Lh|]. apply Rmult_le_compat_l; [lra|]. unfold Tx; rabs. }
  apply Rabs_bounds in Hh2. apply Rabs_bounds in Lf.
  assert (I1 : Rabs (h + (fl + fl)) <= u * Tx + 2 * (u * Fh)) by rabs.
  assert (Ea1 := RN_sum_iv h (fl + fl) _ Bh B2fl I1).
  set (a1 := RN (h + (fl + fl))) in *.
  assert (I2 : Rabs (pi + q) <= (u * Pp + eta) + (u * (u * Pp + eta) + eta) + (u * (Pp + u * Pp + eta))
                                + (u * (u * (Pp + u * Pp + eta)) + eta)) by rabs.
  assert (Ea2 := RN_sum_iv pi q _ Bpi Bq I2).
  set (a2 := RN (pi + q)) in *.
  assert (Ba1 : binary64 a1) by apply binary64_RN.
  assert (Ba2 : binary64 a2) by apply binary64_RN.
  assert (I3 : Rabs (a1 + a2) <= (u * Tx + 2 * (u * Fh)) * (1 + u) + ((u * Pp + eta) + (u * (u * Pp + eta) + eta)
                  + (u * (Pp + u * Pp + eta)) + (u * (u * (Pp + u * Pp + eta)) + eta)) * (1 + u)).
  { apply Rabs_bounds in I1. apply Rabs_bounds in I2. rewrite Uv in *. rabs. }
  assert (EL := RN_sum_iv a1 a2 _ Ba1 Ba2 I3).
  set (L := RN (a1 + a2)) in *.
  assert (BL : binary64 L) by apply binary64_RN.
  assert (BTx : 0 <= Tx) by (unfold Tx; lra).
  assert (HT : 0 <= T) by (apply RN_nonneg; lra).
  assert (TT : (1 - u) * Tx <= T) by (rewrite Uv in *; lra).
  assert (TTx : Tx <= (1 + 3 * u) * T) by (rewrite Uv in *; lra).
  assert (Eu : u * Tx <= u * ((1 + 3 * u) * T)) by (apply Rmult_le_compat_l; lra).
  assert (Eu2 : u * u * Tx <= u * u * ((1 + 3 * u) * T)) by (apply Rmult_le_compat_l; nra).
  assert (Epsilon : u * eta <= eta / 1000) by (rewrite Uv; lra).
  assert (Epsilon2 : u * (u * eta) <= eta / 1000) by (rewrite Uv; lra).
  repeat split; try assumption.
  - rewrite Uv in *. rabs.
  - apply Rabs_bounds in I3. rewrite Uv in *. rabs.
  - replace (2 * (o - c) + (m1 + m2) * d) with (fh + fh + fl + fl + m1d + m2d) by (unfold m1d, m2d; lra).
    apply Rabs_bounds in I1. apply Rabs_bounds in I2. apply Rabs_bounds in I3. rewrite Uv in *. rabs.
Qed.

(** One square: G² − (H² + k), k = L ⊗ ((H ⊕ H) ⊕ L). *)
Lemma prod_le : forall a b A B, Rabs a <= A -> Rabs b <= B -> Rabs (a * b) <= A * B.
Proof.
  intros a b A B Ha Hb. rewrite Rabs_mult.
  apply Rmult_le_compat; [apply Rabs_pos | apply Rabs_pos | exact Ha | exact Hb].
Qed.

Lemma eta_small : eta <= / 1000000 /\ eta * eta <= eta / 1000.
Proof.
  pose proof eta_pos.
  assert (E : eta <= / 1000000).
  { unfold eta. apply Rle_trans with (bpow radix2 (-20)).
    - apply bpow_le. lia.
    - simpl. lra. }
  split; [exact E | nra].
Qed.

Lemma square_part : forall G H L T,
  binary64 H -> binary64 L -> 0 <= T -> Rabs H <= (1 + 3 * u) * T ->
  Rabs L <= 10 * u * T + 7 * eta -> Rabs (G - (H + L)) <= 18 * (u * u) * T + 6 * eta ->
  let k := RN (L * RN (RN (H + H) + L)) in
  Rabs (G * G - (H * H + k)) <=
    80 * (u * u) * (T * Rabs H) + 600 * (u * (u * u)) * (T * T) + 14 * (eta * Rabs H) + eta * T + 2 * eta /\
  Rabs k <= 21 * u * (T * Rabs H) + 101 * (u * u) * (T * T) + 15 * (eta * Rabs H) + eta * T + 2 * eta.
Proof.
  intros G H L T BH BL PT AH AL AD k.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv. destruct eta_small as [Es Es2].
  subst k. rewrite (RN_double H BH).
  assert (B2H : binary64 (H + H)) by (rewrite <- (RN_double H BH); apply binary64_RN).
  absb H. absb L. set (Hh := Rabs H) in *.
  set (Lb := 10 * u * T + 7 * eta) in *. set (D := 18 * (u * u) * T + 6 * eta) in *.
  assert (DLb : Lb = 10 * u * T + 7 * eta) by reflexivity.
  assert (DD : D = 18 * (u * u) * T + 6 * eta) by reflexivity.
  set (delta := G - (H + L)) in *. absb delta.
  assert (I1 : Rabs (H + H + L) <= 2 * Hh + Lb) by rabs.
  pose proof (RN_sum_iv (H + H) L _ B2H BL I1) as Ev.
  set (v := RN (H + H + L)) in *.
  assert (Iv : Rabs v <= (1 + u) * (2 * Hh + Lb)) by (rewrite Uv in *; rabs).
  assert (Ivd : Rabs (v - (H + H + L)) <= u * (2 * Hh + Lb)) by rabs.
  pose proof (prod_le L v _ _ AL Iv) as P3.
  pose proof (prod_le L (v - (H + H + L)) _ _ AL Ivd) as P2.
  assert (I4 : Rabs (2 * H + 2 * L + delta) <= 2 * Hh + 2 * Lb + D) by rabs.
  pose proof (prod_le delta (2 * H + 2 * L + delta) _ _ AD I4) as P1.
  pose proof (RN_err (L * v)) as Ek. set (k := RN (L * v)) in *.
  set (Lv := L * v) in *. absb Lv.
  assert (Ek' : Rabs (k - Lv) <= u * (Lb * ((1 + u) * (2 * Hh + Lb))) + eta).
  { eapply Rle_trans; [exact Ek|]. apply Rplus_le_compat_r. apply Rmult_le_compat_l; lra. }
  apply Rabs_bounds in P1. apply Rabs_bounds in P2. apply Rabs_bounds in P3. apply Rabs_bounds in Ek'.
  assert (EQ : G * G - (H * H + k) =
               delta * (2 * H + 2 * L + delta) - L * (v - (H + H + L)) + (Lv - k)) by (unfold delta, Lv; ring).
  assert (PTH : 0 <= T * Hh) by nra. assert (PTT : 0 <= T * T) by nra.
  assert (PeH : 0 <= eta * Hh) by nra. assert (PeT : 0 <= eta * T) by nra.
  rewrite EQ. rewrite DLb, DD in *. rewrite Uv in *. split; rabs.
Qed.

(** A square by TwoProduct: S = H ⊗ H, σ = fma(H, H, −S). *)
Lemma square_facts : forall H, binary64 H ->
  let S := RN (H * H) in let sg := RN (H * H + - S) in
  binary64 S /\ binary64 sg /\ 0 <= S /\ Rabs (H * H - (S + sg)) <= eta /\
  Rabs sg <= 2 * u * S + 3 * eta /\ H * H <= (1 + u) * S + eta.
Proof.
  intros H BH S sg.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv.
  assert (PS : 0 <= S) by (apply RN_nonneg; nra).
  pose proof (two_prod_error H H BH BH) as E. unfold two_prod, fma in E. cbn [fst snd] in E. fold S sg in E.
  pose proof (RN_err_round (H * H)) as E1. fold S in E1. rewrite (Rabs_nonneg_eq S PS) in E1.
  apply Rabs_bounds in E1.
  assert (E2 := RN_err_iv (H * H + - S) (u * S + eta) ltac:(rabs)). fold sg in E2.
  repeat split; try apply binary64_RN; try assumption.
  - rewrite Uv in *. rabs.
  - lra.
Qed.

(** A rounded sum of two approximations: errors add, plus u times the magnitudes. *)
Lemma sum_step : forall a b A B ea eb ma mb, binary64 a -> binary64 b ->
  Rabs (a - A) <= ea -> Rabs (b - B) <= eb -> Rabs a <= ma -> Rabs b <= mb ->
  Rabs (RN (a + b) - (A + B)) <= ea + eb + u * (ma + mb) /\ Rabs (RN (a + b)) <= (1 + u) * (ma + mb).
Proof.
  intros a b A B ea eb ma mb Ba Bb Ea Eb Ma Mb.
  pose proof u_pos as Hu.
  assert (I : Rabs (a + b) <= ma + mb) by (eapply Rle_trans; [apply Rabs_triang | lra]).
  pose proof (RN_sum_iv a b _ Ba Bb I) as E.
  apply Rabs_bounds in Ea. apply Rabs_bounds in Eb. apply Rabs_bounds in I.
  split; apply Rabs_le; split; nra.
Qed.

Lemma leaf : forall x m, Rabs x <= m -> Rabs (x - x) <= 0 /\ Rabs x <= m.
Proof. intros x m H. split; [unfold Rminus; rewrite Rplus_opp_r, Rabs_R0; lra | exact H]. Qed.

Lemma q_relative_val : sphere_boundary_q_relative = / 79228162514264337593543950336.
Proof. unfold sphere_boundary_q_relative. simpl. lra. Qed.

Lemma tail_val : sphere_boundary_tail = / 35184372088832.
Proof. unfold sphere_boundary_tail. simpl. lra. Qed.

Lemma q_absolute_eta : sphere_boundary_q_absolute = 32768 * eta.
Proof.
  unfold sphere_boundary_q_absolute, eta. replace (-1060)%Z with (15 + -1075)%Z by lia.
  rewrite bpow_plus. simpl. lra.
Qed.

Lemma eta_u3 : eta <= u * (u * u) / 1000000.
Proof.
  rewrite u_val. unfold eta. apply Rle_trans with (bpow radix2 (-180)).
  - apply bpow_le. lia.
  - simpl. lra.
Qed.

(** ηX ≤ η + ηX², and ηX² is below u³X² by far. *)
Lemma absorb : forall X, 0 <= X -> eta * X <= eta + eta * (X * X).
Proof. intros X HX. pose proof eta_pos. assert (X <= 1 + X * X) by nra. nra. Qed.

Lemma absorb2 : forall Y, 0 <= Y -> eta * Y <= u * (u * u) / 1000000 * Y.
Proof. intros Y HY. apply Rmult_le_compat_r; [exact HY | apply eta_u3]. Qed.

(** ** The C++ routine, operation by operation. *)

Record BoundarySigns := {
  bf_value : R;             (* q4 = a₃.hi ⊕ s *)
  bf_w : R;                 (* W *)
  bf_eq : R;                (* E_q = (κ_q ⊗ W) ⊕ μ_q *)
  bf_slope : R;             (* (d₀ ⊗ H₀ ⊕ d₁ ⊗ H₁) ⊕ d₂ ⊗ H₂ *)
  bf_slope_magnitude : R }. (* Σ |d_i| ⊗ ((|H_i| ⊕ T_i) ⊕ 2^-1000), from 0 *)

Definition boundary (o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y : R) : BoundarySigns :=
  let m := two_sum x y in
  let A0 := axis o0 c0 d0 (fst m) (snd m) in
  let A1 := axis o1 c1 d1 (fst m) (snd m) in
  let A2 := axis o2 c2 d2 (fst m) (snd m) in
  let H0 := axis_h A0 in let H1 := axis_h A1 in let H2 := axis_h A2 in
  let L0 := axis_l A0 in let L1 := axis_l A1 in let L2 := axis_l A2 in
  let T0 := axis_t A0 in let T1 := axis_t A1 in let T2 := axis_t A2 in
  let two_r := RN (r + r) in
  let s0 := two_prod H0 H0 in let s1 := two_prod H1 H1 in let s2 := two_prod H2 H2 in
  let rr := two_prod two_r two_r in
  let a1 := two_sum (fst s0) (fst s1) in
  let a2 := two_sum (fst a1) (fst s2) in
  let a3 := two_sum (fst a2) (- fst rr) in
  let k0 := RN (L0 * RN (RN (H0 + H0) + L0)) in
  let k1 := RN (L1 * RN (RN (H1 + H1) + L1)) in
  let k2 := RN (L2 * RN (RN (H2 + H2) + L2)) in
  let small := RN (RN (RN (RN (snd s0 + snd s1) + RN (snd s2 - snd rr)) + RN (RN (snd a1 + snd a2) + snd a3))
                   + RN (RN (k0 + k1) + k2)) in
  let value := RN (fst a3 + small) in
  let w0 := RN (RN (RN (fst s0 + fst s1) + fst s2) + fst rr) in
  let w1 := RN (w0 + RN (T0 * RN (Rabs H0 + RN (sphere_boundary_tail * T0)))) in
  let w2 := RN (w1 + RN (T1 * RN (Rabs H1 + RN (sphere_boundary_tail * T1)))) in
  let w3 := RN (w2 + RN (T2 * RN (Rabs H2 + RN (sphere_boundary_tail * T2)))) in
  let slope := RN (RN (RN (d0 * H0) + RN (d1 * H1)) + RN (d2 * H2)) in
  let e_q := RN (RN (sphere_boundary_q_relative * w3) + sphere_boundary_q_absolute) in
  let sm0 := RN (0 + RN (Rabs d0 * RN (RN (Rabs H0 + T0) + sphere_boundary_slope_floor))) in
  let sm1 := RN (sm0 + RN (Rabs d1 * RN (RN (Rabs H1 + T1) + sphere_boundary_slope_floor))) in
  let sm2 := RN (sm1 + RN (Rabs d2 * RN (RN (Rabs H2 + T2) + sphere_boundary_slope_floor))) in
  {| bf_value := value; bf_w := w3; bf_eq := e_q; bf_slope := slope; bf_slope_magnitude := sm2 |}.

(** The sign of q: uncertain unless W and the value are at most the largest double (in the model, where
    nothing overflows, these checks only make the answer uncertain more often). *)
Definition boundary_q_sign (b : BoundarySigns) : sign :=
  if andb (Rle_bool (bf_w b) largest_finite) (Rle_bool (Rabs (bf_value b)) largest_finite) then
    if Rlt_bool (bf_eq b) (bf_value b) then Positive
    else if Rlt_bool (bf_value b) (- bf_eq b) then Negative else Uncertain
  else Uncertain.

(** The sign of the slope, read only when q's is positive. *)
Definition boundary_slope_sign (b : BoundarySigns) : sign :=
  match boundary_q_sign b with
  | Positive =>
      if Rle_bool (bf_slope_magnitude b) largest_finite then
        let e_s := RN (RN (sphere_boundary_slope_relative * bf_slope_magnitude b) + sphere_boundary_slope_absolute) in
        if Rlt_bool e_s (bf_slope b) then Positive
        else if Rlt_bool (bf_slope b) (- e_s) then Negative else Uncertain
      else Uncertain
  | _ => Uncertain
  end.

(** The exact 4q(m) = Σ_i (2(o_i − c_i) + (x + y)·d_i)² − (2r)². *)
Definition exact_q4 (o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y : R) : R :=
  (2 * (o0 - c0) + (x + y) * d0) * (2 * (o0 - c0) + (x + y) * d0) +
  (2 * (o1 - c1) + (x + y) * d1) * (2 * (o1 - c1) + (x + y) * d1) +
  (2 * (o2 - c2) + (x + y) * d2) * (2 * (o2 - c2) + (x + y) * d2) - (2 * r) * (2 * r).

(** The exact 2(A·m + B) = Σ_i d_i·(2(o_i − c_i) + (x + y)·d_i). *)
Definition exact_slope2 (o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y : R) : R :=
  d0 * (2 * (o0 - c0) + (x + y) * d0) + d1 * (2 * (o1 - c1) + (x + y) * d1) +
  d2 * (2 * (o2 - c2) + (x + y) * d2).

Ltac plow := apply RN_plus_lower; [first [assumption | apply binary64_RN] | first [assumption | apply binary64_RN] | lra].

(** One term of W: T ⊗ (|H| ⊕ τ ⊗ T) ≥ (1 − u)²·T|H| + (1 − u)³·τT² − ηT − η. *)
Lemma w_term : forall H T, binary64 H -> binary64 T -> 0 <= T ->
  let p := RN (T * RN (Rabs H + RN (sphere_boundary_tail * T))) in
  0 <= p /\ binary64 p /\
  (1 - u) * (1 - u) * (T * Rabs H) + (1 - u) * (1 - u) * (1 - u) * sphere_boundary_tail * (T * T)
    - eta * T - eta <= p.
Proof.
  intros H T BH BT PT p.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv. pose proof tail_val as Tv.
  assert (Pt : 0 <= sphere_boundary_tail) by (rewrite Tv; lra).
  set (gt := RN (sphere_boundary_tail * T)) in *.
  assert (Lgt : sphere_boundary_tail * T * (1 - u) - eta <= gt) by (apply RN_lower; nra).
  assert (Pgt : 0 <= gt) by (apply RN_nonneg; nra).
  pose proof (Rabs_pos H) as PH.
  set (bb := RN (Rabs H + gt)) in *.
  assert (Lbb : (Rabs H + gt) * (1 - u) <= bb)
    by (apply RN_plus_lower; [apply binary64_abs; exact BH | apply binary64_RN | lra]).
  assert (Pbb : 0 <= bb) by (apply RN_nonneg; lra).
  assert (Lp : T * bb * (1 - u) - eta <= p) by (apply RN_lower; nra).
  assert (Pp : 0 <= p) by (apply RN_nonneg; nra).
  assert (Tb : T * ((Rabs H + gt) * (1 - u)) <= T * bb) by (apply Rmult_le_compat_l; lra).
  assert (Tg : T * (sphere_boundary_tail * T * (1 - u) - eta) <= T * gt) by (apply Rmult_le_compat_l; lra).
  assert (PTH : 0 <= T * Rabs H) by nra. assert (PTe : 0 <= T * eta) by nra.
  split; [exact Pp | split; [apply binary64_RN |]].
  rewrite Tv, Uv in *. lra.
Qed.

Lemma absorb_sq : forall H, eta * Rabs H <= eta + eta * (H * H).
Proof.
  intros H. pose proof (absorb (Rabs H) (Rabs_pos H)) as A.
  rewrite <- Rabs_mult, (Rabs_nonneg_eq (H * H)) in A by nra. exact A.
Qed.

(** |4q(m) − (a₃.hi + s)| ≤ E_q: the value is RN of a real within E_q of 4q(m). *)
Theorem sphere_boundary_q_encloses : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 d0 -> binary64 d1 -> binary64 d2 ->
  binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r -> binary64 x -> binary64 y ->
  let b := boundary o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y in
  exists z, bf_value b = RN z /\ binary64 (bf_eq b) /\
    Rabs (exact_q4 o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y - z) <= bf_eq b.
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y Bo0 Bo1 Bo2 Bd0 Bd1 Bd2 Bc0 Bc1 Bc2 Br Bx By b.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv. destruct eta_small as [Es Es2].
  unfold b, boundary, exact_q4. cbv zeta. cbn [bf_value bf_eq].
  eexists. split; [reflexivity | split; [apply binary64_RN |]].
  set (M1 := fst (two_sum x y)). set (M2 := snd (two_sum x y)).
  assert (EM : x + y = M1 + M2) by (unfold M1, M2; rewrite two_sum_exact; auto).
  destruct (two_sum_lo_bound x y Bx By) as [_ LM]. fold M1 M2 in LM.
  assert (BM1 : binary64 M1) by apply binary64_two_sum_hi.
  assert (BM2 : binary64 M2) by apply binary64_two_sum_lo.
  rewrite EM.
  pose proof (axis_bounds o0 c0 d0 M1 M2 Bo0 Bc0 Bd0 BM1 BM2 LM) as X0. cbv zeta in X0.
  pose proof (axis_bounds o1 c1 d1 M1 M2 Bo1 Bc1 Bd1 BM1 BM2 LM) as X1. cbv zeta in X1.
  pose proof (axis_bounds o2 c2 d2 M1 M2 Bo2 Bc2 Bd2 BM1 BM2 LM) as X2. cbv zeta in X2.
  set (H0 := axis_h (axis o0 c0 d0 M1 M2)) in *. set (L0 := axis_l (axis o0 c0 d0 M1 M2)) in *.
  set (T0 := axis_t (axis o0 c0 d0 M1 M2)) in *.
  set (H1 := axis_h (axis o1 c1 d1 M1 M2)) in *. set (L1 := axis_l (axis o1 c1 d1 M1 M2)) in *.
  set (T1 := axis_t (axis o1 c1 d1 M1 M2)) in *.
  set (H2 := axis_h (axis o2 c2 d2 M1 M2)) in *. set (L2 := axis_l (axis o2 c2 d2 M1 M2)) in *.
  set (T2 := axis_t (axis o2 c2 d2 M1 M2)) in *.
  destruct X0 as [BH0 [BL0 [PT0 [AH0 [AL0 AD0]]]]].
  destruct X1 as [BH1 [BL1 [PT1 [AH1 [AL1 AD1]]]]].
  destruct X2 as [BH2 [BL2 [PT2 [AH2 [AL2 AD2]]]]].
  set (G0 := 2 * (o0 - c0) + (M1 + M2) * d0) in *.
  set (G1 := 2 * (o1 - c1) + (M1 + M2) * d1) in *.
  set (G2 := 2 * (o2 - c2) + (M1 + M2) * d2) in *.
  pose proof (square_part G0 H0 L0 T0 BH0 BL0 PT0 AH0 AL0 AD0) as Q0. cbv zeta in Q0.
  pose proof (square_part G1 H1 L1 T1 BH1 BL1 PT1 AH1 AL1 AD1) as Q1. cbv zeta in Q1.
  pose proof (square_part G2 H2 L2 T2 BH2 BL2 PT2 AH2 AL2 AD2) as Q2. cbv zeta in Q2.
  set (k0 := RN (L0 * RN (RN (H0 + H0) + L0))) in *.
  set (k1 := RN (L1 * RN (RN (H1 + H1) + L1))) in *.
  set (k2 := RN (L2 * RN (RN (H2 + H2) + L2))) in *.
  destruct Q0 as [Sq0 K0]. destruct Q1 as [Sq1 K1]. destruct Q2 as [Sq2 K2].
  rewrite (RN_double r Br).
  replace (2 * r * (2 * r)) with ((r + r) * (r + r)) by ring.
  assert (Brr : binary64 (r + r)) by (rewrite <- (RN_double r Br); apply binary64_RN).
  unfold two_prod, fma. cbn [fst snd].
  pose proof (square_facts H0 BH0) as F0. pose proof (square_facts H1 BH1) as F1.
  pose proof (square_facts H2 BH2) as F2. pose proof (square_facts (r + r) Brr) as FR.
  cbv zeta in F0, F1, F2, FR.
  set (S0 := RN (H0 * H0)) in *. set (S1 := RN (H1 * H1)) in *. set (S2 := RN (H2 * H2)) in *.
  set (R := RN ((r + r) * (r + r))) in *.
  set (g0 := RN (H0 * H0 + - S0)) in *. set (g1 := RN (H1 * H1 + - S1)) in *.
  set (g2 := RN (H2 * H2 + - S2)) in *. set (rho := RN ((r + r) * (r + r) + - R)) in *.
  destruct F0 as [BS0 [Bg0 [PS0 [ES0 [Ag0 HS0]]]]].
  destruct F1 as [BS1 [Bg1 [PS1 [ES1 [Ag1 HS1]]]]].
  destruct F2 as [BS2 [Bg2 [PS2 [ES2 [Ag2 HS2]]]]].
  destruct FR as [BR [Brho [PR [ER [Arho HR]]]]].
  (* the heads' TwoSums *)
  set (a1h := fst (two_sum S0 S1)). set (a1l := snd (two_sum S0 S1)).
  assert (Ea1 : a1h + a1l = S0 + S1) by (apply two_sum_exact; assumption).
  destruct (two_sum_lo_bound S0 S1 BS0 BS1) as [_ La1]. fold a1h a1l in La1.
  assert (Ba1h : binary64 a1h) by apply binary64_two_sum_hi.
  assert (Ba1l : binary64 a1l) by apply binary64_two_sum_lo.
  assert (Pa1 : 0 <= a1h) by (apply RN_nonneg; lra).
  assert (Ua1 := RN_sum_iv S0 S1 (S0 + S1) BS0 BS1 ltac:(rabs)). change (RN (S0 + S1)) with a1h in Ua1.
  set (a2h := fst (two_sum a1h S2)). set (a2l := snd (two_sum a1h S2)).
  assert (Ea2 : a2h + a2l = a1h + S2) by (apply two_sum_exact; assumption).
  destruct (two_sum_lo_bound a1h S2 Ba1h BS2) as [_ La2]. fold a2h a2l in La2.
  assert (Ba2h : binary64 a2h) by apply binary64_two_sum_hi.
  assert (Ba2l : binary64 a2l) by apply binary64_two_sum_lo.
  assert (Pa2 : 0 <= a2h) by (apply RN_nonneg; lra).
  assert (Ua2 := RN_sum_iv a1h S2 (a1h + S2) Ba1h BS2 ltac:(rabs)). change (RN (a1h + S2)) with a2h in Ua2.
  set (a3h := fst (two_sum a2h (- R))). set (a3l := snd (two_sum a2h (- R))).
  assert (BmR : binary64 (- R)) by (apply binary64_opp; exact BR).
  assert (Ea3 : a3h + a3l = a2h + - R) by (apply two_sum_exact; assumption).
  destruct (two_sum_lo_bound a2h (- R) Ba2h BmR) as [_ La3]. fold a3h a3l in La3.
  assert (Ba3h : binary64 a3h) by apply binary64_two_sum_hi.
  assert (Ba3l : binary64 a3l) by apply binary64_two_sum_lo.
  assert (Ua3 := RN_sum_iv a2h (- R) (a2h + R) Ba2h BmR ltac:(rabs)). change (RN (a2h + - R)) with a3h in Ua3.
  absb a3h.
  assert (Ma3 : Rabs a3h <= (1 + u) * (a2h + R)) by (rewrite Uv in *; rabs).
  (* the sum of the small terms *)
  assert (Bk0 : binary64 k0) by apply binary64_RN. assert (Bk1 : binary64 k1) by apply binary64_RN.
  assert (Bk2 : binary64 k2) by apply binary64_RN.
  assert (Mrho : Rabs (- rho) <= 2 * u * R + 3 * eta) by (rewrite Rabs_Ropp; exact Arho).
  assert (Brho' : binary64 (- rho)) by (apply binary64_opp; exact Brho).
  assert (Ma1 : Rabs a1l <= u * ((1 + u) * (S0 + S1))).
  { eapply Rle_trans; [exact La1|]. rewrite (Rabs_nonneg_eq a1h Pa1). apply Rmult_le_compat_l; lra. }
  assert (Ma2 : Rabs a2l <= u * ((1 + u) * (a1h + S2))).
  { eapply Rle_trans; [exact La2|]. rewrite (Rabs_nonneg_eq a2h Pa2). apply Rmult_le_compat_l; lra. }
  assert (Ma3l : Rabs a3l <= u * ((1 + u) * (a2h + R))).
  { eapply Rle_trans; [exact La3|]. apply Rmult_le_compat_l; lra. }
  change (RN (g2 - rho)) with (RN (g2 + - rho)).
  destruct (leaf _ _ Ag0) as [Z0 N0]. destruct (leaf _ _ Ag1) as [Z1 N1].
  destruct (leaf _ _ Ag2) as [Z2 N2]. destruct (leaf _ _ Mrho) as [Z3 N3].
  destruct (leaf _ _ Ma1) as [Z4 N4]. destruct (leaf _ _ Ma2) as [Z5 N5]. destruct (leaf _ _ Ma3l) as [Z6 N6].
  destruct (leaf _ _ K0) as [Z7 N7]. destruct (leaf _ _ K1) as [Z8 N8]. destruct (leaf _ _ K2) as [Z9 N9].
  destruct (sum_step _ _ _ _ _ _ _ _ Bg0 Bg1 Z0 Z1 N0 N1) as [E10 N10].
  destruct (sum_step _ _ _ _ _ _ _ _ Bg2 Brho' Z2 Z3 N2 N3) as [E11 N11].
  destruct (sum_step _ _ _ _ _ _ _ _ (binary64_RN _) (binary64_RN _) E10 E11 N10 N11) as [E12 N12].
  destruct (sum_step _ _ _ _ _ _ _ _ Ba1l Ba2l Z4 Z5 N4 N5) as [E13 N13].
  destruct (sum_step _ _ _ _ _ _ _ _ (binary64_RN _) Ba3l E13 Z6 N13 N6) as [E14 N14].
  destruct (sum_step _ _ _ _ _ _ _ _ (binary64_RN _) (binary64_RN _) E12 E14 N12 N14) as [E15 N15].
  destruct (sum_step _ _ _ _ _ _ _ _ Bk0 Bk1 Z7 Z8 N7 N8) as [E16 N16].
  destruct (sum_step _ _ _ _ _ _ _ _ (binary64_RN _) Bk2 E16 Z9 N16 N9) as [E17 N17].
  destruct (sum_step _ _ _ _ _ _ _ _ (binary64_RN _) (binary64_RN _) E15 E17 N15 N17) as [E18 _].
  set (small := RN (RN (RN (RN (g0 + g1) + RN (g2 + - rho)) + RN (RN (a1l + a2l) + a3l)) + RN (RN (k0 + k1) + k2))) in *.
  clear E10 E11 E12 E13 E14 E15 E16 E17 N10 N11 N12 N13 N14 N15 N16 N17 Z0 Z1 Z2 Z3 Z4 Z5 Z6 Z7 Z8 Z9.
  (* the lower bound of E_q *)
  assert (BT0 : binary64 T0) by (unfold T0, axis; cbn [axis_t]; apply binary64_RN).
  assert (BT1 : binary64 T1) by (unfold T1, axis; cbn [axis_t]; apply binary64_RN).
  assert (BT2 : binary64 T2) by (unfold T2, axis; cbn [axis_t]; apply binary64_RN).
  pose proof (w_term H0 T0 BH0 BT0 PT0) as W0. pose proof (w_term H1 T1 BH1 BT1 PT1) as W1.
  pose proof (w_term H2 T2 BH2 BT2 PT2) as W2. cbv zeta in W0, W1, W2.
  set (p0 := RN (T0 * RN (Rabs H0 + RN (sphere_boundary_tail * T0)))) in *.
  set (p1 := RN (T1 * RN (Rabs H1 + RN (sphere_boundary_tail * T1)))) in *.
  set (p2 := RN (T2 * RN (Rabs H2 + RN (sphere_boundary_tail * T2)))) in *.
  destruct W0 as [Pp0 [Bp0 Lp0]]. destruct W1 as [Pp1 [Bp1 Lp1]]. destruct W2 as [Pp2 [Bp2 Lp2]].
  assert (Lwa : (S0 + S1) * (1 - u) <= RN (S0 + S1)) by plow.
  set (wa := RN (S0 + S1)) in *. assert (Pwa : 0 <= wa) by (apply RN_nonneg; lra).
  assert (Lwb : (wa + S2) * (1 - u) <= RN (wa + S2)) by plow.
  set (wb := RN (wa + S2)) in *. assert (Pwb : 0 <= wb) by (apply RN_nonneg; lra).
  assert (Lw0 : (wb + R) * (1 - u) <= RN (wb + R)) by plow.
  set (w0 := RN (wb + R)) in *. assert (Pw0 : 0 <= w0) by (apply RN_nonneg; lra).
  assert (Lw1 : (w0 + p0) * (1 - u) <= RN (w0 + p0)) by plow.
  set (w1 := RN (w0 + p0)) in *. assert (Pw1 : 0 <= w1) by (apply RN_nonneg; lra).
  assert (Lw2 : (w1 + p1) * (1 - u) <= RN (w1 + p1)) by plow.
  set (w2 := RN (w1 + p1)) in *. assert (Pw2 : 0 <= w2) by (apply RN_nonneg; lra).
  assert (Lw3 : (w2 + p2) * (1 - u) <= RN (w2 + p2)) by plow.
  set (w3 := RN (w2 + p2)) in *. assert (Pw3 : 0 <= w3) by (apply RN_nonneg; lra).
  pose proof q_relative_val as Kv. pose proof q_absolute_eta as Mv. pose proof tail_val as Tv.
  assert (Lek : sphere_boundary_q_relative * w3 * (1 - u) - eta <= RN (sphere_boundary_q_relative * w3))
    by (apply RN_lower; rewrite Kv; lra).
  assert (Pek : 0 <= RN (sphere_boundary_q_relative * w3)) by (apply RN_nonneg; rewrite Kv; lra).
  set (ek := RN (sphere_boundary_q_relative * w3)) in *.
  assert (Bmu : binary64 sphere_boundary_q_absolute) by (apply binary64_bpow; lia).
  assert (Leq : (ek + sphere_boundary_q_absolute) * (1 - u) <= RN (ek + sphere_boundary_q_absolute))
    by (apply RN_plus_lower; [apply binary64_RN | exact Bmu | rewrite Mv; lra]).
  set (eq := RN (ek + sphere_boundary_q_absolute)) in *.
  (* the η terms *)
  pose proof (absorb_sq H0) as Y0. pose proof (absorb_sq H1) as Y1. pose proof (absorb_sq H2) as Y2.
  assert (Z0 : eta * (H0 * H0) <= eta * ((1 + u) * S0 + eta)) by (apply Rmult_le_compat_l; lra).
  assert (Z1 : eta * (H1 * H1) <= eta * ((1 + u) * S1 + eta)) by (apply Rmult_le_compat_l; lra).
  assert (Z2 : eta * (H2 * H2) <= eta * ((1 + u) * S2 + eta)) by (apply Rmult_le_compat_l; lra).
  pose proof (absorb2 S0 PS0) as V0. pose proof (absorb2 S1 PS1) as V1. pose proof (absorb2 S2 PS2) as V2.
  pose proof (absorb T0 PT0) as U0. pose proof (absorb T1 PT1) as U1. pose proof (absorb T2 PT2) as U2.
  assert (PTT0 : 0 <= T0 * T0) by (apply Rmult_le_pos; assumption). assert (PTT1 : 0 <= T1 * T1) by (apply Rmult_le_pos; assumption). assert (PTT2 : 0 <= T2 * T2) by (apply Rmult_le_pos; assumption).
  pose proof (absorb2 _ PTT0) as R0. pose proof (absorb2 _ PTT1) as R1. pose proof (absorb2 _ PTT2) as R2.
  assert (PTH0 : 0 <= T0 * Rabs H0) by (apply Rmult_le_pos; [assumption | apply Rabs_pos]).
  assert (PTH1 : 0 <= T1 * Rabs H1) by (apply Rmult_le_pos; [assumption | apply Rabs_pos]).
  assert (PTH2 : 0 <= T2 * Rabs H2) by (apply Rmult_le_pos; [assumption | apply Rabs_pos]).
  assert (PeH0 : 0 <= eta * Rabs H0) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (PeH1 : 0 <= eta * Rabs H1) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (PeH2 : 0 <= eta * Rabs H2) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (PeT0 : 0 <= eta * T0) by (apply Rmult_le_pos; lra). assert (PeT1 : 0 <= eta * T1) by (apply Rmult_le_pos; lra). assert (PeT2 : 0 <= eta * T2) by (apply Rmult_le_pos; lra).
  (* the error, in the atoms S_i, R, T_i|H_i|, T_i², η|H_i|, ηT_i *)
  assert (E18' : Rabs (small - (g0 + g1 + (g2 + - rho) + (a1l + a2l + a3l) + (k0 + k1 + k2))) <=
     20 * (u * u) * (S0 + S1 + S2 + R) + 64 * (u * u) * (T0 * Rabs H0 + T1 * Rabs H1 + T2 * Rabs H2)
     + 304 * (u * (u * u)) * (T0 * T0 + T1 * T1 + T2 * T2)
     + (eta * Rabs H0 + eta * Rabs H1 + eta * Rabs H2) / 10 + (eta * T0 + eta * T1 + eta * T2) / 10 + eta / 10).
  { eapply Rle_trans; [exact E18|].
    clear - Ua1 Ua2 Pa1 Pa2 PS0 PS1 PS2 PR PTT0 PTT1 PTT2 PTH0 PTH1 PTH2 PeH0 PeH1 PeH2 PeT0 PeT1 PeT2 Hu He Uv.
    rewrite Uv in *. lra. }
  clear E18.
  assert (Err : Rabs (G0 * G0 + G1 * G1 + G2 * G2 - (r + r) * (r + r) - (a3h + small)) <=
     40 * (u * u) * (S0 + S1 + S2 + R) + 150 * (u * u) * (T0 * Rabs H0 + T1 * Rabs H1 + T2 * Rabs H2)
     + 1000 * (u * (u * u)) * (T0 * T0 + T1 * T1 + T2 * T2)
     + 15 * (eta * Rabs H0 + eta * Rabs H1 + eta * Rabs H2) + 2 * (eta * T0 + eta * T1 + eta * T2) + 20 * eta).
  { apply Rabs_bounds in Sq0. apply Rabs_bounds in Sq1. apply Rabs_bounds in Sq2.
    apply Rabs_bounds in ES0. apply Rabs_bounds in ES1. apply Rabs_bounds in ES2. apply Rabs_bounds in ER.
    apply Rabs_bounds in E18'.
    clear - Sq0 Sq1 Sq2 ES0 ES1 ES2 ER E18' Ea1 Ea2 Ea3 PTT0 PTT1 PTT2 PTH0 PTH1 PTH2 PeH0 PeH1 PeH2
      PeT0 PeT1 PeT2 Hu He Uv PS0 PS1 PS2 PR.
    rewrite Uv in *. apply Rabs_le. split; lra. }
  (* the lower bound of E_q *)
  assert (LB : 1000 * (u * u) * (S0 + S1 + S2 + R) + 1000 * (u * u) * (T0 * Rabs H0 + T1 * Rabs H1 + T2 * Rabs H2)
     + / 5575186299632655785383929568162090376495104 * (T0 * T0 + T1 * T1 + T2 * T2)
     - (eta * T0 + eta * T1 + eta * T2) / 1000 + 30000 * eta <= eq).
  { clear - Lp0 Lp1 Lp2 Pp0 Pp1 Pp2 Lwa Lwb Lw0 Lw1 Lw2 Lw3 Pwa Pwb Pw0 Pw1 Pw2 Pw3 Lek Pek Leq Kv Mv Tv
      PS0 PS1 PS2 PR PTT0 PTT1 PTT2 PTH0 PTH1 PTH2 PeT0 PeT1 PeT2 Hu He Uv.
    rewrite Kv, Mv, Tv, Uv in *. lra. }
  eapply Rle_trans; [exact Err|]. eapply Rle_trans; [|exact LB].
  clear - Y0 Y1 Y2 Z0 Z1 Z2 V0 V1 V2 U0 U1 U2 R0 R1 R2 PTT0 PTT1 PTT2 PTH0 PTH1 PTH2 PeH0 PeH1 PeH2
    PeT0 PeT1 PeT2 PS0 PS1 PS2 PR Hu He Uv Es Es2.
  rewrite Uv in *. lra.
Qed.

(** The certified sign of q is the sign of the exact 4q(m) = Σ_i (2(o_i − c_i) + (x + y)·d_i)² − (2r)². *)
Theorem sphere_boundary_q_sound : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 d0 -> binary64 d1 -> binary64 d2 ->
  binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r -> binary64 x -> binary64 y ->
  certifies (boundary_q_sign (boundary o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y))
    (exact_q4 o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y).
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y Bo0 Bo1 Bo2 Bd0 Bd1 Bd2 Bc0 Bc1 Bc2 Br Bx By.
  destruct (sphere_boundary_q_encloses o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y Bo0 Bo1 Bo2 Bd0 Bd1 Bd2 Bc0 Bc1 Bc2
              Br Bx By) as [z [Ez [Beq Hz]]].
  set (b := boundary o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y) in *.
  set (Q := exact_q4 o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y) in *.
  apply Rabs_bounds in Hz.
  unfold boundary_q_sign.
  destruct (andb _ _); [| exact I].
  destruct (Rlt_bool_spec (bf_eq b) (bf_value b)) as [P|P]; cbv iota beta; unfold certifies.
  - (* value > E_q: z > E_q, since z ≤ E_q would give RN(z) ≤ RN(E_q) = E_q *)
    destruct (Rle_or_lt z (bf_eq b)) as [Z|Z]; [| lra].
    exfalso. pose proof (RN_le _ _ Z) as M. rewrite (RN_binary64 _ Beq), <- Ez in M. lra.
  - destruct (Rlt_bool_spec (bf_value b) (- bf_eq b)) as [N|N]; cbv iota beta; unfold certifies; [| exact I].
    destruct (Rle_or_lt (- bf_eq b) z) as [Z|Z]; [| lra].
    exfalso. pose proof (RN_le _ _ Z) as M.
    rewrite (RN_binary64 _ (binary64_opp _ Beq)), <- Ez in M. lra.
Qed.

(** ** The slope, for every binary64 input. *)

Lemma floor_val : sphere_boundary_slope_floor = bpow radix2 (-1000).
Proof. reflexivity. Qed.

(** η·|d| is far below u·|d|·2^-1000: the floor covers the errors proportional to |d|, whatever d. *)
Lemma eta_floor : eta <= u * sphere_boundary_slope_floor / 1000000.
Proof.
  unfold eta, sphere_boundary_slope_floor, unit_roundoff. rewrite <- bpow_plus.
  apply Rle_trans with (bpow radix2 (-1053 - 20)).
  - apply bpow_le. lia.
  - replace (-1053 - 20)%Z with (-20 + -1053)%Z by lia. rewrite bpow_plus. simpl. lra.
Qed.

Lemma slope_axis : forall d H T G, binary64 d -> binary64 H -> binary64 T -> 0 <= T ->
  Rabs (G - H) <= 11 * u * T + 13 * eta ->
  let q := RN (d * H) in
  let m := RN (Rabs d * RN (RN (Rabs H + T) + sphere_boundary_slope_floor)) in
  binary64 q /\ binary64 m /\ 0 <= m /\
  Rabs (q - d * G) <= u * (Rabs d * Rabs H) + 11 * u * (Rabs d * T)
                      + u * (Rabs d * sphere_boundary_slope_floor) / 10000 + eta /\
  Rabs q <= (1 + u) * (Rabs d * Rabs H) + eta /\
  (1 - u) * (1 - u) * (1 - u) * (Rabs d * Rabs H + Rabs d * T + Rabs d * sphere_boundary_slope_floor) - eta <= m.
Proof.
  intros d H T G Bd BH BT PT EG q m.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv.
  pose proof eta_floor as EF.
  subst q m. set (F := sphere_boundary_slope_floor) in *.
  set (q := RN (d * H)). set (m := RN (Rabs d * RN (RN (Rabs H + T) + F))).
  assert (PF : 0 < F) by apply bpow_gt_0.
  assert (BF : binary64 F) by (apply binary64_bpow; lia).
  pose proof (Rabs_pos H) as PH. pose proof (Rabs_pos d) as Pd.
  assert (Pb1 : 0 <= RN (Rabs H + T)) by (apply RN_nonneg; lra).
  assert (Pb2 : 0 <= RN (RN (Rabs H + T) + F)) by (apply RN_nonneg; lra).
  assert (Pm : 0 <= m) by (apply RN_nonneg; apply Rmult_le_pos; lra).
  assert (W4 : eta * Rabs d <= u * (Rabs d * F) / 1000000).
  { replace (u * (Rabs d * F) / 1000000) with (Rabs d * (u * F / 1000000)) by field.
    rewrite Rmult_comm. apply Rmult_le_compat_l; lra. }
  pose proof (RN_err (d * H)) as Eq. fold q in Eq. rewrite Rabs_mult in Eq.
  assert (EdG : Rabs (d * H - d * G) <= Rabs d * (11 * u * T + 13 * eta)).
  { replace (d * H - d * G) with (d * (H - G)) by ring. rewrite Rabs_mult.
    apply Rmult_le_compat_l; [lra|]. rewrite Rabs_minus_sym. exact EG. }
  assert (Lb1 : (Rabs H + T) * (1 - u) <= RN (Rabs H + T))
    by (apply RN_plus_lower; [apply binary64_abs; exact BH | exact BT | lra]).
  assert (Lb2 : (RN (Rabs H + T) + F) * (1 - u) <= RN (RN (Rabs H + T) + F))
    by (apply RN_plus_lower; [apply binary64_RN | exact BF | lra]).
  set (b1 := RN (Rabs H + T)) in *. set (b2 := RN (b1 + F)) in *.
  assert (Lm : Rabs d * b2 * (1 - u) - eta <= m) by (apply RN_lower; apply Rmult_le_pos; lra).
  assert (P2 : Rabs d * ((b1 + F) * (1 - u)) <= Rabs d * b2) by (apply Rmult_le_compat_l; lra).
  assert (P1 : Rabs d * ((Rabs H + T) * (1 - u)) <= Rabs d * b1) by (apply Rmult_le_compat_l; lra).
  assert (PdH : 0 <= Rabs d * Rabs H) by (apply Rmult_le_pos; lra).
  assert (PdT : 0 <= Rabs d * T) by (apply Rmult_le_pos; lra).
  assert (PdF : 0 <= Rabs d * F) by (apply Rmult_le_pos; lra).
  assert (Pdb1 : 0 <= Rabs d * b1) by (apply Rmult_le_pos; lra).
  apply Rabs_bounds in Eq. apply Rabs_bounds in EdG.
  repeat split; try apply binary64_RN; try lra.
  + rewrite Uv in *. rabs.
  + pose proof (abs_iv (d * H)) as AdH. rewrite Rabs_mult in AdH. rewrite Uv in *. rabs.
  + rewrite Uv in *. lra.
Qed.

(** The slope's enclosure: |2(A·m + B) − slope| ≤ E_s, for every binary64 input. *)
Theorem sphere_boundary_slope_encloses : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 d0 -> binary64 d1 -> binary64 d2 ->
  binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r -> binary64 x -> binary64 y ->
  let b := boundary o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y in
  Rabs (bf_slope b - exact_slope2 o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y) <=
    RN (RN (sphere_boundary_slope_relative * bf_slope_magnitude b) + sphere_boundary_slope_absolute).
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y Bo0 Bo1 Bo2 Bd0 Bd1 Bd2 Bc0 Bc1 Bc2 Br Bx By b.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv.
  unfold b, boundary, exact_slope2. cbv zeta. cbn [bf_slope bf_slope_magnitude].
  set (M1 := fst (two_sum x y)). set (M2 := snd (two_sum x y)).
  assert (EM : x + y = M1 + M2) by (unfold M1, M2; rewrite two_sum_exact; auto).
  destruct (two_sum_lo_bound x y Bx By) as [_ LM]. fold M1 M2 in LM.
  assert (BM1 : binary64 M1) by apply binary64_two_sum_hi.
  assert (BM2 : binary64 M2) by apply binary64_two_sum_lo.
  rewrite EM.
  pose proof (axis_bounds o0 c0 d0 M1 M2 Bo0 Bc0 Bd0 BM1 BM2 LM) as X0. cbv zeta in X0.
  pose proof (axis_bounds o1 c1 d1 M1 M2 Bo1 Bc1 Bd1 BM1 BM2 LM) as X1. cbv zeta in X1.
  pose proof (axis_bounds o2 c2 d2 M1 M2 Bo2 Bc2 Bd2 BM1 BM2 LM) as X2. cbv zeta in X2.
  assert (BT0 : binary64 (axis_t (axis o0 c0 d0 M1 M2))) by (unfold axis; cbn [axis_t]; apply binary64_RN).
  assert (BT1 : binary64 (axis_t (axis o1 c1 d1 M1 M2))) by (unfold axis; cbn [axis_t]; apply binary64_RN).
  assert (BT2 : binary64 (axis_t (axis o2 c2 d2 M1 M2))) by (unfold axis; cbn [axis_t]; apply binary64_RN).
  set (H0 := axis_h (axis o0 c0 d0 M1 M2)) in *. set (L0 := axis_l (axis o0 c0 d0 M1 M2)) in *.
  set (T0 := axis_t (axis o0 c0 d0 M1 M2)) in *.
  set (H1 := axis_h (axis o1 c1 d1 M1 M2)) in *. set (L1 := axis_l (axis o1 c1 d1 M1 M2)) in *.
  set (T1 := axis_t (axis o1 c1 d1 M1 M2)) in *.
  set (H2 := axis_h (axis o2 c2 d2 M1 M2)) in *. set (L2 := axis_l (axis o2 c2 d2 M1 M2)) in *.
  set (T2 := axis_t (axis o2 c2 d2 M1 M2)) in *.
  destruct X0 as [BH0 [BL0 [PT0 [AH0 [AL0 AD0]]]]].
  destruct X1 as [BH1 [BL1 [PT1 [AH1 [AL1 AD1]]]]].
  destruct X2 as [BH2 [BL2 [PT2 [AH2 [AL2 AD2]]]]].
  assert (G0 : Rabs (2 * (o0 - c0) + (M1 + M2) * d0 - H0) <= 11 * u * T0 + 13 * eta).
  { apply Rabs_bounds in AL0. apply Rabs_bounds in AD0. rewrite Uv in *. rabs. }
  assert (G1 : Rabs (2 * (o1 - c1) + (M1 + M2) * d1 - H1) <= 11 * u * T1 + 13 * eta).
  { apply Rabs_bounds in AL1. apply Rabs_bounds in AD1. rewrite Uv in *. rabs. }
  assert (G2 : Rabs (2 * (o2 - c2) + (M1 + M2) * d2 - H2) <= 11 * u * T2 + 13 * eta).
  { apply Rabs_bounds in AL2. apply Rabs_bounds in AD2. rewrite Uv in *. rabs. }
  pose proof (slope_axis d0 H0 T0 _ Bd0 BH0 BT0 PT0 G0) as S0.
  pose proof (slope_axis d1 H1 T1 _ Bd1 BH1 BT1 PT1 G1) as S1.
  pose proof (slope_axis d2 H2 T2 _ Bd2 BH2 BT2 PT2 G2) as S2.
  cbv zeta in S0, S1, S2.
  set (q0 := RN (d0 * H0)) in *. set (q1 := RN (d1 * H1)) in *. set (q2 := RN (d2 * H2)) in *.
  set (m0 := RN (Rabs d0 * RN (RN (Rabs H0 + T0) + sphere_boundary_slope_floor))) in *.
  set (m1 := RN (Rabs d1 * RN (RN (Rabs H1 + T1) + sphere_boundary_slope_floor))) in *.
  set (m2 := RN (Rabs d2 * RN (RN (Rabs H2 + T2) + sphere_boundary_slope_floor))) in *.
  destruct S0 as [Bq0 [Bm0 [Pm0 [E0 [N0 Lm0]]]]].
  destruct S1 as [Bq1 [Bm1 [Pm1 [E1 [N1 Lm1]]]]].
  destruct S2 as [Bq2 [Bm2 [Pm2 [E2 [N2 Lm2]]]]].
  destruct (sum_step _ _ _ _ _ _ _ _ Bq0 Bq1 E0 E1 N0 N1) as [E01 N01].
  destruct (sum_step _ _ _ _ _ _ _ _ (binary64_RN _) Bq2 E01 E2 N01 N2) as [E012 _].
  set (s := RN (RN (q0 + q1) + q2)) in *.
  (* E_s *)
  rewrite Rplus_0_l, (RN_binary64 m0 Bm0).
  assert (Ls1 : (m0 + m1) * (1 - u) <= RN (m0 + m1)) by (apply RN_plus_lower; auto; lra).
  set (sm1 := RN (m0 + m1)) in *.
  assert (Ps1 : 0 <= sm1) by (apply RN_nonneg; lra).
  assert (Ls2 : (sm1 + m2) * (1 - u) <= RN (sm1 + m2)) by (apply RN_plus_lower; [apply binary64_RN | auto | lra]).
  set (sm2 := RN (sm1 + m2)) in *.
  assert (Ps2 : 0 <= sm2) by (apply RN_nonneg; lra).
  assert (Kv : sphere_boundary_slope_relative = 16 * u) by (unfold sphere_boundary_slope_relative, unit_roundoff;
    replace (-49)%Z with (4 + -53)%Z by lia; rewrite bpow_plus; simpl; lra).
  assert (Mv : sphere_boundary_slope_absolute = 32 * eta).
  { unfold sphere_boundary_slope_absolute, eta. replace (-1070)%Z with (5 + -1075)%Z by lia.
    rewrite bpow_plus. simpl. lra. }
  assert (Bmu : binary64 sphere_boundary_slope_absolute) by (apply binary64_bpow; lia).
  assert (Les : sphere_boundary_slope_relative * sm2 * (1 - u) - eta <= RN (sphere_boundary_slope_relative * sm2))
    by (apply RN_lower; rewrite Kv; apply Rmult_le_pos; lra).
  assert (Pes : 0 <= RN (sphere_boundary_slope_relative * sm2)) by (apply RN_nonneg; rewrite Kv; apply Rmult_le_pos; lra).
  set (es1 := RN (sphere_boundary_slope_relative * sm2)) in *.
  assert (Les2 : (es1 + sphere_boundary_slope_absolute) * (1 - u) <= RN (es1 + sphere_boundary_slope_absolute))
    by (apply RN_plus_lower; [apply binary64_RN | exact Bmu | rewrite Mv; lra]).
  set (es := RN (es1 + sphere_boundary_slope_absolute)) in *.
  eapply Rle_trans; [exact E012|].
  pose proof (Rabs_pos d0) as Pd0. pose proof (Rabs_pos d1) as Pd1. pose proof (Rabs_pos d2) as Pd2.
  assert (PX0 : 0 <= Rabs d0 * Rabs H0) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (PX1 : 0 <= Rabs d1 * Rabs H1) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (PX2 : 0 <= Rabs d2 * Rabs H2) by (apply Rmult_le_pos; [lra | apply Rabs_pos]).
  assert (PY0 : 0 <= Rabs d0 * T0) by (apply Rmult_le_pos; lra).
  assert (PY1 : 0 <= Rabs d1 * T1) by (apply Rmult_le_pos; lra).
  assert (PY2 : 0 <= Rabs d2 * T2) by (apply Rmult_le_pos; lra).
  assert (PZ0 : 0 <= Rabs d0 * sphere_boundary_slope_floor) by (apply Rmult_le_pos; [lra | apply bpow_ge_0]).
  assert (PZ1 : 0 <= Rabs d1 * sphere_boundary_slope_floor) by (apply Rmult_le_pos; [lra | apply bpow_ge_0]).
  assert (PZ2 : 0 <= Rabs d2 * sphere_boundary_slope_floor) by (apply Rmult_le_pos; [lra | apply bpow_ge_0]).
  clear - E012 Lm0 Lm1 Lm2 Pm0 Pm1 Pm2 Ls1 Ls2 Ps1 Ps2 Les Pes Les2 Kv Mv Hu He Uv Pd0 Pd1 Pd2 PX0 PX1 PX2 PY0 PY1 PY2 PZ0 PZ1 PZ2.
  rewrite Kv, Mv, Uv in *. lra.
Qed.

(** The certified sign of the slope is the sign of the exact 2(A·m + B) = Σ_i d_i·(2(o_i − c_i) + (x + y)·d_i). *)
Theorem sphere_boundary_slope_sound : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 d0 -> binary64 d1 -> binary64 d2 ->
  binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r -> binary64 x -> binary64 y ->
  certifies (boundary_slope_sign (boundary o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y))
    (exact_slope2 o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y).
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y Bo0 Bo1 Bo2 Bd0 Bd1 Bd2 Bc0 Bc1 Bc2 Br Bx By.
  pose proof (sphere_boundary_slope_encloses o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y Bo0 Bo1 Bo2 Bd0 Bd1 Bd2
                Bc0 Bc1 Bc2 Br Bx By) as Enc. cbv zeta in Enc.
  set (b := boundary o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y) in *.
  set (S := exact_slope2 o0 o1 o2 d0 d1 d2 c0 c1 c2 r x y) in *.
  set (es := RN (RN (sphere_boundary_slope_relative * bf_slope_magnitude b) + sphere_boundary_slope_absolute)) in *.
  apply Rabs_bounds in Enc.
  unfold boundary_slope_sign. destruct (boundary_q_sign b); try exact I.
  destruct (Rle_bool _ _); [| exact I]. fold es. unfold certifies.
  destruct (Rlt_bool_spec es (bf_slope b)); [lra|].
  destruct (Rlt_bool_spec (bf_slope b) (- es)); [lra | exact I].
Qed.
