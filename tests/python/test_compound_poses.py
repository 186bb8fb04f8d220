"""Compound bodies whose parts have poses of their own: built with ``poses=``, answered as the
parts at their composed poses, written to JSON with their poses, saved placed, drawn; and depths
on an axis of symmetry (a point at a cylinder's centre), which the closed form proves."""

import numpy as np
import pytest

import swarmcollide as sc
from swarmcollide.shape_json import body_from_json, body_to_json


def random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def transform(rotation, translation):
    matrix = np.eye(4)
    matrix[:3, :3] = rotation
    matrix[:3, 3] = translation
    return matrix


LYING = transform([[1, 0, 0], [0, 0, -1], [0, 1, 0]], [0, 0, 2])  # axis along y, 2 up


def posed_body(rng):
    parts = [sc.Box([1, 1, 0.1]), sc.Cylinder(0.1, 1), sc.Cone(0.3, 0.4),
             sc.Ellipsoid([0.2, 0.3, 0.1]), [[0, 0, 0], [0.3, 0, 0], [0, 0.3, 0], [0, 0, 0.3]]]
    poses = [np.eye(4), LYING] + [transform(random_rotation(rng), rng.uniform(-1, 1, 3))
                                   for _ in range(3)]
    return parts, poses, sc.CompoundBody(parts, poses=poses)


def test_parts_are_placed_by_their_poses():
    parts, poses, body = posed_body(np.random.default_rng(1))
    np.testing.assert_array_equal(body.part_poses, np.array(poses))
    assert repr(body.given_parts[1]) == "Cylinder(radius=0.1, half_length=1)"
    # The lying cylinder spans y in [-1, 1] at z = 2; placed, it answers queries as that.
    placed = body.parts[1]
    assert placed.curved and not isinstance(placed, sc.Cylinder)
    np.testing.assert_allclose(placed.aabb().max, [0.1, 1, 2.1], atol=1e-12)
    assert sc.distance(body, sc.Sphere(0.5), pose_b=(np.eye(3), [0, 0, 3])).distance == \
        pytest.approx(0.4, abs=1e-9)
    # Unposed, every pose is the identity.
    plain = sc.CompoundBody([sc.Cylinder(0.1, 1)])
    np.testing.assert_array_equal(plain.part_poses, [np.eye(4)])


@pytest.mark.parametrize("method", ["dual", "exact", "fcl"])
def test_queries_answer_as_the_parts_at_their_composed_poses(method):
    rng = np.random.default_rng(2)
    parts, poses, body = posed_body(rng)
    other = sc.Capsule(0.2, 0.5)
    colliding = 0
    for _ in range(10):
        pose_a = transform(random_rotation(rng), rng.uniform(-0.2, 0.2, 3))
        pose_b = transform(random_rotation(rng), rng.uniform(-2, 2, 3))
        best = min(sc.signed_distance(part, other, pose_a=pose_a @ pose, pose_b=pose_b,
                                      method=method).distance
                   for part, pose in zip(parts, poses))
        whole = sc.signed_distance(body, other, pose_a=pose_a, pose_b=pose_b, method=method)
        assert whole.certified
        assert whole.distance == pytest.approx(best, abs=1e-8)
        colliding += whole.distance <= 0
    assert 0 < colliding < 10
    rows = sc.distance_many(body, other, poses_b=np.array([transform(np.eye(3), [0, 0, z])
                                                           for z in (3.0, 3.5)]), method=method)
    np.testing.assert_allclose(rows.distance, [0.2, 0.7], atol=1e-8)


def test_bad_poses_are_refused_by_name():
    parts = [sc.Cylinder(0.1, 1), sc.Box([1, 1, 1])]
    with pytest.raises(ValueError, match="poses"):
        sc.CompoundBody(parts, poses=[np.eye(4)])
    skewed = np.eye(4)
    skewed[0, 1] = 0.5
    with pytest.raises(ValueError, match=r"poses\[1\]"):
        sc.CompoundBody(parts, poses=[np.eye(4), skewed])
    with pytest.raises(TypeError, match="poses must be None when parts is a CompoundBody"):
        sc.CompoundBody(sc.CompoundBody(parts), poses=[np.eye(4), np.eye(4)])
    # Parts each representable but together spanning more than the double range: their size
    # (and the tolerances relative to it) would be infinite.
    far = [transform(np.eye(3), [-1e308, 0, 0]), transform(np.eye(3), [1e308, 0, 0])]
    with pytest.raises(ValueError, match="span more than the largest double"):
        sc.CompoundBody([sc.Sphere(1.0), sc.Sphere(1.0)], poses=far)
    assert sc.CompoundBody([sc.Sphere(1.0), sc.Sphere(1.0)], poses=far[:1] + [np.eye(4)])


def test_json_keeps_the_poses_and_save_writes_placed_points(tmp_path):
    parts, poses, body = posed_body(np.random.default_rng(3))
    record = body_to_json(body)
    assert len(record["poses"]) == 5 and record["parts"][1]["shape"] == "cylinder"
    again = body_from_json(record)
    np.testing.assert_array_equal(again.part_poses, body.part_poses)
    ball = sc.Sphere(0.3)
    for z in (0.5, 2.0, 3.0):
        assert sc.signed_distance(again, ball, pose_b=(np.eye(3), [0.2, 0.1, z])).distance == \
            pytest.approx(sc.signed_distance(body, ball, pose_b=(np.eye(3), [0.2, 0.1, z])).distance,
                          abs=1e-12)
    assert "poses" not in body_to_json(sc.CompoundBody([sc.Cylinder(0.1, 1)]))
    with pytest.raises(ValueError, match=r"record\['poses'\]\[0\] must be a transform"):
        body_from_json({"shape": "compound", "parts": [{"shape": "sphere", "radius": 1}],
                        "poses": [[[1, 0, 0], [0, 1, 0]]]})
    # Polyhedra with poses are saved placed (the same parts); curved parts are refused.
    boxes = sc.CompoundBody([sc.Box([1, 1, 1]), sc.Box([0.5, 0.5, 0.5])],
                            poses=[np.eye(4), LYING])
    boxes.save(tmp_path / "boxes.npz")
    loaded = sc.CompoundBody.load(tmp_path / "boxes.npz")
    np.testing.assert_array_equal(loaded.parts[1].vertices, boxes.parts[1].vertices)
    with pytest.raises(ValueError, match=r"parts\[1\] is a curved shape.*body_to_json"):
        body.save(tmp_path / "posed.npz")


def test_plots_draw_parts_where_their_poses_put_them():
    pytest.importorskip("matplotlib")
    from swarmcollide.plot import _surface, plot_body

    _, _, body = posed_body(np.random.default_rng(4))
    points, _ = _surface(body.parts[1])
    # The lying cylinder's surface: along y, radius 0.1 about the line z = 2.
    assert (np.hypot(points[:, 0], points[:, 2] - 2) <= 0.1 + 1e-12).all()
    np.testing.assert_allclose(points.min(axis=0), [-0.1, -1, 1.9], atol=0.01)
    np.testing.assert_allclose(points.max(axis=0), [0.1, 1, 2.1], atol=0.01)
    figure = plot_body(body)
    assert len(figure.axes[0].collections) == 5


@pytest.mark.parametrize("method", ["dual", "exact", "libccd"])
@pytest.mark.parametrize("shape, depth", [(sc.Cylinder(0.5, 2), 0.5), (sc.Cone(1, 1.5), 1.5 / 10 ** 0.5),
                                          (sc.Ellipsoid([0.6, 0.6, 1.5]), 0.6)])
def test_a_point_on_an_axis_of_symmetry_gets_a_certified_depth(method, shape, depth):
    point = sc.ConvexPolyhedron([[0, 0, 0]])
    for tolerance in (1e-9, 1e-12):
        r = sc.signed_distance(shape, point, method=method, tolerance=tolerance)
        assert r.certified
        assert r.distance == pytest.approx(-depth, abs=tolerance * 4 + 1e-13)
        assert r.lower_bound <= -depth + 1e-13


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e-170, 1e155, 1e170])
@pytest.mark.parametrize("shape", [sc.Cylinder, sc.Cone], ids=lambda kind: kind.__name__)
def test_a_posed_curved_part_answers_alike_at_every_scale(shape, scale):
    """A posed part's ball holds its offset's length, which squared overflowed above 1e154 (the
    part was refused as spanning more than the largest double) and vanished below 1e-162."""
    turn = transform(random_rotation(np.random.default_rng(4)), [0.7, -0.2, 0.4])

    def distance(s):
        posed = turn.copy()
        posed[:3, 3] *= s
        body = sc.CompoundBody([shape(0.5 * s, 0.8 * s)], poses=[posed])
        probe = sc.Box([0.3 * s] * 3)
        at = np.eye(4)
        at[:3, 3] = [2.0 * s, 0.5 * s, 0.0]
        r = sc.signed_distance(body, probe, pose_b=at)
        assert r.certified and sc.collide(body, probe, pose_b=transform(np.eye(3), [0.8 * s, 0, 0]))
        return r.distance / s

    assert distance(scale) == pytest.approx(distance(1.0), rel=1e-6, abs=1e-6)
