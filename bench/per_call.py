"""Per-call cost of one query from Python on prebuilt bodies: swarmcollide beside python-fcl and
coal, in one process, the contenders interleaved round by round (issues 13 and 24).

Bodies are the hull vertices of points on the unit sphere (8 and 64 points), built once. Each
pair is placed, by bisection on the exact signed distance along a random axis, at distance 1
("apart") or overlapping by 0.1 ("overlapping"); before any timing every contender's answer on
every pair is checked against swarmcollide's exact method (the overlapping pairs first, with the
peers' request and result objects shared by all pairs), so that no contender is timed on a wrong,
stale or mislabelled answer. The peers get their best correct usage (``Reused``): requests and
results made once and reused, coal's results cleared before each call, and besides coal's free
functions its ``ComputeDistance`` and ``ComputeCollision`` functors, which keep their solver
between calls. Each contender answers the same pairs in turn, round after round; a contender's
time is the median over rounds of its mean CPU time per call (the thread's, so that other jobs on
a shared machine do not enter it), and each ratio is against the faster python-fcl and the faster
coal contender for the same query from the same run. ``--json`` writes one row per contender and
size (bench/record.py's format).
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np
from scipy.spatial import ConvexHull

import record
import swarmcollide as sc
from peers import coal_convex, fcl_convex_object

STATES = {"apart": 1.0, "overlapping": -0.1}
"""The exact signed distance of the pairs in each state."""


def sphere_pair(n: int, signed_distance: float, rng: np.random.Generator):
    """Two hulls of n points on unit spheres, the second moved along a random axis until the
    pair's exact signed distance is ``signed_distance`` (to 1e-12)."""

    def hull_points():
        p = rng.normal(size=(n, 3))
        p /= np.linalg.norm(p, axis=1, keepdims=True)
        return p[ConvexHull(p).vertices]

    a, b = hull_points(), hull_points()
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    # Coincident centres overlap; 4 + the distance apart along the axis is farther than needed.
    near, far = 0.0, 4.0 + max(signed_distance, 0.0)
    while far - near > 1e-12:
        middle = (near + far) / 2
        if sc.signed_distance(a, b + middle * axis, method="exact").distance < signed_distance:
            near = middle
        else:
            far = middle
    return a, b + far * axis


# A contender: the query it answers ("distance", "signed" or "collide") and the call.
Contender = Tuple[str, Callable[[], object]]


class Reused:
    """The peers' request and result objects, made once for a whole run and reused by every call
    on every pair, as a loop over poses or pairs reuses them. coal's results keep their contact
    or distance from one call to the next (a reused result answers an apart pair after an
    overlapping one with the overlap), so each coal call clears its result first; python-fcl's
    calls return their answers, and its collision result, which appends a contact for every
    colliding call, is emptied after one so that it does not grow."""

    def __init__(self):
        import coal
        import fcl

        self.fcl_distance = fcl.DistanceRequest(), fcl.DistanceResult()
        self.fcl_collision = fcl.CollisionRequest(), fcl.CollisionResult()
        self.coal_distance = coal.DistanceRequest(), coal.DistanceResult()
        self.coal_collision = coal.CollisionRequest(), coal.CollisionResult()
        self.identity = coal.Transform3s()


def contenders(a: np.ndarray, b: np.ndarray, reused: Reused) -> Dict[str, Contender]:
    import coal
    import fcl

    oa, ob = fcl_convex_object(a), fcl_convex_object(b)
    ca, cb = coal_convex(a), coal_convex(b)
    identity = reused.identity
    coal_distance, coal_collision = coal.ComputeDistance(ca, cb), coal.ComputeCollision(ca, cb)
    A, B = sc.ConvexPolyhedron(a), sc.ConvexPolyhedron(b)
    dual, via_fcl = sc.Query("dual"), sc.Query("fcl")

    def fcl_collide() -> bool:
        request, result = reused.fcl_collision
        contacts = fcl.collide(oa, ob, request, result)
        if contacts:
            result.contacts.clear()
        return contacts > 0

    def coal_collide() -> bool:
        request, result = reused.coal_collision
        result.clear()
        return coal.collide(ca, identity, cb, identity, request, result)

    def coal_functor_collide() -> bool:
        request, result = reused.coal_collision
        result.clear()
        return coal_collision(identity, identity, request, result)

    def coal_signed() -> float:
        request, result = reused.coal_distance
        result.clear()
        return coal.distance(ca, identity, cb, identity, request, result)

    def coal_functor_signed() -> float:
        request, result = reused.coal_distance
        result.clear()
        return coal_distance(identity, identity, request, result)

    return {
        "python-fcl distance": ("distance", lambda: fcl.distance(oa, ob, *reused.fcl_distance)),
        "python-fcl collide": ("collide", fcl_collide),
        "coal distance": ("signed", coal_signed),
        "coal ComputeDistance": ("signed", coal_functor_signed),
        "coal collide": ("collide", coal_collide),
        "coal ComputeCollision": ("collide", coal_functor_collide),
        "sc.distance fcl": ("distance", lambda: sc.distance(A, B, method="fcl")),
        "sc.distance dual": ("distance", lambda: sc.distance(A, B)),
        "Query.distance fcl": ("distance", lambda: via_fcl.distance(A, B)),
        "Query.distance dual": ("distance", lambda: dual.distance(A, B)),
        "sc.collide fcl": ("collide", lambda: sc.collide(A, B, method="fcl")),
        "sc.collide dual": ("collide", lambda: sc.collide(A, B)),
        "Query.collide dual": ("collide", lambda: dual.collide(A, B)),
        "sc.signed_distance dual": ("signed", lambda: sc.signed_distance(A, B)),
        "sc.signed_distance exact": ("signed", lambda: sc.signed_distance(A, B, method="exact")),
        "Query.signed_distance dual": ("signed", lambda: dual.signed_distance(A, B)),
    }


def value_of(answer: object) -> float:
    """A contender's answer as a number: a result's distance, a verdict as 0 or 1."""
    if isinstance(answer, sc.DistanceResult):
        return answer.distance
    return float(answer)


def check(cases: List[Dict[str, Contender]], pairs: List[tuple]) -> None:
    """Each contender in turn answers every pair as the exact method does: distances within 1e-6
    (python-fcl's distance is negative for overlapping pairs, where it measures none), signed
    distances within 1e-6, verdicts equal. A contender answers all the pairs in a row, so a
    result object that keeps an answer from one pair to the next is caught."""
    exact = [sc.signed_distance(a, b, method="exact").distance for a, b in pairs]
    for name, (query, _) in cases[0].items():
        for case, signed in zip(cases, exact):
            got = value_of(case[name][1]())
            if name.startswith("python-fcl distance") and signed < 0:
                assert got < 0, f"{name} on an overlapping pair gave {got}"
                continue
            expected = {"distance": max(signed, 0.0), "signed": signed,
                        "collide": float(signed <= 0)}[query]
            assert abs(got - expected) <= 1e-6, f"{name}: {got} against {expected}"


def run(sizes: List[int], pairs: int, rounds: int, calls: int) -> List[dict]:
    rng = np.random.default_rng(13)
    reused = Reused()
    records = []
    for n in sizes:
        placed = {state: [sphere_pair(n, signed, rng) for _ in range(pairs)]
                  for state, signed in STATES.items()}
        every = {state: [contenders(a, b, reused) for a, b in placed[state]] for state in STATES}
        # Overlapping pairs first: a result that kept an answer would give it for the apart ones.
        check(every["overlapping"] + every["apart"], placed["overlapping"] + placed["apart"])
        for state in STATES:
            cases = every[state]
            times: Dict[str, List[float]] = {name: [] for name in cases[0]}
            for _ in range(rounds):
                for name in times:
                    start = time.thread_time()
                    for case in cases:
                        query = case[name][1]
                        for _ in range(calls):
                            query()
                    times[name].append((time.thread_time() - start) / (pairs * calls))
            medians = {name: statistics.median(values) for name, values in times.items()}
            kinds = {name: query for name, (query, _) in cases[0].items()}

            def fastest(peer: str, query: str) -> Optional[str]:
                # coal's distance is signed: it answers the distance queries too.
                wanted = "signed" if peer == "coal" and query == "distance" else query
                named = [name for name in medians if name.startswith(peer) and
                         kinds[name] == wanted]
                return min(named, key=medians.get) if named else None

            for name, seconds in medians.items():
                row = {"vertices": n, "pairs": state, "contender": name,
                       "microseconds": seconds * 1e6}
                for peer in ("python-fcl", "coal"):
                    against = fastest(peer, kinds[name])
                    row[f"against_{peer}"] = against
                    row[f"ratio_{peer}"] = seconds / medians[against] if against else None
                records.append(row)
    return records


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer rounds, under a minute")
    parser.add_argument("--json", type=Path, help="where to write the records")
    arguments = parser.parse_args(argv)
    rounds, calls = (5, 50) if arguments.quick else (15, 200)
    records = run([8, 64], pairs=10, rounds=rounds, calls=calls)
    for r in records:
        ratios = "  ".join(
            f"{r['ratio_' + peer]:5.2f}x {r['against_' + peer]:<22}" if r["ratio_" + peer]
            else f"{'-':>6} {'':<22}" for peer in ("python-fcl", "coal"))
        print(f"{r['vertices']:>3} {r['pairs']:<12} {r['contender']:<27} "
              f"{r['microseconds']:8.3f} us  {ratios}")
    if arguments.json:
        record.write(arguments.json, "per_call", records, quick=arguments.quick, rounds=rounds,
                     calls=calls)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
