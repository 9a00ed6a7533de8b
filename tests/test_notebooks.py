"""The notebooks are tests: each runs with quick=True, and each has a parameters cell."""

import json
import re
from pathlib import Path

import papermill as pm
import pytest
from quickruns import FIGURES, quick_run

from springlab.papers import PAPERS
from springlab.workbench import prose
from springlab.workbench.claims import STATUSES
from springlab.workbench.notebooks import notebook_paths

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = notebook_paths(ROOT / "notebooks")


def test_there_are_notebooks():
    assert NOTEBOOKS


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_has_a_tagged_parameters_cell_with_quick(path):
    params = pm.inspect_notebook(str(path))
    assert "quick" in params, f"{path.name}: no tagged 'parameters' cell defining quick"
    assert "figures_dir" in params


MAX_CELL_LINES = 12


def long_cells(nb: dict) -> list[tuple[int, int]]:
    """(cell index, lines) of every code cell longer than :data:`MAX_CELL_LINES`."""
    out = []
    for k, cell in enumerate(nb["cells"]):
        if cell["cell_type"] == "code":
            lines = len("".join(cell["source"]).rstrip("\n").splitlines())
            if lines > MAX_CELL_LINES:
                out.append((k, lines))
    return out


def test_the_cell_size_check_can_fail():
    cell = {"cell_type": "code", "source": ["x = 1\n"] * (MAX_CELL_LINES + 1)}
    assert long_cells({"cells": [cell]}) == [(0, MAX_CELL_LINES + 1)]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_is_thin(path):
    """Logic lives in the library: no code cell over a dozen lines."""
    assert long_cells(json.loads(path.read_text())) == []


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_is_committed_without_outputs(path):
    nb = json.loads(path.read_text())
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            assert not cell.get("outputs") and cell.get("execution_count") is None


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs_quick(path):
    quick_run(path.stem)  # the book test builds the whole book from the same runs
    figures = FIGURES / path.stem
    claims = json.loads((figures / "claims.json").read_text())
    assert claims and all(c["status"] in STATUSES for c in claims)
    assert all(c["status"] != "discrepancy" or c["note"] for c in claims), "a discrepancy needs a note"
    assert list(figures.glob("*.png")) and list(figures.glob("*.svg"))


def headings(nb: dict) -> list[str]:
    """Every Markdown heading of a notebook, in order."""
    return [line.strip() for cell in nb["cells"] if cell["cell_type"] == "markdown"
            for line in "".join(cell["source"]).splitlines() if line.startswith("#")]


def test_the_heading_check_finds_a_repeated_heading():
    cell = {"cell_type": "markdown", "source": "## 4. Figs\n\ntext\n\n## 4. Figs\n"}
    assert headings({"cells": [cell]}) == ["## 4. Figs", "## 4. Figs"]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_no_section_heading_is_repeated(path):
    """The book's contents and the report's links go by section: each heading once."""
    found = headings(json.loads(path.read_text()))
    assert len(found) == len(set(found)), [h for h in found if found.count(h) > 1]


def markdown_problems(nb: dict) -> list[str]:
    """A notebook's Markdown that the book would show broken: a TeX command written with a
    doubled backslash (``\\\\tfrac``: MathJax reads a line break, then the letters), and a paper
    equation number shown twice (its anchor in the book must be unique)."""
    problems, numbers = [], []
    for k, cell in enumerate(nb["cells"]):
        if cell["cell_type"] != "markdown":
            continue
        text = "".join(cell["source"])
        problems += [f"cell {k}: doubled backslash in {m.group(0)!r}" for m in re.finditer(r"\\\\[A-Za-z]+", text)]
        numbers += prose.equation_numbers(text)
    problems += [f"equation ({n}) is shown twice" for n in sorted({n for n in numbers if numbers.count(n) > 1})]
    return problems


def test_the_markdown_check_finds_a_doubled_backslash_and_a_repeated_number():
    cells = [{"cell_type": "markdown", "source": "$\\\\tfrac12 k$\n\n$$\nx \\tag{8}\n$$\n"},
             {"cell_type": "markdown", "source": "$$\ny \\tag{8}\n$$\n"}]
    assert markdown_problems({"cells": cells}) == ["cell 0: doubled backslash in '\\\\\\\\tfrac'",
                                                   "equation (8) is shown twice"]
    cells = [{"cell_type": "markdown", "source": "$\\tfrac12 k$, $a \\\\ b$\n\n$$\nx \\tag{8}\n$$\n"}]
    assert markdown_problems({"cells": cells}) == []  # a line break before a space is one


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_the_markdown_renders(path):
    assert markdown_problems(json.loads(path.read_text())) == []


@pytest.mark.parametrize("path", [p for p in NOTEBOOKS if PAPERS.get(p.stem, {}).get("key")], ids=lambda p: p.stem)
def test_a_paper_chapter_shows_its_key_equations_numbered_as_printed(path):
    """Each paper's notebook shows the equations it reproduces as display math with the paper's
    own numbers (\\tag{23b}); the book anchors and links them."""
    nb = json.loads(path.read_text())
    numbers = [n for cell in nb["cells"] if cell["cell_type"] == "markdown"
               for n in prose.equation_numbers("".join(cell["source"]))]
    assert len(numbers) >= 4, numbers
