"""The tests' own reference is checked on cases with answers worked out by hand before it judges."""

import numpy as np
import minkowski_oracle
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


# The fuzz suite's oracle (minkowski_oracle) is checked against the brute force above and known
# depths, at every scale it is used at.

CUBE_B = CUBE + [0.5, 0.25, 0.1]  # the unit cube moved to overlap it by half its width
SQUARE = CUBE[[0, 2, 4, 6]]  # the cube's face z = 0


@pytest.mark.parametrize(
    ("a", "b", "expected"),
    [
        (CUBE, CUBE_B, -0.5),
        (CUBE, CUBE + [0.8, 0.1, 0.05], -0.2),
        (CUBE, CUBE + [1, 0, 0], 0.0),
        (CUBE, CUBE + [3, 0, 0], 2.0),
        (CUBE, CUBE + [2, 2, 2], np.sqrt(3)),
        (SQUARE, SQUARE + [0.5, 0.5, 0], 0.0),  # coplanar squares
        (SQUARE, SQUARE + [0.5, 0.5, 0.25], 0.25),  # parallel squares
        ([[-1, 0, 0], [1, 0, 0]], [[0.3, 2, 0]], 2.0),  # segment and point
        ([[-1, 0, 0], [1, 0, 0]], [[0, -1, 0], [0, 1, 0]], 0.0),  # crossing segments
        ([[1, 2, 3]], [[1, 2, 3]], 0.0),
        ([[0, 0, 0]], [[3, 4, 0]], 5.0),
    ],
)
def test_minkowski_oracle_known_signed_distances(a, b, expected):
    answer = minkowski_oracle.signed_distance(a, b)
    assert answer.signed_distance == pytest.approx(expected, abs=1e-12)
    assert answer.error <= 1e-11


def test_minkowski_oracle_matches_the_brute_force():
    rng = np.random.default_rng(12)
    for _ in range(100):
        a = rng.normal(size=(int(rng.integers(1, 7)), 3))
        b = rng.normal(size=(int(rng.integers(1, 7)), 3)) + rng.uniform(-3, 3, size=3)
        answer = minkowski_oracle.signed_distance(a, b)
        assert answer.distance == pytest.approx(exact_distance(a, b), abs=1e-11)
        assert (answer.signed_distance < 0) == (exact_distance(a, b) == 0 and answer.dimension == 3)


@pytest.mark.parametrize("power", [-1000, -330, -20, 0, 40, 250, 990])
def test_minkowski_oracle_scales_exactly_by_powers_of_two(power):
    rng = np.random.default_rng(power + 2000)
    a, b = rng.normal(size=(9, 3)), rng.normal(size=(7, 3)) * 0.6
    s = 2.0**power
    unit = minkowski_oracle.signed_distance(a, b)
    scaled = minkowski_oracle.signed_distance(a * s, b * s)
    assert unit.signed_distance < 0
    assert scaled.signed_distance == unit.signed_distance * s
    assert scaled.error == unit.error * s


@pytest.mark.parametrize("s", [1e-300, 1e-100, 1e-5, 1e77, 1e300])
def test_minkowski_oracle_at_extreme_scales(s):
    assert minkowski_oracle.signed_distance(CUBE * s, CUBE_B * s).signed_distance == pytest.approx(
        -0.5 * s, rel=1e-14
    )
    apart = minkowski_oracle.signed_distance(CUBE * s, CUBE * s + 3 * s)
    assert apart.signed_distance == pytest.approx(2 * np.sqrt(3) * s, rel=1e-14)


def test_minkowski_oracle_far_from_the_origin():
    # The brute force above loses the faces here (its squared areas overflow); this oracle does not.
    shift = np.array([1.2e98, -3e97, 5e97])
    answer = minkowski_oracle.signed_distance(CUBE * 1e93 + shift, CUBE_B * 1e93 + shift)
    assert answer.signed_distance == pytest.approx(-0.5e93, rel=1e-9)


def test_minkowski_oracle_counts_a_sliver_as_flat_and_says_so():
    sliver = np.vstack([SQUARE, [[0.5, 0.5, 1e-12]]])  # a square and an apex 1e-12 above it
    answer = minkowski_oracle.signed_distance(sliver, [[0.4, 0.6, 0.0]])
    assert answer.dimension == 2
    assert abs(answer.signed_distance) <= answer.error  # the exact value is 0: the point is inside
    assert 5e-13 <= answer.error <= 1e-11


def test_minkowski_oracle_point_distance():
    assert minkowski_oracle.point_distance([0.5, 0.5, 2], CUBE).signed_distance == pytest.approx(1)
    assert minkowski_oracle.point_distance([0.5, 0.5, 0.9], CUBE).signed_distance == pytest.approx(
        -0.1
    )
