(** * The ray–triangle fast relation (kernel/src/triangle/ray_triangle_cascade.cpp, [fast_relation]) as a
    twin over IEEE-754 binary64, and docs/contract.md §6 over the reals.

    - [contract_class]: §6's answer (relation, location, owned flag) for exact reals, under either rule
      ([owned_rule] true: the owned rule; false: the closed one), written as [classify_triangle] of
      ray_triangle_formula.hpp takes it from the exact signs;
    - [fast_relation_tri_b]: [fast_relation], operation by operation on TriangleTwins.v's stage-1 twins: the
      four lanes of [triangle_relation_lanes] (πa, πb, πc and π(b, c) seen from a = den, with d broadcast,
      [bcast]), [det3_filter_lanes] of each with the π constant, and, for a line through the triangle,
      [triangle_num_filter]'s sign; [None] where the C++ returns std::nullopt;
    - [fast_relation_tri_correct]: for every 64-bit pattern of o, d, a, b, c, an answer of the twin is §6's
      answer for the exact values, under both rules, and the inputs are finite.

    The differential runner (routine [tri_fast_relation]) compares the twin with the compiled
    [fast_triangle_relation] and the public [relation] for both rules. *)

From Coq Require Import Reals Lra Lia ZArith Bool.
From Flocq Require Import Core IEEE754.BinarySingleNaN.
From Raykernel Require Import Model PlaneClassification PlaneCascade FloatCore ConstantsCpp PlaneTwins TriangleFilter TriangleRule
  TriangleTwins TriangleStage3Twins.
Open Scope R_scope.

(** ** docs/contract.md §6 *)

Inductive tri_relation := THit | TBehind | TMiss | TDegenerate | TParallel | TCoplanar.

(** (relation, location (None: [TriangleLocation::none]), owned). *)
Record TClass := TC { trel : tri_relation; tloc : option location; towned : bool }.

Definition normal_is_zero (a b c : vec3) : Prop := cross (sub b a) (sub c a) = Vec3 0 0 0.

(** §6 from the exact values.  den ≠ 0: the location from the signs of πa, πb, πc, den; owned when the
    location is not outside and every edge's owned sign is den's; through: owned (owned rule) or not outside
    (closed rule); hit when num·den ≥ 0.  den = 0: degenerate (N = 0), coplanar (num = 0) or parallel. *)
Definition contract_class (owned_rule : bool) (o d a b c : vec3) (cl : TClass) : Prop :=
  let sden := sign_of (den_value o d a b c) in
  let sa := sign_of (edge_value o d b c) in let sb := sign_of (edge_value o d c a) in
  let sc := sign_of (edge_value o d a b) in let sn := sign_of (num_value o a b c) in
  if Z.eqb sden 0 then
    tloc cl = None /\ towned cl = false /\
    ((normal_is_zero a b c /\ trel cl = TDegenerate) \/
     (~ normal_is_zero a b c /\ sn = 0%Z /\ trel cl = TCoplanar) \/
     (~ normal_is_zero a b c /\ sn <> 0%Z /\ trel cl = TParallel))
  else
    let loc := triangle_location sa sb sc sden in
    let owned := (negb (match loc with Outside => true | _ => false end) &&
                  Z.eqb (owned_sign_of o d b c) sden && Z.eqb (owned_sign_of o d c a) sden &&
                  Z.eqb (owned_sign_of o d a b) sden)%bool in
    let through := if owned_rule then owned else negb (match loc with Outside => true | _ => false end) in
    tloc cl = Some loc /\ towned cl = owned /\
    trel cl = (if through then (if Z.leb 0 (sn * sden) then THit else TBehind) else TMiss).

(** ** The twin of [fast_relation] *)

Definition pi_sign1_b (A : float) (t : FTermB) : Z := det3_filter_lanes_b t Cpp.triangle_filter_pi_relative A.

Definition fast_relation_tri_b (o d a b c : TVec) : option TClass :=
  let d' := bcast d in
  let A := absolute_bv d' in
  let sa := pi_sign1_b A (pi_stage1_b o d' b c) in
  let sb := pi_sign1_b A (pi_stage1_b o d' c a) in
  let sc := pi_sign1_b A (pi_stage1_b o d' a b) in
  let sden := pi_sign1_b A (pi_stage1_b a d' b c) in
  let certain := (negb (Z.eqb sa uncertain_lane) && negb (Z.eqb sb uncertain_lane) &&
                  negb (Z.eqb sc uncertain_lane) && negb (Z.eqb sden uncertain_lane))%bool in
  if certain then
    if (Z.eqb sa sden && Z.eqb sb sden && Z.eqb sc sden)%bool then
      let sn := det3_filter_lanes_b (num_stage1_b o a b c) Cpp.triangle_filter_num_relative (absolute_bv (tsub a o)) in
      if Z.eqb sn uncertain_lane then None
      else Some (TC (if Z.eqb sn sden then THit else TBehind) (Some Inside) true)
    else Some (TC TMiss (Some Outside) false)
  else None.

(** ** Correctness *)

Lemma det3_filter_lanes_b_range : forall t C A, lane_sign (det3_filter_lanes_b t C A).
Proof. intros. unfold det3_filter_lanes_b. apply sign_lanes_range. Qed.

(** A certain lane sign of π(p, q) computed with d broadcast is the exact sign. *)
Lemma pi_lane_exact : forall o d p q,
  pi_sign1_b (absolute_bv (bcast d)) (pi_stage1_b o (bcast d) p q) <> uncertain_lane ->
  pi_sign1_b (absolute_bv (bcast d)) (pi_stage1_b o (bcast d) p q) = sign_of (edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q)) /\
  edge_value (tvec_R o) (tvec_R d) (tvec_R p) (tvec_R q) <> 0 /\ tfin o /\ tfin d /\ tfin p /\ tfin q.
Proof.
  intros o d p q U. destruct (triangle_pi_lane_filter_twin_sound o d p q) as [C F].
  destruct (lane_sign_exact _ _ (det3_filter_lanes_b_range _ _ _) U C) as [E [_ N]].
  split; [exact E | split; [exact N | exact (F U)]].
Qed.

Lemma owned_sign_of_nonzero : forall o d p q, edge_value o d p q <> 0 ->
  owned_sign_of o d p q = sign_of (edge_value o d p q).
Proof.
  intros o d p q N. unfold owned_sign_of, owned_sign. cbv zeta.
  destruct (Z.eqb_spec (sign_of (edge_value o d p q)) 0) as [E|E]; [|reflexivity].
  apply sign_of_zero_iff in E. contradiction.
Qed.

Lemma sign_pm : forall x, x <> 0 -> sign_of x = (-1)%Z \/ sign_of x = 1%Z.
Proof.
  intros x N. destruct (sign_of_range x) as [E|[E|E]]; auto. apply sign_of_zero_iff in E. contradiction.
Qed.

(** The classification by the exact, nonzero signs (shared by [fast_relation_tri_correct] and
    TriangleIntersectTheorem.v's [decide_nonzero_contract]): deciding inside/outside from the edge signs
    against den's, with a num sign that is exact when certain, gives §6's class under both rules. *)
Lemma decided_class_contract : forall O D A B C sn cl,
  edge_value O D B C <> 0 -> edge_value O D C A <> 0 -> edge_value O D A B <> 0 -> den_value O D A B C <> 0 ->
  (sn <> uncertain_lane -> sn = sign_of (num_value O A B C) /\ num_value O A B C <> 0) ->
  (let sa := sign_of (edge_value O D B C) in let sb := sign_of (edge_value O D C A) in
   let sc := sign_of (edge_value O D A B) in let sden := sign_of (den_value O D A B C) in
   if (Z.eqb sa sden && Z.eqb sb sden && Z.eqb sc sden)%bool then
     if Z.eqb sn uncertain_lane then None else Some (TC (if Z.eqb sn sden then THit else TBehind) (Some Inside) true)
   else Some (TC TMiss (Some Outside) false)) = Some cl ->
  contract_class true O D A B C cl /\ contract_class false O D A B C cl.
Proof.
  intros O D A B C sn cl Na Nb Nc Nd Hn. cbv zeta.
  assert (Sd : Z.eqb (sign_of (den_value O D A B C)) 0 = false).
  { apply Z.eqb_neq. intros E. apply sign_of_zero_iff in E. contradiction. }
  unfold contract_class. cbv zeta. rewrite Sd.
  rewrite (owned_sign_of_nonzero _ _ _ _ Na), (owned_sign_of_nonzero _ _ _ _ Nb), (owned_sign_of_nonzero _ _ _ _ Nc).
  pose proof (sign_pm _ Na) as Ra. pose proof (sign_pm _ Nb) as Rb. pose proof (sign_pm _ Nc) as Rc.
  pose proof (sign_pm _ Nd) as Rd.
  set (sa := sign_of (edge_value O D B C)) in *. set (sb := sign_of (edge_value O D C A)) in *.
  set (sc := sign_of (edge_value O D A B)) in *. set (sden := sign_of (den_value O D A B C)) in *.
  destruct (Z.eqb sa sden && Z.eqb sb sden && Z.eqb sc sden)%bool eqn:I.
  - (* inside *)
    destruct (Z.eqb_spec sn uncertain_lane) as [Un|Un]; [intros H; discriminate H|].
    intros H. injection H as <-.
    destruct (Hn Un) as [En Nn]. rewrite En. pose proof (sign_pm _ Nn) as Rn.
    set (snv := sign_of (num_value O A B C)) in *.
    apply andb_prop in I. destruct I as [I I3]. apply andb_prop in I. destruct I as [I1 I2].
    apply Z.eqb_eq in I1, I2, I3. rewrite I1, I2, I3.
    assert (L : triangle_location sden sden sden sden = Inside)
      by (unfold triangle_location; destruct Rd as [-> | ->]; reflexivity).
    rewrite L. rewrite Z.eqb_refl. cbn [negb andb trel tloc towned].
    destruct Rd as [Ed' | Ed']; destruct Rn as [En' | En']; rewrite Ed', En'; cbn; repeat split; reflexivity.
  - (* outside *)
    intros H. injection H as <-.
    assert (L : triangle_location sa sb sc sden = Outside).
    { unfold triangle_location.
      destruct Ra as [-> | ->]; destruct Rb as [-> | ->]; destruct Rc as [-> | ->]; destruct Rd as [-> | ->];
        cbn in I |- *; first [reflexivity | discriminate]. }
    rewrite L. cbn [negb andb trel tloc towned]. repeat split; reflexivity.
Qed.

(** [fast_relation]: an answer of the twin is §6's, under both rules, for every bit pattern of the inputs
    (which are then finite). *)
Theorem fast_relation_tri_correct : forall o d a b c cl, fast_relation_tri_b o d a b c = Some cl ->
  tfin o /\ tfin d /\ tfin a /\ tfin b /\ tfin c /\
  let O := tvec_R o in let D := tvec_R d in let A := tvec_R a in let B := tvec_R b in let C := tvec_R c in
  den_value O D A B C <> 0 /\
  contract_class true O D A B C cl /\ contract_class false O D A B C cl.
Proof.
  intros o d a b c cl. unfold fast_relation_tri_b. cbv zeta.
  set (A := absolute_bv (bcast d)).
  destruct (Z.eqb_spec (pi_sign1_b A (pi_stage1_b o (bcast d) b c)) uncertain_lane) as [Ua|Ua];
    [intros H; cbn [negb andb] in H; discriminate H|].
  destruct (Z.eqb_spec (pi_sign1_b A (pi_stage1_b o (bcast d) c a)) uncertain_lane) as [Ub|Ub];
    [intros H; cbn [negb andb] in H; discriminate H|].
  destruct (Z.eqb_spec (pi_sign1_b A (pi_stage1_b o (bcast d) a b)) uncertain_lane) as [Uc|Uc];
    [intros H; cbn [negb andb] in H; discriminate H|].
  destruct (Z.eqb_spec (pi_sign1_b A (pi_stage1_b a (bcast d) b c)) uncertain_lane) as [Ud|Ud];
    [intros H; cbn [negb andb] in H; discriminate H|].
  intros H. cbn [negb andb] in H.
  destruct (pi_lane_exact o d b c Ua) as [Ea [Na [Fo [Fd [Fb Fc]]]]].
  destruct (pi_lane_exact o d c a Ub) as [Eb [Nb [_ [_ [_ Fa]]]]].
  destruct (pi_lane_exact o d a b Uc) as [Ec [Nc _]].
  destruct (pi_lane_exact a d b c Ud) as [Ed [Nd _]].
  fold A in Ea, Eb, Ec, Ed.
  rewrite (den_from_a (tvec_R o)) in Ed, Nd.
  rewrite Ea, Eb, Ec, Ed in H.
  set (O := tvec_R o) in *. set (D := tvec_R d) in *. set (Av := tvec_R a) in *. set (B := tvec_R b) in *.
  set (C := tvec_R c) in *.
  do 5 (split; [assumption|]). cbv zeta. split; [exact Nd|].
  revert H. apply (decided_class_contract O D Av B C
    (det3_filter_lanes_b (num_stage1_b o a b c) Cpp.triangle_filter_num_relative (absolute_bv (tsub a o))) cl
    Na Nb Nc Nd).
  intros Un. destruct (triangle_num_filter_twin_sound o a b c) as [Cn _].
  destruct (lane_sign_exact _ _ (det3_filter_lanes_b_range _ _ _) Un Cn) as [En [_ Nn]].
  exact (conj En Nn).
Qed.
