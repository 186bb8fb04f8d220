"""What the compiler made of the swarm's kernels, per instruction set (objdump of their object).

For each kernel function (the instances of a template, such as the row functions for each number
of rows, summed as one): its instructions, how many work on packed doubles (``...pd``), how many
compute on one double (``...sd`` arithmetic, comparisons, minima and maxima; moves and broadcasts
of values shared by all particles are not counted), and the widest register it uses. A kernel
compiled to scalar code shows many more scalar than packed instructions. It reads both this
library's per-set namespaces and the ``target_clones`` suffixes of earlier versions. Run from the
repository root after building (``--json`` writes a row per kernel and set in bench/record.py's
format):

    python bench/kernel_code.py --json bench/results/kernel_code.json \
        --object build/bench/cpp/CMakeFiles/swarmcollide.dir/src/solvers/swarm_kernels.cpp.o
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
from typing import List, Optional

import record

KERNEL = re.compile(r"swarmcollide::detail::(?:(avx512|avx2|baseline)::)?"
                    r"(?:\(anonymous namespace\)::)?(\w+)(?:<\d+>)?\(.*?(?:\[clone \.(\w+)\])?>:$")
CLONES = {"arch_x86_64_v4": "avx512", "arch_x86_64_v3": "avx2", "default": "baseline"}
NOT_COMPUTING = {"movsd", "vmovsd", "vbroadcastsd", "movddup", "vmovddup"}


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--object", required=True)
    parser.add_argument("--json", help="where to write the rows")
    args = parser.parse_args(argv)
    listing = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-C", args.object],
                             capture_output=True, text=True, check=True).stdout
    counts = {}
    current = None
    for line in listing.splitlines():
        if line.endswith(">:"):
            match = KERNEL.search(line)
            isa = match and (match.group(1) or CLONES.get(match.group(3) or ""))
            current = (isa, match.group(2)) if isa else None
            if current:
                counts.setdefault(current, {"all": 0, "pd": 0, "sd": 0, "width": 0})
            continue
        if current is None or not re.match(r"\s+[0-9a-f]+:\t", line):
            continue
        fields = line.split("\t")
        mnemonic = fields[1].split()[0] if len(fields) > 1 and fields[1].split() else ""
        c = counts[current]
        c["all"] += 1
        c["pd"] += mnemonic.endswith("pd")
        c["sd"] += mnemonic.endswith("sd") and mnemonic not in NOT_COMPUTING
        for width, register in ((512, "%zmm"), (256, "%ymm"), (128, "%xmm")):
            if register in line:
                c["width"] = max(c["width"], width)
                break
    print(f"{'instruction set':<16}{'kernel':<26}{'instructions':>13}{'packed (pd)':>13}"
          f"{'scalar (sd)':>13}{'widest register':>17}")
    rows = []
    for (isa, name), c in sorted(counts.items(), key=lambda kv: (kv[0][1], kv[0][0])):
        print(f"{isa:<16}{name:<26}{c['all']:>13}{c['pd']:>13}{c['sd']:>13}"
              f"{str(c['width']) + ' bits':>17}")
        rows.append({"isa": isa, "kernel": name, "instructions": c["all"], "packed": c["pd"],
                     "scalar": c["sd"], "widest_register_bits": c["width"]})
    if args.json:
        record.write(args.json, "kernel_code", rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
