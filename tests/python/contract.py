"""The contract every query result keeps, whatever the method, and the cases it is checked on.

Written once and run against every method (test_contract.py) and reused by the solver tests:
weights on the simplexes reproduce the witnesses, ``distance`` is the distance between them (for
signed distances ``point_b - point_a = distance * direction``), ``lower_bound <= true value <=
distance``, a certified verdict is right, ``status == "converged"`` means the bounds are within the
tolerance, and the method is the one asked for or ``"exact"`` naming it in ``escalated_from``.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

import numpy as np
from oracle import exact_distance, exact_signed_distance

import swarmcollide as sc
from swarmcollide import paper

QUERIES = ("distance", "collide", "signed_distance")
CASE_SETS = ("paper", "hard", "random")

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
TETRA = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)

# The tolerances the contract runs at: the default, and one loose enough that the methods stop
# early, far from their exact answers (one meaning of tolerance for every method and query).
TOLERANCES = (sc.DEFAULT_TOLERANCE, 1e-3)

# How close ``distance`` comes to the true value (the distance, or the signed distance), relative
# to the pair's size, at the default tolerance. The certified methods keep the tolerance; the
# paper's swarms and its penalty baseline reach the paper's Tables 1-2 to about 1e-4 and promise
# only their bounds elsewhere (None). At a looser tolerance no method need come closer than it.
_CERTIFIED = dict.fromkeys(CASE_SETS, sc.DEFAULT_TOLERANCE)
ACCURACY: Dict[str, Dict[str, Optional[float]]] = {
    "dual": _CERTIFIED,
    "exact": _CERTIFIED,
    "fcl": _CERTIFIED,
    "libccd": _CERTIFIED,
    "ipso": {"paper": 1e-4, "hard": None, "random": None},
    "pso": {"paper": 1e-4, "hard": None, "random": None},
    "penalty": {"paper": 1e-4, "hard": None, "random": None},
}


@dataclass(frozen=True)
class Case:
    """A pair with its true distance and signed distance."""

    name: str
    a: np.ndarray
    b: np.ndarray
    distance: float
    signed_distance: float


def hard_pairs() -> Dict[str, Tuple[np.ndarray, np.ndarray, float, float]]:
    """Pairs of the kinds on which solvers have been wrong, with their distance and signed
    distance worked out by hand: touching, nearly touching and overlapping faces, edges and
    vertices, stacked cubes, size ratios and offsets of a million, flat, collinear, single-point
    and repeated points."""
    big = np.array([[x, y, z] for x in (-1e6, 1e6) for y in (-1e6, 1e6) for z in (0, 1e6)])
    segment = np.array([[-1.0, 0, 0], [1.0, 0, 0]])
    square = CUBE[:4]  # the face x = 0
    gap_9 = (1 + 1e-9) - 1  # the gap as the doubles give it
    return {
        "vertex on vertex": (TETRA, -TETRA, 0.0, 0.0),
        "edge on edge": (CUBE, CUBE + [1, 1, 0], 0.0, 0.0),
        "face on face": (CUBE, CUBE + [1, 0.3, 0.2], 0.0, 0.0),
        "faces 1e-16 apart": (CUBE - [1, 0, 0], CUBE + [1e-16, 0.2, 0.3], 1e-16, 1e-16),
        "faces 1e-9 apart": (CUBE, CUBE + [1 + 1e-9, 0, 0], gap_9, gap_9),
        "stacked cubes": (CUBE, CUBE + [0, 0, 1], 0.0, 0.0),
        "stacked cubes 1e-3 apart": (CUBE, CUBE + [0.5, 0.5, 1.001], 0.001, 0.001),
        "cubes overlapping by half": (CUBE, CUBE + [0.5, 0.25, 0.125], 0.0, -0.5),
        # Offsets that are not binary fractions leave face diagonals a rounding from parallel.
        "cubes overlapping by tenths": (CUBE, CUBE + [0.1, 0.1, 0.4], 0.0, -0.6),
        "needle through a plate": (
            CUBE * [2, 2, 2e-3] - [1, 1, 1e-3],
            CUBE * [2e-3, 2e-3, 2] - [1e-3, 1e-3, 1],
            0.0,
            -1.001,
        ),
        "size ratio 1e6": (big, TETRA + [0, 0, 1e6 + 0.5], 0.5, 0.5),
        "offset 1e6": (CUBE + 1e6, CUBE + 1e6 + [2, 0.5, 0.5], 1.0, 1.0),
        "flat square and tetrahedron": (square, TETRA + [0.2, 0.2, 0.3], 0.2, 0.2),
        "coplanar squares overlapping": (square, square + [0, 0.5, 0.5], 0.0, 0.0),
        "point inside a solid": (paper.A, np.array([[0.1, 0.1, 0.1]]), 0.0, -0.1),
        "one point twice": (np.array([[1.0, 2, 3]]), np.array([[1.0, 2, 3]]), 0.0, 0.0),
        "segment and point": (segment, np.array([[0.3, 2.0, 0]]), 2.0, 2.0),
        "crossing segments": (segment, segment[:, [1, 0, 2]], 0.0, 0.0),
        "duplicate vertices": (np.vstack([TETRA, TETRA, TETRA[:2]]), TETRA + [2, 0, 0], 1.0, 1.0),
    }


def _random_pairs() -> Dict[str, Tuple[np.ndarray, np.ndarray]]:
    """Seeded random hulls of 4 to 8 points: apart, close, overlapping, and a flat one."""
    rng = np.random.default_rng(2026)
    pairs = {}
    for k in range(9):
        a = rng.uniform(-1, 1, size=(4 + k % 5, 3))
        if k % 3 == 0:
            offset = rng.normal(size=3)
            offset *= 4 / np.linalg.norm(offset)
        elif k % 3 == 1:
            offset = np.array([2.2, *rng.uniform(-0.3, 0.3, size=2)])
        else:
            offset = rng.uniform(-0.5, 0.5, size=3)
        pairs[f"random {k}"] = (a, rng.uniform(-1, 1, size=(8 - k % 4, 3)) + offset)
    flat = rng.uniform(-1, 1, size=(6, 3)) * [1, 1, 0]
    pairs["flat beside a solid"] = (flat, rng.uniform(-1, 1, size=(6, 3)) + [0.5, 0, 1.5])
    return pairs


@functools.lru_cache(maxsize=None)
def cases(case_set: str) -> Tuple[Case, ...]:
    """The cases of a set with their true answers: the paper's pairs and the hard cases in both
    orders (so the contract also checks d(A, B) = d(B, A)), the random ones in one."""
    found: List[Case] = []

    def both_orders(name, a, b):
        a, b = np.asarray(a, float), np.asarray(b, float)
        distance, signed = exact_distance(a, b), exact_signed_distance(a, b)
        found.append(Case(name, a, b, distance, signed))
        found.append(Case(name + ", swapped", b, a, distance, signed))

    if case_set == "paper":
        both_orders("Section IV-A, touching", paper.A, paper.B_COLLIDING)
        both_orders("Section IV-B, separate", paper.A, paper.B_SEPARATE)
    elif case_set == "hard":
        for name, (a, b, _, _) in hard_pairs().items():
            both_orders(name, a, b)
    else:
        for name, (a, b) in _random_pairs().items():
            found.append(Case(name, a, b, exact_distance(a, b), exact_signed_distance(a, b)))
    return tuple(found)


@dataclass(frozen=True)
class Scale:
    """A pair's size as the library defines it and the margins of the checks, in world units."""

    size: float
    tolerance: float
    rounding: float
    point_rounding: float


def norm(v) -> float:
    """The Euclidean norm without underflow: np.linalg.norm squares the entries, so vectors of
    entries below 1e-154 come out 0 (and a pair of such bodies would get size 0)."""
    v = np.asarray(v, float)
    largest = float(np.abs(v).max()) if v.size else 0.0
    return largest * float(np.linalg.norm(v / largest)) if largest > 0 else 0.0


def pair_scale(a, b, tolerance: float = sc.DEFAULT_TOLERANCE) -> Scale:
    """The size is the diameter of the ball around both bodies that queries compute in: the
    distance between their boxes' centres plus the longer box diagonal. Bounds and the oracle
    are kept to 1e-12 of it (the library's rounding is 64 epsilons of it); world points carry
    besides 16 epsilons of their largest coordinate."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    lo_a, hi_a, lo_b, hi_b = a.min(0), a.max(0), b.min(0), b.max(0)
    centres = norm((lo_b / 2 + hi_b / 2) - (lo_a / 2 + hi_a / 2))
    size = float(centres + max(norm(hi_a - lo_a), norm(hi_b - lo_b)))
    magnitude = float(max(np.abs(a).max(), np.abs(b).max()))
    return Scale(size, tolerance * size, 1e-12 * size, 16 * np.finfo(float).eps * magnitude)


def ask(query: sc.Query, kind: str, a, b) -> sc.DistanceResult:
    """The result of query ``kind``; for collide, the result that decides it."""
    if kind == "collide":
        return query.collision(a, b)
    return getattr(query, kind)(a, b)


def separation(a, b, direction) -> float:
    """min_j n . y_j - max_i n . x_i, on the pairwise differences (exact for nearby points)."""
    differences = np.asarray(b, float)[None, :, :] - np.asarray(a, float)[:, None, :]
    return float(np.min(differences.reshape(-1, 3) @ np.asarray(direction)))


def check_contract(
    kind: str,
    method: str,
    a,
    b,
    r: sc.DistanceResult,
    distance: float,
    signed_distance: float,
    scale: Scale,
    budget_capped: bool = False,
) -> None:
    """The result contract of a query of ``kind`` asked of ``method`` for the pair (a, b), whose
    true distance and signed distance are given. ``budget_capped`` says the options cut an
    iteration budget below what a proof may need, which releases the methods that are always
    certified from being so."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    rounding = scale.rounding
    points = scale.rounding + scale.point_rounding
    # The answer's fields and their types.
    assert r.status in ("converged", "max_iterations")
    assert r.method in sc.METHODS
    assert r.escalated_from is None or r.escalated_from in sc.METHODS
    assert r.gap == r.distance - r.lower_bound
    assert repr(r).startswith(f"DistanceResult(method='{r.method}'")
    # Weights on the simplexes that reproduce the witnesses.
    wa, wb = r.weights_a, r.weights_b
    assert wa.dtype == np.float64 and wa.shape == (len(a),)
    assert wb.dtype == np.float64 and wb.shape == (len(b),)
    assert wa.min() >= 0 and wb.min() >= 0
    assert abs(wa.sum() - 1) <= 1e-12 and abs(wb.sum() - 1) <= 1e-12
    assert norm(a.T @ wa - r.point_a) <= points
    assert norm(b.T @ wb - r.point_b) <= points
    direction_norm = norm(r.direction)
    assert direction_norm == 0 or abs(direction_norm - 1) <= 1e-12
    # Methods without distances answer collide with their signed distance, unless "exact" took
    # over; either way the true signed distance is at most the distance.
    signed_query = kind == "signed_distance" or (
        kind == "collide" and "distance" not in sc.METHODS[method].queries
    )
    gap = r.distance - r.lower_bound
    if kind == "signed_distance":
        assert norm(r.point_b - r.point_a - r.distance * r.direction) <= gap + points
        if direction_norm > 0:
            assert abs(separation(a, b, r.direction) - r.lower_bound) <= rounding
            # The witnesses lie on the supporting planes along the normal, to within the gap.
            assert abs(r.direction @ r.point_a - np.max(a @ r.direction)) <= gap + points
            assert abs(r.direction @ r.point_b - np.min(b @ r.direction)) <= gap + points
        assert r.lower_bound <= signed_distance + rounding
        assert signed_distance <= r.distance + rounding
    else:
        if signed_query:
            assert abs(norm(r.point_b - r.point_a) - abs(r.distance)) <= gap + points
        else:
            assert abs(r.distance - norm(r.point_b - r.point_a)) <= points
            assert r.lower_bound >= 0
        if r.lower_bound > 0:
            assert abs(direction_norm - 1) <= 1e-12
            assert abs(separation(a, b, r.direction) - r.lower_bound) <= rounding
        assert r.lower_bound <= distance + rounding
        assert (signed_distance if signed_query else distance) <= r.distance + rounding
    # A certified verdict is right; at the threshold itself, rounding decides.
    if r.certified:
        if r.colliding:
            assert distance <= scale.tolerance + rounding, "certified contact of bodies apart"
        else:
            assert distance > scale.tolerance - rounding, "certified separation of touching bodies"
        if kind == "signed_distance":
            assert abs(r.distance - signed_distance) <= scale.tolerance + rounding
    if r.status == "converged":
        assert gap <= scale.tolerance + 2 * rounding
    if r.escalated_from is not None:
        assert (r.method, r.escalated_from) == ("exact", method) and method != "exact"
    else:
        assert r.method == method
    if not budget_capped and (sc.METHODS[method].always_certified or r.method == "exact"):
        assert r.certified


def assert_identical(first: sc.DistanceResult, second: sc.DistanceResult) -> None:
    """Two answers are the same, bit for bit."""
    for field in (
        "distance",
        "lower_bound",
        "iterations",
        "evaluations",
        "colliding",
        "certified",
        "method",
        "escalated_from",
        "status",
    ):
        assert getattr(first, field) == getattr(second, field), field
    for field in ("point_a", "point_b", "weights_a", "weights_b", "direction", "history"):
        np.testing.assert_array_equal(getattr(first, field), getattr(second, field), err_msg=field)


def size_accuracy(method: str, case_set: str, scale: Scale, tolerance: float) -> Optional[float]:
    """How far ``distance`` may be from the true value for ``method`` on ``case_set``."""
    relative = ACCURACY[method][case_set]
    return None if relative is None else max(relative, tolerance) * scale.size + scale.rounding

