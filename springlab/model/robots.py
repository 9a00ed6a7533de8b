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


@dataclass(frozen=True)
class Robot:
    """A serial arm in ``example-robot-data``: its URDF (relative to ``robots/``), base and tip links."""

    label: str
    urdf: str
    base: str | None
    tip: str


ROBOTS = {r.label: r for r in (
    Robot("UR3", "ur_description/urdf/ur3_robot.urdf", None, "wrist_3_link"),
    Robot("UR5", "ur_description/urdf/ur5_robot.urdf", None, "wrist_3_link"),
    Robot("UR10", "ur_description/urdf/ur10_robot.urdf", None, "wrist_3_link"),
    Robot("Panda", "panda_description/urdf/panda.urdf", None, "panda_link8"),
    Robot("SO-100", "so_arm_description/urdf/so100.urdf", None, "gripper"),
    Robot("SO-101", "so_arm_description/urdf/so101.urdf", None, "gripper_link"),
    Robot("xArm7", "xarm_description/urdf/xarm7.urdf", None, "link7"),
    Robot("Z1", "z1_description/urdf/z1.urdf", None, "link06"),
    Robot("double pendulum", "double_pendulum_description/urdf/double_pendulum.urdf", None, "link2"),
)}
"""The serial arms of ``example-robot-data`` 6.0.0 springlab is checked on, by label."""

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
    if label not in ROBOTS:
        raise SpringlabError(f"robot = {label!r} is not one of springlab's example robots: give one of "
                             f"{', '.join(map(repr, ROBOTS))}")
    path = robots_folder() / ROBOTS[label].urdf
    if not path.is_file():
        raise SpringlabError(f"{label}: {path} is missing from the installed {PACKAGE} package")
    return path


def load_robot(label: str, *, payload: float | None = None):
    """A robot of :data:`ROBOTS` as a :class:`~springlab.model.revolute.RevoluteChain`, from its base to its tip."""
    from springlab.model.urdf import read_revolute_chain

    robot = ROBOTS.get(label)
    path = robot_urdf(label)
    return read_revolute_chain(path.read_text(), source=path.name, tip=robot.tip, base=robot.base, payload=payload)
