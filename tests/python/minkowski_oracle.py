"""Signed distance between two convex hulls, from the hull of their differences; no swarmcollide.

conv(B) - conv(A) is the convex hull D of the pairwise differences ``y_j - x_i``. The bodies are
apart by the distance from the origin to D when the origin lies outside D; when it lies inside,
they overlap by the distance from the origin to D's boundary, which is the smallest distance to a
facet plane. So the signed distance is ``dist(0, D)`` outside and ``max(facet offsets) <= 0``
inside. A D of affine dimension below 3 has no interior: the bodies then touch at most, and the
signed distance is ``dist(0, D) >= 0``.

Accuracy
--------
Each difference is rounded once (relative error 2**-53 of itself). D is then divided by a power of
two so that its largest coordinate lies in [0.5, 1): an exact operation, so the answer scales
exactly with the input from 1e-300 to 1e300 and is the same in every unit. In that frame Qhull
(merged facets, about 1e-15) and the closest-point formulas are accurate to far below ``ROUNDING``
= 1e-12, and so is the reduction of large bodies to their hull vertices that comes first. A D that lies within ``FLAT`` = 1e-10 (in that frame) of a plane, a line or a point is
treated as that plane, line or point (Qhull is ill-conditioned there), and the distance dropped is
added to ``error``; a thin solid adds ``16 eps / thickness``, the conditioning of its facet normals.
``error`` bounds ``|signed_distance - exact|`` for the float64 values of the inputs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.spatial import ConvexHull, QhullError

ROUNDING = 1e-12
"""Error allowance of the hull and closest-point arithmetic, relative to D's largest coordinate."""

EPSILON = float(np.finfo(np.float64).eps)

FLAT = 1e-10
"""Thickness (relative to D's largest coordinate) below which D is treated as flat."""

# Above this many differences the bodies are first reduced to their hull vertices.
_REDUCE_ABOVE = 4096


@dataclass(frozen=True)
class Answer:
    """The oracle's signed distance and a bound on its own error (both in the input's units)."""

    signed_distance: float
    error: float
    dimension: int
    """Affine dimension of D as used: 0 (a point), 1, 2 (flat) or 3."""

    @property
    def distance(self) -> float:
        """The (unsigned) distance between the bodies."""
        return max(self.signed_distance, 0.0)


class OracleError(ArithmeticError):
    """The differences overflow float64, so the oracle has no answer."""


def signed_distance(a: npt.ArrayLike, b: npt.ArrayLike) -> Answer:
    """Signed distance from conv(a) to conv(b): positive apart, minus the depth when overlapping."""
    a, b = _points(a), _points(b)
    if len(a) * len(b) > _REDUCE_ABOVE:
        a, b = _hull_vertices(a), _hull_vertices(b)
    differences = (b[None, :, :] - a[:, None, :]).reshape(-1, 3)
    if not np.all(np.isfinite(differences)):
        raise OracleError("the differences of the bodies' points overflow float64")
    largest = float(np.max(np.abs(differences)))
    if largest == 0:
        return Answer(0.0, 0.0, 0)
    frame = math.ldexp(1.0, math.frexp(largest)[1])
    value, error, dimension = _signed_distance_from_origin(differences / frame)
    return Answer(value * frame, error * frame, dimension)


def point_distance(point: npt.ArrayLike, body: npt.ArrayLike) -> Answer:
    """Distance from ``point`` to conv(body) (negative inside a solid body)."""
    return signed_distance(body, np.asarray(point, dtype=np.float64).reshape(1, 3))


def _points(points: npt.ArrayLike) -> np.ndarray:
    array = np.asarray(points, dtype=np.float64)
    if array.ndim != 2 or array.shape[1] != 3 or len(array) == 0:
        raise ValueError(f"expected (n, 3) points, got shape {array.shape}")
    return array


def _hull_vertices(points: np.ndarray) -> np.ndarray:
    """The points that are vertices of their hull (all of them for a flat set).

    The hull is taken in a frame centred on the points and scaled by a power of two so that Qhull
    never sees 1e300; only the selection of points comes from it.
    """
    centred = points - points.mean(axis=0)
    largest = float(np.max(np.abs(centred)))
    if largest == 0:
        return points[:1]
    try:
        hull = ConvexHull(centred / math.ldexp(1.0, math.frexp(largest)[1]))
    except QhullError:
        return points
    return points[hull.vertices]


def _signed_distance_from_origin(points: np.ndarray) -> tuple[float, float, int]:
    """(signed distance from the origin to conv(points), error bound, dimension); |points| <= 1."""
    centre = points.mean(axis=0)
    centred = points - centre
    _, _, axes = np.linalg.svd(centred, full_matrices=False)
    # thickness[k]: how far the points lie from the k-dimensional affine subspace of best fit.
    thickness = [float(np.max(np.linalg.norm(centred @ axes[k:].T, axis=1))) for k in range(3)]
    thickness.append(0.0)
    dimension = next(k for k in range(4) if thickness[k] <= FLAT)
    while True:
        try:
            value = _in_dimension(dimension, centre, centred, axes, points)
        except QhullError:
            # Qhull finds the set too thin after all: one dimension down, the thickness as error.
            dimension -= 1
            continue
        # A thin solid's facet normals come from cross products of nearly parallel edges: their
        # rounding, and Qhull's, grows as eps over the thickness (a 1e-9 thin sliver: 1e-7 rad).
        conditioning = 16 * EPSILON / thickness[2] if dimension == 3 else 0.0
        return value, thickness[dimension] + ROUNDING + conditioning, dimension


def _in_dimension(
    dimension: int, centre: np.ndarray, centred: np.ndarray, axes: np.ndarray, points: np.ndarray
) -> float:
    """The signed distance from the origin to the points projected onto ``dimension`` axes."""
    origin = -centre  # the origin, seen from the centre
    if dimension == 0:
        return float(np.linalg.norm(centre))
    if dimension == 1:
        along = centred @ axes[0]
        t = float(np.clip(origin @ axes[0], along.min(), along.max()))
        return float(np.linalg.norm(origin - t * axes[0]))
    if dimension == 2:
        plane = axes[:2]
        height = float(origin @ axes[2])
        return math.hypot(height, _polygon_distance(centred @ plane.T, origin @ plane.T))
    return _solid_signed_distance(points)


def _polygon_distance(points: np.ndarray, query: np.ndarray) -> float:
    """Distance from the 2-D ``query`` to the hull of the 2-D ``points`` (0 inside)."""
    hull = ConvexHull(points)
    if np.all(hull.equations[:, :2] @ query + hull.equations[:, 2] <= 0):
        return 0.0
    start = points[hull.simplices[:, 0]]
    end = points[hull.simplices[:, 1]]
    return float(np.min(_segment_distances(start - query, end - query)))


def _solid_signed_distance(points: np.ndarray) -> float:
    hull = ConvexHull(points)
    offsets = hull.equations[:, 3]  # the signed distance of the origin to each facet plane
    if np.all(offsets <= 0):
        return float(np.max(offsets))
    triangles = points[hull.simplices]
    return float(np.min(_triangle_distances(triangles[:, 0], triangles[:, 1], triangles[:, 2])))


def _segment_distances(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Distances from the origin to the segments [p_k, q_k] (rows of any dimension)."""
    d = q - p
    length2 = np.einsum("ij,ij->i", d, d)
    safe = np.where(length2 > 0, length2, 1.0)
    t = np.clip(np.where(length2 > 0, -np.einsum("ij,ij->i", p, d) / safe, 0.0), 0.0, 1.0)
    return np.linalg.norm(p + t[:, None] * d, axis=1)


def _triangle_distances(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Distances from the origin to the triangles (p_k, q_k, r_k)."""
    u, v = q - p, r - p
    normal = np.cross(u, v)
    area2 = np.einsum("ij,ij->i", normal, normal)
    # A triangle too thin for barycentric coordinates is covered by its edges.
    proper = area2 > 1e-24
    safe = np.where(proper, area2, 1.0)
    beta = np.einsum("ij,ij->i", np.cross(-p, v), normal) / safe
    gamma = np.einsum("ij,ij->i", np.cross(u, -p), normal) / safe
    inside = proper & (beta >= 0) & (gamma >= 0) & (beta + gamma <= 1)
    plane = np.abs(np.einsum("ij,ij->i", p, normal)) / np.sqrt(safe)
    edges = np.minimum.reduce(
        [_segment_distances(p, q), _segment_distances(q, r), _segment_distances(r, p)]
    )
    return np.where(inside, np.minimum(plane, edges), edges)
