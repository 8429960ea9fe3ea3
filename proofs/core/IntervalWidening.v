(** * Interval arithmetic widened by one ulp (kernel/src/core/interval.hpp).

    The C++: each binary64 operation rounded to nearest (ties to even, gradual underflow), then the lower end
    moved to [next_down] and the upper end to [next_up] of the rounded value.  Proved at two levels.

    - Over the reals (Model.v: [RN], no largest exponent): [next_up] is Flocq's [succ] and [next_down] Flocq's
      [pred] for binary64 ([FLT_exp (-1074) 53]); [pred x] is by definition [- succ (- x)], as the C++'s
      [next_down(x) = -next_up(-x)].  [widen_encloses]: pred(RN z) ≤ z ≤ succ(RN z) for every real z (Flocq's
      [pred_round_le_id], [succ_round_ge_id]); [interval_add_encloses], [interval_sub_encloses],
      [interval_neg_encloses], [interval_mul_encloses], [interval_square_encloses], [interval_div_encloses],
      [interval_sign_sound]: the computed interval holds the exact result, for all real ends (no hypothesis
      but, for the division, 0 ≤ x and 0 < b.lo).
    - On IEEE doubles (FloatCore.v's [float] and [fadd], [fmul], [flt], ...; [next_up] is Flocq's [Bsucc],
      [next_down] its [Bpred] = -Bsucc(-x)): [ieee_add_encloses], [ieee_sub_encloses], [ieee_neg_encloses],
      [ieee_mul_encloses], [ieee_square_encloses], [ieee_div_encloses], [ieee_sign_sound], with std::min and
      std::max as the C++'s comparisons and interval_detail::product as written.  The operands' ends are finite
      doubles holding x (and y) ([fin_contains]); every operation may overflow to ±inf (RoundOrder.v's
      [ieee_rn]: RN(z), or the infinity of z's sign when |RN(z)| ≥ 2^1024), and so may the widening
      (next_up(DBL_MAX) = +inf); the result holds the exact value with its ends read as extended reals
      ([fcontains]: the lower end is -inf or a finite double ≤ the value, the upper end the mirror).  No
      overflow hypothesis.

    Not covered: operands with infinite ends (the C++ allows them; then a product 0 · ±inf is NaN, which
    interval_detail::product replaces by 0 — with finite operands it is never NaN, [fproduct_fmul]) and NaN
    ends; both are argued in interval.hpp's header and tested, not proved.  That the C++'s bit-level
    [next_up] computes [Bsucc] on every non-NaN double (±0 → 2^-1074, +inf stays, -inf → -DBL_MAX, otherwise
    the next double) is checked by tests/closest_point_test.cpp, not proved. *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model FloatCore.
From Raykernel Require RoundOrder.
Open Scope R_scope.

Notation fexp := (FLT_exp (-1074) 53).

(** [next_up(x)], [next_down(x)] of interval.hpp on finite doubles. *)
Definition next_up (x : R) : R := succ radix2 fexp x.
Definition next_down (x : R) : R := pred radix2 fexp x.

Lemma next_down_next_up : forall x, next_down x = - next_up (- x).
Proof. reflexivity. Qed.

(** The widening: the exact value lies between the neighbours of its rounding. *)
Theorem widen_encloses : forall z, next_down (RN z) <= z <= next_up (RN z).
Proof.
  intros z. split.
  - apply pred_round_le_id; auto with typeclass_instances.
  - apply succ_round_ge_id; auto with typeclass_instances.
Qed.

(** A double below (above) a rounding of z is widened below (above) z. *)
Lemma down_le : forall p z, binary64 p -> p <= RN z -> next_down p <= z.
Proof.
  intros p z Fp H. apply Rle_trans with (next_down (RN z)); [| apply widen_encloses].
  apply pred_le; auto with typeclass_instances. apply binary64_RN.
Qed.

Lemma up_ge : forall p z, binary64 p -> RN z <= p -> z <= next_up p.
Proof.
  intros p z Fp H. apply Rle_trans with (next_up (RN z)); [apply widen_encloses |].
  apply succ_le; auto with typeclass_instances. apply binary64_RN.
Qed.

Lemma binary64_Rmin : forall a b, binary64 a -> binary64 b -> binary64 (Rmin a b).
Proof. intros a b Ha Hb. unfold Rmin. destruct Rle_dec; assumption. Qed.

Lemma binary64_Rmax : forall a b, binary64 a -> binary64 b -> binary64 (Rmax a b).
Proof. intros a b Ha Hb. unfold Rmax. destruct Rle_dec; assumption. Qed.

(** ** The interval type and its operations, as interval.hpp writes them. *)

Record Interval := { lo : R; hi : R }.

(** lo ≤ exact ≤ hi *)
Definition contains (a : Interval) (x : R) : Prop := lo a <= x <= hi a.

(** [operator+(a, b)] *)
Definition interval_add (a b : Interval) : Interval :=
  {| lo := next_down (RN (lo a + lo b)); hi := next_up (RN (hi a + hi b)) |}.

(** [operator-(a, b)] *)
Definition interval_sub (a b : Interval) : Interval :=
  {| lo := next_down (RN (lo a - hi b)); hi := next_up (RN (hi a - lo b)) |}.

(** [operator-(a)] *)
Definition interval_neg (a : Interval) : Interval := {| lo := - hi a; hi := - lo a |}.

(** [operator*(a, b)]: the four rounded endpoint products (finite: no 0 · ±inf), their min and max widened. *)
Definition interval_mul (a b : Interval) : Interval :=
  let p1 := RN (lo a * lo b) in let p2 := RN (lo a * hi b) in
  let p3 := RN (hi a * lo b) in let p4 := RN (hi a * hi b) in
  {| lo := next_down (Rmin (Rmin p1 p2) (Rmin p3 p4));
     hi := next_up (Rmax (Rmax p1 p2) (Rmax p3 p4)) |}.

(** [square(a)] *)
Definition interval_square (a : Interval) : Interval :=
  let l := RN (lo a * lo a) in let h := RN (hi a * hi a) in
  if Rle_bool (lo a) 0 && Rle_bool 0 (hi a) then {| lo := 0; hi := next_up (Rmax l h) |}
  else {| lo := Rmax 0 (next_down (Rmin l h)); hi := next_up (Rmax l h) |}.

(** [divide_nonnegative(a, b)] (the caller checks b.lo > 0) *)
Definition interval_div (a b : Interval) : Interval :=
  {| lo := Rmax 0 (next_down (RN (Rmax (lo a) 0 / hi b))); hi := next_up (RN (hi a / lo b)) |}.

(** [interval_sign(a)]: 1, -1, 0, or [interval_uncertain] (2), as Model.v's lane integers. *)
Definition interval_sign (a : Interval) : Z :=
  if Rlt_bool 0 (lo a) then 1%Z
  else if Rlt_bool (hi a) 0 then (-1)%Z
  else if Req_bool (lo a) 0 && Req_bool (hi a) 0 then 0%Z
  else uncertain_lane.

(** ** Enclosure. *)

Theorem interval_add_encloses : forall a b x y, contains a x -> contains b y ->
  contains (interval_add a b) (x + y).
Proof.
  intros a b x y [Ha1 Ha2] [Hb1 Hb2]. unfold contains; simpl.
  destruct (widen_encloses (lo a + lo b)). destruct (widen_encloses (hi a + hi b)). lra.
Qed.

Theorem interval_sub_encloses : forall a b x y, contains a x -> contains b y ->
  contains (interval_sub a b) (x - y).
Proof.
  intros a b x y [Ha1 Ha2] [Hb1 Hb2]. unfold contains; simpl.
  destruct (widen_encloses (lo a - hi b)). destruct (widen_encloses (hi a - lo b)). lra.
Qed.

Theorem interval_neg_encloses : forall a x, contains a x -> contains (interval_neg a) (- x).
Proof. intros a x [H1 H2]. unfold contains; simpl. lra. Qed.

(** c·y is linear in y: at least (at most) one of the products at the ends. *)
Lemma linear_ends : forall c l h y, l <= y <= h ->
  (c * l <= c * y \/ c * h <= c * y) /\ (c * y <= c * l \/ c * y <= c * h).
Proof. intros c l h y H. destruct (Rle_or_lt 0 c); split; [left | right | right | left]; nra. Qed.

Lemma min4 : forall p1 p2 p3 p4, let m := Rmin (Rmin p1 p2) (Rmin p3 p4) in
  m <= p1 /\ m <= p2 /\ m <= p3 /\ m <= p4.
Proof.
  intros. pose proof (Rmin_l p1 p2). pose proof (Rmin_r p1 p2). pose proof (Rmin_l p3 p4).
  pose proof (Rmin_r p3 p4). pose proof (Rmin_l (Rmin p1 p2) (Rmin p3 p4)).
  pose proof (Rmin_r (Rmin p1 p2) (Rmin p3 p4)). unfold m. lra.
Qed.

Lemma max4 : forall p1 p2 p3 p4, let M := Rmax (Rmax p1 p2) (Rmax p3 p4) in
  p1 <= M /\ p2 <= M /\ p3 <= M /\ p4 <= M.
Proof.
  intros. pose proof (Rmax_l p1 p2). pose proof (Rmax_r p1 p2). pose proof (Rmax_l p3 p4).
  pose proof (Rmax_r p3 p4). pose proof (Rmax_l (Rmax p1 p2) (Rmax p3 p4)).
  pose proof (Rmax_r (Rmax p1 p2) (Rmax p3 p4)). unfold M. lra.
Qed.

Theorem interval_mul_encloses : forall a b x y, contains a x -> contains b y ->
  contains (interval_mul a b) (x * y).
Proof.
  intros a b x y Ha Hb. unfold contains, interval_mul; simpl.
  set (m := Rmin (Rmin (RN (lo a * lo b)) (RN (lo a * hi b))) (Rmin (RN (hi a * lo b)) (RN (hi a * hi b)))).
  set (M := Rmax (Rmax (RN (lo a * lo b)) (RN (lo a * hi b))) (Rmax (RN (hi a * lo b)) (RN (hi a * hi b)))).
  assert (Fm : binary64 m) by (apply binary64_Rmin; apply binary64_Rmin; apply binary64_RN).
  assert (FM : binary64 M) by (apply binary64_Rmax; apply binary64_Rmax; apply binary64_RN).
  (* every endpoint product is above next_down m and below next_up M *)
  destruct (min4 (RN (lo a * lo b)) (RN (lo a * hi b)) (RN (hi a * lo b)) (RN (hi a * hi b))) as [m1 [m2 [m3 m4]]].
  destruct (max4 (RN (lo a * lo b)) (RN (lo a * hi b)) (RN (hi a * lo b)) (RN (hi a * hi b))) as [M1 [M2 [M3 M4]]].
  fold m in m1, m2, m3, m4. fold M in M1, M2, M3, M4.
  apply down_le in m1, m2, m3, m4; try exact Fm. apply up_ge in M1, M2, M3, M4; try exact FM.
  destruct (linear_ends y (lo a) (hi a) x Ha) as [X1 X2].
  destruct (linear_ends (lo a) (lo b) (hi b) y Hb) as [L1 L2].
  destruct (linear_ends (hi a) (lo b) (hi b) y Hb) as [H1 H2].
  split; [destruct X1, L1, H1 | destruct X2, L2, H2]; lra.
Qed.

Theorem interval_square_encloses : forall a x, contains a x -> contains (interval_square a) (x * x).
Proof.
  intros a x [H1 H2]. unfold contains, interval_square.
  set (l := RN (lo a * lo a)). set (h := RN (hi a * hi a)).
  assert (Fl : binary64 l) by apply binary64_RN. assert (Fh : binary64 h) by apply binary64_RN.
  assert (U : x * x <= next_up (Rmax l h)).
  { destruct (Rle_or_lt 0 x).
    - apply Rle_trans with (hi a * hi a); [apply Rmult_le_compat; lra |].
      apply up_ge; [now apply binary64_Rmax | apply Rmax_r].
    - apply Rle_trans with (lo a * lo a); [nra |].
      apply up_ge; [now apply binary64_Rmax | apply Rmax_l]. }
  assert (Z : 0 <= x * x) by nra.
  destruct (Rle_bool_spec (lo a) 0); destruct (Rle_bool_spec 0 (hi a)); simpl;
    (split; [| exact U]); try exact Z;
    apply Rmax_lub; try exact Z; apply down_le; try now apply binary64_Rmin.
  - (* hi < 0: x ≤ hi < 0 *) apply Rle_trans with h; [apply Rmin_r | apply RN_le; nra].
  - (* lo > 0 *) apply Rle_trans with l; [apply Rmin_l | apply RN_le; nra].
  - apply Rle_trans with l; [apply Rmin_l | apply RN_le; nra].
Qed.

Theorem interval_div_encloses : forall a b x y, contains a x -> contains b y -> 0 <= x -> 0 < lo b ->
  contains (interval_div a b) (x / y).
Proof.
  intros a b x y [Ha1 Ha2] [Hb1 Hb2] X B. unfold contains, interval_div; simpl.
  assert (Y : 0 < y) by lra.
  assert (Q : 0 <= x / y) by (unfold Rdiv; apply Rmult_le_pos; [lra | left; apply Rinv_0_lt_compat; lra]).
  destruct (widen_encloses (Rmax (lo a) 0 / hi b)) as [D _].
  destruct (widen_encloses (hi a / lo b)) as [_ U].
  split.
  - apply Rmax_lub; [exact Q |]. apply Rle_trans with (1 := D).
    unfold Rdiv. apply Rmult_le_compat; try apply Rmax_r.
    + left. apply Rinv_0_lt_compat. lra.
    + apply Rmax_lub; lra.
    + apply Rinv_le_contravar; lra.
  - apply Rle_trans with (2 := U).
    unfold Rdiv. apply Rmult_le_compat; try lra.
    + left. now apply Rinv_0_lt_compat.
    + apply Rinv_le_contravar; lra.
Qed.

(** A certain sign of an interval is the sign of every value it holds ([certifies], Model.v). *)
Theorem interval_sign_sound : forall a x, contains a x -> certifies (sign_from_Z (interval_sign a)) x.
Proof.
  intros a x [H1 H2]. unfold interval_sign.
  destruct (Rlt_bool_spec 0 (lo a)); [simpl; lra |].
  destruct (Rlt_bool_spec (hi a) 0); [simpl; lra |].
  destruct (Req_bool_spec (lo a) 0); destruct (Req_bool_spec (hi a) 0); simpl; try exact I. lra.
Qed.

(** ** On IEEE doubles (FloatCore.v's [float] and operations), overflow included.

    [next_up] is Flocq's [Bsucc] ([Bsucc_correct]: a finite x gives [succ x], or +inf when that is 2^1024),
    [next_down] is [Bpred], by definition [Bopp (Bsucc (Bopp x))]. *)

Definition ext_le (f : float) (z : R) : Prop := f = B754_infinity true \/ (fin f = true /\ B2R f <= z).
Definition ext_ge (f : float) (z : R) : Prop := f = B754_infinity false \/ (fin f = true /\ z <= B2R f).

Record FInterval := { flo : float; fhi : float }.

(** The result holds z (its ends may be infinite). *)
Definition fcontains (a : FInterval) (x : R) : Prop := ext_le (flo a) x /\ ext_ge (fhi a) x.

(** An operand: finite ends holding x. *)
Definition fin_contains (a : FInterval) (x : R) : Prop :=
  fin (flo a) = true /\ fin (fhi a) = true /\ B2R (flo a) <= x <= B2R (fhi a).

(** std::min(x, y) is (y < x) ? y : x, std::max(x, y) is (x < y) ? y : x. *)
Definition fmin (x y : float) : float := if flt y x then y else x.
Definition fmax (x y : float) : float := if flt x y then y else x.

(** interval_detail::product: a NaN product (0 · ±inf) is replaced by 0. *)
Definition fproduct (x y : float) : float := let p := fmul x y in if feq p p then p else fzero.

(** operator+, operator-(a, b), operator-(a), operator*, square, divide_nonnegative, interval_sign. *)
Definition f_add (a b : FInterval) : FInterval :=
  {| flo := Bpred (fadd (flo a) (flo b)); fhi := Bsucc (fadd (fhi a) (fhi b)) |}.
Definition f_sub (a b : FInterval) : FInterval :=
  {| flo := Bpred (fsub (flo a) (fhi b)); fhi := Bsucc (fsub (fhi a) (flo b)) |}.
Definition f_neg (a : FInterval) : FInterval := {| flo := fneg (fhi a); fhi := fneg (flo a) |}.
Definition f_mul (a b : FInterval) : FInterval :=
  let p1 := fproduct (flo a) (flo b) in let p2 := fproduct (flo a) (fhi b) in
  let p3 := fproduct (fhi a) (flo b) in let p4 := fproduct (fhi a) (fhi b) in
  {| flo := Bpred (fmin (fmin p1 p2) (fmin p3 p4)); fhi := Bsucc (fmax (fmax p1 p2) (fmax p3 p4)) |}.
Definition f_square (a : FInterval) : FInterval :=
  let l := fmul (flo a) (flo a) in let h := fmul (fhi a) (fhi a) in
  if fle (flo a) fzero && fle fzero (fhi a) then {| flo := fzero; fhi := Bsucc (fmax l h) |}
  else {| flo := fmax fzero (Bpred (fmin l h)); fhi := Bsucc (fmax l h) |}.
Definition f_div (a b : FInterval) : FInterval :=
  {| flo := fmax fzero (Bpred (fdiv (fmax (flo a) fzero) (fhi b))); fhi := Bsucc (fdiv (fhi a) (flo b)) |}.

(** The reals of an interval of doubles. *)
Definition model (a : FInterval) : Interval := {| lo := B2R (flo a); hi := B2R (fhi a) |}.

(** interval_sign; [uncertain_lane] is interval_uncertain (2). *)
Definition f_sign (a : FInterval) : Z :=
  if flt fzero (flo a) then 1%Z
  else if flt (fhi a) fzero then (-1)%Z
  else if feq (flo a) fzero && feq (fhi a) fzero then 0%Z
  else uncertain_lane.

(** *** The order of non-NaN doubles, as reals: ±inf as ±2^1024, beyond every finite double. *)
Definition ext_val (f : float) : R :=
  match f with
  | B754_infinity s => if s then - bpow radix2 1024 else bpow radix2 1024
  | _ => B2R f
  end.

Lemma B2R_bound : forall f : float, - bpow radix2 1024 < B2R f < bpow radix2 1024.
Proof. intros f. destruct (Rabs_def2 _ _ (B2R_lt_overflow f)). split; lra. Qed.

Lemma ext_val_fin : forall f : float, fin f = true -> ext_val f = B2R f.
Proof. intros [| | |] F; try discriminate; reflexivity. Qed.

(** The C++'s [x < y] on non-NaN doubles is the order of [ext_val]. *)
Lemma flt_ext : forall x y : float, is_nan x = false -> is_nan y = false ->
  flt x y = Rlt_bool (ext_val x) (ext_val y).
Proof.
  intros x y Nx Ny. pose proof (B2R_bound x). pose proof (B2R_bound y). pose proof (bpow_gt_0 radix2 1024).
  destruct x as [sx|[|]| |sx mx ex Hx]; destruct y as [sy|[|]| |sy my ey Hy]; try discriminate;
    try ((rewrite flt_val by reflexivity); (rewrite !ext_val_fin by reflexivity); reflexivity);
    unfold flt; cbn [ext_val]; cbn -[bpow Rlt_bool BinarySingleNaN.B2R];
    first [ rewrite Rlt_bool_false by lra; reflexivity | rewrite Rlt_bool_true by lra; reflexivity ].
Qed.

Notation ieee_rn := RoundOrder.ieee_rn.

(** The sign bit of a finite double is the sign of its value. *)
Lemma Bsign_val : forall x : float, fin x = true ->
  (Bsign x = false -> 0 <= B2R x) /\ (Bsign x = true -> B2R x <= 0).
Proof.
  intros [sx|sx| |sx mx ex Hx] F; try discriminate; simpl; [split; intros; lra |].
  destruct sx; split; intros S; try discriminate; [apply F2R_le_0 | apply F2R_ge_0]; simpl; lia.
Qed.

(** An overflow to the infinity of sign s is the IEEE rounding of a z of that sign. *)
Lemma overflow_rn : forall z (f : float) s, B2SF f = binary_overflow 53 1024 mode_NE s ->
  bpow radix2 1024 <= Rabs (RN z) -> (s = false -> 0 <= z) -> (s = true -> z <= 0) -> ieee_rn z f.
Proof.
  intros z f s O L P N. right. split; [exact L |].
  cbv [binary_overflow overflow_to_inf] in O. rewrite (overflow_sign _ _ O). f_equal.
  assert (z <> 0) by (intros ->; rewrite RN_0, Rabs_R0 in L; pose proof (bpow_gt_0 radix2 1024); lra).
  destruct s.
  - specialize (N eq_refl). rewrite Rlt_bool_true; [reflexivity | lra].
  - specialize (P eq_refl). rewrite Rlt_bool_false; [reflexivity | lra].
Qed.

Lemma fadd_rn : forall x y, fin x = true -> fin y = true -> ieee_rn (B2R x + B2R y) (fadd x y).
Proof.
  intros x y Fx Fy. pose proof (Bplus_correct 53 1024 _ _ mode_NE x y Fx Fy) as C. revert C.
  case Rlt_bool_spec; intros L C.
  - left. destruct C as [V [F _]]. split; assumption.
  - destruct C as [O S]. destruct (Bsign_val x Fx) as [Px Nx]. destruct (Bsign_val y Fy) as [Py Ny].
    apply (overflow_rn _ _ _ O L); intros E; rewrite E in S.
    + pose proof (Px E). pose proof (Py (eq_sym S)). lra.
    + pose proof (Nx E). pose proof (Ny (eq_sym S)). lra.
Qed.

Lemma fsub_rn : forall x y, fin x = true -> fin y = true -> ieee_rn (B2R x - B2R y) (fsub x y).
Proof.
  intros x y Fx Fy. pose proof (Bminus_correct 53 1024 _ _ mode_NE x y Fx Fy) as C. revert C.
  case Rlt_bool_spec; intros L C.
  - left. destruct C as [V [F _]]. split; assumption.
  - destruct C as [O S]. destruct (Bsign_val x Fx) as [Px Nx]. destruct (Bsign_val y Fy) as [Py Ny].
    apply (overflow_rn _ _ _ O L); intros E; rewrite E in S.
    + pose proof (Px E). assert (Bsign y = true) by (destruct (Bsign y); easy). pose proof (Ny H0). lra.
    + pose proof (Nx E). assert (Bsign y = false) by (destruct (Bsign y); easy). pose proof (Py H0). lra.
Qed.

(** The sign of a product (quotient) of non-zero numbers is the exclusive or of the signs. *)
Lemma xorb_sign : forall (x y : float) q, fin x = true -> fin y = true -> q <> 0 ->
  (0 <= B2R x * B2R y -> 0 <= q) -> (B2R x * B2R y <= 0 -> q <= 0) ->
  (xorb (Bsign x) (Bsign y) = false -> 0 <= q) /\ (xorb (Bsign x) (Bsign y) = true -> q <= 0).
Proof.
  intros x y q Fx Fy Nq P N. destruct (Bsign_val x Fx) as [Px Nx]. destruct (Bsign_val y Fy) as [Py Ny].
  destruct (Bsign x), (Bsign y); simpl; split; intros E; try discriminate;
    [apply P | apply N | apply N | apply P];
    first [ pose proof (Nx eq_refl) | pose proof (Px eq_refl) ]; first [ pose proof (Ny eq_refl) | pose proof (Py eq_refl) ]; nra.
Qed.

Lemma fmul_rn : forall x y, fin x = true -> fin y = true -> ieee_rn (B2R x * B2R y) (fmul x y).
Proof.
  intros x y Fx Fy. pose proof (Bmult_correct 53 1024 _ _ mode_NE x y) as C. revert C.
  case Rlt_bool_spec; intros L C.
  - left. destruct C as [V [F _]]. unfold fin in *. rewrite Fx, Fy in F. split; assumption.
  - change (bpow radix2 1024 <= Rabs (RN (B2R x * B2R y))) in L.
    assert (Z : B2R x * B2R y <> 0)
      by (intros E; rewrite E, RN_0, Rabs_R0 in L; pose proof (bpow_gt_0 radix2 1024); lra).
    destruct (xorb_sign x y (B2R x * B2R y) Fx Fy Z) as [P N]; auto.
    apply (overflow_rn _ _ _ C L); assumption.
Qed.

Lemma fdiv_rn : forall x y, fin x = true -> fin y = true -> B2R y <> 0 -> ieee_rn (B2R x / B2R y) (fdiv x y).
Proof.
  intros x y Fx Fy Ny. pose proof (Bdiv_correct 53 1024 _ _ mode_NE x y Ny) as C. revert C.
  case Rlt_bool_spec; intros L C.
  - left. destruct C as [V [F _]]. unfold fin in *. rewrite Fx in F. split; assumption.
  - change (bpow radix2 1024 <= Rabs (RN (B2R x / B2R y))) in L.
    assert (Z : B2R x / B2R y <> 0)
      by (intros E; rewrite E, RN_0, Rabs_R0 in L; pose proof (bpow_gt_0 radix2 1024); lra).
    assert (I : 0 < B2R y /\ 0 < / B2R y \/ B2R y < 0 /\ / B2R y < 0).
    { destruct (Rlt_or_le 0 (B2R y)); [left | right]; split; try lra;
        [apply Rinv_0_lt_compat | apply Rinv_lt_0_compat]; lra. }
    destruct (xorb_sign x y (B2R x / B2R y) Fx Fy Z) as [P N]; unfold Rdiv; try nra.
    apply (overflow_rn _ _ _ C L); assumption.
Qed.

(** *** Widening an IEEE rounding. *)

Lemma Bsucc_ext : forall (p : float) z, fin p = true -> z <= next_up (B2R p) -> ext_ge (Bsucc p) z.
Proof.
  intros p z Fp H. generalize (Bsucc_correct 53 1024 _ _ p Fp). destruct Rlt_bool.
  - intros [V [F _]]. right. split; [exact F |]. rewrite V. exact H.
  - intros O. left. exact (overflow_sign _ _ O).
Qed.

Lemma Bpred_ext : forall (p : float) z, fin p = true -> next_down (B2R p) <= z -> ext_le (Bpred p) z.
Proof.
  intros p z Fp H. generalize (Bpred_correct 53 1024 _ _ p Fp). destruct Rlt_bool.
  - intros [V [F _]]. right. split; [exact F |]. rewrite V. exact H.
  - intros O. left. exact (overflow_sign _ _ O).
Qed.

Lemma rn_cases : forall z (f : float), ieee_rn z f ->
  (fin f = true /\ B2R f = RN z) \/ (f = B754_infinity false /\ bpow radix2 1024 <= RN z) \/
  (f = B754_infinity true /\ RN z <= - bpow radix2 1024).
Proof.
  intros z f [[F V] | [O E]]; [left; split; assumption | right].
  destruct (Rlt_bool_spec z 0) as [N | N]; rewrite E.
  - right. split; [reflexivity |]. now apply RoundOrder.rne_overflow_neg.
  - left. split; [reflexivity |]. now apply RoundOrder.rne_overflow_pos.
Qed.

Lemma rn_not_nan : forall z (f : float), ieee_rn z f -> is_nan f = false.
Proof. intros z f H. destruct (rn_cases z f H) as [[F _] | [[-> _] | [-> _]]]; [| reflexivity ..]. destruct f; easy. Qed.

(** DBL_MAX = next_down(+inf) = pred(2^1024); -DBL_MAX = next_up(-inf). *)
Lemma dbl_max : fin (Bpred (B754_infinity false : float)) = true /\
  B2R (Bpred (B754_infinity false : float)) = next_down (bpow radix2 1024).
Proof.
  let v := eval vm_compute in (Bpred (B754_infinity false : float)) in
    change (Bpred (B754_infinity false : float)) with v.
  split; [reflexivity |]. change (B2R _) with (IZR 9007199254740991 * bpow radix2 971). unfold next_down.
  rewrite pred_bpow. change (FLT_exp (-1074) 53 1024) with 971%Z.
  replace (bpow radix2 1024) with (bpow radix2 53 * bpow radix2 971) by (rewrite <- bpow_plus; reflexivity).
  change (bpow radix2 53) with (IZR 9007199254740992). lra.
Qed.

Lemma binary64_bpow_1024 : binary64 (bpow radix2 1024).
Proof. apply generic_format_bpow; auto with typeclass_instances. unfold FLT_exp. simpl. lia. Qed.

Lemma not_nan_cases : forall f : float, is_nan f = false ->
  f = B754_infinity true \/ f = B754_infinity false \/ fin f = true.
Proof. intros [|[|]| |] N; auto; discriminate. Qed.

(** A non-NaN double m at most (in the doubles' order) the IEEE rounding f of z: next_down(m) ≤ z. *)
Lemma rn_below : forall z (f m : float), ieee_rn z f -> is_nan m = false -> ext_val m <= ext_val f ->
  ext_le (Bpred m) z.
Proof.
  intros z f m R Nm O. pose proof (B2R_bound m). pose proof (B2R_bound f). pose proof (bpow_gt_0 radix2 1024).
  destruct (not_nan_cases m Nm) as [-> | [-> | Fm]]; [left; reflexivity | |];
    [cbn [ext_val] in O | rewrite (ext_val_fin m) in O by exact Fm];
    destruct (rn_cases z f R) as [[F V] | [[-> V] | [-> V]]];
    try (rewrite (ext_val_fin f) in O by exact F); cbn [ext_val] in O; try lra.
  - (* m = +inf = f: next_down(+inf) = DBL_MAX ≤ z *)
    destruct dbl_max as [F D]. right. split; [exact F |]. rewrite D.
    apply down_le; [exact binary64_bpow_1024 | exact V].
  - apply Bpred_ext; [exact Fm |]. apply down_le; [apply binary64_B2R | lra].
  - apply Bpred_ext; [exact Fm |]. apply down_le; [apply binary64_B2R | lra].
Qed.

Lemma rn_above : forall z (f M : float), ieee_rn z f -> is_nan M = false -> ext_val f <= ext_val M ->
  ext_ge (Bsucc M) z.
Proof.
  intros z f M R NM O. pose proof (B2R_bound M). pose proof (B2R_bound f). pose proof (bpow_gt_0 radix2 1024).
  destruct (not_nan_cases M NM) as [-> | [-> | FM]]; [| left; reflexivity |];
    [cbn [ext_val] in O | rewrite (ext_val_fin M) in O by exact FM];
    destruct (rn_cases z f R) as [[F V] | [[-> V] | [-> V]]];
    try (rewrite (ext_val_fin f) in O by exact F); cbn [ext_val] in O; try lra.
  - (* M = -inf = f: next_up(-inf) = -DBL_MAX ≥ z *)
    destruct dbl_max as [F D]. right.
    change (Bsucc (B754_infinity true : float)) with (Bopp (Bpred (B754_infinity false : float))).
    rewrite fneg_fin, B2R_Bopp, D. split; [exact F |].
    assert (W : bpow radix2 1024 <= RN (- z)) by (rewrite RN_opp; lra).
    pose proof (down_le _ _ binary64_bpow_1024 W). lra.
  - apply Bsucc_ext; [exact FM |]. apply up_ge; [apply binary64_B2R | lra].
  - apply Bsucc_ext; [exact FM |]. apply up_ge; [apply binary64_B2R | lra].
Qed.

Lemma rn_down : forall z (f : float), ieee_rn z f -> ext_le (Bpred f) z.
Proof. intros z f R. apply (rn_below z f f R (rn_not_nan z f R) (Rle_refl _)). Qed.

Lemma rn_up : forall z (f : float), ieee_rn z f -> ext_ge (Bsucc f) z.
Proof. intros z f R. apply (rn_above z f f R (rn_not_nan z f R) (Rle_refl _)). Qed.

Lemma ext_le_trans : forall f z z', ext_le f z -> z <= z' -> ext_le f z'.
Proof. intros f z z' [E | [F H]] L; [left; exact E | right; split; [exact F | lra]]. Qed.

Lemma ext_ge_trans : forall f z z', ext_ge f z -> z' <= z -> ext_ge f z'.
Proof. intros f z z' [E | [F H]] L; [left; exact E | right; split; [exact F | lra]]. Qed.

(** *** std::min, std::max, product on doubles. *)

Lemma fmin_ext : forall x y : float, is_nan x = false -> is_nan y = false ->
  is_nan (fmin x y) = false /\ ext_val (fmin x y) = Rmin (ext_val x) (ext_val y).
Proof.
  intros x y Nx Ny. unfold fmin. rewrite flt_ext by assumption.
  destruct (Rlt_bool_spec (ext_val y) (ext_val x)); (split; [assumption |]).
  - rewrite Rmin_right; lra.
  - rewrite Rmin_left; lra.
Qed.

Lemma fmax_ext : forall x y : float, is_nan x = false -> is_nan y = false ->
  is_nan (fmax x y) = false /\ ext_val (fmax x y) = Rmax (ext_val x) (ext_val y).
Proof.
  intros x y Nx Ny. unfold fmax. rewrite flt_ext by assumption.
  destruct (Rlt_bool_spec (ext_val x) (ext_val y)); (split; [assumption |]).
  - rewrite Rmax_right; lra.
  - rewrite Rmax_left; lra.
Qed.

Lemma fmax_val : forall x y, fin x = true -> fin y = true -> fin (fmax x y) = true /\ B2R (fmax x y) = Rmax (B2R x) (B2R y).
Proof.
  intros x y Fx Fy. unfold fmax. rewrite flt_val by assumption.
  destruct (Rlt_bool_spec (B2R x) (B2R y)); (split; [assumption |]).
  - rewrite Rmax_right; lra.
  - rewrite Rmax_left; lra.
Qed.

(** Finite operands: the product is never NaN, and interval_detail::product is the product. *)
Lemma fproduct_fmul : forall x y, fin x = true -> fin y = true -> fproduct x y = fmul x y.
Proof.
  intros x y Fx Fy. unfold fproduct. cbv zeta.
  destruct (rn_cases _ _ (fmul_rn x y Fx Fy)) as [[F V] | [[-> _] | [-> _]]]; [| reflexivity ..].
  rewrite feq_val by assumption. rewrite Req_bool_true; reflexivity.
Qed.

(** std::max(0.0, f) of a lower end f below a non-negative z is a finite double below z. *)
Lemma fmax_zero_ext : forall f z, ext_le f z -> 0 <= z -> ext_le (fmax fzero f) z.
Proof.
  intros f z [-> | [F H]] Z; right.
  - change (fmax fzero (B754_infinity true)) with fzero. split; [reflexivity | exact Z].
  - destruct (fmax_val fzero f eq_refl F) as [F' V]. split; [exact F' |]. rewrite V.
    apply Rmax_lub; [exact Z | exact H].
Qed.

(** *** The interval operations on doubles. *)

Theorem ieee_add_encloses : forall a b x y, fin_contains a x -> fin_contains b y ->
  fcontains (f_add a b) (x + y).
Proof.
  intros a b x y [Fal [Fah Ha]] [Fbl [Fbh Hb]]. split; simpl.
  - eapply ext_le_trans; [apply rn_down, fadd_rn; assumption | lra].
  - eapply ext_ge_trans; [apply rn_up, fadd_rn; assumption | lra].
Qed.

Theorem ieee_sub_encloses : forall a b x y, fin_contains a x -> fin_contains b y ->
  fcontains (f_sub a b) (x - y).
Proof.
  intros a b x y [Fal [Fah Ha]] [Fbl [Fbh Hb]]. split; simpl.
  - eapply ext_le_trans; [apply rn_down, fsub_rn; assumption | lra].
  - eapply ext_ge_trans; [apply rn_up, fsub_rn; assumption | lra].
Qed.

Theorem ieee_mul_encloses : forall a b x y, fin_contains a x -> fin_contains b y ->
  fcontains (f_mul a b) (x * y).
Proof.
  intros a b x y [Fal [Fah Ha]] [Fbl [Fbh Hb]]. unfold f_mul; simpl. rewrite !fproduct_fmul by assumption.
  pose proof (fmul_rn _ _ Fal Fbl) as R1. pose proof (fmul_rn _ _ Fal Fbh) as R2.
  pose proof (fmul_rn _ _ Fah Fbl) as R3. pose proof (fmul_rn _ _ Fah Fbh) as R4.
  pose proof (rn_not_nan _ _ R1) as N1. pose proof (rn_not_nan _ _ R2) as N2.
  pose proof (rn_not_nan _ _ R3) as N3. pose proof (rn_not_nan _ _ R4) as N4.
  destruct (fmin_ext _ _ N1 N2) as [Nm1 Em1]. destruct (fmin_ext _ _ N3 N4) as [Nm2 Em2].
  destruct (fmin_ext _ _ Nm1 Nm2) as [Nm Em]. rewrite Em1, Em2 in Em.
  destruct (fmax_ext _ _ N1 N2) as [NM1 EM1]. destruct (fmax_ext _ _ N3 N4) as [NM2 EM2].
  destruct (fmax_ext _ _ NM1 NM2) as [NM EM]. rewrite EM1, EM2 in EM.
  destruct (min4 (ext_val (fmul (flo a) (flo b))) (ext_val (fmul (flo a) (fhi b)))
                 (ext_val (fmul (fhi a) (flo b))) (ext_val (fmul (fhi a) (fhi b)))) as [m1 [m2 [m3 m4]]].
  destruct (max4 (ext_val (fmul (flo a) (flo b))) (ext_val (fmul (flo a) (fhi b)))
                 (ext_val (fmul (fhi a) (flo b))) (ext_val (fmul (fhi a) (fhi b)))) as [M1 [M2 [M3 M4]]].
  rewrite <- Em in m1, m2, m3, m4. rewrite <- EM in M1, M2, M3, M4.
  destruct (linear_ends y (B2R (flo a)) (B2R (fhi a)) x Ha) as [X1 X2].
  destruct (linear_ends (B2R (flo a)) (B2R (flo b)) (B2R (fhi b)) y Hb) as [L1 L2].
  destruct (linear_ends (B2R (fhi a)) (B2R (flo b)) (B2R (fhi b)) y Hb) as [H1 H2].
  split.
  - destruct X1, L1, H1;
      first [ eapply ext_le_trans; [apply (rn_below _ _ _ R1 Nm m1) | lra]
            | eapply ext_le_trans; [apply (rn_below _ _ _ R2 Nm m2) | lra]
            | eapply ext_le_trans; [apply (rn_below _ _ _ R3 Nm m3) | lra]
            | eapply ext_le_trans; [apply (rn_below _ _ _ R4 Nm m4) | lra] ].
  - destruct X2, L2, H2;
      first [ eapply ext_ge_trans; [apply (rn_above _ _ _ R1 NM M1) | lra]
            | eapply ext_ge_trans; [apply (rn_above _ _ _ R2 NM M2) | lra]
            | eapply ext_ge_trans; [apply (rn_above _ _ _ R3 NM M3) | lra]
            | eapply ext_ge_trans; [apply (rn_above _ _ _ R4 NM M4) | lra] ].
Qed.

Theorem ieee_square_encloses : forall a x, fin_contains a x -> fcontains (f_square a) (x * x).
Proof.
  intros a x [Fl [Fh [H1 H2]]]. unfold f_square.
  pose proof (fmul_rn _ _ Fl Fl) as Rl. pose proof (fmul_rn _ _ Fh Fh) as Rh.
  pose proof (rn_not_nan _ _ Rl) as Nl. pose proof (rn_not_nan _ _ Rh) as Nh.
  destruct (fmin_ext _ _ Nl Nh) as [Nm Em]. destruct (fmax_ext _ _ Nl Nh) as [NM EM].
  assert (Z : 0 <= x * x) by nra.
  assert (U : ext_ge (Bsucc (fmax (fmul (flo a) (flo a)) (fmul (fhi a) (fhi a)))) (x * x)).
  { destruct (Rle_or_lt 0 x).
    - eapply ext_ge_trans; [apply (rn_above _ _ _ Rh NM); rewrite EM; apply Rmax_r |].
      apply Rmult_le_compat; lra.
    - eapply ext_ge_trans; [apply (rn_above _ _ _ Rl NM); rewrite EM; apply Rmax_l | nra]. }
  rewrite !fle_val by easy. change (B2R fzero) with 0.
  destruct (Rle_bool_spec (B2R (flo a)) 0); destruct (Rle_bool_spec 0 (B2R (fhi a))); simpl;
    (split; [| exact U]); [right; split; [reflexivity | exact Z] | ..];
    apply fmax_zero_ext; try exact Z.
  - (* hi < 0 *) eapply ext_le_trans; [apply (rn_below _ _ _ Rh Nm); rewrite Em; apply Rmin_r | nra].
  - (* lo > 0 *) eapply ext_le_trans; [apply (rn_below _ _ _ Rl Nm); rewrite Em; apply Rmin_l | nra].
  - eapply ext_le_trans; [apply (rn_below _ _ _ Rl Nm); rewrite Em; apply Rmin_l | nra].
Qed.

Theorem ieee_div_encloses : forall a b x y, fin_contains a x -> fin_contains b y -> 0 <= x ->
  flt fzero (flo b) = true -> fcontains (f_div a b) (x / y).
Proof.
  intros a b x y [Fal [Fah Ha]] [Fbl [Fbh Hb]] X P.
  rewrite flt_val in P by easy. change (B2R fzero) with 0 in P.
  destruct (Rlt_bool_spec 0 (B2R (flo b))) as [P' | P']; [clear P; rename P' into P | discriminate].
  assert (Y : 0 < y) by lra.
  assert (Q : 0 <= x / y) by (unfold Rdiv; apply Rmult_le_pos; [lra | left; apply Rinv_0_lt_compat; lra]).
  destruct (fmax_val (flo a) fzero Fal eq_refl) as [Fn Vn]. change (B2R fzero) with 0 in Vn.
  unfold f_div; split; simpl.
  - apply fmax_zero_ext; [| exact Q].
    eapply ext_le_trans; [apply rn_down, fdiv_rn; try assumption; lra |]. rewrite Vn.
    unfold Rdiv. apply Rmult_le_compat; try apply Rmax_r.
    + left. apply Rinv_0_lt_compat. lra.
    + apply Rmax_lub; lra.
    + apply Rinv_le_contravar; lra.
  - eapply ext_ge_trans; [apply rn_up, fdiv_rn; try assumption; lra |].
    unfold Rdiv. apply Rmult_le_compat; try lra.
    + left. now apply Rinv_0_lt_compat.
    + apply Rinv_le_contravar; lra.
Qed.

Theorem ieee_sign_sound : forall a x, fin_contains a x -> certifies (sign_from_Z (f_sign a)) x.
Proof.
  intros a x [Fl [Fh H]]. replace (f_sign a) with (interval_sign (model a)).
  - now apply interval_sign_sound.
  - unfold f_sign, interval_sign; simpl. rewrite !flt_val, !feq_val by easy. reflexivity.
Qed.

Theorem ieee_neg_encloses : forall a x, fin_contains a x -> fin_contains (f_neg a) (- x).
Proof.
  intros a x [Fl [Fh H]]. unfold f_neg, fin_contains; simpl. rewrite !fneg_fin, !fneg_val. repeat split; auto; lra.
Qed.
