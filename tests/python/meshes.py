"""Meshes the mesh tests make themselves: polycubes (unions of unit cells), a torus and a tube,
and python-fcl's BVH mesh distance as the exact triangle-mesh oracle."""

from __future__ import annotations

import numpy as np
import trimesh

# Each axis with the two axes spanning the faces perpendicular to it, right-handed.
_AXES = (((1, 0, 0), (0, 1, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
         ((0, 0, 1), (1, 0, 0), (0, 1, 0)))


def polycube(cells, size: float = 1.0) -> trimesh.Trimesh:
    """The watertight surface of a union of unit cells ``(i, j, k)``: the faces between a
    filled cell and an empty one, outward."""
    filled = {tuple(c) for c in cells}
    quads = []
    for cell in filled:
        c = np.array(cell)
        for n, u, v in (tuple(map(np.array, axes)) for axes in _AXES):
            for sign in (1, -1):
                if tuple(c + sign * n) in filled:
                    continue
                base = c + (n if sign > 0 else 0)
                quad = [base, base + u, base + u + v, base + v]
                quads.append(quad if sign > 0 else quad[::-1])
    points = np.array(quads, dtype=float).reshape(-1, 3) * size
    corners = np.arange(len(points)).reshape(-1, 4)
    faces = np.concatenate([corners[:, [0, 1, 2]], corners[:, [0, 2, 3]]])
    mesh = trimesh.Trimesh(points, faces)
    mesh.merge_vertices()
    return mesh


def l_shape() -> trimesh.Trimesh:
    """Two boxes: a 2 x 1 x 1 bar and a 1 x 1 x 1 cube on its end."""
    return polycube([(0, 0, 0), (1, 0, 0), (0, 1, 0)])


def u_shape() -> trimesh.Trimesh:
    """A U, 3 x 3 x 1: a base and two arms, the gap between them 1 x 2."""
    return polycube([(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (0, 2, 0), (2, 1, 0), (2, 2, 0)])


def box_with_hole() -> trimesh.Trimesh:
    """A 3 x 3 x 1 slab with a 1 x 1 hole through its middle."""
    return polycube([(i, j, 0) for i in range(3) for j in range(3) if (i, j) != (1, 1)])


def torus() -> trimesh.Trimesh:
    """A torus around z: major radius 1, minor radius 0.3 (its hole has radius 0.7)."""
    return trimesh.creation.torus(1.0, 0.3, major_sections=24, minor_sections=12)


def cup() -> trimesh.Trimesh:
    """A cup-like annulus: a tube along z of radii 0.6 and 1, height 1.5, centred at 0."""
    return trimesh.creation.annulus(0.6, 1.0, 1.5, sections=24)


MESHES = {
    "l_shape": l_shape,
    "u_shape": u_shape,
    "box_with_hole": box_with_hole,
    "torus": torus,
    "cup": cup,
}


def homogeneous(rotation=None, translation=(0, 0, 0)) -> np.ndarray:
    pose = np.eye(4)
    if rotation is not None:
        pose[:3, :3] = rotation
    pose[:3, 3] = translation
    return pose


def fcl_distance(mesh_a, pose_a, mesh_b, pose_b) -> float:
    """python-fcl's BVH (OBBRSS) distance between the two triangle meshes at their poses: the
    distance between their surfaces, which is the solids' distance when they are apart."""
    import fcl

    objects = []
    for mesh, pose in ((mesh_a, pose_a), (mesh_b, pose_b)):
        model = fcl.BVHModel()
        model.beginModel(len(mesh.vertices), len(mesh.faces))
        model.addSubModel(np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces))
        model.endModel()
        objects.append(fcl.CollisionObject(model, fcl.Transform(pose[:3, :3], pose[:3, 3])))
    return fcl.distance(objects[0], objects[1], fcl.DistanceRequest(), fcl.DistanceResult())
