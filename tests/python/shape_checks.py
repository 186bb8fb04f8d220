"""What the shape tests share: poses by position, and answers checked against a closed form."""

import numpy as np
import pytest

import swarmcollide as sc

IDENTITY = np.eye(3)

# One body of every kind, rounded and not: what must survive any way of writing a body down.
SHAPES = [
    sc.Sphere(0.5),
    sc.Capsule(0.25, 1.5),
    sc.Box([1.0, 2.0, 0.5]),
    sc.Box([1.0, 2.0, 0.5], radius=0.125),
    sc.Cylinder(0.3, 1.1),
    sc.Cone(0.7, 0.4),
    sc.Ellipsoid([0.1, 0.2, 0.3]),
    sc.ConvexPolyhedron([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], radius=0.05),
]


def at(x, y=0.0, z=0.0, rotation=IDENTITY):
    """The pose ``(rotation, translation)`` placing a body at ``(x, y, z)``."""
    return (rotation, [x, y, z])


def assert_encloses(result, expected, size, tolerance=1e-9):
    """``result`` is certified, its bounds hold the closed form ``expected`` and its distance is
    within ``tolerance * size`` of it (a slack of 1e-13 of the size for the closed form's own
    rounding)."""
    slack = 1e-13 * size
    assert result.certified
    assert result.lower_bound <= expected + slack
    assert result.distance >= expected - slack
    assert result.distance == pytest.approx(expected, abs=tolerance * size + slack)
