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

(** D̂ = (B̂ ⊗ B̂) ⊖ (Â ⊗ Ĉ) and E_D, from the values and bounds of A, B, C. *)
Definition d_value (a b c : R) : R := RN (RN (b * b) - RN (a * c)).

Definition d_bound (a b c ea eb ec : R) : R :=
  let bb := RN (b * b) in
  let ac := RN (a * c) in
  let t1 := RN (sphere_filter_d_relative * RN (Rabs bb + Rabs ac)) in
  let t2 := RN (eb * RN (RN (Rabs b + Rabs b) + eb)) in
  let t3 := RN (ea * Rabs c) in
  let t4 := RN (RN (Rabs a + ea) * ec) in
  RN (RN (RN (RN (t1 + t2) + RN (t3 + t4)) * sphere_filter_d_factor) + sphere_filter_d_absolute).

(** The whole filter of D, as sphere_filter() computes it: Â, E_A by dot3_rounded(d, d) and filter_den_relative,
    B̂, E_B by dot3_rounded(f, d) and filter_num_relative. *)
Definition sphere_filter_d (o0 o1 o2 d0 d1 d2 c0 c1 c2 r : R) : sign :=
  let ra := dot3_rounded d0 d1 d2 d0 d1 d2 in
  let rb := dot3_rounded (sphere_f o0 c0) (sphere_f o1 c1) (sphere_f o2 c2) d0 d1 d2 in
  let a := value ra in
  let b := value rb in
  let c := sphere_c_value o0 o1 o2 c0 c1 c2 r in
  let ea := filter_bound ra filter_den_relative in
  let eb := filter_bound rb filter_num_relative in
  let ec := sphere_c_bound o0 o1 o2 c0 c1 c2 r in
  filter_sign (d_value a b c) (d_bound a b c ea eb ec).

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

(** The computed E_D is at least that error bound, for non-negative binary64 E_A, E_B, E_C: every operation of
    E_D loses at most a factor (1 − u) and an η; φ_D(1 − u)⁷ ≥ 1 and μ_D = 128η cover them. *)
Lemma d_bound_lower : forall a b c ea eb ec,
  binary64 a -> binary64 b -> binary64 ea -> binary64 eb -> binary64 ec -> 0 <= ea -> 0 <= eb -> 0 <= ec ->
  2 * u * (Rabs (RN (b * b)) + Rabs (RN (a * c))) + eb * (2 * Rabs b + eb) + ea * Rabs c
    + (Rabs a + ea) * ec + 2 * eta <= d_bound a b c ea eb ec.
Proof.
  intros a b c ea eb ec Bain Bbin Bea Beb Bec Pea Peb Pec.
  pose proof u_pos as Hu. pose proof eta_pos as He. pose proof u_val as Uv.
  unfold d_bound. cbv zeta.
  set (w := 1 - u).
  assert (Hw : 1 / 2 <= w <= 1) by (unfold w; rewrite Uv; lra).
  assert (Lo : forall x, 0 <= x -> x * w - eta <= RN x /\ 0 <= RN x)
    by (intros x Hx; split; [apply RN_lower; exact Hx | apply RN_nonneg; exact Hx]).
  assert (Lp : forall x y, binary64 x -> binary64 y -> 0 <= x -> 0 <= y -> (x + y) * w <= RN (x + y) /\ 0 <= RN (x + y))
    by (intros x y Bx By Px Py; split; [apply RN_plus_lower; auto; lra | apply RN_nonneg; lra]).
  assert (W3 : forall Z, 0 <= Z -> Z * (w * w * w) <= Z * (w * w) /\ Z * (w * w * w) <= Z * w).
  { intros Z PZ. split; apply Rmult_le_compat_l; try exact PZ; nra. }
  set (kd := sphere_filter_d_relative). assert (Kd : kd = 4 * u) by reflexivity.
  set (phi := sphere_filter_d_factor).
  assert (Phi : 1 <= phi * (w * w * w * w * w * w * w) /\ phi * (w * w * w * w) <= 2).
  { unfold phi, sphere_filter_d_factor, w. rewrite Uv.
    replace (bpow radix2 (-40)) with (/ 1099511627776) by (simpl; lra). split; lra. }
  set (mu := sphere_filter_d_absolute).
  assert (Mu : mu = 128 * eta) by (unfold mu, sphere_filter_d_absolute; rewrite min_subnormal_eta; ring).
  assert (Bmu : binary64 mu) by apply binary64_sphere_filter_d_absolute.
  set (bb := RN (b * b)). set (ac := RN (a * c)).
  assert (Bbb : binary64 (Rabs bb)) by (apply binary64_abs, binary64_RN).
  assert (Bac : binary64 (Rabs ac)) by (apply binary64_abs, binary64_RN).
  pose proof (Rabs_pos bb) as Pbb. pose proof (Rabs_pos ac) as Pac. pose proof (Rabs_pos a) as Pa.
  pose proof (Rabs_pos b) as Pb. pose proof (Rabs_pos c) as Pc.
  (* t1 *)
  destruct (Lp _ _ Bbb Bac Pbb Pac) as [X1 PX1]. set (x1 := RN (Rabs bb + Rabs ac)) in *.
  destruct (Lo (kd * x1)) as [T1 Pt1]; [rewrite Kd; nra|]. set (t1 := RN (kd * x1)) in *.
  assert (A1 : kd * ((Rabs bb + Rabs ac) * w) * w <= kd * x1 * w).
  { apply Rmult_le_compat_r; [lra|]. apply Rmult_le_compat_l; [rewrite Kd; lra | exact X1]. }
  (* t2 *)
  assert (Bab : binary64 (Rabs b)) by (apply binary64_abs; exact Bbin).
  destruct (Lp _ _ Bab Bab Pb Pb) as [Y PY]. set (y := RN (Rabs b + Rabs b)) in *.
  destruct (Lp _ _ (binary64_RN _) Beb PY Peb) as [Y2 PY2]. fold y in Y2, PY2. set (y2 := RN (y + eb)) in *.
  destruct (Lo (eb * y2)) as [T2 Pt2]; [nra|]. set (t2 := RN (eb * y2)) in *.
  assert (A2 : eb * (((Rabs b + Rabs b) * w + eb) * w) * w <= eb * y2 * w).
  { apply Rmult_le_compat_r; [lra|]. apply Rmult_le_compat_l; [lra|].
    eapply Rle_trans; [|exact Y2]. apply Rmult_le_compat_r; lra. }
  (* t3 *)
  destruct (Lo (ea * Rabs c)) as [T3 Pt3]; [nra|]. set (t3 := RN (ea * Rabs c)) in *.
  (* t4 *)
  assert (Baa : binary64 (Rabs a)) by (apply binary64_abs; exact Bain).
  destruct (Lp _ _ Baa Bea Pa Pea) as [X4 PX4]. set (x4 := RN (Rabs a + ea)) in *.
  destruct (Lo (x4 * ec)) as [T4 Pt4]; [nra|]. set (t4 := RN (x4 * ec)) in *.
  assert (A4 : (Rabs a + ea) * w * ec * w <= x4 * ec * w).
  { apply Rmult_le_compat_r; [lra|]. apply Rmult_le_compat_r; lra. }
  (* T = t1 + t2 + t3 + t4 ≥ w³V − 4η *)
  set (V := kd * (Rabs bb + Rabs ac) + eb * (2 * Rabs b + eb) + ea * Rabs c + (Rabs a + ea) * ec).
  assert (PV : 0 <= V) by (unfold V; rewrite Kd; nra).
  destruct (W3 (kd * (Rabs bb + Rabs ac))) as [W1 _]; [rewrite Kd; nra|].
  destruct (W3 (eb * eb)) as [W2 _]; [nra|].
  destruct (W3 (eb * (2 * Rabs b))) as [W2' _]; [nra|].
  destruct (W3 (ea * Rabs c)) as [_ W3c]; [nra|].
  destruct (W3 ((Rabs a + ea) * ec)) as [W4 _]; [nra|].
  assert (TT : w * w * w * V - 4 * eta <= t1 + t2 + t3 + t4) by (unfold V; lra).
  (* the sums *)
  assert (Bt : forall x, binary64 (RN x)) by apply binary64_RN.
  destruct (Lp t1 t2 (Bt _) (Bt _) Pt1 Pt2) as [S12 PS12]. set (s12 := RN (t1 + t2)) in *.
  destruct (Lp t3 t4 (Bt _) (Bt _) Pt3 Pt4) as [S34 PS34]. set (s34 := RN (t3 + t4)) in *.
  destruct (Lp s12 s34 (Bt _) (Bt _) PS12 PS34) as [S PS]. set (sd := RN (s12 + s34)) in *.
  assert (A5 : (t1 + t2 + t3 + t4) * (w * w) <= sd).
  { eapply Rle_trans; [|exact S]. replace ((t1 + t2 + t3 + t4) * (w * w)) with (((t1 + t2) * w + (t3 + t4) * w) * w)
      by ring. apply Rmult_le_compat_r; lra. }
  assert (A6 : (w * w * w * V - 4 * eta) * (w * w) <= (t1 + t2 + t3 + t4) * (w * w))
    by (apply Rmult_le_compat_r; nra).
  assert (Pphi : 0 <= phi) by (unfold phi, sphere_filter_d_factor; pose proof (bpow_ge_0 radix2 (-40)); lra).
  destruct (Lo (sd * phi)) as [P1 PP1]; [nra|]. set (pd := RN (sd * phi)) in *.
  assert (A7 : (w * w * w * V - 4 * eta) * (w * w) * phi * w <= sd * phi * w).
  { apply Rmult_le_compat_r; [lra|]. apply Rmult_le_compat_r; lra. }
  destruct (Lp pd mu (Bt _) Bmu PP1 ltac:(rewrite Mu; lra)) as [E PE].
  assert (A8 : ((w * w * w * V - 4 * eta) * (w * w) * phi * w - eta + mu) * w <= (pd + mu) * w)
    by (apply Rmult_le_compat_r; lra).
  assert (A9 : V * 1 <= V * (phi * (w * w * w * w * w * w * w))) by (apply Rmult_le_compat_l; lra).
  assert (A10 : 4 * eta * (phi * (w * w * w * w)) <= 4 * eta * 2) by (apply Rmult_le_compat_l; lra).
  assert (A11 : 2 * u * (Rabs bb + Rabs ac) <= kd * (Rabs bb + Rabs ac)) by (rewrite Kd; nra).
  assert (A12 : eta * w <= eta) by nra.
  assert (A13 : mu * (1 / 2) <= mu * w) by (apply Rmult_le_compat_l; [rewrite Mu|]; lra).
  assert (EQ : ((w * w * w * V - 4 * eta) * (w * w) * phi * w - eta + mu) * w =
               V * (phi * (w * w * w * w * w * w * w)) - 4 * eta * (phi * (w * w * w * w)) - eta * w + mu * w)
    by ring.
  destruct Phi as [Phi1 Phi2].
  assert (VV : V = kd * (Rabs bb + Rabs ac) + eb * (2 * Rabs b + eb) + ea * Rabs c + (Rabs a + ea) * ec) by reflexivity.
  lra.
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
    d_bound (value ra) (value rb) (sphere_c_value o0 o1 o2 c0 c1 c2 r)
      (filter_bound ra filter_den_relative) (filter_bound rb filter_num_relative)
      (sphere_c_bound o0 o1 o2 c0 c1 c2 r).
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r B0 B1 B2 C0 C1 C2 Br ra rb A B C.
  pose proof u_pos as Hu. pose proof u_val as Uv.
  assert (HA : Rabs (value ra - A) <= filter_bound ra filter_den_relative) by apply den_filter_encloses.
  assert (HB : Rabs (value rb - B) <= filter_bound rb filter_num_relative)
    by (apply (num_filter_encloses o0 o1 o2 c0 c1 c2 d0 d1 d2); assumption).
  assert (HC : Rabs (sphere_c_value o0 o1 o2 c0 c1 c2 r - C) <= sphere_c_bound o0 o1 o2 c0 c1 c2 r)
    by (apply sphere_c_encloses; assumption).
  eapply Rle_trans; [apply (d_value_error _ _ _ _ _ _ _ _ _ HA HB HC)|].
  apply d_bound_lower; try apply binary64_RN.
  - apply filter_bound_nonneg. unfold filter_den_relative. nra.
  - apply filter_bound_nonneg. unfold filter_num_relative. nra.
  - apply sphere_c_bound_nonneg.
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
