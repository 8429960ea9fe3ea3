// Scalar ray–plane queries (docs/contract.md §1): one ray, one plane, plain Python values in and out.
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/raykernel.hpp>

#include <optional>
#include <string>

namespace raykernel::python {

void bind_ray_plane(py::module_& m) {
  m.def(
      "validate",
      [](py::handle ray, py::handle plane) -> std::optional<std::string> {
        return validate(ray_from(ray), plane_from(plane));
      },
      py::arg("ray"), py::arg("plane"),
      R"doc(The reason ``ray`` and ``plane`` are invalid input, or None when they are valid.

Invalid input has no answer: a NaN or infinite component, a zero direction or a zero normal. The reason
names the field, e.g. ``"ray direction is the zero vector"`` or ``"plane point y is NaN"``; it is the
message the other functions raise ``ValueError`` (``raykernel.InvalidInput``) with.)doc");

  m.def(
      "intersect", [](py::handle ray, py::handle plane) { return to_python(intersect(ray_from(ray), plane_from(plane))); },
      py::arg("ray"), py::arg("plane"),
      R"doc(The certified intersection of ``ray`` and ``plane``: the exact answer, fast.

``ray`` is ``(origin, direction)`` and ``plane`` is ``(point, normal)``, each vector a sequence of three
numbers (``raykernel.Ray`` and ``raykernel.Plane`` are such pairs). With ``den = d·n`` and ``num = (p − o)·n``
evaluated exactly over the reals, the relation is HIT (den ≠ 0, num/den ≥ 0), BEHIND (den ≠ 0, num/den < 0),
PARALLEL (den = 0, num ≠ 0) or IN_PLANE (den = 0, num = 0), and ``t`` is num/den rounded to the nearest
double, ties to even (±inf beyond the double range, a nonzero t that rounds to zero keeps its sign), NaN
for PARALLEL and IN_PLANE (docs/contract.md §1). Returns ``Intersection(relation, t)``. Raises
``ValueError`` naming the field for invalid input.)doc");

  m.def(
      "intersect_exact",
      [](py::handle ray, py::handle plane) {
        const Ray r = ray_from(ray);
        const Plane p = plane_from(plane);
        Intersection x;
        {
          py::gil_scoped_release release;
          x = intersect_exact(r, p);
        }
        return to_python(x);
      },
      py::arg("ray"), py::arg("plane"),
      R"doc(The reference answer, from exact rational arithmetic (GMP) and MPFR rounding: slow (microseconds)
and obviously right. The same answer as ``intersect``, bit for bit. Releases the GIL.)doc");

  m.def(
      "intersect_exact_rational",
      [](py::handle ray, py::handle plane) {
        const Ray r = ray_from(ray);
        const Plane p = plane_from(plane);
        std::optional<ExactIntersection> x;
        {
          py::gil_scoped_release release;
          x = intersect_exact_rational(r, p);
        }
        return to_python(*x);
      },
      py::arg("ray"), py::arg("plane"),
      R"doc(``intersect_exact`` plus the exact values it decided from, as ``fractions.Fraction``:
``ExactIntersection(relation, t, num, den, exact_t)`` with ``num = (p − o)·n``, ``den = d·n`` and
``exact_t = num/den`` (None for PARALLEL and IN_PLANE). ``t`` is ``exact_t`` correctly rounded. Releases the
GIL.)doc");

  m.def(
      "intersect_naive",
      [](py::handle ray, py::handle plane) { return to_python(intersect_naive(ray_from(ray), plane_from(plane))); },
      py::arg("ray"), py::arg("plane"),
      R"doc(The textbook formula ``t = −((o − p)·n) / (d·n)`` in plain doubles, classified from the computed
values (``d·n == 0`` → PARALLEL or IN_PLANE). No validation and no guarantee: the baseline that the certified
path is measured and tested against.)doc");

  m.def(
      "intersect_traced",
      [](py::handle ray, py::handle plane) { return to_python(intersect_traced(ray_from(ray), plane_from(plane))); },
      py::arg("ray"), py::arg("plane"),
      R"doc(``intersect`` plus the stages of the certified cascade that decided it:
``TracedIntersection(relation, t, relation_stage, t_stage)``, each stage a ``raykernel.Stage`` (FILTER,
COMPENSATED, EXPANSION, EXACT).)doc");

  m.def(
      "round_rational_to_double",
      [](py::handle value, py::handle denominator) {
        std::string num, den;
        if (denominator.is_none()) {
          if (PyLong_Check(value.ptr())) {
            num = decimal_digits(value, "value");
            den = "1";
          } else if (py::hasattr(value, "numerator") && py::hasattr(value, "denominator")) {
            num = decimal_digits(value.attr("numerator"), "value.numerator");
            den = decimal_digits(value.attr("denominator"), "value.denominator");
          } else {
            throw py::type_error("value: expected a fractions.Fraction or an int, got " +
                                 std::string(Py_TYPE(value.ptr())->tp_name));
          }
        } else {
          num = decimal_digits(value, "numerator");
          den = decimal_digits(denominator, "denominator");
        }
        if (den == "0") throw py::value_error("denominator is zero");
        return round_rational_to_double(num, den);
      },
      py::arg("value"), py::arg("denominator") = py::none(),
      R"doc(The exact rational ``value`` (a Fraction or int, or the ints ``value/denominator``) rounded to the
nearest double, ties to even, with overflow to ±inf and gradual underflow; a nonzero value that rounds to
zero keeps its sign. The rounding every exact t uses.)doc");

  m.def("floating_point_environment_is_default", &floating_point_environment_is_default,
        R"doc(Whether this thread's floating-point environment is the one the certified stages assume (round
to nearest, no flush-to-zero or denormals-are-zero, no trapping). When it is not, ``intersect`` answers
through the exact stage, so the answer stays right either way.)doc");

  m.def(
      "version", [] { return std::string(version()); }, "The C++ library's version, \"MAJOR.MINOR.PATCH\".");
}

}  // namespace raykernel::python
