// The exact closest point of a mesh from Python (docs/contract.md §11): closest_point, closest_point_exact and
// closest_point_batch (raykernel/closest_point.hpp).
#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"
#include "mesh.hpp"

#include <raykernel/closest_point.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace raykernel::python {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

py::object to_python(const ClosestPoint& c) {
  return types().closest_point(c.triangle, types().closest_feature[static_cast<std::size_t>(c.feature)],
                               static_cast<int>(c.corner), python::to_python(c.point), c.squared_distance, c.distance,
                               to_fraction(c.squared_distance_exact));
}

py::object closest_point_py(py::handle point, const PythonMesh& mesh, bool exact) {
  const Vec3 p = vec3_from(point, "point");
  if (mesh.mesh().triangles.empty()) throw invalid_input("mesh has no triangles: no closest point");
  std::optional<ClosestPoint> c;
  {
    py::gil_scoped_release release;
    c = exact ? closest_point_exact(p, mesh.mesh()) : closest_point(p, mesh.prepared());
  }
  return to_python(*c);
}

shown::ClosestPointArrays closest_point_batch_py(shown::ArrayLike3 points, const PythonMesh& mesh, bool with_sign,
                                                 const std::string& path_name, const std::string& errors,
                                                 std::optional<unsigned> threads) {
  const bool exact = path_from(path_name, false) == Path::exact;
  const ErrorPolicy policy = error_policy_from(errors);
  const ColumnsView p(points, "points");
  const std::size_t n = p.rows();
  if (mesh.mesh().triangles.empty()) throw invalid_input("mesh has no triangles: no closest point");
  auto triangle = new_array<std::int64_t>(n);
  auto feature = new_array<std::uint8_t>(n);
  auto corner = new_array<std::uint8_t>(n);
  py::array_t<double> point({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto squared = new_array<double>(n);
  auto distance = new_array<double>(n);
  auto signed_distance_array = new_array<double>(with_sign ? n : 0);
  auto valid = new_array<bool>(n);
  const std::span<std::int64_t> triangle_out = span_of(triangle);
  const std::span<std::uint8_t> feature_out = span_of(feature), corner_out = span_of(corner);
  const std::span<double> squared_out = span_of(squared), distance_out = span_of(distance),
                          signed_out = span_of(signed_distance_array);
  const std::span<bool> valid_out = span_of(valid);
  double* const point_out = point.mutable_data();
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    parallel_for(n, threads_from(threads), exact ? 1 : 64, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const Vec3 q = p.row(i);
        valid_out[i] = !point_problem(q).has_value();
        if (!valid_out[i]) {
          triangle_out[i] = -1;
          feature_out[i] = invalid_code;
          corner_out[i] = 0;
          for (std::size_t k = 0; k < 3; ++k) point_out[3 * i + k] = nan;
          squared_out[i] = distance_out[i] = nan;
          if (with_sign) signed_out[i] = nan;
          continue;
        }
        const ClosestPoint c = exact ? closest_point_exact(q, mesh.mesh()) : closest_point(q, mesh.prepared());
        triangle_out[i] = c.triangle;
        feature_out[i] = static_cast<std::uint8_t>(c.feature);
        corner_out[i] = c.corner;
        point_out[3 * i] = c.point.x;
        point_out[3 * i + 1] = c.point.y;
        point_out[3 * i + 2] = c.point.z;
        squared_out[i] = c.squared_distance;
        distance_out[i] = c.distance;
        if (with_sign) signed_out[i] = signed_distance(q, mesh.prepared(), c);
      }
    });
    if (const std::optional<std::size_t> i = first_invalid_row(valid_out))
      error = "point " + std::to_string(*i) + ": " + point_problem(p.row(*i)).value_or("invalid input");
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return types().closest_point_arrays(triangle, feature, corner, point, squared, distance,
                                      with_sign ? py::object(signed_distance_array) : py::none(), valid);
}

}  // namespace

void bind_closest(py::module_& m) {
  m.def(
      "closest_point",
      [](shown::Vec3Like point, const PythonMesh& mesh) -> shown::ClosestPoint {
        return closest_point_py(point, mesh, false);
      },
      py::arg("point"), py::arg("mesh"),
      R"doc(The point of ``mesh`` nearest to ``point`` by the exact Euclidean distance (docs/contract.md §11):
``ClosestPoint(triangle, feature, corner, point, squared_distance, distance, squared_distance_exact)``. Triangles
are closed (edges and vertices included; a degenerate one is its segment or point); among triangles at the same
exact distance, the smallest index. ``point`` has each coordinate of the exact closest point rounded to nearest,
``squared_distance_exact`` is the exact squared distance as a ``Fraction``, ``squared_distance`` its rounding and
``distance`` the square root of the exact value rounded once. Through the mesh's BVH with an interval filter,
rationals where it cannot decide: the same answer as ``closest_point_exact``. Raises ``ValueError`` for a
non-finite point ("point x is not finite") or a mesh without triangles. Releases the GIL.)doc");
  m.def(
      "closest_point_exact",
      [](shown::Vec3Like point, const PythonMesh& mesh) -> shown::ClosestPoint {
        return closest_point_py(point, mesh, true);
      },
      py::arg("point"), py::arg("mesh"),
      R"doc(The reference ``closest_point``: every triangle in exact rationals, no BVH. Slow and obviously right; the
same answer as ``closest_point``. Releases the GIL.)doc");
  m.def("closest_point_batch", with_progress(&closest_point_batch_py), py::arg("points"), py::arg("mesh"),
        py::kw_only(), py::arg("signed") = false, py::arg("path") = "certified", py::arg("errors") = "raise",
        py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        R"doc(``closest_point`` over an (n, 3) array of points (real numbers, read as float64), on threads, with the
GIL released.

Returns ``ClosestPointArrays(triangle, feature, corner, point, squared_distance, distance, signed_distance,
valid)``; ``signed=True`` adds ``signed_distance``: the distance, negated where the exact ``inside`` says inside,
0 on the surface (Open3D's ``compute_signed_distance`` convention; meaningful for a closed mesh). ``path``:
"certified" or "exact" (``closest_point_exact``). ``errors``: "raise" (default) raises ``ValueError`` naming the
first bad row, "point 17: y is not finite"; "mask" answers the others and marks it in ``valid``. ``threads``:
None for all cores, or a count. Ctrl-C stops a long call (``KeyboardInterrupt``); ``progress``, None or a
callable, is called with (done, total) about every 0.1 s and at the end.)doc");
}

}  // namespace raykernel::python
