// Rays with an interval, any-hit, segments and all hits from Python, over arrays (docs/contract.md §8):
// all_hits, occluded_batch, occluded_segment_batch, crossings_batch (raykernel/occlusion.hpp). The scalar
// occluded and occluded_segment are in bind_mesh.cpp.
#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"
#include "mesh.hpp"

#include <raykernel/occlusion.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace raykernel::python {
namespace {

py::object types_attr(const char* name) { return py::module_::import("raykernel._types").attr(name); }

// Why ray row i (with its interval) cannot be asked, or nothing.
std::optional<std::string> ray_problem(const Ray& ray, const RayInterval& interval) {
  if (auto reason = validate(ray)) return reason;
  return validate(interval);
}

shown::MeshHits all_hits_py(shown::RayLike ray, const PythonMesh& mesh, double t_min, double t_max,
                            shown::OptionalRule rule, const std::string& path) {
  const Ray r = ray_from(ray);
  const RayInterval interval{t_min, t_max};
  const TriangleRule chosen = rule_or_owned(rule);
  const bool exact = path_from(path, false) == Path::exact;
  MeshHits hits;
  {
    py::gil_scoped_release release;
    hits = exact ? all_hits_exact(r, interval, mesh.mesh(), chosen) : all_hits(r, interval, mesh.prepared(), chosen);
  }
  py::list list;
  for (const MeshHit& h : hits.hits) list.append(to_python(std::optional<MeshHit>(h)));
  return types_attr("MeshHits")(list, hits.crossings);
}

// The arguments every ray batch here shares, read with the GIL held: the rays (origins, directions) with their
// intervals (t_min, t_max: one number each, or one per ray), the path, the error policy and the rule.
struct RayBatch {
  ColumnsView o, d;
  ValuesView lo, hi;
  bool exact;
  ErrorPolicy policy;
  TriangleRule rule;

  RayBatch(py::handle origins, py::handle directions, py::handle t_min, py::handle t_max, py::handle rule_arg,
           const std::string& path, const std::string& errors)
      : o(origins, "origins"), d(directions, "directions"), lo(t_min, "t_min", true), hi(t_max, "t_max", true),
        exact(path_from(path, false) == Path::exact), policy(error_policy_from(errors)), rule(rule_or_owned(rule_arg)) {
    require_rows(d, "directions", o.rows(), "origins");
    require_rows(lo, "t_min", o.rows(), "origins");
    require_rows(hi, "t_max", o.rows(), "origins");
  }
  [[nodiscard]] std::size_t rows() const noexcept { return o.rows(); }
  [[nodiscard]] Ray ray(std::size_t i) const noexcept { return {o.row(i), d.row(i)}; }
  [[nodiscard]] RayInterval interval(std::size_t i) const noexcept {
    return {lo.value(lo.single() ? 0 : i), hi.value(hi.single() ? 0 : i)};
  }

  // answer(i, ray, interval, valid) for every row, on threads without the GIL; `valid` marks the rows. Then, with
  // the GIL, raises for the first bad row when the policy says so.
  template <class Answer>
  void run(std::span<bool> valid, std::optional<unsigned> threads, std::size_t grain, Answer&& answer) const {
    std::optional<std::string> error;
    {
      py::gil_scoped_release release;
      parallel_for(rows(), threads_from(threads), grain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          valid[i] = !ray_problem(ray(i), interval(i)).has_value();
          answer(i, ray(i), interval(i), valid[i]);
        }
      });
      if (const std::optional<std::size_t> i = first_invalid_row(valid))
        error = "ray " + std::to_string(*i) + ": " + ray_problem(ray(*i), interval(*i)).value_or("invalid input");
    }
    if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  }
};

shown::OcclusionArrays occluded_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                         const PythonMesh& mesh, shown::ScalarOrArray t_min, shown::ScalarOrArray t_max,
                                         shown::OptionalRule rule, const std::string& path_name,
                                         const std::string& errors, std::optional<unsigned> threads) {
  const RayBatch b(origins, directions, t_min, t_max, rule, path_name, errors);
  auto blocked = new_array<bool>(b.rows());
  auto valid = new_array<bool>(b.rows());
  const std::span<bool> blocked_out = span_of(blocked);
  b.run(span_of(valid), threads, b.exact ? 4 : 256, [&](std::size_t i, const Ray& ray, const RayInterval& interval, bool ok) {
    blocked_out[i] = ok && (b.exact ? occluded_exact(ray, interval, mesh.mesh(), b.rule)
                                    : occluded(ray, interval, mesh.prepared(), b.rule));
  });
  return types_attr("OcclusionArrays")(blocked, valid);
}

shown::OcclusionArrays occluded_segment_batch_py(shown::ArrayLike3 ps, shown::ArrayLike3 qs, const PythonMesh& mesh,
                                                 shown::OptionalRule rule, const std::string& path_name,
                                                 const std::string& errors, std::optional<unsigned> threads) {
  const bool exact = path_from(path_name, false) == Path::exact;
  const ErrorPolicy policy = error_policy_from(errors);
  const TriangleRule chosen = rule_or_owned(rule);
  const ColumnsView p(ps, "p"), q(qs, "q");
  const std::size_t n = p.rows();
  require_rows(q, "q", n, "p");
  auto blocked = new_array<bool>(n);
  auto valid = new_array<bool>(n);
  const std::span<bool> blocked_out = span_of(blocked), valid_out = span_of(valid);
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    parallel_for(n, threads_from(threads), exact ? 4 : 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const Vec3 a = p.row(i), b = q.row(i);
        valid_out[i] = !validate_segment(a, b).has_value();
        blocked_out[i] = valid_out[i] && (exact ? occluded_exact(a, b, mesh.mesh(), chosen)
                                                : occluded(a, b, mesh.prepared(), chosen));
      }
    });
    if (const std::optional<std::size_t> i = first_invalid_row(valid_out))
      error = "segment " + std::to_string(*i) + ": " + validate_segment(p.row(*i), q.row(*i)).value_or("invalid input");
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return types_attr("OcclusionArrays")(blocked, valid);
}

shown::CrossingArrays crossings_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                         const PythonMesh& mesh, shown::ScalarOrArray t_min, shown::ScalarOrArray t_max,
                                         shown::OptionalRule rule, const std::string& path_name,
                                         const std::string& errors, std::optional<unsigned> threads) {
  const RayBatch b(origins, directions, t_min, t_max, rule, path_name, errors);
  auto hits = new_array<std::int64_t>(b.rows());
  auto crossings = new_array<std::int64_t>(b.rows());
  auto valid = new_array<bool>(b.rows());
  const std::span<std::int64_t> hits_out = span_of(hits), crossings_out = span_of(crossings);
  b.run(span_of(valid), threads, b.exact ? 1 : 64, [&](std::size_t i, const Ray& ray, const RayInterval& interval, bool ok) {
    if (!ok) {
      hits_out[i] = crossings_out[i] = 0;
      return;
    }
    const MeshHits h = b.exact ? all_hits_exact(ray, interval, mesh.mesh(), b.rule)
                               : all_hits(ray, interval, mesh.prepared(), b.rule);
    hits_out[i] = static_cast<std::int64_t>(h.hits.size());
    crossings_out[i] = h.crossings;
  });
  return types_attr("CrossingArrays")(hits, crossings, valid);
}

constexpr double inf = std::numeric_limits<double>::infinity();

}  // namespace

void bind_occlusion(py::module_& m) {
  m.def("all_hits", &all_hits_py, py::arg("ray"), py::arg("mesh"), py::kw_only(), py::arg("t_min") = 0.0,
        py::arg("t_max") = inf, py::arg("rule") = py::none(), py::arg("path") = "certified",
        R"doc(Every triangle of ``mesh`` that ``ray`` hits within ``[t_min, t_max]`` under ``rule`` (owned by default),
in exact order (by exact t, ties by index), and the signed count of its owned crossings (docs/contract.md §8):
``MeshHits(hits, crossings)``, ``hits`` a list of ``MeshHit``. For a ray from outside a closed, consistently oriented
mesh over [0, inf] the crossings add up to 0 — a nonzero count is a leak. ``path``: "certified" (through the BVH)
or "exact" (every triangle in rationals). Raises ``ValueError`` for an invalid ray or interval. Releases the GIL.)doc");
  m.def("occluded_batch", with_progress(&occluded_batch_py), py::arg("origins"), py::arg("directions"),
        py::arg("mesh"), py::kw_only(), py::arg("t_min") = 0.0, py::arg("t_max") = inf, py::arg("rule") = py::none(),
        py::arg("path") = "certified", py::arg("errors") = "raise", py::arg("threads") = py::none(),
        py::arg("progress") = py::none(),
        R"doc(``occluded`` over (n, 3) arrays of ray origins and directions, on threads with the GIL released: shadow rays
in bulk. ``t_min``, ``t_max``: one number for every ray, or a 1-D array of n (each ray its own interval).
Returns ``OcclusionArrays(occluded, valid)`` (bool). ``errors``: "raise" (default) raises ``ValueError`` naming
the first bad row ("ray 3: t_min is greater than t_max"), "mask" answers the others. ``path``, ``rule``,
``threads``, ``progress`` as ``inside_batch``.)doc");
  m.def("occluded_segment_batch", with_progress(&occluded_segment_batch_py), py::arg("p"), py::arg("q"),
        py::arg("mesh"), py::kw_only(), py::arg("rule") = py::none(), py::arg("path") = "certified",
        py::arg("errors") = "raise", py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        R"doc(``occluded_segment`` over (n, 3) arrays of endpoints: whether some triangle meets each open segment
(p, q) (docs/contract.md §8; the exact direction q − p, endpoints excluded). Returns ``OcclusionArrays(occluded,
valid)``; a bad row ("segment 2: p and q are the same point") raises or is masked as ``errors`` says.)doc");
  m.def("crossings_batch", with_progress(&crossings_batch_py), py::arg("origins"), py::arg("directions"),
        py::arg("mesh"), py::kw_only(), py::arg("t_min") = 0.0, py::arg("t_max") = inf, py::arg("rule") = py::none(),
        py::arg("path") = "certified", py::arg("errors") = "raise", py::arg("threads") = py::none(),
        py::arg("progress") = py::none(),
        R"doc(``all_hits`` over arrays, without the lists: per ray the number of triangles hit within its interval
(``hits``) and the signed count of owned crossings (``crossings``; 0 for a ray from outside a closed mesh to
infinity, so a nonzero count is a leak). Returns ``CrossingArrays(hits, crossings, valid)`` (int64, int64,
bool). Arguments as ``occluded_batch``.)doc");
}

}  // namespace raykernel::python
