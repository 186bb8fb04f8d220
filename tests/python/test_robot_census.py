"""The robots corpus of the fuzz census (tests/python/robot_cases.py), a few cases in-process so
that it cannot rot: each family and source, and the judge's sensitivity to a wrong answer."""

import dataclasses

import numpy as np
import pytest

import swarmcollide as sc

pytest.importorskip("yourdfpy")
pytest.importorskip("mujoco")
pytest.importorskip("trimesh")

import robot_cases  # noqa: E402 - needs the robot extra

CASES = range(25)
"""Five of each family's turn (check, motion, check, motion, argument), every source among them."""

@pytest.mark.parametrize("index", CASES)
def test_robot_census_case_is_ok(index):
    verdict = robot_cases.run_robot_case(0, index)
    assert verdict["category"] in ("ok", "uncertified"), verdict


def test_the_cases_cover_every_family_and_source():
    described = [robot_cases.robot_case(0, index) for index in CASES]
    assert {family for family, *_ in described} == {"check", "motion", "argument"}
    sources = {arguments[0] for family, _, _, arguments in described if family != "argument"}
    assert sources == set(robot_cases.SOURCES)


def test_the_judge_finds_a_flipped_verdict(monkeypatch):
    # A judge that passes everything proves nothing: flip check's verdicts and it must object.
    check = sc.Robot.check

    def flipped(self, q, **options):
        answer = check(self, q, **options)
        return dataclasses.replace(answer, colliding=~np.asarray(answer.colliding))

    monkeypatch.setattr(sc.Robot, "check", flipped)
    checks = [i for i in range(10) if robot_cases.robot_case(0, i)[0] == "check"]
    verdicts = [robot_cases.run_robot_case(0, i)["category"] for i in checks]
    assert "wrong" in verdicts, verdicts
