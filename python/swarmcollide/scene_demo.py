"""``python -m swarmcollide scene``: boxes and random hulls moving through each other in a Scene.

The bodies fly in straight lines and turn at a constant rate inside a closed room, bouncing off
its walls (no physics: they pass through each other). Every frame moves all of them and asks the
scene for its colliding pairs, then for its contacts (signed distances and contact points); the
frame's counts and the two queries' times are printed. Everything is drawn from one seed.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass
from typing import Callable, List, Optional

import numpy as np

from . import _core


@dataclass(frozen=True)
class Frame:
    """What one frame of the demo found, and how long its two queries took."""

    index: int
    candidates: int
    colliding: int
    settled_warm: int
    contact_points: int
    pairs_seconds: float
    contacts_seconds: float

    def __str__(self) -> str:
        warm = 100 * self.settled_warm / self.candidates if self.candidates else 0
        return (
            f"frame {self.index:3d}: {self.candidates:5d} candidates ({warm:5.1f}% settled warm), "
            f"{self.colliding:4d} in contact: colliding_pairs {1e3 * self.pairs_seconds:6.2f} ms; "
            f"{self.contact_points:4d} contact points: contacts {1e3 * self.contacts_seconds:6.2f} ms"
        )


def _rotation(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotations by ``angle[i]`` about unit ``axis[i]`` (Rodrigues), shape (m, 3, 3)."""
    k = np.zeros((len(axis), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -axis[:, 2], axis[:, 1], -axis[:, 0]
    k -= np.transpose(k, (0, 2, 1))
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1 - c) * (k @ k)


def _orthonormal(r: np.ndarray) -> np.ndarray:
    """The nearest rotations, so that turning frame after frame never drifts off rotations."""
    u, _, vt = np.linalg.svd(r)
    return u @ vt


def make_bodies(count: int, rng: np.random.Generator) -> List[np.ndarray]:
    """Half boxes (sides 0.4 to 1.2), half hulls of 6 to 20 random points (radius 0.3 to 0.7)."""
    bodies = []
    for i in range(count):
        if i % 2 == 0:
            half = rng.uniform(0.2, 0.6, 3)
            corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
            bodies.append(corners * half)
        else:
            points = rng.normal(size=(int(rng.integers(6, 21)), 3))
            points /= np.linalg.norm(points, axis=1)[:, None]
            bodies.append(points * rng.uniform(0.3, 0.7) * rng.uniform(0.7, 1.0, 3))
    return bodies


def run(
    bodies: int = 300,
    frames: int = 60,
    *,
    seed: int = 0,
    threads: Optional[int] = None,
    warm_start: bool = True,
    plot: Optional[str] = None,
    out: Callable[[str], None] = print,
) -> List[Frame]:
    """Run the demo and return its frames; ``plot`` saves a picture of the last one there.

    Examples
    --------
    >>> from swarmcollide import scene_demo
    >>> frames = scene_demo.run(bodies=40, frames=3, out=lambda line: None)
    >>> [f.index for f in frames], frames[-1].colliding > 0
    ([0, 1, 2], True)
    """
    rng = np.random.default_rng(seed)
    shapes = make_bodies(bodies, rng)
    # A room holding about one body per 5 unit volumes: one or two contacts per body.
    side = (5.0 * bodies) ** (1 / 3)
    position = rng.uniform(0, side, (bodies, 3))
    velocity = rng.normal(0, 0.03, (bodies, 3))
    axis = rng.normal(size=(bodies, 3))
    axis /= np.linalg.norm(axis, axis=1)[:, None]
    turn = _rotation(axis, rng.uniform(0.01, 0.05, bodies))
    rotation = _rotation(rng.normal(size=(bodies, 3)) / np.sqrt(3), rng.uniform(0, np.pi, bodies))
    rotation = _orthonormal(rotation)

    scene = _core.Scene(threads=threads, warm_start=warm_start, seed=seed)
    ids = scene.add(shapes, poses=(rotation, position))
    progress = _progress(frames)
    results: List[Frame] = []
    contacts = None
    for index in progress:
        if index > 0:
            position += velocity
            # Off the walls: the velocity turns back where a body has left the room.
            outside = (position < 0) | (position > side)
            velocity[outside] *= -1
            rotation = _orthonormal(turn @ rotation)
            scene.set_poses(ids, (rotation, position))
        start = time.perf_counter()
        colliding = scene.colliding_pairs()
        middle = time.perf_counter()
        stats = scene.stats
        contacts = scene.contacts()
        end = time.perf_counter()
        frame = Frame(
            index=index,
            candidates=stats.candidates,
            colliding=len(colliding),
            settled_warm=stats.warm_bounded + stats.warm_rejected + stats.warm_proven,
            contact_points=len(contacts.points),
            pairs_seconds=middle - start,
            contacts_seconds=end - middle,
        )
        results.append(frame)
        _write(progress, out, str(frame))
    if plot is not None and contacts is not None:
        from .plot import plot_scene

        plot_scene(scene, contacts, path=plot, title=f"frame {frames - 1}: {len(contacts)} contacts")
        out(f"picture of frame {frames - 1} saved to {plot}")
    return results


def _progress(frames: int):
    """The frames, behind a tqdm progress bar when tqdm is installed and stderr is a terminal."""
    try:
        from tqdm import tqdm
    except ImportError:
        return range(frames)
    return tqdm(range(frames), unit="frame", disable=not sys.stderr.isatty(), leave=False)


def _write(progress, out: Callable[[str], None], line: str) -> None:
    # tqdm.write keeps the bar below the printed lines.
    if out is print and hasattr(progress, "write"):
        progress.write(line)
    else:
        out(line)
