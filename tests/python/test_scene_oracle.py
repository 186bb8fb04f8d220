"""Every broadphase through one seeded motion against brute force, and scenes with far bodies.

The long version of the motion runs in the census (``tests/fuzz/census.py --surface scene``).
"""

import numpy as np
import pytest

import swarmcollide as sc
from sandbox import RETURNED, Sandbox
from scene_cases import certified_wrong, far_body_answers, motion_mismatches


def test_every_broadphase_equals_brute_force_through_moves_teleports_far_jumps_and_churn():
    # 80 bodies in a box of side 4 (about 50 pairs within 0.1 a frame), 21 frames: teleports at
    # frames 10 and 20, a jump 1e3 away at 10 and back at 20, 4 bodies replaced at 7 and 14.
    problems = motion_mismatches(sc.BROADPHASES, seed=0, bodies=80, frames=21, side=4.0)
    assert not problems, f"{len(problems)} differences, the first: {problems[:5]}"


@pytest.mark.parametrize("method", sc.METHODS)
def test_certified_scene_rows_are_within_the_tolerance_of_the_exact_distance(method):
    # Scene(method="ipso").pairs_within certified 17 rows among 120 such bodies whose distance
    # was up to 1e-3 (not 1e-9) of the size from the exact one: certified meant the verdict only.
    problems = certified_wrong(method, seed=1, bodies=80, side=4.0)
    assert not problems, f"{len(problems)} rows, the first: {problems[:3]}"


def test_fcl_array_tree_is_refused_with_the_reason_and_the_alternative():
    # FCL's array tree rebalanced itself behind its object table and lost 284 of 391 pairs.
    assert "dynamic_aabb_tree_array" not in sc.BROADPHASES
    with pytest.raises(ValueError, match="loses pairs.*use 'dynamic_aabb_tree'"):
        sc.Scene(broadphase="dynamic_aabb_tree_array")


@pytest.fixture(scope="module")
def sandbox():
    with Sandbox(preload=("scene_cases",)) as box:
        yield box


@pytest.mark.parametrize("broadphase", sc.BROADPHASES)
def test_far_bodies_are_refused_with_the_range_never_a_crash_or_hang(sandbox, broadphase):
    # Scene.add of a batch with a body 1e155 away crashed in FCL's tree (its squared extents
    # overflow), and min_distance and nearest never returned.
    for how in ("batch", "alone", "moved"):
        for far in (1e155, 1e200, 1e300):
            outcome = sandbox.run(far_body_answers, broadphase, how, far, timeout=30)
            assert outcome.kind == RETURNED, f"{how} at {far:g}: {outcome.describe()}"
            refused = outcome.value.get("refused", "")
            assert "within 1e+150" in refused, f"{how} at {far:g}: {outcome.value}"
            assert ("poses[0] moves body 2" if how == "moved" else "bodies[") in refused
            assert outcome.value["bodies"] == (3 if how == "moved" else 2 if how == "alone" else 0)


@pytest.mark.parametrize("broadphase", sc.BROADPHASES)
def test_bodies_far_but_within_range_get_every_answer(sandbox, broadphase):
    for how in ("batch", "alone", "moved"):
        for far in (1e100, 1e149):
            outcome = sandbox.run(far_body_answers, broadphase, how, far, timeout=30)
            answers = outcome.unwrap()
            assert answers["colliding_pairs"] == ([], [], [])
            assert answers["pairs_within"] == ([[0, 1]], [2.5], [True])
            assert answers["min_distance"] == ([[0, 1]], [2.5], [True])
            pairs, distances, certified = answers["nearest"]
            assert pairs == [[0, 1], [0, 2], [2, 0], [2, 1]] and all(certified)
            np.testing.assert_allclose(distances, [2.5, far - 1, far - 1, far - 4.5], rtol=1e-12)
            assert answers["contacts"] == ([], [], [])


def test_pairs_within_refuses_distances_beyond_the_range():
    scene = sc.Scene()
    scene.add([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    with pytest.raises(ValueError, match=r"distance must be a number in \[0, 1e\+150\], got 1e\+200"):
        scene.pairs_within(1e200)
