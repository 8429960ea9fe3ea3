(** * The escalation policy of every certified predicate (kernel/src/core/escalation.hpp).

    [Escalation::sign(SignStage{stage, decide}...)] asks a sign of its stages in order, each only while
    every answer before it is uncertain; the first certain answer is the answer ([Uncertain] when none
    certifies).  Its trace, one per query, records the latest [Stage] it was asked of: the maximum, in the
    order filter < compensated < expansion < exact, of the trace before and of every stage asked.
    [exact_sign(exact, stages...)] is [sign], then the caller's exact stage when no stage certified, which it
    records as [Stage::exact].

    The model: a sign's stages as the list of their (Stage, answer) pairs, the answers known in advance (a
    stage's answer does not depend on whether the stages before it were asked), and
    [escalate start steps = (answer, trace, asked)], [asked] the number of stages whose decision was called.
    - [escalate_sound]: whatever a certain answer of the stages satisfies, the answer satisfies: with
      [certifies] ([escalate_certifies]), when every stage is sound the answer is the exact sign;
    - [escalate_first_certain]: the answer is the first certain answer of the list, and exactly the stages
      up to it are asked (all of them, and the answer [Uncertain], when none certifies);
    - [escalate_trace]: the trace is the maximum of the start and of the stages asked, so never below the
      start, and no asked stage is above it;
    - [exact_sign_reaches_exact]: [exact_sign] asks its exact stage, answering the exact sign with the trace
      [StExact], exactly when no stage certified.
    The differential runner (routine [escalate], proofs/twins/Extract.v) runs [escalate] against the template
    itself, instantiated with one stage per step, on random lists of stages and answers: the answer, the
    trace and the number of stages asked compared. *)

From Coq Require Import Reals List Lia.
From Raykernel Require Import Model.
Import ListNotations.
Open Scope nat_scope.

(** [Stage] (raykernel/core.hpp), in its order. *)
Inductive stage := StFilter | StCompensated | StExpansion | StExact.

Definition stage_rank (s : stage) : nat :=
  match s with StFilter => 0 | StCompensated => 1 | StExpansion => 2 | StExact => 3 end.

Definition stage_le (a b : stage) : Prop := stage_rank a <= stage_rank b.

(** [Escalation::reach]: the later of the two. *)
Definition stage_max (a b : stage) : stage := if Nat.ltb (stage_rank a) (stage_rank b) then b else a.

(** [is_certain] (core/sign.hpp). *)
Definition sign_certain (s : sign) : bool := match s with Uncertain => false | _ => true end.

(** [Escalation(start).sign(steps...)]: the answer, the trace, the number of stages asked. *)
Fixpoint escalate (start : stage) (steps : list (stage * sign)) : sign * stage * nat :=
  match steps with
  | [] => (Uncertain, start, 0)
  | (st, s) :: rest =>
    let reached := stage_max start st in
    if sign_certain s then (s, reached, 1)
    else let '(a, t, k) := escalate reached rest in (a, t, S k)
  end.

(** [Escalation(start).exact_sign(exact, steps...)]: the answer, the trace, the number of stages asked, and
    whether the exact stage was asked ([exact] is its answer). *)
Definition exact_sign (start : stage) (exact : sign) (steps : list (stage * sign)) : sign * stage * nat * bool :=
  let '(a, t, k) := escalate start steps in
  if sign_certain a then (a, t, k, false) else (exact, stage_max t StExact, k, true).

(** ** The order of the stages *)

Lemma stage_rank_inj : forall a b, stage_rank a = stage_rank b -> a = b.
Proof. intros [] [] H; try reflexivity; discriminate H. Qed.

Lemma stage_max_rank : forall a b, stage_rank (stage_max a b) = Nat.max (stage_rank a) (stage_rank b).
Proof.
  intros a b. unfold stage_max. destruct (Nat.ltb (stage_rank a) (stage_rank b)) eqn:L;
    [apply Nat.ltb_lt in L | apply Nat.ltb_ge in L]; lia.
Qed.

Lemma stage_max_le_l : forall a b, stage_le a (stage_max a b).
Proof. intros a b. unfold stage_le. rewrite stage_max_rank. lia. Qed.

Lemma stage_max_le_r : forall a b, stage_le b (stage_max a b).
Proof. intros a b. unfold stage_le. rewrite stage_max_rank. lia. Qed.

Lemma stage_max_lub : forall a b c, stage_le a c -> stage_le b c -> stage_le (stage_max a b) c.
Proof. intros a b c. unfold stage_le. rewrite stage_max_rank. lia. Qed.

Lemma stage_max_exact : forall a, stage_max a StExact = StExact.
Proof. intros []; reflexivity. Qed.

Lemma stage_le_trans : forall a b c, stage_le a b -> stage_le b c -> stage_le a c.
Proof. unfold stage_le. lia. Qed.

Lemma stage_le_refl : forall a, stage_le a a.
Proof. unfold stage_le. lia. Qed.

(** ** The theorems *)

(** A certain answer of [escalate] is a certain answer of one of its steps. *)
Lemma escalate_answer_in : forall steps start a t k, escalate start steps = (a, t, k) ->
  sign_certain a = true -> exists st, In (st, a) steps.
Proof.
  induction steps as [|[st s] rest IH]; intros start a t k E C; cbn [escalate] in E.
  - injection E as <- _ _. discriminate C.
  - destruct (sign_certain s) eqn:Cs.
    + injection E as <- _ _. exists st. left. reflexivity.
    + destruct (escalate (stage_max start st) rest) as [[a' t'] k'] eqn:E'. injection E as -> _ _.
      destruct (IH _ _ _ _ E' C) as [st' I]. exists st'. right. exact I.
Qed.

(** Whatever every certain answer of the stages satisfies, a certain answer of [escalate] satisfies. *)
Theorem escalate_sound : forall (P : sign -> Prop) start steps a t k,
  (forall st s, In (st, s) steps -> sign_certain s = true -> P s) ->
  escalate start steps = (a, t, k) -> sign_certain a = true -> P a.
Proof.
  intros P start steps a t k H E C. destruct (escalate_answer_in steps start a t k E C) as [st I].
  exact (H st a I C).
Qed.

(** Hence, when every stage is sound for x (its answer, if certain, is the sign of x: Model.v's
    [certifies]), so is the answer; [Uncertain] certifies nothing. *)
Corollary escalate_certifies : forall (x : R) start steps a t k,
  (forall st s, In (st, s) steps -> certifies s x) ->
  escalate start steps = (a, t, k) -> certifies a x.
Proof.
  intros x start steps a t k H E. destruct (sign_certain a) eqn:C.
  - exact (escalate_sound (fun s => certifies s x) start steps a t k (fun st s I _ => H st s I) E C).
  - destruct a; try discriminate C. exact I.
Qed.

(** The answer is the first certain answer of the steps, and the stages asked are exactly the steps up to it;
    with no certain answer, the answer is [Uncertain] and every stage is asked. *)
Theorem escalate_first_certain : forall start steps a t k, escalate start steps = (a, t, k) ->
  (exists before st after, steps = before ++ (st, a) :: after /\ sign_certain a = true /\
     Forall (fun x => sign_certain (snd x) = false) before /\ k = S (length before))
  \/ (a = Uncertain /\ k = length steps /\ Forall (fun x => sign_certain (snd x) = false) steps).
Proof.
  intros start steps. revert start.
  induction steps as [|[st s] rest IH]; intros start a t k E; cbn [escalate] in E.
  - injection E as <- _ <-. right. repeat split. constructor.
  - destruct (sign_certain s) eqn:Cs.
    + injection E as <- _ <-. left. exists [], st, rest. repeat split; [exact Cs | constructor].
    + destruct (escalate (stage_max start st) rest) as [[a' t'] k'] eqn:E'. injection E as -> _ <-.
      destruct (IH _ _ _ _ E') as [[before [st' [after [Es [Ca [Fb Kb]]]]]] | [Ua [Ka Fa]]].
      * left. exists ((st, s) :: before), st', after. rewrite Es. repeat split; [exact Ca | | cbn; lia].
        constructor; [exact Cs | exact Fb].
      * right. split; [exact Ua|]. split; [cbn; lia|]. constructor; [exact Cs | exact Fa].
Qed.

(** The trace: the maximum of the start and of the stages of the steps asked (the first k), hence never below
    the start, and no stage asked above it; at most every step is asked. *)
Theorem escalate_trace : forall start steps a t k, escalate start steps = (a, t, k) ->
  t = fold_left stage_max (map fst (firstn k steps)) start /\ stage_le start t /\
  Forall (fun x => stage_le (fst x) t) (firstn k steps) /\ k <= length steps.
Proof.
  intros start steps. revert start.
  induction steps as [|[st s] rest IH]; intros start a t k E; cbn [escalate] in E.
  - injection E as _ <- <-. cbn. split; [reflexivity|]. split; [apply stage_le_refl|]. split; [constructor | lia].
  - destruct (sign_certain s) eqn:Cs.
    + injection E as _ <- <-. cbn. split; [reflexivity|]. split; [apply stage_max_le_l|]. split; [|lia].
      constructor; [apply stage_max_le_r | constructor].
    + destruct (escalate (stage_max start st) rest) as [[a' t'] k'] eqn:E'. injection E as _ <- <-.
      destruct (IH _ _ _ _ E') as [T [L [F K]]]. cbn [firstn map fold_left fst length].
      split; [exact T|]. split; [apply stage_le_trans with (stage_max start st); [apply stage_max_le_l | exact L]|].
      split; [|lia]. constructor; [|exact F].
      apply stage_le_trans with (stage_max start st); [apply stage_max_le_r | exact L].
Qed.

(** [exact_sign]: the exact stage is asked exactly when no step certified; then its answer is the answer and
    the trace is [StExact]; else the answer and trace are [escalate]'s. *)
Theorem exact_sign_reaches_exact : forall start exact steps a t k asked_exact,
  exact_sign start exact steps = (a, t, k, asked_exact) ->
  (asked_exact = true <-> Forall (fun x => sign_certain (snd x) = false) steps) /\
  (asked_exact = true -> a = exact /\ t = StExact) /\
  (asked_exact = false -> escalate start steps = (a, t, k)).
Proof.
  intros start exact steps a t k asked_exact. unfold exact_sign.
  destruct (escalate start steps) as [[a' t'] k'] eqn:E.
  pose proof (escalate_first_certain start steps a' t' k' E) as G.
  destruct (sign_certain a') eqn:C; intros H; injection H as <- <- <- <-.
  - split; [|split; [discriminate | reflexivity]].
    split; [discriminate|]. intros F. exfalso.
    destruct G as [[before [st [after [Es _]]]] | [Ua _]]; [|subst a'; discriminate C].
    rewrite Es in F. apply Forall_app in F. destruct F as [_ F]. inversion F as [|? ? Fa _].
    cbn in Fa. rewrite Fa in C. discriminate C.
  - split; [|split; [intros _; split; [reflexivity | apply stage_max_exact] | discriminate]].
    split; [intros _|reflexivity].
    destruct G as [[before [st [after [_ [Ca _]]]]] | [_ [_ F]]]; [discriminate Ca | exact F].
Qed.
