"""Paper 000's rules R1-R6 against physics (:func:`rules_against_physics`): per number of links, the
configurations the rules admit beside every inclusion-minimal balanceable multiset of springs that
000 Eqs. (39) allow (:func:`springlab.design.feasibility.minimal_balanceable`), on several random arms;
and the fewest springs that balance an arm, proved (:func:`fewest_springs`: a design, and every
multiset of fewer springs refuted).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import itertools
import time
from collections import Counter
from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.design.feasibility import (
    ROUTE_TWO_TOLERANCE,
    Decision,
    MinimalSearch,
    balances_by_geometry,
    decide,
    minimal_balanceable,
    multiset_label,
    random_arm,
)
from springlab.design.programme import design_searches
from springlab.design.rules import (
    SpringSlot,
    best_first_configurations,
    enumerate_configurations,
    rule_violations,
)
from springlab.errors import SearchExhaustedError, SpringlabError
from springlab.model.chain import Chain
from springlab.tables import Table


def _first_rule(violations) -> str:
    """The rule a rejected multiset breaks first, in the paper's order (criteria before rules)."""
    return str(violations[0]).split(":")[0] if violations else ""


@dataclass
class RulesAgainstPhysics:
    """Per n: the rules' configurations against the inclusion-minimal balanceable multisets (first arm)."""

    n: int
    arms: int
    search: MinimalSearch  # the complete enumeration on the first arm
    admitted: list[tuple[SpringSlot, ...]]  # R1-R6's configurations with necessary springs
    decisions: dict[str, Decision]  # per admitted configuration
    admitted_single_minimal: int  # admitted, balanceable, no single spring removable
    admitted_inclusion_minimal: int  # admitted and inclusion-minimal balanceable
    rejected: dict[str, list[str]]  # minimal balanceable but rejected: label -> violations
    unlisted: dict[str, list[str]]  # minimal balanceable, admissible, not listed: label -> springs the rules call unnecessary
    same_on_every_arm: bool
    full: MinimalSearch | None = None  # the enumeration over every sign pattern (where run)

    @property
    def arm(self) -> Chain:
        """The first arm, on which everything above was decided."""
        return self.search.arm

    @property
    def minimal(self) -> list[tuple[SpringSlot, ...]]:
        return self.search.multisets

    @property
    def exact(self) -> bool:
        """True when the minimal list is complete (nothing undecided)."""
        return self.search.complete and all(d.verdict != "undecided" for d in self.decisions.values())

    @property
    def admitted_status(self) -> dict[str, str]:
        return {label: d.verdict for label, d in self.decisions.items()}

    @property
    def certificates(self) -> dict:
        """Per admitted configuration proved unbalanceable: its exact certificate."""
        return {label: d.certificate for label, d in self.decisions.items() if d.verdict == "no"}

    def example(self, kind: str) -> tuple[str, object]:
        """A refutation of the given certificate kind to work through: (multiset label, certificate),
        an admitted configuration's where one has that kind, else the first of the search's."""
        for pool in (self.certificates, self.search.refuted):
            for label, cert in pool.items():
                if cert.kind == kind and len(cert.slots) > 1:
                    return label, cert
        raise SpringlabError(f"no refutation of kind {kind!r} at n = {self.n}")

    def unlisted_explained(self) -> int:
        """How many of the admissible-but-unlisted minimal multisets contain an admitted
        configuration that cannot balance (the rules call the extra spring unnecessary)."""
        bad = [Counter(label.split()) for label, d in self.decisions.items() if d.verdict == "no"]
        return sum(any(all(Counter(label.split())[k] >= v for k, v in b.items()) for b in bad) for label in self.unlisted)

    def rejected_by_rule(self) -> dict[str, int]:
        """{rule: how many minimal balanceable multisets it rejects first}."""
        return dict(sorted(Counter(_first_rule(v) for v in self.rejected.values()).items()))

    def row(self) -> dict[str, int | str]:
        """The counts for this n, on the paper's alphabet (exact where nothing is undecided)."""
        no = [d for d in self.decisions.values() if d.verdict == "no"]
        und = sum(d.verdict == "undecided" for d in self.decisions.values())
        count = str(len(self.minimal)) if self.search.complete else f">= {len(self.minimal)}"
        by_rule = self.rejected_by_rule()
        twice = by_rule.pop("duplicate", 0)
        kinds = ", ".join(f"{k}" for k in sorted(Counter(d.certificate.kind for d in no)))
        return {"n": self.n,
                "minimal balanceable": count,
                "their sizes (springs: how many)": ", ".join(f"{k}: {v}" for k, v in self.search.sizes().items()),
                "R1-R6's configurations": len(self.admitted),
                "of them minimal balanceable": self.admitted_inclusion_minimal,
                "of them balanceable, no spring removable": self.admitted_single_minimal,
                "of them unbalanceable": f"{len(no)} ({kinds})" if no else "0",
                "minimal, a rule rejects them": ", ".join(f"{k}: {v}" for k, v in by_rule.items()) or "0",
                "minimal, one spring twice (never listed)": twice,
                "minimal, admitted, not listed": len(self.unlisted),
                "undecided": len(self.search.undecided) + und,
                "arms that agree": self.arms if self.same_on_every_arm else "no"}


def rules_against_physics(n: int, *, arms: int = 3, seed: int = 0, progress: bool = False,
                          full_signs: bool = False) -> RulesAgainstPhysics:
    """Test R1-R6 both ways on ``arms`` random n-link arms (:func:`~springlab.design.feasibility.random_arm`).

    On every arm the inclusion-minimal balanceable multisets over the paper's alphabet are
    enumerated (:func:`~springlab.design.feasibility.minimal_balanceable`); ``same_on_every_arm`` says the lists agree. On the
    first arm each of the rules' configurations (:func:`springlab.design.rules.enumerate_configurations`)
    is decided (:func:`~springlab.design.feasibility.decide`: a design or an exact certificate), with both minimality notions;
    the minimal multisets the rules reject are listed with the rules they break, and those the
    rules admit but do not list (they call a spring unnecessary that physics needs) with the
    springs the rules would drop. With
    ``full_signs`` the first arm is also enumerated over every sign pattern (``full``).
    """
    n = _checks.links(n, "n")
    arms = _checks.count("arms", arms, least=1)
    seed = _checks.count("seed", seed)
    from tqdm import tqdm

    rng = np.random.default_rng(seed)
    chains = [random_arm(n, rng) for _ in range(arms)]
    searches = [minimal_balanceable(c, progress=progress) for c in chains]
    first, search = chains[0], searches[0]
    minimal = {multiset_label(cfg) for cfg in search.multisets}
    designs = {multiset_label(cfg): springs for cfg, springs in search.minimal}
    decided: dict[str, Decision] = {}  # one decision per multiset: sub-multisets recur

    def decide_once(cfg) -> Decision:
        key = multiset_label(cfg)
        if key not in decided:
            decided[key] = Decision("yes") if key in minimal else decide(first, cfg)
        return decided[key]

    admitted = enumerate_configurations(n)
    decisions, single, inclusion = {}, 0, 0
    for cfg in tqdm(admitted, disable=not progress, desc=f"n = {n}, R1-R6 configurations", mininterval=2.0):
        d = decide_once(cfg)
        if d.verdict == "yes" and d.springs is None:  # minimal: its design is the search's
            d = Decision("yes", springs=designs[multiset_label(cfg)])
        decisions[multiset_label(cfg)] = d
        if d.verdict != "yes":
            continue
        if multiset_label(cfg) in minimal:  # inclusion-minimal (the search is complete), so no spring is removable
            inclusion += 1
            single += 1
        elif all(decide_once(cfg[:k] + cfg[k + 1:]).verdict == "no" for k in range(len(cfg))):
            single += 1
    rejected = {multiset_label(cfg): [str(x) for x in rule_violations(n, cfg)] for cfg in search.multisets
                if rule_violations(n, cfg)}
    listed = {multiset_label(cfg) for cfg in admitted}
    unlisted = {multiset_label(cfg): [str(cfg[k]) for k in range(len(cfg)) if not rule_violations(n, cfg[:k] + cfg[k + 1:])]
                for cfg in search.multisets if multiset_label(cfg) not in rejected and multiset_label(cfg) not in listed}
    same = all(sorted(map(multiset_label, s.multisets)) == sorted(minimal) for s in searches[1:])
    full = minimal_balanceable(first, signs="all", progress=progress) if full_signs else None
    return RulesAgainstPhysics(n, arms, search, admitted, decisions, single, inclusion, rejected, unlisted, same, full)


@dataclass
class Fewest:
    """The fewest springs that balance an n-link arm on a sign alphabet, proved.

    :ivar springs: the fewest
    :ivar configuration: a multiset of that many springs that balances, and ``design`` its springs
    :ivar search: the search complete up to one spring fewer (:func:`~springlab.design.feasibility.minimal_balanceable` with
        ``most_springs``): it refutes, each by an exact certificate, every multiset it meets
    :ivar rules_fewest: the fewest springs of a configuration R1-R6 admit that balances (None when none
        of the first :data:`RULES_TRIED` does)
    :ivar route_two: the design's total-energy variation over random poses, relative to gravity's
    :ivar seconds: wall time of the whole
    """

    n: int
    springs: int
    configuration: tuple
    design: tuple
    search: MinimalSearch
    rules_fewest: int
    route_two: float
    seconds: float

    def row(self) -> dict:
        return {"n": self.n, "fewest springs": self.springs,
                "R1-R6's fewest that balance": "none tried" if self.rules_fewest is None else self.rules_fewest,
                "a design": multiset_label(self.configuration),
                "its energy variation (route 2)": f"{self.route_two:.1e}",
                "fewer springs: multisets refuted": len(self.search.refuted),
                "by kind": ", ".join(f"{k}: {v}" for k, v in self.search.kinds().items())}


RULES_TRIED = 500
"""Most of the rules' configurations, fewest springs first, :func:`fewest_springs` decides for a
first design (an upper bound on the fewest springs)."""


def fewest_springs(n: int, *, seed: int = 0, signs: str = "paper", max_nodes: int = 2_000_000) -> Fewest:
    """The fewest springs that balance a random n-link arm (:func:`~springlab.design.feasibility.random_arm`), with a design and the
    proof that fewer cannot.

    A first design comes from the rules' configurations, fewest springs first (the first that
    balances, of at most :data:`RULES_TRIED`); then :func:`~springlab.design.feasibility.minimal_balanceable` searches every
    multiset of fewer springs (``most_springs``), refuting each it meets by an exact certificate: a
    balanceable multiset of fewer springs would contain a minimal one, which the search would find.
    If it finds one, the smallest it finds is the fewest.
    """

    n = _checks.links(n, "n")
    start = time.perf_counter()
    arm = random_arm(n, np.random.default_rng(_checks.count("seed", seed)))
    rules_fewest, upper = None, None
    configurations = list(itertools.islice(best_first_configurations(n), RULES_TRIED))
    for quick in (True, False):  # the central start's quick polish on each first, the whole decision after
        for count, _, cfg in configurations:
            found = next(design_searches(arm, cfg), None) if quick else decide(arm, cfg).springs
            if found is not None and balances_by_geometry(arm, found) <= ROUTE_TWO_TOLERANCE:
                rules_fewest, upper = count, (tuple(cfg), found)
                break
        if upper is not None:
            break
    limit = len(upper[0]) - 1 if upper else None
    search = minimal_balanceable(arm, signs=signs, max_nodes=max_nodes, fewest=True, most_springs=limit)
    if not search.complete:
        raise SearchExhaustedError(f"n = {n}: {len(search.undecided)} multisets undecided; the fewest springs are not proved")
    if search.minimal:
        upper = search.minimal[0]
    if upper is None:
        raise SearchExhaustedError(f"n = {n}: no balanceable multiset found")
    return Fewest(n, len(upper[0]), upper[0], upper[1], search, rules_fewest, balances_by_geometry(arm, upper[1]),
                  time.perf_counter() - start)


def counts_table(results) -> Table:
    """The per-n rows of :meth:`RulesAgainstPhysics.row` as one table (the paper's alphabet)."""
    rows = [r.row() for r in results]
    return Table(list(rows[0]), rows)


def signs_table(results) -> Table:
    """Per n where it was run, the minimal balanceable multisets over every sign pattern beside the
    paper's alphabet: how many, their sizes, the fewest springs."""
    rows = []
    for r in results:
        if r.full is None:
            continue
        s = r.full
        rows.append({"n": r.n, "paper's alphabet": len(r.minimal),
                     "every pattern": str(len(s.minimal)) if s.complete else f">= {len(s.minimal)}",
                     "their sizes (springs: how many)": ", ".join(f"{k}: {v}" for k, v in s.sizes().items()),
                     "fewest springs (paper's, every pattern)": f"{min(r.search.sizes())}, {min(s.sizes())}",
                     "undecided": len(s.undecided)})
    return Table(list(rows[0]), rows)
