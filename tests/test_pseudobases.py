"""Paper 001's pseudobases on a spatial arm (springlab.design.pseudobases): a frame the RSSR modules carry
across joints that are not parallel is route 2's energy derivative, and one spring per loaded link's
subsystem (001 Eqs. 5, 13-16) holds the Panda and the Z1 over their workspaces, with negative controls."""

import json

import numpy as np
import pytest

from springlab.design.arms import workspace_ranges
from springlab.design.pseudobases import pseudobase_layout
from springlab.design.structure import structure
from springlab.energy.geometry import gravity_torques, joint_torques, potential
from springlab.errors import SpringlabError
from springlab.model.revolute import body_frames
from springlab.model.robots import load_robot, robot_urdf
from springlab.model.springs import PointSpring
from springlab.workbench.cli import main


def _poses(model, count, seed=0):
    r = workspace_ranges(model)
    return np.random.default_rng(seed).uniform(r[:, 0], r[:, 1], (count, model.n))


@pytest.fixture(scope="module")
def panda():
    model = load_robot("Panda")
    q = _poses(model, 400)
    return model, q, pseudobase_layout(model, structure(model, q), q=q)


def test_route_2_with_a_pseudobase_across_a_roll_joint_is_the_energys_derivative():
    arm = load_robot("Panda").with_pseudobase("panda_joint4", "panda_link1", along=0.07)
    spring = PointSpring("panda_joint4 pseudobase", (0.0, 0.0, 0.05), "panda_link4", (0.03, 0.12, 0.07), 900.0)
    q = _poses(arm, 4, 3)
    tau = joint_torques(arm, [spring], q)
    h = 1e-6
    for p in range(len(q)):
        fd = [(potential(arm, [spring], q[p] + h * e)["total"] - potential(arm, [spring], q[p] - h * e)["total"])[0]
              / (2 * h) for e in np.eye(arm.n)]
        np.testing.assert_allclose(tau[p], fd, atol=1e-6)  # N m: central differences of J at 1e-6 rad
    R, o = body_frames(arm, q)  # the frame: link1's axes, at a point of joint 4's axis 70 mm from its origin
    np.testing.assert_array_equal(R[:, arm.n + 1], R[:, 1])
    axis = np.einsum("pij,j->pi", R[:, 4], arm.axes[3])
    np.testing.assert_allclose(o[:, arm.n + 1], o[:, 4] + 0.07 * axis, atol=1e-15)


def test_a_belt_refuses_the_roll_joint_that_a_pseudobase_crosses():
    with pytest.raises(SpringlabError, match="not parallel"):
        load_robot("Panda").with_belt("panda_joint4", "panda_link1")
    with pytest.raises(SpringlabError, match="before 'panda_link2'"):  # no level body above a tilting joint
        load_robot("Panda").with_pseudobase("panda_joint4", "panda_link2")


def test_mujoco_holds_the_pseudobases_as_route_2_does(panda):
    # the MJCF's pseudobase: a body on the level link, on three slides, held at its point C by a 'connect';
    # its slides' force passed to the joint's parent at C (where the modules put it): route 2's torques
    pytest.importorskip("mujoco")
    from springlab.model.mjcf import to_mjcf
    from springlab.workbench.references import mujoco_holding_torques

    model, q, lay = panda
    check = _poses(model, 40, 2)
    ours = joint_torques(lay.model, lay.springs, check)
    theirs = mujoco_holding_torques(to_mjcf(lay.model, lay.springs), lay.model, check)
    scale = np.abs(gravity_torques(lay.model, check)).max()
    assert np.abs(ours - theirs).max() <= 1e-9 * scale
    # the control: the file written with the elbow's pseudobase 20 cm further along its axis is not this design
    import dataclasses

    shifted = dataclasses.replace(lay.model, belts=tuple(
        dataclasses.replace(b, along=b.along + 0.2) if b.name == "panda_joint4 pseudobase" else b
        for b in lay.model.belts))
    wrong = mujoco_holding_torques(to_mjcf(shifted, lay.springs), shifted, check)
    assert np.abs(ours - wrong).max() > 0.05 * scale


def test_one_spring_per_subsystem_holds_the_panda_as_001_predicts(panda):
    model, q, lay = panda
    # 001 Eqs. (5), (13)-(16): the loaded links' terms cancel exactly; what is left is the light joint 7's
    # subsystem (its hand's moment off its axis), a few thousandths of the shoulder's peak
    assert len(lay.springs) == 5 and [b.kind for b in lay.model.belts] == ["rssr"] * 4
    check = _poses(model, 600, 1)
    gravity = np.abs(gravity_torques(lay.model, check)).max(axis=0)
    left = np.abs(joint_torques(lay.model, lay.springs, check)).max(axis=0)
    assert np.all(left[1:6] <= 0.002 * gravity[1])  # N m
    for s in lay.springs:  # each post stands on its pseudobase's vertical line (001 Eq. 13)
        assert np.linalg.norm(np.asarray(s.point_b)[:2] if s.link_b.endswith("pseudobase") else [0.0]) < 1e-6


def test_the_z1s_parallel_joints_get_belts_and_its_wrist_yaw_a_pseudobase():
    model = load_robot("Z1")
    q = _poses(model, 400)
    lay = pseudobase_layout(model, structure(model, q), q=q)
    assert [(b.name, b.kind) for b in lay.model.belts] == [("joint3 belt", "belt"), ("joint4 belt", "belt"),
                                                             ("joint5 pseudobase", "rssr")]
    check = _poses(model, 600, 1)
    gravity = np.abs(gravity_torques(lay.model, check)).max(axis=0)
    left = np.abs(joint_torques(lay.model, lay.springs, check)).max(axis=0)
    assert np.all(left[1:5] <= 0.002 * gravity[1])


def test_negative_controls_a_subsystem_moment_not_handed_on_or_a_spring_left_out_unbalance_it(panda):
    model, q, lay = panda
    check = _poses(model, 600, 1)
    gravity = np.abs(gravity_torques(lay.model, check)).max(axis=0)
    without = np.abs(joint_torques(lay.model, lay.springs[:-1], check)).max(axis=0)  # the wrist's spring left out
    assert without[5] > 0.5 * gravity[5]
    s = lay.springs[1]  # the upper arm's spring with its post off the vertical: no longer a pseudobase's
    moved = PointSpring(s.link_a, s.point_a, s.link_b, np.asarray(s.point_b) + [0.03, 0.0, 0.0], s.k)
    off = np.abs(joint_torques(lay.model, [*lay.springs[:1], moved, *lay.springs[2:]], check)).max(axis=0)
    assert off[2] > 0.05 * gravity[2]


def test_the_cli_designs_the_z1_on_pseudobases_and_writes_their_frames(tmp_path, capsys):
    # the default layout takes pseudobases where the loaded joints are no planar chain; the JSON names each
    # post's frame (a belt's across the parallel joints, RSSR modules across the wrist's yaw) and the modules
    out = tmp_path / "z1.json"
    code = main(["design", str(robot_urdf("Z1")), "--tip", "link06", "--json", str(out), "--samples", "300", "--audit-samples", "2000",
                 "--quiet"])
    assert code in (0, 3)  # passed, or flagged with its reasons (exit 3)
    data = json.loads(out.read_text())
    # its payload dial slides each pulley (the first spring's post) along a straight slot: the ideal springs'
    # is exact (each subsystem's moment is linear in the payload, fixed in its link); the built ones', over
    # their pulleys and without the wrist yaw's spring, is a linearisation that leaves some of it
    dial = data["payload"]["dial"]
    assert dial["ideal"]["exact"] and dial["ideal"]["left_fraction"] < 1e-9
    assert not dial["realised"]["exact"] and dial["realised"]["left_fraction"] > 1e-3
    assert data["method"].startswith("pseudobases") and data["inputs"]["layout"] == "auto"
    frames = [s["frame_b"] for s in data["ideal"] if "frame_b" in s]
    assert {f["kept_by"] for f in frames} == {"belt", "RSSR modules"}
    assert all(f["axes_of"] == "link01" for f in frames)
    assert "rssr" in {p["kind"] for p in data["parts"]}
    assert data["hardware_mass_kg"] == pytest.approx(sum(p["mass_kg"] for p in data["parts"]))
    capsys.readouterr()
    bad = ["design", str(robot_urdf("Z1")), "--layout", "pseudobases", "--payload-range", "0:1", "--tip", "link06",
           "--json", str(tmp_path / "x.json"), "--quiet"]
    assert main(bad) == 2 and "--payload-range" in capsys.readouterr().err
    assert not (tmp_path / "x.json").exists()


def test_the_pseudobase_springs_have_an_exact_payload_dial(panda):
    # each subsystem's moment grows linearly with a payload at the tip, fixed in its link: moving each spring's
    # pulley (the post of the first) along a straight slot restores the balance to round-off (001 Eq. 16 is
    # linear in l_CB sigma); the ends on the pseudobases' frames have no link box to leave
    from springlab.design.arms import ends_outside
    from springlab.design.payload import payload_dial

    model, q, lay = panda
    dial = payload_dial(lay.model, lay.springs, q[:100], "panda_link7")
    assert dial.exact and dial.left < 1e-9
    assert {end for _, end, _, _ in dial.moves} == {"A", "B"} and len(dial.moves) == len(lay.springs)
    far = [PointSpring(s.link_a, s.point_a, s.link_b, np.asarray(s.point_b) + 10.0, s.k) if
           s.link_b.endswith("pseudobase") else s for s in lay.springs]  # posts 10 m away: no box to leave
    assert ends_outside(lay.model, far, 0.03) == ends_outside(lay.model, lay.springs, 0.03) < 0.1
