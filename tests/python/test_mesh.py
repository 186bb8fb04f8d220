"""Non-convex bodies from meshes: loading, decomposition, the recorded error, and queries between
compound bodies against python-fcl's exact triangle-mesh distance."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
import trimesh

import swarmcollide as sc
from swarmcollide import mesh as mesh_module

from meshes import MESHES, box_with_hole, cup, fcl_distance, homogeneous, l_shape, torus, u_shape

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)

# Small and fast CoACD settings for tests: a coarse sampling and at most 8 parts.
FAST = dict(decompose="coacd", concavity=0.1, max_hulls=8, resolution=1000, progress=False)


@pytest.fixture(scope="session")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("decompositions")


@pytest.fixture(scope="session")
def decomposed(cache):
    """Every test mesh and its CoACD decomposition, made once per session."""
    return {name: (make(), sc.CompoundBody.from_mesh(make(), cache=cache, **FAST))
            for name, make in MESHES.items()}


def rotation(seed: int) -> np.ndarray:
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q *= np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


# Loading


@pytest.mark.parametrize("suffix", [".obj", ".stl", ".ply", ".glb", ".off"])
def test_every_format_loads_the_same_mesh(tmp_path, suffix):
    path = tmp_path / f"l{suffix}"
    l_shape().export(path)
    loaded = sc.load_mesh(path)
    assert loaded.volume == pytest.approx(3.0)
    assert np.allclose(loaded.bounds, [[0, 0, 0], [2, 2, 1]])
    assert sc.load_mesh(str(path)).faces.shape == loaded.faces.shape


def test_unreadable_empty_non_finite_and_flat_meshes_are_refused(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        sc.load_mesh(tmp_path / "missing.obj")
    garbage = tmp_path / "garbage.stl"
    garbage.write_bytes(b"\x00\x01 not a mesh at all")
    # trimesh reads some garbage as a mesh of no triangles.
    with pytest.raises(ValueError, match="garbage.stl' (is empty|cannot)|cannot read mesh file"):
        sc.load_mesh(garbage)
    # Random bytes under a mesh's suffix are a file that is no mesh, not an empty mesh.
    noise = tmp_path / "noise.stl"
    noise.write_bytes(np.random.default_rng(0).bytes(2000))
    with pytest.raises(ValueError, match=r"^mesh file .*noise.stl' cannot be read as a mesh: no "
                       r"triangles could be read from it \(is it a mesh file\?"):
        sc.load_mesh(noise)
    (tmp_path / "folder.stl").mkdir()
    with pytest.raises(ValueError, match=r"^cannot read mesh file .*folder.stl': it is a "
                       "directory"):
        sc.load_mesh(tmp_path / "folder.stl")
    empty = tmp_path / "empty.obj"
    empty.write_text("# nothing\n")
    with pytest.raises(ValueError, match="empty|not a 3-D"):
        sc.load_mesh(empty)
    non_finite = tmp_path / "nan.obj"
    non_finite.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 nan\nf 1 2 3\nf 1 2 4\nf 1 3 4\n")
    with pytest.raises(ValueError, match="NaN or infinite"):
        sc.load_mesh(non_finite)
    flat = tmp_path / "flat.obj"
    flat.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
    with pytest.raises(ValueError, match="one plane"):
        sc.load_mesh(flat)
    with pytest.raises(TypeError, match="path to a mesh file"):
        sc.load_mesh(42)
    with pytest.raises(ValueError, match="empty"):
        sc.load_mesh(trimesh.Trimesh())


def test_a_tilted_flat_stl_is_refused_though_float32_lifts_its_corners_off_the_plane(tmp_path):
    # STL stores float32: the corners of a square in a tilted plane, rounded, no longer lie in one
    # plane (by about 1e-7 of their size), and a rank test at double precision saw a solid.
    turn = trimesh.transformations.rotation_matrix(0.7, [1, 2, 3])
    square = trimesh.Trimesh([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]], [[0, 1, 2], [0, 2, 3]])
    refused = 0
    for shift in ([0, 0, 0], [1e3, -2e3, 5e2]):
        square.apply_transform(turn @ trimesh.transformations.translation_matrix(shift))
        square.export(tmp_path / "tilted.stl")
        with pytest.raises(ValueError, match="tilted.stl' is not a 3-D solid: .* one plane"):
            sc.load_mesh(tmp_path / "tilted.stl")
        refused += 1
    assert refused == 2
    # A thin solid (a 10 x 10 x 0.01 slab, tilted) is a solid, and is kept.
    slab = trimesh.creation.box((10, 10, 0.01))
    slab.apply_transform(turn)
    slab.export(tmp_path / "slab.stl")
    assert len(sc.load_mesh(tmp_path / "slab.stl").vertices) == 8


def test_parts_files_that_are_not_parts_files_are_refused_naming_the_file(tmp_path):
    good = dict(points=np.vstack([CUBE, CUBE + 2]), offsets=np.array([0, 8, 16]),
                decomposition=np.array(""))
    broken = {
        "zip.npz": b"PK\x03\x04 not a zip at all",
        "npy.npz": None,
        "beyond.npz": dict(good, offsets=np.array([0, 8, 40])),
        "short.npz": dict(good, offsets=np.array([0, 8])),
        "decreasing.npz": dict(good, offsets=np.array([0, 12, 4, 16])),
        "floats.npz": dict(good, offsets=np.array([0.5, 8.5, 16.5])),
        "complex.npz": dict(good, points=good["points"] + 1j),
    }
    for name, content in broken.items():
        path = tmp_path / name
        if isinstance(content, bytes):
            path.write_bytes(content)
        elif content is None:
            with open(path, "wb") as handle:
                np.save(handle, CUBE)
        else:
            np.savez(path, **content)
        with pytest.raises(ValueError, match=f"{name}' is not a parts file"):
            sc.CompoundBody.load(path)
    nan = tmp_path / "nan.npz"
    np.savez(nan, **dict(good, points=np.where(good["points"] == 1, np.nan, good["points"])))
    with pytest.raises(ValueError, match="parts file .*nan.npz': parts"):
        sc.CompoundBody.load(nan)
    with pytest.raises(TypeError, match="path must be a path to a parts file"):
        sc.CompoundBody.load(None)
    with pytest.raises(ValueError, match="cannot read parts file .*missing.npz': no such file"):
        sc.CompoundBody.load(tmp_path / "missing.npz")
    (tmp_path / "folder.npz").mkdir()
    with pytest.raises(ValueError, match="parts file .*folder.npz' is a directory"):
        sc.CompoundBody.load(tmp_path / "folder.npz")
    np.savez(tmp_path / "good.npz", **good)
    assert len(sc.CompoundBody.load(tmp_path / "good.npz")) == 2


def test_a_decomposition_record_of_wrong_types_is_refused_naming_the_file_and_the_field(tmp_path):
    record = dict(method="hull", parameters={}, parts=2, seconds=0.5, parts_to_mesh=0.0,
                  mesh_to_parts=0.0, samples=100, spacing=0.1, mesh_hash="ab", faces=12,
                  decomposed_faces=12, simplification_error=0.0)
    good = dict(points=np.vstack([CUBE, CUBE + 2]), offsets=np.array([0, 8, 16]))
    np.savez(tmp_path / "good.npz", **good, decomposition=np.array(json.dumps(record)))
    assert sc.CompoundBody.load(tmp_path / "good.npz").decomposition.parts == 2
    for name, meta, message in [
            ("parts", dict(record, parts="2"), "field 'parts' must be of type int, got '2'"),
            ("seconds", dict(record, seconds=[1]), "field 'seconds' must be of type float"),
            ("flag", dict(record, samples=True), "field 'samples' must be of type int, got True"),
            ("method", dict(record, method=3), "field 'method' must be of type str, got 3"),
            ("parameters", dict(record, parameters=[]), "field 'parameters' must be of type dict"),
            ("keys", dict(record, bogus=1), "record has unknown fields 'bogus'"),
            ("missing", {"method": "hull"}, "record lacks 'parameters', 'parts'"),
            ("list", [1, 2], "record must be a JSON object, got list")]:
        path = tmp_path / f"{name}.npz"
        np.savez(path, **good, decomposition=np.array(json.dumps(meta)))
        with pytest.raises(ValueError,
                           match=f"^parts file '.*{name}.npz': its decomposition {message}"):
            sc.CompoundBody.load(path)
    np.savez(tmp_path / "text.npz", **good, decomposition=np.array("{not json"))
    with pytest.raises(ValueError, match="text.npz': its decomposition record is not JSON"):
        sc.CompoundBody.load(tmp_path / "text.npz")


# Decomposition


def test_already_convex_parts_and_the_hull():
    two = trimesh.util.concatenate([trimesh.creation.box((1, 1, 1)),
                                    trimesh.creation.box((1, 1, 1)).apply_translation((3, 0, 0))])
    parts = sc.CompoundBody.from_mesh(two, decompose=None, cache=False)
    assert len(parts) == 2
    assert parts.decomposition.hausdorff < 1e-9
    with pytest.raises(ValueError, match="component 0 of 1 .* is not convex"):
        sc.CompoundBody.from_mesh(l_shape(), decompose=None, cache=False)
    hull = sc.CompoundBody.from_mesh(l_shape(), decompose="hull", cache=False)
    assert len(hull) == 1
    # The hull fills the L's empty corner: its farthest point, the middle of the diagonal
    # face, is 0.5 from the L; it misses nothing of the L.
    d = hull.decomposition
    assert 0.5 - 2 * d.spacing < d.parts_to_mesh <= 0.5 + 1e-9
    assert d.mesh_to_parts < 1e-9


def scaled_mesh(mesh, scale):
    return trimesh.Trimesh(mesh.vertices * scale, mesh.faces, process=False)


def write_obj(path, mesh):
    """``mesh`` as an OBJ file at full precision (trimesh's exporter rounds to 8 decimals)."""
    with open(path, "w") as handle:
        handle.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in mesh.vertices.tolist())
        handle.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in mesh.faces.tolist())
    return path


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e-160, 1e-9, 1e-8, 1e20, 1e200, 1e300])
def test_the_hull_and_ready_made_parts_are_the_same_in_any_unit(scale, tmp_path):
    # trimesh merged the hull's points within an absolute 1e-8 (one point at 1e-9, a certified
    # distance of 5 for 4), and its areas and normals squared lengths (NaN at 1e200: a convex
    # box refused as not convex); a file's points were merged at 1e-8 too.
    box = trimesh.creation.box((1, 2, 3))
    spacing = sc.CompoundBody.from_mesh(box, decompose="hull", cache=False,
                                        samples=200).decomposition.spacing
    mesh = scaled_mesh(box, scale)
    for source in (mesh, write_obj(tmp_path / "box.obj", mesh)):
        for decompose in ("hull", None):
            body = sc.CompoundBody.from_mesh(source, decompose=decompose, cache=False,
                                             samples=200)
            assert len(body) == 1
            np.testing.assert_allclose(np.sort(body.parts[0].vertices, axis=0) / scale,
                                       np.sort(box.vertices, axis=0), rtol=1e-15)
            d = body.decomposition
            assert d.mesh_to_parts <= 1e-12 * scale and d.parts_to_mesh <= 1e-12 * scale
            assert d.spacing / scale == pytest.approx(spacing, rel=1e-12)
            r = sc.distance(body, body, pose_b=(np.eye(3), [min(5 * scale, 1e300), 0, 0]))
            assert r.certified and r.distance == pytest.approx(min(5 * scale, 1e300) - scale,
                                                               rel=1e-9)


def test_an_unmerged_mesh_is_one_solid_part(tmp_path):
    # A box of 12 separate triangles (as STL stores them, process=False) fell apart into 12
    # flat parts: a sphere inside it was certified apart, and the cache, whose key does not
    # depend on merging, gave the merged box the same parts.
    box = trimesh.creation.box((2, 2, 2))
    corners = box.vertices[box.faces].reshape(-1, 3)
    unmerged = trimesh.Trimesh(corners, np.arange(36).reshape(-1, 3), process=False)
    inside = sc.Sphere(0.1)
    for mesh in (unmerged, box):
        body = sc.CompoundBody.from_mesh(mesh, decompose=None, cache=tmp_path)
        assert len(body) == 1 and len(body.parts[0].vertices) == 8
        r = sc.signed_distance(body, inside)
        assert r.certified and r.colliding and r.distance == pytest.approx(-1.1, abs=1e-9)


@pytest.mark.parametrize("exponent", [-700, -30, 30, 600])
def test_the_recorded_deviation_is_the_same_in_any_unit(decomposed, exponent):
    # trimesh's samples and proximity queries ran in the mesh's own units: at 1e-6 the record
    # drifted (parts_to_mesh 0.28 for 0.11), at 1e-10 it was 0, at 1e200 NaN. Scaled by a power
    # of two, every figure is scaled by it exactly.
    mesh, body = decomposed["torus"]
    scale = 2.0**exponent
    parts = [p.vertices * scale for p in body.parts]
    one = sc.measure_deviation(mesh, body, samples=300)
    other = sc.measure_deviation(scaled_mesh(mesh, scale), sc.CompoundBody(parts), samples=300)
    for key in ("parts_to_mesh", "mesh_to_parts", "spacing"):
        assert other[key] == one[key] * scale, key
    assert one["parts_to_mesh"] > 0


def test_decomposers_record_their_error_and_settings(decomposed):
    for name, (mesh, body) in decomposed.items():
        d = body.decomposition
        assert d.method == "coacd" and d.parts == len(body) <= 8
        assert d.parameters["threshold"] == 0.1 and d.parameters["max_convex_hull"] == 8
        assert d.samples == sc.mesh.DEFAULT_SAMPLES
        assert 0 <= d.mesh_to_parts < 0.2 and 0 <= d.parts_to_mesh < 0.2, name
        assert d.mesh_hash == sc.mesh_hash(mesh)
    # Boxes decompose into boxes: the L into its two cells.
    _, ell = decomposed["l_shape"]
    assert len(ell) == 2 and ell.decomposition.hausdorff < 0.01
    vhacd = sc.CompoundBody.from_mesh(l_shape(), decompose="vhacd", max_hulls=4,
                                      resolution=10000, cache=False, progress=False)
    assert vhacd.decomposition.method == "vhacd" and 1 <= len(vhacd) <= 4
    assert vhacd.decomposition.parameters["maxConvexHulls"] == 4


def test_a_mesh_above_max_faces_is_simplified_and_its_error_recorded():
    sphere = trimesh.creation.icosphere(subdivisions=3)  # 1280 triangles
    body = sc.CompoundBody.from_mesh(sphere, decompose="hull", max_faces=200, cache=False)
    d = body.decomposition
    assert d.faces == 1280 and d.decomposed_faces <= 200
    assert 0 < d.simplification_error < 0.2
    # The recorded distances hold against the mesh as given, not only the simplified one.
    on_sphere, _ = trimesh.sample.sample_surface(sphere, 500, seed=5)
    missed = sc.distance_many([body.parts[0]] * 500, on_sphere[:, None, :]).distance
    assert missed.max() <= d.mesh_to_parts + d.spacing
    assert d.mesh_to_parts >= d.simplification_error
    assert "simplified 1280 to" in repr(d)
    untouched = sc.CompoundBody.from_mesh(sphere, decompose="hull", cache=False)
    assert untouched.decomposition.decomposed_faces == 1280
    assert untouched.decomposition.simplification_error == 0
    with pytest.raises(ValueError, match="max_faces"):
        sc.CompoundBody.from_mesh(sphere, decompose="hull", max_faces=0, cache=False)


def test_measuring_a_part_of_many_vertices_stays_in_bounded_memory():
    # Each row of a batch copies its part's points: 4000 samples against one part of 10,242
    # points took 2 GB when the batch was not cut into pieces.
    script = (
        "import resource, trimesh, swarmcollide as sc\n"
        "sphere = trimesh.creation.icosphere(subdivisions=5)\n"
        "before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
        "d = sc.measure_deviation(sphere, sc.CompoundBody([sphere.vertices]), samples=4000)\n"
        "assert d['mesh_to_parts'] < 1e-9, d\n"
        "print((resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) // 1024)\n"
    )
    grown = int(subprocess.run([sys.executable, "-c", script], check=True, capture_output=True,
                               text=True).stdout)
    assert grown < 500, f"measuring grew the process by {grown} MB"


def test_presets_and_explicit_settings():
    fast = sc.CompoundBody.from_mesh(l_shape(), cache=False, progress=False)
    assert fast.decomposition.parameters["threshold"] == sc.mesh.PRESETS["fast"]["threshold"]
    assert (fast.decomposition.parameters["mcts_iterations"]
            == sc.mesh.PRESETS["fast"]["mcts_iterations"])
    assert len(fast) == 2
    chosen = sc.mesh._parameters("coacd", "quality", 0.2, None, None, 500, 0)
    assert chosen["threshold"] == 0.2 and chosen["resolution"] == 500
    assert chosen["mcts_iterations"] == sc.mesh.PRESETS["quality"]["mcts_iterations"]
    with pytest.raises(ValueError, match="preset must be one of 'fast', 'quality'"):
        sc.CompoundBody.from_mesh(l_shape(), preset="slow", cache=False)


def test_max_hull_vertices_bounds_coacd_parts(decomposed):
    body = sc.CompoundBody.from_mesh(torus(), cache=False, max_hull_vertices=8, **FAST)
    assert max(len(p.vertices) for p in body.parts) <= 8
    _, exact = decomposed["torus"]
    assert max(len(p.vertices) for p in exact.parts) > 8  # CoACD's exact hulls


def test_a_long_decomposition_says_how_long_before_it_starts(tmp_path, monkeypatch, capsys):
    from swarmcollide.cli import main

    monkeypatch.setattr(mesh_module, "_LONG_RUN", 0.0)
    monkeypatch.setattr(mesh_module, "_TYPICAL_SECONDS", {"fast": 42.0, "quality": 420.0})
    l_shape().export(tmp_path / "l.obj")
    parts = tmp_path / "l.npz"
    assert main(["decompose", str(tmp_path / "l.obj"), "-o", str(parts), "--preset", "quality",
                 "--no-cache"]) == 0
    err = capsys.readouterr().err
    assert "typically ~420 s" in err and "preset='fast' ~42 s" in err
    used = sc.CompoundBody.load(parts).decomposition.parameters
    assert used["mcts_iterations"] == sc.mesh.PRESETS["quality"]["mcts_iterations"]


def test_settings_are_checked():
    with pytest.raises(ValueError, match="decompose must be one of"):
        sc.CompoundBody.from_mesh(l_shape(), decompose="quickhull", cache=False)
    with pytest.raises(ValueError, match="concavity"):
        sc.CompoundBody.from_mesh(l_shape(), concavity=0, cache=False)
    with pytest.raises(ValueError, match="max_hulls"):
        sc.CompoundBody.from_mesh(l_shape(), max_hulls=0, cache=False)
    with pytest.raises(TypeError, match="cache"):
        sc.CompoundBody.from_mesh(l_shape(), decompose="hull", cache=3.5)


def test_the_cache_returns_the_same_parts(tmp_path, monkeypatch):
    first = sc.CompoundBody.from_mesh(u_shape(), cache=tmp_path, **FAST)
    assert not first.decomposition.from_cache
    assert len(list(tmp_path.glob("*.npz"))) == 1
    again = sc.CompoundBody.from_mesh(u_shape(), cache=tmp_path, **FAST)
    assert again.decomposition.from_cache
    assert again.decomposition == first.decomposition
    for p, q in zip(first.parts, again.parts):
        assert np.array_equal(p.vertices, q.vertices)
    # Other settings are another entry; the environment variable moves the default directory.
    monkeypatch.setenv("SWARMCOLLIDE_CACHE_DIR", str(tmp_path / "elsewhere"))
    assert sc.cache_directory() == tmp_path / "elsewhere"
    sc.CompoundBody.from_mesh(u_shape(), decompose="hull", cache=True)
    assert len(list((tmp_path / "elsewhere").glob("*.npz"))) == 1


def test_the_cache_is_found_by_file_bytes_and_by_any_loader(tmp_path, monkeypatch):
    path = tmp_path / "l.stl"
    l_shape().export(path)
    # Read unmerged (three points per triangle, as STL stores them): another loader's mesh.
    raw = trimesh.load_mesh(path, process=False)
    assert len(raw.vertices) == 3 * len(raw.faces)
    first = sc.CompoundBody.from_mesh(raw, decompose="hull", cache=tmp_path)
    assert not first.decomposition.from_cache
    by_path = sc.CompoundBody.from_mesh(path, decompose="hull", cache=tmp_path)
    assert by_path.decomposition.from_cache and by_path.decomposition == first.decomposition
    # The file's bytes now name the entry too: found without reading the mesh at all.
    monkeypatch.setattr(mesh_module, "load_mesh", lambda source: pytest.fail("mesh was read"))
    again = sc.CompoundBody.from_mesh(str(path), decompose="hull", cache=tmp_path)
    assert again.decomposition.from_cache
    assert len(list(tmp_path.glob("*.npz"))) == 2


def test_a_slow_decomposition_shows_a_progress_bar(monkeypatch, capsys):
    monkeypatch.setattr(mesh_module, "_PROGRESS_DELAY", 0.0)

    def slow():
        import time

        time.sleep(0.5)
        return [np.eye(3)]

    assert len(mesh_module._with_progress("CoACD", slow, True)) == 1
    assert "CoACD" in capsys.readouterr().err


CUBE_OBJ = """v {x0} 0 0
v {x1} 0 0
v {x1} 1 0
v {x0} 1 0
v {x0} 0 1
v {x1} 0 1
v {x1} 1 1
v {x0} 1 1
f {a} {d} {c}
f {a} {c} {b}
f {e} {f} {g}
f {e} {g} {h}
f {a} {b} {f}
f {a} {f} {e}
f {b} {c} {g}
f {b} {g} {f}
f {c} {d} {h}
f {c} {h} {g}
f {d} {a} {e}
f {d} {e} {h}
"""


def cube_text(x0: float, first: int) -> str:
    """A unit cube from x0 to x0 + 1 as OBJ points and outward triangles, its points numbered
    from ``first``."""
    corners = dict(zip("abcdefgh", range(first, first + 8)))
    return CUBE_OBJ.format(x0=x0, x1=x0 + 1, **corners)


def test_each_obj_group_is_a_ready_made_part(tmp_path):
    # Two cubes side by side, as V-HACD writes hulls: one object each. Their shared face makes
    # them one connected 2 x 1 x 1 bar, and their groups two cells.
    path = tmp_path / "hulls.obj"
    path.write_text("o convex_0\n" + cube_text(0, 1) + "o convex_1\n" + cube_text(1, 9))
    body = sc.CompoundBody.from_mesh(path, decompose=None, cache=False)
    assert len(body) == 2
    assert sorted(p.aabb().min[0] for p in body.parts) == [0, 1]
    assert body.decomposition.hausdorff < 1e-9
    # `g` groups as well; a group that is not convex is named.
    ell = l_shape()
    points = "".join(f"v {x} {y} {z}\n" for x, y, z in ell.vertices)
    faces = "".join(f"f {i + 9} {j + 9} {k + 9}\n" for i, j, k in ell.faces)  # after the cube's
    elbow = tmp_path / "elbow.obj"
    elbow.write_text("g box\n" + cube_text(5, 1) + "g elbow\n" + points + faces)
    with pytest.raises(ValueError, match=r"group 'elbow', with 28 triangles, is not convex"):
        sc.CompoundBody.from_mesh(elbow, decompose=None, cache=False)


def test_parts_files_round_trip(tmp_path, decomposed):
    _, body = decomposed["torus"]
    body.save(tmp_path / "torus.npz")
    loaded = sc.CompoundBody.load(tmp_path / "torus.npz")
    assert len(loaded) == len(body) and loaded.decomposition == body.decomposition
    (tmp_path / "bad.npz").write_bytes(b"no")
    with pytest.raises(ValueError, match="not a parts file"):
        sc.CompoundBody.load(tmp_path / "bad.npz")
    # A path that cannot be written names itself and leaves no temporary file behind.
    (tmp_path / "folder").mkdir()
    with pytest.raises(OSError, match="cannot write the parts file .*folder"):
        body.save(tmp_path / "folder")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.npz", "folder", "torus.npz"]


# Queries against the exact triangle-mesh distance


POSES = [homogeneous(rotation(seed), (3.2 + 0.4 * seed, 0.5 * seed - 1, 0.3 * seed))
         for seed in range(4)]


@pytest.mark.parametrize("pair", [("l_shape", "u_shape"), ("torus", "cup"),
                                  ("box_with_hole", "torus"), ("cup", "l_shape")])
def test_distances_match_the_mesh_distance_within_the_recorded_error(decomposed, pair):
    (mesh_a, a), (mesh_b, b) = decomposed[pair[0]], decomposed[pair[1]]
    da, db = a.decomposition, b.decomposition
    for pose in POSES:
        r = sc.distance(a, b, pose_b=pose)
        exact = fcl_distance(mesh_a, np.eye(4), mesh_b, pose)
        assert r.certified and r.lower_bound <= r.distance + 1e-12  # up to rounding
        # d_parts - hA - hB <= d_mesh <= d_parts + gA + gB, each sampled to about its spacing.
        slack = da.spacing + db.spacing + 1e-6
        assert exact >= r.distance - da.parts_to_mesh - db.parts_to_mesh - slack
        assert exact <= r.distance + da.mesh_to_parts + db.mesh_to_parts + slack
        assert r.stats.part_pairs == len(a) * len(b)


def test_collide_where_the_hull_would_and_the_shape_does_not(decomposed):
    _, cup_body = decomposed["cup"]
    peg = trimesh.creation.box((0.5, 0.5, 3.0))  # in the cup's hole: its edges 0.24 from the wall
    assert sc.collide(cup_body.envelope, peg.vertices)
    assert not sc.collide(cup_body, peg.vertices)
    assert fcl_distance(cup(), np.eye(4), peg, np.eye(4)) > 0.24
    r = sc.collision(cup_body, peg.vertices)
    assert r.certified and r.lower_bound > 0  # a verdict proves apart, not how far
    d = cup_body.decomposition
    assert sc.distance(cup_body, peg.vertices).distance > 0.24 - d.parts_to_mesh - d.spacing
    beside = sc.collision(cup_body, peg.vertices, pose_b=homogeneous(translation=(0.6, 0, 0)))
    assert beside.colliding and beside.certified
    _, ring = decomposed["torus"]
    point = [[0.0, 0.0, 0.0]]  # the centre of the torus's hole, 0.7 from the ring
    assert sc.collide(ring.envelope, point) and not sc.collide(ring, point)
    exact = trimesh.proximity.closest_point(torus(), point)[1][0]  # 0.7, less the facets' sag
    d = ring.decomposition
    between = sc.distance(ring, point).distance
    assert exact - d.parts_to_mesh - d.spacing <= between <= exact + d.mesh_to_parts + d.spacing
    # The U's gap and the box's hole hold a peg that the hulls would not.
    _, u = decomposed["u_shape"]
    _, holed = decomposed["box_with_hole"]
    assert not sc.collide(u, trimesh.creation.box((0.6, 1.6, 3)).vertices + [1.5, 2, 0.5])
    assert not sc.collide(holed, trimesh.creation.box((0.6, 0.6, 3)).vertices + [1.5, 1.5, 0.5])


def test_signed_distance_is_the_deepest_part_pair(decomposed):
    _, u = decomposed["u_shape"]
    _, ell = decomposed["l_shape"]
    pose = homogeneous(rotation(7), (1.0, 0.8, 0.4))
    r = sc.signed_distance(u, ell, pose_b=pose)
    deepest = min(sc.signed_distance(p, q, pose_b=pose).distance
                  for p in u.parts for q in ell.parts)
    assert r.distance == pytest.approx(deepest, abs=1e-8)
    assert r.distance < 0 and r.certified
    assert r.distance == pytest.approx(
        sc.signed_distance(u.parts[r.part_a], ell.parts[r.part_b], pose_b=pose).distance,
        abs=1e-8)


def test_batches_and_poses_take_compound_bodies(decomposed):
    _, ring = decomposed["torus"]
    _, ell = decomposed["l_shape"]
    poses = np.stack([homogeneous(translation=(x, 0, 0)) for x in (0.0, 4.0)])
    batch = sc.distance_many([ring, ring], [ell, ell], poses_b=poses)
    for k in range(2):
        one = sc.distance(ring, ell, pose_b=poses[k])
        assert batch.distance[k] == pytest.approx(one.distance, abs=1e-9)
        assert (batch.part_a[k], batch.part_b[k]) == (one.part_a, one.part_b)
    assert sc.collide_many([ring, ring], [ell, ell], poses_b=poses).colliding.tolist() == [True,
                                                                                          False]
    # A convex body beside compound ones is a compound body of one part.
    mixed = sc.distance_many([ring, ring.parts[0]], [ell.parts[0], ell], poses_b=poses)
    assert mixed.distance[1] == pytest.approx(
        sc.distance(ring.parts[0], ell, pose_b=poses[1]).distance, abs=1e-9)


def test_most_part_pairs_are_pruned(decomposed):
    _, ring = decomposed["torus"]
    _, mug = decomposed["cup"]
    total = pruned = 0
    for pose in POSES:
        r = sc.distance(ring, mug, pose_b=pose)
        total += r.stats.part_pairs
        pruned += r.stats.pruned
    assert pruned > total / 2
    assert "part pairs" in repr(r) and "pruned" in repr(r.stats)


def test_scenes_hold_compound_bodies(decomposed):
    from swarmcollide.plot import plot_scene

    _, mug = decomposed["cup"]
    _, ring = decomposed["torus"]
    peg = trimesh.creation.box((0.5, 0.5, 3.0)).vertices
    scene = sc.Scene(threads=1)
    ids = scene.add([mug, peg, ring], poses=np.stack([np.eye(4), np.eye(4),
                                                      homogeneous(translation=(6, 0, 0))]))
    assert ids.tolist() == [0, 1, 2]
    assert len(scene.body(0)) == len(mug) and len(scene.body(1)) == 8
    assert len(scene.colliding_pairs()) == 0  # the peg stands in the cup's hole
    near = scene.pairs_within(0.5)
    assert near.pairs.tolist() == [[0, 1]]
    assert near.distance[0] == pytest.approx(sc.distance(mug, peg).distance, abs=1e-9)
    scene.set_poses(1, homogeneous(translation=(0.6, 0, 0)))
    hits = scene.colliding_pairs()
    assert hits.pairs.tolist() == [[0, 1]] and hits.certified.all()
    contacts = scene.contacts()
    assert contacts.distance[0] == pytest.approx(
        sc.signed_distance(mug, peg, pose_b=homogeneous(translation=(0.6, 0, 0))).distance,
        abs=1e-8)
    assert scene.min_distance().pairs.tolist() == [[0, 1]]
    assert len(plot_scene(scene).axes[0].collections) == 3
