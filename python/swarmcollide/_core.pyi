"""
swarmcollide's C++ core: convex polyhedra, model (2), its solvers and queries.
"""
from __future__ import annotations
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Aabb', 'BatchResult', 'ConvexPolyhedron', 'DistanceResult', 'Hull', 'ParticleCoefficients', 'Query', 'as_polyhedron', 'constraint_violation', 'is_feasible', 'linear_decreasing_inertia', 'method_table', 'objective', 'pair_seed', 'project_onto_simplex', 'rank_adaptive_coefficients', 'separation']
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
    point_a, point_b, direction : numpy.ndarray, shape (m, 3)
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
    def direction(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
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
    def radius(self) -> float:
        """
        Half the diagonal of the bounding box: every point lies within it of the box's centre.
        """
    @property
    def vertices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        The ``(n, 3)`` points the body was built from (read-only).
        """
class DistanceResult:
    """
    
    The answer of every query, whatever the method, in the units of the input.
    
    ``lower_bound <= true value <= distance`` always holds (up to rounding, about 1e-14 of the pair's
    size): ``distance`` is achieved by the witness points ``point_a`` and ``point_b`` (convex
    combinations of the bodies' points with ``weights_a`` and ``weights_b``), and ``lower_bound`` is
    the separation along ``direction``. For signed distances the true value is minus the penetration
    depth when the bodies overlap, and ``point_b - point_a = distance * direction``.
    """
    def __repr__(self) -> str:
        ...
    @property
    def certified(self) -> bool:
        """
        True when the bounds prove the verdict (and, for signed distances, the value to within the tolerance).
        """
    @property
    def colliding(self) -> bool:
        """
        True when the bodies are within the tolerance of each other.
        """
    @property
    def direction(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Unit direction from A to B certifying ``lower_bound`` (zero if none).
        """
    @property
    def distance(self) -> float:
        """
        Upper bound on the distance (signed distance), achieved by the witnesses.
        """
    @property
    def escalated_from(self) -> typing.Any:
        """
        The method asked for, when another one answered (None otherwise).
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
        Best upper bound after initialisation and after each iteration.
        """
    @property
    def iterations(self) -> int:
        ...
    @property
    def lower_bound(self) -> float:
        """
        Lower bound on the distance (signed distance), certified by ``direction``.
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
        'converged' (the bounds are within the tolerance, or contact is proven) or 'max_iterations'.
        """
    @property
    def weights_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        lambda of model (2): nonnegative, summing to one (built when read).
        """
    @property
    def weights_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        delta of model (2): nonnegative, summing to one (built when read).
        """
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
class ParticleCoefficients:
    """
    Inertia weight ``w`` and accelerations ``c1``, ``c2`` of one particle.
    """
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
class Query:
    """
    
    A method with its parameters, validated once, that answers queries between pairs of bodies.
    
    Every query computes in a frame centred on the pair and scaled to its size, so answers scale with
    the unit of length. ``tolerance`` is relative to the pair's size (the diameter of a ball around
    both bodies): it is the precision of every answer and the distance below which bodies collide.
    """
    def __init__(self, method: str = 'dual', tolerance: typing.Any = 1e-09, seed: typing.Any = 0, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def collide(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None, escalate: bool = True) -> bool:
        ...
    def collide_many(self, As: typing.Any, Bs: typing.Any, threads: typing.Any = None, first_index: typing.Any = 0, escalate: bool = True) -> BatchResult:
        """
        The query for every pair ``(As[i], Bs[i])``, in C++ threads without the GIL.
        
        Pair i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
        number of threads or on how a batch is split. ``As`` and ``Bs`` are sequences of polyhedra or
        ``(n, 3)`` arrays, or ``(m, n, 3)`` arrays (the fastest: each pair's bodies are then built and
        freed by the thread that answers it).
        """
    def collision(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None, escalate: bool = True) -> DistanceResult:
        ...
    def distance(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None) -> DistanceResult:
        ...
    def distance_many(self, As: typing.Any, Bs: typing.Any, threads: typing.Any = None, first_index: typing.Any = 0) -> BatchResult:
        """
        The query for every pair ``(As[i], Bs[i])``, in C++ threads without the GIL.
        
        Pair i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
        number of threads or on how a batch is split. ``As`` and ``Bs`` are sequences of polyhedra or
        ``(n, 3)`` arrays, or ``(m, n, 3)`` arrays (the fastest: each pair's bodies are then built and
        freed by the thread that answers it).
        """
    def signed_distance(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None) -> DistanceResult:
        ...
    def signed_distance_many(self, As: typing.Any, Bs: typing.Any, threads: typing.Any = None, first_index: typing.Any = 0) -> BatchResult:
        """
        The query for every pair ``(As[i], Bs[i])``, in C++ threads without the GIL.
        
        Pair i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
        number of threads or on how a batch is split. ``As`` and ``Bs`` are sequences of polyhedra or
        ``(n, 3)`` arrays, or ``(m, n, 3)`` arrays (the fastest: each pair's bodies are then built and
        freed by the thread that answers it).
        """
    @property
    def method(self) -> str:
        ...
    @property
    def parameters(self) -> dict:
        """
        The method's parameters and their values.
        """
    @property
    def seed(self) -> int:
        ...
    @property
    def tolerance(self) -> float:
        ...
def as_polyhedron(body: typing.Any, name: str = 'body') -> ConvexPolyhedron:
    """
    Return ``body`` as a ConvexPolyhedron, building one from ``(n, 3)`` points if needed.
    
    Errors name the argument as ``name``.
    """
def constraint_violation(weights_a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], weights_b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> float:
    """
    Constraint violation (6): ``(sum(weights_a) - 1)**2 + (sum(weights_b) - 1)**2``.
    """
def is_feasible(weights_a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], weights_b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], tolerance: typing.SupportsFloat | typing.SupportsIndex = 1e-10) -> bool:
    """
    True when all weights lie in [0, 1] and the violation (6) is at most ``tolerance``.
    """
def linear_decreasing_inertia(iteration: typing.SupportsInt | typing.SupportsIndex, max_iterations: typing.SupportsInt | typing.SupportsIndex, w_start: typing.SupportsFloat | typing.SupportsIndex = 0.9, w_end: typing.SupportsFloat | typing.SupportsIndex = 0.4) -> float:
    """
    (7): the inertia weight after ``iteration`` of ``max_iterations``.
    """
def method_table() -> list:
    """
    Every method as a dictionary: name, summary, queries, always_certified, parameters.
    """
def objective(a: typing.Any, b: typing.Any, weights_a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], weights_b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> float:
    """
    Objective (5): ``|| sum_j weights_b[j] y_j - sum_i weights_a[i] x_i ||``.
    
    The weights need not be feasible; see ``constraint_violation`` and ``is_feasible``.
    """
def pair_seed(seed: typing.SupportsInt | typing.SupportsIndex, index: typing.SupportsInt | typing.SupportsIndex) -> int:
    """
    The seed of the pair with global index ``index`` in a batch seeded with ``seed``.
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
