"""Curved collision shapes of robot models (URDF and MJCF cylinders, MJCF ellipsoids) as bodies.

Until the curved shapes of issue 26 (``Cylinder``, ``Ellipsoid``) are in the core, a cylinder or
an ellipsoid becomes the convex hull of points on its surface, which lies inside the true shape:
``curved_body`` returns that body with a proven bound on how far inside. Spheres and capsules are
exact already (``Sphere``, ``Capsule``). This module is the one place to switch to the real
shapes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple

import numpy as np

from . import _core

SEGMENTS = 32
"""Points around each circle of a sampled cylinder, and meridians of a sampled ellipsoid."""


@dataclass(frozen=True)
class Approximation:
    """A geometry that stands for a curved shape by a hull inside it.

    Attributes
    ----------
    geometry : str
        The geometry's name in the robot.
    shape : str
        ``"cylinder"`` or ``"ellipsoid"``.
    error : float
        A proven bound on how far inside the true shape the hull's surface lies (in the model's
        units): distances are at most this much too large, penetrations this much too shallow.
    """

    geometry: str
    shape: str
    error: float


def curved_body(shape: str, size: Tuple[float, ...], segments: int = SEGMENTS):
    """A body for a curved shape, and how far inside the shape it can lie.

    Parameters
    ----------
    shape : {"cylinder", "ellipsoid"}
        A cylinder along z centred on the origin, ``size = (radius, half_length)``; or an
        ellipsoid centred on the origin, ``size = (a, b, c)``, its semi-axes along x, y and z.
    size : tuple of float
        Positive and finite.
    segments : int
        Points around each circle (at least 8).

    Returns
    -------
    body : ConvexPolyhedron
        The hull of points on the shape's surface, inside the shape.
    error : float
        A bound on the distance from the shape's surface to the hull's: for a cylinder of radius
        r, ``r (1 - cos(pi / segments))`` (the sagitta of a polygon inscribed in the circle); for
        an ellipsoid, ``(1 - rho) max(a, b, c)``, with rho the inradius of the hull of the unit
        sphere's points, measured from the hull's facets.

    Examples
    --------
    >>> from swarmcollide.robot_shapes import curved_body
    >>> body, error = curved_body("cylinder", (0.5, 1.0))
    >>> len(body.vertices), round(error, 6)
    (64, 0.002408)
    """
    values = np.asarray(size, dtype=float)
    if not np.all(np.isfinite(values)) or np.any(values <= 0):
        raise ValueError(f"{shape} size must be positive and finite, got {tuple(size)}")
    if segments < 8:
        raise ValueError(f"segments must be at least 8, got {segments}")
    angles = 2 * math.pi * np.arange(segments) / segments
    if shape == "cylinder":
        radius, half_length = values
        ring = np.column_stack([radius * np.cos(angles), radius * np.sin(angles)])
        points = np.vstack(
            [np.column_stack([ring, np.full(segments, z)]) for z in (-half_length, half_length)]
        )
        return _core.ConvexPolyhedron(points), float(radius * (1 - math.cos(math.pi / segments)))
    if shape == "ellipsoid":
        unit = _sphere_points(segments)
        return _core.ConvexPolyhedron(unit * values), float((1 - _inradius(unit)) * values.max())
    raise ValueError(f"shape must be 'cylinder' or 'ellipsoid', got {shape!r}")


def _sphere_points(segments: int) -> np.ndarray:
    # Meridians every 2 pi / segments and parallels every pi / (segments / 2), with the poles.
    polar = math.pi * np.arange(1, segments // 2) / (segments // 2)
    azimuth = 2 * math.pi * np.arange(segments) / segments
    theta, phi = np.meshgrid(polar, azimuth, indexing="ij")
    ring = np.column_stack(
        [(np.sin(theta) * np.cos(phi)).ravel(), (np.sin(theta) * np.sin(phi)).ravel(),
         np.cos(theta).ravel()]
    )
    return np.vstack([ring, [[0, 0, 1], [0, 0, -1]]])


def _inradius(points: np.ndarray) -> float:
    # The hull of the unit sphere's points holds the ball of radius min over facets of the
    # facet's distance from the origin; the ellipsoid's hull (its image under diag(a, b, c))
    # holds that ball's image, rho E, so no point of E is farther than (1 - rho) max(a, b, c).
    from scipy.spatial import ConvexHull

    offsets = ConvexHull(points).equations[:, 3]
    # A facet's offset is rounded: take a little off the radius so the bound stays proven.
    return float(-offsets.max()) - 1e-12
