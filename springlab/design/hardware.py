"""A realised design as hardware on the arm: where each spring's coil and cable are at every pose, how
near they come to the links (:mod:`springlab.design.collision`, on the URDF's own shapes), and the
springs' own mass carried by the links.

**Where a realised spring is** (:func:`spring_pieces`), in the base frame at each pose:

* a *zero-length spring* is its coil from A to B (the hooks on the brackets at A and B), a capsule of
  the coil's outer diameter;
* a *cable over a pulley* is its cable from the point T where it leaves the pulley to B (route 2's
  cable path, :func:`~springlab.energy.geometry.cable_geometry`), a capsule of :data:`CABLE_DIAMETER`;
  its coil lies on link_a behind the pulley, along the lead: its fixed hook at
  :data:`HOOK_GAP` + the pulley's radius + the coil's longest length from A, its moving hook as far
  from the fixed one as the coil is long at that pose (the cable's path plus its offset
  L_0 - F_i / k), and the cable runs from the moving hook along the lead to the pulley.

Each piece may touch the link it is fixed to within :data:`ALLOWANCE` of its fixed end (its hook and
bracket); everywhere else it must clear every link by the margin.

**Their mass** (:func:`with_spring_mass`): a zero-length spring's coil, stretched evenly between A and
B, has its centre of mass at (A + B) / 2, the same potential energy as half its mass at A and half at
B, exactly; a cable spring's coil rides on link_a, its mass at its centre at mid-stroke (its centre
moves by a quarter of the stroke, which this leaves out). Lengths in m, masses in kg.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab.design.collision import MARGIN, Piece, clearances
from springlab.energy.geometry import cable_geometry
from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, world_points
from springlab.tables import Table

CABLE_DIAMETER = 0.0012
"""m: the cable of a cable spring (1.2 mm steel wire rope, 7 x 7), as :data:`springlab.design.buildable.CABLE_RADIUS`."""

HOOK_GAP = 0.01
"""m: between the pulley's rim and the coil's moving hook at the coil's longest (the cable's clamp)."""

ALLOWANCE = 0.02
"""m: how far from its fixed end a piece may touch the link it is fixed to (its hook, eye and bracket)."""


def _lead(model: RevoluteChain, s, R, o, ia, A, B) -> np.ndarray:
    """The unit direction (in link_a's body's frame) along which a cable spring's coil lies behind its
    pulley: its lead, or with a point pulley, the mean direction from B to A in that frame."""
    if s.pulley_radius > 0 and s.lead is not None:
        return model.direction(s.link_a, s.lead)[1]
    d = np.einsum("pji,pj->pi", R[:, ia], A - B).mean(axis=0)
    return d / max(float(np.linalg.norm(d)), 1e-12)


def spring_pieces(model: RevoluteChain, realised, kinds, coils, names, q) -> list[Piece]:
    """The pieces (coil, cable) of each realised spring at the poses ``q`` (N, n) rad, named
    'S3 coil', 'S3 cable' (see the module docstring)."""
    q = model.check_q(q)
    R, o = body_frames(model, q)
    out = []
    for name, s, kind, (coil, _) in zip(names, realised, kinds, coils, strict=True):
        (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
        A, B = world_points(R, o, ia, pa), world_points(R, o, ib, pb)
        if not kind.startswith("cable"):
            out.append(Piece(f"{name} coil", A, B, coil.outer_diameter / 2, ((ia, "a", ALLOWANCE), (ib, "b", ALLOWANCE))))
            continue
        rho = s.pulley_radius
        u = R[:, ia] @ _lead(model, s, R, o, ia, A, B)
        path, T = cable_geometry(A, B, u, rho) if rho > 0 else (np.linalg.norm(B - A, axis=1), A)
        length = np.clip(path + coil.cable_offset, coil.free_length, None)  # the coil's length at each pose
        fixed = A - u * (rho + HOOK_GAP + coil.max_length)
        moving = fixed + u * length[:, None]
        out.append(Piece(f"{name} coil", fixed, moving, coil.outer_diameter / 2, ((ia, "a", ALLOWANCE),)))
        out.append(Piece(f"{name} cable", moving, A - u * rho, CABLE_DIAMETER / 2, ((ia, "b", ALLOWANCE),)))
        out.append(Piece(f"{name} cable", T, B, CABLE_DIAMETER / 2, ((ia, "a", ALLOWANCE), (ib, "b", ALLOWANCE))))
    return out


@dataclass(frozen=True)
class SpringClearance:
    """Per realised spring, its nearest approach to a link over the poses: (spring, piece, link, pose
    index, clearance m); and the margin (m) it is judged by."""

    rows: tuple
    margin: float
    poses: int

    def failing(self) -> tuple:
        return tuple(r for r in self.rows if r[4] < self.margin)

    def table(self, q=None) -> Table:
        out = []
        for spring, piece, link, pose, gap in self.rows:
            where = "" if q is None else "(" + ", ".join(f"{np.degrees(v):.0f}" for v in q[pose]) + ")"
            out.append((spring, piece, link, f"{1e3 * gap:.1f}", "yes" if gap >= self.margin else "no", where))
        return Table(["spring", "nearest piece", "nearest link", "clearance (mm)",
                      f"clears by {1e3 * self.margin:g} mm", "at the pose (deg)"], out)


def spring_clearance(model: RevoluteChain, realised, kinds, coils, names, q, *, margin: float = MARGIN) -> SpringClearance:
    """Each realised spring's nearest approach to any link over the poses ``q`` (see the module docstring)."""
    pieces = spring_pieces(model, realised, kinds, coils, names, q)
    found = clearances(model, pieces, q, margin=margin)
    best: dict = {}
    for k, piece in enumerate(pieces):
        spring, _, part = piece.name.partition(" ")
        gap, body, pose = found.worst(k)
        if spring not in best or gap < best[spring][4]:
            best[spring] = (spring, part, model.bodies[body], pose, gap)
    return SpringClearance(tuple(best[n] for n in names if n in best), float(margin), int(np.asarray(q).shape[0]))


def with_spring_mass(model: RevoluteChain, realised, kinds, coils, q) -> RevoluteChain:
    """The arm carrying its realised springs' mass (see the module docstring); ``q`` (N, n) rad, the poses
    a point pulley's coil direction is taken over."""
    q = model.check_q(q)
    R, o = body_frames(model, q)
    out = model
    for s, kind, (coil, span) in zip(realised, kinds, coils, strict=True):
        m = float(coil.mass)
        if not kind.startswith("cable"):
            for link, point in ((s.link_a, s.point_a), (s.link_b, s.point_b)):
                body, local = model.locate(link, point)
                if body > model.n:  # a belt's frame: its post turns about the joint, carried at the joint's origin
                    link, point = model.bodies[model.belts[body - model.n - 1].joint + 1], (0.0, 0.0, 0.0)
                out = out.with_point_mass(link, point, m / 2)
            continue
        (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
        if ia > model.n:
            raise SpringlabError(f"{s.label}: a cable spring's coil rides on link_a, here a belt's frame; give the "
                                 "belt's end as link_b")
        u = _lead(model, s, R, o, ia, world_points(R, o, ia, pa), world_points(R, o, ib, pb))
        mid = (min(span) + max(span)) / 2 + coil.cable_offset  # the coil's length at mid-stroke
        behind = s.pulley_radius + HOOK_GAP + coil.max_length - mid / 2  # its centre, from A along -lead
        out = out.with_point_mass(model.bodies[ia], pa - behind * u, m)
    return out
