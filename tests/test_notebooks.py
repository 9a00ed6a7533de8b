"""The notebooks are tests: each runs with quick=True, and each has a parameters cell."""

import json
from pathlib import Path

import papermill as pm
import pytest

from springlab.workbench.claims import STATUSES
from springlab.workbench.notebooks import notebook_paths, run_notebook

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
def test_notebook_runs_quick(path, tmp_path):
    figures = tmp_path / "figures"
    run_notebook(path, tmp_path / path.name, {"quick": True, "figures_dir": str(figures)})
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
