"""The primal swarms: the paper's improved PSO ("ipso") and its linear-inertia baseline ("pso")."""

import math

import numpy as np
import pytest
from contract import check_contract, pair_scale
from oracle import exact_distance, exact_signed_distance, random_pair

import swarmcollide as sc

SWARMS = ["ipso", "pso"]
HANDLINGS = ["projection", "feasibility"]


@pytest.mark.parametrize("rank", [1, 2, 20, 39, 40])
def test_rank_adaptive_coefficients_follow_equations_8_and_9(rank):
    c = sc.rank_adaptive_coefficients(rank, 40, w_min=0.4, w_max=0.9)
    w = 0.4 + (0.9 - 0.4) * (40 - rank) / 39
    assert c.w == pytest.approx(w, abs=1e-15)
    assert c.c1 == c.c2 == pytest.approx((w + 1 + 2 * math.sqrt(w)) / 2, abs=1e-15)


def test_rank_outside_the_swarm_is_refused():
    with pytest.raises(ValueError, match="rank"):
        sc.rank_adaptive_coefficients(0, 40)


def test_linear_decreasing_inertia_follows_equation_7():
    assert sc.linear_decreasing_inertia(0, 200) == pytest.approx(0.9)
    assert sc.linear_decreasing_inertia(50, 200) == pytest.approx(0.775)
    assert sc.linear_decreasing_inertia(200, 200) == pytest.approx(0.4)


@pytest.mark.parametrize("method", SWARMS)
def test_the_papers_separate_pair_reaches_table_2(method, tetra_a, separate_b):
    r = sc.distance(tetra_a, separate_b, method=method)
    assert r.distance == pytest.approx(1, abs=1e-9)
    assert r.weights_a[1] == pytest.approx(1, abs=1e-9)
    assert r.weights_b[0] == pytest.approx(1, abs=1e-9)
    assert r.status == "converged" and r.certified and not r.colliding
    assert len(r.history) == r.iterations + 1 and r.history[-1] == r.distance


@pytest.mark.parametrize("handling", HANDLINGS)
@pytest.mark.parametrize("method", SWARMS)
def test_both_constraint_handlings_keep_the_contract(method, handling):
    rng = np.random.default_rng(2024)
    for trial in range(8):
        a, b = random_pair(rng, points=5)
        r = sc.distance(a, b, method=method, constraint_handling=handling, seed=trial)
        check_contract("distance", method, a, b, r, exact_distance(a, b),
                       exact_signed_distance(a, b), pair_scale(a, b))
        assert np.all(np.diff(r.history) <= 0)


@pytest.mark.parametrize("handling", HANDLINGS)
@pytest.mark.parametrize("method", SWARMS)
def test_the_seed_decides_the_result(method, handling, tetra_a):
    b = np.random.default_rng(7).normal(size=(6, 3)) + [2, 0, 0]
    keywords = dict(method=method, constraint_handling=handling, tolerance=0, max_iterations=30)
    first = sc.distance(tetra_a, b, seed=11, **keywords)
    again = sc.distance(tetra_a, b, seed=11, **keywords)
    other = sc.distance(tetra_a, b, seed=12, **keywords)
    np.testing.assert_array_equal(first.history, again.history)
    np.testing.assert_array_equal(first.weights_a, again.weights_a)
    assert not np.array_equal(first.history, other.history)


@pytest.mark.parametrize("method", SWARMS)
def test_zero_tolerance_runs_the_whole_budget(method, tetra_a, separate_b):
    r = sc.distance(
        tetra_a, separate_b, method=method, tolerance=0, max_iterations=30, swarm_size=10
    )
    assert r.iterations == 30
    assert r.evaluations == 10 * 31
    assert len(r.history) == 31


def test_parameters_reach_the_solver(tetra_a, separate_b):
    short = sc.distance(tetra_a, separate_b, method="ipso", max_iterations=0, seed=3)
    assert short.iterations == 0 and short.evaluations == 40
    small = sc.distance(
        tetra_a, separate_b, method="ipso", swarm_size=5, max_iterations=2, tolerance=0
    )
    assert small.evaluations == 5 * 3
    rng = np.random.default_rng(9)
    a, b = rng.normal(size=(7, 3)), rng.normal(size=(6, 3)) + [2, 0, 0]
    keywords = dict(method="pso", tolerance=0, max_iterations=10)
    assert not np.array_equal(sc.distance(a, b, c1=0.5, **keywords).history,
                              sc.distance(a, b, **keywords).history)
