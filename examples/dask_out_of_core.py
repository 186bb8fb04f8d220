"""Distances between more pairs of bodies than fit in memory, from files on disk and back.

The bodies are written to disk chunk by chunk (as NumPy .npy files or Zarr arrays), read back
lazily as dask arrays, answered chunk by chunk by ``swarmcollide.dask.distance_many`` and the
answers written to disk chunk by chunk: at any time each worker holds a few chunks, whatever the
number of pairs. Small by default; for example, a hundred million pairs (about 40 GB of bodies
and 6 GB of answers) on a cluster that sees the same folder::

    python examples/dask_out_of_core.py --pairs 100_000_000 --chunk 100_000 --store zarr \\
        --dir /shared/pairs --scheduler tcp://scheduler:8786

``--scheduler local-cluster`` starts a cluster of worker processes on this machine instead, and
``--check`` compares the answers on disk with the in-memory call (small sizes only: it loads
everything).
"""

from __future__ import annotations

import argparse
import contextlib
import tempfile
import time
from pathlib import Path
from typing import Any, Dict, Iterator, Tuple

import dask.array as da
import numpy as np

import swarmcollide as sc
import swarmcollide.dask as scd

FIELDS = ("distance", "lower_bound", "point_a", "point_b", "colliding", "certified")


class NpyFile:
    """A .npy file, opened as a memmap where it is read or written.

    It travels to worker processes as its path, where a memmap would travel as a copy of its
    data, so reads and writes reach the file from any process that sees it.
    """

    def __init__(self, path: Path) -> None:
        self.path = str(path)
        opened = np.load(self.path, mmap_mode="r")
        self.shape, self.dtype, self.ndim = opened.shape, opened.dtype, opened.ndim

    def __getitem__(self, region: Any) -> np.ndarray:
        return np.load(self.path, mmap_mode="r")[region]

    def __setitem__(self, region: Any, values: np.ndarray) -> None:
        opened = np.load(self.path, mmap_mode="r+")
        opened[region] = values
        opened.flush()


def create(path: Path, store: str, shape: Tuple[int, ...], chunk: int, dtype: Any) -> Any:
    """An array on disk to be written in chunks of ``chunk`` rows."""
    if store == "zarr":
        import zarr

        return zarr.open_array(str(path), mode="w", shape=shape,
                               chunks=(chunk,) + shape[1:], dtype=dtype)
    np.lib.format.open_memmap(path, mode="w+", dtype=dtype, shape=shape).flush()
    return NpyFile(path)


def open_lazily(path: Path, store: str, chunk: int) -> da.Array:
    if store == "zarr":
        return da.from_zarr(str(path))
    opened = NpyFile(path)
    return da.from_array(opened, chunks=(chunk,) + opened.shape[1:])


def write_bodies(folder: Path, store: str, pairs: int, chunk: int, vertices: int) -> None:
    """Random pairs of point clouds, some overlapping, made and written one chunk at a time."""
    suffix = ".zarr" if store == "zarr" else ".npy"
    As = create(folder / f"As{suffix}", store, (pairs, vertices, 3), chunk, np.float64)
    Bs = create(folder / f"Bs{suffix}", store, (pairs, vertices, 3), chunk, np.float64)
    for index, start in enumerate(range(0, pairs, chunk)):
        count = min(chunk, pairs - start)
        rng = np.random.default_rng([7, index])
        As[start:start + count] = rng.normal(size=(count, vertices, 3))
        Bs[start:start + count] = (rng.normal(size=(count, vertices, 3))
                                   + rng.uniform(-3, 3, size=(count, 1, 3)))


def answer_on_disk(folder: Path, store: str, chunk: int) -> Dict[str, Any]:
    """Every pair's answer, read and written chunk by chunk; returns where each field went."""
    suffix = ".zarr" if store == "zarr" else ".npy"
    As = open_lazily(folder / f"As{suffix}", store, chunk)
    Bs = open_lazily(folder / f"Bs{suffix}", store, chunk)
    result = scd.distance_many(As, Bs)
    targets = {}
    for name in FIELDS:
        field = getattr(result, name)
        targets[name] = create(folder / f"{name}{suffix}", store, field.shape, chunk, field.dtype)
    # The chunks of the answers are the chunks of the targets: no two writers share one.
    result.store(targets, lock=False)
    return targets


@contextlib.contextmanager
def scheduler(name: str, workers: int) -> Iterator[str]:
    """Where the chunks are answered, as a description."""
    if name == "threads":
        import dask

        with dask.config.set(scheduler="threads"):
            yield "the threaded scheduler"
        return
    from distributed import Client, LocalCluster

    if name == "local-cluster":
        with LocalCluster(n_workers=workers, threads_per_worker=1, host="127.0.0.1",
                          dashboard_address="127.0.0.1:0") as cluster, Client(cluster):
            yield f"a local cluster of {workers} worker processes"
    else:
        with Client(name) as client:
            yield f"the cluster at {name} ({len(client.scheduler_info()['workers'])} workers)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pairs", type=int, default=200_000)
    parser.add_argument("--chunk", type=int, default=50_000, help="pairs per chunk")
    parser.add_argument("--vertices", type=int, default=8, help="points per body")
    parser.add_argument("--store", choices=["npy", "zarr"], default="npy")
    parser.add_argument("--scheduler", default="threads",
                        help="threads, local-cluster, or a scheduler's address")
    parser.add_argument("--workers", type=int, default=2, help="processes of a local cluster")
    parser.add_argument("--dir", type=Path, help="where the files go (default: a temporary one)")
    parser.add_argument("--check", action="store_true",
                        help="compare with the in-memory call (loads everything)")
    args = parser.parse_args()

    with contextlib.ExitStack() as stack:
        folder = args.dir or Path(stack.enter_context(tempfile.TemporaryDirectory()))
        folder.mkdir(parents=True, exist_ok=True)
        write_bodies(folder, args.store, args.pairs, args.chunk, args.vertices)
        where = stack.enter_context(scheduler(args.scheduler, args.workers))
        start = time.perf_counter()
        targets = answer_on_disk(folder, args.store, args.chunk)
        seconds = time.perf_counter() - start
        suffix = ".zarr" if args.store == "zarr" else ".npy"
        colliding = open_lazily(folder / f"colliding{suffix}", args.store, args.chunk)
        distance = open_lazily(folder / f"distance{suffix}", args.store, args.chunk)
        print(f"{args.pairs} pairs of {args.vertices}-point bodies in {args.store} files in "
              f"{folder}, {len(range(0, args.pairs, args.chunk))} chunks, on {where}: "
              f"{seconds:.2f} s ({args.pairs / seconds:,.0f} pairs/s); "
              f"{int(colliding.sum().compute())} colliding, "
              f"largest distance {float(distance.max().compute()):.3f}")
        if args.check:
            As = np.asarray(open_lazily(folder / f"As{suffix}", args.store, args.chunk))
            Bs = np.asarray(open_lazily(folder / f"Bs{suffix}", args.store, args.chunk))
            expected = sc.distance_many(As, Bs)
            for name, target in targets.items():
                if np.asarray(target[:]).tobytes() != getattr(expected, name).tobytes():
                    raise SystemExit(f"{name} on disk differs from the in-memory call")
            print("the answers on disk are bitwise equal to the in-memory call")


if __name__ == "__main__":
    main()
