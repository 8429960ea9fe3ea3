(** * What the main theorems depend on.

    Not part of the [proofs] target: the ctest test [proofs_assumptions] (check_assumptions.cmake)
    compiles this file after the others and fails unless every theorem below depends only on the
    standard axioms of Coq's real numbers (ClassicalDedekindReals.sig_forall_dec,
    ClassicalDedekindReals.sig_not_dec), functional extensionality and the excluded middle, which
    Flocq uses.  Each block is announced by a line "@@ name" that the test matches against the
    theorem names kernel/src/certified/*.hpp cite.  The theorems are printed in tuples of up to ten (each Print
    Assumptions walks the whole real-number library, about a second; one per theorem took 2–3 minutes):
    when a tuple fails, print its members one by one to see which. *)

From Raykernel Require Import Constants Model PlaneFilter PlaneCompensated QuotientRounding PlaneClassification
  CompareQuotients PlaneCascade RayBox.
From Raykernel Require Import TriangleFilter TriangleCompensated TriangleRule TriangleCascade.
From Raykernel Require Import FloatCore ConstantsCpp PlaneTwins CompareTwins Expansions PlaneLiveness PlaneQueryTwins.
From Raykernel Require TriangleTwins.
From Raykernel Require TriangleLiveness.
From Raykernel Require PlaneStageTwoFinite.
From Raykernel Require PlaneQueryPairTwins.
From Raykernel Require NearestTwins.
From Raykernel Require PlaneRefinedTwins.

Definition main_results_1 :=
  (@near_bound_sound,
   @far_bound_sound,
   @slab_sound,
   @slab_sound_outward,
   @ray_box_sound,
   @den_filter_sound,
   @num_filter_sound,
   @dot3_filter_sound_gen,
   @dot3_filter_bound_encloses,
   @compensated_dot3_enclosure,
   @compensated_dot3_refined_enclosure).
Goal True. idtac "@@ near_bound_sound far_bound_sound slab_sound slab_sound_outward ray_box_sound den_filter_sound num_filter_sound dot3_filter_sound_gen dot3_filter_bound_encloses compensated_dot3_enclosure compensated_dot3_refined_enclosure". Abort.
Print Assumptions main_results_1.
Definition main_results_2 :=
  (@enclosure_sign_sound,
   @tail_sum_enclosure,
   @round_quotient_sound,
   @round_quotient_if_certain_sound,
   @round_quotient_candidate_normal,
   @relation_correct,
   @compensated_t_correct,
   @refined_t_correct,
   @cascade_signs_correct,
   @cascade_quotient_correct).
Goal True. idtac "@@ enclosure_sign_sound tail_sum_enclosure round_quotient_sound round_quotient_if_certain_sound round_quotient_candidate_normal relation_correct compensated_t_correct refined_t_correct cascade_signs_correct cascade_quotient_correct". Abort.
Print Assumptions main_results_2.
Definition main_results_3 :=
  (@fast_answer_correct,
   @fast_relation_correct,
   @compensated_dot3_exact_inputs,
   @intersect_fast_correct,
   @fast_path_den_valid,
   @expansion_t_correct,
   @compare_quotients_filter_sound,
   @compare_quotients_compensated_enclosure,
   @compare_hit_distances_filter_correct,
   @compare_hit_distances_compensated_correct).
Goal True. idtac "@@ fast_answer_correct fast_relation_correct compensated_dot3_exact_inputs intersect_fast_correct fast_path_den_valid expansion_t_correct compare_quotients_filter_sound compare_quotients_compensated_enclosure compare_hit_distances_filter_correct compare_hit_distances_compensated_correct". Abort.
Print Assumptions main_results_3.

Definition supporting_results :=
  (two_sum_exact,
   two_prod_guard_exact,
   constants_binary64,
   den_filter_encloses,
   num_filter_encloses,
   dot3_rounded_dominated,
   compensated_den_enclosure,
   compensated_num_enclosure,
   half_gap_bits,
   prepare_divisor_spec,
   quotient_residuals,
   quotient_candidate,
   quotient_constants_binary64,
   two_prod_threshold_exact,
   relation_hit_iff,
   relation_behind_iff,
   relation_parallel_iff,
   relation_in_plane_iff,
   ray_meets_plane_iff,
   hit_at_origin,
   certified_sign,
   certified_relation,
   filter_relation_correct,
   compensated_signs_correct,
   filter_enclosure_encloses,
   two_prod_error,
   quotient_order_sign,
   hit_distance_order_correct,
   origin_order_correct,
   compensated_den_refined_enclosure,
   compensated_num_refined_enclosure,
   refined_signs_correct,
   den_filter_lanes_sound,
   num_filter_lanes_sound,
   lane_sign_certain,
   lanes_relation,
   den_nonzero_valid,
   relation_of_nonzero).
Goal True. idtac "@@ two_sum_exact two_prod_guard_exact constants_binary64 den_filter_encloses num_filter_encloses dot3_rounded_dominated compensated_den_enclosure compensated_num_enclosure half_gap_bits prepare_divisor_spec quotient_residuals quotient_candidate quotient_constants_binary64 two_prod_threshold_exact relation_hit_iff relation_behind_iff relation_parallel_iff relation_in_plane_iff ray_meets_plane_iff hit_at_origin certified_sign certified_relation filter_relation_correct compensated_signs_correct filter_enclosure_encloses two_prod_error quotient_order_sign hit_distance_order_correct origin_order_correct compensated_den_refined_enclosure compensated_num_refined_enclosure refined_signs_correct den_filter_lanes_sound num_filter_lanes_sound lane_sign_certain lanes_relation den_nonzero_valid relation_of_nonzero". Abort.
Print Assumptions supporting_results.

(** Ray–triangle (issue 14). *)
Definition main_results_4 :=
  (@absolute_term_lower,
   @det3_filter_encloses,
   @pi_filter_sound,
   @num_filter_sound,
   @den_filter_sound,
   @det3_compensated_encloses,
   @pi_compensated_encloses,
   @num_compensated_encloses,
   @den_compensated_encloses,
   @stage2_filter_view).
Goal True. idtac "@@ absolute_term_lower det3_filter_encloses pi_filter_sound num_filter_sound den_filter_sound det3_compensated_encloses pi_compensated_encloses num_compensated_encloses den_compensated_encloses stage2_filter_view". Abort.
Print Assumptions main_results_4.
Definition main_results_5 :=
  (@owned_sign_antisymmetric,
   @owned_sign_nonzero,
   @edge_value_shift,
   @triangle_location_correct,
   @triangle_fast_sign_correct,
   @fast_location_correct,
   @triangle_quotient_correct,
   @triangle_quotient_expansion_correct,
   @den_nonzero_direction).
Goal True. idtac "@@ owned_sign_antisymmetric owned_sign_nonzero edge_value_shift triangle_location_correct triangle_fast_sign_correct fast_location_correct triangle_quotient_correct triangle_quotient_expansion_correct den_nonzero_direction". Abort.
Print Assumptions main_results_5.

(** The twins (issue 16), one block per file: each tuple's assumptions are the union of its members'. *)

(** PlaneTwins.v: the twins of stages 1 and 2, tied to the model, and sound end to end *)
Definition twin_results_0 :=
  (two_sum_twin,
   two_sum_twin_exact,
   two_prod_twin,
   dot3_rounded_twin,
   dot3_filter_lanes_twin,
   den_filter_twin_sound,
   num_filter_twin_sound,
   compensated_dot3_twin,
   compensated_dot3_exact_twin,
   enclosure_sign_twin,
   den_compensated_twin_sound,
   num_compensated_twin_sound,
   expansion_tail_enclosure_twin).
Goal True. idtac "@@ two_sum_twin two_sum_twin_exact two_prod_twin dot3_rounded_twin dot3_filter_lanes_twin den_filter_twin_sound num_filter_twin_sound compensated_dot3_twin compensated_dot3_exact_twin enclosure_sign_twin den_compensated_twin_sound num_compensated_twin_sound expansion_tail_enclosure_twin". Abort.
Print Assumptions twin_results_0.

(** the compiled constants are the proved ones *)
Definition twin_results_1 :=
  (cpp_filter_den_relative,
   cpp_filter_num_relative,
   cpp_filter_absolute,
   cpp_compensated_relative,
   cpp_compensated_absolute,
   cpp_refined_relative,
   cpp_refined_low_relative,
   cpp_refined_absolute,
   cpp_tail_sum_relative,
   cpp_tail_sum_absolute,
   cpp_tail_sum_max_terms,
   cpp_compare_filter_relative,
   cpp_compare_propagation_factor,
   cpp_compare_absolute,
   cpp_compare_compensated_relative,
   fle_largest_finite).
Goal True. idtac "@@ cpp_filter_den_relative cpp_filter_num_relative cpp_filter_absolute cpp_compensated_relative cpp_compensated_absolute cpp_refined_relative cpp_refined_low_relative cpp_refined_absolute cpp_tail_sum_relative cpp_tail_sum_absolute cpp_tail_sum_max_terms cpp_compare_filter_relative cpp_compare_propagation_factor cpp_compare_absolute cpp_compare_compensated_relative fle_largest_finite". Abort.
Print Assumptions twin_results_1.

(** CompareTwins.v: the comparison of two quotients *)
Definition twin_results_2 :=
  (compare_quotients_filter_twin,
   compare_quotients_compensated_twin).
Goal True. idtac "@@ compare_quotients_filter_twin compare_quotients_compensated_twin". Abort.
Print Assumptions twin_results_2.

(** Expansions.v: stage 3 *)
Definition twin_results_3 :=
  (sum_gen_exact,
   scale_gen_exact,
   multiply_gen_exact,
   build_expansions_exact,
   expansion_sign_sound,
   sum_list_weakly_signed,
   certified_signs_expansion_sound,
   compare_quotients_expansion_sound).
Goal True. idtac "@@ sum_gen_exact scale_gen_exact multiply_gen_exact build_expansions_exact expansion_sign_sound sum_list_weakly_signed certified_signs_expansion_sound compare_quotients_expansion_sound". Abort.
Print Assumptions twin_results_3.

(** PlaneLiveness.v *)
Definition twin_results_4 :=
  (filter_live,
   filter_den_live,
   filter_num_live,
   enclosure_sign_live,
   compensated_live,
   compensated_den_live).
Goal True. idtac "@@ filter_live filter_den_live filter_num_live enclosure_sign_live compensated_live compensated_den_live". Abort.
Print Assumptions twin_results_4.

(** TriangleTwins.v: the ray–triangle stages 1 and 2 (kernel/src/triangle/), tied to TriangleFilter.v and
    TriangleCompensated.v, and sound end to end *)
Definition twin_results_triangle :=
  (TriangleTwins.det3_twin,
   TriangleTwins.det3_filter_lanes_twin,
   TriangleTwins.triangle_pi_filter_twin_sound,
   TriangleTwins.triangle_num_filter_twin_sound,
   TriangleTwins.triangle_den_filter_twin_sound,
   TriangleTwins.cdet3_twin,
   TriangleTwins.det3_enclosure_twin,
   TriangleTwins.triangle_pi_compensated_twin_sound,
   TriangleTwins.triangle_num_compensated_twin_sound,
   TriangleTwins.triangle_den_compensated_twin_sound,
   TriangleTwins.triangle_pi_lane_filter_twin_sound,
   TriangleTwins.triangle_pi_lane_compensated_twin_sound,
   TriangleTwins.triangle_den_lane_compensated_twin_sound,
   TriangleTwins.triangle_num_lane_compensated_twin_sound,
   TriangleTwins.det3n_twin,
   TriangleTwins.triangle_pi_lane_view_filter_twin_sound,
   TriangleTwins.triangle_num_lane_view_filter_twin_sound,
   TriangleTwins.triangle_den_lane_view_filter_twin_sound).
Goal True. idtac "@@ det3_twin det3_filter_lanes_twin triangle_pi_filter_twin_sound triangle_num_filter_twin_sound triangle_den_filter_twin_sound cdet3_twin det3_enclosure_twin triangle_pi_compensated_twin_sound triangle_num_compensated_twin_sound triangle_den_compensated_twin_sound triangle_pi_lane_filter_twin_sound triangle_pi_lane_compensated_twin_sound triangle_den_lane_compensated_twin_sound triangle_num_lane_compensated_twin_sound det3n_twin triangle_pi_lane_view_filter_twin_sound triangle_num_lane_view_filter_twin_sound triangle_den_lane_view_filter_twin_sound". Abort.
Print Assumptions twin_results_triangle.

(** the compiled triangle constants are the proved ones *)
Definition twin_results_triangle_constants :=
  (ConstantsCpp.cpp_triangle_absolute_scale,
   ConstantsCpp.cpp_triangle_absolute,
   ConstantsCpp.cpp_triangle_filter_pi_relative,
   ConstantsCpp.cpp_triangle_filter_num_relative,
   ConstantsCpp.cpp_triangle_filter_den_relative,
   ConstantsCpp.cpp_triangle_compensated_relative,
   ConstantsCpp.cpp_triangle_compensated_den_relative).
Goal True. idtac "@@ cpp_triangle_absolute_scale cpp_triangle_absolute cpp_triangle_filter_pi_relative cpp_triangle_filter_num_relative cpp_triangle_filter_den_relative cpp_triangle_compensated_relative cpp_triangle_compensated_den_relative". Abort.
Print Assumptions twin_results_triangle_constants.

(** PlaneQueryTwins.v: the rounding of t and the fast paths, tied to the models *)
Definition twin_results_5 :=
  (half_gap_twin,
   round_quotient_twin,
   round_quotient_twin_sound,
   fast_relation_twin_correct,
   fast_answer_twin_correct,
   tiny_product_threshold).
Goal True. idtac "@@ half_gap_twin round_quotient_twin round_quotient_twin_sound fast_relation_twin_correct fast_answer_twin_correct tiny_product_threshold". Abort.
Print Assumptions twin_results_5.

(** TriangleLiveness.v: the ray–triangle stages 1 and 2 do certify (inputs of magnitude at most 2^300, |V|
    above 2^-48·P or 2^-95·P plus absolute terms) *)
Definition twin_results_triangle_liveness :=
  (TriangleLiveness.triangle_pi_filter_live,
   TriangleLiveness.triangle_num_filter_live,
   TriangleLiveness.triangle_den_filter_live,
   TriangleLiveness.triangle_pi_compensated_live,
   TriangleLiveness.triangle_num_compensated_live,
   TriangleLiveness.triangle_den_compensated_live).
Goal True. idtac "@@ triangle_pi_filter_live triangle_num_filter_live triangle_den_filter_live triangle_pi_compensated_live triangle_num_compensated_live triangle_den_compensated_live". Abort.
Print Assumptions twin_results_triangle_liveness.

(** PlaneStageTwoFinite.v: stage 2 for every bit pattern, without the hypothesis "hi and lo finite" *)
Definition twin_results_stage_two_finite :=
  (PlaneStageTwoFinite.two_sum_b_nan_or_finite,
   PlaneStageTwoFinite.den_compensated_certain_finite,
   PlaneStageTwoFinite.num_compensated_certain_finite,
   PlaneStageTwoFinite.den_compensated_twin_sound_total,
   PlaneStageTwoFinite.num_compensated_twin_sound_total,
   PlaneStageTwoFinite.compare_compensated_certain_finite,
   PlaneStageTwoFinite.compare_compensated_twin_sound_total,
   PlaneStageTwoFinite.hit_order_compensated_twin_sound_total).
Goal True. idtac "@@ two_sum_b_nan_or_finite den_compensated_certain_finite num_compensated_certain_finite den_compensated_twin_sound_total num_compensated_twin_sound_total compare_compensated_certain_finite compare_compensated_twin_sound_total hit_order_compensated_twin_sound_total". Abort.
Print Assumptions twin_results_stage_two_finite.

(** PlaneQueryPairTwins.v: the Lanes2 one-query forms and stage 3 of plane/ray_plane_stages.hpp *)
Definition twin_results_query_pairs :=
  (fast_answer_from_twin_correct,
   PlaneQueryPairTwins.fast_relation_pair_twin_correct,
   PlaneQueryPairTwins.fast_answer_pair_twin_correct,
   PlaneQueryPairTwins.ray_plane_expansions_twin_exact).
Goal True. idtac "@@ fast_answer_from_twin_correct fast_relation_pair_twin_correct fast_answer_pair_twin_correct ray_plane_expansions_twin_exact". Abort.
Print Assumptions twin_results_query_pairs.

(** NearestTwins.v: the nearest-hit comparison (nearest/nearest_hit.cpp, compare_hit_distances) *)
Definition twin_results_nearest :=
  (NearestTwins.compare_hit_distances_twin_correct).
Goal True. idtac "@@ compare_hit_distances_twin_correct". Abort.
Print Assumptions twin_results_nearest.

(** IntegerDet3.v, IntegerExpansion.v and TriangleIntegerSign.v: stage 3's first try, a determinant's sign in
    integers, and its value as at most four exact doubles for the roundings *)
From Raykernel Require IntegerDet3 IntegerExpansion TriangleIntegerSign.
Definition integer_stage_results :=
  (IntegerDet3.integer_det3_sign_correct, IntegerDet3.integer_vector_value, IntegerDet3.det3_sign_integer,
   IntegerDet3.det3_range, IntegerDet3.det3_scaled, TriangleIntegerSign.integer_value_sign_sound,
   TriangleIntegerSign.difference_vector_ok, IntegerDet3.integer_vector_sum_value, IntegerExpansion.chunks_value, IntegerExpansion.dyadic_value,
   IntegerExpansion.integer_components_sound, TriangleIntegerSign.integer_value_components_sound).
Goal True. idtac "@@ integer_det3_sign_correct integer_vector_value det3_sign_integer det3_range det3_scaled integer_value_sign_sound difference_vector_ok integer_vector_sum_value chunks_value dyadic_value integer_components_sound integer_value_components_sound". Abort.
Print Assumptions integer_stage_results.

(** TriangleStage3Twins.v: stage 3 of the triangle (core/expansion_value.hpp) is the model's determinant *)
From Raykernel Require TriangleStage3Twins.
Goal True. idtac "@@ triangle_expansion_sign_sound". Abort.
Print Assumptions TriangleStage3Twins.triangle_expansion_sign_sound.
Definition twin_results_triangle_stage3 :=
  (TriangleStage3Twins.value_ev_exact,
   TriangleStage3Twins.length_value_ev).
Goal True. idtac "@@ value_ev_exact length_value_ev". Abort.
Print Assumptions twin_results_triangle_stage3.

(** TriangleCascadeTwins.v: the triangle's fast relation (ray_triangle_cascade.cpp) answers as docs/contract.md §6 *)
From Raykernel Require TriangleCascadeTwins.
Goal True. idtac "@@ fast_relation_tri_correct". Abort.
Print Assumptions TriangleCascadeTwins.fast_relation_tri_correct.

(** PlaneRefinedTwins.v: the second level of stage 2 (compensated_dot3_refined) tied to its twin *)
Goal True. idtac "@@ compensated_dot3_refined_twin". Abort.
Print Assumptions PlaneRefinedTwins.compensated_dot3_refined_twin.
Definition twin_results_refined :=
  (PlaneRefinedTwins.den_refined_twin_encloses,
   PlaneRefinedTwins.num_refined_twin_encloses,
   PlaneRefinedTwins.den_refined_twin_sound,
   PlaneRefinedTwins.num_refined_twin_sound).
Goal True. idtac "@@ den_refined_twin_encloses num_refined_twin_encloses den_refined_twin_sound num_refined_twin_sound". Abort.
Print Assumptions twin_results_refined.

(** PlaneCascadeTwins.v: the cascade's control flow (ray_plane_cascade.cpp, validation.cpp) for every bit pattern *)
From Raykernel Require PlaneCascadeTwins.
Goal True. idtac "@@ cascade_twin_correct". Abort.
Print Assumptions PlaneCascadeTwins.cascade_twin_correct.
Definition twin_results_cascade :=
  (PlaneCascadeTwins.certified_signs_twin_sound,
   PlaneCascadeTwins.certified_quotient_twin_sound,
   PlaneCascadeTwins.validate_b_none).
Goal True. idtac "@@ certified_signs_twin_sound certified_quotient_twin_sound validate_b_none". Abort.
Print Assumptions twin_results_cascade.
(** PlaneCascadeTwins.v: [intersect]'s step between its fast path and the cascade (plane_api.cpp) *)
Goal True. idtac "@@ second_level_twin_correct". Abort.
Print Assumptions PlaneCascadeTwins.second_level_twin_correct.
(** PlaneCascadeTwins.v: [relation] past its fast path, and validation's other direction *)
Goal True. idtac "@@ relation_twin_correct". Abort.
Print Assumptions PlaneCascadeTwins.relation_twin_correct.
Definition twin_results_validate := (PlaneCascadeTwins.validate_b_valid, PlaneCascadeTwins.validate_b_some).
Goal True. idtac "@@ validate_b_valid validate_b_some". Abort.
Print Assumptions twin_results_validate.
Definition twin_results_stage2_agrees :=
  (PlaneCascadeTwins.den_stage2_agrees_with_filter, PlaneCascadeTwins.num_stage2_agrees_with_filter).
Goal True. idtac "@@ den_stage2_agrees_with_filter num_stage2_agrees_with_filter". Abort.
Print Assumptions twin_results_stage2_agrees.

(** PlaneRefinedFinite.v: the second level of stage 2, a certain sign implies finite hi and lo (every bit pattern) *)
From Raykernel Require PlaneRefinedFinite.
Definition twin_results_refined_finite :=
  (PlaneRefinedFinite.refined_radius_finite_parts,
   PlaneRefinedFinite.den_refined_certain_finite,
   PlaneRefinedFinite.num_refined_certain_finite,
   PlaneRefinedFinite.den_refined_twin_sound_total,
   PlaneRefinedFinite.num_refined_twin_sound_total).
Goal True. idtac "@@ refined_radius_finite_parts den_refined_certain_finite num_refined_certain_finite den_refined_twin_sound_total num_refined_twin_sound_total". Abort.
Print Assumptions twin_results_refined_finite.

(** TriangleLaneLiveness.v: the triangle fast paths' lanes ([triangle_relation_lanes], [triangle_compensated_lanes],
    [filter_view]) decide as the scalar stages 1 and 2 (every bit pattern), hence certify on TriangleLiveness.v's
    classes *)
From Raykernel Require TriangleLaneLiveness.
Definition twin_results_triangle_lane_liveness :=
  (TriangleLaneLiveness.triangle_pi_relation_lane_is_scalar,
   TriangleLaneLiveness.triangle_pi_compensated_lane_is_scalar,
   TriangleLaneLiveness.triangle_num_compensated_lane_is_scalar,
   TriangleLaneLiveness.triangle_den_compensated_lane_is_scalar,
   TriangleLaneLiveness.triangle_pi_view_lane_is_scalar,
   TriangleLaneLiveness.triangle_num_view_lane_is_scalar,
   TriangleLaneLiveness.triangle_den_view_lane_is_scalar,
   TriangleLaneLiveness.triangle_pi_relation_lane_live,
   TriangleLaneLiveness.triangle_pi_compensated_lane_live,
   TriangleLaneLiveness.triangle_num_compensated_lane_live,
   TriangleLaneLiveness.triangle_den_compensated_lane_live,
   TriangleLaneLiveness.triangle_pi_view_lane_live,
   TriangleLaneLiveness.triangle_num_view_lane_live,
   TriangleLaneLiveness.triangle_den_view_lane_live).
Goal True. idtac "@@ triangle_pi_relation_lane_is_scalar triangle_pi_compensated_lane_is_scalar triangle_num_compensated_lane_is_scalar triangle_den_compensated_lane_is_scalar triangle_pi_view_lane_is_scalar triangle_num_view_lane_is_scalar triangle_den_view_lane_is_scalar triangle_pi_relation_lane_live triangle_pi_compensated_lane_live triangle_num_compensated_lane_live triangle_den_compensated_lane_live triangle_pi_view_lane_live triangle_num_view_lane_live triangle_den_view_lane_live". Abort.
Print Assumptions twin_results_triangle_lane_liveness.

(** TriangleMutations.v: the mutations tri_call_site_den and tri_drop_guard on the twin of fast_triangle_intersection
    (the mutated twin answers as the twin, outside the cases stated) *)
From Raykernel Require TriangleMutations.
Definition twin_results_triangle_mutations :=
  (TriangleMutations.den_filter_constant_monotone,
   TriangleMutations.tri_call_site_den_same_unless_between,
   TriangleMutations.drop_guard_consumers_agree,
   TriangleMutations.tri_drop_guard_same_unless_infinite_low).
Goal True. idtac "@@ den_filter_constant_monotone tri_call_site_den_same_unless_between drop_guard_consumers_agree tri_drop_guard_same_unless_infinite_low". Abort.
Print Assumptions twin_results_triangle_mutations.
(** TriangleStageTwoFinite.v: tri_drop_guard for every bit pattern (stage 2's low parts NaN or finite where h and m
    are finite, hence no_infinite_low for the five stage-2 terms) *)
From Raykernel Require TriangleStageTwoFinite.
Definition twin_results_triangle_drop_guard :=
  (TriangleStageTwoFinite.cdet3_low_nf,
   TriangleStageTwoFinite.pi_no_infinite_low,
   TriangleStageTwoFinite.num_lane_no_infinite_low,
   TriangleStageTwoFinite.den_no_infinite_low,
   TriangleStageTwoFinite.tri_drop_guard_same).
Goal True. idtac "@@ cdet3_low_nf pi_no_infinite_low num_lane_no_infinite_low den_no_infinite_low tri_drop_guard_same". Abort.
Print Assumptions twin_results_triangle_drop_guard.
(** TriangleCascadeFlowCorrect.v: the ray–triangle cascade's control flow (ray_triangle_cascade.cpp,
    TriangleCascade), its answers before the exact stage, for every bit pattern *)
From Raykernel Require TriangleCascadeFlowCorrect.
Goal True. idtac "@@ tc_classify_b_correct". Abort.
Print Assumptions TriangleCascadeFlowCorrect.tc_classify_b_correct.
Definition twin_results_triangle_flow :=
  (TriangleCascadeFlowCorrect.tc_sign_b_correct,
   TriangleCascadeFlowCorrect.tc_tie_break_b_correct,
   TriangleCascadeFlowCorrect.tc_normal_b_correct,
   TriangleCascadeFlowCorrect.tc_relation_b_correct,
   TriangleCascadeFlowCorrect.tc_intersect_b_class_correct,
   TriangleCascadeFlowCorrect.det3_enclosure_certain_finite,
   TriangleCascadeFlowCorrect.tc_zero_quotient_correct,
   TriangleCascadeFlowCorrect.tc_expansion_enclosure_ok,
   TriangleCascadeFlowCorrect.tc_stage3_quotient_correct,
   TriangleCascadeFlowCorrect.tc_stage3_sign_sound,
   TriangleCascadeFlowCorrect.tc_stage3_components_sound).
Goal True. idtac "@@ tc_sign_b_correct tc_tie_break_b_correct tc_normal_b_correct tc_relation_b_correct tc_intersect_b_class_correct det3_enclosure_certain_finite tc_zero_quotient_correct tc_expansion_enclosure_ok tc_stage3_quotient_correct tc_stage3_sign_sound tc_stage3_components_sound". Abort.
Print Assumptions twin_results_triangle_flow.
(** TriangleCascadeQuotients.v: the ray–triangle cascade's whole answer before the exact stage
    (ray_triangle_cascade.cpp, triangle_intersection_cascade): §6's classification, t = RN(num/den),
    barycentrics RN(π_k/den), for every bit pattern *)
From Raykernel Require TriangleCascadeQuotients.
Goal True. idtac "@@ tc_intersect_b_correct". Abort.
Print Assumptions TriangleCascadeQuotients.tc_intersect_b_correct.
Definition triangle_cascade_boundary_results :=
  (TriangleCascadeQuotients.tc_qinv_boundary,
   TriangleCascadeQuotients.tc_short_means,
   TriangleCascadeQuotients.tc_den_sign_means).
Goal True. idtac "@@ tc_qinv_boundary tc_short_means tc_den_sign_means". Abort.
Print Assumptions triangle_cascade_boundary_results.
Definition twin_results_triangle_cascade_quotients :=
  (TriangleCascadeQuotients.tc_stage2_quotient_correct,
   TriangleCascadeQuotients.tc_quot_tail_correct,
   TriangleCascadeQuotients.tc_intersect_b_eq,
   TriangleCascadeQuotients.tc_intersect_b_unasked).
Goal True. idtac "@@ tc_stage2_quotient_correct tc_quot_tail_correct tc_intersect_b_eq tc_intersect_b_unasked". Abort.
Print Assumptions twin_results_triangle_cascade_quotients.
(** TriangleIntersectPublic.v: the public intersect_traced (triangle_api.cpp: the fast path, else the cascade)
    on valid inputs: finite inputs, docs/contract.md §6's class, den ≠ 0 when located, each asked quotient
    with a value RN(·/den) with den ≠ 0; and the cascade's answer with den ≠ 0 *)
From Raykernel Require TriangleIntersectPublic.
Goal True. idtac "@@ intersect_public_correct". Abort.
Print Assumptions TriangleIntersectPublic.intersect_public_correct.
Definition twin_results_triangle_intersect_public :=
  (TriangleIntersectPublic.tc_intersect_b_den_nonzero,
   TriangleIntersectPublic.tc_intersect_b_means,
   TriangleIntersectPublic.contract_class_den,
   TriangleIntersectPublic.tc_intersect_b_unlocated_nan,
   TriangleIntersectPublic.fast_intersection_tri_unasked).
Goal True. idtac "@@ tc_intersect_b_den_nonzero tc_intersect_b_means contract_class_den tc_intersect_b_unlocated_nan fast_intersection_tri_unasked". Abort.
Print Assumptions twin_results_triangle_intersect_public.
(** TriangleIntersectPublic.v: the public relation (triangle_api.cpp: the fast path, else the cascade) on valid
    inputs: finite inputs, docs/contract.md §6's class under the rule, den ≠ 0 exactly when located *)
Goal True. idtac "@@ relation_public_correct". Abort.
Print Assumptions TriangleIntersectPublic.relation_public_correct.
(** TriangleIntersectTheorem.v: the triangle's fast intersection (ray_triangle_cascade.cpp,
    fast_triangle_intersection) answers as docs/contract.md §6, t = RN(num/den), barycentrics RN(π_k/den) *)
From Raykernel Require TriangleIntersectTheorem.
Goal True. idtac "@@ fast_intersection_tri_correct". Abort.
Print Assumptions TriangleIntersectTheorem.fast_intersection_tri_correct.
Definition twin_results_triangle_intersection :=
  (TriangleIntersectTheorem.round_quotient_shared_sound,
   TriangleIntersectTheorem.decide_nonzero_contract,
   TriangleIntersectTheorem.pi_lane_sign,
   TriangleIntersectTheorem.num_lane_sign,
   TriangleIntersectTheorem.den_lane_sign).
Goal True. idtac "@@ round_quotient_shared_sound decide_nonzero_contract pi_lane_sign num_lane_sign den_lane_sign". Abort.
Print Assumptions twin_results_triangle_intersection.
(** TriangleDenCertain.v (with QuotientDivisorBound.v): a quotient certified over den's divisor implies den's
    stage-1 filter sign certain; the mutation tri_call_site_den changes no answer of fast_triangle_intersection *)
From Raykernel Require QuotientDivisorBound TriangleDenCertain.
Definition main_results_15 :=
  (@TriangleDenCertain.tri_call_site_den_same,
   @TriangleDenCertain.tri_by_filter_den_same).
Goal True. idtac "@@ tri_call_site_den_same tri_by_filter_den_same". Abort.
Print Assumptions main_results_15.
Definition twin_results_den_certain :=
  (QuotientDivisorBound.round_quotient_certain_divisor,
   TriangleDenCertain.den_filter_margin,
   TriangleDenCertain.den_quotient_filter_certain).
Goal True. idtac "@@ round_quotient_certain_divisor den_filter_margin den_quotient_filter_certain". Abort.
Print Assumptions twin_results_den_certain.
(** CompareStage1Liveness.v: stage 1 of the nearest-hit comparison (compare_quotients_filter, as
    compare_hit_distances calls it) certifies whenever |x_1·y_2 − x_2·y_1| > c_1·S + c_2·ρ + c_3; not
    vacuous (an example certified by computation) and neither c_1 nor c_2 can be halved *)
From Raykernel Require CompareStage1Liveness.
Goal True. idtac "@@ compare_filter_live compare_filter_live_exact compare_hit_distances_stage1_live". Abort.
Definition liveness_results_compare :=
  (CompareStage1Liveness.compare_filter_live,
   CompareStage1Liveness.compare_filter_live_exact,
   CompareStage1Liveness.compare_hit_distances_stage1_live).
Print Assumptions liveness_results_compare.
Goal True. idtac "@@ compare_filter_live_example compare_filter_half_c1_fails compare_filter_half_c2_fails". Abort.
Definition liveness_sharpness_compare :=
  (CompareStage1Liveness.compare_filter_live_example,
   CompareStage1Liveness.compare_filter_half_c1_fails,
   CompareStage1Liveness.compare_filter_half_c2_fails).
Print Assumptions liveness_sharpness_compare.
(** PlaneRefinedLiveness.v: the second level of stage 2 certifies on a stated class; the class is not vacuous
    and its constant is within a factor 1.2 of the best *)
From Raykernel Require PlaneRefinedLiveness.
Definition main_results_16 :=
  (@PlaneRefinedLiveness.refined_live,
   @PlaneRefinedLiveness.refined_den_live,
   @PlaneRefinedLiveness.refined_num_live).
Goal True. idtac "@@ refined_live refined_den_live refined_num_live". Abort.
Print Assumptions main_results_16.
Definition twin_results_refined_liveness :=
  (PlaneRefinedLiveness.refined_radius_upper,
   PlaneRefinedLiveness.enclosure_sign_live3,
   PlaneRefinedLiveness.refined_den_live_witness,
   PlaneRefinedLiveness.refined_num_live_witness,
   PlaneRefinedLiveness.refined_den_live_half_false).
Goal True. idtac "@@ refined_radius_upper enclosure_sign_live3 refined_den_live_witness refined_num_live_witness refined_den_live_half_false". Abort.
Print Assumptions twin_results_refined_liveness.
(** QuotientLiveness.v: the quotient rounding (quotient_rounding.hpp, prepare_divisor and round_quotient)
    certifies, with t = RN(X/Y), when X/Y is far enough from the points RN(X/Y) ± half_gap(RN(X/Y)) (liveness) *)
From Raykernel Require QuotientLiveness.
Goal True. idtac "@@ round_quotient_live". Abort.
Print Assumptions QuotientLiveness.round_quotient_live.
Definition twin_results_quotient_liveness :=
  (QuotientLiveness.round_quotient_live_exact,
   QuotientLiveness.quotient_residuals_q0,
   QuotientLiveness.round_quotient_b_third,
   QuotientLiveness.near_midpoint_threshold,
   QuotientLiveness.third_radius_threshold).
Goal True. idtac "@@ round_quotient_live_exact quotient_residuals_q0 round_quotient_b_third near_midpoint_threshold third_radius_threshold". Abort.
Print Assumptions twin_results_quotient_liveness.
(** QuotientLivenessTwin.v: the same liveness over the twin (PlaneQueryTwins.v's prepare_divisor_b, round_quotient_b,
    runner-tied): finite parts of magnitude <= 2^1000 in round_quotient_live's class certify, t = RN(X/Y) finite;
    the twin computes the model's rounding forwards on bounded inputs; the computed examples are in the class *)
From Raykernel Require QuotientLivenessTwin.
Goal True. idtac "@@ round_quotient_live_b". Abort.
Print Assumptions QuotientLivenessTwin.round_quotient_live_b.
Definition twin_results_quotient_liveness_twin :=
  (QuotientLivenessTwin.round_quotient_live_exact_b,
   QuotientLivenessTwin.round_quotient_b_fwd,
   QuotientLivenessTwin.prepare_divisor_b_fwd,
   QuotientLivenessTwin.rq_model_bounds,
   QuotientLivenessTwin.round_quotient_b_third_live,
   QuotientLivenessTwin.round_quotient_b_near_midpoint_live,
   QuotientLivenessTwin.fast_answer_from_live_b,
   FloatCore.fdiv_fwd).
Goal True. idtac "@@ round_quotient_live_exact_b round_quotient_b_fwd prepare_divisor_b_fwd rq_model_bounds round_quotient_b_third_live round_quotient_b_near_midpoint_live fast_answer_from_live_b fdiv_fwd". Abort.
Print Assumptions twin_results_quotient_liveness_twin.
(** PlaneCascadeQuotientLiveness.v: the cascade's t (PlaneCascadeTwins.v's certified_quotient_b, intersect_traced_b) is
    rounded by stage 2's first level, to RN(num/den), when the first-level enclosures are in round_quotient_live_b's
    class; the query t = 1/3 is in the class *)
From Raykernel Require PlaneCascadeQuotientLiveness.
Goal True. idtac "@@ cascade_quotient_live_b". Abort.
Print Assumptions PlaneCascadeQuotientLiveness.cascade_quotient_live_b.
Definition twin_results_cascade_quotient_liveness :=
  (PlaneCascadeQuotientLiveness.certified_quotient_b_first,
   PlaneCascadeQuotientLiveness.intersect_cascade_t,
   PlaneCascadeQuotientLiveness.intersect_traced_live_b,
   PlaneCascadeQuotientLiveness.intersect_traced_third,
   PlaneCascadeQuotientLiveness.cascade_quotient_live_third).
Goal True. idtac "@@ certified_quotient_b_first intersect_cascade_t intersect_traced_live_b intersect_traced_third cascade_quotient_live_third". Abort.
Print Assumptions twin_results_cascade_quotient_liveness.
(** PlaneStage3Liveness.v: stage 3's checked sign certifies on one-component expansions; the twin cascade answers at
    stage 3 when the expansions have one component each; a concrete input where stages 1 and 2 do not *)
From Raykernel Require PlaneStage3Liveness.
Definition twin_results_stage3_liveness :=
  (PlaneStage3Liveness.expansion_sign_single_certain,
   PlaneStage3Liveness.expansion_sign_single_exact,
   PlaneStage3Liveness.certified_signs_single_live,
   PlaneStage3Liveness.relation_single_live,
   PlaneStage3Liveness.stage3_plane_live_example,
   PlaneStage3Liveness.build_expansions_single,
   PlaneStage3Liveness.expansions_int_single,
   PlaneStage3Liveness.stage3_int_live,
   PlaneStage3Liveness.relation_int_live).
Goal True. idtac "@@ expansion_sign_single_certain expansion_sign_single_exact certified_signs_single_live relation_single_live stage3_plane_live_example build_expansions_single expansions_int_single stage3_int_live relation_int_live". Abort.
Print Assumptions twin_results_stage3_liveness.
(** CompareStage2Radius.v: the radius of stage 2 of nearest_hit's comparison (compare_quotients_compensated) from
    above, over the model: the first half of stage 2's liveness *)
From Raykernel Require CompareStage2Radius.
Goal True. idtac "@@ compare_compensated_radius_upper". Abort.
Print Assumptions CompareStage2Radius.compare_compensated_radius_upper.
(** TriangleStage3Liveness.v: the ray–triangle stage 3 (value_ev, ev_sign; tc_sign_b in the cascade) certifies on
    integer inputs of magnitude ≤ 2^15; the twin cascades decide before the exact stage there; rays through an
    edge and a vertex where stages 1 and 2 do not; k = 17 gives a two-component expansion *)
From Raykernel Require TriangleStage3Liveness.
Definition twin_results_triangle_stage3_liveness :=
  (TriangleStage3Liveness.value_ev_int_single,
   TriangleStage3Liveness.value_ev_int_certain,
   TriangleStage3Liveness.tie_vector_int_certain,
   TriangleStage3Liveness.normal_vector_int_certain,
   TriangleStage3Liveness.tc_sign_int_live,
   TriangleStage3Liveness.tc_classify_int_live,
   TriangleStage3Liveness.tc_relation_int_live,
   TriangleStage3Liveness.tc_intersect_int_live,
   TriangleStage3Liveness.tri_stage3_live_edge,
   TriangleStage3Liveness.tri_stage3_live_vertex).
Definition twin_results_triangle_stage3_liveness_2 :=
  (TriangleStage3Liveness.live_inputs_in_class,
   TriangleStage3Liveness.tri_stage3_k17_two_components).
Goal True. idtac "@@ value_ev_int_single value_ev_int_certain tie_vector_int_certain normal_vector_int_certain tc_sign_int_live tc_classify_int_live tc_relation_int_live tc_intersect_int_live tri_stage3_live_edge tri_stage3_live_vertex live_inputs_in_class tri_stage3_k17_two_components". Abort.
Print Assumptions twin_results_triangle_stage3_liveness.
Print Assumptions twin_results_triangle_stage3_liveness_2.
(** CompareStage3Liveness.v: stage 3 of nearest_hit's comparison (compare_quotients_expansion) certifies on
    integer queries (components of magnitude ≤ 2^11, or ≤ 2^24 with cross products ≤ 2^51, or ≤ 2^24 on
    exact ties), so compare_hit_distances decides before the exact stage; ties only stage 3 of the three
    certifies *)
From Raykernel Require CompareStage3Liveness.
Definition twin_results_compare_stage3_liveness :=
  (CompareStage3Liveness.compare_quotients_expansion_single,
   CompareStage3Liveness.compare_stage3_int_live_gen,
   CompareStage3Liveness.compare_stage3_int_live,
   CompareStage3Liveness.compare_hit_distances_int_live,
   CompareStage3Liveness.compare_hit_distances_int_correct,
   CompareStage3Liveness.compare_stage3_tie_example,
   CompareStage3Liveness.compare_stage3_tie_in_class,
   CompareStage3Liveness.compare_quotients_expansion_int_tie,
   CompareStage3Liveness.compare_stage3_int_tie,
   CompareStage3Liveness.compare_hit_distances_int_tie_live,
   CompareStage3Liveness.compare_hit_distances_int_tie_correct,
   CompareStage3Liveness.compare_stage3_tie2_example,
   CompareStage3Liveness.compare_stage3_tie2_in_class,
   CompareStage3Liveness.compare_stage3_uncertain_example,
   CompareStage3Liveness.compare_stage3_uncertain_in_class).
Goal True. idtac "@@ compare_quotients_expansion_single compare_stage3_int_live_gen compare_stage3_int_live compare_hit_distances_int_live compare_hit_distances_int_correct compare_stage3_tie_example compare_stage3_tie_in_class compare_quotients_expansion_int_tie compare_stage3_int_tie compare_hit_distances_int_tie_live compare_hit_distances_int_tie_correct compare_stage3_tie2_example compare_stage3_tie2_in_class compare_stage3_uncertain_example compare_stage3_uncertain_in_class". Abort.
Print Assumptions twin_results_compare_stage3_liveness.
(** CompareStage2Liveness.v: the second half of the liveness of stage 2 of nearest_hit's comparison: the error of
    hi + lo (model), the class on which the twin of compare_quotients_compensated is certain,
    compare_hit_distances returning by stage 2 at the latest on it, computed witnesses and the sharpness
    of the class's constants *)
From Raykernel Require CompareStage2Liveness.
Definition twin_results_compare_liveness3 :=
  (CompareStage2Liveness.compare_compensated_error_model,
   CompareStage2Liveness.compare_compensated_live_model,
   CompareStage2Liveness.compare_compensated_live,
   CompareStage2Liveness.compare_hit_distances_stage2_live,
   CompareStage2Liveness.compare_compensated_live_example,
   CompareStage2Liveness.compare_hit_distances_stage2_example,
   CompareStage2Liveness.compare_compensated_k1_fails,
   CompareStage2Liveness.compare_compensated_k2_fails,
   CompareStage2Liveness.compare_hit_distances_stage2_example_in_class,
   CompareStage2Liveness.compare_compensated_live_exact).
Goal True. idtac "@@ compare_compensated_error_model compare_compensated_live_model compare_compensated_live compare_hit_distances_stage2_live compare_compensated_live_example compare_hit_distances_stage2_example compare_compensated_k1_fails compare_compensated_k2_fails compare_hit_distances_stage2_example_in_class compare_compensated_live_exact". Abort.
Print Assumptions twin_results_compare_liveness3.
Definition twin_results_compare_liveness3_exact :=
  (CompareStage2Liveness.compare_hit_distances_stage2_live_exact, CompareStage2Liveness.cross_dd_close).
Goal True. idtac "@@ compare_hit_distances_stage2_live_exact cross_dd_close". Abort.
Print Assumptions twin_results_compare_liveness3_exact.
(** CompareStage2InputsLiveness.v: stage 2 of nearest_hit's comparison decides on a class stated in the ray's and planes'
    inputs (coordinates ≤ 2^180, the bound in Σ|(p_i − o_i)·n_i| and Σ|d_i·n_i|), and an input in it *)
From Raykernel Require CompareStage2InputsLiveness.
Definition twin_results_compare_liveness4 :=
  (CompareStage2InputsLiveness.compare_hit_distances_stage2_live_inputs,
   CompareStage2InputsLiveness.stage2_num_facts,
   CompareStage2InputsLiveness.stage2_den_facts,
   CompareStage2InputsLiveness.compare_hit_distances_stage2_inputs_example_in_class,
   CompareStage2InputsLiveness.compare_hit_distances_stage2_live_inputs_simple,
   CompareStage2InputsLiveness.compare_hit_distances_stage2_inputs_simple_example).
Goal True. idtac "@@ compare_hit_distances_stage2_live_inputs stage2_num_facts stage2_den_facts compare_hit_distances_stage2_inputs_example_in_class compare_hit_distances_stage2_live_inputs_simple compare_hit_distances_stage2_inputs_simple_example". Abort.
Print Assumptions twin_results_compare_liveness4.
(** orient/: the orientation filters of the point-in-mesh query (mesh_predicates.hpp): soundness over the model
    and for every bit pattern, the compiled constants, and liveness with its witnesses *)
From Raykernel Require OrientFilter OrientTwins OrientLiveness.
Definition orient_results :=
  (OrientFilter.orient2d_filter_sound,
   OrientFilter.orient2d_error,
   OrientFilter.orient3d_filter_sound,
   OrientFilter.orient3d_error,
   OrientFilter.orient3d_error_bounds,
   OrientTwins.orient2d_filter_twin_sound,
   OrientTwins.orient3d_filter_twin_sound,
   OrientTwins.orient2d_filter_twin_model,
   OrientTwins.orient3d_filter_twin_model,
   ConstantsCpp.cpp_orient3d_filter_relative).
Goal True. idtac "@@ orient2d_filter_sound orient2d_error orient3d_filter_sound orient3d_error orient3d_error_bounds orient2d_filter_twin_sound orient3d_filter_twin_sound orient2d_filter_twin_model orient3d_filter_twin_model cpp_orient3d_filter_relative". Abort.
Print Assumptions orient_results.
Definition orient_liveness :=
  (OrientLiveness.orient2d_filter_live,
   OrientLiveness.orient2d_filter_b_fwd,
   OrientLiveness.orient2d_filter_twin_live,
   OrientLiveness.orient3d_filter_live,
   OrientLiveness.orient2d_live_witness,
   OrientLiveness.orient2d_live_witness_in_class,
   OrientLiveness.orient2d_uncertain_witness,
   OrientLiveness.orient3d_live_witness,
   OrientLiveness.orient3d_range_witness).
Goal True. idtac "@@ orient2d_filter_live orient2d_filter_b_fwd orient2d_filter_twin_live orient3d_filter_live orient2d_live_witness orient2d_live_witness_in_class orient2d_uncertain_witness orient3d_live_witness orient3d_range_witness". Abort.
Print Assumptions orient_liveness.
(** box/RayBoxTwins.v: the BVH's ray–box test over the bits (make_slabs, ray_box_axis, ray_box_entry), tied to
    RayBox.v and sound in case B *)
From Raykernel Require RayBoxTwins.
Definition box_twin_results :=
  (RayBoxTwins.near_bound_twin_model,
   RayBoxTwins.far_bound_twin_model,
   RayBoxTwins.ray_box_axis_twin_model,
   RayBoxTwins.make_slab_case_b,
   RayBoxTwins.near_bound_twin_sound,
   RayBoxTwins.far_bound_twin_sound,
   RayBoxTwins.ray_box_axis_twin_sound,
   RayBoxTwins.ray_box_axis_nan,
   RayBoxTwins.ray_box_entry_twin_sound,
   RayBoxTwins.ray_box_entries8_twin_sound).
Goal True. idtac "@@ near_bound_twin_model far_bound_twin_model ray_box_axis_twin_model make_slab_case_b near_bound_twin_sound far_bound_twin_sound ray_box_axis_twin_sound ray_box_axis_nan ray_box_entry_twin_sound ray_box_entries8_twin_sound". Abort.
Print Assumptions box_twin_results.
Definition box_twin_constants :=
  (ConstantsCpp.cpp_ray_box_near_factor,
   ConstantsCpp.cpp_ray_box_far_factor,
   ConstantsCpp.cpp_ray_box_absolute,
   ConstantsCpp.cpp_ray_box_min_direction,
   ConstantsCpp.cpp_ray_box_max_direction,
   ConstantsCpp.cpp_ray_box_max_parameter).
Goal True. idtac "@@ cpp_ray_box_near_factor cpp_ray_box_far_factor cpp_ray_box_absolute cpp_ray_box_min_direction cpp_ray_box_max_direction cpp_ray_box_max_parameter". Abort.
Print Assumptions box_twin_constants.
(** core/: the rounding of a quotient at its rounding boundaries (quotient_boundary.hpp): the decision over the
    reals, the twin's soundness, liveness on ties *)
From Raykernel Require MidpointRounding QuotientBoundary.
Definition boundary_results :=
  (MidpointRounding.rn_between_midpoints,
   MidpointRounding.rn_at_midpoint_above,
   MidpointRounding.rn_at_midpoint_below,
   MidpointRounding.boundary_decision_correct,
   MidpointRounding.b754_canonical,
   QuotientBoundary.side_of_midpoint_sound,
   QuotientBoundary.round_quotient_at_boundaries_sound,
   QuotientBoundary.round_quotient_near_sound,
   QuotientBoundary.round_quotient_at_boundaries_tie_even,
   QuotientBoundary.round_quotient_at_boundaries_tie_odd,
   QuotientBoundary.round_quotient_at_boundaries_between).
Goal True. idtac "@@ rn_between_midpoints rn_at_midpoint_above rn_at_midpoint_below boundary_decision_correct b754_canonical side_of_midpoint_sound round_quotient_at_boundaries_sound round_quotient_near_sound round_quotient_at_boundaries_tie_even round_quotient_at_boundaries_tie_odd round_quotient_at_boundaries_between". Abort.
Print Assumptions boundary_results.
(** sphere/: the side of a ray–sphere root against a rounding boundary (ray_sphere_formula.hpp, root_side_of):
    sign(t_k − m) from the signs of q(m) and of the slope A·m + B, for every real m, A > 0, D ≥ 0 *)
From Raykernel Require SphereRoots.
Definition main_results_17 :=
  (@SphereRoots.root_side_of_smaller_correct,
   @SphereRoots.root_side_of_larger_correct).
Goal True. idtac "@@ root_side_of_smaller_correct root_side_of_larger_correct". Abort.
Print Assumptions main_results_17.
(** core/: the compression of an expansion (expansion.hpp, ExpansionBuilder::compress, which ray_sphere_stages.hpp
    applies to A, B, C): Σh = Σe when h is finite, and h fits in e's capacity *)
From Raykernel Require ExpansionCompress.
Definition main_results_18 :=
  (@ExpansionCompress.compress_gen_exact,
   @ExpansionCompress.compress_length).
Goal True. idtac "@@ compress_gen_exact compress_length". Abort.
Print Assumptions main_results_18.
(** sphere/: the expansion stage of the ray–sphere query (ray_sphere_stages.hpp, sphere_abc_expansions,
    sphere_expansions and sphere_root_side; expansion.hpp, ExpansionBuilder::sign_or_compressed): A, B, C, D exact when the builder
    says exact, the two-try sign sound, the side of a root sound *)
From Raykernel Require SphereStages.
Definition main_results_19 :=
  (@SphereStages.sphere_abc_expansions_exact,
   @SphereStages.sphere_expansions_exact,
   @SphereStages.sphere_abc_expansions_length,
   @SphereStages.sphere_expansions_length,
   @SphereStages.compress_finite_or_uncertain,
   @SphereStages.sphere_sign_or_compressed_sound,
   @SphereStages.sphere_root_side_sound,
   @SphereStages.sphere_root_side_expansions_sound).
Goal True. idtac "@@ sphere_abc_expansions_exact sphere_expansions_exact sphere_abc_expansions_length sphere_expansions_length compress_finite_or_uncertain sphere_sign_or_compressed_sound sphere_root_side_sound sphere_root_side_expansions_sound". Abort.
Print Assumptions main_results_19.
(** sphere/: stage 1 of the ray–sphere query (ray_sphere_filter.hpp, sphere_filter): |Ĉ − C| ≤ E_C and
    |D̂ − D| ≤ E_D for every binary64 input, so a certain sign of C or D is the exact sign *)
From Raykernel Require SphereFilter.
Definition main_results_20 :=
  (@SphereFilter.sphere_c_encloses,
   @SphereFilter.sphere_filter_c_sound,
   @SphereFilter.sphere_d_encloses,
   @SphereFilter.sphere_filter_d_sound,
   @SphereFilter.square_magnitude_value,
   @SphereFilter.d_value_error,
   @SphereFilter.floor_covers,
   @SphereFilter.d_bound_lower).
Goal True. idtac "@@ sphere_c_encloses sphere_filter_c_sound sphere_d_encloses sphere_filter_d_sound square_magnitude_value d_value_error floor_covers d_bound_lower". Abort.
Print Assumptions main_results_20.
(** core/: the order of two roundings to nearest (nearest/sphere_candidate.hpp, compare_candidates: a sphere's
    correctly rounded root against another candidate's RN(t)): RN(a) < RN(b) implies a < b, for any tie rule
    and with IEEE overflow to ±inf; equal roundings decide nothing *)
From Raykernel Require RoundOrder.
Definition main_results_21 :=
  (@RoundOrder.rn_strict_order,
   @RoundOrder.rn_equal_or_ordered,
   @RoundOrder.rn_compare_distinct,
   @RoundOrder.rne_strict_order,
   @RoundOrder.rne_compare_distinct,
   @RoundOrder.binary_normalize_ieee_rn,
   @RoundOrder.ieee_rn_strict_order).
Goal True. idtac "@@ rn_strict_order rn_equal_or_ordered rn_compare_distinct rne_strict_order rne_compare_distinct binary_normalize_ieee_rn ieee_rn_strict_order". Abort.
Print Assumptions main_results_21.
(** sphere/: spawning from a sphere (sphere/sphere_spawn.cpp, spawn): an accepted origin's guarantee — leaving
    outward (C > 0, B ≥ 0) no root t ≥ 0; leaving inward (C < 0) exactly one, positive — and the steps' algebra *)
From Raykernel Require SphereSpawn.
Definition main_results_22 :=
  (@SphereSpawn.spawn_outward_never_hits,
   @SphereSpawn.spawn_inward_one_exit,
   @SphereSpawn.spawn_axis_leaving_grows,
   @SphereSpawn.spawn_axis_step_sign,
   @SphereSpawn.spawn_axis_side).
Goal True. idtac "@@ spawn_outward_never_hits spawn_inward_one_exit spawn_axis_leaving_grows spawn_axis_step_sign spawn_axis_side". Abort.
Print Assumptions main_results_22.
(** sphere/: the roots' boundary filter (sphere/ray_sphere_boundary_filter.hpp, sphere_boundary_filter): at a rounding
    boundary m = (x + y)/2, |4q(m) − z| ≤ E_q for the value's unrounded z and |ŝ − 2(A·m + B)| ≤ E_s, so a certain
    sign of q(m) or of the slope is the exact one, for every binary64 input (the slope's absolute term μ_s = 2^-1070
    covers the products' underflow; without it d = (2^-1074, −2^-1074, −2^-1074) was certified wrong) *)
From Raykernel Require SphereBoundaryFilter.
Definition main_results_23 :=
  (@SphereBoundaryFilter.sphere_boundary_q_encloses,
   @SphereBoundaryFilter.sphere_boundary_q_sound,
   @SphereBoundaryFilter.sphere_boundary_slope_encloses,
   @SphereBoundaryFilter.sphere_boundary_slope_sound).
Goal True. idtac "@@ sphere_boundary_q_encloses sphere_boundary_q_sound sphere_boundary_slope_encloses sphere_boundary_slope_sound". Abort.
Print Assumptions main_results_23.
(** core/: interval arithmetic widened by one ulp (core/interval.hpp: next_up, next_down, operator+, operator-,
    operator*, square, divide_nonnegative, interval_sign): pred(RN z) ≤ z ≤ succ(RN z), and each computed interval
    holds the exact result, over the reals for all ends, and on IEEE doubles for finite operand ends with overflow
    to ±inf (of the operations and of the widening) included *)
From Raykernel Require IntervalWidening.
Definition main_results_24 :=
  (@IntervalWidening.widen_encloses,
   @IntervalWidening.interval_add_encloses,
   @IntervalWidening.interval_sub_encloses,
   @IntervalWidening.interval_neg_encloses,
   @IntervalWidening.interval_mul_encloses,
   @IntervalWidening.interval_square_encloses,
   @IntervalWidening.interval_div_encloses,
   @IntervalWidening.interval_sign_sound).
Goal True. idtac "@@ widen_encloses interval_add_encloses interval_sub_encloses interval_neg_encloses interval_mul_encloses interval_square_encloses interval_div_encloses interval_sign_sound". Abort.
Print Assumptions main_results_24.
Definition main_results_25 :=
  (@IntervalWidening.ieee_add_encloses,
   @IntervalWidening.ieee_sub_encloses,
   @IntervalWidening.ieee_neg_encloses,
   @IntervalWidening.ieee_mul_encloses,
   @IntervalWidening.ieee_square_encloses,
   @IntervalWidening.ieee_div_encloses,
   @IntervalWidening.ieee_sign_sound).
Goal True. idtac "@@ ieee_add_encloses ieee_sub_encloses ieee_neg_encloses ieee_mul_encloses ieee_square_encloses ieee_div_encloses ieee_sign_sound". Abort.
Print Assumptions main_results_25.
(** sphere/: whether a sphere meets an open segment (ray_sphere_formula.hpp, segment_root_inside, on the exact signs;
    ray_sphere_cascade.cpp, segment_meets_sphere's two shortcuts on the filter's signs of C_p and C_q): true exactly
    when a root of A·t² + 2B·t + C lies in (0, 1); C_p·C_q < 0 gives one; C_p, C_q < 0 give none on [0, 1] *)
From Raykernel Require SphereSegment.
Definition main_results_26 :=
  (@SphereSegment.segment_root_inside_correct,
   @SphereSegment.segment_ends_opposite_meet,
   @SphereSegment.segment_ends_inside_clear).
Goal True. idtac "@@ segment_root_inside_correct segment_ends_opposite_meet segment_ends_inside_clear". Abort.
Print Assumptions main_results_26.
(** spawn/: the certified fast path of spawn (spawn/spawn_certified.cpp): midpoint_offset's enclosure of
    x + y − 2·o, the side of the hit point o + (num/den)·d against (x + y)/2 from sign(den)·sign(Δ), and
    round_binary32_from_binary64 (binary32 through binary64: RN32(x) = RN32(RN64(x)) off the binary32
    midpoints; at one, the side of x against it decides) *)
From Raykernel Require SpawnRounding.
Definition main_results_27 :=
  (@SpawnRounding.midpoint_offset_encloses,
   @SpawnRounding.midpoint_side_sign,
   @SpawnRounding.binary32_through_binary64,
   @SpawnRounding.binary32_midpoint_side).
Goal True. idtac "@@ midpoint_offset_encloses midpoint_side_sign binary32_through_binary64 binary32_midpoint_side". Abort.
Print Assumptions main_results_27.
(** spawn/: affine_enclosure (spawn/spawn_certified.cpp): an enclosure of o·D + d·N from enclosures of D and N,
    which round_quotient rounds each coordinate of the hit point (o_k·den + d_k·num)/den from *)
From Raykernel Require SpawnAffine.
Definition main_results_28 := (@SpawnAffine.affine_enclosure_sound).
Goal True. idtac "@@ affine_enclosure_sound". Abort.
Print Assumptions main_results_28.
(** triangle/: the open segment from p to q against a triangle (occlusion/segment_triangle.hpp,
    segment_meets_triangle): with S(x) = (x − a)·((b − a) × (c − a)), the §6 values of the line p + t·(q − p) are
    num = −S(p), den = S(q) − S(p), π(u, v) = orient3d(p, q, u, v), and S(x) = orient3d(a, x, b, c); t = num/den
    lies in (0, 1) exactly when S(p), S(q) are nonzero with opposite signs, and then num, den have S(q)'s sign *)
From Raykernel Require SegmentSigns.
Definition main_results_29 :=
  (@SegmentSigns.segment_num_is_side,
   @SegmentSigns.segment_den_is_difference,
   @SegmentSigns.segment_t_in_open_unit,
   @SegmentSigns.segment_crossing_signs,
   @SegmentSigns.segment_plane_test_correct,
   @SegmentSigns.segment_side_is_orient3d,
   @SegmentSigns.segment_pi_is_orient3d,
   @SegmentSigns.orient3d_is_exact).
Goal True. idtac "@@ segment_num_is_side segment_den_is_difference segment_t_in_open_unit segment_crossing_signs segment_plane_test_correct segment_side_is_orient3d segment_pi_is_orient3d orient3d_is_exact". Abort.
Print Assumptions main_results_29.
(** spawn/: the twins of midpoint_offset and affine_enclosure (spawn/spawn_certified.hpp; runner group spawn): for
    every bit pattern, finite results mean finite inputs and the values of SpawnRounding.v's and SpawnAffine.v's
    models, so the enclosures hold for the bits *)
From Raykernel Require SpawnTwins.
Definition main_results_30 :=
  (@SpawnTwins.midpoint_offset_twin_sound,
   @SpawnTwins.affine_enclosure_twin_sound).
Goal True. idtac "@@ midpoint_offset_twin_sound affine_enclosure_twin_sound". Abort.
Print Assumptions main_results_30.
(** core/: the escalation policy of every certified predicate (core/escalation.hpp): a certain answer is a stage's
    (so the exact sign when every stage is sound), the first certain one, the stages up to it asked, the trace
    the latest stage asked; [exact_sign] asks its exact stage exactly when no stage certified; and the plane
    cascade's certified_signs (PlaneCascadeTwins.v's twin) is that escalation of den, then num *)
From Raykernel Require Escalation.
Definition main_results_31 :=
  (@Escalation.escalate_sound,
   @Escalation.escalate_certifies,
   @Escalation.escalate_first_certain,
   @Escalation.escalate_trace,
   @Escalation.exact_sign_reaches_exact,
   @PlaneCascadeTwins.certified_signs_b_escalate).
Goal True. idtac "@@ escalate_sound escalate_certifies escalate_first_certain escalate_trace exact_sign_reaches_exact certified_signs_b_escalate". Abort.
Print Assumptions main_results_31.
(** triangle/: a tie-break component d_j·e_k − d_k·e_j from two TwoProduct pairs (ray_triangle_stages.hpp,
    product_difference_sign): the lexicographic comparison of the exact pairs is the exact sign *)
From Raykernel Require TieBreakPairs.
Definition main_results_32 :=
  (@TieBreakPairs.pair_difference_sign).
Goal True. idtac "@@ pair_difference_sign". Abort.
Print Assumptions main_results_32.
