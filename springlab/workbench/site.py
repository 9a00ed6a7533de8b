"""The reader's side: the executed notebooks as a static site, and the reproduction report.

``python -m springlab.workbench.site`` (run by ``make figures`` after the notebooks):

* renders every executed notebook in ``build/notebooks/`` to ``build/site/<stem>.html``
  (nbconvert's lab template), with MathJax served from the site itself (the
  ``jupyter-server-mathjax`` package) and no script from the internet;
* copies each notebook's figures beside the pages and writes ``build/site/index.html``:
  every paper with its authors, year, title, DOI, a thumbnail of its key figure,
  its run time and its claims counted by status;
* aggregates every ``figures/<stem>/claims.json`` into ``figures/REPRODUCTION.md``.

:func:`check_links` lists what a page points to that is not there (used in tests).
"""

from __future__ import annotations

import argparse
import functools
import html
import json
import re
import shutil
import sys
from collections import Counter
from pathlib import Path

from springlab import tables
from springlab.errors import SolverError
from springlab.papers import PAPERS
from springlab.workbench.cache import Cache, digest, module_closure
from springlab.workbench.claims import REPORT_COLUMNS, markdown_table, report_column

MATHJAX_URL = "mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML-full,Safe"
_EXTERNAL_SCRIPT = re.compile(r'<script[^>]*\ssrc="https?://[^"]*"[^>]*>\s*</script>', re.I)


def load_claims(figures_dir) -> dict[str, list[dict]]:
    """{notebook stem: its claims} from every figures/<stem>/claims.json."""
    out = {}
    for path in sorted(Path(figures_dir).glob("*/claims.json")):
        out[path.parent.name] = json.loads(path.read_text())
    return out


def write_report(figures_dir) -> Path:
    """Aggregate the claims into ``figures/REPRODUCTION.md``: counts per paper and
    status, then every claim."""
    claims = load_claims(figures_dir)
    lines = ["# Reproduction report", "",
             "Every number the notebooks reproduce, beside the paper's (written by `make figures` "
             "from `figures/<notebook>/claims.json`).", "",
             "Statuses: **reproduced** within a stated tolerance; **rounding** within the band the paper's "
             "printed rounding explains; **discrepancy**, its cause found or not; **not reproducible** from "
             "what the paper gives; **input**, a value the notebook fed in (shown, not counted as "
             "reproduced); **consistent** / **inconsistent**, a number recomputed from the paper's own "
             "printed numbers (a check of the paper against itself).", ""]
    counts = []
    for stem, records in claims.items():
        count = Counter(report_column(r) for r in records)
        paper = PAPERS.get(stem, {})
        counts.append([stem, f"{paper.get('authors', '')} ({paper.get('year', '')})",
                       *(count.get(s, 0) for s in REPORT_COLUMNS), len(records)])
    lines.append(tables.markdown_table(["notebook", "paper", *REPORT_COLUMNS, "total"], counts))
    for stem, records in claims.items():
        lines += ["", f"## {stem}", "", markdown_table(records)]
    path = Path(figures_dir) / "REPRODUCTION.md"
    path.write_text("\n".join(lines) + "\n")
    return path


def write_report_page(figures_dir, site_dir) -> Path:
    """The reproduction report as ``site_dir/report.html`` (from REPRODUCTION.md)."""
    import mistune

    text = write_report(figures_dir).read_text()
    body = mistune.create_markdown(plugins=["table"])(text)
    page = Path(site_dir) / "report.html"
    page.write_text('<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>springlab: '
                    "reproduction report</title><style>body{font-family:sans-serif;margin:2em}"
                    "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:.2em .4em;"
                    f'font-size:90%}}</style></head><body><p><a href="index.html">back</a></p>{body}</body></html>\n')
    return page


def _mathjax_dir() -> Path:
    """MathJax's folder in the ``jupyter-server-mathjax`` package, found without importing
    it (its import loads Jupyter Server, 4 s)."""
    import importlib.util

    spec = importlib.util.find_spec("jupyter_server_mathjax")
    if spec is None or not spec.submodule_search_locations:
        raise SolverError("jupyter-server-mathjax is not installed: run `make` to build the environment")
    return Path(list(spec.submodule_search_locations)[0]) / "static"


def render_notebook(executed: Path, site_dir: Path) -> Path:
    """One executed notebook to ``site_dir/<stem>.html``, with local MathJax."""
    from springlab.workbench.notebooks import skip_unused_format_checker

    skip_unused_format_checker()
    import nbformat
    from nbconvert import HTMLExporter

    exporter = HTMLExporter(template_name="lab")
    exporter.mathjax_url = MATHJAX_URL
    body, _ = exporter.from_notebook_node(nbformat.read(executed, as_version=4))
    body = _EXTERNAL_SCRIPT.sub("", body)  # require.js: only interactive widgets need it
    out = site_dir / f"{executed.stem}.html"
    out.write_text(body)
    return out


@functools.cache
def _site_sources() -> tuple[Path, ...]:
    """The files of the modules that build the site (the import graph is read once a process)."""
    return tuple(sorted(module_closure(["springlab.workbench.site"])))


def page_key(executed: Path) -> str:
    """The key of a rendered page: the executed notebook and the modules that render it."""
    return digest([executed, *_site_sources()])


def render_page(executed, site_dir, cache_folder="build/cache") -> Path:
    """:func:`render_notebook`, unless the page was rendered from this executed notebook by
    this code before (its :func:`page_key` under ``cache_folder``): the notebook runner renders
    each page as its notebook finishes, and the site reuses it."""
    executed, site_dir = Path(executed), Path(site_dir)
    key = page_key(executed)
    if _page_fresh(executed, site_dir, cache_folder, key):
        return site_dir / f"{executed.stem}.html"
    site_dir.mkdir(parents=True, exist_ok=True)
    page = render_notebook(executed, site_dir)
    Cache(cache_folder).store(f"page-{executed.stem}", key)
    return page


def _page_fresh(executed: Path, site_dir: Path, cache_folder, key: str | None = None) -> bool:
    """True when ``executed``'s page exists and was rendered from it by this code."""
    key = page_key(executed) if key is None else key
    return Cache(cache_folder).fresh(f"page-{executed.stem}", key, [site_dir / f"{executed.stem}.html"])


def _render_all(executed: list[Path], site_dir: Path, cache_folder) -> list[Path]:
    """:func:`render_page` for each notebook, on every core (nbconvert is pure Python: one
    process per core), the pages in the notebooks' order."""
    import os
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import get_context

    stale = [nb for nb in executed if not _page_fresh(nb, site_dir, cache_folder)]
    workers = min(len(stale), os.cpu_count() or 1)
    if workers > 1:
        # spawned, not forked: page_key has run grimp's threads here, which a fork can deadlock
        with ProcessPoolExecutor(max_workers=workers, mp_context=get_context("spawn")) as pool:
            list(pool.map(render_page, stale, [site_dir] * len(stale), [cache_folder] * len(stale)))
    else:
        for nb in stale:
            render_page(nb, site_dir, cache_folder)
    return [site_dir / f"{nb.stem}.html" for nb in executed]


def _run_time(executed: Path) -> float | None:
    meta = json.loads(executed.read_text()).get("metadata", {}).get("papermill", {})
    return meta.get("duration")


def build_site(notebooks_dir="build/notebooks", site_dir="build/site", figures_dir="figures",
               cache_folder="build/cache") -> Path:
    """Render the executed notebooks (those not rendered already, :func:`render_page`) and
    write the index; returns index.html's path."""
    notebooks_dir, site_dir, figures_dir = Path(notebooks_dir), Path(site_dir), Path(figures_dir)
    site_dir.mkdir(parents=True, exist_ok=True)
    shutil.copytree(_mathjax_dir(), site_dir / "mathjax", dirs_exist_ok=True)
    claims = load_claims(figures_dir)
    rows = []
    executed_notebooks = sorted(notebooks_dir.glob("*.ipynb"))
    for executed, page in zip(executed_notebooks, _render_all(executed_notebooks, site_dir, cache_folder), strict=True):
        stem = executed.stem
        if (figures_dir / stem).is_dir():
            shutil.copytree(figures_dir / stem, site_dir / "figures" / stem, dirs_exist_ok=True)
        paper = PAPERS.get(stem, {"authors": "", "year": "", "title": stem, "venue": "", "doi": None,
                                  "key_figure": None})
        thumb = ""
        if paper.get("key_figure") and (site_dir / "figures" / stem / paper["key_figure"]).exists():
            src = f"figures/{stem}/{paper['key_figure']}"
            thumb = f'<a href="{page.name}"><img src="{src}" alt="key figure of {stem}" width="260"></a>'
        doi = (f'<a href="https://doi.org/{paper["doi"]}">doi:{html.escape(paper["doi"])}</a>'
               if paper.get("doi") else "no DOI given")
        run = _run_time(executed)
        run_text = f"{run:.1f} s" if run is not None else "unknown"
        count = Counter(report_column(r) for r in claims.get(stem, []))
        tally = ", ".join(f"{count[s]} {s}" for s in REPORT_COLUMNS if count.get(s))
        rows.append(
            f"<tr><td>{thumb}</td><td><b>{html.escape(paper['authors'])} ({paper['year']})</b><br>"
            f"<i>{html.escape(paper['title'])}</i><br>{html.escape(paper.get('venue') or '')} {doi}<br>"
            f'<a href="{page.name}">the rendered notebook</a> &middot; run time '
            f"{run_text}<br>claims: {tally or 'none'}</td></tr>")
    report = write_report_page(figures_dir, site_dir)
    index = site_dir / "index.html"
    index.write_text(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>springlab</title>"
        "<style>body{font-family:sans-serif;max-width:60em;margin:2em auto}td{vertical-align:top;padding:.6em}"
        "</style></head><body><h1>springlab: spring gravity balancing, reproduced</h1>"
        "<p>Each paper's derivations, tables and figures, recomputed and checked. "
        f'<a href="{report.name}">The reproduction report</a> lists every claim '
        "(<code>figures/REPRODUCTION.md</code> in the repository).</p>"
        f"<table>{''.join(rows)}</table></body></html>\n")
    return index


_REF = re.compile(r'<(img|script|link|a)\b[^>]*?\s(src|href)="([^"]*)"', re.I)


def check_links(page) -> list[str]:
    """Problems with what an HTML page references: a local file that does not exist,
    or a script, image or stylesheet fetched from the internet. Links (<a>) to other
    sites are allowed; in-page anchors and data: URIs are fine."""
    page = Path(page)
    problems = []
    for tag, _attr, ref in _REF.findall(page.read_text()):
        if not ref or ref.startswith(("#", "data:", "mailto:")):
            if not ref:
                problems.append(f"<{tag}> with an empty reference")
            continue
        if re.match(r"https?://", ref):
            if tag.lower() != "a":
                problems.append(f"<{tag}> fetches {ref} from the internet")
            continue
        target = (page.parent / ref.split("?")[0].split("#")[0]).resolve()
        if not target.exists():
            problems.append(f"<{tag}> points to a missing file: {ref}")
    return problems


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--notebooks", default="build/notebooks")
    parser.add_argument("--site", default="build/site")
    parser.add_argument("--figures", default="figures")
    parser.add_argument("--no-cache", action="store_true", help="rebuild even if nothing changed")
    parser.add_argument("--cache", default="build/cache", help="folder for the key of the last build")
    args = parser.parse_args(argv)
    report = Path(args.figures) / "REPRODUCTION.md"
    key, cache = _site_key(args), Cache(args.cache)
    if not args.no_cache and cache.fresh("site", key, [report, Path(args.site) / "index.html"]):
        print(f"unchanged: report {report}; site {Path(args.site) / 'index.html'}")
        return 0
    cache.forget("site")
    index = build_site(args.notebooks, args.site, args.figures, args.cache)
    problems = [f"{p.name}: {issue}" for p in sorted(Path(args.site).glob("*.html")) for issue in check_links(p)]
    for line in problems:
        print(line, file=sys.stderr)
    print(f"report: {report}; site: {index}")
    if problems:
        return 1
    cache.store("site", key)
    return 0


def _site_key(args) -> str:
    """The site's inputs: the executed notebooks, the figures and claims (not the report it
    writes), the modules that build it, and where it goes."""
    inputs = [p for p in Path(args.notebooks).glob("*.ipynb")]
    inputs += [p for p in Path(args.figures).rglob("*") if p.is_file() and p.name != "REPRODUCTION.md"]
    inputs += _site_sources()
    return digest(inputs, {"site": str(Path(args.site).resolve()), "figures": str(Path(args.figures).resolve())})


if __name__ == "__main__":
    sys.exit(main())


def find_browser() -> tuple[str, str] | None:
    """(chromium, chromedriver) paths from Debian's packages, or None when absent."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver = shutil.which("chromedriver")
    return (chromium, driver) if chromium and driver else None


def browser_check(pages, *, screenshot=None, math_timeout: float = 10.0) -> dict[str, list[str]]:
    """Open each page in headless Chromium and list what a reader would see broken:
    an image that did not load, a link to a missing local file, a traceback in an
    output, or TeX left unrendered on a page that has math. Saves a screenshot of
    the first page to ``screenshot`` if given. Returns {page name: problems}.

    :raises SolverError: when Chromium and its driver are not installed
    """
    import time

    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    found = find_browser()
    if found is None:
        raise SolverError("headless Chromium is not installed: apt-get install chromium chromium-driver")
    options = Options()
    options.binary_location = found[0]
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--no-first-run", "--window-size=1200,1600", "--allow-file-access-from-files"):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(found[1]), options=options)
    out = {}
    try:
        for k, page in enumerate(Path(p).resolve() for p in pages):
            driver.get(page.as_uri())
            problems = list(check_links(page))
            for src in driver.execute_script(
                    "return Array.from(document.images).filter(i => !i.complete || i.naturalWidth === 0)"
                    ".map(i => i.getAttribute('src').slice(0, 120))"):
                problems.append(f"image did not load: {src}")
            text = driver.execute_script("return document.body.innerText")
            if "Traceback (most recent call last)" in text:
                problems.append("an output shows a traceback")
            if "MathJax.js" in page.read_text():
                deadline = time.time() + math_timeout
                rendered = 0
                while time.time() < deadline:
                    rendered = driver.execute_script(
                        "return document.querySelectorAll('.MathJax, .MathJax_Display, .MathJax_SVG, "
                        ".MathJax_CHTML, mjx-container').length")
                    if rendered:
                        break
                    time.sleep(0.2)
                if not rendered:
                    problems.append("no equation was rendered by MathJax")
            if k == 0 and screenshot is not None:
                Path(screenshot).parent.mkdir(parents=True, exist_ok=True)
                driver.save_screenshot(str(screenshot))
            out[page.name] = problems
    finally:
        driver.quit()
    return out


def executed_errors(notebook) -> list[str]:
    """The error outputs of an executed notebook (cell index and error name)."""
    nb = json.loads(Path(notebook).read_text())
    return [f"cell {i}: {o.get('ename')}: {o.get('evalue')}" for i, cell in enumerate(nb.get("cells", []))
            for o in cell.get("outputs", []) if o.get("output_type") == "error"]
