"""Real robots' published URDFs, from the ``example-robot-data`` package (an optional, pinned
dependency: ``pip install example-robot-data``; nothing is copied into springlab).

:data:`ROBOTS` names each serial arm's URDF (relative to the package's ``robots/`` folder), its
base link and its tip (the last link of the arm proper: a gripper's fingers beyond it are locked).
:func:`robot_urdf` finds the file; :func:`load_robot` reads it into the general model.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from springlab.errors import SpringlabError
from springlab.model.urdf import read_revolute_chain


@dataclass(frozen=True)
class Robot:
    """A serial arm in ``example-robot-data``: its URDF (relative to ``robots/``), base and tip links."""

    label: str
    urdf: str
    base: str | None
    tip: str


ROBOTS = {r.label: r for r in (
    Robot("UR3", "ur_description/urdf/ur3_robot.urdf", "base_link", "wrist_3_link"),
    Robot("UR5", "ur_description/urdf/ur5_robot.urdf", "base_link", "wrist_3_link"),
    Robot("UR10", "ur_description/urdf/ur10_robot.urdf", "base_link", "wrist_3_link"),
    Robot("Panda", "panda_description/urdf/panda.urdf", "panda_link0", "panda_link7"),
    Robot("Kinova Jaco", "kinova_description/robots/kinova.urdf", "j2s6s200_link_base", "j2s6s200_link_6"),
    Robot("xArm7", "xarm_description/urdf/xarm7.urdf", "link_base", "link7"),
    Robot("Z1", "z1_description/urdf/z1.urdf", "link00", "link06"),
    Robot("SO-100", "so_arm_description/urdf/so100.urdf", "base", "gripper"),
    Robot("SO-101", "so_arm_description/urdf/so101.urdf", "base_link", "gripper_link"),
    Robot("Talos left arm", "talos_data/robots/talos_reduced.urdf", "torso_2_link", "arm_left_7_link"),
    Robot("Baxter left arm", "baxter_description/urdf/baxter.urdf", "torso", "left_wrist"),
    Robot("double pendulum", "double_pendulum_description/urdf/double_pendulum.urdf", "base_link", "link2"),
)}
"""The twelve serial arms of ``example-robot-data`` 6.0.0 springlab is checked on, by label: the
tip is the last link of the arm proper (fingers and jaws beyond it are locked); Talos's and
Baxter's left arms stand on the torso."""

OTHER_ARMS = {r.label: r for r in (
    Robot("UR3 joint limited", "ur_description/urdf/ur3_joint_limited_robot.urdf", "base_link", "wrist_3_link"),
    Robot("UR5 joint limited", "ur_description/urdf/ur5_joint_limited_robot.urdf", "base_link", "wrist_3_link"),
    Robot("UR10 joint limited", "ur_description/urdf/ur10_joint_limited_robot.urdf", "base_link", "wrist_3_link"),
    Robot("UR3 gripper", "ur_description/urdf/ur3_gripper.urdf", "base_link", "wrist_3_link"),
    Robot("UR5 gripper", "ur_description/urdf/ur5_gripper.urdf", "base_link", "wrist_3_link"),
    Robot("Panda collision", "panda_description/urdf/panda_collision.urdf", "panda_link0", "panda_link7"),
    Robot("TalosLeftArm full v2", "talos_data/robots/talos_full_v2.urdf", "torso_2_link", "arm_left_7_link"),
    Robot("TalosLeftArm armonly 6dof", "talos_data/robots/talos_left_arm.urdf", "arm_left_1_link", "arm_left_7_link"),
    Robot("TalosRightArm", "talos_data/robots/talos_reduced.urdf", "torso_2_link", "arm_right_7_link"),
    Robot("BaxterRightArm", "baxter_description/urdf/baxter.urdf", "torso", "right_wrist"),
    Robot("DoublePendulum continuous", "double_pendulum_description/urdf/double_pendulum_continuous.urdf", "base_link", "link2"),
    Robot("DoublePendulum simple", "double_pendulum_description/urdf/double_pendulum_simple.urdf", "base_link", "link2"),
    Robot("ASR TwoDofs", "asr_twodof_description/urdf/TwoDofs.urdf", "ground", "Link2"),
    Robot("FingerEdu", "finger_edu_description/robots/finger_edu.urdf", "finger_base_link", "finger_lower_link"),
    Robot("AnymalKinova arm", "anymal_b_simple_description/robots/anymal-kinova.urdf", "j2s6s200_link_base", "j2s6s200_link_6"),
    Robot("B1Z1 arm", "b1_description/urdf/b1-z1.urdf", "link00", "link06"),
    Robot("Borinot flying arm 2", "borinot_description/urdf/borinot_flying_arm_2.urdf", "borinot__base_link", "flying_arm_2__link2"),
    Robot("Hextilt flying arm 5", "hextilt_description/urdf/hextilt_flying_arm_5.urdf", "flying_arm_5__base_link", "flying_arm_5__link_5"),
    Robot("Tiago arm", "tiago_description/robots/tiago.urdf", "torso_lift_link", "arm_7_link"),
    Robot("TiagoNoHand arm", "tiago_description/robots/tiago_no_hand.urdf", "torso_lift_link", "arm_7_link"),
    Robot("TiagoDual left", "tiago_description/robots/tiago_dual.urdf", "torso_lift_link", "arm_left_7_link"),
    Robot("TiagoPro left", "tiago_pro_description/robots/tiago_pro.urdf", "torso_lift_link", "arm_left_7_link"),
    Robot("PR2 left", "pr2_description/urdf/pr2.urdf", "torso_lift_link", "l_wrist_roll_link"),
    Robot("Romeo left", "romeo_description/urdf/romeo.urdf", "torso", "l_wrist"),
    Robot("iCub left", "icub_description/robots/icub.urdf", "chest", "l_hand"),
    Robot("G1 left", "g1_description/urdf/g1_29dof_rev_1_0.urdf", "torso_link", "left_wrist_yaw_link"),
    Robot("Alex left", "alex_description/urdf/alex_nub_hands.urdf", "Torso", "LeftWristRollLink"),
    Robot("Centauro arm1", "centauro_description/urdf/centauro.urdf", "torso_2", "arm1_6"),
    Robot("Human left", "human_description/robots/human.urdf", "left_clavicle", "left_hand"),
    Robot("SimpleHumanoid left", "simple_humanoid_description/urdf/simple_humanoid.urdf", "torso", "l_wrist"),
)}
"""Every other serial arm in ``example-robot-data`` 6.0.0 (humanoids' and mobile manipulators' arms
from their torso, arms on legged and flying bases, the joint-limited UR variants)."""


PACKAGE = "example-robot-data"


def robots_folder() -> Path:
    """The ``robots/`` folder of the installed ``example-robot-data`` package."""
    from importlib import metadata

    try:
        dist = metadata.distribution(PACKAGE)
    except metadata.PackageNotFoundError:
        raise SpringlabError(f"the real robots' URDFs come from the {PACKAGE!r} package, which is not installed: "
                             f"pip install {PACKAGE} (or give your robot's URDF file)") from None
    folder = Path(dist.locate_file("cmeel.prefix/share/example-robot-data/robots"))
    if not folder.is_dir():
        raise SpringlabError(f"{PACKAGE} {dist.version} is installed but has no robots/ folder at {folder}")
    return folder


def robot_urdf(label: str) -> Path:
    """The URDF file of a robot in :data:`ROBOTS` (by label, e.g. 'UR5')."""
    robot = _robot(label)
    path = robots_folder() / robot.urdf
    if not path.is_file():
        raise SpringlabError(f"{label}: {path} is missing from the installed {PACKAGE} package")
    return path


def load_robot(label: str, *, payload: float | None = None):
    """A robot of :data:`ROBOTS` (or :data:`OTHER_ARMS`) as a :class:`~springlab.model.revolute.RevoluteChain`, from its base to its tip."""

    robot = _robot(label)
    path = robot_urdf(label)
    return read_revolute_chain(path.read_text(), source=path.name, tip=robot.tip, base=robot.base, payload=payload,
                               folder=path.parent)


def _robot(label: str) -> Robot:
    robot = ROBOTS.get(label) or OTHER_ARMS.get(label)
    if robot is None:
        raise SpringlabError(f"robot = {label!r} is not one of springlab's example robots: give one of "
                             f"{', '.join(map(repr, ROBOTS))} (or of OTHER_ARMS)")
    return robot
