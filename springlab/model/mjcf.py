"""An arm of the general model with its springs, written as a MuJoCo model (MJCF): the hand-over
to the simulator the robotics field uses every day.

What the file holds (:func:`to_mjcf`), all from the :class:`~springlab.model.revolute.RevoluteChain`
and its :class:`~springlab.model.springs.PointSpring` springs, in SI units and radians:

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
* a spring whose cable runs over a pulley of nonzero radius: the tendon starts on the lead's line,
  wraps a cylinder of the pulley's radius at A (its side site on the far side from the lead) and
  ends at B; the pulley swivels about the lead on a light hinge, as route 2's pulley does;
* each body drawn as the hull of its outline (the URDF's collision geometry,
  :mod:`springlab.model.shapes`) where known, else as a capsule from its joint to the next, none of
  them colliding (statics and release only).

MuJoCo's holding torque at rest is ``qfrc_bias - qfrc_passive`` (gravity less the tendons' spring
forces), route 2's :func:`springlab.energy.geometry.joint_torques`; the check lives in
:mod:`springlab.workbench.references`, never in the routes.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain, check_point_springs

TINY_MASS = 1e-12
"""kg: the mass (and, times 1 m^2, the inertia) a massless body is given in MuJoCo, which refuses a
moving body without mass."""


def _vec(values) -> str:
    return " ".join(repr(float(v)) for v in values)


def _quat(R: np.ndarray) -> np.ndarray:
    """A rotation matrix as MuJoCo's unit quaternion (w, x, y, z)."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(R).as_quat()
    return np.array([w, x, y, z])


def to_mjcf(model: RevoluteChain, springs=(), *, name: str | None = None) -> str:
    """The arm and its springs as MJCF text (see the module docstring). ``springs``: the
    :class:`~springlab.model.springs.PointSpring` springs (ideal or realised: each with its rate,
    free length and initial tension)."""
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    springs = check_point_springs(model, springs)
    for s in springs:
        if s.effective_free_length < 0:
            raise SpringlabError(f"{s.label}: its initial tension F_i = {s.initial_tension:g} N exceeds k L_0 = "
                                 f"{s.k * s.free_length:g} N, a force law MuJoCo's tendon spring cannot hold")
    root = ET.Element("mujoco", model=name or model.name)
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
        _shape(model, b, parents[b], asset)
    tendons = ET.SubElement(root, "tendon") if springs else None
    for k, s in enumerate(springs, start=1):
        body_b, local_b = model.locate(s.link_b, s.point_b)
        ET.SubElement(parents[body_b], "site", name=f"S{k} B", pos=_vec(local_b))
        body_a, local_a = model.locate(s.link_a, s.point_a)
        run = 0.0
        if s.pulley_radius > 0:
            run = _pulley(model, s, k, parents[body_a], local_a)
        else:
            ET.SubElement(parents[body_a], "site", name=f"S{k} A", pos=_vec(local_a))
        tendon = ET.SubElement(tendons, "spatial", name=f"S{k}", stiffness=repr(float(s.k)),
                               springlength=repr(float(run + s.effective_free_length)), width="0.003",
                               rgba="0.85 0.2 0.2 1")
        ET.SubElement(tendon, "site", site=f"S{k} A")
        if s.pulley_radius > 0:
            ET.SubElement(tendon, "geom", geom=f"S{k} pulley", sidesite=f"S{k} side")
        ET.SubElement(tendon, "site", site=f"S{k} B")
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


LEAD_RUN = 0.05
"""m: the length of cable drawn between the spring's end and its pulley (straight along the lead,
so it adds a constant to the tendon's length, taken out of its ``springlength``)."""


def _pulley(model: RevoluteChain, s, k: int, parent, centre) -> float:
    """Spring k's pulley: a body at A (``centre``, in link_a's body frame) that swivels about the
    lead (a hinge, 'S{k} swivel'; its x axis the lead), carrying the pulley (a cylinder of the
    spring's radius about its z axis), the cable's start 'S{k} A' on the lead's line at the
    pulley's rim, :data:`LEAD_RUN` back, and the side site that makes the cable wrap the pulley
    away from where it arrives. At rest the swivel holds B in the pulley's plane
    (:func:`springlab.workbench.references.mujoco_holding_torques` sets it so). Returns the run."""
    rho = s.pulley_radius
    u = model.direction(s.link_a, s.lead)[1]
    u = u / np.linalg.norm(u)
    trial = np.array([1.0, 0.0, 0.0]) if abs(u[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    n0 = np.cross(u, trial)
    n0 /= np.linalg.norm(n0)
    frame = np.column_stack([u, n0, np.cross(u, n0)])
    body = ET.SubElement(parent, "body", name=f"S{k} pulley", pos=_vec(centre), quat=_vec(_quat(frame)))
    ET.SubElement(body, "joint", name=f"S{k} swivel", type="hinge", axis="1 0 0", armature="1e-6", damping="1e-4")
    ET.SubElement(body, "inertial", pos="0 0 0", mass=repr(TINY_MASS), diaginertia=_vec([TINY_MASS] * 3))
    ET.SubElement(body, "geom", name=f"S{k} pulley", type="cylinder", size=_vec((rho, rho / 2)), rgba="0.3 0.3 0.35 1")
    ET.SubElement(body, "site", name=f"S{k} A", pos=_vec((-LEAD_RUN, -rho, 0.0)))
    ET.SubElement(body, "site", name=f"S{k} side", pos=_vec((1.5 * rho, 0.0, 0.0)))
    return LEAD_RUN


def _inertial(body, mass: float, com, inertia) -> None:
    J = np.asarray(inertia, dtype=float)
    if mass <= 0:
        mass, J = TINY_MASS, np.eye(3) * TINY_MASS
    w = np.linalg.eigvalsh(J)
    if w[0] <= TINY_MASS:  # a point mass (a payload): MuJoCo needs a positive inertia
        J = J + np.eye(3) * (TINY_MASS - min(w[0], 0.0))
    ET.SubElement(body, "inertial", pos=_vec(com), mass=repr(float(mass)),
                  fullinertia=_vec((J[0, 0], J[1, 1], J[2, 2], J[0, 1], J[0, 2], J[1, 2])))


def _shape(model: RevoluteChain, b: int, body, asset) -> None:
    """Body b drawn: the hull of its outline where known, else a capsule to the next joint."""
    points = model.outline[b] if model.outline else np.zeros((0, 3))
    if len(points) >= 4 and np.linalg.matrix_rank(points - points.mean(axis=0), tol=1e-9) == 3:
        mesh = f"outline {model.bodies[b]}"
        ET.SubElement(asset, "mesh", name=mesh, vertex=" ".join(f"{v:.6g}" for v in np.asarray(points).ravel()))
        ET.SubElement(body, "geom", type="mesh", mesh=mesh, group="1")
        return
    far = model.placements[b][:3, 3] if b < model.n else model.com[b]
    if np.linalg.norm(far) > 1e-9:
        ET.SubElement(body, "geom", type="capsule", size="0.01", fromto=_vec((0, 0, 0, *far)), group="1")
