"""Exact certificates that a spring multiset cannot balance (springlab.design.certificates): a
refutation checks in rational arithmetic; one multiplier changed, the check fails (a negative
control); a spring taken out of paper 000's Table 3 design is refuted; a multiset that balances
gets no certificate; every R1-R6 configuration the linear relaxation refutes at n = 5 gets one."""

from fractions import Fraction

import numpy as np
import pytest

from springlab.design.certificates import Certificate, exact_system, relaxation_certificate
from springlab.design.feasibility import random_arm, relaxation_feasible
from springlab.design.rules import enumerate_configurations, slot
from springlab.energy.quadratic import gravity_entries
from springlab.papers import juang2023 as paper

TABLE_3 = [slot(x) for x in ("S(1,2)(+,+)", "S(1,4)(+,+)", "S(2,4)(+,+)", "S(3,4)(-,-)")]


def test_the_exact_system_is_the_arms_own_numbers():
    arm = paper.example_arm()
    columns, entries, gravity = exact_system(arm, TABLE_3)
    assert len(entries) == 6 and all(isinstance(v, Fraction) for v in gravity.values())
    floats = gravity_entries(arm.r, arm.d, arm.m, arm.g)
    assert all(abs(float(gravity[key]) - floats[key]) <= 1e-12 * abs(floats[key]) for key in floats)
    assert {(idx, name) for idx, name, _, _ in columns} == {(0, "P"), (1, "P"), (1, "A"), (1, "B"), (1, "k"),
                                                            (2, "P"), (2, "A"), (2, "B"), (3, "P")}


@pytest.mark.parametrize("removed", range(4))
def test_a_spring_taken_out_of_table_3_is_refuted_exactly(removed):
    arm = paper.example_arm()
    assert relaxation_certificate(arm, TABLE_3) is None  # it balances: no certificate can exist
    less = TABLE_3[:removed] + TABLE_3[removed + 1:]
    cert = relaxation_certificate(arm, less)
    assert cert is not None and cert.check(arm) and not relaxation_feasible(arm, less)
    assert "relaxation (Stiemke)" in cert.describe(arm)


def test_a_changed_multiplier_fails_the_check():
    arm = paper.example_arm()
    cert = relaxation_certificate(arm, TABLE_3[:3])
    key, value = next(iter(cert.multipliers.items()))
    assert not Certificate(cert.slots, cert.kind, {**cert.multipliers, key: -value}).check(arm)
    assert not Certificate(cert.slots, cert.kind, {k: -v for k, v in cert.multipliers.items()}).check(arm)
    assert not Certificate(cert.slots, cert.kind, {key: 0.5}).check(arm)  # a float is not a proof
    assert not Certificate(cert.slots, cert.kind, {}).check(arm)  # nothing proves nothing


def test_every_relaxation_refutation_of_the_rules_configurations_at_n_5_is_certified():
    arm = random_arm(5, np.random.default_rng(7))
    refuted = [cfg for cfg in enumerate_configurations(5) if not relaxation_feasible(arm, cfg)]
    assert len(refuted) > 10
    assert all((c := relaxation_certificate(arm, cfg)) is not None and c.check(arm) for cfg in refuted)
