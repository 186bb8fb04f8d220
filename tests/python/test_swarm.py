"""The swarm solvers: the paper's improved PSO and its linear-inertia baseline."""

import math
import os
import subprocess
import sys

import numpy as np
import pytest
from oracle import exact_distance, random_pair

import swarmcollide as sc

SWARMS = ["ipso", "pso"]
HANDLINGS = ["projection", "feasibility"]


def assert_answer_is_consistent(a, b, r):
    """What every answer must satisfy, however good it is."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.all(r.weights_a >= 0) and np.all(r.weights_b >= 0)
    assert r.weights_a.sum() == pytest.approx(1, abs=1e-14)
    assert r.weights_b.sum() == pytest.approx(1, abs=1e-14)
    np.testing.assert_allclose(r.point_a, a.T @ r.weights_a, atol=1e-13)
    np.testing.assert_allclose(r.point_b, b.T @ r.weights_b, atol=1e-13)
    assert r.distance == pytest.approx(np.linalg.norm(r.point_b - r.point_a), abs=1e-14)
    assert 0 <= r.lower_bound <= r.distance
    assert len(r.history) == r.iterations + 1
    assert np.all(np.diff(r.history) <= 0) and r.history[-1] == r.distance


@pytest.mark.parametrize("method", SWARMS)
def test_paper_collision_case(method, tetra_a, touching_b):
    r = sc.distance(tetra_a, touching_b, method=method, seed=0)
    assert_answer_is_consistent(tetra_a, touching_b, r)
    assert r.distance <= 1e-6
    assert r.colliding and r.certified
    assert r.method == method
    assert sc.collide(tetra_a, touching_b, method=method)


@pytest.mark.parametrize("method", SWARMS)
def test_paper_separation_case(method, tetra_a, separate_b):
    r = sc.distance(tetra_a, separate_b, method=method, seed=0)
    assert_answer_is_consistent(tetra_a, separate_b, r)
    assert r.distance == pytest.approx(1, abs=1e-4)
    assert r.weights_a[1] == pytest.approx(1, abs=1e-4)
    assert r.weights_b[0] == pytest.approx(1, abs=1e-4)
    assert not r.colliding and r.certified
    assert r.status == "converged"
    assert not sc.collide(tetra_a, separate_b, method=method)


@pytest.mark.parametrize("handling", HANDLINGS)
@pytest.mark.parametrize("method", SWARMS)
def test_bounds_hold_on_random_pairs_against_an_exact_reference(method, handling):
    rng = np.random.default_rng(2024)
    for trial in range(12):
        a, b = random_pair(rng, points=5)
        exact = exact_distance(a, b)
        r = sc.distance(a, b, method=method, constraint_handling=handling, seed=trial)
        assert_answer_is_consistent(a, b, r)
        slack = 1e-12 * (1 + np.abs(np.vstack([a, b])).max())
        assert r.lower_bound <= exact + slack
        assert exact <= r.distance + slack
        if r.colliding:
            assert exact <= 1e-6 + slack
        if r.certified and not r.colliding:
            assert exact > 1e-6


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


@pytest.mark.parametrize("handling", HANDLINGS)
@pytest.mark.parametrize("method", SWARMS)
def test_the_seed_decides_the_result(method, handling, tetra_a):
    rng = np.random.default_rng(7)
    b = rng.normal(size=(6, 3)) + [2, 0, 0]
    first = sc.distance(tetra_a, b, method=method, constraint_handling=handling, seed=11)
    again = sc.distance(tetra_a, b, method=method, constraint_handling=handling, seed=11)
    other = sc.distance(tetra_a, b, method=method, constraint_handling=handling, seed=12)
    np.testing.assert_array_equal(first.history, again.history)
    np.testing.assert_array_equal(first.weights_a, again.weights_a)
    assert not np.array_equal(first.history, other.history)


def test_zero_tolerance_runs_the_whole_budget(tetra_a, separate_b):
    r = sc.distance(tetra_a, separate_b, tolerance=0, max_iterations=30, swarm_size=10)
    assert r.iterations == 30
    assert r.evaluations == 10 * 31
    assert r.status == "max_iterations"
    assert len(r.history) == 31


def test_parameters_reach_the_solver(tetra_a, separate_b):
    short = sc.distance(tetra_a, separate_b, max_iterations=0, seed=3)
    assert short.iterations == 0 and short.evaluations == 40
    small = sc.distance(tetra_a, separate_b, swarm_size=5, max_iterations=2, tolerance=0)
    assert small.evaluations == 5 * 3


def test_degenerate_bodies_are_solved():
    r = sc.distance([[0, 0, 3]], [[-1, 0, 0], [1, 0, 0]], seed=0)
    assert r.distance == pytest.approx(3, abs=1e-6) and r.certified
    flat = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]
    assert sc.collide(flat, [[0.5, 0.5, 0]])


@pytest.mark.parametrize(
    ("parameters", "error", "message"),
    [
        ({"method": "gjk"}, ValueError, "unknown method 'gjk'; choose one of ipso, pso"),
        ({"method": 3}, TypeError, "method must be a string"),
        ({"seed": -1}, ValueError, "seed"),
        ({"seed": 1.5}, TypeError, "seed must be an integer"),
        ({"swarm_size": 1}, ValueError, "swarm_size must be at least 2"),
        ({"swarm_size": 4.5}, TypeError, "swarm_size must be an integer"),
        ({"swarm_size": True}, TypeError, "swarm_size must be an integer"),
        ({"max_iterations": -1}, ValueError, "max_iterations"),
        ({"w_min": 0.95}, ValueError, "w_min must not exceed w_max"),
        ({"w_max": "0.9"}, TypeError, "w_max must be a real number"),
        ({"tolerance": -1e-3}, ValueError, "tolerance"),
        ({"tolerance": math.nan}, ValueError, "tolerance"),
        ({"velocity_limit": 0.0}, ValueError, "velocity_limit"),
        ({"feasibility_tolerance": math.inf}, ValueError, "feasibility_tolerance"),
        ({"constraint_handling": "penalty"}, ValueError, "constraint_handling"),
        ({"c1": 2.0}, ValueError, "c1 does not apply to method='ipso'"),
        ({"method": "pso", "c2": -1.0}, ValueError, "c2"),
    ],
)
def test_bad_parameters_raise_a_clear_error(parameters, error, message, tetra_a, separate_b):
    with pytest.raises(error, match=message):
        sc.distance(tetra_a, separate_b, **parameters)


def test_unknown_keyword_is_a_type_error(tetra_a, separate_b):
    with pytest.raises(TypeError, match="swarmsize"):
        sc.distance(tetra_a, separate_b, swarmsize=10)


@pytest.mark.parametrize("argument", ["a", "b"])
def test_bad_bodies_are_named(argument, tetra_a):
    bodies = {"a": tetra_a, "b": tetra_a}
    bodies[argument] = [[0, 0, np.nan]]
    with pytest.raises(ValueError, match=f"^{argument}: points has a NaN"):
        sc.distance(bodies["a"], bodies["b"])


def test_result_repr_shows_the_answer(tetra_a, separate_b):
    text = repr(sc.distance(tetra_a, separate_b))
    assert text.startswith("DistanceResult(method='ipso', distance=1")
    assert "certified=True" in text and "status='converged'" in text


_SOLVE = """
import numpy as np
import swarmcollide as sc
rng = np.random.default_rng(5)
a, b = rng.normal(size=(12, 3)), rng.normal(size=(17, 3)) + [3, 0, 0]
r = sc.distance(a, b, seed=4, tolerance=0)
print(r.distance.hex(), *(float(w).hex() for w in np.concatenate([r.weights_a, r.weights_b])))
"""


def _solve_with_kernels(isa):
    """A seeded solve in a fresh interpreter whose SWARMCOLLIDE_ISA is `isa` (None: unset)."""
    env = {k: v for k, v in os.environ.items() if k != "SWARMCOLLIDE_ISA"}
    if isa is not None:
        env["SWARMCOLLIDE_ISA"] = isa
    return subprocess.run([sys.executable, "-c", _SOLVE], env=env, capture_output=True, text=True)


def test_forcing_the_baseline_kernels_changes_no_bit():
    widest, baseline = _solve_with_kernels(None), _solve_with_kernels("baseline")
    assert widest.returncode == 0 and baseline.returncode == 0, widest.stderr + baseline.stderr
    assert baseline.stdout == widest.stdout


def test_an_unknown_instruction_set_is_refused():
    run = _solve_with_kernels("sse9")
    assert run.returncode != 0
    assert "SWARMCOLLIDE_ISA=sse9" in run.stderr
