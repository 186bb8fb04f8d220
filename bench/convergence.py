"""The paper's claim checked: do the rank-adaptive parameters (8)-(9) beat the linear inertia (7)?

For each problem, every swarm variant runs with ``tolerance=0`` (all 200 iterations) for 30
seeds: the paper's two pairs with seeds 0-29, and 30 random pairs of 4, 8 and 16 vertices (pair k
solved with seed k). The plot shows the median and quartiles of the error of the best distance
found (``result.history`` minus the exact distance) against the iteration; the JSON also keeps,
per seed, the final errors of ipso and pso with projection, for a paired comparison. The penalty
method is deterministic and has no per-swarm-iteration history: its final error is drawn as a
line. Run from the repository root:

    python bench/convergence.py --json bench/results/convergence.json --plots bench/plots
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import List, Optional

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402
from tqdm import tqdm  # noqa: E402

import record  # noqa: E402
import swarmcollide as sc  # noqa: E402
from workloads import paper_workloads, random_workloads  # noqa: E402

SEEDS = 30
FLOOR = 1e-16  # errors are drawn on a log scale; exact answers sit on this floor
CHECKPOINTS = [25, 50, 100, 200]
VARIANTS = {
    "ipso projection": {"method": "ipso", "constraint_handling": "projection"},
    "pso projection": {"method": "pso", "constraint_handling": "projection"},
    "ipso feasibility (paper's rules)": {"method": "ipso", "constraint_handling": "feasibility"},
    "pso feasibility": {"method": "pso", "constraint_handling": "feasibility"},
}
COLOURS = ["tab:blue", "tab:red", "tab:cyan", "tab:orange"]
CLAIM = ("ipso projection", "pso projection")


def problems(quick: bool):
    """(title, list of (a, b, exact distance)): one pair per seed."""
    seeds = 5 if quick else SEEDS
    for w in paper_workloads():
        pair = w.pairs[0]
        yield f"paper, {w.proximity} pair", [(pair.a, pair.b, pair.reference)] * seeds
    for w in random_workloads((4, 8, 16), ("gap 1e-2",), seeds):
        yield f"random {w.n}-vertex pairs, 1e-2 apart", [(p.a, p.b, p.reference) for p in w.pairs]


def paired(ipso: np.ndarray, pso: np.ndarray) -> dict:
    """Per-seed comparison of final errors; Wilcoxon's signed-rank test on the differences."""
    better = int(np.sum(ipso < pso))
    worse = int(np.sum(ipso > pso))
    p_value = None
    if better + worse > 0:
        p_value = float(stats.wilcoxon(ipso, pso, zero_method="zsplit").pvalue)
    return {"ipso_better": better, "ties": int(len(ipso) - better - worse), "ipso_worse": worse,
            "wilcoxon_p": p_value}


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", required=True)
    parser.add_argument("--plots", required=True, help="folder for the PNG files")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    os.makedirs(args.plots, exist_ok=True)

    results = []
    for title, pairs in problems(args.quick):
        problem = {"problem": title, "seeds": len(pairs), "variants": {}}
        finals = {}
        for name, params in tqdm(VARIANTS.items(), desc=title):
            errors = []
            for seed, (a, b, exact) in enumerate(pairs):
                r = sc.distance(a, b, seed=seed, tolerance=0.0, **params)
                errors.append(np.maximum(np.asarray(r.history) - exact, 0.0))
            errors = np.array(errors)
            q = np.quantile(errors, [0.25, 0.5, 0.75], axis=0)
            finals[name] = errors[:, -1]
            problem["variants"][name] = {
                "p25": q[0].tolist(), "median": q[1].tolist(), "p75": q[2].tolist(),
                "within_1e6": int(np.sum(errors[:, -1] <= 1e-6)),
                "final_errors": errors[:, -1].tolist()}
        problem["claim"] = paired(finals[CLAIM[0]], finals[CLAIM[1]])
        if "penalty" in sc.METHODS:
            final, outer, lbfgs = [], [], []
            for a, b, exact in pairs:
                r = sc.distance(a, b, method="penalty")
                final.append(max(r.distance - exact, 0.0))
                outer.append(len(r.history))
                lbfgs.append(r.iterations)
            problem["penalty"] = {"final_error_median": float(np.median(final)),
                                 "final_error_p25": float(np.quantile(final, 0.25)),
                                 "final_error_p75": float(np.quantile(final, 0.75)),
                                 "outer_iterations_median": float(np.median(outer)),
                                 "lbfgs_iterations_median": float(np.median(lbfgs))}
        else:
            problem["penalty"] = {"note": "method 'penalty' is not in this swarmcollide's API"}
        results.append(problem)

    columns = 3
    rows = (len(results) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(5.0 * columns, 4.0 * rows), sharey=True,
                             squeeze=False)
    for ax, problem in zip(axes.flat, results):
        for (name, curves), colour in zip(problem["variants"].items(), COLOURS):
            x = np.arange(len(curves["median"]))
            ax.plot(x, np.maximum(curves["median"], FLOOR), color=colour, label=name,
                    linestyle="-" if "projection" in name else ":")
            ax.fill_between(x, np.maximum(curves["p25"], FLOOR), np.maximum(curves["p75"], FLOOR),
                            color=colour, alpha=0.2, linewidth=0)
        penalty = problem["penalty"]
        if "final_error_median" in penalty:
            ax.axhline(max(penalty["final_error_median"], FLOOR), color="k", linestyle="--",
                       label="penalty, final error")
        ax.set_yscale("log")
        ax.set_xlabel("iteration")
        ax.set_title(f"{problem['problem']} ({problem['seeds']} seeds)", fontsize=10)
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes[:, 0]:
        ax.set_ylabel("gbest distance - exact")
    # The legend takes the first empty panel, or sits in the last one.
    spare = axes.flat[len(results)] if len(results) < axes.size else None
    handles, labels = axes.flat[0].get_legend_handles_labels()
    if spare is not None:
        spare.axis("off")
        spare.legend(handles, labels, loc="center", title="median and quartiles over the seeds")
    else:
        axes.flat[-1].legend(fontsize=7, loc="upper right")
    fig.suptitle("Rank-adaptive (8)-(9) against linear inertia (7): 40 particles, 200 iterations, "
                 "tolerance 0")
    fig.tight_layout()
    fig.savefig(os.path.join(args.plots, "convergence.png"), dpi=100)

    record.write(args.json, "convergence", results, quick=args.quick, floor=FLOOR,
                 checkpoints=CHECKPOINTS, claim=list(CLAIM))
    return 0


if __name__ == "__main__":
    sys.exit(main())
