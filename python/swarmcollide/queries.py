"""Distance, signed distance and collision queries between convex polyhedra."""

from __future__ import annotations

import numbers
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy.typing as npt

from . import _core

PolyhedronLike = Union[_core.ConvexPolyhedron, npt.ArrayLike]
"""A ``ConvexPolyhedron`` or anything ``ConvexPolyhedron(points)`` accepts: ``(n, 3)`` points."""

METHODS = ("ipso", "pso", "penalty", "fcl", "fcl-indep", "libccd", "dual")
"""The names ``method`` accepts."""

SIGNED_METHODS = ("fcl", "fcl-indep", "libccd", "dual")
"""The methods that measure penetration depth, for ``signed_distance``."""

_CHOICES: Dict[str, Mapping[str, object]] = {
    "constraint_handling": {
        "feasibility": _core.ConstraintHandling.feasibility,
        "projection": _core.ConstraintHandling.projection,
    },
    "penetration": {"epa": _core.PenetrationAlgorithm.epa, "mpr": _core.PenetrationAlgorithm.mpr},
}

# Each method's keyword arguments: the options group they set and whether they are integers
# (True), real numbers (False) or one of _CHOICES (None).
_Parameters = Dict[str, Tuple[str, Optional[bool]]]
_SWARM: _Parameters = {
    "swarm_size": ("swarm", True),
    "max_iterations": ("swarm", True),
    "w_min": ("swarm", False),
    "w_max": ("swarm", False),
    "velocity_limit": ("swarm", False),
    "tolerance": ("swarm", False),
    "feasibility_tolerance": ("swarm", False),
    "constraint_handling": ("swarm", None),
}
_EXACT: _Parameters = {
    "distance_tolerance": ("exact", False),
    "penetration_tolerance": ("exact", False),
    "max_iterations": ("exact", True),
    "tolerance": ("exact", False),
}
_PARAMETERS_OF: Dict[str, _Parameters] = {
    "ipso": _SWARM,
    "pso": {**_SWARM, "c1": ("swarm", False), "c2": ("swarm", False)},
    "penalty": {
        "initial_weight": ("penalty", False),
        "growth_factor": ("penalty", False),
        "outer_iterations": ("penalty", True),
        "inner_iterations": ("penalty", True),
        "tolerance": ("penalty", False),
    },
    "fcl": _EXACT,
    "fcl-indep": _EXACT,
    "libccd": {**_EXACT, "penetration": ("exact", None)},
    "dual": {
        "swarm_size": ("dual", True),
        "max_iterations": ("dual", True),
        "w_min": ("dual", False),
        "w_max": ("dual", False),
        "tolerance": ("dual", False),
        "relative_tolerance": ("dual", False),
        "feature_tolerance": ("dual", False),
        "max_rounds": ("dual", True),
    },
}


def _check_type(name: str, value: object, integer: bool) -> None:
    kind = numbers.Integral if integer else numbers.Real
    if isinstance(value, bool) or not isinstance(value, kind):
        expected = "an integer" if integer else "a real number"
        raise TypeError(f"{name} must be {expected}, got {type(value).__name__}")


def _options(method: str, seed: int, parameters: Mapping[str, object]) -> _core.DistanceOptions:
    """Options for ``method`` from keyword arguments; ``None`` leaves the method's default."""
    if not isinstance(method, str):
        raise TypeError(f"method must be a string, got {type(method).__name__}")
    if method not in _PARAMETERS_OF:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    _check_type("seed", seed, integer=True)
    if not 0 <= seed < 2**64:
        raise ValueError(f"seed must lie in [0, 2**64), got {seed}")
    options = _core.DistanceOptions()
    options.method = method
    options.swarm.seed = int(seed)
    options.dual.seed = int(seed)
    accepted = _PARAMETERS_OF[method]
    for name, value in parameters.items():
        if value is None:
            continue
        if name not in accepted:
            raise ValueError(
                f"{name} does not apply to method={method!r} "
                f"(its parameters: {', '.join(sorted(accepted))})"
            )
        group, integer = accepted[name]
        if integer is None:
            if value not in _CHOICES[name]:
                raise ValueError(
                    f"{name} must be one of {', '.join(map(repr, _CHOICES[name]))}, got {value!r}"
                )
            value = _CHOICES[name][value]  # type: ignore[index]
        else:
            _check_type(name, value, integer)
            value = int(value) if integer else float(value)  # type: ignore[call-overload]
        setattr(getattr(options, group), name, value)
    for group in {group for group, _ in accepted.values()}:
        getattr(options, group).validate()
    return options


def distance(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    method: str = "ipso",
    seed: int = 0,
    swarm_size: Optional[int] = None,
    max_iterations: Optional[int] = None,
    w_min: Optional[float] = None,
    w_max: Optional[float] = None,
    c1: Optional[float] = None,
    c2: Optional[float] = None,
    velocity_limit: Optional[float] = None,
    tolerance: Optional[float] = None,
    feasibility_tolerance: Optional[float] = None,
    constraint_handling: Optional[str] = None,
    initial_weight: Optional[float] = None,
    growth_factor: Optional[float] = None,
    outer_iterations: Optional[int] = None,
    inner_iterations: Optional[int] = None,
    distance_tolerance: Optional[float] = None,
    penetration_tolerance: Optional[float] = None,
    penetration: Optional[str] = None,
    relative_tolerance: Optional[float] = None,
    feature_tolerance: Optional[float] = None,
    max_rounds: Optional[int] = None,
) -> _core.DistanceResult:
    """Distance between two convex polyhedra: model (2) of the paper.

    Every parameter left at ``None`` takes the method's default, shown below; a parameter that
    does not apply to the chosen method is a ValueError.

    Parameters
    ----------
    a, b : ConvexPolyhedron or array_like, shape (n, 3)
        The bodies, or the points whose convex hulls they are.
    method : {"ipso", "pso", "penalty", "fcl", "fcl-indep", "dual"}
        ``"ipso"``: the paper's improved PSO, with rank-adaptive inertia and acceleration (8)-(9).
        ``"pso"``: the standard PSO with linearly decreasing inertia (7).
        ``"penalty"``: the paper's baseline, an exterior quadratic penalty minimised by L-BFGS.
        ``"fcl"``, ``"fcl-indep"``: exact GJK through FCL (libccd's or FCL's own), checked by
        the certificate and completed by an exact solver where FCL gives no answer.
        ``"dual"``: the paper's rank-adaptive swarm over separating directions (two parameters
        whatever the vertex count) with an exact finish on the supporting features; certified
        to ``tolerance`` (see docs/dual.md).
        (``"libccd"`` has no distance; use it with ``collide`` or ``signed_distance``.)
    seed : int
        Seed of the solver's random generator; the same seed gives the same result.

    Other Parameters
    ----------------
    swarm_size : int, default 40 (ipso, pso), 12 (dual)
        ipso, pso, dual: N_p, the number of particles.
    max_iterations : int, default 200 (swarms), 30 (dual, per round), 1000 (exact)
        ipso, pso: G_m, the iteration budget. dual: the budget of one round. Exact methods: their
        iteration cap.
    w_min, w_max : float, default 0.4 and 0.9
        ipso, pso, dual: smallest and largest inertia weight.
    c1, c2 : float, default 2.0
        pso only: acceleration coefficients (``"ipso"`` derives them from (9)).
    velocity_limit : float, default 1.0
        ipso, pso: largest velocity component (the weights live in [0, 1]).
    tolerance : float, default 1e-6 (swarms, penalty), 1e-9 (exact), 0 (dual)
        Absolute distance at or below which the bodies count as colliding. For the swarms it is
        also the precision of the paper's Step 3: they stop once ``distance - lower_bound`` or
        ``distance`` is at most ``tolerance``; 0 runs all ``max_iterations``. dual: the same
        precision test, and 0 means ``relative_tolerance`` times the bodies' size.
    feasibility_tolerance : float, default 1e-10
        ipso, pso: largest constraint violation (6) that counts as feasible.
    constraint_handling : {"projection", "feasibility"}, default "projection"
        ipso, pso: ``"feasibility"`` is the paper's rules (Conditions 1-3); ``"projection"``
        projects every particle's weights onto the simplexes after each move.
    initial_weight, growth_factor : float, default 1 and 10
        penalty: the first penalty weight and its growth between subproblems.
    outer_iterations, inner_iterations : int, default 8 and 200
        penalty: the number of subproblems and the L-BFGS iterations of each.
    distance_tolerance : float, default 1e-10
        fcl, fcl-indep: FCL's GJK stopping threshold (FCL's own default, 1e-6, gives errors up to
        1e-5 on about 1 pair in 500).
    penetration_tolerance : float, default 1e-12
        Exact methods: libccd's EPA/MPR tolerance, for ``signed_distance``.
    penetration : {"epa", "mpr"}, default "epa"
        libccd only: its penetration routine.
    relative_tolerance : float, default 1e-9
        dual: the precision relative to the bodies' size (the larger bounding-box diagonal),
        used when ``tolerance`` is 0.
    feature_tolerance : float, default 1e-3
        dual: slack, relative to the bodies' size, of the supporting features of the finish.
    max_rounds : int, default 20
        dual: the largest number of swarm rounds (re-seeded around the best direction).

    Returns
    -------
    DistanceResult
        ``lower_bound <= true distance <= distance`` holds for every result.

    Raises
    ------
    TypeError
        For an argument of the wrong type.
    ValueError
        For bad points (NaN, infinite, empty, wrong shape), an invalid or inapplicable parameter,
        or ``method="libccd"``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> a = [[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]]
    >>> b = [[1, 0, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]]
    >>> r = sc.distance(a, b, method="ipso", seed=0)
    >>> r.colliding, r.certified, r.weights_a.round(6).tolist()
    (True, True, [0.0, 1.0, 0.0, 0.0])
    >>> sc.distance(a, [[3, 0, 0]], method="fcl").distance
    2.0
    """
    parameters = dict(locals())
    for name in ("a", "b", "method", "seed"):
        del parameters[name]
    return _core.distance(a, b, _options(method, seed, parameters))


def signed_distance(
    a: PolyhedronLike, b: PolyhedronLike, *, method: str = "fcl", seed: int = 0, **parameters: Any
) -> _core.DistanceResult:
    """Distance when apart, minus the penetration depth when overlapping.

    ``direction`` is the unit contact normal from A to B and
    ``point_b - point_a = distance * direction`` for either sign. ``lower_bound`` (the separation
    along the normal) is not clamped at zero here.

    Parameters
    ----------
    a, b : ConvexPolyhedron or array_like, shape (n, 3)
        The bodies.
    method : {"fcl", "fcl-indep", "libccd", "dual"}
        The exact methods and the dual swarm: ``"ipso"``, ``"pso"`` and the penalty method
        measure no penetration.
    **parameters
        The keyword arguments of ``distance`` that apply to ``method``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> moved = [[x + 0.75, y, z] for x, y, z in cube]
    >>> r = sc.signed_distance(cube, moved)
    >>> round(r.distance, 9), r.direction.round(9).tolist()
    (-0.25, [1.0, 0.0, 0.0])
    """
    if method not in SIGNED_METHODS and method in METHODS:
        raise ValueError(
            f"signed_distance needs one of {', '.join(SIGNED_METHODS)}: "
            f"method {method!r} does not measure penetration depth"
        )
    return _core.signed_distance(a, b, _options(method, seed, parameters))


def collide(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    method: str = "ipso",
    seed: int = 0,
    escalate: bool = True,
    **parameters: Any,
) -> bool:
    """True when the bodies intersect.

    The verdict never contradicts its own bounds: when ``method``'s answer does not prove it
    (``certified`` is false), the exact ``"fcl"`` method decides at the same tolerance, unless
    ``escalate=False``. ``collision`` tells which method decided.

    Parameters
    ----------
    a, b : ConvexPolyhedron or array_like, shape (n, 3)
        The bodies.
    method : {"ipso", "pso", "penalty", "fcl", "fcl-indep", "libccd", "dual"}
        ``"libccd"`` answers with libccd's GJK intersection test.
    seed : int
        Seed of the solver's random generator.
    escalate : bool
        Hand unproven verdicts to an exact method.
    **parameters
        The keyword arguments of ``distance`` that apply to ``method``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> shifted = [[x + 0.5, y, z] for x, y, z in cube]
    >>> sc.collide(cube, shifted)
    True
    """
    return _core.collide(a, b, _options(method, seed, parameters), bool(escalate))


def collision(
    a: PolyhedronLike,
    b: PolyhedronLike,
    *,
    method: str = "ipso",
    seed: int = 0,
    escalate: bool = True,
    **parameters: Any,
) -> _core.DistanceResult:
    """The result that decides ``collide``: ``method``'s own if certified, else an exact one.

    ``result.method`` names the method that decided and ``result.escalated_from`` the one whose
    unproven verdict it replaced (empty if none). For ``"libccd"``, which has no distance, the
    result is its signed distance. Takes the arguments of ``collide``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> a = [[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]]
    >>> b = [[1, -1e-7, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]]
    >>> r = sc.collision(a, b, max_iterations=0)
    >>> r.method, r.escalated_from, r.colliding, round(r.distance, 12)
    ('fcl', 'ipso', True, 1e-07)
    """
    return _core.collision(a, b, _options(method, seed, parameters), bool(escalate))


BodiesLike = Union[Sequence[PolyhedronLike], npt.ArrayLike]
"""A sequence of polyhedra (or of ``(n, 3)`` point arrays), or an ``(m, n, 3)`` array."""


def _check_threads(threads: Optional[int]) -> Optional[int]:
    if threads is None:
        return None
    _check_type("threads", threads, integer=True)
    if threads < 1:
        raise ValueError(f"threads must be at least 1 (None: all hardware threads), got {threads}")
    return int(threads)


def distance_many(
    As: BodiesLike,
    Bs: BodiesLike,
    *,
    method: str = "ipso",
    seed: int = 0,
    threads: Optional[int] = None,
    **parameters: Any,
) -> _core.BatchResult:
    """``distance(As[i], Bs[i])`` for every i, in C++ threads without the GIL.

    Pair i is solved with the seed ``pair_seed(seed, i)``, so the results do not depend on the
    number of threads.

    Parameters
    ----------
    As, Bs : sequence of ConvexPolyhedron or array_like, or array_like of shape (m, n, 3)
        The bodies, pairwise. Two (m, n, 3) arrays are the fastest input: each pair's bodies
        are then built and freed by the thread that answers it.
    method, seed
        As for ``distance``.
    threads : int, optional
        Worker threads; None uses one per hardware thread.
    **parameters
        The keyword arguments of ``distance`` that apply to ``method``.

    Returns
    -------
    BatchResult
        NumPy arrays: ``distance``, ``lower_bound`` (m,), ``point_a``, ``point_b`` (m, 3),
        ``colliding``, ``certified`` (m,).

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> As = np.stack([tetra] * 3)
    >>> Bs = np.stack([tetra + [k + 1.5, 0, 0] for k in range(3)])
    >>> r = sc.distance_many(As, Bs, method="fcl")
    >>> r.distance.round(9).tolist(), r.colliding.tolist()
    ([0.5, 1.5, 2.5], [False, False, False])
    """
    options = _options(method, seed, parameters)
    return _core.distance_many(As, Bs, options, _check_threads(threads))


def collide_many(
    As: BodiesLike,
    Bs: BodiesLike,
    *,
    method: str = "ipso",
    seed: int = 0,
    escalate: bool = True,
    threads: Optional[int] = None,
    **parameters: Any,
) -> _core.BatchResult:
    """``collision(As[i], Bs[i])`` for every i: the batch form of ``collide``.

    ``result.colliding`` holds the verdicts and ``result.escalated`` marks the pairs that an exact
    method decided. Takes the arguments of ``distance_many`` and ``escalate``.

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> r = sc.collide_many([cube, cube], [cube + 0.5, cube + 2])
    >>> r.colliding.tolist()
    [True, False]
    """
    options = _options(method, seed, parameters)
    return _core.collide_many(As, Bs, options, bool(escalate), _check_threads(threads))
