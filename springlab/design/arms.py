"""Springs for a real arm: the general model (:class:`~springlab.model.revolute.RevoluteChain`, read
from a URDF's own frames), its structure with proof, exact balance where the structure allows
it and the best springs elsewhere.

**Structure** (:func:`~springlab.design.structure.structure`, in :mod:`springlab.design.structure`):
which joints gravity loads, with proof, and whether the loaded joints form a **planar chain**.

**Exact balance of a planar chain** (:func:`~springlab.design.structure.planar_springs`): one
zero-free-length spring per pair of planar links at most, every one solvable
(:mod:`springlab.design.structure` derives it).

**Best springs elsewhere** (:func:`~springlab.design.search.best_springs`, in
:mod:`springlab.design.search`): attachment points within each body's reach and rates that minimise the
largest holding torque over the workspace.

**Realisation** (:mod:`springlab.design.realise`): each ideal spring wound from stocked wire, as a
zero-length spring or a coil behind a pulley, and re-balanced for the pulley.

**The audit** (:class:`~springlab.design.audit.Audit`): the peaks re-checked on an independent, denser
sample of the workspace.

This module puts them together (:func:`design_model`) and reports the result (:class:`ArmDesign`: its
tables, flags, JSON and spring sheets).

**Pseudobases** (``layout='belts'`` and ``'pseudobases'``, :mod:`springlab.design.layouts`,
:mod:`springlab.design.pseudobases`): paper 001's one spring per link's subsystem, its post on a frame a belt
or RSSR modules carry (001 Eqs. 5, 13-16).

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from springlab import _checks
from springlab.design.audit import AUDIT_SAMPLES, Audit
from springlab.design.buildable import (
    COIL_COLUMNS,
    ENDURANCE_CYCLES,
    MATERIALS,
    SERVICE_COLUMNS,
    check_tolerances,
    coil_cells,
    maker_note,
    service_cells,
    wires,
)
from springlab.design.collision import MARGIN, Sampler, has_geometry
from springlab.design.hardware import (
    HOOK_GAP,
    WITHIN_POSES,
    balanced_body,
    block_room,
    coil_ends,
    parts,
    spring_clearance,
    with_spring_mass,
)
from springlab.design.layouts import SHARE, belt_layout, realise_layout, without_light
from springlab.design.narrowing import narrowed
from springlab.design.pseudobases import pseudobase_layout
from springlab.design.realise import (
    length_range,
    realisation_changes,
    realise_with_origins,
    sized_pulley,
    with_changes,
)
from springlab.design.search import MAX_STIFFNESS, best_springs, sig
from springlab.design.structure import (
    BRACKET,
    Structure,
    attachment_boxes,
    planar_springs,
    structure,
)
from springlab.energy.geometry import gravity_torques, joint_torques, spring_lines
from springlab.errors import GeometryError, SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, check_point_springs
from springlab.tables import Table


def _mm(point) -> str:
    """A point (m) as the tables print it: "(x, y, z)" in mm to 0.1 mm, no "-0.0"."""
    return "(" + ", ".join(f"{round(1e3 * v, 1) + 0.0:.1f}" for v in point) + ")"


def _sizes(part, unit: str = "") -> str:
    """A part's sizes as the tables print them: lengths in mm (followed by ``unit``), counts as they are."""
    return ", ".join(f"{k.replace('_', ' ')} {1e3 * v:.3g}{unit}" if isinstance(v, float) else f"{k.replace('_', ' ')} {v}"
                     for k, v in part.size.items() if not k.endswith("_kg"))


CLEARANCE_SAMPLES = 32
"""Points along each spring at which its clearance from the bodies is measured."""

CLEARANCE_POSES = 100
"""The most workspace poses the clearance is measured at (a mesh's hull has thousands of faces)."""


def clearance(model: RevoluteChain, springs, q, *, names=None) -> Table:
    """Each spring's clearance from the bodies it is not attached to, over the poses ``q`` (the first
    :data:`CLEARANCE_POSES`): the
    nearest body and the smallest distance (mm) from the spring's straight run (A to B, or from its
    pulley to B) to that body's outline (the convex hull of its URDF geometry), negative where the
    spring passes through it. Measured as the largest signed distance to the hull's face planes at
    :data:`CLEARANCE_SAMPLES` points along the run, less half their spacing: a lower bound (the
    distance is 1-Lipschitz along the run, and the face planes' distance never exceeds the hull's).
    Bodies without an outline are not checked (named in the table). Springs are named ``names``, by
    default S1, S2, ... in the order given."""
    from scipy.spatial import ConvexHull, QhullError

    q = model.check_q(q)[:CLEARANCE_POSES]
    R, o = body_frames(model, q)
    planes = {}
    for b, points in enumerate(model.outline):
        try:
            planes[b] = ConvexHull(points).equations if len(points) >= 4 else None
        except (QhullError, ValueError):
            planes[b] = None
    t = np.linspace(0.0, 1.0, CLEARANCE_SAMPLES)
    rows = []
    names = names or [f"S{n}" for n in range(1, len(springs) + 1)]
    for n, s, (P, B, a, b) in zip(names, springs, spring_lines(model, springs, q), strict=True):
        pts = P[:, None] + t[None, :, None] * (B - P)[:, None]  # (N, K, 3)
        half = 0.5 * np.max(np.linalg.norm(B - P, axis=1)) / (CLEARANCE_SAMPLES - 1)
        best, nearest = np.inf, None
        for c, eq in planes.items():
            if c in (a, b) or eq is None:
                continue
            local = np.einsum("pji,pkj->pki", R[:, c], pts - o[:, c, None])
            signed = np.max(local @ eq[:, :3].T + eq[:, 3], axis=2)  # (N, K)
            value = float(np.min(signed)) - half
            if value < best:
                best, nearest = value, model.bodies[c]
        unchecked = [model.bodies[c] for c, eq in planes.items() if eq is None and c not in (a, b)]
        rows.append((f"{n} ({s.label})", nearest or "", f"{1e3 * best:.1f}" if nearest else "", "yes" if best < 0 else "no",
                     ", ".join(unchecked)))
    return Table(["spring", "nearest body", "smallest clearance (mm)", "passes through it", "bodies not checked"], rows)


def torque_table(model: RevoluteChain, q, cases: dict, *, unloaded=()) -> Table:
    """Per joint: peak and RMS gravity torque (N m), the same with each set of springs in ``cases``
    (name -> springs, or -> (springs, the arm that carries them): the arm with the springs' own mass), and
    the percentage of gravity's peak each removes (blank for the ``unloaded`` joints, whose gravity
    torque is zero or negligible)."""
    q = model.check_q(q)
    gravity = gravity_torques(model, q)
    rows = []
    carried = lambda v: isinstance(v, tuple) and len(v) == 2 and isinstance(v[1], RevoluteChain)  # noqa: E731
    with_springs = {name: joint_torques(value[1], value[0], q) if carried(value) else joint_torques(model, value, q)
                    for name, value in cases.items()}
    for i, name in enumerate(model.joints):
        peak, rms = np.max(np.abs(gravity[:, i])), np.sqrt(np.mean(gravity[:, i] ** 2))
        row = [name, f"{peak:.4g}", f"{rms:.4g}"]
        for tau in with_springs.values():
            p = np.max(np.abs(tau[:, i]))
            row += [f"{p:.3g}", f"{np.sqrt(np.mean(tau[:, i] ** 2)):.3g}",
                    f"{100 * (1 - p / peak):.2f}" if peak > 0 and i not in unloaded else ""]
        rows.append(row)
    headers = ["joint", "gravity peak (N m)", "gravity RMS (N m)"]
    for case in cases:
        headers += [f"{case} peak (N m)", f"{case} RMS (N m)", f"{case}: peak removed (%)"]
    return Table(headers, rows)


# --- the best springs where exact balance is out of reach -------------------------------------
def ends_outside(model: RevoluteChain, springs, reach=None) -> float:
    """How far (m) the farthest end of ``springs`` lies outside its body's box
    (:func:`~springlab.design.structure.attachment_boxes` with ``reach``): 0 when every end is where a design may put it (an end on a
    belt's or a pseudobase's frame has no box)."""
    centres, half = attachment_boxes(model, reach)
    worst = 0.0
    for s in check_point_springs(model, springs):
        for link, point in ((s.link_a, s.point_a), (s.link_b, s.point_b)):
            body, local = model.locate(link, point)
            if body > model.n:  # on a frame a belt or RSSR modules carry: a post, bounded by the clearance check
                continue
            worst = max(worst, float(np.linalg.norm(np.maximum(np.abs(local - centres[body]) - half[body], 0.0))))
    return worst


# --- the whole design: structure, springs, realisation, the torques that remain -------------------
def workspace_ranges(model: RevoluteChain, workspace=None) -> np.ndarray:
    """The joint ranges (n, 2) rad the design holds: the URDF limits (an unlimited joint: a full turn,
    [-pi, pi]), narrowed by ``workspace``, a dict joint name -> (low, high) rad that must lie within
    the limits."""
    lo = np.where(np.isfinite(model.limits[:, 0]), model.limits[:, 0], -np.pi)
    hi = np.where(np.isfinite(model.limits[:, 1]), model.limits[:, 1], np.pi)
    ranges = np.stack([lo, hi], axis=1)
    for name, value in dict(workspace or {}).items():
        if name not in model.joints:
            raise SpringlabError(f"workspace names joint {name!r}, which is not on the arm's path: give one of "
                                 f"{', '.join(model.joints)}")
        i = model.joints.index(name)
        low, high = (float(v) for v in value)
        if not (np.isfinite(low) and np.isfinite(high) and low < high):
            raise SpringlabError(f"workspace of {name!r} = ({np.degrees(low):g}, {np.degrees(high):g}) deg: give "
                                 "low < high, both finite")
        if low < ranges[i, 0] - 1e-12 or high > ranges[i, 1] + 1e-12:
            raise SpringlabError(f"workspace of {name!r} = ({np.degrees(low):.1f}, {np.degrees(high):.1f}) deg lies "
                                 f"outside its limits ({np.degrees(ranges[i, 0]):.1f}, {np.degrees(ranges[i, 1]):.1f}) "
                                 "deg: give a range within them")
        ranges[i] = (low, high)
    return ranges


def parse_workspace(text: str) -> dict:
    """--workspace 'joint=low:high,...' (degrees) as a dict joint -> (low, high) rad."""
    out = {}
    for item in (part.strip() for part in str(text).split(",") if part.strip()):
        name, sep, span = item.partition("=")
        low, sep2, high = span.partition(":")
        if name.strip() in out:
            raise SpringlabError(f"--workspace names joint {name.strip()!r} twice: give each joint one range")
        try:
            if not (sep and sep2):
                raise ValueError
            out[name.strip()] = (np.radians(float(low)), np.radians(float(high)))
        except ValueError:
            raise SpringlabError(f"--workspace item {item!r}: write joint=low:high in degrees, e.g. "
                                 "'elbow_joint=-120:120'") from None
    if not out:
        raise SpringlabError(f"--workspace = {text!r}: write joint=low:high in degrees, items separated by commas")
    return out


@dataclass(frozen=True)
class ArmDesign:
    """Springs for an arm of the general model, ideal and realised, and what they leave.

    :ivar model: the arm
    :ivar structure: what gravity loads (:func:`~springlab.design.structure.structure`)
    :ivar method: 'exact: planar chain', 'best springs' or 'nothing to balance'
    :ivar ideal: zero-free-length springs
    :ivar realised: the same springs as wound (free length, initial tension) for a shop, those a
        stocked spring realises (the notes name any left out)
    :ivar kinds: per realised spring, how ('zero-length spring' or 'cable over a pulley')
    :ivar coils: per realised spring, its coil (:class:`~springlab.design.buildable.ExtensionSpring`) and the
        range (m) of the distance between its ends over the workspace
    :ivar q: the workspace poses the design is checked on (N, n) rad, not those it was fitted on: random
        poses, then the worst poses an independent denser sample found (:class:`~springlab.design.audit.Audit`)
    :ivar notes: what was assumed and found
    :ivar origins: per realised spring, the index of the ideal spring it realises (a spring too strong
        for one wire is realised by two or three side by side)
    :ivar changes: per realised spring, what the realisation changed of its ideal spring, and why
    :ivar audit: the independent sample the peaks were re-checked on (:class:`~springlab.design.audit.Audit`), or None
    :ivar left_out: the ideal springs the realisation leaves out, (index, why) each
    :ivar tag: the letter its springs are named by (S: S1, S2, ...), so that two designs of one arm
        shown side by side have distinct names
    :ivar clearance: each realised spring's nearest approach to a link over :attr:`q`, on the URDF's own
        shapes (:class:`~springlab.design.hardware.SpringClearance`), or None for an arm without them
    :ivar massed: the arm carrying its realised springs' own mass
        (:func:`~springlab.design.hardware.with_spring_mass`), or None
    :ivar workspace: what the workspace is (:class:`~springlab.design.collision.Sampler`'s note)
    :ivar carried: whether the springs were designed for the arm carrying their hardware (:attr:`massed`;
        the belt layout), so that their checks are made on it
    :ivar narrowed: where a realised spring runs into a link, the narrower workspaces on which the same springs
        clear every link (:func:`~springlab.design.narrowing.narrowed`: one joint's range, then two), each
        re-measured on fresh poses of it; empty when they clear or none was found
    """

    model: RevoluteChain
    structure: Structure
    method: str
    ideal: tuple
    realised: tuple
    kinds: tuple
    coils: tuple
    q: np.ndarray
    notes: tuple
    origins: tuple = ()
    changes: tuple = ()
    audit: Audit | None = None
    tag: str = "S"
    left_out: tuple = ()
    clearance: object = None
    massed: RevoluteChain | None = None
    workspace: str = ""
    carried: bool = False
    narrowed: tuple = ()

    @property
    def names(self) -> tuple:
        """The ideal springs' names: S1, S2, ..., in order (:attr:`tag` and a number)."""
        return tuple(f"{self.tag}{i}" for i in range(1, len(self.ideal) + 1))

    @property
    def realised_names(self) -> tuple:
        """Each realised spring named after the ideal spring it realises (S3; S3a, S3b side by side)."""
        origins = self.origins or tuple(range(len(self.realised)))
        out = []
        for m, i in enumerate(origins):
            count = origins.count(i)
            out.append(f"{self.tag}{i + 1}" + ("" if count == 1 else "abc"[origins[:m].count(i)]))
        return tuple(out)

    def table(self) -> Table:
        """Per joint: peak and RMS torque (N m) of gravity alone, with the ideal and with the realised
        springs, and the percentage of the peak removed."""
        cases = {"ideal": self.ideal, "realised": self.realised}
        if self.massed is not None:
            cases["realised, springs' mass carried"] = (self.realised, self.massed)
        return torque_table(self.model, self.q, cases, unloaded=self.structure.unloaded)

    def springs_table(self, which: str = "realised") -> Table:
        """Each spring (S1, S2, ...) as a shop builds it (``which='ideal'``: as designed): its ends (link, point in mm
        in the link's URDF frame) and rate, and how it is built: the kind, the pulley's radius and the
        cable's lead, the coil's own free length and longest stretched length (mm, inside the hooks),
        its initial tension (N) and wire (mm). A spring no stocked wire realises is named in the notes."""
        if which == "ideal":
            return Table(["spring", "link_a", "point_a (mm)", "link_b", "point_b (mm)", "k (N/m)"],
                         [(name, s.link_a, _mm(s.point_a), s.link_b, _mm(s.point_b), f"{s.k:.4g}")
                          for name, s in zip(self.names, self.ideal, strict=True)])
        rows = []
        for n, r, kind, (coil, *_) in zip(self.realised_names, self.realised, self.kinds, self.coils, strict=True):
            pulley = (f"{1e3 * r.pulley_radius:g}, lead ({', '.join(f'{v + 0.0:.2f}' for v in r.lead)})"
                      if r.pulley_radius > 0 else "")
            rows.append((n, r.link_a, _mm(r.point_a), r.link_b, _mm(r.point_b), f"{r.k:.4g}", kind, pulley,
                         f"{1e3 * coil.free_length:.1f}", f"{1e3 * coil.max_length:.1f}", f"{coil.initial_tension:.3g}",
                         f"{1e3 * coil.wire:.2g}"))
        return Table(["spring", "link_a", "point_a (mm)", "link_b", "point_b (mm)", "k (N/m)", "realised as",
                      "pulley (mm), lead", "coil free length (mm)", "coil longest (mm)", "initial tension (N)",
                      "wire (mm)"], rows)

    def sheet(self) -> Table:
        """The spec sheet a spring maker works from, one row per realised spring: where it goes (its ends,
        mm in their links' URDF frames), how it is realised, the coil
        (:data:`~springlab.design.buildable.COIL_COLUMNS`), its hooks and fatigue in service
        (:data:`~springlab.design.buildable.SERVICE_COLUMNS`), the cable's offset L_0 - F_i / k, the pulley's
        radius and lead, and the maker's note (:func:`~springlab.design.buildable.maker_note`);
        :data:`~springlab.design.buildable.SHEET_NOTE` says what it is designed to."""

        rows = []
        for n, r, kind, fit in zip(self.realised_names, self.realised, self.kinds, self.coils, strict=True):
            cable, coil = kind.startswith("cable"), fit.coil
            rows.append((n, f"{r.link_a} {_mm(r.point_a)}", f"{r.link_b} {_mm(r.point_b)}", kind, *coil_cells(coil),
                         *service_cells(coil, *fit.forces()),
                         f"{1e3 * coil.cable_offset:.1f}" if cable else "",  # over a block too
                         f"{1e3 * r.pulley_radius:g}" if r.pulley_radius > 0 else "",
                         "(" + ", ".join(f"{v + 0.0:.2f}" for v in r.lead) + ")" if r.pulley_radius > 0 else "",
                         maker_note(coil, cable)))
        return Table(["spring", "end A: link (mm)", "end B: link (mm)", "realisation", *COIL_COLUMNS, *SERVICE_COLUMNS,
                      "cable offset L0 - Fi/k (mm)", "pulley radius (mm)", "lead (link_a frame)", "maker's note"], rows)

    def built(self, *, tension: float = 1.0, free_length: float = 1.0, stiffness: float = 1.0,
              only: int | None = None) -> tuple:
        """The realised springs as wound, each coil's initial tension, free length and rate multiplied by
        the factors (1: as specified; :data:`~springlab.design.buildable.TOLERANCES`), or only the coil of
        realised spring ``only`` (its index), the others as specified. A cable's length
        stays as cut: its offset c = L_0 - F_i / k is kept, so the force along its path is
        F_i' + k' (path + c - L_0'); over a pulley block of ratio n the coil moves path / n and the cable
        pulls (F_i' + k' (path / n + c - L_0')) / n, a spring of rate k' / n^2, initial tension F_i' / n and
        free length n (L_0' - c) along the path."""
        out = []
        factors = [_checks.positive(n, v) for n, v in (("stiffness", stiffness), ("free_length", free_length),
                                                          ("tension", tension))]
        for m, (r, (coil, _, ratio, *_)) in enumerate(zip(self.realised, self.coils, strict=True)):
            f_k, f_L, f_T = factors if only is None or m == only else (1.0, 1.0, 1.0)
            offset = coil.free_length - r.free_length / ratio  # the cable's offset; 0 for a zero-length spring
            k = r.k * f_k
            L0 = ratio * (coil.free_length * f_L - offset)
            Fi = r.initial_tension * f_T
            fields = {"free_length": L0, "initial_tension": Fi} if L0 >= 0 else {"free_length": 0.0,
                                                                                  "initial_tension": Fi - k * L0}
            out.append(with_changes(r, k=k, **fields))
        return tuple(out)

    def tolerance_table(self, tolerances: dict | None = None) -> Table:
        """The balance the built springs leave (route 2, the design's poses, on the arm they were designed for,
        :attr:`designed_for`): per loaded joint, the
        percentage of its peak gravity torque removed, by the ideal springs, the realised ones as
        specified, and with each of the maker's tolerances (default
        :data:`~springlab.design.buildable.TOLERANCES`; each at most 0.5) at its + and - limit on every
        spring at once."""

        tolerances = check_tolerances(tolerances)
        percent = self._removal()

        def removed(springs):
            return [f"{v:.1f}" for v in percent(springs)]

        rows = [("as designed (ideal springs)", *removed(self.ideal)), ("as specified", *removed(self.built()))]
        for name, value in tolerances.items():
            for sign in (1, -1):
                rows.append((f"{name.replace('_', ' ')} {'+' if sign > 0 else '-'}{100 * value:g} %",
                             *removed(self.built(**{name: 1 + sign * value}))))
        return Table(["built", *(f"{self.model.joints[i]} removed (%)" for i in self.structure.loaded)], rows)

    def _removal(self):
        """A function of springs: the percentage of each loaded joint's peak gravity torque they remove (route 2,
        the design's poses, on :attr:`designed_for`, the springs' hardware carried where the layout designed for
        it), the peaks computed once."""
        loaded = list(self.structure.loaded)
        arm = self.designed_for
        peak = np.max(np.abs(gravity_torques(arm, self.q)), axis=0)[loaded]
        return lambda springs: 100 * (1 - np.max(np.abs(joint_torques(arm, springs, self.q)), axis=0)[loaded] / peak)

    def tolerance_ranking(self, tolerances: dict | None = None, *, points: float = 1.0) -> Table:
        """Which spring's tolerance costs the balance most: per realised spring and maker's tolerance (default
        :data:`~springlab.design.buildable.TOLERANCES`), that spring alone at the tolerance's + and - limit, the
        others as specified, and the points of a loaded joint's peak removed it costs at worst (route 2, the
        design's poses, on :attr:`designed_for`); and the band (+- %) that keeps it within ``points`` of the springs as specified
        (bisection; the whole tolerance where that already does). The costliest first."""

        tolerances = check_tolerances(tolerances)
        points = _checks.positive("points", points, unit="percentage points")
        removed = self._removal()
        nominal = removed(self.built())

        def loss(m, name, value):
            return max(float(np.max(nominal - removed(self.built(only=m, **{name: 1 + sign * value}))))
                       for sign in (1, -1))

        rows = []
        for m, label in enumerate(self.realised_names):
            for name, value in tolerances.items():
                cost = loss(m, name, value)
                band, low, high = value, 0.0, value
                if cost > points:  # the largest band within the points, the cost rising with the band: to
                    for _ in range(12):  # 2^-12 of the limit, past the two figures the table prints
                        mid = 0.5 * (low + high)
                        low, high = (mid, high) if loss(m, name, mid) <= points else (low, mid)
                    band = low
                rows.append((cost, label, name.replace("_", " "), value, band))
        rows.sort(key=lambda row: -row[0])
        return Table(["spring", "tolerance", "limit (+- %)", "points lost at worst", f"band within {points:g} point (+- %)"],
                     [(label, name, f"{100 * value:g}", f"{cost:.2f}", f"{100 * band:.2g}")
                      for cost, label, name, value, band in rows])

    def clearance_table(self) -> Table:
        """The realised springs' clearance from the bodies over the workspace (:func:`clearance`)."""
        return clearance(self.model, self.realised, self.q, names=self.realised_names)

    def changes_table(self) -> Table:
        """Per realised spring: the ideal spring it realises and what the realisation changed, and why; then
        each ideal spring the realisation left out, and why."""
        return Table(["realised", "realises", "what changed"],
                     [(n, self.names[i], why) for n, i, why in zip(self.realised_names, self.origins, self.changes,
                                                                   strict=True)]
                     + [("(left out)", self.names[i], why) for i, why in self.left_out])

    def flags(self, factor: float = 0.9) -> tuple:
        """What makes this design fail its own checks, in words (empty: it passes): its balance
        (:meth:`balance_flags`) and its hardware (:meth:`hardware_flags`)."""
        return self.balance_flags(factor) + self.hardware_flags()

    def balance_flags(self, factor: float = 0.9) -> tuple:
        """What makes its balance fail, in words: the ideal springs
        leaving a loaded joint no less than their negative control (every rate times ``factor``) does, joint by
        joint (:meth:`control_by_joint`), or any joint left with
        more holding torque by the ideal or the realised springs than by gravity alone (above round-off:
        1e-9 of the arm's largest gravity torque), a spring with no line of action or whose cable's end
        crosses its lead, a spring that does not clear the links."""
        out = []
        by_joint = self.control_by_joint(factor) if self.ideal else {}
        if self.ideal and not by_joint:
            out.append("the springs move no loaded joint's torque: they do not balance this arm")
        for joint, (designed, control) in by_joint.items():  # joint by joint: a light joint left out hides nothing
            if sig(control) <= sig(designed):
                out.append(f"the springs leave {designed:.3g} N m at {joint} at worst, no less than their negative control "
                           f"(every rate x {factor:g}) leaves, {control:.3g} N m: they do not balance it")
        for case, count, pose, why in (self.audit.undefined if self.audit else ()):
            where = (f"at {count} of the {self.audit.samples:,} poses of the independent check" if count else
                     "at a pose of the workspace the independent check's local search reached")
            number = int(why.split()[1])
            why = why.replace(f"spring {number}", (self.realised_names if case == "realised" else self.names)[number - 1], 1)
            out.append(f"the {case} springs have no line of action {where} ({why}; "
                       f"at {np.round(np.degrees(pose), 1).tolist()} deg): they cannot be built as drawn")
        for m, angle, pose in (self.audit.crossings if self.audit else ()):
            out.append(f"the realised spring {self.realised_names[m]}'s end B crosses the line of its pulley's lead "
                       f"(within {np.degrees(angle):.1g} deg, at {np.round(np.degrees(pose), 1).tolist()} deg): its pulley "
                       "must swivel half a turn there at once, and its pull jumps, so the torques near that pose are not "
                       "what the tables show; give it another lead or other ends")
        for spring, piece, link, pose, gap in (self.clearance.failing() if self.clearance is not None else ()):
            depth = (f"runs {1e3 * -gap:.0f} mm into {link}" if gap < 0 else
                     f"comes within {1e3 * gap:.1f} mm of {link}, less than the {1e3 * self.clearance.margin:g} mm margin")
            share = self.clearance.within.get(spring)
            counted = min(WITHIN_POSES, self.clearance.poses)
            share = ("" if share is None else "; the spring comes within the margin of a link or the table at "
                     + (f"{_percent(share)} of {counted} check poses" if share > 0 else
                        f"none of the first {counted} check poses (a rare pose)"))
            out.append(f"the realised spring {spring}'s {piece} {depth} (at {np.round(np.degrees(self.q[pose]), 1).tolist()} "
                       f"deg){share}: it cannot be mounted as drawn")
        gravity = np.max(np.abs(gravity_torques(self.designed_for, self.q)), axis=0)
        floor = 1e-9 * max(float(np.max(gravity)), 1e-300)
        for which in ("ideal", "realised"):
            springs = getattr(self, which)
            if not springs:
                continue
            left = np.max(np.abs(joint_torques(self.designed_for, springs, self.q)), axis=0)
            for i in np.flatnonzero(left > gravity * (1 + 1e-9) + floor):
                more = (f"{100 * (left[i] / gravity[i] - 1):.0f} % more than gravity alone, {gravity[i]:.3g} N m"
                        if gravity[i] > floor else "where gravity alone needs none")
                out.append(f"joint {self.model.joints[i]}: the {which} springs leave {left[i]:.3g} N m at worst, {more} "
                           f"({100 * left[i] / np.max(gravity):.2g} % of the arm's largest gravity torque)")
        return tuple(out)

    def hardware_flags(self) -> tuple:
        """What its hardware cannot do: a coil stretched at a pose of :attr:`q` (the audit's worst poses
        included) past what it was wound for and past its wire's allowable stress; a machine hook stressed past
        its allowable at the coil's largest force, or a coil, or a hook, that its pull's range over the workspace
        would break in fatigue (:meth:`~springlab.design.buildable.ExtensionSpring.fatigue`); a cable spring with
        no stocked cable for its pull, a
        cable pulled past its working load, a pulley smaller than its cable's D/d asks for, a coil longer
        in service than its link has between its pulley and its joint (it would reach past the joint); a
        stock part stretched past its catalogue's largest extension or load at a pose of :attr:`q`."""

        out = []
        R, o = body_frames(self.model, self.q)
        for name, r, kind, fit in zip(self.realised_names, self.realised, self.kinds, self.coils, strict=True):
            try:
                longest = length_range(self.model, r, R, o)[1]
            except GeometryError:
                longest = float(fit.span[1])  # no line of action at some pose: flagged by the balance checks
            stretched = float(fit.coil_length(longest)) if kind.startswith("cable") else longest
            part = getattr(fit.coil, "part", None)
            if part is not None:  # a stock part: the vendor's limits, at the poses checked
                out += [f"the realised spring {name}'s stock part {part.part_number} is {why}"
                        for why in fit.coil.beyond(stretched)]
            stress = float(fit.coil.stress(fit.coil.force(max(stretched, fit.coil.free_length))))
            if longest > fit.span[1] and stress > fit.coil.allowable_stress:
                out.append(f"the realised spring {name}'s coil is stretched to {1e3 * stretched:.1f} mm at a pose of the "
                           f"check, beyond the {1e3 * fit.coil.max_length:.1f} mm it was wound for: {stress / 1e6:.0f} MPa, "
                           f"above its wire's allowable {fit.coil.allowable_stress / 1e6:.0f} MPa")
            for what, value, allowed in zip(("bends", "twists"), fit.coil.hook_stresses(fit.coil.max_force),
                                            fit.coil.hook_allowables, strict=True):
                if value > allowed * (1 + 1e-9):
                    out.append(f"the realised spring {name}'s hook {what} at {value / 1e6:.0f} MPa under its largest "
                               f"force {fit.coil.max_force:.4g} N, above its allowable {allowed / 1e6:.0f} MPa: it "
                               "would yield where it leaves the coil")
            low, high = fit.forces()
            for place, factor in fit.coil.fatigue(low, high).items():
                if factor < 1:
                    out.append(f"the realised spring {name}'s {place} would fail in fatigue over its pull in the "
                               f"workspace, {low:.4g} to {high:.4g} N: Gerber's factor {factor:.2f} against Zimmerli's "
                               f"endurance, below 1 (not rated for {ENDURANCE_CYCLES:.0e} cycles)")
            if not kind.startswith("cable"):
                continue
            pull = r.k * max(float(fit.span[1]), longest)
            if fit.cable is None:
                out.append(f"the realised spring {name}'s cable pulls {pull:.4g} N: no stocked cable carries it")
                continue
            if fit.cable.working < pull * (1 - 1e-9):
                out.append(f"the realised spring {name}'s cable ({fit.cable.name}) pulls {pull:.4g} N, more than its "
                           f"working load {fit.cable.working:.4g} N")
            if r.pulley_radius > 0 and not fit.cable.fits(r.pulley_radius):
                out.append(f"the realised spring {name}'s pulley ({1e3 * r.pulley_radius:g} mm to the cable's centre) is "
                           f"smaller than its cable ({fit.cable.name}) asks for, {1e3 * fit.cable.pulley_radius:g} mm "
                           f"(D/d {fit.cable.ratio:g}): give a larger --pulley-radius, or leave it to be sized")
            body, at = self.model.locate(r.link_a, r.point_a)
            behind = r.pulley_radius + HOOK_GAP + block_room(fit, r.pulley_radius)
            bracket = fit.bracket
            if bracket is not None:  # on a bracket of the level frame: the room its layout gave it
                block = block_room(fit, r.pulley_radius)
                room = bracket - block
                if fit.coil.max_length > room * (1 + 1e-9):
                    if room > 0:
                        has = f"longer than the {1e3 * room:.0f} mm its bracket has beyond its post within its link's length"
                    elif bracket > 0:
                        has = (f"and its pulley block alone takes {1e3 * block:.0f} mm of the {1e3 * bracket:.0f} mm its "
                               "bracket has beyond its post within its link's length")
                    else:  # the post and its pulley already reach past the link's length
                        has = f"and its post and pulley already reach {-1e3 * bracket:.0f} mm past its link's length"
                    out.append(f"the realised spring {name}'s coil is {1e3 * fit.coil.max_length:.0f} mm long in "
                               f"service, {has}: the bracket would outgrow the arm")
                continue
            if 0 < body <= self.model.n:  # in the plane of its joint's turning (an axial offset is no room)
                w = np.asarray(self.model.axes[body - 1], dtype=float)
                room = float(np.linalg.norm(at - (at @ w) * w)) - behind
            else:
                room = float("inf")
            if fit.coil.max_length > room * (1 + 1e-9):
                space = (f"longer than the {1e3 * room:.0f} mm its link {r.link_a} has between its pulley and its joint"
                         if room > 0 else f"and its pulley leaves it no room on its link {r.link_a} before the joint")
                out.append(f"the realised spring {name}'s coil is {1e3 * fit.coil.max_length:.0f} mm long in service, "
                           f"{space}: it reaches past the joint")
        return tuple(out)

    def removed_by(self, springs) -> np.ndarray:
        """Per loaded joint (:attr:`structure`), the percentage of its peak gravity torque ``springs`` remove
        on the arm they were designed for (:attr:`designed_for`), over :attr:`q`; realised springs on an arm
        that carries them also carry their hardware's mass (:attr:`massed`)."""
        arm = self.massed if self.massed is not None and springs is self.realised else self.designed_for
        loaded = list(self.structure.loaded)
        gravity = np.max(np.abs(gravity_torques(arm, self.q)), axis=0)[loaded]
        left = np.max(np.abs(joint_torques(arm, springs, self.q)), axis=0)[loaded]
        return 100 * (1 - left / np.where(gravity > 0, gravity, np.nan))

    def reached(self, share: float = 0.9) -> dict:
        """Whether the realised springs, carrying their hardware's mass, remove at least ``share`` of every loaded
        joint's peak gravity torque but the light ones (below :data:`~springlab.design.layouts.SHARE` of the
        largest peak, which a layout may leave out): {"share", "reached", "removed_percent" per loaded joint,
        "missed": the joints below it, "light": those not held to it}."""
        share = _checks.number("share", share)
        if not 0 < share <= 1:
            raise SpringlabError(f"target = {share:g}: give the share of each loaded joint's peak to remove, above 0 "
                                 "and at most 1 (e.g. 0.9)")

        names = [self.model.joints[i] for i in self.structure.loaded]
        removed = self.removed_by(self.realised) if self.realised else np.zeros(len(names))
        light = [self.model.joints[i] for i in sorted(self._light())]
        missed = [n for n, v in zip(names, removed, strict=True) if not v >= 100 * share - 1e-9 and n not in light]
        return {"share": share, "reached": not missed,
                "removed_percent": {n: float(v) for n, v in zip(names, removed, strict=True)}, "missed": missed,
                "light": light}

    def trade_off(self) -> Table:
        """The spring count against the share removed: from all the realised springs, the one (with any beside
        it, side by side) whose leaving out costs least is left out, in turn; per count, the percentage of
        each loaded joint's peak the rest remove (on the arm carrying only their hardware)."""

        groups = sorted(set(self.origins or range(len(self.realised))))
        origins = self.origins or tuple(range(len(self.realised)))
        names = [self.model.joints[i] for i in self.structure.loaded]
        loaded = list(self.structure.loaded)

        def shares(kept):
            idx = [m for m, o in enumerate(origins) if o in kept]
            springs = [self.realised[m] for m in idx]
            arm = (with_spring_mass(self.model, springs, [self.kinds[m] for m in idx], [self.coils[m] for m in idx],
                                    self.q) if idx else self.model)
            gravity = np.max(np.abs(gravity_torques(arm, self.q)), axis=0)[loaded]
            left = np.max(np.abs(joint_torques(arm, springs, self.q)), axis=0)[loaded]
            return 100 * (1 - left / np.where(gravity > 0, gravity, np.nan))

        rows, kept = [], list(groups)
        while kept:
            rows.append((str(sum(1 for o in origins if o in kept)), ", ".join(self.names[g] for g in kept),
                         *(f"{v:.1f}" for v in shares(kept))))
            if len(kept) == 1:
                break
            kept.remove(max(kept, key=lambda g: (float(np.nanmin(shares([k for k in kept if k != g]))), -g)))
        rows.append(("0", "none", *("0.0" for _ in names)))
        return Table(["springs", "kept", *(f"{n} removed (%)" for n in names)], rows)

    def narrowed_table(self) -> Table:
        """The narrower workspaces on which the realised springs clear the links (:attr:`narrowed`): the ranges
        (as ``--workspace`` takes them), the share of the workspace they keep, the nearest approach over their fresh
        poses, and each loaded joint's share removed there."""
        names = [self.model.joints[i] for i in self.structure.loaded]
        rows = [(n.workspace(self.model), f"{100 * n.kept:.0f}", f"{n.fresh:,}",
                 f"{1e3 * n.nearest:.1f} ({n.spring}, {n.link})", *(f"{n.removed.get(j, float('nan')):.1f}" for j in names))
                for n in self.narrowed]
        return Table(["narrowed (--workspace, deg)", "workspace kept (%)", "fresh poses, all clear",
                      "nearest link on them (mm)", *(f"{j} removed (%)" for j in names)], rows)

    def parts_table(self) -> Table:
        """Every part of the realised springs' hardware (:func:`springlab.design.hardware.parts`): its kind,
        the link it rides on, its mass (g), sizes (mm) and the largest loads over :attr:`q`."""

        rows = []
        for p in parts(self.model, self.realised, self.kinds, self.coils, self.realised_names, self.q):
            size = _sizes(p)
            loads = ", ".join(f"{k.rsplit('_', 1)[0].replace('_', ' ')} {v:.3g} {k.rsplit('_', 1)[1]}"
                              if isinstance(v, float) else str(v) for k, v in p.loads.items() if k != "breaking_load_N")
            rows.append((p.name, p.kind, p.link, f"{1e3 * p.mass:.0f}", size, loads))
        return Table(["part", "kind", "rides on", "mass (g)", "sizes (mm)", "largest loads"], rows)

    def stock_table(self) -> Table:
        """Each realised spring's stock part (:mod:`springlab.design.catalogue`), or why it is wound to order: the
        part number, how many side by side and over which block, the catalogue's rate, and the part's working
        range over :attr:`q` (length inside the hooks, mm; pull, N) against the catalogue's largest extension
        and load."""
        rows = []
        for name, kind, fit in zip(self.realised_names, self.kinds, self.coils, strict=True):
            part = getattr(fit.coil, "part", None)
            if part is None:
                why = kind.split("custom-wound (", 1)[1].rstrip(")") if "custom-wound (" in kind else "wound to order"
                rows.append((name, "none: wound to order", "", "", "", "", why))
                continue
            low, high = fit.forces()
            short, long = (float(v) for v in fit.coil_length(np.asarray(fit.span, dtype=float)))
            count = kind.split(" side by side")[0].rsplit(" of ", 1)[1] if " side by side" in kind else "1"
            rows.append((name, part.part_number, f"{count}, {fit.ratio}:1", f"{part.rate / 1e3:.4g}",
                         f"{1e3 * short:.1f}-{1e3 * long:.1f} of {1e3 * part.max_extended_length:.1f}",
                         f"{low:.1f}-{high:.1f} of {part.max_load:.1f}", ""))
        return Table(["spring", "stock part", "side by side, block", "rate (N/mm)", "length in service (mm)",
                      "pull in service (N)", "why none"], rows)

    def bom(self) -> Table:
        """The shopping list: one row per item to buy (identical parts at one place counted together), with
        its quantity, what to buy (a coil: its wire, diameters, coils, free length inside its machine hooks,
        initial tension and rate; a rope: its construction and length; a pulley, a belt, a post, a bracket:
        their sizes), the link it rides on and where there (mm, in the link's URDF frame; a spring's and its
        cable's ends too), and its mass (g). Its parts are :func:`springlab.design.hardware.parts`'s."""

        springs = dict(zip(self.realised_names, zip(self.realised, self.coils, strict=True), strict=True))
        rows: dict = {}
        for p in parts(self.model, self.realised, self.kinds, self.coils, self.realised_names, self.q):
            name = p.name.split(" ", 1)[0]
            r, fit = springs.get(name, (None, None))
            ends = f"{r.link_a} {_mm(r.point_a)} to {r.link_b} {_mm(r.point_b)}" if r is not None else ""
            part = getattr(fit.coil, "part", None) if fit is not None else None
            if p.kind == "spring" and part is not None:
                what = (f"stock extension spring {part.part_number}: outer diameter {1e3 * part.outer_diameter:.2f} mm, "
                        f"wire {1e3 * part.wire:.2f} mm, free length {1e3 * part.free_length:.1f} mm, rate "
                        f"{part.rate / 1e3:.4g} N/mm, initial tension {part.initial_tension:.2f} N (catalogue)")
            elif p.kind == "spring":
                c = fit.coil
                what = (f"{c.material} ({MATERIALS[c.material].standard}) extension spring, machine hooks: wire "
                        f"{1e3 * c.wire:.2f} mm, outer diameter {1e3 * c.outer_diameter:.2f} mm, {c.body_coils:.2f} "
                        f"body coils, free length {1e3 * c.free_length:.1f} mm inside the hooks, initial tension "
                        f"{c.initial_tension:.2f} N, rate {c.rate / 1e3:.4g} N/mm")
            elif p.kind == "cable" and fit is not None and fit.cable is not None:
                what = (f"wire rope {fit.cable.name}, breaking load {fit.cable.breaking:.4g} N, cut to "
                        f"{1e3 * p.size['length']:.0f} mm")
            else:
                what = f"{p.kind}: {_sizes(p, ' mm')}"
                ends = ends if p.kind == "cable" else ""
            key = (p.kind, what, p.link, _mm(p.centre), ends, f"{1e3 * p.mass:.0f}")
            rows.setdefault(key, []).append(p.name)
        return Table(["items", "quantity", "what to buy", "rides on", "where (mm, its link's frame)",
                      "ends (mm, their links' frames)", "mass each (g)"],
                     [(", ".join(names), len(names), what, link, at, ends, mass)
                      for (kind, what, link, at, ends, mass), names in rows.items()])

    def control(self, factor: float = 0.9) -> tuple[float, float]:
        """The negative control: the largest holding torque (N m, over joints and the workspace poses)
        of the ideal springs as designed and with every rate times ``factor``. A check that cannot
        fail checks nothing: the scaled springs must leave more."""
        scaled = [s.scaled(factor) for s in self.ideal]
        arm = self.designed_for
        return (float(np.max(np.abs(joint_torques(arm, self.ideal, self.q)))),
                float(np.max(np.abs(joint_torques(arm, scaled, self.q)))))

    def control_by_joint(self, factor: float = 0.9) -> dict:
        """The negative control joint by joint: {loaded joint's name: (the largest holding torque as designed,
        with every rate times ``factor``) N m over the workspace poses}, for the loaded joints but the light
        ones the springs leave alone (below :data:`~springlab.design.layouts.SHARE` of the largest peak, as
        :meth:`reached` counts them: a light joint left out keeps its own torque whatever the rates, which
        would hide the control)."""
        arm = self.designed_for
        designed = np.max(np.abs(joint_torques(arm, self.ideal, self.q)), axis=0)
        scaled = np.max(np.abs(joint_torques(arm, [s.scaled(factor) for s in self.ideal], self.q)), axis=0)
        light = self._light()
        return {self.model.joints[j]: (float(designed[j]), float(scaled[j])) for j in self.structure.loaded
                if j not in light or abs(scaled[j] - designed[j]) > 1e-12 * max(1.0, designed[j])}

    def _light(self) -> set:
        """The loaded joints (indices) whose gravity peak is below :data:`~springlab.design.layouts.SHARE` of
        the largest: those a layout may leave out, which :meth:`reached` and :meth:`control_by_joint` set
        apart."""
        peak = np.asarray(self.structure.peak)
        return {i for i in self.structure.loaded if peak[i] < SHARE * float(np.max(peak))}

    @property
    def designed_for(self) -> RevoluteChain:
        """The arm the springs were designed for: carrying their hardware's mass where the layout designed
        for it (:attr:`carried`), else the arm alone."""
        return self.massed if self.carried and self.massed is not None else self.model

    def removed(self, which: str = "ideal") -> np.ndarray:
        """Per joint, the percentage of its peak gravity torque the springs remove (nan where unloaded)."""
        springs = self.ideal if which == "ideal" else self.realised
        gravity = np.max(np.abs(gravity_torques(self.model, self.q)), axis=0)
        left = np.max(np.abs(joint_torques(self.model, springs, self.q)), axis=0)
        out = 100 * (1 - left / np.where(gravity > 0, gravity, np.nan))
        out[list(self.structure.unloaded)] = np.nan
        return out

    def as_dict(self) -> dict:
        """The design as ``springlab design --json`` writes it; each spring by the contract's names
        (link_a, point_a, link_b, point_b in m and the links' URDF frames, k N/m, free_length m,
        initial_tension N)."""
        gravity = gravity_torques(self.model, self.q)
        torques = {"ideal": joint_torques(self.model, self.ideal, self.q),
                   "realised": joint_torques(self.model, self.realised, self.q)}
        if self.massed is not None:
            torques["realised_with_spring_mass"] = joint_torques(self.massed, self.realised, self.q)
        rows = []
        for i, name in enumerate(self.model.joints):
            row = {"joint": name, "loaded": i not in self.structure.unloaded,
                   "gravity_peak_Nm": float(np.max(np.abs(gravity[:, i]))),
                   "gravity_rms_Nm": float(np.sqrt(np.mean(gravity[:, i] ** 2)))}
            for case, tau in torques.items():
                row[f"{case}_peak_Nm"] = float(np.max(np.abs(tau[:, i])))
                row[f"{case}_rms_Nm"] = float(np.sqrt(np.mean(tau[:, i] ** 2)))
            rows.append(row)
        flags = self.flags()
        origins = self.origins or tuple(range(len(self.realised)))
        changes = self.changes or ("",) * len(self.realised)
        near = {r[0]: r for r in (self.clearance.rows if self.clearance is not None else ())}

        ends = coil_ends(self.model, self.realised, self.kinds, self.coils, self.q) if self.realised else []
        hardware = [{"mass_kg": fit.coil.mass, "coil_outer_diameter": fit.coil.outer_diameter, "block_ratio": fit.ratio,
                     "cable": None if fit.cable is None else fit.cable.as_dict()} | end
                    | ({"clearance_m": near[n][4], "nearest_link": near[n][2], "nearest_piece": near[n][1],
                        "nearest_pose": self.q[near[n][3]].tolist(),
                        "share_of_poses_within_margin": self.clearance.within.get(n, 0.0)} if n in near else {})
                    for n, fit, end in zip(self.realised_names, self.coils, ends, strict=True)]
        listed = [p.as_dict() for p in parts(self.model, self.realised, self.kinds, self.coils, self.realised_names,
                                               self.q)] if self.realised else []
        return {"arm": self.model.name, "method": self.method,
                "status": {"verdict": "flagged" if flags else "passed", "flags": list(flags)},
                "joints": list(self.model.joints),
                "loaded_joints": [self.model.joints[i] for i in self.structure.loaded],
                "structure": self.structure.why, "poses_checked": int(self.q.shape[0]),
                "audit": None if self.audit is None else self.audit.as_dict(),
                "ideal": [{"name": name} | s.as_dict() | belt_frames(self.model, s)
                          for name, s in zip(self.names, self.ideal, strict=True)],
                "realised": [{"name": name, "realises": self.names[i], "changed": why} | s.as_dict()
                             | belt_frames(self.model, s) | _coil_fields(kind, coil, span) | extra
                             for name, i, why, s, kind, (coil, span, *_), extra in zip(
                                 self.realised_names, origins, changes, self.realised, self.kinds, self.coils,
                                 hardware, strict=True)],
                "workspace": self.workspace,
                "clearance": None if self.clearance is None else {
                    "margin_m": self.clearance.margin, "poses": self.clearance.poses,
                    "clears": not self.clearance.failing(),
                    "narrowed_workspaces": [n.as_dict(self.model) for n in self.narrowed]},
                "spring_mass_kg": float(sum(h["mass_kg"] for h in hardware)),
                "hardware_mass_kg": float(sum(p["mass_kg"] for p in listed)),
                "parts": listed,
                "left_out": [{"realises": self.names[i], "why": why} for i, why in self.left_out],
                "torques": rows, "notes": list(self.notes)}


def belt_frames(model: RevoluteChain, spring) -> dict:
    """For --json, each end a belt or paper 001's RSSR modules carry
    (:meth:`~springlab.model.revolute.RevoluteChain.with_belt`,
    :meth:`~springlab.model.revolute.RevoluteChain.with_pseudobase`): ``frame_a`` (or ``frame_b``) = {"at_joint": the joint, "axes_of": the level link,
    "along_axis": d, "kept_by": "belt" or "RSSR modules"}, meaning that ``point_a`` is given from the point d (m)
    along that joint's axis from its origin, in the axes of that link, which the belt keeps (the RSSR modules
    keep its vertical line: the point lies on it)."""
    out = {}
    for end, link in (("a", spring.link_a), ("b", spring.link_b)):
        belt = next((b for b in model.belts if b.name == link), None)
        if belt is not None:
            out[f"frame_{end}"] = {"at_joint": model.joints[belt.joint], "axes_of": model.bodies[belt.level],
                                   "along_axis": belt.along, "kept_by": "belt" if belt.kind == "belt" else
                                   "RSSR modules"}
    return out


def _coil_fields(kind: str, coil, span) -> dict:
    """How a realised spring is built, for --json (m, N): its kind, the coil's own free length (inside
    the hooks), longest stretched length, wire and mean diameters and body coils, and for a cable spring
    the cable's offset L_0 - F_i / k (its force is F_i + k (path + offset - L_0) = k * path along the
    cable's path, whose range over the workspace is ``span``)."""
    out = {"kind": kind, "coil_free_length": coil.free_length, "coil_max_length": coil.max_length,
           "wire_diameter": coil.wire, "mean_diameter": coil.mean_diameter, "body_coils": coil.body_coils,
           "material": coil.material, "end_distance_range": list(span)}
    part = getattr(coil, "part", None)
    if part is not None:  # a stock part: the catalogue's values (k N/m, lengths m, forces N)
        out |= {"part_number": part.part_number,
                "part": {"k": part.rate, "free_length": part.free_length, "initial_tension": part.initial_tension,
                         "max_extended_length": part.max_extended_length, "max_load": part.max_load,
                         "outer_diameter": part.outer_diameter} | {k: v for k, v in part.extra.items() if v}}
    if kind.startswith("cable over a pulley"):
        out["cable_offset"] = coil.cable_offset
    return out


CARRY_ROUNDS = 2
"""How many times the belt layout is designed again for the arm carrying the springs it found (their masses
change a little with their rates)."""


def _check_pulley(model: RevoluteChain, pulley_radius) -> float:
    """``pulley_radius`` (m), refused when a pulley that size would not fit on a link: more than half
    the smallest moving link's size (its outline's largest side, else the distance to the next joint)."""
    pulley_radius = _checks.positive("pulley_radius", pulley_radius, allow_zero=True, unit="m")
    if pulley_radius == 0:
        return pulley_radius
    sizes = []
    for b in range(1, model.n + 1):
        if model.outline and len(model.outline[b]):
            sizes.append((float(np.max(np.ptp(model.outline[b], axis=0))), model.bodies[b]))
        elif b < model.n and np.linalg.norm(model.placements[b][:3, 3]) > 1e-3:
            sizes.append((float(np.linalg.norm(model.placements[b][:3, 3])), model.bodies[b]))
    sizes = [item for item in sizes if item[0] > 1e-3]
    if sizes:
        size, name = min(sizes)
        if pulley_radius > 0.5 * size:
            raise SpringlabError(f"pulley_radius = {pulley_radius:g} m is larger than link {name!r} ({size:.3g} m across) "
                                 f"can carry: a pulley rides on a link; give at most {0.5 * size:.3g} m (e.g. 0.005)")
    return pulley_radius


def _reach_note(model: RevoluteChain, reach) -> str:
    """Where the spring ends may sit (``attachment_boxes``), in words."""
    known = [bool(model.outline) and len(p) > 0 for p in (model.outline or [()] * (model.n + 1))]
    bracket = BRACKET if reach is None else reach
    length = float(np.sum(np.linalg.norm(model.placements[:, :3, 3], axis=1)))
    margin = max(0.05, 0.15 * length) if reach is None else reach
    if all(known):
        return (f"spring ends lie within each body's outline (the bounding box of its URDF geometry) and "
                f"{100 * bracket:.3g} cm beyond it (a bracket; --reach)")
    box = (f"a box centred between its joint and the next, half their distance plus {100 * margin:.3g} cm each "
           "way along its axes")
    if not any(known):
        return f"spring ends lie, on each body, within {box} (the file gives no geometry; --reach)"
    missing = ", ".join(repr(model.bodies[i]) for i, k in enumerate(known) if not k)
    return (f"spring ends lie within each body's outline (the bounding box of its URDF geometry) and "
            f"{100 * bracket:.3g} cm beyond it; for {missing}, which {'has' if missing.count(',') == 0 else 'have'} "
            f"no geometry, within {box} (--reach)")


def _percent(share: float) -> str:
    """A share (0 to 1) as a percentage to two significant digits, "< 0.1 %" and "> 99.9 %" at the ends but for
    none and all: 0.3625 -> '36 %'."""
    if share in (0.0, 1.0):
        return f"{100 * share:.0f} %"
    if share < 0.001:
        return "< 0.1 %"
    if share > 0.999:
        return "> 99.9 %"
    return f"{float(f'{100 * share:.2g}'):g} %"


def design_model(model: RevoluteChain, *, workspace=None, samples: int = 2000, fit_poses: int = 300, seed: int = 1,
                 target: float = 0.1, reach: float | None = None, max_springs: int = 8,
                 max_stiffness: float = MAX_STIFFNESS, material: str = "auto",
                 pulley_radius: float | None = 0.0, tag: str = "S", margin: float | None = None,
                 collisions: bool = True, layout: str = "two-point", share: float | None = None,
                 cable=None, audit_samples: int = AUDIT_SAMPLES, catalogue=None, narrow: bool = True) -> ArmDesign:
    """Springs for an arm of the general model over its workspace (:func:`workspace_ranges`): its
    structure (:func:`~springlab.design.structure.structure`); the exact planar springs where its loaded joints form a planar
    chain (:func:`~springlab.design.structure.planar_springs`), else the best springs (:func:`~springlab.design.search.best_springs`, fitted on
    ``fit_poses`` poses); their realisation (:func:`~springlab.design.realise.realise_springs`); all checked by route 2 on
    ``samples`` other random poses of the workspace, then re-checked on an independent sample of
    ``audit_samples`` poses (:class:`~springlab.design.audit.Audit`; a quick run may take fewer). Its springs
    are named ``tag`` and a number (S1, S2, ...).

    An arm with collision geometry (a URDF read with its shapes) is designed over its free workspace
    (:class:`~springlab.design.collision.Sampler`: no two links in collision, none below the mounting
    plane; ``collisions=False``: the ranges' box), its realised springs' clearance from the links is
    measured against ``margin`` (m, default :data:`~springlab.design.collision.MARGIN`) on the check
    poses, and the arm carrying the springs' own mass is kept beside it
    (:mod:`springlab.design.hardware`). Where a realised spring runs into a link, ``narrow`` (default) seeks the
    narrower workspaces on which the same springs clear (:func:`~springlab.design.narrowing.narrowed`).

    ``layout='auto'`` takes the belts where the loaded joints (the light ones left out) form a planar
    chain and the arm has collision geometry, else the two-point springs.
    ``layout='belts'`` (a planar loaded chain only): one spring per loaded link from a post on a level
    frame a 1:1 belt carries to the link's joint (:func:`springlab.design.layouts.belt_layout`), its coil
    along the link, the pulley compensated for; joints below ``share`` of the largest gravity peak
    (default :data:`springlab.design.layouts.SHARE`) get none; each cable is the stocked one that carries
    its pull (:mod:`springlab.design.cables`, or ``cable``), over a pulley sized to it
    (``pulley_radius=None``) or of ``pulley_radius`` (m). ``'two-point'`` (default): springs between two
    links' points, exact for a planar chain, else the best springs, their cables over pulleys of
    ``pulley_radius`` (None: sized to the cable of the largest pull).

    Each coil is wound from ``material``'s wire (:data:`springlab.design.buildable.MATERIALS`); ``'auto'``
    (default) from music wire, or chrome silicon where that saves a side-by-side coil or a pulley block
    (:func:`springlab.design.realise.coil_for`); with a ``catalogue``
    (:func:`springlab.design.catalogue.read_catalogue`, the belts and pseudobases only) each is made of that
    catalogue's stock parts where some fit, its ends re-placed for their rate
    (:func:`springlab.design.layouts.realise_layout`), else wound to order."""
    if layout not in ("two-point", "belts", "pseudobases", "auto"):
        raise SpringlabError(f"layout = {layout!r}: give 'two-point' (springs between two links), 'belts' (a level "
                             "reference carried by belts to each joint of a planar chain), 'pseudobases' (carried "
                             "by paper 001's RSSR modules, any arm) or 'auto' (belts, else pseudobases, where the "
                             "arm has link shapes to clear)")

    margin = MARGIN if margin is None else _checks.positive("margin", margin, allow_zero=True, unit="m")
    wires(material)  # a wire springlab stocks, or 'auto'
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    if not (isinstance(tag, str) and tag.isalpha() and tag.isupper()):
        raise SpringlabError(f"tag = {tag!r}: give capital letters, e.g. 'S' (springs S1, S2, ...) or 'P'")
    samples = _checks.count("samples", samples, least=1)
    audit_samples = _checks.count("audit_samples", audit_samples, least=100)
    sized = pulley_radius is None  # the pulleys sized to their cables
    if not sized:
        _check_pulley(model, pulley_radius)
    ranges = workspace_ranges(model, workspace)
    rng = np.random.default_rng(seed)
    sampler = (Sampler(model, ranges, np.random.default_rng([seed, 17]), limits=workspace_ranges(model))
               if collisions and has_geometry(model) else None)

    def draw(count):
        if sampler is None:
            return rng.uniform(ranges[:, 0], ranges[:, 1], (count, model.n))
        return sampler.draw(count, rng)

    check = draw(samples)
    found = structure(model, check)  # the poses every table reports on
    notes = list(model.notes)
    if sampler is not None:
        notes += sampler.notes
    if not found.loaded:
        return ArmDesign(model, found, "nothing to balance", (), (), (), (), check,
                         (*notes, "gravity loads no joint of this arm over its workspace: nothing to balance"), tag=tag)
    if layout == "auto":
        trimmed = without_light(model, found, SHARE if share is None else share, check)
        layout = ("two-point" if not has_geometry(model) else "belts" if trimmed.planar else "pseudobases")
        notes.append("layout: " + {"belts": "belts, the loaded joints (the light ones left out) forming a planar chain",
                                   "pseudobases": "pseudobases (paper 001's RSSR modules), the loaded joints not "
                                                  "forming a planar chain",
                                   "two-point": "two-point springs (no link shapes to clear)"}[layout])
    if catalogue is not None and layout == "two-point":
        raise SpringlabError("catalogue: stock parts are chosen for the belts' and the pseudobases' springs, whose "
                             "ends can be re-placed for a part's rate; give --layout belts, pseudobases or auto on an "
                             "arm with link shapes")
    spatial = layout == "pseudobases"
    if spatial:
        layout = "belts"
    if layout == "belts":
        arrange = pseudobase_layout if spatial else belt_layout
        share = SHARE if share is None else share
        lay = arrange(model, found, share=share, q=check)
        realised, kinds, coils, origins = realise_layout(lay, check, material=material, cable=cable,
                                                         pulley_radius=None if sized else pulley_radius, margin=margin,
                                                         catalogue=catalogue)
        bare = (model.mass, model.com, model.inertia)
        for _ in range(CARRY_ROUNDS):  # the springs' own steel rides on the links: designed for too
            arm = replace(lay.model, mass=bare[0], com=bare[1], inertia=bare[2])  # the arm alone, with the belts
            built = [m for m, r in enumerate(realised) if r is not None]
            prefer = {origins[m]: (coils[m].choice, sum(o == origins[m] for o in origins),
                                   None if getattr(coils[m].coil, "part", None) is None else
                                   (coils[m].coil.part.part_number, coils[m].ratio)) for m in built}
            realised, kinds, coils = ([v[m] for m in built] for v in (realised, kinds, coils))
            carried = replace(with_spring_mass(arm, realised, kinds, coils, check), belts=())
            widths = {}  # a pseudobase's C moves beside the links by half its coils' width too
            for r, fit in zip(realised, coils, strict=True):
                t = balanced_body(lay.model, r) - 1
                widths[t] = widths.get(t, 0.0) + fit.coil.outer_diameter
            lay = arrange(carried, structure(carried, check), share=share, q=check,
                          **({"widths": widths} if spatial else {}))
            realised, kinds, coils, origins = realise_layout(lay, check, material=material, cable=cable,
                                                             pulley_radius=None if sized else pulley_radius,
                                                             margin=margin, prefer=prefer, catalogue=catalogue)
        model, ideal = replace(lay.model, mass=bare[0], com=bare[1], inertia=bare[2]), lay.springs
        if spatial:
            method = "pseudobases: a vertical line carried to each loaded joint by paper 001's RSSR modules"
            notes += [f"pseudobases: {found.why}; one spring per loaded link's subsystem (001 Eq. 5), from a post "
                      "above a point of its joint's axis, on a pseudobase (or a belt's frame where the joints between "
                      "are parallel), to the link along the subsystem's moment, its coil along the link behind a "
                      f"pulley, designed for the arm carrying the springs' own mass ({CARRY_ROUNDS} rounds)",
                      *lay.notes]
        else:
            method = "belts: a level reference carried to each loaded joint (paper 001's pseudobases)"
            notes += [f"belts: {found.why}; one spring per loaded link, from a post on the level frame at its joint "
                      "to the link, its coil along the link behind a pulley, designed for the arm carrying the "
                      f"springs' own mass ({CARRY_ROUNDS} rounds)", *lay.notes]
        radii = sorted({r.pulley_radius for r in realised if r is not None})
        if radii and radii[-1] > 0:
            sizes = ", ".join(f"{1e3 * r:.3g}" for r in radii)
            notes.append(f"the springs' cables wrap their pulleys at {sizes} mm" + (
                " (each sized to its cable, the rope maker's D/d)" if sized else "") + ": each one's lever, post and "
                "rate re-fitted for it over the angles the workspace takes its link through (route 2's cable path)")
        pulley_radius = radii[-1] if radii else 0.0
    else:
        notes.append(_reach_note(model, reach))
    if layout == "belts":
        pass
    elif found.planar:
        ideal, method = planar_springs(model, found, reach=reach), "exact: planar chain"
        notes.append(f"exact: {found.why}")
    else:
        fit = best_springs(model, found, draw(fit_poses),
                           target=target, reach=reach, max_springs=max_springs, max_stiffness=max_stiffness)
        ideal, method = fit.springs, "best springs"
        notes.append(f"not exact: {found.why}; springlab's exact construction needs a planar chain, so the "
                     f"best springs were searched: {fit.note}")
    if layout == "two-point" and sized:
        pulley_radius = sized_pulley(model, ideal, check)
    if layout == "two-point":
        realised, kinds, coils, origins = realise_with_origins(
            model, ideal, check, material=material, pulley_radius=pulley_radius, reach=reach,
            fit=draw(min(150, fit_poses)), max_stiffness=max_stiffness)
    for kind in kinds:
        if kind.startswith("not realised"):
            notes.append(f"{kind}: the realised design leaves it out")
    left_out = tuple((origins[m], kinds[m].split("): ", 1)[-1]) for m, r in enumerate(realised) if r is None)
    kept = [m for m, r in enumerate(realised) if r is not None]
    realised, coils, kinds, origins = (tuple(v[m] for m in kept) for v in (realised, coils, kinds, origins))
    changes = realisation_changes(model, ideal, realised, kinds, origins)
    audit = Audit.of(model, ranges, {"ideal": ideal, "realised": realised}, check, seed, samples=audit_samples,
                     sampler=sampler)
    check = np.vstack([check, audit.worst])  # the notes and tables report on the audit's worst poses too
    gravity = np.max(np.abs(gravity_torques(model, check)), axis=0)
    left = np.max(np.abs(joint_torques(model, ideal, check)), axis=0)
    for i in np.flatnonzero(left > gravity * (1 + 1e-9) + 1e-9 * np.max(gravity)):  # above round-off
        notes.append(f"joint {model.joints[i]}: the springs leave {left[i]:.3g} N m at worst, more than gravity's own "
                     f"{gravity[i]:.3g} N m (the search holds every joint below the larger of its own peak and a tenth "
                     f"of the largest, {0.1 * float(np.max(gravity)):.3g} N m)")
    real = np.max(np.abs(joint_torques(model, realised, check)), axis=0)
    for i in found.loaded:
        if pulley_radius > 0 and real[i] > 0.5 * gravity[i] and real[i] > left[i] + 0.1 * gravity[i] and gravity[i] > 0:
            notes.append(f"joint {model.joints[i]}: the realised springs over {1e3 * pulley_radius:g} mm pulleys leave "
                         f"{real[i]:.3g} N m of its {gravity[i]:.3g} N m (the ideal ones {left[i]:.3g}): each pulley adds "
                         "about k rho times the change of its wrap angle, large against this arm's levers and rates; a "
                         "smaller --pulley-radius (or 0, a point) or longer brackets (--reach) do better")
    cables = layout == "two-point" and any(kind.startswith("cable over a pulley") for kind in kinds)
    if cables and pulley_radius == 0:
        notes.append("cable springs are modelled with a point pulley (the force k times |B - A|): give a pulley radius "
                     "(--pulley-radius) to model the pulley")
    elif cables:
        notes.append(f"cable springs run over pulleys of radius {1e3 * pulley_radius:g} mm (route 2's cable path); "
                     "their leads (and where those leave more than a tenth of a joint's peak, their rates and ends) "
                     f"were chosen for it on {min(150, fit_poses)} poses the table does not use")
    reported = structure(model, check)  # the same peaks as the torque tables, the audit's worst poses included
    found = reported if reported.loaded == found.loaded else found
    design = ArmDesign(model, found, method, ideal, realised, kinds, coils, check, tuple(notes), origins, changes, audit,
                       tag, left_out)
    if not realised:
        return design
    clearance, narrower = None, ()
    massed = with_spring_mass(model, realised, kinds, coils, check)
    if sampler is not None:
        clearance = spring_clearance(model, realised, kinds, coils, design.realised_names, check, margin=margin)
        if clearance.failing() and narrow:
            narrower = narrowed(model, realised, kinds, coils, design.realised_names, check, ranges, random=samples,
                                margin=margin, fresh=min(samples, 2000), seed=seed, loaded=found.loaded,
                                massed=massed if layout == "belts" else None, limits=workspace_ranges(model))
    workspace = sampler.note() if sampler is not None else "the joint ranges' box (the arm has no collision geometry)"
    return replace(design, clearance=clearance, massed=massed, workspace=workspace, carried=layout == "belts",
                   narrowed=narrower)
