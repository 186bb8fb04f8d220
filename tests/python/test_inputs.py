"""What users naturally pass (issue 23, items 7 and 8): trimesh meshes as bodies, SciPy rotations
and (3, 4) matrices as poses, quaternions in either order; and the arguments that must be refused
with a message naming them (bytes for names, complex directions, thread counts beyond any int)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from scipy.spatial.transform import Rotation

import dask.array as da

import swarmcollide as sc
import swarmcollide.dask as scd

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
TURN = Rotation.from_rotvec([0.3, -0.2, 0.9])
SHIFT = np.array([3.0, 0.5, -0.25])
STACK = da.from_array(np.stack([CUBE]), chunks=(1, -1, -1))


def homogeneous(rotation: Rotation, translation) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3], pose[:3, 3] = rotation.as_matrix(), translation
    return pose


def box_mesh() -> trimesh.Trimesh:
    return trimesh.creation.box((1, 1, 1), transform=trimesh.transformations.translation_matrix(
        [0.5, 0.5, 0.5]))


# ----- trimesh meshes as bodies -----------------------------------------------------------------


@pytest.mark.parametrize("query", [sc.distance, sc.signed_distance, sc.collision])
def test_a_trimesh_mesh_is_the_convex_hull_of_its_vertices(query):
    mesh = box_mesh()
    pose = homogeneous(TURN, SHIFT)
    expected = query(CUBE, CUBE, pose_b=pose)
    got = query(mesh, mesh, pose_b=pose)
    assert got.distance == expected.distance and got.certified
    assert sc.collide(mesh, mesh, pose_b=pose) == sc.collide(CUBE, CUBE, pose_b=pose)
    # Its hull has the same vertices, so it is the same body.
    assert query(mesh.convex_hull, mesh, pose_b=pose).distance == pytest.approx(
        expected.distance, abs=1e-12)


def test_a_trimesh_mesh_builds_polyhedra_compound_bodies_scenes_and_batches():
    mesh = box_mesh()
    body = sc.ConvexPolyhedron(mesh)
    assert np.array_equal(body.vertices, mesh.vertices)
    assert np.array_equal(sc.as_polyhedron(mesh).vertices, mesh.vertices)
    compound = sc.CompoundBody([mesh, trimesh.PointCloud(CUBE + [2, 0, 0])])
    assert len(compound) == 2
    batch = sc.distance_many([mesh, mesh], [mesh, CUBE], poses_b=np.stack([np.eye(4)] * 2) +
                             np.pad(np.array([[[0, 0, 0, 3.0]]] * 2), ((0, 0), (0, 3), (0, 0))))
    assert batch.distance.tolist() == [2.0, 2.0]
    scene = sc.Scene()
    ids = scene.add(mesh)
    more = scene.add([mesh, CUBE], np.stack([homogeneous(TURN, SHIFT), np.eye(4)]))
    assert len(ids) == 1 and len(more) == 2
    found = scene.pairs_within(10.0)
    assert len(found) == 3


def test_a_single_mesh_serves_every_row_of_a_batch():
    mesh, ball = box_mesh(), trimesh.creation.icosphere(radius=0.5)
    poses = np.tile(np.eye(4), (3, 1, 1))
    poses[:, 0, 3] = [2, 3, 4]
    expected = sc.distance_many(CUBE, ball.vertices, poses_b=poses)
    assert sc.distance_many(mesh, ball, poses_b=poses).distance.tolist() \
        == expected.distance.tolist()
    assert sc.collide_many(mesh, [ball] * 3, poses_b=poses).colliding.tolist() == [False] * 3
    compound = sc.CompoundBody([CUBE])
    assert sc.distance_many(compound, ball, poses_b=poses).distance.tolist() \
        == expected.distance.tolist()


def test_a_mesh_that_is_not_three_dimensional_points_is_refused_naming_the_argument():
    class Drawing:  # what trimesh's Path2D looks like to the queries: 2-D vertices
        vertices = np.zeros((4, 2))

    with pytest.raises(ValueError, match=r"^a must be an \(n, 3\) array"):
        sc.distance(Drawing(), CUBE)


# ----- poses -------------------------------------------------------------------------------------


@pytest.mark.parametrize("form", ["rotation-pair", "3x4", "list-4x4", "list-3x4", "tuple-pair"])
def test_poses_in_the_forms_users_have(form):
    expected = sc.distance(CUBE, CUBE, pose_b=homogeneous(TURN, SHIFT))
    pose = {
        "rotation-pair": (TURN, SHIFT),
        "3x4": homogeneous(TURN, SHIFT)[:3],
        "list-4x4": homogeneous(TURN, SHIFT).tolist(),
        "list-3x4": homogeneous(TURN, SHIFT)[:3].tolist(),
        "tuple-pair": (TURN.as_matrix().tolist(), tuple(SHIFT)),
    }[form]
    got = sc.distance(CUBE, CUBE, pose_b=pose)
    assert got.distance == expected.distance and got.certified


def test_a_rotation_alone_turns_the_body_about_its_origin():
    far = CUBE + [4, 0, 0]
    expected = sc.distance(CUBE, far, pose_b=homogeneous(TURN, [0, 0, 0]))
    assert sc.distance(CUBE, far, pose_b=TURN).distance == expected.distance


def test_batches_and_scenes_take_rotation_stacks_and_3x4_poses():
    turns = Rotation.from_rotvec([[0.3, -0.2, 0.9], [0, 0, 1.5], [1, 0, 0]])
    shifts = np.array([[3.0, 0, 0], [0, 4, 0], [0, 0, 5]])
    matrices = np.stack([homogeneous(turns[i], shifts[i]) for i in range(3)])
    expected = sc.distance_many([CUBE] * 3, [CUBE] * 3, poses_b=matrices).distance
    assert sc.distance_many([CUBE] * 3, [CUBE] * 3, poses_b=(turns, shifts)).distance.tolist() \
        == expected.tolist()
    assert sc.distance_many([CUBE] * 3, [CUBE] * 3, poses_b=matrices[:, :3]).distance.tolist() \
        == expected.tolist()
    scene = sc.Scene()
    ids = scene.add([CUBE] * 3, (turns, shifts))
    placed = np.stack([scene.pose(int(i)) for i in ids])
    assert np.allclose(placed, matrices, atol=1e-15)
    scene.set_poses(ids, matrices[:, :3] + [0, 0, 0, 1])
    assert np.allclose(scene.pose(int(ids[0]))[:3, 3], shifts[0] + 1)


def test_a_list_of_poses_in_any_form_places_bodies_one_by_one():
    turns = Rotation.from_rotvec([[0.3, -0.2, 0.9], [0, 0, 1.5]])
    shifts = np.array([[3.0, 0, 0], [0, 4, 0]])
    matrices = np.stack([homogeneous(turns[i], shifts[i]) for i in range(2)])
    pairs = [(turns[i], shifts[i]) for i in range(2)]
    expected = sc.distance_many([CUBE] * 2, [CUBE] * 2, poses_b=matrices).distance.tolist()
    for poses in (pairs, tuple(pairs), [matrices[0], pairs[1]], [pairs[0], matrices[1][:3]]):
        assert sc.distance_many([CUBE] * 2, [CUBE] * 2, poses_b=poses).distance.tolist() == expected
        assert sc.distance_many(CUBE, CUBE, poses_b=poses).distance.tolist() == expected
    far = CUBE + [4, 0, 0]
    assert sc.distance_many(CUBE, far, poses_b=[turns[0], turns[1]]).distance.tolist() \
        == sc.distance_many(CUBE, far, poses_b=turns).distance.tolist()
    scene = sc.Scene()
    ids = scene.add([CUBE] * 2, pairs)
    assert np.allclose(np.stack([scene.pose(int(i)) for i in ids]), matrices, atol=1e-15)
    scene.set_poses(ids, [(Rotation.identity(), [0, 0, 0]), (Rotation.identity(), [2, 0, 0])])
    assert scene.pose(int(ids[1]))[:3, 3].tolist() == [2, 0, 0]
    compound = sc.CompoundBody([CUBE, CUBE], poses=[(Rotation.identity(), [0, 0, 0]),
                                                    (Rotation.identity(), [2, 0, 0])])
    assert compound.aabb().max.tolist() == [3, 1, 1]
    with pytest.raises(ValueError, match=r"^poses\[1\] is not a rigid motion"):
        sc.CompoundBody([CUBE, CUBE], poses=[(TURN, SHIFT), (TURN.as_matrix() * 2, SHIFT)])


def test_float32_poses_answer_as_the_rigid_motions_they_round():
    """A float32 rotation is off its rotation by its rounding (|R^T R - I| near 1e-7, where a pose
    may be off by 1e-9): it is read as the nearest rotation, and answers as its float64 original."""
    pose = homogeneous(TURN, SHIFT)
    narrow = pose.astype(np.float32)
    expected = sc.distance(CUBE, CUBE, pose_b=pose).distance
    for given in (narrow, narrow[:3], (narrow[:3, :3], SHIFT)):
        got = sc.distance(CUBE, CUBE, pose_b=given)
        assert got.certified and abs(got.distance - expected) <= 1e-6
    many = np.stack([pose, homogeneous(TURN.inv(), -SHIFT)])
    rows = sc.distance_many([CUBE] * 2, [CUBE] * 2, poses_b=many.astype(np.float32))
    assert np.abs(rows.distance - sc.distance_many([CUBE] * 2, [CUBE] * 2, poses_b=many).distance
                  ).max() <= 1e-6
    scene = sc.Scene()
    ids = scene.add([CUBE] * 2, (many[:, :3, :3].astype(np.float32), many[:, :3, 3]))
    placed = np.stack([scene.pose(int(i)) for i in ids])
    assert np.abs(placed - many).max() <= 1e-6
    assert np.abs(placed[0, :3, :3].T @ placed[0, :3, :3] - np.eye(3)).max() <= 1e-15
    scaled = pose.copy()
    scaled[:3, :3] *= 1.01
    with pytest.raises(ValueError, match="^pose_b is not a rigid motion"):
        sc.distance(CUBE, CUBE, pose_b=scaled.astype(np.float32))
    with pytest.raises(ValueError, match=r"^poses_b\[1\] is not a rigid motion"):
        sc.distance_many([CUBE] * 2, [CUBE] * 2,
                         poses_b=np.stack([pose, scaled]).astype(np.float32))


def test_float16_poses_answer_as_the_rigid_motions_they_round():
    """float16 rounds a rotation by up to 5e-4 an entry (|R^T R - I| up to about 2e-3, beyond
    float32's 1e-5): within 84 of its epsilons, as float32 is within 84 of its, it is read as
    the nearest rotation; a scaling of 5% is still refused."""
    pose = homogeneous(TURN, SHIFT)
    half = pose.astype(np.float16)
    assert np.abs(half[:3, :3].astype(float).T @ half[:3, :3] - np.eye(3)).max() > 1e-4
    expected = sc.distance(CUBE, CUBE, pose_b=pose).distance
    for given in (half, (half[:3, :3], SHIFT)):
        got = sc.distance(CUBE, CUBE, pose_b=given)
        assert got.certified and abs(got.distance - expected) <= 5e-3
    scene = sc.Scene()
    placed = scene.pose(int(scene.add(CUBE, half)[0]))
    assert np.abs(placed[:3, :3].T @ placed[:3, :3] - np.eye(3)).max() <= 1e-15
    scaled = pose.copy()
    scaled[:3, :3] *= 1.05
    with pytest.raises(ValueError, match="^pose_b is not a rigid motion"):
        sc.distance(CUBE, CUBE, pose_b=scaled.astype(np.float16))


def test_flags_and_integers_of_the_wrong_type_or_range_name_the_argument():
    """pybind11 took None or 2 for a flag without a word and refused "no" or 2**40 with a message
    naming neither the argument nor what it takes."""
    for keywords in ({"warm_start": "no"}, {"warm_start": None}, {"escalate": 2}):
        (name, value), = keywords.items()
        with pytest.raises(TypeError, match=f"^{name} must be True or False, got "
                                            f"{type(value).__name__}$"):
            sc.Scene(**keywords)
    assert sc.Scene(warm_start=np.bool_(False)).warm_start is False
    query = sc.Query("dual")
    with pytest.raises(TypeError, match="^escalate must be True or False, got str$"):
        query.collide(CUBE, CUBE, escalate="yes")
    with pytest.raises(TypeError, match="^escalate must be True or False, got int$"):
        query.collision(CUBE, CUBE, None, None, 1)
    with pytest.raises(TypeError, match="^escalate must be True or False, got NoneType$"):
        query.collide_many([CUBE], [CUBE], escalate=None)
    with pytest.raises(ValueError, match=r"^joint 'j' child must be at most 2\*\*31 - 1, got "
                                         r"1099511627776$"):
        sc.Joint("j", "revolute", 0, 2 ** 40)
    with pytest.raises(TypeError, match="^joint 'j' parent must be an integer, got float$"):
        sc.Joint("j", "revolute", 0.0, 1)
    with pytest.raises(TypeError, match="^joint 'j' lower must be a real number, got str$"):
        sc.Joint("j", "revolute", 0, 1, lower="-1")
    with pytest.raises(TypeError, match="^joint 'j' type must be a string, got int$"):
        sc.Joint("j", 3, 0, 1)
    robot = sc.Robot(["a", "b"], [sc.Joint("j", "revolute", 0, 1, lower=-1, upper=1)],
                     [("ga", 0, None, sc.Sphere(0.1)), ("gb", 1, [[1, 0, 0, 3], [0, 1, 0, 0],
                                                                  [0, 0, 1, 0]], sc.Sphere(0.1))])
    model, pairs = robot.model, [[0, 1]]
    with pytest.raises(TypeError, match="^gradient must be True or False, got str$"):
        model.check(pairs, [[0.0]], query, gradient="no")
    with pytest.raises(ValueError, match=r"^max_iterations must be at most 2\*\*31 - 1, got "):
        model.check_motion(pairs, [[0.0]], [[0.5]], query, max_iterations=2 ** 31)
    scene = sc.Scene()
    scene.add(CUBE)
    with pytest.raises(ValueError, match="^id must be at least 0, got -1$"):
        scene.body(-1)
    with pytest.raises(TypeError, match="^id must be an integer, got str$"):
        scene.pose("0")


@pytest.mark.parametrize(
    ("pose", "error", "message"),
    [
        (np.zeros((3, 5)), ValueError, r"pose_b must be a \(4, 4\) or \(3, 4\) rigid transform"),
        (np.eye(4)[:2], ValueError, r"got shape \(2, 4\)"),
        (np.eye(4)[:3] * 2, ValueError, "pose_b"),
        ([np.eye(4)[0]] * 5, ValueError, "got a sequence of 5 items"),
        ((TURN, [1, 2]), ValueError, r"pose_b's translation must be a \(3,\) translation"),
        ((Rotation.from_rotvec([[0, 0, 1]] * 2), SHIFT), ValueError, "pose_b's rotation"),
    ],
)
def test_wrong_poses_are_refused_naming_the_argument(pose, error, message):
    with pytest.raises(error, match=message):
        sc.distance(CUBE, CUBE, pose_b=pose)


def test_plots_read_poses_as_the_queries_do():
    pytest.importorskip("matplotlib")
    from swarmcollide.plot import plot_body, plot_pair

    def frame(figure):
        ax = figure.axes[0]
        return ax.get_xlim(), ax.get_ylim(), ax.get_zlim(), ax.get_title()

    capsule = sc.Capsule(0.3, 1)
    assert frame(plot_body(capsule, pose=TURN)) == frame(plot_body(capsule, pose=homogeneous(
        TURN, [0, 0, 0])))
    assert frame(plot_pair(CUBE, CUBE, pose_b=(TURN, SHIFT))) == frame(
        plot_pair(CUBE, CUBE, pose_b=homogeneous(TURN, SHIFT)))
    with pytest.raises(ValueError, match="^pose is not a rigid motion"):
        plot_body(capsule, pose=np.diag([2.0, 1, 1, 1]))
    with pytest.raises(ValueError, match="^pose_a's translation must be"):
        plot_pair(CUBE, CUBE, pose_a=(TURN, [1, 2]))


def test_a_pose_keyword_of_the_other_kind_of_query_names_the_right_ones():
    for batch in (sc.distance_many, sc.collide_many, sc.signed_distance_many):
        for wrong in ("pose_a", "pose_b"):
            taken = r"poses_a and poses_b \(one pose per row\)"
            with pytest.raises(TypeError, match=f"^{batch.__name__} takes {taken}, not {wrong}$"):
                batch(CUBE, CUBE, **{wrong: np.eye(4)})
    for query in (sc.distance, sc.signed_distance, sc.collide, sc.collision):
        message = f"^{query.__name__} takes pose_a and pose_b, not poses_b$"
        with pytest.raises(TypeError, match=message):
            query(CUBE, CUBE, poses_b=np.eye(4)[None])


# ----- quaternions -------------------------------------------------------------------------------


def test_quaternions_in_either_order_give_scipys_rotation():
    turns = Rotation.from_rotvec(np.random.default_rng(0).normal(size=(5, 3)))
    xyzw = turns.as_quat()  # SciPy writes the scalar last
    wxyz = np.roll(xyzw, 1, axis=1)
    for order, q in (("xyzw", xyzw), ("wxyz", wxyz)):
        single = sc.pose_from_quaternion(q[0], SHIFT, order=order)
        assert np.allclose(single[:3, :3], turns[0].as_matrix(), atol=1e-15)
        assert single[:3, 3].tolist() == SHIFT.tolist() and single[3].tolist() == [0, 0, 0, 1]
        many = sc.pose_from_quaternion(q, np.tile(SHIFT, (5, 1)), order=order)
        assert many.shape == (5, 4, 4)
        assert np.allclose(many[:, :3, :3], turns.as_matrix(), atol=1e-15)
    # Slightly off unit norm (printed to 4 digits): normalised, then a rigid pose.
    rounded = sc.pose_from_quaternion([0.7071, 0.7071, 0, 0], order="wxyz")
    assert sc.distance(CUBE, CUBE + [3, 0, 0], pose_b=rounded).certified


@pytest.mark.parametrize(
    ("arguments", "keywords", "error", "message"),
    [
        (([1, 0, 0, 0],), {}, TypeError, "order"),
        (([1, 0, 0, 0],), {"order": "zyxw"}, ValueError, "order must be 'wxyz'"),
        (([1, 0, 0, 0],), {"order": b"wxyz"}, TypeError, "order must be a string"),
        (([0, 0, 0, 0],), {"order": "wxyz"}, ValueError, "quaternion has norm 0"),
        (([2, 0, 0, 0],), {"order": "wxyz"}, ValueError, "quaternion has norm 2"),
        (([1e300, 0, 0, 0],), {"order": "wxyz"}, ValueError, "quaternion has norm 1e.300: "),
        (([1e300, 1e300, 1e300, 1e-300],), {"order": "xyzw"}, ValueError,
         "quaternion has norm 1.73205e.300: "),
        (([1e308] * 4,), {"order": "wxyz"}, ValueError,
         r"quaternion has norm above the largest double \(1.8e308\)"),
        ((np.ma.masked_array([1.0, 0, 0, 0], mask=[0, 0, 0, 1]),), {"order": "wxyz"}, TypeError,
         r"quaternion is a NumPy masked array, whose mask would be ignored: pass "
         r"quaternion.filled\(value\)"),
        (([[1, 0, 0, 0], [0, 0, 0, 0]],), {"order": "xyzw"}, ValueError, r"quaternion\[1\]"),
        (([1, 0, 0, np.nan],), {"order": "wxyz"}, ValueError, "NaN or infinite"),
        (([1, 0, 0],), {"order": "wxyz"}, ValueError, r"shape \(4,\) or \(m, 4\)"),
        (([1j, 0, 0, 0],), {"order": "wxyz"}, TypeError, "quaternion must hold real numbers"),
        (("1 0 0 0",), {"order": "wxyz"}, TypeError, "quaternion must be an array"),
        (([1, 0, 0, 0], [1, 2]), {"order": "wxyz"}, ValueError, r"translation must have shape"),
        (([1, 0, 0, 0], [1, 2, np.inf]), {"order": "wxyz"}, ValueError, "translation has a NaN"),
    ],
)
def test_bad_quaternions_are_refused_naming_the_argument(arguments, keywords, error, message):
    with pytest.raises(error, match=message):
        sc.pose_from_quaternion(*arguments, **keywords)


# ----- arguments refused with a message that names them (item 8) ---------------------------------


def test_thread_counts_beyond_any_integer_are_value_errors_everywhere():
    huge = 2**63
    for call in (
        lambda: sc.distance_many([CUBE], [CUBE], threads=huge),
        lambda: sc.collide_many([CUBE], [CUBE], threads=huge),
        lambda: sc.signed_distance_many([CUBE], [CUBE], threads=huge),
        lambda: sc.Scene(threads=huge),
        lambda: scd.distance_many(STACK, STACK, threads=huge),
    ):
        with pytest.raises(ValueError, match=r"threads must be in \[1, 1024\].*got 9223372036854775808"):
            call()


def test_names_given_as_bytes_are_type_errors_naming_the_argument():
    for call, name in (
        (lambda: sc.distance(CUBE, CUBE, method=b"fcl"), "method"),
        (lambda: sc.Query(b"fcl"), "method"),
        (lambda: sc.distance_many([CUBE], [CUBE], method=b"fcl"), "method"),
        (lambda: sc.Scene(method=b"fcl"), "method"),
        (lambda: sc.Scene(broadphase=b"naive"), "broadphase"),
        (lambda: scd.distance_many(STACK, STACK, method=b"fcl"), "method"),
        (lambda: sc.as_polyhedron(CUBE, name=b"body"), "name"),
    ):
        with pytest.raises(TypeError, match=f"^{name} must be a string, got bytes"):
            call()


def test_complex_directions_and_weights_are_type_errors_naming_the_argument():
    body = sc.ConvexPolyhedron(CUBE)
    complex_direction = np.array([1j, 0, 0])
    for call, name in (
        (lambda: body.support(complex_direction), "direction"),
        (lambda: body.support_index(complex_direction), "direction"),
        (lambda: sc.separation(CUBE, CUBE, complex_direction), "direction"),
        (lambda: sc.objective(CUBE, CUBE, np.full(8, 1 / 8 + 0j), np.full(8, 1 / 8)), "weights_a"),
        (lambda: sc.constraint_violation(np.ones(2), np.ones(2) * 1j), "weights_b"),
        (lambda: sc.is_feasible(np.ones(2) * 1j, np.ones(2)), "weights_a"),
        (lambda: sc.project_onto_simplex(np.ones(3) * 1j), "weights"),
        (lambda: body.support("xyz"), "direction"),
    ):
        with pytest.raises(TypeError, match=f"^{name} must"):
            call()
    with pytest.raises(ValueError, match=r"direction must be a 3-vector .* got shape \(2,\)"):
        body.support([1, 0])
    with pytest.raises(ValueError, match="direction must be finite"):
        body.support([np.nan, 0, 0])
    assert body.support([1, 1, 1]).tolist() == [1, 1, 1]
    assert body.support(np.array([1, 1, 1], dtype=np.float32)).tolist() == [1, 1, 1]


def test_masked_arrays_are_refused_naming_the_argument_and_the_fix():
    # NumPy's conversions drop a mask: the masked entries (here a far point, and a pose's
    # scaling) would be read as numbers without a word.
    cube = np.ma.masked_array(np.vstack([CUBE, [[100.0, 0, 0]]]))
    cube[-1] = np.ma.masked
    shifted = np.ma.masked_array(np.eye(4), mask=np.eye(4, dtype=bool) & False)
    shifted[0, 3] = 3.0
    shifted[0, 0] = np.ma.masked
    stack = np.ma.masked_array(np.stack([CUBE, CUBE]))
    poses = np.ma.masked_array(np.tile(np.eye(4), (2, 1, 1)))
    scene = sc.Scene()
    for call, name in (
        (lambda: sc.distance(cube, CUBE + 3), "a"),
        (lambda: sc.collide(CUBE, cube), "b"),
        (lambda: sc.Query("exact").distance(CUBE, cube), "b"),
        (lambda: sc.ConvexPolyhedron(cube), "points"),
        (lambda: sc.distance(CUBE, CUBE, pose_b=shifted), "pose_b"),
        (lambda: sc.distance(CUBE, CUBE, pose_b=(shifted[:3, :3], [3.0, 0, 0])),
         "pose_b's rotation"),
        (lambda: sc.distance_many(stack, [CUBE, CUBE]), "As"),
        (lambda: sc.distance_many([cube, CUBE], [CUBE, CUBE]), r"As\[0\]"),
        (lambda: sc.distance_many(CUBE, CUBE, poses_b=poses), "poses_b"),
        (lambda: scene.add(cube), "bodies"),
        (lambda: scene.add(CUBE, shifted), "poses"),
        (lambda: sc.time_of_impact(CUBE, CUBE, pose_b=(np.eye(4), shifted)), "pose_b end"),
    ):
        with pytest.raises(TypeError, match=f"^{name} is a NumPy masked array, whose mask would be "
                           f"ignored: pass {name}.filled"):
            call()
    assert len(scene) == 0
    # Filled (or given as its data), it is an array like any other.
    assert sc.distance(cube.filled(0.0), CUBE + [3, 0, 0]).distance == 2.0
    assert sc.distance(CUBE, CUBE + [3, 0, 0], pose_b=np.asarray(np.eye(4))).distance == 2.0


def test_a_mesh_given_whole_as_parts_points_to_from_mesh():
    with pytest.raises(TypeError, match="CompoundBody.from_mesh decomposes a mesh into parts"):
        sc.CompoundBody(box_mesh())


def test_a_sample_count_that_is_not_an_integer_is_refused_by_name():
    with pytest.raises(TypeError, match="samples must be an integer, got float"):
        sc.CompoundBody.from_mesh(box_mesh(), decompose="hull", samples=2.5, cache=False,
                                  progress=False)
    # Refused before trimesh asks for the memory (a point per sample: 24 TB here).
    with pytest.raises(ValueError, match="samples must be at most 10,000,000 .* got "
                       "1,000,000,000,000"):
        sc.CompoundBody.from_mesh(box_mesh(), decompose="hull", samples=10**12, cache=False,
                                  progress=False)
    with pytest.raises(ValueError, match="samples must be at most 10,000,000"):
        sc.measure_deviation(box_mesh(), sc.CompoundBody([box_mesh().vertices]),
                             samples=10**12)
