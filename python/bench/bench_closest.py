#!/usr/bin/env python3
"""raykernel's exact closest point against Open3D's RaycastingScene.compute_closest_points: speed, and how often
Open3D's distances differ from the exact ones and by how many ulps.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_closest.py [--points 100000] [--repeat 3]

Meshes: scenes/icosphere-3.ply, scenes/terrain-12.ply and scenes/cube-8.ply (exact dyadic vertices). Points: uniform in the mesh's box enlarged by half
(fixed seed). Each time is the best of --repeat runs, in wall time, on 2 threads (run it alone):

  raykernel       rk.closest_point_batch(points, mesh): the exact closest point, its squared distance and the
                  distance correctly rounded (threads=2)
  open3d          RaycastingScene.compute_closest_points (float32, Embree's closest-point query; its own threads),
                  then the distance |p − q| in float64 from its float32 points, as a user would compute it
  differ          the share of points whose Open3D distance is not the correctly rounded exact distance, the median
                  and largest difference in ulps of the exact distance, and the share where Open3D names a triangle
                  at another exact distance (its answer is not even a nearest triangle)

Open3D works in float32: its vertices and queries are the float64 values rounded to float32 (exact here for the
mesh, whose vertices have few bits; not for the points), so its error has two sources, both shown. This is a
measurement script, not a test: it prints a table (bench/README.md has the figures of one run).
"""

import argparse
import pathlib
import time

import numpy as np

import raykernel as rk

ROOT = pathlib.Path(__file__).resolve().parents[2]


def best(repeat, run):
    times = []
    result = None
    for _ in range(repeat):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return min(times), result


def ulps(x, exact):
    return np.abs(x - exact) / np.spacing(exact)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--points", type=int, default=100_000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    import open3d as o3d

    meshes = [(f, rk.load_mesh(ROOT / "scenes" / f)) for f in ("icosphere-3.ply", "terrain-12.ply", "cube-8.ply")]
    print(f"{'mesh':<18}{'triangles':>10}{'raykernel/s':>14}{'open3d/s':>12}{'ratio':>8}"
          f"{'differ %':>10}{'median ulps':>13}{'max ulps':>12}{'other tri %':>13}")
    for name, mesh in meshes:
        v = np.asarray(mesh.vertices)
        t = np.asarray(mesh.triangles)
        lo, hi = v.min(axis=0), v.max(axis=0)
        centre, half = (lo + hi) / 2, (hi - lo) * 0.75
        rng = np.random.default_rng(3)
        points = centre + half * rng.uniform(-1, 1, size=(args.points, 3))

        rk_time, exact = best(args.repeat, lambda: rk.closest_point_batch(points, mesh, threads=2))

        scene = o3d.t.geometry.RaycastingScene()
        scene.add_triangles(o3d.core.Tensor(v.astype(np.float32)), o3d.core.Tensor(t.astype(np.uint32)))
        query = o3d.core.Tensor(points.astype(np.float32))

        def open3d_run():
            answer = scene.compute_closest_points(query)
            q = answer["points"].numpy().astype(np.float64)
            return np.sqrt(((points - q) ** 2).sum(axis=1)), answer["primitive_ids"].numpy().astype(np.int64)

        o3d_time, (o3d_distance, o3d_triangle) = best(args.repeat, open3d_run)
        differ = o3d_distance != exact.distance
        u = ulps(o3d_distance, exact.distance)
        # Another triangle is wrong only when it is at another exact distance: check those exactly.
        other = 0
        for i in np.nonzero(o3d_triangle != exact.triangle)[0]:
            k = int(o3d_triangle[i])
            one = rk.Mesh(v[t[k]], np.array([[0, 1, 2]]))
            if rk.closest_point(points[i], one).squared_distance_exact != \
                    rk.closest_point(points[i], mesh).squared_distance_exact:
                other += 1
        print(f"{name:<18}{len(t):>10}{args.points / rk_time:>14,.0f}{args.points / o3d_time:>12,.0f}"
              f"{rk_time / o3d_time:>8.2f}{100 * differ.mean():>10.2f}{np.median(u[differ]) if differ.any() else 0:>13.3g}"
              f"{u.max():>12.3g}{100 * other / args.points:>13.3f}")


if __name__ == "__main__":
    main()
