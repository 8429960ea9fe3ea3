"""The value types of raykernel's Python API: plain NamedTuples and str-valued enums.

Inputs need not be these types: every function takes a vector as any sequence of three numbers, a ray as
any ``(origin, direction)`` pair and a plane as any ``(point, normal)`` pair. Results are these types, so
they unpack like tuples, compare by value, and print readably. The compiled extension builds its results
from the classes defined here.
"""

from __future__ import annotations

import enum
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
        names = np.array([r.value for r in _RELATIONS_BY_CODE] + ["invalid"], dtype=object)
        return names[np.minimum(self.relation, 4)]


class NearestHitArrays(NamedTuple):
    """The answers of ``nearest_hit_batch``, one row per ray: ``plane`` (int64), the nearest plane hit or
    -1 for a miss and for invalid rays; ``t`` (float64), NaN for a miss; ``valid`` (bool); ``stats``."""

    plane: np.ndarray
    t: np.ndarray
    valid: np.ndarray
    stats: Optional[StageCounts] = None


Vec3Like = Union[Vec3, Tuple[float, float, float], "np.ndarray", "list[float]"]
RayLike = Union[Ray, Tuple[Vec3Like, Vec3Like]]
PlaneLike = Union[Plane, Tuple[Vec3Like, Vec3Like]]
