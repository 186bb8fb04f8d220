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

where a closed form gives the signed distance (spheres and capsules: points and segments, less
their radii), it is the truth both are judged by instead of coal's answer (ours must enclose it to
1e-12 of the pair's size), and a coal answer off it by more than coal's precision is counted
apart (``coal off``, printed below the table): coal 3.0.3's capsule pairs are, on extreme sizes;
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


def segment_of(kind: str, sizes: np.ndarray, pose: np.ndarray):
    """A sphere's or capsule's core segment (its ends, equal for a sphere) and radius, placed by
    `pose`; None for the other kinds."""
    if kind not in ("sphere", "capsule"):
        return None
    r, h = sizes[0], (sizes[1] if kind == "capsule" else 0.0)
    axis = pose[:3, :3] @ np.array([0.0, 0.0, h])
    return pose[:3, 3] - axis, pose[:3, 3] + axis, r


def segments_distance(p1, q1, p2, q2) -> float:
    """The distance between segments [p1, q1] and [p2, q2] (points where an end equals the
    other): the closest points' parameters clamped in turn (Ericson, Real-Time Collision
    Detection, 5.1.9)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, f = d1 @ d1, d2 @ d2, d2 @ r
    if a == 0 and e == 0:
        return float(np.linalg.norm(r))
    if a == 0:
        s, t = 0.0, float(np.clip(f / e, 0, 1))
    else:
        c = d1 @ r
        if e == 0:
            s, t = float(np.clip(-c / a, 0, 1)), 0.0
        else:
            b = d1 @ d2
            denominator = a * e - b * b
            s = float(np.clip((b * f - c * e) / denominator, 0, 1)) if denominator > 0 else 0.0
            t = (b * s + f) / e
            if t < 0:
                s, t = float(np.clip(-c / a, 0, 1)), 0.0
            elif t > 1:
                s, t = float(np.clip((b - c) / a, 0, 1)), 1.0
    return float(np.linalg.norm(p1 + s * d1 - (p2 + t * d2)))


def closed_form_signed_distance(kinds, sizes_a, sizes_b, pa, pb):
    """The signed distance of two spheres or capsules (their segments' distance less both
    radii), None for other kinds."""
    a, b = segment_of(kinds[0], sizes_a, pa), segment_of(kinds[1], sizes_b, pb)
    if a is None or b is None:
        return None
    return segments_distance(a[0], a[1], b[0], b[1]) - a[2] - b[2]


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

    # coal's GJK stops within 1e-6 (1 + |distance|) (GJK::checkConvergence, its default),
    # which on pairs smaller than a unit is looser than 1e-6 of their size.
    coal_slack = COAL_PRECISION * max(size, 1 + abs(theirs))
    closed = closed_form_signed_distance(kinds, sizes_a, sizes_b, pa, pb)
    if closed is not None and abs(theirs - closed) > coal_slack:
        found("coal", "coal off", coal=theirs, closed_form=closed)
    truth, slack = (theirs, coal_slack) if closed is None else (closed, 1e-12 * size)

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
        if not signed.lower_bound - slack <= truth <= signed.distance + slack:
            found(method, "outside", coal=theirs, closed_form=closed, lower=signed.lower_bound,
                  upper=signed.distance)
        if verdict.certified and abs(truth) > slack and verdict.colliding != (truth < 0):
            found(method, "wrong verdict", coal=theirs, closed_form=closed,
                  colliding=bool(verdict.colliding))
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
    coal_off: Counter = Counter()
    for kinds in pairs:
        for index in range(args.pairs):
            sweep = args.sweep_every > 0 and index % args.sweep_every == 0
            for finding in one_pair(kinds, rng, methods, args.tolerance, sweep, args.extreme):
                finding["index"] = index
                findings.append(finding)
                counts.setdefault(kinds, Counter())[(finding["method"], finding["category"])] += 1
                if finding["category"] == "coal off":
                    coal_off[kinds] += 1
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
    print()
    print("coal off a closed form by more than its precision: " +
          (", ".join(f"{k[0]}-{k[1]} {n}" for k, n in coal_off.items()) or "none"))
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        with open(args.json, "w", encoding="utf-8") as out:
            for finding in findings:
                out.write(json.dumps(finding) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
