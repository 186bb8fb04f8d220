"""Bodies, parts and edges many decades smaller than the pair they are in, and compound bodies
whose parts are many decades apart: every answer's bounds hold.

A direction made from such a feature (an edge of a speck inside a cube, the line between two
parts' centres in a body 1e-160 across) has entries whose squares underflow, and normalised by
its squared length it came back far from unit length: the separation along it bounded nothing
(a certified depth of 6e-15 for a speck 0.5 deep). Squared distances of parts 1e155 apart
overflowed the other way.
"""

from __future__ import annotations

import numpy as np
import pytest

import swarmcollide as sc

SIGNED = ["dual", "exact", "fcl", "libccd"]
SPECKS = [1e-12, 1e-80, 1e-155, 1e-160, 1e-170, 1e-200, 1e-300]


def encloses(result, truth: float, size: float) -> bool:
    """The result's bounds hold `truth`, to the rounding of a pair of this size."""
    slack = 1e-12 * size
    return result.lower_bound - slack <= truth <= result.distance + slack


def speck(kind: str, size: float) -> sc.ConvexPolyhedron:
    if kind == "box":
        return sc.Box([size] * 3)
    # A tetrahedron about the origin, its points `size` from it.
    return sc.ConvexPolyhedron(np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1.0]])
                               * size / np.sqrt(3))


@pytest.mark.parametrize("method", SIGNED)
@pytest.mark.parametrize("kind", ["box", "tetrahedron"])
@pytest.mark.parametrize("size", SPECKS)
def test_a_speck_at_the_centre_of_a_cube_is_half_its_width_deep(method, kind, size):
    cube = sc.Box([0.5] * 3)
    small = speck(kind, size)
    # Pushed out along an axis: the half width and the speck's own reach along it.
    reach = size if kind == "box" else size / np.sqrt(3)
    truth = -(0.5 + reach)
    for a, b in [(cube, small), (small, cube)]:
        r = sc.signed_distance(a, b, method=method)
        assert encloses(r, truth, 2), (a, b, r)
        assert sc.collide(a, b, method=method)


@pytest.mark.parametrize("size", SPECKS)
def test_a_speck_off_the_centre_of_a_cube_is_as_deep_as_its_place(size):
    cube = sc.Box([0.5] * 3)
    place = (np.eye(3), [0.3, -0.1, 0.2])  # 0.2 from the nearest face (x = 0.5)
    for method in SIGNED:
        r = sc.signed_distance(cube, sc.Box([size] * 3), pose_b=place, method=method)
        assert encloses(r, -(0.2 + size), 2), (method, r)


def random_compounds(seed: int):
    rng = np.random.default_rng(seed)
    a = [rng.normal(size=(8, 3)) * 0.3 + rng.normal(size=3) for _ in range(4)]
    b = [rng.normal(size=(8, 3)) * 0.3 + rng.normal(size=3) + [2.5, 0, 0] for _ in range(3)]
    return a, b


@pytest.mark.parametrize("seed", [14, 3, 7])
@pytest.mark.parametrize("query", ["distance", "signed_distance"])
def test_compound_bodies_in_a_tiny_unit_of_length_answer_as_in_a_unit_one(seed, query):
    # Seed 14 at 3e-162: a node pair's bound along its centres' line came out 0.67 of the
    # truth, and the nearest part pair was pruned (a certified -0.117 where it is -0.175).
    parts_a, parts_b = random_compounds(seed)
    unit = getattr(sc, query)(sc.CompoundBody(parts_a), sc.CompoundBody(parts_b))
    assert unit.certified
    for scale in [1e-150, 1e-155, 3.045135341795397e-162, 1e-170, 1e-250, 1e-300]:
        a = sc.CompoundBody([p * scale for p in parts_a])
        b = sc.CompoundBody([p * scale for p in parts_b])
        r = getattr(sc, query)(a, b)
        assert r.lower_bound / scale <= unit.distance + 1e-9 * 6, (scale, r)
        assert unit.lower_bound - 1e-9 * 6 <= r.distance / scale, (scale, r)


@pytest.mark.parametrize("apart", [1e150, 1e155, 1e200, 1e300])
def test_a_compound_body_with_parts_far_apart_measures_its_nearest_part(apart):
    def at(x):
        pose = np.eye(4)
        pose[0, 3] = x
        return pose

    body = sc.CompoundBody([sc.Sphere(1), sc.Sphere(1)], poses=[at(-apart), at(apart)])
    r = sc.distance(body, sc.Sphere(1))
    truth = apart - 2  # to the nearer sphere's surface, 2 radii off its centre
    assert np.isfinite(r.distance) and np.isfinite(r.lower_bound)
    assert r.lower_bound <= truth * (1 + 1e-9) and truth * (1 - 1e-9) <= r.distance
    assert not sc.collide(body, sc.Sphere(1), pose_b=at(apart * (1 + 1e-6)))
    assert sc.collide(body, sc.Sphere(1), pose_b=at(apart))


def test_nearest_of_no_bodies_in_an_empty_scene_is_empty():
    assert len(sc.Scene().nearest([])) == 0
    scene = sc.Scene()
    ids = scene.add([sc.Box([0.5] * 3)] * 2)
    scene.remove(ids)
    assert len(scene.nearest([])) == 0


def test_a_robot_models_kinematics_refuses_configurations_of_another_length():
    joint = sc.Joint("j", "revolute", 0, 1, lower=-1, upper=1)
    model = sc.Robot(["a", "b"], [joint], [("g", 1, None, sc.Box([0.5] * 3))]).model
    for method in (model.forward_kinematics, model.geometry_poses):
        for q in (np.zeros((1, 0)), np.zeros((2, 3))):
            with pytest.raises(ValueError, match="1 values per configuration"):
                method(q)
        with pytest.raises(ValueError, match="not a finite number"):
            method(np.full((1, 1), np.nan))
        assert method(np.full((3, 1), 0.5)).shape[0] == 3
