"""The fuzz census: every case of a corpus in a sandboxed child, counted by category.

Prints a Markdown table of counts per query and method and writes a JSON Lines file with every
case that is not "ok" (its id, category and reason), so that a fix can be checked case by case:

    .venv/bin/python tests/fuzz/census.py --json build/fuzz/census.jsonl   # 10000 cases
    .venv/bin/python tests/fuzz/census.py --rerun tests/fuzz/before.jsonl  # old -> new per case
    .venv/bin/python tests/fuzz/census.py --corpus files --count 600       # meshes, CLI, inputs
    .venv/bin/python tests/fuzz/census.py --corpus scene --count 200       # scenes
    .venv/bin/python tests/fuzz/census.py --corpus robots --count 1000     # robots
    .venv/bin/python tests/fuzz/census.py --corpus motions --count 1000    # motions

The query corpus's categories are those of tests/python/fuzz_judge.py and its cases those of
fuzz_cases.py; the files corpus (mesh files, the command line, what users pass from other
libraries) has both in tests/python/fuzz_files.py; the scene corpus's cases are those of
scene_cases.py, judged in fuzz_judge.py's categories: every broadphase through long seeded motions
against brute force, every method's certified rows against exact distances, bodies far from the
origin, and bad arguments (a case whose error does not name its argument counts as "error-type").
The robots corpus's cases are those of robot_cases.py: random robots from tables, URDF and MJCF
whose checks, distances and poses are judged against brute force, their motions against dense
sampling, and bad models, configurations and options. The motions corpus's cases are those of
motion_cases.py: time_of_impact against dense sampling and exact sweeps, batches against single
calls, and bad arguments.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import Counter
from pathlib import Path
from types import SimpleNamespace
from typing import Any, Callable, Dict, Iterable, List, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))

from fuzz_cases import make_case  # noqa: E402
from fuzz_files import FILE_CATEGORIES, FILE_FAILURES, make_file_case, run_file_case  # noqa: E402
from fuzz_judge import CATEGORIES, FAILURES, category_of, run_case  # noqa: E402
from motion_cases import motion_case, run_motion_case  # noqa: E402
from robot_cases import robot_case, run_robot_case  # noqa: E402
from sandbox import Sandbox  # noqa: E402
from scene_cases import run_scene_case, scene_case  # noqa: E402

Record = Dict[str, Any]


def make_motion_case(seed: int, index: int) -> SimpleNamespace:
    """Motion case ``index`` described as the other corpora describe theirs."""
    family, query, label, case = motion_case(seed, index)
    note = case["label"] if isinstance(case, dict) else case
    return SimpleNamespace(id=f"motions-{seed}-{index}", family=family, query=query, label=label,
                           note=note)  # fmt: skip


def make_scene_case(seed: int, index: int) -> SimpleNamespace:
    """Scene case ``index`` described as the other corpora describe theirs."""
    family, query, label, arguments = scene_case(seed, index)
    return SimpleNamespace(id=f"scene-{seed}-{index}", family=family, query=query, label=label,
                           note=repr(arguments))  # fmt: skip


def make_robot_case(seed: int, index: int) -> SimpleNamespace:
    """Robot case ``index`` described as the other corpora describe theirs."""
    family, query, label, arguments = robot_case(seed, index)
    return SimpleNamespace(id=f"robots-{seed}-{index}", family=family, query=query, label=label,
                           note=repr(arguments))  # fmt: skip


CORPORA: Dict[str, Tuple[Callable[[int, int], Any], Callable[..., Any], tuple, frozenset]] = {
    "queries": (make_case, run_case, CATEGORIES, FAILURES),
    "files": (make_file_case, run_file_case, FILE_CATEGORIES, FILE_FAILURES),
    "scene": (make_scene_case, run_scene_case, CATEGORIES, FAILURES),
    "motions": (make_motion_case, run_motion_case, CATEGORIES, FAILURES),
    "robots": (make_robot_case, run_robot_case, CATEGORIES, FAILURES),
}
"""Each corpus's case maker, judge (run in the sandbox), categories and failing categories."""

PRELOAD = {"queries": ("fuzz_judge",), "files": ("fuzz_judge", "fuzz_files"),
           "scene": ("scene_cases",), "motions": ("motion_cases",),
           "robots": ("robot_cases",)}  # fmt: skip
"""The modules each corpus's children import once, before their first case."""

TIMEOUT = {"queries": 20.0, "files": 30.0, "scene": 600.0, "motions": 120.0, "robots": 60.0}
"""Seconds before a case counts as a hang: a scene case runs a long motion."""


def census(
    seed: int, indices: Iterable[int], workers: int, timeout: float, progress: bool,
    corpus: str = "queries",
) -> List[Record]:
    """One record per case: id, index, family, query, method, note, category, reason."""
    make, run, _, _ = CORPORA[corpus]
    records = []
    start = time.monotonic()
    tasks = ((index, run, (seed, index)) for index in indices)
    # A file case may ask for much memory (a huge STL header): 4 GB per child at most.
    limit = 4 << 30 if corpus == "files" else None
    with Sandbox(parallel=workers, preload=PRELOAD[corpus]) as sandbox:
        for index, outcome in sandbox.map(tasks, timeout=timeout, memory_limit=limit):
            case = make(seed, index)
            category, reason = category_of(outcome)
            records.append({
                "id": case.id, "index": index, "family": case.family,
                "query": getattr(case, "query", case.family),
                "method": case.label, "note": case.note, "category": category, "reason": reason,
            })  # fmt: skip
            if progress and len(records) % 100 == 0:
                counts = Counter(r["category"] for r in records)
                print(f"{len(records)} cases, {time.monotonic() - start:.0f} s: {dict(counts)}",
                      file=sys.stderr, flush=True)  # fmt: skip
    return sorted(records, key=lambda r: r["index"])


def table(
    records: List[Record], categories: tuple = CATEGORIES, failures: frozenset = FAILURES
) -> str:
    """Counts per (query, method) and category, as Markdown."""
    counts: Dict[Tuple[str, str], Counter] = {}
    for record in records:
        counts.setdefault((record["query"], record["method"]), Counter())[record["category"]] += 1
    total = Counter(record["category"] for record in records)
    lines = [
        "| query | method | cases | " + " | ".join(categories) + " |",
        "|---|---|---:|" + "---:|" * len(categories),
    ]
    for (query, method), row in sorted(counts.items()):
        cells = " | ".join(str(row[c]) for c in categories)
        lines.append(f"| {query} | {method} | {sum(row.values())} | {cells} |")
    cells = " | ".join(f"**{total[c]}**" for c in categories)
    lines.append(f"| **all** | | **{len(records)}** | {cells} |")
    failing = sum(total[c] for c in failures)
    lines.append(f"\n{failing} of {len(records)} cases fail ({', '.join(sorted(failures))}).")
    return "\n".join(lines)


def write_report(
    path: Path, seed: int, timeout: float, seconds: float, records: List[Record],
    corpus: str = "queries",
) -> None:
    """JSON Lines: the run (seed, counts) first, then every case that is not ok, one a line."""
    path.parent.mkdir(parents=True, exist_ok=True)
    header = {
        "seed": seed, "corpus": corpus, "count": len(records), "timeout": timeout,
        "seconds": round(seconds),
        "counts": dict(Counter(r["category"] for r in records)),
    }  # fmt: skip
    lines = [json.dumps(header)]
    lines += [
        json.dumps({**r, "reason": r["reason"][:200]}) for r in records if r["category"] != "ok"
    ]
    path.write_text("\n".join(lines) + "\n")


def read_report(path: Path) -> Tuple[Record, List[Record]]:
    """(the run, its cases that were not ok) from a ``write_report`` file."""
    header, *cases = (json.loads(line) for line in path.read_text().splitlines())
    return header, cases


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--corpus", choices=sorted(CORPORA), default="queries",
                        help="the query cases (default), the files, CLI and inputs cases, scenes, "
                        "robots or motions")
    parser.add_argument("--seed", type=int, default=0, help="the corpus (default 0)")
    parser.add_argument("--count", type=int, default=10000, help="cases 0 .. count-1")
    parser.add_argument("--workers", type=int, default=2, help="children at once")
    parser.add_argument("--timeout", type=float,
                        help="seconds before a hang (default: queries 20, files 30, scene 600)")
    parser.add_argument("--json", type=Path, help="write the cases not ok here (JSON Lines)")
    parser.add_argument("--rerun", type=Path, help="rerun the cases of an earlier --json file")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    args = parser.parse_args()

    seed, indices, earlier, corpus = args.seed, range(args.count), {}, args.corpus
    if args.rerun:
        previous, cases = read_report(args.rerun)
        seed, corpus = previous["seed"], previous.get("corpus", "queries")
        earlier = {record["index"]: record["category"] for record in cases}
        indices = sorted(earlier)
    if args.timeout is None:
        args.timeout = TIMEOUT[corpus]
    start = time.monotonic()
    records = census(seed, indices, args.workers, args.timeout, not args.quiet, corpus)
    seconds = time.monotonic() - start
    print(f"corpus {corpus!r} seed {seed}, {len(records)} cases, timeout {args.timeout:g} s, "
          f"{args.workers} workers, {seconds:.0f} s\n")  # fmt: skip
    _, _, categories, failures = CORPORA[corpus]
    print(table(records, categories, failures))
    if earlier:
        moves = Counter((earlier[r["index"]], r["category"]) for r in records)
        print("\n| before | now | cases |\n|---|---|---:|")
        for (old, new), count in sorted(moves.items()):
            print(f"| {old} | {new} | {count} |")
    if args.json:
        write_report(args.json, seed, args.timeout, seconds, records, corpus)



if __name__ == "__main__":
    main()
