"""Springs for your own arm: ranked, verified designs (paper 000's method, any n).

:func:`design_arm` takes an :class:`~springlab.model.armfile.ArmSpec` (or an arm file)
and returns designs ranked by spring count, then the largest spring force over
the arm's workspace, then the system spring efficiency. Each is verified by route
2 (the total energy over the workspace samples varies by less than 1e-10 of the
gravity energy's range) *before* it is returned; one that fails is dropped, with
the reason kept in the report.

The system spring efficiency that breaks ties is :mod:`springlab.design.efficiency`'s; the
n - 1 ground springs and other sign patterns are in :mod:`springlab.design.ground`, the
methods compared (000, ground springs, 001's pseudobases) in :mod:`springlab.design.methods`.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import functools
import re
import time
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from springlab import _checks
from springlab.design.clearance import clearance
from springlab.design.efficiency import spatial_system_efficiency
from springlab.design.rules import SpringSlot, as_slots, best_first_configurations
from springlab.design.screen import all_pattern_slots, any_sign_candidates, screen_verdicts
from springlab.design.solve import (
    balanced_core,
    find_design,
    largest_force_bound,
    minimise_largest_force,
    relaxation_margin,
)
from springlab.energy import geometry
from springlab.energy.geometry import energies, spring_length
from springlab.errors import SearchExhaustedError, SpringlabError, UnbalanceableError
from springlab.executors import check_executor, map_ordered
from springlab.model.armfile import ArmSpec, load_arm
from springlab.model.chain import Chain, check_springs, limited_poses, random_directions
from springlab.model.springs import Spring
from springlab.tables import Table

METHODS = ("fewest springs", "no auxiliary links", "ground springs")
"""What :func:`design_arm` searches: every family below, ranked together (the default); paper
000's configurations (rules R1-R6); or the n - 1 ground springs alone."""

ANY_SIGNS = "any signs"
"""The family of sets of n - 2 springs of any sign pattern that pass the relaxation screen."""

SCREEN_BUDGET = 200_000
"""Most candidate sets of n - 2 springs the default search screens (n = 6 has 61,712, refuted
by their signs in 0.4 s; n = 7 has about 3.5 million): above it the report says they were not."""


VERIFY_TOLERANCE = 1e-10
"""The largest relative variation of the total energy (of the gravity range) a verified design may show."""
PROOF = "proof"
"""Prefix of a rejection that is proved (the linear relaxation): any other reason is a search
that ran out of starts or limits, not a proof."""


def random_poses(chain: Chain, samples: int, seed) -> np.ndarray:
    """``samples`` seeded link-direction sets (N, n, 3): uniform directions for a spherical
    chain, uniform joint angles for one with revolute joints."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    samples = _checks.count("samples", samples, least=1)
    _checks.memory(f"{samples} workspace samples of a {chain.n}-link arm", 6.0 * samples * chain.n * 3,
                   hint="use fewer samples")
    rng = _checks.rng("seed", seed)
    if chain.all_spherical:
        return random_directions(chain.n, samples, rng)
    return chain.directions(chain.random_angles(samples, rng))


def workspace_poses(spec: ArmSpec, chain: Chain) -> np.ndarray:
    """The poses that judge a design: the arm file's ``samples`` and ``seed``, within its joint
    limits (:func:`springlab.model.chain.limited_poses`) where it gives any."""
    _checks.instance("spec", spec, ArmSpec, "ArmSpec (load_arm(path))")
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    if spec.limits:
        return limited_poses(chain, spec.samples, _checks.rng("seed", spec.seed), spec.limits)
    return random_poses(chain, spec.samples, spec.seed)


def workspace_note(spec: ArmSpec) -> str:
    """Which workspace judges the designs, in words."""
    _checks.instance("spec", spec, ArmSpec, "ArmSpec (load_arm(path))")
    if not spec.limits:
        return (f"workspace: {spec.samples} random poses (seed {spec.seed}), every link in any direction "
                "(no joint limits in the arm file: folded poses included)")
    parts = [f"joint {j}: " + (f"cone {np.degrees(lim):g} deg" if not isinstance(lim, tuple) else
                               f"{np.degrees(lim[0]):g} to {np.degrees(lim[1]):g} deg")
             for j, lim in enumerate(spec.limits, start=2) if lim is not None]
    return f"workspace: {spec.samples} random poses (seed {spec.seed}) within the joint limits ({'; '.join(parts)})"


@dataclass(frozen=True)
class RankedDesign:
    """One verified design. Forces in N, stiffness in N/m, energies in J."""

    method: str
    configuration: tuple
    springs: tuple
    max_force: float
    stiffness_sum: float
    efficiency: float  # mean spatial e_sys over the workspace samples
    energy_variation: float  # route 2: max - min total energy / gravity range
    spans: int  # joints spanned, summed over the springs
    clearance: float = float("inf")  # m: the smallest spring-link clearance over the workspace; < 0 crosses a link

    @property
    def crosses(self) -> bool:
        """True when a spring passes through a link somewhere in the workspace."""
        return self.clearance < 0

    @property
    def spring_count(self) -> int:
        return len(self.springs)

    def label(self) -> str:
        return " ".join(f"{s.label}{s.pattern}" for s in self.springs) or "no springs"

    def to_dict(self) -> dict:
        return {"method": self.method, "configuration": [str(c) for c in self.configuration],
                "springs": [{"i": s.i, "j": s.j, "pattern": s.pattern, "a_m": s.a, "b_m": s.b, "k_N_per_m": s.k}
                            for s in self.springs],
                "max_force_N": self.max_force, "stiffness_sum_N_per_m": self.stiffness_sum,
                "efficiency": self.efficiency, "energy_variation": self.energy_variation,
                "clearance_m": self.clearance if np.isfinite(self.clearance) else None}


@dataclass
class DesignReport:
    """The ranked designs and what was tried: ``rejected`` lists (configuration, reason)."""

    spec: ArmSpec
    designs: list = field(default_factory=list)
    rejected: list = field(default_factory=list)
    configurations_tried: int = 0
    seconds: float = 0.0
    stopped: str = ""  # why the search ended
    notes: list = field(default_factory=list)  # what the designer assumed of this arm

    def reasons(self, top: int = 5) -> list[tuple[int, str]]:
        """The rejections' reasons grouped by kind (springs and numbers blanked), most frequent
        first: (count, the first reason of that kind)."""
        kinds = Counter(_reason_kind(why) for _, why in self.rejected)
        first = {}
        for _, why in self.rejected:
            first.setdefault(_reason_kind(why), why)
        return [(count, first[kind]) for kind, count in kinds.most_common(top)]

    def table(self) -> Table:
        """The ranked designs as a table (shown as Markdown in a notebook)."""
        return Table(["rank", "springs", "family", "configuration", "max force (N)", "clearance (mm)", "sum of k (N/m)",
                      "efficiency", "energy variation"],
                     [(rank, d.spring_count, d.method, d.label(), f"{d.max_force:.1f}",
                       (f"{d.clearance * 1e3:.0f}" + (" (crosses a link)" if d.crosses else "")
                        if np.isfinite(d.clearance) else "no other link"), f"{d.stiffness_sum:.0f}",
                       f"{d.efficiency:.4f}", f"{d.energy_variation:.1e}")
                      for rank, d in enumerate(self.designs, start=1)])

    def criteria_table(self) -> Table:
        """The ranked designs by the criteria the methods are compared on: springs, joints spanned, sum
        of k (N/m), largest spring force (N), mass added (kg: none without auxiliary links) and
        efficiency."""
        return Table(["rank", "springs", "joints spanned", "sum of k (N/m)", "largest spring force (N)",
                      "added mass (kg)", "efficiency"],
                     [(rank, d.spring_count, d.spans, f"{d.stiffness_sum:.0f}", f"{d.max_force:.1f}", "0",
                       f"{d.efficiency:.3f}") for rank, d in enumerate(self.designs, start=1)])

    def csv(self) -> str:
        """Every ranked design as CSV for a spreadsheet: one row a design (rank, family, largest
        force N, clearance m, sum of k N/m, efficiency, energy variation), then one column group
        per spring (slot, pattern, a m, b m, k N/m), empty where a design has fewer springs.
        Numbers at full precision."""
        import csv
        import io

        width = max((d.spring_count for d in self.designs), default=0)
        head = ["rank", "springs", "family", "configuration", "max_force_N", "clearance_m", "stiffness_sum_N_per_m",
                "efficiency", "energy_variation"]
        for idx in range(1, width + 1):
            head += [f"spring{idx}_slot", f"spring{idx}_pattern", f"spring{idx}_a_m", f"spring{idx}_b_m",
                     f"spring{idx}_k_N_per_m"]
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(head)
        for rank, d in enumerate(self.designs, start=1):
            row = [rank, d.spring_count, d.method, d.label(), repr(d.max_force),
                   repr(d.clearance) if np.isfinite(d.clearance) else "", repr(d.stiffness_sum), repr(d.efficiency),
                   repr(d.energy_variation)]
            for sp in d.springs:
                row += [sp.label, sp.pattern, repr(sp.a), repr(sp.b), repr(sp.k)]
            writer.writerow(row + [""] * (len(head) - len(row)))
        return out.getvalue()


def _reason_kind(why: str) -> str:
    return re.sub(r"S\(\d+,\d+\)(\([+-],[+-]\))?|[-+]?\d[\d.e+-]*", "#", why)


def verify(chain: Chain, springs, X) -> float:
    """Route 2: (max - min) of the total energy over the poses X, over the gravity energy's range.
    Raises UnbalanceableError above :data:`VERIFY_TOLERANCE`.

    The poses must move the gravity energy (two or more distinct poses); for an arm whose
    gravity energy cannot vary (its centre of mass on the base joint), the total energy's
    range is compared with m g times the arm's reach instead."""
    E = energies(chain, springs, X)
    spread, gravity = float(np.ptp(E["total"])), float(np.ptp(E["gravity"]))
    scale = chain.g * sum(chain.m) * sum(chain.r)
    if gravity <= 1e-12 * scale:
        if chain.g * max(_gravity_moments(chain)) > 1e-12 * scale:
            raise SpringlabError(f"the {len(E['total'])} workspace pose(s) do not move the arm's gravity energy, "
                                 "so they cannot judge balance: use two or more distinct poses (samples >= 2)")
        gravity = scale
    rel = spread / gravity
    if not rel < VERIFY_TOLERANCE:
        raise UnbalanceableError(f"route 2: the total energy varies by {rel:.2e} of the gravity range "
                                 f"(> {VERIFY_TOLERANCE:g}): not balanced")
    return rel


def _gravity_moments(chain: Chain) -> list[float]:
    """m_j d_j + r_j (masses beyond j), j = 2..n (kg m): the arm's gravity moments, by geometry."""
    return [chain.m[j] * chain.d[j] + chain.r[j] * sum(chain.m[j + 1:]) for j in range(chain.n - 1)]


def evaluate(method: str, chain: Chain, configuration, springs, X, *, link_radii=None) -> RankedDesign:
    """Verify ``springs`` by route 2 and measure them over the poses X: the largest force, the efficiency,
    and the clearance from the links (:func:`springlab.design.clearance.clearance`, links of ``link_radii``
    m, None for the default, the springs as lines)."""

    rel = verify(chain, springs, X)
    force = 0.0
    for s in springs:
        force = max(force, float(s.k * np.max(spring_length(chain, s, X))))
    eff = float(np.mean(spatial_system_efficiency(chain, springs, X)))
    gap = clearance(chain, springs, X, link_radii=link_radii).smallest()
    return RankedDesign(method, tuple(configuration), tuple(springs), force, float(sum(s.k for s in springs)),
                        eff, rel, sum(s.j - s.i for s in springs), float(gap))


def rank_key(d: RankedDesign):
    """The ranking order: a design whose spring passes through a link last; then fewest springs, the
    smallest largest force, the largest clearance, the highest efficiency."""
    _checks.instance("d", d, RankedDesign)
    return (d.crosses, d.spring_count, d.max_force, -d.clearance, -d.efficiency)


def design_arm(arm, *, method: str = "fewest springs", max_designs: int = 10, max_configurations: int | None = None,
               restarts: int = 8, seed: int = 0, progress: bool = False, finder=None,
               minimise_force: bool = True, force_starts: int = 2, time_limit: float | None = None,
               executor=None, batch: int = 8) -> DesignReport:
    """Ranked, verified spring designs for an arm.

    :param arm: an :class:`~springlab.model.armfile.ArmSpec` or the path of an arm file
    :param method: 'fewest springs' (the default: every family below, ranked together; each
        design's ``method`` names its family): the sets of n - 2 springs of any sign pattern that
        the exact sign test and the linear relaxation admit (:data:`ANY_SIGNS`, screened up to
        :data:`SCREEN_BUDGET` candidates), the n - 1 ground springs, then paper 000's
        configurations; or 'no auxiliary links' (paper 000: configurations with necessary springs
        from rules R1-R6, fewest springs and then fewest spanned joints first
        (:func:`~springlab.design.rules.best_first_configurations`); each solved within
        the arm's limits), or 'ground springs' (the n - 1 springs from the base column
        of :func:`ground_springs`, which 000 Eq. 41 forbids: one design)
    :param max_designs: stop after this many verified designs (integer >= 1)
    :param max_configurations: stop after trying this many configurations (None: all)
    :param restarts: random starts of the finder per configuration (integer >= 0)
    :param finder: the solver (default :func:`springlab.design.solve.find_design`); any design it
        returns is verified before it is kept
    :param minimise_force: spend each configuration's free choices on the smallest largest
        spring force (:func:`springlab.design.solve.minimise_largest_force`), within the limits,
        from ``force_starts`` solutions of the finder (the problem has local minima)
    :param time_limit: stop the search after this many seconds (None: no limit); the report's
        ``stopped`` says so
    :param progress: show a progress bar (tqdm) of the search steps, configurations and designs
    :param executor: a concurrent.futures.Executor (a process pool, or a dask cluster's
        ``client.get_executor()``) to solve ``batch`` configurations at a time on; each task
        carries its configuration and seed and the results are read in order, so the report is
        the serial one (None: solve here, one at a time)

    An end link whose centre of mass is on its proximal joint needs no spring
    (:func:`~springlab.design.solve.balanced_core`): the configurations are those of the
    links before it. The report's ``stopped`` says why the search ended, and each rejected
    configuration's reason says whether it is a proof (the linear relaxation) or a search
    that ran out of starts or limits.
    """
    from tqdm import tqdm

    spec = arm if isinstance(arm, ArmSpec) else load_arm(arm)
    method = _checks.choice("method", method, METHODS)
    max_designs = _checks.count("max_designs", max_designs, least=1)
    if max_configurations is not None:
        max_configurations = _checks.count("max_configurations", max_configurations, least=1)
    restarts = _checks.count("restarts", restarts)
    seed = _checks.count("seed", seed)
    force_starts = _checks.count("force_starts", force_starts, least=1)
    time_limit = _checks.optional_positive("time_limit", time_limit, "s")

    executor = check_executor(executor)
    batch = _checks.count("batch", batch, least=1) if executor is not None else 1
    # the default finder stops starting anew once the time is up (a start on a long arm takes seconds)
    finder = finder or functools.partial(find_design, deadline=None if time_limit is None else time.time() + time_limit)
    chain = spec.chain()
    X = workspace_poses(spec, chain)
    report = DesignReport(spec, notes=[workspace_note(spec), *spec.notes])
    t0 = time.perf_counter()
    deadline = None if time_limit is None else t0 + time_limit
    core = balanced_core(chain)
    if core is None:  # the centre of mass is on the base joint: no spring to add
        report.designs.append(evaluate(method, chain, (), (), X, link_radii=spec.link_radii))
        report.stopped = "the arm is balanced without springs (its centre of mass is on the base joint)"
        report.seconds = time.perf_counter() - t0
        return report
    if core is not chain:
        report.notes.append(f"link {chain.n}'s centre of mass is on its proximal joint (d_{chain.n} = 0, "
                            f"G_1,{chain.n} = 0): it needs no spring; the configurations are those of "
                            + (f"links 2..{core.n}" if core.n > 2 else "link 2"))
    bar = tqdm(disable=not progress, desc="search steps", mininterval=1.0)
    # fewest springs first, then fewest spanned joints: best first, without enumerating the rest
    rules = ((method if method != "fewest springs" else "no auxiliary links", cfg)
             for _, _, cfg in best_first_configurations(core.n, deadline=deadline, step=bar.update))
    if method == "ground springs":
        configs = iter([(method, ground_springs(core.n))])
    elif method == "no auxiliary links":
        configs = rules
    else:
        configs = _fewest_first(core, report, rules, executor)
    report.stopped = "every configuration was tried"
    limits = (spec.max_attachment, spec.max_stiffness, spec.link_radii)

    def done() -> bool:  # checked before each configuration is counted, as a serial search would
        if max_configurations is not None and report.configurations_tried >= max_configurations:
            report.stopped = f"max_configurations = {max_configurations} configurations were tried"
        elif len(report.designs) >= max_designs:
            report.stopped = f"max_designs = {max_designs} verified designs were found"
        elif not (deadline is not None and time.perf_counter() > deadline):
            return False
        return True

    while not done():
        todo = []
        for family, cfg in configs:  # the next batch (one configuration when solving here)
            todo.append((family, cfg))
            if len(todo) >= batch:
                break
        if not todo:
            break
        tasks = [(core, chain, family, cfg, X, limits, finder, seed, restarts, minimise_force, force_starts)
                 for family, cfg in todo]
        for (_, cfg), (design, why) in zip(todo, map_ordered(executor, _attempt, tasks), strict=True):
            if done():  # the batch's later results, which a serial search never reached
                break
            report.configurations_tried += 1
            bar.set_postfix(configurations=report.configurations_tried, designs=len(report.designs), refresh=False)
            if design is not None:
                report.designs.append(design)
            else:
                report.rejected.append((cfg, why))
    if deadline is not None and time.perf_counter() > deadline and report.stopped == "every configuration was tried":
        report.stopped = f"the time limit of {time_limit:g} s was reached"
    bar.close()
    report.designs.sort(key=rank_key)
    if spec.com_offsets and report.designs:
        report.notes.append(offset_note(spec, chain, report.designs[0].springs))
    report.seconds = time.perf_counter() - t0
    return report


def workspace_angles(spec: ArmSpec, chain: Chain) -> np.ndarray:
    """Joint angles (N, n-1, 3), rad: the arm file's ``samples`` random poses (seed ``seed``),
    each revolute joint uniform in its range where the file gives one (a spherical joint's cone
    is not applied). Angles, unlike link directions, fix each link's spin about its own line."""
    _checks.instance("spec", spec, ArmSpec, "ArmSpec (load_arm(path))")
    _checks.instance("chain", chain, Chain, "springlab Chain (spec.chain())")
    rng = _checks.rng("seed", spec.seed)
    angles = chain.random_angles(spec.samples, rng)
    for j, lim in enumerate(spec.limits, start=2):
        if isinstance(lim, tuple):
            angles[:, j - 2, 0] = rng.uniform(lim[0], lim[1], spec.samples)
    return angles


def offset_note(spec: ArmSpec, chain: Chain, springs) -> str:
    """What projecting the centres of mass onto the link lines (``spec.com_offsets``) costs a
    design, by route 2: the total energy's variation with the true centres
    (:func:`springlab.energy.geometry.com_offset_energy`) over :func:`workspace_angles`, relative
    to gravity's range."""

    _checks.instance("spec", spec, ArmSpec, "ArmSpec (load_arm(path))")
    _checks.instance("chain", chain, Chain, "springlab Chain (spec.chain())")
    springs = check_springs(chain, springs)
    angles = workspace_angles(spec, chain)
    X = chain.directions(angles)
    gravity = geometry.gravity_energy(chain, X) + geometry.com_offset_energy(chain, spec.com_offsets, angles)
    share = float(np.ptp(gravity + geometry.spring_energy(chain, springs, X)) / np.ptp(gravity))
    return (f"with the true centres of mass (off the lines by up to "
            f"{max(float(np.linalg.norm(o)) for o in spec.com_offsets) * 1e3:.2f} mm), the best design leaves "
            f"the total energy varying by {share:.2%} of gravity's range over {spec.samples} poses (route 2)")



def _attempt(core, chain, family, cfg, X, limits, finder, seed, restarts, minimise_force, force_starts):
    """One configuration of :func:`design_arm`: (RankedDesign, None), or (None, why it was rejected)."""
    max_attachment, max_stiffness, link_radii = limits
    if relaxation_margin(core, cfg) <= 1e-9:
        return None, PROOF + ": 000 Eqs. (39) have no solution with these signs (linear relaxation)"
    try:
        springs = finder(core, cfg, seed=seed, restarts=restarts, max_extension=max_attachment)
        stiff = [s for s in springs if s.k > max_stiffness]
        if stiff:
            raise SearchExhaustedError(f"{stiff[0].label} needs k = {stiff[0].k:.0f} N/m > max_stiffness = "
                                       f"{max_stiffness:.0f} N/m")
        if minimise_force:
            springs = least_force(core, cfg, springs, finder, seed, restarts, force_starts,
                                  max_extension=max_attachment, max_stiffness=max_stiffness)
        return evaluate(family, chain, cfg, springs, X, link_radii=link_radii), None
    except (UnbalanceableError, SearchExhaustedError) as err:
        return None, str(err)


def _fewest_first(core: Chain, report: DesignReport, rules, executor=None):
    """The default search's configurations, (family, configuration), fewest springs first: the
    screened sets of n - 2 springs of any signs, the n - 1 ground springs, then ``rules``
    (paper 000's); a configuration met twice is tried once. Notes what the screen did."""
    import math

    n, count = core.n, core.n - 2
    seen = set()
    if count >= 1:
        slots = all_pattern_slots(n)
        total = 2 * math.comb(len(slots) - 2, count - 1)  # S(1,n) (+,+) or (-,-), and count - 1 others
        if total > SCREEN_BUDGET:
            report.notes.append(f"sets of {count} springs of any signs were not screened ({total:,} candidates, "
                                f"more than {SCREEN_BUDGET:,}): fewer than n - 1 springs were not sought")
        else:
            candidates = any_sign_candidates(n, count)
            verdicts = screen_verdicts(core, candidates, executor=executor)
            passed = [cfg for cfg, v in zip(candidates, verdicts, strict=True) if v == "pass"]
            report.notes.append(f"sets of {count} springs of any signs: {len(candidates):,} candidates, "
                                f"{verdicts.count('signs'):,} refuted by their signs, "
                                f"{verdicts.count('relaxation'):,} by the linear relaxation (proofs); "
                                f"{len(passed)} left to solve")
            for cfg in passed:
                seen.add(tuple(sorted(cfg)))
                yield ANY_SIGNS, tuple(sorted(cfg))
    ground = ground_springs(n)
    if tuple(sorted(ground)) not in seen:
        seen.add(tuple(sorted(ground)))
        yield "ground springs", ground
    for family, cfg in rules:
        if tuple(sorted(cfg)) not in seen:
            seen.add(tuple(sorted(cfg)))
            yield family, cfg


def least_force(chain, cfg, springs, finder, seed, restarts, starts, *, max_extension, max_stiffness):
    """The smallest largest force of ``minimise_largest_force`` from ``springs`` and from
    ``starts - 1`` more solutions of the finder (other seeds)."""
    candidates = [springs]
    for extra in range(1, max(1, int(starts))):
        try:
            candidates.append(finder(chain, cfg, seed=seed + extra, restarts=restarts, max_extension=max_extension))
        except (UnbalanceableError, SearchExhaustedError):
            continue
    best, best_force = springs, np.inf
    for start in candidates:
        if max_stiffness is not None and any(s.k > max_stiffness for s in start):
            continue
        out = minimise_largest_force(chain, cfg, start, max_extension=max_extension, max_stiffness=max_stiffness)
        force = largest_force_bound(chain, out)
        if force < best_force:
            best, best_force = out, force
    return best


def configuration_of(springs) -> tuple[SpringSlot, ...]:
    """The configuration (slots with patterns) of a list of springs."""
    if isinstance(springs, str) or not hasattr(springs, "__iter__"):
        raise SpringlabError(f"springs must be a sequence of Spring objects, got {springs!r}")
    springs = [_checks.instance("each of springs", s, Spring) for s in springs]
    return tuple(sorted(as_slots([f"{s.label}{s.pattern}" for s in springs])))


def springs_from_dict(items) -> list[Spring]:
    """Springs from :meth:`RankedDesign.to_dict`'s 'springs' list."""
    return [Spring(int(d["i"]), int(d["j"]), float(d["a_m"]), float(d["b_m"]), float(d["k_N_per_m"])) for d in items]


def ground_springs(n: int) -> tuple[SpringSlot, ...]:
    """n - 1 springs, all anchored on the base column (x_1, above the base joint):
    S(1,n) (+,+) and S(1,j) (+,-) for j = 3..n. Balances an arm of any n (see
    :func:`springlab.design.ground.ground_spring_design`). 000 Eq. (41) allows only (+,+) on the ground."""
    n = _checks.links(n)
    return tuple(sorted([SpringSlot(1, n, "(+,+)")] + [SpringSlot(1, j, "(+,-)") for j in range(3, n + 1)]))


def springs_table(chain: Chain, springs, X) -> Table:
    """A design's springs: pattern, a, b (m), k (N/m) and the largest force (N) over the poses X."""
    springs = check_springs(chain, springs)
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    rows = []
    for s in springs:
        force = s.k * np.max(spring_length(chain, s, X))
        rows.append((s.label, s.pattern, f"{s.a:.4f}", f"{s.b:.4f}", f"{s.k:.1f}", f"{force:.1f}"))
    return Table(["spring", "pattern", "a (m)", "b (m)", "k (N/m)", "largest force (N)"], rows)


def rank_of(report: DesignReport, configuration) -> int | None:
    """The 1-based rank of ``configuration`` in the report, None if it is not listed."""
    configuration = tuple(sorted(configuration))
    return next((k + 1 for k, d in enumerate(report.designs) if d.configuration == configuration), None)
