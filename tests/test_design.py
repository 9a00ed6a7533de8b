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


def test_a_search_past_its_deadline_begins_no_new_start(arm, monkeypatch):
    """find_design's deadline (and design_arm's time_limit through it): a start on a long arm
    takes seconds, so the limit is checked before each one (a 20-link arm ran 36 s on a 5 s limit)."""
    import time
    from types import SimpleNamespace

    import pytest

    from springlab.design import rank
    from springlab.errors import SearchExhaustedError
    from springlab.model.armfile import arm_from_dict

    calls = []

    def no_convergence(fun, z0, **kwargs):  # every start ends far from a design
        calls.append(1)
        return SimpleNamespace(fun=np.ones(3), x=z0)

    monkeypatch.setattr(design, "least_squares", no_convergence)
    slots = ["S(1,4)(+,+)", "S(1,2)(+,+)", "S(2,4)(+,+)", "S(3,4)(+,+)"]
    with pytest.raises(SearchExhaustedError, match="time limit was reached after 1 of 30 starts"):
        design.find_design(arm, slots, restarts=30, deadline=time.time() - 1.0)
    assert len(calls) == 1
    with pytest.raises(SearchExhaustedError, match="after 30 random starts"):  # the control: no deadline, every start
        design.find_design(arm, slots, restarts=30)
    assert len(calls) == 31
    calls.clear()

    def slow_no_convergence(fun, z0, **kwargs):  # a start of 0.2 s: 30 of them would take 6 s
        time.sleep(0.2)
        return no_convergence(fun, z0, **kwargs)

    monkeypatch.setattr(design, "least_squares", slow_no_convergence)
    spec = arm_from_dict({"name": "six links", "link": [{"length": 0.1, "com": 0.05, "mass": 1.0}] * 6})
    report = rank.design_arm(spec, method="ground springs", restarts=30, time_limit=0.5, minimise_force=False)
    assert not report.designs and "time limit" in report.stopped and 1 <= len(calls) <= 6
