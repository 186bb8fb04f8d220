"""A body of 2,000 points against its own 45-vertex hull: what the points inside cost the exact
methods (issue 24, item 2: within 1.2x of the hull's time).

The dense body is 45 points of a Fibonacci lattice on the unit sphere (every one a vertex of
their hull) among 1,955 points strictly inside that hull, shuffled; the hull body is the 45
points alone. Each faces the same 45-vertex hull of random sphere points, apart (gap 1), near
(gap 0.01) and overlapping (by 0.1), for dual, exact and fcl distance, collide and signed distance.
Both bodies are built once; in every round the dense body and its hull answer the same pairs in
turn, and a time is the median over rounds of the mean time per call. ``--json`` writes one row
per method, query and proximity (bench/record.py's format).
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path
from typing import Dict, List, Optional

import numpy as np
from scipy.spatial import ConvexHull

import record
import swarmcollide as sc

HULL_VERTICES = 45
INSIDE = 1955


def fibonacci_sphere(n: int) -> np.ndarray:
    """n points of the Fibonacci lattice on the unit sphere: all of them vertices of their hull."""
    i = np.arange(n)
    z = 1 - 2 * (i + 0.5) / n
    r = np.sqrt(1 - z * z)
    angle = np.pi * (3 - np.sqrt(5)) * i
    return np.column_stack([r * np.cos(angle), r * np.sin(angle), z])


def dense_body(rng: np.random.Generator) -> np.ndarray:
    """The hull's vertices among points strictly inside it (convex combinations of four
    vertices pulled towards the centre), shuffled."""
    vertices = fibonacci_sphere(HULL_VERTICES)
    weights = rng.uniform(size=(INSIDE, 4))
    weights /= weights.sum(axis=1, keepdims=True)
    corners = vertices[rng.integers(HULL_VERTICES, size=(INSIDE, 4))]
    inside = 0.98 * np.einsum("ik,ikj->ij", weights, corners)
    return rng.permutation(np.vstack([vertices, inside]))


def other_body(rng: np.random.Generator) -> np.ndarray:
    points = rng.normal(size=(HULL_VERTICES, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    return points[ConvexHull(points).vertices]


def calls_of(query: sc.Query, kind: str):
    if kind == "distance":
        return query.distance
    if kind == "collide":
        return query.collide
    return query.signed_distance


def run(rounds: int, calls: int) -> List[dict]:
    rng = np.random.default_rng(24)
    dense_points = dense_body(rng)
    dense = sc.ConvexPolyhedron(dense_points)
    hull = sc.ConvexPolyhedron(fibonacci_sphere(HULL_VERTICES))
    assert ConvexHull(dense_points).vertices.size == HULL_VERTICES
    other = other_body(rng)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    placed = {state: sc.ConvexPolyhedron(other + (2 + gap) * axis)
              for state, gap in (("apart", 1.0), ("near", 0.01), ("overlapping", -0.1))}
    records = []
    for method in ("dual", "exact", "fcl"):
        query = sc.Query(method)
        for kind in ("distance", "collide", "signed_distance"):
            ask = calls_of(query, kind)
            for state, b in placed.items():
                ask(dense, b)  # builds the hulls and any per-body data once
                ask(hull, b)
                times: Dict[str, List[float]] = {"dense": [], "hull": []}
                for _ in range(rounds):
                    for name, a in (("dense", dense), ("hull", hull)):
                        start = time.perf_counter()
                        for _ in range(calls):
                            ask(a, b)
                        times[name].append((time.perf_counter() - start) / calls)
                dense_us = statistics.median(times["dense"]) * 1e6
                hull_us = statistics.median(times["hull"]) * 1e6
                records.append({"method": method, "query": kind, "pairs": state,
                                "points": len(dense_points), "hull_vertices": HULL_VERTICES,
                                "dense_microseconds": dense_us, "hull_microseconds": hull_us,
                                "ratio": dense_us / hull_us})
    return records


def section(data: dict) -> str:
    """bench/RESULTS.md's section: each query's time on the dense body and on its hull, and the
    issue's ratio against its target."""
    from markdown import fmt_time, machine_line, table

    rows = data["rows"]
    first = rows[0]
    lines = [f"Made by {machine_line(data)} {data['rounds']} rounds of {data['calls']} calls; a "
             f"body of {first['points']:,} points whose hull has {first['hull_vertices']} "
             "vertices against that hull alone, the two in turn within each round, each facing "
             "the same other body (times are medians over rounds of wall time per call from "
             "Python, so the load enters both sides alike).", ""]
    lines.append(table(
        ["method", "query", "pairs", "dense body", "its hull", "dense / hull", "target <= 1.2x"],
        [[r["method"], r["query"], r["pairs"], fmt_time(r["dense_microseconds"]),
          fmt_time(r["hull_microseconds"]), f"{r['ratio']:.2f}x",
          "met" if r["ratio"] <= 1.2 else "**not met**"] for r in rows]))
    return "\n".join(lines)


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer rounds, under a minute")
    parser.add_argument("--json", type=Path, help="where to write the records")
    arguments = parser.parse_args(argv)
    rounds, calls = (5, 20) if arguments.quick else (15, 100)
    records = run(rounds, calls)
    for r in records:
        print(f"{r['method']:<6} {r['query']:<16} {r['pairs']:<12} "
              f"dense {r['dense_microseconds']:9.2f} us  hull {r['hull_microseconds']:8.2f} us  "
              f"{r['ratio']:5.2f}x")
    print(f"largest ratio {max(r['ratio'] for r in records):.2f}x")
    if arguments.json:
        record.write(arguments.json, "hull_points", records, quick=arguments.quick, rounds=rounds,
                     calls=calls)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
