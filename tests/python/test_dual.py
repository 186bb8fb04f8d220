"""method="dual": the paper's swarm over separating directions with an exact finish, on bodies too
large for the oracle, against the exact method."""

import numpy as np
import pytest
from contract import assert_identical, pair_scale

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
    r = sc.distance(a, b, method="exact")
    along = (r.point_b - r.point_a) / r.distance
    return a, b - (r.distance - gap) * along


@pytest.mark.parametrize("n", [64, 512])
@pytest.mark.parametrize("gap", [1e-1, 1e-4, -1e-4, -1e-1])
def test_larger_bodies_agree_with_the_exact_methods(n, gap):
    rng = np.random.default_rng(n)
    a, b = placed_pair(rng, n, gap)
    scale = pair_scale(a, b)
    r = sc.distance(a, b)
    assert r.method == "dual" and r.certified and r.status == "converged"
    for method in ("exact", "fcl"):
        other = sc.distance(a, b, method=method)
        assert r.colliding == other.colliding == (gap < 0)
        assert abs(r.distance - other.distance) <= scale.tolerance + scale.rounding


@pytest.mark.parametrize("n", [8, 64])
@pytest.mark.parametrize("gap", [1e-2, -1e-4, -1e-2, -1e-1])
def test_signed_distances_agree_with_the_exact_method(n, gap):
    rng = np.random.default_rng(7 + n)
    a, b = placed_pair(rng, n, gap)
    scale = pair_scale(a, b)
    r = sc.signed_distance(a, b)
    exact = sc.signed_distance(a, b, method="exact")
    assert r.method == "dual" and r.certified
    assert abs(r.distance - exact.distance) <= scale.tolerance + scale.rounding
    np.testing.assert_allclose(r.point_b - r.point_a, r.distance * r.direction, atol=r.gap + 1e-12)


def test_same_seed_same_answer():
    rng = np.random.default_rng(1)
    a, b = placed_pair(rng, 64, 1e-3)
    assert_identical(sc.distance(a, b, seed=3), sc.distance(a, b, seed=3))


def test_parameters_reach_the_solver(tetra_a, separate_b):
    r = sc.distance(tetra_a, separate_b, swarm_size=40, max_iterations=5, w_min=0.3, w_max=0.8,
                    tolerance=1e-3, feature_tolerance=1e-2, max_rounds=3)
    assert r.certified and r.gap <= 1e-3 * pair_scale(tetra_a, separate_b).size
    rng = np.random.default_rng(3)
    a, b = placed_pair(rng, 64, 1e-3)
    capped = sc.distance(a, b, tolerance=0, max_rounds=2, max_iterations=4)
    assert capped.iterations <= 2 * 4
