"""The scene section of bench/RESULTS.md, from scene.json (C++) and scene_python.json (Python).

    python bench/scene_report.py --results bench/results   # prints the section
"""

from __future__ import annotations

import argparse
import os
from typing import Dict, List, Optional, Tuple

from markdown import machine_line, table
from record import load

TARGET_SPEEDUP_WARM = 5
TARGET_WARM_1000_MS = 11
TARGET_PYTHON_SPEEDUP = 10


def by_key(rows: List[dict]) -> Dict[Tuple[str, int, str], dict]:
    return {(r["contender"], r["n"], r["frame"]): r for r in rows}


def ms(row: Optional[dict], field: str = "median_s") -> str:
    return "—" if row is None else f"{1e3 * row[field]:.2f}"


def cell(row: Optional[dict]) -> str:
    """Wall-clock median (CPU-time median) in milliseconds."""
    return "—" if row is None else f"{ms(row)} ({ms(row, 'median_cpu_s')})"


def ratio(slow: Optional[dict], fast: Optional[dict], field: str = "median_cpu_s") -> float:
    if slow is None or fast is None or fast[field] <= 0:
        return float("nan")
    return slow[field] / fast[field]


def settled(row: dict) -> str:
    parts = [("screened", "screened"), ("warm_bounded", "bounded"),
             ("warm_rejected", "rejected"), ("warm_proven", "proven"), ("solved", "solved")]
    return ", ".join(f"{row.get(k, 0)} {name}" for k, name in parts)


def cpp_section(data: dict) -> Tuple[str, Dict]:
    rows = by_key(data["rows"])
    context = data["context"]
    sizes = sorted({r["n"] for r in data["rows"]})
    out = [
        "### C++: `swarmcollide-scene-bench`",
        "",
        f"Load average before/after: {context['load_before']} / {context['load_after']}; "
        f"{context['cold_repeats']} cold frames, {context['warm_frames']} warm frames "
        f"(each contender in turn, on the same poses; mode {context['mode']}). Cells: median "
        "wall-clock ms (median CPU ms of the process). The FCL contender sets each object's "
        "transform, updates its DynamicAABBTree manager and runs `fcl::collide` (GJK, FCL's "
        "default solver) in the manager's callback; the scene runs `set_poses` and "
        "`colliding_pairs()` (its answers certified).",
        "",
    ]
    header = ["N", "frame", "FCL manager + GJK", "scene, 1 thread", "scene, 2 threads",
              "FCL / scene (CPU, 1 thread)", "colliding pairs (FCL / scene)",
              "candidates (FCL / scene)", "scene: certified / candidates", "scene: settled",
              "escalations", "bytes per cached pair"]
    body = []
    for n in sizes:
        for frame in ("cold", "warm"):
            fcl = rows.get(("fcl_manager_gjk", n, frame))
            one = rows.get(("scene_1_thread", n, frame))
            two = rows.get(("scene_2_threads", n, frame))
            if one is None:
                continue
            body.append([
                f"{n:,}", frame, cell(fcl), cell(one), cell(two), f"{ratio(fcl, one):.1f}x",
                f"{fcl['pairs'] if fcl else '—'} / {one['pairs']}",
                f"{fcl['candidates'] if fcl else '—'} / {one['candidates']}",
                f"{one['certified']} / {one['candidates']}", settled(one),
                str(one["escalations"]),
                f"{one['cache_bytes'] / max(one['cached_pairs'], 1):.0f}",
            ])
    out.append(table(header, body))
    within_rows = []
    for n in sizes:
        fcl = rows.get(("fcl_inflated_distance", n, "within"))
        one = rows.get(("scene_1_thread", n, "within"))
        two = rows.get(("scene_2_threads", n, "within"))
        if fcl and one:
            within_rows.append([f"{n:,}", cell(fcl), cell(one), cell(two),
                                f"{ratio(fcl, one):.1f}x", f"{fcl['pairs']} / {one['pairs']}",
                                f"{fcl['candidates']} / {one['candidates']}"])
    if within_rows:
        out += ["", "`pairs_within(0.1)` on a fresh scene against FCL's manager on its own boxes "
                "padded by 0.05 with `fcl::distance` per candidate:", "",
                table(["N", "FCL inflated boxes + distance", "scene, 1 thread",
                       "scene, 2 threads", "FCL / scene (CPU)", "pairs (FCL / scene)",
                       "candidates (FCL / scene)"], within_rows)]
    return "\n".join(out), rows


def python_section(data: dict) -> Tuple[str, Dict]:
    rows = by_key(data["rows"])
    sizes = sorted({r["n"] for r in data["rows"]})
    names = [("python_fcl_counting", "python-fcl, counting callback"),
             ("python_fcl_collide", "python-fcl, fcl.collide in the callback"),
             ("trimesh", "trimesh CollisionManager"),
             ("scene_1_thread", "sc.Scene, 1 thread"), ("scene_2_threads", "sc.Scene, 2 threads")]
    out = [
        "### Python: `bench/scene.py`",
        "",
        f"Made by {machine_line(data)} A frame sets every pose (python-fcl: "
        "`setTransform` per object, then `update()`; trimesh: `set_transform` per object; "
        "sc.Scene: one `set_poses` with an (N, 4, 4) array) and asks for the colliding pairs "
        "(python-fcl counting: only counts the manager's candidate pairs in a Python callback).",
        "",
    ]
    body = []
    for n in sizes:
        for frame in ("cold", "warm"):
            line = [f"{n:,}", frame] + [cell(rows.get((key, n, frame))) for key, _ in names]
            line.append(f"{ratio(rows.get(('python_fcl_counting', n, frame)), rows.get(('scene_1_thread', n, frame))):.1f}x")
            body.append(line)
    out.append(table(["N", "frame"] + [label for _, label in names]
                     + ["python-fcl counting / sc.Scene 1 thread (CPU)"], body))
    return "\n".join(out), rows


def targets_section(cpp: Dict, py: Optional[Dict]) -> str:
    lines = []

    def verdict(ok: bool) -> str:
        return "met" if ok else "**not met**"

    for n in (1000, 10000):
        fcl_cold = cpp.get(("fcl_manager_gjk", n, "cold"))
        fcl_warm = cpp.get(("fcl_manager_gjk", n, "warm"))
        one_cold = cpp.get(("scene_1_thread", n, "cold"))
        one_warm = cpp.get(("scene_1_thread", n, "warm"))
        if not (fcl_cold and one_cold and fcl_warm and one_warm):
            continue
        # FCL has no warm start: its per-frame cost is its warm frame (the manager kept).
        reference = min(fcl_cold["median_cpu_s"], fcl_warm["median_cpu_s"])
        certified = one_cold["certified"] == one_cold["candidates"]
        lines.append([f"cold `colliding_pairs()` no slower than FCL manager + GJK, certifying "
                      f"every pair (N = {n:,})",
                      f"{1e3 * one_cold['median_cpu_s']:.2f} ms vs FCL {1e3 * reference:.2f} ms "
                      f"(CPU); {one_cold['certified']}/{one_cold['candidates']} certified",
                      verdict(one_cold["median_cpu_s"] <= reference and certified)])
        speedup = reference / one_warm["median_cpu_s"]
        lines.append([f"warm frame >= {TARGET_SPEEDUP_WARM}x faster than FCL (N = {n:,})",
                      f"{1e3 * one_warm['median_cpu_s']:.2f} ms vs {1e3 * reference:.2f} ms: "
                      f"{speedup:.1f}x", verdict(speedup >= TARGET_SPEEDUP_WARM)])
        if n == 1000:
            lines.append([f"N = 1,000 warm within {TARGET_WARM_1000_MS} ms",
                          f"{1e3 * one_warm['median_s']:.2f} ms wall",
                          verdict(1e3 * one_warm["median_s"] <= TARGET_WARM_1000_MS)])
    if py:
        counting = py.get(("python_fcl_counting", 1000, "warm"))
        ours = py.get(("scene_1_thread", 1000, "warm"))
        if counting and ours:
            speedup = counting["median_cpu_s"] / ours["median_cpu_s"]
            lines.append([f"from Python >= {TARGET_PYTHON_SPEEDUP}x faster than python-fcl's "
                          "manager with a counting callback (N = 1,000, warm frame)",
                          f"{1e3 * ours['median_cpu_s']:.2f} ms vs "
                          f"{1e3 * counting['median_cpu_s']:.2f} ms: {speedup:.1f}x",
                          verdict(speedup >= TARGET_PYTHON_SPEEDUP)])
    fcl_within = cpp.get(("fcl_inflated_distance", 10000, "within"))
    one_within = cpp.get(("scene_1_thread", 10000, "within"))
    if fcl_within and one_within:
        lines.append(["`pairs_within(0.1)` at N = 10,000 at most FCL's inflated-box approach",
                      f"{1e3 * one_within['median_cpu_s']:.1f} ms vs "
                      f"{1e3 * fcl_within['median_cpu_s']:.1f} ms (CPU)",
                      verdict(one_within["median_cpu_s"] <= fcl_within["median_cpu_s"])])
    return table(["target (one thread)", "measured", "verdict"], lines)


def scene_section(results: str) -> Optional[str]:
    """The whole section, or None without scene.json."""
    cpp = load(os.path.join(results, "scene.json"))
    if cpp is None:
        return None
    py = load(os.path.join(results, "scene_python.json"))
    cpp_text, cpp_rows = cpp_section(cpp)
    parts = [
        "## Scenes: many moving bodies",
        "",
        "N unit-size 8-vertex hulls (8 random points on the sphere of radius 1/2, so every point "
        "is a vertex), random rotations, positions uniform in a cube holding 2.85 bodies per "
        "unit volume: each body collides with 3-4 others. A cold frame builds everything from "
        "nothing; warm frames move every body by a Gaussian step (deviation 0.004 per axis) and "
        "turn it by 0.01 rad. Speed-ups are ratios of CPU time inside one run (the machine is "
        "shared, so wall-clock times carry other jobs' load).",
        "",
        targets_section(cpp_rows, None if py is None else by_key(py["rows"])),
        "",
        cpp_text,
    ]
    if py is not None:
        py_text, _ = python_section(py)
        parts += ["", py_text]
    return "\n".join(parts) + "\n"


CONTACTS = (
    "`bench/contacts.py`: convex hulls of pybullet_data's named object meshes (duck, teddy, "
    "bunny, mug, ...) and of its random objects, centred on their boxes and scaled to radii in "
    "[0.3, 0.6], drifting and turning in a cube of 2.5 bodies per unit volume. Each frame every "
    "contender runs in turn on the same poses: the scene's `set_poses` and `contacts()`; MuJoCo's "
    "qpos written, `mj_kinematics` and `mj_collision` (free bodies, one mesh geom each, with "
    "and without `multiccd`); coal's transforms set from Python, its DynamicAABBTree updated and "
    "its default callback running GJK and EPA with contacts in C++. Ratios are of median CPU "
    "time per frame inside the run. Each peer contact is checked against the scene's certified "
    "signed distance and normal: outliers are depths off by more than the tolerance times the "
    "smaller radius, normals more than the angle off, and normals along which the bodies' gap "
    "(from the hulls' vertices) is off the signed distance by more than the tolerance.")


CONTACTS_PILE = (
    "`bench/contacts.py --scene pile`: the same hulls dropped in a grid on a floor slab (one more "
    "hull, 8 vertices) and left to settle under MuJoCo's own simulation (300 steps of 4 ms, "
    "`multiccd` on); the frames are its next steps, two apart. Faces rest on the floor and on "
    "each other: the contacts a physics loop asks for every step, with manifolds of several "
    "points. The bodies barely move from frame to frame, which suits the scene's warm frames "
    "(see the drifting scene above for bodies that move). Timed and checked as above; each "
    "peer's deepest contact per pair is checked.")


def contacts_section(data: dict) -> str:
    """The contacts table of contacts.json."""
    context = data["context"]
    header = ["contender", "median ms (CPU)", "swarmcollide 1 thread / this (CPU; above 1: ours slower)", "pairs",
              "depth outliers", "angle outliers", "normal outliers", "largest depth error",
              "largest angle (deg)"]
    body = []
    for r in data["rows"]:
        ours = r["contender"].startswith("swarmcollide")
        body.append([
            r["contender"], f"{r['median_ms']:.2f} ({r['median_cpu_ms']:.2f})",
            f"{r['ours_over_this_cpu']:.2f}",
            (f"{r['contacts']} ({r['certified']} certified, {r.get('four_point_pairs', 0)} with 4 "
             "points)") if ours else str(r["pairs"]),
            "—" if ours else str(r["depth_outliers"]), "—" if ours else str(r["angle_outliers"]),
            "—" if ours else str(r["normal_outliers"]),
            "—" if ours else f"{r['depth_error_max']:.2g}",
            "—" if ours else f"{r['angle_max_degrees']:.3g}"])
    return "\n".join([
        f"{context['bodies']} hulls of {context['vertices_min']}-{context['vertices_max']} vertices "
        f"(median {context['vertices_median']}), {context['frames']} frames; tolerances: depth "
        f"{context['depth_tolerance']:g} of the smaller radius, angle {context['angle_degrees']:g} "
        "degree.", "", machine_line(data), "", table(header, body)])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default="bench/results")
    args = parser.parse_args()
    section = scene_section(args.results)
    print(section if section is not None else "no scene.json in " + args.results)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
