"""A seeded, bounded corpus of query cases: ``make_case(seed, index)`` is a pure function.

Each case is one call (or, for the "invariance" family, one call and the same call on the pair
scaled and translated) with what is due: an answer, an error (ValueError or TypeError), or either
(for options whose acceptance is the library's choice, such as more threads than pairs). A case is
rebuilt from its id anywhere, so the census runs it in a child process and reports ids that a
fix can be checked against case by case.

Families (``FAMILIES``, with their shares of a corpus):

geometry
    Two bodies of unit size (random hulls of 1-64 points, boxes axis-aligned, rotated or nearly
    aligned, tetrahedra, spheres sampled by 12-1024 points, flat, collinear, single and repeated
    points, needles, slivers, the unit cube) placed deep in each other, shallowly overlapping,
    touching, 1e-16 to 1e-12 apart or inside, apart or far apart, then scaled by s (log-uniform
    in [1e-100, 1e100], or 1, or one of ``SPECIAL_SCALES``) and translated by up to 1e6 x size.
invariance
    A geometry pair answered at unit scale and after scaling by s in [1e-100, 1e100] and
    translating by up to 1e6 x size: verdicts, certified flags and precise distances must agree.
options
    Geometry with ``tolerance=0``, 1-2 iterations, libccd's MPR, extreme swarm sizes, seeds and
    NaN, infinite or negative values.
batch
    ``distance_many``/``collide_many`` on (m, n, 3) stacks or lists, with extreme thread counts.
dtype, shape, values
    Real dtypes other than float64 (due: an answer), non-real dtypes (bool, complex, str, object,
    datetime; due: an error), wrong shapes, NaN and infinite coordinates, differences that overflow.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Tuple

import numpy as np

from fuzz_api import BATCH_QUERIES, DEFAULT

ANSWER, ERROR, EITHER = "answer", "error", "answer or error"

SPECIAL_SCALES = (1e-5, 1e-4, 1e8, 1e12, 1e77, 1e300)
"""The scales at which issue 12 saw FCL, libccd, the default collide and the hulls fail."""

LARGEST_COORDINATE = 1e306
"""Offsets are shrunk to keep coordinates below this, so that differences stay finite."""

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)

# The methods and options the corpus draws from, as the API had them for the BEFORE census. They
# are frozen: a case's id must name the same case after the API changes (fuzz_api maps them on).
# Changing them changes the cases that follow the first draw they alter: record a new census.
CORPUS_METHODS: Dict[str, Tuple[Optional[str], ...]] = {
    "distance": (DEFAULT, "ipso", "pso", "penalty", "fcl", "fcl-indep", "dual"),
    "signed_distance": (DEFAULT, "fcl", "fcl-indep", "libccd", "dual"),
    "collide": (DEFAULT, "ipso", "pso", "penalty", "fcl", "fcl-indep", "libccd", "dual"),
    "distance_many": (DEFAULT, "ipso", "fcl", "dual"),
    "collide_many": (DEFAULT, "ipso", "fcl", "libccd", "dual"),
}
_NAMED = frozenset({"ipso", "pso", "penalty", "fcl", "fcl-indep", "libccd", "dual"})
CORPUS_OPTIONS_OF: Dict[str, frozenset] = {
    "tolerance": _NAMED,
    "seed": _NAMED | {DEFAULT},
    "max_iterations": _NAMED - {"penalty"},
    "swarm_size": frozenset({"ipso", "pso", "dual"}),
    "penetration": frozenset({"libccd"}),
}


@dataclass(frozen=True)
class Case:
    """One fuzz case: ``sc.<query>(a, b, method=method, **options)`` and what it is due."""

    id: str
    family: str
    query: str
    method: Optional[str]
    a: Any
    b: Any
    options: Mapping[str, Any] = field(default_factory=dict)
    expect: str = ANSWER
    note: str = ""
    scale: float = 1.0
    """invariance only: the scale of the second call."""
    shift: Optional[np.ndarray] = None
    """invariance only: the translation of the second call (after scaling)."""

    @property
    def label(self) -> str:
        """The method as the census tables name it: ``default`` and ``libccd/mpr`` included."""
        name = "default" if self.method is DEFAULT else str(self.method)
        return name + ("/mpr" if self.options.get("penetration") == "mpr" else "")


# ----- bodies of unit size, centred near the origin ------------------------------------------


def _rotation(rng: np.random.Generator) -> np.ndarray:
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    return q * np.sign(np.diag(r))


def _fit(points: np.ndarray) -> np.ndarray:
    """``points`` centred and scaled to diameter about 1 (single points stay near the origin)."""
    centred = points - points.mean(axis=0)
    radius = np.max(np.linalg.norm(centred, axis=1))
    return centred / (2 * radius) if radius > 0 else centred


def _hull(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    n = int(rng.integers(1, 65))
    return _fit(rng.normal(size=(n, 3))), f"hull{n}"


def _box(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    corners = (CUBE - 0.5) * rng.uniform(0.2, 1.0, size=3)
    kind = rng.choice(["box", "rotated-box", "near-aligned-box"])
    if kind == "box":
        return corners, kind
    if kind == "rotated-box":
        return corners @ _rotation(rng).T, kind
    # Turned by 1e-9 to 1e-3 radians (to first order), so its faces are nearly parallel to the axes.
    axis = rng.normal(size=3)
    axis *= 10 ** rng.uniform(-9, -3) / np.linalg.norm(axis)
    cross = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return corners @ (np.eye(3) + cross).T, kind


def _tetrahedron(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    return _fit(rng.normal(size=(4, 3))), "tetra"


def _sphere(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    n = int(rng.choice([12, 32, 64, 128, 256, 1024]))
    points = rng.normal(size=(n, 3))
    return 0.5 * points / np.linalg.norm(points, axis=1, keepdims=True), f"sphere{n}"


def _flat(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    n = int(rng.integers(3, 21))
    points = np.column_stack([rng.normal(size=(n, 2)), np.zeros(n)])
    return _fit(points @ _rotation(rng).T), f"flat{n}"


def _collinear(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    n = int(rng.integers(2, 7))
    return _fit(np.outer(rng.normal(size=n), rng.normal(size=3))), f"collinear{n}"


def _point(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    return rng.normal(size=(1, 3)) * 0.1, "point"


def _repeated(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    if rng.random() < 0.3:
        point = rng.normal(size=(1, 3)) * 0.1
        return np.repeat(point, int(rng.integers(2, 9)), axis=0), "same-point"
    base, _ = _tetrahedron(rng) if rng.random() < 0.5 else _hull(rng)
    return np.repeat(base, int(rng.integers(2, 4)), axis=0), "repeated"


def _needle(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    n = int(rng.integers(3, 9))
    along = np.outer(rng.uniform(-0.5, 0.5, size=n), [1.0, 0, 0])
    needle = along + rng.normal(size=(n, 3)) * np.array([0, 1e-9, 1e-9])
    return needle @ _rotation(rng).T, "needle"


def _sliver(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    base, _ = _flat(rng)
    normal = np.cross(base[1] - base[0], base[2] - base[0])
    normal /= np.linalg.norm(normal) or 1.0
    return np.vstack([base, base.mean(axis=0) + 1e-9 * normal]), "sliver"


def _cube(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    return CUBE - 0.5, "cube"


_SHAPES: List[Tuple[float, Callable[[np.random.Generator], Tuple[np.ndarray, str]]]] = [
    (0.25, _hull), (0.15, _box), (0.1, _tetrahedron), (0.1, _sphere), (0.07, _flat),
    (0.05, _collinear), (0.05, _point), (0.05, _repeated), (0.05, _needle), (0.05, _sliver),
    (0.08, _cube),
]  # fmt: skip


def _pick(rng: np.random.Generator, weighted: List[Tuple[float, Any]]) -> Any:
    weights = np.array([w for w, _ in weighted])
    return weighted[int(rng.choice(len(weighted), p=weights / weights.sum()))][1]


def body(rng: np.random.Generator) -> Tuple[np.ndarray, str]:
    """A body of unit size near the origin and its kind."""
    return _pick(rng, _SHAPES)(rng)


# ----- placements, scales, offsets -----------------------------------------------------------


def _separation(a: np.ndarray, b: np.ndarray, u: np.ndarray) -> float:
    """How far B lies beyond A along the unit ``u`` (negative: they overlap along u)."""
    return float(np.min(b @ u) - np.max(a @ u))


def _axis_or_random(rng: np.random.Generator) -> np.ndarray:
    if rng.random() < 0.5:
        return np.eye(3)[int(rng.integers(3))] * rng.choice([-1.0, 1.0])
    u = rng.normal(size=3)
    return u / np.linalg.norm(u)


def place(rng: np.random.Generator, a: np.ndarray, b: np.ndarray) -> Tuple[np.ndarray, str]:
    """B moved relative to A into one of the configurations, and its name.

    The separation along one direction (an axis half the time, so that box faces are coplanar)
    is set: the true distance is at least that separation, and the depth at most its negative.
    """
    kind = _pick(
        rng,
        [(0.25, "deep"), (0.15, "shallow"), (0.1, "touching"), (0.1, "near"), (0.25, "apart"),
         (0.15, "far")],
    )  # fmt: skip
    if kind == "deep":
        return b + rng.uniform(-0.3, 0.3, size=3), kind
    u = _axis_or_random(rng)
    target = {
        "shallow": lambda: -(10 ** rng.uniform(-6, -1)),
        "touching": lambda: 0.0,
        "near": lambda: rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-16, -12),
        "apart": lambda: 10 ** rng.uniform(-3, 0.5),
        "far": lambda: 10 ** rng.uniform(1, 6),
    }[kind]()
    return b + (target - _separation(a, b, u)) * u, kind


def scale(rng: np.random.Generator, largest: float = 1e300) -> float:
    """1, log-uniform in [1e-100, 1e100], or one of SPECIAL_SCALES up to ``largest``."""
    draw = rng.random()
    if draw < 0.35:
        return 1.0
    if draw < 0.75:
        return float(10 ** rng.uniform(-100, 100))
    return float(rng.choice([s for s in SPECIAL_SCALES if s <= largest]))


def offset(rng: np.random.Generator, size: float) -> np.ndarray:
    """Nothing half the time, else a translation of size x 10^U(-2, 6), kept below 1e306."""
    if rng.random() < 0.5:
        return np.zeros(3)
    u = rng.normal(size=3)
    magnitude = min(size * 10 ** rng.uniform(-2, 6), LARGEST_COORDINATE / 4)
    return magnitude * u / np.linalg.norm(u)


def pair(rng: np.random.Generator) -> Tuple[np.ndarray, np.ndarray, str]:
    """Two unit-size bodies in a configuration, and a note naming them."""
    a, kind_a = body(rng)
    b, kind_b = body(rng)
    b, configuration = place(rng, a, b)
    return a, b, f"{kind_a} {kind_b} {configuration}"


def _scaled_pair(rng: np.random.Generator) -> Tuple[np.ndarray, np.ndarray, str]:
    a, b, note = pair(rng)
    s = scale(rng)
    size = s * max(1.0, float(np.ptp(np.vstack([a, b]), axis=0).max()))
    shift = offset(rng, size)
    return a * s + shift, b * s + shift, f"{note} s={s:.3g} offset={np.abs(shift).max():.3g}"


def _method(rng: np.random.Generator, query: str, option: Optional[str] = None) -> Optional[str]:
    takes = CORPUS_OPTIONS_OF[option] if option else None
    methods = [m for m in CORPUS_METHODS[query] if takes is None or m in takes]
    return methods[int(rng.integers(len(methods)))]


# ----- the families ----------------------------------------------------------------------------

_SINGLE_QUERIES = ("distance", "signed_distance", "collide")


def _geometry(rng: np.random.Generator, case_id: str) -> Case:
    query = _SINGLE_QUERIES[int(rng.integers(3))]
    a, b, note = _scaled_pair(rng)
    return Case(case_id, "geometry", query, _method(rng, query), a, b, note=note)


def _invariance(rng: np.random.Generator, case_id: str) -> Case:
    query = _SINGLE_QUERIES[int(rng.integers(3))]
    a, b, note = pair(rng)
    s = scale(rng, largest=1e100)
    s = s if s != 1.0 else float(10 ** rng.uniform(-100, 100))
    size = s * float(np.ptp(np.vstack([a, b]), axis=0).max())
    shift = offset(rng, size)
    note += f" s={s:.3g} offset={np.abs(shift).max():.3g}"
    method = _method(rng, query)
    return Case(case_id, "invariance", query, method, a, b, note=note, scale=s, shift=shift)


# (option, value, what is due, the queries it applies to)
_OPTION_VALUES: List[Tuple[str, Any, str, Tuple[str, ...]]] = [
    ("tolerance", 0.0, ANSWER, _SINGLE_QUERIES),
    ("max_iterations", 1, ANSWER, _SINGLE_QUERIES),
    ("max_iterations", 2, ANSWER, _SINGLE_QUERIES),
    ("penetration", "mpr", ANSWER, ("signed_distance",)),
    ("swarm_size", 2, ANSWER, ("distance", "collide")),
    ("swarm_size", 2**31 - 1, ERROR, ("distance", "collide")),
    ("swarm_size", 0, ERROR, ("distance", "collide")),
    ("seed", 2**64 - 1, ANSWER, _SINGLE_QUERIES),
    ("seed", -1, ERROR, _SINGLE_QUERIES),
    ("seed", 2**64, ERROR, _SINGLE_QUERIES),
    ("seed", 1.5, ERROR, _SINGLE_QUERIES),
    ("tolerance", float("nan"), ERROR, _SINGLE_QUERIES),
    ("tolerance", float("inf"), ERROR, _SINGLE_QUERIES),
    ("tolerance", -1e-3, ERROR, _SINGLE_QUERIES),
    ("max_iterations", -1, ERROR, _SINGLE_QUERIES),
    ("max_iterations", 2**31, EITHER, _SINGLE_QUERIES),
    ("max_iterations", float("nan"), ERROR, _SINGLE_QUERIES),
]


def _options(rng: np.random.Generator, case_id: str) -> Case:
    name, value, expect, queries = _OPTION_VALUES[int(rng.integers(len(_OPTION_VALUES)))]
    query = queries[int(rng.integers(len(queries)))]
    a, b, note = _scaled_pair(rng) if rng.random() < 0.5 else pair(rng)
    method = _method(rng, query, name)
    note += f" {name}={value}"
    return Case(case_id, "options", query, method, a, b, {name: value}, expect, note)


_THREADS: List[Tuple[Any, str]] = [
    (None, ANSWER), (1, ANSWER), (2, ANSWER), (100_000, EITHER), (2**31, ERROR), (0, ERROR),
    (-1, ERROR), (2.5, ERROR),
]  # fmt: skip


def _batch(rng: np.random.Generator, case_id: str) -> Case:
    query = BATCH_QUERIES[int(rng.integers(2))]
    m = int(rng.integers(1, 7))
    s = scale(rng) if rng.random() < 0.5 else 1.0
    as_stack = rng.random() < 0.6
    n = int(rng.integers(1, 13))
    As, Bs = [], []
    for _ in range(m):
        if as_stack:  # the same number of points in every body
            a, b = _fit(rng.normal(size=(n, 3))), _fit(rng.normal(size=(n, 3)))
            b, _ = place(rng, a, b)
        else:
            a, b, _ = pair(rng)
        As.append(a * s)
        Bs.append(b * s)
    threads, expect = _THREADS[int(rng.integers(len(_THREADS)))]
    options = {} if threads is None else {"threads": threads}
    if as_stack:
        As, Bs = np.stack(As), np.stack(Bs)
    note = f"{m} pairs {'stack' if as_stack else 'list'} s={s:.3g} threads={threads}"
    return Case(case_id, "batch", query, _method(rng, query), As, Bs, options, expect, note)


def _real_dtypes(points: np.ndarray, rng: np.random.Generator) -> Tuple[Any, str]:
    """The same points (or numbers near them) as another real dtype or array-like."""
    kind = rng.choice(["float32", "float16", "int64", "int32", "uint8", "list", "fortran",
                       "strided", "readonly"])  # fmt: skip
    # Clipped into each dtype's range: casting a value out of range is undefined (and warns).
    if kind in ("float32", "float16"):
        return np.clip(points * 8, -6e4, 6e4).astype(kind), kind
    if kind in ("int64", "int32", "uint8"):
        return np.clip(np.round(points * 50 + 100), 0, 255).astype(kind), kind
    if kind == "list":
        return points.tolist(), kind
    if kind == "fortran":
        return np.asfortranarray(points), kind
    if kind == "strided":
        return np.repeat(points, 2, axis=0)[::2], kind
    frozen = points.copy()
    frozen.flags.writeable = False
    return frozen, kind


def _bad_dtype(points: np.ndarray, kind: str) -> np.ndarray:
    return {
        "bool": lambda: points > 0,
        "complex": lambda: points.astype(np.complex128),
        "str": lambda: points.astype(str),
        "bytes": lambda: points.astype(bytes),
        "object": lambda: points.astype(object),
        "datetime": lambda: (points * 100).astype("datetime64[s]"),
        "timedelta": lambda: (points * 100).astype("timedelta64[s]"),
    }[kind]()


_BAD_DTYPES = ("bool", "complex", "str", "bytes", "object", "datetime", "timedelta")


def _dtype(rng: np.random.Generator, case_id: str) -> Case:
    a, b, note = pair(rng)
    batch = rng.random() < 0.4
    query = (BATCH_QUERIES if batch else _SINGLE_QUERIES)[int(rng.integers(2 if batch else 3))]
    if rng.random() < 0.5:
        a, kind = _real_dtypes(a, rng)
        b, _ = _real_dtypes(b, rng) if rng.random() < 0.5 else (b, "")
        expect = ANSWER
        if batch:  # one pair as a list of one body each: real dtypes pass through
            a, b = [a], [b]
    else:
        kind = _BAD_DTYPES[int(rng.integers(len(_BAD_DTYPES)))]
        expect = ERROR
        if batch:  # (m, n, 3) stacks, the path on which issue 12 saw these dtypes cast to float
            a, b = _bad_dtype(a, kind)[None], (a + 2.0)[None]
        else:
            a = _bad_dtype(a, kind)
    method = _method(rng, query)
    return Case(case_id, "dtype", query, method, a, b, {}, expect, f"{note} dtype={kind}")


def _shape(rng: np.random.Generator, case_id: str) -> Case:
    a, b, _ = pair(rng)
    if rng.random() < 0.5:
        query = _SINGLE_QUERIES[int(rng.integers(3))]
        bad = [
            ("(n,2)", a[:, :2]), ("(n,4)", np.column_stack([a, a[:, :1]])), ("(3,)", a[0]),
            ("(0,3)", a[:0]), ("(1,n,3)", a[None]), ("(n,3,1)", a[:, :, None]), ("scalar", 1.0),
            ("None", None), ("text", "cube"), ("ragged", [[0.0, 0.0, 0.0], [1.0, 1.0]]),
            ("empty list", []),
        ]  # fmt: skip
        name, value = bad[int(rng.integers(len(bad)))]
        return Case(case_id, "shape", query, _method(rng, query), value, b, {}, ERROR, name)
    query = BATCH_QUERIES[int(rng.integers(2))]
    n = len(a)
    stack = np.stack([a, a])
    other = np.stack([b[:1].repeat(n, axis=0)] * 2)
    cases = [
        ("m mismatch", stack, other[:1], ERROR), ("(m,0,3)", stack[:, :0], other[:, :0], ERROR),
        ("(m,n,2)", stack[:, :, :2], other[:, :, :2], ERROR),
        ("(0,n,3)", stack[:0], other[:0], EITHER),
        ("(n,3) for every row", a, b, ANSWER), ("mixed lists", [a, b], [b[:1], a], ANSWER),
        ("nested lists and tuples", [a.tolist()], (b,), ANSWER),
    ]  # fmt: skip
    name, As, Bs, expect = cases[int(rng.integers(len(cases)))]
    return Case(case_id, "shape", query, _method(rng, query), As, Bs, {}, expect, name)


def _values(rng: np.random.Generator, case_id: str) -> Case:
    a, b, _ = pair(rng)
    query = _SINGLE_QUERIES[int(rng.integers(3))]
    kind = rng.choice(["nan", "inf", "-inf", "subnormal", "overflowing differences"])
    if kind in ("nan", "inf", "-inf"):
        a = a.copy()
        a[int(rng.integers(len(a))), int(rng.integers(3))] = float(kind)
        return Case(case_id, "values", query, _method(rng, query), a, b, {}, ERROR, kind)
    if kind == "subnormal":
        return Case(case_id, "values", query, _method(rng, query), a * 1e-310, b * 1e-310, {},
                    ANSWER, kind)  # fmt: skip
    # Points 1.5e308 from the origin on either side: the distance itself overflows float64.
    return Case(case_id, "values", query, _method(rng, query), a * 1e300 - 1.5e308,
                b * 1e300 + 1.5e308, {}, ERROR, kind)  # fmt: skip


FAMILIES: Dict[str, Tuple[float, Callable[[np.random.Generator, str], Case]]] = {
    "geometry": (0.5, _geometry),
    "invariance": (0.15, _invariance),
    "options": (0.1, _options),
    "batch": (0.1, _batch),
    "dtype": (0.07, _dtype),
    "shape": (0.05, _shape),
    "values": (0.03, _values),
}


def make_case(seed: int, index: int) -> Case:
    """Case ``index`` of the corpus ``seed``: the same case on every machine and every run."""
    rng = np.random.default_rng([seed, index])
    family = _pick(rng, [(share, name) for name, (share, _) in FAMILIES.items()])
    return FAMILIES[family][1](rng, f"{seed}:{index}")


def corpus(seed: int, count: int) -> List[Case]:
    """Cases 0 .. count - 1 of the corpus ``seed``."""
    return [make_case(seed, index) for index in range(count)]
