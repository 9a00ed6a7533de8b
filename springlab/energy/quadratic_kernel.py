"""Route 1's compiled kernel (numba): U = sum_{u<=v} M_uv x_u . x_v over poses stored
component-major, in one pass over memory.

numba compiles the loop once per machine and caches it on disk (``cache=True``). A block
of poses at a time, each term's products are accumulated in a block-sized buffer that
stays in the first-level cache, and the loop over the block's poses is contiguous, so the
compiler vectorises it; the numpy expression this replaces made several passes over each
chunk. The arithmetic is the same, in the same order, as that expression: the energies
agree to the last bit.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import numba
import numpy as np

BLOCK = 1024
"""Poses per block: the block's accumulator (8 kB) stays in the first-level cache."""


@numba.njit(cache=True, nogil=True)
def component_major_energy(const, lin_v, lin_c, pair_u, pair_v, pair_c, XT, out):  # pragma: no cover
    """out[p] = const + sum_k lin_c[k] x_{lin_v[k]}[0] + sum_k pair_c[k] x_u . x_v (J) at pose p
    of XT (n, 3, N) (000 Eq. 14 and 000 Eq. 24 summed as X^T (G + sum K_S) X, with x_1 = UP
    = e_0 making the ground row linear)."""
    n_pose = XT.shape[2]
    acc = np.empty(BLOCK)
    for start in range(0, n_pose, BLOCK):
        m = min(BLOCK, n_pose - start)
        a = acc[:m]
        a[:] = const
        for k in range(lin_v.shape[0]):
            xv, c = XT[lin_v[k], 0, start:start + m], lin_c[k]
            for p in range(m):
                a[p] += xv[p] * c
        for k in range(pair_u.shape[0]):
            u, v, c = pair_u[k], pair_v[k], pair_c[k]
            u0, u1, u2 = XT[u, 0, start:start + m], XT[u, 1, start:start + m], XT[u, 2, start:start + m]
            v0, v1, v2 = XT[v, 0, start:start + m], XT[v, 1, start:start + m], XT[v, 2, start:start + m]
            for p in range(m):
                a[p] += (u0[p] * v0[p] + u1[p] * v1[p] + u2[p] * v2[p]) * c
        out[start:start + m] = a
    return out
