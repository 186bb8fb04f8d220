"""Batch queries: the same answers as one query at a time, whatever the thread count."""

import numpy as np
import pytest

import swarmcollide as sc

TETRA = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)


@pytest.fixture
def pairs():
    rng = np.random.default_rng(12)
    As = rng.normal(size=(40, 6, 3))
    Bs = rng.normal(size=(40, 6, 3)) + rng.uniform(-3, 3, size=(40, 1, 3))
    return As, Bs


@pytest.mark.parametrize("method", ["ipso", "dual", "fcl"])
def test_each_pair_is_the_single_query_with_its_derived_seed(method, pairs):
    As, Bs = pairs
    batch = sc.distance_many(As, Bs, method=method, seed=5, threads=2)
    assert len(batch) == 40
    assert batch.point_a.shape == (40, 3) and batch.colliding.dtype == bool
    for i in range(0, 40, 7):
        single = sc.distance(As[i], Bs[i], method=method, seed=sc.pair_seed(5, i))
        assert batch.distance[i] == single.distance
        assert batch.lower_bound[i] == single.lower_bound
        np.testing.assert_array_equal(batch.point_b[i], single.point_b)
        assert batch.certified[i] == single.certified


def test_results_do_not_depend_on_the_thread_count(pairs):
    As, Bs = pairs
    one = sc.distance_many(As, Bs, threads=1, max_iterations=20)
    two = sc.distance_many(As, Bs, threads=2, max_iterations=20)
    three = sc.distance_many(As, Bs, threads=3, max_iterations=20)
    for other in (two, three):
        np.testing.assert_array_equal(one.distance, other.distance)
        np.testing.assert_array_equal(one.point_a, other.point_a)


def test_sequences_of_bodies_of_different_sizes():
    As = [TETRA, sc.ConvexPolyhedron(TETRA * 2), [[0, 0, 5]]]
    Bs = [TETRA + [3, 0, 0], TETRA.tolist(), np.array([[0, 0, 0.0]])]
    r = sc.distance_many(As, Bs, method="fcl")
    np.testing.assert_allclose(r.distance, [2, 0, 5], atol=1e-9)
    np.testing.assert_array_equal(r.colliding, [False, True, False])


def test_collide_many_escalates_unproven_verdicts():
    near = TETRA + [1 + 1e-7, 0, 0]
    r = sc.collide_many([TETRA, TETRA], [near, TETRA + 0.1], max_iterations=0)
    np.testing.assert_array_equal(r.colliding, [True, True])
    assert r.escalated[0]
    raw = sc.collide_many([TETRA], [near], max_iterations=0, escalate=False)
    assert not raw.colliding[0] and not raw.escalated[0]


def test_empty_batch():
    r = sc.distance_many(np.zeros((0, 4, 3)), np.zeros((0, 4, 3)))
    assert len(r) == 0 and r.point_a.shape == (0, 3)


@pytest.mark.parametrize(
    ("As", "Bs", "threads", "error", "message"),
    [
        ([TETRA, TETRA], [TETRA], None, ValueError, "same length, got 2 and 1"),
        ([TETRA, [[0, 0, np.nan]]], [TETRA, TETRA], None, ValueError, r"As\[1\]: points has a NaN"),
        (np.full((2, 4, 3), np.inf), np.zeros((2, 4, 3)), None, ValueError, r"As\[0\]"),
        ([TETRA], [[[1, 2]]], None, ValueError, r"Bs\[0\] must have shape \(n, 3\)"),
        (np.zeros((2, 4, 2)), np.zeros((2, 4, 3)), None, ValueError, r"\(m, n, 3\)"),
        (5, [TETRA], None, TypeError, "As must be a sequence"),
        ([TETRA], [TETRA], 0, ValueError, "threads must be at least 1"),
        ([TETRA], [TETRA], 1.5, TypeError, "threads must be an integer"),
    ],
)
def test_bad_batches_raise_a_clear_error(As, Bs, threads, error, message):
    with pytest.raises(error, match=message):
        sc.distance_many(As, Bs, threads=threads)


def test_repr():
    r = sc.collide_many([TETRA], [TETRA + 0.1])
    assert repr(r) == "BatchResult(1 pairs, 1 colliding, 1 certified)"
