import numpy as np
import pytest

from springlab.design.solve import SpringSpec, solve_design
from springlab.papers import juang2023 as paper


@pytest.fixture(scope="session")
def arm():
    """The four-link arm of 000 Table 2."""
    return paper.example_arm()


@pytest.fixture(scope="session")
def exact_springs(arm):
    """000 Table 3, solved exactly from the paper's free choices."""
    specs = [SpringSpec(s.i, s.j, s.pattern, **paper.FREE_CHOICES[(s.i, s.j)])
             for s in paper.EXAMPLE_CONFIGURATION]
    return solve_design(arm, specs).springs


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
