"""Data for Lenzo (2017), *Gravity balancing of a spatial serial 4-dof arm without
auxiliary links using minimum number of springs*, AIMETA 2017 (paper 004).

The paper gives no numerical example. The arm below is illustrative, of the size
of an adult human arm (upper arm 0.30 m, forearm and hand 0.35 m; masses and COM
positions of the order of the usual anthropometric tables); the free choices
are ours. SI units.

References
----------
Lenzo, B. (2017). Gravity balancing of a spatial serial 4-dof arm without auxiliary links
using minimum number of springs. AIMETA 2017.
"""

from __future__ import annotations

from springlab.design import rules
from springlab.design.solve import SpringSpec, solve_design
from springlab.mechanisms.two_spring_arm import Arm, TwoSpringDesign, solve, to_chain_springs
from springlab.tables import Table

FOREARM_LENGTH = 0.35  # m, for drawing and simulation (the balance does not depend on it)

ARM = Arm(m1=2.0, m2=1.5, l1=0.30, h1=0.13, h2=0.18, g=9.81)
"""Illustrative human-sized arm: COM of the forearm and hand beyond the elbow (h2 > 0)."""

ARM_COUNTERMASS = Arm(m1=2.0, m2=1.5, l1=0.30, h1=0.13, h2=-0.05, g=9.81)
"""The same arm with a counter-mass on the forearm bringing its COM behind the elbow
(h2 < 0), as layouts c and d need."""

A2 = 0.15  # m, the frame attachment of k2 above the shoulder (free choice, all layouts)
FREE_CHOICES = {  # (a12, b12) in m per layout (our choices, of Fig. 5's sign patterns)
    "a": (-0.05, 0.20),
    "b": (0.06, 0.40),
    "c": (0.06, 0.20),
    "d": (-0.05, 0.40),
}


def designs() -> dict[str, tuple[Arm, TwoSpringDesign]]:
    """Each layout of Fig. 5 solved from 004 Eq. (15) with our free choices: layouts a and b on
    :data:`ARM`, c and d on :data:`ARM_COUNTERMASS`; {letter: (arm, design)}."""
    out = {}
    for layout, (a12, b12) in FREE_CHOICES.items():
        arm = ARM if layout in ("a", "b") else ARM_COUNTERMASS
        out[layout] = (arm, solve(arm, a2=A2, a12=a12, b12=b12, layout=layout))
    return out


def design_table(designs: dict[str, tuple[Arm, TwoSpringDesign]]) -> Table:
    """The layouts' springs: h2, k2, a2, b2, k12, a12, b12 (m and N/m), a row per layout."""
    return Table(["layout", "h2 (m)", "k2 (N/m)", "a2 (m)", "b2 (m)", "k12 (N/m)", "a12 (m)", "b12 (m)"],
                 [(letter, f"{arm.h2:g}", f"{d.k2:.2f}", f"{d.a2:.3f}", f"{d.b2:.4f}", f"{d.k12:.2f}",
                   f"{d.a12:.3f}", f"{d.b12:.3f}") for letter, (arm, d) in designs.items()])


def enumeration_table(designs: dict[str, tuple[Arm, TwoSpringDesign]]) -> tuple[Table, list[float]]:
    """Each layout's springs in paper 000's numbering, and 000's verdict on them (its rules for n = 3);
    with, for each layout 000 enumerates, the largest relative difference between the rates 000's
    solver finds for it and Lenzo's."""
    rows, agreement = [], []
    for letter, (arm, d) in designs.items():
        s13, s23 = to_chain_springs(arm, d)
        verdict = rules.verdict(3, [s13, s23])
        rows.append((letter, *verdict.labels, "yes" if verdict.enumerated else "no", verdict.why))
        if verdict.enumerated:
            specs = [SpringSpec(1, 3, s13.pattern, a=s13.a), SpringSpec(2, 3, s23.pattern, a=s23.a, b=s23.b)]
            ours = solve_design(arm.chain(FOREARM_LENGTH), specs).springs
            agreement.append(max(abs(x.k - y.k) / y.k for x, y in zip(ours, (s13, s23), strict=True)))
    return Table(["layout", "000: S(1,3)", "000: S(2,3)", "in 000's enumeration (n = 3)", "000's verdict"],
                 rows), agreement
