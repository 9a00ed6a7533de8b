"""The book (build/site): built by Sphinx from executed notebooks, every claim linked to its
section, citations linked to chapters, and the browser check: headless Chromium (Debian's
chromium and chromium-driver) opens every page as a reader would (1280 px wide), searches, reads
the sidebar and records the network log. `.ci/run` installs Chromium and sets
SPRINGLAB_REQUIRE_BROWSER=1, so CI always runs the browser tests; elsewhere they are skipped
when Chromium is not installed.

The book here is the whole book, built (with the API reference and -W, as `make figures` builds
it) from every notebook's quick run, the runs the notebook tests check (tests/quickruns.py). Its
screenshots (every chapter) and network log stay under build/book-check/ for the reader of the
CI log."""

import json
import os
import re
import shutil
from pathlib import Path

import pytest
from quickruns import FIGURES, once, quick_run
from quickruns import OUT as RUNS
from quickruns import STEMS as ALL_STEMS

from springlab.errors import SolverError
from springlab.papers import PAPERS
from springlab.workbench import book, coverage, prose, site, view3d

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build" / "book-check"
STEMS = ("lenzo2017_two_spring_arm", "zhang2023_dyad")  # the chapters the tests below read closely
REQUIRED = os.environ.get("SPRINGLAB_REQUIRE_BROWSER") == "1"
needs_browser = pytest.mark.skipif(site.find_browser() is None and not REQUIRED,
                                   reason="headless Chromium not installed (apt-get install chromium chromium-driver)")


@pytest.fixture(scope="module")
def built():
    """build/book-check/site: the book of every notebook's quick run, with the API reference,
    built once per test run: the first worker to get here builds it, under a lock, and the
    others (pytest-xdist) read it (tests/quickruns.py's ``once``)."""

    def make():
        shutil.rmtree(OUT, ignore_errors=True)
        for stem in reversed(ALL_STEMS):  # the notebook tests run them first to last: meet in the middle
            assert site.executed_errors(quick_run(stem)) == []
        notebooks = OUT / "notebooks"
        notebooks.mkdir(parents=True)
        for stem in ALL_STEMS:
            shutil.copyfile(RUNS / f"{stem}.ipynb", notebooks / f"{stem}.ipynb")
        site.build_site(notebooks, OUT / "site", FIGURES, OUT / "work")

    once(OUT.parent, "book-check", make)
    return OUT / "site"


def test_every_page_resolves_and_fetches_nothing_from_the_internet(built):
    pages = [p for p in built.rglob("*.html") if p.relative_to(built).parts[0] != "_static"]
    assert len(pages) > 20  # chapters, report, API pages, module sources, search, index
    assert {p: site.check_links(p) for p in pages if site.check_links(p)} == {}
    assert (built / "_static" / "mathjax" / book.MATHJAX_SCRIPT).exists()  # MathJax served by the site
    assert (built / "_static" / view3d.PLOTLY_JS).exists()  # and plotly.js, which draws the 3-D views


def test_the_front_page_gives_dois_run_times_and_claims_by_status(built):
    text = (built / "index.html").read_text()
    assert "10.1016/j.mechmachtheory.2023.105497" in text  # 000 prints its DOI
    assert "no DOI (the text prints none" in text  # 002 and 004 print none
    assert "http://shura.shu.ac.uk/16806/" in text  # 004's archive, as its text gives it
    for stem in STEMS:
        run = json.loads((OUT / "notebooks" / f"{stem}.ipynb").read_text())["metadata"]["papermill"]["duration"]
        assert f"run time {run:.1f} s" in text
    assert re.search(r"claims: \d+ reproduced", text)


def test_every_claim_in_the_report_links_to_the_section_that_makes_it(built):
    report = (built / "report.html").read_text()
    for stem in STEMS:
        claims = json.loads((FIGURES / stem / "claims.json").read_text())
        assert all(isinstance(c["cell"], int) for c in claims)  # each recorded in a cell
        links = re.findall(rf'href="{stem}\.html#({stem.replace("_", "-")}-s\d+)"', report)
        assert len(links) == len(claims)
        chapter = (built / f"{stem}.html").read_text()
        assert all(f'id="{anchor}"' in chapter for anchor in set(links))
        # and the section is the one whose cell made it: the cell's heading is the linked section
        executed = json.loads((OUT / "notebooks" / f"{stem}.ipynb").read_text())
        _titles, where = book.sections(executed)
        first = claims[0]
        assert links[0] == book.section_label(stem, where[first["cell"]]).replace("_", "-")


def test_paper_citations_in_docstrings_and_comments_link_to_the_chapter(built):
    dyad = (built / "api" / "springlab.mechanisms.dyad.html").read_text()
    assert 'href="../zhang2023_dyad.html"' in dyad  # "002 Eq. (...)" in a docstring
    source = (built / "_modules" / "springlab" / "mechanisms" / "dyad" / "synthesis.html").read_text()
    assert re.search(r'<span class="c1">[^<]*<a href="(\.\./)+zhang2023_dyad\.html">002</a> Eq', source)


def test_a_broken_cross_reference_fails_the_build(tmp_path):
    notebooks = tmp_path / "nb"
    notebooks.mkdir()
    cell = {"cell_type": "markdown", "metadata": {}, "source": "# A page\n\nSee {ref}`no-such-section`."}
    metadata = {"kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"},
                "language_info": {"name": "python"}}
    nb = {"cells": [cell], "metadata": metadata, "nbformat": 4, "nbformat_minor": 5}
    (notebooks / "lenzo2017_two_spring_arm.ipynb").write_text(json.dumps(nb))
    with pytest.raises(SolverError, match="did not build"):
        book.build_book(notebooks, tmp_path / "figures", tmp_path / "site", tmp_path / "work", api=False)
    cell["source"] = "# A page\n\nNo reference."  # the control: the same book builds once fixed
    (notebooks / "lenzo2017_two_spring_arm.ipynb").write_text(json.dumps(nb))
    assert book.build_book(notebooks, tmp_path / "figures", tmp_path / "site", tmp_path / "work",
                           api=False).exists()


def _term_in_one_page_only(built: Path, stem: str) -> str:
    """A word Sphinx's index holds for ``stem``'s page and no other page (its own stem)."""
    import snowballstemmer

    text = (built / "searchindex.js").read_text()
    index = json.loads(text[text.index("(") + 1: text.rindex(")")])
    doc = index["docnames"].index(stem)
    stem_word = snowballstemmer.stemmer("porter").stemWord
    only = sorted(t for t, docs in index["terms"].items()
                  if docs == doc and t.isalpha() and len(t) >= 6 and stem_word(t) == t)
    assert only, f"no word of {stem} is on its page only"
    return only[0]


@needs_browser
def test_the_book_reads_in_chromium_offline(built):
    # every page but the module sources, of which one (they are all made alike), and search.html
    # (opened by the search below)
    pages = [built / "index.html", *(p for p in sorted(built.rglob("*.html"))
                                     if p.relative_to(built).parts[0] not in ("_static", "_modules")
                                     and p.name not in ("index.html", "search.html")),
             built / "api" / "index.html",
             built / "_modules" / "springlab" / "mechanisms" / "dyad" / "synthesis.html"]
    assert len(pages) >= 17
    shots = OUT / "screenshots"
    chapters = [built / f"{stem}.html" for stem in ALL_STEMS]
    term = _term_in_one_page_only(built, "zhang2023_dyad")
    result = site.browser_check(
        pages, network_log=OUT / "network.log",
        screenshots={built / "index.html": shots / "front-page.png", built / "report.html": shots / "report.png",
                     **{page: shots / f"{page.stem}.png" for page in chapters}},
        chapters=[p.name for p in chapters] + ["report.html", "index.html"], search=(term, "zhang2023_dyad.html"),
        numbered=[f"{stem}.html" for stem in ALL_STEMS if PAPERS.get(stem, {}).get("key")],
        captioned=[f"{stem}.html" for stem in ALL_STEMS],
        covered={f"{stem}.html": [i.item for i in coverage.inventory(PAPERS[stem]["key"])]
                 for stem in ALL_STEMS if PAPERS.get(stem, {}).get("key")},
        prose=[f"{stem}.html" for stem in ALL_STEMS])
    assert result == {**{str(p.relative_to(built)): [] for p in pages}, "search": []}, term
    log = (OUT / "network.log").read_text().splitlines()
    assert any(f"_static/mathjax/{book.MATHJAX_SCRIPT}" in line for line in log)  # the log holds every request
    assert all(line.split("\t")[1].startswith(site.LOCAL_SCHEMES) for line in log)
    assert all((shots / f"{name}.png").stat().st_size > 20_000 for name in [*ALL_STEMS, "front-page", "report"])


@needs_browser
def test_the_browser_check_catches_a_broken_page(tmp_path, built):
    (tmp_path / "ok.png").write_bytes((ROOT / "figures" / "lenzo2017_two_spring_arm" / "fig5_layouts.png").read_bytes())
    page = tmp_path / "broken.html"
    page.write_text('<html><body><img src="ok.png"><img src="missing.png"><a href="gone.html">gone</a>'
                    '<img src="http://example.invalid/pixel.png">'
                    "<pre>Traceback (most recent call last):\n  boom</pre></body></html>")
    problems = site.browser_check([page])[page.name]
    assert any("missing.png" in p and "did not load" in p for p in problems)
    assert any("gone.html" in p for p in problems)
    assert any("traceback" in p for p in problems)
    assert any("left the machine" in p and "example.invalid" in p for p in problems)
    assert not any("ok.png" in p for p in problems)
    # a search that lists nothing is caught too
    found = site.browser_check([built / "index.html"], search=("zzqqxxnotaword", "zhang2023_dyad.html"))
    assert found["search"] and "does not list" in found["search"][0]


@needs_browser
def test_the_browser_check_catches_what_a_reader_would_see_broken(tmp_path, built):
    """Each defect the full book once had, on a page of its own kind: the check must name it;
    the same page without the defects (the control) passes."""
    mathjax = (built / "_static" / "mathjax" / book.MATHJAX_SCRIPT).as_uri()
    (tmp_path / "_sources").mkdir()
    (tmp_path / "_static").mkdir()
    shutil.copyfile(built / "_static" / view3d.PLOTLY_JS, tmp_path / "_static" / view3d.PLOTLY_JS)  # as the book serves it
    tetrahedron = {"type": "mesh3d", "x": [0, 1, 0, 0], "y": [0, 0, 1, 0], "z": [0, 0, 0, 1],
                   "i": [0, 0, 0, 1], "j": [1, 2, 3, 2], "k": [2, 3, 1, 3]}
    view = view3d.ArmView({"data": [tetrahedron], "layout": {}, "frames": [], "config": {}}, "v", "a tetrahedron")

    def page(name, body):
        path = tmp_path / name
        path.write_text('<html><head><script>window.MathJax = {options: {processHtmlClass: "math"}};</script>'
                        "<style>img { max-width: 100%; } .cell_output { overflow-x: auto; }</style>"  # as the book's theme
                        f'<script src="{mathjax}"></script></head><body><article class="bd-article" style="max-width: 600px">'
                        f"{body}</article></body></html>")
        return path

    broken = page("broken.html",
                  "<p>doi:10.1016/j.mechmachtheory." + "2023" * 30 + "</p>"  # one word wider than a phone
                  "<p>| quantity | paper | |---|---| | k | 718.67 |</p>"  # a table left as pipes
                  "<p>the energy $\\tfrac12 k|AB|^2$ as text</p>"  # TeX outside the math
                  '<p><span class="math">\\(\\\\tfrac12 k\\)</span></p>'  # a doubled backslash
                  '<p><span class="math">\\(\\frac{a}\\)</span></p>'  # TeX MathJax cannot parse
                  '<div class="cell_input"><pre style="white-space: pre">' + "x = 1; " * 200 + "</pre></div>"  # scrolls
                  '<div class="cell_input" style="width: 400px"><pre>z = 3</pre></div>'  # holds 88 characters? no
                  '<div class="cell_output"><pre style="white-space: pre">' + "Claim(quantity=...) " * 120 + "</pre></div>"
                  '<a href="_sources/">.ipynb</a>'  # a download of a folder
                  "<p>as <code>expand_gravity_energy</code> in <code>arms/paper000_arm.toml</code> does for the "
                  "issue, see 000 Table 3</p>"  # internal names
                  '<img src="ok.png" alt="a figure with no caption">'
                  '<figure><img src="ok.png" alt="a caption with no number"><figcaption>The arm</figcaption></figure>'
                  '<table class="coverage"><tr data-item="Eq. (1)"><td>Eq. (1)</td></tr></table>'  # Eq. (2) left out
                  + view.html().replace("_static/plotly.min.js", "_static/missing.js")  # a view that cannot draw
                  + view3d.ArmView(view.figure, "w", "a view from a network").html().replace(  # nor one that fetches
                      "'_static/plotly.min.js'", "'https://cdn.example.invalid/plotly.min.js'"))
    good = page("good.html", "<p>A table:</p><table><tr><td>k</td><td>718.67</td></tr></table>"
                             '<p><span class="math">\\(\\tfrac12 k\\)</span></p>'
                             '<div class="math">\\[h_j = d_j \\tag{8}\\]</div>'
                             '<div class="cell_output"><pre>short</pre></div>'
                             '<div class="cell_input"><pre style="font-size: 10px">y = 2</pre></div>'  # 88 fit
                             "<p>run <code>make figures</code>; Table 3 prints 0.004 m</p>"  # words for readers
                             '<div class="admonition"><p><code>notebooks/a.ipynb</code></p></div>'
                             '<figure><img src="ok.png" alt="drawn"><figcaption><p>Figure 1. The arm.</p></figcaption>'
                             '</figure><table class="coverage"><tr data-item="Eq. (1)"><td>Eq. (1)</td></tr>'
                             '<tr data-item="Eq. (2)"><td>Eq. (2)</td></tr></table>'
                             '<div class="cell_output">' + view.html() + "</div>")
    bare = page("bare.html", "<p>A chapter without its coverage table.</p>")
    wide = page("wide.html", '<div class="math">\\[' + " + ".join(f"k_{{{i}}} a_{{{i}}} b_{{{i}}}" for i in range(40))
                + ' = 0 \\tag{9}\\]</div>')  # a numbered display wider than the column
    (tmp_path / "ok.png").write_bytes((ROOT / "figures" / "lenzo2017_two_spring_arm" / "fig5_layouts.png").read_bytes())
    items = ["Eq. (1)", "Eq. (2)"]
    result = site.browser_check([broken, good, bare, wide], numbered=["broken.html", "good.html"],
                                captioned=["broken.html", "good.html"],
                                covered={"broken.html": items, "good.html": items, "bare.html": items},
                                prose=["broken.html", "good.html"])
    assert result["bare.html"] == ["no coverage table of the paper's items"]
    assert any("an equation tag outside the column (a numbered display" in p for p in result["wide.html"])
    problems = "\n".join(result["broken.html"])
    for expected in ("raw Markdown table", "TeX left as text: ", "doubled backslash", "could not parse",
                     "px wide in a 600 px column", "points to a folder", "no numbered equation",
                     "no numbered caption: a figure with no caption", "no numbered caption: a caption with no number",
                     "a paper item missing from the coverage table: Eq. (2)",
                     "a 3-D view that did not draw: a tetrahedron", "a 3-D view that did not draw: a view from a network",
                     "a code cell that scrolls sideways: x = 1;",
                     "a code cell narrower than the 88 characters code is formatted to: z = 3",
                     "an internal name in the prose: expand_gravity_energy",
                     "an internal name in the prose: arms/paper000_arm.toml", "does for the issue, see",
                     "see 000 Table",
                     "request left the machine: https://cdn.example.invalid/plotly.min.js",
                     "the page scrolls sideways on a phone (390 px wide) by", "px: p: doi:10.1016/j.mechmachtheory.2023"):
        assert expected in problems, (expected, problems)
    assert result["good.html"] == []


def test_the_prose_names_papers_and_links_equations_but_leaves_code_and_math_alone():
    names = {"000": ("juang2023_spatial_balance", "Juang et al. (2023)"),
             "003": ("juang2022_spring_efficiency", "Juang et al. (2022)")}
    labels = {("000", "41"), ("003", "7")}
    text = "000's Eq. (41) forbids it; Eq. (7) holds; Eq. (8) is not shown; `000` and $000$ stay; 0.004 m"
    assert prose.link_markdown(text, "003", names, labels) == (
        "{doc}`Juang et al. (2023) <juang2023_spatial_balance>`'s {ref}`Eq. (41) <eq-000-41>` forbids it; "
        "{ref}`Eq. (7) <eq-003-7>` holds; Eq. (8) is not shown; `000` and $000$ stay; 0.004 m")
    # in its own chapter a paper is "the paper" and its equations need no name; headings get no links
    assert prose.link_markdown("Paper 003's Table 2, 003 Eq. (7)", "003", names, labels) == \
        "The paper's Table 2, {ref}`Eq. (7) <eq-003-7>`"
    assert prose.link_markdown("## 4. The tie to 000\n000 and the paper-000 arm", "003", names, labels) == \
        "## 4. The tie to Juang et al. (2023)\n{doc}`Juang et al. (2023) <juang2023_spatial_balance>` and the " \
        "{doc}`Juang et al. (2023) <juang2023_spatial_balance>` arm"
    # HTML keeps its tags
    assert prose.link_html('<td title="000">Section 5, Eq. (7)</td>', "003", names, labels,
                           page="juang2022_spring_efficiency") == '<td title="000">Section 5, <a href="#eq-003-7">Eq. (7)</a></td>'
    printed = "Eq. (41) as printed:\n$$\nk a b = m g d \\tag{41}\n$$\n"
    assert prose.equation_numbers(printed) == ["41"]
    assert prose.anchor_equations(printed, "000") == (
        "Eq. (41) as printed:\n\n(eq-000-41)=\n```{math}\n:nowrap:\n\\[k a b = m g d \\tag{41}\\]\n```\n")
    # an AMS environment goes to MathJax as it is (Sphinx would put a line break's lines in split)
    assert "\n\\begin{align}a &= b \\tag{5} \\\\ c &= d \\tag{6}\\end{align}\n" in prose.anchor_equations(
        "$$\\begin{align}a &= b \\tag{5} \\\\ c &= d \\tag{6}\\end{align}$$", "002")
    assert prose.equation_numbers("inline $$x \\tag{9}$$ in a sentence") == []  # not a block of its own


def test_the_book_links_equations_and_names_papers(built):
    lenzo = (built / "lenzo2017_two_spring_arm.html").read_text()
    numbers = [n for cell in json.loads((ROOT / "notebooks" / "lenzo2017_two_spring_arm.ipynb").read_text())["cells"]
               if cell["cell_type"] == "markdown" for n in prose.equation_numbers("".join(cell["source"]))]
    assert numbers and all(f'id="{prose.equation_label("004", n)}"' in lenzo for n in numbers)
    text = re.sub(r"(?s)<(script|style|pre|code)\b.*?</\1>|<[^>]+>", " ", (built / "springlab_design_your_arm.html").read_text())
    assert not re.search(r"(?<![\w.,/-])00[0-4](?!\w)", text)  # no paper by its key
    assert 'href="juang2023_spatial_balance.html"' in (built / "springlab_design_your_arm.html").read_text()


def test_each_chapter_defines_its_statuses_above_its_first_claims_table(built):
    from springlab.workbench.claims import REPORT_COLUMNS

    report = (built / "report.html").read_text()
    assert 'id="statuses"' in report and all(f"<strong>{s}</strong>" in report for s in REPORT_COLUMNS)
    shown_any = 0
    for stem in ALL_STEMS:
        page = (built / f"{stem}.html").read_text()
        if '<table class="claims">' not in page:
            continue
        shown_any += 1
        start, table = page.find('class="claims-legend"'), page.index('<table class="claims">')
        assert 0 <= start < table, stem  # a reader meets the legend before the first verdict
        legend = page[start:table]
        used = set(re.findall(r'<tr class="claim [^"]*"><td>.*?<td><strong>([^<]+)</strong></td>', page))
        assert used and all(f"<strong>{s}</strong>" in legend for s in used), (stem, used)
        assert 'href="report.html#statuses"' in legend
    assert shown_any >= 5  # every paper chapter shows claims


def _coverage_legend_problems(page: str) -> list[str]:
    """What a reader of a chapter's coverage table would meet undefined: each status its verdicts use that no
    legend above the table defines."""
    from springlab.workbench.claims import REPORT_COLUMNS

    start = page.find('<table class="coverage">')
    if start < 0:
        return []
    table = page[start:page.index("</table>", start)]
    verdicts = re.findall(r'<tr [^>]*data-how="compared">.*?<td>([^<]*)</td></tr>', table)  # a compared row's last cell
    used = {re.sub(r" \(\d+ claims\)$", "", s) for v in verdicts for s in v.split("; ")}
    assert used <= set(REPORT_COLUMNS), used  # a verdict is its claims' statuses
    legend = page.rfind('class="coverage-legend"', 0, start)
    above = page[legend:start] if legend >= 0 else ""
    return [f"{s!r} used before any legend defines it" for s in sorted(used) if f"<strong>{s}</strong>" not in above]


def test_each_chapter_defines_the_statuses_of_its_coverage_table_above_it(built):
    checked = 0
    for stem in ALL_STEMS:
        page = (built / f"{stem}.html").read_text()
        if '<table class="coverage">' in page:
            checked += 1
            assert _coverage_legend_problems(page) == [], stem
    assert checked >= 5  # every paper chapter opens with its coverage
    page = (built / "juang2023_spatial_balance.html").read_text()  # the control: its legend taken out
    cut = re.sub(r'<div class="coverage-legend">.*?</div>', "", page, count=1, flags=re.S)
    assert cut != page and _coverage_legend_problems(cut)


def test_the_api_pages_show_no_path_of_the_machine_that_built_them(built):
    pages = sorted((built / "api").glob("*.html"))
    assert pages and all(str(ROOT) not in p.read_text() for p in pages), [p.name for p in pages if str(ROOT) in p.read_text()]


def test_the_glossary_defines_the_routes_and_links_the_statuses(built):
    page = (built / "glossary.html").read_text()
    assert all(f'id="term-Route-{k}"' in page for k in (1, 2, 3)) and 'href="report.html' in page
    assert 'href="glossary.html"' in (built / "index.html").read_text()  # in the book's table of contents


def test_each_chapter_says_how_to_run_it(built):
    # under each chapter's title: the set-up, and the command that runs that chapter's own notebook
    def text(page):
        return " ".join(re.sub(r"<[^>]+>", " ", (built / page).read_text()).split())

    for stem in ALL_STEMS:
        shown = text(f"{stem}.html")
        assert "Run it yourself" in shown and f"-m papermill notebooks/{stem}.ipynb" in shown and "make lab" in shown
        assert "--cwd notebooks" in shown  # run from notebooks/, as the book ran it:
        cells = json.loads((ROOT / "notebooks" / f"{stem}.ipynb").read_text())["cells"]
        given = re.search(r'^figures_dir = "([^"]+)"', "".join(next(c for c in cells if c["cell_type"] == "code")["source"]), re.M)
        assert (ROOT / "notebooks" / given.group(1)).resolve() == ROOT / "figures" / stem  # its figures where it says
    front = text("index.html")
    assert "Run it yourself" in front and "make figures" in front and "papermill" not in front


def test_glued_numbers_are_written_as_powers_of_ten(built):
    """A number glued into the prose in Python's exponent form ("1e-06") reads "1 × 10⁻⁶"; the control: the
    rewrite leaves other text (an identifier, a plain number, a version) alone."""
    assert prose.powers_of_ten("agree to 2e-12 N m, 1.6e-04 and 3e+02") == "agree to 2 × 10⁻¹² N m, 1.6 × 10⁻⁴ and 3 × 10²"
    assert prose.powers_of_ten("x1e-06, 1.6, v1.2e3x, 12") == "x1e-06, 1.6, v1.2e3x, 12"
    pasted = [m for page in built.glob("*.html")
              for m in re.findall(r'<span class="pasted-text">([^<]*)</span>', page.read_text())]
    assert pasted and any("× 10" in text for text in pasted)
    assert not [text for text in pasted if re.search(r"\de[+-]?\d", text)]
