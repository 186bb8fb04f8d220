"""The files corpus (mesh files, the command line, what users pass from other libraries) in
sandboxed children: a few dozen cases of another seed than the census's keep ``make test`` short;
``tests/fuzz/census.py --corpus files`` runs hundreds. The first tests check the judge itself."""

from __future__ import annotations

from fuzz_files import ERROR, FILE_FAILURES, FILE_FAMILIES, FileCase, _judge, make_file_case
from fuzz_judge import category_of
from sandbox import Sandbox

FILES_SEED = 1  # the census's files corpus is seed 0
FILES_CASES = 24
TIMEOUT = 30.0


def test_the_files_corpus_is_reproducible_and_covers_every_family():
    first = [make_file_case(0, i) for i in range(200)]
    again = [make_file_case(0, i) for i in range(200)]
    assert [repr(c) for c in first] == [repr(c) for c in again]
    assert {case.family for case in first} == set(FILE_FAMILIES)


def test_the_files_judge_finds_unclear_messages_and_refusals(tmp_path):
    wrong_name = FileCase("t:0", "cli", "distance", "", {}, ("distance", "a.obj", "b.obj",
                          "--method", "bogus"), {}, ERROR, ("--tolerance",), (2,))  # fmt: skip
    assert _judge(wrong_name, str(tmp_path))[0] == "unclear"
    refused = FileCase("t:1", "cli", "paper", "", {}, ("paper", "--repeats", "0"))
    assert _judge(refused, str(tmp_path))[0] == "refused"
    missing = FileCase("t:2", "mesh", "CompoundBody.load", "", {}, (str(tmp_path / "p.npz"),),
                       {}, ERROR, ("p.npz",))  # fmt: skip
    assert _judge(missing, str(tmp_path))[0] == "ok"  # a missing file, refused by name


def test_the_files_cases_neither_crash_hang_nor_answer_unclearly():
    from fuzz_files import run_file_case

    failures = []
    tasks = ((i, run_file_case, (FILES_SEED, i)) for i in range(FILES_CASES))
    with Sandbox(parallel=2, preload=("fuzz_files",)) as sandbox:
        for index, outcome in sandbox.map(tasks, timeout=TIMEOUT, memory_limit=4 << 30):
            category, reason = category_of(outcome)
            if category in FILE_FAILURES or category == "suite-error":
                case = make_file_case(FILES_SEED, index)
                failures.append(f"{case.id} {case.family} {case.call} [{case.note}]: "
                                f"{category}: {reason[:200]}")  # fmt: skip
    assert not failures, "\n".join(failures)

