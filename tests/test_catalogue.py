"""Stock parts: the catalogue reader against malformed files, and designs made of a catalogue's parts.

The catalogue used here is springlab's made-up series (:func:`springlab.design.catalogue.example_rows`, from
its own winding formulas), not a vendor's: it exercises the choice, it proves nothing about any vendor's parts.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from springlab.design.catalogue import (
    COLUMNS,
    CatalogueError,
    Part,
    example_rows,
    read_catalogue,
    write_catalogue,
)
from springlab.energy import geometry


def series() -> list[dict]:
    return example_rows()


def write(path, rows, columns=COLUMNS) -> str:
    return str(write_catalogue(path, rows, columns))


@pytest.fixture(scope="module")
def catalogue_file(tmp_path_factory):
    return write(tmp_path_factory.mktemp("catalogue") / "series.csv", series())


def test_reader_converts_to_si(tmp_path):
    row = {"part_number": "A-1", "outer_diameter_mm": "10", "wire_diameter_mm": "1.2", "free_length_mm": "40",
           "rate_N_per_mm": "1.5", "initial_tension_N": "5", "max_load_N": "50", "max_extended_length_mm": "70",
           "material": "music wire", "price": "2.10 USD"}
    part = read_catalogue(write(tmp_path / "c.csv", [row], (*COLUMNS, "price"))).parts[0]
    assert (part.outer_diameter, part.wire, part.free_length) == pytest.approx((0.010, 0.0012, 0.040))
    assert (part.rate, part.initial_tension, part.max_load, part.max_extended_length) == pytest.approx(
        (1500.0, 5.0, 50.0, 0.070))
    assert part.extra == {"price": "2.10 USD"} and part.row == 2
    imperial = {"part_number": "B-1", "outer_diameter_in": "0.375", "wire_diameter_in": "0.041",
                "free_length_in": "1.5", "rate_lbf_per_in": "8.5", "initial_tension_lbf": "1.2",
                "max_load_lbf": "9.7", "max_extended_length_in": "2.5"}
    part = read_catalogue(write(tmp_path / "i.csv", [imperial], tuple(imperial))).parts[0]
    assert part.rate == pytest.approx(8.5 * 4.4482216152605 / 0.0254)
    assert part.free_length == pytest.approx(1.5 * 0.0254)


GOOD = {"part_number": "A-1", "outer_diameter_mm": "10", "wire_diameter_mm": "1.2", "free_length_mm": "40",
        "rate_N_per_mm": "1.5", "initial_tension_N": "5", "max_load_N": "50", "max_extended_length_mm": "70",
        "material": "music wire"}


@pytest.mark.parametrize(("change", "columns", "says"), [
    ({}, tuple(c for c in COLUMNS if c != "rate_N_per_mm"), "column rate_N_per_mm is missing"),
    ({"rate_N_per_mm": "-1.5"}, COLUMNS, "row 2, column rate_N_per_mm: -1.5 must be positive"),
    ({"rate_N_per_mm": "nan"}, COLUMNS, "row 2, column rate_N_per_mm: 'nan' is not a finite number"),
    ({"rate_N_per_mm": "stiff"}, COLUMNS, "row 2, column rate_N_per_mm: 'stiff' is not a number"),
    ({"max_extended_length_mm": "35"}, COLUMNS, "row 2, column max_extended_length_mm: 35 is not beyond the free length"),
    ({"max_load_N": "11.2"}, COLUMNS, "row 2, column max_load_N: 11.2 is not initial tension + rate"),  # in lbf
    ({"wire_diameter_mm": "12"}, COLUMNS, "row 2, column wire_diameter_mm: the wire (12) must be thinner"),
    ({"material": "bronze"}, COLUMNS, "row 2, column material: 'bronze'"),
    ({"part_number": ""}, COLUMNS, "row 2, column part_number: empty"),
    ({"max_load_lbf": "11.2"}, (*COLUMNS, "max_load_lbf"), "inconsistent units: columns outer_diameter_mm and "
                                                            "max_load_lbf mix metric and imperial"),
])
def test_reader_refuses_a_malformed_file(tmp_path, change, columns, says):
    path = write(tmp_path / "bad.csv", [GOOD | change], columns)
    with pytest.raises(CatalogueError) as err:
        read_catalogue(path)
    assert says in str(err.value) and "\n" not in str(err.value)
    assert "bad.csv" in str(err.value)


def test_reader_refuses_empty_and_repeated(tmp_path):
    (tmp_path / "empty.csv").write_text("")
    with pytest.raises(CatalogueError, match="is empty"):
        read_catalogue(tmp_path / "empty.csv")
    with pytest.raises(CatalogueError, match="has a header but no parts"):
        read_catalogue(write(tmp_path / "header.csv", []))
    with pytest.raises(CatalogueError, match="row 3, column part_number: A-1 is already row 2's"):
        read_catalogue(write(tmp_path / "twice.csv", [GOOD, GOOD]))
    with pytest.raises(CatalogueError, match="cannot be read"):
        read_catalogue(tmp_path / "absent.csv")
    good = read_catalogue(write(tmp_path / "good.csv", [GOOD]))  # the control: the same row, once, reads
    assert len(good) == 1


def test_stock_spring_is_the_catalogues_part():
    part = Part("A-1", 0.010, 0.0012, 0.040, 1500.0, 5.0, 50.0, 0.070)
    spring = part.spring(0.060)
    assert (spring.rate, spring.free_length, spring.initial_tension) == (1500.0, 0.040, 5.0)
    assert spring.force(0.060) == pytest.approx(5.0 + 1500.0 * 0.020)
    assert spring.mean_diameter == pytest.approx(0.0088) and spring.mass > 0
    assert spring.problems() == []  # within the vendor's limits
    over = part.spring(0.075)  # the negative control: stretched past its largest extension and load
    assert len(over.problems()) == 2 and "past its catalogue's largest extension 70.0 mm" in over.problems()[0]


@pytest.fixture(scope="module")
def stocked(catalogue_file):
    from springlab.design.arms import design_model
    from springlab.model.robots import load_robot

    catalogue = read_catalogue(catalogue_file)
    return catalogue, design_model(load_robot("double pendulum"), pulley_radius=None, layout="belts", samples=200,
                                   audit_samples=100, catalogue=catalogue)


def _removed(design) -> np.ndarray:
    """Per loaded joint, the share (%) of its peak the realised springs remove with their own mass carried."""
    peak = np.max(np.abs(geometry.gravity_torques(design.massed, design.q)), axis=0)
    left = np.max(np.abs(geometry.joint_torques(design.massed, design.realised, design.q)), axis=0)
    return (100 * (1 - left / peak))[list(design.structure.loaded)]


def test_design_from_stock_parts(stocked):
    catalogue, design = stocked
    numbers = {p.part_number: p for p in catalogue}
    parts = [getattr(fit.coil, "part", None) for fit in design.coils]
    assert all(p is not None and p.part_number in numbers for p in parts)  # every spring a catalogue part
    assert not design.flags(), design.flags()
    assert np.all(_removed(design) >= 95.0)
    for r, fit in zip(design.realised, design.coils, strict=True):  # the spring law: k / ratio^2 of the part's,
        part = fit.coil.part  # at its free length where the cable's path is ratio F_i / k
        assert r.k == pytest.approx(part.rate / fit.ratio**2, rel=1e-12)
        assert r.initial_tension == pytest.approx(part.initial_tension / fit.ratio, rel=1e-12)
        low, high = fit.forces()
        assert fit.coil.free_length <= fit.coil_length(fit.span[0]) and high <= part.max_load
    record = design.as_dict()
    for spring in record["realised"]:
        part = numbers[spring["part_number"]]
        assert (spring["part"]["k"], spring["part"]["free_length"], spring["part"]["initial_tension"]) == (
            part.rate, part.free_length, part.initial_tension)
    bought = [row[2] for row in design.bom().rows if "extension spring" in row[2]]
    assert bought and all("stock extension spring T-" in what for what in bought)
    table = design.stock_table()
    assert [row[1] for row in table.rows] == [p.part_number for p in parts]


def test_stock_choice_no_worse_than_the_nearest_single_part(stocked, tmp_path):
    """The choice among the catalogue against a catalogue holding only the part nearest each spring's rate alone
    (one part, no block): the choice balances at least as well."""
    from springlab.design.arms import design_model
    from springlab.model.robots import load_robot

    catalogue, design = stocked
    nearest = set()
    for s in design.ideal:
        nearest.add(min(catalogue, key=lambda p: abs(np.log(p.rate / s.k))).part_number)
    rows = [row for row in series() if row["part_number"] in nearest]
    alone = read_catalogue(write(tmp_path / "nearest.csv", rows))
    single = design_model(load_robot("double pendulum"), pulley_radius=None, layout="belts", samples=200,
                          audit_samples=100, catalogue=alone)
    assert np.all(_removed(design) >= _removed(single) - 0.05)


def test_a_catalogue_with_no_fitting_part_falls_back(tmp_path, stocked):
    """A catalogue of parts far too weak: each spring is wound to order and says why."""
    from springlab.design.arms import design_model
    from springlab.model.robots import load_robot

    catalogue, design = stocked
    weak = [row for row in series() if row["max_load_N"] < 12][:3]
    single = design_model(load_robot("double pendulum"), pulley_radius=None, layout="belts", samples=200,
                          audit_samples=100, catalogue=read_catalogue(write(tmp_path / "weak.csv", weak)))
    assert all(getattr(fit.coil, "part", None) is None for fit in single.coils)
    assert all("custom-wound (no part of the catalogue fits: " in kind for kind in single.kinds)
    assert all(row[1] == "none: wound to order" for row in single.stock_table().rows)


def test_a_stock_part_past_its_limits_is_flagged(stocked):
    """The negative control of the vendor's limits: the same design with one part listed shorter than it is
    stretched is flagged, naming the part."""
    _, design = stocked
    fit = design.coils[0]
    short = replace(fit.coil.part, max_extended_length=0.9 * fit.coil.max_length, max_load=1e3)
    spoiled = replace(design, coils=(fit._replace(coil=replace(fit.coil, part=short)), *design.coils[1:]))
    flags = [f for f in spoiled.hardware_flags() if "stock part" in f]
    assert len(flags) == 1 and short.part_number in flags[0] and not [
        f for f in design.hardware_flags() if "stock part" in f]


def test_cli_refuses_a_bad_catalogue(tmp_path, capsys):
    """A malformed catalogue: one line naming the row and column, exit 2, nothing written; --catalog with no
    file: springlab ships none yet."""
    from springlab.model.robots import robot_urdf
    from springlab.workbench.cli import main

    urdf = robot_urdf("double pendulum")
    bad = write(tmp_path / "bad.csv", [GOOD | {"rate_N_per_mm": "-1"}])
    out = tmp_path / "d.json"
    for given, says in (([bad], "row 2, column rate_N_per_mm"), ([], "ships no vendor's catalogue")):
        capsys.readouterr()
        assert main(["design", str(urdf), "--catalog", *given, "--json", str(out), "--quiet"]) == 2
        err = capsys.readouterr().err
        assert says in err and len(err.strip().splitlines()) == 1
        assert not out.exists()
