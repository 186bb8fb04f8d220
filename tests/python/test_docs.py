"""The examples in the docstrings run and give what they show."""

import doctest

import pytest

import swarmcollide
import swarmcollide._core
import swarmcollide.dask
import swarmcollide.mesh
import swarmcollide.motion
import swarmcollide.plot
import swarmcollide.poses
import swarmcollide.queries
import swarmcollide.robot
import swarmcollide.robot_plot
import swarmcollide.scene_demo
import swarmcollide.shape_json

MODULES = [
    swarmcollide,
    swarmcollide.queries,
    swarmcollide._core,
    swarmcollide.dask,
    swarmcollide.mesh,
    swarmcollide.plot,
    swarmcollide.poses,
    swarmcollide.scene_demo,
    swarmcollide.robot,
    swarmcollide.robot_plot,
    swarmcollide.shape_json,
    swarmcollide.motion,
]


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__)
def test_docstring_examples(module):
    finder = doctest.DocTestFinder(exclude_empty=True)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    tests = [t for t in finder.find(module, module.__name__) if t.examples]
    for test in tests:
        runner.run(test)
    assert runner.failures == 0
    assert tests, f"{module.__name__} has no examples"
