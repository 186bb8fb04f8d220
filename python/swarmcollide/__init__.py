"""Distance, collision and penetration between convex polyhedra, and between compound bodies
(unions of convex parts, from mesh files by convex decomposition).

The method is the improved particle swarm optimizer of the paper "Research on Convex Polyhedron
Collision Detection Algorithm Based on Improved Particle Swarm Optimization": the distance between
two convex polyhedra is the non-linear program (2) over convex-combination weights, solved by a
swarm whose particles get rank-based inertia (8)-(9). The default method runs that swarm over
separating directions with an exact finish, so every verdict is proven; every answer carries
bounds that state how far from exact it can be.

Examples
--------
>>> import swarmcollide as sc
>>> a = sc.ConvexPolyhedron([[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]])
>>> b = [[1, -1, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]]
>>> r = sc.distance(a, b)
>>> r.distance, r.colliding, r.certified
(1.0, False, True)
"""

from importlib.metadata import version as _version

from . import _core

from ._core import (
    Aabb,
    BatchResult,
    Box,
    Capsule,
    CompoundResult,
    Cone,
    CompoundStats,
    ContactResult,
    ConvexPolyhedron,
    Cylinder,
    DistanceResult,
    Ellipsoid,
    Hull,
    Joint,
    ParticleCoefficients,
    PartNode,
    Query,
    Scene,
    SceneResult,
    SceneStats,
    Sphere,
    as_polyhedron,
    constraint_violation,
    is_feasible,
    linear_decreasing_inertia,
    objective,
    pair_seed,
    project_onto_simplex,
    rank_adaptive_coefficients,
    separation,
)
from .mesh import (
    DECOMPOSERS,
    CompoundBody,
    Decomposition,
    cache_directory,
    load_mesh,
    measure_deviation,
    mesh_hash,
)
from .motion import (
    DEFAULT_TIME_TOLERANCE,
    MotionLike,
    MotionsLike,
    TimeOfImpactBatch,
    TimeOfImpactResult,
    time_of_impact,
    time_of_impact_many,
    MotionKind,
    SweepResult,
)
from .poses import QUATERNION_ORDERS, pose_from_quaternion
from .robot import LIMIT_MODES, PairProposal, Robot, RobotCheck, RobotChecker, RobotMotion
from .queries import (
    DEFAULT_TOLERANCE,
    METHODS,
    BodiesLike,
    MethodInfo,
    Parameter,
    Parameters,
    PolyhedronLike,
    PoseLike,
    PosesLike,
    collide,
    collide_many,
    collision,
    distance,
    distance_many,
    query,
    signed_distance,
    signed_distance_many,
)

__version__ = _version("swarmcollide")

BROADPHASES = tuple(_core.broadphases())
"""The broadphase managers a ``Scene`` can use, the default (``"dynamic_aabb_tree"``) first."""

__all__ = [
    "BROADPHASES",
    "DECOMPOSERS",
    "DEFAULT_TOLERANCE",
    "METHODS",
    "Aabb",
    "BatchResult",
    "BodiesLike",
    "Box",
    "Capsule",
    "CompoundBody",
    "CompoundResult",
    "CompoundStats",
    "Cone",
    "ContactResult",
    "ConvexPolyhedron",
    "Cylinder",
    "Decomposition",
    "DistanceResult",
    "Ellipsoid",
    "Hull",
    "Joint",
    "LIMIT_MODES",
    "MethodInfo",
    "Parameter",
    "Parameters",
    "ParticleCoefficients",
    "PairProposal",
    "PartNode",
    "PolyhedronLike",
    "PoseLike",
    "PosesLike",
    "QUATERNION_ORDERS",
    "Query",
    "Robot",
    "RobotCheck",
    "RobotChecker",
    "RobotMotion",
    "Scene",
    "SceneResult",
    "SceneStats",
    "Sphere",
    "as_polyhedron",
    "cache_directory",
    "collide",
    "collide_many",
    "collision",
    "constraint_violation",
    "distance",
    "distance_many",
    "is_feasible",
    "linear_decreasing_inertia",
    "load_mesh",
    "measure_deviation",
    "mesh_hash",
    "objective",
    "pair_seed",
    "pose_from_quaternion",
    "project_onto_simplex",
    "query",
    "rank_adaptive_coefficients",
    "separation",
    "signed_distance",
    "signed_distance_many",
    "DEFAULT_TIME_TOLERANCE",
    "MotionLike",
    "MotionsLike",
    "TimeOfImpactBatch",
    "TimeOfImpactResult",
    "time_of_impact",
    "time_of_impact_many",
    "MotionKind",
    "SweepResult",
]
