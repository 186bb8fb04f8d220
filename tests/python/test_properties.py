"""Properties over generated bodies (Hypothesis, bounded sizes, derandomised for CI): the contract
for every method and query against the exact reference, and answers that do not depend on the
unit of length or on the order of the bodies."""

import numpy as np
from contract import check_contract, pair_scale
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from oracle import exact_distance, exact_signed_distance

import swarmcollide as sc

coordinates = st.floats(min_value=-10, max_value=10, allow_nan=False, width=64)
bodies = st.integers(min_value=1, max_value=6).flatmap(
    lambda n: arrays(np.float64, (n, 3), elements=coordinates)
)
method_queries = st.sampled_from(
    [(method, kind) for method, info in sc.METHODS.items() for kind in info.queries]
)
property_settings = settings(max_examples=60, deadline=None, derandomize=True)


def ask(method, kind, a, b, **keywords):
    if kind == "collide":
        return sc.collision(a, b, method=method, **keywords)
    return getattr(sc, kind)(a, b, method=method, **keywords)


@property_settings
@given(a=bodies, b=bodies, method_query=method_queries)
def test_every_answer_keeps_the_contract(a, b, method_query):
    method, kind = method_query
    r = ask(method, kind, a, b)
    check_contract(kind, method, a, b, r, exact_distance(a, b), exact_signed_distance(a, b),
                   pair_scale(a, b))


@property_settings
@given(a=bodies, b=bodies, method=st.sampled_from(["dual", "exact", "fcl"]))
def test_certified_distances_are_symmetric(a, b, method):
    forward = sc.distance(a, b, method=method)
    backward = sc.distance(b, a, method=method)
    scale = pair_scale(a, b)
    assert forward.colliding == backward.colliding
    assert abs(forward.distance - backward.distance) <= scale.tolerance + scale.rounding


@property_settings
@given(
    a=bodies,
    b=bodies,
    method_query=method_queries,
    exponent=st.integers(min_value=-100, max_value=100),
)
def test_the_unit_of_length_changes_no_verdict(a, b, method_query, exponent):
    method, kind = method_query
    unit = ask(method, kind, a, b)
    s = 10.0**exponent
    scaled = ask(method, kind, a * s, b * s)
    assert scaled.colliding == unit.colliding
    # A distance of a swarm that stops at its budget (ipso, pso, penalty) is certified only where
    # the swarm reached the tolerance, and scaling by 10**k rounds the input differently, which
    # changes a swarm's path; its verdicts, and every answer of the exact methods, stay the same.
    if kind == "collide" or sc.METHODS[method].always_certified:
        assert scaled.certified == unit.certified
    scale = pair_scale(a, b)
    if sc.METHODS[method].always_certified:
        assert abs(scaled.distance / s - unit.distance) <= scale.tolerance + scale.rounding
