"""The main job: ``python -m swarmcollide paper`` reproduces the paper's Section IV."""

import subprocess
import sys

import numpy as np
import pytest

import swarmcollide as sc
from swarmcollide import paper
from swarmcollide.cli import main


def test_paper_tables_show_the_papers_rows_ours_and_the_exact_answer(capsys):
    assert main(["paper", "--repeats", "1"]) == 0
    out = capsys.readouterr().out
    table1, table2 = out.split("\n\n")
    assert table1.startswith("Table 1") and table2.startswith("Table 2")
    for table, exact in ((table1, "0"), (table2, "1")):
        lines = {line[:38].strip(): line[38:].split() for line in table.splitlines()[2:]}
        assert lines["paper: improved PSO"][1] == "0.9999"
        assert lines["exact"][:8] == ["0.0000", "1.0000", "0.0000", "0.0000"] * 0 + [
            "0.0000",
            "1.0000",
            "0.0000",
            "0.0000",
            "1.0000",
            "0.0000",
            "0.0000",
            "0.0000",
        ]
        assert lines["exact"][8] == exact
        ours = lines["swarmcollide: ipso"]
        assert ours[:8] == lines["exact"][:8]
        assert float(ours[8]) == pytest.approx(float(exact), abs=1e-6)
        assert float(ours[9]) > 0


def test_rows_come_from_the_solver():
    row = paper.solve(paper.CASES[1], "x", {"method": "ipso"}, seed=0, repeats=1)
    assert row.distance == pytest.approx(1.0, abs=1e-6)
    assert row.weights_a[1] == pytest.approx(1.0, abs=1e-6)


def test_module_entry_point_runs():
    done = subprocess.run(
        [sys.executable, "-m", "swarmcollide", "paper", "--repeats", "1"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert "Table 2: separation" in done.stdout


def test_bad_arguments_exit_with_a_message(capsys):
    with pytest.raises(SystemExit):
        main(["paper", "--repeats", "0"])
    assert "argument --repeats: must be an integer at least 1" in capsys.readouterr().err


# Mesh files: distance and decompose


@pytest.fixture
def mesh_files(tmp_path, monkeypatch):
    import trimesh

    from meshes import l_shape

    monkeypatch.setenv("SWARMCOLLIDE_CACHE_DIR", str(tmp_path / "cache"))
    trimesh.creation.box((1, 1, 1)).export(tmp_path / "box.stl")
    l_shape().export(tmp_path / "l.obj")
    return tmp_path


def test_distance_between_mesh_files(mesh_files, capsys):
    import json

    box, ell = str(mesh_files / "box.stl"), str(mesh_files / "l.obj")
    assert main(["distance", box, ell, "--decompose", "hull", "--pose-a=-2,0,0", "--json",
                 "--quiet"]) == 0
    answer = json.loads(capsys.readouterr().out)
    # The box spans x in [-2.5, -1.5], the L starts at x = 0.
    assert answer["distance"] == pytest.approx(1.5) and answer["certified"]
    assert answer["a"]["decomposition"]["method"] == "hull"
    assert main(["distance", box, ell, "--decompose", "none", "--pose-b", "0 0 5 90 0 0",
                 "--query", "collide"]) == 1  # the L is not convex: decompose=None refuses it
    assert "is not convex" in capsys.readouterr().err


def test_decompose_writes_a_parts_file_that_distance_reads(mesh_files, capsys):
    parts = str(mesh_files / "l.npz")
    assert main(["decompose", str(mesh_files / "l.obj"), "-o", parts, "--max-hulls", "2",
                 "--resolution", "500", "--quiet"]) == 0
    assert "2 convex parts (coacd" in capsys.readouterr().out
    assert main(["distance", parts, parts, "--pose-b", "0 0 2", "--plot",
                 str(mesh_files / "pair.png")]) == 0
    out = capsys.readouterr().out
    assert out.startswith("distance: 1 (lower bound 1, certified for the convex parts)")
    assert (mesh_files / "pair.png").stat().st_size > 0
    # A parts file is convex parts already: decompose refuses it, naming it (it raised an
    # AttributeError on its missing decomposition record: files census case files:0:621).
    for made in ("l.npz", "l.json"):
        assert main(["decompose", str(mesh_files / made), "-o", str(mesh_files / "again.npz"),
                     "--quiet"]) == 1
        err = capsys.readouterr().err
        assert f"{made}: decompose reads a mesh file" in err and "Traceback" not in err


def test_mesh_commands_fail_as_a_shell_user_expects(mesh_files, capsys):
    box = str(mesh_files / "box.stl")
    assert main(["distance", box, str(mesh_files / "missing.obj")]) == 1
    assert "cannot read mesh file" in capsys.readouterr().err
    with pytest.raises(SystemExit) as usage:
        main(["distance", box, box, "--pose-a", "1,2"])
    assert usage.value.code == 2
    assert "a pose has 3, 6 or 16 numbers" in capsys.readouterr().err
    with pytest.raises(SystemExit) as usage:
        main(["decompose", box, "-o", "parts.txt"])
    assert usage.value.code == 2
    with pytest.raises(SystemExit) as done:
        main(["distance", "--help"])
    assert done.value.code == 0
    assert "parts files (.npz" in capsys.readouterr().out
    assert main(["distance", box, box, "--decompose", "hull", "--method", "ipso", "--query",
                 "signed"]) == 1
    assert "signed_distance is not available with method 'ipso'" in capsys.readouterr().err


def test_each_query_is_asked_of_the_method_that_answers_it(tmp_path, capsys):
    # libccd answers signed distances and verdicts, not distances: the options' check asked every
    # method for a distance, which refused --query signed and collide with libccd.
    import json

    cylinder = tmp_path / "cylinder.json"
    cylinder.write_text('{"shape": "cylinder", "radius": 0.5, "half_length": 1}')
    pose = np.eye(4)
    pose[0, 3] = 0.5
    for asked, call in (("signed", sc.signed_distance), ("collide", sc.collision)):
        assert main(["distance", str(cylinder), str(cylinder), "--query", asked, "--method",
                     "libccd", "--pose-b", "0.5,0,0", "--json"]) == 0
        answer = json.loads(capsys.readouterr().out)
        r = call(sc.Cylinder(0.5, 1.0), sc.Cylinder(0.5, 1.0), pose_b=pose, method="libccd")
        assert (answer["method"], answer["colliding"], answer["distance"]) == (
            r.method, True, r.distance)
    # A query the method cannot answer is an unusable input (exit 1), refused before any file
    # is read.
    for argv, query in ((["--method", "libccd"], "distance"),
                        (["--method", "ipso", "--query", "signed"], "signed_distance")):
        assert main(["distance", str(cylinder), str(tmp_path / "missing.obj")] + argv) == 1
        assert capsys.readouterr().err.startswith(
            f"swarmcollide distance: error: {query} is not available with method ")


def test_wrong_options_are_usage_errors_before_any_work(mesh_files, capsys):
    box = str(mesh_files / "box.stl")
    usage_errors = [
        (["distance", box, box, "--method", "bogus"], "argument --method: invalid choice"),
        (["distance", box, box, "--tolerance", "nan"], "argument --tolerance: tolerance must"),
        (["distance", box, box, "--pose-a", "2,0,0,0,0,2,0,0,0,0,2,0,0,0,0,1"],
         "argument --pose-a: pose_a"),
        (["distance", box, box, "--plot", str(mesh_files / "no" / "pair.png")],
         "argument --plot: the folder"),
        (["distance", box, box, "--plot", str(mesh_files / "pair.notaformat")],
         "argument --plot: .* does not end in a picture format"),
        (["distance", box, box, "--concavity", "0"], r"argument --concavity: must be a number"),
        (["distance", box, box, "--seed", "-1"], r"argument --seed: must be an integer in \[0, "),
        (["decompose", box, "-o", "x.npz", "--max-hull-vertices", "3"],
         "argument --max-hull-vertices: must be an integer at least 4"),
        (["scene", "--plot", str(mesh_files / "no" / "scene.png")], "argument --plot: the folder"),
        (["scene", "--threads", "0"], "argument --threads: must be an integer at least 1"),
        (["scene", "--threads", str(2**63)], r"argument --threads: threads must be in \[1, 1024\]"),
        (["scene", "--bodies", str(10**9)], r"argument --bodies: must be an integer in \[2, 100000\]"),
        (["scene", "--seed", "-1"], "argument --seed"),
        (["paper", "--repeats", "0"], "argument --repeats: must be an integer at least 1"),
        (["paper", "--seed", str(2**64)], "argument --seed"),
    ]
    import re

    for argv, message in usage_errors:
        with pytest.raises(SystemExit) as usage:
            main(argv)
        assert usage.value.code == 2, argv
        last = capsys.readouterr().err.strip().splitlines()[-1]
        assert re.search(message, last), (argv, last)
    # An option's value refused after parsing is the verb's error, shown with the verb's usage.
    with pytest.raises(SystemExit) as usage:
        main(["distance", box, box, "--tolerance", "-1"])
    assert usage.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: swarmcollide distance ")
    assert err.strip().splitlines()[-1].startswith(
        "swarmcollide distance: error: argument --tolerance: tolerance must")


def test_an_unusable_parts_file_is_one_line_and_exit_1(mesh_files, capsys):
    box = str(mesh_files / "box.stl")
    garbage = mesh_files / "garbage.npz"
    for content in (b"not an npz", b"PK\x03\x04 not a zip either"):
        garbage.write_bytes(content)
        assert main(["distance", box, str(garbage), "--decompose", "hull", "--quiet"]) == 1
        err = capsys.readouterr().err
        assert "Traceback" not in err and len(err.strip().splitlines()) == 1
        assert "garbage.npz' is not a parts file" in err
