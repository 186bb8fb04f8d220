"""The sections of bench/RESULTS.md from swarmcollide-bench's results (cpp.json): the paper's
tables, time against vertices, accuracy, verdicts, what a direct FCL user gets, every workload."""

from __future__ import annotations

import os
from collections import defaultdict
from typing import Dict, List, NamedTuple, Optional

import matplotlib

from markdown import fmt_err, fmt_time, machine_line, table

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PAPER_SECONDS = {"paper touching": {"penalty": 5.532, "ipso": 0.256},
                 "paper separate": {"penalty": 4.832, "ipso": 0.356}}
PROXIMITIES = ["apart", "gap 1e-1", "gap 1e-2", "gap 1e-3", "gap 1e-4", "overlap 1e-4",
               "overlap 1e-3", "overlap 1e-2", "overlap 1e-1"]


class RowNames(NamedTuple):
    """The rows of a run in the binary's order: those with a distance, then the verdict-only."""

    distance: List[str]
    verdict: List[str]

    @property
    def all(self) -> List[str]:
        return self.distance + self.verdict


def load_cpp(data: dict):
    """The context, {(row, workload): cell} from the median, min and max aggregates of Google
    Benchmark's rows, and the row names."""
    cells: Dict[tuple, dict] = defaultdict(dict)
    for b in data["rows"]:
        key = tuple(b["run_name"].split("/")[0].split("|"))
        cell = cells[key]
        if b.get("error_occurred"):
            cell["error"] = b.get("error_message", "skipped")
            continue
        if b.get("run_type") != "aggregate":
            continue
        scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[b["time_unit"]]
        per_query = b["real_time"] * scale / b["pairs"] if b.get("pairs") else None
        name = b["aggregate_name"]
        if name in ("median", "min", "max"):
            cell[f"time_{name}_us"] = per_query
        if name == "median":
            for k, v in b.items():
                if isinstance(v, float) and k not in ("real_time", "cpu_time"):
                    cell[k] = v
            if b.get("label"):
                cell["label"] = b["label"]
    order = list(dict.fromkeys(row for row, _ in cells))
    with_distance = {row for (row, _), c in cells.items() if c.get("has_distance")}
    names = RowNames([r for r in order if r in with_distance],
                     [r for r in order if r not in with_distance])
    return data["context"], cells, names


def spread(cell: dict) -> str:
    lo, hi, med = cell.get("time_min_us"), cell.get("time_max_us"), cell.get("time_median_us")
    if not med or lo is None or hi is None:
        return ""
    return f"±{100 * max(hi - med, med - lo) / med:.0f}%"


def workload_name(n: int, proximity: str) -> str:
    return f"n={n} {proximity}"


def time_cell(cell: Optional[dict]) -> str:
    if not cell:
        return "not run"
    if "error" in cell:
        return f"cannot: {cell['error']}"
    text = fmt_time(cell.get("time_median_us"))
    if cell.get("pairs", 0) < cell.get("of_pairs", 0):
        text += f" ({cell['pairs']:.0f}/{cell['of_pairs']:.0f} pairs)"
    return text


def accuracy_cell(cell: Optional[dict]) -> str:
    """'within/separated, max error, wrong verdicts' for a distance row."""
    if not cell or "error" in cell:
        return "not run"
    parts = []
    if cell.get("evaluations_mean"):
        parts.append(f"{cell['iterations_mean']:.0f} it")
    if cell.get("has_distance"):
        if cell.get("separated", 0) > 0:
            parts.append(f"{cell['within_1e-6']:.0f}/{cell['separated']:.0f}")
        parts.append(f"max {fmt_err(cell['error_max'])}")
    else:
        parts.append("no distance")
    if cell.get("wrong_verdicts", 0):
        parts.append(f"**{cell['wrong_verdicts']:.0f} wrong**")
    return ", ".join(parts)


def sizes_in(cells) -> List[int]:
    sizes = set()
    for _, w in cells:
        if w.startswith("n="):
            sizes.add(int(w.split()[0][2:]))
    return sorted(sizes)


def proximities_in(cells) -> List[str]:
    present = {w.split(" ", 1)[1] for _, w in cells if w.startswith("n=")}
    return [p for p in PROXIMITIES if p in present]


def paper_section(names: "RowNames", cells) -> str:
    rows = []
    for row in names.all:
        r = [row]
        for w in ("paper touching", "paper separate"):
            c = cells.get((row, w))
            if not c:
                r += ["not run", ""]
                continue
            dist = ""
            if c.get("has_distance"):
                dist = f"err {fmt_err(c['error_max'])}"
                if c.get("evaluations_mean"):
                    dist += f", {c['iterations_mean']:.0f} it, {c['evaluations_mean']:.0f} evals"
            if c.get("wrong_verdicts"):
                dist += (", " if dist else "") + "**wrong verdict**"
            if not dist:
                dist = "right verdict"
            r += [f"{fmt_time(c.get('time_median_us'))} {spread(c)}", dist]
        rows.append(r)
    rows.append(["*paper: penalty*", "5.532 s", "2.54e-33 (its λ₂ = 1.0281 is infeasible)",
                 "4.832 s", "0.9855 (true: 1)"])
    rows.append(["*paper: improved PSO*", "0.256 s", "1.33e-35", "0.356 s", "1.0000"])
    text = table(["method", "touching: time/query", "touching: answer",
                  "separate: time/query", "separate: answer"], rows)
    speedups = []
    for w in ("paper touching", "paper separate"):
        c = cells.get(("ipso projection", w))
        if c and c.get("time_median_us"):
            speedups.append(f"{w}: {PAPER_SECONDS[w]['ipso'] / (c['time_median_us'] * 1e-6):,.0f}x")
    if speedups:
        text += ("\n\nipso (projection) against the paper's 0.256 s / 0.356 s: "
                 + "; ".join(speedups) + " faster (different machine and language; the paper's "
                 "timing set-up is not described).")
    return text


def headline_proximity(proximities: List[str]) -> str:
    """The proximity of the headline table and plot: 1e-2 apart, or the nearest one run."""
    gaps = [p for p in proximities if p.startswith("gap")]
    return "gap 1e-2" if "gap 1e-2" in gaps else (gaps[0] if gaps else proximities[0])


def headline_section(names: "RowNames", cells, sizes, proximity) -> str:
    rows = []
    for row in names.all:
        r = [row]
        for n in sizes:
            r.append(time_cell(cells.get((row, workload_name(n, proximity)))))
        rows.append(r)
    fcl_row = next((r for r in names.distance if r == "fcl" or r.startswith("fcl (")), "fcl")
    ratio = [f"*{fcl_row} method / FCL distance direct*"]
    for n in sizes:
        ours = cells.get((fcl_row, workload_name(n, proximity)), {})
        theirs = cells.get(("FCL distance direct", workload_name(n, proximity)), {})
        if ours.get("time_median_us") and theirs.get("time_median_us"):
            ratio.append(f"{ours['time_median_us'] / theirs['time_median_us']:.2f}x")
        else:
            ratio.append("n/a")
    rows.append(ratio)
    return table(["method \\ vertices per body"] + [str(n) for n in sizes], rows)


def fcl_wrap_section(names: "RowNames", cells, sizes, proximities) -> str:
    """The fcl method's distance, verdict and signed distance over the FCL calls they wrap, at
    every proximity and size (issue 25 asks at most 1.1x)."""
    fcl_row = next((r for r in names.distance if r == "fcl" or r.startswith("fcl (")), "fcl")
    wrapped = [(fcl_row, "FCL distance direct"), ("collide fcl", "FCL collide direct"),
               ("signed fcl", "FCL signed distance direct")]
    rows = []
    for proximity in proximities:
        row = [proximity]
        for n in sizes:
            parts = []
            for ours_row, theirs_row in wrapped:
                ours = cells.get((ours_row, workload_name(n, proximity)), {})
                theirs = cells.get((theirs_row, workload_name(n, proximity)), {})
                if ours.get("time_median_us") and theirs.get("time_median_us"):
                    parts.append(f"{ours['time_median_us'] / theirs['time_median_us']:.2f}")
                else:
                    parts.append("–")
            row.append(" / ".join(parts))
        rows.append(row)
    return table(["proximity \\ vertices per body"] + [str(n) for n in sizes], rows)


FCL_RATIO = (
    "`swarmcollide-fcl-ratio` (bench/fcl_ratio.cpp): the same three ratios as the last table of "
    "the time section, on the same pairs and FCL calls, but timed in turns: each round times "
    "the fcl method's call and the FCL call it wraps back to back over the workload's 20 pairs "
    "(a turn lasts at least 2 ms; the order alternates from round to round), and a cell is the "
    "median over 21 rounds of each round's ratio. swarmcollide-bench times every row on its "
    "own, one after another, so that its ratios divide medians taken minutes apart on a shared "
    "machine (cells moved by up to a third between two of its runs, bench/README.md session "
    "67); these are issue 25's figures for its third item (at most 1.1x).")


def fcl_ratio_section(data: dict) -> str:
    """The fcl method over the FCL calls it wraps, timed in turns (fcl_ratio.cpp)."""
    rows = data["rows"]
    sizes = sorted({r["vertices"] for r in rows})
    proximities = list(dict.fromkeys(r["proximity"] for r in rows))
    cell = {(r["vertices"], r["proximity"], r["query"]): r for r in rows}
    queries = ("distance", "collide", "signed distance")
    body = [[proximity] + [" / ".join("–" if (n, proximity, q) not in cell else
                                      f"{cell[n, proximity, q]['ratio']:.2f}" for q in queries)
                           for n in sizes]
            for proximity in proximities]
    above = [f"{r['vertices']} vertices {r['proximity']} {r['query']} {r['ratio']:.2f} "
             f"({r['ratio_min']:.2f}-{r['ratio_max']:.2f})" for r in rows if r["ratio"] > 1.1]
    return "\n".join([
        machine_line(data), "",
        "The fcl method over FCL's call, distance / verdict / signed distance (the signed "
        "distance on pairs apart only), the median over rounds of each round's ratio:", "",
        table(["proximity \\ vertices per body"] + [str(n) for n in sizes], body), "",
        "Above 1.1x (the least and the largest round's ratio in brackets): "
        + ("; ".join(above) if above else "none") + ".", "",
        f"Uncertified answers of the fcl method over all pairs (distance, verdict and signed "
        f"distance of each): {data.get('uncertified', 'not recorded')}."])


def measured(cells, row: str, n: int, proximities) -> List[dict]:
    """The cells of a row that ran, over the workloads of size n at these proximities."""
    found = (cells.get((row, workload_name(n, p))) for p in proximities)
    return [c for c in found if c and "error" not in c]


def accuracy_section(names: "RowNames", cells, sizes, proximities) -> str:
    """Separated pairs within 1e-6 over every 'apart'/'gap' workload, and the worst error."""
    rows = []
    for row in names.distance:
        r = [row]
        for n in sizes:
            done = measured(cells, row, n, proximities)
            within = sum(c.get("within_1e-6", 0) for c in done)
            separated = sum(c.get("separated", 0) for c in done)
            worst = max([c.get("error_max", 0) for c in done], default=0.0)
            wrong = sum(c.get("wrong_verdicts", 0) for c in done)
            text = f"{within:.0f}/{separated:.0f}, max {fmt_err(worst)}"
            if wrong:
                text += f", {wrong:.0f} wrong verdicts"
            r.append(text)
        rows.append(r)
    return table(["method \\ vertices per body"] + [str(n) for n in sizes], rows)


def verdict_section(names: "RowNames", cells, sizes, proximities) -> str:
    rows = []
    for row in names.all:
        r = [row]
        for n in sizes:
            done = measured(cells, row, n, proximities)
            wrong = sum(c.get("wrong_verdicts", 0) for c in done)
            total = sum(c.get("pairs", 0) for c in done)
            r.append(f"{wrong:.0f}/{total:.0f}")
        rows.append(r)
    return table(["method \\ vertices per body"] + [str(n) for n in sizes], rows)


def raw_fcl_section(names: "RowNames", cells, sizes, proximities) -> str:
    probed = [r for r in names.distance
              if any(c.get("raw_fcl_aborts", -1) >= 0 for (row, _), c in cells.items() if row == r)]
    rows = []
    for row in probed:
        r = [f"FCL called directly, as in `{row}`"]
        for n in [0] + sizes:
            ws = (["paper touching", "paper separate"] if n == 0
                  else [workload_name(n, p) for p in proximities])
            aborts = wrong = total = 0
            for w in ws:
                c = cells.get((row, w))
                if c and c.get("raw_fcl_aborts", -1) >= 0:
                    aborts += c["raw_fcl_aborts"]
                    wrong += c["raw_fcl_wrong"]
                    total += c["pairs"]
            r.append(f"{aborts:.0f} aborts, {wrong:.0f} wrong / {total:.0f}")
        rows.append(r)
    return table(["", "paper pairs"] + [f"n={n}" for n in sizes], rows)


def per_size_sections(names: "RowNames", cells, sizes, proximities) -> str:
    out = []
    for n in sizes:
        out.append(f"#### n = {n}\n")
        rows = []
        for row in names.all:
            r = [row]
            for p in proximities:
                c = cells.get((row, workload_name(n, p)))
                r.append(f"{time_cell(c)} {spread(c) if c else ''}<br>{accuracy_cell(c)}")
            rows.append(r)
        out.append(table(["method"] + proximities, rows))
        out.append("")
    return "\n".join(out)


def timing_plot(names: "RowNames", cells, sizes, proximity, path: str) -> None:
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for row in names.distance + ["FCL collide", "libccd GJK intersect"]:
        xs, ys = [], []
        for n in sizes:
            c = cells.get((row, workload_name(n, proximity)))
            if c and c.get("time_median_us"):
                xs.append(n)
                ys.append(c["time_median_us"])
        if xs:
            style = "--" if row in names.verdict else "-"
            ax.plot(xs, ys, style, marker="o", label=row)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("vertices per body")
    ax.set_ylabel("median time per query (µs)")
    ax.set_title(f"Random convex polytope pairs, {proximity}")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def limited_pairs(cells) -> List[str]:
    """Pair-limited cells by method and size: "ipso projection: 3 of 20 pairs at n=4096"."""
    groups: Dict[tuple, set] = defaultdict(set)
    for (r, w), c in cells.items():
        if c.get("pairs", 0) < c.get("of_pairs", 0):
            groups[(r, w.split()[0], int(c["pairs"]), int(c["of_pairs"]))].add(w.split(" ", 1)[1])
    return [f"{r}: {k} of {m} pairs at {size} ({len(ps)} proximities)"
            for (r, size, k, m), ps in sorted(groups.items())]


def cpp_sections(data: dict, plots: str, plots_rel: str) -> List[str]:
    """The header of RESULTS.md and the sections of cpp.json, up to the Python ones."""
    context, cells, names = load_cpp(data)
    sizes = sizes_in(cells)
    proximities = proximities_in(cells)
    separated = [p for p in proximities if not p.startswith("overlap")]
    headline = headline_proximity(proximities)
    timing_plot(names, cells, sizes, headline, os.path.join(plots, "time_vs_vertices.png"))
    md = [
        f"- Made by {machine_line(data)}",
        f"- Compiler: {context.get('compiler')}, Release build; mode: {context.get('mode')}",
        "- Timing: Google Benchmark; one benchmark iteration answers every pair of the workload "
        "once, with the bodies (and FCL/libccd shapes) and the seeded queries built beforehand; "
        "warm-up, then repetitions (9 of at least 0.03 s each; 3 for a row whose single pass "
        "takes over a second; 3 with `--quick`); a cell is the median over repetitions divided "
        "by the number of pairs, ± the largest distance from the median to the fastest or "
        "slowest repetition. Queries are seeded with the pair's index, so every repetition "
        "repeats the same work.",
        f"- Accuracy: against {context.get('reference')}. `a/b` = separated pairs whose distance "
        "is within 1e-6 of the reference / separated pairs; `max` = the largest |distance - "
        "reference| (0 for overlapping pairs means the method reported 0); wrong = collision "
        "verdicts that disagree with the reference. Every method runs at the library's "
        "defaults (the swarms at the paper's budget, 40 particles and 200 iterations).",
        "- Workloads: the paper's two tetrahedron pairs; random convex polytopes (n points on the "
        "unit sphere, the hull's vertices) with B moved along a random ray from A's centroid "
        "until FCL's signed distance is the target (`gap 1e-2`: 1e-2 apart; `overlap 1e-2`: "
        "penetration depth 1e-2), 20 pairs each (5 with `--quick`), fixed seeds.",
        "- The Debian libbenchmark is reported as a debug build; that is the harness library "
        "itself, not the code under test (built with -O3 -DNDEBUG).",
        "",
    ]
    limited = limited_pairs(cells)
    if limited:
        md += ["Fewer pairs where a method is too slow for the full set (said so in every cell "
               "concerned):", ""] + [f"- {x}" for x in limited] + [""]
    md += [
        "## The paper's Tables 1 and 2, rerun", "", paper_section(names, cells), "",
        f"## Time per query against the number of vertices (pairs: {headline})", "",
        headline_section(names, cells, sizes, headline), "",
        "`FCL distance direct` calls `fcl::distance` on `fcl::Convexd` shapes built once, outside "
        "the timed loop; swarmcollide's FCL method runs FCL's GJK on the pair in its normalised "
        "frame and then checks FCL's answer with its own bound, so the ratio row is the price "
        "of that framing and check.", "",
        f"![time per query]({plots_rel}/time_vs_vertices.png)", "",
        "The fcl method over the FCL calls it wraps at every proximity: distance over `FCL "
        "distance direct`, verdict (`collide fcl`) over `FCL collide direct` (`fcl::collide`, "
        "GST_INDEP, which runs FCL's EPA on overlapping pairs, contacts or not), signed distance "
        "over `FCL signed distance direct` (timed on separated pairs only: FCL's EPA asserts on "
        "some overlapping ones). Our verdict first tests the bodies' outer balls and the centres' "
        "line, which settle most pairs apart without FCL's GJK. The rows are timed one after "
        "another, minutes apart: the section \"The fcl method against the FCL calls it wraps, in "
        "turns\" below times the same ratios in turns, round by round, and is the one to read.",
        "",
        fcl_wrap_section(names, cells, sizes, proximities), "",
        "## Accuracy at the paper's budget (all separated workloads of each size)", "",
        accuracy_section(names, cells, sizes, separated), "",
        "## Wrong collision verdicts (all workloads of each size)", "",
        verdict_section(names, cells, sizes, proximities), "",
        "A distance row calls a pair colliding when its answer does (within the method's "
        "tolerance, or not proven apart). `collide libccd` is swarmcollide's `collide` with "
        "method libccd; `FCL collide` and the libccd rows call those libraries directly, as "
        "their users would.", "",
        "## Crashes and wrong answers routed around", "",
        "What a direct FCL user gets on the same pairs (unsigned and signed distance, each pair "
        "in a child process so an abort is counted rather than fatal). swarmcollide's FCL "
        "method answers every one of these pairs (see the accuracy tables).", "",
        raw_fcl_section(names, cells, sizes, proximities), "",
    ]
    return md


def every_workload_section(data: dict) -> List[str]:
    _, cells, names = load_cpp(data)
    return ["## Every workload", "", "Each cell: time per query, then accuracy as above.", "",
            per_size_sections(names, cells, sizes_in(cells), proximities_in(cells))]
