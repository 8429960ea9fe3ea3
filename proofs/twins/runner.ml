(* The twins' side of the differential runner: reads lines "routine x1 x2 ..." (inputs as unsigned
   decimal 64-bit patterns), writes "routine y1 y2 ..." with the extracted twins' outputs (doubles as
   unsigned decimal bit patterns, every NaN as 0x7ff8000000000000; signs and flags as decimal integers).
   The C++ driver (twins/driver.cpp) computes the same lines from the compiled kernel and compares.
   Usage: raykernel_twins INPUTS OUTPUTS *)
let routines : (string * (Z.t list -> Z.t list)) list = [
  ("two_sum", Twins.run_two_sum);
  ("two_diff", Twins.run_two_diff);
  ("two_prod", Twins.run_two_prod);
  ("dot3_rounded", Twins.run_dot3_rounded);
  ("filter_den", Twins.run_filter_den);
  ("filter_num", Twins.run_filter_num);
  ("compensated", Twins.run_compensated);
  ("compensated_exact", Twins.run_compensated_exact);
  ("refined", Twins.run_refined);
  ("enclosure_sign", Twins.run_enclosure_sign);
  ("tail_enclosure", Twins.run_tail_enclosure);
  ("filter_enclosure_den", Twins.run_filter_enclosure_den);
  ("filter_enclosure_num", Twins.run_filter_enclosure_num);
  ("propagated", Twins.run_propagated);
  ("compare_filter", Twins.run_compare_filter);
  ("compare_compensated", Twins.run_compare_compensated);
  ("exp_sum", Twins.run_exp_sum);
  ("exp_scale", Twins.run_exp_scale);
  ("exp_sign", Twins.run_exp_sign);
  ("round_quotient", Twins.run_round_quotient);
  ("half_gap", Twins.run_half_gap);
  ("fast_answer", Twins.run_fast_answer);
  ("fast_answer_pair", Twins.run_fast_answer_pair);
  ("fast_relation", Twins.run_fast_relation);
  ("fast_relation_pair", Twins.run_fast_relation_pair);
  ("build_expansions", Twins.run_build_expansions);
  ("compare_expansion", Twins.run_compare_expansion);
  ("quotient_boundary", Twins.run_quotient_boundary);
  ("nearest_compare", Twins.run_nearest_compare);
  ("tri_filter", Twins.run_tri_filter);
  ("tri_relation_lanes", Twins.run_tri_relation_lanes);
  ("tri_compensated", Twins.run_tri_compensated);
  ("tri_compensated_lanes", Twins.run_tri_compensated_lanes);
  ("tri_expansion", Twins.run_tri_expansion);
  ("tri_fast_relation", Twins.run_tri_fast_relation);
  ("tri_leaf_screen", Twins.run_tri_leaf_screen);
  ("tri_fast_intersect", Twins.run_tri_fast_intersect);
  ("cascade_intersect", Twins.run_cascade_intersect);
  ("cascade_relation", Twins.run_cascade_relation);
  ("tri_cascade_intersect", Twins.run_tri_cascade_intersect);
  ("tri_cascade_relation", Twins.run_tri_cascade_relation);
  ("orient2d", Twins.run_orient2d);
  ("orient3d", Twins.run_orient3d);
  ("sphere_expansions", Twins.run_sphere_expansions);
  ("sphere_abc_expansions", Twins.run_sphere_abc_expansions);
  ("sphere_root_side", Twins.run_sphere_root_side);
  ("midpoint_offset", Twins.run_midpoint_offset);
  ("affine_enclosure", Twins.run_affine_enclosure);
  ("escalate", Twins.run_escalate);
  ("ray_box_setup", Twins.run_ray_box_setup);
  ("ray_box_entry", Twins.run_ray_box_entry);
  ("ray_box_node", Twins.run_ray_box_node);
]

let () =
  if Array.length Sys.argv <> 3 then (prerr_endline "usage: raykernel_twins INPUTS OUTPUTS"; exit 2);
  let ic = open_in Sys.argv.(1) and oc = open_out Sys.argv.(2) in
  let table = Hashtbl.create 64 in
  List.iter (fun (name, f) -> Hashtbl.replace table name f) routines;
  let buf = Buffer.create (1 lsl 16) in
  let lineno = ref 0 in
  (try
     while true do
       let line = input_line ic in
       incr lineno;
       match String.split_on_char ' ' (String.trim line) with
       | [] | [""] -> ()
       | name :: args ->
         (match Hashtbl.find_opt table name with
          | None -> Printf.eprintf "line %d: unknown routine %s\n" !lineno name; exit 2
          | Some f ->
            let outputs = f (List.map Z.of_string args) in
            if outputs = [] then (Printf.eprintf "line %d: wrong arity for %s\n" !lineno name; exit 2);
            Buffer.add_string buf name;
            List.iter (fun z -> Buffer.add_char buf ' '; Buffer.add_string buf (Z.to_string z)) outputs;
            Buffer.add_char buf '\n';
            if Buffer.length buf > 1 lsl 15 then (output_string oc (Buffer.contents buf); Buffer.clear buf))
     done
   with End_of_file -> ());
  output_string oc (Buffer.contents buf);
  close_out oc
