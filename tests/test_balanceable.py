"""The rules against physics: which spring multisets balance an arm (000 Eqs. 39)."""

import numpy as np
import pytest

from springlab.design import feasibility as bal
from springlab.design import rulecheck
from springlab.design.rules import enumerate_configurations, slot
from springlab.energy import geometry
from springlab.model.chain import random_directions
from springlab.papers import juang2023 as paper


def test_n4_rules_are_exactly_the_minimal_balanceable_multisets():
    arm = bal.random_arm(4, 3)
    search = bal.minimal_balanceable(arm)
    assert search.complete and search.nodes > len(search.minimal)
    assert sorted(map(bal.multiset_label, search.multisets)) == sorted(map(bal.multiset_label, enumerate_configurations(4)))
    for cfg, springs in search.minimal:  # each with its design, balanced by direct geometry
        assert [(s.i, s.j, s.pattern) for s in springs] == [(s.i, s.j, s.pattern) for s in cfg]
        assert bal.balances_by_geometry(arm, springs) <= bal.ROUTE_TWO_TOLERANCE
    assert all(cert.check(arm) for cert in search.refuted.values())  # every refutation, exactly


def test_the_full_sign_alphabet_needs_fewer_springs():
    # every pattern on every pair: n = 4 balances with three springs (the paper's alphabet needs four)
    arm = bal.random_arm(4, 3)
    full = bal.minimal_balanceable(arm, signs="all")
    assert full.complete and min(full.sizes()) == 3 and min(bal.minimal_balanceable(arm).sizes()) == 4
    for _, springs in full.minimal[:5]:
        assert bal.balances_by_geometry(arm, springs) <= bal.ROUTE_TWO_TOLERANCE
    assert len(bal.alphabet(4, "all")) == 4 * 6 + 4  # four patterns on six pairs, S(1,4) twice


def test_a_search_that_cannot_finish_says_so():
    with pytest.raises(bal.SearchExhaustedError, match="max_nodes = 5"):
        bal.minimal_balanceable(bal.random_arm(4, 3), max_nodes=5)


def test_a_confirmed_design_balances_by_direct_geometry():
    arm = paper.example_arm()
    springs = bal.confirm(arm, [slot(s) for s in ("S(1,2)", "S(1,4)", "S(2,4)", "S(3,4)(-,-)")])
    assert springs is not None
    X = random_directions(arm.n, 500, np.random.default_rng(0))
    assert np.ptp(geometry.total_energy(arm, springs, X)) < 1e-9 * np.ptp(geometry.gravity_energy(arm, X))
    spoiled = [s.scaled(0.9) for s in springs]  # negative control
    assert np.ptp(geometry.total_energy(arm, spoiled, X)) > 1e-2 * np.ptp(geometry.gravity_energy(arm, X))


@pytest.mark.parametrize("config", [["S(1,4)"], ["S(1,2)", "S(1,4)", "S(3,4)(-,-)"], ["S(1,3)", "S(2,3)(+,-)"]])
def test_unbalanceable_multisets_are_refused(config):
    n = max(slot(s).j for s in config)
    assert bal.is_balanceable(bal.random_arm(n, 1), [slot(s) for s in config]) == "no"


def test_the_alphabet_and_bad_n():
    assert len(bal.alphabet(3)) == 2 + 1 + 3  # S(1,2) two ways, S(1,3), S(2,3) three ways
    assert bal.alphabet(4).count(slot("S(1,4)")) == 2  # spans three joints: twice
    with pytest.raises(ValueError, match="n must be an integer >= 2"):
        bal.alphabet(1)


def test_the_coupling_refutes_what_the_relaxation_allows():
    # (2,3) and (2,4) force b_S(1,4) = r_4, so P k = A B gives P_14 = r_4 A_14; row 1 then needs
    # G_14 / r_4 = G_13 / r_3, false for a generic arm
    arm = bal.random_arm(5, 1)
    config = [slot(s) for s in "S(1,2) S(1,4) S(1,5) S(2,5)(+,+) S(2,5)(+,-) S(3,4)(+,+)".split()]
    assert bal.relaxation_feasible(arm, config)
    decision = bal.decide(arm, config)
    assert decision.verdict == "no" and decision.evidence == "coupling (degree 2)"
    assert decision.certificate.check(arm) and 1 in decision.certificate.couplings  # S(1,4)'s coupling is used
    example = bal.decide(paper.example_arm(), paper.EXAMPLE_CONFIGURATION)  # it balances
    assert example.verdict == "yes" and example.evidence == "design"


def test_the_warm_started_phase_one_gives_the_fresh_solves_value():
    from springlab.design.programme import (
        Programme,
        WarmPhaseOne,
        new_highs,
        phase_one_lp,
        programme,
    )

    def fresh_solve(prog):  # the same programme passed to a new model and solved from scratch
        highs = new_highs()
        highs.passModel(phase_one_lp(prog))
        highs.run()
        return highs.getInfo().objective_function_value

    chain = bal.random_arm(5, np.random.default_rng(3))
    prog = programme(chain, [slot(s) for s in ("S(1,2)", "S(1,5)", "S(2,5)(+,-)", "S(2,5)(-,-)", "S(1,4)")])
    cols = len(prog.signs)
    row = np.zeros((1, cols))
    row[0, 0] = 1.0  # one extra row x_0 - c x_3 = 0, c varied
    row[0, 3] = -1.0
    base = Programme(prog.items, prog.owner, prog.signs, np.vstack([prog.A_eq, row]), np.append(prog.b_eq, 0.0))
    warm = WarmPhaseOne(base, [(prog.A_eq.shape[0], 3)])
    values = []
    for c in np.random.default_rng(0).uniform(-3.0, 3.0, 40):
        A = base.A_eq.copy()
        A[-1, 3] = c
        fresh = fresh_solve(Programme(base.items, base.owner, base.signs, A, base.b_eq))
        values.append(fresh)
        assert abs(warm([c]) - fresh) <= 1e-9 * max(1.0, fresh)
    assert max(values) > 1e-3 and min(values) < max(values)  # the coefficient matters


FORMERLY_UNDECIDED = ["S(1,2)(+,+) S(1,4) S(1,5) S(2,4)(-,-) S(2,5)(+,+) S(2,5)(+,-)",
                      "S(1,2)(-,-) S(1,4) S(1,5) S(2,4)(-,-) S(2,5)(+,+) S(3,5)(-,-)"]


@pytest.mark.parametrize("config", FORMERLY_UNDECIDED)
def test_the_degree_2_certificate_refutes_what_the_relaxation_cannot(config):
    # entry (2,4) with (2,3) needs b_S(1,4) above r_4; entries (1,3), (1,4) keep P/A = b below it:
    # multiplied by A, B and k of S(1,4) and added to its coupling, the equations give a sum > 0
    config = [slot(s) for s in config.split()]
    for seed in range(3):
        arm = bal.random_arm(5, seed)
        assert bal.relaxation_feasible(arm, config)
        cert = bal.decide(arm, config).certificate
        assert cert is not None and cert.kind == "coupling (degree 2)" and cert.check(arm)
        assert set(cert.couplings) == {1}  # S(1,4)'s P k = A B


BALANCEABLE_N5 = ["S(1,3) S(1,5) S(2,4)(+,+) S(2,4)(-,-) S(2,5)(-,-)",
                  "S(1,2)(+,+) S(1,4) S(1,5) S(2,4)(+,-) S(2,5)(+,+) S(2,5)(+,-)",
                  "S(1,3) S(1,4) S(1,5) S(2,5)(+,-) S(2,5)(-,-) S(3,4)(+,+)",
                  "S(1,2)(-,-) S(1,4) S(1,5) S(2,3)(-,-) S(2,4)(-,-) S(2,5)(-,-)"]


@pytest.mark.parametrize("config", BALANCEABLE_N5)
def test_a_balanceable_multiset_gets_a_design_and_no_certificate(config):
    from springlab.design.certificates import coupling_certificate, relaxation_certificate

    arm = bal.random_arm(5, 0)
    config = [slot(s) for s in config.split()]
    decision = bal.decide(arm, config)
    assert decision.verdict == "yes" and bal.balances_by_geometry(arm, decision.springs) <= bal.ROUTE_TWO_TOLERANCE
    assert relaxation_certificate(arm, config) is None and coupling_certificate(arm, config) is None


def test_no_certificate_for_the_papers_example():
    from springlab.design.certificates import coupling_certificate

    assert coupling_certificate(paper.example_arm(), paper.EXAMPLE_CONFIGURATION) is None


def test_the_warm_relaxation_agrees_with_the_exact_certificates():
    """The enumeration's warm-started relaxation says infeasible exactly where an exact relaxation
    certificate exists, on random multisets and on balanceable ones with a spring added."""
    from springlab.design.certificates import relaxation_certificate
    from springlab.design.programme import Relaxation

    arm = bal.random_arm(5, 2)
    kinds = sorted(set(bal.alphabet(5)))
    warm = Relaxation(arm, kinds)
    rng = np.random.default_rng(0)
    verdicts = []
    balanced = [np.array([[slot(x) for x in c.split()].count(k) for k in kinds]) for c in BALANCEABLE_N5]
    for t in range(30):
        counts = rng.integers(0, 3, len(kinds)) * (rng.random(len(kinds)) < 0.25)
        if t % 3 == 0:
            counts = balanced[t % len(balanced)] + (np.arange(len(kinds)) == rng.integers(len(kinds)))
        if not counts.any():
            continue
        cfg = [k for k, c in zip(kinds, counts, strict=True) for _ in range(c)]
        feasible = warm(counts)[0]
        verdicts.append(feasible)
        assert feasible == (relaxation_certificate(arm, cfg) is None)
    assert any(verdicts) and not all(verdicts)  # both met


def test_highs_prints_no_banner():
    """HiGHS prints a banner when a process makes its first model; springlab's models are made
    silently, so a notebook's output shows only what springlab says (the control: highspy itself prints)."""
    import subprocess
    import sys

    quiet = subprocess.run([sys.executable, "-c", "from springlab.design import highs; highs.new_model(); "
                            "highs.new_model(); print('done')"], capture_output=True, text=True, check=True)
    assert quiet.stdout == "done\n"
    loud = subprocess.run([sys.executable, "-c", "import highspy; highspy.Highs()"], capture_output=True, text=True, check=True)
    assert "HiGHS" in loud.stdout


def test_the_fewest_springs_are_proved():
    f = rulecheck.fewest_springs(4, seed=1)
    assert f.springs == 4 == f.rules_fewest == len(f.configuration) and f.search.complete and not f.search.minimal
    assert f.route_two <= bal.ROUTE_TWO_TOLERANCE and f.search.refuted
    assert all(c.check(f.search.arm) for c in f.search.refuted.values())  # every multiset of <= 3 springs met
    assert max(len(c.slots) for c in f.search.refuted.values()) == 3


def test_a_size_limit_keeps_the_search_complete_below_it():
    arm = bal.random_arm(4, 3)
    full = bal.minimal_balanceable(arm, signs="all")
    limited = bal.minimal_balanceable(arm, signs="all", most_springs=4)
    assert sorted(map(bal.multiset_label, limited.multisets)) == sorted(bal.multiset_label(c) for c in full.multisets if len(c) <= 4)
    assert limited.complete and limited.nodes < full.nodes


LIMIT = ((1, 2, "(+,+)"), (1, 4, "(+,+)"), (1, 5, "(+,+)"), (2, 5, "(+,+)"), (2, 5, "(-,-)"), (3, 5, "(+,+)"),
         (3, 5, "(-,-)"))
"""Seven springs on the 000 chapter's n = 5 arm (seed 2023) that balance it only in a limit: an exact degree-2
certificate refutes them, while a search step reaches S(1,4) with a 3e18 m lever and a 3e-17 N/m rate."""


@pytest.mark.parametrize("coretype", [None, "Haswell"])
def test_a_limit_is_no_design_whatever_the_blas_kernels(coretype):
    import os
    import subprocess
    import sys

    code = ("import numpy as np; from springlab.design import feasibility as bal; from springlab.design.rules import "
            f"SpringSlot; arm = bal.random_arm(5, np.random.default_rng(2023)); d = bal.decide(arm, [SpringSlot(*s) for s in "
            f"{LIMIT!r}]); print(d.verdict, d.evidence, d.certificate.check(arm) if d.certificate else None); "
            f"d = bal.decide(arm, [SpringSlot(*s) for s in {LIMIT[1:]!r}]); print(d.verdict)")
    env = dict(os.environ) | ({"OPENBLAS_CORETYPE": coretype} if coretype else {})
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True).stdout
    # on AVX-512 kernels the search once returned the limit as a design ('yes'), on Haswell's the certificate
    assert out.split("\n")[0] == "no coupling (degree 2) True"
    assert out.split("\n")[1] == "no"  # a sub-multiset: refuted too (it would make the seven not minimal)
