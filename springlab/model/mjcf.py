"""An arm of the general model with its springs, written as a MuJoCo model (MJCF): the hand-over
to the simulator the robotics field uses every day.

What the file holds (:func:`to_mjcf`), all from the :class:`~springlab.model.revolute.RevoluteChain`
and its :class:`~springlab.model.springs.PointSpring` springs, in SI units and radians, with XML
comments that say what each generated element is:

* one ``<body>`` per moving body, nested as the chain is, named as the URDF's links, placed by
  the joint's placement (``pos``, ``quat``), with a ``hinge`` joint named as the URDF's joint
  at its origin about its axis, ``range`` from the URDF's limits (none for an unlimited joint);
* each body's mass, centre of mass and full inertia tensor about it (``<inertial>``; a massless
  body, such as the two between a spherical joint's axes, gets :data:`TINY_MASS` kg, because
  MuJoCo refuses a moving body without mass: its gravity torque is below 1e-10 N m);
* the base's bodies fixed to the world (the world is the base frame, gravity as the model has it);
* each spring a spatial tendon between two sites at its attachment points, named S1, S2, ...,
  with the spring's rate (``stiffness``) and its force law's zero (``springlength``: the
  effective free length L_0 - F_i / k, 0 for an ideal spring, so that MuJoCo's force
  k (l - springlength) equals F_i + k (l - L_0));
* a spring whose cable runs over a pulley of radius rho > 0 (route 2's
  :func:`springlab.energy.geometry.cable_geometry`: the cable arrives along the lead u, fixed in
  link A, and the pulley at A swivels about u into the plane of u and B - A): a sphere of radius
  rho centred at A on link A's body stands for the pulley, and the cable starts at a site on the
  lead's line d = :data:`LEAD_RUN` m (at least 4 rho) behind A. MuJoCo wraps a tendon over a
  sphere in the plane through its centre and the tendon's two ends, here the plane of u and B - A,
  route 2's plane at every pose with no joint to turn; going round the sphere's far side from B,
  as route 2's cable does, the wrapped path is route 2's path plus the constant run
  sqrt(d^2 - rho^2) + rho asin(rho / d). MuJoCo (4.0 on) takes the side a side site shows, the
  way the path from the start through the side site to B winds round the sphere; a side site is
  fixed in its body, and no site fixed in link A lies on B's far side at every pose. So the spring
  is three tendons on the same sites, each of springlength (L_0 - F_i / k) + run: two of rate k
  wrapping the sphere with side sites :data:`SIDE_OFFSET` rho in front of A and :data:`SIDE_TILT`
  of that off the lead, on opposite sides (in the direction ``_aside`` picks from B's poses),
  and one of rate -k with no side site (the shortest path). At every pose the tendon whose side
  site lies on B's far side takes route 2's path and the other the shortest path, which the third
  takes too and cancels: MuJoCo's passive forces are route 2's cable's to round-off. They differ
  only where B lies within :data:`SIDE_TILT` rad (about 6e-4 degrees) of the lead's line behind A,
  or where B's offset from the lead is within about 1e-9 rad of square to the side sites' offset;
* a frame a belt carries (:meth:`~springlab.model.revolute.RevoluteChain.with_belt`): a body on the
  joint's parent, on a hinge about its axis that a fixed tendon and an equality hold at minus the signed
  sum of the joints between; a pseudobase that paper 001's RSSR modules carry
  (:meth:`~springlab.model.revolute.RevoluteChain.with_pseudobase`): a body on the level body (so its axes
  are that body's) on three slides, whose origin a ``connect`` equality holds at its point of the joint's
  axis on the joint's parent body;
* every name the file generates (sites, the pulley spheres, tendons, meshes) differs from every
  other name in it, the URDF's links and joints among them (a suffix " (2)", " (3)", ... where one
  would clash);
* each body drawn as the hull of its outline (the URDF's collision geometry,
  :mod:`springlab.model.shapes`) where known, else as a capsule from its joint to the next, none of
  them colliding (statics and release only).

MuJoCo's holding torque at rest is ``qfrc_bias - qfrc_passive`` (gravity less the tendons' spring
forces), route 2's :func:`springlab.energy.geometry.joint_torques`, with only the arm's joints set;
the check lives in :mod:`springlab.workbench.references`, never in the routes.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, check_point_springs, world_points

TINY_MASS = 1e-12
"""kg: the mass (and, times 1 m^2, the inertia) a massless body is given in MuJoCo, which refuses a
moving body without mass."""


def _vec(values) -> str:
    return " ".join(repr(float(v)) for v in values)


def _g(values) -> str:
    return " ".join(f"{float(v) + 0.0:.6g}" for v in values)


def _quat(R: np.ndarray) -> np.ndarray:
    """A rotation matrix as MuJoCo's unit quaternion (w, x, y, z)."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(R).as_quat()
    return np.array([w, x, y, z])


def to_mjcf(model: RevoluteChain, springs=(), *, name: str | None = None) -> str:
    """The arm and its springs as MJCF text (see the module docstring; lengths in m, angles in rad,
    rates in N/m). ``springs``: the :class:`~springlab.model.springs.PointSpring` springs (ideal or
    realised: each with its rate, free length and initial tension, a cable's over its pulley)."""
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    springs = check_point_springs(model, springs)
    for s in springs:
        if s.effective_free_length < 0:
            raise SpringlabError(f"{s.label}: its initial tension F_i = {s.initial_tension:g} N exceeds k L_0 = "
                                 f"{s.k * s.free_length:g} N, a force law MuJoCo's tendon spring cannot hold")
    names = _Names([*model.bodies, *model.joints])
    root = ET.Element("mujoco", model=name or model.name)
    _comment(root, "written by springlab (springlab.model.mjcf.to_mjcf): SI units (m, kg, s, N), angles in rad. "
                   "The holding torque at rest is qfrc_bias - qfrc_passive after mj_forward, only the arm's joints set.")
    ET.SubElement(root, "compiler", angle="radian", autolimits="true", balanceinertia="true")
    ET.SubElement(root, "option", gravity=_vec(model.gravity), timestep="0.001", integrator="implicitfast")
    default = ET.SubElement(root, "default")
    ET.SubElement(default, "geom", contype="0", conaffinity="0", rgba="0.75 0.75 0.78 1")
    ET.SubElement(default, "site", size="0.006", rgba="0.1 0.1 0.1 1")
    asset = ET.SubElement(root, "asset")
    world = ET.SubElement(root, "worldbody")
    ET.SubElement(world, "light", pos=_vec(0.5 * model.up + [0.3, 0.3, 0.0] * (1 - np.abs(model.up))),
                  dir=_vec(-model.up))
    parents = [world]
    for i in range(1, model.n + 1):
        P = model.placements[i - 1]
        body = ET.SubElement(parents[-1], "body", name=model.bodies[i], pos=_vec(P[:3, 3]), quat=_vec(_quat(P[:3, :3])))
        joint = ET.SubElement(body, "joint", name=model.joints[i - 1], type="hinge", axis=_vec(model.axes[i - 1]))
        lo, hi = model.limits[i - 1]
        if np.isfinite(lo) and np.isfinite(hi):
            joint.set("range", _vec((lo, hi)))
        _inertial(body, model.mass[i], model.com[i], model.inertia[i])
        parents.append(body)
    for b in range(model.n + 1):
        _shape(model, b, parents[b], asset, names)
    belts = _belts(model, parents, names)
    tendons = ET.SubElement(root, "tendon") if springs or belts else None
    if belts:
        equality = ET.SubElement(root, "equality")
        for belt, hinge, between in belts:
            if belt.kind != "belt":  # a pseudobase: held at its point of the joint's parent body
                ET.SubElement(equality, "connect", name=names.take(f"{belt.name} holds"), body1=hinge,
                              body2=model.bodies[belt.joint], anchor="0 0 0")
                continue
            fixed = ET.SubElement(tendons, "fixed", name=names.take(f"{belt.name} turns"))
            _comment(tendons, f"'{fixed.get('name')}': the belt holds hinge '{hinge}' at minus the sum of the joints "
                              "between (signed): the pulley keeps the level body's axes")
            ET.SubElement(fixed, "joint", joint=hinge, coef="1")
            for joint, sign in between:
                ET.SubElement(fixed, "joint", joint=joint, coef=repr(float(sign)))
            ET.SubElement(equality, "tendon", name=names.take(f"{belt.name} holds"), tendon1=fixed.get("name"))
    if springs:
        _comment(tendons, "each spring's tendons pull k (l - springlength), springlength = L0 - Fi/k (free length less "
                          "initial tension over rate); a cable's over its pulley also counts the constant run from its "
                          "start site on the lead to the pulley")
    for k, s in enumerate(springs, start=1):
        body_b, local_b = model.locate(s.link_b, s.point_b)
        site_b = names.take(f"S{k} B")
        _comment(parents[body_b], f"'{site_b}': spring S{k}'s end B on link {s.link_b}")
        ET.SubElement(parents[body_b], "site", name=site_b, pos=_vec(local_b))
        body_a, local_a = model.locate(s.link_a, s.point_a)
        if s.pulley_radius > 0:
            _pulley(model, s, k, parents[body_a], local_a, site_b, tendons, names)
            continue
        site_a = names.take(f"S{k} A")
        _comment(parents[body_a], f"'{site_a}': spring S{k}'s end A on link {s.link_a}")
        ET.SubElement(parents[body_a], "site", name=site_a, pos=_vec(local_a))
        tendon_name = names.take(f"S{k}")
        _comment(tendons, f"'{tendon_name}': spring S{k} from '{site_a}' to '{site_b}', rate k = {s.k:.6g} N/m, "
                          f"springlength = L0 - Fi/k = {s.effective_free_length:.6g} m (L0 = {s.free_length:.6g} m the "
                          f"free length, Fi = {s.initial_tension:.6g} N the initial tension)")
        tendon = ET.SubElement(tendons, "spatial", name=tendon_name, stiffness=repr(float(s.k)),
                               springlength=repr(float(s.effective_free_length)), width="0.003", rgba="0.85 0.2 0.2 1")
        ET.SubElement(tendon, "site", site=site_a)
        ET.SubElement(tendon, "site", site=site_b)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


def _belts(model: RevoluteChain, parents: list, names) -> list:
    """A body per belt's frame (:attr:`~springlab.model.revolute.RevoluteChain.belts`): on its joint's parent
    body at the joint's origin, turning on a hinge about the joint's axis, its axes the level body's at
    zero angles; appended to ``parents`` (a spring's site on the belt's frame goes there). Returns, per
    belt, the belt, its hinge's name and the joints between with their signs (the hinge's angle is minus
    their signed sum: :meth:`~springlab.model.revolute.RevoluteChain.belt_turns`). A pseudobase (kind
    'rssr') is a body on the level body, on three slides, and in place of the hinge its body's name (a
    'connect' equality holds it at its point of the joint's parent body), with no joints between."""
    out = []
    if not model.belts:
        return out
    R0, o0 = body_frames(model, np.zeros(model.n))
    for j, belt in enumerate(model.belts):
        if belt.kind != "belt":  # paper 001's pseudobase: the level body's axes by construction, its point held
            at = R0[0, belt.level].T @ (o0[0, model.n + 1 + j] - o0[0, belt.level])
            body = ET.SubElement(parents[belt.level], "body", name=names.take(belt.name), pos=_vec(at))
            _comment(body, f"pseudobase '{belt.name}': paper 001's RSSR modules keep its vertical line; here a body on "
                           f"{model.bodies[belt.level]} (so its axes are that body's) sliding freely, whose origin the "
                           f"'connect' below holds at its point of joint {model.joints[belt.joint]}'s axis")
            for axis, tag in zip(np.eye(3), "xyz", strict=True):
                ET.SubElement(body, "joint", name=names.take(f"{belt.name} slide {tag}"), type="slide", axis=_vec(axis))
            _inertial(body, 0.0, np.zeros(3), np.zeros((3, 3)))
            parents.append(body)
            out.append((belt, body.get("name"), None))
            continue
        axis, signs = model.belt_turns(belt)
        P = model.placements[belt.joint]
        at = P[:3, 3] + belt.along * (P[:3, :3] @ model.axes[belt.joint])  # on the joint's axis
        body = ET.SubElement(parents[belt.joint], "body", name=names.take(belt.name), pos=_vec(at),
                             quat=_vec(_quat(R0[0, belt.joint].T @ R0[0, belt.level])))
        _comment(body, f"belt frame '{belt.name}': a pulley on joint {model.joints[belt.joint]}'s axis, held by a 1:1 "
                       f"belt to {model.bodies[belt.level]}'s axes (set its hinge to minus the signed sum of the joints "
                       "between, or let the equality below hold it)")
        hinge = names.take(f"{belt.name} hinge")
        ET.SubElement(body, "joint", name=hinge, type="hinge", axis=_vec(axis))
        _inertial(body, 0.0, np.zeros(3), np.zeros((3, 3)))
        parents.append(body)
        out.append((belt, hinge, [(model.joints[t], s) for t, s in zip(range(belt.level, belt.joint), signs,
                                                                        strict=True)]))
    return out


LEAD_RUN = 0.05
"""m: how far behind the pulley's centre A, along the lead, the cable's start site lies (at least
4 times the pulley's radius): the cable runs straight from it to the pulley, a constant length
taken out of the tendons' ``springlength``."""

SIDE_OFFSET = 2.0
"""The side sites lie this many pulley radii in front of A along the lead (outside the sphere:
a side site inside it would make MuJoCo pass the tendon through the sphere)."""

SIDE_TILT = 1e-5
"""The side sites' offset off the lead's line, as a fraction of their distance in front of A (so
about this many rad): small, because the tendon through the side site on B's far side takes
route 2's path only while B is more than this angle (rad) from the lead's line behind A."""


SIDE_POSES = 2000
"""How many random poses within the joint limits ``_aside`` reads B's directions from."""


def _aside(model: RevoluteChain, s, n0, m0) -> np.ndarray:
    """The direction (unit, (2,) in the lead's frame: along its y and z axes ``n0``, ``m0``) the side
    sites are set off the lead. They fail to tell B's two sides of the lead apart only where B's
    offset from the lead is square to it, so it is kept as far from that as B goes: over
    :data:`SIDE_POSES` random poses within the limits, the middle of the widest range of directions
    that no pose's offset is square to (along B's offset where B keeps to one plane through the lead)."""
    q = model.random_q(SIDE_POSES, np.random.default_rng(0))
    R, o = body_frames(model, q)
    a, pa = model.locate(s.link_a, s.point_a)
    D = np.einsum("pji,pj->pi", R[:, a], world_points(R, o, *model.locate(s.link_b, s.point_b))
                  - world_points(R, o, a, pa))  # B - A in body a's frame
    x, y = D @ n0, D @ m0
    keep = np.hypot(x, y) > 1e-9 * np.linalg.norm(D, axis=1)  # B off the lead's line
    if not np.any(keep):
        return np.array([1.0, 0.0])
    square = np.sort(np.mod(np.arctan2(y[keep], x[keep]) + np.pi / 2, np.pi))  # the directions, mod pi, to avoid
    gaps = np.diff(np.append(square, square[0] + np.pi))
    widest = int(np.argmax(gaps))
    angle = square[widest] + gaps[widest] / 2
    return np.array([np.cos(angle), np.sin(angle)])


class _Names:
    """The file's names: each generated one made different from every name already taken (a
    suffix ' (2)', ' (3)', ... where it would clash), the arm's own links and joints taken first."""

    def __init__(self, taken):
        self.taken = set(taken)

    def take(self, name: str) -> str:
        out, n = name, 1
        while out in self.taken:
            n += 1
            out = f"{name} ({n})"
        self.taken.add(out)
        return out


def _comment(parent, text: str) -> None:
    """An XML comment as ``parent``'s next child (an XML comment may hold no '--' nor end in '-')."""
    while "--" in text:
        text = text.replace("--", "- -")
    parent.append(ET.Comment(f" {text} "))


def _pulley(model: RevoluteChain, s, k: int, parent, centre, site_b: str, tendons, names: _Names) -> None:
    """Spring k's cable over its pulley (see the module docstring): in link_a's body (``parent``), a
    frame at A (``centre``, m, in that body's frame) whose x axis is the lead u, holding the pulley
    (a sphere of the spring's radius rho, m), the cable's start on the lead d behind A and the two
    side sites; and the three tendons (rates k, k and -k, N/m) from the start over the sphere to B
    (``site_b``), each of springlength (L_0 - F_i / k) + run, the run the constant length from the
    start site round to where the cable would arrive along the lead."""
    rho = s.pulley_radius
    u = model.direction(s.link_a, s.lead)[1]
    u = u / np.linalg.norm(u)
    trial = np.array([1.0, 0.0, 0.0]) if abs(u[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    n0 = np.cross(u, trial)
    n0 /= np.linalg.norm(n0)
    m0 = np.cross(u, n0)
    lead = np.column_stack([u, n0, m0])
    w = _aside(model, s, n0, m0)
    d = max(LEAD_RUN, 4.0 * rho)
    run = float(np.sqrt(d * d - rho * rho) + rho * np.arcsin(rho / d))
    ahead, aside = SIDE_OFFSET * rho, SIDE_TILT * SIDE_OFFSET * rho
    geom, start = names.take(f"S{k} pulley"), names.take(f"S{k} A")
    sides = [names.take(f"S{k} side 1"), names.take(f"S{k} side 2")]
    _comment(parent, f"spring S{k}'s pulley at its end A on link {s.link_a}: a frame at A whose x axis is the lead "
                     f"u = ({_g(s.lead)}) in link {s.link_a}'s frame, the direction the cable arrives along")
    frame = ET.SubElement(parent, "frame", pos=_vec(centre), quat=_vec(_quat(lead)))
    _comment(frame, f"'{geom}': the pulley, a sphere of radius rho = {rho:.6g} m centred at A. MuJoCo wraps a tendon "
                    "over a sphere in the plane through its centre and the tendon's ends: here the plane of the lead "
                    "and B, the plane the pulley swivels into about the lead, at every pose")
    ET.SubElement(frame, "geom", name=geom, type="sphere", size=repr(float(rho)), rgba="0.3 0.3 0.35 1")
    _comment(frame, f"'{start}': the cable's start, on the lead d = {d:.6g} m behind A")
    ET.SubElement(frame, "site", name=start, pos=_vec((-d, 0.0, 0.0)), size=repr(float(rho / 2)))
    _comment(frame, f"'{sides[0]}', '{sides[1]}': side sites {ahead:.6g} m in front of A and {aside:.3g} m off the lead, "
                    "on either side (site group 3, hidden by default): a tendon through the one on B's far side from "
                    "the lead wraps the pulley as the cable does, arriving on that side")
    for side, sign in zip(sides, (1.0, -1.0), strict=True):
        ET.SubElement(frame, "site", name=side, pos=_vec((ahead, *(sign * aside * w))), size=repr(float(rho / 4)),
                      group="3")
    springlength = repr(float(run + s.effective_free_length))
    wraps = [names.take(f"S{k} via side 1"), names.take(f"S{k} via side 2"), names.take(f"S{k} shortest")]
    _comment(tendons, f"spring S{k} (rate k = {s.k:.6g} N/m): a cable from '{start}' over the pulley '{geom}' to "
                      f"'{site_b}'. springlength = (L0 - Fi/k) + run = {s.effective_free_length:.6g} + {run:.6g} m: "
                      f"L0 = {s.free_length:.6g} m the free length, Fi = {s.initial_tension:.6g} N the initial tension, "
                      "run = sqrt(d^2 - rho^2) + rho asin(rho/d) the constant length from the start site round to where "
                      "the cable arrives along the lead. Three tendons pull as the one cable: of the first two (rate k), "
                      "the one whose side site is on B's far side from the lead takes the cable's path, the longer, and "
                      "the other the shortest path, which the third (rate -k, no side site) takes too and cancels")
    for tendon_name, side, rate in zip(wraps, (*sides, None), (s.k, s.k, -s.k), strict=True):
        tendon = ET.SubElement(tendons, "spatial", name=tendon_name, stiffness=repr(float(rate)),
                               springlength=springlength, width="0.003" if side else "0.002",
                               rgba="0.85 0.2 0.2 1" if side else "0.5 0.5 0.5 0.4")
        ET.SubElement(tendon, "site", site=start)
        wrap = ET.SubElement(tendon, "geom", geom=geom)
        if side:
            wrap.set("sidesite", side)
        ET.SubElement(tendon, "site", site=site_b)


def _inertial(body, mass: float, com, inertia) -> None:
    J = np.asarray(inertia, dtype=float)
    if mass <= 0:
        mass, J = TINY_MASS, np.eye(3) * TINY_MASS
    w = np.linalg.eigvalsh(J)
    if w[0] <= TINY_MASS:  # a point mass (a payload): MuJoCo needs a positive inertia
        J = J + np.eye(3) * (TINY_MASS - min(w[0], 0.0))
    ET.SubElement(body, "inertial", pos=_vec(com), mass=repr(float(mass)),
                  fullinertia=_vec((J[0, 0], J[1, 1], J[2, 2], J[0, 1], J[0, 2], J[1, 2])))


def _shape(model: RevoluteChain, b: int, body, asset, names: _Names) -> None:
    """Body b drawn: the hull of its outline where known, else a capsule to the next joint."""
    points = model.outline[b] if model.outline else np.zeros((0, 3))
    if len(points) >= 4 and np.linalg.matrix_rank(points - points.mean(axis=0), tol=1e-9) == 3:
        mesh = names.take(f"outline {model.bodies[b]}")
        _comment(asset, f"'{mesh}': the hull of link {model.bodies[b]}'s collision geometry (m, in its body's frame), "
                        "drawn only")
        ET.SubElement(asset, "mesh", name=mesh, vertex=" ".join(f"{v:.6g}" for v in np.asarray(points).ravel()))
        ET.SubElement(body, "geom", type="mesh", mesh=mesh, group="1")
        return
    far = model.placements[b][:3, 3] if b < model.n else model.com[b]
    if np.linalg.norm(far) > 1e-9:
        ET.SubElement(body, "geom", type="capsule", size="0.01", fromto=_vec((0, 0, 0, *far)), group="1")
