"""Springs for your own arm: ranked, verified designs (paper 000's method, any n).

:func:`design_arm` takes an :class:`~springlab.model.armfile.ArmSpec` (or an arm file)
and returns designs ranked by spring count, then the largest spring force over
the arm's workspace, then the system spring efficiency. Each is verified by route
2 (the total energy over the workspace samples varies by less than 1e-10 of the
gravity energy's range) *before* it is returned; one that fails is dropped, with
the reason kept in the report.

Spatial system spring efficiency
--------------------------------
Paper 003 defines e_sys = (X + Y) / (X + 2Y) (003 Eq. 25) for planar arms. Paper 000's
quadratic form gives the same pieces in space: the energy's pose-dependent part
is sum_{u<v} M_uv x_u . x_v, each spring S contributing entries K^S_uv (000 Eqs.
23a-d) and gravity G_1v. Divided by r_u r_v (r_1 = 1 m, as 003 sets it), an entry
times x_u . x_v is a pseudo-stiffness. Gravity's are positive (x_1 is up), so a
spring term *balances* when its entry is negative and *is balanced* when positive;
with the attachment patterns (+,+) on the ground, (+,+) and (-,-) elsewhere this
is exactly 003's C1/C2 classification. Then, at each pose,

    X = sum_v |G_1v x_1 . x_v| / r_v,   Y = sum_{S, u<v, K^S_uv > 0} |K^S_uv x_u . x_v| / (r_u r_v)

and e_sys = (X + Y)/(X + 2Y): 003 Eq. (25), 'magnitudes' reading. For a planar
motion x_u . x_v = cos Theta_uv and it reduces to 003's (tested against
:func:`springlab.mechanisms.planar.efficiency.system_efficiency`).

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from springlab.design.rules import SpringSlot, as_slots, best_first_configurations
from springlab.design.solve import (
    find_design,
    largest_force_bound,
    minimise_largest_force,
    relaxation_margin,
)
from springlab.energy.geometry import attachment_points, energies
from springlab.energy.quadratic import gravity_entries, spring_entries
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.model.armfile import ArmSpec, load_arm
from springlab.model.chain import Chain
from springlab.model.springs import Spring
from springlab.tables import Table

METHODS = ("no auxiliary links", "ground springs")
VERIFY_TOLERANCE = 1e-10


def spatial_system_efficiency(chain: Chain, springs, X) -> np.ndarray:
    """e_sys (003 Eq. 25, generalised; module docstring) at each pose X (N, n, 3), (N,)."""
    X = chain.check_directions(X)
    r = {1: 1.0} | {t: chain.r[t - 2] for t in range(2, chain.n + 1)}
    dots = np.einsum("nuk,nvk->nuv", X, X)
    Xs = np.zeros(len(X))
    for (u, v), value in gravity_entries(chain.r, chain.d, chain.m, chain.g).items():
        Xs += np.abs(value * dots[:, u - 1, v - 1]) / (r[u] * r[v])
    Ys = np.zeros(len(X))
    for s in springs:
        for (u, v), value in spring_entries(s.i, s.j, s.a, s.b, s.k, chain.r).items():
            if u < v and value > 0:
                Ys += np.abs(value * dots[:, u - 1, v - 1]) / (r[u] * r[v])
    return (Xs + Ys) / (Xs + 2 * Ys)


def random_poses(chain: Chain, samples: int, seed) -> np.ndarray:
    """``samples`` seeded link-direction sets (N, n, 3): uniform directions for a spherical
    chain, uniform joint angles for one with revolute joints."""
    rng = np.random.default_rng(seed)
    if chain.all_spherical:
        from springlab.model.chain import random_directions

        return random_directions(chain.n, samples, rng)
    return chain.directions(chain.random_angles(samples, rng))


def workspace_poses(spec: ArmSpec, chain: Chain) -> np.ndarray:
    """The poses that judge a design: the arm file's ``samples`` and ``seed``."""
    return random_poses(chain, spec.samples, spec.seed)


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

    @property
    def spring_count(self) -> int:
        return len(self.springs)

    def label(self) -> str:
        return " ".join(f"{s.label}{s.pattern}" for s in self.springs)

    def to_dict(self) -> dict:
        return {"method": self.method, "configuration": [str(c) for c in self.configuration],
                "springs": [{"i": s.i, "j": s.j, "pattern": s.pattern, "a_m": s.a, "b_m": s.b, "k_N_per_m": s.k}
                            for s in self.springs],
                "max_force_N": self.max_force, "stiffness_sum_N_per_m": self.stiffness_sum,
                "efficiency": self.efficiency, "energy_variation": self.energy_variation}


@dataclass
class DesignReport:
    """The ranked designs and what was tried: ``rejected`` lists (configuration, reason)."""

    spec: ArmSpec
    designs: list = field(default_factory=list)
    rejected: list = field(default_factory=list)
    configurations_tried: int = 0
    seconds: float = 0.0

    def table(self) -> Table:
        """The ranked designs as a table (shown as Markdown in a notebook)."""
        return Table(["rank", "springs", "configuration", "max force (N)", "sum of k (N/m)", "efficiency",
                      "energy variation"],
                     [(rank, d.spring_count, d.label(), f"{d.max_force:.1f}", f"{d.stiffness_sum:.0f}",
                       f"{d.efficiency:.4f}", f"{d.energy_variation:.1e}")
                      for rank, d in enumerate(self.designs, start=1)])


def verify(chain: Chain, springs, X) -> float:
    """Route 2: (max - min) of the total energy over the poses X, over the gravity energy's range.
    Raises UnbalanceableError above :data:`VERIFY_TOLERANCE`."""
    E = energies(chain, springs, X)
    rel = float(np.ptp(E["total"]) / np.ptp(E["gravity"]))
    if not rel < VERIFY_TOLERANCE:
        raise UnbalanceableError(f"route 2: the total energy varies by {rel:.2e} of the gravity range "
                                 f"(> {VERIFY_TOLERANCE:g}): not balanced")
    return rel


def evaluate(method: str, chain: Chain, configuration, springs, X) -> RankedDesign:
    """Verify ``springs`` by route 2 and measure them over the poses X."""
    rel = verify(chain, springs, X)
    force = 0.0
    for s in springs:
        A, B = attachment_points(chain, s, X)
        force = max(force, float(s.k * np.max(np.linalg.norm(B - A, axis=1))))
    eff = float(np.mean(spatial_system_efficiency(chain, springs, X)))
    return RankedDesign(method, tuple(configuration), tuple(springs), force, float(sum(s.k for s in springs)),
                        eff, rel, sum(s.j - s.i for s in springs))


def _rank_key(d: RankedDesign):
    return (d.spring_count, d.max_force, -d.efficiency)


def design_arm(arm, *, method: str = "no auxiliary links", max_designs: int = 10, max_configurations: int | None = None,
               restarts: int = 8, seed: int = 0, progress: bool = False, finder=None,
               minimise_force: bool = True, force_starts: int = 2) -> DesignReport:
    """Ranked, verified spring designs for an arm.

    :param arm: an :class:`~springlab.model.armfile.ArmSpec` or the path of an arm file
    :param method: 'no auxiliary links' (paper 000: configurations with necessary springs
        from rules R1-R6, fewest springs and then fewest spanned joints first
        (:func:`~springlab.design.rules.best_first_configurations`); each solved within
        the arm's limits), or 'ground springs' (the n - 1 springs from the base column
        of :func:`ground_springs`, which 000's 000 Eq. 41 forbids: one design)
    :param max_designs: stop after this many verified designs
    :param max_configurations: stop after trying this many configurations (None: all)
    :param finder: the solver (default :func:`springlab.design.solve.find_design`); any design it
        returns is verified before it is kept
    :param minimise_force: spend each configuration's free choices on the smallest largest
        spring force (:func:`springlab.design.solve.minimise_largest_force`), within the limits,
        from ``force_starts`` solutions of the finder (the problem has local minima)
    """
    from tqdm import tqdm

    spec = arm if isinstance(arm, ArmSpec) else load_arm(arm)
    if method not in METHODS:
        raise SpringlabError(f"method must be one of {METHODS}, got {method!r}")
    finder = finder or find_design
    chain = spec.chain()
    X = workspace_poses(spec, chain)
    report = DesignReport(spec)
    t0 = time.perf_counter()
    # fewest springs first, then fewest spanned joints: best first, without enumerating the rest
    if method == "ground springs":
        configs = iter([ground_springs(chain.n)])
    else:
        configs = (cfg for _, _, cfg in best_first_configurations(chain.n))
    for cfg in tqdm(configs, disable=not progress, desc="configurations", mininterval=1.0):
        if max_configurations is not None and report.configurations_tried >= max_configurations:
            break
        if len(report.designs) >= max_designs:
            break
        report.configurations_tried += 1
        if relaxation_margin(chain, cfg) <= 1e-9:
            report.rejected.append((cfg, "000 Eqs. (39) have no solution with these signs (linear relaxation)"))
            continue
        try:
            springs = finder(chain, cfg, seed=seed, restarts=restarts, max_extension=spec.max_attachment)
            stiff = [s for s in springs if s.k > spec.max_stiffness]
            if stiff:
                raise UnbalanceableError(f"{stiff[0].label} needs k = {stiff[0].k:.0f} N/m > {spec.max_stiffness:.0f} N/m")
            if minimise_force:
                springs = _least_force(chain, cfg, springs, finder, seed, restarts, force_starts,
                                       max_extension=spec.max_attachment, max_stiffness=spec.max_stiffness)
            report.designs.append(evaluate(method, chain, cfg, springs, X))
        except (UnbalanceableError, SpringlabError) as err:
            report.rejected.append((cfg, str(err)))
    report.designs.sort(key=_rank_key)
    report.seconds = time.perf_counter() - t0
    return report


def _least_force(chain, cfg, springs, finder, seed, restarts, starts, *, max_extension, max_stiffness):
    """The smallest largest force of ``minimise_largest_force`` from ``springs`` and from
    ``starts - 1`` more solutions of the finder (other seeds)."""
    candidates = [springs]
    for extra in range(1, max(1, int(starts))):
        try:
            candidates.append(finder(chain, cfg, seed=seed + extra, restarts=restarts, max_extension=max_extension))
        except (UnbalanceableError, SpringlabError):
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
    return tuple(sorted(as_slots([f"{s.label}{s.pattern}" for s in springs])))


def springs_from_dict(items) -> list[Spring]:
    """Springs from :meth:`RankedDesign.to_dict`'s 'springs' list."""
    return [Spring(int(d["i"]), int(d["j"]), float(d["a_m"]), float(d["b_m"]), float(d["k_N_per_m"])) for d in items]


def all_pattern_slots(n: int) -> list[SpringSlot]:
    """Every spring S(i,j) of an n-link arm with every sign pattern, the paper's
    criteria (000 Eq. 41, Fig. 10) ignored."""
    from springlab.design.rules import PATTERNS

    return [SpringSlot(i, j, p) for i in range(1, n) for j in range(i + 1, n + 1) for p in PATTERNS]


def _any_sign_candidates(n: int, count: int) -> list[tuple[SpringSlot, ...]]:
    """Every set of ``count`` slots, any sign pattern, that includes a same-sign S(1,n) (the
    only spring with an entry (1, n), which gravity's G_1n > 0 needs: -k a b < 0)."""
    import itertools

    if int(count) != count or count < 1:
        raise SpringlabError(f"count must be an integer >= 1, got {count}")
    slots = all_pattern_slots(n)
    end = [s for s in slots if (s.i, s.j) == (1, n) and s.pattern in ("(+,+)", "(-,-)")]
    rest = [s for s in slots if s not in end]
    return [(e, *others) for e in end for others in itertools.combinations(rest, count - 1)]


def fewer_springs(spec_or_chain, count: int, *, max_extension: float | None = None, restarts: int = 20,
                  seed: int = 0, samples: int = 2000, progress: bool = False,
                  minimise_force: bool = True) -> list[RankedDesign]:
    """Verified designs with ``count`` springs of any sign pattern (000's criteria treated
    as the heuristics they are), ranked like :func:`design_arm`.

    Every set of ``count`` slots that includes S(1,n) (the only spring with an entry
    (1, n), which gravity's G_1n needs; (+,+) or (-,-)) is screened by the linear
    relaxation of 000 Eqs. (39) (:func:`springlab.design.solve.relaxation_margin`), then solved
    by least squares (free choices spent on the smallest largest force if
    ``minimise_force``) and verified by route 2 over ``samples`` random poses. The
    candidates number about C(2 n (n - 1), count - 1): practical to n = 5.
    """
    from tqdm import tqdm

    chain = spec_or_chain.chain() if isinstance(spec_or_chain, ArmSpec) else spec_or_chain
    X = random_poses(chain, samples, seed)
    out = []
    candidates = _any_sign_candidates(chain.n, count)
    for cfg in tqdm(candidates, disable=not progress, desc=f"{count} springs, all patterns", mininterval=1.0):
        if relaxation_margin(chain, cfg) <= 1e-9:
            continue
        try:
            springs = find_design(chain, cfg, seed=seed, restarts=restarts, max_extension=max_extension)
            if minimise_force:
                springs = minimise_largest_force(chain, cfg, springs, max_extension=max_extension)
            out.append(evaluate("no auxiliary links, any signs", chain, tuple(sorted(cfg)), springs, X))
        except (UnbalanceableError, SpringlabError):
            continue
    return sorted(out, key=_rank_key)


def relaxation_screen(spec_or_chain, count: int, *, progress: bool = False) -> tuple[int, int]:
    """(candidates, survivors): how many sets of ``count`` springs, any sign pattern, any
    attachment (limits ignored), pass the linear relaxation of 000 Eqs. (39). No survivor
    proves that no ``count`` springs without auxiliary links balance this arm: the
    relaxation only drops constraints (P k = A B per spring)."""
    from tqdm import tqdm

    chain = spec_or_chain.chain() if isinstance(spec_or_chain, ArmSpec) else spec_or_chain
    candidates = _any_sign_candidates(chain.n, count)
    survivors = sum(1 for cfg in tqdm(candidates, disable=not progress, desc=f"{count} springs, screen", mininterval=1.0)
                    if relaxation_margin(chain, cfg) > 1e-9)
    return len(candidates), survivors


def ground_springs(n: int) -> tuple[SpringSlot, ...]:
    """n - 1 springs, all anchored on the base column (x_1, above the base joint):
    S(1,n) (+,+) and S(1,j) (+,-) for j = 3..n. Balances an arm of any n (see
    :func:`ground_spring_design`). 000 Eq. (41) of 000 allows only (+,+) on the ground."""
    if int(n) != n or n < 3:
        raise SpringlabError(f"n (links with the ground) must be an integer >= 3, got {n}")
    return tuple(sorted([SpringSlot(1, n, "(+,+)")] + [SpringSlot(1, j, "(+,-)") for j in range(3, n + 1)]))


def ground_spring_design(spec_or_chain, *, max_extension: float | None = None, max_stiffness: float | None = None,
                         samples: int = 2000, seed: int = 0, restarts: int = 30) -> RankedDesign:
    """The n - 1 ground springs of :func:`ground_springs`, solved, with the free choices
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
    chain = spec_or_chain.chain() if isinstance(spec_or_chain, ArmSpec) else spec_or_chain
    if isinstance(spec_or_chain, ArmSpec):
        max_extension = spec_or_chain.max_attachment if max_extension is None else max_extension
        max_stiffness = spec_or_chain.max_stiffness if max_stiffness is None else max_stiffness
    cfg = ground_springs(chain.n)
    springs = find_design(chain, cfg, seed=seed, restarts=restarts, max_extension=max_extension,
                          max_stiffness=max_stiffness)
    springs = _least_force(chain, cfg, springs, find_design, seed, restarts, 2, max_extension=max_extension,
                           max_stiffness=max_stiffness)
    return evaluate("ground springs", chain, cfg, springs, random_poses(chain, samples, seed))


# --- other methods, for comparison ------------------------------------------------------------
@dataclass(frozen=True)
class MethodSummary:
    """One method's best design for an arm, in the comparison's terms (N, N/m, kg)."""

    method: str
    springs: int
    stiffness_sum: float
    max_force: float
    added_mass: float
    efficiency: float
    energy_variation: float
    note: str = ""


def pseudobase_summary(spec: ArmSpec, *, aux_mass_ratio: float = 0.09, pseudobase_mass: float = 0.47,
                       post: float = 0.1) -> MethodSummary:
    """Paper 001's method on this arm, idealised: one spring per moving link i, from a point
    l_CA above its proximal joint on a pseudobase kept vertical (by RSSR parallelograms and an
    auxiliary link beside link i) to a point l_CB along link i, K_i l_CA l_CB = g mu~_i sigma~_i
    (001 Eq. 16). Both lengths are the arm's ``max_attachment`` (B within the link), the
    stiffness the least that balances.

    The auxiliary links (``aux_mass_ratio`` of each link's mass, 001's Table 2 has 9 %, each with
    its centre of mass beside link i's: a translated copy) and
    pseudobases (``pseudobase_mass`` kg each, at the joint, ``post`` m tall) add mass; their
    energy is folded into the combined subsystems (001 Eqs. 24-25). Verified by route 2: every
    body and spring end placed for each workspace pose.
    """
    from springlab.model.chain import UP

    chain = spec.chain()
    if not (0 <= aux_mass_ratio and pseudobase_mass >= 0 and post > 0):
        raise SpringlabError("aux_mass_ratio and pseudobase_mass must be >= 0 and post > 0")
    m = np.asarray(chain.m)
    m_hat = aux_mass_ratio * m
    total = m + m_hat + pseudobase_mass
    beyond = np.r_[np.cumsum(total[::-1])[::-1][1:], 0.0]
    moment = (m + m_hat) * np.asarray(chain.d) + beyond * np.asarray(chain.r)  # mu~ sigma~ along x_i (kg m)
    reach = spec.max_attachment if spec.max_attachment is not None else max(chain.r)
    l_CA = np.full(len(m), reach)
    l_CB = np.minimum(reach, np.asarray(chain.r))
    K = chain.g * moment / (l_CA * l_CB)  # 001 Eq. (16)
    X = workspace_poses(spec, chain)
    joints = chain.joint_positions(X)
    com = chain.com_positions(X)
    heights = com @ UP
    gravity = chain.g * (heights @ (m + m_hat)) + chain.g * ((joints[:, :-1] @ UP) @ np.full(len(m), pseudobase_mass))
    elastic = np.zeros(len(X))
    force = 0.0
    for idx in range(len(m)):
        A = joints[:, idx] + l_CA[idx] * UP  # on the pseudobase, above the proximal joint
        B = joints[:, idx] + l_CB[idx] * X[:, idx + 1]  # along link idx + 2
        stretch = np.linalg.norm(B - A, axis=1)
        elastic += 0.5 * K[idx] * stretch**2
        force = max(force, float(K[idx] * stretch.max()))
    rel = float(np.ptp(gravity + elastic) / np.ptp(gravity))
    if not rel < VERIFY_TOLERANCE:
        raise UnbalanceableError(f"pseudobase design: route 2 variation {rel:.2e} of the gravity range")
    note = "" if K.max() <= spec.max_stiffness else f"exceeds max_stiffness ({K.max():.0f} N/m)"
    added = float(m_hat.sum() + pseudobase_mass * len(m))
    return MethodSummary("pseudobases (001), idealised", len(m), float(K.sum()), force, added, 1.0, rel, note)


def compare_methods(spec: ArmSpec, report: DesignReport | None = None, **pseudobase_options) -> list[MethodSummary]:
    """The best design of each method that applies to the arm: 000's (no auxiliary links, the
    top of ``report``), the n - 1 ground springs (:func:`ground_spring_design`), 001's
    pseudobases (idealised), and 004's two springs where the arm has
    two moving links (n = 3), which are 000's configurations S(1,3) + S(2,3) (Lenzo's layouts
    a and b; c and d need a COM off the link)."""
    report = report or design_arm(spec, max_designs=5)
    out = []
    if report.designs:
        d = report.designs[0]
        out.append(MethodSummary("no auxiliary links (000)", d.spring_count, d.stiffness_sum, d.max_force, 0.0,
                                 d.efficiency, d.energy_variation))
    try:
        d = ground_spring_design(spec, samples=spec.samples, seed=spec.seed)
        out.append(MethodSummary("ground springs, n - 1 (any signs)", d.spring_count, d.stiffness_sum, d.max_force, 0.0,
                                 d.efficiency, d.energy_variation, "000 Eq. (41) forbids the (+,-) ground springs"))
    except (UnbalanceableError, SpringlabError) as err:
        out.append(MethodSummary("ground springs, n - 1 (any signs)", spec.n - 1, float("nan"), float("nan"), 0.0,
                                 float("nan"), float("nan"), f"none within the limits: {err}"[:120]))
    out.append(pseudobase_summary(spec, **pseudobase_options))
    if spec.n == 3:  # Lenzo's two springs are 000's S(1,3) + S(2,3): layouts b (+,+) and a (-,-)
        two = [d for d in report.designs if [(s.i, s.j) for s in d.springs] == [(1, 3), (2, 3)]]
        if two:
            d = two[0]
            layout = "b" if d.springs[1].pattern == "(+,+)" else "a"
            out.append(MethodSummary("two springs (004)", 2, d.stiffness_sum, d.max_force, 0.0, d.efficiency,
                                     d.energy_variation, f"Lenzo's layout {layout}: 000's {d.label()}"))
    return out


def comparison_table(rows) -> Table:
    """:class:`MethodSummary` rows as a table (shown as Markdown in a notebook)."""
    return Table(["method", "springs", "sum of k (N/m)", "largest spring force (N)", "added mass (kg)",
                  "efficiency", "energy variation", "note"],
                 [(r.method, r.springs, f"{r.stiffness_sum:.0f}", f"{r.max_force:.1f}", f"{r.added_mass:.2f}",
                   f"{r.efficiency:.3f}", f"{r.energy_variation:.1e}", r.note) for r in rows])


def springs_table(chain: Chain, springs, X) -> Table:
    """A design's springs: pattern, a, b (m), k (N/m) and the largest force (N) over the poses X."""
    rows = []
    for s in springs:
        A, B = attachment_points(chain, s, X)
        force = s.k * np.max(np.linalg.norm(B - A, axis=1))
        rows.append((s.label, s.pattern, f"{s.a:.4f}", f"{s.b:.4f}", f"{s.k:.1f}", f"{force:.1f}"))
    return Table(["spring", "pattern", "a (m)", "b (m)", "k (N/m)", "largest force (N)"], rows)


FAMILY_LENGTHS = (0.30, 0.24, 0.20, 0.15, 0.12, 0.10, 0.08)  # m, links 2..8
FAMILY_MASSES = (4.0, 3.2, 2.8, 1.5, 1.2, 1.0, 0.8)  # kg


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
    """For each arm of ``family`` ({n: ArmSpec}): the rules' best design (:func:`design_arm`),
    the ground-spring design checked in exudyn (two poses, 2 s), and for n <= ``screen_up_to``
    the relaxation screen of every n - 2 spring set (:func:`relaxation_screen`)."""
    from springlab.energy.simulation import hold_test
    from springlab.model.chain import random_directions

    out = []
    for n, spec_n in family.items():
        arm_n = spec_n.chain()
        necessary = next(best_first_configurations(n))[0]
        rules = design_arm(spec_n, max_designs=3, max_configurations=12)
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


def rank_of(report: DesignReport, configuration) -> int | None:
    """The 1-based rank of ``configuration`` in the report, None if it is not listed."""
    configuration = tuple(sorted(configuration))
    return next((k + 1 for k, d in enumerate(report.designs) if d.configuration == configuration), None)
