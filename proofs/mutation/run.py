#!/usr/bin/env python3
"""Mutation check of the ties between the certified C++ and the proofs (proofs/README.md, "Mutations").

Applies each mutation of MUTATIONS below, one at a time, to a copy of the repository, rebuilds, and reports
which of three checks catch it:

  runner  the differential runner: the compiled routines (every variant this CPU runs) against the Coq twins
          (proofs/twins/; the twins are rebuilt and rerun when the mutation touches error_bounds.hpp, which
          feeds them; otherwise the clean run's twin outputs are reused, the twins being unchanged)
  tests   the C++ test suite (ctest, every test without the label `proofs`)
  proofs  the proof-side checks: the Coq build (`proofs`: the generated constants against Constants.v) and
          the ctest tests labelled `proofs` other than the runner (constants match, constants in bounds::,
          assumptions, ...)

Every mutation that changes behaviour must be caught by at least one; the script exits 1 otherwise. It is
slow (each mutation rebuilds the kernel, the tests and five drivers): run it by hand, not in CI.

    /usr/bin/python3 proofs/mutation/run.py [--workdir DIR] [--count N] [--only NAME,...] [--tests REGEX]
                                            [--in-place BUILD_DIR]

The copy and its build live in --workdir (default /tmp/raykernel-mutation); the repository is not touched.
--in-place mutates the repository's own files (restored after each mutation) and uses an existing,
configured build directory (with RAYKERNEL_BUILD_PROOFS=ON), which saves the clean build. --tests limits the
C++ tests to a ctest regex (the whole suite by default).
"""

import argparse
import os
import shutil
import subprocess
import sys
import time

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# (name, file, old, new, what it changes). `old` must occur exactly once in the file.
MUTATIONS = [
    ("reassociate_lo", "kernel/src/core/dot3_compensated.hpp",
     "const V lo = ((g[0] + g[1]) + g[2]) + (s2.lo + s3.lo);",
     "const V lo = (g[0] + (g[1] + g[2])) + (s2.lo + s3.lo);",
     "compensated_dot3: reassociate the sum of the low parts"),
    ("reassociate_value", "kernel/src/core/dot3_filter.hpp",
     "r.value = (r.product[0] + r.product[1]) + r.product[2];",
     "r.value = r.product[0] + (r.product[1] + r.product[2]);",
     "dot3_rounded: reassociate the stage-1 value"),
    ("drop_term", "kernel/src/core/dot3_compensated.hpp",
     "const V lo = ((g[0] + g[1]) + g[2]) + (s2.lo + s3.lo);",
     "const V lo = ((g[0] + g[1]) + g[2]) + s2.lo;",
     "compensated_dot3: drop the second TwoSum's error from lo"),
    ("drop_guard", "kernel/src/core/quotient_rounding.hpp",
     "both(abs_D >= bounds::divisor_min_magnitude, abs_D <= bounds::divisor_max_magnitude);",
     "abs_D >= bounds::divisor_min_magnitude;",
     "prepare_divisor: drop the guard |D| ≤ 2^1000"),
    ("drop_absolute", "kernel/src/core/dot3_filter.hpp",
     "return relative_constant * r.magnitude + bounds::filter_absolute;",
     "return relative_constant * r.magnitude;",
     "dot3_filter_bound: drop the absolute term 3μ of the bound"),
    ("quotient_residual", "kernel/src/core/quotient_rounding.hpp",
     "const V r2 = fma(-q0, den.lo, N.lo);",
     "const V r2 = fma(q0, den.lo, N.lo);",
     "round_quotient: a wrong sign in the second residual"),
    ("half_gap_shift", "kernel/src/core/quotient_rounding.hpp",
     "const Bits shift = (Bits{} + 53)",
     "const Bits shift = (Bits{} + 52)",
     "half_gap_to_nearer_neighbour: twice the half gap"),
    ("quotient_test_factor", "kernel/src/core/quotient_rounding.hpp",
     "return {q, both(in_range, (x + y) * quotient_test_factor < h * abs_D)};",
     "return {q, both(in_range, (x + y) < h * abs_D)};",
     "round_quotient: the test without its factor 1 + 2^-45"),
    ("exact_form_for_num", "kernel/src/plane/ray_plane_stages.hpp",
     "return compensated_dot3(q.diff, low, q.n, q.num);",
     "return compensated_dot3_exact(q.diff, q.n, q.num);",
     "num_compensated: the α = 0 form (the TwoDiff low parts dropped)"),
    ("comparison_ge", "kernel/src/core/enclosure.hpp",
     "return sign_lanes(v > twice_radius, v < -twice_radius);",
     "return sign_lanes(v >= twice_radius, v < -twice_radius);",
     "enclosure_sign_lanes: > becomes >="),
    ("two_sum_operand", "kernel/src/core/eft.hpp",
     "const V a_roundoff = a - a_virtual;",
     "const V a_roundoff = a_virtual - a;",
     "two_sum: a wrong sign in the error"),
    ("refined_chain_short", "kernel/src/core/dot3_compensated.hpp",
     "for (int j = 1; j < 8; ++j) {",
     "for (int j = 1; j < 7; ++j) {",
     "compensated_dot3_refined: the TwoSum chain skips w_2"),
    ("compare_delta_sign", "kernel/src/nearest/compare_quotients.hpp",
     "const L delta = p - q;            // δ = P ⊖ Q",
     "const L delta = q - p;            // δ = P ⊖ Q",
     "compare_quotients_filter: δ = Q − P"),
    ("swap_constants", "kernel/src/core/error_bounds.hpp",
     "inline constexpr double filter_den_relative = 0x1.8000000000004p-52;  // (3 + 16u)u\n"
     "inline constexpr double filter_num_relative = 0x1.0000000000004p-51;  // (4 + 32u)u",
     "inline constexpr double filter_den_relative = 0x1.0000000000004p-51;  // (3 + 16u)u\n"
     "inline constexpr double filter_num_relative = 0x1.8000000000004p-52;  // (4 + 32u)u",
     "error_bounds.hpp: swap the den and num filter constants"),
    ("constant_smaller", "kernel/src/core/error_bounds.hpp",
     "inline constexpr double compensated_relative = 0x1p-101;",
     "inline constexpr double compensated_relative = 0x1p-103;",
     "error_bounds.hpp: the stage-2 constant 4 times too small"),
    ("call_site_fast_path", "kernel/src/plane/ray_plane_stages.hpp",
     "return dot3_filter_lanes(q.num, bounds::filter_num_relative);",
     "return dot3_filter_lanes(q.num, bounds::filter_den_relative);",
     "num_filter_sign (fast_answer on the terms, the batch lanes): num filtered with den's constant"),
    ("call_site_pair", "kernel/src/plane/ray_plane_stages.hpp",
     "const Mask2 filter = dot3_filter_lanes(stage1, Lanes2{bounds::filter_den_relative, bounds::filter_num_relative});",
     "const Mask2 filter = dot3_filter_lanes(stage1, Lanes2{bounds::filter_num_relative, bounds::filter_den_relative});",
     "fast_answer(o, d, p, n): the Lanes2 constants swapped"),
    ("call_site_cascade", "kernel/src/plane/ray_plane_cascade.hpp",
     "return dot3_filter(q_.num, bounds::filter_num_relative, zero);",
     "return dot3_filter(q_.num, bounds::filter_den_relative, zero);",
     "RayPlaneCascade::num_filter: num filtered with den's constant"),
    ("call_site_nearest", "kernel/src/nearest/plane_candidate.hpp",
     "return filter_enclosure(num, bounds::filter_num_relative);",
     "return filter_enclosure(num, bounds::filter_den_relative);",
     "compare_hit_distances (HitCandidate::num_filter): num's enclosure with den's constant"),
    ("low_part_dropped", "kernel/src/plane/ray_plane_stages.hpp",
     "for (int i = 0; i < 3; ++i) low[i] = two_diff(q.p[i], q.o[i]).lo;",
     "for (int i = 0; i < 3; ++i) low[i] = V{};",
     "difference_low_parts: num's stage 2 without the TwoDiff low parts"),
    ("sum_first_operand", "kernel/src/core/expansion.hpp",
     "const DoubleDouble s = two_sum(take_smaller(), q);",
     "const DoubleDouble s = two_sum(take_smaller(), -q);",
     "ExpansionBuilder::sum: the smallest component's sign flipped"),
    ("product_guard", "kernel/src/core/expansion.hpp",
     "(std::fabs(p) >= bounds::exact_product_threshold)",
     "(std::fabs(p) >= 0x1p-1000)",
     "note_product: a weaker guard (TwoProduct may be inexact)"),
    ("sign_unchecked", "kernel/src/core/expansion.hpp",
     "if (lower + lower < std::fabs(top)) return top > 0 ? Sign::positive : Sign::negative;",
     "if (lower < std::fabs(top)) return top > 0 ? Sign::positive : Sign::negative;",
     "Expansion::sign: the top component decides when it exceeds the others' sum, not twice it"),
    ("sign_zero", "kernel/src/core/expansion.hpp",
     "return (size == 1 && top == 0) ? Sign::zero : Sign::uncertain;",
     "return top == 0 ? Sign::zero : Sign::uncertain;",
     "Expansion::sign: zero whenever the top component is 0"),
    ("lane_abs", "kernel/src/core/lanes.hpp",
     "(Bits##W{} + 0x7fffffffffffffffULL)",
     "(Bits##W{} + 0x7ffffffffffffffeULL)",
     "Lanes4/Lanes8 abs: clears the last significand bit too"),
    ("literal_for_constant", "kernel/src/core/dot3_filter.hpp",
     "return relative_constant * r.magnitude + bounds::filter_absolute;",
     "return relative_constant * r.magnitude + 0x0.0000000000003p-1022;",
     "dot3_filter_bound: bounds::filter_absolute written as a literal (same value)"),
    # ray–triangle (kernel/src/triangle/)
    ("tri_absolute_reassociate", "kernel/src/core/det3_stages.hpp",
     "const V s = (abs(x0) + abs(x1)) + abs(x2);",
     "const V s = abs(x0) + (abs(x1) + abs(x2));",
     "det3_absolute_term (stage 1, and stage 2's radius): reassociate S = (|x0| + |x1|) + |x2|"),
    ("tri_low_reassociate", "kernel/src/core/det3_stages.hpp",
     "return {s.hi, (a.l + b.l) + s.lo, a.m + b.m};",
     "return {s.hi, a.l + (b.l + s.lo), a.m + b.m};",
     "CompensatedTerm + (stage 2): reassociate the low part (a.l + b.l) + s.lo"),
    ("tri_swap_constants", "kernel/src/core/error_bounds.hpp",
     "inline constexpr double triangle_filter_pi_relative = 0x1p-50;     // 8u\n"
     "inline constexpr double triangle_filter_num_relative = 0x1.2p-50;  // 9u\n"
     "inline constexpr double triangle_filter_den_relative = 0x1.4p-50;  // 10u",
     "inline constexpr double triangle_filter_pi_relative = 0x1.4p-50;     // 8u\n"
     "inline constexpr double triangle_filter_num_relative = 0x1.2p-50;  // 9u\n"
     "inline constexpr double triangle_filter_den_relative = 0x1p-50;  // 10u",
     "error_bounds.hpp: swap the triangle's π and den filter constants"),
    ("tri_call_site_num", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "det3_filter_lanes(num.value, bounds::triangle_filter_num_relative, num.absolute);",
     "det3_filter_lanes(num.value, bounds::triangle_filter_pi_relative, num.absolute);",
     "fast_relation: num filtered with π's constant"),
    ("tri_call_site_den", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "det3_filter_lanes(filter_view(den), bounds::triangle_filter_den_relative, absolute_d);",
     "det3_filter_lanes(filter_view(den), bounds::triangle_filter_pi_relative, absolute_d);",
     "fast_triangle_intersection: den filtered with π's constant"),
    ("tri_call_site_cascade_den", "kernel/src/triangle/ray_triangle_stages.hpp",
     "return value == value_den   ? bounds::triangle_filter_den_relative",
     "return value == value_den   ? bounds::triangle_filter_pi_relative",
     "filter_relative (the full cascade's constants): den filtered with π's constant"),
    ("tri_drop_guard", "kernel/src/core/det3_stages.hpp",
     "both(abs(t.h) <= bounds::largest_finite, abs(t.l) <= bounds::largest_finite);",
     "abs(t.h) <= bounds::largest_finite;",
     "det3_enclosure: drop the guard |l| ≤ largest finite (a finite radius for a non-finite l)"),
    ("tri_by_filter_den", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "(filter[2] != uncertain_lane) & (den_filter != uncertain_lane) &",
     "(filter[2] != uncertain_lane) &",
     "fast_triangle_intersection: the stage label by_filter does not read den's filter sign"),
    ("tri_fast_sign_flip", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "select(s1.lanes.v > bound, one, Lanes4{}) - select(s1.lanes.v < -bound, one, Lanes4{});",
     "select(s1.lanes.v < -bound, one, Lanes4{}) - select(s1.lanes.v > bound, one, Lanes4{});",
     "fast_relation: the inlined ±1.0 sign of each lane flipped"),
    ("tri_tie_break_sign", "kernel/src/triangle/ray_triangle_stages.hpp",
     "s[i] = static_cast<int>(sign);",
     "s[i] = -static_cast<int>(sign);",
     "tie_break_signs_by_expansion: the owned rule's tie-break signs flipped"),
    ("tri_drop_rounded_guard", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "const bool rounded = (!options.t || q.certain[lane_num]) &",
     "const bool rounded = true &",
     "fast_triangle_intersection: t returned without round_quotient's certainty"),
    # the full cascade's control flow (TriangleCascade, triangle_intersection_cascade): the runner's triangles5
    # (tri_cascade_intersect) and triangles6 (tri_cascade_relation), which every variant runs
    ("tri_cascade_tie_break_edge", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "[&](int k) { return tie_break(k); }",
     "[&](int k) { return tie_break((k + 1) % 3); }",
     "TriangleCascade::classify: the owned rule's tie-break asks edge (k + 1) mod 3"),
    ("tri_cascade_normal_negated", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "[&] { return normal_is_zero(); }",
     "[&] { return !normal_is_zero(); }",
     "TriangleCascade::classify: normal_is_zero negated"),
    ("tri_cascade_zero_numerator", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "certain[k] = !asked[k] || numerator_sign[k] == 0;",
     "certain[k] = !asked[k];",
     "triangle_intersection_cascade: the zero-numerator guard dropped (an exactly zero numerator rounded, not +0)"),
    ("tri_cascade_stage3_divisor", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "const Divisor divisor = prepare_divisor(den ? *den : s2.enclosure(value_den));",
     "const Divisor divisor = prepare_divisor(s2.enclosure(value_den));",
     "triangle_intersection_cascade: stage 3's divisor always from stage 2's den enclosure"),
    ("tri_cascade_stage_not_raised", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "      stage_ = later(stage_, Stage::compensated);\n      s = enclosure_sign(compensated().enclosure(v));",
     "      s = enclosure_sign(compensated().enclosure(v));",
     "TriangleCascade::sign: stage 2 deciding a sign does not raise the stage to compensated"),
    ("tri_cascade_stage3_certain", "kernel/src/triangle/ray_triangle_cascade.cpp",
     "certain[k] = e.certain;",
     "certain[k] = true;",
     "triangle_intersection_cascade: stage 3's rounding taken as certain"),
]

# Mutations that change no observable behaviour (proofs/README.md, "Triangle mutations"): reported, not counted as
# escapes. Proved on the twin of fast_triangle_intersection: tri_call_site_den for every bit pattern,
# `tri_call_site_den_same` (proofs/triangle/TriangleDenCertain.v: outside the window between the 8u and 10u bounds by
# TriangleMutations.v's `tri_call_site_den_same_unless_between`; inside it neither twin answers, since a quotient
# certified over den's divisor makes den's 10u filter certain, `den_quotient_filter_certain`);
# tri_drop_guard for every bit pattern, `tri_drop_guard_same` (proofs/triangle/TriangleStageTwoFinite.v: the
# mutated twin equals the twin, stage 2's low parts being NaN or bounded wherever h and m are finite);
# tri_by_filter_den for every bit pattern, `tri_by_filter_den_same` (proofs/triangle/TriangleDenCertain.v: an answer
# with t or a barycentric needs a quotient certified over den's divisor, which makes den's filter sign certain, so
# by_filter reads the same).
UNOBSERVABLE = {"tri_call_site_den", "tri_drop_guard", "tri_by_filter_den"}


def run(cmd, cwd, log, timeout=None):
    with open(log, "a") as out:
        out.write("$ " + " ".join(cmd) + "\n")
        out.flush()
        try:
            return subprocess.run(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            out.write("TIMEOUT\n")
            return 124


def copy_repo(src, dst):
    if os.path.exists(dst):
        shutil.rmtree(dst)
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns(".git", "build*", "*.vo", "*.glob"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--workdir", default="/tmp/raykernel-mutation")
    parser.add_argument("--count", default="100000", help="runner inputs per routine")
    parser.add_argument("--only", default="", help="comma-separated mutation names")
    parser.add_argument("--tests", default="", help="ctest regex of the C++ tests to run (default: all)")
    parser.add_argument("--targets", default="", help="comma-separated build targets per mutation (default: all)")
    parser.add_argument("--variants", default="", help="comma-separated runner variants (default: all built)")
    parser.add_argument("--skip-assumptions", action="store_true",
                        help="leave out proofs_assumptions per mutation (slow; no mutation here edits a citation)")
    parser.add_argument("--no-clean-run", action="store_true",
                        help="with --in-place: the build directory's tests already pass and its twin outputs exist")
    parser.add_argument("--in-place", default="", metavar="BUILD_DIR",
                        help="mutate the repository itself, building in this existing build directory")
    args = parser.parse_args()

    os.makedirs(args.workdir, exist_ok=True)
    log = os.path.join(args.workdir, "log.txt")
    open(log, "w").close()
    jobs = ["-j2"]
    test_filter = ["-R", args.tests] if args.tests else []
    build_targets = ["--target"] + args.targets.split(",") if args.targets else []
    proof_exclude = "proofs_twins|proofs_assumptions" if args.skip_assumptions else "proofs_twins"
    if args.in_place:
        src = REPO
        build = os.path.abspath(args.in_place)
        configure = ["cmake", "-S", src, "-B", build, "-DRAYKERNEL_TWIN_COUNT=" + args.count]
    else:
        src = os.path.join(args.workdir, "src")
        build = os.path.join(args.workdir, "build")
        copy_repo(REPO, src)
        configure = ["cmake", "-S", src, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                     "-DRAYKERNEL_BUILD_PROOFS=ON", "-DRAYKERNEL_BUILD_BENCH=OFF", "-DRAYKERNEL_TWIN_COUNT=" + args.count]
    if run(configure, args.workdir, log) != 0 or run(["cmake", "--build", build] + jobs + build_targets,
                                                     args.workdir, log) != 0:
        sys.exit("the clean copy does not build; see " + log)

    # The clean run: the twins' outputs the drivers are compared with, and all checks green.
    if not (args.in_place and args.no_clean_run) and run(["ctest", "--test-dir", build, "-j2", "--output-on-failure", "-L", "proofs"], args.workdir, log) != 0 or \
            run(["ctest", "--test-dir", build, "-j2", "--output-on-failure", "-LE", "proofs"] + test_filter,
                args.workdir, log) != 0:
        sys.exit("the clean copy fails its tests; see " + log)
    twins_dir = os.path.join(build, "proofs", "twins")
    variants = [v for v in (args.variants.split(",") if args.variants else
                            ("fma", "libm", "lanes4", "lanes8_v3", "lanes8_avx512"))
                if os.path.exists(os.path.join(twins_dir, "raykernel_twin_driver_" + v))]
    groups = sorted(f[len("inputs_"):-len(".txt")] for f in os.listdir(twins_dir) if f.startswith("inputs_"))

    def runner_catches():
        caught = []
        for v in variants:
            files = []
            # the lane drivers run the lane-templated routines: group "lanes" and the triangle groups, which
            # evaluate Lanes4 themselves (proofs/twins/CMakeLists.txt)
            for g in ([g for g in groups if g == "lanes" or g.startswith("triangles")] if v.startswith("lanes")
                      else groups):
                files += [os.path.join(twins_dir, "inputs_" + g + ".txt"), os.path.join(twins_dir, "twins_" + g + ".txt")]
            status = run([os.path.join(twins_dir, "raykernel_twin_driver_" + v)] + files, twins_dir, log)
            if status not in (0, 77):
                caught.append(v)
        return caught

    selected = [m for m in MUTATIONS if not args.only or m[0] in args.only.split(",")]
    rows = []
    for name, path, old, new, what in selected:
        started = time.time()
        target = os.path.join(src, path)
        original = open(target, encoding="utf-8").read()
        if original.count(old) != 1:
            sys.exit(f"{name}: the text to mutate occurs {original.count(old)} times in {path}")
        open(target, "w", encoding="utf-8").write(original.replace(old, new))
        with open(log, "a") as out:
            out.write(f"\n===== {name}: {what}\n")
        try:
            # -k 0: build everything that still builds (a Coq failure does not stop the C++)
            built = run(["cmake", "--build", build] + jobs + build_targets + ["--", "-k", "0"], args.workdir, log) == 0
            proofs_built = run(["cmake", "--build", build, "--target", "proofs"] + jobs, args.workdir, log) == 0
            if "error_bounds.hpp" in path:
                # the twins read the constants: rebuilt and rerun with them, if the proofs still hold
                if proofs_built:
                    run(["ctest", "--test-dir", build, "-R", "proofs_twins_(inputs|model)"], args.workdir, log)
                    runner = runner_catches()
                else:
                    runner = None  # the twins do not build: the proofs caught it
            else:
                runner = runner_catches()
            tests = run(["ctest", "--test-dir", build, "-j2", "-LE", "proofs", "--output-on-failure"] + test_filter,
                        args.workdir, log) != 0
            proof_checks = (not proofs_built) or run(
                ["ctest", "--test-dir", build, "-L", "proofs", "-E", proof_exclude, "--output-on-failure"],
                args.workdir, log) != 0
        finally:
            open(target, "w", encoding="utf-8").write(original)
        runner_text = "n/a (twins do not build)" if runner is None else ", ".join(runner)
        row = (name, what, runner_text, tests, proof_checks, built, proofs_built, int(time.time() - started))
        rows.append(row)
        print(f"{name}: runner={row[2] or '-'} tests={'caught' if tests else '-'} "
              f"proofs={'caught' if proof_checks else '-'}{'' if built else ' (build failed)'}"
              f"{'' if proofs_built else ' (Coq build failed)'} [{row[7]} s]", flush=True)
    # rebuild the clean copy so that the workdir is left consistent
    run(["cmake", "--build", build] + jobs + build_targets, args.workdir, log)

    print("\n| mutation | change | runner | C++ tests | proofs |")
    print("| --- | --- | --- | --- | --- |")
    uncaught = []
    for name, what, runner, tests, proof_checks, built, proofs_built, _ in rows:
        print(f"| `{name}` | {what} | {runner or '—'} | {'caught' if tests else '—'} | "
              f"{('caught' + ('' if proofs_built else ' (Coq build)')) if proof_checks else '—'} |")
        if (not runner or runner.startswith("n/a")) and not tests and not proof_checks:
            uncaught.append(name)
    unobservable = [name for name in uncaught if name in UNOBSERVABLE]
    if unobservable:
        print("\nnot caught, proved unobservable (proofs/README.md, the triangle mutations): " + ", ".join(unobservable))
    uncaught = [name for name in uncaught if name not in UNOBSERVABLE]
    if uncaught:
        print("\nNOT CAUGHT: " + ", ".join(uncaught))
        sys.exit(1)
    print("\nevery mutation is caught")


if __name__ == "__main__":
    main()
