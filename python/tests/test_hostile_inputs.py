"""Hostile inputs (issue 25): values NumPy or Python would silently change on the way into the kernel are refused,
naming the argument and why, and values that are right are answered — bit for bit as before.

- Mesh triangles: integer arrays only, each index checked against [0, vertex count) without wrapping.
- Every vectorized entry point: real numeric arrays only (integer or floating dtypes); complex, str, bytes, object,
  datetime, timedelta, structured and bool arrays, and masked arrays (whose masks would be ignored), raise
  TypeError naming the argument and the dtype.
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
