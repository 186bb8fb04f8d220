"""Robots judged against brute force: seeded random robots built from tables, URDF and MJCF.

Each case draws a small robot (a chain or tree of 2-7 links; revolute, continuous, prismatic and
fixed joints at rotated origins, axes neither unit nor positive; every kind of geometry
``sc.Robot`` takes, several to a link; obstacles; disabled pairs; the whole model scaled by up to
1e6 either way) and judges one of:

check      ``check``, ``distances``, ``forward_kinematics`` and ``geometry_poses`` at a batch of
           configurations (inside the limits, or outside them under ``limits="clamp"`` or
           ``"wrap"``) against forward kinematics written here from the URDF semantics (MuJoCo's
           own for MJCF bodies) and the exact signed distance of every pair at those poses; the
           pairs against the adjacency rule; batches against single calls and 1 thread against 2.
motion     ``check_motion`` against dense sampling of ``distances`` along the segment: random,
           grazing (an obstacle placed at a link's support point mid-motion), still (q0 == q1),
           starting in contact, many turns of the continuous joints, and the whole robot and its
           obstacles 1e3 to 1e6 times its size from the world's origin; batches against single
           calls and threads.
argument   malformed URDF and MJCF files, tables, configurations and options: each must be a
           ValueError or TypeError whose message names what is wrong.

Verdicts are fuzz_judge.py's categories. Tolerances follow the library's contract: answers are
certified to ``tolerance`` times the pair's size (here over-estimated as the distance between the
geometries' frames plus twice the sum of their reaches, so that a judge never asks for more than
the contract), plus ``ROUNDING`` times the largest coordinate, for the rounding of the poses. The
functions are importable by the sandbox's children (``tests/fuzz/census.py --corpus robots``).
"""

from __future__ import annotations

import tempfile
import traceback
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple

import mujoco  # imported once by the sandbox's helper, not by every case's child
import numpy as np
import trimesh
import yourdfpy  # noqa: F401 - as mujoco: swarmcollide imports it when a URDF is read
from scipy.spatial.transform import Rotation

import swarmcollide as sc

TOLERANCE = sc.DEFAULT_TOLERANCE
"""The library's default tolerance, relative to a pair's size: the queries' and check_motion's."""

ROUNDING = 1e-11
"""Rounding allowed, relative to the largest coordinate of the robot's world (the library and
this module compose the same transforms in different orders)."""

TIME_TOLERANCE = 1e-6
"""check_motion's default ``time_tolerance``."""

SAMPLES = 500
"""Configurations sampled along a motion (and again before a contact's bracket)."""

FAMILY_CYCLE = ("check", "motion", "check", "motion", "argument")
"""The families taken in turn by case index."""

SOURCES = ("tables", "urdf", "mjcf")

KINDS = {
    "tables": ("box", "sphere", "capsule", "cylinder", "ellipsoid", "hull", "flat", "collinear",
               "repeated", "rounded", "compound", "mesh"),
    "urdf": ("box", "sphere", "cylinder", "mesh"),
    "mjcf": ("box", "sphere", "capsule", "cylinder", "ellipsoid"),
}  # fmt: skip
"""The geometry kinds each source can say: URDF has boxes, spheres, cylinders and meshes (solid
ones: the mesh reader refuses flat meshes, a bad input below); MJCF has capsules and ellipsoids
too (its meshes MuJoCo recentres, which test_robot.py covers)."""

OBSTACLE_KINDS = ("box", "sphere", "capsule", "ellipsoid", "hull", "rounded", "compound")

MOTIONS = ("random", "graze", "still", "start-in-contact", "turns", "far")


# ----- the model ------------------------------------------------------------------------------


@dataclass
class JointSpec:
    """A URDF joint: ``child = parent * origin(xyz, rpy) * motion(value)``."""

    name: str
    kind: str
    parent: int
    child: int
    xyz: np.ndarray
    rpy: np.ndarray
    axis: np.ndarray
    lower: float = 0.0
    upper: float = 0.0

    @property
    def moving(self) -> bool:
        return self.kind != "fixed"


@dataclass
class GeometrySpec:
    """A geometry on link ``link`` (-1: an obstacle in the world) at ``(xyz, rpy)``.

    ``points`` are a hull's (or a mesh's, before its ``mesh_scale``), ``parts`` a compound's;
    ``sizes`` the shape's (half extents, radius and half length, radii)."""

    name: str
    link: int
    kind: str
    xyz: np.ndarray
    rpy: np.ndarray
    sizes: np.ndarray = field(default_factory=lambda: np.zeros(0))
    points: Optional[np.ndarray] = None
    parts: Tuple[np.ndarray, ...] = ()
    mesh_scale: np.ndarray = field(default_factory=lambda: np.ones(3))
    mesh_file: str = ""


@dataclass
class ModelSpec:
    links: List[str]
    joints: List[JointSpec]
    geometries: List[GeometrySpec]
    obstacles: List[GeometrySpec]
    disabled: List[Tuple[str, str]]
    scale: float

    @property
    def moving(self) -> List[JointSpec]:
        return [j for j in self.joints if j.moving]


def rpy_matrix(rpy: np.ndarray) -> np.ndarray:
    """URDF's fixed-axis roll, pitch, yaw: Rz(yaw) Ry(pitch) Rx(roll)."""
    (cr, cp, cy), (sr, sp, sy) = np.cos(rpy), np.sin(rpy)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def transform(xyz: np.ndarray, rpy: np.ndarray) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3] = rpy_matrix(rpy)
    pose[:3, 3] = xyz
    return pose


def random_axis(rng: np.random.Generator) -> np.ndarray:
    """A joint axis: random or along a coordinate axis, negative or not, of length 1e-3 to 1e3."""
    if rng.random() < 0.4:
        axis = np.zeros(3)
        axis[int(rng.integers(3))] = rng.choice([-1.0, 1.0])
    else:
        axis = rng.normal(size=3)
    return axis * float(rng.choice([1e-3, 0.5, 1.0, 2.0, 1e3]))


def random_joint(rng: np.random.Generator, child: int, parent: int,
                 kinds: Tuple[str, ...]) -> JointSpec:
    kind = str(rng.choice(kinds))
    joint = JointSpec(f"j{child}", kind, parent, child, rng.uniform(-0.5, 0.5, 3),
                      rng.uniform(-np.pi, np.pi, 3), random_axis(rng))  # fmt: skip
    if kind == "revolute":
        joint.lower, joint.upper = -rng.uniform(0.05, 3.5), rng.uniform(0.05, 3.5)
    elif kind == "prismatic":
        joint.lower, joint.upper = -rng.uniform(0.01, 0.4), rng.uniform(0.01, 0.4)
    return joint


def hull_points(rng: np.random.Generator, kind: str) -> np.ndarray:
    """Points of a hull of ``kind``: full, flat (in a plane), collinear, or with repeats."""
    count = int(rng.integers(4, 12))
    points = rng.normal(size=(count, 3)) * rng.uniform(0.03, 0.2, 3)
    if kind == "flat":
        points[:, 2] = 0.0
        points = points @ rpy_matrix(rng.uniform(-np.pi, np.pi, 3)).T
    elif kind == "collinear":
        points = np.outer(rng.normal(size=count), rng.normal(size=3) * 0.1)
    elif kind == "repeated":
        points = np.vstack([points, points[: count // 2], points[:1]])
    return points + rng.uniform(-0.05, 0.05, 3)


def random_geometry(rng: np.random.Generator, name: str, link: int, kind: str) -> GeometrySpec:
    geometry = GeometrySpec(name, link, kind, rng.uniform(-0.3, 0.3, 3),
                            rng.uniform(-np.pi, np.pi, 3))  # fmt: skip
    if kind == "box":
        geometry.sizes = rng.uniform(0.02, 0.2, 3)
    elif kind == "sphere":
        geometry.sizes = rng.uniform(0.02, 0.2, 1)
    elif kind in ("capsule", "cylinder"):
        geometry.sizes = rng.uniform(0.02, 0.2, 2)
    elif kind == "ellipsoid":
        geometry.sizes = rng.uniform(0.02, 0.2, 3)
    elif kind == "rounded":
        geometry.points = hull_points(rng, str(rng.choice(["hull", "flat", "collinear"])))
        geometry.sizes = rng.uniform(0.005, 0.05, 1)
    elif kind == "compound":
        geometry.parts = tuple(hull_points(rng, "hull") + rng.uniform(-0.15, 0.15, 3)
                               for _ in range(int(rng.integers(2, 4))))  # fmt: skip
    elif kind == "mesh":
        # STL holds single precision: the points are what the file says.
        geometry.points = hull_points(rng, kind).astype(np.float32).astype(float)
        geometry.mesh_scale = rng.choice([0.5, 1.0, 2.0], 3)
        geometry.mesh_file = str(rng.choice(["stl", "obj", "package-stl"]))
    else:
        geometry.points = hull_points(rng, kind)
    return geometry


def geometry_names(link: str, count: int) -> List[str]:
    """As the URDF reader names a link's geometries: the link's name for one, ``link/k`` else."""
    return [link] if count == 1 else [f"{link}/{k}" for k in range(count)]


def random_model(rng: np.random.Generator, source: str, max_links: int = 7) -> ModelSpec:
    """A random robot that ``source`` can say, its root named ``world`` (MJCF's name for it)."""
    count = int(rng.integers(2, max_links + 1))
    links = ["world"] + [f"l{i}" for i in range(1, count)]
    chain = rng.random() < 0.5
    joints = [random_joint(rng, i, i - 1 if chain else int(rng.integers(i)),
                           ("revolute", "continuous", "prismatic", "fixed"))
              for i in range(1, count)]  # fmt: skip
    if not any(j.moving for j in joints):
        joints[-1] = random_joint(rng, count - 1, joints[-1].parent, ("revolute", "continuous"))
    geometries = []
    kinds = KINDS[source]
    for link, name in enumerate(links):
        own = int(rng.choice([0, 1, 1, 1, 2, 3]))
        for geometry_name in geometry_names(name, own):
            geometries.append(random_geometry(rng, geometry_name, link,
                                              str(rng.choice(kinds))))  # fmt: skip
    obstacles = []
    for k in range(int(rng.integers(0, 4))):
        obstacle = random_geometry(rng, f"obstacle{k}", -1, str(rng.choice(OBSTACLE_KINDS)))
        obstacle.xyz = rng.uniform(-1.2, 1.2, 3)
        obstacles.append(obstacle)
    owners = links + [o.name for o in obstacles]
    disabled = [tuple(str(n) for n in rng.choice(owners, 2, replace=False))
                for _ in range(int(rng.choice([0, 0, 1, 2])))]  # fmt: skip
    scale = float(10 ** rng.uniform(-6, 6)) if rng.random() < 0.25 else 1.0
    return scaled(ModelSpec(links, joints, geometries, obstacles, disabled, 1.0), scale)


def scaled(model: ModelSpec, scale: float) -> ModelSpec:
    """The model with every length times ``scale``: origins, sizes, points, prismatic limits."""

    def geometry(g: GeometrySpec) -> GeometrySpec:
        if g.kind == "mesh":  # the file's points stay, the URDF scales them
            return replace(g, xyz=g.xyz * scale, mesh_scale=g.mesh_scale * scale)
        points = None if g.points is None else g.points * scale
        return replace(g, xyz=g.xyz * scale, sizes=g.sizes * scale, points=points,
                       parts=tuple(p * scale for p in g.parts))

    def joint(j: JointSpec) -> JointSpec:
        factor = scale if j.kind == "prismatic" else 1.0
        return replace(j, xyz=j.xyz * scale, lower=j.lower * factor, upper=j.upper * factor)

    return ModelSpec(model.links, [joint(j) for j in model.joints],
                     [geometry(g) for g in model.geometries],
                     [geometry(g) for g in model.obstacles], model.disabled,
                     model.scale * scale)  # fmt: skip


# ----- bodies and poses, independently of the robot -------------------------------------------


def body_of(g: GeometrySpec) -> Any:
    """The body ``g`` says, built from its sizes (not read back from the robot)."""
    if g.kind == "box":
        return sc.Box(g.sizes)
    if g.kind == "sphere":
        return sc.Sphere(float(g.sizes[0]))
    if g.kind == "capsule":
        return sc.Capsule(float(g.sizes[0]), float(g.sizes[1]))
    if g.kind == "cylinder":
        return sc.Cylinder(float(g.sizes[0]), float(g.sizes[1]))
    if g.kind == "ellipsoid":
        return sc.Ellipsoid(g.sizes)
    if g.kind == "rounded":
        return sc.ConvexPolyhedron(g.points, radius=float(g.sizes[0]))
    if g.kind == "compound":
        return sc.CompoundBody(list(g.parts))
    if g.kind == "mesh":
        return sc.ConvexPolyhedron(g.points * g.mesh_scale)
    return sc.ConvexPolyhedron(g.points)


def reach(g: GeometrySpec) -> float:
    """The largest distance from the geometry's frame to a point of it."""
    if g.kind == "box":
        return float(np.linalg.norm(g.sizes))
    if g.kind in ("sphere", "ellipsoid"):
        return float(np.max(g.sizes))
    if g.kind == "capsule":
        return float(g.sizes.sum())
    if g.kind == "cylinder":
        return float(np.hypot(*g.sizes))
    if g.kind == "compound":
        return float(max(np.linalg.norm(p, axis=1).max() for p in g.parts))
    points = g.points * g.mesh_scale if g.kind == "mesh" else g.points
    return float(np.linalg.norm(points, axis=1).max()) + (float(g.sizes[0]) if g.kind == "rounded"
                                                          else 0.0)  # fmt: skip


def unit(axis: np.ndarray) -> np.ndarray:
    return axis / np.linalg.norm(axis)


def joint_motion(joint: JointSpec, value: float) -> np.ndarray:
    """The joint's motion at ``value``: a turn about its unit axis, or a slide along it."""
    motion = np.eye(4)
    axis = unit(joint.axis)
    if joint.kind in ("revolute", "continuous"):
        k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        motion[:3, :3] = np.eye(3) + np.sin(value) * k + (1 - np.cos(value)) * k @ k
    elif joint.kind == "prismatic":
        motion[:3, 3] = value * axis
    return motion


def link_transforms(model: ModelSpec, q: np.ndarray) -> List[np.ndarray]:
    """Every link's world transform at ``q`` (the moving joints' values in the model's order);
    a joint's child always comes after its parent here."""
    values = dict(zip((j.name for j in model.moving), q))
    transforms = [np.eye(4)] * len(model.links)
    for joint in model.joints:
        transforms[joint.child] = (transforms[joint.parent] @ transform(joint.xyz, joint.rpy)
                                   @ joint_motion(joint, values.get(joint.name, 0.0)))
    return transforms


def geometry_world_poses(model: ModelSpec, q: np.ndarray) -> Dict[str, np.ndarray]:
    links = link_transforms(model, q)
    poses = {g.name: links[g.link] @ transform(g.xyz, g.rpy) for g in model.geometries}
    poses.update({o.name: transform(o.xyz, o.rpy) for o in model.obstacles})
    return poses


def rigid_groups(model: ModelSpec) -> List[int]:
    """Each link's group: links joined by fixed joints are one rigid body."""
    group = list(range(len(model.links)))

    def find(i: int) -> int:
        while group[i] != i:
            i = group[i]
        return i

    for joint in model.joints:
        if not joint.moving:
            group[find(joint.child)] = find(joint.parent)
    return [find(i) for i in range(len(model.links))]


def geometric_parents(model: ModelSpec, group: List[int]) -> Dict[int, int]:
    """Each rigid group's parent group with geometry (-1: none): a group without geometry
    between two is looked through, as pair_filter.hpp documents (MoveIt's rule)."""
    parent = {group[j.child]: group[j.parent] for j in model.joints if j.moving}
    with_geometry = {group[g.link] for g in model.geometries}
    parents = {}
    for g in set(group):
        up = parent.get(g, -1)
        while up >= 0 and up not in with_geometry:
            up = parent.get(up, -1)
        parents[g] = up
    return parents


def mujoco_parents(model: ModelSpec, group: List[int]) -> Dict[int, int]:
    """Each rigid group's parent group (-1: none), none looked through: MuJoCo's welded bodies
    and their parents, as the census writes its MJCF (a body per link, fixed joints welded)."""
    parent = {group[j.child]: group[j.parent] for j in model.joints if j.moving}
    return {g: parent.get(g, -1) for g in set(group)}


def expected_pairs(model: ModelSpec, mjcf: bool = False) -> set:
    """The documented pairs: geometries of links that are not adjacent (one rigid group, or a
    group and its parent group with geometry), every obstacle against every link's geometry,
    less the disabled pairs of owners (link or obstacle names).

    For an MJCF file (``mjcf``), MuJoCo's contact filter between the links' geometries (the
    census writes default masks, no exclude and no explicit pair): geometries of different
    rigid groups that are not parent and child groups (none looked through), unless one group
    is the world's."""
    group = rigid_groups(model)
    parents = mujoco_parents(model, group) if mjcf else geometric_parents(model, group)
    disabled = {frozenset(pair) for pair in model.disabled}
    pairs = set()
    everything = model.geometries + model.obstacles
    for k, a in enumerate(everything):
        for b in everything[k + 1:]:
            if a.link < 0 and b.link < 0:
                continue
            if a.link >= 0 and b.link >= 0:
                ga, gb = group[a.link], group[b.link]
                related = parents[ga] == gb or parents[gb] == ga
                if mjcf and group[0] in (ga, gb):
                    related = False  # MuJoCo filters no child of the world
                if ga == gb or related:
                    continue
            owners = frozenset(model.links[g.link] if g.link >= 0 else g.name for g in (a, b))
            if owners not in disabled:
                pairs.add(frozenset((a.name, b.name)))
    return pairs


# ----- the robot, from tables, URDF or MJCF -------------------------------------------------


def robot_from_tables(model: ModelSpec) -> sc.Robot:
    joints = [sc.Joint(j.name, j.kind, j.parent, j.child, origin=transform(j.xyz, j.rpy),
                       axis=j.axis, lower=j.lower, upper=j.upper) for j in model.joints]
    geometries = [(g.name, g.link, transform(g.xyz, g.rpy), body_of(g)) for g in model.geometries]
    return sc.Robot(model.links, joints, geometries)


def floats(values: Any) -> str:
    return " ".join(repr(float(v)) for v in np.ravel(values))


def write_mesh(g: GeometrySpec, folder: Path) -> str:
    """Write ``g``'s mesh and return the filename its URDF says (relative, or package://)."""
    mesh = trimesh.convex.convex_hull(g.points)
    name = g.name.replace("/", "_")
    if g.mesh_file == "obj":
        lines = [f"v {floats(v)}" for v in mesh.vertices]
        lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in mesh.faces]
        (folder / "meshes").mkdir(exist_ok=True)
        (folder / "meshes" / f"{name}.obj").write_text("\n".join(lines) + "\n")
        return f"meshes/{name}.obj"
    packaged = g.mesh_file == "package-stl"
    where = folder / "pkg" / "meshes" if packaged else folder / "meshes"
    where.mkdir(parents=True, exist_ok=True)
    mesh.export(where / f"{name}.stl")
    return f"package://pkg/meshes/{name}.stl" if packaged else f"meshes/{name}.stl"


def urdf_geometry(g: GeometrySpec, folder: Path) -> str:
    if g.kind == "box":
        shape = f'<box size="{floats(2 * g.sizes)}"/>'
    elif g.kind == "sphere":
        shape = f'<sphere radius="{floats(g.sizes)}"/>'
    elif g.kind == "cylinder":
        shape = f'<cylinder radius="{floats(g.sizes[:1])}" length="{floats(2 * g.sizes[1:])}"/>'
    else:
        shape = f'<mesh filename="{write_mesh(g, folder)}" scale="{floats(g.mesh_scale)}"/>'
    return (f'<collision><origin xyz="{floats(g.xyz)}" rpy="{floats(g.rpy)}"/>'
            f"<geometry>{shape}</geometry></collision>")


def urdf_text(model: ModelSpec, folder: Path) -> str:
    """The model as URDF, its meshes written under ``folder`` (some as package://pkg/...)."""
    lines = ['<robot name="fuzz">']
    for link, name in enumerate(model.links):
        own = "".join(urdf_geometry(g, folder) for g in model.geometries if g.link == link)
        lines.append(f'<link name="{name}">{own}</link>')
    for j in model.joints:
        limit = (f'<limit lower="{j.lower!r}" upper="{j.upper!r}" effort="1" velocity="1"/>'
                 if j.kind in ("revolute", "prismatic") else "")
        lines.append(
            f'<joint name="{j.name}" type="{j.kind}"><parent link="{model.links[j.parent]}"/>'
            f'<child link="{model.links[j.child]}"/>'
            f'<origin xyz="{floats(j.xyz)}" rpy="{floats(j.rpy)}"/>'
            f'<axis xyz="{floats(j.axis)}"/>{limit}</joint>'
        )
    return "\n".join(lines + ["</robot>"])


def mjcf_quaternion(rpy: np.ndarray) -> str:
    x, y, z, w = Rotation.from_matrix(rpy_matrix(rpy)).as_quat()
    return floats([w, x, y, z])


MJCF_TYPES = {"box": "box", "sphere": "sphere", "capsule": "capsule", "cylinder": "cylinder",
              "ellipsoid": "ellipsoid"}  # fmt: skip


def mjcf_body(model: ModelSpec, link: int) -> str:
    """Link ``link``'s geoms and its children's bodies, each at its joint's origin."""
    parts = []
    for g in model.geometries:
        if g.link == link:
            parts.append(f'<geom name="{g.name}" type="{MJCF_TYPES[g.kind]}" '
                         f'size="{floats(g.sizes)}" pos="{floats(g.xyz)}" '
                         f'quat="{mjcf_quaternion(g.rpy)}"/>')  # fmt: skip
    for j in model.joints:
        if j.parent != link:
            continue
        joint = ""
        if j.moving:
            kind = "slide" if j.kind == "prismatic" else "hinge"
            limits = (f'limited="true" range="{j.lower!r} {j.upper!r}"' if j.kind != "continuous"
                      else 'limited="false"')
            joint = f'<joint name="{j.name}" type="{kind}" axis="{floats(j.axis)}" {limits}/>'
        parts.append(
            f'<body name="{model.links[j.child]}" pos="{floats(j.xyz)}" '
            f'quat="{mjcf_quaternion(j.rpy)}"><inertial pos="0 0 0" mass="1" '
            f'diaginertia="1 1 1"/>{joint}{mjcf_body(model, j.child)}</body>'
        )
    return "".join(parts)


def mjcf_text(model: ModelSpec) -> str:
    return ('<mujoco><compiler angle="radian"/><worldbody>'
            f"{mjcf_body(model, 0)}</worldbody></mujoco>")


def build_robot(model: ModelSpec, source: str, folder: Path) -> sc.Robot:
    """The robot ``source`` makes of ``model``, its obstacles added and its pairs disabled."""
    if source == "urdf":
        path = folder / "robot.urdf"
        path.write_text(urdf_text(model, folder))
        robot = sc.Robot.from_urdf(path, package_dirs=[folder])
    elif source == "mjcf":
        path = folder / "robot.xml"
        path.write_text(mjcf_text(model))
        robot = sc.Robot.from_mjcf(path)
    else:
        robot = robot_from_tables(model)
    for o in model.obstacles:
        robot.add_obstacle(body_of(o), transform(o.xyz, o.rpy), name=o.name)
    return robot.disable_pairs(model.disabled) if model.disabled else robot


def mujoco_geometry_poses(path: Path, q: np.ndarray) -> Dict[str, np.ndarray]:
    """MuJoCo's own world pose of every named geom at ``q`` (its qpos)."""
    compiled = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(compiled)
    data.qpos[:] = q
    mujoco.mj_kinematics(compiled, data)
    poses = {}
    for g in range(compiled.ngeom):
        pose = np.eye(4)
        pose[:3, :3] = data.geom_xmat[g].reshape(3, 3)
        pose[:3, 3] = data.geom_xpos[g]
        poses[compiled.geom(g).name] = pose
    return poses


# ----- configurations ---------------------------------------------------------------------------


def configurations(
    model: ModelSpec, rng: np.random.Generator, count: int, limits: str
) -> Tuple[np.ndarray, np.ndarray]:
    """(asked, admitted): ``count`` configurations in the model's joint order, and what they
    mean under ``limits``: inside the limits for "raise", some values past them for "clamp", and
    revolute values turned by whole turns for "wrap" (on joints whose range is under 2 pi, so
    that one turn at most brings a value within)."""
    asked = np.empty((count, len(model.moving)))
    admitted = np.empty_like(asked)
    for k, joint in enumerate(model.moving):
        if joint.kind == "continuous":
            turns = float(rng.choice([1.0, 1.0, 10.0, 1e3]))
            asked[:, k] = admitted[:, k] = rng.uniform(-np.pi, np.pi, count) * turns
            continue
        inside = rng.uniform(joint.lower, joint.upper, count)
        asked[:, k] = admitted[:, k] = inside
        width = joint.upper - joint.lower
        if limits == "clamp":
            past = inside + rng.choice([-2.0, 0.0, 2.0], count) * width
            asked[:, k], admitted[:, k] = past, np.clip(past, joint.lower, joint.upper)
        elif limits == "wrap" and joint.kind == "revolute" and width < 2 * np.pi:
            asked[:, k] = inside + 2 * np.pi * rng.integers(-3, 4, count)
    return asked, admitted


def robot_order(robot: sc.Robot, model: ModelSpec) -> np.ndarray:
    """The column of each of the robot's joints in the model's joint order."""
    names = [j.name for j in model.moving]
    return np.array([names.index(name) for name in robot.joint_names], dtype=int)


# ----- judging ------------------------------------------------------------------------------


@dataclass
class World:
    """The model's bodies, reaches and pair sizes, for the brute force."""

    model: ModelSpec
    bodies: Dict[str, Any]
    reaches: Dict[str, float]

    @classmethod
    def of(cls, model: ModelSpec) -> "World":
        everything = model.geometries + model.obstacles
        bodies = {g.name: body_of(g) for g in everything}
        # The library's bounding ball is centred on the body's box, not on its frame's origin.
        reaches = {g.name: max(reach(g), float(bodies[g.name].bounding_radius))
                   for g in everything}  # fmt: skip
        return cls(model, bodies, reaches)

    def size(self, a: str, b: str, poses: Dict[str, np.ndarray]) -> float:
        """At least the pair's size as queries measure it (the diameter of a ball around both:
        the distance between the bounding balls' centres, each within its reach of its frame,
        plus the larger diameter)."""
        apart = float(np.linalg.norm(poses[a][:3, 3] - poses[b][:3, 3]))
        return apart + 4 * (self.reaches[a] + self.reaches[b])

    def motion_size(self, a: str, b: str) -> float:
        """At least the pair's size as check_motion measures it (the sum of the bounding balls'
        diameters)."""
        return 2 * (self.reaches[a] + self.reaches[b])

    def rounding(self, poses: Dict[str, np.ndarray]) -> float:
        coordinates = max(
            (float(np.abs(p[:3, 3]).max()) + self.reaches[n] for n, p in poses.items()),
            default=0.0)
        return ROUNDING * max(coordinates, self.model.scale)

    def exact(self, a: str, b: str, poses: Dict[str, np.ndarray]) -> Tuple[float, float]:
        """(lower, upper) bounds on the pair's signed distance, by the exact method."""
        r = sc.signed_distance(self.bodies[a], self.bodies[b], pose_a=poses[a], pose_b=poses[b],
                               method="exact")  # fmt: skip
        return float(r.lower_bound), float(r.distance)


class Wrong(Exception):
    """A judged answer that breaks the contract: the message says how."""


def expect(condition: bool, message: str) -> None:
    if not condition:
        raise Wrong(message)


def same(a: Any, b: Any) -> bool:
    """Bitwise equal arrays (NaN equal to NaN), or equal values."""
    if a is None or b is None:
        return a is b
    return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=np.asarray(a).dtype.kind == "f")


CHECK_FIELDS = ("colliding", "min_distance", "lower_bound", "certified", "pair", "pair_names",
                "point_a", "point_b", "normal")  # fmt: skip


def judge_poses(robot: sc.Robot, model: ModelSpec, q: np.ndarray, admitted: np.ndarray,
                limits: str, mjcf: Optional[Path]) -> None:  # fmt: skip
    """forward_kinematics and geometry_poses against ours (and MuJoCo's, for MJCF)."""
    links = robot.forward_kinematics(q, limits=limits)
    geometry = robot.geometry_poses(q, limits=limits)
    names = robot.geometry_names
    for i, values in enumerate(admitted):
        mine = link_transforms(model, values)
        poses = geometry_world_poses(model, values)
        allowance = ROUNDING * max(1.0, max(float(np.abs(p[:3, 3]).max()) for p in mine),
                                   model.scale)  # fmt: skip
        for k, name in enumerate(robot.link_names):
            difference = np.abs(links[i, k] - mine[model.links.index(name)]).max()
            expect(difference <= allowance, f"row {i}: link '{name}' is {difference:.3g} off")
        for k, name in enumerate(names):
            difference = np.abs(geometry[i, k] - poses[name]).max()
            expect(difference <= allowance, f"row {i}: geometry '{name}' is {difference:.3g} off")
        if mjcf is not None:
            theirs = mujoco_geometry_poses(mjcf, values[robot_order_mjcf(robot, model)])
            for k, name in enumerate(names[: len(model.geometries)]):
                difference = np.abs(geometry[i, k] - theirs[name]).max()
                expect(difference <= allowance,
                       f"row {i}: geometry '{name}' is {difference:.3g} off MuJoCo's")


def robot_order_mjcf(robot: sc.Robot, model: ModelSpec) -> np.ndarray:
    """MuJoCo's qpos order is the robot's joint order (the bodies' depth-first order)."""
    return robot_order(robot, model)


def judge_pairs(robot: sc.Robot, model: ModelSpec, source: str) -> None:
    found = {frozenset(pair) for pair in robot.pairs}
    expect(len(found) == len(robot.pairs), f"a pair is listed twice: {robot.pairs}")
    wanted = expected_pairs(model, mjcf=source == "mjcf")
    extra, missing = found - wanted, wanted - found
    expect(not extra, f"pairs listed that are adjacent or disabled: {sorted(map(sorted, extra))}")
    expect(not missing, f"pairs missing: {sorted(map(sorted, missing))}")


def truth_table(world: World, robot: sc.Robot, admitted: np.ndarray) -> List[Dict[str, Any]]:
    """Per configuration: each pair's exact bounds, size and the rounding allowed."""
    rows = []
    for values in admitted:
        poses = geometry_world_poses(world.model, values)
        bounds = np.array([world.exact(a, b, poses) for a, b in robot.pairs]).reshape(-1, 2)
        sizes = np.array([world.size(a, b, poses) for a, b in robot.pairs])
        rows.append({"lower": bounds[:, 0], "upper": bounds[:, 1], "size": sizes,
                     "rounding": world.rounding(poses)})  # fmt: skip
    return rows


def judge_distances(distances: np.ndarray, truth: List[Dict[str, Any]], pairs: tuple) -> None:
    """Each pair's signed distance is an upper bound within tolerance x size of the exact one."""
    for i, row in enumerate(truth):
        slack = row["rounding"] + 1e-12 * row["size"]
        low = distances[i] < row["lower"] - slack
        high = distances[i] > row["upper"] + TOLERANCE * row["size"] + slack
        for p in np.flatnonzero(low | high):
            raise Wrong(f"row {i}: pair {pairs[p]} distance {distances[i, p]!r}, exact bounds "
                        f"[{row['lower'][p]!r}, {row['upper'][p]!r}], size {row['size'][p]:.3g}")


def judge_check(check: sc.RobotCheck, distances: np.ndarray, truth: List[Dict[str, Any]],
                robot: sc.Robot) -> bool:  # fmt: skip
    """The nearest pair against the brute force; returns whether every row is certified."""
    for i, row in enumerate(truth):
        where = f"row {i}"
        if not len(robot.pairs):
            expect(check.pair[i] == -1 and np.isinf(check.min_distance[i])
                   and not check.colliding[i], f"{where}: an answer without pairs")  # fmt: skip
            continue
        lower, upper, size = row["lower"], row["upper"], row["size"]
        slack = row["rounding"] + 1e-12 * size.max()
        least_lower, least_upper = lower.min(), upper.min()
        d, bound = check.min_distance[i], check.lower_bound[i]
        expect(d >= least_lower - slack, f"{where}: min_distance {d!r} below the exact minimum's "
               f"lower bound {least_lower!r}")
        expect(bound <= least_upper + slack, f"{where}: lower_bound {bound!r} above the exact "
               f"minimum {least_upper!r}")
        p = int(check.pair[i])
        expect(0 <= p < len(robot.pairs), f"{where}: pair {p} is not a pair")
        expect(tuple(check.pair_names[i]) == robot.pairs[p], f"{where}: pair names "
               f"{tuple(check.pair_names[i])} for pair {robot.pairs[p]}")
        expect(lower[p] <= d + slack,
               f"{where}: pair {robot.pairs[p]} is at least {lower[p]!r}, not {d!r}")
        expect(d == distances[i].min(), f"{where}: check's min_distance {d!r} is not the least "
               f"of distances, {distances[i].min()!r}")
        gap = np.linalg.norm(check.point_b[i] - check.point_a[i] - d * check.normal[i])
        expect(gap <= 1e-9 * size[p] + slack, f"{where}: point_b - point_a is {gap:.3g} off "
               "min_distance x normal")
        if not check.certified[i]:
            continue
        expect(d <= least_upper + TOLERANCE * size.max() + slack, f"{where}: certified "
               f"min_distance {d!r}, exact minimum {least_upper!r}")
        judge_verdict(bool(check.colliding[i]), lower, upper, size, slack, where)
    return bool(np.all(check.certified))


def judge_verdict(colliding: bool, lower: np.ndarray, upper: np.ndarray, size: np.ndarray,
                  slack: float, where: str) -> None:  # fmt: skip
    """A certified verdict: colliding when a pair overlaps, free when none is within tolerance
    x size of contact (in between, either)."""
    if colliding:
        expect((lower <= TOLERANCE * size + slack).any(), f"{where}: certified colliding, but "
               f"every pair is apart (exact lower bounds {lower.min()!r} and up)")
    else:
        expect((upper >= -slack).all(), f"{where}: certified free, but a pair overlaps by "
               f"{-upper.min()!r}")


def judge_verdict_alone(check: sc.RobotCheck, truth: List[Dict[str, Any]], robot: sc.Robot) -> bool:
    """``check(q, nearest=False)``: the pair named collides, none is named when free."""
    for i, row in enumerate(truth):
        where = f"nearest=False, row {i}"
        p = int(check.pair[i])
        expect(bool(check.colliding[i]) == (p >= 0), f"{where}: colliding "
               f"{check.colliding[i]} with pair {p}")
        expect(np.isnan(check.min_distance[i]), f"{where}: a min_distance {check.min_distance[i]}")
        if not len(robot.pairs) or not check.certified[i]:
            continue
        slack = row["rounding"] + 1e-12 * row["size"].max()
        judge_verdict(bool(check.colliding[i]), row["lower"], row["upper"], row["size"], slack,
                      where)
        if p >= 0:
            expect(row["lower"][p] <= TOLERANCE * row["size"][p] + slack, f"{where}: pair "
                   f"{robot.pairs[p]} named, its exact lower bound {row['lower'][p]!r}")
    return bool(np.all(check.certified))


def judge_batches(robot: sc.Robot, q: np.ndarray, limits: str, method: str) -> None:
    """Threads change nothing, and each single call is its row of the batch, bitwise."""
    one = robot.check(q, limits=limits, threads=1, method=method)
    two = robot.check(q, limits=limits, threads=2, method=method)
    for name in CHECK_FIELDS:
        expect(same(getattr(one, name), getattr(two, name)), f"check's {name} differs between "
               "1 and 2 threads")
    distances = robot.distances(q, limits=limits, threads=1, method=method)
    expect(same(distances, robot.distances(q, limits=limits, threads=2, method=method)),
           "distances differ between 1 and 2 threads")
    for i in range(len(q)):
        single = robot.check(q[i], limits=limits, method=method)
        for name in CHECK_FIELDS:
            expect(same(getattr(single, name), getattr(one, name)[i]),
                   f"check(q[{i}]).{name} is not row {i} of the batch's")
        expect(same(robot.distances(q[i], limits=limits, method=method), distances[i]),
               f"distances(q[{i}]) is not row {i} of the batch's")


def judge_check_case(rng: np.random.Generator, source: str, method: str, limits: str) -> str:
    """A random robot's check, distances and poses against brute force; returns the category."""
    model = random_model(rng, source)
    world = World.of(model)
    with tempfile.TemporaryDirectory() as folder:
        robot = build_robot(model, source, Path(folder))
        judge_pairs(robot, model, source)
        asked, admitted = configurations(model, rng, int(rng.integers(2, 6)), limits)
        order = robot_order(robot, model)
        q = asked[:, order]
        mjcf = Path(folder) / "robot.xml" if source == "mjcf" else None
        judge_poses(robot, model, q, admitted, limits, mjcf)
    truth = truth_table(world, robot, admitted)
    distances = robot.distances(q, limits=limits, method=method)
    judge_distances(distances, truth, robot.pairs)
    certified = judge_check(robot.check(q, limits=limits, method=method), distances, truth, robot)
    certified &= judge_verdict_alone(robot.check(q, limits=limits, method=method, nearest=False),
                                     truth, robot)  # fmt: skip
    judge_batches(robot, q, limits, method)
    return "ok" if certified else "uncertified"


# ----- motions --------------------------------------------------------------------------------


def support_point(body: Any, pose: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """The body's farthest point along ``direction`` in the world, at ``pose``."""
    local = np.asarray(body.support(pose[:3, :3].T @ direction), dtype=float).ravel()
    return pose[:3, :3] @ local + pose[:3, 3]


def place_ball(model: ModelSpec, world: World, q: np.ndarray, rng: np.random.Generator,
               gap: float) -> Optional[GeometrySpec]:  # fmt: skip
    """A ball obstacle ``gap`` x the model's scale from a random link geometry's support point at
    ``q`` (negative: overlapping it), or None when no link geometry has a support function."""
    candidates = [g for g in model.geometries if g.kind != "compound"]
    if not candidates:
        return None
    target = candidates[int(rng.integers(len(candidates)))]
    direction = unit(rng.normal(size=3))
    pose = geometry_world_poses(model, q)[target.name]
    point = support_point(world.bodies[target.name], pose, direction)
    radius = 0.05 * model.scale
    ball = GeometrySpec("ball", -1, "sphere", point + direction * (radius + gap), np.zeros(3),
                        sizes=np.array([radius]))  # fmt: skip
    return ball


def motion_ends(model: ModelSpec, world: World, rng: np.random.Generator,
                kind: str) -> Tuple[ModelSpec, np.ndarray, np.ndarray]:  # fmt: skip
    """(model, q0, q1) in the model's joint order for a motion of ``kind``; a grazing or
    starting-in-contact motion adds its ball obstacle to the model."""
    q0, _ = configurations(model, rng, 1, "raise")
    q1, _ = configurations(model, rng, 1, "raise")
    q0, q1 = q0[0], q1[0]
    if kind == "still":
        q1 = q0.copy()
    if kind == "turns":
        for k, joint in enumerate(model.moving):
            if joint.kind == "continuous":
                q1[k] = q0[k] + 2 * np.pi * float(rng.integers(-20, 21)) + rng.uniform(-1, 1)
    ball = None
    if kind == "graze":
        t = float(rng.uniform(0.2, 0.9))
        size = max(world.reaches.values()) if world.reaches else model.scale
        gap = float(rng.choice([0.0, 1e-12, 1e-10, 1e-9, 1e-7, -1e-9])) * size
        ball = place_ball(model, world, q0 + t * (q1 - q0), rng, gap)
    elif kind == "start-in-contact":
        ball = place_ball(model, world, q0, rng, -0.01 * model.scale)
    if ball is not None:
        model = replace(model, obstacles=model.obstacles + [ball])
    if kind == "far":
        model = moved(model, unit(rng.normal(size=3)) * 10 ** rng.uniform(3, 6) * model.scale)
    return model, q0, q1


def moved(model: ModelSpec, offset: np.ndarray) -> ModelSpec:
    """The model with its root, and so everything, and its obstacles moved by ``offset``."""
    return replace(
        model,
        joints=[replace(j, xyz=j.xyz + offset) if j.parent == 0 else j for j in model.joints],
        geometries=[replace(g, xyz=g.xyz + offset) if g.link == 0 else g
                    for g in model.geometries],
        obstacles=[replace(o, xyz=o.xyz + offset) for o in model.obstacles],
    )  # fmt: skip


def judge_motion(robot: sc.Robot, world: World, q0: np.ndarray, q1: np.ndarray, result: Any,
                 where: str) -> bool:  # fmt: skip
    """One motion against dense sampling; returns whether it is certified."""
    t_lower, t_upper = float(result.t_lower), float(result.t_upper)
    expect(0 <= t_lower <= t_upper <= 1, f"{where}: t in [{t_lower!r}, {t_upper!r}]")
    pairs = robot.pairs
    if not pairs:
        expect(not result.touches, f"{where}: touches without pairs")
        return bool(result.certified)
    times = np.linspace(0, 1, SAMPLES)
    if result.touches:
        times = np.union1d(times, np.linspace(0, t_lower, SAMPLES, endpoint=False))
    configurations_along = q0 + np.outer(times, q1 - q0)
    distances = robot.distances(configurations_along, limits="clamp", method="exact",
                                tolerance=1e-12)  # fmt: skip
    sizes = np.array([world.motion_size(a, b) for a, b in pairs])
    rounding = max(world.rounding(world_poses(robot, q)) for q in (q0, q1))
    overlap = distances < -(TOLERANCE * sizes + rounding + 1e-12 * sizes)
    before = overlap[times < t_lower].any(axis=1)
    expect(not before.any(), f"{where}: overlap at t = {times[times < t_lower][before][:1]} "
           f"before t_lower = {t_lower!r}")
    if not result.certified:
        return False
    if not result.touches:
        expect(not overlap.any(), f"{where}: certified free, overlap at t = "
               f"{times[overlap.any(axis=1)][:1]}")
        expect(same(result.q, q1), f"{where}: a free motion's q is not q1")
        return True
    expect(t_upper - t_lower <= TIME_TOLERANCE * (1 + 1e-9), f"{where}: bracket "
           f"[{t_lower!r}, {t_upper!r}] wider than the time tolerance")
    p = int(result.pair)
    expect(0 <= p < len(pairs) and tuple(result.pair_names) == pairs[p], f"{where}: pair {p}")
    expected_q = q0 + t_upper * (q1 - q0)
    expect(np.abs(result.q - expected_q).max() <= 1e-12 * max(1.0, np.abs(expected_q).max()),
           f"{where}: q is not q0 + t_upper (q1 - q0)")
    poses = world_poses(robot, np.asarray(result.q))
    lower, _ = world.exact(*pairs[p], poses)
    allowed = TOLERANCE * sizes[p] + rounding + 1e-12 * sizes[p]
    expect(lower <= allowed, f"{where}: pair {pairs[p]} at t_upper is at least {lower!r} apart, "
           f"more than tolerance x size {allowed:.3g}")
    return True


def world_poses(robot: sc.Robot, q: np.ndarray) -> Dict[str, np.ndarray]:
    """The robot's own geometry poses at q (the check family judges them against ours)."""
    return dict(zip(robot.geometry_names, robot.geometry_poses(q, limits="clamp")))


MOTION_FIELDS = ("touches", "t_lower", "t_upper", "q", "pair", "pair_names", "distance",
                 "point_a", "point_b", "normal", "certified", "iterations")  # fmt: skip


def judge_motion_batches(robot: sc.Robot, q0: np.ndarray, q1: np.ndarray) -> Any:
    """The batch at 1 and 2 threads and each single motion agree bitwise; returns the batch."""
    one = robot.check_motion(q0, q1, threads=1)
    two = robot.check_motion(q0, q1, threads=2)
    for name in MOTION_FIELDS + ("status",):
        expect(same(getattr(one, name), getattr(two, name)), f"check_motion's {name} differs "
               "between 1 and 2 threads")
    for i in range(len(q0)):
        single = robot.check_motion(q0[i], q1[i])
        for name in MOTION_FIELDS + ("status",):
            expect(same(getattr(single, name), np.asarray(getattr(one, name))[i]),
                   f"check_motion(q0[{i}], q1[{i}]).{name} is not row {i} of the batch's")
    return one


def judge_motion_case(rng: np.random.Generator, source: str, kind: str) -> str:
    """A random robot's motions of ``kind`` and two random ones, against dense sampling."""
    model = random_model(rng, source, max_links=5)
    if kind == "turns" and not any(j.kind == "continuous" for j in model.moving):
        model.joints[-1] = replace(model.joints[-1], kind="continuous", lower=0.0, upper=0.0)
    world = World.of(model)
    model, q0, q1 = motion_ends(model, world, rng, kind)
    world = World.of(model)
    others = [configurations(model, rng, 2, "raise")[0] for _ in range(2)]
    starts, ends = np.vstack([q0, others[0]]), np.vstack([q1, others[1]])
    with tempfile.TemporaryDirectory() as folder:
        robot = build_robot(model, source, Path(folder))
    order = robot_order(robot, model)
    starts, ends = starts[:, order], ends[:, order]
    batch = judge_motion_batches(robot, starts, ends)
    certified = True
    for i in range(len(starts)):
        row = SimpleRow(batch, i)
        certified &= judge_motion(robot, world, starts[i], ends[i], row, f"motion {i}")
    return "ok" if certified else "uncertified"


class SimpleRow:
    """Row ``i`` of a batched RobotMotion, read as a single motion's fields."""

    def __init__(self, batch: Any, i: int) -> None:
        for name in MOTION_FIELDS:
            setattr(self, name, np.asarray(getattr(batch, name))[i])
        self.status = batch.status[i]


# ----- bad input ------------------------------------------------------------------------------

BASE_URDF = """\
<robot name="bad">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="0 0 0.3"/>
    <geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="hand"><collision><geometry><mesh filename="hand.stl"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.2" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="slide" type="prismatic"><parent link="arm"/><child link="hand"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.3" effort="1" velocity="1"/></joint>
</robot>
"""
"""A valid URDF the bad files are edits of: base, arm (shoulder), hand (slide, a mesh)."""

BAD_URDF = {
    "joint names an absent link": ('<child link="hand"/>', '<child link="ghost"/>', ("'ghost'",)),
    "joints form a cycle": ('<parent link="base"/>', '<parent link="hand"/>', ("cycle",)),
    "NaN joint origin": ('xyz="0 0 0.2"', 'xyz="0 nan 0.2"', ("shoulder",)),
    "NaN joint rpy": ('rpy="0 0 0"', 'rpy="0 nan 0"', ("shoulder",)),
    "zero axis": ('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>', ("shoulder",)),
    "NaN axis": ('<axis xyz="0 1 0"/>', '<axis xyz="nan 1 0"/>', ("shoulder",)),
    "lower above upper": ('lower="-2" upper="2"', 'lower="2" upper="-2"', ("shoulder",)),
    "NaN limit": ('lower="-2" upper="2"', 'lower="nan" upper="2"', ("shoulder",)),
    "floating joint": ('type="revolute"', 'type="floating"', ("shoulder",)),
    "negative sphere radius": ('radius="0.1"', 'radius="-0.1"', ("'arm'",)),
    "NaN sphere radius": ('radius="0.1"', 'radius="nan"', ("'arm'",)),
    "zero box size": ('size="0.2 0.2 0.2"', 'size="0.2 0 0.2"', ("'base'",)),
    "NaN collision origin": ('xyz="0 0 0.3"', 'xyz="0 0 nan"', ("'arm'",)),
    "empty geometry": ('<geometry><sphere radius="0.1"/></geometry>', "<geometry></geometry>",
                       ("'arm'",)),
    "mesh file missing": ('filename="hand.stl"', 'filename="gone.stl"', ("'hand'",)),
    "package:// unresolved": ('filename="hand.stl"', 'filename="package://nopkg/hand.stl"',
                              ("'hand'",)),
    "unreadable mesh": ('filename="hand.stl"', 'filename="garbage.stl"', ("'hand'",)),
    "empty mesh": ('filename="hand.stl"', 'filename="empty.obj"', ("'hand'",)),
    "flat mesh": ('filename="hand.stl"', 'filename="flat.obj"', ("'hand'",)),
    "NaN mesh scale": ('filename="hand.stl"', 'filename="hand.stl" scale="nan 1 1"', ("'hand'",)),
    "truncated XML": ('<joint name="slide"', '<joint name="slide" <', ("cannot read URDF",)),
}  # fmt: skip
"""A URDF edit (old, new) and the fragments one of which the error must hold: the joint, link
or file at fault."""

BASE_MJCF = """\
<mujoco><compiler angle="radian"/><worldbody>
  <geom name="floor" type="box" size="1 1 0.01"/>
  <body name="arm" pos="0 0 0.5"><joint name="turn" type="hinge" axis="0 1 0" range="-2 2"/>
    <geom name="stick" type="capsule" size="0.05 0.3" pos="0 0 0.3"/></body>
</worldbody></mujoco>
"""

BAD_MJCF = {
    "ball joint": ('type="hinge" axis="0 1 0" range="-2 2"', 'type="ball"', ("'turn'",)),
    "free joint": ('<joint name="turn" type="hinge" axis="0 1 0" range="-2 2"/>',
                   '<freejoint name="turn"/>', ("'turn'",)),
    "plane": ('type="box" size="1 1 0.01"', 'type="plane" size="1 1 0.01"', ("skip_planes",)),
    "mesh file missing": ('<worldbody>', '<asset><mesh name="m" file="gone.stl"/></asset>'
                          '<worldbody><geom type="mesh" mesh="m"/>', ("gone.stl",)),
    "zero axis": ('axis="0 1 0"', 'axis="0 0 0"', ("axis", "turn")),
    "malformed XML": ("</mujoco>", "</mujoc>", ("cannot compile",)),
}  # fmt: skip


def urdf_robot(folder: Path, old: str = "", new: str = "") -> sc.Robot:
    """BASE_URDF with ``old`` replaced by ``new``, its meshes (and bad ones) beside it."""
    trimesh.creation.box((0.05, 0.05, 0.1)).export(folder / "hand.stl")
    (folder / "garbage.stl").write_bytes(b"\x00\xff" * 50)
    (folder / "empty.obj").write_text("")
    (folder / "flat.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
    path = folder / "bad.urdf"
    path.write_text(BASE_URDF.replace(old, new) if old else BASE_URDF)
    return sc.Robot.from_urdf(path)


def mjcf_robot(folder: Path, old: str, new: str) -> sc.Robot:
    path = folder / "bad.xml"
    path.write_text(BASE_MJCF.replace(old, new))
    return sc.Robot.from_mjcf(path)


def small_tables(**changes: Any) -> sc.Robot:
    """Two links on a revolute joint 'j1', a box 'g' on each; ``changes`` replace the joint's
    keywords (``joint``), the geometries (``geometries``) or the links (``links``)."""
    joint = dict(name="j1", type="revolute", parent=0, child=1, origin=np.eye(4),
                 axis=[0, 0, 1], lower=-1, upper=1)  # fmt: skip
    joint.update(changes.get("joint", {}))
    geometries = changes.get("geometries", [("g", 0, None, sc.Box([0.1] * 3)),
                                            ("h", 1, np.eye(4), sc.Box([0.1] * 3))])
    return sc.Robot(changes.get("links", ["a", "b"]), [sc.Joint(**joint)], geometries)


def _stretched() -> np.ndarray:
    return np.diag([2.0, 1.0, 1.0, 1.0])


def _nan_translation() -> np.ndarray:
    pose = np.eye(4)
    pose[0, 3] = np.nan
    return pose


BAD_TABLES: Dict[str, Tuple[Callable[[], Any], Tuple[str, ...]]] = {
    "child index out of range": (lambda: small_tables(joint={"child": 5}), ("'j1'",)),
    "geometry on an absent link": (
        lambda: small_tables(geometries=[("g", 7, None, sc.Box([0.1] * 3))]), ("'g'",)),
    "two roots": (lambda: sc.Robot(["a", "b", "c"], [sc.Joint("j1", "fixed", 0, 1)], []),
                  ("parent",)),
    "stretched joint origin": (lambda: small_tables(joint={"origin": _stretched()}), ("'j1'",)),
    "NaN joint origin": (lambda: small_tables(joint={"origin": _nan_translation()}), ("'j1'",)),
    "NaN geometry origin": (
        lambda: small_tables(geometries=[("g", 0, _nan_translation(), sc.Box([0.1] * 3))]),
        ("'g'",)),
    "geometry not a body": (lambda: small_tables(geometries=[("g", 0, None, "box")]), ("'g'",)),
    "NaN hull point": (
        lambda: small_tables(geometries=[("g", 0, None, np.full((4, 3), np.nan))]), ("'g'",)),
    "links named alike": (lambda: small_tables(links=["a", "a"]), ("'a'",)),
    "geometries named alike": (
        lambda: small_tables(geometries=[("g", 0, None, sc.Sphere(1.0)),
                                         ("g", 1, None, sc.Sphere(1.0))]), ("'g'",)),
    "infinite axis": (lambda: small_tables(joint={"axis": [np.inf, 0, 0]}), ("'j1'",)),
    "axis of two numbers": (lambda: small_tables(joint={"axis": [1.0, 0.0]}), ("'j1'",)),
    "planar joint": (lambda: small_tables(joint={"type": "planar"}), ("'j1'",)),
    "negative sphere": (lambda: sc.Sphere(-1.0), ("radius",)),
    "zero ellipsoid radius": (lambda: sc.Ellipsoid([1.0, 0.0, 1.0]), ("radii",)),
    "NaN rounding radius": (lambda: sc.ConvexPolyhedron(np.eye(3), radius=np.nan), ("radius",)),
    "obstacle named like a link": (
        lambda: small_tables().add_obstacle(sc.Sphere(0.1), name="a"), ("'a'",)),
    "obstacle at a NaN pose": (
        lambda: small_tables().add_obstacle(sc.Sphere(0.1), _nan_translation(), name="z"),
        ("'z'",)),
    "disabled pair names an absent link": (
        lambda: small_tables().disable_pairs([("a", "ghost")]), ("'ghost'",)),
    "disabled pair of three names": (
        lambda: small_tables().disable_pairs([("a", "b", "a")]), ("pair", "('a', 'b', 'a')")),
    "disabled pairs as one string": (lambda: small_tables().disable_pairs("ab"), ("pair",)),
}  # fmt: skip
"""Tables a robot must refuse: (the call, fragments one of which its error must hold)."""

BAD_CALLS: Dict[str, Tuple[Callable[[sc.Robot], Any], Tuple[str, ...]]] = {
    "q too long": (lambda r: r.check([0.0, 0.0, 0.0]), ("q ",)),
    "q NaN": (lambda r: r.distances([[0.0, 0.0], [np.nan, 0.0]]), ("q[1]",)),
    "q infinite, clamped": (lambda r: r.check([np.inf, 0.0], limits="clamp"), ("q[0]",)),
    "q of 3 dimensions": (lambda r: r.check(np.zeros((2, 2, 2))), ("q ",)),
    "q of strings": (lambda r: r.check(["a", "b"]), ("q ",)),
    "q None": (lambda r: r.forward_kinematics(None), ("q ",)),
    "q outside the limits": (lambda r: r.check([2.5, 0.0]), ("'shoulder'",)),
    "prismatic wrapped": (lambda r: r.geometry_poses([0.0, 0.9], limits="wrap"), ("'slide'",)),
    "limits='bounce'": (lambda r: r.check([0.0, 0.0], limits="bounce"), ("limits",)),
    "threads=0": (lambda r: r.check([0.0, 0.0], threads=0), ("threads",)),
    "threads=-1": (lambda r: r.distances([0.0, 0.0], threads=-1), ("threads",)),
    "threads=1.5": (lambda r: r.check([0.0, 0.0], threads=1.5), ("threads",)),
    "threads='2'": (lambda r: r.check([0.0, 0.0], threads="2"), ("threads",)),
    "threads=2**40": (lambda r: r.check([0.0, 0.0], threads=2**40), ("threads",)),
    "method='nope'": (lambda r: r.check([0.0, 0.0], method="nope"), ("method",)),
    "method='ipso'": (lambda r: r.check([0.0, 0.0], method="ipso"), ("method",)),
    "tolerance=-1": (lambda r: r.check([0.0, 0.0], tolerance=-1.0), ("tolerance",)),
    "tolerance=NaN": (lambda r: r.distances([0.0, 0.0], tolerance=np.nan), ("tolerance",)),
    "gradient without nearest": (
        lambda r: r.check([0.0, 0.0], nearest=False, gradient=True), ("nearest",)),
    "motion time_tolerance=0": (
        lambda r: r.check_motion([0.0, 0.0], [1.0, 0.1], time_tolerance=0.0), ("time_tolerance",)),
    "motion time_tolerance=NaN": (
        lambda r: r.check_motion([0.0, 0.0], [1.0, 0.1], time_tolerance=np.nan),
        ("time_tolerance",)),
    "motion max_iterations=0": (
        lambda r: r.check_motion([0.0, 0.0], [1.0, 0.1], max_iterations=0), ("max_iterations",)),
    "motion max_iterations=1.5": (
        lambda r: r.check_motion([0.0, 0.0], [1.0, 0.1], max_iterations=1.5),
        ("max_iterations",)),
    "motion rows differ": (
        lambda r: r.check_motion(np.zeros((2, 2)), np.zeros((3, 2))), ("q0", "q1")),
    "motion wrapped": (lambda r: r.check_motion([0.0, 0.0], [1.0, 0.1], limits="wrap"),
                       ("wrap",)),
    "motion method='libccd'": (
        lambda r: r.check_motion([0.0, 0.0], [1.0, 0.1], method="libccd"), ("libccd",)),
    "motion q1 NaN": (lambda r: r.check_motion([0.0, 0.0], [np.nan, 0.1]), ("q1",)),
    "motion threads=0": (lambda r: r.check_motion([0.0, 0.0], [1.0, 0.1], threads=0),
                         ("threads",)),
    "propose 0 samples": (lambda r: r.propose_disabled_pairs(0), ("samples",)),
}  # fmt: skip
"""Calls on BASE_URDF's robot (q = (shoulder, slide)) that must be refused naming the
argument: (the call, fragments one of which its error must hold)."""

BAD_INPUTS = (
    [("urdf", name) for name in BAD_URDF] + [("mjcf", name) for name in BAD_MJCF]
    + [("tables", name) for name in BAD_TABLES] + [("call", name) for name in BAD_CALLS]
)
"""Every bad input: (group, name)."""

UNCLEAR = ("incompatible function arguments", "unpack", "list index out of range")
"""Fragments of messages that say what went wrong inside, not what the user passed wrong."""


def bad_call(group: str, name: str, folder: Path) -> Tuple[Callable[[], Any], Tuple[str, ...]]:
    """The call that must fail, and the fragments one of which its message must hold."""
    if group == "urdf":
        old, new, fragments = BAD_URDF[name]
        return lambda: urdf_robot(folder, old, new), fragments
    if group == "mjcf":
        old, new, fragments = BAD_MJCF[name]
        return lambda: mjcf_robot(folder, old, new), fragments
    if group == "tables":
        return BAD_TABLES[name]
    call, fragments = BAD_CALLS[name]
    robot = urdf_robot(folder)
    return lambda: call(robot), fragments


def judge_bad_input(group: str, name: str) -> Tuple[str, str]:
    """ok for a ValueError or TypeError naming what is wrong; error-type for another exception
    or a message that does not say; slipped for an answer."""
    with tempfile.TemporaryDirectory() as folder:
        call, fragments = bad_call(group, name, Path(folder))
        try:
            call()
        except (ValueError, TypeError) as error:
            text = f"{type(error).__name__}: {error}"
            if any(f in str(error) for f in UNCLEAR) or not any(f in str(error) for f in fragments):
                return "error-type", f"unclear (names none of {fragments}): {text[:200]}"
            return "ok", text[:200]
        except Exception as error:  # noqa: BLE001 - every other exception is the wrong type
            return "error-type", f"{type(error).__name__}: {str(error)[:200]}"
    return "slipped", f"{group}: {name} was accepted"


# ----- the census's robot surface -------------------------------------------------------------


def robot_case(seed: int, index: int) -> Tuple[str, str, str, tuple]:
    """(family, query, label, arguments) of case ``index`` of corpus ``seed``; ``run_robot_case``
    draws the rest of the case from the same generator, after these draws."""
    rng = np.random.default_rng([seed, index, 31])
    family = FAMILY_CYCLE[index % len(FAMILY_CYCLE)]
    source = SOURCES[int(rng.integers(len(SOURCES)))]
    if family == "check":
        method = ("dual", "exact")[int(rng.integers(2))]
        limits = ("raise", "raise", "clamp", "wrap")[int(rng.integers(4))]
        return family, f"check {method}", source, (source, method, limits)
    if family == "motion":
        kind = MOTIONS[int(rng.integers(len(MOTIONS)))]
        return family, f"motion {kind}", source, (source, kind)
    group, name = BAD_INPUTS[int(rng.integers(len(BAD_INPUTS)))]
    return family, "argument", group, (group, name)


def case_generator(seed: int, index: int) -> np.random.Generator:
    """The case's generator, past ``robot_case``'s draws."""
    rng = np.random.default_rng([seed, index, 31])
    family = FAMILY_CYCLE[index % len(FAMILY_CYCLE)]
    rng.integers(len(SOURCES))
    rng.integers(2 if family == "check" else len(MOTIONS) if family == "motion"
                 else len(BAD_INPUTS))  # fmt: skip
    if family == "check":
        rng.integers(4)
    return rng


def run_robot_case(seed: int, index: int) -> Dict[str, Any]:
    """Make and judge robot case ``index``: ``{"category", "reason"}`` (fuzz_judge's)."""
    family, _, _, arguments = robot_case(seed, index)
    rng = case_generator(seed, index)
    try:
        if family == "check":
            category, reason = judge_check_case(rng, *arguments), ""
        elif family == "motion":
            category, reason = judge_motion_case(rng, *arguments), ""
        else:
            category, reason = judge_bad_input(*arguments)
    except Wrong as wrong:
        category, reason = "wrong", str(wrong)
    except Exception as error:  # noqa: BLE001 - the library's or this suite's, told apart
        category = "error-type" if raised_by_the_library(error) else "suite-error"
        where = traceback.extract_tb(error.__traceback__)[-1]
        reason = (f"an answer was due: {type(error).__name__}: {error} "
                  f"(at {Path(where.filename).name}:{where.lineno})")
    return {"category": category, "reason": reason[:600]}


def raised_by_the_library(error: Exception) -> bool:
    """Whether ``error`` came from swarmcollide (its Python, or a call into its core or parsers),
    not from a bug of this judge."""
    frames = traceback.extract_tb(error.__traceback__)
    if any("swarmcollide" in Path(frame.filename).parts for frame in frames):
        return True
    line = frames[-1].line or ""
    return any(call in line for call in ("robot.", "sc.", "Robot", "_core."))
