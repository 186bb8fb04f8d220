"""Rounded bodies and the shapes made of them (Sphere, Capsule, Box): closed forms, batches with
poses, scenes and bad parameters. The queries answer on the cores and subtract the radii."""

import math

import numpy as np
import pytest

import swarmcollide as sc
from shape_checks import IDENTITY, assert_encloses, at

SIGNED_METHODS = ["dual", "exact", "fcl", "libccd"]
DISTANCE_METHODS = ["dual", "exact", "fcl", "ipso"]


def point_to_box(p, half):
    return float(np.linalg.norm(np.maximum(np.abs(p) - half, 0.0)))


@pytest.mark.parametrize("method", DISTANCE_METHODS)
def test_sphere_pairs_match_the_closed_form(method):
    rng = np.random.default_rng(1)
    for _ in range(10):
        r, s = rng.uniform(0.1, 1.0, 2)
        centre = rng.uniform(-3, 3, 3)
        a, b = sc.Sphere(r), sc.Sphere(s)
        expected = max(np.linalg.norm(centre) - r - s, 0.0)
        result = sc.distance(a, b, pose_b=(IDENTITY, centre), method=method)
        size = np.linalg.norm(centre) + 2 * max(r, s)
        assert result.distance == pytest.approx(expected, abs=1e-6 * size)
        assert result.lower_bound <= expected + 1e-13 * size
        if method != "ipso":
            assert_encloses(result, expected, size)


@pytest.mark.parametrize("method", SIGNED_METHODS)
def test_overlapping_spheres_have_their_depth(method):
    for gap in (0.0, 0.3, 1.2):
        result = sc.signed_distance(sc.Sphere(1.0), sc.Sphere(0.5), pose_b=at(0, gap),
                                    method=method)
        assert_encloses(result, gap - 1.5, gap + 2)
        assert result.colliding
        np.testing.assert_allclose(result.point_b - result.point_a,
                                   result.distance * result.direction, atol=1e-12)


@pytest.mark.parametrize("method", ["dual", "exact", "fcl"])
def test_a_sphere_against_a_box_is_the_point_distance_less_the_radius(method):
    rng = np.random.default_rng(2)
    half = np.array([1.0, 0.5, 2.0])
    box = sc.Box(half)
    for _ in range(10):
        centre = rng.uniform(-4, 4, 3)
        radius = rng.uniform(0.05, 1.0)
        outside = point_to_box(centre, half)
        if outside == 0:
            continue
        result = sc.signed_distance(box, sc.Sphere(radius), pose_b=(IDENTITY, centre),
                                    method=method)
        size = np.linalg.norm(centre) + 2 * max(np.linalg.norm(half), radius)
        assert_encloses(result, outside - radius, size)


def segment_distance(p0, p1, q0, q1):
    """Brute force: a fine grid over both segments' parameters."""
    s = np.linspace(0, 1, 801)[:, None]
    p = p0 + s * (p1 - p0)
    q = q0 + s * (q1 - q0)
    return float(np.min(np.linalg.norm(p[:, None, :] - q[None, :, :], axis=2)))


def test_capsules_are_segments_less_the_radii():
    rng = np.random.default_rng(3)
    for _ in range(8):
        a = sc.Capsule(rng.uniform(0.05, 0.3), rng.uniform(0.2, 1.5))
        b = sc.Capsule(rng.uniform(0.05, 0.3), rng.uniform(0.2, 1.5))
        turn = np.linalg.qr(rng.normal(size=(3, 3)))[0]
        turn *= np.linalg.det(turn)
        shift = rng.uniform(-1.5, 1.5, 3)
        ends_a = np.array([[0, 0, -a.half_length], [0, 0, a.half_length]])
        ends_b = np.array([[0, 0, -b.half_length], [0, 0, b.half_length]]) @ turn.T + shift
        brute = segment_distance(*ends_a, *ends_b) - a.radius - b.radius
        result = sc.distance(a, b, pose_b=(turn, shift))
        # The grid's step (1/800 of a segment of at most 3) bounds its error.
        assert result.distance == pytest.approx(max(brute, 0.0), abs=5e-3)
        assert result.certified


@pytest.mark.parametrize("exponent", [-100, -50, 0, 50, 100])
def test_answers_are_the_same_in_any_unit(exponent):
    unit = 10.0**exponent
    a = sc.Capsule(0.5 * unit, 1.0 * unit)
    b = sc.Box(np.array([0.25, 0.25, 0.25]) * unit, radius=0.125 * unit)
    result = sc.distance(a, b, pose_b=at(2 * unit))
    # The capsule's side at x = 0.5, the rounded box's at 2 - 0.375.
    assert result.distance / unit == pytest.approx(1.125, rel=1e-12)
    assert result.certified
    signed = sc.signed_distance(a, b, pose_b=at(0.75 * unit))
    assert signed.distance / unit == pytest.approx(-0.125, rel=1e-9)
    assert signed.certified


@pytest.mark.parametrize("method", SIGNED_METHODS)
@pytest.mark.parametrize("sign", [-1, 1])
def test_verdicts_at_touching_are_certified(method, sign):
    size = 4.5  # centres 1.5 apart, plus twice the capsule's reach of 1.5
    pose = at(1.5 + sign * 1e-9 * size)
    result = sc.collision(sc.Sphere(1.0), sc.Capsule(0.5, 1.0), pose_b=pose, method=method,
                          tolerance=1e-12)
    assert result.certified
    assert result.colliding == (sign < 0)


def test_batches_with_poses_answer_rounded_bodies():
    centres = np.array([[3.0, 0, 0], [0, 2.0, 0], [0, 0, 1.0], [0.5, 0.5, 2.5]])
    poses = np.tile(np.eye(4), (len(centres), 1, 1))
    poses[:, :3, 3] = centres
    sphere, capsule = sc.Sphere(0.5), sc.Capsule(0.25, 1.0)
    expected = []
    for c in centres:
        along = np.clip(c[2], -1.0, 1.0)
        expected.append(np.linalg.norm(c - [0, 0, along]) - 0.75)
    expected = np.array(expected)
    d = sc.distance_many(capsule, sphere, poses_b=poses)
    np.testing.assert_allclose(d.distance, np.maximum(expected, 0), atol=1e-12)
    assert d.certified.all()
    s = sc.signed_distance_many(capsule, sphere, poses_b=poses)
    np.testing.assert_allclose(s.distance, expected, atol=1e-12)
    c = sc.collide_many(capsule, sphere, poses_b=poses)
    np.testing.assert_array_equal(c.colliding, expected <= 0)
    assert c.certified.all()
    # A batch of rows, each a pair of shapes.
    rows = sc.distance_many([sphere, capsule], [sc.Box([1, 1, 1]), sphere], poses_b=poses[:2])
    np.testing.assert_allclose(rows.distance, [3 - 1 - 0.5, 2 - 0.75], atol=1e-12)


def test_the_ball_screens_count_the_radii():
    """A batch's screens prove pairs apart by their balls: for rounded bodies only beyond both
    radii (spheres 0.1 apart have cores 2.1 apart)."""
    near = np.tile(np.eye(4), (2, 1, 1))
    near[:, 0, 3] = [2.1, 1.9]
    r = sc.collide_many(sc.Sphere(1.0), sc.Sphere(1.0), poses_b=near)
    np.testing.assert_array_equal(r.colliding, [False, True])
    assert r.certified.all()
    assert 0 < r.lower_bound[0] <= 0.1


def test_the_face_screens_count_the_radii():
    """Rounded unit boxes whose cores are 0.5 apart across x and offset 1.9 along y: the
    centres' axis proves nothing once the radii are taken off, a face normal does, and only when
    the radii leave a gap (0.5 - 2r)."""
    offsets = np.array([[2.5, 1.9, 0.0], [2.5, -1.9, 0.1], [-2.5, 1.9, 0.0]])
    poses_b = (np.tile(np.eye(3), (3, 1, 1)), offsets)
    for radius, gap in [(0.2, 0.1), (0.24, 0.02), (0.26, -0.02), (0.3, -0.1)]:
        box = sc.Box([1.0, 1.0, 1.0], radius=radius)
        r = sc.collide_many(box, box, poses_b=poses_b)
        assert r.certified.all()
        np.testing.assert_array_equal(r.colliding, [gap < 0] * 3)
        if gap > 0:
            exact = sc.distance_many(box, box, poses_b=poses_b, method="exact")
            assert (r.lower_bound <= exact.lower_bound + 1e-15).all()
            assert (r.lower_bound > 0.9 * gap).all()


def test_scenes_of_spheres_and_capsules():
    scene = sc.Scene()
    bodies = [sc.Sphere(0.5), sc.Capsule(0.25, 1.0), sc.Box([0.5, 0.5, 0.5], radius=0.1)]
    poses = np.tile(np.eye(4), (3, 1, 1))
    poses[:, :3, 3] = [[0, 0, 0], [0.7, 0, 0], [3.0, 0, 0]]
    scene.add(bodies, poses=poses)
    # The sphere and the capsule overlap by 0.05 (their cores' boxes are 0.7 apart: the
    # broadphase finds them only by boxes grown by the radii); the rounded box is
    # 3 - 0.6 - 0.95 = 1.45 from the capsule.
    assert scene.colliding_pairs().pairs.tolist() == [[0, 1]]
    within = scene.pairs_within(1.5)
    assert within.pairs.tolist() == [[0, 1], [1, 2]]
    np.testing.assert_allclose(within.distance, [0.0, 1.45], atol=1e-12)
    contacts = scene.contacts()
    np.testing.assert_allclose(contacts.normal, [[1.0, 0, 0]], atol=1e-12)
    # Halfway between the surfaces: 0.5 and 0.7 - 0.25.
    np.testing.assert_allclose(contacts.points, [[0.475, 0, 0]], atol=1e-12)


def test_compound_bodies_of_rounded_parts():
    dumbbell = sc.CompoundBody([sc.Sphere(1.0), sc.ConvexPolyhedron([[4, 0, 0]], radius=1.0)])
    result = sc.distance(dumbbell, sc.Sphere(0.5), pose_b=at(2, 2))
    assert result.distance == pytest.approx(math.hypot(2, 2) - 1.5, abs=1e-12)
    assert result.certified


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf])
def test_bad_parameters_are_refused_by_name(bad):
    with pytest.raises(ValueError, match="radius"):
        sc.Sphere(bad)
    with pytest.raises(ValueError, match="radius"):
        sc.Capsule(bad, 1.0)
    with pytest.raises(ValueError, match="half_length"):
        sc.Capsule(1.0, bad)
    with pytest.raises(ValueError, match="half_extents"):
        sc.Box([1.0, bad, 1.0])
    if bad != 0:
        with pytest.raises(ValueError, match="radius"):
            sc.ConvexPolyhedron([[0, 0, 0]], radius=bad)
        with pytest.raises(ValueError, match="radius"):
            sc.Box([1, 1, 1], radius=bad)


def test_shapes_are_polyhedra_with_a_radius():
    sphere = sc.Sphere(2.0)
    assert isinstance(sphere, sc.ConvexPolyhedron)
    assert sphere.radius == 2.0 and len(sphere) == 1
    assert repr(sphere) == "Sphere(radius=2)"
    assert repr(sc.Capsule(0.5, 1.5)) == "Capsule(radius=0.5, half_length=1.5)"
    assert repr(sc.Box([1, 2, 3], radius=0.5)) == "Box(half_extents=[1, 2, 3], radius=0.5)"
    np.testing.assert_array_equal(sc.Capsule(0.5, 1.5).vertices, [[0, 0, -1.5], [0, 0, 1.5]])
    assert len(sc.Box([1, 2, 3])) == 8 and sc.Box([1, 2, 3]).radius == 0
    rounded = sc.ConvexPolyhedron([[0, 0, 0], [1, 0, 0]], radius=0.25)
    assert rounded.aabb().min.tolist() == pytest.approx([-0.25, -0.25, -0.25])
    assert sc.ConvexPolyhedron(rounded).radius == 0.25
    assert sc.ConvexPolyhedron(rounded, radius=0).radius == 0
    for shape in (sc.Sphere, sc.Capsule, sc.Box, sc.ConvexPolyhedron):
        assert "'ipso'" in shape.__doc__ and "'fcl'" in shape.__doc__


def test_a_warm_scene_keeps_the_bound_of_the_rounded_bodies():
    """A warm scene settles a pair that moved less than its cached lower bound: that bound must be
    the spheres' (0.26 here), not their cores' (2.26), or the pair moved 0.42 closer stays
    apart."""
    scene = sc.Scene(warm_start=True)
    poses = np.tile(np.eye(4), (2, 1, 1))
    poses[1, :2, 3] = [1.6, 1.6]  # boxes overlap, spheres 0.26 apart
    scene.add([sc.Sphere(1.0), sc.Sphere(1.0)], poses=poses)
    assert scene.colliding_pairs().pairs.tolist() == []
    moved = np.eye(4)
    moved[:2, 3] = [1.3, 1.3]  # 1.84 apart: overlapping by 0.16
    scene.set_poses(1, moved)
    assert scene.colliding_pairs().pairs.tolist() == [[0, 1]]


@pytest.mark.parametrize("warm", [False, True])
def test_scene_queries_agree_with_the_pair_queries(warm):
    rng = np.random.default_rng(4)
    n = 30
    radii = rng.uniform(0.05, 0.6, n)
    bodies = [sc.Sphere(r) if i % 2 else sc.Capsule(r, 0.5) for i, r in enumerate(radii)]
    poses = np.tile(np.eye(4), (n, 1, 1))
    poses[:, :3, 3] = rng.uniform(-3, 3, (n, 3))
    scene = sc.Scene(warm_start=warm)
    scene.add(bodies, poses=poses)
    apart = np.full((n, n), np.inf)
    for i in range(n):
        for j in range(i + 1, n):
            apart[i, j] = apart[j, i] = sc.distance(bodies[i], bodies[j], pose_a=poses[i],
                                                    pose_b=poses[j]).distance
    pairs = [[i, j] for i in range(n) for j in range(i + 1, n)]
    assert scene.colliding_pairs().pairs.tolist() == [p for p in pairs if apart[tuple(p)] == 0]
    assert scene.pairs_within(0.3).pairs.tolist() == [p for p in pairs if apart[tuple(p)] <= 0.3]
    nearest = scene.nearest(list(range(n)), k=1)
    np.testing.assert_allclose(nearest.distance, apart.min(axis=1), atol=1e-12)
    assert nearest.certified.all()
