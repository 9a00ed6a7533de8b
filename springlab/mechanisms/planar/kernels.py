"""Compiled kernels for the planar arms (numba): the workspace index's grid sums.

numba compiles the loops to machine code on first use and caches the result on disk
(``cache=True``), so the index's inner loop runs without the (poses x terms) temporary
arrays a numpy expression allocates at every outer grid point. numba is a well-kept,
widely used compiler for numeric Python; the same loops in numpy are 8 times slower here.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import numba
import numpy as np

BLOCK = 512
"""Inner grid points per block: the block's term values (terms x BLOCK doubles) stay in cache."""


@numba.njit(cache=True, nogil=True)
def index_sums(cos_in, sin_in, cos_out, sin_out, dynamic, base_x, base_y, sides, starts, members, job_of_group,
               static_group, direct):  # pragma: no cover
    """Sum of e_sys (003 Eq. 25, or 003 Eq. 24 where ``direct``) over every outer x inner grid point,
    per job: (J,).

    cos_in, sin_in (T, M): each distinct term's amp cos and amp sin of (phase - Theta_in) over
    the inner grid; cos_out, sin_out (P, T): cos and sin of each term's Theta_out per outer point,
    so that a term's value is cos_in cos_out + sin_in sin_out (N/m); a term not ``dynamic`` (no
    outer joint in its Theta) is cos_in itself. Groups g: the terms members[starts[g]:starts[g + 1]],
    summed, their magnitude added to X (sides[g] = 0) or Y (sides[g] = 1) of job job_of_group[g];
    the groups marked ``static_group`` are already in base_x, base_y (J, M), X and Y's starting
    values. e = (X + Y) / (X + 2 Y) (003 Eq. 25), or X / (X + Y) for a ``direct`` job (003 Eq. 24).
    """
    T, M = cos_in.shape
    P = cos_out.shape[0]
    G = sides.shape[0]
    J = direct.shape[0]
    part = np.zeros((P, J))  # per outer point, summed block by block in the inner grid's order
    vals = np.empty((T, BLOCK))
    acc = np.empty(BLOCK)
    X = np.empty((J, BLOCK))
    Y = np.empty((J, BLOCK))
    # the inner block outside, the outer points inside: a block's cos_in, sin_in (T x BLOCK) is read
    # from memory once and stays in cache for every outer point, instead of the whole inner grid
    # (T x M, tens of MB at 0.5 deg) streamed once per outer point
    for b0 in range(0, M, BLOCK):
        nb = min(BLOCK, M - b0)
        for p in range(P):
            for t in range(T):
                if dynamic[t]:
                    c, s = cos_out[p, t], sin_out[p, t]
                    for b in range(nb):
                        vals[t, b] = cos_in[t, b0 + b] * c + sin_in[t, b0 + b] * s
            for j in range(J):
                for b in range(nb):
                    X[j, b] = base_x[j, b0 + b]
                    Y[j, b] = base_y[j, b0 + b]
            for g in range(G):
                if static_group[g]:
                    continue
                j = job_of_group[g]
                acc[:nb] = 0.0
                for q in range(starts[g], starts[g + 1]):
                    t = members[q]
                    if dynamic[t]:
                        for b in range(nb):
                            acc[b] += vals[t, b]
                    else:
                        for b in range(nb):
                            acc[b] += cos_in[t, b0 + b]
                if sides[g] == 0:
                    for b in range(nb):
                        X[j, b] += abs(acc[b])
                else:
                    for b in range(nb):
                        Y[j, b] += abs(acc[b])
            for j in range(J):
                sj = 0.0
                if direct[j]:
                    for b in range(nb):
                        sj += X[j, b] / (X[j, b] + Y[j, b])  # 003 Eq. (24)
                else:
                    for b in range(nb):
                        sj += (X[j, b] + Y[j, b]) / (X[j, b] + 2.0 * Y[j, b])  # 003 Eq. (25)
                part[p, j] += sj
    totals = np.zeros(J)
    for p in range(P):  # the outer points in order, as the sums were always added
        totals += part[p]
    return totals
