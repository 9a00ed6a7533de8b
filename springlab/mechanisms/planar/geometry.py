r"""Route 2 for paper 003: place the joints, centres of mass and attachment points
in the plane and sum m g h and k |AB|^2 / 2. It shares no formula with route 1
(:mod:`~springlab.mechanisms.planar.quadratic`).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab.mechanisms.planar.model import (
    PlanarArm,
    check_spring,
    check_springs,
    relative_angles,
)


def _direction(angle):
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def energies(arm: PlanarArm, springs, theta) -> dict:
    """Route 2: place the joints, COMs and attachment points in the plane and sum
    m g h and k |AB|^2 / 2. Returns {'gravity', 'springs', 'total'}, each (N,) in J."""
    springs = check_springs(arm, springs)
    theta = relative_angles(theta, arm.n)
    for sp in springs:
        check_spring(arm, sp, criteria=False)
    N = theta.shape[0]
    absolute = np.concatenate([np.zeros((N, 1)), np.cumsum(theta, axis=1)], axis=1)  # Theta_{1,j}, j = 1..n
    x = _direction(absolute)  # (N, n, 2) link directions; the ground's is horizontal
    joints = np.zeros((N, arm.n, 2))  # J_1 (base) .. J_n (distal end of link n)
    for j in range(2, arm.n + 1):
        joints[:, j - 1] = joints[:, j - 2] + arm.r[j - 1] * x[:, j - 1]
    gravity = np.zeros(N)
    for j in range(2, arm.n + 1):
        com = joints[:, j - 2] + arm.s[j - 1] * x[:, j - 1]
        gravity += arm.m[j - 1] * arm.g * com[:, 1]
    elastic = np.zeros(N)
    for sp in springs:
        A = joints[:, sp.i - 1] + sp.a * _direction(absolute[:, sp.i - 1] + np.radians(sp.alpha))
        B = joints[:, sp.j - 2] + sp.b * _direction(absolute[:, sp.j - 1] + np.radians(sp.beta))
        elastic += 0.5 * sp.k * np.sum((B - A) ** 2, axis=1)
    return {"gravity": gravity, "springs": elastic, "total": gravity + elastic}


def holding_torques(arm: PlanarArm, springs, theta, *, delta: float = 1e-6) -> np.ndarray:
    """Joint torques (N m) that hold each pose, (N, n-1): the derivative of route 2's total
    energy (:func:`energies`) with respect to each joint angle theta_2..theta_n (rad), by
    central differences of step ``delta`` rad. Zero everywhere: the arm is balanced."""
    springs = check_springs(arm, springs)
    theta = relative_angles(theta, arm.n)
    delta = _checks.positive("delta", delta, unit="rad")
    out = np.zeros(theta.shape)
    for j in range(theta.shape[1]):
        step = np.zeros(theta.shape[1])
        step[j] = delta
        out[:, j] = (energies(arm, springs, theta + step)["total"] - energies(arm, springs, theta - step)["total"]) / (2 * delta)
    return out
