// spawn and spawn_to (docs/contract.md §9): the origin of a secondary ray that never re-hits the triangle it
// leaves, in binary64 or binary32; spawn also from a sphere (docs/contract.md, "Spawning from a sphere").
#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/spawn.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace raykernel::python {
namespace {

// The hit point: a ray (two vectors: P is where its line crosses the triangle's plane, exactly) or a point
// (three numbers).
HitPoint hit_from(py::handle hit) {
  if (py::len(hit) == 2) return HitPoint::crossing(ray_from(hit, "hit"));
  return HitPoint::at(vec3_from(hit, "hit"));
}

OriginFormat format_from(const std::string& format) {
  if (format == "binary64") return OriginFormat::binary64;
  if (format == "binary32") return OriginFormat::binary32;
  throw py::value_error("format: expected 'binary64' or 'binary32', got '" + format + "'");
}

py::object to_python(const SpawnedOrigin& o) {
  return types().spawned_origin(::raykernel::python::to_python(o.origin), py::int_(o.steps));
}

constexpr const char* hit_doc = R"doc(

``hit`` is a ray ``(origin, direction)`` — P is where its line crosses the triangle's plane, exactly (a rational
point, whatever the sign of t) — or a point of three numbers (P itself). ``triangle`` is ``(a, b, c)`` with
N = (b − a) × (c − a) ≠ 0. ``format`` is "binary64" or "binary32" (a float renderer's origin, rounded straight
from the exact P). Returns ``SpawnedOrigin(origin, steps)``: P rounded to nearest in the format when that point
is strictly on side s, else moved the fewest steps through consecutive values of the format along the axis of
the largest |N_i| until it is (``steps`` = k, exact). Raises ``ValueError`` (``raykernel.InvalidInput``) naming
the reason: a non-finite number, a zero direction, a degenerate triangle, a ray parallel to the plane, )doc";

using TriangleSpawn = SpawnedOrigin (*)(const HitPoint&, const Triangle&, const Vec3&, OriginFormat);

// spawn or spawn_to over arrays: row i is the hit ray (origins[i], directions[i]) on the triangle (a[i], b[i],
// c[i]) and the new direction or target vectors[i]. An invalid row (the kernel's invalid_input) is named or masked.
shown::SpawnArrays spawn_batch_py(TriangleSpawn kernel, const char* vectors_name, shown::ArrayLike3 origins,
                                  shown::ArrayLike3 directions, shown::ArrayLike3 a, shown::ArrayLike3 b,
                                  shown::ArrayLike3 c, shown::ArrayLike3 vectors, const std::string& format,
                                  const std::string& errors, std::optional<unsigned> threads) {
  const OriginFormat f = format_from(format);
  const ErrorPolicy policy = error_policy_from(errors);
  const ColumnsView o(origins, "origins"), d(directions, "directions"), va(a, "a"), vb(b, "b"), vc(c, "c"),
      w(vectors, vectors_name);
  const std::size_t n = o.rows();
  require_rows(d, "directions", n, "origins");
  require_rows(va, "a", n, "origins");
  require_rows(vb, "b", n, "origins");
  require_rows(vc, "c", n, "origins");
  require_rows(w, vectors_name, n, "origins");
  py::array_t<double> origin({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto steps = new_array<std::uint64_t>(n);
  auto valid = new_array<bool>(n);
  double* const origin_out = origin.mutable_data();
  const std::span<std::uint64_t> steps_out = span_of(steps);
  const std::span<bool> valid_out = span_of(valid);
  std::vector<std::string> reasons(n);  // only invalid rows hold one
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    parallel_for(n, threads_from(threads), 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        try {
          const SpawnedOrigin s =
              kernel(HitPoint::crossing(Ray{o.row(i), d.row(i)}), Triangle{va.row(i), vb.row(i), vc.row(i)}, w.row(i), f);
          origin_out[3 * i] = s.origin.x;
          origin_out[3 * i + 1] = s.origin.y;
          origin_out[3 * i + 2] = s.origin.z;
          steps_out[i] = s.steps;
          valid_out[i] = true;
        } catch (const invalid_input& e) {
          for (std::size_t k = 0; k < 3; ++k) origin_out[3 * i + k] = std::numeric_limits<double>::quiet_NaN();
          steps_out[i] = 0;
          valid_out[i] = false;
          reasons[i] = e.what();
        }
      }
    });
    if (const std::optional<std::size_t> i = first_invalid_row(valid_out))
      error = "row " + std::to_string(*i) + ": " + reasons[*i];
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return py::module_::import("raykernel._types").attr("SpawnArrays")(origin, steps, valid);
}

}  // namespace

void bind_spawn(py::module_& m) {
  static const std::string spawn_doc =
      std::string(R"doc(The origin of a new ray along ``direction`` leaving the triangle at the hit point P, on the side s = sign(w·N) it leaves
towards: the ray from it never hits the triangle (docs/contract.md §9).)doc") +
      hit_doc + "w parallel to the plane, a rounded point that overflows the format, or no origin on the side." +
      R"doc(

Leaving a sphere: ``triangle`` is a ``raykernel.Sphere`` and ``hit`` the point p the renderer holds (three numbers;
it need not lie on the sphere). With N = p − c and s = sign(w·N), the origin is strictly outside with
w·(origin − c) ≥ 0 when w leaves outward — the new ray never meets the sphere — and strictly inside when inward —
it meets it once, where it leaves (proofs/sphere/SphereSpawn.v); the fewest steps along the axis of the largest
|N_i| (outward: among the axes with w_i·N_i > 0). Raises ``ValueError`` for a radius not positive, p = c, w
tangent at p (w·N = 0), or no origin along the axis.)doc";
  static const std::string spawn_to_doc =
      std::string(R"doc(The origin of a shadow ray towards the point ``target`` q, on q's side of the triangle's plane: the segment from it to
q never meets the triangle (docs/contract.md §9).)doc") +
      hit_doc + "q on the plane, a rounded point that overflows the format, or no origin on the side.";
  // spawn_to through the one definition a triangle's entry point of this shape needs.
  const auto define = [&m](const char* name, const char* third, const std::string& doc,
                           SpawnedOrigin (*kernel)(const HitPoint&, const Triangle&, const Vec3&, OriginFormat)) {
    m.def(
        name,
        [third, kernel](shown::HitLike hit, shown::TriangleLike triangle, shown::Vec3Like vector,
                        const std::string& format) -> shown::SpawnedOrigin {
          const HitPoint h = hit_from(hit);
          const Triangle t = triangle_from(triangle);
          const Vec3 v = vec3_from(vector, third);
          const OriginFormat f = format_from(format);
          SpawnedOrigin o{};
          {
            py::gil_scoped_release release;
            o = kernel(h, t, v, f);
          }
          return to_python(o);
        },
        py::arg("hit"), py::arg("triangle"), py::arg(third), py::kw_only(), py::arg("format") = "binary64",
        doc.c_str());
  };
  define("spawn_to", "target", spawn_to_doc, &spawn_to);
  // spawn also leaves a sphere: the source a raykernel.Sphere and the hit a point (the sphere's rule,
  // raykernel/spawn.hpp and docs/contract.md's "Spawning from a sphere").
  m.def(
      "spawn",
      [](shown::HitLike hit, shown::SpawnSurfaceLike source, shown::Vec3Like direction,
         const std::string& format) -> shown::SpawnedOrigin {
        const Vec3 w = vec3_from(direction, "direction");
        const OriginFormat f = format_from(format);
        SpawnedOrigin o{};
        if (primitive_kind(source) == PrimitiveKind::sphere) {
          if (py::len(hit) != 3)
            throw py::value_error("hit: leaving a sphere, give the hit point (three numbers), not a ray");
          const Vec3 p = vec3_from(hit, "hit");
          const Sphere sphere = sphere_from(source, "sphere");
          py::gil_scoped_release release;
          o = spawn(p, sphere, w, f);
        } else {
          const HitPoint h = hit_from(hit);
          const Triangle t = triangle_from(source);
          py::gil_scoped_release release;
          o = spawn(h, t, w, f);
        }
        return to_python(o);
      },
      py::arg("hit"), py::arg("triangle"), py::arg("direction"), py::kw_only(), py::arg("format") = "binary64",
      spawn_doc.c_str());

  constexpr const char* batch_doc = R"doc( over arrays, on threads with the GIL released: row i is the hit ray
(``origins[i]``, ``directions[i]``) — P is where its line crosses the plane of the triangle (``a[i]``, ``b[i]``,
``c[i]``), exactly — and the row's vector. Returns ``SpawnArrays(origin, steps, valid)``: ``origin`` (n, 3) float64
(NaN for an invalid row; binary32 values exactly with ``format="binary32"``), ``steps`` uint64, ``valid`` bool.
``errors``: "raise" (default) raises ``ValueError`` naming the first bad row ("row 3: the triangle is
degenerate ..."), "mask" answers the others. ``threads``, ``progress`` as ``inside_batch``.)doc";
  static const std::string spawn_batch_doc =
      std::string("``spawn`` (a triangle's: the new ray along ``directions_out[i]``)") + batch_doc;
  static const std::string spawn_to_batch_doc =
      std::string("``spawn_to`` (shadow rays towards ``targets[i]``)") + batch_doc;
  m.def("spawn_batch",
        with_progress(+[](shown::ArrayLike3 origins, shown::ArrayLike3 directions, shown::ArrayLike3 a,
                          shown::ArrayLike3 b, shown::ArrayLike3 c, shown::ArrayLike3 directions_out,
                          const std::string& format, const std::string& errors, std::optional<unsigned> threads) {
          return spawn_batch_py(&spawn, "directions_out", origins, directions, a, b, c, directions_out, format, errors,
                                threads);
        }),
        py::arg("origins"), py::arg("directions"), py::arg("a"), py::arg("b"), py::arg("c"), py::arg("directions_out"),
        py::kw_only(), py::arg("format") = "binary64", py::arg("errors") = "raise", py::arg("threads") = py::none(),
        py::arg("progress") = py::none(), spawn_batch_doc.c_str());
  m.def("spawn_to_batch",
        with_progress(+[](shown::ArrayLike3 origins, shown::ArrayLike3 directions, shown::ArrayLike3 a,
                          shown::ArrayLike3 b, shown::ArrayLike3 c, shown::ArrayLike3 targets,
                          const std::string& format, const std::string& errors, std::optional<unsigned> threads) {
          return spawn_batch_py(&spawn_to, "targets", origins, directions, a, b, c, targets, format, errors, threads);
        }),
        py::arg("origins"), py::arg("directions"), py::arg("a"), py::arg("b"), py::arg("c"), py::arg("targets"),
        py::kw_only(), py::arg("format") = "binary64", py::arg("errors") = "raise", py::arg("threads") = py::none(),
        py::arg("progress") = py::none(), spawn_to_batch_doc.c_str());
}

}  // namespace raykernel::python
