"""Hostile inputs: values NumPy or Python would silently change on the way into the kernel are refused,
naming the argument and why, and values that are right are answered — bit for bit as before.

- Mesh triangles: integer arrays only, each index checked against [0, vertex count) without wrapping.
- Every vectorized entry point: real numeric arrays only (integer or floating dtypes); complex, str, bytes, object,
  datetime, timedelta, structured and bool arrays, and masked arrays (whose masks would be ignored), raise
  TypeError naming the argument and the dtype.
- Python ints and exact rationals of any size cross between Python and C++ without decimal strings of more
  than the 640 digits CPython always converts (sys.get_int_max_str_digits()).
- load_mesh: a NUL in the path, and a file the kernel rejects once loaded, raise MeshFileError.
"""

import math
import sys
from fractions import Fraction

import numpy as np
import pytest

import raykernel as rk
from raykernel._raykernel import testkit

from test_arrays import same_bits

# ---- Mesh(vertices, triangles) -------------------------------------------------------------------------------

VERTICES = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)


@pytest.mark.parametrize("triangles, dtype", [
    ([[0, 1, 1.9]], "float64"),    # was truncated to 1
    ([[0, 1, -0.5]], "float64"),   # was truncated to 0
    ([[0, 1, 2.0]], "float64"),    # integral, but a float array all the same
    (np.array([[0, 1, np.nan]]), "float64"),
    (np.array([[0, 1, 2]], dtype=np.float32), "float32"),
    ([[True, False, True]], "bool"),
    (np.array([[0, 1, 2]], dtype=complex), "complex128"),
    (np.array([["0", "1", "2"]]), "<U1"),
    (np.array([[0, 1, 2]], dtype=object), "object"),
])
def test_mesh_triangles_must_be_an_integer_array(triangles, dtype):
    with pytest.raises(TypeError, match=r"^triangles: expected an \(m, 3\) array of integer vertex indices, got an "
                                        rf"array of dtype {dtype}"):
        rk.Mesh(VERTICES, triangles)


def test_mesh_triangles_of_every_integer_dtype_are_checked_without_wrapping():
    for dtype in (np.int8, np.uint8, np.int16, np.uint16, np.int32, np.uint32, np.int64, np.uint64):
        mesh = rk.Mesh(VERTICES, np.array([[0, 1, 2]], dtype=dtype))
        assert mesh.triangles.tolist() == [[0, 1, 2]] and mesh.triangles.dtype == np.int64, dtype
    assert rk.Mesh(VERTICES, [[2, 1, 0], [0, 1, 2]]).triangles.tolist() == [[2, 1, 0], [0, 1, 2]]  # lists of ints
    # uint64 max was read as int64 −1 (and 2^32 + 1 would wrap to 1 through uint32): each is named as it is.
    for triangles, value in [(np.array([[0, 2**64 - 1, 2]], dtype=np.uint64), 2**64 - 1),
                             (np.array([[0, 2**32 + 1, 2]], dtype=np.int64), 2**32 + 1),
                             (np.array([[0, -1, 2]], dtype=np.int8), -1),
                             (np.array([[0, 3, 2]], dtype=np.uint8), 3)]:
        with pytest.raises(rk.InvalidInput, match=rf"^mesh: triangle 0: vertex index {value} \(triangles\[0, 1\]\) "
                                                  r"is out of range \(3 vertices\)$"):
            rk.Mesh(VERTICES, triangles)
    with pytest.raises(rk.InvalidInput, match=r"^mesh: triangle 1: vertex index 3 \(triangles\[1, 2\]\)"):
        rk.Mesh(VERTICES, np.array([[0, 1, 2], [0, 1, 3]], dtype=np.int32))
    # An empty array has no index to be wrong: numpy.zeros((0, 3)) (float64) is an empty mesh.
    assert len(rk.Mesh(VERTICES, np.zeros((0, 3)))) == 0 and len(rk.Mesh(VERTICES, np.zeros((0, 3), dtype=int))) == 0


def test_mesh_masked_triangles_are_refused():
    masked = np.ma.masked_array([[0, 1, 2]], mask=[[False, False, True]])
    with pytest.raises(TypeError, match=r"^triangles: .*numpy\.ma\.MaskedArray"):
        rk.Mesh(VERTICES, masked)


# ---- every vectorized entry point: real numeric arrays only ----------------------------------------------------

OCTAHEDRON = testkit.make_octahedron()
RAYS = {"origins": np.array([[0.25, 0.25, -5.0], [3.0, 3.0, -5.0]]), "directions": np.array([[0.0, 0.0, 1.0]] * 2)}
TRIANGLE = {"a": np.array([[-1.0, -1.0, 0.0]] * 2), "b": np.array([[2.0, -1.0, 0.0]] * 2),
            "c": np.array([[-1.0, 2.0, 0.0]] * 2)}
PLANE = {"points": np.array([[0.0, 0.0, 1.0]] * 2), "normals": np.array([[0.0, 1.0, 1.0]] * 2)}

# (name, call with keyword arrays, the arrays it takes): every function that takes arrays.
ENTRY_POINTS = [
    ("intersect_batch", lambda a: rk.intersect_batch(**a), {**RAYS, **PLANE}),
    ("relation_batch", lambda a: rk.relation_batch(**a), {**RAYS, **PLANE}),
    ("intersect_triangle_batch", lambda a: rk.intersect_triangle_batch(**a), {**RAYS, **TRIANGLE}),
    ("relation_triangle_batch", lambda a: rk.relation_triangle_batch(**a), {**RAYS, **TRIANGLE}),
    ("nearest_hit_batch planes", lambda a: rk.nearest_hit_batch(a["origins"], a["directions"],
                                                                 rk.PlaneSet(PLANE["points"], PLANE["normals"])), RAYS),
    ("nearest_hit_batch mesh", lambda a: rk.nearest_hit_batch(a["origins"], a["directions"], OCTAHEDRON), RAYS),
    ("inside_batch", lambda a: rk.inside_batch(a["points"], OCTAHEDRON), {"points": PLANE["points"]}),
    ("PlaneSet", lambda a: rk.PlaneSet(a["points"], a["normals"]), PLANE),
    ("Mesh", lambda a: rk.Mesh(a["vertices"], OCTAHEDRON.triangles), {"vertices": OCTAHEDRON.vertices}),
]


def refused(x: np.ndarray):
    """(what, the array x made hostile, the dtype the error names) for each kind of array that must be refused."""
    n = len(x)
    return [
        ("complex", x.astype(complex), "complex128"),  # its imaginary parts are 0: refused all the same
        ("complex64", x.astype(np.complex64) + 1j, "complex64"),
        ("str", x.astype(str), "<U32"),
        ("bytes", x.astype(bytes), r"\|S32"),
        ("object", x.astype(object), "object"),
        ("datetime64", x.astype(np.int64).astype("datetime64[s]"), r"datetime64\[s\]"),
        ("timedelta64", x.astype(np.int64).astype("timedelta64[s]"), r"timedelta64\[s\]"),
        ("structured", np.zeros(n, dtype=[("x", "f8"), ("y", "f8"), ("z", "f8")]), r"\[\('x', '<f8'\), "),
        ("void", np.zeros((n, 3), dtype="V8"), r"\|V8"),
        ("bool", x != 0, "bool"),
    ]


def cases():
    for name, call, arrays in ENTRY_POINTS:
        for argument, x in arrays.items():
            for what, bad, dtype in refused(x):
                yield pytest.param(call, arrays, argument, bad, dtype, id=f"{name}-{argument}-{what}")


@pytest.mark.parametrize("call, arrays, argument, bad, dtype", cases())
def test_batches_refuse_arrays_that_are_not_real_numbers(call, arrays, argument, bad, dtype):
    with pytest.raises(TypeError, match=rf"^{argument}: expected .*real numbers.*, got an array of dtype {dtype}"):
        call({**arrays, argument: bad})


@pytest.mark.parametrize("name, call, arrays", [pytest.param(*e, id=e[0]) for e in ENTRY_POINTS])
def test_batches_refuse_masked_arrays(name, call, arrays):
    for argument, x in arrays.items():
        mask = np.zeros(x.shape, dtype=bool)
        mask[0, 0] = True  # the row a caller meant to leave out
        with pytest.raises(TypeError, match=rf"^{argument}: .*numpy\.ma\.MaskedArray.*mask would be ignored"):
            call({**arrays, argument: np.ma.masked_array(x, mask=mask)})
        with pytest.raises(TypeError, match=rf"^{argument}: .*numpy\.ma\.MaskedArray"):  # even with nothing masked
            call({**arrays, argument: np.ma.masked_array(x)})


def answers(result):
    """The arrays of a batch's result (or a Mesh/PlaneSet's own arrays), for bit-for-bit comparison."""
    if isinstance(result, rk.Mesh):
        return [result.vertices, result.triangles]
    if isinstance(result, rk.PlaneSet):
        return [result.points, result.normals, result.candidates]
    return [v for v in result if isinstance(v, np.ndarray)]


@pytest.mark.parametrize("name, call, arrays", [pytest.param(*e, id=e[0]) for e in ENTRY_POINTS])
def test_batches_take_integer_and_floating_arrays_and_lists(name, call, arrays):
    reference = answers(call(arrays))
    # The test arrays hold small integers and halves: every dtype below holds them exactly.
    conversions = [lambda x: x.astype(np.float16), lambda x: x.astype(np.float32), lambda x: x.tolist(),
                   lambda x: np.asfortranarray(x), lambda x: x.view(np.matrix)]
    if all((x == np.round(x)).all() for x in arrays.values()):
        conversions += [lambda x, t=t: x.astype(t) for t in (np.int8, np.int16, np.int32, np.int64)]
        conversions += [lambda x: x.astype(int).tolist()]
        if all((x >= 0).all() for x in arrays.values()):
            conversions += [lambda x, t=t: x.astype(t) for t in (np.uint8, np.uint32, np.uint64)]
    for convert in conversions:
        got = answers(call({k: convert(x) for k, x in arrays.items()}))
        assert len(got) == len(reference) and all(
            same_bits(g, r) if r.dtype == np.float64 else (g == r).all() for g, r in zip(got, reference)), name


# ---- Python ints and exact rationals of any size --------------------------------------------------------------


def oracle(n: int, d: int) -> float:
    """n/d rounded to the nearest double, ties to even: CPython's int true division is correctly rounded (with
    gradual underflow and the sign on a zero); it raises OverflowError where the rounding overflows to ±inf."""
    try:
        return n / d
    except OverflowError:
        return math.inf if (n > 0) == (d > 0) else -math.inf


def bits(x: float) -> str:
    return float.hex(x)


def test_round_rational_to_double_of_huge_ints():
    assert rk.round_rational_to_double(Fraction(10**5000, 3)) == math.inf
    assert rk.round_rational_to_double(Fraction(-(10**5000), 3)) == -math.inf
    assert rk.round_rational_to_double(10**5000) == math.inf
    assert bits(rk.round_rational_to_double(Fraction(1, 10**5000))) == "0x0.0p+0"
    assert bits(rk.round_rational_to_double(Fraction(-1, 10**5000))) == "-0x0.0p+0"
    assert bits(rk.round_rational_to_double(-1, 10**5000)) == "-0x0.0p+0"
    assert bits(rk.round_rational_to_double(1, -(10**5000))) == "-0x0.0p+0"
    # Ties and near-ties scaled by a 5000-digit factor (two ints: the quotient is not reduced first).
    big = 10**5000 + 7
    assert rk.round_rational_to_double((2**53 + 1) * big, big) == 2.0**53  # a tie: to even
    assert rk.round_rational_to_double((2**53 + 3) * big, big) == 2.0**53 + 4
    assert rk.round_rational_to_double((2**54 + 3) * big, 2 * big) == 2.0**53 + 2  # 2^53 + 3/2: above the tie
    assert rk.round_rational_to_double(((2**53 + 1) * big + 1), big) == 2.0**53 + 2  # just above a tie
    assert rk.round_rational_to_double(((2**53 + 1) * big - 1), big) == 2.0**53  # just below it
    # The smallest subnormal, half of it (a tie: to 0) and just above the half, at 5000 digits.
    assert rk.round_rational_to_double(big, big * 2**1074) == 5e-324
    assert bits(rk.round_rational_to_double(big, big * 2**1075)) == "0x0.0p+0"
    assert rk.round_rational_to_double(big + 1, big * 2**1075) == 5e-324
    # The largest double, the overflow threshold 2^1024 − 2^970 (a tie: to even, which is inf) and below it.
    max_double = (2**53 - 1) * 2**971
    assert rk.round_rational_to_double(max_double * big, big) == sys.float_info.max
    assert rk.round_rational_to_double((2**1024 - 2**970) * big, big) == math.inf
    assert rk.round_rational_to_double((2**1024 - 2**970) * big - 1, big) == sys.float_info.max


def test_round_rational_to_double_equals_the_oracle_at_every_size():
    rng = np.random.default_rng(25)
    for _ in range(3000):
        bits_n, bits_d = (int(b) for b in rng.integers(1, 20000, 2))
        n = int.from_bytes(rng.bytes(bits_n // 8 + 1), "little") >> (7 - bits_n % 8) or 1
        d = int.from_bytes(rng.bytes(bits_d // 8 + 1), "little") >> (7 - bits_d % 8) or 1
        # Bring the quotient near the double range's interesting parts: 1, the subnormals, the overflow.
        shift = int(rng.choice([0, -1074, -1060, 1000, 1023, 1024])) + int(rng.integers(-60, 60))
        n, d = (n << shift, d) if shift >= 0 else (n, d << -shift)
        n = -n if rng.integers(2) else n
        d = -d if rng.integers(2) else d
        want = oracle(n, d)
        assert bits(rk.round_rational_to_double(n, d)) == bits(want), (n.bit_length(), d.bit_length(), shift)
        assert bits(rk.round_rational_to_double(Fraction(n, d))) == bits(want)


@pytest.fixture
def int_max_str_digits_640():
    """The smallest limit Python lets a program set: every conversion must still work under it."""
    old = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(640)
    yield
    sys.set_int_max_str_digits(old)


def test_exact_rationals_cross_under_the_smallest_digit_limit(int_max_str_digits_640):
    # Subnormal and huge coordinates make exact values of 600 to 1,900 decimal digits (see the digit counts).
    big, tiny = 1.7e308, 5e-324
    ray, plane = ((tiny, big, tiny), (big, tiny, 3e-320)), ((big, tiny, -big), (tiny, big, 1.1e-300))
    x = rk.intersect_exact_rational(ray, plane)
    assert max(x.exact_t.numerator.bit_length(), x.exact_t.denominator.bit_length()) > 4000  # 1,200 digits
    assert x.exact_t == x.num / x.den and oracle(x.exact_t.numerator, x.exact_t.denominator) == x.t
    tri_ray = ((tiny, 1.0, -big), (tiny, 3e-320, 1.0))
    tri = ((big, 1, tiny), (-tiny, big, 1e-300), (1e-310, -1e300, big))
    y = rk.intersect_exact_rational(tri_ray, tri)
    assert max(y.exact_t.numerator.bit_length(), y.exact_t.denominator.bit_length()) > 6000  # 1,800 digits
    assert y.exact_t == y.num / y.den and sum(y.exact_barycentric) == 1
    assert rk.round_rational_to_double(y.exact_t) == y.t
    assert rk.round_rational_to_double(Fraction(10**700 + 1, 10**699)) == 10.0
    assert rk.round_rational_to_double(-(10**700)) == -math.inf


# ---- load_mesh --------------------------------------------------------------------------------------------------

OCTAHEDRON_OFF = "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n" + "".join(
    f"3 {a} {b} {c}\n" for a, b, c in [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5),
                                       (0, 3, 5)])


def test_load_mesh_refuses_a_nul_in_the_path(tmp_path):
    good = tmp_path / "octahedron.off"
    good.write_text(OCTAHEDRON_OFF)
    assert len(rk.load_mesh(str(good))) == 8
    for path in (str(good) + "\0xyz", (str(good) + "\0xyz").encode(), "\0" + str(good)):
        # The NUL is shown as \0 where it is (the message is a C string: a raw NUL would end it).
        shown = r"octahedron\.off\\0xyz" if "xyz" in str(path) else r"^\\0/"
        with pytest.raises(rk.MeshFileError, match=shown + ".*: the path contains a NUL character, which no file name can$"):
            rk.load_mesh(path)
    assert issubclass(rk.MeshFileError, ValueError)  # like open()'s ValueError("embedded null byte")


def test_load_mesh_raises_mesh_file_error_for_every_bad_file(tmp_path):
    # An OBJ relative index −2^63 (the reader's own check is being fixed in io/src): whichever side catches it,
    # the reader or the kernel's validation of the loaded mesh, it is a MeshFileError naming the file.
    path = tmp_path / "overflow.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n")
    with pytest.raises(rk.MeshFileError, match=r"overflow\.obj"):
        rk.load_mesh(str(path))
