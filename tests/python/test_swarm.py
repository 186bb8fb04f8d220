"""The primal swarms: the paper's improved PSO ("ipso") and its linear-inertia baseline ("pso")."""

import math
import os
import subprocess
import sys

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


_SOLVE = """
import numpy as np
import swarmcollide as sc
rng = np.random.default_rng(5)
a, b = rng.normal(size=(12, 3)), rng.normal(size=(17, 3)) + [3, 0, 0]
r = sc.distance(a, b, method="ipso", seed=4, tolerance=0)
print(r.distance.hex(), *(float(w).hex() for w in np.concatenate([r.weights_a, r.weights_b])))
# The exact paths' support scans of small bodies (geometry/column_scan.hpp) follow the same set.
for n in (4, 7, 8, 20, 32):
    p, q = rng.normal(size=(n, 3)), rng.normal(size=(n, 3)) + [0.5, 0, 0]
    for r in (sc.signed_distance(p, q), sc.distance(p, q + [3, 0, 0], tolerance=0)):
        print(*(float(x).hex() for x in [r.distance, r.lower_bound, *r.point_a, *r.point_b]))
"""


def _solve_with_kernels(isa):
    """A seeded solve in a fresh interpreter whose SWARMCOLLIDE_ISA is `isa` (None: unset)."""
    env = {k: v for k, v in os.environ.items() if k != "SWARMCOLLIDE_ISA"}
    if isa is not None:
        env["SWARMCOLLIDE_ISA"] = isa
    return subprocess.run([sys.executable, "-c", _SOLVE], env=env, capture_output=True, text=True)


def test_forcing_the_baseline_kernels_and_scans_changes_no_bit():
    widest, baseline = _solve_with_kernels(None), _solve_with_kernels("baseline")
    assert widest.returncode == 0 and baseline.returncode == 0, widest.stderr + baseline.stderr
    assert baseline.stdout == widest.stdout


def test_an_unknown_instruction_set_is_refused():
    run = _solve_with_kernels("sse9")
    assert run.returncode != 0
    assert "SWARMCOLLIDE_ISA=sse9" in run.stderr
