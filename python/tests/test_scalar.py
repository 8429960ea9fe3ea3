"""The scalar API: hand-derived answers (the derivation beside each), errors naming the field, the types."""

import math
from fractions import Fraction

import pytest

import raykernel as rk
from raykernel import Relation, Stage

H = float.fromhex

# The contract's first example: o = 0, d = e_z, p = (0, 0, 5), n = e_z. den = d·n = 1, num = (p − o)·n = 5,
# so t = 5, a hit.
SEED_RAY = ((0, 0, 0), (0, 0, 1))
SEED_PLANE = ((0, 0, 5), (0, 0, 1))


def bits(x: float) -> str:
    return float.hex(x) if not math.isnan(x) else "nan"


@pytest.mark.parametrize("f", [rk.intersect, rk.intersect_exact])
def test_relations_by_hand(f):
    assert f(SEED_RAY, SEED_PLANE) == (Relation.HIT, 5.0)
    # d = e_x: den = 0, num = 5 ≠ 0: parallel, t NaN.
    x = f(((0, 0, 0), (1, 0, 0)), SEED_PLANE)
    assert x.relation is Relation.PARALLEL and math.isnan(x.t)
    # o = (0, 0, 5) on the plane, d = e_x: den = 0, num = 0: in-plane.
    x = f(((0, 0, 5), (1, 0, 0)), SEED_PLANE)
    assert x.relation is Relation.IN_PLANE and math.isnan(x.t)
    # p = (0, 0, −5): num = −5, den = 1: t = −5, behind.
    assert f(SEED_RAY, ((0, 0, -5), (0, 0, 1))) == (Relation.BEHIND, -5.0)
    # d = (10, 0, 0), p = n = e_x: t = 1/10, rounded to nearest: the double 0.1 (0x1.999999999999ap-4).
    assert bits(f(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0))).t) == "0x1.999999999999ap-4"


@pytest.mark.parametrize("f", [rk.intersect, rk.intersect_exact])
def test_signed_zeros_overflow_and_underflow_by_hand(f):
    # The origin on the plane with den < 0: num = 0, den = −1, t = 0/−1 = 0 exactly, which is +0 (§1).
    x = f(((1, 2, 3), (-1, 0, 0)), ((1, 0, 0), (1, 0, 0)))
    assert x.relation is Relation.HIT and bits(x.t) == "0x0.0p+0"
    # num = 2^-1074, den = −2^1000: t = −2^-2074, nonzero, rounds to zero: keeps its sign, −0 (behind).
    x = f(((0, 0, 0), (-(2.0**1000), 0, 0)), ((H("0x1p-1074"), 0, 0), (1, 0, 0)))
    assert x.relation is Relation.BEHIND and bits(x.t) == "-0x0.0p+0"
    # num = 2^1000, den = 2^-100: t = 2^1100, beyond the double range: +inf.
    x = f(((0, 0, 0), (H("0x1p-100"), 0, 0)), ((2.0**1000, 0, 0), (1, 0, 0)))
    assert x.relation is Relation.HIT and x.t == math.inf
    # The README's example: every component 2^-600 on the x axis. den = d·n = 2^-1200 and num = 2^-1200
    # exactly (both products underflow to 0 in binary64), so t = 1.
    q = ((0, 0, 0), (H("0x1p-600"), 0, 0)), ((H("0x1p-600"), 0, 0), (H("0x1p-600"), 0, 0))
    assert f(*q) == (Relation.HIT, 1.0)


def test_naive_is_the_textbook_formula():
    q = ((0, 0, 0), (H("0x1p-600"), 0, 0)), ((H("0x1p-600"), 0, 0), (H("0x1p-600"), 0, 0))
    x = rk.intersect_naive(*q)  # both products underflow to 0: the doubles see a ray in the plane
    assert x.relation is Relation.IN_PLANE and math.isnan(x.t)
    assert rk.intersect_naive(SEED_RAY, SEED_PLANE) == (Relation.HIT, 5.0)


def test_exact_rational_by_hand():
    x = rk.intersect_exact_rational(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0)))
    assert x == (Relation.HIT, 0.1, Fraction(1), Fraction(10), Fraction(1, 10))
    assert all(type(v) is Fraction for v in (x.num, x.den, x.exact_t))
    # p − o = (1, 0, 0), n = (3, 0, 0): num = 3; d = (0, 7, 0): den = 0: parallel, no t.
    x = rk.intersect_exact_rational(((0, 0, 0), (0, 7, 0)), ((1, 0, 0), (3, 0, 0)))
    assert x.relation is Relation.PARALLEL and x.num == 3 and x.den == 0 and x.exact_t is None
    # The 2^-600 example: num = den = 2^-1200, exactly.
    x = rk.intersect_exact_rational(((0, 0, 0), (H("0x1p-600"), 0, 0)), ((H("0x1p-600"), 0, 0), (H("0x1p-600"), 0, 0)))
    assert x.num == x.den == Fraction(1, 2**1200) and x.exact_t == 1


def test_traced_names_the_stages():
    x = rk.intersect_traced(SEED_RAY, SEED_PLANE)
    assert (x.relation, x.t) == (Relation.HIT, 5.0)
    assert isinstance(x.relation_stage, Stage) and isinstance(x.t_stage, Stage)
    assert x.relation_stage is Stage.FILTER  # d·n = 1 and (p − o)·n = 5: far from zero
    # Products of 2^-1200 are below what the filter's error bound covers: only the exact stage decides.
    q = ((0, 0, 0), (H("0x1p-600"), 0, 0)), ((H("0x1p-600"), 0, 0), (H("0x1p-600"), 0, 0))
    assert rk.intersect_traced(*q).relation_stage is Stage.EXACT


def test_round_rational_to_double_by_hand():
    assert bits(rk.round_rational_to_double(Fraction(1, 10))) == "0x1.999999999999ap-4"
    assert rk.round_rational_to_double(1, 3) == 1 / 3
    assert rk.round_rational_to_double(7) == 7.0
    # 2^53 + 1 is halfway between 2^53 and 2^53 + 2: ties to even, 2^53. 2^53 + 3: halfway, to 2^53 + 4.
    assert rk.round_rational_to_double(2**53 + 1) == 2.0**53
    assert rk.round_rational_to_double(2**53 + 3) == 2.0**53 + 4
    assert rk.round_rational_to_double(2**1024) == math.inf
    assert bits(rk.round_rational_to_double(Fraction(-1, 2**1100))) == "-0x0.0p+0"
    # 3·2^-1076 = 0.75·2^-1074: nearer to 2^-1074 than to 0.
    assert bits(rk.round_rational_to_double(Fraction(3, 2**1076))) == "0x0.0000000000001p-1022"
    with pytest.raises(ValueError, match="denominator is zero"):
        rk.round_rational_to_double(1, 0)
    with pytest.raises(TypeError, match="value"):
        rk.round_rational_to_double(0.5)


@pytest.mark.parametrize(
    "ray, plane, message",
    [
        (((0, 0, 0), (0, 0, 0)), SEED_PLANE, "ray direction is the zero vector"),
        (SEED_RAY, ((0, 0, 5), (0, 0, 0)), "plane normal is the zero vector"),
        (((math.nan, 0, 0), (0, 0, 1)), SEED_PLANE, "ray origin x is NaN"),
        (SEED_RAY, ((0, math.inf, 5), (0, 0, 1)), "plane point y is \\+inf"),
        (SEED_RAY, ((0, 0, 5), (0, 0, -math.inf)), "plane normal z is -inf"),
    ],
)
def test_invalid_input_raises_value_error_naming_the_field(ray, plane, message):
    for f in (rk.intersect, rk.intersect_exact, rk.intersect_exact_rational, rk.intersect_traced):
        with pytest.raises(rk.InvalidInput, match=message):
            f(ray, plane)
    assert issubclass(rk.InvalidInput, ValueError)
    assert rk.validate(ray, plane).replace("+", "\\+") == message
    assert rk.validate(SEED_RAY, SEED_PLANE) is None


def test_malformed_values_name_the_field():
    with pytest.raises(ValueError, match="^ray direction: expected a sequence of 3 numbers, got a sequence of 2 items$"):
        rk.intersect(((0, 0, 0), (0, 1)), SEED_PLANE)
    with pytest.raises(TypeError, match="^plane point y: expected a number, got str$"):
        rk.intersect(SEED_RAY, ((0, "5", 0), (0, 0, 1)))
    with pytest.raises(ValueError, match=r"^ray: expected \(origin, direction\), got a sequence of 3 items$"):
        rk.intersect(((0, 0, 0), (0, 0, 1), (0, 0, 1)), SEED_PLANE)
    with pytest.raises(TypeError, match=r"^primitive: expected a plane \(point, normal\), a triangle \(a, b, c\) or a "
                                        r"raykernel\.Sphere, got NoneType$"):
        rk.intersect(SEED_RAY, None)
    with pytest.raises(ValueError, match="^primitive: expected .*, got a sequence of 4 items$"):
        rk.intersect(SEED_RAY, ((0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)))
    with pytest.raises(ValueError, match="^ray origin z is too large for a double$"):
        rk.intersect(((0, 0, 10**400), (0, 0, 1)), SEED_PLANE)


def test_inputs_are_any_sequences_and_results_are_named_tuples():
    import numpy as np

    ray = rk.Ray(rk.Vec3(0, 0, 0), rk.Vec3(0, 0, 1))
    plane = rk.Plane(np.array([0.0, 0, 5]), [0, 0, np.float32(1)])
    x = rk.intersect(ray, plane)
    assert isinstance(x, rk.Intersection) and x.relation == "hit" and x.t == 5.0
    relation, t = x  # unpacks like a tuple
    assert str(relation) == "hit" and relation.code == 0


def test_relation_enum_is_str_valued_with_codes():
    assert [r.value for r in Relation] == ["hit", "behind", "parallel", "in-plane"]
    assert [r.code for r in Relation] == [0, 1, 2, 3]
    assert all(Relation.from_code(r.code) is r for r in Relation)
    assert Relation("in-plane") is Relation.IN_PLANE and Relation.IN_PLANE == "in-plane"
    assert [s.value for s in Stage] == ["filter", "compensated", "expansion", "exact"]


def test_version_and_environment():
    assert rk.__version__ == rk.version() and rk.version().count(".") == 2
    assert rk.floating_point_environment_is_default() is True
