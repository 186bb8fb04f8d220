"""time_of_impact against a dense-sampling oracle on the exact signed distance, and cases with
known first contacts."""

import inspect

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation, Slerp

import swarmcollide as sc

TOLERANCE = 1e-9


def transform(rotation, translation):
    m = np.eye(4)
    m[:3, :3] = rotation
    m[:3, 3] = translation
    return m


def motion_poses(start, end, times):
    """The motion's poses at ``times``, as the documentation defines it: translation linear,
    rotation R0 exp(t log(R0^T R1)) (SciPy's Slerp turns the same way, the shorter one)."""
    turn = Slerp([0, 1], Rotation.from_matrix([start[:3, :3], end[:3, :3]]))(times).as_matrix()
    poses = np.tile(np.eye(4), (len(times), 1, 1))
    poses[:, :3, :3] = turn
    poses[:, :3, 3] = start[:3, 3] + np.outer(times, end[:3, 3] - start[:3, 3])
    return poses


def motion_size(a, b):
    """The motion's size: the sum of the bodies' bounding-ball diameters."""
    return 2 * (a.bounding_radius + b.bounding_radius)


def random_pose(rng, spread):
    return transform(Rotation.random(random_state=rng).as_matrix(), rng.uniform(-spread, spread, 3))


def check_against_oracle(a, b, motion_a, motion_b, result, samples=400, tolerance=TOLERANCE,
                         path=motion_poses):
    """No overlap the samples see is missed, none happens before ``t_lower``, and the bodies are
    within the tolerance at ``t_upper`` (both on the exact signed distance); ``path(start, end,
    times)`` gives the motion's poses."""
    times = np.linspace(0, 1, samples)
    if result.touches:
        times = np.union1d(times, [result.t_lower, result.t_upper])
    oracle = sc.signed_distance_many(
        a, b, method="exact", tolerance=1e-12,
        poses_a=path(*motion_a, times), poses_b=path(*motion_b, times))
    size = motion_size(a, b)
    # Overlap beyond the oracle's own precision and the poses' rounding.
    overlapping = oracle.distance < -1e-11 * size
    assert result.certified
    if not result.touches:
        assert not overlapping.any(), times[overlapping][:3]
        return False
    assert not overlapping[times < result.t_lower].any()
    at_upper = sc.signed_distance(
        a, b, method="exact", tolerance=1e-12,
        pose_a=path(*motion_a, [result.t_upper])[0],
        pose_b=path(*motion_b, [result.t_upper])[0])
    assert at_upper.lower_bound <= tolerance * size * (1 + 1e-6) + 1e-11 * size
    assert result.t_upper - result.t_lower <= sc.DEFAULT_TIME_TOLERANCE
    return True


@pytest.mark.parametrize("seed", range(4))
def test_random_motions_agree_with_dense_sampling(seed):
    rng = np.random.default_rng(seed)
    touching = 0
    for _ in range(40):
        a = sc.ConvexPolyhedron(rng.normal(size=(8, 3)))
        b = sc.ConvexPolyhedron(rng.normal(size=(8, 3)) * rng.uniform(0.3, 1.5))
        motion_a = (random_pose(rng, 4), random_pose(rng, 4))
        motion_b = (random_pose(rng, 1), random_pose(rng, 1))
        r = sc.time_of_impact(a, b, pose_a=motion_a, pose_b=motion_b)
        touching += check_against_oracle(a, b, motion_a, motion_b, r)
    # The motions are a mix of both answers.
    assert 5 <= touching <= 35


@pytest.mark.parametrize(
    "body",
    [
        sc.Sphere(0.6),
        sc.Capsule(0.3, 0.5),
        sc.Box([0.4, 0.3, 0.5], radius=0.05),
        sc.Cylinder(0.4, 0.6),
        sc.Cone(0.5, 0.6),
        sc.Ellipsoid([0.6, 0.3, 0.4]),
        sc.ConvexPolyhedron(np.random.default_rng(1).normal(size=(12, 3)) * 0.4, radius=0.1),
    ],
    ids=lambda body: type(body).__name__,
)
def test_every_shape_agrees_with_dense_sampling(body):
    rng = np.random.default_rng(5)
    other = sc.Box([0.3, 0.6, 0.2])
    for _ in range(12):
        motion_a = (random_pose(rng, 3), random_pose(rng, 3))
        motion_b = (random_pose(rng, 0.5), random_pose(rng, 0.5))
        r = sc.time_of_impact(body, other, pose_a=motion_a, pose_b=motion_b)
        check_against_oracle(body, other, motion_a, motion_b, r)


def test_compound_bodies_find_the_first_part_hit():
    cube = sc.Box([0.5] * 3)
    pair = sc.CompoundBody([cube, sc.ConvexPolyhedron(cube.vertices + [3, 0, 0])])
    start, end = transform(np.eye(3), [1.5, -5, 0]), transform(np.eye(3), [1.5, 5, 0])
    assert not sc.time_of_impact(sc.Sphere(0.5), pair, pose_a=(start, end)).touches
    start, end = transform(np.eye(3), [8, 0, 0]), transform(np.eye(3), [1.5, 0, 0])
    r = sc.time_of_impact(sc.Sphere(0.5), pair, pose_a=(start, end))
    # The ball's centre reaches x = 4 (the second cube's face at 3.5) after 4 of 6.5.
    assert r.touches and r.certified
    assert r.t_lower <= 4 / 6.5 + 1e-12 and r.t_upper >= 4 / 6.5 - 1e-6


@pytest.mark.parametrize("scale", [1e-100, 1e-6, 1.0, 1e6, 1e100])
def test_a_cube_through_a_thin_plate_at_every_scale(scale):
    cube, plate = sc.Box([0.5 * scale] * 3), sc.Box([5e-4 * scale, 5 * scale, 5 * scale])
    start, end = transform(np.eye(3), [-10 * scale, 0, 0]), transform(np.eye(3), [10 * scale, 0, 0])
    r = sc.time_of_impact(cube, plate, pose_a=(start, end))
    first = 9.4995 / 20
    assert r.touches and r.certified
    assert r.t_lower <= first * (1 + 1e-12)
    assert r.t_upper >= first - TOLERANCE * motion_size(cube, plate) / (20 * scale) - 1e-12
    # Neither end touches: a discrete check misses it.
    assert not sc.collide(cube, plate, pose_a=start) and not sc.collide(cube, plate, pose_a=end)


@pytest.mark.parametrize("gap", [1e-9, -1e-9])
def test_grazing_motions_miss_or_touch_by_a_billionth(gap):
    cube = sc.Box([0.5] * 3)
    y = 1 + gap * motion_size(cube, cube)
    start, end = transform(np.eye(3), [-5, y, 0]), transform(np.eye(3), [5, y, 0])
    r = sc.time_of_impact(cube, cube, pose_a=(start, end), tolerance=1e-12)
    assert r.certified
    assert r.touches == (gap < 0)


def test_a_bar_turning_through_a_gap():
    post, bar = sc.Box([0.05] * 3), sc.Box([1.4, 0.1, 0.1])
    turn = transform(Rotation.from_euler("z", 0.9 * np.pi).as_matrix(), [0, 0, 0])
    at_post = transform(np.eye(3), [0, 1.5, 0])
    # The short bar passes under the post; a long one hits it on the way.
    assert not sc.time_of_impact(bar, post, pose_a=(np.eye(4), turn), pose_b=at_post).touches
    long_bar = sc.Box([2, 0.1, 0.1])
    r = sc.time_of_impact(long_bar, post, pose_a=(np.eye(4), turn), pose_b=at_post)
    # The bar's leading face (0.1 from its axis) meets the post's corner (0.05, 1.45) at the
    # angle where -0.05 sin(phi) + 1.45 cos(phi) = 0.1.
    phi = brentq(lambda p: -0.05 * np.sin(p) + 1.45 * np.cos(p) - 0.1, 0, np.pi / 2)
    first = phi / (0.9 * np.pi)
    assert r.touches and r.certified
    assert r.t_lower <= first + 1e-12 and r.t_upper >= first - 1e-6


@pytest.mark.parametrize("scale", [1e-200, 1e-150, 1.0, 1e150, 1e200])
def test_a_turning_bar_hits_the_post_at_every_scale(scale):
    """The bar's reach about its origin bounds how fast its turn moves it: at 1e-200 its
    vertices' squared norms underflowed to zero, so the turn was taken for no motion and the
    contact missed; at 1e200 they overflowed and nothing was proven."""
    post, bar = sc.Box([0.05 * scale] * 3), sc.Box([2 * scale, 0.1 * scale, 0.1 * scale])
    turn = transform(Rotation.from_euler("z", 0.9 * np.pi).as_matrix(), [0, 0, 0])
    r = sc.time_of_impact(bar, post, pose_a=(np.eye(4), turn),
                          pose_b=transform(np.eye(3), [0, 1.5 * scale, 0]))
    phi = brentq(lambda p: -0.05 * np.sin(p) + 1.45 * np.cos(p) - 0.1, 0, np.pi / 2)
    first = phi / (0.9 * np.pi)
    assert r.touches and r.certified
    assert r.t_lower <= first + 1e-12 and r.t_upper >= first - 1e-6

def test_curved_pairs_the_exact_queries_leave_unproven_are_asked_of_dual():
    """An ellipsoid leaving a polytope from a micrometre away: "exact" alone proves no lower bound
    above the threshold there (uncertified), so the advancement could not step; the motion's
    exact queries ask "dual" again at such times, and the motion is proven free. (An ellipsoid
    and a cylinder stalled so until the exact distance tried its corral's planes. Since Newton's
    steps follow a polytope's edges beside an ellipsoid, "exact" stalls so far more rarely: the
    five pairs of 2 seeds in 400 hold such a case, seed 15's no longer.)"""
    rng = np.random.default_rng(0)
    egg = sc.Ellipsoid([0.3, 0.2, 0.1])
    stalled = 0
    for _ in range(5):
        can = sc.ConvexPolyhedron(rng.normal(size=(12, 3)) * 0.3)
        away = rng.normal(size=3)
        away /= np.linalg.norm(away)
        still, start = np.eye(4), np.eye(4)
        still[:3, :3] = Rotation.random(random_state=rng).as_matrix()
        start[:3, :3] = Rotation.random(random_state=rng).as_matrix()
        start[:3, 3] = brentq(lambda s: sc.distance(egg, can, pose_a=np.block(
            [[start[:3, :3], s * away[:, None]], [np.zeros((1, 3)), 1]]), pose_b=still).distance
            - 1e-6, 0, 3, xtol=1e-14) * away
        alone = sc.distance(egg, can, pose_a=start, pose_b=still, method="exact",
                            tolerance=2.5e-10)
        threshold = 1e-9 * 2 * (egg.bounding_radius + can.bounding_radius)
        stalled += not alone.certified and not alone.lower_bound > threshold
        end = start.copy()
        end[:3, 3] += away
        r = sc.time_of_impact(egg, can, pose_a=(start, end), pose_b=still, method="exact")
        assert not r.touches and r.certified and r.status == "converged"
    assert stalled > 0  # the case this test is for



def test_a_turning_motion_that_exact_alone_leaves_unresolved_is_proven():
    """Random turning motion 21 of bench/motion.py's seed (8-point hulls, A between two random
    poses in a cube of side 8, B near the origin): near its first contact the exact queries
    left times unproven that bisection could not split ('unresolved'); the motion's exact
    queries ask "dual" again there, and the contact is bracketed and certified."""

    def pose(rng, spread):
        p = np.eye(4)
        p[:3, :3] = Rotation.random(random_state=rng).as_matrix()
        p[:3, 3] = rng.uniform(-spread, spread, 3)
        return p

    rng = np.random.default_rng(28)
    for _ in range(22):
        pa, pb = rng.normal(size=(8, 3)) * 0.5, rng.normal(size=(8, 3)) * 0.5
        a0, a1, b0, b1 = pose(rng, 4), pose(rng, 4), pose(rng, 0.5), pose(rng, 0.5)
    r = sc.time_of_impact(pa, pb, pose_a=(a0, a1), pose_b=(b0, b1))
    assert r.touches and r.certified and r.status == "converged"
    assert r.t_upper - r.t_lower <= 1e-6 and r.t_upper == pytest.approx(0.68924, abs=1e-5)


def test_a_body_turning_about_its_own_long_axis_steps_by_its_width():
    """A bar 10 long and 0.02 wide spinning about its own axis while it slides into a post: the
    turn moves its points by their distance from the axis, not from its origin, so the
    advancement steps as for a slide (121 queries when the bound took the bar's half length)."""
    bar, post = sc.Box([0.01, 0.01, 5.0]), sc.Box([0.5, 0.5, 0.5])
    start, end = np.eye(4), np.eye(4)
    start[:3, 3] = [-2, 0, 0]
    spin = end.copy()
    spin[:3, :3] = Rotation.from_rotvec([0, 0, 3.0]).as_matrix()
    slide = sc.time_of_impact(bar, post, pose_a=(start, end))
    turn = sc.time_of_impact(bar, post, pose_a=(start, spin))
    assert slide.touches and turn.touches and slide.certified and turn.certified
    assert turn.iterations <= 4 * slide.iterations + 4


def test_a_plank_turning_onto_a_block_steps_by_its_corner():
    """A plank 10 long turns from 30 to -30 degrees about z, its far end high above, while it
    slides down onto a block under its near end: the corner there meets the block's face at
    about the slide's speed, and a bound on each point's own rate and depth behind the support
    plane steps as for that corner (5 queries; 39 when every point was taken at the fastest
    one's rate)."""
    points = np.array([[x, y, z] for x in (0, 10) for y in (-0.1, 0.1) for z in (-0.5, 0.5)])
    plank, block = sc.ConvexPolyhedron(points), sc.Box([1.0, 0.25, 1.0])

    def pose(degrees, down):
        return transform(Rotation.from_euler("z", degrees, degrees=True).as_matrix(), [0, -down, 0])

    r = sc.time_of_impact(plank, block, pose_a=(pose(30, 0), pose(-30, 4)),
                          pose_b=transform(np.eye(3), [0.5, -1.5, 0]))
    # The corner (0, -0.1) is at height -0.1 cos(30 - 60 t degrees) - 4 t; the face at -1.25.
    meets = brentq(lambda t: 1.25 - 0.1 * np.cos(np.radians(30 - 60 * t)) - 4 * t, 0, 1)
    slack = TOLERANCE * motion_size(plank, block) / 3.9  # contact within the tolerance, in time
    assert r.touches and r.certified and r.t_upper - r.t_lower <= 1e-6
    assert r.t_lower <= meets and r.t_upper >= meets - slack
    assert r.iterations <= 8


@pytest.mark.parametrize("far", [1e10, 1e160, 1e300])
def test_bodies_far_apart_are_proven_free(far):
    """Margins on the translations' sizes are taken without squaring them: squares beyond 1e308
    made them infinite and every motion past 1e154 unresolved."""
    cube = sc.Box([0.5] * 3)
    start, end = transform(np.eye(3), [far, 0, 0]), transform(np.eye(3), [far, far, 0])
    for motion in ((start, start), (start, end)):
        r = sc.time_of_impact(cube, cube, pose_a=motion)
        assert (r.touches, r.certified, r.iterations) == (False, True, 1)
    beyond = transform(np.eye(3), [-1.7e308, 0, 0]), transform(np.eye(3), [1.7e308, 0, 0])
    if far == 1e300:
        with pytest.raises(ValueError, match="double range"):
            sc.time_of_impact(cube, cube, pose_a=beyond)


@pytest.mark.parametrize("x", [1e5, 1e6])
def test_an_overlap_deeper_than_the_poses_rounding_proves_contact(x):
    """Unit cubes given in world coordinates near (x, 0, 0), A moving 2.5 units to end half into
    B: the poses' rounding margin (hundreds of roundoffs of the largest size the motion spans)
    then exceeds the contact threshold, 1e-9 of the size, so a distance of zero proved no contact
    however deep the overlap, and the motion ended unresolved with the bracket [0.8, 1]. An
    overlap deeper than the margin proves it (the signed distance), as for unit spheres flying
    from -x to x past each other, 0.1 deep at mid-motion."""
    corners = np.array([[i, j, k] for i in (-0.5, 0.5) for j in (-0.5, 0.5) for k in (-0.5, 0.5)])
    cube = sc.ConvexPolyhedron(corners + [x, 0, 0])
    start, end = transform(np.eye(3), [-3, 0, 0]), transform(np.eye(3), [-0.5, 0, 0])
    r = sc.time_of_impact(cube, cube, pose_a=(start, end))
    assert r.touches and r.certified and r.status == "converged"
    # First contact at t = 0.8; within the threshold at most its width (over 2.5 a unit of
    # time) earlier.
    assert r.t_lower <= 0.8 and r.t_upper >= 0.8 - TOLERANCE * motion_size(cube, cube) / 2.5
    assert r.t_upper - r.t_lower <= 1e-6
    ball = sc.Sphere(1.0)
    flight = transform(np.eye(3), [-x, 0, 0]), transform(np.eye(3), [x, 0, 0])
    r = sc.time_of_impact(ball, ball, pose_a=flight, pose_b=transform(np.eye(3), [0, 1.9, 0]))
    meets = 0.5 - np.sqrt(4 - 1.9**2) / (2 * x)
    assert r.touches and r.certified and r.status == "converged"
    assert r.t_lower <= meets <= r.t_upper + TOLERANCE * motion_size(ball, ball) / (2 * x)
    assert r.t_upper - r.t_lower <= 1e-6


def test_start_in_contact_and_no_motion():
    cube = sc.Box([0.5] * 3)
    start, end = transform(np.eye(3), [0.9, 0, 0]), transform(np.eye(3), [5, 0, 0])
    r = sc.time_of_impact(cube, cube, pose_a=(start, end))
    assert (r.touches, r.certified, r.t_lower, r.t_upper) == (True, True, 0.0, 0.0)
    still = transform(np.eye(3), [3, 0, 0])
    r = sc.time_of_impact(cube, cube, pose_a=still)
    assert (r.touches, r.certified, r.iterations) == (False, True, 1)
    assert "touches=False" in repr(r) and "certified=True" in repr(r)


def test_results_are_deterministic_and_batches_match_single_calls():
    rng = np.random.default_rng(9)
    cube = sc.Box([0.5] * 3)
    starts = np.stack([random_pose(rng, 3) for _ in range(30)])
    ends = np.stack([random_pose(rng, 3) for _ in range(30)])
    one = sc.time_of_impact_many(cube, cube, poses_a=(starts, ends), threads=1)
    two = sc.time_of_impact_many(cube, cube, poses_a=(starts, ends), threads=2)
    assert len(one) == 30 and "rows=30" in repr(one)
    for name in ("touches", "t_lower", "t_upper", "iterations", "certified"):
        np.testing.assert_array_equal(getattr(one, name), getattr(two, name))
    for i in range(30):
        single = sc.time_of_impact(cube, cube, pose_a=(starts[i], ends[i]))
        again = sc.time_of_impact(cube, cube, pose_a=(starts[i], ends[i]))
        assert (single.t_lower, single.t_upper) == (again.t_lower, again.t_upper)
        assert (single.touches, single.t_lower, single.t_upper) == (
            one.touches[i], one.t_lower[i], one.t_upper[i])
    assert one.pose_a.shape == (30, 4, 4) and one.normal.shape == (30, 3)
    assert one[-1].t_upper == one.t_upper[-1]


def test_bad_input_names_the_argument():
    cube = sc.Box([0.5] * 3)
    scaled = np.eye(4) * 1.01
    scaled[3, 3] = 1
    with pytest.raises(ValueError, match="pose_a end"):
        sc.time_of_impact(cube, cube, pose_a=(np.eye(4), scaled))
    nan = np.eye(4)
    nan[0, 3] = np.nan
    with pytest.raises(ValueError, match="pose_b start"):
        sc.time_of_impact(cube, cube, pose_b=(nan, np.eye(4)))
    with pytest.raises(ValueError, match="time_tolerance"):
        sc.time_of_impact(cube, cube, time_tolerance=0)
    # A fraction of the motion: a bracket is never wider than 1, so more is a mistaken unit.
    for beyond in (1 + 1e-12, 2, 1e300):
        for call in (sc.time_of_impact, sc.time_of_impact_many):
            with pytest.raises(ValueError, match="time_tolerance must be a positive fraction of "
                               "the motion's duration, at most 1"):
                call(cube, cube, time_tolerance=beyond)
    assert sc.time_of_impact(cube, cube, time_tolerance=1).certified
    with pytest.raises(ValueError, match="tolerance"):
        sc.time_of_impact(cube, cube, tolerance=0)
    with pytest.raises(ValueError, match="'dual'"):
        sc.time_of_impact(cube, cube, method="ipso")
    with pytest.raises(ValueError, match=r"max_iterations must be at most 2\*\*31 - 1"):
        sc.time_of_impact(cube, cube, max_iterations=2**40)
    with pytest.raises(TypeError, match="max_iterations must be an integer, got float"):
        sc.time_of_impact_many(cube, cube, max_iterations=1.5)
    with pytest.raises(TypeError, match="time_tolerance must be a real number, got str"):
        sc.time_of_impact(cube, cube, time_tolerance="1e-6")
    # fcl answers curved shapes too (as FCL's own primitives), so every method with signed
    # distances takes every shape.
    rise = (np.eye(4), np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]))
    above = np.eye(4)
    above[2, 3] = 3.0
    answers = [sc.time_of_impact(sc.Cylinder(1, 1), cube, pose_a=(above, above), pose_b=rise,
                                 method=method) for method in ("fcl", "dual")]
    assert all(a.touches and a.certified for a in answers)
    assert abs(answers[0].t_upper - answers[1].t_upper) <= 1e-5
    # The cube's top (0.5 up) meets the cylinder's base (2 up) at t = 1.5 / 5.
    assert all(a.t_lower <= 0.3 + 1e-9 and a.t_upper >= 0.3 - 1e-5 for a in answers)
    with pytest.raises(ValueError, match="poses_a"):
        sc.time_of_impact_many(cube, cube, poses_a=np.eye(4))


def test_motions_take_every_pose_form():
    cube = sc.Box([0.5] * 3)
    start, end = transform(np.eye(3), [-5, 0, 0]), transform(np.eye(3), [5, 0, 0])
    expected = sc.time_of_impact(cube, cube, pose_a=(start, end))
    forms = [
        (start[:3], end[:3]),
        ((np.eye(3), [-5, 0, 0]), (np.eye(3), [5, 0, 0])),
        ((Rotation.identity(), [-5, 0, 0]), (Rotation.identity(), [5, 0, 0])),
        # Stacked as NumPy users stack them: the (start, end) pair as one array.
        np.stack([start, end]),
        np.stack([start[:3], end[:3]]),
    ]
    for form in forms:
        for a in (cube, sc.CompoundBody([cube, sc.Box([0.1] * 3)])):
            r = sc.time_of_impact(a, cube, pose_a=form)
            assert (r.touches, r.t_lower, r.t_upper) == (expected.touches, expected.t_lower,
                                                        expected.t_upper)
    r = sc.time_of_impact(cube, cube, pose_b=np.stack([end, start]))
    listed = sc.time_of_impact(cube, cube, pose_b=[end, start])
    assert r.touches and (r.t_lower, r.t_upper) == (listed.t_lower, listed.t_upper)
    # A single pose keeps the body there; two Rotations turn it about its origin.
    assert not sc.time_of_impact(cube, cube, pose_a=(np.eye(3), [3, 0, 0])).touches
    half_turn = (Rotation.identity(), Rotation.from_euler("z", 90, degrees=True))
    bar = sc.Box([2, 0.1, 0.1])
    r = sc.time_of_impact(bar, cube, pose_a=half_turn, pose_b=(np.eye(3), [0, 1.5, 0]))
    assert r.touches and r.certified


def test_a_rotation_object_and_its_translation_are_one_still_pose():
    """A SciPy Rotation has a length and items, so Python counts it as a sequence: paired with a
    translation it is still one pose (the body stays there), not a start and an end."""
    cube, ball = sc.Box([0.5] * 3), sc.Sphere(0.5)
    turn = Rotation.from_euler("z", 30, degrees=True)
    for rotation in (Rotation.identity(), turn):
        r = sc.time_of_impact(cube, ball, pose_b=(rotation, [3, 0, 0]))
        expected = sc.time_of_impact(cube, ball, pose_b=(rotation.as_matrix(), [3, 0, 0]))
        assert not r.touches and r.certified
        assert (r.t_lower, r.t_upper) == (expected.t_lower, expected.t_upper)


def test_a_batch_of_no_rows_has_no_answers():
    cube = sc.Box([0.5] * 3)
    none = np.zeros((0, 4, 4))
    for batch in (sc.time_of_impact_many([], []),
                  sc.time_of_impact_many(cube, cube, poses_a=(none, none)),
                  sc.time_of_impact_many([], cube, poses_b=(none, none))):
        assert len(batch) == 0 and batch.touches.shape == (0,) and batch.pose_a.shape == (0, 4, 4)
    with pytest.raises(ValueError, match="^As has 0 entries where Bs has 2; give one per row"):
        sc.time_of_impact_many([], [cube, cube])


def test_rows_of_another_length_name_the_argument_that_has_them():
    """The rows are the count most arguments share: the message names the odd one out, by its
    Python name (the core calls poses_a motions_a, and took the longest for the rows)."""
    cube = sc.Box([0.5] * 3)
    starts = np.tile(np.eye(4), (3, 1, 1))
    ends = starts.copy()
    ends[:, 0, 3] = 2
    with pytest.raises(ValueError, match="^poses_a has 2 entries where As and Bs have 3"):
        sc.time_of_impact_many([cube] * 3, [cube] * 3, poses_a=(starts[:2], ends[:2]))
    with pytest.raises(ValueError, match="^As has 5 entries where Bs and poses_a have 3"):
        sc.time_of_impact_many([cube] * 5, [cube] * 3, poses_a=(starts, ends))
    with pytest.raises(ValueError, match="^poses_b has 2 entries where Bs and poses_a have 3"):
        sc.time_of_impact_many(cube, [cube] * 3, poses_a=(starts, ends),
                               poses_b=(starts[:2], ends[:2]))


@pytest.mark.parametrize("offset", [1e6, 1e12])
def test_answers_do_not_depend_on_where_the_motion_happens(offset):
    """Translations are taken relative to A's start, so their rounding is relative to the
    motion's extent, not to its distance from the origin."""
    cube, plate = sc.Box([0.5] * 3), sc.Box([5e-4, 5, 5])

    def answer(shift):
        start = transform(np.eye(3), [-10 + shift, shift, 0])
        end = transform(np.eye(3), [10 + shift, shift, 0])
        return sc.time_of_impact(cube, plate, pose_a=(start, end),
                                 pose_b=transform(np.eye(3), [shift, shift, 0]))

    here, there = answer(0.0), answer(offset)
    assert there.certified and there.touches
    assert (there.t_lower, there.t_upper, there.iterations) == (here.t_lower, here.t_upper,
                                                                here.iterations)


def test_batches_take_compound_bodies_and_point_stacks():
    cube = sc.Box([0.5] * 3)
    pair = sc.CompoundBody([cube, sc.ConvexPolyhedron(cube.vertices + [3, 0, 0])])
    starts, ends = np.tile(np.eye(4), (3, 1, 1)), np.tile(np.eye(4), (3, 1, 1))
    starts[:, 0, 3], ends[:, 0, 3] = 8, [1.5, 5, 4.2]
    r = sc.time_of_impact_many(sc.Sphere(0.5), pair, poses_a=(starts, ends), threads=2)
    # Only the first reaches the second cube's face (x = 3.5): its surface stops at 3.7 and 4.5
    # in the others.
    assert r.touches.tolist() == [True, False, False] and r.certified.all()
    assert r.t_upper[0] == pytest.approx(4 / 6.5, abs=1e-6)
    points = np.random.default_rng(0).normal(size=(4, 8, 3))
    with pytest.raises(ValueError, match="Bs has 3 entries"):
        sc.time_of_impact_many(points, list(points[:3]))
    assert sc.time_of_impact_many(points, points).touches.all()


def test_a_batch_row_answers_as_its_single_call_whatever_the_other_rows_hold():
    # A batch with a compound body in any row wraps every body as a compound body of one part;
    # a convex pair's row must still answer as the pair does alone (its separating directions
    # bound the motion, a compound body's do not), not depend on its neighbours.
    rng = np.random.default_rng(3)
    a, b = (sc.ConvexPolyhedron(rng.normal(size=(12, 3)) * 0.5) for _ in range(2))
    pair = sc.CompoundBody([sc.Box([0.3] * 3), sc.Sphere(0.2)], poses=np.stack([
        transform(np.eye(3), [-0.4, 0, 0]), transform(np.eye(3), [0.4, 0, 0])]))
    starts = np.stack([random_pose(rng, 3) for _ in range(8)])
    ends = np.stack([random_pose(rng, 3) for _ in range(8)])
    for motion in ("linear", "screw"):
        mixed = sc.time_of_impact_many([a] * 7 + [a], [b] * 7 + [pair], poses_a=(starts, ends),
                                       motion=motion)
        for i in range(7):
            single = sc.time_of_impact(a, b, pose_a=(starts[i], ends[i]), motion=motion)
            assert toi_fields(mixed[i]) == toi_fields(single), (motion, i)
        alone = sc.time_of_impact(a, pair, pose_a=(starts[7], ends[7]), motion=motion)
        assert toi_fields(mixed[7]) == toi_fields(alone)


def toi_fields(result):
    # repr: a free motion's distance is NaN, which equals nothing.
    return (result.touches, result.t_lower, result.t_upper, repr(result.distance), result.certified,
            result.iterations, result.status, repr(result), result.point_a.tolist(),
            result.point_b.tolist(), result.normal.tolist(), result.pose_a.tolist(),
            result.pose_b.tolist())


def toi_outcome(function, *arguments, **keywords):
    """What a call gives: ("answer", its fields) or (the error's type, its message)."""
    try:
        return "answer", toi_fields(function(*arguments, **keywords))
    except Exception as error:  # noqa: BLE001 - the comparison is the test
        return type(error), str(error)


def test_the_cpp_and_python_paths_of_time_of_impact_agree():
    """time_of_impact answers calls between two ConvexPolyhedron in C++ (_core.motion_function)
    and hands every other call to its Python definition: both give the same answers and errors."""
    from swarmcollide import queries

    python = queries.PYTHON_PATHS["time_of_impact"]
    assert sc.time_of_impact is not python and sc.time_of_impact.__doc__ == python.__doc__
    assert [(p.name, p.kind, p.default) for p in
            inspect.signature(sc.time_of_impact).parameters.values()] == [
        (p.name, p.kind, p.default) for p in inspect.signature(python).parameters.values()]
    cube = sc.ConvexPolyhedron(np.array([[x, y, z] for x in (0, 1) for y in (0, 1)
                                         for z in (0, 1)], dtype=float))
    start, end = transform(np.eye(3), [-5, 0, 0]), transform(np.eye(3), [5, 0.5, 0])
    turned = transform(Rotation.from_euler("z", 40, degrees=True).as_matrix(), [4, 0, 0])
    nan = np.eye(4)
    nan[0, 3] = np.nan
    calls = [
        ((cube, cube), {}),
        ((cube, cube), {"pose_a": (start, end)}),
        ((cube, cube), {"pose_a": (start, turned), "pose_b": transform(np.eye(3), [1, 2, 0])}),
        ((cube, cube), {"pose_a": (start, turned), "motion": "screw", "method": "dual"}),
        ((cube, cube), {"pose_a": (start, end), "tolerance": 1e-6, "time_tolerance": 1e-3}),
        ((cube, cube), {"pose_a": (start, end), "max_iterations": 1}),
        ((cube, cube), {"pose_a": (start[:3], end[:3]), "method": "fcl"}),
        ((cube, cube), {"pose_b": (np.eye(3), [3, 0, 0])}),
        ((cube, sc.Box([0.5] * 3)), {"pose_a": (start, end)}),
        ((sc.Cylinder(0.5, 1.0), sc.Sphere(0.5)), {"pose_a": (start, turned)}),
        ((cube, cube), {"pose_a": (start, nan)}),
        ((cube, cube), {"pose_a": (start, end), "time_tolerance": 0}),
        ((cube, cube), {"method": "ipso"}),
        ((cube, cube), {"motion": "spiral"}),
        ((cube, cube), {"max_iterations": 1.5}),
        ((cube, cube), {"unknown": 1}),
        ((cube,), {}),
        ((cube, "cube"), {}),
    ]
    for arguments, keywords in calls:
        fast = toi_outcome(sc.time_of_impact, *arguments, **keywords)
        slow = toi_outcome(python, *arguments, **keywords)
        assert fast == slow, (keywords, fast, slow)
