"""Refutations a reader can check: certificates that a spring multiset cannot balance an arm,
verified in exact rational arithmetic (Python's ``fractions``), so that no refutation rests on
floating point.

000 Eqs. (39a-b) are linear in each spring's quantities P = k a b, A = k a, B = k b and k
(000 Eqs. 23a-d): one equation per entry (u, v) of the balance matrix, M x + G t = 0, G the
gravity entries (000 Eq. 18) and t = 1 (written as a variable so that every equation is
homogeneous). A spring's pattern fixes each quantity's sign, so with w = s x (s the signs)
every w must be > 0, and so must t. A spring spanning three or more joints also couples its
quantities: P k = A B, which in the signed variables reads w_P w_K = w_A w_B whatever the
pattern (both sides carry the sign sa sb).

A certificate is a polynomial identity. Multiply each equation eq_e by a factor (1, or one of
the variables w, t) and each coupling q_s = w_P w_K - w_A w_B by a number, and add:

    sum lambda_(e,f) f eq_e  +  sum mu_s q_s  =  sum over monomials of c_m m.

At a solution every eq_e and q_s is zero, so the left side is zero; if every coefficient c_m is
>= 0 and one is > 0, the right side is > 0 at every point with all variables > 0. No solution
exists. Two kinds:

* **relaxation** (degree 1, Stiemke's theorem): factors 1 only, no coupling. It proves that even
  the linear relaxation (the coupling dropped) has no solution of the stated signs; by Stiemke's
  theorem such multipliers exist exactly when that relaxation is infeasible.
* **coupling (degree 2)**: factors w, t and the couplings: a Positivstellensatz certificate of
  degree 2, found by one linear programme over the multipliers. It proves what the relaxation
  cannot, e.g. that the equations force a spring's b = B/k to one length and its b = P/A below it.

The multipliers are found by linear programmes in floating point (scipy's HiGHS), then made
exact: the coefficients the programme leaves at zero are set exactly to zero by projecting the
multipliers, in rational arithmetic, onto those that zero them; :meth:`Certificate.check`
recomputes every coefficient from the arm's own numbers, each float read exactly as the rational
it is.

A certificate also says which springs could break it (:meth:`Certificate.breakers`): adding a
spring adds its variables to the equations, and the certificate survives unless some new
coefficient is negative. A balanceable superset must therefore contain a spring that breaks it,
which keeps a search that branches only on those springs complete.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497

Stiemke, E. (1915). Über positive Lösungen homogener linearer Gleichungen. Mathematische
Annalen 76, 340-342.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from springlab import _checks
from springlab.design.highs import INF, solve
from springlab.design.rules import as_slots
from springlab.design.solve import linear_columns
from springlab.energy.quadratic import gravity_entries
from springlab.errors import SpringlabError
from springlab.model.chain import Chain

ZERO = 1e-9
"""A coefficient of the programme's combination at most this (relative to the largest) is taken to
be exactly zero, and made so by the exact projection."""

GRAVITY = "t"
"""The variable that multiplies the gravity entries (t = 1 at a solution; any t > 0 by homogeneity)."""

KINDS = ("relaxation", "coupling (degree 2)")
_NIL = Fraction(0)
"""The certificate kinds, weakest first."""


def _entries(n: int) -> list[tuple[int, int]]:
    return [(u, v) for u in range(1, n + 1) for v in range(u + 1, n + 1)]


def exact_system(chain: Chain, slots) -> tuple[list, list, dict]:
    """000 Eqs. (39) of the multiset on the arm in rational arithmetic: (columns, entries, gravity).

    ``columns``: per spring quantity that enters an equation, (spring index, 'P' 'A' 'B' or 'k',
    sign, {entry: coefficient}) with the coefficients of 000 Eqs. (23a-d) (P: -1 at (i, j);
    A: -r_v at (i, v); B: r_u at (u, j); k: r_u r_v at (u, v)); ``gravity``: {(1, j): G_1,j}
    (000 Eq. 18). Every float of the arm is read exactly (``Fraction(x)``)."""

    _checks.instance("chain", chain, Chain)
    slots = list(as_slots(slots))
    columns = []
    for idx, (s, cols) in enumerate(zip(slots, linear_columns(chain, slots, exact=True) if slots else [], strict=True)):
        signs = {"P": s.sa * s.sb, "A": s.sa, "B": s.sb, "K": 1}
        for name, coefficients in cols.items():
            if coefficients:
                columns.append((idx, "k" if name == "K" else name, signs[name], coefficients))
    gravity = gravity_entries([Fraction(x) for x in chain.r], [Fraction(x) for x in chain.d],  # 000 Eq. (18)
                              [Fraction(x) for x in chain.m], Fraction(chain.g))
    return columns, _entries(chain.n), gravity


class SignedSystem:
    """One multiset's 000 Eqs. (39) as homogeneous equations in the signed variables, exact and in floats.

    :ivar slots: the multiset
    :ivar variables: (spring index, 'P' 'A' 'B' or 'k') per quantity that enters an equation, then
        :data:`GRAVITY`
    :ivar entries: the entries (u, v), u < v, one equation each
    :ivar rows: per entry, {variable: exact coefficient} (000 Eqs. 23a-d times the quantity's sign;
        G_1,j of 000 Eq. 18 for t)
    :ivar couplings: per spring spanning three or more joints, (its index, its variables P, k, A, B)
    :ivar E: the coefficients as floats, (len(entries), len(variables))
    """

    def __init__(self, chain: Chain, slots):
        self.slots = tuple(as_slots(slots))
        columns, self.entries, gravity = exact_system(chain, self.slots)
        self.variables = [(idx, name) for idx, name, _, _ in columns] + [GRAVITY]
        self.rows = {e: {} for e in self.entries}
        for idx, name, sign, coefficients in columns:
            for key, c in coefficients.items():
                self.rows[key][(idx, name)] = sign * c
        for key, g in gravity.items():
            if g:
                self.rows[key][GRAVITY] = g
        self._finish()

    def _finish(self):
        self.index = {v: c for c, v in enumerate(self.variables)}
        self.couplings = [(idx, ((idx, "P"), (idx, "k"), (idx, "A"), (idx, "B")))
                          for idx, s in enumerate(self.slots) if s.j - s.i >= 3]
        self.E = np.zeros((len(self.entries), len(self.variables)))
        for r, e in enumerate(self.entries):
            for v, c in self.rows[e].items():
                self.E[r, self.index[v]] = float(c)
        self.of_spring: dict[int, list[int]] = {}  # spring index -> its variables' columns
        for c, v in enumerate(self.variables):
            if v != GRAVITY:
                self.of_spring.setdefault(v[0], []).append(c)

    def multiset(self, picks) -> SignedSystem:
        """The system of the multiset whose springs are ``self.slots[k]`` for k in ``picks`` (repeats
        allowed: copies), taken from this one's exact coefficients without recomputing them."""
        out = object.__new__(SignedSystem)
        picks = [int(k) for k in picks]
        out.slots = tuple(self.slots[k] for k in picks)
        out.entries = self.entries
        names = {k: [self.variables[c][1] for c in self.of_spring.get(k, [])] for k in set(picks)}
        out.variables = [(i, name) for i, k in enumerate(picks) for name in names[k]] + [GRAVITY]
        out.rows = {}
        for e, row in self.rows.items():
            new = {(i, name): row[(k, name)] for i, k in enumerate(picks) for name in names[k] if (k, name) in row}
            if GRAVITY in row:
                new[GRAVITY] = row[GRAVITY]
            out.rows[e] = new
        out._finish()
        return out


def _monomial(a, b=None) -> tuple:
    """A monomial as the sorted tuple of its variables (degree 1 or 2)."""
    if b is None:
        return (a,)
    return tuple(sorted((a, b), key=repr))


@dataclass(frozen=True)
class Certificate:
    """A proof that a multiset cannot balance the arm: multipliers of 000 Eqs. (39) and of the
    couplings P k = A B whose combination is a polynomial with every coefficient >= 0, one > 0.

    :ivar slots: the multiset
    :ivar equations: {(entry (u, v), factor): lambda}: the equation of that entry times the factor
        (None for 1, else a variable: (spring index, 'P' 'A' 'B' or 'k') or :data:`GRAVITY`)
    :ivar couplings: {spring index: mu}: that spring's w_P w_K - w_A w_B

    Every multiplier is an exact rational; one left out is 0.
    """

    slots: tuple
    equations: dict
    couplings: dict

    @property
    def kind(self) -> str:
        """'relaxation' (the equations alone, factors 1) or 'coupling (degree 2)'."""
        if not self.couplings and all(f is None for _, f in self.equations):
            return KINDS[0]
        return KINDS[1]

    def polynomial(self, chain: Chain) -> dict:
        """The combination, exactly: {monomial: coefficient} (monomials as sorted tuples of variables)."""
        return _polynomial(SignedSystem(chain, self.slots), self)

    def check(self, chain: Chain) -> bool:
        """True when the certificate proves it, in exact arithmetic: every multiplier a rational,
        every factor a variable of the multiset, every coupling one that binds (a spring spanning
        three or more joints), every coefficient of the combination >= 0 and one of them > 0."""
        values = list(self.equations.values()) + list(self.couplings.values())
        if not values or not all(isinstance(v, Fraction | int) and not isinstance(v, bool) for v in values):
            return False
        system = SignedSystem(chain, self.slots)
        if any(e not in system.rows or (f is not None and f not in system.index) for e, f in self.equations):
            return False
        if not set(self.couplings) <= {idx for idx, _ in system.couplings}:
            return False
        coefficients = list(self.polynomial(chain).values())
        return all(c >= 0 for c in coefficients) and any(c > 0 for c in coefficients)

    def breakers(self, candidates: SignedSystem) -> list[int]:
        """Indices of the springs of ``candidates`` whose addition could break the certificate: some
        monomial of a factor and one of the added spring's variables (or the variable alone) would
        get a negative coefficient. Added springs that break nothing leave it a proof for the larger
        multiset (their own couplings unused), so a balanceable superset must contain one that breaks
        it. Each coefficient is summed in floats and decided there when it is clear of zero by far
        more than the sum's round-off (1e-12 of the sum of its terms' sizes); otherwise exactly."""
        _checks.instance("candidates", candidates, SignedSystem, "SignedSystem(chain, springs)")
        row = {e: r for r, e in enumerate(candidates.entries)}
        by_factor: dict = {}
        for (entry, factor), lam in self.equations.items():
            by_factor.setdefault(factor, []).append((entry, lam))
        negative = np.zeros(len(candidates.variables), dtype=bool)
        E = candidates.E
        for terms in by_factor.values():
            rows = np.array([row[e] for e, _ in terms])
            lam = np.array([float(x) for _, x in terms])
            total = lam @ E[rows]
            size = np.abs(lam) @ np.abs(E[rows])
            negative |= total < -1e-12 * size
            for c in np.flatnonzero((np.abs(total) <= 1e-12 * size) & (size > 0)):
                v = candidates.variables[c]
                negative[c] |= sum(x * candidates.rows[e].get(v, 0) for e, x in terms) < 0
        return [k for k, cols in sorted(candidates.of_spring.items()) if negative[cols].any()]

    def describe(self, chain: Chain) -> str:
        """The refutation in words: which equations are combined, with which factors, and why the
        sum cannot vanish."""
        poly = self.polynomial(chain)
        positive = sorted((_name(self.slots, m) for m, c in poly.items() if c > 0))
        used = sorted({f"({u},{w})" for ((u, w), _), lam in self.equations.items() if lam})
        head = f"{self.kind}: the equations of entries {', '.join(used)} (000 Eqs. 39), each times a rational multiplier"
        if self.kind == KINDS[1]:
            per_spring: dict = {}
            for (_, f), lam in self.equations.items():
                if lam and f is not None and f != GRAVITY:
                    per_spring.setdefault(f[0], set()).add(f[1])
            names = [f"{_and(sorted(q, key='PABk'.index))} of {self.slots[i]}" for i, q in sorted(per_spring.items())]
            if any(f == GRAVITY for (_, f), lam in self.equations.items() if lam):
                names.append("t (the number that multiplies gravity)")
            coupled = ", ".join(f"P k - A B of {self.slots[i]}" for i in sorted(self.couplings))
            head += f" and by one of {', '.join(names)}, plus {coupled or 'no coupling'} times a multiplier of its own"
        shown = ", ".join(positive[:4]) + (", ..." if len(positive) > 4 else "")
        return (f"{head}, add up to a polynomial in the quantities' magnitudes with {len(positive)} positive "
                f"coefficient{'s' if len(positive) > 1 else ''} (on {shown}) and every other one 0 ({len(poly)} in all): "
                "with every quantity of its pattern's sign the sum would be > 0, but the equations make it 0")


def _and(words) -> str:
    """'A', 'A and B', 'A, B and k'."""
    words = list(words)
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]


def _name(slots, monomial) -> str:
    """A monomial in words: 'B of S(1,4)(+,+) * t'."""
    return " * ".join("t" if v == GRAVITY else f"{v[1]} of {slots[v[0]]}" for v in monomial)


# --- finding certificates: a linear programme in floats, then made exact --------------------------

def relaxation_certificate(chain: Chain, slots, *, system: SignedSystem | None = None) -> Certificate | None:
    """The Stiemke certificate that the linear relaxation of 000 Eqs. (39) has no solution with
    every quantity of its sign (module docstring), checked exactly; None when the relaxation has
    a solution (or no exact certificate could be made)."""

    system = system or SignedSystem(chain, slots)
    if not system.slots:
        return None
    E, _ = _scaled_columns(system.E)
    rows = np.maximum(np.abs(E).max(axis=1), 1e-300)
    Er = E / rows[:, None]
    # y with Er^T y >= 0 and their sum = 1 (a box keeps it bounded): every coefficient of y^T E >= 0
    A = np.vstack([Er.T, Er.sum(axis=1)[None, :]])
    out = solve(np.zeros(len(Er)), A, np.r_[np.zeros(Er.shape[1]), 1.0], np.r_[np.full(Er.shape[1], INF), 1.0],
                np.full(len(Er), -1e6), np.full(len(Er), 1e6))
    if out is None:
        return None
    return relaxation_certificate_from(system, out[0] / rows)


def relaxation_certificate_from(system: SignedSystem, y) -> Certificate | None:
    """An exact relaxation certificate of ``system`` from float multipliers ``y`` (one per entry, in
    order, as a linear programme's dual values give them), or None when they do not make one."""
    _checks.instance("system", system, SignedSystem, "SignedSystem(chain, springs)")
    return _exact(system, {(e, None): float(v) for e, v in zip(system.entries, y, strict=True) if v}, {})


def coupling_certificate(chain: Chain, slots, *, system: SignedSystem | None = None,
                         factors: str = "all") -> Certificate | None:
    """A degree-2 certificate (module docstring) that 000 Eqs. (39) with P k = A B have no solution
    with every quantity of its sign, checked exactly, or None when the linear programme finds none.

    The programme has one multiplier per (equation, factor) and per coupling, one row per
    monomial (coefficient >= 0) and one normalising the sum of the coefficients to 1; it minimises
    the sum of |multipliers| so that the certificate uses few of them (and few springs can break it).
    ``factors="coupled"`` offers as factors only the coupled springs' variables and t (a programme a
    third the size, which finds every certificate of the paper-000 enumerations); ``"all"`` every
    variable.
    """
    from scipy.sparse import csc_matrix

    system = system or SignedSystem(chain, slots)
    if not system.slots or not system.couplings:
        return None  # no coupling binds: where the relaxation has a solution no certificate exists
    E, scale = _scaled_columns(system.E)
    ne, m = E.shape
    if factors == "coupled":
        F = np.array(sorted({system.index[v] for _, vs in system.couplings for v in vs} | {m - 1}))
    elif factors == "all":
        F = np.arange(m)
    else:
        raise SpringlabError(f"factors must be 'coupled' or 'all', got {factors!r}")
    nf = len(F)
    e_nz, k_nz = np.nonzero(E)
    f = np.repeat(F, len(e_nz))  # every factor times every term of every equation
    e_all, k_all = np.tile(e_nz, nf), np.tile(k_nz, nf)
    pair = np.minimum(f, k_all) * m + np.maximum(f, k_all)
    cols = e_all * nf + np.repeat(np.arange(nf), len(e_nz))
    vals = np.tile(E[e_nz, k_nz], nf)
    couple_pairs, couple_cols, couple_vals = [], [], []
    for q, (_, (P, K, A, B)) in enumerate(system.couplings):
        ip, ik, ia, ib = (system.index[v] for v in (P, K, A, B))
        couple_pairs += [min(ip, ik) * m + max(ip, ik), min(ia, ib) * m + max(ia, ib)]
        couple_cols += [ne * nf + q] * 2
        couple_vals += [scale[ip] * scale[ik], -scale[ia] * scale[ib]]
    monomials, rows = np.unique(np.r_[pair, couple_pairs], return_inverse=True)
    nv = ne * nf + len(system.couplings)
    # multipliers = plus - minus, both >= 0 (minimise their sum): rows C (x+ - x-) >= 0 and their sum = 1
    r, c, v = rows, np.r_[cols, couple_cols], np.r_[vals, couple_vals]
    total = np.bincount(c, weights=v, minlength=nv)  # the coefficients' sum, per multiplier
    last = np.full(nv, len(monomials))
    every = np.arange(nv)
    A = csc_matrix((np.r_[v, -v, total, -total], (np.r_[r, r, last, last], np.r_[c, c + nv, every, every + nv])),
                   shape=(len(monomials) + 1, 2 * nv))
    low = np.r_[np.zeros(len(monomials)), 1.0]
    up = np.r_[np.full(len(monomials), INF), 1.0]
    out = solve(np.ones(2 * nv), A, low, up, np.zeros(2 * nv), np.full(2 * nv, INF))
    if out is None:
        return None
    res_x = out[0]
    x = res_x[:nv] - res_x[nv:]
    x[np.abs(x) <= 1e-12 * np.abs(x).max()] = 0.0
    equations = {}
    for e in range(ne):
        for j, col in enumerate(F):
            v = x[e * nf + j]
            if v:  # the programme's factor is w_f / scale_f (E_scaled = E * scale): lambda = v / scale_f
                equations[(system.entries[e], system.variables[col])] = float(v / scale[col])
    couplings = {idx: float(x[ne * nf + q]) for q, (idx, _) in enumerate(system.couplings) if x[ne * nf + q]}
    return _exact(system, equations, couplings)


def _scaled_columns(E: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """E with each column divided by its largest |entry|, and the divisors' inverses: E_scaled = E * scale."""
    scale = 1.0 / np.maximum(np.abs(E).max(axis=0), 1e-300)
    return E * scale, scale


def _exact(system: SignedSystem, equations: dict, couplings: dict) -> Certificate | None:
    """An exact certificate near the float multipliers: the coefficients the floats leave within
    :data:`ZERO` of zero (relative to the largest, or to the sum of their terms' sizes) are made
    exactly zero. The multipliers the floats use are replaced by the point of the exact null space
    of those coefficients (a basis by exact row reduction) nearest to them (least squares in floats:
    any rational point of the null space zeroes them exactly). None when the result does not check."""
    keys = list(equations) + [("coupling", idx) for idx in couplings]
    values = np.array([equations[k] for k in equations] + [couplings[idx] for idx in couplings], dtype=float)
    if not keys:
        return None
    columns = [_terms(system, key) for key in keys]  # each multiplier's exact contribution to each monomial
    monomials = list({m for col in columns for m in col})
    at = {m: r for r, m in enumerate(monomials)}
    M = np.zeros((len(monomials), len(keys)))
    for j, col in enumerate(columns):
        for m, c in col.items():
            M[at[m], j] = float(c)
    total, size = M @ values, np.abs(M) @ np.abs(values)
    zero = np.flatnonzero(np.abs(total) <= ZERO * np.maximum(np.abs(total).max(), size))
    Z = [[columns[j].get(monomials[r], _NIL) for j in range(len(keys))] for r in zero]
    basis = _null_space(Z, len(keys))
    if not basis:
        return None
    N = np.array([[float(x) for x in b] for b in basis]).T
    alpha = np.linalg.lstsq(N, values, rcond=None)[0]
    exact = [sum((Fraction(float(a)) * b[j] for a, b in zip(alpha, basis, strict=True) if a), Fraction(0))
             for j in range(len(keys))]
    n_eq = len(equations)
    cert = Certificate(system.slots,
                       {k: x for k, x in zip(keys[:n_eq], exact[:n_eq], strict=True) if x},
                       {k[1]: x for k, x in zip(keys[n_eq:], exact[n_eq:], strict=True) if x})
    return cert if cert.equations and _checks_on(system, cert) else None


def _terms(system: SignedSystem, key) -> dict:
    """What one multiplier multiplies, exactly: {monomial: coefficient}. ``key`` is (entry, factor),
    the entry's equation times the factor (None for 1), or ('coupling', spring index), that spring's
    w_P w_K - w_A w_B."""
    if key[0] == "coupling":
        idx = key[1]
        return {_monomial((idx, "P"), (idx, "k")): Fraction(1), _monomial((idx, "A"), (idx, "B")): Fraction(-1)}
    entry, factor = key
    return {(_monomial(v, factor) if factor is not None else (v,)): c for v, c in system.rows.get(entry, {}).items()}


def _polynomial(system: SignedSystem, cert: Certificate) -> dict:
    """The certificate's combination on a system already built: {monomial: exact coefficient}."""
    poly: dict = {}
    multipliers = [*cert.equations.items(), *((("coupling", idx), mu) for idx, mu in cert.couplings.items())]
    for key, lam in multipliers:
        for m, c in _terms(system, key).items():
            poly[m] = poly.get(m, 0) + lam * c
    return poly


def _checks_on(system: SignedSystem, cert: Certificate) -> bool:
    """:meth:`Certificate.check`'s sign test on a system already built (the arm is the system's)."""
    poly = _polynomial(system, cert)
    return all(c >= 0 for c in poly.values()) and any(c > 0 for c in poly.values())


def sign_certificate(system: SignedSystem, entry, positive: bool) -> Certificate:
    """The relaxation certificate from signs alone: ``entry``'s terms (gravity's included) are all
    positive (``positive``) or all negative, so its equation, times 1 or -1, cannot sum to zero."""
    _checks.instance("system", system, SignedSystem, "SignedSystem(chain, springs)")
    return Certificate(system.slots, {(entry, None): Fraction(1 if positive else -1)}, {})


# --- exact linear algebra over the rationals (small systems: a certificate uses few multipliers) ---

def _rref(rows: list[list[Fraction]]) -> tuple[list[list[Fraction]], list[int]]:
    """Reduced row echelon form of ``rows`` (exact): (the non-zero rows, their pivot columns)."""
    A = [list(r) for r in rows]
    pivots: list[int] = []
    r = 0
    width = len(A[0]) if A else 0
    for c in range(width):
        p = next((i for i in range(r, len(A)) if A[i][c] != 0), None)
        if p is None:
            continue
        A[r], A[p] = A[p], A[r]
        inv = 1 / A[r][c]
        A[r] = [x * inv for x in A[r]]
        for i in range(len(A)):
            if i != r and A[i][c] != 0:
                f = A[i][c]
                A[i] = [a - f * b for a, b in zip(A[i], A[r], strict=True)]
        pivots.append(c)
        r += 1
        if r == len(A):
            break
    return A[:r], pivots


def _null_space(Z: list[list[Fraction]], width: int) -> list[list[Fraction]]:
    """A basis of {v: Z v = 0} (exact), one vector per free column of Z's row echelon form."""
    if not Z:
        return [[Fraction(int(i == j)) for i in range(width)] for j in range(width)]
    R, pivots = _rref(Z)
    free = [c for c in range(width) if c not in pivots]
    basis = []
    for f in free:
        v = [_NIL] * width
        v[f] = Fraction(1)
        for row, p in zip(R, pivots, strict=True):
            v[p] = -row[f]
        basis.append(v)
    return basis
