"""What a robot file parser hands to ``Robot``: links, joints and geometries as plain tables."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, List, Tuple

from . import _core
from .robot_shapes import Approximation

COLLISION_MODES = ("hull", "mesh", "decompose")
"""How a mesh becomes a collision body: its convex hull; the mesh itself or a convex
decomposition (compound bodies: not yet available to robots)."""


@dataclass
class ModelTables:
    """Links (names), joints (``_core.Joint``) and geometries (``(name, link, origin, body)``,
    link -1 for the world) of a model, with the curved shapes approximated on the way."""

    links: List[str]
    joints: List[Any]
    geometries: List[Tuple[str, int, Any, Any]]
    approximations: List[Approximation] = field(default_factory=list)


def geometry_names(link: str, count: int) -> List[str]:
    """The names of a link's ``count`` geometries: the link's own for one, ``link/k`` for more."""
    return [link] if count == 1 else [f"{link}/{k}" for k in range(count)]


def collision_bodies(collision: str) -> Callable[[Any, str], Any]:
    """The function that makes a body of a mesh's points under ``collision``.

    Raises ``ValueError`` for an unknown mode or one robots cannot use yet.
    """
    if collision == "hull":
        return lambda points, name: _core.ConvexPolyhedron(points)
    if collision in COLLISION_MODES:
        raise ValueError(
            f"collision={collision!r} (compound bodies) is not yet available to robots; "
            "use collision='hull'"
        )
    raise ValueError(f"collision must be one of {COLLISION_MODES}, got {collision!r}")
