"""A URDF <collision> whose <geometry> element is empty is refused as "cannot read URDF file
'...': list index out of range" (yourdfpy's IndexError): it names neither the link nor what is
missing. robot_urdf._body has a message for this case ("link '...': a <collision> element has
no <geometry>") that yourdfpy's parser never lets it reach.

Census: robots corpus, family "argument", group "urdf" (error-type, "unclear").
"""

import tempfile
from pathlib import Path

import swarmcollide as sc

path = Path(tempfile.mkdtemp()) / "r.urdf"
path.write_text("""<robot name="r">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="arm"><collision><geometry></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>""")
try:
    sc.Robot.from_urdf(path)
    print("accepted")
except ValueError as error:
    print(f"ValueError: {error}")
