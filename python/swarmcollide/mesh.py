"""Non-convex bodies from mesh files.

``load_mesh`` reads a triangle mesh through trimesh (OBJ, STL, PLY, GLB, OFF, ...);
``CompoundBody.from_mesh`` decomposes it into convex parts (CoACD, V-HACD, one hull, or parts
that are convex already), records how far the parts are from the mesh, and caches the
decomposition on disk. Queries between compound bodies are certified for the convex parts; how
far that is from the mesh is what ``CompoundBody.decomposition`` records.

Needs the ``mesh`` extra: ``pip install swarmcollide[mesh]`` (trimesh, rtree, scipy, coacd, vhacdx,
tqdm).
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
from dataclasses import asdict, dataclass, field
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _core

DECOMPOSERS = ("coacd", "vhacd", "hull", None)
"""What ``CompoundBody.from_mesh(decompose=...)`` takes: CoACD (the default), V-HACD (faster,
coarser), one convex hull, or None for a mesh whose connected components are convex already."""

DEFAULT_SAMPLES = 4000
"""Surface points sampled on each side when the parts' distance from the mesh is measured."""

DEFAULT_CONCAVITY = 0.05
"""CoACD's concavity threshold (its ``threshold``): the largest concavity a part may keep,
relative to the mesh's bounding-box diagonal."""

DEFAULT_MAX_HULL_VERTICES = 64
"""Vertices per convex part, at most (CoACD's ``max_ch_vertex``, V-HACD's
``maxNumVerticesPerCH``)."""

DEFAULT_VHACD_MAX_HULLS = 32
"""V-HACD's ``maxConvexHulls`` when ``max_hulls`` is not given (it needs a number; CoACD does
not and stops when every part is within the concavity threshold)."""

DEFAULT_VHACD_RESOLUTION = 20000
"""V-HACD's voxel count when ``resolution`` is not given."""

CACHE_ENVIRONMENT = "SWARMCOLLIDE_CACHE_DIR"
"""The environment variable that, when set, names the decomposition cache's directory."""

# Bumped when what a cache file holds, or how it is computed, changes.
_CACHE_FORMAT = 1
# A decomposition shows a progress bar once it has run this long (seconds).
_PROGRESS_DELAY = 1.0

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
        checked = _checked(loaded, name)
        # STL and others repeat each triangle's corners: merged, the mesh's edges are shared.
        checked.merge_vertices()
        # Checked again: trimesh merges points closer than 1e-8, which can flatten a tiny mesh.
        return _checked(checked, name)
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
    """SHA-256 of a mesh's points (as float64) and triangles (as int64): the cache's key.

    Examples
    --------
    >>> import trimesh, swarmcollide as sc
    >>> len(sc.mesh_hash(trimesh.creation.box()))
    64
    """
    digest = hashlib.sha256()
    digest.update(np.ascontiguousarray(mesh.vertices, dtype=np.float64).tobytes())
    digest.update(np.ascontiguousarray(mesh.faces, dtype=np.int64).tobytes())
    return digest.hexdigest()


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

    What it means for queries: answers are certified for the parts, and the meshes' true distance
    lies within ``mesh_to_parts`` (of each body) below and ``parts_to_mesh`` (of each body) above
    the parts' distance: ``d_parts - gA - gB <= d_mesh <= d_parts + hA + hB`` with ``h`` the
    ``parts_to_mesh`` and ``g`` the ``mesh_to_parts`` of bodies A and B (parts that miss some of
    a mesh can leave the meshes closer than the parts, parts that stick out can leave them
    farther apart), to within the true values' excess over the sampled ones.

    Attributes
    ----------
    method : str
        ``"coacd"``, ``"vhacd"``, ``"hull"`` or ``"none"`` (the mesh's convex components).
    parameters : dict
        The decomposer's settings, as passed to it.
    parts : int
        Number of convex parts.
    seconds : float
        Time the decomposition took when it was computed (a cached one reports that time).
    parts_to_mesh, mesh_to_parts : float
        The sampled one-sided Hausdorff distances, in the mesh's units.
    samples : int
        Points sampled on each surface.
    spacing : float
        ``sqrt(area / samples)`` of the larger surface: the typical distance between samples.
    mesh_hash : str
        SHA-256 of the mesh (``mesh_hash``).
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
    from_cache: bool = field(default=False, compare=False)

    @property
    def hausdorff(self) -> float:
        """The larger of the two one-sided distances: the (sampled) Hausdorff distance."""
        return max(self.parts_to_mesh, self.mesh_to_parts)

    def __repr__(self) -> str:
        return (
            f"Decomposition(method={self.method!r}, parts={self.parts}, "
            f"parts_to_mesh={self.parts_to_mesh:.4g}, mesh_to_parts={self.mesh_to_parts:.4g}, "
            f"samples={self.samples}, seconds={self.seconds:.3g}"
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

    def __init__(self, parts, decomposition: Optional[Decomposition] = None) -> None:
        super().__init__(parts)
        self.decomposition = decomposition

    @classmethod
    def from_mesh(
        cls,
        mesh: MeshLike,
        decompose: Optional[str] = "coacd",
        *,
        concavity: float = DEFAULT_CONCAVITY,
        max_hulls: Optional[int] = None,
        max_hull_vertices: int = DEFAULT_MAX_HULL_VERTICES,
        resolution: Optional[int] = None,
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
            closest fit (seconds to minutes). ``"vhacd"``: V-HACD, voxel-based, faster and
            coarser. ``"hull"``: the mesh's convex hull, one part. None: the mesh's connected
            components, each of which must be convex already (ValueError names one that is not).
        concavity : float
            CoACD: the concavity threshold (its ``threshold``, relative to the bounding-box
            diagonal; smaller gives more parts, closer). V-HACD: the allowed volume error as a
            fraction (its ``minimumVolumePercentErrorAllowed`` is ``100 * concavity``).
        max_hulls : int, optional
            At most this many parts (CoACD: unlimited when None; V-HACD: 32 when None).
        max_hull_vertices : int
            At most this many vertices per part.
        resolution : int, optional
            CoACD's surface sampling resolution (2000 when None) or V-HACD's voxel count (20000
            when None).
        seed : int
            Seed of CoACD's search and of the surface sampling.
        samples : int
            Points sampled on each surface to measure the parts' distance from the mesh.
        cache : bool or path
            Keep the decomposition on disk, keyed by the mesh's hash and the settings: True uses
            ``cache_directory()``, a path that directory, False nothing.
        progress : bool
            Show a tqdm progress bar (on stderr) when decomposing takes over a second.

        Returns
        -------
        CompoundBody
        """
        loaded = load_mesh(mesh)
        parameters = _parameters(decompose, concavity, max_hulls, max_hull_vertices, resolution,
                                 seed)
        key = _cache_key(loaded, decompose, parameters, samples)
        folder = _cache_folder(cache)
        if folder is not None:
            cached = _read_cache(folder / f"{key}.npz")
            if cached is not None:
                parts, decomposition = cached
                return cls(parts, decomposition)
        start = time.perf_counter()
        parts = _decompose(loaded, decompose, parameters, progress)
        seconds = time.perf_counter() - start
        body = cls(parts)
        deviation = measure_deviation(loaded, body, samples=samples, seed=seed)
        body.decomposition = Decomposition(
            method=decompose or "none",
            parameters=parameters,
            parts=len(parts),
            seconds=seconds,
            mesh_hash=mesh_hash(loaded),
            **deviation,
        )
        if folder is not None:
            _write_cache(folder / f"{key}.npz", parts, body.decomposition)
        return body

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Write the parts (and the decomposition, if any) to a ``.npz`` file ``load`` reads.

        The file holds ``points`` (every part's points, part after part), ``offsets`` (where
        each part starts in ``points``, and the total) and ``decomposition`` (JSON, or empty).
        """
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
        loaded = _read_parts(Path(path))
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
    ``Decomposition`` (which says what they mean).

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
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)):
        raise TypeError(f"samples must be an integer, got {type(samples).__name__}")
    if samples < 1:
        raise ValueError(f"samples must be at least 1, got {samples}")
    parts = body.parts
    # Points on the mesh's surface, and their exact distance to the union of the parts.
    on_mesh, _ = trimesh.sample.sample_surface(mesh, samples, seed=seed)
    to_parts = np.full(len(on_mesh), np.inf)
    singles = on_mesh[:, None, :]
    for part in parts:
        to_parts = np.minimum(to_parts, _core.Query("exact").distance_many(
            [part] * len(on_mesh), singles, threads=None).distance)
    # Points on the parts' surfaces (in proportion to their areas), and their distance to the
    # mesh's solid: outside a watertight mesh its signed distance (trimesh: positive inside),
    # else the distance to its surface, which can only overstate.
    hulls = trimesh.util.concatenate(
        [trimesh.Trimesh(p.vertices, p.hull().faces, process=False) for p in parts
         if p.hull().dimension == 3]
    ) if any(p.hull().dimension == 3 for p in parts) else None
    if hulls is not None and len(hulls.faces):
        on_parts, _ = trimesh.sample.sample_surface(hulls, samples, seed=seed + 1)
        if mesh.is_watertight:
            outside = np.maximum(-trimesh.proximity.signed_distance(mesh, on_parts), 0.0)
        else:
            outside = trimesh.proximity.closest_point(mesh, on_parts)[1]
        parts_to_mesh = float(outside.max())
        area = max(mesh.area, hulls.area)
    else:
        parts_to_mesh, area = 0.0, mesh.area
    return {
        "parts_to_mesh": parts_to_mesh,
        "mesh_to_parts": float(to_parts.max()),
        "samples": int(samples),
        "spacing": float(np.sqrt(area / samples)),
    }


def _parameters(decompose, concavity, max_hulls, max_hull_vertices, resolution, seed):
    if decompose not in DECOMPOSERS:
        raise ValueError(
            f"decompose must be one of 'coacd', 'vhacd', 'hull' or None, got {decompose!r}"
        )
    if decompose in ("hull", None):
        return {}
    if not (isinstance(concavity, (int, float)) and 0 < concavity <= 1):
        raise ValueError(f"concavity must be a number in (0, 1], got {concavity!r}")
    if max_hulls is not None and not (isinstance(max_hulls, int) and max_hulls >= 1):
        raise ValueError(f"max_hulls must be a positive integer or None, got {max_hulls!r}")
    if not (isinstance(max_hull_vertices, int) and max_hull_vertices >= 4):
        raise ValueError(f"max_hull_vertices must be an integer >= 4, got {max_hull_vertices!r}")
    if resolution is not None and not (isinstance(resolution, int) and resolution >= 1):
        raise ValueError(f"resolution must be a positive integer or None, got {resolution!r}")
    if not (isinstance(seed, int) and seed >= 0):
        raise ValueError(f"seed must be a nonnegative integer, got {seed!r}")
    if decompose == "coacd":
        return {
            "threshold": float(concavity),
            "max_convex_hull": -1 if max_hulls is None else max_hulls,
            "max_ch_vertex": max_hull_vertices,
            "resolution": 2000 if resolution is None else resolution,
            "seed": seed,
        }
    return {
        "maxConvexHulls": DEFAULT_VHACD_MAX_HULLS if max_hulls is None else max_hulls,
        "minimumVolumePercentErrorAllowed": 100.0 * concavity,
        "maxNumVerticesPerCH": max_hull_vertices,
        "resolution": DEFAULT_VHACD_RESOLUTION if resolution is None else resolution,
    }


def _decompose(mesh, decompose, parameters, progress) -> List[np.ndarray]:
    if decompose == "hull":
        return [np.asarray(mesh.convex_hull.vertices, dtype=float)]
    if decompose is None:
        return _convex_components(mesh)
    if decompose == "coacd":
        import coacd

        coacd.set_log_level("error")

        def run() -> List[np.ndarray]:
            hulls = coacd.run_coacd(coacd.Mesh(mesh.vertices, mesh.faces), **parameters)
            return [np.asarray(v, dtype=float) for v, _ in hulls]

        return _with_progress("CoACD", run, progress)
    import vhacdx

    def run() -> List[np.ndarray]:
        hulls = vhacdx.compute_vhacd(np.asarray(mesh.vertices, dtype=np.float64),
                                     np.asarray(mesh.faces, dtype=np.uint32), **parameters)
        return [np.asarray(v, dtype=float) for v, _ in hulls]

    return _with_progress("V-HACD", run, progress)


def _convex_components(mesh) -> List[np.ndarray]:
    components = mesh.split(only_watertight=False)
    parts = []
    for index, component in enumerate(components):
        if not component.is_convex:
            raise ValueError(
                f"decompose=None needs convex parts, but part {index} of {len(components)} "
                f"(the connected component with {len(component.faces)} triangles around "
                f"{np.round(component.centroid, 6).tolist()}) is not convex; use "
                "decompose='coacd' or 'vhacd' to split it, or 'hull' for its hull"
            )
        parts.append(np.asarray(component.vertices, dtype=float))
    return parts


def _with_progress(label: str, run: Callable[[], List[np.ndarray]],
                   enabled: bool) -> List[np.ndarray]:
    """``run()`` in a worker thread; once it has taken over a second, a tqdm bar shows the time
    it has run (decomposers report no progress of their own), then how many parts it made."""
    if not enabled:
        return run()
    outcome: Dict[str, Any] = {}

    def work() -> None:
        try:
            outcome["parts"] = run()
        except BaseException as error:  # handed to the caller below
            outcome["error"] = error

    worker = threading.Thread(target=work, name=f"swarmcollide {label}", daemon=True)
    start = time.perf_counter()
    worker.start()
    bar = None
    while worker.is_alive():
        worker.join(0.2)
        if bar is None and worker.is_alive() and time.perf_counter() - start > _PROGRESS_DELAY:
            from tqdm import tqdm

            bar = tqdm(desc=f"{label} decomposing", bar_format="{desc}: {elapsed}",
                       leave=False, file=sys.stderr)
            bar.start_t -= time.perf_counter() - start  # the time since the decomposer started
        if bar is not None:
            bar.refresh()
    if bar is not None:
        bar.set_description_str(f"{label}: {len(outcome.get('parts', []))} parts")
        bar.close()
    if "error" in outcome:
        raise outcome["error"]
    return outcome["parts"]


def _cache_key(mesh, decompose, parameters, samples) -> str:
    package = {"coacd": "coacd", "vhacd": "vhacdx"}.get(decompose or "")
    try:
        decomposer = version(package) if package else ""
    except PackageNotFoundError:  # pragma: no cover - the mesh extra installs both
        decomposer = ""
    description = json.dumps(
        [_CACHE_FORMAT, mesh_hash(mesh), decompose, parameters, decomposer, samples],
        sort_keys=True,
    )
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
    path.parent.mkdir(parents=True, exist_ok=True)
    # Written beside and renamed, so that a reader never sees half a file.
    with tempfile.NamedTemporaryFile(dir=path.parent, suffix=".npz", delete=False) as handle:
        np.savez(handle, points=points, offsets=offsets, decomposition=np.array(meta))
    os.replace(handle.name, path)


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
        decomposition = Decomposition(**json.loads(meta)) if meta else None
    except (OSError, ValueError, KeyError, EOFError, TypeError, zipfile.BadZipFile):
        return None  # unreadable, not an .npz, or a record that is not a Decomposition's
    if (points.ndim != 2 or points.shape[1] != 3 or points.dtype.kind not in "fiu"
            or offsets.ndim != 1 or offsets.dtype.kind not in "iu" or len(offsets) < 2
            or offsets[0] != 0 or offsets[-1] != len(points) or np.any(np.diff(offsets) < 1)):
        return None  # each part's points, in order, and every point in one part
    parts = [points[offsets[k]:offsets[k + 1]] for k in range(len(offsets) - 1)]
    return parts, decomposition


def _write_cache(path: Path, parts, decomposition: Decomposition) -> None:
    try:
        _write_parts(path, parts, decomposition)
    except OSError:
        pass  # a cache that cannot be written costs time, never the answer


def _read_cache(path: Path):
    if not path.is_file():
        return None
    loaded = _read_parts(path)
    if loaded is None or loaded[1] is None:
        return None
    parts, decomposition = loaded
    return parts, Decomposition(**{**asdict(decomposition), "from_cache": True})
