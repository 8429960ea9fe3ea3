// Scene answers as the tests compare and print them: bit-for-bit equality of two SurfaceHit answers (kind,
// index, t and the barycentric coordinates, NaN bits included) and a one-line description for failure messages.
#pragma once

#include <raykernel/nearest_scene.hpp>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

namespace raykernel::test {

inline bool same_bits(double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y); }

inline std::string describe(const std::optional<SurfaceHit>& h) {
  if (!h) return "miss";
  char t[64];
  std::snprintf(t, sizeof t, "%a", h->t);
  return std::string(to_string(h->kind)) + " " + std::to_string(h->index) + " t=" + t;
}

inline bool same_answer(const std::optional<SurfaceHit>& x, const std::optional<SurfaceHit>& y) {
  if (!x || !y) return !x && !y;
  return x->kind == y->kind && x->index == y->index && same_bits(x->t, y->t) &&
         same_bits(x->barycentric[0], y->barycentric[0]) && same_bits(x->barycentric[1], y->barycentric[1]) &&
         same_bits(x->barycentric[2], y->barycentric[2]);
}

}  // namespace raykernel::test
