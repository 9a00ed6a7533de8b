"""Fewer springs than paper 000's rules allow: any sign pattern, screened by the linear
relaxation of 000 Eqs. (39) (:func:`relaxation_screen`, a proof where it fails), solved and
verified by route 2 (:func:`fewer_springs`); the n - 1 springs from the base column
(:func:`ground_spring_design`), which 000 Eq. (41) forbids; and what each n needs
(:func:`springlab.design.ground.springs_per_n`).

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
from springlab.design.rank import (
    ANY_SIGNS,
    RankedDesign,
    design_arm,
    evaluate,
    ground_springs,
    least_force,
    random_poses,
    rank_key,
)
from springlab.design.rules import best_first_configurations
from springlab.design.screen import any_sign_candidates, screen
from springlab.design.solve import (
    find_design,
    minimise_largest_force,
)
from springlab.energy.simulation import hold_test
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.executors import check_executor, map_ordered
from springlab.model.armfile import ArmSpec
from springlab.model.chain import Chain, random_directions
from springlab.tables import Table


def _chain_of(spec_or_chain) -> Chain:
    _checks.instance("spec_or_chain", spec_or_chain, ArmSpec | Chain, "ArmSpec or Chain")
    return spec_or_chain.chain() if isinstance(spec_or_chain, ArmSpec) else spec_or_chain


def fewer_springs(spec_or_chain, count: int, *, max_extension: float | None = None, restarts: int = 20,
                  seed: int = 0, samples: int = 2000, progress: bool = False,
                  minimise_force: bool = True, executor=None) -> list[RankedDesign]:
    """Verified designs with ``count`` springs of any sign pattern (000's criteria treated
    as the heuristics they are), ranked like :func:`springlab.design.rank.design_arm`.

    Every set of ``count`` slots that includes S(1,n) (the only spring with an entry
    (1, n), which gravity's G_1n needs; (+,+) or (-,-)) is screened (:func:`springlab.design.screen.screen`: the
    exact sign test, then the linear relaxation of 000 Eqs. (39)), then solved
    by least squares (free choices spent on the smallest largest force if
    ``minimise_force``) and verified by route 2 over ``samples`` random poses. The
    candidates number about C(2 n (n - 1), count - 1): practical to n = 5. ``executor``
    (a concurrent.futures.Executor) runs the screen and the solves as tasks; the result is
    the serial one.
    """
    from tqdm import tqdm

    chain = _chain_of(spec_or_chain)
    executor = check_executor(executor)
    X = random_poses(chain, samples, seed)
    candidates = any_sign_candidates(chain.n, count)
    passed = [cfg for cfg, ok in zip(candidates, screen(chain, candidates, executor=executor), strict=True) if ok]
    tasks = [(chain, cfg, X, max_extension, seed, restarts, minimise_force)
             for cfg in tqdm(passed, disable=not progress, desc=f"{count} springs, all patterns", mininterval=1.0)]
    return sorted((d for d in map_ordered(executor, _solve_any_signs, tasks) if d is not None), key=rank_key)


def _solve_any_signs(chain, cfg, X, max_extension, seed, restarts, minimise_force):
    """One configuration of :func:`fewer_springs`: its verified design, or None."""
    try:
        springs = find_design(chain, cfg, seed=seed, restarts=restarts, max_extension=max_extension)
        if minimise_force:
            springs = minimise_largest_force(chain, cfg, springs, max_extension=max_extension)
        return evaluate(ANY_SIGNS, chain, tuple(sorted(cfg)), springs, X)
    except (UnbalanceableError, SpringlabError):
        return None


def relaxation_screen(spec_or_chain, count: int, *, progress: bool = False, executor=None) -> tuple[int, int]:
    """(candidates, survivors): how many sets of ``count`` springs, any sign pattern, any
    attachment (limits ignored), pass the linear relaxation of 000 Eqs. (39). No survivor
    proves that no ``count`` springs without auxiliary links balance this arm: the
    relaxation only drops constraints (P k = A B per spring). Candidates the signs alone
    refute (:func:`springlab.design.solve.sign_consistent`, exact) get no linear programme:
    at n = 6 that is all 61,712 sets of four springs, screened in 0.2 s (97 s by programmes).
    ``executor``: as :func:`springlab.design.screen.screen`'s."""
    chain = _chain_of(spec_or_chain)
    candidates = any_sign_candidates(chain.n, count)
    return len(candidates), sum(screen(chain, candidates, executor=executor, progress=progress,
                                       desc=f"{count} springs, screen"))


def ground_spring_design(spec_or_chain, *, max_extension: float | None = None, max_stiffness: float | None = None,
                         samples: int = 2000, seed: int = 0, restarts: int = 30) -> RankedDesign:
    """The n - 1 ground springs of :func:`springlab.design.rank.ground_springs`, solved, with the free choices
    spent on the smallest largest force, and verified by route 2.

    Why n - 1 springs suffice. Spring S(1,j) with A = k a, B = k b puts k r_t r_v on every
    entry (t, v) between joints it spans (2 <= t < v < j, 000 Eq. 23c) and r_t B on (t, j)
    (000 Eq. 23d). Entry (t, v) of 000 Eqs. (39) therefore reads r_t (B_v + r_v K_v) = 0, with
    B_v the sum of B over springs ending on link v and K_v the stiffness of those reaching
    past it: one condition per link v, the same for every t. A (+,-) spring ending on v
    (B_v < 0) meets it, and S(1,n)'s pair meets it at v = n. The ground entries (1, v)
    then read r_v (W_v - a_v K_v) = G_1v for 3 <= v < n, with W_v the sum of k a over the
    springs reaching past v; r_2 W_2 = G_12; and k' b' (a' - a_n) = G_1n at v = n (' for
    the (+,+) spring): triangular in the anchor heights a_v, solved link by link from the
    tip. So n - 1 springs, where rules R1-R6 need 4 at n = 4 and 10 at n = 8.

    :param max_extension: longest bracket (m): the anchor heights up the base column and
        the extensions behind the joints (default the longest link)
    :param max_stiffness: largest k (N/m), or None
    """
    chain = _chain_of(spec_or_chain)
    if isinstance(spec_or_chain, ArmSpec):
        max_extension = spec_or_chain.max_attachment if max_extension is None else max_extension
        max_stiffness = spec_or_chain.max_stiffness if max_stiffness is None else max_stiffness
    cfg = ground_springs(chain.n)
    springs = find_design(chain, cfg, seed=seed, restarts=restarts, max_extension=max_extension,
                          max_stiffness=max_stiffness)
    springs = least_force(chain, cfg, springs, find_design, seed, restarts, 2, max_extension=max_extension,
                           max_stiffness=max_stiffness)
    return evaluate("ground springs", chain, cfg, springs, random_poses(chain, samples, seed))


FAMILY_LENGTHS = (0.30, 0.24, 0.20, 0.15, 0.12, 0.10, 0.08)  # m, links 2..8
"""The example family's link lengths (m), links 2..8: a shoulder-to-wrist arm shrinking outwards."""


FAMILY_MASSES = (4.0, 3.2, 2.8, 1.5, 1.2, 1.0, 0.8)  # kg
"""The example family's link masses (kg), links 2..8."""


def example_family(ns, *, max_attachment: float = 0.3, samples: int = 1000) -> dict[int, ArmSpec]:
    """Arms of n = 3, 4, ... links (spherical joints, COMs at mid-link, g = 9.8 m/s^2): the first
    n - 1 of :data:`FAMILY_LENGTHS` (m) and :data:`FAMILY_MASSES` (kg), brackets up to
    ``max_attachment`` (m), ``samples`` workspace poses seeded by n."""
    return {n: ArmSpec(f"n = {n}", tuple(FAMILY_LENGTHS[:n - 1]), tuple(x / 2 for x in FAMILY_LENGTHS[:n - 1]),
                       tuple(FAMILY_MASSES[:n - 1]), ("spherical",) * (n - 1), 9.8, max_attachment=max_attachment,
                       samples=samples, seed=n) for n in ns}


@dataclass(frozen=True)
class SpringsPerN:
    """What one arm of :func:`example_family` needs: the rules' fewest springs and their best
    design, the n - 1 ground springs (largest force in N, route-2 energy variation, exudyn
    tip drift balanced and with the springs x 0.9, m), and the n - 2 relaxation screen
    (sets tried, sets passing; None when not screened)."""

    n: int
    rules: RankedDesign
    necessary: int
    ground: RankedDesign
    hold_drift: float
    control_drift: float
    screen: tuple | None

    @property
    def ratio(self) -> float:
        """The ground springs' largest force over the rules' best design's."""
        return self.ground.max_force / self.rules.max_force


def springs_per_n(family: dict, *, screen_up_to: int) -> list[SpringsPerN]:
    """For each arm of ``family`` ({n: ArmSpec}): the rules' best design (:func:`springlab.design.rank.design_arm`),
    the ground-spring design checked in exudyn (two poses, 2 s), and for n <= ``screen_up_to``
    the relaxation screen of every n - 2 spring set (:func:`relaxation_screen`)."""
    out = []
    for n, spec_n in family.items():
        arm_n = spec_n.chain()
        necessary = next(best_first_configurations(n))[0]
        rules = design_arm(spec_n, method="no auxiliary links", max_designs=3, max_configurations=12)
        ground = ground_spring_design(spec_n, samples=1000, seed=n)
        hold = hold_test(arm_n, list(ground.springs), random_directions(n, 2, np.random.default_rng(n)), duration=2.0)
        screen = relaxation_screen(arm_n, n - 2) if n <= screen_up_to else None
        out.append(SpringsPerN(n, rules.designs[0], necessary, ground, hold.balanced.max_tip_drift,
                               hold.control.max_tip_drift, screen))
    return out


def springs_per_n_table(rows: list[SpringsPerN]) -> Table:
    return Table(["n", "rules' fewest springs", "their best: largest force (N)", "ground springs",
                  "their largest force (N) (ratio)", "route 2 variation", "exudyn drift / control (m)", "n - 2 springs"],
                 [(r.n, r.necessary, f"{r.rules.max_force:.0f}", r.ground.spring_count,
                   f"{r.ground.max_force:.0f} ({r.ratio:.2f})", f"{r.ground.energy_variation:.0e}",
                   f"{r.hold_drift:.0e} / {r.control_drift:.2f}",
                   f"{r.screen[0]:,} sets, {r.screen[1]} pass: impossible" if r.screen else "not screened") for r in rows])


def designs_table(designs) -> Table:
    """Designs found by :func:`fewer_springs`, best first: their springs, largest force (N), sum of k
    (N/m) and route 2's energy variation (relative to gravity's range)."""
    return Table(["rank", "springs", "largest force (N)", "sum of k (N/m)", "route 2 variation"],
                 [(k, d.label(), f"{d.max_force:.0f}", f"{d.stiffness_sum:.0f}", f"{d.energy_variation:.0e}")
                  for k, d in enumerate(designs, start=1)])
