"""Data of Zhang, Arakelian (2023), *Design and Synthesis of the Gravity Compensator
with a Non-zero Length Spring* (paper 002). Section V's examples, as printed.

SI units: N, m, N/m, J, rad (the paper prints degrees, converted here).

References
----------
Zhang, Y., Arakelian, V. (2023). Design and Synthesis of the Gravity Compensator with a Non-zero
Length Spring.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

from springlab.mechanisms.dyad.model import Compensator, Dyad
from springlab.tables import Table

K, L0, G, S = 1000.0, 1.0, 75.0, 0.84  # k (N/m), l0 (m), G (N), s (m): Section V A and B


def compensator() -> Compensator:
    return Compensator(G=G, s=S, k=K, l0=L0)


EXAMPLE_A_POSITIONS = np.radians([30.0, 60.0, 120.0])  # Section V.A
EXAMPLE_B_POSITIONS = {
    # "n = 120 positions between 30 deg and 150 deg, i.e., with a step of one degree":
    # 120 positions and a 1 deg step over 30-150 cannot both hold. The step gives 121 (used);
    # the other readings are kept for comparison.
    "1 deg steps, 30-150 deg (121)": np.radians(np.arange(30.0, 151.0, 1.0)),
    "120 evenly spaced, 30-150 deg": np.radians(np.linspace(30.0, 150.0, 120)),
    "1 deg steps, 30-149 deg": np.radians(np.arange(30.0, 150.0, 1.0)),
    "1 deg steps, 31-150 deg": np.radians(np.arange(31.0, 151.0, 1.0)),
}
WORKING_RANGE = np.radians([30.0, 150.0])  # the range Figs. 2-3 and the optimiser cover

# Printed results: (value, printed decimals).
PRINTED = {
    "A": {"C": (184.0, 0), "r": (0.132, 3), "l": (0.526, 3), "beta_deg": (-0.662, 3),
          "max_residual": (2.92, 2), "reduction_pct_section_v": (95.37, 2), "reduction_pct_conclusion": (97.8, 1)},
    "B": {"C": (195.0, 0), "r": (0.125, 3), "l": (0.502, 3), "beta_deg": (0.08, 2),
          "max_residual": (1.87, 2), "reduction_pct_section_v": (97.03, 2), "reduction_pct_conclusion": (98.6, 1)},
}
MAX_GRAVITY_MOMENT = (63.0, 0)  # "reduced from 63 Nm" (= G s)


def printed_dyad(example: str) -> Dyad:
    p = PRINTED[example]
    return Dyad(p["r"][0], p["l"][0], np.radians(p["beta_deg"][0]))


def inputs() -> Table:
    """Section V's inputs as the paper prints them: the spring, the load, the prescribed positions.

    >>> print(inputs())  # doctest: +ELLIPSIS
    | input | value | where |
    |---|---|---|
    | spring rate k | 1000 N/m | Section V, examples A and B |
    ...
    """
    return Table(["input", "value", "where"], [
        ["spring rate k", f"{K:g} N/m", "Section V, examples A and B"],
        ["spring free length l0", f"{L0:g} m", "Section V, examples A and B"],
        ["load G", f"{G:g} N", "Section V, examples A and B"],
        ["distance s of the load from the pivot", f"{S:g} m", "Section V, examples A and B"],
        ["prescribed positions, example A", ", ".join(f"{np.degrees(a):g}°" for a in EXAMPLE_A_POSITIONS),
         "Section V.A"],
        ["prescribed positions, example B", "n = 120 positions between 30° and 150°, a step of one degree",
         "Section V.B (quoted: 120 positions and a 1° step cannot both hold)"],
    ])


@dataclass(frozen=True)
class ClosureForms:
    """The dyad's loop closure and the paper's restatements of it, in sympy: ``closure`` is
    |B - A|^2 - l^2 with u = phi - beta; ``printed`` maps 002's equation numbers 8-11, 15-16 and 21-23 to
    each as printed (each = 0); ``z`` is 002 Eqs. (12)-(14)'s substitution; ``eq24`` the slider height y."""

    r: sp.Symbol
    length: sp.Symbol  # l, the rod
    beta: sp.Symbol
    phi: sp.Symbol
    y: sp.Symbol
    closure: sp.Expr
    printed: dict
    z: dict
    eq24: sp.Expr


def closure_forms() -> ClosureForms:
    """002 Eqs. (8)-(16) and (21)-(24) as printed, typed in, beside the loop closure they restate."""
    r, ell, beta, phi, y, z1, z2, z3 = sp.symbols("r l beta varphi y z_1:4", real=True)
    u, cos, sin = phi - beta, sp.cos, sp.sin
    closure = (r * sin(u)) ** 2 + (y - r * cos(u)) ** 2 - ell**2  # |B - A|^2 - l^2
    printed = {
        8: (y - r * cos(u)) ** 2 + r**2 * sin(u) ** 2 - ell**2,  # 002 Eq. (8)
        9: y**2 - 2 * y * r * cos(u) + r**2 - ell**2,  # 002 Eq. (9)
        10: y**2 - 2 * y * r * (cos(phi) * cos(beta) + sin(phi) * sin(beta)) - (ell**2 - r**2),  # 002 Eq. (10)
        11: y**2 - 2 * y * r * cos(phi) * cos(beta) - 2 * y * r * sin(phi) * sin(beta) - (ell**2 - r**2),  # 002 Eq. (11)
        15: y**2 - 2 * y * cos(phi) * z1 - 2 * y * sin(phi) * z2 - z3,  # 002 Eq. (15)
        16: -(2 * y * cos(phi) * z1 + 2 * y * sin(phi) * z2 + z3 - y**2),  # 002 Eq. (16)
        21: r**2 + y**2 - ell**2 - 2 * r * y * cos(u),  # 002 Eq. (21)
        22: y**2 - 2 * r * y * cos(u) + r**2 * (cos(u) ** 2 + sin(u) ** 2) - ell**2,  # 002 Eq. (22)
        23: (y - r * cos(u)) ** 2 - (ell**2 - r**2 * sin(u) ** 2),  # 002 Eq. (23)
    }
    z = {z1: r * cos(beta), z2: r * sin(beta), z3: ell**2 - r**2}  # 002 Eqs. (12)-(14)
    eq24 = r * cos(u) + sp.sqrt(ell**2 - r**2 * sin(u) ** 2)  # 002 Eq. (24)
    return ClosureForms(r, ell, beta, phi, y, closure, printed, z, eq24)


def example_b_table(fits: dict) -> Table:
    """Example B's dyad for each reading of its positions, {label: (C (J), Dyad)}, above the printed one."""
    rows = [(k, f"{c:.3f}", f"{d.r:.5f}", f"{d.l:.5f}", f"{np.degrees(d.beta):.4f}") for k, (c, d) in fits.items()]
    printed = [f"{PRINTED['B'][k][0]:.{PRINTED['B'][k][1]}f}" for k in ("C", "r", "l", "beta_deg")]
    return Table(["positions", "C (J)", "r (m)", "l (m)", "beta (deg)"], rows + [("**printed**", *printed)])
