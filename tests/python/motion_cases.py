"""Motions judged against oracles that share no code with conservative advancement.

The census's ``motions`` corpus (``tests/fuzz/census.py --corpus motions``). Its families:

``sampled``   random bodies of every kind (polytopes from fuzz_cases.py, degenerate ones among
              them, rounded bodies, curved shapes, compound bodies) on random linear and screw
              motions, at scales 1e-100..1e100, judged on a dense sampling of the exact signed
              distance at poses computed here from the documentation's formulas, refined around
              its smallest minima.
``swept``     a polytope (possibly rounded) translating past a still body of any kind. Its sweep
              is the hull of its points at both ends, so the closest approach over the motion is
              one exact signed distance, with no sampling: the still body is shifted so that the
              approach is a chosen multiple of the tolerance (grazes that miss by 1e-9 of the size,
              touch by 1e-9, or lie inside the tolerance's band), and every verdict outside the
              band is checked exactly, as is the proven-free part ``[0, t_lower]``.
``batch``     ``time_of_impact_many`` against single calls, with 1 and 2 threads: every field
              identical.
``argument``  bad input: each call must raise ValueError or TypeError naming the argument.

Judged in fuzz_judge.py's categories; importable by the sandbox's children.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
from scipy.optimize import minimize_scalar
from scipy.spatial.transform import Rotation

import swarmcollide as sc
from fuzz_cases import body as random_points

FAMILIES = ("sampled", "swept", "sampled", "swept", "batch", "argument")
"""Case ``index`` belongs to ``FAMILIES[index % len(FAMILIES)]``."""

SAMPLES = 240
"""Times of the dense sampling (the ends and any bracket added)."""

ORACLE_TOLERANCE = 1e-12
"""The exact oracle's tolerance, relative to the pair's size."""

CURVED_KINDS = ("sphere", "capsule", "box", "cylinder", "cone", "ellipsoid")

Body = Any
Motion = Tuple[np.ndarray, np.ndarray]


def _verdict(category: str, reason: str = "") -> Dict[str, Any]:
    return {"category": category, "reason": reason}


# ----- bodies ----------------------------------------------------------------------------------


def _curved(rng: np.random.Generator, kind: str, scale: float) -> Body:
    radius, half = rng.uniform(0.1, 0.5, 2) * scale
    if kind == "sphere":
        return sc.Sphere(radius)
    if kind == "capsule":
        return sc.Capsule(radius, half)
    if kind == "box":
        return sc.Box(rng.uniform(0.05, 0.5, 3) * scale)
    if kind == "cylinder":
        return sc.Cylinder(radius, half)
    if kind == "cone":
        return sc.Cone(radius, half)
    return sc.Ellipsoid(rng.uniform(0.05, 0.5, 3) * scale)


def random_body(rng: np.random.Generator, scale: float, compound: bool = True) -> Tuple[Body, str]:
    """A body of size about ``scale`` near the origin, and its kind."""
    roll = rng.random()
    if roll < 0.45:
        points, kind = random_points(rng)
        if rng.random() < 0.2:
            radius = float(rng.uniform(0.01, 0.2))
            return sc.ConvexPolyhedron(points * scale, radius=radius * scale), f"rounded-{kind}"
        return sc.ConvexPolyhedron(points * scale), kind
    if roll < 0.85 or not compound:
        kind = CURVED_KINDS[int(rng.integers(len(CURVED_KINDS)))]
        return _curved(rng, kind, scale), kind
    parts, kinds, poses = [], [], []
    for _ in range(int(rng.integers(2, 4))):
        part, kind = random_body(rng, scale * 0.6, compound=False)
        parts.append(part)
        kinds.append(kind)
        poses.append(random_pose(rng, np.zeros(3), 0.5 * scale))
    return sc.CompoundBody(parts, poses=np.stack(poses)), "compound(" + ",".join(kinds) + ")"


# ----- motions, as the documentation defines them ---------------------------------------------


def _hat(w: np.ndarray) -> np.ndarray:
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def _left_jacobian(w: np.ndarray) -> np.ndarray:
    """V(w) with exp([w, v]) = [exp([w]), V(w) v]."""
    angle = np.linalg.norm(w)
    k = _hat(w)
    if angle < 1e-8:
        return np.eye(3) + k / 2 + k @ k / 6
    return (np.eye(3) + (1 - np.cos(angle)) / angle**2 * k
            + (angle - np.sin(angle)) / angle**3 * k @ k)  # fmt: skip


def motion_poses(start: np.ndarray, end: np.ndarray, times: np.ndarray, kind: str) -> np.ndarray:
    """The poses at ``times`` (docs/motions.md): ``R0 exp(t [w])`` with ``w`` the rotation vector
    of ``R0^T R1``; the origin on the segment ("linear") or ``T0 + R0 V(t w) t v`` ("screw")."""
    times = np.asarray(times, dtype=float)
    w = Rotation.from_matrix(start[:3, :3].T @ end[:3, :3]).as_rotvec()
    poses = np.tile(np.eye(4), (len(times), 1, 1))
    turns = Rotation.from_rotvec(np.outer(times, w)).as_matrix()
    poses[:, :3, :3] = start[:3, :3] @ turns
    if kind == "linear":
        poses[:, :3, 3] = start[:3, 3] + np.outer(times, end[:3, 3] - start[:3, 3])
        return poses
    v = np.linalg.solve(_left_jacobian(w), start[:3, :3].T @ (end[:3, 3] - start[:3, 3]))
    for row, t in enumerate(times):
        poses[row, :3, 3] = start[:3, 3] + start[:3, :3] @ _left_jacobian(t * w) @ (t * v)
    return poses


def random_pose(rng: np.random.Generator, centre: np.ndarray, spread: float) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3] = Rotation.random(random_state=rng).as_matrix()
    pose[:3, 3] = centre + rng.uniform(-spread, spread, 3)
    return pose


def random_motion(rng: np.random.Generator, scale: float, travel: float) -> Motion:
    """From a random pose to one ``travel`` away, turned by up to 0.98 pi (a half turn has no
    shorter way round) or hardly at all."""
    start = random_pose(rng, np.zeros(3), travel / 2)
    end = np.eye(4)
    choices = (rng.uniform(0, 0.98 * np.pi), rng.uniform(0, 1e-3), 0.0)
    angle = choices[int(rng.choice(3, p=[0.7, 0.15, 0.15]))]
    axis = rng.normal(size=3)
    turn = Rotation.from_rotvec(angle * axis / np.linalg.norm(axis)).as_matrix()
    end[:3, :3] = start[:3, :3] @ turn
    end[:3, 3] = start[:3, 3] + rng.normal(size=3) / np.sqrt(3) * travel
    return start, end


def random_scale(rng: np.random.Generator) -> float:
    roll = rng.random()
    if roll < 0.6:
        return 1.0
    if roll < 0.8:
        return float(rng.choice([1e-100, 1e-40, 1e-5, 1e5, 1e40, 1e100]))
    return float(10.0 ** rng.uniform(-100, 100))


# ----- the oracle ------------------------------------------------------------------------------


def motion_size(a: Body, b: Body) -> float:
    return 2 * (a.bounding_radius + b.bounding_radius)


class Oracle:
    """Exact signed distances along two documented motions."""

    def __init__(self, a: Body, b: Body, motion_a: Motion, motion_b: Motion, kind: str):
        self.a, self.b, self.kind = a, b, kind
        self.motion_a, self.motion_b = motion_a, motion_b

    def poses(self, times) -> Tuple[np.ndarray, np.ndarray]:
        return (motion_poses(*self.motion_a, times, self.kind),
                motion_poses(*self.motion_b, times, self.kind))  # fmt: skip

    def distances(self, times) -> np.ndarray:
        poses_a, poses_b = self.poses(times)
        result = sc.signed_distance_many(self.a, self.b, method="exact",
                                         tolerance=ORACLE_TOLERANCE, poses_a=poses_a,
                                         poses_b=poses_b, threads=1)  # fmt: skip
        return np.asarray(result.distance)

    def at(self, t: float):
        poses_a, poses_b = self.poses([t])
        return sc.signed_distance(self.a, self.b, method="exact", tolerance=ORACLE_TOLERANCE,
                                  pose_a=poses_a[0], pose_b=poses_b[0])  # fmt: skip

    def lowest(self, low: float, high: float, extra=()) -> Tuple[float, float]:
        """(time, distance) of the smallest signed distance found on [low, high]: dense samples,
        then a bounded search around the three smallest local minima."""
        if high < low:
            return low, np.inf
        times = np.union1d(np.linspace(low, high, SAMPLES), [t for t in extra if low <= t <= high])
        values = self.distances(times)
        best = int(np.argmin(values))
        found = (float(times[best]), float(values[best]))
        minima = [i for i in range(len(times)) if values[i] <= values[max(i - 1, 0)]
                  and values[i] <= values[min(i + 1, len(times) - 1)]]  # fmt: skip
        for i in sorted(minima, key=lambda i: values[i])[:3]:
            left, right = times[max(i - 1, 0)], times[min(i + 1, len(times) - 1)]
            if right <= left:
                continue
            search = minimize_scalar(lambda t: self.at(t).distance, bounds=(left, right),
                                     method="bounded", options={"xatol": 1e-12 * (right - left)
                                                                + 1e-15})  # fmt: skip
            if search.fun < found[1]:
                found = (float(search.x), float(search.fun))
        return found


def rounding(motion_a: Motion, motion_b: Motion, size: float) -> float:
    """How far poses computed two ways may differ: a few units in the last place of the largest
    translation and of the size (the bodies' points turned by rotations equal to 1e-15)."""
    largest = max(np.abs(m[:3, 3]).max() for m in (*motion_a, *motion_b))
    return 64 * np.finfo(float).eps * (largest + size)


# ----- judging one motion -----------------------------------------------------------------------


def judge_motion(oracle: Oracle, result, tolerance: float, time_tolerance: float,
                 exact_free: Optional[Callable[[float], float]] = None) -> Optional[str]:
    """Why ``result`` breaks the contract on this motion, or None. ``exact_free(t)``, where given,
    is the exact least signed distance over ``[0, t]`` (the swept family's)."""
    size = motion_size(oracle.a, oracle.b)
    slack = 4 * ORACLE_TOLERANCE * size + rounding(oracle.motion_a, oracle.motion_b, size)
    if not (0 <= result.t_lower <= result.t_upper <= 1):
        return f"bracket out of order: [{result.t_lower}, {result.t_upper}]"
    if not result.touches and not result.certified:
        return "an uncertified answer must err on the side of contact"
    free_until = result.t_upper if not result.touches else result.t_lower
    if result.touches and free_until == 0:
        return _judge_contact(oracle, result, tolerance, time_tolerance, size, slack)
    if exact_free is not None:
        least = exact_free(free_until)
        where = free_until
    else:
        extra = (result.t_lower, result.t_upper)
        where, least = oracle.lowest(0.0, free_until, extra)
    if least < -slack:
        claim = "free" if not result.touches else f"apart before t_lower={result.t_lower!r}"
        return f"{claim}, but the signed distance is {least:.3e} at t={where!r} (size {size:.3e})"
    return _judge_contact(oracle, result, tolerance, time_tolerance, size, slack)


def _judge_contact(oracle: Oracle, result, tolerance: float, time_tolerance: float, size: float,
                   slack: float) -> Optional[str]:
    """Why a certified contact's bracket, poses or distance break the contract, or None."""
    band = tolerance * size
    if not result.touches or not result.certified:
        return None
    if result.t_upper - result.t_lower > time_tolerance * (1 + 1e-9):
        return f"bracket [{result.t_lower}, {result.t_upper}] wider than {time_tolerance}"
    poses_a, poses_b = oracle.poses([result.t_upper])
    for name, got, due in (("pose_a", result.pose_a, poses_a[0]), ("pose_b", result.pose_b,
                                                                   poses_b[0])):  # fmt: skip
        scale = np.abs(due[:3, 3]).max() + size
        if np.abs(np.asarray(got)[:3, 3] - due[:3, 3]).max() > 1e-9 * scale or np.abs(
                np.asarray(got)[:3, :3] - due[:3, :3]).max() > 1e-9:
            return f"{name} at t_upper is not the documented motion's: {got} against {due}"
    there = oracle.at(result.t_upper)
    if there.lower_bound > band * (1 + 1e-6) + slack:
        return (f"in contact at t_upper={result.t_upper!r}, but the signed distance there is "
                f"{there.distance:.3e} > tolerance x size {band:.3e}")  # fmt: skip
    # The distance reported is one signed distance query's upper bound, not promised tight.
    if result.distance < there.lower_bound - band - slack:
        return f"distance at t_upper {result.distance!r} below the exact lower bound {there!r}"
    return None


# ----- the families -----------------------------------------------------------------------------


def _method(rng: np.random.Generator) -> str:
    """The default method most often; "fcl" answers every shape too (curved ones as FCL's own
    primitives, its answers checked)."""
    return ("exact", "exact", "dual", "fcl")[int(rng.integers(4))]


def _options(rng: np.random.Generator) -> Dict[str, Any]:
    options: Dict[str, Any] = {}
    if rng.random() < 0.25:
        options["tolerance"] = float(rng.choice([1e-6, 1e-4, 1e-11]))
    if rng.random() < 0.25:
        options["time_tolerance"] = float(rng.choice([1e-3, 1e-9, 1e-12]))
    return options


def sampled_case(rng: np.random.Generator) -> Dict[str, Any]:
    scale = random_scale(rng)
    a, kind_a = random_body(rng, scale)
    b, kind_b = random_body(rng, scale)
    travel = float(rng.choice([0.5, 2.0, 6.0, 50.0])) * scale
    motion_a = random_motion(rng, scale, travel)
    if rng.random() < 0.5:
        motion_b = random_motion(rng, scale, travel / 4)
    else:
        still = random_pose(rng, np.zeros(3), travel / 4)
        motion_b = (still, still)
    return {"a": a, "b": b, "motion_a": motion_a, "motion_b": motion_b,
            "motion": ("linear", "screw")[int(rng.integers(2))], "method": _method(rng),
            "options": _options(rng), "label": f"{kind_a} {kind_b} scale {scale:.3g}"}  # fmt: skip


def run_sampled(case: Dict[str, Any]) -> Dict[str, Any]:
    a, b, options = case["a"], case["b"], case["options"]
    result = sc.time_of_impact(a, b, pose_a=case["motion_a"], pose_b=case["motion_b"],
                               method=case["method"], motion=case["motion"], **options)
    oracle = Oracle(a, b, case["motion_a"], case["motion_b"], case["motion"])
    problem = judge_motion(oracle, result, options.get("tolerance", sc.DEFAULT_TOLERANCE),
                           options.get("time_tolerance", sc.DEFAULT_TIME_TOLERANCE))
    if problem:
        return _verdict("wrong", f"{problem}; {result!r}")
    return _verdict("ok" if result.certified else "uncertified", repr(result))


GRAZES = (-1e-6, -3e-9, -1e-9, -2e-10, 0.0, 2e-10, 1e-9, 3e-9, 1e-8, 1e-6, 0.3)
"""The closest approaches the swept family builds, in units of the motion's size."""


def swept_case(rng: np.random.Generator) -> Dict[str, Any]:
    scale = random_scale(rng)
    points, kind_a = random_points(rng)
    radius = float(rng.uniform(0.01, 0.2)) * scale if rng.random() < 0.2 else 0.0
    a = sc.ConvexPolyhedron(points * scale, radius=radius)
    b, kind_b = random_body(rng, scale)
    start = random_pose(rng, np.zeros(3), 0.0)
    travel = float(rng.choice([1.0, 4.0, 50.0])) * scale
    end = start.copy()
    end[:3, 3] = rng.normal(size=3) / np.sqrt(3) * travel
    still = random_pose(rng, end[:3, 3] * rng.uniform(0.2, 0.8), 0.2 * scale)
    graze = float(rng.choice(GRAZES))
    return {"a": a, "b": b, "start": start, "end": end, "still": still, "graze": graze,
            "method": _method(rng), "label": f"{kind_a}{' rounded' if radius else ''} "
            f"{kind_b} graze {graze:g} scale {scale:.3g}"}  # fmt: skip


def _sweep_body(a: sc.ConvexPolyhedron, start: np.ndarray, end: np.ndarray, t: float):
    """A, in its start frame's rotation, swept from time 0 to t (in the world frame)."""
    placed = a.vertices @ start[:3, :3].T + start[:3, 3]
    moved = placed + t * (end[:3, 3] - start[:3, 3])
    return sc.ConvexPolyhedron(np.vstack([placed, moved]), radius=a.rounding_radius)


def _sweep_distance(case: Dict[str, Any], b_pose: np.ndarray, t: float):
    sweep = _sweep_body(case["a"], case["start"], case["end"], t)
    return sc.signed_distance(sweep, case["b"], method="exact", tolerance=ORACLE_TOLERANCE,
                              pose_b=b_pose)  # fmt: skip


def grazing_motions(case: Dict[str, Any]) -> Optional[Tuple[Motion, Motion, Any]]:
    """A's motion, B's (still where A's sweep comes within ``graze`` x the size of it) and that
    closest approach (an exact signed distance), or None where the sweep gives no normal."""
    size = motion_size(case["a"], case["b"])
    approach = _sweep_distance(case, case["still"], 1.0)
    if not np.all(np.isfinite(approach.direction)) or not np.any(approach.direction):
        return None
    shifted = case["still"].copy()
    shifted[:3, 3] += (case["graze"] * size - approach.distance) * np.asarray(approach.direction)
    return (case["start"], case["end"]), (shifted, shifted), _sweep_distance(case, shifted, 1.0)


def run_swept(case: Dict[str, Any]) -> Dict[str, Any]:
    a, b = case["a"], case["b"]
    size = motion_size(a, b)
    grazing = grazing_motions(case)
    if grazing is None:
        return _verdict("ok", "no normal to shift along")
    motion_a, motion_b, closest = grazing
    shifted = motion_b[0]
    result = sc.time_of_impact(a, b, pose_a=motion_a, pose_b=motion_b, method=case["method"])
    band = sc.DEFAULT_TOLERANCE * size
    slack = 4 * ORACLE_TOLERANCE * size + rounding(motion_a, motion_b, size)
    if result.certified and not result.touches and closest.distance < -slack:
        return _verdict("wrong", f"free, but the sweep reaches {closest.distance:.3e} (size "
                        f"{size:.3e}); {result!r}")  # fmt: skip
    # An uncertified answer errs on the side of contact: only a certified one is wrong here.
    if result.certified and result.touches and closest.lower_bound > band * (1 + 1e-6) + slack:
        return _verdict("wrong", f"contact, but the sweep stays {closest.distance:.3e} away "
                        f"(tolerance x size {band:.3e}); {result!r}")  # fmt: skip
    oracle = Oracle(a, b, motion_a, motion_b, "linear")
    problem = judge_motion(oracle, result, sc.DEFAULT_TOLERANCE, sc.DEFAULT_TIME_TOLERANCE,
                           exact_free=lambda t: _sweep_distance(case, shifted, t).distance)
    if problem:
        return _verdict("wrong", f"{problem}; {result!r}")
    return _verdict("ok" if result.certified else "uncertified", repr(result))


def batch_case(rng: np.random.Generator) -> Dict[str, Any]:
    rows = [sampled_case(rng) for _ in range(int(rng.integers(3, 9)))]
    method = _method(rng)
    return {"rows": rows, "method": method, "motion": ("linear", "screw")[int(rng.integers(2))],
            "label": f"{len(rows)} rows"}  # fmt: skip


def _fields(result) -> tuple:
    return (bool(result.touches), float(result.t_lower), float(result.t_upper),
            repr(float(result.distance)), bool(result.certified), int(result.iterations),
            np.asarray(result.point_a).tobytes(), np.asarray(result.point_b).tobytes(),
            np.asarray(result.normal).tobytes(), np.asarray(result.pose_a).tobytes(),
            np.asarray(result.pose_b).tobytes())  # fmt: skip


def run_batch(case: Dict[str, Any]) -> Dict[str, Any]:
    rows, method, motion = case["rows"], case["method"], case["motion"]
    singles = [_fields(sc.time_of_impact(r["a"], r["b"], pose_a=r["motion_a"],
                                         pose_b=r["motion_b"], method=method, motion=motion))
               for r in rows]  # fmt: skip
    starts_a, ends_a = (np.stack([r["motion_a"][i] for r in rows]) for i in (0, 1))
    starts_b, ends_b = (np.stack([r["motion_b"][i] for r in rows]) for i in (0, 1))
    for threads in (1, 2):
        batch = sc.time_of_impact_many([r["a"] for r in rows], [r["b"] for r in rows],
                                       poses_a=(starts_a, ends_a), poses_b=(starts_b, ends_b),
                                       method=method, motion=motion, threads=threads)
        for i, single in enumerate(singles):
            if _fields(batch[i]) != single:
                return _verdict("wrong", f"row {i} with {threads} threads differs from its "
                                f"single call: {batch[i]!r}")  # fmt: skip
    return _verdict("ok")


def _pose(x: float = 0.0) -> np.ndarray:
    pose = np.eye(4)
    pose[0, 3] = x
    return pose


def _sheared() -> np.ndarray:
    pose = _pose()
    pose[0, 1] = 0.1
    return pose


def _nan() -> np.ndarray:
    pose = _pose()
    pose[1, 3] = np.nan
    return pose


_CUBE = sc.Box([0.5] * 3)
_MOVE = (_pose(-5), _pose(5))

BAD_ARGUMENTS: Dict[str, Tuple[Callable[[], Any], Tuple[str, ...]]] = {
    "pose_a end NaN": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=(_pose(), _nan())),
                       ("pose_a",)),
    "pose_b start sheared": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_b=(_sheared(), _pose())),
                             ("pose_b",)),
    "pose_a three poses": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=(_pose(),) * 3),
                           ("pose_a",)),
    "pose_a inf": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=(_pose(), _pose(np.inf))),
                   ("pose_a",)),
    "tolerance 0": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE, tolerance=0.0),
                    ("tolerance",)),
    "tolerance NaN": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE, tolerance=np.nan),
                      ("tolerance",)),
    "tolerance inf": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE, tolerance=np.inf),
                      ("tolerance",)),
    "time_tolerance -1": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE,
                                                    time_tolerance=-1.0), ("time_tolerance",)),
    "time_tolerance NaN": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE,
                                                     time_tolerance=np.nan), ("time_tolerance",)),
    "max_iterations 0": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE, max_iterations=0),
                         ("max_iterations",)),
    "max_iterations -3": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE,
                                                    max_iterations=-3), ("max_iterations",)),
    "method ipso": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE, method="ipso"),
                    ("method",)),
    "motion spiral": (lambda: sc.time_of_impact(_CUBE, _CUBE, pose_a=_MOVE, motion="spiral"),
                      ("motion",)),
    "many: 3 starts, 2 ends": (lambda: sc.time_of_impact_many(
        _CUBE, _CUBE, poses_a=(np.stack([_pose()] * 3), np.stack([_pose()] * 2))), ("poses_a",)),
    "many: threads 0": (lambda: sc.time_of_impact_many(_CUBE, _CUBE, poses_a=_MOVE, threads=0),
                        ("threads",)),
    "many: NaN row 1": (lambda: sc.time_of_impact_many(
        _CUBE, _CUBE, poses_a=(np.stack([_pose(), _pose()]), np.stack([_pose(), _nan()]))),
        ("poses_a", "1")),
    "bodies 1e300 apart": (lambda: sc.time_of_impact(
        _CUBE, _CUBE, pose_a=(_pose(-1e300), _pose(1e300))), ()),
}  # fmt: skip
"""Calls that must raise ValueError or TypeError whose message names each fragment (an empty
tuple: an answer is also right, judged by ``_far_answer``)."""


def run_argument(name: str) -> Dict[str, Any]:
    call, fragments = BAD_ARGUMENTS[name]
    try:
        answer = call()
    except (ValueError, TypeError) as error:
        if all(f in str(error) for f in fragments):
            return _verdict("ok", f"{type(error).__name__}: {error}")
        return _verdict("error-type", f"the message does not name {fragments}: {error}")
    except Exception as error:  # noqa: BLE001 - any other type is the finding
        return _verdict("error-type", f"{type(error).__name__}: {error}")
    if fragments:
        return _verdict("error-type", f"answered {answer!r} instead of raising")
    return _far_answer(answer)


def _far_answer(answer) -> Dict[str, Any]:
    """The cubes 1e300 apart pass through each other at t = 1/2."""
    if answer.touches and answer.t_lower <= 0.5 <= answer.t_upper + 1e-6:
        return _verdict("ok" if answer.certified else "uncertified", repr(answer))
    if answer.touches and not answer.certified and answer.t_lower <= 0.5:
        return _verdict("uncertified", repr(answer))
    return _verdict("wrong", repr(answer))


# ----- the corpus -------------------------------------------------------------------------------


def motion_case(seed: int, index: int) -> Tuple[str, str, str, Any]:
    """(family, query, label, case) of case ``index`` of corpus ``seed``."""
    rng = np.random.default_rng([seed, index, 29])
    family = FAMILIES[index % len(FAMILIES)]
    if family == "sampled":
        case = sampled_case(rng)
        return family, f"{case['motion']} motion", case["method"], case
    if family == "swept":
        case = swept_case(rng)
        return family, "swept graze", case["method"], case
    if family == "batch":
        case = batch_case(rng)
        return family, "batch", case["method"], case
    names = list(BAD_ARGUMENTS)
    name = names[int(rng.integers(len(names)))]
    return family, "argument", name, name


RUNNERS = {"sampled": run_sampled, "swept": run_swept, "batch": run_batch,
           "argument": run_argument}  # fmt: skip


def run_motion_case(seed: int, index: int) -> Dict[str, Any]:
    """Make and judge motion case ``index``: ``{"category", "reason"}``."""
    family, _, _, case = motion_case(seed, index)
    try:
        return RUNNERS[family](case)
    except (ValueError, TypeError) as error:
        if family == "argument":
            raise
        return _verdict("error-type", f"an answer was due: {type(error).__name__}: {error}")
