"""Continuous collision: the first time two moving bodies touch, proven (docs/motions.md).

A motion takes a body from a start pose (time 0) to an end pose (time 1): its origin moves on the
straight segment and it turns at a constant angular velocity about a fixed axis through its
origin, ``R(t) = R0 exp(t log(R0^T R1))`` (the shorter way round). With ``motion="screw"`` the
pose follows ``G(t) = G0 exp(t xi)`` instead, xi the twist (matrix logarithm) of ``G0^-1 G1``:
the same rotation, about a fixed axis that the body slides along. The answer comes from
conservative advancement on the certified distance lower bounds, so a contact between the
sampled times cannot be missed.
"""

from __future__ import annotations

from typing import Any, Literal, Optional, Tuple, Union

from . import _core
from .queries import (
    DEFAULT_TOLERANCE,
    BodiesLike,
    PolyhedronLike,
    PoseLike,
    PosesLike,
    _answered_in_cpp,
)

TimeOfImpactResult = _core.TimeOfImpactResult
TimeOfImpactBatch = _core.TimeOfImpactBatch
SweepResult = _core.SweepResult

DEFAULT_TIME_TOLERANCE = 1e-6
"""The default ``time_tolerance``: the largest width of a first contact's bracket, as a fraction
of the motion's duration."""

DEFAULT_MOTION_ITERATIONS = 100000
"""The default ``max_iterations``: distance queries one motion may run before it answers
uncertified."""

MotionKind = Literal["linear", "screw"]
"""How a body moves between its poses: ``"linear"`` (its origin on the straight segment, turning
about it) or ``"screw"`` (``G(t) = G0 exp(t log(G0^-1 G1))``)."""

MotionLike = Union[None, Tuple[PoseLike, PoseLike], Any]
"""None (the body stays at the identity), a pair ``(start, end)`` of poses (each anything
``distance``'s ``pose_a`` takes) or a ``(2, 4, 4)`` or ``(2, 3, 4)`` array of them, or a single
pose (the body stays there)."""

MotionsLike = Union[None, Tuple[PosesLike, PosesLike]]
"""None (every body stays at the identity), or a pair ``(starts, ends)`` of pose arrays (each
anything ``distance_many``'s ``poses_a`` takes), of m rows or of one row for all."""


@_answered_in_cpp(_core.motion_function)
def time_of_impact(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    pose_a: MotionLike = None,
    pose_b: MotionLike = None,
    method: str = "exact",
    tolerance: float = DEFAULT_TOLERANCE,
    time_tolerance: float = DEFAULT_TIME_TOLERANCE,
    max_iterations: int = DEFAULT_MOTION_ITERATIONS,
    motion: MotionKind = "linear",
) -> _core.TimeOfImpactResult:
    """The first time A and B touch while they move from their start to their end poses.

    Parameters
    ----------
    a, b : ConvexPolyhedron, CompoundBody, shape or array_like of shape (n, 3)
        The bodies, in their own frames: anything ``distance`` takes (curved shapes with every
        method here, ``"fcl"`` as FCL's own primitives).
    pose_a, pose_b : (start, end), a pose, or None
        Each body's motion: its poses at time 0 and time 1 (a ``(4, 4)`` transform, a pair
        ``(rotation, translation)``, a SciPy ``Rotation``, ...), or a ``(2, 4, 4)`` or
        ``(2, 3, 4)`` array of the two (``np.stack([start, end])``). A single pose, or None for
        the identity, keeps the body still.
    method : str
        ``"exact"`` (default), ``"dual"`` or ``"fcl"``: the distance queries run at each sampled
        time. Advancement needs proven lower bounds, not values certified far from contact, which
        "dual" pays its swarm rounds for; with "exact" or "fcl", a time whose query leaves the
        value unproven and proves neither contact nor the bodies farther apart than the
        threshold is asked again of "dual".
    tolerance : float
        Contact threshold (> 0), relative to the motion's size, the sum of the two bodies'
        bounding-ball diameters (between 2/3 and 2 times the pair's size where they touch):
        bodies within ``tolerance x size`` of each other touch.
    time_tolerance : float
        Largest width of the bracket ``[t_lower, t_upper]`` of a first contact, a fraction of
        the motion in (0, 1].
    max_iterations : int
        Distance queries at most; past them the answer is uncertified (and errs on the side of
        contact).
    motion : {"linear", "screw"}
        ``"linear"`` (default): the origin moves on the straight segment, ``T(t) = T0 + t (T1 -
        T0)``, while the body turns at a constant rate about a fixed axis through it, ``R(t) =
        R0 exp(t [w])``, ``w`` the rotation vector of ``R0^T R1`` (angle in [0, pi]).
        ``"screw"``: the 4x4 pose follows ``G(t) = G0 exp(t xi)``, ``xi`` the principal matrix
        logarithm of ``G0^-1 G1`` (the same ``w``, with a translation part ``v`` in the body's
        start frame): a constant turn about a fixed axis with a constant slide along it.

    Returns
    -------
    TimeOfImpactResult
        ``touches``, the bracket ``t_lower`` (apart before it, proven) and ``t_upper`` (in contact
        there, proven), the poses at ``t_upper``, the signed distance, witness points and normal
        there, ``certified``, ``iterations`` and ``status``.

    Raises
    ------
    ValueError
        For a pose that is not rigid or holds a NaN (naming ``pose_a start``, ...), a
        ``tolerance`` that is not positive, a ``time_tolerance`` outside (0, 1], or a method
        without distances.

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> cube, plate = sc.Box([0.5, 0.5, 0.5]), sc.Box([5e-4, 5, 5])
    >>> start, end = np.eye(4), np.eye(4)
    >>> start[0, 3], end[0, 3] = -10, 10     # through the plate in one step
    >>> r = sc.time_of_impact(cube, plate, pose_a=(start, end))
    >>> r.touches, r.certified, round(r.t_upper * 20 - 10, 6), r.normal.round(6).tolist()
    (True, True, -0.5005, [1.0, 0.0, 0.0])
    >>> sc.time_of_impact(cube, plate, pose_a=(start, start)).touches
    False
    """
    return _core.time_of_impact(
        a,
        b,
        pose_a=pose_a,
        pose_b=pose_b,
        method=method,
        tolerance=tolerance,
        time_tolerance=time_tolerance,
        max_iterations=max_iterations,
        motion=motion,
    )


def time_of_impact_many(
    As: BodiesLike,
    Bs: BodiesLike,
    *,
    poses_a: MotionsLike = None,
    poses_b: MotionsLike = None,
    method: str = "exact",
    tolerance: float = DEFAULT_TOLERANCE,
    time_tolerance: float = DEFAULT_TIME_TOLERANCE,
    max_iterations: int = DEFAULT_MOTION_ITERATIONS,
    threads: Optional[int] = None,
    motion: MotionKind = "linear",
) -> _core.TimeOfImpactBatch:
    """``time_of_impact`` for every row, in C++ threads without the GIL.

    Parameters
    ----------
    As, Bs : body, sequence of bodies, or array_like of shape (m, n, 3)
        The bodies row by row, as ``distance_many`` takes them; a single body serves every row.
    poses_a, poses_b : (starts, ends) or None
        Each row's motion: ``starts`` and ``ends`` are pose arrays as ``distance_many``'s
        ``poses_a`` (``(m, 4, 4)``, ``(m, 3, 4)`` or ``(rotations, translations)``), both of m
        rows, or both single poses (one motion for every row); None keeps the bodies still at
        the identity.
    threads : int, optional
        Worker threads (at most 1024); None uses one per hardware thread, woken once the
        motions left would take the calling thread over about 200 us alone. Answers do not
        depend on it.
    method, tolerance, time_tolerance, max_iterations, motion
        As for ``time_of_impact``.

    Returns
    -------
    TimeOfImpactBatch
        NumPy arrays ``touches``, ``t_lower``, ``t_upper``, ``certified``, ``iterations``,
        ``distance``, ``point_a``, ``point_b``, ``normal``, ``pose_a``, ``pose_b`` (one entry per
        row), and ``batch[i]``, row i's ``TimeOfImpactResult``.

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> starts, ends = np.tile(np.eye(4), (3, 1, 1)), np.tile(np.eye(4), (3, 1, 1))
    >>> starts[:, 0, 3], ends[:, 0, 3] = -5, 5
    >>> starts[:, 1, 3] = ends[:, 1, 3] = [0.0, 0.9, 1.1]    # the last misses by 0.1
    >>> r = sc.time_of_impact_many(sc.Box([0.5] * 3), sc.Box([0.5] * 3), poses_a=(starts, ends))
    >>> r.touches.tolist(), r.t_upper.round(4).tolist()
    ([True, True, False], [0.4, 0.4, 1.0])
    """
    return _core.time_of_impact_many(
        As,
        Bs,
        poses_a=poses_a,
        poses_b=poses_b,
        method=method,
        tolerance=tolerance,
        time_tolerance=time_tolerance,
        max_iterations=max_iterations,
        threads=threads,
        motion=motion,
    )
