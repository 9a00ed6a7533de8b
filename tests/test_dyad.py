"""The non-zero-length spring compensator of paper 002: geometry, synthesis, moments."""

import numpy as np
import pytest

from springlab import SpringlabError
from springlab.mechanisms.dyad import algebra as dyalg
from springlab.mechanisms.dyad import geometry as dygeo
from springlab.mechanisms.dyad import model as dy
from springlab.mechanisms.dyad import simulation as dysim
from springlab.mechanisms.dyad import synthesis as dysyn
from springlab.papers import zhang2023 as paper

COMP = dy.Compensator(G=75.0, s=0.84, k=1000.0, l0=1.0)  # 002 Section V
PHI = np.radians(np.linspace(30, 150, 121))


def test_three_positions_are_met_exactly():
    phi = np.radians([30.0, 60.0, 120.0])
    y = dyalg.slider_positions(COMP, 184.0, phi)
    result = dyalg.synthesise(phi, y)
    assert result.residual < 1e-12
    np.testing.assert_allclose(dy.slider_height(result.dyad, phi), y, atol=1e-12)
    # at the prescribed positions the energy is C: the design is balanced there in energy
    np.testing.assert_allclose(dygeo.potential_energy(COMP, result.dyad, phi), 184.0, atol=1e-9)


def test_virtual_work_moment_is_minus_the_energy_derivative():
    d = dyalg.synthesise(PHI, dyalg.slider_positions(COMP, 195.0, PHI)).dyad
    h = 1e-6
    fd = -(dygeo.potential_energy(COMP, d, PHI + h) - dygeo.potential_energy(COMP, d, PHI - h)) / (2 * h)
    np.testing.assert_allclose(dygeo.unbalanced_moment(COMP, d, PHI), fd, atol=1e-6)


def test_printed_moment_takes_the_rod_force_as_f_cos_theta():
    # the printed spring moment is the virtual-work one times cos^2(theta), up to its sign
    d = dyalg.synthesise(PHI, dyalg.slider_positions(COMP, 195.0, PHI)).dyad
    y = dy.slider_height(d, PHI)
    cos_theta = (y**2 + d.l**2 - d.r**2) / (2 * y * d.l)
    spring_vw = dygeo.unbalanced_moment(COMP, d, PHI) - COMP.gravity_moment(PHI)
    spring_printed = COMP.gravity_moment(PHI) - dyalg.unbalanced_moment_paper(COMP, d, PHI)
    np.testing.assert_allclose(spring_printed, spring_vw * cos_theta**2, rtol=1e-10, atol=1e-12)


def test_gravity_alone_without_spring_force():
    # a spring at its free length everywhere cannot be; but with k tiny, M_ub -> G s sin(phi)
    weak = dy.Compensator(G=75.0, s=0.84, k=1e-9, l0=1.0)
    d = dy.Dyad(0.1, 0.5, 0.0)
    np.testing.assert_allclose(dygeo.unbalanced_moment(weak, d, PHI), 63.0 * np.sin(PHI), atol=1e-6)


@pytest.mark.parametrize("reading", dysyn.EQ32_READINGS)
def test_eq32_readings(reading):
    m = np.array([1.0, -2.0, 0.5])
    expected = {"signed sum": -0.5, "sum of magnitudes": 3.5, "sum of squares": 5.25, "maximum magnitude": 2.0}
    assert dysyn.eq32_objective(m, reading) == expected[reading]


def test_bad_inputs():
    with pytest.raises(SpringlabError, match="imaginary"):
        dyalg.slider_positions(COMP, 100.0, np.radians([30.0]))  # 2C < 2 G s (1 + cos 30 deg)
    with pytest.raises(SpringlabError, match="cannot close"):
        dy.slider_height(dy.Dyad(r=0.3, l=0.1, beta=0.0), np.radians([90.0]))
    with pytest.raises(SpringlabError, match="k must be"):
        dy.Compensator(G=75.0, s=0.84, k=0.0, l0=1.0)
    with pytest.raises(SpringlabError, match="at least 3"):
        dyalg.synthesise(np.radians([30.0, 60.0]), [0.6, 0.5])
    with pytest.raises(SpringlabError, match="reading"):
        dysyn.eq32_objective([1.0], "median")


def test_choose_C_readings_on_example_b():
    phi = np.radians(np.linspace(30, 150, 120))
    # minimising the largest |M_ub| (virtual work) over the 120 positions selects C = 194.9 J,
    # the paper's printed C = 195 J to its rounding
    assert abs(dysyn.choose_C(COMP, phi, "maximum magnitude") - 195.0) < 0.5
    with pytest.raises(SpringlabError, match="reading"):
        dysyn.choose_C(COMP, phi, "median")


def test_signed_sum_stationary_point_is_a_minimum_on_example_a():
    phi = np.radians([30.0, 60.0, 120.0])
    C = dysyn.choose_C(COMP, phi, "signed sum stationary")

    def total(c):
        return dygeo.unbalanced_moment(COMP, dysyn.design_for_C(COMP, c, phi), phi).sum()

    assert total(C) < total(C - 1.0) and total(C) < total(C + 1.0)


def test_optimiser_beats_the_start_and_respects_bounds():
    grid = np.radians(np.linspace(30, 150, 121))
    start = dy.Dyad(0.125, 0.502, np.radians(0.08))
    best = dysyn.optimise(COMP, grid, start)
    assert best.value < dygeo.max_unbalanced(COMP, start, grid)
    assert best.parameters["l0"] == COMP.l0
    free = dysyn.optimise(COMP, grid, start, free_l0=True)
    assert free.value <= best.value + 1e-9
    assert 0.0 <= free.parameters["l0"] <= 3.0


def test_the_optimiser_refuses_bounds_that_allow_no_dyad():
    grid = np.radians(np.linspace(30, 150, 121))
    start = dy.Dyad(0.125, 0.502, np.radians(0.08))
    for name, bound in (("r", (-0.5, 1.0)), ("l", (0.0, 2.0)), ("r", (float("nan"), 1.0))):
        with pytest.raises(SpringlabError, match=rf"bounds\['{name}'\].*lower bound above 0"):
            dysyn.optimise(COMP, grid, start, bounds={name: bound})
    assert dysyn.optimise(COMP, grid, start, bounds={"r": (0.05, 1.0)}).parameters["r"] >= 0.05  # the control


def test_the_exchange_of_angles_finds_the_minimax_of_the_whole_grid():
    """optimise constrains only the angles that matter; the epigraph over every angle of the grid
    (SLSQP with finite differences, the textbook form) reaches the same largest |M_ub|, and no
    small step from the optimum lowers it."""
    from scipy.optimize import minimize

    grid = np.radians(np.linspace(30, 150, 601))
    start = dy.Dyad(0.13, 0.55, np.radians(5.0))
    best = dysyn.optimise(COMP, grid, start)

    def m(x):
        return dygeo.unbalanced_moment(COMP, dy.Dyad(*x[:3]), grid)

    x0 = np.array([start.r, start.l, start.beta, dygeo.max_unbalanced(COMP, start, grid)])
    full = minimize(lambda x: x[-1], x0, method="SLSQP", options={"maxiter": 500, "ftol": 1e-12},
                    constraints=[{"type": "ineq", "fun": lambda x: x[-1] - m(x)}, {"type": "ineq", "fun": lambda x: x[-1] + m(x)}],
                    bounds=[(0.01, 1.0), (0.05, 2.0), (-np.pi / 2, np.pi / 2), (0, None)])
    assert abs(best.value - dygeo.max_unbalanced(COMP, dy.Dyad(*full.x[:3]), grid)) < 1e-8 * best.value
    d = best.design  # a local minimax: no small step in r, l or beta lowers the largest |M_ub|
    for step in np.vstack([np.eye(3), -np.eye(3)]) * 1e-6:
        assert dygeo.max_unbalanced(COMP, dy.Dyad(d.r + step[0], d.l + step[1], d.beta + step[2]), grid) > best.value - 1e-12
    assert best.value == dygeo.max_unbalanced(COMP, best.design, grid)  # judged on the whole grid, not the subset


def test_slow_drive_in_exudyn_needs_minus_the_unbalanced_moment():
    design = dy.Dyad(0.125, 0.502, np.radians(0.08))
    run = dysim.follow(COMP, design, np.radians(30.0), np.radians(150.0), duration=10.0, samples=61)
    np.testing.assert_allclose(np.degrees(run.phi[[0, -1]]), [30.0, 150.0])
    assert np.abs(run.torque + dygeo.unbalanced_moment(COMP, design, run.phi)).max() < 1e-3
    # gravity alone: the drive holds the weight, G s sin(phi) against larger phi
    weak = dy.Compensator(G=75.0, s=0.84, k=1e-9, l0=1.0)
    run = dysim.follow(weak, design, np.radians(30.0), np.radians(150.0), duration=10.0, samples=5)
    np.testing.assert_allclose(run.torque, -63.0 * np.sin(run.phi), atol=1e-3)


def test_batch_moments_and_selection_agree_with_the_single_dyad_versions():
    """The batched route of the readings search computes what the one-dyad functions do."""
    comp = paper.compensator()
    dyads = [paper.printed_dyad("A"), paper.printed_dyad("B")]
    phi = np.radians(np.linspace(30, 150, 61))
    for moment, f in dysyn.MOMENTS.items():
        batch, closes = dysyn.batch_moments(comp, [d.r for d in dyads], [d.l for d in dyads], [d.beta for d in dyads],
                                         phi, moment)
        assert closes.all()
        assert np.allclose(batch, [f(comp, d, phi) for d in dyads], rtol=0, atol=1e-9)
    positions = np.radians([30.0, 90.0, 150.0])
    path = dysyn.synthesis_path(comp, positions, [184.0])
    d = dysyn.design_for_C(comp, 184.0, positions)
    assert np.allclose([path["r"][0], path["l"][0], path["beta"][0]], [d.r, d.l, d.beta], rtol=1e-12)
    grid_C = dysyn.select_C(comp, positions, "maximum magnitude", step=0.01)
    assert abs(grid_C - dysyn.choose_C(comp, positions, "maximum magnitude")) < 0.02


def test_the_printed_closure_forms_restate_the_loop_and_a_flipped_angle_does_not():
    import sympy as sp

    forms = paper.closure_forms()
    assert sorted(forms.printed) == [8, 9, 10, 11, 15, 16, 21, 22, 23]
    for number, form in forms.printed.items():
        assert sp.simplify(sp.expand_trig(form.subs(forms.z) - forms.closure)) == 0, number
    assert sp.simplify(forms.closure.subs(forms.y, forms.eq24)) == 0  # Eq. (24) closes the loop
    flipped = forms.printed[9].subs(forms.phi, forms.phi + 2 * forms.beta)  # the control: phi + beta
    assert sp.simplify(sp.expand_trig(flipped - forms.closure)) != 0


def test_example_bs_table_ends_with_the_printed_dyad_to_its_printed_digits():
    table = paper.example_b_table({"a reading": (195.2, paper.printed_dyad("B"))})
    assert list(table.rows[-1]) == ["**printed**", "195", "0.125", "0.502", "0.08"]
    assert list(table.rows[0][:2]) == ["a reading", "195.200"]
