"""Pickling and copying: bodies, results, queries, scenes and robots come back as the same objects
(the same answers bit for bit), across processes too, and a corrupted state is a ValueError."""

import copy
import multiprocessing
import pickle

import numpy as np
import pytest

import swarmcollide as sc
from contract import CUBE, assert_identical
from shape_checks import SHAPES, at

ROTATION = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
LYING = np.array([[1.0, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 2], [0, 0, 0, 1]])


def round_trip(value):
    return pickle.loads(pickle.dumps(value))


def placed_cylinder():
    """A curved part placed by a pose: a ConvexPolyhedron with its support function."""
    return sc.CompoundBody([sc.Cylinder(0.1, 1.0)], poses=[LYING]).parts[0]


def cloud(points=60, seed=1):
    """A polyhedron of many points (its queries climb its hull rather than scan it)."""
    return sc.ConvexPolyhedron(np.random.default_rng(seed).normal(size=(points, 3)))


BODIES = SHAPES + [
    sc.ConvexPolyhedron(CUBE),
    cloud(),
    sc.ConvexPolyhedron([[0.0, 0.0, 0.0]], radius=0.25),
    sc.ConvexPolyhedron(sc.Cylinder(0.3, 1.1)),
    placed_cylinder(),
]

PROBES = [sc.Box([0.5, 0.5, 0.5]), sc.Cylinder(0.25, 0.5), cloud(12, seed=2)]
POSES = [at(3.0), at(0.4, 0.1, -0.2, rotation=ROTATION), at(1.1, 0.9)]


def compounds():
    return [
        sc.CompoundBody([CUBE, CUBE + [1, 0, 0], CUBE + [0, 1, 0]]),
        sc.CompoundBody([sc.Box([1, 1, 0.1]), sc.Cylinder(0.1, 1)], poses=[np.eye(4), LYING]),
        sc.CompoundBody([sc.Sphere(0.5), cloud(40)],
                        poses=[(ROTATION, [0.5, 0, 0]), (np.eye(3), [-1, 0, 0])]),
    ]


def answers(body, method="dual", probes=PROBES):
    """Every pair query `method` answers of `body` against the probes at the poses."""
    query = sc.Query(method)
    # A collision is the result a collide query gives.
    kinds = [kind for kind in ("distance", "signed_distance", "collision")
             if kind.replace("collision", "collide") in sc.METHODS[method].queries]
    return [getattr(query, kind)(body, probe, pose_b=pose)
            for probe in probes for pose in POSES for kind in kinds]


def assert_same_answers(first, second, method="dual", probes=PROBES):
    for x, y in zip(answers(first, method, probes), answers(second, method, probes)):
        assert_identical(x, y)
        assert type(x) is type(y)


def fields(value):
    """The public data of a core object: its attributes that are not methods."""
    return {name: getattr(value, name) for name in dir(value)
            if not name.startswith("_") and not callable(getattr(value, name))}


def is_core_object(value):
    """An object of a class of the C++ core, or of a Python subclass of one."""
    return any(cls.__module__ == "swarmcollide._core" for cls in type(value).__mro__)


def assert_same_fields(first, second):
    """Two objects of one type with every public field equal (recursively, arrays exactly)."""
    assert type(first) is type(second)
    if isinstance(first, (list, tuple)):
        assert len(first) == len(second)
        for x, y in zip(first, second):
            assert_same_fields(x, y)
    elif is_core_object(first) and not isinstance(first, sc.Scene):
        values = fields(first)
        assert values, type(first)
        for name, value in values.items():
            assert_same_fields(value, getattr(second, name))
    elif isinstance(first, np.ndarray):
        assert first.dtype == second.dtype
        np.testing.assert_array_equal(first, second)
    else:
        assert first == second


@pytest.mark.parametrize("body", BODIES, ids=repr)
def test_every_body_answers_bit_for_bit_after_pickling(body):
    again = round_trip(body)
    assert type(again) is type(body) and repr(again) == repr(body)
    np.testing.assert_array_equal(again.vertices, body.vertices)
    assert again.rounding_radius == body.rounding_radius and again.curved == body.curved
    assert_same_answers(body, again)
    assert_same_answers(body, again, method="exact")


@pytest.mark.parametrize("method", ["ipso", "penalty", "fcl"])
def test_polyhedra_answer_alike_by_every_method(method):
    body = cloud(20)
    # The swarms and the penalty method weigh points: polyhedra only.
    polyhedra = [probe for probe in PROBES if not probe.curved]
    assert_same_answers(body, round_trip(body), method=method, probes=polyhedra)


@pytest.mark.parametrize("body", compounds(), ids=repr)
def test_compound_bodies_keep_their_parts_and_poses(body):
    again = round_trip(body)
    assert type(again) is sc.CompoundBody and repr(again) == repr(body)
    np.testing.assert_array_equal(again.part_poses, body.part_poses)
    assert [type(p) for p in again.given_parts] == [type(p) for p in body.given_parts]
    for mine, theirs in zip(again.parts, body.parts):
        np.testing.assert_array_equal(mine.vertices, theirs.vertices)
    assert_same_answers(body, again)


def test_a_compound_body_keeps_its_decomposition_record():
    record = sc.Decomposition(method="hull", parameters={}, parts=1, seconds=0.5,
                              parts_to_mesh=0.0, mesh_to_parts=0.0, samples=10, spacing=0.1,
                              mesh_hash="abc")
    body = sc.CompoundBody([CUBE], record)
    again = round_trip(body)
    assert type(again) is sc.CompoundBody and again.decomposition == record


class LabelledBox(sc.Box):
    def __init__(self, half_extents, label):
        super().__init__(half_extents)
        self.label = label


def test_a_subclass_keeps_its_type_and_attributes():
    again = round_trip(LabelledBox([1.0, 2.0, 3.0], label="crate"))
    assert type(again) is LabelledBox and again.label == "crate"
    np.testing.assert_array_equal(again.half_extents, [1.0, 2.0, 3.0])



def test_a_curved_part_placed_twice_refuses_pickling():
    # Its parameters keep the last pose only, so they would rebuild another body.
    twice = sc.CompoundBody([placed_cylinder()], poses=[LYING]).parts[0]
    with pytest.raises(TypeError, match="placed by two poses"):
        pickle.dumps(twice)


def results():
    """One result of every kind the library returns, with its fields filled."""
    a, b = cloud(10), cloud(12, seed=3)
    ell = compounds()[0]
    scene = sc.Scene(method="exact")
    scene.add([sc.Box([0.5, 0.5, 0.5])] * 3, np.stack([np.eye(4)] * 3))
    moved = np.eye(4)
    moved[0, 3] = 0.9
    scene.set_poses(1, moved)
    start, end = np.eye(4), np.eye(4)
    start[0, 3], end[0, 3] = -3, 3
    scene.set_poses(2, start)
    robot = two_link_robot()
    q = [[0.0, 0.0], [0.0, 3.0]]
    stacks = np.random.default_rng(4).normal(size=(5, 8, 3))
    starts, ends = np.tile(np.eye(4), (2, 1, 1)), np.tile(np.eye(4), (2, 1, 1))
    starts[:, 0, 3], ends[:, 0, 3] = 3, -3
    return {
        "distance": sc.distance(a, b, pose_b=at(2.0)),
        "ipso": sc.distance(a, b, pose_b=at(2.0), method="ipso", seed=3),
        "escalated": sc.collision(a, b, method="ipso", swarm_size=4, max_iterations=2),
        "signed": sc.signed_distance(a, b),
        "compound": sc.distance(ell, ell, pose_b=at(0.5, 2.5)),
        "batch": sc.distance_many(stacks, stacks + [2.0, 0, 0], threads=1),
        "time_of_impact": sc.time_of_impact(a, b, pose_b=(at(3.0), at(-3.0))),
        "time_of_impact_many": sc.time_of_impact_many([a, a], [b, b], poses_b=(starts, ends)),
        "scene": scene.colliding_pairs(),
        "no_pairs": sc.Scene().colliding_pairs(),
        "no_rows": sc.distance_many(stacks[:0], stacks[:0]),
        "contacts": scene.contacts(),
        "scene_stats": scene.stats,
        "sweep": scene.sweep(2, end),
        "hull": a.hull(),
        "aabb": a.aabb(),
        "nodes": ell.tree,
        "coefficients": sc.rank_adaptive_coefficients(2, 10),
        "query": sc.Query("ipso", tolerance=1e-6, seed=7, swarm_size=30,
                          constraint_handling="projection"),
        "joints": robot.model.joints,
        "robot_distances": robot.model.distances(robot._pair_table, q, sc.Query()),
        "robot_check": robot.model.check(robot._pair_table, q, sc.Query(), gradient=True),
        "robot_motion": robot.model.check_motion(robot._pair_table, [[0.0, 0.0]], [[0.0, 3.0]],
                                                 sc.Query("exact")),
        "robot_check_record": robot.check(q),
        "robot_motion_record": robot.check_motion([0.0, 0.0], [0.0, 3.0]),
    }


def two_link_robot():
    elbow = np.eye(4)
    elbow[0, 3] = 1.0
    joints = [sc.Joint("shoulder", "revolute", 0, 1, lower=-3, upper=3),
              sc.Joint("elbow", "revolute", 1, 2, origin=elbow, lower=-3, upper=3)]
    box = sc.Box([0.1, 0.1, 0.1])
    geometries = [("base", 0, None, box), ("upper", 1, None, sc.Sphere(0.1)),
                  ("fore", 2, elbow, sc.CompoundBody([box, sc.Cylinder(0.05, 0.2)]))]
    return sc.Robot(["base", "upper", "fore"], joints, geometries)


RESULTS = results()


@pytest.mark.parametrize("name", RESULTS)
def test_results_round_trip_with_every_field_equal(name):
    value = RESULTS[name]
    again = round_trip(value)
    if name.startswith("robot_") and name.endswith("_record"):
        # A dataclass of arrays: compared field by field, exactly.
        for field, mine in vars(value).items():
            np.testing.assert_array_equal(getattr(again, field), mine, err_msg=field)
    else:
        assert_same_fields(value, again)
    if " object at 0x" not in repr(value):
        assert repr(again) == repr(value)


def test_the_results_picked_fill_their_fields():
    # What the round trips compare is not empty or default.
    assert len(RESULTS["ipso"].history) > 1 and np.count_nonzero(RESULTS["ipso"].weights_a) > 4
    assert RESULTS["escalated"].escalated_from == "ipso"
    assert RESULTS["compound"].part_a == 2 and RESULTS["compound"].stats.part_pairs == 9
    assert len(RESULTS["scene"]) == 1 and len(RESULTS["contacts"].points) == 4
    assert len(RESULTS["sweep"]) == 2 and RESULTS["time_of_impact"].touches
    assert RESULTS["robot_check"].gradient.shape == (2, 2)


def test_a_query_keeps_its_method_and_parameters():
    query = RESULTS["query"]
    again = round_trip(query)
    assert (again.method, again.tolerance, again.seed) == ("ipso", 1e-6, 7)
    assert again.parameters == query.parameters
    a, b = cloud(10), cloud(12, seed=3)
    assert_identical(again.distance(a, b, pose_b=at(2.0)), query.distance(a, b, pose_b=at(2.0)))


def test_a_robot_answers_alike_after_pickling():
    robot = two_link_robot().disable_pairs([("base", "upper")])
    robot = robot.add_obstacle(sc.Sphere(0.2), at(0.0, 1.5), name="ball")
    again = round_trip(robot)
    assert again.pairs == robot.pairs and again.geometry_names == robot.geometry_names
    q = np.random.default_rng(5).uniform(-3, 3, size=(20, 2))
    mine, theirs = again.check(q, gradient=True), robot.check(q, gradient=True)
    for field, value in vars(theirs).items():
        np.testing.assert_array_equal(getattr(mine, field), value, err_msg=field)
    model = round_trip(robot.model)
    np.testing.assert_array_equal(model.geometry_poses(q), robot.model.geometry_poses(q))
    assert model.link_names == robot.model.link_names


@pytest.mark.parametrize("options", [{}, {"nearest": False}, {"gradient": True, "limits": "clamp",
                                                                "method": "exact", "seed": 3}])
def test_a_robot_checker_answers_alike_after_pickling_or_copying(options):
    robot = two_link_robot().add_obstacle(sc.Sphere(0.2), at(0.0, 1.5), name="ball")
    checker = robot.checker(**options)
    q = np.random.default_rng(7).uniform(-3, 3, size=(10, 2))
    for again in (round_trip(checker), copy.copy(checker), copy.deepcopy(checker)):
        assert type(again) is sc.RobotChecker and repr(again) == repr(checker)
        for row in q:
            mine, theirs = again(row), checker(row)
            for field, value in vars(theirs).items():
                np.testing.assert_array_equal(getattr(mine, field), value, err_msg=field)
            assert again.collision_free(row) == checker.collision_free(row)
    # It answers the robot it was made for, not one changed after: as the original does.
    robot.disable_pairs([("upper", "ball")])
    mine, theirs = round_trip(checker)([0.0, 1.5]), checker([0.0, 1.5])
    for field, value in vars(theirs).items():
        np.testing.assert_array_equal(getattr(mine, field), value, err_msg=field)


def busy_scene(warm_start):
    """A scene that has lived: bodies added and removed, moved, filtered and excluded."""
    rng = np.random.default_rng(6)
    scene = sc.Scene(broadphase="dynamic_aabb_tree", warm_start=warm_start, seed=3)
    poses = np.tile(np.eye(4), (12, 1, 1))
    poses[:, :3, 3] = rng.uniform(0, 2.5, (12, 3))
    scene.add(rng.normal(size=(10, 8, 3)) * 0.4, poses[:10])
    scene.add([sc.Cylinder(0.3, 0.5), compounds()[1]], poses[10:], group=2, mask=1)
    scene.remove([3, 11])
    scene.exclude([[0, 1], [4, 7]])
    scene.set_filter(5, group=4, mask=4)
    for _ in range(2):
        poses[:, :3, 3] += rng.normal(0, 0.05, (12, 3))
        ids = scene.ids
        scene.set_poses(ids, poses[ids])
        scene.colliding_pairs()
    scene.add(sc.Sphere(0.3))
    scene.remove(12)
    return scene


def scene_answers(scene):
    return [scene.colliding_pairs(), scene.pairs_within(0.5), scene.contacts(),
            scene.min_distance(), scene.nearest(scene.ids, k=2)]


def test_a_scene_without_warm_starts_answers_bit_for_bit_after_pickling():
    scene = busy_scene(warm_start=False)
    again = round_trip(scene)
    np.testing.assert_array_equal(again.ids, scene.ids)
    for id in scene.ids:
        np.testing.assert_array_equal(again.pose(id), scene.pose(id))
        assert type(again.body(id)) is type(scene.body(id))
    assert (again.method, again.broadphase, again.seed, again.warm_start) == (
        scene.method, scene.broadphase, scene.seed, scene.warm_start)
    for mine, theirs in zip(scene_answers(again), scene_answers(scene)):
        assert_same_fields(mine, theirs)
    # Ids go on where the original's do.
    assert again.add(sc.Sphere(1.0)) == scene.add(sc.Sphere(1.0)) == 13


def test_an_empty_scene_round_trips():
    again = round_trip(sc.Scene(method="exact", broadphase="brute_force", threads=1))
    assert len(again) == 0 and (again.method, again.broadphase) == ("exact", "brute_force")
    assert again.add(sc.Sphere(1.0)) == 0


def test_a_warm_scene_gives_the_same_verdicts_after_pickling():
    # Its cached proofs are not pickled: values agree to the tolerance, verdicts exactly.
    scene = busy_scene(warm_start=True)
    again = round_trip(scene)
    assert again.warm_start
    mine, theirs = again.pairs_within(0.5), scene.pairs_within(0.5)
    np.testing.assert_array_equal(mine.pairs, theirs.pairs)
    np.testing.assert_allclose(mine.distance, theirs.distance, rtol=0, atol=1e-8)


def distance_of(pair):
    a, b, pose = pair
    return sc.distance(a, b, pose_b=pose)


def test_a_spawned_pool_answers_as_this_process_does():
    pairs = [(body, probe, pose) for body in BODIES + compounds() for probe in PROBES[:2]
             for pose in POSES[:2]]
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        theirs = pool.map(distance_of, pairs)
    for pair, result in zip(pairs, theirs):
        assert_identical(result, distance_of(pair))


COPYABLE = BODIES + compounds() + [RESULTS[name] for name in RESULTS if "record" not in name]


@pytest.mark.parametrize("copier", [copy.copy, copy.deepcopy])
@pytest.mark.parametrize("value", COPYABLE, ids=lambda v: type(v).__name__)
def test_copies_are_equal_objects(value, copier):
    again = copier(value)
    assert again is not value
    assert_same_fields(value, again)


@pytest.mark.parametrize("copier", [copy.copy, copy.deepcopy])
def test_copied_scenes_and_robots_answer_alike(copier):
    scene = busy_scene(warm_start=False)
    for mine, theirs in zip(scene_answers(copier(scene)), scene_answers(scene)):
        assert_same_fields(mine, theirs)
    robot = two_link_robot()
    np.testing.assert_array_equal(copier(robot).check([0.0, 3.0]).min_distance,
                                  robot.check([0.0, 3.0]).min_distance)


def state_of(value):
    return value.__getstate__()


def refuse(cls, state, match):
    with pytest.raises(ValueError, match=match):
        cls.__new__(cls).__setstate__(state)


@pytest.mark.parametrize("value", [sc.Box([1, 2, 3]), cloud(), RESULTS["distance"],
                                   RESULTS["batch"], busy_scene(False), RESULTS["query"]],
                         ids=lambda v: type(v).__name__)
def test_a_state_of_another_version_or_length_is_refused(value):
    state = state_of(value)
    refuse(type(value), (2,) + state[1:], "format version 2 is not 1")
    refuse(type(value), ("1",) + state[1:], "format version '1' is not 1")
    refuse(type(value), state[:-1], f"expected {len(state)} items")
    refuse(type(value), state + (0,), f"expected {len(state)} items")
    refuse(type(value), list(state), "expected a tuple, got list")


def test_corrupted_body_states_name_what_is_wrong():
    points, radius, shape, attributes = state_of(cloud())[1:]
    nan = points.copy()
    nan[3, 1] = np.nan
    refuse(sc.ConvexPolyhedron, (1, nan, radius, shape, attributes), "NaN|finite")
    refuse(sc.ConvexPolyhedron, (1, points[:, :2], radius, shape, attributes), "points")
    refuse(sc.ConvexPolyhedron, (1, points, -1.0, shape, attributes), "radius")
    refuse(sc.ConvexPolyhedron, (1, points, "big", shape, attributes), "radius")
    refuse(sc.ConvexPolyhedron, (1, points, radius, shape, None), "attributes")
    refuse(sc.ConvexPolyhedron, (1, points, radius, (sc.Box([1, 1, 1]), None), attributes),
           "shape")
    curved = state_of(placed_cylinder())
    refuse(sc.ConvexPolyhedron, curved[:1] + (points,) + curved[2:], "not those of its curved")
    refuse(sc.Box, (1, [1.0, np.nan, 1.0], 0.0, {}), "half_extents")
    refuse(sc.Box, (1, [1.0, 1.0], 0.0, {}), "half_extents")
    refuse(sc.Sphere, (1, -1.0, {}), "radius|positive")
    refuse(sc.Ellipsoid, (1, [1.0, 0.0, 1.0], {}), "Ellipsoid")
    parts, poses, attributes = state_of(compounds()[1])[1:]
    refuse(sc.CompoundBody, (1, parts, poses[:1], attributes), "poses")
    refuse(sc.CompoundBody, (1, [], None, attributes), "parts")
    scaled = poses.copy()
    scaled[1, :3, :3] *= 2
    refuse(sc.CompoundBody, (1, parts, scaled, attributes), "poses")
    refuse(sc.CompoundBody, (1, parts, poses, {"decomposition": "x"}), "decomposition")


def test_corrupted_result_states_name_what_is_wrong():
    state = state_of(RESULTS["distance"])
    refuse(sc.DistanceResult, state[:13] + ("newton",) + state[14:], "method")
    refuse(sc.DistanceResult, state[:15] + ("done",), "status")
    refuse(sc.DistanceResult, state[:5] + (np.array([0.5, np.nan]),) + state[6:], "weights_a")
    refuse(sc.DistanceResult, state[:3] + ([1.0, 2.0],) + state[4:], "point_a")
    refuse(sc.DistanceResult, state[:11] + (1,) + state[12:], "colliding")
    batch = state_of(RESULTS["batch"])
    refuse(sc.BatchResult, batch[:2] + (batch[2][:-1],) + batch[3:], "lower_bound has 4 rows")
    refuse(sc.BatchResult, batch[:3] + (batch[3][:, :2],) + batch[4:], "point_a")
    contacts = state_of(RESULTS["contacts"])
    refuse(sc.ContactResult, contacts[:9] + (contacts[9][:-1],) + contacts[10:], "point_pair")
    check = state_of(RESULTS["robot_check"])
    refuse(type(RESULTS["robot_check"]), check[:2] + (check[2][:1],) + check[3:], "min_distance")
    motion = state_of(RESULTS["robot_motion"])
    refuse(type(RESULTS["robot_motion"]), motion[:-1] + (["stuck"],), "status")
    sweep = state_of(RESULTS["sweep"])
    refuse(sc.SweepResult, sweep[:4] + (sweep[4] * 2,) + sweep[5:], "pose_a")
    query = state_of(RESULTS["query"])
    refuse(sc.Query, query[:4] + ({"swarm_size": -3},), "swarm_size")
    refuse(sc.Query, query[:4] + ({"colour": 1},), "colour")
    refuse(sc.Query, ("newton",) + query[1:], "version")
    joint = state_of(RESULTS["joints"][0])
    refuse(sc.Joint, joint[:2] + ("spherical",) + joint[3:], "spherical")
    model = two_link_robot().model
    links, joints, geometries = state_of(model)[1:]
    refuse(type(model), (1, links, joints, geometries + [("wall", 0, None, "brick")]), "wall")
    refuse(type(model), (1, links[:2], joints, geometries), "link")


def test_corrupted_scene_states_name_what_is_wrong():
    state = state_of(busy_scene(warm_start=False))
    ids, bodies = state[9], state[10]
    refuse(sc.Scene, state[:10] + (bodies[:-1],) + state[11:], "bodies has")
    refuse(sc.Scene, state[:9] + (ids[::-1].copy(),) + state[10:], "was given out already")
    refuse(sc.Scene, state[:14] + ([[0, 99]],) + state[15:], "99")
    refuse(sc.Scene, state[:5] + ("octree",) + state[6:], "broadphase")
    for next_id in (2**40, -1):
        refuse(sc.Scene, state[:15] + (next_id,),
               r"next_id must be an integer from 0 to 4294967295, got " + str(next_id))


@pytest.mark.parametrize("protocol", [0, 1])
@pytest.mark.parametrize("value", COPYABLE, ids=lambda v: type(v).__name__)
def test_the_oldest_protocols_pickle_as_protocol_two(value, protocol):
    # They reduce through copyreg's _reduce_ex, which calls the nearest built-in base type:
    # pybind11's refused by an exception that aborted the interpreter.
    again = pickle.loads(pickle.dumps(value, protocol=protocol))
    assert_same_fields(value, again)


@pytest.mark.parametrize("protocol", [0, 1])
def test_scenes_and_robots_pickle_in_the_oldest_protocols(protocol):
    scene = busy_scene(warm_start=False)
    again = pickle.loads(pickle.dumps(scene, protocol=protocol))
    for mine, theirs in zip(scene_answers(again), scene_answers(scene)):
        assert_same_fields(mine, theirs)
    robot = two_link_robot()
    q = [[0.0, 0.0], [0.5, 2.9]]
    copied = pickle.loads(pickle.dumps(robot, protocol=protocol))
    np.testing.assert_array_equal(copied.check(q).min_distance, robot.check(q).min_distance)
