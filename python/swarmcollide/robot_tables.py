"""What a robot file parser hands to ``Robot``: links, joints and geometries as plain tables."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, List, Optional, Tuple

from . import _core
from .mesh import CompoundBody

COLLISION_MODES = ("hull", "mesh", "decompose")
"""How a mesh becomes a collision body: its convex hull (the planners' default); a compound body
of the mesh's own convex pieces (each group of an OBJ file, or each connected component, which
must be convex: ``CompoundBody.from_mesh(mesh, decompose=None)``); or a compound body of CoACD's
convex decomposition (``CompoundBody.from_mesh(mesh)``, cached on disk)."""


@dataclass
class ModelTables:
    """Links (names), joints (``_core.Joint``) and geometries (``(name, link, origin, body)``,
    link -1 for the world) of a model, and the pairs of geometries (by name) its file says to
    check, or None where the file says nothing (the links that are not adjacent are checked)."""

    links: List[str]
    joints: List[Any]
    geometries: List[Tuple[str, int, Any, Any]]
    pairs: Optional[List[Tuple[str, str]]] = None


def geometry_names(link: str, count: int) -> List[str]:
    """The names of a link's ``count`` geometries: the link's own for one, ``link/k`` for more."""
    return [link] if count == 1 else [f"{link}/{k}" for k in range(count)]


def collision_bodies(collision: str) -> Callable[[Any, str], Any]:
    """The function that makes a body of a mesh (a ``trimesh.Trimesh``) under ``collision``.

    Raises ``ValueError`` for an unknown mode.
    """
    if collision == "hull":
        return lambda mesh, name: _core.ConvexPolyhedron(mesh.vertices)
    if collision == "mesh":
        return lambda mesh, name: CompoundBody.from_mesh(mesh, decompose=None, cache=False,
                                                         progress=False)
    if collision == "decompose":
        return lambda mesh, name: CompoundBody.from_mesh(mesh, progress=False)
    raise ValueError(f"collision must be one of {COLLISION_MODES}, got {collision!r}")
