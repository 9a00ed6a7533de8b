"""A realised design as hardware on the arm: where each spring's coil, cable and pulley are at every
pose, how near they come to the links (:mod:`springlab.design.collision`, on the URDF's own shapes),
the parts a maker builds it from (:func:`parts`: coils, ropes, pulleys, posts and belts, with their
sizes, masses and loads) and their mass carried by the links.

**Where a realised spring is** (:func:`spring_pieces`), in the base frame at each pose:

* a *zero-length spring* is its coil from A to B (the hooks on the brackets at A and B), a capsule of
  the coil's outer diameter;
* a *cable over a pulley* is its cable from the point T where it leaves the pulley to B (route 2's
  cable path, :func:`~springlab.energy.geometry.cable_geometry`), a capsule of its rope's diameter
  (:mod:`springlab.design.cables`; :data:`CABLE_DIAMETER` where none is named); its pulley a disc out
  to its flanges in the plane of the lead and B; its coil lies on link_a behind the pulley, along the
  lead: its fixed hook at :data:`HOOK_GAP` + the pulley's radius (+ a block's travelling sheave) + the
  coil's longest length from A, its moving hook as far from the fixed one as the coil is long at that
  pose (the cable's path over the block's ratio plus its offset L_0 - F_i / k), and the cable runs
  from the moving hook along the lead to the pulley (over a block, its strands within the sheave's
  width).

Each piece may touch the link it is fixed to within :data:`ALLOWANCE` of its fixed end (its hook and
bracket); everywhere else it must clear every link by the margin.

**Their mass** (:func:`with_spring_mass`, every part's as :func:`parts` places it): a zero-length
spring's coil, stretched evenly between A and B, has its centre of mass at (A + B) / 2, the same
potential energy as half its mass at A and half at B, exactly; a cable spring's coil rides on link_a,
its mass at its centre at mid-stroke (its centre moves by a quarter of the stroke, which this leaves
out). Lengths in m, masses in kg.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from springlab.design.cables import ALUMINIUM, pulley_mass, pulley_width, rope_mass
from springlab.design.collision import MARGIN, Piece, clearances
from springlab.energy.geometry import cable_geometry
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


def balanced_body(model: RevoluteChain, spring) -> int:
    """The body a layout's spring balances (:mod:`springlab.design.layouts`): the farther of its two ends' bodies
    from the base, not counting a belt's frame: end A's on its link, or end B's where end A is the post on a
    bracket of the level frame that carries its pulley and coil."""
    bodies = [model.locate(link, point)[0] for link, point in ((spring.link_a, spring.point_a),
                                                                 (spring.link_b, spring.point_b))]
    return max(b for b in bodies if b <= model.n)


def link_length(model: RevoluteChain, body: int) -> float:
    """The length (m) of a body: from its joint to the next joint (the last body: to its centre of mass), or
    its outline's longest side where that is longer (a body between two joints at one point still has a
    size); the base: unbounded, a coil on it lies on the ground or the arm's stand."""
    if body == 0 or body > model.n:  # the base, or a belt's frame
        return float("inf")
    span = float(np.linalg.norm(model.placements[body][:3, 3] if body < model.n else model.com[body]))
    if model.outline and len(model.outline[body]):
        span = max(span, float(np.max(np.ptp(model.outline[body], axis=0))))
    return span


def coil_bound(model: RevoluteChain, spring, fit) -> float:
    """The length (m) a realised spring's coil is held to: its link's (:func:`link_length` of the body it
    balances, :func:`balanced_body`), or for a coil on a bracket of the level frame, the room its layout gave
    it plus what lies behind its pulley (the pulley, the hook's gap and the rope): the longer link at its
    joint (the base: unbounded)."""
    if fit.bracket is None:
        return link_length(model, balanced_body(model, spring))
    return fit.bracket + spring.pulley_radius + HOOK_GAP + _cable_diameter(fit)


def _cable_diameter(fit) -> float:
    return fit.cable.diameter if getattr(fit, "cable", None) is not None else CABLE_DIAMETER


def block_room(fit, rho: float) -> float:
    """m: what a pulley block's travelling sheave adds between the coil's moving hook and the pulley."""
    return 2 * (rho + _cable_diameter(fit)) if fit.ratio > 1 else 0.0


def _coil_ends(model: RevoluteChain, s, fit, R, o):
    """A cable spring's lead u (link_a's frame), the coil's fixed hook and, per pose, its moving hook (link_a's
    frame), the cable's point T leaving the pulley (base frame) and B (base frame), at the poses of R, o."""
    (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
    A, B = world_points(R, o, ia, pa), world_points(R, o, ib, pb)
    rho = s.pulley_radius
    u = _lead(model, s, R, o, ia, A, B)
    path, T = cable_geometry(A, B, R[:, ia] @ u, rho) if rho > 0 else (np.linalg.norm(B - A, axis=1), A)
    length = fit.coil_length(path)
    fixed = pa - u * (rho + HOOK_GAP + block_room(fit, rho) + fit.coil.max_length)
    return u, fixed, fixed + length[:, None] * u, T, B, ia, ib


def coil_ends(model: RevoluteChain, realised, kinds, coils, q) -> list[dict]:
    """Per realised spring, for ``--json``: its coil's two ends at the pose of ``q`` (N, n) rad where it is
    longest, each as {"link", "point" (m, in that link's frame)} (a cable spring's both on link_a, its fixed
    hook and its moving one), and its cable's diameter (m; None for a zero-length spring)."""
    q = model.check_q(q)
    R, o = body_frames(model, q)
    out = []
    for s, kind, fit in zip(realised, kinds, coils, strict=True):
        if not kind.startswith("cable"):
            out.append({"coil_a": {"link": s.link_a, "point": [float(v) for v in s.point_a]},
                        "coil_b": {"link": s.link_b, "point": [float(v) for v in s.point_b]}, "cable_diameter": None})
            continue
        u, fixed, moving, *_ = _coil_ends(model, s, fit, R, o)
        longest = int(np.argmax(np.linalg.norm(moving - fixed, axis=1)))
        out.append({"coil_a": {"link": s.link_a, "point": [float(v) + 0.0 for v in fixed]},
                    "coil_b": {"link": s.link_a, "point": [float(v) + 0.0 for v in moving[longest]]},
                    "cable_diameter": _cable_diameter(fit)})
    return out


def spring_pieces(model: RevoluteChain, realised, kinds, coils, names, q) -> list[Piece]:
    """The pieces (coil, cable, pulley) of each realised spring at the poses ``q`` (N, n) rad, named
    'S3 coil', 'S3 cable', 'S3 pulley' (see the module docstring)."""
    q = model.check_q(q)
    R, o = body_frames(model, q)
    out = []
    for name, s, kind, fit in zip(names, realised, kinds, coils, strict=True):
        (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
        A, B = world_points(R, o, ia, pa), world_points(R, o, ib, pb)
        if not kind.startswith("cable"):
            out.append(Piece(f"{name} coil", A, B, fit.coil.outer_diameter / 2,
                             ((ia, "a", ALLOWANCE), (ib, "b", ALLOWANCE))))
            continue
        rho, d = s.pulley_radius, _cable_diameter(fit)
        u, fixed, moving, T, B, ia, ib = _coil_ends(model, s, fit, R, o)
        fixed, moving = world_points(R, o, ia, fixed), _world(R, o, ia, moving)
        at_pulley = world_points(R, o, ia, pa - u * rho)
        out.append(Piece(f"{name} coil", fixed, moving, fit.coil.outer_diameter / 2, ((ia, "a", ALLOWANCE),)))
        run = rho + d if fit.ratio > 1 else d / 2  # a block's strands lie within its travelling sheave
        out.append(Piece(f"{name} cable", moving, at_pulley, run, ((ia, "b", ALLOWANCE),)))
        out.append(Piece(f"{name} cable", T, B, d / 2, ((ia, "a", ALLOWANCE), (ib, "b", ALLOWANCE))))
        if rho > 0:  # the sheave: a disc out to its flanges, in the plane of the lead and B (its own link: its bracket)
            lead = np.broadcast_to(R[:, ia] @ u, B.shape)
            normal = np.cross(lead, B - A)
            flat = np.linalg.norm(normal, axis=1) < 1e-9 * np.maximum(np.linalg.norm(B - A, axis=1), 1e-300)
            normal[flat] = np.cross(lead[flat], [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
            normal /= np.linalg.norm(normal, axis=1)[:, None]
            out.append(Piece(f"{name} pulley", A, A, rho + d, ((ia, "a", ALLOWANCE),), normal, pulley_width(d)))
    return out


def _world(R, o, body: int, points) -> np.ndarray:
    """Per pose, a point given per pose in a body's frame, (N, 3), in the base frame."""
    return np.einsum("pij,pj->pi", R[:, body], points) + o[:, body]


@dataclass(frozen=True)
class SpringClearance:
    """Per realised spring, its nearest approach to a link over the poses: (spring, piece, link, pose
    index, clearance m); the margin (m) it is judged by; and, for each spring nearer than the margin, the share
    of the first :data:`WITHIN_POSES` poses at which some piece of it comes within the margin of a link or the
    mounting plane (``within``: spring -> share, 0 to 1). A spring that runs into its own or the next link at most poses is
    laid out there; one that meets a far link at a few, the hand folded back onto it, needs a narrower
    workspace."""

    rows: tuple
    margin: float
    poses: int
    within: dict = field(default_factory=dict)

    def failing(self) -> tuple:
        return tuple(r for r in self.rows if r[4] < self.margin)

    def table(self, q=None) -> Table:
        out = []
        for spring, piece, link, pose, gap in self.rows:
            where = "" if q is None else "(" + ", ".join(f"{np.degrees(v):.0f}" for v in q[pose]) + ")"
            out.append((spring, piece, link, f"{1e3 * gap:.1f}", "yes" if gap >= self.margin else "no", where))
        return Table(["spring", "nearest piece", "nearest link", "clearance (mm)",
                      f"clears by {1e3 * self.margin:g} mm", "at the pose (deg)"], out)


def _same_place(one, other) -> bool:
    """Whether two pieces (:class:`~springlab.design.collision.Piece`) occupy the same place at every pose: their
    names aside, equal in every field."""
    def same(x, y):
        return (x is None) == (y is None) and (x is None or np.array_equal(np.asarray(x), np.asarray(y)))
    return (one.radius == other.radius and one.width == other.width and one.bodies == other.bodies
            and same(one.a, other.a) and same(one.b, other.b) and same(one.axis, other.axis))


WITHIN_POSES = 500
"""How many of the check poses (the first: random draws of the workspace) the share of poses at which a spring
that does not clear comes within the margin is counted on, coal measuring each: a share counted so is within
about 2 points of the workspace's (its standard error, at most sqrt(0.25 / 500), at a share of one half)."""


def _poses(piece, sample: slice):
    """The piece at the poses ``sample`` only."""
    return dataclasses.replace(piece, a=np.asarray(piece.a)[sample], b=np.asarray(piece.b)[sample],
                               axis=None if piece.axis is None else np.asarray(piece.axis)[sample])


def spring_clearance(model: RevoluteChain, realised, kinds, coils, names, q, *, margin: float = MARGIN) -> SpringClearance:
    """Each realised spring's nearest approach to any link over the poses ``q`` (see the module docstring)."""
    pieces = spring_pieces(model, realised, kinds, coils, names, q)
    unique, index = [], []  # coils side by side on the same ends are the same pieces: measured once
    for piece in pieces:
        same = next((u for u, other in enumerate(unique) if _same_place(piece, other)), None)
        if same is None:
            unique.append(piece)
            same = len(unique) - 1
        index.append(same)
    found = clearances(model, unique, q, margin=margin)
    best: dict = {}
    for k, piece in enumerate(pieces):
        spring, _, part = piece.name.partition(" ")
        gap, body, pose = found.worst(index[k])
        if spring not in best or gap < best[spring][4]:
            best[spring] = (spring, part, found.links[body], pose, gap)
    within, sample = {}, slice(0, WITHIN_POSES)
    for spring in (n for n in names if n in best and best[n][4] < margin):  # coal at every pose it may be near at
        own = sorted({index[k] for k, piece in enumerate(pieces) if piece.name.partition(" ")[0] == spring})
        near = clearances(model, [_poses(unique[u], sample) for u in own], np.asarray(q)[sample], margin=margin,
                          every=True).within(margin)
        within[spring] = float(np.mean(near))
    return SpringClearance(tuple(best[n] for n in names if n in best), float(margin), int(np.asarray(q).shape[0]),
                           within)


ROD_STRESS = 100e6
"""Pa: the bending stress a post or bracket (aluminium 6061-T6 rod, yield 276 MPa) is sized to."""

BELT_TENSION = 20.0
"""N per mm of width: the working tension a timing belt of the HTD 5M class with glass-fibre cords carries
(a round figure between GT2's and steel-cord AT5's: check the maker's table for the chosen belt)."""

BELT_MASS = 0.004
"""kg/m per mm of width: such a belt's mass."""

BELT_PULLEY = 0.15
"""A belt's pulleys' pitch diameter over the length of the link it runs along (at least :data:`BELT_LEAST`)."""

BELT_LEAST = 0.012
"""m: the least pitch diameter of a belt's pulley (and the least belt width, 6 mm, is half of it)."""

RSSR_OFFSET = 0.15
"""An RSSR module's parallelogram height (its auxiliary link's offset from the primary link, 001 Section 4.1)
over the length of the link it runs along (at least :data:`BELT_LEAST`): the couple the module carries is its
auxiliary link's force times this height."""

ALUMINIUM_E = 69e9
"""Pa: aluminium's Young's modulus: an RSSR module's auxiliary link (a tube between two ball joints) is sized to
buckle at :data:`BUCKLING` times its largest force (Euler, pinned ends)."""

BUCKLING = 3.0
"""The safety factor on an auxiliary link's Euler buckling load."""

BALL_JOINT = 0.01
"""kg: a small ball joint's (rod end's) mass; an RSSR module has two on its auxiliary link and one at its
pseudobase (001 Fig. 5)."""


BOLTS = (("M3", 3e-3, 5.03e-6), ("M4", 4e-3, 8.78e-6), ("M5", 5e-3, 14.2e-6), ("M6", 6e-3, 20.1e-6),
         ("M8", 8e-3, 36.6e-6), ("M10", 10e-3, 58.0e-6), ("M12", 12e-3, 84.3e-6))
"""Metric coarse bolts: (name, nominal diameter m, tensile stress area m^2), ISO 898-1 Table 4 (ISO 724)."""

BOLT_PROOF = 580e6
"""Pa: the proof stress of property class 8.8 bolts (ISO 898-1, d <= 16 mm)."""

BOLT_SAFETY = 2.0
"""The factor between a bolt's proof load and the largest tension a bracket's bolt pattern puts on it."""

BOLT_COMPACT = 10.0
"""A bolt pattern is sized for the smallest bolt whose spacing stays within this many bolt diameters."""


def bolt_pattern(force: float, moment: float) -> str:
    """The least bolt pattern for a post's or bracket's foot carrying ``force`` (N) and the bending
    ``moment`` (N m) at its root: two class 8.8 bolts in line with the moment, the outer one taking the
    couple M / s on top of half the force, F / 2 + M / s <= A_t S_p / :data:`BOLT_SAFETY`; the smallest
    bolt of :data:`BOLTS` whose least spacing s is at most :data:`BOLT_COMPACT` diameters, and s at least
    three diameters. A minimum for the designer to check against the part the foot is bolted into (a
    printed link's threads hold less than a steel nut).

    >>> bolt_pattern(100.0, 10.0)  # M3's proof load 2.9 kN: 1.41 kN allowed beside F / 2, s = 7.1 mm, 3 d = 9 mm
    '2 x M3 (class 8.8), at least 9 mm apart'
    >>> bolt_pattern(2000.0, 150.0)  # M4 would need 97 mm, over 10 d; M5: 150 / 3.12e3 = 48.1 mm
    '2 x M5 (class 8.8), at least 49 mm apart'
    """
    force, moment = abs(float(force)), abs(float(moment))
    for name, d, area in BOLTS:
        allowed = area * BOLT_PROOF / BOLT_SAFETY - force / 2
        if allowed <= 0:
            continue
        spacing = max(3 * d, moment / allowed)
        if spacing <= BOLT_COMPACT * d:
            return f"2 x {name} (class 8.8), at least {np.ceil(spacing * 1e3 - 1e-6):.0f} mm apart"
    return (f"more than two {BOLTS[-1][0]} bolts: {force:.0f} N and {moment:.1f} N m need a pattern of its own "
            "(ISO 898-1 class 8.8 proof loads)")


@dataclass(frozen=True)
class Part:
    """A part of the springs' hardware: its kind ('spring', 'cable', 'pulley', 'belt', 'post', 'bracket', 'rssr'), name, the
    link (frame) it rides on and its centre there (m), its mass (kg), its sizes (m) and the loads it
    carries (N, N m) over the workspace, and where its mass is carried in the balance: (link, point m,
    kg) each."""

    kind: str
    name: str
    link: str
    centre: tuple
    mass: float
    size: dict
    loads: dict
    carried: tuple

    def as_dict(self) -> dict:
        return {"kind": self.kind, "name": self.name, "link": self.link,
                "centre": [float(v) + 0.0 for v in self.centre], "mass_kg": float(self.mass)} | {
            k: float(v) if isinstance(v, (float, np.floating)) else v for k, v in (self.size | self.loads).items()}


def _joint_in(model: RevoluteChain, body: int) -> np.ndarray:
    """The origin (m, the body's frame) of the joint after ``body``: where a post or bracket on it stands."""
    return np.asarray(model.placements[body][:3, 3], dtype=float) if body < model.n else np.zeros(3)


def _rod(force: float, length: float) -> float:
    """m: the diameter of an aluminium rod cantilevered ``length`` m with ``force`` N at its end, at
    :data:`ROD_STRESS` (32 F L / (pi d^3)), at least 6 mm."""
    return max(0.006, float(np.cbrt(32 * force * length / (np.pi * ROD_STRESS))))


def parts(model: RevoluteChain, realised, kinds, coils, names, q) -> tuple:
    """Every part of the realised springs' hardware (:class:`Part`) over the poses ``q`` (N, n) rad:
    each spring's coil (a zero-length spring's mass half at each end, exactly; a cable spring's on link_a at
    its centre at mid-stroke, which moves by a quarter of its stroke), its cable and pulleys (the pulley at
    end A on link_a; a block's travelling sheave at the coil's moving hook at mid-stroke; the cable's mass
    half at each end of its free span), the post each belt-carried end stands on (an aluminium rod from
    the joint's axis, sized to its bending) and each belt (one per joint it crosses, its pulleys' pitch
    diameter :data:`BELT_PULLEY` of the link, its width carrying the largest moment its springs put on it at
    :data:`BELT_TENSION`), or each RSSR module that keeps a pseudobase's vertical line (one per link, sized to its couple). Its
    loads are the largest over ``q``: a cable's pull, a pulley's load on its shaft, a post's force and bending
    moment at its root, a belt's moment and tension, a module's couple and its auxiliary link's force."""

    q = model.check_q(q)
    R, o = body_frames(model, q)
    out = []

    def on(name, point):  # where a point's mass is carried: a belt frame's at its origin, on its joint's axis
        body, _ = model.locate(name, point)
        if body > model.n:
            belt = model.belts[body - model.n - 1]
            return model.bodies[belt.joint + 1], tuple(belt.along * model.axes[belt.joint])
        return name, tuple(point)

    moments = {b.name: np.zeros(len(q)) for b in model.belts}
    for name, s, kind, fit in zip(names, realised, kinds, coils, strict=True):
        coil = fit.coil
        (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
        A, B = world_points(R, o, ia, pa), world_points(R, o, ib, pb)
        if not kind.startswith("cable"):
            pull = s.k * np.linalg.norm(B - A, axis=1)
            out.append(Part("spring", f"{name} coil", s.link_a, tuple(pa), coil.mass,
                            {"wire_diameter": coil.wire, "outer_diameter": coil.outer_diameter,
                             "free_length": coil.free_length, "longest": coil.max_length},
                            {"largest_force_N": float(np.max(pull))},
                            (on(s.link_a, pa) + (coil.mass / 2,), on(s.link_b, pb) + (coil.mass / 2,))))
            towards, at = A, B
        else:
            rho, d = s.pulley_radius, _cable_diameter(fit)
            u, fixed, moving, T, B, _, _ = _coil_ends(model, s, fit, R, o)
            path = np.linalg.norm(B - T, axis=1)
            pull = s.k * (cable_geometry(A, B, R[:, ia] @ u, rho)[0] if rho > 0 else path)
            mid = float(fit.coil_length(np.mean(fit.span)))
            centre = fixed + u * mid / 2
            out.append(Part("spring", f"{name} coil", s.link_a, tuple(centre), coil.mass,
                            {"wire_diameter": coil.wire, "outer_diameter": coil.outer_diameter,
                             "free_length": coil.free_length, "longest": coil.max_length, "block_ratio": fit.ratio},
                            {"largest_force_N": float(coil.max_force)}, (on(s.link_a, centre) + (coil.mass,),)))
            hook = fixed + u * mid
            run = float(np.linalg.norm(pa - hook))
            free = float(np.max(path))
            cable = fit.cable
            m_cable = (fit.ratio * run + free) * rope_mass(d)
            rating = {} if cable is None else {"cable": cable.name, "working_load_N": cable.working,
                                               "breaking_load_N": cable.breaking}
            out.append(Part("cable", f"{name} cable", s.link_a, tuple((hook + pa) / 2), m_cable,
                            {"diameter": d, "length": fit.ratio * run + free},
                            {"largest_pull_N": float(np.max(pull))} | rating,
                            (on(s.link_a, (hook + pa) / 2) + (m_cable * fit.ratio * run / (fit.ratio * run + free),),
                             on(s.link_a, pa) + (m_cable * free / (fit.ratio * run + free) / 2,),
                             on(s.link_b, pb) + (m_cable * free / (fit.ratio * run + free) / 2,))))
            if rho > 0 and cable is not None:
                m = pulley_mass(cable, rho)
                lead = R[:, ia] @ u
                out_dir = (B - T) / np.maximum(np.linalg.norm(B - T, axis=1), 1e-12)[:, None]
                shaft = pull * np.linalg.norm(out_dir - lead, axis=1)
                out.append(Part("pulley", f"{name} pulley", s.link_a, tuple(pa), m,
                                {"tread_diameter": 2 * rho - d, "cable_radius": rho},
                                {"shaft_load_N": float(np.max(shaft))}, (on(s.link_a, pa) + (m,),)))
                if fit.ratio > 1:
                    sheave = hook + u * (rho + d)
                    out.append(Part("pulley", f"{name} block sheave", s.link_a, tuple(sheave), m,
                                    {"tread_diameter": 2 * rho - d, "cable_radius": rho, "ratio": fit.ratio},
                                    {"shaft_load_N": float(coil.max_force)}, (on(s.link_a, sheave) + (m,),)))
            if fit.bracket is not None:  # the pulley and the coil on a bracket of the level frame
                belt = model.belts[ia - model.n - 1] if ia > model.n else None
                root = np.zeros(3) if belt is not None else _joint_in(model, ia)
                reach = float(np.linalg.norm(fixed - root))  # from the joint's axis out to the coil's fixed hook
                F = float(np.max(shaft)) if rho > 0 and cable is not None else float(np.max(pull))
                arm = float(np.linalg.norm(np.asarray(pa) - root))
                dia = _rod(F, arm)
                m = ALUMINIUM * np.pi * dia**2 / 4 * reach
                centre = (fixed + root) / 2
                out.append(Part("bracket", f"{name} bracket", s.link_a, tuple(centre), m,
                                {"length": reach, "rod_diameter": dia, "bolts": bolt_pattern(F, F * arm)},
                                {"largest_force_N": F, "root_moment_Nm": F * arm}, (on(s.link_a, centre) + (m,),)))
                if belt is not None:  # the cable's pull on the bracket, about the frame's origin: the belt carries it
                    w = R[:, belt.joint + 1] @ model.axes[belt.joint]
                    force = pull[:, None] * (B - T) / np.maximum(np.linalg.norm(B - T, axis=1), 1e-12)[:, None]
                    moments[belt.name] = moments[belt.name] + np.einsum("pi,pi->p", w, np.cross(T - o[:, ia], force))
            towards, at = T, B
        level = model.belts[0].level if model.belts else None
        if ib > model.n or ib == level:  # end B stands on a post at its joint: on a belt's frame, or the level body
            belt = model.belts[ib - model.n - 1] if ib > model.n else None
            root = np.zeros(3) if belt is not None else model.placements[ib][:3, 3]
            joint = belt.joint if belt is not None else ib
            direction = (towards - at) / np.maximum(np.linalg.norm(towards - at, axis=1), 1e-12)[:, None]
            force = pull[:, None] * direction
            if belt is not None:
                w = R[:, joint + 1] @ model.axes[joint]
                couple = np.cross(at - o[:, ib], force)  # about the frame's origin: the belt carries its part
                moments[belt.name] = moments[belt.name] + (np.einsum("pi,pi->p", w, couple) if belt.kind == "belt" else
                                                           np.linalg.norm(couple, axis=1))  # the modules all of it
            length = float(np.linalg.norm(np.asarray(pb) - root))
            F = float(np.max(pull))
            dia = _rod(F, length)
            m = ALUMINIUM * np.pi * dia**2 / 4 * length
            centre = tuple((np.asarray(pb) + root) / 2)
            carried = on(s.link_b, centre) + (m,) if belt is not None else (s.link_b, centre, m)
            out.append(Part("post", f"{name} post", s.link_b, centre, m,
                            {"length": length, "rod_diameter": dia, "bolts": bolt_pattern(F, F * length)},
                            {"largest_force_N": F, "root_moment_Nm": F * length}, (carried,)))
    out += _modules(model, {b: float(np.max(np.abs(moments[b.name]))) for b in model.belts if b.kind != "belt"})
    for belt in model.belts:
        moment = float(np.max(np.abs(moments[belt.name])))
        if belt.kind != "belt":
            continue
        for t in range(belt.level, belt.joint):  # a belt per joint crossed, riding on the link after it
            span = model.placements[t + 1][:3, 3]
            pitch = max(BELT_LEAST, BELT_PULLEY * float(np.linalg.norm(span)))
            tension = moment / (pitch / 2)
            width = max(BELT_LEAST / 2, np.ceil(tension / BELT_TENSION) * 1e-3)
            length = 2 * float(np.linalg.norm(span)) + np.pi * pitch
            m_belt = BELT_MASS * width * 1e3 * length
            m_pulley = ALUMINIUM * np.pi * (pitch / 2) ** 2 * (width + 0.004)
            link = model.bodies[t + 1]
            out.append(Part("belt", f"{belt.name} ({model.joints[t]} to {model.joints[t + 1]})", link,
                            tuple(span / 2), m_belt + 2 * m_pulley,
                            {"length": length, "width": float(width), "pulley_pitch_diameter": pitch,
                             "belt_mass_kg": m_belt, "pulleys_mass_kg": 2 * m_pulley},
                            {"largest_moment_Nm": moment, "tension_N": tension},
                            ((link, tuple(span / 2), m_belt), (link, (0.0, 0.0, 0.0), m_pulley),
                             (link, tuple(span), m_pulley))))
    return tuple(out)


def _modules(model: RevoluteChain, couples: dict) -> list:
    """The chain of RSSR modules (001 Section 4, Fig. 6) that keeps the pseudobases' vertical lines: one per link
    from the level body to the farthest pseudobase, each module's vertical line the next one's base, so that
    module t carries the couples (N m, ``couples``: per pseudobase, its spring's post's largest) of every
    pseudobase at or beyond its link. Its auxiliary link is a tube as long as the link, offset
    :data:`RSSR_OFFSET` of it, sized to buckle at :data:`BUCKLING` times the couple over the offset, with two ball
    joints; each pseudobase adds one."""

    out = []
    links = sorted({t for b in couples for t in range(b.level, b.joint)})
    for t in links:
        moment = sum(m for b, m in couples.items() if b.level <= t < b.joint)
        ends = sum(1 for b in couples if b.joint == t + 1)  # pseudobases at this module's far end
        span = model.placements[t + 1][:3, 3]
        length = max(float(np.linalg.norm(span)), BELT_LEAST)
        offset = max(BELT_LEAST, RSSR_OFFSET * length)
        force = moment / offset
        tube = max(0.004, float((64 * BUCKLING * force * length**2 / (np.pi**3 * ALUMINIUM_E)) ** 0.25))
        m_tube = ALUMINIUM * np.pi * tube**2 / 4 * length
        balls = (2 + ends) * BALL_JOINT
        link = model.bodies[t + 1]
        out.append(Part("rssr", f"RSSR module ({model.joints[t]} to {model.joints[t + 1]})", link,
                        tuple(span / 2), m_tube + balls,
                        {"length": length, "offset": offset, "rod_diameter": tube, "ball_joints_mass_kg": balls},
                        {"largest_moment_Nm": moment, "largest_force_N": force},
                        ((link, tuple(span / 2), m_tube + balls),)))
    return out


def with_spring_mass(model: RevoluteChain, realised, kinds, coils, q) -> RevoluteChain:
    """The arm carrying its realised springs' hardware: every part's mass where :func:`parts` says it is
    carried; ``q`` (N, n) rad, the poses a point pulley's coil direction is taken over."""
    out = model
    names = tuple(f"S{i}" for i in range(1, len(realised) + 1))
    for part in parts(model, realised, kinds, coils, names, q):
        for link, point, m in part.carried:
            if m > 0:
                out = out.with_point_mass(link, point, m)
    return out
