"""How a fuzz case becomes a swarmcollide call: the one place to update when the API changes.

The corpus (``fuzz_cases``) is frozen, so that a case id means the same case before and after a
change; ``call`` maps its cases onto today's API (``RENAMED``), and a call the API refuses as
unknown is counted as "api" by the judge, which reads results only through ``summary``. The tables
here are today's methods and options, over which the tests are parametrised.
"""

from __future__ import annotations

from typing import Any, Dict, Mapping, Optional

import numpy as np

import swarmcollide as sc

DEFAULT: Optional[str] = None
"""The method of a call that passes no ``method`` keyword: the query's own default."""

def _methods_with(query: str) -> tuple:
    return (DEFAULT, *(name for name, info in sc.METHODS.items() if query in info.queries))


METHODS: Dict[str, tuple] = {
    "distance": _methods_with("distance"),
    "signed_distance": _methods_with("signed_distance"),
    "collide": _methods_with("collide"),
    "distance_many": (DEFAULT, "ipso", "fcl", "dual"),
    "collide_many": (DEFAULT, "ipso", "fcl", "libccd", "dual"),
}
"""The methods each query has today (from ``sc.METHODS``): the tests are parametrised over these."""

RENAMED: Dict[str, str] = {"fcl-indep": "fcl"}
"""Corpus method names (``fuzz_cases.CORPUS_METHODS``) that the API now spells differently: FCL's
own GJK, once "fcl-indep", is what "fcl" runs now."""

BATCH_QUERIES = ("distance_many", "collide_many")
"""The queries that take sequences of bodies and a ``threads`` keyword."""

PRECISE_METHODS = frozenset(name for name, info in sc.METHODS.items() if info.always_certified)
"""Methods whose certified answers must also be accurate, not only bracketed (by result.method)."""

_ALL = frozenset(m for methods in METHODS.values() for m in methods if m is not DEFAULT)
OPTIONS_OF: Dict[str, frozenset] = {
    "tolerance": _ALL | {DEFAULT},
    "seed": _ALL | {DEFAULT},
    "max_iterations": _ALL - {"penalty"},
    "swarm_size": frozenset({"ipso", "pso", "dual"}),
    "penetration": frozenset(),
}
"""The methods that take each option today (libccd's ``penetration="mpr"`` is gone)."""

API_MISMATCH = (
    "unexpected keyword argument",
    "unknown method",
    "does not apply",
    "needs one of",
    "penetration must be one of",
    "no query named",
)
"""Fragments of the messages with which a changed API refuses a call the corpus thinks valid."""


def call(query: str, method: Optional[str], a: Any, b: Any, options: Mapping[str, Any]) -> Any:
    """``sc.<query>(a, b, method=method, **options)``, leaving out ``method`` when it is DEFAULT."""
    # Options no method takes any more (libccd's penetration="mpr") are dropped: the case then asks
    # today's API the same question.
    keywords = {k: v for k, v in options.items() if k not in OPTIONS_OF or OPTIONS_OF[k]}
    if method is not DEFAULT:
        keywords["method"] = RENAMED.get(method, method)
    if not hasattr(sc, query):
        raise TypeError(f"swarmcollide has no query named {query!r}")
    return getattr(sc, query)(a, b, **keywords)


def summary(result: Any) -> Any:
    """A result as plain data (dicts of floats, bools, strings and arrays) that pickles anywhere.

    ``collide`` gives a bool; the other queries give a dict with the fields the judge reads, each
    ``None`` when the result has no such field.
    """
    if isinstance(result, (bool, np.bool_)):
        return bool(result)
    fields = (
        "distance", "lower_bound", "point_a", "point_b", "direction", "colliding", "certified",
        "status", "method", "escalated_from",
    )  # fmt: skip
    data = {}
    for name in fields:
        value = getattr(result, name, None)
        data[name] = np.array(value) if isinstance(value, np.ndarray) else value
    return data


def invoke(query: str, args: tuple, keywords: Mapping[str, Any]) -> Any:
    """``summary(sc.<query>(*args, **keywords))``: a call that a sandboxed child can run."""
    return summary(getattr(sc, query)(*args, **keywords))
