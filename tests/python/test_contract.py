"""The contract every method keeps, written once and run against each of them.

Every answer brackets the exact distance (``lower_bound <= exact <= distance``) with witness points
built from its weights, and a certified verdict is right. The exact methods also agree with the
tests' own exact reference to 1e-9 of the bodies' size.
"""

import numpy as np
import pytest
from oracle import exact_distance, random_pair

import swarmcollide as sc

DISTANCE_METHODS = ["ipso", "pso", "penalty", "fcl", "fcl-indep", "dual"]
# "dual" is certified to 1e-9 of the bodies' size, so it is held to the exact methods' standard.
EXACT = {"fcl", "fcl-indep", "dual"}
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
TETRA = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)


def size_of(a, b) -> float:
    points = np.vstack([a, b])
    return float(np.ptp(points, axis=0).max())


def check_contract(method, a, b, exact, result):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = size_of(a, b)
    rounding = 1e-12 * max(scale, np.abs(np.vstack([a, b])).max())
    assert result.method == method
    assert np.all(result.weights_a >= 0) and np.all(result.weights_b >= 0)
    assert result.weights_a.sum() == pytest.approx(1, abs=1e-12)
    assert result.weights_b.sum() == pytest.approx(1, abs=1e-12)
    np.testing.assert_allclose(result.point_a, a.T @ result.weights_a, rtol=0, atol=rounding * 10)
    np.testing.assert_allclose(result.point_b, b.T @ result.weights_b, rtol=0, atol=rounding * 10)
    assert result.lower_bound <= exact + rounding
    assert exact <= result.distance + rounding
    if method in EXACT:
        assert abs(result.distance - exact) <= 1e-9 * scale
    tolerance = 1e-9 if method in EXACT else 1e-6
    if method == "dual":  # relative: 1e-9 of the larger bounding-box diagonal
        tolerance = 1e-9 * max(np.linalg.norm(np.ptp(x, axis=0)) for x in (a, b))
    if result.certified and abs(exact - tolerance) > rounding:
        assert result.colliding == (exact < tolerance)


@pytest.mark.parametrize("method", DISTANCE_METHODS)
@pytest.mark.parametrize("case", ["touching", "separate"])
def test_paper_pairs(method, case, tetra_a, touching_b, separate_b):
    b = touching_b if case == "touching" else separate_b
    exact = 0.0 if case == "touching" else 1.0
    r = sc.distance(tetra_a, b, method=method, seed=0)
    check_contract(method, tetra_a, b, exact, r)
    assert r.certified
    assert r.distance == pytest.approx(exact, abs=1e-4)
    assert sc.collide(tetra_a, b, method=method) == (case == "touching")


def test_libccd_answers_collisions_not_distances(tetra_a, touching_b, separate_b):
    assert sc.collide(tetra_a, touching_b, method="libccd")
    assert not sc.collide(tetra_a, separate_b, method="libccd")
    with pytest.raises(ValueError, match="libccd.*no distance.*'fcl'"):
        sc.distance(tetra_a, separate_b, method="libccd")


@pytest.mark.parametrize("method", DISTANCE_METHODS)
def test_random_pairs_against_the_exact_reference(method):
    rng = np.random.default_rng(99)
    for trial in range(15):
        a, b = random_pair(rng, points=6, spread=2.5)
        r = sc.distance(a, b, method=method, seed=trial)
        check_contract(method, a, b, exact_distance(a, b), r)


@pytest.mark.parametrize("method", DISTANCE_METHODS)
def test_symmetry_and_rigid_motions(method):
    rng = np.random.default_rng(5)
    a, b = random_pair(rng, points=6, spread=3)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    shift = rng.normal(size=3) * 10
    forward = sc.distance(a, b, method=method)
    backward = sc.distance(b, a, method=method)
    moved = sc.distance(a @ q.T + shift, b @ q.T + shift, method=method)
    # Each answer brackets the same exact value, so the brackets overlap.
    for one, other in [(forward, backward), (forward, moved), (backward, moved)]:
        assert one.lower_bound <= other.distance + 1e-9
        assert other.lower_bound <= one.distance + 1e-9
    if method in EXACT:
        assert backward.distance == pytest.approx(forward.distance, abs=1e-9)
        assert moved.distance == pytest.approx(forward.distance, abs=1e-9)


def hard_cases():
    rng = np.random.default_rng(3)
    big = np.array([[x, y, z] for x in (-1e6, 1e6) for y in (-1e6, 1e6) for z in (0, 1e6)])
    return {
        "vertex-vertex touching": (TETRA, -TETRA),
        "edge-edge touching": (CUBE, CUBE @ np.diag([1, 1, 1]) + [1, 1, 0]),
        "face-face touching": (CUBE, CUBE + [1, 0.3, 0.2]),
        "faces 1e-16 apart": (CUBE, CUBE + [1 + 1e-16, 0, 0]),
        "faces 1e-9 apart": (CUBE, CUBE + [1 + 1e-9, 0, 0]),
        "stacked cubes": (CUBE, CUBE + [0, 0, 1]),
        "stacked cubes 1e-3 apart": (CUBE, CUBE + [0.5, 0.5, 1.001]),
        "size ratio 1e6": (big, TETRA * 1e-0 + [0, 0, 1e6 + 0.5]),
        "offset 1e6": (CUBE + 1e6, CUBE + 1e6 + [2, 0.5, 0.5]),
        "flat square and tetra": (CUBE[[0, 2, 4, 6]], TETRA + [0.2, 0.2, 0.3]),
        "segment and point": (np.array([[-1.0, 0, 0], [1.0, 0, 0]]), np.array([[0.3, 2.0, 0]])),
        "crossing segments": (
            np.array([[-1.0, 0, 0], [1.0, 0, 0]]),
            np.array([[0, -1.0, 0], [0, 1.0, 0]]),
        ),
        "duplicate vertices": (np.vstack([TETRA, TETRA, TETRA[:2]]), TETRA + [2, 0, 0]),
        "random overlap": (rng.normal(size=(8, 3)), rng.normal(size=(8, 3)) * 0.5),
    }


HARD = hard_cases()


@pytest.mark.parametrize("method", DISTANCE_METHODS)
@pytest.mark.parametrize("name", list(HARD))
def test_hard_cases(method, name):
    a, b = HARD[name]
    r = sc.distance(a, b, method=method, seed=0)
    check_contract(method, a, b, exact_distance(a, b), r)


@pytest.mark.parametrize("method", ["ipso", "pso", "penalty", "fcl", "fcl-indep", "libccd"])
@pytest.mark.parametrize("name", list(HARD))
def test_collide_never_contradicts_the_exact_answer(method, name):
    a, b = HARD[name]
    exact = exact_distance(a, b)
    verdict = sc.collide(a, b, method=method, seed=0)
    tolerance = 1e-9 if method in EXACT | {"libccd"} else 1e-6
    gap = 1e-12 * max(1.0, np.abs(np.vstack([a, b])).max())
    if exact > tolerance + gap:
        assert not verdict
    elif exact <= tolerance - gap:
        assert verdict


def test_raw_swarm_verdicts_are_available(tetra_a):
    b = [[1, -1e-7, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]]
    raw = sc.collision(tetra_a, b, max_iterations=0, escalate=False)
    assert raw.method == "ipso" and raw.escalated_from == "" and not raw.certified
    assert not sc.collide(tetra_a, b, max_iterations=0, escalate=False)
    assert sc.collide(tetra_a, b, max_iterations=0)


@pytest.mark.parametrize("method", ["fcl", "fcl-indep", "libccd"])
def test_signed_distance_of_overlapping_cubes(method):
    r = sc.signed_distance(CUBE, CUBE + [0.8, 0.1, 0.05], method=method)
    assert r.distance == pytest.approx(-0.2, abs=1e-9)
    np.testing.assert_allclose(r.direction, [1, 0, 0], atol=1e-9)
    np.testing.assert_allclose(r.point_b - r.point_a, r.distance * r.direction, atol=1e-9)
    assert r.lower_bound <= r.distance + 1e-12
    assert r.colliding


@pytest.mark.parametrize("method", ["fcl", "fcl-indep", "libccd"])
def test_signed_distance_of_separate_bodies_is_the_distance(method, tetra_a, separate_b):
    r = sc.signed_distance(tetra_a, separate_b, method=method)
    assert r.distance == pytest.approx(1, abs=1e-9)
    assert not r.colliding


def test_signed_distance_methods_agree_on_random_overlaps():
    rng = np.random.default_rng(8)
    for _ in range(10):
        a = rng.normal(size=(10, 3))
        b = rng.normal(size=(10, 3)) * 0.7 + rng.normal(size=3) * 0.3
        depths = [sc.signed_distance(a, b, method=m).distance for m in ("fcl", "fcl-indep", "libccd")]
        assert depths[0] < 0
        np.testing.assert_allclose(depths, depths[0], rtol=1e-6)


@pytest.mark.parametrize("method", ["ipso", "pso", "penalty"])
def test_signed_distance_needs_an_exact_method(method):
    with pytest.raises(ValueError, match="does not measure penetration"):
        sc.signed_distance(CUBE, CUBE, method=method)


@pytest.mark.parametrize(
    ("method", "parameters", "message"),
    [
        ("fcl", {"swarm_size": 10}, "swarm_size does not apply to method='fcl'"),
        ("penalty", {"growth_factor": 1.0}, "growth_factor"),
        ("penalty", {"outer_iterations": 0}, "outer_iterations"),
        ("fcl", {"distance_tolerance": -1.0}, "distance_tolerance"),
        ("libccd", {"penetration": "gjk"}, "penetration must be one of 'epa', 'mpr'"),
        ("fcl", {"penetration": "epa"}, "penetration does not apply"),
    ],
)
def test_bad_method_parameters(method, parameters, message):
    with pytest.raises(ValueError, match=message):
        sc.collide(CUBE, CUBE + 3, method=method, **parameters)
