(** * The public ray–triangle [intersect_traced] before the exact stage: den ≠ 0, finite inputs, §6's class,
    and each quotient with a value RN(·/den)

    The public entry point (kernel/src/triangle/triangle_api.cpp) answers a valid query (validation.hpp's
    [is_valid] of the ray and the triangle: [tri_valid_b]) with [fast_triangle_intersection]'s answer when it
    has one, else with [triangle_intersection_cascade]'s. [tri_public_intersect_b] is that choice over the two
    twins, the same term as the runner's routine [tri_cascade_intersect] (proofs/twins/Extract.v, its [public])
    compares with the compiled [intersect_traced], bit for bit, on groups triangles5/triangles6 (Extract.v
    calls [tri_public_of], of which [tri_public_intersect_b] is the instance).

    - [contract_class_den]: under docs/contract.md §6's classification, den ≠ 0 exactly when the class has a
      location (the [sign_of den = 0] branch of [contract_class] has none);
    - [tc_intersect_b_unlocated_nan]: an answer of the cascade's twin whose class has no location has no
      quotient (all four NaN), read through [tc_intersect_b_eq] (the twin itself is not unfolded);
    - [tc_intersect_b_den_nonzero]: an answer of [tc_intersect_b] before the exact stage in which some quotient
      has a value has den ≠ 0 — for every bit pattern, every option set, both rules;
    - [tc_intersect_b_means]: [tc_intersect_b_correct] with den ≠ 0 in each quotient's meaning;
    - [intersect_public_correct]: for every bit pattern with [tri_valid_b] true, every option set and both
      rules, an answer of [tri_public_intersect_b] before the exact stage has finite inputs, §6's class under
      the rule, den ≠ 0 exactly when located, each asked quotient with a value finite and RN(num/den),
      RN(π(b, c)/den), RN(π(c, a)/den), RN(π(a, b)/den) with den ≠ 0, and each quotient not asked NaN. *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification PlaneCascade FloatCore ConstantsCpp PlaneTwins Expansions PlaneQueryTwins
  TriangleFilter TriangleRule TriangleTwins TriangleStage3Twins TriangleCascadeTwins TriangleIntersectTwins
  TriangleCascadeFlowTwins TriangleCascadeQuotients.
From Raykernel Require TriangleCascadeFlowCorrect TriangleIntersectTheorem.
Open Scope R_scope.

(** ** den ≠ 0 exactly when located *)

Lemma contract_class_den : forall rule O D A B C cl, contract_class rule O D A B C cl ->
  (den_value O D A B C <> 0 <-> tloc cl <> None).
Proof.
  intros rule O D A B C cl H. unfold contract_class in H. cbv zeta in H.
  destruct (Z.eqb (sign_of (den_value O D A B C)) 0) eqn:S.
  - apply Z.eqb_eq, sign_of_zero_iff in S. destruct H as [L _]. split; intros N; contradiction.
  - apply Z.eqb_neq in S. destruct H as [L _]. rewrite L. split; intros _.
    + intros E; discriminate E.
    + intros E. apply S. rewrite E. apply sign_of_zero_iff. reflexivity.
Qed.

(** ** The cascade: no location, no quotient *)

Lemma tc_quot_tail_class : forall cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 cl' rs' t ua ub uc ts',
  tc_quot_tail cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 = TCDecided cl' rs' t ua ub uc ts' ->
  cl' = cl.
Proof.
  intros cl rs ts x0 x1 x2 x3 q0 q1 q2 q3 p0 p1 p2 p3 ds dn b0 b1 b2 b3 cl' rs' t ua ub uc ts'.
  unfold tc_quot_tail, tc_quot_tail2, tc_quot_tail3, tc_quot_tail4.
  destruct (tc_all x0 x1 x2 x3); [intros E; injection E as <- _; reflexivity|].
  destruct (tc_all _ _ _ _); [intros E; injection E as <- _; reflexivity|].
  destruct (tc_all _ _ _ _); [intros E; injection E as <- _; reflexivity|].
  destruct (tc_all _ _ _ _); intros E; injection E as <- _; reflexivity.
Qed.

Lemma tc_intersect_b_unlocated_nan : forall want_t want_u owned_rule o d a b c cl rs t ua ub uc ts,
  tc_intersect_b want_t want_u owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  tloc cl = None -> t = QNaN /\ ua = QNaN /\ ub = QNaN /\ uc = QNaN.
Proof.
  intros wt wu rule o d a b c cl rs t ua ub uc ts. rewrite tc_intersect_b_eq.
  destruct (tc_classify_b o d a b c rule) as [cl0 f0]. destruct (tf_exact f0); [intros E; discriminate E|].
  destruct (match tloc cl0 with None => true | Some _ => false end || (negb wt && negb wu))%bool eqn:L.
  { intros E. injection E as _ _ <- <- <- <- _. intros _. tsplit; reflexivity. }
  apply orb_false_iff in L. destruct L as [L _].
  assert (Located : tloc cl0 <> None) by (intros E; rewrite E in L; discriminate L).
  destruct (if wt then tc_sign_b o d a b c 4 f0 else (0%Z, f0)) as [n0 f1].
  destruct (if wu then tc_sign_b o d a b c 0 f1 else (0%Z, f1)) as [n1 f2].
  destruct (if wu then tc_sign_b o d a b c 1 f2 else (0%Z, f2)) as [n2 f3].
  destruct (if wu then tc_sign_b o d a b c 2 f3 else (0%Z, f3)) as [n3 f4].
  destruct (tf_exact f4).
  { intros E. injection E as <- _. intros N. contradiction. }
  intros E. rewrite (tc_quot_tail_class _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ E). intros N. contradiction.
Qed.

(** What a quotient of the answer means, den ≠ 0 included: a value is finite and RN(V/VD), VD ≠ 0. *)
Definition tc_quotient_means_nz (q : qval) (V VD : R) : Prop :=
  forall x, q = QVal x -> VD <> 0 /\ fin x = true /\ B2R x = RN (V / VD).

(** [triangle_intersection_cascade] through its twin: for every 64-bit pattern of o, d, a, b, c, every
    option set and both rules, an answer before the exact stage in which t or a barycentric has a value has
    den ≠ 0 (a value is computed only for a located class, and §6's located classes have den ≠ 0). *)
Theorem tc_intersect_b_den_nonzero : forall want_t want_u owned_rule o d a b c cl rs t ua ub uc ts,
  tc_intersect_b want_t want_u owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  (exists x, t = QVal x \/ ua = QVal x \/ ub = QVal x \/ uc = QVal x) ->
  den_value (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) <> 0.
Proof.
  intros wt wu rule o d a b c cl rs t ua ub uc ts H [x V].
  apply (contract_class_den _ _ _ _ _ _ _
           (TriangleCascadeFlowCorrect.tc_intersect_b_class_correct wt wu rule o d a b c cl rs t ua ub uc ts H)).
  intros L. destruct (tc_intersect_b_unlocated_nan wt wu rule o d a b c cl rs t ua ub uc ts H L)
    as [-> [-> [-> ->]]].
  destruct V as [E|[E|[E|E]]]; discriminate E.
Qed.

(** [tc_intersect_b_correct] with den ≠ 0: the full cascade's answer before the exact stage. *)
Theorem tc_intersect_b_means : forall want_t want_u owned_rule o d a b c cl rs t ua ub uc ts,
  tc_intersect_b want_t want_u owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  contract_class owned_rule O D A B C cl /\ (den_value O D A B C <> 0 <-> tloc cl <> None) /\
  tc_quotient_means_nz t (num_value O A B C) (den_value O D A B C) /\
  tc_quotient_means_nz ua (edge_value O D B C) (den_value O D A B C) /\
  tc_quotient_means_nz ub (edge_value O D C A) (den_value O D A B C) /\
  tc_quotient_means_nz uc (edge_value O D A B) (den_value O D A B C).
Proof.
  intros wt wu rule o d a b c cl rs t ua ub uc ts H.
  destruct (tc_intersect_b_correct wt wu rule o d a b c cl rs t ua ub uc ts H) as [Cl [Mt [Ma [Mb Mc]]]].
  pose proof (tc_intersect_b_den_nonzero wt wu rule o d a b c cl rs t ua ub uc ts H) as Nz.
  cbv zeta. split; [exact Cl|]. split; [exact (contract_class_den _ _ _ _ _ _ _ Cl)|].
  tsplit; intros x E.
  - split; [apply Nz; exists x; left; exact E | exact (Mt x E)].
  - split; [apply Nz; exists x; right; left; exact E | exact (Ma x E)].
  - split; [apply Nz; exists x; right; right; left; exact E | exact (Mb x E)].
  - split; [apply Nz; exists x; right; right; right; exact E | exact (Mc x E)].
Qed.

(** ** The fast path: a quotient not asked is NaN *)

Lemma intersect_tail_unasked : forall want_t want_u (fa fb fc fd fn sa sb sc sd sn : Z) (qa qb qc qn : float * bool)
  k, TriangleIntersectTheorem.intersect_tail_b want_t want_u fa fb fc fd fn sa sb sc sd sn qa qb qc qn = Some k ->
  (want_t = false -> tab_t k = fnan) /\ (want_u = false -> tab_ua k = fnan /\ tab_ub k = fnan /\ tab_uc k = fnan).
Proof.
  intros wt wu fa fb fc fd fn sa sb sc sd sn qa qb qc qn k. unfold TriangleIntersectTheorem.intersect_tail_b.
  destruct (negb _); [intros E; discriminate E|].
  destruct (decide_nonzero_b sa sb sc sd sn) as [cl|]; [|intros E; discriminate E].
  destruct (wt && negb (certain_lane sn))%bool; [intros E; discriminate E|].
  destruct (negb _); [intros E; discriminate E|].
  intros E. injection E as <-. cbn [tab_t tab_ua tab_ub tab_uc].
  split; intros ->; [reflexivity | tsplit; reflexivity].
Qed.

Lemma fast_intersection_tri_unasked : forall want_t want_u o d a b c k,
  fast_intersection_tri_b want_t want_u o d a b c = Some k ->
  (want_t = false -> tab_t k = fnan) /\ (want_u = false -> tab_ua k = fnan /\ tab_ub k = fnan /\ tab_uc k = fnan).
Proof.
  intros wt wu o d a b c k.
  destruct (negb wt && negb wu)%bool eqn:W.
  - unfold fast_intersection_tri_b. rewrite W.
    destruct (fast_relation_tri_b o d a b c) as [cl|]; [|intros E; discriminate E].
    intros E. injection E as <-. cbn [tab_t tab_ua tab_ub tab_uc].
    split; intros _; [reflexivity | tsplit; reflexivity].
  - rewrite (TriangleIntersectTheorem.fast_intersection_tri_b_eq wt wu o d a b c W).
    apply intersect_tail_unasked.
Qed.

(** ** The public entry point *)

(** The stage of a stage code (0 filter, 1 compensated, 2 expansion; [tab_relation_stage] is 0 or 1). *)
Definition tri_stage_of_code (z : Z) : stage :=
  if Z.eqb z 0 then StFilter else if Z.eqb z 1 then StCompensated else if Z.eqb z 2 then StExpansion else StExact.

(** The choice [intersect_traced] (triangle_api.cpp) makes on a valid query: the fast path's answer when it
    has one, else the cascade's. Extract.v's [tri_cascade_intersect] calls it with the cascade's answer it has
    already computed, so the runner compares exactly [tri_public_intersect_b] with the compiled entry point. *)
Definition tri_public_of (fast : option TAnswerB) (cascade : tc_answer) : tc_answer :=
  match fast with
  | Some k => TCDecided (tab_class k) (tri_stage_of_code (tab_relation_stage k)) (QVal (tab_t k))
                (QVal (tab_ua k)) (QVal (tab_ub k)) (QVal (tab_uc k)) (tri_stage_of_code (tab_rounding_stage k))
  | None => cascade
  end.

(** [intersect_traced]'s twin on a valid query. *)
Definition tri_public_intersect_b (want_t want_u owned_rule : bool) (o d a b c : TVec) : tc_answer :=
  tri_public_of (fast_intersection_tri_b want_t want_u o d a b c) (tc_intersect_b want_t want_u owned_rule o d a b c).

(** An asked quotient: a value is finite and RN(V/VD) with VD ≠ 0; one not asked has no value but NaN. *)
Definition tri_public_quotient (w : bool) (q : qval) (V VD : R) : Prop :=
  if w then tc_quotient_means_nz q V VD else forall x, q = QVal x -> is_nan x = true.

Lemma tfin_b_tfin : forall v, tfin_b v = true -> tfin v.
Proof.
  intros [x y z] H. unfold tfin_b in H. cbn [tx ty tz] in *. apply andb_prop in H. destruct H as [H Hz].
  apply andb_prop in H. destruct H as [Hx Hy]. unfold tfin. cbn [tx ty tz]. tsplit; assumption.
Qed.

Lemma tri_valid_b_fin : forall o d a b c, tri_valid_b o d a b c = true ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c.
Proof.
  intros o d a b c H. unfold tri_valid_b in H. apply andb_prop in H. destruct H as [H Fc].
  apply andb_prop in H. destruct H as [H Fb]. apply andb_prop in H. destruct H as [H Fa].
  apply andb_prop in H. destruct H as [H _]. apply andb_prop in H. destruct H as [Fo Fd].
  tsplit; apply tfin_b_tfin; assumption.
Qed.

(** The public [intersect_traced] (triangle_api.cpp: [fast_triangle_intersection], else
    [triangle_intersection_cascade]), through its twins: for every 64-bit pattern of o, d, a, b, c with
    [tri_valid_b] true (the inputs the entry point does not reject), every option set and both rules, an
    answer before the exact stage has finite inputs, docs/contract.md §6's classification under the rule,
    den ≠ 0 exactly when the class is located, and t, u_a, u_b, u_c, when asked and with a value, finite and
    RN(num/den), RN(π(b, c)/den), RN(π(c, a)/den), RN(π(a, b)/den) with den ≠ 0; not asked, NaN. *)
Theorem intersect_public_correct : forall want_t want_u owned_rule o d a b c cl rs t ua ub uc ts,
  tri_valid_b o d a b c = true ->
  tri_public_intersect_b want_t want_u owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  contract_class owned_rule O D A B C cl /\ (den_value O D A B C <> 0 <-> tloc cl <> None) /\
  tri_public_quotient want_t t (num_value O A B C) (den_value O D A B C) /\
  tri_public_quotient want_u ua (edge_value O D B C) (den_value O D A B C) /\
  tri_public_quotient want_u ub (edge_value O D C A) (den_value O D A B C) /\
  tri_public_quotient want_u uc (edge_value O D A B) (den_value O D A B C).
Proof.
  intros wt wu rule o d a b c cl rs t ua ub uc ts V. destruct (tri_valid_b_fin o d a b c V) as [Fo [Fd [Fa [Fb Fc]]]].
  unfold tri_public_intersect_b, tri_public_of.
  destruct (fast_intersection_tri_b wt wu o d a b c) as [k|] eqn:Fast.
  - intros E. injection E as <- _ <- <- <- <- _.
    pose proof (TriangleIntersectTheorem.fast_intersection_tri_correct wt wu o d a b c k Fast) as M.
    destruct (fast_intersection_tri_unasked wt wu o d a b c k Fast) as [Ut Uu].
    unfold TriangleIntersectTheorem.intersection_means in M. cbv zeta in M.
    destruct M as [_ [_ [_ [_ [_ [Nz [C1 [C2 [Mt Mu]]]]]]]]].
    assert (Cl : contract_class rule (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) (tab_class k))
      by (destruct rule; assumption).
    split; [exact Fo|]. split; [exact Fd|]. split; [exact Fa|]. split; [exact Fb|]. split; [exact Fc|].
    cbv zeta. split; [exact Cl|]. split; [exact (contract_class_den _ _ _ _ _ _ _ Cl)|].
    unfold tri_public_quotient, tc_quotient_means_nz.
    destruct wt; cbv beta iota.
    + split; [intros x E; injection E as <-; destruct (Mt eq_refl) as [F R]; exact (conj Nz (conj F R))|].
      destruct wu; cbv beta iota.
      * destruct (Mu eq_refl) as [[Fa' Ra] [[Fb' Rb] [Fc' Rc]]].
        tsplit; intros x E; injection E as <-; tsplit; assumption.
      * destruct (Uu eq_refl) as [Ea [Eb Ec]].
        tsplit; intros x E; injection E as <-; [rewrite Ea | rewrite Eb | rewrite Ec]; reflexivity.
    + split; [intros x E; injection E as <-; rewrite (Ut eq_refl); reflexivity|].
      destruct wu; cbv beta iota.
      * destruct (Mu eq_refl) as [[Fa' Ra] [[Fb' Rb] [Fc' Rc]]].
        tsplit; intros x E; injection E as <-; tsplit; assumption.
      * destruct (Uu eq_refl) as [Ea [Eb Ec]].
        tsplit; intros x E; injection E as <-; [rewrite Ea | rewrite Eb | rewrite Ec]; reflexivity.
  - intros E.
    destruct (tc_intersect_b_means wt wu rule o d a b c cl rs t ua ub uc ts E) as [Cl [Dn [Mt [Ma [Mb Mc]]]]].
    destruct (tc_intersect_b_unasked wt wu rule o d a b c cl rs t ua ub uc ts E) as [Ut Uu].
    split; [exact Fo|]. split; [exact Fd|]. split; [exact Fa|]. split; [exact Fb|]. split; [exact Fc|].
    cbv zeta. split; [exact Cl|]. split; [exact Dn|].
    unfold tri_public_quotient.
    destruct wt; cbv beta iota.
    + split; [exact Mt|]. destruct wu; cbv beta iota; [tsplit; assumption|].
      destruct (Uu eq_refl) as [-> [-> ->]]. tsplit; intros x X; discriminate X.
    + split; [rewrite (Ut eq_refl); intros x X; discriminate X|]. destruct wu; cbv beta iota; [tsplit; assumption|].
      destruct (Uu eq_refl) as [-> [-> ->]]. tsplit; intros x X; discriminate X.
Qed.

(** ** The public [relation] *)

(** The choice [relation] (triangle_api.cpp's [certified_relation]) makes on a valid query: the fast path's
    classification when it has one (reported as the filter's), else the cascade's answer. Extract.v's
    [tri_cascade_relation] calls it with the cascade's answer it has already computed, so the runner compares
    exactly [tri_public_relation_b] with the compiled entry point. *)
Definition tri_public_relation_of (fast : option TClass) (cascade : tc_answer) : tc_answer :=
  match fast with
  | Some k => TCDecided k StFilter QNaN QNaN QNaN QNaN StFilter
  | None => cascade
  end.

(** [relation]'s twin on a valid query. *)
Definition tri_public_relation_b (owned_rule : bool) (o d a b c : TVec) : tc_answer :=
  tri_public_relation_of (fast_relation_tri_b o d a b c) (tc_relation_b owned_rule o d a b c).

(** The public [relation] (triangle_api.cpp: [fast_triangle_relation], else [triangle_relation_cascade]),
    through its twins: for every 64-bit pattern of o, d, a, b, c with [tri_valid_b] true (the inputs the entry
    point does not reject) and both rules, an answer before the exact stage has finite inputs, docs/contract.md
    §6's classification under the rule, and den ≠ 0 exactly when the class is located. *)
Theorem relation_public_correct : forall owned_rule o d a b c cl rs t ua ub uc ts,
  tri_valid_b o d a b c = true ->
  tri_public_relation_b owned_rule o d a b c = TCDecided cl rs t ua ub uc ts ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  contract_class owned_rule O D A B C cl /\ (den_value O D A B C <> 0 <-> tloc cl <> None).
Proof.
  intros rule o d a b c cl rs t ua ub uc ts V. destruct (tri_valid_b_fin o d a b c V) as [Fo [Fd [Fa [Fb Fc]]]].
  unfold tri_public_relation_b, tri_public_relation_of. intros E.
  assert (Cl : contract_class rule (tvec_R o) (tvec_R d) (tvec_R a) (tvec_R b) (tvec_R c) cl).
  { revert E. destruct (fast_relation_tri_b o d a b c) as [k|] eqn:Fast.
    - intros E. injection E as <- _ _ _ _ _ _.
      destruct (fast_relation_tri_correct o d a b c k Fast) as [_ [_ [_ [_ [_ M]]]]].
      cbv zeta in M. destruct M as [_ [C1 C2]]. destruct rule; assumption.
    - intros E. exact (TriangleCascadeFlowCorrect.tc_relation_b_correct rule o d a b c cl rs t ua ub uc ts E). }
  split; [exact Fo|]. split; [exact Fd|]. split; [exact Fa|]. split; [exact Fb|]. split; [exact Fc|].
  cbv zeta. split; [exact Cl | exact (contract_class_den _ _ _ _ _ _ _ Cl)].
Qed.
