"""The project's top level holds the layout the README describes and nothing left behind: a file that
`springlab design` writes by default (``<arm>.design.json``, its sheet) is ignored by git, never
committed."""

import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

TOP_LEVEL = {".ci", ".gitignore", ".importlinter", "Makefile", "README.md", "LICENSE", "CITATION.cff", "benchmarks",
             "constraints.txt", "docs", "figures", "notebooks", "pyproject.toml", "springlab", "tests"}
"""What may be committed at the top level (the README's layout; some entries optional)."""


def _git(*args) -> str:
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout


def _top_level(paths) -> set:
    return {p.split("/", 1)[0] for p in paths if p}


@pytest.fixture(scope="module")
def tracked():
    if not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")
    return _git("ls-files").splitlines()


def test_the_top_level_holds_the_layout_alone(tracked):
    assert _top_level(tracked) <= TOP_LEVEL, sorted(_top_level(tracked) - TOP_LEVEL)
    assert _top_level(tracked + ["turned.design.json"]) - TOP_LEVEL == {"turned.design.json"}  # the check can fail


@pytest.mark.parametrize("name", ["ur5_robot.design.json", "ur5_robot.sheet.csv", "ur5_robot.sheet.md",
                                  "notebooks/arms/x.design.json"])
def test_what_springlab_design_writes_by_default_is_ignored(name, tracked):
    assert _git("check-ignore", "--no-index", name).strip() == name
    assert not any(p.endswith((".design.json", ".sheet.csv", ".sheet.md")) for p in tracked)


def test_an_arm_file_is_not_ignored(tracked):
    result = subprocess.run(["git", "check-ignore", "--no-index", "notebooks/arms/my_arm.toml"], cwd=ROOT,
                            capture_output=True, text=True)
    assert result.returncode == 1  # not ignored: the negative control
