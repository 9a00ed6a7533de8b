"""The model of paper 002, shared by its routes: a rotating link balanced by a non-zero-length spring through a crank-slider dyad
(Zhang, Arakelian 2023; paper 002).

Geometry (the paper's Fig. 1, as its 002 Eqs. 1, 8 and 24 imply)::

        B  (slider 4 on the vertical line through O, height y above O)
        |\\
        | \\  rod 3, length l
        |  \\
      y |   A  (on link 2, |OA| = r, at angle phi - beta from the vertical)
        |  /
        | / r
        |/
        O ---- link 2 (COM at distance s, at angle phi from the upward vertical)

    spring 5: between the frame at O's level and the slider, length y,
    free length l0, stiffness k; energy k (y - l0)^2 / 2 (002 Eqs. 2, 7).

Angles in rad (the paper prints degrees), lengths in m, G in N, k in N/m,
energies in J, moments in N m. phi = 0 is the link pointing up; the gravity
energy is G s (1 + cos phi) (002 Eq. 1).

Two unbalanced moments are implemented side by side:

* :func:`springlab.mechanisms.dyad.algebra.unbalanced_moment_paper`: 002 Eqs. (20)-(30)
  as printed (route 1, with the synthesis of 002 Eqs. 5-19);
* :func:`springlab.mechanisms.dyad.geometry.unbalanced_moment`: the moment of gravity
  and spring about O by virtual work, -dP/dphi of the total potential energy (route 2).
  Route 3 (:mod:`~springlab.mechanisms.dyad.simulation`) drives the linkage in exudyn.

They differ in the spring's share by cos^2(theta) (theta = angle OBA): 002 Eq. (26)
takes the rod's force as F_sp cos(theta), but a slider guided along OB passes the
spring force F_sp to the rod as F_sp / cos(theta).
"

References
----------
Zhang, Y., Arakelian, V. (2023). Design and Synthesis of the Gravity Compensator with a
Non-zero Length Spring (no DOI printed in the text).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab._checks import positive
from springlab.errors import GeometryError, SpringlabError


@dataclass(frozen=True)
class Compensator:
    """The link and the spring: weight G (N), COM distance s (m), stiffness k (N/m),
    free length l0 (m)."""

    G: float
    s: float
    k: float
    l0: float

    def __post_init__(self):
        for name in ("G", "s", "k"):
            positive(name, getattr(self, name))
        positive("l0", self.l0, allow_zero=True)

    def gravity_energy(self, phi) -> np.ndarray:
        """P_G = G s (1 + cos phi) (002 Eq. 1), J."""
        return self.G * self.s * (1.0 + np.cos(check_phi(phi)))

    def gravity_moment(self, phi) -> np.ndarray:
        """The moment of gravity about O, G s sin(phi) (N m), positive towards larger phi
        (the paper's 002 Eq. 20 prints it as M_G = -G s sin(phi))."""
        return self.G * self.s * np.sin(check_phi(phi))


@dataclass(frozen=True)
class Dyad:
    """The crank-slider dyad: r = |OA| (m), l = |AB| (m), beta (rad)."""

    r: float
    l: float  # noqa: E741 - the paper's symbol
    beta: float

    def __post_init__(self):
        positive("r", self.r, unit="m")
        positive("l", self.l, unit="m")
        _checks.finite("beta", self.beta, "rad")


def check_pair(comp, dyad) -> None:
    """Raise unless ``comp`` is a :class:`Compensator` and ``dyad`` a :class:`Dyad`."""
    _checks.instance("comp", comp, Compensator, "Compensator(G, s, k, l0)")
    _checks.instance("dyad", dyad, Dyad, "Dyad(r, l, beta)")


def check_phi(phi) -> np.ndarray:
    """Link angles phi (rad): finite, at least one, in any array shape."""
    out = _checks.real_array("phi", phi, finite_only=False)
    if out.size == 0:
        raise SpringlabError("phi is empty: give at least one link angle (rad)")
    if not np.all(np.isfinite(out)):
        raise SpringlabError("phi contains NaN or infinity: link angles must be finite (rad)")
    return out


def closing(dyad: Dyad, phi) -> tuple[np.ndarray, np.ndarray]:
    _checks.instance("dyad", dyad, Dyad, "Dyad(r, l, beta)")
    phi = check_phi(phi)
    u = phi - dyad.beta
    horizontal = dyad.r * np.sin(u)
    if np.any(np.abs(horizontal) >= dyad.l):
        worst = np.degrees(np.atleast_1d(phi)[np.argmax(np.abs(np.atleast_1d(horizontal)))])
        raise GeometryError(
            f"l = {dyad.l:.6g} m <= r |sin(phi - beta)| at phi = {worst:.6g} deg: the dyad cannot close "
            "(or sits at a dead centre); choose l > r or keep phi - beta away from +-90 deg")
    return u, np.sqrt(dyad.l**2 - horizontal**2)  # l cos(theta)


def slider_height(dyad: Dyad, phi) -> np.ndarray:
    """y = r cos(phi - beta) + sqrt(l^2 - r^2 sin^2(phi - beta)) (002 Eq. 24), m."""
    u, l_cos_theta = closing(dyad, phi)
    return dyad.r * np.cos(u) + l_cos_theta
