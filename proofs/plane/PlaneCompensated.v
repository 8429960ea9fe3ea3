(** * Stage 2 and the enclosure decisions.

    - [compensated_dot3_enclosure]: kernel/src/core/dot3_compensated.hpp, [compensated_dot3]
      (with the corollaries [compensated_den_enclosure] and [compensated_num_enclosure] for the two
      calls in intersect_certified.cpp);
    - [compensated_dot3_refined_enclosure]: the same file, [compensated_dot3_refined], the second level
      of stage 2 (corollaries [compensated_den_refined_enclosure], [compensated_num_refined_enclosure]);
    - [enclosure_sign_sound]: kernel/src/core/enclosure.hpp, [enclosure_sign] and (per lane)
      [enclosure_sign_lanes];
    - [tail_sum_enclosure]: kernel/src/core/expansion.hpp, [expansion_tail_enclosure]. *)

From Coq Require Import Reals Lra Lia List.
From Flocq Require Import Core.
From Raykernel Require Import Constants Model PlaneFilter.
Open Scope R_scope.

(** [struct Enclosure { hi, lo, radius }]: the claim |V − (hi + lo)| ≤ radius. *)
Record Enclosure := { hi : R; lo : R; radius : R }.

Definition encloses (e : Enclosure) (V : R) : Prop := Rabs (V - (hi e + lo e)) <= radius e.

(** Σ x and Σ |x| over a list, and the triangle inequality between them. *)
Fixpoint sum_list (l : list R) : R :=
  match l with nil => 0 | x :: l' => x + sum_list l' end.

Fixpoint sum_abs (l : list R) : R :=
  match l with nil => 0 | x :: l' => Rabs x + sum_abs l' end.

Lemma Rabs_sum_list : forall l, Rabs (sum_list l) <= sum_abs l.
Proof.
  induction l as [|x l IH]; simpl.
  - rewrite Rabs_R0. lra.
  - eapply Rle_trans; [apply Rabs_triang | lra].
Qed.

(** ** compensated_dot3, operation by operation.  [stage1] is [dot3_rounded a b]; the C++ loop
    computes l_i then g_i for i = 0, 1, 2.  The C++ replaces the radius by +inf when hi or lo is not
    finite: in the model nothing overflows, so that branch is not taken (proofs/README.md, "Overflow"). *)
Definition compensated_dot3 (a0 a1 a2 al0 al1 al2 b0 b1 b2 : R) : Enclosure :=
  let stage1 := dot3_rounded a0 a1 a2 b0 b1 b2 in
  let h0 := product0 stage1 in let h1 := product1 stage1 in let h2 := product2 stage1 in
  let l0 := fma a0 b0 (- h0) in let g0 := fma al0 b0 l0 in
  let l1 := fma a1 b1 (- h1) in let g1 := fma al1 b1 l1 in
  let l2 := fma a2 b2 (- h2) in let g2 := fma al2 b2 l2 in
  let s2 := two_sum h0 h1 in
  let s3 := two_sum (fst s2) h2 in
  let lo := RN (RN (RN (g0 + g1) + g2) + RN (snd s2 + snd s3)) in
  let radius := RN (RN (compensated_relative * magnitude stage1) + compensated_absolute) in
  {| hi := fst s3; lo := lo; radius := radius |}.

Lemma compensated_relative_val : compensated_relative = 32 * (u * u).
Proof. unfold compensated_relative. rewrite u_val. simpl bpow. lra. Qed.

Lemma compensated_absolute_eta : compensated_absolute = 32 * eta.
Proof.
  unfold compensated_absolute, eta. replace (-1070)%Z with (5 + -1075)%Z by lia.
  rewrite bpow_plus. simpl bpow. lra.
Qed.

Lemma binary64_compensated_absolute : binary64 compensated_absolute.
Proof. apply binary64_bpow. lia. Qed.

(** One term: V_i = (a + α)·b = h + g + δ with |δ| ≤ 4u²|h| + 3η and |g| ≤ 3u|h| + 4η, where
    h = a ⊗ b, l = fma(a, b, −h), g = fma(α, b, l). *)
Lemma term_error : forall a al b, binary64 a -> binary64 b -> Rabs al <= u * Rabs a ->
  let h := RN (a * b) in
  let g := fma al b (fma a b (- h)) in
  Rabs ((a + al) * b - (h + g)) <= 4 * (u * u) * Rabs h + 3 * eta /\
  Rabs g <= 3 * u * Rabs h + 4 * eta.
Proof.
  intros a al b Ba Bb Hal h g.
  set (l := fma a b (- h)) in g.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  (* ab − h, its rounding l, and the error λ of that rounding *)
  pose proof (RN_err_round (a * b)) as Eh. fold h in Eh.
  assert (El : Rabs (l - (a * b - h)) <= u * Rabs (a * b - h) + eta).
  { unfold l, fma. replace (a * b + - h) with (a * b - h) by ring. apply RN_err. }
  assert (Eab : Rabs (a * b - h) <= u * Rabs h + eta) by (rewrite Rabs_minus_sym; exact Eh).
  assert (Hab : Rabs (a * b) <= Rabs h + (u * Rabs h + eta)) by (apply Rabs_close'; exact Eh).
  (* |α b| ≤ u|ab| *)
  assert (Hb : Rabs (al * b) <= u * Rabs (a * b)).
  { rewrite Rabs_mult, (Rabs_mult a b), <- Rmult_assoc.
    apply Rmult_le_compat_r; [apply Rabs_pos | exact Hal]. }
  assert (Hl : Rabs l <= Rabs (a * b - h) + (u * Rabs (a * b - h) + eta)) by (apply Rabs_close; exact El).
  (* g and its rounding error γ *)
  assert (Eg : Rabs (g - (al * b + l)) <= u * Rabs (al * b + l) + eta) by apply RN_err.
  pose proof (Rabs_triang (al * b) l) as T.
  assert (Hg : Rabs g <= Rabs (al * b + l) + (u * Rabs (al * b + l) + eta)) by (apply Rabs_close; exact Eg).
  pose proof (Rabs_pos h). pose proof (Rabs_pos (a * b - h)). pose proof (Rabs_pos (al * b + l)).
  split.
  - replace ((a + al) * b - (h + g)) with (- (l - (a * b - h)) - (g - (al * b + l))) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp, Rabs_Ropp.
    rewrite u_val in *. nra.
  - rewrite u_val in *. nra.
Qed.

(** ** Main theorem of stage 2. *)
Theorem compensated_dot3_enclosure : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  binary64 a0 -> binary64 a1 -> binary64 a2 -> binary64 al0 -> binary64 al1 -> binary64 al2 ->
  binary64 b0 -> binary64 b1 -> binary64 b2 ->
  Rabs al0 <= u * Rabs a0 -> Rabs al1 <= u * Rabs a1 -> Rabs al2 <= u * Rabs a2 ->
  encloses (compensated_dot3 a0 a1 a2 al0 al1 al2 b0 b1 b2)
    ((a0 + al0) * b0 + (a1 + al1) * b1 + (a2 + al2) * b2).
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 Ba0 Ba1 Ba2 Bal0 Bal1 Bal2 Bb0 Bb1 Bb2 H0 H1 H2.
  destruct (magnitude_bound a0 a1 a2 b0 b1 b2) as [Pm Qm].
  unfold encloses, compensated_dot3. cbn [hi lo radius].
  set (stage1 := dot3_rounded a0 a1 a2 b0 b1 b2) in *.
  set (m := magnitude stage1) in *.
  assert (Eh0 : product0 stage1 = RN (a0 * b0)) by reflexivity.
  assert (Eh1 : product1 stage1 = RN (a1 * b1)) by reflexivity.
  assert (Eh2 : product2 stage1 = RN (a2 * b2)) by reflexivity.
  set (h0 := product0 stage1) in *. set (h1 := product1 stage1) in *. set (h2 := product2 stage1) in *.
  destruct (term_error a0 al0 b0 Ba0 Bb0 H0) as [D0 G0]. rewrite <- Eh0 in D0, G0.
  destruct (term_error a1 al1 b1 Ba1 Bb1 H1) as [D1 G1]. rewrite <- Eh1 in D1, G1.
  destruct (term_error a2 al2 b2 Ba2 Bb2 H2) as [D2 G2]. rewrite <- Eh2 in D2, G2.
  set (g0 := fma al0 b0 (fma a0 b0 (- h0))) in *.
  set (g1 := fma al1 b1 (fma a1 b1 (- h1))) in *.
  set (g2 := fma al2 b2 (fma a2 b2 (- h2))) in *.
  assert (Bh0 : binary64 h0) by (rewrite Eh0; apply binary64_RN).
  assert (Bh1 : binary64 h1) by (rewrite Eh1; apply binary64_RN).
  assert (Bh2 : binary64 h2) by (rewrite Eh2; apply binary64_RN).
  assert (Bg0 : binary64 g0) by apply binary64_RN.
  assert (Bg1 : binary64 g1) by apply binary64_RN.
  assert (Bg2 : binary64 g2) by apply binary64_RN.
  (* the two TwoSums *)
  set (s2 := fst (two_sum h0 h1)). set (c2 := snd (two_sum h0 h1)).
  pose proof (two_sum_exact h0 h1 Bh0 Bh1) as X2. fold s2 c2 in X2.
  destruct (two_sum_lo_bound h0 h1 Bh0 Bh1) as [C2 _]. fold c2 in C2.
  assert (Bs2 : binary64 s2) by apply binary64_two_sum_hi.
  set (s3 := fst (two_sum s2 h2)). set (c3 := snd (two_sum s2 h2)).
  pose proof (two_sum_exact s2 h2 Bs2 Bh2) as X3. fold s3 c3 in X3.
  destruct (two_sum_lo_bound s2 h2 Bs2 Bh2) as [C3 _]. fold c3 in C3.
  assert (Bc2 : binary64 c2) by apply binary64_two_sum_lo.
  assert (Bc3 : binary64 c3) by apply binary64_two_sum_lo.
  assert (S2 : Rabs s2 <= Rabs h0 + Rabs h1 + Rabs c2).
  { replace s2 with (h0 + h1 - c2) by lra.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp.
    pose proof (Rabs_triang h0 h1). lra. }
  pose proof (Rabs_triang h0 h1). pose proof (Rabs_triang s2 h2).
  (* the sum tree of lo *)
  set (t1 := RN (g0 + g1)). set (t2 := RN (t1 + g2)). set (t3 := RN (c2 + c3)).
  assert (Bt1 : binary64 t1) by apply binary64_RN.
  assert (Bt2 : binary64 t2) by apply binary64_RN.
  assert (Bt3 : binary64 t3) by apply binary64_RN.
  pose proof (RN_plus_err g0 g1 Bg0 Bg1) as E1. fold t1 in E1.
  pose proof (RN_plus_err t1 g2 Bt1 Bg2) as E2. fold t2 in E2.
  pose proof (RN_plus_err c2 c3 Bc2 Bc3) as E3. fold t3 in E3.
  pose proof (RN_plus_err t2 t3 Bt2 Bt3) as E4.
  set (lo := RN (t2 + t3)) in *.
  pose proof (Rabs_triang g0 g1). pose proof (Rabs_triang t1 g2).
  pose proof (Rabs_triang c2 c3). pose proof (Rabs_triang t2 t3).
  assert (T1 : Rabs t1 <= Rabs (g0 + g1) + u * Rabs (g0 + g1)) by (apply Rabs_close; exact E1).
  assert (T2 : Rabs t2 <= Rabs (t1 + g2) + u * Rabs (t1 + g2)) by (apply Rabs_close; exact E2).
  assert (T3 : Rabs t3 <= Rabs (c2 + c3) + u * Rabs (c2 + c3)) by (apply Rabs_close; exact E3).
  (* the radius *)
  set (Km := RN (compensated_relative * m)).
  pose proof u_pos as Hu. pose proof eta_pos as He.
  assert (PK : 0 <= compensated_relative * m).
  { apply Rmult_le_pos; [rewrite compensated_relative_val, u_val; lra | exact Pm]. }
  assert (EK : Rabs (Km - compensated_relative * m) <= u * (compensated_relative * m) + eta).
  { pose proof (RN_err (compensated_relative * m)) as Hk. rewrite (Rabs_nonneg_eq (compensated_relative * m)) in Hk by exact PK. exact Hk. }
  assert (PKm : 0 <= Km) by (apply RN_nonneg; exact PK).
  set (E := RN (Km + compensated_absolute)).
  assert (EE : Rabs (E - (Km + compensated_absolute)) <= u * Rabs (Km + compensated_absolute)).
  { apply RN_plus_err; [apply binary64_RN | apply binary64_compensated_absolute]. }
  rewrite compensated_absolute_eta in EE.
  rewrite (Rabs_nonneg_eq (Km + 32 * eta)) in EE by lra.
  (* the decomposition of the error *)
  replace ((a0 + al0) * b0 + (a1 + al1) * b1 + (a2 + al2) * b2 - (s3 + lo))
    with (((a0 + al0) * b0 - (h0 + g0)) + ((a1 + al1) * b1 - (h1 + g1)) + ((a2 + al2) * b2 - (h2 + g2))
          - (t1 - (g0 + g1)) - (t2 - (t1 + g2)) - (t3 - (c2 + c3)) - (lo - (t2 + t3)))
    by lra.
  set (x1 := (a0 + al0) * b0 - (h0 + g0)) in *. set (x2 := (a1 + al1) * b1 - (h1 + g1)) in *.
  set (x3 := (a2 + al2) * b2 - (h2 + g2)) in *.
  assert (T : forall y1 y2 y3 y4 y5 y6 y7,
    Rabs (y1 + y2 + y3 - y4 - y5 - y6 - y7) <=
      Rabs y1 + Rabs y2 + Rabs y3 + Rabs y4 + Rabs y5 + Rabs y6 + Rabs y7).
  { intros. unfold Rminus.
    repeat (eapply Rle_trans; [apply Rabs_triang | rewrite ?Rabs_Ropp; apply Rplus_le_compat_r]).
    apply Rle_refl. }
  eapply Rle_trans; [apply T|].
  apply Rabs_bounds in EK. apply Rabs_bounds in EE.
  rewrite compensated_relative_val in *.
  pose proof (Rabs_pos h0). pose proof (Rabs_pos h1). pose proof (Rabs_pos h2).
  pose proof (Rabs_pos g0). pose proof (Rabs_pos g1). pose proof (Rabs_pos g2).
  pose proof (Rabs_pos c2). pose proof (Rabs_pos c3).
  pose proof (Rabs_pos (g0 + g1)). pose proof (Rabs_pos (t1 + g2)). pose proof (Rabs_pos (c2 + c3)).
  rewrite u_val in *. lra.
Qed.

(** The two calls in intersect_certified.cpp.  den: a = d, α = 0, b = n. *)
Corollary compensated_den_enclosure : forall d0 d1 d2 n0 n1 n2,
  binary64 d0 -> binary64 d1 -> binary64 d2 -> binary64 n0 -> binary64 n1 -> binary64 n2 ->
  encloses (compensated_dot3 d0 d1 d2 0 0 0 n0 n1 n2) (d0 * n0 + d1 * n1 + d2 * n2).
Proof.
  intros. pose proof u_pos.
  assert (Z : forall x, Rabs 0 <= u * Rabs x) by (intros; rewrite Rabs_R0; pose proof (Rabs_pos x); nra).
  pose proof (compensated_dot3_enclosure d0 d1 d2 0 0 0 n0 n1 n2) as Hc.
  rewrite !Rplus_0_r in Hc. apply Hc; auto using binary64_0.
Qed.

(** num: a_i = p_i ⊖ o_i and α_i = [two_diff(p_i, o_i).lo], so a_i + α_i = p_i − o_i exactly. *)
Lemma two_diff_low_part : forall p o, binary64 p -> binary64 o ->
  let a := RN (p - o) in let al := snd (two_diff p o) in
  a + al = p - o /\ Rabs al <= u * Rabs a /\ binary64 a /\ binary64 al.
Proof.
  intros p o Bp Bo a al.
  pose proof (two_sum_exact p (- o) Bp (binary64_opp o Bo)) as X.
  destruct (two_sum_lo_bound p (- o) Bp (binary64_opp o Bo)) as [_ L].
  unfold two_diff in al. simpl in X, L. fold al in X, L.
  repeat split.
  - unfold a. exact X.
  - exact L.
  - apply binary64_RN.
  - apply binary64_two_sum_lo.
Qed.

Corollary compensated_num_enclosure : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  binary64 p0 -> binary64 p1 -> binary64 p2 -> binary64 o0 -> binary64 o1 -> binary64 o2 ->
  binary64 n0 -> binary64 n1 -> binary64 n2 ->
  encloses (compensated_dot3 (RN (p0 - o0)) (RN (p1 - o1)) (RN (p2 - o2))
              (snd (two_diff p0 o0)) (snd (two_diff p1 o1)) (snd (two_diff p2 o2)) n0 n1 n2)
    ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 Bp0 Bp1 Bp2 Bo0 Bo1 Bo2 Bn0 Bn1 Bn2.
  destruct (two_diff_low_part p0 o0 Bp0 Bo0) as [X0 [L0 [A0 B0]]].
  destruct (two_diff_low_part p1 o1 Bp1 Bo1) as [X1 [L1 [A1 B1]]].
  destruct (two_diff_low_part p2 o2 Bp2 Bo2) as [X2 [L2 [A2 B2]]].
  replace ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2)
    with ((RN (p0 - o0) + snd (two_diff p0 o0)) * n0 + (RN (p1 - o1) + snd (two_diff p1 o1)) * n1 +
          (RN (p2 - o2) + snd (two_diff p2 o2)) * n2) by (rewrite X0, X1, X2; ring).
  apply compensated_dot3_enclosure; assumption.
Qed.

(** ** compensated_dot3_refined: the second level of stage 2, operation by operation.

    The first-order low parts F = (c_2, c_3, l_0, l_1, l_2, w_0, w_1, w_2) are summed by a TwoSum chain
    whose errors ε_j are summed plainly into τ; the second-order parts w'_i (TwoProduct of α_i b_i) are
    added to τ; (X, Y) = TwoSum(s_3, σ), lo = Y ⊕ τ.  The C++ replaces the radius by +inf when X or lo
    is not finite: in the model nothing overflows (proofs/README.md, "Overflow"). *)

(** The C++ loop [for (j = 1; j < 8; ++j) { step = two_sum(sigma, first_order[j]); sigma = step.hi;
    tail += step.lo; }]. *)
Fixpoint two_sum_chain (sigma tail : R) (rest : list R) : R * R :=
  match rest with
  | nil => (sigma, tail)
  | f :: rest' =>
      let step := two_sum sigma f in
      two_sum_chain (fst step) (RN (tail + snd step)) rest'
  end.

Definition compensated_dot3_refined (a0 a1 a2 al0 al1 al2 b0 b1 b2 : R) : Enclosure :=
  let stage1 := dot3_rounded a0 a1 a2 b0 b1 b2 in
  let s2 := two_sum (product0 stage1) (product1 stage1) in
  let s3 := two_sum (fst s2) (product2 stage1) in
  let l0 := fma a0 b0 (- product0 stage1) in let w0 := two_prod al0 b0 in
  let l1 := fma a1 b1 (- product1 stage1) in let w1 := two_prod al1 b1 in
  let l2 := fma a2 b2 (- product2 stage1) in let w2 := two_prod al2 b2 in
  (* first_order = {c_2, c_3, l_0, l_1, l_2, w_0, w_1, w_2}: sigma starts at first_order[0], tail at 0 *)
  let chain := two_sum_chain (snd s2) 0 (snd s3 :: l0 :: l1 :: l2 :: fst w0 :: fst w1 :: fst w2 :: nil) in
  let tail := RN (RN (RN (snd chain + snd w0) + snd w1) + snd w2) in
  let x := two_sum (fst s3) (fst chain) in
  let lo := RN (snd x + tail) in
  let radius := RN (RN (RN (refined_relative * magnitude stage1) + RN (refined_low_relative * Rabs lo)) +
                    refined_absolute) in
  {| hi := fst x; lo := lo; radius := radius |}.

Lemma refined_relative_val : refined_relative = 512 * (u * (u * u)).
Proof. unfold refined_relative. rewrite u_val. simpl bpow. lra. Qed.

Lemma refined_low_relative_val : refined_low_relative = 2 * u.
Proof. unfold refined_low_relative. rewrite u_val. simpl bpow. lra. Qed.

Lemma refined_absolute_eta : refined_absolute = 16 * eta.
Proof. unfold refined_absolute. rewrite min_subnormal_eta. ring. Qed.

Lemma binary64_refined_absolute : binary64 refined_absolute.
Proof. pose proof constants_binary64. tauto. Qed.

(** One term: with h = a ⊗ b, l = fma(a, b, −h) and (w, w') = TwoProduct(α, b),
    (a + α)·b = h + l + w + w' + δ with |δ| ≤ 2η (the two FMA residuals, [two_prod_error]), and
    |l| ≤ u|h| + 2η, |w| ≤ u(1 + u)²|h| + 2η, |w'| ≤ u²(1 + u)²|h| + 3η. *)
Lemma refined_term : forall a al b, binary64 a -> binary64 al -> binary64 b -> Rabs al <= u * Rabs a ->
  let h := RN (a * b) in
  let l := fma a b (- h) in
  let w := two_prod al b in
  Rabs ((a + al) * b - (h + l + fst w + snd w)) <= 2 * eta /\
  Rabs l <= u * Rabs h + 2 * eta /\
  Rabs (fst w) <= u * ((1 + u) * (1 + u)) * Rabs h + 2 * eta /\
  Rabs (snd w) <= u * u * ((1 + u) * (1 + u)) * Rabs h + 3 * eta.
Proof.
  intros a al b Ba Bal Bb Hal h l w.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  pose proof (two_prod_error a b Ba Bb) as Ep. change (fst (two_prod a b)) with h in Ep.
  change (snd (two_prod a b)) with l in Ep.
  pose proof (two_prod_error al b Bal Bb) as Ew. fold w in Ew.
  pose proof (RN_err_round (a * b)) as Eh. fold h in Eh.
  assert (Ew1 : Rabs (fst w - al * b) <= u * Rabs (al * b) + eta) by apply RN_err.
  assert (Ew2 : Rabs (fst w - al * b) <= u * Rabs (fst w) + eta) by apply RN_err_round.
  assert (Hb : Rabs (al * b) <= u * Rabs (a * b)).
  { rewrite Rabs_mult, (Rabs_mult a b), <- Rmult_assoc.
    apply Rmult_le_compat_r; [apply Rabs_pos | exact Hal]. }
  assert (Hab : Rabs (a * b) <= Rabs h + (u * Rabs h + eta)) by (apply Rabs_close'; exact Eh).
  assert (Hl : Rabs l <= Rabs (a * b - h) + eta).
  { replace l with ((a * b - h) - (a * b - (h + l))) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  assert (Hw : Rabs (fst w) <= Rabs (al * b) + (u * Rabs (al * b) + eta)) by (apply Rabs_close; exact Ew1).
  assert (Hw' : Rabs (snd w) <= Rabs (al * b - fst w) + eta).
  { replace (snd w) with ((al * b - fst w) - (al * b - (fst w + snd w))) by ring.
    eapply Rle_trans; [apply Rabs_triang|]. rewrite Rabs_Ropp. lra. }
  rewrite Rabs_minus_sym in Eh, Ew2.
  pose proof (Rabs_pos h). pose proof (Rabs_pos (al * b)). pose proof (Rabs_pos (fst w)).
  repeat split.
  - replace ((a + al) * b - (h + l + fst w + snd w))
      with ((a * b - (h + l)) + (al * b - (fst w + snd w))) by ring.
    eapply Rle_trans; [apply Rabs_triang | lra].
  - lra.
  - rewrite u_val in *. nra.
  - rewrite u_val in *. nra.
Qed.

(** The TwoSum chain, with P = (1 + u)^j after j steps: the exact sum is kept (σ + E, E the exact sum
    of the errors ε), and with A = Σ|F| so far, B ≥ Σ|ε| so far: |σ| ≤ P·A, B ≤ (P − 1)·A, |E| ≤ B and
    the plain sum τ of the ε satisfies |τ − E| ≤ (P − 1)·B. *)
Lemma two_sum_chain_invariant : forall rest sigma tail E B A (j : nat),
  binary64 sigma -> binary64 tail -> Forall (fun x => binary64 x) rest ->
  Rabs sigma <= (1 + u) ^ j * A -> B <= ((1 + u) ^ j - 1) * A -> Rabs E <= B ->
  Rabs (tail - E) <= ((1 + u) ^ j - 1) * B ->
  exists E' B',
    fst (two_sum_chain sigma tail rest) + E' = sigma + E + sum_list rest /\
    binary64 (fst (two_sum_chain sigma tail rest)) /\ binary64 (snd (two_sum_chain sigma tail rest)) /\
    B' <= ((1 + u) ^ (j + length rest) - 1) * (A + sum_abs rest) /\ Rabs E' <= B' /\
    Rabs (snd (two_sum_chain sigma tail rest) - E') <= ((1 + u) ^ (j + length rest) - 1) * B'.
Proof.
  induction rest as [|f rest IH]; intros sigma tail E B A j Bs Bt Br Hs HB HE Ht.
  - exists E, B. cbn [two_sum_chain fst snd sum_list sum_abs length].
    rewrite Nat.add_0_r, !Rplus_0_r. repeat split; assumption.
  - cbn [two_sum_chain sum_list sum_abs length]. inversion Br as [|x l Bf Br']. subst x l.
    set (s := fst (two_sum sigma f)). set (e := snd (two_sum sigma f)).
    pose proof (two_sum_exact sigma f Bs Bf) as X. fold s e in X.
    destruct (two_sum_lo_bound sigma f Bs Bf) as [Le _]. fold e in Le.
    assert (Es : Rabs (s - (sigma + f)) <= u * Rabs (sigma + f)) by (apply RN_plus_err; assumption).
    pose proof u_pos as Hu.
    pose proof (pow_R1_Rle (1 + u) j ltac:(lra)) as P1.
    set (P := (1 + u) ^ j) in *.
    pose proof (Rabs_pos f) as Pf. pose proof (Rabs_pos e) as Pe.
    assert (PB : 0 <= B) by (eapply Rle_trans; [apply Rabs_pos | exact HE]).
    (* |σ + f| ≤ P (A + |f|) *)
    assert (F1 : Rabs f <= P * Rabs f) by (rewrite <- (Rmult_1_l (Rabs f)) at 1; apply Rmult_le_compat_r; lra).
    assert (Sf : Rabs (sigma + f) <= P * (A + Rabs f)).
    { eapply Rle_trans; [apply Rabs_triang|]. rewrite Rmult_plus_distr_l. lra. }
    pose proof (Rabs_pos (sigma + f)) as Psf.
    assert (Hs' : Rabs s <= (1 + u) ^ S j * (A + Rabs f)).
    { simpl. fold P. apply Rabs_close in Es.
      assert (u * Rabs (sigma + f) <= u * (P * (A + Rabs f))) by (apply Rmult_le_compat_l; lra).
      lra. }
    assert (F2 : (P - 1) * A <= (P - 1) * (A + Rabs f)) by (apply Rmult_le_compat_l; lra).
    assert (F3 : u * Rabs (sigma + f) <= u * (P * (A + Rabs f))) by (apply Rmult_le_compat_l; lra).
    assert (HB' : B + Rabs e <= ((1 + u) ^ S j - 1) * (A + Rabs f)).
    { simpl. fold P. lra. }
    assert (HE' : Rabs (E + e) <= B + Rabs e) by (eapply Rle_trans; [apply Rabs_triang | lra]).
    (* the plain sum of the errors *)
    assert (Et : Rabs (RN (tail + e) - (tail + e)) <= u * Rabs (tail + e)).
    { apply RN_plus_err; [exact Bt | apply binary64_two_sum_lo]. }
    assert (Te : Rabs (tail + e) <= P * B + Rabs e).
    { replace (tail + e) with ((tail - E) + E + e) by ring.
      eapply Rle_trans; [apply Rabs_triang|].
      pose proof (Rabs_triang (tail - E) E). lra. }
    assert (F4 : u * Rabs (tail + e) <= u * (P * B + Rabs e)) by (apply Rmult_le_compat_l; lra).
    assert (F5 : u * Rabs e <= ((1 + u) * P - 1) * Rabs e).
    { apply Rmult_le_compat_r; [lra|]. assert (u * 1 <= u * P) by (apply Rmult_le_compat_l; lra). lra. }
    assert (Ht' : Rabs (RN (tail + e) - (E + e)) <= ((1 + u) ^ S j - 1) * (B + Rabs e)).
    { simpl. fold P.
      replace (RN (tail + e) - (E + e)) with ((RN (tail + e) - (tail + e)) + (tail - E)) by ring.
      eapply Rle_trans; [apply Rabs_triang|]. nra. }
    destruct (IH s (RN (tail + e)) (E + e) (B + Rabs e) (A + Rabs f) (S j)
                 ltac:(apply binary64_two_sum_hi) ltac:(apply binary64_RN) Br' Hs' HB' HE' Ht')
      as [E' [B' [Q [Bq [Bl [HB'' [HE'' Ht'']]]]]]].
    replace (S j + length rest)%nat with (j + S (length rest))%nat in HB'', Ht'' by lia.
    exists E', B'. repeat split; try assumption.
    + rewrite Q. simpl in X |- *. fold s e in X |- *. lra.
    + rewrite <- Rplus_assoc. exact HB''.
Qed.

(** (1 + u)^7 − 1 ≤ 7u + 22u²: the growth over the seven steps of the chain. *)
Lemma growth_7 : 0 <= (1 + u) ^ 7 - 1 <= 7 * u + 22 * (u * u).
Proof. rewrite u_val. simpl pow. lra. Qed.

(** ** Main theorem of the second level of stage 2: for all doubles a_i, α_i, b_i with |α_i| ≤ u|a_i|,
    |Σ (a_i + α_i)·b_i − (hi + lo)| ≤ radius.  The proof bounds the error by about
    283u³·Σ|h_i| + u·|lo| + 7η, which the radius covers with m ≥ Σ|h_i|/(1 + u)²:
    512u³(1 − u)³ ≥ 284u³(1 + u)², 2u(1 − u)³ ≥ u, 16η(1 − u) − 2η ≥ 7η.  (The same proof closes with
    284u³ in place of 2^-150 = 512u³ and fails with 282u³.) *)
Theorem compensated_dot3_refined_enclosure : forall a0 a1 a2 al0 al1 al2 b0 b1 b2,
  binary64 a0 -> binary64 a1 -> binary64 a2 -> binary64 al0 -> binary64 al1 -> binary64 al2 ->
  binary64 b0 -> binary64 b1 -> binary64 b2 ->
  Rabs al0 <= u * Rabs a0 -> Rabs al1 <= u * Rabs a1 -> Rabs al2 <= u * Rabs a2 ->
  encloses (compensated_dot3_refined a0 a1 a2 al0 al1 al2 b0 b1 b2)
    ((a0 + al0) * b0 + (a1 + al1) * b1 + (a2 + al2) * b2).
Proof.
  intros a0 a1 a2 al0 al1 al2 b0 b1 b2 Ba0 Ba1 Ba2 Bal0 Bal1 Bal2 Bb0 Bb1 Bb2 H0 H1 H2.
  destruct (magnitude_bound a0 a1 a2 b0 b1 b2) as [Pm Qm].
  unfold encloses, compensated_dot3_refined. cbn [hi lo radius].
  set (stage1 := dot3_rounded a0 a1 a2 b0 b1 b2) in *.
  set (m := magnitude stage1) in *.
  assert (Eh0 : product0 stage1 = RN (a0 * b0)) by reflexivity.
  assert (Eh1 : product1 stage1 = RN (a1 * b1)) by reflexivity.
  assert (Eh2 : product2 stage1 = RN (a2 * b2)) by reflexivity.
  set (h0 := product0 stage1) in *. set (h1 := product1 stage1) in *. set (h2 := product2 stage1) in *.
  pose proof u_pos as Hu. pose proof eta_pos as He.
  (* the three terms *)
  destruct (refined_term a0 al0 b0 Ba0 Bal0 Bb0 H0) as [D0 [L0 [W0 W0']]]. rewrite <- Eh0 in D0, L0, W0, W0'.
  destruct (refined_term a1 al1 b1 Ba1 Bal1 Bb1 H1) as [D1 [L1 [W1 W1']]]. rewrite <- Eh1 in D1, L1, W1, W1'.
  destruct (refined_term a2 al2 b2 Ba2 Bal2 Bb2 H2) as [D2 [L2 [W2 W2']]]. rewrite <- Eh2 in D2, L2, W2, W2'.
  set (l0 := fma a0 b0 (- h0)) in *. set (l1 := fma a1 b1 (- h1)) in *. set (l2 := fma a2 b2 (- h2)) in *.
  set (w0 := fst (two_prod al0 b0)) in *. set (w0' := snd (two_prod al0 b0)) in *.
  set (w1 := fst (two_prod al1 b1)) in *. set (w1' := snd (two_prod al1 b1)) in *.
  set (w2 := fst (two_prod al2 b2)) in *. set (w2' := snd (two_prod al2 b2)) in *.
  assert (Bh0 : binary64 h0) by (rewrite Eh0; apply binary64_RN).
  assert (Bh1 : binary64 h1) by (rewrite Eh1; apply binary64_RN).
  assert (Bh2 : binary64 h2) by (rewrite Eh2; apply binary64_RN).
  (* the two TwoSums of the high parts *)
  set (s2 := fst (two_sum h0 h1)) in *. set (c2 := snd (two_sum h0 h1)) in *.
  pose proof (two_sum_exact h0 h1 Bh0 Bh1) as X2. fold s2 c2 in X2.
  destruct (two_sum_lo_bound h0 h1 Bh0 Bh1) as [C2 _]. fold c2 in C2.
  assert (S2 : Rabs (s2 - (h0 + h1)) <= u * Rabs (h0 + h1)) by (apply RN_plus_err; assumption).
  assert (Bs2 : binary64 s2) by apply binary64_two_sum_hi.
  set (s3 := fst (two_sum s2 h2)) in *. set (c3 := snd (two_sum s2 h2)) in *.
  pose proof (two_sum_exact s2 h2 Bs2 Bh2) as X3. fold s3 c3 in X3.
  destruct (two_sum_lo_bound s2 h2 Bs2 Bh2) as [C3 _]. fold c3 in C3.
  (* A = Σ|F| ≤ (4u + 3u² + u³)H + 12η and Σ|w'| ≤ u²(1 + u)²H + 9η, H = Σ|h_i| *)
  pose proof (Rabs_pos h0). pose proof (Rabs_pos h1). pose proof (Rabs_pos h2).
  set (HH := Rabs h0 + Rabs h1 + Rabs h2) in *.
  set (F := c3 :: l0 :: l1 :: l2 :: w0 :: w1 :: w2 :: nil).
  assert (A : Rabs c2 + sum_abs F <= (4 * u + 3 * (u * u) + u * (u * u)) * HH + 12 * eta).
  { unfold F. cbn [sum_abs].
    pose proof (Rabs_triang h0 h1). pose proof (Rabs_triang s2 h2).
    apply Rabs_close in S2. pose proof (Rabs_pos (h0 + h1)).
    assert (u * Rabs (s2 + h2) <= u * (Rabs s2 + Rabs h2)) by (apply Rmult_le_compat_l; lra).
    unfold HH. rewrite u_val in *. lra. }
  assert (Wsum : Rabs w0' + Rabs w1' + Rabs w2' <= u * u * ((1 + u) * (1 + u)) * HH + 9 * eta).
  { unfold HH. lra. }
  (* the chain *)
  assert (BF : Forall (fun x => binary64 x) F).
  { unfold F. repeat constructor; first [apply binary64_two_sum_lo | apply binary64_RN]. }
  assert (Bc2 : binary64 c2) by apply binary64_two_sum_lo.
  pose proof (Rabs_pos c2) as Pc2.
  destruct (two_sum_chain_invariant F c2 0 0 0 (Rabs c2) 0 Bc2 binary64_0 BF
              ltac:(simpl; lra) ltac:(simpl; lra) ltac:(rewrite Rabs_R0; lra)
              ltac:(rewrite Rminus_0_r, Rabs_R0; simpl; lra))
    as [E [B [XC [Bsig [Btau [HB [HE Htau]]]]]]].
  change (0 + length F)%nat with 7%nat in HB, Htau.
  set (sigma := fst (two_sum_chain c2 0 F)) in *. set (tau := snd (two_sum_chain c2 0 F)) in *.
  destruct growth_7 as [G0 G7].
  set (k := (1 + u) ^ 7 - 1) in *.
  assert (PA : 0 <= Rabs c2 + sum_abs F).
  { unfold F. cbn [sum_abs]. pose proof (Rabs_pos c3). pose proof (Rabs_pos l0). pose proof (Rabs_pos l1).
    pose proof (Rabs_pos l2). pose proof (Rabs_pos w0). pose proof (Rabs_pos w1). pose proof (Rabs_pos w2). lra. }
  assert (PB : 0 <= B) by (eapply Rle_trans; [apply Rabs_pos | exact HE]).
  assert (HB7 : B <= (7 * u + 22 * (u * u)) * (Rabs c2 + sum_abs F)).
  { eapply Rle_trans; [exact HB|]. apply Rmult_le_compat_r; lra. }
  assert (Ht7 : Rabs (tau - E) <= (7 * u + 22 * (u * u)) * B).
  { eapply Rle_trans; [exact Htau|]. apply Rmult_le_compat_r; lra. }
  clear HB Htau G0 G7. clearbody k. clear k.
  (* the plain sum τ ⊕ w'_0 ⊕ w'_1 ⊕ w'_2 *)
  set (t1 := RN (tau + w0')). set (t2 := RN (t1 + w1')). set (tail := RN (t2 + w2')).
  assert (E1 : Rabs (t1 - (tau + w0')) <= u * Rabs (tau + w0')) by (apply RN_plus_err; [exact Btau | apply binary64_RN]).
  assert (E2 : Rabs (t2 - (t1 + w1')) <= u * Rabs (t1 + w1')) by (apply RN_plus_err; apply binary64_RN).
  assert (E3 : Rabs (tail - (t2 + w2')) <= u * Rabs (t2 + w2')) by (apply RN_plus_err; apply binary64_RN).
  assert (Errt : Rabs (tau - E) + Rabs (t1 - (tau + w0')) + Rabs (t2 - (t1 + w1')) + Rabs (tail - (t2 + w2'))
                 <= (10 * u + 50 * (u * u)) * B + (3 * u + 4 * (u * u)) * (Rabs w0' + Rabs w1' + Rabs w2')).
  { assert (T0 : Rabs tau <= Rabs (tau - E) + Rabs E).
    { replace tau with ((tau - E) + E) at 1 by ring. apply Rabs_triang. }
    pose proof (Rabs_triang tau w0'). pose proof (Rabs_triang t1 w1'). pose proof (Rabs_triang t2 w2').
    assert (T1 : Rabs t1 <= Rabs (tau + w0') + u * Rabs (tau + w0')) by (apply Rabs_close; exact E1).
    assert (T2 : Rabs t2 <= Rabs (t1 + w1') + u * Rabs (t1 + w1')) by (apply Rabs_close; exact E2).
    pose proof (Rabs_pos (tau + w0')). pose proof (Rabs_pos (t1 + w1')). pose proof (Rabs_pos (t2 + w2')).
    pose proof (Rabs_pos w0'). pose proof (Rabs_pos w1'). pose proof (Rabs_pos w2').
    rewrite u_val in *. lra. }
  (* (X, Y) = TwoSum(s_3, σ), lo = Y ⊕ τ' *)
  assert (Bs3 : binary64 s3) by apply binary64_two_sum_hi.
  pose proof (two_sum_exact s3 sigma Bs3 Bsig) as XX.
  set (X := fst (two_sum s3 sigma)) in *. set (Y := snd (two_sum s3 sigma)) in *.
  assert (Elo : Rabs (RN (Y + tail) - (Y + tail)) <= u * Rabs (RN (Y + tail))).
  { apply RN_plus_err_round; [apply binary64_two_sum_lo | apply binary64_RN]. }
  set (lo := RN (Y + tail)) in *.
  (* the radius *)
  rewrite refined_relative_val, refined_low_relative_val.
  set (r0 := RN (512 * (u * (u * u)) * m)). set (r1 := RN (2 * u * Rabs lo)).
  assert (PK : 0 <= 512 * (u * (u * u)) * m) by (apply Rmult_le_pos; [rewrite u_val; lra | exact Pm]).
  assert (PL : 0 <= 2 * u * Rabs lo) by (apply Rmult_le_pos; [rewrite u_val; lra | apply Rabs_pos]).
  assert (Er0 : Rabs (r0 - 512 * (u * (u * u)) * m) <= u * (512 * (u * (u * u)) * m) + eta).
  { pose proof (RN_err (512 * (u * (u * u)) * m)) as Hk. rewrite (Rabs_nonneg_eq _ PK) in Hk. exact Hk. }
  assert (Er1 : Rabs (r1 - 2 * u * Rabs lo) <= u * (2 * u * Rabs lo) + eta).
  { pose proof (RN_err (2 * u * Rabs lo)) as Hk. rewrite (Rabs_nonneg_eq _ PL) in Hk. exact Hk. }
  assert (P0 : 0 <= r0) by (apply RN_nonneg; exact PK).
  assert (P1 : 0 <= r1) by (apply RN_nonneg; exact PL).
  assert (Er2 : Rabs (RN (r0 + r1) - (r0 + r1)) <= u * (r0 + r1)).
  { pose proof (RN_plus_err r0 r1 (binary64_RN _) (binary64_RN _)) as Hk.
    rewrite (Rabs_nonneg_eq (r0 + r1)) in Hk by lra. exact Hk. }
  set (r2 := RN (r0 + r1)) in *.
  assert (P2 : 0 <= r2) by (apply RN_nonneg; lra).
  assert (Er3 : Rabs (RN (r2 + refined_absolute) - (r2 + refined_absolute)) <= u * (r2 + refined_absolute)).
  { pose proof (RN_plus_err r2 refined_absolute (binary64_RN _) binary64_refined_absolute)
      as Hk.
    rewrite (Rabs_nonneg_eq (r2 + refined_absolute)) in Hk; [exact Hk|].
    rewrite refined_absolute_eta. lra. }
  rewrite refined_absolute_eta in Er3 |- *.
  (* the decomposition of the error *)
  assert (Dec : (a0 + al0) * b0 + (a1 + al1) * b1 + (a2 + al2) * b2 - (X + lo) =
    sum_list (((a0 + al0) * b0 - (h0 + l0 + w0 + w0')) :: ((a1 + al1) * b1 - (h1 + l1 + w1 + w1')) ::
              ((a2 + al2) * b2 - (h2 + l2 + w2 + w2')) :: (- (lo - (Y + tail))) :: (- (tau - E)) ::
              (- (t1 - (tau + w0'))) :: (- (t2 - (t1 + w1'))) :: (- (tail - (t2 + w2'))) :: nil)).
  { unfold F in XC. cbn [sum_list] in XC |- *. lra. }
  rewrite Dec. eapply Rle_trans; [apply Rabs_sum_list|]. cbn [sum_abs]. rewrite !Rabs_Ropp.
  apply Rabs_bounds in Er0. apply Rabs_bounds in Er1. apply Rabs_bounds in Er2. apply Rabs_bounds in Er3.
  pose proof (Rabs_pos lo).
  clear Dec XC X2 X3 XX.
  rewrite u_val in *. lra.
Qed.

(** The two calls of compute_refined (ray_plane_stages.hpp) and FastQuery::refined_answer
    (fast_path.hpp), as for the first level.  den: α = 0. *)
Corollary compensated_den_refined_enclosure : forall d0 d1 d2 n0 n1 n2,
  binary64 d0 -> binary64 d1 -> binary64 d2 -> binary64 n0 -> binary64 n1 -> binary64 n2 ->
  encloses (compensated_dot3_refined d0 d1 d2 0 0 0 n0 n1 n2) (d0 * n0 + d1 * n1 + d2 * n2).
Proof.
  intros. pose proof u_pos.
  assert (Z : forall x, Rabs 0 <= u * Rabs x) by (intros; rewrite Rabs_R0; pose proof (Rabs_pos x); nra).
  pose proof (compensated_dot3_refined_enclosure d0 d1 d2 0 0 0 n0 n1 n2) as Hc.
  rewrite !Rplus_0_r in Hc. apply Hc; auto using binary64_0.
Qed.

(** num: a_i = p_i ⊖ o_i and α_i = [two_diff(p_i, o_i).lo] ([two_diff_low_part]). *)
Corollary compensated_num_refined_enclosure : forall p0 p1 p2 o0 o1 o2 n0 n1 n2,
  binary64 p0 -> binary64 p1 -> binary64 p2 -> binary64 o0 -> binary64 o1 -> binary64 o2 ->
  binary64 n0 -> binary64 n1 -> binary64 n2 ->
  encloses (compensated_dot3_refined (RN (p0 - o0)) (RN (p1 - o1)) (RN (p2 - o2))
              (snd (two_diff p0 o0)) (snd (two_diff p1 o1)) (snd (two_diff p2 o2)) n0 n1 n2)
    ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2).
Proof.
  intros p0 p1 p2 o0 o1 o2 n0 n1 n2 Bp0 Bp1 Bp2 Bo0 Bo1 Bo2 Bn0 Bn1 Bn2.
  destruct (two_diff_low_part p0 o0 Bp0 Bo0) as [X0 [L0 [A0 B0]]].
  destruct (two_diff_low_part p1 o1 Bp1 Bo1) as [X1 [L1 [A1 B1]]].
  destruct (two_diff_low_part p2 o2 Bp2 Bo2) as [X2 [L2 [A2 B2]]].
  replace ((p0 - o0) * n0 + (p1 - o1) * n1 + (p2 - o2) * n2)
    with ((RN (p0 - o0) + snd (two_diff p0 o0)) * n0 + (RN (p1 - o1) + snd (two_diff p1 o1)) * n1 +
          (RN (p2 - o2) + snd (two_diff p2 o2)) * n2) by (rewrite X0, X1, X2; ring).
  apply compensated_dot3_refined_enclosure; assumption.
Qed.

(** ** enclosure_sign_lanes: v = hi ⊕ lo, 2r = radius ⊕ radius, then
    [sign_lanes(v > 2r, v < −2r)] (Model.v); v > 2r ⇒ V > 0, v < −2r ⇒ V < 0.  [enclosure_sign] is
    [static_cast<Sign>] of it. *)
Definition enclosure_sign_lanes (e : Enclosure) : Z :=
  let v := RN (hi e + lo e) in
  let twice_radius := RN (radius e + radius e) in
  sign_lanes (Rlt_bool twice_radius v) (Rlt_bool v (- twice_radius)).

Definition enclosure_sign (e : Enclosure) : sign := sign_from_Z (enclosure_sign_lanes e).

Theorem enclosure_sign_sound : forall (e : Enclosure) (V : R),
  binary64 (hi e) -> binary64 (lo e) -> binary64 (radius e) ->
  encloses e V -> certifies (enclosure_sign e) V.
Proof.
  intros [h l r] V Bh Bl Br Enc. unfold encloses in Enc. simpl in *.
  unfold enclosure_sign, enclosure_sign_lanes, sign_lanes. simpl.
  set (v := RN (h + l)). set (tw := RN (r + r)).
  pose proof (RN_plus_err_round h l Bh Bl) as Ev. fold v in Ev.
  pose proof (RN_plus_err_round r r Br Br) as Et. fold tw in Et.
  assert (Pr : 0 <= r) by (eapply Rle_trans; [apply Rabs_pos | exact Enc]).
  assert (Pt : 0 <= tw) by (apply RN_nonneg; lra).
  rewrite (Rabs_nonneg_eq tw Pt) in Et.
  apply Rabs_bounds in Ev. apply Rabs_bounds in Et. apply Rabs_bounds in Enc.
  pose proof u_pos as Hu. rewrite u_val in *.
  destruct (Rlt_bool_spec tw v) as [L|L]; destruct (Rlt_bool_spec v (- tw)) as [L'|L']; simpl.
  - exact I.
  - rewrite (Rabs_nonneg_eq v) in Ev by lra. lra.
  - rewrite (Rabs_left v) in Ev by lra. lra.
  - exact I.
Qed.

Lemma enclosure_sign_lanes_range : forall e, lane_sign (enclosure_sign_lanes e).
Proof. intros. apply sign_lanes_range. Qed.

(** ** expansion_tail_enclosure: one TwoSum pass q ← TwoSum(q, e_j), lo ← lo ⊕ r_j,
    A ← A ⊕ |r_j|, then E = (A ⊗ 2^-48) ⊕ 2μ.  [rest] is the expansion after its first component. *)
Fixpoint tail_loop (q lo magnitude : R) (rest : list R) : R * R * R :=
  match rest with
  | nil => (q, lo, magnitude)
  | e :: rest' =>
      let s := two_sum q e in
      tail_loop (fst s) (RN (lo + snd s)) (RN (magnitude + Rabs (snd s))) rest'
  end.

Definition expansion_tail_enclosure (e0 : R) (rest : list R) : Enclosure :=
  let '(q, lo, magnitude) := tail_loop e0 0 0 rest in
  {| hi := q; lo := lo; radius := RN (RN (magnitude * tail_sum_relative) + tail_sum_absolute) |}.

(** The loop invariant, with P = (1 + u)^j after j steps: the exact sum is q + R (TwoSum), and the
    rounded sums satisfy |lo − R| ≤ (P − 1)·A, |R| ≤ A and A ≤ P·magnitude, where A = Σ|r_j| exactly. *)
Lemma tail_loop_invariant : forall rest q lo mag R A (j : nat),
  binary64 q -> binary64 lo -> binary64 mag -> Forall (fun x => binary64 x) rest ->
  0 <= mag -> Rabs R <= A ->
  Rabs (lo - R) <= ((1 + u) ^ j - 1) * A -> A <= (1 + u) ^ j * mag ->
  let '(q', lo', mag') := tail_loop q lo mag rest in
  exists R' A',
    q' + R' = q + R + sum_list rest /\ binary64 q' /\ binary64 lo' /\ 0 <= mag' /\ Rabs R' <= A' /\
    Rabs (lo' - R') <= ((1 + u) ^ (j + length rest) - 1) * A' /\
    A' <= (1 + u) ^ (j + length rest) * mag'.
Proof.
  induction rest as [|e rest IH]; intros q lo mag R A j Bq Blo Bmag Brest Pmag HR Hlo HA.
  - simpl. exists R, A. rewrite Nat.add_0_r. repeat split; auto. lra.
  - cbn [tail_loop sum_list length]. inversion Brest as [|x l Be Brest']. subst.
    set (s := fst (two_sum q e)). set (r := snd (two_sum q e)).
    pose proof (two_sum_exact q e Bq Be) as X. fold s r in X.
    assert (Br : binary64 r) by apply binary64_two_sum_lo.
    set (lo1 := RN (lo + r)). set (mag1 := RN (mag + Rabs r)).
    pose proof u_pos as Hu.
    pose proof (pow_R1_Rle (1 + u) j ltac:(lra)) as P1.
    set (P := (1 + u) ^ j) in *.
    assert (E1 : Rabs (lo1 - (lo + r)) <= u * Rabs (lo + r)) by (apply RN_plus_err; assumption).
    assert (E2 : Rabs (mag1 - (mag + Rabs r)) <= u * Rabs mag1).
    { apply RN_plus_err_round; [assumption | now apply binary64_abs]. }
    pose proof (Rabs_pos r).
    assert (Pmag1 : 0 <= mag1) by (apply RN_nonneg; lra).
    rewrite (Rabs_nonneg_eq mag1 Pmag1) in E2.
    pose proof (IH s lo1 mag1 (R + r) (A + Rabs r) (S j) ltac:(apply binary64_two_sum_hi)
                   ltac:(apply binary64_RN) ltac:(apply binary64_RN) Brest' Pmag1) as IH'.
    replace (S j + length rest)%nat with (j + S (length rest))%nat in IH' by lia.
    destruct (tail_loop s lo1 mag1 rest) as [[q' lo'] mag'].
    cbv beta iota in IH' |- *.
    assert (HR' : Rabs (R + r) <= A + Rabs r) by (eapply Rle_trans; [apply Rabs_triang | lra]).
    (* the products P·A, P·|r|, P·mag that the invariant needs *)
    assert (F1 : Rabs r <= P * Rabs r) by (rewrite <- (Rmult_1_l (Rabs r)) at 1; apply Rmult_le_compat_r; lra).
    assert (F2 : P * (mag + Rabs r) <= P * ((1 + u) * mag1)).
    { apply Rmult_le_compat_l; [lra|]. apply Rabs_bounds in E2. lra. }
    assert (Hlo1 : Rabs (lo1 - (R + r)) <= ((1 + u) ^ S j - 1) * (A + Rabs r)).
    { simpl. fold P.
      replace (lo1 - (R + r)) with ((lo1 - (lo + r)) + (lo - R)) by ring.
      eapply Rle_trans; [apply Rabs_triang|].
      assert (Rabs (lo + r) <= Rabs (lo - R) + Rabs R + Rabs r).
      { replace (lo + r) with ((lo - R) + R + r) by ring.
        eapply Rle_trans; [apply Rabs_triang|]. pose proof (Rabs_triang (lo - R) R). lra. }
      rewrite u_val in *. nra. }
    assert (HA1 : A + Rabs r <= (1 + u) ^ S j * mag1).
    { simpl. fold P. rewrite u_val in *. nra. }
    destruct (IH' HR' Hlo1 HA1) as [R' [A' [Q' Rest]]].
    exists R', A'. split; [rewrite Q'; simpl in X |- *; lra | exact Rest].
Qed.

Lemma tail_sum_relative_val : tail_sum_relative = 32 * u.
Proof. unfold tail_sum_relative. rewrite u_val. simpl bpow. lra. Qed.

Lemma tail_sum_absolute_eta : tail_sum_absolute = 4 * eta.
Proof. unfold tail_sum_absolute. rewrite min_subnormal_eta. ring. Qed.

Lemma binary64_tail_sum_absolute : binary64 tail_sum_absolute.
Proof.
  unfold tail_sum_absolute, min_subnormal.
  apply generic_format_FLT. exists (Float radix2 2 (-1074)); simpl; try lia.
  unfold F2R; simpl. ring.
Qed.

(** (1 + u)^31 ≤ 1 + 31u + 500u²: the growth of the rounding errors of a 31-term sum. *)
Lemma growth_31 : (1 + u) ^ 31 <= 1 + 31 * u + 500 * (u * u).
Proof.
  rewrite u_val. simpl pow. lra.
Qed.

(** ** Main theorem of the stage-3 enclosure: for every list of at most [tail_sum_max_terms] doubles
    (nonoverlapping or not), the enclosure encloses their exact sum. *)
Theorem tail_sum_enclosure : forall (e0 : R) (rest : list R),
  binary64 e0 -> Forall (fun x => binary64 x) rest ->
  (S (length rest) <= tail_sum_max_terms)%nat ->
  encloses (expansion_tail_enclosure e0 rest) (e0 + sum_list rest).
Proof.
  intros e0 rest B0 Brest Len. unfold tail_sum_max_terms in Len.
  pose proof u_pos as Hu.
  pose proof (tail_loop_invariant rest e0 0 0 0 0 0 B0 binary64_0 binary64_0 Brest (Rle_refl 0)
                ltac:(rewrite Rabs_R0; lra) ltac:(rewrite Rminus_0_r, Rabs_R0; simpl; lra)
                ltac:(simpl; lra)) as Inv.
  unfold encloses, expansion_tail_enclosure.
  destruct (tail_loop e0 0 0 rest) as [[q lo] mag].
  destruct Inv as [R [A [X [Bq [Blo [Pmag [HR [Hlo HA]]]]]]]].
  simpl. simpl in Hlo, HA.
  set (P := (1 + u) ^ length rest) in *.
  assert (P1 : 1 <= P) by (apply pow_R1_Rle; lra).
  assert (P31 : P <= (1 + u) ^ 31) by (apply Rle_pow; [lra | lia]).
  pose proof growth_31 as G.
  assert (PA : 0 <= A) by (eapply Rle_trans; [apply Rabs_pos | exact HR]).
  (* |lo − R| ≤ (P − 1) P mag ≤ (31u + 500u²)(1 + 31u + 500u²) mag *)
  assert (F1 : (P - 1) * A <= (P - 1) * (P * mag)) by (apply Rmult_le_compat_l; lra).
  assert (F2 : (P - 1) * (P * mag) <= ((31 * u + 500 * (u * u)) * (1 + 31 * u + 500 * (u * u))) * mag).
  { rewrite <- Rmult_assoc. apply Rmult_le_compat_r; [exact Pmag|].
    apply Rmult_le_compat; lra. }
  (* the radius *)
  set (Am := RN (mag * tail_sum_relative)).
  assert (PT : 0 <= mag * tail_sum_relative) by (rewrite tail_sum_relative_val; nra).
  assert (EA : Rabs (Am - mag * tail_sum_relative) <= u * (mag * tail_sum_relative) + eta).
  { pose proof (RN_err (mag * tail_sum_relative)) as Ht.
    rewrite (Rabs_nonneg_eq (mag * tail_sum_relative)) in Ht by exact PT. exact Ht. }
  assert (PAm : 0 <= Am) by (apply RN_nonneg; exact PT).
  assert (EE : Rabs (RN (Am + tail_sum_absolute) - (Am + tail_sum_absolute)) <=
               u * Rabs (Am + tail_sum_absolute)).
  { apply RN_plus_err; [apply binary64_RN | apply binary64_tail_sum_absolute]. }
  rewrite tail_sum_absolute_eta in EE |- *. pose proof eta_pos.
  rewrite (Rabs_nonneg_eq (Am + 4 * eta)) in EE by lra.
  replace (e0 + sum_list rest - (q + lo)) with (- (lo - R)) by lra. rewrite Rabs_Ropp.
  apply Rabs_bounds in EA. apply Rabs_bounds in EE.
  rewrite tail_sum_relative_val in *. rewrite u_val in *. lra.
Qed.
