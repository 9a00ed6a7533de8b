"""Numbers in the book's prose that cannot go stale: each one is glued from the computation, printed by
the paper, or a reference.

A chapter's Markdown may quote a number only if it is

* glued from the computation (myst-nb's ``{glue:text}`name``` roles, which the notebook's run fills);
* one the paper prints, kept in :mod:`springlab.papers` (:func:`printed_values`; in the unit the module
  keeps it, or in degrees for an angle kept in rad);
* a reference: an equation, table, figure or section number, a heading's or a list item's number, a
  paper's key, a year, a bibliographic line (one with a DOI), a product's name (the SO-101), a rule R1-R6, route 1-3, a sign pattern or an index inside math;
* a small whole number (0 to 12) without a unit of measure: a count of links, springs or joints, a
  dimension n, which a reader can check by eye and which no run of the notebook moves.

Anything else (a torque, a percentage, a sample count, a grid step) is a number the computation or one
of its inputs sets, and stale prose is what follows when it is typed in: :func:`unglued` lists them.

>>> values = printed_values("000")
>>> unglued("Table 3 prints $k = 718.67$ N/m; ours holds to 1.2e-11 J over 1,000 poses.", values)
['1.2e-11', '1,000']
>>> unglued("Eq. (23b) with $S_{1,4}$ and 4 springs; {glue:text}`peak:.1f` N m", values)
[]
"""

from __future__ import annotations

import math
import re
from dataclasses import fields, is_dataclass

import numpy as np

__all__ = ["MODULES", "printed_values", "values_for", "unglued", "SMALL"]

SMALL = 12
"""A whole number up to this, without a unit, is a count a reader checks by eye (links, springs, n)."""

_DROP = re.compile(
    r"```.*?```"  # fenced code
    r"|\{[\w:-]+\}`[^`]*`"  # roles: {glue:text}`x`, {doc}`x`, {ref}`x`
    r"|`[^`]*`"  # inline code
    r"|\$\$.*?\$\$"  # display math
    r"|!?\[[^\]]*\]\([^)]*\)"  # links and images (their text kept below)
    r"|</?[A-Za-z][\w-]*(?:\s[^<>]*)?/?>"  # HTML tags (not the "<" of "$i<j$")
    r"|^\([^)\n]*\)=[ \t]*$"  # MyST targets
    r"|^#{1,6}[ \t]+\w{1,4}\."  # a heading's number
    r"|^[ \t]*(?:\d+\.|[*-])[ \t]"  # a list item's marker
    r"|^.*\bdoi:.*$"  # a reference's line: its volume, pages and DOI
    r"|https?://\S+", re.S | re.M)
_REFERENCE = re.compile(
    r"(?:\b00[0-4]\s+)?(?:Eqs?\.|Equations?)\s*(?:\((?:[\da-z,\s\-–]|\)\s*[-–]\s*\()*\)|\d+[a-z]?(?:\s*[-–]\s*\d+[a-z]?)?)"
    r"|\b(?:Tables?|Figs?\.|Figures?|Sections?|§)\s*[\dIVX]+(?:\.[\dA-Z]+)*[a-z]?"
    r"(?:\s*(?:[-–]|and|,)\s*[\dIVX]+(?:\.\d+)*[a-z]?(?![\d.]*\s*(?:%|°|mm|m\b|kg|N\b|s\b)))*"
    r"|(?<![\d,.])(?:19|20)\d\d(?![\d,.]?\d)|(?<![\d,.])00[0-4](?![\d,.]?\d)|\bR[1-6]\b|\broutes?\s+[1-3](?:\s*(?:,|and|-)\s*[1-3])*\b"
    r"|\b\d+-(?:DOF|dof|link|joint|spring)s?\b|\([+\-],\s*[+\-]\)"
    r"|\b[A-Z]{2,}[A-Za-z]*-\d+\b")  # a product's name: the SO-101
_MATH = re.compile(r"\$([^$\n]+)\$")
_INDEX = re.compile(r"[_^](?:\{[^{}]*\}|\\?\w)")  # a sub- or superscript: an index
_NUMBER = re.compile(r"(?<![\w.,])[-+−]?(?:\d{1,3}(?:,\d{3})+|\d+)(?:\.\d+)?(?:[eE][-+−]?\d+)?(?![\w])")
"""A number: 1,000 has a thousands separator; (2,4) is a pair of numbers."""
_UNIT_AFTER = re.compile(r"\s*(?:%|°|mm\b|cm\b|m\b|kg\b|g\b|N\b|J\b|s\b|ms\b|rad\b|N m\b|N/m\b|Hz\b|px\b|MB\b|"
                         r"deg\b|points?\b|times\b|x\b)")


def _numbers(value, out: set) -> None:
    if isinstance(value, bool) or value is None:
        return
    if isinstance(value, (int, float, np.integer, np.floating)):
        if math.isfinite(float(value)):
            out.add(float(value))
    elif isinstance(value, np.ndarray):
        if value.dtype.kind in "iuf" and value.size <= 64:  # a printed table; not a grid generated from one
            out.update(float(v) for v in value.ravel() if math.isfinite(float(v)))
    elif isinstance(value, dict):
        for k, v in value.items():
            _numbers(k, out)
            _numbers(v, out)
    elif isinstance(value, (tuple, list, set, frozenset)):
        for v in value:
            _numbers(v, out)
    elif is_dataclass(value) and not isinstance(value, type):
        for f in fields(value):
            _numbers(getattr(value, f.name), out)


MODULES = {"000": "juang2023", "001": "lin2010", "002": "zhang2023", "003": "juang2022", "004": "lenzo2017"}
"""Each paper's data module in :mod:`springlab.papers`."""


def printed_values(*keys: str) -> frozenset[float]:
    """Every number the data modules of papers ``keys`` (all five without) keep: their module constants,
    looked into (tuples, dicts, arrays, dataclasses), in their units and also in degrees (an angle kept in
    rad, where that is a whole number of thousandths of a degree: the radians of any other number would
    match prose by chance)."""
    import importlib

    out: set[float] = set()
    for name in (MODULES[k] for k in keys or MODULES):
        module = importlib.import_module(f"springlab.papers.{name}")
        for attr, value in vars(module).items():
            if not attr.startswith("_") and not callable(value):
                _numbers(value, out)
    degrees = {round(math.degrees(v), 3) for v in out}  # an angle kept in rad, printed in whole thousandths
    return frozenset(out | {d for d in degrees if abs(d - math.degrees(math.radians(d))) < 1e-9
                            and any(abs(math.radians(d) - v) < 1e-12 for v in out)})


def values_for(stem: str) -> frozenset[float]:
    """The printed values chapter ``stem``'s prose may quote: its paper's, or those of the papers it builds
    on (:data:`springlab.papers.PAPERS`), or none."""
    from springlab.papers import PAPERS

    entry = PAPERS.get(stem, {})
    keys = (entry["key"],) if entry.get("key") else tuple(entry.get("builds_on", ()))
    return printed_values(*keys) if keys else frozenset()


def _value(text: str) -> float | None:
    try:
        return float(text.replace(",", "").replace("−", "-"))
    except ValueError:
        return None


def _printed(x: float, text: str, values) -> bool:
    """Whether ``x`` (written ``text``) is one of ``values`` to the digits it is written with (a whole
    number exactly)."""
    decimals = len(text.split(".")[1]) if "." in text and "e" not in text.lower() else 0
    step = 0.5 * 10.0 ** -decimals if decimals else 1e-9 * abs(x)
    return any(abs(abs(x) - abs(v)) <= step * (1 + 1e-9) for v in values)


def unglued(markdown: str, values=frozenset()) -> list[str]:
    """The numbers of ``markdown`` (a Markdown cell's text) that are neither glued, nor printed by a paper
    (``values``, :func:`printed_values`; matched to the prose's own digits), nor a reference, nor a small
    count (see the module docstring), in order."""
    text = _DROP.sub(" ", markdown)
    text = _MATH.sub(lambda m: " " + _INDEX.sub(" ", m.group(1)) + " ", text)
    text = _REFERENCE.sub(" ", text)
    out = []
    for m in _NUMBER.finditer(text):
        token = m.group(0)
        x = _value(token)
        if x is None:
            continue
        whole = re.fullmatch(r"[-+−]?\d+", token) is not None
        if whole and abs(x) <= SMALL and not _UNIT_AFTER.match(text, m.end()):
            continue
        if _printed(x, token.lstrip("+-−"), values):
            continue
        out.append(token)
    return out
