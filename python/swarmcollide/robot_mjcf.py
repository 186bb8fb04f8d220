"""MJCF models compiled by MuJoCo (the ``[robot]`` extra), as the tables of a ``Robot``."""

from __future__ import annotations

import os
import warnings
from pathlib import Path
from typing import Optional, Union
from xml.etree import ElementTree

import numpy as np

from . import _core
from .robot_mjcf_pairs import checked_geom_pairs, contacts_switched_off
from .robot_tables import ModelTables, geometry_names

PathLike = Union[str, "os.PathLike[str]"]


def _mujoco():
    try:
        import mujoco
    except ImportError as error:  # pragma: no cover - the [robot] extra is installed in tests
        raise ImportError("reading MJCF needs mujoco: pip install 'swarmcollide[robot]'") from error
    return mujoco


def _transform(position, quaternion=None) -> np.ndarray:
    mujoco = _mujoco()
    transform = np.eye(4)
    if quaternion is not None:
        rotation = np.zeros(9)
        mujoco.mju_quat2Mat(rotation, np.asarray(quaternion, dtype=float))
        transform[:3, :3] = rotation.reshape(3, 3)
    transform[:3, 3] = position
    return transform


def load_mjcf(path: PathLike, skip_planes: bool = False) -> ModelTables:
    """The bodies, joints and collision geoms of an MJCF file, compiled by MuJoCo.

    See ``Robot.from_mjcf`` for the parameters.
    """
    # As the core checks its flags (to_bool): "no" or 0 is no answer to a yes-or-no question.
    if not isinstance(skip_planes, (bool, np.bool_)):
        raise TypeError(f"skip_planes must be True or False, got {type(skip_planes).__name__}")
    mujoco = _mujoco()
    if Path(path).is_dir():
        raise ValueError(f"MJCF file '{path}' is a directory; pass the model's .xml file")
    if not Path(path).is_file():
        raise ValueError(f"MJCF file '{path}' not found")
    not_mjcf = _not_mjcf(Path(path))
    if not_mjcf:
        raise ValueError(f"'{path}' does not look like an MJCF file: {not_mjcf}")
    try:
        model = mujoco.MjModel.from_xml_path(str(path))
    except Exception as error:  # MuJoCo's compiler raises ValueError with its own message
        raise ValueError(f"cannot compile MJCF file '{path}': {error}") from error
    flag = contacts_switched_off(model)
    if flag:
        # Followed, as MuJoCo follows it, but said: a robot that never collides with itself is
        # more often a model meant for another use than the user's intent.
        warnings.warn(f"MJCF file '{path}' switches contacts off (<option><flag {flag}="
                      f"\"disable\"/>): MuJoCo checks none of its geom pairs, and neither does "
                      f"this robot; its geometries are checked only against obstacles "
                      f"(add_obstacle)", UserWarning, stacklevel=3)
    return tables_of(model, skip_planes)


def _not_mjcf(path: Path) -> Optional[str]:
    """What says a file is no MJCF model, or None: its root element, unless it is ``<mujoco>``.
    MuJoCo compiles a URDF file (root ``<robot>``) with its own importer into another robot
    (mimic joints free, links on fixed joints fused into their parents). A file that is not
    XML is left to MuJoCo, whose reader says where."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError):
        return None
    tag = root.tag.rpartition("}")[2]  # without a namespace
    if tag == "mujoco":
        return None
    hint = {"robot": "; it is a URDF model: read it with Robot.from_urdf (swarmcollide robot "
                     "reads a file ending in .urdf as URDF)"}
    return f"its root element is <{tag}>, where an MJCF model's is <mujoco>{hint.get(tag, '')}"


def body_name(model, body: int) -> str:
    """A body's name, ``body{i}`` when it has none (the world body is ``world``)."""
    return model.body(body).name or f"body{body}"


def tables_of(model, skip_planes: bool = False) -> ModelTables:
    """The tables of a compiled ``mujoco.MjModel``: one link per body, a joint per hinge or
    slide, and a link between two joints of one body (its joints turn about their own anchors)."""
    mujoco = _mujoco()
    links = [body_name(model, b) for b in range(model.nbody)]
    joints = []
    body_link = list(range(model.nbody))
    for b in range(1, model.nbody):
        parent = body_link[model.body_parentid[b]]
        offset = _transform(model.body_pos[b], model.body_quat[b])
        first = model.body_jntadr[b]
        count = model.body_jntnum[b]
        for j in range(first, first + count):
            name = model.joint(j).name or f"joint{j}"
            kind = int(model.jnt_type[j])
            hinge = kind == int(mujoco.mjtJoint.mjJNT_HINGE)
            if not hinge and kind != int(mujoco.mjtJoint.mjJNT_SLIDE):
                raise ValueError(
                    f"joint '{name}' of body '{links[b]}': free and ball joints are not "
                    "supported; a robot's joints must be hinges or slides"
                )
            anchor = np.asarray(model.jnt_pos[j], dtype=float)
            last = j == first + count - 1
            # A hinge turns the body about its anchor: the joint frame sits at the anchor, and the
            # body's frame is back by the anchor from it (a link of its own unless it is the last
            # joint's child and the anchor is the body's origin).
            if last and not anchor.any():
                child = b
            else:
                child = len(links)
                links.append(f"{links[b]}/{name}")
            limited = bool(model.jnt_limited[j])
            lower, upper = (model.jnt_range[j] if limited else (-np.inf, np.inf))
            joint_type = ("revolute" if limited else "continuous") if hinge else "prismatic"
            joints.append(_core.Joint(
                name, joint_type, parent, child, origin=offset @ _transform(anchor),
                axis=np.asarray(model.jnt_axis[j], dtype=float), lower=float(lower),
                upper=float(upper), reference=float(model.qpos0[model.jnt_qposadr[j]])))
            offset = _transform(-anchor)
            parent = child
        if parent != b:
            joints.append(_core.Joint(f"{links[b]}/fixed", "fixed", parent, b, origin=offset))
    geometries = []
    geom_pairs = checked_geom_pairs(model)
    # A geom in a <contact><pair> collides whatever its masks say.
    paired = {g for pair in geom_pairs for g in pair}
    collision = [g for g in range(model.ngeom)
                 if model.geom_contype[g] != 0 or model.geom_conaffinity[g] != 0 or g in paired]
    geometry_of = {}
    # An unnamed geom is named after its body (geometry_names), but geom and body names are apart
    # in MuJoCo: when another geom has that name, it takes the first `body/k` none has.
    taken = {model.geom(g).name for g in collision}
    for b in range(model.nbody):
        own = [g for g in collision if model.geom_bodyid[g] == b]
        for name, g in zip(geometry_names(links[b], len(own)), own):
            if model.geom(g).name:
                name = model.geom(g).name
            else:
                k = 0
                while name in taken:
                    name, k = f"{links[b]}/{k}", k + 1
                taken.add(name)
            body = _geom_body(model, g, name, skip_planes)
            if body is not None:
                geometry_of[g] = name
                geometries.append(
                    (name, b, _transform(model.geom_pos[g], model.geom_quat[g]), body))
    pairs = [(geometry_of[g1], geometry_of[g2]) for g1, g2 in geom_pairs
             if g1 in geometry_of and g2 in geometry_of]
    return ModelTables(links, joints, geometries, pairs)


def _geom_body(model, g: int, name: str, skip_planes: bool):
    mujoco = _mujoco()
    kind = int(model.geom_type[g])
    size = np.asarray(model.geom_size[g], dtype=float)
    types = {int(getattr(mujoco.mjtGeom, f"mjGEOM_{t}")): t.lower()
             for t in ("SPHERE", "CAPSULE", "BOX", "CYLINDER", "ELLIPSOID", "MESH", "PLANE")}
    shape = types.get(kind, "")
    if shape == "sphere":
        return _core.Sphere(size[0])
    if shape == "capsule":
        return _core.Capsule(size[0], size[1])
    if shape == "box":
        return _core.Box(size)
    if shape == "cylinder":
        return _core.Cylinder(size[0], size[1])
    if shape == "ellipsoid":
        return _core.Ellipsoid(size)
    if shape == "mesh":
        mesh = model.geom_dataid[g]
        start = model.mesh_vertadr[mesh]
        return _core.ConvexPolyhedron(model.mesh_vert[start:start + model.mesh_vertnum[mesh]])
    if shape == "plane" and skip_planes:
        return None
    raise ValueError(
        f"geom '{name}': type '{shape or mujoco.mjtGeom(kind).name}' is not supported "
        "(unbounded or not convex)"
        + ("; pass skip_planes=True to leave planes out, or give the floor as a box"
           if shape == "plane" else "")
    )
