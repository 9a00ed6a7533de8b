"""The reproduction report and the site: claims recorded, links resolved."""

import json
import shutil
from pathlib import Path

import nbformat
import pytest

from springlab.workbench import site
from springlab.workbench.notebooks import notebook_paths

ROOT = Path(__file__).resolve().parents[1]
STEMS = [p.stem for p in notebook_paths(ROOT / "notebooks")]


@pytest.mark.parametrize("stem", STEMS)
def test_every_notebook_records_claims_within_their_tolerances(stem):
    path = ROOT / "figures" / stem / "claims.json"
    assert path.exists(), f"{stem} records no claims (run make figures)"
    claims = json.loads(path.read_text())
    assert claims, f"{stem} records no claims"
    for c in claims:
        if c["status"] == "reproduced":
            assert abs(c["ours"] - c["paper"]) <= c["tolerance"], c
    assert stem in site.PAPERS, f"{stem} is missing from springlab.papers.PAPERS"


def test_report_lists_every_claim(tmp_path):
    figures = tmp_path / "figures"
    shutil.copytree(ROOT / "figures", figures)
    text = site.write_report(figures).read_text()
    for stem, claims in site.load_claims(figures).items():
        assert f"## {stem}" in text
        for c in claims:
            assert c["quantity"].replace("|", "\\|") in text  # a '|' in a cell is escaped
    # every table row has as many cells as its header: no '|' in a claim breaks a row
    for block in text.split("\n\n"):
        rows = [r for r in block.splitlines() if r.startswith("|")]
        if rows:
            width = len(rows[0].replace("\\|", "").split("|"))
            assert all(len(r.replace("\\|", "").split("|")) == width for r in rows), rows[0]


def _executed_notebook(path: Path):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# A page\n\nEnergy $U = k l^2 / 2$."),
                nbformat.v4.new_code_cell("1 + 1", outputs=[nbformat.v4.new_output(
                    "execute_result", data={"text/plain": "2"}, execution_count=1)], execution_count=1)]
    nb.metadata["papermill"] = {"duration": 1.5}
    nbformat.write(nb, path)


def test_site_pages_resolve_and_load_nothing_from_the_internet(tmp_path):
    notebooks, figures = tmp_path / "nb", tmp_path / "figures"
    notebooks.mkdir()
    _executed_notebook(notebooks / "juang2023_spatial_balance.ipynb")
    shutil.copytree(ROOT / "figures" / "juang2023_spatial_balance", figures / "juang2023_spatial_balance")
    index = site.build_site(notebooks, tmp_path / "site", figures, tmp_path / "cache")
    page = tmp_path / "site" / "juang2023_spatial_balance.html"
    assert site.check_links(index) == [] and site.check_links(page) == []
    assert "mathjax/MathJax.js" in page.read_text()
    assert "<img" in index.read_text() and "1.5 s" in index.read_text()


def test_a_page_is_rendered_again_only_when_its_notebook_changed(tmp_path):
    notebooks, cache = tmp_path / "nb", tmp_path / "cache"
    notebooks.mkdir()
    executed = notebooks / "juang2023_spatial_balance.ipynb"
    _executed_notebook(executed)
    page = site.render_page(executed, tmp_path / "site", cache)
    page.write_text("rendered before")  # a fresh key: the page is reused as it is
    assert site.render_page(executed, tmp_path / "site", cache).read_text() == "rendered before"
    executed.write_text(executed.read_text().replace("A page", "Another page"))  # the notebook changed
    assert "Another page" in site.render_page(executed, tmp_path / "site", cache).read_text()
    page.unlink()  # a missing page is rendered whatever the key says
    assert "Another page" in site.render_page(executed, tmp_path / "site", cache).read_text()


def test_a_broken_page_is_caught(tmp_path):
    (tmp_path / "here.png").write_bytes(b"\x89PNG")
    page = tmp_path / "broken.html"
    page.write_text('<html><body><img src="here.png"><img src="missing.png"><a href="gone.html">x</a>'
                    '<a href="https://doi.org/10.1/x">doi</a>'
                    '<script src="https://cdn.example.org/lib.js"></script></body></html>')
    problems = site.check_links(page)
    assert len(problems) == 3
    assert any("missing.png" in p for p in problems) and any("gone.html" in p for p in problems)
    assert any("from the internet" in p for p in problems)
