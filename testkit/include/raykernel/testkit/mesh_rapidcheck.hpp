// RapidCheck generators over meshes (meshes.hpp), for RC_GTEST_PROP properties of mesh queries: points to aim
// rays at, exactly on the mesh's vertices, edges and faces, where the hard cases are. Header-only; needs
// <rapidcheck.h> and `rapidcheck`.
#pragma once

#include <raykernel/bvh.hpp>
#include <raykernel/mesh.hpp>
#include <raykernel/testkit/meshes.hpp>

#include <rapidcheck.h>

#include <array>
#include <cmath>
#include <utility>
#include <cstdint>

namespace raykernel::testkit {

// kind 0: a vertex; 1: a point of an edge at k/2^bits (exactly on it when representable); 2: a point inside a
// face (an edge point moved towards the third vertex); 3: a point of the bounding box on a grid of sixteenths.
inline Vec3 target_point(const Mesh& mesh, const Box3& bounds, int kind) {
  const Triangle t = mesh.triangle(*rc::gen::inRange<std::size_t>(0, mesh.triangles.size()));
  switch (kind) {
    case 0: return *rc::gen::element(t.a, t.b, t.c);
    case 1: {
      const int bits = *rc::gen::inRange(1, 8);
      const auto p = edge_point(*rc::gen::element(t.a, t.b, t.c), *rc::gen::element(t.a, t.b, t.c),
                                         *rc::gen::inRange<std::int64_t>(0, (1LL << bits) + 1), bits);
      return p ? *p : t.a;
    }
    case 2: {
      const auto p = edge_point(t.a, t.b, *rc::gen::inRange<std::int64_t>(1, 16), 4);
      const auto r = p ? edge_point(*p, t.c, *rc::gen::inRange<std::int64_t>(1, 16), 4) : std::nullopt;
      return r ? *r : t.c;
    }
    default: {
      auto c = [](double lo, double hi) {
        const auto p = edge_point({lo, 0, 0}, {hi, 0, 0}, *rc::gen::inRange<std::int64_t>(-2, 19), 4);
        return p ? p->x : lo;
      };
      return {c(bounds.lo.x, bounds.hi.x), c(bounds.lo.y, bounds.hi.y), c(bounds.lo.z, bounds.hi.z)};
    }
  }
}

// Appends a triangle to `m`: each vertex an earlier one of `m` (one time in three, so that triangles share
// vertices, edges and whole copies) or a new one of three `coordinate()` values.
template <class Coordinate>
void add_random_triangle(Mesh& m, Coordinate&& coordinate) {
  std::array<std::uint32_t, 3> t{};
  for (auto& index : t) {
    if (!m.vertices.empty() && *rc::gen::inRange(0, 3) == 0) {
      index = static_cast<std::uint32_t>(*rc::gen::inRange<std::size_t>(0, m.vertices.size()));
    } else {
      index = static_cast<std::uint32_t>(m.vertices.size());
      m.vertices.push_back({coordinate(), coordinate(), coordinate()});
    }
  }
  m.triangles.push_back(t);
}

// A soup of triangles of one random scale: shared vertices, repeated (hence degenerate) vertices, duplicated
// triangles (exact ties), coplanar neighbours.
inline Mesh random_soup() {
  const int e = *rc::gen::element(0, 0, -20, 40, -1000, 600);
  const int count = *rc::gen::inRange(1, 13);
  Mesh m;
  auto coordinate = [&] { return std::ldexp(static_cast<double>(*rc::gen::inRange(-16, 17)), e - 3); };
  for (int k = 0; k < count; ++k) {
    const int kind = *rc::gen::inRange(0, 6);
    if (kind == 0 && !m.triangles.empty()) {  // a duplicate, maybe reversed
      auto t = m.triangles[*rc::gen::inRange<std::size_t>(0, m.triangles.size())];
      if (*rc::gen::arbitrary<bool>()) std::swap(t[1], t[2]);
      m.triangles.push_back(t);
      continue;
    }
    add_random_triangle(m, coordinate);
  }
  return m;
}

}  // namespace raykernel::testkit
