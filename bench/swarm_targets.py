"""The swarm's targets at the paper's budget, under each instruction set's kernels.

Runs ``swarmcollide-swarm-targets`` once per instruction set (SWARMCOLLIDE_ISA=avx512, avx2,
baseline), each run timing swarmcollide's ipso against bench/plain_pso.cpp in the same process,
and collects the runs in one JSON file; a set the processor cannot run is recorded as such.
With ``--sweep FILE`` it also runs the velocity-limit sweep and keeps its table in FILE, and with
``--choices FILE`` the plain PSO under the alternatives to the other choices the paper leaves open.
Run from the repository root:

    python bench/swarm_targets.py --binary build/bench/bench/swarmcollide-swarm-targets \\
        --json bench/results/swarm_targets.json --sweep bench/results/velocity_sweep.txt \\
        --choices bench/results/choices.txt
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from typing import List, Optional

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
    parser.add_argument("--sweep", help="also run the velocity-limit sweep; its table goes here")
    parser.add_argument("--choices", help="also run the open choices on the plain PSO; table here")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)

    runs = [run(args.binary, isa, args.quick) for isa in ISAS]
    with open(args.json, "w") as f:
        json.dump({"quick": args.quick, "runs": runs}, f, indent=1)
    for flag, path in (("--sweep", args.sweep), ("--choices", args.choices)):
        if path:
            done = subprocess.run([args.binary, flag] + (["--quick"] if args.quick else []),
                                  capture_output=True, text=True, check=True)
            with open(path, "w") as f:
                f.write(done.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
