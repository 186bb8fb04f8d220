"""The main job: ``python -m swarmcollide paper`` reproduces the paper's Section IV."""

import subprocess
import sys

import pytest

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
    assert "--repeats must be at least 1" in capsys.readouterr().err
