"""Batches over poses (issue 24): one prebuilt body against another at m poses, per row on one
thread, against a prebuilt python-fcl loop (``setTransform`` then the call, request and result
reused) and a coal loop (the same), and 2 threads against 1; ``signed_distance_many`` is timed
beside them (neither loop computes a penetration depth this way).

Bodies are the hulls of 8 and 260 points on the unit sphere; B's centre is 3 from A's (apart) or
1.8 (overlapping), along random directions, under random rotations. The contenders take turns
within each round; a time is the median over rounds of the time per row. The fcl and coal
transforms are built before the timing (a planner's poses arrive as arrays, so this flatters them
slightly). A ratio is the median over rounds of that round's ratio, so that a slow moment of the
shared machine enters both of its times or neither (a 2-thread call of collide_many lasts 1-2 ms,
and the medians of separate times gave gains from 1.1x to 2.9x in runs minutes apart). The load
average is recorded before and after. Run by bench/batch.py ``--poses``.
"""

from __future__ import annotations

import os
import statistics
import time
from typing import Callable, Dict, List

import numpy as np
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation

import swarmcollide as sc
from peers import coal_convex, fcl_convex_object

SIZES = (8, 260)
STATES = {"apart": 1.0, "overlapping": -0.2}  # gap between the unit spheres' surfaces


def sphere_hull(n: int, rng: np.random.Generator) -> np.ndarray:
    points = rng.normal(size=(n, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    return points[ConvexHull(points).vertices]


def contenders(a: np.ndarray, b: np.ndarray, rotations: np.ndarray,
               translations: np.ndarray) -> Dict[str, Callable[[], object]]:
    import coal
    import fcl

    oa, ob = fcl_convex_object(a), fcl_convex_object(b)
    fcl_poses = [fcl.Transform(r, t) for r, t in zip(rotations, translations)]
    ca, cb = coal_convex(a), coal_convex(b)
    identity = coal.Transform3s()
    coal_poses = [coal.Transform3s(r, t) for r, t in zip(rotations, translations)]
    collision_request, collision_result = fcl.CollisionRequest(), fcl.CollisionResult()
    distance_request, distance_result = fcl.DistanceRequest(), fcl.DistanceResult()
    coal_collision = (coal.CollisionRequest(), coal.CollisionResult())
    coal_distance = (coal.DistanceRequest(), coal.DistanceResult())
    A, B = sc.ConvexPolyhedron(a), sc.ConvexPolyhedron(b)
    poses = (rotations, translations)

    def fcl_collide():
        for pose in fcl_poses:
            ob.setTransform(pose)
            fcl.collide(oa, ob, collision_request, collision_result)

    def fcl_distance():
        for pose in fcl_poses:
            ob.setTransform(pose)
            fcl.distance(oa, ob, distance_request, distance_result)

    def coal_collide():
        request, result = coal_collision
        for pose in coal_poses:
            result.clear()
            coal.collide(ca, identity, cb, pose, request, result)

    def coal_distance_loop():
        request, result = coal_distance
        for pose in coal_poses:
            result.clear()
            coal.distance(ca, identity, cb, pose, request, result)

    return {
        "collide_many 1 thread": lambda: sc.collide_many(A, B, poses_b=poses, threads=1),
        "collide_many 2 threads": lambda: sc.collide_many(A, B, poses_b=poses, threads=2),
        "distance_many 1 thread": lambda: sc.distance_many(A, B, poses_b=poses, threads=1),
        "distance_many 2 threads": lambda: sc.distance_many(A, B, poses_b=poses, threads=2),
        "signed_distance_many 1 thread": lambda: sc.signed_distance_many(A, B, poses_b=poses,
                                                                          threads=1),
        "python-fcl collide loop": fcl_collide,
        "python-fcl distance loop": fcl_distance,
        "coal collide loop": coal_collide,
        "coal distance loop": coal_distance_loop,
    }


def run(rows: int, rounds: int) -> Dict[str, object]:
    rng = np.random.default_rng(24)
    load_before = os.getloadavg()
    records: List[dict] = []
    for n in SIZES:
        a, b = sphere_hull(n, rng), sphere_hull(n, rng)
        rotations = Rotation.random(rows, random_state=n).as_matrix()
        axes = rng.normal(size=(rows, 3))
        axes /= np.linalg.norm(axes, axis=1, keepdims=True)
        for state, gap in STATES.items():
            translations = axes * (2 + gap)
            cases = contenders(a, b, rotations, translations)
            times: Dict[str, List[float]] = {name: [] for name in cases}
            cpu: Dict[str, List[float]] = {name: [] for name in cases}
            for _ in range(rounds):
                for name, call in cases.items():
                    start, start_cpu = time.perf_counter(), time.process_time()
                    call()
                    times[name].append((time.perf_counter() - start) / rows)
                    cpu[name].append((time.process_time() - start_cpu) / rows)
            per_row = {name: statistics.median(values) for name, values in times.items()}
            cpu_per_row = {name: statistics.median(values) for name, values in cpu.items()}
            # CPU time over wall time: about 2 for two busy threads; less when the machine's
            # other work (or a serial part) leaves a thread waiting.
            busy = {name: statistics.median(c / w for c, w in zip(cpu[name], times[name]))
                    for name in cases if "2 threads" in name}
            by_round = [{name: times[name][i] * 1e6 for name in cases} for i in range(rounds)]
            colliding = int(sc.collide_many(a, b, poses_b=(rotations, translations))
                            .colliding.sum())
            records.append({"vertices": len(a), "pairs": state, "rows": rows,
                            "colliding_rows": colliding,
                            "microseconds_per_row": {k: v * 1e6 for k, v in per_row.items()},
                            # The process's CPU time: less sensitive to a loaded machine.
                            "cpu_microseconds_per_row": {k: v * 1e6
                                                         for k, v in cpu_per_row.items()},
                            "cpu_over_wall": busy,
                            "rounds_microseconds_per_row": by_round})
    return {"rows": records, "rounds": rounds, "load_before": load_before,
            "load_after": os.getloadavg()}


TARGETS = (("collide_many 1 thread", ("python-fcl collide loop", "coal collide loop"), 0.25),
           ("distance_many 1 thread", ("python-fcl distance loop", "coal distance loop"), 0.35))


def ratios(record: dict, clock: str = "microseconds_per_row") -> Dict[str, float]:
    """The issue's ratios for one workload: ours over each loop, and 2 threads' gain over 1, by
    wall time (``clock="cpu_microseconds_per_row"``: by CPU time; the gain is then meaningless).
    Wall-time ratios are medians over rounds of each round's ratio where the rounds were kept."""
    rounds = record.get("rounds_microseconds_per_row") if clock == "microseconds_per_row" else None
    samples = rounds or [record[clock]]

    def ratio(top: str, bottom: str) -> float:
        return statistics.median(t[top] / t[bottom] for t in samples)

    out = {}
    for ours, loops, _ in TARGETS:
        for loop in loops:
            out[f"{ours} / {loop}"] = ratio(ours, loop)
    for kind in ("collide_many", "distance_many"):
        out[f"{kind} 2 threads gain"] = ratio(f"{kind} 1 thread", f"{kind} 2 threads")
    return out


def section(data: dict) -> str:
    """bench/RESULTS.md's section: times per row, and the issue's ratios against their targets."""
    from markdown import fmt_time, machine_line, table

    lines = [f"Made by {machine_line(data)} {data['rounds']} rounds, the contenders in turn "
             "within each; times per row are medians over rounds. One body against another "
             "at m poses (`sc.collide_many(A, B, poses_b=poses, threads=1)`), against loops over "
             "prebuilt python-fcl and coal objects that set the transform and call with a "
             "reused request and result.", ""]
    names = list(data["rows"][0]["microseconds_per_row"])
    lines += [table(["vertices", "pairs", "rows (colliding)"] + names,
                    [[str(r["vertices"]), r["pairs"], f"{r['rows']:,} ({r['colliding_rows']:,})"]
                     + [fmt_time(r["microseconds_per_row"][n]) for n in names]
                     for r in data["rows"]]), ""]
    rows = []
    for r in data["rows"]:
        found = ratios(r)
        by_cpu = ratios(r, "cpu_microseconds_per_row") if "cpu_microseconds_per_row" in r else {}
        for ours, loops, target in TARGETS:
            for loop in loops:
                value = found[f"{ours} / {loop}"]
                cpu = by_cpu.get(f"{ours} / {loop}")
                rows.append([str(r["vertices"]), r["pairs"], f"{ours} / {loop}",
                             f"**{value:.2f}x**" + (f" (CPU {cpu:.2f}x)" if cpu else ""),
                             f"<= {target}x: " + ("met" if value <= target else "**not met**")])
        for kind in ("collide_many", "distance_many"):
            value = found[f"{kind} 2 threads gain"]
            busy = r.get("cpu_over_wall", {}).get(f"{kind} 2 threads")
            rows.append([str(r["vertices"]), r["pairs"], f"{kind}: 2 threads / 1",
                         f"**{value:.2f}x**" + (f" (CPU/wall {busy:.2f})" if busy else ""),
                         ">= 1.8x: " + ("met" if value >= 1.8 else "**not met**")])
    lines.append(table(["vertices", "pairs", "ratio", "measured", "issue 24's target"], rows))
    return "\n".join(lines)
