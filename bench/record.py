"""The one JSON format of every benchmark's results (bench/README.md):

    {"bench": name, "machine": {...}, "command": "...", "rows": [...], ...the bench's own fields}

``machine`` holds the processor, the core count, the load average at the start and at the end,
the date, and the versions of Python and of the libraries measured. A Python bench calls
``write``; a C++ binary is run through this module, which passes it ``--json TEMPORARY`` and
wraps what it wrote (its ``rows``, or Google Benchmark's ``benchmarks``) in the same header:

    python bench/record.py --bench cpp --json bench/results/cpp.json -- BINARY ARGS...
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import shlex
import subprocess
import sys
import tempfile
from importlib import metadata
from typing import Dict, Iterable, List, Optional

# Distributions whose versions a result may depend on; those not installed are left out.
LIBRARIES = ("swarmcollide", "numpy", "scipy", "python-fcl", "coal", "pyswarms", "trimesh",
             "dask", "distributed", "coacd", "vhacdx")
_START_LOAD = os.getloadavg()


def cpu_model() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def versions(names: Iterable[str] = LIBRARIES) -> Dict[str, str]:
    found = {"python": platform.python_version()}
    for name in names:
        try:
            found[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            pass
    return found


def machine(load_start: Optional[Iterable[float]] = None) -> dict:
    """The machine now; ``load_start`` defaults to the load average when this module loaded."""
    return {
        "cpu": cpu_model(),
        "cores": os.cpu_count(),
        "load_average_start": [round(x, 2) for x in (load_start or _START_LOAD)],
        "load_average_end": [round(x, 2) for x in os.getloadavg()],
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "versions": versions(),
    }


def command_line(argv: Optional[List[str]] = None) -> str:
    """The command as run from the repository root (the interpreter named as ``python``)."""
    return shlex.join(["python"] + list(sys.argv if argv is None else argv))


def write(path, bench: str, rows: list, command: Optional[str] = None,
          load_start: Optional[Iterable[float]] = None, **fields) -> dict:
    """Write the bench's results with the common header; returns what was written."""
    data = {"bench": bench, "machine": machine(load_start), "command": command or command_line(),
            "rows": rows, **fields}
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    with open(path, "w") as f:
        json.dump(data, f, indent=1)
        f.write("\n")
    return data


def load(path: str) -> Optional[dict]:
    """A results file, or None where it was not recorded."""
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description="run a C++ bench binary and record its JSON")
    parser.add_argument("--bench", required=True, help="the bench's name")
    parser.add_argument("--json", required=True, help="where to write the results")
    parser.add_argument("binary", nargs=argparse.REMAINDER, help="-- BINARY ARGS...")
    args = parser.parse_args(argv)
    command = args.binary[1:] if args.binary[:1] == ["--"] else args.binary
    if not command:
        parser.error("give the binary after --")
    load_start = os.getloadavg()
    with tempfile.TemporaryDirectory() as folder:
        raw = os.path.join(folder, "raw.json")
        subprocess.run(command + ["--json", raw], check=True)
        with open(raw) as f:
            data = json.load(f)
    # Google Benchmark calls its rows "benchmarks"; the other binaries write "rows".
    rows = data.pop("rows", None)
    if rows is None:
        rows = data.pop("benchmarks")
    write(args.json, args.bench, rows, command=shlex.join(command + ["--json", args.json]),
          load_start=load_start, **data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
