"""The cable of a cable spring and the pulley it runs over, as a maker buys them.

A cable spring's cable (:mod:`springlab.design.buildable`) carries the spring's pull. It is chosen
from :data:`CABLES`, stainless steel wire rope (AISI 302/304) in the small sizes a hardware store or a
rigging supplier stocks, by its minimum breaking load with a safety factor of :data:`SAFETY`: the
thinnest that carries the largest pull (the least pulley). Its pulley is sized to it: a tread diameter
at least the rope maker's desired minimum ratio D / d to the cable's diameter (42 for 7 x 7, 24 for
7 x 19: a smaller pulley bends the wires harder and shortens the cable's life), rounded up to a whole
millimetre; the cable's centreline then runs at (D + d) / 2 from the axle, the radius the balance is
computed with.

The breaking loads are those of MIL-DTL-83420 (1/32 in. and larger) and, for the two finer 7 x 7
sizes, of the makers' catalogues; the masses per metre take a wire rope's metallic area as
:data:`ROPE_FILL` of its circle (1/16 in. 7 x 19: 11 g/m, as listed). Lengths in m, forces in N.

References
----------
MIL-DTL-83420M (2009). Wire Rope, Flexible, for Aircraft Control. Table I (breaking strengths).
Loos & Co. / Strand Core. Minimum tread diameter for pulleys or sheaves: D/d desired minimum 42 (6 x 7,
7 x 7) and 24 (6 x 19, 7 x 19); critical minimum 28 and 18.
Wire Rope Technical Board (2005). Wire Rope Users Manual, 4th ed.: a design factor of 5 for running ropes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from springlab import _checks
from springlab.errors import SpringlabError

SAFETY = 5.0
"""The cable's minimum breaking load over the largest pull it carries (the Wire Rope Users Manual's
design factor for running rope)."""

ROPE_FILL = 0.7
"""A wire rope's metallic area over its circle's (7 x 7 and 7 x 19): its mass per metre is this times
steel's density times pi d^2 / 4."""

STEEL = 7900.0
"""kg/m^3: stainless steel wire (AISI 302/304)."""

ALUMINIUM = 2700.0
"""kg/m^3: a pulley's sheave."""

LBF = 4.4482216152605
"""N per pound-force."""

INCH = 0.0254


@dataclass(frozen=True)
class Cable:
    """A stocked wire rope: its name, construction, diameter (m), minimum breaking load (N) and the
    rope maker's desired minimum ratio of pulley tread diameter to cable diameter."""

    name: str
    construction: str
    diameter: float
    breaking: float
    ratio: float

    @property
    def working(self) -> float:
        """The largest pull it may carry (N): its breaking load over :data:`SAFETY`."""
        return self.breaking / SAFETY

    @property
    def pulley_diameter(self) -> float:
        """The least tread diameter (m) of its pulley: ``ratio`` times its diameter, up to a whole mm."""
        return math.ceil(round(self.ratio * self.diameter * 1e3, 6)) * 1e-3

    @property
    def pulley_radius(self) -> float:
        """The radius (m) its centreline wraps at on that pulley: (D + d) / 2."""
        return (self.pulley_diameter + self.diameter) / 2

    @property
    def mass_per_length(self) -> float:
        """kg/m (:func:`rope_mass`)."""
        return rope_mass(self.diameter)

    def fits(self, pulley_radius: float) -> bool:
        """Whether a pulley whose cable wraps at ``pulley_radius`` (m) is at least its least pulley."""
        return pulley_radius >= self.pulley_radius - 1e-9

    def as_dict(self) -> dict:
        return {"name": self.name, "construction": self.construction, "diameter": self.diameter,
                "breaking_load_N": self.breaking, "working_load_N": self.working, "pulley_ratio": self.ratio}


def _cable(inch: float, construction: str, lbf: float) -> Cable:
    ratio = 42.0 if construction == "7x7" else 24.0
    mm = inch * INCH * 1e3
    return Cable(f"{mm:.2f} mm ({inch:.3g} in.) stainless {construction}", construction, inch * INCH, lbf * LBF, ratio)


CABLES = (
    _cable(0.018, "7x7", 40.0),
    _cable(0.024, "7x7", 70.0),
    _cable(1 / 32, "7x7", 110.0),
    _cable(3 / 64, "7x7", 270.0),
    _cable(1 / 16, "7x19", 480.0),
    _cable(3 / 32, "7x19", 920.0),
    _cable(1 / 8, "7x19", 1760.0),
    _cable(5 / 32, "7x19", 2400.0),
    _cable(3 / 16, "7x19", 3700.0),
)
"""Stainless wire rope stocked in small sizes: (diameter, construction, minimum breaking load)."""


def choose_cable(pull: float, *, pulley_radius: float | None = None) -> Cable:
    """The cable for a largest ``pull`` (N): of those whose working load (:attr:`Cable.working`) carries
    it, the one with the least pulley; with ``pulley_radius`` (m) given, among those that fit it.

    :raises SpringlabError: when no stocked cable carries the pull (on that pulley)
    """
    pull = _checks.positive("pull", pull, allow_zero=True, unit="N")
    fits = [c for c in CABLES if pulley_radius is None or c.fits(pulley_radius)]
    strong = [c for c in fits if c.working >= pull]
    if strong:
        return min(strong, key=lambda c: (c.pulley_diameter, c.diameter))
    if not fits:
        raise SpringlabError(f"pulley_radius = {1e3 * pulley_radius:g} mm: no stocked cable runs over it (the finest, "
                             f"{CABLES[0].name}, needs {1e3 * CABLES[0].pulley_radius:g} mm); give a larger pulley")
    best = max(fits, key=lambda c: c.working)
    where = "" if pulley_radius is None else f" that fits a {1e3 * pulley_radius:g} mm pulley"
    raise SpringlabError(f"a pull of {pull:.4g} N: no stocked cable{where} carries it with a safety factor of "
                         f"{SAFETY:g} (the strongest, {best.name}, carries {best.working:.4g} N); use springs side by "
                         "side or a larger pulley")


def cable_by_name(name: str, *, option: str = "cable") -> Cable:
    """The stocked cable named ``name`` (:data:`CABLES`; its diameter in mm, e.g. '1.59', is enough);
    ``option`` names the parameter in the message.

    :raises SpringlabError: naming the stocked cables
    """
    for c in CABLES:
        if name == c.name or (isinstance(name, str) and name.strip().removesuffix("mm").strip() == f"{c.diameter * 1e3:.2f}"):
            return c
    raise SpringlabError(f"{option} = {name!r}: give a stocked cable by its diameter in mm, one of "
                         + ", ".join(f"{c.diameter * 1e3:.2f}" for c in CABLES))


def rope_mass(diameter: float) -> float:
    """kg/m: a wire rope of ``diameter`` (m), its metallic area :data:`ROPE_FILL` of its circle."""
    return ROPE_FILL * STEEL * math.pi * diameter**2 / 4


def pulley_width(diameter: float) -> float:
    """m: the width of a pulley for a rope of ``diameter`` (m): four rope diameters, at least 4 mm."""
    return max(4 * diameter, 0.004)


def pulley_mass(cable: Cable, pulley_radius: float) -> float:
    """kg: an aluminium sheave for ``cable`` at ``pulley_radius`` (m, the cable's centreline): a disc out to
    the groove's flanges (a cable diameter beyond its centreline), as wide as four cable diameters and at
    least 4 mm."""
    return ALUMINIUM * math.pi * (pulley_radius + cable.diameter) ** 2 * pulley_width(cable.diameter)
