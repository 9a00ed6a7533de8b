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


def test_a_payload_that_is_not_a_number_is_refused_by_name():
    with pytest.raises(SpringlabError, match="payload mass must be a real number, got '0.5'"):
        chain_with().with_payload("0.5")
    with pytest.raises(SpringlabError, match="payload mass must be finite and >= 0"):
        chain_with().with_payload(-1.0)
    assert chain_with().with_payload(0.5).m[-1] == pytest.approx(3.7)


def test_a_sample_count_below_zero_or_too_large_is_refused_by_name():
    chain = chain_with()
    with pytest.raises(SpringlabError, match="size must be an integer >= 0, got -3"):
        chain.random_angles(-3)
    with pytest.raises(SpringlabError, match=r"random_angles\(size=1000000000000\) would need .* ask for fewer"):
        chain.random_angles(10**12)
    assert chain.random_angles(0, rng=1).shape == (0, 2, 3)


def test_an_attachment_whose_energy_overflows_is_named():
    chain = chain_with()
    with pytest.raises(SpringlabError, match=r"a of S\(1,3\) = 1e\+200 m .* give the attachment in m"):
        geometry.energies(chain, [Spring(1, 3, 1e200, 0.1, 100.0)], random_directions(chain.n, 2, rng=0))
    with pytest.raises(SpringlabError, match=r"b of S\(1,3\) = -1e\+160 m"):
        geometry.energies(chain, [Spring(1, 3, 0.1, -1e160, 100.0)], random_directions(chain.n, 2, rng=0))
    with pytest.raises(SpringlabError, match=r"k of S\(1,3\) = 1e\+308 N/m overflows"):  # the rate, not the ends
        geometry.energies(chain, [Spring(1, 3, 1.0, 0.1, 1e308)], random_directions(chain.n, 2, rng=0))


def test_unknown_free_choices_are_named_before_anything_is_solved():
    import time

    from springlab.mechanisms.planar import synthesis
    from springlab.papers import juang2022

    start = time.perf_counter()
    with pytest.raises(SpringlabError, match=r"choices names 'k_S99', not a parameter of 'Λ3-1': choose among k_S12"):
        synthesis.design(juang2022.ARM, "Λ3-1", {"k_S99": 1.0})
    with pytest.raises(SpringlabError, match=r"free names 'A_S99'"):
        synthesis.solve_configuration("Λ3-1", ["A_S99"])
    assert time.perf_counter() - start < 5.0  # sympy never ran (it took 25-50 s)
    assert len(synthesis.design(juang2022.ARM, "Λ3-1", juang2022.FREE_CHOICES)) == 4


def test_a_search_bound_below_the_feasible_range_names_the_bound_and_the_least_that_works():
    from springlab.mechanisms.dyad import synthesis
    from springlab.papers import zhang2023

    phi = np.radians([30.0, 90.0, 150.0])
    with pytest.raises(SpringlabError, match=r"C_max = 0 J is not above 117\.56 J, the smallest C"):
        synthesis.choose_C(zhang2023.compensator(), phi, synthesis.C_READINGS[0], C_max=0)
    with pytest.raises(SpringlabError, match="C_max must be finite"):
        synthesis.choose_C(zhang2023.compensator(), phi, synthesis.C_READINGS[0], C_max=np.nan)


def test_an_executor_class_instead_of_an_instance_says_to_make_one():
    from concurrent.futures import ThreadPoolExecutor

    from springlab.executors import check_executor

    with pytest.raises(SpringlabError, match=r"got the class ThreadPoolExecutor: pass ThreadPoolExecutor\(\)"):
        check_executor(ThreadPoolExecutor)
    with ThreadPoolExecutor(max_workers=1) as pool:
        assert check_executor(pool) is pool
