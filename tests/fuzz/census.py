"""The fuzz census: every case of a corpus in a sandboxed child, counted by category.

Prints a Markdown table of counts per query and method and writes a JSON Lines file with every
case that is not "ok" (its id, category and reason), so that a fix can be checked case by case:

    .venv/bin/python tests/fuzz/census.py --json build/fuzz/census.jsonl   # 10000 cases
    .venv/bin/python tests/fuzz/census.py --rerun tests/fuzz/before.jsonl  # old -> new per case
    .venv/bin/python tests/fuzz/census.py --surface scene --count 200     # scenes

The categories are those of tests/python/fuzz_judge.py; the cases those of fuzz_cases.py, or with
``--surface scene`` those of scene_cases.py: every broadphase through long seeded motions against
brute force, every method's certified rows against exact distances, bodies far from the origin,
and bad arguments (a case whose error does not name its argument counts as "error-type").
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any, Dict, Iterable, List, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))

from fuzz_cases import make_case  # noqa: E402
from fuzz_judge import CATEGORIES, FAILURES, category_of, run_case  # noqa: E402
from sandbox import Sandbox  # noqa: E402
from scene_cases import run_scene_case, scene_case  # noqa: E402

Record = Dict[str, Any]


def describe(surface: str, seed: int, index: int) -> Record:
    """What case ``index`` of ``surface`` is: id, index, family, query, method, note."""
    if surface == "scene":
        family, query, label, arguments = scene_case(seed, index)
        return {"id": f"scene-{seed}-{index}", "index": index, "family": family, "query": query,
                "method": label, "note": repr(arguments)}  # fmt: skip
    case = make_case(seed, index)
    return {"id": case.id, "index": index, "family": case.family, "query": case.query,
            "method": case.label, "note": case.note}  # fmt: skip


def census(
    seed: int, indices: Iterable[int], workers: int, timeout: float, progress: bool,
    surface: str = "pairs",
) -> List[Record]:
    """One record per case: id, index, family, query, method, note, category, reason."""
    records = []
    start = time.monotonic()
    judge = run_scene_case if surface == "scene" else run_case
    tasks = ((index, judge, (seed, index)) for index in indices)
    preload = ("scene_cases",) if surface == "scene" else ("fuzz_judge",)
    with Sandbox(parallel=workers, preload=preload) as sandbox:
        for index, outcome in sandbox.map(tasks, timeout=timeout):
            category, reason = category_of(outcome)
            records.append({**describe(surface, seed, index), "category": category,
                            "reason": reason})  # fmt: skip
            if progress and len(records) % 100 == 0:
                counts = Counter(r["category"] for r in records)
                print(f"{len(records)} cases, {time.monotonic() - start:.0f} s: {dict(counts)}",
                      file=sys.stderr, flush=True)  # fmt: skip
    return sorted(records, key=lambda r: r["index"])


def table(records: List[Record]) -> str:
    """Counts per (query, method) and category, as Markdown."""
    counts: Dict[Tuple[str, str], Counter] = {}
    for record in records:
        counts.setdefault((record["query"], record["method"]), Counter())[record["category"]] += 1
    total = Counter(record["category"] for record in records)
    lines = [
        "| query | method | cases | " + " | ".join(CATEGORIES) + " |",
        "|---|---|---:|" + "---:|" * len(CATEGORIES),
    ]
    for (query, method), row in sorted(counts.items()):
        cells = " | ".join(str(row[c]) for c in CATEGORIES)
        lines.append(f"| {query} | {method} | {sum(row.values())} | {cells} |")
    cells = " | ".join(f"**{total[c]}**" for c in CATEGORIES)
    lines.append(f"| **all** | | **{len(records)}** | {cells} |")
    failing = sum(total[c] for c in FAILURES)
    lines.append(f"\n{failing} of {len(records)} cases fail ({', '.join(sorted(FAILURES))}).")
    return "\n".join(lines)


def write_report(
    path: Path, seed: int, timeout: float, seconds: float, records: List[Record]
) -> None:
    """JSON Lines: the run (seed, counts) first, then every case that is not ok, one a line."""
    path.parent.mkdir(parents=True, exist_ok=True)
    header = {
        "seed": seed, "count": len(records), "timeout": timeout, "seconds": round(seconds),
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
    parser.add_argument("--seed", type=int, default=0, help="the corpus (default 0)")
    parser.add_argument("--surface", choices=("pairs", "scene"), default="pairs",
                        help="pair queries (fuzz_cases.py) or scenes (scene_cases.py)")
    parser.add_argument("--count", type=int, default=10000, help="cases 0 .. count-1")
    parser.add_argument("--workers", type=int, default=2, help="children at once")
    parser.add_argument("--timeout", type=float, help="seconds before a hang (20; scenes 600)")
    parser.add_argument("--json", type=Path, help="write the cases not ok here (JSON Lines)")
    parser.add_argument("--rerun", type=Path, help="rerun the cases of an earlier --json file")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    args = parser.parse_args()

    seed, indices, earlier = args.seed, range(args.count), {}
    if args.rerun:
        previous, cases = read_report(args.rerun)
        seed = previous["seed"]
        earlier = {record["index"]: record["category"] for record in cases}
        indices = sorted(earlier)
    if args.timeout is None:
        args.timeout = 600.0 if args.surface == "scene" else 20.0
    start = time.monotonic()
    records = census(seed, indices, args.workers, args.timeout, not args.quiet, args.surface)
    seconds = time.monotonic() - start
    print(f"corpus seed {seed}, {len(records)} cases, timeout {args.timeout:g} s, "
          f"{args.workers} workers, {seconds:.0f} s\n")  # fmt: skip
    print(table(records))
    if earlier:
        moves = Counter((earlier[r["index"]], r["category"]) for r in records)
        print("\n| before | now | cases |\n|---|---|---:|")
        for (old, new), count in sorted(moves.items()):
            print(f"| {old} | {new} | {count} |")
    if args.json:
        write_report(args.json, seed, args.timeout, seconds, records)



if __name__ == "__main__":
    main()
