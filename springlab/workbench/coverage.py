"""What each paper chapter covers: every numbered equation, table and figure of its paper, the section that
treats it, and its verdict.

Each paper's inventory is kept with its data, ``springlab/papers/items_<key>.toml``: one entry an item, in
the paper's order, saying what it is, the chapter's section that treats it and how (:data:`HOWS`). An item
the chapter compares gets its verdict from the chapter's claims (:mod:`springlab.workbench.claims`): those
whose ``where`` names it (:func:`references`: "Table 4, Eqs. (27a-e)" names Table 4 and Eqs. (27a) to
(27e)), or that the inventory lists for it. The book puts the table at the top of each paper chapter and
sums it per paper in the report (:mod:`springlab.workbench.book`).

>>> [i.item for i in inventory("004")][:2]
['Eq. (1)', 'Eq. (2)']
>>> sorted(references("Table 5, Eqs. (27b, d, e)", {"Table 5", "Eq. (27b)", "Eq. (27c)", "Eq. (27d)", "Eq. (27e)"}))
['Eq. (27b)', 'Eq. (27d)', 'Eq. (27e)', 'Table 5']
"""

from __future__ import annotations

import re
import sys
from collections import Counter
from dataclasses import dataclass
from html import escape
from importlib import resources

from springlab.errors import SpringlabError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["KINDS", "equation_item", "HOWS", "Item", "inventory", "references", "concerning", "verdict", "how", "summary", "table_html",
           "gaps"]

KINDS = (("Eq.", "numbered equation"), ("Table", "table"), ("Fig.", "figure"))
"""The kinds of numbered item, as an item's name begins, and their name in words."""


def equation_item(number: str) -> str:
    """An equation's item name: '23b' -> the paper's own form, as :class:`Item` writes it."""
    return f"Eq. ({number})"


HOWS = {
    "compared": "the chapter compares the paper's printed numbers with its own in claims; the verdict is their "
                "statuses",
    "derived": "the chapter derives or rebuilds it and checks it by an independent route (the note says which)",
    "used": "the library implements it and the chapter's results rest on it; it is checked through those results",
    "shown": "the chapter shows it as the paper prints it (an input), or redraws it without comparing numbers",
    "not covered": "the chapter does not treat it; the note says why",
}
"""How a chapter treats a paper item, strongest first, with its meaning (the report defines each)."""

_ID = re.compile(r"^(?:Eq\. \((?P<eq>\d+)(?P<sub>[a-z]?)\)|Table (?P<table>\d+)|Fig\. (?P<fig>\d+))$")


@dataclass(frozen=True)
class Item:
    """One numbered item of a paper: ``item`` as the paper numbers it ("Eq. (23b)", "Table 3", "Fig. 16"),
    ``what`` it is, the chapter's ``section`` that treats it ("2b"; "" when not covered), ``how``
    (:data:`HOWS`), a ``note`` (the reason, for one not covered) and the ``claims``' ``where`` prefixes
    that concern it beyond those naming it."""

    item: str
    what: str
    section: str
    how: str
    note: str = ""
    claims: tuple[str, ...] = ()

    @property
    def kind(self) -> str:
        """'Eq.', 'Table' or 'Fig.'."""
        return self.item.split(" ")[0]

    @property
    def number(self) -> tuple[int, str]:
        """(its number, its letter): (23, 'b') for Eq. (23b)."""
        m = _ID.match(self.item)
        return int(m.group("eq") or m.group("table") or m.group("fig")), m.group("sub") or ""


def _item(key: str, k: int, entry: dict) -> Item:
    where = f"springlab/papers/items_{key}.toml, entry {k + 1}"
    unknown = set(entry) - {"item", "what", "section", "how", "note", "claims"}
    if unknown:
        raise SpringlabError(f"{where}: unknown field(s) {sorted(unknown)}: give item, what, section, how, note, "
                             "claims")
    name = str(entry.get("item", ""))
    if not _ID.match(name):
        raise SpringlabError(f"{where}: item = {name!r}: write it as 'Eq. (23b)', 'Table 3' or 'Fig. 16'")
    how = entry.get("how", "")
    if how not in HOWS:
        raise SpringlabError(f"{where} ({name}): how = {how!r}: give one of {', '.join(HOWS)}")
    section, note = str(entry.get("section", "")), str(entry.get("note", ""))
    if how == "not covered" and not note:
        raise SpringlabError(f"{where} ({name}): not covered without a note: say why the chapter leaves it out")
    if how != "not covered" and not section:
        raise SpringlabError(f"{where} ({name}): how = {how!r} without a section: give the chapter's section "
                             "that treats it")
    if not entry.get("what"):
        raise SpringlabError(f"{where} ({name}): no 'what': say in a few words what the item is")
    return Item(name, str(entry["what"]), section, how, note, tuple(entry.get("claims", ())))


def inventory(key: str) -> tuple[Item, ...]:
    """Paper ``key``'s numbered items, in the paper's order (``springlab/papers/items_<key>.toml``).

    :raises SpringlabError: when the paper has no inventory, or an entry is malformed or repeated
    """
    path = resources.files("springlab.papers") / f"items_{key}.toml"
    if not path.is_file():
        raise SpringlabError(f"paper {key!r} has no inventory of its items (springlab/papers/items_{key}.toml)")
    entries = tomllib.loads(path.read_text(encoding="utf-8")).get("items", [])
    items = tuple(_item(key, k, e) for k, e in enumerate(entries))
    seen = Counter(i.item for i in items)
    twice = [name for name, n in seen.items() if n > 1]
    if twice:
        raise SpringlabError(f"springlab/papers/items_{key}.toml lists {', '.join(twice)} more than once")
    return items


def gaps(items) -> list[str]:
    """The numbers missing from each kind's sequence (an equation, table or figure between two listed, or
    before the first): an inventory that skips one has missed an item. Letters run from a with no gap."""
    out = []
    for kind in ("Eq.", "Table", "Fig."):
        numbers = sorted({i.number for i in items if i.kind == kind})
        whole = sorted({n for n, _ in numbers})
        name = "Eq. ({})" if kind == "Eq." else kind + " {}"
        out += [name.format(n) for n in range(1, whole[-1] + 1) if n not in whole] if whole else []
        for n in whole:
            letters = sorted(s for m, s in numbers if m == n and s)
            expected = [chr(ord("a") + j) for j in range(len(letters))]
            if letters != expected:
                out.append(f"Eq. ({n}{'/'.join(sorted(set(expected) - set(letters)))})")
    return out


_KEY = r"(?:(?P<key>00\d)\s+)?"
_EQS = re.compile(_KEY + r"Eqs?\.\s*\((?P<body>[^()]*)\)(?:\s*[-–]\s*\((?P<last>\d+)[a-z]?\))?")
_LAST = r"(?:\s*(?:[-–]|and|,)\s*(?!00\d\b)(?P<last>\d+))?"  # "Figs. 16 and 17", not "Fig. 5 and 000 Table 1"
_TABLES = re.compile(_KEY + r"Tables?\s+(?P<first>\d+)" + _LAST)
_FIGS = re.compile(_KEY + r"(?:Figs?\.|Figures?)\s*(?P<first>\d+)" + _LAST)


def _equations(body: str, last: str | None) -> list[tuple[int, str | None]]:
    """(number, letter or None for any) named by the inside of "Eqs. (...)"."""
    out, number = [], None
    for part in re.split(r"\s*,\s*", body.strip()):
        m = re.fullmatch(r"(\d+)?([a-z])?(?:\s*[-–]\s*(\d+)?([a-z])?)?", part)
        if not m:
            continue
        number = int(m.group(1)) if m.group(1) else number
        if number is None:
            continue
        first, to_n, to_s = m.group(2), m.group(3), m.group(4)
        if to_s and not to_n:  # 27a-e
            out += [(number, chr(c)) for c in range(ord(first or "a"), ord(to_s) + 1)]
        elif to_n:  # 20-30
            out += [(n, None) for n in range(number, int(to_n) + 1)]
        else:
            out.append((number, first))
    if last is not None and out:  # "Eqs. (20)-(30)"
        out += [(n, None) for n in range(out[-1][0] + 1, int(last) + 1)]
    return out


def references(where: str, names, key: str | None = None) -> set[str]:
    """The items among ``names`` that a claim's ``where`` names: its equations (ranges and letter lists
    expanded), tables and figures; one cited with another paper's key than ``key`` is not this paper's."""
    names, out = set(names), set()

    def own(m) -> bool:
        return m.group("key") is None or m.group("key") == key

    for m in _EQS.finditer(where):
        if own(m):
            for n, s in _equations(m.group("body"), m.group("last")):
                out |= {x for x in names if x.startswith(f"Eq. ({n}") and re.fullmatch(
                    rf"Eq\. \({n}{s if s else '[a-z]?'}\)", x)}
    for pattern, kind in ((_TABLES, "Table"), (_FIGS, "Fig.")):
        for m in pattern.finditer(where):
            if own(m):
                first = int(m.group("first"))
                last = int(m.group("last")) if m.group("last") else first
                out |= {f"{kind} {n}" for n in range(first, last + 1)} & names
    return out


def concerning(items, records, key: str | None = None) -> dict[str, list[dict]]:
    """{item: the claims among ``records`` that concern it}: naming it in their ``where``, or listed for it."""
    names = {i.item for i in items}
    out = {i.item: [] for i in items}
    for r in records:
        where = r.get("where", "")
        hit = references(where, names, key) | {i.item for i in items if any(where.startswith(p) for p in i.claims)}
        for name in hit:
            out[name].append(r)
    return out


def how(item: Item, claims: list[dict]) -> str:
    """How the chapter treats ``item``: compared where claims concern it, else as its inventory says."""
    return "compared" if claims else item.how


def verdict(item: Item, claims: list[dict]) -> str:
    """The item's verdict: its claims' statuses with their counts ("reproduced (6 claims); rounding"), or how the
    chapter treats it."""
    from springlab.workbench.claims import REPORT_COLUMNS, report_column

    if not claims:
        return item.how
    counts = Counter(report_column(r) for r in claims)
    return "; ".join(f"{status} ({counts[status]} claims)" if counts[status] > 1 else status
                     for status in REPORT_COLUMNS if counts[status])


def summary(items, claims_by_item) -> Counter:
    """How many of the items the chapter compares, derives, uses, shows and leaves out."""
    return Counter(how(i, claims_by_item[i.item]) for i in items)


def _section_link(item: Item, sections: dict[str, str]) -> str:
    if not item.section:
        return ""
    href = sections.get(item.section)
    label = f"§{escape(item.section)}"
    return f'<a href="#{href}">{label}</a>' if href else label


def table_html(items, claims_by_item, sections: dict[str, str], equations: dict[str, str] | None = None) -> str:
    """The coverage table, one HTML block with no blank line (Markdown keeps it whole): item, what it is,
    the section (a link where ``sections`` maps its number to an anchor), how, and the verdict or the note.
    ``equations`` maps an equation's item to its anchor where the chapter shows it."""
    equations = equations or {}
    rows = []
    for i in items:
        claims = claims_by_item[i.item]
        name = escape(i.item)
        if i.item in equations:
            name = f'<a href="#{equations[i.item]}">{name}</a>'
        said = verdict(i, claims) if claims else i.note
        rows.append(f'<tr data-item="{escape(i.item)}" data-how="{escape(how(i, claims))}"><td>{name}</td>'
                    f"<td>{escape(i.what)}</td><td>{_section_link(i, sections)}</td>"
                    f"<td>{escape(how(i, claims))}</td><td>{escape(said)}</td></tr>")
    return ('<table class="coverage"><thead><tr><th>item</th><th>what it is</th><th>where</th><th>how</th>'
            "<th>verdict, or why not</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table>")
