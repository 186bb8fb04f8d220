"""Pictures: a body (its parts coloured), a pair with a query's witness segment or contact, and
scenes with their contact points and normals (matplotlib).

Needs matplotlib (``pip install swarmcollide[plot]``). Figures are built without pyplot, so
saving one needs no display.
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from . import _core


def plot_scene(
    scene: _core.Scene,
    contacts: Optional[_core.ContactResult] = None,
    *,
    ax=None,
    path: Optional[str] = None,
    normal_length: Optional[float] = None,
    title: Optional[str] = None,
):
    """Draw every body of ``scene`` at its pose, with ``contacts``' points and normals.

    Bodies in contact are drawn in orange, the others in grey; each contact point is a red dot
    and each pair's normal (from A to B) an arrow from its contact points' centre.

    Parameters
    ----------
    scene : Scene
    contacts : ContactResult, optional
        What ``scene.contacts()`` returned; computed here when omitted.
    ax : mpl_toolkits.mplot3d.Axes3D, optional
        Where to draw; a new figure's 3-D axes by default.
    path : str, optional
        Save the figure there (the format follows the extension).
    normal_length : float, optional
        Length of the normal arrows; half the median body size by default.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> from swarmcollide.plot import plot_scene
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> scene = sc.Scene()
    >>> ids = scene.add(np.stack([cube, cube + [0, 0, 1]]))
    >>> figure = plot_scene(scene)
    >>> len(figure.axes[0].collections)  # the bodies, the contact points, the normals
    3
    """
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    if contacts is None:
        contacts = scene.contacts()
    if ax is None:
        figure = Figure(figsize=(8, 8))
        ax = figure.add_subplot(projection="3d")
    else:
        figure = ax.figure
    touching = set(contacts.pairs.ravel().tolist())
    polygons, colours, sizes, corners = [], [], [], []
    for body_id in scene.ids.tolist():
        body = scene.body(body_id)
        pose = scene.pose(body_id)
        sizes.append(2 * body.bounding_radius)
        for part in _parts_of(body):  # a compound body's parts, or the convex body itself
            surface, faces = _surface(part)
            points = surface @ pose[:3, :3].T + pose[:3, 3]
            if faces is None:
                continue
            polygons.extend(points[faces])
            colours.extend([(1.0, 0.55, 0.1, 0.35) if body_id in touching
                            else (0.5, 0.5, 0.5, 0.12)] * len(faces))
            corners.append(points)
    ax.add_collection3d(Poly3DCollection(polygons, facecolors=colours, edgecolors=(0, 0, 0, 0.15),
                                         linewidths=0.3))
    if corners:
        everything = np.concatenate(corners)
        low, high = everything.min(axis=0), everything.max(axis=0)
        centre, half = (low + high) / 2, (high - low).max() / 2
        ax.set(xlim=(centre[0] - half, centre[0] + half), ylim=(centre[1] - half, centre[1] + half),
               zlim=(centre[2] - half, centre[2] + half))
    points = contacts.points
    ax.scatter(points[:, 0], points[:, 1], points[:, 2], color="red", s=12, depthshade=False)
    length = normal_length if normal_length is not None else np.median(sizes or [1.0]) / 2
    if len(contacts):
        centres = np.array([points[o:o + c].mean(axis=0)
                            for o, c in zip(contacts.offsets.tolist(), contacts.counts.tolist())])
        normals = contacts.normal
    else:
        centres = normals = np.zeros((0, 3))
    ax.quiver(centres[:, 0], centres[:, 1], centres[:, 2], normals[:, 0], normals[:, 1],
              normals[:, 2], length=length, color="darkred", linewidth=1.2)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(title if title is not None else
                 f"{len(scene)} bodies, {len(contacts)} pairs in contact, "
                 f"{len(points)} contact points")
    if path is not None:
        figure.savefig(path, dpi=120)
    return figure


def _parts_of(body) -> list:
    """The convex parts of a compound body, or the body itself as one part."""
    if isinstance(body, _core.CompoundBody):
        return list(body.parts)
    return [body if isinstance(body, _core.ConvexPolyhedron) else _core.as_polyhedron(body)]


# Directions the surfaces of curved and rounded bodies are sampled along for drawing: a
# Fibonacci sphere (evenly spread), about 4 degrees apart.
_SAMPLES = 2000


def _directions(count: int = _SAMPLES) -> np.ndarray:
    k = np.arange(count) + 0.5
    z = 1 - 2 * k / count
    turn = np.pi * (1 + 5 ** 0.5) * k
    ring = np.sqrt(1 - z * z)
    return np.stack([ring * np.cos(turn), ring * np.sin(turn), z], axis=1)


def _surface(part) -> tuple:
    """Points to draw a part by, and its triangles as indices into them (None when the part is
    a point or a segment, drawn as its points): a polyhedron's own vertices and hull; a curved
    or rounded body's surface tessellated for drawing only, as the hull of its support points
    (its core's plus the radius along the direction) over many directions."""
    if not part.curved and part.rounding_radius == 0:
        hull = part.hull()
        return part.vertices, (hull.faces if hull.dimension >= 2 else None)
    directions = _directions()
    points = np.array([part.support(d) for d in directions]) + part.rounding_radius * directions
    return points, _core.ConvexPolyhedron(points).hull().faces


def _draw_parts(ax, body, matrix: np.ndarray, colours, start: int, alpha: float) -> list:
    """Draw each part's hull at the ``(4, 4)`` transform ``matrix`` in its own colour; return the
    placed points."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    placed = []
    for k, part in enumerate(_parts_of(body)):
        surface, faces = _surface(part)
        points = surface @ matrix[:3, :3].T + matrix[:3, 3]
        placed.append(points)
        colour = colours((start + k) % colours.N)
        if faces is None:
            ax.scatter(points[:, 0], points[:, 1], points[:, 2], color=colour, s=8)
            continue
        # Tessellated surfaces draw no edges: thousands of them would hide the body.
        edges = (0, 0, 0, 0.2) if len(faces) < 500 else (0, 0, 0, 0)
        ax.add_collection3d(Poly3DCollection(points[faces], facecolors=[(*colour[:3], alpha)],
                                             edgecolors=edges, linewidths=0.3))
    return placed


def _frame_axes(ax, placed: list) -> None:
    everything = np.concatenate(placed)
    low, high = everything.min(axis=0), everything.max(axis=0)
    centre, half = (low + high) / 2, max((high - low).max() / 2, 1e-12)
    ax.set(xlim=(centre[0] - half, centre[0] + half), ylim=(centre[1] - half, centre[1] + half),
           zlim=(centre[2] - half, centre[2] + half), xlabel="x", ylabel="y", zlabel="z")


def _figure(ax, show: bool):
    if ax is not None:
        return ax.figure, ax
    if show:
        import matplotlib.pyplot as plt

        figure = plt.figure(figsize=(8, 8))
    else:
        from matplotlib.figure import Figure

        figure = Figure(figsize=(8, 8))
    return figure, figure.add_subplot(projection="3d")


def _finish(figure, path: Optional[str], show: bool):
    if path is not None:
        figure.savefig(path, dpi=120)
    if show:
        import matplotlib.pyplot as plt

        plt.show()
    return figure


def plot_body(body, pose=None, *, ax=None, path: Optional[str] = None, show: bool = False,
              title: Optional[str] = None):
    """Draw a body (a ConvexPolyhedron, ``(n, 3)`` points or a CompoundBody, each part in its
    own colour) at ``pose``, to a file (``path``) or a window (``show=True``).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import swarmcollide as sc
    >>> from swarmcollide.plot import plot_body
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> ell = sc.CompoundBody([cube, [[x + 1, y, z] for x, y, z in cube]])
    >>> len(plot_body(ell).axes[0].collections)  # one collection per part
    2
    """
    from matplotlib import colormaps

    # Read as the queries read a pose, with their errors.
    matrix = _core.pose_matrix(pose, "pose")
    figure, ax = _figure(ax, show)
    placed = _draw_parts(ax, body, matrix, colormaps["tab20"], 0, 0.45)
    _frame_axes(ax, placed)
    parts = len(placed)
    ax.set_title(title if title is not None else f"{parts} part{'s' if parts != 1 else ''}")
    return _finish(figure, path, show)


def plot_pair(a, b, result=None, *, pose_a=None, pose_b=None, ax=None,
              path: Optional[str] = None, show: bool = False, title: Optional[str] = None):
    """Draw two bodies at their poses (parts coloured: A's in cool, B's in warm colours) and a
    query's answer: the witness segment from ``point_a`` to ``point_b`` for bodies apart, the
    contact point and normal for bodies in contact. The parts that realise a compound answer
    are drawn opaque.

    Parameters
    ----------
    a, b : ConvexPolyhedron, CompoundBody or array_like of shape (n, 3)
    result : DistanceResult or CompoundResult, optional
        The answer to draw; ``swarmcollide.distance(a, b, ...)`` when omitted.
    pose_a, pose_b : array_like, optional
        Where the bodies are, as ``distance`` takes them.
    ax, path, show, title
        As for ``plot_body``.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import swarmcollide as sc
    >>> from swarmcollide.plot import plot_pair
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> figure = plot_pair(cube, [[x + 2, y, z] for x, y, z in cube])
    >>> figure.axes[0].get_title()
    'distance 1 (certified), parts 0 and 0'
    """
    from matplotlib import colormaps

    from .queries import distance

    matrix_a, matrix_b = _core.pose_matrix(pose_a, "pose_a"), _core.pose_matrix(pose_b, "pose_b")
    if result is None:
        result = distance(a, b, pose_a=pose_a, pose_b=pose_b)
    figure, ax = _figure(ax, show)
    part_a = getattr(result, "part_a", 0)
    part_b = getattr(result, "part_b", 0)
    placed = _draw_parts(ax, a, matrix_a, colormaps["winter"].resampled(8), 0, 0.3)
    placed += _draw_parts(ax, b, matrix_b, colormaps["autumn"].resampled(8), 0, 0.3)
    for body, matrix, part, cmap in ((a, matrix_a, part_a, "winter"),
                                     (b, matrix_b, part_b, "autumn")):
        surface, faces = _surface(_parts_of(body)[part])
        points = surface @ matrix[:3, :3].T + matrix[:3, 3]
        if faces is not None:
            from mpl_toolkits.mplot3d.art3d import Poly3DCollection

            ax.add_collection3d(Poly3DCollection(
                points[faces], facecolors=[(*colormaps[cmap](0.5)[:3], 0.8)],
                edgecolors=(0, 0, 0, 0.5) if len(faces) < 500 else (0, 0, 0, 0),
                linewidths=0.5))
    p, q = np.asarray(result.point_a), np.asarray(result.point_b)
    if result.colliding:
        ax.scatter(*((p + q) / 2)[:, None], color="red", s=30, depthshade=False)
        normal = np.asarray(result.direction)
        if np.linalg.norm(normal) > 0:
            size = np.ptp(np.concatenate(placed), axis=0).max() / 4
            ax.quiver(*((p + q) / 2), *normal, length=size, color="darkred")
    else:
        ax.plot(*np.stack([p, q]).T, color="black", linewidth=2, marker="o", markersize=4)
    _frame_axes(ax, placed)
    verdict = "certified" if result.certified else "not certified"
    label = "in contact" if result.colliding else f"distance {result.distance:.6g}"
    ax.set_title(title if title is not None else
                 f"{label} ({verdict}), parts {part_a} and {part_b}")
    return _finish(figure, path, show)
