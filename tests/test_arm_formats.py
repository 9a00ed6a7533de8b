"""Arms as users describe them, and results where engineers keep them: units by pint, CSV out."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

from springlab import Spring
from springlab.design.rank import design_arm
from springlab.energy import geometry
from springlab.errors import SpringlabError
from springlab.model.armfile import load_arm
from springlab.model.chain import random_directions
from springlab.workbench.cli import main

ARMS = Path(__file__).resolve().parents[1] / "notebooks" / "arms"


@pytest.fixture(scope="module")
def paper_report():
    return design_arm(load_arm(ARMS / "paper000_arm.toml"), method="no auxiliary links", max_designs=3,
                      minimise_force=False)


def test_the_csv_holds_every_ranked_design_and_its_springs_balance(paper_report):
    rows = list(csv.DictReader(io.StringIO(paper_report.csv())))
    assert len(rows) == len(paper_report.designs) == 3
    chain = paper_report.spec.chain()
    X = random_directions(chain.n, 300, np.random.default_rng(0))
    for row, design in zip(rows, paper_report.designs, strict=True):
        assert row["configuration"] == design.label() and float(row["max_force_N"]) == design.max_force
        springs = []
        for idx in range(1, int(row["springs"]) + 1):
            i, j = (int(x) for x in row[f"spring{idx}_slot"].strip("S()").split(","))
            springs.append(Spring(i, j, float(row[f"spring{idx}_a_m"]), float(row[f"spring{idx}_b_m"]),
                                  float(row[f"spring{idx}_k_N_per_m"])))
        assert springs == list(design.springs)  # full precision: the same springs
        variation = np.ptp(geometry.total_energy(chain, springs, X)) / np.ptp(geometry.gravity_energy(chain, X))
        assert variation < 1e-8  # route 2: the springs read back from the CSV balance the arm
        spoiled = [s.scaled(0.9) for s in springs]
        assert np.ptp(geometry.total_energy(chain, spoiled, X)) > 1e-3 * np.ptp(geometry.gravity_energy(chain, X))


def test_cli_writes_the_csv_and_checks_its_path_first(tmp_path, capsys):
    out = tmp_path / "ranked.csv"
    code = main(["design", str(ARMS / "paper000_arm.toml"), "--json", str(tmp_path / "d.json"), "--method",
                 "ground springs", "--max-designs", "1", "--quiet", "--csv", str(out)])
    assert code == 0, capsys.readouterr().err
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    assert len(rows) == 1 and rows[0]["spring1_slot"].startswith("S(1,") and rows[0]["family"] == "ground springs"
    code = main(["design", str(ARMS / "paper000_arm.toml"), "--csv", str(tmp_path / "no" / "r.csv")])
    assert code == 2 and "--csv" in capsys.readouterr().err and not (tmp_path / "no").exists()


def test_units_in_an_arm_file_by_pint():
    from springlab.model.armfile import arm_from_dict

    metric = load_arm(ARMS / "paper000_arm.toml")
    other = arm_from_dict({"name": metric.name, "g": "980 cm/s^2", "link": [
        {"length": "30 cm", "com": "150 mm", "mass": "4000 g"}, {"length": "240 mm", "com": "0.012 dam", "mass": "3.2 kg"},
        {"length": "0.2 m", "com": "100 mm", "mass": "2800 g"}], "limits": {"max_stiffness": "5 N/mm",
        "max_attachment": "300 mm"}, "workspace": {"samples": 2000, "seed": 1}})
    for key in ("r", "d", "m"):
        assert getattr(other, key) == pytest.approx(getattr(metric, key), rel=1e-12)
    assert (other.g, other.max_stiffness, other.max_attachment) == pytest.approx(
        (metric.g, metric.max_stiffness, metric.max_attachment), rel=1e-12)
    with pytest.raises(SpringlabError, match="limits: max_stiffness = '3 lbf' is a force, not a stiffness"):
        arm_from_dict({"link": [{"length": "12 in", "com": "6 in", "mass": "4 lb"}], "limits": {"max_stiffness": "3 lbf"}})
    spec = arm_from_dict({"link": [{"length": "12 in", "com": "6 in", "mass": "4 lb"}], "g": "1 g0",
                          "limits": {"max_stiffness": "30 lbf/in"}})
    assert spec.r == pytest.approx((12 * 0.0254,), rel=1e-12) and spec.m == pytest.approx((4 * 0.45359237,), rel=1e-12)
    assert spec.g == 9.80665 and spec.max_stiffness == pytest.approx(30 * 4.4482216152605 / 0.0254, rel=1e-12)


def test_the_cli_starts_in_under_a_second_of_units():
    # pint's registry is made on first use only: an arm file of SI numbers never pays for it,
    # and with pint's cache a unit costs well under a second (measured: see the README)
    import subprocess
    import sys

    code = ("import time, springlab.model.armfile as a; t = time.perf_counter(); a.parse_quantity('400 mm', 'length', 'x');"
            " print(time.perf_counter() - t)")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)  # fills pint's cache
    seconds = float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout)
    assert seconds < 1.0
