"""Exact answers in pure Python (``fractions.Fraction``), written from docs/contract.md alone.

An oracle that shares no code with the C++ kernel: every double is converted to the Fraction it denotes
(exactly), the formulas of the contract are evaluated in rationals, and a result is rounded to a double by
CPython's int/int true division, which is correctly rounded (round half to even, gradual underflow).
Thousands of times slower than the kernel; meant for tests.

``exact_ray_plane`` follows §1 (what ``raykernel.intersect_exact`` computes, by other means);
``exact_ray_triangle`` follows §6 (ray–triangle, both rules), which the C++ kernel does not implement yet:
until it does, this is the reference ``raykernel.testing`` checks triangle code against;
``exact_ray_sphere`` follows §10 (ray–sphere): its irrational roots U ∓ √V are rounded by ``round_root``, a
search over the doubles that compares the root with rationals exactly (w = U − m against √V by w² against V).
"""

from __future__ import annotations

import math
import struct
import sys
from fractions import Fraction
from typing import NamedTuple, Optional, Sequence, Tuple

from .._types import Relation, SphereOrigin, SphereRelation

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


# Ray–sphere (docs/contract.md §10) --------------------------------------------------------------------------

_LARGEST = sys.float_info.max
_OVERFLOW = Fraction(2) ** 1024 - Fraction(2) ** 970  # halfway between the largest double and 2^1024


def root_side(u: Fraction, v: Fraction, upper: bool, m: Fraction) -> int:
    """The sign of r − m for the root r = U − √V (``upper`` False) or U + √V (``upper`` True), V ≥ 0, exactly:
    with w = U − m, r − m = w ∓ √V, whose sign is w's when the other term cannot outweigh it, else that of
    ±(w² − V)."""
    w = u - m
    if not upper:  # w − √V
        return sign(w * w - v) if w > 0 else -1 if (w < 0 or v > 0) else 0
    return sign(v - w * w) if w < 0 else 1 if (w > 0 or v > 0) else 0  # w + √V


def _double_of_key(k: int) -> float:
    """The finite doubles in increasing order: key k ≥ 0 is the double whose bits are k, −k its negation."""
    x = struct.unpack("<d", struct.pack("<Q", abs(k)))[0]
    return -x if k < 0 else x


def round_root(u: Fraction, v: Fraction, upper: bool) -> float:
    """U ∓ √V (``root_side``) rounded to the nearest double, ties to even, ±inf beyond the double range; a
    nonzero root that rounds to zero keeps its sign, an exact zero is +0 (docs/contract.md §10)."""
    side = lambda m: root_side(u, v, upper, Fraction(m))  # noqa: E731
    if side(_OVERFLOW) >= 0:
        return math.inf
    if side(-_OVERFLOW) <= 0:
        return -math.inf
    if side(_LARGEST) >= 0:
        return _LARGEST
    if side(-_LARGEST) <= 0:
        return -_LARGEST
    # The largest key whose double is ≤ r: double(lo) ≤ r < double(hi) throughout.
    top = struct.unpack("<Q", struct.pack("<d", _LARGEST))[0]
    lo, hi = -top, top
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if side(_double_of_key(mid)) >= 0:
            lo = mid
        else:
            hi = mid
    below, above = _double_of_key(lo), _double_of_key(hi)
    halfway = side((Fraction(below) + Fraction(above)) / 2)
    nearest = below if halfway < 0 or (halfway == 0 and lo % 2 == 0) else above  # an even key: an even significand
    if nearest == 0:
        exact_zero = side(0) == 0
        return 0.0 if exact_zero or side(0) > 0 else -0.0
    return nearest


class ExactSphereAnswer(NamedTuple):
    """§10's answer: where the origin is, how the line meets the sphere, the roots rounded (t1 ≤ t2; both the
    root for TANGENT, NaN for MISS), and the exact values A = d·d, B = d·f, C = f·f − r², D = B² − A·C (f = o − c)
    and U = −B/A, V = D/A² (None for MISS), the roots being U ∓ √V."""

    origin: SphereOrigin
    relation: SphereRelation
    t1: float
    t2: float
    a: Fraction
    b: Fraction
    c: Fraction
    d: Fraction
    u: Optional[Fraction]
    v: Optional[Fraction]


def exact_ray_sphere(ray, sphere) -> ExactSphereAnswer:
    """docs/contract.md §10 in rationals. ``ray`` is (origin, direction) with a nonzero direction, ``sphere``
    is (center, radius) with a positive radius; all finite (else ValueError)."""
    o, d = vec(ray[0]), vec(ray[1])
    center, radius = vec(sphere[0]), to_fraction(float(sphere[1]))
    if d == (0, 0, 0):
        raise ValueError("ray direction is the zero vector")
    if radius <= 0:
        raise ValueError("sphere radius is not positive")
    f = sub(o, center)
    a, b = dot(d, d), dot(d, f)
    c = dot(f, f) - radius * radius
    disc = b * b - a * c
    origin = SphereOrigin.INSIDE if c < 0 else SphereOrigin.ON_SURFACE if c == 0 else SphereOrigin.OUTSIDE
    if disc < 0:
        return ExactSphereAnswer(origin, SphereRelation.MISS, math.nan, math.nan, a, b, c, disc, None, None)
    u, v = -b / a, disc / (a * a)
    relation = SphereRelation.TANGENT if disc == 0 else SphereRelation.CROSS
    return ExactSphereAnswer(origin, relation, round_root(u, v, False), round_root(u, v, True), a, b, c, disc, u, v)
