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


@pytest.fixture(scope="session")
def ur5_two_point():
    """The UR5's two-point design over 5 mm pulleys in the limits' box, built once per test run and shared
    by every worker (tests/quickruns.py); tests read it and never change it."""
    from quickruns import shared

    from springlab.design.arms import design_model
    from springlab.model.robots import load_robot

    return shared("ur5-two-point", lambda: design_model(load_robot("UR5"), samples=300, fit_poses=100,
                                                        pulley_radius=0.005, collisions=False))



@pytest.fixture(scope="session")
def pendulum_belts():
    """The double pendulum with belt springs: each link too short for its coil, or its pulley too near the table,
    so both coils ride on brackets of the level frame; built once per test run and shared by every worker."""
    from quickruns import shared

    from springlab.design.arms import design_model
    from springlab.model.robots import load_robot

    return shared("pendulum-belts", lambda: design_model(load_robot("double pendulum"), pulley_radius=None,
                                                         layout="belts", samples=600))
