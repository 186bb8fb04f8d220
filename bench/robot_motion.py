"""Robot motions (issue 28): ``Robot.check_motion`` against discrete checks at OMPL's default
resolution on random planner edges of pybullet_data's Franka Panda (its meshes' hulls, the
default pairs, and the table and two boxes of bench/robot.py).

Edges: a start drawn uniformly within the joint limits until it is free (a planner extends from
valid states), and an end a uniform fraction of OMPL's default RRT range (0.2 of the space's
maximum extent) away in a uniform direction, clamped to the limits. The space's maximum extent is
the joint-limit box's diagonal; OMPL's default motion check (``DiscreteMotionValidator``, longest
valid segment fraction 0.01) checks ``ceil(|q1 - q0| / (0.01 extent)) + 1`` evenly spaced states
of the edge, ends included. Contenders, every one on one thread, their answers per edge:

- ``check_motion``: ``robot.check_motion(q0, q1, threads=1)`` over all edges in one call
  (certified: free, or the first contact bracketed);
- ``discrete, our verdict``: ``robot.check(states, nearest=False, threads=1)`` over every edge's
  states in one call, an edge colliding when any of its states does;
- ``discrete, pinocchio computeCollisions``: ``pin.computeCollisionsInParallel(1, pool,
  states)`` (Pinocchio's C++ loop, coal's GJK on the same hulls) over the same states.

Both discrete checkers check every state of every edge (a planner stops at the first colliding
state; on free edges, most of them, it checks them all). The contenders run interleaved in rounds
(the order reversed every other round); the table gives the median time per edge, as ratios to
``check_motion``'s, with the load average before and after each round. Reported beside them:
the edges where ``check_motion`` proves a contact that the discrete check at OMPL's resolution
misses, and, as a check of check_motion's free answers, a discrete check 20 times denser.

    .venv/bin/python bench/robot_motion.py --edges 1000 --json bench/results/robot_motion.json
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from typing import Callable, Dict, List, Tuple

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import record  # noqa: E402  (bench/record.py: the one results format)
from markdown import table  # noqa: E402
from robot import Pinocchio, robot_of  # noqa: E402  (bench/robot.py: the Panda and its scene)

RESOLUTION = 0.01  # OMPL's default longest valid segment fraction
RRT_RANGE = 0.2  # OMPL's default range of RRT and RRT-Connect, a fraction of the extent


def planner_edges(robot, count: int, seed: int) -> Tuple[np.ndarray, np.ndarray, float]:
    """``count`` edges from free starts, and the space's maximum extent."""
    lower, upper = robot.limits.T
    extent = float(np.linalg.norm(upper - lower))
    rng = np.random.default_rng(seed)
    starts: List[np.ndarray] = []
    while len(starts) < count:
        q = rng.uniform(lower, upper, size=(2 * count, robot.dof))
        free = ~robot.check(q, nearest=False).colliding
        starts.extend(q[free])
    q0 = np.array(starts[:count])
    direction = rng.normal(size=q0.shape)
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    length = rng.uniform(0, RRT_RANGE * extent, size=(count, 1))
    q1 = np.clip(q0 + direction * length, lower, upper)
    return q0, q1, extent


def discrete_states(q0: np.ndarray, q1: np.ndarray, step: float,
                    limits: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Every edge's evenly spaced states, ends included, at most ``step`` apart, stacked (within
    the limits, which the interpolation's rounding can leave by an ulp); and each edge's first
    row in the stack."""
    counts = np.ceil(np.linalg.norm(q1 - q0, axis=1) / step).astype(int) + 1
    firsts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    states = np.concatenate([q0[i] + np.outer(np.linspace(0, 1, n), q1[i] - q0[i])
                             for i, n in enumerate(counts)])
    return np.clip(states, *limits.T), firsts


def per_edge(colliding: np.ndarray, firsts: np.ndarray) -> np.ndarray:
    return np.logical_or.reduceat(np.asarray(colliding, dtype=bool), firsts)


def load() -> List[float]:
    return [round(x, 2) for x in os.getloadavg()]


def run(count: int, rounds: int, seed: int) -> dict:
    robot = robot_of("panda")
    pinocchio = Pinocchio(robot, "panda")
    q0, q1, extent = planner_edges(robot, count, seed)
    states, firsts = discrete_states(q0, q1, RESOLUTION * extent, robot.limits)
    pin_states = pinocchio.configurations(states)
    robot.check_motion(q0[:20], q1[:20], threads=1)  # the hulls are built on first use
    contenders: Dict[str, Callable[[], np.ndarray]] = {
        "check_motion": lambda: robot.check_motion(q0, q1, threads=1),
        "discrete, our verdict": lambda: per_edge(
            robot.check(states, nearest=False, threads=1).colliding, firsts),
        "discrete, pinocchio computeCollisions": lambda: per_edge(
            pinocchio.collisions(pin_states), firsts),
    }
    times: Dict[str, List[float]] = {c: [] for c in contenders}
    loads = []
    answers = {}
    for r in range(rounds):
        before = load()
        order = list(contenders) if r % 2 == 0 else list(reversed(contenders))
        for contender in order:
            start = time.perf_counter()
            answers[contender] = contenders[contender]()
            times[contender].append((time.perf_counter() - start) / count * 1e6)
        loads.append({"round": r, "before": before, "after": load()})
    motion = answers["check_motion"]
    proven = motion.touches & motion.certified
    # check_motion's free answers against a discrete check 20 times denser.
    dense, dense_firsts = discrete_states(q0, q1, RESOLUTION * extent / 20,
                                         robot.limits)
    dense_hits = per_edge(robot.check(dense, nearest=False).colliding, dense_firsts)
    base = statistics.median(times["check_motion"])
    rows = []
    for contender, values in times.items():
        median = statistics.median(values)
        verdict = motion.touches if contender == "check_motion" else answers[contender]
        rows.append({
            "contender": contender, "us_per_edge": round(median, 1),
            "spread": round((max(values) - min(values)) / median, 3),
            "time_over_check_motion": round(median / base, 2),
            "edges_colliding": int(np.count_nonzero(verdict)),
            "contacts_missed": int(np.count_nonzero(proven & ~verdict)),
        })
    return {
        "model": "panda", "dof": robot.dof, "pairs": len(robot.pairs), "edges": count,
        "rounds": rounds, "seed": seed, "extent": extent,
        "states_per_edge_mean": round(len(states) / count, 2),
        "states_per_edge_max": int(np.diff(np.append(firsts, len(states))).max()),
        "check_motion_touching": int(motion.touches.sum()),
        "check_motion_certified": int(motion.certified.sum()),
        "check_motion_iterations_median": float(np.median(motion.iterations)),
        "check_motion_iterations_max": int(motion.iterations.max()),
        "dense_check_states_per_edge_mean": round(len(dense) / count, 1),
        "dense_check_colliding": int(dense_hits.sum()),
        "dense_contacts_check_motion_calls_free": int(np.count_nonzero(
            dense_hits & ~motion.touches)),
        "loads": loads, "rows": rows,
    }


def section(data: dict) -> str:
    """The RESULTS.md section of a recorded run."""
    model = data["models"][0]
    lines = [f"`{data['command']}`, load average {data['machine']['load_average_start']} -> "
             f"{data['machine']['load_average_end']} (per round: "
             + "; ".join(f"{x['before'][0]} -> {x['after'][0]}" for x in model["loads"])
             + f"). {model['edges']} random planner edges of the Panda ({model['pairs']} pairs), "
             f"{model['states_per_edge_mean']} states per edge at OMPL's default resolution (at "
             f"most {model['states_per_edge_max']}); median time per edge of "
             f"{model['rounds']} interleaved rounds, one thread each.", ""]
    rows = [[row["contender"], f"{row['us_per_edge']:.1f}", f"{row['time_over_check_motion']:.2f}",
             str(row["edges_colliding"]), str(row["contacts_missed"])] for row in model["rows"]]
    lines.append(table(["contender", "us / edge", "time / check_motion's", "edges colliding",
                        "contacts check_motion proves that it misses"], rows))
    lines.append("")
    lines.append(
        f"- check_motion: {model['check_motion_touching']} edges touching, "
        f"{model['check_motion_certified']} of {model['edges']} certified, distance queries per "
        f"edge median {model['check_motion_iterations_median']:g}, at most "
        f"{model['check_motion_iterations_max']}; a discrete check 20 times denser "
        f"({model['dense_check_states_per_edge_mean']} states per edge) finds "
        f"{model['dense_check_colliding']} edges colliding, "
        f"{model['dense_contacts_check_motion_calls_free']} of them called free by check_motion.")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--edges", type=int, default=1000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--quick", action="store_true", help="200 edges, 1 round")
    parser.add_argument("--json", help="write the results here (bench/record.py's format)")
    arguments = parser.parse_args()
    count = 200 if arguments.quick else arguments.edges
    rounds = 1 if arguments.quick else arguments.rounds
    load_start = os.getloadavg()
    model = run(count, rounds, arguments.seed)
    for row in model["rows"]:
        print(f"{row['contender']:40s} {row['us_per_edge']:9.1f} us/edge  "
              f"{row['time_over_check_motion']:.2f}x check_motion's time  "
              f"{row['edges_colliding']} colliding, {row['contacts_missed']} contacts missed")
    print({k: v for k, v in model.items() if k != "rows"})
    print(f"load before {tuple(round(x, 2) for x in load_start)} after "
          f"{tuple(round(x, 2) for x in os.getloadavg())}")
    if arguments.json:
        record.write(arguments.json, "robot_motion", model["rows"], load_start=load_start,
                     models=[model])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
