"""Degenerate but valid arms design, and their designs balance by route 2 and by route 1.

A centre of mass on a joint (d = 0) or at the far end (d = r) on any link, the end link
included; a very light link; arms of one and two moving links; millimetre and tonne
scales. An arm whose end link has d = 0 has G_1,n = 0 (000 Eq. 18): it must get a design
with no spring on that link, not a verdict of "unbalanceable".
"""

from __future__ import annotations

import numpy as np
import pytest

from springlab.design.rank import VERIFY_TOLERANCE, design_arm, verify, workspace_poses
from springlab.design.solve import balanced_core, design_for
from springlab.energy import geometry, quadratic
from springlab.model.armfile import ArmSpec
from springlab.model.springs import Spring


def spec(r, d, m, **kw):
    return ArmSpec("degenerate", tuple(r), tuple(d), tuple(m), ("spherical",) * len(r), samples=200, **kw)


R, D, M = [0.3, 0.24, 0.2], [0.15, 0.12, 0.1], [4.0, 3.2, 2.8]

ARMS = {
    "d = 0 on every link": spec(R, [0.0, 0.0, 0.0], M),
    "d = r on every link": spec(R, R, M),
    "d = 0 on the end link": spec(R, [0.15, 0.12, 0.0], M),
    "d = r on the end link": spec(R, [0.15, 0.12, 0.2], M),
    "d = 0 on the first link": spec(R, [0.0, 0.12, 0.1], M),
    "d = r on the middle link": spec(R, [0.15, 0.24, 0.1], M),
    "a very light middle link (1 mg)": spec(R, D, [4.0, 1e-6, 2.8]),
    "a very light end link (1 mg)": spec(R, D, [4.0, 3.2, 1e-6]),
    "one moving link": spec([0.3], [0.15], [4.0]),
    "one moving link, d = r": spec([0.3], [0.3], [4.0]),
    "one moving link, d = 1e-300 m (on the base joint to the last digit)": spec([0.3], [1e-300], [4.0]),
    "d = 1e-300 m on the end link": spec(R, [0.15, 0.12, 1e-300], M),
    "two moving links": spec([0.3, 0.2], [0.15, 0.1], [4.0, 2.8]),
    "two moving links, d = 0 on the end link": spec([0.3, 0.2], [0.15, 0.0], [4.0, 2.8]),
    "millimetres and grams": spec([0.003, 0.0024, 0.002], [0.0015, 0.0012, 0.001], [0.004, 0.0032, 0.0028]),
    "metres and tonnes": spec([3.0, 2.4, 2.0], [1.5, 1.2, 1.0], [4000.0, 3200.0, 2800.0]),
    "a payload on an end link with d = 0": spec(R, [0.15, 0.12, 0.0], M, payload=5.0),
}


def route1_residual(chain, springs) -> float:
    """Largest off-diagonal entry of M = G + sum K_S (000 Eqs. 39), over the arm's energy scale
    g (sum m) (sum r) (J), which bounds every G_1,j."""
    scale = chain.g * sum(chain.m) * sum(chain.r)
    return float(np.abs(quadratic.balance_residual(chain, springs)).max()) / scale


@pytest.mark.parametrize("name", list(ARMS))
def test_a_degenerate_arm_designs_and_balances_by_both_routes(name):
    arm = ARMS[name]
    report = design_arm(arm, max_designs=1, restarts=4, minimise_force=False)
    assert report.designs, (name, report.stopped, report.rejected[:3])
    best = report.designs[0]
    chain = arm.chain()
    X = workspace_poses(arm, chain)
    assert verify(chain, best.springs, X) < VERIFY_TOLERANCE  # route 2
    assert route1_residual(chain, best.springs) < 1e-10  # route 1
    assert np.isfinite(best.max_force) and np.isfinite(best.efficiency) and 0 < best.efficiency <= 1
    # negative control: the same springs 10 % too soft leave the arm unbalanced (route 2 sees it)
    if best.springs:
        soft = [s.scaled(0.9) for s in best.springs]
        E = geometry.energies(chain, soft, X)
        assert np.ptp(E["total"]) / np.ptp(E["gravity"]) > 1e-3


def test_the_end_link_with_d_zero_gets_no_spring_and_is_said_so():
    arm = ARMS["d = 0 on the end link"]
    report = design_arm(arm, max_designs=3, restarts=4)
    assert report.designs and all(s.j < arm.n for d in report.designs for s in d.springs)
    assert any("d_4 = 0" in note for note in report.notes)
    # the old verdict's cause: a spring S(1,4) would offset G_1,4 = 0; no rejection claims a proof for the arm
    assert not any("no configuration" in why for _, why in report.rejected)


def test_design_for_designs_the_end_link_with_d_zero():
    chain = ARMS["d = 0 on the end link"].chain()
    configuration, springs = design_for(chain, restarts=4)
    assert configuration and all(s.j < chain.n for s in springs)
    assert route1_residual(chain, springs) < 1e-10


def test_a_one_link_arm_with_its_centre_of_mass_on_the_base_joint_needs_no_spring():
    arm = spec([0.3], [0.0], [4.0])
    assert balanced_core(arm.chain()) is None
    report = design_arm(arm)
    assert len(report.designs) == 1 and report.designs[0].springs == ()
    assert report.designs[0].label() == "no springs" and "without springs" in report.stopped
    assert design_for(arm.chain()) == ((), ())
    # and a spring added to it unbalances it: route 2 (absolute scale, the gravity energy is constant)
    with pytest.raises(ValueError, match="not balanced"):
        verify(arm.chain(), [Spring(1, 2, 0.1, 0.1, 100.0)], workspace_poses(arm, arm.chain()))


def test_the_core_keeps_the_gravity_entries():
    chain = ARMS["d = 0 on the end link"].chain()
    core = balanced_core(chain)
    full = quadratic.gravity_entries(chain.r, chain.d, chain.m, chain.g)
    reduced = quadratic.gravity_entries(core.r, core.d, core.m, core.g)
    assert core.n == chain.n - 1 and full[(1, chain.n)] == 0.0
    assert all(np.isclose(reduced[key], full[key], rtol=1e-14) for key in reduced)
    other = ARMS["d = r on the end link"].chain()
    assert balanced_core(other) is other


def test_the_minimal_search_does_not_ask_for_a_spring_on_an_idle_end_link():
    from springlab.design.feasibility import minimal_balanceable

    chain = ARMS["d = 0 on the end link"].chain()
    search = minimal_balanceable(chain)
    assert search.complete
    found = [" ".join(map(str, cfg)) for cfg in search.multisets]
    assert "S(1,3)(+,+) S(2,3)(+,+)" in found  # G_1,4 = 0 needs no S(1,4)
    assert not any("S(1,4)" in cfg for cfg in found[:2])
