"""The reader's book: the executed notebooks, the reproduction report and the API reference
as one Sphinx site (myst-nb and sphinx-book-theme), built into ``build/site``.

:func:`build_book` writes the book's sources into ``build/book/src`` (only the files whose
text changed, so Sphinx re-reads only those) and runs Sphinx with warnings as errors:

* ``index.md``, the front page: what springlab is, each paper with its DOI (where its text
  prints one), the notebook's run time and its claims counted by status, and how to read a claim;
* one chapter per paper and the design chapter: the executed notebooks from
  ``build/notebooks``, read, not run (papermill is the executor), each section heading given
  a label ``<stem>-s<k>`` so the report can point at it;
* ``report.md``: every claim beside the paper's value, each linked to the notebook section
  that makes it (the claim's cell, recorded by :class:`~springlab.workbench.claims.Claims`);
* ``using.md``, ``glossary.md`` and ``performance.md`` (:data:`PAGES`): the user's guide and the
  glossary, written by hand beside the notebooks, and what ``make bench`` last measured, written by it;
* ``api/``: the library's docstrings (autodoc), each citation (a paper's key before an
  equation, table or figure) linked to the paper's chapter, and the source of every module
  (viewcode) with the citations in its comments linked too.

MathJax 3 (its ``es5`` folder, from the ``django-static-mathjax`` package) is copied into the
site: the site opens from ``file://`` without a network. Its SVG output draws every glyph as a
path, so no web font has to load from disk (a browser may refuse fonts from ``file://``).
"""

from __future__ import annotations

import json
import os
import pkgutil
import re
import shutil
from collections import Counter
from dataclasses import replace
from pathlib import Path

from docutils.nodes import make_id

from springlab.errors import SolverError
from springlab.papers import PAPERS
from springlab.workbench import coverage, prose, view3d
from springlab.workbench.claims import (
    MEANINGS,
    REPORT_COLUMNS,
    check_statuses,
    html_table,
    legend_html,
    report_column,
)

CONF_DIR = Path(__file__).resolve().parent / "bookconf"
ROOT = Path(__file__).resolve().parents[2]
PAGES = {"using": ROOT / "notebooks" / "using_springlab.md", "glossary": ROOT / "notebooks" / "glossary.md",
         "performance": ROOT / "benchmarks" / "RESULTS.md"}
"""The book's pages that are not notebooks: the user's guide (the command line, arm files, the springs made
real, what to do when something goes wrong, the package's layout), the glossary of the words the chapters
use, and the benchmarks' results (their paths in the project's checkout).

:meta hide-value:
"""
MATHJAX_SCRIPT = "tex-svg-full.js"
"""MathJax 3's component the book loads from ``_static/mathjax``: TeX in (every extension
preloaded, so nothing is fetched on demand), SVG out."""
CHAPTER_ORDER = ("juang2023_spatial_balance", "lin2010_pseudobases", "zhang2023_dyad",
                 "juang2022_spring_efficiency", "lenzo2017_two_spring_arm", "springlab_design_your_arm",
                 "springlab_real_arms")
"""The chapters in the papers' key order (000 .. 004), then the design chapter and the real arms."""

_HEADING = re.compile(r"^(#{1,6})\s+(.+?)\s*$", re.M)
CITATION = re.compile(r"(?<![\w`])(00[0-9])(?= Eqs?\.| Table| Fig| Section)")
"""A paper's key before the number of one of its equations, tables, figures or sections: linked
to the paper's chapter in docstrings (the book's conf) and in the source pages' comments."""


def _write_if_changed(path: Path, content: str | bytes) -> None:
    """Write ``content`` unless ``path`` holds it already (its mtime then tells Sphinx nothing changed)."""
    data = content.encode() if isinstance(content, str) else content
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_bytes() != data:
        path.write_bytes(data)


def section_label(stem: str, k: int) -> str:
    """The label of section ``k`` (0: the title) of notebook ``stem`` in the book."""
    return f"{stem}-s{k}"


def sections(notebook: dict) -> tuple[list[str], dict[int, int]]:
    """A notebook's section titles (its headings in order; 0 is the title) and, for each
    executed code cell's execution count, the section it sits in."""
    titles, where, current = [], {}, 0
    for cell in notebook["cells"]:
        if cell["cell_type"] == "markdown":
            for match in _HEADING.finditer("".join(cell["source"])):
                titles.append(match.group(2))
                current = len(titles) - 1
        elif cell["cell_type"] == "code" and cell.get("execution_count"):
            where[cell["execution_count"]] = current
    return titles, where


def paper_names(stems) -> dict[str, tuple[str, str]]:
    """{paper key: (chapter stem, 'Juang et al. (2023)')} for the papers among ``stems``."""
    return {PAPERS[s]["key"]: (s, short_name(s)) for s in stems if PAPERS.get(s, {}).get("key")}


def equation_labels(notebooks: dict[str, dict]) -> set[tuple[str, str]]:
    """{(paper key, equation number)}: the numbered display equations the chapters show."""
    return {(PAPERS[stem]["key"], number) for stem, nb in notebooks.items() if PAPERS.get(stem, {}).get("key")
            for cell in nb["cells"] if cell["cell_type"] == "markdown"
            for number in prose.equation_numbers("".join(cell["source"]))}


def readable(notebook: dict, stem: str, names: dict, labels: set) -> dict:
    """A copy of the notebook as the book shows it (:mod:`springlab.workbench.prose`): its
    numbered equations anchored, papers named by authors and year and linked, equation
    mentions linked, in its Markdown cells and its cells' Markdown and HTML outputs (papers named,
    unlinked, in its printed outputs); papermill's cell of the run's parameters folded, as the notebook's own
    parameters cell is."""
    notebook = json.loads(json.dumps(notebook))
    key = PAPERS.get(stem, {}).get("key")
    for cell in notebook["cells"]:
        tags = cell.get("metadata", {}).get("tags", [])
        if "injected-parameters" in tags and "hide-input" not in tags:  # papermill's: the run's parameters, folded
            cell["metadata"]["tags"] = [*tags, "hide-input"]
        if cell["cell_type"] == "markdown":
            text = "".join(cell["source"])
            cell["source"] = prose.link_markdown(prose.anchor_equations(text, key) if key else text, key, names, labels)
            continue
        for output in cell.get("outputs", []):
            if output.get("output_type") == "stream":
                output["text"] = prose.name_papers("".join(output["text"]), key, names)
            data = output.get("data", {})
            if "text/plain" in data and len(data) == 1:
                data["text/plain"] = prose.name_papers("".join(data["text/plain"]), key, names)
            if "text/markdown" in data:
                data["text/markdown"] = prose.link_markdown("".join(data["text/markdown"]), key, names, labels)
            if "text/html" in data:
                data["text/html"] = prose.link_html("".join(data["text/html"]), key, names, labels, page=stem)
    return notebook


def with_legend(notebook: dict, records: list[dict]) -> dict:
    """A copy of the notebook with a legend of the statuses its claims ``records`` use
    (:func:`springlab.workbench.claims.legend_html`) above its first claims table: a reader meets each
    verdict's meaning where the verdicts first stand."""
    notebook = json.loads(json.dumps(notebook))
    for cell in notebook["cells"]:
        for output in cell.get("outputs", []):
            data = output.get("data", {})
            html = "".join(data.get("text/html", ""))
            if '<table class="claims">' in html:
                data["text/html"] = html.replace('<table class="claims">', legend_html(records) + '<table class="claims">', 1)
                return notebook
    return notebook


def labelled(notebook: dict, stem: str) -> dict:
    """A copy of the notebook with a MyST label ``(<stem>-s<k>)=`` before each heading."""
    notebook = json.loads(json.dumps(notebook))
    k = 0
    for cell in notebook["cells"]:
        if cell["cell_type"] != "markdown":
            continue
        text = "".join(cell["source"])

        def label(match):
            nonlocal k
            out = f"({section_label(stem, k)})=\n{match.group(0)}"
            k += 1
            return out
        cell["source"] = _HEADING.sub(label, text)
    return notebook


_MD_SPECIAL = re.compile(r"([\\`*_\[\]{}<>|$#])")


def _md(text) -> str:
    """Text made literal inside a Markdown table cell."""
    return _MD_SPECIAL.sub(r"\\\1", str(text)).replace("\n", " ")


def _run_time(notebook: dict) -> float | None:
    return notebook.get("metadata", {}).get("papermill", {}).get("duration")


def load_claims(figures_dir) -> dict[str, list[dict]]:
    """{notebook stem: its claims} from every figures/<stem>/claims.json."""
    return {p.parent.name: json.loads(p.read_text()) for p in sorted(Path(figures_dir).glob("*/claims.json"))}


def _tally(records: list[dict]) -> str:
    count = Counter(report_column(r) for r in records)
    return ", ".join(f"{count[s]} {s}" for s in REPORT_COLUMNS if count.get(s)) or "none"


def _authors(paper: dict, names: dict, default: str = "") -> str:
    """A registry entry's authors as MyST text, any paper they cite by key named and linked."""
    return prose.link_markdown(_md(paper.get("authors", default)), None, names, set())


def short_name(stem: str) -> str:
    """'Juang et al. (2023)', 'design your arm': a chapter's name in a table."""
    paper = PAPERS.get(stem)
    if not paper or not paper.get("key"):
        return stem.replace("springlab_", "").replace("_", " ")
    names = [a.strip().split(" ")[-1] for a in paper["authors"].split(",")]
    who = names[0] + (" et al." if len(names) > 2 else f" and {names[1]}" if len(names) == 2 else "")
    return f"{who} ({paper['year']})"


def front_page(stems: list[str], notebooks: dict[str, dict], claims: dict[str, list[dict]], *,
               api: bool = True, thumbs: frozenset = frozenset()) -> str:
    """The book's front page (MyST Markdown); ``thumbs``: the stems with a key figure in ``thumbs/``."""
    lines = ["# springlab: spring gravity balancing, reproduced", "",
             "springlab recomputes the derivations, tables and figures of five papers on spring gravity "
             "balancing of robot arms, checks every number against the printed one, and designs springs "
             "for a reader's own arm. A design is balanced when the total potential energy (gravity and "
             "springs) does not depend on the pose; springlab checks that three independent ways: the "
             "papers' algebra (the quadratic form), direct geometry, and a multibody simulation (exudyn).",
             "", run_yourself(), "## The papers", ""]
    names = paper_names(stems)
    for stem in stems:
        paper = PAPERS.get(stem, {"authors": "", "year": "", "title": stem, "venue": "", "doi": None})
        doi = (f"doi:[{paper['doi']}](https://doi.org/{paper['doi']})" if paper.get("doi")
               else (f"no DOI (the text prints none; {paper['url']})" if paper.get("url")
                     else "no DOI (the text prints none)") if paper.get("key") else "")
        run = _run_time(notebooks[stem])
        year = f" ({paper['year']})" if paper.get("key") else ""  # springlab's own chapters: no paper's year
        where = "; ".join(t for t in (_md(paper.get("venue") or ""), doi) if t)  # the venue; its DOI
        lines += [f"**{_authors(paper, names)}{year}**, *{_md(paper['title'])}*. {where}", "",
                  f"- chapter: {{doc}}`{stem}`; run time {run:.1f} s" if run is not None else
                  f"- chapter: {{doc}}`{stem}`; run time unknown",
                  f"- claims: {_tally(claims.get(stem, []))}", ""]
        if stem in thumbs:  # at the column's width, its caption also its alt text
            caption = paper.get("key_caption", "")
            lines += [f"```{{figure}} thumbs/{stem}.png", f":alt: {prose.name_papers(caption, None, names)}",
                      f":target: {stem}.html", "",
                      prose.link_markdown(_md(caption), paper.get("key"), names, set()), "```", ""]
    lines += ["## How to read a claim", "",
              "Every number a notebook reproduces is a *claim*: the quantity, where the paper prints it, "
              "the paper's value, ours, the difference, the tolerance and why it is what it is, and a status:",
              "", *_statuses(), "",
              f"All claims: {_tally([r for records in claims.values() for r in records])}. "
              "{doc}`report` lists every one, linked to the notebook section that makes it.", "",
              "```{toctree}", ":hidden:", ":caption: The papers", "", *[s for s in stems if PAPERS.get(s, {}).get("key")],
              "```", "", "```{toctree}", ":hidden:", ":caption: Your arm", "",
              *[s for s in stems if not PAPERS.get(s, {}).get("key")], "```", "",
              "```{toctree}", ":hidden:", ":caption: Using springlab", "", *PAGES, "```", "",
              "```{toctree}", ":hidden:", ":caption: Reference", "", "report", *(["api/index"] if api else []), "```", ""]
    return "\n".join(lines)


def _statuses() -> list[str]:
    """Every status a claim may have, with its meaning (MyST list items)."""
    last = len(REPORT_COLUMNS) - 1
    return [f"- **{status}**: {_md(MEANINGS[status])}{'.' if k == last else ';'}" for k, status in enumerate(REPORT_COLUMNS)]


def _kinds(items) -> str:
    """'48 numbered equations, 5 tables and 17 figures'."""
    counts = Counter(i.kind for i in items)
    parts = [f"{counts[kind]} {word if counts[kind] == 1 else word + 's'}" for kind, word in coverage.KINDS
             if counts[kind]]
    return ", ".join(parts[:-1]) + (" and " if len(parts) > 1 else "") + parts[-1]


def coverage_markdown(stem: str, notebook: dict, records: list[dict]) -> str:
    """What chapter ``stem`` covers of its paper (:mod:`springlab.workbench.coverage`): a sentence counting
    its items by how the chapter treats them, and the whole table, folded, each item linked to the
    section that treats it and, for an equation the chapter shows, to the equation. "" for a chapter
    without a paper."""
    key = PAPERS.get(stem, {}).get("key")
    if not key:
        return ""
    names = paper_names(list(PAPERS))
    items = tuple(replace(i, what=prose.name_papers(i.what, key, names), note=prose.name_papers(i.note, key, names))
                  for i in coverage.inventory(key))  # another paper by its authors and year
    by_item = coverage.concerning(items, records, key)
    titles, _ = sections(notebook)
    anchors = {_section_number(t, k)[1:]: make_id(section_label(stem, k)) for k, t in enumerate(titles) if k}
    shown = {coverage.equation_item(n): make_id(prose.equation_label(key, n)) for cell in notebook["cells"]
             if cell["cell_type"] == "markdown" for n in prose.equation_numbers("".join(cell["source"]))}
    counts = coverage.summary(items, by_item)
    verbs = {"compared": "compares {} with its own numbers", "derived": "derives {}", "used": "uses {}",
             "shown": "shows {} as printed", "not covered": "leaves {} out, each with its reason"}
    said = [verbs[h].format(counts[h]) for h in coverage.HOWS if counts[h]]
    sentence = ", ".join(said[:-1]) + (" and " if len(said) > 1 else "") + said[-1]
    compared = [r for i in items for r in by_item[i.item]]  # a reader meets these statuses here first
    legend = legend_html(compared, lead="How to read the verdicts: a compared item's verdict is the status of its "
                         "claims", css="coverage-legend") if compared else ""
    return (f"**What this chapter covers.** Of the paper's {_kinds(items)}, the chapter {sentence} "
            "({ref}`how and verdict <coverage>`):\n\n"
            '<details class="coverage"><summary>Every numbered item of the paper, where the chapter treats it, '
            "and its verdict</summary>" + legend + coverage.table_html(items, by_item, anchors, shown) + "</details>")


def _coverage_report(stems: list[str], claims: dict[str, list[dict]]) -> list[str]:
    """The report's coverage section: how a chapter treats an item, and the items counted per paper."""
    papers = [s for s in stems if PAPERS.get(s, {}).get("key")]
    lines = ["(coverage)=", "## Coverage of the papers", "",
             "Each paper chapter opens with a table of every numbered equation, table and figure of its paper, "
             "the section that treats it and how:", "",
             *[f"- **{h}**: {_md(m)}{'.' if h == 'not covered' else ';'}" for h, m in coverage.HOWS.items()], "",
             "| how | " + " | ".join(f"{{doc}}`{short_name(s)} <{s}>`" for s in papers) + " | all |",
             "|---|" + "---:|" * (len(papers) + 1)]
    counts = {}
    for s in papers:
        items = coverage.inventory(PAPERS[s]["key"])
        counts[s] = coverage.summary(items, coverage.concerning(items, claims.get(s, []), PAPERS[s]["key"]))
    for h in (*coverage.HOWS, "total"):
        row = [sum(counts[s].values()) if h == "total" else counts[s].get(h, 0) for s in papers]
        lines.append(f"| {'**total**' if h == 'total' else h} | " + " | ".join(map(str, row)) + f" | {sum(row)} |")
    return lines + [""]


def _section_number(title: str, k: int) -> str:
    """'§2b' for a heading "2b. The rules ...", else '§k' (the k-th heading)."""
    number = re.match(r"(\w{1,4})\.\s", title)
    return f"§{number.group(1) if number else k}"


def report_page(stems: list[str], notebooks: dict[str, dict], claims: dict[str, list[dict]],
                labels: set = frozenset()) -> str:
    """The reproduction report (MyST Markdown): counts per paper and status, then every claim
    with a link to the section of its notebook that makes it (and, where it cites one of the
    ``labels``' equations, to the equation)."""
    names = paper_names(stems)
    check_statuses([r for records in claims.values() for r in records])
    lines = ["# Reproduction report", "",
             "Every number the notebooks reproduce, beside the paper's, from `figures/<notebook>/claims.json` "
             "(the same claims as `figures/REPRODUCTION.md`). The last column links to the notebook section "
             "whose cell records the claim.", "", "## Statuses", "", *_statuses(), "",
             *_coverage_report(stems, claims),
             "## Claims by paper and status", "",
             "| status | " + " | ".join(f"{{doc}}`{short_name(stem)} <{stem}>`" for stem in stems) + " | all |",
             "|---|" + "---:|" * (len(stems) + 1)]
    counts = {stem: Counter(report_column(r) for r in claims.get(stem, [])) for stem in stems}
    for status in (*REPORT_COLUMNS, "total"):
        row = [len(claims.get(stem, [])) if status == "total" else counts[stem].get(status, 0) for stem in stems]
        name = "**total**" if status == "total" else status
        lines.append(f"| {name} | " + " | ".join(str(n) for n in row) + f" | {sum(row)} |")
    for stem in stems:
        records = claims.get(stem, [])
        if not records:
            continue
        titles, where = sections(notebooks[stem])
        paper = PAPERS.get(stem, {})
        made = []
        for r in records:
            k = where.get(r.get("cell"))  # None: recorded outside a kernel, or in no numbered cell
            made.append((f"{stem}.html#{make_id(section_label(stem, k))}", _section_number(titles[k], k))
                        if k is not None else None)
        year = f" ({paper['year']})" if paper.get("key") else ""
        lines += ["", f"## {_authors(paper, names, stem)}{year}", "",
                  f"Chapter: {{doc}}`{stem}`.", "",
                  prose.link_html(html_table(records, made_in=made), paper.get("key"), names, labels)]
    return "\n".join(lines) + "\n"


def api_pages() -> dict[str, str]:
    """{path under api/: MyST text}: one page per springlab package with its modules (autodoc)."""
    import springlab

    modules = sorted(m.name for m in pkgutil.walk_packages(springlab.__path__, "springlab.")
                     if not m.name.rsplit(".", 1)[-1].startswith("__"))
    packages = ["springlab", *sorted({m for m in modules if _is_package(m)})]
    groups: dict[str, list[str]] = {p: [] for p in packages}
    for m in modules:
        if _is_package(m):
            continue
        parent = m.rsplit(".", 1)[0]
        groups.setdefault(parent, []).append(m)
    pages = {"index.md": "\n".join(
        ["# API reference", "",
         "The library's docstrings, package by package. An equation's citation (the paper's key, then the number) links to "
         "the chapter of that paper; each module's `[source]` link shows its code, whose equation "
         "comments link to the chapters too.", "", "```{toctree}", ":maxdepth: 1", "",
         *packages, "```", ""])}
    for package in packages:
        # autodoc's directives write reStructuredText: they run inside eval-rst
        lines = [f"# `{package}`", "", "```{eval-rst}", f".. automodule:: {package}",
                 # the top package's names are lazy re-exports, documented in their own modules
                 *(["   :no-members:"] if package == "springlab" else []), "```", ""]
        for m in groups.get(package, []):
            lines += [f"## `{m}`", "", "```{eval-rst}", f".. automodule:: {m}", "```", ""]
        pages[f"{package}.md"] = "\n".join(lines)
    return pages


def _is_package(module: str) -> bool:
    import importlib.util

    spec = importlib.util.find_spec(module)
    return bool(spec and spec.submodule_search_locations)


def mathjax_dir() -> Path:
    """MathJax 3's ``es5`` folder in the ``django-static-mathjax`` package (import name
    ``mathjax``), found without importing it."""
    import importlib.util

    spec = importlib.util.find_spec("mathjax")
    folder = Path(list(spec.submodule_search_locations)[0]) / "static" / "mathjax" / "es5" \
        if spec is not None and spec.submodule_search_locations else None
    if folder is None or not (folder / MATHJAX_SCRIPT).exists():
        raise SolverError("django-static-mathjax (MathJax 3) is not installed: run `make` to build the environment")
    return folder


def repository() -> str | None:
    """The project's repository, from ``pyproject.toml``'s ``[project.urls]`` (its Repository, Source or
    Homepage), or None where it names none."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    try:
        urls = tomllib.loads((ROOT / "pyproject.toml").read_text()).get("project", {}).get("urls", {})
    except (OSError, tomllib.TOMLDecodeError):
        return None
    return next((urls[k] for k in ("Repository", "Source", "Homepage") if k in urls), None)


def run_yourself(stem: str | None = None) -> str:
    """A chapter's (or, without ``stem``, the front page's) "Run it yourself" box (MyST Markdown): where
    springlab comes from, the command that sets it up, and the one that opens or runs the chapter as the
    book ran it."""
    where = repository()
    start = (f"Clone [springlab]({where}) and run `make figures` in it" if where else
             "In a checkout of springlab, run `make figures`")
    lines = ["```{admonition} Run it yourself", ":class: tip",
             f"{start}: it installs everything into `.venv` on its first run (Python 3.10 or later), then runs "
             "every chapter; `make test` runs the tests."]
    if stem is not None:
        lines += ["", f"This chapter is `notebooks/{stem}.ipynb`: `make lab` opens it in JupyterLab, and",
                  "", f"`.venv/bin/python -m papermill notebooks/{stem}.ipynb {stem}.run.ipynb --cwd notebooks`", "",
                  "runs it as the book did, from `notebooks/`, its figures written to `figures/" + stem + "/`; its parameters, in its "
                  "first code cell, are papermill's `-p name value` (`-p figures_dir elsewhere` keeps the book's "
                  "figures). The download button above gives the notebook as the book ran it."]
    return "\n".join([*lines, "```", ""])


def stage(notebooks_dir, figures_dir, src, *, api: bool = True) -> list[str]:
    """Write the book's sources into ``src`` (with the API reference unless ``api`` is False);
    returns the chapters' stems."""
    notebooks_dir, figures_dir, src = Path(notebooks_dir), Path(figures_dir), Path(src)
    found = {p.stem: p for p in notebooks_dir.glob("*.ipynb")}
    stems = [s for s in CHAPTER_ORDER if s in found] + sorted(set(found) - set(CHAPTER_ORDER))
    notebooks = {s: json.loads(found[s].read_text()) for s in stems}
    claims = load_claims(figures_dir)
    thumbs = set()
    names, labels = paper_names(stems), equation_labels(notebooks)
    for stem in stems:
        shown = with_legend(readable(labelled(notebooks[stem], stem), stem, names, labels), claims.get(stem, []))
        if shown["cells"] and shown["cells"][0]["cell_type"] == "markdown":  # under the title, no cell added:
            first = shown["cells"][0]  # the claims' cell numbers stay the notebook's
            covered = coverage_markdown(stem, notebooks[stem], claims.get(stem, []))
            first["source"] = "".join(first["source"]).rstrip("\n") + "\n\n" + (
                covered + "\n\n" if covered else "") + run_yourself(stem)
        _write_if_changed(src / f"{stem}.ipynb", json.dumps(shown, indent=1))
        figure = PAPERS.get(stem, {}).get("key_figure")
        if figure and (figures_dir / stem / figure).exists():
            _write_if_changed(src / "thumbs" / f"{stem}.png", (figures_dir / stem / figure).read_bytes())
            thumbs.add(stem)
    for gone in set(p.stem for p in src.glob("*.ipynb")) - set(stems):
        (src / f"{gone}.ipynb").unlink()
    _write_if_changed(src / "index.md", front_page(stems, notebooks, claims, api=api, thumbs=frozenset(thumbs)))
    _write_if_changed(src / "report.md", report_page(stems, notebooks, claims, labels))
    for name, path in PAGES.items():
        text = path.read_text() if path.exists() else f"# {name.title()}\n\n`make bench` writes this page.\n"
        _write_if_changed(src / f"{name}.md", prose.link_markdown(text, None, names, labels))
    if api:
        for name, text in api_pages().items():
            _write_if_changed(src / "api" / name, text)
    elif (src / "api").exists():
        shutil.rmtree(src / "api")
    return stems


def build_book(notebooks_dir="build/notebooks", figures_dir="figures", site_dir="build/site",
               work_dir="build/book", *, jobs: int | None = None, api: bool = True) -> Path:
    """Stage the sources and run Sphinx (warnings are errors); returns ``site_dir/index.html``.
    ``api=False`` leaves the API reference out (a quicker book, for tests).

    :raises SolverError: when Sphinx reports a warning or an error (its messages are printed)
    """
    from sphinx.cmd.build import build_main

    from springlab.workbench.cache import PACKAGE, digest

    site_dir, work_dir = Path(site_dir), Path(work_dir)
    stems = stage(notebooks_dir, figures_dir, work_dir / "src", api=api)
    # viewcode keeps each module's tags from the build that first read it: after a change to
    # the code, a page could link an anchor the new source page no longer has. The API is read
    # afresh whenever the package changed (a build with the same code reuses everything).
    code = digest(sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts))
    stamp = work_dir / "package.sha256"
    if not stamp.exists() or stamp.read_text() != code:
        shutil.rmtree(work_dir / "doctrees", ignore_errors=True)
        shutil.rmtree(site_dir / "_modules", ignore_errors=True)
    os.environ["SPRINGLAB_BOOK_CHAPTERS"] = ";".join(
        f"{PAPERS[s]['key']}={s}" for s in stems if PAPERS.get(s, {}).get("key"))
    args = ["-b", "html", "-c", str(CONF_DIR), "-d", str(work_dir / "doctrees"), "-W", "--keep-going", "-q",
            "-j", str(jobs or os.cpu_count() or 1), str(work_dir / "src"), str(site_dir)]
    if build_main(args) != 0:
        # a warning is reported only when its page is read: forget the read pages, so the
        # next build reads them again and fails again until the cause is fixed
        shutil.rmtree(work_dir / "doctrees", ignore_errors=True)
        stamp.unlink(missing_ok=True)
        raise SolverError(f"the book did not build: Sphinx's warnings above (sources in {work_dir / 'src'})")
    stamp.write_text(code)
    for stem in stems:  # the download button gives the notebook as papermill executed it (not the staged copy)
        shutil.copyfile(Path(notebooks_dir) / f"{stem}.ipynb", site_dir / "_sources" / f"{stem}.ipynb")
    target = site_dir / "_static" / "mathjax"
    if not (target / MATHJAX_SCRIPT).exists():
        shutil.copytree(mathjax_dir(), target, dirs_exist_ok=True)
    plotly = site_dir / "_static" / view3d.PLOTLY_JS  # the 3-D views load it from there, never from a network
    if not plotly.exists() or plotly.stat().st_size != view3d.plotly_js().stat().st_size:
        shutil.copyfile(view3d.plotly_js(), plotly)
    if api:
        link_source_citations(site_dir, stems)
    return site_dir / "index.html"


_COMMENT = re.compile(r'<span class="c1">([^<]*)</span>')


def link_source_citations(site_dir, stems) -> int:
    """In the module source pages (viewcode), link each :data:`CITATION` in a comment to the
    paper's chapter; returns the number of links made (a page already linked is left as it is)."""
    site_dir = Path(site_dir)
    chapters = {PAPERS[s]["key"]: s for s in stems if PAPERS.get(s, {}).get("key")}
    made = 0
    for page in (site_dir / "_modules").rglob("*.html"):
        up = os.path.relpath(site_dir, page.parent)
        text = page.read_text()

        def cite(match, up=up):
            nonlocal made
            if match.group(1) not in chapters:
                return match.group(0)
            made += 1
            return f'<a href="{up}/{chapters[match.group(1)]}.html">{match.group(1)}</a>'

        new = _COMMENT.sub(lambda m: f'<span class="c1">{CITATION.sub(cite, m.group(1))}</span>', text)
        if new != text:
            page.write_text(new)
    return made
