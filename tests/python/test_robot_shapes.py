"""Robots with curved collision shapes (URDF cylinders, MJCF cylinders, capsules and ellipsoids):
the robot's answers against closed forms at known configurations, their gradients, and the
methods that cannot answer curved shapes."""

import numpy as np
import pytest

import swarmcollide as sc

pytest.importorskip("yourdfpy")
mujoco = pytest.importorskip("mujoco")
trimesh = pytest.importorskip("trimesh")

# A ball on a slide along x (at height 0.5) and a can turning about z at (0, 2, 0): its cylinder
# (radius 0.2, length 0.6) lies along the can link's x axis at height 0.5. The base's box, far
# below, makes the ball and the can a pair (siblings under a base with geometry); each is the
# base's child, so the base is paired with neither.
URDF = """\
<robot name="shapes">
  <link name="base">
    <collision><origin xyz="0 0 -3"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="ball"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="can">
    <collision><origin xyz="0 0 0.5" rpy="0 1.5707963267948966 0"/>
      <geometry><cylinder radius="0.2" length="0.6"/></geometry></collision>
  </link>
  <joint name="x" type="prismatic">
    <parent link="base"/><child link="ball"/><origin xyz="0 0 0.5"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="can"/><origin xyz="0 2 0"/><axis xyz="0 0 1"/>
    <limit lower="-3.2" upper="3.2" effort="1" velocity="1"/>
  </joint>
</robot>
"""

TOLERANCE = 1e-8  # the answers are certified to 1e-9 of each pair's size (a few units here)


@pytest.fixture
def urdf_robot(tmp_path):
    path = tmp_path / "shapes.urdf"
    path.write_text(URDF)
    return sc.Robot.from_urdf(path)


def ball_can(q):
    """The closed-form signed distance from the ball to the can and its derivative in q[0]."""
    x, turn = q
    if turn == 0:  # the can along x, from x = -0.3 to 0.3, 2 from the ball's line
        if abs(x) <= 0.3:
            return 2 - 0.2 - 0.1, 0.0
        reach = np.hypot(abs(x) - 0.3, 1.8)  # to the nearest point of the end's rim
        return reach - 0.1, np.sign(x) * (abs(x) - 0.3) / reach
    # turned a quarter: the can along y from 1.7 to 2.3, its end facing the ball's line
    if abs(x) <= 0.2:
        return 1.7 - 0.1, 0.0
    reach = np.hypot(abs(x) - 0.2, 1.7)
    return reach - 0.1, np.sign(x) * (abs(x) - 0.2) / reach


def test_urdf_cylinders_are_exact_shapes(urdf_robot):
    bodies = {name: body for name, _, _, body in urdf_robot._robot_geometries}
    can = bodies["can"]
    assert isinstance(can, sc.Cylinder) and can.curved
    assert (can.radius, can.half_length) == (0.2, 0.3)
    assert isinstance(bodies["ball"], sc.Sphere)
    assert urdf_robot.pairs == (("ball", "can"),)


@pytest.mark.parametrize("q", [(0.0, 0.0), (0.25, 0.0), (-1.0, 0.0), (2.5, 0.0),
                               (0.1, np.pi / 2), (0.5, np.pi / 2), (-1.2, np.pi / 2)])
def test_a_ball_and_a_cylinder_have_their_closed_form_distance(urdf_robot, q):
    expected, slope = ball_can(q)
    pair = urdf_robot.pairs.index(("ball", "can"))
    distances = urdf_robot.distances(q)
    assert distances[pair] == pytest.approx(expected, abs=TOLERANCE)
    check = urdf_robot.check(q, gradient=True)
    assert tuple(check.pair_names) == ("ball", "can") and check.certified
    assert check.min_distance == pytest.approx(expected, abs=TOLERANCE)
    assert check.lower_bound <= check.min_distance
    assert check.gradient[0] == pytest.approx(slope, abs=1e-6)
    np.testing.assert_allclose(check.point_b - check.point_a, check.min_distance * check.normal,
                               atol=1e-12)


def test_the_ball_against_curved_and_box_obstacles(urdf_robot):
    # An upright cylinder at x = 1 (radius 0.3, z in [0, 1]) and a box at x = -2; an ellipsoid
    # high above (semi-axes 0.5, 0.4, 0.3 centred 1.5 above the ball's line).
    post = np.eye(4)
    post[:3, 3] = [1.0, 0.0, 0.5]
    urdf_robot.add_obstacle(sc.Cylinder(0.3, 0.5), post, name="post")
    block = np.eye(4)
    block[:3, 3] = [-2.0, 0.0, 0.5]
    urdf_robot.add_obstacle(sc.Box([0.1, 0.2, 0.3]), block, name="block")
    egg = np.eye(4)
    egg[:3, 3] = [0.0, 0.0, 2.0]
    urdf_robot.add_obstacle(sc.Ellipsoid([0.5, 0.4, 0.3]), egg, name="egg")
    columns = {pair: k for k, pair in enumerate(urdf_robot.pairs)}
    xs = np.array([-1.5, -0.4, 0.0, 0.45, 0.65, 0.75])
    q = np.column_stack([xs, np.full_like(xs, np.pi / 2)])
    distances = urdf_robot.distances(q, threads=2)
    post_expected = np.abs(xs - 1.0) - 0.3 - 0.1  # radial, the ball within the post's height
    block_expected = (xs + 2.0) - 0.1 - 0.1
    egg_expected = 2.0 - 0.3 - 0.5 - 0.1  # the ellipsoid's lowest point is above x = 0 only
    np.testing.assert_allclose(distances[:, columns[("ball", "post")]], post_expected,
                               atol=TOLERANCE)
    np.testing.assert_allclose(distances[:, columns[("ball", "block")]], block_expected,
                               atol=TOLERANCE)
    assert distances[2, columns[("ball", "egg")]] == pytest.approx(egg_expected, abs=TOLERANCE)
    check = urdf_robot.check(q)
    assert check.certified.all()
    # 0.65 and 0.75 overlap the post by 0.05 and 0.15; the others are apart.
    np.testing.assert_array_equal(check.colliding, [False, False, False, False, True, True])
    np.testing.assert_allclose(check.min_distance[4:], [-0.05, -0.15], atol=TOLERANCE)
    assert [tuple(n) for n in check.pair_names[4:]] == [("ball", "post")] * 2


def test_methods_that_read_points_refuse_curved_geometries_naming_them(urdf_robot):
    # fcl answers curved shapes as FCL's own primitives (libccd through their support functions):
    # only the paper's swarms read a body's points.
    for method in ("ipso", "pso"):
        with pytest.raises(ValueError, match="geometry 'can' is a cylinder.*'dual'"):
            urdf_robot.check([0.0, 0.0], method=method)
        with pytest.raises(ValueError, match="geometry 'can' is a cylinder"):
            urdf_robot.distances([0.0, 0.0], method=method)
    for method in ("exact", "fcl"):
        answer = urdf_robot.check([0.5, np.pi / 2], method=method)
        assert answer.min_distance == pytest.approx(ball_can((0.5, np.pi / 2))[0], abs=TOLERANCE)
    # Without the cylinder's pairs, the fcl method answers the rest: the ball 0.8 from a wall.
    wall = np.eye(4)
    wall[:3, 3] = [0.0, -1.0, 0.5]
    urdf_robot.add_obstacle(sc.Box([1.0, 0.1, 1.0]), wall, name="wall")
    urdf_robot.disable_pairs([("ball", "can"), ("can", "wall")])
    assert urdf_robot.pairs == (("base", "wall"), ("ball", "wall"))
    assert urdf_robot.check([0.0, 0.0], method="fcl").min_distance == pytest.approx(
        0.8, abs=TOLERANCE)


# An ellipsoid on a slide along x, a capsule on a slide along z above it, a cylinder along x on a
# slide along x beside it; the world's box far below pairs them (siblings under the world).
MJCF = """\
<mujoco>
  <worldbody>
    <geom name="floor" type="box" size="1 1 0.01" pos="0 0 -3"/>
    <body name="e"><joint name="ex" type="slide" axis="1 0 0" range="-5 5"/>
      <geom name="egg" type="ellipsoid" size="0.3 0.2 0.1"/></body>
    <body name="c" pos="0 0 1"><joint name="cz" type="slide" axis="0 0 1" range="-5 5"/>
      <geom name="pill" type="capsule" size="0.05 0.2"/></body>
    <body name="k" pos="2 0 0"><joint name="kx" type="slide" axis="1 0 0" range="-5 5"/>
      <geom name="can" type="cylinder" size="0.1 0.3" euler="0 90 0"/></body>
  </worldbody>
</mujoco>
"""


def mjcf_expected(q):
    """Closed forms: egg-pill (the capsule's lowest point above the ellipsoid's top), egg-can
    (the ellipsoid's tip against the middle of the can's end), pill-can (the capsule's lowest
    core point to the rim of the can's end)."""
    ex, cz, kx = q
    return {
        ("egg", "pill"): (1 + cz - 0.2 - 0.05) - 0.1 if ex == 0 else None,
        ("egg", "can"): (2 + kx - 0.3) - (ex + 0.3),
        ("pill", "can"): np.hypot(1.7 + kx, 0.8 + cz - 0.1) - 0.05,
    }


@pytest.fixture
def mjcf_robot(tmp_path):
    path = tmp_path / "shapes.xml"
    path.write_text(MJCF)
    return sc.Robot.from_mjcf(path)


def test_mjcf_ellipsoids_capsules_and_cylinders_are_exact(mjcf_robot):
    bodies = {name: body for name, _, _, body in mjcf_robot._robot_geometries}
    assert isinstance(bodies["egg"], sc.Ellipsoid)
    np.testing.assert_array_equal(bodies["egg"].radii, [0.3, 0.2, 0.1])
    assert isinstance(bodies["pill"], sc.Capsule) and isinstance(bodies["can"], sc.Cylinder)
    assert ("egg", "pill") in mjcf_robot.pairs and ("pill", "can") in mjcf_robot.pairs
    configurations = [(0.0, 0.0, 0.0), (0.0, -0.3, 0.2), (0.0, -0.7, -0.5), (0.4, 1.0, 0.9)]
    distances = mjcf_robot.distances(configurations)
    for row, q in zip(distances, configurations):
        for pair, expected in mjcf_expected(q).items():
            if expected is not None:
                assert row[mjcf_robot.pairs.index(pair)] == pytest.approx(expected, abs=TOLERANCE)
    # q = (0, -0.7, -0.5): the capsule sinks 0.05 into the ellipsoid's top.
    check = mjcf_robot.check(configurations[2])
    assert check.colliding and check.certified
    assert tuple(check.pair_names) == ("egg", "pill")
    assert check.min_distance == pytest.approx(-0.05, abs=TOLERANCE)
    np.testing.assert_allclose(check.normal, [0, 0, 1], atol=1e-9)


def test_mjcf_gradients_are_the_closed_forms(mjcf_robot):
    # The egg-can gap 1.4 + kx - ex is the nearest at (0, 1, -1): 0.4 (the pill is 1.65 away).
    check = mjcf_robot.check([0.0, 1.0, -1.0], gradient=True)
    assert tuple(check.pair_names) == ("egg", "can")
    assert check.min_distance == pytest.approx(0.4, abs=TOLERANCE)
    np.testing.assert_allclose(check.gradient, [-1, 0, 1], atol=1e-9)


def test_proposed_pairs_work_on_curved_shapes(mjcf_robot):
    # A wall far beside the slides never meets them; a ring of the capsule's slide always does.
    wall = np.eye(4)
    wall[:3, 3] = [0.0, 5.0, 0.0]
    mjcf_robot.add_obstacle(sc.Box([9.0, 0.1, 9.0]), wall, name="wall")
    mjcf_robot.add_obstacle(sc.Cylinder(0.06, 9.0), None, name="rail")
    proposal = mjcf_robot.propose_disabled_pairs(100, seed=2)
    assert {("e", "wall"), ("c", "wall"), ("k", "wall")} <= set(proposal.never)
    assert ("c", "rail") in proposal.always
    assert ("e", "k") not in proposal.never and ("e", "k") not in proposal.always


def test_a_compound_geometry_against_a_cylinder_is_answered_part_by_part(tmp_path):
    # The ball's link gets a mesh of two boxes (collision="mesh": a compound of two parts) instead.
    pieces = [trimesh.creation.box((0.1, 0.1, 0.1)), trimesh.creation.box((0.1, 0.1, 0.1))]
    pieces[1].apply_translation((0.3, 0, 0))
    trimesh.util.concatenate(pieces).export(tmp_path / "two.stl")
    path = tmp_path / "shapes.urdf"
    path.write_text(URDF.replace('<sphere radius="0.1"/>', '<mesh filename="two.stl"/>'))
    robot = sc.Robot.from_urdf(path, collision="mesh")
    bodies = {name: body for name, _, _, body in robot._robot_geometries}
    assert isinstance(bodies["ball"], sc.CompoundBody) and len(bodies["ball"].parts) == 2
    q = np.column_stack([np.linspace(-1, 1, 9), np.linspace(-3, 3, 9)])
    distances = robot.distances(q)
    check = robot.check(q)
    column = robot.pairs.index(("ball", "can"))
    names = robot.geometry_names
    for i, poses in enumerate(robot.geometry_poses(q)):
        expected = min(
            sc.signed_distance(part, bodies["can"], pose_a=poses[names.index("ball")],
                               pose_b=poses[names.index("can")]).distance
            for part in bodies["ball"].parts)
        assert distances[i, column] == expected
    np.testing.assert_array_equal(check.min_distance, distances.min(axis=1))
    assert check.certified.all()
    # At q = (0, 0) the boxes' faces at y = 0.05 are 1.75 from the side of the can along x (both
    # parts, at x = 0 and 0.3, lie within its length).
    assert robot.distances([0.0, 0.0])[column] == pytest.approx(2 - 0.05 - 0.2, abs=TOLERANCE)
