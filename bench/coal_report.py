"""RESULTS.md sections of the C++ benches against coal (narrowphase_coal.cpp, penetration_coal.cpp)."""

from __future__ import annotations

from markdown import fmt_err, fmt_time, machine_line, table

NARROWPHASE = (
    "`swarmcollide-narrowphase-coal` (bench/narrowphase_coal.cpp): the default method's distance "
    "and collision verdict against coal's GJK on random polytopes of n points on the unit sphere "
    "(bench/random_pairs.hpp, the pairs of swarmcollide-bench), prebuilt shapes, one reused "
    "`GJKSolver` per coal variant (GJK or Nesterov, default or bounding-box initial guess) with "
    "its carried support hint cleared before every call (it would otherwise start at the "
    "previous answer of the same pair), and coal's collide without contacts and with a zero "
    "distance bound, so that it stops at the first separating plane as ours does. A ratio is "
    "ours over coal's fastest variant for that workload, the median over rounds of each round's "
    "ratio; every answer of ours is checked to enclose coal's distance within coal's precision, "
    "1e-6 x (1 + distance) (its default convergence test; 1e-6 until session 53). Since "
    "session 51 our collision verdict first tests the bodies' bounding balls (proven apart: "
    "answered without a solver), which coal's GJK does not: the collide columns apart, and at "
    "1e-2 from 512 vertices, where the balls settle most pairs, set that test against coal's "
    "GJK; a coal user who screens by bounding volumes first (its broadphase does) would pay "
    "little more than ours there. The 20 pairs of each workload are asked again and again, so "
    "the processor's branch predictors learn every call's path; the next section asks 1,000 "
    "different questions of the same bodies instead.")
NARROWPHASE_POSES = (
    "`swarmcollide-narrowphase-coal --poses 50`: the same 20 pairs of bodies as above, each body "
    "in its own frame about its centroid, at 50 placements each (random rotations of both "
    "bodies, B moved along a random direction until the exact signed distance is the "
    "workload's), asked pair after pair with poses (`Query::distance(a, pose_a, b, pose_b)`, "
    "coal's `shapeDistance` with both transforms): 1,000 different questions a round of the "
    "bodies of the 20 repeated ones, as a planner's poses or a scene's frames ask them. The "
    "bodies, the solvers and the rest of the method are the section above's. Until session 53 "
    "only the 20 repeated pairs were measured, and that flattered coal: from one placement of "
    "each pair to 50 (`--poses 1` against `--poses 50`, two runs each, bench/README.md session "
    "53) coal's time per call grows 1.05-1.55x at 4 vertices and up to 2.0-2.3x at 8-64, ours "
    "0.85-1.11x at 4-16: over 20 repeated questions the branch predictors learn each call's "
    "path, and coal's has more branches to learn (indirect support calls among them). From 512 "
    "vertices both grow, ours 1.0-7.3x and coal's 2.3-15x: 40 large bodies climbed at different "
    "places no longer stay in the caches.")
PENETRATION = (
    "`swarmcollide-penetration-coal` (bench/penetration_coal.cpp): the default method's signed "
    "distance of overlapping pairs against coal's GJK + EPA (`GJKSolver::shapeDistance` with "
    "penetration on), prebuilt shapes, calls alternating. B is placed by bisection on the exact "
    "signed distance (-1e-2, or -0.6, 0.3 of the diameter). `coal outside` counts pairs whose "
    "coal depth falls outside our proven bounds by more than coal's 1e-6 tolerance; `angle` is "
    "the largest angle between the two contact normals; `iterations` are the mean of ours "
    "(Wolfe's and the expanding polytope's) and of coal's (its GJK's and its EPA's).")


def narrowphase_section(data: dict) -> str:
    rows = data["rows"]
    workloads = []
    for r in rows:
        key = (r["proximity"], r["query"])
        if key not in workloads:
            workloads.append(key)
    ours = {(r["vertices"], r["proximity"], r["query"]): r
            for r in rows if not r["contender"].startswith("coal")}
    sizes = sorted({n for n, _, _ in ours})
    header = ["n"] + [f"{query}, {proximity}" for proximity, query in workloads]
    body = []
    for n in sizes:
        cells = [str(n)]
        for proximity, query in workloads:
            r = ours.get((n, proximity, query))
            cells.append("n/a" if r is None else
                         f"{r['ratio_to_coal_best']:.2f}x ({fmt_time(r['microseconds'])})")
        body.append(cells)
    checks = [f"{sum(r[k] for r in ours.values())} {k.replace('_', ' ')}"
              for k in ("uncertified", "outside_bounds", "wrong_verdicts")]
    return "\n".join([
        machine_line(data), "",
        "Ours over coal's fastest variant (our time per query in brackets):", "",
        table(header, body), "",
        f"Over all workloads: {', '.join(checks)}."])


def penetration_section(data: dict) -> str:
    body = [[str(r["n"]), r["overlap"], fmt_time(r["ours_us"]), fmt_time(r["coal_us"]),
             f"{r['ratio']:.2f}x", f"{r['certified']}/{r['pairs']}", str(r["coal_outside"]),
             fmt_err(r["largest_angle_deg"]) + "°", iterations(r)]
            for r in data["rows"]]
    return "\n".join([
        machine_line(data), "",
        table(["n", "overlap", "ours", "coal", "ours / coal", "certified", "coal outside",
               "angle", "iterations (ours / coal)"], body)])


def iterations(row: dict) -> str:
    """Ours / coal's mean iterations; results recorded before coal's were kept have ours only."""
    ours = f"{row['mean_iterations']:.1f}"
    if "coal_mean_iterations" not in row:
        return ours
    return f"{ours} / {row['coal_mean_iterations']:.1f}"
