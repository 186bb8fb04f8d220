"""The type information users see: the checked-in stubs of the C++ core match what the built
module exposes, and a type checker reads the package (stubs and typed Python layer) without
errors and with the results' real types."""

import subprocess
import sys
import textwrap
from pathlib import Path

CHECKED_IN = Path(__file__).resolve().parents[2] / "python" / "swarmcollide" / "_core.pyi"

# The optional extras' libraries (CoACD, MuJoCo, yourdfpy, tqdm, SciPy, ...) ship no types.
MYPY_CONFIG = "[mypy]\nignore_missing_imports = True\n"


def test_core_stubs_are_current(tmp_path):
    subprocess.run(
        [sys.executable, "-m", "pybind11_stubgen", "swarmcollide._core", "-o", str(tmp_path),
         "--numpy-array-use-type-var"],
        check=True,
        capture_output=True,
    )
    generated = (tmp_path / "swarmcollide" / "_core.pyi").read_text()
    assert generated == CHECKED_IN.read_text(), "stubs are stale: run `make stubs`"


def mypy(tmp_path, *targets):
    config = tmp_path / "mypy.ini"
    config.write_text(MYPY_CONFIG)
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--config-file", str(config), "--cache-dir",
         str(tmp_path / "cache"), *targets],
        capture_output=True, text=True, cwd=tmp_path,
    )


def test_package_type_checks(tmp_path):
    # Stubs a type checker cannot read (a name it cannot resolve, a subclass's method whose
    # signature contradicts its base's) turn users' checks of our results into errors or Any.
    checked = mypy(tmp_path, "-p", "swarmcollide")
    assert checked.returncode == 0, checked.stdout + checked.stderr


def test_user_code_sees_the_results_types(tmp_path):
    (tmp_path / "user.py").write_text(textwrap.dedent("""\
        import numpy as np
        import swarmcollide as sc

        r = sc.distance(np.eye(3), np.eye(3) + 2.0)
        gap: float = r.distance - r.lower_bound
        witnesses: np.ndarray = r.point_b - r.point_a
        s = sc.query("dual").signed_distance(sc.Sphere(1.0), sc.Box([1.0, 1.0, 1.0]))
        proven: bool = bool(s.certified)
        print(s.distnce)
        """))
    checked = mypy(tmp_path, "user.py")
    # The misspelt attribute alone is an error: the results are typed, not Any.
    errors = [line for line in checked.stdout.splitlines() if ": error:" in line]
    assert len(errors) == 1, checked.stdout + checked.stderr
    assert 'user.py:9: error: "DistanceResult" has no attribute "distnce"' in errors[0]
