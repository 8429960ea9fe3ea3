// The triangle fuzz input layout (triangle_fuzz_decoder.hpp); byte order assembled explicitly, little-endian.
#include <raykernel/testkit/triangle_fuzz_decoder.hpp>

#include <bit>

namespace raykernel::testkit {
namespace {

std::uint64_t word_at(std::span<const std::uint8_t> bytes, std::size_t offset) {
  std::uint64_t w = 0;
  for (std::size_t k = 0; k < 8; ++k)
    if (offset + k < bytes.size()) w |= std::uint64_t{bytes[offset + k]} << (8 * k);
  return w;
}

void append_word(std::vector<std::uint8_t>& out, std::uint64_t w) {
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<std::uint8_t>(w >> (8 * k)));
}

}  // namespace

TriangleQuery decode_raw_triangle_doubles(std::span<const std::uint8_t> bytes) {
  double c[15];
  for (std::size_t i = 0; i < 15; ++i) c[i] = std::bit_cast<double>(word_at(bytes, 8 * i));
  return {{{c[0], c[1], c[2]}, {c[3], c[4], c[5]}}, {{c[6], c[7], c[8]}, {c[9], c[10], c[11]}, {c[12], c[13], c[14]}}};
}

FuzzTriangleQuery decode_fuzz_triangle_query(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return {decode_raw_triangle_doubles(bytes), {}};
  if (bytes[0] < hard_query_selector) return {decode_raw_triangle_doubles(bytes.subspan(1)), {}};
  const std::size_t index =
      static_cast<std::size_t>(bytes[0] - hard_query_selector) % all_triangle_query_kinds.size();
  const TriangleQueryKind kind = all_triangle_query_kinds[index];
  return {make_triangle_query(kind, bit_source_from_bytes(bytes.subspan(1))), kind};
}

std::vector<std::uint8_t> encode_raw_fuzz_input(const TriangleQuery& q) {
  std::vector<std::uint8_t> out{raw_selector};
  for (const Vec3& v : {q.ray.origin, q.ray.direction, q.triangle.a, q.triangle.b, q.triangle.c})
    for (double c : {v.x, v.y, v.z}) append_word(out, std::bit_cast<std::uint64_t>(c));
  return out;
}

std::vector<std::uint8_t> encode_hard_triangle_fuzz_input(TriangleQueryKind kind,
                                                          std::span<const std::uint64_t> words) {
  std::size_t index = 0;
  while (all_triangle_query_kinds[index] != kind) ++index;
  std::vector<std::uint8_t> out{static_cast<std::uint8_t>(hard_query_selector + index)};
  for (std::uint64_t w : words) append_word(out, w);
  return out;
}

}  // namespace raykernel::testkit
