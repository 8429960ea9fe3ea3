# Type stubs of the compiled extension raykernel._raykernel (python/src/*.cpp). The docstrings are in the
# extension (help(raykernel.intersect)); tests/test_stubs.py checks that these names and parameters are the
# extension's.
import os
from fractions import Fraction
from typing import Callable, Iterator, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from ._types import (
    ClosestPoint,
    ClosestPointArrays,
    CrossingArrays,
    MeshHits,
    OcclusionArrays,
    SpawnArrays,
    ExactIntersection,
    ExactSphereIntersection,
    ExactTriangleIntersection,
    Intersection,
    IntersectionArrays,
    MeshHit,
    MeshHitArrays,
    NearestHit,
    NearestHitArrays,
    Plane,
    PlaneLike,
    PointLocation,
    PointLocationArrays,
    Ray,
    RayLike,
    Relation,
    RelationArrays,
    SpawnedOrigin,
    RuleLike,
    Sphere,
    SphereClassification,
    SphereHit,
    SphereHitArrays,
    SphereIntersection,
    SphereIntersectionArrays,
    SphereLike,
    TracedIntersection,
    TracedSphereIntersection,
    TracedTriangleIntersection,
    TriangleClassification,
    TriangleClassificationArrays,
    TriangleIntersection,
    TriangleIntersectionArrays,
    Triangle,
    TriangleLike,
    Vec3Like,
)

__version__: str
INVALID_RELATION_CODE: int

class InvalidInput(ValueError): ...
class MeshFileError(ValueError):
    file: Optional[str]
    line: Optional[int]
    byte_offset: Optional[int]
    reason: str
    def __init__(
        self,
        message: str,
        file: Optional[str] = ...,
        line: Optional[int] = ...,
        byte_offset: Optional[int] = ...,
        reason: Optional[str] = ...,
    ) -> None: ...

class MeshFileNotFoundError(MeshFileError, FileNotFoundError): ...

# (n, 3), or (3,) where one plane or triangle is allowed: real numbers, an integer or floating dtype (lists of
# numbers too), read as float64. Complex, bool, str, bytes, object, datetime64, timedelta64, structured arrays and
# numpy.ma.MaskedArray (its mask would be ignored) raise TypeError naming the argument and the dtype.
ArrayLike3 = npt.ArrayLike

# The scalar queries take a plane (point, normal), a triangle (a, b, c) or a Sphere (only that type: a bare pair is
# a plane) as `primitive`; the triangle options (rule "owned" or "closed", t, barycentric) are keyword-only and for
# triangles only. The Sphere overloads come first: a Sphere is also a pair.
def validate(ray: RayLike, primitive: Union[SphereLike, PlaneLike, TriangleLike]) -> Optional[str]: ...
@overload
def intersect(ray: RayLike, primitive: SphereLike) -> SphereIntersection: ...
@overload
def intersect(ray: RayLike, primitive: PlaneLike) -> Intersection: ...
@overload
def intersect(
    ray: RayLike, primitive: TriangleLike, *, rule: Optional[RuleLike] = None, t: bool = True, barycentric: bool = True
) -> TriangleIntersection: ...
@overload
def relation(ray: RayLike, primitive: SphereLike) -> SphereClassification: ...
@overload
def relation(ray: RayLike, primitive: PlaneLike) -> Relation: ...
@overload
def relation(ray: RayLike, primitive: TriangleLike, *, rule: Optional[RuleLike] = None) -> TriangleClassification: ...
@overload
def intersect_exact(ray: RayLike, primitive: SphereLike) -> SphereIntersection: ...
@overload
def intersect_exact(ray: RayLike, primitive: PlaneLike) -> Intersection: ...
@overload
def intersect_exact(
    ray: RayLike, primitive: TriangleLike, *, rule: Optional[RuleLike] = None, t: bool = True, barycentric: bool = True
) -> TriangleIntersection: ...
@overload
def intersect_exact_rational(ray: RayLike, primitive: SphereLike) -> ExactSphereIntersection: ...
@overload
def intersect_exact_rational(ray: RayLike, primitive: PlaneLike) -> ExactIntersection: ...
@overload
def intersect_exact_rational(
    ray: RayLike, primitive: TriangleLike, *, rule: Optional[RuleLike] = None
) -> ExactTriangleIntersection: ...
@overload
def intersect_naive(ray: RayLike, primitive: SphereLike) -> SphereIntersection: ...
@overload
def intersect_naive(ray: RayLike, primitive: PlaneLike) -> Intersection: ...
@overload
def intersect_naive(ray: RayLike, primitive: TriangleLike) -> TriangleIntersection: ...
@overload
def intersect_traced(ray: RayLike, primitive: SphereLike) -> TracedSphereIntersection: ...
@overload
def intersect_traced(ray: RayLike, primitive: PlaneLike) -> TracedIntersection: ...
@overload
def intersect_traced(
    ray: RayLike, primitive: TriangleLike, *, rule: Optional[RuleLike] = None, t: bool = True, barycentric: bool = True
) -> TracedTriangleIntersection: ...
@overload
def round_rational_to_double(value: Union[Fraction, int], denominator: None = None) -> float: ...
@overload
def round_rational_to_double(value: int, denominator: int) -> float: ...
def spawn(
    hit: Union[RayLike, Vec3Like], triangle: Union[TriangleLike, Sphere], direction: Vec3Like, *, format: str = "binary64"
) -> SpawnedOrigin: ...
def spawn_to(
    hit: Union[RayLike, Vec3Like], triangle: TriangleLike, target: Vec3Like, *, format: str = "binary64"
) -> SpawnedOrigin: ...
def spawn_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    a: ArrayLike3,
    b: ArrayLike3,
    c: ArrayLike3,
    directions_out: ArrayLike3,
    *,
    format: str = "binary64",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> SpawnArrays: ...
def spawn_to_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    a: ArrayLike3,
    b: ArrayLike3,
    c: ArrayLike3,
    targets: ArrayLike3,
    *,
    format: str = "binary64",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> SpawnArrays: ...
def mesh_bytes(mesh: Mesh, format: str, *, encoding: str = "ascii") -> bytes: ...
def floating_point_environment_is_default() -> bool: ...
def version() -> str: ...

class PlaneSet:
    def __init__(self, planes: Union[Sequence[PlaneLike], ArrayLike3], normals: Optional[ArrayLike3] = None) -> None: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: int) -> Plane: ...
    @property
    def points(self) -> np.ndarray: ...
    @property
    def normals(self) -> np.ndarray: ...
    @property
    def candidates(self) -> np.ndarray: ...

Planes = Union[PlaneSet, Sequence[PlaneLike]]

class Mesh:
    # triangles: (m, 3) vertex indices of an integer dtype (int8..uint64, or lists of ints), each checked against
    # [0, len(vertices)) as it is; float indices (even integral ones), bool and masked arrays raise TypeError.
    def __init__(self, vertices: ArrayLike3, triangles: npt.ArrayLike) -> None: ...
    def __len__(self) -> int: ...
    @property
    def vertices(self) -> np.ndarray: ...
    @property
    def triangles(self) -> np.ndarray: ...
    def triangle(self, index: int) -> Triangle: ...
    @property
    def bvh_depth(self) -> int: ...
    # A Mesh pickles as (vertices, triangles), exactly; unpickling prepares it again (raykernel.dask sends meshes to
    # workers this way).

# Every file that cannot be read as a mesh raises MeshFileError, and so does a path containing a NUL character; a
# path where there is no file raises MeshFileNotFoundError (a MeshFileError and a FileNotFoundError).
def load_mesh(path: Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]) -> Mesh: ...
class SphereSet:
    # centers (m, 3) with radii (m,), or a sequence of Sphere (radii None). Pickles as (centers, radii).
    def __init__(self, centers: Union[ArrayLike3, Sequence[Sphere]], radii: Optional[npt.ArrayLike] = None) -> None: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: int) -> Sphere: ...
    @property
    def centers(self) -> np.ndarray: ...
    @property
    def radii(self) -> np.ndarray: ...

# Every scene takes an interval [t_min, t_max], compared exactly (the naive loop over planes only the whole ray);
# only meshes a rule.
@overload
def nearest_hit(
    ray: RayLike, scene: Mesh, *, rule: Optional[RuleLike] = None, t_min: float = 0.0, t_max: float = ...
) -> Optional[MeshHit]: ...
@overload
def nearest_hit(ray: RayLike, scene: Planes, *, t_min: float = 0.0, t_max: float = ...) -> Optional[NearestHit]: ...
@overload
def nearest_hit(ray: RayLike, scene: SphereSet, *, t_min: float = 0.0, t_max: float = ...) -> Optional[SphereHit]: ...
@overload
def nearest_hit_exact(
    ray: RayLike, scene: Mesh, *, rule: Optional[RuleLike] = None, t_min: float = 0.0, t_max: float = ...
) -> Optional[MeshHit]: ...
@overload
def nearest_hit_exact(ray: RayLike, scene: Planes, *, t_min: float = 0.0, t_max: float = ...) -> Optional[NearestHit]: ...
@overload
def nearest_hit_exact(
    ray: RayLike, scene: SphereSet, *, t_min: float = 0.0, t_max: float = ...
) -> Optional[SphereHit]: ...
@overload
def nearest_hit_naive(ray: RayLike, scene: Planes) -> Optional[NearestHit]: ...
@overload
def nearest_hit_naive(ray: RayLike, scene: Mesh, *, t_min: float = 0.0, t_max: float = ...) -> Optional[MeshHit]: ...
@overload  # no naive form for a SphereSet: TypeError
def nearest_hit_naive(ray: RayLike, scene: SphereSet, *, t_min: float = 0.0, t_max: float = ...) -> Optional[SphereHit]: ...
def occluded(
    ray: RayLike,
    scene: Union[Mesh, SphereSet],
    *,
    t_min: float = 0.0,
    t_max: float = ...,
    rule: Optional[RuleLike] = None,
    path: str = "certified",
) -> bool: ...
def all_hits(
    ray: RayLike,
    mesh: Mesh,
    *,
    t_min: float = 0.0,
    t_max: float = ...,
    rule: Optional[RuleLike] = None,
    path: str = "certified",
) -> MeshHits: ...
def occluded_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    scene: Union[Mesh, SphereSet],
    *,
    t_min: Union[float, npt.ArrayLike] = 0.0,
    t_max: Union[float, npt.ArrayLike] = ...,
    rule: Optional[RuleLike] = None,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> OcclusionArrays: ...
def occluded_segment_batch(
    p: ArrayLike3,
    q: ArrayLike3,
    scene: Union[Mesh, SphereSet],
    *,
    rule: Optional[RuleLike] = None,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> OcclusionArrays: ...
def crossings_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    mesh: Mesh,
    *,
    t_min: Union[float, npt.ArrayLike] = 0.0,
    t_max: Union[float, npt.ArrayLike] = ...,
    rule: Optional[RuleLike] = None,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> CrossingArrays: ...
def occluded_segment(
    p: Vec3Like, q: Vec3Like, scene: Union[Mesh, SphereSet], *, rule: Optional[RuleLike] = None, path: str = "certified"
) -> bool: ...
def inside(point: Vec3Like, mesh: Mesh) -> PointLocation: ...
def inside_exact(point: Vec3Like, mesh: Mesh) -> PointLocation: ...
def closest_point(point: Vec3Like, mesh: Mesh) -> ClosestPoint: ...
def closest_point_exact(point: Vec3Like, mesh: Mesh) -> ClosestPoint: ...
def closest_point_batch(
    points: ArrayLike3,
    mesh: Mesh,
    *,
    signed: bool = False,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> ClosestPointArrays: ...
def inside_batch(
    points: ArrayLike3,
    mesh: Mesh,
    *,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> PointLocationArrays: ...
def intersect_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    points: ArrayLike3,
    normals: ArrayLike3,
    *,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    stats: bool = False,
    progress: Optional[Callable[[int, int], object]] = None,
) -> IntersectionArrays: ...
def relation_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    points: ArrayLike3,
    normals: ArrayLike3,
    *,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    stats: bool = False,
    progress: Optional[Callable[[int, int], object]] = None,
) -> RelationArrays: ...
def intersect_triangle_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    a: ArrayLike3,
    b: ArrayLike3,
    c: ArrayLike3,
    *,
    rule: Optional[RuleLike] = None,
    t: bool = True,
    barycentric: bool = True,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> TriangleIntersectionArrays: ...
def relation_triangle_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    a: ArrayLike3,
    b: ArrayLike3,
    c: ArrayLike3,
    *,
    rule: Optional[RuleLike] = None,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> TriangleClassificationArrays: ...
# centers (n, 3) with radii (n,), or centers one 3-vector with radii one number (one sphere for every ray).
def intersect_sphere_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    centers: ArrayLike3,
    radii: Union[npt.ArrayLike, float],
    *,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> SphereIntersectionArrays: ...
@overload
def nearest_hit_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    scene: Mesh,
    *,
    rule: Optional[RuleLike] = None,
    t_min: Union[float, npt.ArrayLike] = 0.0,
    t_max: Union[float, npt.ArrayLike] = ...,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> MeshHitArrays: ...
@overload
def nearest_hit_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    scene: SphereSet,
    *,
    t_min: Union[float, npt.ArrayLike] = 0.0,
    t_max: Union[float, npt.ArrayLike] = ...,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> SphereHitArrays: ...
@overload
def nearest_hit_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    scene: Planes,
    *,
    t_min: Union[float, npt.ArrayLike] = 0.0,
    t_max: Union[float, npt.ArrayLike] = ...,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], object]] = None,
    stats: bool = False,
) -> NearestHitArrays: ...

class testkit:  # the submodule raykernel._raykernel.testkit
    QUERY_KINDS: Tuple[str, ...]
    PLANE_TIE_KINDS: Tuple[str, ...]
    Words = Union[bytes, Callable[[], int]]
    @staticmethod
    def make_query(kind: str, words: Words) -> Tuple[Ray, Plane]: ...
    @staticmethod
    def make_query_arrays(
        kinds: Sequence[str], count: int, seed: int
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]: ...
    @staticmethod
    def make_plane_pair(kind: Optional[str], words: Words) -> Tuple[str, Ray, Tuple[Plane, Plane], int]: ...
    @staticmethod
    def check_against_reference(
        ray: RayLike, plane: PlaneLike, relation: Union[Relation, str, int], t: float, max_t_ulps: int = 0
    ) -> dict: ...
    TRIANGLE_QUERY_KINDS: Tuple[str, ...]
    @staticmethod
    def make_triangle_query(kind: str, words: Words) -> Tuple[Ray, Triangle]: ...
    @staticmethod
    def make_triangle_query_arrays(
        kinds: Sequence[str], count: int, seed: int
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]: ...
    SPHERE_QUERY_KINDS: Tuple[str, ...]
    @staticmethod
    def make_sphere_query(kind: str, words: Words) -> Tuple[Ray, Sphere]: ...
    @staticmethod
    def make_sphere_query_arrays(
        kinds: Sequence[str], count: int, seed: int
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]: ...
    @staticmethod
    def check_triangle_against_reference(
        ray: RayLike,
        triangle: TriangleLike,
        relation: Union[str, int],
        location: Union[str, int],
        owned: bool,
        t: float,
        barycentric: Sequence[float],
        rule: Optional[RuleLike] = None,
        max_ulps: int = 0,
        check_location: bool = True,
    ) -> dict: ...
    @staticmethod
    def make_octahedron(radius: float = 1.0) -> Mesh: ...
    @staticmethod
    def make_subdivided_cube(n: int, half_size: float = 1.0) -> Mesh: ...
    @staticmethod
    def make_icosphere(level: int, grid_bits: int = 30) -> Mesh: ...
    @staticmethod
    def ulp_distance(a: float, b: float) -> Optional[int]: ...
    @staticmethod
    def ulp_difference(a: float, b: float) -> Optional[int]: ...
    @staticmethod
    def hex_string(x: float) -> str: ...
    @staticmethod
    def shortest_decimal(x: float) -> str: ...
    @staticmethod
    def classify_line(ray: RayLike, plane: PlaneLike) -> str: ...
    @staticmethod
    def decode_fuzz_query(data: bytes) -> Tuple[Ray, Plane, Optional[str]]: ...
    @staticmethod
    def encode_raw_fuzz_input(ray: RayLike, plane: PlaneLike) -> bytes: ...
    @staticmethod
    def encode_hard_query_fuzz_input(kind: str, words: Sequence[int]) -> bytes: ...
