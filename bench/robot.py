"""Robots (issue 27): ``Robot.check`` against Pinocchio + coal and MuJoCo on the same models.

pybullet_data's Franka Panda (``franka_panda/panda.urdf``) and KUKA iiwa (``kuka_iiwa/model.urdf``),
each mesh its convex hull, the default pairs (links not adjacent) plus a table and two boxes as
obstacles against every link, at random configurations within the joint limits (seed 0). Every
contender gets the same bodies at the same poses and the same pairs:

- ``check 1 thread`` / ``check 2 threads``: ``robot.check(q, threads=...)`` (the verdict and the
  minimum signed distance with its pair and witnesses, certified);
- ``verdict 1 thread``: ``robot.check(q, threads=1, nearest=False)`` (the verdict alone, certified,
  as computeCollisions and mj_collision answer it);
- ``verdict per call``: the same, one configuration per call from a Python loop
  (``robot.check(q[i], threads=1, nearest=False)``), as a planner's validity check asks it and as
  the MuJoCo contender below is called;
- ``checker per call``: a planner's prepared validity test, ``free =
  robot.checker(nearest=False).collision_free`` made once, then ``free(q[i])`` from a Python loop
  (colliding where it is not proven free);
- ``pinocchio computeCollisions``: ``pin.computeCollisionsInParallel(1, pool, q)`` (Pinocchio's
  C++ loop over the configurations on one thread; a verdict per configuration), with a
  ``GeometryModel`` of ``coal.Convex`` hulls of our hulls' points placed as our geometries are;
- ``pinocchio computeDistances``: ``pin.computeDistances(model, data, geometry_model,
  geometry_data, q)`` from a Python loop (Pinocchio has no batched distances); the minimum over
  the pairs' ``min_distance`` (signed);
- ``mujoco mj_collision``: the URDF compiled by MuJoCo (its meshes' hulls), every pair given as
  an explicit ``<pair>`` with default contacts off, obstacles as box geoms; ``mj_kinematics`` then
  ``mj_collision`` per configuration from a Python loop; colliding when it finds a contact.

The contenders run interleaved in rounds (the order reversed every other round); the table gives
the median time per configuration and each contender's configurations per second as a ratio to
``check 1 thread``'s. Verdicts are compared with the exact method's (``robot.check(q,
method="exact")``, certified); where coal's verdict differs, the configuration, pair and both
answers are listed, with the exact bounds that prove which is right. The load average is recorded
before and after.

    .venv/bin/python bench/robot.py --configurations 10000 --json bench/results/robot.json
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import sys
import time
from typing import Callable, Dict, List

import numpy as np

import swarmcollide as sc

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import record  # noqa: E402  (bench/record.py: the one results format)
from markdown import table  # noqa: E402

MODELS = {"panda": ("franka_panda", "panda.urdf"), "iiwa": ("kuka_iiwa", "model.urdf")}
OBSTACLES = (("table", (0.6, 0.8, 0.02), (0.55, 0.0, -0.03)),
             ("box_left", (0.1, 0.1, 0.15), (0.5, 0.35, 0.15)),
             ("box_right", (0.08, 0.12, 0.1), (0.45, -0.4, 0.1)))


def urdf_path(name: str) -> str:
    import pybullet_data

    return os.path.join(pybullet_data.getDataPath(), *MODELS[name])


def robot_of(name: str) -> sc.Robot:
    robot = sc.Robot.from_urdf(urdf_path(name))
    for obstacle, half, centre in OBSTACLES:
        pose = np.eye(4)
        pose[:3, 3] = centre
        robot.add_obstacle(sc.Box(half), pose, name=obstacle)
    return robot


def joint_values(robot: sc.Robot, q: np.ndarray) -> Dict[str, np.ndarray]:
    """Every moving joint's values by name, mimic joints included (their own values)."""
    joints = robot.model.joints
    values = dict(zip(robot.joint_names, q.T))
    for joint in joints:
        if joint.mimic >= 0:
            values[joint.name] = joint.multiplier * values[joints[joint.mimic].name] + joint.offset
    return values


def hull_points(body) -> np.ndarray:
    from scipy.spatial import ConvexHull

    points = np.asarray(body.vertices, dtype=float)
    return points[ConvexHull(points).vertices]


def coal_shape(body):
    import coal

    if isinstance(body, sc.Box):
        return coal.Box(*(2 * np.asarray(body.half_extents)))
    from scipy.spatial import ConvexHull

    points = hull_points(body)
    hull = ConvexHull(points)
    vertices = coal.StdVec_Vec3s()
    for point in points:
        vertices.append(point)
    triangles = coal.StdVec_Triangle()
    for a, b, c in hull.simplices:
        triangles.append(coal.Triangle(int(a), int(b), int(c)))
    return coal.Convex(vertices, triangles)


class Pinocchio:
    """Pinocchio's model of the URDF with a GeometryModel of our geometries (coal shapes)."""

    def __init__(self, robot: sc.Robot, name: str):
        import pinocchio as pin

        self.pin = pin
        self.robot = robot
        self.model = pin.buildModelFromUrdf(urdf_path(name))
        self.geometry_model = pin.GeometryModel()
        for geometry_name, link, origin, body in robot._robot_geometries + robot._obstacles:
            origin = np.eye(4) if origin is None else np.asarray(origin, dtype=float)
            if link >= 0:
                frame = self.model.frames[self.model.getFrameId(robot.link_names[link])]
                joint, placement = frame.parentJoint, frame.placement * pin.SE3(origin)
            else:
                joint, placement = 0, pin.SE3(origin)
            self.geometry_model.addGeometryObject(
                pin.GeometryObject(geometry_name, joint, placement, coal_shape(body)))
        index = {g.name: k for k, g in enumerate(self.geometry_model.geometryObjects)}
        for a, b in robot.pairs:
            self.geometry_model.addCollisionPair(pin.CollisionPair(index[a], index[b]))
        self.data = self.model.createData()
        self.geometry_data = pin.GeometryData(self.geometry_model)
        self.pool = pin.GeometryPool(self.model, self.geometry_model, 1)

    def configurations(self, q: np.ndarray) -> np.ndarray:
        """Our configurations as Pinocchio's, ``(nq, m)`` column-major as its batches take them."""
        values = joint_values(self.robot, q)
        columns = np.zeros((len(q), self.model.nq))
        for j in range(1, self.model.njoints):
            columns[:, self.model.joints[j].idx_q] = values[self.model.names[j]]
        return np.asfortranarray(columns.T)

    def check_poses(self, q: np.ndarray) -> float:
        """The largest difference between Pinocchio's geometry placements and ours."""
        pin = self.pin
        worst = 0.0
        ours = self.robot.geometry_poses(q)
        for column, poses in zip(self.configurations(q).T, ours):
            pin.updateGeometryPlacements(self.model, self.data, self.geometry_model,
                                         self.geometry_data, np.ascontiguousarray(column))
            for placement, pose in zip(self.geometry_data.oMg, poses):
                worst = max(worst, float(np.abs(placement.homogeneous - pose).max()))
        return worst

    def collisions(self, pin_q: np.ndarray) -> np.ndarray:
        return np.asarray(self.pin.computeCollisionsInParallel(1, self.pool, pin_q), dtype=bool)

    def distances(self, pin_q: np.ndarray) -> np.ndarray:
        pin = self.pin
        least = np.empty(pin_q.shape[1])
        results = self.geometry_data.distanceResults
        for i in range(pin_q.shape[1]):
            pin.computeDistances(self.model, self.data, self.geometry_model, self.geometry_data,
                                 np.ascontiguousarray(pin_q[:, i]))
            least[i] = min(r.min_distance for r in results)
        return least

    def pair_verdicts(self, column: np.ndarray) -> np.ndarray:
        """Each pair's collision verdict at one configuration."""
        pin = self.pin
        pin.computeCollisions(self.model, self.data, self.geometry_model, self.geometry_data,
                              np.ascontiguousarray(column), False)
        return np.array([r.isCollision() for r in self.geometry_data.collisionResults])


class MuJoCo:
    """The URDF compiled by MuJoCo with exactly our pairs (default contacts off)."""

    def __init__(self, robot: sc.Robot, name: str):
        import mujoco

        self.mujoco = mujoco
        self.robot = robot
        path = urdf_path(name)
        text = open(path).read()
        folder = os.path.dirname(path)
        # MuJoCo reads no package:// paths: every mesh gets its absolute path in a copy.
        text = text.replace("package://", "")
        text = re.sub(r'filename="([^"]+)"',
                      lambda m: f'filename="{os.path.join(folder, m.group(1))}"', text)
        text = text.replace("</robot>", '<mujoco><compiler discardvisual="true" '
                            'fusestatic="false" strippath="false"/></mujoco></robot>')
        spec = mujoco.MjSpec.from_string(text)
        for obstacle, half, centre in OBSTACLES:
            spec.worldbody.add_geom(name=obstacle, type=mujoco.mjtGeom.mjGEOM_BOX, size=half,
                                    pos=centre)
        # Our geometry names: a link's own for one geometry, link/k for more (robot_tables).
        for body in spec.bodies[1:]:
            geoms = list(body.geoms)
            for k, geom in enumerate(geoms):
                geom.name = body.name if len(geoms) == 1 else f"{body.name}/{k}"
        for geom in spec.geoms:
            geom.contype = 0
            geom.conaffinity = 0
        for a, b in robot.pairs:
            spec.add_pair(geomname1=a, geomname2=b)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        self.names = [self.model.joint(j).name for j in range(self.model.njnt)]
        self.columns = [int(self.model.jnt_qposadr[j]) for j in range(self.model.njnt)]

    def configurations(self, q: np.ndarray) -> np.ndarray:
        values = joint_values(self.robot, q)
        qpos = np.zeros((len(q), self.model.nq))
        for name, column in zip(self.names, self.columns):
            qpos[:, column] = values[name]
        return qpos

    def check_poses(self, q: np.ndarray) -> float:
        """The largest difference between MuJoCo's body frames and our link frames (MuJoCo
        recentres meshes, so its geom frames are not ours)."""
        mujoco = self.mujoco
        links = self.robot.link_names
        worst = 0.0
        for row, frames in zip(self.configurations(q), self.robot.forward_kinematics(q)):
            self.data.qpos[:] = row
            mujoco.mj_kinematics(self.model, self.data)
            for b in range(1, self.model.nbody):
                ours = frames[links.index(self.model.body(b).name)]
                worst = max(worst, float(np.abs(ours[:3, 3] - self.data.xpos[b]).max()),
                            float(np.abs(ours[:3, :3].ravel() - self.data.xmat[b]).max()))
        return worst

    def collisions(self, qpos: np.ndarray) -> np.ndarray:
        mujoco, model, data = self.mujoco, self.model, self.data
        colliding = np.empty(len(qpos), dtype=bool)
        for i, row in enumerate(qpos):
            data.qpos[:] = row
            mujoco.mj_kinematics(model, data)
            mujoco.mj_collision(model, data)
            colliding[i] = data.ncon > 0
        return colliding


def disagreements(robot: sc.Robot, pinocchio: Pinocchio, q: np.ndarray, theirs: np.ndarray,
                  exact, limit: int = 5) -> List[dict]:
    """Where coal's verdict differs from the exact method's: the configuration, the exact
    answer's certified bounds on the minimum, and the pairs coal calls colliding when the
    configuration is asked again on its own (``computeCollisions`` on fresh results), with their
    exact signed distances."""
    rows = []
    pin_q = pinocchio.configurations(q)
    for i in np.flatnonzero(theirs != exact.colliding)[:limit]:
        verdicts = pinocchio.pair_verdicts(pin_q[:, i])
        distances = robot.distances(q[i], method="exact")
        rows.append({
            "configuration": int(i), "coal_colliding": bool(theirs[i]),
            "exact_colliding": bool(exact.colliding[i]),
            "exact_min_distance": float(exact.min_distance[i]),
            "exact_lower_bound": float(exact.lower_bound[i]),
            "exact_certified": bool(exact.certified[i]),
            "exact_pair": [str(n) for n in exact.pair_names[i]],
            "coal_colliding_pairs_asked_alone": [list(robot.pairs[p])
                                                 for p in np.flatnonzero(verdicts)],
            "exact_distance_of_those_pairs": [float(distances[p])
                                              for p in np.flatnonzero(verdicts)],
        })
    return rows


def run_model(name: str, count: int, rounds: int) -> dict:
    robot = robot_of(name)
    lower, upper = np.clip(robot.limits, -np.pi, np.pi).T
    q = np.random.default_rng(0).uniform(lower, upper, size=(count, robot.dof))
    pinocchio = Pinocchio(robot, name)
    mujoco = MuJoCo(robot, name)
    pose_error = max(pinocchio.check_poses(q[:20]), mujoco.check_poses(q[:20]))
    pin_q = pinocchio.configurations(q)
    qpos = mujoco.configurations(q)
    robot.check(q[:50], threads=1)  # the hulls are built on first use: not timed
    free = robot.checker(nearest=False).collision_free
    contenders: Dict[str, Callable[[], np.ndarray]] = {
        "check 1 thread": lambda: robot.check(q, threads=1),
        "check 2 threads": lambda: robot.check(q, threads=2),
        "verdict 1 thread": lambda: robot.check(q, threads=1, nearest=False),
        "verdict per call": lambda: np.array([robot.check(row, threads=1, nearest=False).colliding
                                              for row in q]),
        "checker per call": lambda: np.array([not free(row) for row in q]),
        "pinocchio computeCollisions": lambda: pinocchio.collisions(pin_q),
        "pinocchio computeDistances": lambda: pinocchio.distances(pin_q),
        "mujoco mj_collision": lambda: mujoco.collisions(qpos),
    }
    times: Dict[str, List[float]] = {c: [] for c in contenders}
    answers = {}
    for r in range(rounds):
        order = list(contenders) if r % 2 == 0 else list(reversed(contenders))
        for contender in order:
            start = time.perf_counter()
            answers[contender] = contenders[contender]()
            times[contender].append((time.perf_counter() - start) / count * 1e6)
    start = time.perf_counter()
    exact = robot.check(q, method="exact", threads=1)
    exact_time = (time.perf_counter() - start) / count * 1e6
    ours = answers["check 1 thread"]
    verdicts = {
        "check 1 thread": ours.colliding,
        "check 2 threads": answers["check 2 threads"].colliding,
        "verdict 1 thread": answers["verdict 1 thread"].colliding,
        "verdict per call": answers["verdict per call"],
        "checker per call": answers["checker per call"],
        "pinocchio computeCollisions": answers["pinocchio computeCollisions"],
        "pinocchio computeDistances": answers["pinocchio computeDistances"] <= 0,
        "mujoco mj_collision": answers["mujoco mj_collision"],
    }
    base = statistics.median(times["check 1 thread"])
    rows = []
    for contender, values in times.items():
        median = statistics.median(values)
        rows.append({
            "model": name, "contender": contender, "us_per_configuration": round(median, 2),
            "spread": round((max(values) - min(values)) / median, 3),
            "check_speedup": round(median / base, 2),
            "verdicts_differing_from_exact": int(np.count_nonzero(
                verdicts[contender] != exact.colliding)),
        })
    coal_least = answers["pinocchio computeDistances"]
    return {
        "model": name, "urdf": "/".join(MODELS[name]), "dof": robot.dof,
        "pairs": len(robot.pairs), "configurations": count, "rounds": rounds,
        "colliding": int(exact.colliding.sum()), "certified": int(ours.certified.sum()),
        "exact_certified": int(exact.certified.sum()),
        "exact_us_per_configuration": round(exact_time, 2),
        "pose_difference_to_pinocchio_and_mujoco": pose_error,
        "max_min_distance_difference_check_exact": float(
            np.abs(ours.min_distance - exact.min_distance).max()),
        "max_min_distance_difference_coal_exact": float(
            np.abs(coal_least - exact.min_distance).max()),
        "two_threads_speedup": round(base / statistics.median(times["check 2 threads"]), 2),
        "verdict_over_compute_collisions": round(
            statistics.median(times["pinocchio computeCollisions"])
            / statistics.median(times["verdict 1 thread"]), 2),
        "verdict_per_call_over_mj_collision": round(
            statistics.median(times["mujoco mj_collision"])
            / statistics.median(times["verdict per call"]), 2),
        "checker_per_call_over_mj_collision": round(
            statistics.median(times["mujoco mj_collision"])
            / statistics.median(times["checker per call"]), 2),
        "check_over_compute_distances": round(
            statistics.median(times["pinocchio computeDistances"]) / base, 2),
        "coal_disagreements": disagreements(robot, pinocchio, q,
                                            answers["pinocchio computeCollisions"], exact),
        "coal_distance_disagreements": disagreements(robot, pinocchio, q, coal_least <= 0,
                                                     exact),
        "rows": rows,
    }


def section(data: dict) -> str:
    """The RESULTS.md section of a recorded run."""
    lines = [f"`{data['command']}`, load average {data['machine']['load_average_start']} -> "
             f"{data['machine']['load_average_end']}. Time per configuration (median of "
             f"{data['models'][0]['rounds']} interleaved rounds) and `check 1 thread`'s speed "
             "over each contender's (x > 1: check is faster); verdicts against the exact "
             "method's.", ""]
    rows = []
    for model in data["models"]:
        for row in model["rows"]:
            rows.append([model["model"], row["contender"], f"{row['us_per_configuration']:.1f}",
                         f"{row['check_speedup']:.2f}x", str(row["verdicts_differing_from_exact"])])
    lines.append(table(["model", "contender", "us / configuration", "check 1 thread / it (speed)",
                        "verdicts differing from exact"], rows))
    lines.append("")
    for model in data["models"]:
        lines.append(
            f"- {model['model']} ({model['urdf']}, dof {model['dof']}, {model['pairs']} pairs, "
            f"{model['configurations']} configurations, {model['colliding']} colliding): "
            f"{model['certified']} certified; 2 threads / 1: {model['two_threads_speedup']}x; "
            f"verdict 1 thread over computeCollisions (speed): "
            f"{model.get('verdict_over_compute_collisions', float('nan'))}x (target 5x); "
            f"verdict per call over mj_collision's loop (speed): "
            f"{model.get('verdict_per_call_over_mj_collision', float('nan'))}x, checker per "
            f"call over it: {model.get('checker_per_call_over_mj_collision', float('nan'))}x; "
            f"check "
            f"1 thread over computeDistances: "
            f"{model.get('check_over_compute_distances', float('nan'))}x (target 5x); "
            f"exact reference {model['exact_us_per_configuration']:.1f} us; largest minimum "
            f"distance difference to exact: check "
            f"{model['max_min_distance_difference_check_exact']:.2g}, coal "
            f"{model['max_min_distance_difference_coal_exact']:.2g}.")
        for kind in ("coal_disagreements", "coal_distance_disagreements"):
            for d in model[kind]:
                lines.append(
                    f"  - {kind.replace('_', ' ')}: configuration {d['configuration']}: coal says "
                    f"{'colliding' if d['coal_colliding'] else 'apart'}, exact says "
                    f"{'colliding' if d['exact_colliding'] else 'apart'} (minimum "
                    f"{d['exact_min_distance']:.3g}, lower bound {d['exact_lower_bound']:.3g}, "
                    f"{'certified' if d['exact_certified'] else 'not certified'}, pair "
                    f"{' - '.join(d['exact_pair'])}); asked this configuration alone, coal "
                    f"finds {d['coal_colliding_pairs_asked_alone']} colliding, at exact "
                    f"distances {[round(x, 6) for x in d['exact_distance_of_those_pairs']]}")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--configurations", type=int, default=10000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--models", nargs="+", choices=list(MODELS), default=list(MODELS))
    parser.add_argument("--quick", action="store_true", help="1000 configurations, 1 round")
    parser.add_argument("--json", help="write the results here (bench/record.py's format)")
    arguments = parser.parse_args()
    count = 1000 if arguments.quick else arguments.configurations
    rounds = 1 if arguments.quick else arguments.rounds
    load_start = os.getloadavg()
    models = [run_model(name, count, rounds) for name in arguments.models]
    for model in models:
        for row in model["rows"]:
            print(f"{model['model']:6s} {row['contender']:28s} {row['us_per_configuration']:9.1f} "
                  f"us/configuration  check is {row['check_speedup']:.2f}x  "
                  f"{row['verdicts_differing_from_exact']} verdicts differ from exact")
        print({k: v for k, v in model.items() if k != "rows"})
    print(f"load before {tuple(round(x, 2) for x in load_start)} after "
          f"{tuple(round(x, 2) for x in os.getloadavg())}")
    if arguments.json:
        rows = [row for model in models for row in model["rows"]]
        record.write(arguments.json, "robot", rows, load_start=load_start,
                     models=models)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
