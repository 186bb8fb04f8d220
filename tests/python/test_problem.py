"""Model (2): objective (5), violation (6), feasibility and the separation certificate."""

import numpy as np
import pytest

import swarmcollide as sc


def test_objective_is_the_distance_between_the_combinations(tetra_a, separate_b):
    assert sc.objective(tetra_a, separate_b, [0, 1, 0, 0], [1, 0, 0, 0]) == 1.0
    assert sc.objective(tetra_a, separate_b, [0, 0, 0, 1], [0, 0, 0, 1]) == 2.0


def test_objective_checks_the_weights(tetra_a, separate_b):
    a, b = sc.ConvexPolyhedron(tetra_a), sc.ConvexPolyhedron(separate_b)
    with pytest.raises(ValueError, match="lambda has 3 weights but the body has 4"):
        sc.objective(a, b, [0, 1, 0], [1, 0, 0, 0])
    with pytest.raises(ValueError, match="weights_b has a NaN"):
        sc.objective(a, b, [0, 1, 0, 0], [np.nan, 0, 0, 0])


def test_violation_is_equation_6():
    assert sc.constraint_violation([0.5, 0.5], [1.0]) == 0.0
    assert sc.constraint_violation([0.5, 1.0], [0.0, 0.0]) == pytest.approx(0.25 + 1.0)


def test_feasibility_covers_bounds_and_sums():
    assert sc.is_feasible([0.5, 0.5], [1.0, 0.0])
    assert not sc.is_feasible([1.5, -0.5], [1.0, 0.0], tolerance=1.0)
    assert sc.is_feasible([0.5, 0.5001], [1.0], tolerance=1e-6)
    assert not sc.is_feasible([0.5, 0.5001], [1.0], tolerance=1e-9)


def test_separation_is_a_lower_bound_for_every_direction(tetra_a, separate_b):
    a, b = sc.ConvexPolyhedron(tetra_a), sc.ConvexPolyhedron(separate_b)
    assert sc.separation(a, b, [0, -1, 0]) == 1.0
    rng = np.random.default_rng(1)
    for direction in rng.normal(size=(200, 3)):
        assert sc.separation(a, b, direction) <= 1.0 + 1e-15
    with pytest.raises(ValueError, match="nonzero"):
        sc.separation(a, b, [0, 0, 0])


def test_projection_onto_the_simplex():
    np.testing.assert_allclose(sc.project_onto_simplex([2.0, -1.0, 0.5]), [1, 0, 0])
    np.testing.assert_allclose(sc.project_onto_simplex([0.5, 0.5, 0.5]), [1 / 3] * 3)
