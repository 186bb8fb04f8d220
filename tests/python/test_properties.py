"""Properties over generated bodies (Hypothesis, bounded sizes, derandomised for CI)."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from oracle import exact_distance

import swarmcollide as sc

coordinates = st.floats(min_value=-10, max_value=10, allow_nan=False, width=64)
bodies = st.integers(min_value=1, max_value=6).flatmap(
    lambda n: arrays(np.float64, (n, 3), elements=coordinates)
)
property_settings = settings(max_examples=40, deadline=None, derandomize=True)


@property_settings
@given(a=bodies, b=bodies, method=st.sampled_from(["ipso", "pso", "penalty", "fcl", "fcl-indep"]))
def test_every_answer_brackets_the_exact_distance(a, b, method):
    exact = exact_distance(a, b)
    r = sc.distance(a, b, method=method, seed=0)
    slack = 1e-9 * max(1.0, np.abs(np.vstack([a, b])).max())
    assert r.lower_bound <= exact + slack
    assert exact <= r.distance + slack
    np.testing.assert_allclose(r.point_b - r.point_a, b.T @ r.weights_b - a.T @ r.weights_a, atol=slack)


@property_settings
@given(a=bodies, b=bodies)
def test_exact_distance_is_symmetric_and_matches_the_reference(a, b):
    forward = sc.distance(a, b, method="fcl")
    backward = sc.distance(b, a, method="fcl")
    size = max(1.0, float(np.ptp(np.vstack([a, b]), axis=0).max()))
    assert abs(forward.distance - backward.distance) <= 1e-9 * size
    assert abs(forward.distance - exact_distance(a, b)) <= 1e-9 * size
