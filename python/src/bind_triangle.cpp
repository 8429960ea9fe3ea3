// The vectorized ray–triangle queries (docs/contract.md §6): many rays against many triangles (query i is ray i
// and triangle i) or against one triangle, over NumPy arrays, with no Python loop and the GIL released.
//
// The kernel has no ray–triangle batch API: each row goes through the scalar entry point of the path asked
// for (intersect, intersect_exact, intersect_naive, relation), rows spread over threads (answer_rows). Invalid
// rows raise ValueError naming the first one, or with errors="mask" are marked in `valid` while the others are
// answered.
#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/triangle.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace raykernel::python {
namespace {

// The rays and triangles of a vectorized call, read and checked with the GIL held; row(i) without it.
struct TriangleQueries {
  ColumnsView o, d, a, b, c;
  std::size_t n;
  bool one_triangle;

  TriangleQueries(py::handle origins, py::handle directions, py::handle va, py::handle vb, py::handle vc)
      : o(origins, "origins"), d(directions, "directions"), a(va, "a", true), b(vb, "b", true), c(vc, "c", true),
        n(o.rows()), one_triangle(a.single()) {
    require_rows(d, "directions", n, "origins");
    for (auto [view, name] : {std::pair{&a, "a"}, {&b, "b"}, {&c, "c"}}) {
      require_rows(*view, name, n, "origins");
      if (view->single() != one_triangle)
        throw py::value_error("a, b, c: give all three as (n, 3) arrays, or all three as one 3-vector (one triangle)");
    }
  }

  [[nodiscard]] Ray ray(std::size_t i) const noexcept { return {o.row(i), d.row(i)}; }
  [[nodiscard]] Triangle triangle(std::size_t i) const noexcept {
    const std::size_t k = one_triangle ? 0 : i;
    return {a.row(k), b.row(k), c.row(k)};
  }
  // "query 17: ..." (or "ray 17: ..." against one triangle) for the first invalid row, if any.
  [[nodiscard]] std::optional<std::string> first_error(std::span<const bool> valid) const {
    return first_row_error(valid, one_triangle, [&](std::size_t i) { return validate(ray(i), triangle(i)); });
  }
};

shown::TriangleIntersectionArrays intersect_triangle_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                                              shown::ArrayLike3 a, shown::ArrayLike3 b,
                                                              shown::ArrayLike3 c, shown::OptionalRule rule,
                                                              bool want_t, bool want_barycentric,
                                                              const std::string& path_name, const std::string& errors,
                                                              std::optional<unsigned> threads) {
  const Path path = path_from(path_name);
  const ErrorPolicy policy = error_policy_from(errors);
  const TriangleOptions options{rule_or_owned(rule), want_t, want_barycentric};
  const TriangleQueries q(origins, directions, a, b, c);
  const std::size_t n = q.n;

  auto relation = new_array<std::uint8_t>(n);
  auto location = new_array<std::uint8_t>(n);
  auto owned = new_array<bool>(n);
  auto t = new_array<double>(n);
  py::array_t<double> barycentric({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto valid = new_array<bool>(n);
  const std::span<std::uint8_t> relation_out = span_of(relation), location_out = span_of(location);
  const std::span<bool> owned_out = span_of(owned), valid_out = span_of(valid);
  const std::span<double> t_out = span_of(t);
  double* const barycentric_out = barycentric.mutable_data();
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    answer_rows(
        n, threads_from(threads), grain_of(path), valid_out,
        [&](std::size_t i) {
          const Ray ray = q.ray(i);
          const Triangle triangle = q.triangle(i);
          // The naive path answers everything and validates for `valid` alone.
          const TriangleIntersection x = path == Path::certified ? intersect(ray, triangle, options)
                                         : path == Path::exact   ? intersect_exact(ray, triangle, options)
                                                                 : intersect_naive(ray, triangle);
          if (path == Path::naive) valid_out[i] = !validate(ray, triangle).has_value();
          relation_out[i] = static_cast<std::uint8_t>(x.relation);
          location_out[i] = static_cast<std::uint8_t>(x.location);
          owned_out[i] = x.owned;
          t_out[i] = x.t;
          for (std::size_t k = 0; k < 3; ++k) barycentric_out[3 * i + k] = x.barycentric[k];
        },
        [&](std::size_t i) {
          relation_out[i] = location_out[i] = invalid_code;
          owned_out[i] = false;
          t_out[i] = nan;
          for (int k = 0; k < 3; ++k) barycentric_out[3 * i + k] = nan;
        });
    error = q.first_error(valid_out);
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return types().triangle_intersection_arrays(relation, location, owned, t, barycentric, valid);
}

shown::TriangleClassificationArrays relation_triangle_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                                               shown::ArrayLike3 a, shown::ArrayLike3 b,
                                                               shown::ArrayLike3 c, shown::OptionalRule rule,
                                                               const std::string& path_name, const std::string& errors,
                                                               std::optional<unsigned> threads) {
  const Path path = path_from(path_name, false);
  const ErrorPolicy policy = error_policy_from(errors);
  const TriangleRule chosen = rule_or_owned(rule);
  const TriangleQueries q(origins, directions, a, b, c);
  const std::size_t n = q.n;

  auto relation = new_array<std::uint8_t>(n);
  auto location = new_array<std::uint8_t>(n);
  auto owned = new_array<bool>(n);
  auto valid = new_array<bool>(n);
  const std::span<std::uint8_t> relation_out = span_of(relation), location_out = span_of(location);
  const std::span<bool> owned_out = span_of(owned), valid_out = span_of(valid);
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    answer_rows(
        n, threads_from(threads), grain_of(path), valid_out,
        [&](std::size_t i) {
          const Ray ray = q.ray(i);
          const Triangle triangle = q.triangle(i);
          TriangleClassification x{};
          if (path == Path::certified) {
            x = raykernel::relation(ray, triangle, chosen);
          } else {  // the exact classification: intersect_exact without roundings
            const TriangleIntersection e = intersect_exact(ray, triangle, {chosen, false, false});
            x = {e.relation, e.location, e.owned};
          }
          relation_out[i] = static_cast<std::uint8_t>(x.relation);
          location_out[i] = static_cast<std::uint8_t>(x.location);
          owned_out[i] = x.owned;
        },
        [&](std::size_t i) {
          relation_out[i] = location_out[i] = invalid_code;
          owned_out[i] = false;
        });
    error = q.first_error(valid_out);
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return types().triangle_classification_arrays(relation, location, owned, valid);
}

}  // namespace

void bind_triangle(py::module_& m) {
  m.def("intersect_triangle_batch", with_progress(&intersect_triangle_batch_py), py::arg("origins"), py::arg("directions"),
        py::arg("a"), py::arg("b"), py::arg("c"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t") = true,
        py::arg("barycentric") = true, py::arg("path") = "certified", py::arg("errors") = "raise",
        py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        R"doc(``intersect(ray, triangle)`` over arrays: query i is (ray i, triangle i), or (ray i, the one triangle).

``origins``, ``directions``: (n, 3) arrays of real numbers (as in ``intersect_batch``); ``a``, ``b``, ``c``: the vertices, (n, 3) arrays, or all
three a single 3-vector for one triangle against every ray. Any memory layout (a (3, n) structure of arrays
passes as ``soa.T``). ``rule``, ``t``, ``barycentric`` as in ``intersect``.

Returns ``TriangleIntersectionArrays(relation, location, owned, t, barycentric, valid)``: ``relation`` uint8
``TriangleRelation`` codes and ``location`` uint8 ``TriangleLocation`` codes (``INVALID_RELATION_CODE`` for
invalid rows), ``owned`` bool, ``t`` float64, ``barycentric`` (n, 3) float64 (NaN where den = 0, where not
asked for, and for invalid rows), ``valid`` bool. Every row is ``intersect``'s answer, bit for bit.

``path``: "certified" (``intersect`` per row), "exact" (``intersect_exact``) or "naive" (Möller–Trumbore,
``intersect_naive``: no guarantee, and invalid rows are answered too). ``errors``: "raise" (default) raises
``ValueError`` naming the first invalid row ("query 17: ray direction is the zero vector"; "ray 17: ..." with
one triangle); "mask" answers the valid rows and marks the others in ``valid``. ``threads``: None for all
cores (large batches only), or a count. Releases the GIL.

Ctrl-C stops a long call (``KeyboardInterrupt``, within a block of rows); ``progress``, None or a callable, is
called with (done, total) about every 0.1 s and at the end (an exception it raises stops the call too).)doc");

  m.def("relation_triangle_batch", with_progress(&relation_triangle_batch_py), py::arg("origins"), py::arg("directions"),
        py::arg("a"), py::arg("b"), py::arg("c"), py::kw_only(), py::arg("rule") = py::none(),
        py::arg("path") = "certified", py::arg("errors") = "raise", py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        R"doc(``relation(ray, triangle)`` over arrays: the classification alone, nothing rounded.

Arguments as in ``intersect_triangle_batch``; ``path`` is "certified" or "exact". Returns
``TriangleClassificationArrays(relation, location, owned, valid)``. Releases the GIL.

Ctrl-C stops a long call (``KeyboardInterrupt``, within a block of rows); ``progress``, None or a callable, is
called with (done, total) about every 0.1 s and at the end (an exception it raises stops the call too).)doc");
}

}  // namespace raykernel::python
