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


_LAWS = ("linear", "quintic")


def quintic(tau):
    """The rest-to-rest law s = 10 tau^3 - 15 tau^4 + 6 tau^5 on tau in [0, 1] (clipped):
    s(0) = 0, s(1) = 1, zero first and second derivatives at both ends."""
    tau = np.clip(np.asarray(tau, dtype=float), 0.0, 1.0)
    return 10 * tau**3 - 15 * tau**4 + 6 * tau**5


class Sweep:
    """Each joint angle moves from ``initial`` by ``rotation`` over ``duration`` s.

    ``law`` is the time law s(tau), tau = t / T in [0, 1]:

    * 'linear': s = tau, constant rates (000 Tables 4-5 as we read them);
    * 'quintic': s = 10 tau^3 - 15 tau^4 + 6 tau^5, which starts and ends at rest
      (zero velocity and acceleration), as a multibody simulation needs.

    Angles in rad, rates in rad/s, accelerations in rad/s^2; each method takes
    an array of times t (s) and returns shape t.shape + (n-1, 3).
    """

    def __init__(self, initial, rotation, duration: float, law: str = "quintic"):
        initial = np.asarray(initial, dtype=float)
        rotation = np.asarray(rotation, dtype=float)
        if initial.shape != rotation.shape or initial.ndim != 2 or initial.shape[1] != 3:
            raise SpringlabError(
                f"initial and rotation must both have shape (n-1, 3); got {initial.shape} and {rotation.shape}")
        if not (np.all(np.isfinite(initial)) and np.all(np.isfinite(rotation))):
            raise SpringlabError("initial and rotation must be finite angles in rad")
        if not (np.isfinite(duration) and duration > 0):
            raise SpringlabError(f"duration must be > 0 s, got {duration}")
        if law not in _LAWS:
            raise SpringlabError(f"law must be one of {_LAWS}, got {law!r}")
        self.initial, self.rotation, self.duration, self.law = initial, rotation, float(duration), law

    def _law(self, t, order: int):
        tau = np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)
        if self.law == "linear":
            value = [tau, np.ones_like(tau), np.zeros_like(tau)][order]
        else:
            value = [quintic(tau),
                     30 * tau**2 - 60 * tau**3 + 30 * tau**4,
                     60 * tau - 180 * tau**2 + 120 * tau**3][order]
        return value / self.duration**order

    def angles(self, t) -> np.ndarray:
        s = self._law(t, 0)
        return self.initial + s[..., None, None] * self.rotation

    def rates(self, t) -> np.ndarray:
        return self._law(t, 1)[..., None, None] * self.rotation

    def accelerations(self, t) -> np.ndarray:
        return self._law(t, 2)[..., None, None] * self.rotation

    def check_at_rest(self, tol: float = 1e-12) -> None:
        """Raise unless the sweep starts and ends at rest (rates and accelerations 0)."""
        for when, t in (("starts", 0.0), ("ends", self.duration)):
            worst = max(np.abs(self.rates(t)).max(), np.abs(self.accelerations(t)).max())
            if worst > tol:
                raise SpringlabError(
                    f"the trajectory does not {when[:-1]} at rest: joint rates or accelerations reach "
                    f"{worst:.3g} at t = {t:g} s; use law='quintic'")
