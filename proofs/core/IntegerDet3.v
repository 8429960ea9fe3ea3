(** * The sign of a 3×3 determinant of doubles from integers (kernel/src/core/integer_det3.hpp: [integer_vector]
    and [integer_det3_sign]; tied to the C++ through the cascade's twin, triangle/TriangleIntegerSign.v).

    Each vector's components are read as integers over one power of two ([integer_vector], the C++'s
    integer_vector): a finite double is ±m·2^e ([component]: the significand with its trailing zeros stripped,
    [strip]); over E, the least exponent of the vector's nonzero components, every component is the integer
    X_i = ±m_i·2^(e_i − E) ([aligned]); the C++ gives up when some |X_i| ≥ 2^62 or a component is not finite.
    A component may also be the exact sum h_i + l_i of two doubles (TwoDiff's parts of a difference:
    [integer_vector_sum], the C++'s integer_vector_sum with N = 2): E is then the least exponent of the six
    doubles, X_i the sum of the two aligned parts; [integer_vector] is the same reading with zero low parts.
    - [integer_vector_sum_value], [integer_vector_value]: then h_i + l_i = X_i · 2^E (x_i = X_i · 2^E) exactly;
    - [det3_sign_integer]: x·(y × z) = D · 2^(Ex+Ey+Ez) with D the same polynomial over Z, so its sign is D's;
    - [det3_range]: with components below 2^62, every cross component is below 2^125 (a signed 128-bit integer
      holds it) and D below 2^189 (a signed 192-bit sum does not wrap);
    - [integer_det3_sign_correct]: the three composed, the statement the C++ routine needs. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
Import ListNotations.
Open Scope R_scope.

(** The determinant as ray_triangle_formula.hpp's cross_terms and dot_terms write it: x·(y × z) with
    (y × z)_i = y_j z_k − y_k z_j, (i, j, k) = (0, 1, 2), (1, 2, 0), (2, 0, 1), summed (x_0 c_0 + x_1 c_1) + x_2 c_2. *)
Definition cross_R (y0 y1 y2 z0 z1 z2 : R) : R * R * R :=
  (y1 * z2 - y2 * z1, y2 * z0 - y0 * z2, y0 * z1 - y1 * z0).
Definition det3_R (x0 x1 x2 y0 y1 y2 z0 z1 z2 : R) : R :=
  (x0 * (y1 * z2 - y2 * z1) + x1 * (y2 * z0 - y0 * z2)) + x2 * (y0 * z1 - y1 * z0).

Definition cross_Z (y0 y1 y2 z0 z1 z2 : Z) : Z * Z * Z :=
  (y1 * z2 - y2 * z1, y2 * z0 - y0 * z2, y0 * z1 - y1 * z0)%Z.
Definition det3_Z (x0 x1 x2 y0 y1 y2 z0 z1 z2 : Z) : Z :=
  ((x0 * (y1 * z2 - y2 * z1) + x1 * (y2 * z0 - y0 * z2)) + x2 * (y0 * z1 - y1 * z0))%Z.

Lemma det3_scaled : forall (X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 : Z) (Ex Ey Ez : Z),
  det3_R (IZR X0 * bpow radix2 Ex) (IZR X1 * bpow radix2 Ex) (IZR X2 * bpow radix2 Ex)
         (IZR Y0 * bpow radix2 Ey) (IZR Y1 * bpow radix2 Ey) (IZR Y2 * bpow radix2 Ey)
         (IZR Z0 * bpow radix2 Ez) (IZR Z1 * bpow radix2 Ez) (IZR Z2 * bpow radix2 Ez) =
  IZR (det3_Z X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2) * bpow radix2 (Ex + Ey + Ez).
Proof.
  intros. unfold det3_R, det3_Z.
  rewrite !plus_IZR, !mult_IZR, !minus_IZR, !mult_IZR, !bpow_plus. ring.
Qed.

(** The sign of the determinant is the sign of the integer D. *)
Theorem det3_sign_integer : forall (X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 : Z) (Ex Ey Ez : Z),
  Rcompare (det3_R (IZR X0 * bpow radix2 Ex) (IZR X1 * bpow radix2 Ex) (IZR X2 * bpow radix2 Ex)
                   (IZR Y0 * bpow radix2 Ey) (IZR Y1 * bpow radix2 Ey) (IZR Y2 * bpow radix2 Ey)
                   (IZR Z0 * bpow radix2 Ez) (IZR Z1 * bpow radix2 Ez) (IZR Z2 * bpow radix2 Ez)) 0 =
  Z.compare (det3_Z X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2) 0.
Proof.
  intros. rewrite det3_scaled.
  set (D := det3_Z X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2). set (p := bpow radix2 (Ex + Ey + Ez)).
  assert (P : 0 < p) by apply bpow_gt_0.
  rewrite <- Rcompare_IZR.
  destruct (Rcompare_spec (IZR D) (IZR 0)) as [L|E|G].
  - apply Rcompare_Lt. simpl in L. nra.
  - apply Rcompare_Eq. rewrite E. simpl. ring.
  - apply Rcompare_Gt. simpl in G. nra.
Qed.

(** The ranges the C++'s fixed widths rest on: components below 2^62 give cross components below 2^125 (two
    products below 2^124: a signed 128-bit integer holds them) and D below 2^189 (three products below 2^187: a
    signed 192-bit sum does not wrap). *)
Lemma product_bound : forall a b n m : Z, (Z.abs a < 2 ^ n)%Z -> (Z.abs b < 2 ^ m)%Z -> (0 <= n)%Z -> (0 <= m)%Z ->
  (Z.abs (a * b) < 2 ^ (n + m))%Z.
Proof.
  intros a b n m A B N M. rewrite Z.abs_mul, Z.pow_add_r by lia.
  apply Z.mul_lt_mono_nonneg; lia.
Qed.

Lemma difference_bound : forall a b c e : Z, (Z.abs a < 2 ^ 62)%Z -> (Z.abs b < 2 ^ 62)%Z ->
  (Z.abs c < 2 ^ 62)%Z -> (Z.abs e < 2 ^ 62)%Z -> (Z.abs (a * b - c * e) < 2 ^ 125)%Z.
Proof.
  intros a b c e A B C E.
  pose proof (product_bound a b 62 62 A B ltac:(lia) ltac:(lia)) as P1.
  pose proof (product_bound c e 62 62 C E ltac:(lia) ltac:(lia)) as P2.
  change (62 + 62)%Z with 124%Z in P1, P2.
  replace (2 ^ 125)%Z with (2 * 2 ^ 124)%Z by (rewrite <- (Z.pow_succ_r 2 124) by lia; reflexivity).
  set (x := (a * b)%Z) in *. set (y := (c * e)%Z) in *. set (P := (2 ^ 124)%Z) in *. clearbody x y P.
  pose proof (Z.abs_triangle x (- y)) as T. rewrite Z.abs_opp in T.
  replace (x - y)%Z with (x + - y)%Z by ring. clear -P1 P2 T. lia.
Qed.

Theorem det3_range : forall X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 : Z,
  (Z.abs X0 < 2 ^ 62)%Z -> (Z.abs X1 < 2 ^ 62)%Z -> (Z.abs X2 < 2 ^ 62)%Z ->
  (Z.abs Y0 < 2 ^ 62)%Z -> (Z.abs Y1 < 2 ^ 62)%Z -> (Z.abs Y2 < 2 ^ 62)%Z ->
  (Z.abs Z0 < 2 ^ 62)%Z -> (Z.abs Z1 < 2 ^ 62)%Z -> (Z.abs Z2 < 2 ^ 62)%Z ->
  (Z.abs (Y1 * Z2 - Y2 * Z1) < 2 ^ 125)%Z /\ (Z.abs (Y2 * Z0 - Y0 * Z2) < 2 ^ 125)%Z /\
  (Z.abs (Y0 * Z1 - Y1 * Z0) < 2 ^ 125)%Z /\ (Z.abs (det3_Z X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2) < 2 ^ 189)%Z.
Proof.
  intros X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2 HX0 HX1 HX2 HY0 HY1 HY2 HZ0 HZ1 HZ2.
  pose proof (difference_bound Y1 Z2 Y2 Z1 HY1 HZ2 HY2 HZ1) as C0.
  pose proof (difference_bound Y2 Z0 Y0 Z2 HY2 HZ0 HY0 HZ2) as C1.
  pose proof (difference_bound Y0 Z1 Y1 Z0 HY0 HZ1 HY1 HZ0) as C2.
  split; [exact C0 | split; [exact C1 | split; [exact C2 |]]].
  pose proof (product_bound X0 _ 62 125 HX0 C0 ltac:(lia) ltac:(lia)) as P0.
  pose proof (product_bound X1 _ 62 125 HX1 C1 ltac:(lia) ltac:(lia)) as P1.
  pose proof (product_bound X2 _ 62 125 HX2 C2 ltac:(lia) ltac:(lia)) as P2.
  change (62 + 125)%Z with 187%Z in P0, P1, P2.
  unfold det3_Z.
  replace (2 ^ 189)%Z with (4 * 2 ^ 187)%Z by (change 4%Z with (2 ^ 2)%Z; rewrite <- Z.pow_add_r by lia; reflexivity).
  set (u := (X0 * (Y1 * Z2 - Y2 * Z1))%Z) in *. set (v := (X1 * (Y2 * Z0 - Y0 * Z2))%Z) in *.
  set (w := (X2 * (Y0 * Z1 - Y1 * Z0))%Z) in *. set (P := (2 ^ 187)%Z) in *. clearbody u v w P.
  pose proof (Z.abs_triangle (u + v) w). pose proof (Z.abs_triangle u v).
  clear -P0 P1 P2 H H0. lia.
Qed.

(** n·2^e over a smaller exponent E: n·2^(e−E) is an integer and the value is the same. *)
Lemma aligned_value : forall (n e E : Z), (E <= e)%Z ->
  IZR n * bpow radix2 e = IZR (n * Zpower radix2 (e - E)) * bpow radix2 E.
Proof.
  intros n e E H. rewrite mult_IZR, IZR_Zpower by lia.
  rewrite Rmult_assoc, <- bpow_plus. f_equal. f_equal. lia.
Qed.

(** A finite binary64 is ±m·2^e (its Flocq representation): the integer the C++ reads from the bits. *)
Lemma finite_value : forall (x : binary_float 53 1024) s m e B, x = B754_finite s m e B ->
  B2R x = IZR (cond_Zopp s (Zpos m)) * bpow radix2 e.
Proof. intros x s m e B ->. reflexivity. Qed.

(** Stripping k trailing zeros of the significand: m = m'·2^k, the value m'·2^(e+k). *)
Lemma stripped_value : forall (m' k e : Z), (0 <= k)%Z ->
  IZR (m' * Zpower radix2 k) * bpow radix2 e = IZR m' * bpow radix2 (e + k).
Proof.
  intros m' k e K. rewrite mult_IZR, IZR_Zpower by lia. rewrite Rmult_assoc, <- bpow_plus. f_equal. f_equal. lia.
Qed.

(** The C++'s significand with its trailing zeros stripped: m = m'·2^k with m' odd (std::countr_zero). *)
Fixpoint strip (m : positive) : Z * Z :=
  match m with
  | xO p => let '(m', k) := strip p in (m', (k + 1)%Z)
  | _ => (Zpos m, 0%Z)
  end.

Lemma strip_spec : forall m, let '(m', k) := strip m in (0 <= k)%Z /\ Zpos m = (m' * Zpower radix2 k)%Z.
Proof.
  induction m as [p IH|p IH|]; simpl.
  - split; [lia|]. cbn. lia.
  - destruct (strip p) as [m' k]. destruct IH as [K E]. split; [lia|].
    rewrite Zpower_plus by lia. change (Zpower radix2 1) with 2%Z.
    rewrite Pos2Z.inj_xO, E. change (radix_val radix2) with 2%Z. rewrite Z.pow_1_r. ring.
  - split; [lia|]. cbn. lia.
Qed.

(** A component as the C++ reads it: the signed odd significand and its exponent, or 0 for a zero. *)
Definition component (x : binary_float 53 1024) : option (Z * Z) :=
  match x with
  | B754_zero _ => Some (0%Z, 0%Z)
  | B754_finite s m e _ => let '(m', k) := strip m in Some (cond_Zopp s m', (e + k)%Z)
  | _ => None
  end.

Lemma component_value : forall x n e, component x = Some (n, e) -> B2R x = IZR n * bpow radix2 e.
Proof.
  intros [s| | |s m ex B] n e C; simpl in C; try discriminate.
  - injection C as <- <-. simpl. ring.
  - pose proof (strip_spec m) as S. destruct (strip m) as [m' k]. destruct S as [K E].
    injection C as <- <-. simpl. unfold F2R. simpl. rewrite E.
    destruct s; simpl SpecFloat.cond_Zopp.
    + rewrite <- Z.mul_opp_l. apply stripped_value, K.
    + apply stripped_value, K.
Qed.

(** The least exponent of the nonzero components (0 when all three are zero: then every X_i is 0). *)
Definition least_exponent (c : list (Z * Z)) : Z :=
  match filter (fun p => negb (Z.eqb (fst p) 0)) c with
  | nil => 0%Z
  | p :: rest => fold_left (fun (m : Z) (q : Z * Z) => Z.min m (snd q)) rest (snd p)
  end.

Definition aligned (E : Z) (p : Z * Z) : Z :=
  if Z.eqb (fst p) 0 then 0%Z else (fst p * Zpower radix2 (snd p - E))%Z.

(** kernel/src/core/integer_det3.hpp's integer_vector_sum for N = 2: a vector whose components are the exact sums
    h_i + l_i (TwoDiff's parts of a difference), read over E, the least exponent of the six doubles' nonzero
    parts, as X_i = aligned(h_i) + aligned(l_i). None when a part is not finite, an aligned part is 2^62 or more
    in magnitude (the C++'s `shift + width > 62`) or a sum is (its `sum` check). *)
Definition sum_in_range (a b : Z) : bool :=
  (Z.abs a <? 2 ^ 62)%Z && (Z.abs b <? 2 ^ 62)%Z && (Z.abs (a + b) <? 2 ^ 62)%Z.

Definition integer_vector_sum (h0 h1 h2 l0 l1 l2 : binary_float 53 1024) : option (Z * Z * Z * Z) :=
  match component h0, component h1, component h2, component l0, component l1, component l2 with
  | Some c0, Some c1, Some c2, Some d0, Some d1, Some d2 =>
      let E := least_exponent [c0; c1; c2; d0; d1; d2] in
      let a0 := aligned E c0 in let a1 := aligned E c1 in let a2 := aligned E c2 in
      let b0 := aligned E d0 in let b1 := aligned E d1 in let b2 := aligned E d2 in
      if sum_in_range a0 b0 && sum_in_range a1 b1 && sum_in_range a2 b2
      then Some ((a0 + b0)%Z, (a1 + b1)%Z, (a2 + b2)%Z, E) else None
  | _, _, _, _, _, _ => None
  end.

(** integer_vector, the C++'s N = 1: the same reading with zero low parts (zeros do not take part in E and align
    to 0, so it is the C++'s reading of three doubles). *)
Definition integer_vector (x0 x1 x2 : binary_float 53 1024) : option (Z * Z * Z * Z) :=
  integer_vector_sum x0 x1 x2 (B754_zero false) (B754_zero false) (B754_zero false).

Lemma fold_min_le : forall rest m q, In q rest -> (fold_left (fun (m : Z) (q : Z * Z) => Z.min m (snd q)) rest m <= snd q)%Z.
Proof.
  induction rest as [|r rest IH]; intros m q I; [destruct I|].
  simpl. destruct I as [<-|I].
  - clear IH. revert m. induction rest as [|s rest IH2]; intros m; simpl; [lia|].
    specialize (IH2 (Z.min m (snd s))). 
    assert (forall l a b, (a <= b)%Z -> (fold_left (fun (m : Z) (q : Z * Z) => Z.min m (snd q)) l a <= b)%Z) as Mono.
    { induction l as [|t l IHl]; intros a b H; simpl; [exact H|]. apply IHl. lia. }
    apply Mono. lia.
  - apply IH, I.
Qed.

Lemma fold_min_init : forall rest m, (fold_left (fun (m : Z) (q : Z * Z) => Z.min m (snd q)) rest m <= m)%Z.
Proof. induction rest as [|r rest IH]; intros m; simpl; [lia|]. specialize (IH (Z.min m (snd r))). lia. Qed.

Lemma least_le : forall c p, In p c -> fst p <> 0%Z -> (least_exponent c <= snd p)%Z.
Proof.
  intros c p I N. unfold least_exponent.
  assert (F : In p (filter (fun p => negb (Z.eqb (fst p) 0)) c)).
  { apply filter_In. split; [exact I|]. apply Z.eqb_neq in N. now rewrite N. }
  destruct (filter _ c) as [|q rest]; [destruct F|].
  destruct F as [<-|F]; [apply fold_min_init | now apply fold_min_le].
Qed.

Lemma aligned_value_of : forall c E x n e, component x = Some (n, e) -> In (n, e) c ->
  E = least_exponent c -> B2R x = IZR (aligned E (n, e)) * bpow radix2 E.
Proof.
  intros c E x n e C I HE. rewrite (component_value x n e C). unfold aligned. simpl.
  destruct (Z.eqb_spec n 0) as [Z0|N].
  - subst n. simpl. ring.
  - apply aligned_value. subst E. now apply (least_le c (n, e)).
Qed.

Lemma sum_in_range_spec : forall a b, sum_in_range a b = true -> (Z.abs (a + b) < 2 ^ 62)%Z.
Proof. intros a b H. unfold sum_in_range in H. apply andb_prop in H as [_ H]. now apply Z.ltb_lt. Qed.

Lemma aligned_sum_value : forall c E h l nh eh nl el, component h = Some (nh, eh) -> component l = Some (nl, el) ->
  In (nh, eh) c -> In (nl, el) c -> E = least_exponent c ->
  B2R h + B2R l = IZR (aligned E (nh, eh) + aligned E (nl, el))%Z * bpow radix2 E.
Proof.
  intros c E h l nh eh nl el Ch Cl Ih Il HE.
  rewrite (aligned_value_of c E h nh eh Ch Ih HE), (aligned_value_of c E l nl el Cl Il HE), plus_IZR. ring.
Qed.

Theorem integer_vector_sum_value : forall h0 h1 h2 l0 l1 l2 X0 X1 X2 E,
  integer_vector_sum h0 h1 h2 l0 l1 l2 = Some (X0, X1, X2, E) ->
  B2R h0 + B2R l0 = IZR X0 * bpow radix2 E /\ B2R h1 + B2R l1 = IZR X1 * bpow radix2 E /\
  B2R h2 + B2R l2 = IZR X2 * bpow radix2 E /\
  (Z.abs X0 < 2 ^ 62 /\ Z.abs X1 < 2 ^ 62 /\ Z.abs X2 < 2 ^ 62)%Z.
Proof.
  intros h0 h1 h2 l0 l1 l2 X0 X1 X2 E H. unfold integer_vector_sum in H.
  destruct (component h0) as [[n0 e0]|] eqn:C0; [|discriminate].
  destruct (component h1) as [[n1 e1]|] eqn:C1; [|discriminate].
  destruct (component h2) as [[n2 e2]|] eqn:C2; [|discriminate].
  destruct (component l0) as [[k0 f0]|] eqn:D0; [|discriminate].
  destruct (component l1) as [[k1 f1]|] eqn:D1; [|discriminate].
  destruct (component l2) as [[k2 f2]|] eqn:D2; [|discriminate].
  set (c := [(n0, e0); (n1, e1); (n2, e2); (k0, f0); (k1, f1); (k2, f2)]) in H.
  set (E' := least_exponent c) in H.
  destruct (sum_in_range (aligned E' (n0, e0)) (aligned E' (k0, f0)) &&
            sum_in_range (aligned E' (n1, e1)) (aligned E' (k1, f1)) &&
            sum_in_range (aligned E' (n2, e2)) (aligned E' (k2, f2))) eqn:R; [|discriminate].
  injection H as <- <- <- <-.
  apply andb_prop in R as [R R2]. apply andb_prop in R as [R0 R1].
  apply sum_in_range_spec in R0, R1, R2.
  split; [|split; [|split]].
  - apply (aligned_sum_value c); unfold c; simpl; auto 7.
  - apply (aligned_sum_value c); unfold c; simpl; auto 7.
  - apply (aligned_sum_value c); unfold c; simpl; auto 7.
  - auto.
Qed.

Lemma component_finite : forall x c, component x = Some c -> is_finite x = true.
Proof. intros [s| | |s m e B] c C; simpl in C; try discriminate; reflexivity. Qed.

(** An answer means every part is finite (the low parts' finiteness is what makes TwoDiff's parts exact). *)
Lemma integer_vector_sum_fin : forall h0 h1 h2 l0 l1 l2 X, integer_vector_sum h0 h1 h2 l0 l1 l2 = Some X ->
  is_finite l0 = true /\ is_finite l1 = true /\ is_finite l2 = true.
Proof.
  intros h0 h1 h2 l0 l1 l2 X H. unfold integer_vector_sum in H.
  destruct (component h0); [|discriminate]. destruct (component h1); [|discriminate].
  destruct (component h2); [|discriminate].
  destruct (component l0) eqn:D0; [|discriminate]. destruct (component l1) eqn:D1; [|discriminate].
  destruct (component l2) eqn:D2; [|discriminate].
  repeat split; eapply component_finite; eassumption.
Qed.

Theorem integer_vector_value : forall x0 x1 x2 X0 X1 X2 E, integer_vector x0 x1 x2 = Some (X0, X1, X2, E) ->
  B2R x0 = IZR X0 * bpow radix2 E /\ B2R x1 = IZR X1 * bpow radix2 E /\ B2R x2 = IZR X2 * bpow radix2 E /\
  (Z.abs X0 < 2 ^ 62 /\ Z.abs X1 < 2 ^ 62 /\ Z.abs X2 < 2 ^ 62)%Z.
Proof.
  intros x0 x1 x2 X0 X1 X2 E H. destruct (integer_vector_sum_value _ _ _ _ _ _ _ _ _ _ H) as [V0 [V1 [V2 B]]].
  simpl in V0, V1, V2. rewrite Rplus_0_r in V0, V1, V2. auto.
Qed.

(** ** The C++'s integer_det3_sign: the exact sign, and no 128- or 192-bit operation wraps. *)
Theorem integer_det3_sign_correct : forall x0 x1 x2 y0 y1 y2 z0 z1 z2 X0 X1 X2 Ex Y0 Y1 Y2 Ey Z0 Z1 Z2 Ez,
  integer_vector x0 x1 x2 = Some (X0, X1, X2, Ex) ->
  integer_vector y0 y1 y2 = Some (Y0, Y1, Y2, Ey) ->
  integer_vector z0 z1 z2 = Some (Z0, Z1, Z2, Ez) ->
  Rcompare (det3_R (B2R x0) (B2R x1) (B2R x2) (B2R y0) (B2R y1) (B2R y2) (B2R z0) (B2R z1) (B2R z2)) 0 =
    Z.compare (det3_Z X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2) 0%Z /\
  (Z.abs (Y1 * Z2 - Y2 * Z1) < 2 ^ 125 /\ Z.abs (Y2 * Z0 - Y0 * Z2) < 2 ^ 125 /\
   Z.abs (Y0 * Z1 - Y1 * Z0) < 2 ^ 125 /\ Z.abs (det3_Z X0 X1 X2 Y0 Y1 Y2 Z0 Z1 Z2) < 2 ^ 189)%Z.
Proof.
  intros x0 x1 x2 y0 y1 y2 z0 z1 z2 X0 X1 X2 Ex Y0 Y1 Y2 Ey Z0 Z1 Z2 Ez HX HY HZ.
  destruct (integer_vector_value _ _ _ _ _ _ _ HX) as [Vx0 [Vx1 [Vx2 [Bx0 [Bx1 Bx2]]]]].
  destruct (integer_vector_value _ _ _ _ _ _ _ HY) as [Vy0 [Vy1 [Vy2 [By0 [By1 By2]]]]].
  destruct (integer_vector_value _ _ _ _ _ _ _ HZ) as [Vz0 [Vz1 [Vz2 [Bz0 [Bz1 Bz2]]]]].
  split.
  - rewrite Vx0, Vx1, Vx2, Vy0, Vy1, Vy2, Vz0, Vz1, Vz2. apply det3_sign_integer.
  - now apply det3_range.
Qed.
