"""The paper's problem through swarmcollide's Python API, beside what a Python user would pick.

Rivals: pyswarms (GlobalBestPSO, the same 40 particles and 200 iterations), SciPy's SLSQP on
model (2), python-fcl and coal (GJK distance). Every body is built before the clock starts, for
every library: the timed call is the query alone. Run from the repository root:

    python bench/compare_python.py --json bench/results/python_comparison.json
"""

from __future__ import annotations

import argparse
import logging
import statistics
import sys
import time
from typing import Callable, Dict, List, NamedTuple, Optional

import numpy as np
from tqdm import tqdm

import record
import swarmcollide as sc
from workloads import Pair, Workload, paper_workloads, random_workloads

ACCURACY = 1e-6
SWARM_SIZE = 40
ITERATIONS = 200


class Answer(NamedTuple):
    distance: Optional[float]  # None: the method gives a verdict only
    colliding: bool
    iterations: Optional[int] = None
    evaluations: Optional[int] = None


Query = Callable[[int], Answer]  # seed -> answer, with the bodies bound in


def swarmcollide_method(method: str, **parameters) -> Callable[[Pair], Query]:
    def prepare(pair: Pair) -> Query:
        a, b = sc.ConvexPolyhedron(pair.a), sc.ConvexPolyhedron(pair.b)
        a.hull(), b.hull()  # computed once, as the C++ binary does

        def query(seed: int) -> Answer:
            r = sc.distance(a, b, method=method, seed=seed, **parameters)
            return Answer(r.distance, r.colliding, r.iterations, r.evaluations)

        return query

    return prepare


def _weights_distance(a: np.ndarray, b: np.ndarray, z: np.ndarray) -> float:
    """Distance achieved by weights z moved onto the simplexes (so it is an upper bound)."""
    lam = np.clip(z[: len(a)], 0, None)
    dl = np.clip(z[len(a) :], 0, None)
    lam = lam / lam.sum() if lam.sum() > 0 else np.full(len(a), 1 / len(a))
    dl = dl / dl.sum() if dl.sum() > 0 else np.full(len(b), 1 / len(b))
    return float(np.linalg.norm(dl @ b - lam @ a))


def pyswarms_gbest(pair: Pair) -> Query:
    # pyswarms has box bounds but no equality constraints. Its best handling for model (2): keep
    # particles in [0, 1] (bh_strategy="nearest") and score the weights normalised to sum 1, so
    # every particle is feasible. Inertia 0.9 -> 0.4 and c1 = c2 = 2, as swarmcollide's "pso".
    import pyswarms

    a, b = pair.a, pair.b
    ka = len(a)

    def cost(x: np.ndarray) -> np.ndarray:
        lam = x[:, :ka] + 1e-300
        dl = x[:, ka:] + 1e-300
        lam = lam / lam.sum(axis=1, keepdims=True)
        dl = dl / dl.sum(axis=1, keepdims=True)
        return np.linalg.norm(dl @ b - lam @ a, axis=1)

    dims = len(a) + len(b)

    def query(seed: int) -> Answer:
        np.random.seed(seed)  # pyswarms draws from NumPy's global generator
        optimizer = pyswarms.single.GlobalBestPSO(
            n_particles=SWARM_SIZE,
            dimensions=dims,
            options={"c1": 2.0, "c2": 2.0, "w": 0.9},
            bounds=(np.zeros(dims), np.ones(dims)),
            oh_strategy={"w": "lin_variation"},
            bh_strategy="nearest",
            velocity_clamp=(-1.0, 1.0),
        )
        _, position = optimizer.optimize(cost, iters=ITERATIONS, verbose=False)
        x = position + 1e-300
        d = _weights_distance(a, b, x)
        return Answer(d, d <= ACCURACY, ITERATIONS, SWARM_SIZE * (ITERATIONS + 1))

    return query


def scipy_slsqp(pair: Pair) -> Query:
    from scipy.optimize import minimize

    a, b = pair.a, pair.b
    ka, kb = len(a), len(b)
    m = np.hstack([-a.T, b.T])  # m @ z = sum delta y - sum lambda x

    def f(z):
        r = m @ z
        return r @ r, 2 * m.T @ r

    constraints = [
        {"type": "eq", "fun": lambda z: z[:ka].sum() - 1, "jac": lambda z: np.r_[np.ones(ka), np.zeros(kb)]},
        {"type": "eq", "fun": lambda z: z[ka:].sum() - 1, "jac": lambda z: np.r_[np.zeros(ka), np.ones(kb)]},
    ]
    x0 = np.r_[np.full(ka, 1 / ka), np.full(kb, 1 / kb)]

    def query(seed: int) -> Answer:
        del seed  # deterministic
        res = minimize(f, x0, jac=True, method="SLSQP", bounds=[(0, 1)] * (ka + kb),
                       constraints=constraints, options={"ftol": 1e-15, "maxiter": 500})
        d = _weights_distance(a, b, res.x)
        return Answer(d, d <= ACCURACY, int(res.nit), int(res.nfev))

    return query


def _faces(points: np.ndarray) -> np.ndarray:
    return np.asarray(sc.ConvexPolyhedron(points).hull().faces)


def python_fcl(solver_name: str) -> Callable[[Pair], Query]:
    def prepare(pair: Pair) -> Query:
        import fcl

        def shape(points):
            faces = _faces(points)
            flat = np.hstack([np.full((len(faces), 1), 3), faces]).ravel()
            return fcl.CollisionObject(fcl.Convex(points, len(faces), flat), fcl.Transform())

        oa, ob = shape(pair.a), shape(pair.b)
        solver = getattr(fcl.GJKSolverType, solver_name)

        def query(seed: int) -> Answer:
            del seed
            request = fcl.DistanceRequest(enable_nearest_points=True, gjk_solver_type=solver)
            d = fcl.distance(oa, ob, request, fcl.DistanceResult())
            # FCL answers -1 for touching and overlapping bodies: the distance is then 0.
            return Answer(max(d, 0.0), d <= ACCURACY)

        return query

    return prepare


def coal_gjk(pair: Pair) -> Query:
    import coal

    def shape(points):
        vertices = coal.StdVec_Vec3s()
        for v in points:
            vertices.append(np.asarray(v, dtype=float))
        triangles = coal.StdVec_Triangle()
        for i, j, k in _faces(points):
            triangles.append(coal.Triangle(int(i), int(j), int(k)))
        return coal.Convex(vertices, triangles)

    sa, sb = shape(pair.a), shape(pair.b)
    identity = coal.Transform3s()

    def query(seed: int) -> Answer:
        del seed
        d = coal.distance(sa, identity, sb, identity, coal.DistanceRequest(), coal.DistanceResult())
        # coal's distance is signed: negative when the bodies overlap.
        return Answer(max(d, 0.0), d <= ACCURACY)

    return query


METHODS: Dict[str, Callable[[Pair], Query]] = {
    "swarmcollide ipso": swarmcollide_method("ipso"),
    "swarmcollide ipso feasibility": swarmcollide_method("ipso", constraint_handling="feasibility"),
    "swarmcollide pso": swarmcollide_method("pso"),
    "swarmcollide penalty": swarmcollide_method("penalty"),
    "swarmcollide dual": swarmcollide_method("dual"),
    "swarmcollide exact": swarmcollide_method("exact"),
    "swarmcollide fcl": swarmcollide_method("fcl"),
    "pyswarms GlobalBestPSO": pyswarms_gbest,
    "scipy SLSQP": scipy_slsqp,
    "python-fcl GST_LIBCCD": python_fcl("GST_LIBCCD"),
    "python-fcl GST_INDEP": python_fcl("GST_INDEP"),
    "coal GJK": coal_gjk,
}


def unavailable(name: str) -> Optional[str]:
    """Why a method cannot run here, or None."""
    if name.startswith("swarmcollide "):
        method = name.split()[1]
        if method not in sc.METHODS:
            return f"method {method!r} is not in this swarmcollide's Python API"
        return None
    module = {"pyswarms": "pyswarms", "scipy": "scipy", "python-fcl": "fcl", "coal": "coal"}
    try:
        __import__(module[name.split()[0]])
    except ImportError as error:
        return f"not installed ({error}); pip install '.[bench]'"
    return None


def time_query(query: Query, seed: int, budget: float) -> tuple:
    """Warm-up call (its answer is the one scored), then repeats within `budget` seconds."""
    start = time.perf_counter()
    answer = query(seed)
    first = time.perf_counter() - start
    repeats = int(min(20, max(1, budget / max(first, 1e-9))))
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        query(seed)
        times.append(time.perf_counter() - start)
    return answer, statistics.median(times)


def run_cell(name: str, workload: Workload, budget: float) -> dict:
    cell = {"method": name, "workload": workload.name, "n": workload.n,
              "proximity": workload.proximity, "pairs": len(workload.pairs)}
    reason = unavailable(name)
    if reason:
        cell["note"] = reason
        return cell
    times, errors, iterations, evaluations = [], [], [], []
    wrong = separated = within = 0
    for seed, pair in enumerate(workload.pairs):
        answer, t = time_query(METHODS[name](pair), seed, budget)
        times.append(t)
        wrong += answer.colliding != pair.colliding
        if answer.iterations is not None:
            iterations.append(answer.iterations)
            evaluations.append(answer.evaluations)
        if answer.distance is not None:
            error = abs(answer.distance - pair.reference)
            errors.append(error)
            if not pair.colliding:
                separated += 1
                within += error <= ACCURACY
    q = np.quantile(times, [0.25, 0.5, 0.75])
    cell.update(time_p25_s=q[0], time_median_s=q[1], time_p75_s=q[2], wrong_verdicts=wrong,
                  separated=separated, within_1e6=within,
                  error_max=max(errors), error_median=float(np.median(errors)))
    if iterations:
        cell.update(iterations_mean=float(np.mean(iterations)),
                      evaluations_mean=float(np.mean(evaluations)))
    return cell


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", required=True, help="output file")
    parser.add_argument("--quick", action="store_true", help="fewer pairs and workloads")
    args = parser.parse_args(argv)
    logging.getLogger("pyswarms").setLevel(logging.WARNING)

    pairs = 3 if args.quick else 10
    sizes = (8,) if args.quick else (8, 16, 64)
    proximities = ("apart", "gap 1e-2") if args.quick else ("apart", "gap 1e-2", "gap 1e-4",
                                                            "overlap 1e-2")
    print("generating workloads", file=sys.stderr)
    workloads = paper_workloads() + random_workloads(sizes, proximities, pairs)
    budget = 0.01 if args.quick else 0.05
    cells = [(m, w) for w in workloads for m in METHODS]
    records = [run_cell(m, w, budget) for m, w in tqdm(cells, desc="python comparison")]
    record.write(args.json, "python_comparison", records, quick=args.quick,
                 accuracy_threshold=ACCURACY, pairs_per_random_workload=pairs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
