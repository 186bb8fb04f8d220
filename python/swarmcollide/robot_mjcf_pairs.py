"""The geom pairs MuJoCo's collision detection considers: its contact filter, read from a
compiled model (``mj_collision`` in MuJoCo's ``engine_collision_driver.c``)."""

from __future__ import annotations

from typing import List, Optional, Tuple

import numpy as np


def contacts_switched_off(model) -> Optional[str]:
    """The flag of a ``mujoco.MjModel`` that turns its collision detection off, ``"contact"`` or
    ``"constraint"`` (``<option><flag contact="disable"/>``), or None: with either, MuJoCo's
    ``mj_collision`` returns before it tests any pair, ``<contact><pair>`` included."""
    import mujoco  # the model is MuJoCo's: its package is there

    for flag, bit in (("contact", mujoco.mjtDisableBit.mjDSBL_CONTACT),
                      ("constraint", mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)):
        if model.opt.disableflags & int(bit):
            return flag
    return None


def checked_geom_pairs(model) -> List[Tuple[int, int]]:
    """The pairs ``(g1, g2)``, ``g1 < g2``, of a ``mujoco.MjModel``'s geoms that MuJoCo tests
    for contact, before its bounding-volume tests (which depend on the configuration).

    No pair when the model switches contacts off (``contacts_switched_off``). Otherwise a pair
    ``<contact><pair>`` names is always tested, and any other pair when all hold:

    - the geoms' bodies are not welded together (bodies without a joint between them move as
      one, MuJoCo's ``body_weldid``; so never two geoms of one body);
    - their masks match: ``(contype1 & conaffinity2) or (contype2 & conaffinity1)``;
    - their welded bodies are not parent and child, unless one of them is the world (MuJoCo
      filters parents only between moving bodies) or the model turns the filter off
      (``<flag filterparent="disable"/>``);
    - their bodies are not a ``<contact><exclude>`` pair.
    """
    import mujoco  # the model is MuJoCo's: its package is there

    if contacts_switched_off(model):
        return []
    body = np.asarray(model.geom_bodyid, dtype=np.int64)
    weld = np.asarray(model.body_weldid, dtype=np.int64)
    parent = np.asarray(model.body_parentid, dtype=np.int64)
    welded = weld[body]
    welded_parent = weld[parent[welded]]
    contype = np.asarray(model.geom_contype, dtype=np.int64)
    conaffinity = np.asarray(model.geom_conaffinity, dtype=np.int64)
    a, b = np.triu_indices(model.ngeom, 1)
    tested = welded[a] != welded[b]
    tested &= ((contype[a] & conaffinity[b]) | (contype[b] & conaffinity[a])) != 0
    if not model.opt.disableflags & int(mujoco.mjtDisableBit.mjDSBL_FILTERPARENT):
        moving = (welded[a] != 0) & (welded[b] != 0)
        related = (welded[a] == welded_parent[b]) | (welded[b] == welded_parent[a])
        tested &= ~(moving & related)
    # MuJoCo signs an excluded body pair (low << 16) + high, the two bodies' ids in order.
    low, high = np.minimum(body[a], body[b]), np.maximum(body[a], body[b])
    excluded = np.asarray(model.exclude_signature[:model.nexclude], dtype=np.int64)
    tested &= ~np.isin((low << 16) + high, excluded)
    pairs = {(int(g1), int(g2)) for g1, g2 in zip(a[tested], b[tested])}
    for g1, g2 in zip(model.pair_geom1[:model.npair], model.pair_geom2[:model.npair]):
        pairs.add((int(min(g1, g2)), int(max(g1, g2))))
    return sorted(pairs)
