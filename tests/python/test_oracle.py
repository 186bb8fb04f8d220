"""The tests' own reference is checked on cases with answers worked out by hand before it judges."""

import numpy as np
import pytest
from contract import CUBE, hard_pairs
from oracle import exact_distance, exact_signed_distance

from swarmcollide import paper


@pytest.mark.parametrize(
    ("offset", "distance", "signed_distance"),
    [
        ([3, 0, 0], 2.0, 2.0),  # face to face
        ([2, 2, 0], np.sqrt(2), np.sqrt(2)),  # edge to edge
        ([2, 2, 2], np.sqrt(3), np.sqrt(3)),  # vertex to vertex
        ([0.5, 0.5, 0.5], 0.0, -0.5),  # overlapping
        ([0.25, 0.125, 0.9], 0.0, -0.1),  # overlapping, least along z
        ([1, 0, 0], 0.0, 0.0),  # touching faces
        ([0, 0, 0], 0.0, -1.0),  # the same cube
    ],
)
def test_cube_pairs(offset, distance, signed_distance):
    assert exact_distance(CUBE, CUBE + offset) == pytest.approx(distance, abs=1e-12)
    assert exact_signed_distance(CUBE, CUBE + offset) == pytest.approx(signed_distance, abs=1e-12)


def test_paper_pairs():
    assert exact_distance(paper.A, paper.B_COLLIDING) == 0.0
    assert exact_signed_distance(paper.A, paper.B_COLLIDING) == pytest.approx(0, abs=1e-15)
    assert exact_distance(paper.A, paper.B_SEPARATE) == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("name", list(hard_pairs()))
def test_hard_pairs_in_both_orders(name):
    a, b, distance, signed_distance = hard_pairs()[name]
    size = max(1.0, float(np.ptp(np.vstack([a, b]), axis=0).max()))
    for x, y in ((a, b), (b, a)):
        assert exact_distance(x, y) == pytest.approx(distance, abs=1e-15 * size)
        assert exact_signed_distance(x, y) == pytest.approx(signed_distance, abs=1e-15 * size)


@pytest.mark.parametrize("scale", [1e-200, 1e200])
def test_any_scale(scale):
    assert exact_distance(CUBE * scale, (CUBE + [3, 0, 0]) * scale) == pytest.approx(2 * scale)
    assert exact_signed_distance(CUBE * scale, (CUBE + 0.5) * scale) == pytest.approx(-0.5 * scale)


def test_point_above_triangle_interior():
    triangle = np.array([[-1, -1, 0], [2, -1, 0], [-1, 2, 0]], dtype=float)
    assert exact_distance(triangle, [[0, 0, 0.75]]) == pytest.approx(0.75, abs=1e-12)
