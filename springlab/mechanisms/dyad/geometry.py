"""Route 2 for paper 002: the total potential energy with the slider placed by the
linkage's geometry (002 Eq. 24), and the unbalanced moment about O by virtual work,
-dP/dphi. It shares no formula with :mod:`~springlab.mechanisms.dyad.algebra`.

References
----------
Zhang, Y., Arakelian, V. (2023). Design and Synthesis of the Gravity Compensator with a
Non-zero Length Spring (no DOI printed in the text).
"""

from __future__ import annotations

import numpy as np

from springlab.mechanisms.dyad.model import Compensator, Dyad, check_pair, closing, slider_height


def potential_energy(comp: Compensator, dyad: Dyad, phi) -> np.ndarray:
    """Total potential energy P = G s (1 + cos phi) + k (y - l0)^2 / 2 (002 Eqs. 1-3), J,
    with y from the linkage's geometry (002 Eq. 24)."""
    check_pair(comp, dyad)
    y = slider_height(dyad, phi)
    return comp.gravity_energy(phi) + 0.5 * comp.k * (y - comp.l0) ** 2


def energies(comp: Compensator, dyad: Dyad, phi) -> dict:
    """Route 2 energies (J) at link angles phi (rad): {'gravity': G s (1 + cos phi) (002 Eq. 1),
    'springs': k (y - l0)^2 / 2 with y from the linkage (002 Eqs. 2, 24), 'total':
    :func:`potential_energy`}, each shaped like phi."""
    check_pair(comp, dyad)
    gravity = comp.gravity_energy(phi)
    springs = 0.5 * comp.k * (slider_height(dyad, phi) - comp.l0) ** 2
    return {"gravity": gravity, "springs": springs, "total": gravity + springs}  # as potential_energy adds them


def holding_torques(comp: Compensator, dyad: Dyad, phi) -> np.ndarray:
    """The torque (N m) an actuator at O applies to hold the link at each angle phi (rad),
    positive towards larger phi: dP/dphi = -:func:`unbalanced_moment`."""
    check_pair(comp, dyad)
    return -unbalanced_moment(comp, dyad, phi)


def unbalanced_moment(comp: Compensator, dyad: Dyad, phi) -> np.ndarray:
    """The unbalanced moment about O by virtual work: -dP/dphi (N m), the moment
    of gravity and spring together, positive towards larger phi (as the paper's
    M_ub of 002 Eq. 30). An actuator holds the link with the opposite torque.

    dy/dphi = -r sin(phi - beta) y / (l cos theta), so
    M_ub = G s sin(phi) + k (y - l0) r sin(phi - beta) y / (l cos theta).
    """
    check_pair(comp, dyad)
    u, l_cos_theta = closing(dyad, phi)
    y = dyad.r * np.cos(u) + l_cos_theta
    spring_force = comp.k * (y - comp.l0)
    return comp.gravity_moment(phi) + spring_force * dyad.r * np.sin(u) * y / l_cos_theta


def max_unbalanced(comp: Compensator, dyad: Dyad, phi) -> float:
    """The largest |M_ub| (virtual work) over the angles phi, N m."""
    check_pair(comp, dyad)
    return float(np.max(np.abs(unbalanced_moment(comp, dyad, phi))))
