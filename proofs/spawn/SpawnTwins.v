(** * The twins of spawn's two enclosures (kernel/src/spawn/spawn_certified.hpp), over IEEE-754 binary64, tied to
    SpawnRounding.v and SpawnAffine.v.

    [midpoint_offset_b] and [affine_enclosure_b] are spawn_certified.hpp's [midpoint_offset] and
    [affine_enclosure], operation by operation in the C++ order, over FloatCore.v's binary64 and the compiled
    constants [Cpp.midpoint_offset_relative], [Cpp.affine_propagation_factor], [Cpp.affine_absolute]
    (ConstantsCpp.v, whose generated lemmas [cpp_NAME] tie each to Constants.v's value).  [affine_enclosure_b]
    calls PlaneTwins.v's [two_sum_b], [dot3_rounded_b] and [compensated_dot3_b] (the twins of eft.hpp's two_sum,
    dot3_filter.hpp's dot3_rounded and dot3_compensated.hpp's compensated_dot3, themselves run by the runner's
    routines two_sum, dot3_rounded, compensated).  The differential runner (proofs/twins/, group [spawn],
    routines [midpoint_offset] and [affine_enclosure]) compares both twins with the compiled C++ bit for bit.

    - [midpoint_offset_twin_sound]: for every bit pattern of x, y, o, when the twin's hi, lo and radius are
      finite, x, y and o are finite, (hi, lo, radius) as reals is SpawnRounding.v's model [midpoint_offset] of
      the same reals, and so ([midpoint_offset_encloses]) |(x + y − 2·o) − (hi + lo)| ≤ radius.
    - [affine_enclosure_twin_sound]: for every bit pattern of o, d and of the six parts of D and N, when the
      twin's hi, lo and radius are finite, every input is finite, the enclosure as reals is SpawnAffine.v's model
      [affine_enclosure] of the same reals, and so ([affine_enclosure_sound]) it encloses o·X_D + d·X_N for every
      X_D, X_N that D and N enclose.

    A non-finite result (an overflow, or a non-finite input) is the C++'s "no information": the comparison that
    consumes the enclosure (compare_quotients_compensated's enclosure_sign, round_quotient) is then uncertain;
    the theorems say nothing about it, as PlaneTwins.v's [compensated_dot3_twin] does not. *)

From Coq Require Import Reals Lra Lia ZArith.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Constants Model FloatCore ConstantsCpp PlaneCompensated PlaneTwins.
From Raykernel Require Import SpawnRounding SpawnAffine.
Open Scope R_scope.

(** The literal 2 of [-(2 * o)] (0x4000000000000000). *)
Definition spawn_two : float := of_bits 4611686018427387904.

Lemma spawn_two_value : B2R spawn_two = 2 /\ fin spawn_two = true.
Proof. split; [float_real spawn_two; lra | vm_compute; reflexivity]. Qed.

(** ** midpoint_offset *)

(** [midpoint_offset(x, y, o)]: s = two_sum(x, y), h = two_sum(s.hi, −(2·o)), lo = h.lo + s.lo,
    {h.hi, lo, midpoint_offset_relative · |lo|}. *)
Definition midpoint_offset_b (x y o : float) : EnclosureB :=
  let s := two_sum_b x y in
  let h := two_sum_b (fst s) (fneg (fmul spawn_two o)) in
  let lo := fadd (snd h) (snd s) in
  {| hib := fst h; lob := lo; radiusb := fmul Cpp.midpoint_offset_relative (fabs lo) |}.

Theorem midpoint_offset_twin_sound : forall x y o : float,
  let e := midpoint_offset_b x y o in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  fin x = true /\ fin y = true /\ fin o = true /\
  (B2R (hib e), B2R (lob e), B2R (radiusb e)) = midpoint_offset (B2R x) (B2R y) (B2R o) /\
  Rabs ((B2R x + B2R y - 2 * B2R o) - (B2R (hib e) + B2R (lob e))) <= B2R (radiusb e).
Proof.
  intros x y o e Fh Fl Fr. subst e. unfold midpoint_offset_b in *. cbv zeta in *. cbn [hib lob radiusb] in *.
  destruct spawn_two_value as [V2 F2].
  fin_down2.
  assert (E : (B2R (fst (two_sum_b (fst (two_sum_b x y)) (fneg (fmul spawn_two o)))),
               B2R (fadd (snd (two_sum_b (fst (two_sum_b x y)) (fneg (fmul spawn_two o)))) (snd (two_sum_b x y))),
               B2R (fmul Cpp.midpoint_offset_relative
                      (fabs (fadd (snd (two_sum_b (fst (two_sum_b x y)) (fneg (fmul spawn_two o))))
                                  (snd (two_sum_b x y))))))
              = midpoint_offset (B2R x) (B2R y) (B2R o)).
  { unfold midpoint_offset. cbv zeta. to_model2. rewrite V2, cpp_midpoint_offset_relative. reflexivity. }
  split; [assumption|]. split; [assumption|]. split; [assumption|]. split; [exact E|].
  pose proof (midpoint_offset_encloses (B2R x) (B2R y) (B2R o) (binary64_B2R _) (binary64_B2R _) (binary64_B2R _))
    as Enc.
  rewrite <- E in Enc. exact Enc.
Qed.

(** ** affine_enclosure *)

(** [affine_enclosure(o, D, d, N)]: dd = two_sum(D.hi, D.lo), nn = two_sum(N.hi, N.lo); a = {dd.hi, nn.hi, 0},
    alpha = {dd.lo, nn.lo, 0}, b = {o, d, 0} (the literal 0 is +0); v = compensated_dot3(a, alpha, b,
    dot3_rounded(a, b)); propagated = |o|·D.radius + |d|·N.radius;
    {v.hi, v.lo, affine_propagation_factor · (propagated + v.radius) + affine_absolute}. *)
Definition affine_enclosure_b (o : float) (D : EnclosureB) (d : float) (N : EnclosureB) : EnclosureB :=
  let dd := two_sum_b (hib D) (lob D) in
  let nn := two_sum_b (hib N) (lob N) in
  let v := compensated_dot3_b (fst dd) (fst nn) fzero (snd dd) (snd nn) fzero o d fzero
             (dot3_rounded_b (fst dd) (fst nn) fzero o d fzero) in
  let propagated := fadd (fmul (fabs o) (radiusb D)) (fmul (fabs d) (radiusb N)) in
  {| hib := hib v; lob := lob v;
     radiusb := fadd (fmul Cpp.affine_propagation_factor (fadd propagated (radiusb v))) Cpp.affine_absolute |}.

(** The twin's fields from its dot product v, kept as a variable: the kernel then never compares the enclosure
    of [affine_enclosure_b] with the one of [compensated_dot3_b] field by field (their radii differ, and deciding
    that through Flocq's arithmetic on symbolic operands takes minutes). *)
Lemma affine_enclosure_b_fields : forall (o d : float) (D N : EnclosureB),
  exists v : EnclosureB,
    v = compensated_dot3_b (fst (two_sum_b (hib D) (lob D))) (fst (two_sum_b (hib N) (lob N))) fzero
          (snd (two_sum_b (hib D) (lob D))) (snd (two_sum_b (hib N) (lob N))) fzero o d fzero
          (dot3_rounded_b (fst (two_sum_b (hib D) (lob D))) (fst (two_sum_b (hib N) (lob N))) fzero o d fzero) /\
    affine_enclosure_b o D d N =
      {| hib := hib v; lob := lob v;
         radiusb := fadd (fmul Cpp.affine_propagation_factor
                            (fadd (fadd (fmul (fabs o) (radiusb D)) (fmul (fabs d) (radiusb N))) (radiusb v)))
                         Cpp.affine_absolute |}.
Proof. intros o d D N. eexists. split; reflexivity. Qed.

Theorem affine_enclosure_twin_sound : forall (o d : float) (D N : EnclosureB),
  let e := affine_enclosure_b o D d N in
  fin (hib e) = true -> fin (lob e) = true -> fin (radiusb e) = true ->
  (fin o = true /\ fin d = true /\ fin (hib D) = true /\ fin (lob D) = true /\ fin (radiusb D) = true /\
   fin (hib N) = true /\ fin (lob N) = true /\ fin (radiusb N) = true) /\
  enc_R e = affine_enclosure (B2R o) (enc_R D) (B2R d) (enc_R N) /\
  (forall XD XN : R, encloses (enc_R D) XD -> encloses (enc_R N) XN ->
     encloses (enc_R e) (B2R o * XD + B2R d * XN)).
Proof.
  intros o d D N e Fh Fl Fr. subst e.
  destruct (affine_enclosure_b_fields o d D N) as [v [Hv He]]. rewrite He in Fh, Fl, Fr |- *.
  cbn [hib lob radiusb] in Fh, Fl, Fr.
  fin_down.
  (* compensated_dot3's twin: its inputs finite, its enclosure the model's *)
  assert (Fv : fin (radiusb v) = true /\ fin (hib v) = true /\ fin (lob v) = true) by (repeat split; assumption).
  rewrite Hv in Fv. destruct Fv as [Fvr [Fvh Fvl]].
  destruct (compensated_dot3_twin _ _ _ _ _ _ _ _ _ Fvr Fvh Fvl)
    as [_ [_ [_ [Fdl [Fnl [_ [Fo [Fd [_ [_ [_ Ev]]]]]]]]]]].
  rewrite <- Hv in Ev.
  destruct (two_sum_b_inv (hib D) (lob D) Fdl) as [FDh [FDl [_ [Ed1 Ed2]]]].
  destruct (two_sum_b_inv (hib N) (lob N) Fnl) as [FNh [FNl [_ [En1 En2]]]].
  rewrite Ed1, Ed2, En1, En2 in Ev. change (B2R fzero) with 0 in Ev.
  clear Hv He.
  assert (E : enc_R {| hib := hib v; lob := lob v;
                       radiusb := fadd (fmul Cpp.affine_propagation_factor
                                          (fadd (fadd (fmul (fabs o) (radiusb D)) (fmul (fabs d) (radiusb N)))
                                                (radiusb v))) Cpp.affine_absolute |}
              = affine_enclosure (B2R o) (enc_R D) (B2R d) (enc_R N)).
  { unfold affine_enclosure. cbv zeta.
    change (hi (enc_R D)) with (B2R (hib D)). change (lo (enc_R D)) with (B2R (lob D)).
    change (radius (enc_R D)) with (B2R (radiusb D)).
    change (hi (enc_R N)) with (B2R (hib N)). change (lo (enc_R N)) with (B2R (lob N)).
    change (radius (enc_R N)) with (B2R (radiusb N)).
    rewrite <- Ev. unfold enc_R. cbn [hi lo radius hib lob radiusb].
    to_model_ops. rewrite cpp_affine_propagation_factor, cpp_affine_absolute. reflexivity. }
  split; [repeat split; assumption|]. split; [exact E|].
  intros XD XN ED EN. rewrite E.
  apply affine_enclosure_sound; try assumption; cbn [enc_R hi lo radius]; apply binary64_B2R.
Qed.
