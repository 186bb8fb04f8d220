import numpy as np
import pytest

from swarmcollide import paper


@pytest.fixture
def tetra_a() -> np.ndarray:
    return paper.A.copy()


@pytest.fixture
def touching_b() -> np.ndarray:
    return paper.B_COLLIDING.copy()


@pytest.fixture
def separate_b() -> np.ndarray:
    return paper.B_SEPARATE.copy()
