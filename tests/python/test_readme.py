"""The README's Python example runs as written."""

import re
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def python_blocks():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.DOTALL)
    assert blocks, "the README has no Python example"
    return blocks


def test_python_example_runs():
    namespace: dict = {}
    exec(compile(python_blocks()[0], str(README), "exec"), namespace)
    assert namespace["r"].certified
    assert len(namespace["batch"]) == 1000


def test_scene_example_runs():
    namespace: dict = {}
    exec(compile(python_blocks()[1], str(README), "exec"), namespace)
    assert namespace["hits"].certified.all() and len(namespace["hits"]) > 0
    assert (namespace["touching"].counts >= 1).all()
