"""A URDF that would be read into a false arm is refused, with a message that names the file, the
link or the parameter, its value and what to do: a COLLADA unit that is not a length, an inertia no
rigid body has, a ``package://`` path that leaves its package, a tip with no joint before it, a
xacro file not yet expanded; and a point mass at a point that is not one. Each case beside a control
that is still read."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from springlab.errors import MeshError, SpringlabError
from springlab.model.robots import OTHER_ARMS, ROBOTS, robot_urdf
from springlab.model.shapes import resolve_mesh
from springlab.model.urdf import read_revolute_chain, read_urdf
from springlab.workbench.cli import main

INERTIA = '<inertia ixx="0.03" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.002"/>'

ARM = """<robot name="two" {xmlns}>
  <link name="base_link"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper_link"><inertial><origin xyz="0 0 0.2"/><mass value="2"/>{upper_inertia}</inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.04" length="0.4"/></geometry></collision></link>
  <link name="forearm_link"><inertial><origin xyz="0 0 0.15"/><mass value="1"/>{fore_inertia}</inertial>
    <collision><geometry><mesh filename="{mesh}"/></geometry></collision></link>
  <link name="tool0"/>
  <joint name="shoulder_joint" type="revolute"><parent link="base_link"/><child link="upper_link"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="elbow_joint" type="revolute"><parent link="upper_link"/><child link="forearm_link"/>
    <origin xyz="0 0 0.4"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="forearm_link"/><child link="tool0"/><origin xyz="0 0 0.3"/></joint>
</robot>"""

STL = """solid tri
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 0.2 0 0
  vertex 0 0.1 0.05
 endloop
endfacet
endsolid tri
"""


def arm(mesh="tri.stl", fore_inertia=INERTIA, upper_inertia=INERTIA, xmlns=""):
    return ARM.format(mesh=mesh, fore_inertia=fore_inertia, upper_inertia=upper_inertia, xmlns=xmlns)


def refused_at_the_command_line(tmp_path, capsys, text, *flags) -> str:
    """The command's stderr for a URDF text it refuses: exit status 2, one line, no file written."""
    path = tmp_path / "two.urdf"
    path.write_text(text)
    out = tmp_path / "two.json"
    code = main(["design", str(path), "--json", str(out), "--quiet", *flags])
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.startswith("springlab: ") and err.count("\n") == 1, err
    assert not out.exists()
    return err


# -- a COLLADA mesh's unit ---------------------------------------------------------------------------------------

def _collada(tmp_path, meter: str | None, size=(0.06, 0.06, 0.3)) -> None:
    trimesh = pytest.importorskip("trimesh")
    text = trimesh.exchange.dae.export_collada(trimesh.creation.box(size))
    text = text.decode() if isinstance(text, bytes) else text
    if meter is not None:
        unit = f'<unit meter="{meter}" name="u"/>'
        text = re.sub(r"<unit[^>]*/>", unit, text) if "<unit" in text else text.replace("</asset>", unit + "</asset>")
    (tmp_path / "box.dae").write_text(text)


@pytest.mark.parametrize("meter", ["-1", "0", "-0.001", "nan", "inf", "abc"])
def test_a_collada_unit_that_is_not_a_finite_positive_length_is_refused(tmp_path, meter):
    _collada(tmp_path, meter)
    with pytest.raises(MeshError) as err:
        read_revolute_chain(arm(mesh="box.dae"), source="two.urdf", folder=tmp_path)
    message = str(err.value)
    assert "box.dae" in message and f"meter={meter!r}" in message.replace('"', "'")
    assert "metres" in message  # what to give


def test_a_collada_unit_refusal_reaches_the_command_line(tmp_path, capsys):
    _collada(tmp_path, "-1")
    err = refused_at_the_command_line(tmp_path, capsys, arm(mesh="box.dae"), "--reach", "0.05")
    assert "box.dae" in err and "-1" in err


@pytest.mark.parametrize(("meter", "size"), [("0.001", (60, 60, 300)), ("1", (0.06, 0.06, 0.3)), (None, (0.06, 0.06, 0.3))])
def test_a_collada_mesh_in_a_positive_unit_or_none_is_still_read(tmp_path, meter, size):
    _collada(tmp_path, meter, size)
    model = read_revolute_chain(arm(mesh="box.dae"), source="two.urdf", folder=tmp_path)
    assert model.outline[2][:, 2].min() == pytest.approx(-0.15, rel=1e-6)  # the box, 0.3 m long
    assert any("converted to metres" in note for note in model.notes) == (meter == "0.001")


# -- inertia ------------------------------------------------------------------------------------------------------

def _inertia(ixx, iyy, izz, ixy=0.0, ixz=0.0, iyz=0.0) -> str:
    return f'<inertia ixx="{ixx}" ixy="{ixy}" ixz="{ixz}" iyy="{iyy}" iyz="{iyz}" izz="{izz}"/>'


BAD_INERTIA = {
    "a negative moment": (_inertia(-0.5, 0.03, 0.03), "-0.5"),
    "a products term past the moments": (_inertia(0.03, 0.03, 0.03, ixy=0.05), "0.05"),
    "no triangle": (_inertia(0.01, 0.01, 0.03), "0.03"),
}


@pytest.mark.parametrize("case", BAD_INERTIA)
@pytest.mark.parametrize("reader", [read_revolute_chain, read_urdf])
def test_an_inertia_no_rigid_body_has_is_refused_naming_the_link(reader, case):
    inertia, value = BAD_INERTIA[case]
    with pytest.raises(SpringlabError) as err:
        reader(arm(fore_inertia=inertia), source="two.urdf", **({"shapes": False} if reader is read_revolute_chain else {}))
    message = str(err.value)
    assert "'forearm_link'" in message and value in message and "two.urdf" in message
    assert "principal moments" in message and "triangle" in message  # what a rigid body's must be


def test_an_inertia_refusal_reaches_the_command_line(tmp_path, capsys):
    err = refused_at_the_command_line(tmp_path, capsys, arm(fore_inertia=_inertia(-0.5, 0.03, 0.03)))
    assert "'forearm_link'" in err and "-0.5" in err


@pytest.mark.parametrize("inertia", [
    _inertia(0, 0, 0),  # a point mass
    "",  # no <inertia>: a point mass
    _inertia(0.01, 0.01, 0),  # a thin rod: the triangle's equality
    _inertia(0.01, 0.01, 0.02 * (1 + 1e-12)),  # a flat plate, with round-off in the file
    _inertia(0.01, 0.02, 0.025, ixy=0.001, ixz=-0.002, iyz=0.0005),
])
def test_a_physical_inertia_or_a_point_mass_is_read(inertia):
    model = read_revolute_chain(arm(fore_inertia=inertia), source="two.urdf", shapes=False)
    assert np.all(np.linalg.eigvalsh(model.inertia[2]) >= -1e-12)


def test_a_massless_link_is_read():
    text = arm().replace('<mass value="1"/>', '<mass value="0"/>')
    model = read_revolute_chain(text, source="two.urdf", shapes=False)
    assert model.mass[2] == 0 and any("carry no mass" in note for note in model.notes)


def test_an_inertia_the_arm_does_not_carry_is_not_refused():
    """A link fixed to the base (a sensor on a torso, say) is carried by the ground: its inertia is never
    used, and a whole robot is not refused for it when one of its arms is read."""
    text = arm().replace('<link name="tool0"/>', '<link name="tool0"/><link name="camera"><inertial><mass value="0.1"/>'
                         + _inertia(-1, 0.001, 0.001) + "</inertial></link>").replace(
        "</robot>", '<joint name="mount" type="fixed"><parent link="base_link"/><child link="camera"/></joint></robot>')
    model = read_revolute_chain(text, source="two.urdf", shapes=False, tip="tool0")
    assert model.n == 2 and any("'camera'" in note and "not used" in note for note in model.notes)
    with pytest.raises(SpringlabError, match="'camera'"):  # carried by the arm: refused
        read_revolute_chain(text.replace('<parent link="base_link"/><child link="camera"/>',
                                         '<parent link="forearm_link"/><child link="camera"/>'),
                            source="two.urdf", shapes=False, tip="tool0")


# -- package:// paths ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("filename", ["package://pkg/../../../../etc/passwd", "package://../x.stl",
                                      "package://pkg/meshes/../../x.stl", "package://./x.stl", "package://pkg/.."])
def test_a_package_path_that_leaves_its_package_is_refused(tmp_path, filename):
    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    (tmp_path / "x.stl").write_text(STL)
    (tmp_path / "pkg" / "x.stl").write_text(STL)
    with pytest.raises(MeshError) as err:
        resolve_mesh(filename, tmp_path / "pkg" / "meshes", (tmp_path,))
    assert repr(filename) in str(err.value) and "package" in str(err.value)
    with pytest.raises(MeshError) as err:
        read_revolute_chain(arm(mesh=filename), source="two.urdf", folder=tmp_path / "pkg" / "meshes")
    assert repr(filename) in str(err.value)


def test_a_package_path_refusal_reaches_the_command_line(tmp_path, capsys):
    (tmp_path / "pkg").mkdir()
    (tmp_path / "x.stl").write_text(STL)
    err = refused_at_the_command_line(tmp_path, capsys, arm(mesh="package://pkg/../x.stl"), "--package-dir",
                                      str(tmp_path))
    assert "'package://pkg/../x.stl'" in err


def test_a_package_path_within_its_package_and_file_paths_are_read_as_before(tmp_path):
    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    (tmp_path / "pkg" / "meshes" / "tri.stl").write_text(STL)
    (tmp_path / "x.stl").write_text(STL)
    inside = tmp_path / "pkg" / "meshes" / "tri.stl"
    assert resolve_mesh("package://pkg/meshes/../meshes/./tri.stl", None, (tmp_path,)).resolve() == inside
    assert resolve_mesh("package://pkg/meshes/tri.stl", tmp_path / "pkg" / "urdf").resolve() == inside
    assert resolve_mesh("package://pkg//meshes/tri.stl", None, (tmp_path,)).resolve() == inside  # as ROS joins it
    assert resolve_mesh(f"file://{tmp_path}/pkg/../x.stl", None).resolve() == tmp_path / "x.stl"
    assert resolve_mesh("../x.stl", tmp_path / "pkg").resolve() == tmp_path / "x.stl"


# -- a tip with no joint before it ---------------------------------------------------------------------------------

@pytest.mark.parametrize(("flags", "said"), [
    ({"tip": "base_link"}, "tip = 'base_link' is the base link itself"),
    ({"base": "forearm_link", "tip": "forearm_link"}, "tip = 'forearm_link' is the base link itself"),
    ({"base": "forearm_link", "tip": "tool0"}, "no revolute joint lies between base 'forearm_link' and tip 'tool0'"),
])
@pytest.mark.parametrize("reader", [read_revolute_chain, read_urdf])
def test_a_tip_with_no_joint_before_it_names_the_tip_the_base_and_the_joints(reader, flags, said):
    with pytest.raises(SpringlabError) as err:
        reader(arm(), source="two.urdf", **flags)
    message = str(err.value)
    assert said in message
    assert "'shoulder_joint'" in message and "'elbow_joint'" in message  # the file's revolute joints
    assert "'forearm_link'" in message and "'upper_link'" in message  # the tips to give
    assert "nothing moves" not in message


def test_a_tip_at_the_base_is_refused_at_the_command_line(tmp_path, capsys):
    err = refused_at_the_command_line(tmp_path, capsys, arm(), "--tip", "base_link")
    assert "'base_link'" in err and "'shoulder_joint'" in err
    err = refused_at_the_command_line(tmp_path, capsys, arm(), "--base", "forearm_link", "--tip", "forearm_link")
    assert "'forearm_link'" in err and "base link itself" in err


# -- xacro ---------------------------------------------------------------------------------------------------------

XACRO = """<?xml version="1.0"?>
<robot name="two" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="length" value="0.4"/>
  <xacro:macro name="segment" params="name">
    <link name="${name}"><inertial><mass value="1"/></inertial></link>
  </xacro:macro>
  <xacro:segment name="upper_link"/>
</robot>"""


@pytest.mark.parametrize("text", [
    XACRO,
    XACRO.replace(' xmlns:xacro="http://www.ros.org/wiki/xacro"', ""),  # the namespace left out: not even XML
    arm(mesh="$(find pkg)/meshes/x.stl"),  # a substitution left in an attribute
    arm().replace('<origin xyz="0 0 0.4"/>', '<origin xyz="0 0 ${length}"/>'),
])
def test_an_unexpanded_xacro_file_is_named_as_one(text):
    for reader in (read_revolute_chain, read_urdf):
        with pytest.raises(SpringlabError) as err:
            reader(text, source="arm.urdf.xacro")
        message = str(err.value)
        assert "xacro" in message and "expand" in message and "xacro arm.urdf.xacro > arm.urdf" in message
        assert "defines no <link>" not in message


def test_an_unexpanded_xacro_file_is_refused_at_the_command_line(tmp_path, capsys):
    err = refused_at_the_command_line(tmp_path, capsys, XACRO)
    assert "xacro" in err and "expand" in err


def test_an_expanded_file_that_keeps_the_xacro_namespace_is_read(tmp_path, capsys):
    """xacro's output keeps ``xmlns:xacro`` on its <robot> and says in a comment what it was made from."""
    text = "<!-- made by xacro from $(find pkg)/two.urdf.xacro: ${do not edit} -->\n" + arm(
        xmlns='xmlns:xacro="http://www.ros.org/wiki/xacro"')
    assert read_revolute_chain(text, source="two.urdf", shapes=False).n == 2
    path = tmp_path / "two.urdf"
    path.write_text(text)
    assert main(["design", str(path), "--json", str(tmp_path / "two.json"), "--quiet", "--max-designs", "1"]) == 0
    assert json.loads((tmp_path / "two.json").read_text())


# -- a point mass ---------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("point", [(0, float("nan"), 0), (0, float("inf"), 0), (0, 0), "abc", None])
def test_a_point_mass_at_a_point_that_is_not_one_names_point(point):
    model = read_revolute_chain(arm(), source="two.urdf", shapes=False)
    with pytest.raises(SpringlabError) as err:
        model.with_point_mass("tool0", point, 1.0)
    message = str(err.value)
    assert message.startswith("point = ") and "com" not in message
    assert model.with_point_mass("tool0", (0, 0, 0.1), 1.0).mass[2] == pytest.approx(2.0)


# -- the published arms -----------------------------------------------------------------------------------------------

def test_no_published_arm_is_refused_for_its_inertia_or_paths():
    """The 42 example-robot-data arms the tests and benchmarks use are still read: no link they carry has an
    inertia refused (the closest, TIAGo's arm_1_link, meets the triangle inequality with 2e-10 of its largest
    moment to spare), no file is taken for xacro. (Their meshes are read by test_real_arms and test_shapes.)"""
    for label in [*ROBOTS, *OTHER_ARMS]:
        robot = ROBOTS.get(label) or OTHER_ARMS[label]
        path = robot_urdf(label)
        read_revolute_chain(path.read_text(), source=path.name, tip=robot.tip, base=robot.base, shapes=False)


@pytest.mark.parametrize(("flags", "named"), [(("--samples", "50"), "--samples must be an integer >= 100"),
                                              (("--samples", "-3"), "--samples must be an integer >= 100"),
                                              (("--fit-poses", "5"), "--fit-poses must be an integer >= 20")])
def test_too_few_check_or_fitting_poses_are_refused(tmp_path, capsys, flags, named):
    assert named in refused_at_the_command_line(tmp_path, capsys, arm(), *flags)


def test_the_check_poses_asked_for_are_the_ones_checked(tmp_path, capsys):
    path = tmp_path / "two.urdf"
    path.write_text(arm())
    out = tmp_path / "two.json"
    assert main(["design", str(path), "--json", str(out), "--quiet", "--samples", "150"]) in (0, 3)
    assert "checked by route 2 on 15" in capsys.readouterr().out  # 150 and the audit's worst poses


def test_check_poses_are_an_arm_files_own_and_refused_beside_it(tmp_path, capsys):
    out = tmp_path / "a.json"
    assert main(["design", "notebooks/arms/paper000_arm.toml", "--samples", "500", "--json", str(out), "--quiet"]) == 2
    assert "[workspace] table" in capsys.readouterr().err and not out.exists()
