"""Refutations a reader can check: certificates that a spring multiset cannot balance an arm,
verified in exact rational arithmetic (Python's ``fractions``), so that no refutation rests on
floating point.

000 Eqs. (39a-b) are linear in each spring's quantities P = k a b, A = k a, B = k b and k
(000 Eqs. 23a-d): one equation per entry (u, v) of the balance matrix, M x + G = 0, G the
gravity entries (000 Eq. 18). A spring's pattern fixes each quantity's sign, so with
w = s x (s the signs) every w must be > 0. The **linear relaxation** drops the coupling
P k = A B (which binds only for springs spanning three or more joints); where it has no
solution, neither has the multiset.

**Relaxation certificate (Stiemke).** Homogenised, the relaxation asks for z = (w, t) > 0 with
[M S, G] z = 0. By Stiemke's theorem there is none exactly when some multipliers y of the
equations make every coefficient of y^T [M S, G] >= 0, not all zero: the combination
y^T (M S w + G t) = 0 then sums non-negative terms, one of them positive. The certificate is
y (one rational per entry of the balance matrix); :meth:`Certificate.check` recomputes the
coefficients from the arm's own numbers, each float read exactly as the rational it is, and
checks the signs exactly.

The multipliers are found by a linear programme in floating point (scipy's HiGHS), then made
exact: the coefficients the programme leaves at zero are set exactly to zero by projecting y,
in rational arithmetic (sympy), onto the multipliers that zero them.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from springlab import _checks
from springlab.design.rules import as_slots
from springlab.energy.quadratic import gravity_entries
from springlab.model.chain import Chain

ZERO = 1e-9
"""A coefficient of the programme's combination at most this (relative to the largest) is taken to
be exactly zero, and made so by the exact projection."""


def _entries(n: int) -> list[tuple[int, int]]:
    return [(u, v) for u in range(1, n + 1) for v in range(u + 1, n + 1)]


def exact_system(chain: Chain, slots) -> tuple[list, list, dict]:
    """000 Eqs. (39) of the multiset on the arm in rational arithmetic: (columns, entries, gravity).

    ``columns``: per spring quantity that enters an equation, (spring index, 'P' 'A' 'B' or 'k',
    sign, {entry: coefficient}) with the coefficients of 000 Eqs. (23a-d) (P: -1 at (i, j);
    A: -r_v at (i, v); B: r_u at (u, j); k: r_u r_v at (u, v)); ``gravity``: {(1, j): G_1,j}
    (000 Eq. 18). Every float of the arm is read exactly (``Fraction(x)``)."""
    from springlab.design.solve import linear_columns

    _checks.instance("chain", chain, Chain)
    slots = list(as_slots(slots))
    columns = []
    for idx, (s, cols) in enumerate(zip(slots, linear_columns(chain, slots, exact=True), strict=True)):
        signs = {"P": s.sa * s.sb, "A": s.sa, "B": s.sb, "K": 1}
        for name, coefficients in cols.items():
            if coefficients:
                columns.append((idx, "k" if name == "K" else name, signs[name], coefficients))
    gravity = gravity_entries([Fraction(x) for x in chain.r], [Fraction(x) for x in chain.d],  # 000 Eq. (18)
                              [Fraction(x) for x in chain.m], Fraction(chain.g))
    return columns, _entries(chain.n), gravity


@dataclass(frozen=True)
class Certificate:
    """A proof that a multiset cannot balance the arm: multipliers of 000 Eqs. (39), one per entry.

    :ivar slots: the multiset
    :ivar kind: 'relaxation (Stiemke)'
    :ivar multipliers: {entry (u, v): y} as exact rationals (entries left out are 0)
    """

    slots: tuple
    kind: str
    multipliers: dict

    def coefficients(self, chain: Chain) -> tuple:
        """The combination y^T [M S, G], exactly: per quantity (spring index, name, coefficient),
        and gravity's."""
        columns, _, gravity = exact_system(chain, self.slots)
        y = self.multipliers
        per = [(idx, name, sign * sum(y.get(key, 0) * c for key, c in coefficients.items()))
               for idx, name, sign, coefficients in columns]
        return per, sum(y.get(key, 0) * g for key, g in gravity.items())

    def check(self, chain: Chain) -> bool:
        """True when the certificate proves it, in exact arithmetic: every coefficient of the
        combination >= 0 and one of them > 0."""
        if not all(isinstance(v, Fraction | int) for v in self.multipliers.values()):
            return False
        per, g = self.coefficients(chain)
        values = [c for _, _, c in per] + [g]
        return all(v >= 0 for v in values) and any(v > 0 for v in values)

    def describe(self, chain: Chain) -> str:
        """The refutation in words: the combination of the equations and the signs that make it impossible."""
        per, g = self.coefficients(chain)
        used = ", ".join(f"{float(v):+.4g} x ({u},{w})" for (u, w), v in sorted(self.multipliers.items()) if v)
        positive = [f"{name} of {self.slots[idx]}" for idx, name, c in per if c > 0]
        return (f"{self.kind}: the equations of entries {used} add up to a sum of the springs' quantities, each "
                f"times a coefficient >= 0 in its sign, plus gravity times {float(g):.4g} >= 0; "
                + (f"{', '.join(positive)} and gravity" if g > 0 and positive else
                   ", ".join(positive) if positive else "gravity")
                + " enter with a positive coefficient, so the sum cannot be zero with every quantity of its sign")


def relaxation_certificate(chain: Chain, slots) -> Certificate | None:
    """The Stiemke certificate that the linear relaxation of 000 Eqs. (39) has no solution with
    every quantity of its sign (module docstring), checked exactly; None when the relaxation has
    a solution (or no exact certificate could be made)."""
    from scipy.optimize import linprog

    slots = tuple(as_slots(slots))
    columns, entries, gravity = exact_system(chain, slots)
    row = {key: i for i, key in enumerate(entries)}
    # the combination's coefficients as rows of C (one per quantity, then gravity), C y
    C = np.zeros((len(columns) + 1, len(entries)))
    for q, (_, _, sign, coefficients) in enumerate(columns):
        for key, c in coefficients.items():
            C[q, row[key]] = sign * float(c)
    for key, g in gravity.items():
        C[-1, row[key]] = float(g)
    scale = np.maximum(np.abs(C).max(axis=1, keepdims=True), 1e-300)
    Cn = C / scale
    # find y with Cn y >= 0 and sum(Cn y) = 1 (free y in a box: the programme stays bounded)
    res = linprog(np.zeros(len(entries)), A_ub=-Cn, b_ub=np.zeros(len(Cn)), A_eq=Cn.sum(axis=0, keepdims=True),
                  b_eq=[1.0], bounds=[(-1e6, 1e6)] * len(entries), method="highs")
    if res.status != 0:
        return None
    y = res.x
    values = Cn @ y
    zero = np.flatnonzero(np.abs(values) <= ZERO * max(1.0, float(np.max(np.abs(values)))))
    exact = _project(y, [_exact_row(columns, gravity, entries, q) for q in zero])
    cert = Certificate(slots, "relaxation (Stiemke)", {key: v for key, v in zip(entries, exact, strict=True) if v})
    return cert if cert.check(chain) else None


def _exact_row(columns, gravity, entries, q) -> list[Fraction]:
    """Row q of the combination's matrix (a quantity's coefficients, or gravity's) in exact rationals."""
    if q < len(columns):
        _, _, sign, coefficients = columns[q]
        return [sign * coefficients.get(key, Fraction(0)) for key in entries]
    return [gravity.get(key, Fraction(0)) for key in entries]


def _project(y, rows) -> list[Fraction]:
    """y (floats, read exactly) projected in rational arithmetic onto {y: row . y = 0 for every row}."""
    import sympy

    y0 = sympy.Matrix([sympy.Rational(Fraction(float(v)).numerator, Fraction(float(v)).denominator) for v in y])
    if rows:
        R = sympy.Matrix([[sympy.Rational(c.numerator, c.denominator) for c in r] for r in rows])
        _, pivots = R.T.rref()  # independent rows
        R = R[list(pivots), :]
        if R.rows:
            y0 = y0 - R.T * (R * R.T).LUsolve(R * y0)
    return [Fraction(int(v.p), int(v.q)) for v in y0]
