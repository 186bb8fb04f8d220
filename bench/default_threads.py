"""The default threads (``threads=None``, one per hardware thread) against one thread on small and
mid-size batches, as a planner or a learner calls them: each call after some Python work (a busy
loop of ``--between`` microseconds), so that the other cores have been idle that long. Answers do
not depend on the threads; only the time does. A batch whose rows take the calling thread less
than a few hundred microseconds should take no longer on the default threads than on one (see
detail/waking_pace.hpp and bench/README, Session 41).

Cases: ``collide_many`` and ``distance_many`` of one 8-point body against another at m poses
(apart: centres 2.4 apart, unit-sphere points), ``Robot.check`` of m configurations of pybullet's
Franka Panda (needs ``pybullet`` from the bench extra; with and without ``nearest``), and
``time_of_impact_many`` of m translations of an 8-point body past another, and a frame of
``Scene.colliding_pairs`` and ``Scene.contacts`` on scenes of 20-2,000 bodies (each moved a little
before the query; the frame's time includes ``set_poses``). Prints, per case, the
median time per call on 1 thread and on the default threads, in interleaved rounds, and their
ratio (the default's gain: above 1 when it is faster).

    .venv/bin/python bench/default_threads.py --rounds 100 --between 2000
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from typing import Callable, Dict, List

import numpy as np
from scipy.spatial.transform import Rotation

import swarmcollide as sc


def work_for(microseconds: float) -> None:
    """Python work (a busy loop) for about `microseconds`, as a caller between batch calls."""
    end = time.perf_counter() + microseconds * 1e-6
    while time.perf_counter() < end:
        pass


def cases(sizes: List[int]) -> Dict[str, Callable[[object], object]]:
    rng = np.random.default_rng(0)
    points = rng.normal(size=(8, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    body = sc.ConvexPolyhedron(points)
    found: Dict[str, Callable[[object], object]] = {}
    for m in sizes:
        rotations = Rotation.random(m, random_state=1).as_matrix()
        axes = rng.normal(size=(m, 3))
        axes /= np.linalg.norm(axes, axis=1, keepdims=True)
        poses = (rotations, 2.4 * axes)
        for name in ("collide_many", "distance_many"):
            call = getattr(sc, name)
            found[f"{name} m={m} apart"] = (
                lambda threads, call=call, poses=poses: call(body, body, poses_b=poses,
                                                             threads=threads))
        starts = np.repeat(np.eye(4)[None], m, axis=0)
        ends = starts.copy()
        starts[:, 0, 3] = -3
        ends[:, 0, 3] = 3 + rng.normal(size=m)
        ends[:, 1, 3] = 2 * rng.normal(size=m)
        found[f"time_of_impact_many m={m}"] = (
            lambda threads, motions=(starts, ends): sc.time_of_impact_many(
                body, body, poses_b=motions, threads=threads))
    for n, spread in ((20, 3.0), (100, 6.0), (400, 10.0), (2000, 18.0)):
        found.update(scene_cases(n, spread, points))
    try:
        import pybullet_data
    except ImportError:
        print("pybullet_data not found (the bench extra): Robot.check is left out")
        return found
    robot = sc.Robot.from_urdf(os.path.join(pybullet_data.getDataPath(),
                                            "franka_panda/panda.urdf"))
    lower, upper = np.clip(robot.limits, -np.pi, np.pi).T
    q = np.random.default_rng(0).uniform(lower, upper, size=(max(sizes), robot.dof))
    for m in sizes:
        for nearest in (False, True):
            found[f"Robot.check m={m} nearest={nearest}"] = (
                lambda threads, rows=q[:m], nearest=nearest: robot.check(
                    rows, threads=threads, nearest=nearest))
    return found


def scene_cases(n: int, spread: float, points: np.ndarray) -> Dict[str, Callable[[object], object]]:
    """A frame of a scene of n bodies (each body moved a little, then the query), one scene per
    thread count so that each keeps its own warm starts."""
    rng = np.random.default_rng(n)
    centres = rng.uniform(-spread, spread, size=(n, 3))
    scenes = {}
    for threads in (1, None):
        scene = sc.Scene(threads=threads)
        ids = np.concatenate([scene.add(points, np.eye(4)) for _ in range(n)])
        scenes[threads] = (scene, ids)

    def frame(threads: object, query: str) -> object:
        scene, ids = scenes[threads]
        poses = np.repeat(np.eye(4)[None], n, axis=0)
        poses[:, :3, 3] = centres + 0.05 * rng.normal(size=(n, 3))
        scene.set_poses(ids, poses)
        return getattr(scene, query)()

    return {f"Scene.{query} n={n}": (lambda threads, query=query: frame(threads, query))
            for query in ("colliding_pairs", "contacts")}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", default="2,8,32,128,512,2000",
                        help="rows per call (poses, configurations, motions), comma-separated")
    parser.add_argument("--rounds", type=int, default=100, help="interleaved rounds per case")
    parser.add_argument("--between", type=float, default=2000.0,
                        help="microseconds of Python work before each call")
    arguments = parser.parse_args()
    sizes = [int(s) for s in arguments.sizes.split(",")]
    print(f"load before {os.getloadavg()}", flush=True)
    for name, call in cases(sizes).items():
        call(1)  # hulls and caches built before timing
        times: Dict[object, List[float]] = {1: [], None: []}
        for r in range(arguments.rounds):
            for threads in ((1, None) if r % 2 == 0 else (None, 1)):
                work_for(arguments.between)
                start = time.perf_counter()
                call(threads)
                times[threads].append(time.perf_counter() - start)
        one, default = statistics.median(times[1]), statistics.median(times[None])
        print(f"{name:36s} 1 thread {one * 1e6:9.1f} us  default {default * 1e6:9.1f} us  "
              f"gain {one / default:.2f}", flush=True)
    print(f"load after {os.getloadavg()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
