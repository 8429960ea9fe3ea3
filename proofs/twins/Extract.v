(** * Extraction of the twins to OCaml, for the differential runner (proofs/twins/README in
    proofs/README.md, "The twins and the differential runner").

    Every entry point takes the inputs of one call as 64-bit patterns (the runner reads them as decimal
    integers) and returns the outputs: doubles as bit patterns (every NaN as 0x7ff8000000000000, the
    runner compares NaNs as a class), signs and flags as small integers.  The functions called are the
    twins the theorems are about; the only code between them and the numbers the C++ prints is
    [of_bits]/[to_bits] (Flocq's Bits) and the OCaml main (twins/runner.ml), which parses and prints.

    Integers are extracted to zarith (ExtrOcamlZBigInt, exact); Fast.v replaces four of Coq's and
    Flocq's bit-by-bit loops by the equivalent zarith primitives (shifts, bit length, power), which
    makes the extracted arithmetic about 60 times faster.  The runner checks those replacements too: a
    wrong one would show as a mismatch against the compiled C++. *)

From Coq Require Import ZArith List.
From Raykernel Require Import Model FloatCore ConstantsCpp Twins.
Require Import ExtrOcamlBasic ExtrOcamlZBigInt.
From Raykernel Require Import Fast.
Import ListNotations.

Definition b := to_bits.
Definition f := of_bits.

Definition enc_bits (e : EnclosureB) : list Z := [b (hib e); b (lob e); b (radiusb e)].
Definition dot3_bits (r : Dot3B) : list Z := [b (qb0 r); b (qb1 r); b (qb2 r); b (valueb r); b (magnitudeb r)].

(** eft.hpp *)
Definition run_two_sum (x : list Z) : list Z :=
  match x with [a; c] => let r := two_sum_b (f a) (f c) in [b (fst r); b (snd r)] | _ => [] end.
Definition run_two_diff (x : list Z) : list Z :=
  match x with [a; c] => let r := two_diff_b (f a) (f c) in [b (fst r); b (snd r)] | _ => [] end.
Definition run_fast_two_sum (x : list Z) : list Z :=
  match x with [a; c] => let r := fast_two_sum_b (f a) (f c) in [b (fst r); b (snd r)] | _ => [] end.
Definition run_two_prod (x : list Z) : list Z :=
  match x with [a; c] => let r := two_prod_b (f a) (f c) in [b (fst r); b (snd r)] | _ => [] end.

(** dot3_filter.hpp: the rounded dot product and the filter with each constant. *)
Definition run_dot3_rounded (x : list Z) : list Z :=
  match x with [a0; a1; a2; b0; b1; b2] => dot3_bits (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2))
  | _ => [] end.
Definition run_filter (C : float) (x : list Z) : list Z :=
  match x with [a0; a1; a2; b0; b1; b2] =>
    [dot3_filter_lanes_b (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2)) C] | _ => [] end.
Definition run_filter_den := run_filter Cpp.filter_den_relative.
Definition run_filter_num := run_filter Cpp.filter_num_relative.

(** dot3_compensated.hpp: stage 1 computed from a and b, as every caller does. *)
Definition run_compensated (x : list Z) : list Z :=
  match x with [a0; a1; a2; l0; l1; l2; b0; b1; b2] =>
    enc_bits (compensated_dot3_b (f a0) (f a1) (f a2) (f l0) (f l1) (f l2) (f b0) (f b1) (f b2)
                (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2))) | _ => [] end.
Definition run_refined (x : list Z) : list Z :=
  match x with [a0; a1; a2; l0; l1; l2; b0; b1; b2] =>
    enc_bits (compensated_dot3_refined_b (f a0) (f a1) (f a2) (f l0) (f l1) (f l2) (f b0) (f b1) (f b2)
                (dot3_rounded_b (f a0) (f a1) (f a2) (f b0) (f b1) (f b2))) | _ => [] end.

(** enclosure.hpp *)
Definition run_enclosure_sign (x : list Z) : list Z :=
  match x with [h; l; r] => [enclosure_sign_lanes_b {| hib := f h; lob := f l; radiusb := f r |}] | _ => [] end.

(** expansion.hpp: the components e_0 .. e_k. *)
Definition run_tail_enclosure (x : list Z) : list Z :=
  match x with e0 :: rest => enc_bits (expansion_tail_enclosure_b (f e0) (map f rest)) | [] => [] end.

Extraction "twins.ml" run_two_sum run_two_diff run_fast_two_sum run_two_prod run_dot3_rounded run_filter_den
  run_filter_num run_compensated run_refined run_enclosure_sign run_tail_enclosure.
