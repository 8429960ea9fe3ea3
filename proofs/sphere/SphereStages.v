(** * The expansion stage of the ray–sphere query, kernel/src/sphere/ray_sphere_stages.hpp, as twins, proved
    exact and sound.

    Twins, operation by operation in the C++ order, the builder's flag [exact_] threaded through as a bool (as
    Expansions.v's [build_expansions_gen] does for ray_plane_expansions), on Expansions.v's twins of the
    primitives ([from_pair], [product_b], [scale_b], [sum_b], [multiply_gen] with TwoSum, [check_finite],
    [expansion_sign_b]) and ExpansionCompress.v's [compress_b]:
    - [sphere_coord_b]: the body of [sphere_expansions]' loop for coordinate i: f_i = from_pair(TwoDiff(o_i,
      c_i)) (PlaneTwins.v's [two_diff_b] is TwoSum(o_i, −c_i), eft.hpp's two_diff), check_finite(f_i),
      dd_i = from_pair(builder.product(d_i, d_i)), fd_i = builder.scale(f_i, d_i), ff_i = f_i·f_i;
    - [sphere_abc_expansions_b]: [sphere_abc_expansions]: the three coordinates, then sum3 ([sum3_b]:
      ((x + y) + z)) of the dd_i, of the fd_i and of the ff_i, r² = from_pair(builder.product(r, r)) negated
      ([map fneg]), c = Σff + (−r²), the checks of a, b, c, their compressions s.a, s.b, s.c and their
      checks; it returns the flag and (s.a, s.b, s.c);
    - [sphere_d_expansion_b]: [sphere_d_expansion]: b_squared = s.b·s.b, a_c = s.c·s.a negated,
      s.d = b_squared + (−a_c) and the three final checks;
    - [sphere_expansions_b]: [sphere_expansions], the two in turn: the flag and (s.a, s.b, s.c, s.d);
    - [sign_or_compressed_b]: ExpansionBuilder::sign_or_compressed (expansion.hpp): the checked sign of e, or
      when it is uncertain the checked sign of compress(e);
    - [sphere_root_side_b]: [sphere_root_side]: M = from_pair(TwoSum(x, y)), its check, mm = M·M,
      a_mm = mm·A, b_m = B·M, b_m4 = 4·b_m, c4 = 4·C, q4 = sum3(a_mm, b_m4, c4), a_m = A·M, b2 = 2·B,
      slope2 = a_m + b2, the two checks, [Uncertain] unless the builder is exact, the two signs, and
      sign_from_int(root_side_of(root, sign q4, sign slope2)) ([root_side_of] of SphereRoots.v; the enum
      Sign as its ints −1, 0, 1, 2: [sign_to_int]).  The literals 4.0 and 2.0 are [ffour] and [ftwo], by
      their bits.

    What is proved, for every bit pattern of the inputs:
    - [sphere_abc_expansions_exact]: when the flag of [sphere_abc_expansions_b] is true (the C++ caller's
      [builder.exact()]), every component of s.a, s.b, s.c is finite and their exact sums are A = Σ d_i²,
      B = Σ d_i·(o_i − c_i) and C = Σ (o_i − c_i)² − r² of the inputs' real values;
      [sphere_expansions_exact]: the same for [sphere_expansions_b], and s.d's exact sum is D = B² − A·C;
      [sphere_abc_expansions_length], [sphere_expansions_length]: they fit the capacities 6, 12, 26, 600 of
      [SphereExpansions];
    - [sphere_sign_or_compressed_sound]: a certain answer of the two-try sign is the sign of the exact sum,
      for any list of finite doubles (at most 2^20): [expansion_sign_sound] on e, or on compress(e) with
      [compress_gen_exact]; the compression is not checked for finiteness by the C++, and need not be:
      [compress_finite_or_uncertain] shows that compress of finite doubles is finite or has a NaN below its
      top component (PlaneStageTwoFinite.v's [two_sum_b_nan_or_finite]: an overflowing TwoSum has a NaN low
      part, and a NaN spreads through the later TwoSums), and then its checked sign is [Uncertain];
    - [sphere_root_side_sound]: for expansions a, b, c of at most 6, 12, 26 components with A = Σa > 0 and
      D = B² − A·C ≥ 0 (B = Σb, C = Σc), a certain [sphere_root_side_b] is the sign of t_k − (x + y)/2,
      t_k the smaller root t1 of SphereRoots.v when root < 0 and the larger t2 otherwise (the C++ passes
      −1 or +1): the sums of q4 and slope2 are 4·q(m) and 2·(A·m + B) for m = (x + y)/2, whose signs
      [root_side_of_smaller_correct] and [root_side_of_larger_correct] turn into sign(t_k − m);
    - [sphere_root_side_expansions_sound]: the two composed, on the expansions of [sphere_abc_expansions_b]. *)

From Coq Require Import Reals Lra Lia ZArith List Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model FloatCore PlaneTwins Expansions ExpansionCompress SphereRoots.
From Raykernel Require PlaneStageTwoFinite PlaneCascade.
Import ListNotations.
Open Scope R_scope.

(** ** The twins *)

Notation multiply_b := (multiply_gen two_sum_b).

(** The literals 4.0 (0x4010000000000000) and 2.0 (0x4000000000000000) of [sphere_root_side]. *)
Definition ffour : float := of_bits 4616189618054758400.
Definition ftwo : float := of_bits 4611686018427387904.

(** [sum3(x, y, z, h)]: xy = x + y, then h = xy + z. *)
Definition sum3_b (x y z : list float) : list float := sum_b (sum_b x y) z.

(** The body of [sphere_expansions]' loop for one coordinate: the flag after it, and f_i, dd_i, fd_i, ff_i. *)
Definition sphere_coord_b (ex : bool) (o d c : float)
  : bool * (list float * list float * list float * list float) :=
  let f := from_pair (two_diff_b o c) in
  let ex1 := check_finite ex f in
  let pd := product_b ex1 d d in
  let dd := from_pair (snd pd) in
  let fd := scale_b (fst pd) f d in
  let ff := multiply_b (fst fd) f f in
  (fst ff, (f, dd, snd fd, snd ff)).

(** [sphere_abc_expansions(ray, sphere, s)]: the builder's flag and s.a, s.b, s.c. *)
Definition sphere_abc_expansions_b (o d c : float * float * float) (r : float)
  : bool * list float * list float * list float :=
  let '(o0, o1, o2) := o in
  let '(d0, d1, d2) := d in
  let '(c0, c1, c2) := c in
  let '(ex0, (f0, dd0, fd0, ff0)) := sphere_coord_b true o0 d0 c0 in
  let '(ex1, (f1, dd1, fd1, ff1)) := sphere_coord_b ex0 o1 d1 c1 in
  let '(ex2, (f2, dd2, fd2, ff2)) := sphere_coord_b ex1 o2 d2 c2 in
  let a := sum3_b dd0 dd1 dd2 in
  let b := sum3_b fd0 fd1 fd2 in
  let f_squared := sum3_b ff0 ff1 ff2 in
  let pr := product_b ex2 r r in
  let r_squared := map fneg (from_pair (snd pr)) in
  let c := sum_b f_squared r_squared in
  let ex3 := check_finite (check_finite (check_finite (fst pr) a) b) c in
  let sa := compress_b a in
  let sb := compress_b b in
  let sc := compress_b c in
  (check_finite (check_finite (check_finite ex3 sa) sb) sc, sa, sb, sc).

(** [sphere_d_expansion(s)]: from the flag and s.a, s.b, s.c, the flag after it and s.d. *)
Definition sphere_d_expansion_b (ex : bool) (sa sb sc : list float) : bool * list float :=
  let b_squared := multiply_b ex sb sb in
  let a_c := multiply_b (fst b_squared) sc sa in
  let neg_a_c := map fneg (snd a_c) in
  let sd := sum_b (snd b_squared) neg_a_c in
  (check_finite (check_finite (check_finite (fst a_c) (snd b_squared)) neg_a_c) sd, sd).

(** [sphere_expansions(ray, sphere, s)]: the two above; the builder's flag and s.a, s.b, s.c, s.d. *)
Definition sphere_expansions_b (o d c : float * float * float) (r : float)
  : bool * list float * list float * list float * list float :=
  let '(ex, sa, sb, sc) := sphere_abc_expansions_b o d c r in
  let '(ex', sd) := sphere_d_expansion_b ex sa sb sc in
  (ex', sa, sb, sc, sd).

(** [ExpansionBuilder::sign_or_compressed(e)]. *)
Definition sign_or_compressed_b (e : list float) : sign :=
  let direct := expansion_sign_b e in
  if PlaneCascade.is_certain direct then direct else expansion_sign_b (compress_b e).

(** [static_cast<int>(Sign)] (sign.hpp: negative = −1, zero = 0, positive = 1, uncertain = 2). *)
Definition sign_to_int (s : sign) : Z :=
  match s with Negative => (-1)%Z | Zero => 0%Z | Positive => 1%Z | Uncertain => 2%Z end.

(** [sign_from_int(s)]: s < 0 ? negative : (s > 0 ? positive : zero). *)
Definition sign_from_int (i : Z) : sign :=
  if Z.ltb i 0 then Negative else if Z.ltb 0 i then Positive else Zero.

(** [sphere_root_side(s, root, x, y)], on s.a, s.b, s.c. *)
Definition sphere_root_side_b (a b c : list float) (root : Z) (x y : float) : sign :=
  let m2 := from_pair (two_sum_b x y) in
  let ex0 := check_finite true m2 in
  let mm := multiply_b ex0 m2 m2 in
  let a_mm := multiply_b (fst mm) (snd mm) a in
  let b_m := multiply_b (fst a_mm) b m2 in
  let b_m4 := scale_b (fst b_m) (snd b_m) ffour in
  let c4 := scale_b (fst b_m4) c ffour in
  let q4 := sum3_b (snd a_mm) (snd b_m4) (snd c4) in
  let a_m := multiply_b (fst c4) a m2 in
  let b2 := scale_b (fst a_m) b ftwo in
  let slope2 := sum_b (snd a_m) (snd b2) in
  let ex := check_finite (check_finite (fst b2) q4) slope2 in
  if negb ex then Uncertain else
  let q := sign_or_compressed_b q4 in
  let slope := sign_or_compressed_b slope2 in
  if (negb (PlaneCascade.is_certain q) || negb (PlaneCascade.is_certain slope))%bool then Uncertain
  else sign_from_int (root_side_of root (sign_to_int q) (sign_to_int slope)).

(** The real values of the query: A = d·d, B = d·f, C = f·f − r² with f = o − c; D is SphereRoots.v's
    [sphere_disc] = B² − A·C. *)
Definition sphere_A (d0 d1 d2 : R) : R := d0 * d0 + d1 * d1 + d2 * d2.
Definition sphere_B (o0 o1 o2 d0 d1 d2 c0 c1 c2 : R) : R :=
  d0 * (o0 - c0) + d1 * (o1 - c1) + d2 * (o2 - c2).
Definition sphere_C (o0 o1 o2 c0 c1 c2 r : R) : R :=
  (o0 - c0) * (o0 - c0) + (o1 - c1) * (o1 - c1) + (o2 - c2) * (o2 - c2) - r * r.

(** ** Small facts *)

Lemma ffour_val : B2R ffour = 4.
Proof. float_real ffour. lra. Qed.

Lemma ftwo_val : B2R ftwo = 2.
Proof. float_real ftwo. lra. Qed.

Lemma length_sum3 : forall x y z, (length (sum3_b x y z) <= length x + length y + length z)%nat.
Proof.
  intros x y z. unfold sum3_b. pose proof (length_sum_gen two_sum_b (sum_b x y) z).
  pose proof (length_sum_gen two_sum_b x y). lia.
Qed.

Lemma sum3_exact : forall x y z, all_fin (sum3_b x y z) ->
  all_fin x /\ all_fin y /\ all_fin z /\ sumR (sum3_b x y z) = sumR x + sumR y + sumR z.
Proof.
  intros x y z H. unfold sum3_b in *. destruct (sum_gen_exact _ _ H) as [Fxy [Fz S]].
  destruct (sum_gen_exact _ _ Fxy) as [Fx [Fy S']]. repeat split; auto. lra.
Qed.

(** A product's first factor is finite when the product is and the second factor is not empty. *)
Lemma multiply_fin_left : forall ex e f, fst (multiply_b ex e f) = true -> all_fin (snd (multiply_b ex e f)) ->
  f <> nil -> all_fin e.
Proof.
  intros ex e [|f0 rest] Hx H N; [contradiction|]. unfold multiply_gen in *.
  destruct (accumulate_exact rest _ _ _ Hx H) as [Ex [Fp _]].
  now destruct (scale_gen_exact _ _ _ Ex Fp) as [_ [Fe _]].
Qed.

Lemma sumR_nil_nonzero : forall l, sumR l <> 0 -> l <> nil.
Proof. intros l H E. subst l. apply H. reflexivity. Qed.

(** ** The real values of the signs *)

Lemma certifies_sign_to_int : forall s x, certifies s x -> s <> Uncertain -> sign_to_int s = Rsign x.
Proof.
  intros [| | |] x C U; cbn in *; [| | | congruence]; unfold Rsign;
    destruct (Rlt_dec x 0); destruct (Req_EM_T x 0); first [reflexivity | lra].
Qed.

Lemma sign_from_int_Rsign : forall x, certifies (sign_from_int (Rsign x)) x.
Proof.
  intros x. destruct (Rsign_cases x) as [[L E]|[[L E]|[L E]]]; rewrite E; cbn; lra.
Qed.

Lemma Rsign_scale : forall k x, 0 < k -> Rsign (k * x) = Rsign x.
Proof.
  intros k x Hk. replace (k * x) with (x / / k) by (field; lra).
  apply Rsign_div_pos. now apply Rinv_0_lt_compat.
Qed.

(** [root_side_of] reads only whether root < 0. *)
Lemma root_side_of_root : forall root s t,
  root_side_of root s t = root_side_of (if Z.ltb root 0 then (-1)%Z else 1%Z) s t.
Proof. intros root s t. unfold root_side_of. destruct (Z.ltb root 0); reflexivity. Qed.

(** ** The compression of finite doubles: finite, or its checked sign is uncertain *)

Lemma is_nan_eq : forall x : float, is_nan x = true -> x = B754_nan.
Proof. intros [| | |] H; try discriminate; reflexivity. Qed.

Lemma feq_nan : forall x, is_nan x = true -> feq x fzero = false.
Proof. intros x H. now rewrite (is_nan_eq x H). Qed.

Lemma two_sum_b_nan_l : forall x y, is_nan x = true ->
  is_nan (fst (two_sum_b x y)) = true /\ is_nan (snd (two_sum_b x y)) = true.
Proof.
  intros x y H. rewrite (is_nan_eq x H). unfold two_sum_b. cbn [fst snd].
  split; [now apply PlaneStageTwoFinite.fadd_nan_l|].
  apply PlaneStageTwoFinite.fadd_nan_l, PlaneStageTwoFinite.fsub_nan_r, PlaneStageTwoFinite.fsub_nan_l,
    PlaneStageTwoFinite.fadd_nan_l. reflexivity.
Qed.

Lemma two_sum_b_nan_r : forall x y, is_nan y = true ->
  is_nan (fst (two_sum_b x y)) = true /\ is_nan (snd (two_sum_b x y)) = true.
Proof.
  intros x y H. rewrite (is_nan_eq y H). unfold two_sum_b. cbn [fst snd].
  split; [now apply PlaneStageTwoFinite.fadd_nan_r|].
  apply PlaneStageTwoFinite.fadd_nan_r, PlaneStageTwoFinite.fsub_nan_l. reflexivity.
Qed.

(** TwoSum of finite doubles: both parts finite, or a NaN low part (an overflowing sum: inf − inf in the
    low part; a finite sum: PlaneStageTwoFinite.v's [two_sum_b_nan_or_finite]). *)
Lemma two_sum_b_finite_or_nan : forall a b, fin a = true -> fin b = true ->
  (fin (fst (two_sum_b a b)) = true /\ fin (snd (two_sum_b a b)) = true) \/ is_nan (snd (two_sum_b a b)) = true.
Proof.
  intros a b Fa Fb. destruct (fin (fadd a b)) eqn:Fs.
  - destruct (PlaneStageTwoFinite.two_sum_b_nan_or_finite a b Fa Fb Fs) as [N|F]; [now right|left].
    destruct (two_sum_b_inv a b F) as [_ [_ [Fh _]]]. now split.
  - right. unfold two_sum_b. cbn [snd]. set (s := fadd a b) in *. clearbody s.
    destruct s as [sg|sg| |sg ms es Hs]; try discriminate.
    + destruct a as [sa|sa| |sa ma ea Ha]; try discriminate;
        destruct b as [sb|sb| |sb mb eb Hb]; try discriminate; destruct sg; reflexivity.
    + apply PlaneStageTwoFinite.fadd_nan_r, PlaneStageTwoFinite.fsub_nan_r, PlaneStageTwoFinite.fsub_nan_l.
      reflexivity.
Qed.

Definition has_nan (l : list float) : bool := existsb (fun x => is_nan x) l.

Lemma fold_magnitude_nan : forall l acc, (is_nan acc || has_nan l)%bool = true ->
  is_nan (fold_left (fun a x => fadd a (fabs x)) l acc) = true.
Proof.
  induction l as [|x l IH]; intros acc H; cbn [fold_left].
  - cbn in H. now rewrite orb_false_r in H.
  - apply IH. cbn [has_nan existsb] in H. unfold has_nan.
    destruct (is_nan acc) eqn:Na; [now rewrite PlaneStageTwoFinite.fadd_nan_l|].
    destruct (is_nan x) eqn:Nx.
    + rewrite PlaneStageTwoFinite.fadd_nan_r; [reflexivity|]. rewrite (is_nan_eq x Nx). reflexivity.
    + cbn in H. now rewrite H, orb_true_r.
Qed.

(** A NaN below the top component makes the checked sign uncertain: the magnitude of the lower components
    is NaN, the list has more than one component, and a NaN has neither sign. *)
Lemma expansion_sign_nan_lower : forall l, has_nan (removelast l) = true -> expansion_sign_b l = Uncertain.
Proof.
  intros l H. unfold expansion_sign_b.
  assert (Na : is_nan (lower_magnitude l) = true) by (apply fold_magnitude_nan; now rewrite H).
  rewrite PlaneStageTwoFinite.flt_nan_l by now apply PlaneStageTwoFinite.fadd_nan_l.
  assert (L : Nat.eqb (length l) 1 = false).
  { destruct l as [|x [|y l]]; try reflexivity; discriminate. }
  rewrite L. cbn [andb].
  assert (W : forall pos, forallb (weakly_signed pos) (removelast l) = false).
  { intros pos. apply not_true_is_false. intros F. rewrite forallb_forall in F.
    unfold has_nan in H. apply existsb_exists in H. destruct H as [x [Ix Nx]].
    specialize (F x Ix). rewrite (is_nan_eq x Nx) in F. destruct pos; discriminate. }
  rewrite W, andb_false_r. reflexivity.
Qed.

Lemma compress_down_nan : forall rest q big, is_nan q = true -> big <> nil ->
  is_nan (snd (compress_down q big rest)) = true /\ fst (compress_down q big rest) <> nil.
Proof.
  induction rest as [|x rest IH]; intros q big Nq Nb; cbn [compress_down]; [now split|].
  destruct (two_sum_b_nan_l q x Nq) as [_ Nl]. rewrite feq_nan by exact Nl. cbn [negb].
  apply IH; [exact Nl | discriminate].
Qed.

Lemma compress_down_finite_or_nan : forall rest q big, fin q = true -> all_fin big -> all_fin rest ->
  (fin (snd (compress_down q big rest)) = true /\ all_fin (fst (compress_down q big rest))) \/
  (is_nan (snd (compress_down q big rest)) = true /\ fst (compress_down q big rest) <> nil).
Proof.
  induction rest as [|x rest IH]; intros q big Fq Fb Fr; cbn [compress_down]; [left; now split|].
  inversion Fr as [|? ? Fx Frest]; subst.
  destruct (two_sum_b_finite_or_nan q x Fq Fx) as [[Fh Fl]|Nl].
  - destruct (negb (feq (snd (two_sum_b q x)) fzero)); apply IH; auto. now constructor.
  - right. rewrite feq_nan by exact Nl. cbn [negb]. apply compress_down_nan; [exact Nl | discriminate].
Qed.

Lemma compress_up_keep_nan : forall big q low, has_nan low = true ->
  has_nan (removelast (compress_up q low big)) = true.
Proof.
  induction big as [|b big IH]; intros q low H; cbn [compress_up].
  - now rewrite removelast_last.
  - apply IH. rewrite compress_write_push. unfold push. destruct (feq _ fzero); [exact H|].
    unfold has_nan in *. rewrite existsb_app, H. reflexivity.
Qed.

Lemma compress_up_nan : forall big q low, is_nan q = true -> big <> nil ->
  has_nan (removelast (compress_up q low big)) = true.
Proof.
  intros [|b big] q low Nq Nb; [contradiction|]. cbn [compress_up].
  destruct (two_sum_b_nan_r b q Nq) as [_ Nl]. rewrite feq_nan by exact Nl. cbn [negb].
  apply compress_up_keep_nan. unfold has_nan. rewrite existsb_app. cbn [existsb]. rewrite Nl, orb_true_r. reflexivity.
Qed.

Lemma compress_up_finite_or_nan : forall big q low, fin q = true -> all_fin low -> all_fin big ->
  all_fin (compress_up q low big) \/ has_nan (removelast (compress_up q low big)) = true.
Proof.
  induction big as [|b big IH]; intros q low Fq Fl Fb; cbn [compress_up].
  - left. unfold all_fin in *. apply Forall_app. split; [exact Fl | now constructor].
  - inversion Fb as [|? ? Fb0 Fbig]; subst.
    destruct (two_sum_b_finite_or_nan b q Fb0 Fq) as [[Fh Flo]|Nl].
    + apply IH; auto. destruct (negb (feq _ fzero)); [|exact Fl].
      unfold all_fin in *. apply Forall_app. split; [exact Fl | now constructor].
    + right. rewrite feq_nan by exact Nl. cbn [negb]. apply compress_up_keep_nan.
      unfold has_nan. rewrite existsb_app. cbn [existsb]. rewrite Nl, orb_true_r. reflexivity.
Qed.

(** The C++ does not check compress(e) for finiteness: when e is finite, compress(e) is finite, or its
    checked sign is [Uncertain]. *)
Theorem compress_finite_or_uncertain : forall e, all_fin e ->
  all_fin (compress_b e) \/ expansion_sign_b (compress_b e) = Uncertain.
Proof.
  intros [|e0 rest] F; [left; constructor|].
  unfold compress_b. remember (e0 :: rest) as e eqn:Ee.
  assert (D : e = removelast e ++ [last e fzero]) by (apply app_removelast_last; subst e; discriminate).
  clear Ee. unfold all_fin in F. rewrite D in F. apply Forall_app in F. destruct F as [Fl Ft].
  inversion Ft as [|? ? Ftop _]; subst.
  assert (Fr : all_fin (rev (removelast e))) by (unfold all_fin; now apply Forall_rev).
  destruct (compress_down_finite_or_nan (rev (removelast e)) (last e fzero) [] Ftop ltac:(constructor) Fr)
    as [[Fq Fb]|[Nq Nb]].
  - destruct (compress_up_finite_or_nan _ _ [] Fq ltac:(constructor) Fb) as [A|N]; [now left|right].
    now apply expansion_sign_nan_lower.
  - right. apply expansion_sign_nan_lower. now apply compress_up_nan.
Qed.

(** ExpansionBuilder::sign_or_compressed: a certain answer is the sign of the exact sum, for any list of
    finite doubles (at most 2^20 of them). *)
Theorem sphere_sign_or_compressed_sound : forall e, all_fin e -> (Z.of_nat (length e) <= 1048576)%Z ->
  certifies (sign_or_compressed_b e) (sumR e).
Proof.
  intros e F L. unfold sign_or_compressed_b.
  destruct (PlaneCascade.is_certain (expansion_sign_b e)); [now apply expansion_sign_sound|].
  destruct (compress_finite_or_uncertain e F) as [Fc|U]; [|rewrite U; exact I].
  destruct (compress_gen_exact e Fc) as [_ S]. rewrite <- S.
  apply expansion_sign_sound; [exact Fc|]. pose proof (compress_length e). lia.
Qed.

(** ** sphere_expansions: A, B, C, D exactly *)

(** f_i = o_i − c_i exactly when f_i is finite. *)
Lemma two_diff_pair_exact : forall o c, all_fin (from_pair (two_diff_b o c)) ->
  sumR (from_pair (two_diff_b o c)) = B2R o - B2R c.
Proof.
  intros o c F. destruct (from_pair_exact _ F) as [_ [L S]]. rewrite S.
  pose proof (two_sum_twin_exact _ _ L) as T. unfold two_diff_b in *. rewrite fneg_val in T. lra.
Qed.

(** One coordinate: when the flag after it is true and dd_i, fd_i, ff_i are finite, the flag before it was
    true and they are d_i², d_i·(o_i − c_i), (o_i − c_i)². *)
Lemma sphere_coord_exact : forall ex o d c ex' f dd fd ff,
  sphere_coord_b ex o d c = (ex', (f, dd, fd, ff)) ->
  ex' = true -> all_fin dd -> all_fin fd -> all_fin ff ->
  ex = true /\ sumR dd = B2R d * B2R d /\ sumR fd = B2R d * (B2R o - B2R c) /\
  sumR ff = (B2R o - B2R c) * (B2R o - B2R c).
Proof.
  intros ex o d c ex' f dd fd ff E X Fdd Ffd Fff. unfold sphere_coord_b in E.
  injection E as Ex Ef Edd Efd Eff. subst ex' f dd fd ff.
  destruct (multiply_gen_exact _ _ _ X Fff) as [Xfd Sff].
  destruct (scale_gen_exact _ _ _ Xfd Ffd) as [Xpd [Ff [_ Sfd]]].
  cbn [product_b fst] in Xpd. apply andb_prop in Xpd. destruct Xpd as [X1 N].
  apply check_finite_true in X1. destruct X1 as [Xe _].
  destruct (from_pair_exact _ Fdd) as [_ [L Sdd]]. cbn [product_b snd] in L, Sdd.
  destruct (note_product_exact _ _ N L) as [_ [_ P]].
  pose proof (two_diff_pair_exact o c Ff) as Sf.
  repeat split; auto.
  - rewrite Sdd. cbn [product_b snd]. lra.
  - rewrite Sfd, Sf. reflexivity.
  - rewrite Sff, Sf. reflexivity.
Qed.

(** [sphere_abc_expansions]: when the builder says exact, s.a, s.b, s.c are finite and their exact sums are A,
    B and C of the query, whatever the 64-bit patterns of its inputs. *)
Theorem sphere_abc_expansions_exact : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r,
  let A := sphere_A (B2R d0) (B2R d1) (B2R d2) in
  let B := sphere_B (B2R o0) (B2R o1) (B2R o2) (B2R d0) (B2R d1) (B2R d2) (B2R c0) (B2R c1) (B2R c2) in
  let C := sphere_C (B2R o0) (B2R o1) (B2R o2) (B2R c0) (B2R c1) (B2R c2) (B2R r) in
  let '(ex, a, b, c) := sphere_abc_expansions_b (o0, o1, o2) (d0, d1, d2) (c0, c1, c2) r in
  ex = true ->
  all_fin a /\ all_fin b /\ all_fin c /\ sumR a = A /\ sumR b = B /\ sumR c = C.
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r A B C.
  destruct (sphere_abc_expansions_b (o0, o1, o2) (d0, d1, d2) (c0, c1, c2) r) as [[[ex a] b] c] eqn:E.
  intros Ex. unfold sphere_abc_expansions_b in E.
  destruct (sphere_coord_b true o0 d0 c0) as [ex0 [[[f0 dd0] fd0] ff0]] eqn:E0.
  destruct (sphere_coord_b ex0 o1 d1 c1) as [ex1 [[[f1 dd1] fd1] ff1]] eqn:E1.
  destruct (sphere_coord_b ex1 o2 d2 c2) as [ex2 [[[f2 dd2] fd2] ff2]] eqn:E2.
  injection E as Eex Ea Eb Ec. subst ex a b c.
  set (pr := product_b ex2 r r) in *.
  set (ua := sum3_b dd0 dd1 dd2) in *. set (ub := sum3_b fd0 fd1 fd2) in *.
  set (uc := sum_b (sum3_b ff0 ff1 ff2) (map fneg (from_pair (snd pr)))) in *.
  set (ex3 := check_finite (check_finite (check_finite (fst pr) ua) ub) uc) in *.
  (* the final checks *)
  apply check_finite_true in Ex. destruct Ex as [Ex Fc].
  apply check_finite_true in Ex. destruct Ex as [Ex Fb].
  apply check_finite_true in Ex. destruct Ex as [X3 Fa].
  (* the compressions *)
  destruct (compress_gen_exact _ Fa) as [Fua Sa]. destruct (compress_gen_exact _ Fb) as [Fub Sb].
  destruct (compress_gen_exact _ Fc) as [Fuc Sc].
  (* A, B, C before compression *)
  unfold ex3 in X3. apply check_finite_true in X3. destruct X3 as [X3 _].
  apply check_finite_true in X3. destruct X3 as [X3 _]. apply check_finite_true in X3. destruct X3 as [Xpr _].
  destruct (sum_gen_exact _ _ Fuc) as [Fff [Fr2 Suc]]. rewrite sumR_neg in Suc.
  destruct (sum3_exact _ _ _ Fff) as [Fff0 [Fff1 [Fff2 Sff]]].
  destruct (sum3_exact _ _ _ Fub) as [Ffd0 [Ffd1 [Ffd2 Sub]]].
  destruct (sum3_exact _ _ _ Fua) as [Fdd0 [Fdd1 [Fdd2 Sua]]].
  destruct (from_pair_exact _ (all_fin_neg _ Fr2)) as [_ [Lr Sr]].
  unfold pr in Xpr, Lr, Sr. cbn [product_b fst snd] in Xpr, Lr, Sr.
  apply andb_prop in Xpr. destruct Xpr as [X2 Nr].
  destruct (note_product_exact _ _ Nr Lr) as [_ [_ Pr]].
  (* the coordinates *)
  destruct (sphere_coord_exact _ _ _ _ _ _ _ _ _ E2 X2 Fdd2 Ffd2 Fff2) as [X1 [Sdd2 [Sfd2 Sff2]]].
  destruct (sphere_coord_exact _ _ _ _ _ _ _ _ _ E1 X1 Fdd1 Ffd1 Fff1) as [X0 [Sdd1 [Sfd1 Sff1]]].
  destruct (sphere_coord_exact _ _ _ _ _ _ _ _ _ E0 X0 Fdd0 Ffd0 Fff0) as [_ [Sdd0 [Sfd0 Sff0]]].
  repeat split; auto.
  - rewrite Sa. unfold ua. rewrite Sua, Sdd0, Sdd1, Sdd2. unfold A, sphere_A. ring.
  - rewrite Sb. unfold ub. rewrite Sub, Sfd0, Sfd1, Sfd2. unfold B, sphere_B. ring.
  - unfold uc, pr in *. cbn [product_b fst snd] in *. rewrite Sc, Suc, Sff, Sff0, Sff1, Sff2, Sr.
    unfold C, sphere_C. cbn [product_b snd] in Pr. lra.
Qed.

(** [sphere_expansions]: when the builder says exact, s.a, s.b, s.c, s.d are finite and their exact sums
    are A, B, C and D = B² − A·C of the query, whatever the 64-bit patterns of its inputs. *)
Theorem sphere_expansions_exact : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r,
  let A := sphere_A (B2R d0) (B2R d1) (B2R d2) in
  let B := sphere_B (B2R o0) (B2R o1) (B2R o2) (B2R d0) (B2R d1) (B2R d2) (B2R c0) (B2R c1) (B2R c2) in
  let C := sphere_C (B2R o0) (B2R o1) (B2R o2) (B2R c0) (B2R c1) (B2R c2) (B2R r) in
  let '(ex, a, b, c, d) := sphere_expansions_b (o0, o1, o2) (d0, d1, d2) (c0, c1, c2) r in
  ex = true ->
  all_fin a /\ all_fin b /\ all_fin c /\ all_fin d /\
  sumR a = A /\ sumR b = B /\ sumR c = C /\ sumR d = sphere_disc A B C.
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r A B C.
  pose proof (sphere_abc_expansions_exact o0 o1 o2 d0 d1 d2 c0 c1 c2 r) as X.
  cbv zeta in X. fold A B C in X.
  unfold sphere_expansions_b.
  destruct (sphere_abc_expansions_b (o0, o1, o2) (d0, d1, d2) (c0, c1, c2) r) as [[[ex3 a] b] c].
  unfold sphere_d_expansion_b.
  set (b_squared := multiply_b ex3 b b).
  set (a_c := multiply_b (fst b_squared) c a).
  intros Ex.
  apply check_finite_true in Ex. destruct Ex as [Ex Fd].
  apply check_finite_true in Ex. destruct Ex as [Ex Fnac].
  apply check_finite_true in Ex. destruct Ex as [Xac Fbb].
  destruct (sum_gen_exact _ _ Fd) as [_ [_ Sd]]. rewrite sumR_neg in Sd.
  destruct (multiply_gen_exact _ _ _ Xac (all_fin_neg _ Fnac)) as [Xbb Sac]. fold a_c in Sac.
  destruct (multiply_gen_exact _ _ _ Xbb Fbb) as [X3 Sbb]. fold b_squared in Sbb.
  destruct (X X3) as [Fa [Fb [Fc [SA [SB SC]]]]].
  repeat split; auto.
  rewrite Sd, Sbb, Sac, SA, SB, SC. unfold sphere_disc. ring.
Qed.

(** The capacities of [SphereExpansions]: a ≤ 6, b ≤ 12, c ≤ 26, d ≤ 600 components. *)
Lemma length_sphere_coord : forall ex o d c ex' f dd fd ff,
  sphere_coord_b ex o d c = (ex', (f, dd, fd, ff)) ->
  (length f <= 2)%nat /\ (length dd <= 2)%nat /\ (length fd <= 4)%nat /\ (length ff <= 8)%nat.
Proof.
  intros ex o d c ex' f dd fd ff E. unfold sphere_coord_b in E. injection E as _ Ef Edd Efd Eff. subst.
  pose proof (length_from_pair (two_diff_b o c)) as Lf.
  repeat split.
  - exact Lf.
  - apply length_from_pair.
  - eapply Nat.le_trans; [apply length_scale_gen|]. lia.
  - eapply Nat.le_trans; [apply length_multiply|]. nia.
Qed.

Theorem sphere_abc_expansions_length : forall o d c r,
  let '(_, a, b, c) := sphere_abc_expansions_b o d c r in
  (length a <= 6)%nat /\ (length b <= 12)%nat /\ (length c <= 26)%nat.
Proof.
  intros [[o0 o1] o2] [[d0 d1] d2] [[c0 c1] c2] r. unfold sphere_abc_expansions_b.
  destruct (sphere_coord_b true o0 d0 c0) as [ex0 [[[f0 dd0] fd0] ff0]] eqn:E0.
  destruct (sphere_coord_b ex0 o1 d1 c1) as [ex1 [[[f1 dd1] fd1] ff1]] eqn:E1.
  destruct (sphere_coord_b ex1 o2 d2 c2) as [ex2 [[[f2 dd2] fd2] ff2]] eqn:E2.
  pose proof (length_sphere_coord _ _ _ _ _ _ _ _ _ E0) as L0.
  pose proof (length_sphere_coord _ _ _ _ _ _ _ _ _ E1) as L1.
  pose proof (length_sphere_coord _ _ _ _ _ _ _ _ _ E2) as L2.
  cbv beta iota zeta.
  repeat split.
  - eapply Nat.le_trans; [apply compress_length|]. eapply Nat.le_trans; [apply length_sum3|]. lia.
  - eapply Nat.le_trans; [apply compress_length|]. eapply Nat.le_trans; [apply length_sum3|]. lia.
  - eapply Nat.le_trans; [apply compress_length|]. eapply Nat.le_trans; [apply length_sum_gen|].
    rewrite map_length. pose proof (length_sum3 ff0 ff1 ff2). pose proof (length_from_pair (snd (product_b ex2 r r))).
    lia.
Qed.

Theorem sphere_expansions_length : forall o d c r,
  let '(_, a, b, c, d) := sphere_expansions_b o d c r in
  (length a <= 6)%nat /\ (length b <= 12)%nat /\ (length c <= 26)%nat /\ (length d <= 600)%nat.
Proof.
  intros o d c r. pose proof (sphere_abc_expansions_length o d c r) as L.
  unfold sphere_expansions_b.
  destruct (sphere_abc_expansions_b o d c r) as [[[ex a] b] cc].
  destruct L as [La [Lb Lc]]. unfold sphere_d_expansion_b. cbv beta iota zeta.
  repeat split; try assumption.
  eapply Nat.le_trans; [apply length_sum_gen|]. rewrite map_length.
  match goal with |- (length (snd (multiply_gen _ ?e1 ?x ?y)) + length (snd (multiply_gen _ ?e2 ?z ?w)) <= _)%nat =>
    pose proof (length_multiply two_sum_b e1 x y); pose proof (length_multiply two_sum_b e2 z w) end.
  nia.
Qed.

(** ** sphere_root_side: the side of a root *)

(** The last lines of [sphere_root_side]: certain signs of 4·q(m) and 2·(A·m + B) give sign(t_k − m). *)
Lemma root_side_decision : forall A B C m root q s, 0 < A -> 0 <= sphere_disc A B C ->
  certifies q (4 * sphere_q A B C m) -> certifies s (2 * sphere_slope A B m) ->
  certifies (if (negb (PlaneCascade.is_certain q) || negb (PlaneCascade.is_certain s))%bool then Uncertain
             else sign_from_int (root_side_of root (sign_to_int q) (sign_to_int s)))
    ((if Z.ltb root 0 then sphere_t1 A B C else sphere_t2 A B C) - m).
Proof.
  intros A B C m root q s HA HD Cq Cs.
  destruct (PlaneCascade.is_certain q) eqn:Iq; [|exact I]. destruct (PlaneCascade.is_certain s) eqn:Is; [|exact I].
  cbn [negb orb].
  rewrite (certifies_sign_to_int q _ Cq ltac:(destruct q; discriminate)),
    (certifies_sign_to_int s _ Cs ltac:(destruct s; discriminate)), !Rsign_scale by lra.
  rewrite root_side_of_root. destruct (Z.ltb root 0).
  - rewrite <- root_side_of_smaller_correct by assumption. apply sign_from_int_Rsign.
  - rewrite <- root_side_of_larger_correct by assumption. apply sign_from_int_Rsign.
Qed.

(** [sphere_root_side]: for expansions a, b, c of A > 0, B, C with D = B² − A·C ≥ 0 (at most 6, 12, 26
    components, the capacities of [SphereExpansions]), a certain answer is sign(t_k − (x + y)/2), t_k the
    smaller root when root < 0 and the larger otherwise, whatever the 64-bit patterns of x and y. *)
Theorem sphere_root_side_sound : forall a b c root x y,
  (length a <= 6)%nat -> (length b <= 12)%nat -> (length c <= 26)%nat ->
  0 < sumR a -> 0 <= sphere_disc (sumR a) (sumR b) (sumR c) ->
  certifies (sphere_root_side_b a b c root x y)
    ((if Z.ltb root 0 then sphere_t1 (sumR a) (sumR b) (sumR c) else sphere_t2 (sumR a) (sumR b) (sumR c))
     - (B2R x + B2R y) / 2).
Proof.
  intros a b c root x y La Lb Lc HA HD. unfold sphere_root_side_b. cbv zeta.
  set (m2 := from_pair (two_sum_b x y)).
  set (mm := multiply_b (check_finite true m2) m2 m2).
  set (a_mm := multiply_b (fst mm) (snd mm) a).
  set (b_m := multiply_b (fst a_mm) b m2).
  set (b_m4 := scale_b (fst b_m) (snd b_m) ffour).
  set (c4 := scale_b (fst b_m4) c ffour).
  set (q4 := sum3_b (snd a_mm) (snd b_m4) (snd c4)).
  set (a_m := multiply_b (fst c4) a m2).
  set (b2 := scale_b (fst a_m) b ftwo).
  set (slope2 := sum_b (snd a_m) (snd b2)).
  destruct (check_finite (check_finite (fst b2) q4) slope2) eqn:Ex; [|exact I]. cbn [negb].
  (* the flags, from the last operation back *)
  apply check_finite_true in Ex. destruct Ex as [Ex Fsl]. apply check_finite_true in Ex. destruct Ex as [Xb2 Fq4].
  destruct (sum_gen_exact _ _ Fsl) as [Fam [Fb2 Ssl]].
  destruct (scale_gen_exact _ _ _ Xb2 Fb2) as [Xam [_ [_ Sb2]]].
  destruct (multiply_gen_exact _ _ _ Xam Fam) as [Xc4 Sam].
  destruct (sum3_exact _ _ _ Fq4) as [Famm [Fbm4 [Fc4 Sq4]]].
  destruct (scale_gen_exact _ _ _ Xc4 Fc4) as [Xbm4 [_ [_ Sc4]]].
  destruct (scale_gen_exact _ _ _ Xbm4 Fbm4) as [Xbm [Fbm [_ Sbm4]]].
  destruct (multiply_gen_exact _ _ _ Xbm Fbm) as [Xamm Sbm].
  destruct (multiply_gen_exact _ _ _ Xamm Famm) as [Xmm Samm].
  assert (Na : a <> nil) by (apply sumR_nil_nonzero; lra).
  pose proof (multiply_fin_left _ _ _ Xamm Famm Na) as Fmm.
  destruct (multiply_gen_exact _ _ _ Xmm Fmm) as [X0 Smm].
  apply check_finite_true in X0. destruct X0 as [_ Fm2].
  destruct (from_pair_exact _ Fm2) as [_ [Lm Sm]]. pose proof (two_sum_twin_exact _ _ Lm) as Tm.
  rewrite ffour_val in Sbm4, Sc4. rewrite ftwo_val in Sb2.
  (* the values: q4 = 4·q(m), slope2 = 2·(A·m + B) *)
  set (A := sumR a) in *. set (B := sumR b) in *. set (C := sumR c) in *.
  set (m := (B2R x + B2R y) / 2).
  assert (SM : sumR m2 = 2 * m) by (unfold m, m2; lra).
  assert (Q : sumR q4 = 4 * sphere_q A B C m).
  { unfold q4, c4, b_m4, b_m, a_mm, mm, m2 in *. rewrite Sq4, Samm, Smm, Sbm4, Sbm, Sc4, SM. unfold sphere_q. ring. }
  assert (S : sumR slope2 = 2 * sphere_slope A B m).
  { unfold slope2, b2, a_m, c4, b_m4, b_m, a_mm, mm, m2 in *. rewrite Ssl, Sam, Sb2, SM. unfold sphere_slope. ring. }
  (* the lengths *)
  assert (Lm2 : (length m2 <= 2)%nat) by apply length_from_pair.
  assert (Lmm : (length (snd mm) <= 8)%nat) by (eapply Nat.le_trans; [apply length_multiply|]; nia).
  assert (Lq4 : (length q4 <= 244)%nat).
  { eapply Nat.le_trans; [apply length_sum3|].
    pose proof (length_multiply two_sum_b (fst mm) (snd mm) a). fold a_mm in H.
    pose proof (length_multiply two_sum_b (fst a_mm) b m2). fold b_m in H0.
    pose proof (length_scale_gen two_sum_b (fst b_m) (snd b_m) ffour). fold b_m4 in H1.
    pose proof (length_scale_gen two_sum_b (fst b_m4) c ffour). fold c4 in H2. nia. }
  assert (Lsl : (length slope2 <= 48)%nat).
  { eapply Nat.le_trans; [apply length_sum_gen|].
    pose proof (length_multiply two_sum_b (fst c4) a m2). fold a_m in H.
    pose proof (length_scale_gen two_sum_b (fst a_m) b ftwo). fold b2 in H0. nia. }
  (* the signs *)
  pose proof (sphere_sign_or_compressed_sound q4 Fq4 ltac:(lia)) as Cq.
  pose proof (sphere_sign_or_compressed_sound slope2 Fsl ltac:(lia)) as Cs.
  rewrite Q in Cq. rewrite S in Cs.
  exact (root_side_decision A B C m root _ _ HA HD Cq Cs).
Qed.

(** The stage end to end: on the expansions of [sphere_abc_expansions_b] (what sphere_root_side_of and the
    cascade build before a root's side; [sphere_expansions_b] begins with the same) when the builder says exact,
    for a ray that meets the sphere (D ≥ 0) with a nonzero direction (A > 0), a certain [sphere_root_side_b] is
    sign(t_k − (x + y)/2) for the roots t1 ≤ t2 of the query's A·t² + 2B·t + C. *)
Theorem sphere_root_side_expansions_sound : forall o0 o1 o2 d0 d1 d2 c0 c1 c2 r root x y,
  let A := sphere_A (B2R d0) (B2R d1) (B2R d2) in
  let B := sphere_B (B2R o0) (B2R o1) (B2R o2) (B2R d0) (B2R d1) (B2R d2) (B2R c0) (B2R c1) (B2R c2) in
  let C := sphere_C (B2R o0) (B2R o1) (B2R o2) (B2R c0) (B2R c1) (B2R c2) (B2R r) in
  let '(ex, a, b, c) := sphere_abc_expansions_b (o0, o1, o2) (d0, d1, d2) (c0, c1, c2) r in
  ex = true -> 0 < A -> 0 <= sphere_disc A B C ->
  certifies (sphere_root_side_b a b c root x y)
    ((if Z.ltb root 0 then sphere_t1 A B C else sphere_t2 A B C) - (B2R x + B2R y) / 2).
Proof.
  intros o0 o1 o2 d0 d1 d2 c0 c1 c2 r root x y A B C.
  pose proof (sphere_abc_expansions_exact o0 o1 o2 d0 d1 d2 c0 c1 c2 r) as X.
  pose proof (sphere_abc_expansions_length (o0, o1, o2) (d0, d1, d2) (c0, c1, c2) r) as L.
  cbv zeta in X. fold A B C in X.
  destruct (sphere_abc_expansions_b (o0, o1, o2) (d0, d1, d2) (c0, c1, c2) r) as [[[ex a] b] c].
  intros Ex HA HD. destruct (X Ex) as [_ [_ [_ [SA [SB SC]]]]]. destruct L as [La [Lb Lc]].
  pose proof (sphere_root_side_sound a b c root x y La Lb Lc) as R.
  rewrite SA, SB, SC in R. exact (R HA HD).
Qed.
