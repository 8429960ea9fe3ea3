#!/usr/bin/env python3
"""Audit every mesh of a folder on a Dask cluster: watertight leaks and self-hits of secondary rays, exactly.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/dask_mesh_audit.py scenes \\
        [--scheduler tcp://HOST:8786 | --workers 2] [--rays 20000] [--hits 500] [--out audit.csv] [--plot audit.png]

For each mesh file (OBJ, PLY, STL, OFF, glTF) one task on the cluster loads it (the file must be readable from
the workers: a shared folder) and measures, with raykernel's exact queries:

  leaks        random lines from outside the mesh's bounding box through it (rays from a sphere around the box to
               infinity): the share whose signed count of owned crossings is not 0 (``crossings_batch``). For a
               closed, consistently oriented mesh whose shared vertices are the same doubles it is 0 — a nonzero
               share means holes, T-junctions or flipped triangles;
  double hits  the share of those rays that meet more triangles under the closed rule than under the owned one
               (rays through shared edges and vertices: a closed-rule renderer counts those twice);
  self-hits    for rays that hit the mesh, a secondary ray back towards the eye (direction −d) started at the hit
               point rounded to doubles — what a renderer does without an offset — and at ``spawn``'s origin (docs/
               contract.md §9): the share whose first hit is the triangle it leaves (for the rounded point, the
               exact nearest hit finds it; for spawn it is 0 by construction — the audit checks it).

It writes one table (CSV: one row per mesh) and, when matplotlib is installed, one plot (the three shares per
mesh, log scale). Without --scheduler it starts a ``distributed.LocalCluster`` of --workers processes. On a real
cluster: ``dask scheduler`` on one machine, ``dask worker tcp://HOST:8786`` on each of the others (with raykernel
installed and the folder mounted), then this script with ``--scheduler tcp://HOST:8786``.
"""

import argparse
import csv
import pathlib
import sys

import numpy as np

MESH_SUFFIXES = {".obj", ".ply", ".stl", ".off", ".gltf", ".glb"}


def audit_mesh(path, rays, hits, seed):
    """One mesh's figures (runs on a worker)."""
    import raykernel as rk

    mesh = rk.load_mesh(path)
    v = np.asarray(mesh.vertices)
    t = np.asarray(mesh.triangles)
    lo, hi = v.min(axis=0), v.max(axis=0)
    centre, extent = (lo + hi) / 2, np.linalg.norm(hi - lo) + 1.0
    rng = np.random.default_rng(seed)
    u = rng.normal(size=(rays, 3))
    origins = centre + extent * u / np.linalg.norm(u, axis=1, keepdims=True)
    targets = lo + (hi - lo) * rng.uniform(size=(rays, 3))
    directions = targets - origins
    owned = rk.crossings_batch(origins, directions, mesh, threads=1)
    closed = rk.crossings_batch(origins, directions, mesh, rule="closed", threads=1)
    leaks = float(np.mean(owned.crossings != 0))
    double_hits = float(np.mean(closed.hits > owned.hits))

    first = rk.nearest_hit_batch(origins, directions, mesh, threads=1)
    hit_rows = np.nonzero(first.triangle >= 0)[0][:hits]
    rounded_self = spawned_self = 0
    for i in hit_rows:
        k = int(first.triangle[i])
        o, d = origins[i], directions[i]
        back = -d
        point = o + first.t[i] * d  # the hit point rounded to doubles, as a renderer computes it
        again = rk.nearest_hit((point, back), mesh)
        rounded_self += again is not None and again.triangle == k
        tri = tuple(map(tuple, v[t[k]]))
        origin = rk.spawn((o, d), tri, back).origin
        again = rk.nearest_hit((origin, back), mesh)
        spawned_self += again is not None and again.triangle == k
    n = max(len(hit_rows), 1)
    return {
        "mesh": pathlib.Path(path).name,
        "triangles": int(len(t)),
        "rays": rays,
        "leaks": leaks,
        "double_hits": double_hits,
        "hits_audited": int(len(hit_rows)),
        "self_hits_rounded": rounded_self / n,
        "self_hits_spawn": spawned_self / n,
    }


def audit_folder(folder, client, rays, hits, seed=1):
    """The table: one row per mesh file of `folder`, computed on `client`'s cluster (one task per mesh)."""
    import dask

    files = sorted(str(p) for p in pathlib.Path(folder).iterdir() if p.suffix.lower() in MESH_SUFFIXES)
    tasks = [dask.delayed(audit_mesh)(f, rays, hits, seed) for f in files]
    return list(client.compute(tasks, sync=True)) if client is not None else list(dask.compute(*tasks))


FIELDS = ["mesh", "triangles", "rays", "leaks", "double_hits", "hits_audited", "self_hits_rounded", "self_hits_spawn"]


def write_table(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)


def write_plot(rows, path):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("dask_mesh_audit: matplotlib is not installed: no plot", file=sys.stderr)
        return False
    names = [r["mesh"] for r in rows]
    x = np.arange(len(rows))
    fig, ax = plt.subplots(figsize=(max(6, 1.2 * len(rows)), 5))
    floor = 1e-6  # zero shares are drawn at the floor
    for j, (key, label) in enumerate([("leaks", "leaking lines (owned rule)"), ("double_hits", "double hits (closed rule)"),
                                      ("self_hits_rounded", "self-hits, rounded hit point"),
                                      ("self_hits_spawn", "self-hits, spawn")]):
        ax.bar(x + (j - 1.5) * 0.2, [max(r[key], floor) for r in rows], 0.2, label=label)
    ax.set_yscale("log")
    ax.set_ylim(floor / 2, 1.5)
    ax.set_xticks(x, names, rotation=20, ha="right")
    ax.set_ylabel(f"share (0 drawn at {floor:g})")
    ax.set_title("raykernel mesh audit (exact)")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.25), ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    return True


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    parser.add_argument("--rays", type=int, default=20000)
    parser.add_argument("--hits", type=int, default=500)
    parser.add_argument("--out", default="audit.csv")
    parser.add_argument("--plot", default="audit.png")
    args = parser.parse_args(argv)
    from distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
        cluster = None
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        rows = audit_folder(args.folder, client, args.rays, args.hits)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    write_table(rows, args.out)
    for r in rows:
        print(f"{r['mesh']:<24}{r['triangles']:>9} triangles  leaks {100 * r['leaks']:.3f} %  double hits "
              f"{100 * r['double_hits']:.3f} %  self-hits {100 * r['self_hits_rounded']:.1f} % rounded, "
              f"{100 * r['self_hits_spawn']:.1f} % spawn")
    print(f"table: {args.out}")
    if write_plot(rows, args.plot):
        print(f"plot: {args.plot}", file=sys.stderr)  # stderr: the plot needs matplotlib, the table does not
    return 0


if __name__ == "__main__":
    sys.exit(main())
