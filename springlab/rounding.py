"""Rounding bands: what a paper's printed rounding allows. A printed number with d decimals
is within half a unit of its last digit; a number computed from printed, rounded inputs
can move by the inputs' half units propagated (to first order). Used by the claims of
the workbench and by the papers' own reproduction helpers (which sit below the workbench).
"""

from __future__ import annotations

from springlab import _checks

__all__ = ["half_unit", "propagated_rounding", "significant"]


def significant(value: float, digits: int) -> float:
    """``value`` rounded to ``digits`` significant digits (-0.0 read as 0.0): how a claim stores a value
    without a resolution, and the key the real arms' search compares by, which round-off (1e-16) does
    not move.

    >>> significant(183.99252994, 7), significant(-1e-20, 3)
    (183.9925, -1e-20)
    """
    return float(f"{float(value):.{digits}g}") + 0.0


def half_unit(decimals: int) -> float:
    """Half a unit of the last printed digit, with a hair for binary floats."""
    decimals = _checks.count("decimals", decimals, least=-300)
    return 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)


def propagated_rounding(f, x, half) -> float:
    """How far f(x) can move when each printed input x_k is off by up to half a unit of
    its last digit, ``half[k]``: sum_k |f(x + half_k e_k) - f(x - half_k e_k)| / 2, the
    first-order worst case. Used as a tolerance where a paper's outputs were computed
    from inputs it prints rounded.

    >>> round(propagated_rounding(lambda v: v[0] + 2 * v[1], [1.0, 1.0], [0.005, 0.005]), 6)
    0.015
    """
    import numpy as np

    x = np.asarray(x, dtype=float)
    half = np.broadcast_to(np.asarray(half, dtype=float), x.shape)
    total = 0.0
    for k in range(x.size):
        e = np.zeros(x.size)
        e[k] = half.flat[k]
        total += abs(float(f((x.ravel() + e).reshape(x.shape))) - float(f((x.ravel() - e).reshape(x.shape)))) / 2
    return total
