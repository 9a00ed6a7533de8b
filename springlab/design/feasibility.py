"""Which spring multisets balance an arm: paper 000's rules R1-R6 tested against 000 Eqs. (39).

A configuration is a **multiset** of springs over the paper's sign alphabet
(:func:`alphabet`): ground springs S(1,j) (+,+), S(1,2) also (-,-); every other
pair (+,+), (-,-) or (+,-); two springs on one pair in different patterns, and on
a pair spanning three or more joints (j - i >= 3) the same pattern twice.

It is **balanceable** when 000 Eqs. (39) have a solution with every k > 0 and every
a, b of its pattern's sign. 000 Eqs. (39) are linear in P = k a b, A = k a, B = k b
and k of each spring (000 Eqs. 23a-d) except for P k = A B, which binds only for
springs spanning three or more joints. So:

* the **linear relaxation** (drop P k = A B, keep the signs strict) is necessary:
  where it has no solution the multiset is not balanceable (a proof);
* a multiset the relaxation admits is confirmed by a design found by least squares
  (:func:`springlab.design.solve.find_design`, signs only) and checked entry by entry.

**Minimal** has two meanings, both counted (:func:`rules_against_physics`):

* *inclusion-minimal*: balanceable, and no proper sub-multiset is;
* *no single spring removable*: balanceable, and removing any one spring leaves a
  multiset that is not (the paper's enumeration of Table 1 keeps configurations in
  this sense, with "balanceable" replaced by "admitted by R1-R6").

The inclusion-minimal multisets of the relaxation are enumerated exactly, fewest
springs first, by a mixed-integer programme (scipy's HiGHS): a binary z per spring
of the alphabet, each of the spring's linear quantities carrying its sign by at
least ``eps`` when z = 1 and zero when z = 0, minimise sum z, and after each find
forbid every superset of it (sum of its z <= size - 1). When the programme becomes
infeasible there is no further minimal multiset. If every one found is confirmed
by a design, the relaxation's minimal multisets are exactly the true ones (a true
balanceable multiset contains a relaxation-minimal one, which is then balanceable).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field

import numpy as np

from springlab import _checks
from springlab.design.rules import SpringSlot, as_slots, rule_violations
from springlab.design.solve import term_signs
from springlab.errors import SearchExhaustedError, SolverError, SpringlabError
from springlab.model.chain import Chain
from springlab.tables import Table

EPS = 1e-3
"""Smallest |quantity| of a present spring in the programme, in units of the largest
G_1,j (and the mean link length): a design needing a quantity smaller than a
thousandth of gravity's scale is not counted. (The solver's feasibility tolerance is
about 1e-7; a margin far above it keeps 'present' from meaning 'zero within tolerance'.)"""

BOUND = 50.0
"""Largest |quantity| in the same units. With the solver's integrality tolerance (1e-6)
an absent spring can leak up to BOUND * 1e-6 = 5e-5 into the equations, far below
EPS; every multiset the programme returns is re-checked by a plain linear programme
(:func:`relaxation_feasible`) before it is counted."""


def alphabet(n: int) -> list[SpringSlot]:
    """The springs a multiset may contain on an n-link arm, one entry per copy.

    Ground springs S(1,j) (+,+) and S(1,2) (-,-) (000 Eq. 41 and the note below
    it); non-ground springs (+,+), (-,-), (+,-) (Fig. 10); a spring spanning three
    or more joints appears twice (its k enters entries of its own, so a second copy
    of one pattern is not the same as a stiffer first one).
    """
    n = _checks.links(n, "n")
    out = [SpringSlot(1, 2, "(+,+)"), SpringSlot(1, 2, "(-,-)")]
    for j in range(3, n + 1):
        out += [SpringSlot(1, j)] * (2 if j - 1 >= 3 else 1)
    for i in range(2, n):
        for j in range(i + 1, n + 1):
            for p in ("(+,+)", "(-,-)", "(+,-)"):
                out += [SpringSlot(i, j, p)] * (2 if j - i >= 3 else 1)
    return out


def _quantities(chain: Chain, s: SpringSlot) -> list[tuple[int, dict[tuple[int, int], float]]]:
    """The spring's linear quantities that enter 000 Eqs. (39): (sign, {entry: coefficient}), from
    :func:`springlab.design.solve.linear_columns` (000 Eqs. 23a-d written linearly), with lengths
    measured in the mean link length. A quantity that enters no entry (A and B of a spring
    over one joint, k of one over fewer than three) is left out."""
    from springlab.design.solve import linear_columns

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
    from springlab.energy.quadratic import gravity_entries

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


def relaxation_feasible(chain: Chain, slots) -> bool:
    """True when the linear relaxation of 000 Eqs. (39) has a solution in which every
    spring's quantities carry their signs by at least :data:`EPS` (a necessary
    condition for balance; False is a proof that the multiset cannot balance)."""
    _checks.instance("chain", chain, Chain)
    slots = as_slots(slots)
    slots = list(slots)
    return bool(slots) and _phase_one(_programme(chain, slots))[0] <= 1e-9


def _long_columns(prog: _Programme, slots) -> list[list[int]]:
    """Per spring spanning three or more joints: its columns (P, A, B, k) in the programme."""
    where: dict[int, list[int]] = {}
    for col, own in enumerate(prog.owner):
        where.setdefault(int(own), []).append(col)
    return [where[idx] for idx, s in enumerate(slots) if s.j - s.i >= 3]


def _fixed_ratio(x0: np.ndarray, N: np.ndarray, i: int, j: int) -> float | None:
    """c when x_i = c x_j at every point x0 + N z of the equations' solution set, else None."""
    vi, vj = np.r_[x0[i], N[i]], np.r_[x0[j], N[j]]
    if np.abs(vj).max() < 1e-12:
        return None
    c = float(vi @ vj / (vj @ vj))
    return c if np.abs(vi - c * vj).max() <= 1e-9 * max(1.0, np.abs(vi).max()) else None


def tightened_infeasible(chain: Chain, slots) -> bool:
    """True when 000 Eqs. (39) with P k = A B provably have no solution with the stated signs.

    Exact consequences of the coupling are added to the linear equations until none is new:
    where the equations force B = c k for a spring (its b fixed at c), P k = A B gives P = c A;
    likewise A = c k gives P = c B, P = c A gives B = c k, P = c B gives A = c k. Then the
    linear programme with strict signs decides: infeasible is a proof (the added rows hold at
    every solution). False proves nothing.
    """
    _checks.instance("chain", chain, Chain)
    slots = as_slots(slots)
    from scipy.linalg import null_space

    slots = list(slots)
    prog = _programme(chain, slots)
    longs = _long_columns(prog, slots)
    A, rhs = prog.A_eq.copy(), prog.b_eq.copy()
    m = A.shape[1]
    for _ in range(4 * len(longs) + 1):
        x0 = np.linalg.lstsq(A, rhs, rcond=None)[0]
        if np.abs(A @ x0 - rhs).max() > 1e-9:
            return True  # the equations alone are inconsistent
        N = null_space(A)
        N = N if N.size else np.zeros((m, 1))
        new = None
        for P, Aq, Bq, K in longs:
            for (u, v), (p, q) in (((Bq, K), (P, Aq)), ((Aq, K), (P, Bq)), ((P, Aq), (Bq, K)), ((P, Bq), (Aq, K))):
                c = _fixed_ratio(x0, N, u, v)
                if c is None:
                    continue
                row = np.zeros(m)
                row[p], row[q] = 1.0, -c  # x_p = c x_q, from P k = A B
                if abs(row @ x0) > 1e-9 and np.abs(row @ N).max() < 1e-9:
                    return True  # contradicts the equations
                if np.abs(row @ N).max() > 1e-9:
                    new = row
                    break
            if new is not None:
                break
        if new is None:
            break
        A, rhs = np.vstack([A, new]), np.append(rhs, 0.0)
    return _phase_one(_Programme(prog.items, prog.owner, prog.signs, A, rhs))[0] > 1e-9


class _RatioProgramme:
    """The phase-one programme of a multiset with, per spring spanning three or more joints,
    bounds on its two ratios a = A/k = P/B and b = B/k = P/A (in the programme's units),
    written linearly: for b in [l, h], l k <= |B| <= h k and l |A| <= |P| <= h |A| (each
    quantity carries its sign, so |X| is linear). Every design with the multiset's signs and
    ratios within the bounds satisfies these rows, so an infeasible programme is a proof that
    no design has its ratios there. One HiGHS model; a change of bounds changes coefficients
    and re-solves from the last basis."""

    def __init__(self, chain: Chain, slots):
        import highspy

        prog = _programme(chain, slots)
        self.highs = _new_highs()
        self.highs.passModel(_phase_one_lp(prog))
        self.widest = (EPS / BOUND, BOUND / EPS)  # |A| / k and the rest: quantities in [EPS, BOUND]
        sign = prog.signs
        row = prog.A_eq.shape[0]
        self.cells: list[list[tuple[int, int, bool, float]]] = []  # per ratio: (row, column, lower?, sign)
        for P, A, B, K in _long_columns(prog, slots):
            for pairs in (((A, K), (P, B)), ((B, K), (P, A))):  # a = |A|/k = |P|/|B|, b = |B|/k = |P|/|A|
                cells = []
                for num, den in pairs:
                    for lower, bound in ((True, self.widest[0]), (False, self.widest[1])):
                        # lower: |num| - l |den| >= 0; upper: h |den| - |num| >= 0
                        flip = 1.0 if lower else -1.0
                        self.highs.addRow(0.0, highspy.kHighsInf, 2, np.array([num, den], dtype=np.int32),
                                          np.array([flip * sign[num], -flip * bound * sign[den]]))
                        cells.append((row, den, lower, float(sign[den])))
                        row += 1
                self.cells.append(cells)
        self.box = [self.widest] * len(self.cells)

    def feasible(self, box) -> bool:
        """True when some point of the relaxation has every ratio within ``box``: [(low, high)] per ratio."""
        import highspy

        for t, bounds in enumerate(box):
            if bounds != self.box[t]:
                for row, den, lower, sign in self.cells[t]:
                    self.highs.changeCoeff(row, den, -bounds[0] * sign if lower else bounds[1] * sign)
                self.box[t] = bounds
        for _ in range(2):
            self.highs.run()
            status = self.highs.getModelStatus()
            if status == highspy.HighsModelStatus.kInfeasible:
                return False
            if status == highspy.HighsModelStatus.kOptimal:
                return float(self.highs.getInfo().objective_function_value) <= 1e-9
            self.highs.clearSolver()  # numerical trouble from the warm basis: once more from scratch
        return True  # undecided by the solver: claim nothing

    def lowest(self, box, t: int, precision: float) -> float:
        """A lower bound on ratio t: the largest c (to ``precision`` in log) for which no point of
        the relaxation has the ratio in [low, c]."""
        low, high = box[t]
        trial = list(box)
        trial[t] = (low, low)
        if self.feasible(trial):
            return low
        while np.log(high / low) > precision:  # [box low, low] infeasible, [box low, high] feasible
            mid = float(np.sqrt(low * high))
            trial[t] = (box[t][0], mid)
            low, high = (low, mid) if self.feasible(trial) else (mid, high)
        return low

    def highest(self, box, t: int, precision: float) -> float:
        """An upper bound on ratio t: the smallest c for which no point has the ratio in [c, high]."""
        low, high = box[t]
        trial = list(box)
        trial[t] = (high, high)
        if self.feasible(trial):
            return high
        while np.log(high / low) > precision:  # [low, box high] feasible, [high, box high] infeasible
            mid = float(np.sqrt(low * high))
            trial[t] = (mid, box[t][1])
            low, high = (mid, high) if self.feasible(trial) else (low, mid)
        return high


RATIO_PRECISION = 1e-3
"""Bisection precision of :func:`coupling_refuted`'s ratio bounds, in log (0.1 %): the bounds
are proved whatever it is; a finer one only refutes multisets whose infeasibility gap is
narrower."""


def coupling_refuted(chain: Chain, slots, *, passes: int = 10) -> bool:
    """True when 000 Eqs. (39) with P k = A B provably have no solution with the stated signs,
    by bounds on the ratios of the springs spanning three or more joints.

    P k = A B says P / A = B / k (= b) and P / B = A / k (= a). Each ratio starts within what
    the quantities' boxes allow and is tightened in turn: its lower bound rises to the largest c
    for which the linear programme with the ratio in [low, c] has no solution (bisection in log,
    :data:`RATIO_PRECISION`), its upper bound likewise; a ratio whose bounds cross is a proof.
    Passes repeat while some bound moves by more than ten times the precision (at most
    ``passes``). False proves nothing.

    Example (n = 5, a random arm): S(1,2) S(1,4) S(1,5) S(2,4)(-,-) and two springs on (2,5).
    Entry (2,4) with (2,3) needs b of S(1,4) above r_4; entries (1,3) and (1,4) give
    b = P / A = (G_1,4 - r_4 A_S(1,5)) / (G_1,3 / r_3 - A_S(1,5)), below r_4 whenever
    G_1,4 r_3 < G_1,3 r_4 (every arm with d_4 < r_4).
    """
    _checks.instance("chain", chain, Chain)
    slots = list(as_slots(slots))
    passes = _checks.count("passes", passes, least=1)
    if not any(s.j - s.i >= 3 for s in slots):
        return False  # no coupling binds: the relaxation decides
    ratios = _RatioProgramme(chain, slots)
    box = list(ratios.box)
    if not ratios.feasible(box):
        return True
    for _ in range(passes):
        moved = False
        for t in range(len(box)):
            low = ratios.lowest(box, t, RATIO_PRECISION)
            high = ratios.highest(box, t, RATIO_PRECISION)
            if low >= high:
                return True
            moved |= np.log(box[t][1] / box[t][0]) - np.log(high / low) > 10 * RATIO_PRECISION
            box[t] = (low, high)
        if not moved:
            return False
    return False


_HIGHS = None


def _phase_one_lp(prog: _Programme):
    """The phase-one programme of :func:`_phase_one` as a HiGHS model (highspy.HighsLp)."""
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


_BANNER_SHOWN = False


def _new_highs():
    """A silent HiGHS model. The first one of a process is made with the C library's standard
    output sent to /dev/null: HiGHS prints its banner there when the first model is made, before
    any option can turn output off (in a notebook it landed in the cell's output)."""
    import os

    import highspy

    global _BANNER_SHOWN
    if _BANNER_SHOWN:
        h = highspy.Highs()
    else:
        sys.stdout.flush()
        saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(null, 1)
            h = highspy.Highs()
        finally:
            os.dup2(saved, 1)
            os.close(saved)
            os.close(null)
        _BANNER_SHOWN = True
    h.setOptionValue("output_flag", False)
    h.setOptionValue("threads", 1)  # thousands of tiny programmes: no thread pool (n = 5's search 2.23 -> 2.03 s an arm)
    return h


def _solved(h):
    import highspy

    if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        raise SolverError(f"the phase-one programme failed: {h.modelStatusToString(h.getModelStatus())}")
    return float(h.getInfo().objective_function_value)


def _phase_one(prog: _Programme):
    """Least total violation of 000 Eqs. (39) with every quantity in its sign box: (value, y),
    y the equations' dual values (a subgradient of the value in the right-hand side).

    Solved by HiGHS through highspy, which scipy's linprog also wraps: called directly it
    costs about 0.6 ms per programme here against 1.7 ms through linprog, and the
    rules-against-physics search solves thousands.
    """
    global _HIGHS
    if _HIGHS is None:
        _HIGHS = _new_highs()
    _HIGHS.passModel(_phase_one_lp(prog))
    _HIGHS.run()
    return _solved(_HIGHS), np.array(_HIGHS.getSolution().row_dual)


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


class _WarmCounts:
    """:func:`_phase_one` of a multiset over the kinds of ``full`` (one copy of each kind's columns),
    kept in one HiGHS model: c copies of a kind are one copy with its quantities' sign box scaled
    by c ([c EPS, c BOUND]: the copies enter the equations only through their sum), an absent kind
    is fixed at 0, and each call changes the column bounds and solves again from the last basis
    (the n = 5 search on one arm: 4.5 s instead of 5.7 s building and solving each multiset's own
    programme)."""

    def __init__(self, full: _Programme):
        self.highs = _new_highs()
        self.highs.passModel(_phase_one_lp(full))
        self.owner = full.owner
        self.lower = np.where(full.signs > 0, EPS, -BOUND)
        self.upper = np.where(full.signs > 0, BOUND, -EPS)
        self.columns = np.arange(len(full.owner), dtype=np.int32)

    def __call__(self, counts: np.ndarray):
        c = np.asarray(counts, dtype=float)[self.owner]
        self.highs.changeColsBounds(len(self.columns), self.columns, self.lower * c, self.upper * c)
        self.highs.run()
        return _solved(self.highs), np.array(self.highs.getSolution().row_dual)


def minimal_relaxed_multisets(chain: Chain, *, max_nodes: int = 200_000) -> list[tuple[SpringSlot, ...]]:
    """Every inclusion-minimal multiset over :func:`alphabet` whose linear relaxation of
    000 Eqs. (39) is feasible, fewest springs first, then in label order.

    Branch and prune on certificates: a multiset C whose relaxation is infeasible has
    a phase-one dual y with value f > 0, and any feasible T containing C must add a
    spring with a quantity of sign s and column c such that s y.c > 0 (since
    0 = f_T >= f - sum over the added quantities of max(s y.c, 0) * BOUND). Branching
    only on those springs, from the empty multiset, level by level, reaches every
    minimal feasible multiset; a node containing a feasible multiset already found is
    not minimal and is dropped.

    :raises SearchExhaustedError: after ``max_nodes`` programmes (the search says so rather
        than returning a partial list)
    """
    _checks.instance("chain", chain, Chain)
    max_nodes = _checks.count("max_nodes", max_nodes, least=1)
    items = alphabet(chain.n)
    kinds = sorted(set(items))
    most = np.array([items.count(k) for k in kinds])
    full = _programme(chain, kinds)
    keys, pos, neg = term_signs(chain, kinds)  # per kind and entry: a positive (pos) / negative (neg) term there
    from springlab.energy.quadratic import gravity_entries

    G = gravity_entries(chain.r, chain.d, chain.m, chain.g)  # 000 Eq. (18): G_1,n = 0 when d_n = 0
    gravity = np.array([key[0] == 1 and G.get(key, 0.0) > 0 for key in keys])
    level: set[tuple[int, ...]] = {tuple([0] * len(kinds))}
    found: list[np.ndarray] = []
    nodes = 0
    warm = _WarmCounts(full)
    while level:
        nxt: set[tuple[int, ...]] = set()
        F = np.array(found) if found else np.zeros((0, len(kinds)), dtype=int)
        for counts in sorted(level):
            c = np.array(counts)
            if len(F) and np.any(np.all(F <= c, axis=1)):
                continue  # contains a feasible multiset: not minimal
            nodes += 1
            if nodes > max_nodes:
                raise SearchExhaustedError(f"the search visited max_nodes = {max_nodes} multisets without finishing; "
                                     "raise max_nodes")
            present = c > 0
            has_pos = gravity | pos[present].any(axis=0)
            has_neg = neg[present].any(axis=0)
            one_signed = np.flatnonzero(has_pos != has_neg)
            if len(one_signed):  # an entry of one sign only: some spring must bring the other
                e = one_signed[0]
                wanted = np.flatnonzero(neg[:, e] if has_pos[e] else pos[:, e])
            else:
                value, y = warm(c)
                if value <= 1e-9:
                    found.append(c)
                    F = np.array(found)
                    continue
                gain = y @ full.A_eq * full.signs  # s y.c per quantity of every kind of spring
                wanted = np.flatnonzero(np.bincount(full.owner, weights=gain > 1e-12, minlength=len(kinds)))
            for idx in wanted:
                if c[idx] < most[idx]:
                    child = list(counts)
                    child[idx] += 1
                    nxt.add(tuple(child))
        level = nxt
    out = [tuple(kinds[idx] for idx in np.flatnonzero(c) for _ in range(c[idx])) for c in found]
    return sorted(out, key=lambda cfg: (len(cfg), _label(cfg)))


def confirm(chain: Chain, slots, *, starts: int = 2, seed=0):
    """Springs with the slots' signs that satisfy 000 Eqs. (39) exactly, or None.

    000 Eqs. (39) are linear in (P, A, B, k) per spring; the coupling P k = A B binds for
    springs spanning three or more joints (for shorter ones k, or a and b, are free to
    meet it). Two searches, each polished by bounded least squares (scipy) on the
    equations and the couplings together:

    1. from vertices of the linear programme (random objectives);
    2. with each long spring's a fixed (A = a k and P = a B are then linear), Nelder-Mead
       on the a's minimises the programme's least violation; a zero there can sit on a
       thin set (an end forced onto a joint, a = -r_i), which the first search misses.

    The springs are rebuilt (k = K, a = A / K, b = B / K; a shorter spring's k from its P)
    and their balance residual (000 Eqs. 39, route 1) checked to 1e-9 of the largest G_1,j.
    """
    _checks.instance("chain", chain, Chain)
    slots = as_slots(slots)
    for found in _searches(chain, slots, starts=starts, seed=seed):
        if found is not None:
            return found
    return None


def _searches(chain: Chain, slots, *, starts: int = 2, seed=0):
    """:func:`confirm`'s two searches as a generator: yields the springs found, or None, after
    the vertex starts and again after the fixed-a starts (a caller may try a proof between them)."""
    if not slots:
        return  # no spring balances an arm with G_1,j > 0
    from scipy.optimize import least_squares, linprog, minimize

    from springlab.energy.quadratic import balance_residual, gravity_entries
    from springlab.model.springs import Spring

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

    def polish(v0):
        v0 = np.clip(v0, lo, hi)
        if len(P):  # SLSQP on the coupling within the equations: fast when it converges
            v0 = minimize(coupling_squared, v0, jac=coupling_gradient, method="SLSQP", bounds=list(zip(lo, hi, strict=True)),
                          constraints=[{"type": "eq", "fun": lambda x: prog.A_eq @ x - prog.b_eq,
                                        "jac": lambda x: prog.A_eq}], options={"maxiter": 300, "ftol": 1e-30},
                          callback=solved).x
        found = springs_of(v0)
        if found is None:
            found = springs_of(newton(v0))
        if found is not None:
            return found
        sol = least_squares(residual, np.clip(v0, lo, hi), jac=residual_jacobian, bounds=(lo, hi), xtol=1e-15,
                            ftol=1e-15, gtol=1e-15, max_nfev=500)
        return springs_of(sol.x)

    def springs_of(v):
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

    for _ in range(starts):
        lp = linprog(rng.normal(size=m), A_eq=prog.A_eq, b_eq=prog.b_eq, bounds=list(zip(lo, hi, strict=True)), method="highs")
        if lp.status != 0:
            return
        found = polish(lp.x)
        if found is not None:
            yield found
            return
    yield None
    if not longs:
        return
    base_rows = prog.A_eq.shape[0]
    cells = [(base_rows + 2 * q + t, y) for q, (Pc, Ac, Bc, Kc) in enumerate(longs) for t, y in enumerate((Kc, Bc))]
    warm = _WarmPhaseOne(with_a(np.zeros(len(longs))), cells)  # rows A - a k = 0, P - a B = 0 per long spring
    signs_a = np.repeat(np.array(long_signs, dtype=float), 2)
    for _ in range(2 * starts):
        res = minimize(lambda la: warm(-signs_a * np.exp(np.repeat(la, 2))), rng.uniform(-3.0, 1.0, len(longs)),
                       method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-14, "maxiter": 400})
        fixed = with_a(res.x)
        rows = fixed.A_eq.shape[0]
        lp = linprog(np.r_[np.zeros(m), np.ones(2 * rows)], A_eq=np.hstack([fixed.A_eq, np.eye(rows), -np.eye(rows)]),
                     b_eq=fixed.b_eq, bounds=list(zip(lo, hi, strict=True)) + [(0, None)] * (2 * rows), method="highs")
        found = polish(lp.x[:m])
        if found is not None:
            yield found
            return
    yield None


def is_balanceable(chain: Chain, slots) -> str:
    """'yes' (a design was found and checked), 'no' (proved: the linear relaxation, the
    relaxation tightened by the coupling's exact consequences, or the bounds on the
    coupled ratios (:func:`coupling_refuted`) leave no solution) or 'undecided' (neither).
    The cheap searches for a design run first, the ratio bounds next, the costly search last."""
    _checks.instance("chain", chain, Chain)
    slots = as_slots(slots)
    slots = list(slots)
    if not relaxation_feasible(chain, slots) or tightened_infeasible(chain, slots):
        return "no"
    searches = _searches(chain, slots)
    if next(searches, None) is not None:  # the vertex starts: most balanceable multisets end here
        return "yes"
    if coupling_refuted(chain, slots):
        return "no"
    return "yes" if any(found is not None for found in searches) else "undecided"


def random_arm(n: int, rng) -> Chain:
    """A generic n-link arm: lengths 0.15-0.45 m, centres of mass 0.2-0.8 of the length,
    masses 0.5-5 kg, g = 9.81 m/s^2."""
    n = _checks.links(n, "n")
    rng = _checks.rng("rng", rng)
    from springlab.model.chain import serial_chain

    rng = np.random.default_rng(rng)
    r = rng.uniform(0.15, 0.45, n - 1)
    return serial_chain(r, r * rng.uniform(0.2, 0.8, n - 1), rng.uniform(0.5, 5.0, n - 1), g=9.81)


def _label(cfg) -> str:
    return " ".join(str(s) for s in sorted(cfg))


@dataclass
class RulesAgainstPhysics:
    """Per n: the rules' configurations and the balanceable multisets, compared (first arm)."""

    n: int
    arms: int
    minimal: list[tuple[SpringSlot, ...]]  # relaxation-minimal and balanceable: inclusion-minimal
    refuted: list[tuple[SpringSlot, ...]]  # relaxation-minimal, proved unbalanceable by the coupling
    undecided: list[tuple[SpringSlot, ...]]  # relaxation-minimal, neither proved nor confirmed
    admitted: list[tuple[SpringSlot, ...]]  # R1-R6's configurations with necessary springs
    admitted_status: dict[str, str]  # per admitted configuration: 'yes', 'no', 'undecided'
    admitted_single_minimal: int  # admitted, balanceable, no single spring removable
    admitted_inclusion_minimal: int  # admitted and inclusion-minimal balanceable
    rejected: dict[str, list[str]]  # minimal balanceable but rejected: label -> violations
    same_on_every_arm: bool
    certificates: dict = field(default_factory=dict)  # per admitted configuration proved unbalanceable: its exact Certificate, or None
    arm: Chain | None = None  # the first arm, on which everything above was decided

    @property
    def exact(self) -> bool:
        """True when the minimal list is complete: nothing refuted or undecided, so every
        balanceable multiset contains one of ``minimal``."""
        return not self.refuted and not self.undecided

    def row(self) -> dict[str, int | str]:
        bad = sum(1 for v in self.admitted_status.values() if v == "no")
        und = sum(1 for v in self.admitted_status.values() if v == "undecided")
        count = str(len(self.minimal)) if self.exact else f">= {len(self.minimal)}"
        return {"n": self.n, "minimal balanceable (inclusion)": count,
                "relaxation-minimal: refuted / undecided": f"{len(self.refuted)} / {len(self.undecided)}",
                "R1-R6 admit": len(self.admitted),
                "admitted, balanceable, no single spring removable": self.admitted_single_minimal,
                "admitted, inclusion-minimal": self.admitted_inclusion_minimal,
                "admitted, not balanceable (proved)": bad,
                "of them, by an exact certificate": sum(c is not None for c in self.certificates.values()),
                "admitted, undecided": und,
                "minimal balanceable, rejected by R1-R6": len(self.rejected),
                "same on every arm": "yes" if self.same_on_every_arm else "no"}


def rules_against_physics(n: int, *, arms: int = 3, seed: int = 0, progress: bool = False) -> RulesAgainstPhysics:
    """Test R1-R6 both ways on ``arms`` random n-link arms (:func:`random_arm`).

    On the first arm: the relaxation-minimal multisets (:func:`minimal_relaxed_multisets`),
    each confirmed by a design, refuted (:func:`tightened_infeasible`, :func:`coupling_refuted`),
    or undecided (:func:`is_balanceable`); the rules' configurations
    (:func:`springlab.design.rules.enumerate_configurations`), each decided likewise with both
    minimality notions, and each proved unbalanceable given its exact certificate where the
    linear relaxation refutes it (:func:`springlab.design.certificates.relaxation_certificate`;
    None for a refutation by the coupling, which has no exact certificate yet). On every arm the relaxation-minimal lists and their refutations by
    :func:`tightened_infeasible` must agree, and every multiset refuted on the first arm must be
    refuted on the others (``same_on_every_arm``).

    A balanceable multiset that contains a refuted one is not relaxation-minimal and is not
    enumerated: with refutations the minimal count is a lower bound (the result's ``exact``).
    """
    n = _checks.links(n, "n")
    arms = _checks.count("arms", arms, least=1)
    seed = _checks.count("seed", seed)
    from tqdm import tqdm

    from springlab.design.rules import enumerate_configurations

    rng = np.random.default_rng(seed)
    chains = [random_arm(n, rng) for _ in range(arms)]
    signature = []
    for c in chains:
        relaxed = minimal_relaxed_multisets(c)
        signature.append(sorted((_label(cfg), tightened_infeasible(c, cfg)) for cfg in relaxed))
        if len(signature) == 1:
            first_relaxed = relaxed
    first = chains[0]
    decided: dict[tuple[SpringSlot, ...], str] = {}  # one decision per multiset: sub-multisets recur

    def decide(cfg) -> str:
        key = tuple(sorted(cfg))
        if key not in decided:
            decided[key] = is_balanceable(first, cfg)
        return decided[key]

    minimal, refuted, undecided = [], [], []
    for cfg in tqdm(first_relaxed, disable=not progress, desc=f"n = {n}, minimal multisets", mininterval=2.0):
        {"yes": minimal, "no": refuted, "undecided": undecided}[decide(cfg)].append(cfg)
    admitted = enumerate_configurations(n)
    status, single, inclusion = {}, 0, 0
    for cfg in tqdm(admitted, disable=not progress, desc=f"n = {n}, R1-R6 configurations", mininterval=2.0):
        st = decide(cfg)
        status[_label(cfg)] = st
        if st != "yes":
            continue
        if all(decide(cfg[:k] + cfg[k + 1:]) == "no" for k in range(len(cfg))):
            single += 1
        if any(sorted(cfg) == sorted(m) for m in minimal):
            inclusion += 1
    from springlab.design.certificates import relaxation_certificate

    certificates = {_label(cfg): relaxation_certificate(first, cfg) for cfg in admitted if status[_label(cfg)] == "no"}
    rejected = {_label(cfg): [str(x) for x in rule_violations(n, cfg)] for cfg in minimal if rule_violations(n, cfg)}
    same = all(sig == signature[0] for sig in signature[1:]) and all(
        tightened_infeasible(c, cfg) or coupling_refuted(c, cfg) for c in chains[1:] for cfg in refuted)
    return RulesAgainstPhysics(n, arms, minimal, refuted, undecided, admitted, status, single, inclusion,
                               rejected, same, certificates, first)


def counts_table(results) -> Table:
    """The per-n rows of :meth:`RulesAgainstPhysics.row` as one table."""
    rows = [r.row() for r in results]
    return Table(list(rows[0]), rows)
