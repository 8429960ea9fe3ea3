"""raykernel: exact ray–plane intersection for binary64 inputs, from Python.

Every answer is exact for the doubles given (docs/contract.md §1): the relation comes from the exact signs
of ``den = d·n`` and ``num = (p − o)·n``, and ``t`` is the exact ``num/den`` rounded to the nearest double,
ties to even. The C++ kernel does the work; this package converts values and arrays.

    >>> import raykernel as rk
    >>> rk.intersect(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0)))
    Intersection(relation=<Relation.HIT: 'hit'>, t=0.1)
    >>> rk.intersect_exact_rational(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0))).exact_t
    Fraction(1, 10)

Scalar functions take a ray as ``(origin, direction)`` and a plane as ``(point, normal)``, vectors as any
sequence of three numbers: ``intersect`` (certified), ``intersect_exact`` (rational reference),
``intersect_exact_rational`` (with num, den and t as Fractions), ``intersect_naive`` (the textbook formula,
no guarantee), ``intersect_traced``, ``validate``, ``nearest_hit`` / ``nearest_hit_exact`` /
``nearest_hit_naive`` over a ``PlaneSet`` or a list of planes, ``round_rational_to_double``.

Vectorized functions take (n, 3) float64 arrays and loop in C++ with the GIL released:
``intersect_batch(origins, directions, points, normals)`` and ``nearest_hit_batch(origins, directions,
planes)``. Invalid input raises ``ValueError`` (``raykernel.InvalidInput``) naming the field, and for arrays
the row: "query 17: ray direction is the zero vector".

``raykernel.testing`` checks other code against raykernel (ulps, reports); ``raykernel.testing.hypothesis``
has Hypothesis strategies for the hard queries.
"""

from __future__ import annotations

from ._types import (
    ExactIntersection,
    Intersection,
    IntersectionArrays,
    NearestHit,
    NearestHitArrays,
    Plane,
    Ray,
    Relation,
    Stage,
    TracedIntersection,
    Triangle,
    Vec3,
)
from ._raykernel import (  # noqa: E402  (the extension builds its results from ._types)
    INVALID_RELATION_CODE,
    InvalidInput,
    PlaneSet,
    floating_point_environment_is_default,
    intersect,
    intersect_batch,
    intersect_exact,
    intersect_exact_rational,
    intersect_naive,
    intersect_traced,
    nearest_hit,
    nearest_hit_batch,
    nearest_hit_exact,
    nearest_hit_naive,
    round_rational_to_double,
    validate,
    version,
)

__version__ = version()

__all__ = [
    "ExactIntersection",
    "INVALID_RELATION_CODE",
    "Intersection",
    "IntersectionArrays",
    "InvalidInput",
    "NearestHit",
    "NearestHitArrays",
    "Plane",
    "PlaneSet",
    "Ray",
    "Relation",
    "Stage",
    "TracedIntersection",
    "Triangle",
    "Vec3",
    "floating_point_environment_is_default",
    "intersect",
    "intersect_batch",
    "intersect_exact",
    "intersect_exact_rational",
    "intersect_naive",
    "intersect_traced",
    "nearest_hit",
    "nearest_hit_batch",
    "nearest_hit_exact",
    "nearest_hit_naive",
    "round_rational_to_double",
    "validate",
    "version",
]
