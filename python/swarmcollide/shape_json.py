"""Bodies as JSON records, as the CLI reads and writes them: shapes by their parameters,
polyhedra by their points, compound bodies by their parts.

A record is an object with a ``"shape"`` key and the parameters of that shape, named as the
constructors name them::

    {"shape": "sphere", "radius": 0.5}
    {"shape": "capsule", "radius": 0.5, "half_length": 1.0}
    {"shape": "box", "half_extents": [1, 2, 3], "radius": 0.0}
    {"shape": "cylinder", "radius": 0.5, "half_length": 1.0}
    {"shape": "cone", "radius": 0.5, "half_length": 1.0}
    {"shape": "ellipsoid", "radii": [1, 2, 3]}
    {"shape": "polyhedron", "points": [[0, 0, 0], [1, 0, 0], ...], "radius": 0.0}
    {"shape": "compound", "parts": [record, ...], "poses": [4x4 transform, ...]}

Each shape sits in its own frame with the conventions of its class (axis z, centred); a compound's
optional ``"poses"`` place its parts in its frame (one homogeneous transform, a list of 4 rows of
4 numbers, per part; written only when some part has a pose other than the identity). Numbers
are written with Python's ``repr`` of floats, so a body read back is the same body.
"""

from __future__ import annotations

import math
import sys
from typing import Any, Callable, Dict, List, Tuple

import numpy as np

from . import _core

SHAPES = ("sphere", "capsule", "box", "cylinder", "cone", "ellipsoid", "polyhedron", "compound")


def body_to_json(body) -> Dict[str, Any]:
    """The JSON record (a dict) of a body: a ConvexPolyhedron or one of its shapes, or a
    CompoundBody.

    Spheres, capsules and boxes inside a compound body are its parts' points and radius
    (``"polyhedron"``), the same bodies; curved parts keep their shape, and parts with poses
    are written as given, with the compound's ``"poses"``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> from swarmcollide.shape_json import body_to_json, body_from_json
    >>> body_to_json(sc.Cylinder(0.5, 1.0))
    {'shape': 'cylinder', 'radius': 0.5, 'half_length': 1.0}
    >>> body_from_json({"shape": "ellipsoid", "radii": [1, 2, 3]})
    Ellipsoid(radii=[1, 2, 3])
    """
    if isinstance(body, _core.CompoundBody):
        record = {"shape": "compound", "parts": [body_to_json(p) for p in body.given_parts]}
        poses = np.asarray(body.part_poses)
        if not np.array_equal(poses, np.broadcast_to(np.eye(4), poses.shape)):
            record["poses"] = poses.tolist()
        return record
    if isinstance(body, _core.Sphere):
        return {"shape": "sphere", "radius": float(body.radius)}
    if isinstance(body, _core.Capsule):
        return {"shape": "capsule", "radius": float(body.radius),
                "half_length": float(body.half_length)}
    if isinstance(body, _core.Box):
        return {"shape": "box", "half_extents": np.asarray(body.half_extents).tolist(),
                "radius": float(body.radius)}
    if isinstance(body, _core.Cylinder):
        return {"shape": "cylinder", "radius": float(body.radius),
                "half_length": float(body.half_length)}
    if isinstance(body, _core.Cone):
        return {"shape": "cone", "radius": float(body.radius),
                "half_length": float(body.half_length)}
    if isinstance(body, _core.Ellipsoid):
        return {"shape": "ellipsoid", "radii": np.asarray(body.radii).tolist()}
    if isinstance(body, _core.ConvexPolyhedron):
        if body.curved:  # a curved shape sliced to its base class; CompoundBody.parts types them
            raise ValueError("body is a curved shape without its type; pass the Cylinder, Cone "
                             "or Ellipsoid itself")
        return {"shape": "polyhedron", "points": np.asarray(body.vertices).tolist(),
                "radius": float(body.radius)}
    raise TypeError(f"body must be a ConvexPolyhedron (or one of its shapes) or a CompoundBody, "
                    f"got {type(body).__name__}")


def body_from_json(record: Any, name: str = "record"):
    """The body a JSON record (a dict, as ``json.load`` returns) describes; ValueError naming
    the key and the fix for a record that is not one, TypeError for one that is not an object.

    A ``"compound"`` record gives a ``swarmcollide.CompoundBody``; the others a ConvexPolyhedron
    of the shape's class.
    """
    if not isinstance(record, dict):
        raise TypeError(f"{name} must be a JSON object with a 'shape' key, got "
                        f"{type(record).__name__}")
    shape = record.get("shape")
    if shape not in _READERS:
        raise ValueError(f"{name}['shape'] must be one of {', '.join(map(repr, SHAPES))}, got "
                         f"{shape!r}")
    reader, keys, optional = _READERS[shape]
    missing = [key for key in keys if key not in record]
    unknown = sorted(set(record) - set(keys) - set(optional) - {"shape"})
    if missing or unknown:
        wanted = ", ".join(repr(k) for k in keys + optional)
        problem = (f"lacks {', '.join(map(repr, missing))}" if missing
                   else f"has unknown keys {', '.join(map(repr, unknown))}")
        raise ValueError(f"{name} (a {shape}) {problem}; a {shape} takes {wanted}")
    try:
        return reader(record, name)
    except ValueError as error:  # a constructor's, naming the parameter: name the record too
        message = str(error)
        raise ValueError(message if message.startswith(name) else f"{name}: {message}") from None


def _real(value: Any, where: str) -> float:
    """``value`` as a finite float; ValueError naming ``where`` for anything else, a number
    beyond a double's range included (JSON reads 1e400 as infinity, a 400-digit integer as an
    int that float() cannot take)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{where} must be a number, got {value!r}")
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    if not math.isfinite(number):
        shown = (f"an integer of {len(str(abs(value)))} digits" if isinstance(value, int)
                 else repr(value))
        raise ValueError(f"{where} must be a finite number within a double's range (magnitude "
                         f"at most {sys.float_info.max:.4g}), got {shown}")
    return number


def _number(record: dict, key: str, name: str) -> float:
    return _real(record[key], f"{name}['{key}']")


def _triple(record: dict, key: str, name: str) -> list:
    value = record[key]
    if not isinstance(value, list) or len(value) != 3:
        raise ValueError(f"{name}['{key}'] must be a list of 3 numbers, got {value!r}")
    return [_real(v, f"{name}['{key}'][{k}]") for k, v in enumerate(value)]


def _compound(record: dict, name: str):
    from .mesh import CompoundBody

    parts = record["parts"]
    if not isinstance(parts, list) or not parts:
        raise ValueError(f"{name}['parts'] must be a non-empty list of records")
    bodies = []
    for k, part in enumerate(parts):
        # Refused before it is read: a compound nested 3,000 deep would exhaust the recursion.
        if isinstance(part, dict) and part.get("shape") == "compound":
            raise ValueError(f"{name}['parts'][{k}] is a compound; compounds do not nest (one "
                             f"level at most): list its parts instead")
        bodies.append(body_from_json(part, f"{name}['parts'][{k}]"))
    poses = record.get("poses")
    if poses is not None:
        if not isinstance(poses, list) or len(poses) != len(bodies):
            raise ValueError(f"{name}['poses'] must be a list of {len(bodies)} transforms (4 rows "
                             f"of 4 numbers), one per part")
        for k, pose in enumerate(poses):
            if (not isinstance(pose, list) or len(pose) != 4
                    or any(not isinstance(row, list) or len(row) != 4 for row in pose)):
                raise ValueError(f"{name}['poses'][{k}] must be a transform: 4 rows of 4 "
                                 f"numbers, got {pose!r}")
        poses = [[[_real(v, f"{name}['poses'][{k}][{i}][{j}]") for j, v in enumerate(row)]
                  for i, row in enumerate(pose)] for k, pose in enumerate(poses)]
    return CompoundBody(bodies, poses=poses)


def _points(record: dict, name: str):
    try:
        points = np.asarray(record["points"], dtype=float)
    except OverflowError:  # an integer beyond a double's range: found, and named, one by one
        points = None
    except (TypeError, ValueError):
        raise ValueError(f"{name}['points'] must be a list of [x, y, z] points") from None
    if points is None or not np.isfinite(points).all():
        for i, point in enumerate(record["points"]):
            for j, value in enumerate(point if isinstance(point, list) else [point]):
                _real(value, f"{name}['points'][{i}][{j}]")
    return _core.ConvexPolyhedron(points, _number(record, "radius", name)
                                  if "radius" in record else 0.0)


# shape -> (reader, required keys, optional keys)
_READERS: Dict[str, Tuple[Callable[[dict, str], Any], List[str], List[str]]] = {
    "sphere": (lambda r, n: _core.Sphere(_number(r, "radius", n)), ["radius"], []),
    "capsule": (lambda r, n: _core.Capsule(_number(r, "radius", n), _number(r, "half_length", n)),
                ["radius", "half_length"], []),
    "box": (lambda r, n: _core.Box(_triple(r, "half_extents", n),
                                   _number(r, "radius", n) if "radius" in r else 0.0),
            ["half_extents"], ["radius"]),
    "cylinder": (lambda r, n: _core.Cylinder(_number(r, "radius", n),
                                             _number(r, "half_length", n)),
                 ["radius", "half_length"], []),
    "cone": (lambda r, n: _core.Cone(_number(r, "radius", n), _number(r, "half_length", n)),
             ["radius", "half_length"], []),
    "ellipsoid": (lambda r, n: _core.Ellipsoid(_triple(r, "radii", n)), ["radii"], []),
    "polyhedron": (_points, ["points"], ["radius"]),
    "compound": (_compound, ["parts"], ["poses"]),
}
