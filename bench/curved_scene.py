"""A scene of spheres and capsules against one of 8-vertex hulls of the same sizes: issue 26 asks
the first to be as fast per candidate pair as the second. The same random placements (bodies of
radius 0.15-0.35 in a cube, dense enough that many boxes overlap), moved a little each frame;
each frame's ``colliding_pairs`` is timed (thread CPU time) and divided by the scene's candidate
pairs. The two scenes are interleaved frame by frame, and the ratio is of their medians.

    python bench/curved_scene.py [--bodies 400] [--frames 30] [--json bench/results/curved_scene.json]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np

import record
from markdown import table
import swarmcollide as sc


def hull8(rng: np.random.Generator, radius: float) -> np.ndarray:
    """8 points on a sphere of ``radius``: an 8-vertex hull of the same reach."""
    points = rng.normal(size=(8, 3))
    return radius * points / np.linalg.norm(points, axis=1, keepdims=True)


def poses_for(rng: np.random.Generator, count: int, spread: float) -> np.ndarray:
    q, r = np.linalg.qr(rng.normal(size=(count, 3, 3)))
    q = q * np.sign(np.diagonal(r, axis1=1, axis2=2))[:, None, :]
    q[np.linalg.det(q) < 0] *= -1
    poses = np.tile(np.eye(4), (count, 1, 1))
    poses[:, :3, :3] = q
    poses[:, :3, 3] = rng.uniform(-spread, spread, (count, 3))
    return poses


def section(data: dict) -> str:
    """The RESULTS.md section of a recorded run."""
    machine = data["machine"]
    lines = [f"`{data['command']}`, load average {machine['load_average_start']} -> "
             f"{machine['load_average_end']}, {machine['date']}. {data['bodies']} bodies of each "
             f"kind moved over {data['frames']} frames, the two scenes interleaved frame by frame; "
             "each time is the median over frames of `colliding_pairs`' thread CPU time divided by "
             "the scene's candidate pairs. Issue 26 asks the first row to be at most the second.",
             ""]
    rows = [[row["scene"], f"{row['nanoseconds_per_candidate']:.0f} ns",
             f"{row['ratio_to_hulls']:.2f}x"] for row in data["rows"]]
    lines.append(table(["scene", "per candidate pair", "against the hulls"], rows))
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bodies", type=int, default=400)
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--quick", action="store_true", help="100 bodies, 10 frames")
    parser.add_argument("--json", help="write the results here (bench/record.py's format)")
    arguments = parser.parse_args()
    bodies, frames = (100, 10) if arguments.quick else (arguments.bodies, arguments.frames)
    rng = np.random.default_rng(26)
    radii = rng.uniform(0.15, 0.35, bodies)
    rounded = [sc.Sphere(r) if k % 2 else sc.Capsule(r / 2, r / 2) for k, r in enumerate(radii)]
    hulls = [sc.ConvexPolyhedron(hull8(rng, r)) for r in radii]
    spread = 0.45 * bodies ** (1 / 3)
    start = poses_for(rng, bodies, spread)
    scenes = {"spheres and capsules": sc.Scene(threads=1), "8-vertex hulls": sc.Scene(threads=1)}
    ids = {"spheres and capsules": scenes["spheres and capsules"].add(rounded, start),
           "8-vertex hulls": scenes["8-vertex hulls"].add(hulls, start)}
    per_pair = {name: [] for name in scenes}
    found = {name: [] for name in scenes}
    for frame in range(frames):
        poses = start.copy()
        poses[:, :3, 3] += rng.normal(scale=0.02 * (frame + 1), size=(bodies, 3))
        for name, scene in scenes.items():
            scene.set_poses(ids[name], poses)
            before = time.thread_time()
            hits = scene.colliding_pairs()
            elapsed = time.thread_time() - before
            candidates = scene.stats.candidates
            per_pair[name].append(elapsed / max(candidates, 1))
            found[name].append((len(hits), candidates))
    medians = {name: statistics.median(t) * 1e9 for name, t in per_pair.items()}
    ratio = medians["spheres and capsules"] / medians["8-vertex hulls"]
    load = os.getloadavg()[0]
    for name in scenes:
        hits, candidates = found[name][-1]
        print(f"{name:>21}: {medians[name]:8.1f} ns per candidate pair ({candidates} candidates, "
              f"{hits} colliding in the last frame)")
    print(f"ratio spheres and capsules / 8-vertex hulls: {ratio:.2f} (load {load:.1f})")
    if arguments.json:
        rows = [{"scene": name, "nanoseconds_per_candidate": medians[name],
                 "ratio_to_hulls": medians[name] / medians["8-vertex hulls"]} for name in scenes]
        record.write(arguments.json, "curved_scene", rows, bodies=bodies, frames=frames)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
