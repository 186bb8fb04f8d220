"""MJCF robots check the geom pairs MuJoCo's contact filter lets through: contype/conaffinity
masks, welded bodies, the parent filter (and its flag), <contact><exclude> and <contact><pair>;
MuJoCo itself is the oracle."""

import numpy as np
import pytest

import swarmcollide as sc

mujoco = pytest.importorskip("mujoco")

# Masks (contype, conaffinity): the defaults (1, 1) but for the bumper (2, 2), the forearm
# (2, 1), the hand (4, 2) and the ghost (0, 0). The bracket has no joint: it is welded to the
# upper arm. The exclude removes base-fore and bumper-fore; the explicit pairs add ghost-hand
# (masks 0) and upper-bracket (one welded body).
ARM = """\
<mujoco>
  <option><flag filterparent="{filterparent}"/></option>
  <worldbody>
    <geom name="floor" type="box" size="1 1 0.05" pos="0 0 -0.05"/>
    <geom name="ghost" type="sphere" size="0.1" pos="0.4 0 0.6" contype="0" conaffinity="0"/>
    <body name="base" pos="0 0 0.12">
      <joint name="turn" type="hinge" axis="0 0 1" range="-3 3"/>
      <geom name="base" type="cylinder" size="0.1 0.1"/>
      <geom name="bumper" type="sphere" size="0.06" pos="0.12 0 0" contype="2" conaffinity="2"/>
      <body name="upper" pos="0 0 0.15">
        <joint name="lift" type="hinge" axis="0 1 0" range="-2.5 2.5"/>
        <geom name="upper" type="capsule" size="0.04 0.15" pos="0 0 0.2"/>
        <body name="bracket" pos="0 0 0.4">
          <geom name="bracket" type="box" size="0.06 0.06 0.03"/>
          <body name="fore">
            <joint name="elbow" type="hinge" axis="0 1 0" range="-2.8 2.8"/>
            <geom name="fore" type="capsule" size="0.03 0.15" pos="0 0 0.2" contype="2"
                  conaffinity="1"/>
            <body name="hand" pos="0 0 0.4">
              <joint name="wrist" type="hinge" axis="1 0 0" range="-3 3"/>
              <geom name="hand" type="box" size="0.08 0.03 0.06" contype="4" conaffinity="2"/>
            </body>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <contact>
    <exclude body1="fore" body2="base"/>
    <pair geom1="hand" geom2="ghost"/>
    <pair geom1="upper" geom2="bracket"/>
  </contact>
</mujoco>
"""

# Every geom pair the filter lets through, worked out by hand from the rule (see from_mjcf).
FILTERED = {("floor", "base"), ("floor", "upper"), ("floor", "bracket"), ("floor", "fore"),
            ("bumper", "hand"), ("upper", "bracket"), ("ghost", "hand")}
# With filterparent="disable", parents and children are checked too (base-fore stays excluded).
PARENTS = {("base", "upper"), ("base", "bracket"), ("upper", "fore"), ("bracket", "fore"),
           ("fore", "hand")}


def write(tmp_path, text, name="robot.xml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def unordered(pairs):
    return {frozenset(pair) for pair in pairs}


def mujoco_filtered_pairs(path):
    """The geom pairs MuJoCo tests, by name: with every margin huge, each pair its filter lets
    through is reported in contact whatever the configuration."""
    model = mujoco.MjModel.from_xml_path(str(path))
    model.geom_margin[:] = 1e3
    model.body_margin[:] = 1e3
    model.pair_margin[:] = 1e3
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return {frozenset((model.geom(c.geom1).name, model.geom(c.geom2).name))
            for c in data.contact[:data.ncon]}


@pytest.mark.parametrize("filterparent, expected", [("enable", FILTERED),
                                                    ("disable", FILTERED | PARENTS)])
def test_the_pairs_are_those_mujocos_filter_lets_through(tmp_path, filterparent, expected):
    path = write(tmp_path, ARM.format(filterparent=filterparent))
    robot = sc.Robot.from_mjcf(path)
    assert unordered(robot.pairs) == unordered(expected) == mujoco_filtered_pairs(path)
    # A geom of masks 0 is a geometry only through its explicit pair.
    assert "ghost" in robot.geometry_names


def test_the_verdicts_per_pair_are_mujocos(tmp_path):
    path = write(tmp_path, ARM.format(filterparent="enable"))
    robot = sc.Robot.from_mjcf(path)
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    rng = np.random.default_rng(7)
    q = rng.uniform(*robot.limits.T, size=(300, robot.dof))
    distances = robot.distances(q)
    compared = contacts = 0
    for values, row in zip(q, distances):
        data.qpos[:] = values
        mujoco.mj_forward(model, data)
        touching = {frozenset((model.geom(c.geom1).name, model.geom(c.geom2).name))
                    for c in data.contact[:data.ncon]}
        # MuJoCo finds contacts on checked pairs only ...
        assert touching <= unordered(robot.pairs)
        # ... and on each checked pair clear of contact by more than its solvers' accuracy,
        # exactly where our signed distance is negative.
        for pair, distance in zip(robot.pairs, row):
            if abs(distance) > 1e-3:
                assert (frozenset(pair) in touching) == (distance < 0), (values, pair, distance)
                compared += 1
                contacts += distance < 0
    assert compared > 1000 and contacts > 50


def test_a_model_whose_geoms_have_contype_0_checks_no_pair_of_its_own(tmp_path):
    # pybullet_data's inverted pendulum: the rail, cart and pole overlap, but MuJoCo checks none.
    path = write(tmp_path, """\
<mujoco>
  <default><geom contype="0"/></default>
  <worldbody>
    <geom name="rail" type="capsule" size="0.02 1" quat="0.707 0 0.707 0"/>
    <body name="cart">
      <joint name="slider" type="slide" axis="1 0 0" range="-1 1"/>
      <geom name="cart" type="capsule" size="0.1 0.1" quat="0.707 0 0.707 0"/>
      <body name="pole">
        <joint name="hinge" type="hinge" axis="0 1 0"/>
        <geom name="pole" type="capsule" fromto="0 0 0 0.001 0 0.6" size="0.049"/>
      </body>
    </body>
  </worldbody>
</mujoco>
""")
    robot = sc.Robot.from_mjcf(path)
    assert robot.pairs == () and mujoco_filtered_pairs(path) == set()
    check = robot.check([[0.0, 0.0], [0.5, 3.0]])
    assert not check.colliding.any() and np.isinf(check.min_distance).all()
    # An obstacle is checked against every geometry, whatever their masks.
    robot.add_obstacle(sc.Box([0.05, 0.05, 0.05]), None, name="block")
    assert robot.pairs == (("rail", "block"), ("cart", "block"), ("pole", "block"))
    assert robot.check([0.0, 0.0]).colliding


def test_disabled_pairs_apply_on_top_of_mujocos(tmp_path):
    robot = sc.Robot.from_mjcf(write(tmp_path, ARM.format(filterparent="enable")))
    robot.disable_pairs([("world", "base"), ("fore", "world")])
    assert unordered(robot.pairs) == unordered(
        FILTERED - {("floor", "base"), ("floor", "fore")})


def test_pairs_given_to_the_constructor_replace_the_adjacency_rule():
    joints = [sc.Joint("a", "revolute", 0, 1, lower=-1, upper=1),
              sc.Joint("b", "revolute", 1, 2, lower=-1, upper=1)]
    geometries = [(name, link, None, sc.Sphere(0.1))
                  for name, link in [("g0", 0), ("g1", 1), ("g2", 2), ("h2", 2)]]
    links = ["l0", "l1", "l2"]
    assert sc.Robot(links, joints, geometries).pairs == (("g0", "g2"), ("g0", "h2"))
    robot = sc.Robot(links, joints, geometries, pairs=[("g2", "g1"), ("h2", "g2")])
    assert robot.pairs == (("g1", "g2"), ("g2", "h2"))
    with pytest.raises(ValueError, match=r"pairs\[0\].*'g9' is not a geometry"):
        sc.Robot(links, joints, geometries, pairs=[("g0", "g9")])
    with pytest.raises(ValueError, match="'g1' with itself"):
        sc.Robot(links, joints, geometries, pairs=[("g1", "g1")])
    with pytest.raises(TypeError, match=r"pairs\[0\] must be a pair"):
        sc.Robot(links, joints, geometries, pairs=[("g0", "g1", "g2")])


@pytest.mark.parametrize("flag", ["contact", "constraint"])
def test_a_model_that_switches_contacts_off_checks_no_pair_and_says_so(tmp_path, flag):
    # Either flag stops MuJoCo's collision detection before any pair, explicit pairs included.
    text = ARM.format(filterparent="enable").replace(
        '<flag filterparent="enable"/>', f'<flag {flag}="disable"/>')
    path = write(tmp_path, text)
    with pytest.warns(UserWarning, match=f"switches contacts off .*{flag}=\"disable\".*MuJoCo "
                                         "checks none of its geom pairs"):
        robot = sc.Robot.from_mjcf(path)
    assert robot.pairs == () and mujoco_filtered_pairs(path) == set()
    assert "hand" in robot.geometry_names  # still checked against obstacles
    robot.add_obstacle(sc.Box([0.05] * 3), np.eye(4), name="block")
    assert ("base", "block") in robot.pairs
