"""Hypothesis strategies for the queries where floating-point ray code goes wrong.

    from hypothesis import given
    from raykernel.testing.hypothesis import hard_queries
    from raykernel.testing import assert_matches_reference

    @given(hard_queries())
    def test_my_ray_plane(q):
        relation, t = my_ray_plane(q.ray, q.plane)
        assert_matches_reference(q.ray, q.plane, relation, t, max_t_ulps=4)

Ray–plane queries come from raykernel's C++ testing toolkit (testkit/plane_queries.hpp), the same
constructions its RapidCheck generators and fuzz decoder use: near-parallel and near-coplanar queries,
exact degeneracies, rounding ties and near ties, subnormal and huge components, t overflowing and
underflowing (``QUERY_KINDS``). The random 64-bit words a construction uses are read from one block of
bytes that Hypothesis draws (the fuzz decoder's layout: 8 bytes per word, little-endian), so a failing query
shrinks — toward zero words, the simplest query of its kind — and replays from Hypothesis's database. Plane pairs (``plane_pairs``) tie exactly or differ by less than an ulp of t, for
nearest-hit code.

Ray–triangle queries come in two families. ``triangle_queries`` (pure Python) aim rays exactly through edges
and vertices, one ulp beside them, and inside triangles, all on dyadic grids so that the aim is exact, at
moderate, subnormal or huge scales; each carries the location and the exact t it was built to have
(docs/contract.md §6). ``hard_triangle_queries`` come from the C++ toolkit (testkit/triangle_queries.hpp,
``HARD_TRIANGLE_QUERY_KINDS``): through and near vertices and edges, slivers, needles, degenerate, parallel and
coplanar triangles, origins on the triangle, rounding ties of t, wide exponents, tiny and huge scales.
``raykernel.testing.assert_triangle_matches_reference`` checks an answer against them, in ulps.

Ray–sphere queries (``hard_sphere_queries``) come from the C++ toolkit too (testkit/sphere_queries.hpp,
``SPHERE_QUERY_KINDS``): lines exactly tangent and an ulp or a few beside, origins exactly on the sphere and a
few ulps off, roots that are rounding ties, far-away spheres where |o − c|² − r² cancels, wide exponents, tiny
and huge directions, tiny and huge scales (docs/contract.md §10).

Meshes (``closed_meshes``, ``mesh_queries``, pure Python): closed, consistently oriented meshes with exact dyadic
vertices (a tetrahedron, an octahedron or a cube, stretched, moved, faces dented, bumped or spiked; moderate, tiny
or huge scales), and rays from outside aimed exactly at their vertices, edges and faces, for testing BVH,
nearest-hit, watertightness and inside code.

Every strategy has an array form for vectorized code: ``query_arrays``, ``triangle_query_arrays`` and
``hard_sphere_query_arrays`` give float64 arrays built from lists of such queries (the lists shrink too).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Iterable, NamedTuple, Optional, Sequence, Tuple

import numpy as np
from hypothesis import strategies as st
from hypothesis.strategies import SearchStrategy

from .. import _raykernel
from .._types import Plane, Ray, Sphere, Triangle, Vec3

# The strategies and the types they draw: what ``from raykernel.testing.hypothesis import *`` and ``dir()`` give (the
# imports above are not part of it).
__all__ = [
    "ClosedMesh",
    "HARD_TRIANGLE_QUERY_KINDS",
    "HardQuery",
    "MESH_SHAPES",
    "MESH_TARGETS",
    "MeshQuery",
    "PLANE_TIE_KINDS",
    "PlanePair",
    "QUERY_KINDS",
    "QueryArrays",
    "SPHERE_QUERY_KINDS",
    "SphereQuery",
    "SphereQueryArrays",
    "TRIANGLE_QUERY_KINDS",
    "TRIANGLE_SCALES",
    "TriangleQuery",
    "TriangleQueryArrays",
    "WORDS_PER_QUERY",
    "arbitrary_queries",
    "closed_meshes",
    "exact_degeneracies",
    "hard_queries",
    "hard_sphere_queries",
    "hard_sphere_query_arrays",
    "hard_triangle_queries",
    "hard_triangle_query_arrays",
    "huge_product_queries",
    "mesh_queries",
    "near_coplanar_queries",
    "near_parallel_queries",
    "origins_on_spheres",
    "plane_pairs",
    "queries",
    "query_arrays",
    "rays_near_triangle_edges",
    "rays_near_triangle_vertices",
    "rays_through_triangle_edges",
    "rays_through_triangle_vertices",
    "rounding_ties",
    "slivers",
    "sphere_tangencies",
    "subnormal_queries",
    "t_overflow_queries",
    "t_underflow_queries",
    "triangle_queries",
    "triangle_query_arrays",
    "words",
]


def __dir__() -> list:
    return sorted(__all__)

_tk = _raykernel.testkit

QUERY_KINDS: Tuple[str, ...] = tuple(_tk.QUERY_KINDS)
"""The kinds of hard ray–plane queries, as testkit names them: "random", "wide-exponents", "near-parallel",
"near-coplanar", "exact-parallel", "exact-in-plane", "origin-on-plane", "rounding-tie", "near-tie",
"subnormal", "huge-products", "t-overflow", "t-underflow"."""

PLANE_TIE_KINDS: Tuple[str, ...] = tuple(_tk.PLANE_TIE_KINDS)
"""Kinds of plane pairs: "coincident", "pivot" (exact ties), "parallel-offset", "pivot-offset" (< 1 ulp)."""

TRIANGLE_QUERY_KINDS: Tuple[str, ...] = (
    "through-edge", "through-vertex", "near-edge", "near-vertex", "inside", "degenerate")
"""Kinds of ``triangle_queries``: a ray exactly through a point of an edge (not a vertex), exactly through a
vertex, through an edge point or a vertex with one origin coordinate moved by one ulp, through an interior
point, and through a degenerate (collinear) triangle."""

TRIANGLE_SCALES: Tuple[str, ...] = ("moderate", "subnormal", "huge")
"""Scales of ``triangle_queries``: the construction's integers scaled by 2^-60..2^60; by 2^-1050..2^-1030
("subnormal": coordinates below 2^-980, many subnormal, and every product of two of them — the terms of den,
num and the π — underflows in binary64); or by 2^900..2^960 ("huge": every such product overflows). Direction
and points are scaled together at the extreme scales, so t stays moderate."""

HARD_TRIANGLE_QUERY_KINDS: Tuple[str, ...] = tuple(_tk.TRIANGLE_QUERY_KINDS)
"""The kinds of ``hard_triangle_queries``, as testkit names them: "random", "through-vertex", "through-edge",
"through-interior", "near-vertex", "near-edge", "origin-on-triangle", "sliver", "needle", "degenerate",
"parallel", "coplanar", "rounding-tie", "wide-exponents", "tiny", "huge"."""

SPHERE_QUERY_KINDS: Tuple[str, ...] = tuple(_tk.SPHERE_QUERY_KINDS)
"""The kinds of ``hard_sphere_queries``, as testkit names them: "random", "tangent", "near-tangent",
"on-surface", "near-surface", "rounding-tie", "far-cancel", "wide-exponents", "tiny-direction",
"huge-direction", "tiny", "huge", "subnormal-offset"."""

WORDS_PER_QUERY = 32
"""Random words drawn for one construction: more than any kind uses (the most is about 24)."""

words = st.binary(min_size=8 * WORDS_PER_QUERY, max_size=8 * WORDS_PER_QUERY)
"""The random words of one testkit construction, as bytes (shrinking makes them zero, word by word). One
draw per query instead of one per word: Hypothesis generates and shrinks it several times faster."""


def _check_kinds(kinds: Optional[Iterable[str]], known: Sequence[str], what: str) -> Tuple[str, ...]:
    chosen = tuple(known if kinds is None else kinds)
    unknown = [k for k in chosen if k not in known]
    if unknown or not chosen:
        raise ValueError(f"{what}: unknown or no kinds {unknown or chosen!r}; known: {', '.join(known)}")
    return chosen


# Ray–plane ---------------------------------------------------------------------------------------------------


class HardQuery(NamedTuple):
    """A ray–plane query and the kind of construction it came from."""

    kind: str
    ray: Ray
    plane: Plane


@st.composite
def _query_of_kind(draw, kind: str) -> HardQuery:
    ray, plane = _tk.make_query(kind, draw(words))
    return HardQuery(kind, ray, plane)


def queries(kind: str) -> SearchStrategy[HardQuery]:
    """Queries of one kind (one of QUERY_KINDS). Always valid input."""
    _check_kinds([kind], QUERY_KINDS, "queries")
    return _query_of_kind(kind)


def hard_queries(kinds: Optional[Iterable[str]] = None) -> SearchStrategy[HardQuery]:
    """Queries of a kind drawn from ``kinds`` (default: all of QUERY_KINDS). Always valid input."""
    chosen = _check_kinds(kinds, QUERY_KINDS, "hard_queries")
    return st.sampled_from(chosen).flatmap(_query_of_kind)


def near_parallel_queries() -> SearchStrategy[HardQuery]:
    """The direction within a few ulps of the plane: d·n tiny, its sign decided by the last bits."""
    return queries("near-parallel")


def near_coplanar_queries() -> SearchStrategy[HardQuery]:
    """The origin within a few ulps of the plane: (p − o)·n tiny."""
    return queries("near-coplanar")


def exact_degeneracies() -> SearchStrategy[HardQuery]:
    """d·n = 0 exactly (parallel, in-plane) or (p − o)·n = 0 exactly (t = 0), with unround coordinates."""
    return hard_queries(["exact-parallel", "exact-in-plane", "origin-on-plane"])


def rounding_ties() -> SearchStrategy[HardQuery]:
    """t exactly halfway between two doubles, or within 2^-20..2^-60 ulps of halfway."""
    return hard_queries(["rounding-tie", "near-tie"])


def subnormal_queries() -> SearchStrategy[HardQuery]:
    """Components between 2^-1074 and 2^-400: the products underflow in binary64, the exact values do not."""
    return queries("subnormal")


def huge_product_queries() -> SearchStrategy[HardQuery]:
    """Components up to 2^1023: products and differences overflow binary64."""
    return queries("huge-products")


def t_overflow_queries() -> SearchStrategy[HardQuery]:
    """|t| near or beyond the largest double."""
    return queries("t-overflow")


def t_underflow_queries() -> SearchStrategy[HardQuery]:
    """|t| in or below the subnormal range."""
    return queries("t-underflow")


def arbitrary_queries(*, allow_invalid: bool = False) -> SearchStrategy[HardQuery]:
    """Queries with each component any double Hypothesis likes (subnormals, ±0, huge values); with
    ``allow_invalid``, also NaN, ±inf and zero vectors, for testing how code rejects them."""
    component = st.floats(allow_nan=allow_invalid, allow_infinity=allow_invalid)
    vector = st.builds(Vec3, component, component, component)
    query = st.builds(lambda o, d, p, n: HardQuery("arbitrary", Ray(o, d), Plane(p, n)), vector, vector, vector, vector)
    if allow_invalid:
        return query
    return query.filter(lambda q: _raykernel.validate(q.ray, q.plane) is None)


class PlanePair(NamedTuple):
    """One ray and two planes it hits, whose exact t tie (``order`` 0) or differ by less than an ulp of t
    (``order`` the sign of t1 − t0)."""

    kind: str
    ray: Ray
    planes: Tuple[Plane, Plane]
    order: int

    @property
    def nearest(self) -> int:
        """The index docs/contract.md §4 answers: the smaller exact t, ties to the smaller index."""
        return 1 if self.order < 0 else 0


@st.composite
def _plane_pair(draw, kind: Optional[str]) -> PlanePair:
    k, ray, planes, order = _tk.make_plane_pair(kind, draw(words))
    return PlanePair(k, ray, tuple(planes), order)


def plane_pairs(kind: Optional[str] = None) -> SearchStrategy[PlanePair]:
    """Near ties between two planes along one ray (testkit/plane_pairs.hpp), of ``kind`` (one of
    PLANE_TIE_KINDS) or of a drawn kind."""
    if kind is not None:
        _check_kinds([kind], PLANE_TIE_KINDS, "plane_pairs")
    return _plane_pair(kind)


def _exact_repr(name: str, fields: Sequence[Tuple[str, np.ndarray]]) -> str:
    with np.printoptions(floatmode="unique", threshold=10**9, linewidth=10**9):
        inner = ", ".join(f"{k}=np.{np.array_repr(v)}" for k, v in fields)
    return f"{name}({inner})"


class QueryArrays(NamedTuple):
    """n ray–plane queries as (n, 3) float64 arrays, with each query's kind. Its repr is exact (shortest
    round-trip decimals), so a printed counterexample can be pasted back."""

    origins: np.ndarray
    directions: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    kinds: Tuple[str, ...]

    def __repr__(self) -> str:
        fields = [(k, getattr(self, k)) for k in ("origins", "directions", "points", "normals")]
        return _exact_repr("QueryArrays", fields)[:-1] + f", kinds={self.kinds!r})"

    def query(self, i: int) -> Tuple[Ray, Plane]:
        v = lambda a: Vec3(*map(float, a[i]))  # noqa: E731
        return Ray(v(self.origins), v(self.directions)), Plane(v(self.points), v(self.normals))


def _to_query_arrays(qs: Sequence[HardQuery]) -> QueryArrays:
    rows = lambda f: np.array([f(q) for q in qs], dtype=np.float64).reshape(-1, 3)  # noqa: E731
    return QueryArrays(
        rows(lambda q: q.ray.origin),
        rows(lambda q: q.ray.direction),
        rows(lambda q: q.plane.point),
        rows(lambda q: q.plane.normal),
        tuple(q.kind for q in qs),
    )


def query_arrays(
    kinds: Optional[Iterable[str]] = None, *, min_size: int = 1, max_size: int = 16
) -> SearchStrategy[QueryArrays]:
    """Lists of ``hard_queries(kinds)`` as arrays, for vectorized code. (Each query takes 256 bytes of
    Hypothesis's 8 KiB buffer per test case: keep ``max_size`` below about 24.)"""
    return st.lists(hard_queries(kinds), min_size=min_size, max_size=max_size).map(_to_query_arrays)


# Ray–triangle ------------------------------------------------------------------------------------------------
#
# Exactness by construction: the vertices are integers of at most 21 bits, the aimed-at point e has a
# denominator 2^m with m ≤ 20 (so 2^20·e is an integer of at most 42 bits), the direction is an integer vector
# of at most 11 bits, and the origin o = e ∓ 2^j·d (|j| ≤ 8) has 2^20·o an integer of at most 43 bits: every
# coordinate is a double exactly, and the ray meets the aimed-at point at t = ±2^j exactly. Then the points
# are scaled by 2^p and the direction by 2^r (t becomes ±2^(j+p−r)), and the axes permuted and flipped
# (which multiplies den and every π by the same ±1, so the location is unchanged).

_I3 = Tuple[int, int, int]


class TriangleQuery(NamedTuple):
    """A ray and a triangle, with what the construction promises: the location (docs/contract.md §6:
    "edge-ab", "vertex-c", "inside", ...) and the exact t at which the ray meets it (None where nothing is
    promised: "near-edge" queries, degenerate triangles)."""

    kind: str
    ray: Ray
    triangle: Triangle
    location: Optional[str]
    exact_t: Optional[Fraction]


def _cross(u: _I3, v: _I3) -> _I3:
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def _dot(u: _I3, v: _I3) -> int:
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


_vertex_coordinate = st.integers(-(2**20), 2**20)
_direction_coordinate = st.integers(-(2**10), 2**10)


def _int3(coordinate: SearchStrategy[int]) -> SearchStrategy[_I3]:
    return st.tuples(coordinate, coordinate, coordinate)


@st.composite
def _triangle_query(draw, kind: str, scales: Sequence[str] = ("moderate",)) -> TriangleQuery:
    a = draw(_int3(_vertex_coordinate))
    u = draw(_int3(_vertex_coordinate))
    u = u if u != (0, 0, 0) else (1, 0, 0)
    m = draw(st.integers(1, 20))  # the aimed-at point is on the grid 2^-m
    scale = 2**m
    if kind == "degenerate":  # c on the line through a and b, at a + (k/2^m)(b − a): collinear, exactly
        k = draw(st.integers(-(2**m), 2**m))
        b = tuple(a[i] + u[i] for i in range(3))
        c_num = tuple(a[i] * scale + k * u[i] for i in range(3))
        vertices = [tuple(Fraction(x) for x in a), tuple(Fraction(x) for x in b),
                    tuple(Fraction(x, scale) for x in c_num)]
        normal = None
    else:
        v = draw(_int3(_vertex_coordinate))
        if _cross(u, v) == (0, 0, 0):  # keep the triangle proper: a vector orthogonal to u is never parallel to it
            v = _cross(u, (1, 0, 0)) if _cross(u, (1, 0, 0)) != (0, 0, 0) else _cross(u, (0, 1, 0))
        b = tuple(a[i] + u[i] for i in range(3))
        c = tuple(a[i] + v[i] for i in range(3))
        vertices = [tuple(Fraction(x) for x in p) for p in (a, b, c)]
        normal = _cross(u, v)

    names = "abc"
    location: Optional[str]
    if kind in ("through-edge", "near-edge", "degenerate"):
        # (a degenerate triangle's c has the denominator 2^m already: aim at its edge ab, whose ends are integers)
        first = draw(st.integers(0, 2)) if kind != "degenerate" else 0
        p, q = vertices[first], vertices[(first + 1) % 3]
        k = draw(st.integers(1, scale - 1)) if scale > 1 else 1
        e = tuple(p[i] + Fraction(k, scale) * (q[i] - p[i]) for i in range(3))
        location = f"edge-{names[first]}{names[(first + 1) % 3]}" if kind == "through-edge" else None
    elif kind in ("through-vertex", "near-vertex"):
        which = draw(st.integers(0, 2))
        e = vertices[which]
        location = f"vertex-{names[which]}" if kind == "through-vertex" else None
    elif kind == "inside":  # barycentric weights k1/2^m, k2/2^m and the rest, all positive
        m = max(m, 2)
        scale = 2**m
        k1 = draw(st.integers(1, scale - 2))
        k2 = draw(st.integers(1, scale - 1 - k1))
        e = tuple(vertices[0][i] + Fraction(k1, scale) * (vertices[1][i] - vertices[0][i])
                  + Fraction(k2, scale) * (vertices[2][i] - vertices[0][i]) for i in range(3))
        location = "inside"
    else:  # pragma: no cover - guarded by _check_kinds
        raise ValueError(kind)

    d = draw(_int3(_direction_coordinate))
    if d == (0, 0, 0):
        d = (0, 0, 1)
    if normal is not None and _dot(d, normal) == 0:  # not parallel to the plane: d + e_k with N_k ≠ 0 has d·N = N_k
        axis = next(i for i in range(3) if normal[i] != 0)
        d = tuple(d[i] + (1 if i == axis else 0) for i in range(3))
    j = draw(st.integers(-8, 8))
    behind = draw(st.booleans())
    step = Fraction(2) ** j * (-1 if behind else 1)  # o + step·d = e
    o = tuple(e[i] - step * d[i] for i in range(3))
    exact_t = step

    # 2^20·o, 2^20·e and the vertices are integers of at most 43 bits, d of 11: the scales keep every coordinate a
    # double (the least significant bit at 2^(p_scale − 20) ≥ 2^-1074, the largest below 2^(p_scale + 23)).
    scale_kind = draw(st.sampled_from(tuple(scales)))
    if scale_kind == "moderate":
        p_scale, r_scale = draw(st.integers(-60, 60)), draw(st.integers(-30, 30))
    else:
        p_scale = draw(st.integers(-1050, -1030) if scale_kind == "subnormal" else st.integers(900, 960))
        r_scale = p_scale + draw(st.integers(-20, 20))
    points = [tuple(x * Fraction(2) ** p_scale for x in pt) for pt in (o, *vertices)]
    direction = tuple(Fraction(x) * Fraction(2) ** r_scale for x in d)
    exact_t = exact_t * Fraction(2) ** (p_scale - r_scale)

    permutation = draw(st.permutations([0, 1, 2]))
    flips = draw(st.tuples(st.booleans(), st.booleans(), st.booleans()))

    def place(v) -> Vec3:
        out = []
        for axis in range(3):
            x = v[permutation[axis]]
            x = -x if flips[axis] else x
            f = float(x)
            assert Fraction(f) == x, "construction left the doubles"  # the exactness argument above
            out.append(f)
        return Vec3(*out)

    o_v, a_v, b_v, c_v = (place(pt) for pt in points)
    d_v = place(direction)
    ray = Ray(o_v, d_v)
    if kind in ("near-edge", "near-vertex"):  # one coordinate of the origin one ulp off, either side
        axis, up = draw(st.integers(0, 2)), draw(st.booleans())
        moved = list(o_v)
        moved[axis] = float(np.nextafter(moved[axis], np.inf if up else -np.inf))
        ray = Ray(Vec3(*moved), d_v)
        exact_t = None
    if kind == "degenerate":
        exact_t = None
    return TriangleQuery(kind, ray, Triangle(a_v, b_v, c_v), location, exact_t)


def triangle_queries(
    kinds: Optional[Iterable[str]] = None, *, scales: Optional[Iterable[str]] = None
) -> SearchStrategy[TriangleQuery]:
    """Ray–triangle queries of a kind drawn from ``kinds`` (default: all of TRIANGLE_QUERY_KINDS) at a scale
    drawn from ``scales`` (default: all of TRIANGLE_SCALES). Always valid input."""
    chosen = _check_kinds(kinds, TRIANGLE_QUERY_KINDS, "triangle_queries")
    chosen_scales = _check_kinds(scales, TRIANGLE_SCALES, "triangle_queries scales")
    return st.sampled_from(chosen).flatmap(lambda kind: _triangle_query(kind, chosen_scales))


def rays_through_triangle_edges() -> SearchStrategy[TriangleQuery]:
    """A ray exactly through a point of an edge (not a vertex): location "edge-ab", "edge-bc" or "edge-ca"."""
    return _triangle_query("through-edge")


def rays_through_triangle_vertices() -> SearchStrategy[TriangleQuery]:
    """A ray exactly through a vertex: location "vertex-a", "vertex-b" or "vertex-c"."""
    return _triangle_query("through-vertex")


def rays_near_triangle_vertices() -> SearchStrategy[TriangleQuery]:
    """A ray through a vertex with one coordinate of the origin moved by one ulp."""
    return _triangle_query("near-vertex")


def rays_near_triangle_edges() -> SearchStrategy[TriangleQuery]:
    """A ray through an edge point with one coordinate of the origin moved by one ulp: inside, outside or
    still on the edge, decided by the last bit."""
    return _triangle_query("near-edge")


class TriangleQueryArrays(NamedTuple):
    """n ray–triangle queries as (n, 3) float64 arrays (exact repr), with each query's construction."""

    origins: np.ndarray
    directions: np.ndarray
    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    queries: Tuple[TriangleQuery, ...]

    def __repr__(self) -> str:
        fields = [(k, getattr(self, k)) for k in ("origins", "directions", "a", "b", "c")]
        kinds = tuple(q.kind for q in self.queries)
        return _exact_repr("TriangleQueryArrays", fields)[:-1] + f", kinds={kinds!r})"


def _to_triangle_arrays(qs: Sequence[TriangleQuery]) -> TriangleQueryArrays:
    rows = lambda f: np.array([f(q) for q in qs], dtype=np.float64).reshape(-1, 3)  # noqa: E731
    return TriangleQueryArrays(
        rows(lambda q: q.ray.origin),
        rows(lambda q: q.ray.direction),
        rows(lambda q: q.triangle.a),
        rows(lambda q: q.triangle.b),
        rows(lambda q: q.triangle.c),
        tuple(qs),
    )


def triangle_query_arrays(
    kinds: Optional[Iterable[str]] = None,
    *,
    scales: Optional[Iterable[str]] = None,
    min_size: int = 1,
    max_size: int = 16,
) -> SearchStrategy[TriangleQueryArrays]:
    """Lists of ``triangle_queries(kinds, scales=scales)`` as arrays, for vectorized triangle code."""
    return st.lists(triangle_queries(kinds, scales=scales), min_size=min_size, max_size=max_size).map(
        _to_triangle_arrays)


@st.composite
def _hard_triangle_query(draw, kind: str) -> TriangleQuery:
    ray, triangle = _tk.make_triangle_query(kind, draw(words))
    return TriangleQuery(kind, ray, triangle, None, None)


def hard_triangle_queries(kinds: Optional[Iterable[str]] = None) -> SearchStrategy[TriangleQuery]:
    """Ray–triangle queries from the C++ toolkit's constructions, of a kind drawn from ``kinds`` (default: all
    of HARD_TRIANGLE_QUERY_KINDS), their random words drawn as bytes (so they shrink toward the simplest query
    of the kind). Always valid input; nothing promised (``location`` and ``exact_t`` are None): check answers
    with ``raykernel.testing.assert_triangle_matches_reference``."""
    chosen = _check_kinds(kinds, HARD_TRIANGLE_QUERY_KINDS, "hard_triangle_queries")
    return st.sampled_from(chosen).flatmap(_hard_triangle_query)


def slivers() -> SearchStrategy[TriangleQuery]:
    """Sliver and needle triangles (a vertex within a few ulps of the opposite edge; two vertices a few ulps
    apart), from the C++ toolkit."""
    return hard_triangle_queries(["sliver", "needle"])


def hard_triangle_query_arrays(
    kinds: Optional[Iterable[str]] = None, *, min_size: int = 1, max_size: int = 16
) -> SearchStrategy[TriangleQueryArrays]:
    """Lists of ``hard_triangle_queries(kinds)`` as arrays."""
    return st.lists(hard_triangle_queries(kinds), min_size=min_size, max_size=max_size).map(_to_triangle_arrays)


# Ray–sphere --------------------------------------------------------------------------------------------------


class SphereQuery(NamedTuple):
    """A ray–sphere query and the kind of construction it came from."""

    kind: str
    ray: Ray
    sphere: Sphere


@st.composite
def _hard_sphere_query(draw, kind: str) -> SphereQuery:
    ray, sphere = _tk.make_sphere_query(kind, draw(words))
    return SphereQuery(kind, ray, sphere)


def hard_sphere_queries(kinds: Optional[Iterable[str]] = None) -> SearchStrategy[SphereQuery]:
    """Ray–sphere queries from the C++ toolkit's constructions, of a kind drawn from ``kinds`` (default: all of
    SPHERE_QUERY_KINDS), their random words drawn as bytes (so they shrink toward the simplest query of the
    kind). Always valid input; check answers against ``raykernel.intersect`` (or ``raykernel.testing.exact``)."""
    chosen = _check_kinds(kinds, SPHERE_QUERY_KINDS, "hard_sphere_queries")
    return st.sampled_from(chosen).flatmap(_hard_sphere_query)


def sphere_tangencies() -> SearchStrategy[SphereQuery]:
    """Lines exactly tangent to the sphere (D = 0), or with the radius or a component of o or d moved by 1–4
    ulps: tangent, a miss or two roots an ulp apart, decided by the last bits."""
    return hard_sphere_queries(["tangent", "near-tangent"])


def origins_on_spheres() -> SearchStrategy[SphereQuery]:
    """Origins exactly on the sphere (C = 0: a root exactly 0), or with the radius or a component of o moved by
    1–4 ulps: a root near 0 whose sign is decided by the last bits."""
    return hard_sphere_queries(["on-surface", "near-surface"])


class SphereQueryArrays(NamedTuple):
    """n ray–sphere queries as float64 arrays ((n, 3), and (n,) radii; exact repr), with each query."""

    origins: np.ndarray
    directions: np.ndarray
    centers: np.ndarray
    radii: np.ndarray
    queries: Tuple[SphereQuery, ...]

    def __repr__(self) -> str:
        fields = [(k, getattr(self, k)) for k in ("origins", "directions", "centers", "radii")]
        kinds = tuple(q.kind for q in self.queries)
        return _exact_repr("SphereQueryArrays", fields)[:-1] + f", kinds={kinds!r})"


def _to_sphere_arrays(qs: Sequence[SphereQuery]) -> SphereQueryArrays:
    rows = lambda f: np.array([f(q) for q in qs], dtype=np.float64).reshape(-1, 3)  # noqa: E731
    return SphereQueryArrays(
        rows(lambda q: q.ray.origin),
        rows(lambda q: q.ray.direction),
        rows(lambda q: q.sphere.center),
        np.array([q.sphere.radius for q in qs], dtype=np.float64),
        tuple(qs),
    )


def hard_sphere_query_arrays(
    kinds: Optional[Iterable[str]] = None, *, min_size: int = 1, max_size: int = 16
) -> SearchStrategy[SphereQueryArrays]:
    """Lists of ``hard_sphere_queries(kinds)`` as arrays, for vectorized sphere code."""
    return st.lists(hard_sphere_queries(kinds), min_size=min_size, max_size=max_size).map(_to_sphere_arrays)


# Meshes ------------------------------------------------------------------------------------------------------

MESH_SHAPES: Tuple[str, ...] = ("tetrahedron", "octahedron", "cube")
"""The base shapes of ``closed_meshes``: closed, consistently oriented (outward normals), every edge shared by
exactly two triangles in opposite directions."""

MESH_TARGETS: Tuple[str, ...] = ("vertex", "edge", "face")
"""What ``mesh_queries`` aims rays at exactly: a vertex, a point of an edge (dyadic, not a vertex), or a point
inside a face (barycentric (1/2, 1/4, 1/4))."""

_SHAPES = {
    "tetrahedron": ([(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)], [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)]),
    "octahedron": ([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)],
                   [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]),
    "cube": ([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)],
             [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6), (0, 2, 6),
              (0, 6, 4), (1, 5, 7), (1, 7, 3)]),
}
_MESH_SCALES = {"moderate": (0, 0), "tiny": (-900, -860), "huge": (860, 900)}


class ClosedMesh(NamedTuple):
    """A closed, consistently oriented triangle mesh with dyadic vertices: ``vertices`` (n, 3) float64,
    ``triangles`` (m, 3) int64; ``shape`` says what it was built from. ``Mesh(*closed_mesh[:2])`` makes one."""

    vertices: np.ndarray
    triangles: np.ndarray
    shape: str


class MeshQuery(NamedTuple):
    """Rays aimed exactly at features of a closed mesh: ray k starts at ``origins[k]``, outside the mesh's
    bounding box, with ``directions[k] = targets[k] - origins[k]`` exactly, so that ``origins[k] + directions[k]``
    is ``targets[k]``, a point of the mesh's surface (``aimed_at[k]``: "vertex 3", "edge 0-2", "face 5"), at t = 1.
    Every ray therefore has a nearest hit at an exact t <= 1 under the closed rule (edges and vertices included) —
    a BVH that loses one is wrong. Under the owned rule a ray that only grazes the surface at a vertex or an edge
    (touching it without crossing) may pass, and one that crosses there is hit by exactly one triangle."""

    mesh: ClosedMesh
    origins: np.ndarray
    directions: np.ndarray
    targets: np.ndarray
    aimed_at: Tuple[str, ...]


@st.composite
def _closed_mesh(draw, shapes: Sequence[str], scales: Sequence[str]) -> ClosedMesh:
    shape = draw(st.sampled_from(list(shapes)))
    base_vertices, base_triangles = _SHAPES[shape]
    # Each axis stretched by an odd factor and the whole moved on the grid 2^-4; then, optionally, faces replaced
    # by three triangles around an apex (a+b+c)·q for q = 1/4 (a dent), 3/8 (a bump) or 1/2 (a spike): the
    # surface stays closed and consistently oriented whatever the apex.
    stretch = draw(st.tuples(*[st.integers(1, 15).map(lambda k: 2 * k + 1)] * 3))
    shift = draw(st.tuples(*[st.integers(-64, 64)] * 3))
    vertices = [tuple(Fraction(stretch[i] * v[i]) + Fraction(shift[i], 16) for i in range(3)) for v in base_vertices]
    triangles = list(base_triangles)
    apex_kinds = draw(st.lists(st.sampled_from([None, Fraction(1, 4), Fraction(3, 8), Fraction(1, 2)]),
                               min_size=len(triangles), max_size=len(triangles)))
    centre = tuple(Fraction(shift[i], 16) for i in range(3))
    refined = []
    for (a, b, c), q in zip(triangles, apex_kinds):
        if q is None:
            refined.append((a, b, c))
            continue
        apex = tuple(centre[i] + (vertices[a][i] + vertices[b][i] + vertices[c][i] - 3 * centre[i]) * q for i in range(3))
        vertices.append(apex)
        p = len(vertices) - 1
        refined += [(a, b, p), (b, c, p), (c, a, p)]
    low, high = _MESH_SCALES[draw(st.sampled_from(list(scales)))]
    exponent = draw(st.integers(low, high))
    scale = Fraction(2) ** exponent
    as_array = np.array([[float(x * scale) for x in v] for v in vertices], dtype=np.float64)
    return ClosedMesh(as_array, np.array(refined, dtype=np.int64), shape)


def closed_meshes(shapes: Optional[Iterable[str]] = None, *, scales: Sequence[str] = ("moderate",)
                  ) -> SearchStrategy[ClosedMesh]:
    """Closed, consistently oriented meshes with exact dyadic vertices (``MESH_SHAPES``: each axis stretched, the
    whole moved, faces optionally dented, bumped or spiked around an apex), at ``scales`` "moderate" (coordinates
    up to about 2^6), "tiny" (times 2^-900..2^-860) or "huge" (times 2^860..2^900): for testing BVH, nearest-hit
    and inside code. They shrink toward the plain shape."""
    chosen = _check_kinds(shapes, MESH_SHAPES, "closed_meshes")
    unknown = [s for s in scales if s not in _MESH_SCALES]
    if unknown or not scales:
        raise ValueError(f"closed_meshes: unknown or no scales {unknown or scales!r}; known: {', '.join(_MESH_SCALES)}")
    return _closed_mesh(chosen, tuple(scales))


@st.composite
def _mesh_query(draw, meshes: SearchStrategy[ClosedMesh], targets: Sequence[str], max_rays: int) -> MeshQuery:
    mesh = draw(meshes)
    v = [tuple(Fraction(x) for x in row) for row in mesh.vertices]
    extent = max(max(abs(x) for x in row) for row in v)
    n = draw(st.integers(1, max_rays))
    origins, directions, points, names = [], [], [], []
    for _ in range(n):
        kind = draw(st.sampled_from(list(targets)))
        k = draw(st.integers(0, len(mesh.triangles) - 1))
        a, b, c = (int(i) for i in mesh.triangles[k])
        if kind == "vertex":
            target, name = v[a], f"vertex {a}"
        elif kind == "edge":
            j = draw(st.integers(1, 15))  # a + (b - a)·j/16: a dyadic point of the edge, not a vertex
            target = tuple(v[a][i] + (v[b][i] - v[a][i]) * Fraction(j, 16) for i in range(3))
            name = f"edge {a}-{b}"
        else:
            target = tuple((2 * v[a][i] + v[b][i] + v[c][i]) / 4 for i in range(3))
            name = f"face {k}"
        # An origin outside the bounding box (coordinates 3 to 4 times the extent, on a grid of its 64ths), so that
        # target - origin is exact in binary64.
        sign = draw(st.tuples(*[st.sampled_from([-1, 1])] * 3))
        grid = draw(st.tuples(*[st.integers(192, 256)] * 3))
        origin = tuple(sign[i] * extent * Fraction(grid[i], 64) for i in range(3))
        direction = tuple(target[i] - origin[i] for i in range(3))
        as_float = [float(x) for x in origin + direction + target]
        # Exactness of the construction: every value is a double, and origin + direction is the target.
        assert all(Fraction(f) == x for f, x in zip(as_float, origin + direction + target))
        origins.append(as_float[:3])
        directions.append(as_float[3:6])
        points.append(as_float[6:])
        names.append(name)
    to_array = lambda rows: np.array(rows, dtype=np.float64).reshape(-1, 3)  # noqa: E731
    return MeshQuery(mesh, to_array(origins), to_array(directions), to_array(points), tuple(names))


def mesh_queries(meshes: Optional[SearchStrategy[ClosedMesh]] = None, *, targets: Optional[Iterable[str]] = None,
                 max_rays: int = 16) -> SearchStrategy[MeshQuery]:
    """A closed mesh (``closed_meshes()`` by default) and up to ``max_rays`` rays from outside its bounding box
    aimed exactly at its vertices, edges and faces (``MESH_TARGETS``): each meets the surface at t = 1 exactly, so
    under the closed rule a nearest hit must exist with t <= 1, and the origin is outside. The rays through vertices
    and edges are where watertightness fails: ``raykernel.nearest_hit_batch(q.origins, q.directions, Mesh(...),
    rule=...)`` is the reference."""
    chosen = _check_kinds(targets, MESH_TARGETS, "mesh_queries")
    return _mesh_query(meshes if meshes is not None else closed_meshes(), chosen, max_rays)
