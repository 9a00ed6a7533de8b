"""Route 3 for paper 002: the compensator driven slowly in exudyn; the drive's torque
is the static unbalanced moment.

References
----------
Zhang, Y., Arakelian, V. (2023). Design and Synthesis of the Gravity Compensator with a
Non-zero Length Spring (no DOI printed in the text).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.energy.multibody import (
    SimSettings,
    add_body,
    add_sensor,
    add_spring,
    check_constraints,
    new_system,
    solver_settings,
)
from springlab.mechanisms.dyad.model import Compensator, Dyad, closing, slider_height
from springlab.model.rotations import rot_z
from springlab.model.trajectories import quintic


@dataclass(frozen=True)
class Drive:
    """A slow drive of the compensator simulated in exudyn: link angle phi (rad) and the
    input torque (N m) the drive applies to the link, positive towards larger phi,
    at each stored time t (s)."""

    t: np.ndarray
    phi: np.ndarray
    torque: np.ndarray
    cpu_seconds: float


def follow(comp: Compensator, dyad: Dyad, phi_start: float, phi_end: float, *,
           duration: float = 10.0, samples: int = 121, step: float = 1e-2) -> Drive:
    """Drive the link from ``phi_start`` to ``phi_end`` (rad), rest to rest (quintic law),
    in an exudyn model: link 2 on a revolute joint at O, rod 3 jointed to it at A and
    to slider 4 at B, the slider on a vertical prismatic joint through O, the spring
    (k, l0) from O to the slider, the link's weight G at its COM. The bodies carry
    only token masses (1 g) and the weight is a force, so inertia adds nothing
    measurable: the drive's torque is the static one, -M_ub (= dP/dphi). Planar, in the x-y
    plane with y up; phi turns the link from +y towards +x.
    """
    import time as _time

    from exudyn.utilities import LoadForceVector, MarkerBodyPosition

    duration = _checks.duration(duration)
    samples = _checks.sample_count(samples, least=2)
    phi_start, phi_end = _checks.finite("phi_start", phi_start, "rad"), _checks.finite("phi_end", phi_end, "rad")
    step = _checks.at_most("step", step, duration / 2, "s", why=" (half the duration)")
    span = float(phi_end - phi_start)
    closing(dyad, np.linspace(phi_start, phi_end, 64))  # raises if the dyad cannot close

    def along(angle, length):  # a point at distance length, angle from +y towards +x
        return np.array([length * np.sin(angle), length * np.cos(angle), 0.0])

    S0, A0 = along(phi_start, comp.s), along(phi_start - dyad.beta, dyad.r)
    B0 = np.array([0.0, float(slider_height(dyad, phi_start)), 0.0])
    R_link = rot_z(-phi_start)
    token = (1e-3, np.diag([1e-6, 1e-6, 1e-6]))  # 1 g: the weight is a load, inertia adds nothing

    SC, mbs, ground = new_system()
    link = add_body(mbs, *token, S0, R_link)
    rod = add_body(mbs, *token, (A0 + B0) / 2)
    slider = add_body(mbs, *token, B0)

    def offset(mbs_, t, item, values):  # the link turns by -(phi - phi_start) about z
        return [0.0, 0.0, 0.0, 0.0, 0.0, -span * float(quintic(t / duration))]

    drive = mbs.CreateGenericJoint(itemNumbers=[ground, link], position=[0.0, 0.0, 0.0],
                                   constrainedAxes=[1] * 6, offsetUserFunction=offset)
    mbs.CreateRevoluteJoint(itemNumbers=[link, rod], position=list(A0), axis=[0.0, 0.0, 1.0])
    mbs.CreateGenericJoint(itemNumbers=[rod, slider], position=list(B0), constrainedAxes=[1, 1, 0, 0, 0, 0])
    mbs.CreateGenericJoint(itemNumbers=[ground, slider], position=list(B0), constrainedAxes=[1, 0, 1, 1, 1, 1])
    weight_at = mbs.AddMarker(MarkerBodyPosition(bodyNumber=link, localPosition=[0.0, 0.0, 0.0]))
    mbs.AddLoad(LoadForceVector(markerNumber=weight_at, loadVector=[0.0, -comp.G, 0.0]))
    add_spring(mbs, ground, [0.0, 0.0, 0.0], slider, [0.0, 0.0, 0.0], k=comp.k, free_length=comp.l0)
    sensor = add_sensor(mbs, "TorqueLocal", objectNumber=drive)
    mbs.Assemble()
    check_constraints(mbs, "dyad")

    steps = max(samples - 1, int(round(duration / step)))
    ss = solver_settings(SimSettings(step=duration / steps, relative_tolerance=1e-12, absolute_tolerance=1e-12),
                         duration, write_period=duration / (samples - 1))
    t0 = _time.process_time()
    mbs.SolveDynamic(ss)
    cpu = _time.process_time() - t0
    data = mbs.GetSensorStoredData(sensor)
    t = data[:, 0]
    phi = phi_start + span * quintic(t / duration)
    # a joint driven by an offset function holds with diag(-1, 1, 1) @ TorqueLocal (measured, see
    # springlab.energy.simulation); z turns the link by -phi, so the drive's torque towards larger phi is -TorqueLocal_z
    return Drive(t, phi, -data[:, 3], cpu)
