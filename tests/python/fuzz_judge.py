"""The fuzz suite's judge: what one case's outcome says about the library.

``run_case(seed, index)`` rebuilds the case, makes the call (``fuzz_api.call``) and judges it
against ``minkowski_oracle``; it is what the census and the fuzz test run in sandboxed children.
A crash or a hang is the sandbox's to report (``category_of`` names it): the judge itself sees
only answers and exceptions.

Categories (``CATEGORIES``):

ok           the answer is right and certified, or the due error was a ValueError or TypeError
uncertified  the answer is right (bounds, witnesses) but ``certified`` is false
crash, hang  the process died by a signal / gave no answer within the time limit (the sandbox's)
error-type   another exception for bad input, or an exception where an answer was due
wrong        a bound violated, a certified verdict wrong, a certified precise method inaccurate,
             witnesses off their bodies, or a verdict, certified flag or distance that changes
             under scaling and translation
slipped      bad input answered instead of refused
api          a call the corpus thinks valid refused as unknown (keyword, method): the API moved
suite-error  the judge or the oracle raised: a bug in this suite

Tolerances are relative to the pair's size (the largest extent of the two bodies together):
bounds and witnesses must hold within ``SLACK`` x size, and verdicts and precise distances are
judged only where the true signed distance is farther than ``BAND`` x size from 0, and then must be
right within it. Both add the oracle's own error bound and ``ROUNDING`` x the largest coordinate,
for the rounding that arithmetic on coordinates far from the origin cannot avoid.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

import minkowski_oracle as oracle
from contract import pair_scale
from fuzz_api import API_MISMATCH, BATCH_QUERIES, PRECISE_METHODS, call, summary
from fuzz_cases import ANSWER, ERROR, Case, make_case
from sandbox import CRASHED, HUNG, RETURNED, Outcome

CATEGORIES = (
    "ok", "uncertified", "crash", "hang", "error-type", "wrong", "slipped", "api", "suite-error",
)  # fmt: skip
FAILURES = frozenset({"crash", "hang", "error-type", "wrong", "slipped"})
"""The categories that count against the library."""

SLACK = 1e-9
BAND = 1e-6
ROUNDING = 1e-12  # about 4500 units in the last place of the largest coordinate


@dataclass(frozen=True)
class Tolerance:
    """The allowances for one pair, in its units. ``witness`` is the library's own default
    tolerance for the pair (SLACK times its size as the library measures it, the diameter of a
    ball around both bodies, which can exceed the widest extent ``slack`` is relative to): the
    penetration solver accepts witnesses off ``distance * direction`` by up to it where the
    normal is a gap's worth of angle off a long edge's facet (penetration.cpp, ``witnesses``)."""

    slack: float
    band: float
    witness: float


def tolerance_of(a: np.ndarray, b: np.ndarray, truth: oracle.Answer) -> Tolerance:
    """SLACK and BAND for the pair (a, b), whose true signed distance is ``truth``."""
    points = np.vstack([a, b])
    size = float(np.max(np.ptp(points, axis=0)))
    reach = float(np.max(np.abs(points)))
    rounding = ROUNDING * reach + truth.error
    ball_size = pair_scale(a, b).size
    return Tolerance(SLACK * size + rounding, BAND * size + rounding,
                     SLACK * max(size, ball_size) + rounding)


def run_case(seed: int, index: int) -> Dict[str, Any]:
    """Make and judge case ``index`` of corpus ``seed``: ``{"category", "reason", "seconds"}``."""
    return run(make_case(seed, index))


def run(case: Case) -> Dict[str, Any]:
    """Make and judge ``case``'s call(s): ``{"category", "reason", "seconds"}``."""
    start = time.monotonic()
    try:
        answers = answers_of(case)
    except Exception as error:  # noqa: BLE001 - every exception is judged
        category, reason = judge_error(case, error)
    else:
        category, reason = judge_answers(case, answers)
    return {"category": category, "reason": reason, "seconds": time.monotonic() - start}


def answers_of(case: Case) -> List[Any]:
    """The summaries of ``case``'s call, and for an invariance case of the scaled call too."""
    answers = [summary(call(case.query, case.method, case.a, case.b, case.options))]
    if case.family == "invariance":
        a, b = (case.scale * np.asarray(x, dtype=np.float64) + case.shift for x in (case.a, case.b))
        answers.append(summary(call(case.query, case.method, a, b, case.options)))
    return answers


def scale_problems(case: Case) -> List[str]:
    """What changes between an invariance case's two answers (nothing, if the library is right)."""
    a, b = np.asarray(case.a, dtype=np.float64), np.asarray(case.b, dtype=np.float64)
    return compare_scales(case, a, b, answers_of(case))


def category_of(outcome: Outcome) -> Tuple[str, str]:
    """(category, reason) of a sandboxed ``run_case`` or ``run``."""
    if outcome.kind == RETURNED:
        return outcome.value["category"], outcome.value["reason"]
    if outcome.kind == CRASHED:
        return "crash", f"{outcome.error_type}: {outcome.message.strip()[-300:]}"
    if outcome.kind == HUNG:
        return "hang", f"no answer after {outcome.seconds:.0f} s"
    return "suite-error", f"{outcome.error_type}: {outcome.message}"


def judge_error(case: Case, error: Exception) -> tuple:
    """The category of ``error`` raised by ``case``'s call."""
    text = f"{type(error).__name__}: {error}"
    if case.expect == ANSWER:
        if any(fragment in str(error) for fragment in API_MISMATCH):
            return "api", text
        return "error-type", f"an answer was due: {text}"
    if isinstance(error, (ValueError, TypeError)):
        return "ok", text
    return "error-type", f"a ValueError or TypeError was due: {text}"


def judge_answers(case: Case, answers: List[Any]) -> tuple:
    """The category of the answers of ``case``'s call(s)."""
    if case.expect == ERROR:
        return "slipped", f"bad input answered: {_short(answers[0])}"
    if case.query in BATCH_QUERIES:
        problems, certified = _judge_batch(case, answers[0])
    else:
        a, b = np.asarray(case.a, dtype=np.float64), np.asarray(case.b, dtype=np.float64)
        problems, certified = judge_single(case.query, a, b, answers[0])
        if case.family == "invariance":
            a2, b2 = case.scale * a + case.shift, case.scale * b + case.shift
            scaled, scaled_certified = judge_single(case.query, a2, b2, answers[1])
            problems += [f"scaled: {p}" for p in scaled]
            problems += compare_scales(case, a, b, answers)
            certified = certified and scaled_certified
    if problems:
        return "wrong", "; ".join(problems)
    return ("ok", "") if certified else ("uncertified", "")


def judge_single(query: str, a: np.ndarray, b: np.ndarray, answer: Any) -> tuple:
    """(problems, certified) of one answer of ``distance``, ``signed_distance`` or ``collide``."""
    truth = oracle.signed_distance(a, b)
    tolerance = tolerance_of(a, b, truth)
    if query == "collide":
        verdict = answer["colliding"] if isinstance(answer, dict) else answer
        return _verdict_problems(verdict, truth.signed_distance, tolerance), True
    signed = query == "signed_distance"
    true = truth.signed_distance if signed else truth.distance
    problems = _bound_problems(answer["distance"], answer["lower_bound"], true, tolerance)
    problems += _witness_problems(a, b, answer, signed, tolerance)
    certified = bool(answer["certified"])
    if certified:
        problems += _verdict_problems(answer["colliding"], truth.signed_distance, tolerance)
    # "converged" says the bounds are within the tolerance: the value itself is then proven.
    if answer["status"] == "converged" and abs(answer["distance"] - true) > tolerance.band:
        problems.append(
            f"converged {answer['method']} distance {answer['distance']:.9g}, true {true:.9g}"
        )
    return problems, certified


def _bound_problems(distance: float, lower: float, true: float, tolerance: Tolerance) -> List[str]:
    if not (np.isfinite(distance) and np.isfinite(lower)):
        return [f"distance {distance} and lower bound {lower} for a true {true:.9g}"]
    problems = []
    if lower > true + tolerance.slack:
        problems.append(f"lower bound {lower:.9g} above the true {true:.9g}")
    if distance < true - tolerance.slack:
        problems.append(f"distance {distance:.9g} below the true {true:.9g}")
    return problems


def _norm(v: np.ndarray) -> float:
    """|v| without overflow for components near the largest double (largest component first)."""
    largest = float(np.max(np.abs(v)))
    return largest * float(np.linalg.norm(v / largest)) if largest > 0 else 0.0


def _witness_problems(
    a: np.ndarray, b: np.ndarray, answer: Dict[str, Any], signed: bool, tolerance: Tolerance
) -> List[str]:
    point_a, point_b = answer["point_a"], answer["point_b"]
    if point_a is None or point_b is None:
        return []
    if not (np.all(np.isfinite(point_a)) and np.all(np.isfinite(point_b))):
        return [f"witness points {point_a}, {point_b}"]
    problems = []
    for name, point, body in (("point_a", point_a, a), ("point_b", point_b, b)):
        where = oracle.point_distance(point, body)
        off = where.distance
        if off > tolerance.slack + where.error:
            problems.append(f"{name} {off:.3g} off its body")
    distance = answer["distance"]
    if signed and answer["direction"] is not None:
        # The witnesses realise the separation along the normal; the answer's value is its upper
        # bound, so they agree to within the bounds' gap (rounding, once converged).
        mismatch = _norm(point_b - point_a - distance * answer["direction"])
        if mismatch > tolerance.witness + (distance - answer["lower_bound"]):
            problems.append(f"|point_b - point_a - distance * direction| = {mismatch:.3g}")
    elif not signed:
        mismatch = abs(_norm(point_b - point_a) - distance)
        if mismatch > tolerance.slack:
            problems.append(f"| |point_b - point_a| - distance | = {mismatch:.3g}")
    return problems


def _verdict_problems(colliding: Any, true: float, tolerance: Tolerance) -> List[str]:
    if abs(true) <= tolerance.band or bool(colliding) == (true <= 0):
        return []
    return [f"verdict colliding={bool(colliding)} for a true signed distance {true:.9g}"]


def _rows(bodies: Any) -> Optional[List[Any]]:
    """The bodies of a batch's side, one per row; None for one ``(n, 3)`` array, which the batch
    uses for every row."""
    if isinstance(bodies, np.ndarray) and bodies.ndim == 2:
        return None
    return list(bodies)


def _judge_batch(case: Case, answer: Dict[str, Any]) -> tuple:
    """(problems, all certified) of a ``distance_many`` or ``collide_many`` answer."""
    As, Bs = _rows(case.a), _rows(case.b)
    rows = len(As) if As is not None else len(Bs) if Bs is not None else 1
    As = [case.a] * rows if As is None else As
    Bs = [case.b] * rows if Bs is None else Bs
    if len(answer["distance"]) != len(As):
        return [f"{len(answer['distance'])} answers for {len(As)} pairs"], False
    problems: List[str] = []
    for i, (a, b) in enumerate(zip(As, Bs)):
        a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
        truth = oracle.signed_distance(a, b)
        tolerance = tolerance_of(a, b, truth)
        pair = {key: (None if value is None else value[i]) for key, value in answer.items()
                if key in ("distance", "lower_bound", "point_a", "point_b")}  # fmt: skip
        pair["direction"] = None
        # A negative distance claims a depth (collide_many answers libccd's pairs with their
        # signed distance): it is judged as a signed distance.
        signed = bool(pair["distance"] < 0)
        true = truth.signed_distance if signed else truth.distance
        found = _bound_problems(pair["distance"], pair["lower_bound"], true, tolerance)
        found += _witness_problems(a, b, pair, signed, tolerance)
        if case.query == "collide_many" or answer["certified"][i]:
            found += _verdict_problems(answer["colliding"][i], truth.signed_distance, tolerance)
        problems += [f"pair {i}: {p}" for p in found]
    return problems, bool(np.all(answer["certified"]))


def compare_scales(case: Case, a: np.ndarray, b: np.ndarray, answers: List[Any]) -> List[str]:
    """What changed between the unit-scale answer and the scaled, translated one."""
    truth = oracle.signed_distance(a, b)
    if abs(truth.signed_distance) <= tolerance_of(a, b, truth).band:
        return []  # the verdict may flip with the rounding of a touching pair
    unit, scaled = answers
    if case.query == "collide":
        return [] if unit == scaled else [f"collide {unit} at unit scale, {scaled} scaled"]
    # A distance of a swarm that stops at its budget (ipso, pso, penalty) is certified only where
    # the swarm reached the tolerance (since ebe1fe7, as test_properties' unit-of-length property
    # says), and scaling by a factor that is not a power of two rounds the input differently,
    # which changes a swarm's path: its proven verdicts are compared, and every answer of the
    # methods that always certify.
    precise = unit["method"] in PRECISE_METHODS and scaled["method"] in PRECISE_METHODS
    band = tolerance_of(a, b, truth).band
    # Where a swarm's bounds prove neither verdict, it answers "colliding" (bodies not shown apart
    # may touch): uncertified, its upper bound above the band, far above the library's tolerance,
    # within which an upper bound proves contact. Such a verdict says nothing proven, and the
    # swarm's path at the other scale may prove the pair apart (census case 12:6083, the penalty
    # method: lower bound 0 at unit scale, 0.0067 scaled, true distance 0.018); both bounds are
    # judged against the truth all the same (judge_single).
    unproven = [
        answer["colliding"] and not answer["certified"] and answer["distance"] / factor > band
        for answer, factor in ((unit, 1.0), (scaled, case.scale))
    ]
    compare_verdicts = precise or not any(unproven)
    problems = [
        f"{name} {unit[name]} at unit scale, {scaled[name]} scaled"
        for name in ("colliding", "certified")
        if unit[name] != scaled[name] and (compare_verdicts if name == "colliding" else precise)
    ]
    if precise:
        change = abs(scaled["distance"] / case.scale - unit["distance"])
        if change > tolerance_of(a, b, truth).band:
            problems.append(
                f"distance {unit['distance']:.9g} at unit scale, {scaled['distance']:.9g} "
                f"= {scaled['distance'] / case.scale:.9g} x scale"
            )
    return problems


def _short(answer: Any) -> str:
    if isinstance(answer, dict) and "distance" in answer:
        return f"distance {answer['distance']}"
    return repr(answer)[:80]


def describe(seed: int, index: int) -> str:
    """A one-line description of a case (for reports)."""
    case = make_case(seed, index)
    return f"{case.id} {case.family} {case.query} {case.label} [{case.note}] {dict(case.options)}"
