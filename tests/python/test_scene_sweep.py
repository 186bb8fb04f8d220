"""Scene.sweep: every pair's first contact during the bodies' motions, against time_of_impact
on every pair (the oracle), with the scene's filters and its bad-input checks."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import swarmcollide as sc


def transform(rotation, translation):
    m = np.eye(4)
    m[:3, :3] = rotation
    m[:3, 3] = translation
    return m


def random_pose(rng, spread):
    return transform(Rotation.random(random_state=rng).as_matrix(), rng.uniform(-spread, spread, 3))


def random_bodies(rng):
    cube = sc.Box([0.4, 0.3, 0.5])
    bodies = [sc.ConvexPolyhedron(rng.normal(size=(8, 3)) * 0.5) for _ in range(8)]
    bodies += [sc.Sphere(0.4), sc.Capsule(0.2, 0.5), sc.Box([0.3, 0.2, 0.6], radius=0.05)]
    bodies.append(sc.CompoundBody([cube, sc.ConvexPolyhedron(cube.vertices + [1.2, 0, 0])]))
    return bodies


def add_one(scene, body, pose=None):
    """The id of `body`, added at `pose`."""
    return int(scene.add(body, poses=pose)[0])


def build_scene(bodies, poses, **options):
    scene = sc.Scene(**options)
    for body, pose in zip(bodies, poses):
        scene.add(body, poses=pose)
    return scene


def oracle(bodies, starts, ends, moving, **options):
    """time_of_impact on every pair with a moving body: {(i, j): result} for those that touch."""
    found = {}
    for i in range(len(bodies)):
        for j in range(i + 1, len(bodies)):
            if i not in moving and j not in moving:
                continue
            r = sc.time_of_impact(bodies[i], bodies[j], pose_a=(starts[i], ends[i]),
                                  pose_b=(starts[j], ends[j]), **options)
            if r.touches:
                found[(i, j)] = r
    return found


@pytest.mark.parametrize("motion", ["linear", "screw"])
@pytest.mark.parametrize("seed", range(2))
def test_sweep_finds_what_time_of_impact_finds_on_every_pair(seed, motion):
    rng = np.random.default_rng(seed)
    bodies = random_bodies(rng)
    starts = [random_pose(rng, 2.5) for _ in bodies]
    moving = sorted(rng.choice(len(bodies), size=7, replace=False).tolist())
    ends = list(starts)
    for i in moving:
        ends[i] = random_pose(rng, 2.5)
    expected = oracle(bodies, starts, ends, set(moving), method="exact", motion=motion)
    assert 3 <= len(expected) < 40
    answers = []
    for threads in (1, 2):
        scene = build_scene(bodies, starts, method="exact", threads=threads)
        r = scene.sweep(moving, np.stack([ends[i] for i in moving]), motion=motion)
        answers.append(r)
        assert [tuple(p) for p in r.pairs.tolist()] == sorted(expected)
        for k, (i, j) in enumerate(r.pairs.tolist()):
            e = expected[(i, j)]
            assert (r.t_lower[k], r.t_upper[k], r.certified[k], r.iterations[k]) == (
                e.t_lower, e.t_upper, e.certified, e.iterations)
            np.testing.assert_array_equal(r.pose_a[k], e.pose_a)
            np.testing.assert_array_equal(r.pose_b[k], e.pose_b)
            np.testing.assert_array_equal(r.normal[k], e.normal)
        # The bodies are left at their end poses.
        for i in range(len(bodies)):
            np.testing.assert_array_equal(scene.pose(i), ends[i])
    for name in ("pairs", "t_lower", "t_upper", "point_a", "point_b", "normal", "distance"):
        np.testing.assert_array_equal(getattr(answers[0], name), getattr(answers[1], name))


def test_broadphases_give_the_same_answers():
    rng = np.random.default_rng(4)
    bodies = random_bodies(rng)
    starts = [random_pose(rng, 2.5) for _ in bodies]
    ends = [random_pose(rng, 2.5) for _ in bodies]
    answers = []
    for broadphase in sc.BROADPHASES:
        scene = build_scene(bodies, starts, method="exact", broadphase=broadphase)
        answers.append(scene.sweep(np.arange(len(bodies)), np.stack(ends)))
    assert len(answers[0]) > 3
    for r in answers[1:]:
        np.testing.assert_array_equal(r.pairs, answers[0].pairs)
        np.testing.assert_array_equal(r.t_upper, answers[0].t_upper)


def test_a_cube_passes_through_a_thin_plate_in_one_sweep():
    scene = sc.Scene()
    cube = add_one(scene, sc.Box([0.5] * 3), transform(np.eye(3), [-10, 0, 0]))
    plate = add_one(scene, sc.Box([5e-4, 5, 5]))
    far = add_one(scene, sc.Box([0.5] * 3), transform(np.eye(3), [0, 20, 0]))
    end = transform(np.eye(3), [10, 0, 0])
    r = scene.sweep(cube, end)
    assert r.pairs.tolist() == [[cube, plate]] and r.certified.all()
    first = 9.4995 / 20
    assert r.t_lower[0] <= first * (1 + 1e-12) and r.t_upper[0] >= first - 1e-6
    assert r.normal[0].round(9).tolist() == [1.0, 0.0, 0.0]
    assert r.pose_a.shape == (1, 4, 4) and "1 pair" in repr(r)
    # Neither end collides: a discrete check misses it.
    assert len(scene.colliding_pairs()) == 0
    np.testing.assert_array_equal(scene.pose(cube), end)
    np.testing.assert_array_equal(scene.pose(far), transform(np.eye(3), [0, 20, 0]))


def test_a_long_sweep_through_a_deep_overlap_is_certified():
    """A ball of 1e-3 swept 600 units past another, 1e-4 deep at mid-motion: the poses' rounding
    over the motion exceeds the contact threshold, and only the overlap's depth proves contact
    (the sweep was left uncertified with the bracket [0.5, 1])."""
    scene = sc.Scene()
    a = add_one(scene, sc.Sphere(1e-3), transform(np.eye(3), [-300, 0, 0]))
    b = add_one(scene, sc.Sphere(1e-3), transform(np.eye(3), [0, 1.9e-3, 0]))
    swept = scene.sweep(a, transform(np.eye(3), [300, 0, 0]))
    meets = 0.5 - np.sqrt(4 - 1.9**2) * 1e-3 / 600
    assert swept.pairs.tolist() == [[a, b]] and swept.certified.tolist() == [True]
    assert swept.t_lower[0] <= meets <= swept.t_upper[0] + 1e-9 * 4e-3 / 600
    assert swept.t_upper[0] - swept.t_lower[0] <= 1e-6


def test_still_bodies_are_hit_and_stay_where_they_are():
    scene = sc.Scene()
    ball = add_one(scene, sc.Sphere(0.5), transform(np.eye(3), [-5, 0, 0]))
    still = add_one(scene, sc.Box([0.5] * 3))
    # Listed but not moving: a still body too.
    listed = add_one(scene, sc.Box([0.5] * 3), transform(np.eye(3), [5, 0.2, 0]))
    r = scene.sweep([ball, listed],
                    np.stack([transform(np.eye(3), [8, 0, 0]), scene.pose(listed)]))
    assert r.pairs.tolist() == [[ball, still], [ball, listed]]
    # The ball's surface reaches the box (x = -0.5) after 4 of 13, the other (4.5) after 9.
    assert r.t_upper == pytest.approx([4 / 13, 9 / 13], abs=1e-6)
    np.testing.assert_array_equal(scene.pose(still), np.eye(4))
    # A sweep with no motion reports the pairs in contact at the start.
    scene.set_poses(ball, transform(np.eye(3), [0.9, 0, 0]))
    r = scene.sweep(ball, scene.pose(ball))
    assert r.pairs.tolist() == [[ball, still]] and r.t_upper.tolist() == [0.0]
    assert len(scene.sweep([], None)) == 0


def test_filtered_and_excluded_pairs_are_skipped():
    def make():
        scene = sc.Scene()
        ids = [add_one(scene, sc.Sphere(0.5), transform(np.eye(3), [-5, 0, 0])),
               add_one(scene, sc.Box([0.5] * 3)),
               add_one(scene, sc.Box([0.5] * 3), transform(np.eye(3), [3, 0, 0]))]
        return scene, ids

    end = transform(np.eye(3), [8, 0, 0])
    scene, (ball, first, second) = make()
    assert scene.sweep(ball, end).pairs.tolist() == [[ball, first], [ball, second]]
    scene, (ball, first, second) = make()
    scene.exclude([ball, first])
    assert scene.sweep(ball, end).pairs.tolist() == [[ball, second]]
    scene, (ball, first, second) = make()
    scene.set_filter(ball, group=2, mask=2)
    scene.set_filter(second, group=2)
    assert scene.sweep(ball, end).pairs.tolist() == [[ball, second]]


def test_bad_input_moves_nothing_and_says_why():
    scene = sc.Scene()
    ball = add_one(scene, sc.Sphere(0.5))
    other = add_one(scene, sc.Box([0.5] * 3), transform(np.eye(3), [3, 0, 0]))
    end = transform(np.eye(3), [5, 0, 0])
    with pytest.raises(ValueError, match="no body with id 7"):
        scene.sweep([ball, 7], np.stack([end, end]))
    with pytest.raises(ValueError, match="twice"):
        scene.sweep([ball, ball], np.stack([end, end]))
    with pytest.raises(ValueError, match="poses"):
        scene.sweep([ball, other], end)
    with pytest.raises(ValueError, match="poses"):
        scene.sweep(ball, np.eye(3))
    with pytest.raises(ValueError, match="poses"):
        scene.sweep(ball, None)
    nan = end.copy()
    nan[0, 3] = np.nan
    with pytest.raises(ValueError, match="poses"):
        scene.sweep(ball, nan)
    scaled = end.copy()
    scaled[:3, :3] *= 1.01
    with pytest.raises(ValueError, match="poses"):
        scene.sweep(ball, scaled)
    with pytest.raises(ValueError, match="time_tolerance"):
        scene.sweep(ball, end, time_tolerance=0)
    with pytest.raises(ValueError, match="time_tolerance must be .* at most 1 "):
        scene.sweep(ball, end, time_tolerance=2)
    with pytest.raises(ValueError, match="'linear' or 'screw'"):
        scene.sweep(ball, end, motion="helix")
    with pytest.raises(TypeError, match="max_iterations must be an integer"):
        scene.sweep(ball, end, max_iterations=1.5)
    with pytest.raises(TypeError, match="time_tolerance must be a real number"):
        scene.sweep(ball, end, time_tolerance="small")
    with pytest.raises(TypeError, match="ids"):
        scene.sweep("ball", end)
    with pytest.raises(ValueError, match="signed distances"):
        sc.Scene(method="ipso").sweep([], None)
    np.testing.assert_array_equal(scene.pose(ball), np.eye(4))
    assert scene.sweep(ball, end).pairs.tolist() == [[ball, other]]


@pytest.mark.parametrize("motion", ["linear", "screw"])
def test_a_turning_bar_hits_a_post_outside_both_end_boxes(motion):
    """The bar's boxes at its start and end (0.9 pi about z) stop at y = 0.72; the post at y = 1.5
    is hit half-way round: a swept box from the ends alone would miss the pair."""
    scene = sc.Scene()
    bar = add_one(scene, sc.Box([2, 0.1, 0.1]))
    post = add_one(scene, sc.Box([0.05] * 3), transform(np.eye(3), [0, 1.5, 0]))
    end = transform(Rotation.from_euler("z", 0.9 * np.pi).as_matrix(), [0, 0, 0])
    r = scene.sweep(bar, end, motion=motion)
    expected = sc.time_of_impact(sc.Box([2, 0.1, 0.1]), sc.Box([0.05] * 3),
                                 pose_a=(np.eye(4), end), pose_b=scene.pose(post), motion=motion)
    assert expected.touches
    assert r.pairs.tolist() == [[bar, post]] and r.certified.all()
    assert r.t_upper[0] == pytest.approx(expected.t_upper, abs=1e-6)
