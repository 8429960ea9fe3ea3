// The fuzz input layout of fuzz_decoder.hpp. Byte order is assembled explicitly (little-endian), so corpora
// written on one machine decode the same everywhere.
#include <raykernel/testkit/plane_fuzz_decoder.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace raykernel::testkit {
namespace {

// The 8 bytes at `offset`, little-endian; bytes past the end read as zero.
std::uint64_t word_at(std::span<const std::uint8_t> bytes, std::size_t offset) {
  std::uint64_t w = 0;
  for (std::size_t k = 0; k < 8; ++k) {
    if (offset + k < bytes.size()) w |= std::uint64_t{bytes[offset + k]} << (8 * k);
  }
  return w;
}

void append_word(std::vector<std::uint8_t>& out, std::uint64_t w) {
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<std::uint8_t>(w >> (8 * k)));
}

}  // namespace

Query decode_raw_doubles(std::span<const std::uint8_t> bytes) {
  double c[12];
  for (std::size_t i = 0; i < 12; ++i) c[i] = std::bit_cast<double>(word_at(bytes, 8 * i));
  return {{{c[0], c[1], c[2]}, {c[3], c[4], c[5]}}, {{c[6], c[7], c[8]}, {c[9], c[10], c[11]}}};
}

BitSource bit_source_from_bytes(std::span<const std::uint8_t> bytes) {
  // std::function needs a copyable target; the cursor is shared so that copies advance together.
  auto cursor = std::make_shared<std::size_t>(0);
  return [bytes, cursor] {
    const std::uint64_t w = word_at(bytes, *cursor);
    if (*cursor < bytes.size()) *cursor += 8;
    return w;
  };
}

FuzzQuery decode_fuzz_query(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return {decode_raw_doubles(bytes), {}};
  if (bytes[0] < hard_query_selector) return {decode_raw_doubles(bytes.subspan(1)), {}};
  const std::size_t index = static_cast<std::size_t>(bytes[0] - hard_query_selector) % all_query_kinds.size();
  const QueryKind kind = all_query_kinds[index];
  return {make_query(kind, bit_source_from_bytes(bytes.subspan(1))), kind};
}

std::vector<std::uint8_t> encode_raw_fuzz_input(const Ray& ray, const Plane& plane) {
  std::vector<std::uint8_t> out{raw_selector};
  for (const Vec3& v : {ray.origin, ray.direction, plane.point, plane.normal}) {
    for (double c : {v.x, v.y, v.z}) append_word(out, std::bit_cast<std::uint64_t>(c));
  }
  return out;
}

std::vector<std::uint8_t> encode_hard_query_fuzz_input(QueryKind kind, std::span<const std::uint64_t> words) {
  std::size_t index = 0;
  while (all_query_kinds[index] != kind) ++index;
  std::vector<std::uint8_t> out{static_cast<std::uint8_t>(hard_query_selector + index)};
  for (std::uint64_t w : words) append_word(out, w);
  return out;
}

}  // namespace raykernel::testkit
