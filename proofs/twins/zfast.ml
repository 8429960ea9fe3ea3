(* zarith implementations of the extraction overrides of Fast.v (zarith's Z is shadowed inside the
   extracted code, which is why they live here). *)
let numbits n = Z.of_int (Z.numbits n)
let shl z n = Z.shift_left z (Z.to_int n)
let pow x y = if Z.sign y < 0 then Z.zero else Z.pow x (Z.to_int y)

(* n right shifts of Flocq's shr_record (iter_pos shr_1 n): mantissa, round bit, sticky bit. *)
let shr m r s n =
  let k = Z.to_int n in
  let a = Z.abs m in
  let q = Z.shift_right a k in
  let rb = Z.testbit a (k - 1) in
  let low = if k > 1 then Z.extract a 0 (k - 1) else Z.zero in
  ((if Z.sign m < 0 then Z.neg q else q), rb, s || r || Z.sign low <> 0)
