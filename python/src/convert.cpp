// Between Python objects and raykernel's C++ types (convert.hpp).
#include "convert.hpp"

#include <raykernel/mesh_queries.hpp>  // PointLocation

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace raykernel::python {
namespace {

PythonTypes* loaded_types = nullptr;

std::string type_name(py::handle value) { return Py_TYPE(value.ptr())->tp_name; }

std::string str(std::string_view s) { return std::string(s); }

// One component of a vector: any Python number (int, float, NumPy scalar, anything with __float__).
double component(PyObject* item, std::string_view field, int axis) {
  if (PyFloat_CheckExact(item)) return PyFloat_AS_DOUBLE(item);
  const double x = PyFloat_AsDouble(item);
  if (x == -1.0 && PyErr_Occurred()) {
    const bool overflow = PyErr_ExceptionMatches(PyExc_OverflowError) != 0;
    PyErr_Clear();
    const std::string where = str(field) + " " + "xyz"[axis];
    if (overflow) throw py::value_error(where + " is too large for a double");
    throw py::type_error(where + ": expected a number, got " + type_name(item));
  }
  return x;
}

// The items of a sequence of exactly `count` elements, or an error naming `field` and `what`.
py::object fast_sequence(py::handle value, std::string_view field, Py_ssize_t count, std::string_view what) {
  PyObject* seq = PySequence_Fast(value.ptr(), "");
  if (seq == nullptr) {
    PyErr_Clear();
    throw py::type_error(str(field) + ": expected " + str(what) + ", got " + type_name(value));
  }
  py::object holder = py::reinterpret_steal<py::object>(seq);
  const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
  if (n != count)
    throw py::value_error(str(field) + ": expected " + str(what) + ", got a sequence of " + std::to_string(n) +
                          (n == 1 ? " item" : " items"));
  return holder;
}

// CPython converts decimal strings of at most this many digits to and from ints whatever
// sys.set_int_max_str_digits() says: it is _PY_LONG_MAX_STR_DIGITS_THRESHOLD, below which the limit is not
// consulted, and the smallest limit a program may set. Longer strings may be refused (4300 digits by default).
constexpr std::size_t always_convertible_digits = 640;

// A new reference from the Python C API, or the Python error it set.
py::object checked(PyObject* result) {
  if (result == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::object>(result);
}

// A Python int from decimal digits ('-' allowed first) of any length: pieces of at most
// always_convertible_digits, joined as high·10^h + low by halves (no quadratic digit-by-digit loop).
py::object int_from_decimal(std::string_view digits) {
  if (!digits.empty() && digits.front() == '-') return -int_from_decimal(digits.substr(1));
  if (digits.size() <= always_convertible_digits)
    return checked(PyLong_FromString(std::string(digits).c_str(), nullptr, 10));
  const std::size_t low = digits.size() / 2;  // leading zeros of the low half are read as zeros
  const py::object scale = checked(PyNumber_Power(py::int_(10).ptr(), py::int_(low).ptr(), Py_None));
  return int_from_decimal(digits.substr(0, digits.size() - low)) * scale +
         int_from_decimal(digits.substr(digits.size() - low));
}

template <class Pair>
Pair pair_from(py::handle value, std::string_view name, const char* first, const char* second) {
  const py::object seq = fast_sequence(value, name, 2, "(" + std::string(first) + ", " + second + ")");
  PyObject** items = PySequence_Fast_ITEMS(seq.ptr());
  return {vec3_from(items[0], str(name) + " " + first), vec3_from(items[1], str(name) + " " + second)};
}

}  // namespace

void load_types() {
  // Owned for the life of the process: these objects must outlive every call into the extension, and
  // releasing them at interpreter shutdown would race with module teardown.
  auto* t = new PythonTypes;
  const py::module_ m = py::module_::import("raykernel._types");
  t->vec3 = m.attr("Vec3");
  t->ray = m.attr("Ray");
  t->plane = m.attr("Plane");
  t->triangle = m.attr("Triangle");
  t->sphere = m.attr("Sphere");
  t->intersection = m.attr("Intersection");
  t->traced_intersection = m.attr("TracedIntersection");
  t->exact_intersection = m.attr("ExactIntersection");
  t->nearest_hit = m.attr("NearestHit");
  t->intersection_arrays = m.attr("IntersectionArrays");
  t->nearest_hit_arrays = m.attr("NearestHitArrays");
  t->relation_arrays = m.attr("RelationArrays");
  t->barycentric = m.attr("Barycentric");
  t->triangle_intersection = m.attr("TriangleIntersection");
  t->triangle_classification = m.attr("TriangleClassification");
  t->traced_triangle_intersection = m.attr("TracedTriangleIntersection");
  t->exact_triangle_intersection = m.attr("ExactTriangleIntersection");
  t->triangle_intersection_arrays = m.attr("TriangleIntersectionArrays");
  t->triangle_classification_arrays = m.attr("TriangleClassificationArrays");
  t->sphere_intersection = m.attr("SphereIntersection");
  t->sphere_classification = m.attr("SphereClassification");
  t->traced_sphere_intersection = m.attr("TracedSphereIntersection");
  t->exact_sphere_intersection = m.attr("ExactSphereIntersection");
  t->sphere_intersection_arrays = m.attr("SphereIntersectionArrays");
  t->mesh_hit = m.attr("MeshHit");
  t->mesh_hit_arrays = m.attr("MeshHitArrays");
  t->point_location_arrays = m.attr("PointLocationArrays");
  t->spawned_origin = m.attr("SpawnedOrigin");
  t->mesh_hits = m.attr("MeshHits");
  t->occlusion_arrays = m.attr("OcclusionArrays");
  t->crossing_arrays = m.attr("CrossingArrays");
  t->sphere_hit = m.attr("SphereHit");
  t->sphere_hit_arrays = m.attr("SphereHitArrays");
  t->closest_point = m.attr("ClosestPoint");
  t->closest_point_arrays = m.attr("ClosestPointArrays");
  for (std::size_t k = 0; k < 3; ++k) t->closest_feature[k] = m.attr("ClosestFeature").attr("from_code")(k);
  // The Python enums list their members in the C++ enums' order, and their codes are those values.
  for (std::size_t k = 0; k < 6; ++k) t->triangle_relation[k] = m.attr("TriangleRelation").attr("from_code")(k);
  for (std::size_t k = 0; k < 9; ++k) t->triangle_location[k] = m.attr("TriangleLocation").attr("from_code")(k);
  t->triangle_rule = {m.attr("TriangleRule").attr("OWNED"), m.attr("TriangleRule").attr("CLOSED")};
  for (std::size_t k = 0; k < 6; ++k)
    if (t->triangle_relation[k].attr("value").cast<std::string>() != to_string(static_cast<TriangleRelation>(k)))
      throw std::logic_error("raykernel._types.TriangleRelation differs from the C++ enum");
  for (std::size_t k = 0; k < 9; ++k)
    if (t->triangle_location[k].attr("value").cast<std::string>() != to_string(static_cast<TriangleLocation>(k)))
      throw std::logic_error("raykernel._types.TriangleLocation differs from the C++ enum");
  for (std::size_t k = 0; k < 3; ++k) {
    t->point_location[k] = m.attr("PointLocation").attr("from_code")(k);
    if (t->point_location[k].attr("value").cast<std::string>() != to_string(static_cast<PointLocation>(k)))
      throw std::logic_error("raykernel._types.PointLocation differs from the C++ enum");
    t->sphere_origin[k] = m.attr("SphereOrigin").attr("from_code")(k);
    if (t->sphere_origin[k].attr("value").cast<std::string>() != to_string(static_cast<SphereOrigin>(k)))
      throw std::logic_error("raykernel._types.SphereOrigin differs from the C++ enum");
    t->sphere_relation[k] = m.attr("SphereRelation").attr("from_code")(k);
    if (t->sphere_relation[k].attr("value").cast<std::string>() != to_string(static_cast<SphereRelation>(k)))
      throw std::logic_error("raykernel._types.SphereRelation differs from the C++ enum");
  }
  const py::object relation = m.attr("Relation");
  t->relation = {relation.attr("HIT"), relation.attr("BEHIND"), relation.attr("PARALLEL"), relation.attr("IN_PLANE")};
  const py::object stage = m.attr("Stage");
  t->stage = {stage.attr("FILTER"), stage.attr("COMPENSATED"), stage.attr("EXPANSION"), stage.attr("EXACT")};
  t->fraction = py::module_::import("fractions").attr("Fraction");
  t->masked_array = py::module_::import("numpy.ma").attr("MaskedArray");  // numpy is imported by _types already
  // The C++ enums' values are the codes the arrays carry; the Python enums must agree.
  for (int k = 0; k < 4; ++k)
    if (t->relation[static_cast<std::size_t>(k)].attr("code").cast<int>() != k)
      throw std::logic_error("raykernel._types.Relation codes differ from the C++ enum");
  loaded_types = t;
}

const PythonTypes& types() { return *loaded_types; }

Vec3 vec3_from(py::handle value, std::string_view field) {
  const py::object seq = fast_sequence(value, field, 3, "a sequence of 3 numbers");
  PyObject** items = PySequence_Fast_ITEMS(seq.ptr());
  return {component(items[0], field, 0), component(items[1], field, 1), component(items[2], field, 2)};
}

Ray ray_from(py::handle value, std::string_view name) { return pair_from<Ray>(value, name, "origin", "direction"); }

Plane plane_from(py::handle value, std::string_view name) { return pair_from<Plane>(value, name, "point", "normal"); }

Triangle triangle_from(py::handle value, std::string_view name) {
  const py::object seq = fast_sequence(value, name, 3, "(a, b, c)");
  PyObject** items = PySequence_Fast_ITEMS(seq.ptr());
  return {vec3_from(items[0], str(name) + " a"), vec3_from(items[1], str(name) + " b"),
          vec3_from(items[2], str(name) + " c")};
}

Sphere sphere_from(py::handle value, std::string_view name) {
  const py::object seq = fast_sequence(value, name, 2, "(center, radius)");
  PyObject** items = PySequence_Fast_ITEMS(seq.ptr());
  return {vec3_from(items[0], str(name) + " center"), double_from(items[1], str(name) + " radius")};
}

PrimitiveKind primitive_kind(py::handle primitive) {
  if (py::isinstance(primitive, types().sphere)) return PrimitiveKind::sphere;
  if (py::isinstance(primitive, types().triangle)) return PrimitiveKind::triangle;
  if (py::isinstance(primitive, types().plane)) return PrimitiveKind::plane;
  const std::string wanted =
      "primitive: expected a plane (point, normal), a triangle (a, b, c) or a raykernel.Sphere, got ";
  if (!PySequence_Check(primitive.ptr()) || PyUnicode_Check(primitive.ptr()))
    throw py::type_error(wanted + type_name(primitive));
  const Py_ssize_t n = PySequence_Size(primitive.ptr());
  if (n < 0) {
    PyErr_Clear();
    throw py::type_error(wanted + type_name(primitive));
  }
  if (n == 3) return PrimitiveKind::triangle;
  if (n == 2) return PrimitiveKind::plane;
  throw py::value_error(wanted + "a sequence of " + std::to_string(n) + (n == 1 ? " item" : " items"));
}

TriangleRule rule_from(py::handle value) {
  if (PyUnicode_Check(value.ptr())) {
    const std::string s = value.cast<std::string>();
    if (s == "owned") return TriangleRule::owned;
    if (s == "closed") return TriangleRule::closed;
    throw py::value_error("rule: expected 'owned' or 'closed', got '" + s + "'");
  }
  throw py::type_error("rule: expected 'owned' or 'closed' (raykernel.TriangleRule), got " + type_name(value));
}

TriangleRule rule_or_owned(py::handle rule) { return rule.is_none() ? TriangleRule::owned : rule_from(rule); }

void require_no_rule(py::handle rule, py::handle scene) {
  if (!rule.is_none())
    throw py::value_error(std::string("rule: only meshes have rules, the scene is ") +
                          (py::isinstance<raykernel::SphereSet>(scene) ? "spheres" : "planes"));
}

bool is_whole_ray(py::handle t_min, py::handle t_max) {
  const auto is = [](py::handle v, double want) {
    return (PyFloat_Check(v.ptr()) || PyLong_Check(v.ptr())) && v.cast<double>() == want;
  };
  return is(t_min, 0.0) && is(t_max, std::numeric_limits<double>::infinity());
}

void require_whole_ray(py::handle t_min, py::handle t_max, const char* what) {
  if (!is_whole_ray(t_min, t_max)) throw py::value_error(std::string("t_min, t_max: ") + what + " takes the whole ray, t >= 0");
}

double double_from(py::handle value, std::string_view field) {
  if (PyFloat_CheckExact(value.ptr())) return PyFloat_AS_DOUBLE(value.ptr());
  const double x = PyFloat_AsDouble(value.ptr());
  if (x == -1.0 && PyErr_Occurred()) {
    const bool overflow = PyErr_ExceptionMatches(PyExc_OverflowError) != 0;
    PyErr_Clear();
    if (overflow) throw py::value_error(str(field) + " is too large for a double");
    throw py::type_error(str(field) + ": expected a number, got " + type_name(value));
  }
  return x;
}

Relation relation_from(py::handle value, std::string_view field) {
  if (PyUnicode_Check(value.ptr())) {  // raykernel.Relation is a str enum: its value is the name
    const std::string s = value.cast<std::string>();
    if (s == "hit") return Relation::hit;
    if (s == "behind") return Relation::behind;
    if (s == "parallel") return Relation::parallel;
    if (s == "in-plane" || s == "in_plane") return Relation::in_plane;
    throw py::value_error(str(field) + ": expected hit, behind, parallel or in-plane, got '" + s + "'");
  }
  if (PyLong_Check(value.ptr())) {
    const long code = value.cast<long>();
    if (code >= 0 && code <= 3) return static_cast<Relation>(code);
    throw py::value_error(str(field) + ": relation codes are 0..3, got " + std::to_string(code));
  }
  throw py::type_error(str(field) + ": expected a raykernel.Relation, got " + type_name(value));
}

py::int_ int_from(py::handle value, std::string_view field) {
  if (!PyLong_Check(value.ptr()) || PyBool_Check(value.ptr()))
    throw py::type_error(str(field) + ": expected an int, got " + type_name(value));
  return py::reinterpret_borrow<py::int_>(value);
}

double round_to_double(const py::int_& numerator, const py::int_& denominator) {
  // The kernel rounds a rational given as decimal strings. Python ints of any size are first reduced to a
  // rational y = m/2^(K+1) that rounds to the same double as x = numerator/denominator, with m ≤ 2^2101 (at
  // most 633 digits) and 2^(K+1) of 324 digits: within always_convertible_digits.
  //
  // Why y rounds like x. Take x ≥ 0 (the sign is put back on m), x = a/b, K = 1075, q = ⌊a·2^K/b⌋, s = 1 when
  // that division is inexact, else 0, and m = 2q + s. Every double is a multiple of 2^-1074 and every point where
  // the rounding to nearest-even changes (the midpoint of two neighbouring doubles, or the overflow threshold
  // 2^1024 − 2^970) a multiple of 2^-1075 = 2^-K. If s = 0, y = x. If s = 1, x and y = (q + 1/2)/2^K both lie
  // strictly between q/2^K and (q + 1)/2^K, consecutive multiples of 2^-K: no such point separates them and
  // neither is one, so they round alike. y = 0 only when x = 0, so a nonzero x that rounds to zero keeps its sign.
  // An x ≥ 2^1025 rounds to inf as 2^1025 does and is replaced by it; then x ≤ 2^1025, q ≤ 2^(1025+K) and
  // m ≤ 2^2101 (633 digits). The cost: a shift of a and one division whose quotient q has at most 2101 bits.
  constexpr int K = 1075;
  const bool negative = (numerator < py::int_(0)) != (denominator < py::int_(0));
  py::object a = checked(PyNumber_Absolute(numerator.ptr()));
  py::object b = checked(PyNumber_Absolute(denominator.ptr()));
  if (a >= (b << py::int_(1025))) {
    a = py::int_(1) << py::int_(1025);
    b = py::int_(1);
  }
  const py::tuple qr = checked(PyNumber_Divmod((a << py::int_(K)).ptr(), b.ptr()));
  const py::object q = qr[0], remainder = qr[1];
  const int s = PyObject_IsTrue(remainder.ptr());  // a nonzero remainder: the division is inexact
  const py::object m = (q << py::int_(1)) + py::int_(s);
  const py::object two_to_k1 = py::int_(1) << py::int_(K + 1);
  const std::string digits = py::str(m).cast<std::string>();
  return round_rational_to_double(negative && digits != "0" ? "-" + digits : digits,
                                  py::str(two_to_k1).cast<std::string>());
}

py::object to_python(const Vec3& v) { return types().vec3(v.x, v.y, v.z); }
py::object to_python(const Ray& r) { return types().ray(to_python(r.origin), to_python(r.direction)); }
py::object to_python(const Plane& p) { return types().plane(to_python(p.point), to_python(p.normal)); }
py::object to_python(Relation r) { return types().relation[static_cast<std::size_t>(r)]; }
py::object to_python(Stage s) { return types().stage[static_cast<std::size_t>(s)]; }

py::object to_python(const Intersection& x) { return types().intersection(to_python(x.relation), x.t); }

py::object to_python(const TracedIntersection& x) {
  return types().traced_intersection(to_python(x.intersection.relation), x.intersection.t, to_python(x.relation_stage),
                                     to_python(x.t_stage));
}

py::object to_fraction(const Rational& r) {
  return types().fraction(int_from_decimal(r.numerator), int_from_decimal(r.denominator));
}

py::object to_python(const ExactIntersection& x) {
  return types().exact_intersection(to_python(x.intersection.relation), x.intersection.t, to_fraction(x.num),
                                    to_fraction(x.den), x.t ? to_fraction(*x.t) : py::none());
}

py::object to_python(const std::optional<NearestHit>& hit) {
  if (!hit) return py::none();
  return types().nearest_hit(hit->plane, hit->t);
}

py::object to_python(TriangleRelation r) { return types().triangle_relation[static_cast<std::size_t>(r)]; }
py::object to_python(TriangleLocation l) { return types().triangle_location[static_cast<std::size_t>(l)]; }

namespace {
py::object barycentric_to_python(const Barycentric& b) { return types().barycentric(b.a, b.b, b.c); }
}  // namespace

py::object to_python(const TriangleIntersection& x) {
  return types().triangle_intersection(to_python(x.relation), to_python(x.location), x.owned, x.t,
                                       barycentric_to_python(x.barycentric));
}

py::object to_python(const TriangleClassification& x) {
  return types().triangle_classification(to_python(x.relation), to_python(x.location), x.owned);
}

py::object to_python(const TracedTriangleIntersection& x) {
  const TriangleIntersection& i = x.intersection;
  return types().traced_triangle_intersection(to_python(i.relation), to_python(i.location), i.owned, i.t,
                                              barycentric_to_python(i.barycentric), to_python(x.relation_stage),
                                              to_python(x.rounding_stage));
}

py::object to_python(const ExactTriangleIntersection& x) {
  const TriangleIntersection& i = x.intersection;
  py::object exact_barycentric = py::none();
  if (x.barycentric) {
    const auto& b = *x.barycentric;
    exact_barycentric = py::make_tuple(to_fraction(b[0]), to_fraction(b[1]), to_fraction(b[2]));
  }
  return types().exact_triangle_intersection(
      to_python(i.relation), to_python(i.location), i.owned, i.t, barycentric_to_python(i.barycentric),
      to_fraction(x.den), to_fraction(x.num), py::make_tuple(to_fraction(x.pi_a), to_fraction(x.pi_b), to_fraction(x.pi_c)),
      x.t ? to_fraction(*x.t) : py::none(), exact_barycentric);
}

py::object to_python(const Sphere& s) { return types().sphere(to_python(s.center), s.radius); }
py::object to_python(SphereOrigin o) { return types().sphere_origin[static_cast<std::size_t>(o)]; }
py::object to_python(SphereRelation r) { return types().sphere_relation[static_cast<std::size_t>(r)]; }

py::object to_python(const SphereIntersection& x) {
  return types().sphere_intersection(to_python(x.origin), to_python(x.relation), x.t1, x.t2);
}

py::object to_python(const SphereClassification& x) {
  return types().sphere_classification(to_python(x.origin), to_python(x.relation));
}

py::object to_python(const TracedSphereIntersection& x) {
  const SphereIntersection& i = x.intersection;
  return types().traced_sphere_intersection(to_python(i.origin), to_python(i.relation), i.t1, i.t2,
                                            to_python(x.relation_stage), to_python(x.rounding_stage));
}

py::object to_python(const ExactSphereIntersection& x) {
  return types().exact_sphere_intersection(to_python(x.origin), to_python(x.relation),
                                           x.u ? to_fraction(*x.u) : py::none(), x.v ? to_fraction(*x.v) : py::none());
}

py::array numeric_array(py::handle value, std::string_view name, Numbers numbers, std::string_view wanted) {
  const std::string expected = str(name) + ": expected " + str(wanted) + ", got ";
  // Before numpy.asarray, which would give the masked array's data alone.
  if (py::isinstance(value, types().masked_array))
    throw py::type_error(expected + "a numpy.ma.MaskedArray, whose mask would be ignored: pass numpy.ma.getdata(x) to "
                                    "use every value, or only the rows to keep");
  const py::array array = py::array::ensure(value);  // the value's own dtype: no cast, no copy of an ndarray
  if (!array) throw py::type_error(expected + type_name(value));
  const char kind = array.dtype().kind();
  const bool accepted = kind == 'i' || kind == 'u' ||
                        (kind == 'f' && (numbers == Numbers::real || array.size() == 0));
  if (!accepted) throw py::type_error(expected + "an array of dtype " + py::str(array.dtype()).cast<std::string>());
  return array;
}

std::string shape_string(const py::array& array) {
  std::string shape = "(";
  for (py::ssize_t k = 0; k < array.ndim(); ++k) shape += (k ? ", " : "") + std::to_string(array.shape(k));
  return shape + (array.ndim() == 1 ? ",)" : ")");
}

ColumnsView::ColumnsView(py::handle value, std::string_view name, bool allow_single) {
  const std::string shape_wanted = allow_single ? "an array of shape (n, 3) or (3,)" : "an array of shape (n, 3)";
  // A float64 array is used as it is; another real dtype is converted to float64 (a new array).
  array_ = py::array_t<double, py::array::forcecast>::ensure(
      numeric_array(value, name, Numbers::real, shape_wanted + " of real numbers (an integer or floating dtype)"));
  if (!array_) throw py::type_error(str(name) + ": the array cannot be read as float64");  // out of memory
  const auto* base = reinterpret_cast<const char*>(array_.data());
  if (allow_single && array_.ndim() == 1 && array_.shape(0) == 3) {
    single_ = true;
    rows_ = 1;
    for (std::size_t k = 0; k < 3; ++k) firsts_[k] = base + static_cast<py::ssize_t>(k) * array_.strides(0);
    return;
  }
  if (array_.ndim() != 2 || array_.shape(1) != 3)
    throw py::value_error(str(name) + ": expected " + shape_wanted + ", got shape " + shape_string(array_));
  rows_ = static_cast<std::size_t>(array_.shape(0));
  row_stride_ = array_.strides(0);
  for (std::size_t k = 0; k < 3; ++k) firsts_[k] = base + static_cast<py::ssize_t>(k) * array_.strides(1);
}

Vec3 ColumnsView::row(std::size_t i) const noexcept {
  const py::ssize_t offset = static_cast<py::ssize_t>(i) * row_stride_;
  double c[3];
  for (std::size_t k = 0; k < 3; ++k) std::memcpy(&c[k], firsts_[k] + offset, sizeof(double));  // may be unaligned
  return {c[0], c[1], c[2]};
}

std::array<std::span<const double>, 3> ColumnsView::columns(std::size_t begin, std::size_t end) {
  const std::size_t n = end - begin;
  std::array<std::span<const double>, 3> out;
  if (contiguous()) {
    for (std::size_t k = 0; k < 3; ++k)
      out[k] = {reinterpret_cast<const double*>(firsts_[k]) + (single_ ? 0 : begin), single_ ? 1 : n};
    return out;
  }
  scratch_.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {  // row by row: each row is read once, in order
    const Vec3 v = row(begin + i);
    scratch_[i] = v.x, scratch_[n + i] = v.y, scratch_[2 * n + i] = v.z;
  }
  for (std::size_t k = 0; k < 3; ++k) out[k] = {scratch_.data() + k * n, n};
  return out;
}

ValuesView::ValuesView(py::handle value, std::string_view name, bool allow_single) {
  const std::string shape_wanted = allow_single ? "an array of shape (n,) or a number" : "an array of shape (n,)";
  array_ = py::array_t<double, py::array::forcecast>::ensure(
      numeric_array(value, name, Numbers::real, shape_wanted + " of real numbers (an integer or floating dtype)"));
  if (!array_) throw py::type_error(str(name) + ": the array cannot be read as float64");  // out of memory
  first_ = reinterpret_cast<const char*>(array_.data());
  if (allow_single && array_.ndim() == 0) {
    single_ = true;
    rows_ = 1;
    return;
  }
  if (array_.ndim() != 1)
    throw py::value_error(str(name) + ": expected " + shape_wanted + ", got shape " + shape_string(array_));
  rows_ = static_cast<std::size_t>(array_.shape(0));
  stride_ = array_.strides(0);
}

double ValuesView::value(std::size_t i) const noexcept {
  double x;
  std::memcpy(&x, first_ + static_cast<py::ssize_t>(i) * stride_, sizeof(double));  // may be unaligned
  return x;
}

namespace {
void require_rows(bool single, std::size_t view_rows, std::string_view name, std::size_t rows,
                  std::string_view reference_name) {
  if (single || view_rows == rows) return;
  throw py::value_error(str(name) + " has " + std::to_string(view_rows) + " rows, " + str(reference_name) + " has " +
                        std::to_string(rows));
}
}  // namespace

void require_rows(const ColumnsView& view, std::string_view name, std::size_t rows, std::string_view reference_name) {
  require_rows(view.single(), view.rows(), name, rows, reference_name);
}

void require_rows(const ValuesView& view, std::string_view name, std::size_t rows, std::string_view reference_name) {
  require_rows(view.single(), view.rows(), name, rows, reference_name);
}

ErrorPolicy error_policy_from(std::string_view errors) {
  if (errors == "raise") return ErrorPolicy::raise;
  if (errors == "mask") return ErrorPolicy::mask;
  throw py::value_error("errors: expected 'raise' or 'mask', got '" + str(errors) + "'");
}

}  // namespace raykernel::python
