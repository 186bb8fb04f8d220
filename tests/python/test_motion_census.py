"""The motions corpus of the fuzz census (tests/python/motion_cases.py), a few cases in-process so
that it cannot rot: every family, and the judge's sensitivity to a wrong answer."""

import numpy as np
import pytest

import motion_cases
import swarmcollide as sc

CASES = range(18)
"""Three of each turn of ``motion_cases.FAMILIES``."""


@pytest.mark.parametrize("index", CASES)
def test_motion_census_case_is_ok(index):
    verdict = motion_cases.run_motion_case(0, index)
    assert verdict["category"] in ("ok", "uncertified"), verdict


def test_the_cases_cover_every_family():
    families = {motion_cases.motion_case(0, index)[0] for index in CASES}
    assert families == set(motion_cases.FAMILIES)


def test_the_judge_finds_a_missed_contact_and_a_late_bracket(monkeypatch):
    # A judge that passes everything proves nothing: report every motion free, then every
    # bracket 0.05 late, and it must object to both.
    original = sc.time_of_impact
    cube = sc.Box([0.5] * 3)
    start, end = np.eye(4), np.eye(4)
    start[0, 3], end[0, 3] = -4, 4
    oracle = motion_cases.Oracle(cube, cube, (start, end), (np.eye(4), np.eye(4)), "linear")
    honest = original(cube, cube, pose_a=(start, end))
    free = original(cube, cube, pose_a=(start, start))
    assert motion_cases.judge_motion(oracle, honest, 1e-9, 1e-6) is None
    assert "free" in motion_cases.judge_motion(oracle, free, 1e-9, 1e-6)

    class Late:
        touches, certified = True, True
        t_lower, t_upper = honest.t_lower + 0.05, honest.t_upper + 0.05

    assert "apart before" in motion_cases.judge_motion(oracle, Late(), 1e-9, 1e-6)
    monkeypatch.setattr(sc, "time_of_impact", lambda *a, **k: free)
    swept = [i for i in range(60) if motion_cases.motion_case(0, i)[0] == "swept"]
    verdicts = [motion_cases.run_motion_case(0, i)["category"] for i in swept]
    assert "wrong" in verdicts, verdicts


def test_a_polytope_grazing_a_compound_body_steps_by_its_nearest_parts():
    # Census case motions-0-2011: a tetrahedron translating past a compound body of an ellipsoid
    # and a cone, 2e-10 of the size inside the contact threshold. A compound body's lower bound
    # is the least over its part pairs, so the advancement stepped by the whole motion's speed:
    # 25,968 queries and 149 s (a hang in the census). The realising pair's separation along its
    # direction and the other pairs' own separations bound it as the ellipsoid alone is (16).
    # Census case motions-2-1941: a box sliding past a compound of an ellipsoid and a cylinder,
    # whose cylinder part's ball the box's overlaps: the other pair's cheap bounds proved nothing
    # and 63,082 queries (90 s) stepped by the ellipsoid's gap; its own query's bound: 52.
    for seed, index in ((0, 2011), (2, 1941)):
        _, _, _, case = motion_cases.motion_case(seed, index)
        motion_a, motion_b, _ = motion_cases.grazing_motions(case)
        r = sc.time_of_impact(case["a"], case["b"], pose_a=motion_a, pose_b=motion_b,
                              method=case["method"])
        assert r.touches and r.certified and r.iterations < 100, (seed, index, r)
        assert motion_cases.run_motion_case(seed, index)["category"] == "ok"
