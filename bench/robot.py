"""Robots (issue 27): ``Robot.check`` on pybullet_data's Franka Panda against a Python loop of
coal's ``distance`` over the same pairs, at the same geometry poses (our forward kinematics).

The Panda (``franka_panda/panda.urdf``, 11 collision meshes as their convex hulls, the default
pairs) with a table and two boxes as obstacles, at random configurations within the joint limits
(seed 0). Contenders, interleaved in rounds (the order alternating), each answering every
configuration's minimum signed distance over the pairs:

- ``check 1 thread`` / ``check 2 threads``: ``robot.check(q, threads=...)``;
- ``coal loop``: ``robot.geometry_poses(q)`` (timed with it), then for each configuration and pair
  ``coal.distance`` between ``coal.Convex`` hulls (signed: EPA when they overlap), from Python.

Reported: the median time per configuration of each, the ratios to the coal loop, the
configurations where coal's verdict (distance <= 0) differs from ours, and the largest difference
between the minimum distances. The load average is recorded before and after.

    .venv/bin/python bench/robot.py --configurations 2000 --json bench/results/robot.json
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

import numpy as np

import swarmcollide as sc

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import record  # noqa: E402  (bench/record.py: the one results format)


def panda() -> sc.Robot:
    import pybullet_data

    robot = sc.Robot.from_urdf(
        os.path.join(pybullet_data.getDataPath(), "franka_panda", "panda.urdf"))
    for name, half, centre in (("table", (0.6, 0.8, 0.02), (0.55, 0.0, -0.03)),
                               ("box_left", (0.1, 0.1, 0.15), (0.5, 0.35, 0.15)),
                               ("box_right", (0.08, 0.12, 0.1), (0.45, -0.4, 0.1))):
        pose = np.eye(4)
        pose[:3, 3] = centre
        robot.add_obstacle(sc.Box(half), pose, name=name)
    return robot


def coal_loop(robot: sc.Robot):
    """The coal contender: hull shapes built once, then a Python loop over the configurations and
    pairs."""
    import coal
    from scipy.spatial import ConvexHull

    def shape(body):
        points = np.asarray(body.vertices, dtype=float)
        hull = ConvexHull(points)
        vertices = coal.StdVec_Vec3s()
        for i in hull.vertices:
            vertices.append(points[i])
        index = {int(v): k for k, v in enumerate(hull.vertices)}
        triangles = coal.StdVec_Triangle()
        for a, b, c in hull.simplices:
            triangles.append(coal.Triangle(index[int(a)], index[int(b)], index[int(c)]))
        return coal.Convex(vertices, triangles)

    geometries = robot._robot_geometries + robot._obstacles
    shapes = [shape(g[3]) for g in geometries]
    names = robot.geometry_names
    pairs = [(names.index(a), names.index(b)) for a, b in robot.pairs]
    request = coal.DistanceRequest()

    def run(q: np.ndarray) -> np.ndarray:
        poses = robot.geometry_poses(q)
        least = np.empty(len(q))
        for i, row in enumerate(poses):
            transforms = [coal.Transform3s(t[:3, :3], t[:3, 3]) for t in row]
            least[i] = min(
                coal.distance(shapes[a], transforms[a], shapes[b], transforms[b], request,
                              coal.DistanceResult())
                for a, b in pairs)
        return least

    return run


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--configurations", type=int, default=2000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="200 configurations, 1 round")
    parser.add_argument("--json", help="write the results here (bench/record.py's format)")
    arguments = parser.parse_args()
    count = 200 if arguments.quick else arguments.configurations
    rounds = 1 if arguments.quick else arguments.rounds
    load_start = os.getloadavg()
    robot = panda()
    q = np.random.default_rng(0).uniform(*robot.limits.T, size=(count, robot.dof))
    coal_run = coal_loop(robot)
    contenders = {
        "check 1 thread": lambda: robot.check(q, threads=1).min_distance,
        "check 2 threads": lambda: robot.check(q, threads=2).min_distance,
        "coal loop": lambda: coal_run(q),
    }
    robot.check(q[:50], threads=1)  # the hulls are built on first use: not timed
    times = {name: [] for name in contenders}
    answers = {}
    for r in range(rounds):
        order = list(contenders) if r % 2 == 0 else list(reversed(contenders))
        for name in order:
            start = time.perf_counter()
            answers[name] = contenders[name]()
            times[name].append((time.perf_counter() - start) / count * 1e6)
    check = robot.check(q, threads=2)
    ours, theirs = check.min_distance, answers["coal loop"]
    disagree = int(np.count_nonzero(check.colliding != (theirs <= 0)))
    rows = []
    coal_time = statistics.median(times["coal loop"])
    for name, values in times.items():
        median = statistics.median(values)
        rows.append({"contender": name, "us_per_configuration": round(median, 2),
                     "speedup_over_coal_loop": round(coal_time / median, 2)})
        print(f"{name:16s} {median:9.1f} us/configuration  x{coal_time / median:.2f} vs coal loop")
    summary = {
        "robot": "franka_panda/panda.urdf + table + 2 boxes",
        "configurations": count, "pairs": len(robot.pairs), "rounds": rounds,
        "colliding": int(check.colliding.sum()), "certified": int(check.certified.sum()),
        "verdicts_differing_from_coal": disagree,
        "max_min_distance_difference": float(np.abs(ours - theirs).max()),
    }
    print(summary)
    print(f"load before {tuple(round(x, 2) for x in load_start)} after "
          f"{tuple(round(x, 2) for x in os.getloadavg())}")
    if arguments.json:
        record.write(arguments.json, "robot", rows, load_start=load_start, **summary)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
