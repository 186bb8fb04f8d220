"""Non-convex bodies from mesh files.

``load_mesh`` reads a triangle mesh through trimesh (OBJ, STL, PLY, GLB, OFF, ...);
``CompoundBody.from_mesh`` decomposes it into convex parts (CoACD, V-HACD, one hull, or parts
that are convex already), records how far the parts are from the mesh, and caches the
decomposition on disk. Queries between compound bodies are certified for the convex parts; how
far that is from the mesh is what ``CompoundBody.decomposition`` records.

Needs the ``mesh`` extra: ``pip install swarmcollide[mesh]`` (trimesh, rtree, scipy, coacd, vhacdx,
tqdm, fast-simplification).
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import tempfile
import threading
import time
import zipfile
from dataclasses import MISSING, asdict, dataclass, field, fields
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import (Any, Callable, Dict, List, Optional, Sequence, Union, get_origin,
                    get_type_hints)

import numpy as np

from . import _core

DECOMPOSERS = ("coacd", "vhacd", "hull", None)
"""What ``CompoundBody.from_mesh(decompose=...)`` takes: CoACD (the default), V-HACD (faster,
coarser), one convex hull, or None for a mesh whose connected components are convex already."""

DEFAULT_SAMPLES = 4000
"""Surface points sampled on each side when the parts' distance from the mesh is measured."""

MAX_SAMPLES = 10_000_000
"""The most surface points sampled on each side: each is held (a point, a distance) at once, a
few hundred bytes with trimesh's sampling, so more would ask for gigabytes."""

PRESETS: Dict[str, Dict[str, Any]] = {
    "fast": {"threshold": 0.1, "resolution": 1000, "preprocess_resolution": 30,
             "mcts_nodes": 8, "mcts_iterations": 30, "mcts_max_depth": 2},
    "quality": {"threshold": 0.05, "resolution": 2000, "preprocess_resolution": 50,
                "mcts_nodes": 20, "mcts_iterations": 100, "mcts_max_depth": 3},
}
"""CoACD's settings for ``CompoundBody.from_mesh(preset=...)``: ``"fast"`` (the default) answers
in seconds on robot-link meshes, ``"quality"`` fits closer and takes a minute or more (docs/mesh.md
has the measured table). Explicit ``concavity`` and ``resolution`` override a preset's
``threshold`` and ``resolution``."""

DEFAULT_PRESET = "fast"
"""The preset ``from_mesh`` uses when none is given."""

DEFAULT_CONCAVITY = PRESETS[DEFAULT_PRESET]["threshold"]
"""CoACD's concavity threshold (its ``threshold``) of the default preset: the largest concavity
a part may keep, relative to the mesh's bounding-box diagonal."""

DEFAULT_MAX_FACES = 20_000
"""Meshes with more triangles are simplified to this many (quadric decimation, by
fast-simplification through trimesh) before they are decomposed, which bounds the decomposers'
memory and time; the error that adds is measured and recorded (``simplification_error``)."""

DEFAULT_MAX_HULL_VERTICES = 64
"""V-HACD's ``maxNumVerticesPerCH`` when ``max_hull_vertices`` is not given (CoACD's parts are
then the exact hulls of its pieces, which never miss any of the mesh)."""

DEFAULT_VHACD_MAX_HULLS = 32
"""V-HACD's ``maxConvexHulls`` when ``max_hulls`` is not given (it needs a number; CoACD does
not and stops when every part is within the concavity threshold)."""

DEFAULT_VHACD_RESOLUTION = 20000
"""V-HACD's voxel count when ``resolution`` is not given."""

CACHE_ENVIRONMENT = "SWARMCOLLIDE_CACHE_DIR"
"""The environment variable that, when set, names the decomposition cache's directory."""

# Bumped when what a cache file holds, or how it is computed, changes.
_CACHE_FORMAT = 3
# A decomposition shows a progress bar once it has run this long (seconds).
_PROGRESS_DELAY = 1.0
# A typical time at least this long (seconds) is announced before the decomposition starts.
_LONG_RUN = 20.0
# Points times part vertices per batch of exact distances: each row of a batch holds its own copy
# of the part's points, so the batch is cut to hold at most this many (about 25 MB).
_DEVIATION_POINTS = 1 << 20
# Query points per call of trimesh's proximity queries, whose memory grows with the points times
# the triangles near each.
_PROXIMITY_POINTS = 256
# A face or vertex deeper than this inside its hull (relative to the piece's bounding-box
# diagonal) makes a ready-made part not convex: trimesh's planar tolerance, which the six digits
# of typical OBJ files stay within (1.3e-6 at most on pybullet_data's V-HACD files).
_CONVEX_TOLERANCE = 1e-5
# Probe points times hull facets, at most, of that comparison (beyond it trimesh's verdict
# stands): the work and, in pieces, the memory of the heights of every probe over every facet.
_CONVEX_CHECK_PAIRS = 1 << 28

MeshLike = Union[str, "os.PathLike[str]", Any]
"""A path to a mesh file, or a ``trimesh.Trimesh``."""


def _trimesh():
    try:
        import trimesh
    except ImportError as error:  # pragma: no cover - the mesh extra is installed in tests
        raise ImportError(
            "reading meshes needs trimesh: pip install 'swarmcollide[mesh]'"
        ) from error
    return trimesh


def cache_directory() -> Path:
    """Where decompositions are cached: ``$SWARMCOLLIDE_CACHE_DIR`` if set, else the user's cache
    directory (``$XDG_CACHE_HOME`` or ``~/.cache`` on Linux, ``~/Library/Caches`` on macOS,
    ``%LOCALAPPDATA%`` on Windows) under ``swarmcollide/decompositions``.

    Examples
    --------
    >>> import os, swarmcollide as sc
    >>> os.environ["SWARMCOLLIDE_CACHE_DIR"] = "/tmp/my-cache"
    >>> str(sc.cache_directory())
    '/tmp/my-cache'
    >>> del os.environ["SWARMCOLLIDE_CACHE_DIR"]
    """
    chosen = os.environ.get(CACHE_ENVIRONMENT)
    if chosen:
        return Path(chosen)
    if sys.platform == "darwin":
        base = Path.home() / "Library" / "Caches"
    elif os.name == "nt":
        base = Path(os.environ.get("LOCALAPPDATA") or Path.home() / "AppData" / "Local")
    else:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "swarmcollide" / "decompositions"


def load_mesh(source: MeshLike):
    """A triangle mesh from a file (through trimesh) or a ``trimesh.Trimesh``, checked.

    Scenes of several meshes (a GLB, say) are merged into one mesh, in the scene's frame.

    Parameters
    ----------
    source : str, os.PathLike or trimesh.Trimesh
        A mesh file in any format trimesh reads (OBJ, STL, PLY, GLB, OFF, ...), or a mesh.

    Returns
    -------
    trimesh.Trimesh

    Raises
    ------
    TypeError
        For anything but a path or a ``trimesh.Trimesh``.
    ValueError
        For a missing or unreadable file, or a mesh that is empty, has NaN or infinite
        coordinates, or is not a 3-D triangle mesh (a 2-D drawing, a point cloud, or points that
        all lie in one plane).

    Examples
    --------
    >>> import trimesh, swarmcollide as sc
    >>> sc.load_mesh(trimesh.creation.box((1, 2, 3))).bounds.tolist()
    [[-0.5, -1.0, -1.5], [0.5, 1.0, 1.5]]
    >>> sc.load_mesh("no/such/file.obj")
    Traceback (most recent call last):
    ...
    ValueError: cannot read mesh file 'no/such/file.obj': no such file
    """
    trimesh = _trimesh()
    if isinstance(source, trimesh.Trimesh):
        return _checked(source, "mesh")
    if isinstance(source, (str, os.PathLike)):
        path = Path(source)
        name = f"mesh file {str(source)!r}"
        if path.is_dir():
            raise ValueError(f"cannot read {name}: it is a directory; pass a mesh file")
        if not path.is_file():
            raise ValueError(f"cannot read {name}: no such file")
        try:
            # Unprocessed, so that NaN points reach the check instead of being dropped silently.
            loaded = trimesh.load_mesh(path, process=False)
        except Exception as error:  # trimesh raises many types for bad files
            raise ValueError(
                f"cannot read {name}: {error or type(error).__name__} (is it a mesh file? "
                "OBJ, STL, PLY, GLB and OFF are read)"
            ) from error
        if isinstance(loaded, trimesh.Trimesh) and len(loaded.faces) == 0:
            # trimesh reads bytes that are no mesh (random, or another format under a mesh's
            # suffix) as a mesh of no triangles, without an error.
            raise ValueError(
                f"{name} cannot be read as a mesh: no triangles could be read from it (is it a "
                "mesh file? OBJ, STL, PLY, GLB and OFF are read; an empty one holds none)"
            )
        # STL and others repeat each triangle's corners: merged, the mesh's edges are shared. The
        # merge (within 1e-8 of the largest coordinate) cannot flatten a mesh the check passed.
        return _merged(_checked(loaded, name))
    raise TypeError(
        "mesh must be a path to a mesh file (OBJ, STL, PLY, GLB, OFF) or a trimesh.Trimesh, "
        f"got {type(source).__name__}"
    )


def _checked(mesh, name: str):
    trimesh = _trimesh()
    if not isinstance(mesh, trimesh.Trimesh):
        raise ValueError(
            f"{name} is not a 3-D triangle mesh (trimesh read a {type(mesh).__name__}); "
            "give a file of triangles or polygons in 3-D"
        )
    vertices = np.asarray(mesh.vertices)
    faces = np.asarray(mesh.faces)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ValueError(f"{name} is not a 3-D mesh: its points have shape {vertices.shape}")
    if len(vertices) == 0 or len(faces) == 0:
        raise ValueError(f"{name} is empty: it has no triangles")
    if not np.isfinite(vertices).all():
        raise ValueError(f"{name} has NaN or infinite coordinates; fix or remove those points")
    used = vertices[np.unique(faces)]
    if _thickness(used) <= _FLAT * np.abs(used).max():
        raise ValueError(
            f"{name} is not a 3-D solid: all its points lie in one plane (or on one line); "
            "a body needs points that span three dimensions"
        )
    return mesh


# Thickness, relative to the largest coordinate, within which a mesh is flat: 4 units of float32
# rounding (2**-24 of a coordinate each), since STL and most binary formats store float32, and
# rounding lifts the corners of a tilted plane off it by about that much.
_FLAT = 4 * float(np.finfo(np.float32).eps)


def _exponent(points: np.ndarray) -> int:
    """The power of two of the largest coordinate of ``points``: scaled by 2**-exponent (exactly,
    a power of two), they lie in [-1, 1]. trimesh and the decomposers run there, as in any unit
    of length their tolerances are absolute (trimesh merges points closer than 1e-8, its
    proximity queries and CoACD's and V-HACD's cuts have fixed tolerances) and their areas square
    lengths: a box of 1e-9 merged into one point, one of 1e200 had NaN areas."""
    largest = float(np.abs(np.asarray(points, dtype=float)).max())
    return int(np.frexp(largest)[1]) if largest > 0 else 0


def _scaled(mesh, exponent: int):
    """A copy of ``mesh`` with its coordinates times 2**exponent (exact, short of overflow and
    of subnormal numbers)."""
    trimesh = _trimesh()
    return trimesh.Trimesh(np.ldexp(np.asarray(mesh.vertices, dtype=float), exponent),
                           np.array(mesh.faces), process=False)


def _merged(mesh):
    """A copy of ``mesh`` with its repeated points merged (trimesh's merge, points within about
    1e-8 of its largest coordinate, whatever their normals or texture coordinates say): the
    triangles of one piece then share their corners, and ``split`` finds the piece whole where
    an unmerged mesh fell apart into single triangles."""
    exponent = _exponent(mesh.vertices)
    unit = _scaled(mesh, -exponent)
    unit.merge_vertices(merge_tex=True, merge_norm=True)
    return _scaled(unit, exponent)


def _thickness(points: np.ndarray) -> float:
    """Width of ``points`` across their best-fitting plane (0 for a plane, a line or a point)."""
    spread = points - points.mean(axis=0)
    scale = np.abs(spread).max()
    if scale == 0:
        return 0.0
    # Scaled first, so that neither 1e300 nor 1e-300 coordinates overflow or underflow.
    normal = np.linalg.svd(spread / scale, full_matrices=False)[2][-1]
    across = spread @ normal
    return float(across.max() - across.min())


def mesh_hash(mesh) -> str:
    """SHA-256 of a mesh's triangles as coordinates: the cache's key for a mesh.

    The triangles are hashed as their corners' float64 coordinates, each triangle starting at its
    smallest corner (which keeps its orientation) and the triangles in sorted order, so the hash
    does not depend on how a loader numbered, merged or duplicated the points, nor on the order of
    the triangles.

    Examples
    --------
    >>> import numpy as np, trimesh, swarmcollide as sc
    >>> box = trimesh.creation.box()
    >>> corners = box.vertices[box.faces[::-1]].reshape(-1, 3)  # unmerged, triangles reversed
    >>> unmerged = trimesh.Trimesh(corners, np.arange(36).reshape(-1, 3), process=False)
    >>> sc.mesh_hash(unmerged) == sc.mesh_hash(box)
    True
    >>> len(sc.mesh_hash(box))
    64
    """
    # + 0.0 turns -0.0 into 0.0, which compare equal but hash apart.
    points = np.asarray(mesh.vertices, dtype=np.float64) + 0.0
    # Each point's rank in lexicographic order (equal points share one), then each triangle
    # rolled to start at its lowest corner.
    order = np.lexsort(points.T[::-1])
    ordered_points = points[order]
    new = np.ones(len(points), dtype=bool)
    new[1:] = (ordered_points[1:] != ordered_points[:-1]).any(axis=1)
    rank = np.empty(len(points), dtype=np.int64)
    rank[order] = np.cumsum(new)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    first = rank[faces].argmin(axis=1)
    rolled = faces[np.arange(len(faces))[:, None], (first[:, None] + np.arange(3)) % 3]
    # Triangles in the order of their corners' ranks: the same order as their coordinates.
    keys = rank[rolled]
    ordered = rolled[np.lexsort(keys.T[::-1])]
    return hashlib.sha256(np.ascontiguousarray(points[ordered]).tobytes()).hexdigest()


class NotConvexError(ValueError):
    """A piece that ``CompoundBody.from_mesh(mesh, decompose=None)`` would take as a part as it
    is, but which is not convex: ``piece`` names it (a group of the file, or a connected
    component), ``triangles`` counts its faces and ``defect`` says what makes it not convex, so
    a caller with options of its own (``Robot.from_urdf``'s ``collision``) can name those."""

    def __init__(self, piece: str, triangles: int, defect: str) -> None:
        super().__init__(
            f"decompose=None needs convex parts, but {piece}, with {triangles} triangles, is not "
            f"convex ({defect}); use decompose='coacd' or 'vhacd' to split it, or 'hull' for its "
            "hull"
        )
        self.piece = piece
        self.triangles = triangles
        self.defect = defect


@dataclass(frozen=True)
class Decomposition:
    """How a compound body was made from a mesh, and how far its parts are from the mesh.

    The two distances are one-sided Hausdorff distances between the solid of the mesh (M) and
    the union of the parts (P), measured on ``samples`` points sampled by trimesh on each
    surface: ``parts_to_mesh`` is the largest distance from a sampled point of P's surface to M
    (how far the parts stick out), ``mesh_to_parts`` the largest distance from a sampled point of
    M's surface to P (how much of the mesh the parts miss). Distances to the parts are computed
    exactly (by this library's certified queries), distances to the mesh by trimesh (signed for
    a watertight mesh; for an open one, the distance to its surface, which can only overstate).
    Sampled maxima are lower bounds on the true ones; a point of a surface is within about
    ``spacing`` of a sample, and the distance functions are 1-Lipschitz, so the true values
    exceed the measured ones by at most about ``spacing``.

    A mesh of more than ``max_faces`` triangles is simplified before it is decomposed; the parts
    are then measured against the simplified mesh, and ``simplification_error`` (the sampled
    Hausdorff distance between the two surfaces) is added to both distances, which by the
    triangle inequality makes them the parts' distances from the mesh as given.

    What it means for queries: answers are certified for the parts, and the meshes' true distance
    lies within ``mesh_to_parts`` (of each body) below and ``parts_to_mesh`` (of each body) above
    the parts' distance: ``d_parts - gA - gB <= d_mesh <= d_parts + hA + hB`` with ``h`` the
    ``parts_to_mesh`` and ``g`` the ``mesh_to_parts`` of bodies A and B (parts that miss some of
    a mesh can leave the meshes closer than the parts, parts that stick out can leave them
    farther apart), to within the true values' excess over the sampled ones.

    Attributes
    ----------
    method : str
        ``"coacd"``, ``"vhacd"``, ``"hull"`` or ``"none"`` (the file's groups or the mesh's convex
        components).
    parameters : dict
        The decomposer's settings, as passed to it.
    parts : int
        Number of convex parts.
    seconds : float
        Time the decomposition took when it was computed (a cached one reports that time).
    parts_to_mesh, mesh_to_parts : float
        The sampled one-sided Hausdorff distances, in the mesh's units (with
        ``simplification_error`` included).
    samples : int
        Points sampled on each surface.
    spacing : float
        ``sqrt(area / samples)`` of the larger surface: the typical distance between samples.
    mesh_hash : str
        SHA-256 of the mesh (``mesh_hash``).
    faces : int
        Triangles of the mesh as given.
    decomposed_faces : int
        Triangles of the mesh the decomposer saw (``faces`` unless it was simplified).
    simplification_error : float
        Sampled Hausdorff distance between the simplified surface and the mesh's (0 when the mesh
        was not simplified).
    from_cache : bool
        True when the parts came from the on-disk cache.
    """

    method: str
    parameters: Dict[str, Any]
    parts: int
    seconds: float
    parts_to_mesh: float
    mesh_to_parts: float
    samples: int
    spacing: float
    mesh_hash: str
    faces: int = 0
    decomposed_faces: int = 0
    simplification_error: float = 0.0
    from_cache: bool = field(default=False, compare=False)

    @property
    def hausdorff(self) -> float:
        """The larger of the two one-sided distances: the (sampled) Hausdorff distance."""
        return max(self.parts_to_mesh, self.mesh_to_parts)

    def __repr__(self) -> str:
        simplified = (f", simplified {self.faces} to {self.decomposed_faces} faces "
                      f"(error {self.simplification_error:.4g})"
                      if self.decomposed_faces != self.faces else "")
        return (
            f"Decomposition(method={self.method!r}, parts={self.parts}, "
            f"parts_to_mesh={self.parts_to_mesh:.4g}, mesh_to_parts={self.mesh_to_parts:.4g}, "
            f"samples={self.samples}, seconds={self.seconds:.3g}{simplified}"
            f"{', from_cache=True' if self.from_cache else ''})"
        )


class CompoundBody(_core.CompoundBody):
    """A body that is the union of convex parts; ``from_mesh`` builds one from a triangle mesh.

    The core's ``CompoundBody`` (a bounding-volume tree over convex parts, which every query
    accepts), with ``decomposition``: how the parts were made from a mesh and how far they are
    from it (None for bodies built from parts).

    Parameters
    ----------
    parts : sequence of ConvexPolyhedron or array_like of shape (n, 3)
        At least one convex part.
    decomposition : Decomposition, optional
    poses : array_like of shape (len(parts), 4, 4), optional
        Where each part sits in the body's frame (see the core's ``CompoundBody``).

    Examples
    --------
    >>> import trimesh, swarmcollide as sc
    >>> box = trimesh.creation.box((2, 1, 1))
    >>> body = sc.CompoundBody.from_mesh(box, decompose="hull", cache=False)
    >>> body
    CompoundBody(1 part, 8 points, bounds [-1, -0.5, -0.5] to [1, 0.5, 0.5]; hull, ...)
    >>> body.decomposition.hausdorff < 1e-9
    True
    """

    def __init__(self, parts, decomposition: Optional[Decomposition] = None, *,
                 poses=None) -> None:
        super().__init__(parts, poses=poses)
        self.decomposition = decomposition

    def __setstate__(self, state: Any) -> None:
        super().__setstate__(state)
        # The core restores the instance's attributes as they were pickled; a record that is not
        # one (an edited pickle) is refused here, not by the first repr or save that reads it.
        record = self.__dict__.setdefault("decomposition", None)
        if not isinstance(record, (Decomposition, type(None))):
            raise ValueError("a CompoundBody state's decomposition must be a Decomposition or "
                             f"None, got {type(record).__name__}: the state is corrupted")

    @classmethod
    def from_mesh(
        cls,
        mesh: MeshLike,
        decompose: Optional[str] = "coacd",
        *,
        preset: str = DEFAULT_PRESET,
        concavity: Optional[float] = None,
        max_hulls: Optional[int] = None,
        max_hull_vertices: Optional[int] = None,
        resolution: Optional[int] = None,
        max_faces: int = DEFAULT_MAX_FACES,
        seed: int = 0,
        samples: int = DEFAULT_SAMPLES,
        cache: Union[bool, str, "os.PathLike[str]"] = True,
        progress: bool = True,
    ) -> "CompoundBody":
        """Decompose a mesh into convex parts: a compound body with its ``decomposition``.

        Parameters
        ----------
        mesh : str, os.PathLike or trimesh.Trimesh
            A mesh file or a mesh (see ``load_mesh``).
        decompose : {"coacd", "vhacd", "hull", None}
            ``"coacd"`` (default): CoACD, collision-aware approximate convex decomposition, the
            closest fit. ``"vhacd"``: V-HACD, voxel-based, faster and coarser; its voxels follow
            the rounding of the points, so the same mesh in another unit (other than by a power
            of two) can give other parts, each recorded. ``"hull"``: the
            mesh's convex hull, one part. None: parts that are convex already: each ``o``/``g``
            group of an OBJ file (each geometry of a multi-mesh file) is one part, as V-HACD and
            CoACD write them; a single mesh is split into its connected components. ValueError
            names the group or component that is not convex.
        preset : {"fast", "quality"}
            CoACD's settings (``PRESETS``): ``"fast"`` answers in seconds on robot-link meshes,
            ``"quality"`` fits closer and can take minutes.
        concavity : float, optional
            CoACD: the concavity threshold (its ``threshold``, relative to the bounding-box
            diagonal; smaller gives more parts, closer), the preset's when None. V-HACD: the
            allowed volume error as a fraction (its ``minimumVolumePercentErrorAllowed`` is
            ``100 * concavity``; 0.05 when None).
        max_hulls : int, optional
            At most this many parts (CoACD: unlimited when None; V-HACD: 32 when None).
        max_hull_vertices : int, optional
            At most this many vertices per part. CoACD: when given, it decimates its hulls to it
            (a decimated hull can miss some of the mesh, which ``mesh_to_parts`` records); when
            None its parts are the exact hulls of its pieces. V-HACD: 64 when None.
        resolution : int, optional
            CoACD's surface sampling resolution (the preset's when None) or V-HACD's voxel count
            (20000 when None).
        max_faces : int
            A mesh with more triangles is simplified to this many before it is decomposed (not
            for ``decompose=None``); ``simplification_error`` records what that cost.
        seed : int
            Seed of CoACD's search and of the surface sampling.
        samples : int
            Points sampled on each surface to measure the parts' distance from the mesh.
        cache : bool or path
            Keep the decomposition on disk, keyed by the settings and the mesh's hash, and by the
            file's bytes when ``mesh`` is a path (so a file read again, by any loader, is found):
            True uses ``cache_directory()``, a path that directory, False nothing.
        progress : bool
            Show a tqdm progress bar (on stderr) when decomposing takes over a second, with an
            estimate of the time before a long run.

        Returns
        -------
        CompoundBody
        """
        parameters = _parameters(decompose, preset, concavity, max_hulls, max_hull_vertices,
                                 resolution, seed)
        if not (isinstance(max_faces, int) and max_faces >= 4):
            raise ValueError(f"max_faces must be an integer >= 4, got {max_faces!r}")
        _check_samples(samples)  # before a decomposition that can take minutes
        settings = [decompose, parameters, samples,
                    max_faces if decompose is not None else None]
        folder = _cache_folder(cache)
        file_key = None
        if folder is not None and isinstance(mesh, (str, os.PathLike)) and Path(mesh).is_file():
            file_key = _cache_key(settings, file_digest=_file_digest(Path(mesh)))
            cached = _read_cache(folder / f"{file_key}.npz")
            if cached is not None:
                return cls(*cached)
        loaded = load_mesh(mesh)
        mesh_key = _cache_key(settings, mesh_digest=mesh_hash(loaded))
        if folder is not None:
            cached = _read_cache(folder / f"{mesh_key}.npz")
            if cached is not None:
                if file_key is not None:
                    _write_cache(folder / f"{file_key}.npz", *cached)
                return cls(*cached)
        # Merged (an unmerged mesh's triangles are pieces of their own) and decomposed with its
        # largest coordinate in [-1, 1] (_exponent): the parts are the same in any unit.
        exponent = _exponent(loaded.vertices)
        decomposed = _scaled(_merged(loaded), -exponent)
        unit_error = 0.0
        if decompose is not None and len(loaded.faces) > max_faces:
            whole, decomposed = decomposed, _simplified(decomposed, max_faces)
            unit_error = _surface_distance(whole, decomposed, samples, seed)
        simplification_error = float(np.ldexp(unit_error, exponent))
        start = time.perf_counter()
        if decompose is None:
            unit_parts = _ready_made_parts(mesh, decomposed, exponent)
        else:
            unit_parts = _decompose(decomposed, decompose, parameters, preset, progress)
        seconds = time.perf_counter() - start
        parts = [np.ldexp(part, exponent) for part in unit_parts]
        body = cls(parts)
        deviation = measure_deviation(_scaled(decomposed, exponent), body, samples=samples,
                                      seed=seed)
        body.decomposition = Decomposition(
            method=decompose or "none",
            parameters=parameters,
            parts=len(parts),
            seconds=seconds,
            parts_to_mesh=deviation["parts_to_mesh"] + simplification_error,
            mesh_to_parts=deviation["mesh_to_parts"] + simplification_error,
            samples=deviation["samples"],
            spacing=deviation["spacing"],
            mesh_hash=mesh_hash(loaded),
            faces=len(loaded.faces),
            decomposed_faces=len(decomposed.faces),
            simplification_error=simplification_error,
        )
        if folder is not None:
            for key in (mesh_key, file_key):
                if key is not None:
                    _write_cache(folder / f"{key}.npz", parts, body.decomposition)
        return body

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Write the parts (and the decomposition, if any) to a ``.npz`` file ``load`` reads.

        The file holds ``points`` (every part's points, part after part), ``offsets`` (where
        each part starts in ``points``, and the total) and ``decomposition`` (JSON, or empty).
        Points only: a part with a pose is written placed (its points in the body's frame, the
        same part; ``load`` gives it without a pose); a body with a curved or rounded part is
        refused (ValueError), and ``swarmcollide.shape_json.body_to_json`` writes it whole,
        poses included.
        """
        for k, part in enumerate(self.parts):
            if part.curved or part.rounding_radius > 0:
                raise ValueError(
                    f"parts[{k}] is {'a curved shape' if part.curved else 'rounded'}, which a "
                    "parts file (points only) cannot hold; write the body with "
                    "swarmcollide.shape_json.body_to_json instead")
        _write_parts(Path(path), [p.vertices for p in self.parts], self.decomposition)

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "CompoundBody":
        """A compound body from a ``.npz`` file written by ``save`` (or ``swarmcollide
        decompose``); ValueError for a file that is not one, TypeError for a path that is not
        a path."""
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(
                f"path must be a path to a parts file (.npz), got {type(path).__name__}"
            )
        if Path(path).is_dir():
            raise ValueError(f"parts file {str(path)!r} is a directory; pass an .npz file")
        if not Path(path).is_file():
            raise ValueError(f"cannot read parts file {str(path)!r}: no such file")
        try:
            loaded = _read_parts(Path(path))
        except ValueError as error:  # its decomposition record: name the file and the field
            raise ValueError(f"parts file {str(path)!r}: {error}") from None
        if loaded is None:
            raise ValueError(
                f"{str(path)!r} is not a parts file (an .npz with 'points' and 'offsets', as "
                "CompoundBody.save and 'swarmcollide decompose' write)"
            )
        parts, decomposition = loaded
        try:
            return cls(parts, decomposition)
        except (ValueError, TypeError) as error:  # NaN points, say: name the file
            raise type(error)(f"parts file {str(path)!r}: {error}") from None

    def __repr__(self) -> str:
        text = super().__repr__()
        if self.decomposition is None:
            return text
        d = self.decomposition
        return (
            f"{text[:-1]}; {d.method}, parts_to_mesh={d.parts_to_mesh:.3g}, "
            f"mesh_to_parts={d.mesh_to_parts:.3g})"
        )


def measure_deviation(mesh, body: _core.CompoundBody, *, samples: int = DEFAULT_SAMPLES,
                      seed: int = 0) -> Dict[str, Any]:
    """The one-sided Hausdorff distances between a mesh's solid and a compound body's parts.

    Returns the fields ``parts_to_mesh``, ``mesh_to_parts``, ``samples`` and ``spacing`` of a
    ``Decomposition`` (which says what they mean). Memory stays bounded whatever the sizes: the
    exact distances run in batches of at most about a million part points, trimesh's proximity
    queries in chunks of points.

    Examples
    --------
    >>> import trimesh, swarmcollide as sc
    >>> box = trimesh.creation.box((2, 2, 2))
    >>> smaller = sc.CompoundBody([box.vertices * 0.9])
    >>> d = sc.measure_deviation(box, smaller, samples=500)
    >>> 0.1 <= d["mesh_to_parts"] <= 0.1 * 3 ** 0.5, d["parts_to_mesh"]  # faces 0.1, corners more
    (True, 0.0)
    """
    trimesh = _trimesh()
    _check_samples(samples)
    parts = body.parts
    # trimesh samples and measures the mesh and the parts' hulls scaled by 2**-exponent (exact):
    # its areas square lengths and its proximity queries have absolute tolerances, so that in
    # small or large units the record drifted, then was 0 or NaN. Lengths are scaled back.
    exponent = _exponent(np.vstack([mesh.vertices] + [part.vertices for part in parts]))
    unit_mesh = _scaled(mesh, -exponent)
    # Points on the mesh's surface, and their exact distance to the union of the parts.
    on_mesh = np.ldexp(trimesh.sample.sample_surface(unit_mesh, samples, seed=seed)[0], exponent)
    to_parts = np.full(len(on_mesh), np.inf)
    exact = _core.Query("exact")
    for part in parts:
        rows = max(1, _DEVIATION_POINTS // len(part.vertices))
        for begin in range(0, len(on_mesh), rows):
            chunk = on_mesh[begin:begin + rows]
            to_parts[begin:begin + rows] = np.minimum(
                to_parts[begin:begin + rows],
                exact.distance_many([part] * len(chunk), chunk[:, None, :], threads=None).distance)
    # Points on the parts' surfaces (in proportion to their areas), and their distance to the
    # mesh's solid: outside a watertight mesh its signed distance (trimesh: positive inside),
    # else the distance to its surface, which can only overstate.
    solids = [p for p in parts if p.hull().dimension == 3]
    if solids:
        hulls = trimesh.util.concatenate(
            [trimesh.Trimesh(np.ldexp(p.vertices, -exponent), p.hull().faces, process=False)
             for p in solids])
        on_parts, _ = trimesh.sample.sample_surface(hulls, samples, seed=seed + 1)
        if unit_mesh.is_watertight:
            outside = np.maximum(
                -_in_chunks(trimesh.proximity.signed_distance, unit_mesh, on_parts), 0.0)
        else:
            outside = _in_chunks(lambda m, p: trimesh.proximity.closest_point(m, p)[1],
                                 unit_mesh, on_parts)
        unit_parts_to_mesh = float(outside.max())
        area = max(unit_mesh.area, hulls.area)
    else:
        unit_parts_to_mesh, area = 0.0, unit_mesh.area
    return {
        "parts_to_mesh": float(np.ldexp(unit_parts_to_mesh, exponent)),
        "mesh_to_parts": float(to_parts.max()),
        "samples": int(samples),
        "spacing": float(np.ldexp(np.sqrt(area / samples), exponent)),
    }


def _check_samples(samples: int) -> None:
    """TypeError or ValueError naming ``samples`` unless it is an integer in [1, MAX_SAMPLES]."""
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)):
        raise TypeError(f"samples must be an integer, got {type(samples).__name__}")
    if samples < 1:
        raise ValueError(f"samples must be at least 1, got {samples}")
    if samples > MAX_SAMPLES:
        raise ValueError(f"samples must be at most {MAX_SAMPLES:,} (points on each surface), got "
                         f"{samples:,}")


def _in_chunks(distance: Callable[[Any, np.ndarray], np.ndarray], mesh,
               points: np.ndarray) -> np.ndarray:
    """``distance(mesh, points)`` a chunk of points at a time: trimesh gathers every triangle
    near each point at once, which for many points on a fine mesh takes gigabytes."""
    return np.concatenate([np.asarray(distance(mesh, points[k:k + _PROXIMITY_POINTS]))
                           for k in range(0, len(points), _PROXIMITY_POINTS)])


def _simplified(mesh, faces: int):
    """The mesh simplified to about ``faces`` triangles by quadric decimation."""
    try:
        simplified = mesh.simplify_quadric_decimation(face_count=faces)
    except ImportError as error:  # pragma: no cover - the mesh extra installs it
        raise ImportError(
            f"the mesh has {len(mesh.faces)} triangles, more than max_faces={faces}, and "
            "simplifying it needs fast-simplification: pip install 'swarmcollide[mesh]' (or "
            "raise max_faces, which costs memory and time)"
        ) from error
    # Quadric decimation leaves some triangles twice, back to back (a fin that encloses nothing),
    # which make a closed mesh open and its signed distance unavailable: both copies go.
    corners = np.sort(np.asarray(simplified.faces), axis=1)
    _, index, counts = np.unique(corners, axis=0, return_inverse=True, return_counts=True)
    single = counts[index.ravel()] == 1
    trimesh = _trimesh()
    return _checked(trimesh.Trimesh(simplified.vertices, simplified.faces[single]),
                    "the simplified mesh")


def _surface_distance(mesh, simplified, samples: int, seed: int) -> float:
    """The sampled Hausdorff distance between a mesh's surface and its simplification.

    Points sampled on the mesh get their distance to the simplified surface (trimesh). Points
    sampled on the simplified surface get their distance to the nearest of the mesh's triangles
    around its 4 nearest vertices: never less than the distance to the mesh's surface, and for
    points this close to it the same in practice, at the cost of one k-d tree where trimesh's
    query gathers every triangle near each point of a large mesh (a minute and 1.5 GB at 2M).
    """
    trimesh = _trimesh()
    from scipy.spatial import cKDTree

    on_mesh, _ = trimesh.sample.sample_surface(mesh, samples, seed=seed + 2)
    on_simplified, _ = trimesh.sample.sample_surface(simplified, samples, seed=seed + 3)
    to_simplified = _in_chunks(lambda m, p: trimesh.proximity.closest_point(m, p)[1], simplified,
                               on_mesh)
    points = np.asarray(mesh.vertices, dtype=float)
    faces = np.asarray(mesh.faces)
    _, nearest = cKDTree(points).query(on_simplified, k=min(4, len(points)))
    nearest = nearest.reshape(len(on_simplified), -1)
    # The triangles around each vertex: the corners sorted by vertex, and where each one starts.
    corner_order = np.argsort(faces.ravel(), kind="stable")
    starts = np.searchsorted(faces.ravel()[corner_order], np.arange(len(points) + 1))
    vertex = nearest.ravel()
    around = starts[vertex + 1] - starts[vertex]
    sample = np.repeat(np.repeat(np.arange(len(on_simplified)), nearest.shape[1]), around)
    corner = (np.repeat(starts[vertex] - np.cumsum(around) + around, around)
              + np.arange(around.sum()))
    triangles = points[faces[corner_order[corner] // 3]]
    gaps = np.linalg.norm(trimesh.triangles.closest_point(triangles, on_simplified[sample])
                          - on_simplified[sample], axis=1)
    to_mesh = np.full(len(on_simplified), np.inf)
    np.minimum.at(to_mesh, sample, gaps)
    return float(max(to_simplified.max(), to_mesh.max()))


def _parameters(decompose, preset, concavity, max_hulls, max_hull_vertices, resolution, seed):
    if decompose not in DECOMPOSERS:
        raise ValueError(
            f"decompose must be one of 'coacd', 'vhacd', 'hull' or None, got {decompose!r}"
        )
    if preset not in PRESETS:
        raise ValueError(f"preset must be one of {', '.join(map(repr, PRESETS))}, got {preset!r}")
    if decompose in ("hull", None):
        return {}
    if concavity is not None and not (isinstance(concavity, (int, float)) and 0 < concavity <= 1):
        raise ValueError(f"concavity must be a number in (0, 1] or None, got {concavity!r}")
    if max_hulls is not None and not (isinstance(max_hulls, int) and max_hulls >= 1):
        raise ValueError(f"max_hulls must be a positive integer or None, got {max_hulls!r}")
    if max_hull_vertices is not None and not (isinstance(max_hull_vertices, int)
                                              and max_hull_vertices >= 4):
        raise ValueError(
            f"max_hull_vertices must be an integer >= 4 or None, got {max_hull_vertices!r}")
    if resolution is not None and not (isinstance(resolution, int) and resolution >= 1):
        raise ValueError(f"resolution must be a positive integer or None, got {resolution!r}")
    if not (isinstance(seed, int) and seed >= 0):
        raise ValueError(f"seed must be a nonnegative integer, got {seed!r}")
    if decompose == "coacd":
        chosen = dict(PRESETS[preset])
        if concavity is not None:
            chosen["threshold"] = float(concavity)
        if resolution is not None:
            chosen["resolution"] = resolution
        decimation = ({} if max_hull_vertices is None else
                      {"decimate": True, "max_ch_vertex": max_hull_vertices})
        return {**chosen, "max_convex_hull": -1 if max_hulls is None else max_hulls,
                **decimation, "seed": seed}
    return {
        "maxConvexHulls": DEFAULT_VHACD_MAX_HULLS if max_hulls is None else max_hulls,
        "minimumVolumePercentErrorAllowed": 100.0 * (0.05 if concavity is None else concavity),
        "maxNumVerticesPerCH": (DEFAULT_MAX_HULL_VERTICES if max_hull_vertices is None
                                else max_hull_vertices),
        "resolution": DEFAULT_VHACD_RESOLUTION if resolution is None else resolution,
    }


def _decompose(mesh, decompose, parameters, preset, progress) -> List[np.ndarray]:
    if decompose == "hull":
        return [np.asarray(mesh.convex_hull.vertices, dtype=float)]
    if decompose == "coacd":
        import coacd

        coacd.set_log_level("error")

        def run_coacd() -> List[np.ndarray]:
            hulls = coacd.run_coacd(coacd.Mesh(mesh.vertices, mesh.faces), **parameters)
            return [np.asarray(v, dtype=float) for v, _ in hulls]

        custom = any(parameters[k] != v for k, v in PRESETS[preset].items())
        estimate = None if custom else _TYPICAL_SECONDS[preset]
        note = ""
        if estimate is not None:
            note = f"preset={preset!r}, typically ~{estimate:.0f} s"
            if preset != "fast":
                note += f"; preset='fast' ~{_TYPICAL_SECONDS['fast']:.0f} s"
        return _with_progress("CoACD", run_coacd, progress, estimate, note)
    import vhacdx

    def run_vhacd() -> List[np.ndarray]:
        hulls = vhacdx.compute_vhacd(np.asarray(mesh.vertices, dtype=np.float64),
                                     np.asarray(mesh.faces, dtype=np.uint32), **parameters)
        return [np.asarray(v, dtype=float) for v, _ in hulls]

    return _with_progress("V-HACD", run_vhacd, progress)


# CoACD's typical time per preset (seconds): the median of the runs of
# bench/decomposers.py --real on five pybullet_data meshes on this project's 2-core machine. It
# does not predict the mesh at hand (CoACD's time follows the cuts a shape needs, not its
# triangles), but says before a long run what to expect and what the fast preset would take.
_TYPICAL_SECONDS = {"fast": 8.0, "quality": 185.0}


def _ready_made_parts(source, mesh, exponent: int) -> List[np.ndarray]:
    """The parts of a mesh whose pieces are convex already: the file's groups (OBJ ``o``/``g``,
    the geometries of a scene file) when it has several, else the connected components. ``mesh``
    is ``source``'s, merged and scaled by 2**-exponent; so are the parts."""
    pieces = _file_groups(source, exponent) if isinstance(source, (str, os.PathLike)) else None
    if pieces is None:
        components = mesh.split(only_watertight=False, repair=False)
        pieces = [(f"the connected component {k} of {len(components)} (around "
                   f"[{', '.join(f'{x:.6g}' for x in np.ldexp(c.centroid, exponent))}])", c)
                  for k, c in enumerate(components)]
    parts = []
    for name, piece in pieces:
        defect = _convexity_defect(piece)
        if defect is not None:
            raise NotConvexError(name, len(piece.faces), defect)
        parts.append(np.asarray(piece.vertices, dtype=float))
    return parts


def _file_groups(path, exponent: int) -> Optional[List[Any]]:
    """``(name, mesh)`` for each geometry of a file (an OBJ's ``o`` objects and ``g`` groups),
    in the file's frame scaled by 2**-exponent and merged, or None for a file of one geometry."""
    trimesh = _trimesh()
    options = {}
    if str(path).lower().endswith(".obj"):
        options = {"split_objects": True, "split_groups": True, "group_material": False,
                   "skip_materials": True}
    scene = trimesh.load(Path(path), force="scene", process=False, **options)
    nodes = [node for node in scene.graph.nodes_geometry
             if isinstance(scene.geometry[scene.graph[node][1]], trimesh.Trimesh)]
    if len(nodes) < 2:
        return None
    groups = []
    for node in nodes:
        transform, geometry = scene.graph[node]
        piece = scene.geometry[geometry].copy()
        piece.apply_transform(transform)
        groups.append((f"the group {node!r}", _scaled(_merged(piece), -exponent)))
    return groups


def _convexity_defect(piece) -> Optional[str]:
    """None for a convex piece, else what makes it not convex.

    trimesh's test (every pair of adjacent faces folds outward) accepts most pieces at once. One
    it refuses, often for the rounding of a file's six digits, is compared with its hull: a face
    whose centre lies on the hull's boundary lies in a facet of it, so the piece is convex when
    no vertex or face centre lies deeper inside than ``_CONVEX_TOLERANCE`` of its size. A flat
    piece is compared with its hull by area.
    """
    # In [-1, 1] (_exponent): trimesh's test and the normals below square lengths.
    piece = _scaled(piece, -_exponent(piece.vertices))
    if piece.is_convex:
        return None
    points = np.asarray(piece.vertices, dtype=float)
    size = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
    hull = _core.ConvexPolyhedron(points).hull()
    if size == 0 or hull.dimension < 2:
        return None
    corners = points[hull.faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    if hull.dimension == 2:
        # The flat hull lists each triangle once facing each side.
        shortfall = 1.0 - float(piece.area) / (np.linalg.norm(normals, axis=1).sum() / 4)
        return (None if shortfall <= _CONVEX_TOLERANCE else
                f"it is flat and covers {shortfall:.3g} less than its hull")
    probes = np.vstack([points, points[np.asarray(piece.faces)].mean(axis=1)])
    if len(probes) * len(normals) > _CONVEX_CHECK_PAIRS:
        return "two of its adjacent faces fold inward"
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    offsets = np.einsum("ij,ij->i", normals, corners[:, 0])
    rows = max(1, _CONVEX_CHECK_PAIRS // 64 // len(normals))
    depth = max(float((offsets - (probes[k:k + rows] @ normals.T)).min(axis=1).max())
                for k in range(0, len(probes), rows))
    return (None if depth <= _CONVEX_TOLERANCE * size else
            f"a face lies {depth / size:.3g} of its size inside its hull")


def _with_progress(label: str, run: Callable[[], List[np.ndarray]], enabled: bool,
                   estimate: Optional[float] = None, note: str = "") -> List[np.ndarray]:
    """``run()`` in a worker thread; once it has taken over a second (at once when the estimate
    says it is long), a tqdm bar shows the time it has run against the estimate (decomposers
    report no progress of their own), then how many parts it made."""
    if not enabled:
        return run()
    outcome: Dict[str, Any] = {}

    def work() -> None:
        try:
            outcome["parts"] = run()
        except BaseException as error:  # handed to the caller below
            outcome["error"] = error

    worker = threading.Thread(target=work, name=f"swarmcollide {label}", daemon=True)
    delay = 0.0 if estimate is not None and estimate >= _LONG_RUN else _PROGRESS_DELAY
    start = time.perf_counter()
    worker.start()
    bar = None
    while worker.is_alive():
        if bar is None and time.perf_counter() - start >= delay:
            from tqdm import tqdm

            description = f"{label} decomposing" + (f" ({note})" if note else "")
            if estimate is None:
                bar = tqdm(desc=description, bar_format="{desc}: {elapsed}", leave=False,
                           file=sys.stderr)
            else:
                bar = tqdm(desc=description, total=max(1, round(estimate)), unit="s",
                           bar_format="{desc}: {bar} {elapsed} of ~{total} s", leave=False,
                           file=sys.stderr)
            bar.start_t -= time.perf_counter() - start  # the time since the decomposer started
        if bar is not None:
            if estimate is not None:
                bar.n = min(int(time.perf_counter() - start), bar.total)
            bar.refresh()
        worker.join(0.2)
    if bar is not None:
        bar.set_description_str(f"{label}: {len(outcome.get('parts', []))} parts")
        bar.close()
    if "error" in outcome:
        raise outcome["error"]
    return outcome["parts"]


def _file_digest(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _cache_key(settings: List[Any], *, file_digest: Optional[str] = None,
               mesh_digest: Optional[str] = None) -> str:
    """The key of a decomposition: the settings with either the file's bytes (found before the
    file is read) or the mesh's triangles (found whichever loader read it)."""
    decompose = settings[0]
    package = {"coacd": "coacd", "vhacd": "vhacdx"}.get(decompose or "")
    try:
        decomposer = version(package) if package else ""
    except PackageNotFoundError:  # pragma: no cover - the mesh extra installs both
        decomposer = ""
    source = ["file", file_digest] if file_digest is not None else ["mesh", mesh_digest]
    description = json.dumps([_CACHE_FORMAT, source, settings, decomposer], sort_keys=True)
    return hashlib.sha256(description.encode()).hexdigest()[:32]


def _cache_folder(cache) -> Optional[Path]:
    if cache is True:
        return cache_directory()
    if cache is False or cache is None:
        return None
    if isinstance(cache, (str, os.PathLike)):
        return Path(cache)
    raise TypeError(f"cache must be True, False or a directory path, got {type(cache).__name__}")


def _write_parts(path: Path, parts: Sequence[np.ndarray],
                 decomposition: Optional[Decomposition]) -> None:
    points = np.concatenate([np.asarray(p, dtype=float) for p in parts])
    offsets = np.cumsum([0] + [len(p) for p in parts])
    meta = "" if decomposition is None else json.dumps(
        {k: v for k, v in asdict(decomposition).items() if k != "from_cache"})
    # Written beside and renamed, so that a reader never sees half a file; a rename that fails
    # (the path is a directory, say) leaves no file behind, and the error names the path given.
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path.parent, suffix=".npz", delete=False) as handle:
            np.savez(handle, points=points, offsets=offsets, decomposition=np.array(meta))
        try:
            os.replace(handle.name, path)
        except OSError:
            os.unlink(handle.name)
            raise
    except OSError as error:
        raise type(error)(error.errno, f"cannot write the parts file {str(path)!r}: "
                                       f"{error.strerror}") from None


def _read_parts(path: Path):
    """(parts, decomposition) from a parts file; None for anything else, however broken."""
    try:
        # Opened here: np.load leaves a file it opened open when the file is a broken zip.
        with open(path, "rb") as handle:
            data = np.load(handle, allow_pickle=False)
            if not isinstance(data, np.lib.npyio.NpzFile):
                return None  # a single array (.npy), not a parts file
            with data:
                points, offsets = data["points"], data["offsets"]
                meta = str(data["decomposition"]) if "decomposition" in data else ""
    except (OSError, ValueError, KeyError, EOFError, TypeError, zipfile.BadZipFile):
        return None  # unreadable, or not an .npz
    if (points.ndim != 2 or points.shape[1] != 3 or points.dtype.kind not in "fiu"
            or offsets.ndim != 1 or offsets.dtype.kind not in "iu" or len(offsets) < 2
            or offsets[0] != 0 or offsets[-1] != len(points) or np.any(np.diff(offsets) < 1)):
        return None  # each part's points, in order, and every point in one part
    parts = [points[offsets[k]:offsets[k + 1]] for k in range(len(offsets) - 1)]
    return parts, _decomposition_of(meta)


def _decomposition_of(meta: str) -> Optional[Decomposition]:
    """The decomposition record of a parts file (JSON; empty for none); ValueError naming the
    field missing, unknown or not of its type (with others, the body's repr raised, and its
    deviation bounds were not numbers)."""
    if not meta:
        return None
    try:
        record = json.loads(meta)
    except (ValueError, RecursionError):
        raise ValueError("its decomposition record is not JSON") from None
    if not isinstance(record, dict):
        raise ValueError(f"its decomposition record must be a JSON object, got "
                         f"{type(record).__name__}")
    types = get_type_hints(Decomposition)
    missing = [f.name for f in fields(Decomposition)
               if f.default is MISSING and f.default_factory is MISSING and f.name not in record]
    unknown = sorted(set(record) - set(types))
    if missing or unknown:
        problem = (f"lacks {', '.join(map(repr, missing))}" if missing
                   else f"has unknown fields {', '.join(map(repr, unknown))}")
        raise ValueError(f"its decomposition record {problem}")
    values = {}
    for key, value in record.items():
        kind = get_origin(types[key]) or types[key]
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if not isinstance(value, kind) or (isinstance(value, bool) and kind is not bool):
            raise ValueError(f"its decomposition field '{key}' must be of type {kind.__name__}, "
                             f"got {value!r}")
        values[key] = value
    return Decomposition(**values)


def _write_cache(path: Path, parts, decomposition: Decomposition) -> None:
    try:
        _write_parts(path, parts, decomposition)
    except OSError:
        pass  # a cache that cannot be written costs time, never the answer


def _read_cache(path: Path):
    if not path.is_file():
        return None
    try:
        loaded = _read_parts(path)
    except ValueError:  # a record written by a version with other fields
        return None
    if loaded is None or loaded[1] is None:
        return None
    parts, decomposition = loaded
    return parts, Decomposition(**{**asdict(decomposition), "from_cache": True})
