"""Scenes against a brute-force oracle, poses against transformed vertices, contact manifolds."""

import gc
import itertools
import os
import signal

import numpy as np
import pytest

import swarmcollide as sc
from swarmcollide import scene_demo
from swarmcollide.cli import main

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
CENTRED = CUBE - 0.5


def rotation(axis, angle):
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def random_rotation(rng):
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def transform(rot, shift):
    m = np.eye(4)
    m[:3, :3] = rot
    m[:3, 3] = shift
    return m


def random_body(rng):
    points = rng.normal(size=(int(rng.integers(4, 11)), 3))
    return points / np.linalg.norm(points, axis=1)[:, None] * rng.uniform(0.3, 0.8) + [0.2, 0, -0.1]


class World:
    """What the scene should hold, for the oracle."""

    def __init__(self):
        self.bodies, self.poses, self.excluded = {}, {}, set()

    def pairs(self):
        ids = sorted(self.bodies)
        return [(a, b) for a, b in itertools.combinations(ids, 2) if (a, b) not in self.excluded]

    def placed(self, i):
        pose = self.poses[i]
        return self.bodies[i] @ pose[:3, :3].T + pose[:3, 3]


def check_against_oracle(scene, world):
    truth = {p: sc.distance(world.placed(p[0]), world.placed(p[1]), method="exact").distance
             for p in world.pairs()}
    colliding = {p for p in world.pairs()
                 if sc.collide(world.bodies[p[0]], world.bodies[p[1]],
                               pose_a=world.poses[p[0]], pose_b=world.poses[p[1]])}

    found = scene.colliding_pairs()
    assert {tuple(p) for p in found.pairs.tolist()} == colliding
    assert found.certified.all()
    stats = scene.stats
    assert stats.certified == stats.candidates

    for d in (0.05, 0.4):
        within = scene.pairs_within(d)
        assert {tuple(p) for p in within.pairs.tolist()} == {p for p, t in truth.items() if t <= d}
        for (a, b), lower, upper in zip(within.pairs.tolist(), within.lower_bound, within.distance):
            assert lower - 1e-9 <= truth[(a, b)] <= upper + 1e-9

    nearest_pair = scene.min_distance()
    if truth:
        assert len(nearest_pair) == 1
        assert nearest_pair.distance[0] == pytest.approx(min(truth.values()), abs=1e-8)

    asked = sorted(world.bodies)[:3]
    near = scene.nearest(asked, k=2)
    expected = []
    for i in asked:
        ranked = sorted((t, b if a == i else a) for (a, b), t in truth.items() if i in (a, b))
        expected += [(i, t) for t, _ in ranked[:2]]
    assert near.pairs[:, 0].tolist() == [i for i, _ in expected]
    np.testing.assert_allclose(near.distance, [t for _, t in expected], atol=1e-8)

    contacts = scene.contacts()
    assert {tuple(p) for p in contacts.pairs.tolist()} == colliding
    assert contacts.certified.all()
    assert (contacts.counts >= 1).all() and (contacts.counts <= 4).all()
    assert len(contacts.points) == contacts.counts.sum()
    np.testing.assert_allclose(np.linalg.norm(contacts.normal, axis=1), 1)


@pytest.mark.parametrize("broadphase,warm_start", [
    ("dynamic_aabb_tree", True),
    ("dynamic_aabb_tree", False),
    ("sap", True),
    ("spatial_hashing", True),
    ("brute_force", False),
])
def test_scene_answers_equal_the_oracle_through_moves_adds_and_removes(broadphase, warm_start):
    rng = np.random.default_rng(4)
    scene = sc.Scene(broadphase=broadphase, warm_start=warm_start, threads=2)
    world = World()

    def add(count):
        bodies = [random_body(rng) for _ in range(count)]
        poses = np.stack([transform(random_rotation(rng), rng.uniform(0, 3, 3))
                          for _ in range(count)])
        for i, body, pose in zip(scene.add(bodies, poses).tolist(), bodies, poses):
            world.bodies[i], world.poses[i] = body, pose

    add(18)
    check_against_oracle(scene, world)
    for _ in range(2):
        ids = np.array(sorted(world.poses))
        poses = np.stack([transform(rotation(rng.normal(size=3), 0.05) @ world.poses[i][:3, :3],
                                    world.poses[i][:3, 3] + rng.normal(0, 0.05, 3))
                          for i in ids])
        scene.set_poses(ids, poses)
        world.poses.update(zip(ids.tolist(), poses))
        check_against_oracle(scene, world)
    scene.remove([1, 7])
    for i in (1, 7):
        del world.bodies[i], world.poses[i]
    scene.exclude([[2, 3], [5, 4]])
    world.excluded = {(2, 3), (4, 5)}
    add(4)
    check_against_oracle(scene, world)


def test_groups_and_masks_choose_the_pairs():
    scene = sc.Scene()
    ids = scene.add(np.stack([CUBE, CUBE + 0.5, CUBE + 1]))
    assert scene.colliding_pairs().pairs.tolist() == [[0, 1], [0, 2], [1, 2]]
    # Body 1 in group 2, which body 0's mask leaves out.
    scene.set_filter(ids[1], group=2)
    scene.set_filter(ids[0], group=1, mask=1)
    assert scene.colliding_pairs().pairs.tolist() == [[0, 2], [1, 2]]
    scene.exclude((2, 1))
    assert scene.colliding_pairs().pairs.tolist() == [[0, 2]]
    scene.include([[1, 2]])
    assert scene.colliding_pairs().pairs.tolist() == [[0, 2], [1, 2]]


def test_without_warm_starts_answers_do_not_depend_on_history_or_threads():
    rng = np.random.default_rng(8)
    bodies = [random_body(rng) for _ in range(30)]
    start = np.stack([transform(random_rotation(rng), rng.uniform(0, 3, 3)) for _ in range(30)])
    end = np.stack([transform(random_rotation(rng), rng.uniform(0, 3, 3)) for _ in range(30)])
    travelled = sc.Scene(warm_start=False, threads=1)
    ids = travelled.add(bodies, start)
    travelled.pairs_within(0.3)
    travelled.set_poses(ids, end)
    fresh = sc.Scene(warm_start=False, threads=2, broadphase="interval_tree")
    fresh.add(bodies, end)
    a, b = travelled.pairs_within(0.3), fresh.pairs_within(0.3)
    assert a.pairs.tolist() == b.pairs.tolist()
    for field in ("distance", "lower_bound", "point_a", "point_b", "normal"):
        np.testing.assert_array_equal(getattr(a, field), getattr(b, field))


def test_a_scene_kept_across_a_fork_answers_and_is_freed_in_the_child():
    # The child has none of the parent's pool threads: freeing the scene there must not wait for
    # them (it did, forever), and its frames must still be answered, by threads of its own.
    rng = np.random.default_rng(9)
    bodies = [random_body(rng) for _ in range(60)]
    poses = np.stack([transform(random_rotation(rng), rng.uniform(0, 2, 3)) for _ in range(60)])
    scene = sc.Scene(threads=2)
    scene.add(bodies, poses)
    expected = scene.colliding_pairs().pairs.tolist()  # the pool's threads have run
    assert expected
    child = os.fork()
    if child == 0:  # pragma: no cover - the child's verdict is its exit status
        status = 1
        try:
            signal.alarm(20)
            same = scene.colliding_pairs().pairs.tolist() == expected
            del scene
            gc.collect()
            status = 0 if same else 2
        finally:
            os._exit(status)
    _, status = os.waitpid(child, 0)
    assert os.WIFEXITED(status), f"the child was killed by signal {os.WTERMSIG(status)}"
    assert os.WEXITSTATUS(status) == 0
    assert scene.colliding_pairs().pairs.tolist() == expected


def test_warm_frames_settle_most_pairs_from_the_cache():
    rng = np.random.default_rng(2)
    scene = sc.Scene(threads=1)
    poses = np.stack([transform(random_rotation(rng), rng.uniform(0, 4, 3)) for _ in range(60)])
    ids = scene.add([random_body(rng) for _ in range(60)], poses)
    scene.colliding_pairs()
    cold = scene.stats
    assert cold.warm_bounded + cold.warm_rejected + cold.warm_proven == 0 and cold.cached_pairs > 0
    poses[:, :3, 3] += [1e-3, -2e-3, 1e-3]
    scene.set_poses(ids, poses)
    scene.colliding_pairs()
    warm = scene.stats
    assert warm.candidates == cold.candidates
    assert warm.warm_bounded + warm.warm_rejected + warm.warm_proven >= 0.8 * warm.candidates
    assert warm.warm_bounded > 0
    assert "warm_rejected=" in repr(warm)


def test_results_are_numpy_arrays_with_a_repr():
    scene = sc.Scene()
    scene.add(np.stack([CUBE, CUBE + [0.5, 0, 0], CUBE + [3, 0, 0]]))
    r = scene.pairs_within(2.5)
    assert r.pairs.dtype == np.int64 and r.pairs.shape == (3, 2)
    assert r.distance.shape == r.lower_bound.shape == r.certified.shape == (3,)
    assert r.point_a.shape == r.point_b.shape == r.normal.shape == (3, 3)
    assert r.certified.dtype == bool
    assert repr(r).startswith("SceneResult(3 pairs, 3 certified, distances 0 to 2")
    c = scene.contacts()
    assert repr(c).endswith("4 contact points)")
    assert repr(scene) == ("Scene(3 bodies, method='dual', broadphase='dynamic_aabb_tree', "
                           "warm_start=True)")
    assert len(scene) == 3 and 2 in scene and 3 not in scene
    np.testing.assert_array_equal(scene.pose(1), transform(np.eye(3), [0, 0, 0]))
    assert scene.ids.tolist() == [0, 1, 2]


def test_the_id_add_returns_for_one_body_is_taken_wherever_one_id_is():
    scene = sc.Scene()
    scene.add(CUBE)
    placed = transform(np.eye(3), [4, 0, 0])
    ids = scene.add(sc.Box([0.5] * 3), placed)  # an array of one id
    assert ids.shape == (1,)
    for given in (ids, ids.astype(np.int32), ids.reshape(1, 1), ids[0], int(ids[0])):
        np.testing.assert_array_equal(scene.pose(given), placed)
        assert type(scene.body(given)) is sc.Box
        assert given in scene
    assert np.array([7]) not in scene and np.array([0, 1]) not in scene
    for name, call in (("id", scene.pose), ("id", scene.body)):
        with pytest.raises(TypeError, match=f"^{name} must be one id .* got an array of 2 int64 "
                           "values; pass one of its items"):
            call(np.array([0, 1]))
        with pytest.raises(TypeError, match=f"^{name} must be one id .* got an array of 1 "
                           "float64 values"):
            call(np.array([1.0]))
        with pytest.raises(ValueError, match="no body with id 7"):
            call(np.array([7]))
        with pytest.raises(ValueError, match="id must be at least 0"):
            call(np.array([-1]))


def contacts_of(b, pose):
    """Contacts of the unit cube A and B at ``pose``, asked both ways round."""
    forward, backward = sc.Scene(), sc.Scene()
    forward.add(CUBE)
    forward.add(b, pose)
    backward.add(b, pose)
    backward.add(CUBE)
    return forward.contacts(), backward.contacts()


def same_points(p, q):
    assert len(p) == len(q)
    for point in p:
        assert np.min(np.linalg.norm(q - point, axis=1)) < 1e-9


def test_box_resting_on_a_box_touches_at_four_corners_either_way_round():
    forward, backward = contacts_of(CUBE * [1.5, 1.5, 0.5] + [0.25, 0.5, 0], transform(np.eye(3), [0, 0, 1]))
    assert forward.counts.tolist() == [4]
    np.testing.assert_allclose(forward.normal, [[0, 0, 1]], atol=1e-9)
    same_points(forward.points, np.array([[0.25, 0.5, 1], [1, 0.5, 1], [1, 1, 1], [0.25, 1, 1]]))
    np.testing.assert_allclose(backward.normal, -forward.normal, atol=1e-9)
    same_points(backward.points, forward.points)
    assert forward.distance[0] == pytest.approx(0, abs=1e-12)


def test_edge_on_face_touches_at_two_points_and_vertex_on_face_at_one():
    on_edge = transform(rotation([1, 0, 0], np.pi / 4), [0.5, 0.5, 1 + np.sqrt(0.5)])
    forward, backward = contacts_of(CENTRED, on_edge)
    assert forward.counts.tolist() == backward.counts.tolist() == [2]
    same_points(forward.points, np.array([[0, 0.5, 1], [1, 0.5, 1]]))
    same_points(backward.points, forward.points)
    diagonal = np.array([-1.0, -1.0, -1.0]) / np.sqrt(3)
    axis = np.cross(diagonal, [0, 0, -1])
    turn = rotation(axis, np.arccos(np.dot(diagonal, [0, 0, -1])))
    forward, backward = contacts_of(CENTRED, transform(turn, [0.5, 0.5, 1 + np.sqrt(0.75)]))
    assert forward.counts.tolist() == backward.counts.tolist() == [1]
    np.testing.assert_allclose(forward.points, [[0.5, 0.5, 1]], atol=1e-9)
    np.testing.assert_allclose(backward.normal, -forward.normal, atol=1e-9)


def test_poses_equal_transformed_vertices_in_every_query_and_batch():
    rng = np.random.default_rng(6)
    a, b = random_body(rng), random_body(rng)
    for _ in range(10):
        pa = transform(random_rotation(rng), rng.uniform(0, 1.5, 3))
        pb = transform(random_rotation(rng), rng.uniform(0, 1.5, 3))
        wa, wb = a @ pa[:3, :3].T + pa[:3, 3], b @ pb[:3, :3].T + pb[:3, 3]
        posed = sc.distance(a, b, pose_a=pa, pose_b=(pb[:3, :3], pb[:3, 3]))
        assert posed.distance == pytest.approx(sc.distance(wa, wb).distance, abs=1e-9)
        assert sc.collide(a, b, pose_a=pa, pose_b=pb) == sc.collide(wa, wb)
        assert sc.signed_distance(a, b, pose_a=pa, pose_b=pb).distance == pytest.approx(
            sc.signed_distance(wa, wb).distance, abs=1e-9)
    poses_a = np.stack([transform(random_rotation(rng), rng.uniform(0, 1.5, 3)) for _ in range(6)])
    poses_b = np.stack([transform(random_rotation(rng), rng.uniform(0, 1.5, 3)) for _ in range(6)])
    As, Bs = np.stack([a] * 6), np.stack([b] * 6)
    moved_a = np.einsum("mij,mnj->mni", poses_a[:, :3, :3], As) + poses_a[:, None, :3, 3]
    moved_b = np.einsum("mij,mnj->mni", poses_b[:, :3, :3], Bs) + poses_b[:, None, :3, 3]
    expected = sc.distance_many(moved_a, moved_b).distance
    np.testing.assert_allclose(sc.distance_many(As, Bs, poses_a=poses_a, poses_b=poses_b).distance,
                               expected, atol=1e-9)
    pairs = (poses_b[:, :3, :3], poses_b[:, :3, 3])
    np.testing.assert_allclose(sc.distance_many([a] * 6, [b] * 6, poses_a=poses_a,
                                                poses_b=pairs).distance, expected, atol=1e-9)
    assert (sc.collide_many(As, Bs, poses_a=poses_a, poses_b=poses_b).colliding
            == sc.collide_many(moved_a, moved_b).colliding).all()


@pytest.mark.parametrize("pose,message", [
    (np.diag([2.0, 1, 1, 1]), "not a rigid motion"),
    (np.diag([1.0, 1, -1, 1]), "not a rigid motion"),
    (np.where(np.eye(4) == 0, 0, np.array([np.nan, 1, 1, 1])), "NaN or infinite"),
    (np.eye(3), r"\(4, 4\)"),
])
def test_invalid_poses_are_value_errors_naming_the_argument(pose, message):
    with pytest.raises(ValueError, match=message):
        sc.distance(CUBE, CUBE, pose_b=pose)
    scene = sc.Scene()
    with pytest.raises(ValueError, match="poses"):
        scene.add(CUBE, pose)
    scene.add(CUBE)
    with pytest.raises(ValueError, match=r"poses\[0\]|poses"):
        scene.set_poses([0], pose[None] if pose.shape == (4, 4) else pose)
    with pytest.raises(ValueError, match="poses_a"):
        sc.distance_many([CUBE], [CUBE], poses_a=pose[None])


def test_a_pose_of_nans_is_named_for_its_nans_not_its_last_row():
    nans = np.full((4, 4), np.nan)
    scene = sc.Scene()
    with pytest.raises(ValueError, match=r"^poses\[0\] has a NaN or infinite entry"):
        scene.add([CUBE], nans[None])
    body = scene.add(CUBE)
    with pytest.raises(ValueError, match=r"^poses\[0\] has a NaN or infinite entry"):
        scene.set_poses(body, nans)
    with pytest.raises(ValueError, match="^pose_b has a NaN or infinite entry"):
        sc.distance(CUBE, CUBE, pose_b=nans)


def test_a_bad_pose_among_many_is_named_by_its_index():
    # The poses' names are made only for a message (a name per pose was 2.5% of a frame).
    scene = sc.Scene()
    ids = np.concatenate([scene.add(CUBE) for _ in range(4)])
    poses = np.repeat(np.eye(4)[None], 4, axis=0)
    poses[2, 3] = [0, 0, 1, 1]
    with pytest.raises(ValueError, match=r"^poses\[2\] must be a homogeneous rigid transform"):
        scene.set_poses(ids, poses)
    poses[2] = np.eye(4)
    poses[3, 0, 0] = 2.0
    with pytest.raises(ValueError, match=r"poses\[3\].*not a rigid motion"):
        scene.set_poses(ids, poses)


@pytest.mark.parametrize("shapes", [
    [sc.Cylinder(1, 2), sc.Cone(0.5, 1), sc.Ellipsoid([1, 2, 3])],
    [sc.Sphere(0.5), sc.Capsule(0.25, 1.5), sc.Box([1, 2, 3]), sc.Box([0.5, 0.5, 1e-3], 0.1)],
])
def test_a_shape_comes_back_as_its_own_class(shapes):
    from swarmcollide import shape_json

    scene = sc.Scene()
    ids = scene.add(shapes)
    for shape, body_id in zip(shapes, ids):
        body = scene.body(int(body_id))
        assert type(body) is type(shape) and repr(body) == repr(shape)
        assert shape_json.body_to_json(body) == shape_json.body_to_json(shape)
    # Other polyhedra stay polyhedra, however near a shape's points theirs are.
    near = [sc.ConvexPolyhedron([[0, 0, -1], [0, 1e-9, 1]], 0.5),
            sc.ConvexPolyhedron([[0, 0, 0]]), sc.ConvexPolyhedron(sc.Box([1, 2, 3]).vertices[:7])]
    for body_id in scene.add(near):
        assert type(scene.body(int(body_id))) is sc.ConvexPolyhedron


def test_scene_errors_name_the_argument_and_the_fix():
    with pytest.raises(ValueError, match="unknown broadphase 'octree'; choose one of"):
        sc.Scene(broadphase="octree")
    with pytest.raises(ValueError, match="threads must be in"):
        sc.Scene(threads=0)
    with pytest.raises(ValueError, match="at most 0.1"):
        sc.Scene(tolerance=0.5)
    with pytest.raises(ValueError, match="swarm_size"):
        sc.Scene(swarm_size=0)
    scene = sc.Scene()
    scene.add(CUBE)
    with pytest.raises(ValueError, match="no body with id 5"):
        scene.set_poses(5, np.eye(4))
    with pytest.raises(ValueError, match="twice"):
        scene.remove([0, 0])
    moved = np.eye(4)
    moved[0, 3] = 10
    with pytest.raises(ValueError, match="^ids lists body 0 twice; give each body one pose"):
        scene.set_poses([0, 0], np.stack([moved, np.eye(4)]))
    assert scene.pose(0)[0, 3] == 0
    with pytest.raises(TypeError, match="bodies must be"):
        scene.add("cube")
    with pytest.raises(TypeError, match="ids must be"):
        scene.remove([0.5])
    with pytest.raises(ValueError, match="distance must be"):
        scene.pairs_within(-1)
    with pytest.raises(ValueError, match="pairs_within is not available with method 'libccd'"):
        sc.Scene(method="libccd").pairs_within(1)
    with pytest.raises(ValueError, match="max_points must be at least 1"):
        scene.contacts(max_points=0)
    assert len(scene.min_distance()) == 0


def test_the_scene_demo_prints_frames_and_saves_a_picture(tmp_path, capsys):
    picture = tmp_path / "frame.png"
    assert main(["scene", "--bodies", "30", "--frames", "3", "--plot", str(picture)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split(":")[0] for line in lines[:3]] == ["frame   0", "frame   1", "frame   2"]
    assert "in contact" in lines[0] and "contacts" in lines[0]
    assert picture.stat().st_size > 10_000
    frames = scene_demo.run(bodies=30, frames=3, seed=0, out=lambda line: None)
    again = scene_demo.run(bodies=30, frames=3, seed=0, out=lambda line: None)
    assert [f.colliding for f in frames] == [f.colliding for f in again]


def test_warm_contacts_equal_cold_ones_up_to_the_certificate():
    # Overlapping pairs that stay in contact start their penetration from the tetrahedron their
    # warm proof keeps; a pair teleported into contact, bodies sent far away and back, and a
    # refused NaN pose must all give what a scene without warm starts gives.
    rng = np.random.default_rng(26)
    bodies = [random_body(rng) for _ in range(24)]
    bodies += [rng.normal(size=(60, 3)) * 0.4 for _ in range(6)]  # climbed, not scanned
    poses = np.stack([transform(random_rotation(rng), rng.uniform(0, 2.2, 3)) for _ in bodies])
    warm = sc.Scene(threads=1)
    cold = sc.Scene(warm_start=False, threads=2)
    ids = warm.add(bodies, poses)
    cold.add(bodies, poses)
    steps = [transform(rotation(rng.normal(size=3), 0.03), rng.normal(0, 0.02, 3))
             for _ in bodies]
    warm_proven = 0
    for frame in range(12):
        poses = np.stack([p @ s for p, s in zip(poses, steps)])
        if frame == 5:
            poses[3] = poses[4]  # into contact in one frame: same place as body 4
            poses[7:10, :3, 3] += 1e6
        if frame == 8:
            poses[7:10, :3, 3] -= 1e6
        warm.set_poses(ids, poses)
        cold.set_poses(ids, poses)
        a, b = warm.contacts(), cold.contacts()
        warm_proven += warm.stats.warm_proven
        assert a.certified.all() and b.certified.all()
        assert a.pairs.tolist() == b.pairs.tolist()
        if frame == 5:
            assert [3, 4] in a.pairs.tolist()
        # Each answer's bounds [lower_bound, distance] enclose the signed distance.
        assert (np.maximum(a.lower_bound, b.lower_bound)
                <= np.minimum(a.distance, b.distance) + 1e-12).all()
        assert (a.counts >= 1).all()
    assert warm_proven > 0
    before = warm.contacts()
    nan_pose = poses.copy()
    nan_pose[2, 0, 3] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        warm.set_poses(ids, nan_pose)
    after = warm.contacts()  # at the poses before the refused call
    assert after.pairs.tolist() == before.pairs.tolist() == b.pairs.tolist()
    assert (np.maximum(after.lower_bound, b.lower_bound)
            <= np.minimum(after.distance, b.distance) + 1e-12).all()


def test_a_sinking_turning_box_keeps_four_contact_points_warm_or_cold():
    # Face on face: the contact tetrahedron's base is searched among 4 x 4 differences of the
    # faces' corners, and the manifold's buffers are reused from frame to frame.
    box = CENTRED * [1.0, 1.0, 0.5]
    scenes = [sc.Scene(threads=1), sc.Scene(warm_start=False, threads=1)]
    for scene in scenes:
        scene.add(np.stack([box, box]), np.stack([np.eye(4), transform(np.eye(3), [0, 0, 0.5])]))
    for frame in range(1, 8):
        top = transform(rotation([0, 0, 1], 0.05 * frame), [0.02 * frame, 0, 0.5 - 1e-3 * frame])
        warm, cold = [(s.set_poses([1], top[None]), s.contacts())[1] for s in scenes]
        for c in (warm, cold):
            assert c.pairs.tolist() == [[0, 1]] and c.certified.all()
            assert c.counts.tolist() == [4]
            np.testing.assert_allclose(c.normal, [[0, 0, 1]], atol=1e-9)
            assert c.distance[0] == pytest.approx(-1e-3 * frame, abs=1e-9)
        same_points(warm.points, cold.points)
    assert scenes[0].stats.warm_proven == 1


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e-170, 1e100])
def test_a_scene_answers_alike_at_every_scale(scale):
    """A scene's lengths (its extent, a body's reach, how far a new pose moves a body) and a
    large body's support tree are taken without squares, which vanished below 1e-162: there
    min_distance of two boxes 3e-170 apart found no pair at all."""
    cloud = np.random.default_rng(3).normal(size=(60, 3)) * 0.5

    def frames(s):
        scene = sc.Scene(seed=1)
        poses = np.tile(np.eye(4), (3, 1, 1))
        poses[:, 0, 3] = [0, 3 * s, 6 * s]
        scene.add([sc.Box([s, s, s]), sc.ConvexPolyhedron(cloud * s), sc.Cylinder(0.5 * s, s)],
                  poses)
        answers = []
        for _ in range(3):
            poses[:, 0, 3] -= [0, 0.8 * s, 1.6 * s]
            scene.set_poses(scene.ids, poses)
            answers += [scene.min_distance(), scene.colliding_pairs(), scene.contacts()]
        return answers

    for k, (unit, scaled) in enumerate(zip(frames(1.0), frames(scale))):
        # min_distance's pair is any of those at the least distance (here touching: 0).
        if k % 3 != 0:
            np.testing.assert_array_equal(scaled.pairs, unit.pairs)
        assert len(scaled) == len(unit) and np.all(scaled.certified)
        np.testing.assert_allclose(np.asarray(scaled.distance) / scale, unit.distance, rtol=1e-6,
                                   atol=1e-6)
