"""An arm read from URDF, the ROS robot description that CAD tools export: ``load_arm("arm.urdf")``.

Read with the standard library's XML parser: springlab needs seven URDF elements (``link``,
``joint``, ``origin``, ``axis``, ``limit``, ``inertial`` and, for where springs may attach on the
general model, ``collision``/``visual`` geometry: :mod:`springlab.model.shapes`, meshes read with
trimesh), so a URDF library is not worth its weight here. Python's expat refuses
entity-expansion bombs.

What becomes of the URDF (all at the zero configuration, every joint at 0):

* with a **tip** (``--tip LINK``), the joints on the path from the **base** (``--base LINK``,
  default the root) to the tip are the arm; every other joint below the base (a gripper's
  fingers, prismatic or not) is locked at zero, so its bodies ride on the link they hang from,
  as Pinocchio's reduced models do; what is not below the base (a rail, a torso) is left out.
  A **payload** (kg) is a point mass at the tip frame's origin. Without a tip the whole tree
  must be one serial chain of revolute joints;
* a revolute joint whose limits read ``lower = upper`` is taken as unlimited, with a note (some
  exporters write a continuous joint so);
* the **root link** (with everything fixed to it) is the ground, link 1; its mass is not used;
* **links joined by fixed joints are merged**: their masses added, their centres of mass combined;
* **three consecutive revolute joints whose axes meet in one point and span three directions**
  become one spherical joint (a wrist); the bodies between them, which turn with part of the
  wrist only, must have their centres of mass on that point (within :data:`COM_TOLERANCE` of the
  next link's length) and are counted at it, on the link before;
* every other revolute (or continuous) joint stays a revolute joint, its axis given in the
  previous link's springlab frame (:func:`springlab.model.chain.serial_chain`); springlab's
  revolute chains have all links on one line at zero angles, so the axis must make the same
  angle with the link before and the link after (a planar elbow, a vertical base joint under a
  vertical column), else the file is refused;
* a link runs from its joint to the next joint; the last link to the origin of the deepest frame
  fixed to it (a ``tool0`` or flange), else to its own centre of mass;
* **up** is +z of the root link (URDF's gravity acts along -z), unless ``up`` is given;
* a revolute joint's **limits** become the joint's range in the arm file's sense (shifted by
  the angle between springlab's zero and the URDF's); a spherical group's limits are not
  turned into a cone (noted);
* a **centre of mass off the line** between a link's joints (paper 000's method assumes it on
  the line) is projected onto the line when the offset is at most :data:`COM_TOLERANCE` of
  the link's length, and kept as ``ArmSpec.com_offsets`` so that the designer reports what the
  projection costs (route 2); a larger offset is refused, pointing to paper 001's method.

Refused with the element named: a file that is not URDF, a branching tree, a closed loop, a
prismatic, planar or floating joint on the arm's path (or anywhere, without a tip), a link without ``<inertial>`` that would leave a moving
link massless, two revolute joints at one point that are not a wrist, a zero-length link; a xacro
file not yet expanded (``<xacro:...>`` elements, ``${...}`` or ``$(...)`` in an attribute); a tip
with no movable joint between it and the base (the base itself, or a frame fixed to it), with the
file's revolute joints named; a link the arm carries whose ``<inertia>`` is no rigid body's (a
negative principal moment, or one larger than the sum of the other two, beyond
:data:`INERTIA_TOLERANCE`: a point mass, all six zero, is one), where such a link riding on the
base, whose inertia is never used, is only noted; on the general model, a mesh that would give a
false outline (:class:`springlab.model.shapes.RefusedMeshError`).
Refused at once, before the text is parsed into objects (its elements counted as they stream
past): a text of more than 16 MiB, more movable joints
than an arm of ``max_links`` links can have (or than :data:`MAX_MOVABLE_JOINTS`), more than
:data:`MAX_BODIES` links. A file refused that another up (:data:`UP_AXES`) would read is refused
with that up named (``--up 0,1,0`` for a y-up export). Trees of fixed bodies are walked with a
stack, not recursion: a tool of thousands of bodies is merged like one of two.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from xml.parsers import expat

import numpy as np

from springlab import _checks
from springlab.errors import LineChainError, MeshError, SpringlabError, UpAdviceError
from springlab.model.chain import STANDARD_GRAVITY
from springlab.model.revolute import RevoluteChain
from springlab.model.rotations import rot_axis, rot_rpy
from springlab.model.shapes import RefusedMeshError, link_shapes, shape_points, shape_solid

SLIDING = ("prismatic", "planar", "floating")
"""Joint types springlab's arms do not have: refused on the arm's path, locked at zero off it."""

COM_TOLERANCE = 0.02
"""Largest distance of a link's centre of mass from the line between its joints that is
projected onto the line, as a fraction of the link's length (2 %); a farther one is refused."""

MEET_TOLERANCE = 1e-6
"""m: how close three revolute axes must pass to one point to be one spherical joint."""

MAX_MOVABLE_JOINTS = 1000
"""The most movable (revolute, continuous) joints springlab reads from a URDF, even with
``allow_large``: counted before the file is parsed (an arm of more is a whole robot, or a fuzzer's)."""

MAX_BODIES = 10_000
"""The most ``<link>`` elements springlab reads from a URDF (a tool of thousands of bodies fixed
together is read; a file of more is refused before it is parsed)."""


INERTIA_TOLERANCE = 1e-9
"""How far a link's principal moments of inertia may miss a rigid body's (each >= 0, each at most
the sum of the other two) and be read as round-off in the file: this fraction of the largest
moment, or of the link's mass times (1 mm)^2 where that is larger (a point mass written with
round-off in its zeros)."""


@dataclass(frozen=True)
class _Inertial:
    mass: float  # kg
    com: np.ndarray  # (3,) m, in the link's frame
    inertia: np.ndarray  # (3, 3) kg m^2 about the centre of mass, in the link's frame
    given: str = ""  # the <inertia> element's six values as the file writes them


def _inertia_fault(inertial: _Inertial) -> str | None:
    """Why a link's inertia is no rigid body's (a negative principal moment, or one larger than the
    sum of the other two), or None; within :data:`INERTIA_TOLERANCE`."""
    J = inertial.inertia
    w = np.linalg.eigvalsh((J + J.T) / 2)
    tol = INERTIA_TOLERANCE * max(float(np.max(np.abs(w))), inertial.mass * 1e-6)
    moments = ", ".join(f"{x:.6g}" for x in w)
    if w[0] < -tol:
        return f"its principal moments ({moments} kg m^2) include a negative one"
    if w[2] > w[0] + w[1] + tol:
        return (f"its principal moments ({moments} kg m^2) break the triangle inequality: "
                f"{w[2]:.6g} > {w[0]:.6g} + {w[1]:.6g}")
    return None


def _combine(parts) -> _Inertial:
    """One body of several (mass, com, inertia), all in one frame: masses added, centres combined,
    inertias moved to the common centre (parallel axes)."""
    parts = list(parts)
    mass = sum(p.mass for p in parts)
    if mass <= 0:
        return _Inertial(0.0, np.zeros(3), sum((p.inertia for p in parts), np.zeros((3, 3))))
    com = sum(p.mass * np.asarray(p.com) for p in parts) / mass
    inertia = np.zeros((3, 3))
    for p in parts:
        d = np.asarray(p.com) - com
        inertia += p.inertia + p.mass * (float(d @ d) * np.eye(3) - np.outer(d, d))
    return _Inertial(float(mass), com, inertia)


@dataclass
class _Joint:
    name: str
    kind: str
    parent: str
    child: str
    origin: np.ndarray  # 4x4, parent link frame -> joint (child link) frame
    axis: np.ndarray
    limit: tuple | None


@dataclass
class UrdfArm:
    """What :func:`read_urdf` found: the arm's fields (SI units) and what it assumed."""

    name: str
    r: list = field(default_factory=list)
    d: list = field(default_factory=list)
    m: list = field(default_factory=list)
    joints: list = field(default_factory=list)
    limits: list = field(default_factory=list)
    offsets: list = field(default_factory=list)  # per moving link: the COM's offset from its line, link frame (m)
    notes: list = field(default_factory=list)


def _floats(text, count: int, where: str, default=None) -> np.ndarray:
    if text is None:
        if default is None:
            raise SpringlabError(f"{where}: missing")
        return np.array(default, dtype=float)
    try:
        values = [float(x) for x in text.split()]
    except ValueError:
        raise SpringlabError(f"{where} = {text!r}: expected {count} numbers") from None
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise SpringlabError(f"{where} = {text!r}: expected {count} finite numbers")
    return np.array(values)


def _origin(element, where: str) -> np.ndarray:
    T = np.eye(4)
    origin = element.find("origin")
    if origin is not None:
        T[:3, 3] = _floats(origin.get("xyz"), 3, f"{where}: <origin xyz>", (0, 0, 0))
        T[:3, :3] = rot_rpy(*_floats(origin.get("rpy"), 3, f"{where}: <origin rpy>", (0, 0, 0)))
    return T


def _xacro_refusal(source: str, what: str) -> SpringlabError:
    name = Path(source).name
    out = (name[:-len(".xacro")] if name.endswith(".xacro") else f"{Path(name).stem}.expanded")
    out += "" if out.endswith(".urdf") else ".urdf"
    return SpringlabError(f"{source}: a xacro file, not yet a URDF ({what}): expand it first with xacro (ROS's "
                          f"xacro package), e.g. xacro {name} > {out}, and give the URDF it writes")


def _xacro_in(root, source: str) -> None:
    """Refuse a parsed file that xacro has not expanded: an element of xacro's namespace (a macro, a
    property, an include) or a ``${...}`` or ``$(...)`` substitution in an attribute. An expanded
    file may keep ``xmlns:xacro`` on its <robot> and name its source in a comment: that is read."""
    for element in root.iter():
        if isinstance(element.tag, str) and element.tag.startswith("{") and "xacro" in element.tag.partition("}")[0]:
            raise _xacro_refusal(source, f"it has <xacro:{element.tag.partition('}')[2]}> elements")
        for key, value in element.attrib.items():
            if "${" in value or "$(" in value:
                raise _xacro_refusal(source, f"<{element.tag} {key}={value!r}> holds a substitution")


def _parse(text: str, source: str):
    try:
        root = ET.fromstring(text)
    except ET.ParseError as err:
        if "<xacro:" in text:  # xacro's elements without their namespace declared
            raise _xacro_refusal(source, "it has <xacro:...> elements") from None
        raise SpringlabError(f"{source}: not valid XML: {err}") from None
    _xacro_in(root, source)
    if root.tag != "robot":
        raise SpringlabError(f"{source}: not a URDF file (its root element is <{root.tag}>, not <robot>)")
    links = {}
    for el in root.findall("link"):
        name = el.get("name")
        if not name:
            raise SpringlabError(f"{source}: a <link> without a name")
        if name in links:
            raise SpringlabError(f"{source}: link {name!r} is defined twice")
        inertial = el.find("inertial")
        if inertial is None:
            links[name] = None
            continue
        where = f"{source}: link {name!r}: <inertial>"
        mass_el = inertial.find("mass")
        if mass_el is None or mass_el.get("value") is None:
            raise SpringlabError(f"{where} has no <mass value=...>: give the link's mass in kg")
        mass = _floats(mass_el.get("value"), 1, f"{where} <mass value>")[0]
        if mass < 0:
            raise SpringlabError(f"{where} <mass value> = {mass:g} kg must be >= 0")
        frame = _origin(inertial, where)
        inertia, given = np.zeros((3, 3)), ""
        inertia_el = inertial.find("inertia")
        if inertia_el is not None:
            keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
            v = {key: _floats(inertia_el.get(key), 1, f"{where} <inertia {key}>", (0.0,))[0] for key in keys}
            given = " ".join(f'{key}="{inertia_el.get(key, "0").strip()}"' for key in keys)
            inertia = np.array([[v["ixx"], v["ixy"], v["ixz"]], [v["ixy"], v["iyy"], v["iyz"]],
                                [v["ixz"], v["iyz"], v["izz"]]])
            inertia = frame[:3, :3] @ inertia @ frame[:3, :3].T  # about the centre of mass, in the link's frame
        links[name] = _Inertial(float(mass), frame[:3, 3], inertia, given)
    joints, notes = [], []
    for el in root.findall("joint"):
        name = el.get("name") or "?"
        where = f"{source}: joint {name!r}"
        kind = el.get("type")
        parent, child = el.find("parent"), el.find("child")
        if parent is None or child is None or parent.get("link") is None or child.get("link") is None:
            raise SpringlabError(f"{where}: needs <parent link=...> and <child link=...>")
        for end in (parent.get("link"), child.get("link")):
            if end not in links:
                raise SpringlabError(f"{where} names link {end!r}, which the file does not define")
        if kind not in ("revolute", "continuous", "fixed", *SLIDING):
            raise SpringlabError(f"{where}: unknown joint type {kind!r} (URDF: revolute, continuous, fixed, ...)")
        axis_el = el.find("axis")
        axis = _floats(axis_el.get("xyz") if axis_el is not None else None, 3, f"{where}: <axis xyz>", (1, 0, 0))
        if kind != "fixed":
            if np.linalg.norm(axis) < 1e-12:
                raise SpringlabError(f"{where}: <axis xyz> is zero: give the joint's axis")
            axis = axis / np.linalg.norm(axis)
        limit = None
        limit_el = el.find("limit")
        if kind == "revolute" and limit_el is not None and limit_el.get("lower") is not None \
                and limit_el.get("upper") is not None:
            lo = _floats(limit_el.get("lower"), 1, f"{where}: <limit lower>")[0]
            hi = _floats(limit_el.get("upper"), 1, f"{where}: <limit upper>")[0]
            if lo == hi:  # some exporters write a continuous joint so
                notes.append(f"joint {name!r}: <limit lower={lo:g} upper={hi:g}> read as unlimited "
                             "(some exporters write a continuous joint with equal limits)")
            elif not lo < hi:
                raise SpringlabError(f"{where}: <limit lower={lo:g} upper={hi:g}> must have lower < upper (rad)")
            else:
                limit = (lo, hi)
        joints.append(_Joint(name, kind, parent.get("link"), child.get("link"), _origin(el, where), axis, limit))
    return root.get("name") or Path(source).stem, links, joints, notes


def _sliding_refusal(joint: _Joint, source: str, why: str = "") -> SpringlabError:
    return SpringlabError(f"{source}: joint {joint.name!r} is {joint.kind}{why}: springlab balances arms of revolute "
                          "and spherical joints only (a sliding joint moves the centre of mass along a line no "
                          "spring set here is designed for)")


def _choose(links: dict, joints: list, source: str, base: str | None, tip: str | None) -> tuple[list, str | None]:
    """The joints of the arm from ``base`` (None: the root) to ``tip`` (None: the whole tree):
    the path's joints as they are, every other joint below the base locked at zero (made fixed:
    its bodies ride on the link they hang from, as Pinocchio's reduced models do), the joints
    outside the base's subtree left out (they carry no load the arm's springs take). Returns the
    joints and the base link (None: the root)."""
    if tip is None and base is None:
        for j in joints:
            if j.kind in SLIDING:
                raise _sliding_refusal(j, source, " (choose the arm's chain with --tip LINK to lock it)")
        refusal = _no_joint_refusal(links, joints, source, None, None, []) if links and all(
            j.kind == "fixed" for j in joints) else None
        if refusal is not None:
            raise refusal
        return joints, None
    for name, what in ((tip, "tip"), (base, "base")):
        if name is not None and name not in links:
            near = sorted(links)[:12]
            raise SpringlabError(f"{source}: {what} = {name!r} is not a link of the file: give one of its <link> names "
                                 f"({', '.join(map(repr, near))}{', ...' if len(links) > 12 else ''})")
    into = {j.child: j for j in joints}
    if tip is None:
        path = []
    else:
        path, here = [], tip
        while here in into and here != base:
            path.append(into[here])
            here = into[here].parent
        if base is not None and here != base:
            raise SpringlabError(f"{source}: tip = {tip!r} is not below base = {base!r}: the arm runs from the base "
                                 "link out to the tip link (choose a base on the tip's path to the root)")
        path.reverse()
    for j in path:
        if j.kind in SLIDING:
            raise _sliding_refusal(j, source, f" and lies on the path from {base or 'the root'!r} to tip {tip!r} "
                                              "(choose a tip before it)")
    below = None
    if base is not None:  # the base's subtree: walked with a stack
        by_parent: dict[str, list] = {}
        for j in joints:
            by_parent.setdefault(j.parent, []).append(j)
        below, stack = set(), [base]
        while stack:
            here = stack.pop()
            if here not in below:
                below.add(here)
                stack += [j.child for j in by_parent.get(here, [])]
    on_path = {id(j) for j in path}
    chosen = [j if id(j) in on_path or tip is None else _Joint(j.name, "fixed", j.parent, j.child, j.origin, j.axis, None)
              for j in joints if below is None or (j.parent in below and j.child in below)]
    if tip is None:
        for j in chosen:
            if j.kind in SLIDING:
                raise _sliding_refusal(j, source, " (choose the arm's chain with --tip LINK to lock it)")
    if links and all(j.kind == "fixed" for j in (path if tip is not None else chosen)):
        refusal = _no_joint_refusal(links, joints, source, base, tip, path)
        if refusal is not None:
            raise refusal
    return chosen, base


def _no_joint_refusal(links: dict, joints: list, source: str, base: str | None, tip: str | None,
                      path: list) -> SpringlabError | None:
    """The refusal of a base and tip with no movable joint between them (or of a base with none below
    it): names them, the file's revolute joints and the tips beyond the base that one would give.
    None where the tree itself is at fault (no single root): :func:`_serial` names that."""
    by_parent: dict[str, list] = {}
    for j in joints:
        by_parent.setdefault(j.parent, []).append(j)
    root = base
    if root is None:
        children = {j.child for j in joints}
        roots = [name for name in links if name not in children]
        if len(roots) != 1:
            return None
        root = roots[0]
    if tip is not None and not path and tip != root:
        return None  # a tip that is a second root
    movable = [j for j in joints if j.kind in ("revolute", "continuous")]
    beyond, stack, seen = [], [(root, False)], set()  # the links below the base, and whether a joint moves them
    while stack:
        here, moved = stack.pop()
        if here in seen:
            continue
        seen.add(here)
        out = by_parent.get(here, [])
        if moved and not out:
            beyond.append(here)  # a leaf a movable joint turns: a tip to give
        stack += [(j.child, moved or j.kind in ("revolute", "continuous")) for j in reversed(out)]
    below = [j for j in movable if j.parent in seen]
    if tip is not None and tip == root:
        where = (f"base = {base!r}" if base is not None else "the file's root link, where the arm stands")
        said = f"tip = {tip!r} is the base link itself ({where}): no joint lies between them"
    elif tip is not None:
        said = (f"no revolute joint lies between base {root!r} and tip {tip!r} (only fixed joint"
                f"{'s' if len(path) > 1 else ''} {', '.join(repr(j.name) for j in path)}): nothing there moves")
    elif base is not None:
        said = f"no revolute joint lies below base {root!r}: nothing there moves"
    else:
        said = "no joint of the file moves"
    if not movable:
        return SpringlabError(f"{source}: {said + '; ' if tip or base else ''}the file has no revolute or continuous "
                              "joint: nothing to balance")
    shown = below or movable
    listed = ", ".join(f"{j.name!r} ({j.parent!r} to {j.child!r})" for j in shown[:8])
    more = f" and {len(shown) - 8} more" if len(shown) > 8 else ""
    if below:
        tips = ", ".join(map(repr, beyond[:6])) + (", ..." if len(beyond) > 6 else "")
        advice = f"give a tip beyond the base that they move (--tip LINK), e.g. {tips}"
        return SpringlabError(f"{source}: {said}; the revolute joints below {root!r} are {listed}{more}: {advice}")
    return SpringlabError(f"{source}: {said}; the file's revolute joints are {listed}{more}, none of them below "
                          f"{root!r}: give a base nearer the root (--base LINK; the root by default)")


def _serial(links: dict, joints: list, source: str) -> tuple[str, list, str]:
    """The root link, the joints in order from it outward (the arm's path, with the subtrees
    fixed to it), and the last link of the path; checks that the movable joints form one chain."""
    by_parent: dict[str, list] = {}
    by_child: dict[str, list] = {}
    for j in joints:
        by_parent.setdefault(j.parent, []).append(j)
        by_child.setdefault(j.child, []).append(j)
    for child, into in by_child.items():
        if len(into) > 1:
            raise SpringlabError(f"{source}: link {child!r} is the child of joints "
                                 f"{', '.join(repr(j.name) for j in into)}: a closed loop; springlab designs "
                                 "serial chains (open kinematic trees of one branch)")
    roots = [name for name in links if name not in by_child]
    if not links:
        raise SpringlabError(f"{source}: the file defines no <link>: no arm to read")
    if len(roots) != 1:
        if not roots:
            raise SpringlabError(f"{source}: every link is some joint's child: the joints close a loop")
        raise SpringlabError(f"{source}: {len(roots)} root links ({', '.join(map(repr, roots))}): "
                             "a URDF arm has one base link")
    moves: dict[str, bool] = {}

    def carries(link: str) -> bool:  # a movable joint somewhere below the link
        if link not in moves:  # walk the subtree with a stack (a tool of thousands of fixed bodies is deep)
            below, stack, seen = [], [link], set()
            while stack:
                here = stack.pop()
                if here in moves:
                    continue
                if here in seen:
                    raise SpringlabError(f"{source}: the joints below link {link!r} close a loop")
                seen.add(here)
                below.append(here)
                stack += [j.child for j in by_parent.get(here, [])]
            for here in reversed(below):  # each link after every link below it
                moves[here] = any(j.kind != "fixed" or moves[j.child] for j in by_parent.get(here, []))
        return moves[link]

    order, reached, name, last = [], {roots[0]}, roots[0], roots[0]
    while True:
        out = by_parent.get(name, [])
        main = [j for j in out if carries(j.child) or j.kind != "fixed"]
        if len(main) > 1:
            raise SpringlabError(f"{source}: link {name!r} branches into joints "
                                 f"{', '.join(repr(j.name) for j in main)}, each carrying movable joints: springlab "
                                 "designs serial chains; remove the branches that do not carry the arm")
        side = [j for j in out if j not in main]
        if not main and len(side) == 1:  # the end: one frame fixed beyond the last link (a tool0)
            main, side = side, []
        stack = list(side)
        while stack:  # bodies fixed to this link: merged into it
            j = stack.pop()
            order.append(j)
            reached.add(j.child)
            stack += by_parent.get(j.child, [])
        if not main:
            break
        order.append(main[0])
        reached.add(main[0].child)
        name = last = main[0].child
    lost = sorted(set(links) - reached)
    if lost:
        raise SpringlabError(f"{source}: links {', '.join(map(repr, lost))} are not joined to the base link "
                             f"{roots[0]!r} (a closed loop or a second tree)")
    return roots[0], order, last


def _frame_to(u: np.ndarray) -> np.ndarray:
    """A rotation taking [1, 0, 0] to the unit vector u (the smallest one)."""
    e = np.array([1.0, 0.0, 0.0])
    v = np.cross(e, u)
    c = float(e @ u)
    if np.linalg.norm(v) < 1e-12 or 1 + c < 1e-9:  # along +x, or (within round-off) along -x: a half turn about z
        return np.eye(3) if c > 0 else _half_turn_to(u)
    K = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + K + K @ K / (1 + c)


def _half_turn_to(u: np.ndarray) -> np.ndarray:
    """A rotation taking [1, 0, 0] to u when u is within round-off of [-1, 0, 0]: a half turn about z,
    then the small turn that remains (so that the result takes x exactly to u)."""
    flip = np.diag([-1.0, -1.0, 1.0])
    rest = flip.T @ u  # within round-off of +x
    v = np.cross([1.0, 0.0, 0.0], rest)
    K = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return flip @ (np.eye(3) + K + K @ K / (1 + float(rest[0])))


def _meet(points, axes) -> np.ndarray | None:
    """The point where the lines p + t w all pass (least squares), or None if they miss it."""
    A = sum(np.eye(3) - np.outer(w, w) for w in axes)
    b = sum((np.eye(3) - np.outer(w, w)) @ p for p, w in zip(points, axes, strict=True))
    if np.linalg.matrix_rank(A, tol=1e-9) < 3:
        return None
    x = np.linalg.solve(A, b)
    far = max(np.linalg.norm((np.eye(3) - np.outer(w, w)) @ (x - p)) for p, w in zip(points, axes, strict=True))
    return x if far <= MEET_TOLERANCE else None


def _count(text: str, source: str) -> tuple[int, int]:
    """The ``<link>`` elements of a URDF's ``<robot>`` and its joints that are not fixed, counted
    by expat's callbacks as the text streams past: no element is built, so that a file of a
    whole robot (or a hundred thousand links) is refused before it is parsed into objects."""
    counts = [0, 0, 0]  # depth, links, movable joints

    def start(tag, attrs):
        if counts[0] == 1:
            if tag == "link":
                counts[1] += 1
            elif tag == "joint" and attrs.get("type") != "fixed":
                counts[2] += 1
        counts[0] += 1

    def end(tag):
        counts[0] -= 1

    parser = expat.ParserCreate()
    parser.StartElementHandler, parser.EndElementHandler = start, end
    try:
        parser.Parse(text, True)
    except expat.ExpatError as err:
        raise SpringlabError(f"{source}: not valid XML: {err}") from None
    return counts[1], counts[2]


def _check_size(text: str, source: str, max_links: int | None) -> None:
    """Refuse, before anything is built, a URDF text longer than
    16 MiB, one of more than :data:`MAX_BODIES` links, or
    one with more movable joints than an arm of ``max_links`` links (ground included; None: no
    such limit) can have, or than :data:`MAX_MOVABLE_JOINTS`."""
    if max_links is not None:
        max_links = _checks.count("max_links", max_links, least=2,
                                  why=" (links with the ground), or None for no limit but MAX_MOVABLE_JOINTS")
    if len(text) > _checks.MAX_FILE_BYTES:
        raise SpringlabError(f"{source}: {len(text) / 2 ** 20:.1f} MiB of URDF text is more than springlab reads "
                             f"({_checks.MAX_FILE_BYTES / 2 ** 20:g} MiB; an arm's URDF is a few kB a link): give the URDF of "
                             "the arm's own serial chain")
    bodies, movable = _count(text, source)
    most = None if max_links is None else 3 * (max_links - 1)
    if most is not None and movable > most:
        large = (", or pass allow_large=True (--allow-large) to try anyway" if movable <= MAX_MOVABLE_JOINTS else
                 f" (allow_large=True, --allow-large, reads at most {MAX_MOVABLE_JOINTS})")
        raise SpringlabError(f"{source}: {movable} movable joints: an arm of at most {max_links} links (ground "
                             f"included) has at most {most} (each moving link on one revolute joint or a spherical "
                             f"wrist of three), so this one has more than {max_links} links; designs grow "
                             f"combinatorially with n: give the URDF of the arm's own serial chain{large}")
    if movable > MAX_MOVABLE_JOINTS:
        raise SpringlabError(f"{source}: {movable} movable joints is more than springlab reads from a URDF "
                             f"({MAX_MOVABLE_JOINTS}, with allow_large=True): give the URDF of the arm's own "
                             "serial chain")
    if bodies > MAX_BODIES:
        raise SpringlabError(f"{source}: {bodies} links is more than springlab reads from a URDF ({MAX_BODIES}): "
                             "give the URDF of the arm's own serial chain, its tool merged into fewer bodies")


UP_AXES = {(0, 1, 0): "y-up", (1, 0, 0): "x-up", (0, -1, 0): "-y-up", (-1, 0, 0): "-x-up", (0, 0, -1): "-z-up",
           (0, 0, 1): "z-up"}
"""The up directions a refused URDF is read with again, in this order, to say which one it
looks like (CAD tools often export y-up)."""


@dataclass
class _Selection:
    """A URDF's arm chosen and read (:func:`_select`): its links' inertials, the root, the joints
    from the root outward (the path and the bodies fixed to it), the path's last link, up in the
    root's frame, notes, the up the caller gave and the base."""

    name: str
    links: dict
    root: str
    chain: list
    last_link: str
    up: np.ndarray
    notes: list
    given: object
    base: str | None


def _select(text: str, *, source: str, up, max_links: int | None, tip: str | None, base: str | None,
            payload: float | None) -> _Selection:
    """Parse a URDF text and choose its arm (the keywords: see :func:`read_urdf`)."""
    if not isinstance(text, str):
        raise SpringlabError(f"{source}: expected URDF text, got {type(text).__name__}")
    for value, what in ((tip, "tip"), (base, "base")):
        if value is not None and not isinstance(value, str):
            raise SpringlabError(f"{what} = {value!r}: give a link's name (a string)")
    if payload is not None:
        payload = float(_checks.positive("payload", payload, allow_zero=True, unit="kg"))
        if tip is None:
            raise SpringlabError(f"payload = {payload:g} kg is carried at the tip frame: give the tip link too (--tip LINK)")
    # a chosen chain may be a small part of a whole robot: the count that matters is the path's
    _check_size(text, source, max_links if tip is None else None)
    name, links, every_joint, notes = _parse(text, source)
    joints, base = _choose(links, every_joint, source, base, tip)
    given = up
    try:
        up = np.array([0.0, 0.0, 1.0]) if up is None else np.asarray(up, dtype=float)
    except (TypeError, ValueError):
        up = np.array([math.nan])
    if up.shape != (3,) or not np.all(np.isfinite(up)) or np.linalg.norm(up) < 1e-12:
        raise SpringlabError(f"up = {given!r}: give a nonzero 3-vector in the root link's frame, e.g. [0, 0, 1]")
    if base is not None:  # up in the base's frame at the zero configuration
        into = {j.child: j for j in every_joint}
        R, here = np.eye(3), base
        while here in into:
            R, here = into[here].origin[:3, :3] @ R, into[here].parent
        up = R.T @ up
        kept = {base, *(j.child for j in joints)}
        links = {k: v for k, v in links.items() if k in kept}
    as_written = links
    if payload:
        held = _Inertial(payload, np.zeros(3), np.zeros((3, 3)))  # a point mass at the tip frame's origin
        links = {**links, tip: held if links.get(tip) is None else _combine([links[tip], held])}
        notes.append(f"payload {payload:g} kg at the origin of link {tip!r}'s frame")
    root, chain, last_link = _serial(links, joints, source)
    notes += _check_inertias(as_written, chain, source)
    if tip is not None:
        notes.append(f"the arm runs from {root!r} to {tip!r}; every other joint is locked at zero, its bodies "
                     "carried by the link they hang from")
    return _Selection(str(name), links, root, chain, last_link, up, notes, given, base)


def _check_inertias(links: dict, chain: list, source: str) -> list:
    """Refuse a link the arm carries (one that turns with a movable joint) whose inertia is no rigid
    body's (:func:`_inertia_fault`), naming the link and its values; such a link that rides on the
    base, whose inertia is never used, is only noted."""
    moving: set = set()
    for j in chain:  # from the root outward: a joint's parent is placed before it
        if j.kind != "fixed" or j.parent in moving:
            moving.add(j.child)
    notes = []
    for name, inertial in links.items():
        why = None if inertial is None else _inertia_fault(inertial)
        if why is None:
            continue
        if name in moving:
            raise SpringlabError(
                f"{source}: link {name!r}: <inertia {inertial.given}> is no rigid body's: {why}; a rigid body's "
                "principal moments are >= 0 and each at most the sum of the other two (the triangle inequality): "
                "give the link's inertia about its centre of mass (kg m^2, e.g. from its CAD model's mass "
                "properties), or all six zero for a point mass")
        notes.append(f"link {name!r}: <inertia {inertial.given}> is no rigid body's ({why}); not used: the link "
                     "rides on the base")
    return notes


def read_urdf(text: str, *, source: str = "arm.urdf", up=None, max_links: int | None = None,
              tip: str | None = None, base: str | None = None, payload: float | None = None) -> UrdfArm:
    """The arm in a URDF text, as the fields of an arm file (see the module docstring).

    :param tip: the arm's last link: the joints on the path from the base to it are the arm,
        every other joint (a gripper's fingers, prismatic or not) is locked at zero and its
        bodies ride on the link they hang from (None: the whole tree must be one serial chain)
    :param base: the link the arm stands on (default the root); ``up`` stays in the root's frame
    :param payload: a point mass (kg) at the origin of the tip link's frame (with ``tip`` only)

    :param up: the up direction in the root link's frame (default +z: URDF's gravity is -z)
    :param max_links: refuse at once, before the file is parsed into objects, a file with more
        movable joints than an arm of this many links (ground included) can have (None: only
        :data:`MAX_MOVABLE_JOINTS`)
    """
    sel = _select(text, source=source, up=up, max_links=max_links, tip=tip, base=base, payload=payload)
    name, links, root, chain, last_link, up, notes, given, base = (sel.name, sel.links, sel.root, sel.chain,
                                                                  sel.last_link, sel.up, sel.notes, sel.given, sel.base)
    try:
        arm = _build(str(name), links, root, chain, last_link, up, source)
        arm.notes[:0] = notes
        return arm
    except SpringlabError as err:  # would the file load read with another up? then say which
        fits = [] if base is not None else [axis for axis in UP_AXES if np.linalg.norm(np.subtract(axis, up / np.linalg.norm(up))) > 1e-9
                and _loads(str(name), links, root, chain, last_link, np.array(axis, dtype=float), source)]
        if not fits:
            raise
        others = "".join(f" (or {_up_flag(axis)})" for axis in fits[1:])
        assumed = "URDF's default z-up was assumed" if given is None else f"up = {given!r} was given"
        # not a LineChainError: the general model would take the file with the wrong up, unless up was given
        kept = "" if given is not None else ("; if it is z-up, pass --up 0,0,1 to design it on the general model")
        raise UpAdviceError(f"{err}. The file looks {UP_AXES[fits[0]]}: read with up = {list(fits[0])} it loads "
                            f"({assumed}): pass {_up_flag(fits[0])}{others} (load_arm(..., up={list(fits[0])})){kept}"
                            ) from None


def _up_flag(axis) -> str:
    """The command line's option for an up axis: ``--up 0,1,0``, ``--up=0,-1,0`` (argparse takes a
    value that starts with '-' for an option unless it follows '=')."""
    value = ",".join(map(str, axis))
    return f"--up={value}" if value.startswith("-") else f"--up {value}"


def _loads(*args) -> bool:
    try:
        _build(*args)
    except SpringlabError:
        return False
    return True


def _build(name: str, links: dict, root: str, chain: list, last_link: str, up: np.ndarray, source: str) -> UrdfArm:
    """The springlab arm of a serial URDF tree (:func:`_serial`) read with ``up`` as up."""
    W = _frame_to(up / np.linalg.norm(up)).T  # URDF world -> springlab world (up -> [1, 0, 0])
    # world poses at the zero configuration; bodies grouped by the movable joint they follow
    pose = {root: np.eye(4)}
    moving = []  # (joint, its world origin, world axis)
    owner = {root: -1}  # link -> index into moving of the joint it follows (-1: the ground)
    for j in chain:
        pose[j.child] = pose[j.parent] @ j.origin
        if j.kind == "fixed":
            owner[j.child] = owner[j.parent]
            continue
        moving.append((j, W @ pose[j.child][:3, 3], W @ pose[j.child][:3, :3] @ j.axis))
        owner[j.child] = len(moving) - 1
    if not moving:
        raise SpringlabError(f"{source}: no revolute joint: nothing moves, nothing to balance")
    # group revolute joints into springlab joints: a wrist (three axes through one point) or one revolute
    groups, k = [], 0
    while k < len(moving):
        if k + 2 < len(moving):
            trio = moving[k:k + 3]
            axes = [w for _, _, w in trio]
            centre = _meet([p for _, p, _ in trio], axes)
            if centre is not None and abs(np.linalg.det(np.array(axes))) > 1e-3:
                groups.append(("spherical", trio, centre))
                k += 3
                continue
        groups.append(("revolute", [moving[k]], moving[k][1]))
        k += 1
    centres = [g[2] for g in groups]
    end = W @ pose[last_link][:3, 3]
    out = UrdfArm(name)
    # each body's mass and world COM, assigned to a springlab link (index into groups; -1 ground)
    place = [(gi, pos, len(members)) for gi, (_, members, _) in enumerate(groups) for pos in range(len(members))]
    mass = np.zeros(len(groups))
    moment = np.zeros((len(groups), 3))
    for link, idx in owner.items():
        if idx < 0 or links.get(link) is None:
            continue
        m, com = links[link].mass, links[link].com
        c = W @ (pose[link][:3, :3] @ com + pose[link][:3, 3])
        gi, pos, size = place[idx]  # the groups take the movable joints in order
        if pos < size - 1:  # inside a wrist: counted at its centre, on the link before
            reach = np.linalg.norm(c - centres[gi])
            lim = COM_TOLERANCE * (np.linalg.norm((centres[gi + 1] if gi + 1 < len(groups) else end) - centres[gi]))
            if m > 0 and reach > max(lim, MEET_TOLERANCE):
                raise LineChainError(f"{source}: link {link!r} turns with part of the wrist at joints "
                                     f"{', '.join(repr(j.name) for j, _, _ in groups[gi][1])} and its centre of mass is "
                                     f"{reach * 1e3:.1f} mm from the wrist's centre: springlab models the wrist as a "
                                     "spherical joint, exact only with such bodies' masses at its centre")
            if gi == 0:
                continue  # a wrist at the base: on the ground
            gi, c = gi - 1, centres[gi]
        mass[gi] += m
        moment[gi] += m * c
    R_prev = np.eye(3)
    for gi, (kind, members, centre) in enumerate(groups):
        link_no = gi + 2
        far = centres[gi + 1] if gi + 1 < len(groups) else end
        if gi + 1 == len(groups) and np.linalg.norm(far - centre) < 1e-9:
            if mass[gi] <= 0:
                raise LineChainError(f"{source}: the last link has no mass and no frame beyond its joint")
            far = moment[gi] / mass[gi]
            out.notes.append(f"link {link_no} (the last) runs to its centre of mass: no frame is fixed beyond its joint")
        length = float(np.linalg.norm(far - centre))
        names = ", ".join(repr(j.name) for j, _, _ in members)
        if length < 1e-9:
            raise LineChainError(f"{source}: joints {names} and the next meet at one point (a link of zero length): "
                                 "springlab models spherical joints (three axes through one point) and revolute "
                                 "joints joined by links of nonzero length")
        if mass[gi] <= 0:
            bodies = [lk for lk, idx in owner.items() if idx >= 0 and place[idx][0] == gi]
            raise LineChainError(f"{source}: link {link_no} (URDF links {', '.join(map(repr, bodies))}, after joint(s) "
                                 f"{names}) has no mass: give its <inertial> with <mass> and <origin>")
        u = (far - centre) / length
        c = moment[gi] / mass[gi]
        t = float((c - centre) @ u)
        off = c - centre - t * u
        if np.linalg.norm(off) > COM_TOLERANCE * length or not -1e-12 <= t <= length + 1e-12:
            raise LineChainError(
                f"{source}: link {link_no} (after joint(s) {names}): its centre of mass is "
                f"{np.linalg.norm(off) * 1e3:.1f} mm off the line between its joints and {t * 1e3:.1f} mm along it "
                f"(length {length * 1e3:.1f} mm); paper 000's method needs it on the line (offsets up to "
                f"{COM_TOLERANCE:.0%} of the length are projected): paper 001's pseudobase method "
                "(springlab.mechanisms.pseudobase) balances centres of mass off the line")
        if kind == "spherical":
            R = R_prev @ _frame_to(R_prev.T @ u)  # the wrist at zero: the smallest turn onto u
            out.joints.append("spherical")
            out.limits.append(None)
            if any(j.limit for j, _, _ in members):
                out.notes.append(f"joints {names}: their limits are not turned into a cone (link {link_no} "
                                 "is taken free to point anywhere)")
        else:
            j, _, w = members[0]
            a = R_prev.T @ w
            v = R_prev.T @ u
            e = np.array([1.0, 0.0, 0.0])
            if abs(a @ e - a @ v) > 1e-6:
                raise LineChainError(
                    f"{source}: joint {j.name!r}: its axis makes {math.degrees(math.acos(np.clip(a @ e, -1, 1))):.1f} deg "
                    f"with link {link_no - 1} and {math.degrees(math.acos(np.clip(a @ v, -1, 1))):.1f} deg with link "
                    f"{link_no}; springlab's revolute chains line every link up at zero angles, which needs the "
                    "same angle (an offset shoulder or elbow is not such a chain)")
            e_p, v_p = e - (a @ e) * a, v - (a @ v) * a
            theta0 = 0.0 if np.linalg.norm(e_p) < 1e-12 else math.atan2(float(a @ np.cross(e_p, v_p)), float(e_p @ v_p))
            R = R_prev @ rot_axis(a, theta0)
            out.joints.append(tuple(float(x) for x in a))
            out.limits.append(_range(j, theta0, out.notes))
        out.r.append(length)
        out.d.append(min(max(t, 0.0), length))
        out.m.append(float(mass[gi]))
        out.offsets.append(tuple(float(x) for x in R.T @ off))
        R_prev = R
    return out


def _range(joint, theta0: float, notes: list):
    """A URDF joint's limits in springlab's angle (theta0 + q), within [-pi, pi], or None."""
    if joint.limit is None:
        return None
    lo, hi = theta0 + joint.limit[0], theta0 + joint.limit[1]
    if hi - lo >= 2 * math.pi - 1e-12:
        return None
    for shift in (0.0, 2 * math.pi, -2 * math.pi):
        if -math.pi <= lo + shift and hi + shift <= math.pi:
            return (lo + shift, hi + shift)
    notes.append(f"joint {joint.name!r}: its range straddles the half turn from springlab's zero; taken as unlimited")
    return None


def urdf_to_dict(text: str, *, source: str = "arm.urdf", up=None, max_links: int | None = None,
                 tip: str | None = None, base: str | None = None, payload: float | None = None) -> tuple[dict, UrdfArm]:
    """The arm file's fields (as :func:`springlab.model.armfile.arm_from_dict` takes them, SI
    numbers) for a URDF text, and what :func:`read_urdf` found (the keywords: see there)."""
    arm = read_urdf(text, source=source, up=up, max_links=max_links, tip=tip, base=base, payload=payload)
    links = []
    for r, d, m, joint, lim in zip(arm.r, arm.d, arm.m, arm.joints, arm.limits, strict=True):
        link = {"length": r, "com": d, "mass": m, "joint": joint if joint == "spherical" else list(joint)}
        if lim is not None:
            link["range"] = [lim[0], lim[1]]  # rad
        links.append(link)
    return {"name": arm.name, "link": links}, arm


def read_revolute_chain(text: str, *, source: str = "arm.urdf", up=None, tip: str | None = None,
                        base: str | None = None, payload: float | None = None, g: float | None = None,
                        folder=None, package_dirs=(), shapes: bool = True):
    """The arm in a URDF text as the general model, a :class:`~springlab.model.revolute.RevoluteChain`
    built from the file's own frames: nothing is projected or refused for its geometry (offset
    shoulders, centres of mass anywhere, joints meeting at a point are all kept as they are).

    Body 0 is the base (``base``, default the root) with every body fixed to it; body i is the
    child link of the i-th movable joint on the path, its frame that link's URDF frame, carrying
    every link fixed to it (and, with a tip, every joint off the path locked at zero, as
    Pinocchio's ``buildReducedModel`` does): masses added, centres combined, inertias moved to the
    common centre. Gravity is ``-g up`` (``up`` default +z of the root, expressed in the base's
    frame; g default :data:`springlab.model.chain.STANDARD_GRAVITY`). A revolute joint's URDF
    limits are its range (rad); a continuous joint (or lower = upper) is unlimited.

    Each body's **outline** is read from the links' geometry (:mod:`springlab.model.shapes`: the
    collision shapes, else the visual ones, meshes found from ``folder``, the URDF's folder, and
    ``package_dirs`` as ROS resolves ``package://``): points in the body's frame whose hull bounds
    it, what a spring may be attached to. ``shapes=False`` skips it.

    The keywords ``tip``, ``base``, ``payload`` and ``up`` are those of :func:`read_urdf`.
    """
    g = STANDARD_GRAVITY if g is None else _checks.positive("g", g, unit="m/s^2")
    sel = _select(text, source=source, up=up, max_links=None, tip=tip, base=base, payload=payload)
    pose, owner, movers, frames = {sel.root: np.eye(4)}, {sel.root: 0}, [], [np.eye(4)]
    for j in sel.chain:  # from the root outward: a joint's parent is placed before it
        pose[j.child] = pose[j.parent] @ j.origin
        if j.kind == "fixed":
            owner[j.child] = owner[j.parent]
            continue
        movers.append(j)
        frames.append(pose[j.child])
        owner[j.child] = len(movers)
    if not movers:
        raise SpringlabError(f"{source}: no revolute joint between {sel.root!r} and the tip: nothing moves, "
                             "nothing to balance")
    parts: list[list] = [[] for _ in frames]
    for link, body in owner.items():
        inertial = sel.links.get(link)
        if inertial is None or body == 0:
            continue
        T = np.linalg.solve(frames[body], pose[link])  # the link's frame in its body's
        parts[body].append(_Inertial(inertial.mass, T[:3, :3] @ inertial.com + T[:3, 3],
                                     T[:3, :3] @ inertial.inertia @ T[:3, :3].T))
    bodies = [_combine(p) if p else _Inertial(0.0, np.zeros(3), np.zeros((3, 3))) for p in parts]
    placements = [np.linalg.solve(frames[i - 1], frames[i]) for i in range(1, len(frames))]
    limits = [j.limit if j.kind == "revolute" and j.limit is not None else (-np.inf, np.inf) for j in movers]
    massless = [j.child for i, j in enumerate(movers, start=1) if bodies[i].mass == 0]
    notes = list(sel.notes)
    if massless:
        notes.append(f"links {', '.join(map(repr, massless))} carry no mass (no <inertial>, or mass 0)")
    fixed = {link: (body, np.linalg.solve(frames[body], pose[link])) for link, body in owner.items()
             if link != sel.root and link not in (j.child for j in movers)}
    up_unit = sel.up / np.linalg.norm(sel.up)
    outline, solids = (), ()
    if shapes:
        T_body = {link: np.linalg.solve(frames[body], pose[link]) for link, body in owner.items()}
        names = (sel.root, *(j.child for j in movers))
        length = float(np.sum(np.linalg.norm(np.array(placements)[:, :3, 3], axis=1)))
        outline, solids, said = _outlines(text, owner, T_body, names, folder, package_dirs, length, source)
        notes += said
    return RevoluteChain(sel.name, (sel.root, *(j.child for j in movers)), tuple(j.name for j in movers),
                         np.array(placements), np.array([j.axis for j in movers]),
                         np.array([b.mass for b in bodies]), np.array([b.com for b in bodies]),
                         np.array([(b.inertia + b.inertia.T) / 2 for b in bodies]), -g * up_unit,
                         np.array(limits, dtype=float), tuple(notes), fixed, outline, solids)


def _hull(points: np.ndarray) -> np.ndarray:
    """The vertices of the points' convex hull (the points themselves when they are flat)."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        return points[ConvexHull(points).vertices]
    except (QhullError, ValueError):
        return points


OUTLINE_LIMITS = (1e-3, 5.0)
"""A body's outline is ignored (with a note) when its largest side is under 1 mm (a point: a zero
scale or size) or over 5 times the arm's length (at least 2 m: a mesh in millimetres read as metres,
a misplaced scale)."""


def _outlines(text, owner, T_body, names, folder, package_dirs, length, source) -> tuple[tuple, tuple, list]:
    """Each body's outline (points, m, body frame) and solids (:class:`~springlab.model.shapes.Solid`, what
    the collision check reads) from its links' shapes (collision, else visual:
    also where no collision shape of a link could be read), and notes on what was read and what was
    not (a mesh not found or unreadable, an outline out of proportion, a body with no geometry). A
    mesh that would give a false outline (:class:`~springlab.model.shapes.RefusedMeshError`) is
    refused, with its link named."""

    found, notes = link_shapes(text)
    points = [[] for _ in names]
    solids = [[] for _ in names]
    missing, unreadable, read = {}, {}, 0
    for link, body in owner.items():
        for shapes in found.get(link, ((), ())):
            placed, kept = [], []
            for shape in shapes:
                try:
                    local = shape_points(shape, folder, package_dirs, notes)
                except MeshError as err:
                    if isinstance(err, RefusedMeshError):  # a false outline, not a missing one: refused
                        raise RefusedMeshError(f"{source}: link {link!r}: {err}", filename=err.filename) from None
                    if err.found:
                        unreadable.setdefault(str(err), None)
                    else:
                        missing.setdefault(shape.filename, None)
                    continue
                T = T_body[link]
                placed.append(local @ T[:3, :3].T + T[:3, 3])
                kept.append(shape_solid(shape, link, T, folder, package_dirs))
            if placed:  # the collision shapes read, else the visual ones
                points[body] += placed
                solids[body] += kept
                read += len(placed)
                break
    if missing:
        shown = ", ".join(map(repr, list(missing)[:3])) + (f" and {len(missing) - 3} more" if len(missing) > 3 else "")
        packages = sorted({m[len("package://"):].lstrip("/").split("/")[0] for m in missing if m.startswith("package://")})
        where = (f"give the folder that holds package {', '.join(map(repr, packages))} with --package-dir (searched: "
                 "folders above the URDF, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH)" if packages
                 else "relative paths are read from the URDF's folder")
        notes.append(f"{_plural(len(missing), 'mesh', 'meshes')} not found ({shown}): {where}; those links fall "
                     "back to their other shapes or the default reach")
    if unreadable:
        notes.append(f"{_plural(len(unreadable), 'mesh', 'meshes')} could not be read ({next(iter(unreadable))}): "
                     "left out")
    if not read:
        return (), (), notes
    small, large = OUTLINE_LIMITS[0], max(2.0, OUTLINE_LIMITS[1] * length)
    outline = []
    for i, p in enumerate(points):
        hull = _hull(np.vstack(p)) if p else np.zeros((0, 3))
        side = float(np.max(np.ptp(hull, axis=0))) if len(hull) else 0.0
        if len(hull) and not small <= side <= large:
            why = "a point (a zero scale or size?)" if side < small else (
                f"{side:.3g} m across, more than {large:.3g} m (5 times the arm's length, at least 2 m): a mesh in "
                "other units, or a wrong scale?")
            notes.append(f"the geometry of {names[i]!r} is {why}: ignored, the default reach there")
            hull = np.zeros((0, 3))
            solids[i] = []
        outline.append(hull)
    empty = [repr(names[i]) for i, p in enumerate(outline) if len(p) == 0]
    if len(empty) == len(outline):
        return (), (), notes
    notes.append(f"the bodies' outlines (where springs attach) come from {_plural(read, 'shape', 'shapes')} of the "
                 "file's geometry" + (f"; {', '.join(empty)} {'has' if len(empty) == 1 else 'have'} none (the default "
                                      "reach there)" if empty else ""))
    return tuple(outline), tuple(tuple(s) for s in solids), notes


def _plural(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"
