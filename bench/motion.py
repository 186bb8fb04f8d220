"""Time of impact: swarmcollide's ``time_of_impact`` against FCL's conservative advancement
through python-fcl (``fcl.continuousCollide`` with ``CCDM_LINEAR`` motions, which interpolate
as ours do: the origin on the segment, a constant angular velocity about a fixed axis, and
``CCDC_CONSERVATIVE_ADVANCEMENT`` on ``fcl.Convex`` hulls; FCL's BVH meshes missed a cube
crossing a thin plate in a probe, so they are not used). Screw motions (``--kinds screw``) go to
ours as ``motion="screw"`` and to FCL as ``CCDM_SCREW``: both G(t) = G0 exp(t log(G0^-1 G1)).

Random motions of random hulls (8 points): A moves between two random poses (translations in a
cube of side 8, any rotation), B between two poses near the origin. Both answer each motion; a
dense-sampling oracle (swarmcollide's exact signed distance at 400 times, plus the times each
contender names) judges them: a free answer is wrong when a sample overlaps (deeper than 1e-11 of
the size); a contact at time t is wrong when a sample before ``t - 1e-6`` overlaps, or when the
bodies are farther apart at t than 1e-6 of the size (FCL's ``toc_err`` is 1e-6; ours is proven to
1e-9 of the size and 1e-6 of the time). The time of a motion is the median over rounds of the
thread's CPU time per call, the contenders interleaved motion by motion; the ratio (ours / FCL's)
is taken per motion, over the motions where FCL is right. ``--json`` writes bench/record.py's
format.

    python bench/motion.py [--motions 300] [--rounds 5] [--kinds turning translating screw]
        [--json bench/results/motion.json]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from typing import List

import numpy as np
from scipy.linalg import logm
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation, Slerp

import record
import swarmcollide as sc
from markdown import table

TIME_TOLERANCE = 1e-6
SAMPLES = 400


def fcl_convex(points: np.ndarray, keep: list):
    """An ``fcl.Convex`` of the points' hull. The arrays and the Convex go to ``keep``, which
    must outlive the collision objects: python-fcl's objects may read them in place without
    holding them."""
    import fcl

    hull = ConvexHull(points)
    vertices = np.ascontiguousarray(points, dtype=float)
    faces = np.hstack([np.full((len(hull.simplices), 1), 3), hull.simplices]).ravel()
    convex = fcl.Convex(vertices, len(hull.simplices), faces)
    keep += [vertices, faces, convex]
    return convex


def fcl_transform(pose: np.ndarray):
    import fcl

    return fcl.Transform(pose[:3, :3].copy(), pose[:3, 3].copy())


def random_pose(rng: np.random.Generator, spread: float) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3] = Rotation.random(random_state=rng).as_matrix()
    pose[:3, 3] = rng.uniform(-spread, spread, 3)
    return pose


def poses_at(start: np.ndarray, end: np.ndarray, times: np.ndarray,
             screw: bool = False) -> np.ndarray:
    if screw:
        # start @ expm(t xi) in closed form (Murray, Li and Sastry, (2.36)), xi = logm(G0^-1 G1).
        twist = np.real(logm(np.linalg.solve(start, end)))
        w, v = np.array([twist[2, 1], twist[0, 2], twist[1, 0]]), twist[:3, 3]
        times = np.atleast_1d(np.asarray(times, dtype=float))
        turns = Rotation.from_rotvec(np.outer(times, w)).as_matrix()
        angle = np.linalg.norm(w)
        if angle == 0:
            moved = np.outer(times, v)
        else:
            across = np.cross(w, v) / angle**2
            moved = across - turns @ across + np.outer(times, w * (w @ v) / angle**2)
        poses = np.tile(np.eye(4), (len(times), 1, 1))
        poses[:, :3, :3] = start[:3, :3] @ turns
        poses[:, :3, 3] = start[:3, 3] + moved @ start[:3, :3].T
        return poses
    turn = Slerp([0, 1], Rotation.from_matrix([start[:3, :3], end[:3, :3]]))(times).as_matrix()
    poses = np.tile(np.eye(4), (len(times), 1, 1))
    poses[:, :3, :3] = turn
    poses[:, :3, 3] = start[:3, 3] + np.outer(times, end[:3, 3] - start[:3, 3])
    return poses


class Oracle:
    """The exact signed distance along one motion."""

    def __init__(self, case: dict):
        self.case = case
        self.size = 2 * (case["a"].bounding_radius + case["b"].bounding_radius)

    def distances(self, times) -> np.ndarray:
        c = self.case
        times = np.asarray(times, dtype=float)
        return sc.signed_distance_many(
            c["a"], c["b"], method="exact", tolerance=1e-12,
            poses_a=poses_at(c["a0"], c["a1"], times, c["screw"]),
            poses_b=poses_at(c["b0"], c["b1"], times, c["screw"])).distance

    def first_overlap(self, extra=()) -> float:
        times = np.union1d(np.linspace(0, 1, SAMPLES), np.clip(list(extra), 0, 1))
        overlap = self.distances(times) < -1e-11 * self.size
        return float(times[overlap][0]) if overlap.any() else float("nan")

    def judge(self, touches: bool, t: float, first: float) -> str:
        """'right', or what is wrong: 'missed' (free, but a sample overlaps), 'late' (a sample
        before t - 1e-6 overlaps), 'early' (the bodies are farther apart at t than 1e-6 of the
        size, before any overlap) or 'false' (contact reported, none sampled, apart at t)."""
        if not touches:
            return "right" if np.isnan(first) else "missed"
        if not np.isnan(first) and first < t - TIME_TOLERANCE:
            return "late"
        if self.distances([t])[0] <= 1e-6 * self.size:
            return "right"
        return "false" if np.isnan(first) else "early"


def make_cases(count: int, rng: np.random.Generator, kind: str) -> List[dict]:
    """Random motions; "translating" ones keep each body's start rotation."""
    cases = []
    for _ in range(count):
        pa, pb = rng.normal(size=(8, 3)) * 0.5, rng.normal(size=(8, 3)) * 0.5
        case = {"pa": pa, "pb": pb, "a": sc.ConvexPolyhedron(pa), "b": sc.ConvexPolyhedron(pb),
                "a0": random_pose(rng, 4), "a1": random_pose(rng, 4),
                "b0": random_pose(rng, 0.5), "b1": random_pose(rng, 0.5),
                "screw": kind == "screw"}
        if kind == "translating":
            case["a1"][:3, :3] = case["a0"][:3, :3]
            case["b1"][:3, :3] = case["b0"][:3, :3]
        cases.append(case)
    return cases


KINDS = {"turning": "CCDM_LINEAR", "translating": "CCDM_TRANS", "screw": "CCDM_SCREW"}


def run(motions: int, rounds: int, kind: str) -> dict:
    """Turning motions go to FCL as ``CCDM_LINEAR``, translations as ``CCDM_TRANS``, screws as
    ``CCDM_SCREW`` (and to ours as ``motion="screw"``)."""
    import fcl

    rng = np.random.default_rng(28)
    cases = make_cases(motions, rng, kind)
    request = fcl.ContinuousCollisionRequest(
        num_max_iterations=1000, toc_err=TIME_TOLERANCE,
        ccd_motion_type=getattr(fcl.CCDMotionType, KINDS[kind]),
        ccd_solver_type=fcl.CCDSolverType.CCDC_CONSERVATIVE_ADVANCEMENT)
    per_motion = []
    disagreements = []
    counts = {"motions": motions, "touching_by_oracle": 0, "ours_right": 0, "fcl_right": 0,
              "ours_uncertified": 0}
    for index, c in enumerate(cases):
        keep: list = []
        objects = (fcl.CollisionObject(fcl_convex(c["pa"], keep), fcl_transform(c["a0"])),
                   fcl.CollisionObject(fcl_convex(c["pb"], keep), fcl_transform(c["b0"])))
        ends = (fcl_transform(c["a1"]), fcl_transform(c["b1"]))

        def ours():
            return sc.time_of_impact(c["a"], c["b"], pose_a=(c["a0"], c["a1"]),
                                     pose_b=(c["b0"], c["b1"]),
                                     motion="screw" if c["screw"] else "linear")

        def theirs():
            result = fcl.ContinuousCollisionResult()
            fcl.continuousCollide(objects[0], ends[0], objects[1], ends[1], request, result)
            return result

        times = {"ours": [], "fcl": []}
        for _ in range(rounds):
            for name, call in (("ours", ours), ("fcl", theirs)):
                start = time.thread_time()
                answer = call()
                times[name].append(time.thread_time() - start)
                if name == "ours":
                    mine = answer
                else:
                    their = answer
        oracle = Oracle(c)
        first = oracle.first_overlap([mine.t_lower, mine.t_upper, their.time_of_contact])
        counts["touching_by_oracle"] += not np.isnan(first)
        counts["ours_uncertified"] += not mine.certified
        ours_verdict = oracle.judge(mine.touches, mine.t_upper, first)
        if ours_verdict == "right" and not np.isnan(first) and mine.t_lower > first:
            ours_verdict = "late"
        fcl_verdict = oracle.judge(bool(their.is_collide), their.time_of_contact, first)
        ours_right, fcl_right = ours_verdict == "right", fcl_verdict == "right"
        counts["ours_right"] += ours_right
        counts["fcl_right"] += fcl_right
        for who, verdict in (("ours", ours_verdict), ("fcl", fcl_verdict)):
            if verdict != "right":
                counts[f"{who}_{verdict}"] = counts.get(f"{who}_{verdict}", 0) + 1
        if mine.touches != bool(their.is_collide) or not (ours_right and fcl_right):
            disagreements.append({
                "motion": index, "oracle_first_overlap": first,
                "ours": {"touches": mine.touches, "t_lower": mine.t_lower,
                         "t_upper": mine.t_upper, "certified": mine.certified,
                         "verdict": ours_verdict},
                "fcl": {"touches": bool(their.is_collide), "time": their.time_of_contact,
                        "verdict": fcl_verdict,
                        "early_by": first - their.time_of_contact if fcl_verdict == "early"
                        else None}})
        mine_time, fcl_time = statistics.median(times["ours"]), statistics.median(times["fcl"])
        per_motion.append({"motion": index, "touches": mine.touches,
                           "iterations": mine.iterations, "ours_us": mine_time * 1e6,
                           "fcl_us": fcl_time * 1e6, "fcl_right": bool(fcl_right)})
    fair = [m for m in per_motion if m["fcl_right"]] or per_motion
    ratios = [m["ours_us"] / m["fcl_us"] for m in fair]
    every = [m["ours_us"] / m["fcl_us"] for m in per_motion]
    summary = {
        **counts,
        "ratio_median_all_motions": statistics.median(every),
        "ratio_median": statistics.median(ratios),
        "ratio_geometric_mean": float(np.exp(np.mean(np.log(ratios)))),
        "ratio_quartiles": [float(q) for q in np.quantile(ratios, [0.25, 0.75])],
        "ours_us_median": statistics.median(m["ours_us"] for m in fair),
        "fcl_us_median": statistics.median(m["fcl_us"] for m in fair),
        "ours_iterations_median": statistics.median(m["iterations"] for m in per_motion),
        "ours_iterations_max": max(m["iterations"] for m in per_motion),
    }
    for touching in (True, False):
        chosen = [m["ours_us"] / m["fcl_us"] for m in fair if m["touches"] == touching]
        if chosen:
            key = "ratio_median_" + ("touching" if touching else "free")
            summary[key] = statistics.median(chosen)
    return {"summary": summary, "disagreements": disagreements, "per_motion": per_motion}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--motions", type=int, default=300)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--quick", action="store_true", help="60 motions, 3 rounds")
    parser.add_argument("--kinds", nargs="+", choices=list(KINDS), default=list(KINDS))
    parser.add_argument("--json", help="write the results here")
    args = parser.parse_args()
    if args.quick:
        args.motions, args.rounds = 60, 3
    load = os.getloadavg()
    rows, disagreements, per_motion = [], {}, {}
    for name in args.kinds:
        kind = f"{name} (FCL {KINDS[name]})"
        print(kind)
        outcome = run(args.motions, args.rounds, name)
        report(outcome)
        rows.append({"motions_kind": kind, **outcome["summary"]})
        disagreements[kind] = outcome["disagreements"]
        per_motion[kind] = outcome["per_motion"]
    print(f"load average {load} -> {os.getloadavg()}")
    if args.json:
        record.write(args.json, "motion", rows, disagreements=disagreements,
                     per_motion=per_motion, load_start=load)
    return 0


def report(outcome: dict) -> None:
    s = outcome["summary"]
    print(f"{s['motions']} motions, {s['touching_by_oracle']} touching by the oracle; right: ours "
          f"{s['ours_right']}, FCL {s['fcl_right']}; ours uncertified {s['ours_uncertified']}")
    print(f"per motion where FCL is right, ours / FCL: median {s['ratio_median']:.2f} "
          f"(quartiles {s['ratio_quartiles'][0]:.2f}-{s['ratio_quartiles'][1]:.2f}, geometric mean "
          f"{s['ratio_geometric_mean']:.2f}; touching "
          f"{s.get('ratio_median_touching', float('nan')):.2f}, free "
          f"{s.get('ratio_median_free', float('nan')):.2f}); over all motions "
          f"{s['ratio_median_all_motions']:.2f}; ours {s['ours_us_median']:.1f} us, FCL "
          f"{s['fcl_us_median']:.1f} us; our iterations median {s['ours_iterations_median']}, max "
          f"{s['ours_iterations_max']}")
    print("wrong answers by kind:", {k: v for k, v in s.items()
                                     if k.startswith(("ours_", "fcl_")) and k.split("_")[-1] in
                                     ("missed", "late", "early", "false")})
    early = [d["fcl"]["early_by"] for d in outcome["disagreements"] if d["fcl"]["early_by"]]
    if early:
        print(f"FCL early by (time): median {statistics.median(early):.2e}, max {max(early):.2e}")
    for d in outcome["disagreements"]:
        if d["ours"]["verdict"] != "right" or d["fcl"]["verdict"] not in ("right", "early",
                                                                          "false"):
            print("disagreement:", d)


def section(data: dict) -> str:
    """The RESULTS.md section of a recorded run: per kind of motion, ours over FCL's where FCL
    answers right (issue 28's target: at most 1), and how often each answers right."""
    machine = data["machine"]
    lines = [f"`{data['command']}`, load average {machine['load_average_start']} -> "
             f"{machine['load_average_end']}, {machine['date']}. Random motions of 8-point hulls "
             "against a dense-sampling oracle on the exact signed distance; each motion's time is "
             "the median over interleaved rounds of the thread's CPU time per call from Python "
             "(FCL: `fcl.continuousCollide` with conservative advancement, request made once).",
             ""]
    rows = []
    for row in data["rows"]:
        rows.append([row["motions_kind"], str(row["motions"]), str(row["touching_by_oracle"]),
                     f"{row['ours_right']} / {row['fcl_right']}",
                     f"{row['ours_us_median']:.1f} µs", f"{row['fcl_us_median']:.1f} µs",
                     f"**{row['ratio_median']:.2f}x**",
                     f"{row.get('ratio_median_touching', float('nan')):.2f}x",
                     f"{row.get('ratio_median_free', float('nan')):.2f}x"])
    lines.append(table(["motions", "count", "touching", "right (ours / FCL)", "ours (median)",
                        "FCL (median)", "ours / FCL where FCL is right", "touching", "free"],
                       rows))
    return "\n".join(lines)


if __name__ == "__main__":
    raise SystemExit(main())
