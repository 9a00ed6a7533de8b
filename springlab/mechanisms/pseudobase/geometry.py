r"""Route 2 for paper 001: direct geometry. Every body and attachment point of the
pseudobase arm placed in space for a pose, then m g h and K |AB|^2 / 2 summed.
It shares no formula with the subsystems of route 1 (:mod:`~springlab.mechanisms.pseudobase.subsystems`).

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general
spatial serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003.
doi:10.1115/1.4001816
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.mechanisms.pseudobase.model import (
    PseudobaseArm,
    check_springs,
    world_point,
)


def positions(arm: PseudobaseArm, springs, q) -> dict:
    """Every body and attachment point in frame 0 (m), for joint angles q (N, n).

    The auxiliary chain is placed by its own DH transforms from Ô_0 = O_0 +
    aux_offset (its angles equal the primary ones on the parallelogram branch);
    the pseudobase's direction is then the line C_i D_i as placed, not assumed.

    :returns: dict of arrays: 'com' (N, n, 3) primary COMs; 'aux_com', 'star_com',
        'C', 'D' (N, k, 3) per module; 'A', 'B' (N, k, 3) per spring; 'O' (N, n+1, 3) the frame origins
    """
    springs = check_springs(arm, springs)
    q = arm.dh.check_angles(q)
    R, org = arm.dh.frames(q)
    O_aux = org + arm.aux_offset  # parallel frames, translated: frame î
    com = np.stack([world_point(R, org, i, arm.s[i - 1]) for i in range(1, arm.n + 1)], axis=1)
    C = np.stack([world_point(R, org, i, arm.c[i - 1]) for i in arm.modules], axis=1)
    D = np.stack([world_point(R, O_aux, i, arm.c[i - 1]) for i in arm.modules], axis=1)
    aux_com = np.stack([world_point(R, O_aux, i, arm.s_hat[i - 1]) for i in arm.modules], axis=1)
    line = D - C
    u = line / np.linalg.norm(line, axis=-1, keepdims=True)  # the pseudobase's axis
    star_com = C + arm.star_height * u
    index = {i: col for col, i in enumerate(arm.modules)}
    A, B = [], []
    for sp in springs:
        if sp.link not in index:
            raise SpringlabError(f"spring on link {sp.link}: that link has no module (modules {arm.modules})")
        A.append(C[:, index[sp.link]] + sp.l_CA * u[:, index[sp.link]])
        B.append(world_point(R, org, sp.link, sp.b))
    shape = (q.shape[0], 0, 3)
    return {"O": org, "com": com, "C": C, "D": D, "aux_com": aux_com, "star_com": star_com,
            "A": np.stack(A, axis=1) if A else np.zeros(shape), "B": np.stack(B, axis=1) if B else np.zeros(shape)}


def energies(arm: PseudobaseArm, springs, q) -> dict:
    """Route 2 energies (J) at joint angles q (N, n): 'gravity', 'springs', 'total' (the
    shape every route's ``energies`` has), and gravity's parts 'gravity_primary',
    'gravity_aux', 'gravity_pseudobase', each (N,).
    Heights are measured along ``up`` from O_0."""
    springs = check_springs(arm, springs)
    p = positions(arm, springs, q)
    mod = np.asarray(arm.modules) - 1
    out = {
        "gravity_primary": arm.g * (p["com"] @ arm.up) @ arm.m,
        "gravity_aux": arm.g * (p["aux_com"] @ arm.up) @ arm.m_hat[mod],
        "gravity_pseudobase": arm.g * (p["star_com"] @ arm.up) @ arm.m_star[mod],
    }
    out["gravity"] = out["gravity_primary"] + out["gravity_aux"] + out["gravity_pseudobase"]
    K = np.array([sp.K for sp in springs])
    out["springs"] = 0.5 * (np.sum((p["A"] - p["B"]) ** 2, axis=-1) @ K) if len(K) else np.zeros(len(p["O"]))
    out["total"] = out["gravity"] + out["springs"]
    return out


def holding_torques(arm: PseudobaseArm, springs, poses, *, spring_scale: float = 1.0,
                           delta: float = 1e-6) -> np.ndarray:
    """Holding torques dV/dq (N m), (N, n), route 2: the total energy of :func:`energies`
    differentiated by central differences (step ``delta`` rad); springs scaled by ``spring_scale``."""
    springs = check_springs(arm, springs)
    poses = arm.dh.check_angles(poses)
    spring_scale = _checks.positive("spring_scale", spring_scale, allow_zero=True)
    delta = _checks.positive("delta", delta, unit="rad")
    scaled = [sp.scaled(spring_scale) for sp in springs]
    out = np.zeros(poses.shape)
    for j in range(arm.n):
        e = np.zeros(arm.n)
        e[j] = delta
        out[:, j] = (energies(arm, scaled, poses + e)["total"] - energies(arm, scaled, poses - e)["total"]) / (2 * delta)
    return out
