"""Joint-space trajectories.

:func:`linear_sweep` is the motion of 000 Tables 4-5: each angle moves from its
initial value by a given rotation, linearly in time, over the duration T. The
paper does not state the time law; a linear one is the plainest reading, and a
balanced arm's total energy is constant along any law.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError


def linear_sweep(initial, rotation, duration: float, samples: int):
    """Angles moving linearly from ``initial`` to ``initial + rotation``.

    :param initial: array (n-1, 3) of (theta, phi, psi) in rad
    :param rotation: array (n-1, 3), the change of each angle in rad
    :param duration: T in s, > 0
    :param samples: number of time samples (>= 2), both ends included
    :returns: (t, angles): t ndarray(samples,) in s, angles ndarray(samples, n-1, 3) in rad
    """
    initial = _checks.real_array("initial (angles, rad)", initial)
    rotation = _checks.real_array("rotation (angles, rad)", rotation)
    if initial.shape != rotation.shape or initial.ndim != 2 or initial.shape[1] != 3:
        raise SpringlabError(
            f"initial and rotation must both have shape (n-1, 3); got {initial.shape} and {rotation.shape}")
    duration = _checks.duration(duration)
    samples = _checks.sample_count(samples, least=2)
    _checks.memory(f"samples = {samples} poses", samples * (initial.size + 1), hint="use fewer samples")
    t = np.linspace(0.0, duration, int(samples))
    s = (t / duration)[:, None, None]
    return t, initial[None] + s * rotation[None]


_LAWS = ("linear", "quintic")


def quintic(tau):
    """The rest-to-rest law s = 10 tau^3 - 15 tau^4 + 6 tau^5 on tau in [0, 1] (clipped):
    s(0) = 0, s(1) = 1, zero first and second derivatives at both ends."""
    tau = np.clip(_checks.real_array("tau", tau), 0.0, 1.0)
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
        initial = _checks.real_array("initial (angles, rad)", initial, finite_only=False)
        rotation = _checks.real_array("rotation (angles, rad)", rotation, finite_only=False)
        if initial.shape != rotation.shape or initial.ndim != 2 or initial.shape[1] != 3:
            raise SpringlabError(
                f"initial and rotation must both have shape (n-1, 3); got {initial.shape} and {rotation.shape}")
        if not (np.all(np.isfinite(initial)) and np.all(np.isfinite(rotation))):
            raise SpringlabError("initial and rotation must be finite angles in rad")
        duration = _checks.duration(duration)
        if law not in _LAWS:
            raise SpringlabError(f"law must be one of {_LAWS}, got {law!r}")
        self.initial, self.rotation, self.duration, self.law = initial, rotation, float(duration), law

    def _law(self, t, order: int):
        tau = np.clip(_checks.real_array("t (times, s)", t) / self.duration, 0.0, 1.0)
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


# --- 001 Eq. (26): rest-to-rest cubics, held before and after -------------------------
def rest_to_rest_cubic(t_I: float, t_F: float, theta_I: float, theta_F: float) -> np.ndarray:
    """Coefficients (a_0, a_1, a_2, a_3) of the cubic in absolute time t (s) that goes
    from theta_I at t_I to theta_F at t_F with zero rate at both ends (001 Eq. 26)."""
    t_I, t_F = _checks.finite("t_I", t_I, "s"), _checks.finite("t_F", t_F, "s")
    theta_I, theta_F = _checks.finite("theta_I", theta_I, "rad"), _checks.finite("theta_F", theta_F, "rad")
    if not t_F > t_I:
        raise SpringlabError(f"need t_F > t_I (s), got t_I = {t_I}, t_F = {t_F}")
    T, delta = t_F - t_I, theta_F - theta_I
    # theta = theta_I + delta (3 u^2 - 2 u^3), u = (t - t_I) / T, expanded in powers of t
    c2, c3 = 3 * delta / T**2, -2 * delta / T**3
    return np.array([theta_I + c2 * t_I**2 - c3 * t_I**3,
                     -2 * c2 * t_I + 3 * c3 * t_I**2,
                     c2 - 3 * c3 * t_I,
                     c3])


class PiecewiseCubic:
    """001 Eq. (26): joint i holds theta_I before t_I, follows a_0 + a_1 t + a_2 t^2 +
    a_3 t^3 from t_I to t_F, and holds theta_F after.

    :param rows: (n, 4) of t_I, t_F (s), theta_I, theta_F (rad)
    :param coefficients: (n, 4) of a_0..a_3 in absolute time; None: the rest-to-rest
        cubic of each row (:func:`rest_to_rest_cubic`)

    >>> traj = PiecewiseCubic([[0.0, 2.0, 0.0, 1.0]])
    >>> [round(float(traj.angles(t)[0]), 6) for t in (0.0, 1.0, 2.0, 3.0)]
    [0.0, 0.5, 1.0, 1.0]
    """

    def __init__(self, rows, coefficients=None):
        rows = _checks.real_array("rows", rows, finite_only=False)
        if rows.ndim != 2 or rows.shape[1] != 4 or not np.all(np.isfinite(rows)):
            raise SpringlabError(f"rows must be finite with shape (n, 4): t_I, t_F, theta_I, theta_F; got {rows.shape}")
        for k, (t_I, t_F, _, _) in enumerate(rows):
            if not t_F > t_I:
                raise SpringlabError(f"row {k + 1}: t_F = {t_F} s must be after t_I = {t_I} s")
        if coefficients is None:
            coefficients = np.array([rest_to_rest_cubic(*row) for row in rows])
        coefficients = np.asarray(coefficients, dtype=float)
        if coefficients.shape != (rows.shape[0], 4) or not np.all(np.isfinite(coefficients)):
            raise SpringlabError(f"coefficients must be finite with shape ({rows.shape[0]}, 4), got {coefficients.shape}")
        self.rows, self.coefficients = rows, coefficients

    def _eval(self, t, order: int) -> np.ndarray:
        t = _checks.real_array("t (times, s)", t)[..., None]
        t_I, t_F, th_I, th_F = self.rows.T
        a0, a1, a2, a3 = self.coefficients.T
        inside = (t >= t_I) & (t < t_F)
        if order == 0:
            cubic = a0 + a1 * t + a2 * t**2 + a3 * t**3
            return np.where(t < t_I, th_I, np.where(inside, cubic, th_F))
        cubic = a1 + 2 * a2 * t + 3 * a3 * t**2 if order == 1 else 2 * a2 + 6 * a3 * t
        return np.where(inside, cubic, 0.0)

    def angles(self, t) -> np.ndarray:
        """Joint angles (rad), shape t.shape + (n,)."""
        return self._eval(t, 0)

    def rates(self, t) -> np.ndarray:
        """Joint rates (rad/s) inside the cubic segments, 0 outside."""
        return self._eval(t, 1)

    def accelerations(self, t) -> np.ndarray:
        """Joint accelerations (rad/s^2) inside the cubic segments, 0 outside."""
        return self._eval(t, 2)

    def endpoint_errors(self) -> np.ndarray:
        """(n, 2): cubic(t_I) - theta_I and cubic(t_F) - theta_F (rad): the jumps
        001 Eq. (26) makes at t_I and t_F when a row's coefficients miss its own endpoints."""
        a = self.coefficients
        out = np.zeros((len(a), 2))
        for k, (t_I, t_F, th_I, th_F) in enumerate(self.rows):
            out[k] = np.polyval(a[k, ::-1], [t_I, t_F]) - [th_I, th_F]
        return out
