(** * The orientation filters of the point-in-mesh query (kernel/src/orient/orient_predicates.hpp,
    [orient2d_filter], [orient3d_filter]), over the model of Model.v.

    - [orient2d_filter_sound]: for doubles p_i, p_j, q_i, q_j, r_i, r_j, a sign +1 or −1 the filter returns is the
      sign of orient2d(p, q, r) = (p_i − r_i)(q_j − r_j) − (p_j − r_j)(q_i − r_i), exactly.  Valid for every
      double (the model has no overflow; OrientTwins.v shows that an overflow makes the C++ answer 0).
    - [orient3d_filter_sound]: for doubles o, a, b, c, a sign +1 or −1 the filter returns is the sign of
      det(a − o, b − o, c − o), exactly.  The C++ answers 0 unless every rounded difference is 0 or of magnitude
      in [2^-300, 2^300]; in that range every product of two differences is 0 or at least 2^-600, a difference
      of two such products 0 or at least 2^-652 (both are multiples of 2^-652: [ranged_minus]), and every
      product the filter rounds 0 or at least 2^-952: no rounding underflows, each has a relative error u
      only ([RN_rel_ranged]).

    The C++ returns an int, (det > bound) − (det < −bound): [filter_decision].  Both filters use the
    constants of Constants.v ([orient2d_filter_relative] = 2^-51 = 4u, [orient2d_filter_absolute] = 2^-1071 =
    16η, [orient3d_filter_relative] = 2^-49 = 16u, the range [2^-300, 2^300]); none was changed.  The bounds
    proved: |(L − R) − orient2d| ≤ (3u + 9u²)(|L| + |R|) + 4η ([orient2d_error]), covered by the computed
    bound over 1 + u; |D − det| ≤ (8u + 64u²)·Σ|z_k|(|a_k| + |b_k|) ([orient3d_error]), covered by
    16u(1 − u)^5 times the same sum. *)

From Coq Require Import Reals Lra Lia ZArith Bool List.
From Flocq Require Import Core Relative.
From Raykernel.Core Require Import Constants Model.
Open Scope R_scope.
Import ListNotations.

(** ** The C++ decision: (det > bound) − (det < −bound). *)

Definition filter_decision (det bound : R) : Z :=
  ((if Rlt_bool bound det then 1 else 0) - (if Rlt_bool det (- bound) then 1 else 0))%Z.

Lemma filter_decision_sound : forall det bound V,
  (bound < det -> 0 < V) -> (det < - bound -> V < 0) ->
  (filter_decision det bound = 1%Z -> 0 < V) /\ (filter_decision det bound = (-1)%Z -> V < 0).
Proof.
  intros det bound V Hp Hn. unfold filter_decision.
  destruct (Rlt_bool_spec bound det) as [A|A]; destruct (Rlt_bool_spec det (- bound)) as [B|B];
    split; intros E; try discriminate; auto.
Qed.

Lemma filter_decision_range : forall det bound,
  filter_decision det bound = 1%Z \/ filter_decision det bound = (-1)%Z \/ filter_decision det bound = 0%Z.
Proof.
  intros det bound. unfold filter_decision.
  destruct (Rlt_bool bound det); destruct (Rlt_bool det (- bound)); simpl; auto.
Qed.

(** ** Rounding a product of two rounded differences. *)

Lemma u_le : u <= / 9007199254740992.
Proof. rewrite u_val. lra. Qed.

(** x, y within u of X, Y (relative), r within u|r| + e0 of x·y: r is within (3u + 9u²)|r| + 2·e0 of X·Y. *)
Lemma prod_close : forall X Y x y r e0,
  Rabs (x - X) <= u * Rabs X -> Rabs (y - Y) <= u * Rabs Y ->
  Rabs (r - x * y) <= u * Rabs r + e0 -> 0 <= e0 ->
  Rabs (r - X * Y) <= (3 * u + 9 * (u * u)) * Rabs r + 2 * e0.
Proof.
  intros X Y x y r e0 Hx Hy Hr He0. pose proof u_pos as Up. pose proof u_le as Ul.
  pose proof (Rabs_pos X) as PX. pose proof (Rabs_pos Y) as PY.
  assert (Ay : Rabs y <= (1 + u) * Rabs Y) by (apply Rabs_close in Hy; lra).
  assert (Bx : (1 - u) * Rabs X <= Rabs x) by (apply Rabs_close' in Hx; lra).
  assert (By : (1 - u) * Rabs Y <= Rabs y) by (apply Rabs_close' in Hy; lra).
  assert (H1 : Rabs (x * y - X * Y) <= (2 * u + u * u) * (Rabs X * Rabs Y)).
  { replace (x * y - X * Y) with ((x - X) * y + X * (y - Y)) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite !Rabs_mult.
    assert (Rabs (x - X) * Rabs y <= (u * Rabs X) * ((1 + u) * Rabs Y)).
    { apply Rmult_le_compat; try apply Rabs_pos; assumption. }
    assert (Rabs X * Rabs (y - Y) <= Rabs X * (u * Rabs Y)).
    { apply Rmult_le_compat_l; assumption. }
    nra. }
  assert (H2 : ((1 - u) * Rabs X) * ((1 - u) * Rabs Y) <= Rabs (x * y)).
  { rewrite Rabs_mult. apply Rmult_le_compat; try assumption; nra. }
  assert (H3 : Rabs (x * y) <= (1 + u) * Rabs r + e0) by (apply Rabs_close' in Hr; lra).
  set (P := Rabs X * Rabs Y) in *. assert (PP : 0 <= P) by (unfold P; nra).
  replace (((1 - u) * Rabs X) * ((1 - u) * Rabs Y)) with ((1 - u) * (1 - u) * P) in H2 by (unfold P; ring).
  replace (r - X * Y) with ((r - x * y) + (x * y - X * Y)) by ring.
  eapply Rle_trans; [apply Rabs_triang|].
  pose proof (Rabs_pos r). clearbody P. rewrite u_val in *. lra.
Qed.

(** ** orient2d_filter *)

Definition orient2d_exact (pi pj qi qj ri rj : R) : R := (pi - ri) * (qj - rj) - (pj - rj) * (qi - ri).

(** The C++, operation by operation: x1 = p_i ⊖ r_i, y2 = q_j ⊖ r_j, y1 = p_j ⊖ r_j, x2 = q_i ⊖ r_i,
    L = x1 ⊗ y2, R = y1 ⊗ x2, D = L ⊖ R, B = (A ⊗ (|L| ⊕ |R|)) ⊕ U. *)
Definition orient2d_left (pi pj qi qj ri rj : R) : R := RN (RN (pi - ri) * RN (qj - rj)).
Definition orient2d_right (pi pj qi qj ri rj : R) : R := RN (RN (pj - rj) * RN (qi - ri)).

Definition orient2d_det (pi pj qi qj ri rj : R) : R :=
  RN (orient2d_left pi pj qi qj ri rj - orient2d_right pi pj qi qj ri rj).

Definition orient2d_bound (pi pj qi qj ri rj : R) : R :=
  RN (RN (orient2d_filter_relative *
          RN (Rabs (orient2d_left pi pj qi qj ri rj) + Rabs (orient2d_right pi pj qi qj ri rj)))
      + orient2d_filter_absolute).

Definition orient2d_filter (pi pj qi qj ri rj : R) : Z :=
  filter_decision (orient2d_det pi pj qi qj ri rj) (orient2d_bound pi pj qi qj ri rj).

Lemma orient2d_relative_u : orient2d_filter_relative = 4 * u.
Proof. unfold orient2d_filter_relative. rewrite u_val. simpl. lra. Qed.

Lemma orient2d_absolute_eta : orient2d_filter_absolute = 16 * eta.
Proof.
  unfold orient2d_filter_absolute, eta. replace (-1071)%Z with (4 + -1075)%Z by lia.
  rewrite bpow_plus. simpl. lra.
Qed.

(** The error of L − R against orient2d. *)
Theorem orient2d_error : forall pi pj qi qj ri rj,
  binary64 pi -> binary64 pj -> binary64 qi -> binary64 qj -> binary64 ri -> binary64 rj ->
  let L := orient2d_left pi pj qi qj ri rj in
  let R := orient2d_right pi pj qi qj ri rj in
  Rabs ((L - R) - orient2d_exact pi pj qi qj ri rj) <= (3 * u + 9 * (u * u)) * (Rabs L + Rabs R) + 4 * eta.
Proof.
  intros pi pj qi qj ri rj Hpi Hpj Hqi Hqj Hri Hrj L R. pose proof eta_pos.
  assert (EL : Rabs (L - (pi - ri) * (qj - rj)) <= (3 * u + 9 * (u * u)) * Rabs L + 2 * eta).
  { apply prod_close with (x := RN (pi - ri)) (y := RN (qj - rj));
      [apply RN_minus_err; assumption | apply RN_minus_err; assumption | apply RN_err_round | lra]. }
  assert (ER : Rabs (R - (pj - rj) * (qi - ri)) <= (3 * u + 9 * (u * u)) * Rabs R + 2 * eta).
  { apply prod_close with (x := RN (pj - rj)) (y := RN (qi - ri));
      [apply RN_minus_err; assumption | apply RN_minus_err; assumption | apply RN_err_round | lra]. }
  unfold orient2d_exact.
  replace (L - R - ((pi - ri) * (qj - rj) - (pj - rj) * (qi - ri)))
    with ((L - (pi - ri) * (qj - rj)) - (R - (pj - rj) * (qi - ri))) by ring.
  eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra.
Qed.

(** The computed bound from below: B ≥ (1 − u)³·4u·(|L| + |R|) + (1 − u)·15η. *)
Lemma orient2d_bound_lower : forall pi pj qi qj ri rj,
  let L := orient2d_left pi pj qi qj ri rj in
  let R := orient2d_right pi pj qi qj ri rj in
  (1 - u) * ((1 - u) * (1 - u) * (4 * u) * (Rabs L + Rabs R)) + (1 - u) * (15 * eta)
    <= orient2d_bound pi pj qi qj ri rj.
Proof.
  intros pi pj qi qj ri rj L R. unfold orient2d_bound. fold L R.
  pose proof u_pos as Up. pose proof u_le as Ul. pose proof eta_pos.
  pose proof (Rabs_pos L). pose proof (Rabs_pos R).
  set (S' := RN (Rabs L + Rabs R)).
  assert (ES : Rabs (S' - (Rabs L + Rabs R)) <= u * Rabs (Rabs L + Rabs R)).
  { apply RN_plus_err; apply binary64_abs; apply binary64_RN. }
  rewrite (Rabs_nonneg_eq (Rabs L + Rabs R)) in ES by lra.
  apply Rabs_bounds in ES.
  set (M := RN (orient2d_filter_relative * S')).
  assert (EM : Rabs (M - orient2d_filter_relative * S') <= u * Rabs (orient2d_filter_relative * S') + eta)
    by apply RN_err.
  rewrite orient2d_relative_u in EM.
  assert (PS : 0 <= S') by (unfold S'; apply RN_nonneg; lra).
  rewrite (Rabs_nonneg_eq (4 * u * S')) in EM by nra. apply Rabs_bounds in EM.
  assert (PM : 0 <= M) by (unfold M; rewrite orient2d_relative_u; apply RN_nonneg; nra).
  assert (EB : Rabs (RN (M + orient2d_filter_absolute) - (M + orient2d_filter_absolute))
               <= u * Rabs (M + orient2d_filter_absolute)).
  { apply RN_plus_err; [apply binary64_RN | unfold orient2d_filter_absolute; apply binary64_bpow; lia]. }
  rewrite orient2d_absolute_eta in EB |- *.
  rewrite (Rabs_nonneg_eq (M + 16 * eta)) in EB by lra. apply Rabs_bounds in EB.
  assert (u * S' <= u * ((1 + u) * (Rabs L + Rabs R))) by (apply Rmult_le_compat_l; lra).
  assert (u * ((1 - u) * (Rabs L + Rabs R)) <= u * S') by (apply Rmult_le_compat_l; lra).
  assert (u * (4 * u * S') <= u * (4 * u * ((1 + u) * (Rabs L + Rabs R)))) by
    (apply Rmult_le_compat_l; [lra | apply Rmult_le_compat_l; lra]).
  assert (u * (M + 16 * eta) >= 0) by nra.
  clearbody S' M. set (T := Rabs L + Rabs R) in *. clearbody T.
  rewrite u_val in *. lra.
Qed.

Theorem orient2d_filter_sound : forall pi pj qi qj ri rj,
  binary64 pi -> binary64 pj -> binary64 qi -> binary64 qj -> binary64 ri -> binary64 rj ->
  (orient2d_filter pi pj qi qj ri rj = 1%Z -> 0 < orient2d_exact pi pj qi qj ri rj) /\
  (orient2d_filter pi pj qi qj ri rj = (-1)%Z -> orient2d_exact pi pj qi qj ri rj < 0).
Proof.
  intros pi pj qi qj ri rj Hpi Hpj Hqi Hqj Hri Hrj. unfold orient2d_filter.
  pose proof (orient2d_error pi pj qi qj ri rj Hpi Hpj Hqi Hqj Hri Hrj) as Err.
  pose proof (orient2d_bound_lower pi pj qi qj ri rj) as Low.
  cbv zeta in Err, Low. unfold orient2d_det.
  set (L := orient2d_left pi pj qi qj ri rj) in *. set (R := orient2d_right pi pj qi qj ri rj) in *.
  set (B := orient2d_bound pi pj qi qj ri rj) in *. set (O := orient2d_exact pi pj qi qj ri rj) in *.
  assert (BL : binary64 L) by apply binary64_RN. assert (BR : binary64 R) by apply binary64_RN.
  pose proof (RN_minus_err L R BL BR) as ED.
  pose proof u_pos as Up. pose proof u_le as Ul. pose proof eta_pos.
  pose proof (Rabs_pos L). pose proof (Rabs_pos R).
  assert (S0 : 0 <= (1 - u) * ((1 - u) * (1 - u) * (4 * u) * (Rabs L + Rabs R))).
  { apply Rmult_le_pos; [lra|]. apply Rmult_le_pos; [|lra]. nra. }
  assert (E0 : 0 < (1 - u) * (15 * eta)) by (apply Rmult_lt_0_compat; lra).
  clearbody L R B O. apply Rabs_bounds in Err.
  apply filter_decision_sound; intros Hc.
  - assert (Pos : 0 < L - R).
    { destruct (Rle_or_lt (L - R) 0) as [N|N]; [|exact N].
      apply RN_le in N. rewrite RN_0 in N. lra. }
    rewrite (Rabs_nonneg_eq (L - R)) in ED by lra. apply Rabs_bounds in ED.
    set (T := Rabs L + Rabs R) in *. clearbody T. rewrite u_val in *. lra.
  - assert (Neg : L - R < 0).
    { destruct (Rle_or_lt 0 (L - R)) as [N|N]; [|exact N].
      apply RN_le in N. rewrite RN_0 in N. lra. }
    rewrite (Rabs_left (L - R)) in ED by lra. apply Rabs_bounds in ED.
    set (T := Rabs L + Rabs R) in *. clearbody T. rewrite u_val in *. lra.
Qed.

(** ** Rounding without underflow: values that are 0 or at least 2^k. *)

Definition ranged (k : Z) (v : R) : Prop := v = 0 \/ bpow radix2 k <= Rabs v.

Lemma ranged_mult : forall k l m x y, (m <= k + l)%Z -> ranged k x -> ranged l y -> ranged m (x * y).
Proof.
  intros k l m x y Hm [X|X] [Y|Y].
  - left. rewrite X. ring.
  - left. rewrite X. ring.
  - left. rewrite Y. ring.
  - right. rewrite Rabs_mult. apply Rle_trans with (bpow radix2 k * bpow radix2 l).
    + rewrite <- bpow_plus. apply bpow_le. exact Hm.
    + apply Rmult_le_compat; try apply bpow_ge_0; assumption.
Qed.

Lemma ranged_RN : forall k v, (-1074 <= k)%Z -> ranged k v -> ranged k (RN v).
Proof.
  intros k v Hk [Z|H].
  - left. rewrite Z. apply RN_0.
  - right. rewrite <- RN_abs. rewrite <- (RN_binary64 (bpow radix2 k)) by (apply binary64_bpow; exact Hk).
    apply RN_le. exact H.
Qed.

Lemma ranged_abs_sum : forall k a b, ranged k a -> ranged k b -> ranged k (Rabs a + Rabs b).
Proof.
  intros k a b [A|A] [B|B].
  - left. rewrite A, B, Rabs_R0. ring.
  - right. rewrite A, Rabs_R0, Rplus_0_l, Rabs_Rabsolu. exact B.
  - right. rewrite B, Rabs_R0, Rplus_0_r, Rabs_Rabsolu. exact A.
  - right. pose proof (Rabs_pos a). pose proof (Rabs_pos b).
    rewrite Rabs_nonneg_eq by lra. lra.
Qed.

Lemma ranged_abs : forall k v, ranged k v -> ranged k (Rabs v).
Proof. intros k v [Z|H]; [left; rewrite Z; apply Rabs_R0 | right; rewrite Rabs_Rabsolu; exact H]. Qed.

Lemma ranged_nonneg_sum : forall k a b, 0 <= a -> 0 <= b -> ranged k a -> ranged k b -> ranged k (a + b).
Proof.
  intros k a b Pa Pb Ra Rb. rewrite <- (Rabs_nonneg_eq a Pa), <- (Rabs_nonneg_eq b Pb).
  apply ranged_abs_sum; assumption.
Qed.

(** Above 2^-1022 (or at 0) a rounding has a relative error u only. *)
Lemma RN_rel_ranged : forall k v, (-1022 <= k)%Z -> ranged k v -> Rabs (RN v - v) <= u * Rabs v.
Proof.
  intros k v Hk [Z|H].
  - rewrite Z, RN_0. replace (0 - 0) with 0 by ring. rewrite Rabs_R0. pose proof u_pos. lra.
  - assert (H' : bpow radix2 (-1022) <= Rabs v) by (eapply Rle_trans; [apply bpow_le; exact Hk | exact H]).
    pose proof (relative_error_N_FLT radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) v H') as H1.
    rewrite half_bpow_52 in H1. exact H1.
Qed.

Lemma RN_rel_ranged_round : forall k v, (-1022 <= k)%Z -> ranged k v -> Rabs (RN v - v) <= u * Rabs (RN v).
Proof.
  intros k v Hk [Z|H].
  - rewrite Z, RN_0. replace (0 - 0) with 0 by ring. rewrite Rabs_R0. pose proof u_pos. lra.
  - assert (H' : bpow radix2 (-1022) <= Rabs v) by (eapply Rle_trans; [apply bpow_le; exact Hk | exact H]).
    pose proof (relative_error_N_FLT_round radix2 (-1074) 53 eq_refl (fun t => negb (Z.even t)) v H') as H1.
    rewrite half_bpow_52 in H1. exact H1.
Qed.

(** A double of magnitude at least 2^k (k ≥ −1022) is a multiple of 2^(k − 52). *)
Lemma binary64_grid : forall a k, binary64 a -> (-1022 <= k)%Z -> bpow radix2 k <= Rabs a ->
  exists m : Z, a = IZR m * bpow radix2 (k - 52).
Proof.
  intros a k Ha Hk Hb. unfold generic_format in Ha.
  set (e := cexp radix2 (FLT_exp (-1074) 53) a) in Ha.
  assert (He : (k - 52 <= e)%Z).
  { unfold e, cexp, FLT_exp.
    assert (M : (k + 1 <= mag radix2 a)%Z) by (apply mag_ge_bpow; replace (k + 1 - 1)%Z with k by lia; exact Hb).
    lia. }
  exists (Ztrunc (scaled_mantissa radix2 (FLT_exp (-1074) 53) a) * Zpower radix2 (e - (k - 52)))%Z.
  rewrite Ha at 1. unfold F2R. simpl Fnum. simpl Fexp.
  rewrite mult_IZR, IZR_Zpower by lia. rewrite Rmult_assoc, <- bpow_plus. f_equal. f_equal. lia.
Qed.

(** So two doubles that are each 0 or at least 2^k differ by 0 or at least 2^(k − 52). *)
Lemma ranged_minus : forall k a b, (-1022 <= k)%Z -> binary64 a -> binary64 b ->
  ranged k a -> ranged k b -> ranged (k - 52) (a - b).
Proof.
  intros k a b Hk Ba Bb Ra Rb.
  assert (G : forall x, binary64 x -> ranged k x -> exists m, x = IZR m * bpow radix2 (k - 52)).
  { intros x Bx [Z|H]; [exists 0%Z; rewrite Z; ring | now apply binary64_grid]. }
  destruct (G a Ba Ra) as [ma Ea]. destruct (G b Bb Rb) as [mb Eb].
  destruct (Z.eq_dec ma mb) as [E|N].
  - left. rewrite Ea, Eb, E. ring.
  - right. rewrite Ea, Eb.
    replace (IZR ma * bpow radix2 (k - 52) - IZR mb * bpow radix2 (k - 52))
      with (IZR (ma - mb) * bpow radix2 (k - 52)) by (rewrite minus_IZR; ring).
    rewrite Rabs_mult, (Rabs_nonneg_eq (bpow radix2 (k - 52))) by apply bpow_ge_0.
    assert (1 <= Rabs (IZR (ma - mb))) by (rewrite <- abs_IZR; apply IZR_le; lia).
    pose proof (bpow_ge_0 radix2 (k - 52)). nra.
Qed.

(** ** orient3d_filter *)

(** det(a − o, b − o, c − o) in Shewchuk's order: Σ z·(x1·y1 − x2·y2) over the three rows' z. *)
Definition orient3d_exact (o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 : R) : R :=
  let adx := a0 - o0 in let ady := a1 - o1 in let adz := a2 - o2 in
  let bdx := b0 - o0 in let bdy := b1 - o1 in let bdz := b2 - o2 in
  let cdx := c0 - o0 in let cdy := c1 - o1 in let cdz := c2 - o2 in
  adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady).

Lemma orient3d_exact_det : forall o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2,
  let adx := a0 - o0 in let ady := a1 - o1 in let adz := a2 - o2 in
  let bdx := b0 - o0 in let bdy := b1 - o1 in let bdz := b2 - o2 in
  let cdx := c0 - o0 in let cdy := c1 - o1 in let cdz := c2 - o2 in
  orient3d_exact o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 =
    adx * (bdy * cdz - bdz * cdy) - ady * (bdx * cdz - bdz * cdx) + adz * (bdx * cdy - bdy * cdx).
Proof. intros. unfold orient3d_exact. subst adx ady adz bdx bdy bdz cdx cdy cdz. ring. Qed.

(** One of the three terms, z ⊗ ((x1 ⊗ y1) ⊖ (x2 ⊗ y2)), and its part of the permanent,
    (|x1 ⊗ y1| ⊕ |x2 ⊗ y2|) ⊗ |z|. *)
Definition o3_term (z x1 y1 x2 y2 : R) : R := RN (z * RN (RN (x1 * y1) - RN (x2 * y2))).
Definition o3_perm (z x1 y1 x2 y2 : R) : R := RN (RN (Rabs (RN (x1 * y1)) + Rabs (RN (x2 * y2))) * Rabs z).

(** The range test of the C++: |v| == 0 || (|v| >= 2^-300 && |v| <= 2^300). *)
Definition in_difference_range (v : R) : bool :=
  Req_bool (Rabs v) 0 ||
  (Rle_bool orient3d_filter_min_difference (Rabs v) && Rle_bool (Rabs v) orient3d_filter_max_difference).

Record Orient3dValues := { o3_in_range : bool; o3_det : R; o3_bound : R }.

Definition orient3d_values (o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 : R) : Orient3dValues :=
  let adx := RN (a0 - o0) in let ady := RN (a1 - o1) in let adz := RN (a2 - o2) in
  let bdx := RN (b0 - o0) in let bdy := RN (b1 - o1) in let bdz := RN (b2 - o2) in
  let cdx := RN (c0 - o0) in let cdy := RN (c1 - o1) in let cdz := RN (c2 - o2) in
  let t1 := o3_term adz bdx cdy cdx bdy in let p1 := o3_perm adz bdx cdy cdx bdy in
  let t2 := o3_term bdz cdx ady adx cdy in let p2 := o3_perm bdz cdx ady adx cdy in
  let t3 := o3_term cdz adx bdy bdx ady in let p3 := o3_perm cdz adx bdy bdx ady in
  {| o3_in_range := forallb in_difference_range [adx; ady; adz; bdx; bdy; bdz; cdx; cdy; cdz];
     o3_det := RN (RN (t1 + t2) + t3);
     o3_bound := RN (orient3d_filter_relative * RN (RN (p1 + p2) + p3)) |}.

Definition orient3d_filter (o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 : R) : Z :=
  let v := orient3d_values o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 in
  if o3_in_range v then filter_decision (o3_det v) (o3_bound v) else 0%Z.

Lemma in_difference_range_ranged : forall v, in_difference_range v = true -> ranged (-300) v.
Proof.
  intros v H. unfold in_difference_range in H. apply orb_prop in H. destruct H as [H|H].
  - left. apply Req_bool_true_iff in H. destruct (Req_dec v 0) as [Z|Z]; [exact Z|].
    apply Rabs_no_R0 in Z. contradiction.
  - right. apply andb_prop in H. destruct H as [H _].
    destruct (Rle_bool_spec orient3d_filter_min_difference (Rabs v)) as [L|L]; [exact L | discriminate].
Qed.

Lemma orient3d_relative_u : orient3d_filter_relative = 16 * u.
Proof. unfold orient3d_filter_relative. rewrite u_val. simpl. lra. Qed.

Lemma o3_term_error : forall Z X1 Y1 X2 Y2 z x1 y1 x2 y2,
  binary64 z -> binary64 x1 -> binary64 y1 -> binary64 x2 -> binary64 y2 ->
  ranged (-300) z -> ranged (-300) x1 -> ranged (-300) y1 -> ranged (-300) x2 -> ranged (-300) y2 ->
  Rabs (z - Z) <= u * Rabs Z -> Rabs (x1 - X1) <= u * Rabs X1 -> Rabs (y1 - Y1) <= u * Rabs Y1 ->
  Rabs (x2 - X2) <= u * Rabs X2 -> Rabs (y2 - Y2) <= u * Rabs Y2 ->
  let Q := Rabs z * (Rabs (RN (x1 * y1)) + Rabs (RN (x2 * y2))) in
  Rabs (o3_term z x1 y1 x2 y2 - Z * (X1 * Y1 - X2 * Y2)) <= 8 * u * Q /\
  Rabs (o3_term z x1 y1 x2 y2) <= (1 + 3 * u) * Q /\
  (1 - 3 * u) * Q <= o3_perm z x1 y1 x2 y2 /\ 0 <= o3_perm z x1 y1 x2 y2 /\
  ranged (-900) (o3_perm z x1 y1 x2 y2) /\
  o3_perm z x1 y1 x2 y2 <= (1 + 3 * u) * Q /\
  Q <= (1 + 6 * u) * (Rabs Z * (Rabs (X1 * Y1) + Rabs (X2 * Y2))).
Proof.
  intros Z X1 Y1 X2 Y2 z x1 y1 x2 y2 Bz Bx1 By1 Bx2 By2 Rz Rx1 Ry1 Rx2 Ry2 Ez Ex1 Ey1 Ex2 Ey2 Q.
  unfold o3_term, o3_perm in *.
  assert (Rp1 : ranged (-600) (x1 * y1)) by (eapply ranged_mult; [|exact Rx1 | exact Ry1]; lia).
  assert (Rp2 : ranged (-600) (x2 * y2)) by (eapply ranged_mult; [|exact Rx2 | exact Ry2]; lia).
  pose proof (RN_rel_ranged_round (-600) (x1 * y1) ltac:(lia) Rp1) as Ra0.
  pose proof (RN_rel_ranged_round (-600) (x2 * y2) ltac:(lia) Rp2) as Rb0.
  set (a := RN (x1 * y1)) in *. set (b := RN (x2 * y2)) in *.
  assert (Ra : ranged (-600) a) by (apply ranged_RN; [lia | exact Rp1]).
  assert (Rb : ranged (-600) b) by (apply ranged_RN; [lia | exact Rp2]).
  assert (Ea : Rabs (a - X1 * Y1) <= (3 * u + 9 * (u * u)) * Rabs a + 2 * 0).
  { apply prod_close with (x := x1) (y := y1); try assumption; lra. }
  assert (Eb : Rabs (b - X2 * Y2) <= (3 * u + 9 * (u * u)) * Rabs b + 2 * 0).
  { apply prod_close with (x := x2) (y := y2); try assumption; lra. }
  assert (Ba : binary64 a) by apply binary64_RN. assert (Bb : binary64 b) by apply binary64_RN.
  (* the inner difference e = a ⊖ b: relative error, and 0 or at least 2^-652 *)
  pose proof (RN_minus_err a b Ba Bb) as Ee.
  assert (Re : ranged (-652) (RN (a - b))) by (apply ranged_RN; [lia | apply (ranged_minus (-600)); auto; lia]).
  set (e := RN (a - b)) in *.
  set (s := Rabs a + Rabs b) in *.
  assert (Dab : Rabs (a - b) <= s).
  { unfold s, Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  (* the outer product t = z ⊗ e *)
  assert (Rze : ranged (-952) (z * e)) by (eapply ranged_mult; [|exact Rz | exact Re]; lia).
  pose proof (RN_rel_ranged (-952) (z * e) ltac:(lia) Rze) as Et.
  (* the permanent's term p = (|a| ⊕ |b|) ⊗ |z| *)
  assert (Es : Rabs (RN s - s) <= u * Rabs s) by (apply RN_plus_err; apply binary64_abs; assumption).
  assert (Rs : ranged (-600) (RN s)) by (apply ranged_RN; [lia | apply ranged_abs_sum; assumption]).
  assert (Rsz : ranged (-900) (RN s * Rabs z)).
  { eapply ranged_mult; [| exact Rs | apply ranged_abs; exact Rz]. lia. }
  pose proof (RN_rel_ranged (-900) (RN s * Rabs z) ltac:(lia) Rsz) as Ep.
  pose proof u_pos as Up. pose proof u_le as Ul.
  pose proof (Rabs_pos a). pose proof (Rabs_pos b). pose proof (Rabs_pos z).
  assert (Ps : 0 <= s) by (unfold s; lra).
  rewrite (Rabs_nonneg_eq s Ps) in Es.
  assert (PRs : 0 <= RN s) by (apply RN_nonneg; exact Ps).
  assert (Ppz : 0 <= RN s * Rabs z) by (apply Rmult_le_pos; assumption).
  rewrite (Rabs_nonneg_eq _ Ppz) in Ep.
  set (W := X1 * Y1 - X2 * Y2) in *.
  assert (F1 : Rabs (e - W) <= Rabs (e - (a - b)) + Rabs (a - X1 * Y1) + Rabs (b - X2 * Y2)).
  { replace (e - W) with ((e - (a - b)) + (a - X1 * Y1) - (b - X2 * Y2)) by (unfold W; ring).
    unfold Rminus at 1. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
    pose proof (Rabs_triang (e - (a - b)) (a - X1 * Y1)). lra. }
  assert (Fe : Rabs e <= Rabs (a - b) + Rabs (e - (a - b))) by (apply Rabs_close; lra).
  assert (FW : Rabs W <= Rabs e + Rabs (e - W)) by (apply Rabs_close; rewrite Rabs_minus_sym; lra).
  assert (FZ : Rabs Z <= Rabs z + Rabs (z - Z)) by (apply Rabs_close; rewrite Rabs_minus_sym; lra).
  assert (Sdef : s = Rabs a + Rabs b) by reflexivity.
  (* numeric u from here on *)
  assert (Ke : Rabs (e - W) <= (4 * u + 9 * (u * u)) * s) by (rewrite u_val in *; lra).
  assert (Ke' : Rabs e <= (1 + u) * s) by (rewrite u_val in *; lra).
  assert (KW : Rabs W <= (1 + 5 * u + 9 * (u * u)) * s) by (rewrite u_val in *; lra).
  assert (Kz : Rabs (z - Z) <= 2 * u * Rabs z) by (rewrite u_val in *; lra).
  assert (G1 : Rabs z * Rabs (e - W) <= Rabs z * ((4 * u + 9 * (u * u)) * s)) by (apply Rmult_le_compat_l; assumption).
  assert (G2 : Rabs (z - Z) * Rabs W <= (2 * u * Rabs z) * ((1 + 5 * u + 9 * (u * u)) * s))
    by (apply Rmult_le_compat; try apply Rabs_pos; assumption).
  assert (G3 : Rabs z * Rabs e <= Rabs z * ((1 + u) * s)) by (apply Rmult_le_compat_l; assumption).
  assert (G4 : ((1 - u) * s) * Rabs z <= RN s * Rabs z) by (apply Rmult_le_compat_r; [assumption | apply Rabs_bounds in Es; lra]).
  assert (PQ : 0 <= Q) by (unfold Q; apply Rmult_le_pos; assumption).
  rewrite Rabs_mult in Et.
  assert (T : Rabs (RN (z * e) - Z * W) <= Rabs (RN (z * e) - z * e) + Rabs z * Rabs (e - W) + Rabs (z - Z) * Rabs W).
  { replace (RN (z * e) - Z * W) with ((RN (z * e) - z * e) + z * (e - W) + (z - Z) * W) by ring.
    rewrite <- !Rabs_mult. pose proof (Rabs_triang (RN (z * e) - z * e + z * (e - W)) ((z - Z) * W)).
    pose proof (Rabs_triang (RN (z * e) - z * e) (z * (e - W))). lra. }
  assert (Tz : Rabs (RN (z * e)) <= Rabs z * Rabs e + Rabs (RN (z * e) - z * e)) by (rewrite <- Rabs_mult; apply Rabs_close; lra).
  apply Rabs_bounds in Ep.
  assert (G5 : RN s * Rabs z <= ((1 + u) * s) * Rabs z) by (apply Rmult_le_compat_r; [assumption | apply Rabs_bounds in Es; lra]).
  (* the computed Q against the exact one *)
  assert (Ca : Rabs a <= Rabs (X1 * Y1) + Rabs (a - X1 * Y1)) by (apply Rabs_close; lra).
  assert (Cb : Rabs b <= Rabs (X2 * Y2) + Rabs (b - X2 * Y2)) by (apply Rabs_close; lra).
  assert (Cz : Rabs z <= Rabs Z + Rabs (z - Z)) by (apply Rabs_close; lra).
  assert (Ks : s <= (1 + 4 * u) * (Rabs (X1 * Y1) + Rabs (X2 * Y2))) by (rewrite u_val in *; lra).
  assert (Kz' : Rabs z <= (1 + u) * Rabs Z) by lra.
  assert (G6 : Rabs z * s <= ((1 + u) * Rabs Z) * ((1 + 4 * u) * (Rabs (X1 * Y1) + Rabs (X2 * Y2))))
    by (apply Rmult_le_compat; try assumption; apply Rabs_pos).
  assert (PZ : 0 <= Rabs Z * (Rabs (X1 * Y1) + Rabs (X2 * Y2)))
    by (apply Rmult_le_pos; [apply Rabs_pos | pose proof (Rabs_pos (X1 * Y1)); pose proof (Rabs_pos (X2 * Y2)); lra]).
  unfold Q. fold s. clearbody a b e s W. split; [|split; [|split; [|split; [|split; [|split]]]]].
  - rewrite u_val in *. lra.
  - rewrite u_val in *. lra.
  - rewrite u_val in *. lra.
  - apply RN_nonneg. exact Ppz.
  - apply ranged_RN; [lia | exact Rsz].
  - rewrite u_val in *. lra.
  - rewrite u_val in *. lra.
Qed.

Lemma RN_minus_rel : forall a b, binary64 a -> binary64 b -> Rabs (RN (a - b) - (a - b)) <= u * Rabs (a - b).
Proof. exact RN_minus_err. Qed.

(** The exact permanent of Shewchuk's evaluation order: Σ|Z_k|·(|X_k·Y_k| + |X'_k·Y'_k|). *)
Definition orient3d_permanent (o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 : R) : R :=
  let adx := a0 - o0 in let ady := a1 - o1 in let adz := a2 - o2 in
  let bdx := b0 - o0 in let bdy := b1 - o1 in let bdz := b2 - o2 in
  let cdx := c0 - o0 in let cdy := c1 - o1 in let cdz := c2 - o2 in
  Rabs adz * (Rabs (bdx * cdy) + Rabs (cdx * bdy)) + Rabs bdz * (Rabs (cdx * ady) + Rabs (adx * cdy)) +
  Rabs cdz * (Rabs (adx * bdy) + Rabs (bdx * ady)).

(** In range, with Q = Σ_k |z_k|·(|x1 ⊗ y1| + |x2 ⊗ y2|) over the computed values: |D − det| ≤ 11u·Q, and
    12u·Q ≤ bound ≤ 17u·Q, and Q ≤ (1 + 6u) times the exact permanent. *)
Theorem orient3d_error_bounds : forall o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 a0 -> binary64 a1 -> binary64 a2 ->
  binary64 b0 -> binary64 b1 -> binary64 b2 -> binary64 c0 -> binary64 c1 -> binary64 c2 ->
  let v := orient3d_values o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 in
  o3_in_range v = true ->
  exists Q, 0 <= Q /\
    Rabs (o3_det v - orient3d_exact o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2) <= 11 * u * Q /\
    12 * u * Q <= o3_bound v /\ o3_bound v <= 17 * u * Q /\
    Q <= (1 + 6 * u) * orient3d_permanent o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2.
Proof.
  intros o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 Bo0 Bo1 Bo2 Ba0 Ba1 Ba2 Bb0 Bb1 Bb2 Bc0 Bc1 Bc2 v IR.
  unfold v, orient3d_values in IR |- *. cbn [o3_in_range o3_det o3_bound] in IR |- *.
  unfold forallb in IR.
  repeat match goal with H : (_ && _)%bool = true |- _ => apply andb_prop in H; destruct H end.
  repeat match goal with H : in_difference_range _ = true |- _ => apply in_difference_range_ranged in H end.
  pose proof (RN_minus_rel a0 o0 Ba0 Bo0). pose proof (RN_minus_rel a1 o1 Ba1 Bo1).
  pose proof (RN_minus_rel a2 o2 Ba2 Bo2). pose proof (RN_minus_rel b0 o0 Bb0 Bo0).
  pose proof (RN_minus_rel b1 o1 Bb1 Bo1). pose proof (RN_minus_rel b2 o2 Bb2 Bo2).
  pose proof (RN_minus_rel c0 o0 Bc0 Bo0). pose proof (RN_minus_rel c1 o1 Bc1 Bo1).
  pose proof (RN_minus_rel c2 o2 Bc2 Bo2).
  unfold orient3d_exact.
  set (adx := RN (a0 - o0)) in *. set (ady := RN (a1 - o1)) in *. set (adz := RN (a2 - o2)) in *.
  set (bdx := RN (b0 - o0)) in *. set (bdy := RN (b1 - o1)) in *. set (bdz := RN (b2 - o2)) in *.
  set (cdx := RN (c0 - o0)) in *. set (cdy := RN (c1 - o1)) in *. set (cdz := RN (c2 - o2)) in *.
  assert (D1 := o3_term_error (a2 - o2) (b0 - o0) (c1 - o1) (c0 - o0) (b1 - o1) adz bdx cdy cdx bdy
    ltac:(apply binary64_RN) ltac:(apply binary64_RN) ltac:(apply binary64_RN) ltac:(apply binary64_RN)
    ltac:(apply binary64_RN) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)
    ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)).
  assert (D2 := o3_term_error (b2 - o2) (c0 - o0) (a1 - o1) (a0 - o0) (c1 - o1) bdz cdx ady adx cdy
    ltac:(apply binary64_RN) ltac:(apply binary64_RN) ltac:(apply binary64_RN) ltac:(apply binary64_RN)
    ltac:(apply binary64_RN) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)
    ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)).
  assert (D3 := o3_term_error (c2 - o2) (a0 - o0) (b1 - o1) (b0 - o0) (a1 - o1) cdz adx bdy bdx ady
    ltac:(apply binary64_RN) ltac:(apply binary64_RN) ltac:(apply binary64_RN) ltac:(apply binary64_RN)
    ltac:(apply binary64_RN) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)
    ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption) ltac:(assumption)).
  cbv zeta in D1, D2, D3.
  set (t1 := o3_term adz bdx cdy cdx bdy) in *. set (p1 := o3_perm adz bdx cdy cdx bdy) in *.
  set (t2 := o3_term bdz cdx ady adx cdy) in *. set (p2 := o3_perm bdz cdx ady adx cdy) in *.
  set (t3 := o3_term cdz adx bdy bdx ady) in *. set (p3 := o3_perm cdz adx bdy bdx ady) in *.
  set (Q1 := Rabs adz * (Rabs (RN (bdx * cdy)) + Rabs (RN (cdx * bdy)))) in *.
  set (Q2 := Rabs bdz * (Rabs (RN (cdx * ady)) + Rabs (RN (adx * cdy)))) in *.
  set (Q3 := Rabs cdz * (Rabs (RN (adx * bdy)) + Rabs (RN (bdx * ady)))) in *.
  destruct D1 as [E1 [A1 [L1 [P1 [R1 H1']]]]]. destruct D2 as [E2 [A2 [L2 [P2 [R2 H2']]]]].
  destruct D3 as [E3 [A3 [L3 [P3 [R3 H3']]]]].
  assert (Bt1 : binary64 t1) by apply binary64_RN. assert (Bt2 : binary64 t2) by apply binary64_RN.
  assert (Bt3 : binary64 t3) by apply binary64_RN.
  assert (Bp1 : binary64 p1) by apply binary64_RN. assert (Bp2 : binary64 p2) by apply binary64_RN.
  assert (Bp3 : binary64 p3) by apply binary64_RN.
  (* the sums *)
  pose proof (RN_plus_err t1 t2 Bt1 Bt2) as S12.
  pose proof (RN_plus_err (RN (t1 + t2)) t3 (binary64_RN _) Bt3) as S3.
  assert (St12 : Rabs (t1 + t2) <= Rabs t1 + Rabs t2) by apply Rabs_triang.
  assert (St3 : Rabs (RN (t1 + t2) + t3) <= Rabs (RN (t1 + t2)) + Rabs t3) by apply Rabs_triang.
  assert (Ct12 : Rabs (RN (t1 + t2)) <= Rabs (t1 + t2) + Rabs (RN (t1 + t2) - (t1 + t2))) by (apply Rabs_close; lra).
  (* the permanent and the bound *)
  pose proof (RN_plus_err p1 p2 Bp1 Bp2) as SP12.
  pose proof (RN_plus_err (RN (p1 + p2)) p3 (binary64_RN _) Bp3) as SP3.
  assert (PP12 : 0 <= RN (p1 + p2)) by (apply RN_nonneg; lra).
  rewrite (Rabs_nonneg_eq (p1 + p2)) in SP12 by lra.
  rewrite (Rabs_nonneg_eq (RN (p1 + p2) + p3)) in SP3 by lra.
  set (P := RN (RN (p1 + p2) + p3)) in *.
  assert (RP : ranged (-900) P).
  { apply ranged_RN; [lia|]. apply ranged_nonneg_sum; [lra | lra | | exact R3].
    apply ranged_RN; [lia|]. apply ranged_nonneg_sum; [lra | lra | exact R1 | exact R2]. }
  assert (PP : 0 <= P) by (unfold P; apply RN_nonneg; lra).
  assert (RA : ranged (-49) orient3d_filter_relative).
  { right. unfold orient3d_filter_relative. rewrite Rabs_nonneg_eq by apply bpow_ge_0. apply Rle_refl. }
  assert (RAP : ranged (-949) (orient3d_filter_relative * P)) by (eapply ranged_mult; [| exact RA | exact RP]; lia).
  pose proof (RN_rel_ranged (-949) _ ltac:(lia) RAP) as EB.
  rewrite orient3d_relative_u in EB |- *.
  rewrite (Rabs_nonneg_eq (16 * u * P)) in EB by (pose proof u_pos; nra).
  apply Rabs_bounds in EB.
  assert (PQ1 : 0 <= Q1) by (unfold Q1; apply Rmult_le_pos; [apply Rabs_pos | pose proof (Rabs_pos (RN (bdx * cdy))); pose proof (Rabs_pos (RN (cdx * bdy))); lra]).
  assert (PQ2 : 0 <= Q2) by (unfold Q2; apply Rmult_le_pos; [apply Rabs_pos | pose proof (Rabs_pos (RN (cdx * ady))); pose proof (Rabs_pos (RN (adx * cdy))); lra]).
  assert (PQ3 : 0 <= Q3) by (unfold Q3; apply Rmult_le_pos; [apply Rabs_pos | pose proof (Rabs_pos (RN (adx * bdy))); pose proof (Rabs_pos (RN (bdx * ady))); lra]).
  set (X := RN (RN (t1 + t2) + t3)) in *.
  replace (X - ((a2 - o2) * ((b0 - o0) * (c1 - o1) - (c0 - o0) * (b1 - o1)) +
                (b2 - o2) * ((c0 - o0) * (a1 - o1) - (a0 - o0) * (c1 - o1)) +
                (c2 - o2) * ((a0 - o0) * (b1 - o1) - (b0 - o0) * (a1 - o1))))
    with ((X - (RN (t1 + t2) + t3)) + (RN (t1 + t2) - (t1 + t2))
          + (t1 - (a2 - o2) * ((b0 - o0) * (c1 - o1) - (c0 - o0) * (b1 - o1)))
          + (t2 - (b2 - o2) * ((c0 - o0) * (a1 - o1) - (a0 - o0) * (c1 - o1)))
          + (t3 - (c2 - o2) * ((a0 - o0) * (b1 - o1) - (b0 - o0) * (a1 - o1)))) by ring.
  set (e0 := X - (RN (t1 + t2) + t3)) in *. set (e1 := RN (t1 + t2) - (t1 + t2)) in *.
  set (f1 := t1 - _) in *. set (f2 := t2 - _) in *. set (f3 := t3 - _) in *.
  assert (Tri : Rabs (e0 + e1 + f1 + f2 + f3) <= Rabs e0 + Rabs e1 + Rabs f1 + Rabs f2 + Rabs f3).
  { pose proof (Rabs_triang (e0 + e1 + f1 + f2) f3). pose proof (Rabs_triang (e0 + e1 + f1) f2).
    pose proof (Rabs_triang (e0 + e1) f1). pose proof (Rabs_triang e0 e1). lra. }
  apply Rabs_bounds in SP12. apply Rabs_bounds in SP3.
  exists (Q1 + Q2 + Q3). unfold orient3d_permanent.
  destruct H1' as [U1 K1]. destruct H2' as [U2 K2]. destruct H3' as [U3 K3].
  clearbody e0 e1 f1 f2 f3 t1 t2 t3 p1 p2 p3 Q1 Q2 Q3 P.
  split; [lra|]. split; [|split; [|split]]; rewrite u_val in *; lra.
Qed.

(** |D − det| ≤ A ⊗ P, in range. *)
Theorem orient3d_error : forall o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 a0 -> binary64 a1 -> binary64 a2 ->
  binary64 b0 -> binary64 b1 -> binary64 b2 -> binary64 c0 -> binary64 c1 -> binary64 c2 ->
  let v := orient3d_values o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 in
  o3_in_range v = true ->
  Rabs (o3_det v - orient3d_exact o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2) <= o3_bound v.
Proof.
  intros o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 Bo0 Bo1 Bo2 Ba0 Ba1 Ba2 Bb0 Bb1 Bb2 Bc0 Bc1 Bc2 v IR.
  destruct (orient3d_error_bounds o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 Bo0 Bo1 Bo2 Ba0 Ba1 Ba2 Bb0 Bb1 Bb2 Bc0 Bc1
              Bc2 IR) as [Q [PQ [E [L _]]]].
  fold v in E, L. pose proof u_pos. nra.
Qed.

Theorem orient3d_filter_sound : forall o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 a0 -> binary64 a1 -> binary64 a2 ->
  binary64 b0 -> binary64 b1 -> binary64 b2 -> binary64 c0 -> binary64 c1 -> binary64 c2 ->
  (orient3d_filter o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 = 1%Z ->
     0 < orient3d_exact o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2) /\
  (orient3d_filter o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 = (-1)%Z ->
     orient3d_exact o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 < 0).
Proof.
  intros o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 Bo0 Bo1 Bo2 Ba0 Ba1 Ba2 Bb0 Bb1 Bb2 Bc0 Bc1 Bc2.
  unfold orient3d_filter.
  destruct (o3_in_range (orient3d_values o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2)) eqn:IR;
    [| split; intros E; discriminate].
  pose proof (orient3d_error o0 o1 o2 a0 a1 a2 b0 b1 b2 c0 c1 c2 Bo0 Bo1 Bo2 Ba0 Ba1 Ba2 Bb0 Bb1 Bb2 Bc0 Bc1 Bc2 IR)
    as Err.
  apply Rabs_bounds in Err. apply filter_decision_sound; intros H; lra.
Qed.
