(** * Stage 3: the expansion arithmetic of kernel/src/core/expansion.hpp, as twins, proved exact.

    Twins, operation by operation (the builder's flag [exact_] is threaded through as a bool):
    [push], [finish] (zero elimination), [note_product_b], [product_b], [scale_gen] (Shewchuk's
    scale_expansion_zeroelim), [merge] and [sum_gen] (fast_expansion_sum_zeroelim with the take_smaller
    merge), [from_pair], [check_finite], [expansion_sign_b] ([Expansion::sign]: the checked sign),
    [build_expansions_gen] (plane/ray_plane_stages.hpp's ray_plane_expansions), [multiply_gen] and
    [compare_quotients_expansion_gen] (compare_quotients.hpp).  [scale_gen] and [sum_gen] take the two-term
    transformation as a parameter [fts]; the C++ uses TwoSum, [two_sum_b], and so do the names [scale_b],
    [sum_b], [build_expansions_b], [compare_quotients_expansion_b] that the theorems and the differential
    runner use.

    What is proved, for every bit pattern of the inputs:
    - [sum_gen_exact], [scale_gen_exact], [multiply_gen_exact]: when every output component is finite (and
      the builder's flag stayed true: every TwoProduct passed the guard of [note_product]), the
      expansions sum exactly: Σh = Σe + Σf, Σh = b·Σe, Σ(e·f) = Σe·Σf;
    - [build_expansions_exact]: when the builder says exact, Σnum and Σden are the exact num = (p − o)·n
      and den = d·n of the query;
    - [expansion_sign_sound]: the checked sign [expansion_sign_b] (the top component decides when it
      exceeds twice the rounded sum of the others' magnitudes) is the sign of the exact sum, for any list
      of finite doubles, nonoverlapping or not;
    - [certified_signs_expansion_sound], [compare_quotients_expansion_sound]: stage 3 of the relation and of
      the nearest-hit comparison, end to end.

    Why TwoSum where Shewchuk's algorithms use Fast2Sum, and a checked sign: Dekker's Fast2Sum is exact only
    when |a| ≥ |b|, which his algorithms get from the invariant of his Theorems 13 and 19 (the expansions
    are nonoverlapping and sorted by magnitude), and the sign of the last component is the sign of the sum
    only for nonoverlapping expansions.  With TwoSum (exact for all finite doubles) and the checked sign,
    neither fact is needed: his theorems only say how often stage 3 decides. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated PlaneClassification CompareQuotients FloatCore
  ConstantsCpp PlaneTwins.
Import ListNotations.
Open Scope R_scope.

(** ** The twins *)

(** [push(h, x)]: append x unless x == 0 (a NaN is kept, so that check_finite sees it). *)
Definition push (h : list float) (x : float) : list float := if feq x fzero then h else h ++ [x].

(** [finish(h, q)]: append q unless q == 0 and h is not empty. *)
Definition finish (h : list float) (q : float) : list float :=
  if (negb (feq q fzero) || Nat.eqb (length h) 0)%bool then h ++ [q] else h.

(** The guard of [note_product]: the compiled [bounds::exact_product_threshold] (ConstantsCpp.v), which
    [tiny_product_threshold] proves is Constants.v's [exact_product_threshold] = 2^-968. *)
Definition tiny_product : float := Cpp.exact_product_threshold.

Lemma tiny_product_threshold : B2R tiny_product = exact_product_threshold.
Proof.
  unfold tiny_product, exact_product_threshold. float_value Cpp.exact_product_threshold.
  replace (-968)%Z with (52 + -1020)%Z by reflexivity. rewrite bpow_plus. reflexivity.
Qed.

(** [note_product(a, b, p)]: the TwoProduct a·b = p + lo is exact when p == 0 with a zero factor, or
    |p| ≥ 2^-968; and p is finite. *)
Definition note_product_b (a b p : float) : bool :=
  ((if feq p fzero then (feq a fzero || feq b fzero) else fle tiny_product (fabs p)) && fin p)%bool.

(** [builder.product(a, b)]. *)
Definition product_b (ex : bool) (a b : float) : bool * (float * float) :=
  let p := two_prod_b a b in ((ex && note_product_b a b (fst p))%bool, p).

Section WithFts.
Variable fts : float -> float -> float * float.

(** [builder.scale(e, b, h)] after its first product. *)
Fixpoint scale_loop (ex : bool) (q : float) (h : list float) (rest : list float) (b : float)
  : bool * list float :=
  match rest with
  | nil => (ex, finish h q)
  | ei :: rest' =>
      let pe := product_b ex ei b in
      let p := snd pe in
      let sum := two_sum_b q (snd p) in
      let h1 := push h (snd sum) in
      let next := fts (fst p) (fst sum) in
      scale_loop (fst pe) (fst next) (push h1 (snd next)) rest' b
  end.

Definition scale_gen (ex : bool) (e : list float) (b : float) : bool * list float :=
  match e with
  | nil => (ex, nil)
  | e0 :: rest => let pe := product_b ex e0 b in
      scale_loop (fst pe) (fst (snd pe)) (push nil (snd (snd pe))) rest b
  end.

(** [take_smaller]: the next component by magnitude, f's on ties: [(fn > en) == (fn > -en)] takes e's. *)
Fixpoint merge (e : list float) : list float -> list float :=
  match e with
  | nil => fun f => f
  | en :: e' =>
      fix merge_f (f : list float) : list float :=
        match f with
        | nil => e
        | fn :: f' => if Bool.eqb (flt en fn) (flt (fneg en) fn) then en :: merge e' f else fn :: merge_f f'
        end
  end.

(** [ExpansionBuilder::sum(e, f, h)] after the first two components. *)
Fixpoint sum_loop (q : float) (h : list float) (rest : list float) : list float :=
  match rest with
  | nil => finish h q
  | x :: rest' => let t := two_sum_b q x in sum_loop (fst t) (push h (snd t)) rest'
  end.

Definition sum_gen (e f : list float) : list float :=
  match merge e f with
  | nil => nil
  | [g0] => finish nil g0
  | g0 :: g1 :: rest => let s := fts g1 g0 in sum_loop (fst s) (push nil (snd s)) rest
  end.

(** [multiply_expansions(builder, e, f)]: scale e by each component of f and sum. *)
Fixpoint accumulate (ex : bool) (e partial rest : list float) : bool * list float :=
  match rest with
  | nil => (ex, partial)
  | fj :: rest' => let t := scale_gen ex e fj in accumulate (fst t) e (sum_gen partial (snd t)) rest'
  end.

Definition multiply_gen (ex : bool) (e f : list float) : bool * list float :=
  match f with
  | nil => (ex, nil)
  | f0 :: rest => let first := scale_gen ex e f0 in accumulate (fst first) e (snd first) rest
  end.

End WithFts.

(** [from_pair(p, h)]. *)
Definition from_pair (p : float * float) : list float := finish (push nil (snd p)) (fst p).

(** [builder.check_finite(e)]. *)
Definition check_finite (ex : bool) (e : list float) : bool := (ex && forallb fin e)%bool.

(** [Expansion::sign()]: the top component decides when it exceeds twice the rounded sum of the magnitudes
    of the others (then it exceeds their exact sum); a single zero component is the zero expansion. *)
Definition lower_magnitude (e : list float) : float :=
  fold_left (fun acc x => fadd acc (fabs x)) (removelast e) fzero.

(** [top > 0 ? x >= 0 : x <= 0]: x not of the sign opposite to top's. *)
Definition weakly_signed (pos : bool) (x : float) : bool := if pos then fle fzero x else fle x fzero.

Definition expansion_sign_b (e : list float) : sign :=
  let top := last e fzero in
  let a := lower_magnitude e in
  if flt (fadd a a) (fabs top) then (if flt fzero top then Positive else Negative)
  else if (Nat.eqb (length e) 1 && feq top fzero)%bool then Zero
  else if (negb (feq top fzero) && forallb (weakly_signed (flt fzero top)) (removelast e))%bool
  then (if flt fzero top then Positive else Negative)
  else Uncertain.

(** [ray_plane_expansions(q)] (plane/ray_plane_stages.hpp): den = Σ d_i n_i and num = Σ (p_i − o_i) n_i. *)
Definition build_expansions_gen (fts : float -> float -> float * float)
  (o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2 : float) : list float * list float * bool :=
  let pd0 := product_b true d0 n0 in
  let pd1 := product_b (fst pd0) d1 n1 in
  let pd2 := product_b (fst pd1) d2 n2 in
  let den := sum_gen fts (sum_gen fts (from_pair (snd pd0)) (from_pair (snd pd1))) (from_pair (snd pd2)) in
  let t0 := scale_gen fts (fst pd2) (from_pair (two_diff_b p0 o0)) n0 in
  let t1 := scale_gen fts (fst t0) (from_pair (two_diff_b p1 o1)) n1 in
  let t2 := scale_gen fts (fst t1) (from_pair (two_diff_b p2 o2)) n2 in
  let num := sum_gen fts (sum_gen fts (snd t0) (snd t1)) (snd t2) in
  (num, den, check_finite (check_finite (fst t2) num) den).

(** [compare_quotients_expansion(first, second)] (compare_quotients.hpp) with a sign function. *)
Definition compare_quotients_expansion_gen (fts : float -> float -> float * float) (sgn : list float -> sign)
  (num1 den1 : list float) (exact1 : bool) (num2 den2 : list float) (exact2 : bool) : sign :=
  if negb (exact1 && exact2) then Uncertain else
  let m1 := multiply_gen fts true num1 den2 in
  let m2 := multiply_gen fts (fst m1) num2 den1 in
  let neg := map fneg (snd m2) in
  let delta := sum_gen fts (snd m1) neg in
  if check_finite (check_finite (check_finite (fst m2) (snd m1)) neg) delta then sgn delta else Uncertain.

(** The C++. *)
Notation scale_b := (scale_gen two_sum_b).
Notation sum_b := (sum_gen two_sum_b).
Notation build_expansions_b := (build_expansions_gen two_sum_b).
Notation compare_quotients_expansion_b := (compare_quotients_expansion_gen two_sum_b expansion_sign_b).

(** ** Exactness *)

Definition sumR (l : list float) : R := sum_list (map B2R l).
Definition all_fin (l : list float) : Prop := Forall (fun x => fin x = true) l.

Lemma sumR_app : forall l1 l2, sumR (l1 ++ l2) = sumR l1 + sumR l2.
Proof. intros l1 l2. unfold sumR. rewrite map_app. induction l1 as [|x l IH]; simpl; lra. Qed.

Lemma sumR_cons : forall x l, sumR (x :: l) = B2R x + sumR l.
Proof. reflexivity. Qed.

Lemma all_fin_app : forall l1 l2, all_fin (l1 ++ l2) -> all_fin l1 /\ all_fin l2.
Proof. intros l1 l2 H. unfold all_fin in *. now apply Forall_app in H. Qed.

Lemma feq_zero : forall x, feq x fzero = true -> fin x = true /\ B2R x = 0.
Proof.
  intros [sx|sx| |sx mx ex Hx] H.
  - split; reflexivity.
  - destruct sx; discriminate.
  - discriminate.
  - exfalso. unfold feq, Beqb, SpecFloat.SFeqb, SpecFloat.SFcompare in H. simpl in H. destruct sx; discriminate.
Qed.

(** A pushed value is in the output; a dropped one is a zero: either way finite. *)
Lemma push_spec : forall h x, all_fin (push h x) -> all_fin h /\ fin x = true /\ sumR (push h x) = sumR h + B2R x.
Proof.
  intros h x H. unfold push in *. destruct (feq x fzero) eqn:Z.
  - destruct (feq_zero x Z) as [F V]. rewrite V. repeat split; auto. lra.
  - destruct (all_fin_app _ _ H) as [A B]. inversion B. repeat split; auto.
    rewrite sumR_app. unfold sumR at 2. simpl. lra.
Qed.

Lemma finish_spec : forall h q, all_fin (finish h q) -> all_fin h /\ fin q = true /\ sumR (finish h q) = sumR h + B2R q.
Proof.
  intros h q H. unfold finish in *. destruct (negb (feq q fzero) || Nat.eqb (length h) 0)%bool eqn:C.
  - destruct (all_fin_app _ _ H) as [A B]. inversion B. repeat split; auto.
    rewrite sumR_app. unfold sumR at 2. simpl. lra.
  - apply orb_false_iff in C. destruct C as [C _]. apply negb_false_iff in C.
    destruct (feq_zero q C) as [F V]. rewrite V. repeat split; auto. lra.
Qed.

(** TwoSum, TwoProduct with the guard: exact. *)
Lemma two_sum_b_exact : forall a b, fin (snd (two_sum_b a b)) = true ->
  fin a = true /\ fin b = true /\ B2R (fst (two_sum_b a b)) + B2R (snd (two_sum_b a b)) = B2R a + B2R b.
Proof.
  intros a b H. destruct (two_sum_b_inv a b H) as [Fa [Fb [_ _]]]. repeat split; auto.
  now apply two_sum_twin_exact.
Qed.

Lemma note_product_exact : forall a b, note_product_b a b (fst (two_prod_b a b)) = true ->
  fin (snd (two_prod_b a b)) = true ->
  fin a = true /\ fin b = true /\ B2R (fst (two_prod_b a b)) + B2R (snd (two_prod_b a b)) = B2R a * B2R b.
Proof.
  intros a b N Fl. destruct (two_prod_b_inv a b Fl) as [Fa [Fb [Fh [Eh El]]]].
  repeat split; auto. rewrite Eh, El.
  apply two_prod_guard_exact; try apply binary64_B2R.
  unfold note_product_b in N. apply andb_prop in N. destruct N as [G _].
  assert (P : B2R (fst (two_prod_b a b)) = RN (B2R a * B2R b)).
  { cbn [two_prod_b fst]. now apply fmul_val. }
  destruct (feq (fst (two_prod_b a b)) fzero) eqn:Z.
  - left. destruct (feq_zero _ Z) as [_ V]. rewrite <- P, V. split; [reflexivity|].
    apply orb_prop in G. destruct G as [G|G]; [left | right]; now destruct (feq_zero _ G).
  - right. rewrite <- P. rewrite fle_val in G; [| vm_compute; reflexivity | now rewrite fabs_fin].
    destruct (Rle_bool_spec (B2R tiny_product) (B2R (fabs (fst (two_prod_b a b))))) as [L|L];
      [|discriminate]. rewrite fabs_val in L.
    replace (bpow radix2 (-968)) with (B2R tiny_product); [exact L|].
    float_value tiny_product. replace (-968)%Z with (52 + -1020)%Z by reflexivity.
    rewrite bpow_plus. reflexivity.
Qed.

Lemma sum_loop_exact : forall rest q h, all_fin (sum_loop q h rest) ->
  all_fin h /\ fin q = true /\ all_fin rest /\ sumR (sum_loop q h rest) = sumR h + B2R q + sumR rest.
Proof.
  induction rest as [|x rest IH]; intros q h H.
  - cbn [sum_loop] in *. destruct (finish_spec h q H) as [A [F S]].
    repeat split; auto; [constructor|]. rewrite S. unfold sumR. simpl. lra.
  - cbn [sum_loop] in *. destruct (IH _ _ H) as [A [_ [R S]]].
    destruct (push_spec _ _ A) as [Ah [Fl Sp]].
    destruct (two_sum_b_exact q x Fl) as [Fq [Fx E]].
    repeat split; auto.
    + constructor; auto.
    + rewrite S, Sp, sumR_cons. lra.
Qed.

Lemma merge_spec : forall e f, sumR (merge e f) = sumR e + sumR f /\
  (all_fin (merge e f) <-> all_fin e /\ all_fin f).
Proof.
  induction e as [|en e IHe]; intros f.
  - cbn. unfold sumR. simpl. split; [lra|]. unfold all_fin. intuition.
  - induction f as [|fn f IHf].
    + cbn. unfold sumR. simpl. split; [lra|]. unfold all_fin. intuition.
    + cbn [merge]. destruct (Bool.eqb (flt en fn) (flt (fneg en) fn)).
      * destruct (IHe (fn :: f)) as [S F]. rewrite !sumR_cons, S, sumR_cons. split; [lra|].
        unfold all_fin in *. rewrite !Forall_cons_iff. rewrite F, Forall_cons_iff. tauto.
      * change ((fix merge_f (f0 : list float) : list float :=
                  match f0 with
                  | [] => en :: e
                  | fn0 :: f' => if Bool.eqb (flt en fn0) (flt (fneg en) fn0) then en :: merge e f0
                                 else fn0 :: merge_f f'
                  end) f) with (merge (en :: e) f).
        destruct IHf as [S F]. rewrite !sumR_cons, S, sumR_cons. split; [lra|].
        unfold all_fin in *. rewrite !Forall_cons_iff. rewrite F, !Forall_cons_iff. tauto.
Qed.

(** ExpansionBuilder::sum with TwoSum in place of Fast2Sum: exact whenever the result is finite. *)
Theorem sum_gen_exact : forall e f, all_fin (sum_b e f) ->
  all_fin e /\ all_fin f /\ sumR (sum_b e f) = sumR e + sumR f.
Proof.
  intros e f H. destruct (merge_spec e f) as [Sm Fm].
  assert (G : all_fin (merge e f) /\ sumR (sum_gen two_sum_b e f) = sumR (merge e f)).
  { unfold sum_gen in *. destruct (merge e f) as [|g0 [|g1 rest]].
    - split; [constructor | reflexivity].
    - destruct (finish_spec [] g0 H) as [_ [F S]]. split; [constructor; auto|].
      rewrite S. unfold sumR. simpl. lra.
    - destruct (sum_loop_exact rest _ _ H) as [A [_ [R S]]].
      destruct (push_spec _ _ A) as [_ [Fl Sp]].
      destruct (two_sum_b_exact g1 g0 Fl) as [F1 [F0 E]].
      split; [repeat constructor; auto|].
      rewrite S, Sp, !sumR_cons. change (sumR []) with 0. lra. }
  destruct G as [G S]. apply Fm in G. destruct G as [Ge Gf].
  repeat split; auto. rewrite S, Sm. reflexivity.
Qed.

Lemma scale_loop_exact : forall rest ex q h b,
  let r := scale_loop two_sum_b ex q h rest b in
  fst r = true -> all_fin (snd r) ->
  ex = true /\ all_fin h /\ fin q = true /\ all_fin rest /\ (rest = nil \/ fin b = true) /\
  sumR (snd r) = sumR h + B2R q + B2R b * sumR rest.
Proof.
  induction rest as [|ei rest IH]; intros ex q h b r Hx H; subst r.
  - cbn [scale_loop fst snd] in *. destruct (finish_spec h q H) as [A [F S]].
    repeat split; auto; [constructor|]. rewrite S. unfold sumR. simpl. lra.
  - cbn [scale_loop] in *.
    set (p := two_prod_b ei b) in *.
    destruct (IH _ _ _ b Hx H) as [Ex [A [_ [R [_ S]]]]].
    cbn [product_b fst] in Ex. apply andb_prop in Ex. destruct Ex as [Ex N].
    destruct (push_spec _ _ A) as [A1 [Fn Sp2]]. destruct (push_spec _ _ A1) as [Ah [Fs Sp1]].
    destruct (two_sum_b_exact _ _ Fn) as [Fph [Fsh En]].
    destruct (two_sum_b_exact _ _ Fs) as [Fq [Fpl Es]].
    cbn [product_b snd] in *. fold p in N, Fpl, Es, En.
    destruct (note_product_exact ei b N Fpl) as [Fei [Fb Ep]]. fold p in Ep.
    repeat split; auto.
    + constructor; auto.
    + rewrite S, Sp2, Sp1, sumR_cons. unfold p in *. lra.
Qed.

(** ExpansionBuilder::scale with TwoSum in place of Fast2Sum: exact when the flag stays true (every
    TwoProduct passed note_product's guard) and the result is finite. *)
Theorem scale_gen_exact : forall ex e b, fst (scale_b ex e b) = true -> all_fin (snd (scale_b ex e b)) ->
  ex = true /\ all_fin e /\ (e = nil \/ fin b = true) /\ sumR (snd (scale_b ex e b)) = B2R b * sumR e.
Proof.
  intros ex [|e0 rest] b Hx H; unfold scale_gen in *.
  - cbn in *. repeat split; auto; try constructor. unfold sumR. simpl. ring.
  - destruct (scale_loop_exact rest _ _ _ b Hx H) as [Ex [A [Fh [R [_ S]]]]].
    cbn [product_b fst snd] in *. apply andb_prop in Ex. destruct Ex as [Ex N].
    destruct (push_spec _ _ A) as [_ [Fl Sp]].
    destruct (note_product_exact e0 b N Fl) as [F0 [Fb Ep]].
    repeat split; auto.
    + constructor; auto.
    + rewrite S, Sp, sumR_cons. change (sumR []) with 0. lra.
Qed.

Lemma from_pair_exact : forall p, all_fin (from_pair p) ->
  fin (fst p) = true /\ fin (snd p) = true /\ sumR (from_pair p) = B2R (snd p) + B2R (fst p).
Proof.
  intros p H. unfold from_pair in *. destruct (finish_spec _ _ H) as [A [F S]].
  destruct (push_spec _ _ A) as [_ [Fl Sp]]. repeat split; auto. rewrite S, Sp. unfold sumR. simpl. lra.
Qed.

Lemma check_finite_true : forall ex e, check_finite ex e = true -> ex = true /\ all_fin e.
Proof.
  intros ex e H. unfold check_finite in H. apply andb_prop in H. destruct H as [H1 H2].
  split; [exact H1|]. unfold all_fin. apply Forall_forall. exact (proj1 (forallb_forall _ _) H2).
Qed.

(** The builder's [exact()] after [build_expansions] (with TwoSum in place of Fast2Sum): num and den are
    the exact num = (p − o)·n and den = d·n of the query, whatever the 64-bit patterns of its inputs. *)
Theorem build_expansions_exact : forall o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2,
  let '(num, den, ex) := build_expansions_b o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2 in
  ex = true ->
  all_fin num /\ all_fin den /\
  sumR den = B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2 /\
  sumR num = (B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2.
Proof.
  intros. unfold build_expansions_gen. cbv zeta. intros Ex.
  apply check_finite_true in Ex. destruct Ex as [Ex Fden]. apply check_finite_true in Ex. destruct Ex as [Ex Fnum].
  (* num *)
  destruct (sum_gen_exact _ _ Fnum) as [F01 [F2 Sn]]. destruct (sum_gen_exact _ _ F01) as [F0 [F1 Sn']].
  destruct (scale_gen_exact _ _ _ Ex F2) as [Ex1 [Fd2 [_ S2]]].
  destruct (scale_gen_exact _ _ _ Ex1 F1) as [Ex0 [Fd1 [_ S1]]].
  destruct (scale_gen_exact _ _ _ Ex0 F0) as [Exd [Fd0 [_ S0]]].
  (* den *)
  destruct (sum_gen_exact _ _ Fden) as [G01 [G2 Sd]]. destruct (sum_gen_exact _ _ G01) as [G0 [G1 Sd']].
  cbn [product_b fst snd] in Exd. apply andb_prop in Exd. destruct Exd as [Exd N2].
  apply andb_prop in Exd. destruct Exd as [Exd N1]. apply andb_prop in Exd. destruct Exd as [_ N0].
  destruct (from_pair_exact _ G0) as [_ [L0 E0]]. destruct (from_pair_exact _ G1) as [_ [L1 E1]].
  destruct (from_pair_exact _ G2) as [_ [L2 E2]]. cbn [snd] in L0, L1, L2, E0, E1, E2.
  destruct (note_product_exact _ _ N0 L0) as [_ [_ P0]]. destruct (note_product_exact _ _ N1 L1) as [_ [_ P1]].
  destruct (note_product_exact _ _ N2 L2) as [_ [_ P2]].
  destruct (from_pair_exact _ Fd0) as [_ [M0 D0]]. destruct (from_pair_exact _ Fd1) as [_ [M1 D1]].
  destruct (from_pair_exact _ Fd2) as [_ [M2 D2]].
  pose proof (two_sum_twin_exact _ _ M0) as T0. pose proof (two_sum_twin_exact _ _ M1) as T1.
  pose proof (two_sum_twin_exact _ _ M2) as T2. unfold two_diff_b in *. rewrite fneg_val in T0, T1, T2.
  repeat split; auto.
  - rewrite Sd, Sd', E0, E1, E2. cbn [product_b fst snd]. lra.
  - rewrite Sn, Sn', S0, S1, S2, D0, D1, D2.
    replace (B2R (snd (two_sum_b p0 (fneg o0))) + B2R (fst (two_sum_b p0 (fneg o0)))) with (B2R p0 - B2R o0) by lra.
    replace (B2R (snd (two_sum_b p1 (fneg o1))) + B2R (fst (two_sum_b p1 (fneg o1)))) with (B2R p1 - B2R o1) by lra.
    replace (B2R (snd (two_sum_b p2 (fneg o2))) + B2R (fst (two_sum_b p2 (fneg o2)))) with (B2R p2 - B2R o2) by lra.
    ring.
Qed.

Lemma accumulate_exact : forall rest ex e partial,
  let r := accumulate two_sum_b ex e partial rest in
  fst r = true -> all_fin (snd r) ->
  ex = true /\ all_fin partial /\ sumR (snd r) = sumR partial + sumR e * sumR rest.
Proof.
  induction rest as [|fj rest IH]; intros ex e partial r Hx H; subst r.
  - cbn in *. repeat split; auto. fold (sumR partial). change (sumR []) with 0. ring.
  - cbn [accumulate] in *. destruct (IH _ _ _ Hx H) as [Ex [Fp S]].
    destruct (sum_gen_exact _ _ Fp) as [Fpar [Ft St]].
    destruct (scale_gen_exact _ _ _ Ex Ft) as [Ex0 [Fe [Fb Ss]]].
    repeat split; auto. rewrite S, St, Ss, sumR_cons. ring.
Qed.

(** [multiply_expansions] with TwoSum in place of Fast2Sum: Σ(e·f) = Σe·Σf. *)
Theorem multiply_gen_exact : forall ex e f,
  fst (multiply_gen two_sum_b ex e f) = true -> all_fin (snd (multiply_gen two_sum_b ex e f)) ->
  ex = true /\ sumR (snd (multiply_gen two_sum_b ex e f)) = sumR e * sumR f.
Proof.
  intros ex e [|f0 rest] Hx H; unfold multiply_gen in *.
  - cbn in *. split; auto. unfold sumR. simpl. ring.
  - destruct (accumulate_exact rest _ _ _ Hx H) as [Ex [Fp S]].
    destruct (scale_gen_exact _ _ _ Ex Fp) as [Ex0 [Fe [_ Ss]]].
    split; auto. rewrite S, Ss, sumR_cons. ring.
Qed.

Lemma sumR_neg : forall l, sumR (map fneg l) = - sumR l.
Proof. induction l as [|x l IH]; [unfold sumR; simpl; ring|]. cbn [map]. rewrite !sumR_cons, IH, fneg_val. ring. Qed.

Lemma all_fin_neg : forall l, all_fin (map fneg l) -> all_fin l.
Proof.
  induction l as [|x l IH]; intros H; [constructor|]. inversion H as [|y k Fx Fl].
  rewrite fneg_fin in Fx. constructor; [exact Fx | apply IH; exact Fl].
Qed.

(** ** The certified sign *)

(** (1 + u)^k ≤ 2 while k·u ≤ 1/2. *)
Lemma growth_le_2 : forall k, INR k * u <= / 2 -> (1 + u) ^ k <= 2.
Proof.
  assert (G : forall k, INR k * u <= 1 -> (1 + u) ^ k * (1 - INR k * u) <= 1).
  { induction k as [|k IH]; intros Hk; [simpl; lra|].
    rewrite S_INR in *. pose proof u_pos. pose proof (pos_INR k).
    assert (Hk' : INR k * u <= 1) by nra.
    specialize (IH Hk'). pose proof (pow_le (1 + u) k ltac:(lra)) as P.
    assert (Q : (1 + u) * (1 - (INR k + 1) * u) <= 1 - INR k * u) by nra.
    simpl. replace ((1 + u) * (1 + u) ^ k * (1 - (INR k + 1) * u))
      with ((1 + u) ^ k * ((1 + u) * (1 - (INR k + 1) * u))) by ring.
    eapply Rle_trans; [apply Rmult_le_compat_l; [exact P | exact Q] | exact IH]. }
  intros k Hk. pose proof (G k ltac:(lra)) as H. pose proof (pow_le (1 + u) k ltac:(pose proof u_pos; lra)). nra.
Qed.

Lemma fold_fin : forall l acc,
  fin (fold_left (fun a x => fadd a (fabs x)) l acc) = true -> fin acc = true.
Proof.
  induction l as [|x l IH]; intros acc H; [exact H|]. cbn [fold_left] in H. apply IH in H.
  now destruct (fadd_fin _ _ H).
Qed.

Lemma fold_magnitude : forall l acc,
  let A := fold_left (fun a x => fadd a (fabs x)) l acc in
  fin A = true -> 0 <= B2R acc ->
  fin acc = true /\ all_fin l /\ 0 <= B2R A /\ B2R acc + sum_abs (map B2R l) <= (1 + u) ^ length l * B2R A.
Proof.
  induction l as [|x l IH]; intros acc A H P; subst A.
  - cbn in *. repeat split; auto; [constructor | lra].
  - cbn [fold_left] in *. pose proof (fold_fin _ _ H) as Fa.
    destruct (fadd_inv _ _ Fa) as [Facc [Fx V]]. rewrite fabs_fin in Fx.
    assert (P' : 0 <= B2R (fadd acc (fabs x))).
    { rewrite V, fabs_val. rewrite <- RN_0. apply RN_le. pose proof (Rabs_pos (B2R x)). lra. }
    destruct (IH _ H P') as [_ [Fl [PA S]]].
    repeat split; auto; [constructor; auto|].
    rewrite V, fabs_val in S.
    destruct (RN_sum_lower (B2R acc) (Rabs (B2R x)) (binary64_B2R _) (binary64_abs _ (binary64_B2R _))
                ltac:(pose proof (Rabs_pos (B2R x)); lra)) as [_ L].
    cbn [map sum_abs length]. rewrite <- tech_pow_Rmult.
    pose proof u_pos. pose proof (pow_le (1 + u) (length l) ltac:(lra)) as Pw.
    assert (Sa : 0 <= sum_abs (map B2R l)) by (eapply Rle_trans; [apply Rabs_pos | apply Rabs_sum_list]).
    assert (Pw1 : 1 <= (1 + u) ^ length l) by (apply pow_R1_Rle; lra).
    nra.
Qed.

Lemma sum_list_app : forall l1 l2, sum_list (l1 ++ l2) = sum_list l1 + sum_list l2.
Proof. induction l1 as [|x l IH]; intros; simpl; [ring | rewrite IH; ring]. Qed.

(** A list of finite doubles none of which has the sign opposite to [pos]'s sums to that (weak) sign. *)
Lemma sum_list_weakly_signed : forall (pos : bool) l, Forall (fun x => fin x = true) l ->
  forallb (weakly_signed pos) l = true ->
  if pos then 0 <= sum_list (map B2R l) else sum_list (map B2R l) <= 0.
Proof.
  intros pos l F W. induction l as [|x l IH]; [simpl; destruct pos; lra|].
  inversion F as [|? ? Fx Fl]; subst. simpl in W. apply andb_prop in W. destruct W as [Wx Wl].
  specialize (IH Fl Wl). simpl. unfold weakly_signed in Wx.
  destruct pos; rewrite fle_val in Wx by (reflexivity || assumption).
  - destruct (Rle_bool_spec (B2R fzero) (B2R x)) as [H|H]; [|discriminate]. change (B2R fzero) with 0 in H. lra.
  - destruct (Rle_bool_spec (B2R x) (B2R fzero)) as [H|H]; [|discriminate]. change (B2R fzero) with 0 in H. lra.
Qed.

(** The certified sign is the sign of the exact sum, for any list of finite doubles (at most 2^20 of
    them; the C++ expansions have at most 288). *)
Theorem expansion_sign_sound : forall e, all_fin e -> (Z.of_nat (length e) <= 1048576)%Z ->
  certifies (expansion_sign_b e) (sumR e).
Proof.
  intros e F Len. unfold expansion_sign_b.
  destruct e as [|e0 rest] eqn:Ee.
  - cbn. unfold sumR. simpl. destruct (flt (fadd (lower_magnitude []) (lower_magnitude [])) (fabs fzero)) eqn:C;
      [vm_compute in C; discriminate|]. exact I.
  - rewrite <- Ee in *.
    assert (D : e = removelast e ++ [last e fzero]) by (apply app_removelast_last; rewrite Ee; discriminate).
    assert (Ft : fin (last e fzero) = true).
    { unfold all_fin in F. rewrite D in F. apply Forall_app in F. destruct F as [_ F]. now inversion F. }
    set (top := last e fzero) in *. set (A := lower_magnitude e).
    destruct (flt (fadd A A) (fabs top)) eqn:C.
    + (* the top decides *)
      assert (NA : nonneg A).
      { assert (Gen : forall l acc, nonneg acc -> nonneg (fold_left (fun a x => fadd a (fabs x)) l acc)).
        { induction l as [|x l IH]; intros acc N; [exact N|]. cbn. apply IH. apply fadd_nonneg; [exact N | apply fabs_nonneg]. }
        apply Gen, fzero_nonneg. }
      assert (FAA : fin (fadd A A) = true) by (apply (certifying_bound_finite _ (fabs top)); [now apply fadd_nonneg | now left]).
      destruct (fadd_inv _ _ FAA) as [FA [_ VAA]].
      destruct (fold_magnitude (removelast e) fzero FA ltac:(change (B2R fzero) with 0; lra)) as [_ [Fl [PA Sm]]].
      change (fold_left (fun a x => fadd a (fabs x)) (removelast e) fzero) with A in PA, Sm.
      change (B2R fzero) with 0 in Sm.
      rewrite flt_val in C by (try rewrite fabs_fin; assumption).
      destruct (Rlt_bool_spec (B2R (fadd A A)) (B2R (fabs top))) as [C'|C']; [clear C | discriminate].
      rewrite VAA, fabs_val in C'.
      destruct (RN_sum_lower (B2R A) (B2R A) (binary64_B2R _) (binary64_B2R _) ltac:(lra)) as [_ L2].
      (* |Σ lower| ≤ Σ|lower| ≤ (1+u)^n A ≤ (1+u)^(n+1)/2 · RN(2A) < |top| *)
      assert (Gr : (1 + u) ^ S (length (removelast e)) <= 2).
      { apply growth_le_2. rewrite INR_IZR_INZ. pose proof u_pos.
        assert (length (removelast e) < length e)%nat.
        { rewrite D at 2. rewrite app_length. simpl. lia. }
        assert (IZR (Z.of_nat (S (length (removelast e)))) <= 1048576) by (apply IZR_le; lia).
        rewrite u_val in *. lra. }
      simpl in Gr. pose proof u_pos. pose proof (pow_le (1 + u) (length (removelast e)) ltac:(lra)).
      assert (Lower : Rabs (sum_list (map B2R (removelast e))) < Rabs (B2R top)).
      { eapply Rle_lt_trans; [apply Rabs_sum_list|]. nra. }
      assert (Sum : sumR e = sum_list (map B2R (removelast e)) + B2R top).
      { unfold sumR. rewrite D at 1. rewrite map_app, sum_list_app. simpl. ring. }
      rewrite Sum. clearbody top A.
      assert (Bd : - Rabs (B2R top) < sum_list (map B2R (removelast e)) < Rabs (B2R top)).
      { pose proof (Rle_abs (sum_list (map B2R (removelast e)))).
        pose proof (Rle_abs (- sum_list (map B2R (removelast e)))). rewrite Rabs_Ropp in *. lra. }
      destruct (flt fzero top) eqn:P.
      * rewrite flt_val in P by (reflexivity || assumption).
        destruct (Rlt_bool_spec (B2R fzero) (B2R top)) as [P'|P']; [clear P | discriminate].
        change (B2R fzero) with 0 in P'. cbn [certifies]. rewrite Rabs_pos_eq in Bd by lra.
        destruct Bd as [B1 B2]. clear - B1. lra.
      * rewrite flt_val in P by (reflexivity || assumption).
        destruct (Rlt_bool_spec (B2R fzero) (B2R top)) as [P'|P']; [discriminate | clear P].
        change (B2R fzero) with 0 in P'. cbn [certifies].
        assert (B2R top <> 0).
        { intros Z. rewrite Z, Rabs_R0 in C'. pose proof (RN_nonneg (B2R A + B2R A) ltac:(lra)). lra. }
        rewrite Rabs_left in Bd by lra. destruct Bd as [B1 B2]. clear - B2. lra.
    + destruct (Nat.eqb (length e) 1 && feq top fzero)%bool eqn:Z.
      * apply andb_prop in Z. destruct Z as [L Z]. apply Nat.eqb_eq in L.
        destruct (feq_zero _ Z) as [_ V]. cbn.
        destruct e as [|x [|y l]]; try (simpl in L; discriminate). unfold sumR. simpl. cbn in V. rewrite V. ring.
      * (* no lower component of the sign opposite to the nonzero top's *)
        destruct (negb (feq top fzero) && forallb (weakly_signed (flt fzero top)) (removelast e))%bool eqn:W;
          [|exact I].
        apply andb_prop in W. destruct W as [NZ W]. apply negb_true_iff in NZ.
        rewrite feq_val in NZ by (reflexivity || assumption).
        destruct (Req_bool_spec (B2R top) (B2R fzero)) as [E|E]; [discriminate|]. change (B2R fzero) with 0 in E.
        assert (Fl : Forall (fun x => fin x = true) (removelast e)).
        { unfold all_fin in F. rewrite D in F. apply Forall_app in F. tauto. }
        pose proof (sum_list_weakly_signed (flt fzero top) (removelast e) Fl W) as Sg.
        assert (Sum : sumR e = sum_list (map B2R (removelast e)) + B2R top).
        { unfold sumR. rewrite D at 1. rewrite map_app, sum_list_app. simpl. ring. }
        rewrite Sum. clearbody top A.
        destruct (flt fzero top) eqn:P.
        -- rewrite flt_val in P by (reflexivity || assumption).
           destruct (Rlt_bool_spec (B2R fzero) (B2R top)) as [P'|P']; [clear P | discriminate].
           change (B2R fzero) with 0 in P'. cbn [certifies]. lra.
        -- rewrite flt_val in P by (reflexivity || assumption).
           destruct (Rlt_bool_spec (B2R fzero) (B2R top)) as [P'|P']; [discriminate | clear P].
           change (B2R fzero) with 0 in P'. cbn [certifies]. lra.
Qed.

(** ** Lengths (the C++ capacities: num ≤ 12, den ≤ 6, products ≤ 2·12·6, Δ ≤ 2·2·12·6) *)

Lemma length_push : forall h x, (length (push h x) <= S (length h))%nat.
Proof. intros. unfold push. destruct (feq x fzero); rewrite ?app_length; simpl; lia. Qed.

Lemma length_finish : forall h q, (length (finish h q) <= S (length h))%nat.
Proof. intros. unfold finish. destruct (_ || _)%bool; rewrite ?app_length; simpl; lia. Qed.

Lemma length_sum_loop : forall rest q h, (length (sum_loop q h rest) <= length h + length rest + 1)%nat.
Proof.
  induction rest as [|x rest IH]; intros q h; cbn [sum_loop length].
  - pose proof (length_finish h q). lia.
  - pose proof (IH (fst (two_sum_b q x)) (push h (snd (two_sum_b q x)))). pose proof (length_push h (snd (two_sum_b q x))). lia.
Qed.

Lemma length_merge : forall e f, length (merge e f) = (length e + length f)%nat.
Proof.
  induction e as [|en e IHe]; intros f; [reflexivity|].
  induction f as [|fn f IHf]; [cbn; lia|]. cbn [merge].
  destruct (Bool.eqb (flt en fn) (flt (fneg en) fn)); cbn [length].
  - rewrite IHe. cbn. lia.
  - change ((fix merge_f (f0 : list float) : list float :=
              match f0 with
              | [] => en :: e
              | fn0 :: f' => if Bool.eqb (flt en fn0) (flt (fneg en) fn0) then en :: merge e f0 else fn0 :: merge_f f'
              end) f) with (merge (en :: e) f). rewrite IHf. cbn. lia.
Qed.

Lemma length_sum_gen : forall fts e f, (length (sum_gen fts e f) <= length e + length f)%nat.
Proof.
  intros fts e f. unfold sum_gen. pose proof (length_merge e f) as L.
  destruct (merge e f) as [|g0 [|g1 rest]]; cbn [length] in *.
  - lia.
  - pose proof (length_finish [] g0). simpl in *. lia.
  - pose proof (length_sum_loop rest (fst (fts g1 g0)) (push [] (snd (fts g1 g0)))).
    pose proof (length_push [] (snd (fts g1 g0))). simpl in *. lia.
Qed.

Lemma length_scale_loop : forall fts rest ex q h b,
  (length (snd (scale_loop fts ex q h rest b)) <= length h + 2 * length rest + 1)%nat.
Proof.
  intros fts. induction rest as [|x rest IH]; intros ex q h b; cbn [scale_loop length snd].
  - pose proof (length_finish h q). lia.
  - match goal with |- (length (snd (scale_loop fts ?E ?Q (push (push h ?X1) ?X2) rest b)) <= _)%nat =>
      pose proof (IH E Q (push (push h X1) X2) b); pose proof (length_push (push h X1) X2);
      pose proof (length_push h X1) end.
    lia.
Qed.

Lemma length_scale_gen : forall fts ex e b, (length (snd (scale_gen fts ex e b)) <= 2 * length e)%nat.
Proof.
  intros fts ex [|e0 rest] b; [cbn; lia|]. unfold scale_gen.
  pose proof (length_scale_loop fts rest (fst (product_b ex e0 b)) (fst (snd (product_b ex e0 b)))
                (push [] (snd (snd (product_b ex e0 b)))) b).
  pose proof (length_push [] (snd (snd (product_b ex e0 b)))). cbn [length] in *. lia.
Qed.

Lemma length_accumulate : forall fts rest ex e partial,
  (length (snd (accumulate fts ex e partial rest)) <= length partial + 2 * length e * length rest)%nat.
Proof.
  intros fts. induction rest as [|x rest IH]; intros ex e partial; cbn [accumulate length snd]; [lia|].
  pose proof (IH (fst (scale_gen fts ex e x)) e (sum_gen fts partial (snd (scale_gen fts ex e x)))).
  pose proof (length_sum_gen fts partial (snd (scale_gen fts ex e x))).
  pose proof (length_scale_gen fts ex e x). nia.
Qed.

Lemma length_multiply : forall fts ex e f, (length (snd (multiply_gen fts ex e f)) <= 2 * length e * length f)%nat.
Proof.
  intros fts ex e [|f0 rest]; [cbn; lia|]. unfold multiply_gen.
  pose proof (length_accumulate fts rest (fst (scale_gen fts ex e f0)) e (snd (scale_gen fts ex e f0))).
  pose proof (length_scale_gen fts ex e f0). cbn [length]. nia.
Qed.

Lemma length_from_pair : forall p, (length (from_pair p) <= 2)%nat.
Proof. intros p. unfold from_pair. pose proof (length_finish (push [] (snd p)) (fst p)). pose proof (length_push [] (snd p)). simpl in *. lia. Qed.

Lemma length_build_expansions : forall fts o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2,
  let '(num, den, _) := build_expansions_gen fts o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2 in
  (length num <= 12)%nat /\ (length den <= 6)%nat.
Proof.
  intros. unfold build_expansions_gen. cbv zeta. split.
  - match goal with |- (length (sum_gen fts (sum_gen fts ?a ?b) ?c) <= _)%nat =>
      pose proof (length_sum_gen fts (sum_gen fts a b) c); pose proof (length_sum_gen fts a b);
      pose proof (length_scale_gen fts (fst (product_b (fst (product_b (fst (product_b true d0 n0)) d1 n1)) d2 n2))
                    (from_pair (two_diff_b p0 o0)) n0) end.
    set (t0 := scale_gen fts _ (from_pair (two_diff_b p0 o0)) n0) in *.
    pose proof (length_scale_gen fts (fst t0) (from_pair (two_diff_b p1 o1)) n1).
    set (t1 := scale_gen fts (fst t0) (from_pair (two_diff_b p1 o1)) n1) in *.
    pose proof (length_scale_gen fts (fst t1) (from_pair (two_diff_b p2 o2)) n2).
    pose proof (length_from_pair (two_diff_b p0 o0)). pose proof (length_from_pair (two_diff_b p1 o1)).
    pose proof (length_from_pair (two_diff_b p2 o2)). lia.
  - match goal with |- (length (sum_gen fts (sum_gen fts ?a ?b) ?c) <= _)%nat =>
      pose proof (length_sum_gen fts (sum_gen fts a b) c); pose proof (length_sum_gen fts a b) end.
    pose proof (length_from_pair (snd (product_b true d0 n0))).
    pose proof (length_from_pair (snd (product_b (fst (product_b true d0 n0)) d1 n1))).
    pose proof (length_from_pair (snd (product_b (fst (product_b (fst (product_b true d0 n0)) d1 n1)) d2 n2))).
    lia.
Qed.

(** ** Stage 3 end to end *)

(** The relation's stage 3 ([certified_signs], intersect_certified.cpp): when the builder says exact, the
    checked signs of the expansions are the exact signs of num and den. *)
Theorem certified_signs_expansion_sound : forall o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2,
  let '(num, den, ex) := build_expansions_b o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2 in
  ex = true ->
  certifies (expansion_sign_b num)
    ((B2R p0 - B2R o0) * B2R n0 + (B2R p1 - B2R o1) * B2R n1 + (B2R p2 - B2R o2) * B2R n2) /\
  certifies (expansion_sign_b den) (B2R d0 * B2R n0 + B2R d1 * B2R n1 + B2R d2 * B2R n2).
Proof.
  intros. pose proof (build_expansions_exact o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2) as X.
  pose proof (length_build_expansions two_sum_b o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2) as L.
  destruct (build_expansions_b o0 o1 o2 d0 d1 d2 p0 p1 p2 n0 n1 n2) as [[num den] ex].
  intros Ex. destruct (X Ex) as [Fn [Fd [Sd Sn]]]. destruct L as [Ln Ld].
  rewrite <- Sn, <- Sd. split; apply expansion_sign_sound; auto; lia.
Qed.

(** The nearest-hit comparison's stage 3 ([compare_quotients_expansion]): a certain sign is the sign of
    Δ = Σnum_1·Σden_2 − Σnum_2·Σden_1 (each Σ the exact num or den, [build_expansions_exact]). *)
Theorem compare_quotients_expansion_sound : forall num1 den1 ex1 num2 den2 ex2,
  (length num1 <= 16)%nat -> (length den1 <= 16)%nat -> (length num2 <= 16)%nat -> (length den2 <= 16)%nat ->
  certifies (compare_quotients_expansion_b num1 den1 ex1 num2 den2 ex2)
    (sumR num1 * sumR den2 - sumR num2 * sumR den1).
Proof.
  intros num1 den1 ex1 num2 den2 ex2 L1 L2 L3 L4. unfold compare_quotients_expansion_gen.
  destruct (negb (ex1 && ex2)); [exact I|].
  set (m1 := multiply_gen two_sum_b true num1 den2). set (m2 := multiply_gen two_sum_b (fst m1) num2 den1).
  destruct (check_finite (check_finite (check_finite (fst m2) (snd m1)) (map fneg (snd m2)))
              (sum_gen two_sum_b (snd m1) (map fneg (snd m2)))) eqn:C; [|exact I].
  apply check_finite_true in C. destruct C as [C Fd]. apply check_finite_true in C. destruct C as [C Fneg].
  apply check_finite_true in C. destruct C as [X2 F1].
  destruct (multiply_gen_exact _ _ _ X2 (all_fin_neg _ Fneg)) as [X1 S2]. fold m2 in S2.
  destruct (multiply_gen_exact _ _ _ X1 F1) as [_ S1]. fold m1 in S1.
  destruct (sum_gen_exact _ _ Fd) as [_ [_ Sd]].
  assert (Len : (length (sum_gen two_sum_b (snd m1) (map fneg (snd m2))) <= 1024)%nat).
  { pose proof (length_sum_gen two_sum_b (snd m1) (map fneg (snd m2))). rewrite map_length in *.
    pose proof (length_multiply two_sum_b true num1 den2) as LM1. change (multiply_gen two_sum_b true num1 den2) with m1 in LM1.
    pose proof (length_multiply two_sum_b (fst m1) num2 den1) as LM2.
    change (multiply_gen two_sum_b (fst m1) num2 den1) with m2 in LM2.
    nia. }
  pose proof (expansion_sign_sound _ Fd ltac:(lia)) as H.
  rewrite Sd, sumR_neg, S1, S2 in H. replace (sumR num1 * sumR den2 - sumR num2 * sumR den1)
    with (sumR num1 * sumR den2 + - (sumR num2 * sumR den1)) by ring. exact H.
Qed.
