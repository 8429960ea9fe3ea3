// raykernel::testkit: tools for testing your own ray code against raykernel (link raykernel::testkit).
//
//   hard_queries.hpp     make_query(kind, bits): near-parallel, near-coplanar, exact degeneracies, rounding
//                        ties, subnormals, huge exponents ...; SplitMix64 for seeded streams
//   reference_check.hpp  check_against_reference(query, your_answer, max_ulps): relation and t against the
//                        exact answer, ulp_distance, and a printable report
//   plane_pairs.hpp      make_plane_pair_near_tie(bits): two planes tying along a ray, or less than an ulp
//                        of t apart, with the exact order, for nearest-hit code
//   fuzz_decoder.hpp     decode_fuzz_query(bytes): fuzzer bytes to queries, for libFuzzer harnesses
//   triangle_queries.hpp make_triangle_query(kind, bits): rays through vertices and edges exactly or an ulp
//                        off, slivers, needles, degenerate, parallel and coplanar cases, ties, tiny and huge
//   triangle_reference_check.hpp  check_against_reference(triangle query, your answer, rule, max_ulps)
//   triangle_fuzz_decoder.hpp     decode_fuzz_triangle_query(bytes)
//   meshes.hpp           closed meshes with exact shared vertices: octahedron, subdivided cube, icosphere,
//                        terrain solid
//
// The RapidCheck generators are in <raykernel/testkit/plane_rapidcheck.hpp> (and triangle_rapidcheck.hpp), not included here because they need
// RapidCheck (find_package(raykernel CONFIG REQUIRED COMPONENTS testing), link `rapidcheck`).
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_fuzz_decoder.hpp>
#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/meshes.hpp>
#include <raykernel/testkit/plane_pairs.hpp>
#include <raykernel/testkit/plane_reference_check.hpp>
#include <raykernel/testkit/triangle_fuzz_decoder.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/testkit/triangle_reference_check.hpp>
