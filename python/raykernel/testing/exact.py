"""Exact answers in pure Python (``fractions.Fraction``), written from docs/contract.md alone.

An oracle that shares no code with the C++ kernel: every double is converted to the Fraction it denotes
(exactly), the formulas of the contract are evaluated in rationals, and a result is rounded to a double by
CPython's int/int true division, which is correctly rounded (round half to even, gradual underflow).
Thousands of times slower than the kernel; meant for tests.

``exact_ray_plane`` follows §1 (what ``raykernel.intersect_exact`` computes, by other means);
``exact_ray_triangle`` follows §6 (ray–triangle, both rules), which the C++ kernel does not implement yet:
until it does, this is the reference ``raykernel.testing`` checks triangle code against.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import NamedTuple, Optional, Sequence, Tuple

from .._types import Relation

Q3 = Tuple[Fraction, Fraction, Fraction]


def to_fraction(x: float) -> Fraction:
    """The exact value of a finite double."""
    if not math.isfinite(x):
        raise ValueError(f"{x!r} is not finite: it has no exact value")
    return Fraction(x)


def vec(v: Sequence[float]) -> Q3:
    x, y, z = v
    return (to_fraction(float(x)), to_fraction(float(y)), to_fraction(float(z)))


def sub(a: Q3, b: Q3) -> Q3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a: Q3, b: Q3) -> Fraction:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Q3, b: Q3) -> Q3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def sign(x: Fraction) -> int:
    return (x > 0) - (x < 0)


def round_to_double(q: Fraction) -> float:
    """q rounded to the nearest double, ties to even; ±inf beyond the double range; a nonzero q that rounds
    to zero keeps its sign; an exact zero is +0 (docs/contract.md §1)."""
    if q == 0:
        return 0.0
    try:
        return q.numerator / q.denominator  # int/int true division: correctly rounded in CPython
    except OverflowError:
        return math.inf if q > 0 else -math.inf


class ExactPlaneAnswer(NamedTuple):
    relation: Relation
    t: float  # NaN for PARALLEL and IN_PLANE
    num: Fraction  # (p − o)·n
    den: Fraction  # d·n
    exact_t: Optional[Fraction]


def exact_ray_plane(ray, plane) -> ExactPlaneAnswer:
    """docs/contract.md §1 in rationals. ``ray`` is (origin, direction), ``plane`` is (point, normal), all
    finite, direction and normal nonzero (else ValueError)."""
    o, d = vec(ray[0]), vec(ray[1])
    p, n = vec(plane[0]), vec(plane[1])
    if d == (0, 0, 0):
        raise ValueError("ray direction is the zero vector")
    if n == (0, 0, 0):
        raise ValueError("plane normal is the zero vector")
    num, den = dot(sub(p, o), n), dot(d, n)
    if den == 0:
        return ExactPlaneAnswer(Relation.IN_PLANE if num == 0 else Relation.PARALLEL, math.nan, num, den, None)
    t = num / den
    return ExactPlaneAnswer(Relation.HIT if t >= 0 else Relation.BEHIND, round_to_double(t), num, den, t)


# Ray–triangle (docs/contract.md §6) -------------------------------------------------------------------------

TRIANGLE_LOCATIONS = ("inside", "edge-ab", "edge-bc", "edge-ca", "vertex-a", "vertex-b", "vertex-c", "outside")


class ExactTriangleAnswer(NamedTuple):
    """§6's answer. ``kind`` is "degenerate", "parallel", "coplanar", or "crossing" (den ≠ 0); for a crossing,
    ``location``, the relation under each rule ("hit", "behind" or "miss"), t and the barycentric
    coordinates (πa, πb, πc)/den, exactly and rounded."""

    kind: str
    location: Optional[str]
    closed: Optional[str]  # relation under the closed rule
    owned: Optional[str]  # relation under the owned rule
    t: float
    exact_t: Optional[Fraction]
    barycentric: Optional[Tuple[Fraction, Fraction, Fraction]]
    num: Fraction
    den: Fraction


def _pi(d: Q3, o: Q3, p: Q3, q: Q3) -> Fraction:
    """π(p, q) = d · ((p − o) × (q − o))."""
    return dot(d, cross(sub(p, o), sub(q, o)))


def _owned_sign(d: Q3, p: Q3, q: Q3) -> int:
    """The owned rule's sign for a zero π(p, q): the first nonzero of the x, y, z components of d × (q − p)."""
    for component in cross(d, sub(q, p)):
        if component != 0:
            return sign(component)
    return 0


def exact_ray_triangle(ray, triangle) -> ExactTriangleAnswer:
    """docs/contract.md §6 in rationals. ``ray`` is (origin, direction) with a nonzero direction, ``triangle``
    is (a, b, c); all finite."""
    o, d = vec(ray[0]), vec(ray[1])
    a, b, c = (vec(v) for v in triangle)
    if d == (0, 0, 0):
        raise ValueError("ray direction is the zero vector")
    normal = cross(sub(b, a), sub(c, a))
    den, num = dot(d, normal), dot(sub(a, o), normal)
    if normal == (0, 0, 0):
        return ExactTriangleAnswer("degenerate", None, None, None, math.nan, None, None, num, den)
    if den == 0:
        kind = "coplanar" if num == 0 else "parallel"
        return ExactTriangleAnswer(kind, None, None, None, math.nan, None, None, num, den)
    pa, pb, pc = _pi(d, o, b, c), _pi(d, o, c, a), _pi(d, o, a, b)
    s = sign(den)
    signs = (sign(pa), sign(pb), sign(pc))
    zeros = tuple(x == 0 for x in signs)
    if any(x == -s for x in signs):
        location = "outside"
    elif zeros == (False, False, False):
        location = "inside"
    else:  # πa = π(b, c), πb = π(c, a), πc = π(a, b); two zero π meet at a vertex (all three: den = 0)
        location = {
            (True, False, False): "edge-bc",
            (False, True, False): "edge-ca",
            (False, False, True): "edge-ab",
            (False, True, True): "vertex-a",
            (True, False, True): "vertex-b",
            (True, True, False): "vertex-c",
        }[zeros]
    t = num / den
    forward = "hit" if t >= 0 else "behind"
    closed = forward if location != "outside" else "miss"
    owned_signs = (
        signs[0] or _owned_sign(d, b, c),
        signs[1] or _owned_sign(d, c, a),
        signs[2] or _owned_sign(d, a, b),
    )
    owned = forward if all(x == s for x in owned_signs) else "miss"
    barycentric = (pa / den, pb / den, pc / den)
    return ExactTriangleAnswer("crossing", location, closed, owned, round_to_double(t), t, barycentric, num, den)
