"""The checked-in type stubs of the C++ core match what the built module exposes."""

import subprocess
import sys
from pathlib import Path

CHECKED_IN = Path(__file__).resolve().parents[2] / "python" / "swarmcollide" / "_core.pyi"


def test_core_stubs_are_current(tmp_path):
    subprocess.run(
        [sys.executable, "-m", "pybind11_stubgen", "swarmcollide._core", "-o", str(tmp_path),
         "--numpy-array-use-type-var"],
        check=True,
        capture_output=True,
    )
    generated = (tmp_path / "swarmcollide" / "_core.pyi").read_text()
    assert generated == CHECKED_IN.read_text(), "stubs are stale: run `make stubs`"
