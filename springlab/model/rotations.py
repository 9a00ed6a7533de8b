"""Rotation conventions used by the papers, vectorised over poses.

Juang, Jhuang, Chen (2023) give each link's posture as three angles
(theta_i, phi_i, psi_i), "the angular displacement of the links with respect to
the x_{i-1}, y_{i-1} and z_{i-1} coordinates" (Section 4, Tables 4-5). The paper
does not state the order. springlab uses intrinsic x-y-z (Cardan) angles::

    R_i = R_{i-1} @ Rx(theta_i) @ Ry(phi_i) @ Rz(psi_i)

first a twist about the previous link's own axis x_{i-1}, then a swing about the
new y, then about the new z. The link's direction is the first column,
x_i = R_i @ [1, 0, 0]. For planar motion (phi only, Table 5) every order gives
the same pose; a balanced arm's total energy does not depend on the order at all.

All angles are in radians.
"""

from __future__ import annotations

import math

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError


def _basic(angle, axis: int, name: str = "angle") -> np.ndarray:
    angle = _checks.real_array(name, angle)
    c, s = np.cos(angle), np.sin(angle)
    out = np.zeros(angle.shape + (3, 3))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    out[..., axis, axis] = 1.0
    out[..., i, i] = c
    out[..., j, j] = c
    out[..., i, j] = -s
    out[..., j, i] = s
    return out


def rot_x(angle) -> np.ndarray:
    """Rotation matrices about x, shape ``angle.shape + (3, 3)``; angle in rad.

    >>> import numpy as np
    >>> np.round(rot_x(np.pi / 2) @ [0, 1, 0], 12)
    array([0., 0., 1.])
    """
    return _basic(angle, 0)


def rot_y(angle) -> np.ndarray:
    """Rotation matrices about y, shape ``angle.shape + (3, 3)``; angle in rad.

    >>> import numpy as np
    >>> np.round(rot_y(np.pi / 2) @ [1, 0, 0], 12)
    array([ 0.,  0., -1.])
    """
    return _basic(angle, 1)


def rot_z(angle) -> np.ndarray:
    """Rotation matrices about z, shape ``angle.shape + (3, 3)``; angle in rad."""
    return _basic(angle, 2)


def rot_axis(axis, angle) -> np.ndarray:
    """Rotations by ``angle`` (rad, any shape) about a fixed unit ``axis`` (Rodrigues),
    shape ``angle.shape + (3, 3)``."""
    u = _checks.real_array("axis", axis, shape=(3,))
    if not np.isclose(np.linalg.norm(u), 1.0, atol=1e-9):
        raise SpringlabError(f"axis must be a unit 3-vector, got {u.tolist()} (length {np.linalg.norm(u):.6g})")
    angle = _checks.real_array("angle", angle)
    K = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    s, c = np.sin(angle)[..., None, None], np.cos(angle)[..., None, None]
    return np.eye(3) + s * K + (1.0 - c) * (K @ K)


def rot_xyz(theta, phi, psi) -> np.ndarray:
    """Intrinsic x-y-z rotation ``Rx(theta) @ Ry(phi) @ Rz(psi)``; angles in rad.

    Broadcasts over the angle arrays; returns shape ``broadcast.shape + (3, 3)``.
    """
    theta, phi, psi = _angle_triple(theta, phi, psi)
    return rot_x(theta) @ rot_y(phi) @ rot_z(psi)


def rot_rpy(r: float, p: float, y: float) -> np.ndarray:
    """URDF's fixed-axis roll, pitch, yaw (rad): Rz(y) Ry(p) Rx(r), one (3, 3) rotation."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _angle_triple(theta, phi, psi):
    """theta, phi, psi as finite float arrays that broadcast together (rad)."""
    out = [_checks.real_array(name, v) for name, v in (("theta", theta), ("phi", phi), ("psi", psi))]
    try:
        np.broadcast_shapes(*(v.shape for v in out))
    except ValueError:
        raise SpringlabError(f"theta, phi and psi must broadcast together, got shapes "
                             f"{[v.shape for v in out]}") from None
    return out


ORDERS = ("xyz", "xzy", "yxz", "yzx", "zxy", "zyx")
"""The six orders in which a joint's three turns (theta about x, phi about y, psi about z)
can be composed."""


def rot_ordered(theta, phi, psi, order: str = "xyz") -> np.ndarray:
    """The intrinsic rotation composed in ``order``: "zyx" is Rz(psi) @ Ry(phi) @ Rx(theta).
    theta always turns about x, phi about y, psi about z; angles in rad.

    >>> bool(np.allclose(rot_ordered(0.1, 0.2, 0.3, "xyz"), rot_xyz(0.1, 0.2, 0.3)))
    True
    """
    if order not in ORDERS:
        raise SpringlabError(f"order must be one of {ORDERS}, got {order!r}")
    theta, phi, psi = _angle_triple(theta, phi, psi)
    turn = {"x": rot_x(theta), "y": rot_y(phi), "z": rot_z(psi)}
    return turn[order[0]] @ turn[order[1]] @ turn[order[2]]


def directions_in_order(angles, order: str) -> np.ndarray:
    """Link directions (N, n, 3) of a spherical chain from joint angles (N, n-1, 3) (rad),
    each joint's turns composed in ``order`` (see :func:`rot_ordered`)."""
    angles = _checks.real_array("angles", angles)
    if angles.ndim != 3 or angles.shape[-1] != 3:
        raise SpringlabError(f"angles must have shape (N, n-1, 3) (rad), got {angles.shape}")
    rel = rot_ordered(angles[..., 0], angles[..., 1], angles[..., 2], order)
    return directions_from_relative(rel)


def frames_from_relative(rel) -> np.ndarray:
    """Link frames (N, n, 3, 3) from each joint's relative rotation (N, n-1, 3, 3):
    R_1 = I (the ground), R_i = R_{i-1} rel_i."""
    rel = _checks.real_array("rel (relative rotations)", rel)
    if rel.ndim != 4 or rel.shape[2:] != (3, 3):
        raise SpringlabError(f"rel (relative rotations) must have shape (N, n-1, 3, 3), got {rel.shape}")
    n_pose, n_moving = rel.shape[:2]
    out = np.empty((n_pose, n_moving + 1, 3, 3))
    out[:, 0] = np.eye(3)
    for j in range(n_moving):
        out[:, j + 1] = out[:, j] @ rel[:, j]
    return out


def directions_from_relative(rel) -> np.ndarray:
    """Link directions (N, n, 3) from each joint's relative rotation (N, n-1, 3, 3)."""
    return frames_from_relative(rel)[..., 0]


def frames_from_directions(X) -> np.ndarray:
    """A right-handed orthonormal frame for each link direction: R with
    R @ [1, 0, 0] = x, shape (N, n, 3, 3).

    The second axis is normal to x and to z (or to y when x is nearly along z);
    the spin about the link's own axis is a free choice for links on
    spherical joints.
    """
    X = _checks.real_array("X (link directions)", X)
    if X.ndim < 1 or X.shape[-1] != 3:
        raise SpringlabError(f"X (link directions) must have a last axis of 3, got shape {X.shape}")
    norms = np.linalg.norm(X, axis=-1)
    if np.any(np.abs(norms - 1.0) > 1e-6):
        raise SpringlabError("X (link directions) must hold unit vectors; |x| reaches "
                             f"{float(norms.flat[np.argmax(np.abs(norms - 1.0))]):.6g}")
    helper = np.zeros(X.shape)
    along_z = np.abs(X[..., 2]) > 0.9
    helper[..., 2] = np.where(along_z, 0.0, 1.0)
    helper[..., 1] = np.where(along_z, 1.0, 0.0)
    y = np.cross(helper, X)
    y /= np.linalg.norm(y, axis=-1, keepdims=True)
    z = np.cross(X, y)
    return np.stack([X, y, z], axis=-1)
