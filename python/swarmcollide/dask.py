"""The batch queries on Dask arrays, for batches beyond one call or one machine.

``distance_many``, ``collide_many`` and ``signed_distance_many`` take bodies as dask arrays of
shape ``(m, n, 3)`` chunked along the pair axis and return a ``BatchArrays`` whose fields are
dask arrays, lazily. Each chunk is answered by the in-memory batch call (``Query.distance_many``
and its siblings, which release the GIL) told the global index of its first pair, so every answer
is bitwise the in-memory call's whatever the chunking, the scheduler or the number of workers:
pair i is seeded with ``pair_seed(seed, i)`` and errors name pair i by its global index.

The threaded scheduler (Dask's default for arrays) uses every core of one machine; a
``distributed`` cluster spreads the chunks over processes and machines. Inputs that do not fit in
memory stay on disk: ``dask.array.from_zarr`` reads bodies chunk by chunk and
``BatchArrays.store`` writes the answers back, one pass over the chunks. Install with
``pip install swarmcollide[dask]``; docs/dask.md says which scheduler and chunk size to choose.

Examples
--------
>>> import dask.array as da, numpy as np
>>> import swarmcollide as sc, swarmcollide.dask as scd
>>> tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
>>> As = np.stack([tetra] * 6)
>>> Bs = np.stack([tetra + [k + 0.5, 0, 0] for k in range(6)])
>>> lazy = scd.distance_many(da.from_array(As, chunks=(4, -1, -1)), da.from_array(Bs))
>>> lazy
BatchArrays(6 pairs in 2 chunks, lazy)
>>> r = lazy.compute()
>>> r.distance.round(9).tolist(), r.colliding.tolist()
([0.0, 0.5, 1.5, 2.5, 3.5, 4.5], [True, False, False, False, False, False])
>>> np.array_equal(r.point_b, sc.distance_many(As, Bs).point_b)
True
"""

from __future__ import annotations

import contextlib
import functools
import math
import operator
import sys
import uuid
from dataclasses import dataclass, fields
from typing import Any, Generic, Mapping, Optional, Tuple, TypeVar

import dask
import dask.array as da
import dask.local
import dask.threaded
import numpy as np
from dask.base import get_scheduler
from dask.layers import ArraySliceDep
from dask.utils import get_scheduler_lock

from swarmcollide import queries
from swarmcollide.queries import DEFAULT_TOLERANCE, Parameters

if sys.version_info >= (3, 11):
    from typing import Unpack
else:  # pragma: no cover - exercised on older interpreters only
    from typing_extensions import Unpack

__all__ = ["BatchArrays", "collide_many", "distance_many", "signed_distance_many"]

# The fields of a BatchResult: their NumPy types, and whether they hold a point per pair.
_FIELDS = {
    "distance": (np.float64, False),
    "lower_bound": (np.float64, False),
    "point_a": (np.float64, True),
    "point_b": (np.float64, True),
    "direction": (np.float64, True),
    "colliding": (np.bool_, False),
    "certified": (np.bool_, False),
    "escalated": (np.bool_, False),
    "iterations": (np.int32, False),
}


ArrayT = TypeVar("ArrayT")


@dataclass(frozen=True, repr=False)
class BatchArrays(Generic[ArrayT]):
    """The fields of a ``BatchResult``, as dask arrays (lazy) or, once computed, NumPy arrays.

    Compute fields together (``compute``, ``persist``, ``store`` or
    ``dask.compute(r.distance, r.colliding)``): each chunk is then answered once for all of them,
    whereas computing two fields one after the other answers every chunk twice.

    Attributes
    ----------
    distance, lower_bound : array, shape (m,)
    point_a, point_b, direction : array, shape (m, 3)
    colliding, certified, escalated : array of bool, shape (m,)
    iterations : array of int32, shape (m,)
    """

    distance: ArrayT
    lower_bound: ArrayT
    point_a: ArrayT
    point_b: ArrayT
    direction: ArrayT
    colliding: ArrayT
    certified: ArrayT
    escalated: ArrayT
    iterations: ArrayT

    def compute(self, **kwargs: Any) -> BatchArrays[np.ndarray]:
        """Every field as a NumPy array, each chunk answered once.

        ``kwargs`` go to ``dask.compute`` (``scheduler=``, ``num_workers=``, ...); with a
        ``distributed.Client`` active or passed as ``scheduler=``, its cluster computes and the
        answers come here. Each chunk's answers go into the result as soon as the chunk is
        answered: with the threaded or the synchronous scheduler, by the thread that answered
        it; from a cluster, by this process as each chunk arrives, straight from the worker
        that holds it. Only the chunks in flight are held besides the result.
        """
        chunks = _chunks_of(self)
        if chunks is None:  # made from dask arrays by hand: compute them as they are
            return BatchArrays(*dask.compute(*self._values(), **kwargs))
        answers = chunks.answers
        result = BatchArrays(*(np.empty(value.shape, value.dtype) for value in self._values()))
        schedule = get_scheduler(scheduler=kwargs.get("scheduler"), collections=[answers])
        if schedule in (dask.threaded.get, dask.local.get_sync):
            dask.compute(chunks.written(vars(result), None), **kwargs)
            return result
        starts = np.cumsum((0,) + answers.chunks[0])
        client = _client_of(schedule)
        if client is None:  # another scheduler: the chunks' answers come back together
            computed = dask.compute(*answers.to_delayed(), **kwargs)
            for i, chunk in enumerate(computed):
                _write_chunk(chunk, vars(result), slice(starts[i], starts[i + 1]), None)
            return result
        from distributed import as_completed, futures_of

        kwargs.pop("scheduler", None)
        futures = futures_of(client.persist(answers, **kwargs))
        block = {future.key: i for i, future in enumerate(futures)}
        # Straight from the worker that holds each chunk: through the scheduler, every chunk
        # would be received and sent again by the scheduler's process.
        for future in as_completed(futures, loop=client.loop):
            i = block[future.key]
            chunk = client.gather(future, direct=True)
            _write_chunk(chunk, vars(result), slice(starts[i], starts[i + 1]), None)
            future.release()
        return result

    def persist(self, **kwargs: Any) -> BatchArrays[da.Array]:
        """The answers computed and kept (on a cluster, in the memory of the workers that
        answered them), each chunk once for all fields; the fields are then dask arrays that
        take their parts from the kept chunks.

        ``kwargs`` go to ``dask.persist`` (``scheduler=``, ...) or, with a ``distributed.Client``
        active, to ``Client.persist``. A chunk's answers are kept as one piece with every field,
        so a cluster tracks one key per chunk rather than one per field and chunk.
        """
        chunks = _chunks_of(self)
        if chunks is None:
            return BatchArrays(*dask.persist(*self._values(), **kwargs))
        (answers,) = dask.persist(chunks.answers, **kwargs)
        return _lazy(_Chunks(answers))

    def store(self, targets: Mapping[str, Any], *, lock: Any = True, **kwargs: Any) -> None:
        """Write the fields named in ``targets`` into them, each chunk answered once.

        Parameters
        ----------
        targets : mapping from field name to array-like
            Where each field goes: an array of the field's shape that takes
            ``target[region] = values``, such as a Zarr array, an ``h5py`` dataset or a NumPy
            memmap (in this process only: a memmap sent to another process is a copy). Chunks
            of a Zarr target should be whole chunks of the result, or concurrent writers must
            share a lock.
        lock : bool or lock, default True
            As in ``dask.array.store``: held while a chunk is written; True for one suited to
            the scheduler, False for none (targets that take concurrent writes of disjoint
            regions, such as NumPy arrays or Zarr arrays written in whole chunks).
        **kwargs
            Passed to ``dask.compute`` (``scheduler=``, ...).

        Raises
        ------
        ValueError
            Before anything is computed, for a name that is no field or a target whose shape is
            not its field's (naming ``targets['name']``, its shape and the field's).
        TypeError
            For a target without a shape.

        Examples
        --------
        >>> import dask.array as da, numpy as np, swarmcollide.dask as scd
        >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
        >>> As = np.stack([cube] * 4)
        >>> Bs = np.stack([cube + [k * 0.5, 0, 0] for k in range(4)])
        >>> chunked = [da.from_array(bodies, chunks=(2, -1, -1)) for bodies in (As, Bs)]
        >>> lazy = scd.distance_many(*chunked)
        >>> distance, colliding = np.empty(4), np.empty(4, bool)
        >>> lazy.store({"distance": distance, "colliding": colliding})
        >>> distance.round(9).tolist(), colliding.tolist()
        ([0.0, 0.0, 0.0, 0.5], [True, True, True, False])
        """
        names = [f.name for f in fields(self)]
        unknown = [name for name in targets if name not in names]
        if unknown:
            raise ValueError(f"targets has no field named {unknown[0]!r}; use some of {names}")
        for name, target in targets.items():
            _check_target_shape(name, target, getattr(self, name).shape)
        chunks = _chunks_of(self)
        if chunks is None:
            sources = [getattr(self, name) for name in targets]
            da.store(sources, list(targets.values()), lock=lock, **kwargs)
            return
        if lock is True:
            lock = get_scheduler_lock(chunks.answers, scheduler=kwargs.get("scheduler"))
        dask.compute(chunks.written(dict(targets), lock or None), **kwargs)

    def _values(self) -> list:
        return [getattr(self, f.name) for f in fields(self)]

    def __len__(self) -> int:
        return len(self.distance)  # type: ignore[arg-type]

    def __repr__(self) -> str:
        if isinstance(self.distance, da.Array):
            return f"BatchArrays({len(self)} pairs in {self.distance.numblocks[0]} chunks, lazy)"
        return (
            f"BatchArrays({len(self)} pairs, {np.count_nonzero(np.asarray(self.colliding))} "
            f"colliding, {np.count_nonzero(np.asarray(self.certified))} certified)"
        )


def _check_target_shape(name: str, target: Any, expected: Tuple[float, ...]) -> None:
    """Raise before anything is computed unless ``target`` has the field's shape ``expected``:
    a shorter one failed in a chunk's write with NumPy's broadcasting message, which names no
    target, and a longer one was written in part with its tail left as it was.

    A field whose chunks' sizes dask does not know (NaN in ``expected``) is not checked.
    """
    shape = getattr(target, "shape", None)
    if shape is None:
        raise TypeError(f"targets[{name!r}] must be an array with a shape, such as a NumPy or "
                        f"Zarr array or an h5py dataset, got {type(target).__name__}")
    if any(math.isnan(size) for size in expected):
        return
    expected = tuple(int(size) for size in expected)
    if tuple(shape) != expected:
        raise ValueError(f"targets[{name!r}] has shape {tuple(shape)}, where the field "
                         f"{name!r} has shape {expected}: give a target of shape {expected}")


@dataclass(frozen=True)
class _Call:
    """What every chunk asks, in plain values: it travels to worker processes and names tasks."""

    query: str
    method: str
    tolerance: float
    seed: int
    parameters: Tuple[Tuple[str, Any], ...]
    threads: Optional[int]
    keywords: Tuple[Tuple[str, Any], ...]


def _answer(
    where: Tuple[slice], As: np.ndarray, Bs: np.ndarray, call: _Call
) -> Tuple[np.ndarray, ...]:
    """One chunk's fields, from the in-memory batch call; ``where`` is its slice of the pairs.

    ``As`` and ``Bs`` come as blockwise gives unconcatenated blocks, nested lists over their
    point and coordinate axes, each of one block (``_many`` rechunks them so): taking that block
    avoids the copy that concatenating a single block costs (about a tenth of the chunk's time).
    """
    As, Bs = As[0][0], Bs[0][0]
    query = queries.query(
        call.method, tolerance=call.tolerance, seed=call.seed, **dict(call.parameters)
    )
    result = getattr(query, f"{call.query}_many")(
        As, Bs, threads=call.threads, first_index=where[0].start, **dict(call.keywords)
    )
    return tuple(getattr(result, name) for name in _FIELDS)


def _write_chunk(
    answers: Tuple[np.ndarray, ...], targets: Mapping[str, Any], rows: slice, lock: Any
) -> None:
    with lock if lock is not None else contextlib.nullcontext():
        for index, name in enumerate(_FIELDS):
            if name in targets:
                targets[name][rows] = answers[index]


def _write(
    answers: Tuple[np.ndarray, ...], where: Tuple[slice], targets: Mapping[str, Any], lock: Any
) -> np.ndarray:
    _write_chunk(answers, targets, where[0], lock)
    return np.empty(0, bool)


def _answer_and_write(
    where: Tuple[slice],
    As: np.ndarray,
    Bs: np.ndarray,
    call: _Call,
    targets: Mapping[str, Any],
    lock: Any,
) -> np.ndarray:
    return _write(_answer(where, As, Bs, call), where, targets, lock)


@dataclass(frozen=True)
class _Chunks:
    """What a lazy ``BatchArrays`` is made of: ``answers``, whose chunks are the tuples of the
    fields, and, until they are persisted, the bodies and the call that answer them."""

    answers: da.Array
    bodies: Optional[Tuple[da.Array, da.Array, _Call]] = None

    def written(self, targets: Mapping[str, Any], lock: Any) -> da.Array:
        """Each chunk's fields written into ``targets`` (field name to array-like) by the task
        that answers the chunk (and, where the bodies are read in the graph, reads them)."""
        # The targets ride in the function: as an argument, dask would hash every byte of NumPy
        # targets (95 bytes per pair) to name them.
        common = dict(
            name=f"write-{uuid.uuid4().hex}",
            align_arrays=False,
            concatenate=False,
            adjust_chunks={"i": 0},
            meta=np.empty(0, bool),
        )
        where = ArraySliceDep(self.answers.chunks)
        if self.bodies is None:
            write = functools.partial(_write, targets=targets, lock=lock)
            return da.blockwise(write, "i", self.answers, "i", where, "i", **common)
        # One task answers and writes: _write over answers would be a second task per chunk, as
        # blockwise fuses no layers that differ in `concatenate` (answers contracts the point
        # axes, a write does not).
        As, Bs, call = self.bodies
        answer_and_write = functools.partial(
            _answer_and_write, call=call, targets=targets, lock=lock
        )
        return da.blockwise(
            answer_and_write, "i", where, "i", As, "ijk", Bs, "ilk", **common
        )


def _lazy(chunks: _Chunks) -> BatchArrays[da.Array]:
    """The fields as dask arrays, each of whose chunks takes its part of the chunk's answers;
    ``compute``, ``persist`` and ``store`` use the chunks' answers themselves."""
    token = chunks.answers.name.rsplit("-", 1)[-1]
    result = BatchArrays(
        *(
            da.blockwise(
                operator.getitem,
                "ij" if point else "i",
                chunks.answers,
                "i",
                index,
                None,
                new_axes={"j": 3} if point else None,
                name=f"{name}-{token}",
                meta=np.empty((0, 3) if point else (0,), dtype),
            )
            for index, (name, (dtype, point)) in enumerate(_FIELDS.items())
        )
    )
    object.__setattr__(result, "_chunks", chunks)
    return result


def _chunks_of(result: BatchArrays) -> Optional[_Chunks]:
    """What ``result`` is made of, or None for a BatchArrays made by hand or computed."""
    return getattr(result, "_chunks", None)


def _client_of(schedule: Any) -> Any:
    """The ``distributed.Client`` whose ``get`` ``schedule`` is, or None."""
    distributed = sys.modules.get("distributed")
    client = getattr(schedule, "__self__", None)
    return client if distributed is not None and isinstance(client, distributed.Client) else None


def _bodies(bodies: Any, name: str) -> da.Array:
    if not isinstance(bodies, da.Array):
        raise TypeError(
            f"{name} must be a dask array of shape (m, n, 3), got {type(bodies).__name__}; wrap "
            f"NumPy arrays and memmaps with dask.array.from_array({name}, chunks=(pairs, -1, -1))"
            " or read Zarr with dask.array.from_zarr"
        )
    if bodies.ndim != 3 or bodies.shape[2] != 3 or bodies.shape[1] == 0:
        raise ValueError(f"{name} must have shape (m, n, 3) with n >= 1, got {bodies.shape}")
    if bodies.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got an array of dtype {bodies.dtype}")
    if math.isnan(bodies.shape[0]):
        raise ValueError(
            f"{name} has chunks of unknown size; call {name}.compute_chunk_sizes() first"
        )
    return bodies


def _many(
    query: str,
    As: da.Array,
    Bs: da.Array,
    method: str,
    tolerance: float,
    seed: int,
    threads: Optional[int],
    keywords: Mapping[str, Any],
    parameters: Mapping[str, Any],
) -> BatchArrays[da.Array]:
    # A body's points in one block: chunks along the points or coordinates are joined here.
    As = _bodies(As, "As").rechunk({1: -1, 2: -1})
    Bs = _bodies(Bs, "Bs").rechunk({1: -1, 2: -1})
    if As.shape[0] != Bs.shape[0]:
        raise ValueError(
            f"As and Bs must hold the same number of pairs, got {As.shape[0]} and {Bs.shape[0]}"
        )
    # Arguments are checked now, by the core, rather than in every chunk when computed.
    checked = queries.query(method, tolerance=tolerance, seed=seed, **parameters)
    if query not in queries.METHODS[method].queries:
        able = [name for name, info in queries.METHODS.items() if query in info.queries]
        raise ValueError(f"{query} is not available with method {method!r}; use one of {able}")
    empty = np.empty((0, 1, 3))
    getattr(checked, f"{query}_many")(empty, empty, threads=threads, **keywords)

    call = _Call(
        query,
        method,
        tolerance,
        seed,
        tuple(sorted(parameters.items())),
        threads,
        tuple(sorted(keywords.items())),
    )
    # Where As and Bs are chunked differently, both are cut at the boundaries of either; each
    # chunk is then told its slice of the pairs, so it knows where it starts.
    _, (As, Bs) = da.core.unify_chunks(As, "ijk", Bs, "ilk")
    # One task per chunk answers it and gives a tuple of fields (as dask.array.apply_gufunc does
    # for several outputs): computed, persisted or stored together, the fields cost one task per
    # chunk; a field computed alone takes its part of the tuple.
    answers = da.blockwise(
        _answer,
        "i",
        ArraySliceDep((As.chunks[0],)),
        "i",
        As,
        "ijk",
        Bs,
        "ilk",
        call=call,
        token=f"{query}_many",
        concatenate=False,
        align_arrays=False,
        meta=tuple(np.empty((0, 3) if point else (0,), dtype) for dtype, point in _FIELDS.values()),
    )
    return _lazy(_Chunks(answers, (As, Bs, call)))


def distance_many(
    As: da.Array,
    Bs: da.Array,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    threads: Optional[int] = 1,
    **parameters: Unpack[Parameters],
) -> BatchArrays[da.Array]:
    """``swarmcollide.distance_many`` chunk by chunk, lazily.

    Parameters
    ----------
    As, Bs : dask.array.Array, shape (m, n, 3)
        The bodies, pairwise, chunked along the pair axis (the first); a chunk should hold 100 ms
        of work or more (docs/dask.md). Where the chunks of As and Bs differ, both are cut at
        the boundaries of either. The number of points ``n`` may differ between As and Bs.
    threads : int, optional
        C++ threads per chunk. The default, 1, leaves the parallelism to Dask (one chunk per
        core); None uses every hardware thread in each chunk.
    method, tolerance, seed, **parameters
        As for ``swarmcollide.distance``, checked now.

    Returns
    -------
    BatchArrays
        Dask arrays chunked as the pairs; bitwise the fields of
        ``swarmcollide.distance_many(As, Bs, ...)`` once computed.

    Raises
    ------
    TypeError, ValueError
        Now, for arguments the in-memory call would refuse, and when computed, for the pair with
        the lowest global index that fails in the first chunk to fail (``"pair 12345: ..."``,
        ``"As[12345]: ..."``), as the in-memory call raises it.

    Examples
    --------
    >>> import dask.array as da, swarmcollide.dask as scd
    >>> rng = da.random.default_rng(0)
    >>> As = rng.normal(size=(1000, 8, 3), chunks=(250, 8, 3))
    >>> Bs = rng.normal(size=(1000, 8, 3), chunks=(250, 8, 3)) + 5.0
    >>> r = scd.distance_many(As, Bs)
    >>> r.distance
    dask.array<distance, shape=(1000,), dtype=float64, chunksize=(250,), chunktype=numpy.ndarray>
    >>> bool((r.distance > 0).all().compute())
    True
    """
    return _many("distance", As, Bs, method, tolerance, seed, threads, {}, parameters)


def collide_many(
    As: da.Array,
    Bs: da.Array,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    threads: Optional[int] = 1,
    escalate: bool = True,
    **parameters: Unpack[Parameters],
) -> BatchArrays[da.Array]:
    """``swarmcollide.collide_many`` chunk by chunk, lazily; the keywords of ``distance_many``.

    Examples
    --------
    >>> import dask.array as da, numpy as np, swarmcollide.dask as scd
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> As = np.stack([cube] * 4)
    >>> Bs = np.stack([cube + [k * 0.6, 0, 0] for k in range(4)])
    >>> r = scd.collide_many(*(da.from_array(x, chunks=(2, -1, -1)) for x in (As, Bs)))
    >>> r.colliding.compute().tolist()
    [True, True, False, False]
    """
    return _many(
        "collide", As, Bs, method, tolerance, seed, threads, {"escalate": escalate}, parameters
    )


def signed_distance_many(
    As: da.Array,
    Bs: da.Array,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    threads: Optional[int] = 1,
    **parameters: Unpack[Parameters],
) -> BatchArrays[da.Array]:
    """``swarmcollide.signed_distance_many`` chunk by chunk, lazily; the keywords of
    ``distance_many``.

    Examples
    --------
    >>> import dask.array as da, numpy as np, swarmcollide.dask as scd
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> As = np.stack([cube] * 4)
    >>> Bs = np.stack([cube + [k * 0.5, 0, 0] for k in range(4)])
    >>> r = scd.signed_distance_many(*(da.from_array(x, chunks=(2, -1, -1)) for x in (As, Bs)))
    >>> r.distance.compute().round(9).tolist()
    [-1.0, -0.5, 0.0, 0.5]
    """
    return _many("signed_distance", As, Bs, method, tolerance, seed, threads, {}, parameters)

