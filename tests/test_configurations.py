"""Rules R1-R6, the enumerator, and the plain criterion."""

import itertools

import pytest

from springlab import serial_chain
from springlab.design import rules as cfgs
from springlab.design import solve as design
from springlab.papers import juang2023 as paper


def names(violations):
    return {v.rule for v in violations}


def test_the_papers_example_is_admissible():
    assert cfgs.is_admissible(4, paper.EXAMPLE_CONFIGURATION)


@pytest.mark.parametrize("config, rule", [
    (["S(1,2)", "S(1,3)", "S(2,3)"], "R1"),
    (["S(1,4)", "S(2,4)", "S(3,4)(-,-)"], "R2"),
    (["S(1,2)", "S(1,4)", "S(3,4)(-,-)"], "R3"),
    (["S(1,2)", "S(1,4)", "S(2,4)(-,-)"], "R4"),
    (["S(1,2)", "S(1,4)", "S(2,4)"], "R5"),
    (["S(1,2)", "S(1,4)(-,-)", "S(2,4)", "S(3,4)(-,-)"], "000 Eq. (41)"),
    (["S(1,2)", "S(1,4)", "S(2,4)(-,+)", "S(3,4)(-,-)"], "Fig. 10"),
])
def test_rules_reject_with_the_rule_named(config, rule):
    assert rule in names(cfgs.rule_violations(4, config))


def test_r6_on_five_links():
    # S(1,5) leaves component (3,4) positive; only R6's springs may offset it
    config = ["S(1,2)", "S(1,4)", "S(1,5)", "S(2,3)", "S(2,5)(-,-)", "S(2,4)(+,+)", "S(4,5)(-,-)"]
    assert "R6" in names(cfgs.rule_violations(5, config))


def test_enumerator_contains_table_1():
    for n in (3, 4):
        assert set(paper.table1_configurations(n)) <= set(cfgs.enumerate_configurations(n))
    assert len(cfgs.enumerate_configurations(3)) == 2
    assert len(cfgs.enumerate_configurations(4)) == 21


def test_every_enumerated_configuration_has_necessary_springs_only():
    for cfg in cfgs.enumerate_configurations(4):
        assert cfgs.is_admissible(4, cfg)
        for s in cfg:
            assert not cfgs.is_admissible(4, set(cfg) - {s})


def test_enumerator_agrees_with_the_plain_criterion_for_four_links(arm):
    for cfg in cfgs.enumerate_configurations(4):
        result = design.feasibility(arm, cfg)
        assert result.status == "feasible", cfg


def test_rules_agree_with_the_plain_criterion_on_small_configurations():
    chain = serial_chain([0.3, 0.24], [0.15, 0.12], [4.0, 3.2], g=9.8)
    for size in (1, 2, 3):
        for cfg in itertools.combinations(design.candidate_slots(3), size):
            status = design.feasibility(chain, cfg, restarts=4).status
            assert (status == "feasible") == cfgs.is_admissible(3, cfg), cfg
            assert status != "unknown"


def test_rules_are_not_sufficient_on_five_links():
    # admitted by R1-R6, yet Eqs. (39b) at (3,5) and (4,5) force a_S(3,5) = -r_3 < 0
    chain = serial_chain([0.30, 0.24, 0.20, 0.16], [0.15, 0.12, 0.10, 0.08], [4.0, 3.2, 2.8, 2.0])
    cfg = [cfgs.slot(s) for s in
           ["S(1,2)", "S(1,4)", "S(1,5)", "S(2,3)", "S(2,5)(+,+)", "S(2,5)(-,-)", "S(3,5)(+,-)"]]
    assert cfgs.is_admissible(5, cfg)
    assert design.relaxation_margin(chain, cfg) <= 1e-9
    assert design.feasibility(chain, cfg).status == "infeasible"


def test_grouping_writes_the_papers_alternatives():
    groups = cfgs.group_alternatives(cfgs.enumerate_configurations(3))
    assert groups == [{(1, 3): frozenset({("(+,+)",)}), (2, 3): frozenset({("(+,+)",), ("(-,-)",)})}]
    assert "1(+,+)/1(-,-)" in cfgs.format_group(groups[0], 3)


def test_the_sign_refutation_never_refutes_what_the_relaxation_admits():
    from springlab.design.ground import example_family
    from springlab.design.screen import any_sign_candidates

    chain = example_family([4])[4].chain()
    candidates = any_sign_candidates(4, 3)  # 462 sets of three springs, any pattern, with S(1,4)
    signs = design.sign_consistent(chain, candidates)
    relaxed = [design.relaxation_margin(chain, cfg) > 1e-9 for cfg in candidates]
    assert all(ok for ok, lp in zip(signs, relaxed, strict=True) if lp)  # a refutation is a proof
    assert 0 < sum(relaxed) < sum(signs) < len(candidates)  # it decides some, leaves the rest to the programme
    # negative controls: an entry with only same-signed terms, and one missing its negative term
    assert not design.sign_consistent(chain, [["S(1,2)", "S(1,3)", "S(1,4)", "S(2,4)(+,-)"]])[0]
    assert not design.sign_consistent(chain, [["S(1,2)", "S(1,3)"]])[0]
    ground = ["S(1,3)(+,-)", "S(1,4)(+,+)", "S(1,4)(+,-)"]  # rank.ground_springs(4): balances every arm
    assert design.sign_consistent(chain, [ground, []]).tolist() == [True, False]


def test_the_bitmask_checks_agree_with_the_rules_word_for_word():
    import random

    from springlab.design.rules import _bits

    rng = random.Random(5)
    for n in (3, 4, 5):
        bits = _bits(n)
        for _ in range(2000):
            cfg = rng.sample(bits.slots, rng.randint(1, 2 * n))
            mask = bits.mask(bits.bit[s] for s in cfg)
            assert bits.admissible(mask) == (not cfgs.rule_violations(n, cfg)), cfg
        assert any(bits.admissible(m) for m in (bits.mask(bits.bit[s] for s in c) for c in cfgs.enumerate_configurations(n)))
