"""Synthesis of paper 002's dyad: the readings of 002 Eq. (32) that choose the energy
constant C, the searches over positions and readings, and the minimax optimum.
It compares route 1's printed moments with route 2's virtual-work moment.

References
----------
Zhang, Y., Arakelian, V. (2023). Design and Synthesis of the Gravity Compensator with a
Non-zero Length Spring (no DOI printed in the text).
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab.errors import SearchExhaustedError, SpringlabError
from springlab.mechanisms.dyad.algebra import (
    slider_positions,
    synthesise,
    unbalanced_moment_paper,
    unbalanced_moment_paper_sign_corrected,
)
from springlab.mechanisms.dyad.geometry import max_unbalanced, unbalanced_moment
from springlab.mechanisms.dyad.model import Compensator, Dyad, check_pair, check_phi, slider_height
from springlab.optimum import Optimum
from springlab.tables import Table

EQ32_READINGS = ("signed sum", "sum of magnitudes", "sum of squares", "maximum magnitude")
"""How 002 Eq. (31)'s total of the moments at the prescribed positions can be read."""


def eq32_objective(moments: np.ndarray, reading: str):
    """002 Eq. (31)'s total unbalanced moment under one reading of what is summed, over the last
    axis: a float for one set of moments (P,), an array for a batch (D, P)."""
    moments = _checks.real_array("moments (N m)", moments)
    if moments.size == 0:
        raise SpringlabError("moments is empty: give at least one unbalanced moment (N m)")
    totals = {"signed sum": lambda: np.sum(moments, axis=-1),
              "sum of magnitudes": lambda: np.sum(np.abs(moments), axis=-1),
              "sum of squares": lambda: np.sum(moments**2, axis=-1),
              "maximum magnitude": lambda: np.max(np.abs(moments), axis=-1)}
    if reading not in totals:
        raise SpringlabError(f"reading must be one of {EQ32_READINGS}, got {reading!r}")
    out = totals[reading]()
    return float(out) if np.ndim(out) == 0 else out


MOMENTS = {
    "virtual work": unbalanced_moment,
    "002 Eqs. (20)-(30) as printed": unbalanced_moment_paper,
    "002 Eqs. (20)-(30), spring sign corrected": unbalanced_moment_paper_sign_corrected,
}
"""The unbalanced-moment definitions compared in the paper-002 notebook."""


C_READINGS = ("signed sum stationary", "smallest |signed sum|", "sum of magnitudes", "sum of squares",
              "maximum magnitude")
"""Readings of 002 Eq. (32), dM_total/dC = 0: the first is literal (an extremum of the
signed sum of 002 Eq. 31); 'smallest |signed sum|' brings the sum closest to zero; the others minimise
the sum of |M|, of M^2, or the largest |M| over the prescribed positions."""


def design_for_C(comp: Compensator, C: float, phi, *, branch: int = -1) -> Dyad:
    """The dyad that 002 Eqs. (6)-(19) give for an energy constant C and positions phi."""
    _checks.instance("comp", comp, Compensator, "Compensator(G, s, k, l0)")
    return synthesise(phi, slider_positions(comp, C, phi, branch=branch)).dyad


def choose_C(comp: Compensator, phi, reading: str, *, moment: str = "virtual work",
             C_max: float | None = None, grid: int = 4000, branch: int = -1) -> float:
    """The energy constant C (J) that one reading of 002 Eq. (32) selects.

    Each C gives slider positions (002 Eq. 6), a dyad (002 Eq. 16) and the unbalanced
    moments at the prescribed positions; the reading turns those into one number
    (see :data:`C_READINGS`). C is searched on a grid from the smallest value with
    real slider positions to ``C_max`` (default: that value plus 4 G s), then refined.

    :raises SpringlabError: for an unknown reading or moment, or when no C works
    """
    from scipy.optimize import minimize_scalar

    if reading not in C_READINGS:
        raise SpringlabError(f"reading must be one of {C_READINGS}, got {reading!r}")
    if moment not in MOMENTS:
        raise SpringlabError(f"moment must be one of {tuple(MOMENTS)}, got {moment!r}")
    if int(grid) != grid or grid < 3:
        raise SpringlabError(f"grid must be an integer >= 3, got {grid}")
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    C_min = float(np.max(comp.gravity_energy(phi)))
    default = C_min + 4 * comp.G * comp.s
    if C_max is None:
        C_max = default
    elif _checks.finite("C_max", C_max, "J") <= C_min:
        raise SpringlabError(f"C_max = {C_max:g} J is not above {C_min:.6g} J, the smallest C with real slider "
                             f"positions at these positions (002 Eq. 6): give C_max above it, or None for "
                             f"{default:.6g} J")
    f = MOMENTS[moment]

    def total(C):
        try:
            m = f(comp, design_for_C(comp, C, phi, branch=branch), phi)
        except SpringlabError:
            return np.nan
        if reading in ("signed sum stationary", "smallest |signed sum|"):
            return float(np.sum(m))
        return eq32_objective(m, reading)

    Cs = np.linspace(C_min, C_max, grid)[1:]
    path = synthesis_path(comp, phi, Cs, branch=branch)  # the grid in one batch; total(C) refines below
    m, closes = batch_moments(comp, path["r"], path["l"], path["beta"], phi, moment)
    ok = path["ok"] & closes
    signed = reading in ("signed sum stationary", "smallest |signed sum|")
    values = np.where(ok, np.sum(m, axis=1) if signed else eq32_objective(m, reading), np.nan)
    if not np.any(ok):
        raise SpringlabError(f"no C in the search range {C_min:.6g} to {C_max:.6g} J gives a dyad that closes at "
                             f"every position: give a larger C_max (the default is {default:.6g} J)")
    if reading == "signed sum stationary":  # 002 Eq. (32) read literally: d(sum M)/dC = 0
        from scipy.optimize import brentq

        slope = np.gradient(values, Cs)
        flips = np.where(ok[:-1] & ok[1:] & (np.sign(slope[:-1]) != np.sign(slope[1:])))[0]
        if not len(flips):
            raise SpringlabError("the signed sum of 002 Eq. (31) has no stationary point in the search range")
        h = 1e-4 * (Cs[1] - Cs[0])
        k = int(flips[0])
        lo, hi = Cs[max(k - 1, 0)], Cs[min(k + 2, len(Cs) - 1)]  # np.gradient's flip lies within
        return float(brentq(lambda C: total(C + h) - total(C - h), lo, hi, xtol=1e-10))
    target = np.abs(values) if reading == "smallest |signed sum|" else values
    i = int(np.nanargmin(np.where(ok, target, np.nan)))
    lo, hi = Cs[max(i - 1, 0)], Cs[min(i + 1, len(Cs) - 1)]
    g = (lambda C: abs(total(C))) if reading == "smallest |signed sum|" else total
    res = minimize_scalar(lambda C: g(C) if np.isfinite(g(C)) else 1e300, bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-9})
    return float(res.x)


def optimise(comp: Compensator, phi, start: Dyad, *, free_l0: bool = False,
             bounds: dict | None = None) -> Optimum:
    """Minimise the largest |M_ub| (virtual work) over the angles ``phi`` by
    choosing r, l, beta (and l0 with ``free_l0``), from ``start``.

    The minimax is solved in epigraph form with SLSQP (scipy): minimise t subject
    to -t <= M_ub(phi_j) <= t, with the constraints' Jacobians in closed form. Only the
    angles that matter carry constraints (an exchange method for a minimax over a grid):
    SLSQP solves on every tenth angle, then the angles where |M_ub| tops t, or where the
    dyad fails to close, are added and it solves again from there, until the whole grid
    holds (|M_ub| <= t (1 + 1e-9) + 1e-12 N m at every angle of ``phi``). Default bounds: r in
    [0.01, 1] m, l in [0.05, 2] m, beta in [-pi/2, pi/2], l0 in [0, 3] m.
    """
    from scipy.optimize import minimize

    check_pair(comp, start)
    phi = np.atleast_1d(check_phi(phi))
    b = {"r": (0.01, 1.0), "l": (0.05, 2.0), "beta": (-np.pi / 2, np.pi / 2), "l0": (0.0, 3.0)}
    b.update(bounds or {})
    for name in ("r", "l"):  # the trial points are not built as a Dyad (which checks them): the bounds must hold it
        if not (np.isfinite(b[name][0]) and b[name][0] > 0):
            raise SpringlabError(f"bounds['{name}'] = {b[name]} allows {name} <= 0 m: give a lower bound above 0, "
                                 f"e.g. {name}: (0.01, 1.0)")
    keys = ["r", "l", "beta"] + (["l0"] if free_l0 else [])

    def unpack(x):
        l0 = x[3] if free_l0 else comp.l0
        return Dyad(x[0], x[1], x[2]), Compensator(comp.G, comp.s, comp.k, l0)

    def moments(x, angles):  # the fields of unpack(x) read straight from x: this runs tens of thousands of times
        r, rod, beta, l0 = x[0], x[1], x[2], (x[3] if free_l0 else comp.l0)
        u = angles - beta
        closing = np.maximum(rod**2 - (r * np.sin(u)) ** 2, 1e-12)
        y = r * np.cos(u) + np.sqrt(closing)
        return comp.G * comp.s * np.sin(angles) + comp.k * (y - l0) * r * np.sin(u) * y / np.sqrt(closing)

    def moments_jacobian(x, angles):
        """d M_ub / d (r, l, beta[, l0]) at each angle, (P, 3 or 4): ``moments`` differentiated
        term by term (the closing term's derivative is zero where it is clamped)."""
        r, rod, beta, l0, k = x[0], x[1], x[2], (x[3] if free_l0 else comp.l0), comp.k
        u = angles - beta
        sin_u, cos_u, zero, one = np.sin(u), np.cos(u), np.zeros_like(u), np.ones_like(u)
        raw = rod**2 - (r * sin_u) ** 2
        q = np.sqrt(np.maximum(raw, 1e-12))  # l cos(theta)
        y = r * cos_u + q
        f = (y - l0) * y
        dq = (raw > 1e-12) * np.stack([-r * sin_u**2 / q, rod / q, r**2 * sin_u * cos_u / q])
        dy = dq + np.stack([cos_u, zero, r * sin_u])
        dr, dsin = np.stack([one, zero, zero]), np.stack([zero, zero, -cos_u])  # d r, d sin(u) / d (r, l, beta)
        out = k * (dr * sin_u * f / q + r * dsin * f / q + r * sin_u * (2 * y - l0) * dy / q
                   - r * sin_u * f * dq / q**2)
        if free_l0:
            out = np.vstack([out, -k * r * sin_u * y / q])
        return out.T

    def closes(x, angles):  # l > r |sin(phi - beta)|: the dyad closes
        return x[1] - x[0] * np.abs(np.sin(angles - x[2])) - 1e-6

    def closes_jacobian(x, angles):
        s_u, c_u, zero = np.sin(angles - x[2]), np.cos(angles - x[2]), np.zeros(angles.size)
        return np.column_stack([-np.abs(s_u), np.ones(angles.size), x[0] * np.sign(s_u) * c_u]
                               + [zero] * (len(keys) - 3) + [zero])

    def solve(x0, angles):
        ones = np.ones((angles.size, 1))
        cons = [{"type": "ineq", "fun": lambda x: x[-1] - moments(x[:-1], angles),
                 "jac": lambda x: np.hstack([-moments_jacobian(x[:-1], angles), ones])},
                {"type": "ineq", "fun": lambda x: x[-1] + moments(x[:-1], angles),
                 "jac": lambda x: np.hstack([moments_jacobian(x[:-1], angles), ones])},
                {"type": "ineq", "fun": lambda x: closes(x, angles), "jac": lambda x: closes_jacobian(x, angles)}]
        gradient = np.zeros(len(x0))
        gradient[-1] = 1.0
        return minimize(lambda x: x[-1], x0, jac=lambda x: gradient, method="SLSQP", constraints=cons,
                        bounds=[b[k] for k in keys] + [(0, None)], options={"maxiter": 500, "ftol": 1e-12})

    x = [start.r, start.l, start.beta] + ([comp.l0] if free_l0 else [])
    x = np.array(x + [float(np.max(np.abs(moments(np.array(x), phi))))])
    active = np.zeros(phi.size, dtype=bool)
    active[::10] = active[-1] = True
    evaluations = 0
    for _ in range(50):
        res = solve(x, phi[active])
        x, evaluations = res.x, evaluations + int(res.nfev)
        m = np.abs(moments(x[:-1], phi))
        over = (m > x[-1] * (1 + 1e-9) + 1e-12) | (closes(x, phi) < 0)
        if not over[~active].any():
            break
        # each run of angles over the bound adds its worst angle, and the grid's worst adds too
        worst = np.where(over & ~active, m, -np.inf)
        edges = np.flatnonzero(np.diff(np.concatenate([[False], over & ~active, [False]]).astype(int)))
        for lo, hi in zip(edges[::2], edges[1::2], strict=True):
            active[lo + int(np.argmax(worst[lo:hi]))] = True
        x[-1] = max(x[-1], float(np.max(m[active])))  # a start that meets every bound on t
    else:
        raise SearchExhaustedError(f"the minimax over {phi.size} angles did not settle in 50 exchanges of "
                                   "the constrained angles: give fewer angles or another start")
    d, c = unpack(x[:-1])
    return Optimum(d, {"r": d.r, "l": d.l, "beta": d.beta, "l0": c.l0}, "largest |M_ub| (N m), minimised",
                   max_unbalanced(c, d, phi), evaluations, {k: b[k] for k in keys},
                   {"free_l0": free_l0})


# --- the readings the paper allows, searched in batches -----------------------------
def synthesis_path(comp: Compensator, phi, Cs, *, branch: int = -1) -> dict[str, np.ndarray]:
    """The dyads 002 Eqs. (6)-(19) give for every energy constant in ``Cs`` (J) at the
    positions ``phi`` (rad), in one batch: {'C', 'r', 'l', 'beta', 'ok'}. ``ok`` is False
    where a slider position is imaginary (002 Eq. 6), the system is singular or l^2 <= 0
    (002 Eq. 19); the other entries there are 0, never NaN."""
    _checks.instance("comp", comp, Compensator, "Compensator(G, s, k, l0)")
    phi = np.atleast_1d(check_phi(phi))
    Cs = np.atleast_1d(_checks.real_array("Cs (energy constants, J)", Cs))
    if Cs.size == 0:
        raise SpringlabError("Cs is empty: give at least one energy constant C (J)")
    _checks.memory(f"{Cs.size} energy constants at {phi.size} positions", Cs.size * phi.size * 12,
                   hint="use fewer constants or positions")
    radicand = (2.0 * Cs[:, None] - 2.0 * comp.gravity_energy(phi)[None, :]) / comp.k  # 002 Eq. (6)
    ok = np.all(radicand >= 0, axis=1)
    y = comp.l0 + branch * np.sqrt(np.where(ok[:, None], radicand, 0.0))  # 002 Eq. (7)
    A = np.stack([2 * y * np.cos(phi), 2 * y * np.sin(phi), np.ones_like(y)], axis=2)  # 002 Eq. (16)
    c = y**2
    AT = np.transpose(A, (0, 2, 1))
    normal = AT @ A
    ok &= np.abs(np.linalg.det(normal)) > 1e-12 * np.linalg.norm(normal, axis=(1, 2)) ** 3
    safe = np.where(ok[:, None, None], normal, np.eye(3))
    z = np.linalg.solve(safe, (AT @ c[:, :, None]))[:, :, 0]  # least squares (exact for 3 positions)
    r = np.hypot(z[:, 0], z[:, 1])  # 002 Eqs. (12)-(13), (18)
    beta = np.arctan2(z[:, 1], z[:, 0])  # 002 Eq. (17)
    l_sq = z[:, 2] + r**2  # 002 Eq. (19)
    ok &= (l_sq > 0) & (r > 0)
    zero = lambda v: np.where(ok, v, 0.0)  # noqa: E731
    return {"C": Cs, "r": zero(r), "l": zero(np.sqrt(np.maximum(l_sq, 0.0))), "beta": zero(beta), "ok": ok}


def batch_moments(comp: Compensator, r, l, beta, phi, moment: str = "virtual work") -> tuple[np.ndarray, np.ndarray]:  # noqa: E741 - the paper's symbol
    """Unbalanced moments (N m) of many dyads (arrays r, l, beta of one shape (D,)) at the
    angles phi (P,): (moments (D, P), closes (D,)), where a dyad that cannot close at some
    angle has closes False and zero moments. ``moment`` is a key of :data:`MOMENTS`."""
    if moment not in MOMENTS:
        raise SpringlabError(f"moment must be one of {tuple(MOMENTS)}, got {moment!r}")
    r, l, beta = (np.asarray(v, dtype=float)[:, None] for v in (r, l, beta))  # noqa: E741
    phi = np.atleast_1d(np.asarray(phi, dtype=float))[None, :]
    u = phi - beta
    closing = l**2 - (r * np.sin(u)) ** 2
    closes = np.all(closing > 0, axis=1) & (l[:, 0] > 0)
    l_cos = np.sqrt(np.where(closes[:, None], closing, 1.0))  # l cos(theta)
    y = r * np.cos(u) + l_cos  # 002 Eq. (24)
    F_sp = comp.k * (y - comp.l0)  # 002 Eq. (25)
    gravity = comp.G * comp.s * np.sin(phi)
    vw = gravity + F_sp * r * np.sin(u) * y / l_cos  # -dP/dphi
    if moment == "virtual work":
        out = vw
    else:
        cos_theta = l_cos / np.where(closes[:, None], l, 1.0)
        spring_printed = (vw - gravity) * cos_theta**2  # 002 Eq. (26)'s F_sp cos(theta): the true share x cos^2
        # 002 Eq. (30) as printed, -(M_sp + M_G) with M_G = -G s sin(phi), subtracts the spring's share
        out = gravity + spring_printed if moment.endswith("sign corrected") else gravity - spring_printed
    return np.where(closes[:, None], out, 0.0), closes


def _candidate_Cs(comp: Compensator, phi, step: float, span: float | None, branch: int, moment_names):
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    if not (np.isfinite(step) and step > 0):
        raise SpringlabError(f"step must be > 0 J, got {step}")
    C_min = float(np.max(comp.gravity_energy(phi)))
    span = 4 * comp.G * comp.s if span is None else span
    path = synthesis_path(comp, phi, np.arange(C_min + step, C_min + span, step), branch=branch)
    out = {}
    for moment in moment_names:
        m, closes = batch_moments(comp, path["r"], path["l"], path["beta"], phi, moment)
        ok = path["ok"] & closes
        out[moment] = (path["C"][ok], m[ok])
    return out


def _select(Cs: np.ndarray, m: np.ndarray, reading: str) -> float:
    if not len(Cs):
        raise SpringlabError("no C in the search range gives a dyad that closes at every position")
    if reading == "signed sum stationary":  # d(sum M)/dC = 0 read literally: the first turn of the sum
        slope = np.diff(eq32_objective(m, "signed sum"))
        flips = np.flatnonzero(np.sign(slope[:-1]) != np.sign(slope[1:]))
        if not len(flips):
            raise SpringlabError("the signed sum of 002 Eq. (31) has no stationary point in the search range")
        return float(Cs[flips[0] + 1])
    if reading == "smallest |signed sum|":
        value = np.abs(eq32_objective(m, "signed sum"))
    else:
        value = eq32_objective(m, reading)
    return float(Cs[int(np.argmin(value))])


def select_C(comp: Compensator, phi, reading: str, moment: str = "virtual work", *, step: float = 0.05,
             span: float | None = None, branch: int = -1) -> float:
    """The energy constant C (J) one reading of 002 Eq. (32) selects, on a grid of ``step`` J
    from the smallest C with real slider positions to that plus ``span`` (default 4 G s):
    the batch counterpart of :func:`choose_C` (same readings, :data:`C_READINGS`), without
    its final refinement.

    :raises SpringlabError: an unknown reading or moment, or no C gives a dyad that closes
        at every position (or, read literally, the signed sum has no stationary point)
    """
    if reading not in C_READINGS:
        raise SpringlabError(f"reading must be one of {C_READINGS}, got {reading!r}")
    Cs, m = _candidate_Cs(comp, phi, step, span, branch, [moment])[moment]
    return _select(Cs, m, reading)


def position_sets(low_deg: float = 30.0, high_deg: float = 150.0, step_deg: float = 10.0) -> dict[str, np.ndarray]:
    """Every set of three prescribed angles on a grid of ``step_deg`` over [low, high] (deg),
    keyed '30, 60, 120 deg', in rad."""
    import itertools

    low_deg, high_deg = _checks.finite("low_deg", low_deg, "deg"), _checks.finite("high_deg", high_deg, "deg")
    step_deg = _checks.positive("step_deg", step_deg, unit="deg")
    if not high_deg > low_deg:
        raise SpringlabError(f"high_deg = {high_deg:g} must be above low_deg = {low_deg:g}")
    _checks.memory(f"positions every {step_deg:g} deg", ((high_deg - low_deg) / step_deg + 1) ** 3 / 6 * 3,
                   hint="use a coarser step_deg")
    grid = np.arange(low_deg, high_deg + step_deg / 2, step_deg)
    return {", ".join(f"{a:g}" for a in trio) + " deg": np.radians(trio) for trio in itertools.combinations(grid, 3)}


def readings_search(comp: Compensator, sets: dict[str, np.ndarray], printed: dict[str, tuple[float, float]], *,
                    rules=None, step: float = 0.05, refine: int = 10) -> list[dict]:
    """For every set of prescribed positions and every rule (reading of 002 Eq. 32, moment
    definition) for C: the C it selects, the dyad 002 Eqs. (6)-(19) give there, and how far
    each of C, r, l, beta is from the printed value in half-units of its last printed
    digit (``printed``: {'C': (value, decimals), 'r': ..., 'l': ..., 'beta_deg': ...}).
    ``worst`` <= 1 means all four reproduce to the printed rounding. C is first chosen
    on a grid of ``step`` J for every row; the ``refine`` closest rows are then recomputed
    with C refined off the grid (:func:`choose_C`). Rows sorted by worst.
    """
    rules = rules or [(reading, moment) for moment in MOMENTS for reading in C_READINGS]
    rows = []

    def row(label, phi, reading, moment, C):
        fit = synthesise(phi, slider_positions(comp, C, phi))
        ours = {"C": C, "r": fit.dyad.r, "l": fit.dyad.l, "beta_deg": float(np.degrees(fit.dyad.beta))}
        miss = {k: abs(ours[k] - v) / (0.5 * 10.0 ** -d) for k, (v, d) in printed.items()}
        return {"positions": label, "reading": reading, "moment": moment, **ours,
                "worst": max(miss.values()), "miss": miss, "why": ""}

    for label, phi in sets.items():
        candidates = _candidate_Cs(comp, phi, step, None, -1, sorted({m for _, m in rules}))
        for reading, moment in rules:
            try:
                rows.append(row(label, phi, reading, moment, _select(*candidates[moment], reading)))
            except SpringlabError as err:
                rows.append({"positions": label, "reading": reading, "moment": moment, "C": None,
                             "r": None, "l": None, "beta_deg": None, "worst": np.inf, "why": str(err)})
    rows.sort(key=lambda r: (r["worst"], r["positions"], r["reading"], r["moment"]))
    for k, r in enumerate(rows[:refine]):  # the closest: C refined off the grid (choose_C)
        if np.isfinite(r["worst"]):
            phi = sets[r["positions"]]
            rows[k] = row(r["positions"], phi, r["reading"], r["moment"],
                          choose_C(comp, phi, r["reading"], moment=r["moment"]))
    return sorted(rows, key=lambda row: (row["worst"], row["positions"], row["reading"], row["moment"]))


def optimise_from_many(comp: Compensator, phi, starts, *, free_l0: bool = False) -> tuple[Optimum, list[Optimum]]:
    """:func:`optimise` from every dyad in ``starts``: (the best optimum, all of them).
    Starting from several points shows whether the minimax has one optimum or several."""
    runs = []
    for start in starts:
        try:
            runs.append(optimise(comp, phi, start, free_l0=free_l0))
        except SpringlabError:
            continue
    if not runs:
        raise SpringlabError("the optimiser failed from every start; give starts whose dyad closes over phi")
    return min(runs, key=lambda o: o.value), runs


def start_grid(r=(0.08, 0.13, 0.2), l=(0.4, 0.55, 0.8), beta_deg=(-10.0, 0.0, 10.0)) -> list[Dyad]:  # noqa: E741
    """Starting dyads on a grid of r (m), l (m) and beta (deg), for :func:`optimise_from_many`."""
    return [Dyad(ri, li, np.radians(bi)) for ri in r for li in l for bi in beta_deg if li > ri]


def readings_table(rows: list[dict], *, top: int = 12, always=()) -> Table:
    """The first ``top`` rows of :func:`readings_search` (and every row whose positions are
    in ``always``) as a table, with each quantity's miss in half-units."""
    keep = rows[:top] + [r for r in rows[top:] if r["positions"] in always]
    out = []
    for r in keep:
        if r["C"] is None:
            out.append((r["positions"], r["reading"], r["moment"], f"none: {r['why']}", None, None, None, None))
            continue
        out.append((r["positions"], r["reading"], r["moment"], f"{r['C']:.2f}", f"{r['r']:.5f}", f"{r['l']:.5f}",
                    f"{r['beta_deg']:.4f}", f"{r['worst']:.2f}"))
    return Table(["positions", "reading of 002 Eq. (32)", "moment", "C (J)", "r (m)", "l (m)", "beta (deg)",
                  "worst miss (half-units)"], out)


def residual_readings(comp: Compensator, dyad: Dyad, phi) -> dict[str, float]:
    """The largest residual moment (N m) of one dyad over the angles ``phi`` (rad) under the
    computations a reader of Section IV might make: each moment of :data:`MOMENTS`, beta with
    its sign flipped, beta read in degrees where radians were meant, and the spring's moment
    F_sp r sin(psi) with 002 Eq. (26)'s cos(theta) left out. Used to look for the computation
    behind the printed maxima."""
    check_pair(comp, dyad)
    phi = check_phi(phi)
    out = {}
    for name, f in MOMENTS.items():
        out[name] = float(np.max(np.abs(f(comp, dyad, phi))))
    out["virtual work, beta sign flipped"] = float(np.max(np.abs(unbalanced_moment(comp, Dyad(dyad.r, dyad.l, -dyad.beta), phi))))
    misread = Dyad(dyad.r, dyad.l, np.radians(np.radians(np.degrees(dyad.beta))))
    out["virtual work, beta in degrees read as radians"] = float(np.max(np.abs(unbalanced_moment(comp, misread, phi))))
    y = slider_height(dyad, phi)
    psi = np.arcsin(np.clip(y * np.sin(phi - dyad.beta) / dyad.l, -1, 1))  # 002 Eq. (29)
    no_cos = comp.gravity_moment(phi) + comp.k * (y - comp.l0) * dyad.r * np.sin(psi)
    out["002 Eqs. (25)-(30) without 002 Eq. (26)'s cos(theta), sign corrected"] = float(np.max(np.abs(no_cos)))
    return out


def designs_table(comp: Compensator, designs: dict, phi) -> Table:
    """Dyads side by side: {label: (dyad, l0)} with r, l (m), beta (deg), l0 (m) and the
    largest |M_ub| (virtual work, N m) over the angles ``phi`` (rad)."""
    rows = []
    for label, (d, l0) in designs.items():
        worst = max_unbalanced(Compensator(comp.G, comp.s, comp.k, l0), d, phi)
        rows.append((label, f"{d.r:.4f}", f"{d.l:.4f}", f"{np.degrees(d.beta):.3f}", f"{l0:.3f}", f"{worst:.3f}"))
    return Table(["design", "r (m)", "l (m)", "beta (deg)", "l0 (m)", "max abs M_ub (N m)"], rows)
