"""check_motion certifies no contact once the robot stands 1e4 times its pair size from the
world's origin: a box turning into a ball is bracketed to 1e-6 at 1e3 from the origin, but at
1e4 and beyond the answer is "unresolved", uncertified, t in [t_lower, 1]; even a motion that
starts in deep overlap (-0.05 on a pair 0.5 across, which check() certifies as colliding at the
same place) is answered t in [0, 1], uncertified, after 1056 distance queries. The contract
holds (uncertified answers err on the side of contact), but the rounding of coordinates of 1e4
is about 1e-12, far under the tolerance (1e-9 x 0.5): the certificate is lost, not impossible.

Census: robots corpus, family "motion", query "motion far" (uncertified).
"""

import numpy as np

import swarmcollide as sc


def arm(far: float, ball_at: float) -> sc.Robot:
    """A 0.2 box turning about z at (far, 0, 0), and a ball of radius 0.1 at far + ball_at."""
    origin = np.eye(4)
    origin[0, 3] = far
    robot = sc.Robot(["a", "b"], [sc.Joint("j", "continuous", 0, 1, origin=origin)],
                     [("box", 1, np.eye(4), sc.Box([0.1, 0.1, 0.1]))])
    ball = np.eye(4)
    ball[0, 3] = far + ball_at
    return robot.add_obstacle(sc.Sphere(0.1), ball, name="ball")


for far in (0.0, 1e3, 1e4, 1e5, 1e6):
    touching = arm(far, 0.22).check_motion([0.0], [0.7])  # the box's corner reaches the ball
    start = arm(far, 0.15)  # overlapping at q0 already
    deep = start.check_motion([0.0], [0.5])
    print(f"far {far:g}: contact mid-motion {touching} {touching.status}; starting in overlap "
          f"(check(q0): colliding={bool(start.check([0.0]).colliding)}, certified="
          f"{bool(start.check([0.0]).certified)}): {deep} {deep.status}")
