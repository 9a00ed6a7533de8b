"""Bad input raises a springlab error (a ValueError) that names the parameter."""

import numpy as np
import pytest

from springlab import Spring, SpringlabError, UnbalanceableError, random_directions, serial_chain
from springlab.design.rules import SpringSlot, rule_violations
from springlab.design.solve import SpringSpec, solve_design
from springlab.energy import geometry, quadratic
from springlab.model.trajectories import linear_sweep

GOOD = dict(r=[0.3, 0.24], d=[0.15, 0.12], m=[4.0, 3.2])


def chain_with(**changes):
    return serial_chain(**{**GOOD, **changes})


@pytest.mark.parametrize("changes, fragment", [
    (dict(m=[4.0, -1.0]), "m_3"),
    (dict(m=[0.0, 3.2]), "m_2"),
    (dict(r=[0.3, 0.0]), "r_3"),
    (dict(r=[-0.3, 0.24]), "r_2"),
    (dict(d=[0.15, 0.30]), "d_3"),
    (dict(d=[-0.01, 0.12]), "d_2"),
    (dict(r=[np.nan, 0.24]), "r_2"),
    (dict(d=[0.15, np.inf]), "d_3"),
    (dict(m=[4.0]), "one entry per moving link"),
    (dict(g=0.0), "g must be"),
])
def test_bad_chain_data(changes, fragment):
    with pytest.raises(SpringlabError, match=fragment):
        chain_with(**changes)


@pytest.mark.parametrize("kwargs, fragment", [
    (dict(i=1, j=2, a=0.1, b=0.1, k=0.0), "k of S"),
    (dict(i=1, j=2, a=0.1, b=0.1, k=-5.0), "k of S"),
    (dict(i=2, j=2, a=0.1, b=0.1, k=5.0), "i < j"),
    (dict(i=0, j=2, a=0.1, b=0.1, k=5.0), "1 <= i < j"),
    (dict(i=1, j=2, a=np.nan, b=0.1, k=5.0), "a of S"),
    (dict(i=1, j=2, a=0.1, b=0.1, k=5.0, free_length=-0.1), "free_length"),
])
def test_bad_springs(kwargs, fragment):
    with pytest.raises(SpringlabError, match=fragment):
        Spring(**kwargs)


def test_spring_beyond_the_chain():
    with pytest.raises(SpringlabError, match="only 3 links"):
        geometry.total_energy(chain_with(), [Spring(1, 4, 0.1, 0.1, 10.0)], random_directions(3, 2, 0))


@pytest.mark.parametrize("make, fragment", [
    (lambda: np.zeros((5, 4, 3)), "shape"),
    (lambda: np.full((5, 3, 3), np.nan), "NaN"),
    (lambda: 2 * random_directions(3, 5, 0), "unit vectors"),
    (lambda: -random_directions(3, 5, 0), "ground link"),
])
def test_bad_poses(make, fragment):
    with pytest.raises(SpringlabError, match=fragment):
        geometry.gravity_energy(chain_with(), make())


def test_bad_angles():
    with pytest.raises(SpringlabError, match="angles must have shape"):
        chain_with().directions(np.zeros((4, 3, 3)))


def test_quadratic_form_rejects_free_length_springs():
    with pytest.raises(ValueError, match="zero-free-length"):
        quadratic.spring_matrix(chain_with(), Spring(1, 2, 0.1, 0.1, 10.0, free_length=0.05))


def test_bad_pattern_and_configuration_range():
    with pytest.raises(SpringlabError, match="pattern"):
        SpringSlot(1, 2, "(+,0)")
    assert rule_violations(3, ["S(1,4)"])[0].rule == "range"


def test_spec_sign_contradicts_pattern():
    with pytest.raises(SpringlabError, match="contradicts its pattern"):
        SpringSpec(3, 4, "(-,-)", a=0.2)


def test_underdetermined_design_asks_for_more_choices():
    with pytest.raises(SpringlabError, match="undetermined: fix"):
        solve_design(chain_with(), [SpringSpec(1, 3, "(+,+)", a=0.1), SpringSpec(2, 3, "(+,+)")])


def test_negative_stiffness_is_rejected(arm):
    with pytest.raises(UnbalanceableError, match="negative stiffness"):
        solve_design(arm, [SpringSpec(1, 3, "(+,+)", a=0.1), SpringSpec(1, 4, "(+,+)", a=0.1, k=1000.0),
                           SpringSpec(2, 3, "(+,+)", a=0.1, b=0.1), SpringSpec(2, 4, "(-,-)", k=500.0)])


def test_unbalanceable_configuration_is_rejected(arm):
    # without S(2,4) nothing offsets component (2,4): Eqs. (39) have no solution
    with pytest.raises(UnbalanceableError):
        solve_design(arm, [SpringSpec(1, 2, "(+,+)", a=0.15, b=0.24), SpringSpec(1, 4, "(+,+)", a=0.06),
                           SpringSpec(3, 4, "(-,-)", a=-0.2)])


def test_attachment_off_the_link_is_rejected(arm):
    # the printed example, but S(1,2) attached at b = 0.24 m on a link made 0.2 m long
    short = serial_chain([0.2, 0.24, 0.20], [0.1, 0.12, 0.10], [4.0, 3.2, 2.8], g=9.8)
    with pytest.raises(UnbalanceableError, match="off the link"):
        solve_design(short, [SpringSpec(1, 4, "(+,+)", a=0.06), SpringSpec(1, 2, "(+,+)", a=0.15, b=0.24),
                             SpringSpec(2, 4, "(+,+)", a=0.1), SpringSpec(3, 4, "(-,-)", a=-0.2, b=-0.1)])


@pytest.mark.parametrize("kwargs, fragment", [
    (dict(duration=0.0, samples=10), "duration"),
    (dict(duration=30.0, samples=1), "samples"),
])
def test_bad_trajectory(kwargs, fragment):
    with pytest.raises(SpringlabError, match=fragment):
        linear_sweep(np.zeros((3, 3)), np.ones((3, 3)), **kwargs)


def test_bad_random_pose_request():
    with pytest.raises(SpringlabError, match="n must be"):
        random_directions(1, 10)
