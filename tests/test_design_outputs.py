"""What ``springlab design FILE.urdf`` tells a user about a design on the general model, checked against
an independent computation each: the payload dial's range (never negative, never a zero-width range
printed as a result: one line where the dial cannot be turned), each realised spring named after the
ideal one it realises with what changed, a design that fails its own checks flagged (exit status 3, a
warning line, the files written, a JSON status), every reported peak holding on an independent
sample of 20,000 poses, the wall time of the whole command, the tip named as given, and a payload
out of bounds refused before any work."""

import dataclasses
import json
import time

import numpy as np
import pytest

from springlab.design import realise
from springlab.design.arms import ArmDesign, design_model, workspace_ranges
from springlab.design.audit import AUDIT_SAMPLES
from springlab.design.collision import Sampler
from springlab.design.payload import payload_study
from springlab.design.realise import defined_torques
from springlab.energy.geometry import gravity_torques, joint_torques
from springlab.errors import SpringlabError
from springlab.model.robots import ROBOTS, load_robot, robot_urdf
from springlab.model.springs import PointSpring
from springlab.workbench.cli import EXIT_FLAGGED, main

TWO_LINKS = """<robot name="two_links">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="upper"><inertial><origin xyz="0.03 0 0.15"/><mass value="1.2"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.002" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="fore"><inertial><origin xyz="0 0 0.12"/><mass value="0.8"/>
    <inertia ixx="0.005" iyy="0.005" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tool"><inertial><mass value="0.2"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="10" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0 0 0.3"/>
    <axis xyz="0 1 0"/><limit lower="-2.5" upper="2.5" effort="10" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="fore"/><child link="tool"/><origin xyz="0 0 0.25"/></joint>
</robot>
"""


@pytest.fixture(scope="module")
def so101():
    """The SO-101 designed by the command line, as a user runs it: its exit status, output and JSON."""
    import contextlib
    import io
    import tempfile
    from pathlib import Path

    folder = Path(tempfile.mkdtemp())
    out, printed = folder / "so101.design.json", io.StringIO()
    started = time.perf_counter()
    with contextlib.redirect_stdout(printed):
        code = main(["design", str(robot_urdf("SO-101")), "--layout", "two-point", "--tip", ROBOTS["SO-101"].tip,
                     "--json", str(out), "--samples", "300", "--fit-poses", "100",  # what it prints, not the shares
                     "--pulley-radius", "0.005", "--audit-samples", "2000", "--quiet"])  # the default: below
    return code, printed.getvalue(), json.loads(out.read_text()), time.perf_counter() - started


@pytest.fixture(scope="module")
def ur5(ur5_two_point):
    return ur5_two_point  # the dial: the limits' box will do


def test_a_dial_that_cannot_be_turned_is_one_line_and_never_a_negative_range(ur5):
    # designed at 0 kg, the UR5's anchors sit on their boxes' faces: any payload takes one off its link
    study = payload_study(ur5, ROBOTS["UR5"].tip, [0.0, 1.0], nominal=0.0, dial_poses=100)
    for which in ("ideal", "realised"):
        lo, hi = study.holds[which]
        assert 0.0 <= lo <= hi and not study.usable(which)
    refusals = [w for w in study.warnings() if w.startswith("no payload dial")]
    assert len(refusals) == 1 and "holds only its nominal 0 kg" in refusals[0] and "\n" not in refusals[0]
    assert not any("from 0 to 0 kg" in w for w in study.warnings())
    assert not any("dial turned" in row[1] for row in study.table().rows)  # no rows for a dial that cannot turn
    data = study.as_dict()
    assert all(v >= 0 for pair in data["dial_holds_kg"].values() for v in pair)
    assert data["dial_usable"] == {"ideal": False, "realised": False}


def test_a_dial_that_holds_a_sliver_of_the_range_is_none(ur5):
    study = payload_study(ur5, ROBOTS["UR5"].tip, [0.0, 1.0], nominal=0.0, dial_poses=100)
    sliver = dataclasses.replace(study, holds={"ideal": (0.0, 0.02), "realised": (0.0, 0.2)})
    assert not sliver.usable("ideal") and sliver.usable("realised")  # 20 g of a 1 kg study is none; 200 g is
    assert any(w.startswith("no payload dial for the ideal springs") and "only 0 to 0.02 kg" in w
               for w in sliver.warnings())


def test_a_dial_that_turns_says_the_range_it_holds():
    # the control: designed at 2.5 kg, the anchors can move towards lighter payloads, down to 0 kg
    design = design_model(load_robot("UR5", payload=2.5), samples=300, fit_poses=100, collisions=False,
                          audit_samples=500)  # the dial is checked, not the re-check
    study = payload_study(design, ROBOTS["UR5"].tip, [0.0, 3.5], nominal=2.5, dial_poses=100)
    lo, hi = study.holds["ideal"]
    assert study.usable("ideal") and lo == 0.0 and hi == pytest.approx(2.5, abs=1e-6)
    assert any(row[1] == "ideal, dial turned" for row in study.table().rows)


def test_each_realised_spring_names_its_ideal_one_and_what_changed(so101):
    code, printed, data, _ = so101
    names = [s["name"] for s in data["ideal"]]
    assert names == [f"S{i}" for i in range(1, len(names) + 1)]
    for s in data["realised"]:
        assert s["realises"] in names and s["name"].startswith(s["realises"]) and s["changed"]
        ideal = data["ideal"][names.index(s["realises"])]
        together = sum(t["k"] for t in data["realised"] if t["realises"] == s["realises"])  # side by side: k / m each
        if f"{ideal['k']:.4g}" != f"{together:.4g}":  # a changed rate is said, with its size
            assert f"rate {ideal['k']:.4g} -> {together:.4g} N/m" in s["changed"]
        else:
            assert f"rate {ideal['k']:.4g} ->" not in s["changed"]
    assert "what the realisation changed" in printed


def test_springs_side_by_side_are_named_after_the_one_they_realise(ur5):
    design = dataclasses.replace(ur5, origins=(0, 1, 1, 2, 2, 2))
    assert design.realised_names == ("S1", "S2a", "S2b", "S3a", "S3b", "S3c")


def test_a_rebalanced_spring_left_with_nothing_is_left_out(monkeypatch):
    model = load_robot("SO-101")
    q = model.random_q(200, 3)
    spring = PointSpring("shoulder_link", (-0.03, -0.05, -0.05), "lower_arm_link", (0.04, 0.0, 0.0), 200.0)
    monkeypatch.setattr(realise, "_worst", lambda *a: 1.0)  # the leads "leave too much": re-balance
    monkeypatch.setattr(realise, "_rebalance", lambda m, springs, cable, *a: [s.scaled(1e-3) for s in springs])
    realised, kinds, _ = realise.realise_springs(model, [spring], q, pulley_radius=0.005)
    assert realised == (None,) and "carries next to nothing" in kinds[0] and "S1" in kinds[0]
    monkeypatch.setattr(realise, "_rebalance", lambda m, springs, cable, *a: [s.scaled(0.5) for s in springs])
    realised, kinds, _ = realise.realise_springs(model, [spring], q, pulley_radius=0.005)  # the control: kept
    assert realised[0] is not None and sum(r.k for r in realised) == pytest.approx(100.0)  # side by side: k / m each


def test_every_reported_peak_holds_on_an_independent_sample(so101):
    # a design checked on only 40 random poses: the audit's worst poses must still bound what 10,000
    # other random poses (another seed) find, for gravity, the ideal and the realised springs
    design = design_model(load_robot("SO-101"), samples=40, fit_poses=60, max_springs=3, pulley_radius=0.005)
    assert design.audit.samples == AUDIT_SAMPLES and len(design.q) > 40
    ranges = workspace_ranges(design.model)
    rng = np.random.default_rng(12345)  # the same workspace (free of collisions), drawn anew
    fresh = Sampler(design.model, ranges, rng).draw(10_000, rng)
    own = design.q[:40]
    missed = False
    for springs in ((), design.ideal, design.realised):
        reported = np.max(np.abs(joint_torques(design.model, springs, design.q)), axis=0)
        found = np.max(np.abs(joint_torques(design.model, springs, fresh)), axis=0)
        assert np.all(reported >= found * (1 - 1e-3))
        missed |= bool(np.any(np.max(np.abs(joint_torques(design.model, springs, own)), axis=0) < found * (1 - 1e-3)))
    assert missed  # the negative control: the 40 poses alone miss a peak
    _, printed, data, _ = so101
    assert "re-checked on 2,000 independent ones" in printed and data["audit"]["samples"] == 2_000  # as asked


def test_poses_without_a_line_of_action_are_found_not_fatal():
    # a cable whose end B comes within its pulley's radius of A at some poses (the median |B - A|):
    # exactly those poses are undefined, named by the spring; the others keep route 2's torques
    from springlab.energy.geometry import spring_lengths
    from springlab.model.revolute import body_frames

    model = load_robot("SO-101")
    q = model.random_q(64, 1)
    point = PointSpring("shoulder_link", (0.0, -0.03, -0.05), "lower_arm_link", (0.05, 0.0, 0.0), 100.0)
    length = spring_lengths(model, [point], *body_frames(model, q))[0]
    radius = float(np.median(length))
    cable = dataclasses.replace(point, pulley_radius=radius, lead=(1.0, 0.0, 0.0))
    tau, why = defined_torques(model, [point, cable], q)
    assert np.array_equal(np.isnan(tau[:, 0]), length <= radius) and 0 < np.sum(length <= radius) < 64
    assert why.startswith("spring 2 (shoulder_link-lower_arm_link): the cable's end B comes within")
    fine = ~np.isnan(tau[:, 0])
    assert np.array_equal(tau[fine], joint_torques(model, [point, cable], q[fine]))
    tau, why = defined_torques(model, [point], q)  # the control: defined everywhere
    assert not why and np.all(np.isfinite(tau))


def test_a_design_worse_than_its_control_or_gravity_is_flagged(ur5):
    assert ur5.balance_flags() == ()  # the UR5's exact springs pass every torque check (designed without link shapes)
    strong = dataclasses.replace(ur5, ideal=tuple(s.scaled(3.0) for s in ur5.ideal))  # 3 times the rates: 2 g left
    flags = strong.flags()
    assert any("negative control" in f for f in flags)
    assert any("the ideal springs leave" in f and "more than gravity alone" in f for f in flags)
    assert strong.as_dict()["status"]["verdict"] == "flagged"
    assert all(f in strong.flags() for f in ur5.hardware_flags())  # the same hardware flags beside the torque's


def test_the_cli_flags_a_failing_design_with_exit_3_and_writes_the_files(tmp_path, capsys, monkeypatch):
    urdf = tmp_path / "two.urdf"
    urdf.write_text(TWO_LINKS)
    out = tmp_path / "two.design.json"
    monkeypatch.setattr(ArmDesign, "flags", lambda self, factor=0.9: ())  # a design that passes its checks
    code = main(["design", str(urdf), "--tip", "tool", "--json", str(out), "--quiet", "--sheet"])
    printed = capsys.readouterr()
    assert code == 0 and "status: passed" in printed.out and json.loads(out.read_text())["status"]["verdict"] == "passed"
    monkeypatch.setattr(ArmDesign, "flags", lambda self, factor=0.9: ("the springs are made worse on purpose",))
    code = main(["design", str(urdf), "--tip", "tool", "--json", str(out), "--quiet", "--sheet"])
    printed = capsys.readouterr()
    assert code == EXIT_FLAGGED == 3
    assert "status: flagged" in printed.out and printed.err.count("\n") == 1 and "warning" in printed.err
    assert json.loads(out.read_text())["status"] == {"verdict": "flagged",
                                                     "flags": ["the springs are made worse on purpose"]}
    assert (tmp_path / "two.sheet.md").exists()


def test_the_header_names_the_tip_given_and_the_wall_time_is_the_whole_commands(tmp_path, capsys, so101):
    urdf = tmp_path / "two.urdf"
    urdf.write_text(TWO_LINKS)
    main(["design", str(urdf), "--tip", "tool", "--json", str(tmp_path / "d.json"), "--quiet"])
    printed = capsys.readouterr().out
    first = printed.splitlines()[0]
    assert "to the tip 'tool' (fixed to 'fore', the last body a joint moves); target 90 % reached (" in first
    code, printed, _, elapsed = so101
    last = printed.strip().splitlines()[-1]
    assert code == EXIT_FLAGGED and last.startswith("done in ") and last.endswith("(wall time of the whole command)")
    seconds = float(last.split()[2])
    assert 0.8 * elapsed <= seconds <= elapsed + 0.1  # the whole call, not the search alone


def test_a_payload_out_of_bounds_is_refused_before_any_work(tmp_path, capsys):
    started = time.perf_counter()
    code = main(["design", str(robot_urdf("UR5")), "--tip", "wrist_3_link", "--payload", "1e9 kg",
                 "--json", str(tmp_path / "d.json"), "--quiet"])
    err = capsys.readouterr()
    assert code == 2 and err.err.startswith("springlab: --payload = '1e9 kg'") and err.err.count("\n") == 1
    assert err.out == "" and not list(tmp_path.iterdir()) and time.perf_counter() - started < 5


def test_help_explains_the_search_steps_and_the_exit_statuses(capsys):
    with pytest.raises(SystemExit):
        main(["design", "--help"])
    text = capsys.readouterr().out
    assert "after each spring the greedy search added" in text and "3 a design written that fails" in text


def test_gravity_is_what_the_flags_compare_with(ur5):
    gravity = np.max(np.abs(gravity_torques(ur5.model, ur5.q)), axis=0)
    assert ur5.structure.peak == pytest.approx(gravity, rel=1e-12)


def test_a_xacro_file_is_refused_with_how_to_expand_it(tmp_path, capsys):
    arm = tmp_path / "arm.urdf.xacro"
    arm.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="a"><xacro:include filename="x"/></robot>')
    code = main(["design", str(arm), "--json", str(tmp_path / "d.json")])
    err = capsys.readouterr().err
    assert code == 2 and "is a xacro file" in err and "xacro arm.urdf.xacro > arm.urdf" in err
    assert err.count("\n") == 1 and not (tmp_path / "d.json").exists()


def test_a_spring_left_out_is_named_in_the_changes_and_the_json(monkeypatch):
    monkeypatch.setattr(realise, "_worst", lambda *a: 1.0)
    monkeypatch.setattr(realise, "_rebalance", lambda m, springs, cable, *a: [
        s.scaled(1e-3) if i == cable[0] else s for i, s in enumerate(springs)])
    design = design_model(load_robot("SO-101"), samples=40, fit_poses=60, max_springs=3, pulley_radius=0.005,
                          collisions=False, audit_samples=500)  # what the realisation leaves out: the box will do
    (index, why), = design.left_out
    assert "carries next to nothing" in why and design.names[index] not in design.realised_names
    assert ["(left out)", design.names[index], why] in [list(row) for row in design.changes_table().rows]
    assert design.as_dict()["left_out"] == [{"realises": design.names[index], "why": why}]


def test_the_books_two_ur5_designs_name_their_springs_apart():
    from springlab.workbench import real_arms

    loaded = real_arms.payload_study("UR5", samples=100, fit_poses=60, masses=3)
    assert loaded.names["ideal"] == ("P1", "P2", "P3", "P4", "P5", "P6")
    assert all(row[0].startswith("P") for row in loaded.dials["ideal"].table(loaded.names["ideal"]).rows)
    unloaded = design_model(load_robot("UR5"), samples=100, fit_poses=60, collisions=False, audit_samples=500)
    assert unloaded.names[0] == "S1" and not set(unloaded.names) & set(loaded.names["ideal"])
    with pytest.raises(SpringlabError, match="tag"):
        design_model(load_robot("UR5"), samples=10, tag="s1")


@pytest.mark.parametrize("outputs", [["--json", "{arm}"], ["--json", "x.xml", "--mjcf", "x.xml"],
                                     ["--json", "x.realised.xml", "--mjcf", "x.xml"]],
                         ids=["json is the arm", "json is the mjcf", "json is the realised mjcf"])
def test_an_output_that_overwrites_the_arm_or_another_output_is_refused(outputs, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    urdf = tmp_path / "two.urdf"
    urdf.write_text(TWO_LINKS)
    code = main(["design", str(urdf), "--tip", "tool", "--quiet", *[a.format(arm=urdf) for a in outputs]])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and ("arm file itself" in err or "overwrite the other" in err)
    assert urdf.read_text() == TWO_LINKS and sorted(p.name for p in tmp_path.iterdir()) == ["two.urdf"]


def test_a_cable_whose_end_crosses_its_lead_line_is_found_and_avoided(ur5):
    from springlab.design.audit import Audit
    from springlab.design.realise import CROSSING, lead_angles

    model, ranges = ur5.model, workspace_ranges(ur5.model)
    spring = dataclasses.replace(ur5.ideal[1], pulley_radius=0.005, lead=(0.0, 1.0, 0.0))  # S2 along link y
    q = model.random_q(50, 2)
    angle = lead_angles(model, spring, q)  # against the angle computed directly
    from springlab.model.revolute import body_frames, world_points
    R, o = body_frames(model, q)
    a, pa = model.locate(spring.link_a, spring.point_a)
    d = world_points(R, o, *model.locate(spring.link_b, spring.point_b)) - world_points(R, o, a, pa)
    u = R[:, a] @ model.direction(spring.link_a, spring.lead)[1]
    alpha = np.arccos(np.einsum("pi,pi->p", d, u) / np.linalg.norm(d, axis=1) / np.linalg.norm(u, axis=1))
    np.testing.assert_allclose(angle, np.minimum(alpha, np.pi - alpha), atol=1e-12)
    crossing = Audit.of(model, ranges, {"realised": [spring]}, q, seed=5, samples=2000).crossings
    assert len(crossing) == 1 and crossing[0][1] < CROSSING  # the compass search reaches the line
    clear = dataclasses.replace(spring, lead=(1.0, 0.0, 0.0))  # the control: B keeps 0.6 deg from this line
    assert Audit.of(model, ranges, {"realised": [clear]}, q, seed=5, samples=2000).crossings == ()
    flagged = dataclasses.replace(ur5, realised=(spring,), kinds=("cable over a pulley",), coils=(ur5.coils[1],),
                                  origins=(1,), changes=("",), audit=Audit.of(model, ranges, {"realised": [spring]}, q,
                                                                                 seed=5, samples=2000))
    assert any("crosses the line of its pulley's lead" in f for f in flagged.flags())
    for s in ur5.realised:  # the design's own leads: none crosses (where one must, the design is flagged)
        assert s.pulley_radius == 0 or np.min(lead_angles(model, s, ur5.q)) > CROSSING or ur5.flags()


def test_the_audits_worst_poses_leave_every_case_defined():
    # a cable undefined near some poses (|B - A| within its pulley's radius) beside springs defined everywhere:
    # the poses the other cases climb to join the check only where the cable has a line of action too
    from springlab.design.audit import Audit
    from springlab.energy.geometry import spring_lengths
    from springlab.model.revolute import body_frames

    model = load_robot("SO-101")
    q = model.random_q(200, 4)
    point = PointSpring("shoulder_link", (0.0, -0.03, -0.05), "lower_arm_link", (0.05, 0.0, 0.0), 100.0)
    radius = float(np.quantile(spring_lengths(model, [point], *body_frames(model, q))[0], 0.05))
    cable = dataclasses.replace(point, pulley_radius=radius, lead=(1.0, 0.0, 0.0))
    audit = Audit.of(model, workspace_ranges(model), {"ideal": [point], "realised": [cable]}, q, seed=3, samples=2000)
    tau, why = defined_torques(model, [cable], audit.worst)
    assert len(audit.worst) and not why and np.all(np.isfinite(tau))
    assert any(case == "realised" for case, *_ in audit.undefined)  # and the undefined poses are reported


def test_payload_peaks_skip_poses_where_a_cable_has_no_line_of_action():
    from springlab.design.payload import payload_torques
    from springlab.energy.geometry import spring_lengths
    from springlab.model.revolute import body_frames

    model = load_robot("SO-101", payload=0.0)
    q = model.random_q(100, 6)
    point = PointSpring("shoulder_link", (0.0, -0.03, -0.05), "lower_arm_link", (0.05, 0.0, 0.0), 100.0)
    length = spring_lengths(model, [point], *body_frames(model, q))[0]
    cable = dataclasses.replace(point, pulley_radius=float(np.median(length)), lead=(1.0, 0.0, 0.0))
    peaks = payload_torques(model, [cable], q, ROBOTS["SO-101"].tip, [0.0, 0.5])  # raised GeometryError before
    fine = length > cable.pulley_radius
    expected = payload_torques(model, [cable], q[fine], ROBOTS["SO-101"].tip, [0.0, 0.5])
    np.testing.assert_array_equal(peaks, expected)


def test_output_piped_into_a_reader_that_stops_is_no_internal_error(tmp_path):
    """`springlab design arm.urdf | head -1`: the reader closes the pipe after one line; the command stops
    quietly with the shell's SIGPIPE status (141), never 'internal error'. Negative control: read to the
    end, it finishes with its own status."""
    import subprocess
    import sys

    urdf = tmp_path / "two.urdf"
    urdf.write_text(TWO_LINKS)
    command = [sys.executable, "-m", "springlab.workbench.cli", "design", str(urdf), "--tip", "tool", "--quiet",
               "--json", str(tmp_path / "d.json")]
    run = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    run.stdout.readline()
    run.stdout.close()  # as `head -1` does
    err = run.stderr.read().decode()
    assert run.wait(timeout=120) == 141 and "internal error" not in err, err
    whole = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert whole.returncode in (0, 3) and "internal error" not in whole.stderr
