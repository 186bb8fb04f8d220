"""Render bench/RESULTS.md and its plots from the recorded results (bench/results/*.json).

It only renders: every number comes from a results file in bench/record.py's format, and a
section whose file has not been recorded is left out. Run from the repository root:

    python bench/report.py --results bench/results --plots bench/plots --out bench/RESULTS.md
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import Callable, List, Optional, Tuple

from coal_report import (NARROWPHASE, NARROWPHASE_POSES, PENETRATION, narrowphase_section,
                         penetration_section)
from compound import compound_section
from curved_coal import section as curved_coal_section
from curved_scene import section as curved_scene_section
from hull_points import section as hull_points_section
from pose_batch import section as pose_batch_section
from robot import section as robot_section
from motion import section as motion_section
from robot_motion import section as robot_motion_section
from cpp_report import FCL_RATIO, cpp_sections, every_workload_section, fcl_ratio_section
from record import load
from scene_report import CONTACTS, CONTACTS_PILE, contacts_section, scene_section
from sections import (
    batch_section,
    convergence_section,
    dask_section,
    kernel_code_section,
    per_call_section,
    python_section,
    swarm_speed_section,
    swarm_targets_section,
)

PYTHON_COMPARISON = (
    "pyswarms: GlobalBestPSO with 40 particles and 200 iterations, inertia 0.9 to 0.4 "
    "(`lin_variation`), c1 = c2 = 2, velocity clamp 1, particles kept in [0, 1] and weights "
    "normalised inside the cost (pyswarms has no equality constraints). SciPy: SLSQP on the "
    "squared objective with the sums as equality constraints and [0, 1] bounds, ftol 1e-15, from "
    "uniform weights. Distances of both are those of the returned weights moved onto the "
    "simplexes.")
SWARM_TARGETS = (
    "`bench/swarm_targets.py` runs `swarmcollide-swarm-targets` once per instruction set "
    "(`SWARMCOLLIDE_ISA`); each run answers the same separated pairs of sphere polytopes (n points "
    "on the unit sphere, their hull; B's centre 2.01 or 2.5 from A's) with `ipso` at its defaults "
    "(40 particles, 200 iterations, certified stop at the default tolerance) and with "
    "`bench/plain_pso.cpp`, the same method written as a plain scalar loop and compiled with -O3 "
    "-march=native, for the whole budget; pair k uses seed k. Times are for the whole budget "
    "(tolerance 0) on the first 4 pairs of each size, the two contenders alternating solve by "
    "solve in one process; a ratio is the median over rounds of each round's ratio.")
KERNEL_CODE = (
    "`bench/kernel_code.py` reads `objdump -d` of the kernels' object: per kernel and "
    "instruction set, its instructions, those on packed doubles and those computing on one "
    "double (arithmetic, comparisons, minima, maxima).")
SWARM_SPEED = (
    "`swarmcollide-swarm-speed`: ipso's time per query on the paper's pairs over 3,000 seeds, "
    "with the whole budget (tolerance 0) and with the certified stop (tolerance 1e-6, relative to "
    "the pair's size), and its accuracy at the paper's budget. The figures of earlier versions "
    "are in the history of bench/RESULTS.md; times of different runs are not interleaved (the "
    "targets section compares the swarm with the plain PSO inside one process).")
PER_CALL = (
    "`bench/per_call.py`: the cost of one call from Python on prebuilt bodies, swarmcollide's "
    "functions and `sc.Query` beside python-fcl and coal, each ratio against the faster "
    "python-fcl and the faster coal contender for the same query in the same run (coal's "
    "distance is signed, so it stands for both distances). Pairs are placed by bisection on the "
    "exact signed distance (1 apart, -0.1 overlapping), and every contender's answer on every "
    "pair is checked against the exact method before any timing, pair after pair with the "
    "peers' request and result objects shared, as a loop over pairs shares them. Earlier "
    "figures here were flattered:\n\n"
    "- Until issue 24 the python-fcl and coal contenders built new result objects on every call "
    "(and coal a new request), which flattered swarmcollide's ratios (the 2026-11-23 run gave "
    "sc.distance dual 0.58x python-fcl's distance at 8 vertices).\n"
    "- The 2026-11-26 08:47 run's overlapping pairs were not overlapping: its pairs had centres "
    "1.9 apart, but hulls of points on a unit sphere are smaller than the sphere, so the "
    "8-vertex pairs were 0.19 to 1.23 apart and half the 64-vertex ones apart by up to 0.011. "
    "Its overlapping rows timed apart or touching pairs, which flattered swarmcollide (its "
    "overlapping path is the slower one).\n"
    "- That run reused coal's results without clearing them. coal takes a result's distance as "
    "the bound to beat, so on the same pair again it skips the work (0.23 us for "
    "ComputeDistance on the overlapping pairs, against 1.9-3.3 us cleared), and in a loop over "
    "different pairs it answers with the previous pair's overlap. That flattered coal; each "
    "coal call now clears its result. coal's `ComputeDistance` and `ComputeCollision` functors, "
    "which keep their solver between calls and are 0.2-1 us faster than its free functions, "
    "were not timed, which flattered swarmcollide against coal.\n"
    "- python-fcl's reused collision result appends a contact on every colliding call; the "
    "bench empties it after one, so that the list does not grow through the run.\n\n"
    "Times are the thread's CPU time, so that other jobs on the shared machine do not enter "
    "them.")

# (results file, heading, text before, the section's renderer, text after), in document order.
Section = Tuple[str, str, str, Callable[[dict], str], str]
SECTIONS: List[Section] = [
    ("fcl_ratio.json", "The fcl method against the FCL calls it wraps, in turns (C++)",
     FCL_RATIO, fcl_ratio_section, ""),
    ("python_comparison.json", "From Python: swarmcollide against pyswarms, SciPy, python-fcl "
     "and coal", "", python_section, PYTHON_COMPARISON),
    ("narrowphase_coal.json", "Distance and verdicts against coal's GJK (C++)", NARROWPHASE,
     narrowphase_section, ""),
    ("narrowphase_coal_poses.json", "Distance and verdicts against coal's GJK at many poses "
     "(C++)", NARROWPHASE_POSES, narrowphase_section, ""),
    ("penetration_coal.json", "Penetration against coal's EPA (C++)", PENETRATION,
     penetration_section, ""),
    ("per_call.json", "Per call from Python", PER_CALL, per_call_section, ""),
    ("hull_points.json", "A body of many points against its hull (bench/hull_points.py)", "",
     hull_points_section, ""),
    ("swarm_targets.json", "The paper's swarm at its budget against a plain scalar PSO",
     SWARM_TARGETS, swarm_targets_section, ""),
    ("kernel_code.json", "The kernels' machine code per instruction set", KERNEL_CODE,
     kernel_code_section, ""),
    ("convergence.json", "Convergence (the paper's claim)",
     "![convergence]({plots}/convergence.png)", convergence_section, ""),
    ("batch.json", "Batch queries from Python", "", batch_section, ""),
    ("pose_batch.json", "Batches over poses from Python (bench/pose_batch.py)", "",
     pose_batch_section, ""),
]
LATE_SECTIONS: List[Section] = [
    ("swarm_speed.json", "The swarm's speed and accuracy at the paper's budget", SWARM_SPEED,
     swarm_speed_section, ""),
    ("dask_batch.json", "Batches on Dask (bench/dask_batch.py)", "", dask_section, ""),
    ("contacts.json", "Contacts of real object meshes: the scene against MuJoCo and coal",
     CONTACTS, contacts_section, ""),
    ("contacts_pile.json", "Resting contacts: the same meshes settled on a floor",
     CONTACTS_PILE, contacts_section, ""),
    ("curved_coal.json", "Curved shapes against coal's primitives (bench/curved_coal.py)", "",
     curved_coal_section, ""),
    ("curved_scene.json", "Scenes of spheres and capsules against 8-vertex hulls "
     "(bench/curved_scene.py)", "", curved_scene_section, ""),
    ("robot.json", "Robots against Pinocchio + coal and MuJoCo (bench/robot.py)", "",
     robot_section, ""),
    ("robot_motion.json", "Robot motions against discrete checks at OMPL's resolution "
     "(bench/robot_motion.py)", "", robot_motion_section, ""),
    ("motion.json", "Motions against FCL's conservative advancement (bench/motion.py)", "",
     motion_section, ""),
]


def render(results: str, sections: List[Section], plots_rel: str) -> List[str]:
    md: List[str] = []
    for name, heading, before, renderer, after in sections:
        data = load(os.path.join(results, name))
        if data is None:
            continue
        md += [f"## {heading}", ""]
        md += [text.format(plots=plots_rel) + "\n" for text in (before,) if text]
        md += [renderer(data), ""]
        md += [text + "\n" for text in (after,) if text]
    return md


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default="bench/results")
    parser.add_argument("--plots", default="bench/plots")
    parser.add_argument("--out", default="bench/RESULTS.md")
    args = parser.parse_args(argv)
    os.makedirs(args.plots, exist_ok=True)
    plots_rel = os.path.relpath(args.plots, os.path.dirname(os.path.abspath(args.out)))

    md = ["# Benchmark results", "",
          "Generated by `make bench` (bench/report.py) from bench/results/*.json; do not edit. "
          "bench/README.md says how each bench measures.", ""]
    cpp = load(os.path.join(args.results, "cpp.json"))
    if cpp is not None:
        md += cpp_sections(cpp, args.plots, plots_rel)
    md += render(args.results, SECTIONS, plots_rel)
    for section in (scene_section(args.results), compound_section(args.results)):
        if section is not None:
            md.append(section)
    md += render(args.results, LATE_SECTIONS, plots_rel)
    if cpp is not None:
        md += every_workload_section(cpp)
    with open(args.out, "w") as f:
        f.write("\n".join(md))
    return 0


if __name__ == "__main__":
    sys.exit(main())
