"""Which spring multisets balance an arm: paper 000's rules R1-R6 tested against 000 Eqs. (39),
with every verdict proved.

A configuration is a **multiset** of springs over a sign alphabet (:func:`alphabet`). The paper's
(``signs="paper"``): ground springs S(1,j) (+,+), S(1,2) also (-,-); every other pair (+,+),
(-,-) or (+,-). Every pattern on every pair (``signs="all"``). Two springs may join one pair in
different patterns, and a pair spanning three or more joints (j - i >= 3) in the same pattern twice.

A multiset is **balanceable** when 000 Eqs. (39) have a solution with every k > 0 and every a, b of
its pattern's sign. :func:`decide` settles it either way:

* **yes**: a design (k, a, b per spring), found from the linear programme's centre and vertices by
  least squares on the couplings (:func:`confirm`), checked entry by entry (route 1) and by the total
  energy over random poses (route 2, :func:`balances_by_geometry`);
* **no**: an exact certificate (:mod:`springlab.design.certificates`): the linear relaxation's
  (Stiemke), or, where only the coupling P k = A B forbids it, a degree-2 one. Each is checked in
  rational arithmetic;
* **undecided** when neither is found (none is, on the arms and alphabets of the paper-000 chapter).

**Minimal**: a balanceable multiset none of whose proper sub-multisets is balanceable
(inclusion-minimal). :func:`minimal_balanceable` enumerates them all, fewest springs first, by
branching on certificates: a multiset proved unbalanceable is extended only by the springs that
could break its certificate (:meth:`springlab.design.certificates.Certificate.breakers`), which
every balanceable superset must contain. The enumeration is complete when no multiset it meets is
undecided.

The linear programme and the searches for a design live in :mod:`springlab.design.programme`; the rules
checked against these verdicts, and the fewest springs, in :mod:`springlab.design.rulecheck`.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import functools
import time
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from springlab import _checks
from springlab.design.certificates import (
    SignedSystem,
    coupling_certificate,
    relaxation_certificate,
    relaxation_certificate_from,
    sign_certificate,
)
from springlab.design.programme import Relaxation, design_searches
from springlab.design.rules import PATTERNS, SpringSlot, as_slots
from springlab.energy.geometry import gravity_energy, total_energy
from springlab.errors import SearchExhaustedError, SpringlabError
from springlab.model.chain import Chain, random_directions, serial_chain

SIGNS = ("paper", "all")
"""The sign alphabets: the paper's (000 Eq. 41 and Fig. 10) and every pattern on every pair."""


def alphabet(n: int, signs: str = "paper") -> list[SpringSlot]:
    """The springs a multiset may contain on an n-link arm, one entry per copy.

    ``signs="paper"``: ground springs S(1,j) (+,+) and S(1,2) (-,-) (000 Eq. 41 and the note below
    it); non-ground springs (+,+), (-,-), (+,-) (Fig. 10). ``signs="all"``: all four patterns on
    every pair. A spring spanning three or more joints appears twice in each pattern (its k enters
    entries of its own, so a second copy is not the same as a stiffer first one).
    """
    n = _checks.links(n, "n")
    if signs not in SIGNS:
        raise SpringlabError(f"signs must be one of {SIGNS}, got {signs!r}")

    out = []
    for i in range(1, n):
        for j in range(i + 1, n + 1):
            if signs == "all":
                patterns = PATTERNS
            elif i == 1:
                patterns = ("(+,+)", "(-,-)") if j == 2 else ("(+,+)",)
            else:
                patterns = ("(+,+)", "(-,-)", "(+,-)")
            for p in patterns:
                out += [SpringSlot(i, j, p)] * (2 if j - i >= 3 else 1)
    return out


def relaxation_feasible(chain: Chain, slots) -> bool:
    """True when the linear relaxation of 000 Eqs. (39) (P k = A B dropped) has a solution with
    every spring's quantities strictly of their signs; False is proved by the exact certificate
    :func:`springlab.design.certificates.relaxation_certificate`."""
    _checks.instance("chain", chain, Chain)

    slots = list(as_slots(slots))
    return bool(slots) and relaxation_certificate(chain, slots) is None


ROUTE_TWO_POSES = 64
"""Random poses on which a found design's total energy must be constant (route 2)."""
ROUTE_TWO_TOLERANCE = 1e-9
"""Largest variation of a found design's total energy over those poses, relative to gravity's (the
designs satisfy 000 Eqs. 39 to 1e-9 of the largest G_1,j; the energies' round-off is near 1e-15)."""


def balances_by_geometry(chain: Chain, springs, *, poses: int = ROUTE_TWO_POSES, seed: int = 0) -> float:
    """Route 2 on a found design: the variation of the total energy over ``poses`` random poses
    (every link in any direction, drawn from ``seed``), relative to the gravity energy's
    (dimensionless)."""
    _checks.instance("chain", chain, Chain)
    poses = _checks.count("poses", poses, least=2)
    seed = _checks.count("seed", seed)

    X = _random_poses(chain.n, poses, seed)
    return float(np.ptp(total_energy(chain, springs, X)) / np.ptp(gravity_energy(chain, X)))


@functools.lru_cache(maxsize=16)
def _random_poses(n: int, poses: int, seed) -> np.ndarray:
    """Route 2's poses, made once per (n, poses, seed): the searches check hundreds of designs."""

    X = random_directions(n, poses, np.random.default_rng(seed))
    X.flags.writeable = False
    return X


@dataclass(frozen=True)
class Decision:
    """Whether a multiset balances an arm, with the evidence.

    :ivar verdict: 'yes', 'no' or 'undecided'
    :ivar springs: for 'yes', the design (checked by routes 1 and 2)
    :ivar certificate: for 'no', the exact :class:`~springlab.design.certificates.Certificate`
    """

    verdict: str
    springs: tuple | None = None
    certificate: object | None = None

    @property
    def evidence(self) -> str:
        """'design', the certificate's kind, or 'none'."""
        if self.springs is not None:
            return "design"
        return self.certificate.kind if self.certificate is not None else "none"


def _entry_terms(system) -> dict:
    """Per entry of a :class:`~springlab.design.certificates.SignedSystem`, per spring (-1 for
    gravity), the signs of the terms it puts there (True: positive)."""
    terms: dict = {e: {} for e in system.entries}
    for e, row in system.rows.items():
        for v, c in row.items():
            terms[e].setdefault(-1 if v == "t" else v[0], set()).add(c > 0)
    return terms


def _one_signed(terms: dict, present, can_add) -> list[tuple]:
    """The entries whose terms, from gravity and the ``present`` springs, all have one sign:
    (how many springs of ``can_add`` would bring the other sign, entry, the sign, those springs),
    the fewest first."""
    out = []
    for e, per in terms.items():
        signs = set().union(*(per.get(k, set()) for k in [-1, *present]))
        if len(signs) == 1:
            sign = next(iter(signs))
            fixers = frozenset(k for k, sg in per.items() if k >= 0 and (not sign) in sg and k in can_add)
            out.append((len(fixers), e, sign, fixers))
    return sorted(out, key=lambda x: (x[0], x[1]))


def decide(chain: Chain, slots, *, seed=0) -> Decision:
    """Decide whether the multiset balances the arm (module docstring), cheapest evidence first:
    signs alone, the linear relaxation's certificate, the degree-2 certificate with the coupled
    springs' variables as factors, the design search (:func:`confirm`'s), the degree-2 certificate
    with every variable as a factor."""
    _checks.instance("chain", chain, Chain)
    slots = list(as_slots(slots))

    system = SignedSystem(chain, slots)
    signed = _one_signed(_entry_terms(system), range(len(slots)), ())
    cert = sign_certificate(system, signed[0][1], signed[0][2]) if signed else None
    cert = cert or relaxation_certificate(chain, slots, system=system)
    if cert is not None:
        return Decision("no", certificate=cert)
    return _after_relaxation(chain, slots, seed=seed, system=system)


def _after_relaxation(chain: Chain, slots, *, seed=0, system=None) -> Decision:
    """:func:`decide` once the relaxation is feasible: Newton steps from the programme's centre (the
    design search's first, cheap step), the degree-2 certificate with the coupled springs' variables
    as factors (one linear programme, infeasible at once for a multiset that balances), the rest of
    the design search (:func:`confirm`'s), and last the degree-2 certificate with every variable as a
    factor."""

    searches = design_searches(chain, slots, seed=seed)
    found = next(searches, None)  # Newton steps from the centre: cheap, and most balanceable multisets end here
    if found is not None and balances_by_geometry(chain, found) <= ROUTE_TWO_TOLERANCE:
        return Decision("yes", springs=found)
    cert = coupling_certificate(chain, slots, system=system, factors="coupled")
    if cert is not None:
        return Decision("no", certificate=cert)
    for found in searches:
        if found is not None and balances_by_geometry(chain, found) <= ROUTE_TWO_TOLERANCE:
            return Decision("yes", springs=found)
    cert = coupling_certificate(chain, slots, system=system, factors="all")
    if cert is not None:
        return Decision("no", certificate=cert)
    return Decision("undecided")


def is_balanceable(chain: Chain, slots) -> str:
    """:func:`decide`'s verdict: 'yes', 'no' or 'undecided'."""
    return decide(chain, slots).verdict


@dataclass
class MinimalSearch:
    """Every inclusion-minimal balanceable multiset over an alphabet, with the proofs.

    :ivar minimal: (multiset, design) per minimal balanceable multiset, fewest springs first
    :ivar refuted: per multiset the search proved unbalanceable (label), its certificate
    :ivar undecided: multisets neither confirmed nor refuted (the search is then not complete)
    :ivar nodes: multisets decided
    :ivar seconds: wall time
    """

    n: int
    signs: str
    arm: Chain
    minimal: list = field(default_factory=list)
    refuted: dict = field(default_factory=dict)
    undecided: list = field(default_factory=list)
    nodes: int = 0
    seconds: float = 0.0

    @property
    def complete(self) -> bool:
        """True when every multiset the search met was decided: the list is then every
        inclusion-minimal balanceable multiset."""
        return not self.undecided

    @property
    def multisets(self) -> list[tuple[SpringSlot, ...]]:
        return [cfg for cfg, _ in self.minimal]

    def sizes(self) -> dict[int, int]:
        """{number of springs: how many minimal multisets have it}."""
        return dict(sorted(Counter(len(cfg) for cfg, _ in self.minimal).items()))

    def kinds(self) -> dict[str, int]:
        """{certificate kind: how many of the refutations use it}."""
        return dict(sorted(Counter(c.kind for c in self.refuted.values()).items()))


def minimal_balanceable(chain: Chain, *, signs: str = "paper", max_nodes: int = 200_000,
                        fewest: bool = False, most_springs: int | None = None, progress: bool = False) -> MinimalSearch:
    """Every inclusion-minimal balanceable multiset over :func:`alphabet` (``signs``), each with a
    design, and an exact certificate for every multiset the search refutes.

    Level by level from the empty multiset: a multiset containing a minimal one already found is
    skipped (it is not minimal); any other is decided (:func:`decide`, with the relaxation solved
    in one warm-started model). A balanceable one is minimal: a balanceable proper sub-multiset
    would contain a minimal one, found at a lower level, and supersets of those are skipped. A
    refuted one is extended by each spring that could
    break its certificate (:meth:`~springlab.design.certificates.Certificate.breakers`): a
    balanceable superset must contain one, so every minimal multiset is reached, and the search
    is complete when no multiset it meets is undecided.

    With ``fewest`` the search stops after the first level (number of springs) at which a multiset
    balances: it returns every minimal multiset of that size, and its refutations prove that no
    multiset with fewer springs balances.

    With ``most_springs`` the search is complete for multisets of at most that many springs: a
    refuted multiset is not extended when it would need more. Each entry whose terms all have one
    sign needs one of the springs that bring the other sign; entries whose sets of such springs are
    pairwise disjoint need one spring each, so their number (a greedy packing) bounds the springs
    still to add from below.

    :raises SearchExhaustedError: after ``max_nodes`` multisets (rather than a partial list)
    """
    _checks.instance("chain", chain, Chain)
    max_nodes = _checks.count("max_nodes", max_nodes, least=1)
    if most_springs is not None:
        most_springs = _checks.count("most_springs", most_springs, least=0)
    from tqdm import tqdm

    start = time.perf_counter()
    items = alphabet(chain.n, signs)
    kinds = sorted(set(items))
    most = np.array([items.count(k) for k in kinds])
    relaxation = Relaxation(chain, kinds)
    universe = relaxation.system
    terms = _entry_terms(universe)  # entry -> kind -> the signs of its terms there
    out = MinimalSearch(chain.n, signs, chain)
    level: set[tuple[int, ...]] = {tuple([0] * len(kinds))}
    found: list[np.ndarray] = []
    bar = tqdm(disable=not progress, desc=f"n = {chain.n}, {signs} signs: minimal multisets", mininterval=2.0)
    while level:
        children: set[tuple[int, ...]] = set()
        F = np.array(found) if found else np.zeros((0, len(kinds)), dtype=int)
        for counts in sorted(level):
            c = np.array(counts)
            if len(F) and np.any(np.all(F <= c, axis=1)):
                continue
            out.nodes += 1
            bar.update()
            if out.nodes > max_nodes:
                raise SearchExhaustedError(f"the search decided max_nodes = {max_nodes} multisets without finishing; "
                                           "raise max_nodes")
            slots = [kinds[k] for k in np.flatnonzero(c) for _ in range(c[k])]
            label = multiset_label(slots)
            cert = None
            present = np.flatnonzero(c)
            system = universe.multiset([k for k in present for _ in range(c[k])])
            one_signed = _one_signed(terms, present, set(np.flatnonzero(c < most)))
            still = 1  # springs still to add, at least (a packing of one-signed entries with disjoint fixers)
            if one_signed:
                used: set = set()
                still = 0
                for _, _, _, fixers in one_signed:
                    if not fixers & used:
                        used |= fixers
                        still += 1
                _, e, sign, _ = one_signed[0]  # branch on the entry the fewest kinds can fix
                cert = sign_certificate(system, e, sign)
            if cert is None:
                feasible, y = relaxation(c)
                last = most_springs is not None and len(slots) + 1 > most_springs  # no children: any certificate
                if not feasible:
                    y2 = None if last else relaxation.pruning(c)
                    cert = (relaxation_certificate_from(system, y2) if y2 is not None else None) or relaxation_certificate_from(system, y)
            if cert is None:
                decision = _after_relaxation(chain, slots, system=system)
                if decision.verdict == "yes":
                    out.minimal.append((tuple(slots), decision.springs))
                    found.append(c)
                    F = np.array(found)
                    continue
                if decision.verdict == "undecided":
                    out.undecided.append(tuple(slots))
                    continue
                cert = decision.certificate
            out.refuted[label] = cert
            if most_springs is not None and len(slots) + still > most_springs:
                continue  # every balanceable superset has more than most_springs springs
            for k in cert.breakers(universe):
                if c[k] < most[k]:
                    child = list(counts)
                    child[k] += 1
                    children.add(tuple(child))
        level = children if not (fewest and found) else set()
    bar.close()
    out.minimal.sort(key=lambda x: (len(x[0]), multiset_label(x[0])))
    out.seconds = time.perf_counter() - start
    return out


def confirm(chain: Chain, slots, *, starts: int = 2, seed=0):
    """Springs with the slots' signs that satisfy 000 Eqs. (39) exactly, or None.

    000 Eqs. (39) are linear in (P, A, B, k) per spring; the coupling P k = A B binds for
    springs spanning three or more joints (for shorter ones k, or a and b, are free to
    meet it). The searches, in order:

    0. Newton steps on the equations and couplings from the linear programme's centre (cheap:
       most balanceable multisets end here);
    1. quick polishes (SLSQP on the couplings within the equations, then Newton steps) from the
       linear programme's centre (every quantity as far from zero as the equations allow, so the
       springs come out well scaled) and from :data:`~springlab.design.programme.QUICK_STARTS` vertices (random objectives);
    2. with each long spring's a fixed (A = a k and P = a B are then linear), Nelder-Mead
       on the a's minimises the programme's least violation, and the centre of the programme
       with those a's is a design; a zero there can sit on a thin set (an end forced onto a
       joint, a = -r_i), which the first search misses;
    3. the thorough polish (bounded least squares) from the first ``starts`` starts of 1.

    The springs are rebuilt (k = K, a = A / K, b = B / K; a shorter spring's k from its P)
    and their balance residual (000 Eqs. 39, route 1) checked to 1e-9 of the largest G_1,j.
    """
    _checks.instance("chain", chain, Chain)
    slots = as_slots(slots)
    for found in design_searches(chain, slots, starts=starts, seed=seed):
        if found is not None:
            return found
    return None


def random_arm(n: int, rng) -> Chain:
    """A generic n-link arm: lengths 0.15-0.45 m, centres of mass 0.2-0.8 of the length,
    masses 0.5-5 kg, g = 9.81 m/s^2."""
    n = _checks.links(n, "n")
    rng = _checks.rng("rng", rng)

    rng = np.random.default_rng(rng)
    r = rng.uniform(0.15, 0.45, n - 1)
    return serial_chain(r, r * rng.uniform(0.2, 0.8, n - 1), rng.uniform(0.5, 5.0, n - 1), g=9.81)


def multiset_label(cfg) -> str:
    return " ".join(str(s) for s in sorted(cfg))


