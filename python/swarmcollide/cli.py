"""Command line: ``swarmcollide distance a.obj b.stl`` measures the distance between two mesh
files (decomposed into convex parts); ``swarmcollide decompose mesh.obj -o parts.npz`` writes a
mesh's convex parts; ``swarmcollide paper`` reproduces the paper's Section IV; ``swarmcollide
scene`` runs a scene of moving bodies and prints each frame; ``swarmcollide robot MODEL`` checks
a robot (URDF or MJCF) at random configurations.

Exit status: 0 on success, 1 when an input cannot be used (a missing or unreadable file, a mesh
that is not a 3-D solid, a query the method cannot answer), 2 for wrong arguments (an unknown
method, a value out of range, a pose that is not rigid, a picture into a folder that does not
exist). Either way one line on standard error says what is wrong; never a traceback."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from . import _core, paper, robot_cli

POSE_HELP = (
    "where the body is: 3 numbers (a translation x,y,z), 6 (a translation and then rotations "
    "about x, y and z in degrees, applied in that order) or 16 (a 4x4 transform, row by row), "
    "separated by commas or spaces (write --pose-a=-1,0,0 when the first is negative); "
    "default: the identity"
)


def _pose(text: str) -> np.ndarray:
    """A pose from the command line (see POSE_HELP); argparse turns ValueError into a usage
    error naming the option."""
    try:
        values = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a list of numbers") from None
    matrix = np.eye(4)
    if len(values) in (3, 6):
        matrix[:3, 3] = values[:3]
        if len(values) == 6:
            rx, ry, rz = np.radians(values[3:])
            c, s = np.cos([rx, ry, rz]), np.sin([rx, ry, rz])
            x = np.array([[1, 0, 0], [0, c[0], -s[0]], [0, s[0], c[0]]])
            y = np.array([[c[1], 0, s[1]], [0, 1, 0], [-s[1], 0, c[1]]])
            z = np.array([[c[2], -s[2], 0], [s[2], c[2], 0], [0, 0, 1]])
            matrix[:3, :3] = z @ y @ x
    elif len(values) == 16:
        matrix = np.array(values).reshape(4, 4)
    else:
        raise argparse.ArgumentTypeError(
            f"a pose has 3, 6 or 16 numbers, got {len(values)} in {text!r}"
        )
    if not np.isfinite(matrix).all():
        raise argparse.ArgumentTypeError(f"{text!r} has a NaN or infinite number")
    return matrix


def _integer(low: int, high: Optional[int] = None) -> Callable[[str], int]:
    """An argparse type: an integer in [low, high] (no upper end when high is None)."""
    span = f"at least {low}" if high is None else f"in [{low}, {high}]"

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
        if value < low or (high is not None and value > high):
            raise argparse.ArgumentTypeError(f"must be an integer {span}, got {value}")
        return value

    return parse


def _concavity(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not 0 < value <= 1:  # NaN fails too
        raise argparse.ArgumentTypeError(f"must be a number in (0, 1], got {text}")
    return value


_SEED = _integer(0, 2**64 - 1)

MAX_SCENE_BODIES = 100_000
"""The most bodies ``scene`` makes: more would ask for memory the demo has no use for."""


def _add_decomposer_options(parser: argparse.ArgumentParser, default: str) -> None:
    from .mesh import DEFAULT_CONCAVITY, DEFAULT_MAX_HULL_VERTICES

    group = parser.add_argument_group("convex decomposition")
    group.add_argument(
        "--decompose", choices=["coacd", "vhacd", "hull", "none"], default=default,
        help=f"how meshes become convex parts: CoACD (closest, seconds to minutes), V-HACD "
        f"(faster, coarser), their convex hull, or 'none' for meshes whose connected components "
        f"are convex already (default: {default})",
    )
    group.add_argument("--preset", choices=["fast", "quality"], default="fast",
                       help="CoACD's settings: fast (seconds) or quality (minutes) (default: fast)")
    group.add_argument("--concavity", type=_concavity, default=None,
                       help=f"CoACD's concavity threshold; V-HACD's volume error as a fraction "
                       f"(default: the preset's, {DEFAULT_CONCAVITY} for fast)")
    group.add_argument("--max-hulls", type=_integer(1), default=None,
                       help="at most this many parts (default: CoACD unlimited, V-HACD 32)")
    group.add_argument("--max-hull-vertices", type=_integer(4), default=None,
                       help=f"at most this many vertices per part (default: CoACD's exact hulls, "
                       f"V-HACD {DEFAULT_MAX_HULL_VERTICES})")
    group.add_argument("--resolution", type=_integer(1), default=None,
                       help="CoACD's sampling resolution or V-HACD's voxel count")
    group.add_argument("--seed", type=_SEED, default=0, help="decomposition seed (default 0)")
    group.add_argument("--no-cache", action="store_true",
                       help="decompose again instead of reading the on-disk cache "
                       "($SWARMCOLLIDE_CACHE_DIR, else the user cache directory)")
    group.add_argument("--quiet", action="store_true", help="no progress bar")


def _body(path: str, arguments: argparse.Namespace):
    """A compound body from a mesh file, from a parts file (.npz) as decompose writes, or from a
    shape file (.json: a record of swarmcollide.shape_json)."""
    from .mesh import CompoundBody

    if path.endswith(".npz"):
        return CompoundBody.load(path)
    if path.endswith(".json"):
        return CompoundBody(_shape_parts(path))
    return CompoundBody.from_mesh(
        path,
        decompose=None if arguments.decompose == "none" else arguments.decompose,
        preset=arguments.preset,
        concavity=arguments.concavity,
        max_hulls=arguments.max_hulls,
        max_hull_vertices=arguments.max_hull_vertices,
        resolution=arguments.resolution,
        seed=arguments.seed,
        cache=not arguments.no_cache,
        progress=not arguments.quiet,
    )


def _shape_parts(path: str) -> list:
    """The parts of the body a shape file (.json) describes: a compound's parts, or the one
    shape; ValueError naming the file for one that is not a record."""
    from .shape_json import body_from_json

    try:
        with open(path, encoding="utf-8") as handle:
            record = json.load(handle)
    except OSError as error:
        raise ValueError(f"cannot read the shape file {path!r}: {error.strerror}") from None
    except json.JSONDecodeError as error:
        raise ValueError(f"shape file {path!r} is not JSON: {error}") from None
    except ValueError as error:  # an integer of more digits than Python converts (4,300)
        raise ValueError(f"shape file {path!r} cannot be read: {error}") from None
    except RecursionError:
        raise ValueError(f"shape file {path!r} nests deeper than Python's JSON reader follows "
                         f"(about {sys.getrecursionlimit()} levels); a shape file holds one "
                         f"record, and a compound's parts are shapes, never compounds") from None
    try:
        body = body_from_json(record, name=path)
    except TypeError as error:
        raise ValueError(str(error)) from None
    return list(body.parts) if isinstance(body, _core.CompoundBody) else [body]


def _decomposition(body) -> Optional[dict]:
    d = body.decomposition
    if d is None:
        return None
    return {"method": d.method, "parts": d.parts, "seconds": d.seconds,
            "parts_to_mesh": d.parts_to_mesh, "mesh_to_parts": d.mesh_to_parts,
            "samples": d.samples, "spacing": d.spacing, "from_cache": d.from_cache,
            "parameters": d.parameters}


def _distance(arguments: argparse.Namespace) -> int:
    from .mesh import load_mesh
    from .queries import query

    q = query(arguments.method, tolerance=arguments.tolerance)
    ask = {"distance": q.distance, "signed": q.signed_distance,
           "collide": q.collision}[arguments.query]
    # A query the method cannot answer is refused (in the core's words) before any file is read,
    # and both files are checked before either is decomposed, which can take minutes.
    ask([[0.0, 0.0, 0.0]], [[0.0, 0.0, 0.0]])
    for path in (arguments.a, arguments.b):
        if not path.endswith((".npz", ".json")):
            load_mesh(path)
    a = _body(arguments.a, arguments)
    b = _body(arguments.b, arguments)
    r = ask(a, b, arguments.pose_a, arguments.pose_b)
    assert isinstance(r, _core.CompoundResult)  # the files' bodies are compound: parts named
    if arguments.plot:
        from .plot import plot_pair

        plot_pair(a, b, r, pose_a=arguments.pose_a, pose_b=arguments.pose_b, path=arguments.plot)
    answer = {
        "query": arguments.query,
        "method": r.method,
        "distance": r.distance,
        "lower_bound": r.lower_bound,
        "colliding": bool(r.colliding),
        "certified": bool(r.certified),
        "part_a": r.part_a,
        "part_b": r.part_b,
        "point_a": r.point_a.tolist(),
        "point_b": r.point_b.tolist(),
        "direction": r.direction.tolist(),
        "part_pairs": r.stats.part_pairs,
        "solved": r.stats.solved,
        "pruned": r.stats.pruned,
        "a": {"file": arguments.a, "parts": len(a), "decomposition": _decomposition(a)},
        "b": {"file": arguments.b, "parts": len(b), "decomposition": _decomposition(b)},
    }
    for side, path, body in (("a", arguments.a, a), ("b", arguments.b, b)):
        if path.endswith(".json"):  # shapes read from JSON are written back as JSON
            from .shape_json import body_to_json

            answer[side]["shape"] = body_to_json(body)
    if arguments.json:
        print(json.dumps(answer, indent=2))
        return 0
    value = "signed distance" if arguments.query == "signed" else "distance"
    if arguments.query == "collide":
        print(f"colliding: {'yes' if r.colliding else 'no'}"
              f" ({'certified' if r.certified else 'not certified'} for the convex parts)")
    else:
        print(f"{value}: {r.distance:.9g} (lower bound {r.lower_bound:.9g}, "
              f"{'certified' if r.certified else 'not certified'} for the convex parts)")
    print(f"parts: {r.part_a} of {arguments.a} and {r.part_b} of {arguments.b}; "
          f"{r.stats.solved} of {r.stats.part_pairs} part pairs solved, {r.stats.pruned} pruned")
    print(f"witnesses: {np.round(r.point_a, 9).tolist()} and {np.round(r.point_b, 9).tolist()}")
    for name, body in ((arguments.a, a), (arguments.b, b)):
        d = body.decomposition
        if d is not None:
            print(f"{name}: {d.parts} {d.method} parts, {d.parts_to_mesh:.3g} beyond the mesh, "
                  f"{d.mesh_to_parts:.3g} of the mesh missed ({d.samples} samples)")
    return 0


def _decompose(arguments: argparse.Namespace) -> int:
    # A parts file or a shape file is convex parts already: there is no mesh to decompose (and no
    # decomposition record to report).
    for suffix, kind in ((".npz", "a parts file"), (".json", "a shape file")):
        if arguments.mesh.endswith(suffix):
            raise ValueError(
                f"{arguments.mesh}: decompose reads a mesh file (.obj, .stl, .ply, .off, .glb); "
                f"this is {kind}, convex parts already, which `swarmcollide distance` takes as "
                "it is")
    body = _body(arguments.mesh, arguments)
    body.save(arguments.output)
    d = body.decomposition
    if arguments.json:
        summary = _decomposition(body)
        assert summary is not None  # a body made by decomposing has its decomposition
        print(json.dumps({"mesh": arguments.mesh, "output": arguments.output, **summary},
                         indent=2))
        return 0
    print(f"{arguments.output}: {d.parts} convex parts ({d.method}"
          f"{', from the cache' if d.from_cache else ''}, {d.seconds:.2f} s)")
    print(f"parts stick out of the mesh by up to {d.parts_to_mesh:.4g} and miss it by up to "
          f"{d.mesh_to_parts:.4g} (one-sided Hausdorff distances, {d.samples} samples on each "
          f"surface, spacing {d.spacing:.3g})")
    return 0


def _parser() -> Tuple[argparse.ArgumentParser, Dict[str, argparse.ArgumentParser]]:
    """The command line's parser, and each verb's own (whose errors show that verb's usage)."""
    from .queries import METHODS

    parser = argparse.ArgumentParser(prog="swarmcollide", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)

    measure = commands.add_parser(
        "distance", help="distance (or signed distance, or collision) between two mesh files",
        description="Distance between two bodies given as mesh files (OBJ, STL, PLY, GLB, OFF: "
        "decomposed into convex parts), parts files (.npz, from 'swarmcollide decompose') or "
        "shape files (.json: a record such as {\"shape\": \"cylinder\", \"radius\": 0.5, "
        "\"half_length\": 1}, see swarmcollide.shape_json). "
        "Answers are certified for the convex parts; each body's decomposition error says how "
        "far the parts are from its mesh.")
    measure.add_argument("a", help="the first body: a mesh file, a parts file (.npz) or a shape "
                         "file (.json)")
    measure.add_argument("b", help="the second body")
    measure.add_argument("--pose-a", type=_pose, default=None, metavar="POSE", help=POSE_HELP)
    measure.add_argument("--pose-b", type=_pose, default=None, metavar="POSE", help=POSE_HELP)
    measure.add_argument("--query", choices=["distance", "signed", "collide"], default="distance",
                         help="what to compute (default: distance)")
    measure.add_argument("--method", default="dual", choices=list(METHODS),
                         help="the solver for each part pair (default: dual)")
    measure.add_argument("--tolerance", type=float, default=1e-9,
                         help="relative to the pair's size (default 1e-9)")
    measure.add_argument("--json", action="store_true", help="print the answer as JSON")
    measure.add_argument("--plot", metavar="FILE",
                         help="save a picture of the pair and the answer (needs matplotlib)")
    _add_decomposer_options(measure, "coacd")

    split = commands.add_parser(
        "decompose", help="decompose a mesh file into convex parts (an .npz file)",
        description="Decompose a mesh file into convex parts and write them to an .npz file "
        "(points, offsets and the decomposition's record), which 'swarmcollide distance' and "
        "CompoundBody.load read.")
    split.add_argument("mesh", help="a mesh file (OBJ, STL, PLY, GLB, OFF)")
    split.add_argument("-o", "--output", required=True, help="the parts file to write (.npz)")
    split.add_argument("--json", action="store_true", help="print the record as JSON")
    _add_decomposer_options(split, "coacd")

    reproduce = commands.add_parser(
        "paper", help="print the paper's Tables 1 and 2 beside ours and the exact answers"
    )
    reproduce.add_argument("--seed", type=_SEED, default=0, help="solver seed (default 0)")
    reproduce.add_argument(
        "--repeats", type=_integer(1), default=20, help="runs per row; the median time is shown"
    )
    scene = commands.add_parser(
        "scene",
        help="boxes and random hulls moving through each other: contacts and times per frame",
    )
    scene.add_argument("--bodies", type=_integer(2, MAX_SCENE_BODIES), default=300,
                       help="number of bodies (default 300)")
    scene.add_argument("--frames", type=_integer(1), default=60,
                       help="number of frames (default 60)")
    scene.add_argument("--seed", type=_SEED, default=0, help="seed of the bodies and their motion")
    scene.add_argument("--threads", type=_integer(1), default=None, help="narrowphase threads")
    scene.add_argument(
        "--cold", action="store_true", help="answer every frame from scratch (no warm start)"
    )
    scene.add_argument(
        "--plot", metavar="FILE", help="save a picture of the last frame there (needs matplotlib)"
    )
    robot_cli.add_parser(commands, _integer, _SEED)
    return parser, commands.choices


def _check_picture(parser: argparse.ArgumentParser, path: Optional[str]) -> None:
    """A usage error, before any work, for a picture matplotlib could not save at ``path``."""
    if path is None:
        return
    folder = Path(path).parent
    if not folder.is_dir():
        parser.error(f"argument --plot: the folder {str(folder)!r} does not exist")
    try:
        from matplotlib.figure import Figure
    except ImportError:
        parser.error("argument --plot needs matplotlib: pip install 'swarmcollide[plot]'")
    formats = Figure().canvas.get_supported_filetypes()
    if Path(path).suffix.lstrip(".").lower() not in formats:
        parser.error(f"argument --plot: {path!r} does not end in a picture format matplotlib "
                     f"writes ({', '.join('.' + f for f in sorted(formats))})")


# The options that name the core's arguments, for its messages ("pose_a must ...").
_OPTION_OF = {"tolerance": "--tolerance", "pose_a": "--pose-a", "pose_b": "--pose-b",
              "threads": "--threads"}


def _check_core(parser: argparse.ArgumentParser, check: Callable[[], object]) -> None:
    """Run ``check`` (the core validating options); a ValueError or TypeError is a usage error
    naming the option."""
    try:
        check()
    except (ValueError, TypeError) as error:
        message = str(error)
        first = message.replace("'", " ").split(" ", 1)[0]
        option = _OPTION_OF.get(first)
        parser.error(f"argument {option}: {message}" if option else message)


def main(argv: Optional[Sequence[str]] = None) -> int:
    top, verbs = _parser()
    arguments = top.parse_args(argv)
    # Errors found after parsing are the verb's: its usage, not the list of verbs.
    parser = verbs[arguments.command]
    if arguments.command in ("distance", "scene", "robot"):
        _check_picture(parser, arguments.plot)
    if arguments.command == "robot":
        robot_cli.check_arguments(parser, arguments)
    if arguments.command == "distance":
        from .queries import query

        # The options through collision, which every method answers: a query the method cannot
        # answer is an unusable input (exit 1, said by _distance), not a wrong option.
        point = [[0.0, 0.0, 0.0]]
        _check_core(parser, lambda: query(arguments.method, tolerance=arguments.tolerance)
                    .collision(point, point, arguments.pose_a, arguments.pose_b))
    if arguments.command == "scene":
        _check_core(parser, lambda: _core.Scene(threads=arguments.threads, seed=arguments.seed))
    if arguments.command == "decompose" and not arguments.output.endswith(".npz"):
        parser.error("-o/--output must name an .npz file")
    try:
        return _run(arguments)
    except BrokenPipeError:  # the reader went away (`| head`): nothing more to say
        return 0
    except (ValueError, TypeError, OSError, ImportError, MemoryError) as error:
        print(f"swarmcollide {arguments.command}: error: {error}", file=sys.stderr)
        return 1


def _run(arguments: argparse.Namespace) -> int:
    if arguments.command == "distance":
        return _distance(arguments)
    if arguments.command == "decompose":
        return _decompose(arguments)
    if arguments.command == "robot":
        return robot_cli.run(arguments)
    if arguments.command == "paper":
        print(paper.reproduce(seed=arguments.seed, repeats=arguments.repeats))
        return 0
    from . import scene_demo

    scene_demo.run(
        arguments.bodies,
        arguments.frames,
        seed=arguments.seed,
        threads=arguments.threads,
        warm_start=not arguments.cold,
        plot=arguments.plot,
    )
    return 0
