"""Reproduction claims: every number a notebook reproduces, beside the paper's.

A notebook records each reproduced quantity with :meth:`Claims.compare`, which
classifies it and asserts the expected status, shows the records as a table,
and writes them to ``figures/<notebook-stem>/claims.json`` for the report.

Statuses:

* ``reproduced``: |ours - paper| <= tolerance (the tolerance's basis recorded);
* ``rounding``: not within the tolerance, but within a rounding band (recorded as
  ``band``: half a unit of the paper's last printed digit, or the paper's rounded
  inputs propagated): the paper printed a rounded value;
* ``discrepancy``: further off than the printed rounding explains; ``cause`` names
  the cause when one was found, else the note says what was tried;
* ``not reproducible``: the paper gives too little to recompute it;
* ``not compared``: the paper has it (a curve in a figure, say), and the book does not compare it: its
  note says why, and what is checked instead;
* ``alternative reading``: the paper's text read literally gives a value further off than rounding
  explains, while another reading the text allows agrees (recorded as a claim of its own, both shown);
  ``cause`` names that reading;
* ``reproduced with corrected input``: within the tolerance, but only once an input the paper prints was
  changed; ``cause`` names the input, its printed and its changed value, and how the change was chosen;
* ``input``: a value the notebook chose or fed in (a design's free choice, a value
  equal by construction): shown, never counted as reproduced;
* ``consistent`` / ``inconsistent``: a number recomputed from the paper's own printed
  numbers (a percentage from printed maxima): a check of the paper against itself,
  not a reproduction;
* ``bound``: ours is only a bound (at least, or at most, the value recorded), because the
  computation behind it stopped short of the whole answer (an enumeration that leaves some
  cases out): never counted as reproduced, nor as an exact discrepancy. Its basis says what
  was left out; its note says whether the paper's value lies inside the bound.

Every claim records ``tolerance_basis``: why its tolerance is what it is.

Precision: a claim stores its value at the precision its tolerance gives it, so that the file
says what the computation supports and not the round-off of one CPU (another CPU's SIMD paths,
BLAS kernels or an optimiser's last iterations move the trailing digits; ``claims.json`` is
committed, and rerunning the notebooks on any machine must leave it unchanged). The
``resolution`` of a claim with a tolerance t > 0 is one decade below t's leading digit,
10^(floor(log10 t) - 1) (t = 0.005 stores 1e-4; t = 1e-9 stores 1e-10); ``ours`` and the
difference are rounded to it (:func:`stored`). A value that rounds to zero is round-off at that
resolution and reads "< resolution" (:func:`number_text`): a drift of 1.2e-11 m against a
tolerance of 1e-8 m is recorded as "< 1e-09", not as its noise. The status is decided on the
unrounded value. Exact counts (t = 0) and values without a tolerance (inputs, bounds) are stored
to 12 significant digits; the tolerance and the rounding band to 6.
"""

from __future__ import annotations

import json
import math
import numbers
import sys
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from springlab import _checks, tables
from springlab.errors import SpringlabError
from springlab.rounding import half_unit, significant

STATUSES = ("reproduced", "reproduced with corrected input", "rounding", "alternative reading", "discrepancy",
            "not reproducible", "not compared", "input", "consistent", "inconsistent", "bound")
REPORT_COLUMNS = ("reproduced", "reproduced with corrected input", "rounding", "alternative reading",
                  "discrepancy, cause found", "discrepancy, no cause found", "not reproducible", "not compared",
                  "input", "consistent", "inconsistent", "bound")
"""The columns of the reproduction report: the statuses, discrepancies split by cause."""

MEANINGS = {
    "reproduced": "ours is within the stated tolerance of the paper's value (the claim records why the tolerance "
                  "is what it is)",
    "reproduced with corrected input": "within the tolerance, but only once an input the paper prints was changed; "
                                       "the claim names the input, both values and how the change was chosen",
    "rounding": "outside the tolerance, but within the band the paper's printed rounding explains",
    "alternative reading": "the paper's text read literally gives a value further off than rounding explains, "
                           "while another reading the text allows agrees; both are shown, and the claim names the "
                           "other",
    "discrepancy, cause found": "further off than the paper's rounding explains; the claim names the cause",
    "discrepancy, no cause found": "further off than the paper's rounding explains, and no cause was found; the "
                                   "claim says what was tried",
    "not reproducible": "the paper gives too little to recompute it",
    "not compared": "the paper has it, and the book does not compare it; the claim says why, and what is checked "
                    "instead",
    "input": "a value the notebook fed in or chose, shown beside the paper's and never counted as reproduced",
    "consistent": "a number recomputed from the paper's own printed numbers agrees with the paper: the paper "
                  "checked against itself, not a reproduction",
    "inconsistent": "a number recomputed from the paper's own printed numbers disagrees with the paper",
    "bound": "ours is only a bound (at least, or at most, the value shown), because the computation behind it "
             "stopped short of the whole answer; the claim says what was left out and whether the paper's value "
             "lies inside the bound",
}
"""What each report column (:data:`REPORT_COLUMNS`) means, in a reader's words: the book's legends and its
report define every status from here."""


def undefined_statuses(records) -> list[str]:
    """The report columns of claim ``records`` that :data:`MEANINGS` does not define (none, for a book that
    may be built)."""
    return sorted({report_column(r) for r in records} - set(MEANINGS))


def check_statuses(records) -> None:
    """Refuse claim ``records`` whose status :data:`MEANINGS` does not define: a book cannot tell its reader
    what it means.

    :raises SpringlabError: naming the first such status
    """
    missing = undefined_statuses(records)
    if missing:
        raise SpringlabError(f"status {missing[0]!r} has no meaning in springlab.workbench.claims.MEANINGS: "
                             "define it there before a claim uses it")


LEGEND_LEAD = "How to read the claims below: each row gives the paper's value, ours, their difference and a status"
"""The sentence that opens a chapter's legend above its first claims table."""


def legend_html(records, report: str = "report.html#statuses", *, lead: str = LEGEND_LEAD,
                css: str = "claims-legend") -> str:
    """A short legend (HTML, a ``div`` of class ``css``) of the statuses claim ``records`` use, in
    :data:`REPORT_COLUMNS`' order, each with its meaning, after the sentence ``lead``, linking to ``report``
    where every status is defined.

    :raises SpringlabError: naming a status that :data:`MEANINGS` does not define
    """
    from html import escape

    check_statuses(records)
    used = {report_column(r) for r in records}
    shown = [s for s in REPORT_COLUMNS if s in used]
    items = "".join(f"<li><strong>{escape(s)}</strong>: {escape(MEANINGS[s])}{'.' if k == len(shown) - 1 else ';'}</li>"
                    for k, s in enumerate(shown))
    return (f'<div class="{escape(css)}"><p>{escape(lead)} (<a href="{escape(report)}">every status</a>):</p>'
            f'<ul>{items}</ul></div>')


@dataclass(frozen=True)
class Claim:
    quantity: str
    where: str
    paper: float | None
    ours: float | None
    unit: str
    tolerance: float | None
    status: str
    note: str = ""
    tolerance_basis: str = ""
    band: dict | None = None  # {"value": the rounding band, "basis": how it was propagated}
    cause: str = ""  # a discrepancy's cause, when one was found
    cell: int | None = None  # the execution count of the notebook cell that recorded it (the book links it)
    resolution: float | None = None  # the quantum ours is stored at (module docstring); None: 12 digits
    paper_decimals: int | None = None  # the decimals the paper prints its value with (1.50, not 1.5); None: unknown

    def __post_init__(self):
        object.__setattr__(self, "ours", stored(self.ours, self.resolution))
        if self.tolerance is not None:  # a computed tolerance (1e-9 of a simulated range) carries round-off too
            object.__setattr__(self, "tolerance", significant(self.tolerance, TOLERANCE_DIGITS))
        if self.band is not None:
            object.__setattr__(self, "band", {**self.band, "value": significant(self.band["value"], TOLERANCE_DIGITS)})

    @property
    def difference(self) -> float | None:
        if self.paper is None or self.ours is None:
            return None
        return stored(self.ours - self.paper, self.resolution)

    def _repr_html_(self) -> str:
        """A claim a cell ends with shows as a one-row claims table, not as its repr."""
        return html_table([{**asdict(self), "difference": self.difference}])


def report_column(record: dict) -> str:
    """The report column a claim record counts in (see :data:`REPORT_COLUMNS`)."""
    if record["status"] == "discrepancy":
        return "discrepancy, cause found" if record.get("cause") else "discrepancy, no cause found"
    return record["status"]


def _current_cell() -> int | None:
    """The execution count of the notebook cell running now, or None outside a kernel: the
    count of the result IPython is running the cell for (its own ``execution_count`` is
    already the next cell's while a cell runs)."""
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None
    result = getattr(getattr(shell, "displayhook", None), "exec_result", None)
    count = getattr(result, "execution_count", None)
    return count if isinstance(count, int) else None


TOLERANCE_DIGITS = 6
"""Significant digits a claim's tolerance and rounding band are stored to (the status is decided
on the unrounded ones)."""

SIGNIFICANT_DIGITS = 12
"""Digits a claim's value is stored to when it has no tolerance to set its resolution."""


def resolution(tolerance: float | None) -> float | None:
    """The quantum a claim with this tolerance stores its value at: one decade below the
    tolerance's leading digit, 10^(floor(log10 t) - 1); None for no tolerance or t = 0.

    >>> resolution(0.005), resolution(1e-9), resolution(0.5000000005), resolution(0.0)
    (0.0001, 1e-10, 0.01, None)
    """
    if tolerance is None or tolerance <= 0:
        return None
    return 10.0 ** (math.floor(math.log10(tolerance)) - 1)


def stored(value: float | None, resolution: float | None = None) -> float | None:
    """``value`` as a claim stores it: rounded to ``resolution`` (a power of ten), or to
    :data:`SIGNIFICANT_DIGITS` significant digits without one; never -0.0.

    >>> stored(183.99253097059903, 0.01), stored(3.867e-10, 1e-9), stored(2 / 3)
    (183.99, 0.0, 0.666666666667)
    """
    if value is None:
        return None
    if resolution is None:
        return significant(value, SIGNIFICANT_DIGITS)
    decimals = _decimals(resolution)
    out = float(f"{value:.{decimals}f}") if decimals >= 0 else float(round(value, decimals))
    return out + 0.0  # -0.0 -> 0.0


def _decimals(resolution: float) -> int:
    """The decimals of a resolution that is a power of ten (1e-4 -> 4, 10 -> -1)."""
    return -round(math.log10(resolution))


def number_text(value, resolution: float | None = None) -> str:
    """A claim's number as the report prints it: with a ``resolution``, to its decimals (every
    digit stored, so that ours minus the paper's is the difference shown), and "< resolution" for
    a value stored as zero there (it is round-off); without one, 6 significant digits; empty for None.

    >>> number_text(183.99, 0.01), number_text(21.48438, 1e-05), number_text(0.0, 1e-09), number_text(48.0)
    ('183.99', '21.48438', '< 1e-09', '48')
    """
    if value is None:
        return ""
    if resolution:
        if value == 0:
            return f"< {resolution:g}"
        return f"{value:.{max(0, _decimals(resolution))}f}"  # every digit stored, no more
    return f"{value:.6g}"


def paper_text(record: dict) -> str:
    """A claim's paper value as the paper prints it: to its printed decimals where the claim knows
    them (2156.00, not 2156), else as :func:`number_text`.

    >>> paper_text({"paper": 2156.0, "paper_decimals": 2}), paper_text({"paper": 0.5})
    ('2156.00', '0.5')
    """
    decimals = record.get("paper_decimals")
    if record.get("paper") is None or decimals is None:
        return number_text(record.get("paper"))
    return f"{record['paper']:.{decimals}f}"


def markdown_table(records: list[dict]) -> str:
    """Claim records (as in claims.json) as a Markdown table: paper, ours, difference, status."""
    rows = []
    for r in records:
        band = f"; band {number_text(r['band']['value'])} ({r['band']['basis']})" if r.get("band") else ""
        cause = f" Cause: {r['cause']}" if r.get("cause") else ""
        res = r.get("resolution")
        rows.append((r["quantity"], r["where"], paper_text(r), number_text(r["ours"], res),
                     number_text(r["difference"], res),
                     r["unit"], f"{number_text(r['tolerance'])} ({r.get('tolerance_basis', '')}{band})",
                     f"**{r['status']}**", f"{r['note']}{cause}"))
    return tables.markdown_table(["quantity", "where", "paper", "ours", "difference", "unit", "tolerance (basis)",
                                  "status", "note"], rows)


def claim_details(record: dict) -> str:
    """A claim's tolerance with its basis, rounding band, note and cause, as one sentence."""
    parts = []
    if record.get("tolerance") is not None:
        parts.append(f"tolerance {number_text(record['tolerance'])} {record.get('unit', '')}".rstrip()
                     + (f" ({record['tolerance_basis']})" if record.get("tolerance_basis") else ""))
    elif record.get("tolerance_basis"):
        parts.append(record["tolerance_basis"])
    if record.get("band"):
        parts.append(f"band {number_text(record['band']['value'])} ({record['band']['basis']})")
    text = "; ".join(parts)
    for extra in (record.get("note"), f"Cause: {record['cause']}" if record.get("cause") else ""):
        if extra:
            text = f"{text}. {extra}" if text else extra
    return text


HTML_COLUMNS = ("quantity", "paper", "ours", "difference", "unit", "status")
"""The columns of a claims table in HTML; each claim's tolerance, basis, note and cause sit on
a row of their own under it (:func:`claim_details`), so the table fits a page's text column."""


def html_table(records: list[dict], made_in: list | None = None) -> str:
    """Claim records as an HTML table (the book, and Jupyter): per claim a row with the
    quantity (and where the paper prints it), paper, ours, difference, unit and status, then a
    row under it with :func:`claim_details`. ``made_in``: per record, ``(href, text)`` or None,
    a last column linking each claim to where it is made. One line, no blank line: Markdown
    passes it through as one HTML block."""
    from html import escape

    columns = list(HTML_COLUMNS) + (["made in"] if made_in is not None else [])
    head = "".join(f"<th>{escape(c)}</th>" for c in columns)
    rows = []
    for k, r in enumerate(records):
        status = report_column(r)  # a discrepancy says whether its cause was found
        cells = [f'{escape(r["quantity"])}<br><span class="claim-where">{escape(r["where"])}</span>',
                 escape(paper_text(r)), escape(number_text(r["ours"], r.get("resolution"))),
                 escape(number_text(r.get("difference"), r.get("resolution"))),
                 escape(r["unit"]), f"<strong>{escape(status)}</strong>"]
        if made_in is not None:
            link = made_in[k]
            cells.append(f'<a href="{escape(link[0])}">{escape(link[1])}</a>' if link else "")
        css = "claim-status-" + r["status"].replace(" ", "-")
        rows.append(f'<tr class="claim {css}">' + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
        details = claim_details(r)
        if details:
            rows.append(f'<tr class="claim-details {css}"><td colspan="{len(columns)}">{escape(details)}</td></tr>')
    return (f'<table class="claims"><thead><tr>{head}</tr></thead><tbody>' + "".join(rows)
            + "</tbody></table>")


def _finite(name: str, value, quantity: str) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise SpringlabError(f"claim {quantity!r}: {name} must be a number, got {value!r}") from None
    if not math.isfinite(value):
        raise SpringlabError(f"claim {quantity!r}: {name} is {value}; a claim records finite numbers only "
                             "(record a value that cannot be computed with Claims.not_reproducible)")
    return value


def _printed(quantity: str, decimals) -> int | None:
    """A paper value's printed decimals, checked: None or a whole number from 0 to 15."""
    if decimals is None:
        return None
    if isinstance(decimals, bool) or not isinstance(decimals, numbers.Integral) or not 0 <= decimals <= 15:
        raise SpringlabError(f"claim {quantity!r}: printed decimals must be a whole number from 0 to 15, got "
                             f"{decimals!r}")
    return int(decimals)


class Claims:
    """The list of a notebook's claims."""

    def __init__(self, source: str):
        self.source = source
        self.records: list[Claim] = []

    def _check_expect(self, quantity: str, expect: str) -> None:
        if expect not in STATUSES:
            raise SpringlabError(f"claim {quantity!r}: expect must be one of {STATUSES}, got {expect!r}")

    def _classify(self, quantity, paper, ours, tolerance, decimals, rounding, band_basis):
        paper = _finite("paper", paper, quantity)
        ours = _finite("ours", ours, quantity)
        tolerance = _finite("tolerance", tolerance, quantity)
        if tolerance < 0:
            raise SpringlabError(f"claim {quantity!r}: tolerance must be >= 0, got {tolerance}")
        band = None
        if rounding is not None:
            rounding = _finite("rounding", rounding, quantity)
            if rounding < 0:
                raise SpringlabError(f"claim {quantity!r}: rounding must be >= 0, got {rounding}")
            if not band_basis:
                raise SpringlabError(f"claim {quantity!r}: a rounding band needs band_basis, the way it was "
                                     "propagated (e.g. 'Table 2's inputs rounded, propagated to first order')")
            band = {"value": rounding, "basis": band_basis}
        elif decimals is not None:
            band = {"value": half_unit(decimals),
                    "basis": band_basis or f"half a unit of the last printed digit ({decimals} decimals)"}
        diff = abs(ours - paper)
        if diff <= tolerance:
            status = "reproduced"
        elif band is not None and diff <= band["value"]:
            status = "rounding"
        else:
            status = "discrepancy"
        return paper, ours, tolerance, band, status, diff

    def compare(self, quantity: str, where: str, paper: float, ours: float, *, unit: str,
                tolerance: float, tolerance_basis: str, decimals: int | None = None,
                rounding: float | None = None, band_basis: str | None = None,
                expect: str = "reproduced", note: str = "", cause: str = "", reading: str = "",
                corrected: str = "", printed_decimals: int | None = None) -> Claim:
        """Record ours against the paper's printed value and assert the status.

        :param tolerance: absolute tolerance for 'reproduced', in ``unit``
        :param tolerance_basis: why the tolerance is what it is (a solver's stated
            tolerance, half a unit of the last printed digit, ...)
        :param decimals: the paper's printed decimals, for the 'rounding' status (band:
            half a unit of the last digit)
        :param rounding: instead of ``decimals``, the largest difference the paper's
            rounding explains (e.g. its rounded inputs propagated, :func:`springlab.rounding.propagated_rounding`),
            with ``band_basis`` saying how it was propagated
        :param expect: the status this claim must have; anything else raises AssertionError
        :param cause: for a discrepancy, its cause when one was found
        :param reading: for a literal reading of the text: the other reading the text allows, which agrees
            (its own claim); a discrepancy is then an 'alternative reading'
        :param corrected: the input changed from the paper's printed one (both values) and how the change
            was chosen; a claim reproduced only with it is 'reproduced with corrected input'
        :param printed_decimals: the decimals the paper prints ``paper`` with, for the tables (default
            ``decimals``)
        :raises SpringlabError: for NaN or infinite numbers, a negative tolerance, an
            unknown status, or a claim without ``tolerance_basis``
        """
        self._check_expect(quantity, expect)
        if not tolerance_basis:
            raise SpringlabError(f"claim {quantity!r}: tolerance_basis must say why the tolerance is {tolerance}")
        paper, ours, tolerance, band, status, diff = self._classify(
            quantity, paper, ours, tolerance, decimals, rounding, band_basis)
        if status == "discrepancy" and str(reading).strip():
            status, cause = "alternative reading", f"another reading the text allows agrees: {reading}"
        elif status == "reproduced" and str(corrected).strip():
            status, cause = "reproduced with corrected input", f"input corrected: {corrected}"
        kept = status in ("discrepancy", "alternative reading", "reproduced with corrected input")
        claim = Claim(quantity, where, paper, ours, unit, tolerance, status, note, tolerance_basis,
                      band, cause if kept else "", resolution=resolution(tolerance),
                      paper_decimals=_printed(quantity, decimals if printed_decimals is None else printed_decimals))
        self.records.append(claim := replace(claim, cell=_current_cell()))
        assert status == expect, (
            f"{quantity} ({where}): paper {paper}, ours {ours:.10g}, |difference| {diff:.3g} {unit}: "
            f"status {status}, expected {expect} (tolerance {tolerance:g})")
        return claim

    def compare_printed(self, quantity: str, where: str, printed: tuple[float, int], ours: float, *,
                        unit: str, **kwargs) -> Claim:
        """:meth:`compare` against a value the paper prints to a number of decimals, ``printed`` =
        (value, decimals): reproduced within half a unit of its last digit (the tolerance and its basis),
        and shown to those decimals. ``kwargs`` go to :meth:`compare` (expect, note, cause, ...)."""
        value, decimals = printed
        decimals = _printed(quantity, decimals)
        digits = {0: "integers", 1: "1 decimal"}.get(decimals, f"{decimals} decimals")
        return self.compare(quantity, where, value, ours, unit=unit, tolerance=half_unit(decimals),
                            tolerance_basis=f"half a unit of the printed last digit ({digits})",
                            printed_decimals=decimals, **kwargs)

    def consistency(self, quantity: str, where: str, paper: float, recomputed: float, *, unit: str,
                    tolerance: float, tolerance_basis: str, decimals: int | None = None,
                    rounding: float | None = None, band_basis: str | None = None,
                    expect: str = "consistent", note: str = "") -> Claim:
        """Record a number recomputed from the paper's own printed numbers against the
        paper's: 'consistent' (within the tolerance or the rounding band) or 'inconsistent'.
        A check of the paper against itself, never a reproduction."""
        self._check_expect(quantity, expect)
        if not tolerance_basis:
            raise SpringlabError(f"claim {quantity!r}: tolerance_basis must say why the tolerance is {tolerance}")
        paper, ours, tolerance, band, status, diff = self._classify(
            quantity, paper, recomputed, tolerance, decimals, rounding, band_basis)
        status = "inconsistent" if status == "discrepancy" else "consistent"
        claim = Claim(quantity, where, paper, ours, unit, tolerance, status, note, tolerance_basis, band,
                      resolution=resolution(tolerance), paper_decimals=_printed(quantity, decimals))
        self.records.append(claim := replace(claim, cell=_current_cell()))
        assert status == expect, (
            f"{quantity} ({where}): paper {paper}, from its own numbers {ours:.10g}, |difference| "
            f"{diff:.3g} {unit}: {status}, expected {expect}")
        return claim

    def input(self, quantity: str, where: str, paper: float | None, ours: float, *, unit: str,
              note: str, printed_decimals: int | None = None) -> Claim:
        """Record a value the notebook chose or fed in (a design's free choice, a value equal
        by construction): shown beside the paper's (to its ``printed_decimals``), not counted as reproduced."""
        ours = _finite("ours", ours, quantity)
        paper = None if paper is None else _finite("paper", paper, quantity)
        claim = Claim(quantity, where, paper, ours, unit, None, "input", note,
                      "none: a value fed in is shown, not compared",
                      paper_decimals=_printed(quantity, printed_decimals))
        self.records.append(claim := replace(claim, cell=_current_cell()))
        return claim

    def not_reproducible(self, quantity: str, where: str, paper: float | None, *, unit: str,
                         note: str) -> Claim:
        """Record a printed value the paper gives too little to recompute; ``note`` says
        what is missing and what was tried."""
        paper = None if paper is None else _finite("paper", paper, quantity)
        claim = Claim(quantity, where, paper, None, unit, None, "not reproducible", note,
                      "none: no value could be computed")
        self.records.append(claim := replace(claim, cell=_current_cell()))
        return claim

    def not_compared(self, quantity: str, where: str, *, unit: str, note: str) -> Claim:
        """Record an item the paper has (a curve of a figure, a value it prints) that the book does not
        compare; ``note`` says why, and what is checked instead. Never counted as reproduced."""
        if not str(note).strip():
            raise SpringlabError(f"claim {quantity!r}: a claim not compared needs its note: why not, and what is "
                                 "checked instead")
        claim = Claim(quantity, where, None, None, unit, None, "not compared", note,
                      "none: not compared")
        self.records.append(claim := replace(claim, cell=_current_cell()))
        return claim

    def bound(self, quantity: str, where: str, paper: float | None, ours: float, *, unit: str, direction: str,
              basis: str, note: str = "") -> Claim:
        """Record a value of which ours is only a bound: ``direction`` 'at least' (the true value is
        ours or more) or 'at most'. ``basis`` says why it is a bound (what the computation left
        out); the note says whether the paper's value lies inside it (outside: the paper is wrong
        whatever the exact value)."""
        ours = _finite("ours", ours, quantity)
        paper = None if paper is None else _finite("paper", paper, quantity)
        direction = _checks.choice("direction", direction, ("at least", "at most"))
        if not basis:
            raise SpringlabError(f"claim {quantity!r}: a bound needs its basis, what the computation left out")
        if paper is None:
            where_paper = ""
        else:
            inside = paper >= ours if direction == "at least" else paper <= ours
            where_paper = (f"; the paper's {number_text(paper)} lies inside the bound" if inside else
                           f"; the paper's {number_text(paper)} lies outside it: the paper is off whatever the exact "
                           "value")
        claim = Claim(quantity, where, paper, ours, unit, None, "bound",
                      f"{direction} {number_text(ours)} {unit}".rstrip() + where_paper + (f". {note}" if note else ""),
                      f"none: a bound, not a value ({basis})")
        self.records.append(claim := replace(claim, cell=_current_cell()))
        return claim

    def markdown(self) -> str:
        """The records as a Markdown table (paper, ours, difference, status)."""
        return markdown_table(self.to_records())

    def _repr_markdown_(self) -> str:
        return self.markdown()

    def _repr_html_(self) -> str:
        return html_table(self.to_records())

    def to_records(self) -> list[dict]:
        out = []
        for c in self.records:
            rec = asdict(c)
            rec["difference"] = c.difference
            rec["source"] = self.source
            out.append(rec)
        return out

    def write(self, directory) -> Path:
        """Write ``directory/claims.json`` (deterministic: fixed key order and formatting;
        strict JSON, no NaN)."""
        path = Path(directory) / "claims.json"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(self.to_records(), indent=1, sort_keys=True, allow_nan=False) + "\n")
        return path


NUMERIC_FIELDS = ("paper", "ours", "difference", "tolerance")
PLACE_FIELDS = ("cell",)
"""Where a claim is made, not what it says: :func:`diff_claims` ignores them."""


def diff_claims(before_dir, after_dir, *, rel: float = 1e-12) -> list[str]:
    """Every difference between two sets of ``<stem>/claims.json`` (two ``figures/`` folders):
    a notebook or claim present in one only, a changed status or label, and a number that
    moved by more than ``rel`` relative to the largest number of its claim. Empty: the same claims.
    Used to show that a change of code leaves every verdict as it was."""
    out = []
    before = {p.parent.name: json.loads(p.read_text()) for p in sorted(Path(before_dir).glob("*/claims.json"))}
    after = {p.parent.name: json.loads(p.read_text()) for p in sorted(Path(after_dir).glob("*/claims.json"))}
    for stem in sorted(set(before) | set(after)):
        if stem not in after or stem not in before:
            out.append(f"{stem}: only {'before' if stem in before else 'after'}")
            continue
        old = {(r["quantity"], r["where"]): r for r in before[stem]}
        new = {(r["quantity"], r["where"]): r for r in after[stem]}
        for key in sorted(set(old) | set(new)):
            if key not in new or key not in old:
                out.append(f"{stem}: {key[0]!r} ({key[1]}) only {'before' if key in old else 'after'}")
                continue
            a, b = old[key], new[key]
            # a number's change counts against the size of the quantity compared, so that a
            # difference of 0 becoming 1e-16 J on a 100 J quantity is round-off, not a change
            scale = max((abs(v) for r in (a, b) for f, v in r.items()
                         if f in NUMERIC_FIELDS and isinstance(v, (int, float))), default=0.0)
            for field in sorted(set(a) | set(b) - set(PLACE_FIELDS)):
                x, y = a.get(field), b.get(field)
                if field in NUMERIC_FIELDS and isinstance(x, (int, float)) and isinstance(y, (int, float)):
                    if abs(x - y) > rel * max(scale, 1e-300):
                        out.append(f"{stem}: {key[0]!r} {field} {x!r} -> {y!r}")
                elif x != y:
                    out.append(f"{stem}: {key[0]!r} {field} {x!r} -> {y!r}")
    return out


def main(argv=None) -> int:
    """``python -m springlab.workbench.claims diff BEFORE AFTER``: list what changed."""
    import argparse

    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("command", choices=["diff"])
    parser.add_argument("before", help="a figures/ folder (claims.json per notebook)")
    parser.add_argument("after", help="another figures/ folder")
    parser.add_argument("--rel", type=float, default=1e-12, help="relative change of a number that counts")
    args = parser.parse_args(argv)
    changes = diff_claims(args.before, args.after, rel=args.rel)
    print("\n".join(changes) if changes else "the same claims: every status, label and number (to "
          f"{args.rel:g} relative) unchanged")
    return 1 if changes else 0


if __name__ == "__main__":
    import sys

    sys.exit(main())
