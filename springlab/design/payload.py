"""The payload a design holds, and the payload dial that keeps it balanced when the payload changes.

A design is made for a nominal payload: a point mass at a frame of the arm (the tip frame's origin
for ``springlab design --payload``). Another payload adds (or takes off) a point mass there
(:meth:`springlab.model.revolute.RevoluteChain.with_point_mass`), whose gravity torques are linear
in its mass; the springs, unchanged, leave those torques unbalanced (:func:`payload_torques`).

**The dial.** Moving a zero-free-length spring's end A by a fixed vector d in its link's frame
changes its energy from k |B - A|^2 / 2 to k |B - A - d|^2 / 2 = k |B - A|^2 / 2 - k d . (B - A)
+ k |d|^2 / 2: the last term is a constant (d turns with its link), so the holding torques are
exactly linear in the moves, as they are in the payload's mass. The moves that cancel one
kilogram are therefore a linear least-squares problem over the design's poses: route 2's torques
of the payload's kilogram against those of unit moves of the candidate ends. Three sets are tried,
in the order an engineer would rather adjust them:

1. the ends on the bodies the loaded joints do not move (anchors on the base, the usual slot of
   a gravity balancer);
2. every spring's proximal end (the one on the body nearer the base);
3. each single end alone.

A set is exact when what it leaves of the kilogram's torques is round-off (:data:`EXACT`); the
first exact set is the dial. Where none is, the dial is whichever of them (the best single end
among them) leaves the least, and what each leaves is stated. For a planar chain balanced by springlab's construction the base
anchors are exact: each anchor's product with its spring's other offset is what gravity's first
moment fixes, and that is linear in the payload.

Springs with a free length, or cables over a pulley, are not linear in the moves: their dial is the
linearisation (finite differences of :data:`STEP`), and :func:`payload_torques` checks it by route 2
at the payloads themselves.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from springlab import _checks
from springlab.design.arms import ArmDesign, ends_outside
from springlab.design.realise import defined_torques
from springlab.design.structure import attachment_boxes
from springlab.energy.geometry import gravity_torques, joint_torques, spring_lengths
from springlab.errors import GeometryError, SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, check_point_springs
from springlab.model.springs import PointSpring
from springlab.tables import Table

EXACT = 1e-9
"""A set of moves restores the balance exactly when the largest holding torque it leaves of one
kilogram's is at most this fraction of the kilogram's own largest (round-off is about 1e-14)."""

STEP = 1e-3
"""m: the moves' finite-difference step (exact for zero-free-length springs, whose torques are
linear in the moves; a linearisation for the others)."""

DIAL_SPAN = 0.1
"""A payload dial is worth turning where the payloads over which it keeps every moved end on its link
span at least this fraction of the payloads studied (a dial for 0 to 1 kg that holds 20 g is none)."""

MAX_PAYLOAD_RANGE = 1e3
"""kg: the largest payload a range may reach (more is a unit mistake for an arm's payload)."""


@dataclass(frozen=True)
class PayloadDial:
    """Which spring ends to move, and by how much per kilogram of payload, to keep the balance.

    :ivar frame: the frame the payload is carried at (a link name)
    :ivar point: where in that frame (m)
    :ivar moves: per moved end, (spring index, 'A' or 'B', link name, the move per kilogram as a
        vector in that link's frame, m/kg)
    :ivar exact: True when the moves restore the balance exactly (to :data:`EXACT`)
    :ivar left: the largest holding torque the moves leave of one kilogram's, as a fraction of the
        kilogram's own largest (0 exact, 1 nothing restored)
    :ivar how: which candidate set the moves come from, in words
    """

    frame: str
    point: tuple
    moves: tuple
    exact: bool
    left: float
    how: str

    def turned(self, springs, kg: float) -> tuple:
        """The springs with the dial turned for ``kg`` (kg, may be negative) more payload."""
        kg = _checks.finite("kg", kg, unit="kg")
        out = list(springs)
        for i, end, _, per_kg in self.moves:
            out[i] = _moved(out[i], end, kg * np.asarray(per_kg))
        return tuple(out)

    def table(self, names=None) -> Table:
        """Each move: the spring (``names``, by default S1, S2, ... in order), its end and link, the move
        per kilogram (mm/kg, in the link's frame) and its size (mm/kg)."""
        return Table(["spring", "end", "link", "move per kg (mm/kg, link frame)", "size of the move (mm/kg)"],
                     [(names[i] if names else f"S{i + 1}", end, link, "(" + ", ".join(f"{round(1e3 * v, 2) + 0.0:.2f}" for v in per_kg) + ")",
                       f"{1e3 * float(np.linalg.norm(per_kg)):.2f}") for i, end, link, per_kg in self.moves])

    def as_dict(self, names=None) -> dict:
        """For ``springlab design --json``: lengths in m per kg, in each link's frame; each move's spring by
        its place in the list (1, 2, ...) and by its name (``names``, by default S1, S2, ...)."""
        return {"frame": self.frame, "point_m": list(self.point), "exact": self.exact,
                "left_fraction": self.left, "how": self.how,
                "moves": [{"spring": i + 1, "name": names[i] if names else f"S{i + 1}", "end": end, "link": link,
                           "move_m_per_kg": list(map(float, per_kg))} for i, end, link, per_kg in self.moves]}


def _moved(spring: PointSpring, end: str, by) -> PointSpring:
    """The spring with its end 'A' or 'B' moved by ``by`` (m, in that end's link frame)."""
    name = "point_a" if end == "A" else "point_b"
    return replace(spring, **{name: tuple(np.asarray(getattr(spring, name)) + by)})


def _ground(model: RevoluteChain, q) -> int:
    """The last body the loaded joints do not move: bodies 0..this index are the loaded chain's base."""

    peak = np.max(np.abs(gravity_torques(model, q)), axis=0)
    loaded = np.flatnonzero(peak > 1e-10 * max(float(np.max(peak)), 1e-300))
    return int(loaded[0]) if len(loaded) else model.n


def _columns(model, springs, q, ends, base):
    """Route 2's holding torques (N m, flattened over poses and joints) of unit moves of ``ends``
    ((spring, 'A' or 'B') each, three axes of its body), by finite differences of :data:`STEP`."""
    columns = []
    for i, end in ends:
        s = springs[i]
        for e in np.eye(3):
            link = s.link_a if end == "A" else s.link_b
            axis = np.linalg.solve(model.rotation(link), e)  # the body's axis e in the link's frame
            moved = list(springs)
            moved[i] = _moved(s, end, STEP * axis)
            columns.append(((joint_torques(model, moved, q) - base) / STEP).ravel())
    return np.array(columns).T


def payload_dial(model: RevoluteChain, springs, q, frame: str, point=(0.0, 0.0, 0.0), *, ends=None) -> PayloadDial:
    """The payload dial of ``springs`` on ``model`` (module docstring) over the poses ``q`` (N, n) rad,
    for a payload at ``point`` (m) in ``frame``. ``ends`` ((spring index, 'A' or 'B') each) fixes the
    ends to move (for the realised springs: those of the ideal springs' dial); the moves are then
    those that leave the least, exact or not.

    :raises SpringlabError: when there are no springs to move, or the payload loads no joint
    """
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    springs = check_point_springs(model, springs)
    q = model.check_q(q)
    point = tuple(float(v) for v in _checks.real_array("point", point, shape=(3,)))
    if not springs:
        raise SpringlabError("a payload dial moves spring ends: this design has no springs")
    base = joint_torques(model, springs, q)
    kilo = (joint_torques(model.with_point_mass(frame, point, 1.0), springs, q) - base).ravel()
    scale = float(np.max(np.abs(kilo)))
    if scale == 0:
        raise SpringlabError(f"a payload at {point} in {frame!r} loads no joint: nothing to dial")
    cache = {}

    def solve(chosen):
        J = np.hstack([cache.setdefault(e, _columns(model, springs, q, [e], base)) for e in chosen])
        x, *_ = np.linalg.lstsq(J, -kilo, rcond=1e-12)
        return x, float(np.max(np.abs(kilo + J @ x))) / scale

    if ends is not None:
        ends = [(_checks.count("ends: spring index", i), _checks.choice("ends: end", e, ("A", "B"))) for i, e in ends]
        if not ends or any(i >= len(springs) for i, _ in ends):
            raise SpringlabError(f"ends = {ends}: give (spring index 0..{len(springs) - 1}, 'A' or 'B') pairs")
        x, left = solve(ends)
        return PayloadDial(frame, point, _moves(model, springs, ends, x), left <= EXACT, left,
                           "the ends given (those of the ideal springs' dial)")
    ground = _ground(model, q)
    body = [(model.locate(s.link_a, (0, 0, 0))[0], model.locate(s.link_b, (0, 0, 0))[0]) for s in springs]
    proximal = [(i, "A" if a <= b else "B") for i, (a, b) in enumerate(body)]
    sets = []
    anchors = [(i, end) for i, end in proximal if min(body[i]) <= ground]
    if anchors:
        sets.append((anchors, "the springs' anchors on the bodies the loaded joints do not move"))
    if len(proximal) > len(anchors):
        sets.append((proximal, "every spring's end on the body nearer the base"))
    tried = []
    for ends, how in sets:
        x, left = solve(ends)
        if left <= EXACT:
            return PayloadDial(frame, point, _moves(model, springs, ends, x), True, left, how)
        tried.append((left, ends, x, how))
    single = None
    for e in [(i, end) for i in range(len(springs)) for end in "AB"]:
        x, left = solve([e])
        if single is None or left < single[0] - 1e-12:
            single = (left, [e], x, "the best single end")
    if single[0] <= EXACT:
        return PayloadDial(frame, point, _moves(model, springs, single[1], x=single[2]), True, single[0], "a single end")
    left, ends, x, how = min([single, *tried], key=lambda t: t[0])
    others = "; ".join(f"{h}: {100 * v:.2g} %" for v, _, _, h in [single, *tried] if h != how)
    return PayloadDial(frame, point, _moves(model, springs, ends, x), False, left,
                       f"{how}, which leave the least of the kilogram's torque ({100 * left:.2g} %; no set of ends "
                       f"restores the balance exactly; {others})")


def _moves(model, springs, ends, x) -> tuple:
    out = []
    for m, (i, end) in enumerate(ends):
        link = springs[i].link_a if end == "A" else springs[i].link_b
        per_kg = np.linalg.solve(model.rotation(link), x[3 * m:3 * m + 3])  # body frame -> link frame
        if np.linalg.norm(per_kg) > 1e-12:
            out.append((i, end, link, tuple(float(v) + 0.0 for v in per_kg)))
    return tuple(out)


def payload_range(low, high) -> tuple[float, float]:
    """A payload range (kg), checked: finite, 0 <= low <= high <= :data:`MAX_PAYLOAD_RANGE`."""
    low = _checks.finite("payload range: low", low, unit="kg")
    high = _checks.finite("payload range: high", high, unit="kg")
    if low < 0 or high < low or high > MAX_PAYLOAD_RANGE:
        raise SpringlabError(f"payload range = {low:g} to {high:g} kg: give 0 <= low <= high <= "
                             f"{MAX_PAYLOAD_RANGE:g} kg, e.g. 0 to 5 kg")
    return low, high


def payload_torques(model: RevoluteChain, springs, q, frame: str, masses, *, nominal: float = 0.0,
                    point=(0.0, 0.0, 0.0), dial: PayloadDial | None = None) -> np.ndarray:
    """Route 2's peak holding torque (N m) per joint over the poses ``q``, at each payload of
    ``masses`` (kg): ``model`` carries ``nominal`` kg at ``point`` in ``frame``, each payload changes
    it; with ``dial``, the dial turned for the change. (len(masses), n)."""
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    springs = check_point_springs(model, springs)
    q = model.check_q(q)
    nominal = _checks.positive("nominal", nominal, allow_zero=True, unit="kg")
    masses = _checks.real_array("masses", masses, shape=(None,))
    if np.any(masses < 0):
        raise SpringlabError(f"masses = {masses.tolist()} kg: a payload is at least 0 kg")
    out = []
    for m in masses:
        carried = model.with_point_mass(frame, point, float(m) - nominal)
        used = springs if dial is None else dial.turned(springs, float(m) - nominal)
        out.append(np.max(np.abs(_defined(carried, used, q)), axis=0))
    return np.array(out)


def _defined(model, springs, q) -> np.ndarray:
    """Route 2's holding torques (N m) at the poses where every spring has a line of action (a dial
    turned far can bring a cable's end within its pulley's radius: those poses count as 0 here, and
    :func:`payload_study` names them)."""

    tau = defined_torques(model, springs, q)[0]
    return np.where(np.isnan(tau), 0.0, tau)


def _undefined(model, springs, q) -> int:
    """How many of the poses ``q`` leave a spring of ``springs`` without a line of action."""

    return int(np.sum(np.isnan(defined_torques(model, springs, q)[0][:, 0])))


@dataclass(frozen=True)
class PayloadStudy:
    """A design's springs at other payloads than its nominal one, unchanged and with the dial turned.

    :ivar frame: the frame the payload is carried at; ``point`` where in it (m)
    :ivar nominal: the payload (kg) the design was made for
    :ivar masses: the payloads studied (kg)
    :ivar dials: the dial of the ideal and of the realised springs (:func:`payload_dial`)
    :ivar peaks: per case ('gravity alone', 'ideal', 'ideal, dial turned', 'realised', 'realised, dial
        turned'), route 2's peak holding torque (N m) per joint over the design's poses, (len(masses), n)
    :ivar outside: per payload, how far (m) the dial takes a moved ideal end outside its body's box
        (:func:`springlab.design.arms.ends_outside`; 0: every end stays where the design may put it)
    :ivar loaded: the loaded joints' indices; ``joints`` all joints' names
    :ivar holds: per dial ('ideal', 'realised'), the payloads (kg, 0 <= low <= nominal <= high) over
        which every end it moves stays in its body's box (the outline and its bracket, where the design
        may put an end): beyond them the dial needs a longer slot. Where it is no wider than a gram
        (:meth:`usable` False), the dial cannot be turned at all
    :ivar stretch: per payload, the longest (m) a realised spring, its dial turned, is stretched
        beyond the longest its coil was wound for (0: within it), and the spring ('' for none)
    :ivar names: per dial, its springs' names
    :ivar undefined: (dial, payload kg, how many poses) where the dial turned for that payload leaves a
        spring without a line of action (a cable's end within its pulley's radius): those poses are left
        out of its peaks
    """

    frame: str
    point: tuple
    nominal: float
    masses: np.ndarray
    dials: dict
    peaks: dict
    outside: np.ndarray
    loaded: tuple
    joints: tuple
    holds: dict
    stretch: tuple
    names: dict | None = None
    undefined: tuple = ()

    def usable(self, which: str) -> bool:
        """Whether the ``which`` ('ideal' or 'realised') springs' dial is worth turning: the payloads it
        holds span at least :data:`DIAL_SPAN` of the payloads studied, and at least a gram (the printed
        0.001 kg)."""
        lo, hi = self.holds[which]
        span = float(np.max(self.masses) - np.min(self.masses))
        return round(hi - lo, 3) > 0 and hi - lo >= DIAL_SPAN * span

    def refusal(self, which: str) -> str:
        """The one line that says a dial (``which``: 'ideal', 'realised', or 'ideal or the realised' for
        both, the ideal one's move quoted) cannot be turned, with the move it would need and the payload
        the design does hold."""
        dial = self.dials[which.split()[0]]
        i, end, link, per_kg = max(dial.moves, key=lambda m: float(np.linalg.norm(m[3])))
        name = self.names[which.split()[0]][i] if self.names else f"S{i + 1}"
        lo, hi = self.holds[which.split()[0]]
        at_once = round(hi - lo, 3) == 0
        holds = (f"only its nominal {self.nominal:g} kg" if at_once else
                 f"only {round(lo, 3):g} to {round(hi, 3):g} kg with it")
        return (f"no payload dial for the {which} springs: the moves that would keep the balance (up to "
                f"{1e3 * float(np.linalg.norm(per_kg)):,.0f} mm per kg, {name}'s end {end} on {link!r}) take an end "
                f"off its link and bracket {'at once' if at_once else 'within a tenth of the payloads checked'}, so "
                f"the design holds {holds}; design for the payload you carry or a mid-range one (--payload), or allow "
                "longer brackets (--reach)")

    def warnings(self) -> list[str]:
        """What the study finds an engineer must know: a dial that cannot be turned, payloads beyond the
        dial's slot, coils stretched past their design, a dial that leaves a joint worse than the springs
        unchanged."""
        out = []
        low, high = float(np.min(self.masses)), float(np.max(self.masses))
        if not self.usable("ideal") and not self.usable("realised"):
            out.append(self.refusal("ideal or the realised"))
        for which, (lo, hi) in self.holds.items():
            if not self.usable(which):
                if self.usable("ideal") or self.usable("realised"):
                    out.append(self.refusal(which))
            elif lo > low + 1e-9 or hi < high - 1e-9:
                out.append(f"the {which} springs' dial keeps every moved end on its link only from "
                           f"{round(lo, 3):g} to {round(hi, 3):g} kg (checked {low:g}-{high:g} kg): beyond, it needs a longer slot than the link and "
                           "its bracket give; a design made for a payload mid-range (--payload) has stiffer springs "
                           "and a shorter dial")
        worst = max(range(len(self.masses)), key=lambda m: self.stretch[m][0])
        if self.stretch[worst][0] > 0 and self.usable("realised"):
            out.append(f"turned for {self.masses[worst]:g} kg, the built spring {self.stretch[worst][1]} is stretched "
                       f"{1e3 * self.stretch[worst][0]:.0f} mm past the longest its coil was wound for: wind the coils "
                       "for the dial's whole stroke")
        for which, mass, count in self.undefined:
            out.append(f"turned for {mass:g} kg, the {which} springs' dial brings a cable's end within its pulley's "
                       f"radius at {count} of the poses (left out of its peaks): it cannot be turned that far")
        loaded = list(self.loaded)
        for which in [w for w in ("ideal", "realised") if self.usable(w)]:
            turned, unchanged = self.peaks[f"{which}, dial turned"][:, loaded], self.peaks[which][:, loaded]
            worse = [(float(self.masses[m]), self.joints[loaded[i]]) for m, i in zip(*np.nonzero(
                turned > unchanged * (1 + 1e-6) + 1e-12), strict=True)]
            if worse:
                out.append(f"turning the {which} springs' dial leaves more than leaving it alone at "
                           + ", ".join(f"{joint} at {m:g} kg" for m, joint in worse[:4])
                           + (" and elsewhere" if len(worse) > 4 else "") + " (the dial is not exact there)")
        return out

    def table(self) -> Table:
        """Per payload and case: the peak holding torque (N m) of each loaded joint (a dial that cannot be
        turned, :meth:`usable`, has no rows)."""
        rows = []
        for m, mass in enumerate(self.masses):
            for case, peaks in self.peaks.items():
                which = case.split(",")[0]
                if case.endswith(", dial turned") and not self.usable(which):
                    continue
                lo, hi = self.holds.get(which, (-np.inf, np.inf))
                beyond = case.endswith(", dial turned") and not lo - 1e-9 <= mass <= hi + 1e-9
                rows.append((f"{mass:g}", case + (" (beyond its slot: an end off its link)" if beyond else ""),
                             *(f"{peaks[m, i]:.3g}" for i in self.loaded)))
        return Table(["payload (kg)", "springs", *(f"{self.joints[i]} peak (N m)" for i in self.loaded)], rows)

    def left(self, case: str = "ideal, dial turned") -> np.ndarray:
        """Per payload, the largest peak over the loaded joints a case leaves, as a fraction of gravity's
        own largest peak at that payload."""
        loaded = list(self.loaded)
        return np.max(self.peaks[case][:, loaded], axis=1) / np.max(self.peaks["gravity alone"][:, loaded], axis=1)

    def as_dict(self) -> dict:
        """For ``springlab design --json``: the dials and their check at the payloads (N m, kg, m)."""
        return {"frame": self.frame, "point_m": list(self.point), "nominal_kg": self.nominal,
                "dial": {which: self.dials[which].as_dict(self.names[which] if self.names else None)
                         for which in ("ideal", "realised")},
                "checked_by": "route 2 (direct geometry) over the design's poses (its random poses and the worst its "
                              "independent check found at the nominal payload; not re-checked at the other payloads)",
                "dial_holds_kg": {which: list(v) for which, v in self.holds.items()},
                "dial_usable": {which: self.usable(which) for which in self.holds},
                "warnings": self.warnings(),
                "checks": [{"payload_kg": float(mass), "dial_end_outside_box_m": float(self.outside[m]),
                            "realised_stretch_past_coil_m": float(self.stretch[m][0]),
                            "peak_Nm": {case: {self.joints[i]: float(peaks[m, i]) for i in self.loaded}
                                        for case, peaks in self.peaks.items()}}
                           for m, mass in enumerate(self.masses)]}


def payload_study(design, frame: str, masses, *, nominal: float = 0.0, point=(0.0, 0.0, 0.0), reach=None,
                  dial_poses: int = 200) -> PayloadStudy:
    """The payload study of an :class:`~springlab.design.arms.ArmDesign` made for ``nominal`` kg at
    ``point`` (m) in ``frame``: its dials (fitted on the design's first ``dial_poses`` poses) and
    route 2's peak holding torques at ``masses`` (kg) over all its poses. The realised springs' dial
    moves the same ends as the ideal springs' where the two designs pair spring by spring."""

    _checks.instance("design", design, ArmDesign, "springlab ArmDesign (design_model)")
    masses = _checks.real_array("masses", masses, shape=(None,))
    if not len(masses) or np.any(masses < 0) or np.any(masses > MAX_PAYLOAD_RANGE):
        raise SpringlabError(f"masses = {masses.tolist()} kg: give payloads from 0 to {MAX_PAYLOAD_RANGE:g} kg")
    model, q = design.model, design.q
    fit = q[:_checks.count("dial_poses", dial_poses, least=1)]
    ideal = payload_dial(model, design.ideal, fit, frame, point)
    pairs = lambda springs: [(s.link_a, s.link_b) for s in springs]  # noqa: E731
    same = pairs(design.ideal) == pairs(design.realised)
    realised = payload_dial(model, design.realised, fit, frame, point,
                            ends=[(i, end) for i, end, _, _ in ideal.moves] if same and ideal.moves else None)
    peaks = {"gravity alone": payload_torques(model, [], q, frame, masses, nominal=nominal, point=point)}
    for which, dial in (("ideal", ideal), ("realised", realised)):
        springs = getattr(design, which)
        peaks[which] = payload_torques(model, springs, q, frame, masses, nominal=nominal, point=point)
        peaks[f"{which}, dial turned"] = payload_torques(model, springs, q, frame, masses, nominal=nominal, point=point,
                                                         dial=dial)
    outside = np.array([ends_outside(model, ideal.turned(design.ideal, float(m) - nominal), reach) for m in masses])
    holds = {which: _holds(nominal, _travel(model, getattr(design, which), dial, reach))
             for which, dial in (("ideal", ideal), ("realised", realised))}

    frames = body_frames(model, q)
    stretch = tuple(_stretch(design, realised.turned(design.realised, float(m) - nominal), *frames) for m in masses)
    undefined = tuple((which, float(m), count) for which, dial in (("ideal", ideal), ("realised", realised))
                      for m in masses
                      if (count := _undefined(model, dial.turned(getattr(design, which), float(m) - nominal), q)))
    return PayloadStudy(frame, tuple(float(v) for v in point), float(nominal), masses, {"ideal": ideal, "realised": realised},
                        peaks, outside, tuple(design.structure.loaded), tuple(model.joints), holds, stretch,
                        {"ideal": design.names, "realised": design.realised_names}, undefined)


def _holds(nominal: float, travel) -> tuple[float, float]:
    """The payloads (kg) a dial holds, from its travel (kg, the changes from ``nominal``): never below
    0 kg (no payload is negative), and the nominal alone where the travel does not contain 0 (an end
    already off its box)."""
    low, high = travel
    if not low <= 0.0 <= high:
        return nominal, nominal
    return max(nominal + low, 0.0) + 0.0, min(nominal + high, MAX_PAYLOAD_RANGE)


def _travel(model: RevoluteChain, springs, dial: PayloadDial, reach) -> tuple[float, float]:
    """The payload changes (kg, low <= 0 <= high when every end starts inside) over which every end
    the dial moves stays in its body's box: each end moves on a line, so per box face a bound."""

    centres, half = attachment_boxes(model, reach)
    low, high = -np.inf, np.inf
    for i, end, link, per_kg in dial.moves:
        s = springs[i]
        body, p = model.locate(link, s.point_a if end == "A" else s.point_b)
        if body > model.n:  # a post on a belt's or a pseudobase's frame: no box (the clearance check bounds it)
            continue
        v = model.rotation(link) @ np.asarray(per_kg)
        lo, hi = centres[body] - half[body] - 1e-9, centres[body] + half[body] + 1e-9
        for a in range(3):
            if abs(v[a]) < 1e-15:
                if not lo[a] <= p[a] <= hi[a]:
                    return 0.0, 0.0
                continue
            t1, t2 = sorted(((lo[a] - p[a]) / v[a], (hi[a] - p[a]) / v[a]))
            low, high = max(low, t1), min(high, t2)
    return (float(low), float(high)) if low <= high else (0.0, 0.0)


def _stretch(design, turned, R, o) -> tuple[float, str]:
    """How far (m) the longest of the turned realised springs is stretched (over the design's poses,
    whose body frames are R, o) beyond the longest length its coil was wound for, and which spring."""

    worst = (0.0, "")
    for n, spring, (_, span, *_) in zip(design.realised_names, turned, design.coils, strict=True):
        try:
            length = spring_lengths(design.model, [spring], R, o)[0]
        except GeometryError:  # its cable meets its pulley at some pose: named in the study's warnings
            continue
        excess = float(np.max(length)) - float(span[1])
        if excess > max(worst[0], 1e-9 * span[1]):
            worst = (excess, n)
    return worst
