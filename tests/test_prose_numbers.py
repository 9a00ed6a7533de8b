"""Numbers in the chapters' prose cannot go stale (springlab.workbench.numbers): each is glued from the
computation, printed by the paper (springlab.papers), a reference, or a small count."""

import json
import re
from pathlib import Path

import pytest

from springlab.workbench import numbers

ROOT = Path(__file__).resolve().parents[1]
STEMS = sorted(p.stem for p in (ROOT / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("stem", STEMS)
def test_every_number_in_the_prose_is_glued_printed_or_a_reference(stem):
    values = numbers.values_for(stem)
    cells = json.loads((ROOT / "notebooks" / f"{stem}.ipynb").read_text())["cells"]
    typed = [(k, n) for k, cell in enumerate(cells) if cell["cell_type"] == "markdown"
             for n in numbers.unglued("".join(cell["source"]), values)]
    assert typed == [], f"{stem}: numbers typed into the prose (cell, number); glue them from the computation"


def test_the_check_catches_a_typed_number_and_passes_a_glued_one():
    values = numbers.values_for("zhang2023_dyad")
    # the stale numbers the book once had, typed in: each is caught
    assert numbers.unglued("the shoulder keeps 14.57 N m; on a 10° grid; 0.75 to 1.17 times", values) == [
        "14.57", "10", "0.75", "1.17"]
    # the controls: glued, printed by the paper (s = 0.84 m, C = 184), references and small counts pass
    assert numbers.unglued("{glue:text}`balanced_torque:.2f` N m; the paper prints s = 0.84 m and C = 184; "
                           "Eqs. (24)-(25), Fig. 2, Section V.A, 001's 6 links and $S_{1,4}$, R3, route 2 (2023), the SO-101",
                           values) == []
    assert numbers.unglued("s = 0.85 m", values) == ["0.85"]  # one digit off is not printed


@pytest.mark.parametrize("stem", STEMS)
def test_every_glued_name_the_prose_uses_is_glued_by_a_code_cell(stem):
    cells = json.loads((ROOT / "notebooks" / f"{stem}.ipynb").read_text())["cells"]
    code = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
    glued = set(re.findall(r"""\bglue\(\s*f?["']([\w{}]+)["']""", code))
    used = {m for c in cells if c["cell_type"] == "markdown"
            for m in re.findall(r"\{glue(?::\w+)?\}`([\w]+)", "".join(c["source"]))}
    loose = {u for u in used if u not in glued and not any("{" in g and re.fullmatch(
        re.sub(r"\\\{\w+\\\}", r"\\w+", re.escape(g)), u) for g in glued)}
    assert loose == set(), f"{stem}: the prose uses glue names no code cell glues"
