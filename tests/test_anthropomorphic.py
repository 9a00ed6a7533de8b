"""Paper 004: the two-spring arm, its layouts, and its tie to paper 000."""

import numpy as np
import pytest
import sympy as sp

from springlab import SpringlabError, UnbalanceableError
from springlab.design.rules import enumerate_configurations, is_admissible
from springlab.design.solve import SpringSpec, solve_design
from springlab.energy import geometry
from springlab.mechanisms import two_spring_arm as an
from springlab.papers import lenzo2017 as paper


def arm_for(layout):
    return paper.ARM if layout in ("a", "b") else paper.ARM_COUNTERMASS


def test_eq15_derived_from_the_geometry_equals_the_printed_one():
    derived, printed = an.derived_conditions(), an.printed_eq15()
    assert set(derived) == set(printed)
    for key in derived:
        assert sp.expand(derived[key] + printed[key]) != 0  # a wrong sign would be caught
        assert sp.expand(derived[key] - printed[key]) == 0


def test_eqs_7_10_and_14_derived_equal_the_printed_ones_and_fig_4a_has_no_rates():
    _, eq7 = an.one_link_condition()
    assert sp.expand(eq7 - an.printed_eq7()) == 0 and sp.expand(eq7 + an.printed_eq7()) != 0
    eq10 = an.two_link_conditions()
    assert [sp.expand(d - p) for d, p in zip(eq10, an.printed_eq10(), strict=True)] == [0, 0]
    assert sp.expand(eq10[0] - an.printed_eq10()[1]) != 0  # the control: the lines are not interchangeable
    kept, printed = an.derived_conditions(k1=True), an.printed_eq14()
    assert all(sp.expand(kept[key] - printed[key]) == 0 for key in kept)
    assert an.rates_without_k12() == []  # Fig. 4a: k1 and k2 alone cannot balance the arm
    s = an.energy_symbols()  # the control: with k12 kept, the same solve finds rates
    assert sp.solve(list(kept.values()), [s["k1"], s["k2"], s["k12"]], dict=True) != []


def test_the_layouts_tables_hold_every_layout_and_000s_solver_agrees_on_a_and_b():
    designs = paper.designs()
    assert [d.layout for _, d in designs.values()] == ["a", "b", "c", "d"]
    assert len(paper.design_table(designs).rows) == 4
    table, agreement = paper.enumeration_table(designs)
    assert [r[3] for r in table.rows] == ["yes", "yes", "no", "no"] and max(agreement) < 1e-12


@pytest.mark.parametrize("layout", ["a", "b", "c", "d"])
@pytest.mark.parametrize("elbow_axis", [(0, 0, 1), (0, 1, 1)])
def test_each_layout_balances_for_any_elbow_axis(layout, elbow_axis):
    arm = arm_for(layout)
    a12, b12 = paper.FREE_CHOICES[layout]
    design = an.solve(arm, a2=paper.A2, a12=a12, b12=b12, layout=layout)
    assert design.layout == layout
    chain = arm.chain(paper.FOREARM_LENGTH, elbow_axis=elbow_axis)
    X = chain.directions(chain.random_angles(1000, np.random.default_rng(4)))
    springs = an.to_chain_springs(arm, design)
    gravity_range = np.ptp(geometry.gravity_energy(chain, X))
    assert np.ptp(geometry.total_energy(chain, springs, X)) < 1e-10 * gravity_range
    assert np.ptp(geometry.total_energy(chain, springs[:1], X)) > 1e-3 * gravity_range


@pytest.mark.parametrize("layout, pattern", [("a", "(-,-)"), ("b", "(+,+)")])
def test_paper_000_enumerator_and_solver_give_the_same_designs(layout, pattern):
    arm = paper.ARM
    a12, b12 = paper.FREE_CHOICES[layout]
    lenzo = an.solve(arm, a2=paper.A2, a12=a12, b12=b12)
    chain = arm.chain(paper.FOREARM_LENGTH)
    s13, s23 = an.to_chain_springs(arm, lenzo)
    assert (s13.pattern, s23.pattern) == ("(+,+)", pattern)
    configs = {tuple(str(s) for s in cfg) for cfg in enumerate_configurations(3)}
    assert ("S(1,3)(+,+)", f"S(2,3){pattern}") in configs
    ours = solve_design(chain, [SpringSpec(1, 3, "(+,+)", a=paper.A2),
                                SpringSpec(2, 3, pattern, a=b12 - arm.l1, b=a12)]).springs
    for mine, theirs in zip(ours, (s13, s23), strict=True):
        assert mine.i == theirs.i and mine.j == theirs.j
        np.testing.assert_allclose([mine.a, mine.b, mine.k], [theirs.a, theirs.b, theirs.k], rtol=1e-12)


def test_layouts_c_and_d_lie_outside_paper_000s_rules():
    arm = paper.ARM_COUNTERMASS
    for layout in ("c", "d"):
        a12, b12 = paper.FREE_CHOICES[layout]
        springs = an.to_chain_springs(arm, an.solve(arm, a2=paper.A2, a12=a12, b12=b12))
        assert not is_admissible(3, [f"S(1,3){springs[0].pattern}", f"S(2,3){springs[1].pattern}"])


def test_bad_inputs():
    with pytest.raises(UnbalanceableError, match="a2 > 0"):
        an.solve(paper.ARM, a2=-0.1, a12=0.06, b12=0.4)
    with pytest.raises(UnbalanceableError, match="needs h2 < 0"):
        an.solve(paper.ARM, a2=0.15, a12=0.06, b12=0.2, layout="c")
    with pytest.raises(UnbalanceableError, match="layout a, not b"):
        an.solve(paper.ARM, a2=0.15, a12=-0.05, b12=0.2, layout="b")
    with pytest.raises(UnbalanceableError, match="k12"):
        an.solve(paper.ARM, a2=0.15, a12=0.06, b12=0.2)  # a layout-c choice on an h2 > 0 arm
    with pytest.raises(SpringlabError, match="h1 must be > 0"):
        an.Arm(m1=2.0, m2=1.5, l1=0.3, h1=0.0, h2=0.18)


def test_exudyn_hold_of_the_arm():
    from springlab.energy import simulation as sim

    arm = paper.ARM
    a12, b12 = paper.FREE_CHOICES["b"]
    springs = an.to_chain_springs(arm, an.solve(arm, a2=paper.A2, a12=a12, b12=b12))
    chain = arm.chain(paper.FOREARM_LENGTH)
    hold = sim.hold_test(chain, springs, chain.random_angles(3, np.random.default_rng(5)), duration=1.0)
    assert hold.balanced.max_angle_drift < 1e-6
    assert hold.control.max_angle_drift > 0.1
