"""From ideal to buildable springs: the extension-spring formulas, the two realisations, the
pulley's route-2 model, the balance the built springs leave, checked in exudyn, and the spec sheet."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from springlab import Spring
from springlab.design import buildable as bd
from springlab.design.rank import design_arm, workspace_poses
from springlab.energy import geometry, pulley, simulation
from springlab.energy.quadratic import spring_matrix
from springlab.errors import SpringlabError
from springlab.model.armfile import load_arm
from springlab.model.chain import random_directions
from springlab.workbench.cli import main

PAPER_ARM = Path(__file__).resolve().parents[1] / "notebooks" / "arms" / "paper000_arm.toml"


@pytest.fixture(scope="module")
def paper_arm():
    spec = load_arm(PAPER_ARM)
    chain = spec.chain()
    report = design_arm(spec, max_designs=1, progress=False)
    X = workspace_poses(spec, chain)
    return chain, report.designs[0].springs, X


def test_textbook_formulas():
    # Shigley, Section 10-2: K_W at C = 8 is 1.184; the preferred initial tension at C = 6 is 125-175 MPa
    assert bd.wahl_factor(8.0) == pytest.approx(1.1840, abs=5e-4)
    lo, hi = bd.initial_tension_stress_range(6.0)
    assert lo / 1e6 == pytest.approx(231 * np.exp(-0.63) - 6.9 * (4 - 3 / 6.5))
    assert hi / 1e6 == pytest.approx(231 * np.exp(-0.63) + 6.9 * (4 - 3 / 6.5))
    # S_ut of 1 mm music wire is A = 2211 MPa; of 2 mm, 2211 / 2^0.145
    mw = bd.MATERIALS["music wire"]
    assert mw.tensile_strength(1e-3) == pytest.approx(2211e6)
    assert mw.tensile_strength(2e-3) == pytest.approx(2211e6 / 2**0.145)
    spring = bd.ExtensionSpring("music wire", 1e-3, 8e-3, 20.0, 5.0, 0.1)
    G, E = mw.moduli_at(1e-3)
    assert spring.rate == pytest.approx(1e-12 * G / (8 * 512e-9 * (20 + G / E)))
    assert spring.free_length == pytest.approx((2 * 8 - 1 + 20) * 1e-3)
    with pytest.raises(SpringlabError, match="C"):
        bd.wahl_factor(0.5)
    with pytest.raises(SpringlabError, match="outside"):
        mw.tensile_strength(20e-3)


def test_zero_length_needs_more_initial_tension_than_makers_wind():
    spring, why = bd.zero_length_spring(300.0, (0.1, 0.4))
    assert spring is None and "MPa" in why and "makers wind at most" in why
    # a maker who winds three to five times the preferred range can make one: its force is k l exactly
    spring, why = bd.zero_length_spring(200.0, (0.3, 0.5), tension_scale=5.0)
    assert spring is not None and why == ""
    length = np.linspace(spring.free_length, spring.max_length, 50)
    assert np.allclose(spring.force(length), spring.rate * length, rtol=0, atol=1e-12 * spring.max_force)
    assert spring.rate == pytest.approx(200.0, rel=1e-12)
    assert spring.stress(spring.max_force) <= spring.allowable_stress
    assert any("above the windable" in p for p in spring.problems())  # the sheet says it is not standard winding
    with pytest.raises(SpringlabError, match="coils are closed"):
        spring.force(0.5 * spring.free_length)


def test_overstressed_springs_are_rejected():
    spring = bd.ExtensionSpring("music wire", 1e-3, 10e-3, 20.0, 2.0, 5.0)  # stretched to 5 m
    assert any("stress" in p and f"above {100 * bd.STRESS_SHARE:.0f} % of the allowable" in p for p in spring.problems())
    ok = bd.ExtensionSpring("music wire", 1e-3, 10e-3, 20.0, 3.0, spring.free_length + 0.01)  # F_i in 2.38-3.97 N
    assert ok.problems() == []
    coil, why = bd.cable_spring(2e3, (0.1, 100.0))  # 200 kN: no stocked wire carries it
    assert coil is None and "stress" in why
    chain = load_arm(PAPER_ARM).chain()
    with pytest.raises(SpringlabError, match=r"S\(1,2\).*no cable spring"):
        bd.realise(chain, [Spring(1, 2, 0.2, 0.2, 1e6)], random_directions(chain.n, 20, 0))


def test_cable_springs_of_a_design_fit_and_their_sheet_reproduces_k_l(paper_arm):
    chain, springs, X = paper_arm
    built = bd.realise(chain, springs, X)
    rows = list(csv.DictReader(io.StringIO(bd.sheet_csv(built))))
    assert len(rows) == len(springs)
    for r, row in zip(built, rows, strict=True):
        assert r.kind == "cable over a pulley" and "makers wind at most" in r.note
        # what a maker checks: stress within the share designed to; an initial tension below the windable
        # range is flagged (problems, and the sheet's note names the process), never silently off the table
        lo, hi = r.coil.initial_tension_range
        assert r.coil.stress(r.coil.max_force) <= bd.STRESS_SHARE * r.coil.allowable_stress * (1 + 1e-9)
        below = r.coil.initial_tension < lo * (1 - 1e-9)
        assert [p for p in r.coil.problems() if "below the windable" not in p] == []
        assert below == any("below the windable" in p for p in r.coil.problems())
        assert below == ("stress-relieve" in row["maker's note"])
        assert r.coil.initial_tension <= hi
        assert r.built().effective_free_length == pytest.approx(0.0, abs=1e-12)
        # the spring rebuilt from the sheet's rounded numbers pulls k times the path to 1 %
        coil = bd.ExtensionSpring("music wire", float(row["wire d (mm)"]) / 1e3, float(row["mean coil D (mm)"]) / 1e3,
                                  float(row["body coils"]), float(row["initial tension (N)"]),
                                  float(row["longest in service (mm)"]) / 1e3)
        offset = float(row["cable offset L0 - Fi/k (mm)"]) / 1e3
        path, _ = pulley.cable_path(chain, r.spring, X, r.pulley_radius)
        force = coil.force(path + offset)
        assert np.max(np.abs(force / (r.spring.k * path) - 1)) < 0.01


def test_pulley_route2_is_the_energy_gradient_and_vanishes_with_the_radius(paper_arm):
    chain, springs, X = paper_arm
    X = X[:6]
    plain = geometry.holding_torques(chain, springs, X)
    assert np.abs(pulley.holding_torques_with_pulleys(chain, springs, [0.0] * len(springs), X) - plain).max() < 1e-12
    radii = [0.02, None, 0.01, 0.015][:len(springs)]
    tau = pulley.holding_torques_with_pulleys(chain, springs, radii, X)

    def energy(Y):
        out = geometry.gravity_energy(chain, Y)
        for s, rho in zip(springs, radii, strict=True):
            out = out + (geometry.spring_energy(chain, [s], Y) if rho is None else pulley.cable_energy(chain, s, Y, rho))
        return out

    h, worst = 1e-6, 0.0
    for j in range(2, chain.n + 1):
        for axis in np.eye(3):
            R = Rotation.from_rotvec(h * axis).as_matrix()
            up, down = X.copy(), X.copy()
            up[:, j - 1:] = X[:, j - 1:] @ R.T
            down[:, j - 1:] = X[:, j - 1:] @ R
            worst = max(worst, np.abs((energy(up) - energy(down)) / (2 * h) - tau[:, j - 2] @ axis).max())
    assert worst < 1e-6 * np.abs(tau).max()
    assert np.abs(tau - plain).max() > 1e-3  # the pulley does move the balance (a check that can fail)
    with pytest.raises(SpringlabError, match="pulley's radius"):
        pulley.cable_path(chain, springs[0], X, 10.0)


def test_balance_loss_grows_with_the_pulley_and_the_tolerances(paper_arm):
    chain, springs, X = paper_arm
    X = X[:200]
    small = bd.balance_loss(chain, bd.realise(chain, springs, X, pulley_radius=0.002), X)
    large = bd.balance_loss(chain, bd.realise(chain, springs, X, pulley_radius=0.01), X)
    rows = dict(large.rows)
    assert rows["as designed (ideal springs)"] < 1e-10 * large.gravity
    assert 0 < dict(small.rows)["as specified"] < rows["as specified"] < large.gravity
    assert rows["tension +10 %"] != rows["tension -10 %"]
    assert "%" in large.table().markdown()
    point = bd.balance_loss(chain, bd.realise(chain, springs, X, pulley_radius=0.0), X)
    assert dict(point.rows)["as specified"] < 1e-9 * point.gravity  # point pulleys: the cable emulates k l exactly


def test_built_springs_route2_matches_exudyn(paper_arm):
    """The residual of real springs (free length and initial tension modelled in exudyn's
    spring-damper, initial tension 10 % high) by route 2 and by exudyn's statics, to 1e-6 N m."""
    chain, springs, X = paper_arm
    built = bd.realise(chain, springs, X, pulley_radius=0.0)
    real = [r.built(tension=1.1) for r in built]
    assert all(s.free_length > 0 and s.initial_tension > 0 for s in real)
    poses = X[:4]
    result = simulation.holding_torques(chain, real, poses)
    assert result.max_difference < 1e-6
    gravity = np.abs(geometry.holding_torques(chain, [], poses)).max()
    assert 1e-3 * gravity < np.abs(result.simulated).max() < gravity  # a residual, smaller than gravity's
    ideal = simulation.holding_torques(chain, springs, poses)
    assert np.abs(ideal.simulated).max() < 1e-6 and np.abs(result.simulated - ideal.simulated).max() > 1e-3


def test_initial_tension_is_a_spring_field():
    s = Spring(1, 2, 0.1, 0.2, 100.0, free_length=0.05, initial_tension=8.0)
    assert s.effective_free_length == pytest.approx(-0.03) and not s.ideal
    assert s.scaled(0.9).initial_tension == pytest.approx(7.2)
    with pytest.raises(SpringlabError, match="initial_tension"):
        Spring(1, 2, 0.1, 0.2, 100.0, initial_tension=-1.0)
    chain = load_arm(PAPER_ARM).chain()
    with pytest.raises(SpringlabError, match="zero-free-length"):
        spring_matrix(chain, Spring(1, 2, 0.1, 0.2, 100.0, initial_tension=1.0))
    X = random_directions(chain.n, 30, 1)
    # F_i + k (l - L_0) is the spring of free length L_0 - F_i / k (route 2)
    a = geometry.holding_torques(chain, [s], X)
    b = geometry.holding_torques(chain, [Spring(1, 2, 0.1, 0.2, 100.0, initial_tension=3.0)], X)
    assert np.abs(a - b).max() < 1e-12


def test_cli_writes_the_sheet(tmp_path, capsys):
    out = tmp_path / "arm.design.json"
    code = main(["design", str(PAPER_ARM), "--json", str(out), "--max-designs", "1", "--quiet", "--sheet"])
    assert code == 0, capsys.readouterr().err
    sheet = (tmp_path / "arm.sheet.csv").read_text()
    rows = list(csv.DictReader(io.StringIO(sheet)))
    assert len(rows) == len(json.loads(out.read_text())["springs"])
    md = (tmp_path / "arm.sheet.md").read_text()
    assert "| spring |" in md and "as specified" in md and "largest force (N)" in md
    code = main(["design", str(PAPER_ARM), "--json", str(out), "--sheet", "--pulley-radius", "-1"])
    assert code == 2 and "--pulley-radius" in capsys.readouterr().err


def test_clearance_flags_a_spring_through_a_link():
    from springlab import serial_chain
    from springlab.design.clearance import clearance, segment_distance

    rng = np.random.default_rng(0)
    P0, P1, Q0, Q1 = (rng.normal(size=(100, 3)) for _ in range(4))
    s = np.linspace(0, 1, 301)
    brute = [np.min(np.linalg.norm((P0[k] + s[:, None] * (P1[k] - P0[k]))[:, None]
                                   - (Q0[k] + s[:, None] * (Q1[k] - Q0[k]))[None], axis=2)) for k in range(100)]
    d = segment_distance(P0, P1, Q0, Q1)
    assert np.all(d <= np.array(brute) + 1e-12) and np.max(np.array(brute) - d) < 1e-3
    chain = serial_chain([0.4, 0.3], [0.2, 0.15], [2.0, 1.0])
    up, side = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    spring = Spring(1, 3, 0.2, 0.2, 100.0)  # A on the column 0.2 m above the base, B 0.2 m along link 3
    folded = np.array([[up, up, side]])  # link 2 vertical: A lies on it
    bent = np.array([[up, side, up]])  # link 2 horizontal, the spring 0.2 m above and parallel to it
    crossing = clearance(chain, [spring], folded)
    assert crossing.crossing and crossing.per_spring()["S(1,3)(+,+)"][1] == 2
    clear = clearance(chain, [spring], bent, link_radii=0.02)
    assert not clear.crossing and clear.per_spring()["S(1,3)(+,+)"][0] == pytest.approx(0.2 - 0.02)
    assert clearance(chain, [spring], bent, link_radii=0.02, spring_radii=[0.19]).crossing  # a fat spring touches
    with pytest.raises(SpringlabError, match="link_radii"):
        clearance(chain, [spring], bent, link_radii=[0.1, 0.1, 0.1])


def test_bad_spring_specs_are_refused():
    with pytest.raises(SpringlabError, match="material"):
        bd.ExtensionSpring("cheese", 1e-3, 8e-3, 10.0, 1.0, 0.1)
    with pytest.raises(SpringlabError, match="wire"):
        bd.ExtensionSpring("music wire", float("nan"), 8e-3, 10.0, 1.0, 0.1)
    with pytest.raises(SpringlabError, match="mean_diameter"):
        bd.ExtensionSpring("music wire", 2e-3, 1e-3, 10.0, 1.0, 0.1)
    with pytest.raises(SpringlabError, match="lengths"):
        bd.cable_spring(100.0, (0.5, 0.1))


def test_joint_limits_shape_the_workspace_and_crossing_designs_rank_last(tmp_path):
    from dataclasses import replace

    from springlab.design.rank import rank_key, workspace_note
    from springlab.model.armfile import arm_from_dict
    from springlab.model.chain import bend_angles

    link = {"length": "300 mm", "com": "150 mm", "mass": "4 kg"}
    data = {"link": [link | {"cone": "60 deg", "radius": "30 mm"}, link | {"cone": "90 deg"}, link]}
    spec = arm_from_dict(data, source="limited")
    assert spec.limits[0] == pytest.approx(np.pi / 3) and spec.limits[2] is None
    assert spec.link_radii == (0.03, 0.025, 0.025)
    X = workspace_poses(spec, spec.chain())
    bends = np.degrees(bend_angles(X))
    assert bends[:, 0].max() <= 60 + 1e-9 and bends[:, 1].max() <= 90 + 1e-9 and bends[:, 2].max() > 150
    assert "cone 60 deg" in workspace_note(spec)
    revolute = {"link": [link | {"joint": [0, 0, 1], "range": ["-30 deg", "45 deg"]}, link | {"joint": [0, 0, 1]}]}
    angles = np.degrees(bend_angles(workspace_poses(arm_from_dict(revolute), arm_from_dict(revolute).chain())))
    assert angles[:, 0].max() <= 45 + 1e-9  # planar: the bend is the joint angle's size
    for bad, match in (({"cone": "60 deg", "joint": [0, 0, 1]}, "cone limits a spherical joint"),
                       ({"range": ["0 deg", "10 deg"]}, "range limits a revolute joint"),
                       ({"cone": "200 deg"}, "half-angle"), ({"cone": "60 kg"}, "is a mass, not an angle"),
                       ({"joint": [0, 0, 1], "range": ["10 deg", "0 deg"]}, "low < high")):
        with pytest.raises(SpringlabError, match=match):
            arm_from_dict({"link": [link | bad, link]})
    report = design_arm(spec, max_designs=2)
    assert "within the joint limits" in report.notes[0] and "clearance (mm)" in report.table().headers
    crossing, clear = report.designs[0], replace(report.designs[0], clearance=0.01, max_force=1e9)
    assert crossing.crosses and not clear.crosses
    assert sorted([crossing, clear], key=rank_key)[0] is clear  # a spring through a link ranks last


def test_a_cable_spring_longer_than_its_link_is_flagged():
    spec = load_arm(PAPER_ARM)
    chain = spec.chain()
    X = workspace_poses(spec, chain)[:300]
    springs = design_arm(spec, method="no auxiliary links", max_designs=1).designs[0].springs
    built = bd.realise(chain, springs, X)
    for r in built:
        if r.spring.i == 1:
            assert r.room is None and r.fits  # on the base column
        else:
            assert r.room == pytest.approx(chain.length(r.spring.i) + r.spring.a)
            assert r.fits == (r.coil.max_length <= r.room)
    assert not all(r.fits for r in built)  # the paper-000 arm's link-2 springs outgrow link 2
    assert "too short" in bd.sheet_csv(built)


def test_a_cable_springs_initial_tension_is_windable_or_flagged():
    """A maker's check: the initial tension lies in the windable range where a stocked wire allows it;
    where the force at the shortest path is too small for any wire's range, the spring is wound below
    it and flagged with the process that reaches it; the stress stays within the share designed to."""
    coil, why = bd.cable_spring(300.0, (0.2, 0.5))
    lo, hi = coil.initial_tension_range
    assert why == "" and lo <= coil.initial_tension <= hi and coil.problems() == []
    assert coil.stress(coil.max_force) <= bd.STRESS_SHARE * coil.allowable_stress
    slack, _ = bd.cable_spring(200.8, (0.032, 0.675))  # 6.4 N at the shortest path, 136 N at the longest
    assert slack.initial_tension < slack.initial_tension_range[0]
    assert any("stress-relieved" in p for p in slack.problems())


KPSI, INCH, LBF = 6.894757e6, 0.0254, 4.4482216


def test_hook_and_fatigue_formulas_reproduce_shigleys_worked_extension_spring(monkeypatch):
    # Shigley (10th ed.), Examples 10-7 and 10-8: hard-drawn wire (ASTM A227, S_ut = 140 kpsi / d^0.190), d 0.035 in,
    # OD 0.248 in, hook radii r1 0.106 in and r2 0.089 in. At 5.25 lbf the book's hook stresses are 156.9 kpsi
    # bending at A and 78.4 kpsi torsion at B (with (K)_B rounded to 1.18; unrounded 1.184 gives 78.7); cycled
    # from 1.5 to 5 lbf, its Gerber factors against Zimmerli's endurance are 1.08 (hook bending) and 1.30
    # (hook torsion), and 1.24 for the body with Bergstrasser's factor, where springlab takes Wahl's (1.1 %
    # higher at C = 6.09: 1.22)
    wire = bd.Material("hard-drawn", "ASTM A227", ((0.7, 12.7, 1783.0, 0.190),), ((1e9, 79.3e9, 196.5e9),), 0.45, (0.9,))
    monkeypatch.setitem(bd.MATERIALS, "hard-drawn", wire)
    d, od = 0.035 * INCH, 0.248 * INCH
    spring = bd.ExtensionSpring("hard-drawn", d, od - d, 12.17, 1.19 * LBF, 0.03)
    hooks = dict(r1=0.106 * INCH, r2=0.089 * INCH)
    bending, torsion = spring.hook_stresses(5.25 * LBF, **hooks)
    assert bending / KPSI == pytest.approx(156.9, rel=2e-3)  # the book's three figures; S_ut from metric A, m
    assert torsion / KPSI == pytest.approx(78.4, rel=5e-3)  # the book's rounded (K)_B
    factors = spring.fatigue(1.5 * LBF, 5.0 * LBF, **hooks)
    assert factors["hook bending"] == pytest.approx(1.08, abs=0.01)
    assert factors["hook torsion"] == pytest.approx(1.30, abs=0.015)
    assert factors["body"] == pytest.approx(1.24, rel=0.02)  # Wahl for Bergstrasser
    assert spring.fatigue(5.0 * LBF, 5.0 * LBF, **hooks)["body"] == np.inf  # no cycle, no fatigue
    with pytest.raises(SpringlabError, match="high = 1 N is below low"):
        spring.fatigue(5.0, 1.0)


def test_a_hook_stressed_past_its_allowable_is_named():
    spring = bd.ExtensionSpring("music wire", 1e-3, 10e-3, 20.0, 2.0, 0.2)  # C = 10, machine hooks, 80 N
    bending, torsion = spring.hook_stresses(spring.max_force)
    assert bending > spring.hook_allowables[0] and torsion > spring.hook_allowables[1]
    assert sum("hook's" in p for p in spring.problems()) == 2
    easy = bd.ExtensionSpring("music wire", 1e-3, 10e-3, 20.0, 2.0, spring.free_length * 1.05)  # the control
    assert not any("hook's" in p for p in easy.problems())


def test_the_open_coil_alternative_pulls_as_the_closed_coil_and_is_offered_only_below_the_windable_range():
    # a light cable spring: its initial tension falls below what a maker winds at its index
    coil, why = bd.cable_spring(500.0, (0.02, 0.2))  # its shortest path allows less tension than the index winds
    assert coil is not None, why
    lo, _ = coil.initial_tension_range
    assert coil.initial_tension < lo  # the case the alternative is for
    o = coil.open_coil()
    k, paths = coil.rate, np.linspace(0.02, 0.2, 7)
    closed = coil.initial_tension + k * (paths + coil.cable_offset - coil.free_length)  # F_i + k (x - L_0)
    opened = k * (paths + o.cable_offset - o.free_length)  # no initial tension, x' - L_0'
    assert np.allclose(closed, k * paths) and np.allclose(opened, k * paths)  # both k times the path
    assert np.all(paths + o.cable_offset > o.free_length)  # stretched everywhere: never slack
    grown = (coil.body_coils - 1) * bd.OPEN_GAP * coil.wire
    assert o.max_length == pytest.approx(coil.max_length + coil.initial_tension / k + grown)
    assert o.pitch == pytest.approx(coil.wire * (1 + bd.OPEN_GAP))
    assert "wind it open" in bd.maker_note(coil, cable=True)
    assert "wind it open" not in bd.maker_note(coil)  # a zero-length spring needs its initial tension
    inside, _ = bd.cable_spring(2000.0, (0.1, 0.3))  # the control: inside the range, no note at all
    lo, _ = inside.initial_tension_range
    assert inside.initial_tension >= lo * (1 - 1e-9) and bd.maker_note(inside, cable=True) == ""
