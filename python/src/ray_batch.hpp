// The rays of a batch with their intervals (docs/contract.md §8), read from Python with the GIL held and answered on
// threads without it: nearest_hit_batch, occluded_batch and crossings_batch over meshes and sphere sets.
#pragma once

#include "batch_support.hpp"
#include "convert.hpp"

#include <raykernel/occlusion.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace raykernel::python {

// Why ray row i (with its interval) cannot be asked, or nothing.
[[nodiscard]] inline std::optional<std::string> ray_problem(const Ray& ray, const RayInterval& interval) {
  if (auto reason = validate(ray)) return reason;
  return validate(interval);
}

// answer(i, valid) for every row of [0, rows), on threads without the GIL, valid[i] the absence of problem(i) (an
// optional reason); then, with the GIL, "<label> i: <reason>" for the first bad row, raised when `policy` says so.
template <class Problem, class Answer>
void run_checked_rows(std::size_t rows, std::span<bool> valid, std::optional<unsigned> threads, std::size_t grain,
                      ErrorPolicy policy, const char* label, Problem&& problem, Answer&& answer) {
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    parallel_for(rows, threads_from(threads), grain, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        valid[i] = !problem(i).has_value();
        answer(i, valid[i]);
      }
    });
    if (const std::optional<std::size_t> i = first_invalid_row(valid))
      error = std::string(label) + " " + std::to_string(*i) + ": " + problem(*i).value_or("invalid input");
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
}

// The arguments every ray batch here shares, read with the GIL held: the rays (origins, directions) with their
// intervals (t_min, t_max: one number each, or one per ray), the path, the error policy and the rule.
struct RayRows {
  ColumnsView o, d;
  ValuesView lo, hi;
  Path path;  // certified or exact; naive too where the query has a naive form (allow_naive)
  bool exact;
  ErrorPolicy policy;
  TriangleRule rule;

  RayRows(py::handle origins, py::handle directions, py::handle t_min, py::handle t_max, py::handle rule_arg,
           const std::string& path_name, const std::string& errors, bool allow_naive = false)
      : o(origins, "origins"),
        d(directions, "directions"),
        lo(t_min, "t_min", true),
        hi(t_max, "t_max", true),
        path(path_from(path_name, allow_naive)),
        exact(path == Path::exact),
        policy(error_policy_from(errors)),
        rule(rule_or_owned(rule_arg)) {
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
    run_checked_rows(
        rows(), valid, threads, grain, policy, "ray", [&](std::size_t i) { return ray_problem(ray(i), interval(i)); },
        [&](std::size_t i, bool ok) { answer(i, ray(i), interval(i), ok); });
  }
};

// Per ray the nearest hit within its interval as two columns: `index` (int64, −1 for none and for an invalid row)
// and `t` (float64, NaN there), from nearest(ray, interval) → an optional hit of two members (index, t): a plane
// set's NearestHit, a sphere set's SphereHit.
struct NearestColumns {
  py::array_t<std::int64_t> index;
  py::array_t<double> t;
  py::array_t<bool> valid;
};
template <class Nearest>
[[nodiscard]] NearestColumns nearest_columns(const RayRows& b, std::optional<unsigned> threads, std::size_t grain,
                                             Nearest&& nearest) {
  NearestColumns c{new_array<std::int64_t>(b.rows()), new_array<double>(b.rows()), new_array<bool>(b.rows())};
  const std::span<std::int64_t> index_out = span_of(c.index);
  const std::span<double> t_out = span_of(c.t);
  b.run(span_of(c.valid), threads, grain, [&](std::size_t i, const Ray& ray, const RayInterval& interval, bool ok) {
    index_out[i] = -1;
    t_out[i] = nan;
    if (!ok) return;
    if (const auto hit = nearest(ray, interval)) {
      const auto& [index, t] = *hit;
      index_out[i] = static_cast<std::int64_t>(index);
      t_out[i] = t;
    }
  });
  return c;
}

// The open segments of a batch (p[i], q[i]; docs/contract.md §8), read with the GIL held: occluded_segment_batch
// over meshes and sphere sets.
struct SegmentRows {
  ColumnsView p, q;
  bool exact;
  ErrorPolicy policy;

  SegmentRows(py::handle ps, py::handle qs, const std::string& path_name, const std::string& errors)
      : p(ps, "p"), q(qs, "q"), exact(path_from(path_name, false) == Path::exact), policy(error_policy_from(errors)) {
    require_rows(q, "q", p.rows(), "p");
  }
  [[nodiscard]] std::size_t rows() const noexcept { return p.rows(); }

  // answer(i, p, q, valid) for every row, as RayRows::run.
  template <class Answer>
  void run(std::span<bool> valid, std::optional<unsigned> threads, std::size_t grain, Answer&& answer) const {
    run_checked_rows(
        rows(), valid, threads, grain, policy, "segment",
        [&](std::size_t i) { return validate_segment(p.row(i), q.row(i)); },
        [&](std::size_t i, bool ok) { answer(i, p.row(i), q.row(i), ok); });
  }
};

}  // namespace raykernel::python
