"""Robots: models from URDF and MJCF, forward kinematics against yourdfpy's and MuJoCo's, the
pair filter, SRDF, obstacles, and queries over configurations against the single queries."""

import dataclasses
import textwrap

import numpy as np
import pytest

import swarmcollide as sc
import swarmcollide.robot as sc_robot

trimesh = pytest.importorskip("trimesh")
yourdfpy = pytest.importorskip("yourdfpy")
mujoco = pytest.importorskip("mujoco")

URDF = """\
<robot name="arm">
  <link name="base">
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.4 0.4 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><origin xyz="0 0 0.25" rpy="0 0 0.3"/>
      <geometry><cylinder radius="0.05" length="0.4"/></geometry></collision>
  </link>
  <link name="fore">
    <collision><origin xyz="0 0 0.2" rpy="0.1 0.2 0.3"/>
      <geometry><mesh filename="package://pkg/meshes/fore.stl" scale="1 1 2"/></geometry>
    </collision>
  </link>
  <link name="tool">
    <collision><geometry><mesh filename="meshes/tool.obj"/></geometry></collision>
    <collision><origin xyz="0 0 0.1"/><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <link name="slider">
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="finger">
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.02 0.02 0.1"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="continuous">
    <parent link="upper"/><child link="fore"/><origin xyz="0 0 0.5" rpy="0 0.2 0"/>
    <axis xyz="0 1 0"/>
  </joint>
  <joint name="wrist" type="fixed">
    <parent link="fore"/><child link="tool"/><origin xyz="0 0 0.4"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="base"/><child link="slider"/><origin xyz="0.5 0 0.05"/><axis xyz="0.6 0.8 0"/>
    <limit lower="-0.2" upper="0.6" effort="1" velocity="1"/>
  </joint>
  <joint name="grip" type="prismatic">
    <parent link="slider"/><child link="finger"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/>
    <mimic joint="slide" multiplier="-0.5" offset="0.01"/>
  </joint>
</robot>
"""


def write_urdf(tmp_path, text=URDF, meshes=True):
    if meshes:
        (tmp_path / "pkg" / "meshes").mkdir(parents=True)
        trimesh.creation.box((0.06, 0.08, 0.2)).export(tmp_path / "pkg" / "meshes" / "fore.stl")
        (tmp_path / "meshes").mkdir()
        trimesh.creation.icosphere(1, radius=0.05).export(tmp_path / "meshes" / "tool.obj")
    path = tmp_path / "arm.urdf"
    path.write_text(text)
    return path


@pytest.fixture
def urdf(tmp_path):
    return write_urdf(tmp_path)


@pytest.fixture
def arm(urdf):
    return sc.Robot.from_urdf(urdf, package_dirs=[urdf.parent])


def random_configurations(robot, count, seed=0):
    rng = np.random.default_rng(seed)
    lower, upper = np.clip(robot.limits, -np.pi, np.pi).T
    return rng.uniform(lower, upper, size=(count, robot.dof))


def test_urdf_forward_kinematics_is_yourdfpys(arm, urdf):
    reference = yourdfpy.URDF.load(str(urdf), load_meshes=False)
    assert arm.joint_names == tuple(reference.actuated_joint_names)
    q = random_configurations(arm, 20)
    transforms = arm.forward_kinematics(q)
    assert transforms.shape == (20, 6, 4, 4)
    for row, values in zip(transforms, q):
        reference.update_cfg(values)
        for link, transform in zip(arm.link_names, row):
            expected = reference.get_transform(link)
            np.testing.assert_allclose(transform, expected, rtol=0, atol=1e-12 * 2)
    np.testing.assert_array_equal(arm.forward_kinematics(q[3]), transforms[3])


def test_urdf_geometries_have_their_scales_and_shapes(arm):
    assert arm.geometry_names == ("base", "upper", "fore", "tool/0", "tool/1", "slider", "finger")
    fore = arm._robot_geometries[2]
    # The box mesh is 0.06 x 0.08 x 0.2, scaled by 2 along z.
    np.testing.assert_allclose(np.ptp(fore[3].vertices, axis=0), [0.06, 0.08, 0.4])
    upper = arm._robot_geometries[1][3]
    assert isinstance(upper, sc.Cylinder) and (upper.radius, upper.half_length) == (0.05, 0.2)


def test_adjacent_links_and_links_joined_by_fixed_joints_are_not_paired(arm):
    # base-upper, upper-fore (and fore's fixed tool), base-slider, slider-finger are adjacent.
    assert arm.pairs == (
        ("base", "fore"), ("base", "tool/0"), ("base", "tool/1"), ("base", "finger"),
        ("upper", "slider"), ("upper", "finger"), ("fore", "slider"), ("fore", "finger"),
        ("tool/0", "slider"), ("tool/0", "finger"), ("tool/1", "slider"), ("tool/1", "finger"),
    )
    assert arm.dof == 3  # the mimic joint follows the slide


def test_srdf_disables_its_pairs(urdf, tmp_path):
    srdf = tmp_path / "arm.srdf"
    srdf.write_text(textwrap.dedent("""\
        <robot name="arm">
          <disable_collisions link1="tool" link2="base" reason="Never"/>
          <disable_collisions link1="upper" link2="slider" reason="Never"/>
        </robot>"""))
    robot = sc.Robot.from_urdf(urdf, package_dirs=[tmp_path], srdf=srdf)
    assert robot.pairs == (
        ("base", "fore"), ("base", "finger"), ("upper", "finger"), ("fore", "slider"),
        ("fore", "finger"), ("tool/0", "slider"), ("tool/0", "finger"), ("tool/1", "slider"),
        ("tool/1", "finger"),
    )
    bad = tmp_path / "bad.srdf"
    bad.write_text('<robot><disable_collisions link1="tool" link2="hand"/></robot>')
    with pytest.raises(ValueError, match="'hand' is not a link"):
        sc.Robot.from_urdf(urdf, package_dirs=[tmp_path], srdf=bad)


def posed_bodies(robot, q):
    """Every geometry's body and world pose at q, from the robot's FK and the tables."""
    transforms = robot.forward_kinematics(q)
    bodies = {}
    for name, link, origin, body in robot._robot_geometries + robot._obstacles:
        origin = np.eye(4) if origin is None else np.asarray(origin, float)
        bodies[name] = (body, origin if link < 0 else transforms[link] @ origin)
    return bodies


def test_check_and_distances_are_the_single_signed_distances(arm):
    table = np.eye(4)
    table[:3, 3] = [0.6, 0.0, 0.7]
    arm.add_obstacle(sc.Box([0.1, 0.1, 0.02]), table, name="table")
    assert ("base", "table") in arm.pairs and ("slider", "table") in arm.pairs
    q = random_configurations(arm, 60, seed=1)
    distances = arm.distances(q)
    check = arm.check(q)
    assert distances.shape == (60, len(arm.pairs))
    names = arm.geometry_names
    for i in range(0, 60, 7):
        posed = posed_bodies(arm, q[i])
        poses = arm.geometry_poses(q[i])
        for name, pose in zip(names, poses):
            np.testing.assert_allclose(pose, posed[name][1], rtol=0, atol=1e-15)
        for p, (a, b) in enumerate(arm.pairs):
            single = sc.signed_distance(posed[a][0], posed[b][0], pose_a=poses[names.index(a)],
                                        pose_b=poses[names.index(b)])
            assert distances[i, p] == single.distance
    # check skips the pairs whose bounding balls are farther than its nearest pair: its answer
    # is every pair's row reduced (the lowest index on ties).
    nearest = np.argmin(distances, axis=1)
    np.testing.assert_array_equal(check.pair, nearest)
    np.testing.assert_array_equal(check.min_distance, distances[np.arange(60), nearest])
    for i in range(60):
        assert tuple(check.pair_names[i]) == arm.pairs[nearest[i]]
        np.testing.assert_allclose(check.point_b[i] - check.point_a[i],
                                   check.min_distance[i] * check.normal[i], atol=1e-12)
    assert check.certified.all()
    # Bounds hold up to rounding (about 1e-14 of the pair's size, DistanceResult's contract).
    assert (check.lower_bound <= check.min_distance + 1e-13).all()
    np.testing.assert_array_equal(check.colliding, (distances <= 1e-9 * 2).any(axis=1))
    assert 0 < check.colliding.sum() < 60


def test_the_verdict_alone_agrees_with_the_nearest_pair(arm):
    table = np.eye(4)
    table[:3, 3] = [0.6, 0.0, 0.7]
    arm.add_obstacle(sc.Box([0.1, 0.1, 0.02]), table, name="table")
    q = random_configurations(arm, 200, seed=4)
    full = arm.check(q)
    verdict = arm.check(q, nearest=False)
    assert full.certified.all() and verdict.certified.all()
    np.testing.assert_array_equal(verdict.colliding, full.colliding)
    assert 0 < verdict.colliding.sum() < 200
    # The pair named collides (its own row of distances says so); none is named when free.
    distances = arm.distances(q)
    rows = np.flatnonzero(verdict.colliding)
    assert (verdict.pair[rows] >= 0).all()
    assert (distances[rows, verdict.pair[rows]] <= 1e-9 * 2).all()
    assert (verdict.pair[~verdict.colliding] == -1).all()
    assert np.isnan(verdict.min_distance).all() and np.isnan(verdict.lower_bound).all()
    # Answers do not depend on the threads.
    two = arm.check(q, nearest=False, threads=2)
    np.testing.assert_array_equal(two.pair, verdict.pair)
    np.testing.assert_array_equal(two.colliding, verdict.colliding)
    with pytest.raises(ValueError, match="nearest=True"):
        arm.check(q, nearest=False, gradient=True)


def test_answers_do_not_depend_on_the_threads(arm):
    q = random_configurations(arm, 50, seed=2)
    one = arm.check(q, threads=1, gradient=True)
    two = arm.check(q, threads=2, gradient=True)
    for field in ("colliding", "min_distance", "lower_bound", "pair", "point_a", "point_b",
                  "normal", "gradient"):
        np.testing.assert_array_equal(getattr(one, field), getattr(two, field))
    np.testing.assert_array_equal(arm.distances(q, threads=1), arm.distances(q, threads=2))


def assert_is_row(one, batch, i):
    """The check of one configuration holds row i of the batch's, value and shape."""
    for field in ("colliding", "min_distance", "lower_bound", "certified", "pair", "pair_names",
                  "point_a", "point_b", "normal", "gradient"):
        mine, theirs = getattr(one, field), getattr(batch, field)
        if theirs is None:
            assert mine is None
            continue
        np.testing.assert_array_equal(mine, theirs[i])
        assert np.shape(mine) == np.shape(theirs[i]), field


def test_one_configuration_is_its_row_of_the_batch(arm):
    # A check of one configuration reads its row alone (RobotCheck.row): the same values.
    q = random_configurations(arm, 12, seed=5)
    for kinds in ({"gradient": True}, {"nearest": False}, {}):
        batch = arm.check(q, **kinds)
        for i in range(len(q)):
            assert_is_row(arm.check(q[i], **kinds), batch, i)
    with pytest.raises(IndexError, match="row 1 is not in"):
        arm.model.check(arm._pair_table, arm.model.admit(q[:1]), sc.query()).row(1)
    # Outside the limits, one configuration is brought within them as the batch brings its rows
    # (a single configuration is admitted and checked by the checker Robot.check keeps).
    beyond = q + 7.0
    batch = arm.check(beyond, limits="clamp")
    for i in range(len(q)):
        one = arm.check(beyond[i], limits="clamp")
        assert one.min_distance == batch.min_distance[i]
        assert one.pair == batch.pair[i]
    with pytest.raises(ValueError, match=r"q\[0\], joint"):
        arm.check(beyond[0])


def test_a_checker_answers_as_check_and_its_validity_test_is_the_proven_verdict(arm):
    q = random_configurations(arm, 30, seed=8)
    for kinds in ({"gradient": True}, {"nearest": False}, {"tolerance": 1e-6, "seed": 3}, {}):
        checker = arm.checker(**kinds)
        batch = arm.check(q, **kinds)
        for i in range(len(q)):
            assert_is_row(checker(q[i]), batch, i)
            assert checker.collision_free(q[i]) == bool(batch.certified[i] and
                                                        not batch.colliding[i])
    # Both verdicts occur in these configurations, so the test above tells them apart.
    assert 0 < arm.check(q, nearest=False).colliding.sum() < len(q)
    # The checks are built without the dataclass's constructor: every field is there, and the
    # object is what the constructor makes (a frozen RobotCheck equal to one built from them).
    check = arm.checker()(q[0])
    assert list(vars(check)) == [field.name for field in dataclasses.fields(sc.RobotCheck)]
    assert check == dataclasses.replace(check)
    with pytest.raises(dataclasses.FrozenInstanceError):
        check.pair = 0
    # A configuration given with threads is checked on the calling thread, the same answer.
    assert arm.check(q[0], threads=2).min_distance == arm.check(q[0]).min_distance
    assert "limits='clamp'" in repr(arm.checker(limits="clamp"))
    assert f"{len(arm.pairs)} pairs" in repr(arm.checker())


def test_threads_sharing_a_checker_get_their_own_answers(arm):
    # The GIL is released while a checker checks: threads calling one checker (and Robot.check's
    # kept one) at once must each get the answer of their own configuration.
    from concurrent.futures import ThreadPoolExecutor

    q = random_configurations(arm, 400, seed=9)
    batch = arm.check(q, gradient=True)
    checker = arm.checker(gradient=True)
    with ThreadPoolExecutor(4) as pool:
        shared = list(pool.map(checker, q))
        kept = list(pool.map(lambda row: arm.check(row, gradient=True), q))
    for i in range(len(q)):
        assert_is_row(shared[i], batch, i)
        assert_is_row(kept[i], batch, i)


def test_a_checker_refuses_bad_options_and_configurations_by_name(arm):
    with pytest.raises(ValueError, match="limits must be one of"):
        arm.checker(limits="bounce")
    with pytest.raises(ValueError, match="gradient needs the nearest pair"):
        arm.checker(nearest=False, gradient=True)
    with pytest.raises(TypeError, match="nearest must be True or False"):
        arm.checker(nearest=1)
    with pytest.raises(ValueError, match="tolerance"):
        arm.checker(tolerance=-1.0)
    with pytest.raises(ValueError, match="method"):
        arm.checker(method="bogus")
    checker = arm.checker(nearest=False)
    with pytest.raises(ValueError, match=r"shape \(3,\)"):
        checker(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="3 values per configuration.*got 2"):
        checker.collision_free([0.0, 0.0])
    with pytest.raises(ValueError, match=r"q\[1\], joint 'elbow': nan"):
        checker([0.0, np.nan, 0.0])
    with pytest.raises(ValueError, match=r"q\[0\], joint .*limits='clamp'"):
        checker(np.full(3, 7.0))
    with pytest.raises(TypeError, match="real numbers"):
        checker.collision_free(["a", "b", "c"])
    # Robot.check's kept checker refuses what a fresh one refuses, after a call that made it.
    q = random_configurations(arm, 1, seed=1)[0]
    arm.check(q)
    with pytest.raises(TypeError, match="nearest must be True or False"):
        arm.check(q, nearest=1)
    with pytest.raises(ValueError, match="threads"):
        arm.check(q, threads=-1)


def test_methods_without_signed_distances_are_refused_for_the_nearest_pair_up_front():
    # ipso answers verdicts only: a batch's check refused it at its first configuration, naming
    # q[0] as if it were at fault, and a checker was made with it, to fail at its first call.
    points = np.random.default_rng(0).normal(size=(8, 3)) * 0.1
    robot = sc.Robot(["a", "b"], [sc.Joint("j", "revolute", 0, 1, axis=[0, 0, 1], lower=-1,
                                           upper=1)],
                     [("ga", 0, np.eye(4), points), ("gb", 1, (np.eye(3), [1, 0, 0]), points)])
    robot.add_obstacle(points, (np.eye(3), [3.0, 0, 0]), name="rock")
    message = (r"^method 'ipso' answers verdicts, not the signed distances the nearest pair is "
               r"found by: pass nearest=False for the verdict alone, or a method that answers "
               r"them \('dual', 'exact', 'fcl', 'libccd'\)$")
    for call in (lambda: robot.check(np.zeros((3, 1)), method="ipso"),
                 lambda: robot.check(np.zeros(1), method="ipso"),
                 lambda: robot.checker(method="ipso")):
        with pytest.raises(ValueError, match=message):
            call()
    assert not robot.check(np.zeros((3, 1)), method="ipso", nearest=False).colliding.any()
    assert robot.checker(method="ipso", nearest=False).collision_free([0.0])


def test_robot_check_answers_the_robot_as_it_is_now(arm):
    # Robot.check keeps a checker from one call to the next; a change of pairs makes a new one.
    q = random_configurations(arm, 1, seed=3)[0]
    before = arm.checker()
    arm.check(q)
    arm.add_obstacle(sc.Sphere(0.3), None, name="blob")  # deep into the base
    assert arm.check(q).pair_names.tolist() == ["base", "blob"]
    assert "blob" not in before(q).pair_names  # a checker answers the robot it was made for


def test_the_gradient_matches_finite_differences_where_the_nearest_pair_is_unique(arm):
    q = random_configurations(arm, 40, seed=3)
    check = arm.check(q, gradient=True)
    step = 1e-6
    compared = 0
    for i in np.flatnonzero(check.min_distance > 0.02):
        distances = arm.distances(q[i])
        if np.sort(distances)[1] - distances.min() < 0.01:
            continue  # two pairs nearly tie: the minimum may switch pair within a step
        numeric = [(arm.check(q[i] + step * e).min_distance -
                    arm.check(q[i] - step * e).min_distance) / (2 * step)
                   for e in np.eye(arm.dof)]
        np.testing.assert_allclose(check.gradient[i], numeric, atol=1e-5)
        compared += 1
    assert compared >= 5


MJCF = """\
<mujoco>
  <compiler angle="radian"/>
  <asset><mesh name="part" file="{mesh}" scale="1 2 1"/></asset>
  <worldbody>
    <geom name="floor" type="box" size="1 1 0.01" pos="0 0 -0.01"/>
    <body name="base" pos="0 0 0.1" quat="0.9 0 0.1 0.2">
      <joint name="turn" type="hinge" axis="0 0 1" range="-2 2" ref="0.3"/>
      <geom type="cylinder" size="0.05 0.1"/>
      <body name="arm" pos="0 0 0.3">
        <joint name="lift" type="hinge" axis="0 1 0" pos="0 0 -0.05"/>
        <joint name="roll" type="hinge" axis="1 0 0" pos="0.02 0 0" range="-1 1"/>
        <geom type="capsule" size="0.03 0.15" pos="0 0 0.1"/>
        <geom type="ellipsoid" size="0.03 0.04 0.05" pos="0 0 0.3"/>
        <body name="hand" pos="0 0 0.4">
          <joint name="push" type="slide" axis="0 0 1" range="-0.1 0.1"/>
          <geom type="mesh" mesh="part"/>
          <geom type="sphere" size="0.02" pos="0 0 0.1" contype="0" conaffinity="0"/>
          <body name="finger" pos="0.05 0 0.05">
            <geom type="box" size="0.01 0.01 0.04"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


@pytest.fixture
def mjcf(tmp_path):
    trimesh.creation.box((0.05, 0.05, 0.1)).export(tmp_path / "part.stl")
    path = tmp_path / "arm.xml"
    path.write_text(MJCF.format(mesh=tmp_path / "part.stl"))
    return path


def test_mjcf_forward_kinematics_is_mujocos(mjcf):
    robot = sc.Robot.from_mjcf(mjcf)
    model = mujoco.MjModel.from_xml_path(str(mjcf))
    data = mujoco.MjData(model)
    assert robot.dof == model.nq == 4
    assert robot.joint_names == ("turn", "lift", "roll", "push")
    assert robot.link_names[:model.nbody] == ("world", "base", "arm", "hand", "finger")
    q = random_configurations(robot, 20, seed=4)
    transforms = robot.forward_kinematics(q)
    for row, values in zip(transforms, q):
        data.qpos[:] = values
        mujoco.mj_kinematics(model, data)
        for body in range(model.nbody):
            np.testing.assert_allclose(row[body][:3, 3], data.xpos[body], rtol=0, atol=1e-12)
            np.testing.assert_allclose(row[body][:3, :3], data.xmat[body].reshape(3, 3), rtol=0,
                                       atol=1e-12)
        # The geoms' world poses too; collision geoms only, in MuJoCo's order.
        posed = posed_bodies(robot, values)
        collision = [g for g in range(model.ngeom) if model.geom_contype[g] != 0]
        assert len(collision) == len(robot.geometry_names) == model.ngeom - 1
        for g, name in zip(collision, robot.geometry_names):
            np.testing.assert_allclose(posed[name][1][:3, 3], data.geom_xpos[g], rtol=0,
                                       atol=1e-12)
            np.testing.assert_allclose(posed[name][1][:3, :3], data.geom_xmat[g].reshape(3, 3),
                                       rtol=0, atol=1e-12)
    assert [type(g[3]).__name__ for g in robot._robot_geometries] == [
        "Box", "Cylinder", "Capsule", "Ellipsoid", "ConvexPolyhedron", "Box"]
    # MuJoCo's filter: the links between arm's two joints are looked through (arm is base's
    # child, hand arm's), the finger is welded to the hand, and a child of the world (base) is
    # checked against the world's floor.
    assert robot.pairs == (("floor", "base"), ("floor", "arm/0"), ("floor", "arm/1"),
                           ("floor", "hand"), ("floor", "finger"), ("base", "hand"),
                           ("base", "finger"))
    assert robot.check(q).certified.all()


def test_mjcf_planes_raise_unless_skipped(tmp_path):
    path = tmp_path / "plane.xml"
    path.write_text('<mujoco><worldbody><geom name="ground" type="plane" size="1 1 0.1"/>'
                    '<body name="b"><joint type="slide" axis="0 0 1"/>'
                    '<geom type="sphere" size="0.1"/></body></worldbody></mujoco>')
    with pytest.raises(ValueError, match="geom 'ground'.*skip_planes=True"):
        sc.Robot.from_mjcf(path)
    robot = sc.Robot.from_mjcf(path, skip_planes=True)
    assert robot.pairs == ()
    assert sc.Robot.from_mjcf(path, skip_planes=np.True_).pairs == ()
    for flag in ("yes", "no", 1, None):
        with pytest.raises(TypeError, match="skip_planes must be True or False, got"):
            sc.Robot.from_mjcf(path, skip_planes=flag)
    path.write_text('<mujoco><worldbody><body name="b"><joint name="loose" type="ball"/>'
                    '<geom type="sphere" size="0.1"/></body></worldbody></mujoco>')
    with pytest.raises(ValueError, match="joint 'loose'"):
        sc.Robot.from_mjcf(path)
    path.write_text('<mujoco><asset><mesh name="m" file="gone.stl"/></asset><worldbody>'
                    '<body name="b"><joint type="slide"/><geom type="mesh" mesh="m"/></body>'
                    '</worldbody></mujoco>')
    with pytest.raises(ValueError, match="cannot compile MJCF file .*'gone.stl'"):
        sc.Robot.from_mjcf(path)


def test_unnamed_mjcf_geoms_keep_clear_of_named_ones(tmp_path):
    # An unnamed geom is named after its body; a geom elsewhere named like that body (geom and
    # body names are apart in MuJoCo) made two geometries of one name, refused as "pairs[1] pairs
    # geometry 'b' with itself".
    path = tmp_path / "names.xml"
    path.write_text("""<mujoco><worldbody>
  <body name="a"><geom type="box" size="0.1 0.1 0.1"/>
    <body name="b" pos="0 0 0.3"><joint name="j1" axis="0 1 0" range="-3 3"/>
      <geom type="sphere" size="0.1"/>
      <body name="c" pos="0 0 0.3"><joint name="j2" axis="0 1 0" range="-3 3"/>
        <geom type="box" size="0.05 0.05 0.2" pos="0 0 0.2"/><geom type="sphere" size="0.1"/>
      </body></body>
    <body name="d" pos="5 0 0"><geom name="b" type="sphere" size="0.1"/>
      <geom name="c/1" type="sphere" size="0.1" pos="0 1 0"/></body>
  </body></worldbody></mujoco>""")
    robot = sc.Robot.from_mjcf(path)
    # The names no other geom has are kept: the body's own for one geom, body/k for several.
    assert robot.geometry_names == ("a", "b/0", "c/0", "c/2", "b", "c/1")
    assert [type(g[3]).__name__ for g in robot._robot_geometries] == [
        "Box", "Sphere", "Box", "Sphere", "Sphere", "Sphere"]
    assert robot.pairs == (("a", "b/0"), ("a", "c/0"), ("a", "c/2"), ("b/0", "b"), ("b/0", "c/1"),
                           ("c/0", "b"), ("c/0", "c/1"), ("c/2", "b"), ("c/2", "c/1"))


def test_configurations_outside_the_limits_raise_clamp_or_wrap(arm):
    q = np.array([2.5 + 2 * np.pi - 0.5, 7.0, 0.1])
    with pytest.raises(ValueError, match=r"q\[0\], joint 'shoulder'.*limits='clamp'"):
        arm.check(q)
    clamped = arm.forward_kinematics(q, limits="clamp")
    np.testing.assert_array_equal(clamped, arm.forward_kinematics([2.5, 7.0, 0.1]))
    wrapped = arm.forward_kinematics(q, limits="wrap")
    np.testing.assert_allclose(wrapped, arm.forward_kinematics([2.0, 7.0, 0.1]), atol=1e-14)
    with pytest.raises(ValueError, match="joint 'slide'.*revolute joints only"):
        arm.check([0.0, 0.0, 0.7], limits="wrap")
    with pytest.raises(ValueError, match="limits must be one of"):
        arm.check([0.0, 0.0, 0.0], limits="bounce")


def test_bad_configurations_name_what_is_wrong(arm):
    with pytest.raises(ValueError, match="3 values per configuration.*got 2"):
        arm.check([0.0, 0.0])
    with pytest.raises(ValueError, match=r"q\[1\], joint 'elbow': nan"):
        arm.distances([[0.0, 0.0, 0.0], [0.0, np.nan, 0.0]])
    # A configuration alone is named by its value's index, one of a table by its row.
    with pytest.raises(ValueError, match=r"q\[2\], joint 'slide': -inf is not a finite"):
        arm.check([0.0, 0.0, -np.inf], limits="clamp")
    for call in (arm.forward_kinematics, arm.geometry_poses, arm.distances, arm.checker()):
        with pytest.raises(ValueError, match=r"^q\[2\], joint 'slide': 0.7 is outside"):
            call([0.0, 0.0, 0.7])
    with pytest.raises(ValueError, match=r"^q\[3\], joint 'slide': 0.7 is outside"):
        arm.check(np.array([[0.0, 0.0, 0.0]] * 3 + [[0.0, 0.0, 0.7]]))
    with pytest.raises(ValueError, match=r"^q must be an array of real numbers, \(dof,\) or "
                       r"\(m, dof\): setting an array element with a sequence"):
        arm.check([[0.0, 0.0, 0.0], [0.0]])
    with pytest.raises(ValueError, match=r"^q must be an array of real numbers"):
        arm.checker()([[0.0, 0.0], 0.0])
    with pytest.raises(ValueError, match=r"^q1 must be an array of real numbers"):
        arm.check_motion([0.0, 0.0, 0.0], [[0.0, 0.0, 0.0], [0.0]])
    masked = np.ma.masked_array([0.0, 7.0, 0.0], mask=[False, True, False])
    for call in (arm.check, arm.checker(), arm.checker().collision_free, arm.distances,
                 arm.forward_kinematics, lambda q: arm.check_motion(np.zeros(3), q)):
        with pytest.raises(TypeError, match=r"^q1? is a NumPy masked array, whose mask would be "
                           r"ignored: pass q1?\.filled\(value\)"):
            call(masked)
    # Filled, it is a configuration like any other.
    assert arm.check(masked.filled(0.0)).min_distance == arm.check(np.zeros(3)).min_distance
    with pytest.raises(ValueError, match=r"shape \(dof,\) or \(m, dof\)"):
        arm.check(np.zeros((2, 2, 3)))
    with pytest.raises(TypeError, match="real numbers"):
        arm.check(["a", "b", "c"])
    assert arm.distances(np.zeros((0, 3))).shape == (0, len(arm.pairs))
    assert arm.check(np.zeros((0, 3))).min_distance.shape == (0,)


def test_bad_files_name_the_link_or_joint(tmp_path):
    urdf = write_urdf(tmp_path)
    # The package is found beside the URDF without package_dirs, a missing one is named.
    assert sc.Robot.from_urdf(urdf).pairs == sc.Robot.from_urdf(urdf, [tmp_path]).pairs
    missing = tmp_path / "missing.urdf"
    missing.write_text(URDF.replace("package://pkg/", "package://nopkg/"))
    with pytest.raises(ValueError, match="link 'fore'.*package 'nopkg' not found"):
        sc.Robot.from_urdf(missing, package_dirs=[tmp_path])
    (tmp_path / "meshes" / "tool.obj").unlink()
    with pytest.raises(ValueError, match="link 'tool': mesh file 'meshes/tool.obj' not found"):
        sc.Robot.from_urdf(urdf, package_dirs=[tmp_path])
    other = tmp_path / "other"
    other.mkdir()
    path = write_urdf(other, URDF.replace('name="elbow" type="continuous"',
                                          'name="elbow" type="hinge"'), meshes=False)
    with pytest.raises(ValueError, match="joint 'elbow': type 'hinge' is not supported"):
        sc.Robot.from_urdf(path, package_dirs=[tmp_path])
    (tmp_path / "meshes" / "tool.obj").write_text("not a mesh")
    with pytest.raises(ValueError, match="link 'tool': mesh file .*tool.obj"):
        sc.Robot.from_urdf(urdf, package_dirs=[tmp_path])
    dangling = write_urdf(tmp_path / "other", URDF.replace('<child link="finger"/>',
                                                          '<child link="thumb"/>'), meshes=False)
    with pytest.raises(ValueError, match="joint 'grip': link 'thumb' is not in the URDF"):
        sc.Robot.from_urdf(dangling, package_dirs=[tmp_path])
    with pytest.raises(ValueError, match="collision must be one of"):
        sc.Robot.from_urdf(urdf, package_dirs=[tmp_path], collision="hulls")
    with pytest.raises(ValueError, match="not found"):
        sc.Robot.from_urdf(tmp_path / "none.urdf")
    (tmp_path / "folder.urdf").mkdir()
    with pytest.raises(ValueError, match="URDF file .*folder.urdf' is a directory; pass the "):
        sc.Robot.from_urdf(tmp_path / "folder.urdf")
    with pytest.raises(ValueError, match="MJCF file .*folder.urdf' is a directory; pass the "):
        sc.Robot.from_mjcf(tmp_path / "folder.urdf")
    # A shape's own refusal, an empty <geometry> (yourdfpy fails on it without saying where) and
    # a mesh scale that is not finite name their link.
    for bad, message in [('<sphere radius="-0.1"/>', "link 'arm': radius must be"),
                         ('<box size="0.2 0 0.2"/>', r"link 'arm': half_extents\[1\] must be"),
                         ("", "link 'arm': its <collision> element's <geometry> is empty"),
                         ("<mesh/>", "link 'arm': a <collision>'s <mesh> has no filename "
                          "attribute"),
                         ('<mesh filename="arm.stl" scale="nan 1 1"/>',
                          "link 'arm': mesh scale must be finite")]:
        path = other / "bad.urdf"
        trimesh.creation.box((0.1, 0.1, 0.1)).export(other / "arm.stl")
        path.write_text(f"""<robot name="r">
  <link name="base"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="arm"><collision><geometry>{bad}</geometry></collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>""")
        with pytest.raises(ValueError, match=message):
            sc.Robot.from_urdf(path)


TWO_LINKS = """<robot name="r">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="base">
    <inertial><origin xyz="0 0 0"/><mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><sphere radius="0.1"/></geometry><material name="red"/></visual>
    <collision><origin xyz="0 0 0.1" rpy="0 0 0"/><geometry><sphere radius="0.1"/></geometry>
    </collision>
  </link>
  <link name="arm"><collision><geometry><cylinder radius="0.1" length="0.5"/></geometry>
  </collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


@pytest.mark.parametrize("old, new, message", [
    ('<sphere radius="0.1"/></geometry>\n', "<sphere/></geometry>\n",
     "link 'base': <collision><sphere> has no radius attribute"),
    ('<sphere radius="0.1"/></geometry><material',
     '<box size="1 1"/></geometry><material',
     r"link 'base': <visual><box size=\"1 1\"> must be 3 numbers, got 2"),
    ('length="0.5"', "", "link 'arm': <collision><cylinder> has no length attribute"),
    ('radius="0.1" length', 'radius="abc" length',
     r"link 'arm': <collision><cylinder radius=\"abc\">: 'abc' is not a number"),
    ('<robot name="r">', '<robot name="r">', None),  # the file as it is loads
    ("<cylinder", "<capsule", "link 'arm': its <collision> element's <geometry> holds <capsule>, "
     "which is not a URDF shape"),
    ('<collision><origin xyz="0 0 0.1" rpy="0 0 0"/><geometry><sphere radius="0.1"/></geometry>',
     '<collision><origin xyz="0 0 0.1" rpy="0 0 0"/>',
     "link 'base': its <collision> element has no <geometry>"),
    ('<parent link="base"/>', "", r"joint 'j' has no <parent link=\"...\"/> naming its parent"),
    ('<child link="arm"/>', '<child/>', r"joint 'j' has no <child link=\"...\"/> naming its "),
    (' type="revolute"', "", "joint 'j' has no type attribute "
     r"\(give one of revolute, continuous, prismatic, fixed\)"),
    ('<origin xyz="0 0 1"', '<origin xyz="0 0"',
     r"joint 'j': <origin xyz=\"0 0\"> must be 3 numbers, got 2"),
    ('rpy="0 0 0"/><axis', 'rpy="0 0 0 0"/><axis', r"joint 'j': <origin rpy=\"0 0 0 0\"> must "),
    ('lower="-1"', 'lower="x"', r"joint 'j': <limit lower=\"x\">: 'x' is not a number"),
    ('<axis xyz="0 1 0"/>', '<axis xyz="0 1,0"/>', r"joint 'j': <axis xyz=\"0 1,0\">: '1,0' is "),
    ('velocity="1"/>', 'velocity="1"/><mimic multiplier="2"/>',
     "joint 'j': its <mimic> has no joint attribute naming the joint it follows"),
    ('<mass value="1"/>', '<mass value="1 kg"/>',
     r"link 'base': <inertial><mass value=\"1 kg\">: '1 kg' is not a number"),
    ('<inertia ixx="1"', '<inertia ixx="one"', r"link 'base': <inertial><inertia ixx=\"one\">"),
    ('<material name="red"/>', '<material name="red"><color rgba="1 0 red 1"/></material>',
     r"link 'base': <visual><material><color rgba=\"1 0 red 1\">: 'red' is not a number"),
    ('rgba="1 0 0 1"', 'rgba="1 0 0 x"', r"material 'red': <color rgba=\"1 0 0 x\">: 'x' is "),
    ('<link name="arm">', "<link>", "a <link> has no name attribute"),
    ('<joint name="j"', "<joint", "a <joint> has no name attribute"),
    ('<robot name="r">', "<robot>", r"<robot> has no name attribute \(<robot name=\"...\">\)"),
])
def test_urdf_attributes_yourdfpy_cannot_read_name_the_link_or_joint(tmp_path, old, new,
                                                                    message):
    # yourdfpy failed with a bare KeyError ("'radius'"), an AttributeError, float()'s or NumPy's
    # broadcasting message, or read a missing type or child link as None.
    path = tmp_path / "bad.urdf"
    assert old in TWO_LINKS
    path.write_text(TWO_LINKS.replace(old, new, 1))
    if message is None:
        assert sc.Robot.from_urdf(path).joint_names == ("j",)
        return
    with pytest.raises(ValueError, match=rf"^cannot read URDF file '.*bad.urdf': {message}"):
        sc.Robot.from_urdf(path)


def test_a_mesh_scale_is_three_numbers_or_one_for_a_uniform_scale(tmp_path):
    # "1 1" used to read as no scale, and "2 3" or "1 1 1 5" failed in NumPy's broadcasting,
    # naming neither the link nor the scale.
    trimesh.creation.box((0.1, 0.2, 0.3)).export(tmp_path / "arm.stl")
    path = tmp_path / "scaled.urdf"

    def extents(scale):
        path.write_text(f"""<robot name="r"><link name="arm"><collision><geometry>
  <mesh filename="arm.stl" scale="{scale}"/></geometry></collision></link></robot>""")
        return np.ptp(sc.Robot.from_urdf(path)._robot_geometries[0][3].vertices, axis=0)

    np.testing.assert_allclose(extents("1 2 3"), [0.1, 0.4, 0.9])
    np.testing.assert_allclose(extents("2"), [0.2, 0.4, 0.6])  # as yourdfpy and pybullet read it
    for scale, count in [("1 1", 2), ("2 3", 2), ("1 1 1 5", 4)]:
        with pytest.raises(ValueError, match=rf"^link 'arm': mesh scale must be 3 numbers "
                                             rf"\(x y z\), or 1 for a uniform scale, got {count}"):
            extents(scale)


def test_answers_name_the_pairs_checked_after_the_pairs_change(arm):
    # The names an answer reads are made when the pairs change (add_obstacle, disable_pairs).
    q = random_configurations(arm, 1, seed=3)[0]
    before = arm.check(q)
    assert tuple(before.pair_names) == arm.pairs[before.pair]
    arm.add_obstacle(sc.Sphere(0.3), None, name="blob")  # deep into the base
    deepest = arm.check(q)
    assert tuple(deepest.pair_names) == arm.pairs[deepest.pair] == ("base", "blob")
    arm.disable_pairs([("base", "blob")])
    after = arm.check(q, nearest=False)
    assert after.colliding and tuple(after.pair_names) == arm.pairs[after.pair]
    assert ("base", "blob") not in arm.pairs and "blob" in after.pair_names
    motion = arm.check_motion(q, q)
    assert tuple(motion.pair_names) == arm.pairs[motion.pair]


def test_disabled_pairs_must_be_pairs_of_names(arm):
    with pytest.raises(TypeError, match=r"pairs\[0\] must be a pair of link or obstacle names"):
        arm.disable_pairs([("base", "fore", "base")])
    with pytest.raises(TypeError, match="pairs must be a sequence of .name, name. pairs"):
        arm.disable_pairs("base")
    with pytest.raises(ValueError, match="'nothing' is not a link or obstacle"):
        arm.disable_pairs([("base", "nothing")])


def test_obstacle_names_must_be_new(arm):
    with pytest.raises(ValueError, match="'base' is taken"):
        arm.add_obstacle(sc.Sphere(0.1), name="base")
    arm.add_obstacle(sc.Sphere(0.1), np.eye(4))
    assert arm.geometry_names[-1] == "obstacle0"


def test_bad_obstacle_poses_name_the_pose_and_leave_the_robot_as_it_was(arm):
    pairs = arm.pairs
    sheared = np.eye(4)
    sheared[3, 0] = 1.0
    for pose, error, message in [(sheared, ValueError, "last row must be"),
                                 (np.eye(3), ValueError, r"got shape \(3, 3\)"),
                                 ("up", TypeError, "got str")]:
        with pytest.raises(error, match=r"^pose \(of obstacle 'table'\) must be .*" + message):
            arm.add_obstacle(sc.Box([0.5, 0.5, 0.02]), pose, name="table")
    assert arm.pairs == pairs


def test_files_that_are_not_urdf_say_so(tmp_path):
    path = tmp_path / "arm.xml"
    path.write_text('<mujoco><worldbody><body name="b"><joint type="slide"/>'
                    '<geom type="sphere" size="0.1"/></body></worldbody></mujoco>')
    with pytest.raises(ValueError, match=r"does not look like a URDF file: its root element is "
                                         r"<mujoco>.*Robot.from_mjcf"):
        sc.Robot.from_urdf(path)
    assert sc.Robot.from_mjcf(path).dof == 1
    path = tmp_path / "gripper.sdf"
    path.write_text('<sdf version="1.6"><model name="gripper"><link name="palm"/></model></sdf>')
    with pytest.raises(ValueError, match="root element is <sdf>.*convert it to URDF"):
        sc.Robot.from_urdf(path)


def test_files_that_are_not_mjcf_say_so(tmp_path):
    # MuJoCo compiles a URDF with its own importer, into another robot: a mimic joint became a
    # degree of freedom of its own, and the links on a fixed joint one link.
    path = tmp_path / "arm_urdf.xml"
    path.write_text(TWO_LINKS)
    with pytest.raises(ValueError, match=r"^'.*arm_urdf.xml' does not look like an MJCF file: its "
                       r"root element is <robot>, where an MJCF model's is <mujoco>; it is a URDF "
                       r"model: read it with Robot.from_urdf \(swarmcollide robot reads a file "
                       r"ending in .urdf as URDF\)$"):
        sc.Robot.from_mjcf(path)
    assert sc.Robot.from_urdf(path).dof == 1
    path.write_text('<sdf version="1.6"><model name="gripper"><link name="palm"/></model></sdf>')
    with pytest.raises(ValueError, match=r"root element is <sdf>, where an MJCF model's is "
                                         r"<mujoco>$"):
        sc.Robot.from_mjcf(path)


def test_a_urdf_that_is_not_well_formed_xml_is_refused_naming_the_line(tmp_path):
    # yourdfpy's lxml recovered from a file cut short by dropping the rest: the arm, cut inside
    # a joint's tag, loaded without its last links.
    path = write_urdf(tmp_path, URDF[:URDF.index('<joint name="slide"') + 9])
    with pytest.raises(ValueError, match=r"^cannot read URDF file '.*arm.urdf': it is not "
                       r"well-formed XML \(unclosed token: line 35, column 2\); the file ends "
                       r"before its elements do: it may have been cut short"):
        sc.Robot.from_urdf(path)
    path.write_text(URDF.replace("</link>", "</lnk>", 1))
    with pytest.raises(ValueError, match=r"well-formed XML \(mismatched tag: line 4, column 4\)$"):
        sc.Robot.from_urdf(path)
    path.write_text(" \n")
    with pytest.raises(ValueError, match=r"^cannot read URDF file '.*arm.urdf': the file is empty"):
        sc.Robot.from_urdf(path)
    # Blank lines before the XML declaration (as in some of pybullet_data's files) are read, and
    # an error after them is named at its own line.
    path.write_text('\n\n<?xml version="1.0"?>\n' + URDF)
    assert sc.Robot.from_urdf(path).joint_names == ("shoulder", "elbow", "slide")
    path.write_text('\n\n<?xml version="1.0"?>\n' + URDF.replace("</link>", "</lnk>", 1))
    with pytest.raises(ValueError, match=r"\(mismatched tag: line 7, column 4\)$"):
        sc.Robot.from_urdf(path)


def test_proposed_pairs_are_those_that_always_or_never_collided(arm):
    # A stake through the base always meets it; the sampled rows say which pairs never meet.
    arm.add_obstacle(sc.Box([0.05, 0.05, 0.05]), None, name="stake")
    proposal = arm.propose_disabled_pairs(200, seed=1)
    assert ("base", "stake") in proposal.always and ("slider", "stake") not in proposal.always
    q = np.random.default_rng(1).uniform(*np.clip(arm.limits, -np.pi, np.pi).T, size=(200, 3))
    hits = (arm.distances(q) <= 1e-9 * 2).any(axis=0)
    owners = [tuple(name.split("/")[0] for name in pair) for pair in arm.pairs]
    for owner in set(owners):
        met = any(hit for hit, o in zip(hits, owners) if o == owner)
        assert (owner in proposal.never) == (not met)
    assert proposal.never and set(proposal.never).isdisjoint(proposal.always)
    with pytest.raises(ValueError, match="samples must be a positive integer"):
        arm.propose_disabled_pairs(0)
    # Refused before any memory is asked for (the configurations alone would take 24 TB).
    with pytest.raises(ValueError, match="samples must be at most 1,000,000, got 1,000,000,000,000"):
        arm.propose_disabled_pairs(10**12)
    with pytest.raises(ValueError, match="seed must be a non-negative integer, got -1"):
        arm.propose_disabled_pairs(10, seed=-1)
    with pytest.raises(TypeError, match="seed must be an integer, got str"):
        arm.propose_disabled_pairs(10, seed="1")


def slide_robot(tmp_path, lower, upper):
    """A ball of radius 0.3 on a slide along x with limits [lower, upper], and a wall (a box of
    half extents 1, 0.5, 0.5 at x = 5) that it meets for slide values in [3.7, 6.3]."""
    path = tmp_path / f"slide_{lower}_{upper}.urdf"
    path.write_text(f"""<robot name="r"><link name="base"/>
  <link name="carriage"><collision><geometry><sphere radius="0.3"/></geometry></collision></link>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/>
    <axis xyz="1 0 0"/><limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/></joint>
</robot>""")
    wall = np.eye(4)
    wall[0, 3] = 5.0
    return sc.Robot.from_urdf(path).add_obstacle(sc.Box([1.0, 0.5, 0.5]), wall, name="wall")


@pytest.mark.parametrize(("lower", "upper", "always", "never"), [
    (0, 10, False, False), (5, 10, False, False), (4, 6, True, False), (7, 10, False, True)])
def test_proposed_pairs_sample_each_joint_within_its_own_limits(tmp_path, lower, upper, always,
                                                                 never):
    # The samples were every joint's limits clipped to [-pi, pi]: a slide in [5, 10] was refused
    # (pi is outside its limits), and one in [0, 10] sampled in [0, pi] only never met the wall,
    # which it meets over a quarter of its range, so the pair was proposed as never colliding.
    proposal = slide_robot(tmp_path, lower, upper).propose_disabled_pairs(200, seed=3)
    pair = ("carriage", "wall")
    assert (pair in proposal.always, pair in proposal.never) == (always, never)


def test_random_configurations_turn_joints_without_finite_limits_once():
    # A revolute or continuous joint without a finite range takes one turn within its limits;
    # every other joint is uniform within its own, however far beyond [-pi, pi].
    limits = [("slide", "prismatic", 5.0, 10.0), ("wide", "revolute", -10.0, 10.0),
              ("spin", "continuous", 0.0, 0.0), ("up", "revolute", 0.0, np.inf),
              ("down", "revolute", -np.inf, 1.0), ("huge", "revolute", -1e308, 1e308)]
    joints = [sc.Joint(name, kind, 0, k + 1, lower=lower, upper=upper)
              for k, (name, kind, lower, upper) in enumerate(limits)]
    robot = sc.Robot(["base"] + [f"link{k}" for k in range(len(limits))], joints, [])
    q = sc_robot.random_configurations(robot, 20_000, seed=0)
    lower, upper = np.array([[5, 10], [-10, 10], [-np.pi, np.pi], [0, 2 * np.pi],
                             [1 - 2 * np.pi, 1], [-np.pi, np.pi]]).T
    assert (q >= lower).all() and (q <= upper).all()
    np.testing.assert_allclose(q.min(axis=0), lower, atol=0.01 * (upper - lower).max())
    np.testing.assert_allclose(q.max(axis=0), upper, atol=0.01 * (upper - lower).max())
    robot.check(q[:10])  # within the limits the model admits


def test_a_slide_without_finite_limits_is_refused_for_sampling(tmp_path):
    # A slide has no period to sample over, as a turn has: [-pi, pi] metres was a guess.
    path = tmp_path / "rail.xml"
    path.write_text('<mujoco><worldbody><body name="cart"><joint name="rail" type="slide"/>'
                    '<geom type="sphere" size="0.1"/></body></worldbody></mujoco>')
    robot = sc.Robot.from_mjcf(path)
    assert robot.limits.tolist() == [[-np.inf, np.inf]]
    with pytest.raises(ValueError, match=r"^joint 'rail' is prismatic with limits \[-inf, inf\]: "
                                         r".*give it finite limits in the model"):
        robot.propose_disabled_pairs(10)


def test_collision_mesh_makes_compound_bodies_of_the_meshes_convex_pieces(urdf, tmp_path):
    # fore's mesh: two boxes 5 cm apart along z, two convex components.
    pieces = [trimesh.creation.box((0.06, 0.08, 0.1)), trimesh.creation.box((0.06, 0.08, 0.1))]
    pieces[1].apply_translation((0, 0, 0.15))
    trimesh.util.concatenate(pieces).export(tmp_path / "pkg" / "meshes" / "fore.stl")
    robot = sc.Robot.from_urdf(urdf, [tmp_path], collision="mesh")
    fore = robot._robot_geometries[2][3]
    assert isinstance(fore, sc.CompoundBody) and len(fore.parts) == 2
    hull = sc.Robot.from_urdf(urdf, [tmp_path])
    assert robot.pairs == hull.pairs
    q = random_configurations(robot, 40, seed=6)
    distances = robot.distances(q)
    check = robot.check(q, threads=2)
    names = robot.geometry_names
    bodies = {g[0]: g[3] for g in robot._robot_geometries}
    for i in range(0, 40, 9):
        poses = robot.geometry_poses(q[i])
        for p, (a, b) in enumerate(robot.pairs):
            single = sc.signed_distance(bodies[a], bodies[b], pose_a=poses[names.index(a)],
                                        pose_b=poses[names.index(b)])
            assert distances[i, p] == single.distance
    nearest = np.argmin(distances, axis=1)
    np.testing.assert_array_equal(check.pair, nearest)
    np.testing.assert_array_equal(check.min_distance, distances[np.arange(40), nearest])
    assert check.certified.all()
    # The hull holds both boxes: its distances are never larger, and smaller where the gap
    # between the boxes is the nearest point.
    hull_distances = hull.distances(q)
    assert (hull_distances <= distances + 1e-12).all()
    assert (hull_distances < distances - 1e-6).any()


def test_collision_mesh_names_the_link_the_file_and_the_option_for_a_concave_piece(urdf,
                                                                                    tmp_path):
    # One connected piece with a dent: a sphere with a vertex pushed to half its radius.
    dented = trimesh.creation.icosphere(1, radius=0.05)
    vertices = dented.vertices.copy()
    vertices[0] *= 0.5
    trimesh.Trimesh(vertices, dented.faces).export(tmp_path / "pkg" / "meshes" / "fore.stl")
    with pytest.raises(ValueError) as raised:
        sc.Robot.from_urdf(urdf, [tmp_path], collision="mesh")
    message = str(raised.value)
    assert message.startswith("link 'fore': mesh 'package://pkg/meshes/fore.stl' (")
    assert str(tmp_path / "pkg" / "meshes" / "fore.stl") in message
    assert "the connected component 0 of 1" in message and "is not convex" in message
    assert "collision='decompose'" in message and "collision='hull'" in message
    assert "decompose=None" not in message and "decompose='coacd'" not in message
    # The hull of the same mesh is taken as it is.
    assert len(sc.Robot.from_urdf(urdf, [tmp_path]).pairs) > 0


def test_collision_decompose_makes_coacds_parts(urdf, tmp_path, monkeypatch):
    monkeypatch.setenv("SWARMCOLLIDE_CACHE_DIR", str(tmp_path / "cache"))
    pieces = [trimesh.creation.box((0.06, 0.08, 0.1)), trimesh.creation.box((0.06, 0.08, 0.1))]
    pieces[1].apply_translation((0, 0, 0.15))
    trimesh.util.concatenate(pieces).export(tmp_path / "pkg" / "meshes" / "fore.stl")
    robot = sc.Robot.from_urdf(urdf, [tmp_path], collision="decompose")
    fore = robot._robot_geometries[2][3]
    assert fore.decomposition.method == "coacd" and len(fore.parts) == 2
    assert any((tmp_path / "cache").iterdir())
    assert robot.check(random_configurations(robot, 10)).certified.all()


def test_model_tables_are_checked_naming_the_joint():
    with pytest.raises(ValueError, match="joint 'j': type 'planar' is not supported"):
        sc.Joint("j", "planar", 0, 1)
    with pytest.raises(ValueError, match="'a' and 'b' both have no parent joint"):
        sc.Robot(["a", "b"], [], [])
    with pytest.raises(ValueError, match="joint 'k'.*already the child of joint 'j'"):
        sc.Robot(["a", "b"], [sc.Joint("j", "fixed", 0, 1), sc.Joint("k", "fixed", 0, 1)], [])
    with pytest.raises(ValueError, match="cycle"):
        sc.Robot(["a", "b"], [sc.Joint("j", "fixed", 0, 1), sc.Joint("k", "fixed", 1, 0)], [])
    with pytest.raises(ValueError, match="joint 'j': the axis must be finite and nonzero"):
        sc.Robot(["a", "b"], [sc.Joint("j", "revolute", 0, 1, axis=[0, 0, 0])], [])
    # Finite and nonzero however large or small (the plain norm's squares overflow or vanish).
    for axis in ([1e300, 1e300, 0], [1e-300, 0, 0]):
        turned = sc.Robot(["a", "b"], [sc.Joint("j", "revolute", 0, 1, axis=axis)], [])
        expected = np.array(axis) / np.array(axis).max()
        np.testing.assert_allclose(turned.model.joints[0].axis, expected / np.linalg.norm(expected),
                                   rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match="joint 'j': limits must satisfy lower <= upper"):
        sc.Robot(["a", "b"], [sc.Joint("j", "prismatic", 0, 1, lower=1, upper=0)], [])


@pytest.mark.parametrize("mimics, message", [
    ({"m": ("fixed", "j", 1.0, 0.0)}, "joint 'm': a fixed joint cannot mimic another "
     r"\(a mimic joint moves\): make it revolute, continuous or prismatic, or drop its mimic"),
    ({"m": ("revolute", 7, 1.0, 0.0)},
     r"joint 'm': mimic must be a joint index, or -1 for none, got 7 \(the model has 3 joints\)"),
    ({"m": ("revolute", "m", 1.0, 0.0)},
     "joint 'm': it mimics itself; a mimic joint follows another, moving joint"),
    ({"m": ("revolute", "f", 1.0, 0.0)},
     "joint 'm': it mimics joint 'f', which is fixed; a mimic joint follows a moving joint"),
    ({"m": ("revolute", "j", 2.0, 0.0), "f": ("prismatic", "m", 1.0, 0.0)},
     "joint 'f': it mimics joint 'm', which mimics joint 'j'; a mimic joint follows a joint that "
     r"mimics none \(mimic 'j', with the two multipliers and offsets composed\)"),
    ({"m": ("revolute", "j", 1.0, 0.0), "j": ("revolute", "m", 1.0, 0.0)},
     "joint 'j': it mimics joint 'm', which mimics joint 'j'; a mimic joint follows a joint that "
     "mimics none$"),
    ({"m": ("revolute", "j", np.nan, 0.0)}, "joint 'm': its mimic multiplier must be finite"),
    ({"m": ("revolute", "j", 1.0, np.inf)}, "joint 'm': its mimic offset must be finite, got inf"),
])
def test_mimic_joints_name_the_rule_they_break(mimics, message):
    # One message listed every rule ("a mimic joint must move and mimic a moving joint that mimics
    # none, with a finite multiplier and offset"), saying neither which nor whose.
    order = ["j", "m", "f"]
    kinds = {"j": "revolute", "m": "revolute", "f": "fixed"}
    joints = []
    for k, name in enumerate(order):
        kind, follows, multiplier, offset = mimics.get(name, (kinds[name], None, 1.0, 0.0))
        mimic = -1 if follows is None else order.index(follows) if follows in order else follows
        joints.append(sc.Joint(name, kind, k, k + 1, mimic=mimic, multiplier=multiplier,
                               offset=offset))
    with pytest.raises(ValueError, match=f"^{message}"):
        sc.Robot(["a", "b", "c", "d"], joints, [])


def test_a_raw_model_refuses_a_mimic_below_minus_one_and_pairs_that_are_not_indices():
    """RobotModel is public (Robot.model): -2 is not 'no mimic' (-1 is), and pairs of floats
    were truncated to other geometries' indices without a word."""
    with pytest.raises(ValueError, match=r"^joint 'j' mimic \(-1: none\) must be at least -1, "
                                         r"got -2$"):
        sc.Joint("j", "revolute", 0, 1, mimic=-2)
    joints = [sc.Joint("j", "revolute", 0, 1, lower=-1, upper=1)]
    model = sc._core.RobotModel(["a", "b"], joints, [("ga", 0, None, sc.Sphere(0.1)),
                                                     ("gb", 1, None, sc.Sphere(0.1))])
    query = sc.Query("dual")
    assert model.check([[0, 1]], [[0.0]], query).colliding.all()
    for pairs in ([[0.0, 1.0]], [[0.4, 1.7]], np.array([[0, 1]], dtype=np.float32)):
        with pytest.raises(TypeError, match=r"^pairs must be an \(n, 2\) array of integer "
                                            r"geometry indices, got float"):
            model.check(pairs, [[0.0]], query)
    with pytest.raises(ValueError, match=r"^pairs\[0\] = \(0, 1099511627776\) must name two "):
        model.distances([[0, 2 ** 40]], [[0.0]], query)
    with pytest.raises(ValueError, match=r"pairs must be an \(n, 2\) array .* got shape \(3,\)"):
        model.distances([0, 1, 2], [[0.0]], query)
    with pytest.raises(ValueError, match=r"^geometry 'ga' link \(-1: the world\) must be at "):
        sc._core.RobotModel(["a", "b"], joints, [("ga", -2, None, sc.Sphere(0.1))])
    with pytest.raises(TypeError, match=r"^geometry 'ga' link \(-1: the world\) must be an "
                                        r"integer, got float"):
        sc._core.RobotModel(["a", "b"], joints, [("ga", 0.0, None, sc.Sphere(0.1))])
