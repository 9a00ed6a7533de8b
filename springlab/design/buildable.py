"""From ideal to buildable: a helical extension spring a shop can wind for each ideal spring.

A design's springs are zero-free-length: force k l at every length l between the ends.
No stock spring does that. Two realisations, both from standard wire sizes:

* **zero-length spring**: an extension spring wound with initial tension F_i equal to k
  times its free length L_0 pulls F_i + k (l - L_0) = k l once stretched past L_0 (the
  classical zero-length spring). It must never be shorter than L_0 over the workspace,
  and the initial tension must be one a maker can wind: for a spring index C = D/d the
  uncorrected stress 8 F_i D / (pi d^3) lies in the preferred range
  231 exp(-0.105 C) -/+ 6.9 (4 - (C - 3) / 6.5) MPa (Shigley, Section 10-11). Since
  F_i = k L_0 and L_0 holds at least the body's coils, that stress is at least about
  G / (pi C^2): 180 MPa for music wire at C = 12, where makers wind at most 84 MPa. So
  with standard winding this realisation fails for every index from 4 to 12, and
  :func:`zero_length_spring` says so with the numbers; a maker who winds above the range
  (as for instruments) can pass a wider one;
* **cable over a pulley**: the spring is mounted along link i and a cable from its moving
  end runs over a pulley at end A to end B. Cut so that its length absorbs L_0 - F_i / k,
  the cable makes the force k times the cable's path from the pulley to B, which is
  |B - A| for a point pulley; any initial tension in the preferred range will do. A pulley
  of radius rho adds rho times the wrap angle to the path
  (:mod:`springlab.energy.pulley`); its effect on the balance is reported.

Either way the spring must carry the largest force over the workspace, k times the longest
length, with its body's torsional stress, corrected by the Wahl factor
K_W = (4C - 1)/(4C - 4) + 0.615/C, at most the allowable share of the wire's tensile
strength S_ut = A / d^m (music wire and chrome silicon 45 %, stainless 35 %, static service). The rate is
k = d^4 G / (8 D^3 N_a), with N_a = N_b + G / E active coils for N_b body coils and two
machine hooks, and the free length inside the hooks L_0 = (2 C - 1 + N_b) d.

:func:`realise` picks, per spring of a design, the realisation that fits (the smallest
wire that does); :func:`balance_loss` measures the holding torque the built springs leave
(route 2, with the pulleys' radii) as built and with the maker's tolerances; the spec
sheet (:func:`spec_sheet`) is the table to hand to a spring maker. Lengths in m unless a
column says mm; forces in N; stresses in Pa (MPa in tables).

References
----------
Budynas, R. G., Nisbett, J. K. Shigley's Mechanical Engineering Design, 10th ed. McGraw-Hill,
2015. Chapter 10 (Mechanical Springs): Section 10-2 (stresses, the Wahl factor), 10-3 (the
rate), 10-4 (spring materials: Table 10-4, the constants A and m of S_ut = A / d^m, and
Table 10-5, G and E), 10-11 (extension springs: free length, active coils, the preferred
range of initial tension, Table 10-7, the allowable stresses).
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from springlab import _checks
from springlab.energy.geometry import holding_torques, spring_length
from springlab.energy.pulley import cable_path, holding_torques_with_pulleys
from springlab.errors import SpringlabError
from springlab.model.chain import Chain, check_springs
from springlab.model.springs import Spring
from springlab.tables import Table

STEEL_DENSITY = 7800.0
"""kg/m^3: spring steel (Shigley, Table A-5: carbon steel's unit weight 76.5 kN/m^3, stainless steel's 76.0,
so 7800 and 7750 kg/m^3; music wire and stainless alike to within 1 %)."""

INDEX_RANGE = (4.0, 12.0)
"""Spring indices C = D / d a maker winds without trouble (Shigley, Section 10-2)."""

CABLE_RADIUS = 0.0006
"""m: the cable of the cable realisation (1.2 mm steel cable), for the clearance."""

PULLEY_RADIUS = 0.01
"""m: the default pulley (a 20 mm sheave, about 15 times a 1.2 mm steel cable)."""

STRETCH_MARGIN = 0.8
"""A cable spring's initial tension is at most this share of its force at the shortest path, so that
it stays stretched past its free length there (by 20 % of that force) when built within tolerance."""

MIN_BODY_COILS = 3.0
"""Fewest body coils of a realised spring (fewer make a ring, not a spring)."""

STRESS_SHARE = 0.85
"""A realised spring's body stress at its largest force is at most this share of the allowable: the
sheet designs to a margin of 1 / 0.85 = 1.18 on the allowable stress, room for the maker's
tolerances on the wire and coil diameters (the stress goes as D / d^3) and on the rate."""

HOOK_BEND = 2.5
"""A machine hook's bend where it leaves the body: its mean radius r_2, in wire diameters (C_2 = 2 r_2 / d
= 5; Shigley, Section 10-11, asks C_2 > 4). The hook itself (A) is a full loop of the coil's mean radius
(r_1 = D / 2, C_1 = C)."""

ZIMMERLI = (241e6, 379e6)
"""Pa: Zimmerli's endurance of unpeened spring wire under 10 mm, whatever the steel: an alternating shear
stress S_sa = 241 MPa (35 kpsi) about a mean S_sm = 379 MPa (55 kpsi), for unlimited life (Shigley,
Section 10-9)."""

ENDURANCE_CYCLES = 1e7
"""The cycles Zimmerli's endurance is read as lasting (Shigley's fatigue tables end at 10^7): a spring whose
every fatigue factor is at least 1 is rated for them, and for any fewer."""


@dataclass(frozen=True)
class Material:
    """A spring wire: S_ut = A / d^m per diameter band (d in mm, A in MPa mm^m), moduli per
    band, the allowable share of S_ut for an extension spring's body in static service, and the
    wire diameters stocked (mm)."""

    name: str
    standard: str
    strength: tuple  # (d_min_mm, d_max_mm, A_MPa_mm^m, m)
    moduli: tuple  # (d_max_mm, G_Pa, E_Pa): the first band with d <= d_max
    body_allowable: float
    diameters_mm: tuple
    end_torsion: float = 0.40  # the hook's allowable torsion (at B) and bending (at A), shares of S_ut in static
    end_bending: float = 0.75  # service (Shigley, Table 10-7: carbon and low-alloy steels 40 and 75 %)

    def _band(self, d: float):
        mm = d * 1e3
        for lo, hi, A, m in self.strength:
            if lo - 1e-9 <= mm <= hi + 1e-9:
                return A, m
        raise SpringlabError(f"wire diameter {mm:g} mm is outside {self.name}'s range "
                             f"({self.strength[0][0]:g}-{self.strength[-1][1]:g} mm): choose a stocked diameter")

    def tensile_strength(self, d: float) -> float:
        """S_ut = A / d^m (Pa) of wire of diameter ``d`` (m) (Shigley, Table 10-4)."""
        A, m = self._band(d)
        return A / (d * 1e3) ** m * 1e6

    def moduli_at(self, d: float) -> tuple[float, float]:
        """(G, E) in Pa of wire of diameter ``d`` (m) (Shigley, Table 10-5)."""
        self._band(d)
        for d_max, G, E in self.moduli:
            if d * 1e3 <= d_max + 1e-9:
                return G, E
        return self.moduli[-1][1:]


_PREFERRED_MM = (0.10, 0.12, 0.16, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50, 0.55, 0.60, 0.65, 0.70, 0.80, 0.90,
                 1.00, 1.10, 1.20, 1.40, 1.60, 1.80, 2.00, 2.20, 2.50, 2.80, 3.00, 3.50, 4.00, 4.50, 5.00, 5.50,
                 6.00, 6.50, 7.00, 8.00, 9.00, 10.0)

MATERIALS = {
    "music wire": Material("music wire", "ASTM A228", ((0.10, 6.5, 2211.0, 0.145),),
                           ((0.8, 82.7e9, 203.4e9), (1.6, 81.7e9, 200.0e9), (3.0, 81.0e9, 196.5e9),
                            (1e9, 80.0e9, 193.0e9)), 0.45,
                           tuple(d for d in _PREFERRED_MM if d <= 6.5)),
    "stainless 302": Material("stainless 302", "ASTM A313", ((0.3, 2.5, 1867.0, 0.146), (2.5, 5.0, 2065.0, 0.263),
                                                              (5.0, 10.0, 2911.0, 0.478)),
                              ((1e9, 69.0e9, 193.0e9),), 0.35,
                              tuple(d for d in _PREFERRED_MM if 0.3 <= d <= 10.0), 0.30, 0.55),
    "chrome silicon": Material("chrome silicon", "ASTM A401", ((1.6, 9.5, 1974.0, 0.108),),
                               ((1e9, 77.2e9, 203.4e9),), 0.45,
                               tuple(d for d in _PREFERRED_MM if 1.6 <= d <= 9.5)),
}
"""The wires offered: music wire (the strongest common spring wire, stocked to 6.5 mm), one stainless grade,
and chrome-silicon wire, the valve-spring steel stocked to 9.5 mm for springs too strong for music wire (its
body allowed 45 % of S_ut, the low end of Table 10-7's 45-50 % for hardened and tempered low-alloy steel)."""

AUTO = "auto"
"""A material choice: music wire, and chrome silicon where that saves a side-by-side spring or a pulley
block (:func:`~springlab.design.realise.coil_for`)."""


def wires(material: str) -> tuple[str, ...]:
    """The wires a material choice tries, in order: ``'auto'`` music wire then chrome silicon; else the one
    named (a :data:`MATERIALS` key)."""
    if material == AUTO:
        return ("music wire", "chrome silicon")
    if not isinstance(material, str) or material not in MATERIALS:
        raise SpringlabError(f"material = {material!r}: give one of {', '.join(map(repr, MATERIALS))} or 'auto' "
                             "(music wire, chrome silicon where that saves a coil or a pulley block)")
    return (material,)


def _index(name: str, C) -> np.ndarray:
    C = _checks.real_array(name, C)
    if np.any(C <= 1):
        raise SpringlabError(f"{name} (a spring index D / d) must be above 1, got {np.min(C):g}")
    return C


def _strong(mat: Material, d: float, C, K, force: float):
    """Whether springs of wire ``d`` (m) at indices ``C`` (Wahl factors ``K``) carry ``force`` (N) within
    :data:`STRESS_SHARE` of each allowable: the body's, and a machine hook's bending and torsion
    (:meth:`ExtensionSpring.hook_stresses`, the same formulas on arrays)."""
    C = np.asarray(C, dtype=float)
    Sut = mat.tensile_strength(d)
    body = K * 8 * force * C / (np.pi * d**2)
    bending, torsion = _hook_stresses(force, d, C * d, C, 2 * HOOK_BEND)
    return ((body <= STRESS_SHARE * mat.body_allowable * Sut) & (bending <= STRESS_SHARE * mat.end_bending * Sut)
            & (torsion <= STRESS_SHARE * mat.end_torsion * Sut))


def _hook_stresses(F, d: float, D, C1, C2) -> tuple:
    """(sigma_A, tau_B) Pa of machine hooks of indices ``C1`` (the hook, 2 r_1 / d) and ``C2`` (its root,
    2 r_2 / d) on a coil of wire ``d`` and mean diameter ``D`` (m) under force ``F`` (N), any of them arrays
    (:meth:`ExtensionSpring.hook_stresses`)."""
    KA = (4 * C1**2 - C1 - 1) / (4 * C1 * (C1 - 1))
    KB = (4 * C2 - 1) / (4 * C2 - 4)
    return F * (KA * 16 * D / (np.pi * d**3) + 4 / (np.pi * d**2)), KB * 8 * F * D / (np.pi * d**3)


def _gerber(a: float, m: float, Se: float, Su: float) -> float:
    """Gerber's factor of safety for an alternating stress ``a`` about a mean ``m`` (Pa), endurance ``Se`` and
    ultimate strength ``Su`` (Pa) (Shigley, Section 10-9); inf for no alternation."""
    if a <= 0:
        return float("inf")
    return float(0.5 * (Su / m) ** 2 * (a / Se) * (-1 + np.sqrt(1 + (2 * m * Se / (Su * a)) ** 2))) if m > 0 else Se / a


def wahl_factor(C):
    """K_W = (4C - 1)/(4C - 4) + 0.615/C: the body's stress concentration at index C (Shigley, Section 10-2)."""
    C = _index("C", C)
    return (4 * C - 1) / (4 * C - 4) + 0.615 / C


def initial_tension_stress_range(C):
    """(low, high) uncorrected stress 8 F_i D / (pi d^3) (Pa) of the initial tension a maker
    winds at index C: 231 exp(-0.105 C) -/+ 6.9 (4 - (C - 3) / 6.5) MPa (Shigley, Section 10-11)."""
    C = _index("C", C)
    mid, half = 231.0 * np.exp(-0.105 * C), 6.9 * (4.0 - (C - 3.0) / 6.5)
    return (mid - half) * 1e6, (mid + half) * 1e6


OPEN_GAP = 0.25
"""An open-wound coil's gap between its body coils, as a share of the wire's diameter (its pitch d (1 + gap))."""


@dataclass(frozen=True)
class OpenCoil:
    """An extension spring's open-wound alternative (:meth:`ExtensionSpring.open_coil`): its body coils'
    pitch, free length (inside the hooks), the cable offset that takes up that free length, and its longest
    length in service (m)."""

    pitch: float
    free_length: float
    cable_offset: float
    max_length: float


@dataclass(frozen=True)
class ExtensionSpring:
    """A helical extension spring with two machine hooks.

    :ivar material: a :data:`MATERIALS` key
    :ivar wire: wire diameter d (m)
    :ivar mean_diameter: mean coil diameter D (m)
    :ivar body_coils: N_b
    :ivar initial_tension: F_i (N)
    :ivar max_length: the longest it is stretched in service (m, inside the hooks)
    """

    material: str
    wire: float
    mean_diameter: float
    body_coils: float
    initial_tension: float
    max_length: float

    def __post_init__(self):
        _material(self.material)
        for name, unit in (("wire", "m"), ("mean_diameter", "m"), ("body_coils", ""), ("max_length", "m")):
            object.__setattr__(self, name, _checks.positive(name, getattr(self, name), unit=unit))
        object.__setattr__(self, "initial_tension",
                           _checks.positive("initial_tension", self.initial_tension, allow_zero=True, unit="N"))
        if self.mean_diameter <= self.wire:
            raise SpringlabError(f"mean_diameter = {self.mean_diameter:g} m must exceed the wire's {self.wire:g} m")

    @property
    def wire_material(self) -> Material:
        return MATERIALS[self.material]

    @property
    def index(self) -> float:
        """C = D / d."""
        return self.mean_diameter / self.wire

    @property
    def active_coils(self) -> float:
        """N_a = N_b + G / E (the hooks' share, Shigley, Section 10-11)."""
        G, E = self.wire_material.moduli_at(self.wire)
        return self.body_coils + G / E

    @property
    def rate(self) -> float:
        """k = d^4 G / (8 D^3 N_a) (N/m)."""
        G, _ = self.wire_material.moduli_at(self.wire)
        return self.wire**4 * G / (8 * self.mean_diameter**3 * self.active_coils)

    @property
    def free_length(self) -> float:
        """L_0 = (2 C - 1 + N_b) d (m), inside the hooks."""
        return (2 * self.index - 1 + self.body_coils) * self.wire

    @property
    def outer_diameter(self) -> float:
        return self.mean_diameter + self.wire

    @property
    def cable_offset(self) -> float:
        """L_0 - F_i / k (m): what a cable realisation adds to its path so that the coil pulls k times the
        path (the coil's length is the path plus this)."""
        return self.free_length - self.initial_tension / self.rate

    def open_coil(self, gap: float = None) -> OpenCoil:
        """The same wire, coil diameter, body coils and rate wound open, with no initial tension: the
        alternative for a cable spring whose initial tension lies below the windable range. Its body coils
        stand ``gap`` (a share of the wire, :data:`OPEN_GAP`) apart, so its free length grows by
        (N_b - 1) gap d; its cable absorbs that whole free length, L_0' (the coil pre-stretched at assembly, and
        stretched everywhere in service, as long as the path is), so the force is k times the path as
        before. It is then F_i / k + (N_b - 1) gap d longer in service than the closed coil, at the same
        force and stress."""
        gap = OPEN_GAP if gap is None else _checks.positive("gap", gap, unit="of the wire's diameter")
        grown = (self.body_coils - 1) * gap * self.wire
        free = self.free_length + grown
        return OpenCoil(pitch=self.wire * (1 + gap), free_length=free, cable_offset=free,
                        max_length=self.max_length + self.initial_tension / self.rate + grown)

    @property
    def mass(self) -> float:
        """The spring's mass (kg): its wire, pi d^2 / 4 times its length pi D (N_b + 2) (the body coils and a
        full loop for each machine hook), at :data:`STEEL_DENSITY`."""
        return STEEL_DENSITY * np.pi * self.wire**2 / 4 * np.pi * self.mean_diameter * (self.body_coils + 2)

    def force(self, length):
        """F_i + k (l - L_0) (N) at lengths ``length`` (m) >= L_0."""
        length = np.asarray(length, dtype=float)
        if np.any(length < self.free_length * (1 - 1e-12)):
            raise SpringlabError(f"an extension spring of free length {self.free_length * 1e3:.2f} mm cannot be "
                                 f"shorter than it (got {np.min(length) * 1e3:.2f} mm): its coils are closed")
        return self.initial_tension + self.rate * (length - self.free_length)

    @property
    def max_force(self) -> float:
        return float(self.force(self.max_length))

    def stress(self, force):
        """The body's torsional stress K_W 8 F D / (pi d^3) (Pa) under ``force`` (N)."""
        return wahl_factor(self.index) * 8 * np.asarray(force, dtype=float) * self.mean_diameter / (np.pi * self.wire**3)

    @property
    def allowable_stress(self) -> float:
        """The allowable body stress in static service (Pa): the material's share of S_ut."""
        return self.wire_material.body_allowable * self.wire_material.tensile_strength(self.wire)

    @property
    def initial_tension_range(self) -> tuple[float, float]:
        """The preferred initial tension (N) at this index (:func:`initial_tension_stress_range`); more
        cannot be wound, less is wound with the coils just touching."""
        lo, hi = initial_tension_stress_range(self.index)
        per = np.pi * self.wire**3 / (8 * self.mean_diameter)
        return float(max(lo, 0.0) * per), float(hi * per)

    def hook_stresses(self, force, *, r1: float | None = None, r2: float | None = None) -> tuple:
        """(sigma_A, tau_B) Pa under ``force`` (N): the hook's bending stress where it turns,
        F ((K)_A 16 D / (pi d^3) + 4 / (pi d^2)) with (K)_A = (4 C_1^2 - C_1 - 1) / (4 C_1 (C_1 - 1)), and its
        torsion where it leaves the body, (K)_B 8 F D / (pi d^3) with (K)_B = (4 C_2 - 1) / (4 C_2 - 4),
        C_1 = 2 r_1 / d and C_2 = 2 r_2 / d (Shigley, Section 10-11). Where extension springs break. A
        machine hook by default: r_1 = D / 2 (m), r_2 = :data:`HOOK_BEND` d."""
        F = np.asarray(force, dtype=float)
        d, D = self.wire, self.mean_diameter
        r1 = D / 2 if r1 is None else _checks.positive("r1", r1, unit="m")
        r2 = HOOK_BEND * d if r2 is None else _checks.positive("r2", r2, unit="m")
        C1, C2 = 2 * r1 / d, 2 * r2 / d
        if min(C1, C2) <= 1:
            raise SpringlabError(f"a hook's bend radius of {1e3 * min(r1, r2):g} mm is no more than half the "
                                 f"{1e3 * d:g} mm wire: give r1, r2 above d / 2")
        return _hook_stresses(F, d, D, C1, C2)

    @property
    def hook_allowables(self) -> tuple[float, float]:
        """(bending at A, torsion at B) Pa: the hook's allowable stresses in static service, the wire's shares
        of S_ut (:class:`Material`'s ``end_bending``, ``end_torsion``)."""
        Sut = self.wire_material.tensile_strength(self.wire)
        return self.wire_material.end_bending * Sut, self.wire_material.end_torsion * Sut

    def fatigue(self, low: float, high: float, *, r1: float | None = None, r2: float | None = None) -> dict:
        """Gerber's factors of safety in fatigue of a spring cycled between forces ``low`` and ``high`` (N),
        against Zimmerli's endurance (:data:`ZIMMERLI`), as Shigley's Section 10-9 and its extension-spring
        example do: S_su = 0.67 S_ut, S_se = S_sa / (1 - (S_sm / S_su)^2), and per place n = (1/2) (S_u / m)^2
        (a / S_e) (-1 + sqrt(1 + (2 m S_e / (S_u a))^2)) for an alternating stress a about a mean m: the body
        (torsion, Wahl-corrected), the hook's bend at A (bending: S_e = S_se / 0.577, S_u = S_ut) and its root
        at B (torsion); ``r1``, ``r2`` (m) as :meth:`hook_stresses`. A spring that does not cycle has no fatigue (inf).

        :returns: {"body", "hook bending", "hook torsion"}: each factor (>= 1: rated for
            :data:`ENDURANCE_CYCLES` cycles and more)
        """
        low = _checks.positive("low", low, allow_zero=True, unit="N")
        high = _checks.positive("high", high, allow_zero=True, unit="N")
        if high < low:
            raise SpringlabError(f"high = {high:g} N is below low = {low:g} N: give the force range low to high")
        Sut = self.wire_material.tensile_strength(self.wire)
        Ssu = 0.67 * Sut
        Ssa, Ssm = ZIMMERLI
        Sse = Ssa / (1 - (Ssm / Ssu) ** 2)
        Fa, Fm = (high - low) / 2, (high + low) / 2
        (sA_a, tB_a), (sA_m, tB_m) = self.hook_stresses(Fa, r1=r1, r2=r2), self.hook_stresses(Fm, r1=r1, r2=r2)
        places = {"body": (float(self.stress(Fa)), float(self.stress(Fm)), Sse, Ssu),
                  "hook bending": (float(sA_a), float(sA_m), Sse / 0.577, Sut),
                  "hook torsion": (float(tB_a), float(tB_m), Sse, Ssu)}
        return {name: _gerber(a, m, Se, Su) for name, (a, m, Se, Su) in places.items()}

    def problems(self) -> list[str]:
        """Why a maker could not wind this spring or it would not survive its service (empty: fine)."""
        out = []
        lo, hi = INDEX_RANGE
        if not lo <= self.index <= hi:
            out.append(f"index C = {self.index:.2f} outside {lo:g}-{hi:g}")
        if self.body_coils < MIN_BODY_COILS:
            out.append(f"{self.body_coils:.2f} body coils (fewer than {MIN_BODY_COILS:g})")
        t_lo, t_hi = self.initial_tension_range
        if self.initial_tension > t_hi * (1 + 1e-9):
            out.append(f"initial tension {self.initial_tension:.3g} N above the windable {t_hi:.3g} N")
        if self.initial_tension < t_lo * (1 - 1e-9):
            out.append(f"initial tension {self.initial_tension:.3g} N below the windable {t_lo:.3g}-{t_hi:.3g} N: "
                       "wound within the range, then stress-relieved (a heat treatment lowers it), or wound with "
                       "the coils apart and pre-stretched")
        stress = float(self.stress(self.max_force))
        if stress > STRESS_SHARE * self.allowable_stress * (1 + 1e-9):
            out.append(f"stress {stress / 1e6:.0f} MPa at the largest force {self.max_force:.1f} N above "
                       f"{100 * STRESS_SHARE:.0f} % of the allowable {self.allowable_stress / 1e6:.0f} MPa")
        for what, value, allowed in zip(("hook's bending", "hook's torsion"), self.hook_stresses(self.max_force),
                                        self.hook_allowables, strict=True):
            if value > allowed * (1 + 1e-9):
                out.append(f"the {what} {value / 1e6:.0f} MPa at the largest force {self.max_force:.1f} N above its "
                           f"allowable {allowed / 1e6:.0f} MPa (Shigley, Table 10-7)")
        return out


class Fitted(NamedTuple):
    """A realised spring's coil and how it is mounted on the arm (a URDF arm's design,
    :class:`springlab.design.arms.ArmDesign`).

    :ivar coil: the coil as wound
    :ivar span: (shortest, longest) m: the distance between the spring's ends (a zero-length spring) or
        its cable's path from the pulley to end B (a cable spring) over the workspace
    :ivar ratio: a cable spring's pulley block, 1 to 4: the coil moves 1 / ratio of the cable's path
        at ratio times the cable's pull (its rate is ratio^2 times the spring's), so that a coil too long
        for its link fits; the coil's length is path / ratio + its cable offset
    :ivar cable: the cable (:class:`springlab.design.cables.Cable`) a cable spring runs on, or None
    :ivar bracket: for a coil on a bracket of the level frame beyond its pulley at the post (a layout's, where its
        link has no room for it), the room (m) the bracket gives it: its link's length less the post's and the
        pulley's; None for a coil on its link
    :ivar choice: a layout's spring: how its realisation placed it, (pulley at the post, the lengths' change:
        False as laid out, True the point's and the post's swapped, a number the point's scaled by it), and
        whether its coil fit its room and its pulley cleared the table so placed
        (:func:`springlab.design.layouts.realise_layout`)
    """

    coil: ExtensionSpring
    span: tuple
    ratio: int = 1
    cable: object = None
    bracket: float | None = None
    choice: tuple = (False, False, True, True)

    def coil_length(self, path):
        """The coil's length (m, inside the hooks) at the cable's paths ``path`` (m): path / ratio plus the
        cable's offset, never shorter than its free length."""
        return np.maximum(np.asarray(path, dtype=float) / self.ratio + self.coil.cable_offset, self.coil.free_length)

    def forces(self) -> tuple[float, float]:
        """(least, largest) N: the coil's pull over its span in the workspace, the range it cycles through
        (:meth:`ExtensionSpring.fatigue`)."""
        low, high = self.coil.force(self.coil_length(np.asarray(self.span, dtype=float)))
        return float(low), float(high)


def _coils_for(material: Material, d, C, k):
    """N_b for the rate k (N/m) at wire d (m) and index C: N_a = d G / (8 C^3 k), less G / E."""
    G, E = material.moduli_at(d)
    return d * G / (8 * C**3 * k) - G / E


def zero_length_spring(k: float, lengths, material: str = "music wire", *, tension_scale: float = 1.0):
    """A spring with F_i = k L_0 (force k l over ``lengths`` = (shortest, longest) m), or the reason none fits.

    Searches every stocked wire and indices C in :data:`INDEX_RANGE` (steps of 0.01).
    ``tension_scale`` widens the windable initial-tension range (1: the preferred range).

    :returns: (ExtensionSpring, '') or (None, why)
    """
    k = _checks.positive("k", k, unit="N/m")
    short, long = _lengths(lengths)
    mat = _material(material)
    tension_scale = _checks.positive("tension_scale", tension_scale)
    best, closest, other = None, None, {}
    C = np.arange(INDEX_RANGE[0], INDEX_RANGE[1] + 1e-9, 0.01)
    for d_mm in mat.diameters_mm:
        d = d_mm * 1e-3
        Nb = _coils_for(mat, d, C, k)
        L0 = (2 * C - 1 + Nb) * d
        need = 8 * k * L0 * C / (np.pi * d**2)  # the stress of F_i = k L_0
        lo, hi = initial_tension_stress_range(C)
        ratio = np.where(need >= lo, need / (hi * tension_scale), np.inf)  # inside the windable range only
        if closest is None or ratio.min() < closest[0]:
            at = int(np.argmin(ratio))
            closest = (float(ratio[at]), d_mm, float(C[at]), float(need[at]), float(hi[at] * tension_scale))
        windable = ratio <= 1 + 1e-9
        if np.any(windable & (Nb < MIN_BODY_COILS)):
            other.setdefault("coils", f"fewer than {MIN_BODY_COILS:g} body coils")
        if np.any(windable & (L0 > short)):
            other.setdefault("short", f"a free length above the shortest length over the workspace ({short:.3g} m)")
        ok = windable & (Nb >= MIN_BODY_COILS) & (L0 <= short)
        for c, nb, l0 in zip(C[ok], Nb[ok], L0[ok], strict=True):
            spring = ExtensionSpring(material, d, float(c * d), float(nb), float(k * l0), long)
            if not _strong(mat, d, c, wahl_factor(c), spring.max_force):
                other.setdefault("stress", f"a body or hook stress above {100 * STRESS_SHARE:.0f} % of its allowable "
                                           f"at {k * long:.1f} N")
            elif best is None or _volume(spring) < _volume(best):
                best = spring
    if best is not None:
        return best, ""
    if other:
        return None, (f"every {material} spring whose initial tension k L_0 can be wound has "
                      + " or ".join(other.values()))
    _, d_mm, c, need, hi = closest
    return None, (f"F_i = k L_0 needs an initial-tension stress of at least {need / 1e6:.0f} MPa ({material}, d = "
                  f"{d_mm:g} mm, C = {c:.2f}), and makers wind at most {hi / 1e6:.0f} MPa at that index: "
                  f"no {material} spring of C {INDEX_RANGE[0]:g}-{INDEX_RANGE[1]:g} is zero-length")


def cable_spring(k: float, lengths, material: str = "music wire", *, room: float | None = None):
    """A spring for the cable realisation (force k times the cable's path over ``lengths`` = (shortest,
    longest) m): initial tension in the middle of the windable range, or :data:`STRETCH_MARGIN` times
    k times the shortest path where that is less (the spring must be stretched past its free length
    everywhere, with a margin for the maker's tolerances), inside the windable range where a wire and
    index allow it (else below it, flagged by :meth:`ExtensionSpring.problems` and on the sheet:
    wound at the range and stress-relieved down to it), stress within :data:`STRESS_SHARE` of the
    allowable. Among those, the
    shortest when fully stretched (it lies along a link), then the least wire; ``room`` (m) bounds that
    length if given.

    :returns: (ExtensionSpring, '') or (None, why)
    """
    k = _checks.positive("k", k, unit="N/m")
    short, long = _lengths(lengths)
    mat = _material(material)
    room = _checks.optional_positive("room", room, "m")
    spring, why = _cable_spring(k, short, long, mat, material, room, in_range=True)
    if spring is not None:
        return spring, ""
    below, why_below = _cable_spring(k, short, long, mat, material, room, in_range=False)
    if below is not None:  # flagged by its problems() and on the sheet: stress-relieved down to it
        return below, ""
    return None, why_below


def _cable_spring(k, short, long, mat, material, room, *, in_range: bool):
    """:func:`cable_spring`'s search; ``in_range=False`` lets the initial tension fall below the
    windable range (for a spring the range cannot give: flagged)."""
    best, reasons = None, {}
    C = np.arange(INDEX_RANGE[0], INDEX_RANGE[1] + 1e-9, 0.05)
    K = wahl_factor(C)
    lo, hi = initial_tension_stress_range(C)
    for d_mm in mat.diameters_mm:  # each wire's indices at once; the spring built for the winner only
        d = d_mm * 1e-3
        Nb = _coils_for(mat, d, C, k)
        per = np.pi * d**3 / (8 * C * d)  # N per Pa of initial-tension stress
        # in the windable range, nearest its middle, and at most STRETCH_MARGIN of the force at the shortest path
        Fi = np.minimum(0.5 * (lo + hi) * per, STRETCH_MARGIN * k * short)
        windable = Fi >= lo * per * (1 - 1e-9) if in_range else np.ones_like(C, dtype=bool)
        L0 = (2 * C - 1 + Nb) * d
        longest = L0 + long - Fi / k
        coils = Nb >= MIN_BODY_COILS
        strong = _strong(mat, d, C, K, k * long)  # at the largest force, k times the longest path
        fits = np.ones_like(C, dtype=bool) if room is None else longest <= room
        if not coils.all():
            reasons.setdefault("coils", f"fewer than {MIN_BODY_COILS:g} body coils for k = {k:.4g} N/m")
        if np.any(coils & ~strong):
            reasons.setdefault("stress", f"the body's or a hook's stress at {k * long:.1f} N exceeds "
                                         f"{100 * STRESS_SHARE:.0f} % of its allowable for every wire")
        if np.any(coils & strong & ~windable):
            reasons.setdefault("tension", f"the windable initial tension exceeds {STRETCH_MARGIN:g} of the force at the "
                                          f"shortest path, {k * short:.3g} N (the coil would go slack)")
        if np.any(coils & strong & windable & ~fits):
            reasons.setdefault("room", f"no spring stretched to carry it is shorter than the room, {room:g} m")
        ok = np.flatnonzero(coils & strong & windable & fits)
        if not len(ok):
            continue
        volume = np.pi * d**2 / 4 * np.pi * C * d * (Nb + 2)
        at = ok[np.lexsort((volume[ok], np.round(longest[ok], 4)))[0]]
        spring = ExtensionSpring(material, d, float(C[at] * d), float(Nb[at]), float(Fi[at]), float(longest[at]))
        if best is None or (round(spring.max_length, 4), _volume(spring)) < (round(best.max_length, 4), _volume(best)):
            best = spring
    if best is not None:
        return best, ""
    return None, "; ".join(reasons.values()) or f"no {material} wire is stocked"


def _windable(spring: ExtensionSpring, scale: float) -> bool:
    lo, hi = spring.initial_tension_range
    return lo <= spring.initial_tension <= hi * scale


def _volume(spring: ExtensionSpring) -> float:
    """Wire volume (m^3) of the body and hooks."""
    return np.pi * spring.wire**2 / 4 * np.pi * spring.mean_diameter * (spring.body_coils + 2)


def _lengths(lengths) -> tuple[float, float]:
    values = _checks.real_array("lengths", lengths, shape=(2,))
    short, long = float(values[0]), float(values[1])
    if not 0 < short <= long:
        raise SpringlabError(f"lengths must be (shortest, longest) with 0 < shortest <= longest (m), got {tuple(values)}")
    return short, long


def _material(name) -> Material:
    return MATERIALS[_checks.choice("material", name, tuple(MATERIALS))]


@dataclass(frozen=True)
class Realisation:
    """How one ideal spring is built.

    :ivar spring: the ideal spring (zero-free-length)
    :ivar kind: 'zero-length spring' or 'cable over a pulley'
    :ivar coil: the extension spring
    :ivar pulley_radius: m (cable kind), None for the zero-length kind
    :ivar lengths: (shortest, longest) distance between the ends over the workspace (m)
    :ivar note: why the zero-length kind was not used (cable kind)
    :ivar room: m, the length of link i from A back to its proximal joint, along which a cable
        spring lies (None: the base column, taken as long enough)
    """

    spring: Spring
    kind: str
    coil: ExtensionSpring
    pulley_radius: float | None
    lengths: tuple
    note: str = ""
    room: float | None = None

    @property
    def fits(self) -> bool:
        """False when a cable spring, stretched to its longest, is longer than its room along link i."""
        return not self.cable or self.room is None or self.coil.max_length <= self.room

    @property
    def cable(self) -> bool:
        """True for the cable-over-a-pulley kind."""
        return self.kind == "cable over a pulley"

    @property
    def cable_offset(self) -> float:
        """L_0 - F_i / k (m): what the cable's length absorbs so that the force is k times the path
        (0 for the zero-length kind, whose F_i = k L_0)."""
        return self.coil.free_length - self.coil.initial_tension / self.coil.rate

    def built(self, *, tension: float = 1.0, free_length: float = 1.0, stiffness: float = 1.0) -> Spring:
        """The line spring route 2 and exudyn model, with the built spring's initial tension, free
        length and rate multiplied by the factors (1: as specified). Its force along the spring's
        path (the cable's, for the cable kind) is F_i + k (path + c - L_0), c the cable offset."""
        s, coil = self.spring, self.coil
        k = s.k * stiffness
        L0 = coil.free_length * free_length - (self.cable_offset if self.cable else 0.0)
        Fi = coil.initial_tension * tension
        if L0 >= 0:
            return Spring(s.i, s.j, s.a, s.b, k, free_length=L0, initial_tension=Fi)
        return Spring(s.i, s.j, s.a, s.b, k, free_length=0.0, initial_tension=Fi - k * L0)


def spring_lengths(chain: Chain, spring: Spring, X) -> tuple[float, float]:
    """(shortest, longest) distance |B - A| (m) over the poses X (route 2)."""
    L = spring_length(chain, spring, X)
    return float(L.min()), float(L.max())


def realise(chain: Chain, springs, X, *, material: str = "music wire", pulley_radius: float = PULLEY_RADIUS,
            tension_scale: float = 1.0) -> list[Realisation]:
    """A realisation per ideal spring over the workspace poses X (N, n, 3): the zero-length spring
    where one fits, else a cable over a pulley of ``pulley_radius`` (m).

    :raises SpringlabError: naming the spring and why, where neither fits
    """
    springs = check_springs(chain, springs)
    X = chain.check_directions(X)
    pulley_radius = _checks.positive("pulley_radius", pulley_radius, allow_zero=True, unit="m")
    out = []
    for s in springs:
        if not s.ideal:
            raise SpringlabError(f"{s.label} already has a free length or initial tension: realise ideal springs")
        lengths = spring_lengths(chain, s, X)
        coil, why = zero_length_spring(s.k, lengths, material, tension_scale=tension_scale)
        if coil is not None:
            out.append(Realisation(s, "zero-length spring", coil, None, lengths))
            continue
        path, _ = cable_path(chain, s, X, pulley_radius)
        room = None if s.i == 1 else chain.length(s.i) + s.a  # from A back to link i's proximal joint
        span = (float(path.min()), float(path.max()))
        coil, why_cable = cable_spring(s.k, span, material, room=room) if room and room > 0 else (None, "")
        if coil is None:  # none fits the room: the shortest that carries it, flagged (Realisation.fits)
            coil, why_cable = cable_spring(s.k, span, material)
        if coil is None:
            raise SpringlabError(f"{s.label} (k = {s.k:.4g} N/m, {lengths[0]:.3f}-{lengths[1]:.3f} m): no zero-length "
                                 f"spring ({why}) and no cable spring ({why_cable}); try material='stainless 302' "
                                 "or another design")
        out.append(Realisation(s, "cable over a pulley", coil, pulley_radius, lengths, why, room))
    return out


def line_radii(realisations) -> list[float]:
    """The radius (m) of what runs between each spring's ends: the coil's outer radius for a
    zero-length spring, :data:`CABLE_RADIUS` for a cable (:func:`springlab.design.clearance.clearance`)."""
    return [CABLE_RADIUS if r.cable else r.coil.outer_diameter / 2 for r in realisations]


def realised_torques(chain: Chain, realisations, X, **factors) -> np.ndarray:
    """Route 2's holding torques (N m), (N, n-1, 3), of the built springs (factors as in
    :meth:`Realisation.built`), cables led over their pulleys."""
    built = [r.built(**factors) for r in realisations]
    radii = [r.pulley_radius if r.cable else None for r in realisations]
    return holding_torques_with_pulleys(chain, built, radii, X)


def _worst(torques: np.ndarray) -> float:
    return float(np.max(np.linalg.norm(torques, axis=-1)))


@dataclass(frozen=True)
class BalanceLoss:
    """The largest holding torque (N m, the norm at a joint, over joints and poses) each case leaves,
    and gravity's own (no springs) to compare: rows (case, N m, percent of gravity's)."""

    rows: list
    gravity: float

    def table(self) -> Table:
        return Table(["built", "largest holding torque (N m)", "of gravity's unbalanced (%)"],
                     [(case, f"{t:.3g}", f"{100 * t / self.gravity:.3g}") for case, t in self.rows])

    def worst(self) -> float:
        return max(t for _, t in self.rows)


TOLERANCES = {"tension": 0.10, "free_length": 0.02, "stiffness": 0.10}
"""Relative tolerances of a wound spring assumed by :func:`balance_loss`: initial tension +-10 %,
free length +-2 %, rate +-10 % (the order makers quote for standard quality; give your maker's)."""


def check_tolerances(tolerances: dict | None, *, largest: float = 0.5) -> dict:
    """A maker's relative tolerances by name (:data:`TOLERANCES`, the default), each checked: a name it
    knows, a number from 0 to ``largest``."""
    tolerances = dict(TOLERANCES if tolerances is None else tolerances)
    for name, value in tolerances.items():
        _checks.choice("tolerance", name, tuple(TOLERANCES))
        value = _checks.positive(f"tolerance {name}", value, allow_zero=True)
        if np.isfinite(largest):
            _checks.at_most(f"tolerance {name}", value, largest)
    return tolerances


def balance_loss(chain: Chain, realisations, X, *, tolerances: dict | None = None) -> BalanceLoss:
    """What the built springs leave unbalanced over the poses X (route 2): as designed (ideal), as
    built (the pulleys' radii), and with each tolerance at its + and - limit on every spring at once."""
    X = chain.check_directions(X)
    tolerances = check_tolerances(tolerances, largest=np.inf)
    gravity = _worst(holding_torques(chain, [], X))
    rows = [("as designed (ideal springs)", _worst(holding_torques(chain, [r.spring for r in realisations], X))),
            ("as specified", _worst(realised_torques(chain, realisations, X)))]
    for name, value in tolerances.items():
        for sign in (1, -1):
            rows.append((f"{name.replace('_', ' ')} {'+' if sign > 0 else '-'}{100 * value:g} %",
                         _worst(realised_torques(chain, realisations, X, **{name: 1 + sign * value}))))
    return BalanceLoss(rows, gravity)


def pulley_study(chain: Chain, springs, X, radii, *, material: str = "music wire") -> dict[str, list[float]]:
    """The balance the built springs leave against the pulley's radius: for each radius (m), the
    largest holding torque in percent of gravity's, as specified and at the worst tolerance limit
    (:func:`balance_loss`)."""
    radii = _checks.real_array("radii", radii, shape=(None,))
    out = {"as specified": [], "worst tolerance limit": []}
    for rho in radii:
        loss = balance_loss(chain, realise(chain, springs, X, material=material, pulley_radius=float(rho)), X)
        out["as specified"].append(100 * dict(loss.rows)["as specified"] / loss.gravity)
        out["worst tolerance limit"].append(100 * loss.worst() / loss.gravity)
    return out


COIL_COLUMNS = ("material", "wire d (mm)", "mean coil D (mm)", "outer diameter (mm)", "index C", "body coils",
                "active coils", "free length inside hooks (mm)", "initial tension (N)", "windable initial tension (N)",
                "rate (N/mm)", "longest in service (mm)", "largest force (N)", "stress at largest force (MPa)",
                "allowable stress (MPa)", "stress / allowable (%)")
"""The spec sheet's columns that describe the coil itself (:func:`coil_cells`)."""

SERVICE_COLUMNS = ("hook bending at A / allowable (MPa)", "hook torsion at B / allowable (MPa)",
                   "pull in service (N)", "fatigue factor: body, hook A, hook B", "rated cycles")
"""The spec sheet's columns on what the coil goes through in service (:func:`service_cells`): its machine hooks'
stresses at the largest force beside their allowables (Shigley, Table 10-7), the range of its pull over the
workspace, Gerber's factors of safety for that cycle against Zimmerli's endurance
(:meth:`ExtensionSpring.fatigue`) and the cycles it is rated for."""


def service_cells(coil: ExtensionSpring, low: float, high: float) -> tuple:
    """A coil's cells of the spec sheet in service, as :data:`SERVICE_COLUMNS` names them, cycled between the
    pulls ``low`` and ``high`` (N)."""
    (bending, torsion), (b_ok, t_ok) = coil.hook_stresses(coil.max_force), coil.hook_allowables
    factors = coil.fatigue(low, high)
    rated = f"{ENDURANCE_CYCLES:.0e} and more" if min(factors.values()) >= 1 else "not rated: below the endurance"
    return (f"{bending / 1e6:.0f} / {b_ok / 1e6:.0f}", f"{torsion / 1e6:.0f} / {t_ok / 1e6:.0f}", f"{low:.1f}-{high:.1f}",
            ", ".join("inf" if not np.isfinite(v) else f"{v:.2f}" for v in factors.values()), rated)


SHEET_COLUMNS = ("spring", "realisation", *COIL_COLUMNS, "a (mm)", "b (mm)", "cable offset L0 - Fi/k (mm)",
                 "pulley radius (mm)", "room along link i (mm)", "maker's note")


SHEET_NOTE = (f"Designed to: body and machine-hook stresses at the largest force at most {100 * STRESS_SHARE:.0f} % of "
              f"their allowables (a margin of {1 / STRESS_SHARE:.2f} on each); initial tension inside the windable range where a stocked "
              "wire allows it (the cable offset takes up the rest of the force law), else below it and flagged: wound "
              "at the range and stress-relieved down to it, or, for a cable spring, wound open with no initial tension "
              "and its cable shortened (the maker's note gives both); at least 3 body coils; index C 4-12.")
"""The sheet's statement of what it designs to, printed with it."""


def coil_cells(coil: ExtensionSpring) -> tuple:
    """A coil's cells of the spec sheet, as :data:`COIL_COLUMNS` names them (mm, N, N/mm, MPa)."""
    c = coil
    lo, hi = c.initial_tension_range
    return (f"{c.material} ({MATERIALS[c.material].standard})", f"{c.wire * 1e3:.2f}", f"{c.mean_diameter * 1e3:.2f}",
            f"{c.outer_diameter * 1e3:.2f}", f"{c.index:.2f}", f"{c.body_coils:.2f}", f"{c.active_coils:.2f}",
            f"{c.free_length * 1e3:.1f}", f"{c.initial_tension:.2f}", f"{lo:.2f}-{hi:.2f}", f"{c.rate / 1e3:.4f}",
            f"{c.max_length * 1e3:.1f}", f"{c.max_force:.1f}", f"{c.stress(c.max_force) / 1e6:.0f}",
            f"{c.allowable_stress / 1e6:.0f}", f"{100 * c.stress(c.max_force) / c.allowable_stress:.0f}")


def maker_note(coil: ExtensionSpring, cable: bool = False) -> str:
    """The sheet's note to the maker: how to reach an initial tension below the windable range ('' when
    it lies inside it); for a cable spring (``cable``), also the open-coil alternative
    (:meth:`ExtensionSpring.open_coil`), which needs no initial tension at all. A stock part
    (:class:`springlab.design.catalogue.StockSpring`) is bought, not wound: its part number."""
    part = getattr(coil, "part", None)
    if part is not None:
        return f"stock part {part.part_number}: bought as listed, not wound"
    lo, _ = coil.initial_tension_range
    if coil.initial_tension < lo * (1 - 1e-9):
        note = (f"wind at {lo:.2f} N or more, then stress-relieve to {coil.initial_tension:.2f} N (below the windable "
                "range)")
        if cable:
            o = coil.open_coil()
            note += (f"; or wind it open, no initial tension, pitch {1e3 * o.pitch:.2f} mm, free length "
                     f"{1e3 * o.free_length:.1f} mm, and shorten the cable to a {1e3 * o.cable_offset:.1f} mm offset "
                     f"(pre-stretched at assembly): {1e3 * o.max_length:.1f} mm long in service, check its room")
        return note
    return ""


def spec_sheet(realisations) -> Table:
    """One row per spring: what a spring maker needs (and where it goes on the arm); :data:`SHEET_NOTE`
    says what it is designed to."""
    rows = []
    for r in realisations:
        rows.append((f"{r.spring.label}{r.spring.pattern}", r.kind, *coil_cells(r.coil),
                     f"{r.spring.a * 1e3:.1f}", f"{r.spring.b * 1e3:.1f}",
                     f"{r.cable_offset * 1e3:.1f}" if r.cable else "",
                     f"{r.pulley_radius * 1e3:.1f}" if r.pulley_radius is not None else "",
                     "" if not r.cable else "base column" if r.room is None else
                     f"{r.room * 1e3:.0f}" + ("" if r.fits else " (too short: mount it past the joint)"),
                     maker_note(r.coil, bool(r.cable))))
    return Table(list(SHEET_COLUMNS), rows)


def table_csv(table: Table) -> str:
    """A table as CSV text."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(table.headers)
    writer.writerows(table.rows)
    return buf.getvalue()


def sheet_csv(realisations) -> str:
    """:func:`spec_sheet` as CSV text."""
    return table_csv(spec_sheet(realisations))
