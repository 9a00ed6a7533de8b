"""Route 1 for paper 002: the paper's algebra. Slider positions that keep the total
energy constant (002 Eqs. 5-7), the linear synthesis of r, l, beta (002 Eqs. 12-19) and
the unbalanced moment as 002 Eqs. (20)-(30) print it.

References
----------
Zhang, Y., Arakelian, V. (2023). Design and Synthesis of the Gravity Compensator with a
Non-zero Length Spring (no DOI printed in the text).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.mechanisms.dyad.model import Compensator, Dyad, check_pair, check_phi, slider_height


def slider_positions(comp: Compensator, C: float, phi, *, branch: int = -1) -> np.ndarray:
    """Slider heights y (m) that keep the total energy at C (J): 002 Eqs. (5)-(7).

    y = l0 + branch * sqrt((2C - 2 G s (1 + cos phi)) / k); ``branch`` = -1 (the
    spring shorter than free, the paper's examples) or +1.

    :raises SpringlabError: where 2C < 2 G s (1 + cos phi): the root is imaginary
    """
    _checks.instance("comp", comp, Compensator, "Compensator(G, s, k, l0)")
    C = _checks.number("C", C)
    if branch not in (-1, 1):
        raise SpringlabError(f"branch must be -1 or +1, got {branch}")
    phi = check_phi(phi)
    radicand = (2.0 * C - 2.0 * comp.gravity_energy(phi)) / comp.k  # 002 Eq. (6)
    if np.any(radicand < 0) or not np.isfinite(C):
        worst = np.degrees(np.atleast_1d(phi)[np.argmin(np.atleast_1d(radicand))])
        need = float(np.max(comp.gravity_energy(phi)))
        raise SpringlabError(
            f"C = {C} J is below the gravity energy G s (1 + cos phi) = {need:.6g} J at phi = {worst:.6g} deg: "
            f"the slider position of 002 Eq. (6) is imaginary; choose C >= {need:.6g} J")
    return comp.l0 + branch * np.sqrt(radicand)  # 002 Eq. (7)


@dataclass(frozen=True)
class Synthesis:
    """The dyad from 002 Eq. (16) and how well-posed the system was."""

    dyad: Dyad
    condition_number: float  # of the matrix [a_i, b_i, 1]
    residual: float  # largest |a z1 + b z2 + z3 - c| (m^2); 0 for 3 positions


def synthesise(phi, y) -> Synthesis:
    """r, l, beta from prescribed positions (phi_i, y_i): 002 Eqs. (12)-(19).

    Exact for 3 positions, least squares for more.

    :raises SpringlabError: fewer than 3 positions, a singular system, or
        z3 + r^2 < 0 (no real rod length)
    """
    phi = np.atleast_1d(check_phi(phi))
    y = np.atleast_1d(_checks.real_array("y (slider heights, m)", y))
    if phi.shape != y.shape or phi.ndim != 1:
        raise SpringlabError(f"phi and y must be 1-D of one length, got {phi.shape} and {y.shape}")
    if len(phi) < 3:
        raise SpringlabError(f"the synthesis needs at least 3 prescribed positions, got {len(phi)}")
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(y))):
        raise SpringlabError("phi and y must be finite")
    A = np.stack([2 * y * np.cos(phi), 2 * y * np.sin(phi), np.ones_like(y)], axis=1)  # 002 Eq. (16)
    c = y**2
    cond = float(np.linalg.cond(A))
    if not np.isfinite(cond) or cond > 1e12:
        raise SpringlabError(f"the positions give a singular system (condition number {cond:.3g})")
    z, *_ = np.linalg.lstsq(A, c, rcond=None)
    r = float(np.hypot(z[0], z[1]))  # 002 Eqs. (12)-(13), (18)
    beta = float(np.arctan2(z[1], z[0]))  # 002 Eq. (17)
    l_sq = z[2] + r**2  # 002 Eq. (19)
    if l_sq <= 0:
        raise SpringlabError(f"z3 + r^2 = {l_sq:.6g} m^2 <= 0: no real rod length l for these positions")
    return Synthesis(Dyad(r, float(np.sqrt(l_sq)), beta), cond, float(np.max(np.abs(A @ z - c))))


def unbalanced_moment_paper(comp: Compensator, dyad: Dyad, phi) -> np.ndarray:
    """M_ub as 002 Eqs. (20)-(30) print it (N m).

    M_G = -G s sin phi (20); y (24); F_sp = k (y - l0) (25); F_ab = F_sp cos theta
    (26), theta = arccos((y^2 + l^2 - r^2) / (2 y l)) (27); M_sp = F_ab r sin psi
    (28), psi = arcsin(y sin(phi - beta) / l) (29); M_ub = -(M_sp + M_G) (30).
    """
    check_pair(comp, dyad)
    phi = check_phi(phi)
    y = slider_height(dyad, phi)
    M_G = -comp.G * comp.s * np.sin(phi)  # 002 Eq. (20)
    F_sp = comp.k * (y - comp.l0)  # 002 Eq. (25)
    theta = np.arccos(np.clip((y**2 + dyad.l**2 - dyad.r**2) / (2 * y * dyad.l), -1, 1))  # 002 Eq. (27)
    F_ab = F_sp * np.cos(theta)  # 002 Eq. (26)
    psi = np.arcsin(np.clip(y * np.sin(phi - dyad.beta) / dyad.l, -1, 1))  # 002 Eq. (29)
    M_sp = F_ab * dyad.r * np.sin(psi)  # 002 Eq. (28)
    return -(M_sp + M_G)  # 002 Eq. (30)


def unbalanced_moment_paper_sign_corrected(comp: Compensator, dyad: Dyad, phi) -> np.ndarray:
    """002 Eqs. (20)-(30) with the spring's moment taken with the sign of a moment towards
    larger phi (as M_G's gravity is): G s sin(phi) + M_sp. As printed, 002 Eq. (30)
    subtracts a spring moment of the same sign as gravity's and so adds the two."""
    check_pair(comp, dyad)
    return 2.0 * comp.gravity_moment(phi) - unbalanced_moment_paper(comp, dyad, phi)
