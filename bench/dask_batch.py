"""swarmcollide.dask against the in-memory batch call: a million pairs of 8-point bodies with
method "dual", on in-memory threads, on Dask's threaded scheduler and on distributed LocalClusters
of one and of two worker processes.

Every configuration answers the same pairs (made block by block from fixed seeds), gives
bitwise the in-memory answers (checked once for each before timing) and is timed from the call
to the answers:
- in memory: ``sc.distance_many(As, Bs, threads=t)`` on NumPy arrays, t = 1 and every core.
- threaded scheduler: ``scd.distance_many(...).compute(scheduler="threads")`` on dask arrays
  wrapping the same NumPy arrays, every field to NumPy (one Dask thread per core, one C++ thread
  per chunk).
- LocalCluster: the bodies made and kept on the workers beforehand (as data of that size would
  be), one thread per worker, each chunk's A and B made by one task and the chunks dealt to the
  workers in turn (where docs/dask.md says bodies should be: a chunk whose A and B are on two
  workers moves one of them first); every field either kept on the workers (``persist()``: the
  cluster's own throughput) or gathered to the client (``compute()``: plus moving 95 bytes per
  pair between processes).
The machine is shared, so the configurations take turns in rounds (both clusters stay up
throughout): first, in short rounds, those the targets compare (in memory, and chunks of 100,000
pairs), then the other chunk sizes in a third as many rounds. Each target's ratio is taken within
each round, where the others' load is about the same for both sides, and the median over rounds
is reported; the in-memory speed-up from one core to every core says how many cores the run
really had. Times are medians over rounds, with the fastest run beside them. The
overhead per chunk is the time beyond the in-memory call on the same cores, per chunk and core:
``(seconds - ideal) * cores / chunks``, where ideal is the in-memory call on every core (threaded
scheduler) or the one-thread call divided by the workers (cluster).

Writes a JSON file in bench/record.py's format (a row per configuration; the load averages at
the start and the end are in its machine record); bench/report.py renders it.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import time
from pathlib import Path
from typing import Callable, Dict, List, Tuple

import dask
import dask.array as da
import numpy as np
from distributed import Client, LocalCluster, wait

import record
import swarmcollide as sc
import swarmcollide.dask as scd

VERTICES = 8
METHOD = "dual"
BLOCK = 10_000  # pairs made per generator call; every chunk size here is a multiple of it


def make_block(index: int, which: int) -> np.ndarray:
    """Block ``index`` of the A bodies (which=0) or the B bodies (which=1): unit point clouds,
    B's moved by up to 3 along each axis, so that about a quarter of the pairs overlap."""
    rng = np.random.default_rng([index, which])
    bodies = rng.normal(size=(BLOCK, VERTICES, 3))
    if which:
        bodies += np.random.default_rng([index, 2]).uniform(-3, 3, size=(BLOCK, 1, 3))
    return bodies


def make_chunk(first_block: int, blocks: int) -> Tuple[np.ndarray, np.ndarray]:
    """The A and the B bodies of ``blocks`` blocks from ``first_block`` on, made together."""
    return tuple(np.concatenate([make_block(first_block + j, which) for j in range(blocks)])
                 for which in (0, 1))


def placed_bodies(pairs: int, chunk: int, workers: List[str]) -> List[da.Array]:
    """The A and the B bodies as dask arrays of ``chunk`` pairs per chunk, each chunk's A and B
    made by one task on one worker and the chunks dealt to the workers in turn: where reading
    each chunk in the graph would put them, and where docs/dask.md says persisted bodies
    should be (a chunk whose A and B are on two workers moves one of them before it is
    answered)."""
    parts: Tuple[List[da.Array], List[da.Array]] = ([], [])
    for k, start in enumerate(range(0, pairs, chunk)):
        with dask.annotate(workers=[workers[k % len(workers)]], allow_other_workers=False):
            both = dask.delayed(make_chunk, nout=2, pure=True)(start // BLOCK, chunk // BLOCK)
            for which, part in enumerate(parts):
                part.append(da.from_delayed(both[which], (chunk, VERTICES, 3), float))
    return [da.concatenate(part) for part in parts]


def warm_up() -> None:
    """Import swarmcollide.dask in a worker and answer a few pairs there."""
    bodies = np.stack([make_block(0, which)[:10] for which in (0, 1)])
    sc.distance_many(*bodies, method=METHOD)


def timed(run: Callable[[], object]) -> float:
    start = time.perf_counter()
    run()
    return time.perf_counter() - start


def scheduler_tasks(client: Client) -> int:
    return client.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks))


def settle(client: Client, tasks: int) -> None:
    """Wait until the scheduler holds no more than ``tasks`` tasks again, having forgotten the
    answers of the last run, which the next would otherwise find computed under the same keys."""
    while scheduler_tasks(client) > tasks:
        time.sleep(0.01)


class Cluster:
    """A LocalCluster of ``workers`` one-thread processes holding the bodies in each chunking."""

    def __init__(self, stack: contextlib.ExitStack, workers: int, pairs: int, chunks: List[int]):
        self.workers = workers
        cluster = stack.enter_context(LocalCluster(
            n_workers=workers, threads_per_worker=1, host="127.0.0.1",
            dashboard_address="127.0.0.1:0"))
        self.client = stack.enter_context(Client(cluster, set_as_default=False))
        addresses = sorted(self.client.scheduler_info()["workers"])
        self.bodies = {chunk: self.client.persist(placed_bodies(pairs, chunk, addresses))
                       for chunk in chunks}
        with self.client.as_current():
            wait(list(self.bodies.values()))
        self.client.run(warm_up)
        self.tasks = scheduler_tasks(self.client)

    def check(self, expected: sc.BatchResult) -> None:
        """Every chunking's answers on this cluster are bitwise those of the in-memory call."""
        for chunk, bodies in self.bodies.items():
            got = scd.distance_many(*bodies, method=METHOD).compute(scheduler=self.client)
            for name in vars(got):
                if getattr(got, name).tobytes() != getattr(expected, name).tobytes():
                    raise AssertionError(f"{self.workers} workers, chunks of {chunk}: {name} "
                                         "differs from the in-memory call")
        settle(self.client, self.tasks)

    def kept(self, chunk: int) -> float:
        result = scd.distance_many(*self.bodies[chunk], method=METHOD)
        with self.client.as_current():
            seconds = timed(lambda: wait(result.persist(scheduler=self.client).distance))
        settle(self.client, self.tasks)
        return seconds

    def gathered(self, chunk: int) -> float:
        result = scd.distance_many(*self.bodies[chunk], method=METHOD)
        seconds = timed(lambda: result.compute(scheduler=self.client))
        settle(self.client, self.tasks)
        return seconds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="200,000 pairs, fewer rounds")
    parser.add_argument("--json", type=Path, required=True, help="where to write the results")
    parser.add_argument("--rounds", type=int,
                        help="rounds of the targets' configurations (default 9; the other chunk "
                             "sizes get a third as many)")
    args = parser.parse_args()
    pairs = 200_000 if args.quick else 1_000_000
    rounds = args.rounds or (2 if args.quick else 9)
    target_chunk = 100_000
    cores = os.cpu_count() or 1
    thread_chunks = [c for c in (1_000, 10_000, 100_000, 250_000) if c <= pairs]
    cluster_chunks = [c for c in (10_000, 100_000) if c <= pairs]
    load_before = os.getloadavg()

    As = np.concatenate([make_block(i, 0) for i in range(pairs // BLOCK)])
    Bs = np.concatenate([make_block(i, 1) for i in range(pairs // BLOCK)])
    expected = sc.distance_many(As, Bs, method=METHOD)  # also loads and warms up
    lazy = {c: (da.from_array(As, chunks=(c, -1, -1)), da.from_array(Bs, chunks=(c, -1, -1)))
            for c in thread_chunks}
    for chunk, bodies in lazy.items():  # the answers timed are the in-memory ones
        got = scd.distance_many(*bodies, method=METHOD).compute(scheduler="threads")
        if any(getattr(got, n).tobytes() != getattr(expected, n).tobytes() for n in vars(got)):
            raise AssertionError(f"threaded scheduler, chunks of {chunk}: answers differ")

    configurations: Dict[str, Dict] = {}

    def add(key: str, run: Callable[[], float], **info) -> None:
        # The targets' configurations take turns in short rounds; the other chunk sizes after.
        target = info["chunk"] in (None, target_chunk)
        configurations[key] = {"run": run, "seconds": [], "target": target, **info}

    for threads in (1, cores):
        add(f"memory-{threads}",
            lambda t=threads: timed(lambda: sc.distance_many(As, Bs, method=METHOD, threads=t)),
            kind="in memory", cores=threads, chunk=None, answers="NumPy")
    for chunk in thread_chunks:
        add(f"threads-{chunk}",
            lambda c=chunk: timed(lambda: scd.distance_many(*lazy[c], method=METHOD)
                                  .compute(scheduler="threads")),
            kind="threaded scheduler", cores=cores, chunk=chunk, answers="NumPy")
    with contextlib.ExitStack() as stack:
        clusters = {workers: Cluster(stack, workers, pairs, cluster_chunks) for workers in (1, 2)}
        for cluster in clusters.values():
            cluster.check(expected)
        del expected
        # The two clusters' runs that a ratio compares come one after the other.
        for chunk in cluster_chunks:
            for answers, where in (("kept", "kept on the workers"),
                                   ("gathered", "gathered to the client")):
                for workers, cluster in clusters.items():
                    add(f"cluster{workers}-{chunk}-{answers}",
                        lambda c=chunk, k=cluster, a=answers: getattr(k, a)(c),
                        kind=f"LocalCluster, {workers} process{'es' if workers > 1 else ''}",
                        cores=workers, chunk=chunk, answers=where)
        for phase, count in ((True, rounds), (False, max(1, rounds // 3))):
            for _ in range(count):
                for configuration in configurations.values():
                    if configuration["target"] == phase:
                        configuration["seconds"].append(round(configuration["run"](), 4))

    for configuration in configurations.values():
        del configuration["run"], configuration["target"]
    results = summarise(configurations, pairs, rounds, cores)
    rows = [{"key": key, **row} for key, row in results.pop("rows").items()]
    written = record.write(args.json, "dask_batch", rows, load_start=load_before, **results)
    print(json.dumps(written, indent=1))
    return 0


def summarise(rows: Dict[str, Dict], pairs: int, rounds: int, cores: int) -> Dict:
    one_thread = rows["memory-1"]["seconds"]
    every_core = rows[f"memory-{cores}"]["seconds"]
    for row in rows.values():
        row["median"] = statistics.median(row["seconds"])
        row["fastest"] = min(row["seconds"])
        row["pairs_per_second"] = round(pairs / row["median"])
        if row["chunk"]:
            ideal = (statistics.median(every_core) if row["kind"] == "threaded scheduler"
                     else statistics.median(one_thread) / row["cores"])
            chunks = -(-pairs // row["chunk"])
            row["chunks"] = chunks
            row["work_per_chunk_ms"] = round(statistics.median(one_thread) / chunks * 1e3, 1)
            row["overhead_per_chunk_ms"] = round(
                (row["median"] - ideal) * row["cores"] / chunks * 1e3, 1)

    # A round had both cores free when the in-memory call was about twice as fast on both.
    free = [one / every >= 0.9 * cores for one, every in zip(one_thread, every_core)]
    comparisons = [
        ("memory_every_core_vs_one", "in memory, every core / one core, throughput",
         "(no target: the cores the run had)", "memory-1", f"memory-{cores}"),
        ("threaded_vs_memory", "threaded scheduler / in memory, throughput, chunks of 100,000",
         ">= 0.90", f"memory-{cores}", "threads-100000"),
        ("cluster_2_vs_1_kept", "LocalCluster 2 processes / 1, answers kept, chunks of 100,000",
         ">= 1.7", "cluster1-100000-kept", "cluster2-100000-kept"),
        ("cluster_2_vs_1_gathered",
         "LocalCluster 2 processes / 1, answers gathered, chunks of 100,000", ">= 1.7",
         "cluster1-100000-gathered", "cluster2-100000-gathered"),
    ]
    targets = {}
    for key, name, target, numerator, denominator in comparisons:
        if numerator in rows and denominator in rows:
            ratios = [a / b for a, b in zip(rows[numerator]["seconds"],
                                            rows[denominator]["seconds"])]
            quiet = [ratio for ratio, both in zip(ratios, free) if both]
            targets[key] = {
                "name": name,
                "target": target,
                "within_rounds": round(statistics.median(ratios), 3),
                "rounds_with_every_core_free": len(quiet),
                "within_those_rounds": round(statistics.median(quiet), 3) if quiet else None,
                "fastest": round(rows[numerator]["fastest"] / rows[denominator]["fastest"], 3),
            }
    return {"pairs": pairs, "vertices": VERTICES, "method": METHOD, "rounds": rounds,
            "cores": cores, "rows": rows, "targets": targets}


if __name__ == "__main__":
    raise SystemExit(main())
