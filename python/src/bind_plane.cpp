// Scalar queries: one ray and one plane (docs/contract.md §1) or one triangle (§6), plain Python values in and
// out. Each function takes the primitive as its second argument and answers for what it is (is_triangle: a
// 2-sequence is a plane, a 3-sequence a triangle); the triangle options are keyword-only.
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

#include <optional>
#include <string>

namespace raykernel::python {
namespace {

// The triangle options from the keyword arguments; for a plane they must be left at their defaults.
TriangleOptions triangle_options(py::handle rule, bool t, bool barycentric) {
  return {rule.is_none() ? TriangleRule::owned : rule_from(rule), t, barycentric};
}
void require_plane_defaults(py::handle rule, bool t = true, bool barycentric = true) {
  if (!rule.is_none()) throw py::value_error("rule: only triangles have rules, the second argument is a plane");
  if (!t || !barycentric)
    throw py::value_error("t, barycentric: only for triangles (a plane's t is always computed)");
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
      [](py::handle ray, py::handle primitive) -> std::optional<std::string> {
        if (is_triangle(primitive)) return validate(ray_from(ray), triangle_from(primitive));
        return validate(ray_from(ray), plane_from(primitive));
      },
      py::arg("ray"), py::arg("primitive"),
      R"doc(The reason ``ray`` and ``primitive`` (a plane or a triangle) are invalid input, or None when they are valid.

Invalid input has no answer: a NaN or infinite component, a zero direction or a zero normal. The reason
names the field, e.g. ``"ray direction is the zero vector"`` or ``"plane point y is NaN"``; it is the
message the other functions raise ``ValueError`` (``raykernel.InvalidInput``) with. A degenerate triangle
(collinear or repeated vertices) is valid: its relation is DEGENERATE.)doc");

  m.def(
      "intersect",
      [](py::handle ray, py::handle primitive, py::handle rule, bool t, bool barycentric) {
        if (is_triangle(primitive))
          return to_python(intersect(ray_from(ray), triangle_from(primitive), triangle_options(rule, t, barycentric)));
        require_plane_defaults(rule, t, barycentric);
        return to_python(intersect(ray_from(ray), plane_from(primitive)));
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t") = true,
      py::arg("barycentric") = true,
      R"doc(The certified intersection of ``ray`` with a plane or a triangle: the exact answer, fast.

``ray`` is ``(origin, direction)``; ``primitive`` is a plane ``(point, normal)`` or a triangle ``(a, b, c)``,
each vector a sequence of three numbers (``raykernel.Ray``, ``Plane`` and ``Triangle`` are such tuples).

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

Raises ``ValueError`` (``raykernel.InvalidInput``) naming the field for invalid input.)doc");

  m.def(
      "relation",
      [](py::handle ray, py::handle primitive, py::handle rule) {
        if (is_triangle(primitive)) {
          const Ray r = ray_from(ray);
          const Triangle tri = triangle_from(primitive);
          return to_python(relation(r, tri, rule.is_none() ? TriangleRule::owned : rule_from(rule)));
        }
        require_plane_defaults(rule);
        return to_python(relation(ray_from(ray), plane_from(primitive)));
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(),
      R"doc(The certified relation alone, nothing rounded: the yes/no predicate, cheaper than ``intersect``.

Plane: a ``Relation`` (HIT, BEHIND, PARALLEL, IN_PLANE), ``intersect(ray, plane).relation`` exactly.
Triangle: ``TriangleClassification(relation, location, owned)`` under ``rule`` ("owned" or "closed"), the
same as ``intersect``'s. Raises ``ValueError`` naming the field for invalid input.)doc");

  m.def(
      "intersect_exact",
      [](py::handle ray, py::handle primitive, py::handle rule, bool t, bool barycentric) {
        const Ray r = ray_from(ray);
        if (is_triangle(primitive)) {
          const Triangle tri = triangle_from(primitive);
          const TriangleOptions options = triangle_options(rule, t, barycentric);
          return to_python(without_gil([&] { return intersect_exact(r, tri, options); }));
        }
        require_plane_defaults(rule, t, barycentric);
        const Plane p = plane_from(primitive);
        return to_python(without_gil([&] { return intersect_exact(r, p); }));
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t") = true,
      py::arg("barycentric") = true,
      R"doc(The reference answer, from exact rational arithmetic (GMP) and MPFR rounding: slow (microseconds)
and obviously right. The same answer as ``intersect``, bit for bit, for a plane or a triangle (same
options). Releases the GIL.)doc");

  m.def(
      "intersect_exact_rational",
      [](py::handle ray, py::handle primitive, py::handle rule) {
        const Ray r = ray_from(ray);
        if (is_triangle(primitive)) {
          const Triangle tri = triangle_from(primitive);
          const TriangleRule chosen = rule.is_none() ? TriangleRule::owned : rule_from(rule);
          return to_python(without_gil([&] { return intersect_exact_rational(r, tri, chosen); }));
        }
        require_plane_defaults(rule);
        const Plane p = plane_from(primitive);
        return to_python(without_gil([&] { return intersect_exact_rational(r, p); }));
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(),
      R"doc(``intersect_exact`` plus the exact values it decided from, as ``fractions.Fraction``.

Plane: ``ExactIntersection(relation, t, num, den, exact_t)`` with ``num = (p − o)·n``, ``den = d·n`` and
``exact_t = num/den`` (None for PARALLEL and IN_PLANE).
Triangle: ``ExactTriangleIntersection(relation, location, owned, t, barycentric, den, num, pi, exact_t,
exact_barycentric)`` with ``pi = (πa, πb, πc)``, ``exact_t = num/den`` and ``exact_barycentric =
(πa, πb, πc)/den`` (None when den = 0). ``t`` and ``barycentric`` are the exact values correctly rounded.
Releases the GIL.)doc");

  m.def(
      "intersect_naive",
      [](py::handle ray, py::handle primitive) {
        if (is_triangle(primitive)) return to_python(intersect_naive(ray_from(ray), triangle_from(primitive)));
        return to_python(intersect_naive(ray_from(ray), plane_from(primitive)));
      },
      py::arg("ray"), py::arg("primitive"),
      R"doc(The textbook formula in plain doubles, no validation and no guarantee: the baseline that the
certified path is measured and tested against.

Plane: ``t = −((o − p)·n) / (d·n)``, classified from the computed values (``d·n == 0`` → PARALLEL or
IN_PLANE). Triangle: Möller–Trumbore (1997) with its own closed test (u ≥ 0, v ≥ 0, u + v ≤ 1) and
barycentric (1 − u − v, u, v); ``owned`` is that test (it has no owned rule).)doc");

  m.def(
      "intersect_traced",
      [](py::handle ray, py::handle primitive, py::handle rule, bool t, bool barycentric) {
        if (is_triangle(primitive))
          return to_python(
              intersect_traced(ray_from(ray), triangle_from(primitive), triangle_options(rule, t, barycentric)));
        require_plane_defaults(rule, t, barycentric);
        return to_python(intersect_traced(ray_from(ray), plane_from(primitive)));
      },
      py::arg("ray"), py::arg("primitive"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t") = true,
      py::arg("barycentric") = true,
      R"doc(``intersect`` plus the stages of the certified cascade that decided it, each a ``raykernel.Stage``
(FILTER, COMPENSATED, EXPANSION, EXACT). Plane: ``TracedIntersection(relation, t, relation_stage, t_stage)``.
Triangle: ``TracedTriangleIntersection(..., relation_stage, rounding_stage)``, the rounding stage the slowest
of the roundings asked for.)doc");

  m.def(
      "round_rational_to_double",
      [](py::handle value, py::handle denominator) {
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
