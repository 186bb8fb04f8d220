"""check_motion of a batch of motions answers a row otherwise than check_motion of that row
alone (t_lower and the iteration count differ), for robots far from the world's origin (census
"motion far": 22 of 650 cases at seed 0, e.g. robots-0-2076). The docstring and
test_robot_motion.py promise that a single motion "reads its row alone": the same answer. Both
answers here are uncertified ("unresolved"), so neither breaks the time bounds, but the answer
depends on what else is in the batch.

Built from census case 2076 (tests/python/robot_cases.py draws the robot and the motions).
"""

import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
import robot_cases as rc  # noqa: E402

SEED, INDEX = 0, 2076
family, query, source, (source, kind) = rc.robot_case(SEED, INDEX)
rng = rc.case_generator(SEED, INDEX)
model = rc.random_model(rng, source, max_links=5)
world = rc.World.of(model)
model, q0, q1 = rc.motion_ends(model, world, rng, kind)
others = [rc.configurations(model, rng, 2, "raise")[0] for _ in range(2)]
starts, ends = np.vstack([q0, others[0]]), np.vstack([q1, others[1]])
with tempfile.TemporaryDirectory() as folder:
    robot = rc.build_robot(model, source, Path(folder))
order = rc.robot_order(robot, model)
starts, ends = starts[:, order], ends[:, order]
print(f"{query} ({source}): {robot}")
batch = robot.check_motion(starts, ends, threads=1)
for i in range(len(starts)):
    single = robot.check_motion(starts[i], ends[i], threads=1)
    print(f"row {i}: batch t in [{batch.t_lower[i]!r}, {batch.t_upper[i]!r}] iterations "
          f"{batch.iterations[i]} {batch.status[i]} | alone t in [{single.t_lower!r}, "
          f"{single.t_upper!r}] iterations {single.iterations} {single.status}")
    # The same row as the first of a batch of one: is it the batch or the position?
    first = robot.check_motion(starts[i:i + 1], ends[i:i + 1], threads=1)
    print(f"        as a batch of one: t_lower {first.t_lower[0]!r}, iterations "
          f"{first.iterations[0]}")
