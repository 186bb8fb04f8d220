"""``swarmcollide robot MODEL``: the report, its JSON, the picture and the errors a shell user
meets."""

import json

import numpy as np
import pytest

import swarmcollide as sc
from swarmcollide.cli import main

pytest.importorskip("yourdfpy")
pytest.importorskip("mujoco")

# Two arms turning about z on a base, one with a ball, one with a cylinder, which meet when
# their angles put them side by side.
URDF = """\
<robot name="pair">
  <link name="base">
    <collision><origin xyz="0 0 -1"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="left">
    <collision><origin xyz="0.5 0 0"/><geometry><sphere radius="0.15"/></geometry></collision>
  </link>
  <link name="right">
    <collision><origin xyz="0.5 0 0"/><geometry><cylinder radius="0.1" length="0.4"/></geometry>
    </collision>
  </link>
  <joint name="a" type="revolute">
    <parent link="base"/><child link="left"/><origin xyz="0 0.3 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="b" type="continuous">
    <parent link="base"/><child link="right"/><origin xyz="0 -0.3 0"/><axis xyz="0 0 1"/>
  </joint>
</robot>
"""

MJCF = """\
<mujoco><worldbody>
  <geom name="floor" type="box" size="1 1 0.1" pos="0 0 -1"/>
  <body name="arm"><joint name="turn" type="hinge" axis="0 1 0" range="-3 3"/>
    <geom name="stick" type="capsule" size="0.05 0.5" pos="0 0 0.5"/></body>
</worldbody><contact><exclude body1="world" body2="arm"/></contact></mujoco>
"""


@pytest.fixture
def urdf(tmp_path):
    path = tmp_path / "pair.urdf"
    path.write_text(URDF)
    return path


def test_the_json_report_is_the_robots_check(urdf, capsys):
    assert main(["robot", str(urdf), "--samples", "300", "--seed", "4", "--threads", "2",
                 "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    robot = sc.Robot.from_urdf(urdf)
    lower, upper = np.clip(robot.limits, -np.pi, np.pi).T
    q = np.random.default_rng(4).uniform(lower, upper, size=(300, robot.dof))
    check = robot.check(q)
    assert (report["links"], report["dof"], report["pairs"]) == (3, 2, 1)
    assert report["samples"] == 300 and report["model"] == str(urdf)
    assert report["colliding"] == int(check.colliding.sum()) > 0
    assert report["collision_rate"] == pytest.approx(check.colliding.mean())
    assert report["certified"] == 300
    assert report["min_distance"] == check.min_distance.min() < 0
    assert report["median_min_distance"] == np.median(check.min_distance)
    assert report["us_per_configuration"] > 0
    nearest = int(np.argmin(check.min_distance))
    assert report["nearest"]["configuration"] == q[nearest].tolist()
    assert report["nearest"]["pair"] == ["left", "right"]
    assert report["nearest"]["distance"] == report["min_distance"]


def test_the_text_report_and_the_picture(urdf, tmp_path, capsys):
    picture = tmp_path / "nearest.png"
    assert main(["robot", str(urdf), "--samples", "50", "--plot", str(picture)]) == 0
    out = capsys.readouterr().out
    assert "3 links, 2 degrees of freedom, 1 pairs checked" in out
    assert "50 configurations (seed 0):" in out and "50 certified" in out
    assert "nearest pair: left - right" in out and "us per configuration" in out
    assert picture.stat().st_size > 10_000
    assert f"saved to {picture}" in out


def test_mjcf_models_are_read_by_their_suffix(tmp_path, capsys):
    path = tmp_path / "stick.xml"
    path.write_text(MJCF)
    assert main(["robot", str(path), "--samples", "20", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["pairs"] == 0 and report["nearest"] is None and report["min_distance"] is None


def test_a_urdf_named_like_mjcf_is_refused(tmp_path, capsys):
    # Read by suffix, it was compiled by MuJoCo's URDF importer into another robot.
    path = tmp_path / "pair.xml"
    path.write_text(URDF)
    assert main(["robot", str(path)]) == 1
    assert capsys.readouterr().err == (f"swarmcollide robot: error: '{path}' does not look like "
                                       "an MJCF file: its root element is <robot>, where an MJCF "
                                       "model's is <mujoco>; it is a URDF model: read it with "
                                       "Robot.from_urdf (swarmcollide robot reads a file ending "
                                       "in .urdf as URDF)\n")


def test_a_missing_model_is_one_line_and_exit_1(tmp_path, capsys):
    assert main(["robot", str(tmp_path / "none.urdf")]) == 1
    err = capsys.readouterr().err
    assert err.strip() == f"swarmcollide robot: error: URDF file '{tmp_path / 'none.urdf'}' not " \
                          "found"
    broken = tmp_path / "broken.urdf"
    broken.write_text(URDF.replace('type="continuous"', 'type="floating"'))
    assert main(["robot", str(broken)]) == 1
    assert "joint 'b': type 'floating' is not supported" in capsys.readouterr().err
    # A mesh without a file escaped as an AttributeError, a traceback.
    broken.write_text(URDF.replace('<sphere radius="0.15"/>', "<mesh/>"))
    assert main(["robot", str(broken)]) == 1
    assert capsys.readouterr().err == ("swarmcollide robot: error: link 'left': a <collision>'s "
                                       "<mesh> has no filename attribute; give its mesh file "
                                       "(<mesh filename=\"...\"/>)\n")


def test_configurations_are_sampled_within_each_joints_own_limits(tmp_path, capsys):
    # Limits clipped to [-pi, pi] made a slide in [5, 10] fail (pi "is outside its limits"), and
    # a slide without finite limits was sampled in [-pi, pi] metres, a guess.
    path = tmp_path / "slide.urdf"
    path.write_text(URDF.replace('type="continuous"', 'type="prismatic"').replace(
        '<axis xyz="0 0 1"/>\n  </joint>',
        '<axis xyz="1 0 0"/><limit lower="5" upper="10" effort="1" velocity="1"/>\n  </joint>'))
    assert sc.Robot.from_urdf(path).limits.tolist() == [[-3, 3], [5, 10]]
    assert main(["robot", str(path), "--samples", "50", "--json"]) == 0
    slide = json.loads(capsys.readouterr().out)["nearest"]["configuration"][1]
    assert 5 <= slide <= 10
    rail = tmp_path / "rail.xml"
    rail.write_text(MJCF.replace('type="hinge" axis="0 1 0" range="-3 3"', 'type="slide"'))
    assert main(["robot", str(rail)]) == 1
    assert "joint 'turn' is prismatic with limits [-inf, inf]" in capsys.readouterr().err


@pytest.mark.parametrize("arguments,message", [
    (["model.obj"], "must end in .urdf (URDF) or .xml or .mjcf (MJCF)"),
    (["model.urdf", "--samples", "0"], "argument --samples: must be an integer at least 1"),
    (["model.urdf", "--samples", str(10**12)],
     "argument --samples: must be at most 1,000,000, got 1,000,000,000,000"),
    (["model.xml", "--collision", "mesh"], "--collision and --package-dir apply to URDF files"),
    (["model.urdf", "--collision", "hulls"], "argument --collision: invalid choice"),
    (["model.urdf", "--plot", "/no/such/folder/x.png"], "does not exist"),
])
def test_wrong_arguments_are_usage_errors(arguments, message, capsys):
    with pytest.raises(SystemExit) as stop:
        main(["robot"] + arguments)
    assert stop.value.code == 2
    assert message in capsys.readouterr().err
