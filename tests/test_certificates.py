"""Exact certificates that a spring multiset cannot balance (springlab.design.certificates): a
refutation checks in rational arithmetic; one multiplier changed, the check fails (a negative
control); a spring taken out of paper 000's Table 3 design is refuted; a multiset that balances
gets no certificate; the degree-2 kind proves what the relaxation cannot; the springs that could
break a certificate are exactly those whose addition leaves it no proof."""

from fractions import Fraction

import numpy as np
import pytest

from springlab.design.certificates import (
    Certificate,
    SignedSystem,
    coupling_certificate,
    exact_system,
    relaxation_certificate,
)
from springlab.design.feasibility import alphabet, decide, random_arm, relaxation_feasible
from springlab.design.rules import enumerate_configurations, slot
from springlab.energy.quadratic import gravity_entries
from springlab.papers import juang2023 as paper

TABLE_3 = [slot(x) for x in ("S(1,2)(+,+)", "S(1,4)(+,+)", "S(2,4)(+,+)", "S(3,4)(-,-)")]
COUPLED = [slot(x) for x in "S(1,2) S(1,4) S(1,5) S(2,5)(+,+) S(2,5)(+,-) S(3,4)(+,+)".split()]


def test_the_exact_system_is_the_arms_own_numbers():
    arm = paper.example_arm()
    columns, entries, gravity = exact_system(arm, TABLE_3)
    assert len(entries) == 6 and all(isinstance(v, Fraction) for v in gravity.values())
    floats = gravity_entries(arm.r, arm.d, arm.m, arm.g)
    assert all(abs(float(gravity[key]) - floats[key]) <= 1e-12 * abs(floats[key]) for key in floats)
    assert {(idx, name) for idx, name, _, _ in columns} == {(0, "P"), (1, "P"), (1, "A"), (1, "B"), (1, "k"),
                                                            (2, "P"), (2, "A"), (2, "B"), (3, "P")}


def test_a_multiset_taken_from_a_larger_system_is_the_same_system():
    arm = random_arm(5, np.random.default_rng(4))
    kinds = sorted(set(alphabet(5)))
    picks = [0, 3, 3, 7, 11]
    part = SignedSystem(arm, kinds).multiset(picks)
    whole = SignedSystem(arm, [kinds[k] for k in picks])
    assert part.slots == whole.slots and part.variables == whole.variables and part.rows == whole.rows
    assert np.array_equal(part.E, whole.E)


@pytest.mark.parametrize("removed", range(4))
def test_a_spring_taken_out_of_table_3_is_refuted_exactly(removed):
    arm = paper.example_arm()
    assert relaxation_certificate(arm, TABLE_3) is None  # it balances: no certificate can exist
    assert coupling_certificate(arm, TABLE_3) is None
    less = TABLE_3[:removed] + TABLE_3[removed + 1:]
    cert = relaxation_certificate(arm, less)
    assert cert is not None and cert.check(arm) and cert.kind == "relaxation" and not relaxation_feasible(arm, less)
    assert "relaxation" in cert.describe(arm)


def test_a_changed_multiplier_fails_the_check():
    arm = paper.example_arm()
    cert = relaxation_certificate(arm, TABLE_3[:3])
    key, value = next(iter(cert.equations.items()))
    assert not Certificate(cert.slots, {**cert.equations, key: -value}, {}).check(arm)
    assert not Certificate(cert.slots, {k: -v for k, v in cert.equations.items()}, {}).check(arm)
    assert not Certificate(cert.slots, {key: 0.5}, {}).check(arm)  # a float is not a proof
    assert not Certificate(cert.slots, {}, {}).check(arm)  # nothing proves nothing
    assert not Certificate(cert.slots, {((9, 9), None): Fraction(1)}, {}).check(arm)  # no such entry


def test_the_degree_2_certificate_proves_what_the_relaxation_cannot():
    arm = random_arm(5, 1)
    assert relaxation_certificate(arm, COUPLED) is None
    cert = coupling_certificate(arm, COUPLED)
    assert cert is not None and cert.kind == "coupling (degree 2)" and cert.check(arm)
    assert "coupling" in cert.describe(arm)
    # negative controls: without its coupling multiplier, with it negated, or one multiplier nudged
    assert not Certificate(cert.slots, cert.equations, {}).check(arm)
    assert not Certificate(cert.slots, cert.equations, {k: -v for k, v in cert.couplings.items()}).check(arm)
    key, value = next(iter(cert.equations.items()))
    assert not Certificate(cert.slots, {**cert.equations, key: value * Fraction(101, 100)}, cert.couplings).check(arm)
    # a coupling on a spring too short to have one is not allowed
    assert not Certificate(cert.slots, cert.equations, {**cert.couplings, 0: Fraction(1)}).check(arm)


def test_a_spring_that_breaks_nothing_keeps_the_proof_and_a_breaker_ends_it():
    """breakers() says which added springs could break a certificate: for every other spring the
    same multipliers still prove the larger multiset; for at least one breaker they do not."""
    arm = random_arm(5, 1)
    kinds = sorted(set(alphabet(5)))
    for slots in (COUPLED, TABLE_3[:3] + [slot("S(1,5)")]):
        cert = decide(arm, slots).certificate
        broken = set(cert.breakers(SignedSystem(arm, kinds)))
        assert broken and len(broken) < len(kinds)
        for k, kind in enumerate(kinds):
            larger = Certificate(tuple(slots) + (kind,), cert.equations, cert.couplings)
            if k not in broken:
                assert larger.check(arm)
        assert any(not Certificate(tuple(slots) + (kinds[k],), cert.equations, cert.couplings).check(arm)
                   for k in broken)


def test_every_refutation_of_the_rules_configurations_at_n_5_is_certified():
    arm = random_arm(5, np.random.default_rng(7))
    refuted = [cfg for cfg in enumerate_configurations(5) if not relaxation_feasible(arm, cfg)]
    assert len(refuted) > 10
    assert all((c := relaxation_certificate(arm, cfg)) is not None and c.check(arm) for cfg in refuted)
