"""``Robot``: a kinematic model with convex or compound collision geometry, checked over many
configurations.

The model (links, joints, geometries) is parsed in Python by well-kept libraries (yourdfpy for
URDF, MuJoCo's compiler for MJCF: the ``[robot]`` extra) into the core's ``RobotModel``, a plain
immutable table; forward kinematics and the queries over configurations x pairs run in C++
threads without the GIL, and their answers do not depend on the number of threads.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from typing import Any, Dict, FrozenSet, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core
from .motion import DEFAULT_MOTION_ITERATIONS, DEFAULT_TIME_TOLERANCE
from .queries import DEFAULT_TOLERANCE, PoseLike, query
from .robot_tables import ModelTables

PathLike = Union[str, "os.PathLike[str]"]

LIMIT_MODES = ("raise", "clamp", "wrap")
"""What a configuration outside the joint limits does: raise ValueError naming the joint, clamp
it to the nearest limit, or wrap a revolute joint's angle by a multiple of 2 pi."""

# A field of the answer for one configuration or motion is a Python scalar (bool, float, int);
# for many, an array. Typed as either (Any): a union would make every reader narrow it first.
Bools = Any
Reals = Any
Ints = Any

MAX_SAMPLES = 1_000_000
"""The most configurations ``propose_disabled_pairs`` samples and the ``robot`` verb checks
(``--samples``): a hundred times MoveIt's default of 10,000; more would ask for memory (a value
per sample and pair, or per sample) that neither needs."""


def _array(q: npt.ArrayLike, name: str) -> np.ndarray:
    """``q`` as a NumPy array. Raises ``TypeError`` for a masked array (NumPy's conversion drops
    its mask, so its masked entries would be read as joint values) and ``ValueError`` naming
    ``name`` for a sequence NumPy cannot make an array of (rows of different lengths)."""
    if isinstance(q, np.ma.MaskedArray):
        raise TypeError(f"{name} is a NumPy masked array, whose mask would be ignored: pass "
                        f"{name}.filled(value) with the value the masked entries should take, "
                        "or a plain array")
    try:
        return np.asarray(q)
    except ValueError as error:  # a ragged sequence
        raise ValueError(f"{name} must be an array of real numbers, (dof,) or (m, dof): "
                         f"{error}") from None


@dataclass(frozen=True)
class RobotCheck:
    """Per configuration: whether any checked pair collides, and the nearest (or deepest) pair.

    For a single configuration ``q`` of shape ``(dof,)`` each field is that configuration's
    (a scalar, or a ``(3,)`` or ``(dof,)`` array); for ``(m, dof)`` each has a leading axis m.

    Attributes
    ----------
    colliding : bool array
        True when some pair is within the tolerance of contact.
    min_distance : float array
        The least signed distance over the checked pairs (negative: penetration depth), an upper
        bound achieved by the witness points; inf when no pair is checked.
    lower_bound : float array
        A lower bound on the minimum: ``lower_bound <= true minimum <= min_distance``.
    certified : bool array
        True when every pair answered is certified (``check`` skips the pairs whose bounding
        balls are proven farther apart than the nearest pair found), so the verdict and both
        bounds are proven.
    pair : int array
        Index into ``Robot.pairs`` of the nearest pair (-1 when none is checked); for a check of
        the verdict alone (``check(q, nearest=False)``), of the pair found in contact (-1 when
        none is), and ``min_distance`` and ``lower_bound`` are NaN.
    pair_names : str array, (..., 2)
        Its two geometries' names (link names, or obstacle names).
    point_a, point_b : float array, (..., 3)
        Its witness points in the world, on the pair's first and second geometry.
    normal : float array, (..., 3)
        The unit normal from the first to the second: ``point_b - point_a = min_distance *
        normal``.
    gradient : float array (..., dof), or None
        ``d min_distance / dq`` when asked (``check(q, gradient=True)``): from the witness points
        and the link Jacobians. It is the derivative where the nearest pair and its nearest
        features are unique; where they are not, it is one of the one-sided derivatives.
    """

    colliding: Bools
    min_distance: Reals
    lower_bound: Reals
    certified: Bools
    pair: Ints
    pair_names: np.ndarray
    point_a: np.ndarray
    point_b: np.ndarray
    normal: np.ndarray
    gradient: Optional[np.ndarray] = None

    def __repr__(self) -> str:
        colliding = np.atleast_1d(self.colliding)
        certified = np.atleast_1d(self.certified)
        distance = np.atleast_1d(self.min_distance)
        # A check of the verdict alone (nearest=False) has no distances to show.
        verdict_only = bool(np.isnan(distance).all())
        if colliding.size == 1:
            names = tuple(str(name) for name in np.atleast_2d(self.pair_names)[0])
            shown = "" if verdict_only else f"min_distance={distance[0]:.6g}, "
            return (f"RobotCheck(colliding={bool(colliding[0])}, {shown}"
                    f"pair={names}, certified={bool(certified[0])})")
        shown = "" if verdict_only else (
            f", min_distance in [{distance.min():.6g}, {distance.max():.6g}]")
        return (f"RobotCheck({colliding.size} configurations, {int(colliding.sum())} colliding, "
                f"{int(certified.sum())} certified{shown})")


def _robot_check(colliding: Bools, min_distance: Reals, lower_bound: Reals,
                 certified: Bools, pair: Ints, pair_names: np.ndarray,
                 point_a: np.ndarray, point_b: np.ndarray, normal: np.ndarray,
                 gradient: Optional[np.ndarray]) -> RobotCheck:
    """``RobotCheck(colliding, ..., gradient)``, the same object (fields, equality, pickling),
    its attribute dict given whole: the frozen dataclass's constructor sets each field through
    ``object.__setattr__``, 1.08 us a check against 0.50 us here (timeit, 10 fields), of the 16.5
    us a planner's ``checker(q)`` takes on the Panda with obstacles."""
    check = object.__new__(RobotCheck)
    check.__dict__.update({"colliding": colliding, "min_distance": min_distance,
                           "lower_bound": lower_bound, "certified": certified, "pair": pair,
                           "pair_names": pair_names, "point_a": point_a, "point_b": point_b,
                           "normal": normal, "gradient": gradient})
    return check


class RobotChecker:
    """A planner's check of one configuration at a time, prepared once (``Robot.checker``).

    The pairs, the method and its options and the limit mode are validated when it is made, and
    its buffers kept from one call to the next, so each call pays for the configuration alone:
    ``checker(q)`` answers as ``robot.check(q, ...)`` does with the same options, and
    ``checker.collision_free(q)`` is the bare validity test a sampling planner asks of every
    state (OMPL's ``isValid``). It answers the robot as it was when made: make another after
    ``add_obstacle`` or ``disable_pairs``. Threads may share it (the GIL is released while it
    checks; a call that finds its buffers in use by another thread takes a copy of its own).
    """

    __slots__ = ("_core", "_limits", "_pair_names", "_dof", "_description", "_made_of")

    def __init__(self, core: _core.RobotChecker, limits: str, pair_names: np.ndarray, dof: int,
                 description: str, made_of: Tuple[_core.RobotModel, np.ndarray, _core.Query]
                 ) -> None:
        self._core = core
        self._limits = limits
        self._pair_names = pair_names
        self._dof = dof
        self._description = description
        self._made_of = made_of  # the model, pairs and query the core was made of, to pickle

    def __reduce__(self):
        # The core's checker holds buffers and refers to its model: it travels as what it was
        # made of (each of which pickles) and is made again, validated as when it was first.
        model, pairs, query = self._made_of
        return (_unpickled_checker, (model, pairs, query, self._core.nearest, self._core.gradient,
                                     self._limits, self._pair_names, self._dof,
                                     self._description))

    def _configuration(self, q: npt.ArrayLike) -> np.ndarray:
        values = q if type(q) is np.ndarray else _array(q, "q")
        if values.dtype.kind not in "fiu":
            raise TypeError(f"q must hold real numbers, got an array of dtype {values.dtype}")
        if values.ndim != 1:
            raise ValueError(f"q must have shape ({self._dof},), one value per moving joint, got "
                             f"shape {values.shape}; Robot.check takes (m, dof) tables")
        return values

    def __call__(self, q: npt.ArrayLike) -> RobotCheck:
        """The check of the configuration ``q`` (dof,): a ``RobotCheck`` of one configuration.

        Raises ``ValueError`` naming the joint for a NaN or a value beyond the limits (under
        ``limits="raise"``), or for a wrong shape; ``TypeError`` for values that are not real.
        """
        colliding, min_distance, lower_bound, certified, pair, point_a, point_b, normal, slope = (
            self._core.check(self._configuration(q), self._limits))
        return _robot_check(colliding, min_distance, lower_bound, certified, pair,
                            self._pair_names[pair], point_a, point_b, normal, slope)

    def collision_free(self, q: npt.ArrayLike) -> bool:
        """True when the configuration ``q`` (dof,) is proven free of contact: no checked pair
        within the tolerance of contact, and the verdict certified. An unproven verdict gives
        False, so a planner that trusts True never accepts a state in contact."""
        return self._core.collision_free(self._configuration(q), self._limits)

    def __repr__(self) -> str:
        return f"RobotChecker({self._description})"


def _unpickled_checker(model: _core.RobotModel, pairs: np.ndarray, query: _core.Query,
                       nearest: bool, gradient: bool, limits: str, pair_names: np.ndarray,
                       dof: int, description: str) -> RobotChecker:
    """A pickled ``RobotChecker`` made again (``RobotChecker.__reduce__``)."""
    if limits not in LIMIT_MODES:
        raise ValueError(f"RobotChecker state: limits must be one of {LIMIT_MODES}, got "
                         f"{limits!r}")
    core = _core.RobotChecker(model, pairs, query, nearest, gradient)
    return RobotChecker(core, limits, pair_names, dof, description, (model, pairs, query))


@dataclass(frozen=True)
class RobotMotion:
    """Per straight joint-space motion q(t) = q0 + t (q1 - q0), t in [0, 1]: proven free, or its
    first contact bracketed (``Robot.check_motion``).

    For a single motion (``q0`` and ``q1`` of shape ``(dof,)``) each field is that motion's; for
    m motions each has a leading axis m.

    Attributes
    ----------
    touches : bool array
        False only when no checked pair is in contact at any time of the motion (when
        ``certified``). Uncertified answers are True (they err on the side of contact).
    t_lower : float array
        No pair is in contact before this time (proven, certified or not); 1 for a free motion.
    t_upper : float array
        When certified and touching, the pair ``pair`` is proven within ``tolerance x size`` of
        contact at this time, and ``t_upper - t_lower <= time_tolerance``; 1 for a free motion.
        Uncertified: the earliest time found in contact, or 1.
    q : float array (..., dof)
        The configuration at ``t_upper`` (``q1`` for a free motion).
    pair : int array
        Index into ``Robot.pairs`` of the pair in contact at ``t_upper`` (uncertified without a
        contact found: the pair left unproven); -1 for a free motion.
    pair_names : str array (..., 2)
        That pair's names (empty strings for -1).
    distance : float array
        The pair's signed distance at ``q`` (an upper bound; NaN for a free motion).
    point_a, point_b, normal : float arrays (..., 3)
        Its witness points in the world and the unit normal from its first geometry to its
        second (zeros for a free motion).
    certified : bool array
    iterations : int array
        Distance queries run (the bounding-ball and box screens not counted).
    status : str or tuple of str
        ``"converged"``, ``"max_iterations"`` (the cap ran out) or ``"unresolved"`` (a query
        stayed unproven where the times could no longer be split).
    """

    touches: Bools
    t_lower: Reals
    t_upper: Reals
    q: np.ndarray
    pair: Ints
    pair_names: np.ndarray
    distance: Reals
    point_a: np.ndarray
    point_b: np.ndarray
    normal: np.ndarray
    certified: Bools
    iterations: Ints
    status: Union[str, Tuple[str, ...]]

    def __repr__(self) -> str:
        touches = np.atleast_1d(self.touches)
        certified = np.atleast_1d(self.certified)
        if touches.size == 1 and np.ndim(self.touches) == 0:
            if not touches[0]:
                return f"RobotMotion(touches=False, certified={bool(certified[0])})"
            names = tuple(str(name) for name in np.atleast_2d(self.pair_names)[0])
            return (f"RobotMotion(touches=True, t in [{float(self.t_lower):.6g}, "
                    f"{float(self.t_upper):.6g}], pair={names}, certified={bool(certified[0])})")
        return (f"RobotMotion({touches.size} motions, {int(touches.sum())} touching, "
                f"{int(certified.sum())} certified)")


@dataclass(frozen=True)
class PairProposal:
    """Pairs of links (or obstacles) that collided in every sampled configuration, or in none:
    candidates for ``Robot.disable_pairs`` (as MoveIt's setup assistant proposes them), shown,
    not applied. A pair that never collided in the samples may still collide elsewhere.

    Attributes
    ----------
    always, never : tuple of (str, str)
    samples : int
        The configurations sampled (uniform within each joint's limits; a revolute or continuous
        joint without finite limits over one turn within them).
    """

    always: Tuple[Tuple[str, str], ...]
    never: Tuple[Tuple[str, str], ...]
    samples: int


class Robot:
    """A robot: links, joints and convex collision geometries, and the pairs checked.

    Build one with ``from_urdf`` or ``from_mjcf`` (or from tables: ``links``, ``joints`` as
    ``Joint``, ``geometries`` as ``(name, link index, origin, body)``, the body a
    ``ConvexPolyhedron``, a shape such as ``Box``, ``Sphere``, ``Capsule``, ``Cylinder`` or
    ``Ellipsoid``, or a ``CompoundBody``, and optionally ``pairs``, the pairs of geometry names
    to check, in place of every pair of geometries on links that are not adjacent). The model
    is immutable and shared across threads; ``add_obstacle`` and ``disable_pairs`` make a new
    model. Curved shapes (``Cylinder``, ``Ellipsoid``, ...) are exact and answered through
    their support functions, by the methods ``"dual"`` (the default), ``"exact"``, ``"fcl"``
    and ``"libccd"``; a method that reads a body's points (``"ipso"``, ``"pso"``,
    ``"penalty"``) refuses them with ``ValueError`` naming the geometry.

    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> elbow = np.eye(4)
    >>> elbow[0, 3] = 1.0                       # the elbow is 1 along the upper arm
    >>> joints = [sc.Joint("shoulder", "revolute", 0, 1, lower=-3, upper=3),
    ...           sc.Joint("elbow", "revolute", 1, 2, origin=elbow, lower=-3, upper=3)]
    >>> box = sc.Box([0.1, 0.1, 0.1])
    >>> geometries = [("base", 0, None, box), ("upper", 1, None, sc.Sphere(0.1)),
    ...               ("fore", 2, elbow, box)]  # fore's box at its far end
    >>> robot = sc.Robot(["base", "upper", "fore"], joints, geometries)
    >>> robot.pairs
    (('base', 'fore'),)
    >>> robot.check([0.0, 3.0])
    RobotCheck(colliding=True, min_distance=-0.0..., pair=('base', 'fore'), certified=True)
    >>> robot.check([[0.0, 0.0], [0.0, 3.0]], threads=1).colliding
    array([False,  True])
    >>> free = robot.checker(nearest=False).collision_free  # a planner's validity test
    >>> free([0.0, 0.0]), free([0.0, 3.0])
    (True, False)
    """

    def __init__(self, links: Sequence[str], joints: Sequence[Any],
                 geometries: Sequence[Tuple[str, int, PoseLike, Any]], *,
                 pairs: Optional[Sequence[Tuple[str, str]]] = None) -> None:
        self._links = list(links)
        self._joints = list(joints)
        self._robot_geometries = list(geometries)
        self._obstacles: List[Tuple[str, int, PoseLike, Any]] = []
        self._disabled: FrozenSet[FrozenSet[str]] = frozenset()
        self._own_pairs = None if pairs is None else self._geometry_pairs(pairs)
        self._rebuild()

    @classmethod
    def _from_tables(cls, tables: ModelTables) -> "Robot":
        return cls(tables.links, tables.joints, tables.geometries, pairs=tables.pairs)

    def _geometry_pairs(self, pairs: Sequence[Tuple[str, str]]) -> List[Tuple[int, int]]:
        """``pairs`` of geometry names as index pairs ``(a, b)``, ``a < b``.

        Raises ``TypeError`` for an entry that is not two names, ``ValueError`` for a name that
        is no geometry of the robot or a geometry paired with itself.
        """
        if isinstance(pairs, (str, bytes)):
            raise TypeError(f"pairs must be a sequence of (name, name) pairs, got the string "
                            f"{pairs!r}")
        index = {geometry[0]: g for g, geometry in enumerate(self._robot_geometries)}
        table = set()
        for i, pair in enumerate(pairs):
            if isinstance(pair, (str, bytes)) or len(pair) != 2:
                raise TypeError(f"pairs[{i}] must be a pair of geometry names, got {pair!r}")
            for end in pair:
                if end not in index:
                    raise ValueError(f"pairs[{i}] = {tuple(pair)!r}: '{end}' is not a geometry "
                                     "of the robot")
            a, b = sorted(index[end] for end in pair)
            if a == b:
                raise ValueError(f"pairs[{i}] pairs geometry '{pair[0]}' with itself")
            table.add((a, b))
        return sorted(table)

    @classmethod
    def from_urdf(cls, path: PathLike, package_dirs: Optional[Sequence[PathLike]] = None,
                  collision: str = "hull", *, srdf: Optional[PathLike] = None) -> "Robot":
        """A robot from a URDF file, parsed by yourdfpy.

        Parameters
        ----------
        path : str or os.PathLike
        package_dirs : sequence of paths, optional
            Where ``package://NAME/...`` mesh paths are looked up: each directory is the package
            NAME itself or holds it. Relative mesh paths are read from the URDF's directory.
        collision : {"hull", "mesh", "decompose"}
            ``"hull"``: each ``<collision>`` mesh is its convex hull (the body finds the hull of
            the mesh's vertices, scaled). ``"mesh"``: a compound body of the mesh's convex pieces
            (OBJ groups or connected components, each convex). ``"decompose"``: a compound body
            of CoACD's decomposition (``CompoundBody.from_mesh``, cached on disk). A compound
            geometry's signed distance is the least over its parts' (``signed_distance``).
        srdf : str or os.PathLike, optional
            An SRDF whose ``disable_collisions`` pairs are not checked.

        Boxes, spheres and cylinders are exact (``Box``, ``Sphere``, ``Cylinder`` at their
        ``<origin>``). A mesh's ``scale`` is URDF's three numbers (x y z), or one for a uniform
        scale (as yourdfpy and pybullet read it). Joints are revolute, continuous, prismatic or
        fixed; the degrees of freedom are the moving joints in the file's order (yourdfpy's
        ``actuated_joints``).

        Raises
        ------
        ValueError
            For a missing file, a file that is not a URDF (its root element is not
            ``<robot>``: an MJCF file is pointed to ``from_mjcf``), an unknown or unsupported
            joint type (naming the joint), a mesh file that is missing or a ``package://`` path
            that cannot be resolved, a mesh scale of other than 3 numbers (or 1) or one that is
            not finite and non-zero (naming the link), a mesh whose pieces are not convex under
            ``collision="mesh"`` (naming the link, the file and the modes that take it), or an
            unknown ``collision`` mode.
        """
        from .robot_urdf import load_urdf

        robot = cls._from_tables(load_urdf(path, package_dirs, collision))
        return robot.disable_pairs(read_srdf(srdf)) if srdf is not None else robot

    @classmethod
    def from_mjcf(cls, path: PathLike, *, skip_planes: bool = False,
                  srdf: Optional[PathLike] = None) -> "Robot":
        """A robot from an MJCF file, compiled by MuJoCo (``mujoco.MjModel.from_xml_path``).

        Each body is a link (the world body is the root, ``"world"``); hinge joints are revolute
        (continuous when unlimited), slide joints prismatic, and a body with several joints or an
        off-origin hinge anchor gets a link per joint (named ``body/joint``). The collision geoms
        (``contype`` or ``conaffinity`` nonzero, or named by a ``<contact><pair>``) are the
        geometries: meshes (the hull of the compiled mesh's vertices), and boxes, spheres,
        capsules, cylinders and ellipsoids exactly (``Box``, ``Sphere``, ``Capsule``,
        ``Cylinder``, ``Ellipsoid`` at the geom's pose). The degrees of freedom are MuJoCo's
        ``qpos``.

        The pairs checked are those MuJoCo's own contact filter lets through (``pairs``):

        - each ``<contact><pair>``, whatever its geoms' masks and bodies;
        - any other two geoms whose masks match, ``(contype1 & conaffinity2) or (contype2 &
          conaffinity1)``, except geoms of one body or of bodies welded together (no joint
          between them), geoms of a parent body and its child (unless the parent is the world
          body, or the model has ``<option><flag filterparent="disable"/>``), and geoms of a
          ``<contact><exclude body1 body2>`` pair of bodies.

        So a model whose geoms all have ``contype="0"`` checks no pair of its own. The geoms
        are checked against every obstacle (``add_obstacle``) whatever their masks, and
        ``srdf`` or ``disable_pairs`` removes pairs from MuJoCo's. A model that switches
        contacts off (``<option><flag contact="disable"/>``, or ``constraint="disable"``)
        checks no pair of its own, as in MuJoCo, with a ``UserWarning`` that says so.

        Parameters
        ----------
        path : str or os.PathLike
        skip_planes : bool
            Leave plane geoms (unbounded) out instead of raising ValueError.
        srdf : str or os.PathLike, optional
            An SRDF whose ``disable_collisions`` pairs are not checked.
        """
        from .robot_mjcf import load_mjcf

        robot = cls._from_tables(load_mjcf(path, skip_planes))
        return robot.disable_pairs(read_srdf(srdf)) if srdf is not None else robot

    def __getstate__(self) -> Dict[str, Any]:
        # The kept checker is a cache of the model's (made again on the first check).
        state = self.__dict__.copy()
        state["_last_checker"] = None
        return state

    def _rebuild(self) -> None:
        # Robot.check's checker of one configuration answers the model it was made for.
        self._last_checker: Optional[Tuple[tuple, RobotChecker]] = None
        self._model = _core.RobotModel(self._links, self._joints,
                                       self._robot_geometries + self._obstacles)
        names = self.geometry_names
        owners = [self._links[link] if link >= 0 else names[g]
                  for g, link in enumerate(self._model.geometry_links)]
        default = np.asarray(self._model.default_pairs()).reshape(-1, 2)
        candidates = [(int(a), int(b)) for a, b in default]
        if self._own_pairs is not None:
            # The model's own pairs replace the adjacency rule between its geometries; each
            # obstacle (after them in the table) stays checked against every one of them.
            robot = len(self._robot_geometries)
            candidates = sorted(self._own_pairs + [(a, b) for a, b in candidates if b >= robot])
        table = [(a, b) for a, b in candidates
                 if frozenset((owners[a], owners[b])) not in self._disabled]
        self._pair_table = np.asarray(table, dtype=np.int32).reshape(-1, 2)
        # Each answer's pair names, indexed by its pair (-1, nothing checked, reads the last row):
        # made here once, as building it took longer than a configuration's verdict.
        self._pair_names = np.array(list(self.pairs) + [("", "")], dtype=str).reshape(-1, 2)
        self._pair_names.setflags(write=False)  # a single answer's names are a view of a row

    @property
    def model(self) -> _core.RobotModel:
        """The core's model: immutable, shared by every call and thread."""
        return self._model

    @property
    def dof(self) -> int:
        """The number of degrees of freedom (moving joints)."""
        return self._model.dof

    @property
    def link_names(self) -> Tuple[str, ...]:
        return tuple(self._model.link_names)

    @property
    def joint_names(self) -> Tuple[str, ...]:
        """The moving joints, in the order of the configuration's values."""
        joints = self._model.joints
        return tuple(joints[j].name for j in self._model.moving_joints)

    @property
    def limits(self) -> np.ndarray:
        """``(dof, 2)`` lower and upper limits (-inf, inf for continuous joints)."""
        joints = self._model.joints
        return np.array([[joints[j].lower, joints[j].upper] for j in self._model.moving_joints],
                        dtype=float).reshape(-1, 2)

    @property
    def geometry_names(self) -> Tuple[str, ...]:
        return tuple(g[0] for g in self._robot_geometries + self._obstacles)

    @property
    def pairs(self) -> Tuple[Tuple[str, str], ...]:
        """The checked pairs by geometry name (a link's name when it has one geometry), in the
        order of ``distances``' columns: geometries of links that are not adjacent (parent and
        child, or joined by fixed joints), or the model's own pairs (``pairs``; an MJCF file's
        contact filter), less the disabled pairs, and every obstacle against every link's
        geometry."""
        names = self.geometry_names
        return tuple((names[a], names[b]) for a, b in self._pair_table)

    def add_obstacle(self, body: Any, pose: PoseLike = None, *,
                     name: Optional[str] = None) -> "Robot":
        """Add a body fixed in the world, checked against every link; returns the robot.

        Parameters
        ----------
        body : ConvexPolyhedron, CompoundBody or (n, 3) array_like
            A convex body (a ``Box``, ``Sphere``, ...) or a compound one (a mesh's parts).
        pose : pose, optional
            Where it is: a ``(4, 4)`` rigid transform or ``(rotation, translation)``.
        name : str, optional
            Its name in ``pairs`` (default ``obstacle{k}``); must differ from every geometry's.

        A pose that is not a rigid transform raises ``ValueError`` (``TypeError`` for one of
        the wrong type) naming ``pose``, and leaves the robot as it was.
        """
        name = f"obstacle{len(self._obstacles)}" if name is None else name
        if not isinstance(name, str):
            raise TypeError(f"name must be a str, got {type(name).__name__}")
        if name in self.geometry_names or name in self._links:
            raise ValueError(f"name '{name}' is taken by a link or geometry; choose another")
        self._obstacles.append((name, -1, pose, body))
        try:
            self._rebuild()
        except Exception as error:
            self._obstacles.pop()
            # The core checks an obstacle's pose as its geometry's origin: name the argument.
            origin = f"geometry '{name}' origin"
            if isinstance(error, (ValueError, TypeError)) and str(error).startswith(origin):
                raise type(error)(f"pose (of obstacle '{name}')" + str(error)[len(origin):]
                                  ) from None
            raise
        return self

    def disable_pairs(self, pairs: Sequence[Tuple[str, str]]) -> "Robot":
        """Stop checking these pairs of link (or obstacle) names; returns the robot.

        Raises ``TypeError`` for ``pairs`` that is not a sequence of pairs of names (a single
        string, an entry of one or three names), ``ValueError`` for a name that is no link or
        obstacle of the robot.
        """
        known = set(self._links) | {o[0] for o in self._obstacles}
        disabled = set(self._disabled)
        if isinstance(pairs, (str, bytes)):
            raise TypeError(f"pairs must be a sequence of (name, name) pairs, got the string "
                            f"{pairs!r}: write [({pairs!r}, ...)]")
        for i, pair in enumerate(pairs):
            if isinstance(pair, (str, bytes)) or len(pair) != 2:
                raise TypeError(f"pairs[{i}] must be a pair of link or obstacle names, got "
                                f"{pair!r}")
            a, b = pair
            for end in (a, b):
                if end not in known:
                    raise ValueError(f"disabled pair ({a!r}, {b!r}): '{end}' is not a link or "
                                     "obstacle of the robot")
            disabled.add(frozenset((a, b)))
        self._disabled = frozenset(disabled)
        self._rebuild()
        return self

    def _configurations(self, q: npt.ArrayLike, limits: str,
                        name: str = "q") -> Tuple[np.ndarray, bool]:
        values = _array(q, name)
        if values.dtype.kind not in "fiu":
            raise TypeError(f"{name} must hold real numbers, got an array of dtype "
                            f"{values.dtype}")
        if values.ndim not in (1, 2):
            raise ValueError(f"{name} must have shape (dof,) or (m, dof) with dof = {self.dof}, "
                             f"got shape {values.shape}")
        single = values.ndim == 1
        table = np.ascontiguousarray(values.reshape(1, -1) if single else values, dtype=float)
        if limits not in LIMIT_MODES:
            raise ValueError(f"limits must be one of {LIMIT_MODES}, got {limits!r}")
        try:
            return self._model.admit(table, limits, single), single
        except ValueError as error:
            # The core names the configurations q ("q[3], joint 'elbow': ..."); say which.
            message = str(error)
            if name == "q" or not message.startswith("q"):
                raise
            raise ValueError(name + message[1:]) from None

    def forward_kinematics(self, q: npt.ArrayLike, *, limits: str = "raise") -> np.ndarray:
        """Every link's world transform: ``(links, 4, 4)`` for q of shape ``(dof,)``, ``(m,
        links, 4, 4)`` for ``(m, dof)``; the links in ``link_names``' order.

        Raises ``ValueError`` naming the configuration and joint for a wrong length, a NaN, or a
        value outside the limits under ``limits="raise"`` (``"clamp"``, ``"wrap"``: see
        ``LIMIT_MODES``).
        """
        table, single = self._configurations(q, limits)
        transforms = self._model.forward_kinematics(table)
        return transforms[0] if single else transforms

    def geometry_poses(self, q: npt.ArrayLike, *, limits: str = "raise") -> np.ndarray:
        """Every geometry's world transform (its link's times its origin), in
        ``geometry_names``' order: ``(geometries, 4, 4)`` or ``(m, geometries, 4, 4)``; the poses
        the queries place the geometries at."""
        table, single = self._configurations(q, limits)
        transforms = self._model.geometry_poses(table)
        return transforms[0] if single else transforms

    def distances(self, q: npt.ArrayLike, *, limits: str = "raise",
                  threads: Optional[int] = None, method: str = "dual",
                  tolerance: float = DEFAULT_TOLERANCE, seed: int = 0) -> np.ndarray:
        """The signed distance of every checked pair (``pairs``), ``(m, pairs)`` (``(pairs,)``
        for a single configuration): upper bounds achieved by witness points, certified to
        ``tolerance`` times each pair's size.

        Each pair is ``signed_distance_many`` over the configurations with the geometries' world
        poses read in place; ``threads`` (default: one per hardware thread) does not change the
        answers.
        """
        table, single = self._configurations(q, limits)
        answer = self._model.distances(self._pair_table, table,
                                       query(method, tolerance=tolerance, seed=seed), threads)
        return answer.distance[0] if single else answer.distance

    def check(self, q: npt.ArrayLike, *, limits: str = "raise", threads: Optional[int] = None,
              nearest: bool = True, gradient: bool = False, method: str = "dual",
              tolerance: float = DEFAULT_TOLERANCE, seed: int = 0) -> RobotCheck:
        """Whether each configuration collides, and its nearest pair with witness points.

        Each configuration's pairs are answered (``signed_distance`` at the geometries' world
        poses) in increasing order of the separation of their bounding balls, until the next
        pair's balls are proven farther apart than the nearest pair found: the answer is that of
        every pair (``distances``) reduced to its nearest, at a fraction of the cost. Each
        configuration is answered whole by one C++ thread, without the GIL.

        With ``nearest=False`` only the verdict is computed, as a planner's validity check needs
        it: the pairs whose bounding balls are not proven apart are answered by ``collide``
        (which stops at the first separating plane it proves), nearest balls first, until one is
        proven in contact. ``pair`` is then that pair (-1 when none collides), ``certified`` says
        whether the verdict is proven, ``min_distance`` and ``lower_bound`` are NaN and the
        witnesses zero.

        Parameters
        ----------
        q : array_like, (dof,) or (m, dof)
            Joint values in ``joint_names``' order.
        limits : {"raise", "clamp", "wrap"}
            What a value outside its joint's limits does (``LIMIT_MODES``).
        threads : int, optional
            C++ threads (default one per hardware thread, woken once the configurations left
            would take the calling thread over about 200 us alone); answers do not depend on it.
        nearest : bool
            Find the nearest pair and its distance (default), or only the verdict.
        gradient : bool
            Also ``d min_distance / dq`` (see ``RobotCheck.gradient``); needs ``nearest``.
        method, tolerance, seed
            The pair queries' (see ``signed_distance``).

        Returns
        -------
        RobotCheck
        """
        if gradient and not nearest:
            raise ValueError("gradient needs the nearest pair: pass nearest=True with "
                             "gradient=True")
        configurations = _array(q, "q")
        if (configurations.ndim == 1 and configurations.dtype.kind in "fiu"
                and limits in LIMIT_MODES):
            # A planner's check of one state, by the checker of these options (kept for the
            # next call with the same ones), on the calling thread whatever `threads` says.
            # The types too: 1 == True, and a flag given as 1 must be refused as before.
            key = (limits, nearest, gradient, method, tolerance, seed, threads, type(nearest),
                   type(gradient), type(tolerance), type(seed), type(threads))
            if self._last_checker is None or self._last_checker[0] != key:
                checker = self.checker(limits=limits, nearest=nearest, gradient=gradient,
                                       method=method, tolerance=tolerance, seed=seed)
                if threads is not None:
                    # Refused by name as a batch refuses it: a table of no configuration.
                    self._model.check(self._pair_table, np.empty((0, self.dof)),
                                      query(method, tolerance=tolerance, seed=seed), threads,
                                      gradient, nearest)
                self._last_checker = (key, checker)
            return self._last_checker[1](configurations)
        # Many configurations (a single one of another kind or with unknown limits is refused
        # here, by name).
        table, _ = self._configurations(configurations, limits)
        raw = self._model.check(self._pair_table, table, query(method, tolerance=tolerance,
                                                              seed=seed), threads, gradient,
                                nearest)
        return _robot_check(raw.colliding, raw.min_distance, raw.lower_bound, raw.certified,
                            raw.pair, self._pair_names[raw.pair], raw.point_a, raw.point_b,
                            raw.normal, raw.gradient if gradient else None)

    def checker(self, *, limits: str = "raise", nearest: bool = True, gradient: bool = False,
                method: str = "dual", tolerance: float = DEFAULT_TOLERANCE,
                seed: int = 0) -> RobotChecker:
        """A check of one configuration at a time with these options validated once: what a
        sampling planner calls for every state. ``checker(q)`` answers as ``check(q, ...)``
        with the same options; ``checker.collision_free(q)`` is the bare validity test, True
        only when q is proven free of contact (``Robot``'s example shows one).

        Parameters are ``check``'s (``limits``, ``nearest``, ``gradient``, ``method``,
        ``tolerance``, ``seed``), refused here, by name, when invalid. The checker answers the
        robot as it is now (its obstacles and pairs).
        """
        if limits not in LIMIT_MODES:
            raise ValueError(f"limits must be one of {LIMIT_MODES}, got {limits!r}")
        if gradient and not nearest:
            raise ValueError("gradient needs the nearest pair: pass nearest=True with "
                             "gradient=True")
        queries = query(method, tolerance=tolerance, seed=seed)
        core = _core.RobotChecker(self._model, self._pair_table, queries, nearest, gradient)
        description = (f"{len(self._pair_table)} pairs, dof {self.dof}, limits={limits!r}, "
                       f"nearest={nearest}, gradient={gradient}, method={method!r}, "
                       f"tolerance={tolerance:g}, seed={seed}")
        return RobotChecker(core, limits, self._pair_names, self.dof, description,
                            (self._model, self._pair_table, queries))

    def check_motion(self, q0: npt.ArrayLike, q1: npt.ArrayLike, *, limits: str = "raise",
                     threads: Optional[int] = None,
                     time_tolerance: float = DEFAULT_TIME_TOLERANCE,
                     max_iterations: int = DEFAULT_MOTION_ITERATIONS, method: str = "exact",
                     tolerance: float = DEFAULT_TOLERANCE, seed: int = 0) -> RobotMotion:
        """Whether the robot touches anything while its joints move along the straight segment
        q(t) = q0 + t (q1 - q0), t in [0, 1] (a planner's edge), and if so when first.

        Never sampled at a resolution: each pair is advanced conservatively on its certified
        distance lower bounds, with a bound on how fast its links can move that follows from
        the joint displacements (Schwarzer, Saha and Latombe): a point of a link moves by at most
        sum |dq_j| r_j over the joints j of its chain, r_j bounding the distance from joint j's
        axis to the link's points (1 for a prismatic joint); a pair leaves out the joints its two
        links share. Near a contact the remaining time is bisected. The answer is a proof that
        no pair touches, or the first contact within ``[t_lower, t_upper]`` (see
        ``RobotMotion``). Each motion is answered whole by one C++ thread, without the GIL.

        Parameters
        ----------
        q0, q1 : array_like, (dof,) or (m, dof)
            The motions' ends in ``joint_names``' order; a single configuration of either serves
            every motion.
        limits : {"raise", "clamp"}
            What an end outside its joints' limits does: raise ``ValueError`` naming ``q0`` or
            ``q1``, the row and the joint, or move it to the nearest limit (the motion is then
            the segment between the clamped ends). Between ends within the limits the whole
            segment is (the limits are a box). ``"wrap"`` is refused: turning an end by 2 pi is
            the same pose but another motion.
        threads : int, optional
            C++ threads (default one per hardware thread, woken once the configurations left
            would take the calling thread over about 200 us alone); answers do not depend on it.
        time_tolerance : float
            The largest width of a first contact's bracket, as a fraction of the motion, in
            (0, 1].
        max_iterations : int
            Distance queries per motion at most; past it the motion is answered uncertified.
        method, tolerance, seed
            The pair queries' (``method`` must answer distances: ``"exact"``, the default and
            the fastest here, ``"dual"``, ``"fcl"``; a query one leaves unproven is asked again
            of ``"exact"``, or of ``"dual"`` after ``"exact"``); pairs within ``tolerance`` times
            their size (the sum of their bounding balls' diameters) are in contact;
            ``tolerance`` must be positive. Every motion's queries take ``seed``, so a row of a
            batch answers as the same motion alone.

        Returns
        -------
        RobotMotion

        Examples
        --------
        >>> import numpy as np, swarmcollide as sc
        >>> arm = sc.Robot(["base", "arm"], [sc.Joint("turn", "revolute", 0, 1, lower=-3,
        ...                                           upper=3)],
        ...                [("bar", 1, np.array([[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0],
        ...                                      [0, 0, 0, 1.0]]), sc.Box([0.5, 0.02, 0.02]))])
        >>> pole = np.eye(4)
        >>> pole[:3, 3] = [0.0, 0.6, 0.0]
        >>> arm = arm.add_obstacle(sc.Cylinder(0.01, 1.0), pole, name="pole")
        >>> bool(arm.check([-1.0]).colliding), bool(arm.check([2.5]).colliding)
        (False, False)
        >>> hit = arm.check_motion([-1.0], [2.5])
        >>> hit
        RobotMotion(touches=True, t in [0.7..., 0.7...], pair=('bar', 'pole'), certified=True)
        >>> arm.check_motion([-1.0], [0.5]).touches
        False
        """
        if limits == "wrap":
            raise ValueError("limits='wrap' is refused for motions: turning an end by 2 pi is "
                             "the same pose but another motion; use 'raise' or 'clamp'")
        if isinstance(max_iterations, bool) or not isinstance(max_iterations, (int, np.integer)):
            raise TypeError(f"max_iterations must be an int, got {max_iterations!r}")
        # As time_of_impact reads it: a bool or a string is no tolerance.
        if isinstance(time_tolerance, (bool, np.bool_)) or not isinstance(
                time_tolerance, (int, float, np.integer, np.floating)):
            raise TypeError(f"time_tolerance must be a real number, got {time_tolerance!r}")
        start, single_start = self._configurations(q0, limits, "q0")
        end, single_end = self._configurations(q1, limits, "q1")
        raw = self._model.check_motion(self._pair_table, start, end,
                                       query(method, tolerance=tolerance, seed=seed),
                                       float(time_tolerance), int(max_iterations), threads)
        # One motion (a planner's edge) reads its row alone, without every field's array.
        values = raw.row(0) if single_start and single_end else (
            raw.touches, raw.t_lower, raw.t_upper, raw.configuration, raw.pair, raw.distance,
            raw.point_a, raw.point_b, raw.normal, raw.certified, raw.iterations, tuple(raw.status))
        (touches, t_lower, t_upper, configuration, pair, distance, point_a, point_b, normal,
         certified, iterations, status) = values
        return RobotMotion(touches=touches, t_lower=t_lower, t_upper=t_upper, q=configuration,
                           pair=pair, pair_names=self._pair_names[pair], distance=distance,
                           point_a=point_a, point_b=point_b, normal=normal, certified=certified,
                           iterations=iterations, status=status)

    def propose_disabled_pairs(self, samples: int = 1000, *, seed: int = 0,
                               threads: Optional[int] = None) -> PairProposal:
        """Sample configurations and propose the checked pairs that always or never collide.

        Parameters
        ----------
        samples : int
            Configurations, each joint's value uniform within its limits (a revolute or
            continuous joint without finite limits over one turn within them, [-pi, pi] when
            they hold it; a prismatic one without finite limits raises ``ValueError``).
        seed : int
            Seeds the sampler (NumPy's default generator).
        threads : int, optional
            As for ``distances``.

        Returns
        -------
        PairProposal
            By link (or obstacle) name: a link pair collides in a sample when any pair of their
            geometries does. Nothing is disabled: pass the pairs you accept to
            ``disable_pairs``.
        """
        if isinstance(samples, bool) or not isinstance(samples, int) or samples < 1:
            raise ValueError(f"samples must be a positive integer, got {samples!r}")
        if samples > MAX_SAMPLES:
            raise ValueError(f"samples must be at most {MAX_SAMPLES:,}, got {samples:,}: each "
                             "sample holds a value per checked pair")
        # NumPy's message for a negative seed names no argument.
        if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
            raise TypeError(f"seed must be an integer, got {type(seed).__name__}")
        if seed < 0:
            raise ValueError(f"seed must be a non-negative integer, got {seed}")
        q = random_configurations(self, samples, seed)
        colliding = self._model.distances(self._pair_table, self._model.admit(q, "raise"),
                                          query(), threads).colliding
        names = self.geometry_names
        links = self._model.geometry_links
        owners = [self._links[link] if link >= 0 else names[g] for g, link in enumerate(links)]
        by_owner: Dict[Tuple[str, str], np.ndarray] = {}
        for p, (a, b) in enumerate(self._pair_table):
            key = (owners[a], owners[b])
            by_owner[key] = by_owner.get(key, np.zeros(samples, bool)) | colliding[:, p]
        return PairProposal(
            always=tuple(k for k, hits in by_owner.items() if hits.all()),
            never=tuple(k for k, hits in by_owner.items() if not hits.any()),
            samples=samples)

    def __repr__(self) -> str:
        return (f"Robot({len(self._links)} links, dof {self.dof}, "
                f"{len(self._robot_geometries)} geometries, {len(self._obstacles)} obstacles, "
                f"{len(self._pair_table)} pairs)")


def random_configurations(robot: Robot, samples: int, seed: int) -> np.ndarray:
    """``(samples, dof)`` configurations of ``robot``, each joint's value uniform within its own
    limits, from NumPy's default generator seeded by ``seed``: the samples of
    ``propose_disabled_pairs`` and of the ``robot`` verb.

    A revolute or continuous joint without a finite range (``upper - lower``) is sampled over one
    turn within its limits, as its poses repeat every 2 pi: [-pi, pi] when they hold it, else
    the turn from its finite limit. A prismatic joint has no such period: one without a finite
    range raises ``ValueError`` naming it.
    """
    lower, upper = robot.limits.T
    with np.errstate(over="ignore", invalid="ignore"):  # inf - inf, or 1e308 - -1e308
        bounded = np.isfinite(upper - lower)
    joints = robot.model.joints
    for k, j in enumerate(robot.model.moving_joints):
        if not bounded[k] and joints[j].type == "prismatic":
            raise ValueError(
                f"joint '{joints[j].name}' is prismatic with limits [{lower[k]:g}, "
                f"{upper[k]:g}]: configurations are sampled within each joint's limits, so a "
                "sliding joint needs a finite range; give it finite limits in the model (URDF "
                "<limit lower=... upper=...>, MJCF range=\"...\" limited=\"true\")")
    # The turn [-pi, pi], moved up to a finite lower limit or down to a finite upper one.
    turn_start = np.clip(-np.pi, lower, upper - 2 * np.pi)
    lower = np.where(bounded, lower, turn_start)
    upper = np.where(bounded, upper, turn_start + 2 * np.pi)
    return np.random.default_rng(seed).uniform(lower, upper, size=(samples, robot.dof))


def read_srdf(path: PathLike) -> List[Tuple[str, str]]:
    """The ``disable_collisions`` pairs ``(link1, link2)`` of an SRDF file.

    Raises ``ValueError`` for a missing or malformed file, or an entry without both links.
    """
    try:
        root = ElementTree.parse(os.fspath(path)).getroot()
    except (OSError, ElementTree.ParseError) as error:
        raise ValueError(f"cannot read SRDF file '{path}': {error}") from error
    pairs = []
    for element in root.iter("disable_collisions"):
        a, b = element.get("link1"), element.get("link2")
        if not a or not b:
            raise ValueError(f"SRDF file '{path}': a disable_collisions entry needs link1 and "
                             "link2")
        pairs.append((a, b))
    return pairs
