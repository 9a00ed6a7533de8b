"""Data of Juang, Jhuang, Chen (2023), *A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links*, Mechanism and Machine
Theory 191, 105497, doi:10.1016/j.mechmachtheory.2023.105497.

SI units: m, kg, N/m, rad (the tables print degrees; converted here).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

from springlab.design.rules import SpringSlot
from springlab.energy import quadratic as q
from springlab.errors import SpringlabError
from springlab.model.chain import serial_chain
from springlab.model.springs import Spring
from springlab.tables import Table

G = 9.8
"""m/s^2. The paper does not print g; Table 3's k_S(1,2) = 294.00 N/m follows
from 000 Eq. (48c) with g = 9.8 exactly (with 9.81 it would be 294.30)."""

# Table 2: dimension and mass of the example arm (links 2..4; link 1 is the ground).
R = (0.30, 0.24, 0.20)  # r_2, r_3, r_4 (m)
D = (0.15, 0.12, 0.10)  # d_2, d_3, d_4 (m)
M = (4.0, 3.2, 2.8)  # m_2, m_3, m_4 (kg)


def example_arm():
    """The four-link spatial arm of Table 2 (spherical joints)."""
    return serial_chain(R, D, M, g=G)


# 000 Eq. (46): the configuration of the example.
EXAMPLE_CONFIGURATION = (
    SpringSlot(1, 2, "(+,+)"),
    SpringSlot(1, 4, "(+,+)"),
    SpringSlot(2, 4, "(+,+)"),
    SpringSlot(3, 4, "(-,-)"),
)

# The free choices the paper made: the values of Table 3 that 000 Eqs. (48a-f) do
# not determine (six equations, twelve parameters).
FREE_CHOICES = {
    (1, 4): {"a": 0.060},
    (1, 2): {"a": 0.150, "b": 0.240},
    (2, 4): {"a": 0.100},
    (3, 4): {"a": -0.200, "b": -0.100},
}


@dataclass(frozen=True)
class PrintedSpring:
    """One row of Table 3 as printed: a (m), b (m), k (N/m), and the printed decimals."""

    i: int
    j: int
    a: float
    b: float
    k: float
    decimals_ab: int = 3
    decimals_k: int = 2

    def spring(self) -> Spring:
        return Spring(self.i, self.j, self.a, self.b, self.k)


# Table 3: spring parameters to achieve gravity balance, as printed.
TABLE_3 = (
    PrintedSpring(1, 4, a=0.060, b=0.064, k=718.67),
    PrintedSpring(1, 2, a=0.150, b=0.240, k=294.00),
    PrintedSpring(2, 4, a=0.100, b=0.064, k=2156.00),
    PrintedSpring(3, 4, a=-0.200, b=-0.100, k=2195.20),
)


def table3_entries():
    """Each printed number of Table 3 in print order: (row, name 'a'/'b'/'k', unit, decimals)."""
    for row in TABLE_3:
        for name, unit, dec in (("a", "m", row.decimals_ab), ("b", "m", row.decimals_ab), ("k", "N/m", row.decimals_k)):
            yield row, name, unit, dec


def table3_springs() -> tuple[Spring, ...]:
    """Table 3's springs with the printed (rounded) values."""
    return tuple(p.spring() for p in TABLE_3)


def _deg(rows):
    return np.radians(np.asarray(rows, dtype=float))


# Table 4: initial posture and rotation of the links, (theta, phi, psi) for i = 2, 3, 4.
TABLE_4_INITIAL = _deg([[0, -50, -20], [0, 20, -20], [90, -2, -50]])
TABLE_4_ROTATION = _deg([[21, 60, 36], [0, 96, 30], [-75, -30, 30]])

# Table 5: the planar trajectory (rotation about y only).
TABLE_5_INITIAL = _deg([[0, -40, 0], [0, -30, 0], [0, -30, 0]])
TABLE_5_ROTATION = _deg([[0, 120, 0], [0, 15, 0], [0, 15, 0]])

DURATION = 30.0
"""s: 'the manipulator's end effector can be seen to move from the starting point
to the end point in 30 seconds' (Section 4)."""

# Table 1: acceptable configurations with necessary springs, n = 3 and n = 4.
# Each row maps a link pair to its alternatives; an alternative is a tuple of
# patterns installed together on that pair ('1^(+,-), 1^(+,+)' is two springs).
_PM = (("(+,+)",), ("(-,-)",))
_PP = (("(+,+)",),)
TABLE_1 = {
    3: [
        {(1, 3): _PP, (2, 3): _PM},
    ],
    4: [
        {(1, 2): _PM, (1, 4): _PP, (2, 3): _PM, (2, 4): (("(-,-)",),)},
        {(1, 3): _PP, (1, 4): _PP, (2, 3): _PM, (2, 4): (("(-,-)",),)},
        {(1, 2): _PM, (1, 4): _PP, (2, 4): _PP, (3, 4): _PM},
        {(1, 3): _PP, (1, 4): _PP, (2, 4): _PP, (3, 4): _PM},
        {(1, 2): _PM, (1, 4): _PP, (2, 4): (("(+,+)", "(+,-)"),)},
        {(1, 3): _PP, (1, 4): _PP, (2, 4): (("(+,+)", "(+,-)"),)},
    ],
}
"""The extracted text of Table 1 garbles some cells of rows 2-3 (a spring printed in
column 2 of row 2); they are read here as the paper's own text describes the
configurations (Section 3.3 and 000 Eq. 46)."""


def table1_configurations(n: int) -> list[tuple[SpringSlot, ...]]:
    """Table 1's rows for n links expanded into concrete configurations."""
    if isinstance(n, bool) or not isinstance(n, int) or n not in TABLE_1:
        raise SpringlabError(f"Table 1 of 000 lists n = {sorted(TABLE_1)} links, got n = {n!r}")
    import itertools

    out = set()
    for row in TABLE_1[n]:
        pairs = sorted(row)
        for choice in itertools.product(*(row[p] for p in pairs)):
            slots = [SpringSlot(i, j, pat) for (i, j), alt in zip(pairs, choice, strict=True) for pat in alt]
            out.add(tuple(sorted(slots)))
    return sorted(out)


def table_2() -> Table:
    """Table 2 as the paper prints it: each link's length r_i (m), centre of mass d_i (m) and mass m_i (kg).

    >>> print(table_2())  # doctest: +NORMALIZE_WHITESPACE
    | link | length r_i (m) | mass centre d_i (m) | mass m_i (kg) |
    |---|---|---|---|
    | 2 | 0.30 | 0.15 | 4.0 |
    | 3 | 0.24 | 0.12 | 3.2 |
    | 4 | 0.20 | 0.10 | 2.8 |
    """
    return Table(["link", "length r_i (m)", "mass centre d_i (m)", "mass m_i (kg)"],
                 [[i + 2, f"{R[i]:.2f}", f"{D[i]:.2f}", f"{M[i]:.1f}"] for i in range(3)])


def _angle(value: float, moved: bool) -> str:
    """A printed angle: '+21°', '-50°', '0°' in a posture, '±0°' in a rotation."""
    deg = round(float(np.degrees(value)))
    return ("±0°" if moved else "0°") if deg == 0 else f"{deg:+d}°"


def _trajectory(initial, rotation) -> Table:
    rows = [[f"initial posture, i = {i + 2}", *(_angle(v, False) for v in initial[i])] for i in range(3)]
    rows += [[f"rotation of links, i = {i + 2}", *(_angle(v, True) for v in rotation[i])] for i in range(3)]
    return Table(["", "theta_i", "phi_i", "psi_i"], rows)


def table_4() -> Table:
    """Table 4 as the paper prints it: the spatial trajectory's initial posture and the links' rotations
    (deg) about x, y and z of the link before."""
    return _trajectory(TABLE_4_INITIAL, TABLE_4_ROTATION)


def table_5() -> Table:
    """Table 5 as the paper prints it: the planar trajectory's initial posture and rotations (deg)."""
    return _trajectory(TABLE_5_INITIAL, TABLE_5_ROTATION)


def printed_planar() -> dict:
    """000 Eqs. (3), (4) and (7) as printed, typed in (sympy, in :func:`springlab.energy.quadratic.chain_symbols`
    and :func:`~springlab.energy.quadratic.planar_symbols` for n = 4): the planar arm's gravity energy in
    the joint angles (000 Eq. 3), the entries G^p_{1,j} (000 Eq. 7, {j: entry}) and the energy as their sum
    (000 Eq. 4)."""
    (r2, r3, r4), (d2, d3, d4), (m2, m3, m4), g = q.chain_symbols(4)
    (t2, t3, t4), r1 = q.planar_symbols(4)
    s2, s23, s234 = sp.sin(t2), sp.sin(t2 + t3), sp.sin(t2 + t3 + t4)
    eq3 = g * (d2 * m2 + r2 * (m3 + m4)) * s2 + g * (d3 * m3 + r3 * m4) * s23 + g * d4 * m4 * s234  # 000 Eq. (3)
    eq7 = {2: (m2 * g * d2 / (r1 * r2) + (m3 + m4) * g / r1) * s2,  # 000 Eq. (7a)
           3: (m3 * g * d3 / (r1 * r3) + m4 * g / r1) * s23,  # 000 Eq. (7b)
           4: m4 * g * d4 / (r1 * r4) * s234}  # 000 Eq. (7c)
    eq4 = r1 * eq7[2] * r2 + r1 * eq7[3] * r3 + r1 * eq7[4] * r4  # 000 Eq. (4)
    return {"3": eq3, "4": eq4, "7": eq7}


def printed_eq13() -> dict:
    """000 Eq. (13) as printed, typed in: the gravity matrix's entries G_{1,j} of a 4-link chain."""
    (r2, r3, _), (d2, d3, d4), (m2, m3, m4), g = q.chain_symbols(4)
    return {(1, 2): m2 * g * d2 + (m3 + m4) * r2 * g,  # 000 Eq. (13)
            (1, 3): m3 * g * d3 + m4 * r3 * g,
            (1, 4): m4 * g * d4}


def printed_eq28() -> dict:
    """000 Eq. (28) as printed, typed in: spring S(1,4)'s matrix on a 4-link chain, its entries by
    (u, v) and its constant term ("C", the trace)."""
    (r2, r3, _), _, _, _ = q.chain_symbols(4)
    a, b, k = q.spring_symbols(1, 4)
    return {"C": k * (a**2 + b**2 + r2**2 + r3**2) / 2,  # 000 Eq. (28)
            (1, 4): -k * a * b, (1, 3): -k * a * r3, (1, 2): -k * a * r2,
            (2, 4): k * r2 * b, (3, 4): k * r3 * b, (2, 3): k * r2 * r3}


def printed_eq48() -> dict:
    """000 Eqs. (48a-f) as printed, typed in: the balancing equations of the example configuration
    (each = 0), by entry (u, v)."""
    (r2, r3, _), (d2, d3, d4), (m2, m3, m4), g = q.chain_symbols(4)
    (a14, b14, k14), (a12, b12, k12), (a24, b24, k24), (a34, b34, k34) = (
        q.spring_symbols(*p) for p in [(1, 4), (1, 2), (2, 4), (3, 4)])
    return {(1, 4): k14 * a14 * b14 - m4 * g * d4,  # 000 Eq. (48a)
            (1, 3): k14 * a14 * r3 - (m3 * g * d3 + m4 * r3 * g),  # 000 Eq. (48b)
            (1, 2): k14 * a14 * r2 + k12 * a12 * b12 - (m2 * g * d2 + (m3 + m4) * r2 * g),  # 000 Eq. (48c)
            (2, 4): k14 * r2 * b14 - k24 * a24 * b24,  # 000 Eq. (48d)
            (2, 3): k14 * r2 * r3 - k24 * a24 * r3,  # 000 Eq. (48e)
            (3, 4): k14 * r3 * b14 + k24 * r3 * b24 - k34 * a34 * b34}  # 000 Eq. (48f)


def mono_articulated_lengths(arm, poses: int, seed) -> dict:
    """Fig. 12's mono-articulated spring S(2,3) (k 100 N/m), its ends a = 0.08 m before and b = 0.1 m
    past joint 2, turned about z by (alpha, beta) = (0, 0), (45, 45) and (45, 30) deg, on the first two
    links of ``arm`` with planar joints and with spherical ones: {joints: {(alpha, beta): lengths (m)
    at ``poses`` random poses}}. On a planar arm, turning both ends by the same angle keeps every length
    (000 Eq. 45)."""
    from springlab.energy.geometry import spring_lengths
    from springlab.model.revolute import body_frames
    from springlab.model.springs import PointSpring

    def turned(deg):
        c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    def mono(alpha, beta, a=0.08, b=0.1):
        start = np.array([arm.r[0], 0, 0]) + turned(alpha) @ [-a, 0, 0]
        return PointSpring("link 2", tuple(start), "link 3", tuple(turned(beta) @ [b, 0, 0]), 100.0)

    lengths = {}
    for label, joints in (("planar", [(0.0, 0.0, 1.0)] * 2), ("spherical", None)):
        two = serial_chain(arm.r[:2], arm.d[:2], arm.m[:2], g=arm.g, joints=joints).revolute_chain()
        R, o = body_frames(two, two.random_q(poses, seed))
        lengths[label] = {ab: spring_lengths(two, [mono(*ab)], R, o)[0] for ab in ((0, 0), (45, 45), (45, 30))}
    return lengths


TRAJECTORIES = {
    "fig16_spatial": (TABLE_4_INITIAL, TABLE_4_ROTATION, "Fig. 16: spatial trajectory (Table 4)"),
    "fig17_planar": (TABLE_5_INITIAL, TABLE_5_ROTATION, "Fig. 17: planar trajectory (Table 5)"),
}
"""The paper's two trajectories by the figure that draws them: (initial angles, rotation, title)."""
