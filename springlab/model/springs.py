"""Springs attached on the joint lines (Juang, Jhuang, Chen 2023, 000 Eq. 19 and Fig. 6).

A spring S(i, j), i < j, joins link i (proximally attached) to link j (distally
attached). Its ends lie on the links' joint lines (principle P1, 000 Eq. 38):

* end A on link i, at signed distance ``a`` from link i's **distal** joint,
  measured along x_i: A = J_i + a x_i;
* end B on link j, at signed distance ``b`` from link j's **proximal** joint,
  measured along x_j: B = J_{j-1} + b x_j.

So the spring vector is B - A = -a x_i + b x_j + sum_{t=i+1}^{j-1} r_t x_t
(000 Eq. 19), and the paper's sign patterns read::

             link i                         link j
    o----------------o~ ~ ~ ~ ~ ~ ~ ~ o----------------o
    prox.       J_i (distal)     J_{j-1} (prox.)       distal
          a < 0  |  a > 0                 b < 0  |  b > 0
     A on link i | A on an extension       B on an | B on link j
                 | of link i past J_i      extension of link j behind J_{j-1}

    ground link 1: J_1 is the base joint and x_1 points up, so a > 0 is above it.

A pattern is written (sign a, sign b): the example arm of 000 uses S(1,4) (+,+)
and S(3,4) (-,-). Stiffness k is in N/m; a, b in m. Springs are zero-free-length
unless ``free_length`` (m) or ``initial_tension`` (N) is given; the quadratic form of 000
holds only for zero-free-length springs.

A real helical extension spring pulls with F = F_i + k (l - L_0) once it is stretched past
its free length L_0 (F_i, the initial tension it was wound with): along its working range
that is a spring of stiffness k whose force vanishes at the **effective free length**
l_0 = L_0 - F_i / k (:attr:`Spring.effective_free_length`), which is zero exactly when
F_i = k L_0, the classical zero-length spring (:mod:`springlab.design.buildable`).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError


def sign_char(value: float) -> str:
    """'+' for a positive number, '-' for a negative one, '0' for zero."""
    value = _checks.number("value", value)
    if np.isnan(value):
        raise SpringlabError("value is NaN: it has no sign")
    return "+" if value > 0 else "-" if value < 0 else "0"


def _check_force_law(spring) -> None:
    """Validate and store a spring's k (N/m, > 0), free_length (m, >= 0) and initial_tension (N, >= 0),
    each finite, naming the spring by its label (:class:`Spring` and :class:`PointSpring` share them)."""
    k = _checks.number(f"k of {spring.label}", spring.k)
    if not (np.isfinite(k) and k > 0):
        raise SpringlabError(f"k of {spring.label} must be a finite stiffness > 0 N/m, got {spring.k}")
    object.__setattr__(spring, "k", k)
    free = _checks.number(f"free_length of {spring.label}", spring.free_length)
    if not (np.isfinite(free) and free >= 0):
        raise SpringlabError(f"free_length of {spring.label} must be >= 0 m, got {spring.free_length}")
    object.__setattr__(spring, "free_length", free)
    pull = _checks.number(f"initial_tension of {spring.label}", spring.initial_tension)
    if not (np.isfinite(pull) and pull >= 0):
        raise SpringlabError(
            f"initial_tension of {spring.label} must be a finite force >= 0 N, got {spring.initial_tension}")
    object.__setattr__(spring, "initial_tension", pull)


@dataclass(frozen=True)
class Spring:
    """A spring S(i, j) on the joint lines of links i < j.

    :ivar i: proximally attached link (1 = ground)
    :ivar j: distally attached link
    :ivar a: signed distance of end A from link i's distal joint along x_i (m)
    :ivar b: signed distance of end B from link j's proximal joint along x_j (m)
    :ivar k: stiffness (N/m), > 0
    :ivar free_length: free length L_0 (m), >= 0; 0 (with no initial tension) is an ideal
        zero-free-length spring
    :ivar initial_tension: the force F_i (N), >= 0, the spring pulls with at its free length
        (an extension spring wound with its coils pressed together); the force is
        F_i + k (l - L_0), valid for l >= L_0

    >>> Spring(1, 2, a=0.15, b=0.24, k=294.0).pattern
    '(+,+)'
    >>> Spring(1, 2, a=0.15, b=0.24, k=0.0)
    Traceback (most recent call last):
    ...
    springlab.errors.SpringlabError: k of S(1,2) must be a finite stiffness > 0 N/m, got 0.0
    """

    i: int
    j: int
    a: float
    b: float
    k: float
    free_length: float = 0.0
    initial_tension: float = 0.0

    def __post_init__(self):
        for name in ("i", "j"):
            object.__setattr__(self, name, _checks.count(
                f"spring link index {name}", getattr(self, name), least=1, why=" (S(i,j) needs 1 <= i < j)"))
        if not (1 <= self.i < self.j):
            raise SpringlabError(
                f"a spring S(i,j) needs 1 <= i < j (link 1 is the ground), got i={self.i}, j={self.j}"
            )
        for name in ("a", "b"):
            object.__setattr__(self, name, _checks.finite(f"{name} of {self.label}", getattr(self, name), "m"))
        _check_force_law(self)

    @property
    def label(self) -> str:
        return f"S({self.i},{self.j})"

    @property
    def pattern(self) -> str:
        """The sign pattern '(sign a, sign b)' of 000 Section 3.2."""
        return f"({sign_char(self.a)},{sign_char(self.b)})"

    @property
    def effective_free_length(self) -> float:
        """L_0 - F_i / k (m): the length at which the spring's force F_i + k (l - L_0) would
        vanish; negative when the initial tension exceeds k L_0."""
        return self.free_length - self.initial_tension / self.k

    @property
    def ideal(self) -> bool:
        """True for a zero-free-length spring (no free length, no initial tension)."""
        return self.free_length == 0 and self.initial_tension == 0

    def scaled(self, factor: float) -> Spring:
        """The same spring with its force law multiplied by ``factor`` (stiffness and initial
        tension; the free length kept)."""
        return Spring(self.i, self.j, self.a, self.b, self.k * factor, self.free_length, self.initial_tension * factor)


@dataclass(frozen=True)
class PointSpring:
    """A spring between two points fixed in two bodies of a :class:`~springlab.model.revolute.RevoluteChain`:
    the general spring, attached anywhere (the papers' springs on the joint lines are special
    cases: :func:`springlab.model.chain.point_springs`). Its field names are the contract of ``springlab design --json``.

    :ivar link_a: the body of end A (its name)
    :ivar point_a: end A (m), in link_a's frame (a URDF link's own frame)
    :ivar link_b: the body of end B
    :ivar point_b: end B (m), in link_b's frame
    :ivar k: stiffness (N/m), > 0
    :ivar free_length: free length L_0 (m), >= 0
    :ivar initial_tension: the pull F_i (N), >= 0, at the free length: the force is F_i + k (l - L_0)
    :ivar pulley_radius: rho (m), >= 0: 0 for a spring from A to B (or a cable over a point pulley);
        else the spring is mounted on link_a and its cable arrives at A along ``lead`` and runs over a
        pulley of this radius centred at A (swivelling about ``lead`` so that its plane holds B) to
        B: l is then the cable's path (:func:`springlab.energy.geometry.cable_geometry`)
    :ivar lead: with a pulley, the unit direction (in link_a's frame) along which the cable arrives
        at A

    >>> PointSpring("base", (0, 0, 0.1), "upper_arm", (0.2, 0, 0), k=500.0).label
    'base-upper_arm'
    """

    link_a: str
    point_a: tuple
    link_b: str
    point_b: tuple
    k: float
    free_length: float = 0.0
    initial_tension: float = 0.0
    pulley_radius: float = 0.0
    lead: tuple | None = None

    def __post_init__(self):
        for name in ("link_a", "link_b"):
            value = getattr(self, name)
            if not (isinstance(value, str) and value):
                raise SpringlabError(f"{name} must name a body (a link's name), got {value!r}")
        if self.link_a == self.link_b:
            raise SpringlabError(f"a spring joins two bodies; both ends are on {self.link_a!r}")
        for name in ("point_a", "point_b"):
            p = _checks.real_array(f"{name} of {self.label}", getattr(self, name), finite_only=False)
            if p.shape != (3,) or not np.all(np.isfinite(p)):
                raise SpringlabError(f"{name} of {self.label} must be 3 finite coordinates (m) in its link's frame, "
                                     f"got {getattr(self, name)!r}")
            object.__setattr__(self, name, tuple(float(v) for v in p))
        _check_force_law(self)
        rho = _checks.number(f"pulley_radius of {self.label}", self.pulley_radius)
        if not (np.isfinite(rho) and rho >= 0):
            raise SpringlabError(f"pulley_radius of {self.label} must be a finite radius >= 0 m, got {self.pulley_radius}")
        object.__setattr__(self, "pulley_radius", rho)
        if rho > 0:
            lead = _checks.real_array(f"lead of {self.label}", self.lead if self.lead is not None else (),
                                      finite_only=False)
            if lead.shape != (3,) or not np.all(np.isfinite(lead)) or not np.linalg.norm(lead) > 0:
                raise SpringlabError(f"lead of {self.label} must be a nonzero direction (3 numbers, link_a's frame) "
                                     f"along which the cable arrives at its pulley, got {self.lead!r}")
            object.__setattr__(self, "lead", tuple(float(v) for v in lead / np.linalg.norm(lead)))
        elif self.lead is not None:
            raise SpringlabError(f"lead of {self.label} is the direction of a cable over a pulley: give pulley_radius > 0 "
                                 "too, or leave lead out")

    @property
    def label(self) -> str:
        return f"{self.link_a}-{self.link_b}"

    @property
    def effective_free_length(self) -> float:
        """L_0 - F_i / k (m), as :attr:`Spring.effective_free_length`."""
        return self.free_length - self.initial_tension / self.k

    def scaled(self, factor: float) -> PointSpring:
        """The same spring with its force law multiplied by ``factor`` (stiffness and initial
        tension; the ends and the free length kept): the negative control's spring at 0.9."""
        return PointSpring(self.link_a, self.point_a, self.link_b, self.point_b, self.k * factor, self.free_length,
                           self.initial_tension * factor, self.pulley_radius, self.lead)

    def as_dict(self) -> dict:
        """The spring as the ``--json`` contract names it (SI numbers; ``pulley_radius`` and ``lead``
        only for a cable over a pulley of nonzero radius)."""
        out = {"link_a": self.link_a, "point_a": list(self.point_a), "link_b": self.link_b,
               "point_b": list(self.point_b), "k": self.k, "free_length": self.free_length,
               "initial_tension": self.initial_tension}
        if self.pulley_radius > 0:
            out |= {"pulley_radius": self.pulley_radius, "lead": list(self.lead)}
        return out


def chain_body(j: int) -> str:
    """The body name of a chain's link j in its revolute chain: 'ground' for link 1, else 'link j'."""
    return "ground" if j == 1 else f"link {j}"
