// raykernel::testkit for Python (the submodule raykernel._raykernel.testkit, used by raykernel.testing): the
// hard-query constructors with the random words drawn from a Python callable (so that Hypothesis draws each
// word and shrinks it), the reference check, ulp distances, and the fuzz decoder.
#include "bindings.hpp"
#include "convert.hpp"
#include "mesh.hpp"

#include <raykernel/testkit/plane_fuzz_decoder.hpp>
#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/meshes.hpp>
#include <raykernel/testkit/plane_pairs.hpp>
#include <raykernel/testkit/plane_reference_check.hpp>
#include <raykernel/testkit/sphere_queries.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/testkit/triangle_reference_check.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::python {
namespace {

using testkit::PlaneTieKind;
using testkit::QueryKind;

// The kind named `name` among `all` (one of testkit's all_*_kinds), or ValueError naming `what` ("query",
// "triangle query") and listing the kinds.
template <class Kind, std::size_t N>
Kind kind_from(const std::array<Kind, N>& all, const std::string& name, std::string_view what) {
  std::string known;
  for (Kind k : all) {
    if (testkit::to_string(k) == name) return k;
    known += (known.empty() ? "" : ", ") + std::string(testkit::to_string(k));
  }
  throw py::value_error("unknown " + std::string(what) + " kind '" + name + "' (kinds: " + known + ")");
}

// The kinds named `names` (at least one), for the *_arrays constructions.
template <class Kind, std::size_t N>
std::vector<Kind> kinds_from(const std::array<Kind, N>& all, const std::vector<std::string>& names,
                             std::string_view what) {
  if (names.empty()) throw py::value_error("kinds: give at least one query kind");
  std::vector<Kind> chosen;
  for (const std::string& name : names) chosen.push_back(kind_from(all, name, what));
  return chosen;
}

// The names of `all`, as the tuple of kinds the submodule exports (QUERY_KINDS, ...).
template <class Kind, std::size_t N>
py::tuple kind_names(const std::array<Kind, N>& all) {
  py::list names;
  for (Kind k : all) names.append(std::string(testkit::to_string(k)));
  return py::tuple(names);
}

QueryKind query_kind_from(const std::string& name) { return kind_from(testkit::all_query_kinds, name, "query"); }

testkit::TriangleQueryKind triangle_kind_from(const std::string& name) {
  return kind_from(testkit::all_triangle_query_kinds, name, "triangle query");
}

testkit::SphereQueryKind sphere_kind_from(const std::string& name) {
  return kind_from(testkit::all_sphere_query_kinds, name, "sphere query");
}

// A TriangleIntersection from what Python code answered: (relation, location, owned, t, barycentric), each a
// raykernel enum member, its string value or its code; t and the coordinates may be NaN ("not computed").
TriangleIntersection triangle_answer_from(py::handle relation, py::handle location, bool owned, double t,
                                          py::handle barycentric) {
  auto code_of = [](py::handle value, std::string_view field, int count) {
    if (PyUnicode_Check(value.ptr())) {  // the str enums' values and plain strings
      const py::module_ types = py::module_::import("raykernel._types");
      const char* type = field == "relation" ? "TriangleRelation" : "TriangleLocation";
      try {
        return types.attr(type)(value).attr("code").cast<int>();
      } catch (py::error_already_set&) {
        throw py::value_error(std::string(field) + ": unknown value '" + value.cast<std::string>() + "'");
      }
    }
    const int code = value.cast<int>();
    if (code < 0 || code >= count) throw py::value_error(std::string(field) + ": code out of range");
    return code;
  };
  TriangleIntersection x{};
  x.relation = static_cast<TriangleRelation>(code_of(relation, "relation", 6));
  x.location = static_cast<TriangleLocation>(code_of(location, "location", 9));
  x.owned = owned;
  x.t = t;
  const Vec3 u = vec3_from(barycentric, "barycentric");
  x.barycentric = {u.x, u.y, u.z};
  return x;
}

PlaneTieKind plane_tie_kind_from(const std::string& name) {
  return kind_from(testkit::all_plane_tie_kinds, name, "plane tie");
}

// The words a construction draws: from bytes (8 at a time, little-endian, then zero words: the fuzz decoder's
// source, testkit::bit_source_from_bytes), or from a Python callable returning ints (taken modulo 2^64;
// exceptions it raises, e.g. Hypothesis stopping a test case, propagate through the construction unchanged).
// `storage` keeps the bytes alive while the source reads them.
testkit::BitSource python_bits(py::handle words, std::string& storage) {
  if (PyBytes_Check(words.ptr())) {
    storage = words.cast<std::string>();
    return testkit::bit_source_from_bytes({reinterpret_cast<const std::uint8_t*>(storage.data()), storage.size()});
  }
  if (!PyCallable_Check(words.ptr()))
    throw py::type_error("words: expected bytes or a callable returning ints, got " +
                         std::string(Py_TYPE(words.ptr())->tp_name));
  const py::function draw = py::reinterpret_borrow<py::function>(words);
  return [draw]() -> std::uint64_t {
    const py::object word = draw();
    const unsigned long long w = PyLong_AsUnsignedLongLongMask(word.ptr());
    if (w == static_cast<unsigned long long>(-1) && PyErr_Occurred()) throw py::error_already_set();
    return w;
  };
}

py::object query_to_python(const testkit::Query& q) { return py::make_tuple(to_python(q.ray), to_python(q.plane)); }

py::bytes to_bytes(const std::vector<std::uint8_t>& v) {
  return {reinterpret_cast<const char*>(v.data()), v.size()};
}

// `count` queries of kinds drawn from `chosen`, reproducibly from `seed` (SplitMix64: for each query the index of
// its kind, then the words of its construction), as arrays: `make(kind, bits)` builds a query and `fields(query)`
// gives its V vectors and S numbers. Returns a tuple of V (count, 3) float64 arrays, S (count,) float64 arrays,
// and the int32 index into `chosen` of each query's kind.
template <std::size_t V, std::size_t S, class Kind, class Make, class Fields>
py::tuple query_arrays(const std::vector<Kind>& chosen, std::size_t count, std::uint64_t seed, Make&& make,
                       Fields&& fields) {
  std::array<py::array_t<double>, V> vectors;
  std::array<py::array_t<double>, S> numbers;
  std::array<double*, V> vectors_out{};
  std::array<double*, S> numbers_out{};
  for (std::size_t a = 0; a < V; ++a) {
    vectors[a] = py::array_t<double>({count, std::size_t{3}});
    vectors_out[a] = vectors[a].mutable_data();
  }
  for (std::size_t a = 0; a < S; ++a) {
    numbers[a] = py::array_t<double>(static_cast<py::ssize_t>(count));
    numbers_out[a] = numbers[a].mutable_data();
  }
  py::array_t<std::int32_t> kind_index(static_cast<py::ssize_t>(count));
  std::int32_t* const kinds_out = kind_index.mutable_data();
  {
    py::gil_scoped_release release;
    testkit::SplitMix64 rng(seed);
    const testkit::BitSource bits = [&rng] { return rng(); };
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t which = static_cast<std::size_t>(rng() % chosen.size());
      const auto [vs, xs] = fields(make(chosen[which], bits));
      for (std::size_t a = 0; a < V; ++a) {
        const Vec3& v = vs[a];
        vectors_out[a][3 * i] = v.x, vectors_out[a][3 * i + 1] = v.y, vectors_out[a][3 * i + 2] = v.z;
      }
      for (std::size_t a = 0; a < S; ++a) numbers_out[a][i] = xs[a];
      kinds_out[i] = static_cast<std::int32_t>(which);
    }
  }
  py::list out;
  for (auto& a : vectors) out.append(a);
  for (auto& a : numbers) out.append(a);
  out.append(kind_index);
  return py::tuple(out);
}

}  // namespace

void bind_testkit(py::module_& parent) {
  py::module_ m = parent.def_submodule("testkit", "raykernel::testkit: hard queries, reference check, fuzz decoder.");

  m.attr("QUERY_KINDS") = kind_names(testkit::all_query_kinds);
  m.attr("PLANE_TIE_KINDS") = kind_names(testkit::all_plane_tie_kinds);

  m.def(
      "make_query",
      [](const std::string& kind, shown::Words words) -> shown::PlaneQuery {
        std::string storage;
        return query_to_python(make_query(query_kind_from(kind), python_bits(words, storage)));
      },
      py::arg("kind"), py::arg("words"),
      R"doc(A hard ray–plane query of ``kind`` (one of QUERY_KINDS), as ``(Ray, Plane)``: testkit::make_query with
its random 64-bit words read from ``words``: bytes (8 per word, little-endian, zero words after the end) or a
callable returning one word per call. Deterministic in the words: the same words give the same query, and
smaller words give simpler queries (all zero words: the simplest of the kind).)doc");

  m.def(
      "make_query_arrays",
      [](const std::vector<std::string>& kinds, std::size_t count, std::uint64_t seed) -> shown::PlaneQueryArrays {
        return query_arrays<4, 0>(
            kinds_from(testkit::all_query_kinds, kinds, "query"), count, seed,
            [](QueryKind kind, const testkit::BitSource& bits) { return make_query(kind, bits); },
            [](const testkit::Query& q) {
              return std::pair{std::array{q.ray.origin, q.ray.direction, q.plane.point, q.plane.normal},
                               std::array<double, 0>{}};
            });
      },
      py::arg("kinds"), py::arg("count"), py::arg("seed"),
      R"doc(``count`` hard queries as arrays, reproducibly from ``seed`` (SplitMix64): ``(origins, directions,
points, normals, kind_index)``, four (count, 3) float64 arrays and the index into ``kinds`` of each query's
kind. For benchmarks and for vectorized code.)doc");

  m.def(
      "make_plane_pair",
      [](const std::optional<std::string>& kind, shown::Words words) -> shown::PlanePair {
        std::string storage;
        const testkit::BitSource bits = python_bits(words, storage);
        const testkit::PlanePair pp = kind ? testkit::make_plane_pair_near_tie(plane_tie_kind_from(*kind), bits)
                                           : testkit::make_plane_pair_near_tie(bits);
        return py::make_tuple(std::string(testkit::to_string(pp.kind)), to_python(pp.ray),
                              py::make_tuple(to_python(pp.planes[0]), to_python(pp.planes[1])), pp.order);
      },
      py::arg("kind"), py::arg("words"),
      R"doc(One ray and two planes it hits whose exact t tie or differ by less than an ulp
(testkit::make_plane_pair_near_tie): ``(kind, ray, (plane0, plane1), order)``, ``order`` the sign of t1 − t0.
``kind`` one of PLANE_TIE_KINDS, or None to draw it; ``words`` as in make_query.)doc");

  m.def(
      "check_against_reference",
      [](shown::RayLike ray, shown::PlaneLike plane, shown::RelationLike relation, shown::Real t,
         std::uint64_t max_t_ulps) {
        const testkit::Query q{ray_from(ray), plane_from(plane)};
        const Relation r = relation_from(relation);
        const double got_t = double_from(t, "t");
        testkit::ReferenceCheck c;
        {
          py::gil_scoped_release release;
          c = testkit::check_against_reference(q, Intersection{r, got_t}, max_t_ulps);
        }
        py::dict d;
        d["expected"] = to_python(c.expected);
        d["got"] = to_python(c.got);
        d["exact_num"] = to_fraction(c.exact_num);
        d["exact_den"] = to_fraction(c.exact_den);
        d["exact_t"] = c.exact_t ? to_fraction(*c.exact_t) : py::none();
        d["max_t_ulps"] = c.max_t_ulps;
        d["relation_matches"] = c.relation_matches;
        d["t_compared"] = c.t_compared;
        d["t_ulps"] = c.t_ulps ? py::object(py::int_(*c.t_ulps)) : py::none();
        d["t_direction"] = c.t_direction;
        d["passed"] = c.passed();
        d["report"] = c.report();
        return d;
      },
      py::arg("ray"), py::arg("plane"), py::arg("relation"), py::arg("t"), py::arg("max_t_ulps") = 0,
      R"doc(testkit::check_against_reference: the exact answer to (ray, plane) compared with ``relation``
and ``t``, as a dict (expected, got, exact_num, exact_den, exact_t, relation_matches, t_compared, t_ulps,
t_direction, passed, report). Raises ValueError for invalid input: it has no answer to compare with.)doc");

  m.attr("TRIANGLE_QUERY_KINDS") = kind_names(testkit::all_triangle_query_kinds);

  m.def(
      "make_triangle_query",
      [](const std::string& kind, shown::Words words) -> shown::TriangleQuery {
        std::string storage;
        const testkit::TriangleQuery q = make_triangle_query(triangle_kind_from(kind), python_bits(words, storage));
        return py::make_tuple(to_python(q.ray),
                              types().triangle(to_python(q.triangle.a), to_python(q.triangle.b), to_python(q.triangle.c)));
      },
      py::arg("kind"), py::arg("words"),
      R"doc(A hard ray–triangle query of ``kind`` (one of TRIANGLE_QUERY_KINDS), as ``(Ray, Triangle)``:
testkit::make_triangle_query with its words read as in make_query (bytes or a callable). Always valid input.)doc");

  m.def(
      "make_triangle_query_arrays",
      [](const std::vector<std::string>& kinds, std::size_t count, std::uint64_t seed) -> shown::TriangleQueryArrays {
        return query_arrays<5, 0>(
            kinds_from(testkit::all_triangle_query_kinds, kinds, "triangle query"), count, seed,
            [](testkit::TriangleQueryKind kind, const testkit::BitSource& bits) {
              return make_triangle_query(kind, bits);
            },
            [](const testkit::TriangleQuery& q) {
              return std::pair{std::array{q.ray.origin, q.ray.direction, q.triangle.a, q.triangle.b, q.triangle.c},
                               std::array<double, 0>{}};
            });
      },
      py::arg("kinds"), py::arg("count"), py::arg("seed"),
      R"doc(``count`` hard ray–triangle queries as arrays, reproducibly from ``seed``: ``(origins, directions,
a, b, c, kind_index)``.)doc");

  m.attr("SPHERE_QUERY_KINDS") = kind_names(testkit::all_sphere_query_kinds);

  m.def(
      "make_sphere_query",
      [](const std::string& kind, shown::Words words) -> shown::SphereQuery {
        std::string storage;
        const testkit::SphereQuery q = make_sphere_query(sphere_kind_from(kind), python_bits(words, storage));
        return py::make_tuple(to_python(q.ray), to_python(q.sphere));
      },
      py::arg("kind"), py::arg("words"),
      R"doc(A hard ray–sphere query of ``kind`` (one of SPHERE_QUERY_KINDS), as ``(Ray, Sphere)``:
testkit::make_sphere_query with its words read as in make_query (bytes or a callable). Always valid input.)doc");

  m.def(
      "make_sphere_query_arrays",
      [](const std::vector<std::string>& kinds, std::size_t count, std::uint64_t seed) -> shown::SphereQueryArrays {
        return query_arrays<3, 1>(
            kinds_from(testkit::all_sphere_query_kinds, kinds, "sphere query"), count, seed,
            [](testkit::SphereQueryKind kind, const testkit::BitSource& bits) { return make_sphere_query(kind, bits); },
            [](const testkit::SphereQuery& q) {
              return std::pair{std::array{q.ray.origin, q.ray.direction, q.sphere.center},
                               std::array{q.sphere.radius}};
            });
      },
      py::arg("kinds"), py::arg("count"), py::arg("seed"),
      R"doc(``count`` hard ray–sphere queries as arrays, reproducibly from ``seed``: ``(origins, directions,
centers, radii, kind_index)``, three (count, 3) float64 arrays, a (count,) float64 array and the index into
``kinds`` of each query's kind.)doc");

  m.def(
      "check_triangle_against_reference",
      [](shown::RayLike ray, shown::TriangleLike triangle, shown::NameOrCode relation, shown::NameOrCode location,
         bool owned, double t, shown::FloatSequence barycentric, shown::OptionalRule rule, std::uint64_t max_ulps,
         bool check_location) {
        const testkit::TriangleQuery q{ray_from(ray), triangle_from(triangle)};
        const TriangleIntersection got = triangle_answer_from(relation, location, owned, t, barycentric);
        const TriangleRule chosen = rule_or_owned(rule);
        std::optional<testkit::TriangleReferenceCheck> c;
        {
          py::gil_scoped_release release;
          c = testkit::check_against_reference(q, got, chosen, max_ulps, check_location);
        }
        py::dict d;
        d["expected"] = to_python(c->expected);
        d["got"] = to_python(c->got);
        d["exact"] = to_python(c->exact);
        d["rule"] = types().triangle_rule[static_cast<std::size_t>(chosen)];
        d["max_ulps"] = c->max_ulps;
        d["check_location"] = c->check_location;
        d["relation_matches"] = c->relation_matches;
        d["location_matches"] = c->location_matches;
        d["owned_matches"] = c->owned_matches;
        py::list ulps;
        for (const auto& u : c->ulps) ulps.append(u ? py::object(py::int_(*u)) : py::none());
        d["ulps"] = py::tuple(ulps);
        d["passed"] = c->passed();
        d["report"] = c->report();
        return d;
      },
      py::arg("ray"), py::arg("triangle"), py::arg("relation"), py::arg("location"), py::arg("owned"), py::arg("t"),
      py::arg("barycentric"), py::arg("rule") = py::none(), py::arg("max_ulps") = 0, py::arg("check_location") = true,
      R"doc(testkit::check_against_reference for a ray–triangle answer: the exact answer under ``rule`` compared
with (relation, location, owned, t, barycentric), as a dict (expected, got, exact, rule, max_ulps,
check_location, relation_matches, location_matches, owned_matches, ulps — of t, ua, ub, uc, None where not
compared —, passed, report). Raises ValueError for invalid input.)doc");

  m.def(
      "make_octahedron", [](double radius) { return PythonMesh(testkit::make_octahedron(radius)); },
      py::arg("radius") = 1.0, "testkit::make_octahedron: a closed mesh, vertices ±radius on the axes, 8 triangles.");
  m.def(
      "make_subdivided_cube",
      [](int n, double half_size) {
        if (n < 1) throw py::value_error("n: expected n ≥ 1");
        return PythonMesh(testkit::make_subdivided_cube(n, half_size));
      },
      py::arg("n"), py::arg("half_size") = 1.0,
      "testkit::make_subdivided_cube: the cube [−h, h]^3, each face cut into n × n squares of two triangles.");
  m.def(
      "make_icosphere",
      [](int level, int grid_bits) {
        if (level < 0 || level > 8) throw py::value_error("level: expected 0..8");
        return PythonMesh(testkit::make_icosphere(level, grid_bits));
      },
      py::arg("level"), py::arg("grid_bits") = 30,
      "testkit::make_icosphere: the icosahedron subdivided `level` times, 20·4^level triangles, vertices on a grid.");

  m.def(
      "ulp_distance",
      [](double a, double b) -> std::optional<std::uint64_t> { return testkit::ulp_distance(a, b); }, py::arg("a"),
      py::arg("b"),
      R"doc(The number of steps from a to b through the doubles in increasing order (−0 and +0 one step apart,
DBL_MAX to inf one step): 0 exactly when a and b have the same bits. None when either is NaN.)doc");
  m.def(
      "ulp_difference",
      [](double a, double b) -> std::optional<std::int64_t> { return testkit::ulp_difference(a, b); }, py::arg("a"),
      py::arg("b"), "ulp_distance with the sign of b − a in that order (saturated to ±(2^63 − 1)); None for NaN.");
  m.def("hex_string", &testkit::hex_string, py::arg("x"), "x as a hexadecimal float (\"0x1.8p+1\"): exact.");
  m.def("shortest_decimal", &testkit::shortest_decimal, py::arg("x"),
        "x in the shortest decimal that reads back to the same double.");
  m.def(
      "classify_line",
      [](shown::RayLike ray, shown::PlaneLike plane) {
        return testkit::classify_line({ray_from(ray), plane_from(plane)});
      },
      py::arg("ray"), py::arg("plane"), "The query as one line of `raykernel classify` input, in hex floats.");

  m.def(
      "decode_fuzz_query",
      [](const py::bytes& data) -> shown::FuzzQuery {
        const std::string s = data;
        const testkit::FuzzQuery f = testkit::decode_fuzz_query(
            {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
        return py::make_tuple(to_python(f.query.ray), to_python(f.query.plane),
                              f.kind ? py::object(py::str(std::string(testkit::to_string(*f.kind)))) : py::none());
      },
      py::arg("data"),
      R"doc(Any bytes as a query (testkit/plane_fuzz_decoder.hpp): raw doubles when the first byte is below 0x80
(possibly invalid input), else a hard query of kind QUERY_KINDS[(byte − 0x80) mod 13] built from the
following bytes. ``(ray, plane, kind or None)``.)doc");
  m.def(
      "encode_raw_fuzz_input",
      [](shown::RayLike ray, shown::PlaneLike plane) {
        return to_bytes(testkit::encode_raw_fuzz_input(ray_from(ray), plane_from(plane)));
      },
      py::arg("ray"), py::arg("plane"), "The raw-mode fuzz input that decodes to exactly (ray, plane).");
  m.def(
      "encode_hard_query_fuzz_input",
      [](const std::string& kind, const std::vector<std::uint64_t>& words) {
        return to_bytes(testkit::encode_hard_query_fuzz_input(query_kind_from(kind), words));
      },
      py::arg("kind"), py::arg("words"), "The fuzz input that decodes to make_query(kind, words then zeros).");
}

}  // namespace raykernel::python
