"""System spring efficiency of a spatial arm: paper 003's e_sys generalised through paper
000's quadratic form.

Spatial system spring efficiency
--------------------------------
Paper 003 defines e_sys = (X + Y) / (X + 2Y) (003 Eq. 25) for planar arms. Paper 000's
quadratic form gives the same pieces in space: the energy's pose-dependent part
is sum_{u<v} M_uv x_u . x_v, each spring S contributing entries K^S_uv (000 Eqs.
23a-d) and gravity G_1v. Divided by r_u r_v (r_1 = 1 m, as 003 sets it), an entry
times x_u . x_v is a pseudo-stiffness. Gravity's are positive (x_1 is up), so a
spring term *balances* when its entry is negative and *is balanced* when positive;
with the attachment patterns (+,+) on the ground, (+,+) and (-,-) elsewhere this
is exactly 003's C1/C2 classification. Then, at each pose,

    X = sum_v |G_1v x_1 . x_v| / r_v,   Y = sum_{S, u<v, K^S_uv > 0} |K^S_uv x_u . x_v| / (r_u r_v)

and e_sys = (X + Y)/(X + 2Y): 003 Eq. (25), 'magnitudes' reading. For a planar
motion x_u . x_v = cos Theta_uv and it reduces to 003's (tested against
:func:`springlab.mechanisms.planar.efficiency.system_efficiency`).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab.energy.quadratic import gravity_entries, spring_entries
from springlab.model.chain import Chain, check_springs


def spatial_system_efficiency(chain: Chain, springs, X) -> np.ndarray:
    """e_sys (003 Eq. 25, generalised; module docstring) at each pose X (N, n, 3), (N,).

    Where no spring term is balanced (Y = 0) e_sys is 1, its limit as Y -> 0, also at a
    pose where X = 0 too (every link horizontal and no spring working): there 003 Eq. (25)
    reads 0/0, and no spring energy is wasted."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    X = chain.check_directions(X)
    springs = check_springs(chain, springs)
    r = {1: 1.0} | {t: chain.r[t - 2] for t in range(2, chain.n + 1)}
    dots = np.einsum("nuk,nvk->nuv", X, X)
    Xs = np.zeros(len(X))
    for (u, v), value in gravity_entries(chain.r, chain.d, chain.m, chain.g).items():
        Xs += np.abs(value * dots[:, u - 1, v - 1]) / (r[u] * r[v])
    Ys = np.zeros(len(X))
    for s in springs:
        for (u, v), value in spring_entries(s.i, s.j, s.a, s.b, s.k, chain.r).items():
            if u < v and value > 0:
                Ys += np.abs(value * dots[:, u - 1, v - 1]) / (r[u] * r[v])
    den = Xs + 2 * Ys
    return np.divide(Xs + Ys, den, out=np.ones_like(den), where=Ys > 0)  # 003 Eq. (25)
