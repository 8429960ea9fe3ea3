// The vectorized forms: many queries per call over NumPy arrays, with no Python loop and the GIL released.
//
// Rays and planes come as (n, 3) float64 arrays (origins, directions, points, normals). The certified path
// runs the C++ batch API (raykernel/batch.hpp: the SIMD fast path, then the cascade for what it leaves, over
// threads for large batches); the exact and naive paths loop over the scalar functions in C++, on threads.
// Invalid rows either raise ValueError naming the first one ("query 17: ray direction is the zero vector")
// or, with errors="mask", are marked in the `valid` array while the others are answered.
#include "bindings.hpp"
#include "convert.hpp"
#include "plane_set.hpp"

#include <raykernel/batch.hpp>
#include <raykernel/nearest_hit.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace raykernel::python {
namespace {

// relation[i] where valid[i] is false: no relation (not one of the four codes).
constexpr std::uint8_t invalid_relation_code = 255;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

enum class Path { certified, exact, naive };

Path path_from(const std::string& path) {
  if (path == "certified") return Path::certified;
  if (path == "exact") return Path::exact;
  if (path == "naive") return Path::naive;
  throw py::value_error("path: expected 'certified', 'exact' or 'naive', got '" + path + "'");
}

// Runs work(begin, end) over [0, n) on up to `threads` threads (0: the hardware's), at least `grain` items
// each; rethrows the first exception after all have joined.
template <class Work>
void parallel_for(std::size_t n, unsigned threads, std::size_t grain, Work&& work) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t wanted = threads != 0 ? threads : hardware;
  const std::size_t count = std::max<std::size_t>(1, std::min(wanted, n / std::max<std::size_t>(grain, 1)));
  std::vector<std::exception_ptr> failures(count);
  auto part = [&](std::size_t k) {
    try {
      work(n * k / count, n * (k + 1) / count);
    } catch (...) {
      failures[k] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < count; ++k) pool.emplace_back(part, k);
  part(0);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& f : failures)
    if (f) std::rethrow_exception(f);
}

// Items per thread below which a thread costs more than it saves (exact queries take microseconds).
constexpr std::size_t exact_grain = 256;
constexpr std::size_t naive_grain = std::size_t{1} << 15;

unsigned threads_from(const std::optional<unsigned>& threads) { return threads.value_or(0); }

py::dict stats_to_python(const BatchStats& stats) {
  py::dict relation, t;
  for (int s = 0; s < stage_count; ++s) {
    const py::object name = to_python(static_cast<Stage>(s)).attr("value");
    relation[name] = stats.relation_stage[static_cast<std::size_t>(s)];
    t[name] = stats.t_stage[static_cast<std::size_t>(s)];
  }
  py::dict d;
  d["relation"] = relation;
  d["t"] = t;
  return d;
}

// Rows per call into the batch API when an input must be gathered into columns (a row-major array): the
// gathered chunk stays in cache for the batch, and a large array is never copied whole. 2^16 queries are
// still enough for the batch API to split over threads.
constexpr std::size_t gather_chunk = std::size_t{1} << 16;

// Calls work(begin, end) over [0, n) in chunks: one chunk when every view is contiguous, else gather_chunk rows.
template <class Work>
void in_chunks(std::size_t n, std::initializer_list<const ColumnsView*> views, Work&& work) {
  bool contiguous = true;
  for (const ColumnsView* v : views) contiguous = contiguous && v->contiguous();
  const std::size_t step = contiguous ? std::max<std::size_t>(n, 1) : gather_chunk;
  for (std::size_t begin = 0; begin < n; begin += step) work(begin, std::min(n, begin + step));
}

RayBatch ray_batch(ColumnsView& o, ColumnsView& d, std::size_t begin, std::size_t end) {
  const auto oc = o.columns(begin, end), dc = d.columns(begin, end);
  return {oc[0], oc[1], oc[2], dc[0], dc[1], dc[2]};
}

py::object intersect_batch_py(py::handle origins, py::handle directions, py::handle points, py::handle normals,
                              const std::string& path_name, const std::string& errors,
                              std::optional<unsigned> threads, bool want_stats) {
  const Path path = path_from(path_name);
  const ErrorPolicy policy = error_policy_from(errors);
  ColumnsView o(origins, "origins"), d(directions, "directions");
  ColumnsView p(points, "points", true), nv(normals, "normals", true);
  const std::size_t n = o.rows();
  require_rows(d, "directions", n, "origins");
  require_rows(p, "points", n, "origins");
  require_rows(nv, "normals", n, "origins");
  if (p.single() != nv.single())
    throw py::value_error("points and normals: give both as (n, 3) arrays, or both as one 3-vector (one plane)");
  const bool one_plane = p.single();
  if (want_stats && path != Path::certified) throw py::value_error("stats: only the certified path has stages");

  auto relation = new_array<std::uint8_t>(n);
  auto t = new_array<double>(n);
  auto valid = new_array<bool>(n);
  const std::span<std::uint8_t> relation_out = span_of(relation);
  const std::span<double> t_out = span_of(t);
  const std::span<bool> valid_out = span_of(valid);
  BatchStats stats;
  std::optional<std::pair<std::size_t, std::string>> first_invalid;
  {
    py::gil_scoped_release release;
    auto query = [&](std::size_t i) { return std::pair{Ray{o.row(i), d.row(i)}, Plane{p.row(i), nv.row(i)}}; };
    if (path == Path::certified) {
      const BatchOptions options{threads_from(threads), want_stats ? &stats : nullptr};
      in_chunks(n, {&o, &d, &p, &nv}, [&](std::size_t begin, std::size_t end) {
        const std::size_t m = end - begin;
        const IntersectionBatch out{{reinterpret_cast<Relation*>(relation_out.data()) + begin, m},
                                    t_out.subspan(begin, m), valid_out.subspan(begin, m)};
        const RayBatch rays = ray_batch(o, d, begin, end);
        if (one_plane) {
          intersect_batch(rays, Plane{p.row(0), nv.row(0)}, out, options);
        } else {
          const auto pc = p.columns(begin, end), nc = nv.columns(begin, end);
          intersect_batch(rays, PlaneBatch{pc[0], pc[1], pc[2], nc[0], nc[1], nc[2]}, out, options);
        }
      });
    } else {
      parallel_for(n, threads_from(threads), path == Path::exact ? exact_grain : naive_grain,
                   [&](std::size_t begin, std::size_t end) {
                     for (std::size_t i = begin; i < end; ++i) {
                       const auto [ray, plane] = query(i);
                       valid_out[i] = !validate(ray, plane).has_value();
                       if (!valid_out[i]) continue;
                       const Intersection x = path == Path::exact ? intersect_exact(ray, plane) : intersect_naive(ray, plane);
                       relation_out[i] = static_cast<std::uint8_t>(x.relation);
                       t_out[i] = x.t;
                     }
                   });
    }
    // Invalid rows get a definite answer: no relation, t NaN; the first one's reason for the error.
    for (std::size_t i = 0; i < n; ++i) {
      if (valid_out[i]) continue;
      relation_out[i] = invalid_relation_code;
      t_out[i] = nan;
      if (!first_invalid) {
        const auto [ray, plane] = query(i);
        first_invalid.emplace(i, validate(ray, plane).value_or("invalid input"));
      }
    }
  }
  if (first_invalid && policy == ErrorPolicy::raise)
    throw invalid_input((one_plane ? "ray " : "query ") + std::to_string(first_invalid->first) + ": " +
                        first_invalid->second);
  return types().intersection_arrays(relation, t, valid, want_stats ? py::object(stats_to_python(stats)) : py::none());
}

py::object nearest_hit_batch_py(py::handle origins, py::handle directions, py::handle planes_arg,
                                const std::string& path_name, const std::string& errors,
                                std::optional<unsigned> threads, bool want_stats) {
  const Path path = path_from(path_name);
  const ErrorPolicy policy = error_policy_from(errors);
  ColumnsView o(origins, "origins"), d(directions, "directions");
  const std::size_t n = o.rows();
  require_rows(d, "directions", n, "origins");
  std::vector<Plane> storage;
  const std::span<const Plane> planes = planes_from(planes_arg, storage);
  if (want_stats && path != Path::certified) throw py::value_error("stats: only the certified path has stages");

  auto plane = new_array<std::int64_t>(n);
  auto t = new_array<double>(n);
  auto valid = new_array<bool>(n);
  const std::span<std::int64_t> plane_out = span_of(plane);
  const std::span<double> t_out = span_of(t);
  const std::span<bool> valid_out = span_of(valid);
  BatchStats stats;
  std::optional<std::pair<std::size_t, std::string>> first_invalid;
  {
    py::gil_scoped_release release;
    for (std::size_t k = 0; k < planes.size(); ++k)  // PlaneSets are valid already; this is for sequences
      if (const std::optional<std::string> reason = validate(planes[k]))
        throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
    std::size_t valid_count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::optional<std::string> reason = validate(Ray{o.row(i), d.row(i)});
      valid_out[i] = !reason;
      valid_count += valid_out[i];
      if (reason && !first_invalid) first_invalid.emplace(i, *reason);
    }
    if (!(first_invalid && policy == ErrorPolicy::raise)) {
      std::vector<std::optional<NearestHit>> hits(n);
      if (path == Path::certified) {
        const BatchOptions options{threads_from(threads), want_stats ? &stats : nullptr};
        if (valid_count == n) {
          in_chunks(n, {&o, &d}, [&](std::size_t begin, std::size_t end) {
            nearest_hit_batch(ray_batch(o, d, begin, end), planes, std::span(hits).subspan(begin, end - begin),
                              options);
          });
        } else {  // the batch stops at an invalid ray: answer the valid ones as a batch of their own
          std::array<std::vector<double>, 6> c;
          std::vector<std::size_t> index;
          index.reserve(valid_count);
          for (auto& v : c) v.reserve(valid_count);
          for (std::size_t i = 0; i < n; ++i) {
            if (!valid_out[i]) continue;
            index.push_back(i);
            const Vec3 oi = o.row(i), di = d.row(i);
            for (auto [k, x] : {std::pair{0, oi.x}, {1, oi.y}, {2, oi.z}, {3, di.x}, {4, di.y}, {5, di.z}})
              c[static_cast<std::size_t>(k)].push_back(x);
          }
          std::vector<std::optional<NearestHit>> compact(valid_count);
          nearest_hit_batch({c[0], c[1], c[2], c[3], c[4], c[5]}, planes, compact, options);
          for (std::size_t j = 0; j < valid_count; ++j) hits[index[j]] = compact[j];
        }
      } else {
        parallel_for(n, threads_from(threads), path == Path::exact ? std::size_t{4} : std::size_t{1024},
                     [&](std::size_t begin, std::size_t end) {
                       for (std::size_t i = begin; i < end; ++i) {
                         if (!valid_out[i]) continue;
                         const Ray ray{o.row(i), d.row(i)};
                         hits[i] = path == Path::exact ? nearest_hit_exact(ray, planes) : nearest_hit_naive(ray, planes);
                       }
                     });
      }
      for (std::size_t i = 0; i < n; ++i) {
        plane_out[i] = hits[i] ? static_cast<std::int64_t>(hits[i]->plane) : -1;
        t_out[i] = hits[i] ? hits[i]->t : nan;
      }
    }
  }
  if (first_invalid && policy == ErrorPolicy::raise)
    throw invalid_input("ray " + std::to_string(first_invalid->first) + ": " + first_invalid->second);
  return types().nearest_hit_arrays(plane, t, valid, want_stats ? py::object(stats_to_python(stats)) : py::none());
}

}  // namespace

void bind_batch(py::module_& m) {
  m.attr("INVALID_RELATION_CODE") = invalid_relation_code;

  m.def("intersect_batch", &intersect_batch_py, py::arg("origins"), py::arg("directions"), py::arg("points"),
        py::arg("normals"), py::kw_only(), py::arg("path") = "certified", py::arg("errors") = "raise",
        py::arg("threads") = py::none(), py::arg("stats") = false,
        R"doc(``intersect`` over arrays: query i is (ray i, plane i), or (ray i, the one plane).

``origins``, ``directions``: (n, 3) float64 arrays (or anything ``numpy.asarray`` turns into one);
``points``, ``normals``: (n, 3) arrays, or both a single 3-vector for one plane against every ray. Any memory
layout works; a column-contiguous one (Fortran order, e.g. ``soa.T`` of a (3, n) structure of arrays) is read
without a copy.

Returns ``IntersectionArrays(relation, t, valid, stats)``: ``relation`` uint8 codes (``Relation.HIT.code``
… ``Relation.IN_PLANE.code``; ``INVALID_RELATION_CODE`` where the row is invalid), ``t`` float64 (NaN for
PARALLEL, IN_PLANE and invalid rows), ``valid`` bool. Every answer is ``intersect``'s, bit for bit.

``path``: "certified" (the C++ batch API: SIMD fast path, then the cascade), "exact" (``intersect_exact``
per row, on threads) or "naive" (``intersect_naive`` per row). ``errors``: "raise" (default) raises
``ValueError`` naming the first invalid row, "query 17: ray direction is the zero vector" ("ray 17: ..." with
one plane); "mask" answers the valid rows and marks the others in ``valid``. ``threads``: None for all
cores (large batches only), or a count. ``stats=True`` (certified path) adds how many rows each stage
decided. Releases the GIL.)doc");

  m.def("nearest_hit_batch", &nearest_hit_batch_py, py::arg("origins"), py::arg("directions"), py::arg("planes"),
        py::kw_only(), py::arg("path") = "certified", py::arg("errors") = "raise", py::arg("threads") = py::none(),
        py::arg("stats") = false,
        R"doc(``nearest_hit`` for every ray: the first plane of ``planes`` each ray meets.

``origins``, ``directions``: (n, 3) arrays; ``planes``: a ``PlaneSet`` (read and validated once) or a sequence
of ``(point, normal)`` pairs. Returns ``NearestHitArrays(plane, t, valid, stats)``: ``plane`` int64, the
index of the nearest plane hit or -1 for a miss (and for invalid rays), ``t`` float64 (NaN for a miss),
``valid`` bool. ``path``, ``errors``, ``threads`` and ``stats`` as in ``intersect_batch``; an invalid plane
always raises ("plane 3: plane normal is the zero vector"), an invalid ray raises "ray 17: ..." unless
errors="mask". Releases the GIL.)doc");
}

}  // namespace raykernel::python
