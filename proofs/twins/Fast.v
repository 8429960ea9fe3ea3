(** * Faster OCaml for four bit-by-bit loops of Coq's and Flocq's integer code (extraction only).

    Flocq's binary arithmetic normalizes significands with loops that shift one bit at a time
    ([SpecFloat.shr] iterates [shr_1], [shift_pos] iterates doubling, [digits2_pos] counts bits one by
    one, [Z.pow] multiplies repeatedly); extracted to zarith they cost O(n) big-integer operations per
    call, up to 2000 for an addition of doubles of distant exponents.  These directives replace them by
    the equivalent zarith primitives (twins/zfast.ml):
      shift_pos n z                = z · 2^n                (a left shift)
      Z.pow x y                    = x^y, 0 for y < 0       (Coq's convention)
      digits2_pos n                = the bit length of n
      shr {m, r, s} e n            = n right shifts of m with round bit r and sticky bit s:
                                     m' = |m| >> n (sign kept), r' = bit n−1 of |m|,
                                     s' = s ∨ r ∨ (bits 0..n−2 of |m| not all zero)
    This is trusted extraction, like ExtrOcamlZBigInt itself; the differential runner checks it
    (a wrong replacement would make the twins disagree with the compiled C++). *)
From Coq Require Import ZArith SpecFloat.
Require Import ExtrOcamlBasic ExtrOcamlZBigInt.
Extract Constant shift_pos => "(fun n z -> Zfast.shl z n)".
Extract Constant Z.pow => "Zfast.pow".
Extract Constant SpecFloat.digits2_pos => "Zfast.numbits".
Extract Constant SpecFloat.shr => "(fun mrs e n ->
  if Big_int_Z.sign_big_int n <= 0 then (mrs, e) else
  let (m, r, s) = Zfast.shr mrs.shr_m mrs.shr_r mrs.shr_s n in
  ({ shr_m = m; shr_r = r; shr_s = s }, Big_int_Z.add_big_int e n))".
