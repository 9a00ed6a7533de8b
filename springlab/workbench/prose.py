"""The book's prose made readable: papers named by author and year, equations numbered and linked.

The notebooks, the library's comments and the claims cite a paper by its key (``000 Eq. (23b)``,
``paper 003's``), which a reader of the code can grep. A reader of the book wants the author and
the year, linked to the paper's chapter, and an equation mention that opens the equation. While
the book's sources are staged (:mod:`springlab.workbench.book`):

* every display equation of a chapter's Markdown that carries the paper's own number
  (``$$ ... \\tag{23b} $$``, a block of its own) gets an anchor ``eq-<key>-<number>``
  (:func:`anchor_equations`);
* in Markdown cells and in the cells' Markdown and HTML outputs, a paper's key becomes its
  authors and year, linked to its chapter, and an equation mention (in the chapter of paper
  000 "Eq. (23b)" or "Eq. 23b"; anywhere "000 Eq. (23b)") a link to the equation where the book
  shows it with that number
  (:func:`link_markdown`, :func:`link_html`). Code, math, links and HTML tags are left as
  they are; an equation the book does not show stays plain text.

>>> names = {"000": ("juang2023_spatial_balance", "Juang et al. (2023)")}
>>> link_markdown("as in 000 Eq. (23b) and 000 Table 3", "003", names, {("000", "23b")})
'as in {doc}`Juang et al. (2023) <juang2023_spatial_balance>`, {ref}`Eq. (23b) <eq-000-23b>` and {doc}`Juang et al. (2023) <juang2023_spatial_balance>`, Table 3'
"""

from __future__ import annotations

import re
from html import escape

__all__ = ["equation_label", "equation_numbers", "anchor_equations", "link_markdown", "link_html", "name_papers"]

_BLOCK = re.compile(r"(?ms)^[ \t]*\$\$.*?\$\$[ \t]*$")
"""A display equation that is a block of its own: ``$$`` opens a line, ``$$`` closes one."""
_TAG = re.compile(r"\\tag\{([^{}]+)\}")
_EQ = (r"Eqs?\.\s?(?:\((?P<{0}1>\d+[a-z]?)(?:[\-–][a-z]|[\-–]\d+[a-z]?)?\)|(?P<{0}2>\d+[a-z]?)\b)"
       r"(?:[\-–](?:\(\d+[a-z]?\)|\d+[a-z]?\b|[a-z]\b\)?))?")
"""An equation mention, "Eq. (23b)" or "Eq. 8", or a range, "Eqs. (20)-(30)", "Eqs. 8-18",
"Eqs. (48a-f)": a range links to its first equation."""
_MENTION = re.compile(
    r"(?<![\w.,/\-])(?P<paper>[Pp]apers?[\s-]+)?(?P<key>00[0-9])(?![\w]|[.,]\d)(?P<poss>(?:['’]|&#x27;|&#39;)s)?"
    r"(?:(?P<gap>\s+)(?P<eq>" + _EQ.format("n") + r")|\s+(?P<other>Table|Fig|Section))?"
    r"|(?<![\w])(?P<eq0>" + _EQ.format("m") + r")")
"""A paper's key ("000", "paper 000's", "papers 000"), perhaps followed by an equation mention
or a table, figure or section; or an equation mention on its own."""
_PROTECTED_MD = re.compile(
    r"```.*?```|\{[\w:-]+\}`[^`]*`|`[^`]*`|\$\$.*?\$\$|\$[^$\n]+\$|!?\[[^\]]*\]\([^)]*\)|<[^>]+>"
    r"|^\([^)\n]*\)=[ \t]*$", re.S | re.M)
"""Markdown that stays as it is: code, roles, math, links and images, HTML tags, MyST targets."""
_PROTECTED_HTML = re.compile(r"<(script|style|code|pre|a)\b.*?</\1>|<[^>]+>", re.S | re.I)


def equation_label(key: str, number: str) -> str:
    """The anchor of paper ``key``'s equation ``number`` in the book: ``eq-000-23b``."""
    return f"eq-{key}-{number}"


def equation_numbers(text: str) -> list[str]:
    """The ``\\tag`` numbers of the display equations (blocks of their own) in Markdown ``text``."""
    return [tag.strip() for block in _BLOCK.findall(text) for tag in _TAG.findall(block)]


_ENVIRONMENT = re.compile(r"\\begin\{(equation|align|alignat|gather|multline|flalign)\*?\}")


def anchor_equations(text: str, key: str) -> str:
    """``text`` with each display equation that carries a ``\\tag`` set as Sphinx math that
    MathJax receives unchanged (``nowrap``), after a MyST target ``(eq-<key>-<number>)=`` per tag.

    Sphinx would wrap a display with a line break (``\\\\``) in ``split``, where MathJax refuses
    ``\\tag``; unwrapped, the block is ``\\[...\\]``, or an AMS environment (``align``) as it is.
    """
    def anchor(match):
        tags = [t.strip() for t in _TAG.findall(match.group(0))]
        if not tags:
            return match.group(0)
        body = match.group(0).strip()[2:-2].strip()
        math = body if _ENVIRONMENT.match(body) else f"\\[{body}\\]"
        targets = "".join(f"({equation_label(key, t)})=\n" for t in tags)
        return f"\n{targets}```{{math}}\n:nowrap:\n{math}\n```"
    return _BLOCK.sub(anchor, text)


def _outside(text: str, protected: re.Pattern, change) -> str:
    out, last = [], 0
    for match in protected.finditer(text):
        out += [change(text[last:match.start()]), match.group(0)]
        last = match.end()
    return "".join(out + [change(text[last:])])


def _rewrite(text: str, here: str | None, names: dict, labels: set, paper, equation) -> str:
    """Replace each mention in plain ``text``: ``paper(key, shown)`` and ``equation(key,
    number, shown)`` give the replacement's pieces (``equation`` is called only for an
    equation the book labels)."""
    def one(match):
        if match.group("eq0"):
            number = match.group("m1") or match.group("m2")
            return equation(here, number, match.group("eq0")) if (here, number) in labels else match.group(0)
        key = match.group("key")
        if key not in names:
            return match.group(0)
        if match.group("eq"):
            number = match.group("n1") or match.group("n2")
            shown = match.group("eq")
            eq = equation(key, number, shown) if (key, number) in labels else shown
            if key == here:  # the chapter's own paper: its equation needs no name
                return eq
        if key == here:  # "the paper", "The paper's"
            name = ("The paper" if match.group(0)[0].isupper() else "the paper") + (match.group("poss") or "")
        else:
            name = paper(key, names[key][1]) + (match.group("poss") or "")
        if match.group("eq"):
            return f"{name}{'' if match.group('poss') else ','}{match.group('gap')}{eq}"
        if match.group("other"):
            return f"{name}{'' if match.group('poss') else ','} {match.group('other')}"
        return name
    return _MENTION.sub(one, text)


def name_papers(text: str, here: str | None, names: dict) -> str:
    """Plain ``text`` (a printed output) with each paper's key replaced by its authors and year."""
    return _rewrite(text, here, names, set(), lambda key, shown: shown, lambda key, number, shown: shown)


def link_markdown(text: str, here: str | None, names: dict, labels: set) -> str:
    """MyST ``text`` of the chapter of paper ``here`` (None: no paper's chapter) with paper keys
    named and linked (``names``: {key: (chapter stem, "Juang et al. (2023)")}; in its own
    chapter a paper is "the paper", and its equations need no name) and equation mentions
    linked to the ``labels`` ({(key, number)}). Headings name papers without links."""
    def paper(key, shown):
        return shown if key == here else f"{{doc}}`{shown} <{names[key][0]}>`"

    def equation(key, number, shown):
        return f"{{ref}}`{shown} <{equation_label(key, number)}>`"

    def line(text_line):
        if text_line.lstrip().startswith("#"):  # a heading names papers, unlinked (it is a link in the contents)
            return _outside(text_line, _PROTECTED_MD, lambda t: name_papers(t, here, names))
        return _outside(text_line, _PROTECTED_MD, lambda t: _rewrite(t, here, names, labels, paper, equation))

    blocks = re.split(r"(```.*?```)", text, flags=re.S)  # a fence spans lines: kept whole
    return "".join(b if b.startswith("```") else "".join(line(x) for x in b.splitlines(keepends=True))
                   for b in blocks)


def link_html(text: str, here: str | None, names: dict, labels: set, *, page: str = "") -> str:
    """HTML ``text`` (a cell's HTML output, a claims table) with the same links as
    :func:`link_markdown`, outside tags, links and code. ``page``: the chapter the HTML sits in
    (its equations link in-page); elsewhere links go to ``<stem>.html``."""
    def paper(key, shown):
        return escape(shown) if key == here and page else f'<a href="{names[key][0]}.html">{escape(shown)}</a>'

    def equation(key, number, shown):
        where = "" if names[key][0] == page else f"{names[key][0]}.html"
        return f'<a href="{where}#{equation_label(key, number)}">{shown}</a>'

    return _outside(text, _PROTECTED_HTML, lambda t: _rewrite(t, here, names, labels, paper, equation))


_POWER = re.compile(r"(?<![\w.])(-?\d+(?:\.\d+)?)e([+-]?)0*(\d+)(?![\w.])")
_SUPERSCRIPT = str.maketrans("0123456789-", "\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079\u207b")


def powers_of_ten(text: str) -> str:
    """A number Python printed in exponent form ("1e-06", "1.6e-04", "2e+03") written as a paper prints it:
    "1 × 10⁻⁶", "1.6 × 10⁻⁴", "2 × 10³". The book applies it to the numbers glued into its prose."""

    def power(m: re.Match) -> str:
        exponent = ("-" if m.group(2) == "-" else "") + m.group(3)
        return f"{m.group(1)} \u00d7 10{exponent.translate(_SUPERSCRIPT)}"

    return _POWER.sub(power, text)
