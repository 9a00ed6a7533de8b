"""Route 3: the multibody simulation of a springlab arm in exudyn.

The model is built from the same :class:`~springlab.model.chain.Chain` and
:class:`~springlab.model.springs.Spring` objects as the algebra: nothing is described
twice. Each moving link is a rigid body with its mass at the COM (on the joint
line, d_j from the proximal joint) and the inertia of a slender rod about the
COM (m r^2 / 12 transverse, a small axial part so the spin about the link axis
is not singular). Joints are spherical; springs are exudyn spring-dampers with
``referenceLength`` = the spring's free length (0: a true zero-free-length
spring, F = k (B - A)). Gravity acts along -x_1 (-UP). Nothing is drawn and no
file is written.

Three checks, each returning a result with the numbers:

* :func:`hold_test`: release at rest at each pose, report the largest drift,
  always beside the negative control (springs scaled by 0.9); :func:`hold_motion`
  returns the same test's motion at one pose (for an animation);
* :func:`holding_torques`: lock every joint, solve the statics, read the joint
  torques, and compare them with route 2 (:func:`springlab.energy.geometry.holding_torques`);
* :func:`follow`: drive the joints along a :class:`~springlab.model.trajectories.Sweep`
  that starts and ends at rest, recording gravity, spring and total energy and
  the joint torques.

The exudyn helpers and the measured facts they rely on (torque signs of locked and
driven joints) are in :mod:`springlab.energy.multibody`; ``SolveStatic`` converging
says nothing about balance.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.energy.geometry import energies
from springlab.energy.geometry import holding_torques as route2_holding_torques
from springlab.energy.multibody import (
    DRIVEN_TORQUE_SIGN,
    LOCKED_TORQUE_SIGN,
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
from springlab.model.chain import SPHERICAL, UP, Chain, check_attachments, check_springs
from springlab.model.revolute import RevoluteChain, body_frames, check_point_springs
from springlab.model.trajectories import Sweep
from springlab.tables import Table

JOINT_KINDS = ("spherical", "locked", "prescribed")


class Model:
    """An exudyn system built from a chain and its springs (see :func:`build_model`)."""

    def __init__(self, SC, mbs, bodies, joints, joint_axes, spring_objects, chain, springs, kind):
        self.SC, self.mbs = SC, mbs
        self.bodies, self.joints, self.spring_objects = bodies, joints, spring_objects
        self.joint_axes = joint_axes  # (3, 3) per joint: its axes in the world, reference configuration
        self.chain, self.springs, self.kind = chain, springs, kind


def _local_x(value: float) -> list[float]:
    return [float(value), 0.0, 0.0]


def build_model(chain: Chain, springs, reference_frames, *, joints: str = "spherical",
                initial_frames=None, sweep: Sweep | None = None, payload: float = 0.0,
                settings: SimSettings = SimSettings()) -> Model:
    """Build the exudyn system of an arm.

    :param reference_frames: (n, 3, 3) link frames of the reference configuration
        (the first column of each is the link direction; frame 1 is the ground's, I)
    :param joints: 'spherical' (free), 'locked' (every joint fully constrained in
        the reference configuration) or 'prescribed' (locked to follow ``sweep``;
        the reference configuration must then be the zero-angle one)
    :param initial_frames: (n, 3, 3) frames at t = 0 if not the reference ones
    :param payload: mass (kg) added at the end link's centre of mass
    """
    if joints not in JOINT_KINDS:
        raise SpringlabError(f"joints must be one of {JOINT_KINDS}, got {joints!r}")
    chain = chain.with_payload(payload)
    springs = check_springs(chain, springs)
    check_attachments(chain, springs)
    reference_frames = np.asarray(reference_frames, dtype=float)
    initial_frames = reference_frames if initial_frames is None else np.asarray(initial_frames, dtype=float)
    for name, frames in (("reference_frames", reference_frames), ("initial_frames", initial_frames)):
        if frames.shape != (chain.n, 3, 3) or not np.all(np.isfinite(frames)):
            raise SpringlabError(f"{name} must be finite with shape ({chain.n}, 3, 3), got {frames.shape}")
    ref_joints = chain.joint_positions(reference_frames[None, :, :, 0])[0]
    ref_com = chain.com_positions(reference_frames[None, :, :, 0])[0]
    init_com = chain.com_positions(initial_frames[None, :, :, 0])[0]

    SC, mbs, ground = new_system()
    bodies = [ground]
    for j in range(2, chain.n + 1):
        r, m = chain.r[j - 2], chain.m[j - 2]
        transverse = m * r**2 / 12.0
        com_ref, com_init = ref_com[j - 2], init_com[j - 2]
        bodies.append(add_body(
            mbs, m, np.diag([settings.axial_inertia * transverse, transverse, transverse]), com_ref,
            reference_frames[j - 1], gravity=-chain.g * UP,
            initialDisplacement=list(com_init - com_ref),
            initialRotationMatrix=reference_frames[j - 1].T @ initial_frames[j - 1]))  # superimposed on the reference
    if joints == "prescribed" and sweep is None:
        raise SpringlabError("joints='prescribed' needs a sweep")
    sweep_angles = once_per_time(sweep.angles) if sweep is not None else None
    joint_items, joint_axes = [], []
    for j in range(2, chain.n + 1):
        items, position = [bodies[j - 2], bodies[j - 1]], list(ref_joints[j - 2])
        axis = chain.joint(j)
        revolute = axis != SPHERICAL
        axes = reference_frames[j - 2]  # the joint's axes: link j-1's frame
        if revolute:
            axes = axes @ frame_with_z(np.asarray(axis))  # z along the revolute axis
        joint_axes.append(axes)
        if joints == "spherical":
            if revolute:
                joint_items.append(mbs.CreateRevoluteJoint(itemNumbers=items, position=position,
                                                           axis=list(axes[:, 2])))
            else:
                joint_items.append(mbs.CreateSphericalJoint(itemNumbers=items, position=position))
            continue
        offset = 0
        if joints == "prescribed":
            def offset(mbs_, t, item, values, _k=j - 2, _revolute=revolute):
                a = sweep_angles(t)[_k]  # frame 1 = frame 0 @ RotXYZ(offset)
                if _revolute:
                    return [0.0, 0.0, 0.0, 0.0, 0.0, float(a[0])]
                return [0.0, 0.0, 0.0, float(a[0]), float(a[1]), float(a[2])]

        joint_items.append(mbs.CreateGenericJoint(
            itemNumbers=items, position=position, rotationMatrixAxes=axes,
            constrainedAxes=[1] * 6, offsetUserFunction=offset))
    spring_items = []
    for s in springs:
        local_a = s.a if s.i == 1 else chain.r[s.i - 2] - chain.d[s.i - 2] + s.a  # A = J_i + a x_i
        local_b = s.b - chain.d[s.j - 2]  # B = J_{j-1} + b x_j
        spring_items.append(add_spring(mbs, bodies[s.i - 1], _local_x(local_a), bodies[s.j - 1], _local_x(local_b),
                                       k=s.k, free_length=s.free_length, initial_tension=s.initial_tension,
                                       damping=settings.damping))
    return Model(SC, mbs, bodies, joint_items, joint_axes, spring_items, chain, springs, joints)


# --- 1. hold test ------------------------------------------------------------------
@dataclass(frozen=True)
class HoldRun:
    """Drifts of one set of springs released at rest at each pose.

    tip_drift: (N,) largest distance of the end link's distal joint from its start (m);
    angle_drift: (N,) largest angle between any link's direction and its start
    direction (rad); a link's spin about its own axis (free on spherical joints,
    and irrelevant to the pose) is not counted.
    """

    springs_scale: float
    tip_drift: np.ndarray
    angle_drift: np.ndarray
    cpu_seconds: float
    simulated_seconds: float

    @property
    def max_tip_drift(self) -> float:
        return float(np.max(self.tip_drift))

    @property
    def max_angle_drift(self) -> float:
        return float(np.max(self.angle_drift))


@dataclass(frozen=True)
class HoldResult:
    balanced: HoldRun
    control: HoldRun  # springs scaled by ``control_scale``: must move

    def summary(self) -> str:
        return (f"max tip drift {self.balanced.max_tip_drift:.2e} m with the springs, "
                f"{self.control.max_tip_drift:.2e} m with them scaled by {self.control.springs_scale}")

    def table(self, balanced: str = "balanced", control: str | None = None) -> Table:
        """Largest tip drift (m) and link direction drift (rad) of the balanced run and the control."""
        control = control or f"scaled by {self.control.springs_scale:g} (control)"
        return Table(["springs", "max tip drift (m)", "max link direction drift (rad)"],
                     [(label, f"{run.max_tip_drift:.2e}", f"{run.max_angle_drift:.2e}")
                      for label, run in ((balanced, self.balanced), (control, self.control))])


CONTROL_TOLERANCES = (1e-8, 1e-10)
"""Newton tolerances (relative, absolute) of the negative control's runs at least: the control must
move by centimetres or more, read to three digits, and at the balanced run's 1e-12 it took 8 Newton
iterations a step instead of 2 (2.8 s of the 000 notebook's 3.8 s hold test; 2.2 s now). The balanced
run keeps the settings' tolerances: its drift is set by them."""


def _control_settings(settings: SimSettings) -> SimSettings:
    rel, absolute = CONTROL_TOLERANCES
    return dataclasses.replace(settings, relative_tolerance=max(settings.relative_tolerance, rel),
                               absolute_tolerance=max(settings.absolute_tolerance, absolute))


def _hold_run(chain, springs, frames, duration, settings, scale, histories=None) -> HoldRun:
    """One set of springs released at each pose; with ``histories`` (a list), each pose's
    (times (T,), link directions (T, n, 3)) is appended to it."""
    tip_local = _local_x(chain.r[-1] - chain.d[-1])
    tip_drift, angle_drift = np.zeros(len(frames)), np.zeros(len(frames))
    cpu, scaled = 0.0, [s.scaled(scale) for s in springs]
    for p in range(len(frames)):
        model = build_model(chain, scaled, frames[p], settings=settings)
        tip = add_sensor(model.mbs, "Position", bodyNumber=model.bodies[-1], localPosition=tip_local)
        rot = [add_sensor(model.mbs, "RotationMatrix", bodyNumber=b) for b in model.bodies[1:]]
        model.mbs.Assemble()
        t0 = time.process_time()
        model.mbs.SolveDynamic(solver_settings(settings, duration))
        cpu += time.process_time() - t0
        path = model.mbs.GetSensorStoredData(tip)[:, 1:]
        tip_drift[p] = np.max(np.linalg.norm(path - path[0], axis=1))
        directions = []
        for sensor in rot:  # the link's direction x_j is the first column of its rotation matrix
            x = model.mbs.GetSensorStoredData(sensor)[:, 1:].reshape(-1, 3, 3)[:, :, 0]
            angle = np.arctan2(np.linalg.norm(np.cross(x[0], x), axis=1), x @ x[0])
            angle_drift[p] = max(angle_drift[p], float(np.max(angle)))
            directions.append(x)
        if histories is not None:
            t = model.mbs.GetSensorStoredData(tip)[:, 0]
            ground = np.broadcast_to(UP, (len(t), 3))
            histories.append((t, np.stack([ground, *directions], axis=1)))
    return HoldRun(scale, tip_drift, angle_drift, cpu, duration * len(frames))


def _hold_inputs(chain, springs, poses, duration, control_scale, settings):
    """The hold test's inputs checked: (frames, duration, springs, control_scale)."""
    frames = chain.pose_frames(poses)
    duration = _checks.duration(duration)
    springs = check_springs(chain, springs)
    control_scale = _checks.positive("control_scale", control_scale, allow_zero=True)
    if control_scale == 1.0:
        raise SpringlabError("control_scale = 1 makes the negative control the design itself: use e.g. 0.9")
    _checks.instance("settings", settings, SimSettings)
    return frames, duration, springs, control_scale


@dataclass(frozen=True)
class HoldMotion:
    """The hold test at one pose, as motion: link directions (T, n, 3) at times t (s) of the
    balanced arm and of the control (springs scaled by ``control_scale``)."""

    t: np.ndarray
    balanced: np.ndarray
    control: np.ndarray
    control_scale: float

    def tip_travel(self, chain: Chain) -> tuple[float, float]:
        """The largest distance (m) the tip moves from where it was released: balanced, control."""
        def travel(X):
            tip = chain.joint_positions(X)[:, -1]
            return float(np.max(np.linalg.norm(tip - tip[0], axis=1)))
        return travel(self.balanced), travel(self.control)

    def sampled(self, frames: int) -> HoldMotion:
        """The motion at ``frames`` evenly spaced stored steps (for an animation)."""
        k = np.unique(np.linspace(0, len(self.t) - 1, frames).round().astype(int))
        return HoldMotion(self.t[k], self.balanced[k], self.control[k], self.control_scale)


def hold_motion(chain: Chain, springs, pose, duration: float = 2.0, *, control_scale: float = 0.9,
                settings: SimSettings = SimSettings()) -> HoldMotion:
    """:func:`hold_test` at one pose (link directions (n, 3), or joint angles), returning the
    motion of the balanced arm and of the control instead of their drifts."""
    frames, duration, springs, control_scale = _hold_inputs(
        chain, springs, np.asarray(pose, dtype=float)[None], duration, control_scale, settings)
    runs: list = []
    _hold_run(chain, springs, frames, duration, settings, 1.0, runs)
    _hold_run(chain, springs, frames, duration, _control_settings(settings), control_scale, runs)
    (t, balanced), (_, control) = runs
    return HoldMotion(t, balanced, control, control_scale)


def hold_test(chain: Chain, springs, poses, duration: float = 2.0, *, control_scale: float = 0.9,
              settings: SimSettings = SimSettings()) -> HoldResult:
    """Release the arm at rest at each pose and measure how far it drifts.

    A balanced arm is neutrally stable: it stays put, its drift set by the
    Newton tolerance alone. The negative control, the same springs scaled by
    ``control_scale``, always runs beside it and must move (at Newton tolerances
    no tighter than :data:`CONTROL_TOLERANCES`: it only has to show motion).

    :param poses: link directions (N, n, 3), or joint angles (N, n-1, 3) (needed
        for chains with revolute joints)
    :param duration: simulated time per pose (s)
    """
    frames, duration, springs, control_scale = _hold_inputs(chain, springs, poses, duration, control_scale, settings)
    return HoldResult(_hold_run(chain, springs, frames, duration, settings, 1.0),
                      _hold_run(chain, springs, frames, duration, _control_settings(settings), control_scale))


# --- 2. holding torques ------------------------------------------------------------
@dataclass(frozen=True)
class TorqueResult:
    """Joint torques (N m, world frame) that hold each pose, shape (N, n-1, 3):
    ``simulated`` by exudyn's statics with locked joints, ``analytic`` by route 2."""

    simulated: np.ndarray
    analytic: np.ndarray

    @property
    def max_difference(self) -> float:
        return float(np.max(np.abs(self.simulated - self.analytic)))


def holding_torques(chain: Chain, springs, poses, *, settings: SimSettings = SimSettings()) -> TorqueResult:
    """The joint torques needed to hold each pose, from a statics solve with every
    joint locked, beside route 2's analytic torques.

    :param poses: link directions (N, n, 3), or joint angles (N, n-1, 3)

    For a revolute joint the component along its axis is the actuator's share;
    the bearing carries the rest.
    """
    frames = chain.pose_frames(poses)
    springs = check_springs(chain, springs)
    _checks.instance("settings", settings, SimSettings)
    out = np.zeros((len(frames), chain.n - 1, 3))
    for p in range(len(frames)):
        model = build_model(chain, springs, frames[p], joints="locked", settings=settings)
        model.mbs.Assemble()
        out[p] = static_joint_torques(model, settings)
    return TorqueResult(out, route2_holding_torques(chain, springs, frames[..., 0]))


def static_joint_torques(model: Model, settings: SimSettings = SimSettings()) -> np.ndarray:
    """Solve the statics of an assembled model with locked joints and return the
    torque each joint applies to the links beyond it (N m, world frame), (n-1, 3)."""
    import exudyn as exu

    if model.kind != "locked":
        raise SpringlabError(f"static joint torques need a model with locked joints, not {model.kind!r}")
    model.mbs.SolveStatic(solver_settings(settings))
    out = np.zeros((len(model.joints), 3))
    for k, joint in enumerate(model.joints):
        local = np.asarray(model.mbs.GetObjectOutput(joint, exu.OutputVariableType.TorqueLocal))
        out[k] = model.joint_axes[k] @ LOCKED_TORQUE_SIGN @ local
    return out


# --- 3. following a trajectory ---------------------------------------------------
@dataclass(frozen=True)
class FollowResult:
    """Energies (J) and joint torques (N m) along a prescribed motion.

    t: (T,) s; gravity, springs, total: (T,) J from exudyn's body positions and
    spring connectors; torques: (T, n-1, 3) the torque each joint applies to the
    link it drives (link j), in that link's frame (for a revolute joint, in the
    joint's axes, z along the axis); in a slow motion they approach the holding
    torques. route2: the same energies by route 2 at the same angles.
    """

    t: np.ndarray
    gravity: np.ndarray
    springs: np.ndarray
    total: np.ndarray
    torques: np.ndarray
    route2: dict
    cpu_seconds: float


def follow(chain: Chain, springs, sweep: Sweep, *, samples: int = 301,
           settings: SimSettings = SimSettings(step=1e-2)) -> FollowResult:
    """Drive the joints along ``sweep`` (which must start and end at rest) and record
    the potential energies and the joint torques at ``samples`` times."""
    if not isinstance(sweep, Sweep):
        raise SpringlabError(f"sweep must be a springlab.model.trajectories.Sweep, got {type(sweep).__name__}")
    if sweep.initial.shape != (chain.n - 1, 3):
        raise SpringlabError(f"the sweep has {sweep.initial.shape[0]} joints, the chain {chain.n - 1}")
    samples = _checks.sample_count(samples, least=2)
    sweep.check_at_rest()
    chain.check_angles(np.stack([sweep.initial, sweep.initial + sweep.rotation]))
    springs = check_springs(chain, springs)
    upright = np.broadcast_to(np.eye(3), (chain.n, 3, 3))
    initial = chain.frames(sweep.angles(0.0)[None])[0]
    model = build_model(chain, springs, upright, joints="prescribed", initial_frames=initial,
                        sweep=sweep, settings=settings)
    com = [add_sensor(model.mbs, "Position", bodyNumber=b) for b in model.bodies[1:]]
    pot = [add_sensor(model.mbs, "PotentialEnergy", objectNumber=o) for o in model.spring_objects]
    tq = [add_sensor(model.mbs, "TorqueLocal", objectNumber=o) for o in model.joints]
    model.mbs.Assemble()
    period = sweep.duration / (samples - 1)
    steps_per_sample = max(1, int(np.ceil(period / settings.step)))
    run = dataclasses.replace(settings, step=period / steps_per_sample)
    t0 = time.process_time()
    model.mbs.SolveDynamic(solver_settings(run, sweep.duration, write_period=period))
    cpu = time.process_time() - t0
    data = [model.mbs.GetSensorStoredData(s) for s in com]
    t = data[0][:, 0]
    gravity = sum(chain.g * m * d[:, 1:] @ UP for m, d in zip(chain.m, data, strict=True))
    elastic = sum((model.mbs.GetSensorStoredData(s)[:, 1] for s in pot), np.zeros_like(t))
    torques = np.stack([model.mbs.GetSensorStoredData(s)[:, 1:] @ DRIVEN_TORQUE_SIGN for s in tq], axis=1)
    route2 = energies(chain, springs, chain.directions(sweep.angles(t)))
    return FollowResult(t, gravity, elastic, gravity + elastic, torques, route2, cpu)


# --- 4. the general model: holding torques of any revolute chain -----------------------------
def build_locked_model(model: RevoluteChain, springs, q, *, settings: SimSettings = SimSettings()):
    """The exudyn system of a :class:`~springlab.model.revolute.RevoluteChain` at one pose ``q`` (n,)
    (rad) with every joint locked: each body a rigid body with its mass and inertia at its centre of
    mass (massless bodies too: the statics needs no mass matrix), each joint a generic joint at its
    origin with z along its axis, constraining all six motions, each spring an exudyn spring-damper
    between its two points. Returns (SC, mbs, joints, axes): the joint items and their axes frames."""
    springs = check_point_springs(model, springs)
    for spring in springs:
        if spring.pulley_radius > 0:
            raise SpringlabError(f"{spring.label} runs as a cable over a pulley of radius {spring.pulley_radius:g} m, which "
                                 "exudyn's springs cannot model: check it with route 2 and MuJoCo "
                                 "(springlab.model.mjcf), or give its point-pulley equivalent (pulley_radius 0)")
    if model.belts:
        raise SpringlabError(f"the arm carries belt frames ({', '.join(b.name for b in model.belts)}), which this "
                             "exudyn model has no pulley and belt for: check it with route 2 and MuJoCo "
                             "(springlab.model.mjcf writes the belts)")
    q = model.check_q(q)
    if q.shape[0] != 1:
        raise SpringlabError(f"build_locked_model takes one pose, got {q.shape[0]}")
    R, o = (a[0] for a in body_frames(model, q))
    SC, mbs, ground = new_system()
    items = [ground]
    for b in range(1, model.n + 1):
        items.append(add_body(mbs, float(model.mass[b]), model.inertia[b], o[b] + R[b] @ model.com[b], R[b],
                              gravity=model.gravity))
    joints, frames = [], []
    for i in range(1, model.n + 1):
        axes = R[i] @ frame_with_z(model.axes[i - 1])  # z along the joint's axis
        frames.append(axes)
        joints.append(mbs.CreateGenericJoint(itemNumbers=[items[i - 1], items[i]], position=list(o[i]),
                                             rotationMatrixAxes=axes, constrainedAxes=[1] * 6))
    for s in springs:
        (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
        ends = [p - (model.com[b] if b else 0.0) for b, p in ((ia, pa), (ib, pb))]  # exudyn's body frame is at its COM
        add_spring(mbs, items[ia], ends[0], items[ib], ends[1], k=s.k,
                   free_length=s.free_length, initial_tension=s.initial_tension, damping=settings.damping)
    return SC, mbs, joints, frames


def joint_torques(model: RevoluteChain, springs, q, *, settings: SimSettings = SimSettings()) -> np.ndarray:
    """The torque (N m) each joint applies to hold each pose, (N, n), route 3: exudyn's statics of
    :func:`build_locked_model` at each pose, the locked joint's reaction about its axis. Compare with
    route 2, :func:`springlab.energy.geometry.joint_torques`.

    :param q: joint angles (N, n) or (n,) (rad)
    """
    import exudyn as exu

    _checks.instance("settings", settings, SimSettings)
    springs = check_point_springs(model, springs)
    q = model.check_q(q)
    out = np.empty(q.shape)
    for p in range(q.shape[0]):
        SC, mbs, joints, frames = build_locked_model(model, springs, q[p], settings=settings)
        mbs.Assemble()
        mbs.SolveStatic(solver_settings(settings))
        for i, joint in enumerate(joints):
            local = np.asarray(mbs.GetObjectOutput(joint, exu.OutputVariableType.TorqueLocal))
            out[p, i] = (LOCKED_TORQUE_SIGN @ local)[2]  # the holding torque's component along z = the axis
    return out
