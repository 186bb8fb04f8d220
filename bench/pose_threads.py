"""Two threads against one on batches over poses (issue 24): wall time of each batch call with
``threads=1`` and ``threads=2``, in interleaved rounds (the order alternating), as the median ratio,
with the CPU time over the wall time of the 2-thread calls and the load average before and after.

One random body of n points on the unit sphere against itself, B under random rotations and
translations of length 2.4 ("apart": most collide rows settled by the ball screens) or 1.9
("near": most rows need a solver), ``poses_b=(rotations, translations)``. Prints a line per case;
nothing is recorded (bench/pose_batch.py records the 20,000-row figures).

With ``--between US`` each call follows US microseconds of Python work (a busy loop), as in a
planner's loop, so that the other core has been idle that long; with ``--default`` the 2-thread
calls pass ``threads=None`` (one per hardware thread) instead of ``threads=2``; ``--rows`` takes a
comma-separated list.

A result freed before the next call leaves its memory for the next result of its size (see
BatchResult), as in a loop that uses each batch's answers and drops them. ``--hold`` keeps every
result of a case alive instead, so that each call writes into fresh memory (faulted and zeroed
inside the call), as when a caller keeps many results.

    .venv/bin/python bench/pose_threads.py --rows 100000 --rounds 7
    .venv/bin/python bench/pose_threads.py --rows 500,1000,2000,20000 --rounds 200 --between 2000 \
        --default --sizes 8
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np
from scipy.spatial.transform import Rotation

import swarmcollide as sc

CALLS = ("collide_many", "distance_many", "signed_distance_many")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rows", default="100000", help="rows per batch call, comma-separated")
    parser.add_argument("--rounds", type=int, default=7, help="interleaved rounds per case")
    parser.add_argument("--sizes", default="8,260", help="body sizes (points), comma-separated")
    parser.add_argument("--calls", default=",".join(CALLS), help="batch calls, comma-separated")
    parser.add_argument("--hold", action="store_true",
                        help="keep every result of a case alive (no freed memory reused)")
    parser.add_argument("--between", type=float, default=0.0,
                        help="microseconds of Python work before each call")
    parser.add_argument("--default", action="store_true",
                        help="threads=None (one per hardware thread) instead of threads=2")
    arguments = parser.parse_args()
    print(f"load before {os.getloadavg()}", flush=True)
    for m in (int(s) for s in arguments.rows.split(",")):
        run(m, arguments)
    print(f"load after {os.getloadavg()}")
    return 0


def work_for(microseconds: float) -> None:
    """Python work (a busy loop) for about `microseconds`, as a caller between batch calls."""
    end = time.perf_counter() + microseconds * 1e-6
    while time.perf_counter() < end:
        pass


def run(m: int, arguments: argparse.Namespace) -> None:
    rng = np.random.default_rng(0)
    two = None if arguments.default else 2
    for n in (int(s) for s in arguments.sizes.split(",")):
        points = rng.normal(size=(n, 3))
        points /= np.linalg.norm(points, axis=1)[:, None]
        body = sc.ConvexPolyhedron(points)
        rotations = Rotation.random(m, random_state=1).as_matrix()
        for label, length in (("apart", 2.4), ("near", 1.9)):
            translations = rng.normal(size=(m, 3))
            translations *= length / np.linalg.norm(translations, axis=1)[:, None]
            poses = (rotations, translations)
            for name in arguments.calls.split(","):
                call = getattr(sc, name)
                call(body, body, poses_b=poses, threads=1)  # warm the body's caches
                gains, busy, one, held = [], [], [], []
                for r in range(arguments.rounds):
                    wall, cpu = {}, {}
                    for threads in ((1, two) if r % 2 == 0 else (two, 1)):
                        work_for(arguments.between)
                        start, start_cpu = time.perf_counter(), time.process_time()
                        result = call(body, body, poses_b=poses, threads=threads)
                        wall[threads] = time.perf_counter() - start
                        cpu[threads] = time.process_time() - start_cpu
                        if arguments.hold:
                            held.append(result)
                        del result
                    gains.append(wall[1] / wall[two])
                    busy.append(cpu[two] / wall[two])
                    one.append(wall[1] / m * 1e6)
                print(f"m={m:6d} n={n:4d} {label:5s} {name:20s} 1 thread "
                      f"{statistics.median(one):.3f} "
                      f"us/row  2 threads/1 median {statistics.median(gains):.2f} "
                      f"(min {min(gains):.2f} max {max(gains):.2f}) "
                      f"cpu/wall(2) {statistics.median(busy):.2f}", flush=True)


if __name__ == "__main__":
    raise SystemExit(main())
