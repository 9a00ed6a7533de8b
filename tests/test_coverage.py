"""Each paper's inventory of numbered items (springlab/papers/items_<key>.toml) and the coverage table
built from it and the chapter's claims: complete (no number skipped), every item's section a section of
its chapter, every compared item backed by claims and every item with claims said to be compared."""

import json
from pathlib import Path

import pytest
from docutils.nodes import make_id

from springlab.errors import SpringlabError
from springlab.papers import PAPERS
from springlab.workbench import book, coverage

ROOT = Path(__file__).resolve().parents[1]
CHAPTERS = {v["key"]: stem for stem, v in PAPERS.items() if v.get("key")}


def _claims(stem):
    return json.loads((ROOT / "figures" / stem / "claims.json").read_text())


@pytest.mark.parametrize("key", sorted(CHAPTERS))
def test_each_inventory_is_complete_and_agrees_with_its_chapter(key):
    stem = CHAPTERS[key]
    items = coverage.inventory(key)
    assert coverage.gaps(items) == []
    assert {i.kind for i in items} >= {"Eq.", "Fig."}
    notebook = json.loads((ROOT / "notebooks" / f"{stem}.ipynb").read_text())
    titles, _ = book.sections(notebook)
    numbers = {book._section_number(t, k)[1:] for k, t in enumerate(titles) if k}
    assert {i.section for i in items if i.section} <= numbers
    by_item = coverage.concerning(items, _claims(stem), key)
    said = {i.item for i in items if i.how == "compared"}
    backed = {name for name, claims in by_item.items() if claims}
    assert said == backed  # "compared" exactly where claims concern the item


def test_the_gaps_and_the_references_are_found():
    items = [coverage.Item(name, "x", "1", "used") for name in ("Eq. (1)", "Eq. (3a)", "Eq. (3c)", "Table 2", "Fig. 1")]
    assert coverage.gaps(items) == ["Eq. (2)", "Eq. (3b)", "Table 1"]
    assert coverage.gaps(items[:1] + items[-1:]) == []  # the control
    names = {"Table 1", "Table 2", "Fig. 16", "Fig. 17", *(f"Eq. ({n})" for n in ("20", "21", "30", "31", "48a", "48f"))}
    assert coverage.references("Tables 1-2", names) == {"Table 1", "Table 2"}
    assert coverage.references("Figs. 16 and 17 (flat total curve)", names) == {"Fig. 16", "Fig. 17"}
    assert coverage.references("Eqs. (20)-(30)", names) == {"Eq. (20)", "Eq. (21)", "Eq. (30)"}
    assert coverage.references("Eqs. (48a-f)", names) == {"Eq. (48a)", "Eq. (48f)"}
    names |= {"Fig. 5"}
    assert coverage.references("Fig. 5 and 000 Table 1", names, "004") == {"Fig. 5"}  # not 000's table
    assert coverage.references("000 Table 1 (each spring once)", names, "000") == {"Table 1"}
    assert coverage.references("Section V.A", names) == set()


def test_a_malformed_inventory_entry_is_refused_with_its_place():
    good = {"item": "Eq. (8)", "what": "x", "section": "1", "how": "derived"}
    assert coverage._item("000", 0, good).number == (8, "")
    for bad, said in (({"item": "Equation 8"}, "item = 'Equation 8'"), ({"how": "checked"}, "how = 'checked'"),
                      ({"how": "not covered", "section": ""}, "without a note"),
                      ({"section": ""}, "without a section"), ({"colour": "red"}, "unknown field")):
        with pytest.raises(SpringlabError, match="entry 3") as err:
            coverage._item("000", 2, {**good, **bad})
        assert said in str(err.value)


def test_the_chapter_opens_with_its_coverage_and_the_report_sums_it():
    stem = CHAPTERS["004"]
    notebook = json.loads((ROOT / "notebooks" / f"{stem}.ipynb").read_text())
    text = book.coverage_markdown(stem, notebook, _claims(stem))
    items = coverage.inventory("004")
    assert text.count("<tr data-item=") == len(items) and "\n\n" not in text.split("<details", 1)[1]
    assert f'href="#{make_id(stem)}-s' in text  # sections linked
    assert book.coverage_markdown("springlab_design_your_arm", notebook, []) == ""
    report = "\n".join(book._coverage_report([stem], {stem: _claims(stem)}))
    assert f"| **total** | {len(items)} | {len(items)} |" in report
    assert all(f"**{h}**" in report for h in coverage.HOWS)
