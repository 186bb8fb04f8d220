"""A URDF with a bad collision geometry (negative or NaN sphere radius, a zero box size, a NaN
mesh scale) is refused with the shape's own message, which names neither the link nor the file:
in a robot of 30 links the user cannot tell which one is at fault. The mesh errors of the same
reader name the link ("link 'hand': mesh file ... not found"), so these should too.

Census: robots corpus, family "argument", group "urdf" (error-type, "unclear").
"""

import tempfile
from pathlib import Path

import trimesh

import swarmcollide as sc

URDF = """<robot name="r">
  <link name="base"><collision><geometry>{base}</geometry></collision></link>
  <link name="arm"><collision><geometry>{arm}</geometry></collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""

folder = Path(tempfile.mkdtemp())
trimesh.creation.box((0.1, 0.1, 0.1)).export(folder / "arm.stl")
box, sphere = '<box size="0.2 0.2 0.2"/>', '<sphere radius="0.1"/>'
for what, base, arm in [
    ("negative sphere radius on link 'arm'", box, '<sphere radius="-0.1"/>'),
    ("NaN sphere radius on link 'arm'", box, '<sphere radius="nan"/>'),
    ("zero box size on link 'base'", '<box size="0.2 0 0.2"/>', sphere),
    ("NaN mesh scale on link 'arm'", box, '<mesh filename="arm.stl" scale="nan 1 1"/>'),
]:
    path = folder / "r.urdf"
    path.write_text(URDF.format(base=base, arm=arm))
    try:
        sc.Robot.from_urdf(path)
        print(f"{what}: accepted")
    except ValueError as error:
        print(f"{what}: ValueError: {error}")
