"""Testing other ray code against raykernel, in Python (the counterpart of raykernel::testkit in C++).

    from raykernel.testing import assert_matches_reference, ulp_distance
    assert_matches_reference(ray, plane, my_relation, my_t, max_t_ulps=4)   # AssertionError with a report

- ``check_against_reference`` / ``assert_matches_reference``: one ray–plane answer against the exact one
  (relation, and t in ulps), with a report that gives the query in hexadecimal floats, a
  ``raykernel classify`` line that replays it, the expected and the got answers, and the exact t as a fraction;
- ``assert_arrays_match_reference``: the same for arrays of answers, in one vectorized pass;
- ``check_triangle_against_reference`` / ``assert_triangle_matches_reference``: one ray–triangle answer
  (relation, location, owned flag, t and barycentric coordinates in ulps) against docs/contract.md §6 under a
  rule, with the C++ toolkit's report (``raykernel triangle`` replay line, exact rationals, ulps);
  ``assert_triangle_arrays_match_reference`` for arrays;
- ``check_triangle_hit_against_reference`` / ``assert_triangle_hit_matches_reference``: a bare hit/miss and t
  (what a Möller–Trumbore test computes), checked in Fractions by ``raykernel.testing.exact``;
- ``ulp_distance``, ``ulp_difference``, ``ulp_distances`` (arrays), ``hex_string``;
- ``raykernel.testing.exact``: the contract in pure-Python Fractions, an oracle sharing no code with the kernel
  (ray–plane, ray–triangle, and ray–sphere with its irrational roots rounded by exact comparisons);
- ``raykernel.testing.hypothesis``: Hypothesis strategies for the hard queries, planes, triangles and spheres
  (imports Hypothesis).
"""

from .reference import (
    ReferenceCheck,
    TriangleHitCheck,
    TriangleReferenceCheck,
    assert_arrays_match_reference,
    assert_matches_reference,
    assert_triangle_arrays_match_reference,
    assert_triangle_hit_matches_reference,
    assert_triangle_matches_reference,
    check_against_reference,
    check_triangle_against_reference,
    check_triangle_hit_against_reference,
    hex_string,
    ulp_difference,
    ulp_distance,
    ulp_distances,
)

__all__ = [
    "ReferenceCheck",
    "TriangleHitCheck",
    "TriangleReferenceCheck",
    "assert_arrays_match_reference",
    "assert_matches_reference",
    "assert_triangle_arrays_match_reference",
    "assert_triangle_hit_matches_reference",
    "assert_triangle_matches_reference",
    "check_against_reference",
    "check_triangle_against_reference",
    "check_triangle_hit_against_reference",
    "hex_string",
    "ulp_difference",
    "ulp_distance",
    "ulp_distances",
]


def __dir__() -> list:
    """The API (``__all__``) and the submodules: not the modules it is made of."""
    return sorted(__all__ + ["exact", "hypothesis", "reference"])
