"""raykernel: exact ray–plane, ray–triangle, ray–sphere and ray–mesh intersection for binary64 inputs, from Python.

Every answer is exact for the doubles given (docs/contract.md §1): the relation comes from the exact signs
of ``den = d·n`` and ``num = (p − o)·n``, and ``t`` is the exact ``num/den`` rounded to the nearest double,
ties to even. The C++ kernel does the work; this package converts values and arrays.

    >>> import raykernel as rk
    >>> rk.intersect(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0)))
    Intersection(relation=<Relation.HIT: 'hit'>, t=0.1)
    >>> rk.intersect_exact_rational(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0))).exact_t
    Fraction(1, 10)
    >>> x = rk.intersect(((0, 0, 0), (1, 0, 0)), rk.Sphere((5, 0, 0), 1))   # roots 5 ∓ 1
    >>> x.origin, x.relation, x.t1, x.t2
    (<SphereOrigin.OUTSIDE: 'outside'>, <SphereRelation.CROSS: 'cross'>, 4.0, 6.0)

Scalar functions take a ray as ``(origin, direction)`` and a plane as ``(point, normal)``, a triangle as
``(a, b, c)`` (docs/contract.md §6; keyword ``rule="owned"|"closed"``) or a sphere as ``Sphere(center,
radius)`` (§10: the origin inside, on the surface or outside, the line missing, tangent or crossing, and both
roots correctly rounded; ``intersect_exact_rational`` gives them exactly as U ∓ √V), vectors as any sequence of
three numbers: ``intersect`` (certified), ``relation`` (the relation alone), ``intersect_exact`` (rational
reference), ``intersect_exact_rational`` (the exact values as Fractions), ``intersect_naive`` (the textbook
formula / Möller–Trumbore, no guarantee), ``intersect_traced``, ``validate``; ``nearest_hit`` /
``nearest_hit_exact`` over a ``PlaneSet``, a list of planes or a ``Mesh`` (``load_mesh(path)``: OBJ, PLY, STL,
OFF), ``nearest_hit_naive`` (the baseline) over either; ``inside`` / ``inside_exact(point, mesh)`` (docs/contract.md
§7: "inside", "outside" or "on-surface" by the exact winding number); ``closest_point`` /
``closest_point_exact(point, mesh)`` (§11: the exact closest point, its squared distance as a Fraction, the
distance correctly rounded); ``round_rational_to_double``.

Vectorized functions take (n, 3) arrays of real numbers (integer or floating dtypes, read as float64; complex,
bool, str, object, datetime, structured and masked arrays raise ``TypeError``) and loop in C++ with the GIL
released:
``intersect_batch`` / ``relation_batch(origins, directions, points, normals)``,
``intersect_triangle_batch`` / ``relation_triangle_batch(origins, directions, a, b, c)``,
``intersect_sphere_batch(origins, directions, centers, radii)`` and
``nearest_hit_batch(origins, directions, scene)``, ``inside_batch(points, mesh)``,
``closest_point_batch(points, mesh)``. Invalid input raises ``ValueError`` (``raykernel.InvalidInput``) naming the field, and for arrays
the row: "query 17: ray direction is the zero vector".

``raykernel.testing`` checks other code against raykernel (ulps, reports); ``raykernel.testing.hypothesis``
has Hypothesis strategies for the hard queries.
"""

from __future__ import annotations

from ._types import (
    Barycentric,
    ClosestFeature,
    ClosestPoint,
    ClosestPointArrays,
    CrossingArrays,
    ExactIntersection,
    ExactSphereIntersection,
    ExactTriangleIntersection,
    Intersection,
    IntersectionArrays,
    MeshHit,
    MeshHitArrays,
    MeshHits,
    NearestHit,
    NearestHitArrays,
    OcclusionArrays,
    Plane,
    PointLocation,
    PointLocationArrays,
    Ray,
    Relation,
    RelationArrays,
    SpawnArrays,
    SpawnedOrigin,
    Sphere,
    SphereClassification,
    SphereHit,
    SphereHitArrays,
    SphereIntersection,
    SphereIntersectionArrays,
    SphereOrigin,
    SphereRelation,
    Stage,
    TracedIntersection,
    TracedSphereIntersection,
    TracedTriangleIntersection,
    Triangle,
    TriangleClassification,
    TriangleClassificationArrays,
    TriangleIntersection,
    TriangleIntersectionArrays,
    TriangleLocation,
    TriangleRelation,
    TriangleRule,
    Vec3,
)
from ._raykernel import (  # noqa: E402  (the extension builds its results from ._types)
    INVALID_RELATION_CODE,
    InvalidInput,
    Mesh,
    MeshFileError,
    MeshFileNotFoundError,
    PlaneSet,
    SphereSet,
    all_hits,
    closest_point,
    closest_point_batch,
    closest_point_exact,
    crossings_batch,
    floating_point_environment_is_default,
    inside,
    inside_batch,
    inside_exact,
    intersect,
    intersect_batch,
    intersect_exact,
    intersect_exact_rational,
    intersect_naive,
    intersect_sphere_batch,
    intersect_traced,
    intersect_triangle_batch,
    load_mesh,
    mesh_bytes,
    nearest_hit,
    nearest_hit_batch,
    nearest_hit_exact,
    nearest_hit_naive,
    occluded,
    occluded_batch,
    occluded_segment,
    occluded_segment_batch,
    relation,
    relation_batch,
    relation_triangle_batch,
    round_rational_to_double,
    spawn,
    spawn_batch,
    spawn_to,
    spawn_to_batch,
    validate,
    version,
)

__version__ = version()

__all__ = [
    "Barycentric",
    "ClosestFeature",
    "ClosestPoint",
    "ClosestPointArrays",
    "CrossingArrays",
    "ExactIntersection",
    "ExactSphereIntersection",
    "ExactTriangleIntersection",
    "INVALID_RELATION_CODE",
    "Intersection",
    "IntersectionArrays",
    "InvalidInput",
    "Mesh",
    "MeshFileError",
    "MeshFileNotFoundError",
    "MeshHit",
    "MeshHitArrays",
    "MeshHits",
    "NearestHit",
    "NearestHitArrays",
    "OcclusionArrays",
    "Plane",
    "PlaneSet",
    "PointLocation",
    "PointLocationArrays",
    "Ray",
    "Relation",
    "RelationArrays",
    "SpawnArrays",
    "SpawnedOrigin",
    "Sphere",
    "SphereClassification",
    "SphereHit",
    "SphereHitArrays",
    "SphereIntersection",
    "SphereIntersectionArrays",
    "SphereOrigin",
    "SphereRelation",
    "SphereSet",
    "Stage",
    "TracedIntersection",
    "TracedSphereIntersection",
    "TracedTriangleIntersection",
    "Triangle",
    "TriangleClassification",
    "TriangleClassificationArrays",
    "TriangleIntersection",
    "TriangleIntersectionArrays",
    "TriangleLocation",
    "TriangleRelation",
    "TriangleRule",
    "Vec3",
    "all_hits",
    "closest_point",
    "closest_point_batch",
    "closest_point_exact",
    "crossings_batch",
    "floating_point_environment_is_default",
    "inside",
    "inside_batch",
    "inside_exact",
    "intersect",
    "intersect_batch",
    "intersect_exact",
    "intersect_exact_rational",
    "intersect_naive",
    "intersect_sphere_batch",
    "intersect_traced",
    "intersect_triangle_batch",
    "load_mesh",
    "mesh_bytes",
    "nearest_hit",
    "nearest_hit_batch",
    "nearest_hit_exact",
    "nearest_hit_naive",
    "occluded",
    "occluded_batch",
    "occluded_segment",
    "occluded_segment_batch",
    "relation",
    "relation_batch",
    "relation_triangle_batch",
    "round_rational_to_double",
    "save_mesh",
    "spawn",
    "spawn_batch",
    "spawn_to",
    "spawn_to_batch",
    "validate",
    "version",
]


def __dir__() -> list:
    """The API (``__all__``), the version and the submodules ``testing`` and ``dask``: not the modules the package is
    made of (``_raykernel``, ``_types``)."""
    return sorted(__all__ + ["__version__", "dask", "testing"])


def __getattr__(name: str):
    """``raykernel.testing`` and ``raykernel.dask`` on first use (``dask`` needs Dask installed)."""
    if name in ("testing", "dask"):
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'raykernel' has no attribute '{name}'")


def save_mesh(mesh: Mesh, path, *, format: "str | None" = None, encoding: str = "ascii") -> None:
    """Writes ``mesh`` to the file at ``path`` (str, bytes or ``os.PathLike``) exactly, in ``format`` ("obj", "ply",
    "stl", "off"; by default from the extension), as ``mesh_bytes`` gives it: ``load_mesh(path)`` reads back the
    same vertices and triangles bit for bit (STL: unshared vertices). Every write is checked: a full disk or a
    missing folder raises ``OSError``; an unknown extension or a format/encoding the format lacks, ``ValueError``."""
    import os

    name = os.fsdecode(os.fspath(path))
    if format is None:
        extension = os.path.splitext(name)[1].lower().lstrip(".")
        if extension not in ("obj", "ply", "stl", "off"):
            raise ValueError(f"save_mesh: {name}: cannot tell the format from the extension '.{extension}' "
                             "(give format='obj', 'ply', 'stl' or 'off')")
        format = extension
    data = mesh_bytes(mesh, format, encoding=encoding)
    with open(path, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
