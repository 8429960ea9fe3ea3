(** * Stage 1 of the ray–sphere cascade: the binary64 filter of the signs of C and D
    (kernel/src/sphere/ray_sphere_filter.hpp; the bounds' derivation: kernel/src/core/error_bounds.hpp, ray–sphere).

    Main theorems: [sphere_filter_c_sound] (a certain sign of Ĉ against E_C is the sign of the exact
    C = (o − c)·(o − c) − r²) and [sphere_filter_d_sound] (a certain sign of D̂ against E_D is the sign of the
    exact D = B² − A·C, A = d·d, B = (o − c)·d), for every binary64 input. *)

From Coq Require Import Reals Lra Lia.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model.
From Raykernel.Plane Require Import PlaneFilter.
Open Scope R_scope.

(** ** The C++ code, operation by operation. *)

(** [sphere_filter_sign(value, bound)]: value > bound, value < −bound, else uncertain. *)
Definition filter_sign (v b : R) : sign :=
  if Rlt_bool b v then Positive else if Rlt_bool v (- b) then Negative else Uncertain.

Definition sphere_f (o c : R) : R := RN (o - c).

(** S = dot3_rounded(f, f). *)
Definition sphere_s (o0 o1 o2 c0 c1 c2 : R) : Dot3Rounded :=
  dot3_rounded (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)
               (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2).

(** Ĉ = S.value ⊖ q, q = r ⊗ r. *)
Definition sphere_c_value (o0 o1 o2 c0 c1 c2 r : R) : R :=
  RN (value (sphere_s o0 o1 o2 c0 c1 c2) - RN (r * r)).

(** E_C = (κ_C ⊗ (S.magnitude ⊕ q)) ⊕ μ_C. *)
Definition sphere_c_bound (o0 o1 o2 c0 c1 c2 r : R) : R :=
  RN (RN (sphere_filter_c_relative * RN (magnitude (sphere_s o0 o1 o2 c0 c1 c2) + RN (r * r)))
      + sphere_filter_c_absolute).

Definition sphere_filter_c (o0 o1 o2 c0 c1 c2 r : R) : sign :=
  filter_sign (sphere_c_value o0 o1 o2 c0 c1 c2 r) (sphere_c_bound o0 o1 o2 c0 c1 c2 r).

(** D̂ = (B̂ ⊗ B̂) ⊖ (Â ⊗ Ĉ). *)
Definition d_value (a b c : R) : R := RN (RN (b * b) - RN (a * c)).

(** P_C = S.magnitude ⊕ q, the magnitude E_C is computed from (and a bound on |Ĉ|: [c_value_le_magnitude]). *)
Definition sphere_c_magnitude (o0 o1 o2 c0 c1 c2 r : R) : R :=
  RN (magnitude (sphere_s o0 o1 o2 c0 c1 c2) + RN (r * r)).

(** E_D = (κ_D ⊗ ((X ⊗ X) ⊕ (Y ⊗ Z))) ⊕ μ_D with X = m_B ⊕ θ, Y = Â ⊕ θ, Z = P_C ⊕ θ (m_B: B̂'s magnitude,
    θ = sphere_filter_d_floor). *)
Definition d_bound (a mb pc : R) : R :=
  let x := RN (mb + sphere_filter_d_floor) in
  let y := RN (a + sphere_filter_d_floor) in
  let z := RN (pc + sphere_filter_d_floor) in
  RN (RN (sphere_filter_d_relative * RN (RN (x * x) + RN (y * z))) + sphere_filter_d_absolute).

(** The whole filter of D, as sphere_filter() computes it: Â = dot3_rounded(d, d).value, B̂ and m_B =
    dot3_rounded(f, d)'s value and magnitude. *)
Definition sphere_filter_d (o0 o1 o2 d0 d1 d2 c0 c1 c2 r : R) : sign :=
  let ra := dot3_rounded d0 d1 d2 d0 d1 d2 in
  let rb := dot3_rounded (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2) d0 d1 d2 in
  filter_sign (d_value (value ra) (value rb) (sphere_c_value o0 o1 o2 c0 c1 c2 r))
              (d_bound (value ra) (magnitude rb) (sphere_c_magnitude o0 o1 o2 c0 c1 c2 r)).

(** ** Soundness of the sign test from an enclosure. *)

Lemma filter_sign_sound : forall v b X, Rabs (v - X) <= b -> certifies (filter_sign v b) X.
Proof.
  intros v b X H. apply Rabs_bounds in H. unfold filter_sign.
  destruct (Rlt_bool_spec b v) as [L|L]; simpl; [lra|].
  destruct (Rlt_bool_spec v (- b)) as [L'|L']; simpl; [lra | exact I].
Qed.

(** Lower bounds of a rounding of a non-negative real. *)
Lemma RN_lower : forall x, 0 <= x -> x * (1 - u) - eta <= RN x.
Proof.
  intros x Hx. pose proof (RN_err x) as E. rewrite (Rabs_nonneg_eq x Hx) in E.
  apply Rabs_bounds in E. lra.
Qed.

Lemma RN_plus_lower : forall a b, binary64 a -> binary64 b -> 0 <= a + b -> (a + b) * (1 - u) <= RN (a + b).
Proof.
  intros a b Ha Hb H. pose proof (RN_plus_err a b Ha Hb) as E. rewrite (Rabs_nonneg_eq _ H) in E.
  apply Rabs_bounds in E. lra.
Qed.

(** ** C. *)

(** One square of a rounded difference: |f̂ ⊗ f̂ − (o − c)²| ≤ 4u|f̂ ⊗ f̂| + 2η. *)
Lemma square_term_error : forall o c, binary64 o -> binary64 c ->
  Rabs (RN (sphere_f o c * sphere_f o c) - (o - c) * (o - c)) <=
    4 * u * Rabs (RN (sphere_f o c * sphere_f o c)) + 2 * eta.
Proof.
  intros o c Bo Bc. unfold sphere_f.
  set (f := o - c). set (g := RN (o - c)). set (q := RN (g * g)).
  pose proof u_pos as Hu. pose proof eta_pos as He.
  pose proof (RN_minus_err_round o c Bo Bc) as E1. change (Rabs (g - f) <= u * Rabs g) in E1.
  pose proof (RN_err_round (g * g)) as E2. fold q in E2.
  assert (Hgg : Rabs (g * g) <= Rabs q + u * Rabs q + eta).
  { pose proof (Rabs_close' _ _ _ E2). lra. }
  rewrite Rabs_mult in Hgg.
  assert (D : Rabs (g * g - f * f) <= (2 * u + u * u) * (Rabs g * Rabs g)).
  { replace (g * g - f * f) with ((g - f) * (g + f)) by ring. rewrite Rabs_mult.
    assert (S : Rabs (g + f) <= (2 + u) * Rabs g).
    { replace (g + f) with (2 * g - (g - f)) by ring.
      eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp, Rabs_mult, (Rabs_nonneg_eq 2) by lra. lra. }
    pose proof (Rabs_pos (g - f)). pose proof (Rabs_pos (g + f)). pose proof (Rabs_pos g).
    apply Rle_trans with (u * Rabs g * ((2 + u) * Rabs g)).
    - apply Rmult_le_compat; lra.
    - nra. }
  change (Rabs (q - f * f) <= 4 * u * Rabs q + 2 * eta).
  replace (q - f * f) with ((q - g * g) + (g * g - f * f)) by ring.
  eapply Rle_trans; [apply Rabs_triang|].
  pose proof (Rabs_pos q). pose proof (Rabs_pos g).
  assert (G : (2 * u + u * u) * (Rabs g * Rabs g) <= (2 * u + u * u) * (Rabs q + u * Rabs q + eta))
    by (apply Rmult_le_compat_l; nra).
  assert (K : u + (2 * u + u * u) * (1 + u) <= 4 * u) by (rewrite u_val; lra).
  assert (K2 : (u + (2 * u + u * u) * (1 + u)) * Rabs q <= 4 * u * Rabs q) by (apply Rmult_le_compat_r; lra).
  assert (K3 : (1 + (2 * u + u * u)) * eta <= 2 * eta) by (rewrite u_val; lra).
  replace ((2 * u + u * u) * (Rabs q + u * Rabs q + eta))
    with ((u + (2 * u + u * u) * (1 + u)) * Rabs q - u * Rabs q + (1 + (2 * u + u * u)) * eta - eta) in G by ring.
  lra.
Qed.

(** |S − f·f| ≤ (6u + u²)Σ|q_i| + 6η. *)
Lemma sphere_s_error : forall o0 o1 o2 c0 c1 c2,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 c0 -> binary64 c1 -> binary64 c2 ->
  let s := sphere_s o0 o1 o2 c0 c1 c2 in
  Rabs (value s - ((o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2))) <=
    (6 * u + u * u) * (Rabs (product0 s) + Rabs (product1 s) + Rabs (product2 s)) + 6 * eta.
Proof.
  intros o0 o1 o2 c0 c1 c2 B0 B1 B2 C0 C1 C2 s.
  pose proof (square_term_error o0 c0 B0 C0) as E0. pose proof (square_term_error o1 c1 B1 C1) as E1.
  pose proof (square_term_error o2 c2 B2 C2) as E2.
  pose proof (dot3_value_error _ _ _ _ _ _ _ _ _ _ _ _ E0 E1 E2) as H.
  unfold s, sphere_s. simpl in H |- *. lra.
Qed.

Lemma binary64_sphere_filter_c_absolute : binary64 sphere_filter_c_absolute.
Proof.
  unfold sphere_filter_c_absolute, min_subnormal.
  apply generic_format_FLT. exists (Float radix2 8 (-1074)); simpl; try lia.
  unfold F2R; simpl. ring.
Qed.

Lemma binary64_sphere_filter_d_absolute : binary64 sphere_filter_d_absolute.
Proof.
  unfold sphere_filter_d_absolute, min_subnormal.
  apply generic_format_FLT. exists (Float radix2 64 (-1074)); simpl; try lia.
  unfold F2R; simpl. ring.
Qed.

(** A rounding of a non-negative real is non-negative and at least x(1 − u) − η; a rounded sum of
    non-negative doubles is at least (a + b)(1 − u).  The lower bounds of the computed bounds below are chains of
    these. *)

Lemma sphere_c_bound_nonneg : forall o0 o1 o2 c0 c1 c2 r,
  0 <= sphere_c_bound o0 o1 o2 c0 c1 c2 r.
Proof.
  intros. unfold sphere_c_bound. pose proof u_pos as Hu.
  set (S := sphere_s o0 o1 o2 c0 c1 c2).
  assert (Pm : 0 <= magnitude S) by (apply (magnitude_bound (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)
                                             (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2))).
  assert (Pq : 0 <= RN (r * r)) by (apply RN_nonneg; nra).
  assert (P1 : 0 <= RN (magnitude S + RN (r * r))) by (apply RN_nonneg; lra).
  assert (P2 : 0 <= RN (sphere_filter_c_relative * RN (magnitude S + RN (r * r)))).
  { apply RN_nonneg. apply Rmult_le_pos; [unfold sphere_filter_c_relative; lra | exact P1]. }
  apply RN_nonneg. unfold sphere_filter_c_absolute, min_subnormal. pose proof (bpow_ge_0 radix2 (-1074)). lra.
Qed.

(** |Ĉ − C| ≤ E_C for every binary64 input: with m = S.magnitude and q = r ⊗ r,
    |Ĉ − C| ≤ ((6u + u²)(1 + u)² + u)(m + q) + 7η, and E_C ≥ 8u(1 − u)³(m + q) + 15η(1 − u). *)
Theorem sphere_c_encloses : forall o0 o1 o2 c0 c1 c2 r,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r ->
  Rabs (sphere_c_value o0 o1 o2 c0 c1 c2 r -
        ((o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2) - r * r)) <=
    sphere_c_bound o0 o1 o2 c0 c1 c2 r.
Proof.
  intros o0 o1 o2 c0 c1 c2 r B0 B1 B2 C0 C1 C2 Br.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv.
  pose proof (sphere_s_error o0 o1 o2 c0 c1 c2 B0 B1 B2 C0 C1 C2) as ES. cbv zeta in ES.
  destruct (magnitude_bound (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)
                            (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)) as [Pm Qm].
  destruct (dot3_rounded_dominated (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)
                            (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)) as [_ [_ [_ [_ Dm]]]].
  unfold sphere_c_value, sphere_c_bound. fold (sphere_s o0 o1 o2 c0 c1 c2) in *.
  set (S := sphere_s o0 o1 o2 c0 c1 c2) in *.
  set (F := (o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2)) in *.
  set (Q := Rabs (product0 S) + Rabs (product1 S) + Rabs (product2 S)) in *.
  set (s := value S) in *. set (m := magnitude S) in *.
  set (q := RN (r * r)).
  assert (Bs : binary64 s) by apply binary64_RN.
  assert (Bm : binary64 m) by apply binary64_RN.
  assert (Bq : binary64 q) by apply binary64_RN.
  assert (Pq : 0 <= q) by (apply RN_nonneg; nra).
  (* the three errors *)
  assert (Eq : Rabs (q - r * r) <= u * q + eta).
  { pose proof (RN_err_round (r * r)) as H. fold q in H. rewrite (Rabs_nonneg_eq q Pq) in H. exact H. }
  assert (Ec : Rabs (RN (s - q) - (s - q)) <= u * (m + q)).
  { eapply Rle_trans; [apply RN_minus_err; assumption|].
    apply Rmult_le_compat_l; [lra|]. unfold Rminus. eapply Rle_trans; [apply Rabs_triang|].
    rewrite Rabs_Ropp, (Rabs_nonneg_eq q Pq). lra. }
  assert (EQ : (6 * u + u * u) * Q <= (6 * u + u * u) * ((1 + u) * (1 + u) * m))
    by (apply Rmult_le_compat_l; nra).
  set (K := (6 * u + u * u) * ((1 + u) * (1 + u)) + u).
  assert (Err : Rabs (RN (s - q) - (F - r * r)) <= K * (m + q) + 7 * eta).
  { replace (RN (s - q) - (F - r * r)) with ((RN (s - q) - (s - q)) + (s - F) - (q - r * r)) by ring.
    set (x := RN (s - q) - (s - q)) in *. set (y := s - F) in *. set (z := q - r * r) in *.
    assert (T3 : Rabs (x + y - z) <= Rabs x + Rabs y + Rabs z).
    { unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
      pose proof (Rabs_triang x y). lra. }
    assert (Ku : u <= (6 * u + u * u) * ((1 + u) * (1 + u))) by (rewrite Uv; lra).
    assert (Kq : u * q <= (6 * u + u * u) * ((1 + u) * (1 + u)) * q) by (apply Rmult_le_compat_r; assumption).
    unfold K. lra. }
  (* the lower bound of E_C *)
  set (P := RN (m + q)). set (T := RN (sphere_filter_c_relative * P)).
  assert (LP : (m + q) * (1 - u) <= P) by (apply RN_plus_lower; auto; lra).
  assert (Pk : 0 <= sphere_filter_c_relative) by (unfold sphere_filter_c_relative; lra).
  assert (LT : sphere_filter_c_relative * P * (1 - u) - eta <= T)
    by (apply RN_lower; apply Rmult_le_pos; [lra | apply RN_nonneg; lra]).
  assert (PT : 0 <= T) by (apply RN_nonneg; apply Rmult_le_pos; [lra | apply RN_nonneg; lra]).
  assert (Babs : binary64 sphere_filter_c_absolute) by apply binary64_sphere_filter_c_absolute.
  assert (Mu : sphere_filter_c_absolute = 16 * eta)
    by (unfold sphere_filter_c_absolute; rewrite min_subnormal_eta; ring).
  assert (LE : (T + sphere_filter_c_absolute) * (1 - u) <= RN (T + sphere_filter_c_absolute))
    by (apply RN_plus_lower; [apply binary64_RN | exact Babs | lra]).
  (* K (m + q) ≤ κ (1 − u)³ (m + q) *)
  assert (KK : K <= sphere_filter_c_relative * (1 - u) * (1 - u) * (1 - u))
    by (unfold K, sphere_filter_c_relative; rewrite Uv; lra).
  assert (Pmq : 0 <= m + q) by lra.
  assert (S1 : K * (m + q) <= sphere_filter_c_relative * (1 - u) * (1 - u) * (1 - u) * (m + q))
    by (apply Rmult_le_compat_r; assumption).
  assert (S2 : sphere_filter_c_relative * ((m + q) * (1 - u)) * (1 - u) <= sphere_filter_c_relative * P * (1 - u)).
  { apply Rmult_le_compat_r; [lra|]. apply Rmult_le_compat_l; assumption. }
  assert (S3 : (sphere_filter_c_relative * P * (1 - u) - eta + 16 * eta) * (1 - u) <=
               (T + sphere_filter_c_absolute) * (1 - u)) by (apply Rmult_le_compat_r; lra).
  assert (S4 : (sphere_filter_c_relative * ((m + q) * (1 - u)) * (1 - u) - eta + 16 * eta) * (1 - u) <=
               (sphere_filter_c_relative * P * (1 - u) - eta + 16 * eta) * (1 - u)) by (apply Rmult_le_compat_r; lra).
  assert (S5 : 7 * eta <= 15 * eta * (1 - u)) by (rewrite Uv; lra).
  assert (S6 : (sphere_filter_c_relative * ((m + q) * (1 - u)) * (1 - u) - eta + 16 * eta) * (1 - u) =
               sphere_filter_c_relative * (1 - u) * (1 - u) * (1 - u) * (m + q) + 15 * eta * (1 - u)) by ring.
  lra.
Qed.

(** The certified sign of Ĉ against E_C is the sign of the exact C = (o − c)·(o − c) − r². *)
Theorem sphere_filter_c_sound : forall o0 o1 o2 c0 c1 c2 r,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r ->
  certifies (sphere_filter_c o0 o1 o2 c0 c1 c2 r)
    ((o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2) - r * r).
Proof.
  intros. unfold sphere_filter_c. apply filter_sign_sound. now apply sphere_c_encloses.
Qed.

(** ** D. *)

(** The error of D̂ from enclosures of Â, B̂, Ĉ: with b = B̂ ⊗ B̂ and a = Â ⊗ Ĉ,
    |D̂ − D| ≤ 2u(|b| + |a|) + E_B(2|B̂| + E_B) + E_A|Ĉ| + (|Â| + E_A)E_C + 2η. *)
Lemma d_value_error : forall A B C a b c ea eb ec,
  Rabs (a - A) <= ea -> Rabs (b - B) <= eb -> Rabs (c - C) <= ec ->
  Rabs (d_value a b c - (B * B - A * C)) <=
    2 * u * (Rabs (RN (b * b)) + Rabs (RN (a * c))) + eb * (2 * Rabs b + eb) + ea * Rabs c
    + (Rabs a + ea) * ec + 2 * eta.
Proof.
  intros A B C a b c ea eb ec HA HB HC.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  unfold d_value. set (bb := RN (b * b)). set (ac := RN (a * c)).
  assert (E1 : Rabs (RN (bb - ac) - (bb - ac)) <= u * (Rabs bb + Rabs ac)).
  { eapply Rle_trans; [apply RN_minus_err; apply binary64_RN|]. apply Rmult_le_compat_l; [lra|].
    unfold Rminus. eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  pose proof (RN_err_round (b * b)) as E2. fold bb in E2.
  pose proof (RN_err_round (a * c)) as E3. fold ac in E3.
  assert (E4 : Rabs (b * b - B * B) <= eb * (2 * Rabs b + eb)).
  { replace (b * b - B * B) with ((b - B) * (b + B)) by ring. rewrite Rabs_mult.
    assert (S : Rabs (b + B) <= 2 * Rabs b + eb).
    { replace (b + B) with (2 * b + - (b - B)) by ring.
      eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp, Rabs_mult, (Rabs_nonneg_eq 2) by lra. lra. }
    apply Rmult_le_compat; [apply Rabs_pos | apply Rabs_pos | exact HB | exact S]. }
  assert (E5 : Rabs (a * c - A * C) <= ea * Rabs c + (Rabs a + ea) * ec).
  { replace (a * c - A * C) with ((a - A) * c + A * (c - C)) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite !Rabs_mult.
    assert (HA' : Rabs A <= Rabs a + ea) by (apply (Rabs_close' a A); exact HA).
    apply Rplus_le_compat.
    - apply Rmult_le_compat_r; [apply Rabs_pos | exact HA].
    - apply Rmult_le_compat; [apply Rabs_pos | apply Rabs_pos | exact HA' | exact HC]. }
  pose proof (Rabs_sum5 (RN (bb - ac) - (bb - ac)) (bb - b * b) (- (ac - a * c)) (b * b - B * B)
                        (- (a * c - A * C))) as T.
  replace (RN (bb - ac) - (bb - ac) + (bb - b * b) + - (ac - a * c) + (b * b - B * B) + - (a * c - A * C))
    with (RN (bb - ac) - (B * B - A * C)) in T by ring.
  rewrite !Rabs_Ropp in T. lra.
Qed.

(** A rounded dot product of a vector with itself: its products are never negative, so its magnitude is its value
    (sphere_filter reads it so: dot3_rounded_square, core/dot3_filter.hpp). *)
Lemma square_magnitude_value : forall x0 x1 x2,
  magnitude (dot3_rounded x0 x1 x2 x0 x1 x2) = value (dot3_rounded x0 x1 x2 x0 x1 x2).
Proof.
  intros. unfold dot3_rounded; simpl.
  assert (H : forall x, Rabs (RN (x * x)) = RN (x * x)) by (intro x; apply Rabs_nonneg_eq, RN_nonneg; nra).
  rewrite !H. reflexivity.
Qed.

Lemma value_le_magnitude : forall a0 a1 a2 b0 b1 b2,
  Rabs (value (dot3_rounded a0 a1 a2 b0 b1 b2)) <= magnitude (dot3_rounded a0 a1 a2 b0 b1 b2).
Proof.
  intros. unfold dot3_rounded; simpl.
  set (q0 := RN (a0 * b0)). set (q1 := RN (a1 * b1)). set (q2 := RN (a2 * b2)).
  rewrite <- RN_abs. apply RN_le.
  eapply Rle_trans; [apply Rabs_triang|]. rewrite <- RN_abs.
  apply Rplus_le_compat_r. apply RN_le. apply Rabs_triang.
Qed.

(** |Ĉ| ≤ P_C: Ĉ = S ⊖ q with S and q non-negative. *)
Lemma c_value_le_magnitude : forall o0 o1 o2 c0 c1 c2 r,
  Rabs (sphere_c_value o0 o1 o2 c0 c1 c2 r) <= sphere_c_magnitude o0 o1 o2 c0 c1 c2 r.
Proof.
  intros. unfold sphere_c_value, sphere_c_magnitude, sphere_s.
  rewrite square_magnitude_value.
  set (S := value _). set (q := RN (r * r)).
  assert (PS : 0 <= S).
  { unfold S. rewrite <- square_magnitude_value.
    apply (magnitude_bound (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)
                           (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)). }
  assert (Pq : 0 <= q) by (apply RN_nonneg; nra).
  rewrite <- RN_abs. apply RN_le. apply Rabs_le. lra.
Qed.

Lemma RN_upper : forall x, 0 <= x -> RN x <= x * (1 + u) + eta.
Proof.
  intros x Hx. pose proof (RN_err x) as E. rewrite (Rabs_nonneg_eq x Hx) in E.
  apply Rabs_bounds in E. lra.
Qed.

Lemma binary64_sphere_filter_d_floor : binary64 sphere_filter_d_floor.
Proof. apply binary64_bpow. lia. Qed.

(** u·θ = 16η: the floor θ = 2^-1018 turns an absolute error of a few η into a relative one. *)
Lemma floor_eta : u * sphere_filter_d_floor = 16 * eta.
Proof.
  unfold sphere_filter_d_floor, eta, unit_roundoff.
  rewrite <- bpow_plus.
  replace (-53 + -1018)%Z with (4 + -1075)%Z by lia. rewrite bpow_plus.
  replace (bpow radix2 4) with 16 by (simpl; lra). reflexivity.
Qed.

(** A filter bound (κ ⊗ m) ⊕ μ, u ≤ κ and μ ≤ 16η, is at most 2κ·(m ⊕ θ) for a non-negative double m. *)
Lemma floor_covers : forall k mu m, binary64 m -> 0 <= m -> u <= k -> 0 <= mu <= 16 * eta ->
  RN (RN (k * m) + mu) <= 2 * k * RN (m + sphere_filter_d_floor).
Proof.
  intros k mu m Bm Pm Hk Hmu.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv. pose proof floor_eta as Fe.
  assert (Pk : 0 <= k * m) by nra.
  pose proof (RN_upper (k * m) Pk) as U1. pose proof (RN_nonneg (k * m) Pk) as P1.
  pose proof (RN_upper (RN (k * m) + mu) ltac:(lra)) as U2.
  assert (Pt : 0 <= sphere_filter_d_floor) by apply bpow_ge_0.
  assert (L : (m + sphere_filter_d_floor) * (1 - u) <= RN (m + sphere_filter_d_floor))
    by (apply RN_plus_lower; [exact Bm | apply binary64_sphere_filter_d_floor | lra]).
  assert (L2 : 2 * k * ((m + sphere_filter_d_floor) * (1 - u)) <= 2 * k * RN (m + sphere_filter_d_floor))
    by (apply Rmult_le_compat_l; lra).
  (* (k m (1 + u) + η + μ)(1 + u) + η ≤ 2k(1 − u)(m + θ) *)
  assert (A1 : (RN (k * m) + mu) * (1 + u) <= (k * m * (1 + u) + eta + mu) * (1 + u))
    by (apply Rmult_le_compat_r; lra).
  assert (A2 : k * m * ((1 + u) * (1 + u)) <= k * m * (2 * (1 - u))) by (apply Rmult_le_compat_l; [lra | rewrite Uv; lra]).
  assert (A3 : u * sphere_filter_d_floor <= k * sphere_filter_d_floor) by (apply Rmult_le_compat_r; lra).
  assert (A4 : (eta + mu) * (1 + u) + eta <= 2 * (1 - u) * (u * sphere_filter_d_floor)) by (rewrite Fe, Uv; lra).
  assert (A5 : 2 * (1 - u) * (u * sphere_filter_d_floor) <= 2 * (1 - u) * (k * sphere_filter_d_floor))
    by (apply Rmult_le_compat_l; [rewrite Uv|]; lra).
  lra.
Qed.

(** The computed E_D is at least the error bound of [d_value_error], for E_A, E_B, E_C within 2κ of Y, X, Z
    ([floor_covers]): with x = X, y = Y, z = Z, the error is at most 2u(X⊗X + Y⊗Z) + 4κ_B(1 + κ_B)x² +
    (2κ_A + 2κ_C(1 + 2κ_A))yz + 2η ≤ 31u(X⊗X ⊕ Y⊗Z) + 3η, and E_D at least 32u(1 − u)³(X⊗X ⊕ Y⊗Z) + 127η(1 − u). *)
Lemma d_bound_lower : forall a b c mb pc ea eb ec,
  binary64 a -> binary64 mb -> binary64 pc -> 0 <= a -> Rabs b <= mb -> Rabs c <= pc ->
  0 <= ea -> ea <= 2 * filter_den_relative * RN (a + sphere_filter_d_floor) ->
  0 <= eb -> eb <= 2 * filter_num_relative * RN (mb + sphere_filter_d_floor) ->
  0 <= ec -> ec <= 2 * sphere_filter_c_relative * RN (pc + sphere_filter_d_floor) ->
  2 * u * (Rabs (RN (b * b)) + Rabs (RN (a * c))) + eb * (2 * Rabs b + eb) + ea * Rabs c
    + (Rabs a + ea) * ec + 2 * eta <= d_bound a mb pc.
Proof.
  intros a b c mb pc ea eb ec Ba Bmb Bpc Pa Hb Hc Pea Hea Peb Heb Pec Hec.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv.
  unfold d_bound. cbv zeta.
  assert (Pt : 0 <= sphere_filter_d_floor) by apply bpow_ge_0.
  assert (Bt : binary64 sphere_filter_d_floor) by apply binary64_sphere_filter_d_floor.
  set (x := RN (mb + sphere_filter_d_floor)) in *.
  set (y := RN (a + sphere_filter_d_floor)) in *.
  set (z := RN (pc + sphere_filter_d_floor)) in *.
  assert (Pmb : 0 <= mb) by (pose proof (Rabs_pos b); lra).
  assert (Ppc : 0 <= pc) by (pose proof (Rabs_pos c); lra).
  assert (Xm : mb <= x) by (unfold x; rewrite <- (RN_binary64 mb Bmb) at 1; apply RN_le; lra).
  assert (Ya : a <= y) by (unfold y; rewrite <- (RN_binary64 a Ba) at 1; apply RN_le; lra).
  assert (Zp : pc <= z) by (unfold z; rewrite <- (RN_binary64 pc Bpc) at 1; apply RN_le; lra).
  rewrite (Rabs_nonneg_eq a Pa).
  set (XX := RN (x * x)). set (YZ := RN (y * z)).
  (* |b ⊗ b| ≤ X ⊗ X and |Â ⊗ Ĉ| ≤ Y ⊗ Z *)
  assert (Hbb : Rabs (RN (b * b)) <= XX).
  { rewrite <- RN_abs. apply RN_le. rewrite Rabs_mult.
    pose proof (Rabs_pos b). apply Rmult_le_compat; lra. }
  assert (Hac : Rabs (RN (a * c)) <= YZ).
  { rewrite <- RN_abs. apply RN_le. rewrite Rabs_mult, (Rabs_nonneg_eq a Pa).
    pose proof (Rabs_pos c). apply Rmult_le_compat; lra. }
  assert (Lxx : x * x * (1 - u) - eta <= XX) by (apply RN_lower; nra).
  assert (Lyz : y * z * (1 - u) - eta <= YZ) by (apply RN_lower; nra).
  set (ka := 2 * filter_den_relative) in *. set (kb := 2 * filter_num_relative) in *.
  set (kc := 2 * sphere_filter_c_relative) in *.
  assert (Ka : ka = 2 * ((3 + 16 * u) * u)) by reflexivity.
  assert (Kb : kb = 2 * ((4 + 32 * u) * u)) by reflexivity.
  assert (Kc : kc = 2 * (8 * u)) by reflexivity.
  assert (Pka : 0 <= ka) by (rewrite Ka; nra). assert (Pkb : 0 <= kb) by (rewrite Kb; nra).
  assert (Pkc : 0 <= kc) by (rewrite Kc; nra).
  (* the three products of the error bound *)
  assert (Tb : eb * (2 * Rabs b + eb) <= kb * (2 + kb) * (x * x)).
  { replace (kb * (2 + kb) * (x * x)) with (kb * x * (2 * x + kb * x)) by ring.
    pose proof (Rabs_pos b). apply Rmult_le_compat; nra. }
  assert (Ta : ea * Rabs c <= ka * (y * z)).
  { replace (ka * (y * z)) with (ka * y * z) by ring. pose proof (Rabs_pos c). apply Rmult_le_compat; nra. }
  assert (Tc : (a + ea) * ec <= (1 + ka) * kc * (y * z)).
  { replace ((1 + ka) * kc * (y * z)) with ((y + ka * y) * (kc * z)) by ring. apply Rmult_le_compat; nra. }
  assert (Px : 0 <= x * x) by nra. assert (Pyz : 0 <= y * z) by nra.
  set (X2 := x * x) in *. set (P2 := y * z) in *.
  (* the computed bound *)
  assert (BXX : binary64 XX) by apply binary64_RN. assert (BYZ : binary64 YZ) by apply binary64_RN.
  assert (PXX : 0 <= XX) by (apply RN_nonneg; exact Px). assert (PYZ : 0 <= YZ) by (apply RN_nonneg; exact Pyz).
  assert (Ls : (XX + YZ) * (1 - u) <= RN (XX + YZ)) by (apply RN_plus_lower; auto; lra).
  set (s := RN (XX + YZ)) in *.
  set (K := sphere_filter_d_relative). assert (HK : K = 32 * u) by reflexivity.
  assert (PKs : 0 <= K * s) by (rewrite HK; apply Rmult_le_pos; [lra | apply RN_nonneg; lra]).
  assert (Lt : K * s * (1 - u) - eta <= RN (K * s)) by (apply RN_lower; exact PKs).
  set (t := RN (K * s)) in *.
  assert (Pt' : 0 <= t) by (apply RN_nonneg; exact PKs).
  set (mu := sphere_filter_d_absolute).
  assert (Mu : mu = 128 * eta) by (unfold mu, sphere_filter_d_absolute; rewrite min_subnormal_eta; ring).
  assert (Lf : (t + mu) * (1 - u) <= RN (t + mu))
    by (apply RN_plus_lower; [apply binary64_RN | apply binary64_sphere_filter_d_absolute | lra]).
  (* linear in X2, P2, XX, YZ, s, t once the constants are numbers *)
  assert (S1 : K * ((XX + YZ) * (1 - u)) <= K * s) by (apply Rmult_le_compat_l; [rewrite HK|]; lra).
  assert (S2 : K * ((XX + YZ) * (1 - u)) * (1 - u) <= K * s * (1 - u)) by (apply Rmult_le_compat_r; lra).
  assert (S3 : (K * ((XX + YZ) * (1 - u)) * (1 - u) - eta + mu) * (1 - u) <= (t + mu) * (1 - u))
    by (apply Rmult_le_compat_r; lra).
  rewrite Ka in Ta, Tc. rewrite Kb in Tb. rewrite Kc in Tc. rewrite HK in S3.
  rewrite Uv in *. lra.
Qed.

Lemma filter_bound_nonneg : forall a0 a1 a2 b0 b1 b2 K, 0 <= K ->
  0 <= filter_bound (dot3_rounded a0 a1 a2 b0 b1 b2) K.
Proof.
  intros a0 a1 a2 b0 b1 b2 K HK. unfold filter_bound.
  destruct (magnitude_bound a0 a1 a2 b0 b1 b2) as [Pm _].
  apply RN_nonneg. rewrite filter_absolute_eta. pose proof eta_pos.
  assert (0 <= RN (K * magnitude (dot3_rounded a0 a1 a2 b0 b1 b2))) by (apply RN_nonneg; nra). lra.
Qed.

(** |D̂ − D| ≤ E_D for every binary64 input, D = B² − A·C with A = d·d, B = (o − c)·d,
    C = (o − c)·(o − c) − r². *)
Theorem sphere_d_encloses : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r ->
  let ra := dot3_rounded d0 d1 d2 d0 d1 d2 in
  let rb := dot3_rounded (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2) d0 d1 d2 in
  let A := d0 * d0 + d1 * d1 + d2 * d2 in
  let B := (o0 - c0) * d0 + (o1 - c1) * d1 + (o2 - c2) * d2 in
  let C := (o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2) - r * r in
  Rabs (d_value (value ra) (value rb) (sphere_c_value o0 o1 o2 c0 c1 c2 r) - (B * B - A * C)) <=
    d_bound (value ra) (magnitude rb) (sphere_c_magnitude o0 o1 o2 c0 c1 c2 r).
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r B0 B1 B2 C0 C1 C2 Br ra rb A B C.
  pose proof u_pos as Hu. pose proof u_val as Uv. pose proof eta_pos as He.
  assert (HA : Rabs (value ra - A) <= filter_bound ra filter_den_relative) by apply den_filter_encloses.
  assert (HB : Rabs (value rb - B) <= filter_bound rb filter_num_relative)
    by (apply (num_filter_encloses o0 o1 o2 c0 c1 c2 d0 d1 d2); assumption).
  assert (HC : Rabs (sphere_c_value o0 o1 o2 c0 c1 c2 r - C) <= sphere_c_bound o0 o1 o2 c0 c1 c2 r)
    by (apply sphere_c_encloses; assumption).
  eapply Rle_trans; [apply (d_value_error _ _ _ _ _ _ _ _ _ HA HB HC)|].
  assert (Fa : filter_absolute = 6 * eta) by apply filter_absolute_eta.
  assert (Pa : 0 <= value ra).
  { unfold ra. rewrite <- square_magnitude_value. apply (magnitude_bound d0 d1 d2 d0 d1 d2). }
  apply d_bound_lower; try apply binary64_RN.
  - exact Pa.
  - apply value_le_magnitude.
  - apply c_value_le_magnitude.
  - apply filter_bound_nonneg. unfold filter_den_relative. nra.
  - unfold filter_bound. unfold ra. rewrite square_magnitude_value. fold ra.
    apply floor_covers; [apply binary64_RN | exact Pa | unfold filter_den_relative; nra | lra].
  - apply filter_bound_nonneg. unfold filter_num_relative. nra.
  - unfold filter_bound. apply floor_covers;
      [apply binary64_RN | apply (magnitude_bound (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2) d0 d1 d2)
      | unfold filter_num_relative; nra | lra].
  - apply sphere_c_bound_nonneg.
  - unfold sphere_c_bound. fold (sphere_c_magnitude o0 o1 o2 c0 c1 c2 r).
    apply floor_covers; [apply binary64_RN | | unfold sphere_filter_c_relative; lra |].
    + unfold sphere_c_magnitude. apply RN_nonneg.
      pose proof (magnitude_bound (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)
                                  (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2)) as [Pm _].
      assert (0 <= RN (r * r)) by (apply RN_nonneg; nra). unfold sphere_s. lra.
    + unfold sphere_filter_c_absolute. rewrite min_subnormal_eta. lra.
Qed.

(** The certified sign of D̂ against E_D is the sign of the exact D = B² − A·C. *)
Theorem sphere_filter_d_sound : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r,
  binary64 o0 -> binary64 o1 -> binary64 o2 -> binary64 c0 -> binary64 c1 -> binary64 c2 -> binary64 r ->
  certifies (sphere_filter_d o0 o1 o2 d0 d1 d2 c0 c1 c2 r)
    (((o0 - c0) * d0 + (o1 - c1) * d1 + (o2 - c2) * d2) * ((o0 - c0) * d0 + (o1 - c1) * d1 + (o2 - c2) * d2)
     - (d0 * d0 + d1 * d1 + d2 * d2) *
       ((o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2) - r * r)).
Proof.
  intros. unfold sphere_filter_d. cbv zeta. apply filter_sign_sound.
  apply (sphere_d_encloses o0 o1 o2 d0 d1 d2 c0 c1 c2 r); assumption.
Qed.
