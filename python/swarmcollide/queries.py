"""Distance and collision queries between convex polyhedra."""

from __future__ import annotations

import numbers
from typing import Dict, FrozenSet, Optional, Union

import numpy.typing as npt

from . import _core

PolyhedronLike = Union[_core.ConvexPolyhedron, npt.ArrayLike]
"""A ``ConvexPolyhedron`` or anything ``ConvexPolyhedron(points)`` accepts: ``(n, 3)`` points."""

METHODS = ("ipso", "pso")
"""The names ``method`` accepts."""

_SWARM_PARAMETERS = frozenset(
    {
        "swarm_size",
        "max_iterations",
        "w_min",
        "w_max",
        "c1",
        "c2",
        "velocity_limit",
        "tolerance",
        "feasibility_tolerance",
        "constraint_handling",
    }
)
_PARAMETERS_OF: Dict[str, FrozenSet[str]] = {
    "ipso": _SWARM_PARAMETERS - {"c1", "c2"},
    "pso": _SWARM_PARAMETERS,
}
_INTEGER_PARAMETERS = frozenset({"swarm_size", "max_iterations"})
_CONSTRAINT_HANDLING = {
    "feasibility": _core.ConstraintHandling.feasibility,
    "projection": _core.ConstraintHandling.projection,
}


def _check_number(name: str, value: object, integer: bool) -> None:
    kind = numbers.Integral if integer else numbers.Real
    if isinstance(value, bool) or not isinstance(value, kind):
        expected = "an integer" if integer else "a real number"
        raise TypeError(f"{name} must be {expected}, got {type(value).__name__}")


def _options(method: str, seed: int, parameters: Dict[str, object]) -> _core.DistanceOptions:
    if not isinstance(method, str):
        raise TypeError(f"method must be a string, got {type(method).__name__}")
    if method not in _PARAMETERS_OF:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    _check_number("seed", seed, integer=True)
    if not 0 <= seed < 2**64:
        raise ValueError(f"seed must lie in [0, 2**64), got {seed}")
    options = _core.DistanceOptions()
    options.method = method
    swarm = options.swarm
    swarm.seed = int(seed)
    for name, value in parameters.items():
        if value is None:
            continue
        if name not in _PARAMETERS_OF[method]:
            accepted = ", ".join(sorted(_PARAMETERS_OF[method])) or "none"
            raise ValueError(
                f"{name} does not apply to method={method!r} (its parameters: {accepted})"
            )
        if name == "constraint_handling":
            if value not in _CONSTRAINT_HANDLING:
                raise ValueError(
                    f"constraint_handling must be 'feasibility' or 'projection', got {value!r}"
                )
            swarm.constraint_handling = _CONSTRAINT_HANDLING[value]
        else:
            _check_number(name, value, integer=name in _INTEGER_PARAMETERS)
            setattr(swarm, name, int(value) if name in _INTEGER_PARAMETERS else float(value))
    swarm.validate()
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
) -> _core.DistanceResult:
    """Distance between two convex polyhedra: model (2) of the paper.

    Parameters
    ----------
    a, b : ConvexPolyhedron or array_like, shape (n, 3)
        The bodies, or the points whose convex hulls they are.
    method : {"ipso", "pso"}
        ``"ipso"``: the paper's improved PSO, with rank-adaptive inertia and acceleration (8)-(9).
        ``"pso"``: the standard PSO with linearly decreasing inertia (7).
    seed : int
        Seed of the solver's random generator; the same seed gives the same result.
    swarm_size : int, default 40
        N_p, the number of particles.
    max_iterations : int, default 200
        G_m, the iteration budget.
    w_min, w_max : float, default 0.4 and 0.9
        Smallest and largest inertia weight.
    c1, c2 : float, default 2.0
        Acceleration coefficients, ``"pso"`` only: ``"ipso"`` derives them from (9).
    velocity_limit : float, default 1.0
        Largest velocity component (the weights live in [0, 1]).
    tolerance : float, default 1e-6
        Precision of the paper's Step 3, an absolute distance: the solver stops once
        ``distance - lower_bound <= tolerance`` or ``distance <= tolerance``, and the bodies count
        as colliding when ``distance <= tolerance``. 0 runs all ``max_iterations``.
    feasibility_tolerance : float, default 1e-10
        Largest constraint violation (6) that counts as feasible.
    constraint_handling : {"projection", "feasibility"}, default "projection"
        ``"feasibility"``: the paper's rules (Conditions 1-3). ``"projection"``: every particle's
        weights are projected onto the simplexes after each move.

    Returns
    -------
    DistanceResult
        ``lower_bound <= true distance <= distance`` holds for every result.

    Raises
    ------
    TypeError
        For an argument of the wrong type.
    ValueError
        For bad points (NaN, infinite, empty, wrong shape) or an invalid parameter.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> a = [[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]]
    >>> b = [[1, 0, 0], [2, -2, 0], [0, -2, 2], [0, -2, 0]]
    >>> r = sc.distance(a, b, method="ipso", seed=0)
    >>> r.colliding, r.certified, r.weights_a.round(6).tolist()
    (True, True, [0.0, 1.0, 0.0, 0.0])
    """
    options = _options(
        method,
        seed,
        {
            "swarm_size": swarm_size,
            "max_iterations": max_iterations,
            "w_min": w_min,
            "w_max": w_max,
            "c1": c1,
            "c2": c2,
            "velocity_limit": velocity_limit,
            "tolerance": tolerance,
            "feasibility_tolerance": feasibility_tolerance,
            "constraint_handling": constraint_handling,
        },
    )
    return _core.distance(a, b, options)


def collide(a: PolyhedronLike, b: PolyhedronLike, **parameters: object) -> bool:
    """True when the bodies intersect: ``distance(a, b, **parameters).colliding``.

    Takes the same keyword arguments as ``distance``.

    Examples
    --------
    >>> import swarmcollide as sc
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> shifted = [[x + 0.5, y, z] for x, y, z in cube]
    >>> sc.collide(cube, shifted)
    True
    """
    return distance(a, b, **parameters).colliding  # type: ignore[arg-type]
