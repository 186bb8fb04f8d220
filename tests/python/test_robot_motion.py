"""Robot.check_motion: a link sweeping through a thin pole between two free configurations, free
motions proven free, agreement with a dense-sampling oracle on the exact signed distances of a
small arm's random motions, batches equal to single calls, thread counts, bad input."""

import numpy as np
import pytest

import swarmcollide as sc

TOLERANCE = 1e-9
TIME_TOLERANCE = 1e-6


def transform(translation, rotation=None):
    m = np.eye(4)
    if rotation is not None:
        m[:3, :3] = rotation
    m[:3, 3] = translation
    return m


def sweeping_bar(pole_radius=1e-3):
    """A bar 1 long and 2e-3 thick turning about z at the origin, and a thin pole standing at
    (0, 0.6) in its way."""
    joints = [sc.Joint("turn", "revolute", 0, 1, lower=-3, upper=3)]
    bar = ("bar", 1, transform([0.5, 0, 0]), sc.Box([0.5, 1e-3, 1e-3]))
    robot = sc.Robot(["base", "arm"], joints, [bar])
    return robot.add_obstacle(sc.Cylinder(pole_radius, 1.0), transform([0, 0.6, 0]), name="pole")


def small_arm():
    """Four degrees of freedom: a turn about z, a shoulder about y, a slide along the upper arm,
    and a wrist turning about x that a mimic joint (a finger) follows; a table, a thin pole and a
    ball as obstacles. Its self pairs share the first joints (the pair bound leaves them out)."""
    joints = [
        sc.Joint("turn", "revolute", 0, 1, origin=transform([0, 0, 0.1]), lower=-2.5, upper=2.5),
        sc.Joint("shoulder", "revolute", 1, 2, origin=transform([0, 0, 0.3]), axis=[0, 1, 0],
                 lower=-1.5, upper=2.0),
        sc.Joint("slide", "prismatic", 2, 3, origin=transform([0.45, 0, 0]), axis=[1, 0, 0],
                 lower=-0.1, upper=0.2),
        sc.Joint("wrist", "continuous", 3, 4, origin=transform([0.1, 0, 0]), axis=[1, 0, 0]),
        sc.Joint("finger", "revolute", 2, 5, origin=transform([0.2, 0, 0.05]), axis=[0, 0, 1],
                 lower=-5, upper=5, mimic=1, multiplier=-1.5, offset=0.2),
    ]
    geometries = [
        ("base", 0, transform([0, 0, 0.05]), sc.Box([0.08, 0.08, 0.05])),
        ("column", 1, transform([0, 0, 0.15]), sc.Capsule(0.04, 0.1)),
        ("upper", 2, transform([0.22, 0, 0]), sc.Box([0.22, 0.03, 0.03])),
        ("carriage", 3, None, sc.Sphere(0.05)),
        ("hand", 4, transform([0.08, 0, 0]), sc.Box([0.08, 0.04, 0.01])),
        ("finger", 5, transform([0.1, 0, 0]), sc.Cylinder(0.01, 0.1)),
    ]
    robot = sc.Robot(["base", "l1", "l2", "l3", "l4", "l5"], joints, geometries)
    robot.add_obstacle(sc.Box([0.6, 0.6, 0.01]), transform([0, 0, -0.02]), name="table")
    robot.add_obstacle(sc.Cylinder(0.004, 0.5), transform([0.35, 0.25, 0.3]), name="pole")
    return robot.add_obstacle(sc.Sphere(0.06), transform([-0.3, -0.3, 0.45]), name="ball")


def along(q0, q1, times):
    return q0 + np.outer(times, q1 - q0)


def pair_sizes(robot):
    """Per pair, the sum of its geometries' bounding-ball diameters (the motion's size)."""
    radii = {name: body.bounding_radius for name, _, _, body in
             robot._robot_geometries + robot._obstacles}
    return np.array([2 * (radii[a] + radii[b]) for a, b in robot.pairs])


def check_against_oracle(robot, q0, q1, result, samples=600):
    """Every overlap the exact signed distances see on `samples` times is reported, none happens
    before t_lower, the pair named is within the tolerance at t_upper, and the bracket is within
    the time tolerance. Returns whether the motion touches."""
    assert result.certified and result.status == "converged"
    times = np.linspace(0, 1, samples)
    if result.touches:
        # Denser just before the bracket, where a contact missed would hide.
        times = np.union1d(times, np.linspace(0, result.t_lower, samples, endpoint=False))
    distances = robot.distances(along(q0, q1, times), method="exact", tolerance=1e-12)
    overlapping = (distances < -1e-11).any(axis=1)
    if not result.touches:
        assert not overlapping.any(), times[overlapping][:3]
        np.testing.assert_array_equal(result.q, q1)
        assert result.pair == -1 and np.isnan(result.distance)
        return False
    assert not overlapping[times < result.t_lower].any(), times[overlapping][:3]
    assert 0 <= result.t_lower <= result.t_upper <= 1
    assert result.t_upper - result.t_lower <= TIME_TOLERANCE
    np.testing.assert_allclose(result.q, q0 + result.t_upper * (q1 - q0), rtol=0, atol=1e-15)
    at_upper = robot.distances(result.q, method="exact", tolerance=1e-12)
    assert at_upper[result.pair] <= TOLERANCE * pair_sizes(robot)[result.pair]
    assert tuple(result.pair_names) == robot.pairs[result.pair]
    assert result.distance <= TOLERANCE * pair_sizes(robot)[result.pair]
    return True


def test_a_link_sweeps_through_a_thin_pole_between_two_free_configurations():
    robot = sweeping_bar()
    q0, q1 = np.array([-1.0]), np.array([2.5])
    assert not robot.check(q0).colliding and not robot.check(q1).colliding
    result = robot.check_motion(q0, q1, tolerance=TOLERANCE, time_tolerance=TIME_TOLERANCE)
    assert result.touches and result.certified
    assert tuple(result.pair_names) == ("bar", "pole")
    # The bar's near side (1e-3 thick) meets the pole (radius 1e-3) at (0, 0.6): the turn is then
    # pi/2 less asin(2e-3 / 0.6) from the x axis.
    contact = np.pi / 2 - np.arcsin(2e-3 / 0.6)
    t_contact = (contact + 1.0) / 3.5
    assert result.t_lower <= t_contact <= result.t_upper + 1e-9
    assert check_against_oracle(robot, q0, q1, result)
    # The pole is thinner than OMPL's default resolution steps (1% of the limits' extent, 6 rad
    # x 0.01 x 0.6 = 3.6 cm at the pole): a discrete check between the ends sees nothing.
    states = int(np.ceil(3.5 / (0.01 * 6))) + 1
    assert not robot.check(along(q0, q1, np.linspace(0, 1, states)), nearest=False).colliding.any()


def test_a_free_motion_is_proven_free():
    robot = sweeping_bar()
    result = robot.check_motion([-1.0], [1.2])
    assert not result.touches and result.certified and result.status == "converged"
    assert result.t_lower == result.t_upper == 1
    check_against_oracle(robot, np.array([-1.0]), np.array([1.2]), result)
    # Far from the pole the screens alone prove it.
    assert robot.check_motion([-2.0], [-1.0]).iterations == 0


def test_a_motion_starting_in_contact_is_bracketed_at_zero():
    robot = sweeping_bar()
    result = robot.check_motion([np.pi / 2], [2.0])
    assert result.touches and result.certified and result.t_lower == result.t_upper == 0


@pytest.mark.parametrize("seed", [0, 1])
def test_random_motions_of_a_small_arm_agree_with_dense_sampling(seed):
    robot = small_arm()
    rng = np.random.default_rng(seed)
    lower, upper = np.clip(robot.limits, -np.pi, np.pi).T
    count = 40
    q0 = rng.uniform(lower, upper, size=(count, robot.dof))
    # Edges of a planner: the second end a step of up to a third of the ranges away.
    q1 = np.clip(q0 + rng.uniform(-1, 1, size=q0.shape) * (upper - lower) / 3, lower, upper)
    results = robot.check_motion(q0, q1, threads=2)
    touching = 0
    for i in range(count):
        row = robot.check_motion(q0[i], q1[i], threads=1)
        touching += check_against_oracle(robot, q0[i], q1[i], row)
        assert row.touches == results.touches[i] and row.t_upper == results.t_upper[i]
    # Both kinds of motion are exercised.
    assert 5 <= touching <= count - 5


@pytest.mark.parametrize("method", ["exact", "dual"])
def test_batches_equal_single_calls_and_threads_do_not_change_answers(method):
    # Every motion's queries take the caller's seed (as time_of_impact_many's): seeded by its
    # row, a batch's row whose samples the dual method decided differed from it alone.
    robot = small_arm()
    rng = np.random.default_rng(7)
    lower, upper = np.clip(robot.limits, -np.pi, np.pi).T
    q0 = rng.uniform(lower, upper, size=(30, robot.dof))
    q1 = rng.uniform(lower, upper, size=(30, robot.dof))
    one = robot.check_motion(q0, q1, threads=1, method=method, seed=5)
    two = robot.check_motion(q0, q1, threads=2, method=method, seed=5)
    for field in ("touches", "t_lower", "t_upper", "q", "pair", "point_a", "point_b", "normal",
                  "certified", "iterations"):
        np.testing.assert_array_equal(getattr(one, field), getattr(two, field))
    np.testing.assert_array_equal(one.distance, two.distance)
    assert one.status == two.status
    for i in (0, 13, 29):
        # A single motion reads its row alone (RobotMotionCheck.row): every field the same.
        row = robot.check_motion(q0[i], q1[i], method=method, seed=5)
        assert (row.touches, row.t_lower, row.t_upper, row.pair, row.iterations, row.certified,
                row.status) == (one.touches[i], one.t_lower[i], one.t_upper[i], one.pair[i],
                                one.iterations[i], one.certified[i], one.status[i])
        assert isinstance(row.touches, bool) and isinstance(row.certified, bool)
        np.testing.assert_array_equal(row.distance, one.distance[i])
        for field in ("q", "pair_names", "point_a", "point_b", "normal"):
            np.testing.assert_array_equal(getattr(row, field), getattr(one, field)[i])
    # One start serves every motion.
    fan = robot.check_motion(q0[0], q1[:5], method=method, seed=5)
    for i in range(5):
        assert fan.t_upper[i] == robot.check_motion(q0[0], q1[i], method=method, seed=5).t_upper


@pytest.mark.parametrize("far", [1e4, 1e5])
def test_a_robot_far_from_the_world_origin_is_still_certified(far):
    # There the placed frames' rounding margin (some 400 roundoffs of 1e4 or more) exceeds the
    # contact threshold (1e-9 of the pair's size, 0.55): a distance of 0 proves no contact, but
    # an overlap deeper than the margin does, measured by the signed distance.
    def box_and_ball(x, ball_at):
        """A 0.2 box turning about z at (x, 0, 0), and a ball of radius 0.1 at x + ball_at."""
        arm = sc.Robot(["a", "b"], [sc.Joint("j", "continuous", 0, 1, origin=transform([x, 0, 0]))],
                       [("box", 1, np.eye(4), sc.Box([0.1, 0.1, 0.1]))])
        return arm.add_obstacle(sc.Sphere(0.1), transform([x + ball_at, 0, 0]), name="ball")

    hit = box_and_ball(far, 0.22).check_motion([0.0], [0.7])  # the box's corner reaches the ball
    at_origin = box_and_ball(0.0, 0.22).check_motion([0.0], [0.7])
    assert hit.touches and hit.certified and at_origin.certified
    assert abs(hit.t_upper - at_origin.t_upper) < 1e-5
    start = box_and_ball(far, 0.15).check_motion([0.0], [0.5])  # overlapping at q0
    assert start.touches and start.certified and start.t_upper == 0


@pytest.mark.parametrize("travel", [1.35e154, 1e200])
def test_a_slide_too_long_to_resolve_is_never_proven_free(travel):
    # Centres more than sqrt(DBL_MAX) apart once squared their difference to infinity, and that
    # infinite ball separation proved motions that end in contact free.
    box = sc.Box([0.1, 0.1, 0.1])
    robot = sc.Robot(["base", "slider"],
                     [sc.Joint("slide", "prismatic", 0, 1, axis=[1, 0, 0], lower=-1e300,
                               upper=1e300)],
                     [("slider", 1, None, box)])
    robot.add_obstacle(box, np.eye(4), name="post")
    assert robot.check([0.0]).colliding
    for q0, q1 in (([-travel], [0.0]), ([-travel], [travel])):
        motion = robot.check_motion(q0, q1)
        assert motion.touches, (q0, q1, motion)


def test_the_exact_method_is_the_default_and_agrees_with_the_dual_one():
    robot = small_arm()
    rng = np.random.default_rng(3)
    lower, upper = np.clip(robot.limits, -np.pi, np.pi).T
    q0 = rng.uniform(lower, upper, size=(20, robot.dof))
    q1 = rng.uniform(lower, upper, size=(20, robot.dof))
    default = robot.check_motion(q0, q1)
    exact = robot.check_motion(q0, q1, method="exact")
    dual = robot.check_motion(q0, q1, method="dual")
    for field in ("touches", "t_lower", "t_upper", "pair", "iterations"):
        np.testing.assert_array_equal(getattr(default, field), getattr(exact, field))
    assert default.certified.all() and dual.certified.all()
    np.testing.assert_array_equal(default.touches, dual.touches)
    # Both brackets are proven: each lies within the other's time tolerance.
    touching = default.touches
    assert (default.t_lower[touching] <= dual.t_upper[touching]).all()
    assert (dual.t_lower[touching] <= default.t_upper[touching]).all()


def test_the_iteration_cap_answers_uncertified_with_a_proven_lower_time():
    robot = sweeping_bar()
    capped = robot.check_motion([-1.0], [2.5], max_iterations=2)
    assert capped.touches and not capped.certified and capped.status == "max_iterations"
    exact = robot.check_motion([-1.0], [2.5])
    assert capped.t_lower <= exact.t_upper
    assert capped.iterations <= 2


def test_bad_input_names_the_argument():
    robot = small_arm()
    q = np.zeros(robot.dof)
    with pytest.raises(ValueError, match="q0 must have 4 values"):
        robot.check_motion(np.zeros(3), q)
    with pytest.raises(ValueError, match="q1 must have shape"):
        robot.check_motion(q, np.zeros((2, 2, 4)))
    with pytest.raises(ValueError, match="q0 has 2 rows and q1 3"):
        robot.check_motion(np.zeros((2, 4)), np.zeros((3, 4)))
    with pytest.raises(ValueError, match=r"q1\[1\], joint 'slide': nan is not a finite number"):
        robot.check_motion(q, [q, [0, 0, np.nan, 0]])
    # A configuration given alone is named by the value's index: -2 is q0[1].
    with pytest.raises(ValueError, match=r"q0\[1\], joint 'shoulder': -2 is outside its limits"):
        robot.check_motion([0, -2, 0, 0], q)
    clamped = robot.check_motion([0, -2, 0, 0], q, limits="clamp")
    assert clamped.certified
    with pytest.raises(ValueError, match="limits='wrap' is refused for motions"):
        robot.check_motion(q, q, limits="wrap")
    with pytest.raises(TypeError, match="q0 must hold real numbers"):
        robot.check_motion(["a"] * 4, q)
    for bad in (0.0, -1e-3, np.nan, np.inf):
        with pytest.raises(ValueError, match="time_tolerance must be a positive"):
            robot.check_motion(q, q, time_tolerance=bad)
    for bad in (1.5, 2, 1e300):
        with pytest.raises(ValueError, match="time_tolerance must be .* at most 1 "):
            robot.check_motion(q, q, time_tolerance=bad)
    for bad in (True, "0.5", None):
        with pytest.raises(TypeError, match="time_tolerance must be a real number"):
            robot.check_motion(q, q, time_tolerance=bad)
    with pytest.raises(ValueError, match="tolerance must be positive"):
        robot.check_motion(q, q, tolerance=0.0)
    with pytest.raises(ValueError, match="max_iterations must be at least 1"):
        robot.check_motion(q, q, max_iterations=0)
    with pytest.raises(TypeError, match="max_iterations must be an int"):
        robot.check_motion(q, q, max_iterations=1.5)
    with pytest.raises(ValueError, match="threads"):
        robot.check_motion(q, q, threads=-1)


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e-170, 1e-150, 1e100, 1e200])
def test_a_folding_arm_hits_itself_at_every_scale(scale):
    """Three boxes on two pitch joints folding onto each other: the links' reaches about the
    joints' axes are lengths, whose squares vanished below 1e-162, so a robot that small moved
    nowhere by the motion's bound and its colliding motion was certified free; above 1e154 they
    overflowed, and a free motion was left unresolved."""

    def motion(s, q0=(1.19409338, -1.83584714), q1=(-1.83741193, -2.66206451)):
        joints = [sc.Joint(f"j{k}", "revolute", k, k + 1, origin=transform([0, 0, s]),
                           axis=[0, 1, 0], lower=-3, upper=3) for k in range(2)]
        boxes = [(f"box{k}", k, transform([0, 0, s / 2]), sc.Box([s / 10, s / 10, s / 2]))
                 for k in range(3)]
        robot = sc.Robot(["base", "l1", "l2"], joints, boxes)
        return robot.check_motion(q0, q1)

    unit, scaled = motion(1.0), motion(scale)
    assert unit.touches and unit.certified and scaled.touches and scaled.certified
    assert scaled.t_lower <= unit.t_upper and unit.t_lower <= scaled.t_upper
    free = motion(scale, (0.27392337, -0.46042657), (-0.91805295, -0.96694473))
    assert not free.touches and free.certified
