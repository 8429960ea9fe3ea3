// From fuzzer bytes to ray–triangle queries: the decoder raykernel's own triangle harness uses
// (fuzz/fuzz_triangle.cpp), for harnesses that test other ray–triangle code against raykernel. The layout
// follows fuzz_decoder.hpp's:
//
//   byte 0 < 0x80, or an empty input: RAW. Bytes 1..120 are ox oy oz dx dy dz ax ay az bx by bz cx cy cz, each
//       the 8 bytes of a binary64 bit pattern, little-endian; missing bytes read as zero, later bytes are
//       ignored. Raw queries may be invalid input (NaN, ±inf, a zero direction).
//   byte 0 ≥ 0x80: HARD QUERY. The kind is all_triangle_query_kinds[(byte 0 − 0x80) mod
//       triangle_query_kind_count]; the remaining bytes, 8 at a time little-endian, are the words
//       make_triangle_query draws (zero once exhausted). Always valid input.
//
//   extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
//     const auto f = raykernel::testkit::decode_fuzz_triangle_query({data, size});
//     if (raykernel::validate(f.query.ray, f.query.triangle)) return 0;
//     ... check your code against raykernel::intersect(f.query.ray, f.query.triangle) ...
//   }
#pragma once

#include <raykernel/testkit/plane_fuzz_decoder.hpp>
#include <raykernel/testkit/triangle_queries.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace raykernel::testkit {

// Selector byte plus 15 doubles: the size of a complete raw triangle input.
inline constexpr std::size_t raw_triangle_fuzz_input_size = 1 + 15 * 8;

struct FuzzTriangleQuery {
  TriangleQuery query;
  std::optional<TriangleQueryKind> kind;  // nothing for the raw mode
};

// Decodes any byte string (the layout above). Deterministic, never fails.
[[nodiscard]] FuzzTriangleQuery decode_fuzz_triangle_query(std::span<const std::uint8_t> bytes);

// The 15 little-endian doubles of `bytes` (no selector byte), missing bytes as zero.
[[nodiscard]] TriangleQuery decode_raw_triangle_doubles(std::span<const std::uint8_t> bytes);

// The raw-mode input that decodes to exactly `query` (NaN payloads and signed zeros included).
[[nodiscard]] std::vector<std::uint8_t> encode_raw_fuzz_input(const TriangleQuery& query);

// The hard-query-mode input that decodes to make_triangle_query(kind, a source yielding `words` then zeros).
[[nodiscard]] std::vector<std::uint8_t> encode_hard_triangle_fuzz_input(TriangleQueryKind kind,
                                                                        std::span<const std::uint64_t> words);

}  // namespace raykernel::testkit
