"""The paper's claim checked: how fast ipso closes in on the distance, beside pso and penalty.

For each problem, every swarm variant runs with ``tolerance=0`` (all 200 iterations) for 30
seeds; the plot shows the median and quartiles of the error of the best distance found
(``result.history`` minus the exact distance) against the iteration. The penalty method is
deterministic and has no per-swarm-iteration history (one entry per outer penalty subproblem):
its final error is drawn as a line. Run from the repository root:

    python bench/convergence.py --json bench/results/convergence.json --plots bench/plots
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from typing import List, Optional

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from tqdm import tqdm  # noqa: E402

import swarmcollide as sc  # noqa: E402
from workloads import paper_workloads, random_workloads  # noqa: E402

SEEDS = 30
FLOOR = 1e-16  # errors are drawn on a log scale; exact answers sit on this floor
VARIANTS = {
    "ipso projection": {"method": "ipso", "constraint_handling": "projection"},
    "ipso feasibility (paper's rules)": {"method": "ipso", "constraint_handling": "feasibility"},
    "pso projection": {"method": "pso", "constraint_handling": "projection"},
    "pso feasibility": {"method": "pso", "constraint_handling": "feasibility"},
}
COLOURS = ["tab:blue", "tab:cyan", "tab:red", "tab:orange"]


def problems(quick: bool):
    """(title, list of (a, b, exact distance)): one pair per seed."""
    paper = paper_workloads()
    for w in paper:
        pair = w.pairs[0]
        yield f"paper, {w.proximity} pair", [(pair.a, pair.b, pair.reference)] * SEEDS
    for w in random_workloads((8,), ("gap 1e-2",), 5 if quick else SEEDS):
        yield "random 8-vertex pairs, 1e-2 apart", [(p.a, p.b, p.reference) for p in w.pairs]


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", required=True)
    parser.add_argument("--plots", required=True, help="folder for the PNG files")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    os.makedirs(args.plots, exist_ok=True)

    results = []
    for title, pairs in problems(args.quick):
        record = {"problem": title, "seeds": len(pairs), "variants": {}}
        for name, params in tqdm(VARIANTS.items(), desc=title):
            errors = []
            for seed, (a, b, exact) in enumerate(pairs):
                r = sc.distance(a, b, seed=seed, tolerance=0.0, **params)
                errors.append(np.maximum(np.asarray(r.history) - exact, 0.0))
            errors = np.array(errors)
            q = np.quantile(errors, [0.25, 0.5, 0.75], axis=0)
            record["variants"][name] = {"p25": q[0].tolist(), "median": q[1].tolist(),
                                        "p75": q[2].tolist()}
        if "penalty" in sc.METHODS:
            finals = []
            outer = []
            lbfgs = []
            for a, b, exact in pairs:
                r = sc.distance(a, b, method="penalty")
                finals.append(max(r.distance - exact, 0.0))
                outer.append(len(r.history))
                lbfgs.append(r.iterations)
            record["penalty"] = {"final_error_median": float(np.median(finals)),
                                 "final_error_p25": float(np.quantile(finals, 0.25)),
                                 "final_error_p75": float(np.quantile(finals, 0.75)),
                                 "outer_iterations_median": float(np.median(outer)),
                                 "lbfgs_iterations_median": float(np.median(lbfgs))}
        else:
            record["penalty"] = {"note": "method 'penalty' is not in this swarmcollide's API"}
        results.append(record)

    fig, axes = plt.subplots(1, len(results), figsize=(5.2 * len(results), 4.4), sharey=True)
    for ax, record in zip(np.atleast_1d(axes), results):
        for (name, curves), colour in zip(record["variants"].items(), COLOURS):
            x = np.arange(len(curves["median"]))
            ax.plot(x, np.maximum(curves["median"], FLOOR), color=colour, label=name)
            ax.fill_between(x, np.maximum(curves["p25"], FLOOR), np.maximum(curves["p75"], FLOOR),
                            color=colour, alpha=0.2, linewidth=0)
        penalty = record["penalty"]
        if "final_error_median" in penalty:
            ax.axhline(max(penalty["final_error_median"], FLOOR), color="k", linestyle="--",
                       label=f"penalty, final ({penalty['lbfgs_iterations_median']:.0f} L-BFGS its)")
        ax.set_yscale("log")
        ax.set_xlabel("iteration")
        ax.set_title(f"{record['problem']} ({record['seeds']} seeds)", fontsize=10)
        ax.grid(True, which="major", alpha=0.3)
    np.atleast_1d(axes)[0].set_ylabel("gbest distance - exact (median, quartiles)")
    np.atleast_1d(axes)[0].legend(fontsize=8, loc="center right")
    fig.suptitle("Convergence at the paper's budget: 40 particles, 200 iterations, tolerance 0")
    fig.tight_layout()
    fig.savefig(os.path.join(args.plots, "convergence.png"), dpi=110)

    with open(args.json, "w") as f:
        json.dump({"floor": FLOOR, "problems": results}, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
