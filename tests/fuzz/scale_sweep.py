"""Issue 12's scale sweep: one pair at scales 1e-100 .. 1e300, every method, in sandboxed children.

The pair is the unit cube c and c + [0.5, 0.25, 0.1], both scaled by s: they overlap by half their
width, so ``signed_distance / s`` is -0.5 and ``collide`` is True at every s. Prints two Markdown
tables (the signed distance over s, the collide verdict), a cell per scale and method, with
"crash", "hang" or the exception's type where there is no answer:

    .venv/bin/python tests/fuzz/scale_sweep.py
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Dict, List, Tuple

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))

from fuzz_api import METHODS, invoke  # noqa: E402
from sandbox import CRASHED, HUNG, RAISED, Outcome, Sandbox  # noqa: E402

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
OFFSET = np.array([0.5, 0.25, 0.1])
# Every twentieth decade, and the scales at which issue 12 saw a method change its answer.
SCALES = sorted({10.0**k for k in range(-100, 101, 20)} | {1e-6, 1e-5, 5.6e-5, 1e-4, 3e-4, 1e-3,
                 1.8e-3, 1.0, 1e6, 1e8, 1e12, 1e77, 1e300})  # fmt: skip


def cell(outcome: Outcome, s: float) -> str:
    if outcome.kind == CRASHED:
        return f"crash ({outcome.error_type})"
    if outcome.kind == HUNG:
        return "hang"
    if outcome.kind == RAISED:
        return outcome.error_type
    value = outcome.value
    if isinstance(value, bool):
        return str(value)
    text = f"{value['distance'] / s:.6g}"
    return text if value["certified"] else text + " (uncertified)"


def sweep(timeout: float) -> Dict[Tuple[str, str, float], str]:
    tasks = []
    for query in ("signed_distance", "collide"):
        for method in (m for m in METHODS[query] if m):
            for s in SCALES:
                arguments = (query, (CUBE * s, (CUBE + OFFSET) * s), {"method": method})
                tasks.append(((query, method, s), invoke, arguments))
    with Sandbox(parallel=2, preload=("fuzz_api",)) as sandbox:
        return {key: cell(outcome, key[2]) for key, outcome in sandbox.map(tasks, timeout=timeout)}


def table(cells: Dict[Tuple[str, str, float], str], query: str) -> str:
    methods: List[str] = [m for m in METHODS[query] if m]
    lines = ["| s | " + " | ".join(methods) + " |", "|---:|" + "---|" * len(methods)]
    for s in SCALES:
        lines.append(f"| {s:.3g} | " + " | ".join(cells[query, m, s] for m in methods) + " |")
    return "\n".join(lines)


def main() -> None:
    cells = sweep(timeout=20.0)
    print("signed_distance(c * s, (c + [0.5, 0.25, 0.1]) * s) / s (exact: -0.5)\n")
    print(table(cells, "signed_distance"))
    print("\ncollide(c * s, (c + [0.5, 0.25, 0.1]) * s) (exact: True)\n")
    print(table(cells, "collide"))


if __name__ == "__main__":
    main()
