(** * The sign of a difference of two products from two TwoProduct pairs
    (kernel/src/triangle/ray_triangle_stages.hpp, [product_difference_sign]).

    Each component of a tie-break vector d × (q − p) is d_j·e_k − d_k·e_j. When every leaf is one double, the
    C++ computes (h₁, l₁) = TwoProduct(a, b) and (h₂, l₂) = TwoProduct(c, e) under ExpansionBuilder's guard (a
    zero factor, or |a ⊗ b| ≥ 2^-968: Model.v's [two_prod_guard_exact]) and answers sign(h₁ − h₂) when h₁ ≠ h₂,
    else sign(l₁ − l₂), with comparisons only.

    - [pair_difference_sign]: that answer is Rcompare (a·b) (c·e), the exact sign of a·b − c·e. Different highs:
      h = RN(a·b) (the high part of TwoProduct is the rounded product), and distinct roundings order the exact
      values as they are ordered (RoundOrder.v, [rne_compare_distinct]); equal highs: the pairs are exact, so
      a·b − c·e = l₁ − l₂. *)

From Coq Require Import Reals Lra.
From Flocq Require Import Core.
From Raykernel Require Import Model RoundOrder.
Open Scope R_scope.

(** ExpansionBuilder's guard on one TwoProduct (expansion.hpp, note_product; the finiteness half is the model's
    no-overflow assumption). *)
Definition product_guard (a b : R) : Prop :=
  (RN (a * b) = 0 /\ (a = 0 \/ b = 0)) \/ bpow radix2 (-968) <= Rabs (RN (a * b)).

(** The C++'s answer, as a comparison. *)
Definition pair_difference_compare (a b c e : R) : comparison :=
  let x := two_prod a b in
  let y := two_prod c e in
  if Req_bool (fst x) (fst y) then Rcompare (snd x) (snd y) else Rcompare (fst x) (fst y).

Theorem pair_difference_sign : forall a b c e,
  binary64 a -> binary64 b -> binary64 c -> binary64 e -> product_guard a b -> product_guard c e ->
  pair_difference_compare a b c e = Rcompare (a * b) (c * e).
Proof.
  intros a b c e Ba Bb Bc Be Gx Gy. unfold pair_difference_compare.
  pose proof (two_prod_guard_exact a b Ba Bb Gx) as Ex.
  pose proof (two_prod_guard_exact c e Bc Be Gy) as Ey.
  assert (Hx : fst (two_prod a b) = RN (a * b)) by reflexivity.
  assert (Hy : fst (two_prod c e) = RN (c * e)) by reflexivity.
  destruct (Req_bool_spec (fst (two_prod a b)) (fst (two_prod c e))) as [H|H].
  - rewrite <- Ex, <- Ey, H. rewrite Rcompare_plus_l. reflexivity.
  - rewrite Hx, Hy in *. symmetry. apply rne_compare_distinct. exact H.
Qed.
