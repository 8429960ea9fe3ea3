"""The kernel against raykernel.testing.exact: docs/contract.md §1 evaluated in Python's Fractions, an oracle
that shares no code with the C++ (its rounding is CPython's correctly rounded int division)."""

import math

import numpy as np

import raykernel as rk
from raykernel._raykernel import testkit
from raykernel.testing import exact


def test_kernel_equals_the_fraction_oracle_on_hard_queries():
    kinds = list(testkit.QUERY_KINDS)
    o, d, p, n, _ = testkit.make_query_arrays(kinds, 1300, 2024)  # 100 of each kind, on average
    batch = rk.intersect_batch(o, d, p, n)
    for i in range(len(o)):
        ray, plane = (o[i], d[i]), (p[i], n[i])
        want = exact.exact_ray_plane(ray, plane)
        x = rk.intersect_exact_rational(ray, plane)
        assert x.relation is want.relation, i
        assert (x.num, x.den, x.exact_t) == (want.num, want.den, want.exact_t), i
        assert float.hex(x.t) == float.hex(want.t) or (math.isnan(x.t) and math.isnan(want.t)), i
        assert batch.relation[i] == want.relation.code
        assert np.float64(batch.t[i]).tobytes() == np.float64(want.t).tobytes() or math.isnan(want.t)


def test_the_oracle_rounds_like_the_contract():
    from fractions import Fraction as F

    assert exact.round_to_double(F(1, 10)) == 0.1
    assert exact.round_to_double(F(0)) == 0.0 and math.copysign(1, exact.round_to_double(F(0))) == 1
    assert math.copysign(1, exact.round_to_double(F(-1, 2**2000))) == -1  # −0 for a tiny negative t
    assert exact.round_to_double(F(2**1024)) == math.inf and exact.round_to_double(F(-(2**1024))) == -math.inf
    assert exact.round_to_double(F(2**53 + 1)) == 2.0**53  # a tie goes to the even neighbour
    for k in range(2000):  # against the kernel's MPFR rounding: pseudo-random quotients, scaled by 2^-350 .. 2^349
        q = F((2 * k + 1) * 0x9E3779B97F4A7C15 % 2**60 + 1, (k * 0x632BE59BD9B4E019 % 2**61) | 1) * F(2) ** (k % 700 - 350)
        assert float.hex(exact.round_to_double(q)) == float.hex(rk.round_rational_to_double(q))
