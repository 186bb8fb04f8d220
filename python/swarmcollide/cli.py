"""Command line: ``python -m swarmcollide paper`` reproduces the paper's Section IV;
``python -m swarmcollide scene`` runs a scene of moving bodies and prints each frame."""

from __future__ import annotations

import argparse
from typing import Optional, Sequence

from . import paper


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="swarmcollide", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    reproduce = commands.add_parser(
        "paper", help="print the paper's Tables 1 and 2 beside ours and the exact answers"
    )
    reproduce.add_argument("--seed", type=int, default=0, help="solver seed (default 0)")
    reproduce.add_argument(
        "--repeats", type=int, default=20, help="runs per row; the median time is shown"
    )
    scene = commands.add_parser(
        "scene",
        help="boxes and random hulls moving through each other: contacts and times per frame",
    )
    scene.add_argument("--bodies", type=int, default=300, help="number of bodies (default 300)")
    scene.add_argument("--frames", type=int, default=60, help="number of frames (default 60)")
    scene.add_argument("--seed", type=int, default=0, help="seed of the bodies and their motion")
    scene.add_argument("--threads", type=int, default=None, help="narrowphase threads")
    scene.add_argument(
        "--cold", action="store_true", help="answer every frame from scratch (no warm start)"
    )
    scene.add_argument(
        "--plot", metavar="FILE", help="save a picture of the last frame there (needs matplotlib)"
    )
    arguments = parser.parse_args(argv)
    if arguments.command == "paper":
        if arguments.repeats < 1:
            parser.error("--repeats must be at least 1")
        print(paper.reproduce(seed=arguments.seed, repeats=arguments.repeats))
        return 0
    if arguments.bodies < 2 or arguments.frames < 1:
        parser.error("--bodies must be at least 2 and --frames at least 1")
    from . import scene_demo

    scene_demo.run(
        arguments.bodies,
        arguments.frames,
        seed=arguments.seed,
        threads=arguments.threads,
        warm_start=not arguments.cold,
        plot=arguments.plot,
    )
    return 0
