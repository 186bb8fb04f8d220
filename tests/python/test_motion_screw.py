"""Screw motions (``motion="screw"``): G(t) = G0 exp(t xi), xi = log(G0^-1 G1), against a dense
oracle that follows the same path through SciPy's matrix exponential and logarithm."""

import numpy as np
import pytest
from scipy.linalg import expm, logm
from scipy.spatial.transform import Rotation

import swarmcollide as sc
from test_motion import check_against_oracle, motion_poses, random_pose, transform


def screw_poses(start, end, times):
    """The screw motion's poses at ``times``, ``start @ expm(t xi)`` for the twist xi =
    ``logm(start^-1 end)`` (the principal logarithm is the shorter turn, as the documentation
    defines it), by the exponential's closed form (Murray, Li and Sastry, (2.36)): SciPy's
    ``expm`` takes 15 ms a pose here. ``test_the_oracle_is_the_matrix_exponential`` checks it."""
    twist = np.real(logm(np.linalg.solve(start, end)))
    w = np.array([twist[2, 1], twist[0, 2], twist[1, 0]])
    v = twist[:3, 3]
    times = np.asarray(times, dtype=float)
    poses = np.tile(np.eye(4), (len(times), 1, 1))
    turns = Rotation.from_rotvec(np.outer(times, w)).as_matrix()
    angle = np.linalg.norm(w)
    if angle == 0:
        moved = np.outer(times, v)
    else:
        # exp([t w, t v]) translates by (I - R) (w x v) / |w|^2 + w w^T v t / |w|^2.
        across = np.cross(w, v) / angle**2
        moved = across - turns @ across + np.outer(times, w * (w @ v) / angle**2)
    poses[:, :3, :3] = start[:3, :3] @ turns
    poses[:, :3, 3] = start[:3, 3] + moved @ start[:3, :3].T
    return poses


def test_the_oracle_is_the_matrix_exponential():
    rng = np.random.default_rng(0)
    for _ in range(5):
        start, end = random_pose(rng, 3), random_pose(rng, 3)
        twist = np.real(logm(np.linalg.solve(start, end)))
        poses = screw_poses(start, end, [0.0, 0.3, 1.0])
        for t, pose in zip([0.0, 0.3, 1.0], poses):
            np.testing.assert_allclose(pose, start @ expm(t * twist), atol=1e-12)
        np.testing.assert_allclose(poses[-1], end, atol=1e-12)


@pytest.mark.parametrize("seed", range(3))
def test_random_screw_motions_agree_with_dense_sampling(seed):
    rng = np.random.default_rng(100 + seed)
    touching = 0
    for _ in range(20):
        a = sc.ConvexPolyhedron(rng.normal(size=(8, 3)))
        b = sc.ConvexPolyhedron(rng.normal(size=(8, 3)) * rng.uniform(0.3, 1.5))
        motion_a = (random_pose(rng, 4), random_pose(rng, 4))
        motion_b = (random_pose(rng, 1), random_pose(rng, 1))
        r = sc.time_of_impact(a, b, pose_a=motion_a, pose_b=motion_b, motion="screw")
        touching += check_against_oracle(a, b, motion_a, motion_b, r, path=screw_poses)
    assert 3 <= touching <= 17


@pytest.mark.parametrize(
    "body",
    [sc.Sphere(0.6), sc.Capsule(0.3, 0.5), sc.Box([0.4, 0.3, 0.5], radius=0.05), sc.Cone(0.5, 0.6)],
    ids=lambda body: type(body).__name__,
)
def test_curved_shapes_on_screw_motions(body):
    rng = np.random.default_rng(7)
    other = sc.Box([0.3, 0.6, 0.2])
    for _ in range(8):
        motion_a = (random_pose(rng, 3), random_pose(rng, 3))
        motion_b = (random_pose(rng, 0.5), random_pose(rng, 0.5))
        r = sc.time_of_impact(body, other, pose_a=motion_a, pose_b=motion_b, motion="screw")
        check_against_oracle(body, other, motion_a, motion_b, r, path=screw_poses)


def test_screw_poses_follow_the_documented_path():
    rng = np.random.default_rng(3)
    cube = sc.Box([0.1] * 3)
    far = transform(np.eye(3), [100, 0, 0])
    for _ in range(10):
        start, end = random_pose(rng, 3), random_pose(rng, 3)
        # Free: the poses returned are the end's, reached along the screw.
        r = sc.time_of_impact(cube, cube, pose_a=(start, end), pose_b=far, motion="screw")
        assert not r.touches
        np.testing.assert_allclose(r.pose_a, end, atol=1e-12)
    # In contact: the pose at t_upper is the screw's there, not the linear motion's.
    start = np.eye(4)
    end = transform(Rotation.from_euler("z", 0.9 * np.pi).as_matrix(), [2, 0, 0])
    wall = transform(np.eye(3), [1, -0.9, 0])
    r = sc.time_of_impact(cube, sc.Box([3, 0.1, 3]), pose_a=(start, end), pose_b=wall,
                          motion="screw")
    assert r.touches and r.certified
    np.testing.assert_allclose(r.pose_a, screw_poses(start, end, [r.t_upper])[0], atol=1e-12)
    assert np.abs(r.pose_a - motion_poses(start, end, [r.t_upper])[0]).max() > 0.1


def test_linear_is_the_default_and_differs_from_the_screw():
    """A half turn (0.9 pi) about z while moving 2 along x: the linear motion's origin goes
    straight through (1, 0, 0); the screw's swings round an axis through (1, 0.16, 0), passing
    0.85 below it."""
    ball = sc.Sphere(0.2)
    end = transform(Rotation.from_euler("z", 0.9 * np.pi).as_matrix(), [2, 0, 0])
    post = transform(np.eye(3), [1, 0, 0])
    default = sc.time_of_impact(ball, ball, pose_a=(np.eye(4), end), pose_b=post)
    linear = sc.time_of_impact(ball, ball, pose_a=(np.eye(4), end), pose_b=post, motion="linear")
    screw = sc.time_of_impact(ball, ball, pose_a=(np.eye(4), end), pose_b=post, motion="screw")
    assert default.touches and default.certified
    assert (default.t_lower, default.t_upper) == (linear.t_lower, linear.t_upper)
    assert not screw.touches and screw.certified
    # Batches take the option alike.
    many = sc.time_of_impact_many(ball, ball, poses_a=(np.eye(4), end), poses_b=(post, post),
                                  motion="screw")
    assert many.touches.tolist() == [False]


def test_a_screw_about_its_own_axis_along_a_thin_rod():
    """A nut screwing 5 up z beside a rod parallel to z: its corners swing within 0.24 of the
    rod and never touch it."""
    nut = sc.Box([0.5, 0.5, 0.1])
    rod = sc.Box([0.05, 0.05, 10])
    end = transform(Rotation.from_euler("z", 0.8 * np.pi).as_matrix(), [0, 0, 5])
    r = sc.time_of_impact(nut, rod, pose_a=(np.eye(4), end),
                          pose_b=transform(np.eye(3), [1.0, 0, 0]), motion="screw")
    check_against_oracle(nut, rod, (np.eye(4), end),
                         (transform(np.eye(3), [1.0, 0, 0]),) * 2, r, path=screw_poses)
    assert not r.touches


def test_bad_motion_names():
    cube = sc.Box([0.5] * 3)
    with pytest.raises(ValueError, match="'linear' or 'screw'"):
        sc.time_of_impact(cube, cube, motion="helix")
    with pytest.raises(TypeError, match="motion must be a string"):
        sc.time_of_impact(cube, cube, motion=1)


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e-170, 1e-150, 1e150, 1e250])
def test_a_screw_brackets_the_same_contact_at_every_scale(scale):
    """A box screwing past another: the screw's translation across its axis is a length, whose
    squares vanished below 1e-162, so the slide's growth was left out of the motion's bound and
    a box of 1e-170 was certified apart until 0.3123, past its contact at 0.2933 (signed distance
    -0.04 of its size at 0.30). Both brackets are proven, so they share the true first contact;
    the screw poses of the scaled motion are the unit one's scaled."""

    def bracket(s):
        start = transform(np.eye(3), [-3 * s, -1.0 * s, 0])
        turn = Rotation.from_euler("xyz", [-151, -158, 94], degrees=True).as_matrix()
        a, b = sc.Box(np.array([0.8, 0.6, 0.2]) * s), sc.Box([0.5 * s] * 3)
        r = sc.time_of_impact(a, b, pose_a=(start, transform(turn, [3 * s, 0, 0])), motion="screw")
        assert r.touches and r.certified
        return r.t_lower, r.t_upper

    lower, upper = bracket(1.0)
    scaled_lower, scaled_upper = bracket(scale)
    assert scaled_lower <= upper and lower <= scaled_upper
