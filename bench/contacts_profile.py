"""One scene of bench/contacts.py for a profiler: the same hulls and poses (seed 25), a few warm
frames, then ``Scene.contacts()`` on the next ones, with a checksum of the answers (the load does
not change it) and the scene's settled counts.

    valgrind --tool=callgrind --instr-atstart=no --toggle-collect='swarmcollide::Scene::contacts*' \
        .venv/bin/python bench/contacts_profile.py --warm 20 --frames 5 --callgrind

With ``--callgrind`` the script turns callgrind's instrumentation on (callgrind_control) only
before the measured frames: the meshes' loading and the warm frames run at full speed, and the
bodies' support trees and hulls, built once on first use, are not counted in the frames.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from contacts import floor_slab, hulls, motion, settled_pile  # noqa: E402

import swarmcollide as sc  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", choices=("drift", "pile"), default="drift")
    parser.add_argument("--bodies", type=int, default=300)
    parser.add_argument("--warm", type=int, default=2, help="frames run before the measured ones")
    parser.add_argument("--frames", type=int, default=5, help="measured frames")
    parser.add_argument("--callgrind", action="store_true",
                        help="turn callgrind's instrumentation on before the measured frames")
    args = parser.parse_args()
    points = hulls(args.bodies, seed=25)
    total = args.warm + args.frames
    if args.scene == "pile":
        rotations, translations = settled_pile(points, total, seed=25)
        points.append(floor_slab(points)[0])
    else:
        rotations, translations = motion(args.bodies, total, seed=25)
    scene = sc.Scene(threads=1)
    ids = scene.add(points)
    checksum = 0.0
    digest = hashlib.sha256()
    contacts = certified = count = 0
    for f in range(total):
        if args.callgrind and f == args.warm:
            subprocess.run(["callgrind_control", "-i", "on", str(os.getpid())], check=True,
                           stdout=subprocess.DEVNULL)
        scene.set_poses(ids, (rotations[f], translations[f]))
        result = scene.contacts()
        if f >= args.warm:
            contacts += len(result)
            certified += int(result.certified.sum())
            count += int(result.counts.sum())
            checksum += float(np.sum(result.distance)) + float(np.sum(result.lower_bound))
            checksum += float(np.sum(np.abs(result.normal))) + float(np.sum(result.points))
            for values in (result.pairs, result.distance, result.lower_bound, result.normal,
                           result.certified, result.counts, result.points):
                digest.update(np.ascontiguousarray(values).tobytes())
    print(f"{args.scene}: {args.frames} frames, contacts {contacts} certified {certified} points "
          f"{count}; checksum {checksum:.12g}; answers' sha256 {digest.hexdigest()[:16]}")


if __name__ == "__main__":
    main()
