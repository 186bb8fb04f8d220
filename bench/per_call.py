"""Per-call cost of one query from Python on prebuilt bodies: swarmcollide beside python-fcl and
coal, in one process, the contenders interleaved round by round (issue 13's fast path).

Bodies are the hull vertices of points on the unit sphere (8 and 64 points), built once; pairs
are apart (distance 1) or overlapping by a tenth of their size. python-fcl and coal reuse their
request and result objects, as their users write a loop (until issue 24 a new result per call
added its construction to their time, which flattered swarmcollide's ratios). Each contender
answers the same pairs in turn, round after round; a contender's time is the median over rounds of its mean time
per call, and the ratios are taken against python-fcl's distance and collide and coal's signed
distance from the same run. ``--json`` writes one row per contender and size (bench/record.py's
format).
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path
from typing import Callable, Dict, List, Optional

import numpy as np
from scipy.spatial import ConvexHull

import record
import swarmcollide as sc
from peers import coal_convex, fcl_convex_object


def sphere_pair(n: int, gap: float, rng: np.random.Generator):
    """Two hulls of n points on unit spheres whose centres are 2 + gap apart along a random axis."""

    def hull_points():
        p = rng.normal(size=(n, 3))
        p /= np.linalg.norm(p, axis=1, keepdims=True)
        return p[ConvexHull(p).vertices]

    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    return hull_points(), hull_points() + (2 + gap) * axis


def contenders(a: np.ndarray, b: np.ndarray) -> Dict[str, Callable[[], object]]:
    import coal
    import fcl

    oa, ob = fcl_convex_object(a), fcl_convex_object(b)
    ca, cb = coal_convex(a), coal_convex(b)
    identity = coal.Transform3s()
    # Requests and results made once and reused, as python-fcl's and coal's users write a loop.
    distance_request, collision_request = fcl.DistanceRequest(), fcl.CollisionRequest()
    distance_result, collision_result = fcl.DistanceResult(), fcl.CollisionResult()
    coal_request, coal_result = coal.DistanceRequest(), coal.DistanceResult()
    A, B = sc.ConvexPolyhedron(a), sc.ConvexPolyhedron(b)
    dual, via_fcl = sc.Query("dual"), sc.Query("fcl")
    return {
        "python-fcl distance": lambda: fcl.distance(oa, ob, distance_request, distance_result),
        "python-fcl collide": lambda: fcl.collide(oa, ob, collision_request, collision_result),
        "coal distance": lambda: coal.distance(ca, identity, cb, identity, coal_request,
                                               coal_result),
        "sc.distance fcl": lambda: sc.distance(A, B, method="fcl"),
        "sc.distance dual": lambda: sc.distance(A, B),
        "Query.distance fcl": lambda: via_fcl.distance(A, B),
        "Query.distance dual": lambda: dual.distance(A, B),
        "sc.collide fcl": lambda: sc.collide(A, B, method="fcl"),
        "sc.collide dual": lambda: sc.collide(A, B),
        "sc.signed_distance dual": lambda: sc.signed_distance(A, B),
        "sc.signed_distance exact": lambda: sc.signed_distance(A, B, method="exact"),
    }


REFERENCE = {"distance": "python-fcl distance", "collide": "python-fcl collide",
             "signed": "coal distance"}


def reference_of(name: str) -> str:
    if "collide" in name:
        return REFERENCE["collide"]
    if "signed" in name or name.startswith("coal"):
        return REFERENCE["signed"]
    return REFERENCE["distance"]


def run(sizes: List[int], pairs: int, rounds: int, calls: int) -> List[dict]:
    rng = np.random.default_rng(13)
    records = []
    for n in sizes:
        for state, gap in (("apart", 1.0), ("overlapping", -0.1)):
            cases = [contenders(*sphere_pair(n, gap, rng)) for _ in range(pairs)]
            times: Dict[str, List[float]] = {name: [] for name in cases[0]}
            for _ in range(rounds):
                for name in times:
                    start = time.perf_counter()
                    for case in cases:
                        query = case[name]
                        for _ in range(calls):
                            query()
                    times[name].append((time.perf_counter() - start) / (pairs * calls))
            medians = {name: statistics.median(values) for name, values in times.items()}
            for name, seconds in medians.items():
                records.append({
                    "vertices": n, "pairs": state, "contender": name,
                    "microseconds": seconds * 1e6,
                    "ratio": seconds / medians[reference_of(name)],
                    "against": reference_of(name),
                })
    return records


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer rounds, under a minute")
    parser.add_argument("--json", type=Path, help="where to write the records")
    arguments = parser.parse_args(argv)
    rounds, calls = (5, 50) if arguments.quick else (15, 200)
    records = run([8, 64], pairs=10, rounds=rounds, calls=calls)
    for r in records:
        print(f"{r['vertices']:>3} {r['pairs']:<12} {r['contender']:<26} "
              f"{r['microseconds']:8.2f} us  {r['ratio']:5.2f}x {r['against']}")
    if arguments.json:
        record.write(arguments.json, "per_call", records, quick=arguments.quick, rounds=rounds,
                     calls=calls)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
