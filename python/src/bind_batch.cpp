// The vectorized forms: many queries per call over NumPy arrays, with no Python loop and the GIL released.
//
// Rays and planes come as (n, 3) arrays of real numbers, read as float64 (origins, directions, points, normals). The certified path
// runs the C++ batch API (raykernel/batch.hpp: the SIMD fast path, then the cascade for what it leaves, over
// threads for large batches); the exact and naive paths loop over the scalar functions in C++, on threads.
// Invalid rows either raise ValueError naming the first one ("query 17: ray direction is the zero vector")
// or, with errors="mask", are marked in the `valid` array while the others are answered.
#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"
#include "mesh.hpp"
#include "plane_set.hpp"
#include "ray_batch.hpp"
#include "sphere_set.hpp"

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

// The four arrays of a batch of ray–plane queries, checked: n rays, against n planes or against one plane
// (points and normals both given as one 3-vector).
struct PlaneQueries {
  ColumnsView o, d, p, nv;
  std::size_t n;
  bool one_plane;

  PlaneQueries(py::handle origins, py::handle directions, py::handle points, py::handle normals)
      : o(origins, "origins"), d(directions, "directions"), p(points, "points", true), nv(normals, "normals", true),
        n(o.rows()) {
    require_rows(d, "directions", n, "origins");
    require_rows(p, "points", n, "origins");
    require_rows(nv, "normals", n, "origins");
    if (p.single() != nv.single())
      throw py::value_error("points and normals: give both as (n, 3) arrays, or both as one 3-vector (one plane)");
    one_plane = p.single();
  }

  [[nodiscard]] std::pair<Ray, Plane> query(std::size_t i) const { return {Ray{o.row(i), d.row(i)}, Plane{p.row(i), nv.row(i)}}; }

  // batch(rays, planes, begin, count) over chunks of the queries, `planes` the one Plane or a PlaneBatch.
  template <class Batch>
  void certified_chunks(Batch&& batch) {
    in_chunks(n, {&o, &d, &p, &nv}, [&](std::size_t begin, std::size_t end) {
      const RayBatch rays = ray_batch(o, d, begin, end);
      if (one_plane) {
        batch(rays, Plane{p.row(0), nv.row(0)}, begin, end - begin);
      } else {
        const auto pc = p.columns(begin, end), nc = nv.columns(begin, end);
        batch(rays, PlaneBatch{pc[0], pc[1], pc[2], nc[0], nc[1], nc[2]}, begin, end - begin);
      }
    });
  }

  // answer(i, ray, plane) for every valid row on threads, valid[i] set for each row.
  template <class Answer>
  void scalar_rows(std::span<bool> valid, unsigned threads, std::size_t grain, Answer&& answer) const {
    parallel_for(n, threads, grain, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const auto [ray, plane] = query(i);
        valid[i] = !validate(ray, plane).has_value();
        if (valid[i]) answer(i, ray, plane);
      }
    });
  }

  // Gives each invalid row its definite answer (`mark(i)`), and raises ValueError for the first one under
  // errors="raise" (after the rows are marked: the arrays are never left half written).
  template <class Mark>
  void finish_invalid_rows(std::span<const bool> valid, ErrorPolicy policy, Mark&& mark) const {
    std::optional<std::pair<std::size_t, std::string>> first_invalid;
    for (std::size_t i = 0; i < n; ++i) {
      if (valid[i]) continue;
      mark(i);
      if (!first_invalid) {
        const auto [ray, plane] = query(i);
        first_invalid.emplace(i, validate(ray, plane).value_or("invalid input"));
      }
    }
    if (first_invalid && policy == ErrorPolicy::raise)
      throw invalid_input(row_error(first_invalid->first, one_plane, first_invalid->second));
  }
};

shown::IntersectionArrays intersect_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                             shown::ArrayLike3 points, shown::ArrayLike3 normals,
                                             const std::string& path_name, const std::string& errors,
                                             std::optional<unsigned> threads, bool want_stats) {
  const Path path = path_from(path_name);
  const ErrorPolicy policy = error_policy_from(errors);
  PlaneQueries q(origins, directions, points, normals);
  if (want_stats && path != Path::certified) throw py::value_error("stats: only the certified path has stages");

  auto relation = new_array<std::uint8_t>(q.n);
  auto t = new_array<double>(q.n);
  auto valid = new_array<bool>(q.n);
  const std::span<std::uint8_t> relation_out = span_of(relation);
  const std::span<double> t_out = span_of(t);
  const std::span<bool> valid_out = span_of(valid);
  BatchStats stats;
  {
    py::gil_scoped_release release;
    if (path == Path::certified) {
      const BatchOptions options{threads_from(threads), want_stats ? &stats : nullptr};
      q.certified_chunks([&](const RayBatch& rays, const auto& planes, std::size_t begin, std::size_t m) {
        intersect_batch(rays, planes,
                        IntersectionBatch{{reinterpret_cast<Relation*>(relation_out.data()) + begin, m},
                                          t_out.subspan(begin, m), valid_out.subspan(begin, m)},
                        options);
      });
    } else {
      q.scalar_rows(valid_out, threads_from(threads), grain_of(path), [&](std::size_t i, const Ray& ray, const Plane& plane) {
        const Intersection x = path == Path::exact ? intersect_exact(ray, plane) : intersect_naive(ray, plane);
        relation_out[i] = static_cast<std::uint8_t>(x.relation);
        t_out[i] = x.t;
      });
    }
    // Invalid rows get a definite answer: no relation, t NaN.
    q.finish_invalid_rows(valid_out, policy, [&](std::size_t i) {
      relation_out[i] = invalid_code;
      t_out[i] = nan;
    });
  }
  return types().intersection_arrays(relation, t, valid, want_stats ? py::object(stats_to_python(stats)) : py::none());
}

shown::RelationArrays relation_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                        shown::ArrayLike3 points, shown::ArrayLike3 normals,
                                        const std::string& path_name, const std::string& errors,
                                        std::optional<unsigned> threads, bool want_stats) {
  const Path path = path_from(path_name, false);
  const ErrorPolicy policy = error_policy_from(errors);
  PlaneQueries q(origins, directions, points, normals);
  if (want_stats && path != Path::certified) throw py::value_error("stats: only the certified path has stages");

  auto relation = new_array<std::uint8_t>(q.n);
  auto valid = new_array<bool>(q.n);
  const std::span<std::uint8_t> relation_out = span_of(relation);
  const std::span<bool> valid_out = span_of(valid);
  BatchStats stats;
  {
    py::gil_scoped_release release;
    if (path == Path::certified) {
      const BatchOptions options{threads_from(threads), want_stats ? &stats : nullptr};
      q.certified_chunks([&](const RayBatch& rays, const auto& planes, std::size_t begin, std::size_t m) {
        relation_batch(rays, planes,
                       RelationBatch{{reinterpret_cast<Relation*>(relation_out.data()) + begin, m},
                                     valid_out.subspan(begin, m)},
                       options);
      });
    } else {  // the exact relation: intersect_exact's, per row
      q.scalar_rows(valid_out, threads_from(threads), exact_grain, [&](std::size_t i, const Ray& ray, const Plane& plane) {
        relation_out[i] = static_cast<std::uint8_t>(intersect_exact(ray, plane).relation);
      });
    }
    q.finish_invalid_rows(valid_out, policy, [&](std::size_t i) { relation_out[i] = invalid_code; });
  }
  py::object stats_py = py::none();
  if (want_stats) {
    py::dict dict = stats_to_python(stats);
    dict.attr("pop")("t");  // a relation has no t
    stats_py = dict;
  }
  return types().relation_arrays(relation, valid, stats_py);
}

// nearest_hit_batch on planes within per-ray intervals (docs/contract.md §8): each row through the plane set's
// interval query (certified) or its reference (exact), on threads; the vectorized whole-ray path is not used.
py::object nearest_plane_batch_within(py::handle origins, py::handle directions, py::handle planes_arg,
                                      py::handle t_min, py::handle t_max, const std::string& path_name,
                                      const std::string& errors, std::optional<unsigned> threads, bool want_stats) {
  if (want_stats) throw py::value_error("stats: only for the whole ray");
  const RayRows b(origins, directions, t_min, t_max, py::none(), path_name, errors);
  std::optional<raykernel::PlaneSet> storage;
  const raykernel::PlaneSet& planes = planes_from(planes_arg, storage);  // validated: "plane 3: ..."
  const NearestColumns c = nearest_columns(b, threads, b.exact ? 16 : 1024, [&](const Ray& ray, const RayInterval& i) {
    return b.exact ? nearest_hit_exact(ray, i, planes.planes()) : nearest_hit(ray, i, planes);
  });
  return types().nearest_hit_arrays(c.index, c.t, c.valid, py::none());
}

py::object nearest_hit_batch_py(py::handle origins, py::handle directions, py::handle planes_arg, py::handle rule,
                                py::handle t_min, py::handle t_max, const std::string& path_name,
                                const std::string& errors, std::optional<unsigned> threads, bool want_stats) {
  if (want_stats && (py::isinstance<PythonMesh>(planes_arg) || is_sphere_set(planes_arg)))
    throw py::value_error("stats: only for planes");
  if (py::isinstance<PythonMesh>(planes_arg))
    return nearest_hit_mesh_batch(origins, directions, planes_arg.cast<const PythonMesh&>(), t_min, t_max, rule,
                                  path_name, errors, threads);
  require_no_rule(rule, planes_arg);
  if (is_sphere_set(planes_arg))
    return nearest_hit_spheres_batch(origins, directions, planes_arg.cast<const raykernel::SphereSet&>(), t_min, t_max,
                                     path_name, errors, threads);
  if (!is_whole_ray(t_min, t_max)) return nearest_plane_batch_within(origins, directions, planes_arg, t_min, t_max,
                                                                     path_name, errors, threads, want_stats);
  const Path path = path_from(path_name);
  const ErrorPolicy policy = error_policy_from(errors);
  ColumnsView o(origins, "origins"), d(directions, "directions");
  const std::size_t n = o.rows();
  require_rows(d, "directions", n, "origins");
  std::optional<raykernel::PlaneSet> storage;
  const raykernel::PlaneSet& planes = planes_from(planes_arg, storage);  // validated: "plane 3: ..."
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
                         hits[i] = path == Path::exact ? nearest_hit_exact(ray, planes.planes())
                                                       : nearest_hit_naive(ray, planes.planes());
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
  m.attr("INVALID_RELATION_CODE") = invalid_code;

  m.def("intersect_batch", with_progress(&intersect_batch_py), py::arg("origins"), py::arg("directions"), py::arg("points"),
        py::arg("normals"), py::kw_only(), py::arg("path") = "certified", py::arg("errors") = "raise",
        py::arg("threads") = py::none(), py::arg("stats") = false, py::arg("progress") = py::none(),
        R"doc(``intersect`` over arrays: query i is (ray i, plane i), or (ray i, the one plane).

``origins``, ``directions``: (n, 3) arrays of real numbers (float64, or any integer or floating dtype, or
lists: read as float64; complex, bool, str, object, datetime, structured and masked arrays raise ``TypeError``);
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
decided. Releases the GIL.

Ctrl-C stops a long call (``KeyboardInterrupt``, within a block of rows); ``progress``, None or a callable, is
called with (done, total) about every 0.1 s and at the end (an exception it raises stops the call too); the
certified path on planes is one vectorized C++ call, which reports nothing.)doc");

  m.def("relation_batch", with_progress(&relation_batch_py), py::arg("origins"), py::arg("directions"), py::arg("points"),
        py::arg("normals"), py::kw_only(), py::arg("path") = "certified", py::arg("errors") = "raise",
        py::arg("threads") = py::none(), py::arg("stats") = false, py::arg("progress") = py::none(),
        R"doc(``relation`` over arrays: the relation alone, no t rounded (the cheapest certified answer).

Arguments as in ``intersect_batch``; ``path`` is "certified" (the C++ batch API: the binary64 filter as one
vectorized loop, the cascade for the rest) or "exact" (rational arithmetic per row, on threads). Returns
``RelationArrays(relation, valid, stats)``: ``relation`` uint8 codes (``INVALID_RELATION_CODE`` where the row is
invalid), ``valid`` bool, and with ``stats=True`` how many rows each stage decided (``{"relation": {...}}``).
Every relation is ``relation``'s (and ``intersect``'s). Releases the GIL.

Ctrl-C stops a long call (``KeyboardInterrupt``, within a block of rows); ``progress``, None or a callable, is
called with (done, total) about every 0.1 s and at the end (an exception it raises stops the call too); the
certified path on planes is one vectorized C++ call, which reports nothing.)doc");

  // `progress` before `stats`, which only plane scenes take (the stubs' two overloads list them in this order).
  m.def(
      "nearest_hit_batch",
      [](shown::ArrayLike3 origins, shown::ArrayLike3 directions, shown::Scene scene, shown::OptionalRule rule,
         shown::ScalarOrArray t_min, shown::ScalarOrArray t_max, const std::string& path, const std::string& errors,
         std::optional<unsigned> threads, shown::Progress progress, bool stats) -> shown::NearestHitArrays {
        const ProgressScope scope(progress);
        return nearest_hit_batch_py(origins, directions, scene, rule, t_min, t_max, path, errors, threads, stats);
      },
      py::arg("origins"), py::arg("directions"), py::arg("scene"), py::kw_only(), py::arg("rule") = py::none(),
      py::arg("t_min") = 0.0, py::arg("t_max") = std::numeric_limits<double>::infinity(), py::arg("path") = "certified",
      py::arg("errors") = "raise", py::arg("threads") = py::none(), py::arg("progress") = py::none(),
      py::arg("stats") = false,
      R"doc(``nearest_hit`` for every ray: the first plane of ``scene`` each ray meets (or triangle, for a mesh).

``origins``, ``directions``: (n, 3) arrays; ``scene``: a ``PlaneSet`` (read and validated once) or a sequence
of ``(point, normal)`` pairs. Returns ``NearestHitArrays(plane, t, valid, stats)``: ``plane`` int64, the
index of the nearest plane hit or -1 for a miss (and for invalid rays), ``t`` float64 (NaN for a miss),
``valid`` bool. ``path``, ``errors``, ``threads`` and ``stats`` as in ``intersect_batch``; a ``PlaneSet`` is
prepared once, a sequence is prepared for the call; an invalid plane
always raises ("plane 3: plane normal is the zero vector"), an invalid ray raises "ray 17: ..." unless
errors="mask". Releases the GIL.

``scene`` may be a ``raykernel.Mesh`` instead: then each ray's ``nearest_hit(ray, mesh, rule=rule)``, as
``MeshHitArrays(triangle, t, location, barycentric, valid)``: ``triangle`` int64 (-1 for a miss), ``t``
float64 and ``barycentric`` (n, 3) float64 (NaN for a miss), ``location`` uint8 ``TriangleLocation`` codes
(NONE for a miss, ``INVALID_RELATION_CODE`` for invalid rays); ``path`` "certified" (the BVH) or "exact"
(brute force in rationals); rays spread over threads. A ``raykernel.SphereSet`` gives ``SphereHitArrays(sphere,
t, valid)`` (``sphere`` int64, -1 for a miss). Every scene takes ``t_min`` and ``t_max``, one number each or
one per ray (a 1-D array of n), compared exactly (docs/contract.md §8); on planes another interval than the whole
ray runs each row through the plane set's interval query on threads (no ``stats``, no naive path).

Ctrl-C stops a long call (``KeyboardInterrupt``, within a block of rows); ``progress``, None or a callable, is
called with (done, total) about every 0.1 s and at the end (an exception it raises stops the call too); the
certified path on planes is one vectorized C++ call, which reports nothing.)doc");
}

}  // namespace raykernel::python
