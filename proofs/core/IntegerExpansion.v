(** * A 3×3 determinant of doubles as a short exact expansion, from its integer (kernel/src/core/integer_det3.hpp:
    [integer_det3_components]; tied to the C++ through the ray–triangle cascade's twin,
    triangle/TriangleIntegerSign.v and TriangleCascadeFlowTwins.v).

    IntegerDet3.v reads x·(y × z) as D·2^E, D an integer below 2^189 in magnitude ([det3_scaled],
    [det3_range]). The C++ writes |D| in chunks of 53 bits ([chunks]: c_k = ⌊|D| / 2^(53k)⌋ mod 2^53, k = 0..3)
    and each nonzero chunk as the double ±c_k·2^(E + 53k) ([dyadic]: built from its bits, exact), in increasing
    order, when its exponent lies in [−1074, 971] (then the double is exact: [binary64_dyadic], and below
    2^1024); the zero determinant is the expansion {0}, as core/expansion.hpp's convention. Otherwise it gives up
    (the caller goes on to the expansions of doubles).
    - [chunks_value]: the chunks are |D|'s digits in base 2^53 (|D| below 2^212);
    - [integer_components_sound]: at most four finite doubles whose exact sum is D·2^E — what round_quotient's
      tail enclosure and round_quotient_near need of an expansion (PlaneCompensated.v's [tail_sum_enclosure],
      QuotientBoundary.v's [round_quotient_near_sound]: finite components, a bounded count, the exact sum). *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneCompensated FloatCore Expansions.
Import ListNotations.
Open Scope R_scope.

(** The digits of M in base 2^53, lowest first: n of them. *)
Fixpoint chunks (n : nat) (M : Z) : list Z :=
  match n with
  | O => []
  | S n' => (M mod 2 ^ 53)%Z :: chunks n' (M / 2 ^ 53)%Z
  end.

(** Σ c_k·2^(53k). *)
Fixpoint chunks_weight (cs : list Z) : Z :=
  match cs with
  | [] => 0%Z
  | c :: rest => (c + 2 ^ 53 * chunks_weight rest)%Z
  end.

Lemma chunks_value : forall n M, (0 <= M)%Z -> chunks_weight (chunks n M) = (M mod 2 ^ (53 * Z.of_nat n))%Z.
Proof.
  induction n as [|n IH]; intros M P.
  - simpl. rewrite Z.mod_1_r. reflexivity.
  - cbn [chunks chunks_weight]. rewrite IH by (apply Z.div_pos; lia).
    replace (53 * Z.of_nat (S n))%Z with (53 + 53 * Z.of_nat n)%Z by lia.
    rewrite Z.pow_add_r by lia.
    rewrite (Z.rem_mul_r M (2 ^ 53) (2 ^ (53 * Z.of_nat n))) by lia. reflexivity.
Qed.

Lemma chunks_bound : forall n M c, In c (chunks n M) -> (0 <= c < 2 ^ 53)%Z.
Proof.
  induction n as [|n IH]; intros M c I; [destruct I|].
  destruct I as [<-|I]; [apply Z.mod_pos_bound; lia | exact (IH _ _ I)].
Qed.

Lemma chunks_length : forall n M, length (chunks n M) = n.
Proof. induction n as [|n IH]; intros M; simpl; [reflexivity | now rewrite IH]. Qed.

(** ±c·2^q as a double (the C++ builds its bits: the same value when −1074 ≤ q ≤ 971 and 0 ≤ c < 2^53). *)
Definition dyadic (negative : bool) (c q : Z) : float :=
  binary_normalize 53 1024 eq_refl eq_refl mode_NE (cond_Zopp negative c) q false.

Lemma dyadic_value : forall negative c q, (0 <= c < 2 ^ 53)%Z -> (-1074 <= q <= 971)%Z ->
  fin (dyadic negative c q) = true /\ B2R (dyadic negative c q) = IZR (cond_Zopp negative c) * bpow radix2 q.
Proof.
  intros negative c q C Q. unfold dyadic, fin.
  assert (A : (Z.abs (cond_Zopp negative c) < 2 ^ 53)%Z) by (destruct negative; simpl; lia).
  assert (G : binary64 (IZR (cond_Zopp negative c) * bpow radix2 q)) by (apply binary64_dyadic; lia).
  pose proof (binary_normalize_correct 53 1024 eq_refl eq_refl mode_NE (cond_Zopp negative c) q false) as H.
  cbv zeta in H. unfold F2R in H. cbn [Fnum Fexp] in H.
  rewrite (round_generic radix2 (SpecFloat.fexp 53 1024) (round_mode mode_NE)) in H by exact G.
  rewrite Rlt_bool_true in H.
  - destruct H as [V [F _]]. split; [exact F | exact V].
  - rewrite Rabs_mult, (Rabs_pos_eq (bpow radix2 q)) by apply bpow_ge_0.
    apply Rlt_le_trans with (bpow radix2 53 * bpow radix2 q).
    + apply Rmult_lt_compat_r; [apply bpow_gt_0|]. rewrite <- abs_IZR, <- IZR_Zpower by lia.
      apply IZR_lt. exact A.
    + rewrite <- bpow_plus. apply bpow_le. lia.
Qed.

(** The nonzero chunks as doubles, the first at exponent q, each next 53 higher; nothing when an exponent a
    nonzero chunk needs lies outside [−1074, 971]. *)
Fixpoint chunk_floats (negative : bool) (q : Z) (cs : list Z) : option (list float) :=
  match cs with
  | [] => Some []
  | c :: rest =>
      match chunk_floats negative (q + 53) rest with
      | None => None
      | Some l =>
          if Z.eqb c 0 then Some l
          else if (Z.leb (-1074) q && Z.leb q 971)%bool then Some (dyadic negative c q :: l) else None
      end
  end.

Lemma chunk_floats_sound : forall cs negative q l,
  (forall c, In c cs -> (0 <= c < 2 ^ 53)%Z) -> chunk_floats negative q cs = Some l ->
  all_fin l /\ sumR l = IZR (cond_Zopp negative (chunks_weight cs)) * bpow radix2 q /\ (length l <= length cs)%nat.
Proof.
  induction cs as [|c rest IH]; intros negative q l B H.
  - injection H as <-. split; [constructor|]. split; [|simpl; lia]. unfold sumR. simpl. destruct negative; simpl; ring.
  - cbn [chunk_floats] in H.
    destruct (chunk_floats negative (q + 53)%Z rest) as [l'|] eqn:R; [|discriminate].
    destruct (IH negative (q + 53)%Z l' (fun c I => B c (or_intror I)) R) as [F [S L]].
    assert (W : IZR (cond_Zopp negative (chunks_weight (c :: rest))) * bpow radix2 q =
                IZR (cond_Zopp negative c) * bpow radix2 q +
                IZR (cond_Zopp negative (chunks_weight rest)) * bpow radix2 (q + 53)%Z).
    { cbn [chunks_weight]. rewrite bpow_plus. change (bpow radix2 53) with (IZR (2 ^ 53)).
      destruct negative; cbn [cond_Zopp];
        rewrite ?opp_IZR, plus_IZR, mult_IZR; ring. }
    rewrite W. destruct (Z.eqb_spec c 0) as [Z0|N].
    + injection H as <-. subst c. split; [exact F|]. split; [rewrite S; destruct negative; simpl; ring | simpl; lia].
    + destruct (Z.leb (-1074) q && Z.leb q 971)%bool eqn:Q; [|discriminate].
      injection H as <-. apply andb_prop in Q. destruct Q as [Q1 Q2]. apply Z.leb_le in Q1, Q2.
      destruct (dyadic_value negative c q (B c (or_introl eq_refl)) (conj Q1 Q2)) as [Fd Vd].
      split; [constructor; assumption|]. split; [|simpl; lia].
      unfold sumR in *. cbn [map sum_list]. rewrite Vd, S. reflexivity.
Qed.

(** [integer_det3_components]: D·2^E as at most four doubles, increasing; {0} for D = 0. *)
Definition integer_components (D E : Z) : option (list float) :=
  match chunk_floats (Z.ltb D 0) E (chunks 4 (Z.abs D)) with
  | Some [] => Some [fzero]
  | r => r
  end.

Theorem integer_components_sound : forall D E l, (Z.abs D < 2 ^ 212)%Z -> integer_components D E = Some l ->
  all_fin l /\ sumR l = IZR D * bpow radix2 E /\ (length l <= 4)%nat.
Proof.
  intros D E l R H. unfold integer_components in H.
  destruct (chunk_floats (Z.ltb D 0) E (chunks 4 (Z.abs D))) as [l'|] eqn:C; [|discriminate].
  destruct (chunk_floats_sound _ _ _ _ (chunks_bound 4 (Z.abs D)) C) as [F [S L]].
  rewrite chunks_length in L.
  rewrite chunks_value in S by lia. change (53 * Z.of_nat 4)%Z with 212%Z in S.
  rewrite Z.mod_small in S by lia.
  assert (V : cond_Zopp (Z.ltb D 0) (Z.abs D) = D) by (destruct (Z.ltb_spec D 0); simpl; lia).
  rewrite V in S.
  destruct l' as [|x rest].
  - injection H as <-. unfold sumR in S. simpl in S.
    assert (D0 : D = 0%Z).
    { destruct (Z.eq_dec D 0) as [|N]; [assumption|]. exfalso.
      assert (P : 0 < bpow radix2 E) by apply bpow_gt_0.
      apply (Rmult_integral_contrapositive (IZR D) (bpow radix2 E)); [split; [now apply not_0_IZR | lra] | lra]. }
    subst D. split; [constructor; [reflexivity | constructor]|]. split; [|simpl; lia].
    unfold sumR. simpl. ring.
  - injection H as <-. auto.
Qed.
