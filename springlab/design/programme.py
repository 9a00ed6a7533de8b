"""000 Eqs. (39) for a multiset of springs as a linear programme, and the searches for springs that
satisfy them.

Each spring's quantities P = k a b, A = k a, B = k b and k (000 Eqs. 23a-d written linearly,
:func:`springlab.design.solve.linear_columns`) enter the equations linearly; the coupling P k = A B of
a spring spanning three or more joints is the one non-linear condition. :func:`programme` writes the
linear relaxation (the coupling dropped) with each quantity's sign; :class:`WarmPhaseOne` and
:class:`Relaxation` keep its phase-one programme in one HiGHS model and solve it again from the last
basis as coefficients or bounds change; :func:`design_searches` looks for a design that meets the couplings
too, from the programme's centre and vertices (Newton steps, SLSQP, Nelder-Mead and bounded least
squares, in that order).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab.design.certificates import GRAVITY, SignedSystem
from springlab.design.highs import INF, new_model, solve
from springlab.design.rules import SpringSlot
from springlab.design.solve import linear_columns
from springlab.energy.quadratic import balance_residual, gravity_entries
from springlab.errors import SolverError, SpringlabError
from springlab.model.chain import Chain
from springlab.model.springs import Spring

EPS = 1e-3
"""Smallest |quantity| the design search (:func:`~springlab.design.feasibility.confirm`) gives a present spring, in units of the
largest G_1,j (and the mean link length): its starts stay a thousandth of gravity's scale away from
zero (the solver's feasibility tolerance is about 1e-7). It bounds the search only: a verdict rests on
a design found or on an exact certificate, which knows no such bound."""


BOUND = 50.0
"""Largest |quantity| the design search gives a spring, in the same units (a box that keeps its
linear programmes bounded)."""

LEVER_SPAN = 1e6
"""A design the searches find is kept only with every lever |a|, |b| within this factor of the mean link
length, either way. Beyond it a 'design' is a limit, not a solution: a spring's energy k |A - B|^2 is then
about |a| / length times its variation over the poses, so route 2's check in double precision loses the
digits it needs (a spring of a 3e18 m lever and a 3e-17 N/m rate, which an exact certificate proves no
design reaches, passed it with a variation of exactly 0, its own lost to round-off, on one CPU's BLAS
and not on another's)."""


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
class Programme:
    items: list[SpringSlot]
    owner: np.ndarray  # quantity -> item
    signs: np.ndarray
    A_eq: np.ndarray
    b_eq: np.ndarray


def programme(chain: Chain, items) -> Programme:
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
    return Programme(list(items), np.array(owner), np.array(signs, dtype=float), A_eq, b_eq)


def long_columns(prog: Programme, slots) -> list[list[int]]:
    """Per spring spanning three or more joints: its columns (P, A, B, k) in the programme."""
    where: dict[int, list[int]] = {}
    for col, own in enumerate(prog.owner):
        where.setdefault(int(own), []).append(col)
    return [where[idx] for idx, s in enumerate(slots) if s.j - s.i >= 3]


def phase_one_lp(prog: Programme):
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


def new_highs():
    """A silent HiGHS model (:func:`springlab.design.highs.new_model`)."""

    return new_model()


def solved(h):
    import highspy

    if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        raise SolverError(f"the phase-one programme failed: {h.modelStatusToString(h.getModelStatus())}")
    return float(h.getInfo().objective_function_value)


class WarmPhaseOne:
    """:func:`phase_one_lp`'s value for a family of programmes that differ only in a few matrix
    coefficients, kept in one HiGHS model: each call changes those coefficients and solves again
    from the previous optimal basis (a warm start), about 3 times faster than a fresh solve.

    :param prog: the programme with every varying coefficient present (non-zero)
    :param cells: (row, column) of each varying coefficient
    """

    def __init__(self, prog: Programme, cells):
        self.highs = new_highs()
        self.highs.passModel(phase_one_lp(prog))
        self.cells = list(cells)

    def __call__(self, values) -> float:
        for (row, col), value in zip(self.cells, values, strict=True):
            self.highs.changeCoeff(int(row), int(col), float(value))
        self.highs.run()
        return solved(self.highs)


class Relaxation:
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
        lp = phase_one_lp(Programme(list(kinds), self.owner, np.ones(m), Es, np.zeros(rows)))
        lp.col_lower_ = np.concatenate([np.ones(m), np.zeros(2 * rows)])  # homogeneous: [1, inf) is > 0
        lp.col_upper_ = np.full(m + 2 * rows, highspy.kHighsInf)
        self.highs = new_highs()
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
        value = solved(self.highs)
        y = -np.array(self.highs.getSolution().row_dual) * self.row_scale  # reduced costs >= 0 at z = 1
        return value <= 1e-9, y


SLSQP_ITERATIONS = 100
"""Most SLSQP iterations of one quick polish."""


QUICK_STARTS = 6
"""Vertices of the linear programme from which :func:`~springlab.design.feasibility.confirm` polishes quickly (SLSQP, then Newton
steps); the thorough polish (bounded least squares, about 0.1 s a call) comes last."""


def design_searches(chain: Chain, slots, *, starts: int = 2, seed=0):
    """:func:`~springlab.design.feasibility.confirm`'s searches as a generator: yields each design found, and None after the
    central start, after the vertex starts and at the end (checkpoints: a caller may try a proof
    between them, or reject a design and ask for the next)."""
    if not slots:
        return  # no spring balances an arm with G_1,j > 0
    from scipy.optimize import least_squares, minimize

    slots = list(slots)
    prog = programme(chain, slots)
    m = len(prog.signs)
    lo = np.where(prog.signs > 0, EPS, -BOUND)
    hi = np.where(prog.signs > 0, BOUND, -EPS)
    longs = long_columns(prog, slots)
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
        return Programme(prog.items, prog.owner, prog.signs, np.vstack([prog.A_eq, *rows]),
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
        levers = np.abs([x for sp in out for x in (sp.a, sp.b)]) / length
        if not np.all((levers >= 1 / LEVER_SPAN) & (levers <= LEVER_SPAN)):
            return None  # a limit, not a design: route 2 could not check it in double precision
        ok = np.abs(balance_residual(chain, out)).max() <= 1e-9 * scale
        return tuple(out) if ok else None

    # the first start is central: every quantity as far from zero as the equations allow (max t with
    # |x_j| >= t, |x_j| <= BOUND), so its springs are well scaled; then vertices of random objectives
    def centre(p: Programme):  # max t with |x_j| >= t: every quantity as far from zero as p allows
        out = solve(np.r_[np.zeros(m), -1.0], np.block([[p.A_eq, np.zeros((len(p.A_eq), 1))],
                                                           [np.diag(prog.signs), -np.ones((m, 1))]]),
                       np.r_[p.b_eq, np.zeros(m)], np.r_[p.b_eq, np.full(m, np.inf)], np.r_[lo, 0.0], np.r_[hi, BOUND])
        return None if out is None else out[0][:m]

    vertices = [centre(prog)]
    if vertices[0] is None:
        return
    yield settled(vertices[0])
    yield polish(vertices[0], thorough=False)  # None too: the caller may try a proof before the rest
    for _ in range(QUICK_STARTS):  # quick polishes from several vertices, then the thorough one from the first
        lp = solve(rng.normal(size=m), prog.A_eq, prog.b_eq, prog.b_eq, lo, hi)
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
        warm = WarmPhaseOne(with_a(np.zeros(len(longs))), cells)  # rows A - a k = 0, P - a B = 0 per long spring
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
