// fuzz_closest: the exact closest point of a small mesh (docs/contract.md §11), answered by raykernel's
// closest_point (BVH, interval filter, rationals) and checked against closest_point_exact (every triangle in
// rationals) and signed_distance against inside.
//
// Input (structure-aware, mesh_words.hpp): byte 0 the mesh (words_mesh: octahedron or subdivided cube at a scale
// 2^(4·(b − 4)), up to 3 extra triangles from the words: shared vertices, slivers, degenerate triangles, copies),
// then the extra triangles' words and the query point (3 words: vertex coordinates, grid points around the mesh,
// raw bits — NaN and inf included).
//
// Checked for every input:
//   - a non-finite query point throws invalid_input, a finite one does not;
//   - closest_point == closest_point_exact: the triangle, the feature and corner, the point's bits, the exact
//     squared distance (as text), its rounding and the distance's bits;
//   - the distance is 0 exactly when the exact squared distance is 0, and then inside() says on-surface;
//   - signed_distance is −distance where inside() is inside, +distance where outside.
#include "fuzz_support.hpp"
#include "mesh_words.hpp"

#include <raykernel/closest_point.hpp>

#include <cstdint>
#include <string>

namespace {

using raykernel::Vec3;
using raykernel::fuzz::bits;
using raykernel::fuzz::check;
using raykernel::fuzz::hex;

std::string text(const Vec3& v) { return hex(v.x) + " " + hex(v.y) + " " + hex(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  raykernel::fuzz::set_harness_name("closest");
  if (size == 0) return 0;
  raykernel::fuzz::Reader r{data, size, 1};
  raykernel::fuzz::WordsMesh built = raykernel::fuzz::words_mesh(data[0], r);
  const raykernel::Mesh& mesh = built.mesh;
  const raykernel::PreparedMesh prepared(mesh);
  const Vec3 p = raykernel::fuzz::point(r, mesh, built.scale);
  raykernel::fuzz::set_input_describer([&] {
    return "point " + text(p) + ", " + std::to_string(mesh.triangles.size()) + " triangles";
  });
  if (!raykernel::fuzz::finite_vector_by_bits(p)) {
    bool threw = false;
    try {
      (void)raykernel::closest_point(p, prepared);
    } catch (const raykernel::invalid_input&) {
      threw = true;
    }
    check(threw, "a non-finite point must throw invalid_input");
    return 0;
  }
  const raykernel::ClosestPoint fast = raykernel::closest_point(p, prepared);
  const raykernel::ClosestPoint exact = raykernel::closest_point_exact(p, mesh);
  check(fast.triangle == exact.triangle, "closest_point: the exact path's triangle");
  check(fast.feature == exact.feature && fast.corner == exact.corner, "closest_point: the exact path's feature");
  check(bits(fast.point.x) == bits(exact.point.x) && bits(fast.point.y) == bits(exact.point.y) &&
            bits(fast.point.z) == bits(exact.point.z),
        "closest_point: the exact path's point");
  check(fast.squared_distance_exact.str() == exact.squared_distance_exact.str(),
        "closest_point: the exact squared distance");
  check(bits(fast.squared_distance) == bits(exact.squared_distance) && bits(fast.distance) == bits(exact.distance),
        "closest_point: the rounded squared distance and distance");
  const bool on = exact.squared_distance_exact.numerator == "0";
  check(!on || (fast.distance == 0 && fast.squared_distance == 0), "a zero squared distance has distance 0");
  const raykernel::PointLocation where = raykernel::inside(p, prepared);
  check(on == (where == raykernel::PointLocation::on_surface), "distance 0 exactly when inside() says on-surface");
  const double s = raykernel::signed_distance(p, prepared, fast);
  check(on ? s == 0
           : bits(s) == bits(where == raykernel::PointLocation::inside ? -fast.distance : fast.distance),
        "signed_distance: the distance with inside()'s sign");
  return 0;
}
