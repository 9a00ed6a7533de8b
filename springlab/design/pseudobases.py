"""Paper 001's pseudobases on a spatial arm: one spring per loaded link, whatever its joints' axes.

Where the loaded joints are not a planar chain (the Panda's upper-arm roll, the Z1's wrist yaw), no belt
carries a level reference across them; paper 001 carries one by spatial parallelogram RSSR modules
(Section 4, Fig. 6), which keep a vertical line vertical on a *pseudobase* jointed to each link at a point
C_i. The arm's gravity energy is a sum of rotational subsystems, one per link, each a first moment fixed in
its link (001 Eq. 5, :func:`springlab.mechanisms.pseudobase.subsystems.subsystem_moments`, the code the
paper-001 chapter verifies), so each one is balanced alone, like a single-link equilibrator (001 Eqs. 9-18):
a zero-free-length spring from A_i, ``l_CA`` above C_i on the pseudobase (001 Eq. 13), to B_i, ``l_CB``
from C_i along the subsystem's moment sigma_i on the link (001 Eq. 14), with K l_CA l_CB = mu g sigma
(001 Eq. 16).

C_i may be any point of link i (001 Section 3); here it is a point of joint i's axis (a point of the link
before it too, so that the moments chain, 001 Eq. 2), moved along the axis by
:data:`~springlab.design.layouts.AXIAL_GAP` beyond the two links' shapes, on the nearer side, so that the
spring and its post run beside the links. (Beside every link that sweeps past within the spring's reach of
the axis over the workspace, it would clear them: on the Panda, the Z1, the Kinova and the xArm7 that puts
the shoulder's spring 0.25 to 0.7 m to the side of a 0.1 m wide arm, out of all proportion; the design
names the collisions instead.) The part of a subsystem's moment along its joint's axis turns with the link before it alone:
it is handed to that link's subsystem, so that a joint that carries little needs no spring (its term then
left is the torque it keeps, named). The first loaded link's post stands on the body before it, which turns
about the vertical alone; the others' stand on a pseudobase
(:meth:`~springlab.model.revolute.RevoluteChain.with_pseudobase`), or a belt's frame where every joint
between turns about a parallel axis (:meth:`~springlab.model.revolute.RevoluteChain.with_belt`).

Where the link turns in one plane of its post's frame (the first loaded link, on the level body, or one a
belt carries to across parallel joints), its spring is laid out as the belt layout's
(:class:`~springlab.design.layouts.SpringPlane`: its lead tilted out of the plane, its pulley compensated
with the lever and the post free to turn). Elsewhere each spring is a coil along its link between C_i and a pulley at B_i (:data:`PULLEY` of the link's reach
along sigma_i from C_i), its cable over the pulley to A_i (:data:`POST` above C_i)
(:func:`springlab.design.layouts.realise_layout`): the cable arrives at the pulley along sigma_i, so its
path, like the gravity term, depends on the angle phi between sigma_i and the vertical alone, and the pulley
is compensated for in that plane (the lever and the post keep their directions, 001 Eqs. 13-14; the rate and
their lengths move). Where sigma_i points straight up or down the post lies on that line, and the pulley,
which swivels about it to hold the post in its plane, must turn half a turn at once: the design's audit
looks for such poses in the workspace and flags them (a planar chain's belts tilt the lead out of the plane
instead; a spatial link's lead cannot leave every plane its post sweeps).

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.design.layouts import (
    AXIAL_GAP,
    SHARE,
    Layout,
    Plane,
    SpringPlane,
    axial_extent,
    without_light,
)
from springlab.design.structure import PARALLEL, Structure, zero_pose
from springlab.errors import SpringlabError
from springlab.mechanisms.pseudobase.subsystems import subsystem_moments
from springlab.model.revolute import RevoluteChain
from springlab.model.springs import PointSpring

PULLEY = 0.9
"""The pulley B_i lies this share of the link's reach along sigma_i from C_i (001 Eq. 14's l_CB): its coil lies
between it and C_i, along the link."""

POST = 0.25
"""The post A_i stands this share of the link's reach above C_i (001 Eq. 13's l_CA)."""

PULLEY_CLEAR = 2.0
"""The cable's free run from the pulley to the post is at least this many pulley radii (|A - B| >= l_CB - l_CA):
where a pulley is too large for it, the post is lowered (and the rate raised, 001 Eq. 16)."""


@dataclass(frozen=True)
class Subsystem(Plane):
    """One link's subsystem and its spring's plane: C (world, zero pose, m), the moment's direction ``ghat``
    (world, zero pose) and in the link's frame (``ghat_link``), the vertical ``up``, the link's body, the
    frame the post stands on (its name, origin and axes at the zero pose), and g |mu sigma| (N m, ``gG``,
    real: in the plane (sigma, up) the link's angle theta = pi/2 - phi)."""

    C: np.ndarray
    ghat: np.ndarray
    ghat_link: np.ndarray
    up: np.ndarray

    turn = False  # 001 Eqs. (13)-(14): the post on the vertical, the point on sigma
    tilt = 0.0  # the lead along sigma: the cable's path depends on phi alone
    beside = False  # C is already beside the links (its coil's width counted: pseudobase_layout's widths)
    bracket = False  # the coil rides its link: the pseudobase's post is a vertical line, not a level frame

    def prepare(self, c: complex, p: complex, k: float, rho: float) -> tuple[complex, complex, float]:
        """The spring's (c, p, k) with room for a pulley of radius ``rho`` (m): the post lowered to
        l_CB - :data:`PULLEY_CLEAR` rho where it stands higher, the rate raised to keep 001 Eq. (16)'s product.

        :raises SpringlabError: where the post would sink below a fifth of l_CB
        """
        a, b = abs(p), abs(c)
        if b - a >= PULLEY_CLEAR * rho:
            return c, p, k
        lowered = b - PULLEY_CLEAR * rho
        if lowered < 0.2 * b:
            raise SpringlabError(f"its link reaches {1e3 * b / PULLEY:.0f} mm along its subsystem's moment, too "
                                 f"short for a pulley of {1e3 * rho:.3g} mm: give a smaller --pulley-radius (a finer "
                                 "--cable) or leave the joint out (--share)")
        return c, complex(0.0, lowered), k * a / lowered

    def spring(self, model: RevoluteChain, c: complex, p: complex, k: float) -> PointSpring:
        """The spring from |c| along sigma to |p| above C (m), rate k (N/m)
        (:meth:`~springlab.design.layouts.Plane.placed`)."""
        return self.placed(model, self.C + abs(c) * self.ghat, self.C + abs(p) * self.up, k)  # 001 Eqs. (14), (13)

    def offsets(self, spring) -> tuple[complex, complex]:
        """A spring's point and post as complex offsets (m) from C in the plane (sigma, up): |l_CB|, i |l_CA|."""
        at = self.R0[self.link] @ np.asarray(spring.point_a) + self.o0[self.link] - self.C
        post = self.level_rotation @ np.asarray(spring.point_b) + self.level_origin - self.C
        return complex(float(np.linalg.norm(at)), 0.0), complex(0.0, float(np.linalg.norm(post)))

    def towards(self, c: complex) -> tuple:
        """Where the coil lies from the pulley, in the link's frame: back along sigma, towards C."""
        return tuple(-self.ghat_link)

    def angles(self, R) -> np.ndarray:
        """theta = pi/2 - phi (rad) at the poses of ``R``, phi the angle between sigma and the vertical, on a
        whole-degree grid (each once): where the workspace takes the subsystem."""
        cos = np.clip(np.einsum("pij,j->pi", R[:, self.link], self.ghat_link) @ self.up, -1.0, 1.0)
        return np.radians(np.unique(np.round(90.0 - np.degrees(np.arccos(cos)))))


def _reach(model: RevoluteChain, body: int, R0, o0, C, ghat, fallback: float) -> float:
    """How far (m) the link's shape reaches from C along ``ghat`` (its outline; ``fallback`` without one)."""
    pts = model.outline[body] if model.outline and len(model.outline[body]) else None
    if pts is None:
        return fallback
    return float(np.max((pts @ R0[body].T + o0[body] - C) @ ghat))


def pseudobase_layout(model: RevoluteChain, found: Structure, *, share: float = SHARE, q=None,
                      widths=None) -> Layout:
    """One spring per loaded link of any serial arm, from a post on the link's pseudobase to the link (see the
    module docstring); joints below ``share`` of the largest gravity peak get none (with ``q``, poses (N, n)
    rad, judged as :func:`~springlab.design.layouts.without_light` does). ``widths`` (joint index -> m): the
    width of the coils on that joint's link, which C is moved beside the links by as well (half of it).

    :raises SpringlabError: when a joint before the first loaded one turns about a non-vertical axis (no body
        stays level), or ``share`` is outside [0, 1)
    """

    share = _checks.number("share", share)
    if not 0.0 <= share < 1.0:
        raise SpringlabError(f"share = {share:g}: give the share of the largest gravity peak below which a joint "
                             "gets no spring, from 0 to 1 (e.g. 0.02)")
    if not found.loaded:
        raise SpringlabError(f"gravity loads no joint of {model.name!r}: nothing to balance")
    notes = []
    if q is not None:
        trimmed = without_light(model, found, share, q)
        notes += [f"joint {model.joints[i]}: {trimmed.reasons[i]}" for i in found.loaded if i not in trimmed.loaded]
        found = trimmed
    first = found.loaded[0]
    R0, o0 = zero_pose(model)
    up = model.up
    tilted = model.first_tilted(first, PARALLEL)
    if tilted is not None:
        raise SpringlabError(f"joint {model.joints[tilted]} before the first loaded one turns about a non-vertical "
                             f"axis: no body of {model.name!r} stays level to carry the posts")
    joints = list(range(first, model.n))
    w = {t: R0[t + 1] @ model.axes[t] for t in joints}
    planar = {t: t > first and model.first_unparallel(first, t) is None for t in joints}  # a belt carries its frame
    C = {}
    for t in joints:  # C_t on joint t's axis, beside the two links it joins, on the nearer side
        lo_p, hi_p = axial_extent(model, t, R0, o0, o0[t + 1], w[t])
        lo_c, hi_c = axial_extent(model, t + 1, R0, o0, o0[t + 1], w[t])
        hi, lo = max(hi_p, hi_c), min(lo_p, lo_c)
        gap = AXIAL_GAP + (0.0 if t == first or planar[t] else 0.5 * (widths or {}).get(t, 0.0))
        C[t] = o0[t + 1] + (hi + gap if hi <= -lo else lo - gap) * w[t]
    bodies = [t + 1 for t in joints]
    s_rows, r_rows = [], []
    for i, (t, b) in enumerate(zip(joints, bodies, strict=True)):  # 001's link i: O_{i-1} = C_t, O_i the next C
        ahead = C[joints[i + 1]] if i + 1 < len(joints) else C[t]
        s_rows.append(R0[b].T @ (o0[b] + R0[b] @ model.com[b] - ahead))
        r_rows.append(R0[b].T @ (C[t] - ahead))
    moment = [R0[b] @ row for b, row in zip(bodies, subsystem_moments(model.mass[bodies], s_rows, r_rows),
                                             strict=True)]  # 001 Eq. (5), kg m, world at the zero pose
    for i in range(len(joints) - 1, 0, -1):  # the part along a joint's axis turns with the link before it
        axial = (moment[i] @ w[joints[i]]) * w[joints[i]]
        moment[i] = moment[i] - axial
        moment[i - 1] = moment[i - 1] + axial
    level_name = model.bodies[first]
    out, springs, leads, outward, planes, rooms = model, [], [], [], [], []
    for i, t in enumerate(joints):
        b, size = bodies[i], float(np.linalg.norm(moment[i]))
        if t not in found.loaded:
            if size > 1e-9 * max(float(np.linalg.norm(v)) for v in moment) and not found.reasons.get(t, "").startswith(
                    "light"):
                notes.append(f"joint {model.joints[t]}: no spring; its link's subsystem (mu sigma = {1e3 * size:.3g} "
                             "g m about its joint's axis) is left, what the checks measure")
            continue
        if size == 0:
            notes.append(f"joint {model.joints[t]}: its subsystem has no first moment: no spring")
            continue
        ghat = moment[i] / size
        ahead = o0[joints[i + 1] + 1] if i + 1 < len(joints) else o0[b] + R0[b] @ model.com[b]
        reach = _reach(model, b, R0, o0, C[t], ghat, float(np.linalg.norm(ahead - o0[t + 1])))
        if reach <= 0:
            notes.append(f"joint {model.joints[t]}: its link reaches nowhere along its subsystem's moment: no spring")
            continue
        r_b, r_a = PULLEY * reach, POST * reach
        kappa = model.g * size / (r_a * r_b)  # 001 Eq. (16): K l_CA l_CB = mu g sigma
        along = float((C[t] - o0[t + 1]) @ w[t])
        if t == first or planar[t]:  # the link turns in one plane of its post's frame: the belts' plane
            h = np.cross(up, w[t])
            if t == first:
                level, origin = level_name, o0[first]
            else:
                out = out.with_belt(model.joints[t], level_name)
                level, origin = out.belts[-1].name, o0[t + 1]
            G = complex(moment[i] @ h, moment[i] @ up)  # kg m, in the plane (h, up)
            W = -model.g * np.conj(1j) * G  # the spring's k conj(c_0) c_k, as belt_layout's
            p = 1j * r_a
            c = W / (kappa * np.conj(-p))
            plane = SpringPlane(b, level, np.asarray(origin), R0[first], R0, o0, complex(model.g * G),
                                joint_at=np.asarray(o0[t + 1]), h=h, up=up, w=w[t], d=along)
            springs.append(plane.spring(out, c, p, kappa))
            leads.append(plane.towards(c))
            side = 1.0 if along > 0 else -1.0
            outward.append((R0[b].T @ (side * w[t]), R0[first].T @ (side * w[t])))  # the coils' width: realise
        else:
            out = out.with_pseudobase(model.joints[t], level_name, along=along)
            level, origin = out.belts[-1].name, C[t]
            plane = Subsystem(b, level, origin, R0[first], R0, o0, complex(model.g * size),
                              C=C[t], ghat=ghat, ghat_link=R0[b].T @ ghat, up=up)
            springs.append(plane.spring(out, complex(r_b), complex(0.0, r_a), kappa))
            leads.append(plane.towards(0j))
            outward.append((np.zeros(3), np.zeros(3)))  # C is already beside the links, its coils' width too
        planes.append(plane)
        rooms.append(reach)
    return Layout(out, tuple(springs), tuple(leads), tuple(notes), tuple(outward), tuple(planes), tuple(rooms))

