"""Batch queries: each pair is the single query with its own seed, whatever the thread count and
however the batch is split; bad batches get errors that name the pair or body."""

import numpy as np
import pytest
from contract import TETRA

import swarmcollide as sc


@pytest.fixture
def pairs():
    rng = np.random.default_rng(12)
    As = rng.normal(size=(80, 6, 3))
    Bs = rng.normal(size=(80, 6, 3)) + rng.uniform(-3, 3, size=(80, 1, 3))
    return As, Bs


@pytest.mark.parametrize("method", ["ipso", "dual", "fcl"])
def test_each_pair_is_the_single_query_with_its_derived_seed(method, pairs):
    As, Bs = pairs
    batch = sc.distance_many(As, Bs, method=method, seed=5, threads=2)
    assert len(batch) == 80
    assert batch.point_a.shape == batch.direction.shape == (80, 3)
    assert batch.colliding.dtype == bool and batch.escalated.dtype == bool
    for i in range(0, 80, 9):
        single = sc.distance(As[i], Bs[i], method=method, seed=sc.pair_seed(5, i))
        assert batch.distance[i] == single.distance
        assert batch.lower_bound[i] == single.lower_bound
        np.testing.assert_array_equal(batch.point_b[i], single.point_b)
        np.testing.assert_array_equal(batch.direction[i], single.direction)
        assert batch.certified[i] == single.certified
        assert batch.iterations[i] == single.iterations
        assert batch.escalated[i] == (single.escalated_from is not None)


def test_collide_and_signed_distance_batches_are_their_single_queries(pairs):
    As, Bs = pairs
    verdicts = sc.collide_many(As, Bs, method="pso", seed=2, threads=2)
    depths = sc.signed_distance_many(As, Bs, threads=2)
    for i in range(0, 80, 11):
        decided = sc.collision(As[i], Bs[i], method="pso", seed=sc.pair_seed(2, i))
        assert verdicts.colliding[i] == decided.colliding
        assert verdicts.escalated[i] == (decided.escalated_from is not None)
        single = sc.signed_distance(As[i], Bs[i], seed=sc.pair_seed(0, i))
        assert depths.distance[i] == single.distance


@pytest.mark.parametrize("method", ["ipso", "dual"])
def test_results_do_not_depend_on_the_thread_count(method, pairs):
    As, Bs = pairs
    one = sc.distance_many(As, Bs, method=method, threads=1, max_iterations=20)
    for threads in (2, 3, None):
        other = sc.distance_many(As, Bs, method=method, threads=threads, max_iterations=20)
        np.testing.assert_array_equal(one.distance, other.distance)
        np.testing.assert_array_equal(one.point_a, other.point_a)
        np.testing.assert_array_equal(one.iterations, other.iterations)


def test_parts_told_their_first_index_answer_as_the_whole(pairs):
    As, Bs = pairs
    whole = sc.distance_many(As, Bs, method="ipso", seed=9, threads=2)
    for cut in (1, 33, 64):
        head = sc.distance_many(As[:cut], Bs[:cut], method="ipso", seed=9)
        tail = sc.distance_many(As[cut:], Bs[cut:], method="ipso", seed=9, first_index=cut)
        joined = np.concatenate([head.distance, tail.distance])
        np.testing.assert_array_equal(joined, whole.distance)
        np.testing.assert_array_equal(np.concatenate([head.point_b, tail.point_b]), whole.point_b)


def test_sequences_of_bodies_of_different_sizes_and_stacks_agree(pairs):
    As = [TETRA, sc.ConvexPolyhedron(TETRA * 2), [[0, 0, 5]]]
    Bs = [TETRA + [3, 0, 0], TETRA.tolist(), np.array([[0, 0, 0.0]])]
    r = sc.distance_many(As, Bs, method="fcl")
    np.testing.assert_allclose(r.distance, [2, 0, 5], atol=1e-12)
    np.testing.assert_array_equal(r.colliding, [False, True, False])
    stacks_a, stacks_b = pairs
    from_stacks = sc.distance_many(stacks_a, stacks_b, method="ipso", seed=1)
    from_lists = sc.distance_many(list(stacks_a), list(stacks_b), method="ipso", seed=1)
    np.testing.assert_array_equal(from_stacks.distance, from_lists.distance)


def test_collide_many_escalates_unproven_verdicts_only_when_asked():
    near = TETRA + [1 + 1e-10, 0, 0]  # within the tolerance; the swarm cannot tell
    r = sc.collide_many([TETRA, TETRA], [near, TETRA + 0.1], method="ipso", max_iterations=0)
    np.testing.assert_array_equal(r.colliding, [True, True])
    assert r.escalated[0] and r.certified.all()
    raw = sc.collide_many([TETRA], [near], method="ipso", max_iterations=0, escalate=False)
    assert not raw.escalated[0] and not raw.certified[0]


def test_empty_batch():
    r = sc.distance_many(np.zeros((0, 4, 3)), np.zeros((0, 4, 3)))
    assert len(r) == 0 and r.point_a.shape == (0, 3)


def test_the_lowest_failing_pair_is_reported(pairs):
    As, Bs = pairs
    As, Bs = As.copy(), Bs.copy()
    for bad in (5, 40):  # bodies whose distance exceeds the double range
        As[bad], Bs[bad] = 1.5e308, -1.5e308
    for threads in (1, 2, 4):
        with pytest.raises(ValueError, match=r"^pair 5: "):
            sc.distance_many(As, Bs, threads=threads)
        with pytest.raises(ValueError, match=r"^pair 1005: "):
            sc.collide_many(As, Bs, threads=threads, first_index=1000)


@pytest.mark.parametrize(
    ("As", "Bs", "keywords", "error", "message"),
    [
        ([TETRA, TETRA], [TETRA], {}, ValueError, "same length, got 2 and 1"),
        ([TETRA, [[0, 0, np.nan]]], [TETRA, TETRA], {}, ValueError, r"As\[1\]: points has a NaN"),
        ([TETRA, [[0, 0, np.nan]]], [TETRA, TETRA], {"first_index": 7}, ValueError, r"As\[8\]: "),
        (np.full((2, 4, 3), np.inf), np.zeros((2, 4, 3)), {}, ValueError, r"As\[0\]"),
        ([TETRA], [[[1, 2]]], {}, ValueError, r"Bs\[0\] must be an \(n, 3\) array"),
        (np.zeros((2, 4, 2)), np.zeros((2, 4, 3)), {}, ValueError, r"\(m, n, 3\)"),
        (np.zeros((2, 0, 3)), np.zeros((2, 0, 3)), {}, ValueError, r"\(m, n, 3\) with n >= 1"),
        (np.ones((2, 4, 3), dtype=bool), np.zeros((2, 4, 3)), {}, TypeError, "As must hold real"),
        (np.zeros((2, 4, 3)), np.zeros((2, 4, 3), dtype=complex), {}, TypeError, "Bs must hold"),
        (np.zeros((2, 4, 3), dtype="U1"), np.zeros((2, 4, 3)), {}, TypeError, "As must hold real"),
        (5, [TETRA], {}, TypeError, "As must be a sequence"),
        ("bodies", [TETRA], {}, TypeError, "As must be a sequence"),
        ([TETRA], [TETRA], {"threads": 0}, ValueError, r"threads must be in \[1, 1024\]"),
        ([TETRA], [TETRA], {"threads": 2**31}, ValueError, r"threads must be in \[1, 1024\]"),
        ([TETRA], [TETRA], {"threads": 1.5}, TypeError, "threads must be an integer or None"),
        ([TETRA], [TETRA], {"threads": True}, TypeError, "threads must be an integer or None"),
        ([TETRA], [TETRA], {"first_index": -1}, ValueError, "first_index must be a nonnegative"),
        ([TETRA], [TETRA], {"method": "libccd"}, ValueError, "distance is not available"),
    ],
)
def test_bad_batches_raise_a_clear_error(As, Bs, keywords, error, message):
    with pytest.raises(error, match=message):
        sc.distance_many(As, Bs, **keywords)


def test_the_most_threads_are_no_more_than_the_pairs():
    r = sc.distance_many([TETRA, TETRA], [TETRA + 2, TETRA + 3], threads=1024)
    assert len(r) == 2 and r.certified.all()


def test_repr():
    r = sc.collide_many([TETRA], [TETRA + 0.1])
    assert repr(r) == "BatchResult(1 pairs, 1 colliding, 1 certified)"
