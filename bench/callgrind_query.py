"""Instructions per query, ours against coal's GJK and EPA, counted by callgrind.

Runs ``swarmcollide-callgrind-query`` (bench/callgrind_query.cpp, built with the coal benches)
once under ``valgrind --tool=callgrind --collect-atstart=no``; the binary turns collection on
around each contender's timed loop and dumps the counts under a label, and this script reads the
dumps and prints instructions per query and ours / coal (and the fcl method's distance and
verdict over the raw FCL calls it wraps, `fcl::distance` and `fcl::collide`). A second table sets
ours beside each of coal's GJK variants for distance and collide (its default, the bounding boxes'
centres as initial guess, Nesterov's acceleration, both: narrowphase_coal.cpp's, natively the
fastest is often one of the others) and over the variant counted fewest. Instruction counts do
not depend on the machine's load, so they compare contenders on a shared machine where
wall-clock cannot.

    .venv/bin/python bench/callgrind_query.py --binary build/bench/bench/swarmcollide-callgrind-query

With ``--curved`` it runs ``swarmcollide-callgrind-curved`` (bench/callgrind_curved.cpp) instead:
signed distances of curved shapes (bench/curved_coal.py's pairs of kinds) against coal's
primitives, apart and overlapping, one row per pair of kinds; a second table sets coal's GJK and
EPA tolerances (an absolute 1e-6 by default) to ours, 1e-9 of the pair's size, and prints ours
against coal at the same precision; a third asks ours for coal's absolute 1e-6 instead.

With ``--profile "n=8 overlap distance"`` it also prints where one row's instructions go: each
function's inclusive instructions per query for ours (``callgrind_annotate --inclusive=yes`` on
that row's dump, the library's functions and Eigen's left out), the largest first.

    .venv/bin/python bench/callgrind_query.py --sizes 8 --profile "n=8 overlap distance"
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path


def profile(dump: Path, calls: int, top: int) -> list[tuple[float, str]]:
    """The `top` largest inclusive costs per query in one callgrind dump, by function (the
    program's own, not the C and C++ libraries' or Eigen's). A binary with debug information
    splits a function's cost by the file each inlined line came from: the parts are summed."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", str(dump)],
                          check=True, capture_output=True, text=True).stdout
    totals: dict[str, int] = {}
    for line in text.splitlines():
        match = re.match(r"^\s*([\d,]+) \(\s*[\d.]+%\)\s+(?:[^\s:]*:(?!:))?(.*?) \[", line)
        if match is None:
            continue
        name = match.group(2).replace("(anonymous namespace)::", "")
        name = re.sub(r"\(.*", "", name).replace("swarmcollide::detail::", "")
        name = re.sub(r"^void ", "", name)
        if name.startswith(("std::", "Eigen::", "main", "(below main)", "0x", "__")) or not name:
            continue
        totals[name] = totals.get(name, 0) + int(match.group(1).replace(",", ""))
    ranked = sorted(totals.items(), key=lambda item: -item[1])
    return [(cost / calls, name) for name, cost in ranked[:top]]


def counts(binary: str, arguments: list[str], profiled: str | None = None,
           top: int = 25) -> dict[tuple[str, str, str, str], float]:
    """Instructions per query of each (workload, proximity, query, contender) the binary dumped
    (the workload is "n=N" for polytopes, "pair=KINDS" for curved shapes); with `profiled`
    ("WORKLOAD PROXIMITY QUERY [CONTENDER]", the contender ours unless named: ours_fcl, coal,
    ...), that row's largest functions for that contender are printed too."""
    with tempfile.TemporaryDirectory() as directory:
        out = Path(directory) / "callgrind.out"
        subprocess.run(
            [
                "valgrind",
                "--tool=callgrind",
                "--collect-atstart=no",
                f"--callgrind-out-file={out}",
                binary,
                *arguments,
            ],
            check=True,
            stdout=sys.stderr,
            stderr=subprocess.DEVNULL,
        )
        found = {}
        for dump in Path(directory).glob("callgrind.out*"):
            text = dump.read_text()
            label = re.search(r"^desc: Trigger: Client Request: (.*)$", text, re.MULTILINE)
            total = re.search(r"^(?:summary|totals): (\d+)", text, re.MULTILINE)
            if label is None or total is None:
                continue
            n, proximity, query, contender, calls = label.group(1).split()
            found[(n, proximity, query, contender)] = int(total.group(1)) / int(calls)
            if profiled is not None and (profiled.split() + ["ours"])[:4] == \
                    [n, proximity, query, contender]:
                print(f"{profiled}, {contender}: inclusive instructions per query")
                for cost, name in profile(dump, int(calls), top):
                    print(f"{cost:10.0f}  {name}")
                print()
        return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--binary", help="the driver (default: the polytope or curved one)")
    parser.add_argument("--curved", action="store_true",
                        help="curved shapes against coal's primitives (callgrind_curved.cpp)")
    parser.add_argument("--sizes", default="4,8,16,64")
    parser.add_argument("--pairs", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--gap", action="store_true",
                        help="also the pairs apart by 1e-2 (narrowphase_coal.cpp's \"gap 1e-2\")")
    parser.add_argument("--json", help="write the counts here")
    parser.add_argument("--profile", metavar="ROW",
                        help='also print where ours spends one row\'s instructions, by function '
                             '(e.g. "n=8 overlap distance"; a fourth word names another '
                             'contender: "n=4 overlap distance ours_fcl")')
    parser.add_argument("--top", type=int, default=25, help="functions --profile prints")
    args = parser.parse_args()
    driver = "swarmcollide-callgrind-curved" if args.curved else "swarmcollide-callgrind-query"
    binary = args.binary or f"build/bench/bench/{driver}"
    sizes = [] if args.curved else ["--sizes", args.sizes] + (["--gap"] if args.gap else [])
    found = counts(binary, [*sizes, "--pairs", str(args.pairs), "--repeats", str(args.repeats)],
                   args.profile, args.top)
    rows = []
    print(f"{'workload':>20} {'proximity':9} {'query':16} {'ours':>8} {'batch':>8} {'coal':>8} "
          f"{'ours/coal':>9} {'batch/coal':>10}")
    def order(key: tuple[str, str, str]) -> tuple:
        name, value = key[0].split("=")
        return (int(value) if name == "n" else 0, value, key[1], key[2])

    keys = sorted({key[:3] for key in found}, key=order)
    for workload, proximity, query in keys:
        ours = found.get((workload, proximity, query, "ours"))
        batch = found.get((workload, proximity, query, "ours_batch"))
        coal = found.get((workload, proximity, query, "coal"))
        name, value = workload.split("=")
        shape = {"vertices": int(value)} if name == "n" else {"shapes": value}
        row = {**shape, "proximity": proximity, "query": query, "ours": ours,
               "ours_batch_row": batch, "coal": coal}
        rows.append(row)

        def show(value: float | None) -> str:
            return f"{value:8.0f}" if value is not None else f"{'-':>8}"

        def ratio(value: float | None) -> str:
            return f"{value / coal:.2f}" if value is not None and coal else "-"

        print(f"{workload.split('=')[1]:>20} {proximity:9} {query:16} {show(ours)} {show(batch)} {show(coal)} "
              f"{ratio(ours):>9} {ratio(batch):>10}")
    def both(first: str, second: str):
        """(workload, proximity, query, first's count, second's count) wherever both contenders
        were counted."""
        for workload, proximity, query in keys:
            x = found.get((workload, proximity, query, first))
            y = found.get((workload, proximity, query, second))
            if x is not None and y is not None:
                yield workload.split("=")[1], proximity, query, x, y

    def print_ratios(title: str, key: str, rows: list[dict], top: str, bottom: str) -> None:
        """A table of `top`'s and `bottom`'s counts per row and their ratio, under `title`."""
        if not rows:
            return
        print(f"\n{title}\n{key:>20} {'proximity':9} {'query':16} {top:>22} {bottom:>22} "
              f"{'ratio':>6}")
        for row in rows:
            print(f"{row[key]!s:>20} {row['proximity']:9} {row['query']:16} {row[top]:22.0f} "
                  f"{row[bottom]:22.0f} {row[top] / row[bottom]:6.2f}")

    fcl_rows = [{"vertices": int(size), "proximity": proximity, "query": query,
                 "fcl_method": method, "fcl_direct": direct}
                for size, proximity, query, method, direct in both("ours_fcl", "fcl")]
    print_ratios("the fcl method against the raw FCL call it wraps:", "vertices", fcl_rows,
                 "fcl_method", "fcl_direct")
    variant_names = ["coal", "coal_box", "coal_nesterov", "coal_nesterov_box"]
    variant_rows = []
    for workload, proximity, query in keys:
        ours = found.get((workload, proximity, query, "ours"))
        variants = {name: found.get((workload, proximity, query, name))
                    for name in variant_names}
        if ours is None or any(count is None for count in variants.values()):
            continue
        fewest = min(variant_names, key=lambda name: variants[name])
        variant_rows.append({"vertices": int(workload.split("=")[1]), "proximity": proximity,
                             "query": query, "ours": ours, **variants,
                             "coal_fewest": fewest})
    if variant_rows:
        print("\nours against each of coal's GJK variants (narrowphase_coal.cpp's: natively the "
              "fastest is often the box guess or Nesterov's):")
        print(f"{'vertices':>8} {'proximity':9} {'query':9} {'ours':>8} "
              + " ".join(f"{name:>17}" for name in variant_names)
              + f" {'ours/fewest':>11} fewest")
        for row in variant_rows:
            fewest = row["coal_fewest"]
            print(f"{row['vertices']:8} {row['proximity']:9} {row['query']:9} {row['ours']:8.0f} "
                  + " ".join(f"{row[name]:17.0f}" for name in variant_names)
                  + f" {row['ours'] / row[fewest]:11.2f} {fewest}")
    matched_rows = [{"shapes": shapes, "proximity": proximity, "query": query, "ours": ours,
                     "coal_at_our_tolerance": matched}
                    for shapes, proximity, query, ours, matched in both("ours", "coal_matched")]
    print_ratios("coal at our tolerance (1e-9 of the pair's size, not its absolute 1e-6):",
                 "shapes", matched_rows, "ours", "coal_at_our_tolerance")
    coarse_rows = [{"shapes": shapes, "proximity": proximity, "query": query,
                    "ours_at_1e-6": coarse, "coal": coal}
                   for shapes, proximity, query, coarse, coal in both("ours_at_1e-6", "coal")]
    print_ratios("ours at coal's precision (an absolute 1e-6, as coal's defaults):", "shapes",
                 coarse_rows, "ours_at_1e-6", "coal")
    if args.json:
        rows += fcl_rows + variant_rows + matched_rows + coarse_rows
        Path(args.json).write_text(json.dumps({"pairs": args.pairs, "repeats": args.repeats,
                                               "instructions_per_query": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()
