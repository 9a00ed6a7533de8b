"""MuJoCo beside springlab's routes: an arm exported with its springs (springlab.model.mjcf) is held
at rest by the same torques as route 2, the realised cables over their pulleys too, the file loaded
as written with only the arm's joints set; its gravity is Pinocchio's on the original URDF, released
at rest the exact design stays put while the 0.9-rate control falls, and a tendon with the wrong
rate fails the agreement (the negative control). The file's generated names never clash with the
arm's. Bad --mjcf input is refused before anything is written."""

import json

import numpy as np
import pytest

from springlab.design.arms import design_model
from springlab.energy import geometry
from springlab.model.chain import point_springs
from springlab.model.mjcf import TINY_MASS, to_mjcf
from springlab.model.robots import load_robot, robot_urdf
from springlab.model.springs import PointSpring
from springlab.workbench.cli import main

mujoco = pytest.importorskip("mujoco")
from springlab.workbench.references import (  # noqa: E402
    mujoco_holding_torques,
    mujoco_release,
    pinocchio_gravity,
)

AGREE = 1e-9
"""Relative agreement of MuJoCo's and route 2's holding torques: both evaluate the same rigid-body
and spring sums in float64 (about 1e-15); the real-arms target is 1e-9."""


@pytest.fixture(scope="module")
def designs(ur5_two_point):
    """The UR5's and the Panda's designs, the realised cable springs over 5 mm pulleys (the ideal
    springs are the same with or without pulleys)."""
    panda = design_model(load_robot("Panda"), samples=200, fit_poses=100, pulley_radius=0.005, collisions=False,
                         audit_samples=500)  # MuJoCo against route 2: the limits' box and a short re-check do
    return {"UR5": ur5_two_point, "Panda": panda}


@pytest.mark.parametrize("label", ["UR5", "Panda"])
def test_mujoco_holds_the_design_as_route_2_does(designs, label):
    design = designs[label]
    model, q = design.model, design.q[:20]
    ours = geometry.joint_torques(model, design.ideal, q)
    scale = np.max(np.abs(geometry.gravity_torques(model, q)))
    theirs = mujoco_holding_torques(to_mjcf(model, design.ideal), model, q)
    assert np.max(np.abs(theirs - ours)) < AGREE * scale
    # the negative control: one tendon at 0.9 of its rate must fail the same comparison
    wrong = list(design.ideal)
    wrong[0] = wrong[0].scaled(0.9)
    off = mujoco_holding_torques(to_mjcf(model, wrong), model, q)
    assert np.max(np.abs(off - ours)) > 1e3 * AGREE * scale


def _held_as_written(mjcf: str, model, q) -> np.ndarray:
    """MuJoCo's holding torques (N m), qfrc_bias - qfrc_passive after mj_forward, of the MJCF text loaded
    as written, only the arm's joints set to ``q`` (N, n) rad (every other coordinate left as loaded)."""
    mj = mujoco.MjModel.from_xml_string(mjcf)
    data = mujoco.MjData(mj)
    joints = [mj.joint(name) for name in model.joints]
    out = np.empty(q.shape)
    for p, angles in enumerate(q):
        mujoco.mj_resetData(mj, data)
        for joint, angle in zip(joints, angles, strict=True):
            data.qpos[joint.qposadr[0]] = angle
        mujoco.mj_forward(mj, data)
        out[p] = [(data.qfrc_bias - data.qfrc_passive)[joint.dofadr[0]] for joint in joints]
    return out


@pytest.mark.parametrize("label", ["UR5", "Panda"])
def test_the_realised_file_holds_route_2s_torques_as_written(designs, label):
    """The realised file opened in MuJoCo as it is, only the arm's joints set (random poses within
    their limits): the cables over their pulleys hold what route 2 holds, with nothing to turn."""
    design = designs[label]
    model = design.model
    assert sum(s.pulley_radius > 0 for s in design.realised) >= 3
    q = model.random_q(24, 11)
    held = _held_as_written(to_mjcf(model, design.realised), model, q)
    ours = geometry.joint_torques(model, design.realised, q)
    scale = np.max(np.abs(geometry.gravity_torques(model, q)))
    assert np.max(np.abs(held - ours)) < AGREE * scale


TWO_JOINTS = """<robot name="two">
  <link name="base"/>
  <link name="turn"><inertial><origin xyz="0 0 0.05"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><origin xyz="0 0 0.2"/><mass value="2"/>
    <inertia ixx="0.02" iyy="0.02" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="yaw" type="revolute"><parent link="base"/><child link="turn"/><axis xyz="0 0 1"/>
    <limit lower="-3.1416" upper="3.1416" effort="1" velocity="1"/></joint>
  <joint name="pitch" type="revolute"><parent link="turn"/><child link="arm"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="-3.1416" upper="3.1416" effort="1" velocity="1"/></joint>
</robot>"""
"""A turntable (yaw about z) and an arm pitching on it about y, 0.1 m up."""


def test_a_cable_is_held_from_every_side_of_its_lead():
    """Two cables from A on the lead's line (u = +z, A on both joints' axes) to B on the arm: the
    pitch is the angle alpha between the lead and B - A, from next to 0 (B straight ahead, the path
    S -> B through the pulley) to next to pi (B behind A, the straight path clear of it). The first
    is on the base, so the yaw swings B all round its lead; the second on the turntable, where B
    keeps to one plane through the lead. MuJoCo holds route 2's torques at every side of the lead
    but within SIDE_TILT rad of the lead's line behind A (the side sites' one limit)."""
    from springlab.model.mjcf import SIDE_TILT
    from springlab.model.urdf import read_revolute_chain

    model = read_revolute_chain(TWO_JOINTS, source="two.urdf")
    springs = [PointSpring("base", (0.0, 0.0, 0.1), "arm", (0.0, 0.0, 0.3), 200.0, 0.05, 2.0, pulley_radius=0.01,
                           lead=(0.0, 0.0, 1.0)),
               PointSpring("turn", (0.0, 0.0, 0.1), "arm", (0.01, 0.0, 0.25), 150.0, 0.04, 1.0, pulley_radius=0.008,
                           lead=(0.0, 0.0, 1.0))]
    alphas = [1e-6, 1e-3, 0.3, 1.0, np.pi / 2, 2.0, 3.0, np.pi - 1e-3, np.pi - 10 * SIDE_TILT]
    yaws = np.random.default_rng(4).uniform(-np.pi, np.pi, 8)
    q = np.array([(yaw, alpha) for alpha in alphas for yaw in (0.0, *yaws)])
    mjcf = to_mjcf(model, springs)
    ours = geometry.joint_torques(model, springs, q)
    assert np.max(np.abs(_held_as_written(mjcf, model, q) - ours)) < AGREE * np.max(np.abs(ours))


def test_generated_names_never_clash_with_the_arms():
    """Links and joints named as the file's generated elements (the pulley 'S1 pulley', the sites
    'S1 A', 'S1 side 1', 'S2 B', the tendon 'S2', the mesh 'outline gripper_link', the former
    'S1 swivel'), and a '--' that an XML comment may not hold: MuJoCo loads the file, every name in
    it once, and holds route 2's torques."""
    import re

    from springlab.model.urdf import read_revolute_chain

    path = robot_urdf("SO-101")
    text = path.read_text()
    renamed = {"shoulder_link": "S1 pulley", "upper_arm_link": "S1 A", "lower_arm_link": "outline gripper_link",
               "wrist_link": "S2", "base_link": "base--link", "shoulder_lift": "S1 swivel", "elbow_flex": "S1 side 1",
               "wrist_flex": "S2 B"}
    for old, new in renamed.items():
        text = text.replace(f'"{old}"', f'"{new}"')
    model = read_revolute_chain(text, source=path.name, folder=path.parent)
    assert set(renamed.values()) <= {*model.bodies, *model.joints}
    springs = [PointSpring("S1 pulley", (0.0, 0.01, 0.03), "outline gripper_link", (0.02, 0.0, 0.01), 300.0, 0.02, 1.0,
                           pulley_radius=0.004, lead=(0.0, 0.0, -1.0)),
               PointSpring("base--link", (0.02, 0.0, 0.05), "S2", (0.0, 0.01, 0.02), 80.0, 0.03, 2.4)]
    mjcf = to_mjcf(model, springs)
    mj = mujoco.MjModel.from_xml_string(mjcf)  # MuJoCo refuses a repeated name
    names = re.findall(r'\bname="([^"]*)"', mjcf)
    assert len(names) == len(set(names)) and "outline gripper_link" in names
    assert mj.nq == model.n
    q = model.random_q(10, 3)
    ours = geometry.joint_torques(model, springs, q)
    assert np.max(np.abs(_held_as_written(mjcf, model, q) - ours)) < AGREE * np.max(np.abs(ours))


def test_realised_springs_keep_their_force_law_in_mujoco():
    """A spring of free length L_0 and initial tension F_i pulls F_i + k (l - L_0): MuJoCo's tendon
    spring k (l - springlength) with springlength = L_0 - F_i / k."""
    model = load_robot("SO-101")
    springs = [PointSpring("shoulder_link", (0.01, 0.02, 0.03), "lower_arm_link", (0.05, 0.0, 0.01), 300.0,
                           0.04, 5.0),
               PointSpring("base_link", (0.02, 0.0, 0.05), "wrist_link", (0.0, 0.01, 0.02), 80.0, 0.03, 2.4)]
    q = model.random_q(10, 2)
    ours = geometry.joint_torques(model, springs, q)
    theirs = mujoco_holding_torques(to_mjcf(model, springs), model, q)
    assert np.max(np.abs(theirs - ours)) < AGREE * np.max(np.abs(ours))


@pytest.mark.parametrize("label", ["UR5", "Panda", "SO-101", "Kinova Jaco"])
def test_mujocos_gravity_is_pinocchios_on_the_urdf(label):
    """URDF -> springlab's model -> MJCF -> MuJoCo against URDF -> Pinocchio: the export end to end."""
    pytest.importorskip("pinocchio")
    model = load_robot(label)
    q = model.random_q(10, 4)
    theirs = mujoco_holding_torques(to_mjcf(model), model, q)
    reference = pinocchio_gravity(robot_urdf(label).read_text(), model, q)
    massless = int(np.sum(model.mass == 0))  # MuJoCo needs a mass: TINY_MASS kg each, at most a metre out
    bound = AGREE * np.max(np.abs(reference)) + massless * TINY_MASS * model.g
    assert np.max(np.abs(theirs - reference)) < bound


def test_a_papers_chain_exports_with_its_spherical_joints(arm, exact_springs, rng):
    """Paper 000's arm (spherical joints as three revolute ones, two massless bodies each) with its
    exact design, held by MuJoCo as by route 2 on the general model: the torques at round-off, the
    massless bodies' TINY_MASS aside."""
    model, springs = arm.revolute_chain(), point_springs(arm, exact_springs)
    q = arm.joint_coordinates(arm.random_angles(20, rng))
    ours = geometry.joint_torques(model, springs, q)
    theirs = mujoco_holding_torques(to_mjcf(model, springs), model, q)
    scale = np.max(np.abs(geometry.gravity_torques(model, q)))
    assert np.max(np.abs(theirs - ours)) < AGREE * scale
    assert np.max(np.abs(theirs)) < AGREE * scale  # balanced in MuJoCo too


def test_released_the_exact_design_stays_and_the_control_falls(designs):
    design = designs["UR5"]
    q0 = design.q[0]
    _, held = mujoco_release(to_mjcf(design.model, design.ideal), q0, 1.0)
    _, falls = mujoco_release(to_mjcf(design.model, [s.scaled(0.9) for s in design.ideal]), q0, 1.0)
    assert np.max(np.abs(held - q0)) < 1e-9  # rad after 1 s
    assert np.max(np.abs(falls - q0)) > 0.1


def test_the_cli_writes_both_models(tmp_path, capsys):
    out = tmp_path / "ur5.json"
    mjcf = tmp_path / "ur5_balanced.xml"
    assert main(["design", str(robot_urdf("UR5")), "--layout", "two-point", "--json", str(out), "--mjcf", str(mjcf),
                 "--samples", "300", "--audit-samples", "2000", "--quiet"]) == 3  # flagged: the two-point springs run through the links
    assert mjcf.exists() and (tmp_path / "ur5_balanced.realised.xml").exists()
    # the --json contract read alone rebuilds the realised springs over their pulleys: route 2 on them is
    # what MuJoCo holds with the realised file
    data = json.loads(out.read_text())
    cables = [s for s in data["realised"] if "pulley_radius" in s]  # (a spring whose ends come near: a point)
    assert cables and len({s["pulley_radius"] for s in cables}) == 1  # one pulley, sized to the strongest cable
    assert all(s["pulley_radius"] > 0.005 and len(s["lead"]) == 3 for s in cables)
    fields = ("link_a", "point_a", "link_b", "point_b", "k", "free_length", "initial_tension", "pulley_radius", "lead")
    springs = [PointSpring(**{key: s[key] for key in fields if key in s}) for s in data["realised"]]
    model = load_robot("UR5")
    q = model.random_q(20, 9)
    realised = (tmp_path / "ur5_balanced.realised.xml").read_text()
    ours = geometry.joint_torques(model, springs, q)
    assert np.max(np.abs(mujoco_holding_torques(realised, model, q) - ours)) < AGREE * 100
    mj = mujoco.MjModel.from_xml_path(str(mjcf))
    assert mj.ntendon == 6 and mj.nq == 6
    names = [mujoco.mj_id2name(mj, mujoco.mjtObj.mjOBJ_JOINT, i) for i in range(mj.njnt)]
    assert names == ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint",
                     "wrist_3_joint"]
    assert np.allclose(mj.jnt_range[2], [-np.pi, np.pi], atol=1e-9)  # the URDF's limits
    # an arm file of paper 000's method exports too
    assert main(["design", "notebooks/arms/paper000_arm.toml", "--json", str(tmp_path / "a.json"),
                 "--mjcf", str(tmp_path / "a.xml"), "--quiet"]) == 0
    assert mujoco.MjModel.from_xml_path(str(tmp_path / "a.xml")).ntendon >= 1


def test_a_pulley_larger_than_a_link_is_refused(tmp_path, capsys):
    out = tmp_path / "so101.json"
    code = main(["design", str(robot_urdf("SO-101")), "--pulley-radius", "0.05", "--json", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "pulley_radius = 0.05 m is larger than link" in err and err.count("\n") == 1
    assert not out.exists()


MJCF_BAD = [
    (["notebooks/arms/paper001_arm.toml"], "pseudobase"),
    ([None, "--mjcf", "{tmp}"], "is a directory"),
    ([None, "--mjcf", "{tmp}/missing/x.xml"], "does not exist"),
    ([None, "--mjcf", "{tmp}/x.txt"], "ending in .xml"),
]


@pytest.mark.parametrize(("args", "message"), MJCF_BAD, ids=[m for _, m in MJCF_BAD])
def test_bad_mjcf_is_one_line_exit_2_nothing_written(args, message, tmp_path, capsys):
    out = tmp_path / "d.json"
    arm = args[0] or str(robot_urdf("UR5"))
    extra = [a.format(tmp=tmp_path) for a in args[1:]] or ["--mjcf", str(tmp_path / "x.xml")]
    code = main(["design", arm, "--json", str(out), "--quiet", *extra])
    err = capsys.readouterr().err
    assert code == 2 and message in err and err.count("\n") == 1
    assert not out.exists() and not list(tmp_path.glob("*.xml"))


@pytest.fixture(scope="module")
def ur5_pulleys(ur5_two_point):
    return ur5_two_point


def test_the_ur5_over_5_mm_pulleys_keeps_90_percent_by_route_2_and_mujoco(ur5_pulleys):
    design = ur5_pulleys
    assert all(r.pulley_radius == 0.005 for r, kind in zip(design.realised, design.kinds, strict=True)
               if kind == "cable over a pulley")
    removed = design.removed("realised")
    assert all(removed[i] >= 90 for i in design.structure.loaded)
    model, q = design.model, design.q
    held = mujoco_holding_torques(to_mjcf(model, design.realised), model, q)
    ours = geometry.joint_torques(model, design.realised, q)
    scale = np.max(np.abs(geometry.gravity_torques(model, q)))
    assert np.max(np.abs(held - ours)) < AGREE * scale  # MuJoCo's wrapped spheres: route 2's cable path
    # negative control: the same springs exported with 4 mm pulleys must disagree
    smaller = [PointSpring(**(s.as_dict() | {"pulley_radius": 0.004})) if s.pulley_radius else s
               for s in design.realised]
    off = mujoco_holding_torques(to_mjcf(model, smaller), model, q[:50])
    assert np.max(np.abs(off - ours[:50])) > 1e3 * AGREE * scale


def test_route_2s_pulley_torques_are_the_energys_gradient(ur5_pulleys):
    model, springs = ur5_pulleys.model, ur5_pulleys.realised
    q = ur5_pulleys.q[:4]
    torques = geometry.joint_torques(model, springs, q)
    step = 1e-6
    for j in range(model.n):
        e = np.zeros(model.n)
        e[j] = step
        slope = (geometry.potential(model, springs, q + e)["total"] - geometry.potential(model, springs, q - e)["total"])
        np.testing.assert_allclose(slope / (2 * step), torques[:, j], atol=1e-6)


def test_a_pulley_spring_is_checked_and_exudyn_refuses_it():
    from springlab.energy import simulation
    from springlab.errors import SpringlabError

    with pytest.raises(SpringlabError, match="lead of"):
        PointSpring("a", (0, 0, 0), "b", (0, 0, 1), 10.0, pulley_radius=0.01)
    with pytest.raises(SpringlabError, match="pulley_radius of"):
        PointSpring("a", (0, 0, 0), "b", (0, 0, 1), 10.0, pulley_radius=-0.01, lead=(1, 0, 0))
    with pytest.raises(SpringlabError, match="give pulley_radius > 0"):
        PointSpring("a", (0, 0, 0), "b", (0, 0, 1), 10.0, lead=(1, 0, 0))
    spring = PointSpring("shoulder_link", (0, 0, 0.05), "forearm_link", (0, 0, 0.2), 100.0, pulley_radius=0.005,
                         lead=(0, 0, 2))
    assert spring.lead == (0.0, 0.0, 1.0) and spring.as_dict()["pulley_radius"] == 0.005
    model = load_robot("UR5")
    with pytest.raises(SpringlabError, match="exudyn's springs cannot model"):
        simulation.joint_torques(model, [spring], model.random_q(1, 0))
