"""Poses from quaternions, with the order of the components stated rather than guessed.

Libraries disagree on where a quaternion's scalar goes: MuJoCo writes ``w x y z``; SciPy's
``Rotation.as_quat``, pybullet and ROS write ``x y z w``. Both orders of a unit quaternion are unit
quaternions, so no check can tell them apart: ``pose_from_quaternion`` takes the order as a
required keyword.
"""

from __future__ import annotations

from typing import Optional

import numpy as np
import numpy.typing as npt

QUATERNION_ORDERS = ("wxyz", "xyzw")
"""The orders ``pose_from_quaternion`` takes: scalar first (MuJoCo) or last (SciPy, pybullet)."""

UNIT_TOLERANCE = 1e-3
"""How far from 1 a quaternion's norm may be; within it the quaternion is normalised (a
quaternion printed to 4 digits is that far off), beyond it refused as not a rotation."""


def pose_from_quaternion(
    quaternion: npt.ArrayLike, translation: Optional[npt.ArrayLike] = None, *, order: str
) -> np.ndarray:
    """A ``(4, 4)`` rigid transform from a unit quaternion and a translation.

    Parameters
    ----------
    quaternion : array_like, shape (4,) or (m, 4)
        A unit quaternion (or m of them) in the order ``order`` names. A norm within
        ``UNIT_TOLERANCE`` of 1 is normalised; any other norm (zero included) is refused.
    translation : array_like, shape (3,) or (m, 3), optional
        Where the body's origin goes (default: nowhere, the zero vector).
    order : {"wxyz", "xyzw"}
        Where the scalar part is: ``"wxyz"`` as MuJoCo writes quaternions, ``"xyzw"`` as SciPy's
        ``Rotation.as_quat``, pybullet and ROS do. Required: the two cannot be told apart.

    Returns
    -------
    numpy.ndarray, shape (4, 4) or (m, 4, 4)
        What every ``pose`` and ``poses`` argument takes.

    Raises
    ------
    TypeError
        For a quaternion or translation that does not hold real numbers, or an order that is not
        a string.
    ValueError
        For another order, a shape other than those above, a NaN or infinite value, or a
        quaternion whose norm is not 1.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> half_turn = [0.0, 0.0, 1.0, 0.0]  # 180 degrees about z, scalar last
    >>> (sc.pose_from_quaternion(half_turn, [1, 2, 3], order="xyzw") + 0.0).tolist()
    [[-1.0, 0.0, 0.0, 1.0], [0.0, -1.0, 0.0, 2.0], [0.0, 0.0, 1.0, 3.0], [0.0, 0.0, 0.0, 1.0]]
    >>> quarter_turn = [0.7071, 0, 0, 0.7071]  # 90 degrees about z, scalar first, 4 digits
    >>> (sc.pose_from_quaternion(quarter_turn, order="wxyz")[:3, :3].round(12) + 0.0).tolist()
    [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    """
    if not isinstance(order, str):
        raise TypeError(f"order must be a string, 'wxyz' or 'xyzw', got {type(order).__name__}")
    if order not in QUATERNION_ORDERS:
        raise ValueError(
            f"order must be 'wxyz' (scalar first, as MuJoCo writes quaternions) or 'xyzw' "
            f"(scalar last, as SciPy and pybullet do), got {order!r}"
        )
    q = _real(quaternion, "quaternion")
    if q.ndim not in (1, 2) or q.shape[-1] != 4:
        raise ValueError(f"quaternion must have shape (4,) or (m, 4), got {q.shape}")
    if not np.isfinite(q).all():
        raise ValueError("quaternion has a NaN or infinite component")
    # Scaled by the largest component first: the squares of a component of 1e300 overflow, and
    # its norm would be said as inf.
    scale = np.abs(q).max(axis=-1, keepdims=True)
    scale[scale == 0] = 1
    with np.errstate(over="ignore"):  # a norm beyond the largest double is inf, said below
        norm = scale * np.linalg.norm(q / scale, axis=-1, keepdims=True)
    off = np.abs(norm - 1) > UNIT_TOLERANCE
    if off.any():
        at = "" if q.ndim == 1 else f"[{int(np.flatnonzero(off)[0])}]"
        value = float(norm.flat[np.flatnonzero(off)[0]])
        shown = f"{value:.6g}" if np.isfinite(value) else "above the largest double (1.8e308)"
        raise ValueError(
            f"quaternion{at} has norm {shown}: a rotation's "
            f"quaternion has norm 1 (within {UNIT_TOLERANCE:g}); divide it by its norm yourself "
            "if it is a rotation"
        )
    q = q / norm
    w, x, y, z = np.moveaxis(q if order == "wxyz" else np.roll(q, 1, axis=-1), -1, 0)
    rows = (
        (1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
        (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
        (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)),
    )
    pose = np.zeros(q.shape[:-1] + (4, 4))
    pose[..., :3, :3] = np.stack([np.stack(row, axis=-1) for row in rows], axis=-2)
    pose[..., 3, 3] = 1
    if translation is not None:
        t = _real(translation, "translation")
        if t.shape != q.shape[:-1] + (3,):
            expected = "(3,)" if q.ndim == 1 else f"({len(q)}, 3), one per quaternion"
            raise ValueError(f"translation must have shape {expected}, got {t.shape}")
        if not np.isfinite(t).all():
            raise ValueError("translation has a NaN or infinite component")
        pose[..., :3, 3] = t
    return pose


def _real(value: npt.ArrayLike, name: str) -> np.ndarray:
    """``value`` as a float64 array; TypeError naming ``name`` unless it holds real numbers."""
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be an array of real numbers, got {type(value).__name__}")
    if isinstance(value, np.ma.MaskedArray):  # NumPy's conversion would drop its mask
        raise TypeError(f"{name} is a NumPy masked array, whose mask would be ignored: pass "
                        f"{name}.filled(value) with the value the masked entries should take, "
                        "or a plain array")
    try:
        array = np.asarray(value)
    except ValueError as error:  # a ragged sequence
        raise ValueError(f"{name} must be an array of real numbers: {error}") from None
    if array.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got an array of dtype {array.dtype}")
    return array.astype(np.float64)
