"""One thread of bench/robot_motion.py's workload, for a profiler: ``check_motion`` on the same
random Panda planner edges (seed 0), repeated, with the distance queries per edge printed (the
load does not change them) beside the time per edge (it does).

    .venv/bin/python bench/robot_motion_profile.py --edges 300 --repeats 3
    perf record -g -o /tmp/perf.data .venv/bin/python bench/robot_motion_profile.py
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from robot import robot_of  # noqa: E402  (bench/robot.py: the Panda and its scene)
from robot_motion import planner_edges  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edges", type=int, default=300)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    robot = robot_of("panda")
    q0, q1, _ = planner_edges(robot, args.edges, args.seed)
    robot.check_motion(q0[:20], q1[:20], threads=1)  # the hulls are built on first use
    best = float("inf")
    for _ in range(args.repeats):
        start = time.perf_counter()
        motion = robot.check_motion(q0, q1, threads=1)
        best = min(best, time.perf_counter() - start)
    iterations = motion.iterations
    print(f"{args.edges} edges: {best / args.edges * 1e6:.1f} us/edge (best of {args.repeats}), "
          f"load {os.getloadavg()[0]:.2f}; touching {int(motion.touches.sum())}, certified "
          f"{int(motion.certified.sum())}; queries per edge mean {iterations.mean():.2f} median "
          f"{np.median(iterations):.1f} max {iterations.max()}; checksum "
          f"{float(np.sum(np.where(motion.touches, motion.t_upper, 0))):.12g}")


if __name__ == "__main__":
    main()
