"""The exudyn helpers every route-3 model uses: the general chain
(:mod:`springlab.energy.simulation`), the pseudobase arm
(:mod:`springlab.mechanisms.pseudobase.simulation`) and the dyad
(:mod:`springlab.mechanisms.dyad.simulation`).

Facts about exudyn 1.13.6 these rely on (measured, and tested in ``tests/test_sim.py``):
a locked generic joint's ``TorqueLocal`` reads diag(-1, 1, 1) R^T M, where M is the
moment of the loads on the child side and R the joint axes (so the holding torque is
R @ :data:`LOCKED_TORQUE_SIGN` @ TorqueLocal); the same joint driven by an
``offsetUserFunction`` reads the opposite, in the frame of the driven link
(:data:`DRIVEN_TORQUE_SIGN`). Sensors are stored internally; nothing is written to disk.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.errors import SolverError
from springlab.model.rotations import frames_from_directions

__all__ = ["SimSettings", "solver_settings", "new_system", "add_body", "add_spring", "frame_with_z", "add_sensor",
           "check_constraints", "LOCKED_TORQUE_SIGN", "DRIVEN_TORQUE_SIGN"]

LOCKED_TORQUE_SIGN = np.diag([1.0, -1.0, -1.0])
"""A locked joint's holding torque is R @ LOCKED_TORQUE_SIGN @ TorqueLocal."""
DRIVEN_TORQUE_SIGN = np.diag([-1.0, 1.0, 1.0])
"""A joint driven by an offset function: the torque on the driven link, in its frame."""


@dataclass(frozen=True)
class SimSettings:
    """Solver settings.

    :ivar step: time step (s), > 0
    :ivar relative_tolerance, absolute_tolerance: Newton tolerances, > 0
    :ivar damping: damping of every spring along its line (N s/m), >= 0; light damping
        does not change the statics
    :ivar axial_inertia: axial moment of inertia as a fraction of the transverse one, > 0
    :ivar dense: solve the Newton steps' linear systems with a dense LU (exudyn's EigenDense)
        instead of the sparse one: springlab's models have at most a few hundred unknowns,
        where dense is faster (paper 001's driven ideal model 4.9 -> 3.3 s, its notebook's
        exudyn runs 17.4 -> 11.3 s CPU); the answers agree to the Newton tolerance
    """

    step: float = 1e-3
    relative_tolerance: float = 1e-12
    absolute_tolerance: float = 1e-14
    damping: float = 0.0
    axial_inertia: float = 1e-2
    dense: bool = True

    def __post_init__(self):
        for name in ("step", "relative_tolerance", "absolute_tolerance", "axial_inertia"):
            _checks.positive(name, getattr(self, name))
        _checks.positive("damping", self.damping, allow_zero=True)


def solver_settings(settings: SimSettings, end_time: float = 0.0, write_period: float = 0.01):
    """exudyn SimulationSettings from springlab's: quiet, no files written, sensors
    stored every ``write_period`` s, Newton tolerances, ``end_time`` / ``step`` steps."""
    import exudyn as exu

    ss = exu.SimulationSettings()
    ss.solution.file.write = False  # no solution/ folder in the working directory
    ss.solution.sensors.writePeriod = write_period
    ss.timeIntegration.verboseMode = 0
    ss.staticSolver.verboseMode = 0
    ss.show.statistics = False
    ss.show.computationTime = False
    for newton in (ss.timeIntegration.newton, ss.staticSolver.newton):
        newton.relativeTolerance = settings.relative_tolerance
        newton.absoluteTolerance = settings.absolute_tolerance
    if settings.dense:
        ss.linearSolver.solverType = exu.LinearSolverType.EigenDense
    if end_time:
        ss.timeIntegration.endTime = end_time
        ss.timeIntegration.numberOfSteps = max(1, int(round(end_time / settings.step)))
    return ss


def once_per_time(f):
    """``f(t)`` remembered for the last t: exudyn asks each driven joint's offset at the same time
    in turn, so a trajectory evaluated through this is evaluated once per time, not once per joint."""
    last = [None, None]

    def at(t):
        if last[0] != t:
            last[0], last[1] = t, f(t)
        return last[1]

    return at


def new_system():
    """A fresh exudyn system with its ground at the origin: (SystemContainer, mbs, ground)."""
    import exudyn as exu

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    return SC, mbs, mbs.CreateGround(referencePosition=[0.0, 0.0, 0.0])


def add_body(mbs, mass: float, inertia, position, rotation=None, *, gravity=None, **initial):
    """A rigid body: ``mass`` (kg), ``inertia`` (3, 3) about its centre of mass in its own
    frame (kg m^2), the centre at ``position`` (m) and the frame ``rotation`` (3, 3) in the
    reference configuration; ``gravity`` (3,) m/s^2 if the body carries its own weight
    (None: no gravity, e.g. a weight applied as a load). ``initial`` passes exudyn's
    initialDisplacement / initialRotationMatrix / initialVelocity through."""
    from exudyn.utilities import RigidBodyInertia

    kwargs = {"inertia": RigidBodyInertia(mass, np.asarray(inertia, dtype=float)),
              "referencePosition": list(position)}
    if rotation is not None:
        kwargs["referenceRotationMatrix"] = rotation
    kwargs.update(initial)
    if gravity is not None:
        kwargs["gravity"] = list(gravity)
    return mbs.CreateRigidBody(**kwargs)


def add_spring(mbs, body_a: int, local_a, body_b: int, local_b, *, k: float, free_length: float = 0.0,
               initial_tension: float = 0.0, damping: float = 0.0) -> int:
    """A spring-damper between a point of ``body_a`` and a point of ``body_b`` (each given in
    its body's frame, m): stiffness ``k`` (N/m), ``free_length`` (m; 0 is a zero-free-length
    spring, F = k (B - A)), ``initial_tension`` (N, a constant pull added to k (l - free_length):
    exudyn's own ``force`` of the connector, f > 0 tension), ``damping`` along its line (N s/m)."""
    from exudyn.utilities import MarkerBodyPosition, ObjectConnectorSpringDamper

    mA = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body_a, localPosition=list(local_a)))
    mB = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body_b, localPosition=list(local_b)))
    return mbs.AddObject(ObjectConnectorSpringDamper(markerNumbers=[mA, mB], referenceLength=float(free_length),
                                                     stiffness=float(k), damping=float(damping),
                                                     force=float(initial_tension)))


def frame_with_z(axis: np.ndarray) -> np.ndarray:
    """A rotation (3, 3) whose third column is the unit ``axis``."""
    return frames_from_directions(np.asarray(axis, dtype=float)[None])[0][:, [1, 2, 0]]


def add_sensor(mbs, kind: str, **kwargs):
    """An internally stored sensor of output ``kind`` ('Position', 'TorqueLocal', ...):
    on a body with ``bodyNumber=``, on an object with ``objectNumber=``."""
    import exudyn as exu

    if "bodyNumber" in kwargs:
        from exudyn.utilities import SensorBody as make
    else:
        from exudyn.utilities import SensorObject as make
    return mbs.AddSensor(make(storeInternal=True, writeToFile=False,
                              outputVariableType=getattr(exu.OutputVariableType, kind), **kwargs))


def check_constraints(mbs, what: str) -> None:
    """Raise :class:`~springlab.errors.SolverError` if the assembled system ``mbs`` has redundant constraints."""
    dof = mbs.ComputeSystemDegreeOfFreedom()
    if dof["redundantConstraints"]:
        raise SolverError(f"the {what} model has redundant constraints: {dof}")
