(** * IEEE-754 binary64 as the C++ computes it: the operations of the twins, and how they meet the model.

    The twins (PlaneTwins.v, CompareTwins.v, Expansions.v) are the certified routines written over Flocq's
    IEEE-754 binary64 type ([BinarySingleNaN.binary_float 53 1024]: ±0, subnormals, ±inf and one NaN,
    the NaN payloads of the machine being irrelevant to every routine, which treats NaN as a class), one
    Flocq operation per C++ operation, in the C++ order.  They are computable: Extract.v extracts them to
    OCaml, and the differential runner (proofs/twins/) checks them bit for bit against the compiled C++.

    This file: the C++ operations as Flocq operations ([fadd] is [a + b] on doubles, [ffma] is
    [std::fma], [flt x y] is [x < y], ...), and the three facts that connect an IEEE computation to the
    model of Model.v (where [RN] has no overflow and there is no inf or NaN):
    - backward: a finite result of [+ − × fma] has finite operands, and then its value is the model's
      [RN] of the exact result ([fadd_inv], [fsub_inv], [fmul_inv], [ffma_inv]): an IEEE operation
      either returns [RN] of the exact result or overflows to ±inf (Flocq's [Bplus_correct] etc.);
    - comparisons: [flt] and [fle] on finite operands are the real comparisons; a certifying comparison
      against a bound that is "non-negative or NaN" ([nonneg]) implies the bound is finite
      ([certifying_bound_finite]);
    - forward: finite operands whose model result is below 2^1024 give a finite result ([fadd_fwd] ...,
      [fdiv_fwd] with a non-zero divisor), used by the liveness theorems.

    Nothing here assumes anything about the inputs: a twin theorem states what a certain answer implies,
    for every 64-bit pattern of every input. *)

From Coq Require Import Reals Lra Lia ZArith SpecFloat.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Flocq Require IEEE754.Binary IEEE754.Bits.
From Raykernel Require Import Constants Model.
Open Scope R_scope.

Notation float := (BinarySingleNaN.binary_float 53 1024).

Global Instance binary64_prec_lt_emax : Prec_lt_emax 53 1024.
Proof. reflexivity. Qed.

(** ** The C++ operations on doubles (round to nearest, ties to even). *)
Definition fadd (x y : float) : float := BinarySingleNaN.Bplus mode_NE x y.     (* x + y *)
Definition fsub (x y : float) : float := BinarySingleNaN.Bminus mode_NE x y.    (* x - y *)
Definition fmul (x y : float) : float := BinarySingleNaN.Bmult mode_NE x y.     (* x * y *)
Definition fdiv (x y : float) : float := BinarySingleNaN.Bdiv mode_NE x y.      (* x / y *)
Definition ffma (x y z : float) : float := BinarySingleNaN.Bfma mode_NE x y z.  (* std::fma(x, y, z) *)
Definition fabs (x : float) : float := BinarySingleNaN.Babs x.                 (* std::fabs, lanes' abs *)
Definition fneg (x : float) : float := BinarySingleNaN.Bopp x.                 (* -x *)
Definition flt (x y : float) : bool := BinarySingleNaN.Bltb x y.               (* x < y; false on NaN *)
Definition fle (x y : float) : bool := BinarySingleNaN.Bleb x y.               (* x <= y; false on NaN *)
Definition feq (x y : float) : bool := BinarySingleNaN.Beqb x y.               (* x == y; false on NaN *)
Definition fzero : float := B754_zero false.                                   (* 0.0, V{} *)
Definition finf : float := B754_infinity false.                                (* HUGE_VAL, V{} + HUGE_VAL *)
Definition fin (x : float) : bool := BinarySingleNaN.is_finite x.              (* std::isfinite *)

(** Bit patterns, as std::bit_cast<std::uint64_t> sees them; every NaN is written as the default quiet
    NaN 0x7ff8000000000000 (the runner compares NaNs as a class). *)
Definition of_bits (z : Z) : float := Binary.B2BSN 53 1024 (Bits.b64_of_bits z).
Definition to_bits (x : float) : Z := Bits.bits_of_b64 (Binary.BSN2B 53 1024 Bits.default_nan_pl64 x).

Notation B2R := (BinarySingleNaN.B2R (prec := 53) (emax := 1024)).
Notation Bsign := (BinarySingleNaN.Bsign (prec := 53) (emax := 1024)).
Notation is_nan := (BinarySingleNaN.is_nan (prec := 53) (emax := 1024)).

(** Flocq's rounding of binary64 is the model's [RN]. *)
Lemma RN_flocq : forall x, round radix2 (SpecFloat.fexp 53 1024) (round_mode mode_NE) x = RN x.
Proof. reflexivity. Qed.

Lemma binary64_B2R : forall x : float, binary64 (B2R x).
Proof. intros x. apply (generic_format_B2R 53 1024). Qed.

Lemma B2R_lt_overflow : forall x : float, Rabs (B2R x) < bpow radix2 1024.
Proof. intros x. apply (abs_B2R_lt_emax 53 1024). Qed.

Lemma overflow_not_finite : forall (z : float) sg, B2SF z = S754_infinity sg -> fin z = false.
Proof. intros [| | |] sg H; simpl in H; try discriminate; reflexivity. Qed.

Lemma overflow_sign : forall (z : float) sg, B2SF z = S754_infinity sg -> z = B754_infinity sg.
Proof. intros [| | |] sg H; simpl in H; try discriminate; now injection H as ->. Qed.

(** ** Backward: a finite result has finite operands, and its value is the model's. *)

Lemma fadd_fin : forall x y, fin (fadd x y) = true -> fin x = true /\ fin y = true.
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; unfold fadd, fin; simpl; try easy;
    destruct (Bool.eqb _ _); easy.
Qed.

Lemma fsub_fin : forall x y, fin (fsub x y) = true -> fin x = true /\ fin y = true.
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; unfold fsub, fin; simpl; try easy;
    destruct (Bool.eqb _ _); easy.
Qed.

Lemma fmul_fin : forall x y, fin (fmul x y) = true -> fin x = true /\ fin y = true.
Proof. intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; unfold fmul, fin; simpl; easy. Qed.

Lemma ffma_fin : forall x y z, fin (ffma x y z) = true -> fin x = true /\ fin y = true /\ fin z = true.
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy] [sz|sz| |sz mz ez Hz];
    unfold ffma, fin; simpl; try easy; destruct (Bool.eqb _ _); easy.
Qed.

Lemma fabs_fin : forall x, fin (fabs x) = fin x.
Proof. intros [| | |]; reflexivity. Qed.

Lemma fneg_fin : forall x, fin (fneg x) = fin x.
Proof. intros [| | |]; reflexivity. Qed.

Lemma fabs_val : forall x, B2R (fabs x) = Rabs (B2R x).
Proof. intros x. apply B2R_Babs. Qed.

Lemma fneg_val : forall x, B2R (fneg x) = - B2R x.
Proof. intros x. apply B2R_Bopp. Qed.

Lemma fadd_val : forall x y, fin (fadd x y) = true -> B2R (fadd x y) = RN (B2R x + B2R y).
Proof.
  intros x y H. destruct (fadd_fin x y H) as [Fx Fy].
  pose proof (Bplus_correct 53 1024 _ _ mode_NE x y Fx Fy) as C.
  destruct Rlt_bool.
  - destruct C as [V _]. exact V.
  - destruct C as [O _]. unfold fadd in H. rewrite (overflow_not_finite _ _ O) in H. discriminate.
Qed.

Lemma fsub_val : forall x y, fin (fsub x y) = true -> B2R (fsub x y) = RN (B2R x - B2R y).
Proof.
  intros x y H. destruct (fsub_fin x y H) as [Fx Fy].
  pose proof (Bminus_correct 53 1024 _ _ mode_NE x y Fx Fy) as C.
  destruct Rlt_bool.
  - destruct C as [V _]. exact V.
  - destruct C as [O _]. unfold fsub in H. rewrite (overflow_not_finite _ _ O) in H. discriminate.
Qed.

Lemma fmul_val : forall x y, fin (fmul x y) = true -> B2R (fmul x y) = RN (B2R x * B2R y).
Proof.
  intros x y H.
  pose proof (Bmult_correct 53 1024 _ _ mode_NE x y) as C.
  destruct Rlt_bool.
  - destruct C as [V _]. exact V.
  - unfold fmul in H. rewrite (overflow_not_finite _ _ C) in H. discriminate.
Qed.

Lemma ffma_val : forall x y z, fin (ffma x y z) = true -> B2R (ffma x y z) = RN (B2R x * B2R y + B2R z).
Proof.
  intros x y z H. destruct (ffma_fin x y z H) as [Fx [Fy Fz]].
  pose proof (Bfma_correct 53 1024 _ _ mode_NE x y z Fx Fy Fz) as C. cbv zeta in C.
  destruct Rlt_bool.
  - destruct C as [V _]. exact V.
  - unfold ffma in H. rewrite (overflow_not_finite _ _ C) in H. discriminate.
Qed.

Lemma fdiv_fin : forall x y, fin (fdiv x y) = true -> fin x = true.
Proof. intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy]; unfold fdiv, fin; simpl; easy. Qed.

Lemma fdiv_val : forall x y, fin (fdiv x y) = true -> fin y = true -> B2R y <> 0 ->
  B2R (fdiv x y) = RN (B2R x / B2R y).
Proof.
  intros x y H Fy Nz.
  pose proof (Bdiv_correct 53 1024 _ _ mode_NE x y Nz) as C.
  destruct Rlt_bool.
  - destruct C as [V _]. exact V.
  - unfold fdiv in H. rewrite (overflow_not_finite _ _ C) in H. discriminate.
Qed.

(** The combined forms the tactics below use. *)
Lemma fadd_inv : forall x y, fin (fadd x y) = true ->
  fin x = true /\ fin y = true /\ B2R (fadd x y) = RN (B2R x + B2R y).
Proof. intros x y H. destruct (fadd_fin x y H). repeat split; auto using fadd_val. Qed.

Lemma fsub_inv : forall x y, fin (fsub x y) = true ->
  fin x = true /\ fin y = true /\ B2R (fsub x y) = RN (B2R x - B2R y).
Proof. intros x y H. destruct (fsub_fin x y H). repeat split; auto using fsub_val. Qed.

Lemma fmul_inv : forall x y, fin (fmul x y) = true ->
  fin x = true /\ fin y = true /\ B2R (fmul x y) = RN (B2R x * B2R y).
Proof. intros x y H. destruct (fmul_fin x y H). repeat split; auto using fmul_val. Qed.

Lemma ffma_inv : forall x y z, fin (ffma x y z) = true ->
  fin x = true /\ fin y = true /\ fin z = true /\ B2R (ffma x y z) = RN (B2R x * B2R y + B2R z).
Proof. intros x y z H. destruct (ffma_fin x y z H) as [? [? ?]]. repeat split; auto using ffma_val. Qed.

(** [a - b] and [a + (-b)] are the same operation (two_diff is two_sum(a, -b)). *)
Lemma fsub_val' : forall x y, fin (fsub x y) = true -> B2R (fsub x y) = RN (B2R x + - B2R y).
Proof. intros x y H. rewrite fsub_val by exact H. reflexivity. Qed.

(** ** Comparisons. *)

Lemma flt_val : forall x y, fin x = true -> fin y = true -> flt x y = Rlt_bool (B2R x) (B2R y).
Proof. intros x y Fx Fy. apply Bltb_correct; assumption. Qed.

Lemma fle_val : forall x y, fin x = true -> fin y = true -> fle x y = Rle_bool (B2R x) (B2R y).
Proof. intros x y Fx Fy. apply Bleb_correct; assumption. Qed.

Lemma feq_val : forall x y, fin x = true -> fin y = true -> feq x y = Req_bool (B2R x) (B2R y).
Proof. intros x y Fx Fy. apply Beqb_correct; assumption. Qed.

(** A value is "non-negative or NaN": +0, a positive number, +inf, or NaN.  Every error bound of the
    stages is of this kind: sums and products of magnitudes and non-negative constants. *)
Definition nonneg (x : float) : Prop := is_nan x = true \/ Bsign x = false.

Lemma fabs_nonneg : forall x, nonneg (fabs x).
Proof. intros [| | |]; unfold nonneg; simpl; auto. Qed.

Lemma finf_nonneg : nonneg finf.
Proof. right. reflexivity. Qed.

Lemma fzero_nonneg : nonneg fzero.
Proof. right. reflexivity. Qed.

Lemma B2SF_Bsign : forall (z : float) sg, B2SF z = S754_infinity sg -> Bsign z = sg.
Proof. intros z sg H. now rewrite (overflow_sign z sg H). Qed.

Lemma fadd_nonneg : forall x y, nonneg x -> nonneg y -> nonneg (fadd x y).
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy] [Nx|Nx] [Ny|Ny]; simpl in Nx, Ny;
    try discriminate; unfold nonneg, fadd; subst; try solve [simpl; auto; destruct (Bool.eqb _ _); simpl; auto].
  (* two positive finite numbers *)
  right.
  pose proof (Bplus_correct 53 1024 _ _ mode_NE (B754_finite false mx ex Hx) (B754_finite false my ey Hy)
                eq_refl eq_refl) as C.
  destruct Rlt_bool.
  - destruct C as [_ [_ S]]. rewrite S.
    assert (P : 0 < BinarySingleNaN.B2R (B754_finite false mx ex Hx) + BinarySingleNaN.B2R (B754_finite false my ey Hy)).
    { simpl. apply Rplus_lt_0_compat; apply F2R_gt_0; simpl; lia. }
    now rewrite Rcompare_Gt.
  - destruct C as [O _]. exact (B2SF_Bsign _ _ O).
Qed.

Lemma fmul_nonneg : forall x y, nonneg x -> nonneg y -> nonneg (fmul x y).
Proof.
  intros [sx|sx| |sx mx ex Hx] [sy|sy| |sy my ey Hy] [Nx|Nx] [Ny|Ny]; simpl in Nx, Ny;
    try discriminate; unfold nonneg, fmul; subst; try solve [simpl; auto].
  pose proof (Bmult_correct 53 1024 _ _ mode_NE (B754_finite false mx ex Hx) (B754_finite false my ey Hy)) as C.
  destruct Rlt_bool.
  - destruct C as [_ [_ S]].
    destruct (BinarySingleNaN.is_nan (BinarySingleNaN.Bmult mode_NE (B754_finite false mx ex Hx)
                 (B754_finite false my ey Hy))) eqn:N; [left; reflexivity | right; now apply S].
  - right. exact (B2SF_Bsign _ _ C).
Qed.

(** x < y and x > −y are false when y is NaN or +inf: a comparison that certifies something against
    a non-negative-or-NaN bound implies the bound is finite. *)
Lemma certifying_bound_finite : forall b v, nonneg b -> flt b v = true \/ flt v (fneg b) = true -> fin b = true.
Proof.
  intros [sb|[|]| |sb mb eb Hb] v [N|N] H; simpl in N; try discriminate; try reflexivity;
    destruct H as [H|H]; destruct v as [sv|[|]| |sv mv ev Hv]; unfold flt, fneg in H; simpl in H; discriminate.
Qed.

(** A certain [sign_lanes] means one of its two comparisons held. *)
Lemma sign_lanes_certain : forall a b, sign_lanes a b <> uncertain_lane -> a = true \/ b = true.
Proof. intros [|] [|]; cbv; auto. Qed.

(** ** Tactics: from "this result is finite" to "every operand is finite" (the twins of every family).

    Saturate the context with the finiteness of every operand of a finite result. *)
Ltac have_fin x := match goal with _ : fin x = true |- _ => idtac end.
Ltac fin_down_step :=
  match goal with
  | H : fin (fadd ?x ?y) = true |- _ =>
      tryif (have_fin x; have_fin y) then fail else destruct (fadd_fin x y H)
  | H : fin (fsub ?x ?y) = true |- _ =>
      tryif (have_fin x; have_fin y) then fail else destruct (fsub_fin x y H)
  | H : fin (fmul ?x ?y) = true |- _ =>
      tryif (have_fin x; have_fin y) then fail else destruct (fmul_fin x y H)
  | H : fin (ffma ?x ?y ?z) = true |- _ =>
      tryif (have_fin x; have_fin y; have_fin z) then fail else destruct (ffma_fin x y z H) as [? [? ?]]
  | H : fin (fabs ?x) = true |- _ => tryif have_fin x then fail else (rewrite fabs_fin in H)
  | H : fin (fneg ?x) = true |- _ => tryif have_fin x then fail else (rewrite fneg_fin in H)
  end.
Ltac fin_down := repeat fin_down_step.

Ltac fin_solve := solve [assumption | rewrite ?fabs_fin, ?fneg_fin; assumption].

(** Rewrite every B2R of an operation and every comparison into the model's terms, the operands' finiteness
    from [fin_down] ([fin_down_step], [to_model_step]: one step each, which PlaneTwins.v's two-level forms
    extend). *)
Ltac to_model_step :=
  match goal with
  | |- context [B2R (fadd ?x ?y)] => rewrite (fadd_val x y) by fin_solve
  | |- context [B2R (fsub ?x ?y)] => rewrite (fsub_val' x y) by fin_solve
  | |- context [B2R (fmul ?x ?y)] => rewrite (fmul_val x y) by fin_solve
  | |- context [B2R (ffma ?x ?y ?z)] => rewrite (ffma_val x y z) by fin_solve
  | |- context [B2R (fabs ?x)] => rewrite (fabs_val x)
  | |- context [B2R (fneg ?x)] => rewrite (fneg_val x)
  | |- context [flt ?x ?y] => rewrite (flt_val x y) by fin_solve
  | |- context [fle ?x ?y] => rewrite (fle_val x y) by fin_solve
  | |- context [B2R fzero] => change (B2R fzero) with 0
  end.
Ltac to_model_ops := fin_down; repeat to_model_step.

(** ** Domination: an operation whose model result is at most a finite double does not overflow. *)

Lemma fadd_fwd : forall x y, fin x = true -> fin y = true ->
  Rabs (RN (B2R x + B2R y)) < bpow radix2 1024 ->
  fin (fadd x y) = true /\ B2R (fadd x y) = RN (B2R x + B2R y).
Proof.
  intros x y Fx Fy L. pose proof (Bplus_correct 53 1024 _ _ mode_NE x y Fx Fy) as C.
  rewrite Rlt_bool_true in C by exact L. destruct C as [V [F _]]. split; assumption.
Qed.

Lemma fsub_fwd : forall x y, fin x = true -> fin y = true ->
  Rabs (RN (B2R x - B2R y)) < bpow radix2 1024 ->
  fin (fsub x y) = true /\ B2R (fsub x y) = RN (B2R x - B2R y).
Proof.
  intros x y Fx Fy L. pose proof (Bminus_correct 53 1024 _ _ mode_NE x y Fx Fy) as C.
  rewrite Rlt_bool_true in C by exact L. destruct C as [V [F _]]. split; assumption.
Qed.

Lemma fmul_fwd : forall x y, fin x = true -> fin y = true ->
  Rabs (RN (B2R x * B2R y)) < bpow radix2 1024 ->
  fin (fmul x y) = true /\ B2R (fmul x y) = RN (B2R x * B2R y).
Proof.
  intros x y Fx Fy L. pose proof (Bmult_correct 53 1024 _ _ mode_NE x y) as C.
  rewrite Rlt_bool_true in C by exact L. destruct C as [V [F _]]. unfold fin in *.
  rewrite Fx, Fy in F. split; assumption.
Qed.

Lemma ffma_fwd : forall x y z, fin x = true -> fin y = true -> fin z = true ->
  Rabs (RN (B2R x * B2R y + B2R z)) < bpow radix2 1024 ->
  fin (ffma x y z) = true /\ B2R (ffma x y z) = RN (B2R x * B2R y + B2R z).
Proof.
  intros x y z Fx Fy Fz L. pose proof (Bfma_correct 53 1024 _ _ mode_NE x y z Fx Fy Fz) as C. cbv zeta in C.
  rewrite Rlt_bool_true in C by exact L. destruct C as [V [F _]]. split; assumption.
Qed.

(** Division: [Bdiv_correct] read forwards (a non-zero divisor, hence finite or infinite; the result is
    finite only when RN(x/y) is below 2^1024). *)
Lemma fdiv_fwd : forall x y, fin x = true -> B2R y <> 0 ->
  Rabs (RN (B2R x / B2R y)) < bpow radix2 1024 ->
  fin (fdiv x y) = true /\ B2R (fdiv x y) = RN (B2R x / B2R y).
Proof.
  intros x y Fx Nz L. pose proof (Bdiv_correct 53 1024 _ _ mode_NE x y Nz) as C.
  rewrite Rlt_bool_true in C by exact L. destruct C as [V [F _]]. unfold fin in *.
  rewrite Fx in F. split; assumption.
Qed.

Lemma fadd_dominated : forall x y z, fin x = true -> fin y = true ->
  Rabs (RN (B2R x + B2R y)) <= B2R z ->
  fin (fadd x y) = true /\ B2R (fadd x y) = RN (B2R x + B2R y).
Proof.
  intros x y z Fx Fy D. apply fadd_fwd; try assumption.
  eapply Rle_lt_trans; [exact D|]. eapply Rle_lt_trans; [apply Rle_abs | apply B2R_lt_overflow].
Qed.

(** ** Constants: the value of a concrete double, by computation. *)

Definition mant (x : float) : Z := match x with B754_finite s m _ _ => cond_Zopp s (Zpos m) | _ => 0%Z end.
Definition expo (x : float) : Z := match x with B754_finite _ _ e _ => e | _ => 0%Z end.

Lemma B2R_mant_expo : forall x, B2R x = IZR (mant x) * bpow radix2 (expo x).
Proof. intros [| | |]; simpl; try ring. reflexivity. Qed.

(** [float_value c]: rewrites B2R c into IZR m * bpow radix2 e with m, e computed. *)
Ltac float_value c :=
  rewrite (B2R_mant_expo c);
  let m := eval vm_compute in (mant c) in
  let e := eval vm_compute in (expo c) in
  change (mant c) with m; change (expo c) with e.

(** [pow_vals]: every [bpow radix2 k] of the goal as a numeral or its inverse ([simpl bpow], then [Z.pow_pos 2 p]
    computed), for [lra]. *)
Ltac pow_vals := simpl bpow;
  repeat match goal with |- context [Z.pow_pos 2 ?p] =>
    let v := eval vm_compute in (Z.pow_pos 2 p) in change (Z.pow_pos 2 p) with v end.

(** [float_real c]: B2R c as an exact rational, for [lra]. *)
Ltac float_real c := float_value c; pow_vals.

(** [tie c]: proves [B2R c = NAME] for a compiled constant c = [Cpp.NAME] (ConstantsCpp.v) and its Constants.v
    definition NAME: both sides as exact rationals.  The one tactic of every family's constants lemmas
    ([cpp_NAME] in PlaneTwins.v, PlaneQueryTwins.v, TriangleTwins.v, RayBox.v, OrientTwins.v). *)
Ltac tie c :=
  try lazymatch goal with |- _ = ?k => unfold k end;
  try unfold unit_roundoff; try unfold min_subnormal;
  float_value c; simpl bpow;
  first [ lra | pow_vals; first [lra | field] ].

(** [|x| <= largest finite double] is [std::isfinite(x)] (dot3_compensated.hpp writes it so for both lane
    types).  The largest finite double, 0x1.fffffffffffffp+1023 = 0x7fefffffffffffff. *)
Definition largest_finite_f : float := of_bits 9218868437227405311.

Lemma largest_finite_f_fin : fin largest_finite_f = true.
Proof. vm_compute. reflexivity. Qed.

Lemma largest_finite_f_val : B2R largest_finite_f = IZR 9007199254740991 * bpow radix2 971.
Proof. float_value largest_finite_f. reflexivity. Qed.

Lemma fle_largest_finite : forall x, fle (fabs x) largest_finite_f = fin x.
Proof.
  intros [sx|sx| |sx mx ex Hx]; [destruct sx; vm_compute; reflexivity | destruct sx; vm_compute; reflexivity | vm_compute; reflexivity |].
  rewrite fle_val; [| reflexivity | exact largest_finite_f_fin].
  apply Rle_bool_true. rewrite fabs_val, largest_finite_f_val.
  simpl BinarySingleNaN.B2R. rewrite <- F2R_Zabs, abs_cond_Zopp.
  pose proof (bounded_le_emax_minus_prec 53 1024 _ mx ex Hx) as H.
  replace (1024 - 53)%Z with 971%Z in H by reflexivity.
  replace (bpow radix2 1024) with (bpow radix2 53 * bpow radix2 971) in H
    by (rewrite <- bpow_plus; reflexivity).
  change (bpow radix2 53) with (IZR 9007199254740992) in H.
  change (Z.abs (Zpos mx)) with (Zpos mx). lra.
Qed.
