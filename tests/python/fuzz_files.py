"""The census of the edges around the queries: mesh files, the command line, and what users pass.

``make_file_case(seed, index)`` is a pure function, like ``fuzz_cases.make_case``; a case is
rebuilt from its id in a sandboxed child (``run_file_case``), which writes the case's files into a
fresh folder and makes the call. Families (``FILE_FAMILIES``):

mesh
    ``load_mesh``, ``CompoundBody.from_mesh`` and ``CompoundBody.load`` on good and odd files
    (garbage bytes, empty, truncated, NaN, flat and tilted-flat STL, point clouds, parts files
    with broken offsets, keys or records, directories, missing paths) and odd arguments.
cli
    ``swarmcollide distance | decompose | scene | paper`` with good and odd files and option
    values, as a shell user would type them.
natural
    What users pass from other libraries: ``trimesh.Trimesh`` bodies, SciPy ``Rotation`` in
    poses, ``(3, 4)`` poses, quaternions through ``pose_from_quaternion``; answers are checked
    against ``minkowski_oracle``.

Judged (``FILE_CATEGORIES``): an error due must be a ValueError or TypeError (the CLI: exit status
2 for a wrong argument, 1 for an input it cannot use) whose message names the argument or file;
an answer due must come, and be right; nothing may crash, hang or print a traceback.
"""

from __future__ import annotations

import contextlib
import io
import os
import struct
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np

ANSWER, ERROR, EITHER = "answer", "error", "answer or error"

FILE_CATEGORIES = (
    "ok", "crash", "hang", "traceback", "unclear", "refused", "slipped", "wrong", "suite-error",
)  # fmt: skip
"""ok; crash and hang (the sandbox's); traceback (the CLI let an exception out); unclear (an
error of another type, exit status or message that does not name the argument); refused (an
answer was due); slipped (bad input answered); wrong (an answer off the oracle, or a certified
one that is not right)."""

FILE_FAILURES = frozenset(FILE_CATEGORIES) - {"ok", "suite-error"}

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
CUBE_FACES = np.array([
    [0, 3, 2], [0, 1, 3], [4, 7, 5], [4, 6, 7], [0, 5, 1], [0, 4, 5],
    [2, 7, 6], [2, 3, 7], [0, 6, 4], [0, 2, 6], [1, 7, 3], [1, 5, 7],
])  # fmt: skip
"""The unit cube's triangles, outward."""


@dataclass(frozen=True)
class FileCase:
    """One call and what is due: ``expect``, and for an error the fragments one of which the
    message must hold (and for the CLI, the exit statuses it may end with)."""

    id: str
    family: str
    call: str
    note: str
    files: Dict[str, bytes] = field(default_factory=dict)
    arguments: Tuple[Any, ...] = ()
    keywords: Dict[str, Any] = field(default_factory=dict)
    expect: str = ANSWER
    names: Tuple[str, ...] = ()
    statuses: Tuple[int, ...] = (1, 2)
    truth: Optional[float] = None
    """The distance due (CLI and natural answers), checked within 1e-6 of the size."""

    @property
    def label(self) -> str:
        return self.call


# ----- files -------------------------------------------------------------------------------------


def _box(rng: np.random.Generator) -> np.ndarray:
    return CUBE * rng.uniform(0.2, 2.0, 3) + rng.uniform(-5, 5, 3)


def obj_text(points: np.ndarray, faces: Optional[np.ndarray] = CUBE_FACES) -> bytes:
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(points, dtype=float).tolist()]
    if faces is not None:
        lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    return ("\n".join(lines) + "\n").encode()


def stl_binary(points: np.ndarray, faces: np.ndarray = CUBE_FACES, count: Optional[int] = None
               ) -> bytes:
    """A binary STL (float32 corners); ``count`` overrides the triangle count of the header."""
    triangles = np.asarray(points, dtype=np.float32)[faces]
    body = b"".join(struct.pack("<3f", 0, 0, 0) + t.tobytes() + b"\0\0" for t in triangles)
    return b"\0" * 80 + struct.pack("<I", len(faces) if count is None else count) + body


def _tilted_square(rng: np.random.Generator) -> np.ndarray:
    """Four corners of a square in a random plane (not axis-aligned), at unit scale."""
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    return square @ q.T * rng.uniform(0.5, 100) + rng.uniform(-10, 10, 3)


def npz_bytes(**arrays: Any) -> bytes:
    handle = io.BytesIO()
    np.savez(handle, **arrays)
    return handle.getvalue()


def _parts_file(rng: np.random.Generator) -> Tuple[bytes, str, str]:
    """A parts file, good or broken in one way: (bytes, note, expect)."""
    points = np.vstack([_box(rng), _box(rng)])
    offsets = np.array([0, 8, 16])
    kind = str(rng.choice([
        "good", "garbage", "zip-garbage", "npy", "no-offsets", "offsets-decreasing",
        "offsets-beyond", "offsets-short", "offsets-float", "offsets-negative", "points-2d",
        "points-complex", "points-nan", "record-not-json", "record-wrong-keys", "record-list",
        "points-str",
    ]))  # fmt: skip
    record = np.array("")
    if kind == "good":
        return npz_bytes(points=points, offsets=offsets, decomposition=record), kind, ANSWER
    if kind == "garbage":
        return rng.bytes(int(rng.integers(0, 400))), kind, ERROR
    if kind == "zip-garbage":
        return b"PK\x03\x04" + rng.bytes(int(rng.integers(0, 400))), kind, ERROR
    if kind == "npy":
        handle = io.BytesIO()
        np.save(handle, points)
        return handle.getvalue(), kind, ERROR
    changed: Dict[str, Any] = {"points": points, "offsets": offsets, "decomposition": record}
    if kind == "no-offsets":
        del changed["offsets"]
    elif kind == "offsets-decreasing":
        changed["offsets"] = np.array([0, 12, 4, 16])
    elif kind == "offsets-beyond":
        changed["offsets"] = np.array([0, 8, 40])
    elif kind == "offsets-short":
        changed["offsets"] = np.array([0, 8])  # drops the second part's points
    elif kind == "offsets-float":
        changed["offsets"] = offsets.astype(float) + 0.5
    elif kind == "offsets-negative":
        changed["offsets"] = np.array([-8, 8, 16])
    elif kind == "points-2d":
        changed["points"] = points[:, :2]
    elif kind == "points-complex":
        changed["points"] = points + 1j
    elif kind == "points-nan":
        changed["points"] = np.where(rng.random(points.shape) < 0.1, np.nan, points)
    elif kind == "points-str":
        changed["points"] = points.astype(str)
    elif kind == "record-not-json":
        changed["decomposition"] = np.array("{not json")
    elif kind == "record-wrong-keys":
        changed["decomposition"] = np.array('{"method": "coacd", "bogus": 1}')
    elif kind == "record-list":
        changed["decomposition"] = np.array("[1, 2]")
    return npz_bytes(**changed), kind, ERROR


def _mesh_file(rng: np.random.Generator) -> Tuple[str, bytes, str, str, Optional[np.ndarray]]:
    """A mesh file, good or odd: (name, bytes, note, expect, the box it holds if good)."""
    kind = str(rng.choice([
        "box-obj", "box-stl", "box-off", "garbage-obj", "garbage-stl", "garbage-ply",
        "garbage-glb", "empty-obj", "empty-stl", "truncated-stl", "stl-huge-count", "nan-obj",
        "inf-obj", "flat-stl", "tilted-flat-stl", "tilted-flat-obj", "line-obj", "cloud-obj",
        "faces-out-of-range-obj", "huge-obj", "tiny-obj", "no-extension", "unknown-extension",
    ]))  # fmt: skip
    box = _box(rng)
    if kind == "box-obj":
        return "box.obj", obj_text(box), kind, ANSWER, box
    if kind == "box-stl":
        return "box.stl", stl_binary(box), kind, ANSWER, box.astype(np.float32).astype(float)
    if kind == "box-off":
        text = "OFF\n8 12 0\n" + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in box.tolist())
        text += "".join(f"3 {a} {b} {c}\n" for a, b, c in CUBE_FACES)
        return "box.off", text.encode(), kind, ANSWER, box
    if kind.startswith("garbage"):
        ext = kind.split("-")[1]
        return f"garbage.{ext}", rng.bytes(int(rng.integers(1, 2000))), kind, ERROR, None
    if kind.startswith("empty"):
        return f"empty.{kind.split('-')[1]}", b"", kind, ERROR, None
    if kind == "truncated-stl":
        data = stl_binary(box)
        return "cut.stl", data[: int(rng.integers(84, len(data) - 1))], kind, EITHER, None
    if kind == "stl-huge-count":
        return "huge.stl", stl_binary(box, count=2**32 - 1), kind, EITHER, None
    if kind in ("nan-obj", "inf-obj"):
        bad = box.copy()
        bad[int(rng.integers(8)), int(rng.integers(3))] = np.nan if kind == "nan-obj" else np.inf
        return "bad.obj", obj_text(bad), kind, ERROR, None
    if kind == "flat-stl":
        flat = box.copy()
        flat[:, 2] = 0.25
        return "flat.stl", stl_binary(flat), kind, ERROR, None
    if kind.startswith("tilted-flat"):
        square = _tilted_square(rng)
        faces = np.array([[0, 1, 2], [0, 2, 3]])
        data = stl_binary(square, faces) if kind.endswith("stl") else obj_text(square, faces)
        return f"tilted.{kind[-3:]}", data, kind, ERROR, None
    if kind == "line-obj":
        line = np.outer(np.arange(4.0), rng.normal(size=3))
        return "line.obj", obj_text(line, np.array([[0, 1, 2], [1, 2, 3]])), kind, ERROR, None
    if kind == "cloud-obj":
        return "cloud.obj", obj_text(rng.normal(size=(20, 3)), None), kind, ERROR, None
    if kind == "faces-out-of-range-obj":
        return "faces.obj", obj_text(box, CUBE_FACES + 5), kind, EITHER, None
    if kind == "huge-obj":
        return "huge.obj", obj_text(box * 1e300), kind, EITHER, None
    if kind == "tiny-obj":
        return "tiny.obj", obj_text(box * 1e-300), kind, EITHER, None
    if kind == "no-extension":
        return "box", obj_text(box), kind, EITHER, None
    return "box.xyz", obj_text(box), kind, EITHER, None


# ----- the families ------------------------------------------------------------------------------


def _mesh(rng: np.random.Generator, case_id: str) -> FileCase:
    roll = rng.random()
    if roll < 0.25:
        data, kind, expect = _parts_file(rng)
        return FileCase(case_id, "mesh", "CompoundBody.load", f"parts:{kind}", {"parts.npz": data},
                        ("{dir}/parts.npz",), {}, expect, ("parts.npz",))  # fmt: skip
    if roll < 0.35:
        kind = str(rng.choice(["missing", "directory", "none", "number", "bytes-path", "list"]))
        target: Any = {"missing": "{dir}/missing.obj", "directory": "{dir}", "none": None,
                       "number": 42, "bytes-path": b"box.obj", "list": ["box.obj"]}[kind]
        call = str(rng.choice(["load_mesh", "CompoundBody.from_mesh", "CompoundBody.load"]))
        names = {"missing": ("missing.obj",), "directory": ("{dir}",)}.get(
            kind, ("mesh", "path", "file"))
        return FileCase(case_id, "mesh", call, f"target:{kind}", {}, (target,), {}, ERROR, names)
    if roll < 0.5:
        # Odd keywords of from_mesh on a good mesh.
        name, value = [
            ("decompose", "bogus"), ("decompose", b"hull"), ("decompose", 3),
            ("concavity", float("nan")), ("concavity", -1.0), ("concavity", "0.1"),
            ("max_hulls", 0), ("max_hull_vertices", 3), ("resolution", -5), ("seed", -1),
            ("samples", 0), ("samples", 2.5), ("samples", -3), ("cache", 3), ("progress", "yes"),
        ][int(rng.integers(15))]
        box = _box(rng)
        # V-HACD reads every setting (the hull reads none) and takes a box in a fraction of a second.
        keywords = {"decompose": "vhacd", "cache": False, "progress": False, "samples": 200,
                    "resolution": 10000, name: value}  # fmt: skip
        # A truthy flag is a flag in Python: progress="yes" may show progress.
        expect = EITHER if name == "progress" else ERROR
        return FileCase(case_id, "mesh", "CompoundBody.from_mesh", f"{name}={value!r}",
                        {"box.obj": obj_text(box)}, ("{dir}/box.obj",), keywords, expect,
                        (name,))  # fmt: skip
    name, data, kind, expect, box = _mesh_file(rng)
    call = str(rng.choice(["load_mesh", "CompoundBody.from_mesh"]))
    keywords = {} if call == "load_mesh" else {
        "decompose": str(rng.choice(["hull", "none"])), "cache": False, "progress": False,
        "samples": 200}  # fmt: skip
    if keywords.get("decompose") == "none":
        keywords["decompose"] = None
    truth = None if box is None else float(np.linalg.norm(box.max(axis=0) - box.min(axis=0)))
    return FileCase(case_id, "mesh", call, f"file:{kind}", {name: data}, (f"{{dir}}/{name}",),
                    keywords, expect, (name,), truth=truth)  # fmt: skip


def _pose_text(rng: np.random.Generator) -> Tuple[str, np.ndarray]:
    t = rng.uniform(-5, 5, 3).round(3)
    return ",".join(repr(float(v)) for v in t), t


def _cli(rng: np.random.Generator, case_id: str) -> FileCase:
    a, b = _box(rng), _box(rng)
    files = {"a.obj": obj_text(a), "b.stl": stl_binary(b)}
    roll = rng.random()
    if roll < 0.2:
        # A good distance query whose answer is known: two boxes moved apart.
        text, shift = _pose_text(rng)
        b32 = b.astype(np.float32).astype(float)
        truth = _box_distance(a, b32 + shift)
        argv = ["distance", "{dir}/a.obj", "{dir}/b.stl", f"--pose-b={text}", "--decompose",
                str(rng.choice(["hull", "none"])), "--json", "--quiet", "--no-cache"]
        return FileCase(case_id, "cli", "distance", "good", files, tuple(argv), truth=truth)
    if roll < 0.4:
        # One input file odd.
        name, data, kind, expect, _ = _mesh_file(rng)
        if rng.random() < 0.3:
            data, kind, expect = _parts_file(rng)
            name, kind = "parts.npz", f"parts:{kind}"
        files = {**files, name: data}
        command = str(rng.choice(["distance", "decompose"]))
        argv = (["distance", "{dir}/a.obj", f"{{dir}}/{name}"] if command == "distance"
                else ["decompose", f"{{dir}}/{name}", "-o", "{dir}/out.npz"])
        argv += ["--decompose", "hull", "--quiet", "--no-cache"]
        if command == "decompose" and name.endswith(".npz"):
            expect = ERROR  # decompose reads meshes, not parts files
        return FileCase(case_id, "cli", command, f"file:{kind}", files, tuple(argv), {},
                        expect, (name,), (1,))  # fmt: skip
    # One option odd.
    options = [
        ("distance", "--method", ["bogus", "", "DUAL", "ipso "], ("--method",)),
        ("distance", "--tolerance", ["nan", "-1", "abc", "inf", "1e400"], ("--tolerance",)),
        ("distance", "--pose-a", ["1,2", "nan,0,0", "1,0,0,0,1,0,0,0,0,0,1,0,0,0,0,1",
                                  "2,0,0,0,0,2,0,0,0,0,2,0,0,0,0,1", "1,0,0,0,1,0,0,0,0,0,1,0,1,1,1,1",
                                  "x"], ("--pose-a",)),
        ("distance", "--query", ["bogus"], ("--query",)),
        ("distance", "--decompose", ["bogus"], ("--decompose",)),
        ("distance", "--concavity", ["0", "2", "nan", "-0.1", "abc"], ("--concavity",)),
        ("distance", "--max-hulls", ["0", "-3", "1.5"], ("--max-hulls",)),
        ("distance", "--max-hull-vertices", ["3", "0"], ("--max-hull-vertices",)),
        ("distance", "--resolution", ["0", "-1"], ("--resolution",)),
        ("distance", "--seed", ["-1", "x"], ("--seed",)),
        ("distance", "--plot", ["{dir}/no/such/folder/p.png", "{dir}/p.notaformat"], ("--plot",)),
        ("decompose", "-o", ["{dir}/out.txt", "{dir}/no/such/folder/out.npz"], ("-o", "--output",
                                                                                 "out")),
        ("scene", "--bodies", ["0", "1", "-5", "x", str(10**9)], ("--bodies",)),
        ("scene", "--frames", ["0", "-1"], ("--frames",)),
        ("scene", "--threads", ["0", "-1", str(2**63), "5000", "x"], ("--threads",)),
        ("scene", "--seed", ["-1", str(2**64)], ("--seed",)),
        ("scene", "--plot", ["{dir}/no/such/folder/s.png", "{dir}/s.notaformat"], ("--plot",)),
        ("paper", "--repeats", ["0", "-1", "x"], ("--repeats",)),
        ("paper", "--seed", ["-1", str(2**64)], ("--seed",)),
    ]
    command, option, values, names = options[int(rng.integers(len(options)))]
    value = str(values[int(rng.integers(len(values)))])
    if command == "distance":
        argv = ["distance", "{dir}/a.obj", "{dir}/b.stl", "--decompose", "hull", "--quiet",
                "--no-cache"]
    elif command == "decompose":
        argv = ["decompose", "{dir}/a.obj", "--decompose", "hull", "--quiet", "--no-cache"]
    elif command == "scene":
        argv = ["scene", "--bodies", "4", "--frames", "1"]
    else:
        argv = ["paper", "--repeats", "1"]
    if option in argv:
        at = argv.index(option)
        del argv[at:at + 2]
    argv += [f"{option}={value}"]
    if command == "decompose" and option != "-o":
        argv += ["-o", "{dir}/out.npz"]
    if command == "decompose" and value.endswith("folder/out.npz"):
        expect = EITHER  # a folder decompose may make
    else:
        expect = ERROR
    return FileCase(case_id, "cli", command, f"{option}={value}", files, tuple(argv), {}, expect,
                    names, (2,))  # fmt: skip


def _natural(rng: np.random.Generator, case_id: str) -> FileCase:
    a, b = _box(rng), _box(rng) + [12, 0, 0]
    kind = str(rng.choice([
        "trimesh-bodies", "rotation-pose", "rotation-alone", "pose-3x4", "pose-list-4x4",
        "quaternion-wxyz", "quaternion-xyzw", "quaternion-bad", "batch-rotations",
        "batch-3x4", "scene-trimesh", "polyhedron-trimesh",
    ]))  # fmt: skip
    angle = float(rng.uniform(0, 2 * np.pi))
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    translation = rng.uniform(-3, 3, 3)
    rotation = _axis_angle(axis, angle)
    truth = _oracle(a, b @ rotation.T + translation)
    spec = {"a": a, "b": b, "axis": axis, "angle": angle, "translation": translation}
    names: Tuple[str, ...] = ()
    expect = ANSWER
    if kind == "quaternion-bad":
        bad = [("order", "zyxw"), ("order", b"wxyz"), ("order", None), ("quaternion", [0, 0, 0, 0]),
               ("quaternion", [1, 0, 0, np.nan]), ("quaternion", [2, 0, 0, 0]),
               ("quaternion", [1, 0, 0]), ("quaternion", [1j, 0, 0, 0]),
               ("translation", [1, 2]), ("translation", ["a", "b", "c"])]
        name, value = bad[int(rng.integers(len(bad)))]
        spec[name] = value
        expect, names, truth = ERROR, (name,), None
    return FileCase(case_id, "natural", kind, kind, {}, (spec,), {}, expect, names, truth=truth)


FILE_FAMILIES: Dict[str, Tuple[float, Callable[[np.random.Generator, str], FileCase]]] = {
    "mesh": (0.45, _mesh),
    "cli": (0.4, _cli),
    "natural": (0.15, _natural),
}


def make_file_case(seed: int, index: int) -> FileCase:
    """Case ``index`` of the files corpus ``seed``: the same case on every machine and run."""
    rng = np.random.default_rng([seed, 23, index])
    names = list(FILE_FAMILIES)
    shares = np.array([FILE_FAMILIES[n][0] for n in names])
    family = names[int(rng.choice(len(names), p=shares / shares.sum()))]
    return FILE_FAMILIES[family][1](rng, f"files:{seed}:{index}")


# ----- geometry for the answers ------------------------------------------------------------------


def _box_distance(a: np.ndarray, b: np.ndarray) -> float:
    gap = np.maximum(0, np.maximum(a.min(0) - b.max(0), b.min(0) - a.max(0)))
    return float(np.linalg.norm(gap))


def _axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def _oracle(a: np.ndarray, b: np.ndarray) -> float:
    import minkowski_oracle

    return float(minkowski_oracle.signed_distance(a, b).distance)


# ----- running and judging (in the sandboxed child) ----------------------------------------------


def run_file_case(seed: int, index: int) -> Dict[str, Any]:
    """Make, run and judge case ``index``: ``{"category", "reason", "seconds"}``."""
    case = make_file_case(seed, index)
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="swarmcollide-census-") as folder:
        os.environ["SWARMCOLLIDE_CACHE_DIR"] = str(Path(folder) / "cache")
        for name, data in case.files.items():
            (Path(folder) / name).write_bytes(data)
        try:
            category, reason = _judge(case, folder)
        except Exception as error:  # noqa: BLE001 - a bug of this suite
            category, reason = "suite-error", f"{type(error).__name__}: {error}"
    return {"category": category, "reason": reason, "seconds": time.monotonic() - start}


def _fill(value: Any, folder: str) -> Any:
    if isinstance(value, str):
        return value.replace("{dir}", folder)
    if isinstance(value, (list, tuple)) and not isinstance(value, np.ndarray):
        return type(value)(_fill(v, folder) for v in value)
    return value


def _judge(case: FileCase, folder: str) -> Tuple[str, str]:
    names = tuple(_fill(n, folder) for n in case.names)
    if case.family == "cli":
        return _judge_cli(case, [_fill(a, folder) for a in case.arguments], names)
    try:
        answer = _call(case, folder)
    except Exception as error:  # noqa: BLE001 - every exception is judged
        text = f"{type(error).__name__}: {error}"
        if case.expect == ANSWER:
            return "refused", text
        if not isinstance(error, (ValueError, TypeError)):
            return "unclear", f"a ValueError or TypeError was due: {text}"
        if names and not any(n in str(error) for n in names):
            return "unclear", f"the message names none of {names}: {text}"
        return "ok", text
    if case.expect == ERROR:
        return "slipped", f"answered: {answer!r:.100}"
    return answer


def _call(case: FileCase, folder: str) -> Tuple[str, str]:
    import swarmcollide as sc

    if case.family == "natural":
        return _natural_answer(case.call, case.arguments[0], case.truth)
    arguments = [_fill(a, folder) for a in case.arguments]
    target = {"load_mesh": sc.load_mesh, "CompoundBody.from_mesh": sc.CompoundBody.from_mesh,
              "CompoundBody.load": sc.CompoundBody.load}[case.call]  # fmt: skip
    result = target(*arguments, **case.keywords)
    if case.truth is not None:
        box = None if case.call == "load_mesh" else result.envelope.aabb()
        bounds = np.asarray(result.bounds) if box is None else np.array([box.min, box.max])
        diagonal = float(np.linalg.norm(bounds[1] - bounds[0]))
        if abs(diagonal - case.truth) > 1e-6 * case.truth:
            return "wrong", f"bounding box diagonal {diagonal}, the file's box {case.truth}"
    return "ok", ""


def _natural_answer(kind: str, spec: Dict[str, Any], truth: Optional[float]) -> Tuple[str, str]:
    import swarmcollide as sc

    a, b, t = spec["a"], spec["b"], spec["translation"]
    rotation = _axis_angle(spec["axis"], spec["angle"])
    if kind.startswith("quaternion"):
        half = spec["angle"] / 2
        wxyz = np.concatenate([[np.cos(half)], np.sin(half) * spec["axis"]])
        order = spec.get("order", "wxyz" if kind == "quaternion-wxyz" else "xyzw")
        q = spec.get("quaternion", wxyz if order == "wxyz" else np.roll(wxyz, -1))
        pose = sc.pose_from_quaternion(q, spec["translation"], order=order)
        return _check(sc.distance(a, b, pose_b=pose), truth)
    from scipy.spatial.transform import Rotation

    turn = Rotation.from_matrix(rotation)
    pose = np.eye(4)
    pose[:3, :3], pose[:3, 3] = rotation, t
    if kind in ("trimesh-bodies", "scene-trimesh", "polyhedron-trimesh"):
        import trimesh

        mesh_a = trimesh.Trimesh(a, CUBE_FACES, process=False)
        mesh_b = trimesh.Trimesh(b, CUBE_FACES, process=False)
        if kind == "trimesh-bodies":
            return _check(sc.distance(mesh_a, mesh_b, pose_b=pose), truth)
        if kind == "polyhedron-trimesh":
            return _check(sc.distance(sc.ConvexPolyhedron(mesh_a), mesh_b, pose_b=pose), truth)
        scene = sc.Scene()
        scene.add(mesh_a)
        scene.add(mesh_b, pose)
        found = scene.pairs_within(100.0)
        return _check_value(float(found.distance[0]), bool(found.certified[0]), truth)
    if kind == "rotation-pose":
        return _check(sc.distance(a, b, pose_b=(turn, t)), truth)
    if kind == "rotation-alone":
        return _check(sc.distance(a, b - [12, 0, 0] + [30, 0, 0], pose_b=turn),
                      _oracle(a, (b - [12, 0, 0] + [30, 0, 0]) @ rotation.T))
    if kind == "pose-3x4":
        return _check(sc.distance(a, b, pose_b=pose[:3]), truth)
    if kind == "pose-list-4x4":
        return _check(sc.distance(a, b, pose_b=pose.tolist()), truth)
    poses = (Rotation.from_matrix([rotation, rotation]), [t, t]) if kind == "batch-rotations" \
        else np.stack([pose[:3], pose[:3]])
    result = sc.distance_many([a, a], [b, b], poses_b=poses)
    return _check_value(float(result.distance[1]), bool(result.certified[1]), truth)


def _check(result: Any, truth: Optional[float]) -> Tuple[str, str]:
    return _check_value(result.distance, result.certified, truth)


def _check_value(distance: float, certified: bool, truth: Optional[float]) -> Tuple[str, str]:
    if truth is not None and abs(distance - truth) > 1e-6 * max(1.0, truth):
        return "wrong", f"distance {distance}, true {truth} (certified={certified})"
    return "ok", ""


def _judge_cli(case: FileCase, argv: List[str], names: Tuple[str, ...]) -> Tuple[str, str]:
    from swarmcollide.cli import main

    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main(argv)
            except SystemExit as done:
                status = done.code if isinstance(done.code, int) else 1
    except Exception as error:  # noqa: BLE001 - what the shell user would see as a traceback
        return "traceback", f"{type(error).__name__}: {str(error)[:200]}"
    lines = [line for line in err.getvalue().splitlines() if line.strip()]
    last = lines[-1] if lines else ""
    if "Traceback" in err.getvalue():
        return "traceback", last
    if case.expect == ANSWER or (case.expect == EITHER and status == 0):
        if status != 0:
            return "refused", f"exit {status}: {last}"
        if case.truth is not None:
            import json

            answer = json.loads(out.getvalue())
            return _check_value(answer["distance"], answer["certified"], case.truth)
        return "ok", ""
    if status == 0:
        return "slipped", f"exit 0: {out.getvalue()[-100:]!r}"
    if status not in case.statuses:
        return "unclear", f"exit {status}, due {case.statuses}: {last}"
    if "error:" not in last or (names and not any(n in last for n in names)):
        return "unclear", f"the last line names none of {names}: {last}"
    return "ok", last
