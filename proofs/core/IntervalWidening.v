(** * Interval arithmetic widened by one ulp (kernel/src/core/interval.hpp).

    The C++: every binary64 operation rounded to nearest (ties to even, gradual underflow), then the lower end
    moved to [next_down] and the upper end to [next_up] of the rounded value.  Here [next_up] is Flocq's [succ]
    and [next_down] is Flocq's [pred] for the binary64 format of Model.v ([FLT_exp (-1074) 53]); [pred x] is
    by definition [- succ (- x)], the C++'s [next_down(x) = -next_up(-x)].  On finite doubles [succ] is IEEE
    nextUp (the smallest double above x; [succ 0 = 2^-1074]), which is what the C++ [next_up] computes on the
    bit pattern; that bit-level identity is checked by tests/closest_point_test.cpp, not proved here.

    The model (Model.v): an operation on doubles is [RN] of the exact real result, with no largest exponent.
    So the theorems below need no overflow hypothesis: they hold for every real endpoint (in particular for
    every binary64 endpoint), and they are the C++'s semantics whenever each rounded value is a finite double
    (FloatCore.v's [fadd_val], [fmul_val], ... give [RN] of the exact result exactly then).  [succ] of the
    largest finite double is 2^1024 here, where IEEE gives +inf; both are above every real in question.

    Not covered: infinite or NaN endpoints and overflowing operations (the C++ then works with ±inf, and
    replaces the NaN of a product 0 · ±inf by 0); the argument for those cases is in interval.hpp's header
    and tested, not proved.  The signed zeros of std::min / std::max are the same real 0.

    Main theorems: [widen_encloses], [interval_add_encloses], [interval_sub_encloses], [interval_neg_encloses],
    [interval_mul_encloses], [interval_square_encloses], [interval_div_encloses], [interval_sign_sound]. *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model FloatCore.
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

(** ** On IEEE doubles (FloatCore.v's [float], the operations of the C++ on doubles).

    [next_up] is Flocq's [Bsucc]: +0 and -0 give 2^-1074, +inf stays, -inf gives -DBL_MAX, a finite x gives
    [succ x] or +inf when that is 2^1024 ([Bsucc_correct]); [next_down] is [Bpred], by definition
    [-Bsucc(-x)], as in the C++.  That the C++'s bit manipulation computes [Bsucc] is checked by
    tests/closest_point_test.cpp, not proved.

    An end of a computed interval may be infinite (a widening past DBL_MAX): [ext_le f z] says f is -inf or a
    finite double at most z, [ext_ge] the mirror.  The hypotheses: every value that is rounded and then widened
    (the sums, the four products, the squares, the quotients) is a finite double; that makes the operands
    finite too.  Left out: infinite rounded values (overflow) and infinite operands. *)

Definition ext_le (f : float) (z : R) : Prop := f = B754_infinity true \/ (fin f = true /\ B2R f <= z).
Definition ext_ge (f : float) (z : R) : Prop := f = B754_infinity false \/ (fin f = true /\ z <= B2R f).

Record FInterval := { flo : float; fhi : float }.

Definition fcontains (a : FInterval) (x : R) : Prop := ext_le (flo a) x /\ ext_ge (fhi a) x.

(** std::min(x, y) is (y < x) ? y : x, std::max(x, y) is (x < y) ? y : x. *)
Definition fmin (x y : float) : float := if flt y x then y else x.
Definition fmax (x y : float) : float := if flt x y then y else x.

(** interval_detail::product: a NaN product (0 · ±inf) is replaced by 0. *)
Definition fproduct (x y : float) : float := let p := fmul x y in if feq p p then p else fzero.

Definition f_add (a b : FInterval) : FInterval :=
  {| flo := Bpred (fadd (flo a) (flo b)); fhi := Bsucc (fadd (fhi a) (fhi b)) |}.
Definition f_sub (a b : FInterval) : FInterval :=
  {| flo := Bpred (fsub (flo a) (fhi b)); fhi := Bsucc (fsub (fhi a) (flo b)) |}.
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
Definition f_sign (a : FInterval) : Z :=
  if flt fzero (flo a) then 1%Z
  else if flt (fhi a) fzero then (-1)%Z
  else if feq (flo a) fzero && feq (fhi a) fzero then 0%Z
  else uncertain_lane.

(** The reals of a finite interval. *)
Definition model (a : FInterval) : Interval := {| lo := B2R (flo a); hi := B2R (fhi a) |}.

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

Lemma ext_le_fin : forall f z, ext_le f z -> fin f = true -> B2R f <= z.
Proof. intros f z [-> | [_ H]] F; [discriminate | exact H]. Qed.

Lemma ext_ge_fin : forall f z, ext_ge f z -> fin f = true -> z <= B2R f.
Proof. intros f z [-> | [_ H]] F; [discriminate | exact H]. Qed.

(** A finite interval of doubles holding x is its model holding x. *)
Lemma fcontains_model : forall a x, fcontains a x -> fin (flo a) = true -> fin (fhi a) = true ->
  contains (model a) x.
Proof. intros a x [L H] Fl Fh. split; [now apply ext_le_fin | now apply ext_ge_fin]. Qed.

Lemma fmin_val : forall x y, fin x = true -> fin y = true -> fin (fmin x y) = true /\ B2R (fmin x y) = Rmin (B2R x) (B2R y).
Proof.
  intros x y Fx Fy. unfold fmin. rewrite flt_val by assumption.
  destruct (Rlt_bool_spec (B2R y) (B2R x)); (split; [assumption |]).
  - rewrite Rmin_right; lra.
  - rewrite Rmin_left; lra.
Qed.

Lemma fmax_val : forall x y, fin x = true -> fin y = true -> fin (fmax x y) = true /\ B2R (fmax x y) = Rmax (B2R x) (B2R y).
Proof.
  intros x y Fx Fy. unfold fmax. rewrite flt_val by assumption.
  destruct (Rlt_bool_spec (B2R x) (B2R y)); (split; [assumption |]).
  - rewrite Rmax_right; lra.
  - rewrite Rmax_left; lra.
Qed.

Lemma fproduct_val : forall x y, fin (fmul x y) = true -> fproduct x y = fmul x y.
Proof.
  intros x y F. unfold fproduct. rewrite feq_val by assumption.
  destruct (Req_bool_spec (B2R (fmul x y)) (B2R (fmul x y))); [reflexivity | lra].
Qed.

(** max(0, f) of a lower end f below a non-negative z is a finite double below z. *)
Lemma fmax_zero_ext : forall f z, ext_le f z -> 0 <= z -> ext_le (fmax fzero f) z.
Proof.
  intros f z [-> | [F H]] Z; right; [split; [reflexivity | exact Z] |].
  destruct (fmax_val fzero f eq_refl F) as [F' V]. split; [exact F' |]. rewrite V.
  apply Rmax_lub; [exact Z | exact H].
Qed.

Theorem ieee_add_encloses : forall a b x y, fcontains a x -> fcontains b y ->
  fin (fadd (flo a) (flo b)) = true -> fin (fadd (fhi a) (fhi b)) = true ->
  fcontains (f_add a b) (x + y).
Proof.
  intros a b x y Ha Hb Fl Fh. destruct (fadd_inv _ _ Fl) as [F1 [F2 V1]]. destruct (fadd_inv _ _ Fh) as [F3 [F4 V2]].
  destruct (interval_add_encloses (model a) (model b) x y) as [L H]; try now apply fcontains_model.
  simpl in L, H. split; [apply Bpred_ext | apply Bsucc_ext]; try assumption; [rewrite V1 | rewrite V2]; assumption.
Qed.

Theorem ieee_sub_encloses : forall a b x y, fcontains a x -> fcontains b y ->
  fin (fsub (flo a) (fhi b)) = true -> fin (fsub (fhi a) (flo b)) = true ->
  fcontains (f_sub a b) (x - y).
Proof.
  intros a b x y Ha Hb Fl Fh. destruct (fsub_inv _ _ Fl) as [F1 [F2 V1]]. destruct (fsub_inv _ _ Fh) as [F3 [F4 V2]].
  destruct (interval_sub_encloses (model a) (model b) x y) as [L H]; try now apply fcontains_model.
  simpl in L, H. split; [apply Bpred_ext | apply Bsucc_ext]; try assumption; [rewrite V1 | rewrite V2]; assumption.
Qed.

Theorem ieee_mul_encloses : forall a b x y, fcontains a x -> fcontains b y ->
  fin (fmul (flo a) (flo b)) = true -> fin (fmul (flo a) (fhi b)) = true ->
  fin (fmul (fhi a) (flo b)) = true -> fin (fmul (fhi a) (fhi b)) = true ->
  fcontains (f_mul a b) (x * y).
Proof.
  intros a b x y Ha Hb F1 F2 F3 F4.
  destruct (fmul_inv _ _ F1) as [Al [Bl V1]]. destruct (fmul_inv _ _ F4) as [Ah [Bh V4]].
  pose proof (fmul_val _ _ F2) as V2. pose proof (fmul_val _ _ F3) as V3.
  destruct (interval_mul_encloses (model a) (model b) x y) as [L H]; try now apply fcontains_model.
  unfold f_mul, interval_mul in *; simpl in L, H |- *.
  rewrite !fproduct_val by assumption. rewrite <- V1, <- V2, <- V3, <- V4 in L, H.
  destruct (fmin_val _ _ F1 F2) as [G1 W1]. destruct (fmin_val _ _ F3 F4) as [G2 W2].
  destruct (fmin_val _ _ G1 G2) as [G W]. rewrite <- W1, <- W2, <- W in L.
  destruct (fmax_val _ _ F1 F2) as [K1 X1]. destruct (fmax_val _ _ F3 F4) as [K2 X2].
  destruct (fmax_val _ _ K1 K2) as [K X]. rewrite <- X1, <- X2, <- X in H.
  split; [apply Bpred_ext | apply Bsucc_ext]; assumption.
Qed.

Theorem ieee_square_encloses : forall a x, fcontains a x ->
  fin (fmul (flo a) (flo a)) = true -> fin (fmul (fhi a) (fhi a)) = true ->
  fcontains (f_square a) (x * x).
Proof.
  intros a x Ha Fl Fh. destruct (fmul_inv _ _ Fl) as [Al [_ Vl]]. destruct (fmul_inv _ _ Fh) as [Ah [_ Vh]].
  pose proof (interval_square_encloses (model a) x (fcontains_model a x Ha Al Ah)) as S.
  assert (Z : 0 <= x * x) by nra.
  destruct (fmin_val _ _ Fl Fh) as [G W]. destruct (fmax_val _ _ Fl Fh) as [K X].
  unfold f_square, interval_square in *; simpl in S.
  rewrite !fle_val by easy. change (B2R fzero) with 0. rewrite <- Vl, <- Vh, <- W, <- X in S.
  destruct (Rle_bool (B2R (flo a)) 0 && Rle_bool 0 (B2R (fhi a))); simpl in S |- *; destruct S as [L H];
    (split; [| apply Bsucc_ext; assumption]).
  - right. split; [reflexivity | exact Z].
  - apply fmax_zero_ext; [| exact Z]. apply Bpred_ext; [exact G |]. eapply Rle_trans; [apply Rmax_r | exact L].
Qed.

Theorem ieee_div_encloses : forall a b x y, fcontains a x -> fcontains b y -> 0 <= x -> flt fzero (flo b) = true ->
  fin (fhi b) = true ->
  fin (fdiv (fmax (flo a) fzero) (fhi b)) = true -> fin (fdiv (fhi a) (flo b)) = true ->
  fcontains (f_div a b) (x / y).
Proof.
  intros a b x y [La Ha] [Lb Hb] X P Fbh Fq1 Fq2.
  assert (Fbl : fin (flo b) = true) by (destruct Lb as [E | [F _]]; [rewrite E in P; vm_compute in P; discriminate | exact F]).
  rewrite flt_val in P by easy. change (B2R fzero) with 0 in P.
  destruct (Rlt_bool_spec 0 (B2R (flo b))) as [P' | P']; [clear P; rename P' into P | discriminate].
  pose proof (ext_le_fin _ _ Lb Fbl). pose proof (ext_ge_fin _ _ Hb Fbh).
  assert (Y : 0 < y) by lra.
  assert (Q : 0 <= x / y) by (unfold Rdiv; apply Rmult_le_pos; [lra | left; apply Rinv_0_lt_compat; lra]).
  pose proof (fdiv_val _ _ Fq1 Fbh ltac:(lra)) as V1. pose proof (fdiv_val _ _ Fq2 Fbl ltac:(lra)) as V2.
  pose proof (fdiv_fin _ _ Fq1) as Fn. pose proof (fdiv_fin _ _ Fq2) as Fah.
  pose proof (ext_ge_fin _ _ Ha Fah).
  (* the numerator max(a.lo, 0) is a double in [0, x] *)
  assert (N : 0 <= B2R (fmax (flo a) fzero) <= x).
  { unfold fmax in *. destruct La as [E | [Fal Hal]]; [rewrite E; vm_compute; lra |].
    rewrite flt_val in * by easy. change (B2R fzero) with 0 in *.
    destruct (Rlt_bool_spec (B2R (flo a)) 0); simpl; lra. }
  unfold f_div; split; simpl.
  - apply fmax_zero_ext; [| exact Q]. apply Bpred_ext; [exact Fq1 |]. rewrite V1.
    apply Rle_trans with (B2R (fmax (flo a) fzero) / B2R (fhi b)); [apply widen_encloses |].
    unfold Rdiv. apply Rmult_le_compat; try lra.
    + left. apply Rinv_0_lt_compat. lra.
    + apply Rinv_le_contravar; lra.
  - apply Bsucc_ext; [exact Fq2 |]. rewrite V2.
    apply Rle_trans with (B2R (fhi a) / B2R (flo b)); [| apply widen_encloses].
    unfold Rdiv. apply Rmult_le_compat; try lra.
    + left. now apply Rinv_0_lt_compat.
    + apply Rinv_le_contravar; lra.
Qed.

Theorem ieee_sign_sound : forall a x, fcontains a x -> fin (flo a) = true -> fin (fhi a) = true ->
  certifies (sign_from_Z (f_sign a)) x.
Proof.
  intros a x Ha Fl Fh. replace (f_sign a) with (interval_sign (model a)).
  - apply interval_sign_sound. now apply fcontains_model.
  - unfold f_sign, interval_sign; simpl. rewrite !flt_val, !feq_val by easy. reflexivity.
Qed.
