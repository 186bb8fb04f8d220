"""A Scene from Python against python-fcl's manager and trimesh's CollisionManager.

N unit-size 8-vertex hulls with random rotations, about 3-4 colliding pairs per body (the
workload of bench/scene_bench.cpp, drawn with NumPy), a cold frame, then warm frames of small
motion; every contender runs each frame in turn, on the same poses.

    python bench/scene.py [--quick] [--json bench/results/scene_python.json]
"""

from __future__ import annotations

import argparse
import os
import time
from typing import Callable, Dict, List, Optional

import fcl
import numpy as np
import trimesh
from trimesh.collision import CollisionManager

import record
import swarmcollide as sc

# As in scene_bench.cpp: bodies per unit volume, and per-frame motion.
DENSITY = 2.85
STEP = 0.004
TURN = 0.01


def rotations(rng: np.random.Generator, count: int) -> np.ndarray:
    q = rng.normal(size=(count, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], 1)


def axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    k = np.zeros((len(axis), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -axis[:, 2], axis[:, 1], -axis[:, 0]
    k -= np.transpose(k, (0, 2, 1))
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k)


def workload(n: int, frames: int, seed: int):
    """The bodies, their hulls' faces, and (frames, n, 4, 4) poses."""
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(n, 8, 3))
    points *= 0.5 / np.linalg.norm(points, axis=2)[:, :, None]
    faces = [sc.ConvexPolyhedron(p).hull().faces for p in points]
    side = (n / DENSITY) ** (1 / 3)
    rotation = rotations(rng, n)
    position = rng.uniform(0, side, (n, 3))
    velocity = rng.normal(0, STEP, (n, 3))
    axis = rng.normal(size=(n, 3))
    spin = axis_angle(axis / np.linalg.norm(axis, axis=1)[:, None], TURN)
    poses = np.zeros((frames, n, 4, 4))
    poses[:, :, 3, 3] = 1
    for f in range(frames):
        poses[f, :, :3, :3] = rotation
        poses[f, :, :3, 3] = position
        # Re-orthonormalised so that rounding never accumulates past the pose tolerance.
        u, _, vt = np.linalg.svd(spin @ rotation)
        rotation = u @ vt
        position = position + velocity
    return points, faces, poses


class OurScene:
    def __init__(self, points, threads):
        self.points, self.threads = points, threads

    def cold(self, poses):
        self.scene = sc.Scene(threads=self.threads)
        self.ids = self.scene.add(self.points, poses)
        return self.count()

    def frame(self, poses):
        self.scene.set_poses(self.ids, poses)
        return self.count()

    def count(self):
        return {"pairs": len(self.scene.colliding_pairs())}

    def stats(self):
        """The last query's stats, read after its timing (their cache_bytes walks the pair
        table, which a frame does not need)."""
        stats = self.scene.stats
        return {"candidates": stats.candidates, "certified": stats.certified,
                "escalations": stats.escalations,
                "bytes_per_cached_pair": stats.cache_bytes / max(stats.cached_pairs, 1)}


class PythonFcl:
    """python-fcl as its users run it: a transform per object set from Python, the manager
    updated, and a Python callback per candidate pair that counts it (``narrow``: that also
    runs fcl.collide on it)."""

    def __init__(self, points, faces, narrow):
        self.shapes = [fcl.Convex(p, len(f), np.hstack([np.full((len(f), 1), 3), f]).ravel())
                       for p, f in zip(points, faces)]
        self.narrow = narrow

    def place(self, poses):
        for obj, pose in zip(self.objects, poses):
            obj.setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))

    def cold(self, poses):
        self.objects = [fcl.CollisionObject(s, fcl.Transform(p[:3, :3], p[:3, 3]))
                        for s, p in zip(self.shapes, poses)]
        self.manager = fcl.DynamicAABBTreeCollisionManager()
        self.manager.registerObjects(self.objects)
        self.manager.setup()
        return self.count()

    def frame(self, poses):
        self.place(poses)
        self.manager.update()
        return self.count()

    def count(self):
        counts = {"candidates": 0, "pairs": 0}
        request = fcl.CollisionRequest()

        def counting(o1, o2, data):
            counts["candidates"] += 1
            return False

        def colliding(o1, o2, data):
            counts["candidates"] += 1
            counts["pairs"] += fcl.collide(o1, o2, request, fcl.CollisionResult()) > 0
            return False

        self.manager.collide(None, colliding if self.narrow else counting)
        if not self.narrow:
            counts.pop("pairs")
        return counts


class Trimesh:
    """trimesh's CollisionManager: a transform per object, then in_collision_internal."""

    def __init__(self, points, faces):
        self.meshes = [trimesh.Trimesh(p, f, process=False) for p, f in zip(points, faces)]

    def cold(self, poses):
        self.manager = CollisionManager()
        for i, (mesh, pose) in enumerate(zip(self.meshes, poses)):
            self.manager.add_object(str(i), mesh, transform=pose)
        return self.count()

    def frame(self, poses):
        for i, pose in enumerate(poses):
            self.manager.set_transform(str(i), pose)
        return self.count()

    def count(self):
        _, names = self.manager.in_collision_internal(return_names=True)
        return {"pairs": len(names)}


def timed(run: Callable[[], Dict], after: Optional[Callable[[], Dict]] = None) -> Dict:
    """`run()`'s result with its times, and then what `after()` adds (untimed)."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = run()
    result["seconds"] = time.perf_counter() - wall
    result["cpu_seconds"] = time.process_time() - cpu
    if after is not None:
        result.update(after())
    return result


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer frames and repeats")
    parser.add_argument("--json", default=None, help="write the results there")
    args = parser.parse_args()
    warm_frames = 3 if args.quick else 10
    cold_repeats = 1 if args.quick else 3
    load_before = os.getloadavg()
    rows: List[Dict] = []
    for n in (1000, 10000):
        points, faces, poses = workload(n, warm_frames + 1, seed=2024 + n)
        contenders = {
            "scene_1_thread": OurScene(points, 1),
            "scene_2_threads": OurScene(points, 2),
            "python_fcl_counting": PythonFcl(points, faces, narrow=False),
            "python_fcl_collide": PythonFcl(points, faces, narrow=True),
            "trimesh": Trimesh(points, faces),
        }
        if n > 1000 and args.quick:
            # A Python call per candidate with FCL's sphere boxes: a quarter of a million a frame.
            del contenders["python_fcl_collide"]
        runs = {(name, kind): [] for name in contenders for kind in ("cold", "warm")}
        for _ in range(cold_repeats):
            for name, c in contenders.items():
                runs[(name, "cold")].append(
                    timed(lambda: c.cold(poses[0]), getattr(c, "stats", None)))
        for f in range(1, warm_frames + 1):
            for name, c in contenders.items():
                runs[(name, "warm")].append(
                    timed(lambda: c.frame(poses[f]), getattr(c, "stats", None)))
        for (name, kind), results in runs.items():
            row = {"contender": name, "n": n, "frame": kind, "repeats": len(results),
                   "median_s": float(np.median([r["seconds"] for r in results])),
                   "median_cpu_s": float(np.median([r["cpu_seconds"] for r in results])),
                   "min_s": float(min(r["seconds"] for r in results))}
            row.update({k: v for k, v in results[-1].items() if k not in ("seconds", "cpu_seconds")})
            rows.append(row)
            print(f"{name:22s} N={n:<6d} {kind:5s} {1e3 * row['median_s']:9.2f} ms "
                  f"(cpu {1e3 * row['median_cpu_s']:8.2f}, min {1e3 * row['min_s']:8.2f}) "
                  + " ".join(f"{k}={v:g}" for k, v in results[-1].items()
                             if k not in ("seconds", "cpu_seconds")), flush=True)
    if args.json:
        context = {"mode": "quick" if args.quick else "full", "warm_frames": warm_frames,
                   "cold_repeats": cold_repeats}
        record.write(args.json, "scene_python", rows, load_start=load_before, context=context)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
