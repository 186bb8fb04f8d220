"""Batch queries: sc.distance_many against the plain C++ loop over the same calls, against a Python
loop over python-fcl and coal, on one thread and two, and its peak memory for a million pairs.

Every body is fresh (a new array of points per pair), so each pair pays for two hulls and two
FCL shapes, as the Python loops do. distance_many is timed on one thread (the like-for-like
comparison with the single-threaded loops) and with its default, threads=None (every hardware
thread); both are recorded and labelled.

Writes a JSON file (bench/record.py's format, a row per method of the thread scaling) that
bench/report.py turns into a section of bench/RESULTS.md.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Callable, Dict, List

import numpy as np
from tqdm import tqdm

import record
import swarmcollide as sc

VERTICES = 8
# Pairs per method for the thread-scaling runs: about a second of work each on one thread.
SCALING_PAIRS = {"ipso": 4000, "pso": 4000, "penalty": 1000, "dual": 40000, "exact": 20000,
                 "fcl": 20000}


def make_pairs(count: int, seed: int = 0):
    """``count`` pairs of 8-point clouds of unit size, centres up to 3 apart: apart and overlapping."""
    rng = np.random.default_rng(seed)
    As = rng.normal(size=(count, VERTICES, 3))
    Bs = rng.normal(size=(count, VERTICES, 3)) + rng.uniform(-3, 3, size=(count, 1, 3))
    return As, Bs


def median_seconds(run: Callable[[], object], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def interleaved_seconds(first: Callable[[], object], second: Callable[[], object],
                        repeats: int) -> tuple:
    """The median seconds of `first` and of `second`, run in turn (which goes first alternates),
    and the median over rounds of each round's first / second: the load of a shared machine
    changes between two medians taken one after the other (session 57 had 1 thread against 2 at
    2.2x on the swarms that way)."""
    firsts, seconds = [], []
    for round_index in range(repeats):
        order = [(first, firsts), (second, seconds)]
        for run, times in order if round_index % 2 == 0 else reversed(order):
            start = time.perf_counter()
            run()
            times.append(time.perf_counter() - start)
    ratio = statistics.median(a / b for a, b in zip(firsts, seconds))
    return statistics.median(firsts), statistics.median(seconds), ratio


def cpp_loop_seconds(binary: Path, As: np.ndarray, Bs: np.ndarray, method: str, repeats: int):
    with tempfile.TemporaryDirectory() as folder:
        a_file, b_file = Path(folder) / "a.bin", Path(folder) / "b.bin"
        np.ascontiguousarray(As, dtype=np.float64).tofile(a_file)
        np.ascontiguousarray(Bs, dtype=np.float64).tofile(b_file)
        done = subprocess.run(
            [str(binary), str(a_file), str(b_file), str(len(As)), str(VERTICES), method,
             str(repeats)],
            check=True, capture_output=True, text=True,
        )
    return json.loads(done.stdout)


def python_fcl_loop(As: np.ndarray, Bs: np.ndarray) -> List[float]:
    """What a Python user of python-fcl writes: a hull per body, then one query per pair."""
    import fcl
    from scipy.spatial import ConvexHull

    def shape(points):
        hull = ConvexHull(points)
        faces = np.hstack([np.full((len(hull.simplices), 1), 3), hull.simplices]).ravel()
        return fcl.CollisionObject(fcl.Convex(points, len(hull.simplices), faces))

    out = []
    for a, b in zip(tqdm(As, desc="python-fcl loop", leave=False), Bs):
        request, result = fcl.DistanceRequest(), fcl.DistanceResult()
        out.append(fcl.distance(shape(a), shape(b), request, result))
    return out


def coal_loop(As: np.ndarray, Bs: np.ndarray) -> List[float]:
    """The same with coal, FCL's successor."""
    import coal

    identity = coal.Transform3s()

    def shape(points):
        vertices = coal.StdVec_Vec3s()
        for p in points:
            vertices.append(p)
        return coal.Convex.convexHull(vertices, False, None)

    out = []
    for a, b in zip(tqdm(As, desc="coal loop", leave=False), Bs):
        request, result = coal.DistanceRequest(), coal.DistanceResult()
        out.append(coal.distance(shape(a), identity, shape(b), identity, request, result))
    return out


def peak_memory(pairs: int, method: str) -> Dict[str, float]:
    """Memory of a fresh process that solves ``pairs`` pairs, in MiB: the resident size with the
    input arrays built, and the peak while solving. The kernel's peak counter is reset once the
    inputs exist, so the temporaries of building them do not hide the solve's own peak."""
    script = f"""
import sys
sys.path.insert(0, {str(Path(__file__).parent)!r})
from batch import make_pairs
import record
import swarmcollide as sc

def status_mib(field):
    with open("/proc/self/status") as f:
        line = next(l for l in f if l.startswith(field + ":"))
    return float(line.split()[1]) / 1024

As, Bs = make_pairs({pairs})
with open("/proc/self/clear_refs", "w") as f:
    f.write("5")
inputs = status_mib("VmRSS")
r = sc.distance_many(As, Bs, method={method!r}, threads=2)
assert len(r) == {pairs}
print(inputs, status_mib("VmHWM"))
"""
    done = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True,
                          text=True)
    inputs, peak = (float(x) for x in done.stdout.split())
    return {"pairs": pairs, "method": method, "inputs_mib": inputs, "peak_mib": peak,
            "solve_mib": peak - inputs}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="a reduced run, under a minute")
    parser.add_argument("--json", type=Path, required=True, help="where to write the results")
    parser.add_argument("--loop-binary", type=Path,
                        help="the swarmcollide-batch-loop binary (the plain C++ loop)")
    parser.add_argument("--poses", action="store_true",
                        help="only the pose batches of issue 24 (bench/pose_batch.py)")
    arguments = parser.parse_args()
    quick = arguments.quick
    if arguments.poses:
        import pose_batch

        data = pose_batch.run(rows=2_000 if quick else 20_000, rounds=3 if quick else 15)
        written = record.write(arguments.json, "pose_batch", data.pop("rows"), quick=quick,
                               load_start=data["load_before"], **data)
        print(json.dumps(written, indent=1))
        return 0
    if arguments.loop_binary is None:
        parser.error("--loop-binary is required (except with --poses)")
    pairs = 10_000 if quick else 100_000
    loop_pairs = 1_000 if quick else 10_000
    memory_pairs = 100_000 if quick else 1_000_000
    repeats = 1 if quick else 3
    scaling_rounds = 1 if quick else 5
    scale = 0.1 if quick else 1.0

    As, Bs = make_pairs(pairs)
    results: Dict[str, object] = {"vertices": VERTICES, "pairs": pairs, "quick": quick}

    cpp = cpp_loop_seconds(arguments.loop_binary, As, Bs, "fcl", repeats)
    batch = median_seconds(lambda: sc.distance_many(As, Bs, method="fcl", threads=1), repeats)
    batch_default = median_seconds(lambda: sc.distance_many(As, Bs, method="fcl"), repeats)
    check = sc.distance_many(As, Bs, method="fcl", threads=1).distance.sum()
    results["fcl_overhead"] = {
        "threads": 1,
        "cpp_loop_seconds": cpp["seconds"],
        "distance_many_seconds": batch,
        "ratio": batch / cpp["seconds"],
        "same_answers": bool(abs(check - cpp["checksum"]) <= 1e-9 * abs(check)),
    }
    # threads=None runs one worker per hardware thread (std::thread::hardware_concurrency).
    results["fcl_default_threads"] = {"threads": os.cpu_count(), "seconds": batch_default}

    exact = sc.distance_many(As[:loop_pairs], Bs[:loop_pairs], method="fcl").distance
    python_loops = {}
    for name, loop in (("python-fcl", python_fcl_loop), ("coal", coal_loop)):
        loop(As[:10], Bs[:10])  # imports and first-call set-up, outside the timing
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            answers = np.array(loop(As[:loop_pairs], Bs[:loop_pairs]))
            times.append(time.perf_counter() - start)
        per_pair = statistics.median(times) / loop_pairs
        separated = exact > 1e-9
        python_loops[name] = {
            "seconds_per_pair": per_pair,
            "seconds_for_all_pairs": per_pair * pairs,
            "distance_many_speedup": per_pair * pairs / batch,
            "distance_many_default_threads_speedup": per_pair * pairs / batch_default,
            "max_error_on_separated": float(np.max(np.abs(answers[separated] - exact[separated]))),
        }
    results["python_loops"] = python_loops

    scaling = []
    for method, count in tqdm(list(SCALING_PAIRS.items()), desc="thread scaling", leave=False):
        count = max(100, int(count * scale))
        one, two, speedup = interleaved_seconds(
            lambda: sc.distance_many(As[:count], Bs[:count], method=method, threads=1),
            lambda: sc.distance_many(As[:count], Bs[:count], method=method, threads=2),
            scaling_rounds)
        scaling.append({"method": method, "pairs": count, "one_thread_seconds": one,
                        "two_threads_seconds": two, "speedup": speedup})
    results["memory"] = peak_memory(memory_pairs, "dual")

    written = record.write(arguments.json, "batch", scaling, **results)
    print(json.dumps(written, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
