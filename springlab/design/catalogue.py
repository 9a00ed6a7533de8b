"""Stock extension springs, as a vendor's catalogue lists them, read from a CSV file.

A builder's first question is which spring to buy. :func:`read_catalogue` reads a catalogue of stock
extension springs; :class:`Part` is one of its rows and :class:`StockSpring` a part as the design uses it
(the coil behind a cable spring's pulley, :mod:`springlab.design.realise`), with the catalogue's rate, free
length and initial tension in place of the winding formulas'.

The format
----------
A CSV file (comma separated, UTF-8), one row a part, its first row naming the columns. The units are in
the names; a file is metric (the left names) or imperial (the right ones) throughout::

    part_number                                 the vendor's part number (text, required)
    outer_diameter_mm        outer_diameter_in      OD
    wire_diameter_mm         wire_diameter_in       d
    free_length_mm           free_length_in         L_0, inside the hooks
    rate_N_per_mm            rate_lbf_per_in        k
    initial_tension_N        initial_tension_lbf    F_i
    max_load_N               max_load_lbf           the largest load the vendor rates it for
    max_extended_length_mm   max_extended_length_in the longest it may be stretched, inside the hooks
    material                                    music wire, stainless 302 or chrome silicon (default music wire)
    mass_g                                      optional; else computed from the wire and coil
    price, pack_size                            optional, as the vendor lists them (text)

Other columns are kept as they are (a source, a note). Each row is checked: every number finite, the
diameters, the free length and the rate positive, the wire thinner than the outer diameter, the initial
tension at least 0 and below the largest load, the largest extension beyond the free length, and the
largest load within :data:`CONSISTENT` of F_i + k (L_max - L_0), which a row in other units than its
column's name says would miss by a factor of 4.4 (pounds) or 25.4 (inches). A file that fails names the
row and the column.

springlab ships no vendor's catalogue yet: give your supplier's stock list in this format.
:func:`example_rows` makes a series in it from springlab's own winding formulas, to try the stock path
and to test and time it; its parts are no vendor's.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass, field
from pathlib import Path

from springlab.design.buildable import MATERIALS, ExtensionSpring, initial_tension_stress_range
from springlab.design.cables import INCH, LBF
from springlab.errors import SpringlabError

CONSISTENT = 0.25
"""A row's largest load may differ from F_i + k (L_max - L_0) by at most this share of it: the vendors round
each value, but a value in other units (pounds for newtons, inches for millimetres) misses by far more."""

_METRIC = {"outer_diameter": ("outer_diameter_mm", 1e-3), "wire": ("wire_diameter_mm", 1e-3),
           "free_length": ("free_length_mm", 1e-3), "rate": ("rate_N_per_mm", 1e3),
           "initial_tension": ("initial_tension_N", 1.0), "max_load": ("max_load_N", 1.0),
           "max_extended_length": ("max_extended_length_mm", 1e-3)}
_IMPERIAL = {"outer_diameter": ("outer_diameter_in", INCH), "wire": ("wire_diameter_in", INCH),
             "free_length": ("free_length_in", INCH), "rate": ("rate_lbf_per_in", LBF / INCH),
             "initial_tension": ("initial_tension_lbf", LBF), "max_load": ("max_load_lbf", LBF),
             "max_extended_length": ("max_extended_length_in", INCH)}


class CatalogueError(SpringlabError):
    """A catalogue file that cannot be read: the message names the file, the row and the column."""


@dataclass(frozen=True)
class Part:
    """A stock extension spring (SI units: m, N, N/m, kg).

    :ivar part_number: the vendor's
    :ivar outer_diameter: OD (m)
    :ivar wire: d (m)
    :ivar free_length: L_0 inside the hooks (m)
    :ivar rate: k (N/m)
    :ivar initial_tension: F_i (N)
    :ivar max_load: the largest load the vendor rates it for (N)
    :ivar max_extended_length: the longest it may be stretched, inside the hooks (m)
    :ivar material: a :data:`springlab.design.buildable.MATERIALS` key
    :ivar mass: kg, where the catalogue gives it (else None)
    :ivar extra: the row's other columns (price, pack size, source, ...)
    :ivar row: the row's number in its file (the header is row 1)
    """

    part_number: str
    outer_diameter: float
    wire: float
    free_length: float
    rate: float
    initial_tension: float
    max_load: float
    max_extended_length: float
    material: str = "music wire"
    mass: float | None = None
    extra: dict = field(default_factory=dict, compare=False)
    row: int = 0

    @property
    def mean_diameter(self) -> float:
        return self.outer_diameter - self.wire

    @property
    def stroke(self) -> float:
        """m: how far it may be stretched beyond its free length."""
        return self.max_extended_length - self.free_length

    def spring(self, max_length: float) -> StockSpring:
        """The part as the design uses it, stretched to ``max_length`` (m, inside the hooks) at most in service."""
        G, E = MATERIALS[self.material].moduli_at(self.wire)
        active = self.wire**4 * G / (8 * self.mean_diameter**3 * self.rate)  # Shigley's rate, solved for N_a
        return StockSpring(self.material, self.wire, self.mean_diameter, max(active - G / E, 1e-6),
                           self.initial_tension, float(max_length), part=self)


@dataclass(frozen=True)
class StockSpring(ExtensionSpring):
    """A stock part (:attr:`part`) in service: an :class:`~springlab.design.buildable.ExtensionSpring` whose
    rate, free length and initial tension are the catalogue's, its body coils those its rate implies
    (N_a = d^4 G / (8 D^3 k), less the hooks' G / E), for its mass and stresses."""

    part: Part = None

    @property
    def rate(self) -> float:
        """k (N/m): the catalogue's."""
        return self.part.rate

    @property
    def free_length(self) -> float:
        """L_0 (m, inside the hooks): the catalogue's."""
        return self.part.free_length

    @property
    def mass(self) -> float:
        """kg: the catalogue's where it gives one, else its wire's (body coils and two hooks)."""
        return self.part.mass if self.part.mass is not None else ExtensionSpring.mass.fget(self)

    def beyond(self, length: float) -> list[str]:
        """What the vendor's limits refuse of the part stretched to ``length`` (m, inside the hooks): past its
        largest extension, pulling past its largest load (empty: within them)."""
        pull = float(self.force(max(length, self.free_length)))
        out = []
        if length > self.part.max_extended_length * (1 + 1e-9):
            out.append(f"stretched to {1e3 * length:.1f} mm, past its catalogue's largest extension "
                       f"{1e3 * self.part.max_extended_length:.1f} mm")
        if pull > self.part.max_load * (1 + 1e-9):
            out.append(f"pulling {pull:.1f} N, past its catalogue's largest load {self.part.max_load:.1f} N")
        return out

    def problems(self) -> list[str]:
        """The vendor's limits at its longest in service (:meth:`beyond`; the stresses and fatigue are on the
        sheet, computed from its wire and coil)."""
        return self.beyond(self.max_length)


@dataclass(frozen=True)
class Catalogue:
    """Stock parts read from ``source`` (a file's path), in its rows' order."""

    parts: tuple
    source: str

    def __len__(self) -> int:
        return len(self.parts)

    def __iter__(self):
        return iter(self.parts)


def _number(text: str, path, row: int, column: str) -> float:
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise CatalogueError(f"catalogue {path}, row {row}, column {column}: {text!r} is not a number; give the value "
                             "in the unit the column's name says") from None
    if not math.isfinite(value):
        raise CatalogueError(f"catalogue {path}, row {row}, column {column}: {text!r} is not a finite number")
    return value


def _units(path, header: list[str]) -> dict:
    metric = [name for name, _ in _METRIC.values() if name in header]
    imperial = [name for name, _ in _IMPERIAL.values() if name in header]
    if metric and imperial:
        raise CatalogueError(f"catalogue {path}: inconsistent units: columns {metric[0]} and {imperial[0]} mix metric "
                             "and imperial; give every column in one system")
    units = _IMPERIAL if imperial else _METRIC
    for name, _ in units.values():
        if name not in header:
            raise CatalogueError(f"catalogue {path}: column {name} is missing (the header has {', '.join(header)}); "
                                 "see springlab.design.catalogue for the format")
    if "part_number" not in header:
        raise CatalogueError(f"catalogue {path}: column part_number is missing; see springlab.design.catalogue for "
                             "the format")
    return units


def _part(path, row: int, record: dict, units: dict) -> Part:
    values = {key: _number(record.get(name), path, row, name) * scale for key, (name, scale) in units.items()}
    name = {key: column for key, (column, _) in units.items()}
    number = (record.get("part_number") or "").strip()
    if not number:
        raise CatalogueError(f"catalogue {path}, row {row}, column part_number: empty; give the vendor's part number")
    for key in ("outer_diameter", "wire", "free_length", "rate", "max_load", "max_extended_length"):
        if values[key] <= 0:
            raise CatalogueError(f"catalogue {path}, row {row}, column {name[key]}: {record[name[key]]} must be positive")
    if values["initial_tension"] < 0:
        raise CatalogueError(f"catalogue {path}, row {row}, column {name['initial_tension']}: "
                             f"{record[name['initial_tension']]} must be 0 or more")
    if values["wire"] >= values["outer_diameter"]:
        raise CatalogueError(f"catalogue {path}, row {row}, column {name['wire']}: the wire ({record[name['wire']]}) "
                             f"must be thinner than the outer diameter ({record[name['outer_diameter']]})")
    if values["max_extended_length"] <= values["free_length"]:
        raise CatalogueError(f"catalogue {path}, row {row}, column {name['max_extended_length']}: "
                             f"{record[name['max_extended_length']]} is not beyond the free length "
                             f"{record[name['free_length']]}: a part must stretch")
    if values["initial_tension"] >= values["max_load"]:
        raise CatalogueError(f"catalogue {path}, row {row}, column {name['max_load']}: {record[name['max_load']]} is not "
                             f"above the initial tension {record[name['initial_tension']]}")
    implied = values["initial_tension"] + values["rate"] * (values["max_extended_length"] - values["free_length"])
    if abs(values["max_load"] - implied) > CONSISTENT * implied:
        shown = implied / units["max_load"][1]  # in the column's own unit
        raise CatalogueError(f"catalogue {path}, row {row}, column {name['max_load']}: {record[name['max_load']]} is "
                             f"not initial tension + rate x (largest extension - free length) = {shown:.4g} within "
                             f"{100 * CONSISTENT:g} %: are the columns' units consistent?")
    material = (record.get("material") or "music wire").strip()
    if material not in MATERIALS:
        raise CatalogueError(f"catalogue {path}, row {row}, column material: {material!r}; give one of "
                             f"{', '.join(MATERIALS)}")
    mass = None
    if (record.get("mass_g") or "").strip():
        mass = _number(record["mass_g"], path, row, "mass_g") * 1e-3
        if mass <= 0:
            raise CatalogueError(f"catalogue {path}, row {row}, column mass_g: {record['mass_g']} must be positive")
    known = {"part_number", "material", "mass_g", *(column for column, _ in units.values())}
    extra = {k: v for k, v in record.items() if k not in known and k is not None}
    return Part(number, **values, material=material, mass=mass, extra=extra, row=row)


def read_catalogue(path) -> Catalogue:
    """The stock parts of a catalogue file (the module's format).

    :raises CatalogueError: naming the file, and the row and column where one is at fault: a file that
        cannot be read or is empty, a missing column, a value that is no finite number, a negative or zero
        rate, mixed units, a largest extension below the free length, a largest load that disagrees
        with the rest of its row
    """
    if not isinstance(path, (str, os.PathLike)):
        raise CatalogueError(f"path = {path!r}: give a catalogue file's path (a CSV file of stock parts)")
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as err:
        raise CatalogueError(f"catalogue {path} cannot be read ({err.strerror}); give a CSV file of stock parts") from None
    except UnicodeDecodeError:
        raise CatalogueError(f"catalogue {path} is not a UTF-8 text file; give a CSV file of stock parts") from None
    lines = [line for line in text.splitlines() if line.strip()]
    if not lines:
        raise CatalogueError(f"catalogue {path} is empty; give a CSV file with a header row and one row a part")
    reader = csv.DictReader(lines)
    header = [h.strip() for h in (reader.fieldnames or [])]
    reader.fieldnames = header
    units = _units(path, header)
    parts, seen = [], {}
    for row, record in enumerate(reader, start=2):
        if None in record:
            raise CatalogueError(f"catalogue {path}, row {row}: more values than the header's {len(header)} columns")
        part = _part(path, row, record, units)
        if part.part_number in seen:
            raise CatalogueError(f"catalogue {path}, row {row}, column part_number: {part.part_number} is already "
                                 f"row {seen[part.part_number]}'s")
        seen[part.part_number] = row
        parts.append(part)
    if not parts:
        raise CatalogueError(f"catalogue {path} has a header but no parts; give one row a part")
    return Catalogue(tuple(parts), str(path))


COLUMNS = ("part_number", "outer_diameter_mm", "wire_diameter_mm", "free_length_mm", "rate_N_per_mm",
           "initial_tension_N", "max_load_N", "max_extended_length_mm", "material")
"""The format's required columns, metric, in the order :func:`write_catalogue` writes them."""


def example_rows() -> list[dict]:
    """A made-up series of music-wire extension springs in the module's format (no vendor's parts): wires of
    0.5 to 2 mm, indices 6, 8 and 10, 10 to 40 body coils; the rate from Shigley's formula
    (:class:`~springlab.design.buildable.ExtensionSpring`), the initial tension in the middle of the windable
    range, and the largest load where the body's stress reaches 0.7 x 0.45 of the wire's strength over the
    Wahl factor 1.2, within its hooks' allowables. For trying, testing and timing the stock path."""
    rows = []
    for d in (0.5, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 2.0):
        for index in (6, 8, 10):
            wire, mean = d * 1e-3, index * d * 1e-3
            lo, hi = initial_tension_stress_range(index)
            tension = float(0.5 * (lo + hi) * math.pi * wire**3 / (8 * mean))
            for coils in (10, 15, 20, 30, 40):
                s = ExtensionSpring("music wire", wire, mean, coils, tension, 1.0)
                load = 0.7 * 0.45 * s.wire_material.tensile_strength(wire) * math.pi * wire**3 / (8 * mean * 1.2)
                if load <= 1.2 * tension:
                    continue
                rows.append({"part_number": f"T-{len(rows) + 1:03d}", "outer_diameter_mm": round(1e3 * s.outer_diameter, 2),
                             "wire_diameter_mm": d, "free_length_mm": round(1e3 * s.free_length, 2),
                             "rate_N_per_mm": round(s.rate / 1e3, 4), "initial_tension_N": round(tension, 2),
                             "max_load_N": round(load, 2),
                             "max_extended_length_mm": round(1e3 * (s.free_length + (load - tension) / s.rate), 2),
                             "material": "music wire"})
    return rows


def write_catalogue(path, rows, columns=COLUMNS) -> Path:
    """Rows (dicts of the module's columns) written as a catalogue file at ``path``; returns its path."""
    path = Path(path)
    with path.open("w", newline="", encoding="utf-8") as f:
        out = csv.DictWriter(f, fieldnames=list(columns), extrasaction="ignore")
        out.writeheader()
        out.writerows(rows)
    return path
