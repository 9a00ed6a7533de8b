"""One Markdown table helper for the notebooks, the library's reports and the reproduction
report. A :class:`Table` shows itself as Markdown in Jupyter (so a cell that ends with
one renders it) and as its Markdown text elsewhere.

It sits beside :mod:`springlab.errors` rather than in the workbench because the design
and mechanism layers render tables too, and they must not import the layer above them.

>>> t = Table(["link", "m (kg)"], [[2, 4.0], [3, 3.2]])
>>> print(t)
| link | m (kg) |
|---|---|
| 2 | 4.0 |
| 3 | 3.2 |
"""

from __future__ import annotations

from springlab.errors import SpringlabError

__all__ = ["Table", "Note", "markdown_table"]


def _cell(value) -> str:
    return str(value).replace("\n", " ").replace("|", "\\|") if value is not None else ""


def markdown_table(headers, rows) -> str:
    """A Markdown table: one header row, then one line per row (each row a sequence of
    cells, or a dict keyed by the headers). ``None`` prints as an empty cell; '|' is escaped."""
    headers = [str(h) for h in headers]
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    for row in rows:
        cells = [row.get(h) for h in headers] if isinstance(row, dict) else list(row)
        if len(cells) != len(headers):
            raise SpringlabError(f"a table row has {len(cells)} cells for {len(headers)} headers: {cells!r}")
        lines.append("| " + " | ".join(_cell(c) for c in cells) + " |")
    return "\n".join(lines)


class Table:
    """Headers and rows, shown as Markdown (see :func:`markdown_table`)."""

    def __init__(self, headers, rows):
        self.headers = list(headers)
        self.rows = [row if isinstance(row, dict) else list(row) for row in rows]

    def markdown(self) -> str:
        return markdown_table(self.headers, self.rows)

    def transposed(self) -> Table:
        """The table on its side: a row per column after the first (its header, then its
        cells), a column per row (headed by the row's first cell). A wide table of a few rows
        reads down a page's column instead of running off it.

        >>> print(Table(["spring", "k (N/m)", "L0 (mm)"], [["S(1,2)", 294, 40.0], ["S(1,4)", 719, 52.5]]).transposed())
        | spring | S(1,2) | S(1,4) |
        |---|---|---|
        | k (N/m) | 294 | 719 |
        | L0 (mm) | 40.0 | 52.5 |
        """
        rows = [[row.get(h) for h in self.headers] if isinstance(row, dict) else list(row) for row in self.rows]
        return Table([self.headers[0], *(str(row[0]) for row in rows)],
                     [[header, *(row[k] for row in rows)] for k, header in enumerate(self.headers) if k])

    def records(self) -> list[dict]:
        """The rows as dicts keyed by the headers (for JSON)."""
        return [dict(row) if isinstance(row, dict) else dict(zip(self.headers, row, strict=True)) for row in self.rows]

    def _repr_markdown_(self) -> str:
        return self.markdown()

    def __str__(self) -> str:
        return self.markdown()

    def titled(self, title: str) -> Note:
        """The table under a bold ``title``, as one Markdown output (a printed title and a displayed table
        would come apart in the book, which gathers a cell's printed lines together)."""
        return Note(f"**{title}**\n\n{self.markdown()}")


class Note:
    """Markdown text a cell displays where it stands: a title over a table, or a list.

    >>> print(Note.bullets("status", ["a coil too long", "a hook past its allowable"]))
    **status**:
    <BLANKLINE>
    - a coil too long
    - a hook past its allowable
    """

    def __init__(self, text: str):
        self.text = str(text)

    @classmethod
    def bullets(cls, title: str, items, empty: str = "none") -> Note:
        """``title`` and the ``items`` as a list (``empty`` where there are none)."""
        items = [str(i) for i in items]
        return cls(f"**{title}**: {empty}" if not items else f"**{title}**:\n\n" + "\n".join(f"- {i}" for i in items))

    def _repr_markdown_(self) -> str:
        return self.text

    def __str__(self) -> str:
        return self.text
