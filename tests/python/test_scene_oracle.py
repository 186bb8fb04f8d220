"""Every broadphase through one seeded motion against brute force, and scenes with far bodies.

The long version of the motion runs in the census (``tests/fuzz/census.py --corpus scene``).
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
            assert "stays within 1e+150" in refused, f"{how} at {far:g}: {outcome.value}"
            expected = {"batch": "poses[2] moves its body", "alone": "poses[0] moves its body",
                        "moved": "poses[0] moves body 2"}[how]  # fmt: skip
            assert f"{expected} along an axis by {far:g}" in refused
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


def test_bodies_reaching_far_from_their_own_origin_are_refused():
    with pytest.raises(ValueError, match=r"bodies\[0\] reaches from its own origin to 1.7\d*e\+155"):
        sc.Scene().add(np.eye(3) * 1e155)


def test_pairs_within_refuses_distances_beyond_the_range():
    scene = sc.Scene()
    scene.add([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    with pytest.raises(ValueError, match=r"distance must be a number in \[0, 1e\+150\], got 1e\+200"):
        scene.pairs_within(1e200)


def test_pair_lists_name_self_pairs_and_unknown_ids():
    scene = sc.Scene()
    scene.add(np.stack([np.eye(3)] * 2))
    for call in (scene.exclude, scene.include):
        with pytest.raises(ValueError, match=r"pairs lists \(0, 0\): a body is never paired"):
            call([0, 0])
        with pytest.raises(ValueError, match="no body with id 7"):
            call([0, 7])
    assert len(scene.colliding_pairs()) == 1


def test_group_and_mask_take_numpy_integers_and_name_arrays():
    scene = sc.Scene()
    assert scene.add(np.eye(3), group=np.int64(2), mask=np.array(3)).tolist() == [0]
    with pytest.raises(TypeError, match=r"group must be one integer bit mask .* shape \(2,\)"):
        scene.add(np.eye(3), group=np.array([1, 2]))


def test_an_empty_move_is_a_no_op():
    scene = sc.Scene()
    scene.add(np.eye(3))
    scene.set_poses([], [])
    scene.set_poses(np.array([], dtype=int), np.zeros((0, 4, 4)))
    with pytest.raises(ValueError, match=r"one pose per id \(got None for 1 ids\)"):
        scene.set_poses([0], None)


@pytest.mark.parametrize("call,message", [
    (lambda s: s.pairs_within("a"), "distance must be a real number, got str"),
    (lambda s: s.pairs_within(np.array([0.5])), "distance must be a real number, got ndarray"),
    (lambda s: s.pairs_within(1j), "distance must be a real number, got complex"),
    (lambda s: s.contacts("x"), "max_points must be an integer, got str"),
    (lambda s: s.contacts(2.5), "max_points must be an integer, got float"),
    (lambda s: s.nearest([0], k="2"), "k must be an integer, got str"),
    (lambda s: s.nearest([0], k=True), "k must be an integer, got bool"),
])  # fmt: skip
def test_query_arguments_of_the_wrong_type_are_named(call, message):
    scene = sc.Scene()
    scene.add(np.stack([np.eye(3)] * 2))
    with pytest.raises(TypeError, match=message):
        call(scene)


def test_query_arguments_take_numpy_scalars_and_name_their_range():
    scene = sc.Scene()
    scene.add(np.stack([np.eye(3)] * 2))
    assert len(scene.pairs_within(np.float64(0.5))) == len(scene.contacts(np.int64(2))) == 1
    assert len(scene.nearest([0], k=np.int32(1))) == 1
    with pytest.raises(ValueError, match=r"k must be at most 2\*\*31 - 1, got 1099511627776"):
        scene.nearest([0], k=2**40)


def test_a_rejected_rotation_prints_its_deviation_in_general_notation():
    pose = np.eye(4)
    pose[0, 0] = 1 + 3e-8
    with pytest.raises(ValueError, match=r"\|R\^T R - I\| = 6e-08, det R = 1.00000003\)"):
        sc.Scene().add(np.eye(3), pose)
