"""The tests' own exact reference is checked on cases with known answers before it judges."""

import numpy as np
import pytest
from oracle import exact_distance

from swarmcollide import paper

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)


@pytest.mark.parametrize(
    ("offset", "expected"),
    [
        ([3, 0, 0], 2.0),  # face to face
        ([2, 2, 0], np.sqrt(2)),  # edge to edge
        ([2, 2, 2], np.sqrt(3)),  # vertex to vertex
        ([0.5, 0.5, 0.5], 0.0),  # overlapping
        ([1, 0, 0], 0.0),  # touching faces
    ],
)
def test_cube_pairs(offset, expected):
    assert exact_distance(CUBE, CUBE + offset) == pytest.approx(expected, abs=1e-12)


def test_paper_pairs():
    assert exact_distance(paper.A, paper.B_COLLIDING) == 0.0
    assert exact_distance(paper.A, paper.B_SEPARATE) == pytest.approx(1.0, abs=1e-12)


def test_point_above_triangle_interior():
    triangle = np.array([[-1, -1, 0], [2, -1, 0], [-1, 2, 0]], dtype=float)
    assert exact_distance(triangle, [[0, 0, 0.75]]) == pytest.approx(0.75, abs=1e-12)
