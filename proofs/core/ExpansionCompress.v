(** * The compression of an expansion, kernel/src/core/expansion.hpp's [ExpansionBuilder::compress], as a twin,
    proved exact.

    The C++ is Shewchuk's compress with TwoSum in place of his Fast2Sum.  The twin [compress_b] mirrors it pass
    by pass (lists in the order of the C++ arrays, index 0 first; [s.lo != 0] is [negb (feq (snd s) fzero)],
    false on ±0 and true on NaN, as in Expansions.v's [push]):
    - [compress_down], the first pass: q starts at the top component e[e.size − 1]; for i = e.size − 2 down to
      0 (the list [rev (removelast e)]), s = TwoSum(q, e[i]); when s.lo ≠ 0 the large part s.hi is kept below
      the ones kept before (h[--kept], the head of the list of kept parts) and q = s.lo, else q = s.hi;
    - [compress_up], the second pass: over the kept parts h[kept, e.size) from the smallest index up,
      s = TwoSum(h[i], q); when s.lo ≠ 0 it is written at h[top++] (appended to the output), and q = s.hi;
    - then h[top] = q: q appended, h.size = top + 1.
    The C++ requires e.size ≥ 1; the twin maps the empty list, which it is never called on, to itself.

    What is proved, for every bit pattern of the components:
    - [compress_gen_exact]: when every output component is finite, so is every input component and the
      compression keeps the exact sum, Σh = Σe (every TwoSum has a finite low part, so it is exact:
      Expansions.v's [two_sum_b_exact]; a low part that is dropped compares equal to 0, so it is a zero; no
      nonoverlapping invariant is needed);
    - [compress_length]: h has at most as many components as e (the capacity N of [Expansion<N>]). *)

From Coq Require Import Reals Lra Lia List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model FloatCore PlaneTwins Expansions.
Import ListNotations.
Open Scope R_scope.

(** ** The twin *)

(** The first pass: [q] the running value, [big] the large parts kept so far (h[kept, e.size), index order),
    [rest] the components still to read, from the top down (e[i] for i = e.size − 2, …, 0).  Returns the kept
    parts and q. *)
Fixpoint compress_down (q : float) (big : list float) (rest : list float) : list float * float :=
  match rest with
  | nil => (big, q)
  | x :: rest' =>
      let s := two_sum_b q x in
      if negb (feq (snd s) fzero) then compress_down (snd s) (fst s :: big) rest'
      else compress_down (fst s) big rest'
  end.

(** The second pass: [q] the running value, [low] the parts written so far (h[0, top)), [big] the kept parts
    still to read (h[i] for i = kept, …, e.size − 1); at the end, h[top] = q. *)
Fixpoint compress_up (q : float) (low : list float) (big : list float) : list float :=
  match big with
  | nil => low ++ [q]
  | b :: big' =>
      let s := two_sum_b b q in
      compress_up (fst s) (if negb (feq (snd s) fzero) then low ++ [snd s] else low) big'
  end.

(** [ExpansionBuilder::compress(e, h)]. *)
Definition compress_b (e : list float) : list float :=
  match e with
  | nil => nil
  | _ :: _ =>
      let first := compress_down (last e fzero) nil (rev (removelast e)) in
      compress_up (snd first) nil (fst first)
  end.

(** ** Exactness *)

Lemma all_fin_rev : forall l, all_fin (rev l) -> all_fin l.
Proof.
  intros l H. unfold all_fin in *. apply Forall_forall. intros x Hx.
  rewrite Forall_forall in H. apply H. now apply in_rev in Hx.
Qed.

Lemma sumR_rev : forall l, sumR (rev l) = sumR l.
Proof.
  induction l as [|x l IH]; [reflexivity|]. cbn [rev]. rewrite sumR_app, IH, !sumR_cons.
  change (sumR []) with 0. lra.
Qed.

(** The write of the second pass is [push]. *)
Lemma compress_write_push : forall low x,
  (if negb (feq x fzero) then low ++ [x] else low) = push low x.
Proof. intros low x. unfold push. now destruct (feq x fzero). Qed.

Lemma compress_up_exact : forall big q low, all_fin (compress_up q low big) ->
  all_fin low /\ fin q = true /\ all_fin big /\
  sumR (compress_up q low big) = sumR low + B2R q + sumR big.
Proof.
  induction big as [|b big IH]; intros q low H.
  - cbn [compress_up] in *. destruct (all_fin_app _ _ H) as [A B]. inversion B as [|? ? Fq].
    split; [exact A | split; [exact Fq | split; [constructor |]]].
    rewrite sumR_app, sumR_cons. change (sumR []) with 0. lra.
  - cbn [compress_up] in *. rewrite compress_write_push in H.
    destruct (IH _ _ H) as [A [_ [Fb S]]].
    destruct (push_spec _ _ A) as [Al [Fl Sp]].
    destruct (two_sum_b_exact b q Fl) as [Fb0 [Fq E]].
    repeat split; auto.
    + constructor; auto.
    + rewrite compress_write_push, S, Sp, sumR_cons. lra.
Qed.

Lemma compress_down_exact : forall rest q big,
  let r := compress_down q big rest in
  fin (snd r) = true -> all_fin (fst r) ->
  fin q = true /\ all_fin big /\ all_fin rest /\ sumR (fst r) + B2R (snd r) = sumR big + B2R q + sumR rest.
Proof.
  induction rest as [|x rest IH]; intros q big r Fr Ar; subst r.
  - cbn [compress_down fst snd] in *. split; [exact Fr | split; [exact Ar | split; [constructor |]]].
    change (sumR []) with 0. lra.
  - cbn [compress_down] in *. destruct (negb (feq (snd (two_sum_b q x)) fzero)) eqn:Z.
    + destruct (IH _ _ Fr Ar) as [Fl [Ab [Ar' S]]]. inversion Ab as [|? ? Fh Abig]; subst.
      destruct (two_sum_b_exact q x Fl) as [Fq [Fx E]].
      repeat split; auto; [constructor; auto|]. rewrite S, !sumR_cons. lra.
    + apply negb_false_iff in Z. destruct (feq_zero _ Z) as [Fl V].
      destruct (IH _ _ Fr Ar) as [Fh [Ab [Ar' S]]].
      destruct (two_sum_b_exact q x Fl) as [Fq [Fx E]].
      repeat split; auto; [constructor; auto|]. rewrite S, sumR_cons. lra.
Qed.

(** ExpansionBuilder::compress with TwoSum in place of Fast2Sum: when the output is finite, so is the input,
    and the output sums exactly to the input's sum, whatever the input (nonoverlapping or not). *)
Theorem compress_gen_exact : forall e, all_fin (compress_b e) ->
  all_fin e /\ sumR (compress_b e) = sumR e.
Proof.
  intros [|e0 rest] H; [split; [constructor | reflexivity]|].
  unfold compress_b in *. remember (e0 :: rest) as e eqn:Ee.
  assert (D : e = removelast e ++ [last e fzero]) by (apply app_removelast_last; subst e; discriminate).
  clear Ee. set (first := compress_down (last e fzero) [] (rev (removelast e))) in *.
  destruct (compress_up_exact _ _ _ H) as [_ [Fq [Ab S]]].
  destruct (compress_down_exact _ _ _ Fq Ab) as [Ft [_ [Ar Sd]]]. fold first in Sd.
  split.
  - rewrite D. unfold all_fin. apply Forall_app. split; [exact (all_fin_rev _ Ar) | now constructor].
  - rewrite S. rewrite D at 1. rewrite sumR_app, sumR_cons. rewrite sumR_rev in Sd.
    change (sumR []) with 0 in Sd |- *. lra.
Qed.

(** ** Length: h fits in e's capacity *)

Lemma length_compress_down : forall rest q big,
  (length (fst (compress_down q big rest)) <= length big + length rest)%nat.
Proof.
  induction rest as [|x rest IH]; intros q big; cbn [compress_down fst length]; [lia|].
  destruct (negb (feq (snd (two_sum_b q x)) fzero)).
  - specialize (IH (snd (two_sum_b q x)) (fst (two_sum_b q x) :: big)). cbn [length] in IH. lia.
  - specialize (IH (fst (two_sum_b q x)) big). lia.
Qed.

Lemma length_compress_up : forall big q low,
  (length (compress_up q low big) <= length low + length big + 1)%nat.
Proof.
  induction big as [|b big IH]; intros q low; cbn [compress_up length].
  - rewrite app_length. simpl. lia.
  - rewrite compress_write_push. pose proof (length_push low (snd (two_sum_b b q))).
    specialize (IH (fst (two_sum_b b q)) (push low (snd (two_sum_b b q)))). lia.
Qed.

Theorem compress_length : forall e, (length (compress_b e) <= length e)%nat.
Proof.
  intros [|e0 rest]; [cbn; lia|].
  unfold compress_b. remember (e0 :: rest) as e eqn:Ee.
  assert (D : e = removelast e ++ [last e fzero]) by (apply app_removelast_last; subst e; discriminate).
  pose proof (length_compress_down (rev (removelast e)) (last e fzero) []) as L1.
  pose proof (length_compress_up (fst (compress_down (last e fzero) [] (rev (removelast e))))
                (snd (compress_down (last e fzero) [] (rev (removelast e)))) []) as L2.
  rewrite rev_length in L1. cbn [length] in L1, L2.
  assert (Le : length e = (length (removelast e) + 1)%nat) by (rewrite D at 1; rewrite app_length; simpl; lia).
  lia.
Qed.
