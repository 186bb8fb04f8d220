"""Command line: ``python -m swarmcollide paper`` reproduces the paper's Section IV."""

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
    arguments = parser.parse_args(argv)
    if arguments.repeats < 1:
        parser.error("--repeats must be at least 1")
    print(paper.reproduce(seed=arguments.seed, repeats=arguments.repeats))
    return 0
