"""The reader's side: the reproduction report and the book, and the checks a reader's browser makes.

``python -m springlab.workbench.site`` (run by ``make figures`` after the notebooks):

* aggregates every ``figures/<stem>/claims.json`` into ``figures/REPRODUCTION.md``;
* builds the book into ``build/site`` (:mod:`springlab.workbench.book`: Sphinx, myst-nb and
  sphinx-book-theme), unless nothing it is built from changed.

:func:`check_links` lists what a page points to that is not there; :func:`browser_check`
opens pages in headless Chromium and lists what a reader would see broken, including any
request that leaves the machine (used in tests).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import sys
from collections import Counter
from pathlib import Path

from springlab import tables
from springlab.errors import SolverError
from springlab.papers import PAPERS
from springlab.workbench.book import PAGES, load_claims
from springlab.workbench.cache import PACKAGE, Cache, digest
from springlab.workbench.claims import MEANINGS, REPORT_COLUMNS, markdown_table, report_column


def write_report(figures_dir) -> Path:
    """Aggregate the claims into ``figures/REPRODUCTION.md``: counts per paper and
    status, then every claim."""
    claims = load_claims(figures_dir)
    lines = ["# Reproduction report", "",
             "Every number the notebooks reproduce, beside the paper's (written by `make figures` "
             "from `figures/<notebook>/claims.json`).", "",
             "Statuses: " + "; ".join(f"**{s}**: {MEANINGS[s]}" for s in REPORT_COLUMNS) + ".", ""]
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


def build_site(notebooks_dir="build/notebooks", site_dir="build/site", figures_dir="figures",
               work_dir="build/book") -> Path:
    """The reproduction report (``figures/REPRODUCTION.md``) and the book
    (:func:`springlab.workbench.book.build_book`); returns the book's index.html."""
    from springlab.workbench.book import build_book

    write_report(figures_dir)
    return build_book(notebooks_dir, figures_dir, site_dir, work_dir)


_REF = re.compile(r'<(img|script|link|a)\b[^>]*?\s(src|href)="([^"]*)"', re.I)


def check_links(page) -> list[str]:
    """Problems with what an HTML page references: a local file that does not exist (a link
    to a folder counts as missing unless the folder holds an index.html: a download that
    points to a folder downloads nothing), an in-page or cross-page anchor (``#id``) that no
    element carries, or a script, image or stylesheet fetched from the internet. Links (<a>)
    to other sites are allowed; data: URIs are fine."""
    page = Path(page)
    text = page.read_text()
    problems = []
    for tag, _attr, ref in _REF.findall(text):
        if not ref or ref.startswith(("data:", "mailto:")):
            if not ref:
                problems.append(f"<{tag}> with an empty reference")
            continue
        if re.match(r"https?://", ref):
            if tag.lower() != "a":
                problems.append(f"<{tag}> fetches {ref} from the internet")
            continue
        path, _, fragment = ref.split("?")[0].partition("#")
        if path.startswith("file://"):
            from urllib.parse import unquote, urlparse

            target = Path(unquote(urlparse(path).path))
        else:
            target = (page.parent / path).resolve() if path else page.resolve()
        if target.is_dir() and not (target / "index.html").is_file():
            problems.append(f"<{tag}> points to a folder, not a file: {ref}")
        elif not target.exists():
            problems.append(f"<{tag}> points to a missing file: {ref}")
        elif fragment and target.suffix == ".html" and not _has_id(target, fragment):
            problems.append(f"<{tag}> points to an anchor that is not there: {ref}")
    return problems


_IDS: dict[tuple[Path, float], set[str]] = {}


def _has_id(page: Path, fragment: str) -> bool:
    from urllib.parse import unquote

    key = (page, page.stat().st_mtime)
    if key not in _IDS:
        _IDS[key] = set(re.findall(r'\sid="([^"]+)"', page.read_text()))
    return unquote(fragment) in _IDS[key]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--notebooks", default="build/notebooks")
    parser.add_argument("--site", default="build/site")
    parser.add_argument("--figures", default="figures")
    parser.add_argument("--no-cache", action="store_true", help="rebuild even if nothing changed")
    parser.add_argument("--cache", default="build/cache", help="folder for the key of the last build")
    parser.add_argument("--work", default="build/book", help="folder for the book's sources and Sphinx's state")
    args = parser.parse_args(argv)
    report = Path(args.figures) / "REPRODUCTION.md"
    key, cache = _site_key(args), Cache(args.cache)
    if not args.no_cache and cache.fresh("site", key, [report, Path(args.site) / "index.html"]):
        print(f"unchanged: report {report}; site {Path(args.site) / 'index.html'}")
        return 0
    cache.forget("site")
    try:
        index = build_site(args.notebooks, args.site, args.figures, args.work)
    except SolverError as err:
        print(err, file=sys.stderr)
        return 1
    site = Path(args.site)
    pages = [p for p in sorted(site.rglob("*.html")) if p.relative_to(site).parts[0] != "_static"]  # not templates
    problems = [f"{p.relative_to(site)}: {issue}" for p in pages for issue in check_links(p)]
    for line in problems:
        print(line, file=sys.stderr)
    print(f"report: {report}; site: {index}")
    if problems:
        return 1
    cache.store("site", key)
    return 0


def _site_key(args) -> str:
    """The site's inputs: the executed notebooks, the figures and claims (not the report it
    writes), the pages written beside them (the guide, the glossary, the benchmarks' results), every
    file of the package (the book documents all of it) and where it goes."""
    inputs = [p for p in Path(args.notebooks).glob("*.ipynb")]
    inputs += [p for p in PAGES.values() if p.exists()]
    inputs += [p for p in Path(args.figures).rglob("*") if p.is_file() and p.name != "REPRODUCTION.md"]
    inputs += sorted(p for p in PACKAGE.rglob("*") if p.is_file() and "__pycache__" not in p.parts)
    return digest(inputs, {"site": str(Path(args.site).resolve()), "figures": str(Path(args.figures).resolve()),
                           "work": str(Path(args.work).resolve())})


if __name__ == "__main__":
    sys.exit(main())


def find_browser() -> tuple[str, str] | None:
    """(chromium, chromedriver) paths from Debian's packages, or None when absent."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver = shutil.which("chromedriver")
    return (chromium, driver) if chromium and driver else None


LOCAL_SCHEMES = ("file:", "data:", "blob:", "about:", "chrome:", "chrome-extension:", "devtools:")
"""The requests a page may make: none of them leaves the machine."""

_MATH_DONE = r"""
if (!window.MathJax) return true;
if (!MathJax.startup || !MathJax.startup.promise) return false;
if (window.__springlabMath === undefined) {
    window.__springlabMath = false;
    MathJax.startup.promise.then(() => { window.__springlabMath = true; });
}
return window.__springlabMath;
"""
_MATH_LEFT = r"""
const doc = window.MathJax && MathJax.startup && MathJax.startup.document;
const sources = doc ? Array.from(doc.math).map(m => m.math) : [];
return {math: document.querySelectorAll('span.math, div.math').length,
        rendered: document.querySelectorAll('mjx-container').length,
        raw: Array.from(document.querySelectorAll('span.math, div.math'))
                  .filter(e => !e.querySelector('mjx-container') && /\\\(|\\\[|\$\$/.test(e.textContent)).length,
        errors: document.querySelectorAll('mjx-merror, [data-mjx-error]').length,
        doubled: sources.filter(t => /\\\\[A-Za-z]/.test(t)).map(t => t.slice(0, 60))};
"""


_READER = r"""
const article = document.querySelector('article.bd-article') || document.body;
const column = article.clientWidth;
const pipes = Array.from(article.querySelectorAll('p, li'))
    .filter(e => /\|\s*:?-{3,}:?\s*\|/.test(e.textContent)).map(e => e.textContent.slice(0, 80));
const leaks = [];
const walker = document.createTreeWalker(article, NodeFilter.SHOW_TEXT);
const tex = /\\[A-Za-z]{2,}|\\[()[\]]|\$\$|\$[^$\s][^$\n]*\$/;
while (walker.nextNode()) {
    const node = walker.currentNode, el = node.parentElement;
    if (!el || el.closest('mjx-container, script, style, code, .cell_input, .highlight, .doctest, dl.py'))
        continue;
    if (el.closest('pre') && !el.closest('.cell_output')) continue;
    const m = node.textContent.match(tex);
    if (m) leaks.push(node.textContent.slice(Math.max(0, m.index - 20), m.index + 40).trim());
}
const wide = [];
for (const el of article.querySelectorAll('.cell_output > *, mjx-container[display="true"]')) {
    const width = Math.max(el.scrollWidth, ...Array.from(el.querySelectorAll('pre, table, svg'))
                                                  .map(e => Math.max(e.scrollWidth, e.getBoundingClientRect().width)));
    if (width > 2 * column) wide.push([Math.round(width), el.textContent.trim().slice(0, 60)]);
}
const numbered = Array.from(article.querySelectorAll('mjx-container [data-mml-node="mlabeledtr"]')).length;
const uncaptioned = Array.from(article.querySelectorAll('img')).filter(img => {
    const caption = img.closest('figure') && img.closest('figure').querySelector('figcaption');
    return !(caption && /^\s*Figure \d+\. \S/.test(caption.textContent));
}).map(img => (img.getAttribute('alt') || img.getAttribute('src') || '').slice(0, 80));
const covered = Array.from(article.querySelectorAll('table.coverage tr[data-item]')).map(tr => tr.dataset.item);
const undrawn = Array.from(article.querySelectorAll('.springlab-view3d')).filter(
    v => !(v.classList.contains('js-plotly-plot') && v.querySelector('canvas'))).map(v => v.getAttribute('aria-label') || v.id);
const mj = window.MathJax && MathJax.startup && MathJax.startup.document;
const texts = new Map(mj ? Array.from(mj.math).map(m => [m.typesetRoot, m.math]) : []);
const cut = Array.from(article.querySelectorAll('mjx-container[display="true"]')).filter(
    c => c.querySelector('[data-mml-node="mlabeledtr"]') && c.scrollWidth > c.parentElement.clientWidth + 1).map(
    c => [c.scrollWidth, c.parentElement.clientWidth, (texts.get(c) || '').trim().slice(0, 60)]);
const sideways = Array.from(article.querySelectorAll('pre')).filter(p => !p.closest('.cell_output')).filter(
    p => p.scrollWidth > p.clientWidth + 1).map(p => p.textContent.trim().split('\n')[0].slice(0, 60));
const narrow = Array.from(article.querySelectorAll('.cell_input pre')).filter(p => p.clientWidth > 0).filter(p => {
    const probe = document.createElement('span');  // a line of the width the chapters are formatted to
    probe.textContent = 'x'.repeat(CODE_COLUMN);
    probe.style.whiteSpace = 'pre';
    p.appendChild(probe);
    const need = probe.getBoundingClientRect().width;
    probe.remove();
    const style = getComputedStyle(p);
    return need > p.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight) + 0.5;
}).map(p => p.textContent.trim().split('\n')[0].slice(0, 60));
const internal = [];
const name = /^(?:[A-Za-z_]\w*\.)*[a-z_][a-z0-9]*_[a-z0-9_]*(?:\(\))?$|^(?:[a-z_]\w*\.)+[A-Za-z_]\w*(?:\(\))?$|^[\w.-]+\/[\w.\/-]*\.\w+$|^[\w-]+\.(?:toml|json|py|urdf|csv|ipynb|md)$/;
for (const el of article.querySelectorAll('p, li, figcaption')) {
    if (el.closest('.admonition, .cell_input, .cell_output, table, details.coverage, dl.py, .doctest')) continue;
    for (const c of el.querySelectorAll('code')) if (name.test(c.textContent.trim())) internal.push(c.textContent.trim());
    const text = el.textContent;
    const key = text.match(/(?<![\w.,\/-])00[0-4](?![\w,]|\.\d)/), issue = text.match(/\bissues?\b/i);
    if (key) internal.push(text.slice(Math.max(0, key.index - 30), key.index + 20).trim());
    if (issue) internal.push(text.slice(Math.max(0, issue.index - 30), issue.index + 20).trim());
}
return {column, pipes, leaks, wide, numbered, uncaptioned, covered, undrawn, cut, sideways, narrow, internal};
"""

CODE_COLUMN = 88
"""Characters a line of a chapter's code may hold (notebooks/ruff.toml's line length): the browser check
fails on a code cell too narrow to show them without wrapping."""


DESKTOP = (1280, 1000)
"""px: the window the browser check reads each page in first, as a reader at a desk does."""


def _driver(found):
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    options = Options()
    options.binary_location = found[0]
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--no-first-run", f"--window-size={DESKTOP[0]},{DESKTOP[1]}", "--allow-file-access-from-files"):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"performance": "ALL"})  # the network log
    return webdriver.Chrome(service=Service(found[1]), options=options)


def _requests(driver) -> tuple[list[str], list[str]]:
    """The URLs requested since the last call, and those that failed to load (Chromium's
    performance log)."""
    urls, ids, failed = [], {}, []
    for entry in driver.get_log("performance"):
        message = json.loads(entry["message"])["message"]
        params = message.get("params", {})
        if message.get("method") == "Network.requestWillBeSent":
            urls.append(params["request"]["url"])
            ids[params["requestId"]] = params["request"]["url"]
        elif (message.get("method") == "Network.loadingFailed" and not params.get("canceled")
              and not ids.get(params.get("requestId"), "").startswith("about:")):  # MathJax's blank frame
            failed.append(f"{ids.get(params.get('requestId'), '?')} ({params.get('errorText', '')})")
    return urls, failed


def _network_problems(driver, page: str, log: list) -> list[str]:
    """The requests since the last call, appended to ``log`` under ``page``; the problems: any
    request that left the machine, any resource that did not load."""
    urls, failed = _requests(driver)
    log += [f"{page}\t{url}" for url in urls]
    return ([f"request left the machine: {url[:160]}" for url in urls if not url.startswith(LOCAL_SCHEMES)]
            + [f"did not load: {what[:200]}" for what in failed])


def _wait(driver, script: str, timeout: float):
    import time

    deadline = time.time() + timeout
    while True:
        value = driver.execute_script(script)
        if value or time.time() > deadline:
            return value
        time.sleep(0.1)


PHONE = (390, 844)
"""px: the phone the browser check also reads each page on (an iPhone 12's viewport), after :data:`DESKTOP`."""

_PHONE = """
const de = document.documentElement, W = de.clientWidth;
const free = e => {  // not inside a box that scrolls (or clips) on its own
    for (let p = e.parentElement; p && p !== document.body; p = p.parentElement)
        if (getComputedStyle(p).overflowX !== 'visible') return false;
    return true;
};
const wide = [];
for (const e of document.querySelectorAll('article *')) {
    const r = e.getBoundingClientRect();
    const spills = e.clientWidth > 0 && e.scrollWidth > e.clientWidth + 1 && getComputedStyle(e).overflowX === 'visible';
    if (r.width > 0 && (r.right > W + 1 || spills) && free(e)) wide.push(e);
}
const named = wide.filter(e => !wide.some(o => o !== e && e.contains(o)))  // the innermost: what is too wide
    .map(e => e.tagName.toLowerCase() + ': ' + (e.textContent || '').trim().replace(/\\s+/g, ' ').slice(0, 60));
return {over: de.scrollWidth - W, wide: named.slice(0, 3)};
"""


def browser_check(pages, *, screenshots=None, network_log=None, chapters=None, search=None, numbered=(),
                  captioned=(), covered=None, prose=(), math_timeout: float = 30.0) -> dict[str, list[str]]:
    """Open each page in headless Chromium and list what a reader would see broken: an image
    that did not load, a link to a missing local file, folder or anchor (:func:`check_links`:
    a download included), a traceback in an output, TeX that MathJax left unrendered or could
    not parse, TeX with a doubled backslash (``\\\\tfrac``), a paragraph that is a raw Markdown
    table (pipes and ``---``), TeX shown as text outside the math (``\\frac``, ``$...$``, in
    prose and in outputs), an output (or a display equation) more than twice as wide as the
    text column, a code cell that scrolls sideways or holds fewer than :data:`CODE_COLUMN`
    characters, a numbered display equation wider than its column (its tag out of sight), a 3-D view
    (:mod:`springlab.workbench.view3d`) that did not draw, a page that scrolls sideways on a phone
    (:data:`PHONE`: the page's own text wider than the screen; a table or display scrolls in its own box),
    and any request that leaves the machine (Chromium's network log: every request must be ``file://`` or inline).

    :param screenshots: {page: png path}: screenshots to save (the page as a reader first sees it)
    :param network_log: a file to write every request to, page by page
    :param chapters: the page names (``lenzo2017_two_spring_arm.html``) the first page's
        sidebar must link; a missing one is a problem of the first page
    :param search: (term, page name): searching the book for ``term`` must list that page
        (reported under "search")
    :param numbered: page names (``zhang2023_dyad.html``) that must show a numbered display
        equation (a ``\\tag``: a paper's own equation number)
    :param captioned: page names whose every image (a figure, an animation) must stand in a figure
        with a numbered caption ("Figure 3. ...")
    :param prose: page names whose prose (paragraphs, list items, captions; not code, outputs, tables or
        the boxes that say how to run a chapter) must name no function, module, variable or file, no
        paper by its key and no "issue": words for readers
    :param covered: {page name: the paper's items}: the page's coverage table
        (:mod:`springlab.workbench.coverage`) must list each of them
    :returns: {page: problems}, each page named by its path from the first page's folder
    :raises SolverError: when Chromium and its driver are not installed
    """
    found = find_browser()
    if found is None:
        raise SolverError("headless Chromium is not installed: apt-get install chromium chromium-driver")
    pages = [Path(p).resolve() for p in pages]
    shots = {Path(k).resolve(): Path(v) for k, v in (screenshots or {}).items()}
    driver = _driver(found)
    out, log = {}, []
    try:
        for k, page in enumerate(pages):
            driver.get(page.as_uri())
            _wait(driver, "return document.readyState === 'complete'", 10)
            problems = list(check_links(page))
            for src in driver.execute_script(
                    "return Array.from(document.images).filter(i => !i.complete || i.naturalWidth === 0)"
                    ".map(i => i.getAttribute('src').slice(0, 120))"):
                problems.append(f"image did not load: {src}")
            outputs = driver.execute_script(  # the page's text but its doctests (which may show an error)
                "const body = document.body.cloneNode(true);"
                "body.querySelectorAll('.doctest').forEach(e => e.remove());"
                "return body.textContent")
            if "Traceback (most recent call last)" in outputs:
                problems.append("an output shows a traceback")
            if not _wait(driver, _MATH_DONE, math_timeout):
                problems.append(f"MathJax did not finish within {math_timeout:g} s")
            math = driver.execute_script(_MATH_LEFT)
            if math["math"] and not math["rendered"]:
                problems.append(f"no equation was rendered by MathJax ({math['math']} on the page)")
            if math["raw"]:
                problems.append(f"{math['raw']} equation(s) left as raw TeX")
            if math["errors"]:
                problems.append(f"{math['errors']} equation(s) MathJax could not parse")
            problems += [f"TeX with a doubled backslash (a command read as a line break): {t}" for t in math["doubled"]]
            _wait(driver, "return Array.from(document.querySelectorAll('.springlab-view3d'))"
                          ".every(v => v.querySelector('canvas') || v.dataset.failed)", 20)  # drawn once plotly.js loads
            reader = driver.execute_script(_READER.replace("CODE_COLUMN", str(CODE_COLUMN)))
            problems += [f"a raw Markdown table in a paragraph: {t}" for t in reader["pipes"]]
            problems += [f"TeX left as text: {t}" for t in reader["leaks"]]
            problems += [f"an output {w} px wide in a {reader['column']} px column: {t}" for w, t in reader["wide"]]
            if page.name in numbered and not reader["numbered"]:
                problems.append("no numbered equation (a display equation with the paper's number, \\tag{...})")
            if page.name in captioned:
                problems += [f"a figure with no numbered caption: {t}" for t in reader["uncaptioned"]]
            problems += [f"a 3-D view that did not draw: {v}" for v in reader["undrawn"]]
            problems += [f"a code cell that scrolls sideways: {t}" for t in reader["sideways"]]
            problems += [f"a code cell narrower than the {CODE_COLUMN} characters code is formatted to: {t}"
                         for t in reader["narrow"]]
            if page.name in prose:
                problems += [f"an internal name in the prose: {t}" for t in reader["internal"]]
            problems += [f"an equation tag outside the column (a numbered display {w} px wide in {c} px): {t}"
                         for w, c, t in reader["cut"]]
            if page.name in (covered or {}):
                listed = set(reader["covered"])
                problems += ([f"a paper item missing from the coverage table: {i}" for i in covered[page.name]
                              if i not in listed] if listed else ["no coverage table of the paper's items"])
            if k == 0 and chapters:
                linked = {Path(h.split("#")[0]).name for h in driver.execute_script(
                    "return Array.from(document.querySelectorAll('nav.bd-docs-nav a')).map(a => a.href)")}
                problems += [f"the sidebar does not link {name}" for name in chapters if name not in linked]
            if page in shots:
                shots[page].parent.mkdir(parents=True, exist_ok=True)
                driver.save_screenshot(str(shots[page]))
            driver.set_window_size(*PHONE)  # the same page on a phone
            phone = driver.execute_script(_PHONE)
            driver.set_window_size(*DESKTOP)
            if phone["over"] > 1:
                problems.append(f"the page scrolls sideways on a phone ({PHONE[0]} px wide) by {phone['over']} px: "
                                + "; ".join(phone["wide"]))
            problems += _network_problems(driver, page.name, log)
            out[os.path.relpath(page, pages[0].parent)] = problems
        if search is not None:
            term, expected = search
            results = pages[0].parent / "search.html"
            driver.get(f"{results.as_uri()}?q={term}")
            # Sphinx titles the results "Search Results" once it has listed them all
            listed = _wait(driver, "const t = document.querySelector('#search-results h2');"
                                   "if (!t || !t.innerText.startsWith('Search Results')) return null;"
                                   "return {links: Array.from(document.querySelectorAll('#search-results ul.search li a'))"
                                   ".map(a => a.href)}", 20)  # an object: an empty list is an answer too
            listed = listed["links"] if listed else []
            names = {Path(h.split("?")[0].split("#")[0]).name for h in listed}
            out["search"] = ([] if expected in names else [f"searching {term!r} does not list {expected} "
                                                            f"(listed: {sorted(names)})"])
            out["search"] += _network_problems(driver, f"search.html?q={term}", log)
    finally:
        driver.quit()
    if network_log is not None:
        Path(network_log).parent.mkdir(parents=True, exist_ok=True)
        Path(network_log).write_text("\n".join(log) + "\n")
    return out


def executed_errors(notebook) -> list[str]:
    """The error outputs of an executed notebook (cell index and error name)."""
    nb = json.loads(Path(notebook).read_text())
    return [f"cell {i}: {o.get('ename')}: {o.get('evalue')}" for i, cell in enumerate(nb.get("cells", []))
            for o in cell.get("outputs", []) if o.get("output_type") == "error"]
