"""Ideal springs made real: each as a helical extension spring wound from stocked wire
(:mod:`springlab.design.buildable`), zero-length where one can be wound, else a coil on one link whose
cable runs over a pulley at its end to the other (:func:`realise_springs`); the cable and its pulley
(:func:`cable_for`, :mod:`springlab.design.cables`), the coil side by side or over a pulley block where
one is too weak or too long (:func:`coil_for`); each cable's lead chosen clear of the cable's own
crossing of its pulley (:func:`lead_angles`), and the springs re-balanced for the pulley's
pose-dependent energy (sequential linear programmes, :func:`springlab.design.search.minimax`).
Where a lead cannot stay clear, a spring's torque is undefined at a pose (:func:`defined_torques`).
"""

from __future__ import annotations

import re

import numpy as np

from springlab import _checks
from springlab.design.buildable import Fitted, cable_spring, wires, zero_length_spring
from springlab.design.cables import CABLES, choose_cable
from springlab.design.hardware import HOOK_GAP
from springlab.design.search import (
    MAX_STIFFNESS,
    compass_searches,
    faces,
    minimax,
    sig,
    variable_scales,
)
from springlab.design.structure import NEGLIGIBLE, attachment_boxes
from springlab.energy.geometry import gravity_torques, joint_torques, spring_lengths
from springlab.errors import GeometryError, SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, check_point_springs, world_points
from springlab.model.springs import PointSpring


def realise_springs(model: RevoluteChain, springs, q, *, material: str = "music wire", pulley_radius: float = 0.0,
                    reach=None, fit=None, max_stiffness: float = MAX_STIFFNESS) -> tuple[tuple, tuple, tuple]:
    """Each ideal spring as a helical extension spring from stocked wire (:mod:`springlab.design.buildable`):
    a zero-length spring (F_i = k L_0) where one can be wound, else a spring mounted on link_a whose
    cable runs over a pulley at end A to end B, cut so that the force is k times the cable's path.
    Returns the realised springs (free length L_0 and initial tension F_i as wound; a cable spring's
    free length is the cable's equivalent, F_i / k), their kinds and coils.

    With ``pulley_radius`` (m) > 0 the pulley is modelled (route 2's cable path,
    :func:`springlab.energy.geometry.cable_geometry`): it adds a pose-dependent energy of about
    k L rho alpha that no ideal spring had. So the cable springs are re-balanced on the poses ``fit``
    (default: ``q``'s first 150): each spring's lead (the direction its cable arrives from) is chosen
    among its body's axes and the mean direction to B, and, where that leaves more than
    :data:`REBALANCE` of a joint's scale (its own peak gravity torque, or for a light joint ten times what
    the ideal springs leave on it), their rates and ends (within
    :func:`~springlab.design.structure.attachment_boxes` with ``reach``, rates at most ``max_stiffness``) are moved to bring the
    largest holding torque down again (sequential linear programmes, as the best springs are polished).
    The zero-length springs stay as designed.

    A re-balanced spring whose rate falls below :data:`DROP_RATE` of its designed rate carries next to
    nothing and is left out (its kind says so, as for a spring no wire realises).

    :raises SpringlabError: naming the spring when neither realisation fits
    """
    return realise_with_origins(model, springs, q, material=material, pulley_radius=pulley_radius, reach=reach, fit=fit,
                    max_stiffness=max_stiffness)[:3]


def realise_with_origins(model: RevoluteChain, springs, q, *, material, pulley_radius, reach, fit, max_stiffness):
    """:func:`realise_springs`, with a fourth tuple: per realised spring, the index of the ideal
    spring it realises."""

    q = model.check_q(q)
    pulley_radius = _checks.positive("pulley_radius", pulley_radius, allow_zero=True, unit="m")
    springs = check_point_springs(model, springs)
    R, o = body_frames(model, q)
    kinds = []
    for s in springs:
        lengths = length_range(model, s, R, o)
        coil, why = zero_length_spring(s.k, lengths, wires(material)[0])
        kinds.append(("zero-length spring", coil, lengths) if coil is not None else ("cable", None, why))
    cable = [i for i, (kind, _, _) in enumerate(kinds) if kind == "cable"]
    built = list(springs)
    if pulley_radius > 0:  # a cable whose ends come within the pulley's radius cannot run over it
        fit = q[:150] if fit is None else model.check_q(fit)
        Rf, of = body_frames(model, fit)
        near = [i for i in cable if min(length_range(model, springs[i], R, o)[0],
                                        length_range(model, springs[i], Rf, of)[0]) <= 2 * pulley_radius]
        cable = [i for i in cable if i not in near]
    else:
        near = []
    if pulley_radius > 0 and cable:
        fit = q[:150] if fit is None else model.check_q(fit)
        scale = _realised_scales(model, springs, fit)
        led = _leads(model, built, cable, fit, pulley_radius, scale, clear_q=q)
        built = led
        if max(_worst(model, led, fit, scale), _worst(model, led, q, scale)) > REBALANCE:  # the leads leave too much
            built = _rebalance(model, led, cable, fit, reach, max_stiffness, scale)
        def windable(spring):  # None: its cable comes within the pulley's radius of A at a pose of ``q``
            try:  # a stocked wire carries it alone or up to MAX_PARALLEL side by side, as the realisation winds it
                span = length_range(model, spring, R, o)
                return any(cable_spring(spring.k / m, span, wires(material)[0])[0] is not None for m in range(1, MAX_PARALLEL + 1))
            except GeometryError:
                return None

        built = list(built)
        swapped = []
        dense = _dense(model, q)
        for i in cable:  # a re-balanced spring no stocked wire carries, whose cable meets its pulley at a pose
            fits = windable(built[i])  # the fit did not see, or whose end now crosses its lead's line, keeps its
            crosses = built[i] is not led[i] and _lead_tier(_lead_clearance(model, built[i], dense)) == 2
            if fits is None or (not fits and windable(led[i])) or crosses:  # designed rate and ends
                built[i] = led[i]
                swapped.append(i)
        rest = [i for i in cable if i not in swapped]
        if swapped and rest and _worst(model, built, q, scale) > REBALANCE:  # the others re-balanced around them
            again = _rebalance(model, led, rest, fit, reach, max_stiffness, scale)  # from the leads, as the first
            if all(windable(again[i]) and _lead_tier(_lead_clearance(model, again[i], dense)) < 2 for i in rest):
                built = list(again)
        if swapped and sig(_worst(model, built, fit, scale)) > sig(_worst(model, led, fit, scale)):
            built = list(led)  # the others were re-balanced around the springs put back: the leads alone do better
    out, names, coils, origins = [], [], [], []
    for i, s in enumerate(built):
        kind, coil, detail = kinds[i]
        origins.append(i)
        if kind == "zero-length spring":
            out.append(PointSpring(s.link_a, s.point_a, s.link_b, s.point_b, s.k, coil.free_length, s.k * coil.free_length))
            names.append(kind)
            coils.append(Fitted(coil, detail))
            continue
        if s.k < DROP_RATE * springs[i].k:
            names.append(f"not realised: spring S{i + 1} ({s.label}): the re-balance over the pulleys took its rate "
                         f"from {springs[i].k:.4g} to {s.k:.3g} N/m ({100 * s.k / springs[i].k:.2g} % of it), so it "
                         "carries next to nothing")
            out.append(None)
            coils.append(None)
            continue
        lengths = length_range(model, s, R, o)
        room, block = coil_room(model, s, lengths)
        found = coil_for(s.k, lengths, room, material, block=block)  # side by side where one wire is too weak, over
        # a block where the coil would reach past its joint
        coil, why_cable = (found[0], found[1]) if found[0] is None else (found[0], "")  # where too long for its link
        ratio, parallel = (found[1], found[2]) if coil is not None else (1, 1)
        if coil is None:
            names.append(f"not realised: spring S{i + 1} ({s.label}, k = {s.k:.4g} N/m): no zero-length spring "
                         f"({detail}) and no cable spring ({why_cable}), nor {MAX_PARALLEL} side by side")
            out.append(None)
            coils.append(None)
            continue
        k = s.k / parallel
        try:  # the stocked cable that carries its pull (the flags say when the pulley is too small for it)
            rope = cable_for(k * lengths[1], s.pulley_radius)
        except SpringlabError:
            rope = None
        tension = coil.initial_tension / ratio  # along the cable: a block divides the coil's pull
        single = parallel > 1 and coil_for(s.k, lengths, np.inf, material)[0] is not None
        for m in range(parallel):
            if m:
                origins.append(i)
            out.append(PointSpring(s.link_a, s.point_a, s.link_b, s.point_b, k, tension / k,
                                   tension, s.pulley_radius, s.lead))
            names.append("cable over a pulley" + (f", with a {ratio}:1 pulley block" if ratio > 1 else "")
                         + (f" ({m + 1} of {parallel} side by side" + (", so that each coil fit its link)" if single
                                                                      else ")") if parallel > 1 else "")
                         + (" (a point pulley: its ends come within twice the pulley's radius)" if i in near else ""))
            coils.append(Fitted(coil, lengths, ratio, rope))
    return tuple(out), tuple(names), tuple(coils), tuple(origins)


def sized_pulley(model: RevoluteChain, springs, q) -> float:
    """The two-point springs' one pulley radius (m), sized to the cable of the largest pull (N) any of them
    pulls over the poses ``q`` (:mod:`springlab.design.cables`: the rope maker's D/d); the strongest
    cable's where none carries it (the flags then say so)."""

    R, o = body_frames(model, q)
    pull = max((s.k * length_range(model, s, R, o)[1] for s in springs), default=0.0)
    try:
        return choose_cable(pull).pulley_radius
    except SpringlabError:
        return CABLES[-1].pulley_radius


REBALANCE = 0.1
"""Where the realised springs over their pulleys, leads chosen, leave more than this fraction of a
joint's scale (its own peak gravity torque, or for a light joint ten times what the ideal springs leave
on it) on the fitting poses, their rates and ends are re-balanced too."""


DROP_RATE = 0.01
"""A cable spring the re-balance leaves with less than this fraction of its designed rate carries next to
nothing: the realisation leaves it out (the Z1's S7 went from 5.2 to 0.007 N/m, a 0.1 mm wire 8 m long)."""


REBALANCE_STEPS = 40
"""The most linear programmes the re-balance of the cable springs takes (each on a finite-difference
Jacobian, 7 route-2 evaluations per cable spring)."""


MAX_PARALLEL = 3
"""The most springs a realised spring is split into, side by side on the same ends, when no stocked
wire carries its force alone."""


def length_range(model: RevoluteChain, spring, R, o) -> tuple[float, float]:
    """The shortest and longest length (m) of a spring (its cable's path over a pulley) at the poses."""

    length = spring_lengths(model, [spring], R, o)[0]
    return max(float(length.min()), 1e-6), max(float(length.max()), 1e-6)


def _worst(model: RevoluteChain, springs, q, scale) -> float:
    return float(np.max(np.abs(joint_torques(model, springs, q)) / scale))


def with_changes(s, **changes) -> PointSpring:
    fields = {"link_a": s.link_a, "point_a": s.point_a, "link_b": s.link_b, "point_b": s.point_b, "k": s.k,
              "free_length": s.free_length, "initial_tension": s.initial_tension, "pulley_radius": s.pulley_radius,
              "lead": s.lead}
    return PointSpring(**(fields | changes))


LEAD_CLEAR = 0.1
"""rad: a cable spring's lead is chosen, where one can be, so that at every pose of the design's check B
stays at least this far in angle from the lead's line through A (:func:`lead_angles`): where B crosses
that line a swivelling pulley must turn half a turn at once and the cable's pull jumps (over 5 mm
pulleys the UR5's S2 passed within 1e-6 rad of its line, its elbow torque jumping by 4 N m)."""


LEAD_AXES = 2
"""How many of the directions that B keeps furthest from (``_clearest_axes``) join a cable spring's
candidate leads."""


def _clearest_axes(model: RevoluteChain, spring, q, count: int = LEAD_AXES, directions: int = 400) -> np.ndarray:
    """The ``count`` lines through A (unit vectors in body a's frame, (count, 3)) that the direction from A
    to the spring's end B keeps furthest from, in angle, over the poses ``q``: the best of ``directions``
    spread evenly over a hemisphere (a line and its opposite are one)."""
    d = _span(model, spring, *body_frames(model, q))
    d /= np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
    k = np.arange(directions) + 0.5  # a Fibonacci lattice on the upper hemisphere
    z, phi = k / directions, np.pi * (1 + 5 ** 0.5) * k
    U = np.column_stack([np.sqrt(1 - z**2) * np.cos(phi), np.sqrt(1 - z**2) * np.sin(phi), z])
    nearest = np.min(np.arccos(np.clip(np.abs(d @ U.T), 0.0, 1.0)), axis=0)
    keys = [-sig(v) for v in nearest]
    return U[np.argsort(keys, kind="stable")[:count]]


def _lead_tier(clearance: float) -> int:
    """0: B keeps :data:`LEAD_CLEAR` from the lead's line; 1: it comes nearer, but not within
    :data:`CROSSING`; 2: it does (the audit flags a third of that: a margin, since it searches other poses)."""
    return 0 if clearance >= LEAD_CLEAR else 1 if clearance >= CROSSING else 2


LEAD_SAMPLES = 20_000
"""Random poses of the workspace's box (their own seed) on which a candidate lead's clearance is measured
(``_lead_clearance``): as many as the audit's, so that the two find the same near crossings."""


def _dense(model: RevoluteChain, q):
    """:data:`LEAD_SAMPLES` random poses within the box of the poses ``q`` (their own seed), with their body
    frames, and the box: what the leads' clearances are measured on."""
    lo, hi = np.min(q, axis=0), np.max(q, axis=0)
    dense = np.random.default_rng([LEAD_SAMPLES, model.n]).uniform(lo, hi, (LEAD_SAMPLES, model.n))
    return dense, body_frames(model, dense), lo, hi


def _lead_clearance(model: RevoluteChain, spring, dense) -> float:
    """rad: how near B comes to a cable spring's lead line over the poses of ``dense`` (``_dense``): the
    nearest of them, refined by a compass search towards the line within their box until it is taken to cross
    (:data:`CROSSING`)."""
    return _lead_clearances(model, [spring], dense)[0]


def _lead_clearances(model: RevoluteChain, springs, dense) -> list[float]:
    """:func:`_lead_clearance` of each of ``springs``, value for value: B - A is computed once per spring's ends
    (whatever its lead), and the refining searches run in lockstep
    (:func:`~springlab.design.search.compass_searches`), one call of the body frames a step for them all."""
    q, frames, lo, hi = dense
    ends = [(s.link_a, s.point_a, s.link_b, s.point_b) for s in springs]
    spans = {e: _span(model, s, *frames) for e, s in zip(ends, springs, strict=True)}
    angles = [_lead_angles(model, s, spans[e]) for e, s in zip(ends, springs, strict=True)]
    found = [float(a.min()) for a in angles]
    search = [m for m, a in enumerate(found) if not a < CROSSING]  # already near enough: no need to refine
    if search:
        starts = np.array([q[int(np.argmin(angles[m]))] for m in search])
        best = compass_searches(towards_leads(model, [springs[m] for m in search]), starts, lo, hi, enough=-CROSSING)[1]
        for m, v in zip(search, best, strict=True):
            found[m] = -float(v)
    return [sig(v) for v in found]


def _leads(model: RevoluteChain, springs, cable, q, radius: float, scale, clear_q=None) -> list:
    """Each cable spring over a pulley of ``radius`` (m), its lead (in link_a's frame) chosen, one
    spring at a time and twice over, among +-x, +-y, +-z of link_a, the direction from its joint to A
    and the mean direction from A to B and its opposite: whichever leaves the smallest largest
    holding torque (relative to each joint's ``scale``, N m) at the poses ``q``, among the leads
    whose line B keeps :data:`LEAD_CLEAR` from (:func:`_lead_clearance` over the poses ``clear_q``,
    default ``q``) where any does, else among those it does not cross (:func:`_lead_tier`); the
    candidates include the lines B keeps furthest from (:func:`_clearest_axes`)."""

    clear_q = q if clear_q is None else clear_q
    R, o = body_frames(model, q)
    out = list(springs)
    candidates = {}
    for i in cable:
        s = springs[i]
        pa = model.locate(s.link_a, s.point_a)[1]
        towards = np.sum(_span(model, s, R, o), axis=0)  # summed over the poses, in body a's frame
        own = np.asarray(model.locate(s.link_a, (0.0, 0.0, 0.0))[1])  # link_a's origin in body a's frame
        found = [*np.eye(3), *-np.eye(3), towards, -towards, np.asarray(pa) - own]
        rotation = model.rotation(s.link_a)  # link_a -> body
        found += list(_clearest_axes(model, s, clear_q))
        candidates[i] = [tuple(rotation.T @ (u / np.linalg.norm(u))) for u in found if np.linalg.norm(u) > 1e-9]
        out[i] = with_changes(s, pulley_radius=radius, lead=candidates[i][-1 - LEAD_AXES])  # link_a's origin to A, or -towards
    dense = _dense(model, clear_q)
    trying = [with_changes(out[i], lead=u) for i in cable for u in candidates[i]]
    tiers = iter(_lead_tier(v) for v in _lead_clearances(model, trying, dense))
    crosses = {i: [next(tiers) for _ in candidates[i]] for i in cable}
    for _ in range(2):
        for i in cable:
            trials = [(crosses[i][c], out[:i] + [with_changes(out[i], lead=u)] + out[i + 1:]) for c, u in enumerate(candidates[i])]
            out = min(trials, key=lambda t: (t[0], sig(_worst(model, t[1], q, scale))))[1]  # ties to the first lead
    return out


def _rebalance(model: RevoluteChain, springs, cable, q, reach, max_stiffness, scale) -> list:
    """Move the cable springs' rates and ends (within :func:`~springlab.design.structure.attachment_boxes`) to bring the largest
    holding torque at the poses ``q``, relative to each joint's ``scale`` (N m), down
    (:func:`~springlab.design.search.minimax`, at most :data:`REBALANCE_STEPS` programmes on a finite-difference Jacobian).
    Kept only where it lowers the largest torque."""
    centres, half = attachment_boxes(model, reach)
    ends = {i: (model.locate(springs[i].link_a, springs[i].point_a), model.locate(springs[i].link_b, springs[i].point_b))
            for i in cable}
    x0, lo, hi = [], [], []
    for i in cable:
        (a, pa), (b, pb) = ends[i]
        (lo_a, hi_a), (lo_b, hi_b) = faces(centres[a], half[a]), faces(centres[b], half[b])
        x0 += [springs[i].k, *pa, *pb]
        lo += [0.0, *lo_a, *lo_b]
        hi += [max_stiffness, *hi_a, *hi_b]
    x0, lo, hi = (np.array(v, dtype=float) for v in (x0, lo, hi))
    lo, hi = np.minimum(lo, x0), np.maximum(hi, x0)  # the designed springs stay reachable
    x0 = np.clip(x0, lo, hi)
    leads = {i: tuple(model.direction(springs[i].link_a, springs[i].lead)[1]) for i in cable}  # in the bodies' frames

    def build(x):
        out = list(springs)
        for m, i in enumerate(cable):
            (a, _), (b, _) = ends[i]
            v = x[7 * m:7 * m + 7]
            out[i] = PointSpring(model.bodies[a], tuple(v[1:4]), model.bodies[b], tuple(v[4:7]), max(v[0], 1e-9),
                                 pulley_radius=springs[i].pulley_radius, lead=leads[i])
        return out

    def residual(v):
        return (joint_torques(model, build(v), q) / scale).ravel()

    def jacobian(v, r):  # forward differences, a step of 1e-7 of each variable's scale, inward at a bound
        J = np.empty((len(r), len(v)))
        for c in range(len(v)):
            step = 1e-7 * var_scale[c] * (1 if v[c] + 1e-7 * var_scale[c] <= hi[c] else -1)
            w = v.copy()
            w[c] += step
            J[:, c] = (residual(w) - r) / step
        return J

    var_scale = variable_scales(lo, hi, max_stiffness, x0)
    x = minimax(x0, lo, hi, var_scale, residual, jacobian, REBALANCE_STEPS, groups=np.tile(np.arange(model.n), len(q)),
                 spread=1.0)
    better = sig(_worst(model, build(x), q, scale)) < sig(_worst(model, build(x0), q, scale))
    return build(x if better else x0)


def _realised_scales(model: RevoluteChain, springs, q) -> np.ndarray:
    """Each joint's scale (N m) for the realised springs' leads and re-balance over the poses ``q``: its own
    peak gravity torque, or ten times what the ideal ``springs`` leave there where that is more (a light
    joint the ideal springs leave near its own peak does not take the pulleys' whole correction: held to
    its own peak, the Panda's joint 7, 0.03 N m, set the whole re-balance and cost a shoulder joint half
    its balance), a tenth of the arm's largest for a joint gravity leaves (nearly) alone."""
    peak = np.max(np.abs(gravity_torques(model, q)), axis=0)
    left = np.max(np.abs(joint_torques(model, springs, q)), axis=0)
    return np.where(peak > NEGLIGIBLE * np.max(peak), np.maximum(peak, left / REBALANCE), 0.1 * np.max(peak))


def _span(model: RevoluteChain, spring, R, o) -> np.ndarray:
    """B - A (m), (N, 3), in body a's frame at the poses whose body frames are ``R``, ``o``."""

    a, pa = model.locate(spring.link_a, spring.point_a)
    B = world_points(R, o, *model.locate(spring.link_b, spring.point_b))
    return np.einsum("pji,pj->pi", R[:, a], B - world_points(R, o, a, pa))


def lead_angles(model: RevoluteChain, spring, q, frames=None) -> np.ndarray:
    """rad, (N,): at each pose ``q``, how far the direction from a cable spring's pulley (at A) to its
    end B lies from the line of its lead, either way: min(alpha, pi - alpha), alpha the angle between
    the lead and B - A. Where it is zero the pulley, which swivels about the lead to hold B in its plane,
    must turn half a turn at once, and the cable's line of action jumps (route 2's
    :func:`springlab.energy.geometry.cable_geometry` is discontinuous there). ``frames``: the poses'
    body frames (:func:`springlab.model.revolute.body_frames`), where already computed."""
    return _lead_angles(model, spring, _span(model, spring, *(body_frames(model, q) if frames is None else frames)))


def towards_leads(model: RevoluteChain, springs):
    """The value :func:`~springlab.design.search.compass_searches` climbs towards each of ``springs``' lead
    line, search s towards ``springs[s]``'s: minus :func:`lead_angles` at each trial pose, the body frames
    of every search's trials computed in one call."""

    def value(trials, which):
        A, M, n = trials.shape
        R, o = body_frames(model, trials.reshape(A * M, n))
        return np.stack([-_lead_angles(model, springs[s], _span(model, springs[s], R[a * M:(a + 1) * M], o[a * M:(a + 1) * M]))
                         for a, s in enumerate(which)])

    return value


def _lead_angles(model: RevoluteChain, spring, d) -> np.ndarray:
    """:func:`lead_angles` from B - A, ``d`` (N, 3) m in body a's frame (:func:`_span`)."""
    u = np.asarray(model.direction(spring.link_a, spring.lead)[1])
    along = np.abs(d @ u)
    across = np.linalg.norm(np.cross(d, u), axis=1)
    return np.arctan2(across, along)  # accurate near the line, where arccos of the cosine loses half the digits


CROSSING = 1e-3
"""rad: a lead whose line a cable spring's end B comes within this angle of (20,000 poses, then a compass
search towards the line) is taken to be crossed, and avoided; the audit flags a realised spring whose end
comes within a third of it (its own sample and search: a margin)."""


def defined_torques(model: RevoluteChain, springs, q) -> tuple[np.ndarray, str]:
    """Route 2's holding torques (N m, (N, n)) at the poses ``q``, nan at the poses where a spring has no
    line of action (route 2 raises GeometryError there: a cable's end within its pulley's radius, a
    spring's ends coinciding), found by halving the batch; and the first such reason ('' for none)."""
    try:
        return joint_torques(model, springs, q), ""
    except GeometryError as err:
        if len(q) == 1:
            m = next(m for m, s in enumerate(springs) if not _defined(model, s, q))  # which spring
            return (np.full((1, model.n), np.nan),
                    f"spring {m + 1} ({springs[m].label}): " + str(err).split(" at pose ")[0])
        half = len(q) // 2
        (first, why_1), (second, why_2) = defined_torques(model, springs, q[:half]), defined_torques(model, springs, q[half:])
        return np.vstack([first, second]), why_1 or why_2


def _defined(model: RevoluteChain, spring, q) -> bool:
    """Whether route 2 gives ``spring`` a line of action at the poses ``q``."""
    try:
        joint_torques(model, [spring], q)
    except GeometryError:
        return False
    return True


def coil_room(model: RevoluteChain, spring, lengths) -> tuple[float, float]:
    """The room (m) a cable spring's coil has on link_a, from behind its pulley to the link's joint in the
    plane the joint turns in (the base: unbounded), and what a pulley block's travelling sheave takes
    from it (m), for the rope that carries its largest pull over ``lengths`` (m)."""

    body, at = model.locate(spring.link_a, spring.point_a)
    rho = spring.pulley_radius
    try:
        d = cable_for(spring.k * float(lengths[1]), rho).diameter if rho > 0 else 0.0
    except SpringlabError:
        d = 0.0
    if not 0 < body <= model.n:
        return float("inf"), 2 * (rho + d)
    w = np.asarray(model.axes[body - 1], dtype=float)
    return float(np.linalg.norm(at - (at @ w) * w)) - rho - HOOK_GAP - d, 2 * (rho + d)


def _side_by_side(kind: str) -> str:
    """Why a realised spring is one of several side by side, from its kind
    (:func:`~springlab.design.realise.coil_for`'s order: the fewest that a stocked wire carries and whose
    coil fits its link)."""
    if "stock part " in kind:
        return "one stock part is too weak, or too stiff for its lengths, alone"
    return ("one coil would be longer than its link" if "fit its link" in kind else
            "no stocked wire carries its force alone")


def realisation_changes(model: RevoluteChain, ideal, realised, kinds, origins) -> tuple:
    """Per realised spring, what the realisation changed of the ideal spring it realises (``origins``:
    its index), and why, in words: the rate (N/m, and the share), each end's move (mm), the pulley and
    its lead, a pulley block, a split side by side; or that only its free length and initial tension
    were chosen."""
    out = []
    for r, kind, i in zip(realised, kinds, origins, strict=True):
        s = ideal[i]
        if kind == "zero-length spring":
            out.append("the designed rate and ends; wound with an initial tension equal to k times its free length")
            continue
        parts = []
        together = sum(x.k for x, o in zip(realised, origins, strict=True) if o == i)
        if f"{together:.4g}" != f"{s.k:.4g}":
            parts.append(f"rate {s.k:.4g} -> {together:.4g} N/m ({100 * (together / s.k - 1):+.1f} %)")
        moves = []
        for end, (link_i, p_i), (link_r, p_r) in (("A", (s.link_a, s.point_a), (r.link_a, r.point_a)),
                                                   ("B", (s.link_b, s.point_b), (r.link_b, r.point_b))):
            bi, pi = model.locate(link_i, p_i)
            br, pr = model.locate(link_r, p_r)
            d = float(np.linalg.norm(np.asarray(pr) - np.asarray(pi)))
            if bi != br or d >= 5e-5:
                moves.append(f"end {end} moved {1e3 * d:.1f} mm")
        parts += moves
        why = ("re-balanced for its pulley: the wrap adds about k rho times the change of the wrap angle, which the "
               "ideal springs did not have" if parts else "")
        stock = re.search(r"stock part (.+?)(?: \(\d+ of \d+ side by side.*)?$", kind)
        if stock and parts:  # the layout's balance fixes the rate times the two lengths
            why = (f"re-placed for stock part {stock.group(1)}'s rate, the product of the rate and the two lengths "
                   "kept, and re-balanced for its pulley")
        how = (f"a cable over a {1e3 * r.pulley_radius:g} mm pulley at end A, its lead (the direction the cable arrives "
               "from) chosen for the least torque left" if r.pulley_radius > 0 else
               "a cable over a point pulley at end A (its coil on link A), the force k times |B - A|")
        text = how + ("; " + ", ".join(parts) + " (" + why + ")" if parts else "; the designed rate and ends")
        ratio = re.search(r"(\d):1 pulley block", kind)
        if ratio:
            text += (f"; over a {ratio.group(1)}:1 pulley block (its coil moves 1/{ratio.group(1)} of the cable's path "
                     f"at {ratio.group(1)} times its pull): a coil on the cable alone would be longer than its link")
        count = origins.count(i)
        if count > 1:
            text += f"; one of {count} side by side at k / {count} each: {_side_by_side(kind)}"
        out.append(text)
    return tuple(out)


BLOCKS = (1, 2, 3, 4)
"""The pulley blocks a coil too long for its link is tried with, in turn: the coil moves 1 / n of the cable's
path at n times its pull."""


def coil_for(k: float, lengths, room: float, material: str, *, block: float = 0.0):
    """The coil, pulley block and side-by-side count for a cable spring of rate ``k`` (N/m) over cable paths
    ``lengths`` (m): the fewest side by side (up to :data:`~springlab.design.realise.MAX_PARALLEL`), then the
    least block (:data:`BLOCKS`), then the first of the material's wires
    (:func:`~springlab.design.buildable.wires`: ``'auto'`` tries music wire, then chrome silicon), whose coil is
    no longer than ``room`` (m) in service (less ``block``, m, what a block's travelling sheave takes, for a
    block); where none fits, the shortest coil of the fewest side by side (the design's flags then say so).
    Returns (coil, ratio, parallel) or (None, why)."""

    lengths = np.asarray(lengths, dtype=float)
    best, why = None, ""
    for parallel in range(1, MAX_PARALLEL + 1):
        for n in BLOCKS:
            for wire in wires(material):
                coil, reason = cable_spring(k * n * n / parallel, lengths / n, wire)
                why = why or reason
                if coil is None:
                    continue
                if coil.max_length <= room - (block if n > 1 else 0.0):
                    return coil, n, parallel
                if best is None or (parallel, coil.max_length) < (best[2], best[0].max_length):
                    best = (coil, n, parallel)  # none fits: the fewest side by side, the shortest of those
    return best if best is not None else (None, why)


def cable_for(pull: float, given: float | None):
    """The stocked cable for a pull (N) over a given pulley (m; None or 0: sized to the cable): the one with
    the least pulley that carries it, among those the given pulley fits where one does (else by strength
    alone: the design's flags name the pulley too small for it)."""

    if given:
        try:
            return choose_cable(pull, pulley_radius=given)
        except SpringlabError:
            pass
    return choose_cable(pull)
