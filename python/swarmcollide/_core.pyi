"""
swarmcollide's C++ core: convex polyhedra and compound bodies, model (2), its solvers, queries and scenes.
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Aabb', 'BatchResult', 'Box', 'Capsule', 'CompoundBody', 'CompoundResult', 'CompoundStats', 'Cone', 'ContactResult', 'ConvexPolyhedron', 'Cylinder', 'DistanceResult', 'Ellipsoid', 'Hull', 'Joint', 'PartNode', 'ParticleCoefficients', 'Query', 'RobotCheck', 'RobotChecker', 'RobotDistances', 'RobotModel', 'RobotMotionCheck', 'Scene', 'SceneResult', 'SceneStats', 'Sphere', 'SweepResult', 'TimeOfImpactBatch', 'TimeOfImpactResult', 'as_polyhedron', 'broadphases', 'constraint_violation', 'is_feasible', 'linear_decreasing_inertia', 'method_table', 'motion_function', 'objective', 'pair_seed', 'pose_matrix', 'project_onto_simplex', 'query_function', 'rank_adaptive_coefficients', 'separation', 'time_of_impact', 'time_of_impact_many']
class Aabb:
    """
    An axis-aligned bounding box with corners ``min`` and ``max``.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
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
    part_a, part_b : numpy.ndarray of int, shape (m,)
        The parts of compound bodies that realise each answer (0 for convex bodies).
    """
    def __getstate__(self) -> tuple:
        ...
    def __len__(self) -> int:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def certified(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def colliding(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def direction(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]:
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
    def part_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def part_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]:
        ...
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]:
        ...
class Box(ConvexPolyhedron):
    """
    
    An axis-aligned box centred on the origin of its frame, ``2 half_extents`` across (URDF's
    ``<box size>`` is ``2 half_extents``; MJCF's box geom size is ``half_extents``): the hull of its
    8 corners, rounded by ``radius`` (a rounded box then spans ``half_extents + radius``).
    
    Queries answer rounded bodies on their cores (the points' hull) and subtract the radii: the signed distance of two rounded convex bodies is exactly that of their cores less both radii, so bounds, certificates and verdicts keep their meaning, relative to the size of the rounded bodies. Methods ``'ipso'``, ``'pso'`` and ``'penalty'`` (model (2)) weigh the core's points; ``'fcl'`` and ``'libccd'`` also answer on the cores (not on FCL's own sphere and capsule primitives). Support points, hulls, centroids and weights are the core's.
    
    Parameters
    ----------
    half_extents : array_like, shape (3,)
        Half the box's size along x, y and z, each finite and ``> 0``.
    radius : float, optional
        The rounding radius, finite and ``>= 0`` (0, the default, for a sharp box).
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> box = sc.Box([1, 2, 3])
    >>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> sc.distance(box, sc.Sphere(1), pose_b=(identity, [3, 0, 0])).distance
    1.0
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, half_extents: typing.Any, radius: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def half_extents(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Half the box's size along x, y and z.
        """
class Capsule(ConvexPolyhedron):
    """
    
    A capsule along the z axis of its frame, centred on its origin (MJCF's capsule geom, size =
    (radius, half_length)): the segment from ``(0, 0, -half_length)`` to ``(0, 0, half_length)``
    rounded by ``radius``, ``2 (half_length + radius)`` long in all.
    
    Queries answer rounded bodies on their cores (the points' hull) and subtract the radii: the signed distance of two rounded convex bodies is exactly that of their cores less both radii, so bounds, certificates and verdicts keep their meaning, relative to the size of the rounded bodies. Methods ``'ipso'``, ``'pso'`` and ``'penalty'`` (model (2)) weigh the core's points; ``'fcl'`` and ``'libccd'`` also answer on the cores (not on FCL's own sphere and capsule primitives). Support points, hulls, centroids and weights are the core's.
    
    Parameters
    ----------
    radius : float
        Finite and ``> 0``.
    half_length : float
        Half the length of the core segment (of the cylinder part), finite and ``> 0``.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> upright = sc.Capsule(0.5, 1.0)
    >>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> sc.distance(upright, upright, pose_b=(identity, [2, 0, 0.5])).distance
    1.0
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, radius: typing.SupportsFloat | typing.SupportsIndex, half_length: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def half_length(self) -> float:
        """
        Half the length of the core segment.
        """
class CompoundBody:
    """
    
    A body that is the union of convex parts, each a ConvexPolyhedron in the body's own frame.
    
    The body keeps a bounding-volume tree over its parts whose every node holds a box, a ball and the
    convex hull of the parts below it, the paper's "convex Bounding Volume Hierarchies": queries between compound bodies (``distance``, ``collide``,
    ``signed_distance``, the batches, scenes) open only the part pairs whose volumes' certified lower
    bounds cannot rule them out, and name the parts that realise the answer. Answers are certified
    for the union of the convex parts. ``CompoundBody.from_mesh`` builds one from a triangle mesh by
    convex decomposition.
    
    Parameters
    ----------
    parts : sequence of ConvexPolyhedron or array_like of shape (n, 3)
        At least one convex part (or the points whose hull it is).
    poses : array_like of shape (len(parts), 4, 4), optional
        Where each part sits in the body's frame (as ``Scene`` takes poses: also ``(n, 3, 4)``, a
        pair ``(rotations, translations)`` or a list of poses such as ``(Rotation, translation)``
        pairs): part ``i``'s points ``x`` are at ``R_i x + t_i``. None
        (default): every part is given in the body's frame. A curved part (Cylinder, Cone, Ellipsoid)
        keeps its exact support function under its pose; a polyhedron's points are moved.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> cube = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> ell = sc.CompoundBody([cube, [[x + 1, y, z] for x, y, z in cube],
    ...                        [[x, y + 1, z] for x, y, z in cube]])
    >>> ell
    CompoundBody(3 parts, 24 points, bounds [0, 0, 0] to [2, 2, 1])
    >>> r = sc.distance(ell, [[x + 1.6, y + 1.5, z] for x, y, z in cube])
    >>> round(r.distance, 9), r.part_a, r.certified  # the corner of the L is empty
    (0.5, 1, True)
    >>> import numpy as np
    >>> lying = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 2], [0, 0, 0, 1]])  # axis along y
    >>> bar = sc.CompoundBody([sc.Box([1, 1, 0.1]), sc.Cylinder(0.1, 1)], poses=[np.eye(4), lying])
    >>> r = sc.distance(bar, sc.Sphere(0.5), pose_b=(np.eye(3), [0, 0, 3]))
    >>> round(r.distance, 9), r.part_a, r.certified  # the cylinder's side: 3 - 2 - 0.1 - 0.5
    (0.4, 1, True)
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, parts: typing.Any, *, poses: typing.Any = None) -> None:
        ...
    def __len__(self) -> int:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    def aabb(self) -> Aabb:
        """
        Smallest axis-aligned box containing the body.
        """
    @property
    def bounding_radius(self) -> float:
        """
        Half the diagonal of the bounding box (as ConvexPolyhedron.bounding_radius).
        """
    @property
    def envelope(self) -> ConvexPolyhedron:
        """
        The convex hull of every part's points (a ConvexPolyhedron holding the body).
        """
    @property
    def given_parts(self) -> list[ConvexPolyhedron]:
        """
        The parts as given, each in its own frame (``parts`` for a body built without poses).
        """
    @property
    def node_envelopes(self) -> list[ConvexPolyhedron]:
        """
        The convex hull of the parts below each node of ``tree``.
        """
    @property
    def part_poses(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        Where each part sits in the body's frame: a (len(parts), 4, 4) array of homogeneous transforms (identities without poses).
        """
    @property
    def parts(self) -> list[ConvexPolyhedron]:
        """
        The convex parts in the body's frame, placed by their poses (copies that share the parts' hulls; a curved part as its own Cylinder, Cone or Ellipsoid, or, placed by a pose, as a ConvexPolyhedron with its support function).
        """
    @property
    def point_count(self) -> int:
        """
        Total number of points of the parts.
        """
    @property
    def radius(self) -> float:
        """
        Half the diagonal of the bounding box.
        """
    @property
    def tree(self) -> list[PartNode]:
        """
        The bounding-volume tree: a list of PartNode, the root first.
        """
class CompoundResult(DistanceResult):
    """
    
    The answer of a query between compound bodies: a DistanceResult for the union of the convex parts,
    with the pair of parts that realises it.
    
    ``lower_bound <= true value <= distance`` holds for the union of the parts (certified for the
    parts, not for the mesh they approximate). The witnesses lie on parts ``part_a`` and ``part_b``;
    ``weights_a`` and ``weights_b`` are over those parts' points. For signed distances the value is
    the smallest signed distance over part pairs: minus the deepest part-pair penetration, which is
    not in general the penetration depth of the non-convex union.
    """
    def __getstate__(self) -> tuple[int, tuple, int, int, CompoundStats]:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def part_a(self) -> int:
        """
        Index of A's part that realises the answer.
        """
    @property
    def part_b(self) -> int:
        """
        Index of B's part that realises the answer.
        """
    @property
    def stats(self) -> CompoundStats:
        """
        What the search did (a CompoundStats).
        """
class CompoundStats:
    """
    
    What a query between compound bodies did with their part pairs.
    
    Attributes
    ----------
    part_pairs : int
        Parts of A times parts of B.
    volume_tests : int
        Pairs of tree nodes whose bounding volumes were compared.
    screened : int
        Part pairs settled by the separation along their centres' line, with no solver.
    solved : int
        Part pairs handed to the method's solver.
    pruned : int
        Part pairs never looked at: ruled out by the tree's certified lower bounds.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def part_pairs(self) -> int:
        ...
    @property
    def pruned(self) -> int:
        ...
    @property
    def screened(self) -> int:
        ...
    @property
    def solved(self) -> int:
        ...
    @property
    def volume_tests(self) -> int:
        ...
class Cone(ConvexPolyhedron):
    """
    
    A solid right circular cone along the z axis of its frame, centred on its axis' midpoint (FCL's
    and coal's convention): its base, a disk of radius ``radius``, at ``z = -half_length``, its apex
    at ``(0, 0, half_length)``; its centre of mass is at ``z = -half_length / 2``.
    
    A curved shape, defined by its support function: methods ``'dual'`` (the default) and ``'exact'`` answer it, exactly to their tolerance and certified, against any other body; ``'fcl'`` runs FCL's GJK on FCL's own primitive and ``'libccd'`` libccd on its support function, both checked by the certificate as for polyhedra; the methods that read a body's points (``'ipso'``, ``'pso'``, ``'penalty'``) raise ValueError. Its ``vertices`` are a few points on its surface (an inner polytope with the shape's bounding box), not the body; results carry no weights (empty), and witnesses are points of the shape.
    
    Parameters
    ----------
    radius : float
        The radius of the base disk, finite and ``> 0``.
    half_length : float
        Half the cone's height, finite and ``> 0``.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> cone = sc.Cone(1.0, 1.0)
    >>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> round(sc.distance(cone, sc.Sphere(0.5), pose_b=(identity, [0, 0, 3])).distance, 9)
    1.5
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, radius: typing.SupportsFloat | typing.SupportsIndex, half_length: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def half_length(self) -> float:
        """
        Half the cone's height.
        """
    @property
    def radius(self) -> float:
        """
        The radius of the base disk (a cone is not rounded: its rounding radius is 0).
        """
class ContactResult(SceneResult):
    """
    
    The contacts of every pair in contact: a SceneResult whose ``distance`` is the certified signed
    distance (negative: the penetration depth) and ``normal`` the contact normal from A to B, with
    each pair's contact points.
    
    Attributes
    ----------
    counts : numpy.ndarray of int, shape (m,)
        Contact points of each pair (1 to ``max_points``).
    points : numpy.ndarray, shape (p, 3)
        All contact points, pair by pair, halfway between the two supporting planes.
    point_pair : numpy.ndarray of int64, shape (p,)
        Row in ``pairs`` of each contact point.
    offsets : numpy.ndarray of int64, shape (m,)
        Index in ``points`` of each pair's first contact point.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def counts(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def offsets(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int64], "[m, 1]"]:
        ...
    @property
    def point_pair(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int64], "[m, 1]"]:
        ...
    @property
    def points(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
class ConvexPolyhedron:
    """
    
    A convex polyhedron: the convex hull of a finite set of points (the paper's Definition 3),
    rounded by ``radius``: the set of points within ``radius`` of that hull (a sphere is one point
    rounded, a capsule a segment; see ``Sphere``, ``Capsule`` and ``Box``).
    
    Queries answer rounded bodies on their cores (the points' hull) and subtract the radii: the signed distance of two rounded convex bodies is exactly that of their cores less both radii, so bounds, certificates and verdicts keep their meaning, relative to the size of the rounded bodies. Methods ``'ipso'``, ``'pso'`` and ``'penalty'`` (model (2)) weigh the core's points; ``'fcl'`` and ``'libccd'`` also answer on the cores (not on FCL's own sphere and capsule primitives). Support points, hulls, centroids and weights are the core's.
    
    Parameters
    ----------
    points : array_like, shape (n, 3)
        At least one finite point. The points are kept as given: they are the vertices ``x_i`` of
        model (2). Flat, collinear and single-point sets are valid bodies. A ConvexPolyhedron is
        taken as it is (with its radius unless ``radius`` is given).
    radius : float, optional
        The rounding radius, finite and ``>= 0``; 0 (the default) for a plain polyhedron.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> tetra = sc.ConvexPolyhedron([[0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 0, 0]])
    >>> tetra.support([1, 0, 0]).tolist()
    [1.0, 0.0, 0.0]
    >>> tetra.hull().dimension
    3
    >>> sc.distance(sc.ConvexPolyhedron([[0, 0, 0]], radius=1), [[3, 0, 0]]).distance
    2.0
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, points: typing.Any, radius: typing.SupportsFloat | typing.SupportsIndex | None = None) -> None:
        ...
    def __len__(self) -> int:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    def aabb(self) -> Aabb:
        """
        Smallest axis-aligned box containing the body (its rounding included).
        """
    def centroid(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Centre of mass of the solid (of the polygon, segment or point for lower-dimensional bodies).
        """
    def hull(self) -> Hull:
        """
        Convex hull through Qhull (an exact planar hull for flat bodies).
        """
    def support(self, direction: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        A point of the body farthest along ``direction`` (3 real numbers).
        """
    def support_index(self, direction: typing.Any) -> int:
        """
        Index of the point farthest along ``direction`` (first on ties); ValueError for a curved shape, whose support points are not among its vertices.
        """
    @property
    def bounding_radius(self) -> float:
        """
        Half the diagonal of the points' bounding box plus the rounding radius: every point of the body lies within it of the box's centre.
        """
    @property
    def curved(self) -> bool:
        """
        True for a curved shape (Cylinder, Cone, Ellipsoid), defined by its support function rather than by the hull of its vertices.
        """
    @property
    def radius(self) -> float:
        """
        The rounding radius (0 for a plain polyhedron).
        """
    @property
    def rounding_radius(self) -> float:
        """
        The rounding radius of every kind of body: a ConvexPolyhedron's or Box's ``radius``, a Sphere's or Capsule's radius, 0 for a Cylinder, Cone or Ellipsoid, whose ``radius`` (where they have one) is their own dimension. Code that handles any body reads this.
        """
    @property
    def vertices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        The ``(n, 3)`` points the body was built from (read-only).
        """
class Cylinder(ConvexPolyhedron):
    """
    
    A solid circular cylinder along the z axis of its frame, centred on its origin: radius
    ``radius``, from ``z = -half_length`` to ``z = half_length`` (FCL's and coal's convention; URDF's
    ``<cylinder radius length>`` has ``length = 2 half_length``; MJCF's cylinder geom has size =
    (radius, half_length)).
    
    A curved shape, defined by its support function: methods ``'dual'`` (the default) and ``'exact'`` answer it, exactly to their tolerance and certified, against any other body; ``'fcl'`` runs FCL's GJK on FCL's own primitive and ``'libccd'`` libccd on its support function, both checked by the certificate as for polyhedra; the methods that read a body's points (``'ipso'``, ``'pso'``, ``'penalty'``) raise ValueError. Its ``vertices`` are a few points on its surface (an inner polytope with the shape's bounding box), not the body; results carry no weights (empty), and witnesses are points of the shape.
    
    Parameters
    ----------
    radius : float
        The radius of the circular section, finite and ``> 0``.
    half_length : float
        Half the cylinder's length along z, finite and ``> 0``.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> can = sc.Cylinder(0.5, 1.0)
    >>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> round(sc.distance(can, sc.Sphere(0.25), pose_b=(identity, [2, 0, 0])).distance, 9)
    1.25
    >>> round(sc.signed_distance(can, can, pose_b=(identity, [0, 0, 1.5])).distance, 9)
    -0.5
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, radius: typing.SupportsFloat | typing.SupportsIndex, half_length: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def half_length(self) -> float:
        """
        Half the cylinder's length along z.
        """
    @property
    def radius(self) -> float:
        """
        The radius of the circular section (a cylinder is not rounded: its rounding radius is 0).
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
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
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
class Ellipsoid(ConvexPolyhedron):
    """
    
    A solid ellipsoid centred on the origin of its frame with semi-axes ``radii`` along x, y and z:
    the points with ``(x/a)^2 + (y/b)^2 + (z/c)^2 <= 1`` (MJCF's ellipsoid geom, size = radii).
    
    A curved shape, defined by its support function: methods ``'dual'`` (the default) and ``'exact'`` answer it, exactly to their tolerance and certified, against any other body; ``'fcl'`` runs FCL's GJK on FCL's own primitive and ``'libccd'`` libccd on its support function, both checked by the certificate as for polyhedra; the methods that read a body's points (``'ipso'``, ``'pso'``, ``'penalty'``) raise ValueError. Its ``vertices`` are a few points on its surface (an inner polytope with the shape's bounding box), not the body; results carry no weights (empty), and witnesses are points of the shape.
    
    Parameters
    ----------
    radii : array_like, shape (3,)
        The semi-axes along x, y and z, each finite and ``> 0``.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> egg = sc.Ellipsoid([1, 2, 3])
    >>> identity = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> round(sc.distance(egg, sc.Sphere(1), pose_b=(identity, [0, 0, 5])).distance, 9)
    1.0
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, radii: typing.Any) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def radii(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The semi-axes along x, y and z.
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
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
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
class Joint:
    """
    
    A joint of a RobotModel: the child link's frame is ``parent * origin * motion(q - reference)``.
    
    Parameters
    ----------
    name : str
    type : str
        'revolute', 'continuous', 'prismatic' or 'fixed'.
    parent, child : int
        Link indices.
    origin : pose
        The joint frame in the parent link's frame (a (4, 4) rigid transform).
    axis : (3,) array
        In the joint frame; normalised by the model.
    lower, upper : float
        Limits (ignored for continuous and fixed joints).
    reference : float
        The value at which the child sits at ``origin`` (MJCF's ``ref``).
    mimic : int
        The index of the joint this one mimics (-1: none); its value is then ``multiplier *
        value(mimicked) + offset`` and it is no degree of freedom.
    multiplier, offset : float
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, name: str, type: str, parent: typing.SupportsInt | typing.SupportsIndex, child: typing.SupportsInt | typing.SupportsIndex, origin: typing.Any = None, axis: typing.Any = ..., lower: typing.SupportsFloat | typing.SupportsIndex = 0.0, upper: typing.SupportsFloat | typing.SupportsIndex = 0.0, reference: typing.SupportsFloat | typing.SupportsIndex = 0.0, mimic: typing.SupportsInt | typing.SupportsIndex = -1, multiplier: typing.SupportsFloat | typing.SupportsIndex = 1.0, offset: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def axis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def child(self) -> int:
        ...
    @property
    def lower(self) -> float:
        ...
    @property
    def mimic(self) -> int:
        ...
    @property
    def multiplier(self) -> float:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def offset(self) -> float:
        ...
    @property
    def parent(self) -> int:
        ...
    @property
    def reference(self) -> float:
        ...
    @property
    def type(self) -> str:
        ...
    @property
    def upper(self) -> float:
        ...
class PartNode:
    """
    
    A node of a compound body's bounding-volume tree, in the body's own frame.
    
    Attributes
    ----------
    box : Aabb
        The smallest axis-aligned box holding the parts below the node.
    centre, radius : numpy.ndarray, float
        A ball holding the parts below the node.
    left, right : int
        Indices of the children in ``CompoundBody.tree``; -1 for a leaf.
    part : int
        The part a leaf holds; -1 for an inner node.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def box(self) -> Aabb:
        ...
    @property
    def centre(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def leaf(self) -> bool:
        ...
    @property
    def left(self) -> int:
        ...
    @property
    def part(self) -> int:
        ...
    @property
    def radius(self) -> float:
        ...
    @property
    def right(self) -> int:
        ...
class ParticleCoefficients:
    """
    Inertia weight ``w`` and accelerations ``c1``, ``c2`` of one particle.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
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
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, method: typing.Any = 'dual', tolerance: typing.Any = 1e-09, seed: typing.Any = 0, **kwargs) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    def collide(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None, escalate: bool = True) -> bool:
        ...
    def collide_many(self, As: typing.Any, Bs: typing.Any, threads: typing.Any = None, first_index: typing.Any = 0, escalate: bool = True, poses_a: typing.Any = None, poses_b: typing.Any = None) -> BatchResult:
        """
        The query for every row ``(As[i], Bs[i])``, in C++ threads without the GIL.
        
        Row i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
        number of threads or on how a batch is split. ``As`` and ``Bs`` are each a single body used in
        every row (a ConvexPolyhedron, a CompoundBody or an ``(n, 3)`` NumPy array, never copied, or a
        mesh such as a ``trimesh.Trimesh``: its vertices' hull), a sequence of bodies (polyhedra,
        compound bodies or ``(n, 3)`` arrays), or an ``(m, n, 3)`` array (each row's bodies then built
        and freed by the thread that answers it). ``poses_a`` and ``poses_b`` place them: None (the
        identity), an ``(m, 4, 4)`` or ``(m, 3, 4)`` array of rigid transforms, a pair
        ``(rotations (m, 3, 3), translations (m, 3))`` or a list of m poses (each as ``distance`` takes
        it); a single pose serves every row, as a single body does. With a single body on both sides the
        poses set the number of rows: "A against B at these m poses" is one call.
        """
    def collision(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None, escalate: bool = True) -> DistanceResult:
        ...
    def distance(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None) -> DistanceResult:
        ...
    def distance_many(self, As: typing.Any, Bs: typing.Any, threads: typing.Any = None, first_index: typing.Any = 0, poses_a: typing.Any = None, poses_b: typing.Any = None) -> BatchResult:
        """
        The query for every row ``(As[i], Bs[i])``, in C++ threads without the GIL.
        
        Row i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
        number of threads or on how a batch is split. ``As`` and ``Bs`` are each a single body used in
        every row (a ConvexPolyhedron, a CompoundBody or an ``(n, 3)`` NumPy array, never copied, or a
        mesh such as a ``trimesh.Trimesh``: its vertices' hull), a sequence of bodies (polyhedra,
        compound bodies or ``(n, 3)`` arrays), or an ``(m, n, 3)`` array (each row's bodies then built
        and freed by the thread that answers it). ``poses_a`` and ``poses_b`` place them: None (the
        identity), an ``(m, 4, 4)`` or ``(m, 3, 4)`` array of rigid transforms, a pair
        ``(rotations (m, 3, 3), translations (m, 3))`` or a list of m poses (each as ``distance`` takes
        it); a single pose serves every row, as a single body does. With a single body on both sides the
        poses set the number of rows: "A against B at these m poses" is one call.
        """
    def signed_distance(self, a: typing.Any, b: typing.Any, pose_a: typing.Any = None, pose_b: typing.Any = None) -> DistanceResult:
        ...
    def signed_distance_many(self, As: typing.Any, Bs: typing.Any, threads: typing.Any = None, first_index: typing.Any = 0, poses_a: typing.Any = None, poses_b: typing.Any = None) -> BatchResult:
        """
        The query for every row ``(As[i], Bs[i])``, in C++ threads without the GIL.
        
        Row i is seeded with ``pair_seed(seed, first_index + i)``, so answers do not depend on the
        number of threads or on how a batch is split. ``As`` and ``Bs`` are each a single body used in
        every row (a ConvexPolyhedron, a CompoundBody or an ``(n, 3)`` NumPy array, never copied, or a
        mesh such as a ``trimesh.Trimesh``: its vertices' hull), a sequence of bodies (polyhedra,
        compound bodies or ``(n, 3)`` arrays), or an ``(m, n, 3)`` array (each row's bodies then built
        and freed by the thread that answers it). ``poses_a`` and ``poses_b`` place them: None (the
        identity), an ``(m, 4, 4)`` or ``(m, 3, 4)`` array of rigid transforms, a pair
        ``(rotations (m, 3, 3), translations (m, 3))`` or a list of m poses (each as ``distance`` takes
        it); a single pose serves every row, as a single body does. With a single body on both sides the
        poses set the number of rows: "A against B at these m poses" is one call.
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
class RobotCheck:
    """
    Per configuration: the verdict and the nearest pair.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    def row(self, i: typing.SupportsInt | typing.SupportsIndex) -> tuple[bool, float, float, bool, int, numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], typing.Any]:
        """
        Configuration i's (colliding, min_distance, lower_bound, certified, pair, point_a, point_b, normal, gradient or None), as Python values and (3,) or (dof,) arrays: cheaper than reading every field's array to index it, for a check of one configuration.
        """
    @property
    def certified(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def colliding(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def gradient(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def lower_bound(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def min_distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def pair(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
class RobotChecker:
    """
    
    A check of one configuration at a time with the pairs and options validated once (Robot.checker
    wraps it): its buffers are kept from one call to the next. Keeps its model alive. Threads may
    share it (the GIL is released while it checks): a call that finds its buffers busy uses its own.
    
    Parameters
    ----------
    model : RobotModel
    pairs : int array, (pairs, 2)
        Geometry index pairs, as RobotModel.check takes them.
    query : Query
        The pair queries' method and options.
    nearest, gradient : bool
        As RobotModel.check.
    """
    def __init__(self, model: RobotModel, pairs: typing.Annotated[numpy.typing.ArrayLike, numpy.int32, "[m, 2]"], query: Query, nearest: bool = True, gradient: bool = False) -> None:
        ...
    def check(self, q: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[1, n]"], limits: typing.Any = 'raise') -> tuple[bool, float, float, bool, int, numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], typing.Any]:
        """
        The configuration q (dof,) admitted ('raise', 'clamp' or 'wrap') and checked, answered as RobotCheck.row answers a row: (colliding, min_distance, lower_bound, certified, pair, point_a, point_b, normal, gradient or None).
        """
    def collision_free(self, q: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[1, n]"], limits: typing.Any = 'raise') -> bool:
        """
        True when q (dof,) is proven free of contact: no pair collides and the verdict is certified.
        """
    @property
    def gradient(self) -> bool:
        ...
    @property
    def nearest(self) -> bool:
        ...
    @property
    def pair_count(self) -> int:
        ...
class RobotDistances:
    """
    Signed distances of every checked pair, (m, pairs) each.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def certified(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, n]"]:
        ...
    @property
    def colliding(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, n]"]:
        ...
    @property
    def distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def lower_bound(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
class RobotModel:
    """
    
    A robot as a plain table of links, joints and geometries: immutable, shared by every thread.
    
    Parameters
    ----------
    links : list of str
        The link names; joints and geometries refer to links by index.
    joints : list of Joint
        Every link but one (the root) is the child of exactly one joint. The moving joints are the
        degrees of freedom, in the order given.
    geometries : list of (name, link, origin, body)
        A ConvexPolyhedron or CompoundBody fixed to link ``link`` at ``origin`` (a rigid transform),
        or to the world for ``link == -1`` (an obstacle).
    
    Raises
    ------
    ValueError
        Naming the joint, link or geometry at fault.
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, links: collections.abc.Sequence[str], joints: collections.abc.Sequence[Joint], geometries: collections.abc.Sequence[tuple]) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    def adjacent_links(self, a: typing.SupportsInt | typing.SupportsIndex, b: typing.SupportsInt | typing.SupportsIndex) -> bool:
        """
        True when links ``a`` and ``b`` are one rigid group or joined by one moving joint.
        """
    def admit(self, q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], limits: typing.Any = 'raise', single: bool = False) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        The configurations (m, dof) checked and brought within the limits ('raise', 'clamp' or 'wrap'); ``single``: q's one row is a configuration given alone, whose messages name its values (q[j]) rather than its row.
        """
    def check(self, pairs: typing.Annotated[numpy.typing.ArrayLike, numpy.int32, "[m, 2]"], q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], query: Query, threads: typing.Any = None, gradient: bool = False, nearest: bool = True) -> RobotCheck:
        """
        The nearest pair per admitted configuration (m, dof), with d min_distance / dq when ``gradient``; without ``nearest``, the verdict alone.
        """
    def check_motion(self, pairs: typing.Annotated[numpy.typing.ArrayLike, numpy.int32, "[m, 2]"], q0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], q1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], query: Query, time_tolerance: typing.SupportsFloat | typing.SupportsIndex = 1e-06, max_iterations: typing.SupportsInt | typing.SupportsIndex = 100000, threads: typing.Any = None) -> RobotMotionCheck:
        """
        The first contact of each straight joint-space motion from admitted q0 to q1 rows (m, dof; one row of either serves every motion), or a proof that there is none.
        """
    def default_pairs(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 2]"]:
        """
        The geometry pairs checked by default, (pairs, 2): geometries of links that are not adjacent, and each obstacle against each link's geometry.
        """
    def distances(self, pairs: typing.Annotated[numpy.typing.ArrayLike, numpy.int32, "[m, 2]"], q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], query: Query, threads: typing.Any = None) -> RobotDistances:
        """
        Signed distances of geometry pairs (pairs, 2) at admitted configurations (m, dof).
        """
    def forward_kinematics(self, q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"]) -> numpy.typing.NDArray[numpy.float64]:
        """
        Every link's (4, 4) world transform at admitted configurations, (m, links, 4, 4).
        """
    def geometry_poses(self, q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"]) -> numpy.typing.NDArray[numpy.float64]:
        """
        Every geometry's (4, 4) world transform at admitted configurations, (m, geometries, 4, 4).
        """
    @property
    def dof(self) -> int:
        ...
    @property
    def geometry_links(self) -> list[int]:
        ...
    @property
    def joints(self) -> list[Joint]:
        ...
    @property
    def link_names(self) -> list[str]:
        ...
    @property
    def moving_joints(self) -> list[int]:
        ...
class RobotMotionCheck:
    """
    Per motion: free, or the first contact bracketed (see Robot.check_motion).
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    def row(self, i: typing.SupportsInt | typing.SupportsIndex) -> tuple[bool, float, float, numpy.typing.NDArray[numpy.float64], int, float, numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], bool, int, str]:
        """
        Motion i's (touches, t_lower, t_upper, configuration, pair, distance, point_a, point_b, normal, certified, iterations, status), as Python values and arrays.
        """
    @property
    def certified(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def configuration(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def iterations(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def pair(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def status(self) -> list[str]:
        """
        Per motion: 'converged', 'max_iterations' or 'unresolved'.
        """
    @property
    def t_lower(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def t_upper(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def touches(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
class Scene:
    """
    
    Many convex bodies, each defined once in its own frame and placed by a pose, and the queries
    about all their pairs.
    
    FCL's broadphase manager, given tight boxes from the bodies' support functions, collects the
    candidate pairs; the narrowphase (``method``, certified as ``Query.collision`` is) answers them
    in C++ threads without the GIL. With ``warm_start``, each candidate pair keeps what the last
    query proved (a separating direction and its support points in the bodies' own frames, or a
    simplex enclosing the origin) and the next query tries it first; a pair's proof is dropped when
    the broadphase stops returning it. Without, every answer is computed from scratch and depends only
    on the bodies, their poses and ``seed``.
    
    Parameters
    ----------
    method : str
        The narrowphase's method (see ``METHODS``); ``"dual"`` by default.
    broadphase : str
        FCL's manager: ``"dynamic_aabb_tree"`` (default), ``"sap"``, ``"ssap"``,
        ``"interval_tree"``, ``"spatial_hashing"`` or ``"brute_force"`` (``BROADPHASES``). Answers do
        not depend on it.
    threads : int, optional
        Narrowphase threads, the caller's included; None uses one per hardware thread. The others
        are woken once a query's candidates left would take the caller over about 200 us alone.
    tolerance : float
        Precision and contact threshold, relative to each pair's size (at most 0.1).
    seed : int
        Pair ``(i, j)`` is seeded with ``pair_seed(seed, (i << 32) | j)``.
    warm_start : bool
        Start each query from what the last one proved.
    escalate : bool
        Hand verdicts the method cannot prove to the exact method.
    **parameters
        Solver parameters of ``method``.
    
    Examples
    --------
    >>> import numpy as np, swarmcollide as sc
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> scene = sc.Scene()
    >>> scene.add(np.stack([cube, cube, cube]), poses=np.stack([np.eye(4)] * 3)).tolist()
    [0, 1, 2]
    >>> moved = np.eye(4)
    >>> moved[:3, 3] = [0.5, 0, 0]
    >>> scene.set_poses(1, moved)
    >>> moved[:3, 3] = [3, 0, 0]
    >>> scene.set_poses(2, moved)
    >>> scene.colliding_pairs().pairs.tolist()
    [[0, 1]]
    >>> r = scene.pairs_within(1.6)
    >>> r.pairs.tolist(), r.distance.round(9).tolist()
    ([[0, 1], [1, 2]], [0.0, 1.5])
    >>> c = scene.contacts()
    >>> c.normal.round(9).tolist(), c.counts.tolist()
    ([[1.0, 0.0, 0.0]], [4])
    """
    def __contains__(self, arg0: typing.Any) -> bool:
        ...
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, method: typing.Any = 'dual', broadphase: typing.Any = 'dynamic_aabb_tree', threads: typing.Any = None, tolerance: typing.Any = 1e-09, seed: typing.Any = 0, warm_start: bool = True, escalate: bool = True, **kwargs) -> None:
        ...
    def __len__(self) -> int:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    def add(self, bodies: typing.Any, poses: typing.Any = None, group: typing.Any = 1, mask: typing.Any = 4294967295) -> numpy.typing.NDArray[numpy.int64]:
        """
        Add one body (a ConvexPolyhedron, ``(n, 3)`` points or a CompoundBody) or many (a sequence of
        them or an ``(m, n, 3)`` array) at ``poses``; return their ids (never reused).
        
        A compound body is boxed and first screened by its envelope (the hull of its parts); pairs the
        envelopes do not settle are answered by the compound queries (branch and bound over the parts,
        certified for them), and its contacts are found between the deepest pair of parts.
        
        ``poses`` is None (the identity), an ``(m, 4, 4)`` array of rigid transforms, a pair
        ``(rotations (m, 3, 3), translations (m, 3))`` or a list of m poses (each as ``distance`` takes
        it); one body also takes a single ``(4, 4)`` transform.
        Bodies A and B are paired when ``A.group & B.mask`` and ``B.group & A.mask`` are both nonzero.
        """
    def body(self, id: typing.SupportsInt | typing.SupportsIndex) -> typing.Any:
        """
        The body with this id (an integer or the array of one id ``add`` returns for one body), in its own frame: a ConvexPolyhedron (a Sphere, Capsule, Box, Cylinder, Cone or Ellipsoid as its own class) or a CompoundBody (the core's, without a decomposition record).
        """
    def colliding_pairs(self) -> SceneResult:
        """
        Every pair in contact (within the tolerance of each other), certified.
        """
    def contacts(self, max_points: typing.Any = 4) -> ContactResult:
        """
        Every pair in contact with its certified signed distance, contact normal (from A to B) and up to
        ``max_points`` contact points, from clipping the two supporting features along the normal
        against each other: a box resting on a face gives its four corners.
        """
    def exclude(self, pairs: typing.Any) -> None:
        """
        Never pair the bodies of each pair (one pair or an (m, 2) array).
        """
    def include(self, pairs: typing.Any) -> None:
        """
        Pair again the bodies of excluded pairs.
        """
    def min_distance(self) -> SceneResult:
        """
        The pair at the smallest distance (one row; none for fewer than two pairable bodies).
        """
    def nearest(self, ids: typing.Any, k: typing.Any = 1) -> SceneResult:
        """
        For each of ``ids``, its ``k`` nearest bodies, nearest first: rows ``(id, other)``.
        """
    def pairs_within(self, distance: typing.Any) -> SceneResult:
        """
        Every pair whose distance is at most ``distance`` (up to the tolerance), with its distance to the tolerance.
        """
    def pose(self, id: typing.SupportsInt | typing.SupportsIndex) -> numpy.typing.NDArray[numpy.float64]:
        """
        The body's pose as a (4, 4) homogeneous transform; ``id`` an integer or the array of one id ``add`` returns for one body.
        """
    def remove(self, ids: typing.Any) -> None:
        """
        Remove bodies, with every cached proof and exclusion concerning them.
        """
    def set_filter(self, ids: typing.Any, group: typing.Any = 1, mask: typing.Any = 4294967295) -> None:
        """
        Set the group and mask of bodies (see ``add``).
        """
    def set_poses(self, ids: typing.Any, poses: typing.Any) -> None:
        """
        Move bodies (one id or an array of ids, each at most once) to ``poses`` (as for ``add``); their hulls are never recomputed.
        """
    def sweep(self, ids: typing.Any, poses: typing.Any, *, motion: typing.Any = 'linear', time_tolerance: typing.Any = 1e-06, max_iterations: typing.Any = 100000) -> SweepResult:
        """
        Move bodies from their poses to ``poses``, reporting every pair that touches on the way.
        
        Parameters
        ----------
        ids : int or array_like of int
            The bodies that move; the others stay still.
        poses : array_like
            Their end poses, as ``set_poses`` takes them.
        motion : str
            ``"linear"`` (default): each origin moves on the straight segment while the body turns at a
            constant rate about a fixed axis through it; ``"screw"``: the pose follows
            ``G(t) = G0 exp(t xi)``, xi the twist of ``G0^-1 G1`` (see ``time_of_impact``).
        time_tolerance : float
            Largest width of a first contact's bracket, as a fraction of the motion, in (0, 1].
        max_iterations : int
            Distance queries at most per pair; past them the pair is reported uncertified.
        
        Returns
        -------
        SweepResult
            Every pair with at least one moving body that comes within the tolerance of each other
            during the motion, with its first contact bracketed (``time_of_impact`` on the pair, seeded
            as the scene seeds its queries). Candidates are the pairs the scene's filters and exclusions
            allow whose swept boxes (proven to hold each body over its whole motion) overlap. Pairs of
            two still bodies are not reported: ``colliding_pairs`` answers them.
        
        The bodies are left at ``poses`` whatever is found (``set_poses`` puts them back at the poses a
        row gives). Raises ValueError, moving nothing, for an unknown or repeated id, a pose that is not
        rigid or holds a NaN, lengths that differ, a ``time_tolerance`` outside (0, 1] or a method without
        signed distances.
        
        Examples
        --------
        >>> import numpy as np, swarmcollide as sc
        >>> scene = sc.Scene(method="exact")
        >>> cube, plate = scene.add([sc.Box([0.5, 0.5, 0.5]), sc.Box([5e-4, 5, 5])])
        >>> start, end = np.eye(4), np.eye(4)
        >>> start[0, 3], end[0, 3] = -10, 10
        >>> scene.set_poses(cube, start)
        >>> r = scene.sweep(cube, end)               # through the plate in one step
        >>> r.pairs.tolist(), r.certified.tolist(), (r.t_upper * 20 - 10).round(6).tolist()
        ([[0, 1]], [True], [-0.5005])
        >>> float(scene.pose(cube)[0, 3])
        10.0
        """
    @property
    def broadphase(self) -> str:
        ...
    @property
    def ids(self) -> numpy.typing.NDArray[numpy.int64]:
        """
        The bodies' ids, ascending.
        """
    @property
    def method(self) -> str:
        ...
    @property
    def seed(self) -> int:
        ...
    @property
    def stats(self) -> SceneStats:
        """
        What the last query did (a SceneStats).
        """
    @property
    def tolerance(self) -> float:
        ...
    @property
    def warm_start(self) -> bool:
        ...
class SceneResult:
    """
    
    Pairs a Scene query found, one row per pair, as NumPy arrays.
    
    Row k is the pair ``(A, B) = pairs[k]``; vectors point from A to B, and
    ``lower_bound[k] <= distance between A and B <= distance[k]``.
    
    Attributes
    ----------
    pairs : numpy.ndarray of int64, shape (m, 2)
        Ids of A and B.
    distance, lower_bound : numpy.ndarray, shape (m,)
        Upper bound (achieved by the witnesses) and certified lower bound on the distance.
    point_a, point_b : numpy.ndarray, shape (m, 3)
        Witness points on A and B.
    normal : numpy.ndarray, shape (m, 3)
        Unit direction from A to B certifying ``lower_bound`` (zero where overlap was proven by a
        common point; ``contacts`` gives those their contact normals).
    certified : numpy.ndarray of bool, shape (m,)
        The pair's membership (and value, for distances and contacts) is proven.
    """
    def __getstate__(self) -> tuple:
        ...
    def __len__(self) -> int:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def certified(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def lower_bound(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def pairs(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int64], "[m, 2]"]:
        ...
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
class SceneStats:
    """
    
    What the last Scene query did with its candidate pairs.
    
    Attributes
    ----------
    candidates : int
        Pairs that passed the filters whose boxes, padded for the query, overlap.
    screened : int
        Found apart along the line between their centres, before any solver.
    warm_bounded : int
        Found apart by a cached lower bound on their distance less how far the bodies have moved
        since: no support evaluated.
    warm_rejected, warm_proven : int
        Settled by re-evaluating a cached separating direction or enclosing simplex (or one that
        Wolfe's algorithm found from it in a step or two).
    solved : int
        Handed to the method's solver.
    escalations : int
        Verdicts the method could not prove, handed to the exact method.
    certified : int
        Candidates whose answer is proven.
    cached_pairs, cache_bytes : int
        Pairs with a cached proof after the query, and the bytes their storage takes: a 64-byte
        record for every pair whose broadphase boxes (padded boxes with margins for motion)
        overlap, and for a pair in contact the last expanding polytope's surface (at most 16
        corners). cache_bytes is summed when ``scene.stats`` is read (the storage then), not by
        every query: the sum reads every pair's record.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def cache_bytes(self) -> int:
        ...
    @property
    def cached_pairs(self) -> int:
        ...
    @property
    def candidates(self) -> int:
        ...
    @property
    def certified(self) -> int:
        ...
    @property
    def escalations(self) -> int:
        ...
    @property
    def screened(self) -> int:
        ...
    @property
    def solved(self) -> int:
        ...
    @property
    def warm_bounded(self) -> int:
        ...
    @property
    def warm_proven(self) -> int:
        ...
    @property
    def warm_rejected(self) -> int:
        ...
class Sphere(ConvexPolyhedron):
    """
    
    A ball of radius ``radius`` centred on the origin of its frame (URDF's ``<sphere radius>``;
    MJCF's sphere geom, size = radius): the one point ``(0, 0, 0)`` rounded by ``radius``.
    
    Queries answer rounded bodies on their cores (the points' hull) and subtract the radii: the signed distance of two rounded convex bodies is exactly that of their cores less both radii, so bounds, certificates and verdicts keep their meaning, relative to the size of the rounded bodies. Methods ``'ipso'``, ``'pso'`` and ``'penalty'`` (model (2)) weigh the core's points; ``'fcl'`` and ``'libccd'`` also answer on the cores (not on FCL's own sphere and capsule primitives). Support points, hulls, centroids and weights are the core's.
    
    Parameters
    ----------
    radius : float
        Finite and ``> 0``.
    
    Examples
    --------
    >>> import swarmcollide as sc
    >>> a, b = sc.Sphere(1.0), sc.Sphere(0.5)
    >>> sc.distance(a, b, pose_b=([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [3, 0, 0])).distance
    1.5
    >>> sc.signed_distance(a, b).distance
    -1.5
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, radius: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
class SweepResult:
    """
    
    The pairs that touch during ``Scene.sweep``, one row per pair in increasing id order, as NumPy
    arrays: row k is ``time_of_impact`` of bodies ``(A, B) = pairs[k]`` over the sweep's motions
    (time 0 at the poses before the sweep, 1 at the given ones).
    
    Attributes
    ----------
    pairs : numpy.ndarray of int64, shape (m, 2)
        Ids of A and B, the smaller first.
    t_lower, t_upper : numpy.ndarray, shape (m,)
        The first contact's bracket: the pair is proven apart before ``t_lower`` and within
        ``tolerance x size`` at ``t_upper`` (``t_upper - t_lower <= time_tolerance``).
    pose_a, pose_b : numpy.ndarray, shape (m, 4, 4)
        The bodies' poses at ``t_upper``.
    distance : numpy.ndarray, shape (m,)
        Signed distance at ``t_upper`` (its upper bound).
    point_a, point_b, normal : numpy.ndarray, shape (m, 3)
        Witness points on A and B and the unit contact normal from A to B at ``t_upper``.
    certified : numpy.ndarray of bool, shape (m,)
        The bracket is proven; uncertified rows err on the side of contact.
    iterations : numpy.ndarray of int, shape (m,)
        Distance queries each pair ran.
    """
    def __getstate__(self) -> tuple:
        ...
    def __len__(self) -> int:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def certified(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        ...
    @property
    def distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def iterations(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def pairs(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int64], "[m, 2]"]:
        ...
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def pose_a(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def pose_b(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def t_lower(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def t_upper(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
class TimeOfImpactBatch:
    """
    
    The answers of ``time_of_impact_many``: NumPy arrays with one entry per row (built when read),
    and each row's ``TimeOfImpactResult`` by indexing.
    """
    def __getitem__(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> TimeOfImpactResult:
        ...
    def __getstate__(self) -> tuple[int, list[TimeOfImpactResult]]:
        ...
    def __len__(self) -> int:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def certified(self) -> numpy.typing.NDArray[numpy.bool]:
        ...
    @property
    def distance(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def iterations(self) -> numpy.typing.NDArray[numpy.int32]:
        ...
    @property
    def normal(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def point_a(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def point_b(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def pose_a(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def pose_b(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def t_lower(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def t_upper(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def touches(self) -> numpy.typing.NDArray[numpy.bool]:
        ...
class TimeOfImpactResult:
    """
    
    The first contact of two moving bodies (``time_of_impact``).
    
    When ``certified``: ``touches`` is False only when the bodies are proven never to overlap during
    the motion; when True, they are proven apart before ``t_lower`` and within ``tolerance x size``
    of each other at ``t_upper``, with ``t_upper - t_lower <= time_tolerance``. Uncertified answers
    err on the side of contact: ``t_lower`` is still proven, ``touches`` is True.
    """
    def __getstate__(self) -> tuple:
        ...
    def __reduce_ex__(self, protocol: typing.Any) -> typing.Any:
        """
        Reduction for pickle, as protocol 2's in every protocol (copyreg.__newobj__ and __getstate__).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: typing.Any) -> None:
        ...
    @property
    def certified(self) -> bool:
        """
        True when the answer is proven.
        """
    @property
    def distance(self) -> float:
        """
        Signed distance at ``t_upper`` (NaN for a free motion).
        """
    @property
    def iterations(self) -> int:
        """
        Distance queries run.
        """
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Unit contact normal from A to B at ``t_upper`` (zero for a free motion).
        """
    @property
    def point_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Witness point on A at t_upper.
        """
    @property
    def point_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        Witness point on B at t_upper.
        """
    @property
    def pose_a(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[4, 4]"]:
        """
        A's pose at ``t_upper``, a (4, 4) transform.
        """
    @property
    def pose_b(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[4, 4]"]:
        """
        B's pose at ``t_upper``, a (4, 4) transform.
        """
    @property
    def status(self) -> str:
        """
        'converged', 'max_iterations' or 'unresolved'.
        """
    @property
    def t_lower(self) -> float:
        """
        The bodies are proven apart before this time (1 for a free motion).
        """
    @property
    def t_upper(self) -> float:
        """
        The bodies are proven in contact at this time (1 for a free motion).
        """
    @property
    def touches(self) -> bool:
        """
        True when the bodies come within the tolerance of each other.
        """
def as_polyhedron(body: typing.Any, name: typing.Any = 'body') -> ConvexPolyhedron:
    """
    Return ``body`` as a ConvexPolyhedron, building one from ``(n, 3)`` points if needed.
    
    Errors name the argument as ``name``.
    """
def broadphases() -> list[str]:
    """
    The names of the broadphase managers a Scene can use.
    """
def constraint_violation(weights_a: typing.Any, weights_b: typing.Any) -> float:
    """
    Constraint violation (6): ``(sum(weights_a) - 1)**2 + (sum(weights_b) - 1)**2``.
    """
def is_feasible(weights_a: typing.Any, weights_b: typing.Any, tolerance: typing.SupportsFloat | typing.SupportsIndex = 1e-10) -> bool:
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
def motion_function(python_path: collections.abc.Callable, text_signature: str) -> typing.Any:
    """
    ``python_path``, swarmcollide.motion's ``time_of_impact``, as a C++ function with its name,
    module, documentation and ``text_signature`` (without annotations): it answers calls between two
    ConvexPolyhedron itself, with the conversions of ``_core.time_of_impact``, and hands every other
    call (compound bodies, points, calls that raise) to ``python_path``.
    """
def objective(a: typing.Any, b: typing.Any, weights_a: typing.Any, weights_b: typing.Any) -> float:
    """
    Objective (5): ``|| sum_j weights_b[j] y_j - sum_i weights_a[i] x_i ||``.
    
    The weights need not be feasible; see ``constraint_violation`` and ``is_feasible``.
    """
def pair_seed(seed: typing.SupportsInt | typing.SupportsIndex, index: typing.SupportsInt | typing.SupportsIndex) -> int:
    """
    The seed of the pair with global index ``index`` in a batch seeded with ``seed``.
    """
def pose_matrix(pose: typing.Any, name: typing.Any = 'pose') -> numpy.typing.NDArray[numpy.float64]:
    """
    Return ``pose``, in any form the queries take (see ``swarmcollide.PoseLike``), as a ``(4, 4)``
    float64 homogeneous transform, read exactly as the queries read it.
    
    Errors name the argument as ``name``.
    """
def project_onto_simplex(weights: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    Euclidean projection onto the probability simplex.
    """
def query_function(python_path: collections.abc.Callable, text_signature: str) -> typing.Any:
    """
    ``python_path`` (``distance``, ``signed_distance``, ``collision`` or ``collide`` of
    swarmcollide.queries, told by its ``__name__``) as a C++ function with its name, module,
    documentation and ``text_signature`` (without annotations).
    
    The C++ function answers ``f(a, b, *, method, tolerance, seed, pose_a, pose_b, escalate)``
    itself (a method that is a str, a float tolerance, an int seed, ``escalate`` a bool and only for
    the verdicts), with a Query per method, tolerance and seed kept as Python's ``query`` keeps them,
    and hands every other call (solver parameters, other types, calls that raise) to
    ``python_path``, which answers it or raises as it always has.
    """
def rank_adaptive_coefficients(rank: typing.SupportsInt | typing.SupportsIndex, swarm_size: typing.SupportsInt | typing.SupportsIndex, w_min: typing.SupportsFloat | typing.SupportsIndex = 0.4, w_max: typing.SupportsFloat | typing.SupportsIndex = 0.9) -> ParticleCoefficients:
    """
    (8)-(9): ``(w, c1, c2)`` of the particle ranked ``rank`` (1 = best).
    """
def separation(a: typing.Any, b: typing.Any, direction: typing.Any) -> float:
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
def time_of_impact(a: typing.Any, b: typing.Any, *, pose_a: typing.Any = None, pose_b: typing.Any = None, method: typing.Any = 'exact', tolerance: typing.Any = 1e-09, time_tolerance: typing.Any = 1e-06, max_iterations: typing.Any = 100000, motion: typing.Any = 'linear') -> TimeOfImpactResult:
    """
    The first contact of A and B moving from their start to their end poses (see swarmcollide.time_of_impact).
    """
def time_of_impact_many(As: typing.Any, Bs: typing.Any, *, poses_a: typing.Any = None, poses_b: typing.Any = None, method: typing.Any = 'exact', tolerance: typing.Any = 1e-09, time_tolerance: typing.Any = 1e-06, max_iterations: typing.Any = 100000, threads: typing.Any = None, motion: typing.Any = 'linear') -> TimeOfImpactBatch:
    """
    time_of_impact for every row (see swarmcollide.time_of_impact_many).
    """
