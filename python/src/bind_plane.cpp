// Scalar queries: one ray and one plane (docs/contract.md §1), one triangle (§6) or one sphere (§10), plain Python
// values in and out. Each function takes the primitive as its second argument and answers for what it is
// (primitive_kind: a raykernel.Sphere is a sphere, a 2-sequence a plane, a 3-sequence a triangle); the triangle
// options are keyword-only.
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/triangle.hpp>

#include <optional>
#include <string>

namespace raykernel::python {
namespace {

// The triangle options from the keyword arguments; for a plane or a sphere they must be left at their defaults.
TriangleOptions triangle_options(py::handle rule, bool t, bool barycentric) {
  return {rule_or_owned(rule), t, barycentric};
}
void require_no_triangle_options(PrimitiveKind kind, py::handle rule, bool t = true, bool barycentric = true) {
  const bool plane = kind == PrimitiveKind::plane;
  if (!rule.is_none())
    throw py::value_error(std::string("rule: only triangles have rules, the second argument is a ") +
                          (plane ? "plane" : "sphere"));
  if (!t || !barycentric)
    throw py::value_error(std::string("t, barycentric: only for triangles (") +
                          (plane ? "a plane's t is" : "a sphere's roots are") + " always computed)");
}

// on_plane(plane), on_triangle(triangle) or on_sphere(sphere), for what `primitive` is (primitive_kind). `ray`
// is read before the primitive's values.
template <class OnPlane, class OnTriangle, class OnSphere>
auto for_primitive(py::handle primitive, py::handle ray, OnPlane&& on_plane, OnTriangle&& on_triangle,
                   OnSphere&& on_sphere) {
  const PrimitiveKind kind = primitive_kind(primitive);
  const Ray r = ray_from(ray);
  if (kind == PrimitiveKind::triangle) return on_triangle(r, triangle_from(primitive));
  if (kind == PrimitiveKind::sphere) return on_sphere(r, sphere_from(primitive));
  return on_plane(r, plane_from(primitive));
}

// Exact answers take microseconds: release the GIL for them.
template <class F>
auto without_gil(F&& f) {
  py::gil_scoped_release release;
  return f();
}

}  // namespace

void bind_ray_plane(py::module_& m) {
  m.def(
      "validate",
      [](shown::RayLike ray, shown::PrimitiveLike primitive) -> std::optional<std::string> {
        auto reason = [](const Ray& r, const auto& p) { return validate(r, p); };
        return for_primitive(primitive, ray, reason, reason, reason);
      },
      py::arg("ray"), py::arg("primitive"),
      R"doc(The reason ``ray`` and ``primitive`` (a plane, a triangle or a ``raykernel.Sphere``) are invalid input,
or None when they are valid.

Invalid input has no answer: a NaN or infinite component, a zero direction or a zero normal, a sphere radius
that is not positive. The reason names the field, e.g. ``"ray direction is the zero vector"``, ``"plane point
y is NaN"`` or ``"sphere radius is not positive"``; it is the message the other functions raise
``ValueError`` (``raykernel.InvalidInput``) with. A degenerate triangle (collinear or repeated vertices) is
valid: its relation is DEGENERATE.)doc");

  m.def(
      "intersect",
      [](shown::RayLike ray, shown::PrimitiveLike primitive, shown::OptionalRule rule, bool t,
         bool barycentric) -> shown::PrimitiveIntersection {
        return for_primitive(
            primitive, ray,
            [&](const Ray& r, const Plane& p) {
              require_no_triangle_options(PrimitiveKind::plane, rule, t, barycentric);
              return to_python(intersect(r, p));
            },
            [&](const Ray& r, const Triangle& tri) {
              return to_python(intersect(r, tri, triangle_options(rule, t, barycentric)));
            },
            [&](const Ray& r, const Sphere& s) {
              require_no_triangle_options(PrimitiveKind::sphere, rule, t, barycentric);
              return to_python(intersect(r, s));
            });
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t") = true,
      py::arg("barycentric") = true,
      R"doc(The certified intersection of ``ray`` with a plane, a triangle or a sphere: the exact answer, fast.

``ray`` is ``(origin, direction)``; ``primitive`` is a plane ``(point, normal)``, a triangle ``(a, b, c)``,
each vector a sequence of three numbers (``raykernel.Ray``, ``Plane`` and ``Triangle`` are such tuples), or
a ``raykernel.Sphere(center, radius)`` (only that type: a bare pair is a plane).

Plane: with ``den = d·n`` and ``num = (p − o)·n`` evaluated exactly over the reals, the relation is HIT
(den ≠ 0, num/den ≥ 0), BEHIND (den ≠ 0, num/den < 0), PARALLEL (den = 0, num ≠ 0) or IN_PLANE (den = 0,
num = 0), and ``t`` is num/den rounded to the nearest double, ties to even (±inf beyond the double range, a
nonzero t that rounds to zero keeps its sign), NaN for PARALLEL and IN_PLANE (docs/contract.md §1). Returns
``Intersection(relation, t)``.

Triangle (docs/contract.md §6): with N = (b − a) × (c − a), den = d·N, num = (a − o)·N and the edge functions
πa, πb, πc (summing to den), returns ``TriangleIntersection(relation, location, owned, t, barycentric)``:
``relation`` under ``rule`` ("owned", the default: watertight, each shared edge and vertex of a closed mesh
belongs to exactly one triangle; or "closed": the triangle with its boundary) is HIT, BEHIND, MISS,
DEGENERATE, PARALLEL or COPLANAR; ``location`` says where the line crosses the plane (INSIDE, EDGE_AB, ...,
VERTEX_C, OUTSIDE; NONE when den = 0); ``owned`` whether the owned rule lets the line through; ``t`` = num/den
and ``barycentric`` = (πa, πb, πc)/den each rounded to nearest (NaN when den = 0, or when ``t=False`` /
``barycentric=False`` skip them).

Sphere (docs/contract.md §10): with f = o − c, A = d·d, B = d·f, C = f·f − r² and D = B² − A·C exactly, returns
``SphereIntersection(origin, relation, t1, t2)``: ``origin`` INSIDE (C < 0), ON_SURFACE (C = 0) or OUTSIDE
(C > 0); ``relation`` MISS (D < 0), TANGENT (D = 0) or CROSS (D > 0); ``t1`` ≤ ``t2`` the roots
(−B ∓ √D)/A each rounded to the nearest double, ties to even (both the root −B/A for TANGENT, NaN for MISS).

Raises ``ValueError`` (``raykernel.InvalidInput``) naming the field for invalid input.)doc");

  m.def(
      "relation",
      [](shown::RayLike ray, shown::PrimitiveLike primitive, shown::OptionalRule rule) -> shown::PrimitiveRelation {
        return for_primitive(
            primitive, ray,
            [&](const Ray& r, const Plane& p) {
              require_no_triangle_options(PrimitiveKind::plane, rule);
              return to_python(relation(r, p));
            },
            [&](const Ray& r, const Triangle& tri) { return to_python(relation(r, tri, rule_or_owned(rule))); },
            [&](const Ray& r, const Sphere& s) {
              require_no_triangle_options(PrimitiveKind::sphere, rule);
              return to_python(relation(r, s));
            });
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(),
      R"doc(The certified relation alone, nothing rounded: the yes/no predicate, cheaper than ``intersect``.

Plane: a ``Relation`` (HIT, BEHIND, PARALLEL, IN_PLANE), ``intersect(ray, plane).relation`` exactly.
Triangle: ``TriangleClassification(relation, location, owned)`` under ``rule`` ("owned" or "closed"), the
same as ``intersect``'s. Sphere: ``SphereClassification(origin, relation)``, the same as ``intersect``'s.
Raises ``ValueError`` naming the field for invalid input.)doc");

  m.def(
      "intersect_exact",
      [](shown::RayLike ray, shown::PrimitiveLike primitive, shown::OptionalRule rule, bool t,
         bool barycentric) -> shown::PrimitiveIntersection {
        return for_primitive(
            primitive, ray,
            [&](const Ray& r, const Plane& p) {
              require_no_triangle_options(PrimitiveKind::plane, rule, t, barycentric);
              return to_python(without_gil([&] { return intersect_exact(r, p); }));
            },
            [&](const Ray& r, const Triangle& tri) {
              const TriangleOptions options = triangle_options(rule, t, barycentric);
              return to_python(without_gil([&] { return intersect_exact(r, tri, options); }));
            },
            [&](const Ray& r, const Sphere& s) {
              require_no_triangle_options(PrimitiveKind::sphere, rule, t, barycentric);
              return to_python(without_gil([&] { return intersect_exact(r, s); }));
            });
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t") = true,
      py::arg("barycentric") = true,
      R"doc(The reference answer, from exact rational arithmetic (GMP) and MPFR rounding: slow (microseconds)
and obviously right. The same answer as ``intersect``, bit for bit, for a plane, a triangle (same options) or
a sphere. Releases the GIL.)doc");

  m.def(
      "intersect_exact_rational",
      [](shown::RayLike ray, shown::PrimitiveLike primitive,
         shown::OptionalRule rule) -> shown::ExactPrimitiveIntersection {
        return for_primitive(
            primitive, ray,
            [&](const Ray& r, const Plane& p) {
              require_no_triangle_options(PrimitiveKind::plane, rule);
              return to_python(without_gil([&] { return intersect_exact_rational(r, p); }));
            },
            [&](const Ray& r, const Triangle& tri) {
              const TriangleRule chosen = rule_or_owned(rule);
              return to_python(without_gil([&] { return intersect_exact_rational(r, tri, chosen); }));
            },
            [&](const Ray& r, const Sphere& s) {
              require_no_triangle_options(PrimitiveKind::sphere, rule);
              return to_python(without_gil([&] { return intersect_exact_rational(r, s); }));
            });
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(),
      R"doc(``intersect_exact`` plus the exact values it decided from, as ``fractions.Fraction``.

Plane: ``ExactIntersection(relation, t, num, den, exact_t)`` with ``num = (p − o)·n``, ``den = d·n`` and
``exact_t = num/den`` (None for PARALLEL and IN_PLANE).
Triangle: ``ExactTriangleIntersection(relation, location, owned, t, barycentric, den, num, pi, exact_t,
exact_barycentric)`` with ``pi = (πa, πb, πc)``, ``exact_t = num/den`` and ``exact_barycentric =
(πa, πb, πc)/den`` (None when den = 0). ``t`` and ``barycentric`` are the exact values correctly rounded.
Sphere: ``ExactSphereIntersection(origin, relation, u, v)``, the exact roots being U ∓ √V with ``u`` = U =
−B/A and ``v`` = V = D/A² (0 for TANGENT; both None for MISS); ``intersect_exact`` rounds them.
Releases the GIL.)doc");

  m.def(
      "intersect_naive",
      [](shown::RayLike ray, shown::PrimitiveLike primitive) -> shown::PrimitiveIntersection {
        auto naive = [](const Ray& r, const auto& p) { return to_python(intersect_naive(r, p)); };
        return for_primitive(primitive, ray, naive, naive, naive);
      },
      py::arg("ray"), py::arg("primitive"),
      R"doc(The textbook formula in plain doubles, no validation and no guarantee: the baseline that the
certified path is measured and tested against.

Plane: ``t = −((o − p)·n) / (d·n)``, classified from the computed values (``d·n == 0`` → PARALLEL or
IN_PLANE). Triangle: Möller–Trumbore (1997) with its own closed test (u ≥ 0, v ≥ 0, u + v ≤ 1) and
barycentric (1 − u − v, u, v); ``owned`` is that test (it has no owned rule). Sphere: the quadratic with the
half b (h = d·f, disc = h² − a·c, roots (−h ∓ √disc)/a; TANGENT when disc = 0), in the caller's
floating-point environment.)doc");

  m.def(
      "intersect_traced",
      [](shown::RayLike ray, shown::PrimitiveLike primitive, shown::OptionalRule rule, bool t,
         bool barycentric) -> shown::TracedPrimitiveIntersection {
        return for_primitive(
            primitive, ray,
            [&](const Ray& r, const Plane& p) {
              require_no_triangle_options(PrimitiveKind::plane, rule, t, barycentric);
              return to_python(intersect_traced(r, p));
            },
            [&](const Ray& r, const Triangle& tri) {
              return to_python(intersect_traced(r, tri, triangle_options(rule, t, barycentric)));
            },
            [&](const Ray& r, const Sphere& s) {
              require_no_triangle_options(PrimitiveKind::sphere, rule, t, barycentric);
              return to_python(intersect_traced(r, s));
            });
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t") = true,
      py::arg("barycentric") = true,
      R"doc(``intersect`` plus the stages of the certified cascade that decided it, each a ``raykernel.Stage``
(FILTER, COMPENSATED, EXPANSION, EXACT). Plane: ``TracedIntersection(relation, t, relation_stage, t_stage)``.
Triangle: ``TracedTriangleIntersection(..., relation_stage, rounding_stage)``, the rounding stage the slowest
of the roundings asked for. Sphere: ``TracedSphereIntersection(origin, relation, t1, t2, relation_stage,
rounding_stage)``, the relation's stage deciding the signs of C and D, the rounding stage the latest any root
needed (the relation's for MISS).)doc");

  m.def(
      "round_rational_to_double",
      [](shown::RationalLike value, shown::OptionalInt denominator) -> double {
        py::int_ num, den;
        if (denominator.is_none()) {
          if (PyLong_Check(value.ptr())) {
            num = int_from(value, "value");
            den = py::int_(1);
          } else if (py::hasattr(value, "numerator") && py::hasattr(value, "denominator")) {
            num = int_from(value.attr("numerator"), "value.numerator");
            den = int_from(value.attr("denominator"), "value.denominator");
          } else {
            throw py::type_error("value: expected a fractions.Fraction or an int, got " +
                                 std::string(Py_TYPE(value.ptr())->tp_name));
          }
        } else {
          num = int_from(value, "numerator");
          den = int_from(denominator, "denominator");
        }
        if (den.equal(py::int_(0))) throw py::value_error("denominator is zero");
        return round_to_double(num, den);
      },
      py::arg("value"), py::arg("denominator") = py::none(),
      R"doc(The exact rational ``value`` (a Fraction or int, or the ints ``value/denominator``) rounded to the
nearest double, ties to even, with overflow to ±inf and gradual underflow; a nonzero value that rounds to
zero keeps its sign. The rounding every exact t uses. Ints of any size, whatever ``sys.set_int_max_str_digits``
says: ``Fraction(10**5000, 3)`` gives inf.)doc");

  m.def("floating_point_environment_is_default", &floating_point_environment_is_default,
        R"doc(Whether this thread's floating-point environment is the one the certified stages assume (round
to nearest, no flush-to-zero or denormals-are-zero, no trapping). When it is not, ``intersect`` answers
through the exact stage, so the answer stays right either way.)doc");

  m.def(
      "version", [] { return std::string(version()); }, "The C++ library's version, \"MAJOR.MINOR.PATCH\".");
}

}  // namespace raykernel::python
