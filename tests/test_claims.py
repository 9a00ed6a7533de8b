"""Claims that say what they are: every claims.json holds its verdicts to their own rules,
and Claims refuses what would make a verdict untrustworthy."""

import json
import math
from pathlib import Path

import pytest

from springlab.errors import SpringlabError
from springlab.workbench.claims import STATUSES, Claims
from springlab.workbench.notebooks import notebook_paths

ROOT = Path(__file__).resolve().parents[1]
STEMS = [p.stem for p in notebook_paths(ROOT / "notebooks")]


def _no_nan(value, where):
    if isinstance(value, float):
        assert math.isfinite(value), f"NaN or inf in {where}"
    elif isinstance(value, dict):
        for k, v in value.items():
            _no_nan(v, f"{where}.{k}")
    elif isinstance(value, list):
        for k, v in enumerate(value):
            _no_nan(v, f"{where}[{k}]")


def check_records(records, where):
    """The rules every claims.json obeys; returns the problems found."""
    problems = []
    for c in records:
        label = f"{where}: {c.get('quantity')}"
        if c.get("status") not in STATUSES:
            problems.append(f"{label}: unknown status {c.get('status')!r}")
        if not c.get("tolerance_basis"):
            problems.append(f"{label}: no tolerance_basis")
        if c.get("status") == "rounding" and not (c.get("band") and c["band"].get("basis")
                                                  and c["band"].get("value") is not None):
            problems.append(f"{label}: a rounding claim without its band")
        if c.get("status") == "bound" and not (c.get("tolerance") is None and str(c.get("note", "")).startswith(
                ("at least ", "at most ")) and c.get("ours") is not None):
            problems.append(f"{label}: a bound must say its direction (at least / at most) and carry no tolerance")
        if c.get("status") == "not compared" and not (str(c.get("note", "")).strip() and c.get("ours") is None):
            problems.append(f"{label}: not compared, but with a value of ours or without the note saying why")
        if c.get("status") in ("reproduced", "reproduced with corrected input") and not (
                abs(c["ours"] - c["paper"]) <= c["tolerance"]):
            problems.append(f"{label}: reproduced, but |ours - paper| > tolerance")
        if c.get("status") in ("alternative reading", "reproduced with corrected input") and not c.get("cause"):
            problems.append(f"{label}: {c['status']} without the reading or the correction it rests on")
        try:
            _no_nan(c, label)
        except AssertionError as err:
            problems.append(str(err))
    return problems


@pytest.mark.parametrize("stem", STEMS)
def test_every_claims_file_keeps_its_rules(stem):
    path = ROOT / "figures" / stem / "claims.json"
    text = path.read_text()
    assert "NaN" not in text and "Infinity" not in text
    records = json.loads(text)
    assert records
    assert check_records(records, stem) == []


def test_the_check_catches_each_kind_of_bad_claim():  # negative controls: the check above can fail
    good = {"quantity": "x", "status": "reproduced", "paper": 1.0, "ours": 1.0, "tolerance": 0.1,
            "tolerance_basis": "half a unit"}
    assert check_records([good], "t") == []
    bad = [dict(good, ours=2.0), dict(good, tolerance_basis=""), dict(good, status="rounding", band=None),
           dict(good, note=float("nan")), dict(good, status="echoed"), dict(good, status="not compared", note=""),
           dict(good, status="alternative reading", cause=""), dict(good, status="reproduced with corrected input"),
           dict(good, status="reproduced with corrected input", cause="x", ours=2.0)]
    assert all(len(check_records([b], "t")) >= 1 for b in bad)


def test_compare_refuses_nan_negative_tolerance_unknown_status_and_a_missing_basis():
    claims = Claims("t")
    with pytest.raises(SpringlabError, match="ours is nan"):
        claims.compare("q", "w", 1.0, float("nan"), unit="m", tolerance=0.1, tolerance_basis="b")
    with pytest.raises(SpringlabError, match="tolerance must be >= 0"):
        claims.compare("q", "w", 1.0, 1.0, unit="m", tolerance=-0.1, tolerance_basis="b")
    with pytest.raises(SpringlabError, match="expect must be one of"):
        claims.compare("q", "w", 1.0, 1.0, unit="m", tolerance=0.1, tolerance_basis="b", expect="fine")
    with pytest.raises(SpringlabError, match="tolerance_basis"):
        claims.compare("q", "w", 1.0, 1.0, unit="m", tolerance=0.1, tolerance_basis="")
    with pytest.raises(SpringlabError, match="band_basis"):
        claims.compare("q", "w", 1.0, 1.0, unit="m", tolerance=0.1, tolerance_basis="b", rounding=0.2)
    with pytest.raises(SpringlabError, match="needs its note"):
        claims.not_compared("q", "w", unit="J", note=" ")
    assert claims.records == []
    assert claims.not_compared("q", "w", unit="J", note="why").status == "not compared"


def test_statuses_and_the_written_file(tmp_path):
    claims = Claims("t")
    assert claims.compare("a", "w", 1.0, 1.004, unit="m", tolerance=1e-9, tolerance_basis="exact",
                          decimals=2, expect="rounding").band["value"] > 0.004
    claims.input("b", "w", 0.06, 0.06, unit="m", note="free choice")
    claims.consistency("c", "w", 95.37, 95.366, unit="%", tolerance=0.005, tolerance_basis="half a unit")
    with pytest.raises(AssertionError):
        claims.compare("d", "w", 1.0, 2.0, unit="m", tolerance=0.1, tolerance_basis="b")  # a discrepancy
    claims.bound("e", "w", 0.0, 25.0, unit="configurations", direction="at least", basis="an enumeration stopped")
    with pytest.raises(SpringlabError, match="basis"):
        claims.bound("f", "w", 0.0, 25.0, unit="-", direction="at least", basis="")
    records = json.loads(claims.write(tmp_path).read_text())
    assert [r["status"] for r in records] == ["rounding", "input", "consistent", "discrepancy", "bound"]
    assert "lies outside it" in records[-1]["note"] and records[-1]["tolerance"] is None
    assert check_records(records, "t") == []
    records[-1]["note"] = "25 configurations"  # a bound that does not say which way: the check must catch it
    assert check_records(records, "t") != []


def test_diff_claims_finds_a_changed_verdict_and_nothing_else(tmp_path):
    from springlab.workbench.claims import diff_claims

    before, after = tmp_path / "before", tmp_path / "after"
    for root in (before, after):
        c = Claims("demo")
        c.compare("k_S(1,2)", "Table 3", 4998.0, 4998.0 + (1e-10 if root is after else 0.0), unit="N/m",
                  tolerance=0.5, tolerance_basis="half a unit")
        c.compare("index", "Table 5", 0.5389, 0.53891 if root is after else 0.5389, unit="-", tolerance=5e-5,
                  tolerance_basis="half a unit")
        c.write(root / "demo")
    changes = diff_claims(before, after)
    assert len(changes) == 2 and all("ours" in x or "difference" in x for x in changes)
    assert any("index" in x for x in changes)
    assert diff_claims(before, after, rel=1e-3) == []  # within a loose tolerance, the same
    assert diff_claims(before, before) == []


def _executed_code_cells(notebook: Path) -> list[str]:
    """The sources of the code cells a kernel numbers 1, 2, ... (IPython skips blank cells)."""
    cells = json.loads(notebook.read_text())["cells"]
    return ["".join(c["source"]) for c in cells if c["cell_type"] == "code" and "".join(c["source"]).strip()]


@pytest.mark.parametrize("stem", STEMS)
def test_every_claim_names_the_cell_that_records_it(stem):
    """make figures runs the notebooks without injected parameters, so a claim's execution
    count is its cell's place among the notebook's code cells; that cell records claims."""
    cells = _executed_code_cells(ROOT / "notebooks" / f"{stem}.ipynb")
    for c in json.loads((ROOT / "figures" / stem / "claims.json").read_text()):
        assert isinstance(c["cell"], int) and 1 <= c["cell"] <= len(cells), c["quantity"]
        assert "claims." in cells[c["cell"] - 1], (c["quantity"], cells[c["cell"] - 1][:200])


def test_a_claim_outside_a_kernel_has_no_cell():
    claims = Claims("test")
    claims.input("x", "here", None, 1.0, unit="m", note="fed in")
    assert claims.records[0].cell is None


def test_the_html_table_shows_every_claim_with_its_details_under_it():
    from springlab.workbench.claims import HTML_COLUMNS, html_table

    c = Claims("t")
    c.compare("k_S(1,4) <spring>", "Table 3", 718.67, 2156 / 3, unit="N/m", tolerance=0.005,
              tolerance_basis="half a unit", decimals=2, note="printed rounded")
    c.compare("n", "Table 1", 15, 21, unit="configurations", tolerance=0, tolerance_basis="a count: exact",
              expect="discrepancy", cause="rows omitted")
    records = c.to_records()
    table = html_table(records, made_in=[("x.html#x-s1", "§1"), None])
    assert table.count('<tr class="claim ') == 2 and table.count('<tr class="claim-details') == 2
    assert "&lt;spring&gt;" in table and "<spring>" not in table  # text is escaped
    assert "tolerance 0.005 N/m (half a unit)" in table and "Cause: rows omitted" in table
    assert "discrepancy, cause found" in table and '<a href="x.html#x-s1">§1</a>' in table
    assert table.count("<th>") == len(HTML_COLUMNS) + 1 and "\n" not in table  # one HTML block in Markdown
    # a notebook shows the claims, and a claim a cell ends with, as this table (not a repr)
    assert c._repr_html_() == html_table(records)
    assert c.records[0]._repr_html_().count('<tr class="claim ') == 1


def test_every_status_has_a_meaning_and_an_undefined_one_stops_the_book():
    from springlab.workbench import book
    from springlab.workbench.claims import MEANINGS, REPORT_COLUMNS, legend_html, report_column

    assert set(MEANINGS) == set(REPORT_COLUMNS)  # "bound" included: every column of the report defined
    claims = Claims("test")
    claims.compare("a length", "Table 1", 1.0, 1.0, unit="m", tolerance=1e-9, tolerance_basis="exact")
    claims.input("a rate", "Table 2", 2.0, 2.0, unit="N/m", note="chosen")
    records = claims.to_records()
    legend = legend_html(records)
    assert "<strong>reproduced</strong>" in legend and "<strong>input</strong>" in legend
    assert "<strong>rounding</strong>" not in legend  # only the statuses the chapter uses
    assert {report_column(r) for r in records} == {"reproduced", "input"}
    odd = [dict(records[0], status="approximately")]  # the control: a status no one defined
    with pytest.raises(SpringlabError, match="'approximately' has no meaning"):
        legend_html(odd)
    with pytest.raises(SpringlabError, match="'approximately' has no meaning"):
        book.report_page(["test"], {"test": {"cells": []}}, {"test": odd})


def test_the_legend_stands_above_the_chapters_first_claims_table_only():
    from springlab.workbench import book

    claims = Claims("test")
    claims.compare("a length", "Table 1", 1.0, 1.0, unit="m", tolerance=1e-9, tolerance_basis="exact")
    table = {"output_type": "display_data", "metadata": {}, "data": {"text/html": claims._repr_html_()}}
    notebook = {"cells": [{"cell_type": "code", "source": "", "outputs": []},
                          {"cell_type": "code", "source": "", "outputs": [dict(table)]},
                          {"cell_type": "code", "source": "", "outputs": [dict(table)]}]}
    shown = book.with_legend(notebook, claims.to_records())
    first, second = (c["outputs"][0]["data"]["text/html"] for c in shown["cells"][1:])
    assert first.index('class="claims-legend"') < first.index('<table class="claims">')
    assert "claims-legend" not in second and "claims-legend" not in json.dumps(notebook)  # the input untouched
    assert book.with_legend({"cells": []}, claims.to_records()) == {"cells": []}  # no table, no legend


def test_a_literal_reading_and_a_corrected_input_are_filed_as_what_they_are():
    claims = Claims("t")
    off = claims.compare("index, read literally", "Eq. (30a)", 0.5389, 0.5351, unit="-", tolerance=5e-5,
                         tolerance_basis="half a unit", expect="alternative reading", reading="sums of magnitudes")
    assert off.status == "alternative reading" and "sums of magnitudes" in off.cause
    near = claims.compare("index", "Eq. (30a)", 0.5389, 0.5389, unit="-", tolerance=5e-5, tolerance_basis="half a unit",
                          reading="sums of magnitudes")  # within the tolerance: no other reading is needed
    assert near.status == "reproduced" and near.cause == ""
    fixed = claims.compare("C, example A", "Sec. V.A", 184.0, 183.99, unit="J", tolerance=0.05, tolerance_basis="half",
                           expect="reproduced with corrected input", corrected="positions 30, 90, 150 for 30, 60, 120")
    assert fixed.cause.startswith("input corrected: positions")
    with pytest.raises(AssertionError):  # the control: a correction does not turn a miss into a reproduction
        claims.compare("C, example A", "Sec. V.A", 184.0, 150.0, unit="J", tolerance=0.05, tolerance_basis="half",
                       expect="reproduced with corrected input", corrected="positions")
    assert check_records(claims.to_records()[:3], "t") == []


def test_a_paper_value_shows_the_decimals_the_paper_prints():
    from springlab.workbench.claims import html_table, markdown_table

    c = Claims("t")
    c.compare("k", "Table 3", 2156.0, 2156.001, unit="N/m", tolerance=0.005, tolerance_basis="half a unit",
              decimals=2)
    c.compare("sigma", "Table 2", 0.0, 0.001, unit="m", tolerance=0.005, tolerance_basis="half a unit",
              rounding=0.006, band_basis="inputs rounded", printed_decimals=2)
    c.input("m", "Table 1", 1.5, 1.5, unit="kg", note="fed in", printed_decimals=2)
    c.compare("n", "Table 1", 15, 15, unit="configurations", tolerance=0, tolerance_basis="a count: exact")
    records = c.to_records()
    for table in (html_table(records), markdown_table(records)):
        assert "2156.00" in table and "0.00" in table and "1.50" in table
    # the control: a claim that does not know its printed decimals shows the number as stored
    assert [r["paper_decimals"] for r in records] == [2, 2, 2, None] and "| 15 |" in markdown_table(records)
    with pytest.raises(SpringlabError, match="printed decimals must be a whole number"):
        c.compare("k", "Table 3", 1.0, 1.0, unit="m", tolerance=0.1, tolerance_basis="b", printed_decimals=-1)
    with pytest.raises(SpringlabError, match="got 2.5"):
        c.input("m", "Table 1", 1.5, 1.5, unit="kg", note="fed in", printed_decimals=2.5)


def test_compare_printed_takes_half_a_unit_of_the_printed_digit_and_shows_those_digits():
    c = Claims("t")
    claim = c.compare_printed("r", "Section V.B", (0.125, 3), 0.12549, unit="m")
    assert claim.status == "reproduced" and claim.tolerance == 0.0005 and claim.paper_decimals == 3
    assert "(3 decimals)" in claim.tolerance_basis
    words = [c.compare_printed("n", "T", (4.0, d), 4.0, unit="-").tolerance_basis for d in (0, 1)]
    assert words == ["half a unit of the printed last digit (integers)",
                     "half a unit of the printed last digit (1 decimal)"]
    # the control: just past half a unit it is no longer reproduced
    assert c.compare_printed("r", "Section V.B", (0.125, 3), 0.12551, unit="m",
                             expect="discrepancy").status == "discrepancy"
    with pytest.raises(SpringlabError, match="printed decimals must be a whole number"):
        c.compare_printed("r", "Section V.B", (0.125, 3.5), 0.125, unit="m")
