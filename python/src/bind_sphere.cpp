// The vectorized ray–sphere query (docs/contract.md §10): many rays against many spheres (query i is ray i and
// sphere i) or against one sphere, over NumPy arrays, with no Python loop and the GIL released.
//
// The kernel has no ray–sphere batch API: each row goes through the scalar entry point of the path asked for
// (intersect, intersect_exact, intersect_naive), rows spread over threads (answer_rows), as for triangles.
// Invalid rows raise ValueError naming the first one, or with errors="mask" are marked in `valid` while the
// others are answered.
#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/sphere.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace raykernel::python {
namespace {

// The rays and spheres of a vectorized call, read and checked with the GIL held; ray(i), sphere(i) without it.
struct SphereQueries {
  ColumnsView o, d, c;
  ValuesView r;
  std::size_t n;
  bool one_sphere;

  SphereQueries(py::handle origins, py::handle directions, py::handle centers, py::handle radii)
      : o(origins, "origins"), d(directions, "directions"), c(centers, "centers", true), r(radii, "radii", true),
        n(o.rows()), one_sphere(c.single()) {
    require_rows(d, "directions", n, "origins");
    require_rows(c, "centers", n, "origins");
    require_rows(r, "radii", n, "origins");
    if (r.single() != one_sphere)
      throw py::value_error("centers, radii: give both as arrays of n rows ((n, 3) and (n,)), or both as one sphere "
                            "(a 3-vector and a number)");
  }

  [[nodiscard]] Ray ray(std::size_t i) const noexcept { return {o.row(i), d.row(i)}; }
  [[nodiscard]] Sphere sphere(std::size_t i) const noexcept {
    const std::size_t k = one_sphere ? 0 : i;
    return {c.row(k), r.value(k)};
  }
  // "query 17: ..." (or "ray 17: ..." against one sphere) for the first invalid row, if any.
  [[nodiscard]] std::optional<std::string> first_error(std::span<const bool> valid) const {
    return first_row_error(valid, one_sphere, [&](std::size_t i) { return validate(ray(i), sphere(i)); });
  }
};

shown::SphereIntersectionArrays intersect_sphere_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                                          shown::ArrayLike3 centers, shown::ScalarOrArray radii,
                                                          const std::string& path_name, const std::string& errors,
                                                          std::optional<unsigned> threads) {
  const Path path = path_from(path_name);
  const ErrorPolicy policy = error_policy_from(errors);
  const SphereQueries q(origins, directions, centers, radii);
  const std::size_t n = q.n;

  auto origin = new_array<std::uint8_t>(n);
  auto relation = new_array<std::uint8_t>(n);
  auto t1 = new_array<double>(n);
  auto t2 = new_array<double>(n);
  auto valid = new_array<bool>(n);
  const std::span<std::uint8_t> origin_out = span_of(origin), relation_out = span_of(relation);
  const std::span<double> t1_out = span_of(t1), t2_out = span_of(t2);
  const std::span<bool> valid_out = span_of(valid);
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    answer_rows(
        n, threads_from(threads), grain_of(path), valid_out,
        [&](std::size_t i) {
          const Ray ray = q.ray(i);
          const Sphere sphere = q.sphere(i);
          // The naive path answers everything and validates for `valid` alone.
          const SphereIntersection x = path == Path::certified ? intersect(ray, sphere)
                                       : path == Path::exact   ? intersect_exact(ray, sphere)
                                                               : intersect_naive(ray, sphere);
          if (path == Path::naive) valid_out[i] = !validate(ray, sphere).has_value();
          origin_out[i] = static_cast<std::uint8_t>(x.origin);
          relation_out[i] = static_cast<std::uint8_t>(x.relation);
          t1_out[i] = x.t1;
          t2_out[i] = x.t2;
        },
        [&](std::size_t i) {
          origin_out[i] = relation_out[i] = invalid_code;
          t1_out[i] = t2_out[i] = nan;
        });
    error = q.first_error(valid_out);
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return types().sphere_intersection_arrays(origin, relation, t1, t2, valid);
}

}  // namespace

void bind_sphere(py::module_& m) {
  m.def("intersect_sphere_batch", with_progress(&intersect_sphere_batch_py), py::arg("origins"), py::arg("directions"),
        py::arg("centers"), py::arg("radii"), py::kw_only(), py::arg("path") = "certified",
        py::arg("errors") = "raise", py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        R"doc(``intersect(ray, sphere)`` over arrays: query i is (ray i, sphere i), or (ray i, the one sphere).

``origins``, ``directions``: (n, 3) arrays of real numbers (as in ``intersect_batch``); ``centers``: an (n, 3)
array and ``radii`` an (n,) array, or ``centers`` a single 3-vector and ``radii`` a single number for one sphere
against every ray. Any memory layout (a (3, n) structure of arrays passes as ``soa.T``).

Returns ``SphereIntersectionArrays(origin, relation, t1, t2, valid)``: ``origin`` uint8 ``SphereOrigin`` codes
and ``relation`` uint8 ``SphereRelation`` codes (``INVALID_RELATION_CODE`` for invalid rows), ``t1`` and ``t2``
float64 (the rounded roots, both t0 for TANGENT; NaN for MISS and for invalid rows), ``valid`` bool. Every row
is ``intersect``'s answer, bit for bit.

``path``: "certified" (``intersect`` per row), "exact" (``intersect_exact``) or "naive" (the textbook quadratic,
``intersect_naive``: no guarantee, and invalid rows are answered too). ``errors``: "raise" (default) raises
``ValueError`` naming the first invalid row ("query 17: sphere radius is not positive"; "ray 17: ..." with one
sphere); "mask" answers the valid rows and marks the others in ``valid``. ``threads``: None for all cores
(large batches only), or a count. Releases the GIL.

Ctrl-C stops a long call (``KeyboardInterrupt``, within a block of rows); ``progress``, None or a callable, is
called with (done, total) about every 0.1 s and at the end (an exception it raises stops the call too).)doc");
}

}  // namespace raykernel::python
