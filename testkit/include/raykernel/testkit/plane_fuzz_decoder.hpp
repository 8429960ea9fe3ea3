// From fuzzer bytes to ray–plane queries: the decoder raykernel's own libFuzzer harnesses use (fuzz/), for
// harnesses that test other ray code against raykernel.
//
// Plain bytes read as 12 doubles reach every bit pattern (subnormals, signed zeros, NaN, ±inf, every
// exponent) but almost never a near-degenerate query: a random direction is essentially never within a few
// ulps of a plane. The first byte therefore selects between two modes:
//
//   byte 0 < 0x80, or an empty input: RAW. Bytes 1..96 are the components ox oy oz dx dy dz px py pz nx ny nz,
//       each the 8 bytes of a binary64 bit pattern, little-endian; missing bytes read as zero, bytes after
//       the 97th are ignored. Raw queries may be invalid input (NaN, ±inf, a zero direction or normal).
//   byte 0 ≥ 0x80: HARD QUERY. The kind is all_query_kinds[(byte 0 − 0x80) mod query_kind_count]; the
//       remaining bytes, 8 at a time little-endian, are the words make_query draws (zero once exhausted,
//       so every input decodes). Always valid input.
//
//   extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
//     const raykernel::testkit::FuzzQuery f = raykernel::testkit::decode_fuzz_query({data, size});
//     if (raykernel::validate(f.query.ray, f.query.plane)) return 0;  // or check your code rejects it too
//     check_my_ray_code_against(raykernel::intersect(f.query.ray, f.query.plane), f.query);
//     return 0;
//   }
//
// The encoders are the inverses, for writing seed corpora: decode_fuzz_query(encode_raw_fuzz_input(q)) is q
// bit for bit, and decode_fuzz_query(encode_hard_query_fuzz_input(kind, w)) is make_query(kind, w...).
#pragma once

#include <raykernel/testkit/plane_queries.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace raykernel::testkit {

// The selector byte values: below hard_query_selector raw, from it on hard queries.
inline constexpr std::uint8_t raw_selector = 0x00;
inline constexpr std::uint8_t hard_query_selector = 0x80;
// Selector byte plus 12 doubles: the size of a complete raw input.
inline constexpr std::size_t raw_fuzz_input_size = 1 + 12 * 8;

struct FuzzQuery {
  Query query;                    // the decoded query (possibly invalid input in the raw mode)
  std::optional<QueryKind> kind;  // the hard-query kind, or nothing for the raw mode
};

// Decodes any byte string (see the layout above). Deterministic, never fails.
[[nodiscard]] FuzzQuery decode_fuzz_query(std::span<const std::uint8_t> bytes);

// The 12 little-endian doubles of `bytes` (no selector byte), missing bytes as zero.
[[nodiscard]] Query decode_raw_doubles(std::span<const std::uint8_t> bytes);

// A BitSource reading `bytes` 8 at a time, little-endian, then zero words. It refers to `bytes`, which must
// outlive it.
[[nodiscard]] BitSource bit_source_from_bytes(std::span<const std::uint8_t> bytes);

// The raw-mode input (raw_fuzz_input_size bytes) that decodes to exactly `ray` and `plane`, NaN payloads
// and signed zeros included.
[[nodiscard]] std::vector<std::uint8_t> encode_raw_fuzz_input(const Ray& ray, const Plane& plane);

// The hard-query-mode input that decodes to make_query(kind, a source yielding `words` then zeros).
[[nodiscard]] std::vector<std::uint8_t> encode_hard_query_fuzz_input(QueryKind kind,
                                                                     std::span<const std::uint64_t> words);

}  // namespace raykernel::testkit
