"""Joint-space trajectories.

:func:`linear_sweep` is the motion of 000 Tables 4-5: each angle moves from its
initial value by a given rotation, linearly in time, over the duration T. The
paper does not state the time law; a linear one is the plainest reading, and a
balanced arm's total energy is constant along any law.
"""

from __future__ import annotations

import numpy as np

from springlab.errors import SpringlabError


def linear_sweep(initial, rotation, duration: float, samples: int):
    """Angles moving linearly from ``initial`` to ``initial + rotation``.

    :param initial: array (n-1, 3) of (theta, phi, psi) in rad
    :param rotation: array (n-1, 3), the change of each angle in rad
    :param duration: T in s, > 0
    :param samples: number of time samples (>= 2), both ends included
    :returns: (t, angles): t ndarray(samples,) in s, angles ndarray(samples, n-1, 3) in rad
    """
    initial = np.asarray(initial, dtype=float)
    rotation = np.asarray(rotation, dtype=float)
    if initial.shape != rotation.shape or initial.ndim != 2 or initial.shape[1] != 3:
        raise SpringlabError(
            f"initial and rotation must both have shape (n-1, 3); got {initial.shape} and {rotation.shape}")
    if not (np.isfinite(duration) and duration > 0):
        raise SpringlabError(f"duration must be > 0 s, got {duration}")
    if int(samples) != samples or samples < 2:
        raise SpringlabError(f"samples must be an integer >= 2, got {samples}")
    t = np.linspace(0.0, duration, int(samples))
    s = (t / duration)[:, None, None]
    return t, initial[None] + s * rotation[None]
