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


def test_rows_past_the_last_global_row_are_refused(pairs):
    # Row i is the global row first_index + i: rows past 2**64 - 1 wrapped, named and seeded as
    # the first global rows.
    As, Bs = pairs
    last = 2**64 - 1
    assert len(sc.distance_many(As[:2], Bs[:2], method="ipso", first_index=last - 1)) == 2
    assert len(sc.distance_many(As[:0], Bs[:0], first_index=last)) == 0
    message = (r"^first_index \+ the number of rows must be at most 2\*\*64 \(the rows are the "
               rf"global rows first_index, first_index \+ 1, ...\), got first_index {last - 1} "
               r"and 3 rows$")
    poses = np.tile(np.eye(4), (3, 1, 1))
    compound = sc.CompoundBody([sc.ConvexPolyhedron(TETRA)])
    for batch in (sc.distance_many, sc.collide_many, sc.signed_distance_many):
        for a, b, keywords in ((As[:3], Bs[:3], {}), (list(As[:3]), list(Bs[:3]), {}),
                               (TETRA, TETRA, {"poses_b": poses}),
                               ([compound] * 3, TETRA, {})):
            with pytest.raises(ValueError, match=message):
                batch(a, b, first_index=last - 1, **keywords)


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
        (5, [TETRA], {}, TypeError, "As must be a body .*, a sequence of bodies"),
        ("bodies", [TETRA], {}, TypeError, "As must be a body .*, a sequence of bodies"),
        ([TETRA], [TETRA], {"threads": 0}, ValueError, r"threads must be in \[1, 1024\]"),
        ([TETRA], [TETRA], {"threads": 2**31}, ValueError, r"threads must be in \[1, 1024\]"),
        ([TETRA], [TETRA], {"threads": 1.5}, TypeError, "threads must be an integer or None"),
        ([TETRA], [TETRA], {"threads": True}, TypeError, "threads must be an integer or None"),
        ([TETRA], [TETRA], {"first_index": -1}, ValueError, "first_index must be a nonnegative"),
        ([TETRA], [TETRA], {"first_index": 2**64}, ValueError, r"first_index .* below 2\*\*64"),
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


def random_transforms(count, seed, spread):
    """``count`` rigid (4, 4) transforms: random rotations, translations up to ``spread``."""
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(seed)
    poses = np.tile(np.eye(4), (count, 1, 1))
    poses[:, :3, :3] = Rotation.random(count, random_state=seed).as_matrix()
    poses[:, :3, 3] = rng.uniform(-spread, spread, size=(count, 3))
    return poses


@pytest.fixture
def posed():
    rng = np.random.default_rng(24)
    a = sc.ConvexPolyhedron(rng.normal(size=(30, 3)))
    b = sc.ConvexPolyhedron(rng.normal(size=(9, 3)))
    return a, b, random_transforms(60, 1, 0.5), random_transforms(60, 2, 4.0)


def assert_same(x, y):
    for field in ("distance", "lower_bound", "point_a", "point_b", "direction", "colliding",
                  "certified", "iterations", "escalated", "part_a", "part_b"):
        np.testing.assert_array_equal(getattr(x, field), getattr(y, field), err_msg=field)


@pytest.mark.parametrize("batch", [sc.distance_many, sc.collide_many, sc.signed_distance_many])
def test_a_single_body_serves_every_row(batch, posed):
    a, b, poses_a, poses_b = posed
    listed = batch([a] * 60, [b] * 60, poses_a=poses_a, poses_b=poses_b, threads=2)
    assert_same(batch(a, b, poses_a=poses_a, poses_b=poses_b, threads=2), listed)
    assert_same(batch(a, [b] * 60, poses_a=poses_a, poses_b=poses_b), listed)
    assert_same(batch(a.vertices, b, poses_a=poses_a, poses_b=poses_b), listed)
    # Every pose form gives the same rows.
    rotations, translations = poses_b[:, :3, :3], poses_b[:, :3, 3]
    assert_same(batch(a, b, poses_a=poses_a, poses_b=poses_b[:, :3, :]), listed)
    assert_same(batch(a, b, poses_a=poses_a, poses_b=(rotations, translations)), listed)
    # With single bodies on both sides, the poses count the rows; without them there is one.
    assert len(batch(a, b, poses_b=poses_b)) == 60
    assert len(batch(a, b)) == 1


def test_a_rotation_object_counts_the_rows_of_single_bodies(posed):
    from scipy.spatial.transform import Rotation

    a, b, _, poses_b = posed
    turns, translations = Rotation.from_matrix(poses_b[:, :3, :3]), poses_b[:, :3, 3]
    for poses in ((turns, translations), turns):
        single = sc.distance_many(a, b, poses_b=poses)
        assert len(single) == 60
        assert_same(single, sc.distance_many([a] * 60, [b] * 60, poses_b=poses))


def test_a_single_pose_serves_every_row(posed):
    from scipy.spatial.transform import Rotation

    a, b, poses_a, poses_b = posed
    one = poses_a[0]
    listed = sc.distance_many(a, b, poses_a=np.stack([one] * 60), poses_b=poses_b)
    for single in (one, one[:3], (one[:3, :3], one[:3, 3]), one.tolist()):
        assert_same(sc.distance_many(a, b, poses_a=single, poses_b=poses_b), listed)
        assert_same(sc.distance_many([a] * 60, b, poses_a=single, poses_b=poses_b), listed)
    turn = Rotation.from_matrix(one[:3, :3])
    turned = (np.tile(turn.as_matrix(), (60, 1, 1)), np.zeros((60, 3)))
    assert_same(sc.collide_many(a, b, poses_a=turn, poses_b=poses_b),
                sc.collide_many(a, b, poses_a=turned, poses_b=poses_b))
    with pytest.raises(ValueError, match=r"^poses_a is not a rigid motion"):
        sc.distance_many(a, b, poses_a=np.diag([2.0, 1, 1, 1]), poses_b=poses_b)


def test_pose_arrays_read_in_place_answer_as_converted_poses(posed):
    # C-contiguous float64 arrays are read where they are; lists, other dtypes and strided views
    # are converted first: the rows are the same.
    a, b, poses_a, poses_b = posed
    rotations = np.ascontiguousarray(poses_b[:, :3, :3])
    translations = np.ascontiguousarray(poses_b[:, :3, 3])
    for batch in (sc.distance_many, sc.collide_many):
        in_place = batch(a, b, poses_a=poses_a, poses_b=(rotations, translations))
        assert_same(batch(a, b, poses_a=list(poses_a), poses_b=(list(rotations), translations)),
                    in_place)
        assert_same(batch(a, b, poses_a=np.asfortranarray(poses_a), poses_b=poses_b), in_place)
        assert_same(batch(a, b, poses_a=np.ascontiguousarray(poses_a[:, :3]), poses_b=poses_b),
                    in_place)
    broken = poses_b.copy()
    broken[7, 3, 0] = 1e-3
    with pytest.raises(ValueError, match=r"poses_b\[7\] must be a homogeneous rigid transform"):
        sc.distance_many(a, b, poses_b=broken)
    bent = poses_b.copy()
    bent[9, 0, 0] = 1.5
    with pytest.raises(ValueError, match=r"^poses_b\[9\] is not a rigid motion"):
        sc.collide_many(a, b, poses_b=bent, first_index=0)


def test_single_body_rows_are_the_single_queries(posed):
    a, b, poses_a, poses_b = posed
    distances = sc.distance_many(a, b, poses_a=poses_a, poses_b=poses_b, seed=3)
    depths = sc.signed_distance_many(a, b, poses_a=poses_a, poses_b=poses_b, seed=3)
    for i in (0, 17, 59):
        seed = sc.pair_seed(3, i)
        single = sc.distance(a, b, pose_a=poses_a[i], pose_b=poses_b[i], seed=seed)
        assert distances.distance[i] == single.distance
        np.testing.assert_array_equal(distances.point_b[i], single.point_b)
        signed = sc.signed_distance(a, b, pose_a=poses_a[i], pose_b=poses_b[i], seed=seed)
        assert depths.distance[i] == signed.distance


def test_a_single_compound_body_serves_every_row(posed):
    a, b, _, poses_b = posed
    ring = sc.CompoundBody([a, sc.ConvexPolyhedron(a.vertices + [3, 0, 0])])
    listed = sc.distance_many([ring] * 60, [b] * 60, poses_b=poses_b)
    assert_same(sc.distance_many(ring, b, poses_b=poses_b), listed)
    assert_same(sc.collide_many(ring, b, poses_b=poses_b),
                sc.collide_many([ring] * 60, [b] * 60, poses_b=poses_b))


@pytest.mark.parametrize("batch", [sc.distance_many, sc.collide_many, sc.signed_distance_many])
def test_a_convex_row_answers_alike_beside_a_compound_row(batch, posed):
    # A compound body in any row wraps every row's bodies; a row of one part each is still the
    # convex row, bit for bit (it was answered by the compound search, whose start and part-pair
    # seed differ).
    a, b, poses_a, poses_b = posed
    ring = sc.CompoundBody([a, sc.ConvexPolyhedron(a.vertices + [3, 0, 0])])
    convex = batch([a] * 60, [b] * 60, poses_a=poses_a, poses_b=poses_b, seed=4, threads=2)
    mixed = batch([a] * 60 + [ring], [b] * 61, poses_a=np.concatenate([poses_a, poses_a[:1]]),
                  poses_b=np.concatenate([poses_b, poses_b[:1]]), seed=4, threads=2)
    for field in ("distance", "lower_bound", "point_a", "point_b", "direction", "colliding",
                  "certified", "iterations", "escalated", "part_a", "part_b"):
        np.testing.assert_array_equal(getattr(mixed, field)[:60], getattr(convex, field),
                                      err_msg=field)


@pytest.mark.parametrize("query", [sc.distance, sc.collision, sc.signed_distance])
def test_compound_bodies_of_one_part_answer_as_their_parts(query, posed):
    a, b, poses_a, poses_b = posed
    for i in (0, 23, 41):
        plain = query(a, b, pose_a=poses_a[i], pose_b=poses_b[i], seed=i)
        wrapped = query(sc.CompoundBody([a]), b, pose_a=poses_a[i], pose_b=poses_b[i], seed=i)
        assert (wrapped.part_a, wrapped.part_b, wrapped.stats.part_pairs) == (0, 0, 1)
        for field in ("distance", "lower_bound", "colliding", "certified", "iterations"):
            assert getattr(wrapped, field) == getattr(plain, field), field
        for field in ("point_a", "point_b", "direction"):
            np.testing.assert_array_equal(getattr(wrapped, field), getattr(plain, field))


def test_posed_rows_answer_alike_on_any_threads_and_cuts(posed):
    a, b, poses_a, poses_b = posed
    for batch in (sc.distance_many, sc.collide_many, sc.signed_distance_many):
        whole = batch(a, b, poses_a=poses_a, poses_b=poses_b, threads=1)
        for threads in (2, 3, None):
            assert_same(batch(a, b, poses_a=poses_a, poses_b=poses_b, threads=threads), whole)
        cut = 37
        tail = batch(a, b, poses_a=poses_a[cut:], poses_b=poses_b[cut:], first_index=cut)
        np.testing.assert_array_equal(tail.distance, whole.distance[cut:])
        np.testing.assert_array_equal(tail.point_a, whole.point_a[cut:])


def test_collisions_settled_by_the_balls_keep_their_bounds(posed):
    a, b, _, _ = posed
    poses_b = random_transforms(60, 3, 8.0)
    verdicts = sc.collide_many(a, b, poses_b=poses_b)
    assert verdicts.certified.all()
    settled = 0
    for i in range(60):
        truth = sc.distance(a, b, pose_b=poses_b[i], method="exact", tolerance=0)
        assert verdicts.lower_bound[i] <= truth.distance + 1e-12
        assert verdicts.distance[i] >= truth.lower_bound - 1e-12
        assert verdicts.colliding[i] == truth.colliding
        first_b = poses_b[i, :3, :3] @ b.vertices[0] + poses_b[i, :3, 3]
        settled += bool(np.allclose(verdicts.point_b[i], first_b, atol=1e-12)
                        and verdicts.iterations[i] == 0)
    assert settled > 10  # pairs beyond their balls are settled without a solver


ROTATION = np.eye(3)


@pytest.mark.parametrize(
    ("poses_b", "error", "message"),
    [
        (np.tile(np.eye(4), (3, 1, 1)), ValueError, r"poses_b must be a \(4, 4, 4\) or \(4, 3, 4\)"),
        (np.tile(np.eye(4), (4, 1, 1))[:, :, :3], ValueError, r"poses_b must be a \(4, 4, 4\)"),
        (np.tile(np.eye(4), (4, 1, 1)).astype(complex), TypeError, "poses_b must hold real"),
        (np.tile(np.eye(4), (4, 1, 1)).astype(str), TypeError, "poses_b must hold real"),
        (np.stack([np.eye(4)] * 3 + [np.diag([2.0, 1, 1, 1])]), ValueError,
         r"poses_b\[3\] is not a rigid motion"),
        (np.stack([np.eye(4)] * 2 + [np.diag([1.0, 1, -1, 1])] * 2), ValueError,
         r"poses_b\[2\] is not a rigid motion"),
        (np.stack([np.eye(4)] + [np.full((4, 4), np.nan)] * 3), ValueError,
         r"poses_b\[1\] has a NaN or infinite entry"),
        ((np.tile(ROTATION, (4, 1, 1)), np.array([[0, 0, 0]] * 3 + [[np.inf, 0, 0]])),
         ValueError, r"poses_b\[3\] has a NaN or infinite entry"),
        ((np.tile(ROTATION, (4, 1, 1)), np.zeros((3, 3))), ValueError,
         r"poses_b's translations must be"),
        # The translations' own shape, not the transforms' (a (4, 4, 4) or (4, 3, 4) array).
        ((np.tile(ROTATION, (4, 1, 1)), np.zeros((1, 3))), ValueError,
         r"^poses_b's translations must be a \(4, 3\) array, one translation per rotation, got "
         r"shape \(1, 3\)$"),
        ((np.tile(ROTATION, (2, 1, 1)), np.zeros((4, 3))), ValueError,
         r"^poses_b's rotations must be a \(4, 3, 3\) array of rotation matrices \(or a SciPy "
         r"Rotation of 4\), one per row, got shape \(2, 3, 3\)$"),
        (np.tile(np.eye(4)[:3], (4, 1, 1)) * [1, 1, 1, np.nan], ValueError,
         r"poses_b\[0\] has a NaN"),
    ],
)
def test_bad_poses_name_the_argument_and_the_row(poses_b, error, message):
    with pytest.raises(error, match=message):
        sc.collide_many(sc.ConvexPolyhedron(TETRA), TETRA, poses_a=np.tile(np.eye(4), (4, 1, 1)),
                        poses_b=poses_b)


def test_mismatched_rows_are_refused():
    poses = np.tile(np.eye(4), (3, 1, 1))
    with pytest.raises(ValueError, match=r"poses_b must be a \(2, 4, 4\)"):
        sc.distance_many([TETRA, TETRA], TETRA, poses_b=poses)
    with pytest.raises(ValueError, match=r"poses_b must be a \(3, 4, 4\)"):
        sc.distance_many(TETRA, sc.ConvexPolyhedron(TETRA), poses_a=poses, poses_b=poses[:2])


def test_result_arrays_are_read_only_views_that_keep_their_memory():
    # A large result's memory is kept for the next result of its size once the result is freed:
    # an array still held keeps its result (and memory) alive, so later batches never write
    # into it.
    rng = np.random.default_rng(27)
    body = sc.ConvexPolyhedron(rng.normal(size=(8, 3)))
    translations = rng.normal(size=(30_000, 3)) * 3
    rotations = np.broadcast_to(np.eye(3), (30_000, 3, 3)).copy()
    first = sc.collide_many(body, body, poses_b=(rotations, translations))
    distance, points = first.distance, first.point_a
    kept = distance.copy(), points.copy()
    assert not distance.flags.writeable and not points.flags.writeable
    assert points.flags.c_contiguous and points.shape == (30_000, 3)
    with pytest.raises(ValueError):
        distance[0] = 1
    del first
    for _ in range(3):
        sc.collide_many(body, body, poses_b=(rotations, translations[::-1].copy()))
    np.testing.assert_array_equal(distance, kept[0])
    np.testing.assert_array_equal(points, kept[1])
