"""URDF models read by yourdfpy (the ``[robot]`` extra), as the tables of a ``Robot``."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Sequence, Tuple, Union
from xml.etree import ElementTree
from xml.parsers.expat import errors as expat_errors

import numpy as np

from . import _core
from .mesh import load_mesh
from .robot_tables import ModelTables, collision_bodies, geometry_names

PathLike = Union[str, "os.PathLike[str]"]

_SUPPORTED = ("revolute", "continuous", "prismatic", "fixed")

_SHAPES = {"box": ("size",), "sphere": ("radius",), "cylinder": ("radius", "length"), "mesh": ()}
"""URDF's shapes and the attributes yourdfpy requires of each (it failed on a missing one with a
bare KeyError); a collision mesh's filename is checked where the mesh is read (yourdfpy reads no
visual's)."""

_NUMBERS: Dict[str, Dict[str, int]] = {
    "origin": {"xyz": 3, "rpy": 3},
    "axis": {"xyz": 3},
    "box": {"size": 3},
    "sphere": {"radius": 1},
    "cylinder": {"radius": 1, "length": 1},
    "mesh": {"scale": 0},
    "limit": dict.fromkeys(("lower", "upper", "effort", "velocity"), 1),
    "mimic": dict.fromkeys(("multiplier", "offset"), 1),
    "calibration": dict.fromkeys(("rising", "falling"), 1),
    "safety_controller": dict.fromkeys(
        ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"), 1),
    "mass": {"value": 1},
    "inertia": dict.fromkeys(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), 1),
    "color": {"rgba": 0},
}
"""The attributes yourdfpy reads as numbers, and how many each holds (0: any count; a mesh's
scale is counted where it is applied): other text failed in float() or in NumPy's broadcasting,
naming neither the attribute nor its link or joint."""

_COMMAS = {("box", "size"), ("mesh", "scale")}
"""The attributes yourdfpy also reads with commas between the numbers."""


def _yourdfpy():
    try:
        import yourdfpy
    except ImportError as error:  # pragma: no cover - the [robot] extra is installed in tests
        raise ImportError(
            "reading URDF needs yourdfpy: pip install 'swarmcollide[robot]'"
        ) from error
    return yourdfpy


def resolve_mesh_path(filename: str, urdf_path: Path, package_dirs: Sequence[PathLike],
                      link: str) -> Path:
    """The file a URDF mesh ``filename`` names: ``package://name/rest`` in one of
    ``package_dirs`` (a directory that is the package ``name``, or that holds it), then in the
    URDF's folder or one of its parents (as ROS's workspaces and pybullet_data lay packages out);
    ``file://`` and absolute paths as they are, relative paths from the URDF's directory.

    Raises ``ValueError`` naming ``link`` and the fix when no such file exists.
    """
    if filename.startswith("package://"):
        package, _, rest = filename[len("package://"):].partition("/")
        roots = [Path(d) for d in package_dirs] + list(urdf_path.resolve().parents)
        for root in roots:
            for candidate in ([root / rest] if root.name == package else []) + [
                    root / package / rest]:
                if candidate.is_file():
                    return candidate
        searched = ", ".join(str(Path(d)) for d in package_dirs) or "none given"
        raise ValueError(
            f"link '{link}': cannot resolve mesh '{filename}': package '{package}' not found in "
            f"package_dirs ({searched}) nor in the URDF's folder or its parents; pass "
            f"package_dirs=[the directory holding '{package}']"
        )
    path = Path(filename[len("file://"):] if filename.startswith("file://") else filename)
    if not path.is_absolute():
        path = urdf_path.parent / path
    if not path.is_file():
        raise ValueError(f"link '{link}': mesh file '{filename}' not found (looked at {path})")
    return path


def load_urdf(path: PathLike, package_dirs: Optional[Sequence[PathLike]] = None,
              collision: str = "hull") -> ModelTables:
    """The links, joints and collision geometries of a URDF file.

    See ``Robot.from_urdf`` for the parameters.
    """
    yourdfpy = _yourdfpy()
    urdf_path = Path(path)
    if urdf_path.is_dir():
        raise ValueError(f"URDF file '{path}' is a directory; pass the robot's .urdf file")
    if not urdf_path.is_file():
        raise ValueError(f"URDF file '{path}' not found")
    collision_bodies(collision)  # the mode is checked before anything is read
    root = _xml_root(urdf_path, path)
    not_urdf = _not_urdf(root)
    if not_urdf:
        raise ValueError(f"'{path}' does not look like a URDF file: {not_urdf}")
    malformed = next(_malformed(root), None)
    if malformed:
        raise ValueError(f"cannot read URDF file '{path}': {malformed}")
    if isinstance(package_dirs, (str, os.PathLike)):
        package_dirs = [package_dirs]
    dirs = list(package_dirs or [])
    try:
        model = yourdfpy.URDF.load(str(urdf_path), build_scene_graph=False, load_meshes=False,
                                   load_collision_meshes=False)
    except Exception as error:  # yourdfpy and lxml raise many types for bad files
        raise ValueError(f"cannot read URDF file '{path}': {error}") from error
    robot = model.robot
    links = [link.name for link in robot.links]
    index = {name: i for i, name in enumerate(links)}
    joints = []
    joint_index = {joint.name: j for j, joint in enumerate(robot.joints)}
    for joint in robot.joints:
        if joint.type not in _SUPPORTED:
            raise ValueError(
                f"joint '{joint.name}': type '{joint.type}' is not supported; a robot's joints "
                f"must be one of {', '.join(_SUPPORTED)}"
            )
        for end in (joint.parent, joint.child):
            if end not in index:
                raise ValueError(f"joint '{joint.name}': link '{end}' is not in the URDF")
        mimic = joint.mimic
        if mimic is not None and mimic.joint not in joint_index:
            raise ValueError(f"joint '{joint.name}' mimics '{mimic.joint}', which is not in the "
                             "URDF")
        limit = joint.limit
        lower = limit.lower if limit is not None and limit.lower is not None else 0.0
        upper = limit.upper if limit is not None and limit.upper is not None else 0.0
        joints.append(_core.Joint(
            joint.name, joint.type, index[joint.parent], index[joint.child],
            origin=np.eye(4) if joint.origin is None else joint.origin,
            axis=np.array([1.0, 0.0, 0.0]) if joint.axis is None else joint.axis,
            lower=lower, upper=upper,
            mimic=-1 if mimic is None else joint_index[mimic.joint],
            multiplier=1.0 if mimic is None or mimic.multiplier is None else mimic.multiplier,
            offset=0.0 if mimic is None or mimic.offset is None else mimic.offset))
    geometries = []
    for link in robot.links:
        names = geometry_names(link.name, len(link.collisions))
        for name, element in zip(names, link.collisions):
            origin = np.eye(4) if element.origin is None else element.origin
            body = _body(element.geometry, name, link.name, urdf_path, dirs, collision)
            geometries.append((name, index[link.name], origin, body))
    return ModelTables(links, joints, geometries)


def _xml_root(urdf_path: Path, path: PathLike) -> ElementTree.Element:
    """The root element of a URDF file; ValueError naming the file, and the line and column,
    for one that is not well-formed XML (yourdfpy's lxml recovers from it by dropping what it
    cannot read: a file cut short loaded as a smaller robot)."""
    try:
        data = urdf_path.read_bytes()
    except OSError as error:
        raise ValueError(f"cannot read URDF file '{path}': {error.strerror}") from None
    if not data.strip():
        raise ValueError(f"cannot read URDF file '{path}': the file is empty")
    # Blank lines before the XML declaration (pybullet_data's diff_ring.urdf) are read by ROS's
    # and yourdfpy's parsers, not by expat: they go after it, which keeps the lines' numbers.
    text = data.lstrip()
    end = text.find(b"?>") if text.startswith(b"<?xml") else -1
    if end >= 0 and len(text) < len(data):
        data = text[:end + 2] + data[:len(data) - len(text)] + text[end + 2:]
    try:
        return ElementTree.fromstring(data)
    except ElementTree.ParseError as error:
        short = error.code in (expat_errors.codes[expat_errors.XML_ERROR_NO_ELEMENTS],
                               expat_errors.codes[expat_errors.XML_ERROR_UNCLOSED_TOKEN])
        raise ValueError(
            f"cannot read URDF file '{path}': it is not well-formed XML ({error})"
            + ("; the file ends before its elements do: it may have been cut short (an "
               "interrupted download or write)" if short else "")) from None


def _not_urdf(root: ElementTree.Element) -> Optional[str]:
    """What says a file is no URDF (yourdfpy fails on one with a bare KeyError), or None: its
    root element, unless it is ``<robot>``."""
    tag = root.tag.rpartition("}")[2]  # without a namespace
    if tag == "robot":
        return None
    hint = {"mujoco": "; it is an MJCF model: read it with Robot.from_mjcf",
            "sdf": "; SDF is not read: convert it to URDF (or MJCF)"}
    return f"its root element is <{tag}>, where a URDF's is <robot>{hint.get(tag, '')}"


def _malformed(root: ElementTree.Element) -> Iterator[str]:
    """What yourdfpy fails on naming neither the attribute nor its link or joint (a bare
    KeyError, IndexError or AttributeError, float()'s or NumPy's message), or reads as None: a
    missing name, joint type, parent, child or mimicked joint, a <geometry> without a URDF shape
    or a shape without its size, and attributes read as numbers that are not (or not as many as
    they must be). The elements are found as yourdfpy finds them (a link's or joint's first
    <origin>, a <geometry>'s first element)."""
    if root.get("name") is None:
        yield "<robot> has no name attribute (<robot name=\"...\">)"
    # (owner, the elements above the one read, the element read), checked for numbers at the end
    parts: List[Tuple[str, str, Optional[ElementTree.Element]]] = [
        (f"material '{material.get('name')}'", "", material.find("color"))
        for material in root.findall("material")]
    for link in root.findall("link"):
        if link.get("name") is None:
            yield "a <link> has no name attribute"
        owner = f"link '{link.get('name')}'"
        inertial = link.find("inertial")
        if inertial is not None:
            parts += [(owner, "<inertial>", inertial.find(tag))
                      for tag in ("origin", "mass", "inertia")]
        for element in link.findall("visual") + link.findall("collision"):
            where = f"<{element.tag}>"
            geometry = element.find("geometry")
            if geometry is None:
                yield f"{owner}: its {where} element has no <geometry>"
            elif len(geometry) == 0:
                yield (f"{owner}: its {where} element's <geometry> is empty (give a box, sphere, "
                       "cylinder or mesh)")
            elif geometry[0].tag not in _SHAPES:
                yield (f"{owner}: its {where} element's <geometry> holds <{geometry[0].tag}>, "
                       "which is not a URDF shape (give a box, sphere, cylinder or mesh)")
            else:
                shape = geometry[0]
                for attribute in _SHAPES[shape.tag]:
                    if shape.get(attribute) is None:
                        yield f"{owner}: {where}<{shape.tag}> has no {attribute} attribute"
                parts.append((owner, where, shape))
            parts.append((owner, where, element.find("origin")))
            material = element.find("material")
            if material is not None:
                parts.append((owner, where + "<material>", material.find("color")))
    for joint in root.findall("joint"):
        if joint.get("name") is None:
            yield "a <joint> has no name attribute"
        owner = f"joint '{joint.get('name')}'"
        if joint.get("type") is None:
            yield f"{owner} has no type attribute (give one of {', '.join(_SUPPORTED)})"
        for end in ("parent", "child"):
            named = joint.find(end)
            if named is None or named.get("link") is None:
                yield f"{owner} has no <{end} link=\"...\"/> naming its {end} link"
        mimic = joint.find("mimic")
        if mimic is not None and mimic.get("joint") is None:
            yield f"{owner}: its <mimic> has no joint attribute naming the joint it follows"
        parts += [(owner, "", joint.find(tag)) for tag in
                  ("origin", "axis", "limit", "mimic", "calibration", "safety_controller")]
    for owner, where, read in parts:
        for problem in _not_numbers(read):
            yield f"{owner}: {where}{problem}"


def _not_numbers(element: Optional[ElementTree.Element]) -> Iterator[str]:
    """What is wrong with the attributes of ``element`` that yourdfpy reads as numbers."""
    if element is None:
        return
    for attribute, count in _NUMBERS.get(element.tag, {}).items():
        text = element.get(attribute)
        if text is None:
            continue
        read = f"<{element.tag} {attribute}=\"{text}\">"
        # One number is read by float() whole, several split at blanks (and commas for some).
        words = [text] if count == 1 else (
            text.replace(",", " ") if (element.tag, attribute) in _COMMAS else text).split()
        for word in words:
            try:
                float(word)
            except ValueError:
                yield f"{read}: {word!r} is not a number"
                break
        else:
            if count > 1 and len(words) != count:
                yield f"{read} must be {count} numbers, got {len(words)}"


def _body(geometry, name: str, link: str, urdf_path: Path, dirs, collision: str):
    try:
        if geometry.box is not None:
            return _core.Box(np.asarray(geometry.box.size, dtype=float) / 2)
        if geometry.sphere is not None:
            return _core.Sphere(float(geometry.sphere.radius))
        if geometry.cylinder is not None:
            return _core.Cylinder(float(geometry.cylinder.radius),
                                  float(geometry.cylinder.length) / 2)
    except ValueError as error:  # the shape's own message: say whose shape it is
        raise ValueError(f"link '{link}': {error}") from error
    if geometry.mesh is not None:
        if geometry.mesh.filename is None:  # yourdfpy reads it as None
            raise ValueError(f"link '{link}': a <collision>'s <mesh> has no filename attribute; "
                             "give its mesh file (<mesh filename=\"...\"/>)")
        mesh_path = resolve_mesh_path(geometry.mesh.filename, urdf_path, dirs, link)
        try:
            mesh = load_mesh(mesh_path)
        except ValueError as error:  # a file that is not a mesh: say whose it is
            raise ValueError(f"link '{link}': {error}") from error
        if geometry.mesh.scale is not None:
            scale = np.asarray(geometry.mesh.scale, float)
            # URDF's scale is "x y z"; one number, which yourdfpy, pybullet and trimesh read
            # as a uniform scale, is taken as one too. Any other count would be broadcast by
            # NumPy into a wrong shape, or ignored ("1 1" reads as no scale).
            if scale.size not in (1, 3):
                raise ValueError(f"link '{link}': mesh scale must be 3 numbers (x y z), or 1 for "
                                 f"a uniform scale, got {scale.size}: {scale.tolist()}")
            if not (np.all(np.isfinite(scale)) and np.all(scale != 0)):
                raise ValueError(f"link '{link}': mesh scale must be finite and non-zero, got "
                                 f"{scale.tolist()}")
            mesh.apply_scale(scale)
        try:
            return collision_bodies(collision)(mesh, name)
        except ValueError as error:  # say whose mesh, and which file
            raise ValueError(f"link '{link}': mesh '{geometry.mesh.filename}' ({mesh_path}): "
                             f"{error}") from error
    raise ValueError(f"link '{link}': a <collision> geometry has no box, sphere, cylinder or mesh")
