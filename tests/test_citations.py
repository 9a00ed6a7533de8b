"""Citations a reader can grep: every equation the library mentions carries its paper's
key ("000 Eq. (23b)"; four papers share equation numbers), and every module that cites a
paper names it in a References block."""

import re
from pathlib import Path

import pytest

from springlab.papers import BY_KEY

ROOT = Path(__file__).resolve().parents[1] / "springlab"
UNKEYED = re.compile(r"(?<!\b\d{3} )\bEqs?\.")
KEYED = re.compile(r"\b(\d{3}) Eqs?\.")


def unkeyed(text: str) -> list[str]:
    """Lines that mention an equation without a paper key in front of it."""
    return [line.strip() for line in text.splitlines() if UNKEYED.search(line)]


def test_the_check_finds_an_equation_without_its_paper():
    assert unkeyed("x = 1  # Eq. (24)") == ["x = 1  # Eq. (24)"]
    assert unkeyed("from Eqs. 5-8 of the paper") == ["from Eqs. 5-8 of the paper"]
    assert unkeyed("x = 1  # 000 Eq. (23b); y  # 003 Eqs. (11a-d)") == []


QUOTING = {ROOT / "workbench" / "prose.py", ROOT / "workbench" / "coverage.py", ROOT / "workbench" / "numbers.py"}
"""Modules that cite no paper but quote the forms a mention takes ("Eq. 8", "000's"): the
book's prose module, which turns them into links, the coverage tables', which read them in the claims,
and the prose numbers' check, which passes them as references."""
MODULES = sorted(p for p in ROOT.rglob("*.py") if p not in QUOTING)


def test_the_quoting_modules_exist():
    assert QUOTING and all(p.exists() for p in QUOTING)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_equation_names_its_paper(path):
    assert unkeyed(path.read_text()) == []


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_a_module_that_cites_a_paper_lists_it_in_its_references(path):
    text = path.read_text()
    keys = set(KEYED.findall(text))
    assert keys <= set(BY_KEY), f"unknown paper keys {keys - set(BY_KEY)}"
    if not keys:
        return
    doc = text.split('"""')[1] if text.lstrip().startswith(('"""', 'r"""')) else ""
    assert "References\n----------" in doc, "a module that cites a paper needs a References block"
    flat = " ".join(doc.lower().split())
    for key in keys:
        title = " ".join(BY_KEY[key]["title"].lower().split())
        assert title[:40] in flat, f"{key}: {BY_KEY[key]['title']!r} is not in the References block"
