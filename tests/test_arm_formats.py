"""Arms as users describe them, and results where engineers keep them: units by pint, CSV out."""

from __future__ import annotations

import csv
import io
import json
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

    code = ("import time, springlab.model.armfile as a; a.parse_quantity(0.4, 'length', 'x'); assert a._UNITS is None; "
            "t = time.process_time(); a.parse_quantity('400 mm', 'length', 'x'); print(time.process_time() - t)")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)  # fills pint's cache
    # the process's own CPU seconds: a busy machine (the other tests, on every core) does not count
    seconds = float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout)
    assert seconds < 1.0


URDF = (ARMS / "example_arm.urdf").read_text()


def test_the_example_urdf_and_its_toml_twin_give_the_same_chain_and_best_design():
    a, b = load_arm(ARMS / "example_arm.urdf"), load_arm(ARMS / "example_arm.toml")
    for key in ("r", "d", "m"):
        assert np.abs(np.subtract(getattr(a, key), getattr(b, key))).max() <= 1e-12
    assert a.joints == b.joints and a.limits == b.limits and a.g == b.g
    assert any("not turned into a cone" in note for note in a.notes)  # the wrist's limits
    da, db = (design_arm(s, max_designs=1).designs[0] for s in (a, b))
    assert da.configuration == db.configuration and da.max_force == pytest.approx(db.max_force, rel=1e-6)
    # a URDF whose arm stands along +y (a y-up export) gives the same chain with --up 0,1,0
    y_up = URDF.replace('<origin xyz="0 0 0.10" rpy="0 0 0"/>', '<origin xyz="0 0 0.10" rpy="-1.5707963267948966 0 0"/>')
    from springlab.model.armfile import _from_urdf

    c = _from_urdf(y_up, "y_up.urdf", False, [0, 1, 0])
    assert np.abs(np.subtract(c.r, b.r)).max() <= 1e-12 and np.abs(np.subtract(c.d, b.d)).max() <= 1e-12
    assert np.allclose(c.joints[0], (1, 0, 0), atol=1e-12)  # the base joint about up
    assert np.allclose(c.joints[1], c.joints[2], atol=1e-12) and abs(c.joints[1][0]) < 1e-12  # parallel, level
    with pytest.raises(SpringlabError, match="same angle"):  # the default up leaves this arm lying down
        _from_urdf(y_up, "y_up.urdf", False, None)


def _long_chain(joints: int, kind: str = "revolute", *, solid: bool = False) -> str:
    """A URDF of ``joints`` joints of one kind in a row, about 95 bytes a joint: links without inertia
    at one point, or (``solid``) a planar arm of 0.1 m links on axes along y, their masses on their lines."""
    shape = '<origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>' if solid else ""
    body = '<inertial><origin xyz="0 0 0.05"/><mass value="1"/></inertial>' if solid else ""
    return ('<robot name="long"><link name="l0"/>' + "".join(
        f'<joint name="j{k}" type="{kind}"><parent link="l{k - 1}"/><child link="l{k}"/>{shape}</joint>'
        f'<link name="l{k}">{body}</link>' for k in range(1, joints + 1)) + "</robot>")


def test_a_urdf_of_100000_links_is_refused_at_once_by_its_count_of_movable_joints(tmp_path, monkeypatch, capsys):
    import time
    import xml.etree.ElementTree as ET

    import springlab.model.urdf as urdf

    path = tmp_path / "big.urdf"
    path.write_text(_long_chain(100_000))  # 9.5 MiB; it once took 40 s to be refused for its 100 001 links

    def built(*args, **kwargs):
        raise AssertionError("the URDF was parsed into elements before its joints were counted")

    with monkeypatch.context() as patch:  # structural: nothing per link is built before the refusal
        patch.setattr(urdf, "_parse", built)
        patch.setattr(ET, "fromstring", built)
        t0 = time.perf_counter()
        with pytest.raises(SpringlabError, match=r"big.urdf: 100000 movable joints: an arm of at most 8 links \(ground "
                           r"included\) has at most 21 .*serial chain \(allow_large=True, --allow-large, reads at most 1000\)"):
            load_arm(path)
        seconds = time.perf_counter() - t0
        with pytest.raises(SpringlabError, match=r"100000 movable joints is more than springlab reads from a URDF "
                           r"\(1000, with allow_large=True\)"):
            load_arm(path, allow_large=True)
    assert seconds < 5, f"the refusal took {seconds:.1f} s"  # measured: 0.4 s
    t0 = time.perf_counter()
    assert main(["design", str(path), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "100000 movable joints" in err and "--allow-large" in err and err.count("\n") == 1, err
    assert time.perf_counter() - t0 < 5
    # the class: just over the limit, a chain of fixed bodies past MAX_BODIES, a file past MAX_FILE_BYTES
    from springlab.model.armfile import _from_urdf

    with pytest.raises(SpringlabError, match=r"22 movable joints: an arm of at most 8 links.*or pass allow_large=True"):
        _from_urdf(_long_chain(22), "22.urdf", False, None)
    with pytest.raises(SpringlabError, match=r"10 links \(ground included\) is more than 8"):  # 9 joints: read, then refused
        _from_urdf(_long_chain(9, solid=True), "9.urdf", False, None)
    assert _from_urdf(_long_chain(9, solid=True), "9.urdf", True, None).n == 10
    with pytest.raises(SpringlabError, match=r"10002 links is more than springlab reads from a URDF \(10000\)"):
        _from_urdf(_long_chain(10_001, "fixed"), "fixed.urdf", False, None)
    huge = tmp_path / "huge.urdf"
    with huge.open("wb") as f:
        f.truncate(17 * 2 ** 20)  # sparse: refused by its size, never read
    with pytest.raises(SpringlabError, match=r"huge.urdf: 17.0 MiB is more than an arm file springlab reads \(16 MiB"):
        load_arm(huge)


def _with_fixed_bodies(count: int, where: str) -> str:
    """The example URDF with ``count`` small bodies fixed in a row along the arm's line: beyond its
    tool frame (a long tool), or hanging off the upper arm at its shoulder (a cable carrier)."""
    parent = {"tool": "tool0", "side": "upper_arm"}[where]
    bodies = "".join(
        f'<joint name="f{k}" type="fixed"><parent link="{parent if k == 1 else f"b{k - 1}"}"/><child link="b{k}"/>'
        f'<origin xyz="0 0 {0.0005 if where == "tool" else 0}"/></joint>'
        f'<link name="b{k}"><inertial><mass value="0.001"/></inertial></link>' for k in range(1, count + 1))
    return URDF.replace('<link name="tool0"/>', '<link name="tool0"/>' + bodies)


@pytest.mark.parametrize("where", ["tool", "side"])
def test_a_tool_of_2000_bodies_fixed_together_loads(tmp_path, capsys, where):
    # the fixed-joint merge once recursed a level a body: a RecursionError, "internal error", exit 3
    path = tmp_path / "long_tool.urdf"
    path.write_text(_with_fixed_bodies(2000, where))
    spec, plain = load_arm(path), load_arm(ARMS / "example_arm.urdf")
    if where == "tool":  # the last link runs to the deepest frame, 2000 x 0.5 mm beyond tool0, and carries 2 kg more
        assert spec.r[:3] == plain.r[:3] and spec.m[:3] == plain.m[:3]
        assert spec.r[3] == pytest.approx(plain.r[3] + 1.0, rel=1e-9) and spec.m[3] == pytest.approx(plain.m[3] + 2.0)
    else:  # 2 kg at the shoulder, on the upper arm's line
        assert spec.r == plain.r and spec.m[1] == pytest.approx(plain.m[1] + 2.0) and spec.m[2:] == plain.m[2:]
        assert spec.d[1] == pytest.approx(plain.m[1] * plain.d[1] / (plain.m[1] + 2.0), rel=1e-9)
    code = main(["design", str(path), "--json", str(tmp_path / "d.json"), "--method", "ground springs", "--quiet",
                 "--max-designs", "1"])
    assert code == 0, capsys.readouterr().err


Y_UP = URDF.replace('<origin xyz="0 0 0.10" rpy="0 0 0"/>', '<origin xyz="0 0 0.10" rpy="-1.5707963267948966 0 0"/>')


@pytest.mark.parametrize("rpy, up, looks", [
    ("-1.5707963267948966 0 0", "0,1,0", "y-up"), ("0 1.5707963267948966 0", "1,0,0", "x-up"),
    ("1.5707963267948966 0 0", "0,-1,0", "-y-up"),
])
def test_a_urdf_exported_with_another_up_is_refused_with_the_up_that_reads_it(tmp_path, capsys, rpy, up, looks):
    path = tmp_path / "turned.urdf"
    path.write_text(URDF.replace('<origin xyz="0 0 0.10" rpy="0 0 0"/>', f'<origin xyz="0 0 0.10" rpy="{rpy}"/>'))
    with pytest.raises(SpringlabError, match=rf"joint 'base_yaw': .*same angle.*The file looks {looks}: .*--up {up} "):
        load_arm(path)  # without up: read z-up, the column lies down (an "offset shoulder")
    spec, plain = load_arm(path, up=[float(x) for x in up.split(",")]), load_arm(ARMS / "example_arm.urdf")
    for key in ("r", "d", "m"):
        assert np.abs(np.subtract(getattr(spec, key), getattr(plain, key))).max() <= 1e-12
    assert main(["design", str(path), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert f"pass --up {up}" in err and err.count("\n") == 1, err
    code = main(["design", str(path), "--up", up, "--json", str(tmp_path / "d.json"), "--method", "ground springs",
                 "--quiet", "--max-designs", "1"])
    assert code == 0, capsys.readouterr().err
    # the wrong up given explicitly: the same advice
    with pytest.raises(SpringlabError, match=rf"--up {up} "):
        load_arm(path, up=[0, 0, -1])
    # a refusal that no up lifts gives no such advice
    with pytest.raises(SpringlabError, match=r"20\.0 mm off the line") as refused:
        load_arm(_write(tmp_path / "off.urdf", _revolute_arm(20.0)))
    assert "--up" not in str(refused.value)


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


def _revolute_arm(offset_mm: float) -> str:
    """A three-link arm on horizontal axes whose forearm's centre of mass is offset_mm off its line."""
    link = ('<link name="{n}"><inertial><origin xyz="{x} 0 {z}"/><mass value="{m}"/>'
            '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>')
    joint = ('<joint name="{n}" type="revolute"><parent link="{p}"/><child link="{c}"/><origin xyz="0 0 {z}"/>'
             '<axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>')
    return ('<robot name="offset arm"><link name="base"/>'
            + joint.format(n="j2", p="base", c="l2", z=0.1) + link.format(n="l2", x=0, z=0.15, m=3.0)
            + joint.format(n="j3", p="l2", c="l3", z=0.4) + link.format(n="l3", x=offset_mm / 1e3, z=0.12, m=2.0)
            + joint.format(n="j4", p="l3", c="l4", z=0.3) + link.format(n="l4", x=0, z=0.05, m=0.5)
            + '<joint name="tool" type="fixed"><parent link="l4"/><child link="tool0"/><origin xyz="0 0 0.1"/></joint>'
            + '<link name="tool0"/></robot>')


def test_a_centre_of_mass_off_the_line_is_refused_with_its_offset():
    from springlab.model.armfile import _from_urdf

    with pytest.raises(SpringlabError, match=r"link 3 \(after joint\(s\) 'j3'\).* 20\.0 mm off the line.*paper 001"):
        _from_urdf(_revolute_arm(20.0), "off.urdf", False, None)


def test_a_small_offset_is_projected_and_its_balance_error_confirmed_by_the_urdfs_own_kinematics():
    import re

    from springlab.design.rank import workspace_angles
    from springlab.model.armfile import _from_urdf

    spec = _from_urdf(_revolute_arm(3.0), "small.urdf", False, None)  # 3 mm on a 300 mm forearm: 1 %
    assert spec.com_offsets[1] == pytest.approx((0.0, 0.0, -0.003), abs=1e-12)  # URDF x is springlab -z
    report = design_arm(spec, method="ground springs", max_designs=1)
    share = float(re.search(r"varying by ([\d.]+)% of gravity's range", report.notes[-1]).group(1)) / 100
    # independent: the URDF's own forward kinematics (z up), every joint turning about y by q = theta
    chain = spec.chain()
    angles = workspace_angles(spec, chain)
    X, q = chain.directions(angles), angles[:, :, 0]

    def rot_y(t):
        c, s = np.cos(t), np.sin(t)
        return np.array([[c, np.zeros_like(t), s], [np.zeros_like(t), np.ones_like(t), np.zeros_like(t)],
                         [-s, np.zeros_like(t), c]]).transpose(2, 0, 1)

    R, p, height = np.broadcast_to(np.eye(3), (len(q), 3, 3)), np.zeros((len(q), 3)), 0.0
    for k, (z, com, mass) in enumerate([(0.1, (0, 0, 0.15), 3.0), (0.4, (0.003, 0, 0.12), 2.0), (0.3, (0, 0, 0.05), 0.5)]):
        p = p + R @ np.array([0, 0, z])
        R = R @ rot_y(q[:, k])
        height = height + mass * (p + R @ np.array(com))[:, 2]
    gravity = chain.g * height
    springs = report.designs[0].springs
    total = gravity + geometry.spring_energy(chain, springs, X)
    assert np.ptp(total) / np.ptp(gravity) == pytest.approx(share, abs=1e-4)  # the note, to its rounding
    assert share > 1e-3  # the offset costs something ...
    projected = geometry.total_energy(chain, springs, X)
    assert np.ptp(projected) < 1e-8 * np.ptp(gravity)  # ... and nothing on the projected arm


@pytest.mark.parametrize("edit, match", [
    (lambda t: t.replace('type="revolute">\n    <parent link="column"/>', 'type="prismatic">\n    <parent link="column"/>'),
     r"joint 'shoulder' is prismatic"),
    (lambda t: t.replace('<link name="tool0"/>', '<link name="tool0"/><joint name="extra" type="revolute"><parent link='
                         '"upper_arm"/><child link="gripper"/><axis xyz="0 1 0"/></joint><link name="gripper"/>'),
     r"link 'upper_arm' branches into joints 'elbow', 'extra'"),
    (lambda t: t.replace('<link name="tool0"/>', '<link name="tool0"/><joint name="loop" type="fixed"><parent link='
                         '"tool0"/><child link="column"/></joint>'), r"link 'column' is the child of joints .*closed loop"),
    (lambda t: t.replace('<link name="hand">\n    <inertial>', '<link name="hand">\n    <visual>').replace(
        '<inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.001"/>\n    </inertial>',
        '<inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.001"/>\n    </visual>'),
     r"link 5 \(URDF links .*'hand', 'tool0', after joint\(s\) 'wrist_1'.*has no mass: give its <inertial>"),
    (lambda t: t.replace('<mass value="3.0"/>', '<mass/>'), r"link 'upper_arm': <inertial> has no <mass value"),
    (lambda t: "<robot><link name='a'/>", r"not valid XML"),
    (lambda t: "<sdf version='1.6'/>", r"not a URDF file \(its root element is <sdf>"),
    (lambda t: t.replace('<origin xyz="0 0 0.25"/>', '<origin xyz="0 0 nan"/>'), r"joint 'shoulder': <origin xyz> = '0 0 nan'"),
    (lambda t: '<?xml version="1.0"?><!DOCTYPE b [<!ENTITY a "aaaaaaaaaa">' + "".join(
        f'<!ENTITY a{k} "{("&a;" if k == 1 else f"&a{k - 1};") * 10}">' for k in range(1, 9))
        + ']><robot name="&a8;"><link name="x"/></robot>', r"not valid XML: limit on input amplification"),
])
def test_bad_urdfs_are_refused_naming_the_element(edit, match):
    from springlab.model.armfile import _from_urdf

    with pytest.raises(SpringlabError, match=match):
        _from_urdf(edit(URDF), "bad.urdf", False, None)


def test_cli_designs_a_urdf(tmp_path, capsys):
    code = main(["design", str(ARMS / "example_arm.urdf"), "--json", str(tmp_path / "d.json"), "--method",
                 "ground springs", "--quiet"])
    assert code == 0, capsys.readouterr().err
    assert "not turned into a cone" in capsys.readouterr().out
    code = main(["design", str(ARMS / "example_arm.urdf"), "--up", "0,1", "--quiet"])
    assert code == 2 and "--up = '0,1'" in capsys.readouterr().err


def test_the_paper001_arm_loads_from_its_dh_file_and_designs_as_the_notebook():
    from springlab.mechanisms.pseudobase import geometry as pbgeo
    from springlab.mechanisms.pseudobase.armfile import load_dh_arm
    from springlab.mechanisms.pseudobase.subsystems import design_equilibrators
    from springlab.papers import lin2010 as paper

    dh, ref = load_dh_arm(ARMS / "paper001_arm.toml"), paper.arm()
    for key in ("m", "s", "m_hat", "s_hat", "m_star", "c", "aux_offset"):
        assert np.abs(np.asarray(getattr(dh.arm, key)) - np.asarray(getattr(ref, key))).max() <= 1e-12, key
    for key in ("d", "a", "alpha"):
        assert np.abs(getattr(dh.arm.dh, key) - getattr(ref.dh, key)).max() <= 1e-12, key
    assert dh.arm.modules == ref.modules and dh.arm.g == ref.g and dh.K == tuple(paper.K)
    ours, notebook = dh.design(), design_equilibrators(ref, paper.K, paper.L_CA)  # the notebook's call
    for a, b in zip(ours, notebook, strict=True):
        assert a.link == b.link and abs(a.l_CB - b.l_CB) <= 1e-12 and np.abs(a.b - b.b).max() <= 1e-12
    q = np.random.default_rng(0).uniform(-np.pi, np.pi, (300, 6))
    energy = pbgeo.energies(dh.arm, ours, q)
    assert np.ptp(energy["total"]) < 1e-9 * np.ptp(energy["gravity"])  # route 2: balanced
    spoiled = pbgeo.energies(dh.arm, [s.scaled(0.9) for s in ours], q)
    assert np.ptp(spoiled["total"]) > 1e-3 * np.ptp(spoiled["gravity"])


def _dh_data():
    import tomllib

    return tomllib.loads((ARMS / "paper001_arm.toml").read_text())


@pytest.mark.parametrize("edit, match", [
    (lambda d: d.pop("auxiliary_d1"), r"missing field 'auxiliary_d1'"),
    (lambda d: d["frame"][2]["module"].pop("stiffness"), r"frame 3: module: missing field\(s\) \['stiffness'\]"),
    (lambda d: d["frame"][3].pop("module"), r"modules must be the links k..6"),
    (lambda d: d["frame"][1].update(com=[0.1, 0.2]), r"frame 2: com = \[0.1, 0.2\]: give three lengths"),
    (lambda d: d["frame"][1].update(alpha="90 m"), r"frame 2: alpha = '90 m' is a length, not an angle"),
    (lambda d: d["frame"][1]["module"].update(stiffness="-2 kN/m"), r"frame 2: module: stiffness = -2000 N/m must be > 0"),
])
def test_bad_dh_arm_files_name_the_field(edit, match):
    from springlab.mechanisms.pseudobase.armfile import dh_arm_from_dict

    data = _dh_data()
    edit(data)
    with pytest.raises(SpringlabError, match=match):
        dh_arm_from_dict(data, source="dh.toml")


def test_cli_designs_a_dh_arm_and_load_arm_points_to_it(tmp_path, capsys):
    import json

    out = tmp_path / "p1.json"
    code = main(["design", str(ARMS / "paper001_arm.toml"), "--json", str(out), "--quiet"])
    assert code == 0, capsys.readouterr().err
    record = json.loads(out.read_text())
    assert len(record["springs"]) == 5 and record["energy_variation"] < 1e-9
    code = main(["design", str(ARMS / "paper001_arm.toml"), "--sheet"])
    assert code == 2 and "--sheet applies to arms for paper 000's method" in capsys.readouterr().err
    with pytest.raises(SpringlabError, match="describes its arm by DH frames"):
        load_arm(ARMS / "paper001_arm.toml")


def _finger(side: str, y: float) -> str:
    """A prismatic finger of 0.1 kg on tool0, sliding along y (a gripper's jaw)."""
    return (f'  <joint name="finger_{side}" type="prismatic">\n    <parent link="tool0"/>\n'
            f'    <child link="finger_{side[0]}"/>\n    <origin xyz="0 {y} 0.03"/>\n'
            f'    <axis xyz="0 {1 if y > 0 else -1} 0"/>\n'
            '    <limit lower="0" upper="0.04" effort="20" velocity="0.2"/>\n  </joint>\n'
            f'  <link name="finger_{side[0]}"><inertial><origin xyz="0 0 0"/><mass value="0.1"/>\n'
            '    <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link>\n')


GRIPPER = _finger("left", 0.02) + _finger("right", -0.02) + "</robot>"
RAIL = """<robot name="example arm (URDF)">
  <link name="world"/>
  <joint name="rail" type="prismatic">
    <parent link="world"/>
    <child link="base_link"/>
    <origin xyz="0.5 0 0"/>
    <axis xyz="1 0 0"/>
    <limit lower="0" upper="1" effort="200" velocity="1"/>
  </joint>"""


def _urdf(tmp_path, text, name="arm.urdf"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_tip_chooses_the_chain_and_locks_a_grippers_fingers(tmp_path):
    plain = load_arm(ARMS / "example_arm.urdf")
    gripper = _urdf(tmp_path, URDF.replace("</robot>", GRIPPER))
    with pytest.raises(SpringlabError, match=r"joint 'finger_left' is prismatic \(choose the arm's chain with --tip"):
        load_arm(gripper)
    spec = load_arm(gripper, tip="hand")
    assert spec.r == pytest.approx(plain.r) and spec.m[:-1] == pytest.approx(plain.m[:-1])
    assert spec.m[-1] == pytest.approx(plain.m[-1] + 0.2)  # the locked fingers ride on the hand
    assert spec.d[-1] == pytest.approx((plain.m[-1] * plain.d[-1] + 0.2 * 0.15) / (plain.m[-1] + 0.2))
    assert any("every other joint is locked at zero" in note for note in spec.notes)
    # a joint on the chosen path that slides is still refused, naming the tip
    sliding = _urdf(tmp_path, URDF.replace('"elbow" type="revolute"', '"elbow" type="prismatic"'), "sliding.urdf")
    with pytest.raises(SpringlabError, match=r"'elbow' is prismatic and lies on the path .* to tip 'hand'"):
        load_arm(sliding, tip="hand")


def test_the_base_leaves_out_what_the_arm_stands_on(tmp_path):
    plain = load_arm(ARMS / "example_arm.urdf")
    railed = _urdf(tmp_path, URDF.replace('<robot name="example arm (URDF)">', RAIL))
    with pytest.raises(SpringlabError, match="'rail' is prismatic"):
        load_arm(railed)
    spec = load_arm(railed, base="base_link", tip="tool0")
    assert spec.r == pytest.approx(plain.r) and spec.m == pytest.approx(plain.m) and spec.d == pytest.approx(plain.d)


def test_a_payload_at_the_tip_frame_and_equal_limits_read_as_unlimited(tmp_path):
    plain = load_arm(ARMS / "example_arm.urdf")
    spec = load_arm(ARMS / "example_arm.urdf", tip="hand", payload="2 kg")
    assert spec.m[-1] == pytest.approx(plain.m[-1] + 2.0)
    assert spec.d[-1] == pytest.approx(plain.m[-1] * plain.d[-1] / (plain.m[-1] + 2.0))  # at the hand frame's origin
    assert any("payload 2 kg" in note for note in spec.notes)
    stuck = _urdf(tmp_path, URDF.replace('<limit lower="-1.5" upper="1.5"', '<limit lower="0" upper="0"'))
    spec = load_arm(stuck)
    assert spec.limits[0] == load_arm(ARMS / "example_arm.urdf").limits[0]  # the base joint: unlimited in both
    assert spec.limits[1] is None  # the shoulder, limited in the plain file, has no range
    assert any("'shoulder'" in note and "read as unlimited" in note for note in spec.notes)


@pytest.mark.parametrize("kwargs, fragment", [
    (dict(tip="nope"), r"tip = 'nope' is not a link of the file: give one of its <link> names"),
    (dict(tip="column", base="hand"), r"tip = 'column' is not below base = 'hand'"),
    (dict(tip="hand", payload="-1 kg"), r"payload must be finite and >= 0"),
    (dict(tip="hand", payload="2 m"), r"payload"),
    (dict(payload="2 kg"), r"carried at the tip frame: give the tip link too"),
    (dict(tip=3), r"tip = 3: give a link's name"),
])
def test_a_bad_tip_base_or_payload_is_refused_by_name(kwargs, fragment):
    with pytest.raises(SpringlabError, match=fragment):
        load_arm(ARMS / "example_arm.urdf", **kwargs)


def test_tip_base_and_payload_apply_to_urdf_only_and_reach_the_command_line(tmp_path):
    with pytest.raises(SpringlabError, match=r"tip = 'hand' applies to URDF files only"):
        load_arm(ARMS / "example_arm.toml", tip="hand")
    gripper = _urdf(tmp_path, URDF.replace("</robot>", GRIPPER))
    code = main(["design", str(gripper), "--tip", "hand", "--payload", "0.5 kg", "--json", str(tmp_path / "d.json"),
                 "--method", "ground springs", "--quiet", "--max-designs", "1"])
    assert code == 0 and json.loads((tmp_path / "d.json").read_text())
    assert main(["design", str(gripper), "--tip", "nope", "--quiet"]) == 2
