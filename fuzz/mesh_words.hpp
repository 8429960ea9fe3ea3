// Structure-aware input words for the mesh harnesses (fuzz_occlusion, fuzz_closest): 8-byte little-endian words,
// each read as a coordinate by its top byte, so that a mesh's vertices, grid points around it and exact small
// multiples of its scale are the common case:
//   tag < 0x40: the raw bits of the rest (any double, NaN and inf included); 0x40..0x7F: a vertex coordinate of
//   the mesh; 0x80..0xBF: a multiple of a quarter of the scale in [−2, 2]; 0xC0..0xFF: a small integer times the
//   scale.
#pragma once

#include "fuzz_support.hpp"

#include <raykernel/mesh.hpp>
#include <raykernel/testkit/meshes.hpp>

#include <array>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace raykernel::fuzz {

struct Reader {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t offset = 0;
  std::uint64_t word() {
    std::uint64_t w = 0;
    for (std::size_t k = 0; k < 8; ++k, ++offset)
      if (offset < size) w |= std::uint64_t{data[offset]} << (8 * k);
    return w;
  }
};

// One coordinate, by the tag in the word's top byte (see the header).
inline double choose(std::uint64_t w, const Mesh& mesh, int scale) {
  const auto tag = static_cast<std::uint8_t>(w >> 56);
  const std::uint64_t rest = w & ((std::uint64_t{1} << 56) - 1);
  if (tag < 0x40) return std::bit_cast<double>(rest | (std::uint64_t{tag} << 58));
  if (tag < 0x80) {
    const Vec3& v = mesh.vertices[rest % mesh.vertices.size()];
    const std::uint64_t axis = (rest / mesh.vertices.size()) % 3;
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
  }
  if (tag < 0xC0) return std::ldexp(static_cast<double>(static_cast<int>(rest % 17) - 8), scale - 2);
  return std::ldexp(static_cast<double>(static_cast<int>(rest % 9) - 4), scale);
}

inline Vec3 point(Reader& r, const Mesh& mesh, int scale) {
  const double x = choose(r.word(), mesh, scale), y = choose(r.word(), mesh, scale);
  return {x, y, choose(r.word(), mesh, scale)};
}

// The mesh of byte `head`: bit 0 octahedron or subdivided cube (testkit, closed, vertices on a coarse dyadic grid),
// bits 1–3 its scale 2^(4·(b − 4)), bits 6–7 how many extra triangles (0–3), each of three points read from `r`
// (a non-finite point is replaced by vertex 0, so the mesh stays valid): shared vertices, edges, slivers, copies.
struct WordsMesh {
  Mesh mesh;
  int scale;
};
inline WordsMesh words_mesh(std::uint8_t head, Reader& r) {
  const int scale = 4 * (((head >> 1) & 7) - 4);
  Mesh mesh = (head & 1) ? testkit::make_subdivided_cube(1, 1) : testkit::make_octahedron(1);
  for (Vec3& v : mesh.vertices) v = {std::ldexp(v.x, scale), std::ldexp(v.y, scale), std::ldexp(v.z, scale)};
  const int extra = (head >> 6) & 3;
  for (int k = 0; k < extra; ++k) {
    std::array<std::uint32_t, 3> t{};
    for (auto& index : t) {
      const Vec3 v = point(r, mesh, scale);
      if (!finite_vector_by_bits(v)) {
        index = 0;
        continue;
      }
      mesh.vertices.push_back(v);
      index = static_cast<std::uint32_t>(mesh.vertices.size() - 1);
    }
    mesh.triangles.push_back(t);
  }
  return {std::move(mesh), scale};
}

}  // namespace raykernel::fuzz
