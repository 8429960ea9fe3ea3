# Type stubs of the compiled extension raykernel._raykernel (python/src/*.cpp). The docstrings are in the
# extension (help(raykernel.intersect)); tests/test_stubs.py checks that these names and parameters are the
# extension's.
from fractions import Fraction
from typing import Callable, Iterator, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from ._types import (
    ExactIntersection,
    Intersection,
    IntersectionArrays,
    NearestHit,
    NearestHitArrays,
    Plane,
    PlaneLike,
    Ray,
    RayLike,
    Relation,
    TracedIntersection,
)

__version__: str
INVALID_RELATION_CODE: int

class InvalidInput(ValueError): ...

ArrayLike3 = npt.ArrayLike  # (n, 3) float64, or (3,) where one plane is allowed

def validate(ray: RayLike, plane: PlaneLike) -> Optional[str]: ...
def intersect(ray: RayLike, plane: PlaneLike) -> Intersection: ...
def intersect_exact(ray: RayLike, plane: PlaneLike) -> Intersection: ...
def intersect_exact_rational(ray: RayLike, plane: PlaneLike) -> ExactIntersection: ...
def intersect_naive(ray: RayLike, plane: PlaneLike) -> Intersection: ...
def intersect_traced(ray: RayLike, plane: PlaneLike) -> TracedIntersection: ...
@overload
def round_rational_to_double(value: Union[Fraction, int], denominator: None = None) -> float: ...
@overload
def round_rational_to_double(value: int, denominator: int) -> float: ...
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

Planes = Union[PlaneSet, Sequence[PlaneLike]]

def nearest_hit(ray: RayLike, planes: Planes) -> Optional[NearestHit]: ...
def nearest_hit_exact(ray: RayLike, planes: Planes) -> Optional[NearestHit]: ...
def nearest_hit_naive(ray: RayLike, planes: Planes) -> Optional[NearestHit]: ...
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
) -> IntersectionArrays: ...
def nearest_hit_batch(
    origins: ArrayLike3,
    directions: ArrayLike3,
    planes: Planes,
    *,
    path: str = "certified",
    errors: str = "raise",
    threads: Optional[int] = None,
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
