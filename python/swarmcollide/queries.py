"""Distance, signed distance and collision queries between convex polyhedra and compound bodies.

Every query function takes the same keywords: ``method``, ``tolerance``, ``seed``, the bodies'
poses, and the solver parameters of ``Parameters`` that apply to the method (``METHODS`` lists
them). The work is done by a cached ``Query`` per distinct set of keywords, so repeated calls
cost a dictionary lookup before the C++ solver runs. ``distance``, ``signed_distance``,
``collision`` and ``collide`` are read in C++ (``_core.query_function``) when no solver parameter
is given, which costs less than a call to a Python function.
"""

from __future__ import annotations

import inspect
import sys
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Tuple, TypeVar, Union, cast

import numpy.typing as npt

from . import _core

if sys.version_info >= (3, 11):
    from typing import TypedDict, Unpack
else:  # pragma: no cover - exercised on older interpreters only
    from typing_extensions import TypedDict, Unpack

Query = _core.Query
DistanceResult = _core.DistanceResult
BatchResult = _core.BatchResult

PolyhedronLike = Union[_core.ConvexPolyhedron, _core.CompoundBody, npt.ArrayLike, Any]
"""A ``ConvexPolyhedron``, anything ``ConvexPolyhedron(points)`` accepts (``(n, 3)`` points, or a
mesh such as a ``trimesh.Trimesh``, which stands for the convex hull of its ``vertices``), or a
``CompoundBody``: a query with a compound body on either side returns a ``CompoundResult``."""

PoseLike = Union[None, npt.ArrayLike, Tuple[Any, npt.ArrayLike], Any]
"""None (the identity), a ``(4, 4)`` rigid transform or its top ``(3, 4)`` rows, a pair
``(rotation, translation)`` whose rotation is a ``(3, 3)`` matrix or a SciPy ``Rotation``, or a
``Rotation`` alone (no translation). ``pose_from_quaternion`` makes one from a quaternion. A
float32 (or float16) rotation is its rounding of a rotation: within 1e-5 of one, it is read as
the nearest rotation; anything farther (a scaling, a shear) is refused as in float64."""

PosesLike = Union[None, npt.ArrayLike, Tuple[Any, npt.ArrayLike], Any]
"""None (every body at the identity), an ``(m, 4, 4)`` or ``(m, 3, 4)`` array of rigid
transforms, or a pair ``(rotations, translations (m, 3))`` whose rotations are an ``(m, 3, 3)``
array or a SciPy ``Rotation`` of m rotations (alone: no translations), or a list of m poses
(each a ``PoseLike``). In a batch, a single pose serves every row. Float32 rotations are read as
for a ``PoseLike``."""

BodiesLike = Union[PolyhedronLike, Sequence[PolyhedronLike], npt.ArrayLike]
"""One body for every row (a ``ConvexPolyhedron``, a ``CompoundBody``, an ``(n, 3)`` NumPy array
or a mesh such as a ``trimesh.Trimesh``), a sequence of polyhedra (or of ``(n, 3)`` point arrays,
or of compound bodies), or an ``(m, n, 3)`` array."""

DEFAULT_TOLERANCE = 1e-9
"""The default ``tolerance``, relative to the pair's size."""


class Parameters(TypedDict, total=False):
    """Solver parameters; each applies to the methods ``METHODS`` lists it for."""

    swarm_size: int
    max_iterations: int
    w_min: float
    w_max: float
    c1: float
    c2: float
    velocity_limit: float
    feasibility_tolerance: float
    constraint_handling: str
    initial_weight: float
    growth_factor: float
    outer_iterations: int
    inner_iterations: int
    feature_tolerance: float
    max_rounds: int


@dataclass(frozen=True)
class Parameter:
    """A solver parameter as the core's method table describes it."""

    name: str
    kind: str
    description: str
    minimum: float
    maximum: float
    minimum_excluded: bool
    choices: Tuple[str, ...]
    default: Any


@dataclass(frozen=True)
class MethodInfo:
    """A method: what it answers, whether its verdicts are always proven, and its parameters."""

    name: str
    summary: str
    queries: Tuple[str, ...]
    always_certified: bool
    parameters: Tuple[Parameter, ...]


METHODS: Mapping[str, MethodInfo] = MappingProxyType(
    {
        entry["name"]: MethodInfo(
            name=entry["name"],
            summary=entry["summary"],
            queries=entry["queries"],
            always_certified=entry["always_certified"],
            parameters=tuple(Parameter(**p) for p in entry["parameters"]),
        )
        for entry in _core.method_table()
    }
)
"""Every method, from the core's table, the default (``"dual"``) first."""

_CACHE_SIZE = 256
_queries: Dict[tuple, _core.Query] = {}


def query(
    method: str = "dual",
    *,
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    **parameters: Unpack[Parameters],
) -> _core.Query:
    """The ``Query`` for these keywords, built and validated on first use and then reused.

    Raises ``ValueError`` for an unknown method, a parameter that does not apply to it or a
    value out of range, and ``TypeError`` for a value of the wrong type.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> q = sc.query("ipso", swarm_size=20)
    >>> q
    Query(method='ipso', tolerance=1e-09, seed=0, swarm_size=20, max_iterations=200, w_min=0.4, w_max=0.9, velocity_limit=0.02, feasibility_tolerance=1e-10, constraint_handling='projection')
    >>> q is sc.query("ipso", swarm_size=20)
    True
    """
    # Types are part of the key: True == 1 and 1.0 == 1, but they are not the same argument.
    key: tuple = (method, tolerance, type(tolerance), seed, type(seed))
    if parameters:
        key += tuple((k, v, type(v)) for k, v in sorted(parameters.items()))
    try:
        return _queries[key]
    except KeyError:
        pass
    except TypeError:  # an unhashable value: the constructor names what is wrong with it
        return _core.Query(method, tolerance, seed, **parameters)
    built = _core.Query(method, tolerance, seed, **parameters)
    if len(_queries) >= _CACHE_SIZE:
        _queries.clear()
    _queries[key] = built
    return built


_DEFAULT_SEED = 0
_default_queries: Dict[str, _core.Query] = {}


def _query_for(method: str, tolerance: float, seed: int, parameters: Mapping[str, Any]) -> Query:
    """``query(method, tolerance=tolerance, seed=seed, **parameters)`` for the query functions.

    The usual call, the default tolerance and seed without parameters, finds its query by the
    method's name alone: building ``query``'s typed key costs about a third of a small query.
    The identity tests let only the defaults themselves through (``seed=False`` equals 0).
    """
    if (
        tolerance is DEFAULT_TOLERANCE
        and seed is _DEFAULT_SEED
        and not parameters
        and type(method) is str
    ):
        try:
            return _default_queries[method]
        except KeyError:
            # query() raises for an unknown method, so only valid names are kept.
            built = _default_queries[method] = query(method)
            return built
    return query(method, tolerance=tolerance, seed=seed, **parameters)


def _refuse_pose_keywords(function: str, parameters: Mapping[str, Any], batch: bool) -> None:
    """Raise TypeError for the other kind of query's pose keyword (``pose_b`` to a batch,
    ``poses_b`` to a pair query), which would otherwise reach ``Query`` as a solver parameter
    and be answered with the method's parameters."""
    if batch:
        wrong, taken = ("pose_a", "pose_b"), "poses_a and poses_b (one pose per row)"
    else:
        wrong, taken = ("poses_a", "poses_b"), "pose_a and pose_b"
    for name in wrong:
        if name in parameters:
            raise TypeError(f"{function} takes {taken}, not {name}")


QueryFunction = TypeVar("QueryFunction", bound=Callable[..., Any])

PYTHON_PATHS: Dict[str, Callable[..., Any]] = {}
"""The query functions as written in Python, by name: their C++ versions hand them every call they
do not answer themselves (solver parameters, unusual types, errors), and the tests check that
both give the same answers."""


def _answered_in_cpp(
    make: Callable[[Callable[..., Any], str], Any] = _core.query_function,
) -> Callable[[QueryFunction], QueryFunction]:
    """A decorator: the function as the C++ function ``make`` builds from it (``query_function``,
    or ``motion_function`` for ``time_of_impact``), with its name, documentation and signature
    (less the annotations, which only the Python definition keeps for type checkers)."""

    def answered(python_path: QueryFunction) -> QueryFunction:
        PYTHON_PATHS[python_path.__name__] = python_path
        signature = inspect.signature(python_path)
        plain = signature.replace(
            parameters=[p.replace(annotation=p.empty) for p in signature.parameters.values()],
            return_annotation=signature.empty,
        )
        return cast(QueryFunction, make(python_path, str(plain)))

    return answered


@_answered_in_cpp()
def distance(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    pose_a: PoseLike = None,
    pose_b: PoseLike = None,
    **parameters: Unpack[Parameters],
) -> _core.DistanceResult:
    """Distance between two convex polyhedra: model (2) of the paper.

    Parameters
    ----------
    a, b : ConvexPolyhedron or array_like, shape (n, 3)
        The bodies, or the points whose convex hulls they are, in their own frames; a mesh
        (a ``trimesh.Trimesh``, or any object with ``(n, 3)`` ``vertices``) stands for the convex
        hull of its vertices (``CompoundBody.from_mesh`` keeps a non-convex one's shape).
    method : str
        One of ``METHODS``: ``"dual"`` (default; the paper's rank-adaptive swarm over separating
        directions, certified), ``"ipso"`` (the paper's improved PSO on model (2)), ``"pso"``
        (linearly decreasing inertia (7)), ``"penalty"`` (the paper's baseline), ``"exact"``
        (Wolfe's algorithm), ``"fcl"`` (FCL's GJK, checked).
    tolerance : float
        Precision and contact threshold, relative to the pair's size (the diameter of a ball
        around both bodies), so that answers do not depend on the unit of length. Zero asks for
        answers as exact as double precision can prove.
    seed : int
        Seed of the randomised methods; the same seed gives the same answer.
    pose_a, pose_b : array_like, optional
        Where the bodies are: a ``(4, 4)`` rigid transform (or its top ``(3, 4)`` rows), a pair
        ``(rotation, translation)`` whose rotation is a ``(3, 3)`` matrix or a SciPy ``Rotation``,
        or a ``Rotation`` alone; ``pose_from_quaternion`` turns a quaternion into one. Results
        are in world coordinates. Moving a body never recomputes its hull.
    **parameters
        Solver parameters of ``method`` (see ``METHODS[method].parameters``). The largest budgets
        of ``"ipso"``, ``"pso"`` and ``"penalty"`` run for hours; Ctrl-C stops them
        (``KeyboardInterrupt``, within 20 ms of the solver's iterations).

    Returns
    -------
    DistanceResult
        ``lower_bound <= true distance <= distance``; ``certified`` when the bounds prove the
        verdict. A ``CompoundResult`` (a DistanceResult naming ``part_a`` and ``part_b``) when
        either body is a ``CompoundBody``: the distance between the unions of their convex
        parts, found by branch and bound over their bounding-volume trees and certified for the
        parts.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> a = [[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]]
    >>> b = [[1, -1, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]]
    >>> r = sc.distance(a, b)
    >>> r.method, r.distance, r.lower_bound, r.certified
    ('dual', 1.0, 1.0, True)
    >>> r.weights_a.tolist(), r.weights_b.tolist()
    ([0.0, 1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0])
    >>> round(sc.distance(a, b, method="ipso", seed=0).distance, 6)
    1.0
    """
    _refuse_pose_keywords("distance", parameters, batch=False)
    return _query_for(method, tolerance, seed, parameters).distance(
        a, b, pose_a, pose_b
    )


@_answered_in_cpp()
def signed_distance(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    pose_a: PoseLike = None,
    pose_b: PoseLike = None,
    **parameters: Unpack[Parameters],
) -> _core.DistanceResult:
    """Distance when apart, minus the penetration depth when overlapping.

    ``direction`` is the unit contact normal from A to B and
    ``point_b - point_a = distance * direction`` for either sign. ``certified`` means the verdict
    and the value are proven: the depth lies within ``tolerance`` of the answer. Methods
    ``"dual"``, ``"exact"``, ``"fcl"`` and ``"libccd"`` measure penetration; takes the keywords
    of ``distance``.

    Between compound bodies it is the smallest signed distance over pairs of parts: minus the
    deepest part-pair penetration when parts overlap. That is not, in general, the penetration
    depth of the non-convex unions (the shortest translation that separates the unions can be
    longer than any part pair's); ``part_a`` and ``part_b`` name the deepest pair.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> moved = [[x + 0.75, y, z] for x, y, z in cube]
    >>> r = sc.signed_distance(cube, moved)
    >>> round(r.distance, 9), r.direction.round(9).tolist(), r.certified
    (-0.25, [1.0, 0.0, 0.0], True)
    """
    _refuse_pose_keywords("signed_distance", parameters, batch=False)
    return _query_for(method, tolerance, seed, parameters).signed_distance(
        a, b, pose_a, pose_b
    )


@_answered_in_cpp()
def collide(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    pose_a: PoseLike = None,
    pose_b: PoseLike = None,
    escalate: bool = True,
    **parameters: Unpack[Parameters],
) -> bool:
    """True when the bodies are within ``tolerance`` of each other (they touch or overlap).

    A verdict that ``method``'s bounds do not prove is handed to the exact method at the same
    tolerance, unless ``escalate=False``; ``collision`` tells which method decided. Bodies whose
    bounding balls (about their boxes' centres) are proven farther apart than the tolerance are
    answered apart from the balls alone, before any solver runs, whatever the method. Takes the
    keywords of ``distance``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> sc.collide(cube, [[x + 0.5, y, z] for x, y, z in cube])
    True
    """
    _refuse_pose_keywords("collide", parameters, batch=False)
    return _query_for(method, tolerance, seed, parameters).collide(
        a, b, pose_a, pose_b, escalate
    )


@_answered_in_cpp()
def collision(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    pose_a: PoseLike = None,
    pose_b: PoseLike = None,
    escalate: bool = True,
    **parameters: Unpack[Parameters],
) -> _core.DistanceResult:
    """The result that decides ``collide``: ``method``'s own if certified, else an exact one.

    ``result.method`` names the method that decided and ``result.escalated_from`` the one whose
    unproven verdict it replaced (None if none). Takes the keywords of ``collide``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> a = [[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]]
    >>> b = [[1, -1e-10, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]]  # within the tolerance of a
    >>> r = sc.collision(a, b, method="ipso", max_iterations=0)
    >>> r.method, r.escalated_from, r.colliding, r.certified
    ('exact', 'ipso', True, True)
    """
    _refuse_pose_keywords("collision", parameters, batch=False)
    return _query_for(method, tolerance, seed, parameters).collision(
        a, b, pose_a, pose_b, escalate
    )


def distance_many(
    As: BodiesLike,
    Bs: BodiesLike,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    threads: Optional[int] = None,
    first_index: int = 0,
    poses_a: PosesLike = None,
    poses_b: PosesLike = None,
    **parameters: Unpack[Parameters],
) -> _core.BatchResult:
    """``distance(As[i], Bs[i])`` for every row i, in C++ threads without the GIL.

    Row i is seeded with ``pair_seed(seed, first_index + i)``, so the results depend neither on
    the number of threads nor on how a batch is split (``first_index`` is the global index of the
    first row). The options and poses are checked once, and bodies are read where they are, never
    copied: "A against B at these m poses" is ``distance_many(A, B, poses_b=poses)``.

    Parameters
    ----------
    As, Bs : body, sequence of bodies, or array_like of shape (m, n, 3)
        The bodies, row by row. A single body (a ConvexPolyhedron, a CompoundBody, an ``(n, 3)``
        NumPy array or a mesh) is used in every row; with single bodies on both sides the poses
        set the number of rows (one without poses). ``(m, n, 3)`` arrays are built into bodies
        row by row on the threads.
    threads : int, optional
        Worker threads (at most 1024); None uses one per hardware thread. They are kept
        between calls, so a short batch does not pay for starting them, and the calling thread
        wakes them only once the rows left would take it over about 200 us alone (waking an
        idle core costs tens of microseconds): a short batch runs on the calling thread.
    first_index : int
        The global index of the first pair, for seeds and error messages.
    poses_a, poses_b : array_like, optional
        Where the bodies are: an ``(m, 4, 4)`` or ``(m, 3, 4)`` array of rigid transforms or a
        pair ``(rotations, translations (m, 3))`` whose rotations are an ``(m, 3, 3)`` array or a
        SciPy ``Rotation`` of m rotations, or a list of m poses (each as ``distance`` takes it);
        a single pose serves every row, as a single body does. Results are in world coordinates.
    method, tolerance, seed, **parameters
        As for ``distance``.

    Returns
    -------
    BatchResult
        NumPy arrays, one entry (row) per pair.

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> As = np.stack([tetra] * 3)
    >>> Bs = np.stack([tetra + [k + 1.5, 0, 0] for k in range(3)])
    >>> r = sc.distance_many(As, Bs)
    >>> r.distance.round(9).tolist(), r.colliding.tolist(), r.certified.tolist()
    ([0.5, 1.5, 2.5], [False, False, False], [True, True, True])
    >>> moves = np.tile(np.eye(4), (3, 1, 1))
    >>> moves[:, 0, 3] = [1.5, 2.5, 3.5]
    >>> sc.distance_many(tetra, tetra, poses_b=moves).distance.round(9).tolist()
    [0.5, 1.5, 2.5]
    """
    _refuse_pose_keywords("distance_many", parameters, batch=True)
    return _query_for(method, tolerance, seed, parameters).distance_many(
        As, Bs, threads, first_index, poses_a, poses_b
    )


def collide_many(
    As: BodiesLike,
    Bs: BodiesLike,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    threads: Optional[int] = None,
    first_index: int = 0,
    escalate: bool = True,
    poses_a: PosesLike = None,
    poses_b: PosesLike = None,
    **parameters: Unpack[Parameters],
) -> _core.BatchResult:
    """``collision(As[i], Bs[i])`` for every i: the batch form of ``collide``.

    ``result.colliding`` holds the verdicts and ``result.escalated`` marks the pairs another
    method decided. Balls about the centres of the bodies' boxes settle rows before any solver
    runs. Bounding balls proven apart settle a row as apart: its ``lower_bound`` is the balls'
    separation and its ``distance`` that of the bodies' first points (its witnesses). Balls
    proven inside both bodies (a closed hull surface around the centre) that overlap settle it as
    colliding: distance and ``lower_bound`` 0, a point common to both balls as the witness. Bodies
    of at most 32 points proven apart along the axis through those centres (outward-rounded) are
    settled as apart too: ``lower_bound`` is their separation along it, the witnesses their
    supporting points. All are valid bounds, looser than a solver's, so a row's bounds depend on
    the screen that settled it. Bodies given as an ``(m, n, 3)`` stack are built row by row, with
    no hull for the screens that need one (the inner balls, and the axes normal to a hull's
    faces): their rows can carry a solver's bounds where a sequence of the same bodies carries a
    screen's. The verdicts are the same. Takes the keywords of ``distance_many`` and
    ``escalate``.

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> sc.collide_many([cube, cube], [cube + 0.5, cube + 2]).colliding.tolist()
    [True, False]
    """
    _refuse_pose_keywords("collide_many", parameters, batch=True)
    return _query_for(method, tolerance, seed, parameters).collide_many(
        As, Bs, threads, first_index, escalate, poses_a, poses_b
    )


def signed_distance_many(
    As: BodiesLike,
    Bs: BodiesLike,
    *,
    method: str = "dual",
    tolerance: float = DEFAULT_TOLERANCE,
    seed: int = 0,
    threads: Optional[int] = None,
    first_index: int = 0,
    poses_a: PosesLike = None,
    poses_b: PosesLike = None,
    **parameters: Unpack[Parameters],
) -> _core.BatchResult:
    """``signed_distance(As[i], Bs[i])`` for every i; takes the keywords of ``distance_many``.

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> sc.signed_distance_many([cube], [cube + [0.75, 0, 0]]).distance.round(9).tolist()
    [-0.25]
    """
    _refuse_pose_keywords("signed_distance_many", parameters, batch=True)
    return _query_for(method, tolerance, seed, parameters).signed_distance_many(
        As, Bs, threads, first_index, poses_a, poses_b
    )
