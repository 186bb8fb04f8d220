"""The measurement behind the default decomposer settings: time, parts and the sampled one-sided
Hausdorff distances of CoACD and V-HACD at several settings on the test meshes (an L, a U, a
box with a hole, a torus and a cup-like tube, made with trimesh as the tests make them), and
with ``--real`` of CoACD's presets on robot and object meshes of pybullet_data (the ``bench``
extra installs pybullet).

    python bench/decomposers.py --json bench/results/decomposers.json   # prints a table too
    python bench/decomposers.py --real --json bench/results/decomposers_real.json

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
    ("coacd", dict(concavity=0.05)),  # the default threshold before the presets
    ("coacd", dict(concavity=0.1)),
    ("coacd", dict(concavity=0.03)),
    ("coacd", dict(concavity=0.05, max_hulls=8)),
    ("coacd", dict(concavity=0.05, resolution=1000)),
    ("vhacd", dict()),  # the library's default: 32 hulls, 20000 voxels, 5% volume error
    ("vhacd", dict(max_hulls=8)),
    ("vhacd", dict(max_hulls=64, resolution=100000)),
    ("vhacd", dict(concavity=0.01, resolution=100000)),
]


# pybullet_data meshes: robot links (Franka Panda's link6 collision mesh, KUKA iiwa's link 3) and
# objects (the tray, the duck, the bunny), decomposed by CoACD at each preset.
REAL_MESHES = ["franka_panda/meshes/collision/link6.obj", "tray/tray_textured.obj",
               "kuka_iiwa/meshes/link_3.obj", "duck.obj", "bunny.obj"]
REAL_SETTINGS = [("coacd", dict(preset="fast")), ("coacd", dict(preset="quality"))]


def main(argv: Optional[List[str]] = None) -> int:
    import swarmcollide as sc
    from meshes import MESHES

    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--json", help="write the rows there")
    parser.add_argument("--real", action="store_true", help="CoACD's presets on pybullet_data")
    args = parser.parse_args(argv)
    rows = []
    load_start = os.getloadavg()
    if args.real:
        import pybullet_data

        real = {name: (lambda n=name: os.path.join(pybullet_data.getDataPath(), n))
                for name in REAL_MESHES}
        runs = [(d, s, real) for d, s in REAL_SETTINGS]
    else:
        runs = [(d, s, MESHES) for d, s in SETTINGS]
    for decomposer, settings, meshes in runs:
        for name, make in meshes.items():
            mesh = sc.load_mesh(make())
            start = time.perf_counter()
            body = sc.CompoundBody.from_mesh(mesh, decompose=decomposer, cache=False,
                                             progress=False, **settings)
            d = body.decomposition
            rows.append({"decomposer": decomposer, "settings": settings, "mesh": name,
                         "faces": len(mesh.faces), "watertight": bool(mesh.is_watertight),
                         "parts": d.parts, "points": body.point_count, "seconds": d.seconds,
                         "total_seconds": time.perf_counter() - start,
                         "parts_to_mesh": d.parts_to_mesh, "mesh_to_parts": d.mesh_to_parts,
                         "diagonal": float(((mesh.bounds[1] - mesh.bounds[0]) ** 2).sum() ** 0.5)})
            r = rows[-1]
            print(f"{decomposer:6s} {json.dumps(settings):45s} {name:40s} parts {r['parts']:3d} "
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
