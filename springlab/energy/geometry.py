"""Route 2: potential energies from direct geometry.

Every body and spring end is placed in space for each pose, then the energies
are summed as ``m g h`` (h = height of the COM above the base joint, along
x_1 = UP) and ``k (l - l0)**2 / 2`` (l = distance between the spring's ends, l0 the
spring's effective free length L_0 - F_i / k: a real extension spring's initial tension F_i
shifts its energy only by a constant along its working range l >= L_0).
Nothing here uses the quadratic form of :mod:`springlab.energy.quadratic`; the two
routes agreeing is a check.

All energies in J; poses ``X`` of shape (N, n, 3) as in :mod:`springlab.model.chain`.
Large batches are processed in chunks, so memory stays bounded.
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab.errors import GeometryError, SpringlabError
from springlab.model.chain import UP, Chain, check_springs
from springlab.model.revolute import (
    RevoluteChain,
    body_frames,
    centres_of_mass,
    check_point_springs,
    joint_axes,
    remembered,
    world_points,
)
from springlab.model.springs import Spring

DEFAULT_CHUNK = 8192


def attachment_points(chain: Chain, spring: Spring, X) -> tuple[np.ndarray, np.ndarray]:
    """World positions (m) of a spring's ends A (on link i) and B (on link j).

    A = J_i + a x_i and B = J_{j-1} + b x_j, with J_1 the base joint
    (see :mod:`springlab.model.springs`). Returns two arrays of shape (N, 3).
    """
    (spring,) = check_springs(chain, [spring])
    X = chain.check_directions(X)
    joints = chain.joint_positions(X)
    A = joints[:, spring.i - 1] + spring.a * X[:, spring.i - 1]
    B = joints[:, spring.j - 2] + spring.b * X[:, spring.j - 1]
    return A, B


def spring_length(chain: Chain, spring: Spring, X) -> np.ndarray:
    """|B - A| (m), the distance between a spring's ends at each pose, ndarray(N,)."""
    A, B = attachment_points(chain, spring, X)
    return np.linalg.norm(B - A, axis=1)


def _energy_chunk(chain: Chain, springs, xt: np.ndarray, out: np.ndarray,
                  gravity: bool, elastic: bool) -> None:
    """Energies of one component-major chunk ``xt`` (n, 3, m) into ``out`` (m,).

    Joints: J_1 = 0, J_j = J_{j-1} + r_j x_j. COM of link j: J_{j-1} + d_j x_j,
    its height the first coordinate (x_1 = UP). Spring ends: A = J_i + a x_i,
    B = J_{j-1} + b x_j.
    """
    n, _, m = xt.shape
    joints = np.empty((n, 3, m))  # joints[j - 1] = J_j
    joints[0] = 0.0
    for j in range(2, n + 1):
        np.multiply(xt[j - 1], chain.r[j - 2], out=joints[j - 1])
        joints[j - 1] += joints[j - 2]
    out.fill(0.0)
    tmp = np.empty(m)
    if gravity:
        for j in range(2, n + 1):  # m_j g h_j, h_j = (J_{j-1} + d_j x_j) . UP
            np.multiply(xt[j - 1, 0], chain.d[j - 2], out=tmp)
            tmp += joints[j - 2, 0]
            tmp *= chain.m[j - 2] * chain.g
            out += tmp
    if elastic:
        diff = np.empty((3, m))
        part = np.empty((3, m))
        for s in springs:
            np.subtract(joints[s.j - 2], joints[s.i - 1], out=diff)  # J_{j-1} - J_i
            np.multiply(xt[s.j - 1], s.b, out=part)
            diff += part
            np.multiply(xt[s.i - 1], s.a, out=part)
            diff -= part  # B - A
            np.multiply(diff, diff, out=diff)
            np.sum(diff, axis=0, out=tmp)  # l^2
            l0 = s.effective_free_length
            if l0:
                np.sqrt(tmp, out=tmp)
                tmp -= l0
                tmp *= tmp
            tmp *= 0.5 * s.k
            out += tmp


def _evaluate(chain, springs, X, chunk, gravity: bool, elastic: bool) -> np.ndarray:
    springs = check_springs(chain, springs)
    X = chain.as_poses(X)
    out = np.empty(X.shape[0])
    for start, stop, xt in chain.component_major_chunks(X, chunk):
        _energy_chunk(chain, springs, xt, out[start:stop], gravity, elastic)
    return out


def gravity_energy(chain: Chain, X, *, chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Gravity energy sum_j m_j g h_j (J) at each pose, ndarray(N,).

    The zero is the horizontal plane through the base joint (000 Section 2.2).
    """
    return _evaluate(chain, (), X, chunk, gravity=True, elastic=False)


def spring_energy(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Elastic energy sum_S k (l - l0)^2 / 2 (J) at each pose, ndarray(N,)."""
    return _evaluate(chain, springs, X, chunk, gravity=False, elastic=True)


def total_energy(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> np.ndarray:
    """Gravity plus elastic energy (J) at each pose, ndarray(N,)."""
    return _evaluate(chain, springs, X, chunk, gravity=True, elastic=True)


def energies(chain: Chain, springs, X, *, chunk: int = DEFAULT_CHUNK) -> dict[str, np.ndarray]:
    """Gravity, spring and total energy (J) at each pose, route 2: {'gravity', 'springs',
    'total'}, each ndarray(N,). The same name and shape as every route's ``energies``."""
    gravity = gravity_energy(chain, X, chunk=chunk)
    elastic = spring_energy(chain, springs, X, chunk=chunk)
    return {"gravity": gravity, "springs": elastic, "total": gravity + elastic}


def com_offset_energy(chain: Chain, offsets, poses) -> np.ndarray:
    """Gravity energy (J) at each pose of centres of mass off the link lines, beyond what
    :func:`gravity_energy` counts: sum_j m_j g (R_j delta_j) . UP, ndarray(N,).

    :param offsets: per moving link, the COM's offset from its line in the link's frame (m), (n-1, 3)
    :param poses: joint angles (N, n-1, 3) or, for an all-spherical chain, directions (N, n, 3)
        (then each link's spin about its own axis is :func:`~springlab.model.rotations.frames_from_directions`' choice)
    """
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    delta = _checks.real_array("offsets", offsets, shape=(chain.n - 1, 3))
    R = chain.pose_frames(poses)
    return chain.g * np.einsum("j,nji,ji->n", np.asarray(chain.m), R[:, 1:, 0, :], delta)  # UP . R d = R[0, :] . d


def rotation_order_spread(chain: Chain, springs, angles) -> dict[str, float]:
    """How much each energy depends on the order of a joint's three turns: the largest
    |E_order - E_xyz| (J) over the six orders (:data:`springlab.model.rotations.ORDERS`) and
    the poses, for 'gravity', 'springs' and 'total'. ``angles`` (N, n-1, 3) in rad,
    spherical joints."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    angles = chain.check_angles(angles)
    from springlab.model.rotations import ORDERS, directions_in_order

    ref = energies(chain, springs, directions_in_order(angles, "xyz"))
    out = dict.fromkeys(ref, 0.0)
    for order in ORDERS[1:]:
        e = energies(chain, springs, directions_in_order(angles, order))
        for key in out:
            out[key] = max(out[key], float(np.max(np.abs(e[key] - ref[key]))))
    return out


def holding_torques(chain: Chain, springs, X, *, out=None) -> np.ndarray:
    """Joint torques (N m) that hold each pose against gravity and the springs.

    For the joint between links j-1 and j (at J_{j-1}), the torque the joint
    must apply to the links j..n is minus the moment of the loads on them about
    the joint: gravity at their centres of mass, and the forces of the springs
    that cross the joint (one end on a link before j, the other on j or after)::

        tau_j = sum_{t>=j} (c_t - J_{j-1}) x (m_t g UP) + sum_S k_eff (B - J_{j-1}) x (B - A)

    with k_eff = k (1 - l0 / l), l0 the effective free length L_0 - F_i / k. It equals the gradient of the total energy with
    respect to a small rotation of links j..n about the joint; zero everywhere
    means the arm is balanced.

    :param out: a float64 array of shape (N, n-1, 3) to write the torques into (a batch loop can
        reuse one, as Pinocchio reuses its ``data``); None allocates a new one
    :returns: ndarray(N, n-1, 3) in the world frame; row j-2 is joint j's torque
    """
    from springlab.energy import geometry_kernel as kernel

    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    X = chain.as_poses(X)  # float64, any strides: the kernel reads it in place
    springs = check_springs(chain, springs)
    shape = (X.shape[0], chain.n - 1, 3)
    if out is None:
        out = np.empty(shape)
    elif not (isinstance(out, np.ndarray) and out.shape == shape and out.dtype == np.float64 and out.flags.writeable):
        raise SpringlabError(f"out must be a writeable float64 array of shape {shape} (N, n-1, 3), got "
                             f"{type(out).__name__} {getattr(out, 'shape', '')} {getattr(out, 'dtype', '')}; "
                             "or leave it None")
    ints = lambda name: np.array([getattr(s, name) for s in springs], dtype=np.int64)  # noqa: E731
    floats = lambda name: np.array([getattr(s, name) for s in springs], dtype=float)  # noqa: E731
    status, pose, which = kernel.holding_torques(np.asarray(chain.r, dtype=float), np.asarray(chain.d, dtype=float),
                                          np.asarray(chain.m, dtype=float), float(chain.g), UP, ints("i"), ints("j"),
                                          floats("a"), floats("b"), floats("k"), floats("effective_free_length"), X, out)
    if status == kernel.BAD_POSE:
        chain.check_directions(X[pose:pose + 1])  # raises, naming what is wrong
        raise SpringlabError(f"pose {pose} of X is not a valid pose (unit link vectors, x_1 = UP)")
    if status == kernel.ENDS_MEET:
        s = springs[which]
        raise GeometryError(
            f"{s.label}'s ends coincide at pose {pose}: a spring of effective free length {s.effective_free_length:g} m has "
            "no line of action there; move its attachments (a, b) or leave that pose out")
    return out


def _cross(a, b) -> np.ndarray:
    """a x b over the last axis (3): :func:`numpy.cross`'s arithmetic, bit for bit (each component one
    product less another), without its axis handling, which took a tenth of a search's time on small
    batches of poses."""
    a, b = np.asarray(a), np.asarray(b)
    return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                     a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


def cable_geometry(A, B, u, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """A cable from a spring mounted along ``u`` over a pulley of ``radius`` (m) centred at A to B:
    its path (m), (N,), and the point T (N, 3) where it leaves the pulley. The cable arrives along
    u (unit, (N, 3) or (3,)), the pulley swivels about u so that its plane holds B, and the cable
    wraps it until it leaves along the tangent towards B::

        path = rho (alpha + asin(rho / L)) + sqrt(L^2 - rho^2)

    with L = |B - A| and alpha the angle between u and B - A: the wrapped arc plus the straight run
    (:mod:`springlab.energy.pulley`). The cable pulls B towards T.

    :raises GeometryError: where B comes within the pulley's radius of A
    """
    A, B = np.atleast_2d(A), np.atleast_2d(B)
    u = np.broadcast_to(np.asarray(u, dtype=float), A.shape)
    D = B - A
    L = np.linalg.norm(D, axis=1)
    if np.any(L <= radius):
        p = int(np.argmax(L <= radius))
        raise GeometryError(f"the cable's end B comes within the pulley's radius ({radius:g} m) of its centre A at pose "
                            f"{p} (|B - A| = {L[p]:.3g} m): use a smaller pulley or move the attachments")
    along = np.einsum("ij,ij->i", D, u)
    normal = D - along[:, None] * u
    q = np.linalg.norm(normal, axis=1)
    trial = np.where(np.abs(u[:, :1]) < 0.9, np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))
    any_normal = _cross(u, trial)
    any_normal /= np.linalg.norm(any_normal, axis=1)[:, None]  # B on the lead's line: any plane holds it
    e2 = np.where(q[:, None] > 1e-15 * L[:, None], normal / np.maximum(q, 1e-300)[:, None], any_normal)
    alpha = np.arctan2(q, along)  # in [0, pi]
    wrap = alpha + np.arcsin(radius / L)
    path = radius * wrap + np.sqrt(L**2 - radius**2)
    phi = wrap - np.pi / 2  # T's polar angle about A in the plane (u, e2)
    T = A + radius * (np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * e2)
    return path, T


def _spring_ends(model: RevoluteChain, s, R, o):
    """A spring's line of action at each pose: the points it pulls together (on its bodies a and b:
    A, or the point T where its cable leaves the pulley, and B), its length l (m, the cable's path
    over a pulley), (N, 3), (N, 3), (N,), and the bodies' indices."""
    (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
    A, B = world_points(R, o, ia, pa), world_points(R, o, ib, pb)
    if s.pulley_radius > 0:
        path, T = cable_geometry(A, B, R[:, ia] @ model.direction(s.link_a, s.lead)[1], s.pulley_radius)
        return T, B, path, ia, ib
    return A, B, np.linalg.norm(B - A, axis=1), ia, ib


def spring_lines(model: RevoluteChain, springs, q) -> list:
    """Each spring's straight run at the poses ``q`` (N, n) rad: (P, B, a, b), P the point its pull
    on body a acts at (A, or where its cable leaves the pulley), B its end on body b, (N, 3) m each,
    and the two bodies' indices."""
    R, o = body_frames(model, q)
    out = []
    for s in check_point_springs(model, springs):
        P, B, _, a, b = _spring_ends(model, s, R, o)
        out.append((P, B, a, b))
    return out


def spring_lengths(model: RevoluteChain, springs, R, o) -> np.ndarray:
    """Each spring's length l (m) at the poses of :func:`~springlab.model.revolute.body_frames`' ``R``,
    ``o``: |B - A|, or its cable's path over a pulley; (S, N)."""
    return np.array([_spring_ends(model, s, R, o)[2] for s in check_point_springs(model, springs)])


# --- the general model: any revolute chain, springs between any two points ------------------
def _loads(model: RevoluteChain, springs, q, *, gravity: bool = True):
    """Per body, the force (N) and its moment about the base origin (N m) of the loads on it:
    its weight at its centre of mass and the spring forces at its attachment points. Returns
    (F, M, o, axes), F and M of shape (N, n+1, 3); o the bodies' origins, axes the joints' axes.

    Each spring's force and moments at a set of poses are remembered (:func:`_spring_load`) while
    :func:`~springlab.model.revolute.body_frames` keeps those poses' frames: a search that moves one
    spring at a time recomputes that spring alone, and the sums are the same, term by term."""
    springs = check_point_springs(model, springs)
    R, o = body_frames(model, q)
    N, n1 = R.shape[0], model.n + 1
    F = np.zeros((N, R.shape[1], 3))  # the bodies, then the belts' frames (springlab.model.revolute.Belt)
    M = np.zeros((N, R.shape[1], 3))
    if gravity:
        F[:, 1:n1] = model.mass[1:, None] * model.gravity  # the base's weight is the ground's
        M[:, 1:n1] = _cross(centres_of_mass(model, R, o)[:, 1:], F[:, 1:n1])
    for s in springs:
        ia, ib, f_b, m_b, m_a = _spring_load(model, s, R, o)
        F[:, ib] += f_b
        M[:, ib] += m_b
        F[:, ia] -= f_b
        M[:, ia] -= m_a
    for j, belt in enumerate(model.belts):  # a belt's frame: its pulley turns on the joint's parent body about
        at = o[:, n1 + j]  # a point of the joint's axis, and the belt (or the RSSR modules) holds it to the level
        f = F[:, n1 + j]  # body: the force on the frame goes to the parent there, its moment about there to the level
        F[:, belt.joint] += f
        M[:, belt.joint] += _cross(at, f)
        M[:, belt.level] += M[:, n1 + j] - _cross(at, f)
    return F[:, :n1], M[:, :n1], o[:, :n1], joint_axes(model, R)


def _spring_load(model: RevoluteChain, s, R, o):
    """One spring's pull on its body b (N), (N, 3), its moment about the base origin (N m), and
    the moment of the opposite pull on body a, with the bodies' indices: (ia, ib, f_b, m_b, m_a).
    Remembered with the frames :func:`~springlab.model.revolute.body_frames` keeps
    (:func:`~springlab.model.revolute.remembered`), keyed by the spring (its every field)."""
    return remembered(R, ("spring load", s), lambda: _spring_load_now(model, s, R, o))


def _spring_load_now(model: RevoluteChain, s, R, o):
    A, B, length, ia, ib = _spring_ends(model, s, R, o)  # A: where the pull on body a acts (T over a pulley)
    d = B - A
    l0 = s.effective_free_length
    chord = np.linalg.norm(d, axis=1) if (l0 or s.pulley_radius) else None
    if chord is not None and np.any(chord == 0):
        p = int(np.argmax(chord == 0))
        raise GeometryError(f"{s.label}'s ends coincide at pose {p}: a spring of effective free length {l0:g} m "
                            "has no line of action there; move its attachments or leave that pose out")
    # the tension k (l - l0) along the line from B to A (or T), l the length (the cable's path)
    k_eff = np.full(R.shape[0], s.k) if chord is None else s.k * (length - l0) / chord
    f_b = -k_eff[:, None] * d  # the spring pulls B towards A
    return ia, ib, f_b, _cross(B, f_b), _cross(A, f_b)


def joint_torques(model: RevoluteChain, springs, q, *, gravity: bool = True) -> np.ndarray:
    """The torque (N m) each joint must apply to hold each pose against gravity and the springs,
    (N, n), route 2 on the general model.

    For joint i (at body i's origin o_i, axis w_i) the bodies i..n beyond it carry loads whose
    moment about o_i is sum_{b>=i} (p - o_i) x f over their weights and spring forces; the joint
    holds -w_i . that moment. It equals dV/dq_i, the energy's derivative, and Pinocchio's
    ``computeGeneralizedGravity`` without springs. A spring with both ends beyond the joint
    loads it not at all (its two forces cancel).

    :param q: joint angles (N, n) or (n,) (rad)
    :param gravity: False: the springs' torques alone
    """
    F, M, o, w = _loads(model, springs, q, gravity=gravity)
    F_out = np.cumsum(F[:, ::-1], axis=1)[:, ::-1][:, 1:]  # sum over bodies b >= i, i = 1..n
    M_out = np.cumsum(M[:, ::-1], axis=1)[:, ::-1][:, 1:]
    about_joint = M_out - _cross(o[:, 1:], F_out)
    return -np.einsum("pjc,pjc->pj", about_joint, w)


def gravity_torques(model: RevoluteChain, q) -> np.ndarray:
    """The gravity torques (N m) of each joint, (N, n): :func:`joint_torques` without springs."""
    return joint_torques(model, (), q)


def potential(model: RevoluteChain, springs, q) -> dict[str, np.ndarray]:
    """Gravity, spring and total potential energy (J) at each pose of the general model, route 2:
    {'gravity', 'springs', 'total'}, each (N,). The gravity energy's zero is the base frame's
    origin: -sum_b m_b gravity . c_b; a spring's is k (l - l0)^2 / 2, l0 its effective free length.

    :param q: joint angles (N, n) or (n,) (rad)
    """
    springs = check_point_springs(model, springs)
    R, o = body_frames(model, q)
    c = centres_of_mass(model, R, o)
    grav = -np.einsum("pjc,j,c->p", c[:, 1:], model.mass[1:], model.gravity)
    elastic = np.zeros(R.shape[0])
    for s in springs:
        length = _spring_ends(model, s, R, o)[2]  # |B - A|, or the cable's path over its pulley
        elastic += 0.5 * s.k * (length - s.effective_free_length) ** 2
    return {"gravity": grav, "springs": elastic, "total": grav + elastic}
