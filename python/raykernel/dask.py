"""raykernel.dask: raykernel's batch queries over Dask arrays, chunk by chunk, on a laptop or a cluster.

Each function here is the batch function of the same name in ``raykernel``, with the same arguments and the same
answers, bit for bit: the rows are cut into Dask's row chunks and each chunk is one call of the batch function
(in C++, GIL released). The result is the same NamedTuple (``MeshHitArrays``, ``SphereIntersectionArrays``, ...)
with a lazy ``dask.array.Array`` in each array field; ``raykernel.dask.compute(result)`` runs it into the batch
function's NumPy NamedTuple (each chunk written into place as it is done), ``dask.compute(*result)`` or
``.compute()`` on a field work too. Fields that are not arrays (``stats``) are None: ask the plain batch function for them.

    >>> import dask.array as da, raykernel as rk, raykernel.dask as rkd
    >>> mesh = rk.load_mesh("bunny.ply")
    >>> origins = da.from_array(o, chunks=(1_000_000, 3))       # o, d: (n, 3) float64
    >>> hits = rkd.nearest_hit_batch(origins, d, mesh)          # lazy
    >>> triangle, t = dask.compute(hits.triangle, hits.t)        # exact, as rk.nearest_hit_batch(o, d, mesh)

- **The scene travels once.** A ``Mesh`` or ``PlaneSet`` is one node of the task graph, shared by every chunk: a
  worker process receives it once (a ``Mesh`` pickles as its vertices and triangles and is prepared again on the
  worker: its BVH is rebuilt, deterministically) and keeps it for all its chunks.
- **Threads.** ``threads`` is the batch function's (threads per chunk); it defaults to 1 here, because Dask
  already runs one chunk per worker thread. With the local threaded scheduler, chunks run in parallel threads
  (the C++ releases the GIL); with ``distributed``, in the workers' threads and processes.
- **Errors.** With ``errors="raise"`` (the default) a chunk with an invalid row raises the batch function's
  ``ValueError`` when computed, its row number counted over the whole array ("ray 1000017: direction is the zero
  vector"); ``errors="mask"`` answers the other rows and marks the bad one in ``valid``.
- **Inputs.** Row arguments are (n, 3) arrays (NumPy or Dask; radii (n,)); they are rechunked to the first row
  argument's row chunks. ``points`` / ``normals`` / ``a``, ``b``, ``c`` / ``centers`` may also be one (3,)
  vector for every row, as in the batch functions; ``radii`` one number.

On a cluster: start ``dask scheduler`` on one machine and ``dask worker tcp://SCHEDULER:8786`` on each of the
others (raykernel installed on each), then ``distributed.Client("tcp://SCHEDULER:8786")`` before computing
(README.md, "Python", "Scale-out with Dask").
"""

from __future__ import annotations

import re
import uuid
from typing import Any, Callable, List, NamedTuple, Optional, Sequence

import dask
import dask.array as da
import numpy as np

import raykernel as _rk

__all__ = [
    "closest_point_batch",
    "compute",
    "crossings_batch",
    "inside_batch",
    "intersect_batch",
    "intersect_sphere_batch",
    "intersect_triangle_batch",
    "map_rows",
    "nearest_hit_batch",
    "occluded_batch",
    "occluded_segment_batch",
    "relation_batch",
    "relation_triangle_batch",
    "spawn_batch",
    "spawn_to_batch",
]

_ROW_NAME = re.compile(r"^(\w+) (\d+): ")


def _shift_row(error: ValueError, offset: int) -> ValueError:
    """The batch function's error with its row number counted over the whole array."""
    message = str(error)
    match = _ROW_NAME.match(message)
    if not match or offset == 0:
        return error
    shifted = f"{match.group(1)} {int(match.group(2)) + offset}: " + message[match.end():]
    return type(error)(shifted)


def _shippable(function: Callable[..., Any]) -> Any:
    """What a task carries for ``function``: the name of a raykernel function (the extension's functions do not
    pickle, and need not: the worker imports raykernel), else the callable itself (which must pickle)."""
    name = getattr(function, "__name__", None)
    return name if name is not None and getattr(_rk, name, None) is function else function


def _run_chunk(function: Any, offset: int, shared: Sequence[Any], kwargs: dict, keyword_rows: Sequence[str],
               *blocks: Any) -> Any:
    if isinstance(function, str):
        function = getattr(_rk, function)
    positional = len(blocks) - len(keyword_rows)
    try:
        return function(*blocks[:positional], *shared, **kwargs, **dict(zip(keyword_rows, blocks[positional:])))
    except ValueError as error:
        raise _shift_row(error, offset) from None


def _as_rows(value: Any, name: str, per_row_ndim: int) -> Optional[da.Array]:
    """``value`` as a Dask array of rows, or None when it is one value for every row (a (3,) vector, a number)."""
    if isinstance(value, da.Array):
        array = value
    else:
        array = np.asarray(value)
        if array.ndim < per_row_ndim + 1:
            return None  # one vector (or number) for every row
        array = da.from_array(array, chunks=-1)
    if array.ndim != per_row_ndim + 1:
        raise ValueError(f"{name}: expected {'an (n, 3)' if per_row_ndim else 'an (n,)'} array, got shape {array.shape}")
    return array


class _Empty(NamedTuple):
    fields: List[str]
    template: Any  # the batch function's answer on zero rows: the fields' dtypes and trailing shapes


def map_rows(
    function: Callable[..., Any],
    rows: Sequence[Any],
    shared: Sequence[Any] = (),
    *,
    names: Optional[Sequence[str]] = None,
    per_row_ndims: Optional[Sequence[int]] = None,
    keyword_rows: Sequence[str] = (),
    **kwargs: Any,
) -> Any:
    """``function(*rows, *shared, **kwargs)`` chunk by chunk over the rows: the general form of this module's
    functions, for any raykernel batch function whose first arguments are row arrays.

    ``rows``: the row arguments (Dask or NumPy arrays of n rows, or one value for every row, which is passed
    whole to each chunk); ``per_row_ndims``: for each, the dimensions of one row (1 for an (n, 3) array, 0 for
    an (n,) array; default 1); ``shared``: arguments after them passed whole (a ``Mesh``: one graph node, sent to
    each worker once); ``kwargs``: the keyword arguments; ``keyword_rows``: the names under which the last
    ``len(keyword_rows)`` row arguments are passed (per-row keyword arguments, like ``t_max``). Returns the
    function's NamedTuple with a Dask array in each array field and None in the others."""
    names = list(names) if names is not None else [f"argument {k}" for k in range(len(rows))]
    ndims = list(per_row_ndims) if per_row_ndims is not None else [1] * len(rows)
    arrays = [_as_rows(value, name, ndim) for value, name, ndim in zip(rows, names, ndims)]
    leading = next((a for a in arrays if a is not None), None)
    if leading is None:
        raise ValueError("map_rows: no argument is an array of rows")
    n = leading.shape[0]
    for array, name in zip(arrays, names):
        if array is not None and array.shape[0] != n:
            raise ValueError(f"{name}: {array.shape[0]} rows, but {names[arrays.index(leading)]} has {n}")
    row_chunks = leading.chunks[0]
    # Each row argument in the leading one's row chunks, whole along its other axis.
    aligned = [None if a is None else a.rechunk({0: row_chunks, **{k: -1 for k in range(1, a.ndim)}}) for a in arrays]
    # One graph node per shared value (a Mesh: pickled once into the graph, fetched once by each worker).
    shared_nodes = [dask.delayed(value, name=f"raykernel-shared-{uuid.uuid4().hex}") for value in shared]

    # The answer on zero rows: which fields are arrays, their dtypes and trailing shapes.
    empty_rows = [np.asarray(value) if a is None else np.zeros((0,) + a.shape[1:], dtype=a.dtype)
                  for value, a in zip(rows, aligned)]
    positional = len(rows) - len(keyword_rows)
    template = function(*empty_rows[:positional], *shared, **kwargs,
                        **dict(zip(keyword_rows, empty_rows[positional:])))

    blocks = [None if a is None else a.to_delayed().ravel() for a in aligned]
    chunk_results = []
    offset = 0
    for i, size in enumerate(row_chunks):
        arguments = [np.asarray(value) if b is None else b[i] for value, b in zip(rows, blocks)]
        chunk_results.append(
            dask.delayed(_run_chunk, pure=True)(_shippable(function), offset, shared_nodes, kwargs, tuple(keyword_rows),
                                                *arguments))
        offset += size

    fields = {}
    for field in template._fields:
        value = getattr(template, field)
        if not isinstance(value, np.ndarray):
            fields[field] = None
            continue
        parts = [da.from_delayed(dask.delayed(getattr, pure=True)(result, field), shape=(size,) + value.shape[1:],
                                 dtype=value.dtype)
                 for result, size in zip(chunk_results, row_chunks)]
        fields[field] = da.concatenate(parts, axis=0) if parts else da.from_array(value)
    return type(template)(**fields)


def _batch(function: Callable[..., Any], rows: dict, shared: Sequence[Any], per_row_ndims: Sequence[int],
           threads: Optional[int], kwargs: dict, keyword_rows: Sequence[str] = ()) -> Any:
    return map_rows(function, list(rows.values()), shared, names=list(rows), per_row_ndims=per_row_ndims,
                    keyword_rows=keyword_rows, threads=threads, **kwargs)


def _interval_rows(function: Callable[..., Any], origins, directions, scene, t_min, t_max, threads, kwargs) -> Any:
    """A ray batch with intervals: t_min and t_max one number for every ray (passed whole) or one per ray."""
    rows = dict(origins=origins, directions=directions)
    ndims, keyword_rows = [1, 1], []
    for name, value in (("t_min", t_min), ("t_max", t_max)):
        if isinstance(value, da.Array) or np.ndim(value) > 0:
            rows[name] = value
            ndims.append(0)
            keyword_rows.append(name)
        else:
            kwargs[name] = value
    return _batch(function, rows, (scene,), ndims, threads, kwargs, keyword_rows)


def intersect_batch(origins, directions, points, normals, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.intersect_batch`` over Dask arrays (ray–plane, one plane per row or one for all)."""
    kwargs.pop("stats", None)
    return _batch(_rk.intersect_batch, dict(origins=origins, directions=directions, points=points, normals=normals),
                  (), (1, 1, 1, 1), threads, kwargs)


def relation_batch(origins, directions, points, normals, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.relation_batch`` over Dask arrays."""
    kwargs.pop("stats", None)
    return _batch(_rk.relation_batch, dict(origins=origins, directions=directions, points=points, normals=normals),
                  (), (1, 1, 1, 1), threads, kwargs)


def intersect_triangle_batch(origins, directions, a, b, c, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.intersect_triangle_batch`` over Dask arrays (one triangle per row or one for all)."""
    return _batch(_rk.intersect_triangle_batch, dict(origins=origins, directions=directions, a=a, b=b, c=c), (),
                  (1, 1, 1, 1, 1), threads, kwargs)


def relation_triangle_batch(origins, directions, a, b, c, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.relation_triangle_batch`` over Dask arrays."""
    return _batch(_rk.relation_triangle_batch, dict(origins=origins, directions=directions, a=a, b=b, c=c), (),
                  (1, 1, 1, 1, 1), threads, kwargs)


def intersect_sphere_batch(origins, directions, centers, radii, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.intersect_sphere_batch`` over Dask arrays (radii: (n,), or one number for every row)."""
    return _batch(_rk.intersect_sphere_batch, dict(origins=origins, directions=directions, centers=centers,
                                                   radii=radii), (), (1, 1, 1, 0), threads, kwargs)


def nearest_hit_batch(origins, directions, scene, *, t_min=0.0, t_max=np.inf, threads: Optional[int] = 1,
                      **kwargs):
    """``raykernel.nearest_hit_batch`` over Dask arrays; ``scene`` (a ``Mesh``, ``SphereSet`` or ``PlaneSet``) goes
    to each worker once; ``t_min``, ``t_max`` one number, or an (n,) array chunked with the rays."""
    kwargs.pop("stats", None)
    return _interval_rows(_rk.nearest_hit_batch, origins, directions, scene, t_min, t_max, threads, kwargs)


def inside_batch(points, mesh, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.inside_batch`` over a Dask array of points; ``mesh`` goes to each worker once."""
    return _batch(_rk.inside_batch, dict(points=points), (mesh,), (1,), threads, kwargs)


def occluded_batch(origins, directions, scene, *, t_min=0.0, t_max=np.inf, threads: Optional[int] = 1, **kwargs):
    """``raykernel.occluded_batch`` over Dask arrays: any-hit per ray within [t_min, t_max] (each one number, or
    an (n,) array of per-ray bounds, chunked with the rays); ``scene`` (a ``Mesh`` or ``SphereSet``) goes to each
    worker once."""
    return _interval_rows(_rk.occluded_batch, origins, directions, scene, t_min, t_max, threads, kwargs)


def crossings_batch(origins, directions, mesh, *, t_min=0.0, t_max=np.inf, threads: Optional[int] = 1, **kwargs):
    """``raykernel.crossings_batch`` over Dask arrays: each ray's signed count of owned crossings within its
    interval (t_min, t_max as in ``occluded_batch``)."""
    return _interval_rows(_rk.crossings_batch, origins, directions, mesh, t_min, t_max, threads, kwargs)


def occluded_segment_batch(p, q, scene, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.occluded_segment_batch`` over Dask arrays of segment ends (the open segments p → q; ``scene`` a
    ``Mesh`` or ``SphereSet``)."""
    return _batch(_rk.occluded_segment_batch, dict(p=p, q=q), (scene,), (1, 1), threads, kwargs)


def closest_point_batch(points, mesh, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.closest_point_batch`` over a Dask array of points (``signed=True`` as there)."""
    return _batch(_rk.closest_point_batch, dict(points=points), (mesh,), (1,), threads, kwargs)


def spawn_batch(origins, directions, a, b, c, directions_out, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.spawn_batch`` over Dask arrays (one triangle per row)."""
    return _batch(_rk.spawn_batch, dict(origins=origins, directions=directions, a=a, b=b, c=c,
                                        directions_out=directions_out), (), (1,) * 6, threads, kwargs)


def spawn_to_batch(origins, directions, a, b, c, targets, *, threads: Optional[int] = 1, **kwargs):
    """``raykernel.spawn_to_batch`` over Dask arrays (one triangle and one target per row)."""
    return _batch(_rk.spawn_to_batch, dict(origins=origins, directions=directions, a=a, b=b, c=c, targets=targets),
                  (), (1,) * 6, threads, kwargs)


def compute(result: Any, **compute_kwargs: Any) -> Any:
    """A result of this module computed: the batch function's NamedTuple of NumPy arrays, bit for bit
    ``dask.compute(*result)``'s, faster on one machine.

    Every field is computed in one pass and each chunk's answer is written into its rows of arrays allocated once
    (``dask.array.store``) as soon as it is done, on the worker thread that computed it, instead of the chunks
    being concatenated one field after the other at the end. With a ``distributed`` client (the answers live in
    other processes) it is ``dask.compute``. ``compute_kwargs`` go to the scheduler (``scheduler="threads"``,
    ``num_workers=2``)."""
    lazy = {name: value for name, value in result._asdict().items() if isinstance(value, da.Array)}
    if lazy and _local_scheduler(compute_kwargs.get("scheduler")):
        computed = {name: np.empty(value.shape, value.dtype) for name, value in lazy.items()}
        da.store(list(lazy.values()), list(computed.values()), lock=False, **compute_kwargs)
    else:
        computed = dict(zip(lazy, dask.compute(*lazy.values(), **compute_kwargs)))
    return type(result)(**{name: computed.get(name, value) for name, value in result._asdict().items()})


def _local_scheduler(scheduler: Any) -> bool:
    """Whether the scheduler computing now runs in this process (Dask's threaded or synchronous one), so that
    chunks can be written into arrays here; not for a distributed client's or a process pool's."""
    import dask.local
    import dask.threaded
    from dask.base import get_scheduler

    chosen = get_scheduler(scheduler=scheduler)
    return chosen is None or chosen in (dask.threaded.get, dask.local.get_sync)
