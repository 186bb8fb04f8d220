"""The curved-shape census: thousands of random posed pairs of every pair of shape kinds (sphere,
capsule, box, cylinder, cone, ellipsoid), answered by swarmcollide and checked against coal's own
primitives in the same run, then the scale sweep 1e-100..1e100.

Counts per pair of kinds and method, at tolerance 1e-12 (``--tolerance``):

- ``unproven``: a distance, signed distance or verdict not certified;
- ``outside``: coal's signed distance outside our bounds by more than coal's own precision
  (1e-6 (1 + |distance|), its GJK's default convergence test, or 1e-6 of the pair's size if that
  is larger: coal stops there) — one of the two libraries is wrong;
- ``wrong verdict``: our certified verdict against coal's where coal is sure (|sd| beyond that
  precision);
- ``scale``: at a scale 10^k (k = -100..100), an answer not certified, or its distance over the
  scale off the unit pair's by more than the tolerance.

With ``--extreme`` the shapes' sizes are drawn log-uniformly over six and a half decades
(1e-6..3, each dimension apart: wires, plates, needles and pancakes, aspect ratios up to 3e6) and
B's offset is the larger body's size times 0.1, 0.5, 1, 2, 1e3 or 1e8 (touching to far apart); the
default draws sizes in [0.1, 1.1] and offsets within 1.6.

Writes every case that is not fine as JSON Lines (``--json``), so a fix can be checked case by
case. Needs coal (``pip install swarmcollide[bench]``); behind ``make census``, not the fast suite:

    .venv/bin/python tests/fuzz/curved_census.py --pairs 200 --json build/fuzz/curved.jsonl
"""

from __future__ import annotations

import argparse
import itertools
import json
import sys
from collections import Counter
from pathlib import Path
from typing import Dict, List

import numpy as np

import swarmcollide as sc

KINDS = ("sphere", "capsule", "box", "cylinder", "cone", "ellipsoid")
SCALES = [10.0 ** k for k in (-100, -50, -10, 0, 10, 50, 100)]
COAL_PRECISION = 1e-6


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def make(kind: str, sizes: np.ndarray, scale: float = 1.0):
    """Our shape and coal's, of the same size (coal's lengths are full lengths: lz = 2
    half_length, a box's sides 2 half_extents; its cone's base at -lz/2, as ours)."""
    import coal

    r, h, c = sizes * scale
    if kind == "sphere":
        return sc.Sphere(r), coal.Sphere(r)
    if kind == "capsule":
        return sc.Capsule(r, h), coal.Capsule(r, 2 * h)
    if kind == "box":
        return sc.Box([r, h, c]), coal.Box(2 * r, 2 * h, 2 * c)
    if kind == "cylinder":
        return sc.Cylinder(r, h), coal.Cylinder(r, 2 * h)
    if kind == "cone":
        return sc.Cone(r, h), coal.Cone(r, 2 * h)
    return sc.Ellipsoid([r, h, c]), coal.Ellipsoid(r, h, c)


def coal_signed_distance(ca, pa, cb, pb) -> float:
    import coal

    request, result = coal.DistanceRequest(), coal.DistanceResult()
    return coal.distance(ca, coal.Transform3s(pa[:3, :3], pa[:3, 3]), cb,
                         coal.Transform3s(pb[:3, :3], pb[:3, 3]), request, result)


# --extreme: the decades sizes span, and B's offset in units of the larger body's size.
EXTREME_SIZE_DECADES = (-6.0, 0.5)
EXTREME_OFFSETS = (0.1, 0.5, 1.0, 2.0, 1e3, 1e8)


def one_pair(kinds, rng: np.random.Generator, methods: List[str], tolerance: float,
             sweep: bool, extreme: bool = False) -> List[dict]:
    """The findings (dicts) of one random posed pair: empty when every answer is fine."""
    if extreme:
        sizes_a, sizes_b = (10.0 ** rng.uniform(*EXTREME_SIZE_DECADES, 3) for _ in range(2))
    else:
        sizes_a, sizes_b = rng.uniform(0.1, 1.1, 3), rng.uniform(0.1, 1.1, 3)
    pa, pb = np.eye(4), np.eye(4)
    pa[:3, :3], pb[:3, :3] = random_rotation(rng), random_rotation(rng)
    if extreme:
        largest = max(sizes_a.max(), sizes_b.max())
        pb[:3, 3] = rng.uniform(-1, 1, 3) * largest * rng.choice(EXTREME_OFFSETS)
    else:
        pb[:3, 3] = rng.uniform(-1.6, 1.6, 3)
    (a, ca), (b, cb) = make(kinds[0], sizes_a), make(kinds[1], sizes_b)
    size = np.linalg.norm(pb[:3, 3]) + 2 * max(a.bounding_radius, b.bounding_radius)
    theirs = coal_signed_distance(ca, pa, cb, pb)
    findings = []
    case = {"kinds": list(kinds), "sizes_a": sizes_a.tolist(), "sizes_b": sizes_b.tolist(),
            "pose_a": pa.tolist(), "pose_b": pb.tolist()}

    def found(method, category, **details):
        findings.append({**case, "method": method, "category": category, **details})

    for method in methods:
        signed = sc.signed_distance(a, b, pose_a=pa, pose_b=pb, method=method, tolerance=tolerance)
        verdict = sc.collision(a, b, pose_a=pa, pose_b=pb, method=method, tolerance=tolerance)
        answers = [("signed_distance", signed), ("collision", verdict)]
        if "distance" in sc.METHODS[method].queries:
            answers.append(("distance", sc.distance(a, b, pose_a=pa, pose_b=pb, method=method,
                                                    tolerance=tolerance)))
        for query, r in answers:
            if not r.certified:
                found(method, "unproven", query=query, lower=r.lower_bound, upper=r.distance)
        # coal's GJK stops within 1e-6 (1 + |distance|) (GJK::checkConvergence, its default),
        # which on pairs smaller than a unit is looser than 1e-6 of their size.
        slack = COAL_PRECISION * max(size, 1 + abs(theirs))
        if not signed.lower_bound - slack <= theirs <= signed.distance + slack:
            found(method, "outside", coal=theirs, lower=signed.lower_bound, upper=signed.distance)
        if verdict.certified and abs(theirs) > slack and verdict.colliding != (theirs < 0):
            found(method, "wrong verdict", coal=theirs, colliding=bool(verdict.colliding))
        if sweep:
            for scale in SCALES:
                sa, sb = make(kinds[0], sizes_a, scale)[0], make(kinds[1], sizes_b, scale)[0]
                qa, qb = pa.copy(), pb.copy()
                qb[:3, 3] *= scale
                r = sc.signed_distance(sa, sb, pose_a=qa, pose_b=qb, method=method,
                                       tolerance=tolerance)
                if not r.certified or abs(r.distance / scale - signed.distance) > \
                        2 * tolerance * size + 1e-14 * size:
                    found(method, "scale", scale=scale, certified=bool(r.certified),
                          unit=signed.distance, scaled=r.distance / scale)
    return findings


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pairs", type=int, default=200, help="random pairs per pair of kinds")
    parser.add_argument("--methods", default="dual,exact,fcl,libccd")
    parser.add_argument("--tolerance", type=float, default=1e-12)
    parser.add_argument("--sweep-every", type=int, default=10,
                        help="run the scale sweep on every n-th pair (0: never)")
    parser.add_argument("--seed", type=int, default=26)
    parser.add_argument("--extreme", action="store_true",
                        help="sizes over six decades and offsets up to 1e8 sizes (see above)")
    parser.add_argument("--json", help="write the findings here (JSON Lines)")
    args = parser.parse_args(argv)
    methods = args.methods.split(",")
    rng = np.random.default_rng(args.seed)
    counts: Dict[tuple, Counter] = {}
    findings: List[dict] = []
    pairs = list(itertools.combinations_with_replacement(KINDS, 2))
    for kinds in pairs:
        for index in range(args.pairs):
            sweep = args.sweep_every > 0 and index % args.sweep_every == 0
            for finding in one_pair(kinds, rng, methods, args.tolerance, sweep, args.extreme):
                finding["index"] = index
                findings.append(finding)
                counts.setdefault(kinds, Counter())[(finding["method"], finding["category"])] += 1
    categories = ("unproven", "outside", "wrong verdict", "scale")
    print(f"{args.pairs} random posed pairs per pair of kinds ({len(pairs) * args.pairs} in all"
          f"{', extreme sizes and offsets' if args.extreme else ''}), "
          f"tolerance {args.tolerance:g}, methods {', '.join(methods)}; scale sweep "
          f"{SCALES[0]:g}..{SCALES[-1]:g} on every {args.sweep_every}th pair")
    print()
    print("| kinds | method | " + " | ".join(categories) + " |")
    print("|---|---|" + "---|" * len(categories))
    totals: Counter = Counter()
    for kinds in pairs:
        for method in methods:
            row = [counts.get(kinds, Counter())[(method, c)] for c in categories]
            totals.update({(method, c): n for c, n in zip(categories, row)})
            if any(row):
                print(f"| {kinds[0]}-{kinds[1]} | {method} | " + " | ".join(map(str, row)) + " |")
    for method in methods:
        print(f"| **all** | {method} | " +
              " | ".join(str(totals[(method, c)]) for c in categories) + " |")
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        with open(args.json, "w", encoding="utf-8") as out:
            for finding in findings:
                out.write(json.dumps(finding) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
