"""raykernel.dask: the batch functions over Dask arrays give the plain batch functions' answers bit for bit, on
Dask's threaded scheduler and on a distributed.LocalCluster of 2 worker processes; errors name the row over the
whole array; the scene is one node of the graph."""

import pathlib

import dask
import dask.array as da
import numpy as np
import pytest

import raykernel as rk
import raykernel.dask as rkd

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes"


def same(lazy, plain):
    """Every array field equal bit for bit (NaN where NaN); non-array fields None in the Dask result."""
    assert type(lazy) is type(plain)
    computed = dask.compute(*[f for f in lazy if f is not None])
    arrays = iter(computed)
    for name, l, p in zip(plain._fields, lazy, plain):
        if isinstance(p, np.ndarray):
            got = next(arrays)
            assert got.dtype == p.dtype and got.shape == p.shape, name
            assert np.array_equal(got.view(np.uint8), np.ascontiguousarray(p).view(np.uint8)), name
        else:
            assert l is None, name


@pytest.fixture(scope="module")
def mesh():
    return rk.load_mesh(SCENES / "icosphere-3.ply")


@pytest.fixture(scope="module")
def rays():
    rng = np.random.default_rng(20261129)
    n = 20_011  # not a multiple of the chunk sizes below
    origins = rng.normal(size=(n, 3)) * 3
    directions = -origins + rng.normal(size=(n, 3)) * 0.2
    return origins, directions


@pytest.mark.parametrize("chunks", [1_000, 7_777, 50_000])
def test_nearest_hit_on_a_mesh_is_the_batch_answer(mesh, rays, chunks):
    o, d = rays
    # Rays aimed at the vertices (up to the rounding of the difference): ties between the triangles around them.
    k = min(500, len(mesh.vertices))
    d = d.copy()
    d[:k] = mesh.vertices[:k] - o[:k]
    same(rkd.nearest_hit_batch(da.from_array(o, chunks=(chunks, 3)), d, mesh), rk.nearest_hit_batch(o, d, mesh))
    same(rkd.nearest_hit_batch(o, da.from_array(d, chunks=(chunks, 3)), mesh, rule="closed"),
         rk.nearest_hit_batch(o, d, mesh, rule="closed"))


def test_inside_planes_spheres_and_triangles_are_the_batch_answers(mesh, rays):
    o, d = rays
    chunked = da.from_array(o, chunks=(3_000, 3))
    same(rkd.inside_batch(chunked, mesh), rk.inside_batch(o, mesh))
    planes = rk.PlaneSet(np.eye(3), np.eye(3))
    same(rkd.nearest_hit_batch(chunked, d, planes), rk.nearest_hit_batch(o, d, planes))
    same(rkd.intersect_batch(chunked, d, (0, 0, 0), (0.1, 0.2, 0.3)), rk.intersect_batch(o, d, (0, 0, 0), (0.1, 0.2, 0.3)))
    same(rkd.relation_batch(chunked, d, o[::-1], d[::-1]), rk.relation_batch(o, d, o[::-1], d[::-1]))
    radii = np.abs(o[:, 0]) + 0.5
    same(rkd.intersect_sphere_batch(chunked, d, o[::-1], radii), rk.intersect_sphere_batch(o, d, o[::-1], radii))
    same(rkd.intersect_sphere_batch(chunked, d, (0, 0, 0), 1.0), rk.intersect_sphere_batch(o, d, (0, 0, 0), 1.0))
    a, b, c = (0, 0, 0), (1, 0, 0), (0, 1, 0)
    same(rkd.intersect_triangle_batch(chunked, d, a, b, c, rule="closed"),
         rk.intersect_triangle_batch(o, d, a, b, c, rule="closed"))
    same(rkd.relation_triangle_batch(chunked, d, o, o[::-1], d), rk.relation_triangle_batch(o, d, o, o[::-1], d))


def test_the_queries_after_the_first_hit_are_the_batch_answers(mesh, rays):
    """§8, §9 and §11 over Dask arrays: intervals one number or one per ray (chunked with the rays)."""
    o, d = rays
    chunked = da.from_array(o, chunks=(3_000, 3))
    rng = np.random.default_rng(8)
    t_max = rng.uniform(0.5, 3.0, size=len(o))
    t_max[::7] = np.inf
    same(rkd.occluded_batch(chunked, d, mesh), rk.occluded_batch(o, d, mesh))
    same(rkd.occluded_batch(chunked, d, mesh, t_min=0.5, t_max=t_max), rk.occluded_batch(o, d, mesh, t_min=0.5, t_max=t_max))
    t_min = np.where(np.isinf(t_max), 1.0, t_max / 2)
    lazy_t_min = da.from_array(t_min, chunks=5_000)  # a Dask array of other chunks: rechunked to the rays'
    same(rkd.crossings_batch(chunked, d, mesh, t_min=lazy_t_min, rule="closed"),
         rk.crossings_batch(o, d, mesh, t_min=t_min, rule="closed"))
    same(rkd.occluded_segment_batch(chunked, -o, mesh), rk.occluded_segment_batch(o, -o, mesh))
    same(rkd.closest_point_batch(chunked[:4_000], mesh, signed=True), rk.closest_point_batch(o[:4_000], mesh, signed=True))
    hit = rk.nearest_hit_batch(o, d, mesh)
    rows = np.flatnonzero(hit.triangle >= 0)[:5_000]
    tri = mesh.triangles[hit.triangle[rows]]
    a, b, c = (mesh.vertices[tri[:, k]] for k in range(3))
    lazy_o = da.from_array(o[rows], chunks=(1_000, 3))
    same(rkd.spawn_batch(lazy_o, d[rows], a, b, c, -d[rows]), rk.spawn_batch(o[rows], d[rows], a, b, c, -d[rows]))
    same(rkd.spawn_to_batch(lazy_o, d[rows], a, b, c, o[rows], format="binary32"),
         rk.spawn_to_batch(o[rows], d[rows], a, b, c, o[rows], format="binary32"))


def test_compute_writes_the_batch_answer_in_place(mesh, rays):
    """rkd.compute: the plain batch answer bit for bit (NumPy arrays, None where the batch gives stats), on the
    threaded and the synchronous scheduler; an invalid row raises as with dask.compute."""
    o, d = rays
    chunked = da.from_array(o, chunks=(3_000, 3))
    plain = rk.nearest_hit_batch(o, d, mesh)
    for kwargs in ({}, {"scheduler": "threads", "num_workers": 2}, {"scheduler": "sync"}):
        got = rkd.compute(rkd.nearest_hit_batch(chunked, d, mesh), **kwargs)
        assert type(got) is type(plain)
        for name, g, p in zip(plain._fields, got, plain):
            assert isinstance(g, np.ndarray) and g.dtype == p.dtype and g.shape == p.shape, name
            assert np.array_equal(g.view(np.uint8), np.ascontiguousarray(p).view(np.uint8)), name
    planes = rk.PlaneSet(np.eye(3), np.eye(3))
    got = rkd.compute(rkd.nearest_hit_batch(chunked, d, planes))
    assert got.stats is None and np.array_equal(got.t, rk.nearest_hit_batch(o, d, planes).t, equal_nan=True)
    bad = d.copy()
    bad[4_321] = np.inf
    with pytest.raises(ValueError, match=r"^ray 4321: "):
        rkd.compute(rkd.nearest_hit_batch(chunked, bad, mesh))


def test_an_invalid_row_is_named_over_the_whole_array_or_masked(mesh, rays):
    o, d = rays
    d = d.copy()
    d[12_345] = 0.0  # in the chunk starting at 12_000
    chunked = da.from_array(o, chunks=(3_000, 3))
    lazy = rkd.nearest_hit_batch(chunked, d, mesh)
    with pytest.raises(ValueError, match=r"^ray 12345: ") as caught:
        lazy.t.compute()
    with pytest.raises(ValueError) as plain:
        rk.nearest_hit_batch(o, d, mesh)
    assert str(caught.value) == str(plain.value)
    masked = rkd.nearest_hit_batch(chunked, d, mesh, errors="mask")
    same(masked, rk.nearest_hit_batch(o, d, mesh, errors="mask"))
    assert not masked.valid[12_345].compute()


def test_rows_must_agree_and_the_scene_is_one_graph_node(mesh, rays):
    o, d = rays
    with pytest.raises(ValueError, match="directions: 10 rows, but origins has"):
        rkd.nearest_hit_batch(o, d[:10], mesh)
    lazy = rkd.nearest_hit_batch(da.from_array(o, chunks=(2_000, 3)), d, mesh)
    graph = dict(lazy.t.__dask_graph__())
    shared = [k for k in graph if isinstance(k, str) and k.startswith("raykernel-shared-")]
    assert len(shared) == 1 and graph[shared[0]] is mesh


def test_on_a_local_cluster_of_two_worker_processes(mesh, rays):
    distributed = pytest.importorskip("distributed")
    o, d = rays
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        lazy = rkd.nearest_hit_batch(da.from_array(o, chunks=(2_500, 3)), d, mesh)
        computed = client.compute(list(lazy), sync=True)
        assert all(np.array_equal(x, y, equal_nan=True) for x, y in zip(rkd.compute(lazy), computed))
        plain = rk.nearest_hit_batch(o, d, mesh)
        for name, got, want in zip(plain._fields, computed, plain):
            assert np.array_equal(got, want, equal_nan=True), name
        assert len(client.scheduler_info()["workers"]) == 2
        # An error raised on a worker comes back with the whole array's row number.
        bad = d.copy()
        bad[7_501] = np.nan
        with pytest.raises(ValueError, match=r"^ray 7501: "):
            client.compute(rkd.nearest_hit_batch(da.from_array(o, chunks=(2_500, 3)), bad, mesh).t, sync=True)
        audit_example_on(client)


OCTAHEDRON_OBJ = """v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6
"""


def audit_example_on(client):
    """python/examples/dask_mesh_audit.py on the cluster: a closed octahedron does not leak, the same without one face
    does (the lines through the hole cross it once), and spawn's secondary rays never re-hit their triangle."""
    import importlib.util
    import tempfile

    path = pathlib.Path(__file__).resolve().parents[1] / "examples" / "dask_mesh_audit.py"
    spec = importlib.util.spec_from_file_location("dask_mesh_audit", path)
    audit = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(audit)
    with tempfile.TemporaryDirectory() as folder:
        (pathlib.Path(folder) / "closed.obj").write_text(OCTAHEDRON_OBJ)
        (pathlib.Path(folder) / "holed.obj").write_text(OCTAHEDRON_OBJ.replace("f 1 3 5\n", ""))
        (pathlib.Path(folder) / "notes.txt").write_text("not a mesh")
        rows = audit.audit_folder(folder, client, rays=3000, hits=100)
        audit.write_table(rows, pathlib.Path(folder) / "audit.csv")
        table = (pathlib.Path(folder) / "audit.csv").read_text().splitlines()
    by_name = {r["mesh"]: r for r in rows}
    assert sorted(by_name) == ["closed.obj", "holed.obj"]
    assert by_name["closed.obj"]["leaks"] == 0.0 and by_name["closed.obj"]["triangles"] == 8
    assert by_name["holed.obj"]["leaks"] > 0.01 and by_name["holed.obj"]["triangles"] == 7
    for r in rows:
        assert r["hits_audited"] == 100 and r["self_hits_spawn"] == 0.0
    assert table[0].split(",") == audit.FIELDS and len(table) == 3
