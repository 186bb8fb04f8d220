"""Pictures of scenes: bodies at their poses, contact points and contact normals (matplotlib).

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
        points = body.vertices @ pose[:3, :3].T + pose[:3, 3]
        hull = body.hull()
        if hull.dimension < 2:
            continue
        polygons.extend(points[hull.faces])
        colours.extend([(1.0, 0.55, 0.1, 0.35) if body_id in touching else (0.5, 0.5, 0.5, 0.12)]
                       * len(hull.faces))
        sizes.append(2 * body.radius)
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
