"""The reproduction report and the site: claims recorded, links resolved."""

import json
import shutil
from pathlib import Path

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


def test_the_front_page_names_each_chapter_once_with_its_venue_and_doi():
    from springlab.workbench import book

    stems = list(book.CHAPTER_ORDER)
    page = book.front_page(stems, {s: {"cells": [], "metadata": {}} for s in stems}, {})
    lines = [line for line in page.splitlines() if line.startswith("**")]
    assert len(lines) == len(stems)
    assert any(line.endswith("*. Mechanical Sciences (2022); no DOI (the text prints none)") for line in lines)
    assert not any("(2026)" in line for line in lines)  # springlab's own chapters carry no paper's year
