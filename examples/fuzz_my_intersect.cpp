// Example (b): a libFuzzer harness for your ray code, built on raykernel's fuzz decoder and reference check.
//
// decode_fuzz_query turns any byte string into a query: raw doubles (every bit pattern, possibly invalid
// input) or, when the first byte is ≥ 0x80, one of raykernel's hard-query constructions driven by the
// bytes (near-parallel, near-coplanar, ties, subnormals, ...). Valid queries must get the exact relation
// from my::ray_plane, and a t within 4 ulps. A mismatch prints the reference check's report and aborts,
// so libFuzzer saves the input (crash-<sha1>); the replay program (replay_main.cpp) runs saved inputs
// without libFuzzer:
//
//   ./fuzz_my_intersect -max_total_time=60 corpus/       # clang -fsanitize=fuzzer build
//   ./fuzz_my_intersect_replay crash-1234abcd...          # any compiler
#include "my_ray_code.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_fuzz_decoder.hpp>
#include <raykernel/testkit/plane_reference_check.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>

// Whether my::ray_plane answers the query encoded by `bytes` correctly; if not, `report` says how.
bool my_intersect_matches_raykernel(std::span<const std::uint8_t> bytes, std::string& report) {
  const raykernel::testkit::FuzzQuery f = raykernel::testkit::decode_fuzz_query(bytes);
  const raykernel::Ray& ray = f.query.ray;
  const raykernel::Plane& plane = f.query.plane;
  // Invalid input (NaN, ±inf, a zero vector): raykernel has no answer; my::ray_plane promises nothing
  // either, but must not crash (the sanitizers watch that).
  if (raykernel::validate(ray, plane)) {
    (void)my::ray_plane(ray, plane);
    return true;
  }
  const raykernel::testkit::ReferenceCheck check =
      raykernel::testkit::check_against_reference(f.query, my::ray_plane(ray, plane), 4);
  if (check.passed()) return true;
  report =
      "input: " + (f.kind ? "hard query, kind " + std::string(raykernel::testkit::to_string(*f.kind)) : "raw doubles") +
      "\n" + check.report();
  return false;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string report;
  if (!my_intersect_matches_raykernel({data, size}, report)) {
    std::fputs(report.c_str(), stderr);
    std::abort();  // libFuzzer saves this input as crash-<sha1>
  }
  return 0;
}
