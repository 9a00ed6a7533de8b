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
