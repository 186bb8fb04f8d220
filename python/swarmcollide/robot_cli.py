"""The ``swarmcollide robot MODEL`` verb: a robot checked at random configurations, with its
collision rate, minimum distances and time per configuration (``cli.py`` adds it)."""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, Optional

import numpy as np

from .robot import MAX_SAMPLES

URDF_SUFFIXES = (".urdf",)
MJCF_SUFFIXES = (".xml", ".mjcf")

CHUNK = 500
"""Configurations per call of ``check``: the progress bar moves once per chunk."""


def add_parser(commands, integer: Callable[..., Callable[[str], int]], seed) -> None:
    """Add the ``robot`` verb to ``commands`` (an argparse subparsers object); ``integer`` and
    ``seed`` are the CLI's argument types."""
    robot = commands.add_parser(
        "robot", help="check a robot (URDF or MJCF) at random configurations",
        description="Check a robot for self-collision at random configurations within its joint "
        "limits (a continuous joint over one turn; a sliding joint needs finite limits): the "
        "collision rate, the minimum signed distances, how many answers are certified and the "
        "time per configuration.")
    robot.add_argument("model", help="a URDF file (.urdf) or an MJCF file (.xml, .mjcf)")
    robot.add_argument("--samples", type=integer(1), default=1000,
                       help=f"random configurations to check (default 1000, at most "
                       f"{MAX_SAMPLES:,})")
    robot.add_argument("--seed", type=seed, default=0, help="seed of the configurations")
    robot.add_argument("--threads", type=integer(1, 1024), default=None,
                       help="C++ threads (default: one per hardware thread)")
    robot.add_argument("--srdf", help="an SRDF file whose disable_collisions pairs are skipped")
    robot.add_argument("--collision", choices=["hull", "mesh", "decompose"], default="hull",
                       help="URDF meshes as their convex hulls (default), compound bodies of "
                       "their convex pieces, or CoACD's parts")
    robot.add_argument("--package-dir", action="append", default=[], metavar="DIR",
                       help="where URDF package:// paths are looked up (repeatable)")
    robot.add_argument("--json", action="store_true", help="print the report as JSON")
    robot.add_argument("--plot", metavar="FILE",
                       help="save a picture of the robot at the configuration of smallest "
                       "distance, its nearest pair marked (needs matplotlib)")
    robot.add_argument("--quiet", action="store_true", help="no progress bar")


def check_arguments(parser: argparse.ArgumentParser, arguments: argparse.Namespace) -> None:
    """Usage errors found before any file is read."""
    if arguments.samples > MAX_SAMPLES:
        # Each configuration and its answer are kept for the report: more would ask for memory
        # (gigabytes) before the first check.
        parser.error(f"argument --samples: must be at most {MAX_SAMPLES:,}, got "
                     f"{arguments.samples:,}")
    suffix = Path(arguments.model).suffix.lower()
    if suffix not in URDF_SUFFIXES + MJCF_SUFFIXES:
        parser.error(f"argument model: {arguments.model!r} must end in .urdf (URDF) or .xml or "
                     f".mjcf (MJCF)")
    if suffix in MJCF_SUFFIXES and (arguments.collision != "hull" or arguments.package_dir):
        parser.error("arguments --collision and --package-dir apply to URDF files only")


def load(arguments: argparse.Namespace):
    """The robot of ``arguments.model``; ValueError for a file that cannot be used."""
    from .robot import Robot

    if Path(arguments.model).suffix.lower() in URDF_SUFFIXES:
        return Robot.from_urdf(arguments.model, package_dirs=arguments.package_dir,
                               collision=arguments.collision, srdf=arguments.srdf)
    return Robot.from_mjcf(arguments.model, srdf=arguments.srdf)


def _progress(total: int, quiet: bool):
    """A tqdm bar over ``total`` configurations when tqdm is installed, stderr is a terminal and
    the work is long (more than one chunk); None otherwise."""
    if quiet or total <= CHUNK or not sys.stderr.isatty():
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, unit="configuration", unit_scale=True, leave=False)


def report(robot, samples: int, seed: int, threads: Optional[int], quiet: bool = True):
    """Check ``samples`` random configurations (``random_configurations``: uniform within the
    limits, seeded by ``seed``); returns the report (a dict) and the check of each one."""
    from .robot import RobotCheck, random_configurations

    q = random_configurations(robot, samples, seed)
    bar = _progress(samples, quiet)
    parts = []
    seconds = 0.0
    try:
        for start in range(0, samples, CHUNK):
            begin = time.perf_counter()
            parts.append(robot.check(q[start:start + CHUNK], threads=threads))
            seconds += time.perf_counter() - begin
            if bar is not None:
                bar.update(len(q[start:start + CHUNK]))
    finally:
        if bar is not None:
            bar.close()
    check = RobotCheck(**{field: np.concatenate([getattr(p, field) for p in parts])
                          for field in ("colliding", "min_distance", "lower_bound", "certified",
                                        "pair", "pair_names", "point_a", "point_b", "normal")})
    distances = check.min_distance
    nearest = int(np.argmin(distances))
    checked = bool(robot.pairs)  # without pairs every distance is inf: nothing to report
    answer: Dict[str, Any] = {
        "links": len(robot.link_names), "dof": robot.dof, "pairs": len(robot.pairs),
        "samples": samples, "seed": seed, "threads": threads,
        "colliding": int(check.colliding.sum()),
        "collision_rate": float(check.colliding.mean()),
        "certified": int(check.certified.sum()),
        "min_distance": float(distances.min()) if checked else None,
        "median_min_distance": float(np.median(distances)) if checked else None,
        "seconds": seconds,
        "us_per_configuration": seconds / samples * 1e6,
        "nearest": {
            "configuration": q[nearest].tolist(),
            "pair": [str(name) for name in check.pair_names[nearest]],
            "distance": float(distances[nearest]),
            "certified": bool(check.certified[nearest]),
            "point_a": check.point_a[nearest].tolist(),
            "point_b": check.point_b[nearest].tolist(),
        } if checked else None,
    }
    return answer, q[nearest]


def run(arguments: argparse.Namespace) -> int:
    robot = load(arguments)
    answer, nearest = report(robot, arguments.samples, arguments.seed, arguments.threads,
                             quiet=arguments.quiet or arguments.json)
    answer["model"] = arguments.model
    if arguments.plot:
        from .robot_plot import plot_robot

        plot_robot(robot, nearest, path=arguments.plot)
    if arguments.json:
        print(json.dumps(answer, indent=2))
        return 0
    print(f"{arguments.model}: {answer['links']} links, {answer['dof']} degrees of freedom, "
          f"{answer['pairs']} pairs checked")
    print(f"{answer['samples']} configurations (seed {answer['seed']}): {answer['colliding']} "
          f"colliding ({100 * answer['collision_rate']:.1f}%), {answer['certified']} certified")
    if answer["nearest"] is not None:
        pair = answer["nearest"]["pair"]
        print(f"minimum signed distance: least {answer['min_distance']:.6g}, median "
              f"{answer['median_min_distance']:.6g} (per configuration)")
        print(f"nearest pair: {pair[0]} - {pair[1]} at {answer['nearest']['distance']:.6g}")
    print(f"time: {answer['us_per_configuration']:.1f} us per configuration "
          f"({answer['seconds']:.3f} s)")
    if arguments.plot:
        print(f"picture of the nearest configuration saved to {arguments.plot}")
    return 0
