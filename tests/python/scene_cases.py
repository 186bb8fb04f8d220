"""Scenes judged against pairwise queries: one seeded motion run through every broadphase, and
scenes holding bodies far from the origin.

``motion_mismatches`` drives scenes (one per broadphase, the same motion) through small moves and
turns, teleports, jumps 1e3 away and back, and bodies added and removed, and compares every
frame's ``colliding_pairs()`` and ``pairs_within(d)`` with brute force: exact distances of every
pair from ``distance_many`` (the batch path, which shares no code with the scene's broadphase or
pair table). The short run is a test (test_scene_oracle.py), the long one a census surface
(``tests/fuzz/census.py --surface scene``). The functions here are importable by the sandbox's
children (tests/python/sandbox.py), so that a crash or a hang fails one case, not the run.
"""

from __future__ import annotations

import itertools
import time
from typing import Any, Dict, List, Tuple

import numpy as np

import swarmcollide as sc

THRESHOLD = 0.1
"""The distance of the ``pairs_within`` query each frame."""


def random_hull(rng: np.random.Generator) -> np.ndarray:
    """4 to 10 points on a sphere of radius 0.3-0.6, off centre."""
    points = rng.normal(size=(int(rng.integers(4, 11)), 3))
    points /= np.linalg.norm(points, axis=1)[:, None]
    return points * rng.uniform(0.3, 0.6) + rng.uniform(-0.1, 0.1, 3)


def random_rotations(rng: np.random.Generator, count: int, angle: float) -> np.ndarray:
    """``count`` rotations about random axes by normal angles of deviation ``angle``."""
    axes = rng.normal(size=(count, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    angles = rng.normal(0, angle, count)
    k = np.zeros((count, 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -axes[:, 2], axes[:, 1], -axes[:, 0]
    k -= k.transpose(0, 2, 1)
    s, c = np.sin(angles)[:, None, None], np.cos(angles)[:, None, None]
    return np.eye(3) + s * k + (1 - c) * k @ k


def pair_size(a: np.ndarray, pose_a: np.ndarray, b: np.ndarray, pose_b: np.ndarray) -> float:
    """The size tolerances are relative to (docs: the diameter of a ball around both bodies):
    |c_b - c_a| + 2 max(r_a, r_b), each body's ball centred on its own box, of half its diagonal.
    """
    def ball(points: np.ndarray, pose: np.ndarray) -> Tuple[np.ndarray, float]:
        low, high = points.min(axis=0), points.max(axis=0)
        return pose[:3, :3] @ ((low + high) / 2) + pose[:3, 3], float(np.linalg.norm(high - low) / 2)

    (ca, ra), (cb, rb) = ball(a, pose_a), ball(b, pose_b)
    return float(np.linalg.norm(cb - ca)) + 2 * max(ra, rb)


class Motion:
    """A seeded world of bodies in a box, moved frame by frame.

    Each frame every body moves by about 1% of the box and turns by about 0.05 rad; every 10th
    frame 5% of them teleport to random places, and 1% jump 1e3 away and come back 10 frames
    later; at ``churn_every`` frames, 5% are removed and as many new ones added.
    """

    def __init__(self, seed: int, bodies: int, side: float, churn_every: int = 7) -> None:
        self.rng = np.random.default_rng(seed)
        self.side = side
        self.churn_every = churn_every
        self.frame = 0
        self.next_id = 0
        self.hulls: Dict[int, np.ndarray] = {}
        self.poses: Dict[int, np.ndarray] = {}
        self.returns: Dict[int, List[Tuple[int, np.ndarray]]] = {}
        self.added: List[int] = self.new_bodies(bodies)
        self.removed: List[int] = []

    def new_bodies(self, count: int) -> List[int]:
        ids = list(range(self.next_id, self.next_id + count))
        self.next_id += count
        rotations = random_rotations(self.rng, count, np.pi)
        for i, rotation in zip(ids, rotations):
            self.hulls[i] = random_hull(self.rng)
            pose = np.eye(4)
            pose[:3, :3] = rotation
            pose[:3, 3] = self.rng.uniform(0, self.side, 3)
            self.poses[i] = pose
        return ids

    def step(self) -> None:
        """The next frame: ``added``, ``removed`` and ``poses`` say what changed."""
        self.frame += 1
        rng, ids = self.rng, sorted(self.poses)
        turns = random_rotations(rng, len(ids), 0.05)
        for i, turn in zip(ids, turns):
            self.poses[i][:3, :3] = turn @ self.poses[i][:3, :3]
            self.poses[i][:3, 3] += rng.normal(0, 0.01 * self.side / 5, 3)
        for i, position in self.returns.pop(self.frame, []):
            if i in self.poses:
                self.poses[i][:3, 3] = position
        if self.frame % 10 == 0:
            count = max(1, len(ids) // 20)
            for i in rng.choice(ids, count, replace=False).tolist():
                self.poses[i][:3, 3] = rng.uniform(0, self.side, 3)
            far = rng.choice(ids, max(1, len(ids) // 100), replace=False).tolist()
            self.returns[self.frame + 10] = [(i, self.poses[i][:3, 3].copy()) for i in far]
            for i in far:
                self.poses[i][:3, 3] += 1e3 * rng.normal(size=3) / np.sqrt(3)
        self.added, self.removed = [], []
        if self.frame % self.churn_every == 0:
            count = max(1, len(ids) // 20)
            self.removed = sorted(rng.choice(ids, count, replace=False).tolist())
            for i in self.removed:
                del self.hulls[i], self.poses[i]
            self.added = self.new_bodies(count)

    def truth(self, tolerance: float) -> Tuple[Dict[Tuple[int, int], float], Dict[Tuple[int, int], float]]:
        """(exact distance, tolerance x size) of every pair, by ``distance_many``."""
        ids = sorted(self.poses)
        pairs = list(itertools.combinations(ids, 2))
        if not pairs:
            return {}, {}
        first, second = zip(*pairs)
        placed = {i: self.hulls[i] @ self.poses[i][:3, :3].T + self.poses[i][:3, 3] for i in ids}
        result = sc.distance_many([placed[i] for i in first], [placed[i] for i in second],
                                  method="exact")  # fmt: skip
        sizes = [pair_size(self.hulls[a], self.poses[a], self.hulls[b], self.poses[b])
                 for a, b in pairs]  # fmt: skip
        distance = dict(zip(pairs, result.distance.tolist()))
        allowance = {p: tolerance * s + 1e-12 * s for p, s in zip(pairs, sizes)}
        return distance, allowance


def _apply(scene: "sc.Scene", motion: Motion, first: bool) -> None:
    if motion.removed:
        scene.remove(motion.removed)
    if motion.added:
        ids = scene.add([motion.hulls[i] for i in motion.added],
                        np.stack([motion.poses[i] for i in motion.added]))  # fmt: skip
        assert ids.tolist() == motion.added, "the scene gave other ids than the motion's"
    moved = sorted(set(motion.poses) - set(motion.added)) if not first else []
    if moved:
        scene.set_poses(moved, np.stack([motion.poses[i] for i in moved]))


def _compare(name: str, rows: Any, truth: Dict, allowance: Dict, within: float) -> List[str]:
    """What is wrong with ``rows`` (a SceneResult) for pairs within ``within`` of each other."""
    problems = []
    found = {tuple(p): k for k, p in enumerate(rows.pairs.tolist())}
    for pair, d in truth.items():
        if d < within - allowance[pair] and pair not in found:
            problems.append(f"{name}: pair {pair} at distance {d:.3g} is missing")
        if d > within + allowance[pair] and pair in found:
            problems.append(f"{name}: pair {pair} at distance {d:.3g} is listed")
    for pair, k in found.items():
        if pair not in truth:
            problems.append(f"{name}: pair {pair} is not a pair of the scene")
            continue
        if not rows.certified[k]:
            problems.append(f"{name}: pair {pair} is not certified")
    return problems


def motion_mismatches(
    broadphases: Tuple[str, ...], seed: int, bodies: int, frames: int, side: float = 5.0
) -> List[str]:
    """Every difference, frame by frame, between each broadphase's scene and brute force."""
    motion = Motion(seed, bodies, side)
    scenes = {b: sc.Scene(broadphase=b, threads=1) for b in broadphases}
    problems: List[str] = []
    for frame in range(frames):
        if frame:
            motion.step()
        truth, allowance = motion.truth(scenes[broadphases[0]].tolerance)
        for broadphase, scene in scenes.items():
            _apply(scene, motion, first=frame == 0)
            where = f"frame {frame}, {broadphase}"
            problems += _compare(f"{where}, colliding_pairs", scene.colliding_pairs(), truth,
                                 allowance, 0.0)  # fmt: skip
            problems += _compare(f"{where}, pairs_within({THRESHOLD})",
                                 scene.pairs_within(THRESHOLD), truth, allowance, THRESHOLD)
    return problems


SCENE_QUERIES = {
    "colliding_pairs": ("collide", lambda scene: scene.colliding_pairs()),
    "pairs_within": ("distance", lambda scene: scene.pairs_within(0.5)),
    "min_distance": ("distance", lambda scene: scene.min_distance()),
    "nearest": ("distance", lambda scene: scene.nearest(scene.ids[:10], k=3)),
    "contacts": ("signed_distance", lambda scene: scene.contacts()),
}
"""Each scene query: the pair query whose capability it needs, and how a check calls it."""


def certified_wrong(method: str, seed: int, bodies: int, side: float) -> List[str]:
    """Certified rows of every scene query whose bounds miss the exact distance, or whose
    distance is farther from it than tolerance x size (pairs_within, min_distance, nearest)."""
    motion = Motion(seed, bodies, side)
    ids = sorted(motion.hulls)
    scene = sc.Scene(method=method, threads=1)
    scene.add([motion.hulls[i] for i in ids], np.stack([motion.poses[i] for i in ids]))
    truth, allowance = motion.truth(scene.tolerance)
    problems = []
    for name, (capability, query) in SCENE_QUERIES.items():
        if capability not in sc.METHODS[method].queries:
            continue
        rows = query(scene)
        for k, (a, b) in enumerate(rows.pairs.tolist()):
            if not rows.certified[k]:
                continue
            pair = (min(a, b), max(a, b))
            t, slack = truth[pair], allowance[pair]
            lower, upper = rows.lower_bound[k], rows.distance[k]
            if capability == "signed_distance":
                wrong = t > slack or upper > slack  # in contact, at a signed distance <= 0
            elif capability == "collide":
                # Methods without distances (libccd) bound the signed distance, negative here.
                wrong = t > slack or lower - slack > t
            else:
                wrong = not lower - slack <= t <= upper + slack or upper - t > slack
            if wrong:
                problems.append(f"{method} {name}: pair {pair} certified with [{lower!r}, "
                                f"{upper!r}], exact distance {t!r}, tolerance x size {slack:.3g}")
    return problems


# ----- far bodies ------------------------------------------------------------------------------

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)


def _at(x: float) -> np.ndarray:
    pose = np.eye(4)
    pose[0, 3] = x
    return pose


def far_body_answers(broadphase: str, how: str, far: float) -> Dict[str, Any]:
    """Every query of a scene of two cubes 2.5 apart and a third ``far`` away along x.

    ``how``: "batch" adds the three at once, "alone" adds the far one by itself, "moved" moves
    the third there with ``set_poses``. Returns each query's (pairs, distances, certified), or
    ``{"refused": message}`` when the scene refuses the far pose with a ValueError.
    """
    scene = sc.Scene(broadphase=broadphase, threads=1)
    near = [_at(0.0), _at(3.5)]
    try:
        if how == "batch":
            scene.add([CUBE] * 3, np.stack(near + [_at(far)]))
        elif how == "alone":
            scene.add([CUBE] * 2, np.stack(near))
            scene.add(CUBE, _at(far))
        else:
            scene.add([CUBE] * 3, np.stack(near + [_at(7.0)]))
            scene.set_poses(2, _at(far))
    except ValueError as error:
        return {"refused": str(error), "bodies": len(scene)}
    queries = {
        "colliding_pairs": scene.colliding_pairs,
        "pairs_within": lambda: scene.pairs_within(3.0),
        "min_distance": scene.min_distance,
        "nearest": lambda: scene.nearest([0, 2], k=2),
        "contacts": scene.contacts,
    }
    answers = {}
    for name, query in queries.items():
        r = query()
        answers[name] = (r.pairs.tolist(), r.distance.tolist(), r.certified.tolist())
    return answers


def timed(function: Any, *args: Any) -> Dict[str, Any]:
    """``function(*args)`` with the seconds it took (for the census)."""
    start = time.monotonic()
    value = function(*args)
    return {"value": value, "seconds": time.monotonic() - start}
