"""
swarmcollide's C++ core: convex polyhedra, model (2) and its solvers.
"""
from __future__ import annotations
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Aabb', 'BatchResult', 'ConstraintHandling', 'ConvexPolyhedron', 'DistanceOptions', 'DistanceResult', 'DualOptions', 'ExactOptions', 'Hull', 'InertiaStrategy', 'ParticleCoefficients', 'PenaltyOptions', 'PenetrationAlgorithm', 'SwarmOptions', 'as_polyhedron', 'collide', 'collide_many', 'collision', 'constraint_violation', 'distance', 'distance_many', 'is_feasible', 'linear_decreasing_inertia', 'objective', 'pair_seed', 'project_onto_simplex', 'rank_adaptive_coefficients', 'separation', 'signed_distance']
class Aabb:
    """
    An axis-aligned bounding box with corners ``min`` and ``max``.
    """
    def __repr__(self) -> str:
        ...
    @property
    def max(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def min(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
class BatchResult:
    """
    
    Answers to many queries, one entry (or row) per pair, as NumPy arrays.
    
    Attributes
    ----------
    distance, lower_bound : numpy.ndarray, shape (m,)
    point_a, point_b : numpy.ndarray, shape (m, 3)
    colliding, certified, escalated : numpy.ndarray of bool, shape (m,)
    iterations : numpy.ndarray of int, shape (m,)
    """
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def certified(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def colliding(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def escalated(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def iterations(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def lower_bound(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
class ConstraintHandling:
    """
    How particles meet the constraints of model (2).
    
    Members:
    
      feasibility
    
      projection
    """
    __members__: typing.ClassVar[dict[str, ConstraintHandling]]  # value = {'feasibility': <ConstraintHandling.feasibility: 0>, 'projection': <ConstraintHandling.projection: 1>}
    feasibility: typing.ClassVar[ConstraintHandling]  # value = <ConstraintHandling.feasibility: 0>
    projection: typing.ClassVar[ConstraintHandling]  # value = <ConstraintHandling.projection: 1>
    @typing.overload
    def __eq__(self, other: ConstraintHandling) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: ConstraintHandling) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ConvexPolyhedron:
    """
    
    A convex polyhedron: the convex hull of a finite set of points (the paper's Definition 3).
    
    Parameters
    ----------
    points : array_like, shape (n, 3)
        At least one finite point. The points are kept as given: they are the vertices ``x_i`` of
        model (2). Flat, collinear and single-point sets are valid bodies.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> tetra = sc.ConvexPolyhedron([[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]])
    >>> tetra.support([1, 0, 0]).tolist()
    [1.0, 0.0, 0.0]
    >>> tetra.hull().dimension
    3
    """
    def __init__(self, points: typing.Any) -> None:
        ...
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def aabb(self) -> Aabb:
        """
        Smallest axis-aligned box containing the body.
        """
    def centroid(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Centre of mass of the solid (of the polygon, segment or point for lower-dimensional bodies).
        """
    def hull(self) -> Hull:
        """
        Convex hull through Qhull (an exact planar hull for flat bodies).
        """
    def support(self, direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        A point of the body farthest along ``direction``.
        """
    def support_index(self, direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> int:
        """
        Index of the point farthest along ``direction`` (first on ties).
        """
    @property
    def vertices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        The ``(n, 3)`` points the body was built from (read-only).
        """
class DistanceOptions:
    """
    A method and the parameters of its solver.
    """
    dual: DualOptions
    exact: ExactOptions
    method: str
    penalty: PenaltyOptions
    swarm: SwarmOptions
    def __init__(self) -> None:
        ...
class DistanceResult:
    """
    
    The answer of every distance query, whatever the method.
    
    ``lower_bound <= true distance <= distance`` always holds: ``distance`` is achieved by the witness
    points ``point_a`` and ``point_b`` (convex combinations of the bodies' points with ``weights_a``
    and ``weights_b``), and ``lower_bound`` is the separation along ``direction``.
    """
    def __repr__(self) -> str:
        ...
    @property
    def certified(self) -> bool:
        """
        True when the bounds prove the verdict.
        """
    @property
    def colliding(self) -> bool:
        ...
    @property
    def direction(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Unit direction certifying ``lower_bound`` (zero if none separates).
        """
    @property
    def distance(self) -> float:
        """
        Upper bound on the distance, achieved by the witness points.
        """
    @property
    def escalated_from(self) -> str:
        """
        The method whose unproven collision verdict was handed to ``method`` (empty if none).
        """
    @property
    def evaluations(self) -> int:
        ...
    @property
    def gap(self) -> float:
        """
        ``distance - lower_bound``: how far from exact the answer can be.
        """
    @property
    def history(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        Best distance after initialisation and after each iteration.
        """
    @property
    def iterations(self) -> int:
        ...
    @property
    def lower_bound(self) -> float:
        """
        Lower bound on the distance, certified by ``direction``.
        """
    @property
    def method(self) -> str:
        """
        The method that produced the answer.
        """
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Witness point on A.
        """
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Witness point on B.
        """
    @property
    def status(self) -> str:
        """
        'converged', 'max_iterations' or 'exact'.
        """
    @property
    def weights_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        lambda of model (2): nonnegative, summing to one.
        """
    @property
    def weights_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        delta of model (2): nonnegative, summing to one.
        """
class DualOptions:
    """
    
    Parameters of the dual swarm (method ``"dual"``): the paper's rank-adaptive swarm over unit
    directions, with an exact finish on the supporting features.
    
    ``tolerance`` is absolute; 0 (the default) means ``relative_tolerance`` times the bodies' size.
    ``feature_tolerance`` is relative to the bodies' size.
    """
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        """
        Raise ValueError naming the first invalid parameter.
        """
    @property
    def feature_tolerance(self) -> float:
        ...
    @feature_tolerance.setter
    def feature_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_iterations(self) -> int:
        ...
    @max_iterations.setter
    def max_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_rounds(self) -> int:
        ...
    @max_rounds.setter
    def max_rounds(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def relative_tolerance(self) -> float:
        ...
    @relative_tolerance.setter
    def relative_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        ...
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def swarm_size(self) -> int:
        ...
    @swarm_size.setter
    def swarm_size(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def tolerance(self) -> float:
        ...
    @tolerance.setter
    def tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def w_max(self) -> float:
        ...
    @w_max.setter
    def w_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def w_min(self) -> float:
        ...
    @w_min.setter
    def w_min(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class ExactOptions:
    """
    Parameters of the exact reference methods.
    """
    penetration: PenetrationAlgorithm
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        """
        Raise ValueError naming the first invalid parameter.
        """
    @property
    def distance_tolerance(self) -> float:
        ...
    @distance_tolerance.setter
    def distance_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_iterations(self) -> int:
        ...
    @max_iterations.setter
    def max_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def penetration_tolerance(self) -> float:
        ...
    @penetration_tolerance.setter
    def penetration_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def tolerance(self) -> float:
        ...
    @tolerance.setter
    def tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class Hull:
    """
    
    Convex hull of a polyhedron's points, as indices into those points.
    
    Attributes
    ----------
    dimension : int
        Affine dimension of the points: 0 (a point), 1 (a segment), 2 (a flat polygon) or 3 (a solid).
    vertex_indices : numpy.ndarray
        Indices of the points that are hull vertices, ascending.
    faces : numpy.ndarray
        ``(m, 3)`` triangles indexing the polyhedron's points, outward by the right-hand rule. A flat
        polygon is listed once facing each side; segments and points have no faces.
    """
    def __repr__(self) -> str:
        ...
    @property
    def dimension(self) -> int:
        ...
    @property
    def faces(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 3]"]:
        ...
    @property
    def vertex_indices(self) -> numpy.typing.NDArray[numpy.int32]:
        ...
class InertiaStrategy:
    """
    How inertia and acceleration are chosen: rank-adaptive (8)-(9) or linearly decreasing (7).
    
    Members:
    
      rank_adaptive
    
      linear_decreasing
    """
    __members__: typing.ClassVar[dict[str, InertiaStrategy]]  # value = {'rank_adaptive': <InertiaStrategy.rank_adaptive: 0>, 'linear_decreasing': <InertiaStrategy.linear_decreasing: 1>}
    linear_decreasing: typing.ClassVar[InertiaStrategy]  # value = <InertiaStrategy.linear_decreasing: 1>
    rank_adaptive: typing.ClassVar[InertiaStrategy]  # value = <InertiaStrategy.rank_adaptive: 0>
    @typing.overload
    def __eq__(self, other: InertiaStrategy) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: InertiaStrategy) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ParticleCoefficients:
    def __repr__(self) -> str:
        ...
    @property
    def c1(self) -> float:
        ...
    @property
    def c2(self) -> float:
        ...
    @property
    def w(self) -> float:
        ...
class PenaltyOptions:
    """
    Parameters of the exterior quadratic penalty baseline.
    """
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        """
        Raise ValueError naming the first invalid parameter.
        """
    @property
    def growth_factor(self) -> float:
        ...
    @growth_factor.setter
    def growth_factor(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def initial_weight(self) -> float:
        ...
    @initial_weight.setter
    def initial_weight(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def inner_iterations(self) -> int:
        ...
    @inner_iterations.setter
    def inner_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def outer_iterations(self) -> int:
        ...
    @outer_iterations.setter
    def outer_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def tolerance(self) -> float:
        ...
    @tolerance.setter
    def tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class PenetrationAlgorithm:
    """
    libccd's penetration routine: EPA or MPR.
    
    Members:
    
      epa
    
      mpr
    """
    __members__: typing.ClassVar[dict[str, PenetrationAlgorithm]]  # value = {'epa': <PenetrationAlgorithm.epa: 0>, 'mpr': <PenetrationAlgorithm.mpr: 1>}
    epa: typing.ClassVar[PenetrationAlgorithm]  # value = <PenetrationAlgorithm.epa: 0>
    mpr: typing.ClassVar[PenetrationAlgorithm]  # value = <PenetrationAlgorithm.mpr: 1>
    @typing.overload
    def __eq__(self, other: PenetrationAlgorithm) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: PenetrationAlgorithm) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class SwarmOptions:
    """
    Parameters of the swarm solvers; defaults are the paper's.
    """
    constraint_handling: ConstraintHandling
    inertia: InertiaStrategy
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        """
        Raise ValueError naming the first invalid parameter.
        """
    @property
    def c1(self) -> float:
        ...
    @c1.setter
    def c1(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def c2(self) -> float:
        ...
    @c2.setter
    def c2(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def feasibility_tolerance(self) -> float:
        ...
    @feasibility_tolerance.setter
    def feasibility_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_iterations(self) -> int:
        ...
    @max_iterations.setter
    def max_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        ...
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def swarm_size(self) -> int:
        ...
    @swarm_size.setter
    def swarm_size(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def tolerance(self) -> float:
        ...
    @tolerance.setter
    def tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def velocity_limit(self) -> float:
        ...
    @velocity_limit.setter
    def velocity_limit(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def w_max(self) -> float:
        ...
    @w_max.setter
    def w_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def w_min(self) -> float:
        ...
    @w_min.setter
    def w_min(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
def as_polyhedron(body: typing.Any, name: str = 'body') -> ConvexPolyhedron:
    """
    Return ``body`` as a ConvexPolyhedron, building one from ``(n, 3)`` points if needed.
    
    Errors name the argument as ``name``.
    """
def collide(a: typing.Any, b: typing.Any, options: DistanceOptions, escalate: bool) -> bool:
    ...
def collide_many(As: typing.Any, Bs: typing.Any, options: DistanceOptions, escalate: bool, threads: typing.Any) -> BatchResult:
    ...
def collision(a: typing.Any, b: typing.Any, options: DistanceOptions, escalate: bool) -> DistanceResult:
    ...
def constraint_violation(weights_a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], weights_b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> float:
    """
    Constraint violation (6): ``(sum(weights_a) - 1)**2 + (sum(weights_b) - 1)**2``.
    """
def distance(a: typing.Any, b: typing.Any, options: DistanceOptions) -> DistanceResult:
    ...
def distance_many(As: typing.Any, Bs: typing.Any, options: DistanceOptions, threads: typing.Any) -> BatchResult:
    ...
def is_feasible(weights_a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], weights_b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], tolerance: typing.SupportsFloat | typing.SupportsIndex = 1e-10) -> bool:
    """
    True when all weights lie in [0, 1] and the violation (6) is at most ``tolerance``.
    """
def linear_decreasing_inertia(iteration: typing.SupportsInt | typing.SupportsIndex, max_iterations: typing.SupportsInt | typing.SupportsIndex, w_start: typing.SupportsFloat | typing.SupportsIndex = 0.9, w_end: typing.SupportsFloat | typing.SupportsIndex = 0.4) -> float:
    """
    (7): the inertia weight after ``iteration`` of ``max_iterations``.
    """
def objective(a: typing.Any, b: typing.Any, weights_a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], weights_b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> float:
    """
    Objective (5): ``|| sum_j weights_b[j] y_j - sum_i weights_a[i] x_i ||``.
    
    The weights need not be feasible; see ``constraint_violation`` and ``is_feasible``.
    """
def pair_seed(seed: typing.SupportsInt | typing.SupportsIndex, index: typing.SupportsInt | typing.SupportsIndex) -> int:
    """
    The seed of pair ``index`` in a batch seeded with ``seed``.
    """
def project_onto_simplex(weights: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    Euclidean projection onto the probability simplex.
    """
def rank_adaptive_coefficients(rank: typing.SupportsInt | typing.SupportsIndex, swarm_size: typing.SupportsInt | typing.SupportsIndex, w_min: typing.SupportsFloat | typing.SupportsIndex = 0.4, w_max: typing.SupportsFloat | typing.SupportsIndex = 0.9) -> ParticleCoefficients:
    """
    (8)-(9): ``(w, c1, c2)`` of the particle ranked ``rank`` (1 = best).
    """
def separation(a: typing.Any, b: typing.Any, direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> float:
    """
    Separation of A and B along ``direction``: ``min_j n.y_j - max_i n.x_i`` for the unit ``n``.
    
    Every direction gives a lower bound on the distance; the best direction gives the distance itself
    when the bodies are apart.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> a = sc.ConvexPolyhedron([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> b = sc.ConvexPolyhedron([[3, 0, 0], [4, 0, 0], [3, 1, 0], [3, 0, 1]])
    >>> sc.separation(a, b, [1, 0, 0])
    2.0
    """
def signed_distance(a: typing.Any, b: typing.Any, options: DistanceOptions) -> DistanceResult:
    ...
