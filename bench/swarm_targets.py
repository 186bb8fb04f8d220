"""The swarm's targets at the paper's budget, under each instruction set's kernels.

Runs ``swarmcollide-swarm-targets`` once per instruction set (SWARMCOLLIDE_ISA=avx512, avx2,
baseline), each run timing swarmcollide's ipso against bench/plain_pso.cpp in the same process,
and collects the runs in one JSON file; a set the processor cannot run is recorded as such.
A row per run. With ``--sweep`` it also runs the velocity-limit sweep and keeps its table in the
JSON's ``velocity_sweep``, and with ``--choices`` the plain PSO under the alternatives to the other
choices the paper leaves open (``choices``). Run from the repository root:

    python bench/swarm_targets.py --binary build/bench/bench/swarmcollide-swarm-targets \\
        --json bench/results/swarm_targets.json --sweep --choices
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from typing import List, Optional

import record

ISAS = ["avx512", "avx2", "baseline"]


def run(binary: str, isa: str, quick: bool) -> dict:
    env = dict(os.environ, SWARMCOLLIDE_ISA=isa)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "run.json")
        command = [binary, "--json", path] + (["--quick"] if quick else [])
        done = subprocess.run(command, env=env, capture_output=True, text=True)
        if done.returncode != 0:
            return {"isa": isa, "unavailable": done.stderr.strip().splitlines()[-1]}
        print(done.stdout, end="", flush=True)
        with open(path) as f:
            return json.load(f)


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--binary", required=True)
    parser.add_argument("--json", required=True)
    parser.add_argument("--sweep", action="store_true", help="also run the velocity-limit sweep")
    parser.add_argument("--choices", action="store_true",
                        help="also run the open choices on the plain PSO")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)

    runs = [run(args.binary, isa, args.quick) for isa in ISAS]
    tables = {}
    for flag, key, wanted in (("--sweep", "velocity_sweep", args.sweep),
                              ("--choices", "choices", args.choices)):
        if wanted:
            done = subprocess.run([args.binary, flag] + (["--quick"] if args.quick else []),
                                  capture_output=True, text=True, check=True)
            tables[key] = done.stdout
    record.write(args.json, "swarm_targets", runs, quick=args.quick, **tables)
    return 0


if __name__ == "__main__":
    sys.exit(main())
