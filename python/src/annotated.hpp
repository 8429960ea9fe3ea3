// The types help() shows: the names of raykernel/_raykernel.pyi for the arguments the extension reads itself.
//
// Most arguments reach the extension as Python objects it converts with convert.hpp's readers (a ray is any
// (origin, direction) pair, an array any (n, 3) array-like), and pybind11 would show such a parameter as
// ``handle`` and such a result as ``object``. Each type here is a py::object that accepts anything (the reader
// still checks it, with its own message) and that pybind11 names as the stub does: ``RayLike``,
// ``Optional[RuleLike]``, ``ArrayLike3``. tests/test_stubs.py checks every function's shown signature against
// the stub's, so the two cannot drift apart.
#pragma once

#include <pybind11/pybind11.h>

#include <utility>

namespace raykernel::python {

namespace py = pybind11;

// A py::object under the name Tag::name. Implicit from py::object both ways, so a function returns one as it
// returns a py::object, and passes one wherever a py::handle is taken.
template <class Tag>
class Annotated : public py::object {
 public:
  using py::object::object;
  Annotated() = default;
  Annotated(const py::object& o) : py::object(o) {}                // NOLINT(google-explicit-constructor)
  Annotated(py::object&& o) : py::object(std::move(o)) {}          // NOLINT(google-explicit-constructor)
  static bool check_(py::handle h) { return h.ptr() != nullptr; }  // pybind11's isinstance: anything
};

namespace shown {

#define RAYKERNEL_PY_TYPE(Name, Shown)                                  \
  struct Name##Tag {                                                    \
    static constexpr auto name = ::pybind11::detail::const_name(Shown); \
  };                                                                    \
  using Name = Annotated<Name##Tag>

// Arguments (write shown::RayLike: the result names below are also raykernel's C++ types).
RAYKERNEL_PY_TYPE(Vec3Like, "Vec3Like");
RAYKERNEL_PY_TYPE(RayLike, "RayLike");
RAYKERNEL_PY_TYPE(PlaneLike, "PlaneLike");
RAYKERNEL_PY_TYPE(TriangleLike, "TriangleLike");
RAYKERNEL_PY_TYPE(PrimitiveLike, "Union[SphereLike, PlaneLike, TriangleLike]");
RAYKERNEL_PY_TYPE(HitLike, "Union[RayLike, Vec3Like]");
RAYKERNEL_PY_TYPE(SpawnSurfaceLike, "Union[TriangleLike, Sphere]");
RAYKERNEL_PY_TYPE(OptionalRule, "Optional[RuleLike]");
RAYKERNEL_PY_TYPE(ArrayLike3, "ArrayLike3");
RAYKERNEL_PY_TYPE(OptionalArrayLike3, "Optional[ArrayLike3]");
RAYKERNEL_PY_TYPE(ArrayLike, "npt.ArrayLike");
RAYKERNEL_PY_TYPE(ScalarOrArray, "Union[float, npt.ArrayLike]");
RAYKERNEL_PY_TYPE(Progress, "Optional[Callable[[int, int], object]]");
RAYKERNEL_PY_TYPE(Planes, "Planes");
RAYKERNEL_PY_TYPE(PlanesOrArray, "Union[Sequence[PlaneLike], ArrayLike3]");
RAYKERNEL_PY_TYPE(Scene, "Union[Mesh, SphereSet, Planes]");
RAYKERNEL_PY_TYPE(MeshOrSpheres, "Union[Mesh, SphereSet]");
RAYKERNEL_PY_TYPE(SpheresLike, "Union[ArrayLike3, Sequence[Sphere]]");
RAYKERNEL_PY_TYPE(OptionalArrayLike, "Optional[npt.ArrayLike]");
RAYKERNEL_PY_TYPE(Words, "Words");
RAYKERNEL_PY_TYPE(RationalLike, "Union[Fraction, int]");
RAYKERNEL_PY_TYPE(OptionalInt, "Optional[int]");
RAYKERNEL_PY_TYPE(RelationLike, "Union[Relation, str, int]");
RAYKERNEL_PY_TYPE(NameOrCode, "Union[str, int]");
RAYKERNEL_PY_TYPE(FloatSequence, "Sequence[float]");
RAYKERNEL_PY_TYPE(Real, "float");
RAYKERNEL_PY_TYPE(PathLike, "Union[str, bytes, os.PathLike[str], os.PathLike[bytes]]");

// Results (the NamedTuples of raykernel._types the extension builds).
RAYKERNEL_PY_TYPE(PrimitiveIntersection, "Union[SphereIntersection, Intersection, TriangleIntersection]");
RAYKERNEL_PY_TYPE(PrimitiveRelation, "Union[SphereClassification, Relation, TriangleClassification]");
RAYKERNEL_PY_TYPE(ExactPrimitiveIntersection,
                  "Union[ExactSphereIntersection, ExactIntersection, ExactTriangleIntersection]");
RAYKERNEL_PY_TYPE(TracedPrimitiveIntersection,
                  "Union[TracedSphereIntersection, TracedIntersection, TracedTriangleIntersection]");
RAYKERNEL_PY_TYPE(NearestHit, "Optional[Union[NearestHit, MeshHit, SphereHit]]");
RAYKERNEL_PY_TYPE(MeshHits, "MeshHits");
RAYKERNEL_PY_TYPE(PointLocation, "PointLocation");
RAYKERNEL_PY_TYPE(ClosestPoint, "ClosestPoint");
RAYKERNEL_PY_TYPE(SpawnedOrigin, "SpawnedOrigin");
RAYKERNEL_PY_TYPE(Triangle, "Triangle");
RAYKERNEL_PY_TYPE(Plane, "Plane");
RAYKERNEL_PY_TYPE(Sphere, "Sphere");
RAYKERNEL_PY_TYPE(IntersectionArrays, "IntersectionArrays");
RAYKERNEL_PY_TYPE(RelationArrays, "RelationArrays");
RAYKERNEL_PY_TYPE(TriangleIntersectionArrays, "TriangleIntersectionArrays");
RAYKERNEL_PY_TYPE(TriangleClassificationArrays, "TriangleClassificationArrays");
RAYKERNEL_PY_TYPE(SphereIntersectionArrays, "SphereIntersectionArrays");
RAYKERNEL_PY_TYPE(NearestHitArrays, "Union[NearestHitArrays, MeshHitArrays, SphereHitArrays]");
RAYKERNEL_PY_TYPE(MeshHitArrays, "MeshHitArrays");
RAYKERNEL_PY_TYPE(PointLocationArrays, "PointLocationArrays");
RAYKERNEL_PY_TYPE(ClosestPointArrays, "ClosestPointArrays");
RAYKERNEL_PY_TYPE(OcclusionArrays, "OcclusionArrays");
RAYKERNEL_PY_TYPE(CrossingArrays, "CrossingArrays");
RAYKERNEL_PY_TYPE(SpawnArrays, "SpawnArrays");
RAYKERNEL_PY_TYPE(PlaneQuery, "Tuple[Ray, Plane]");
RAYKERNEL_PY_TYPE(PlaneQueryArrays, "Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]");
RAYKERNEL_PY_TYPE(PlanePair, "Tuple[str, Ray, Tuple[Plane, Plane], int]");
RAYKERNEL_PY_TYPE(TriangleQuery, "Tuple[Ray, Triangle]");
RAYKERNEL_PY_TYPE(TriangleQueryArrays, "Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]");
RAYKERNEL_PY_TYPE(SphereQuery, "Tuple[Ray, Sphere]");
RAYKERNEL_PY_TYPE(SphereQueryArrays, "Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]");
RAYKERNEL_PY_TYPE(FuzzQuery, "Tuple[Ray, Plane, Optional[str]]");

#undef RAYKERNEL_PY_TYPE

}  // namespace shown

}  // namespace raykernel::python

namespace pybind11::detail {
template <class Tag>
struct handle_type_name<raykernel::python::Annotated<Tag>> {
  static constexpr auto name = Tag::name;
};
}  // namespace pybind11::detail
