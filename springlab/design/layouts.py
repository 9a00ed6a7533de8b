"""Spring layouts an engineer builds on a real arm, beside the search's two-point springs.

**Belts carrying a level reference** (:func:`belt_layout`; paper 001's pseudobases on a real arm).
Where the loaded joints form a planar chain (:func:`~springlab.design.structure.structure`), the body
before the first loaded joint turns about the vertical only: its axes are a level reference. A 1:1
belt (:meth:`~springlab.model.revolute.RevoluteChain.with_belt`) carries those axes to each later
loaded joint, and one zero-free-length spring per link, from a post on that level frame at the
link's joint to a point on the link, cancels the link's gravity term exactly: with the post at p
above the joint and the point at c on the link, 001 Eq. (16), K l_CA l_CB = mu g sigma, holds
when the post is along "up" (001 Eq. (13)) and c along the link's first moment sigma (001 Eq. (14)).
Each spring spans one joint, so it stays as short as its lever: between |p| - |c| and |p| + |c|.

In the plane (complex coordinates, :func:`~springlab.design.structure.planar_moments`) link k's gravity
energy is g Re(conj(i) e^{i theta_k} G_k), G_k its subsystem's first moment (001 Eq. (5), :func:`link_moments`
by the paper-001 chapter's own code) and the spring's k Re(conj(c_0) c_k e^{i theta_k}) with
c_0 = -p: their sum is constant when k conj(c_0) c_k = -g conj(i) G_k. Only the product is fixed;
this module takes |c| = :data:`LEVER` of the link's length and |p| = :data:`POST` of it: the pulley
near the link's far end, so that the coil lies along the link between it and the joint (over a pulley
block where it would be longer), and the cable's path spans 0.65 to 1.15 of the link's length. Point and post
may also turn together about the joint, which changes no length at any pose: the realisation turns them
where the pulley would otherwise come within its radius, its rope and the margin of the table the arm
stands on (:func:`turned_clear_of_table`). Where that fails, or where the link is too short for the coil
even over a pulley block, the realisation turns the spring inside out: its pulley stands at the post, on
a bracket of the level frame, with the coil beyond it along the joint's axis (away from the links), and
the cable runs from the pulley to a clamp at the point on the link (:meth:`SpringPlane.posted`). The
cable then arrives along the pulley's axis of swivel, so it wraps a quarter turn at every angle and its
path depends on the spring's length alone (a lead in the plane would have it wrap from none to half a
turn as the point sweeps about the joint); the point's and the post's lengths may trade places
(conj(p) c alone is fixed), which brings the clamp near the joint where the link sweeps down to the
table. Such a coil is held to the longer of the two links that meet at its joint. Both ends
move along the joint's axis together
(which changes no length's variation) to one side of the links, :data:`AXIAL_GAP` beyond the
farther of the two links' shapes, so that the spring and its post run beside the links.

A joint whose gravity torque stays below ``share`` of the arm's largest (default :data:`SHARE`) gets
no spring: the torque it keeps is named.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.design.buildable import STRETCH_MARGIN, Fitted, wires
from springlab.design.collision import MARGIN, mounting_plane
from springlab.design.hardware import HOOK_GAP, link_length
from springlab.design.realise import BLOCKS, MAX_PARALLEL, cable_for, coil_for, length_range
from springlab.design.search import END_GRID, RATE_DIGITS, compass_search, sig
from springlab.design.structure import PARALLEL, Structure, planar_chain, planar_moments
from springlab.errors import SpringlabError
from springlab.mechanisms.pseudobase.subsystems import subsystem_moments
from springlab.model.revolute import RevoluteChain, body_frames, joint_axes
from springlab.model.springs import PointSpring
from springlab.rounding import significant

SHARE = 0.02
"""Joints whose peak gravity torque is below this share of the arm's largest get no spring by default."""

LEVER = 0.9
"""The spring's point (its pulley) on its link lies this share of the link's length from the link's joint:
the coil lies between it and the joint, so that it stays on its own link."""

POST = 0.25
"""The post on the level frame reaches this share of the link's length above the joint."""

AXIAL_GAP = 0.02
"""m: how far beyond the farther of the two links' shapes, along the joint's axis, the spring runs."""


LEAD_TILT = np.radians(10.0)
"""rad: the coil lies along its link towards the joint, tilted this far out of the spring's plane (away
from the links): the post then never comes onto the lead's line behind the pulley, where the pulley would
have to swivel half a turn at once (the post sweeps a circle about the joint that the lead's line in the
plane would cross)."""

def on_grid(x) -> tuple:
    """Coordinates (m, or a direction's components) rounded to :data:`~springlab.design.search.END_GRID`, as
    the search keeps its ends: another CPU's round-off then moves none of them."""
    return tuple(float(np.round(v / END_GRID) * END_GRID) + 0.0 for v in x)


@dataclass(frozen=True)
class Plane:
    """What a spring's plane (:class:`SpringPlane`, :class:`springlab.design.pseudobases.Subsystem`) shares:
    its link's body ``link``, the frame its post stands on (``level``, ``level_origin``, ``level_rotation``),
    the zero pose's frames (``R0``, ``o0``) and the link's gravity term ``gG`` (N m)."""

    link: int
    level: str
    level_origin: np.ndarray
    level_rotation: np.ndarray
    R0: np.ndarray
    o0: np.ndarray
    gG: complex

    def placed(self, model: RevoluteChain, point, post, k: float) -> PointSpring:
        """The spring from ``point`` on the link to ``post`` (world, zero pose, m), rate ``k`` (N/m), its ends on
        :data:`~springlab.design.search.END_GRID` and its rate to :data:`~springlab.design.search.RATE_DIGITS`
        significant digits, as the search's: another CPU's round-off (1e-16) then moves no end and no rate,
        and draws the same figure."""
        on_link = self.R0[self.link].T @ (np.asarray(point) - self.o0[self.link])
        on_level = self.level_rotation.T @ (np.asarray(post) - self.level_origin)
        return PointSpring(model.bodies[self.link], on_grid(on_link), self.level, on_grid(on_level),
                           significant(k, RATE_DIGITS))

    def coil_room(self, c: complex, room: float, behind: float) -> float:
        """m: the room a coil has between the pulley at c (less ``behind``, m: the pulley's, the hook's and the
        rope's) and the joint, within ``room`` (m)."""
        return min(room, abs(c) - behind)


@dataclass(frozen=True)
class SpringPlane(Plane):
    """A belt spring's plane: its joint's origin (world, zero pose), the plane's axes h, up and the joint's
    axis w, the axial offset d (m), the link's body and the level frame (name, and the point its offsets
    are given from), the zero pose's frames, and g G_k (N m: the link's gravity term, complex)."""

    joint_at: np.ndarray
    h: np.ndarray
    up: np.ndarray
    w: np.ndarray
    d: float
    mast: float = 0.0  # m: the room of a coil on a bracket of the level frame at its joint: the longer link there

    def spring(self, model: RevoluteChain, c: complex, p: complex, k: float) -> PointSpring:
        """The spring from c on the link to the post p (complex offsets from the joint, in the plane), rate k
        (N/m) (:meth:`Plane.placed`)."""
        point = self.joint_at + c.real * self.h + c.imag * self.up + self.d * self.w
        post = self.joint_at + p.real * self.h + p.imag * self.up + self.d * self.w
        return self.placed(model, point, post, k)

    def posted(self, model: RevoluteChain, c: complex, p: complex, k: float) -> PointSpring:
        """:meth:`spring` with its ends swapped: end A the post p, where a bracket of the level frame carries the
        pulley and, beyond it, the coil; end B the point c on the link, where the cable is clamped."""
        s = self.spring(model, c, p, k)
        return PointSpring(s.link_b, s.point_b, s.link_a, s.point_a, s.k)

    @staticmethod
    def bracket_lead(out_b) -> tuple:
        """The lead (unit, the level frame's axes) of a pulley at the post: from the coil on the bracket beyond
        the post along the joint's axis (``out_b``, the level frame's outward axis, away from the links), back
        towards the links. The cable's path then depends on the spring's length alone: the point c sweeps
        a whole turn about the joint, and a lead in the plane would have the cable wrap from none to half a
        turn of the pulley as it does."""
        return tuple(-np.asarray(out_b, dtype=float))

    turn = True  # the compensation may turn the lever and the post (compensate_pulley)
    bracket = True  # where its link has no room or its pulley would meet the table, the coil may ride the level frame
    tilt = LEAD_TILT  # rad: the lead's out of the plane
    beside = True  # the realised ends move beside the links by the coils' width

    def prepare(self, c: complex, p: complex, k: float, rho: float) -> tuple[complex, complex, float]:
        """The spring's (c, p, k) before its pulley's compensation: unchanged (the compensation turns them)."""
        return c, p, k

    def offsets(self, spring) -> tuple[complex, complex]:
        """A spring's point and post as complex offsets (m) from the joint in the plane."""
        at = np.asarray(self.R0[self.link]) @ np.asarray(spring.point_a) + self.o0[self.link] - self.joint_at
        post = self.level_rotation @ np.asarray(spring.point_b) + self.level_origin - self.joint_at
        return complex(at @ self.h, at @ self.up), complex(post @ self.h, post @ self.up)

    def towards(self, c: complex) -> tuple:
        """The unit direction (link's frame) from the point c back towards the joint: where the coil lies."""
        return tuple(self.R0[self.link].T @ (-(c.real * self.h + c.imag * self.up)) / abs(c))

    def angles(self, R) -> np.ndarray:
        """The link's angles (rad) in the plane at the poses of ``R``: where the workspace takes it (whole
        degrees, each once)."""
        return _link_angles(self, R)


@dataclass(frozen=True)
class Layout:
    """Springs in a layout: the arm with the frames it adds (belts), the springs, and what it left out.

    :ivar model: the arm, with the layout's belts
    :ivar springs: zero-free-length springs; each one's ``link_a`` is the link it balances (a cable
        spring's coil rides there), its ``link_b`` the level frame
    :ivar leads: per spring, the direction (unit, link_a's frame) along the link from the point towards
        the joint: where the coil lies, behind a pulley at point_a
    :ivar notes: what was left out and why
    :ivar outward: per spring, the joint's axis pointing away from the links, in link_a's and in link_b's
        frames: moving both ends along it by the same length changes no length's variation, so a coil is
        set off by its own radius there (:func:`realise_layout`)
    """

    model: RevoluteChain
    springs: tuple
    leads: tuple
    notes: tuple
    outward: tuple = ()
    planes: tuple = ()  # per spring, its plane (SpringPlane): where its complex offsets are placed
    rooms: tuple = ()  # per spring, its link's length (m): the longest its coil may be in service


def axial_extent(model: RevoluteChain, body: int, R0, o0, origin, w) -> tuple[float, float]:
    """The least and largest reach (m) of a body's outline along ``w`` from ``origin`` (zero pose)."""
    pts = model.outline[body] if model.outline and len(model.outline[body]) else np.zeros((1, 3))
    along = (pts @ R0[body].T + o0[body] - origin) @ w
    return float(along.min()), float(along.max())


def without_light(model: RevoluteChain, found: Structure, share: float, q) -> Structure:
    """The structure with the loaded joints below ``share`` of the largest gravity peak counted as unloaded
    (named, with the torque they keep), its planar chain judged again on the poses ``q`` (N, n) rad: the
    SO-101's wrist roll, 0.3 % of its shoulder's peak, keeps its three lifting joints from being a planar
    chain otherwise. What the light joints' masses do to the heavier ones is then left to the check."""

    peak = np.asarray(found.peak)
    largest = float(np.max(peak))
    light = [i for i in found.loaded if peak[i] < share * largest]
    if not light:
        return found
    R, _ = body_frames(model, model.check_q(q))
    w = joint_axes(model, R)
    vertical = np.all(np.linalg.norm(np.cross(w, model.up), axis=-1) <= PARALLEL, axis=0)
    loaded = tuple(i for i in found.loaded if i not in light)
    planar, why = planar_chain(model, loaded, w, vertical, model.up)
    reasons = dict(found.reasons) | {i: f"light: at most {peak[i]:.3g} N m, {100 * peak[i] / largest:.2g} % of the "
                                        f"largest, below {100 * share:g} %: no spring, it keeps that torque"
                                     for i in light}
    return dataclasses.replace(found, unloaded=tuple(sorted((*found.unloaded, *light))), reasons=reasons,
                               loaded=loaded, planar=planar, why=why)


def link_moments(model: RevoluteChain, plane: dict) -> list:
    """Each planar link's first moment g G_k / g (kg m, complex in the plane; 0 for the ground), 001 Eq. (5)
    by :func:`springlab.mechanisms.pseudobase.subsystems.subsystem_moments`, the code the paper-001 chapter
    verifies: link k's bodies (from its joint's child to the next loaded joint; the last link carries every
    body beyond) lumped, O_{k-1} its joint's origin and O_k the next loaded joint's (the last link's own)."""

    R0, o0, bodies, joint_at, m = (plane[k] for k in ("R0", "o0", "bodies", "joint_at", "m"))
    masses, s_rows, r_rows = [], [], []
    for k in range(1, m + 1):
        carried = range(bodies[k], bodies[k + 1] if k < m else model.n + 1)
        mass = float(sum(model.mass[b] for b in carried))
        moment = sum(model.mass[b] * (o0[b] + R0[b] @ model.com[b]) for b in carried)
        ahead = np.asarray(joint_at[k + 1] if k < m else joint_at[k])
        masses.append(mass)
        s_rows.append(moment / mass - ahead if mass > 0 else np.zeros(3))
        r_rows.append(np.asarray(joint_at[k]) - ahead)
    moments = subsystem_moments(masses, s_rows, r_rows)  # 001 Eq. (5): m_k s_k - (sum_{j >= k} m_j) r_k, world
    return [0j] + [complex(v @ plane["h"], v @ plane["up"]) for v in moments]


def belt_layout(model: RevoluteChain, found: Structure, *, share: float = SHARE, q=None) -> Layout:
    """One spring per loaded link of a planar chain, each on a belt carrying the level reference to its
    joint (see the module docstring); joints below ``share`` of the largest gravity peak get none (with
    ``q``, poses (N, n) rad, a chain that is planar once they are left out is taken: :func:`without_light`).

    :raises SpringlabError: when the loaded joints are not a planar chain (no level reference), or
        ``share`` is outside [0, 1)
    """
    share = _checks.number("share", share)
    if not 0.0 <= share < 1.0:
        raise SpringlabError(f"share = {share:g}: give the share of the largest gravity peak below which a joint "
                             "gets no spring, from 0 to 1 (e.g. 0.02)")
    notes = []
    if not found.planar and q is not None:
        trimmed = without_light(model, found, share, q)
        if trimmed.planar:
            notes += [f"joint {model.joints[i]}: {trimmed.reasons[i]}" for i in found.loaded if i not in trimmed.loaded]
            found = trimmed
    if not found.planar:
        raise SpringlabError(f"the loaded joints of {model.name!r} are not a planar chain ({found.why}): no body "
                             "carries a level reference to them; use the best springs")
    plane = planar_moments(model, found)  # the plane, its links and joints
    R0, o0, h, up, w, z = (plane[k] for k in ("R0", "o0", "h", "up", "w", "z"))
    first, bodies, joint_at, nxt = (plane[k] for k in ("first", "bodies", "joint_at", "next"))
    G = link_moments(model, plane)  # 001 Eq. (5), by the code the paper-001 chapter verifies
    peak = np.asarray(found.peak)
    largest = float(np.max(peak))
    out, leads, outward, planes, rooms = model, [], [], [], []
    springs = []
    for k, joint in enumerate(found.loaded, start=1):
        if peak[joint] < share * largest:
            notes.append(f"joint {model.joints[joint]} carries {peak[joint]:.3g} N m at most, "
                         f"{100 * peak[joint] / largest:.2g} % of the largest ({largest:.3g} N m), below "
                         f"{100 * share:g} %: no spring, and it keeps that torque")
            continue
        W = -model.g * np.conj(1j) * G[k]  # the spring's k conj(c_0) c_k
        link = bodies[k]
        far = nxt[k] if nxt[k] is not None else o0[link] + R0[link] @ model.com[link]
        length = float(np.linalg.norm(np.asarray(far) - joint_at[k]))
        if nxt[k] is None and abs(W) > 0 and model.outline and len(model.outline[link]):  # the last link: as far as
            u = W / (1j * abs(W))  # its shape reaches along the spring's lever (c's direction), if beyond its centre
            towards = u.real * h + u.imag * up
            pts = model.outline[link] @ R0[link].T + o0[link] - joint_at[k]
            length = max(length, float(np.max(pts @ towards)))
        if length <= 0 or abs(W) == 0:
            notes.append(f"joint {model.joints[joint]}: its link has no length to lever on: no spring")
            continue
        r_b, r_a = LEVER * length, POST * length
        kappa = abs(W) / (r_a * r_b)
        p = 1j * r_a  # the post, straight up from the joint
        c = W / (kappa * np.conj(-p))  # kappa conj(c_0) c_k = W, c_0 = -p
        lo_p, hi_p = axial_extent(model, link - 1, R0, o0, joint_at[k], w)
        lo_c, hi_c = axial_extent(model, link, R0, o0, joint_at[k], w)
        hi, lo = max(hi_p, hi_c), min(lo_p, lo_c)
        side = 1.0 if hi <= -lo else -1.0  # the nearer side of the two links
        d = hi + AXIAL_GAP if side > 0 else lo - AXIAL_GAP
        if k == 1:  # the level body itself carries the first link's post
            level, level_origin = model.bodies[first], o0[first]
        else:
            out = out.with_belt(model.joints[joint], model.bodies[first])
            level, level_origin = out.belts[-1].name, joint_at[k]
        carrier = (float(np.linalg.norm(np.asarray(joint_at[k]) - joint_at[k - 1])) if k > 1 else
                   link_length(model, first))  # the link before the joint (the base: unbounded)
        plane = SpringPlane(link, level, np.asarray(level_origin), R0[first], R0, o0, complex(model.g * G[k]),
                            joint_at=np.asarray(joint_at[k]), h=h, up=up, w=w, d=float(d), mast=max(length, carrier))
        planes.append(plane)
        rooms.append(length)
        springs.append(plane.spring(out, c, p, kappa))
        towards = R0[link].T @ (-(c.real * h + c.imag * up))
        leads.append(tuple(towards / np.linalg.norm(towards)))
        outward.append((R0[link].T @ (side * w), R0[first].T @ (side * w)))
    return Layout(out, tuple(springs), tuple(leads), tuple(notes), tuple(outward), tuple(planes), tuple(rooms))


TABLE_SLACK = 0.005
"""m: what a spring's pulley and post keep above the mounting plane at every pose of the design's check, beyond
the pulley's radius, its rope and the clearance margin: the poses the design's audit adds lie between them."""


def _heights(plane: SpringPlane, R, o, floor: float) -> tuple:
    """Per pose of ``R``, ``o``: the joint's height (m) above the mounting plane ``floor`` and the heights of
    the link's in-plane axes h and up (a point c on the link is zero + Re(c) z_h + Im(c) z_u high)."""
    link, up = plane.link, plane.up
    base = plane.R0[link].T @ (np.asarray(plane.joint_at) - plane.o0[link])  # the joint, in the link's frame
    zero = np.einsum("pij,j->pi", R[:, link], base) @ up + o[:, link] @ up - floor  # its height, per pose
    z_h = np.einsum("pij,j->pi", R[:, link], plane.R0[link].T @ plane.h) @ up  # the plane's axes' heights
    z_u = np.einsum("pij,j->pi", R[:, link], plane.R0[link].T @ up) @ up
    return zero, z_h, z_u


def table_room(plane: SpringPlane, R, o, floor: float, c: complex, p: complex) -> tuple[float, float]:
    """The least heights (m) above the mounting plane ``floor`` of a spring's point c on the link and of its post p
    on the level frame (complex, m, from the joint in the plane) over the poses of ``R``, ``o``."""
    zero, z_h, z_u = _heights(plane, R, o, floor)
    return float(np.min(zero + c.real * z_h + c.imag * z_u)), float(np.min(zero) + p.imag)


def turned_clear_of_table(plane: SpringPlane, R, o, floor: float, c: complex, p: complex, room: float,
                          post_room: float | None = None) -> complex:
    """The turn (a unit complex number) of a spring's point c and post p (complex, m, from the joint in the
    plane) about the joint that keeps the point ``room`` (m) and the post ``post_room`` (default ``room``)
    above the mounting plane at every pose of ``R``, ``o``: none where they already are, else the least turn
    that does, else the one that keeps them highest (on a half-degree grid). Turning both together changes
    no length at any pose, so neither the balance nor the pulley's compensation: only conj(p) c is fixed
    (001 Eq. (16)). Where a link reaches down to the table, a pulley at its far end would otherwise run
    into the table beside it."""
    zero, z_h, z_u = _heights(plane, R, o, floor)
    turns = np.exp(1j * np.radians(np.concatenate([np.arange(0, 180.5, 0.5), -np.arange(0.5, 180, 0.5)])))
    point = c * turns  # (angles,)
    heights = zero[:, None] + point.real[None] * z_h[:, None] + point.imag[None] * z_u[:, None]
    post_room = room if post_room is None else post_room
    low = np.minimum(heights.min(axis=0) - room, zero.min() + (p * turns).imag - post_room)  # above what each needs
    keys = [sig(v) for v in low]  # the search's key: round-off decides no turn
    fits = [i for i in np.argsort(np.abs(np.angle(turns)), kind="stable") if keys[i] >= 0]
    return complex(turns[fits[0] if fits else int(np.argmax(keys))])


REFIT = 0.3
"""A pulley's compensation moves the lever and the post by at most this share of their lengths (the coil's
stroke and the spring's proportion stay the layout's)."""

FIT_STEPS = 1500
"""The most steps the pulley compensation's compass search takes (each tries +- its step on every variable,
from 0.05 down to 1e-5 of the variables' units)."""

FIT_PULL = 1e-3
"""The pulley compensation's pull towards the point-pulley design, per unit of its variables (rate and
lengths relative to theirs, angles in rad): the torque alone leaves a shallow valley of equally good
fits, where another CPU's round-off would land elsewhere."""

ANGLES = 360
"""The link's angles (a full turn) a pulley's compensation is fitted on."""


def _cable_terms(x, rho: float, theta: np.ndarray, gG: complex,
                 tilt: float = LEAD_TILT, at_post: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The link's gravity energy plus its cable spring's (J) at the link's angles ``theta`` (rad): the
    spring k (x[0]) from a pulley of radius ``rho`` centred at c = x[1] + i x[2] on the link (its cable
    arriving along the lead, ``tilt`` (rad, default :data:`LEAD_TILT`) out of the plane from c's direction: from the coil on the
    joint's side) to the post p = x[3] + i x[4]; route 2's path over the pulley
    (:func:`springlab.energy.geometry.cable_geometry`: the angle alpha between the lead and B - A). ``x``
    may hold several designs, (M, 5): the energies are then (M, len(theta)). With ``at_post`` the pulley is
    at the post instead, on a bracket of the level frame that carries the coil beyond it along the joint's
    axis, away from the links: the cable arrives along the axis, the pulley swivels about it and wraps a
    quarter turn, alpha = pi / 2 at every angle, and runs to the point c on the link. Returns the energy and
    its derivative dV/dtheta (N m, the torque) in closed form: a finite difference would lose some ten digits
    to cancellation, and the compass search compares its values to nine."""
    x = np.asarray(x, dtype=float)
    k, c, p = x[..., 0, None], (x[..., 1] + 1j * x[..., 2])[..., None], (x[..., 3] + 1j * x[..., 4])[..., None]
    turn = np.exp(1j * theta)
    if at_post:  # the pulley at p, fixed in the plane; the cable runs from it to c on the link
        D = turn * c - p
        dD = 1j * turn * c  # d/dtheta
        along = d_along = np.zeros(np.broadcast_shapes(D.shape))  # the lead along the joint's axis: alpha = pi / 2
    else:  # the pulley at c, on the link; the cable runs from it to the post p
        A = turn * c
        D = p - A
        dD = -1j * A
        u = turn * c / np.abs(c)  # the lead's direction in the plane, turning with the link
        along = np.cos(tilt) * np.real(np.conj(u) * D)
        d_along = np.cos(tilt) * np.real(np.conj(1j * u) * D + np.conj(u) * dD)
    L = np.abs(D)
    dL = np.real(np.conj(D) * dD) / L
    ratio = np.clip(along / L, -1.0, 1.0)
    alpha = np.arccos(ratio)
    d_ratio = (d_along * L - along * dL) / L**2
    d_alpha = -d_ratio / np.sqrt(np.maximum(1 - ratio**2, 1e-300))
    s = np.clip(rho / L, -1, 1)
    straight = np.sqrt(np.maximum(L**2 - rho**2, 0.0))
    path = rho * (alpha + np.arcsin(s)) + straight
    d_path = rho * d_alpha - rho * (rho / L**2) * dL / np.sqrt(np.maximum(1 - s**2, 1e-300)) + L * dL / np.maximum(
        straight, 1e-300)
    gravity = np.real(np.conj(1j) * turn * gG)
    d_gravity = np.real(np.conj(1j) * 1j * turn * gG)
    return gravity + 0.5 * k * path**2, d_gravity + k * path * d_path


def compensate_pulley(plane: SpringPlane, c: complex, p: complex, k: float, rho: float,
                      angles=None, *, turn: bool = True, tilt: float = LEAD_TILT,
                      at_post: bool = False, fixed_rate: bool = False) -> tuple[complex, complex, float]:
    """The offsets and rate (c, p, k) that hold the link best with a pulley of radius ``rho`` (m):
    the least mean square of the torque dV/dtheta (in closed form) over the link's angles ``angles`` (rad;
    default a full turn, :data:`ANGLES`; its gravity term and its
    spring's energy depend on that angle alone), with a small pull (:data:`FIT_PULL`) towards the
    point-pulley design it starts from, the lever's and the post's lengths within :data:`REFIT` of theirs,
    their directions and the rate free; the lead stays on the line from the pulley to the joint. The
    ``turn=False`` keeps both directions (only the rate and the two lengths move: paper 001's post stays on
    the vertical and the point on sigma, 001 Eqs. 13-14); ``tilt`` is the lead's out of the plane (rad);
    ``at_post`` puts the pulley at the post, its coil on a bracket beyond it along the joint's axis (the
    cable's wrap is then a quarter turn at every angle); ``fixed_rate`` keeps the rate (a stock part's: the
    lengths and directions alone move, which 001 Eq. (16) trades against it). The
    search is a compass search that compares to 9 significant digits
    (:func:`springlab.design.search.compass_search`), so another CPU's round-off takes no other step.
    Returns them unchanged for rho = 0."""
    if rho == 0:
        return c, p, k

    theta = np.linspace(0.0, 2 * np.pi, ANGLES, endpoint=False) if angles is None else np.asarray(angles, float)

    def cartesian(v):  # (k / k0, |c| / |c0|, arg c, |p| / |p0|, arg p), (5,) or (M, 5)
        v = np.asarray(v, dtype=float)
        c_ = v[..., 1] * abs(c) * np.exp(1j * v[..., 2])
        p_ = v[..., 3] * abs(p) * np.exp(1j * v[..., 4])
        return np.stack([v[..., 0] * k, c_.real, c_.imag, p_.real, p_.imag], axis=-1)

    def torque(v):  # dV/dtheta over |g G| at each angle, (M, len(theta)) for designs v (M, 5)
        return _cable_terms(cartesian(v), rho, theta, plane.gG, tilt, at_post)[1] / abs(plane.gG)

    start = np.array([1.0, 1.0, np.angle(c), 1.0, np.angle(p)])
    swing = np.pi if turn else 0.0
    rate = (1.0, 1.0) if fixed_rate else (0.5, 2.0)
    lo = np.array([rate[0], 1.0 - REFIT, start[2] - swing, 1.0 - REFIT, start[4] - swing])
    hi = np.array([rate[1], 1.0 + REFIT, start[2] + swing, 1.0 + REFIT, start[4] + swing])

    def value(trials):  # the compass search maximises: minus the torques' mean square, and a pull to the start
        trials = np.atleast_2d(trials)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # a cable's end on its pulley: no fit
            out = -(np.mean(torque(trials) ** 2, axis=1) + FIT_PULL**2 * np.sum((trials - start) ** 2, axis=1))
        return np.where(np.isfinite(out), out, -np.inf)

    v, _ = compass_search(value, start, lo, hi, max_steps=FIT_STEPS)
    x = cartesian(v)
    return complex(x[1], x[2]), complex(x[3], x[4]), float(x[0])


def _link_angles(plane: SpringPlane, R) -> np.ndarray:
    """The link's angles (rad) in its spring's plane at the poses of ``R`` (body rotations, (N, bodies, 3, 3)),
    from the zero pose's, on a whole-degree grid (each once): where the workspace takes it."""
    v = np.einsum("pij,j->pi", R[:, plane.link], plane.R0[plane.link].T @ plane.h)
    theta = np.degrees(np.arctan2(v @ plane.up, v @ plane.h))
    return np.radians(np.unique(np.round(theta)))


SCALES = (0.9, 0.8, 0.7, 0.6, 0.5)
"""Where a spring on a level frame (a belt layout's, or a pseudobase layout's first) needs coils side by
side, or its coil does not fit or its pulley meets the table, the realisation tries its point's length
scaled by each of these and its post's by the inverse, the pulley on its link and on the bracket
(001 Eq. (16) fixes their product alone): a pulley nearer its joint stays higher above the table, and the
cable's stroke changes with the lengths."""


def _better(one: dict, other: dict) -> bool:
    """Whether realisation ``one`` beats ``other``: it fits and clears where the other does not, or meets more
    of the two, or as many with fewer coils side by side."""
    def key(got):
        return got["fits"] and got["clear"], got["fits"] + got["clear"], -got["parallel"]
    return key(one) > key(other)


STOCK_TRIES = 6
"""How many of a spring's stock candidates (:func:`stock_candidates`, nearest first) are realised in full, the
pulley compensated, in turn until one fits and clears."""

STOCK_SCALE = (0.5, 2.0)
"""The point's and the post's lengths may each be scaled within these bounds to suit a stock part's rate (the
point no farther than its link's room)."""


def stock_candidates(catalogue, rate: float, c: complex, p: complex, theta, room: float, reach: float,
                      behind: float, pulley: float | None = None) -> tuple[list, str]:
    """Stock parts for a cable spring of rate ``rate`` (N/m) from the point c to the post p (complex, m, in its
    plane) over the link's angles ``theta`` (rad): for each part, block ratio
    (:data:`~springlab.design.realise.BLOCKS`) and count side by side (up to
    :data:`~springlab.design.realise.MAX_PARALLEL`) whose rate along the cable, count k / ratio^2, balances
    with the point's and the post's lengths scaled by a and b (a b = rate / that rate, 001 Eq. (16); each within :data:`STOCK_SCALE`,
    the point no farther than ``reach``, m) and whose part, with a point pulley, stays stretched past its free
    length (:data:`~springlab.design.buildable.STRETCH_MARGIN`), within its catalogue's largest extension and
    load, and no longer than ``room`` (m, less ``behind`` for a block's sheave; with ``pulley``, m, a pulley on
    the link: no longer than the scaled point's length less that either). Returns them, the fewest parts
    first, then the least change of the lengths, then the least block: (part, ratio, count, a, b), and why the
    others failed (the commonest reason)."""
    parts = list(catalogue)
    k = np.array([q.rate for q in parts])
    Fi = np.array([q.initial_tension for q in parts])
    L0 = np.array([q.free_length for q in parts])
    Lmax = np.array([q.max_extended_length for q in parts])
    Fmax = np.array([q.max_load for q in parts])
    turn = np.exp(1j * np.asarray(theta, dtype=float))
    lo, hi = STOCK_SCALE
    found, reasons = [], {}
    for count in range(1, MAX_PARALLEL + 1):
        for ratio in BLOCKS:
            scale = rate / (count * k / ratio**2)  # a b
            a = np.clip(np.sqrt(scale), lo, min(hi, reach / abs(c)))
            b = scale / a
            path = np.abs(p * b[:, None] - c * a[:, None] * turn[None])
            short, long = path.min(axis=1), path.max(axis=1)
            longest = L0 + (long - ratio * Fi / k) / ratio
            checks = (("the lengths would change past their bounds", (b >= lo) & (b <= hi) & (a * abs(c) <= reach)),
                      ("their initial tension would leave them slack", ratio * Fi / k <= STRETCH_MARGIN * short),
                      ("stretched past their largest extension", longest <= Lmax),
                      ("pulling past their largest load", Fi + k * (longest - L0) <= Fmax),
                      ("too long for the room", longest <= (room if pulley is None else np.minimum(
                          room, a * abs(c) - pulley)) - (behind if ratio > 1 else 0.0)))
            ok = np.ones(len(parts), dtype=bool)
            for why, passes in checks:
                reasons[why] = reasons.get(why, 0) + int(np.sum(ok & ~passes))
                ok &= passes
            found += [((count, sig(abs(np.log(scale[i]))), ratio, i), (parts[i], ratio, count, float(a[i]),
                                                                       float(b[i]))) for i in np.flatnonzero(ok)]
    found.sort(key=lambda item: item[0])
    why = max(reasons, key=reasons.get) if reasons else "the catalogue is empty"
    return [item[1] for item in found], why


def _stocked(got: dict, attempt, catalogue, plane, R, before=None) -> dict:
    """A custom realisation ``got`` made of stock parts where some fit (:func:`stock_candidates`): the first of
    the nearest :data:`STOCK_TRIES` candidates that, realised in full by ``attempt`` with the custom coil's
    placing (the pulley compensated at the parts' rate), fits and clears; else ``got``, saying why none did.
    ``before``: (part number, block ratio) an earlier round chose, tried first and kept where it fits and
    clears again (the design's rounds for the springs' own mass change the rates a little)."""
    at_post, swap = got["choice"]
    rho = got["rho"]
    d = got["chosen"].diameter if rho > 0 else 0.0
    on_link = None if at_post else rho + HOOK_GAP + d  # the coil between the pulley and the joint
    tries, why = stock_candidates(catalogue, got["k0"], got["c0"], got["p0"], plane.angles(R),
                                   got["fits_in"] if at_post else got["reach"], got["reach"], 2 * (rho + d), on_link)
    again = [t for t in tries if before is not None and (t[0].part_number, t[1]) == tuple(before)][:1]
    for stock in again + tries[:STOCK_TRIES]:  # the earlier round's part, then the nearest: the first that fits
        try:
            other = attempt(at_post, swap, stock)
        except SpringlabError:
            continue
        if "left" not in other and other["fits"] and other["clear"]:
            return other
    why = why if not tries else (f"none of the {min(len(tries), STOCK_TRIES)} nearest choices (part, block, side by "
                                 "side) fits and clears once its pulley is compensated")
    return got | {"unstocked": f"no part of the catalogue fits: {why}"}


def realise_layout(layout: Layout, q, *, material: str = "auto", pulley_radius: float | None = 0.0,
                   cable=None, margin: float = MARGIN, prefer=None, catalogue=None) -> tuple:
    """Each spring of a layout as a coil on its link behind a pulley at its point, the cable running to the
    post (:func:`springlab.design.buildable.cable_spring`; up to
    :data:`~springlab.design.realise.MAX_PARALLEL` side by side where one wire is too weak, and over a pulley
    block, :data:`~springlab.design.realise.BLOCKS`, where the coil would reach past its joint). Returns the realised springs,
    their kinds, their coils (:class:`~springlab.design.buildable.Fitted`: the coil, the cable's paths, the
    block and the cable) and the index of the layout's spring each realises, as
    :func:`~springlab.design.realise.realise_springs` does; the coil lies along the link towards the joint
    (the cable arrives from there).

    The cable (:func:`springlab.design.cables.choose_cable`, or ``cable``) carries the spring's largest pull
    with the stated safety factor; the pulley is sized to it (``pulley_radius=None``: the rope maker's
    ratio) or given (m; 0: a point pulley, no hardware). With a pulley each spring's lever, post and rate
    are first re-fitted for it (:func:`compensate_pulley`), and the cable chosen again for the re-fitted
    pull. Each spring's pulley and post are turned about their joint where that keeps the pulley ``margin`` (m)
    clear of the mounting plane (:func:`turned_clear_of_table`).

    Where the coil has no room on its link, or the pulley meets the table, the pulley moves to the post, on a
    bracket of the level frame (the module's docstring); where a spring still needs coils side by side, or
    fits nowhere, its point's and post's lengths are scaled in inverse proportion (:data:`SCALES`), on the
    link and on the bracket, and the first placing that fits and clears with the fewest coils is kept. Each
    coil records its placing (:attr:`~springlab.design.buildable.Fitted.choice`); ``prefer`` maps a layout
    spring's index to an earlier round's (placing, coils side by side[, (stock part number, block)]), tried
    first and kept where it does as well again, fitting and clearing as it did with no more coils (the design's
    rounds for the springs' own mass).

    With a ``catalogue`` (:class:`springlab.design.catalogue.Catalogue`) each spring is then made of stock
    parts where some fit (:func:`stock_candidates`, :data:`STOCK_TRIES`): the placing found for its custom
    coil is kept, and the point's and the post's lengths are scaled so that the parts' rate balances the link
    (001 Eq. (16): the rate times the two lengths is fixed), the pulley compensated with that rate held.
    Where none fits, the custom coil stays and its kind says why.

    :raises SpringlabError: naming a spring no stocked wire realises or no stocked cable carries, or a given
        cable that a given pulley is too small for
    """

    model = layout.model
    q = model.check_q(q)
    given = None if pulley_radius is None else _checks.positive("pulley_radius", pulley_radius, allow_zero=True,
                                                                unit="m")
    margin = _checks.positive("margin", margin, allow_zero=True, unit="m")
    if cable is not None and given is not None and given > 0 and not cable.fits(given):
        raise SpringlabError(f"cable {cable.name}: a pulley of {1e3 * given:g} mm is too small for it (the rope maker's "
                             f"D/d of {cable.ratio:g} asks for {1e3 * cable.pulley_radius:g} mm); give a larger "
                             "--pulley-radius or a finer --cable")
    prefer = {} if prefer is None else dict(prefer)
    R, o = body_frames(model, q)
    floor = mounting_plane(model)
    realised, kinds, coils, origins = [], [], [], []
    rooms = layout.rooms or (np.inf,) * len(layout.springs)
    rows = zip(layout.springs, layout.leads, layout.outward, layout.planes, rooms, strict=True)
    for index, (ideal, ideal_towards, (out_a, out_b), plane, room) in enumerate(rows):
        def attempt(at_post: bool, swap: bool | float = False, stock=None, ideal=ideal, ideal_towards=ideal_towards,
                    out_a=out_a, out_b=out_b, plane=plane, room=room, index=index) -> dict:
            """The spring realised with its pulley on its link (or ``at_post``: on the level frame's bracket;
            ``swap``: with the point's and the post's lengths swapped, the cable's clamp near the joint; a number:
            the point's length scaled by it and the post's by its inverse). ``stock``: (part, ratio, count, a, b),
            ``count`` of a catalogue's part side by side over a ``ratio``:1 block, the point's length scaled by
            ``a`` and the post's by ``b`` so that their rate along the cable, count part.rate / ratio^2,
            balances the link (001 Eq. (16)); the compensation keeps that rate."""
            rate = ideal.k if stock is None else stock[2] * stock[0].rate / stock[1] ** 2
            pull = rate * length_range(model, ideal, R, o)[1]
            chosen = cable
            for _ in range(4):  # the cable for the pull, its pulley, the spring re-fitted for it, and again
                if chosen is None or chosen.working < pull:
                    chosen = cable_for(pull, given)
                rho = chosen.pulley_radius if given is None else given
                s, towards = ideal, ideal_towards
                c0, p0 = plane.offsets(ideal)
                if swap is True:  # conj(p) c is what 001 Eq. (16) fixes: |c| and |p| trade places
                    c0, p0 = c0 * abs(p0) / abs(c0), p0 * abs(c0) / abs(p0)
                elif swap:  # or their lengths move in inverse proportion
                    c0, p0 = c0 * swap, p0 / swap
                if stock is not None:  # 001 Eq. (16): K l_CA l_CB fixed, K the parts' rate
                    c0, p0 = c0 * stock[3], p0 * stock[4]
                    s = plane.posted(model, c0, p0, rate) if at_post else plane.spring(model, c0, p0, rate)
                    towards = plane.towards(c0)
                c, p = c0, p0
                d = chosen.diameter if rho > 0 else 0.0
                need = rho + d + margin + TABLE_SLACK  # a pulley's (and its rope's) room above the table
                clamp = d + margin + TABLE_SLACK  # a cable's clamp's
                if rho > 0:  # the pulley adds k rho (its wrap's change): c, p and k re-fitted for it
                    try:
                        c, p, k = plane.prepare(c0, p0, s.k, rho)
                    except SpringlabError as why:
                        return {"left": f"not realised: spring S{index + 1} ({ideal.label}, k = {ideal.k:.4g} N/m): "
                                        f"{why}"}
                    if stock is not None and k != rate:
                        return {"left": "its post would be lowered for the pulley, which changes the rate"}
                    c, p, k = compensate_pulley(plane, c, p, k, rho, plane.angles(R), turn=plane.turn,
                                                tilt=plane.tilt, at_post=at_post, fixed_rate=stock is not None)
                    if plane.turn:  # clear of the table: the pulley and its rope, and the cable's clamp, with the margin
                        turn = (turned_clear_of_table(plane, R, o, floor, c, p, clamp, need) if at_post else
                                turned_clear_of_table(plane, R, o, floor, c, p, need))
                        c, p = c * turn, p * turn
                    s = plane.posted(model, c, p, k) if at_post else plane.spring(model, c, p, k)
                    towards = plane.towards(c)
                if at_post:  # from the coil on the bracket beyond the post, towards the joint
                    lead = plane.bracket_lead(out_b)
                else:  # from the coil, on the joint's side and out of the plane, the cable arrives at the pulley
                    lead = tuple(-np.cos(plane.tilt) * np.asarray(towards) - np.sin(plane.tilt) * np.asarray(out_a))
                led = PointSpring(s.link_a, s.point_a, s.link_b, s.point_b, s.k, pulley_radius=rho,
                                  lead=lead if rho > 0 else None)
                lengths = length_range(model, led, R, o)
                behind = rho + HOOK_GAP + d
                fits_in = plane.mast - behind if at_post else plane.coil_room(c0 if rho == 0 else c, room, behind)
                if stock is None:
                    found = coil_for(s.k, lengths, fits_in, material, block=2 * (rho + d))
                else:  # the part at its free length where the path is ratio F_i / k: the force is k / ratio^2 the path
                    part, ratio, count = stock[:3]
                    longest = part.free_length + (lengths[1] - ratio * part.initial_tension / part.rate) / ratio
                    found = part.spring(max(longest, part.free_length)), ratio, count
                if found[0] is None:
                    raise SpringlabError(f"{s.label} (k = {s.k:.4g} N/m): no stocked {' or '.join(wires(material))} wire realises it, "
                                         f"even side by side or over a pulley block ({found[1]})")
                coil, ratio, parallel = found
                pull = s.k / parallel * lengths[1]  # each side-by-side spring has its own cable
                if chosen.working >= pull or cable is not None:
                    break
            clear = 0.0  # a pseudobase's spring: its table is the clearance check's
            if plane.turn:
                point, post = table_room(plane, R, o, floor, c, p)
                clear = sig(min(post - need, point - clamp) if at_post else min(point, post) - need)
            fits = coil.max_length <= fits_in - (2 * (rho + d) if ratio > 1 else 0.0)
            if stock is not None:  # within the vendor's limits, and stretched past its free length everywhere
                fits = fits and not coil.problems() and (
                    ratio * coil.initial_tension / coil.rate <= STRETCH_MARGIN * lengths[0])
            return {"s": s, "lead": lead, "rho": rho, "chosen": chosen, "lengths": lengths, "coil": coil,
                    "ratio": ratio, "parallel": parallel, "room": fits_in if at_post else None,
                    "fits": fits, "clear": clear >= 0, "choice": (at_post, swap), "stock": stock,
                    "c0": c0, "p0": p0, "k0": rate, "fits_in": fits_in, "reach": room}

        got = None
        if index in prefer:  # the placing the previous round searched for, where it does as well again (fits
            (at_post, swap, fits, clear), parallel, *_ = prefer[index]  # and clears as it did, with no more coils):
            try:  # the arm carries the hardware it was designed for, and the search is not run again
                got = attempt(at_post, swap)
            except SpringlabError:
                got = None
            if got is not None and ("left" in got or _better({"fits": fits, "clear": clear, "parallel": parallel}, got)):
                got = None
        if got is None:
            got = attempt(False)
            if "left" not in got and given != 0 and plane.bracket and not (got["fits"] and got["clear"]):
                for swap in (False, True):  # its link has no room for the coil, or the pulley meets the table
                    other = attempt(True, swap)
                    if other["fits"] + other["clear"] > got["fits"] + got["clear"]:
                        got = other
                    if got["fits"] and got["clear"]:
                        break
            if "left" not in got and given != 0 and plane.bracket:
                # fewer coils side by side, or any that fit and clear: the point nearer its joint, the post farther
                tries = [(at_post, scale) for scale in SCALES for at_post in (False, True)]
                for at_post, scale in tries:
                    if got["fits"] and got["clear"] and got["parallel"] == 1:  # none can do better than one coil
                        break
                    try:
                        other = attempt(at_post, scale)
                    except SpringlabError:  # its cable's end meets the pulley, or no wire: not this one
                        continue
                    if "left" not in other and _better(other, got):
                        got = other
        if catalogue is not None and "left" not in got:
            before = prefer[index][2] if len(prefer.get(index, ())) > 2 else None  # an earlier round's part
            got = _stocked(got, attempt, catalogue, plane, R, before)
        left = got.get("left")
        if left is not None:  # no room for its pulley: the design leaves it out and says so
            realised.append(None)
            kinds.append(left)
            coils.append(None)
            origins.append(index)
            continue
        s, lead, rho, chosen, lengths = (got[key] for key in ("s", "lead", "rho", "chosen", "lengths"))
        coil, ratio, parallel, bracket = got["coil"], got["ratio"], got["parallel"], got["room"]
        choice = (*got["choice"], got["fits"], got["clear"])  # the placing, and how well it did
        shift = parallel * coil.outer_diameter if plane.beside else 0.0  # beside the links by the coils' width
        out_a, out_b = layout.outward[index] if bracket is None else layout.outward[index][::-1]
        s = PointSpring(s.link_a, on_grid(np.asarray(s.point_a) + shift * out_a), s.link_b,
                        on_grid(np.asarray(s.point_b) + shift * out_b), s.k)
        lead = on_grid(lead)  # on the same grid: another CPU's round-off moves nothing
        k = s.k / parallel
        tension = coil.initial_tension / ratio  # along the cable: the block divides the coil's pull
        block = (" on a bracket of the level frame" if bracket is not None else "") + (
            f", with a {ratio}:1 pulley block" if ratio > 1 else "")
        stock = got.get("stock")
        single = stock is None and parallel > 1 and coil_for(s.k, lengths, np.inf, material)[0] is not None
        if stock is not None:
            block += f", stock part {stock[0].part_number}"
        elif got.get("unstocked"):
            block += f", custom-wound ({got['unstocked']})"
        for m in range(parallel):
            realised.append(PointSpring(s.link_a, s.point_a, s.link_b, s.point_b, k, tension / k, tension, rho,
                                        lead if rho > 0 else None))
            kinds.append("cable over a pulley" + block + (f" ({m + 1} of {parallel} side by side"
                                                          + (", so that each coil fit its link)" if single else ")")
                                                          if parallel > 1 else ""))
            coils.append(Fitted(coil, lengths, ratio, chosen if rho > 0 else None, bracket, choice))
            origins.append(index)
    return tuple(realised), tuple(kinds), tuple(coils), tuple(origins)
