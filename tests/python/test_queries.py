"""The query layer: the method table as Python sees it, the typed keywords, the cached queries,
poses, and the errors bad arguments get."""

import math
import typing

import numpy as np
import pytest
from contract import CUBE, check_contract, pair_scale, separation
from oracle import exact_distance, exact_signed_distance

import swarmcollide as sc
from swarmcollide import _core

KINDS = {"integer": int, "real": float, "choice": str}


def test_methods_are_the_core_table():
    table = _core.method_table()
    assert list(sc.METHODS) == [entry["name"] for entry in table]
    for entry in table:
        info = sc.METHODS[entry["name"]]
        assert info.queries == entry["queries"]
        assert info.always_certified == entry["always_certified"]
        assert [p.name for p in info.parameters] == [p["name"] for p in entry["parameters"]]
        # Each parameter's default is what a query built without it reads.
        assert sc.Query(info.name).parameters == {p.name: p.default for p in info.parameters}
        for p in info.parameters:
            assert p.kind in KINDS
            assert bool(p.choices) == (p.kind == "choice")
            if p.kind == "choice":
                assert p.default in p.choices
            else:
                assert p.minimum <= p.default <= p.maximum
                assert isinstance(p.default, KINDS[p.kind])


def test_parameters_are_the_union_of_the_tables_parameters_with_their_types():
    hints = typing.get_type_hints(sc.Parameters)
    by_name = {p.name: p for info in sc.METHODS.values() for p in info.parameters}
    assert set(hints) == set(by_name)
    for name, p in by_name.items():
        assert hints[name] is KINDS[p.kind], name
    # A parameter shared by several methods has one kind everywhere.
    for info in sc.METHODS.values():
        for p in info.parameters:
            assert p.kind == by_name[p.name].kind


def test_every_parameter_reaches_its_method_and_shows_in_the_repr():
    for name, info in sc.METHODS.items():
        for p in info.parameters:
            value = p.choices[0] if p.kind == "choice" else KINDS[p.kind](p.maximum)
            if p.name == "w_min":  # w_min may not exceed w_max
                value = info.parameters[[q.name for q in info.parameters].index("w_max")].default
            q = sc.Query(name, **{p.name: value})
            assert q.parameters[p.name] == value
            assert f"{p.name}={value!r}" in repr(q)


def test_query_is_built_once_per_distinct_set_of_keywords():
    q = sc.query("ipso", swarm_size=21, tolerance=1e-6)
    assert q is sc.query("ipso", tolerance=1e-6, swarm_size=21)
    assert q is not sc.query("ipso", swarm_size=22, tolerance=1e-6)
    assert (q.method, q.tolerance, q.seed, q.parameters["swarm_size"]) == ("ipso", 1e-6, 0, 21)
    # Equal values of another type are another argument: True is no seed, even once 1 is cached.
    assert sc.query("dual", seed=1) is sc.query("dual", seed=1)
    with pytest.raises(TypeError, match="seed must be an integer, got bool"):
        sc.query("dual", seed=True)
    with pytest.raises(TypeError, match="swarm_size must be an integer, got float"):
        sc.query("ipso", swarm_size=21.0)


def test_the_default_keywords_reach_the_same_query_as_any_other_spelling():
    a, b = CUBE, CUBE + [1.5, 0.2, 0.1]
    for method in ("dual", "fcl"):
        assert sc.distance(a, b, method=method).distance == sc.query(method).distance(a, b).distance
        # An equal tolerance that is not the default object, and seeds equal to 0 but of another
        # type, take the general path: the same answer, and the same type errors.
        spelled = sc.distance(a, b, method=method, tolerance=float("1e-9"), seed=int("0"))
        assert spelled.distance == sc.distance(a, b, method=method).distance
    with pytest.raises(TypeError, match="seed must be an integer, got bool"):
        sc.collide(a, b, seed=False)
    with pytest.raises(TypeError, match="method must be a string, got list"):
        sc.collide(a, b, method=["dual"])
    with pytest.raises(ValueError, match="unknown method 'gjk'"):
        sc.collide(a, b, method="gjk")
    with pytest.raises(ValueError, match="unknown method 'gjk'"):  # not remembered by the failure
        sc.collide(a, b, method="gjk")


def test_module_functions_are_the_cached_querys_answers():
    a, b = CUBE, CUBE + [1.5, 0.2, 0.1]
    q = sc.query("ipso", seed=3, max_iterations=7)
    keywords = dict(method="ipso", seed=3, max_iterations=7)
    assert sc.distance(a, b, **keywords).distance == q.distance(a, b).distance
    assert sc.collide(a, b, **keywords) == q.collide(a, b)
    r = sc.collision(a, b, escalate=False, **keywords)
    assert r.distance == q.collision(a, b, escalate=False).distance
    signed = sc.signed_distance(a, b, method="exact")
    assert signed.distance == sc.Query("exact").signed_distance(a, b).distance


@pytest.mark.parametrize(
    ("keywords", "error", "message"),
    [
        ({"method": "gjk"}, ValueError, "unknown method 'gjk'; choose one of 'dual', 'ipso'"),
        ({"method": "fcl-indep"}, ValueError, "unknown method 'fcl-indep'"),
        ({"method": 3}, TypeError, "method must be a string, got int"),
        ({"seed": -1}, ValueError, r"seed must lie in \[0, 2\*\*64\)"),
        ({"seed": 2**64}, ValueError, "seed must lie in"),
        ({"seed": 1.5}, TypeError, "seed must be an integer, got float"),
        ({"tolerance": -1e-3}, ValueError, r"tolerance must be a number in \[0, 1\]"),
        ({"tolerance": math.nan}, ValueError, "tolerance must be a number"),
        ({"tolerance": 2.0}, ValueError, "tolerance must be a number"),
        ({"tolerance": 1e300}, ValueError, r"\(relative to the pair's size\), got 1e\+300$"),
        ({"tolerance": "1e-9"}, TypeError, "tolerance must be a real number, got str"),
        ({"tolerance": True}, TypeError, "tolerance must be a real number, got bool"),
        ({"swarm_size": 1}, ValueError, r"swarm_size must be an integer in \[2, 10000\], got 1"),
        ({"method": "ipso", "swarm_size": 10**6}, ValueError, r"in \[2, 100000\]"),
        ({"max_iterations": 2**40}, ValueError, r"max_iterations must be an integer in \[0, 10"),
        ({"method": "exact", "max_iterations": 0}, ValueError, r"max_iterations .* in \[1, "),
        ({"swarm_size": 4.5}, TypeError, "swarm_size must be an integer, got float"),
        ({"swarm_size": True}, TypeError, "swarm_size must be an integer, got bool"),
        ({"swarm_size": "12"}, TypeError, "swarm_size must be an integer, got str"),
        ({"w_max": "0.9"}, TypeError, "w_max must be a real number, got str"),
        ({"method": "ipso", "w_min": 0.95}, ValueError, "w_min must not exceed w_max"),
        ({"method": "ipso", "velocity_limit": 0.0}, ValueError, "velocity_limit must be a number"),
        ({"method": "ipso", "feasibility_tolerance": math.inf}, ValueError, "feasibility_toler"),
        ({"method": "ipso", "constraint_handling": "penalty"}, ValueError,
         "constraint_handling must be one of 'feasibility', 'projection', got 'penalty'"),
        ({"method": "ipso", "constraint_handling": 1}, TypeError, "must be a string, got int"),
        ({"method": "pso", "c2": -1.0}, ValueError, r"c2 must be a number in \[0, 10\]"),
        ({"method": "penalty", "growth_factor": 1.0}, ValueError, "growth_factor must be a number"),
        ({"method": "penalty", "outer_iterations": 0}, ValueError, r"integer in \[1, 100\], got 0"),
    ],
)
def test_bad_keywords_name_the_argument_and_the_range(keywords, error, message):
    with pytest.raises(error, match=message):
        sc.query(**keywords)
    with pytest.raises(error, match=message):
        sc.distance(CUBE, CUBE + 3, **keywords)


@pytest.mark.parametrize(
    ("method", "parameter"),
    [("ipso", "c1"), ("fcl", "swarm_size"), ("dual", "velocity_limit"), ("exact", "swarmsize"),
     ("libccd", "penetration"), ("dual", "relative_tolerance")],
)
def test_a_parameter_the_method_does_not_read_names_the_ones_it_does(method, parameter):
    names = ", ".join(["tolerance", "seed"] + [p.name for p in sc.METHODS[method].parameters])
    message = f"{parameter} does not apply to method '{method}'"
    with pytest.raises(ValueError, match=message) as raised:
        sc.collide(CUBE, CUBE + 3, method=method, **{parameter: 1})
    assert f"(its parameters: {names})" in str(raised.value)


@pytest.mark.parametrize(
    ("method", "kind"),
    [("libccd", "distance"), ("ipso", "signed_distance"), ("pso", "signed_distance"),
     ("penalty", "signed_distance")],
)
def test_a_query_the_method_cannot_answer_names_those_that_can(method, kind):
    able = [name for name, info in sc.METHODS.items() if kind in info.queries]
    message = f"{kind} is not available with method '{method}'"
    with pytest.raises(ValueError, match=message) as raised:
        getattr(sc, kind)(CUBE, CUBE + 3, method=method)
    assert str(raised.value).endswith("use one of " + ", ".join(f"'{n}'" for n in able))


def test_fcl_settles_overlapping_distances_with_its_own_enclosing_simplex():
    # FCL's GJK ends on a tetrahedron around the origin: contact is proven and the distance is
    # zero without the exact solver (whose answer agrees).
    rng = np.random.default_rng(5)
    answered_by_fcl = 0
    for _ in range(20):
        a = rng.normal(size=(64, 3))
        b = rng.normal(size=(64, 3)) + rng.uniform(-0.3, 0.3, size=3)
        r = sc.distance(a, b, method="fcl")
        assert r.colliding and r.certified and r.distance <= pair_scale(a, b).tolerance
        answered_by_fcl += r.method == "fcl"
    assert answered_by_fcl >= 18


def test_fcl_collide_proves_separated_bodies_apart_without_running_gjk():
    b = CUBE + [3, 0.5, 0.2]
    r = sc.collision(CUBE, b, method="fcl")
    # One support evaluation along the centres' line, its separation the proof.
    assert (r.method, r.certified, r.colliding, r.evaluations) == ("fcl", True, False, 1)
    np.testing.assert_allclose(r.direction, [3, 0.5, 0.2] / np.linalg.norm([3, 0.5, 0.2]))
    assert r.lower_bound == pytest.approx(separation(CUBE, b, r.direction), abs=1e-12)


def test_escalated_from_is_none_or_the_method_asked_for(tetra_a, separate_b, touching_b):
    assert sc.distance(tetra_a, separate_b, method="fcl").escalated_from is None
    # FCL proves the contact itself; the depth takes the exact solver.
    assert sc.distance(tetra_a, touching_b, method="fcl").escalated_from is None
    touching = sc.signed_distance(tetra_a, touching_b, method="fcl")
    assert (touching.method, touching.escalated_from) == ("exact", "fcl")
    assert "escalated_from='fcl'" in repr(touching)
    near = separate_b + [0, 1 - 1e-10, 0]  # 1e-10 apart: within the tolerance
    decided = sc.collision(tetra_a, near, method="ipso", max_iterations=0)
    assert (decided.method, decided.escalated_from, decided.colliding) == ("exact", "ipso", True)
    own = sc.collision(tetra_a, near, method="ipso", max_iterations=0, escalate=False)
    assert own.escalated_from is None and not own.certified


def rotation(angles) -> np.ndarray:
    (a, b, c) = angles
    rz = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    ry = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rx = np.array([[1, 0, 0], [0, math.cos(c), -math.sin(c)], [0, math.sin(c), math.cos(c)]])
    return rz @ ry @ rx


@pytest.mark.parametrize("method", list(sc.METHODS))
@pytest.mark.parametrize(
    "offset", [[1.7, 0.3, 0.2], [0.5, 0.25, 0.1]], ids=["apart", "overlapping"]
)
def test_poses_answer_as_the_transformed_points(method, offset):
    rng = np.random.default_rng(4)
    a, b = CUBE, CUBE + offset
    rotation_a, rotation_b = rotation(rng.uniform(0, 6, 3)), rotation(rng.uniform(0, 6, 3))
    t_a, t_b = rng.normal(size=3) * 5, rng.normal(size=3)
    t_b += t_a
    matrix_a = np.eye(4)
    matrix_a[:3, :3], matrix_a[:3, 3] = rotation_a, t_a
    moved_a, moved_b = a @ rotation_a.T + t_a, b @ rotation_b.T + t_b
    truth = (exact_distance(moved_a, moved_b), exact_signed_distance(moved_a, moved_b))
    scale = pair_scale(moved_a, moved_b)
    q = sc.query(method)
    for kind in sc.METHODS[method].queries:
        ask = q.collision if kind == "collide" else getattr(q, kind)
        posed = ask(a, b, pose_a=matrix_a, pose_b=(rotation_b, t_b))
        check_contract(kind, method, moved_a, moved_b, posed, *truth, scale)
        as_points = ask(moved_a, moved_b)
        assert posed.colliding == as_points.colliding
        if sc.METHODS[method].always_certified:
            assert abs(posed.distance - as_points.distance) <= scale.tolerance + scale.rounding
        # The pair (rotation, translation) and the 4 x 4 matrix are the same pose; None is none.
        same = ask(a, b, pose_a=(rotation_a, t_a), pose_b=(rotation_b.tolist(), list(t_b)))
        assert same.distance == posed.distance
        assert ask(a, b, pose_a=None, pose_b=np.eye(4)).distance == ask(a, b).distance


@pytest.mark.parametrize(
    ("pose", "error", "message"),
    [
        (np.diag([2.0, 1, 1, 1]), ValueError, "pose_a is not a rigid motion"),
        ((np.diag([1.0, 1, -1]), np.zeros(3)), ValueError, "det R = -1"),
        ((np.eye(3), [np.nan, 0, 0]), ValueError, "pose_a has a NaN or infinite entry"),
        (np.vstack([np.eye(4)[:3], [0, 0, 0, 2]]), ValueError, r"last row must be \[0, 0, 0, 1\]"),
        (np.eye(3), ValueError, r"\(4, 4\) or \(3, 4\) rigid transform .* got shape \(3, 3\)"),
        ((np.eye(3),), ValueError, "got a sequence of 1 items"),
        ((np.eye(3), np.zeros(4)), ValueError, r"translation must be a \(3,\) translation"),
        ((np.eye(3, dtype=complex), np.zeros(3)), TypeError, "rotation must hold real numbers"),
        ("identity", TypeError, "pose_a must be a .* got str"),
    ],
)
def test_bad_poses_are_refused(pose, error, message):
    with pytest.raises(error, match=message):
        sc.distance(CUBE, CUBE + 3, pose_a=pose)


def test_a_rotation_from_rounded_trigonometry_is_a_pose():
    r = rotation([0.1, 0.2, 0.3])
    r[0, 0] += 1e-12
    assert sc.distance(CUBE, CUBE + 3, pose_a=(r, np.zeros(3))).certified


@pytest.mark.parametrize("argument", ["a", "b"])
def test_bad_bodies_are_named(argument):
    bodies = {"a": CUBE, "b": CUBE}
    bodies[argument] = [[0, 0, np.nan]]
    with pytest.raises(ValueError, match=f"^{argument}: points has a NaN"):
        sc.distance(bodies["a"], bodies["b"])


def test_the_result_repr_shows_the_answer(tetra_a, separate_b):
    text = repr(sc.distance(tetra_a, separate_b))
    assert text.startswith("DistanceResult(method='dual', distance=1, lower_bound=1")
    assert "certified=True" in text and "status='converged'" in text
    assert "escalated_from" not in text


@pytest.mark.parametrize("method", ["dual", "exact"])
@pytest.mark.parametrize("contact", ["face", "vertex"])
def test_touching_polytopes_get_the_contact_normal(method, contact):
    """Touching pairs settle their signed distance from Wolfe's nearest point (its triangle's
    normal) without the expanding polytope; the normal must still be the contact's, not the
    direction between witnesses a few roundoffs apart. A unit cube on another's top face, and one
    standing on a vertex there, under random poses of the pair."""
    from scipy.spatial.transform import Rotation

    cube = sc.ConvexPolyhedron(CUBE)  # [0, 1]^3
    stand = np.eye(4)
    if contact == "face":
        stand[:3, 3] = [0.3, 1.0, 0.2]
    else:
        # Turned about its vertex (0, 0, 0) until its diagonal points up: that vertex, alone
        # lowest, stands on the middle of the top face.
        turn, _ = Rotation.align_vectors([[0.0, 1.0, 0.0]], [np.ones(3) / np.sqrt(3)])
        stand[:3, :3] = turn.as_matrix()
        stand[:3, 3] = [0.5, 1.0, 0.5]
    rng = np.random.default_rng(11)
    for _ in range(20):
        world = np.eye(4)
        world[:3, :3] = Rotation.random(random_state=rng).as_matrix()
        world[:3, 3] = rng.normal(size=3)
        r = sc.signed_distance(cube, cube, pose_a=world, pose_b=world @ stand, method=method)
        assert r.certified and abs(r.distance) <= 1e-9 * 2
        np.testing.assert_allclose(r.direction, world[:3, :3] @ [0.0, 1.0, 0.0], atol=1e-9)
