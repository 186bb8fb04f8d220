"""An exact distance between convex hulls, independent of swarmcollide, for the tests.

The distance is that of the origin to the Minkowski difference D = conv{y_j - x_i}: zero when the
origin lies in D (behind every facet plane of D, or, for a flat D, when the linear program
"X^T lambda = Y^T delta on the two simplexes" is feasible), otherwise attained on a triangle, an
edge or a vertex of D, over all of which a brute force is exact for the small bodies the tests use.
"""

from __future__ import annotations

import itertools

import numpy as np
from scipy.optimize import linprog
from scipy.spatial import ConvexHull, QhullError


def overlap(x: np.ndarray, y: np.ndarray) -> bool:
    """True when conv(x) and conv(y) share a point."""
    n, m = len(x), len(y)
    equality = np.zeros((5, n + m))
    equality[:3, :n] = x.T
    equality[:3, n:] = -y.T
    equality[3, :n] = 1
    equality[4, n:] = 1
    rhs = np.array([0, 0, 0, 1, 1], dtype=float)
    solution = linprog(np.zeros(n + m), A_eq=equality, b_eq=rhs, bounds=(0, None), method="highs")
    return bool(solution.status == 0)


def _segment_distances(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    d = q - p
    length2 = np.einsum("ij,ij->i", d, d)
    t = np.where(length2 > 0, -np.einsum("ij,ij->i", p, d) / np.where(length2 > 0, length2, 1), 0)
    t = np.clip(t, 0, 1)
    return np.linalg.norm(p + t[:, None] * d, axis=1)


def _triangle_interior_distances(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    u, v = q - p, r - p
    normal = np.cross(u, v)
    area2 = np.einsum("ij,ij->i", normal, normal)
    ok = area2 > 1e-24 * np.maximum(1, np.einsum("ij,ij->i", u, u)) ** 2
    safe = np.where(ok, area2, 1)
    # Barycentric coordinates of the origin's projection onto each triangle's plane.
    beta = np.einsum("ij,ij->i", np.cross(-p, v), normal) / safe
    gamma = np.einsum("ij,ij->i", np.cross(u, -p), normal) / safe
    inside = ok & (beta >= 0) & (gamma >= 0) & (beta + gamma <= 1)
    plane = np.abs(np.einsum("ij,ij->i", p, normal)) / np.sqrt(safe)
    return np.where(inside, plane, np.inf)


def exact_distance(x: np.ndarray, y: np.ndarray) -> float:
    """The distance between conv(x) and conv(y)."""
    # Distances do not change under translation; centring keeps the linear program well scaled.
    origin = np.asarray(x, dtype=float)[0]
    x = np.asarray(x, dtype=float) - origin
    y = np.asarray(y, dtype=float) - origin
    points = (y[None, :, :] - x[:, None, :]).reshape(-1, 3)
    try:
        origin_inside = bool(np.all(ConvexHull(points).equations[:, 3] <= 0))
    except QhullError:
        origin_inside = overlap(x, y)
    if origin_inside:
        return 0.0
    best = float(np.min(np.linalg.norm(points, axis=1)))
    pairs = np.array(list(itertools.combinations(range(len(points)), 2)))
    if len(pairs):
        best = min(best, float(np.min(_segment_distances(points[pairs[:, 0]], points[pairs[:, 1]]))))
    triples = np.array(list(itertools.combinations(range(len(points)), 3)))
    if len(triples):
        interior = _triangle_interior_distances(*(points[triples[:, k]] for k in range(3)))
        best = min(best, float(np.min(interior)))
    return best


def random_pair(rng: np.random.Generator, points: int = 5, spread: float = 3.0):
    """Two random point clouds of unit size whose centres lie up to ``spread`` apart."""
    a = rng.normal(size=(points, 3))
    b = rng.normal(size=(points, 3)) + rng.uniform(-spread, spread, size=3)
    return a, b
