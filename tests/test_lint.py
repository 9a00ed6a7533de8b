import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.skipif(shutil.which("ruff") is None and not (Path(sys.prefix) / "bin" / "ruff").exists(),
                    reason="ruff is not installed (dev extra)")
def test_ruff_is_clean():
    ruff = shutil.which("ruff") or str(Path(sys.prefix) / "bin" / "ruff")
    result = subprocess.run([ruff, "check", "springlab", "tests", "benchmarks"], cwd=ROOT,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


CHAPTERS = sorted((ROOT / "notebooks").glob("*.ipynb"))
"""Every chapter's code cells are formatted to the book's column (``ruff format notebooks``, at
notebooks/ruff.toml's line length), and none passes a dozen lines once they are
(tests/test_notebooks.py): logic that would lives in the library."""


def _ruff() -> str:
    return shutil.which("ruff") or str(Path(sys.prefix) / "bin" / "ruff")


def _unformatted(path: Path) -> str:
    """ruff's diff for a notebook that is not formatted to the column; empty when it is."""
    result = subprocess.run([_ruff(), "format", "--config", str(ROOT / "notebooks" / "ruff.toml"), "--diff", str(path)],
                            cwd=ROOT, capture_output=True, text=True)
    return result.stdout + result.stderr if result.returncode else ""


@pytest.mark.skipif(shutil.which("ruff") is None and not (Path(sys.prefix) / "bin" / "ruff").exists(),
                    reason="ruff is not installed (dev extra)")
@pytest.mark.parametrize("path", CHAPTERS, ids=lambda p: p.stem)
def test_the_chapters_code_is_formatted_to_the_column(path):
    assert _unformatted(path) == ""
    assert _wider_than_the_column(json.loads(path.read_text())) == []  # strings ruff cannot split


def _wider_than_the_column(notebook: dict) -> list[str]:
    """Code lines longer than the book's column (notebooks/ruff.toml's line length)."""
    from springlab.workbench.site import CODE_COLUMN

    return [line for cell in notebook["cells"] if cell["cell_type"] == "code"
            for line in "".join(cell["source"]).splitlines() if len(line) > CODE_COLUMN]


@pytest.mark.skipif(shutil.which("ruff") is None and not (Path(sys.prefix) / "bin" / "ruff").exists(),
                    reason="ruff is not installed (dev extra)")
def test_the_format_check_catches_a_line_wider_than_the_column(tmp_path):
    notebook = json.loads(CHAPTERS[0].read_text())
    cell = next(c for c in notebook["cells"] if c["cell_type"] == "code")
    cell["source"] = ["x = {" + ", ".join(f'"key{k}": {k}' for k in range(12)) + "}\n"]  # 120 characters
    control = tmp_path / "control.ipynb"
    control.write_text(json.dumps(notebook, indent=1))
    assert "key11" in _unformatted(control)
    cell["source"] = ['print("' + "a string ruff will not split " * 4 + '")\n']  # 130 characters
    assert len(_wider_than_the_column(notebook)) == 1


def test_the_book_sets_code_at_the_width_it_is_formatted_to():
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    from springlab.workbench.site import CODE_COLUMN

    assert tomllib.loads((ROOT / "notebooks" / "ruff.toml").read_text())["line-length"] == CODE_COLUMN


def _pyflakes(path: Path) -> str:
    """ruff's pyflakes findings (unused imports and names, undefined names) in a notebook; empty when none."""
    result = subprocess.run([_ruff(), "check", "--select", "F", "--output-format", "concise", str(path)], cwd=ROOT,
                            capture_output=True, text=True)
    return result.stdout + result.stderr if result.returncode else ""


@pytest.mark.skipif(shutil.which("ruff") is None and not (Path(sys.prefix) / "bin" / "ruff").exists(),
                    reason="ruff is not installed (dev extra)")
@pytest.mark.parametrize("path", CHAPTERS, ids=lambda p: p.stem)
def test_no_chapter_imports_what_it_does_not_use_or_uses_what_it_never_defines(path, tmp_path):
    assert _pyflakes(path) == ""
    notebook = json.loads(path.read_text())  # the control: an unused import is named
    notebook["cells"].append({"cell_type": "code", "execution_count": None, "id": "control", "metadata": {},
                              "outputs": [], "source": ["import colorsys\n"]})
    control = tmp_path / path.name
    control.write_text(json.dumps(notebook, indent=1))
    assert "colorsys" in _pyflakes(control)
