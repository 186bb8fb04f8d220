"""Scenes judged against pairwise queries: one seeded motion run through every broadphase, and
scenes holding bodies far from the origin.

``motion_mismatches`` drives scenes (one per broadphase, the same motion) through small moves and
turns, teleports, jumps 1e3 away and back, and bodies added and removed, and compares every
frame's ``colliding_pairs()`` and ``pairs_within(d)`` with brute force: exact distances of every
pair from ``distance_many`` (the batch path, which shares no code with the scene's broadphase or
pair table). The short run is a test (test_scene_oracle.py), the long one a census corpus
(``tests/fuzz/census.py --corpus scene``). The functions here are importable by the sandbox's
children (tests/python/sandbox.py), so that a crash or a hang fails one case, not the run.
"""

from __future__ import annotations

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


NEAR = 1.0
"""Pairs whose bounding balls are farther apart than this are farther than every query's
threshold here (``THRESHOLD``, and 0.5 for ``certified_wrong``)."""


def ball(points: np.ndarray, pose: np.ndarray) -> Tuple[np.ndarray, float]:
    """The ball the library sizes a body by: centred on its own box, of half its diagonal."""
    low, high = points.min(axis=0), points.max(axis=0)
    return pose[:3, :3] @ ((low + high) / 2) + pose[:3, 3], float(np.linalg.norm(high - low) / 2)


def pair_size(a: np.ndarray, pose_a: np.ndarray, b: np.ndarray, pose_b: np.ndarray) -> float:
    """The size tolerances are relative to (docs: the diameter of a ball around both bodies):
    |c_b - c_a| + 2 max(r_a, r_b), with each body's ``ball``.
    """
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

    def placed(self, i: int) -> np.ndarray:
        return self.hulls[i] @ self.poses[i][:3, :3].T + self.poses[i][:3, 3]

    def truth(self, tolerance: float) -> Tuple[Dict[Tuple[int, int], float], Dict[Tuple[int, int], float]]:
        """(exact distance, tolerance x size) of every pair whose bounding balls lie within
        ``NEAR`` of each other (the others are farther apart than any query here asks about),
        by ``distance_many``; ``exact`` answers the others."""
        ids = sorted(self.poses)
        balls = [ball(self.hulls[i], self.poses[i]) for i in ids]
        centres = np.array([c for c, _ in balls]).reshape(-1, 3)
        radii = np.array([r for _, r in balls])
        gaps = np.linalg.norm(centres[:, None] - centres[None], axis=2) - radii[:, None] - radii
        first, second = np.nonzero(np.triu(gaps <= NEAR, 1))
        pairs = [(ids[a], ids[b]) for a, b in zip(first.tolist(), second.tolist())]
        if not pairs:
            return {}, {}
        result = sc.distance_many([self.placed(a) for a, _ in pairs],
                                  [self.placed(b) for _, b in pairs], method="exact")  # fmt: skip
        distance = dict(zip(pairs, result.distance.tolist()))
        allowance = {(a, b): self.allowance(a, b, tolerance) for a, b in pairs}
        return distance, allowance

    def allowance(self, a: int, b: int, tolerance: float) -> float:
        """tolerance x size of the pair, and rounding."""
        size = pair_size(self.hulls[a], self.poses[a], self.hulls[b], self.poses[b])
        return tolerance * size + 1e-12 * size

    def exact(self, a: int, b: int) -> float:
        return sc.distance(self.placed(a), self.placed(b), method="exact").distance


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


def _compare(
    name: str, rows: Any, truth: Dict, allowance: Dict, within: float, ids: Any
) -> List[str]:
    """What is wrong with ``rows`` (a SceneResult) for pairs within ``within`` of each other."""
    problems = []
    found = {tuple(p): k for k, p in enumerate(rows.pairs.tolist())}
    for pair, d in truth.items():
        if d < within - allowance[pair] and pair not in found:
            problems.append(f"{name}: pair {pair} at distance {d:.3g} is missing")
        if d > within + allowance[pair] and pair in found:
            problems.append(f"{name}: pair {pair} at distance {d:.3g} is listed")
    for pair, k in found.items():
        if pair[0] not in ids or pair[1] not in ids or pair[0] >= pair[1]:
            problems.append(f"{name}: pair {pair} is not a pair of the scene")
            continue
        if pair not in truth:
            problems.append(f"{name}: pair {pair} is listed, its balls {NEAR} apart or more")
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
                                 allowance, 0.0, motion.poses)  # fmt: skip
            problems += _compare(f"{where}, pairs_within({THRESHOLD})",
                                 scene.pairs_within(THRESHOLD), truth, allowance, THRESHOLD,
                                 motion.poses)
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
            t = truth[pair] if pair in truth else motion.exact(*pair)
            slack = allowance[pair] if pair in allowance else motion.allowance(*pair, scene.tolerance)
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


# ----- the census's scene surface --------------------------------------------------------------

FAMILIES = ("motion", "certified", "far", "argument")
"""The scene census's families of cases, taken in turn by case index."""

FAR = (1e100, 1e149, 1e155, 1e200, 1e300)

CORPUS_BROADPHASES = ("dynamic_aabb_tree", "dynamic_aabb_tree_array", "sap", "ssap",
                      "interval_tree", "spatial_hashing", "brute_force")  # fmt: skip
"""The broadphases cases are drawn from, frozen (main's list when the surface was added), so
that a case index names the same case before and after a change; a name the scene refuses with
its reason counts as ok."""

UNCLEAR = ("incompatible function arguments", "only integer scalar arrays", "must not be None")
"""Fragments of error messages that do not name the argument and the fix."""

BAD_ARGUMENTS = {
    "exclude([0, 0])": lambda s: s.exclude([0, 0]),
    "include([0, 0])": lambda s: s.include([0, 0]),
    "include([0, 99])": lambda s: s.include([0, 99]),
    "add(group=array)": lambda s: s.add(np.eye(3), group=np.array([1, 2])),
    "pairs_within('a')": lambda s: s.pairs_within("a"),
    "pairs_within(-1)": lambda s: s.pairs_within(-1.0),
    "pairs_within(inf)": lambda s: s.pairs_within(float("inf")),
    "pairs_within(1e200)": lambda s: s.pairs_within(1e200),
    "contacts('x')": lambda s: s.contacts("x"),
    "contacts(0)": lambda s: s.contacts(0),
    "nearest(k='2')": lambda s: s.nearest([0], k="2"),
    "nearest(k=0)": lambda s: s.nearest([0], k=0),
    "nearest([99])": lambda s: s.nearest([99]),
    "set_poses(99)": lambda s: s.set_poses(99, np.eye(4)),
    "set_poses(nan)": lambda s: s.set_poses(0, np.full((4, 4), np.nan)),
    "remove([0, 0])": lambda s: s.remove([0, 0]),
}
"""Calls a scene of three bodies must refuse with a ValueError or TypeError that names the
argument: (name, call)."""

NO_OPS = {"set_poses([], [])": lambda s: s.set_poses([], [])}
"""Calls that must change nothing and answer nothing."""


def _verdict(category: str, reason: str = "") -> Dict[str, Any]:
    return {"category": category, "reason": reason}


def scene_case(seed: int, index: int) -> Tuple[str, str, str, tuple]:
    """(family, query, label, arguments) of case ``index`` of corpus ``seed``."""
    rng = np.random.default_rng([seed, index, 23])
    family = FAMILIES[index % len(FAMILIES)]
    broadphases = CORPUS_BROADPHASES
    if family == "motion":
        broadphase = broadphases[int(rng.integers(len(broadphases)))]
        bodies, frames = int(rng.integers(60, 301)), int(rng.integers(20, 61))
        side = float(rng.uniform(3.0, 6.0)) * (bodies / 150) ** (1 / 3)
        return family, "motion", broadphase, (broadphase, int(rng.integers(2**31)), bodies, frames,
                                              side)  # fmt: skip
    if family == "certified":
        method = list(sc.METHODS)[int(rng.integers(len(sc.METHODS)))]
        return family, "every query", method, (method, int(rng.integers(2**31)), 80, 4.0)
    if family == "far":
        broadphase = broadphases[int(rng.integers(len(broadphases)))]
        how = ("batch", "alone", "moved")[int(rng.integers(3))]
        far = FAR[int(rng.integers(len(FAR)))]
        return family, f"far {far:g}", broadphase, (broadphase, how, far)
    names = list(BAD_ARGUMENTS) + list(NO_OPS)
    name = names[int(rng.integers(len(names)))]
    return family, "argument", name, (name,)


def run_scene_case(seed: int, index: int) -> Dict[str, Any]:
    """Make and judge scene case ``index``: ``{"category", "reason"}`` (fuzz_judge's categories)."""
    family, _, _, arguments = scene_case(seed, index)
    try:
        if family == "motion":
            broadphase, *rest = arguments
            problems = motion_mismatches((broadphase,), *rest)
            return _verdict("wrong", problems[0]) if problems else _verdict("ok")
        if family == "certified":
            problems = certified_wrong(*arguments)
            return _verdict("wrong", problems[0]) if problems else _verdict("ok")
        if family == "far":
            return _judge_far(*arguments)
        return _judge_argument(*arguments)
    except (ValueError, TypeError) as error:
        if "dynamic_aabb_tree_array" in str(error) and "no longer offered" in str(error):
            return _verdict("ok", str(error))
        return _verdict("error-type", f"an answer was due: {type(error).__name__}: {error}")


def _judge_far(broadphase: str, how: str, far: float) -> Dict[str, Any]:
    answers = far_body_answers(broadphase, how, far)
    if "refused" in answers:
        if far > 1e150 and "within 1e+150" in answers["refused"]:
            return _verdict("ok", answers["refused"])
        return _verdict("error-type", f"refused: {answers['refused']}")
    expected = {
        "colliding_pairs": [],
        "pairs_within": [((0, 1), 2.5)],
        "min_distance": [((0, 1), 2.5)],
        "nearest": [((0, 1), 2.5), ((0, 2), far - 1), ((2, 0), far - 1), ((2, 1), far - 4.5)],
        "contacts": [],
    }
    for query, rows in expected.items():
        pairs, distances, certified = answers[query]
        got = [(tuple(p), d) for p, d in zip(pairs, distances)]
        if [p for p, _ in got] != [p for p, _ in rows] or not all(certified) or any(
            abs(d - e) > 1e-12 * max(1.0, e) + 1e-9 for (_, d), (_, e) in zip(got, rows)
        ):
            return _verdict("wrong", f"{query}: {answers[query]}")
    return _verdict("ok")


def _judge_argument(name: str) -> Dict[str, Any]:
    scene = sc.Scene()
    scene.add([CUBE] * 3, np.stack([_at(0.0), _at(0.5), _at(3.0)]))
    if name in NO_OPS:
        NO_OPS[name](scene)
        return _verdict("ok")
    try:
        BAD_ARGUMENTS[name](scene)
    except (ValueError, TypeError) as error:
        text = f"{type(error).__name__}: {error}"
        if any(fragment in str(error) for fragment in UNCLEAR):
            return _verdict("error-type", f"unclear: {text[:200]}")
        return _verdict("ok", text)
    return _verdict("slipped", f"{name} was accepted")
