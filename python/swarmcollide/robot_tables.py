"""What a robot file parser hands to ``Robot``: links, joints and geometries as plain tables."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, List, Optional, Tuple

from . import _core
from .mesh import CompoundBody, NotConvexError

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
        return _convex_pieces
    if collision == "decompose":
        return lambda mesh, name: CompoundBody.from_mesh(mesh, progress=False)
    raise ValueError(f"collision must be one of {COLLISION_MODES}, got {collision!r}")


def _convex_pieces(mesh, name: str):
    try:
        return CompoundBody.from_mesh(mesh, decompose=None, cache=False, progress=False)
    except NotConvexError as error:  # name the robot's options, not CompoundBody's
        raise ValueError(
            f"collision='mesh' needs convex pieces, but {error.piece}, with {error.triangles} "
            f"triangles, is not convex ({error.defect}); pass collision='decompose' to split "
            "each mesh into CoACD's convex parts, or collision='hull' for each mesh's hull"
        ) from None
