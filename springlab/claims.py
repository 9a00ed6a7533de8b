"""Reproduction claims: every number a notebook reproduces, beside the paper's.

A notebook records each reproduced quantity with :meth:`Claims.compare`, which
classifies it and asserts the expected status, shows the records as a table,
and writes them to ``figures/<notebook-stem>/claims.json`` for the report.

Statuses:

* ``reproduced``: |ours - paper| <= tolerance;
* ``rounding``: not within the tolerance, but within half a unit of the paper's
  last printed digit: the paper printed a rounded value;
* ``discrepancy``: further off than the printed rounding explains;
* ``not reproducible``: the paper gives too little to recompute it.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path

STATUSES = ("reproduced", "rounding", "discrepancy", "not reproducible")


@dataclass(frozen=True)
class Claim:
    quantity: str
    where: str
    paper: float | None
    ours: float | None
    unit: str
    tolerance: float
    status: str
    note: str = ""

    @property
    def difference(self) -> float | None:
        if self.paper is None or self.ours is None:
            return None
        return self.ours - self.paper


def half_unit(decimals: int) -> float:
    """Half a unit of the last printed digit, with a hair for binary floats."""
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


def _number(value) -> str:
    return "" if value is None else f"{value:.6g}"


def markdown_table(records: list[dict]) -> str:
    """Claim records (as in claims.json) as a Markdown table: paper, ours, difference, status."""
    lines = ["| quantity | where | paper | ours | difference | unit | tolerance | status | note |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in records:
        lines.append(f"| {r['quantity']} | {r['where']} | {_number(r['paper'])} | {_number(r['ours'])} | "
                     f"{_number(r['difference'])} | {r['unit']} | {_number(r['tolerance'])} | **{r['status']}** | "
                     f"{r['note']} |".replace("\n", " "))
    return "\n".join(lines)


class Claims:
    """The list of a notebook's claims."""

    def __init__(self, source: str):
        self.source = source
        self.records: list[Claim] = []

    def compare(self, quantity: str, where: str, paper: float, ours: float, *, unit: str,
                tolerance: float, decimals: int | None = None, rounding: float | None = None,
                expect: str = "reproduced", note: str = "") -> Claim:
        """Record ours against the paper's printed value and assert the status.

        :param tolerance: absolute tolerance for 'reproduced', in ``unit``
        :param decimals: the paper's printed decimals, for the 'rounding' status
        :param rounding: instead of ``decimals``, the largest difference the paper's
            rounding explains (e.g. its rounded inputs propagated, :func:`propagated_rounding`)
        :param expect: the status this claim must have; anything else raises AssertionError
        """
        diff = abs(float(ours) - float(paper))
        if diff <= tolerance:
            status = "reproduced"
        elif rounding is not None and diff <= rounding:
            status = "rounding"
        elif decimals is not None and diff <= half_unit(decimals):
            status = "rounding"
        else:
            status = "discrepancy"
        claim = Claim(quantity, where, float(paper), float(ours), unit, float(tolerance), status, note)
        self.records.append(claim)
        assert status == expect, (
            f"{quantity} ({where}): paper {paper}, ours {ours:.10g}, |difference| {diff:.3g} {unit}: "
            f"status {status}, expected {expect} (tolerance {tolerance:g})")
        return claim

    def not_reproducible(self, quantity: str, where: str, paper: float | None, *, unit: str,
                         note: str) -> Claim:
        claim = Claim(quantity, where, paper, None, unit, math.nan, "not reproducible", note)
        self.records.append(claim)
        return claim

    def markdown(self) -> str:
        """The records as a Markdown table (paper, ours, difference, status)."""
        return markdown_table(self.to_records())

    def _repr_markdown_(self) -> str:
        return self.markdown()

    def to_records(self) -> list[dict]:
        out = []
        for c in self.records:
            rec = asdict(c)
            rec["difference"] = c.difference
            rec["source"] = self.source
            if isinstance(rec["tolerance"], float) and math.isnan(rec["tolerance"]):
                rec["tolerance"] = None
            out.append(rec)
        return out

    def write(self, directory) -> Path:
        """Write ``directory/claims.json`` (deterministic: fixed key order and formatting)."""
        path = Path(directory) / "claims.json"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(self.to_records(), indent=1, sort_keys=True) + "\n")
        return path
