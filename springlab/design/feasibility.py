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

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import functools
import itertools
import time
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from springlab import _checks
from springlab.design.certificates import (
    GRAVITY,
    SignedSystem,
    coupling_certificate,
    relaxation_certificate,
    relaxation_certificate_from,
    sign_certificate,
)
from springlab.design.highs import INF, new_model, solve
from springlab.design.highs import solve as solve_lp
from springlab.design.rules import (
    PATTERNS,
    SpringSlot,
    as_slots,
    best_first_configurations,
    enumerate_configurations,
    rule_violations,
)
from springlab.design.solve import linear_columns
from springlab.energy.geometry import gravity_energy, total_energy
from springlab.energy.quadratic import balance_residual, gravity_entries
from springlab.errors import SearchExhaustedError, SolverError, SpringlabError
from springlab.model.chain import Chain, random_directions, serial_chain
from springlab.model.springs import Spring
from springlab.tables import Table

EPS = 1e-3
"""Smallest |quantity| the design search (:func:`confirm`) gives a present spring, in units of the
largest G_1,j (and the mean link length): its starts stay a thousandth of gravity's scale away from
zero (the solver's feasibility tolerance is about 1e-7). It bounds the search only: a verdict rests on
a design found or on an exact certificate, which knows no such bound."""

BOUND = 50.0
"""Largest |quantity| the design search gives a spring, in the same units (a box that keeps its
linear programmes bounded)."""


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


def _quantities(chain: Chain, s: SpringSlot) -> list[tuple[int, dict[tuple[int, int], float]]]:
    """The spring's linear quantities that enter 000 Eqs. (39): (sign, {entry: coefficient}), from
    :func:`springlab.design.solve.linear_columns` (000 Eqs. 23a-d written linearly), with lengths
    measured in the mean link length. A quantity that enters no entry (A and B of a spring
    over one joint, k of one over fewer than three) is left out."""

    length = float(np.mean(chain.r))
    cols = linear_columns(chain, [s])[0]
    unit = {"P": 1.0, "A": length, "B": length, "K": length**2}  # P = k a b, A = k a, B = k b, k
    sign = {"P": s.sa * s.sb, "A": s.sa, "B": s.sb, "K": 1}
    return [(sign[q], {key: coef / unit[q] for key, coef in cols[q].items()}) for q in "PABK" if cols[q]]


@dataclass
class _Programme:
    items: list[SpringSlot]
    owner: np.ndarray  # quantity -> item
    signs: np.ndarray
    A_eq: np.ndarray
    b_eq: np.ndarray


def _programme(chain: Chain, items) -> _Programme:
    """The linear relaxation's equations for ``items``."""

    G = gravity_entries(chain.r, chain.d, chain.m, chain.g)
    scale = max(abs(v) for v in G.values())
    if scale <= 0:
        raise SpringlabError("the arm has no gravity moment to balance (all G_1,j = 0)")
    keys = [(u, v) for u in range(1, chain.n + 1) for v in range(u + 1, chain.n + 1)]
    row = {k: idx for idx, k in enumerate(keys)}
    cols, owner, signs = [], [], []
    for idx, s in enumerate(items):
        for sign, entries in _quantities(chain, s):
            cols.append(entries)
            owner.append(idx)
            signs.append(sign)
    A_eq = np.zeros((len(keys), len(cols)))
    for c, entries in enumerate(cols):
        for key, coef in entries.items():
            A_eq[row[key], c] = coef
    b_eq = np.array([-G.get(k, 0.0) / scale for k in keys])  # 000 Eqs. (39a-b): G + sum K = 0
    return _Programme(list(items), np.array(owner), np.array(signs, dtype=float), A_eq, b_eq)


def _long_columns(prog: _Programme, slots) -> list[list[int]]:
    """Per spring spanning three or more joints: its columns (P, A, B, k) in the programme."""
    where: dict[int, list[int]] = {}
    for col, own in enumerate(prog.owner):
        where.setdefault(int(own), []).append(col)
    return [where[idx] for idx, s in enumerate(slots) if s.j - s.i >= 3]


def _phase_one_lp(prog: _Programme):
    """The phase-one programme of ``prog`` as a HiGHS model (highspy.HighsLp): least total violation
    of 000 Eqs. (39) (slacks both ways, each costing 1) with every quantity in its sign box."""
    import highspy

    rows, m = prog.A_eq.shape
    present = prog.A_eq.T != 0  # column-wise storage of [A_eq, I, -I], built directly
    per_column = np.concatenate([present.sum(axis=1), np.ones(2 * rows, dtype=int)])
    lp = highspy.HighsLp()
    lp.num_col_, lp.num_row_ = m + 2 * rows, rows
    lp.col_cost_ = np.concatenate([np.zeros(m), np.ones(2 * rows)])
    lp.col_lower_ = np.concatenate([np.where(prog.signs > 0, EPS, -BOUND), np.zeros(2 * rows)])
    lp.col_upper_ = np.concatenate([np.where(prog.signs > 0, BOUND, -EPS), np.full(2 * rows, highspy.kHighsInf)])
    lp.row_lower_ = lp.row_upper_ = prog.b_eq
    lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
    lp.a_matrix_.start_ = np.concatenate([[0], np.cumsum(per_column)]).astype(np.int32)
    lp.a_matrix_.index_ = np.concatenate([np.nonzero(present)[1], np.arange(rows), np.arange(rows)]).astype(np.int32)
    lp.a_matrix_.value_ = np.concatenate([prog.A_eq.T[present], np.ones(rows), -np.ones(rows)])
    return lp


def _new_highs():
    """A silent HiGHS model (:func:`springlab.design.highs.new_model`)."""

    return new_model()


def _solved(h):
    import highspy

    if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        raise SolverError(f"the phase-one programme failed: {h.modelStatusToString(h.getModelStatus())}")
    return float(h.getInfo().objective_function_value)


class _WarmPhaseOne:
    """:func:`_phase_one`'s value for a family of programmes that differ only in a few matrix
    coefficients, kept in one HiGHS model: each call changes those coefficients and solves again
    from the previous optimal basis (a warm start), about 3 times faster than a fresh solve.

    :param prog: the programme with every varying coefficient present (non-zero)
    :param cells: (row, column) of each varying coefficient
    """

    def __init__(self, prog: _Programme, cells):
        self.highs = _new_highs()
        self.highs.passModel(_phase_one_lp(prog))
        self.cells = list(cells)

    def __call__(self, values) -> float:
        for (row, col), value in zip(self.cells, values, strict=True):
            self.highs.changeCoeff(int(row), int(col), float(value))
        self.highs.run()
        return _solved(self.highs)


class _Relaxation:
    """The linear relaxation of 000 Eqs. (39) for multisets over ``kinds``, in one HiGHS model.

    Homogeneous (gravity times t): every present quantity, signed, and t lie in [1, inf), which for
    a homogeneous system is the same as > 0 (scale any strictly positive solution up); an absent
    kind's quantities are fixed at 0. The phase-one programme (least total violation of the
    equations) is 0 exactly when the relaxation has a solution of the stated signs; otherwise its
    dual values are Stiemke multipliers (:mod:`springlab.design.certificates`). The copies of a kind
    need no columns of their own: a sum of positive quantities is any positive quantity. Each call
    changes column bounds and solves again from the last basis.
    """

    def __init__(self, chain: Chain, kinds):
        import highspy

        self.system = SignedSystem(chain, kinds)
        E = self.system.E
        self.col_scale = 1.0 / np.maximum(np.abs(E).max(axis=0), 1e-300)
        Es = E * self.col_scale
        self.row_scale = 1.0 / np.maximum(np.abs(Es).max(axis=1), 1e-300)
        Es = Es * self.row_scale[:, None]
        self.Es = Es
        rows, m = Es.shape
        self.owner = np.array([-1 if v == GRAVITY else v[0] for v in self.system.variables])
        lp = _phase_one_lp(_Programme(list(kinds), self.owner, np.ones(m), Es, np.zeros(rows)))
        lp.col_lower_ = np.concatenate([np.ones(m), np.zeros(2 * rows)])  # homogeneous: [1, inf) is > 0
        lp.col_upper_ = np.full(m + 2 * rows, highspy.kHighsInf)
        self.highs = _new_highs()
        self.highs.passModel(lp)
        self.columns = np.arange(m, dtype=np.int32)
        self.m = m
        self.inf = highspy.kHighsInf

    def pruning(self, counts) -> np.ndarray | None:
        """Stiemke multipliers for an infeasible relaxation chosen to leave few springs that could break
        them: minimise the negative parts of the absent kinds' coefficients (plus a little of |y|),
        with the present ones >= 0 summing to 1. One entry per equation, unscaled; None if none found."""

        rows, m = self.Es.shape
        present = np.ones(m, dtype=bool)
        kinds = self.owner >= 0
        present[kinds] = np.asarray(counts)[self.owner[kinds]] > 0
        P, Q = self.Es[:, present].T, self.Es[:, ~present].T
        na = Q.shape[0]
        # variables y+ (rows), y- (rows), s (one per absent column); rows: P y >= 0, Q y + s >= 0, sum P y = 1
        A = np.block([[P, -P, np.zeros((P.shape[0], na))], [Q, -Q, np.eye(na)],
                      [P.sum(axis=0)[None, :], -P.sum(axis=0)[None, :], np.zeros((1, na))]])
        low = np.r_[np.zeros(P.shape[0] + na), 1.0]
        up = np.r_[np.full(P.shape[0] + na, INF), 1.0]
        cost = np.r_[np.full(2 * rows, 1e-3), np.ones(na)]
        out = solve(cost, A, low, up, np.zeros(2 * rows + na), np.full(2 * rows + na, INF))
        if out is None:
            return None
        x = out[0]
        return (x[:rows] - x[rows:2 * rows]) * self.row_scale

    def __call__(self, counts) -> tuple[bool, np.ndarray]:
        """(feasible, y): y the equations' multipliers (one per entry, unscaled), meaningful when not
        feasible."""
        present = np.ones(self.m, dtype=bool)
        kinds = self.owner >= 0
        present[kinds] = np.asarray(counts)[self.owner[kinds]] > 0
        self.highs.changeColsBounds(self.m, self.columns, np.where(present, 1.0, 0.0),
                                    np.where(present, self.inf, 0.0))
        self.highs.run()
        value = _solved(self.highs)
        y = -np.array(self.highs.getSolution().row_dual) * self.row_scale  # reduced costs >= 0 at z = 1
        return value <= 1e-9, y


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

    searches = _searches(chain, slots, seed=seed)
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
    relaxation = _Relaxation(chain, kinds)
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
            label = _label(slots)
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
    out.minimal.sort(key=lambda x: (len(x[0]), _label(x[0])))
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
       springs come out well scaled) and from :data:`QUICK_STARTS` vertices (random objectives);
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
    for found in _searches(chain, slots, starts=starts, seed=seed):
        if found is not None:
            return found
    return None


SLSQP_ITERATIONS = 100
"""Most SLSQP iterations of one quick polish."""
QUICK_STARTS = 6
"""Vertices of the linear programme from which :func:`confirm` polishes quickly (SLSQP, then Newton
steps); the thorough polish (bounded least squares, about 0.1 s a call) comes last."""


def _searches(chain: Chain, slots, *, starts: int = 2, seed=0):
    """:func:`confirm`'s searches as a generator: yields each design found, and None after the
    central start, after the vertex starts and at the end (checkpoints: a caller may try a proof
    between them, or reject a design and ask for the next)."""
    if not slots:
        return  # no spring balances an arm with G_1,j > 0
    from scipy.optimize import least_squares, minimize

    slots = list(slots)
    prog = _programme(chain, slots)
    m = len(prog.signs)
    lo = np.where(prog.signs > 0, EPS, -BOUND)
    hi = np.where(prog.signs > 0, BOUND, -EPS)
    longs = _long_columns(prog, slots)
    long_signs = [s.sa for s in slots if s.j - s.i >= 3]
    P, A, B, K = (np.array([c[q] for c in longs], dtype=int) for q in range(4)) if longs else [np.zeros(0, int)] * 4
    scale = max(abs(v) for v in gravity_entries(chain.r, chain.d, chain.m, chain.g).values())
    length = float(np.mean(chain.r))
    rng = np.random.default_rng(seed)

    def residual(v):
        return np.concatenate([prog.A_eq @ v - prog.b_eq, v[P] * v[K] - v[A] * v[B]])

    coupling_rows = prog.A_eq.shape[0] + np.arange(len(P))

    def residual_jacobian(v):  # exact: the equations' rows, then d(P k - A B)
        J = np.zeros((len(coupling_rows) + prog.A_eq.shape[0], m))
        J[:prog.A_eq.shape[0]] = prog.A_eq
        J[coupling_rows, P], J[coupling_rows, K] = v[K], v[P]
        J[coupling_rows, A], J[coupling_rows, B] = -v[B], -v[A]
        return J

    def with_a(log_a):  # the equations with each long spring's a fixed
        rows = []
        for (Pc, Ac, Bc, Kc), la, sa in zip(longs, log_a, long_signs, strict=True):
            for x, y in ((Ac, Kc), (Pc, Bc)):
                row = np.zeros(m)
                row[x], row[y] = 1.0, -sa * np.exp(la)
                rows.append(row)
        return _Programme(prog.items, prog.owner, prog.signs, np.vstack([prog.A_eq, *rows]),
                          np.concatenate([prog.b_eq, np.zeros(len(rows))]))

    def coupling_squared(v):
        r = v[P] * v[K] - v[A] * v[B]
        return float(r @ r)

    def coupling_gradient(v):
        r = v[P] * v[K] - v[A] * v[B]
        g = np.zeros_like(v)
        np.add.at(g, P, 2 * r * v[K])
        np.add.at(g, K, 2 * r * v[P])
        np.add.at(g, A, -2 * r * v[B])
        np.add.at(g, B, -2 * r * v[A])
        return g

    def solved(intermediate_result):  # stop SLSQP once the equations and couplings hold to 1e-13
        v = intermediate_result.x
        worst = max(np.abs(prog.A_eq @ v - prog.b_eq).max(), np.abs(v[P] * v[K] - v[A] * v[B]).max())
        if worst <= 1e-13:  # in units of the largest G_1,j: springs_of's check (1e-9) then passes
            raise StopIteration

    def newton(v0):  # minimum-norm Newton steps on the equations and couplings, unknowns at a bound held
        v = np.clip(v0, lo, hi)
        free = np.minimum(v - lo, hi - v) > 1e-9 * np.maximum(1.0, np.abs(v))
        for _ in range(8):
            F = residual(v)
            if np.abs(F).max() <= 1e-15:
                break
            step = np.zeros(m)
            step[free] = np.linalg.lstsq(residual_jacobian(v)[:, free], -F, rcond=None)[0]
            v = v + step
        return v if np.all((v >= lo) & (v <= hi)) else v0

    def newton_free(v0):  # minimum-norm Newton steps with every unknown free: a design needs only the signs
        v = v0.copy()
        for _ in range(12):
            F = residual(v)
            if np.abs(F).max() <= 1e-15:
                break
            v = v + np.linalg.lstsq(residual_jacobian(v), -F, rcond=None)[0]
        return v if np.all(v * prog.signs > 0) else v0

    def settled(v):  # a design at v, or after Newton steps with the bounds held, or with every unknown free
        return springs_of(v) or springs_of(newton(v)) or springs_of(newton_free(v))

    def polish(v0, thorough=True):
        v0 = np.clip(v0, lo, hi)
        if len(P):  # SLSQP on the coupling within the equations: fast when it converges
            v0 = minimize(coupling_squared, v0, jac=coupling_gradient, method="SLSQP", bounds=list(zip(lo, hi, strict=True)),
                          constraints=[{"type": "eq", "fun": lambda x: prog.A_eq @ x - prog.b_eq,
                                        "jac": lambda x: prog.A_eq}], options={"maxiter": SLSQP_ITERATIONS, "ftol": 1e-30},
                          callback=solved).x
        found = settled(v0)
        if found is not None:
            return found
        if not thorough:
            return None
        sol = least_squares(residual, np.clip(v0, lo, hi), jac=residual_jacobian, bounds=(lo, hi), xtol=1e-15,
                            ftol=1e-15, gtol=1e-15, max_nfev=500)
        return springs_of(sol.x)

    def springs_of(v):
        if not np.all(v * prog.signs > 0) or np.abs(residual(v)).max() > 1e-6:
            return None  # far from a design (in units of the largest G_1,j): no springs to build and check
        where: dict[int, list[int]] = {}
        for col, own in enumerate(prog.owner):
            where.setdefault(int(own), []).append(col)
        out = []
        for idx, s in enumerate(slots):
            cols = where[idx]
            Pv = v[cols[0]] * scale  # J
            if s.j - s.i == 1:  # only P = k a b enters: any k with a b = P / k
                k = scale / length**2
                a, b = s.sa * np.sqrt(abs(Pv) / k), s.sb * np.sqrt(abs(Pv) / k)
            else:
                Av, Bv = v[cols[1]] * scale / length, v[cols[2]] * scale / length  # N
                k = v[cols[3]] * scale / length**2 if s.j - s.i >= 3 else Av * Bv / Pv  # N/m
                a, b = Av / k, Bv / k
            out.append(Spring(s.i, s.j, float(a), float(b), float(k)))
        ok = np.abs(balance_residual(chain, out)).max() <= 1e-9 * scale
        return tuple(out) if ok else None

    # the first start is central: every quantity as far from zero as the equations allow (max t with
    # |x_j| >= t, |x_j| <= BOUND), so its springs are well scaled; then vertices of random objectives
    def centre(p: _Programme):  # max t with |x_j| >= t: every quantity as far from zero as p allows
        out = solve_lp(np.r_[np.zeros(m), -1.0], np.block([[p.A_eq, np.zeros((len(p.A_eq), 1))],
                                                           [np.diag(prog.signs), -np.ones((m, 1))]]),
                       np.r_[p.b_eq, np.zeros(m)], np.r_[p.b_eq, np.full(m, np.inf)], np.r_[lo, 0.0], np.r_[hi, BOUND])
        return None if out is None else out[0][:m]

    vertices = [centre(prog)]
    if vertices[0] is None:
        return
    yield settled(vertices[0])
    yield polish(vertices[0], thorough=False)  # None too: the caller may try a proof before the rest
    for _ in range(QUICK_STARTS):  # quick polishes from several vertices, then the thorough one from the first
        lp = solve_lp(rng.normal(size=m), prog.A_eq, prog.b_eq, prog.b_eq, lo, hi)
        if lp is None:
            return
        vertices.append(lp[0])
        found = polish(lp[0], thorough=False)
        if found is not None:
            yield found
    yield None
    if longs:  # each long spring's a fixed: the couplings are linear, and the centre is a design
        base_rows = prog.A_eq.shape[0]
        cells = [(base_rows + 2 * q + t, y) for q, (Pc, Ac, Bc, Kc) in enumerate(longs) for t, y in enumerate((Kc, Bc))]
        warm = _WarmPhaseOne(with_a(np.zeros(len(longs))), cells)  # rows A - a k = 0, P - a B = 0 per long spring
        signs_a = np.repeat(np.array(long_signs, dtype=float), 2)
        for t in range(2 * starts):
            res = minimize(lambda la: warm(-signs_a * np.exp(np.repeat(la, 2))),
                           np.zeros(len(longs)) if t == 0 else rng.uniform(-3.0, 1.0, len(longs)),
                           method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-14, "maxiter": 400})
            x = centre(with_a(res.x))
            found = polish(x) if x is not None else None
            if found is not None:
                yield found
    for v in vertices[:starts]:  # the thorough polish last: bounded least squares, about 0.1 s a call
        found = polish(v)
        if found is not None:
            yield found
    yield None


def random_arm(n: int, rng) -> Chain:
    """A generic n-link arm: lengths 0.15-0.45 m, centres of mass 0.2-0.8 of the length,
    masses 0.5-5 kg, g = 9.81 m/s^2."""
    n = _checks.links(n, "n")
    rng = _checks.rng("rng", rng)

    rng = np.random.default_rng(rng)
    r = rng.uniform(0.15, 0.45, n - 1)
    return serial_chain(r, r * rng.uniform(0.2, 0.8, n - 1), rng.uniform(0.5, 5.0, n - 1), g=9.81)


def _label(cfg) -> str:
    return " ".join(str(s) for s in sorted(cfg))


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
    """Test R1-R6 both ways on ``arms`` random n-link arms (:func:`random_arm`).

    On every arm the inclusion-minimal balanceable multisets over the paper's alphabet are
    enumerated (:func:`minimal_balanceable`); ``same_on_every_arm`` says the lists agree. On the
    first arm each of the rules' configurations (:func:`springlab.design.rules.enumerate_configurations`)
    is decided (:func:`decide`: a design or an exact certificate), with both minimality notions;
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
    minimal = {_label(cfg) for cfg in search.multisets}
    designs = {_label(cfg): springs for cfg, springs in search.minimal}
    decided: dict[str, Decision] = {}  # one decision per multiset: sub-multisets recur

    def decide_once(cfg) -> Decision:
        key = _label(cfg)
        if key not in decided:
            decided[key] = Decision("yes") if key in minimal else decide(first, cfg)
        return decided[key]

    admitted = enumerate_configurations(n)
    decisions, single, inclusion = {}, 0, 0
    for cfg in tqdm(admitted, disable=not progress, desc=f"n = {n}, R1-R6 configurations", mininterval=2.0):
        d = decide_once(cfg)
        if d.verdict == "yes" and d.springs is None:  # minimal: its design is the search's
            d = Decision("yes", springs=designs[_label(cfg)])
        decisions[_label(cfg)] = d
        if d.verdict != "yes":
            continue
        if _label(cfg) in minimal:  # inclusion-minimal (the search is complete), so no spring is removable
            inclusion += 1
            single += 1
        elif all(decide_once(cfg[:k] + cfg[k + 1:]).verdict == "no" for k in range(len(cfg))):
            single += 1
    rejected = {_label(cfg): [str(x) for x in rule_violations(n, cfg)] for cfg in search.multisets
                if rule_violations(n, cfg)}
    listed = {_label(cfg) for cfg in admitted}
    unlisted = {_label(cfg): [str(cfg[k]) for k in range(len(cfg)) if not rule_violations(n, cfg[:k] + cfg[k + 1:])]
                for cfg in search.multisets if _label(cfg) not in rejected and _label(cfg) not in listed}
    same = all(sorted(map(_label, s.multisets)) == sorted(minimal) for s in searches[1:])
    full = minimal_balanceable(first, signs="all", progress=progress) if full_signs else None
    return RulesAgainstPhysics(n, arms, search, admitted, decisions, single, inclusion, rejected, unlisted, same, full)


@dataclass
class Fewest:
    """The fewest springs that balance an n-link arm on a sign alphabet, proved.

    :ivar springs: the fewest
    :ivar configuration: a multiset of that many springs that balances, and ``design`` its springs
    :ivar search: the search complete up to one spring fewer (:func:`minimal_balanceable` with
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
                "a design": _label(self.configuration),
                "its energy variation (route 2)": f"{self.route_two:.1e}",
                "fewer springs: multisets refuted": len(self.search.refuted),
                "by kind": ", ".join(f"{k}: {v}" for k, v in self.search.kinds().items())}


RULES_TRIED = 500
"""Most of the rules' configurations, fewest springs first, :func:`fewest_springs` decides for a
first design (an upper bound on the fewest springs)."""


def fewest_springs(n: int, *, seed: int = 0, signs: str = "paper", max_nodes: int = 2_000_000) -> Fewest:
    """The fewest springs that balance a random n-link arm (:func:`random_arm`), with a design and the
    proof that fewer cannot.

    A first design comes from the rules' configurations, fewest springs first (the first that
    balances, of at most :data:`RULES_TRIED`); then :func:`minimal_balanceable` searches every
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
            found = next(_searches(arm, cfg), None) if quick else decide(arm, cfg).springs
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
