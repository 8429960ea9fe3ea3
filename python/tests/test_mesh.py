"""Meshes from Python (docs/contract.md §7): Mesh, load_mesh, the nearest hit through the BVH against the
brute-force exact answer, inside against inside_exact; hand-derived hits and locations; errors naming the vertex,
triangle, point, file and line."""

import errno
import pickle

import numpy as np
import pytest

import raykernel as rk
from raykernel._raykernel import testkit

from test_arrays import same_bits

L = rk.TriangleLocation
P = rk.PointLocation


def test_hand_derived_hits_on_the_octahedron():
    octahedron = testkit.make_octahedron()  # vertices ±1 on the axes, 8 triangles, outward normals
    assert len(octahedron) == 8 and octahedron.vertices.shape == (6, 3)
    # Along +z from (1/4, 1/4, −5): the lower face with x, y > 0 is the plane x + y − z = 1, met at z = −1/2,
    # t = 4.5, strictly inside that face (barycentric weights 1/4 of +x, 1/4 of +y, 1/2 of −z).
    hit = rk.nearest_hit(((0.25, 0.25, -5), (0, 0, 1)), octahedron)
    assert hit.t == 4.5 and hit.location is L.INSIDE
    assert sorted(hit.barycentric) == [0.25, 0.25, 0.5]
    face = octahedron.triangle(hit.triangle)
    assert sorted(map(tuple, face)) == sorted([(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, -1.0)])
    # Along +z from (0, 0, −5): exactly through the vertex −z, t = 4. Four faces share it; the owned rule gives
    # it to exactly one of them, the closed rule to all four (the smallest index wins the exact tie).
    ray = ((0, 0, -5), (0, 0, 1))
    owned_hits = [k for k in range(8) if rk.intersect(ray, octahedron.triangle(k)).relation is rk.TriangleRelation.HIT
                  and rk.intersect(ray, octahedron.triangle(k)).t == 4.0]
    closed_hits = [k for k in range(8)
                   if rk.intersect(ray, octahedron.triangle(k), rule="closed").relation is rk.TriangleRelation.HIT
                   and rk.intersect(ray, octahedron.triangle(k), rule="closed").t == 4.0]
    assert len(owned_hits) == 1 and len(closed_hits) == 4
    assert rk.nearest_hit(ray, octahedron).triangle == owned_hits[0]
    closed = rk.nearest_hit(ray, octahedron, rule="closed")
    assert closed.triangle == min(closed_hits) and closed.t == 4.0 and closed.location.value.startswith("vertex")
    # Pointing away, and passing beside: no hit.
    assert rk.nearest_hit(((0, 0, -5), (0, 0, -1)), octahedron) is None
    assert rk.nearest_hit(((3, 3, -5), (0, 0, 1)), octahedron) is None


@pytest.mark.parametrize("rule", ["owned", "closed"])
def test_bvh_nearest_hit_equals_brute_force_exact(rule):
    rng = np.random.default_rng(7)
    for mesh in (testkit.make_icosphere(2), testkit.make_subdivided_cube(4)):
        # Rays from outside aimed near the centre, and rays through the cube's grid points exactly (edges and
        # vertices shared by several triangles: dyadic coordinates, axis-parallel directions).
        o = rng.uniform(-1, 1, (300, 3)) * 3
        d = -o + rng.uniform(-0.3, 0.3, (300, 3))
        grid = rng.integers(-4, 5, (100, 2)) / 4.0
        o2 = np.column_stack([grid, np.full(100, -5.0)])
        d2 = np.tile([0.0, 0.0, 1.0], (100, 1))
        o, d = np.vstack([o, o2]), np.vstack([d, d2])
        got = rk.nearest_hit_batch(o, d, mesh, rule=rule)
        exact = rk.nearest_hit_batch(o, d, mesh, rule=rule, path="exact")
        assert (got.triangle == exact.triangle).all() and same_bits(got.t, exact.t)
        assert same_bits(got.barycentric, exact.barycentric) and (got.location == exact.location).all()
        assert (got.triangle >= 0).sum() > 300  # most rays do hit
        for i in range(0, len(o), 37):  # scalar == vectorized
            one = rk.nearest_hit((o[i], d[i]), mesh, rule=rule)
            assert (one.triangle if one else -1) == got.triangle[i]
            assert one is None or (same_bits(one.t, got.t[i]) and one == rk.nearest_hit_exact((o[i], d[i]), mesh, rule=rule))


def test_nearest_hit_within_an_interval():
    """docs/contract.md §8: the nearest hit among the triangles whose exact t lies in [t_min, t_max]."""
    octahedron = testkit.make_octahedron()
    # Along −x from (2, 0, 0): the vertex +x at t = 1, the vertex −x at t = 3 (each shared by four faces).
    ray = ((2, 0, 0), (-1, 0, 0))
    assert rk.nearest_hit(ray, octahedron).t == 1.0
    far = rk.nearest_hit(ray, octahedron, t_min=1.5)
    assert far.t == 3.0 and far.location.value.startswith("vertex")
    assert rk.nearest_hit(ray, octahedron, t_min=1.0, t_max=1.0).t == 1.0  # a closed interval
    assert rk.nearest_hit(ray, octahedron, t_min=np.nextafter(1.0, 2.0), t_max=np.nextafter(3.0, 0.0)) is None
    assert rk.nearest_hit_exact(ray, octahedron, t_min=1.5) == far
    assert rk.nearest_hit_naive(ray, octahedron, t_max=0.5) is None
    with pytest.raises(ValueError, match="t_min is greater than t_max"):
        rk.nearest_hit(ray, octahedron, t_min=2, t_max=1)
    # Per-ray intervals in the batch: certified == exact, and each row the scalar answer.
    mesh = testkit.make_icosphere(2)
    rng = np.random.default_rng(30)
    o = rng.uniform(-1, 1, (400, 3)) * 3
    d = -o + rng.uniform(-0.3, 0.3, (400, 3))
    t_min = rng.uniform(0.0, 1.5, 400)
    t_max = t_min + rng.uniform(0.0, 1.0, 400)
    got = rk.nearest_hit_batch(o, d, mesh, t_min=t_min, t_max=t_max)
    exact = rk.nearest_hit_batch(o, d, mesh, t_min=t_min, t_max=t_max, path="exact")
    assert (got.triangle == exact.triangle).all() and same_bits(got.t, exact.t)
    whole = rk.nearest_hit_batch(o, d, mesh)
    inside = (got.triangle >= 0)
    assert inside.sum() > 50 and (got.t[inside] >= t_min[inside]).all() and (got.t[inside] <= t_max[inside]).all()
    assert (got.triangle != whole.triangle).sum() > 50  # the interval changes the answer often
    for i in range(0, 400, 23):
        one = rk.nearest_hit((o[i], d[i]), mesh, t_min=t_min[i], t_max=t_max[i])
        assert (one.triangle if one else -1) == got.triangle[i]


def test_the_closed_cube_is_watertight_under_the_owned_rule():
    cube = testkit.make_subdivided_cube(4)  # grid lines at multiples of 1/4 on each face
    tris = [cube.triangle(k) for k in range(len(cube))]
    a, b, c = (np.array([t[j] for t in tris]) for j in range(3))
    for x in np.arange(-1, 1.25, 0.25)[1:-1]:
        for y in np.arange(-1, 1.25, 0.25)[1:-1]:  # through grid vertices and edges of both z faces, exactly
            o = np.tile([x, y, -5.0], (len(tris), 1))
            d = np.tile([0.0, 0.0, 1.0], (len(tris), 1))
            r = rk.intersect_triangle_batch(o, d, a, b, c)
            assert (r.relation == rk.TriangleRelation.HIT.code).sum() == 2, (x, y)  # in once, out once


def test_mesh_from_arrays_and_its_errors():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)
    mesh = rk.Mesh(vertices, [[0, 1, 2]])
    assert same_bits(mesh.vertices, vertices) and mesh.triangles.tolist() == [[0, 1, 2]] and "1 triangles" in repr(mesh)
    assert rk.nearest_hit(((0.25, 0.25, -1), (0, 0, 1)), mesh) == rk.MeshHit(0, 1.0, L.INSIDE, (0.5, 0.25, 0.25))
    bad = vertices.copy()
    bad[1, 1] = np.nan
    with pytest.raises(ValueError, match="^mesh: vertex 1: y is not finite$"):
        rk.Mesh(bad, [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"^mesh: triangle 0: vertex index 5 \(triangles\[0, 2\]\) is out of range "
                                         r"\(3 vertices\)$"):
        rk.Mesh(vertices, [[0, 1, 5]])
    with pytest.raises(ValueError, match=r"^mesh: triangle 0: vertex index -1 \(triangles\[0, 1\]\) is out of range"):
        rk.Mesh(vertices, [[0, -1, 2]])
    with pytest.raises(ValueError, match=r"^triangles: expected an \(m, 3\) array"):
        rk.Mesh(vertices, [0, 1, 2])
    with pytest.raises(ValueError, match="^rule: only meshes have rules"):
        rk.nearest_hit(((0, 0, 0), (0, 0, 1)), [((0, 0, 1), (0, 0, 1))], rule="closed")
    # Möller–Trumbore on this ray is exact (every product and quotient is a small dyadic): t = 1 on triangle 0.
    naive = rk.nearest_hit_naive(((0.25, 0.25, -1), (0, 0, 1)), mesh)
    assert naive.triangle == 0 and naive.t == 1.0
    with pytest.raises(ValueError, match="^rule: the naive path has no rule"):
        rk.nearest_hit_batch(np.zeros((1, 3)), np.ones((1, 3)), mesh, rule="closed", path="naive")
    with pytest.raises(ValueError, match="zero"):
        rk.nearest_hit_naive(((0, 0, 0), (0, 0, 0)), mesh)


def test_mesh_batch_invalid_rays_raise_or_are_masked():
    mesh = testkit.make_octahedron()
    o = np.tile([0.25, 0.25, -5.0], (5, 1))
    d = np.tile([0.0, 0.0, 1.0], (5, 1))
    d[3] = 0
    with pytest.raises(rk.InvalidInput, match="^ray 3: ray direction is the zero vector$"):
        rk.nearest_hit_batch(o, d, mesh)
    masked = rk.nearest_hit_batch(o, d, mesh, errors="mask")
    assert masked.valid.tolist() == [True, True, True, False, True]
    assert masked.triangle[3] == -1 and masked.location[3] == rk.INVALID_RELATION_CODE
    assert (masked.t[masked.valid] == 4.5).all() and list(masked.locations()[:1]) == ["inside"]


def test_load_mesh_reads_exactly_and_names_file_and_line(tmp_path):
    path = tmp_path / "square.obj"
    # 0.1 and 1e-310 (subnormal) must be read correctly rounded; the quad is fanned into (0, 1, 2), (0, 2, 3).
    path.write_text("v 0 0 0\nv 0.1 0 0\nv 0.1 1e-310 0\nv 0 1 0\nf 1 2 3 4\n")
    mesh = rk.load_mesh(str(path))
    assert mesh.vertices[1, 0] == 0.1 and mesh.vertices[2, 1] == 1e-310
    assert mesh.triangles.tolist() == [[0, 1, 2], [0, 2, 3]]
    broken = tmp_path / "broken.obj"
    broken.write_text("v 0 0 0\nv 1 0 0\nf 1 2\n")
    with pytest.raises(rk.MeshFileError, match=r"broken\.obj:3: "):
        rk.load_mesh(str(broken))
    with pytest.raises(ValueError, match="missing.obj"):
        rk.load_mesh(str(tmp_path / "missing.obj"))


def test_the_gil_is_released_during_a_mesh_batch():
    from test_arrays import longest_pause_of_this_thread_while

    mesh = testkit.make_icosphere(1)
    rng = np.random.default_rng(3)
    o = rng.uniform(-1, 1, (400, 3)) * 3
    d = -o
    longest, total = longest_pause_of_this_thread_while(
        lambda: rk.nearest_hit_batch(o, d, mesh, path="exact", threads=1))
    assert total > 0.05, "the batch was too short to tell"
    assert longest < total / 4, f"this thread stopped for {longest:.3f} s of a {total:.3f} s batch"


def test_mesh_naive_path_is_the_baseline_and_usually_agrees():
    # No guarantee, so no equality: it answers every ray of a batch, and on rays aimed at the middle of a
    # icosphere's triangles (far from any edge) it finds the certified triangle.
    mesh = testkit.make_icosphere(2)
    rng = np.random.default_rng(11)
    o = rng.uniform(-1, 1, (200, 3)) * 3
    d = -o
    naive = rk.nearest_hit_batch(o, d, mesh, path="naive")
    certified = rk.nearest_hit_batch(o, d, mesh)
    assert naive.valid.all() and (naive.triangle >= 0).all()
    assert (naive.triangle == certified.triangle).mean() > 0.95
    for i in range(0, 200, 41):
        one = rk.nearest_hit_naive((o[i], d[i]), mesh)
        assert one.triangle == naive.triangle[i] and same_bits(one.t, naive.t[i])


# ---- inside (docs/contract.md §7) ------------------------------------------------------------------------------

BELOW_HALF = np.nextafter(0.5, 0.0)  # 1/2 − 2^−54
ABOVE_HALF = np.nextafter(0.5, 1.0)  # 1/2 + 2^−53


def octahedron_cases():
    """The octahedron of testkit is |x| + |y| + |z| ≤ 1 (vertices ±1 on the axes): a point is on its surface iff
    the exact sum of |coordinates| is 1, inside iff it is below 1. Each expected answer is that sum, by hand."""
    return [
        ((0, 0, 0), P.INSIDE),  # the centre: sum 0
        ((0.2, -0.2, 0.2), P.INSIDE),  # sum 0.6
        ((5, 0, 0), P.OUTSIDE),  # outside the bounding box
        ((0.5, 0.5, 0.5), P.OUTSIDE),  # inside the bounding box, sum 1.5
        ((1, 0, 0), P.ON_SURFACE),  # a vertex (shared by four triangles)
        ((0, -1, 0), P.ON_SURFACE),  # another vertex
        ((0.5, 0.5, 0), P.ON_SURFACE),  # the midpoint of the edge from +x to +y
        ((0.25, 0.25, 0.5), P.ON_SURFACE),  # a face point: 1/4 + 1/4 + 1/2 = 1
        ((-0.25, 0.25, -0.5), P.ON_SURFACE),  # a face point of another face
        # One ulp off the face: 1/4 + 1/4 + (1/2 − 2^−54) = 1 − 2^−54 < 1, inside — though the double sum
        # rounds to exactly 1.0 (ties to even); 1/2 + 2^−53 makes 1 + 2^−53 > 1, outside.
        ((0.25, 0.25, BELOW_HALF), P.INSIDE),
        ((0.25, 0.25, ABOVE_HALF), P.OUTSIDE),
        ((0.5, 0.5, 2.0 ** -1074), P.OUTSIDE),  # the edge midpoint lifted by the smallest subnormal
    ]


@pytest.mark.parametrize("point, expected", octahedron_cases())
def test_inside_hand_derived_on_the_octahedron(point, expected):
    octahedron = testkit.make_octahedron()
    assert rk.inside(point, octahedron) is expected
    assert rk.inside_exact(point, octahedron) is expected
    # Inward normals (every triangle reversed): winding number −1 instead of +1, still inside.
    v, t = octahedron.vertices, octahedron.triangles
    inverted = rk.Mesh(v, t[:, ::-1])
    assert rk.inside(point, inverted) is expected and rk.inside_exact(point, inverted) is expected


def test_inside_batch_hand_derived_on_the_octahedron():
    octahedron = testkit.make_octahedron()
    points = np.array([p for p, _ in octahedron_cases()], dtype=float)
    expected = [e.code for _, e in octahedron_cases()]
    for path in ("certified", "exact"):
        got = rk.inside_batch(points, octahedron, path=path)
        assert got.location.tolist() == expected and got.valid.all()
        assert list(got.locations()) == [e.value for _, e in octahedron_cases()]


def test_inside_equals_inside_exact_on_testkit_meshes():
    rng = np.random.default_rng(5)
    for mesh in (testkit.make_icosphere(2), testkit.make_subdivided_cube(4), testkit.make_octahedron()):
        # Random points around the mesh, and points on a grid of step 1/8: on the cube's faces, edges and
        # vertices exactly (its grid lines are multiples of 1/4), on the octahedron's faces, inside and outside.
        random = rng.uniform(-1.3, 1.3, (300, 3))
        grid = rng.integers(-10, 11, (300, 3)) / 8.0
        points = np.vstack([random, grid])
        got = rk.inside_batch(points, mesh)
        exact = rk.inside_batch(points, mesh, path="exact")
        assert (got.location == exact.location).all()
        counts = np.bincount(got.location, minlength=3)
        assert counts[P.INSIDE.code] > 0 and counts[P.OUTSIDE.code] > 0
        for i in range(0, len(points), 29):  # scalar == vectorized, certified == exact
            assert rk.inside(points[i], mesh).code == got.location[i] == rk.inside_exact(points[i], mesh).code
    cube_grid = rk.inside_batch(np.array([[1, 0.25, -0.5], [0.75, 1, 1], [1, 1, 1], [0.75, 0.5, 0.25]]),
                                testkit.make_subdivided_cube(4))
    # A face point, an edge point, a corner of the cube [−1, 1]^3, and an interior point (all |coordinates| < 1).
    assert list(cube_grid.locations()) == ["on-surface", "on-surface", "on-surface", "inside"]


def test_inside_errors_name_the_point_and_row():
    mesh = testkit.make_octahedron()
    with pytest.raises(ValueError, match="^point x is not finite$"):
        rk.inside((np.nan, 0, 0), mesh)
    with pytest.raises(ValueError, match="^point z is not finite$"):
        rk.inside_exact((0, 0, np.inf), mesh)
    with pytest.raises(ValueError, match="^point: expected a sequence of 3 numbers, got a sequence of 2 items$"):
        rk.inside((0, 0), mesh)
    points = np.zeros((5, 3))
    points[2, 1] = np.nan
    with pytest.raises(rk.InvalidInput, match="^point 2: y is not finite$"):
        rk.inside_batch(points, mesh)
    masked = rk.inside_batch(points, mesh, errors="mask", path="exact")
    assert masked.valid.tolist() == [True, True, False, True, True]
    assert masked.location[2] == rk.INVALID_RELATION_CODE and list(masked.locations()) == ["inside"] * 2 + ["invalid"] + ["inside"] * 2
    with pytest.raises(ValueError, match="^path: expected 'certified' or 'exact'"):
        rk.inside_batch(points, mesh, path="naive")


def test_the_gil_is_released_during_an_inside_batch():
    from test_arrays import longest_pause_of_this_thread_while

    mesh = testkit.make_icosphere(1)
    points = np.random.default_rng(4).uniform(-1.2, 1.2, (400, 3))
    longest, total = longest_pause_of_this_thread_while(lambda: rk.inside_batch(points, mesh, path="exact", threads=1))
    assert total > 0.05, "the batch was too short to tell"
    assert longest < total / 4, f"this thread stopped for {longest:.3f} s of a {total:.3f} s batch"


def test_occluded_rays_with_intervals_and_segments_on_the_octahedron():
    """docs/contract.md §8, hand-derived: the vertex +x at t = 1 from (2, 0, 0) along −x; t = 1/3 along −3x, just
    above RN(1/3); segments through a vertex, ending exactly on a face, and invalid input named."""
    octahedron = testkit.make_octahedron()
    ray = ((2, 0, 0), (-1, 0, 0))
    assert rk.occluded(ray, octahedron)
    assert rk.occluded(ray, octahedron, t_min=1.0, t_max=1.0)
    assert not rk.occluded(ray, octahedron, t_max=np.nextafter(1.0, 0))
    assert not rk.occluded(ray, octahedron, t_min=np.nextafter(3.0, 4), rule="closed")  # the exit is at t = 3
    third = 1.0 / 3.0
    slow = ((2, 0, 0), (-3, 0, 0))
    from fractions import Fraction
    assert Fraction(third) < Fraction(1, 3) < Fraction(float(np.nextafter(third, 1)))
    for path in ("certified", "exact"):
        assert not rk.occluded(slow, octahedron, t_max=third, path=path)
        assert rk.occluded(slow, octahedron, t_max=float(np.nextafter(third, 1)), path=path)
        assert rk.occluded_segment((0, 0, 0), (2, 0, 0), octahedron, path=path)
        assert not rk.occluded_segment((0, 0, 0), (0.25, 0.25, 0.5), octahedron, path=path)  # ends on a face
        assert rk.occluded_segment((0, 0, 0), (0.25, 0.25, float(np.nextafter(0.5, 1))), octahedron, path=path)
    with pytest.raises(ValueError, match="t_min is greater than t_max"):
        rk.occluded(ray, octahedron, t_min=2.0, t_max=1.0)
    with pytest.raises(ValueError, match="t_min is NaN"):
        rk.occluded(ray, octahedron, t_min=float("nan"))
    with pytest.raises(ValueError, match="segment endpoints are equal"):
        rk.occluded_segment((1, 2, 3), (1, 2, 3), octahedron)


def test_load_mesh_takes_path_likes_and_its_errors_carry_their_parts(tmp_path):
    good = tmp_path / "tetra.off"
    good.write_text("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    for path in (good, str(good), bytes(good)):
        assert len(rk.load_mesh(path)) == 4
    broken = tmp_path / "broken.obj"
    broken.write_text("v 0 0 0\nv 1 0 0\nf 1 2\n")
    with pytest.raises(rk.MeshFileError) as caught:
        rk.load_mesh(broken)
    e = caught.value
    assert (e.file, e.line, e.byte_offset) == (str(broken), 3, None)
    assert str(e) == f"{broken}:3: {e.reason}" and "3 vertices" in e.reason
    # A binary STL cut short: the error is at a byte offset (84-byte header and count, then 50 bytes per facet).
    stl = tmp_path / "short.stl"
    stl.write_bytes(b"\0" * 80 + (2).to_bytes(4, "little") + b"\0" * 60)
    with pytest.raises(rk.MeshFileError) as caught:
        rk.load_mesh(stl)
    assert caught.value.line is None and caught.value.byte_offset is not None and caught.value.file == str(stl)
    with pytest.raises(TypeError):
        rk.load_mesh(3)


def test_a_missing_file_is_file_not_found_and_a_mesh_file_error(tmp_path):
    missing = tmp_path / "nowhere" / "mesh.ply"
    with pytest.raises(FileNotFoundError) as caught:
        rk.load_mesh(missing)
    e = caught.value
    assert isinstance(e, rk.MeshFileError) and isinstance(e, rk.MeshFileNotFoundError)
    assert e.errno == errno.ENOENT and e.filename == str(missing) and e.file == str(missing)
    assert str(e).startswith(f"{missing}: ") and e.line is None
    # A directory exists: it is not "not found" (the reader's own error).
    with pytest.raises(rk.MeshFileError) as caught:
        rk.load_mesh(tmp_path)
    assert not isinstance(caught.value, FileNotFoundError)


def test_meshes_plane_sets_and_file_errors_pickle_exactly(tmp_path):
    vertices = np.array([[0.1, 0.2, 0.3], [1, 0, 0], [0, 1, 0], [0, 0, 1 + 2**-52]])
    mesh = rk.Mesh(vertices, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    copy = pickle.loads(pickle.dumps(mesh))
    assert same_bits(copy.vertices, mesh.vertices) and np.array_equal(copy.triangles, mesh.triangles)
    rays = np.array([[0.3, 0.3, 0.3, -1, -1, -1.5], [2, 2, 2, -1, -1, -1]])
    assert [rk.nearest_hit(((r[:3]), (r[3:])), copy) for r in rays] == [rk.nearest_hit(((r[:3]), (r[3:])), mesh)
                                                                        for r in rays]
    planes = rk.PlaneSet([((0, 0, 0.1), (0, 0, 1)), ((0, 0, 0.1), (0, 0, 3)), ((1, 0, 0), (1, 0, 0))])
    planes_copy = pickle.loads(pickle.dumps(planes))
    assert same_bits(planes_copy.points, planes.points) and same_bits(planes_copy.normals, planes.normals)
    assert list(planes_copy.candidates) == list(planes.candidates) == [0, 2]
    broken = tmp_path / "broken.obj"
    broken.write_text("v 0 0 0\nf 1 1 1 x\n")
    with pytest.raises(rk.MeshFileError) as caught:
        rk.load_mesh(broken)
    again = pickle.loads(pickle.dumps(caught.value))
    assert type(again) is rk.MeshFileError
    assert (str(again), again.file, again.line, again.reason) == (str(caught.value), str(broken), 2, caught.value.reason)


def test_load_mesh_reads_gltf_and_glb_exactly(tmp_path):
    import base64
    import json
    import struct

    positions = [(0.1, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    buffer = b"".join(struct.pack("<3f", *p) for p in positions) + struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    document = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(buffer)}],
                "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                                {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
                "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                              {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
                "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}]}
    binary = json.dumps(document).encode()
    binary += b" " * (-len(binary) % 4)
    glb = (b"glTF" + struct.pack("<II", 2, 12 + 8 + len(binary) + 8 + len(buffer)) + struct.pack("<I", len(binary))
           + b"JSON" + binary + struct.pack("<I", len(buffer)) + b"BIN\0" + buffer)
    (tmp_path / "tetra.glb").write_bytes(glb)
    document["buffers"][0]["uri"] = "tetra.bin"  # an external buffer beside the .gltf
    (tmp_path / "tetra.bin").write_bytes(buffer)
    (tmp_path / "tetra.gltf").write_text(json.dumps(document))
    expected = np.array(positions, dtype=np.float32).astype(np.float64)  # 0.1f widened: 0.100000001490116...
    for name in ("tetra.glb", "tetra.gltf"):
        mesh = rk.load_mesh(tmp_path / name)
        assert same_bits(mesh.vertices, expected) and mesh.triangles.tolist() == [[0, 1, 2], [0, 2, 3]]
    document["nodes"], document["scenes"] = [{"mesh": 0, "rotation": [0, 0, 1, 0]}], [{"nodes": [0]}]
    (tmp_path / "rotated.gltf").write_text(json.dumps(document))
    with pytest.raises(rk.MeshFileError, match="node 0: it rotates") as caught:
        rk.load_mesh(tmp_path / "rotated.gltf")
    assert caught.value.file == str(tmp_path / "rotated.gltf") and caught.value.line is None


def test_save_mesh_round_trips_exactly(tmp_path):
    """save_mesh writes every format so that load_mesh reads back the same doubles bit for bit (STL: unshared
    vertices); a bad extension, format or encoding is a ValueError; a write into a missing folder an OSError."""
    vertices = np.array([[0.1, 1e-300, -0.0], [1 / 3, 2.5, 5e-324], [1e300, -7.0, 0.2], [3.0, 0.0, 1.0]])
    triangles = np.array([[0, 1, 2], [0, 2, 3]])
    mesh = rk.Mesh(vertices, triangles)
    for name, kwargs in [("m.obj", {}), ("m.off", {}), ("m.ply", {}), ("b.ply", {"encoding": "binary"}),
                         ("be.ply", {"encoding": "binary_big_endian"}), ("m.stl", {})]:
        path = tmp_path / name
        rk.save_mesh(mesh, path, **kwargs)
        back = rk.load_mesh(path)
        if name.endswith(".stl"):
            assert np.array_equal(back.vertices.view(np.uint64), vertices[triangles.ravel()].view(np.uint64)), name
        else:
            assert np.array_equal(back.vertices.view(np.uint64), vertices.view(np.uint64)), name
            assert np.array_equal(back.triangles, triangles), name
    with pytest.raises(ValueError, match="extension"):
        rk.save_mesh(mesh, tmp_path / "m.xyz")
    with pytest.raises(ValueError):
        rk.save_mesh(mesh, tmp_path / "m.obj", encoding="binary")
    with pytest.raises(ValueError):
        rk.save_mesh(mesh, tmp_path / "m.stl", encoding="binary")  # 0.1 is not a float
    with pytest.raises(ValueError, match="glTF"):
        rk.mesh_bytes(mesh, "gltf")
    with pytest.raises(OSError):
        rk.save_mesh(mesh, tmp_path / "missing" / "m.obj")
