"""Contacts of a few hundred real object meshes (pybullet_data's duck, teddy, bunny, mug, ... and
its random objects, as convex hulls) over ~100 frames: ``Scene.contacts()`` against MuJoCo
(``mj_kinematics`` + ``mj_collision``, free bodies) and coal (its DynamicAABBTree broadphase with
GJK/EPA contacts in C++), interleaved frame by frame on the same poses, with wall and CPU time per
frame and the load average. Every peer contact is checked against the exact reference, the scene's
certified signed distance and normal: depth errors, normal angles, and whether the peer's normal
separates the bodies by the true depth (its separation along it, from the hulls' vertices).

Two scenes: ``drift`` (bodies drifting and turning through a box, about one contact per body,
mostly vertex and edge contacts) and ``pile`` (the bodies dropped on a floor slab and left to
settle under MuJoCo's own simulation; the frames are its last steps, so faces rest on the floor
and on each other, the contacts a physics loop asks for frame after frame, with manifolds of
several points). The floor is one more hull, posed like the others in every contender.

    python bench/contacts.py [--quick] [--scene drift|pile] [--json bench/results/contacts.json]
"""

from __future__ import annotations

import argparse
import os
import time
from typing import Dict, List, Tuple

# NumPy's BLAS threads spin after each call (the checks' products): they would bill their CPU to
# whichever contender runs next.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from scipy.spatial import ConvexHull  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

import record  # noqa: E402
import swarmcollide as sc  # noqa: E402

# Named object meshes of pybullet_data (the robots' links and the planes are left out); the rest
# of the bodies are its random objects, in order.
NAMED = ["duck.obj", "teddy2_VHACD_CHs.obj", "bunny.obj", "objects/mug.obj", "soccerball.obj",
         "torus/torus_textured.obj", "lego/lego.obj", "jenga/jenga.obj", "domino/domino.obj",
         "toys/cube.obj", "toys/cylinder.obj", "toys/prism.obj", "toys/shape_sorter.obj",
         "sphere_smooth.obj", "textured_sphere_smooth.obj", "stone.obj", "cube.obj",
         "tray/tray_textured.obj", "racecar/meshes/cone.obj", "racecar/meshes/left_front_wheel.obj",
         "kuka_iiwa/meshes/link_0.obj", "kuka_iiwa/meshes/link_3.obj",
         "franka_panda/meshes/collision/hand.obj", "franka_panda/meshes/collision/link4.obj"]
# Bodies per unit volume (radii 0.3 to 0.6), per-frame motion and turn: about one contact per body.
DENSITY = 2.5
STEP = 0.01
TURN = 0.02
# Peer answers off the reference by more than these count as outliers: depth relative to the
# pair's smaller body radius (MuJoCo keeps its meshes in single precision, ~1e-7), and angle.
DEPTH_TOLERANCE = 1e-4
ANGLE_DEGREES = 1.0


def hulls(count: int, seed: int) -> List[np.ndarray]:
    """``count`` hulls' vertices, each centred on its box and scaled to a radius in [0.3, 0.6]."""
    import pybullet_data
    import trimesh

    root = pybullet_data.getDataPath()
    files = [os.path.join(root, name) for name in NAMED]
    random_objects = sorted(os.listdir(os.path.join(root, "random_urdfs")))
    files += [os.path.join(root, "random_urdfs", d, d + ".obj") for d in random_objects]
    rng = np.random.default_rng(seed)
    out = []
    for path in files:
        if len(out) == count:
            break
        mesh = trimesh.load(path, force="mesh", process=False)
        points = np.asarray(mesh.vertices, dtype=float)
        # A few random objects have NaN vertices, or none at all: they are passed over.
        points = points[np.isfinite(points).all(axis=1)]
        if len(points) < 4:
            continue
        points = points[ConvexHull(points).vertices]
        points -= (points.min(axis=0) + points.max(axis=0)) / 2
        out.append(points * rng.uniform(0.3, 0.6) / np.linalg.norm(points, axis=1).max())
    return out


def motion(n: int, frames: int, seed: int) -> Tuple[np.ndarray, np.ndarray]:
    """Rotations (frames, n, 3, 3) and translations (frames, n, 3): drifting, turning bodies."""
    rng = np.random.default_rng(seed)
    side = (n / DENSITY) ** (1 / 3)
    rotation = Rotation.random(n, random_state=seed)
    position = rng.uniform(0, side, (n, 3))
    velocity = rng.normal(0, STEP, (n, 3))
    spin = Rotation.from_rotvec(rng.normal(size=(n, 3)) * TURN / np.sqrt(3))
    rotations = np.empty((frames, n, 3, 3))
    translations = np.empty((frames, n, 3))
    for f in range(frames):
        rotations[f] = rotation.as_matrix()
        translations[f] = position
        rotation = spin * rotation
        position = position + velocity
    return rotations, translations


def floor_slab(points: List[np.ndarray]) -> Tuple[np.ndarray, float]:
    """The corners of a slab 0.5 thick (top face at z = 0) under a square grid of the bodies, and
    the grid's spacing (1.2: the bodies' largest diameter, so neighbours touch as they tumble)."""
    columns = int(np.ceil(np.sqrt(len(points))))
    half = columns * 1.2 / 2 + 1
    corners = np.array([[x, y, z] for x in (-half, half) for y in (-half, half)
                        for z in (-0.25, 0.25)])
    return corners, 1.2


def settled_pile(points: List[np.ndarray], frames: int, seed: int) -> Tuple[np.ndarray, np.ndarray]:
    """Rotations (frames, n + 1, 3, 3) and translations (frames, n + 1, 3): the bodies dropped in a
    grid on the floor slab (body n, fixed, centre at z = -0.25), simulated by MuJoCo until they
    rest, the frames being its last ``frames`` steps, two steps apart."""
    import mujoco

    corners, spacing = floor_slab(points)
    columns = int(np.ceil(np.sqrt(len(points))))
    rng = np.random.default_rng(seed)
    start = Rotation.random(len(points), random_state=seed).as_quat(scalar_first=True)
    assets = "".join(f'<mesh name="m{i}" vertex="{" ".join(f"{x:.17g}" for x in p.ravel())}"/>'
                     for i, p in enumerate(points))
    bodies = []
    for i, p in enumerate(points):
        x = (i % columns - (columns - 1) / 2) * spacing + rng.uniform(-0.05, 0.05)
        y = (i // columns - (columns - 1) / 2) * spacing + rng.uniform(-0.05, 0.05)
        z = float(np.linalg.norm(p, axis=1).max()) + 0.02
        quat = " ".join(f"{v:.17g}" for v in start[i])
        bodies.append(f'<body pos="{x} {y} {z}" quat="{quat}"><freejoint/>'
                      f'<geom type="mesh" mesh="m{i}" density="500"/></body>')
    slab = " ".join(f"{v:.17g}" for v in np.abs(corners).max(axis=0))
    xml = (f'<mujoco><option timestep="0.004"><flag multiccd="enable"/></option>'
           f'<size memory="400M"/><asset>{assets}</asset><worldbody>'
           f'<geom type="box" size="{slab}" pos="0 0 -0.25"/>{"".join(bodies)}'
           f"</worldbody></mujoco>")
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    settle = 300
    rotations = np.empty((frames, len(points) + 1, 3, 3))
    translations = np.empty((frames, len(points) + 1, 3))
    rotations[:, -1] = np.eye(3)
    translations[:, -1] = (0, 0, -0.25)
    for step in range(settle + 2 * frames):
        mujoco.mj_step(model, data)
        kept = step - settle
        if kept >= 0 and kept % 2 == 1:
            # A mesh geom's frame is the mesh's inertial frame, offset within its body so that
            # the mesh's own coordinates are the body's: the hull's pose is the body's.
            rotations[kept // 2, :-1] = data.xmat[1:].reshape(-1, 3, 3)
            translations[kept // 2, :-1] = data.xpos[1:]
    return rotations, translations


class Ours:
    def __init__(self, points, threads):
        self.scene = sc.Scene(threads=threads)
        self.ids = self.scene.add(points)
        self.name = f"swarmcollide_{threads}_thread" + ("s" if threads > 1 else "")

    def frame(self, rotations, translations):
        self.scene.set_poses(self.ids, (rotations, translations))
        return self.scene.contacts()


class MuJoCo:
    """Free bodies with one mesh geom each (MuJoCo takes the hull); qpos set, then kinematics and
    collision. ``multiccd`` asks MuJoCo for several contacts per convex pair."""

    def __init__(self, points, multiccd):
        import mujoco

        self.mujoco = mujoco
        assets = "".join(f'<mesh name="m{i}" vertex="{" ".join(f"{x:.17g}" for x in p.ravel())}"/>'
                         for i, p in enumerate(points))
        bodies = "".join(f'<body><freejoint/><geom type="mesh" mesh="m{i}"/></body>'
                         for i in range(len(points)))
        flag = '<option><flag multiccd="enable"/></option>' if multiccd else ""
        xml = (f'<mujoco>{flag}<size memory="200M"/><asset>{assets}</asset>'
               f"<worldbody>{bodies}</worldbody></mujoco>")
        self.model = mujoco.MjModel.from_xml_string(xml)
        self.data = mujoco.MjData(self.model)
        self.name = "mujoco_multiccd" if multiccd else "mujoco"

    def frame(self, rotations, translations):
        qpos = self.data.qpos.reshape(-1, 7)
        qpos[:, :3] = translations
        qpos[:, 3:] = Rotation.from_matrix(rotations).as_quat(scalar_first=True)
        self.mujoco.mj_kinematics(self.model, self.data)
        self.mujoco.mj_collision(self.model, self.data)
        return self.data

    def contacts(self, data) -> Dict[Tuple[int, int], Tuple[float, np.ndarray]]:
        """The deepest contact of each pair: (signed distance, normal from the first body)."""
        found = {}
        for c in data.contact[: data.ncon]:
            a, b = int(c.geom[0]), int(c.geom[1])
            normal = np.array(c.frame[:3])
            if a > b:
                a, b, normal = b, a, -normal
            if (a, b) not in found or c.dist < found[(a, b)][0]:
                found[(a, b)] = (float(c.dist), normal)
        return found


class Coal:
    """coal's DynamicAABBTree manager, a transform set per object, and its default callback
    running GJK and EPA on every candidate in C++, contacts collected in one result."""

    def __init__(self, points):
        import coal

        self.coal = coal
        self.objects = []
        self.radius_to_body = {}
        for i, p in enumerate(points):
            vertices = coal.StdVec_Vec3s()
            for q in p:
                vertices.append(np.asarray(q, dtype=float))
            triangles = coal.StdVec_Triangle()
            for u, v, w in ConvexHull(p).simplices:
                triangles.append(coal.Triangle(int(u), int(v), int(w)))
            shape = coal.Convex(vertices, triangles)
            shape.computeLocalAABB()
            self.radius_to_body[shape.aabb_radius] = i
            self.objects.append(coal.CollisionObject(shape, coal.Transform3s()))
        # Contacts name their shapes through fresh Python wrappers: a shape is found by its radius.
        assert len(self.radius_to_body) == len(points), "two shapes of one radius"
        self.manager = coal.DynamicAABBTreeCollisionManager()
        for o in self.objects:
            self.manager.registerObject(o)
        self.manager.setup()
        self.name = "coal"

    def frame(self, rotations, translations):
        for o, r, t in zip(self.objects, rotations, translations):
            o.setTransform(self.coal.Transform3s(r, t))
        self.manager.update()
        callback = self.coal.CollisionCallBackDefault()
        callback.data.request.num_max_contacts = 1 << 30
        callback.data.request.enable_contact = True
        self.manager.collide(callback)
        return callback.data.result

    def contacts(self, result) -> Dict[Tuple[int, int], Tuple[float, np.ndarray]]:
        found = {}
        for c in result.getContacts():
            a = self.radius_to_body[c.o1.aabb_radius]
            b = self.radius_to_body[c.o2.aabb_radius]
            normal = np.array(c.normal)
            if a > b:
                a, b, normal = b, a, -normal
            found[(a, b)] = (float(c.penetration_depth), normal)
        return found


def separation(a: np.ndarray, b: np.ndarray, n: np.ndarray) -> float:
    """min over B of n.y minus max over A of n.x: the bodies' gap along unit ``n``."""
    return float((b @ n).min() - (a @ n).max())


def check(reference, peer, points, rotations, translations, radii) -> Dict:
    """The peer's contacts against the reference (the scene's certified contacts)."""
    ours = {(int(a), int(b)): (d, low, n) for (a, b), d, low, n in
            zip(reference.pairs, reference.distance, reference.lower_bound, reference.normal)}
    counts = {"pairs": len(peer), "missed": 0, "extra": 0, "depth_outliers": 0,
              "angle_outliers": 0, "normal_outliers": 0, "depth_error_max": 0.0,
              "angle_max_degrees": 0.0}
    world = lambda i: points[i] @ rotations[i].T + translations[i]  # noqa: E731
    for key, (depth, low, normal) in ours.items():
        scale = min(radii[key[0]], radii[key[1]])
        if key not in peer and depth < -DEPTH_TOLERANCE * scale:
            counts["missed"] += 1
    for key, (signed, normal) in peer.items():
        scale = min(radii[key[0]], radii[key[1]])
        if key not in ours:
            counts["extra"] += signed < -DEPTH_TOLERANCE * scale
            continue
        depth, low, exact_normal = ours[key]
        error = max(low - signed, signed - depth, 0.0) / scale
        counts["depth_error_max"] = max(counts["depth_error_max"], error)
        counts["depth_outliers"] += error > DEPTH_TOLERANCE
        n = normal / np.linalg.norm(normal)
        angle = np.degrees(np.arccos(np.clip(n @ exact_normal, -1, 1)))
        counts["angle_max_degrees"] = max(counts["angle_max_degrees"], float(angle))
        counts["angle_outliers"] += angle > ANGLE_DEGREES
        # A normal is right when the bodies' gap along it is the signed distance (ties allowed).
        gap = separation(world(key[0]), world(key[1]), n)
        counts["normal_outliers"] += (low - gap) / scale > DEPTH_TOLERANCE
    return counts


def timed(run):
    wall, cpu = time.perf_counter(), time.process_time()
    out = run()
    return out, time.perf_counter() - wall, time.process_time() - cpu


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="100 bodies, 20 frames")
    parser.add_argument("--bodies", type=int, default=None, help="bodies (default 300)")
    parser.add_argument("--frames", type=int, default=None, help="frames (default 100)")
    parser.add_argument("--scene", choices=("drift", "pile"), default="drift",
                        help="bodies drifting through a box, or settled on a floor (see above)")
    parser.add_argument("--json", default=None, help="write the results there")
    args = parser.parse_args()
    n = args.bodies or (100 if args.quick else 300)
    frames = args.frames or (20 if args.quick else 100)
    load_before = os.getloadavg()
    points = hulls(n, seed=25)
    if args.scene == "pile":
        rotations, translations = settled_pile(points, frames + 1, seed=25)
        points.append(floor_slab(points)[0])
    else:
        rotations, translations = motion(n, frames + 1, seed=25)
    radii = [float(np.linalg.norm(p, axis=1).max()) for p in points]
    contenders = [Ours(points, 1), Ours(points, 2), MuJoCo(points, False), MuJoCo(points, True),
                  Coal(points)]
    # Frame 0 builds the peers' caches and ours (hulls, boxes, proofs): untimed.
    for c in contenders:
        c.frame(rotations[0], translations[0])
    times = {c.name: [] for c in contenders}
    checks = {c.name: [] for c in contenders if not isinstance(c, Ours)}
    stats = []
    for f in range(1, frames + 1):
        outputs = {}
        # The order turns frame by frame, so that none always runs first or after another.
        for c in contenders[f % len(contenders):] + contenders[: f % len(contenders)]:
            out, wall, cpu = timed(lambda: c.frame(rotations[f], translations[f]))
            times[c.name].append((wall, cpu))
            outputs[c.name] = out
        reference = outputs["swarmcollide_1_thread"]
        stats.append({"contacts": len(reference), "certified": int(reference.certified.sum()),
                      "points": int(reference.counts.sum()),
                      "four_point_pairs": int((reference.counts == 4).sum())})
        for c in contenders:
            if c.name in checks:
                checks[c.name].append(check(reference, c.contacts(outputs[c.name]), points,
                                            rotations[f], translations[f], radii))
    vertex_counts = [len(p) for p in points]
    rows = []
    ours_cpu = np.median([t[1] for t in times["swarmcollide_1_thread"]])
    for name, samples in times.items():
        wall = np.array([t[0] for t in samples])
        cpu = np.array([t[1] for t in samples])
        row = {"contender": name, "bodies": len(points), "scene": args.scene, "frames": frames,
               "median_ms": 1e3 * float(np.median(wall)), "median_cpu_ms": 1e3 * float(np.median(cpu)),
               "min_ms": 1e3 * float(wall.min()),
               "ours_over_this_cpu": float(ours_cpu / np.median(cpu))}
        if name in checks:
            total = {k: int(sum(c[k] for c in checks[name])) for k in checks[name][0]
                     if not k.endswith("_max") and not k.endswith("_degrees")}
            total["depth_error_max"] = float(max(c["depth_error_max"] for c in checks[name]))
            total["angle_max_degrees"] = float(max(c["angle_max_degrees"] for c in checks[name]))
            row.update(total)
        else:
            row.update({k: int(sum(s[k] for s in stats)) for k in stats[0]})
        rows.append(row)
        print(f"{name:24s} {row['median_ms']:8.2f} ms (cpu {row['median_cpu_ms']:8.2f}, min "
              f"{row['min_ms']:8.2f})  ours/this cpu {row['ours_over_this_cpu']:5.2f}  "
              + " ".join(f"{k}={v:.3g}" if isinstance(v, float) else f"{k}={v}"
                         for k, v in row.items()
                         if k not in ("contender", "bodies", "frames", "median_ms",
                                      "median_cpu_ms", "min_ms", "ours_over_this_cpu")),
              flush=True)
    print(f"{n} hulls of {min(vertex_counts)}-{max(vertex_counts)} vertices (median "
          f"{int(np.median(vertex_counts))}); load {load_before} -> {os.getloadavg()}")
    if args.json:
        context = {"mode": "quick" if args.quick else "full", "scene": args.scene,
                   "bodies": len(points), "frames": frames,
                   "vertices_min": min(vertex_counts), "vertices_max": max(vertex_counts),
                   "vertices_median": int(np.median(vertex_counts)),
                   "depth_tolerance": DEPTH_TOLERANCE, "angle_degrees": ANGLE_DEGREES}
        record.write(args.json, "contacts", rows, load_start=load_before, context=context)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
