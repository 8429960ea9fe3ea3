"""The value types of raykernel's Python API: plain NamedTuples and str-valued enums.

Inputs need not be these types: every function takes a vector as any sequence of three numbers, a ray as
any ``(origin, direction)`` pair and a plane as any ``(point, normal)`` pair; a sphere is a ``Sphere``
(which tells it from a plane). Results are these types, so they unpack like tuples, compare by value, and
print readably. The compiled extension builds its results from the classes defined here.
"""

from __future__ import annotations

import enum
import errno as _errno
import os
from fractions import Fraction
from typing import Dict, NamedTuple, Optional, Tuple, Union

import numpy as np

try:  # Python 3.11: str() of a member is its value
    from enum import StrEnum as _StrEnum
except ImportError:  # pragma: no cover - older Pythons

    class _StrEnum(str, enum.Enum):
        def __str__(self) -> str:
            return str(self.value)


class Vec3(NamedTuple):
    x: float
    y: float
    z: float


class Ray(NamedTuple):
    """The half-line {origin + t·direction : t ≥ 0}; the direction need not have unit length."""

    origin: Vec3
    direction: Vec3


class Plane(NamedTuple):
    """The plane {x : (x − point)·normal = 0}; the normal need not have unit length."""

    point: Vec3
    normal: Vec3


class Triangle(NamedTuple):
    """The triangle a, b, c (docs/contract.md §6); its normal is (b − a) × (c − a)."""

    a: Vec3
    b: Vec3
    c: Vec3


class Sphere(NamedTuple):
    """The sphere {x : |x − center| = radius} (docs/contract.md §10), a closed surface; radius > 0, finite.

    Only this type is taken as a sphere by ``intersect(ray, primitive)`` and its sisters: a bare pair
    ``(point, normal)`` is a plane."""

    center: Vec3
    radius: float


class Relation(_StrEnum):
    """How a ray meets a plane (docs/contract.md §1). Members are strings: ``Relation.HIT == "hit"``.

    ``code`` is the value the vectorized functions put in their uint8 ``relation`` arrays.
    """

    HIT = "hit"  # den ≠ 0 and num/den ≥ 0: the ray meets the plane at t = num/den
    BEHIND = "behind"  # den ≠ 0 and num/den < 0: the line meets the plane behind the origin
    PARALLEL = "parallel"  # den = 0 and num ≠ 0: no point of the line is on the plane
    IN_PLANE = "in-plane"  # den = 0 and num = 0: the whole ray lies in the plane

    @property
    def code(self) -> int:
        return _RELATION_CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "Relation":
        return _RELATIONS_BY_CODE[int(code)]


_RELATIONS_BY_CODE = (Relation.HIT, Relation.BEHIND, Relation.PARALLEL, Relation.IN_PLANE)
_RELATION_CODES = {r: k for k, r in enumerate(_RELATIONS_BY_CODE)}


class Stage(_StrEnum):
    """The stages of the certified cascade, cheapest first (README, "How it is fast")."""

    FILTER = "filter"  # binary64 with a certified error bound: signs only
    COMPENSATED = "compensated"  # double-double: signs and the correct rounding of t
    EXPANSION = "expansion"  # Shewchuk's exact expansions
    EXACT = "exact"  # exact rationals (GMP) and MPFR


class Intersection(NamedTuple):
    """The answer to one ray–plane query: the relation, and t (NaN for PARALLEL and IN_PLANE)."""

    relation: Relation
    t: float


class TracedIntersection(NamedTuple):
    relation: Relation
    t: float
    relation_stage: Stage
    t_stage: Stage


class ExactIntersection(NamedTuple):
    """The answer with the exact values it was decided from: num = (p − o)·n, den = d·n, and exact_t =
    num/den (None for PARALLEL and IN_PLANE); t is exact_t rounded to nearest, ties to even."""

    relation: Relation
    t: float
    num: Fraction
    den: Fraction
    exact_t: Optional[Fraction]


class NearestHit(NamedTuple):
    """The first plane a ray meets: its index among the planes given, and its t."""

    plane: int
    t: float


StageCounts = Dict[str, Dict[str, int]]


# Ray–triangle (docs/contract.md §6) --------------------------------------------------------------------------


class TriangleRule(_StrEnum):
    """Which points of a triangle count as a hit (docs/contract.md §6). ``TriangleRule.OWNED == "owned"``."""

    OWNED = "owned"  # watertight: an edge or vertex shared by a closed mesh's triangles belongs to exactly one
    CLOSED = "closed"  # the triangle with its boundary: a ray through a shared edge hits both triangles


class TriangleRelation(_StrEnum):
    """How a ray meets a triangle under a rule. Members are strings: ``TriangleRelation.MISS == "miss"``.

    ``code`` is the value the vectorized functions put in their uint8 ``relation`` arrays (the C++ enum's).
    """

    HIT = "hit"  # the ray passes through the triangle under the rule, at t ≥ 0
    BEHIND = "behind"  # the line passes through it at t < 0
    MISS = "miss"  # the line crosses the plane (den ≠ 0) outside the triangle under the rule
    DEGENERATE = "degenerate"  # N = (b − a) × (c − a) = 0: collinear or repeated vertices, never hit
    PARALLEL = "parallel"  # N ≠ 0, den = d·N = 0, num ≠ 0: the line never meets the plane
    COPLANAR = "coplanar"  # N ≠ 0, den = 0, num = 0: the line lies in the plane (never a hit)

    @property
    def code(self) -> int:
        return _TRIANGLE_RELATION_CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "TriangleRelation":
        return _TRIANGLE_RELATIONS_BY_CODE[int(code)]


class TriangleLocation(_StrEnum):
    """Where the ray's line meets the triangle's plane, from the signs of πa, πb, πc against den's (§6).
    ``code`` is the value of the vectorized functions' uint8 ``location`` arrays."""

    INSIDE = "inside"  # all three π nonzero with den's sign
    EDGE_AB = "edge-ab"  # πc = 0, the others with den's sign
    EDGE_BC = "edge-bc"  # πa = 0
    EDGE_CA = "edge-ca"  # πb = 0
    VERTEX_A = "vertex-a"  # πb = πc = 0
    VERTEX_B = "vertex-b"  # πc = πa = 0
    VERTEX_C = "vertex-c"  # πa = πb = 0
    OUTSIDE = "outside"  # some π with the sign opposite to den's
    NONE = "none"  # den = 0 (degenerate, parallel, coplanar): the line does not cross the plane

    @property
    def code(self) -> int:
        return _TRIANGLE_LOCATION_CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "TriangleLocation":
        return _TRIANGLE_LOCATIONS_BY_CODE[int(code)]


_TRIANGLE_RELATIONS_BY_CODE = tuple(TriangleRelation)
_TRIANGLE_RELATION_CODES = {r: k for k, r in enumerate(_TRIANGLE_RELATIONS_BY_CODE)}
_TRIANGLE_LOCATIONS_BY_CODE = tuple(TriangleLocation)
_TRIANGLE_LOCATION_CODES = {r: k for k, r in enumerate(_TRIANGLE_LOCATIONS_BY_CODE)}


class PointLocation(_StrEnum):
    """Where a point is against a mesh (docs/contract.md §7, ``inside``). ``code`` is the value of
    ``inside_batch``'s uint8 ``location`` array."""

    OUTSIDE = "outside"  # winding number 0
    INSIDE = "inside"  # winding number nonzero (outward or inward normals alike)
    ON_SURFACE = "on-surface"  # on some triangle, boundary included, exactly

    @property
    def code(self) -> int:
        return _POINT_LOCATION_CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "PointLocation":
        return _POINT_LOCATIONS_BY_CODE[int(code)]


_POINT_LOCATIONS_BY_CODE = tuple(PointLocation)
_POINT_LOCATION_CODES = {r: k for k, r in enumerate(_POINT_LOCATIONS_BY_CODE)}


class ClosestFeature(_StrEnum):
    """Where on its triangle a closest point lies (docs/contract.md §11). ``code`` is the value of
    ``closest_point_batch``'s uint8 ``feature`` array."""

    VERTEX = "vertex"  # a vertex of the triangle (corner 0, 1, 2: a, b, c)
    EDGE = "edge"  # inside an edge (corner 0, 1, 2: ab, bc, ca)
    FACE = "face"  # inside the face

    @property
    def code(self) -> int:
        return _CLOSEST_FEATURE_CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "ClosestFeature":
        return _CLOSEST_FEATURES_BY_CODE[int(code)]


_CLOSEST_FEATURES_BY_CODE = tuple(ClosestFeature)
_CLOSEST_FEATURE_CODES = {r: k for k, r in enumerate(_CLOSEST_FEATURES_BY_CODE)}


class Barycentric(NamedTuple):
    """Barycentric coordinates (πa, πb, πc)/den of the point where the line crosses the plane: the weights of
    the vertices a, b, c (they sum to 1 exactly; each is rounded on its own)."""

    a: float
    b: float
    c: float


class TriangleIntersection(NamedTuple):
    """The answer to one ray–triangle query (docs/contract.md §6). ``relation`` is under the rule asked
    for; ``location`` is NONE unless the line crosses the plane; ``owned`` says whether the owned rule lets
    the line through (False unless it crosses); ``t`` and ``barycentric`` are the exact values rounded to
    nearest, NaN when the line does not cross the plane or when not asked for."""

    relation: TriangleRelation
    location: TriangleLocation
    owned: bool
    t: float
    barycentric: Barycentric


class TriangleClassification(NamedTuple):
    """The relation, location and owned flag alone (``relation(ray, triangle)``): nothing rounded."""

    relation: TriangleRelation
    location: TriangleLocation
    owned: bool


class TracedTriangleIntersection(NamedTuple):
    """``TriangleIntersection`` plus the stages that decided the relation and the roundings."""

    relation: TriangleRelation
    location: TriangleLocation
    owned: bool
    t: float
    barycentric: Barycentric
    relation_stage: Stage
    rounding_stage: Stage


class ExactTriangleIntersection(NamedTuple):
    """The exact answer with the rationals it was decided from (``intersect_exact_rational(ray, triangle)``):
    den = d·N, num = (a − o)·N, pi = (πa, πb, πc); when den ≠ 0, exact_t = num/den and exact_barycentric =
    (πa, πb, πc)/den (None otherwise). ``t`` and ``barycentric`` are those rounded to nearest."""

    relation: TriangleRelation
    location: TriangleLocation
    owned: bool
    t: float
    barycentric: Barycentric
    den: Fraction
    num: Fraction
    pi: Tuple[Fraction, Fraction, Fraction]
    exact_t: Optional[Fraction]
    exact_barycentric: Optional[Tuple[Fraction, Fraction, Fraction]]


# Ray–sphere (docs/contract.md §10) ----------------------------------------------------------------------------


class SphereOrigin(_StrEnum):
    """Where the ray's origin lies against the sphere: the sign of C = |o − c|² − r² (docs/contract.md §10).
    Members are strings: ``SphereOrigin.ON_SURFACE == "on-surface"``. ``code`` is the value of
    ``intersect_sphere_batch``'s uint8 ``origin`` array (the C++ enum's)."""

    INSIDE = "inside"  # C < 0
    ON_SURFACE = "on-surface"  # C = 0: a root is exactly 0
    OUTSIDE = "outside"  # C > 0

    @property
    def code(self) -> int:
        return _SPHERE_ORIGIN_CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "SphereOrigin":
        return _SPHERE_ORIGINS_BY_CODE[int(code)]


class SphereRelation(_StrEnum):
    """How the ray's line meets the sphere: the sign of D = B² − A·C (docs/contract.md §10). Members are strings:
    ``SphereRelation.CROSS == "cross"``. ``code`` is the value of ``intersect_sphere_batch``'s uint8
    ``relation`` array (the C++ enum's)."""

    MISS = "miss"  # D < 0: no real root
    TANGENT = "tangent"  # D = 0: one root t0 = −B/A
    CROSS = "cross"  # D > 0: two roots t1 < t2

    @property
    def code(self) -> int:
        return _SPHERE_RELATION_CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "SphereRelation":
        return _SPHERE_RELATIONS_BY_CODE[int(code)]


_SPHERE_ORIGINS_BY_CODE = tuple(SphereOrigin)
_SPHERE_ORIGIN_CODES = {r: k for k, r in enumerate(_SPHERE_ORIGINS_BY_CODE)}
_SPHERE_RELATIONS_BY_CODE = tuple(SphereRelation)
_SPHERE_RELATION_CODES = {r: k for k, r in enumerate(_SPHERE_RELATIONS_BY_CODE)}


class SphereIntersection(NamedTuple):
    """The answer to one ray–sphere query (docs/contract.md §10): the origin's location, the line's relation, and
    the roots U ∓ √V each rounded to the nearest double, ties to even: ``t1 < t2`` for CROSS, ``t1 == t2`` the
    root t0 for TANGENT, both NaN for MISS. Roots may be negative (behind the origin)."""

    origin: SphereOrigin
    relation: SphereRelation
    t1: float
    t2: float


class SphereClassification(NamedTuple):
    """The origin's location and the line's relation alone (``relation(ray, sphere)``): nothing rounded."""

    origin: SphereOrigin
    relation: SphereRelation


class TracedSphereIntersection(NamedTuple):
    """``SphereIntersection`` plus the stages that decided the relation (the signs of C and D) and the roots
    (the latest stage any root needed; the relation's stage for MISS)."""

    origin: SphereOrigin
    relation: SphereRelation
    t1: float
    t2: float
    relation_stage: Stage
    rounding_stage: Stage


class ExactSphereIntersection(NamedTuple):
    """The exact roots of ``intersect_exact_rational(ray, sphere)``: U ∓ √V with the rationals U = −B/A and
    V = D/A² (V = 0 for TANGENT), where f = o − c, A = d·d, B = d·f, C = f·f − r², D = B² − A·C; ``u`` and ``v``
    are None for MISS."""

    origin: SphereOrigin
    relation: SphereRelation
    u: Optional[Fraction]
    v: Optional[Fraction]


class MeshHit(NamedTuple):
    """The nearest hit of a ray on a mesh (docs/contract.md §7): the index of the triangle, and its ``t``,
    ``location`` and ``barycentric`` coordinates as ``intersect(ray, triangle)`` gives them."""

    triangle: int
    t: float
    location: TriangleLocation
    barycentric: Barycentric


class ClosestPoint(NamedTuple):
    """The exact closest point of a mesh to a point (``closest_point``; docs/contract.md §11): the ``triangle``
    (its index; the smallest among triangles at the same exact distance), where on it the point lies
    (``feature``, ``corner``), the ``point`` with each coordinate correctly rounded, the exact
    ``squared_distance_exact`` (a ``Fraction``), ``squared_distance`` its rounding to nearest, and
    ``distance``, the square root of the exact squared distance rounded once to nearest."""

    triangle: int
    feature: ClosestFeature
    corner: int
    point: Vec3
    squared_distance: float
    distance: float
    squared_distance_exact: Fraction


class MeshHits(NamedTuple):
    """Every hit of a ray on a mesh within its interval (``all_hits``; docs/contract.md §8): ``hits``, each triangle
    once as a ``MeshHit``, in exact order (by exact t, ties by index), and ``crossings``, the signed count of the
    owned crossings (+1 through the front, −1 through the back): 0 for a ray from outside a closed, consistently
    oriented mesh to infinity."""

    hits: list
    crossings: int


class SpawnedOrigin(NamedTuple):
    """The origin of a secondary ray (``spawn``, ``spawn_to``; docs/contract.md §9): ``origin`` (values of the
    format asked for: binary32 values are exact floats) and ``steps``, k, the steps it took from the rounded hit
    point (an exact int; it can exceed 2**53)."""

    origin: Vec3
    steps: int


class IntersectionArrays(NamedTuple):
    """The answers of ``intersect_batch``, one row per query.

    ``relation`` (uint8): ``Relation.code`` of each answer, ``INVALID_RELATION_CODE`` (255) where the query
    is invalid; ``t`` (float64): NaN for PARALLEL, IN_PLANE and invalid rows; ``valid`` (bool); ``stats``:
    with ``stats=True``, how many rows each stage decided (``{"relation": {...}, "t": {...}}``).
    """

    relation: np.ndarray
    t: np.ndarray
    valid: np.ndarray
    stats: Optional[StageCounts] = None

    def relations(self) -> np.ndarray:
        """The relations as strings ("hit", "behind", "parallel", "in-plane"; "invalid")."""
        return _names(_RELATIONS_BY_CODE, self.relation)


class NearestHitArrays(NamedTuple):
    """The answers of ``nearest_hit_batch``, one row per ray: ``plane`` (int64), the nearest plane hit or
    -1 for a miss and for invalid rays; ``t`` (float64), NaN for a miss; ``valid`` (bool); ``stats``."""

    plane: np.ndarray
    t: np.ndarray
    valid: np.ndarray
    stats: Optional[StageCounts] = None


class SphereHit(NamedTuple):
    """The nearest sphere of a ``SphereSet`` a ray meets within its interval (docs/contract.md §8, §10): its index
    (an exact tie to the smaller) and its root t, the smallest in the interval, rounded to nearest."""

    sphere: int
    t: float


class SphereHitArrays(NamedTuple):
    """The answers of ``nearest_hit_batch`` on a ``SphereSet``, one row per ray: ``sphere`` (int64, -1 for a miss and
    for invalid rays), ``t`` (float64, NaN for a miss), ``valid`` (bool)."""

    sphere: np.ndarray
    t: np.ndarray
    valid: np.ndarray


class MeshHitArrays(NamedTuple):
    """The answers of ``nearest_hit_batch`` on a mesh, one row per ray: ``triangle`` (int64, -1 for a miss and
    for invalid rays), ``t`` (float64) and ``barycentric`` ((n, 3) float64), NaN for a miss; ``location``
    (uint8 ``TriangleLocation.code``: NONE for a miss, ``INVALID_RELATION_CODE`` for invalid rays); ``valid``."""

    triangle: np.ndarray
    t: np.ndarray
    location: np.ndarray
    barycentric: np.ndarray
    valid: np.ndarray

    def locations(self) -> np.ndarray:
        return _names(_TRIANGLE_LOCATIONS_BY_CODE, self.location)


class PointLocationArrays(NamedTuple):
    """The answers of ``inside_batch``, one row per point: ``location`` (uint8 ``PointLocation.code``,
    ``INVALID_RELATION_CODE`` (255) for a non-finite point) and ``valid`` (bool)."""

    location: np.ndarray
    valid: np.ndarray

    def locations(self) -> np.ndarray:
        """The locations as strings ("outside", "inside", "on-surface"; "invalid")."""
        return _names(_POINT_LOCATIONS_BY_CODE, self.location)


class ClosestPointArrays(NamedTuple):
    """The answers of ``closest_point_batch``, one row per point: ``triangle`` (int64, -1 for an invalid point),
    ``feature`` (uint8 ``ClosestFeature.code``, ``INVALID_RELATION_CODE`` for an invalid point), ``corner``
    (uint8), ``point`` ((n, 3) float64), ``squared_distance``, ``distance`` and, with ``signed=True``,
    ``signed_distance`` (float64; NaN for an invalid point), ``valid`` (bool)."""

    triangle: np.ndarray
    feature: np.ndarray
    corner: np.ndarray
    point: np.ndarray
    squared_distance: np.ndarray
    distance: np.ndarray
    signed_distance: Optional[np.ndarray]
    valid: np.ndarray

    def features(self) -> np.ndarray:
        """The features as strings ("vertex", "edge", "face"; "invalid")."""
        return _names(_CLOSEST_FEATURES_BY_CODE, self.feature)


class OcclusionArrays(NamedTuple):
    """The answers of ``occluded_batch`` and ``occluded_segment_batch``, one row per ray or segment: ``occluded``
    (bool: False for an invalid row) and ``valid`` (bool)."""

    occluded: np.ndarray
    valid: np.ndarray


class CrossingArrays(NamedTuple):
    """The answers of ``crossings_batch``, one row per ray: ``hits`` (int64, the triangles hit within the interval),
    ``crossings`` (int64, the signed count of owned crossings; 0 for an invalid row) and ``valid`` (bool)."""

    hits: np.ndarray
    crossings: np.ndarray
    valid: np.ndarray


class SpawnArrays(NamedTuple):
    """The answers of ``spawn_batch`` and ``spawn_to_batch``, one row per hit: ``origin`` ((n, 3) float64, NaN for an
    invalid row), ``steps`` (uint64: the steps from the rounded hit point) and ``valid`` (bool)."""

    origin: np.ndarray
    steps: np.ndarray
    valid: np.ndarray


class RelationArrays(NamedTuple):
    """The answers of ``relation_batch``, one row per query: ``relation`` (uint8 ``Relation.code``,
    ``INVALID_RELATION_CODE`` for invalid rows), ``valid`` (bool), ``stats`` (relation stages)."""

    relation: np.ndarray
    valid: np.ndarray
    stats: Optional[StageCounts] = None

    def relations(self) -> np.ndarray:
        """The relations as strings ("hit", "behind", "parallel", "in-plane"; "invalid")."""
        return _names(_RELATIONS_BY_CODE, self.relation)


def _names(members, codes: np.ndarray) -> np.ndarray:
    names = np.array([m.value for m in members] + ["invalid"], dtype=object)
    return names[np.minimum(codes, len(members))]


class TriangleIntersectionArrays(NamedTuple):
    """The answers of ``intersect_triangle_batch``, one row per query.

    ``relation`` (uint8): ``TriangleRelation.code``, ``INVALID_RELATION_CODE`` (255) where the query is
    invalid; ``location`` (uint8): ``TriangleLocation.code`` (255 for invalid rows); ``owned`` (bool);
    ``t`` (float64) and ``barycentric`` ((n, 3) float64, the coordinates of a, b, c): NaN where the line does
    not cross the plane, where not asked for, and for invalid rows; ``valid`` (bool).
    """

    relation: np.ndarray
    location: np.ndarray
    owned: np.ndarray
    t: np.ndarray
    barycentric: np.ndarray
    valid: np.ndarray

    def relations(self) -> np.ndarray:
        """The relations as strings ("hit", "behind", "miss", ...; "invalid")."""
        return _names(_TRIANGLE_RELATIONS_BY_CODE, self.relation)

    def locations(self) -> np.ndarray:
        """The locations as strings ("inside", "edge-ab", ..., "none"; "invalid")."""
        return _names(_TRIANGLE_LOCATIONS_BY_CODE, self.location)


class TriangleClassificationArrays(NamedTuple):
    """The answers of ``relation_triangle_batch``: ``relation``, ``location``, ``owned``, ``valid`` as in
    ``TriangleIntersectionArrays``."""

    relation: np.ndarray
    location: np.ndarray
    owned: np.ndarray
    valid: np.ndarray

    def relations(self) -> np.ndarray:
        return _names(_TRIANGLE_RELATIONS_BY_CODE, self.relation)

    def locations(self) -> np.ndarray:
        return _names(_TRIANGLE_LOCATIONS_BY_CODE, self.location)


class SphereIntersectionArrays(NamedTuple):
    """The answers of ``intersect_sphere_batch``, one row per query: ``origin`` (uint8 ``SphereOrigin.code``)
    and ``relation`` (uint8 ``SphereRelation.code``), ``INVALID_RELATION_CODE`` (255) where the query is
    invalid; ``t1``, ``t2`` (float64): the rounded roots as in ``SphereIntersection``, NaN for MISS and for
    invalid rows; ``valid`` (bool)."""

    origin: np.ndarray
    relation: np.ndarray
    t1: np.ndarray
    t2: np.ndarray
    valid: np.ndarray

    def origins(self) -> np.ndarray:
        """The origins' locations as strings ("inside", "on-surface", "outside"; "invalid")."""
        return _names(_SPHERE_ORIGINS_BY_CODE, self.origin)

    def relations(self) -> np.ndarray:
        """The relations as strings ("miss", "tangent", "cross"; "invalid")."""
        return _names(_SPHERE_RELATIONS_BY_CODE, self.relation)


class MeshFileError(ValueError):
    """A file that cannot be read as a mesh (``load_mesh``): a ``ValueError`` whose message names the file, the
    line or byte offset and the reason ("cube.obj:12: face with fewer than 3 vertices"), with each part as an
    attribute: ``file`` (the path as given, str), ``line`` (counted from 1, for text) or ``byte_offset``
    (counted from 0, for binary data), either None when the error is about the whole file, and ``reason``.
    Pickles with its attributes (so that it travels back from a Dask worker)."""

    def __init__(
        self,
        message: str,
        file: Optional[str] = None,
        line: Optional[int] = None,
        byte_offset: Optional[int] = None,
        reason: Optional[str] = None,
    ) -> None:
        super().__init__(message)
        self.file = file
        self.line = line
        self.byte_offset = byte_offset
        self.reason = message if reason is None else reason

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""

    def __reduce__(self):  # type: ignore[override]
        return (type(self), (str(self), self.file, self.line, self.byte_offset, self.reason))


class MeshFileNotFoundError(MeshFileError, FileNotFoundError):
    """``load_mesh`` on a path where there is no file: both a ``MeshFileError`` (with its attributes) and a
    ``FileNotFoundError`` (``errno`` ENOENT, ``filename`` the path), so that either ``except`` catches it."""

    def __init__(self, *args: object, **kwargs: object) -> None:  # MeshFileError's arguments
        super().__init__(*args, **kwargs)  # type: ignore[arg-type]
        self.errno = _errno.ENOENT
        self.strerror = os.strerror(_errno.ENOENT)
        self.filename = self.file


Vec3Like = Union[Vec3, Tuple[float, float, float], "np.ndarray", "list[float]"]
RayLike = Union[Ray, Tuple[Vec3Like, Vec3Like]]
PlaneLike = Union[Plane, Tuple[Vec3Like, Vec3Like]]
TriangleLike = Union[Triangle, Tuple[Vec3Like, Vec3Like, Vec3Like]]
SphereLike = Sphere  # a bare (center, radius) pair is not taken for a sphere where a plane is also possible
RuleLike = Union[TriangleRule, str]
