"""A frame a 1:1 belt carries (paper 001's pseudobases on a real arm): route 2's torques are the energy's
derivatives, MuJoCo holds the same file, the UR5's two belt springs remove what a hand computation finds,
and a belt across a joint that is not parallel is refused."""

import numpy as np
import pytest

from springlab.energy.geometry import gravity_torques, joint_torques, potential
from springlab.errors import SpringlabError
from springlab.model.robots import load_robot
from springlab.model.springs import PointSpring


@pytest.fixture(scope="module")
def ur5():
    return load_robot("UR5").with_belt("elbow_joint", "shoulder_link")


SHOULDER = PointSpring("shoulder_link", (0.0, 0.1358, 0.140), "upper_arm_link", (0.0, 0.0, 0.260), 1194.7)
ELBOW = PointSpring("elbow_joint belt", (0.0, 0.0, 0.140), "forearm_link", (0.0, 0.0, 0.260), 430.9)


def test_route_2_with_a_belt_is_the_energys_derivative(ur5):
    q = ur5.random_q(4, 3)
    tau = joint_torques(ur5, [SHOULDER, ELBOW], q)
    h = 1e-6
    for p in range(len(q)):
        fd = [(potential(ur5, [SHOULDER, ELBOW], q[p] + h * e)["total"]
               - potential(ur5, [SHOULDER, ELBOW], q[p] - h * e)["total"])[0] / (2 * h) for e in np.eye(ur5.n)]
        np.testing.assert_allclose(tau[p], fd, atol=1e-7)  # N m: central differences of J at 1e-6 rad
    # the belt's frame keeps shoulder_link's axes at the elbow's origin whatever the joints do
    from springlab.model.revolute import body_frames

    R, o = body_frames(ur5, q)
    np.testing.assert_array_equal(R[:, ur5.n + 1], R[:, 1])
    np.testing.assert_array_equal(o[:, ur5.n + 1], o[:, 3])


def test_the_ur5s_two_belt_springs_remove_what_paper_001s_rule_predicts(ur5):
    # 001 Eq. (16): k a b = g |mu sigma| per link; the shoulder's and the elbow's gravity terms cancel and only
    # wrist_3's offset mass (a term in wrist_1's absolute angle, 0.1745 N m) is left on both joints
    q = ur5.random_q(4000, 1)
    tau = np.abs(joint_torques(ur5, [SHOULDER, ELBOW], q)).max(axis=0)
    g = np.abs(gravity_torques(ur5, q)).max(axis=0)
    assert tau[1] < 0.18 and tau[2] < 0.18 and g[1] > 55 and g[2] > 15  # N m
    # the negative control: the same elbow spring on the upper arm, no belt, balances nothing of the elbow
    plain = PointSpring("upper_arm_link", (0.0, 0.0, 0.425 + 0.14), "forearm_link", (0.0, 0.0, 0.260), 430.9)
    without = np.abs(joint_torques(ur5, [SHOULDER, plain], q)).max(axis=0)
    assert without[2] > 0.5 * g[2]


def test_mujoco_holds_the_belt_as_route_2_does(ur5):
    pytest.importorskip("mujoco")
    from springlab.model.mjcf import to_mjcf
    from springlab.workbench.references import mujoco_holding_torques

    q = ur5.random_q(100, 2)
    mjcf = to_mjcf(ur5, [SHOULDER, ELBOW])
    assert 'tendon1="elbow_joint belt turns"' in mjcf
    ours = joint_torques(ur5, [SHOULDER, ELBOW], q)
    theirs = mujoco_holding_torques(mjcf, ur5, q)
    assert np.max(np.abs(theirs - ours)) < 1e-9 * np.max(np.abs(gravity_torques(ur5, q)))


def test_a_belt_across_a_joint_that_is_not_parallel_is_refused():
    arm = load_robot("UR5")
    with pytest.raises(SpringlabError, match="shoulder_pan_joint.*not parallel"):
        arm.with_belt("elbow_joint", "base_link")
    with pytest.raises(SpringlabError, match="lies beyond"):
        arm.with_belt("shoulder_lift_joint", "forearm_link")
    assert arm.with_belt("wrist_1_joint", "shoulder_link").belts  # three parallel joints: a belt runs across
    from springlab.energy.simulation import build_locked_model

    with pytest.raises(SpringlabError, match="belt frames"):  # route 3 says it has no belt
        build_locked_model(arm.with_belt("elbow_joint", "shoulder_link"), [], np.zeros(6))
