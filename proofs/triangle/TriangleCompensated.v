(** * Stage 2 of the ray–triangle cascade: double-double enclosures of a 3×3 determinant
    (kernel/src/core/det3_stages.hpp, [CompensatedLeaf], [CompensatedTerm], [det3_enclosure]; evaluated in
    the order of kernel/src/triangle/ray_triangle_formula.hpp).

    Leaves are exact double-doubles (h, l), |l| ≤ u|h| (d with l = 0, and TwoDiff(v, o)).  A product keeps
    the first-order low part by three FMAs, a sum or difference is a TwoSum with the low parts added.  Main
    theorems: [det3_compensated_encloses] (any determinant of such leaves: |V − (h + l)| ≤ (K ⊗ m) ⊕ A), and
    for the query's values [pi_compensated_encloses], [num_compensated_encloses], [den_compensated_encloses],
    stated as [encloses] (PlaneCompensated.v) of the [Enclosure] the C++ builds, so that [enclosure_sign_sound]
    and [round_quotient_sound] apply to them; [compensated_filter_view]: the high parts and
    magnitudes are stage 1's values, so the C++ takes the filter's signs from them.

    The invariant [capprox] carried through each operation: h, l, m are doubles, |h| ≤ m,
    |l| ≤ λ·m + κ and |h + l − V| ≤ α·m + β, with α of order u² and λ of order u. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model PlaneClassification PlaneCompensated TriangleFilter.
Open Scope R_scope.

(** ** The C++ code. *)

Record CTerm := { ch : R; cl : R; cm : R }.

(** [product_low_part(ah, al, bh, bl, p)] = fma(ah, bl, fma(al, bh, fma(ah, bh, −p))). *)
Definition product_low_part (ah al bh bl p : R) : R := fma ah bl (fma al bh (fma ah bh (- p))).

Definition cleaf_mul (yh yl zh zl : R) : CTerm :=
  let p := RN (yh * zh) in {| ch := p; cl := product_low_part yh yl zh zl p; cm := Rabs p |}.
Definition cleaf_scale (xh xl : R) (c : CTerm) : CTerm :=
  let p := RN (xh * ch c) in {| ch := p; cl := product_low_part xh xl (ch c) (cl c) p; cm := RN (Rabs xh * cm c) |}.
Definition cterm_add (a b : CTerm) : CTerm :=
  let s := two_sum (ch a) (ch b) in {| ch := fst s; cl := RN (RN (cl a + cl b) + snd s); cm := RN (cm a + cm b) |}.
Definition cterm_sub (a b : CTerm) : CTerm :=
  let s := two_sum (ch a) (- ch b) in {| ch := fst s; cl := RN (RN (cl a - cl b) + snd s); cm := RN (cm a + cm b) |}.

Definition cdet3 (xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 : R) : CTerm :=
  cterm_add (cterm_add (cleaf_scale xh0 xl0 (cterm_sub (cleaf_mul yh1 yl1 zh2 zl2) (cleaf_mul yh2 yl2 zh1 zl1)))
                       (cleaf_scale xh1 xl1 (cterm_sub (cleaf_mul yh2 yl2 zh0 zl0) (cleaf_mul yh0 yl0 zh2 zl2))))
            (cleaf_scale xh2 xl2 (cterm_sub (cleaf_mul yh0 yl0 zh1 zl1) (cleaf_mul yh1 yl1 zh0 zl0))).

(** [det3_enclosure(t, K, A)]: (h, l, (K ⊗ m) ⊕ A).  (The C++ replaces the radius by +inf when h or l is not
    finite; in the model nothing overflows: proofs/README.md, "Overflow".) *)
Definition det3_enclosure (t : CTerm) (K A : R) : Enclosure :=
  {| hi := ch t; lo := cl t; radius := RN (RN (K * cm t) + A) |}.

(** ** The high parts and magnitudes are stage 1's. *)
Lemma cleaf_mul_view : forall yh yl zh zl, ch (cleaf_mul yh yl zh zl) = fv (leaf_mul yh zh) /\
                                          cm (cleaf_mul yh yl zh zl) = fm (leaf_mul yh zh).
Proof. intros. split; reflexivity. Qed.

Lemma compensated_filter_view : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  let t := cdet3 xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 in
  let f := det3 xh0 xh1 xh2 yh0 yh1 yh2 zh0 zh1 zh2 in
  ch t = fv f /\ cm t = fm f.
Proof.
  intros. subst t f. unfold cdet3, det3, cterm_add, cterm_sub, cleaf_scale, cleaf_mul, term_add, term_sub,
    leaf_scale, leaf_mul. cbn [ch cm fv fm]. rewrite !two_sum_hi. unfold Rminus. split; reflexivity.
Qed.

(** ** The invariant. *)
Definition capprox (t : CTerm) (V alpha beta lam kap : R) : Prop :=
  binary64 (ch t) /\ binary64 (cl t) /\ binary64 (cm t) /\ 0 <= cm t /\ Rabs (ch t) <= cm t /\
  Rabs (cl t) <= lam * cm t + kap /\ Rabs (ch t + cl t - V) <= alpha * cm t + beta.

Lemma capprox_weaken : forall t V a b l k a' b' l' k', capprox t V a b l k ->
  a <= a' -> b <= b' -> l <= l' -> k <= k' -> capprox t V a' b' l' k'.
Proof.
  intros t V a b l k a' b' l' k' [B1 [B2 [B3 [P [D [L E]]]]]] Ha Hb Hl Hk.
  assert (a * cm t <= a' * cm t) by (apply Rmult_le_compat_r; assumption).
  assert (l * cm t <= l' * cm t) by (apply Rmult_le_compat_r; assumption).
  repeat split; try assumption; lra.
Qed.

(** The error of a product's low part: with p = a_h ⊗ b_h and w = product_low_part:
    p + w = a_h b_h + a_h b_l + a_l b_h + ε, |ε| ≤ η + |ε_1| + |ε_2|, where ε_1, ε_2 are the errors of the
    two outer FMAs. *)
Lemma product_low_part_error : forall ah al bh bl, binary64 ah -> binary64 bh ->
  let p := RN (ah * bh) in
  let w0 := fma ah bh (- p) in
  let w1 := fma al bh w0 in
  let w := product_low_part ah al bh bl p in
  Rabs (p + w - (ah * bh + ah * bl + al * bh)) <= eta + Rabs (w1 - (al * bh + w0)) + Rabs (w - (ah * bl + w1)) /\
  Rabs w0 <= u * Rabs (ah * bh) + 2 * eta.
Proof.
  intros ah al bh bl Ba Bb p w0 w1 w.
  pose proof (two_prod_error ah bh Ba Bb) as E0. unfold two_prod in E0. cbn [fst snd] in E0. fold p w0 in E0.
  split.
  - replace (p + w - (ah * bh + ah * bl + al * bh))
      with (- (ah * bh - (p + w0)) + (w1 - (al * bh + w0)) + (w - (ah * bl + w1))) by (unfold w; ring).
    eapply Rle_trans; [apply Rabs_triang|]. eapply Rle_trans; [apply Rplus_le_compat_r, Rabs_triang|].
    rewrite Rabs_Ropp. lra.
  - pose proof (RN_err (ah * bh)) as E. fold p in E.
    replace w0 with ((ah * bh - p) - (ah * bh - (p + w0))) by ring.
    unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
    rewrite Rabs_minus_sym in E. lra.
Qed.

(** |a_l·b| ≤ u·|a_h·b| for a low part |a_l| ≤ u|a_h|. *)
Lemma low_product : forall al ah b, Rabs al <= u * Rabs ah -> Rabs (al * b) <= u * Rabs (ah * b).
Proof.
  intros. rewrite !Rabs_mult. rewrite <- Rmult_assoc. apply Rmult_le_compat_r; [apply Rabs_pos | assumption].
Qed.

(** A product of two leaves (exact double-doubles). *)
Lemma cleaf_mul_capprox : forall yh yl zh zl, binary64 yh -> binary64 zh ->
  Rabs yl <= u * Rabs yh -> Rabs zl <= u * Rabs zh ->
  capprox (cleaf_mul yh yl zh zl) ((yh + yl) * (zh + zl)) (7 * (u * u)) (4 * eta) (4 * u) (7 * eta).
Proof.
  intros yh yl zh zl Byh Bzh Hy Hz. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  unfold capprox, cleaf_mul. cbn [ch cl cm].
  set (p := RN (yh * zh)).
  destruct (product_low_part_error yh yl zh zl Byh Bzh) as [E Hw0]. cbv zeta in E, Hw0. fold p in E, Hw0.
  set (w0 := fma yh zh (- p)) in *.
  set (w1 := fma yl zh w0) in *.
  set (w := product_low_part yh yl zh zl p) in *.
  set (A := Rabs (yh * zh)) in *.
  assert (HA : A <= (1 + 2 * u) * (Rabs p + eta)) by apply abs_before_rounding.
  assert (L1 : Rabs (yl * zh) <= u * A) by (apply low_product; exact Hy).
  assert (L2 : Rabs (yh * zl) <= u * A).
  { unfold A. rewrite (Rmult_comm yh zl), (Rmult_comm yh zh). apply low_product. exact Hz. }
  assert (L3 : Rabs (yl * zl) <= u * (u * A)).
  { rewrite Rabs_mult. unfold A. rewrite Rabs_mult.
    pose proof (Rabs_pos yl). pose proof (Rabs_pos zl).
    assert (Rabs yl * Rabs zl <= (u * Rabs yh) * (u * Rabs zh)) by (apply Rmult_le_compat; assumption).
    lra. }
  assert (G1 : Rabs (yl * zh + w0) <= 2 * u * A + 2 * eta) by (eapply Rle_trans; [apply Rabs_triang | lra]).
  assert (E1 : Rabs (w1 - (yl * zh + w0)) <= u * Rabs (yl * zh + w0) + eta) by apply RN_err.
  assert (W1 : Rabs w1 <= Rabs (yl * zh + w0) + Rabs (w1 - (yl * zh + w0))) by (apply Rabs_close; lra).
  assert (G2 : Rabs (yh * zl + w1) <= u * A + Rabs w1) by (eapply Rle_trans; [apply Rabs_triang | lra]).
  assert (E2 : Rabs (w - (yh * zl + w1)) <= u * Rabs (yh * zl + w1) + eta) by apply RN_err.
  assert (W : Rabs w <= Rabs (yh * zl + w1) + Rabs (w - (yh * zl + w1))) by (apply Rabs_close; lra).
  assert (F1 : u * Rabs (yl * zh + w0) <= u * (2 * u * A + 2 * eta)) by (apply Rmult_le_compat_l; lra).
  assert (F2 : u * Rabs (yh * zl + w1) <= u * (u * A + Rabs w1)) by (apply Rmult_le_compat_l; lra).
  pose proof (Rabs_pos p). pose proof (Rabs_pos (yh * zh)).
  assert (F3 : u * (u * A) <= u * (u * ((1 + 2 * u) * (Rabs p + eta)))) by (repeat apply Rmult_le_compat_l; lra).
  repeat split.
  - apply binary64_RN.
  - apply binary64_RN.
  - apply binary64_abs_RN.
  - apply Rabs_pos.
  - apply Rle_refl.
  - rewrite u_val in *. nra.
  - replace (p + w - (yh + yl) * (zh + zl)) with ((p + w - (yh * zh + yh * zl + yl * zh)) - yl * zl) by ring.
    unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
    rewrite u_val in *. nra.
Qed.

(** The sum of two double-doubles: TwoSum of the high parts, the low parts added and the TwoSum error added
    to them. *)
Lemma cterm_add_capprox : forall a b A B alpha beta1 beta2 lam kap1 kap2,
  capprox a A alpha beta1 lam kap1 -> capprox b B alpha beta2 lam kap2 ->
  0 <= alpha -> 0 <= lam -> 0 <= kap1 -> 0 <= kap2 ->
  capprox (cterm_add a b) (A + B)
    ((alpha + u * u + (u * (1 + u) + u) * lam) * (1 + u))
    (beta1 + beta2 + (u * (1 + u) + u) * (kap1 + kap2))
    ((1 + u) * ((1 + u) * lam + u) * (1 + u))
    ((1 + u) * (1 + u) * (kap1 + kap2)).
Proof.
  intros a b A B alpha beta1 beta2 lam kap1 kap2 [Bha [Bla [Bma [Pa [Da [La Ea]]]]]]
    [Bhb [Blb [Bmb [Pb [Db [Lb Eb]]]]]] Halpha Hlam Hk1 Hk2.
  pose proof u_pos. pose proof u_small. pose proof eta_pos.
  unfold capprox, cterm_add. cbn [ch cl cm].
  set (st := two_sum (ch a) (ch b)).
  set (s := fst st). set (sigma := snd st).
  set (l1 := RN (cl a + cl b)). set (lo := RN (l1 + sigma)). set (m := RN (cm a + cm b)).
  set (M := cm a + cm b).
  pose proof (RN_plus_err_round (cm a) (cm b) Bma Bmb) as Em. fold m M in Em.
  assert (Pm : 0 <= m) by (unfold m; apply RN_nonneg; lra).
  rewrite (Rabs_nonneg_eq m Pm) in Em.
  assert (HM : M <= (1 + u) * m) by (apply Rabs_bounds in Em; lra).
  pose proof (two_sum_exact (ch a) (ch b) Bha Bhb) as X. fold st s sigma in X.
  destruct (two_sum_lo_bound (ch a) (ch b) Bha Bhb) as [Sg _]. fold st sigma in Sg.
  assert (Hsum : Rabs (ch a + ch b) <= M) by (eapply Rle_trans; [apply Rabs_triang|]; unfold M; lra).
  assert (Sg' : Rabs sigma <= u * M) by (eapply Rle_trans; [exact Sg | apply Rmult_le_compat_l; lra]).
  set (L := Rabs (cl a) + Rabs (cl b)).
  assert (HL : L <= lam * M + (kap1 + kap2)) by (unfold L, M; lra).
  assert (Hl1 : Rabs (cl a + cl b) <= L) by (apply Rabs_triang).
  pose proof (RN_plus_err (cl a) (cl b) Bla Blb) as E1. fold l1 in E1.
  assert (L1 : Rabs l1 <= (1 + u) * L).
  { assert (Rabs l1 <= Rabs (cl a + cl b) + u * Rabs (cl a + cl b)) by (apply Rabs_close; exact E1).
    assert (u * Rabs (cl a + cl b) <= u * L) by (apply Rmult_le_compat_l; lra). lra. }
  assert (Bl1 : binary64 l1) by apply binary64_RN.
  assert (Bsg : binary64 sigma) by apply binary64_two_sum_lo.
  pose proof (RN_plus_err l1 sigma Bl1 Bsg) as E2. fold lo in E2.
  assert (G : Rabs (l1 + sigma) <= (1 + u) * L + u * M) by (eapply Rle_trans; [apply Rabs_triang | lra]).
  pose proof (Rabs_pos (cl a)). pose proof (Rabs_pos (cl b)).
  assert (PM : 0 <= M) by (unfold M; lra).
  assert (F1 : u * Rabs (l1 + sigma) <= u * ((1 + u) * L + u * M)) by (apply Rmult_le_compat_l; lra).
  assert (F2 : u * Rabs (cl a + cl b) <= u * L) by (apply Rmult_le_compat_l; lra).
  assert (F3 : (1 + u) * ((1 + u) * lam + u) * M <= (1 + u) * ((1 + u) * lam + u) * ((1 + u) * m))
    by (apply Rmult_le_compat_l; nra).
  assert (F4 : (alpha + u * u + (u * (1 + u) + u) * lam) * M <= (alpha + u * u + (u * (1 + u) + u) * lam) * ((1 + u) * m))
    by (apply Rmult_le_compat_l; nra).
  assert (F5 : (1 + u) * L <= (1 + u) * (lam * M + (kap1 + kap2))) by (apply Rmult_le_compat_l; lra).
  assert (F6 : (u * (1 + u) + u) * L <= (u * (1 + u) + u) * (lam * M + (kap1 + kap2))) by (apply Rmult_le_compat_l; nra).
  assert (F7 : (1 + u) * ((1 + u) * L + u * M) <= (1 + u) * ((1 + u) * (lam * M + (kap1 + kap2)) + u * M))
    by (apply Rmult_le_compat_l; nra).
  repeat split.
  - apply binary64_two_sum_hi.
  - apply binary64_RN.
  - apply binary64_RN.
  - exact Pm.
  - unfold s, st. rewrite two_sum_hi, <- RN_abs. apply RN_le. exact Hsum.
  - assert (Rabs lo <= Rabs (l1 + sigma) + u * Rabs (l1 + sigma)) by (apply Rabs_close; exact E2).
    assert (Rabs lo <= (1 + u) * ((1 + u) * L + u * M)) by nra.
    nra.
  - replace (s + lo - (A + B))
      with ((lo - (l1 + sigma)) + (l1 - (cl a + cl b)) + (ch a + cl a - A) + (ch b + cl b - B)) by lra.
    eapply Rle_trans; [apply Rabs_triang|].
    eapply Rle_trans; [apply Rplus_le_compat_r; eapply Rle_trans; [apply Rabs_triang|];
                       apply Rplus_le_compat_r, Rabs_triang|].
    assert (alpha * cm a + alpha * cm b = alpha * M) by (unfold M; ring).
    nra.
Qed.

(** The negation of a double-double (exact), and the difference as a sum with it. *)
Definition cneg (b : CTerm) : CTerm := {| ch := - ch b; cl := - cl b; cm := cm b |}.

Lemma cneg_capprox : forall b B alpha beta lam kap, capprox b B alpha beta lam kap -> capprox (cneg b) (- B) alpha beta lam kap.
Proof.
  intros b B alpha beta lam kap [B1 [B2 [B3 [P [D [L E]]]]]]. unfold capprox, cneg. cbn [ch cl cm].
  rewrite !Rabs_Ropp. replace (- ch b + - cl b - - B) with (- (ch b + cl b - B)) by ring. rewrite Rabs_Ropp.
  repeat split; try apply binary64_opp; assumption.
Qed.

Lemma cterm_sub_as_add : forall a b, cterm_sub a b = cterm_add a (cneg b).
Proof. intros. unfold cterm_sub, cterm_add, cneg. cbn [ch cl cm]. unfold Rminus. reflexivity. Qed.

Lemma cterm_sub_capprox : forall a b A B alpha beta1 beta2 lam kap1 kap2,
  capprox a A alpha beta1 lam kap1 -> capprox b B alpha beta2 lam kap2 ->
  0 <= alpha -> 0 <= lam -> 0 <= kap1 -> 0 <= kap2 ->
  capprox (cterm_sub a b) (A - B)
    ((alpha + u * u + (u * (1 + u) + u) * lam) * (1 + u))
    (beta1 + beta2 + (u * (1 + u) + u) * (kap1 + kap2))
    ((1 + u) * ((1 + u) * lam + u) * (1 + u))
    ((1 + u) * (1 + u) * (kap1 + kap2)).
Proof.
  intros. rewrite cterm_sub_as_add. unfold Rminus. apply cterm_add_capprox; try assumption. now apply cneg_capprox.
Qed.

(** A leaf (xh, xl) times a double-double: the absolute parts β and κ of the factor are scaled by |xh|. *)
Lemma cleaf_scale_capprox : forall xh xl c C alpha beta lam kap,
  binary64 xh -> Rabs xl <= u * Rabs xh -> capprox c C alpha beta lam kap ->
  0 <= alpha <= u -> 0 <= beta -> 0 <= lam <= 1 / 16 -> 0 <= kap ->
  capprox (cleaf_scale xh xl c) ((xh + xl) * C)
    (((1 + u) * alpha + 2 * u * lam + 5 * (u * u)) * (1 + 2 * u))
    (Rabs xh * ((1 + u) * beta + 2 * u * kap) + 5 * eta)
    ((1 + u) * (lam + 3 * u) * (1 + 2 * u))
    (Rabs xh * ((1 + u) * kap) + 6 * eta).
Proof.
  intros xh xl c C alpha beta lam kap Bxh Hxl [Bch [Bcl [Bcm [Pc [Dc [Lc Ec]]]]]] Ha Hb Hl Hk.
  pose proof u_pos. pose proof u_small. pose proof eta_pos.
  unfold capprox, cleaf_scale. cbn [ch cl cm].
  set (p := RN (xh * ch c)).
  destruct (product_low_part_error xh xl (ch c) (cl c) Bxh Bch) as [E Hw0]. cbv zeta in E, Hw0. fold p in E, Hw0.
  set (w0 := fma xh (ch c) (- p)) in *.
  set (w1 := fma xl (ch c) w0) in *.
  set (w := product_low_part xh xl (ch c) (cl c) p) in *.
  set (Q := Rabs xh * cm c).
  pose proof (Rabs_pos xh) as Px.
  assert (PQ : 0 <= Q) by (unfold Q; apply Rmult_le_pos; lra).
  set (m := RN Q).
  assert (Pm : 0 <= m) by (apply RN_nonneg; exact PQ).
  assert (HQ : Q <= (1 + 2 * u) * (m + eta)).
  { pose proof (abs_before_rounding Q) as HH. fold m in HH.
    rewrite (Rabs_nonneg_eq Q PQ), (Rabs_nonneg_eq m Pm) in HH. exact HH. }
  assert (Hxc : Rabs (xh * ch c) <= Q) by (rewrite Rabs_mult; apply Rmult_le_compat_l; lra).
  assert (L1 : Rabs (xl * ch c) <= u * Q).
  { eapply Rle_trans; [apply low_product; exact Hxl|]. apply Rmult_le_compat_l; lra. }
  assert (Hxcl : Rabs (xh * cl c) <= lam * Q + kap * Rabs xh).
  { rewrite Rabs_mult. assert (Rabs xh * Rabs (cl c) <= Rabs xh * (lam * cm c + kap)) by (apply Rmult_le_compat_l; lra).
    unfold Q. lra. }
  assert (Hlcl : Rabs (xl * cl c) <= u * (lam * Q + kap * Rabs xh)).
  { eapply Rle_trans; [apply low_product; exact Hxl|]. apply Rmult_le_compat_l; lra. }
  assert (Hw0' : Rabs w0 <= u * Q + 2 * eta).
  { eapply Rle_trans; [exact Hw0|]. assert (u * Rabs (xh * ch c) <= u * Q) by (apply Rmult_le_compat_l; lra). lra. }
  assert (G1 : Rabs (xl * ch c + w0) <= 2 * u * Q + 2 * eta) by (eapply Rle_trans; [apply Rabs_triang | lra]).
  assert (E1 : Rabs (w1 - (xl * ch c + w0)) <= u * Rabs (xl * ch c + w0) + eta) by apply RN_err.
  assert (W1 : Rabs w1 <= Rabs (xl * ch c + w0) + Rabs (w1 - (xl * ch c + w0))) by (apply Rabs_close; lra).
  assert (G2 : Rabs (xh * cl c + w1) <= lam * Q + kap * Rabs xh + Rabs w1) by (eapply Rle_trans; [apply Rabs_triang | lra]).
  assert (E2 : Rabs (w - (xh * cl c + w1)) <= u * Rabs (xh * cl c + w1) + eta) by apply RN_err.
  assert (W : Rabs w <= Rabs (xh * cl c + w1) + Rabs (w - (xh * cl c + w1))) by (apply Rabs_close; lra).
  assert (F1 : u * Rabs (xl * ch c + w0) <= u * (2 * u * Q + 2 * eta)) by (apply Rmult_le_compat_l; lra).
  assert (F2 : u * Rabs (xh * cl c + w1) <= u * (lam * Q + kap * Rabs xh + Rabs w1)) by (apply Rmult_le_compat_l; lra).
  (* the exact value: (xh + xl)·C = (xh + xl)(ch + cl) + (xh + xl)(C − ch − cl) *)
  assert (HX : Rabs ((xh + xl) * (C - (ch c + cl c))) <= (1 + u) * (alpha * Q + beta * Rabs xh)).
  { rewrite Rabs_mult. assert (Rabs (xh + xl) <= (1 + u) * Rabs xh) by (eapply Rle_trans; [apply Rabs_triang | lra]).
    rewrite Rabs_minus_sym.
    assert (Rabs (xh + xl) * Rabs (ch c + cl c - C) <= (1 + u) * Rabs xh * (alpha * cm c + beta))
      by (apply Rmult_le_compat; try apply Rabs_pos; lra).
    unfold Q. lra. }
  (* linear facts for lra: the products of two variables are atoms *)
  assert (AQ : alpha * Q <= alpha * ((1 + 2 * u) * (m + eta))) by (apply Rmult_le_compat_l; lra).
  assert (LQ : lam * Q <= lam * ((1 + 2 * u) * (m + eta))) by (apply Rmult_le_compat_l; lra).
  assert (AE : alpha * eta <= u * eta) by (apply Rmult_le_compat_r; lra).
  assert (LE : lam * eta <= 1 / 16 * eta) by (apply Rmult_le_compat_r; lra).
  assert (PA : 0 <= alpha * Q) by (apply Rmult_le_pos; lra).
  assert (PL : 0 <= lam * Q) by (apply Rmult_le_pos; lra).
  assert (PK : 0 <= kap * Rabs xh) by (apply Rmult_le_pos; lra).
  assert (PB : 0 <= beta * Rabs xh) by (apply Rmult_le_pos; lra).
  assert (PAm : 0 <= alpha * m) by (apply Rmult_le_pos; lra).
  assert (PLm : 0 <= lam * m) by (apply Rmult_le_pos; lra).
  assert (HW1 : Rabs w1 <= (1 + u) * (2 * u * Q + 2 * eta) + eta).
  { rewrite u_val in *. lra. }
  repeat split.
  - apply binary64_RN.
  - apply binary64_RN.
  - apply binary64_RN.
  - exact Pm.
  - unfold p, m. rewrite <- RN_abs. apply RN_le. exact Hxc.
  - rewrite u_val in *. lra.
  - replace (p + w - (xh + xl) * C)
      with ((p + w - (xh * ch c + xh * cl c + xl * ch c)) + - (xl * cl c) + - ((xh + xl) * (C - (ch c + cl c))))
      by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
    eapply Rle_trans; [apply Rplus_le_compat_r, Rabs_triang|]. rewrite Rabs_Ropp.
    rewrite u_val in *. lra.
Qed.

(** ** The determinant. *)

Lemma ccross_capprox : forall yhj ylj zhk zlk yhk ylk zhj zlj,
  binary64 yhj -> binary64 zhk -> binary64 yhk -> binary64 zhj ->
  Rabs ylj <= u * Rabs yhj -> Rabs zlk <= u * Rabs zhk -> Rabs ylk <= u * Rabs yhk -> Rabs zlj <= u * Rabs zhj ->
  capprox (cterm_sub (cleaf_mul yhj ylj zhk zlk) (cleaf_mul yhk ylk zhj zlj))
          ((yhj + ylj) * (zhk + zlk) - (yhk + ylk) * (zhj + zlj))
          (17 * (u * u)) (81 / 10 * eta) (6 * u) (15 * eta).
Proof.
  intros. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  eapply capprox_weaken.
  - apply cterm_sub_capprox; try (apply cleaf_mul_capprox; assumption); nra.
  - rewrite u_val. nra.
  - rewrite u_val. nra.
  - rewrite u_val. nra.
  - rewrite u_val. nra.
Qed.

Lemma couter_capprox : forall xh xl c C, binary64 xh -> Rabs xl <= u * Rabs xh ->
  capprox c C (17 * (u * u)) (81 / 10 * eta) (6 * u) (15 * eta) ->
  capprox (cleaf_scale xh xl c) ((xh + xl) * C) (35 * (u * u)) (Rabs xh * (82 / 10 * eta) + 5 * eta) (10 * u)
          (Rabs xh * (16 * eta) + 6 * eta).
Proof.
  intros xh xl c C Bx Hx Hc. pose proof u_pos. pose proof u_small. pose proof eta_pos. pose proof (Rabs_pos xh).
  eapply capprox_weaken.
  - apply cleaf_scale_capprox; try eassumption; rewrite ?u_val in *; split || idtac; nra.
  - rewrite u_val. nra.
  - assert (Rabs xh * ((1 + u) * (81 / 10 * eta) + 2 * u * (15 * eta)) <= Rabs xh * (82 / 10 * eta)).
    { apply Rmult_le_compat_l; [lra|]. rewrite u_val. nra. }
    lra.
  - rewrite u_val. nra.
  - assert (Rabs xh * ((1 + u) * (15 * eta)) <= Rabs xh * (16 * eta)).
    { apply Rmult_le_compat_l; [lra|]. rewrite u_val. nra. }
    lra.
Qed.

Definition cdet3_alpha : R := 80 * (u * u).
Definition cdet3_lam : R := 13 * u.

Lemma cdet3_capprox : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2,
  binary64 xh0 -> binary64 xh1 -> binary64 xh2 -> binary64 yh0 -> binary64 yh1 -> binary64 yh2 ->
  binary64 zh0 -> binary64 zh1 -> binary64 zh2 ->
  Rabs xl0 <= u * Rabs xh0 -> Rabs xl1 <= u * Rabs xh1 -> Rabs xl2 <= u * Rabs xh2 ->
  Rabs yl0 <= u * Rabs yh0 -> Rabs yl1 <= u * Rabs yh1 -> Rabs yl2 <= u * Rabs yh2 ->
  Rabs zl0 <= u * Rabs zh0 -> Rabs zl1 <= u * Rabs zh1 -> Rabs zl2 <= u * Rabs zh2 ->
  let S := Rabs xh0 + Rabs xh1 + Rabs xh2 in
  capprox (cdet3 xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2)
          (det3_exact (xh0 + xl0) (xh1 + xl1) (xh2 + xl2) (yh0 + yl0) (yh1 + yl1) (yh2 + yl2)
                      (zh0 + zl0) (zh1 + zl1) (zh2 + zl2))
          cdet3_alpha (S * (83 / 10 * eta) + 16 * eta) cdet3_lam (S * (17 * eta) + 19 * eta).
Proof.
  intros. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  pose proof (Rabs_pos xh0). pose proof (Rabs_pos xh1). pose proof (Rabs_pos xh2).
  unfold cdet3, det3_exact.
  assert (T0 := couter_capprox xh0 xl0 _ _ ltac:(assumption) ltac:(assumption)
                  (ccross_capprox yh1 yl1 zh2 zl2 yh2 yl2 zh1 zl1 ltac:(assumption) ltac:(assumption)
                     ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)
                     ltac:(assumption))).
  assert (T1 := couter_capprox xh1 xl1 _ _ ltac:(assumption) ltac:(assumption)
                  (ccross_capprox yh2 yl2 zh0 zl0 yh0 yl0 zh2 zl2 ltac:(assumption) ltac:(assumption)
                     ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)
                     ltac:(assumption))).
  assert (T2 := couter_capprox xh2 xl2 _ _ ltac:(assumption) ltac:(assumption)
                  (ccross_capprox yh0 yl0 zh1 zl1 yh1 yl1 zh0 zl0 ltac:(assumption) ltac:(assumption)
                     ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)
                     ltac:(assumption))).
  assert (K0 : 0 <= Rabs xh0 * (16 * eta) + 6 * eta) by nra.
  assert (K1 : 0 <= Rabs xh1 * (16 * eta) + 6 * eta) by nra.
  assert (K2 : 0 <= Rabs xh2 * (16 * eta) + 6 * eta) by nra.
  pose proof (cterm_add_capprox _ _ _ _ _ _ _ _ _ _ T0 T1 ltac:(nra) ltac:(nra) K0 K1) as S01.
  set (a01 := (35 * (u * u) + u * u + (u * (1 + u) + u) * (10 * u)) * (1 + u)) in S01.
  set (l01 := (1 + u) * ((1 + u) * (10 * u) + u) * (1 + u)) in S01.
  assert (T2' : capprox (cleaf_scale xh2 xl2 (cterm_sub (cleaf_mul yh0 yl0 zh1 zl1) (cleaf_mul yh1 yl1 zh0 zl0)))
                  ((xh2 + xl2) * ((yh0 + yl0) * (zh1 + zl1) - (yh1 + yl1) * (zh0 + zl0))) a01
                  (Rabs xh2 * (82 / 10 * eta) + 5 * eta) l01 (Rabs xh2 * (16 * eta) + 6 * eta)).
  { eapply capprox_weaken; [exact T2| unfold a01; nra | lra | unfold l01; nra | lra]. }
  assert (K01 : 0 <= (1 + u) * (1 + u) * (Rabs xh0 * (16 * eta) + 6 * eta + (Rabs xh1 * (16 * eta) + 6 * eta))) by nra.
  pose proof (cterm_add_capprox _ _ _ _ _ _ _ _ _ _ S01 T2' ltac:(unfold a01; nra) ltac:(unfold l01; nra) K01 K2) as Sum.
  assert (X0 : 0 <= Rabs xh0 * eta) by nra. assert (X1 : 0 <= Rabs xh1 * eta) by nra.
  assert (X2 : 0 <= Rabs xh2 * eta) by nra.
  eapply capprox_weaken; [exact Sum | | | |].
  - unfold a01, l01, cdet3_alpha. rewrite u_val. lra.
  - subst S. rewrite u_val in *. lra.
  - unfold l01, cdet3_lam. rewrite u_val. lra.
  - subst S. rewrite u_val in *. lra.
Qed.

(** ** The radius covers the error. *)
Lemma radius_covers : forall t V alpha beta lam kap K A,
  capprox t V alpha beta lam kap -> binary64 A -> 0 <= K -> eta <= A ->
  alpha <= K * ((1 - u) * (1 - u)) -> beta <= (1 - u) * (A - eta) ->
  encloses (det3_enclosure t K A) V.
Proof.
  intros t V alpha beta lam kap K A [_ [_ [_ [Pm [_ [_ E]]]]]] BA PK HA Ha Hb.
  pose proof u_pos. pose proof u_small. pose proof eta_pos.
  unfold encloses, det3_enclosure. cbn [hi lo radius]. rewrite Rabs_minus_sym.
  set (m := cm t) in *.
  set (X := RN (K * m)).
  pose proof (RN_err (K * m)) as E1. fold X in E1.
  rewrite (Rabs_nonneg_eq (K * m)) in E1 by nra. apply Rabs_bounds in E1.
  assert (PX : 0 <= X) by (apply RN_nonneg; nra).
  pose proof (RN_plus_err X A ltac:(apply binary64_RN) BA) as E2.
  rewrite (Rabs_nonneg_eq (X + A)) in E2 by lra. apply Rabs_bounds in E2.
  assert (F : alpha * m <= K * ((1 - u) * (1 - u)) * m) by (apply Rmult_le_compat_r; assumption).
  nra.
Qed.

Lemma det3_enclosure_binary64 : forall t V alpha beta lam kap K A, capprox t V alpha beta lam kap ->
  binary64 (hi (det3_enclosure t K A)) /\ binary64 (lo (det3_enclosure t K A)) /\
  binary64 (radius (det3_enclosure t K A)).
Proof. intros t V alpha beta lam kap K A [B1 [B2 _]]. repeat split; try assumption. apply binary64_RN. Qed.

Lemma triangle_compensated_relative_val : triangle_compensated_relative = 128 * (u * u).
Proof. reflexivity. Qed.

(** The general enclosure. *)
Theorem det3_compensated_encloses : forall xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2 K,
  binary64 xh0 -> binary64 xh1 -> binary64 xh2 -> binary64 yh0 -> binary64 yh1 -> binary64 yh2 ->
  binary64 zh0 -> binary64 zh1 -> binary64 zh2 ->
  Rabs xl0 <= u * Rabs xh0 -> Rabs xl1 <= u * Rabs xh1 -> Rabs xl2 <= u * Rabs xh2 ->
  Rabs yl0 <= u * Rabs yh0 -> Rabs yl1 <= u * Rabs yh1 -> Rabs yl2 <= u * Rabs yh2 ->
  Rabs zl0 <= u * Rabs zh0 -> Rabs zl1 <= u * Rabs zh1 -> Rabs zl2 <= u * Rabs zh2 ->
  cdet3_alpha <= K * ((1 - u) * (1 - u)) ->
  encloses (det3_enclosure (cdet3 xh0 xl0 xh1 xl1 xh2 xl2 yh0 yl0 yh1 yl1 yh2 yl2 zh0 zl0 zh1 zl1 zh2 zl2) K
                           (absolute_term xh0 xh1 xh2))
           (det3_exact (xh0 + xl0) (xh1 + xl1) (xh2 + xl2) (yh0 + yl0) (yh1 + yl1) (yh2 + yl2)
                       (zh0 + zl0) (zh1 + zl1) (zh2 + zl2)).
Proof.
  intros. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  destruct (absolute_term_lower xh0 xh1 xh2) as [BA HA]; try assumption.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  pose proof (Rabs_pos xh0). pose proof (Rabs_pos xh1). pose proof (Rabs_pos xh2).
  assert (PK : 0 <= K).
  { unfold cdet3_alpha in *. assert (0 < (1 - u) * (1 - u)) by nra. nra. }
  eapply radius_covers; [apply cdet3_capprox; eassumption | exact BA | exact PK | | eassumption |];
    rewrite u_val in *; nra.
Qed.

(** ** The values of a ray–triangle query (kernel/src/triangle/ray_triangle_stages.hpp,
    [triangle_compensated_values]): the leaves d = (d, 0) and e_v = TwoDiff(v, o). *)

Definition pi_stage2 (o d p q : vec3) : CTerm :=
  cdet3 (vx d) 0 (vy d) 0 (vz d) 0
        (RN (vx p - vx o)) (snd (two_diff (vx p) (vx o))) (RN (vy p - vy o)) (snd (two_diff (vy p) (vy o)))
        (RN (vz p - vz o)) (snd (two_diff (vz p) (vz o)))
        (RN (vx q - vx o)) (snd (two_diff (vx q) (vx o))) (RN (vy q - vy o)) (snd (two_diff (vy q) (vy o)))
        (RN (vz q - vz o)) (snd (two_diff (vz q) (vz o))).
Definition num_stage2 (o a b c : vec3) : CTerm :=
  cdet3 (RN (vx a - vx o)) (snd (two_diff (vx a) (vx o))) (RN (vy a - vy o)) (snd (two_diff (vy a) (vy o)))
        (RN (vz a - vz o)) (snd (two_diff (vz a) (vz o)))
        (RN (vx b - vx o)) (snd (two_diff (vx b) (vx o))) (RN (vy b - vy o)) (snd (two_diff (vy b) (vy o)))
        (RN (vz b - vz o)) (snd (two_diff (vz b) (vz o)))
        (RN (vx c - vx o)) (snd (two_diff (vx c) (vx o))) (RN (vy c - vy o)) (snd (two_diff (vy c) (vy o)))
        (RN (vz c - vz o)) (snd (two_diff (vz c) (vz o))).
Definition den_stage2 (o d a b c : vec3) : CTerm :=
  cterm_add (cterm_add (pi_stage2 o d b c) (pi_stage2 o d c a)) (pi_stage2 o d a b).

Lemma zero_low : forall x, Rabs 0 <= u * Rabs x.
Proof. intros. rewrite Rabs_R0. pose proof u_pos. pose proof (Rabs_pos x). nra. Qed.

Lemma pi_capprox : forall o d p q, doubles3 o -> doubles3 d -> doubles3 p -> doubles3 q ->
  capprox (pi_stage2 o d p q) (edge_value o d p q) cdet3_alpha
          ((Rabs (vx d) + Rabs (vy d) + Rabs (vz d)) * (83 / 10 * eta) + 16 * eta) cdet3_lam
          ((Rabs (vx d) + Rabs (vy d) + Rabs (vz d)) * (17 * eta) + 19 * eta).
Proof.
  intros [ox oy oz] [dx dy dz] [px py pz] [qx qy qz] [Box [Boy Boz]] [Bdx [Bdy Bdz]] [Bpx [Bpy Bpz]] [Bqx [Bqy Bqz]].
  cbn [vx vy vz] in *.
  destruct (two_diff_low_part px ox Bpx Box) as [Xpx [Lpx _]]. destruct (two_diff_low_part py oy Bpy Boy) as [Xpy [Lpy _]].
  destruct (two_diff_low_part pz oz Bpz Boz) as [Xpz [Lpz _]]. destruct (two_diff_low_part qx ox Bqx Box) as [Xqx [Lqx _]].
  destruct (two_diff_low_part qy oy Bqy Boy) as [Xqy [Lqy _]]. destruct (two_diff_low_part qz oz Bqz Boz) as [Xqz [Lqz _]].
  unfold pi_stage2, edge_value, dot, cross, sub. cbn [vx vy vz].
  replace (dx * ((py - oy) * (qz - oz) - (pz - oz) * (qy - oy)) + dy * ((pz - oz) * (qx - ox) - (px - ox) * (qz - oz)) +
           dz * ((px - ox) * (qy - oy) - (py - oy) * (qx - ox)))
    with (det3_exact (dx + 0) (dy + 0) (dz + 0)
            (RN (px - ox) + snd (two_diff px ox)) (RN (py - oy) + snd (two_diff py oy))
            (RN (pz - oz) + snd (two_diff pz oz))
            (RN (qx - ox) + snd (two_diff qx ox)) (RN (qy - oy) + snd (two_diff qy oy))
            (RN (qz - oz) + snd (two_diff qz oz)))
    by (rewrite Xpx, Xpy, Xpz, Xqx, Xqy, Xqz; unfold det3_exact; ring).
  apply cdet3_capprox; try apply binary64_RN; try apply zero_low; assumption.
Qed.

Lemma num_capprox : forall o a b c, doubles3 o -> doubles3 a -> doubles3 b -> doubles3 c ->
  capprox (num_stage2 o a b c) (num_value o a b c) cdet3_alpha
    ((Rabs (vx (rsub a o)) + Rabs (vy (rsub a o)) + Rabs (vz (rsub a o))) * (83 / 10 * eta) + 16 * eta) cdet3_lam
    ((Rabs (vx (rsub a o)) + Rabs (vy (rsub a o)) + Rabs (vz (rsub a o))) * (17 * eta) + 19 * eta).
Proof.
  intros [ox oy oz] [ax ay az] [bx by_ bz] [cx cy cz] [Box [Boy Boz]] [Bax [Bay Baz]] [Bbx [Bby Bbz]] [Bcx [Bcy Bcz]].
  cbn [vx vy vz] in *.
  destruct (two_diff_low_part ax ox Bax Box) as [Xax [Lax _]]. destruct (two_diff_low_part ay oy Bay Boy) as [Xay [Lay _]].
  destruct (two_diff_low_part az oz Baz Boz) as [Xaz [Laz _]]. destruct (two_diff_low_part bx ox Bbx Box) as [Xbx [Lbx _]].
  destruct (two_diff_low_part by_ oy Bby Boy) as [Xby [Lby _]]. destruct (two_diff_low_part bz oz Bbz Boz) as [Xbz [Lbz _]].
  destruct (two_diff_low_part cx ox Bcx Box) as [Xcx [Lcx _]]. destruct (two_diff_low_part cy oy Bcy Boy) as [Xcy [Lcy _]].
  destruct (two_diff_low_part cz oz Bcz Boz) as [Xcz [Lcz _]].
  unfold num_stage2, num_value, rsub, dot, cross, sub. cbn [vx vy vz].
  replace ((ax - ox) * ((by_ - oy) * (cz - oz) - (bz - oz) * (cy - oy)) +
           (ay - oy) * ((bz - oz) * (cx - ox) - (bx - ox) * (cz - oz)) +
           (az - oz) * ((bx - ox) * (cy - oy) - (by_ - oy) * (cx - ox)))
    with (det3_exact (RN (ax - ox) + snd (two_diff ax ox)) (RN (ay - oy) + snd (two_diff ay oy))
            (RN (az - oz) + snd (two_diff az oz))
            (RN (bx - ox) + snd (two_diff bx ox)) (RN (by_ - oy) + snd (two_diff by_ oy))
            (RN (bz - oz) + snd (two_diff bz oz))
            (RN (cx - ox) + snd (two_diff cx ox)) (RN (cy - oy) + snd (two_diff cy oy))
            (RN (cz - oz) + snd (two_diff cz oz)))
    by (rewrite Xax, Xay, Xaz, Xbx, Xby, Xbz, Xcx, Xcy, Xcz; unfold det3_exact; ring).
  apply cdet3_capprox; try apply binary64_RN; assumption.
Qed.

(** ** Main theorems. *)

Theorem pi_compensated_encloses : forall o d p q, doubles3 o -> doubles3 d -> doubles3 p -> doubles3 q ->
  encloses (det3_enclosure (pi_stage2 o d p q) triangle_compensated_relative (absolute_v d)) (edge_value o d p q).
Proof.
  intros o d p q Bo Bd Bp Bq. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  pose proof Bd as [Bdx [Bdy Bdz]].
  destruct (absolute_term_lower (vx d) (vy d) (vz d) Bdx Bdy Bdz) as [BA HA]. fold (absolute_v d) in BA, HA.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  pose proof (Rabs_pos (vx d)). pose proof (Rabs_pos (vy d)). pose proof (Rabs_pos (vz d)).
  eapply radius_covers; [apply pi_capprox; assumption | exact BA | | | |].
  - unfold triangle_compensated_relative. rewrite u_val. lra.
  - rewrite u_val in *. nra.
  - unfold cdet3_alpha, triangle_compensated_relative. rewrite u_val. lra.
  - rewrite u_val in *. nra.
Qed.

Theorem num_compensated_encloses : forall o a b c, doubles3 o -> doubles3 a -> doubles3 b -> doubles3 c ->
  encloses (det3_enclosure (num_stage2 o a b c) triangle_compensated_relative (absolute_v (rsub a o)))
           (num_value o a b c).
Proof.
  intros o a b c Bo Ba Bb Bc. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  destruct (absolute_term_lower (vx (rsub a o)) (vy (rsub a o)) (vz (rsub a o)) ltac:(apply binary64_RN)
              ltac:(apply binary64_RN) ltac:(apply binary64_RN)) as [BA HA].
  fold (absolute_v (rsub a o)) in BA, HA.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  pose proof (Rabs_pos (vx (rsub a o))). pose proof (Rabs_pos (vy (rsub a o))). pose proof (Rabs_pos (vz (rsub a o))).
  eapply radius_covers; [apply num_capprox; assumption | exact BA | | | |].
  - unfold triangle_compensated_relative. rewrite u_val. lra.
  - rewrite u_val in *. nra.
  - unfold cdet3_alpha, triangle_compensated_relative. rewrite u_val. lra.
  - rewrite u_val in *. nra.
Qed.

Theorem den_compensated_encloses : forall o d a b c, doubles3 o -> doubles3 d -> doubles3 a -> doubles3 b ->
  doubles3 c ->
  encloses (det3_enclosure (den_stage2 o d a b c) triangle_compensated_den_relative (absolute_v d)) (den_value o d a b c).
Proof.
  intros o d a b c Bo Bd Ba Bb Bc. pose proof u_pos. pose proof u_small. pose proof eta_pos.
  pose proof Bd as [Bdx [Bdy Bdz]].
  destruct (absolute_term_lower (vx d) (vy d) (vz d) Bdx Bdy Bdz) as [BA HA]. fold (absolute_v d) in BA, HA.
  rewrite triangle_absolute_scale_eta, triangle_absolute_eta in HA.
  set (S := Rabs (vx d) + Rabs (vy d) + Rabs (vz d)) in *.
  assert (PS : 0 <= S) by (unfold S; pose proof (Rabs_pos (vx d)); pose proof (Rabs_pos (vy d));
                           pose proof (Rabs_pos (vz d)); lra).
  assert (PSe : 0 <= S * eta) by nra.
  assert (Pk : 0 <= S * (17 * eta) + 19 * eta) by nra.
  assert (Pa : 0 <= cdet3_alpha) by (unfold cdet3_alpha; nra).
  assert (Pl : 0 <= cdet3_lam) by (unfold cdet3_lam; nra).
  pose proof (cterm_add_capprox _ _ _ _ _ _ _ _ _ _ (pi_capprox o d b c Bo Bd Bb Bc) (pi_capprox o d c a Bo Bd Bc Ba)
                Pa Pl Pk Pk) as S01.
  fold S in S01.
  set (a01 := (cdet3_alpha + u * u + (u * (1 + u) + u) * cdet3_lam) * (1 + u)) in S01.
  set (l01 := (1 + u) * ((1 + u) * cdet3_lam + u) * (1 + u)) in S01.
  assert (P2 : capprox (pi_stage2 o d a b) (edge_value o d a b) a01 (S * (83 / 10 * eta) + 16 * eta) l01
                       (S * (17 * eta) + 19 * eta)).
  { eapply capprox_weaken; [apply pi_capprox; assumption | | unfold S; lra | | unfold S; lra];
      unfold a01, l01, cdet3_alpha, cdet3_lam; rewrite u_val; lra. }
  assert (Pk01 : 0 <= (1 + u) * (1 + u) * (S * (17 * eta) + 19 * eta + (S * (17 * eta) + 19 * eta))) by nra.
  pose proof (cterm_add_capprox _ _ _ _ _ _ _ _ _ _ S01 P2
                ltac:(unfold a01, cdet3_alpha, cdet3_lam; rewrite u_val; lra)
                ltac:(unfold l01, cdet3_lam; rewrite u_val; lra) Pk01 Pk) as Sum.
  unfold den_stage2, den_value.
  eapply radius_covers; [exact Sum | exact BA | | | |].
  - unfold triangle_compensated_den_relative. rewrite u_val. lra.
  - rewrite u_val in *. nra.
  - unfold a01, l01, cdet3_alpha, cdet3_lam, triangle_compensated_den_relative. rewrite u_val. lra.
  - rewrite u_val in *. lra.
Qed.

(** The fast path takes stage 1's signs from stage 2's high parts and magnitudes (filter_view): they are
    stage 1's values. *)
Lemma cterm_add_view : forall a b fa fb, ch a = fv fa -> cm a = fm fa -> ch b = fv fb -> cm b = fm fb ->
  ch (cterm_add a b) = fv (term_add fa fb) /\ cm (cterm_add a b) = fm (term_add fa fb).
Proof.
  intros a b fa fb Ha Ma Hb Mb. unfold cterm_add, term_add. cbn [ch cm fv fm]. rewrite two_sum_hi.
  rewrite Ha, Ma, Hb, Mb. split; reflexivity.
Qed.

Theorem stage2_filter_view : forall o d a b c,
  (forall p q, ch (pi_stage2 o d p q) = fv (pi_stage1 o d p q) /\ cm (pi_stage2 o d p q) = fm (pi_stage1 o d p q)) /\
  (ch (num_stage2 o a b c) = fv (num_stage1 o a b c) /\ cm (num_stage2 o a b c) = fm (num_stage1 o a b c)) /\
  (ch (den_stage2 o d a b c) = fv (den_stage1 o d a b c) /\ cm (den_stage2 o d a b c) = fm (den_stage1 o d a b c)).
Proof.
  intros. assert (Pi : forall p q, ch (pi_stage2 o d p q) = fv (pi_stage1 o d p q) /\
                                   cm (pi_stage2 o d p q) = fm (pi_stage1 o d p q)).
  { intros. unfold pi_stage2, pi_stage1, det3v, rsub. cbn [vx vy vz]. apply compensated_filter_view. }
  split; [exact Pi | split].
  - unfold num_stage2, num_stage1, det3v, rsub. cbn [vx vy vz]. apply compensated_filter_view.
  - unfold den_stage2, den_stage1.
    destruct (Pi b c) as [H1 M1]. destruct (Pi c a) as [H2 M2]. destruct (Pi a b) as [H3 M3].
    destruct (cterm_add_view _ _ _ _ H1 M1 H2 M2) as [H12 M12].
    apply cterm_add_view; assumption.
Qed.
