"""method="dual": the paper's swarm over separating directions with an exact finish.

Every answer is certified to 1e-9 of the bodies' size, against the tests' own exact oracle for
small bodies and against FCL (GJK and EPA) for larger ones.
"""

import numpy as np
import pytest
from oracle import exact_distance

import swarmcollide as sc


def sphere_polytope(rng: np.random.Generator, n: int) -> np.ndarray:
    points = rng.normal(size=(n, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    return points[sc.ConvexPolyhedron(points).hull().vertex_indices]


def placed_pair(rng: np.random.Generator, n: int, gap: float):
    """A and B with B moved so that it is `gap` from A (or pushed `-gap` past touching)."""
    a = sphere_polytope(rng, n)
    u = rng.normal(size=3)
    b = sphere_polytope(rng, n) + 3 * u / np.linalg.norm(u)
    r = sc.distance(a, b, method="fcl")
    along = (r.point_b - r.point_a) / r.distance
    return a, b - (r.distance - gap) * along


def size_of(a, b) -> float:
    return max(float(np.linalg.norm(np.ptp(x, axis=0))) for x in (a, b))


def check_certified(a, b, r):
    assert r.method == "dual"
    assert r.certified
    assert np.all(r.weights_a >= 0) and np.all(r.weights_b >= 0)
    assert r.weights_a.sum() == pytest.approx(1, abs=1e-12)
    assert r.weights_b.sum() == pytest.approx(1, abs=1e-12)
    np.testing.assert_allclose(r.point_a, np.asarray(a).T @ r.weights_a, atol=1e-12)
    np.testing.assert_allclose(r.point_b, np.asarray(b).T @ r.weights_b, atol=1e-12)
    if not r.colliding:
        assert r.distance - r.lower_bound <= 1e-9 * size_of(a, b)


def test_paper_pairs(tetra_a, touching_b, separate_b):
    apart = sc.distance(tetra_a, separate_b, method="dual")
    check_certified(tetra_a, separate_b, apart)
    assert apart.distance == pytest.approx(1, abs=1e-12)
    touching = sc.distance(tetra_a, touching_b, method="dual")
    check_certified(tetra_a, touching_b, touching)
    assert touching.colliding
    assert sc.collide(tetra_a, touching_b, method="dual")
    assert not sc.collide(tetra_a, separate_b, method="dual")


@pytest.mark.parametrize("gap", [1.0, 1e-1, 1e-2, 1e-3, 1e-4, -1e-4, -1e-3, -1e-2, -1e-1])
def test_small_bodies_against_the_oracle(gap):
    rng = np.random.default_rng(int(abs(np.log10(abs(gap)))) + (gap < 0) * 10)
    for _ in range(3):
        a, b = placed_pair(rng, 8, gap)
        r = sc.distance(a, b, method="dual")
        check_certified(a, b, r)
        exact = exact_distance(a, b)
        assert r.distance == pytest.approx(exact, abs=1e-9 * size_of(a, b))
        assert r.colliding == (gap < 0)


@pytest.mark.parametrize("n", [64, 512])
@pytest.mark.parametrize("gap", [1e-1, 1e-4, -1e-4, -1e-1])
def test_larger_bodies_against_fcl(n, gap):
    rng = np.random.default_rng(n)
    a, b = placed_pair(rng, n, gap)
    r = sc.distance(a, b, method="dual")
    check_certified(a, b, r)
    fcl = sc.distance(a, b, method="fcl")
    assert r.colliding == fcl.colliding == (gap < 0)
    assert r.distance == pytest.approx(fcl.distance, abs=1e-9 * size_of(a, b))


@pytest.mark.parametrize("n", [8, 64])
@pytest.mark.parametrize("gap", [1e-2, -1e-4, -1e-2, -1e-1])
def test_signed_distance_agrees_with_fcl_epa(n, gap):
    rng = np.random.default_rng(7 + n)
    a, b = placed_pair(rng, n, gap)
    r = sc.signed_distance(a, b, method="dual")
    fcl = sc.signed_distance(a, b, method="fcl")
    assert r.method == "dual"
    assert r.distance == pytest.approx(fcl.distance, rel=1e-6)
    np.testing.assert_allclose(r.point_b - r.point_a, r.distance * r.direction, atol=1e-9)


def test_same_seed_same_answer():
    rng = np.random.default_rng(1)
    a, b = placed_pair(rng, 64, 1e-3)
    first = sc.distance(a, b, method="dual", seed=3)
    second = sc.distance(a, b, method="dual", seed=3)
    assert first.distance == second.distance
    assert first.evaluations == second.evaluations
    np.testing.assert_array_equal(first.history, second.history)


def test_parameters(tetra_a, separate_b):
    r = sc.distance(
        tetra_a,
        separate_b,
        method="dual",
        swarm_size=40,
        max_iterations=5,
        w_min=0.3,
        w_max=0.8,
        tolerance=1e-3,
        feature_tolerance=1e-2,
        max_rounds=3,
    )
    assert r.certified and r.distance - r.lower_bound <= 1e-3


@pytest.mark.parametrize(
    "name, value",
    [
        ("swarm_size", 1),
        ("max_iterations", -1),
        ("w_max", -1.0),
        ("tolerance", -1.0),
        ("relative_tolerance", 0.0),
        ("feature_tolerance", -1.0),
        ("max_rounds", 0),
    ],
)
def test_bad_options_name_the_field(tetra_a, separate_b, name, value):
    with pytest.raises(ValueError, match=name):
        sc.distance(tetra_a, separate_b, method="dual", **{name: value})


def test_inapplicable_parameter(tetra_a, separate_b):
    with pytest.raises(ValueError, match="velocity_limit does not apply"):
        sc.distance(tetra_a, separate_b, method="dual", velocity_limit=1.0)
