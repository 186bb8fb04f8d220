"""The query functions answered in C++ (``_core.query_function``) and their Python definitions
(``queries.PYTHON_PATHS``) give the same answers, raise the same errors, and look the same."""

import inspect
import pickle
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import swarmcollide as sc
from swarmcollide import queries

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
TETRA = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
NAMES = ["distance", "signed_distance", "collision", "collide"]
VERDICTS = {"collision", "collide"}


def moved(x, y, z):
    pose = np.eye(4)
    pose[:3, 3] = (x, y, z)
    return pose


class Mine(sc.ConvexPolyhedron):
    """A user's subclass, which only the Python definitions convert."""


def bodies():
    rng = np.random.default_rng(5)
    cloud = rng.normal(size=(60, 3))  # more points than a small query keeps the GIL for
    return {
        "polyhedra": (sc.ConvexPolyhedron(CUBE), sc.ConvexPolyhedron(TETRA + [1.5, 0, 0])),
        "overlapping": (sc.ConvexPolyhedron(CUBE), sc.ConvexPolyhedron(CUBE + 0.5)),
        "arrays": (CUBE, TETRA + [0.25, 0.25, 0.25]),
        "lists": (CUBE.tolist(), (TETRA + 3).tolist()),
        "large": (sc.ConvexPolyhedron(cloud), sc.ConvexPolyhedron(cloud + [5, 0, 0])),
        "compound": (sc.CompoundBody([CUBE, CUBE + [2, 0, 0]]), sc.ConvexPolyhedron(TETRA + 4)),
        "shapes": (sc.Cylinder(0.5, 1.0), sc.Capsule(0.25, 0.5)),  # bound subclasses: C++ too
        "box and ellipsoid": (sc.Box([0.5, 0.25, 1.0]), sc.Ellipsoid([0.5, 0.75, 0.25])),
        "cone and sphere": (sc.Cone(0.5, 0.5), sc.Sphere(0.375)),
        "polyhedron subclass": (Mine(CUBE), sc.ConvexPolyhedron(TETRA + 1.5)),  # Python's path
    }


KEYWORDS = [
    {},
    {"method": "exact"},
    {"method": "fcl"},
    {"method": "ipso"},
    {"method": "ipso", "swarm_size": 12, "max_iterations": 30},  # parameters: the Python path
    {"tolerance": 1e-6},
    {"tolerance": 0.0, "seed": 7},
    {"seed": 3, "method": "pso"},
    {"pose_b": moved(0.5, 0.25, 0)},
    {"pose_a": moved(0, 0, -1), "pose_b": moved(0.5, 0, 0)[:3]},
    {"pose_a": (Rotation.from_euler("z", 30, degrees=True), [0.1, 0.2, 0.3])},
    {"pose_b": (np.eye(3), np.array([0.0, 2.0, 0.0]))},
    {"pose_a": None, "pose_b": None, "method": "dual"},
]


def same_answer(fast, python):
    if isinstance(python, bool):
        assert type(fast) is bool and fast == python
        return
    assert type(fast) is type(python)
    assert repr(fast) == repr(python)
    for field in ("distance", "lower_bound", "colliding", "certified", "iterations",
                  "evaluations", "method", "escalated_from", "status"):
        assert getattr(fast, field) == getattr(python, field), field
    for field in ("point_a", "point_b", "direction", "weights_a", "weights_b", "history"):
        np.testing.assert_array_equal(getattr(fast, field), getattr(python, field))
    if isinstance(python, sc.CompoundResult):
        assert (fast.part_a, fast.part_b) == (python.part_a, python.part_b)


def outcome(function, *arguments, **keywords):
    """What a call gives: ("answer", its answer) or (the error's type, its message)."""
    try:
        return "answer", function(*arguments, **keywords)
    except Exception as error:  # noqa: BLE001 - the comparison is the test
        return type(error), str(error)


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("case", list(bodies()))
@pytest.mark.parametrize("keywords", KEYWORDS, ids=lambda k: ",".join(k) or "none")
def test_the_cpp_and_python_paths_give_the_same_answers(name, case, keywords):
    a, b = bodies()[case]
    calls = [keywords]
    if name in VERDICTS:
        calls.append({**keywords, "escalate": False})
    for call in calls:
        fast = outcome(getattr(sc, name), a, b, **call)
        python = outcome(queries.PYTHON_PATHS[name], a, b, **call)
        assert fast[0] == python[0], (fast, python)
        if fast[0] == "answer":
            same_answer(fast[1], python[1])
        else:  # the swarms measure no penetration: signed_distance refuses them alike
            assert fast[1] == python[1]


def test_an_unescalated_verdict_stays_the_methods_own():
    a, b = sc.ConvexPolyhedron(TETRA), sc.ConvexPolyhedron(TETRA + [1 + 1e-10, 0, 0])
    # ipso with its default budget may or may not prove this; escalation decides either way
    kept = sc.collision(a, b, method="ipso", escalate=False)
    assert kept.method == "ipso" and kept.escalated_from is None
    decided = sc.collision(a, b, method="ipso", max_iterations=0)
    assert decided.method == "exact" and decided.escalated_from == "ipso"


# Wrong calls, and calls some queries refuse (libccd has no distance, penalty no penetration).
BAD_CALLS = [
    ((CUBE,), {}),
    ((CUBE, CUBE, CUBE), {}),
    ((CUBE, CUBE), {"method": "gjk"}),
    ((CUBE, CUBE), {"method": 3}),
    ((CUBE, CUBE), {"tolerance": float("nan")}),
    ((CUBE, CUBE), {"tolerance": -1.0}),
    ((CUBE, CUBE), {"tolerance": True}),
    ((CUBE, CUBE), {"tolerance": "1e-9"}),
    ((CUBE, CUBE), {"seed": -1}),
    ((CUBE, CUBE), {"seed": 2**64}),
    ((CUBE, CUBE), {"seed": True}),
    ((CUBE, CUBE), {"swarm_size": 5}),  # not a parameter of "dual"
    ((CUBE, CUBE), {"method": "ipso", "swarm_size": 1}),
    ((CUBE, CUBE), {"pose_b": np.eye(3)}),
    ((CUBE, CUBE), {"pose_a": np.diag([2.0, 1.0, 1.0, 1.0])}),
    ((CUBE, CUBE), {"pose_a": np.full((4, 4), np.nan)}),
    ((CUBE, CUBE), {"pose_b": "identity"}),
    ((CUBE, [[0, 0]]), {}),
    ((np.zeros((0, 3)), CUBE), {}),
    ((CUBE, "cube"), {}),
    ((CUBE, CUBE), {"escalate": "yes"}),
    ((CUBE, CUBE), {"escalate": 1}),  # a flag is True or False: 2 or None would pass for one
    ((CUBE, CUBE), {"unknown": 1}),
    ((CUBE, CUBE * 1e300), {}),
    ((CUBE, CUBE), {"method": "libccd"}),
    ((CUBE, CUBE), {"method": "penalty"}),
]


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize(("arguments", "keywords"), BAD_CALLS)
def test_the_cpp_and_python_paths_raise_the_same_errors(name, arguments, keywords):
    outcomes = [outcome(function, *arguments, **keywords)
                for function in (getattr(sc, name), queries.PYTHON_PATHS[name])]
    assert outcomes[0][0] == outcomes[1][0], outcomes
    if outcomes[0][0] == "answer":  # libccd and penalty answer collide, and 1e300 is in range
        same_answer(outcomes[0][1], outcomes[1][1])
    else:
        assert outcomes[0][1] == outcomes[1][1]


@pytest.mark.parametrize("name", NAMES)
def test_the_cpp_functions_keep_the_python_signatures_documentation_and_names(name):
    fast, python = getattr(sc, name), queries.PYTHON_PATHS[name]
    assert fast is getattr(queries, name) and fast is not python
    assert fast.__doc__ == python.__doc__
    assert (fast.__name__, fast.__qualname__, fast.__module__) == (
        python.__name__, python.__qualname__, python.__module__)
    fast_parameters = inspect.signature(fast).parameters.values()
    python_parameters = inspect.signature(python).parameters.values()
    assert [(p.name, p.kind, p.default) for p in fast_parameters] == [
        (p.name, p.kind, p.default) for p in python_parameters]
    assert pickle.loads(pickle.dumps(fast)) is fast


def test_query_function_refuses_other_functions():
    def nearest(a, b):
        """Not a query function."""

    with pytest.raises(ValueError, match="python_path must be distance, signed_distance"):
        sc._core.query_function(nearest, "(a, b)")


def python_calls(call):
    """How many times ``call()`` enters a query function's Python definition."""
    codes = {function.__code__ for function in queries.PYTHON_PATHS.values()}
    entered = []

    def profile(frame, event, arg):
        if event == "call" and frame.f_code in codes:
            entered.append(frame.f_code.co_name)

    previous = sys.getprofile()
    sys.setprofile(profile)
    try:
        call()
    finally:
        sys.setprofile(previous)
    return len(entered)


def test_the_usual_calls_stay_in_cpp_and_the_others_go_to_python():
    a, b = sc.ConvexPolyhedron(CUBE), sc.ConvexPolyhedron(CUBE + 2)
    pose = moved(0, 1, 0)
    assert python_calls(lambda: sc.distance(a, b)) == 0
    assert python_calls(lambda: sc.signed_distance(a, b, method="exact", pose_b=pose)) == 0
    assert python_calls(lambda: sc.collide(a, b, method="fcl", escalate=False, seed=2)) == 0
    assert python_calls(lambda: sc.collision(a, b, tolerance=1e-6, pose_a=pose)) == 0
    assert python_calls(lambda: sc.distance(a, b, method="ipso", swarm_size=10)) == 1
    assert python_calls(lambda: sc.distance(a, b, tolerance=0)) == 1  # an int: Python keys it
    assert python_calls(lambda: sc.collide(a, b, escalate=np.bool_(True))) == 1
    assert python_calls(lambda: sc.distance(a, b=b)) == 1


class Subquery(sc.Query):
    """A Query subclass: its calls take pybind11's methods."""


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("method", ["dual", "exact", "ipso"])
def test_query_methods_read_in_cpp_answer_as_pybind11s(name, method):
    q, sub = sc.Query(method), Subquery(method)
    a, b = sc.ConvexPolyhedron(CUBE), sc.ConvexPolyhedron(TETRA + [1.5, 0, 0])
    pose = moved(0.25, 0, 0)
    verdict = name in VERDICTS
    usual = outcome(getattr(q, name), a, b)
    assert usual[0] == "answer" or (name == "signed_distance" and method == "ipso")
    forms = [
        ((a, b), {}),
        ((a, b, None, pose), {}),
        ((a, b), {"pose_b": pose}),
        ((a,), {"b": b}),  # pybind11's dispatch reads this one
        ((), {"a": a, "b": b, "pose_a": pose}),
    ]
    if verdict:
        forms += [((a, b, None, None, False), {}), ((a, b), {"escalate": False}),
                  ((a, b), {"escalate": 0})]
    for arguments, keywords in forms:
        got = outcome(getattr(q, name), *arguments, **keywords)
        via_pybind11 = outcome(getattr(sub, name), *arguments, **keywords)
        assert got[0] == via_pybind11[0]
        if got[0] == "answer":
            same_answer(got[1], via_pybind11[1])
        else:
            assert got[1] == via_pybind11[1]


@pytest.mark.parametrize("name", NAMES)
def test_query_methods_refuse_wrong_calls_as_pybind11_does(name):
    q = sc.Query()
    wrong = [((CUBE,), {}), ((CUBE, CUBE, None, None, True, True), {}),
             ((CUBE, CUBE, None), {"pose_a": None}), ((CUBE, CUBE), {"unknown": 1})]
    for arguments, keywords in wrong:
        with pytest.raises(TypeError, match=f"{name}\\(\\): incompatible function arguments"):
            getattr(q, name)(*arguments, **keywords)
    with pytest.raises(ValueError, match="pose_b must be a"):
        getattr(q, name)(CUBE, CUBE, pose_b=np.eye(3))
    assert getattr(sc.Query, name).__doc__.startswith(f"{name}(self: swarmcollide._core.Query")


def poses():
    rotation = Rotation.from_euler("xyz", [10, 20, 30], degrees=True).as_matrix()
    pose = np.eye(4)
    pose[:3, :3], pose[:3, 3] = rotation, [0.5, -0.25, 2.0]
    return pose


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize(
    "form",
    [lambda p: p, lambda p: p[:3], lambda p: np.asfortranarray(p), lambda p: p[:3].copy(order="F"),
     lambda p: p.astype(">f8"), lambda p: p.tolist()],
    ids=["c4x4", "c3x4", "fortran", "fortran3x4", "big-endian", "lists"],
)
def test_array_poses_read_in_place_answer_as_the_pair_form(name, form):
    a, b = sc.ConvexPolyhedron(CUBE), sc.ConvexPolyhedron(TETRA)
    pose = poses()
    pair = (pose[:3, :3].tolist(), pose[:3, 3].tolist())
    same_answer(getattr(sc, name)(a, b, pose_b=form(pose)), getattr(sc, name)(a, b, pose_b=pair))


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize(
    "form",
    [lambda r, t: (r, t), lambda r, t: [r, t], lambda r, t: (np.asfortranarray(r), t),
     lambda r, t: (np.hstack([r, r])[:, :3], t), lambda r, t: (r, t.reshape(3, 1))],
    ids=["tuple", "list", "fortran-rotation", "strided-rotation", "column-translation"],
)
def test_rotation_translation_pairs_read_in_place_answer_as_lists(name, form):
    a, b = sc.ConvexPolyhedron(CUBE), sc.ConvexPolyhedron(TETRA)
    pose = poses()
    given = form(pose[:3, :3].copy(), pose[:3, 3].copy())
    if given[1].shape == (3, 1):
        with pytest.raises(ValueError, match="pose_b's translation"):
            getattr(sc, name)(a, b, pose_b=given)
        return
    lists = tuple(np.asarray(part, dtype=float).tolist() for part in given)
    same_answer(getattr(sc, name)(a, b, pose_b=given), getattr(sc, name)(a, b, pose_b=lists))


@pytest.mark.parametrize(
    "rotation, translation",
    [(2 * np.eye(3), np.zeros(3)), (-np.eye(3), np.zeros(3)),
     (np.full((3, 3), np.nan), np.zeros(3)), (np.eye(3), np.array([np.inf, 0.0, 0.0]))],
    ids=["scaled", "reflection", "nan", "inf"],
)
def test_rotation_translation_pairs_read_in_place_fail_as_lists_do(rotation, translation):
    messages = []
    for given in ((rotation, translation), (rotation.tolist(), translation.tolist())):
        with pytest.raises(ValueError) as error:
            sc.distance(CUBE, CUBE, pose_a=given)
        messages.append(str(error.value))
    assert messages[0] == messages[1] and messages[0].startswith("pose_a")


@pytest.mark.parametrize(
    "pose",
    [np.diag([1.0, 1.0, 1.0, 2.0]), np.diag([2.0, 1.0, 1.0, 1.0]),
     np.diag([1.0, 1.0, 1.0, 1.0])[:3] * np.nan, np.full((3, 4), np.inf), -np.eye(4)[:3]],
    ids=["last-row", "scaled", "nan", "inf", "reflection"],
)
def test_array_poses_read_in_place_fail_as_lists_do(pose):
    messages = []
    for given in (pose, pose.tolist()):
        with pytest.raises(ValueError) as error:
            sc.distance(CUBE, CUBE, pose_a=given)
        messages.append(str(error.value))
    assert messages[0] == messages[1] and messages[0].startswith("pose_a")
