"""The benchmark's bodies for the Python scripts: the paper's tetrahedra and random polytopes.

The random pairs follow the C++ binary's recipe (points on the unit sphere, their hull's
vertices, B moved along a random ray from A's centroid until the exact signed distance is the
target) with NumPy's seeded generator, so the scripts need nothing but swarmcollide.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import List

import numpy as np

import swarmcollide as sc

PAPER_A = np.array([[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]], dtype=float)
PAPER_B_TOUCHING = np.array([[1, 0, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]], dtype=float)
PAPER_B_SEPARATE = np.array([[1, -1, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]], dtype=float)

PROXIMITIES = {
    "apart": 1.0,
    "gap 1e-1": 1e-1,
    "gap 1e-2": 1e-2,
    "gap 1e-3": 1e-3,
    "gap 1e-4": 1e-4,
    "overlap 1e-4": -1e-4,
    "overlap 1e-3": -1e-3,
    "overlap 1e-2": -1e-2,
    "overlap 1e-1": -1e-1,
}


@dataclass
class Pair:
    """Two bodies and the exact distance between them (0 when they touch or overlap)."""

    a: np.ndarray
    b: np.ndarray
    reference: float

    @property
    def colliding(self) -> bool:
        return self.reference <= 1e-9


@dataclass
class Workload:
    name: str
    n: int
    proximity: str
    pairs: List[Pair]


def exact_distance(a: np.ndarray, b: np.ndarray) -> float:
    """The certified exact distance (the "exact" method, as in swarmcollide-bench) used as the
    reference everywhere."""
    return sc.distance(a, b, method="exact").distance


def paper_workloads() -> List[Workload]:
    return [
        Workload("paper touching", 4, "touching", [Pair(PAPER_A, PAPER_B_TOUCHING, 0.0)]),
        Workload("paper separate", 4, "separate", [Pair(PAPER_A, PAPER_B_SEPARATE, 1.0)]),
    ]


def _sphere_polytope(n: int, rng: np.random.Generator) -> np.ndarray:
    points = rng.standard_normal((n, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    return points[np.asarray(sc.ConvexPolyhedron(points).hull().vertex_indices)]


def _signed(a: np.ndarray, b: np.ndarray) -> float:
    return sc.signed_distance(a, b, method="fcl").distance


def random_pair(n: int, target: float, seed: int) -> Pair:
    """Random n-vertex pair whose signed distance is `target` (to bisection precision)."""
    rng = np.random.default_rng(seed)
    while True:
        a = _sphere_polytope(n, rng)
        b0 = _sphere_polytope(n, rng)
        b0 += a.mean(axis=0) - b0.mean(axis=0)
        u = rng.standard_normal(3)
        u /= np.linalg.norm(u)
        # Thin bodies cannot overlap by every target: draw again.
        if not _signed(a, b0) < target:
            continue
        lo = 0.0
        hi = max(0.0, target + (a @ u).max() - (b0 @ u).min())
        while _signed(a, b0 + hi * u) < target:
            hi += 0.5
        for _ in range(60):
            mid = (lo + hi) / 2
            if _signed(a, b0 + mid * u) < target:
                lo = mid
            else:
                hi = mid
        b = b0 + hi * u
        return Pair(a, b, exact_distance(a, b))


def random_workloads(sizes, proximities, pairs: int) -> List[Workload]:
    workloads = []
    for n in sizes:
        for k, name in enumerate(proximities):
            target = PROXIMITIES[name]
            ps = [random_pair(n, target, 1_000_003 * n + 1009 * k + i) for i in range(pairs)]
            workloads.append(Workload(f"n={n} {name}", n, name, ps))
    return workloads
