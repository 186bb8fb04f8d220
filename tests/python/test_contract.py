"""The contract suite: every method in ``sc.METHODS``, every query it answers, on the paper's
pairs, the hard cases and seeded random pairs, against the tests' own exact reference."""

import pytest
from contract import (
    CASE_SETS,
    TOLERANCES,
    ask,
    assert_identical,
    cases,
    check_contract,
    pair_scale,
    size_accuracy,
)

import swarmcollide as sc

PARAMETERS = [
    pytest.param(method, kind, tolerance, case_set, case,
                 id=f"{method}-{kind}-{tolerance:g}-{case.name}")
    for method, info in sc.METHODS.items()
    for kind in info.queries
    for tolerance in TOLERANCES
    for case_set in CASE_SETS
    for case in cases(case_set)
]


@pytest.mark.parametrize(("method", "kind", "tolerance", "case_set", "case"), PARAMETERS)
def test_contract(method, kind, tolerance, case_set, case):
    query = sc.query(method, tolerance=tolerance)
    scale = pair_scale(case.a, case.b, tolerance)
    r = ask(query, kind, case.a, case.b)
    check_contract(kind, method, case.a, case.b, r, case.distance, case.signed_distance, scale)
    if kind == "collide":
        assert query.collide(case.a, case.b) == r.colliding
        # Every unproven verdict goes to "exact", so a verdict is always certified (and then, by
        # the contract, right); a proven one stands.
        assert r.certified
        own = query.collision(case.a, case.b, escalate=False)
        if own.certified:
            assert_identical(r, own)
        else:
            assert (r.method, r.escalated_from) == ("exact", method)
    else:
        accuracy = size_accuracy(method, case_set, scale, tolerance)
        value = case.signed_distance if kind == "signed_distance" else case.distance
        if accuracy is not None:
            assert abs(r.distance - value) <= accuracy
    assert_identical(r, ask(query, kind, case.a, case.b))


def test_every_method_answers_collide_and_the_table_says_what_else():
    assert set(sc.METHODS) == {"dual", "ipso", "pso", "penalty", "exact", "fcl", "libccd"}
    assert next(iter(sc.METHODS)) == "dual"
    for info in sc.METHODS.values():
        assert "collide" in info.queries
        assert set(info.queries) <= {"distance", "collide", "signed_distance"}
    assert sc.METHODS["libccd"].queries == ("collide", "signed_distance")
    for method in ("ipso", "pso", "penalty"):
        assert "signed_distance" not in sc.METHODS[method].queries
        assert not sc.METHODS[method].always_certified
