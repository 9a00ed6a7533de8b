r"""Designs for paper 003's planar arm: the balancing equations of a configuration
(003 Eqs. 16a-b) solved in sympy, Table 1's configurations, payload adjustment
(003 Eq. 32), and the index optimised over the free parameters.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import functools
import itertools

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.mechanisms.planar.efficiency import efficiency_index
from springlab.mechanisms.planar.model import (
    PlanarArm,
    PlanarSpring,
    Workspace,
    check_arm,
    check_spring,
    check_springs,
    wrap_degrees,
)
from springlab.mechanisms.planar.quadratic import gravity_terms, spring_terms
from springlab.optimum import Optimum

# --- balancing equations, configurations, design (003 Eqs. 16, 26-27, 32; Tables 1-2) ---------------
CONFIGURATIONS = {
    "Λ1": (((1, 2), (90.0, 0.0)),),
    "Λ2": (((1, 3), (90.0, 0.0)), ((2, 3), (0.0, 0.0))),
    "Λ3-1": (((1, 2), (90.0, 0.0)), ((1, 4), (90.0, 0.0)), ((2, 4), (0.0, 0.0)), ((3, 4), (180.0, 180.0))),
    "Λ3-2": (((1, 2), (90.0, 0.0)), ((1, 4), (90.0, 0.0)), ((2, 3), (0.0, 0.0)), ((2, 4), (180.0, 180.0))),
}
"""Table 1's efficient configurations: spring (i, j) and (alpha, beta) in degrees. Where
Table 1 gives only alpha - beta, (90, 0) or (0, 0) is used; Table 4 attaches S(3,4) at (180, 180)."""


def _configuration(config) -> tuple:
    """A configuration given by its Table 1 name ('Λ3-1', ...) or as ((i, j), (alpha, beta)) pairs."""
    if isinstance(config, str):
        if config not in CONFIGURATIONS:
            raise SpringlabError(f"unknown configuration {config!r}; Table 1's are {list(CONFIGURATIONS)}")
        return CONFIGURATIONS[config]
    if not hasattr(config, "__iter__"):
        raise SpringlabError(f"config must be a Table 1 name such as 'Λ3-1' or ((i, j), (alpha, beta)) pairs, "
                             f"got {config!r}")
    config = tuple(config)
    for pair in config:
        try:
            (i, j), (alpha, beta) = pair
        except (TypeError, ValueError):
            raise SpringlabError(f"each spring of config must be ((i, j), (alpha, beta)), got {pair!r}") from None
    return config


def _symbols(config):
    import sympy as sp

    out = {}
    for (i, j), _ in config:
        out[(i, j)] = sp.symbols(f"k_S{i}{j} A_S{i}{j} B_S{i}{j}", positive=True)
    return out


def balance_equations(config, G=None) -> dict:
    """003 Eqs. (16a-b) for a configuration, in sympy: {(u, v): sum of the pair's pseudo-
    stiffness amplitudes, signed} = 0, with symbols k_Sij, A_Sij, B_Sij and |G_1u|
    (``G`` numbers instead of the symbols G_1u if given)."""
    import sympy as sp

    config = _configuration(config)
    n = max(j for (_, j), _ in config)
    syms = _symbols(config)
    Gs = [sp.Symbol(f"G_1{u}", positive=True) for u in range(2, n + 1)] if G is None else [sp.nsimplify(x) for x in G]
    eqs = {}
    all_terms = gravity_terms(Gs)
    for (i, j), (alpha, beta) in config:
        k, A, B = syms[(i, j)]
        all_terms += spring_terms(i, j, k, A, B, alpha, beta)
    for t in all_terms:
        ref = 90.0 if t.u == 1 else 0.0  # each pair's terms must be in phase or opposite
        d = wrap_degrees(t.phase - ref)
        if np.isclose(d, 0.0) or np.isclose(d, 360.0):
            sign = 1
        elif np.isclose(d, 180.0):
            sign = -1
        else:
            raise SpringlabError(f"a term of {t.source} on ({t.u},{t.v}) has phase {t.phase:g} deg: "
                                 "not an efficient attachment; 003 Eqs. (16) need in-phase terms")
        eqs[(t.u, t.v)] = eqs.get((t.u, t.v), 0) + sign * t.amplitude
    return {key: sp.expand(v) for key, v in eqs.items()}


def _known_names(name: str, given, allowed, config) -> None:
    """Refuse names in ``given`` that are no parameter of ``config`` (before sympy: an unknown
    name would only show after a long solve, and would never be named)."""
    unknown = sorted(str(x) for x in given if x not in allowed)
    if unknown:
        raise SpringlabError(f"{name} names {', '.join(map(repr, unknown))}, not a parameter of {config!r}: "
                             f"choose among {', '.join(allowed)}")


def solve_configuration(config, free, G=None, values=None) -> dict:
    """Solve 003 Eqs. (16) for every parameter not in ``free`` (names like 'A_S14', or sympy
    symbols). With ``values`` ({name: number}) the free parameters are numbers, put in
    before solving. Returns {symbol: expression}; raises UnbalanceableError if no
    positive solution exists."""
    import sympy as sp

    eqs = balance_equations(config, G)
    if values is not None and not isinstance(values, dict):
        raise SpringlabError(f"values must be a dict {{name: number}}, got {values!r}")
    if isinstance(free, str) or not hasattr(free, "__iter__"):
        raise SpringlabError(f"free must be a list of parameter names such as ['A_S14'], got {free!r}")
    names = {f if isinstance(f, str) else f.name for f in free}
    params = sorted(set().union(*[e.free_symbols for e in eqs.values()]), key=lambda x: x.name)
    allowed = [x.name for x in params if not x.name.startswith("G_")]
    _known_names("free", names, allowed, config)
    _known_names("values", values or {}, allowed, config)
    subs = {sp.Symbol(k, positive=True): sp.nsimplify(v) for k, v in (values or {}).items()}
    system = [e.subs(subs) for e in eqs.values()]
    unknown = [x for x in params if x.name not in names and not x.name.startswith("G_")]
    sol = sp.solve([e for e in system if e != 0], unknown, dict=True)
    sol = [x for x in sol if all(v.is_positive is not False for v in x.values())]
    if not sol or any(e.subs(sol[0]).simplify() != 0 for e in system):
        raise UnbalanceableError(f"003 Eqs. (16) have no positive solution for {[x.name for x in unknown]} "
                                 f"with {sorted(names)} given")
    return sol[0]


@functools.lru_cache(maxsize=64)
def _symbolic_designer(cfg, names):
    """003 Eqs. (16) solved once, with the |G| and the chosen parameters as symbols, and
    compiled: (G values, chosen values) -> {parameter name: value}; None if sympy cannot
    solve it generally (e.g. when a chosen parameter is in fact forced)."""
    import sympy as sp

    try:
        sol = solve_configuration(cfg, list(names))
    except UnbalanceableError:
        return None
    n = max(j for (_, j), _ in cfg)
    args = [sp.Symbol(f"G_1{u}", positive=True) for u in range(2, n + 1)] + [sp.Symbol(x, positive=True) for x in names]
    if any(not expr.free_symbols <= set(args) for expr in sol.values()):
        return None
    keys = [x.name for x in sol]
    f = sp.lambdify(args, list(sol.values()), "math")
    return lambda G, values: dict(zip(keys, f(*G, *values), strict=True))


def design(arm: PlanarArm, config, choices: dict) -> list[PlanarSpring]:
    """Springs of ``config`` for the arm, from 003 Eqs. (16) and the user's ``choices``
    ({'A_S14': 0.1, 'k_S12': 4998, ...}: enough of k, A, B to fix the rest).

    Raises :class:`~springlab.errors.UnbalanceableError` if the equations have no positive solution or
    leave a parameter undetermined, SpringlabError if an attachment falls off its link.
    """
    check_arm(arm)
    import sympy as sp

    cfg = _configuration(config)
    if not isinstance(choices, dict):
        raise SpringlabError(f"choices must be a dict such as {{'A_S14': 0.1, 'k_S12': 4998}}, got {choices!r}")
    _known_names("choices", choices, [f"{name}_S{i}{j}" for (i, j), _angles in cfg for name in ("k", "A", "B")],
                  config)
    names = tuple(sorted(choices))
    fast = _symbolic_designer(cfg, names)
    if fast is not None:
        known = dict(choices) | fast(tuple(arm.G), tuple(float(choices[x]) for x in names))
    else:
        sol = solve_configuration(cfg, list(choices), G=arm.G, values=choices)
        known = dict(choices) | {x.name: (float(v) if not sp.sympify(v).free_symbols else None) for x, v in sol.items()}
    out = []
    for (i, j), (alpha, beta) in cfg:
        got = []
        for name in ("k", "A", "B"):
            value = known.get(f"{name}_S{i}{j}")
            if value is None:
                raise UnbalanceableError(f"S({i},{j}): {name}_S{i}{j} is not determined by 003 Eqs. (16); choose it")
            if not (np.isfinite(value) and value > 0):
                raise UnbalanceableError(f"S({i},{j}): 003 Eqs. (16) give {name}_S{i}{j} = {value:.6g}, not > 0")
            got.append(float(value))
        k, A, B = got
        spring = PlanarSpring(i, j, k, A * arm.r[i - 1], B * arm.r[j - 1], alpha, beta)
        check_spring(arm, spring)
        out.append(spring)
    return out


def payload_adjustment(arm: PlanarArm, springs, config, payload: float, *, keep: str = "stiffness",
                       mono: str = "A") -> list[PlanarSpring]:
    """Rebalance ``springs`` for a payload (kg) at the end link's COM (003 Eq. 32).

    :param keep: 'stiffness', Section 4.3's rule (Table 2): every k kept, the
        attachments moved; or 'attachments': every A kept (and B where 003 Eqs. (16)
        leave it free), the stiffnesses (and the B that 003 Eqs. 27a, c force) re-solved
    :param mono: under keep='stiffness', which of A, B moves on a spring over one
        joint, where 003 Eqs. (16) fix only the product A B
    """
    springs = check_springs(arm, springs)
    if keep not in ("stiffness", "attachments"):
        raise SpringlabError(f"keep must be 'stiffness' or 'attachments', got {keep!r}")
    if mono not in ("A", "B"):
        raise SpringlabError(f"mono must be 'A' or 'B', got {mono!r}")
    loaded = arm.with_payload(payload)
    cfg = _configuration(config)
    if keep == "stiffness":
        choices = {}
        for sp in springs:
            tag = f"S{sp.i}{sp.j}"
            choices[f"k_{tag}"] = sp.k
            if sp.j == sp.i + 1:
                other = "B" if mono == "A" else "A"
                choices[f"{other}_{tag}"] = sp.B(arm) if other == "B" else sp.A(arm)
        return design(loaded, cfg, choices)
    # keep='attachments': every A and B kept, except the B that 003 Eqs. (16) force (27a, 27c):
    # drop the fewest such B for a solution to exist
    base = {f"A_S{sp.i}{sp.j}": sp.A(arm) for sp in springs}
    Bs = {f"B_S{sp.i}{sp.j}": sp.B(arm) for sp in springs}
    multi = [f"B_S{sp.i}{sp.j}" for sp in springs if sp.j > sp.i + 1]
    for size in range(len(multi) + 1):
        for dropped in itertools.combinations(multi, size):
            try:
                return design(loaded, cfg, base | {k: v for k, v in Bs.items() if k not in dropped})
            except UnbalanceableError:
                continue
    raise UnbalanceableError(f"no design keeps the attachments of {config} under a payload of {payload} kg")


def com_distances(r, m, G, g: float) -> np.ndarray:
    """s_2..s_n (m) that give the printed |G_{1,u}| (N/m) by 003 Eq. (7), for a given g:
    s_u = (|G_1u| r_1 / g - sum_{w>u} m_w) r_u / m_u.

    :param r: r_1..r_n (m); m: m_2..m_n (kg); G: |G_12|..|G_1n| (N/m)
    """
    r, m, G = (_checks.real_array(name, x) for name, x in (("r", r), ("m", m), ("G", G)))
    g = _checks.positive("g", g, unit="m/s^2")
    if not (r.size == m.size + 1 == G.size + 1):
        raise SpringlabError(f"need r_1..r_n, m_2..m_n, |G_12|..|G_1n|; got {r.size}, {m.size}, {G.size} values")
    beyond = np.r_[np.cumsum(m[::-1])[::-1][1:], 0.0]
    return (G * r[0] / g - beyond) * r[1:] / m


def optimise_index(arm: PlanarArm, config: str, free: dict, fixed: dict, workspace: Workspace, *,
                   step: float = 5.0, k_max: float = 20000.0, start: dict | None = None) -> Optimum:
    """Maximise the efficiency index (grid ``step``, 'magnitudes' reading) over the
    parameters in ``free`` ({name: (low, high)}, e.g. {'A_S14': (0.05, 1)}), with the
    others in ``fixed``, every stiffness <= ``k_max`` (N/m) and every A, B in (0, 1]
    (scipy SLSQP from ``start``, default the middle of the bounds)."""
    check_arm(arm)
    from scipy.optimize import minimize

    names = list(free)
    lo = np.array([free[x][0] for x in names])
    hi = np.array([free[x][1] for x in names])
    if np.any(lo <= 0) or np.any(hi > 1 + 1e-12) or np.any(lo > hi):
        raise SpringlabError(f"bounds must satisfy 0 < low <= high <= 1, got {free}")
    x0 = np.array([(start or {}).get(x, 0.5 * (free[x][0] + free[x][1])) for x in names])
    count = [0]

    def springs_of(x):
        return design(arm, config, fixed | dict(zip(names, map(float, x), strict=True)))

    def objective(x):
        count[0] += 1
        try:
            return -efficiency_index(arm, springs_of(x), workspace, step=step)
        except SpringlabError:
            return 0.0

    def stiffness_margin(x):
        try:
            return np.array([k_max - s.k for s in springs_of(x)]) / k_max
        except SpringlabError:
            return -np.ones(len(_configuration(config)))

    res = minimize(objective, x0, method="SLSQP", bounds=list(zip(lo, hi, strict=True)),
                   constraints=[{"type": "ineq", "fun": stiffness_margin}], options={"ftol": 1e-9, "maxiter": 200})
    best = dict(zip(names, map(float, np.clip(res.x, lo, hi)), strict=True))
    springs = springs_of(list(best.values()))
    if max(s.k for s in springs) > k_max * (1 + 1e-6):
        raise UnbalanceableError(f"no design of {config} within k <= {k_max} N/m was found")
    return Optimum(springs, best, f"efficiency index (grid step {step:g} deg, 'magnitudes'), maximised",
                   efficiency_index(arm, springs, workspace, step=step), count[0], dict(free),
                   {"config": config, "k_max": k_max})


def index_over_attachments(arm: PlanarArm, workspace: Workspace, choices: dict, A_axis, *, step: float,
                           config: str = "Λ3-1") -> np.ndarray:
    """The efficiency index (grid ``step`` deg) with A_S14 and A_S24 over ``A_axis`` and the
    other ``choices`` kept (003 Fig. 7a): array [A_S24 index, A_S14 index]."""
    check_arm(arm)
    return np.array([[efficiency_index(arm, design(arm, config, choices | {"A_S14": a1, "A_S24": a2}), workspace, step=step)
                      for a1 in A_axis] for a2 in A_axis])


def index_over_stiffnesses(arm: PlanarArm, workspace: Workspace, choices: dict, k14_axis, k24_axis, *, step: float,
                           config: str = "Λ3-1") -> np.ndarray:
    """The efficiency index over k_S14 (columns) and k_S24 (rows), N/m (003 Fig. 7b): with
    |G_13| fixed, A_S14 = |G_13| / k_S14 and A_S24 = k_S14 / k_S24 (003 Eqs. 27b, d);
    NaN where an A would exceed 1 (the spring would leave its link)."""
    check_arm(arm)
    G13 = arm.G[1]
    out = np.full((len(k24_axis), len(k14_axis)), np.nan)
    for i, k24 in enumerate(k24_axis):
        for j, k14 in enumerate(k14_axis):
            a1, a2 = G13 / k14, k14 / k24
            if a1 <= 1 and a2 <= 1:
                out[i, j] = efficiency_index(arm, design(arm, config, choices | {"A_S14": a1, "A_S24": a2}), workspace,
                                             step=step)
    return out
