// Between Python objects and raykernel's C++ types: the one place that knows both.
//
// Inputs are read from any Python sequence of the right length (tuples, lists, the NamedTuples of
// raykernel._types, NumPy rows), and every error names the field it is about ("ray origin: expected 3
// numbers, got 2"), so a user sees which argument to fix. Results are built as the NamedTuples and enums of
// raykernel._types (loaded once, when the extension is imported). Arrays are (n, 3) NumPy arrays of real numbers
// (numeric_array refuses the dtypes NumPy would cast with a loss, and masked arrays), read as float64:
// `ColumnsView` reads their three columns as the contiguous spans the batch API takes, without a copy when a
// column is contiguous (an F-ordered array, e.g. `soa.T` for a (3, n) structure of arrays), copying it
// otherwise.
//
// Adding a primitive (triangles, spheres, meshes) means adding its `*_from` reader and its result builders here
// (and, for the scalar functions, a PrimitiveKind), and a bind_*.cpp beside the others; nothing else changes.
#pragma once

#include "annotated.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/triangle.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // std::optional, std::vector arguments and results

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::python {

namespace py = pybind11;

// ---------------------------------------------------------------------------------------------------------
// Python objects the extension builds its results from (raykernel._types), loaded by load_types().

struct PythonTypes {
  py::object vec3, ray, plane, triangle, sphere;
  py::object intersection, traced_intersection, exact_intersection, nearest_hit;
  py::object intersection_arrays, nearest_hit_arrays, relation_arrays;
  py::object barycentric, triangle_intersection, triangle_classification, traced_triangle_intersection,
      exact_triangle_intersection, triangle_intersection_arrays, triangle_classification_arrays;
  py::object sphere_intersection, sphere_classification, traced_sphere_intersection, exact_sphere_intersection,
      sphere_intersection_arrays;
  py::object mesh_hit, mesh_hit_arrays, point_location_arrays;
  py::object spawned_origin;
  py::object mesh_hits, occlusion_arrays, crossing_arrays;  // §8
  py::object sphere_hit, sphere_hit_arrays;                 // sphere sets
  py::object closest_point, closest_point_arrays;           // §11
  std::array<py::object, 3> closest_feature;                // indexed by the C++ enum's value
  std::array<py::object, 3> point_location;
  std::array<py::object, 4> relation;  // indexed by the C++ enum's value
  std::array<py::object, 6> triangle_relation;
  std::array<py::object, 9> triangle_location;
  std::array<py::object, 2> triangle_rule;
  std::array<py::object, 3> sphere_origin;
  std::array<py::object, 3> sphere_relation;
  std::array<py::object, stage_count> stage;
  py::object fraction;                 // fractions.Fraction
  py::object masked_array;             // numpy.ma.MaskedArray
};

// Imports raykernel._types and fractions once; called from the module's init.
void load_types();
[[nodiscard]] const PythonTypes& types();

// ---------------------------------------------------------------------------------------------------------
// Reading Python values. Each throws py::type_error or py::value_error naming `field`.

// A sequence of three real numbers (int, float, or anything with __float__), e.g. "ray origin".
[[nodiscard]] Vec3 vec3_from(py::handle value, std::string_view field);
// (origin, direction): a raykernel.Ray or any pair of 3-sequences. `name` prefixes the fields ("ray").
[[nodiscard]] Ray ray_from(py::handle value, std::string_view name = "ray");
// (point, normal): a raykernel.Plane or any pair of 3-sequences.
[[nodiscard]] Plane plane_from(py::handle value, std::string_view name = "plane");
// (a, b, c): a raykernel.Triangle or any triple of 3-sequences.
[[nodiscard]] Triangle triangle_from(py::handle value, std::string_view name = "triangle");
// (center, radius): a raykernel.Sphere or any pair of a 3-sequence and a number.
[[nodiscard]] Sphere sphere_from(py::handle value, std::string_view name = "sphere");
// What the second argument of intersect(ray, primitive) & co. is: a sphere only as a raykernel.Sphere (a bare
// pair stays a plane), a triangle as a raykernel.Triangle or any 3-sequence, a plane as a raykernel.Plane or any
// 2-sequence; TypeError or ValueError for anything else.
enum class PrimitiveKind { plane, triangle, sphere };
[[nodiscard]] PrimitiveKind primitive_kind(py::handle primitive);
// A TriangleRule from a raykernel.TriangleRule or its value ("owned", "closed"); rule_or_owned also takes None,
// the default of every function with a `rule` keyword: the owned rule.
[[nodiscard]] TriangleRule rule_from(py::handle value);
[[nodiscard]] TriangleRule rule_or_owned(py::handle rule);
// Whether t_min and t_max (numbers, or arrays in a batch) are the whole ray [0, +inf]; require_whole_ray refuses
// another interval where the query takes none ("t_min, t_max: <what> take the whole ray, t >= 0").
[[nodiscard]] bool is_whole_ray(py::handle t_min, py::handle t_max);
void require_whole_ray(py::handle t_min, py::handle t_max, const char* what);
// Refuses a rule where the scene (planes, spheres) has none.
void require_no_rule(py::handle rule, py::handle scene);
// A finite double from a Python number (for round_rational_to_double's sister functions, t values...).
[[nodiscard]] double double_from(py::handle value, std::string_view field);
// A Relation from a raykernel.Relation, its string value ("in-plane") or its code (0..3).
[[nodiscard]] Relation relation_from(py::handle value, std::string_view field = "relation");
// A Python int (not a bool), or TypeError naming `field`.
[[nodiscard]] py::int_ int_from(py::handle value, std::string_view field);
// The exact rational numerator/denominator (Python ints of any size, denominator nonzero) rounded to the nearest
// double by the kernel's round_rational_to_double: ties to even, overflow to ±inf, gradual underflow, a nonzero
// value that rounds to zero keeps its sign. No decimal string of more than 640 digits is made on the way, so
// sys.set_int_max_str_digits() never refuses it and a huge int costs one division.
[[nodiscard]] double round_to_double(const py::int_& numerator, const py::int_& denominator);

// ---------------------------------------------------------------------------------------------------------
// Building Python results.

[[nodiscard]] py::object to_python(const Vec3& v);
[[nodiscard]] py::object to_python(const Ray& r);
[[nodiscard]] py::object to_python(const Plane& p);
[[nodiscard]] py::object to_python(Relation r);
[[nodiscard]] py::object to_python(Stage s);
[[nodiscard]] py::object to_python(const Intersection& x);
[[nodiscard]] py::object to_python(const TracedIntersection& x);
[[nodiscard]] py::object to_python(const ExactIntersection& x);
[[nodiscard]] py::object to_python(const std::optional<NearestHit>& hit);
[[nodiscard]] py::object to_python(TriangleRelation r);
[[nodiscard]] py::object to_python(TriangleLocation l);
[[nodiscard]] py::object to_python(const TriangleIntersection& x);
[[nodiscard]] py::object to_python(const TriangleClassification& x);
[[nodiscard]] py::object to_python(const TracedTriangleIntersection& x);
[[nodiscard]] py::object to_python(const ExactTriangleIntersection& x);
[[nodiscard]] py::object to_python(const Sphere& s);
[[nodiscard]] py::object to_python(SphereOrigin o);
[[nodiscard]] py::object to_python(SphereRelation r);
[[nodiscard]] py::object to_python(const SphereIntersection& x);
[[nodiscard]] py::object to_python(const SphereClassification& x);
[[nodiscard]] py::object to_python(const TracedSphereIntersection& x);
[[nodiscard]] py::object to_python(const ExactSphereIntersection& x);
// An exact rational (decimal strings in lowest terms) as a fractions.Fraction, whatever the number of digits and
// sys.set_int_max_str_digits() (the digits are converted in pieces CPython always converts).
[[nodiscard]] py::object to_fraction(const Rational& r);

// ---------------------------------------------------------------------------------------------------------
// Arrays.

// What an array argument holds: real numbers (coordinates, read as float64) or integers (vertex indices).
enum class Numbers { real, integer };

// `value` as a NumPy array of its own dtype (numpy.asarray(value): nothing converted yet), once what it holds is
// checked: the one check of every array argument, through ColumnsView (every vectorized function, PlaneSet and
// Mesh vertices) and Mesh triangles. Real: an integer or floating dtype (int8..uint64, float16..longdouble).
// Integer: an integer dtype, or an empty array of a floating one (numpy.asarray([]) is float64). Everything NumPy
// would otherwise cast with a loss or a guess raises TypeError naming `name`, `wanted` and the dtype: complex
// (the imaginary part dropped), bool, str and bytes (parsed), object (float() of each item), datetime64 and
// timedelta64, structured and void, floats for indices (truncated: 1.9 → 1, NaN → -2^63) — and a
// numpy.ma.MaskedArray, whose mask would be dropped, silently answering the rows it masks.
[[nodiscard]] py::array numeric_array(py::handle value, std::string_view name, Numbers numbers,
                                      std::string_view wanted);

// "(4, 2)", "(3,)": an array's shape as NumPy prints it.
[[nodiscard]] std::string shape_string(const py::array& array);

// The rows of an (n, 3) array of real numbers (numeric_array; read as float64: exactly for float16, float32 and
// integers up to 2^53, to the nearest double beyond, as float() does), or of a single 3-vector, a broadcast row,
// when allowed; any memory layout. Construct with the GIL held (it converts the Python value); reading needs no
// GIL. The batch API takes contiguous columns: `columns(begin, end)` gives them as views into the array when its
// columns are contiguous (Fortran order, e.g. `soa.T` of a (3, n) structure of arrays), and otherwise gathers the
// rows [begin, end) into a scratch buffer of this view, overwritten by the next call — so callers work through a
// row-major array in chunks that stay in cache instead of copying it whole.
class ColumnsView {
 public:
  ColumnsView(py::handle value, std::string_view name, bool allow_single = false);

  [[nodiscard]] std::size_t rows() const noexcept { return rows_; }
  [[nodiscard]] bool single() const noexcept { return single_; }
  // The columns can be handed to the batch API as they are.
  [[nodiscard]] bool contiguous() const noexcept { return single_ || rows_ <= 1 || row_stride_ == sizeof(double); }
  // Row i as a Vec3 (row 0 when single()).
  [[nodiscard]] Vec3 row(std::size_t i) const noexcept;
  // The x, y, z columns of rows [begin, end), contiguous.
  [[nodiscard]] std::array<std::span<const double>, 3> columns(std::size_t begin, std::size_t end);

 private:
  py::array_t<double, py::array::forcecast> array_;  // keeps the data alive
  std::array<const char*, 3> firsts_{};              // the first element of each column
  py::ssize_t row_stride_ = 0;                       // bytes from one row to the next (0 for a single row)
  std::size_t rows_ = 0;
  bool single_ = false;
  std::vector<double> scratch_;                      // gathered columns of a non-contiguous array
};

// The values of a 1-D array of n real numbers (numeric_array; read as float64, any stride), or of a single number
// (a Python number or a 0-d array), a broadcast value, when allowed: the radii of spheres. Construct with the GIL
// held; value(i) needs no GIL.
class ValuesView {
 public:
  ValuesView(py::handle value, std::string_view name, bool allow_single = false);

  [[nodiscard]] std::size_t rows() const noexcept { return rows_; }
  [[nodiscard]] bool single() const noexcept { return single_; }
  // Value i (value 0 when single()).
  [[nodiscard]] double value(std::size_t i) const noexcept;

 private:
  py::array_t<double, py::array::forcecast> array_;  // keeps the data alive
  const char* first_ = nullptr;
  py::ssize_t stride_ = 0;                           // bytes from one value to the next (0 for a single value)
  std::size_t rows_ = 0;
  bool single_ = false;
};

// Checks that `view` has `rows` rows (or is a single row when that is allowed), naming both arrays.
void require_rows(const ColumnsView& view, std::string_view name, std::size_t rows, std::string_view reference_name);
void require_rows(const ValuesView& view, std::string_view name, std::size_t rows, std::string_view reference_name);

// A fresh 1-D NumPy array of n elements (uninitialized).
template <class T>
[[nodiscard]] py::array_t<T> new_array(std::size_t n) {
  return py::array_t<T>(static_cast<py::ssize_t>(n));
}
template <class T>
[[nodiscard]] std::span<T> span_of(py::array_t<T>& a) {
  return {a.mutable_data(), static_cast<std::size_t>(a.size())};
}

// What a vectorized call does with invalid rows.
enum class ErrorPolicy { raise, mask };
[[nodiscard]] ErrorPolicy error_policy_from(std::string_view errors);

}  // namespace raykernel::python
