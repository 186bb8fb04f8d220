"""Exact distances and signed distances between convex hulls, independent of swarmcollide.

Both are read off the Minkowski difference D = conv{y_j - x_i}. The distance is that of the origin
from D: zero when the origin lies in D (behind every facet plane of D, or, for a flat D, when the
linear program "X^T lambda = Y^T delta on the two simplexes" is feasible), otherwise attained on
a triangle, an edge or a vertex of D, over all of which a brute force is exact for the small
bodies the tests use. When the origin lies in D, the penetration depth is the distance from the
origin to the nearest facet plane of D: the smallest support value max(D @ n) over the facet
normals n (a flat D has no interior, and no depth).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from scipy.optimize import linprog
from scipy.spatial import ConvexHull, QhullError


def _as_points(x) -> np.ndarray:
    return np.asarray(x, dtype=float).reshape(-1, 3)


def _differences(x, y):
    """The points of D, scaled by a power of two (exactly) into the unit ball, and the exponent.

    Differences of nearby coordinates are exact, and the scaling keeps the squares and cross
    products below from overflowing or underflowing for bodies of any size.
    """
    points = (_as_points(y)[None, :, :] - _as_points(x)[:, None, :]).reshape(-1, 3)
    largest = float(np.abs(points).max())
    exponent = math.frexp(largest)[1] if largest > 0 else 0
    return np.ldexp(points, -exponent), exponent


def overlap(x, y) -> bool:
    """True when conv(x) and conv(y) share a point."""
    x, y = _as_points(x), _as_points(y)
    origin = x[0]
    x, y = x - origin, y - origin  # a well-scaled linear program
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


def _hull(points: np.ndarray):
    """The hull of D, or None when D is flat (no interior)."""
    try:
        return ConvexHull(points)
    except QhullError:
        return None


def exact_distance(x, y) -> float:
    """The distance between conv(x) and conv(y)."""
    points, exponent = _differences(x, y)
    hull = _hull(points)
    inside = bool(np.all(hull.equations[:, 3] <= 0)) if hull is not None else overlap(x, y)
    if inside:
        return 0.0
    best = float(np.min(np.linalg.norm(points, axis=1)))
    pairs = np.array(list(itertools.combinations(range(len(points)), 2)))
    if len(pairs):
        best = min(best, float(np.min(_segment_distances(points[pairs[:, 0]], points[pairs[:, 1]]))))
    triples = np.array(list(itertools.combinations(range(len(points)), 3)))
    if len(triples):
        interior = _triangle_interior_distances(*(points[triples[:, k]] for k in range(3)))
        best = min(best, float(np.min(interior)))
    return math.ldexp(best, exponent)


def exact_signed_distance(x, y) -> float:
    """The distance between conv(x) and conv(y) when apart, minus the penetration depth when
    they overlap."""
    distance = exact_distance(x, y)
    points, exponent = _differences(x, y)
    hull = _hull(points)
    if distance > 0 or hull is None:
        return distance
    # Support values of all of D's points along each facet normal: a point Qhull merged into a
    # facet cannot lower the depth.
    depth = float(np.min(np.max(points @ hull.equations[:, :3].T, axis=0)))
    return -math.ldexp(depth, exponent)


def random_pair(rng: np.random.Generator, points: int = 5, spread: float = 3.0):
    """Two random point clouds of unit size whose centres lie up to ``spread`` apart."""
    a = rng.normal(size=(points, 3))
    b = rng.normal(size=(points, 3)) + rng.uniform(-spread, spread, size=3)
    return a, b
