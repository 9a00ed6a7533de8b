"""The one model of an arm: a serial chain of revolute joints, built from a URDF's own frames.

Pinocchio's habit: an immutable model (:class:`RevoluteChain`) holds what does not change
with the pose; free functions (:func:`body_frames`, :func:`world_points`) compute the per-pose
data, vectorised over N poses. Body 0 is the base (the ground, with everything fixed to it);
body i (i = 1..n) turns with joint i. Each joint sits in its parent body's frame::

    world <- body 0 --placement_1--> joint 1 frame = body 1's frame --placement_2--> ...

    T_i(q) = T_{i-1}(q) @ placement_i @ Rot(axis_i, q_i),   T_0 = I

so joint i's frame at q_i = 0 is body i's frame (URDF's convention: a joint's frame is its child
link's frame; the axis is given in it). A body's mass sits at its centre of mass ``com`` (m, in
the body's frame), its ``inertia`` (kg m^2) is about that centre, in the body's frame. Gravity
is a vector (m/s^2) in the base frame: URDF's is ``[0, 0, -9.81]``.

The papers' idealised chains are special cases: :meth:`springlab.model.chain.Chain.revolute_chain`
builds this model from a :class:`~springlab.model.chain.Chain` (a spherical joint is three
revolute joints about x, y, z through one point, the two bodies between them massless), and
:func:`springlab.model.urdf.read_revolute_chain` from a URDF. Route 2
(:func:`springlab.energy.geometry.potential`, :func:`springlab.energy.geometry.joint_torques`)
and route 3 (:func:`springlab.energy.simulation.joint_torques`) take this model and
:class:`~springlab.model.springs.PointSpring` springs.

Frames a belt or paper 001's RSSR modules carry (:class:`Belt`, :meth:`RevoluteChain.with_belt`,
:meth:`RevoluteChain.with_pseudobase`) follow the bodies: a point of a joint's axis with a level body's axes.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

import os
import threading
from collections import OrderedDict
from dataclasses import dataclass, field, replace

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.model.springs import PointSpring


def _array(name: str, value, shape) -> np.ndarray:
    out = _checks.real_array(name, value, finite_only=False)
    if out.shape != shape:
        raise SpringlabError(f"{name} must have shape {shape}, got {out.shape}")
    if not np.all(np.isfinite(out)):
        raise SpringlabError(f"{name} contains NaN or infinity")
    out = out.copy()
    out.setflags(write=False)
    return out


BELT_PARALLEL = 1e-6
"""|sin| of the angle between two axes below which a belt may run across them (a URDF's rounded angles are
good to about 1e-6 rad)."""


@dataclass(frozen=True)
class Belt:
    """A frame a 1:1 belt carries (:meth:`RevoluteChain.with_belt`), or a chain of paper 001's spatial
    parallelogram RSSR modules (:meth:`RevoluteChain.with_pseudobase`): at the origin of joint ``joint``
    (0-based; its child body's origin), moved ``along`` (m) its axis, with the axes of body ``level`` (an
    index, at most ``joint``). ``kind`` is ``'belt'`` (every joint between turns about a parallel axis) or
    ``'rssr'`` (any axes: the modules keep the frame's vertical line vertical, 001 Section 4)."""

    name: str
    joint: int
    level: int
    along: float = 0.0
    kind: str = "belt"


@dataclass(frozen=True, eq=False)
class RevoluteChain:
    """A serial chain of n revolute joints carrying n + 1 rigid bodies (body 0 the base).

    :ivar name: the arm's name
    :ivar bodies: n + 1 body names (a URDF's link names; body 0 the base)
    :ivar joints: n joint names
    :ivar placements: (n, 4, 4) homogeneous transforms: body i-1's frame -> joint i's frame at q_i = 0
    :ivar axes: (n, 3) unit axes, each in its joint's frame
    :ivar mass: (n + 1,) kg (the base's is carried by the ground and never used)
    :ivar com: (n + 1, 3) centres of mass (m), each in its body's frame
    :ivar inertia: (n + 1, 3, 3) inertia tensors (kg m^2) about the centre of mass, body frame
    :ivar gravity: (3,) gravitational acceleration (m/s^2) in the base frame
    :ivar limits: (n, 2) joint ranges (rad); -inf, inf for an unlimited joint
    :ivar notes: what the builder assumed (read from a file: what it did with it)
    :ivar fixed: the other named frames fixed to the bodies (a URDF's links merged into a body: a
        flange, a tool0, a locked finger), as name -> (body index, (4, 4) transform from that frame
        to the body's); a spring may attach to any of them (:meth:`locate`)
    :ivar outline: () when the shapes are unknown, else per body the points (m, body frame, (k, 3),
        k = 0 for a body without geometry) whose convex hull bounds it (a URDF's collision shapes:
        :mod:`springlab.model.shapes`); where a spring may be attached
    :ivar belts: frames a 1:1 belt carries (:class:`Belt`, :meth:`with_belt`): each at a joint's origin,
        its axes those of a body before it (a level reference carried to that joint); a spring may
        attach to one by its name (:meth:`locate`), and :func:`body_frames` gives their frames after the
        bodies'
    :ivar solids: () when the shapes are unknown, else per body its collision shapes
        (:class:`~springlab.model.shapes.Solid`, each in the body's frame): what springs must clear
        (:mod:`springlab.design.collision`)
    """

    name: str
    bodies: tuple
    joints: tuple
    placements: np.ndarray
    axes: np.ndarray
    mass: np.ndarray
    com: np.ndarray
    inertia: np.ndarray
    gravity: np.ndarray
    limits: np.ndarray | None = None
    notes: tuple = field(default=(), compare=False)
    fixed: dict = field(default_factory=dict, compare=False)
    outline: tuple = field(default=(), compare=False)
    solids: tuple = field(default=(), compare=False)
    belts: tuple = ()

    def __post_init__(self):
        bodies, joints = tuple(self.bodies), tuple(self.joints)
        n = len(joints)
        if n < 1:
            raise SpringlabError("a revolute chain needs at least one joint")
        for what, names in (("bodies", bodies), ("joints", joints)):
            if not all(isinstance(x, str) and x for x in names):
                raise SpringlabError(f"{what} must be non-empty names (strings), got {names!r}")
            if len(set(names)) != len(names):
                raise SpringlabError(f"{what} must have distinct names, got {names!r}")
        if len(bodies) != n + 1:
            raise SpringlabError(f"a chain of {n} joints carries {n + 1} bodies (the base first), got {len(bodies)}")
        placements = _array("placements", self.placements, (n, 4, 4))
        for i, T in enumerate(placements):
            R = T[:3, :3]
            if np.max(np.abs(R.T @ R - np.eye(3))) > 1e-9 or np.linalg.det(R) < 0 or np.any(T[3] != [0, 0, 0, 1]):
                raise SpringlabError(f"placement of joint {joints[i]!r} must be a rigid transform (a rotation "
                                     "and a translation, last row 0 0 0 1)")
        axes = _array("axes", self.axes, (n, 3))
        norms = np.linalg.norm(axes, axis=1)
        if np.any(np.abs(norms - 1.0) > 1e-9):
            i = int(np.argmax(np.abs(norms - 1.0)))
            raise SpringlabError(f"axis of joint {joints[i]!r} must be a unit vector, got {axes[i].tolist()}")
        mass = _array("mass", self.mass, (n + 1,))
        if np.any(mass < 0):
            i = int(np.argmin(mass))
            raise SpringlabError(f"mass of body {bodies[i]!r} = {mass[i]:g} kg must be >= 0")
        com = _array("com", self.com, (n + 1, 3))
        inertia = _array("inertia", self.inertia, (n + 1, 3, 3))
        for i, J in enumerate(inertia):
            if np.max(np.abs(J - J.T)) > 1e-9 * max(1.0, float(np.max(np.abs(J)))):
                raise SpringlabError(f"inertia of body {bodies[i]!r} must be symmetric (kg m^2), got {J.tolist()}")
        gravity = _array("gravity", self.gravity, (3,))
        if not np.linalg.norm(gravity) > 0:
            raise SpringlabError("gravity must be a nonzero vector (m/s^2) in the base frame, e.g. [0, 0, -9.81]")
        if self.limits is None:
            limits = np.tile([-np.inf, np.inf], (n, 1))
        else:
            limits = _checks.real_array("limits", self.limits, finite_only=False)
            if limits.shape != (n, 2) or np.any(np.isnan(limits)) or np.any(limits[:, 0] >= limits[:, 1]):
                raise SpringlabError(f"limits must be (n, 2) = ({n}, 2) ranges (rad) with lower < upper "
                                     f"(-inf, inf: unlimited), got {limits.tolist()}")
            limits = limits.copy()
        limits.setflags(write=False)
        with np.errstate(over="ignore"):
            scale = float(np.sum(mass)) * float(np.linalg.norm(gravity)) * (
                float(np.sum(np.linalg.norm(placements[:, :3, 3], axis=1))) + float(np.max(np.linalg.norm(com, axis=1))))
        if not np.isfinite(scale):
            raise SpringlabError("masses, lengths and gravity this large overflow the energies: give them in SI "
                                 "units (kg, m, m/s^2)")
        fixed = {}
        for frame, (body, T) in dict(self.fixed).items():
            if frame in bodies or not isinstance(frame, str) or not (isinstance(body, int) and 0 <= body <= n):
                raise SpringlabError(f"fixed frame {frame!r} must be a new name on a body index 0..{n}, got body {body!r}")
            T = _array(f"transform of fixed frame {frame!r}", T, (4, 4))
            fixed[frame] = (body, T)
        object.__setattr__(self, "fixed", fixed)
        outline = tuple(self.outline)
        if outline:
            if len(outline) != n + 1:
                raise SpringlabError(f"outline must hold one point set per body ({n + 1}), got {len(outline)}")
            outline = tuple(_array(f"outline of body {bodies[i]!r}", p, (len(np.atleast_2d(p)), 3))
                            if np.size(p) else np.zeros((0, 3)) for i, p in enumerate(outline))
        object.__setattr__(self, "outline", outline)
        solids = tuple(tuple(s) for s in self.solids)
        if solids and len(solids) != n + 1:
            raise SpringlabError(f"solids must hold one tuple of shapes per body ({n + 1}), got {len(solids)}")
        object.__setattr__(self, "solids", solids)
        belts = tuple(self.belts)
        for b in belts:
            if (not isinstance(b, Belt) or not 0 <= b.joint < n or not 0 <= b.level <= b.joint
                    or b.kind not in ("belt", "rssr") or not np.isfinite(b.along)):
                raise SpringlabError(f"belt {b!r}: give a Belt at a joint (0..{n - 1}) whose axes are a body's before it, "
                                     "of kind 'belt' or 'rssr', a finite distance along the joint's axis")
        object.__setattr__(self, "belts", belts)
        for name, value in (("bodies", bodies), ("joints", joints), ("placements", placements), ("axes", axes),
                            ("mass", mass), ("com", com), ("inertia", inertia), ("gravity", gravity),
                            ("limits", limits), ("notes", tuple(self.notes))):
            object.__setattr__(self, name, value)

    @property
    def n(self) -> int:
        """The number of joints (the chain's degrees of freedom)."""
        return len(self.joints)

    @property
    def g(self) -> float:
        """|gravity| (m/s^2)."""
        return float(np.linalg.norm(self.gravity))

    @property
    def up(self) -> np.ndarray:
        """The unit vector against gravity, in the base frame."""
        return -self.gravity / self.g

    @property
    def frame_names(self) -> tuple:
        """Every name a spring may attach to: the bodies, the fixed frames, then the belts' frames."""
        return self.bodies + tuple(self.fixed) + tuple(b.name for b in self.belts)

    def first_unparallel(self, level: int, joint: int) -> int | None:
        """The first joint (index) from body ``level`` to ``joint`` (indices) whose axis is not parallel to
        ``joint``'s (within :data:`BELT_PARALLEL`, zero pose): where no belt keeps the level body's axes; None
        where every one is."""
        R, _ = body_frames(self, np.zeros(self.n))
        w = R[0, joint + 1] @ self.axes[joint]
        return next((t for t in range(level, joint)
                     if np.linalg.norm(np.cross(R[0, t + 1] @ self.axes[t], w)) > BELT_PARALLEL), None)

    def first_tilted(self, body: int, tolerance: float = BELT_PARALLEL) -> int | None:
        """The first joint (index) before body ``body`` (an index) whose axis is not vertical (|sin| of its angle
        to the vertical above ``tolerance``): where that body stops staying level; None where it stays level."""
        R, _ = body_frames(self, np.zeros(self.n))
        return next((t for t in range(body)
                     if np.linalg.norm(np.cross(R[0, t + 1] @ self.axes[t], self.up)) > tolerance), None)

    def _carried(self, joint: str, level: str, how: str) -> tuple[int, int]:
        """The indices of ``joint`` and of body ``level`` (a body before it) for a frame a belt or RSSR modules
        carry (``how``: what the message says carries it).

        :raises SpringlabError: naming the joint or the body that is not the arm's, or a level body beyond
        """
        if joint not in self.joints:
            raise SpringlabError(f"joint = {joint!r} is not a joint of {self.name!r}: give one of {', '.join(self.joints)}")
        if level not in self.bodies:
            raise SpringlabError(f"level = {level!r} is not a body of {self.name!r}: give one of {', '.join(self.bodies)}")
        i, L = self.joints.index(joint), self.bodies.index(level)
        if L > i:
            raise SpringlabError(f"level = {level!r} lies beyond joint {joint!r}: {how} the axes of a body before the "
                                 f"joint (one of {', '.join(self.bodies[:i + 1])})")
        return i, L

    def with_belt(self, joint: str, level: str, name: str | None = None, *, along: float = 0.0) -> RevoluteChain:
        """The same chain with a frame a 1:1 belt carries to ``joint``'s origin, its axes those of body
        ``level`` (a body before the joint): a pulley on the joint's axis (``along`` it, m, from the joint's
        origin), turning on the joint's parent body, tied by belts (one per joint between) to a pulley fixed to
        ``level``. Named ``name``
        (default '<joint> belt'). Every joint between ``level`` and ``joint`` must turn about an axis
        parallel to the joint's: only then can a belt keep the frame's axes those of ``level``.

        :raises SpringlabError: naming the joint, the body or the axis that prevents it
        """
        i, L = self._carried(joint, level, "a belt carries")
        t = self.first_unparallel(L, i)
        if t is not None:
            raise SpringlabError(f"joint {self.joints[t]!r} between {level!r} and {joint!r} turns about an axis "
                                 f"not parallel to {joint!r}'s: no belt keeps {level!r}'s axes across it; choose "
                                 "a level body after it")
        name = f"{joint} belt" if name is None else name
        if name in self.frame_names:
            raise SpringlabError(f"name = {name!r} is already a frame of {self.name!r}: give the belt another name")
        return replace(self, belts=(*self.belts, Belt(name, i, L, float(_checks.number("along", along)))))

    def with_pseudobase(self, joint: str, level: str, *, along: float = 0.0, name: str | None = None) -> RevoluteChain:
        """The same chain with paper 001's pseudobase at ``joint``: a frame at the point ``along`` (m) the joint's
        axis from its origin (a point of the joint's parent and child bodies alike: the module's spherical
        joint C_i), whose vertical line a chain of spatial parallelogram RSSR modules keeps vertical across any
        joints (001 Section 4, Fig. 6). The frame is given the axes of body ``level``, a body that turns about
        the vertical alone; the modules keep only its vertical line, the frame's spin about it idle
        (001 Eq. 19), so a point on it must lie on that line, as a spring's post A_i does (001 Eq. 13). Named
        ``name`` (default '<joint> pseudobase').

        :raises SpringlabError: naming the joint or the body that prevents it
        """
        i, L = self._carried(joint, level, "a pseudobase keeps")
        t = self.first_tilted(L)
        if t is not None:
            raise SpringlabError(f"joint {self.joints[t]!r} before {level!r} turns about a non-vertical axis: "
                                     f"{level!r} does not stay level; choose a body before it")
        name = f"{joint} pseudobase" if name is None else name
        if name in self.frame_names:
            raise SpringlabError(f"name = {name!r} is already a frame of {self.name!r}: give the pseudobase another name")
        along = _checks.number("along", along)
        return replace(self, belts=(*self.belts, Belt(name, i, L, float(along), "rssr")))

    def belt_turns(self, belt: Belt) -> tuple[np.ndarray, np.ndarray]:
        """How a belt's pulley turns on its joint's parent body: its axis (unit, in the level body's frame)
        and, per joint between the level body and the belt's joint, the sign s_t (+1 or -1) such that the
        pulley's angle about that axis, relative to the parent body, is -sum_t s_t q_t (the joints' axes
        are parallel to it, along or against)."""
        if belt.kind != "belt":
            raise SpringlabError(f"{belt.name!r} is kept by RSSR modules, not by a belt: it has no pulley to turn")
        R, _ = body_frames(self, np.zeros(self.n))
        w = R[0, belt.joint + 1] @ self.axes[belt.joint]
        signs = np.array([np.sign((R[0, t + 1] @ self.axes[t]) @ w) for t in range(belt.level, belt.joint)])
        return R[0, belt.level].T @ w, signs

    def locate(self, name, point) -> tuple[int, np.ndarray]:
        """A point (m) given in a named frame (a body, a fixed frame or a belt's frame) as (body index, the
        point in that body's frame); a belt's frame has the index n + 1 + its place in :attr:`belts`."""
        for j, b in enumerate(self.belts):
            if b.name == name:
                return self.n + 1 + j, np.asarray(point, dtype=float)
        if name in self.fixed:
            body, T = self.fixed[name]
            return body, T[:3, :3] @ np.asarray(point, dtype=float) + T[:3, 3]
        if name not in self.bodies:
            names = self.frame_names
            shown = ", ".join(map(repr, names[:12])) + (", ..." if len(names) > 12 else "")
            raise SpringlabError(f"{name!r} is not a link of {self.name!r}: give one of {shown}")
        return self.bodies.index(name), np.asarray(point, dtype=float)

    def direction(self, name, vector) -> tuple[int, np.ndarray]:
        """A direction given in a named frame (a body or a fixed frame) as (body index, the direction
        in that body's frame): :meth:`locate` for vectors, rotated but not moved."""
        body, origin = self.locate(name, (0.0, 0.0, 0.0))
        return body, self.locate(name, vector)[1] - origin

    def rotation(self, name) -> np.ndarray:
        """The rotation (3, 3) from a named frame (a body or a fixed frame) to its body's frame: its
        columns are the named frame's axes in the body's frame (:meth:`direction` of each)."""
        return np.array([self.direction(name, e)[1] for e in np.eye(3)]).T

    def with_point_mass(self, name, point, mass) -> RevoluteChain:
        """The same chain carrying ``mass`` (kg) more at ``point`` (m, in the named frame): a payload
        added, or with a negative mass one taken off again (down to none). The body's mass, centre of
        mass and inertia are combined as one rigid body's (parallel axes); the gravity torques are
        linear in ``mass``.

        :raises SpringlabError: when the point is not three finite numbers, or the body would be left
            with a negative mass
        """
        mass = _checks.finite("mass", mass, unit="kg")
        try:
            given = np.asarray(point, dtype=float)
        except (TypeError, ValueError):
            given = np.full(1, np.nan)
        if given.shape != (3,) or not np.all(np.isfinite(given)):
            raise SpringlabError(f"point = {point!r}: give three finite numbers (m, in frame {name!r}), where the "
                                 "mass is carried")
        body, p = self.locate(name, given)
        total = float(self.mass[body]) + mass
        if total < -1e-12 * max(1.0, float(self.mass[body])):
            raise SpringlabError(f"mass = {mass:g} kg takes more off body {self.bodies[body]!r} than its "
                                 f"{float(self.mass[body]):g} kg: give a payload of at least 0 kg")
        masses, coms, inertias = self.mass.copy(), self.com.copy(), self.inertia.copy()
        if total <= 0:
            masses[body], coms[body] = 0.0, p
        else:
            com = (self.mass[body] * self.com[body] + mass * p) / total
            J = self.inertia[body].copy()
            for m, c in ((self.mass[body], self.com[body]), (mass, p)):
                d = c - com
                J += m * (float(d @ d) * np.eye(3) - np.outer(d, d))
            masses[body], coms[body], inertias[body] = total, com, 0.5 * (J + J.T)
        return replace(self, mass=masses, com=coms, inertia=inertias)

    def check_q(self, q) -> np.ndarray:
        """Joint angles (rad) as a float array (N, n); a single pose (n,) becomes N = 1."""
        q = _checks.real_array("q (joint angles)", q, finite_only=False)
        if q.ndim == 1:
            q = q[None]
        if q.ndim != 2 or q.shape[1] != self.n:
            raise SpringlabError(f"q (joint angles) must have shape (N, {self.n}) for the {self.n} joints of "
                                 f"{self.name!r} (rad), got {q.shape}")
        if q.shape[0] == 0:
            raise SpringlabError("q (joint angles) holds no pose (shape (0, n)): give at least one pose")
        if not np.all(np.isfinite(q)):
            raise SpringlabError("q (joint angles) contains NaN or infinity")
        return q

    def random_q(self, size: int, rng=None) -> np.ndarray:
        """Random joint angles (N, n) in rad, uniform within each joint's limits (an unlimited joint in
        [-pi, pi))."""
        size = _checks.count("size", size)
        rng = _checks.rng("rng", rng)
        _checks.memory(f"random_q(size={size})", 1.0 * size * self.n, hint="ask for fewer poses")
        lo = np.where(np.isfinite(self.limits[:, 0]), self.limits[:, 0], -np.pi)
        hi = np.where(np.isfinite(self.limits[:, 1]), self.limits[:, 1], np.pi)
        return rng.uniform(lo, hi, (size, self.n))


def body_frames(model: RevoluteChain, q) -> tuple[np.ndarray, np.ndarray]:
    """Every body's frame in the base frame at each pose: rotations (N, n+1, 3, 3) and origins
    (N, n+1, 3) (m); body 0 (the base) is the identity at the origin. A model with belts
    (:attr:`RevoluteChain.belts`) has their frames after the bodies' (N, n+1+b, ...): each at its
    joint's origin (moved ``along`` its axis), with its level body's axes.

    T_i = T_{i-1} @ placement_i @ Rot(axis_i, q_i) (see the module docstring).

    The arrays are read-only: the last few results are kept (:data:`FRAMES_KEPT`, for at most
    :data:`FRAMES_CACHED_POSES` poses each) and given again for the same model and angles, as a
    search asks for the torques of one set of poses thousands of times with other springs
    (:func:`remembered` keeps what is computed from them alongside).
    """
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    q = model.check_q(q)
    N, n = q.shape
    key = (id(model), q.shape, q.tobytes()) if N <= FRAMES_CACHED_POSES else None
    with _KEPT_LOCK:
        kept = _FRAMES.get(key) if key is not None else None
        if kept is not None and kept.model is model:  # the model itself kept alive with its frames: an id is not reused
            _FRAMES.move_to_end(key)
            return kept.R, kept.o
    R = np.empty((N, n + 1 + len(model.belts), 3, 3))
    o = np.empty((N, n + 1 + len(model.belts), 3))
    R[:, 0], o[:, 0] = np.eye(3), 0.0
    for i in range(1, n + 1):
        P = model.placements[i - 1]
        o[:, i] = o[:, i - 1] + R[:, i - 1] @ P[:3, 3]
        R[:, i] = (R[:, i - 1] @ P[:3, :3]) @ _turns(model.axes[i - 1], q[:, i - 1])
    for j, b in enumerate(model.belts):  # at joint b.joint's origin (its child body's), moved along its axis,
        R[:, n + 1 + j] = R[:, b.level]  # with the level body's axes
        o[:, n + 1 + j] = o[:, b.joint + 1] + b.along * (R[:, b.joint + 1] @ model.axes[b.joint])
    R.setflags(write=False)
    o.setflags(write=False)
    if key is not None:
        with _KEPT_LOCK:
            _FRAMES[key] = _Kept(model, R, o, OrderedDict())
            _BY_ROTATIONS[id(R)] = _FRAMES[key]
            while len(_FRAMES) > FRAMES_KEPT:
                del _BY_ROTATIONS[id(_FRAMES.popitem(last=False)[1].R)]
    return R, o


def _turns(axis, angle) -> np.ndarray:
    """:func:`~springlab.model.rotations.rot_axis` (the same arithmetic, bit for bit) without its checks, for a
    model's axes (unit vectors, checked when the model was made) and its checked angles: a search asks for
    thousands of frames, and the checks took a tenth of its time."""
    u = np.asarray(axis, dtype=float)
    K = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    s, c = np.sin(angle)[..., None, None], np.cos(angle)[..., None, None]
    return np.eye(3) + s * K + (1.0 - c) * (K @ K)


def remembered(R: np.ndarray, key, compute):
    """``compute()``, remembered with the frames ``R`` while :func:`body_frames` keeps them (the
    :data:`RESULTS_KEPT` most recently used per frames, keyed by ``key``, which must name everything
    ``compute`` reads besides the frames); frames not kept: computed each time. What is kept goes
    with its frames, so the memory stays bounded (about 30 MB at most for a seven-joint arm)."""
    with _KEPT_LOCK:
        kept = _BY_ROTATIONS.get(id(R))
        if kept is not None and kept.R is R and key in kept.results:
            kept.results.move_to_end(key)
            return kept.results[key]
    value = compute()
    if kept is not None and kept.R is R:
        with _KEPT_LOCK:
            kept.results[key] = value
            while len(kept.results) > RESULTS_KEPT:
                kept.results.popitem(last=False)
    return value


def _forget_kept() -> None:
    """Drop every kept frame and what was remembered with it."""
    with _KEPT_LOCK:
        _FRAMES.clear()
        _BY_ROTATIONS.clear()


@dataclass
class _Kept:
    model: RevoluteChain
    R: np.ndarray
    o: np.ndarray
    results: OrderedDict


FRAMES_KEPT = 8
"""How many results :func:`body_frames` keeps (the most recently used)."""
FRAMES_CACHED_POSES = 2_000
"""The most poses a kept result of :func:`body_frames` may hold (0.77 MB per thousand poses of a
seven-joint arm); more are computed each time."""
RESULTS_KEPT = 16
"""How many results :func:`remembered` keeps with each kept set of frames (a spring's loads at 2,000
poses are 0.14 MB)."""
_FRAMES: OrderedDict = OrderedDict()
_BY_ROTATIONS: dict = {}
_KEPT_LOCK = threading.Lock()


def _new_lock_after_fork() -> None:
    """A process forked while another thread held the lock starts with a fresh one (a pool's workers)."""
    global _KEPT_LOCK
    _KEPT_LOCK = threading.Lock()


os.register_at_fork(after_in_child=_new_lock_after_fork)


def world_points(R: np.ndarray, o: np.ndarray, body: int, point) -> np.ndarray:
    """A point fixed in a body (m, in the body's frame) in the base frame at each pose, (N, 3),
    from :func:`body_frames`' rotations and origins."""
    return o[:, body] + R[:, body] @ np.asarray(point, dtype=float)


def joint_axes(model: RevoluteChain, R: np.ndarray) -> np.ndarray:
    """Each joint's unit axis in the base frame at each pose, (N, n, 3): body i turns about axis i."""
    return np.einsum("pjab,jb->pja", R[:, 1:model.n + 1], model.axes)


def centres_of_mass(model: RevoluteChain, R: np.ndarray, o: np.ndarray) -> np.ndarray:
    """Every body's centre of mass in the base frame (m), (N, n+1, 3)."""
    return o[:, :model.n + 1] + np.einsum("pjab,jb->pja", R[:, :model.n + 1], model.com)


def check_point_springs(model: RevoluteChain, springs) -> tuple:
    """Validate springs on a model: each a :class:`~springlab.model.springs.PointSpring` whose
    bodies are the model's; returns them as a tuple."""
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    if isinstance(springs, PointSpring | str) or not hasattr(springs, "__iter__"):
        raise SpringlabError(f"springs must be a sequence of PointSpring objects, got {springs!r}")
    springs = tuple(springs)
    reach = float(np.sum(np.linalg.norm(model.placements[:, :3, 3], axis=1)))  # the arm's length, once
    for s in springs:
        if not isinstance(s, PointSpring):
            raise SpringlabError(f"expected PointSpring objects (springs between points of two bodies), got "
                                 f"{type(s).__name__}; the papers' springs convert with springlab.model.chain.point_springs")
        ends = [model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)]  # raises on a name
        if ends[0][0] == ends[1][0]:
            raise SpringlabError(f"{s.label}: both ends ride on body {model.bodies[ends[0][0]]!r} (fixed to each "
                                 "other): such a spring does no work; attach its ends to two bodies a joint separates")
        length = np.float64(reach + np.linalg.norm(s.point_a) + np.linalg.norm(s.point_b))
        with np.errstate(over="ignore"):
            if not np.isfinite(s.k * length * length):
                raise SpringlabError(f"{s.label}: k = {s.k:g} N/m with ends {length:g} m apart overflows the spring's "
                                     "energy: give k in N/m and the points in m")
    return springs
