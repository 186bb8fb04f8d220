"""The measurement behind the default decomposer settings: time, parts and the sampled one-sided
Hausdorff distances of CoACD and V-HACD at several settings on the test meshes (an L, a U, a
box with a hole, a torus and a cup-like tube, made with trimesh as the tests make them).

    python bench/decomposers.py --json bench/results/decomposers.json   # prints a table too

Each setting runs once per mesh without the cache (decompositions are deterministic for a
seed); times are wall-clock on a shared machine, so compare them within one run.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from typing import List, Optional

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "python"))

SETTINGS = [
    ("coacd", dict(concavity=0.05)),  # the library's default
    ("coacd", dict(concavity=0.1)),
    ("coacd", dict(concavity=0.03)),
    ("coacd", dict(concavity=0.05, max_hulls=8)),
    ("coacd", dict(concavity=0.05, resolution=1000)),
    ("vhacd", dict()),  # the library's default: 32 hulls, 20000 voxels, 5% volume error
    ("vhacd", dict(max_hulls=8)),
    ("vhacd", dict(max_hulls=64, resolution=100000)),
    ("vhacd", dict(concavity=0.01, resolution=100000)),
]


def main(argv: Optional[List[str]] = None) -> int:
    import swarmcollide as sc
    from meshes import MESHES

    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--json", help="write the rows there")
    args = parser.parse_args(argv)
    rows = []
    load_start = os.getloadavg()
    for decomposer, settings in SETTINGS:
        for name, make in MESHES.items():
            mesh = make()
            start = time.perf_counter()
            body = sc.CompoundBody.from_mesh(mesh, decompose=decomposer, cache=False,
                                             progress=False, **settings)
            d = body.decomposition
            rows.append({"decomposer": decomposer, "settings": settings, "mesh": name,
                         "parts": d.parts, "points": body.point_count, "seconds": d.seconds,
                         "total_seconds": time.perf_counter() - start,
                         "parts_to_mesh": d.parts_to_mesh, "mesh_to_parts": d.mesh_to_parts,
                         "diagonal": float(((mesh.bounds[1] - mesh.bounds[0]) ** 2).sum() ** 0.5)})
            r = rows[-1]
            print(f"{decomposer:6s} {json.dumps(settings):45s} {name:14s} parts {r['parts']:3d} "
                  f"{r['seconds']:6.2f} s  beyond {r['parts_to_mesh'] / r['diagonal']:.4f}  "
                  f"missed {r['mesh_to_parts'] / r['diagonal']:.4f} (of the diagonal)",
                  flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"load_average_start": load_start, "load_average_end": os.getloadavg(),
                       "rows": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
