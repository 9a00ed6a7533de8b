"""Route 2's compiled kernel (numba): the holding torques of a serial chain, pose by pose,
from the positions of its joints, centres of mass and spring ends alone.

numba compiles the loop once per machine and caches it on disk (``cache=True``). One pass
per pose: the link directions are checked (unit length, the ground link up), the joints
placed, and the torques summed from the end link inwards; nothing of size (poses x links)
is allocated but the result. It imports nothing of route 1.
"""

from __future__ import annotations

import numba
import numpy as np

OK, BAD_POSE, ENDS_MEET = 0, 1, 2
"""Kernel status: every pose valid; a pose fails the checks of ``Chain.check_directions``;
a spring with a free length has coinciding ends."""


@numba.njit(cache=True, nogil=True)
def holding_torques(r, d, m, g, up, spr_i, spr_j, spr_a, spr_b, spr_k, spr_l0, X, out):  # pragma: no cover
    """Fill out (N, n-1, 3) with each joint's holding torque (N m, world frame) at the poses
    X (N, n, 3); returns (status, pose, spring): the first pose that fails (and the spring whose
    ends meet there), or (OK, -1, -1).

    Gravity, for joint j (at J_{j-1}): sum_{t>=j} (c_t - J_{j-1}) x (m_t g UP)
    = g (S_j - M_j J_{j-1}) x UP with S_j = sum_{t>=j} m_t c_t and M_j = sum_{t>=j} m_t,
    accumulated from the end link inwards. A spring from A = J_i + a x_i to B = J_{j-1} + b x_j
    adds k_eff (B - J_{t-1}) x (B - A) at each joint t it crosses (i < t <= j),
    k_eff = k (1 - l0 / |B - A|).
    """
    N, n = X.shape[0], X.shape[1]
    J = np.zeros((n, 3))
    for p in range(N):
        for q in range(n):
            sq = X[p, q, 0] * X[p, q, 0] + X[p, q, 1] * X[p, q, 1] + X[p, q, 2] * X[p, q, 2] - 1.0
            if not abs(sq) <= 2e-9:  # also NaN
                return BAD_POSE, p, -1
        for c in range(3):
            if abs(X[p, 0, c] - up[c]) > 1e-12:
                return BAD_POSE, p, -1
        for q in range(1, n):
            for c in range(3):
                J[q, c] = J[q - 1, c] + r[q - 1] * X[p, q, c]
        sx = sy = sz = M = 0.0
        ux, uy, uz = up[0], up[1], up[2]
        for q in range(n - 1, 0, -1):  # link q + 1 (q 0-based), pivot J[q - 1] of joint q + 1
            mq, dq = m[q - 1], d[q - 1]
            jx, jy, jz = J[q - 1, 0], J[q - 1, 1], J[q - 1, 2]
            sx += mq * (jx + dq * X[p, q, 0])
            sy += mq * (jy + dq * X[p, q, 1])
            sz += mq * (jz + dq * X[p, q, 2])
            M += mq
            vx, vy, vz = g * (sx - M * jx), g * (sy - M * jy), g * (sz - M * jz)
            out[p, q - 1, 0] = vy * uz - vz * uy
            out[p, q - 1, 1] = vz * ux - vx * uz
            out[p, q - 1, 2] = vx * uy - vy * ux
        for s in range(spr_i.shape[0]):
            i, j, k = spr_i[s], spr_j[s], spr_k[s]
            ax = J[i - 1, 0] + spr_a[s] * X[p, i - 1, 0]
            ay = J[i - 1, 1] + spr_a[s] * X[p, i - 1, 1]
            az = J[i - 1, 2] + spr_a[s] * X[p, i - 1, 2]
            bx = J[j - 2, 0] + spr_b[s] * X[p, j - 1, 0]
            by = J[j - 2, 1] + spr_b[s] * X[p, j - 1, 1]
            bz = J[j - 2, 2] + spr_b[s] * X[p, j - 1, 2]
            px, py, pz = bx - ax, by - ay, bz - az
            if spr_l0[s] != 0.0:
                length = np.sqrt(px * px + py * py + pz * pz)
                if length <= 1e-12 * spr_l0[s]:
                    return ENDS_MEET, p, s
                scale = 1.0 - spr_l0[s] / length
                px, py, pz = px * scale, py * scale, pz * scale
            for t in range(i + 1, j + 1):  # the joints the spring crosses
                qx, qy, qz = bx - J[t - 2, 0], by - J[t - 2, 1], bz - J[t - 2, 2]
                out[p, t - 2, 0] += k * (qy * pz - qz * py)
                out[p, t - 2, 1] += k * (qz * px - qx * pz)
                out[p, t - 2, 2] += k * (qx * py - qy * px)
    return OK, -1, -1
