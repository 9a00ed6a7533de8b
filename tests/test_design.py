import numpy as np
import sympy as sp

from springlab import random_directions, serial_chain
from springlab.design import solve as design
from springlab.energy import geometry, quadratic
from springlab.papers import juang2023 as paper


def test_table_3_solved_exactly(arm):
    specs = [design.SpringSpec(s.i, s.j, s.pattern, **paper.FREE_CHOICES[(s.i, s.j)])
             for s in paper.EXAMPLE_CONFIGURATION]
    solved = design.solve_design(arm, specs)
    assert solved.exact["b_S(1,4)"] == sp.Rational(7, 110)
    assert solved.exact["k_S(1,4)"] == sp.Rational(2156, 3)
    assert solved.exact["k_S(1,2)"] == 294
    assert solved.exact["k_S(2,4)"] == 2156
    assert solved.exact["k_S(3,4)"] == sp.Rational(10976, 5)
    assert solved.exact["b_S(2,4)"] == sp.Rational(7, 110)


def test_find_design_balances_a_random_arm(rng):
    r = rng.uniform(0.1, 0.5, 3)
    chain = serial_chain(r, r * rng.uniform(0.1, 0.9, 3), rng.uniform(0.5, 5, 3))
    cfg, springs = design.design_for(chain, seed=3)
    assert np.abs(quadratic.balance_residual(chain, springs)).max() < 1e-12 * chain.g * sum(chain.m)
    X = random_directions(chain.n, 300, rng)
    assert np.ptp(geometry.total_energy(chain, springs, X)) < 1e-10 * np.ptp(geometry.gravity_energy(chain, X))
    assert [s.pattern for s in springs] == [c.pattern for c in cfg]
