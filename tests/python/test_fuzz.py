"""The bounded fuzz suite and the scale-invariance property, both run in sandboxed children.

The corpus, oracle and judge are those of the census (tests/fuzz/census.py); here a few hundred
cases of another corpus seed and a derandomised Hypothesis property keep ``make test`` short. The
first tests check the suite itself: a judge or sandbox that never fails would pass anything.
"""

from __future__ import annotations

import os
import signal
import time

import numpy as np
import pytest
from fuzz_api import METHODS
from fuzz_cases import CORPUS_METHODS, Case, corpus, pair
from fuzz_judge import category_of, compare_scales, judge_single, run_case, scale_problems
from hypothesis import Phase, given, settings
from hypothesis import strategies as st
from sandbox import CRASHED, HUNG, RAISED, Sandbox

FUZZ_SEED = 1  # the census's corpus is seed 0
FUZZ_CASES = 300
TIMEOUT = 10.0
SINGLE_CALLS = [(q, m) for q in ("distance", "signed_distance", "collide") for m in METHODS[q]]
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)


@pytest.fixture(scope="module")
def sandbox():
    with Sandbox(parallel=2) as box:
        yield box


# ----- the suite itself ------------------------------------------------------------------------


def test_the_corpus_is_reproducible_and_covers_every_query_and_method():
    first, again = corpus(0, 300), corpus(0, 300)
    for one, other in zip(first, again):
        assert repr(one) == repr(other)
    covered = {(case.query, case.method) for case in corpus(0, 2000)}
    assert covered >= {(query, method) for query, methods in CORPUS_METHODS.items()
                       for method in methods}  # fmt: skip


def answer_like(**fields):
    result = {
        "distance": 2.0, "lower_bound": 2.0, "point_a": np.array([1.0, 0.5, 0.5]),
        "point_b": np.array([3.0, 0.5, 0.5]), "direction": np.array([1.0, 0, 0]),
        "colliding": False, "certified": True, "status": "converged", "method": "fcl",
        "escalated_from": "",
    }  # fmt: skip
    result.update(fields)
    return result


@pytest.mark.parametrize(
    ("fields", "problem"),
    [
        ({}, None),
        ({"lower_bound": 2.1}, "lower bound"),
        ({"distance": 1.9, "point_b": np.array([2.9, 0.5, 0.5])}, "below the true"),
        ({"point_a": np.array([1.5, 0.5, 0.5]), "distance": 1.5, "lower_bound": 1.5},
         "off its body"),
        ({"colliding": True}, "verdict"),
        ({"distance": 2.5, "point_b": np.array([3.5, 0.5, 0.5])}, "converged fcl distance"),
    ],
)
def test_the_judge_finds_what_is_wrong(fields, problem):
    problems, _ = judge_single("distance", CUBE, CUBE + [3, 0, 0], answer_like(**fields))
    if problem is None:
        assert problems == []
    else:
        assert any(problem in p for p in problems), problems


def test_the_judge_compares_a_swarms_proven_verdicts_across_scales():
    # The cubes 2 apart, the second call 4 times larger: a swarm that proved them apart at one
    # scale and nothing at the other (colliding, its upper bound far above the tolerance) is
    # consistent; one that proved contact (an upper bound of 0) against apart is not.
    far = CUBE + [3, 0, 0]
    case = Case("judge", "invariance", "distance", "penalty", CUBE, far, scale=4.0)
    apart = answer_like(method="penalty", certified=False, status="max_iterations",
                        lower_bound=1.5, distance=2.5)  # fmt: skip
    unproven = dict(apart, colliding=True, lower_bound=0.0)
    contact = dict(unproven, distance=0.0)

    def scaled(answer):
        return dict(answer, distance=4 * answer["distance"], lower_bound=4 * answer["lower_bound"])

    assert compare_scales(case, CUBE, far, [unproven, scaled(apart)]) == []
    assert compare_scales(case, CUBE, far, [apart, scaled(unproven)]) == []
    assert any("colliding" in p for p in compare_scales(case, CUBE, far, [contact, scaled(apart)]))
    precise = Case("judge", "invariance", "distance", "exact", CUBE, far, scale=4.0)
    exact = dict(apart, method="exact", certified=True)
    assert any("colliding" in p for p in compare_scales(
        precise, CUBE, far, [dict(exact, colliding=True), scaled(exact)]))


def segfault() -> None:
    os.kill(os.getpid(), signal.SIGSEGV)


def sleep_long() -> None:
    time.sleep(60)


def divide_by_zero() -> float:
    return 1 / 0


def test_the_sandbox_reports_crashes_hangs_and_exceptions(sandbox):
    assert sandbox.run(segfault).kind == CRASHED
    assert sandbox.run(sleep_long, timeout=0.5).kind == HUNG
    raised = sandbox.run(divide_by_zero)
    assert (raised.kind, raised.error_type) == (RAISED, "ZeroDivisionError")
    assert sandbox.run(divmod, 7, 2).unwrap() == (3, 1)


# ----- the library -----------------------------------------------------------------------------


def test_bounded_fuzz(sandbox):
    tasks = ((index, run_case, (FUZZ_SEED, index)) for index in range(FUZZ_CASES))
    failures = []
    for index, outcome in sandbox.map(tasks, timeout=TIMEOUT):
        category, reason = category_of(outcome)
        if category not in ("ok", "uncertified"):
            failures.append(f"{FUZZ_SEED}:{index} {category}: {reason[:200]}")
    summary = "\n".join(sorted(failures, key=lambda f: int(f.split()[0].split(":")[1]))[:40])
    assert not failures, f"{len(failures)} of {FUZZ_CASES} cases fail:\n{summary}"


@settings(max_examples=60, deadline=None, derandomize=True, phases=[Phase.explicit, Phase.generate])
@given(
    pair_seed=st.integers(0, 2**32 - 1),
    exponent=st.floats(-100, 100),
    shift_exponent=st.none() | st.floats(-2, 6),
    query_method=st.sampled_from(SINGLE_CALLS),
)
def test_scaling_and_translating_changes_no_answer(
    sandbox, pair_seed, exponent, shift_exponent, query_method
):
    # Hypothesis does not shrink here: shrinking re-runs failing (possibly hanging) calls.
    rng = np.random.default_rng(pair_seed)
    a, b, note = pair(rng)
    s = 10.0**exponent
    shift = np.zeros(3)
    if shift_exponent is not None:
        direction = rng.normal(size=3)
        size = s * float(np.ptp(np.vstack([a, b]), axis=0).max())
        shift = size * 10.0**shift_exponent * direction / np.linalg.norm(direction)
    query, method = query_method
    case = Case("property", "invariance", query, method, a, b, note=note, scale=s, shift=shift)
    outcome = sandbox.run(scale_problems, case, timeout=TIMEOUT)
    assert not outcome.unwrap(), (note, outcome.value)
