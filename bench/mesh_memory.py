"""Peak memory and time of ``CompoundBody.from_mesh`` on large meshes: a noisy torus (a scan-like
surface, decomposed by CoACD at the default preset) and a sphere (one convex hull, whose many
points made the deviation measurement grow as samples x points), at about 20k, 300k and 2M
triangles, each run in its own process from a binary PLY file.

    python bench/mesh_memory.py --json bench/results/mesh_memory.json   # prints a table too

The peak is each child's maximum resident set size (``os.wait4``); a run that fails
(``MemoryError``) under ``--limit-gb`` of address space is recorded as such.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
from typing import List, Optional

import numpy as np

SIZES = (20_000, 300_000, 2_000_000)

CHILD = """
import json, sys, time, swarmcollide as sc
start = time.perf_counter()
body = sc.CompoundBody.from_mesh(sys.argv[1], decompose=None if sys.argv[2] == "none" else
                                 sys.argv[2], cache=False, progress=False)
d = body.decomposition
print(json.dumps({"seconds": time.perf_counter() - start, "parts": d.parts,
                  "parts_to_mesh": d.parts_to_mesh, "mesh_to_parts": d.mesh_to_parts,
                  "decomposed_faces": d.decomposed_faces,
                  "simplification_error": d.simplification_error}))
"""


def noisy_torus(faces: int, seed: int = 0):
    """A torus of radii 1 and 0.3 with about ``faces`` triangles, its points moved along their
    normals by 0.002 (standard deviation), as a scanner would leave them."""
    import trimesh

    minor = max(4, int(round((faces / 8) ** 0.5)))
    major = max(8, int(round(faces / (2 * minor))))
    mesh = trimesh.creation.torus(1.0, 0.3, major_sections=major, minor_sections=minor)
    rng = np.random.default_rng(seed)
    mesh.vertices += mesh.vertex_normals * rng.normal(scale=0.002, size=(len(mesh.vertices), 1))
    return mesh


def sphere(faces: int):
    """A unit sphere with about ``faces`` triangles (a UV sphere: every point on its hull)."""
    import trimesh

    count = max(4, int(round((faces / 4) ** 0.5)))
    return trimesh.creation.uv_sphere(1.0, count=[count, count])


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--json", help="write the rows there")
    parser.add_argument("--limit-gb", type=float, default=12.0,
                        help="address-space limit of each run (default 12 GB)")
    args = parser.parse_args(argv)
    limit = int(args.limit_gb * 2**30)
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for shape, make, decompose in (("noisy torus", noisy_torus, "coacd"),
                                       ("sphere", sphere, "hull")):
            for size in SIZES:
                mesh = make(size)
                path = os.path.join(folder, f"{shape.replace(' ', '_')}_{size}.ply")
                mesh.export(path)
                child = subprocess.Popen(
                    [sys.executable, "-c", CHILD, path, decompose], stdout=subprocess.PIPE,
                    stderr=subprocess.PIPE, text=True,
                    preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (limit, limit)))
                stdout, stderr = child.stdout.read(), child.stderr.read()
                # wait4 gives this child's own peak, where RUSAGE_CHILDREN keeps the largest.
                _, status, usage = os.wait4(child.pid, 0)
                row = {"shape": shape, "decompose": decompose, "faces": len(mesh.faces),
                       "peak_mb": usage.ru_maxrss // 1024}
                if os.waitstatus_to_exitcode(status) == 0:
                    row.update(json.loads(stdout.strip().splitlines()[-1]))
                else:
                    row["error"] = (stderr.strip().splitlines() or ["killed"])[-1]
                rows.append(row)
                print(json.dumps(row), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"load_average_end": os.getloadavg(), "limit_gb": args.limit_gb,
                       "rows": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
