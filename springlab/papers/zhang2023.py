"""Data of Zhang, Arakelian (2023), *Design and Synthesis of the Gravity Compensator
with a Non-zero Length Spring* (paper 002). Section V's examples, as printed.

SI units: N, m, N/m, J, rad (the paper prints degrees, converted here).
"""

from __future__ import annotations

import numpy as np

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
