"""The printed formulas against the geometry, symbolically (sympy)."""

import pytest
import sympy as sp

from springlab.energy import quadratic as q


@pytest.mark.parametrize("n", [2, 3, 4, 5])
def test_gravity_matrix_equals_expanded_geometry(n):
    assert sp.expand(q.expand_gravity_energy(n) - q.quadratic_form(q.symbolic_gravity_matrix(n))) == 0


@pytest.mark.parametrize("i, j, n", [(1, 2, 2), (1, 3, 3), (2, 3, 3), (1, 4, 4), (2, 4, 4), (1, 5, 5), (2, 5, 5)])
def test_spring_matrix_equals_expanded_geometry(i, j, n):
    names = ["a" if u == i else "b" if u == j else u for u in range(1, n + 1)]
    form = q.quadratic_form(q.symbolic_spring_matrix(i, j, n), names)
    assert sp.expand(q.expand_spring_energy(i, j, n, on_joint_lines=False) - form) == 0


def test_a_wrong_formula_would_be_caught():
    # a check that cannot fail is no check: flip Eq. (23a)'s sign and the comparison must fail
    K = q.symbolic_spring_matrix(1, 3, 3)
    K[0, 2] = -K[0, 2]
    assert sp.expand(q.expand_spring_energy(1, 3, 3) - q.quadratic_form(K)) != 0


def test_eq_48_for_the_example():
    eqs = q.balancing_equations(4, [(1, 2), (1, 4), (2, 4), (3, 4)])
    r, d, m, g = q.chain_symbols(4)
    a14, b14, k14 = q.spring_symbols(1, 4)
    assert sp.expand(eqs[(1, 4)] - (m[2] * g * d[2] - k14 * a14 * b14)) == 0  # Eq. (48a)
    assert sp.expand(eqs[(1, 3)] - (m[1] * g * d[1] + m[2] * r[1] * g - k14 * a14 * r[1])) == 0  # (48b)


def test_000s_printed_equations_equal_the_derived_ones_and_a_wrong_sign_is_caught():
    import sympy as sp

    from springlab.energy import quadratic as qd
    from springlab.papers import juang2023 as p

    planar = p.printed_planar()
    assert sp.expand(qd.planar_gravity_energy(4) - planar["3"]) == 0
    assert sp.expand(planar["4"] - planar["3"]) == 0
    Gp = qd.planar_gravity_matrix(4)
    assert all(sp.simplify(Gp[0, j - 1] - planar["7"][j]) == 0 for j in (2, 3, 4))
    G4 = qd.symbolic_gravity_matrix(4)
    assert all(sp.expand(G4[u - 1, v - 1] - e) == 0 for (u, v), e in p.printed_eq13().items())
    assert sp.expand(G4[0, 1] + p.printed_eq13()[(1, 2)]) != 0  # the control: a flipped sign
    eq28, K14 = p.printed_eq28(), qd.symbolic_spring_matrix(1, 4, 4)
    assert sp.expand(K14.trace() - eq28.pop("C")) == 0
    assert all(sp.expand(K14[u - 1, v - 1] - e) == 0 for (u, v), e in eq28.items())
    eqs39 = qd.balancing_equations(4, [(s.i, s.j) for s in p.EXAMPLE_CONFIGURATION])
    eq48 = p.printed_eq48()
    assert set(eqs39) == set(eq48)
    assert all(sp.expand(eqs39[k] - e) == 0 or sp.expand(eqs39[k] + e) == 0 for k, e in eq48.items())


def test_a_mono_articulated_spring_turned_equally_at_both_ends_keeps_its_length_on_a_planar_arm():
    from springlab.papers import juang2023 as p

    lengths = p.mono_articulated_lengths(p.example_arm(), 200, 5)
    planar, spherical = lengths["planar"], lengths["spherical"]
    assert abs(planar[45, 45] - planar[0, 0]).max() < 1e-12
    assert abs(planar[45, 30] - planar[0, 0]).max() > 1e-3  # the controls: unequal turns,
    assert abs(spherical[45, 45] - spherical[0, 0]).max() > 1e-3  # and a spatial arm
    assert set(p.TRAJECTORIES) == {"fig16_spatial", "fig17_planar"}
