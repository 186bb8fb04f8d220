"""swarmcollide.dask against the in-memory batch call: a million pairs of 8-point bodies with
method "dual", on in-memory threads, on Dask's threaded scheduler and on a distributed
LocalCluster of one and of two worker processes.

Every configuration answers the same pairs (made chunk by chunk from fixed seeds) and is timed
from the call to the answers; configurations take turns, each repeated, and the median is kept.
- in memory: ``sc.distance_many(As, Bs, threads=t)`` on NumPy arrays, t = 1 and every core.
- threads: ``scd.distance_many`` on dask arrays wrapping the same NumPy arrays, every field
  computed to NumPy with the threaded scheduler (one thread per core, one C++ thread per chunk).
- cluster: the bodies made and kept on the workers beforehand (as data of that size would be),
  then every field either kept on the workers (``persist``: the cluster's own throughput) or
  gathered to the client (``compute``: plus moving 115 bytes per pair between processes).
The overhead per chunk is the time beyond the in-memory call at the same number of cores, per
chunk and core: ``(seconds - ideal) * cores / chunks``, where ideal is the in-memory call on all
those cores (threads) or the one-thread call divided by the workers (cluster).

Writes a JSON file, prints a Markdown section, and with ``--results-md`` puts that section into
bench/RESULTS.md (replacing its previous version). Run it when the machine is quiet: the load
averages before and after are recorded.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import statistics
import time
from pathlib import Path
from typing import Callable, Dict, List

import dask
import dask.array as da
import distributed
import numpy as np
from distributed import Client, LocalCluster, wait

import swarmcollide as sc
import swarmcollide.dask as scd

VERTICES = 8
METHOD = "dual"
BLOCK = 10_000  # pairs made per generator call; every chunk size here is a multiple of it
MARKER = "<!-- bench/dask_batch.py -->"


def make_block(index: int, which: int) -> np.ndarray:
    """Block ``index`` of the A bodies (which=0) or the B bodies (which=1): half of the pairs
    overlap, as in bench/batch.py."""
    rng = np.random.default_rng([index, which])
    bodies = rng.normal(size=(BLOCK, VERTICES, 3))
    if which:
        bodies += np.random.default_rng([index, 2]).uniform(-3, 3, size=(BLOCK, 1, 3))
    return bodies


def lazy_bodies(pairs: int, which: int) -> da.Array:
    blocks = [da.from_delayed(dask.delayed(make_block)(i, which), (BLOCK, VERTICES, 3), float)
              for i in range(pairs // BLOCK)]
    return da.concatenate(blocks)


def timed(run: Callable[[], object]) -> float:
    start = time.perf_counter()
    run()
    return time.perf_counter() - start


def settle(client: Client, tasks: int) -> None:
    """Wait until the scheduler holds no more than ``tasks`` tasks again, having forgotten the
    answers of the last run, which the next would otherwise find computed under the same keys."""
    while client.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks)) > tasks:
        time.sleep(0.01)


def loadavg() -> List[float]:
    return [round(x, 2) for x in os.getloadavg()]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="200,000 pairs, 2 repeats")
    parser.add_argument("--json", type=Path, required=True, help="where to write the results")
    parser.add_argument("--results-md", type=Path, help="put the section into this Markdown file")
    parser.add_argument("--repeats", type=int, help="runs per configuration (default 5)")
    args = parser.parse_args()
    pairs = 200_000 if args.quick else 1_000_000
    repeats = args.repeats or (2 if args.quick else 5)
    cores = os.cpu_count() or 1
    thread_chunks = [c for c in (1_000, 10_000, 100_000, 250_000) if c <= pairs]
    cluster_chunks = [c for c in (10_000, 100_000) if c <= pairs]
    load_before = loadavg()

    As = np.concatenate([make_block(i, 0) for i in range(pairs // BLOCK)])
    Bs = np.concatenate([make_block(i, 1) for i in range(pairs // BLOCK)])
    sc.distance_many(As[:BLOCK], Bs[:BLOCK])  # load and warm up

    rows: Dict[str, Dict] = {}

    def record(key: str, seconds: float, **info) -> None:
        rows.setdefault(key, {"seconds": [], **info})["seconds"].append(round(seconds, 4))

    # In memory and the threaded scheduler, taking turns.
    lazy = {c: (da.from_array(As, chunks=(c, -1, -1)), da.from_array(Bs, chunks=(c, -1, -1)))
            for c in thread_chunks}
    for _ in range(repeats):
        for threads in (1, None):
            record(f"memory-{threads or cores}",
                   timed(lambda: sc.distance_many(As, Bs, method=METHOD, threads=threads)),
                   kind="in memory", cores=threads or cores, chunk=None)
        for chunk in thread_chunks:
            record(f"threads-{chunk}",
                   timed(lambda: scd.distance_many(*lazy[chunk], method=METHOD)
                         .compute(scheduler="threads")),
                   kind="threaded scheduler", cores=cores, chunk=chunk)

    # Clusters of one and two processes, one thread each, bodies made and kept on the workers.
    for workers in (1, 2):
        kind = f"LocalCluster, {workers} process{'es' if workers > 1 else ''}"
        with LocalCluster(n_workers=workers, threads_per_worker=1, host="127.0.0.1",
                          dashboard_address="127.0.0.1:0") as cluster, Client(cluster) as client:
            resident = {}
            for chunk in cluster_chunks:
                resident[chunk] = client.persist(
                    [lazy_bodies(pairs, which).rechunk((chunk, -1, -1)) for which in (0, 1)])
                wait(resident[chunk])
            tasks = client.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks))
            for chunk in cluster_chunks:
                scd.distance_many(*(x[:10] for x in resident[chunk])).compute()  # warm up
            settle(client, tasks)
            for _ in range(repeats):
                for chunk in cluster_chunks:
                    result = scd.distance_many(*resident[chunk], method=METHOD)

                    def kept():
                        wait(client.persist(list(vars(result).values())))

                    record(f"cluster{workers}-{chunk}-persist", timed(kept), kind=kind,
                           cores=workers, chunk=chunk, answers="kept on the workers")
                    settle(client, tasks)
                    record(f"cluster{workers}-{chunk}-compute", timed(result.compute), kind=kind,
                           cores=workers, chunk=chunk, answers="gathered to the client")
                    settle(client, tasks)

    one_thread = statistics.median(rows["memory-1"]["seconds"])
    all_threads = statistics.median(rows[f"memory-{cores}"]["seconds"])
    for row in rows.values():
        row["median"] = statistics.median(row["seconds"])
        row["pairs_per_second"] = round(pairs / row["median"])
        if row["chunk"]:
            ideal = all_threads if row["kind"] == "threaded scheduler" else one_thread / row["cores"]
            chunks = -(-pairs // row["chunk"])
            row["overhead_per_chunk_ms"] = round(
                (row["median"] - ideal) * row["cores"] / chunks * 1e3, 2)
    results = {
        "pairs": pairs,
        "vertices": VERTICES,
        "method": METHOD,
        "repeats": repeats,
        "cores": cores,
        "machine": platform.processor() or platform.machine(),
        "load_average_before": load_before,
        "load_average_after": loadavg(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "versions": {"swarmcollide": sc.__version__, "dask": dask.__version__,
                     "distributed": distributed.__version__, "numpy": np.__version__},
        "rows": rows,
    }
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(json.dumps(results, indent=2) + "\n")
    section = markdown(results)
    print(section)
    if args.results_md:
        put_section(args.results_md, section)
    return 0


def markdown(results: Dict) -> str:
    rows = results["rows"]
    memory = rows[f"memory-{results['cores']}"]
    lines = [
        MARKER,
        "## Batches on Dask (bench/dask_batch.py)",
        "",
        f"{results['pairs']:,} pairs of {results['vertices']}-point bodies, method "
        f"`{results['method']}`, every field computed; median of {results['repeats']} runs taken "
        f"in turns; {results['cores']} cores; load average {results['load_average_before']} "
        f"before, {results['load_average_after']} after; {results['date']}; dask "
        f"{results['versions']['dask']}. Overhead per chunk: time beyond the in-memory call on "
        "the same cores, times the cores, per chunk.",
        "",
        "| configuration | pairs per chunk | cores | answers | seconds | pairs/s | vs in memory "
        "| overhead per chunk |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for row in rows.values():
        chunk = f"{row['chunk']:,}" if row["chunk"] else "all"
        overhead = f"{row['overhead_per_chunk_ms']:.1f} ms" if row["chunk"] else ""
        lines.append(
            f"| {row['kind']} | {chunk} | {row['cores']} | {row.get('answers', 'NumPy')} "
            f"| {row['median']:.3f} | {row['pairs_per_second']:,} "
            f"| {row['pairs_per_second'] / memory['pairs_per_second']:.2f}x | {overhead} |"
        )
    return "\n".join(lines) + "\n"


def put_section(path: Path, section: str) -> None:
    """Replace the section after MARKER (to the next '## ' heading or the end), or append it."""
    text = path.read_text() if path.exists() else ""
    if MARKER in text:
        before, after = text.split(MARKER, 1)
        rest = after.split("\n## ", 2)
        after = "\n## " + rest[2] if len(rest) > 2 else ""
        text = before + section + after
    else:
        text = text.rstrip("\n") + "\n\n" + section
    path.write_text(text)


if __name__ == "__main__":
    raise SystemExit(main())
