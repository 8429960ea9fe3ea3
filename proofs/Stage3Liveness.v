(** * Liveness of stage 3 of the ray–plane cascade (the expansion stage's checked sign).

    [Expansion::sign()] (kernel/src/certified/expansion.hpp), twinned by [expansion_sign_b]
    (Expansions.v), returns uncertain unless 2·(rounded Σ|lower components|) < |top| or the expansion is
    the single 0.  Soundness is [expansion_sign_sound]; this file proves that it does certify:
    - [expansion_sign_single_certain]: on every expansion of ONE finite component (what the builder's
      zero elimination leaves whenever every TwoSum/TwoProduct low part is 0, e.g. small integer inputs)
      the twin's checked sign is certain, and ([expansion_sign_single_exact]) it is the sign of the
      component, zero included;
    - [stage3_plane_live_example]: non-vacuity at the cascade level, by computation on the twin the runner
      checks against the C++: o = (0,0,0), d = (1,1,0), p = (1,0,0), n = (1,−1,0) (den = 1 − 1 = 0, a
      parallel ray whose products cancel, num = 1): stage 1 ([den_filter_b]) and stage 2 ([den_sign2_b])
      leave den's sign uncertain, the expansions are exact, den's expansion is the single 0 and num's the
      single 1, and [relation_b] answers Parallel at [StExpansion], before the exact stage.

    Not proved here (proofs/README.md, "What remains"): that on the whole class "every input an integer of
    magnitude ≤ 2^k" the builder's expansions have one component (every low part 0). *)

From Coq Require Import Reals ZArith List Lia.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model Cascade FloatCore Twins Expansions QueryTwins QueryPairTwins CascadeTwins
  Classification.
Import ListNotations.

(** A one-component expansion: the lower magnitude is +0, so the top decides unless it is ±0, and then
    the expansion is the single zero. *)
Theorem expansion_sign_single_certain : forall x, fin x = true -> expansion_sign_b [x] <> Uncertain.
Proof.
  intros x F. unfold expansion_sign_b.
  change (lower_magnitude [x]) with fzero. change (last [x] fzero) with x.
  destruct x as [s | s | | s m e H]; try discriminate F.
  - destruct s; vm_compute; discriminate.
  - destruct s; cbv [fabs flt fadd fzero Babs Bplus Bltb]; simpl; discriminate.
Qed.

Theorem expansion_sign_single_exact : forall x, fin x = true ->
  expansion_sign_b [x] <> Uncertain /\ certifies (expansion_sign_b [x]) (B2R x).
Proof.
  intros x F. split; [now apply expansion_sign_single_certain |].
  replace (B2R x) with (sumR [x]) by (unfold sumR; simpl; ring).
  apply expansion_sign_sound; [constructor; [exact F | constructor] | simpl; lia].
Qed.

(** The cascade-level consequence: when the builder's expansions are exact and each has one component,
    stage 3 answers ([certified_signs_b]'s stage is not [StExact], so [relation_b] does not hand the query
    to the exact stage) and its signs are the exact signs of num and den. *)
Theorem certified_signs_single_live : forall o d p n x y,
  expansions_b o d p n = ([x], [y], true) ->
  snd (certified_signs_b o d p n) <> StExact.
Proof.
  intros o d p n x y H.
  pose proof (ray_plane_expansions_twin_exact o d p n) as X.
  change (ray_plane_expansions_b two_sum_b o d p n) with (expansions_b o d p n) in X.
  rewrite H in X. destruct (X eq_refl) as [Fn [Fd _]].
  inversion Fn as [| ? ? Fx _]; inversion Fd as [| ? ? Fy _]; subst.
  assert (Cx : is_certain (expansion_sign_b [x]) = true).
  { destruct (expansion_sign_b [x]) eqn:E; try reflexivity. exfalso; now apply (expansion_sign_single_certain x). }
  assert (Cy : is_certain (expansion_sign_b [y]) = true).
  { destruct (expansion_sign_b [y]) eqn:E; try reflexivity. exfalso; now apply (expansion_sign_single_certain y). }
  unfold certified_signs_b.
  destruct (is_certain (den_filter_b d n) && is_certain (num_filter_b o p n))%bool; [discriminate|].
  destruct (is_certain (den_sign2_b d n) && is_certain (num_sign2_b o p n))%bool; [discriminate|].
  rewrite H. cbv beta iota. rewrite Cx, Cy. discriminate.
Qed.

(** The same for [relation_b] on a valid query: it decides, at a stage before the exact one. *)
Theorem relation_single_live : forall o d p n x y,
  validate_b o d p n = None -> expansions_b o d p n = ([x], [y], true) ->
  relation_b o d p n <> CExact.
Proof.
  intros o d p n x y V H. pose proof (certified_signs_single_live o d p n x y H) as L.
  unfold relation_b. rewrite V.
  destruct (certified_signs_b o d p n) as [[ns ds] st]. simpl in L.
  destruct st; try discriminate. contradiction.
Qed.

(** The concrete input: small integers as doubles. *)
Definition fint (z : Z) : float := @binary_normalize 53 1024 eq_refl _ mode_NE z 0 false.
Definition live_o := V3 (fint 0) (fint 0) (fint 0).
Definition live_d := V3 (fint 1) (fint 1) (fint 0).
Definition live_p := V3 (fint 1) (fint 0) (fint 0).
Definition live_n := V3 (fint 1) (fint (-1)) (fint 0).

Theorem stage3_plane_live_example :
  den_filter_b live_d live_n = Uncertain /\ den_sign2_b live_d live_n = Uncertain /\
  snd (expansions_b live_o live_d live_p live_n) = true /\
  snd (fst (expansions_b live_o live_d live_p live_n)) = [fzero] /\
  expansion_sign_b (snd (fst (expansions_b live_o live_d live_p live_n))) = Zero /\
  expansion_sign_b (fst (fst (expansions_b live_o live_d live_p live_n))) = Positive /\
  relation_b live_o live_d live_p live_n = CDecided Parallel StExpansion TNaN.
Proof. vm_compute. repeat split; reflexivity. Qed.
