"""The reference check: is an answer the exact one, and if not, how far off — in ulps, with a report that
reproduces the query exactly (raykernel::testkit's reference check, testkit/plane_reference_check.hpp).

Ray–plane and ray–triangle answers are checked by the C++ toolkit (exact rationals, correctly rounded t and
barycentric coordinates; testkit/triangle_reference_check.hpp for triangles). A bare hit/miss and t (what a
Möller–Trumbore test gives) can also be checked against ``raykernel.testing.exact`` (docs/contract.md §6 in
Fractions, sharing no code with the kernel). Arrays are compared in one vectorized pass, and the first
mismatching row gets the full report.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from fractions import Fraction
from typing import Optional, Tuple, Union

import numpy as np

from .. import _raykernel
from .._types import (
    ExactTriangleIntersection,
    Intersection,
    Relation,
    TriangleIntersection,
    TriangleLocation,
    TriangleRelation,
)
from . import exact

_tk = _raykernel.testkit

RelationLike = Union[Relation, str, int]


def ulp_distance(a: float, b: float) -> Optional[int]:
    """The number of steps from ``a`` to ``b`` through the doubles in increasing order, where −0 and +0 are
    one step apart and DBL_MAX to inf is one step: 0 exactly when the bits are the same. None for NaN."""
    return _tk.ulp_distance(a, b)


def ulp_difference(a: float, b: float) -> Optional[int]:
    """``ulp_distance(a, b)`` with the sign of b − a in that order (negative when b is below a)."""
    return _tk.ulp_difference(a, b)


def _order_keys(x: np.ndarray) -> np.ndarray:
    """The position of each double in the increasing order of all doubles, −0 and +0 distinct (as uint64;
    reference_check.cpp's order_key): consecutive doubles get consecutive keys."""
    bits = np.ascontiguousarray(x, dtype=np.float64).view(np.uint64)
    sign = np.uint64(1) << np.uint64(63)
    negative = (bits & sign) != 0
    return np.where(negative, (sign - np.uint64(1)) - (bits & ~sign), sign + bits)


def ulp_distances(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``ulp_distance`` elementwise, as uint64; where either is NaN the result is 2^64 − 1."""
    ka, kb = _order_keys(a), _order_keys(b)
    d = np.where(ka > kb, ka - kb, kb - ka)
    nan = np.isnan(np.asarray(a, dtype=np.float64)) | np.isnan(np.asarray(b, dtype=np.float64))
    return np.where(nan, np.iinfo(np.uint64).max, d)


def hex_string(x: float) -> str:
    """x as a hexadecimal float, exact ("0x1.8p+1", "-0x0p+0", "inf", "nan"), as C's %a writes it."""
    return _tk.hex_string(x)


@dataclass(frozen=True)
class ReferenceCheck:
    """One answer compared with the exact one (testkit::ReferenceCheck)."""

    expected: Intersection
    got: Intersection
    exact_num: Fraction
    exact_den: Fraction
    exact_t: Optional[Fraction]
    max_t_ulps: int
    relation_matches: bool
    t_compared: bool
    t_ulps: Optional[int]
    t_direction: int
    passed: bool
    report: str

    def __bool__(self) -> bool:
        return self.passed


def check_against_reference(ray, plane, relation: RelationLike, t: float, max_t_ulps: int = 0) -> ReferenceCheck:
    """Compares ``(relation, t)`` with the exact answer to (``ray``, ``plane``): the relations must be equal,
    and for HIT and BEHIND, ``t`` must be within ``max_t_ulps`` of the correctly rounded t (0: the same bits).
    Raises ValueError for invalid input (it has no answer)."""
    return ReferenceCheck(**_tk.check_against_reference(ray, plane, relation, t, max_t_ulps))


def assert_matches_reference(ray, plane, relation: RelationLike, t: float, max_t_ulps: int = 0) -> None:
    """``check_against_reference``, raising AssertionError with the report when the answer is not right."""
    check = check_against_reference(ray, plane, relation, t, max_t_ulps)
    if not check.passed:
        raise AssertionError("\n" + check.report)


def _relation_codes(relation) -> np.ndarray:
    r = np.asarray(relation)
    if r.dtype.kind in "iu":
        return r.astype(np.int64)
    names = {rel.value: rel.code for rel in Relation}
    names["in_plane"] = Relation.IN_PLANE.code
    return np.array([names.get(str(x), -1) for x in r.ravel()], dtype=np.int64).reshape(r.shape)


def assert_arrays_match_reference(
    origins, directions, points, normals, relation, t, max_t_ulps: int = 0, *, reference_path: str = "certified"
) -> None:
    """Vectorized ``assert_matches_reference``: row i of the answers (``relation`` as Relation codes or
    names, ``t``) against the exact answer to query i. Rows that are invalid input must be absent (the
    assertion fails naming the first one). The exact answers come from ``intersect_batch`` (certified: equal
    to the exact path bit for bit, and fast) or, with ``reference_path="exact"``, from the rational path. On
    a mismatch the AssertionError carries the count of wrong rows and the reference check's report of the
    first one."""
    exact_answers = _raykernel.intersect_batch(origins, directions, points, normals, path=reference_path)
    got_codes = _relation_codes(relation)
    got_t = np.asarray(t, dtype=np.float64)
    expected_codes = exact_answers.relation.astype(np.int64)
    if got_codes.shape != expected_codes.shape or got_t.shape != expected_codes.shape:
        raise AssertionError(
            f"answers have shapes {got_codes.shape} and {got_t.shape}, expected ({expected_codes.shape[0]},)"
        )
    with_t = (expected_codes == Relation.HIT.code) | (expected_codes == Relation.BEHIND.code)
    t_error = ulp_distances(exact_answers.t, got_t)
    wrong = (got_codes != expected_codes) | (with_t & (t_error > np.uint64(max_t_ulps)))
    if not wrong.any():
        return
    bad = np.flatnonzero(wrong)
    i = int(bad[0])
    row = lambda a: tuple(float(x) for x in np.asarray(a, dtype=np.float64).reshape(-1, 3)[i])  # noqa: E731
    points_a, normals_a = np.asarray(points, dtype=np.float64), np.asarray(normals, dtype=np.float64)
    point = tuple(map(float, points_a)) if points_a.shape == (3,) else row(points_a)
    normal = tuple(map(float, normals_a)) if normals_a.shape == (3,) else row(normals_a)
    code = int(got_codes[i])
    got_relation = Relation.from_code(code) if 0 <= code <= 3 else Relation.HIT
    check = check_against_reference((row(origins), row(directions)), (point, normal), got_relation, float(got_t[i]), max_t_ulps)
    note = "" if 0 <= code <= 3 else f"  (row {i} answered relation code {code}, not a relation)\n"
    raise AssertionError(f"\n{len(bad)} of {len(wrong)} rows differ from the exact answer; row {i}:\n{note}{check.report}")


# Ray–triangle ------------------------------------------------------------------------------------------------


def _hex3(v) -> str:
    return "(" + ", ".join(hex_string(float(x)) for x in v) + ")"


def _tolerance(max_ulps: Optional[int]) -> str:
    return " (t not checked)" if max_ulps is None else f" (tolerance {max_ulps} ulps)"


_UNSET = object()  # a keyword not given


def _describe_t(t: float) -> str:
    return "nan" if math.isnan(t) else f"{hex_string(t)} ({t!r})"


@dataclass(frozen=True)
class TriangleReferenceCheck:
    """A full ray–triangle answer compared with the exact one (testkit::TriangleReferenceCheck): relation,
    location and owned flag, and t and the barycentric coordinates in ulps (``ulps``: t, ua, ub, uc; None
    where not compared: den = 0, or the answer's value NaN, i.e. not computed)."""

    expected: TriangleIntersection
    got: TriangleIntersection
    exact: ExactTriangleIntersection
    rule: str
    max_ulps: int
    check_location: bool
    relation_matches: bool
    location_matches: bool
    owned_matches: bool
    ulps: Tuple[Optional[int], Optional[int], Optional[int], Optional[int]]
    passed: bool
    report: str

    def __bool__(self) -> bool:
        return self.passed


def check_triangle_against_reference(
    ray, triangle, answer, *, rule: str = "owned", max_ulps: int = 0, check_location: bool = True
) -> TriangleReferenceCheck:
    """Compares ``answer`` — ``(relation, location, owned, t, barycentric)``, e.g. a ``TriangleIntersection``;
    relation and location as raykernel enum members, their strings or their codes — with the exact answer to
    (``ray``, ``triangle``) under ``rule`` (docs/contract.md §6). The relation must be equal; the location and
    the owned flag too when ``check_location`` (False for code that computes neither, like Möller–Trumbore);
    t and each barycentric coordinate within ``max_ulps`` of the correctly rounded exact value, where the exact
    den ≠ 0 and the answer's value is not NaN. The report gives the query in hexadecimal floats, a
    ``raykernel triangle`` line that replays it, both answers, the exact rationals and the errors in ulps.
    Raises ValueError for invalid input."""
    relation, location, owned, t, barycentric = answer
    d = _tk.check_triangle_against_reference(ray, triangle, relation, location, bool(owned), float(t),
                                             tuple(float(x) for x in barycentric), rule, max_ulps, check_location)
    d["rule"] = str(d["rule"].value)
    d["ulps"] = tuple(d["ulps"])
    return TriangleReferenceCheck(**d)


def assert_triangle_matches_reference(
    ray, triangle, answer, *, rule: str = "owned", max_ulps: int = 0, check_location: bool = True
) -> None:
    """``check_triangle_against_reference``, raising AssertionError with the report on a mismatch."""
    check = check_triangle_against_reference(ray, triangle, answer, rule=rule, max_ulps=max_ulps,
                                             check_location=check_location)
    if not check.passed:
        raise AssertionError("\n" + check.report)


def _codes(values, enum) -> np.ndarray:
    v = np.asarray(values)
    if v.dtype.kind in "iub":
        return v.astype(np.int64)
    names = {m.value: m.code for m in enum}
    return np.array([names.get(str(getattr(x, "value", x)), -1) for x in v.ravel()], dtype=np.int64).reshape(v.shape)


def assert_triangle_arrays_match_reference(
    origins, directions, a, b, c, relation=None, t=None, barycentric=None, *, hit=None, location=None, owned=None,
    rule: str = "owned", max_ulps: int = 0, reference_path: str = "certified",
) -> None:
    """Vectorized ``assert_triangle_matches_reference``: row i of the answers against the exact answer to
    query i (ray i, triangle i; or the one triangle when ``a``, ``b``, ``c`` are 3-vectors) under ``rule``.
    ``relation`` (and ``location``) as codes or names; ``t``, ``barycentric`` ((n, 3)), ``location`` and
    ``owned`` are compared when given (NaN values are "not computed" and not compared). Code that only says hit
    or not (Möller–Trumbore) passes ``hit=`` (bool array) instead of ``relation``: a row must be a hit exactly
    when the exact relation is HIT, and its t and coordinates are compared where the line crosses the plane
    (and not NaN). The exact answers come
    from ``intersect_triangle_batch`` (certified: equal to the exact path bit for bit) or, with
    ``reference_path="exact"``, the rational path. On a mismatch the AssertionError carries the count of
    wrong rows and the reference check's report of the first one."""
    expected = _raykernel.intersect_triangle_batch(origins, directions, a, b, c, rule=rule, path=reference_path)
    n = expected.relation.shape[0]
    if (relation is None) == (hit is None):
        raise ValueError("give either relation or hit")
    if hit is not None:  # judged as hit or not: a non-hit stands for the exact relation when that is not HIT
        expected_codes = expected.relation.astype(np.int64)
        got_hit = np.asarray(hit, dtype=bool).reshape(-1)
        if got_hit.shape != (n,):
            raise AssertionError(f"hit has shape {got_hit.shape}, expected ({n},)")
        miss = np.where(expected_codes == TriangleRelation.HIT.code, TriangleRelation.MISS.code, expected_codes)
        relation = np.where(got_hit, TriangleRelation.HIT.code, miss)
    got_relation = _codes(relation, TriangleRelation)
    if got_relation.shape != (n,):
        raise AssertionError(f"relation has shape {got_relation.shape}, expected ({n},)")
    wrong = got_relation != expected.relation.astype(np.int64)
    crossing = expected.location != TriangleLocation.NONE.code
    if location is not None:
        wrong |= _codes(location, TriangleLocation) != expected.location.astype(np.int64)
    if owned is not None:
        wrong |= np.asarray(owned, dtype=bool) != expected.owned
    got_t = np.full(n, np.nan) if t is None else np.asarray(t, dtype=np.float64).reshape(n)
    got_u = np.full((n, 3), np.nan) if barycentric is None else np.asarray(barycentric, dtype=np.float64).reshape(n, 3)
    too_far = lambda want, got: crossing & ~np.isnan(got) & (ulp_distances(want, got) > np.uint64(max_ulps))  # noqa: E731
    wrong |= too_far(expected.t, got_t)
    for k in range(3):
        wrong |= too_far(expected.barycentric[:, k], got_u[:, k])
    if not wrong.any():
        return
    bad = np.flatnonzero(wrong)
    i = int(bad[0])

    def row(x):
        x = np.asarray(x, dtype=np.float64)
        return tuple(float(v) for v in (x if x.shape == (3,) else x.reshape(-1, 3)[i]))

    code = int(got_relation[i])
    got_location = (int(_codes(location, TriangleLocation)[i]) if location is not None
                    else int(expected.location[i]))
    got_owned = bool(np.asarray(owned)[i]) if owned is not None else bool(expected.owned[i])
    note = "" if 0 <= code < len(TriangleRelation) else f"  (row {i} answered relation code {code})\n"
    answer = (code if 0 <= code < len(TriangleRelation) else TriangleRelation.MISS.code,
              got_location if 0 <= got_location < len(TriangleLocation) else TriangleLocation.NONE.code,
              got_owned, float(got_t[i]), tuple(float(x) for x in got_u[i]))
    check = check_triangle_against_reference((row(origins), row(directions)), (row(a), row(b), row(c)), answer,
                                             rule=rule, max_ulps=max_ulps,
                                             check_location=location is not None or owned is not None)
    raise AssertionError(f"\n{len(bad)} of {n} rows differ from the exact answer; row {i}:\n{note}{check.report}")


@dataclass(frozen=True)
class TriangleHitCheck:
    """A ray–triangle hit answer compared with the exact one (docs/contract.md §6) under ``rule``."""

    expected: exact.ExactTriangleAnswer
    rule: str
    got_hit: bool
    got_t: float
    max_ulps: Optional[int]
    hit_matches: bool
    t_ulps: Optional[int]
    passed: bool
    report: str

    def __bool__(self) -> bool:
        return self.passed


def _tolerance_argument(max_ulps, max_t_ulps, function: str):
    """max_ulps, or the max_t_ulps of an older call (the triangle checks' one name is max_ulps)."""
    if max_t_ulps is _UNSET:
        return max_ulps
    if max_ulps != 0:
        raise TypeError(f"{function}: give max_ulps only (max_t_ulps is its old name)")
    warnings.warn(f"{function}: max_t_ulps is now max_ulps, as in the other triangle checks", DeprecationWarning,
                  stacklevel=3)
    return max_t_ulps


def check_triangle_hit_against_reference(
    ray, triangle, hit: bool, t: float, *, rule: str = "owned", max_ulps: Optional[int] = 0, max_t_ulps=_UNSET
) -> TriangleHitCheck:
    """Is ``hit`` (and, when it is a hit, ``t``) the exact answer for the ray and the triangle (a, b, c)?

    The exact hit is §6's relation "hit" under ``rule`` ("owned", the default of every triangle check and of
    ``intersect``: the watertight tie-break; "closed": the triangle with its boundary, what Möller–Trumbore's
    u ≥ 0, v ≥ 0, u + v ≤ 1 tests), i.e. the ray meets the triangle at t ≥ 0; degenerate, parallel and coplanar
    triangles are never hit. t must be within ``max_ulps`` of the correctly rounded exact t (None: t is not
    checked, only the hit). ``max_t_ulps``, the old name of ``max_ulps``, still works with a
    DeprecationWarning."""
    max_ulps = _tolerance_argument(max_ulps, max_t_ulps, "check_triangle_hit_against_reference")
    if rule not in ("closed", "owned"):
        raise ValueError(f"rule: expected 'closed' or 'owned', got {rule!r}")
    answer = exact.exact_ray_triangle(ray, triangle)
    relation = answer.closed if rule == "closed" else answer.owned
    expected_hit = relation == "hit"
    hit_matches = bool(hit) == expected_hit
    t_ulps = ulp_distance(answer.t, t) if expected_hit and hit else None
    t_ok = not (expected_hit and hit) or max_ulps is None or (t_ulps is not None and t_ulps <= max_ulps)
    passed = hit_matches and t_ok

    problems = []
    if not hit_matches:
        problems.append(f"{'hit' if hit else 'miss'}, expected {'hit' if expected_hit else 'miss'}")
    if not t_ok:
        if t_ulps is None:
            problems.append("t is nan, expected a number")
        else:
            direction = "below" if (ulp_difference(answer.t, t) or 0) < 0 else "above"
            problems.append(f"t is {t_ulps} ulp{'s' if t_ulps != 1 else ''} {direction} the correctly rounded t")
    o, d = ray
    a, b, c = triangle
    where = answer.kind if answer.kind != "crossing" else f"{answer.location}, {relation} under the {rule} rule"
    line = " ".join(hex_string(float(x)) for v in (o, d, a, b, c) for x in v)
    lines = [
        "raykernel reference check "
        + ("passed" if passed else "FAILED: " + "; ".join(problems) + _tolerance(max_ulps)),
        f"  query     o = {_hex3(o)}  d = {_hex3(d)}  a = {_hex3(a)}  b = {_hex3(b)}  c = {_hex3(c)}",
        f"  replay    echo '{line}' | raykernel triangle --rule={rule} --exact",
        f"  expected  {'hit ' if expected_hit else 'miss'}  ({where})"
        + (f"  t = {_describe_t(answer.t)}" if answer.exact_t is not None else ""),
        f"  got       {'hit ' if hit else 'miss'}" + (f"  t = {_describe_t(t)}" if hit else ""),
    ]
    if answer.exact_t is not None:
        ua, ub, uc = answer.barycentric
        lines.append(f"  exact     t = num/den = {answer.exact_t}, barycentric (πa, πb, πc)/den = ({ua}, {ub}, {uc})")
    else:
        lines.append(f"  exact     num = (a − o)·N = {answer.num}, den = d·N = {answer.den}")
    if t_ulps is not None:
        lines.append(f"  t error   {t_ulps} ulps" + _tolerance(max_ulps))
    return TriangleHitCheck(answer, rule, bool(hit), float(t), max_ulps, hit_matches, t_ulps, passed,
                                  "\n".join(lines) + "\n")


def assert_triangle_hit_matches_reference(
    ray, triangle, hit: bool, t: float, *, rule: str = "owned", max_ulps: Optional[int] = 0, max_t_ulps=_UNSET
) -> None:
    """``check_triangle_hit_against_reference``, raising AssertionError with the report on a mismatch."""
    max_ulps = _tolerance_argument(max_ulps, max_t_ulps, "assert_triangle_hit_matches_reference")
    check = check_triangle_hit_against_reference(ray, triangle, hit, t, rule=rule, max_ulps=max_ulps)
    if not check.passed:
        raise AssertionError("\n" + check.report)
