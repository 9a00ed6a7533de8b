"""The field's reference libraries beside springlab's routes (never inside them): Pinocchio's
gravity torques on a robot's own URDF.

Pinocchio (``pin``, the ``robots`` extra) reads the file itself and locks every joint off the arm's
path at zero with ``buildReducedModel``, as :func:`springlab.model.urdf.read_revolute_chain` does;
its ``computeGeneralizedGravity`` is the torque that holds each pose, our
:func:`springlab.energy.geometry.gravity_torques`. MuJoCo (``mujoco``, the same extra) holds and
releases the MJCF :func:`springlab.model.mjcf.to_mjcf` writes, taken as written: only the arm's
joints are set.
"""

from __future__ import annotations

import re

import numpy as np

from springlab.errors import SpringlabError


def pinocchio_gravity(urdf_text: str, model, q) -> np.ndarray:
    """Pinocchio's gravity torques (N m), (N, n) in ``model``'s joint order, at joint angles ``q``
    (N, n) rad, on the URDF text the model was read from (every joint not in ``model.joints``
    locked at zero; a continuous joint's (cos, sin) set from its angle).

    :raises SpringlabError: when Pinocchio is not installed
    """
    try:
        import pinocchio as pin
    except ImportError:
        raise SpringlabError("Pinocchio is not installed: pip install pin (the 'robots' extra)") from None
    q = model.check_q(q)
    links = set(re.findall(r'<link\s+name="([^"]+)"', urdf_text))
    for name in set(re.findall(r'<joint\s+name="([^"]+)"', urdf_text)) & links:
        # a joint named as a link (SO-100's 'gripper'): buildReducedModel refuses the ambiguous frame
        urdf_text = urdf_text.replace(f'<joint name="{name}"', f'<joint name="{name} (joint)"')
    full = pin.buildModelFromXML(urdf_text)
    full.gravity.linear = np.asarray(_gravity_in_root(model, full, pin), dtype=float)
    lock = [full.getJointId(name) for name in full.names[1:] if name not in model.joints]
    reduced = pin.buildReducedModel(full, lock, pin.neutral(full)) if lock else full
    data = reduced.createData()
    joints = [reduced.joints[reduced.getJointId(name)] for name in model.joints]
    out = np.empty(q.shape)
    for p, angles in enumerate(q):
        config = _configuration(pin, reduced, joints, angles)
        tau = pin.computeGeneralizedGravity(reduced, data, config)
        out[p] = [tau[joint.idx_v] for joint in joints]
    return out


def _configuration(pin, model, joints, angles):
    """Pinocchio's configuration vector: every joint neutral but ``joints``, set to ``angles`` (rad;
    a continuous joint's (cos, sin))."""
    config = pin.neutral(model)
    for joint, value in zip(joints, angles, strict=True):
        if joint.nq == 2:
            config[joint.idx_q:joint.idx_q + 2] = np.cos(value), np.sin(value)
        else:
            config[joint.idx_q] = value
    return config


def _gravity_in_root(model, full, pin):
    """The model's gravity (given in its base's frame) in the URDF root's frame, where Pinocchio
    takes it: the base's placement at the zero configuration."""
    base = model.bodies[0]
    if not full.existFrame(base, pin.FrameType.BODY):
        return model.gravity
    data = full.createData()
    pin.framesForwardKinematics(full, data, pin.neutral(full))
    rotation = data.oMf[full.getFrameId(base, pin.FrameType.BODY)].rotation
    return rotation @ model.gravity


def pinocchio_outline_boxes(urdf_path, model, q, package_dirs=()) -> np.ndarray:
    """Each body's collision geometry placed by Pinocchio (its own URDF reader, meshes read by
    assimp) at joint angles ``q`` (N, n) rad: the axis-aligned box that bounds it in ``model``'s base
    frame, (N, n + 1, 2, 3) m (lower, upper corner); NaN for a body with no geometry. A mesh's box
    is its vertices'; a box's, its corners'; a sphere's and a cylinder's, exact.

    :raises SpringlabError: when Pinocchio is not installed
    """
    try:
        import pinocchio as pin
    except ImportError:
        raise SpringlabError("Pinocchio is not installed: pip install pin (the 'robots' extra)") from None
    q = model.check_q(q)
    full = pin.buildModelFromUrdf(str(urdf_path))
    dirs = [str(d) for d in package_dirs]
    geometry = pin.buildGeomFromUrdf(full, str(urdf_path), pin.GeometryType.COLLISION, package_dirs=dirs)
    data, gdata = full.createData(), pin.GeometryData(geometry)
    joints = [full.joints[full.getJointId(name)] for name in model.joints]
    frames = set(model.frame_names)
    out = np.full((q.shape[0], model.n + 1, 2, 3), np.nan)
    for p, angles in enumerate(q):
        config = _configuration(pin, full, joints, angles)
        pin.framesForwardKinematics(full, data, config)
        pin.updateGeometryPlacements(full, data, geometry, gdata, config)
        base = data.oMf[full.getFrameId(model.bodies[0], pin.FrameType.BODY)]
        for index, obj in enumerate(geometry.geometryObjects):
            link = full.frames[obj.parentFrame].name
            if link not in frames:
                continue
            body = model.locate(link, np.zeros(3))[0]
            placed = base.actInv(gdata.oMg[index])
            lo, hi = _placed_box(obj.geometry, placed.rotation, placed.translation)
            box = out[p, body]
            box[0] = np.fmin(box[0], lo)
            box[1] = np.fmax(box[1], hi)
    return out


def _placed_box(shape, R, t):
    kind = type(shape).__name__
    if hasattr(shape, "vertices"):
        v = np.asarray(shape.vertices()) @ R.T + t
        return v.min(axis=0), v.max(axis=0)
    if kind == "Box":
        h = np.asarray(shape.halfSide)
        e = np.abs(R) @ h
    elif kind == "Sphere":
        e = np.full(3, shape.radius)
    elif kind in ("Cylinder", "Capsule"):
        a = R[:, 2]  # the shape's axis
        e = np.abs(a) * shape.halfLength + shape.radius * np.sqrt(np.clip(1 - a**2, 0, 1))
        if kind == "Capsule":
            e = np.abs(a) * shape.halfLength + shape.radius
    else:
        raise SpringlabError(f"a collision shape of kind {kind} has no box here")
    return t - e, t + e


def _mujoco():
    try:
        import mujoco
    except ImportError:
        raise SpringlabError("MuJoCo is not installed: pip install mujoco (the 'robots' extra)") from None
    return mujoco


def mujoco_holding_torques(mjcf: str, model, q) -> np.ndarray:
    """MuJoCo's holding torques (N m), (N, n), of an arm written by :func:`springlab.model.mjcf.to_mjcf`
    at joint angles ``q`` (N, n) rad, at rest: ``qfrc_bias - qfrc_passive`` after ``mj_forward`` (gravity
    less the tendons' spring forces), route 2's :func:`springlab.energy.geometry.joint_torques`. The file
    is taken as written: only the arm's joints are set (its cables' pulleys need no turning); a belt's
    pulley (:meth:`~springlab.model.revolute.RevoluteChain.with_belt`) is set where its belt holds it, and
    the torque on its hinge, which the belt carries, is passed to the joints between, as the file's
    equality constraint does (virtual work: the hinge turns by minus their signed sum). A pseudobase's slides
    are set where its modules hold it, and the force they take, which MuJoCo hands to the level body, is
    moved to the joint's parent at the pseudobase's point, where the file's 'connect' (and the modules) put
    it; its moment stays with the level body, as the modules carry it.

    :raises SpringlabError: when MuJoCo is not installed, or the MJCF is not ``model``'s arm
    """
    from springlab.model.revolute import body_frames

    mujoco = _mujoco()
    q = model.check_q(q)
    mj = mujoco.MjModel.from_xml_string(mjcf)
    data = mujoco.MjData(mj)
    arm = [_joint(mujoco, mj, name) for name in model.joints]
    belts = [(_joint(mujoco, mj, f"{b.name} hinge"), *model.belt_turns(b), b) for b in model.belts if b.kind == "belt"]
    bases = [(j, b, [_joint(mujoco, mj, f"{b.name} slide {t}") for t in "xyz"]) for j, b in enumerate(model.belts)
             if b.kind != "belt"]  # paper 001's pseudobases
    if mj.nq != len(arm) + len(belts) + 3 * len(bases):
        raise SpringlabError(f"the MJCF has {mj.nq} joint coordinates, the model {model.n}, {len(belts)} belts and "
                             f"{len(bases)} pseudobases: not the same arm")
    qpos = [int(mj.jnt_qposadr[j]) for j in arm]
    dof = [int(mj.jnt_dofadr[j]) for j in arm]
    R, o = body_frames(model, q)
    R0, o0 = body_frames(model, np.zeros(model.n))
    out = np.empty(q.shape)
    for p, angles in enumerate(q):
        data.qpos[:] = mj.qpos0
        data.qpos[qpos] = angles
        for hinge, _, signs, belt in belts:  # each belt's pulley where its belt holds it
            data.qpos[mj.jnt_qposadr[hinge]] = -float(signs @ angles[belt.level:belt.joint])
        for j, b, slides in bases:  # each pseudobase where its modules hold it: at its point C, level
            at = R[p, b.level].T @ (o[p, model.n + 1 + j] - o[p, b.level]) - R0[0, b.level].T @ (
                o0[0, model.n + 1 + j] - o0[0, b.level])
            data.qpos[[mj.jnt_qposadr[s] for s in slides]] = at
        data.qvel[:] = 0.0
        mujoco.mj_forward(mj, data)
        held = data.qfrc_bias - data.qfrc_passive
        tau = held[dof].copy()
        for hinge, _, signs, belt in belts:  # the belt carries its pulley's torque to the joints between
            tau[belt.level:belt.joint] -= signs * held[mj.jnt_dofadr[hinge]]
        for j, b, slides in bases:  # the slides take the pseudobase's force to the level body; the modules take
            force = R[p, b.level] @ held[[mj.jnt_dofadr[s] for s in slides]]  # it to the joint's parent at C
            C = o[p, model.n + 1 + j]
            tau += (_point_jacobian(mujoco, mj, data, C, model.bodies[b.joint], dof)
                    - _point_jacobian(mujoco, mj, data, C, model.bodies[b.level], dof)).T @ force
        out[p] = tau
    return out


def _point_jacobian(mujoco, mj, data, point, body: str, dof) -> np.ndarray:
    """d point / d q (3, len(dof)) for a point (world, m) fixed in ``body``, over the arm's dofs ``dof``."""
    jacp = np.zeros((3, mj.nv))
    index = mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_BODY, body)
    mujoco.mj_jac(mj, data, jacp, None, np.asarray(point, dtype=float), index)
    return jacp[:, dof]


def _joint(mujoco, mj, name: str) -> int:
    index = mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_JOINT, name)
    if index < 0:
        raise SpringlabError(f"the MJCF has no joint {name!r}: not the arm it was given with")
    return index


def mujoco_release(mjcf: str, q0, seconds: float, *, every: int = 10) -> tuple[np.ndarray, np.ndarray]:
    """Release the arm at rest at joint angles ``q0`` (n,) rad in MuJoCo and let it move for
    ``seconds`` (s, the model's own time step and integrator): the times (s) and joint angles
    (rad), every ``every``-th step, (T,) and (T, n).

    :raises SpringlabError: when MuJoCo is not installed
    """
    mujoco = _mujoco()
    mj = mujoco.MjModel.from_xml_string(mjcf)
    data = mujoco.MjData(mj)
    data.qpos[:] = np.asarray(q0, dtype=float)
    data.qvel[:] = 0.0
    steps = int(round(seconds / mj.opt.timestep))
    times, angles = [0.0], [data.qpos.copy()]
    for step in range(1, steps + 1):
        mujoco.mj_step(mj, data)
        if step % every == 0 or step == steps:
            times.append(float(data.time))
            angles.append(data.qpos.copy())
    return np.array(times), np.array(angles)
