"""Where springs attach on a real arm: each body's outline from its URDF geometry (collision
shapes, meshes found as ROS finds them), checked against Pinocchio's own placement of the same
geometry, and the designs' ends kept within the outlines' boxes."""

import dataclasses
import json
import math
import re

import numpy as np
import pytest

from springlab.design.arms import ends_outside
from springlab.design.structure import BRACKET, attachment_boxes, planar_springs, structure
from springlab.energy import geometry
from springlab.model.robots import load_robot, robot_urdf, robots_folder
from springlab.model.shapes import ROUND_POINTS, Shape, link_shapes, resolve_mesh, shape_points
from springlab.model.springs import PointSpring
from springlab.model.urdf import read_revolute_chain
from springlab.workbench.cli import main
from springlab.workbench.real_arms import outline_difference

STL = """solid tri
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 0.2 0 0
  vertex 0 0.1 0.05
 endloop
endfacet
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 0.2 0 0
  vertex 0 0 -0.03
 endloop
endfacet
endsolid tri
"""

ARM = """<robot name="two"><link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry>
    <origin xyz="0 0 0.05"/></collision></link>
  <link name="upper"><inertial><origin xyz="0 0 0.2"/><mass value="2"/></inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.04" length="0.4"/></geometry></collision></link>
  <link name="fore"><inertial><origin xyz="0 0 0.15"/><mass value="1"/></inertial>
    <visual><geometry><mesh filename="{mesh}" scale="1 2 1"/></geometry></visual></link>
  <link name="tool"><collision><geometry><sphere radius="0.03"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0 0 0.4"/>
    <axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="fore"/><child link="tool"/><origin xyz="0 0 0.3"/></joint>
</robot>"""


def _arm(tmp_path, mesh="meshes/tri.stl", **kw):
    (tmp_path / "meshes").mkdir(exist_ok=True)
    (tmp_path / "meshes" / "tri.stl").write_text(STL)
    text = ARM.format(mesh=mesh)
    return read_revolute_chain(text, source="two.urdf", folder=tmp_path, **kw), text


def test_each_primitive_is_bounded_by_its_points():
    T = np.eye(4)
    T[:3, 3] = [1, 2, 3]
    box = shape_points(Shape("box", T, (0.2, 0.4, 0.6)))
    np.testing.assert_allclose(box.min(0), [0.9, 1.8, 2.7])
    np.testing.assert_allclose(box.max(0), [1.1, 2.2, 3.3])
    cyl = shape_points(Shape("cylinder", np.eye(4), (0.05, 0.4)))
    np.testing.assert_allclose(np.hypot(cyl[:, 0], cyl[:, 1]), 0.05)  # on the surface
    np.testing.assert_allclose([cyl[:, 2].min(), cyl[:, 2].max()], [-0.2, 0.2])
    ball = shape_points(Shape("sphere", np.eye(4), (0.1,)))
    np.testing.assert_allclose(np.linalg.norm(ball, axis=1), 0.1)
    # the hull lies inside by at most r (1 - cos(pi / ROUND_POINTS)) along any axis
    assert ball[:, 0].max() >= 0.1 * math.cos(math.pi / ROUND_POINTS) - 1e-15
    capsule = shape_points(Shape("capsule", np.eye(4), (0.05, 0.4)))
    np.testing.assert_allclose([capsule[:, 2].min(), capsule[:, 2].max()], [-0.25, 0.25])


def test_an_arms_outline_is_in_each_bodys_frame(tmp_path):
    model, _ = _arm(tmp_path)
    base, upper, fore = model.outline
    np.testing.assert_allclose([base.min(0), base.max(0)], [[-0.1, -0.1, 0], [0.1, 0.1, 0.1]], atol=1e-12)
    np.testing.assert_allclose([upper[:, 2].min(), upper[:, 2].max()], [0, 0.4], atol=1e-12)
    # the forearm carries its (visual) mesh, y scaled by 2, and the tool's sphere 0.3 m out (a fixed link)
    np.testing.assert_allclose(fore.min(0), [-0.03, -0.03, -0.03], atol=1e-12)
    np.testing.assert_allclose(fore.max(0), [0.2, 0.2, 0.33], atol=1e-12)
    assert any("outlines" in note and "4 shapes" in note for note in model.notes)


def test_meshes_are_found_as_ros_finds_them(tmp_path, monkeypatch):
    pkg = tmp_path / "share" / "my_arm"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "meshes" / "tri.stl").write_text(STL)
    urdf_folder = pkg / "urdf"
    urdf_folder.mkdir()
    name = "package://my_arm/meshes/tri.stl"
    assert resolve_mesh(name, urdf_folder) == pkg / "meshes" / "tri.stl"  # a folder above, named as the package
    assert resolve_mesh(name, tmp_path / "elsewhere") is None
    assert resolve_mesh(name, None, [tmp_path / "share"]) == pkg / "meshes" / "tri.stl"
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "share"))
    assert resolve_mesh(name, None) == pkg / "meshes" / "tri.stl"
    monkeypatch.delenv("ROS_PACKAGE_PATH")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path))
    assert resolve_mesh(name, None) == pkg / "meshes" / "tri.stl"
    assert resolve_mesh("file://" + str(pkg / "meshes" / "tri.stl"), None) == pkg / "meshes" / "tri.stl"
    assert resolve_mesh("meshes/tri.stl", pkg) == pkg / "meshes" / "tri.stl"


def test_a_missing_or_broken_mesh_is_named_and_left_out(tmp_path):
    model, _ = _arm(tmp_path, mesh="package://nowhere/tri.stl")
    assert any("1 mesh not found ('package://nowhere/tri.stl')" in note for note in model.notes)
    np.testing.assert_allclose(model.outline[2].max(0), [0.03, 0.03, 0.33])  # the tool's sphere only
    (tmp_path / "broken.stl").write_bytes(b"\x00" * 7)
    model, _ = _arm(tmp_path, mesh="broken.stl")
    assert any("could not be read" in note for note in model.notes)


def test_a_malformed_shape_is_skipped_with_a_note():
    shapes, notes = link_shapes('<robot><link name="a"><collision><geometry><box size="1 nan 2"/></geometry>'
                                '</collision><visual><geometry><sphere radius="0.1"/></geometry></visual></link></robot>')
    assert "malformed" in notes[0]
    collision, visual = shapes["a"]
    assert collision == () and visual[0].kind == "sphere"  # no usable collision shape: the visual one


def test_a_file_without_geometry_keeps_the_default_reach():
    text = ARM.format(mesh="x.stl").replace("<collision>", "<!--").replace("</collision>", "-->")
    text = text.replace("<visual>", "<!--").replace("</visual>", "-->")
    model = read_revolute_chain(text, source="two.urdf")
    assert model.outline == ()
    centres, half = attachment_boxes(model, None)
    assert np.all(half >= 0.05)  # the link and a 5 cm bracket at least


@pytest.mark.parametrize("label", ["UR5", "Panda", "Kinova Jaco", "Z1", "Talos left arm", "Baxter left arm"])
def test_outlines_agree_with_pinocchios_geometry(label):
    """Pinocchio reads the file and its meshes itself (assimp, not trimesh) and places every
    collision object; each body's bounding box at random poses must agree with ours: meshes
    exactly (ours are their hulls' vertices), round shapes within r (1 - cos(pi / 64)), below
    3e-4 m for these arms' radii below 0.25 m. Bodies whose geometry is visual only (Pinocchio
    reads collision geometry) are not compared. STL, COLLADA (Kinova), cylinders and STL (Z1), a
    torso's meshes (Talos), boxes, spheres and cylinders (Baxter); the SO-101 in the Real arms
    chapter, all twelve in `make bench`."""
    pytest.importorskip("pinocchio")
    model = load_robot(label)
    assert outline_difference(label, model, model.random_q(2, 3)) < 3e-4


def test_a_misplaced_outline_fails_the_pinocchio_check():
    """Negative control: the same comparison on outlines shifted by 1 cm must fail."""
    pytest.importorskip("pinocchio")
    model = load_robot("Panda")
    shifted = dataclasses.replace(model, outline=tuple(p + [0.0, 0.01, 0.0] for p in model.outline))
    assert outline_difference("Panda", shifted, model.random_q(1, 3)) > 3e-4


@pytest.mark.parametrize("label", ["UR5", "UR10"])
def test_exact_springs_stay_on_the_outlines(label):
    model = load_robot(label)
    springs = planar_springs(model, structure(model))
    assert ends_outside(model, springs) < 1e-9
    q = model.random_q(300, 4)
    scale = np.max(np.abs(geometry.gravity_torques(model, q)))
    assert np.max(np.abs(geometry.joint_torques(model, springs, q))) < 1e-11 * scale
    # no bracket: still exact, each end on its body's geometry box
    tight = planar_springs(model, structure(model), reach=0.0)
    assert ends_outside(model, tight, 0.0) < 1e-9 < ends_outside(model, springs, 0.0)  # the bracket was used
    assert np.max(np.abs(geometry.joint_torques(model, tight, q))) < 1e-11 * scale


def test_the_bracket_is_the_default_reach_beyond_the_outline():
    model = load_robot("SO-101")
    centres, half = attachment_boxes(model, None)
    lo, hi = model.outline[2].min(0), model.outline[2].max(0)
    np.testing.assert_allclose(half[2], (hi - lo) / 2 + BRACKET)


def test_the_cli_takes_package_dirs_and_refuses_a_missing_one(tmp_path, capsys):
    out = tmp_path / "ur5.json"
    share = robots_folder().parent.parent
    assert main(["design", str(robot_urdf("UR5")), "--tip", "wrist_3_link", "--package-dir", str(share),
                 "--reach", "0", "--json", str(out), "--quiet", "--pulley-radius", "0",
                 "--samples", "300", "--audit-samples", "2000"]) == 3  # flagged: not clear
    data = json.loads(out.read_text())
    assert data["inputs"]["package_dirs"] == [str(share)] and data["inputs"]["reach_m"] == 0.0
    flags = data["status"]["flags"]
    assert any("cannot be mounted" in f for f in flags)  # the meshes found: clearance measured
    assert all("cannot be mounted" in f or "reaches past the joint" in f or "fail in fatigue" in f for f in flags)
    assert "outline (the bounding box of its URDF geometry) and 0 cm beyond it" in capsys.readouterr().out
    out.unlink()
    code = main(["design", str(robot_urdf("UR5")), "--tip", "wrist_3_link", "--package-dir",
                 str(tmp_path / "nowhere"), "--json", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "--package-dir" in err and err.count("\n") == 1 and not out.exists()


def test_a_collision_mesh_not_found_falls_back_to_the_visual_shapes(tmp_path):
    text = ARM.format(mesh="x.stl").replace(
        '<collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.04" length="0.4"/></geometry></collision>',
        '<collision><geometry><mesh filename="package://nowhere/upper.stl"/></geometry></collision>'
        '<visual><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.04" length="0.4"/></geometry></visual>')
    model = read_revolute_chain(text, source="two.urdf", folder=tmp_path)
    np.testing.assert_allclose([model.outline[1][:, 2].min(), model.outline[1][:, 2].max()], [0, 0.4], atol=1e-12)
    assert any("package 'nowhere' with --package-dir" in note for note in model.notes)


@pytest.mark.parametrize(("size", "message"), [("1e9 1e9 1e9", "more than"), ("0 0 0", "a point")])
def test_an_outline_out_of_proportion_is_ignored_with_a_note(size, message):
    text = ARM.format(mesh="x.stl").replace('<box size="0.2 0.2 0.1"/>', f'<box size="{size}"/>')
    model = read_revolute_chain(text, source="two.urdf")
    assert len(model.outline[0]) == 0  # the base falls back to the default reach
    assert any("'base'" in note and message in note for note in model.notes)
    assert np.all(np.isfinite(attachment_boxes(model)[1]))


def test_a_collada_mesh_in_millimetres_is_read_in_metres(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    text = trimesh.exchange.dae.export_collada(trimesh.creation.box([60, 60, 300]))
    text = text.decode() if isinstance(text, bytes) else text
    unit = '<unit meter="0.001" name="millimeter"/>'
    text = re.sub(r"<unit[^>]*/>", unit, text) if "<unit" in text else text.replace("</asset>", unit + "</asset>")
    (tmp_path / "box.dae").write_text(text)
    model = read_revolute_chain(ARM.format(mesh="box.dae"), source="two.urdf", folder=tmp_path)
    fore = model.outline[2]  # the box, 0.3 m long, y scaled by 2, and the tool's sphere 0.3 m out
    np.testing.assert_allclose([fore[:, 1].min(), fore[:, 2].min(), fore[:, 2].max()], [-0.06, -0.15, 0.33], atol=1e-9)
    assert any("converted to metres" in note for note in model.notes)


def test_a_reach_longer_than_the_arm_is_refused(tmp_path, capsys):
    out = tmp_path / "so101.json"
    code = main(["design", str(robot_urdf("SO-101")), "--reach", "3", "--json", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "longer than the arm itself" in err and err.count("\n") == 1 and not out.exists()


def test_reach_or_package_dir_designs_a_line_chain_urdf_on_the_general_model(tmp_path, capsys):
    path = tmp_path / "two.urdf"  # a planar arm with its links on one line: paper 000's method would take it
    _arm(tmp_path)
    path.write_text(ARM.format(mesh="meshes/tri.stl"))
    out = tmp_path / "two.json"
    assert main(["design", str(path), "--json", str(out), "--quiet", "--max-designs", "1"]) == 0
    assert "general model" not in capsys.readouterr().out and "ideal" not in json.loads(out.read_text())
    # flagged (exit 3) where the springs on the outlines' faces run through the other link's mesh
    assert main(["design", str(path), "--reach", "0", "--json", str(out), "--quiet", "--pulley-radius", "0"]) in (0, 3)
    data = json.loads(out.read_text())
    assert all("cannot be mounted" in f or "fail in fatigue" in f for f in data["status"]["flags"])
    assert data["inputs"]["reach_m"] == 0.0 and data["ideal"]
    model = read_revolute_chain(path.read_text(), source="two.urdf", folder=tmp_path)
    springs = [PointSpring(**{key: s[key] for key in ("link_a", "point_a", "link_b", "point_b", "k")})
               for s in data["ideal"]]
    assert ends_outside(model, springs, 0.0) < 1e-9  # on the outlines, no bracket
    assert main(["design", str(path), "--reach", "abc", "--json", str(out), "--quiet"]) == 2
    assert "--reach" in capsys.readouterr().err
    code = main(["design", "notebooks/arms/paper001_arm.toml", "--reach", "3 cm", "--json", str(out), "--quiet"])
    assert code == 2 and "--reach applies to arms for paper 000's method" in capsys.readouterr().err


def test_clearance_is_measured_from_the_outlines_and_can_fail(tmp_path):
    """The two-link arm's base is a 0.2 x 0.2 x 0.1 m box: a spring from the upper arm to the forearm
    straight above it, starting 0.25 m above its top, passes it at 0.25 m (less half the sampling's
    spacing, the bound's margin); one run from inside the box passes through it (negative), the check
    that must be able to fail."""
    from springlab.design.arms import clearance

    model, _ = _arm(tmp_path)
    q = np.zeros((1, 2))  # both links straight up from the shoulder at z = 0.1
    above = PointSpring("upper", (0.0, 0.0, 0.25), "fore", (0.0, 0.0, 0.1), 10.0)  # z = 0.35 to 0.6 m
    through = PointSpring("upper", (0.0, 0.0, -0.05), "fore", (0.3, 0.0, 0.1), 10.0)  # from inside the base box
    table = clearance(model, [above, through], q)
    far, inside = (float(row[2]) for row in table.rows)
    assert table.rows[0][1] == "base" and far == pytest.approx(250.0 - 0.5 * 250 / 31, abs=0.05)
    assert inside < 0 and table.rows[1][3] == "yes"


def test_a_cable_whose_ends_meet_runs_over_a_point_pulley(tmp_path):
    """A spring whose ends pass within the pulley's radius of each other (here 4 mm apart, across the
    elbow) cannot wrap a 5 mm pulley: it is realised with a point pulley and named, never a crash."""
    from springlab.design.realise import realise_springs

    model, _ = _arm(tmp_path)
    spring = PointSpring("upper", (0.0, 0.004, 0.4), "fore", (0.0, 0.0, 0.0), 50.0)
    q = model.random_q(100, 1)
    realised, kinds, _ = realise_springs(model, [spring], q, pulley_radius=0.005)
    assert all(r is None or r.pulley_radius == 0 for r in realised)
    assert all("point pulley" in kind or kind.startswith(("zero-length", "not realised")) for kind in kinds)
