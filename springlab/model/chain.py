"""Serial chains of links joined by spherical joints (Juang, Jhuang, Chen 2023, Fig. 4).

Link 1 is the ground. Its unit vector x_1 points up, against gravity, and the
plane through the base joint normal to x_1 is the zero of gravity energy
(000 Section 2.2). springlab's world frame is the ground link's frame, so
``UP = x_1 = [1, 0, 0]``::

        x_1 (up)             joint j-1          joint j
         ^                      o-----*-----------o
         |                      |<-d_j->|          |
    base o (joint 1)            |<------ r_j ----->|
                                 x_j: from the proximal to the distal joint

Each moving link j = 2..n has a length r_j (m), a centre of mass at distance
d_j (m) from its proximal joint along x_j, and a mass m_j (kg).

A pose is the set of link directions, ``X`` with shape (N, n, 3): X[:, 0] is
x_1 = UP and X[:, j-1] is x_j. Every function is vectorised over the N poses.

The papers' springs (:class:`~springlab.model.springs.Spring`, on the joint lines, 000 Eq. 19) are
checked against a chain here (:func:`check_springs`, :func:`check_attachments`) and converted to
springs between points of its revolute chain (:func:`point_springs`).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.errors import AttachmentError, SpringlabError
from springlab.model.revolute import RevoluteChain
from springlab.model.rotations import (
    frames_from_directions,
    frames_from_relative,
    rot_axis,
    rot_xyz,
)
from springlab.model.springs import PointSpring, Spring, chain_body

UP = np.array([1.0, 0.0, 0.0])
"""x_1, the ground link's direction: vertical, up. Gravity acts along -UP."""

SPHERICAL = "spherical"

STANDARD_GRAVITY = 9.81
"""m/s^2. Papers that use another value say so in their data module."""


@dataclass(frozen=True)
class Chain:
    """A serial chain with spherical joints; link 1 is the ground.

    Build it with :func:`serial_chain`, which validates the data.

    :ivar r: lengths r_2..r_n (m)
    :ivar d: COM distances d_2..d_n from each link's proximal joint (m)
    :ivar m: masses m_2..m_n (kg)
    :ivar g: gravitational acceleration (m/s^2), acting along -x_1
    :ivar joints: per moving link j = 2..n, the joint to link j-1: 'spherical', or
        a revolute joint's unit axis in link j-1's frame (empty: all spherical)
    """

    r: tuple[float, ...]
    d: tuple[float, ...]
    m: tuple[float, ...]
    g: float = STANDARD_GRAVITY
    joints: tuple = ()

    def __post_init__(self):
        # types, finiteness and signs; serial_chain adds the range of d (on the link)
        r = _checks.positive_vector("r", self.r)
        m = _checks.positive_vector("m", self.m)
        d = _checks.real_array("d", self.d, finite_only=False)
        if d.ndim != 1:
            raise SpringlabError(f"d must be a 1-D sequence, got shape {d.shape}")
        if not (len(r) == len(d) == len(m)):
            raise SpringlabError(
                f"r, d and m must have one entry per moving link; got {len(r)}, {len(d)}, {len(m)}")
        for idx, dj in enumerate(d):
            if not np.isfinite(dj):
                raise SpringlabError(f"d_{idx + 2} must be finite, got {dj}")
        g = _checks.number("g", self.g)
        if not (np.isfinite(g) and g > 0):
            raise SpringlabError(f"g must be a finite positive acceleration in m/s^2, got {self.g!r}")
        with np.errstate(over="ignore"):
            scale = max(m) * max(max(r), float(np.max(np.abs(d)))) * len(r) * g * max(r)
        if not np.isfinite(scale):
            raise SpringlabError("masses, lengths and g this large overflow the energies (m g r^2 beyond 1e308): "
                                 "give them in SI units (kg, m, m/s^2)")
        object.__setattr__(self, "r", r)
        object.__setattr__(self, "m", m)
        object.__setattr__(self, "d", tuple(float(v) for v in d))
        object.__setattr__(self, "g", g)
        object.__setattr__(self, "joints", _joint_spec(self.joints, len(r)))

    def joint(self, j: int):
        """'spherical' or the revolute axis (a 3-tuple in link j-1's frame) of joint j."""
        self._check_moving(j)
        return self.joints[j - 2] if self.joints else SPHERICAL

    @property
    def all_spherical(self) -> bool:
        return all(self.joint(j) == SPHERICAL for j in range(2, self.n + 1))

    @property
    def n(self) -> int:
        """Number of links, the ground included."""
        return len(self.r) + 1

    def length(self, j: int) -> float:
        """r_j (m) for a moving link j = 2..n."""
        self._check_moving(j)
        return self.r[j - 2]

    def with_payload(self, mass: float) -> Chain:
        """The same chain with a payload (kg) at the end link's centre of mass."""
        mass = _checks.positive("payload mass", mass, allow_zero=True, unit="kg")
        return Chain(self.r, self.d, self.m[:-1] + (self.m[-1] + float(mass),), self.g, self.joints)

    def revolute_chain(self, name: str = "chain"):
        """This chain as the general model of an arm, a :class:`~springlab.model.revolute.RevoluteChain`
        (the papers' chains are special cases of it).

        Body 'ground' is link 1 (its frame is the world's, x_1 = UP); body 'link j' is link j, its
        frame at its proximal joint J_{j-1} with x along the link, the centre of mass at (d_j, 0, 0)
        and a slender rod's inertia (m r^2 / 12 across, 1 % of it about the link's own axis). A
        revolute joint turns about its axis; a spherical joint is three revolute joints through
        J_{j-1}, about x, the new y and the new z (the order of
        :func:`~springlab.model.rotations.rot_xyz`), carrying two massless bodies 'link j (x)',
        'link j (y)'. Joint coordinates: :meth:`joint_coordinates`; springs:
        :func:`point_springs`.
        """
        bodies, joints, placements, axes, mass, com, inertia = ["ground"], [], [], [], [0.0], [np.zeros(3)], [np.zeros((3, 3))]
        for j in range(2, self.n + 1):
            P = np.eye(4)
            P[0, 3] = self.r[j - 3] if j >= 3 else 0.0  # J_{j-1} = J_{j-2} + r_{j-1} x_{j-1}
            axis = self.joint(j)
            turns = [("", axis)] if axis != SPHERICAL else [(" (x)", (1.0, 0.0, 0.0)), (" (y)", (0.0, 1.0, 0.0)),
                                                            (" (z)", (0.0, 0.0, 1.0))]
            for k, (suffix, u) in enumerate(turns):
                last = k == len(turns) - 1
                joints.append(f"joint {j}{suffix}")
                bodies.append(chain_body(j) if last else f"{chain_body(j)}{suffix}")
                placements.append(P if k == 0 else np.eye(4))
                axes.append(u)
                m = self.m[j - 2] if last else 0.0
                transverse = m * self.r[j - 2] ** 2 / 12.0
                mass.append(m)
                com.append(np.array([self.d[j - 2] if last else 0.0, 0.0, 0.0]))
                inertia.append(np.diag([0.01 * transverse, transverse, transverse]))
        return RevoluteChain(name, tuple(bodies), tuple(joints), np.array(placements), np.array(axes), np.array(mass),
                             np.array(com), np.array(inertia), -self.g * UP)

    def joint_coordinates(self, angles) -> np.ndarray:
        """Joint angles (N, n-1, 3) (rad, see :meth:`frames`) as the coordinates q (N, nq) of
        :meth:`revolute_chain`: one per revolute joint, three per spherical joint."""
        angles = self.check_angles(angles)
        cols = [angles[:, j - 2, :1] if self.joint(j) != SPHERICAL else angles[:, j - 2, :]
                for j in range(2, self.n + 1)]
        return np.concatenate(cols, axis=1)

    def _check_moving(self, j: int) -> None:
        if not (2 <= j <= self.n):
            raise SpringlabError(f"link index must be in 2..{self.n}, got {j}")

    # --- poses ---------------------------------------------------------------
    def check_angles(self, angles) -> np.ndarray:
        """Validate joint angles: shape (N, n-1, 3), finite; for a revolute joint only
        the first entry (the rotation about its axis) may be nonzero."""
        angles = _checks.real_array("angles", angles, finite_only=False)
        if angles.ndim == 2:
            angles = angles[None]
        if angles.ndim != 3 or angles.shape[1:] != (self.n - 1, 3):
            raise SpringlabError(
                f"angles must have shape (N, {self.n - 1}, 3) for a {self.n}-link chain, "
                f"got {angles.shape}")
        if not np.all(np.isfinite(angles)):
            raise SpringlabError("angles contain NaN or infinity")
        if angles.shape[0] == 0:
            raise SpringlabError("angles hold no pose (shape (0, ...)): give at least one pose")
        for j in range(2, self.n + 1):
            if self.joint(j) != SPHERICAL and np.any(angles[:, j - 2, 1:]):
                raise SpringlabError(
                    f"joint {j} is revolute: only angles[:, {j - 2}, 0] (the rotation about its axis) may be nonzero")
        return angles

    def frames(self, angles) -> np.ndarray:
        """Link frames R_1..R_n (N, n, 3, 3) from joint angles (rad).

        A spherical joint turns link j by Rx(theta) Ry(phi) Rz(psi) relative to
        link j-1 (see :mod:`springlab.model.rotations`); a revolute joint by
        angles[:, j-2, 0] about its axis. R_1 = I; x_j is the first column of R_j.
        """
        angles = self.check_angles(angles)
        rel = rot_xyz(angles[..., 0], angles[..., 1], angles[..., 2])
        for j in range(2, self.n + 1):
            axis = self.joint(j)
            if axis != SPHERICAL:
                rel[:, j - 2] = rot_axis(axis, angles[:, j - 2, 0])
        return frames_from_relative(rel)

    def directions(self, angles) -> np.ndarray:
        """Link directions (N, n, 3) from joint angles (rad), see :meth:`frames`."""
        return self.frames(angles)[..., 0]

    def pose_frames(self, poses) -> np.ndarray:
        """Link frames (N, n, 3, 3) of a batch of poses given either as joint angles
        (N, n-1, 3) or, for a chain of spherical joints, as link directions (N, n, 3)
        (then each link's spin about its own axis is a free choice)."""
        poses = _checks.real_array("poses", poses, finite_only=False)
        if poses.ndim == 3 and poses.shape[1:] == (self.n - 1, 3):
            return self.frames(poses)
        X = self.check_directions(poses)
        if not self.all_spherical:
            raise SpringlabError(
                "a chain with revolute joints needs its poses as joint angles (N, n-1, 3), "
                "not as link directions: directions do not fix the joint axes")
        return frames_from_directions(X)

    def random_angles(self, size: int, rng=None) -> np.ndarray:
        """Random joint angles (N, n-1, 3) in rad: theta and psi uniform in
        [-pi, pi), phi in [-pi/2, pi/2] for spherical joints (not uniform over
        orientations: :func:`random_directions` is, for spherical chains);
        revolute joints turn by an angle uniform in [-pi, pi)."""
        size = _checks.count("size", size)
        rng = _checks.rng("rng", rng)
        _checks.memory(f"random_angles(size={size})", 3.0 * size * (self.n - 1), hint="ask for fewer poses")
        shape = (size, self.n - 1)
        out = np.stack([rng.uniform(-np.pi, np.pi, shape), rng.uniform(-np.pi / 2, np.pi / 2, shape),
                        rng.uniform(-np.pi, np.pi, shape)], axis=-1)
        for j in range(2, self.n + 1):
            if self.joint(j) != SPHERICAL:
                out[:, j - 2, 1:] = 0.0
        return out

    def as_poses(self, X) -> np.ndarray:
        """A batch of poses as a float array of shape (N, n, 3) (a single pose
        (n, 3) becomes N = 1); checks the shape only."""
        X = _checks.real_array("poses X", X, finite_only=False)
        if X.ndim == 2:
            X = X[None]
        if X.ndim != 3 or X.shape[1:] != (self.n, 3):
            raise SpringlabError(
                f"poses X must have shape (N, {self.n}, 3) for a {self.n}-link chain, got {X.shape}")
        if X.shape[0] == 0:
            raise SpringlabError("poses X hold no pose (shape (0, n, 3)): give at least one pose")
        return X

    def check_directions(self, X) -> np.ndarray:
        """Validate a batch of poses and return it as a float array of shape (N, n, 3).

        Raises :class:`~springlab.errors.SpringlabError` on a wrong shape, NaN, a non-unit vector or
        a ground link that does not point up.
        """
        X = self.as_poses(X)
        for _ in self.component_major_chunks(X):
            pass
        return X

    def component_major_chunks(self, X, chunk: int = 8192):
        """Iterate over a batch of poses in chunks, each validated and copied into
        component-major layout: yields ``(start, stop, xt)`` with ``xt`` of shape
        (n, 3, stop - start) (link, coordinate, pose), so that the energy kernels
        multiply contiguous rows. ``xt`` is a reused buffer: consume it before
        the next step. Memory stays bounded by the chunk, whatever N is.

        Raises :class:`~springlab.errors.SpringlabError` on a wrong shape, NaN, a non-unit vector
        (|x|^2 off 1 by more than 2e-9) or a ground link that does not point up.
        """
        X = self.as_poses(X)
        if int(chunk) != chunk or chunk < 1:
            raise SpringlabError(f"chunk must be a positive integer, got {chunk}")
        buf = np.empty((self.n, 3, min(int(chunk), max(X.shape[0], 1))))
        sq = np.empty((self.n, buf.shape[2]))
        for start in range(0, X.shape[0], buf.shape[2]):
            stop = min(start + buf.shape[2], X.shape[0])
            xt = buf[:, :, : stop - start]
            np.copyto(xt.reshape(3 * self.n, -1), X[start:stop].reshape(stop - start, -1).T)
            s = sq[:, : stop - start]
            np.einsum("lcp,lcp->lp", xt, xt, out=s)
            s -= 1.0
            worst = float(np.max(np.abs(s)))
            if not worst <= 2e-9:  # also catches NaN
                if not np.all(np.isfinite(xt)):
                    raise SpringlabError("poses X contain NaN or infinity")
                raise SpringlabError(f"link directions must be unit vectors; |x|^2 - 1 reaches {worst:.3g}")
            ground = xt[0]
            if not (np.all(ground[0] == 1.0) and not np.any(ground[1:])):
                if np.max(np.abs(ground - UP[:, None])) > 1e-12:
                    raise SpringlabError("X[:, 0] is the ground link x_1 and must equal UP = [1, 0, 0]")
            yield start, stop, xt

    def joint_positions(self, X) -> np.ndarray:
        """Positions of joints 1..n (m): joint 1 is the base at the origin, joint j
        the distal joint of link j (joint n is the tip). ndarray(N, n, 3)."""
        X = self.check_directions(X)
        out = np.zeros(X.shape)
        out[:, 1:] = np.cumsum(np.asarray(self.r)[None, :, None] * X[:, 1:], axis=1)
        return out

    def com_positions(self, X) -> np.ndarray:
        """Centres of mass of links 2..n (m), ndarray(N, n-1, 3)."""
        X = self.check_directions(X)
        joints = self.joint_positions(X)
        return joints[:, :-1] + np.asarray(self.d)[None, :, None] * X[:, 1:]

    def tip_position(self, X) -> np.ndarray:
        """Position of the end link's distal joint (m), ndarray(N, 3)."""
        return self.joint_positions(X)[:, -1]


def serial_chain(r, d, m, g: float = STANDARD_GRAVITY, *, joints=None, com_off_link: bool = False) -> Chain:
    """Build and validate a serial chain; link 1 is the ground.

    :param r: lengths r_2..r_n (m), each > 0
    :param d: COM distances d_2..d_n (m), each in [0, r_j] (unless ``com_off_link``)
    :param m: masses m_2..m_n (kg), each > 0
    :param g: gravitational acceleration (m/s^2), > 0
    :param joints: per moving link, 'spherical' (the default for all) or a revolute
        joint's axis, a 3-vector in the previous link's frame (normalised here)
    :param com_off_link: allow d_j < 0 or d_j > r_j (a COM on the link's line but
        beyond a joint, e.g. with a counter-mass)

    >>> arm = serial_chain(r=[0.30, 0.24, 0.20], d=[0.15, 0.12, 0.10], m=[4.0, 3.2, 2.8], g=9.8)
    >>> arm.n
    4
    >>> serial_chain(r=[0.3], d=[0.4], m=[1.0])
    Traceback (most recent call last):
    ...
    springlab.errors.SpringlabError: d_2 = 0.4 m puts the centre of mass off link 2 (r_2 = 0.3 m); d must lie in [0, r], or pass com_off_link=True
    """
    chain = Chain(r=r, d=d, m=m, g=g, joints=() if joints is None else joints)
    if not com_off_link:
        for idx, (dj, rj) in enumerate(zip(chain.d, chain.r, strict=True)):
            if not (0.0 <= dj <= rj):
                link = idx + 2
                raise SpringlabError(
                    f"d_{link} = {dj:g} m puts the centre of mass off link {link} (r_{link} = {rj:g} m); "
                    "d must lie in [0, r], or pass com_off_link=True")
    return chain


def _joint_spec(joints, n_moving: int) -> tuple:
    if joints is None:
        return ()
    if isinstance(joints, str) or not hasattr(joints, "__len__"):
        raise SpringlabError(f"joints must be a sequence with one entry per moving link, got {joints!r}")
    if len(joints) == 0:
        return ()
    joints = list(joints)
    if len(joints) != n_moving:
        raise SpringlabError(f"joints must have one entry per moving link ({n_moving}), got {len(joints)}")
    out = []
    for idx, spec in enumerate(joints):
        if isinstance(spec, str):
            if spec != SPHERICAL:
                raise SpringlabError(f"joint {idx + 2} must be 'spherical' or a revolute axis, got {spec!r}")
            out.append(SPHERICAL)
            continue
        axis = _checks.real_array(f"revolute axis of joint {idx + 2}", spec, finite_only=False)
        norm = np.linalg.norm(axis) if axis.shape == (3,) else 0.0
        if not (np.all(np.isfinite(axis)) and norm > 1e-12):
            raise SpringlabError(f"revolute axis of joint {idx + 2} must be a nonzero 3-vector, got {spec!r}")
        out.append(tuple(float(v) for v in axis / norm))
    return () if all(j == SPHERICAL for j in out) else tuple(out)


def random_directions(n: int, size: int, rng=None) -> np.ndarray:
    """Random poses of an n-link spherical chain: each moving link's direction is
    uniform on the sphere (a spherical joint reaches every direction).

    :param n: number of links, the ground included (>= 2)
    :param size: number of poses N
    :param rng: a ``numpy.random.Generator`` or a seed
    :returns: ndarray(N, n, 3), X[:, 0] = UP
    """
    n = _checks.count("n", n, least=2)
    size = _checks.count("size", size, least=0)
    _checks.memory(f"{size} poses of a {n}-link chain", 2.0 * size * n * 3, hint="ask for fewer poses")
    rng = np.random.default_rng(rng)
    v = rng.standard_normal((int(size), int(n) - 1, 3))
    v /= np.linalg.norm(v, axis=2, keepdims=True)
    out = np.empty((int(size), int(n), 3))
    out[:, 0] = UP
    out[:, 1:] = v
    return out


def planar_directions(theta) -> np.ndarray:
    """The link directions X (N, n, 3) of a planar arm at angles ``theta`` (N, n - 1) rad (each link's from the
    one before, link 2's from the horizontal), in a vertical plane of route 2's chain: x_1 is :data:`UP`, so link j's
    height per unit length is sin(theta_2 + ... + theta_j), as 000 Eqs. (2a)-(2c) have it."""
    theta = _checks.real_array("theta", theta)
    if theta.ndim != 2:
        raise SpringlabError(f"theta must be (poses, links - 1) angles, got shape {theta.shape}")
    phi = np.cumsum(theta, axis=1)
    out = np.zeros((theta.shape[0], theta.shape[1] + 1, 3))
    out[:, 0, 0] = 1.0
    out[:, 1:, 0], out[:, 1:, 1] = np.sin(phi), np.cos(phi)
    return out


def _cap(axis: np.ndarray, half_angle: float, rng) -> np.ndarray:
    """Unit vectors uniform on the spherical cap of ``half_angle`` (rad) about each row of ``axis`` (N, 3)."""
    N = axis.shape[0]
    cos = rng.uniform(np.cos(half_angle), 1.0, N)
    phi = rng.uniform(0.0, 2 * np.pi, N)
    helper = np.where(np.abs(axis[:, :1]) < 0.9, np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))
    e1 = np.cross(axis, helper)
    e1 /= np.linalg.norm(e1, axis=1)[:, None]
    e2 = np.cross(axis, e1)
    sin = np.sqrt(1.0 - cos**2)
    return cos[:, None] * axis + sin[:, None] * (np.cos(phi)[:, None] * e1 + np.sin(phi)[:, None] * e2)


def bend_angles(X) -> np.ndarray:
    """The angle (rad) between each link's direction and the previous link's (x_1 = UP for link 2):
    (N, n - 1), a spherical joint's bend."""
    X = _checks.real_array("X", X, shape=(None, None, 3))
    cos = np.einsum("pjk,pjk->pj", X[:, 1:], X[:, :-1])
    return np.arccos(np.clip(cos, -1.0, 1.0))


def limited_poses(chain: Chain, size: int, rng, limits) -> np.ndarray:
    """Random link directions (N, n, 3) within joint limits, one entry per moving link: None (free),
    a cone half-angle (rad) for a spherical joint (the link within that angle of the previous link's
    direction, uniform on the cap), or (low, high) (rad) for a revolute joint (uniform in the range).

    An all-spherical chain is sampled link by link from the base; a chain with revolute joints by
    joint angles, spherical joints' cones kept by rejection (raises if fewer than one draw in a
    thousand is kept: the cones are too tight for random angles).
    """
    size = _checks.count("size", size, least=1)
    rng = np.random.default_rng(rng)
    limits = tuple(limits)
    if len(limits) != chain.n - 1:
        raise SpringlabError(f"limits must give one entry per moving link ({chain.n - 1}), got {len(limits)}")
    for j, lim in enumerate(limits, start=2):
        spherical = chain.joint(j) == SPHERICAL
        if lim is None:
            continue
        if spherical and not (isinstance(lim, float | int) and 0 < lim <= np.pi):
            raise SpringlabError(f"joint {j} is spherical: its limit is a cone half-angle in (0, pi] rad, got {lim!r}")
        if not spherical and not (isinstance(lim, tuple) and len(lim) == 2 and -np.pi <= lim[0] < lim[1] <= np.pi):
            raise SpringlabError(f"joint {j} is revolute: its limit is a range (low, high) within [-pi, pi] rad, "
                                 f"low < high, got {lim!r}")
    _checks.memory(f"{size} poses of a {chain.n}-link chain", 2.0 * size * chain.n * 3, hint="ask for fewer poses")
    if chain.all_spherical:
        X = random_directions(chain.n, size, rng)
        for j, lim in enumerate(limits, start=2):
            if lim is not None:
                X[:, j - 1] = _cap(X[:, j - 2], float(lim), rng)
        return X
    kept, drawn = [], 0
    while sum(len(k) for k in kept) < size:
        angles = chain.random_angles(size, rng)
        for j, lim in enumerate(limits, start=2):
            if lim is not None and chain.joint(j) != SPHERICAL:
                angles[:, j - 2, 0] = rng.uniform(lim[0], lim[1], size)
        X = chain.directions(angles)
        bends = bend_angles(X)
        ok = np.ones(size, dtype=bool)
        for j, lim in enumerate(limits, start=2):
            if lim is not None and chain.joint(j) == SPHERICAL:
                ok &= bends[:, j - 2] <= lim
        kept.append(X[ok])
        drawn += size
        if drawn >= 1000 * size and sum(len(k) for k in kept) < size:
            raise SpringlabError("the spherical joints' cones are too tight to sample by random joint angles "
                                 "(fewer than one draw in a thousand falls within them): widen them")
    return np.concatenate(kept)[:size]


def check_springs(chain, springs) -> tuple[Spring, ...]:
    """Validate that every spring fits the chain (j <= n) and that its energy over the
    chain's reach is a finite number of joules; return them as a tuple."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    if isinstance(springs, Spring) or isinstance(springs, str) or not hasattr(springs, "__iter__"):
        raise SpringlabError(f"springs must be a sequence of Spring objects, got {springs!r}")
    springs = tuple(springs)
    reach = float(sum(chain.r))
    for s in springs:
        if not isinstance(s, Spring):
            raise SpringlabError(f"expected Spring objects, got {type(s).__name__}")
        if s.j > chain.n:
            raise SpringlabError(
                f"{s.label} attaches to link {s.j}, but the chain has only {chain.n} links"
            )
        length = np.float64(reach + abs(s.a) + abs(s.b))  # numpy: an overflow is inf, not an OverflowError
        with np.errstate(over="ignore"):
            if not np.isfinite(length * length):
                end, value = ("a", s.a) if abs(s.a) >= abs(s.b) else ("b", s.b)
                raise SpringlabError(f"{end} of {s.label} = {value:g} m puts its end so far from its joint that the "
                                     f"spring's energy overflows: give the attachment in m (the arm reaches {reach:g} m)")
            if not np.isfinite(s.k * length * length):
                raise SpringlabError(f"k of {s.label} = {s.k:g} N/m overflows the spring's energy "
                                     f"(k L^2 with L ~ {float(length):g} m): give k in N/m")
    return springs


def measured_from_other_joints(chain, springs) -> tuple[Spring, ...]:
    """The springs as they would be built if a and b were read from the other joint of each
    link: end A at a from link i's **proximal** joint (A = J_{i-1} + a x_i, i.e. a - r_i in
    the convention above; a ground spring keeps its a, the ground having one joint), end B at
    b from link j's **distal** joint (B = J_j + b x_j, i.e. b + r_j). 000 Eq. (19) and the
    text below it fix the reading of this module; this one shows why it matters.

    :returns: springs in this module's convention (m, N/m)
    """
    out = []
    for s in check_springs(chain, springs):
        a = s.a - chain.length(s.i) if s.i >= 2 else s.a
        out.append(Spring(s.i, s.j, a, s.b + chain.length(s.j), s.k, s.free_length, s.initial_tension))
    return tuple(out)


def check_attachments(chain, springs, *, max_extension: float | None = None) -> None:
    """Raise :class:`~springlab.errors.AttachmentError` if a spring end lies off its link.

    An end on the link side of its joint (a < 0 on link i >= 2, b > 0 on link j)
    must stay within the link: |a| <= r_i, b <= r_j. An end on the other side
    (a > 0 past link i's distal joint, b < 0 behind link j's proximal joint) sits
    on a bracket that extends the link; ``max_extension`` (m) bounds it if given.
    """
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    springs = check_springs(chain, springs)
    max_extension = _checks.optional_positive("max_extension", max_extension, "m")
    for s in springs:
        if s.i >= 2 and s.a < 0 and -s.a > chain.length(s.i) * (1 + 1e-12):
            raise AttachmentError(
                f"a_{s.label} = {s.a:.6g} m puts end A beyond link {s.i}'s proximal joint "
                f"(r_{s.i} = {chain.length(s.i):g} m): the attachment is off the link")
        if s.b > 0 and s.b > chain.length(s.j) * (1 + 1e-12):
            raise AttachmentError(
                f"b_{s.label} = {s.b:.6g} m puts end B beyond link {s.j}'s distal joint "
                f"(r_{s.j} = {chain.length(s.j):g} m): the attachment is off the link")
        if max_extension is not None:
            for name, value, extended in (("a", s.a, s.a > 0), ("b", s.b, s.b < 0)):
                if extended and abs(value) > max_extension:
                    raise AttachmentError(
                        f"{name}_{s.label} = {value:.6g} m needs a bracket longer than "
                        f"max_extension = {max_extension:g} m")


def point_springs(chain, springs) -> tuple[PointSpring, ...]:
    """The papers' springs S(i, j) on a chain's joint lines as springs between points of the bodies
    of :meth:`springlab.model.chain.Chain.revolute_chain` (body 'ground' and 'link j', each
    link's frame at its proximal joint with x along the link):

    A = J_i + a x_i is (r_i + a, 0, 0) in link i's frame (a, 0, 0) on the ground, whose frame
    is at the base joint with x up; B = J_{j-1} + b x_j is (b, 0, 0) in link j's frame.
    """
    springs = check_springs(chain, springs)
    out = []
    for s in springs:
        point_a = (s.a if s.i == 1 else chain.length(s.i) + s.a, 0.0, 0.0)
        out.append(PointSpring(chain_body(s.i), point_a, chain_body(s.j), (s.b, 0.0, 0.0), s.k,
                               s.free_length, s.initial_tension))
    return tuple(out)
