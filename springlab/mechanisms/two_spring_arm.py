"""The two-spring anthropomorphic arm of Lenzo (2017), paper 004.

A 4-dof arm: a spherical shoulder at O (3 dof) and a revolute elbow (1 dof).
Lenzo's notation: link 0 is the frame, x_0 points up; link 1 (upper arm) has
mass m1, length l1 and its COM at h1 along x_1; link 2 (forearm) has mass m2 and
its COM at h2 along x_2 from the elbow. Two zero-free-length springs::

    k2:  from P = a2 x_0 (on the frame, above O) to Q = l1 x_1 + b2 x_2 (on the forearm)
    k12: from U = b12 x_1 (on the upper arm, b12 from O) to V = l1 x_1 + a12 x_2 (on the forearm)

balance the arm when (004 Eq. 15)::

    m1 g h1 + m2 g l1 - k2 a2 l1 = 0
    m2 g h2 - k2 a2 b2 = 0
    k2 b2 l1 + k12 a12 (l1 - b12) = 0

In paper 000's notation (ground = link 1) these springs are S(1,3) with
(a, b) = (a2, b2) and S(2,3) with (a, b) = (b12 - l1, a12): see :func:`to_chain_springs`.
The elbow axis does not enter: every attachment lies on a link's axis, so the
energy depends on the link directions only.

Units: kg, m, N/m, m/s^2.

References
----------
Lenzo, B. (2017). Gravity balancing of a spatial serial 4-dof arm without auxiliary links
using minimum number of springs. AIMETA 2017.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

from springlab import _checks
from springlab.energy.quadratic import dot_symbol, expand_vectors_dot
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.model.chain import STANDARD_GRAVITY, Chain, serial_chain
from springlab.model.springs import Spring

LAYOUTS = {  # Lenzo Fig. 5: signs of a12, of (b12 - l1), of b2
    "a": (-1, -1, +1),
    "b": (+1, +1, +1),
    "c": (+1, -1, -1),
    "d": (-1, +1, -1),
}
PREFERRED = ("a", "b")
"""Layouts c and d need h2 < 0 and may make spring k2 cross link 1; d extends both
links. Lenzo chooses b: layout a's extension of the forearm behind the elbow may
reduce the shoulder's range."""


@dataclass(frozen=True)
class Arm:
    """Lenzo's arm: masses m1, m2 (kg), upper-arm length l1 (m), COM distances h1
    (from O along x_1, > 0) and h2 (from the elbow along x_2, may be negative), g (m/s^2)."""

    m1: float
    m2: float
    l1: float
    h1: float
    h2: float
    g: float = STANDARD_GRAVITY

    def __post_init__(self):
        for name in ("m1", "m2", "l1", "g"):
            _checks.positive(name, getattr(self, name))
        if not (np.isfinite(self.h1) and self.h1 > 0):
            raise SpringlabError(f"h1 must be > 0 (the paper assumes the upper arm's COM beyond O), got {self.h1}")
        if not (np.isfinite(self.h2) and self.h2 != 0):
            raise SpringlabError(f"h2 must be finite and nonzero, got {self.h2}")

    def chain(self, forearm_length: float, elbow_axis=(0.0, 0.0, 1.0)) -> Chain:
        """The arm as a springlab chain in 000's numbering (ground = link 1): a
        spherical shoulder and a revolute elbow about ``elbow_axis`` (in the upper
        arm's frame)."""
        return serial_chain([self.l1, forearm_length], [self.h1, self.h2], [self.m1, self.m2], g=self.g,
                            joints=["spherical", elbow_axis], com_off_link=True)


@dataclass(frozen=True)
class TwoSpringDesign:
    """k2 (N/m), a2, b2 (m); k12 (N/m), a12, b12 (m); and the layout letter."""

    k2: float
    a2: float
    b2: float
    k12: float
    a12: float
    b12: float
    layout: str

    def __post_init__(self):
        for name in ("k2", "k12"):
            object.__setattr__(self, name, _checks.positive(name, getattr(self, name), unit="N/m"))
        for name in ("a2", "b2", "a12", "b12"):
            object.__setattr__(self, name, _checks.finite(name, getattr(self, name), "m"))


def layout_of(a12: float, b12: float, l1: float, b2: float) -> str:
    """The letter of Fig. 5 for the signs of a12, b12 - l1 and b2."""
    signs = (int(np.sign(a12)), int(np.sign(b12 - l1)), int(np.sign(b2)))
    for letter, pattern in LAYOUTS.items():
        if signs == pattern:
            return letter
    raise SpringlabError(f"a12 = {a12}, b12 - l1 = {b12 - l1}, b2 = {b2} match no layout of Fig. 5")


def energy_symbols():
    """sympy symbols of Lenzo's 004 Eqs. (11)-(15)."""
    names = "m1 m2 l1 h1 h2 g k2 a2 b2 k12 a12 b12 k1 a1 b1"
    return dict(zip(names.split(), sp.symbols(names, real=True), strict=True))


def derived_conditions(*, k1: bool = False) -> dict[str, sp.Expr]:
    """004 Eq. (15) derived from the geometry: the coefficients of x1.x0, x2.x0 and x1.x2
    in the total energy E_g + E_s (004 Eqs. 11-13 without spring k1), which must vanish; with ``k1``,
    Fig. 4b's third spring k1 from a1 x_0 on the frame to b1 x_1 on the upper arm kept (004 Eq. 14)."""
    s = energy_symbols()
    x0, x1, x2 = 0, 1, 2
    com1 = {x1: s["h1"]}
    com2 = {x1: s["l1"], x2: s["h2"]}
    gravity = s["m1"] * s["g"] * expand_vectors_dot(com1, {x0: 1}) + s["m2"] * s["g"] * expand_vectors_dot(com2, {x0: 1})
    k2_vec = {x0: s["a2"], x1: -s["l1"], x2: -s["b2"]}  # QP = a2 x0 - (l1 x1 + b2 x2)
    k12_vec = {x1: s["l1"] - s["b12"], x2: s["a12"]}  # UV = (l1 - b12) x1 + a12 x2
    energy = gravity + s["k2"] / 2 * expand_vectors_dot(k2_vec, k2_vec) + s["k12"] / 2 * expand_vectors_dot(k12_vec, k12_vec)
    if k1:
        k1_vec = {x0: s["a1"], x1: -s["b1"]}  # from b1 x_1 to a1 x_0
        energy += s["k1"] / 2 * expand_vectors_dot(k1_vec, k1_vec)
    energy = sp.expand(energy)
    return {name: sp.expand(energy.coeff(dot_symbol(*pair)))
            for name, pair in (("x1.x0", (x0, x1)), ("x2.x0", (x0, x2)), ("x1.x2", (x1, x2)))}


def _one_link_symbols():
    """sympy symbols of 004 Eqs. (1)-(7): m, g, h, k, a, b."""
    return sp.symbols("m g h k a b", real=True)


def _two_link_symbols():
    """sympy symbols of 004 Eqs. (8)-(10): m1, m2, g, h1, h2, l1, k1, k2, a1, b1, a2, b2."""
    return sp.symbols("m1 m2 g h1 h2 l1 k1 k2 a1 b1 a2 b2", real=True)


def one_link_condition() -> tuple[sp.Expr, sp.Expr]:
    """004 Eqs. (1)-(7) derived: one link (mass m, COM h along x_1) and one zero-free-length spring k
    from P = a x_0 to Q = b x_1. Returns the total energy and its coefficient of x_1.x_0, which must
    vanish (004 Eq. 7: k a b = m g h)."""
    m, g, h, k, a, b = _one_link_symbols()
    energy = sp.expand(m * g * h * expand_vectors_dot({1: 1}, {0: 1})  # 004 Eq. (4)
                       + k / 2 * expand_vectors_dot({0: a, 1: -b}, {0: a, 1: -b}))  # 004 Eq. (5)
    return energy, energy.coeff(dot_symbol(0, 1))  # 004 Eq. (6)


def printed_eq7() -> sp.Expr:
    """004 Eq. (7) as printed, typed in: m g h - k a b (= 0)."""
    m, g, h, k, a, b = _one_link_symbols()
    return m * g * h - k * a * b  # 004 Eq. (7)


def two_link_conditions() -> list[sp.Expr]:
    """004 Eqs. (8)-(10) derived: two links, spring k1 from a1 x_0 to b1 x_1 and, through the
    parallelogram of Fig. 2, spring k2 from a2 x_0 to b2 x_2. The coefficients of x_1.x_0 and
    x_2.x_0 in the total energy, which must vanish (004 Eq. 10)."""
    m1, m2, g, h1, h2, l1, k1, k2, a1, b1, a2, b2 = _two_link_symbols()
    energy = sp.expand(m1 * g * expand_vectors_dot({1: h1}, {0: 1})
                       + m2 * g * expand_vectors_dot({1: l1, 2: h2}, {0: 1})
                       + k1 / 2 * expand_vectors_dot({0: a1, 1: -b1}, {0: a1, 1: -b1})
                       + k2 / 2 * expand_vectors_dot({0: a2, 2: -b2}, {0: a2, 2: -b2}))
    return [energy.coeff(dot_symbol(0, j)) for j in (1, 2)]


def printed_eq10() -> list[sp.Expr]:
    """004 Eq. (10) as printed, typed in (each = 0)."""
    m1, m2, g, h1, h2, l1, k1, k2, a1, b1, a2, b2 = _two_link_symbols()
    return [m1 * g * h1 + m2 * g * l1 - k1 * a1 * b1, m2 * g * h2 - k2 * a2 * b2]  # 004 Eq. (10)


def condition_latex(key: str, derived: sp.Expr, difference: sp.Expr) -> str:
    """One condition of 004 Eq. (15) in LaTeX: its unit-vector product ('x1.x0' as x̂_1·x̂_0), the
    derived coefficient = 0, and the printed form minus the derived one."""
    product = key.replace("x", r"\hat x_")
    return (rf"{product}:\quad {sp.latex(derived)} = 0 \quad"
            rf"(\text{{printed minus derived}}: {sp.latex(difference)})")


def rates_without_k12() -> list[dict]:
    """Fig. 4a's arm, springs k1 and k2 without k12: the rates k1, k2 and the point b2 that would
    balance it (004 Eq. 14 with k12 = 0). Empty: none do (x1.x2 asks b2 = 0, then x2.x0 fails)."""
    s = energy_symbols()
    kept = derived_conditions(k1=True)
    return sp.solve([v.subs(s["k12"], 0) for v in kept.values()], [s["k1"], s["k2"], s["b2"]], dict=True)


def printed_eq14() -> dict[str, sp.Expr]:
    """004 Eq. (14) as printed, typed in: the coefficients with Fig. 4b's three springs k1, k2, k12."""
    s = energy_symbols()
    return {"x1.x0": s["m1"] * s["g"] * s["h1"] + s["m2"] * s["g"] * s["l1"] - s["k1"] * s["a1"] * s["b1"]
            - s["k2"] * s["a2"] * s["l1"],  # 004 Eq. (14)
            "x2.x0": s["m2"] * s["g"] * s["h2"] - s["k2"] * s["a2"] * s["b2"],
            "x1.x2": s["k2"] * s["b2"] * s["l1"] + s["k12"] * s["a12"] * (s["l1"] - s["b12"])}


def printed_eq15() -> dict[str, sp.Expr]:
    """004 Eq. (15) as printed, typed in."""
    s = energy_symbols()
    return {"x1.x0": s["m1"] * s["g"] * s["h1"] + s["m2"] * s["g"] * s["l1"] - s["k2"] * s["a2"] * s["l1"],
            "x2.x0": s["m2"] * s["g"] * s["h2"] - s["k2"] * s["a2"] * s["b2"],
            "x1.x2": s["k2"] * s["b2"] * s["l1"] + s["k12"] * s["a12"] * (s["l1"] - s["b12"])}


def solve(arm: Arm, *, a2: float, a12: float, b12: float, layout: str | None = None) -> TwoSpringDesign:
    """Solve 004 Eq. (15) for k2, b2 and k12 given the free choices a2, a12, b12 (m).

    b2 = m2 h2 l1 / (m1 h1 + m2 l1) is fixed by the arm; its sign is h2's.

    :param layout: optional letter the design must have
    :raises UnbalanceableError: a2 <= 0 (the frame point must lie above O),
        a layout the arm cannot have (c and d need h2 < 0, a and b need h2 > 0),
        free choices of another layout, or b12 = l1 or a12 = 0 (spring k12 cannot act)
    """
    _checks.instance("arm", arm, Arm)
    a2, a12, b12 = (_checks.finite(name, v, "m") for name, v in (("a2", a2), ("a12", a12), ("b12", b12)))
    if layout is not None and layout not in LAYOUTS:
        raise SpringlabError(f"layout must be one of {tuple(LAYOUTS)}, got {layout!r}")
    if not a2 > 0:
        raise UnbalanceableError(
            f"a2 = {a2} m: the frame attachment of k2 must lie above the shoulder (a2 > 0), or k2 pulls the arm down")
    if layout is not None and np.sign(arm.h2) != LAYOUTS[layout][2]:
        need = "h2 < 0" if LAYOUTS[layout][2] < 0 else "h2 > 0"
        raise UnbalanceableError(f"layout {layout} needs {need}; this arm has h2 = {arm.h2} m")
    if a12 == 0 or b12 == arm.l1 or not (np.isfinite(a12) and np.isfinite(b12)):
        raise UnbalanceableError(f"a12 = {a12} m, b12 = {b12} m: spring k12 needs a12 != 0 and b12 != l1")
    k2a2 = arm.g * (arm.m1 * arm.h1 + arm.m2 * arm.l1) / arm.l1  # 004 Eq. (15), first line
    k2 = k2a2 / a2
    b2 = arm.m2 * arm.g * arm.h2 / k2a2  # second line
    k12 = k2 * b2 * arm.l1 / (a12 * (b12 - arm.l1))  # third line
    if k12 <= 0:
        raise UnbalanceableError(
            f"k12 = {k12:.6g} N/m < 0: with h2 = {arm.h2} m, a12 (b12 - l1) must have h2's sign "
            f"(layouts {'a, b' if arm.h2 > 0 else 'c, d'})")
    letter = layout_of(a12, b12, arm.l1, b2)
    if layout is not None and letter != layout:
        raise UnbalanceableError(f"these free choices give layout {letter}, not {layout}")
    return TwoSpringDesign(k2, a2, b2, k12, a12, b12, letter)


def to_chain_springs(arm: Arm, design: TwoSpringDesign) -> tuple[Spring, Spring]:
    """The design as springlab springs in 000's numbering: S(1,3) and S(2,3)."""
    _checks.instance("arm", arm, Arm)
    _checks.instance("design", design, TwoSpringDesign)
    return (Spring(1, 3, a=design.a2, b=design.b2, k=design.k2),
            Spring(2, 3, a=design.b12 - arm.l1, b=design.a12, k=design.k12))
