"""A picture of a robot at one configuration, its nearest pair marked (matplotlib)."""

from __future__ import annotations

from typing import Optional

import numpy as np

from . import _core
from .plot import _draw_parts, _figure, _finish, _frame_axes

SURFACE_DIRECTIONS = 400
"""Directions whose support points draw a curved or rounded body (its hull stands for it)."""


def _directions(count: int) -> np.ndarray:
    # A Fibonacci sphere: nearly even directions, the same every time.
    k = np.arange(count) + 0.5
    polar = np.arccos(1 - 2 * k / count)
    azimuth = np.pi * (1 + 5**0.5) * k
    return np.column_stack([np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth),
                            np.cos(polar)])


def drawn_body(body):
    """What stands for ``body`` in a picture: a polyhedron as it is, a curved or rounded shape
    (``Cylinder``, ``Sphere``, ...) as the hull of its support points in
    ``SURFACE_DIRECTIONS`` directions, a compound body part by part."""
    if isinstance(body, _core.CompoundBody):
        return _core.CompoundBody([drawn_body(part) for part in body.parts])
    if not body.curved and body.rounding_radius == 0:
        return body
    directions = _directions(SURFACE_DIRECTIONS)
    points = np.array([body.support(d) for d in directions]) + body.rounding_radius * directions
    return _core.ConvexPolyhedron(points)


def plot_robot(robot, q, check=None, *, ax=None, path: Optional[str] = None, show: bool = False,
               title: Optional[str] = None):
    """Draw every geometry of ``robot`` (links and obstacles) at the configuration ``q``, the
    nearest pair of ``check`` opaque (its first geometry in blue, its second in orange) and its
    answer: the witness segment for a pair apart, the contact point and normal for one in
    contact.

    Parameters
    ----------
    robot : Robot
    q : array_like, (dof,)
    check : RobotCheck, optional
        ``robot.check(q)`` when omitted.
    ax, path, show, title
        As for ``plot.plot_body``.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> from swarmcollide.robot_plot import plot_robot
    >>> robot = sc.Robot(["base", "arm"], [sc.Joint("turn", "continuous", 0, 1)],
    ...                  [("arm", 1, None, sc.Cylinder(0.1, 0.5))])
    >>> robot = robot.add_obstacle(sc.Box([0.2, 0.2, 0.2]), ([[1, 0, 0], [0, 1, 0], [0, 0, 1]],
    ...                                                      [1, 0, 0]), name="crate")
    >>> plot_robot(robot, [0.0]).axes[0].get_title()
    'nearest: arm - crate, distance 0.7 (certified)'
    """
    from matplotlib import colormaps

    values = np.asarray(q, dtype=float)
    if values.ndim != 1:
        raise ValueError(f"q must be one configuration of shape ({robot.dof},), got shape "
                         f"{values.shape}")
    if check is None:
        check = robot.check(values)
    figure, ax = _figure(ax, show)
    poses = robot.geometry_poses(values)
    geometries = robot._robot_geometries + robot._obstacles
    nearest = tuple(str(name) for name in check.pair_names)
    grey = colormaps["Greys"].resampled(8)
    placed = []
    for (name, _, _, body), pose in zip(geometries, poses):
        if name in nearest:
            shade = colormaps["winter" if name == nearest[0] else "autumn"].resampled(8)
            placed += _draw_parts(ax, drawn_body(body), pose, shade, 3, 0.85)
        else:
            placed += _draw_parts(ax, drawn_body(body), pose, grey, 2, 0.15)
    label = "no pair checked"
    if int(check.pair) >= 0:
        p, r = np.asarray(check.point_a), np.asarray(check.point_b)
        if check.colliding:
            middle = (p + r) / 2
            ax.scatter(*middle[:, None], color="red", s=30, depthshade=False)
            size = np.ptp(np.concatenate(placed), axis=0).max() / 6
            ax.quiver(*middle, *np.asarray(check.normal), length=size, color="darkred")
            state = f"in contact, depth {-float(check.min_distance):.3g}"
        else:
            ax.plot(*np.stack([p, r]).T, color="black", linewidth=2, marker="o", markersize=4)
            state = f"distance {float(check.min_distance):.3g}"
        verdict = "certified" if check.certified else "not certified"
        label = f"nearest: {nearest[0]} - {nearest[1]}, {state} ({verdict})"
    _frame_axes(ax, placed)
    ax.set_title(title if title is not None else label)
    return _finish(figure, path, show)
