"""Cables a maker buys, the pulleys sized to them and pulley blocks (springlab.design.cables,
springlab.design.layouts.coil_for, springlab.design.buildable.Fitted), with negative controls."""

import numpy as np
import pytest

from springlab.design.buildable import Fitted, cable_spring
from springlab.design.cables import CABLES, SAFETY, cable_by_name, choose_cable, pulley_mass
from springlab.design.layouts import coil_for
from springlab.errors import SpringlabError
from springlab.model.robots import robot_urdf
from springlab.workbench.cli import main


def test_a_cable_carries_its_pull_five_times_over_on_the_least_pulley():
    for pull in (1.0, 30.0, 100.0, 400.0, 3000.0):
        cable = choose_cable(pull)
        assert cable.breaking >= SAFETY * pull
        cheaper = [c for c in CABLES if c.pulley_diameter < cable.pulley_diameter]
        assert all(c.breaking < SAFETY * pull for c in cheaper)  # no smaller pulley's cable carries it
        assert cable.pulley_diameter >= cable.ratio * cable.diameter  # the rope maker's D/d, up to a whole mm
        assert cable.pulley_radius == pytest.approx((cable.pulley_diameter + cable.diameter) / 2)
    with pytest.raises(SpringlabError, match="no stocked cable"):  # the control: past the strongest
        choose_cable(CABLES[-1].working * 1.01)
    with pytest.raises(SpringlabError, match="runs over it"):  # a pulley no cable fits
        choose_cable(1.0, pulley_radius=0.005)
    assert choose_cable(1.0, pulley_radius=0.03).fits(0.03)


def test_a_pulley_block_keeps_the_cable_a_zero_free_length_spring():
    # over an n:1 block the coil moves path / n and pulls n times the cable: the cable's pull is k * path
    k, paths = 800.0, (0.12, 0.40)
    for n in (1, 2, 3):
        coil, _ = cable_spring(k * n * n, np.asarray(paths) / n)
        fit = Fitted(coil, paths, n)
        x = np.linspace(*paths, 7)
        pull = coil.force(fit.coil_length(x)) / n
        np.testing.assert_allclose(pull, k * x, rtol=1e-9)
        assert coil.max_length == pytest.approx(float(fit.coil_length(paths[1])), rel=1e-9)
    one, _ = cable_spring(k, paths)
    two, _ = cable_spring(4 * k, np.asarray(paths) / 2)
    assert two.max_length < one.max_length  # the block shortens the coil


def test_a_coil_too_long_for_its_link_takes_a_block_and_where_none_fits_stays_single():
    k, paths = 800.0, (0.12, 0.40)
    alone, _ = cable_spring(k, paths)
    coil, ratio, parallel = coil_for(k, paths, np.inf, "music wire")
    assert (ratio, parallel) == (1, 1)  # room enough: the coil alone
    coil, ratio, parallel = coil_for(k, paths, 0.8 * alone.max_length, "music wire")
    assert coil.max_length <= 0.8 * alone.max_length and (ratio > 1 or parallel > 1)
    coil, ratio, parallel = coil_for(k, paths, 1e-3, "music wire")  # nothing fits a millimetre
    assert parallel == 1 and coil.max_length > 1e-3  # the fewest side by side: the flags say it is too long


def test_chrome_silicon_saves_a_coil_where_music_wire_needs_two_and_never_costs_one():
    # a UR5 shoulder's spring: 1,215 N/m over a 0.49-0.58 m path, 0.6 m of room; music wire (to 6.5 mm) needs
    # coils side by side at every block, chrome silicon (to 9.5 mm, ASTM A401) winds one
    k, paths, room = 1215.0, (0.49, 0.578), 0.6
    music = coil_for(k, paths, room, "music wire", block=0.06)
    auto = coil_for(k, paths, room, "auto", block=0.06)
    assert music[2] >= 2 and auto[2] == 1 and auto[0].material == "chrome silicon"
    assert auto[0].max_length <= room - 0.06
    for k, paths in ((50.0, (0.1, 0.3)), (800.0, (0.12, 0.40)), (3000.0, (0.2, 0.3))):  # auto is never worse
        music, auto = coil_for(k, paths, 0.3, "music wire"), coil_for(k, paths, 0.3, "auto")
        assert (auto[2], auto[1]) <= (music[2], music[1])  # (coils side by side, block)
    with pytest.raises(SpringlabError, match="material = 'brass'"):
        coil_for(k, paths, room, "brass")


def test_a_pulley_is_lighter_than_its_cable_is_strong():
    masses = [pulley_mass(c, c.pulley_radius) for c in CABLES]
    assert all(0 < m < 1.0 for m in masses) and masses[0] < masses[-1]


def test_a_cable_is_named_by_its_diameter_and_a_bad_one_refused():
    assert cable_by_name("1.59") is cable_by_name("1.59 mm") is CABLES[4]
    with pytest.raises(SpringlabError, match="cable = '1.6'"):
        cable_by_name("1.6")


@pytest.mark.parametrize("bad, word", [(["--cable", "2.38", "--pulley-radius", "10 mm"], "--cable"),
                                       (["--cable", "7"], "--cable"), (["--target", "0"], "--target"),
                                       (["--target", "1.5"], "--target"), (["--margin", "-1 mm"], "--margin")])
def test_the_cli_refuses_a_cable_its_pulley_cannot_take_and_a_bad_target(tmp_path, capsys, bad, word):
    out = tmp_path / "x.json"
    assert main(["design", str(robot_urdf("UR5")), *bad, "--json", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert word in err and err.count("\n") == 1 and not out.exists()


def test_a_bracket_foot_gets_the_least_bolt_pattern_that_holds_it():
    from springlab.design.hardware import BOLT_PROOF, BOLT_SAFETY, BOLTS, bolt_pattern

    # the pattern named holds: the outer bolt's F / 2 + M / s within its proof load over the safety factor
    for force, moment in ((50.0, 2.0), (400.0, 30.0), (2000.0, 150.0)):
        said = bolt_pattern(force, moment)
        name, spacing = said.split(" ")[2], float(said.split("least ")[1].split(" mm")[0]) * 1e-3
        _, d, area = next(b for b in BOLTS if b[0] == name)
        assert force / 2 + moment / spacing <= area * BOLT_PROOF / BOLT_SAFETY
        assert 3 * d <= spacing <= 10 * d + 1e-3
        smaller = [b for b in BOLTS if b[1] < d]  # and no smaller bolt would do within ten diameters
        assert all(force / 2 + moment / (10 * db) > ab * BOLT_PROOF / BOLT_SAFETY for _, db, ab in smaller)
    assert "pattern of its own" in bolt_pattern(2e4, 2e3)  # the control: past two M12s, no pattern is claimed
