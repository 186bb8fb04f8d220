"""What the shape tests share: poses by position, and answers checked against a closed form."""

import numpy as np
import pytest

IDENTITY = np.eye(3)


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
