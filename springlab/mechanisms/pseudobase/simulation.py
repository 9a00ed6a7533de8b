"""Route 3 for paper 001: the arm, its auxiliary links, pseudobases and springs in exudyn.

Two models of the pseudobases, built from the same :class:`~springlab.mechanisms.pseudobase.model.PseudobaseArm`:

* ``'rssr'``, the mechanism of 001 Section 4: auxiliary link î turns on a free
  revolute joint about an axis parallel to joint i through Ô_{i-1} (on auxiliary
  link i-1, or on link 1 when joint 1 is vertical), and pseudobase i is a coupler
  with spherical joints at C_i (on link i) and D_i (on auxiliary link î). Nothing
  holds a pseudobase vertical but the closed loops. Its spin about C_i D_i is the
  idle DOF of 001 Eq. (19);
* ``'ideal'``: what the loops are meant to achieve. Each pseudobase's rotation is
  locked to the ground (a generic joint constraining rotations only), with a
  spherical joint at C_i; each auxiliary link's rotation is locked to its primary
  link, with a spherical joint at D_i. It cannot fold (see
  :func:`springlab.mechanisms.pseudobase.model.fold_margin`), so it can follow paths the RSSR
  loops cannot.

Every body is its mass at its COM with an isotropic radius of gyration (the
paper gives no inertia tensors); a pseudobase is a rod C_i D_i. A body the paper
gives no mass (link 1) gets ``placeholder_mass``: it turns about a vertical axis
with its COM on it, so it changes no energy and no holding torque of joints 2..n.
Gravity acts along -up; springs are exudyn spring-dampers with reference length 0.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.energy.multibody import (
    SimSettings,
    add_body,
    add_sensor,
    add_spring,
    frame_with_z,
    new_system,
    once_per_time,
    solver_settings,
)
from springlab.errors import SpringlabError
from springlab.mechanisms.pseudobase.geometry import energies, positions
from springlab.mechanisms.pseudobase.model import PseudobaseArm
from springlab.tables import Table

MODELS = ("rssr", "ideal")
_SETTINGS = SimSettings()
_DRIVEN_Z_SIGN = 1.0  # a driven generic joint's TorqueLocal z = the torque on the driven link (energy/multibody.py)
_LOCKED_Z_SIGN = 1.0  # a locked generic joint's TorqueLocal z = the holding torque dV/dq (measured)


@dataclass(frozen=True)
class Inertias:
    """Inertia model: ``gyration`` (m), radius of gyration of links and auxiliary links;
    ``placeholder_mass`` (kg) for bodies given no mass; pseudobase axial inertia as a
    fraction of its transverse one (non-zero: its spin must not be singular)."""

    gyration: float = 0.05
    placeholder_mass: float = 1.0
    axial_fraction: float = 1e-2

    def __post_init__(self):
        object.__setattr__(self, "gyration", _checks.positive("gyration", self.gyration, unit="m"))
        object.__setattr__(self, "placeholder_mass", _checks.positive("placeholder_mass", self.placeholder_mass,
                                                                      unit="kg"))
        object.__setattr__(self, "axial_fraction", _checks.positive("axial_fraction", self.axial_fraction))


class PseudobaseModel:
    def __init__(self, SC, mbs, kind, arm, springs, links, aux, stars, drives, spring_items):
        self.SC, self.mbs, self.kind, self.arm, self.springs = SC, mbs, kind, arm, springs
        self.links, self.aux, self.stars = links, aux, stars  # body numbers
        self.drives, self.spring_items = drives, spring_items  # joint objects, spring objects


def build_model(arm: PseudobaseArm, springs, q0, *, model: str = "rssr", joints: str = "driven",
                trajectory=None, spring_scale: float = 1.0, inertias: Inertias = Inertias(),
                settings: SimSettings = _SETTINGS) -> PseudobaseModel:
    """The exudyn system at the reference pose q0 (rad, (n,)).

    :param model: 'rssr' or 'ideal' (module docstring)
    :param joints: 'driven' (each primary joint follows ``trajectory``, a callable
        t -> (n,) angles with trajectory(0) = q0) or 'locked'
    :param spring_scale: multiplies every stiffness (0 removes the springs)
    """
    if model not in MODELS:
        raise SpringlabError(f"model must be one of {MODELS}, got {model!r}")
    if joints not in ("driven", "locked"):
        raise SpringlabError(f"joints must be 'driven' or 'locked', got {joints!r}")
    if joints == "driven" and trajectory is None:
        raise SpringlabError("joints='driven' needs a trajectory (a callable t -> joint angles)")
    if not (np.isfinite(spring_scale) and spring_scale >= 0):
        raise SpringlabError(f"spring_scale must be >= 0, got {spring_scale}")
    q0 = arm.dh.check_angles(q0)
    R, org = (x[0] for x in arm.dh.frames(q0))
    p = {k: v[0] for k, v in positions(arm, springs, q0).items()}
    if joints == "driven" and not np.allclose(np.asarray(trajectory(0.0), dtype=float), q0[0], atol=1e-12):
        raise SpringlabError("the trajectory must start at the reference pose q0")
    up, g = arm.up, arm.g
    star_frame = frame_with_z(up)  # a pseudobase's frame: z along C_i D_i (vertical)

    SC, mbs, ground = new_system()

    def body(mass, J, com, rot):
        return add_body(mbs, mass, J, com, rot, gravity=-g * up)

    rho2 = inertias.gyration**2
    links, com = [ground], {}
    for i in range(1, arm.n + 1):
        mass = arm.m[i - 1] if arm.m[i - 1] > 0 else inertias.placeholder_mass
        links.append(body(mass, mass * max(rho2, 1e-6) * np.eye(3), p["com"][i - 1], R[i]))
        com[links[-1]] = p["com"][i - 1]
    aux, stars = {}, {}
    for col, i in enumerate(arm.modules):
        mass = arm.m_hat[i - 1]
        aux[i] = body(mass, mass * max(rho2, 1e-6) * np.eye(3), p["aux_com"][col], R[i])
        com[aux[i]] = p["aux_com"][col]
        ms = arm.m_star[i - 1]
        transverse = ms * arm.h**2 / 12
        stars[i] = body(ms, np.diag([transverse, transverse, inertias.axial_fraction * transverse]),
                        p["star_com"][col], star_frame)
        com[stars[i]] = p["star_com"][col]

    def local(b, world_point, rot):  # a point given in the world, in body b's frame
        return rot.T @ (world_point - com[b])

    angle_offsets = once_per_time(lambda t: np.asarray(trajectory(t), dtype=float) - q0[0])
    drives = []
    for i in range(1, arm.n + 1):
        offset = 0
        if joints == "driven":
            def offset(mbs_, t, item, values, _k=i - 1):
                return [0.0, 0.0, 0.0, 0.0, 0.0, float(angle_offsets(t)[_k])]
        drives.append(mbs.CreateGenericJoint(itemNumbers=[links[i - 1], links[i]], position=list(org[i - 1]),
                                             rotationMatrixAxes=R[i - 1], constrainedAxes=[1] * 6,
                                             offsetUserFunction=offset))
    for col, i in enumerate(arm.modules):
        C, D = p["C"][col], p["D"][col]
        mbs.CreateSphericalJoint(itemNumbers=[links[i], stars[i]], position=list(C))
        mbs.CreateSphericalJoint(itemNumbers=[aux[i], stars[i]], position=list(D))
        if model == "rssr":
            # Ô_{i-1} is on auxiliary link i-1; on link 1 when the modules start at link 2
            # (joint 1 vertical); on the ground for module 1
            parent = ground if i == 1 else aux.get(i - 1, links[i - 1])
            mbs.CreateRevoluteJoint(itemNumbers=[parent, aux[i]], position=list(org[i - 1] + arm.aux_offset),
                                    axis=list(R[i - 1][:, 2]))
        else:
            mbs.CreateGenericJoint(itemNumbers=[ground, stars[i]], position=list(C),
                                   rotationMatrixAxes=star_frame, constrainedAxes=[0, 0, 0, 1, 1, 1])
            mbs.CreateGenericJoint(itemNumbers=[links[i], aux[i]], position=list(D),
                                   rotationMatrixAxes=R[i], constrainedAxes=[0, 0, 0, 1, 1, 1])
    spring_items = []
    for col, sp in enumerate(springs):
        i = sp.link
        spring_items.append(add_spring(mbs, stars[i], local(stars[i], p["A"][col], star_frame),
                                       links[i], local(links[i], p["B"][col], R[i]),
                                       k=sp.K * spring_scale, damping=settings.damping))
    return PseudobaseModel(SC, mbs, model, arm, springs, links, aux, stars, drives, spring_items)


@dataclass(frozen=True)
class FollowRun:
    """One driven run. t (T,) s; gravity, springs, total (T,) J from exudyn's body
    positions and spring connectors (heights from O_0); tilt (T, k) rad, each
    pseudobase's axis from vertical; torques (T, n) N m, each actuator's torque
    about its joint axis; route2: route 2's energies at the same angles."""

    model: str
    spring_scale: float
    t: np.ndarray
    q: np.ndarray
    gravity: np.ndarray
    springs: np.ndarray
    total: np.ndarray
    tilt: np.ndarray
    torques: np.ndarray
    route2: dict
    cpu_seconds: float

    @property
    def gravity_range(self) -> float:
        return float(np.ptp(self.gravity))

    @property
    def total_variation(self) -> float:
        return float(np.ptp(self.total))


def follow(arm: PseudobaseArm, springs, trajectory, duration: float, *, model: str = "rssr",
           spring_scale: float = 1.0, samples: int = 201, step: float = 2e-3,
           inertias: Inertias = Inertias(), settings: SimSettings = _SETTINGS) -> FollowRun:
    """Drive the primary joints along ``trajectory`` (t -> (n,) rad) for ``duration`` s
    and record energies, pseudobase tilts and actuator torques at ``samples`` times."""
    duration = _checks.duration(duration)
    samples = _checks.sample_count(samples, least=2)
    q0 = np.asarray(trajectory(0.0), dtype=float)
    m = build_model(arm, springs, q0, model=model, joints="driven", trajectory=trajectory,
                    spring_scale=spring_scale, inertias=inertias, settings=settings)
    bodies = [(b, mass) for b, mass in zip(m.links[1:], arm.m, strict=True)]
    bodies += [(m.aux[i], arm.m_hat[i - 1]) for i in arm.modules] + [(m.stars[i], arm.m_star[i - 1]) for i in arm.modules]
    pos = [add_sensor(m.mbs, "Position", bodyNumber=b) for b, _ in bodies]
    rot = [add_sensor(m.mbs, "RotationMatrix", bodyNumber=m.stars[i]) for i in arm.modules]
    pot = [add_sensor(m.mbs, "PotentialEnergy", objectNumber=o) for o in m.spring_items]
    tq = [add_sensor(m.mbs, "TorqueLocal", objectNumber=o) for o in m.drives]
    m.mbs.Assemble()
    period = duration / (samples - 1)
    per = max(1, int(np.ceil(period / step)))
    run = dataclasses.replace(settings, step=period / per)
    t0 = time.process_time()
    m.mbs.SolveDynamic(solver_settings(run, duration, write_period=period))
    cpu = time.process_time() - t0
    data = [m.mbs.GetSensorStoredData(s) for s in pos]
    t = data[0][:, 0]
    gravity = sum(arm.g * mass * (d[:, 1:] @ arm.up) for (_, mass), d in zip(bodies, data, strict=True))
    spring_energy = sum((m.mbs.GetSensorStoredData(s)[:, 1] for s in pot), np.zeros_like(t))
    tilt = []
    for s in rot:
        Rm = m.mbs.GetSensorStoredData(s)[:, 1:].reshape(-1, 3, 3)
        axis = Rm[:, :, 2]  # the pseudobase's z, vertical in the reference
        tilt.append(np.arctan2(np.linalg.norm(np.cross(axis, arm.up), axis=1), axis @ arm.up))
    torques = np.stack([_DRIVEN_Z_SIGN * m.mbs.GetSensorStoredData(s)[:, 3] for s in tq], axis=1)
    q = np.array([trajectory(x) for x in t])
    return FollowRun(model, spring_scale, t, q, gravity, spring_energy, gravity + spring_energy, np.stack(tilt, axis=1),
                     torques, energies(arm, [sp.scaled(spring_scale) for sp in springs], q), cpu)


def holding_torques(arm: PseudobaseArm, springs, poses, *, model: str = "ideal", spring_scale: float = 1.0,
                    hold: float = 0.01, inertias: Inertias = Inertias(),
                    settings: SimSettings = _SETTINGS) -> np.ndarray:
    """The actuator torques (N m) that hold each pose, (N, n): every primary joint
    locked, the model released at rest for ``hold`` s (the only free motions are the
    idle spins, which no load drives), then the joints' reaction torques read."""
    import exudyn as exu

    poses = arm.dh.check_angles(poses)
    out = np.zeros(poses.shape)
    for k, q in enumerate(poses):
        m = build_model(arm, springs, q, model=model, joints="locked", spring_scale=spring_scale,
                        inertias=inertias, settings=settings)
        m.mbs.Assemble()
        m.mbs.SolveDynamic(solver_settings(settings, hold))
        out[k] = [_LOCKED_Z_SIGN * m.mbs.GetObjectOutput(j, exu.OutputVariableType.TorqueLocal)[2] for j in m.drives]
    return out


def runs_table(runs, gravity_range: float):
    """Runs of :func:`follow`, ``runs`` = [(run, label)], as a table: the total energy's variation (J, and
    of ``gravity_range``), the largest pseudobase tilt (rad), exudyn's gravity and spring energies against
    route 2's (J) and the CPU time (s)."""
    return Table(["run", "total energy varies (J)", "of the gravity range", "largest pseudobase tilt (rad)",
                  "exudyn - route 2, gravity (J)", "exudyn - route 2, springs (J)", "CPU (s)"],
                 [(label, f"{run.total_variation:.1e}", f"{run.total_variation / gravity_range:.1e}",
                   f"{run.tilt.max():.1e}", f"{np.max(np.abs(run.gravity - run.route2['gravity'])):.1e}",
                   f"{np.max(np.abs(run.springs - run.route2['springs'])):.1e}", f"{run.cpu_seconds:.1f}")
                  for run, label in runs])
