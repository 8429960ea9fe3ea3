// Rays with an interval, any-hit, segments and all hits from Python, over arrays (docs/contract.md §8):
// all_hits, occluded_batch, occluded_segment_batch, crossings_batch (raykernel/occlusion.hpp). The scalar
// occluded and occluded_segment are in bind_mesh.cpp.
#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"
#include "mesh.hpp"
#include "ray_batch.hpp"
#include "sphere_set.hpp"

#include <raykernel/occlusion.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace raykernel::python {
namespace {

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
  return types().mesh_hits(list, hits.crossings);
}

// OcclusionArrays of a ray batch (rows: a ray and its interval) or a segment batch (rows: p and q) over a Mesh or a
// SphereSet: on_spheres(spheres, x, y) or on_mesh(mesh, rule, x, y) for each valid row.
template <class Batch, class OnSpheres, class OnMesh>
py::object occlusion_arrays(const Batch& b, py::handle scene, py::handle rule, std::optional<unsigned> threads,
                            OnSpheres&& on_spheres, OnMesh&& on_mesh) {
  auto blocked = new_array<bool>(b.rows());
  auto valid = new_array<bool>(b.rows());
  const std::span<bool> blocked_out = span_of(blocked);
  const std::size_t grain = b.exact ? 4 : 256;
  if (is_sphere_set(scene)) {
    require_no_rule(rule, scene);
    const auto& spheres = scene.cast<const raykernel::SphereSet&>();
    b.run(span_of(valid), threads, grain, [&](std::size_t i, const auto& x, const auto& y, bool ok) {
      blocked_out[i] = ok && on_spheres(spheres, x, y);
    });
  } else {
    const PythonMesh& mesh = mesh_from(scene, "a raykernel.Mesh or a raykernel.SphereSet");
    const TriangleRule chosen = rule_or_owned(rule);
    b.run(span_of(valid), threads, grain, [&](std::size_t i, const auto& x, const auto& y, bool ok) {
      blocked_out[i] = ok && on_mesh(mesh, chosen, x, y);
    });
  }
  return types().occlusion_arrays(blocked, valid);
}

shown::OcclusionArrays occluded_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                         shown::MeshOrSpheres scene, shown::ScalarOrArray t_min,
                                         shown::ScalarOrArray t_max, shown::OptionalRule rule,
                                         const std::string& path_name, const std::string& errors,
                                         std::optional<unsigned> threads) {
  const RayRows b(origins, directions, t_min, t_max, rule, path_name, errors);
  return occlusion_arrays(
      b, scene, rule, threads,
      [&](const raykernel::SphereSet& spheres, const Ray& ray, const RayInterval& interval) {
        return occluded_spheres(ray, interval, spheres, b.exact);
      },
      [&](const PythonMesh& mesh, TriangleRule chosen, const Ray& ray, const RayInterval& interval) {
        return b.exact ? occluded_exact(ray, interval, mesh.mesh(), chosen)
                       : occluded(ray, interval, mesh.prepared(), chosen);
      });
}

shown::OcclusionArrays occluded_segment_batch_py(shown::ArrayLike3 ps, shown::ArrayLike3 qs, shown::MeshOrSpheres scene,
                                                 shown::OptionalRule rule, const std::string& path_name,
                                                 const std::string& errors, std::optional<unsigned> threads) {
  const SegmentRows b(ps, qs, path_name, errors);
  return occlusion_arrays(
      b, scene, rule, threads,
      [&](const raykernel::SphereSet& spheres, const Vec3& p, const Vec3& q) {
        return occluded_segment_spheres(p, q, spheres, b.exact);
      },
      [&](const PythonMesh& mesh, TriangleRule chosen, const Vec3& p, const Vec3& q) {
        return b.exact ? occluded_exact(p, q, mesh.mesh(), chosen) : occluded(p, q, mesh.prepared(), chosen);
      });
}

shown::CrossingArrays crossings_batch_py(shown::ArrayLike3 origins, shown::ArrayLike3 directions,
                                         const PythonMesh& mesh, shown::ScalarOrArray t_min, shown::ScalarOrArray t_max,
                                         shown::OptionalRule rule, const std::string& path_name,
                                         const std::string& errors, std::optional<unsigned> threads) {
  const RayRows b(origins, directions, t_min, t_max, rule, path_name, errors);
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
  return types().crossing_arrays(hits, crossings, valid);
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
  m.def(
      "occluded_batch", with_progress(&occluded_batch_py), py::arg("origins"), py::arg("directions"), py::arg("scene"),
      py::kw_only(), py::arg("t_min") = 0.0, py::arg("t_max") = inf, py::arg("rule") = py::none(),
      py::arg("path") = "certified", py::arg("errors") = "raise", py::arg("threads") = py::none(),
      py::arg("progress") = py::none(),
      R"doc(``occluded`` over (n, 3) arrays of ray origins and directions, on threads with the GIL released: shadow rays
in bulk. ``t_min``, ``t_max``: one number for every ray, or a 1-D array of n (each ray its own interval).
Returns ``OcclusionArrays(occluded, valid)`` (bool). ``errors``: "raise" (default) raises ``ValueError`` naming
the first bad row ("ray 3: t_min is greater than t_max"), "mask" answers the others. ``path``, ``rule``,
``threads``, ``progress`` as ``inside_batch``.)doc");
  m.def("occluded_segment_batch", with_progress(&occluded_segment_batch_py), py::arg("p"), py::arg("q"),
        py::arg("scene"), py::kw_only(), py::arg("rule") = py::none(), py::arg("path") = "certified",
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
