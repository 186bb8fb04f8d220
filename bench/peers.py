"""The peers' convex shapes built as their users build them: python-fcl's and coal's convex hulls
of a point set (faces from SciPy's hull), shared by the per-call and the pose-batch benches."""

from __future__ import annotations

import numpy as np
from scipy.spatial import ConvexHull


def fcl_convex_object(points: np.ndarray):
    """A python-fcl collision object holding the convex hull of ``points``, at the identity."""
    import fcl

    faces = ConvexHull(points).simplices
    flat = np.hstack([np.full((len(faces), 1), 3), faces]).ravel()
    return fcl.CollisionObject(fcl.Convex(points, len(faces), flat), fcl.Transform())


def coal_convex(points: np.ndarray):
    """A coal ``Convex`` of the hull of ``points``."""
    import coal

    vertices = coal.StdVec_Vec3s()
    for p in points:
        vertices.append(np.asarray(p, dtype=float))
    triangles = coal.StdVec_Triangle()
    for i, j, k in ConvexHull(points).simplices:
        triangles.append(coal.Triangle(int(i), int(j), int(k)))
    return coal.Convex(vertices, triangles)
