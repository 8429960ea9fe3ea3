"""What raykernel answers after the first hit (docs/contract.md §8–§11), from Python: each line is a call on the
octahedron of scenes/octahedron.off (vertices ±1 on the axes) and what it returns. The README shows this output;
tools/docs.py regenerates it and the docs_outputs test checks that it is current.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/tour.py [scenes/octahedron.off]
"""

import sys

import numpy as np

import raykernel as rk

mesh = rk.load_mesh(sys.argv[1] if len(sys.argv) > 1 else "scenes/octahedron.off")
ray = ((2, 0, 0), (-1, 0, 0))  # along the x axis towards the vertex (1, 0, 0), met at t = 1
tri = ((0, 0, 0), (1, 0, 0), (0, 1, 0))
sphere = rk.Sphere((5, 0, 0), 1)
np.set_printoptions(precision=17)

CALLS = [
    # §8 intervals, any-hit, segments, all hits
    "rk.occluded(ray, mesh)",
    "rk.occluded(ray, mesh, t_max=0.5)",
    "rk.occluded(ray, mesh, t_min=1.0, t_max=1.0)",
    "rk.occluded_segment((0, 0, 0), (2, 0, 0), mesh)",
    "rk.occluded_segment((0, 0, 0), (0.25, 0.25, 0.5), mesh)",
    "rk.all_hits(((0.25, 0.25, 3), (0, 0, -1)), mesh)",
    "rk.occluded_batch([[2, 0, 0], [2, 0, 0]], [[-1, 0, 0], [-1, 0, 0]], mesh, t_max=[0.5, 1.0]).occluded",
    "rk.crossings_batch([[0.25, 0.25, 3], [0.25, 0.25, 0]], [[0, 0, -1], [0, 0, -1]], mesh).crossings",
    "rk.nearest_hit(ray, mesh, t_min=1.5)",
    # §9 spawning: an origin from which the new ray provably never meets the triangle it leaves
    "rk.spawn(((0.1, 0.2, 1), (0, 0, -3)), tri, (1, 1, 1))",
    "rk.spawn(((0.1, 0.2, 1), (0, 0, -3)), tri, (1, 1, 1), format='binary32').origin",
    "rk.spawn_to(((0.1, 0.2, 1), (0, 0, -3)), tri, (0.3, 0.3, -5))",
    "rk.spawn_batch([[0.1, 0.2, 1]], [[0, 0, -3]], [tri[0]], [tri[1]], [tri[2]], [[1, 1, 1]]).origin",
    # §10 spheres
    "rk.intersect(((0, 0, 0), (1, 0, 0)), sphere)",
    "rk.intersect(((0, 0.5, 0), (1, 0, 0)), sphere)",
    "rk.intersect_exact_rational(((0, 0.5, 0), (1, 0, 0)), sphere)",
    "rk.spawn((4, 0, 0), sphere, (-1, 0, 0))",
    "rk.nearest_hit(((0, 0, 0), (1, 0, 0)), rk.SphereSet([[5, 0, 0], [5, 0.5, 0]], [1, 0.5]), t_min=4.5)",
    "rk.occluded_segment((0, 0, 0), (4, 0, 0), rk.SphereSet([sphere]))",
    # §11 closest points, signed
    "rk.closest_point((1, 1, 1), mesh)",
    "rk.closest_point_batch([[2, 0, 0], [0, 0, 0.5]], mesh, signed=True).signed_distance",
]

for call in CALLS:
    print(f">>> {call}")
    print(repr(eval(call)))  # noqa: S307 - the calls above, shown as written
print(">>> help(rk.occluded_batch)  # first line: the stub's types")
print(rk.occluded_batch.__doc__.splitlines()[0])
