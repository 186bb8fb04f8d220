"""Issue 12's examples: no abort, no hang, a right answer or a clear error, in any unit.

Every call that could abort or spin runs in a sandboxed child (``sandbox.py``) with a time limit,
so a failure fails one test, not the run. The tests assert the behaviour the issue asks for; the
methods come from ``fuzz_api.METHODS``, the one table to update when the method names change.
"""

from __future__ import annotations

import os
from typing import Any, List

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from fuzz_api import METHODS, OPTIONS_OF, invoke
from fuzz_judge import judge_single, run_case
from minkowski_oracle import signed_distance as exact_signed_distance
from sandbox import RAISED, RETURNED, Outcome, Sandbox

import swarmcollide as sc

TIMEOUT = 10.0  # every example answers in milliseconds once fixed; libccd spun for minutes
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
HALF_OVERLAP = np.array([0.5, 0.25, 0.1])  # B = CUBE + HALF_OVERLAP overlaps CUBE by half its width

SIGNED = [m for m in METHODS["signed_distance"] if m]
DISTANCE = [m for m in METHODS["distance"] if m]
COLLIDE = [m for m in METHODS["collide"] if m]
BATCH = ["distance_many", "collide_many"]
SCALES = [1e-100, 1e-6, 1e-5, 1e-4, 3e-4, 1e-3, 1.5e-3, 1e8, 1e12, 1e77, 1e100]


@pytest.fixture(scope="module")
def sandbox():
    with Sandbox(preload=("fuzz_judge",)) as box:
        yield box


def answer(sandbox: Sandbox, query: str, a: Any, b: Any, **keywords: Any) -> Any:
    """``sc.<query>(a, b, **keywords)`` in a child, as plain data; fails on a crash, hang, error."""
    return sandbox.run(invoke, query, (a, b), keywords, timeout=TIMEOUT).unwrap()


def assert_right(query: str, a: Any, b: Any, result: Any) -> None:
    """Bounds, witnesses and (certified) verdict agree with the oracle (see fuzz_judge)."""
    problems, _ = judge_single(query, np.asarray(a, float), np.asarray(b, float), result)
    assert not problems, problems


def assert_refused(outcome: Outcome, error_type: str, match: str = "") -> None:
    assert outcome.kind == RAISED and outcome.error_type == error_type, outcome.describe()
    assert match in outcome.message, outcome.message


def random_overlaps(count: int) -> List[tuple]:
    """Pairs of random 8-point hulls, as in the issue's counts: the first 24 overlap."""
    rng = np.random.default_rng(8)
    return [
        (rng.normal(size=(8, 3)), rng.normal(size=(8, 3)) * 0.8 + rng.normal(size=3) * 0.3)
        for _ in range(count)
    ]


# ----- the process dies ------------------------------------------------------------------------


@pytest.mark.parametrize("method", SIGNED)
@pytest.mark.parametrize("s", SCALES)
def test_signed_distance_of_half_overlapping_cubes_at_any_scale(sandbox, method, s):
    # fcl aborted in its EPA at 1e-4 and certified 0 below 5.6e-5; libccd spun at 1e-5 and was
    # wrong between 3e-4 and 1.8e-3.
    a, b = CUBE * s, (CUBE + HALF_OVERLAP) * s
    r = answer(sandbox, "signed_distance", a, b, method=method)
    assert r["distance"] == pytest.approx(-0.5 * s, rel=1e-6)
    assert_right("signed_distance", a, b, r)


def test_dual_collide_with_points_at_1e300_keeps_the_heap(sandbox):
    a, b = np.full((8, 3), 1e300), CUBE + [2, 0.3, 0.1]
    assert answer(sandbox, "collide", a, b, method="dual") is False


@pytest.mark.parametrize("method", DISTANCE)
def test_distance_of_cubes_at_1e300(sandbox, method):
    a, b = CUBE * 1e300, CUBE * 1e300 + 3e300  # fcl segfaulted in polygon_hull
    r = answer(sandbox, "distance", a, b, method=method)
    assert r["distance"] == pytest.approx(2 * np.sqrt(3) * 1e300, rel=1e-6)
    assert_right("distance", a, b, r)


def distances_with_threads_that_cannot_start(pairs: int) -> np.ndarray:
    """distance_many with a thread per pair in a child whose address space has no room for them."""
    result = sc.distance_many(np.zeros((pairs, 1, 3)), np.ones((pairs, 1, 3)), method="fcl",
                              threads=pairs)  # fmt: skip
    return np.asarray(result.distance)


@pytest.mark.skipif(
    os.environ.get("SWARMCOLLIDE_SANITIZED") == "1",
    reason="under ASan the address-space limit that stops the threads also stops ASan's own "
    "mappings (its signal stack), so the child dies before the library runs; the "
    "uninstrumented suite runs this test",
)
def test_threads_that_cannot_start_give_a_clean_error(sandbox):
    # 1000 stacks of 8 MiB do not fit in 512 MiB more: std::thread's constructor throws.
    outcome = sandbox.run(
        distances_with_threads_that_cannot_start, 1000, timeout=TIMEOUT, memory_limit=512 << 20
    )
    assert outcome.kind in (RETURNED, RAISED), outcome.describe()
    if outcome.kind == RETURNED:  # falling back to the threads that did start is fine too
        np.testing.assert_allclose(outcome.value, np.sqrt(3))


@pytest.mark.parametrize("query", BATCH)
def test_threads_beyond_an_int_is_a_value_error(sandbox, query):
    stack = CUBE[None]
    outcome = sandbox.run(invoke, query, (stack, stack + 2), {"threads": 2**31}, timeout=TIMEOUT)
    assert_refused(outcome, "ValueError", "threads")


# ----- the call never returns ------------------------------------------------------------------


def test_libccd_on_a_coplanar_pair(sandbox):
    a, b = CUBE, CUBE + [0.5, 0.5, 0]  # two faces coplanar; libccd's MPR spun here
    r = answer(sandbox, "signed_distance", a, b, method="libccd")
    assert r["distance"] == pytest.approx(-0.5, rel=1e-6)
    assert_right("signed_distance", a, b, r)


def test_libccds_mpr_is_refused_by_name():
    # MPR had no iteration cap and certified depths that were not the minimum; it is gone.
    with pytest.raises(ValueError, match="penetration does not apply to method 'libccd'"):
        sc.signed_distance(CUBE, CUBE + 0.5, method="libccd", penetration="mpr")


# ----- certified answers that are wrong --------------------------------------------------------

# Pairs of random_overlaps(60) on which dual (some seeds) or libccd's MPR certified a wrong depth.
WRONG_DEPTH_PAIRS = [4, 13, 20, 26, 30, 50, 53]


@pytest.mark.parametrize("pair", WRONG_DEPTH_PAIRS)
def test_dual_signed_distance_is_right_for_every_seed(sandbox, pair):
    a, b = random_overlaps(60)[pair]
    for seed in range(10):
        r = answer(sandbox, "signed_distance", a, b, method="dual", seed=seed)
        assert_right("signed_distance", a, b, r)


@pytest.mark.parametrize("pair", WRONG_DEPTH_PAIRS)
def test_libccd_depth_is_right_when_certified(sandbox, pair):
    a, b = random_overlaps(60)[pair]
    r = answer(sandbox, "signed_distance", a, b, method="libccd")
    assert_right("signed_distance", a, b, r)


def rotated_cubes_far_from_the_origin(count: int, offset: float) -> List[tuple]:
    """Pairs of unit cubes turned at random, their points ``offset`` from the origin: faces meet
    faces, so supports tie, and heights compared in the given coordinates round at 1e-8."""
    rng = np.random.default_rng(21)
    corners = CUBE - 0.5

    def turned() -> np.ndarray:
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        return corners @ q.T + offset

    return [(turned(), turned() + rng.normal(size=3) * 1.5) for _ in range(count)]


@pytest.mark.parametrize(
    "query, method",
    [("distance", m) for m in DISTANCE] + [("signed_distance", m) for m in SIGNED],
)
def test_certified_bounds_of_unit_bodies_1e8_from_the_origin(sandbox, query, method):
    # Supports chosen by heights rounded at the coordinates' 1e8 put certified lower bounds up to
    # 6e-9 above the true distance (rotated cubes, dual, exact and fcl): the bounds are proven to
    # the pair's size, so they must hold to within a few roundoffs of it, not of the coordinates.
    for a, b in rotated_cubes_far_from_the_origin(25, 1e8):
        r = answer(sandbox, query, a, b, method=method)
        true = exact_signed_distance(a, b).signed_distance
        if query == "distance":
            true = max(true, 0.0)
        if r["certified"]:
            assert r["lower_bound"] <= true + 1e-12 and r["distance"] >= true - 1e-12, (r, true)


@pytest.mark.parametrize("x", [0.3, 0.5465540192976328, 0.12361943746177984, -0.5726255611389037])
@pytest.mark.parametrize("point_first", [False, True])
def test_dual_signed_witnesses_of_a_point_on_a_segment(sandbox, x, point_first):
    segment, point = np.array([[-1.0, 0, 0], [1.0, 0, 0]]), np.array([[x, 0.0, 0.0]])
    a, b = (point, segment) if point_first else (segment, point)
    r = answer(sandbox, "signed_distance", a, b, method="dual")
    np.testing.assert_allclose(r["point_b"] - r["point_a"], r["distance"] * r["direction"],
                               atol=1e-9)  # fmt: skip
    assert_right("signed_distance", a, b, r)


# ----- the answer depends on the unit of length ------------------------------------------------


@pytest.mark.parametrize("method", COLLIDE)
@pytest.mark.parametrize("s", SCALES)
def test_collide_of_half_overlapping_cubes_at_any_scale(sandbox, method, s):
    # fcl said False at 1e8.
    assert answer(sandbox, "collide", CUBE * s, (CUBE + HALF_OVERLAP) * s, method=method) is True


def test_default_collide_of_random_overlaps_at_1e12(sandbox):
    verdicts = [answer(sandbox, "collide", a * 1e12, b * 1e12) for a, b in random_overlaps(20)]
    assert all(verdicts)


def polyhedron_at(s: float) -> dict:
    body = sc.ConvexPolyhedron(CUBE * s)
    hull = body.hull()
    return {"dimension": hull.dimension, "vertices": len(hull.vertex_indices),
            "centroid": np.asarray(body.centroid())}  # fmt: skip


@pytest.mark.parametrize("s", [1e76, 1e77, 1e100, 1e300])
def test_hull_of_a_huge_cube(sandbox, s):
    hull = sandbox.run(polyhedron_at, s, timeout=TIMEOUT).unwrap()
    assert (hull["dimension"], hull["vertices"]) == (3, 8)
    np.testing.assert_allclose(hull["centroid"], 0.5 * s, rtol=1e-12)


@pytest.mark.parametrize("method", DISTANCE)
def test_point_1e300_from_the_origin_is_not_colliding(sandbox, method):
    a, b = [[1e300, 1e300, 1e300]], [[0.0, 0.0, 0.0]]
    r = answer(sandbox, "distance", a, b, method=method)
    assert r["distance"] == pytest.approx(np.sqrt(3) * 1e300, rel=1e-9)
    assert not r["colliding"]
    assert_right("distance", a, b, r)


def test_every_method_gives_one_verdict_for_a_gap_of_1e_9_of_the_size(sandbox):
    # At scale 1e6 a gap of 1e-3 collided for dual and not for fcl: tolerance had several meanings.
    a, b = CUBE * 1e6, CUBE * 1e6 + [1e6 + 1e-3, 0, 0]
    verdicts = {method: answer(sandbox, "collide", a, b, method=method) for method in COLLIDE}
    assert len(set(verdicts.values())) == 1, verdicts


@pytest.mark.parametrize("method", COLLIDE)
def test_micrometre_cubes_a_nanometre_apart_do_not_collide(sandbox, method):
    a, b = CUBE * 1e-6, CUBE * 1e-6 + [1e-6 + 1e-9, 0, 0]
    assert answer(sandbox, "collide", a, b, method=method) is False


# ----- a documented option gives wrong verdicts ------------------------------------------------


@pytest.mark.parametrize("method", COLLIDE)
def test_collide_with_zero_tolerance(sandbox, method):
    # fcl said False on 293 of 298 overlapping random pairs.
    verdicts = [answer(sandbox, "collide", a, b, method=method, tolerance=0.0)
                for a, b in random_overlaps(20)]  # fmt: skip
    assert all(verdicts)


@pytest.mark.parametrize("method", SIGNED)
def test_signed_distance_with_zero_tolerance(sandbox, method):
    for a, b in random_overlaps(10):
        r = answer(sandbox, "signed_distance", a, b, method=method, tolerance=0.0)
        assert r["distance"] == pytest.approx(exact_signed_distance(a, b).signed_distance, abs=1e-6)
        assert_right("signed_distance", a, b, r)


@pytest.mark.parametrize("method", sorted(OPTIONS_OF["max_iterations"]))
@pytest.mark.parametrize("iterations", [1, 2])
def test_collide_with_one_or_two_iterations(sandbox, method, iterations):
    a, b = CUBE, CUBE + HALF_OVERLAP
    assert answer(sandbox, "collide", a, b, method=method, max_iterations=iterations) is True


# ----- bad input slips through -----------------------------------------------------------------

BAD_STACKS = {
    "bool": np.ones((2, 8, 3), dtype=bool),
    "complex": np.ones((2, 8, 3), dtype=complex),
    "str": np.full((2, 8, 3), "1"),
    "datetime": np.zeros((2, 8, 3), dtype="datetime64[s]"),
}


@pytest.mark.parametrize("query", BATCH)
@pytest.mark.parametrize("dtype", list(BAD_STACKS))
def test_stacks_of_non_real_dtypes_are_type_errors(sandbox, query, dtype):
    good = np.stack([CUBE, CUBE])
    for As, Bs in [(BAD_STACKS[dtype], good), (good, BAD_STACKS[dtype])]:
        outcome = sandbox.run(invoke, query, (As, Bs), {}, timeout=TIMEOUT)
        assert_refused(outcome, "TypeError", "dtype")


@pytest.mark.parametrize("method", sorted(OPTIONS_OF["swarm_size"]))
def test_a_swarm_too_large_to_run_is_a_value_error(sandbox, method):
    outcome = sandbox.run(invoke, "distance", (CUBE, CUBE + 2),
                          {"method": method, "swarm_size": 2**31 - 1}, timeout=TIMEOUT)  # fmt: skip
    assert_refused(outcome, "ValueError", "swarm_size")


def copied_polyhedron() -> np.ndarray:
    return np.asarray(sc.ConvexPolyhedron(sc.ConvexPolyhedron(CUBE)).vertices)


def test_a_polyhedron_is_built_from_a_polyhedron(sandbox):
    np.testing.assert_array_equal(sandbox.run(copied_polyhedron, timeout=TIMEOUT).unwrap(), CUBE)


# ----- cases the fuzz census found (tests/fuzz/BEFORE.md, before.jsonl) -------------------------

CENSUS_CASES = {
    "0:267": "libccd's EPA spins: a tetrahedron in an 18-point hull at scale 1e-5",
    "0:1564": "libccd's EPA spins: two rotated boxes at scale 1e-4",
    "0:9811": "libccd's EPA spins: a nearly axis-aligned box on a box at unit scale",
    "0:6437": "FCL's EPA aborts (ComputeVisiblePatch): a 64-point sphere in a cube at scale 1e-4",
    "0:2608": "FCL's EPA aborts: a cube and a 5-point hull at scale 1e8, offset 1e12",
    "0:2302": "dual's signed distance raises for two cubes far apart at scale 1e300",
    "0:683": "fcl with max_iterations=1 calls a deep overlap apart",
    "0:585": "fcl-indep certifies 0 for an overlap of subnormal bodies",
    "47:3210": "fcl with max_iterations=1: a signed distance apart whose witnesses lie nearer (0.033) "
    "than its distance (0.136), off its normal",
    "49:8148": "fcl's distance of a deep overlap certified at 0.02: FCL's weights on a tetrahedron of "
    "other points (ties of repeated and collinear points) proved contact but left the witnesses "
    "apart",
    "49:9455": "a needle in a 256-point sphere at scale 3.5e51: witnesses off distance * direction "
    "by the tolerance of the pair's size, which is larger than its widest extent",
}


@pytest.mark.parametrize("case", list(CENSUS_CASES))
def test_census_case(sandbox, case):
    seed, index = map(int, case.split(":"))
    verdict = sandbox.run(run_case, seed, index, timeout=TIMEOUT).unwrap()
    assert verdict["category"] in ("ok", "uncertified"), (CENSUS_CASES[case], verdict)


def test_fcl_contact_settles_a_distance_in_batches_and_scenes_too():
    # Census case 49:8148's pair (a tetrahedron's points each twice, a segment of five collinear
    # points through it): FCL's weights on the tetrahedron the support scans find again proved
    # contact but left the witnesses 0.02 apart, and the distance was certified there. Batches and
    # scenes answer with the same solver.
    from fuzz_cases import make_case

    case = make_case(49, 8148)
    size = float(np.ptp(np.vstack([case.a, case.b]), axis=0).max()) * 2
    single = sc.distance(case.a, case.b, method="fcl")
    batch = sc.distance_many([case.a], [case.b], method="fcl")
    scene = sc.Scene(method="fcl")
    scene.add(case.a)
    scene.add(case.b)
    within = scene.pairs_within(0.0)
    for distance, certified in ((single.distance, single.certified),
                                (batch.distance[0], batch.certified[0]),
                                (within.distance[0], within.certified[0])):
        assert certified and 0 <= distance <= 1e-9 * size


# ----- certified means the value too ------------------------------------------------------------


@pytest.mark.parametrize("method", ["ipso", "pso", "penalty"])
def test_a_certified_distance_is_within_the_tolerance_of_the_true_one(method):
    # These methods stop at their iteration budget. A separation that proved the verdict used to
    # certify their distances too, up to 3e-3 of the pair's size away from the true distance.
    from scene_cases import pair_size

    rng = np.random.default_rng(23)
    identity = np.eye(4)
    for index in range(40):
        a = rng.normal(size=(8, 3))
        b = rng.normal(size=(8, 3)) + rng.normal(size=3) * 3
        r = sc.distance(a, b, method=method, seed=index)
        if not r.certified:
            continue
        true = max(exact_signed_distance(a, b).signed_distance, 0.0)
        size = pair_size(a, identity, b, identity)
        assert r.distance - true <= 1e-9 * size + 1e-12 * size, (index, r, true)
        assert r.lower_bound <= true + 1e-12 * size, (index, r, true)


def near_touching_pairs(seed, count):
    """A random 4-39 point polytope against each shape a hair apart: B placed along a random
    direction by bisection on whether the exact distance proves the bodies apart (collide's verdict
    converges to the tolerance's border, where the dual method's swarm spends 0.1-1 s a call),
    then moved out by delta x the pair's size."""
    rng = np.random.default_rng(seed)
    shapes = {"box": lambda r: sc.Box(r), "cylinder": lambda r: sc.Cylinder(r[0], r[1]),
              "cone": lambda r: sc.Cone(r[0], r[1]), "ellipsoid": lambda r: sc.Ellipsoid(r)}
    for _ in range(count):
        a = sc.ConvexPolyhedron(rng.normal(size=(int(rng.integers(4, 40)), 3)) * 0.5)
        for name, make in shapes.items():
            b = make(rng.uniform(0.1, 0.6, 3))
            u = rng.normal(size=3)
            u /= np.linalg.norm(u)
            pose = np.eye(4)
            pose[:3, :3] = Rotation.random(random_state=rng).as_matrix()
            low, high = 0.0, 5.0
            for _ in range(45):
                middle = (low + high) / 2
                pose[:3, 3] = middle * u
                if sc.distance(a, b, pose_b=pose, method="exact").lower_bound > 0:
                    high = middle
                else:
                    low = middle
            size = 2 * (a.bounding_radius + b.bounding_radius)
            for delta in (1e-9, 1e-8, 1e-7):
                pose[:3, 3] = (high + delta * size) * u
                yield name, delta, a, b, pose.copy()


def test_the_exact_distance_of_bodies_a_hair_apart_is_mostly_certified():
    # Wolfe's nearest point a hair from the origin has a direction off by the rounding of unit
    # points over its norm, and the separation along it lost that angle times a face's width: of
    # such pairs with boxes, cylinders, cones and ellipsoids (1e-9 to 1e-7 of the size apart), 16
    # of 48 were uncertified at the default tolerance, some with lower bound 0. The corral's
    # planes prove most of them (here 5 of 96 are left: near the tolerance's border, for
    # "dual", the default, whose finish and swarm prove them).
    unproven = [(name, delta) for seed in (1, 2)
                for name, delta, a, b, pose in near_touching_pairs(seed, 4)
                if not sc.distance(a, b, pose_b=pose, method="exact").certified]
    assert len(unproven) <= 6, unproven
