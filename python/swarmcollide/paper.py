"""The paper's Section IV: its two tetrahedron pairs and the rows of its Tables 1 and 2."""

from __future__ import annotations

import statistics
import time
from dataclasses import dataclass
from typing import Dict, List, Sequence, Tuple

import numpy as np

from ._core import ConvexPolyhedron
from .queries import distance

A = np.array([[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]], dtype=float)
"""Tetrahedron A of both examples."""
B_COLLIDING = np.array([[1, 0, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]], dtype=float)
"""Tetrahedron B of Section IV-A: it touches A at (1, 0, 0)."""
B_SEPARATE = np.array([[1, -1, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]], dtype=float)
"""Tetrahedron B of Section IV-B: its distance to A is 1."""


@dataclass(frozen=True)
class Row:
    """One row of a table: the weights lambda_1..4, delta_1..4, O_AB and a time in seconds."""

    label: str
    weights_a: Tuple[float, ...]
    weights_b: Tuple[float, ...]
    distance: float
    seconds: float


@dataclass(frozen=True)
class Case:
    """One of the paper's examples, with its exact answer and the paper's table rows."""

    title: str
    b: np.ndarray
    exact: Row
    paper_rows: Tuple[Row, ...]


_VERTEX = ((0.0, 1.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))

CASES = (
    Case(
        "Table 1: collision (Section IV-A)",
        B_COLLIDING,
        Row("exact", *_VERTEX, 0.0, float("nan")),
        (
            Row(
                "paper: penalty function",
                (0.0004, 1.0281, -0.0005, 0.0401),
                (0.9882, -0.0003, 0.0022, 0.0005),
                2.54e-33,
                5.532,
            ),
            Row(
                "paper: improved PSO",
                (0.0001, 0.9999, -0.0001, 0.0001),
                (0.9999, -0.0001, 0.0001, 0.0002),
                1.33e-35,
                0.256,
            ),
        ),
    ),
    Case(
        "Table 2: separation (Section IV-B)",
        B_SEPARATE,
        Row("exact", *_VERTEX, 1.0, float("nan")),
        (
            Row(
                "paper: penalty function",
                (0.0002, 1.042, -0.0004, 0.0205),
                (0.9890, -0.0007, 0.0032, 0.0006),
                0.9855,
                4.832,
            ),
            Row(
                "paper: improved PSO",
                (0.0001, 0.9999, -0.0001, 0.0001),
                (0.9999, -0.0001, 0.0001, 0.0001),
                1.0000,
                0.356,
            ),
        ),
    ),
)

SOLVERS: Dict[str, Dict[str, object]] = {
    "swarmcollide: ipso": {"method": "ipso"},
    "swarmcollide: ipso, paper's rules": {"method": "ipso", "constraint_handling": "feasibility"},
    "swarmcollide: pso (7)": {"method": "pso"},
    "swarmcollide: penalty": {"method": "penalty"},
    "swarmcollide: dual (certified)": {"method": "dual"},
    "swarmcollide: exact (Wolfe)": {"method": "exact"},
    "swarmcollide: fcl (exact GJK)": {"method": "fcl"},
}
"""Our rows: a label and the keyword arguments of ``distance``."""


def solve(case: Case, label: str, parameters: Dict[str, object], seed: int, repeats: int) -> Row:
    """Our row for ``case``: the answer for ``seed`` and the median time over ``repeats`` runs.

    The bodies are built once, outside the timing, as an application holding its shapes would.
    """
    a, b = ConvexPolyhedron(A), ConvexPolyhedron(case.b)
    times: List[float] = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = distance(a, b, seed=seed, **parameters)  # type: ignore[arg-type]
        times.append(time.perf_counter() - start)
    return Row(
        label,
        tuple(result.weights_a.tolist()),
        tuple(result.weights_b.tolist()),
        result.distance,
        statistics.median(times),
    )


def format_table(case: Case, rows: Sequence[Row]) -> str:
    """The table as the paper lays it out, one line per row."""
    header = ["λ1", "λ2", "λ3", "λ4", "δ1", "δ2", "δ3", "δ4", "O_AB", "time/s"]
    width = max(len(row.label) for row in rows) + 2
    lines = [case.title, " " * width + "".join(f"{h:>10}" for h in header)]
    for row in rows:
        weights = "".join(f"{w:>10.4f}" for w in row.weights_a + row.weights_b)
        seconds = "" if np.isnan(row.seconds) else f"{row.seconds:>10.3g}"
        lines.append(f"{row.label:<{width}}{weights}{row.distance:>10.4g}{seconds}")
    return "\n".join(lines)


def reproduce(seed: int = 0, repeats: int = 20) -> str:
    """Both tables: the paper's rows, ours, and the exact answer."""
    tables = []
    for case in CASES:
        ours = [solve(case, label, parameters, seed, repeats) for label, parameters in SOLVERS.items()]
        tables.append(format_table(case, [*case.paper_rows, *ours, case.exact]))
    return "\n\n".join(tables)
