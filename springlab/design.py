"""Designing the springs: solve the balancing equations (Eqs. 39a-b of 000).

Three tools:

* :func:`solve_design`: the paper's way. For a configuration and the user's
  free choices (for example a and k of some springs), solve Eqs. (39a-b)
  exactly (sympy, rational arithmetic) for the rest, or say why it cannot.
* :func:`find_design`: any balanced design of a configuration, found
  numerically (least squares on the logarithms of |a|, |b|, k, so the signs hold
  by construction). Used for random arms and for the plain feasibility check.
* :func:`feasibility`: the plain criterion, independent of rules R1-R6: do
  Eqs. (39) have a solution with k > 0 and the stated signs of a and b?
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy as sp
from scipy.optimize import least_squares, linprog

from springlab.chain import Chain
from springlab.configurations import SpringSlot, as_slots
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.quadratic import balance_residual, gravity_entries, spring_entries
from springlab.springs import Spring, sign_char


@dataclass(frozen=True)
class SpringSpec:
    """A spring to design: S(i,j) with a pattern, and whichever of a (m), b (m),
    k (N/m) the designer fixes; ``None`` marks an unknown to solve for."""

    i: int
    j: int
    pattern: str | None = None
    a: float | None = None
    b: float | None = None
    k: float | None = None

    def __post_init__(self):
        SpringSlot(self.i, self.j, self.pattern or "(+,+)")  # validates indices and pattern
        if self.k is not None and not (np.isfinite(self.k) and self.k > 0):
            raise SpringlabError(f"k of S({self.i},{self.j}) must be > 0 N/m, got {self.k}")
        for name in ("a", "b"):
            v = getattr(self, name)
            if v is not None and not np.isfinite(v):
                raise SpringlabError(f"{name} of S({self.i},{self.j}) must be finite, got {v}")
            if v is not None and self.pattern is not None:
                want = self.pattern[1] if name == "a" else self.pattern[3]
                if sign_char(v) != want:
                    raise SpringlabError(
                        f"{name} of S({self.i},{self.j}) = {v} m contradicts its pattern {self.pattern}")


@dataclass(frozen=True)
class Design:
    """A balanced set of springs with the exact values behind it."""

    springs: tuple[Spring, ...]
    exact: dict = field(default_factory=dict)  # symbol name -> sympy number
    equations: dict = field(default_factory=dict)  # (u, v) -> sympy expression (= 0)


def _rational(x: float) -> sp.Rational:
    return sp.Rational(repr(float(x)))


def check_attachments(chain: Chain, springs, *, max_extension: float | None = None) -> None:
    """Raise if a spring end lies off its link.

    An end on the link side of its joint (a < 0 on link i >= 2, b > 0 on link j)
    must stay within the link: |a| <= r_i, b <= r_j. An end on the other side
    (a > 0 past link i's distal joint, b < 0 behind link j's proximal joint) sits
    on a bracket that extends the link; ``max_extension`` (m) bounds it if given.
    """
    for s in springs:
        if s.i >= 2 and s.a < 0 and -s.a > chain.length(s.i) * (1 + 1e-12):
            raise UnbalanceableError(
                f"a_{s.label} = {s.a:.6g} m puts end A beyond link {s.i}'s proximal joint "
                f"(r_{s.i} = {chain.length(s.i):g} m): the attachment is off the link")
        if s.b > 0 and s.b > chain.length(s.j) * (1 + 1e-12):
            raise UnbalanceableError(
                f"b_{s.label} = {s.b:.6g} m puts end B beyond link {s.j}'s distal joint "
                f"(r_{s.j} = {chain.length(s.j):g} m): the attachment is off the link")
        if max_extension is not None:
            for name, value, extended in (("a", s.a, s.a > 0), ("b", s.b, s.b < 0)):
                if extended and abs(value) > max_extension:
                    raise UnbalanceableError(
                        f"{name}_{s.label} = {value:.6g} m needs a bracket longer than "
                        f"max_extension = {max_extension:g} m")


def solve_design(chain: Chain, specs, *, max_extension: float | None = None) -> Design:
    """Solve Eqs. (39a-b) for the unknown spring parameters, exactly.

    :param chain: the arm
    :param specs: :class:`SpringSpec` per spring; give each spring's pattern and
        fix as many of a, b, k as make the system determined
    :returns: :class:`Design` with floats in ``springs`` and exact values in ``exact``
    :raises UnbalanceableError: no solution, a negative stiffness, a sign that
        contradicts the pattern, or an attachment off the link
    :raises SpringlabError: the free choices leave unknowns undetermined
    """
    specs = list(specs)
    if not specs:
        raise UnbalanceableError("no springs: gravity cannot be balanced without springs")
    r = [_rational(v) for v in chain.r]
    d = [_rational(v) for v in chain.d]
    m = [_rational(v) for v in chain.m]
    g = _rational(chain.g)
    M = sp.zeros(chain.n, chain.n)
    for (u, v), val in gravity_entries(r, d, m, g).items():
        M[u - 1, v - 1] += val
    unknowns, params = [], []
    for idx, s in enumerate(specs):
        if s.j > chain.n:
            raise SpringlabError(f"S({s.i},{s.j}) attaches to link {s.j}, but the chain has {chain.n} links")
        tag = f"S({s.i},{s.j})" + ("'" * sum(1 for t in specs[:idx] if (t.i, t.j) == (s.i, s.j)))
        values = {}
        for name in ("a", "b", "k"):
            given = getattr(s, name)
            if given is None:
                sym = sp.Symbol(f"{name}_{tag}", real=True)
                unknowns.append(sym)
                values[name] = sym
            else:
                values[name] = _rational(given)
        params.append((tag, values))
        for (u, v), val in spring_entries(s.i, s.j, values["a"], values["b"], values["k"], r).items():
            M[u - 1, v - 1] += val
    equations = {(u + 1, v + 1): sp.expand(M[u, v])
                 for u in range(chain.n) for v in range(u + 1, chain.n) if M[u, v] != 0}
    eqs = list(equations.values())
    if not unknowns:
        bad = {key: e for key, e in equations.items() if e != 0}
        if bad:
            raise UnbalanceableError(f"the fixed springs leave Eqs. (39) unsatisfied at {sorted(bad)}")
        solutions = [{}]
    else:
        solutions = sp.solve(eqs, unknowns, dict=True)
    if not solutions:
        raise UnbalanceableError(
            "Eqs. (39a-b) have no solution with these free choices; the configuration cannot "
            "balance this arm, or the fixed values contradict each other")
    reasons, designs = [], []
    for sol in solutions:
        missing = [u for u in unknowns if u not in sol or sol[u].free_symbols]
        if missing:
            raise SpringlabError(
                "Eqs. (39a-b) leave " + ", ".join(str(u) for u in missing) +
                " undetermined: fix that many more of a, b, k")
        try:
            exact, springs = _springs_of_solution(chain, specs, params, sol, max_extension)
        except UnbalanceableError as err:
            reasons.append(str(err))
            continue
        designs.append(Design(springs, exact, equations))
    if not designs:
        raise UnbalanceableError("no admissible solution of Eqs. (39a-b): " + "; ".join(reasons))
    return designs[0]


def _springs_of_solution(chain, specs, params, sol, max_extension):
    """The springs of one exact solution of Eqs. (39), or UnbalanceableError saying
    what is wrong with it (not real, a negative stiffness, a sign against the
    pattern, an attachment off the link)."""
    exact, springs = {}, []
    for s, (tag, values) in zip(specs, params, strict=True):
        for name, v in values.items():
            val = v.subs(sol)
            if not val.is_real:
                raise UnbalanceableError(f"{name}_{tag} = {val} is not real")
            exact[f"{name}_{tag}"] = val
        a, b, k = (float(exact[f"{x}_{tag}"]) for x in ("a", "b", "k"))
        if k <= 0:
            raise UnbalanceableError(f"k_{tag} = {k:.6g} N/m: a negative stiffness")
        if s.pattern and (sign_char(a), sign_char(b)) != (s.pattern[1], s.pattern[3]):
            raise UnbalanceableError(f"{tag} comes out ({sign_char(a)},{sign_char(b)}), not {s.pattern} "
                                     f"(a = {a:.6g} m, b = {b:.6g} m)")
        springs.append(Spring(s.i, s.j, a, b, k))
    check_attachments(chain, springs, max_extension=max_extension)
    return exact, tuple(springs)


# --- numeric search and the plain feasibility criterion -------------------------
def _residual_entries(chain: Chain, slots) -> list[tuple[int, int]]:
    keys = {(1, j) for j in range(2, chain.n + 1)}
    for s in slots:
        keys |= {k for k in spring_entries(s.i, s.j, 1.0, 1.0, 1.0, chain.r) if k[0] < k[1]}
    return sorted(keys)


def find_design(chain: Chain, slots, *, seed=0, restarts: int = 30, tol: float = 1e-13,
                within_links: bool = True, max_extension: float | None = None) -> tuple[Spring, ...]:
    """A balanced design of the configuration ``slots``, found numerically.

    Least squares over (log k, log|a|, log|b|) of every spring, with the signs
    of the slots' patterns, from random starts. Succeeds when every entry of
    Eqs. (39) is below ``tol`` times the largest G_1,j.

    :param within_links: keep every end on its link (see :func:`check_attachments`)
        and every bracket (an end beyond a joint) no longer than ``max_extension``
        (m; default the longest link). ``False`` asks for the signs only.
    :raises UnbalanceableError: when no start converges
    """
    slots = as_slots(slots)
    for s in slots:
        if s.j > chain.n:
            raise SpringlabError(f"{s} attaches to link {s.j}, but the chain has {chain.n} links")
    rng = np.random.default_rng(seed)
    G = np.array(list(gravity_entries(chain.r, chain.d, chain.m, chain.g).values()))
    scale_u = float(np.max(np.abs(G)))
    if scale_u <= 0:
        raise UnbalanceableError("the arm has no gravity moment to balance (all G_1,j = 0)")
    length = float(np.mean(chain.r))
    scale_k = scale_u / length**2
    signs = np.array([(s.sa, s.sb) for s in slots], dtype=float)
    keys = _residual_entries(chain, slots)
    upper = np.full(3 * len(slots), 20.0)
    if within_links:
        reach = max_extension if max_extension is not None else max(chain.r)
        for idx, s in enumerate(slots):
            on_link_a = s.i >= 2 and s.sa < 0  # a < 0 lies on link i
            upper[3 * idx + 1] = np.log((chain.length(s.i) if on_link_a else reach) / length)
            upper[3 * idx + 2] = np.log((chain.length(s.j) if s.sb > 0 else reach) / length)
    lower = np.full_like(upper, -20.0)

    def springs_of(z):
        z = z.reshape(-1, 3)
        k = scale_k * np.exp(z[:, 0])
        a = signs[:, 0] * length * np.exp(z[:, 1])
        b = signs[:, 1] * length * np.exp(z[:, 2])
        return [Spring(s.i, s.j, float(ai), float(bi), float(ki)) for s, ai, bi, ki in zip(slots, a, b, k, strict=True)]

    def residual(z):
        R = balance_residual(chain, springs_of(z))
        return np.array([R[u - 1, v - 1] for u, v in keys]) / scale_u

    best = None
    for _ in range(restarts):
        z0 = np.minimum(rng.uniform(-1.5, 0.5, size=3 * len(slots)), upper - 0.05)
        try:
            sol = least_squares(residual, z0, method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                                bounds=(lower, upper), max_nfev=2000)
        except (ValueError, FloatingPointError):
            continue
        worst = float(np.max(np.abs(sol.fun)))
        if best is None or worst < best[0]:
            best = (worst, sol.x)
        if worst < tol:
            springs = tuple(springs_of(sol.x))
            if within_links:
                check_attachments(chain, springs, max_extension=reach * (1 + 1e-9))
            return springs
    raise UnbalanceableError(
        f"no balanced design found for {' '.join(map(str, slots))} after {restarts} starts "
        f"(best relative residual {best[0] if best else float('nan'):.3g})")


@dataclass(frozen=True)
class Feasibility:
    """Outcome of the plain criterion for one configuration.

    status: 'feasible' (a design was found: ``springs``), 'infeasible' (the
    linear relaxation has no solution with the stated signs: a proof), or
    'unknown' (the relaxation allows one, the search found none).
    """

    status: str
    margin: float  # the linear relaxation's sign margin; <= 0 proves infeasibility
    springs: tuple[Spring, ...] | None = None


def relaxation_margin(chain: Chain, slots) -> float:
    """Largest margin t such that Eqs. (39), written linearly in P = k a b,
    A = k a, B = k b and k of each spring, hold with every quantity carrying
    its pattern's sign by at least t (in units of max G). Drops only the
    coupling P k = A B, which binds only for springs spanning 3 or more links,
    so t <= 0 proves the configuration infeasible."""
    slots = as_slots(slots)
    G = gravity_entries(chain.r, chain.d, chain.m, chain.g)
    scale = max(abs(v) for v in G.values())
    keys = _residual_entries(chain, slots)
    row = {key: idx for idx, key in enumerate(keys)}
    columns, col_signs = [], []
    rr = {t: chain.r[t - 2] for t in range(2, chain.n + 1)}
    for s in slots:
        span = s.j - s.i
        col = {"P": {(s.i, s.j): -1.0}}
        col_signs.append(s.sa * s.sb)
        if span >= 2:
            col["A"] = {(s.i, t): -rr[t] for t in range(s.i + 1, s.j)}
            col["B"] = {(t, s.j): rr[t] for t in range(s.i + 1, s.j)}
            col_signs += [s.sa, s.sb]
        if span >= 3:
            col["K"] = {(t, v): rr[t] * rr[v] for t in range(s.i + 1, s.j) for v in range(t + 1, s.j)}
            col_signs.append(1)
        columns += list(col.values())
    n_var = len(columns)
    A_eq = np.zeros((len(keys), n_var + 1))
    for c, entries in enumerate(columns):
        for key, coef in entries.items():
            A_eq[row[key], c] = coef
    b_eq = np.array([-G.get(key, 0.0) / scale for key in keys])
    # sign_c * z_c >= t  <=>  -sign_c * z_c + t <= 0
    A_ub = np.zeros((n_var, n_var + 1))
    for c, sgn in enumerate(col_signs):
        A_ub[c, c] = -sgn
        A_ub[c, -1] = 1.0
    cost = np.zeros(n_var + 1)
    cost[-1] = -1.0
    bounds = [(-1e3, 1e3)] * n_var + [(None, 1.0)]
    res = linprog(cost, A_ub=A_ub, b_ub=np.zeros(n_var), A_eq=A_eq, b_eq=b_eq, bounds=bounds,
                  method="highs")
    if res.status == 2:  # infeasible even without the sign constraints
        return -np.inf
    if res.status != 0:
        raise RuntimeError(f"linear programme failed: {res.message}")
    return float(res.x[-1])


def feasibility(chain: Chain, slots, *, seed=0, restarts: int = 30) -> Feasibility:
    """The plain criterion: do Eqs. (39) have a solution with k > 0 and the signs
    of the slots' patterns, for this arm? See :class:`Feasibility`."""
    slots = as_slots(slots)
    margin = relaxation_margin(chain, slots)
    if margin <= 1e-9:
        return Feasibility("infeasible", margin)
    try:
        springs = find_design(chain, slots, seed=seed, restarts=restarts, within_links=False)
    except UnbalanceableError:
        return Feasibility("unknown", margin)
    return Feasibility("feasible", margin, springs)


def candidate_slots(n: int) -> list[SpringSlot]:
    """Every spring slot the attachment criteria allow on an n-link arm: ground
    springs (+,+) (and S(1,2) (-,-)), non-ground springs (+,+), (-,-), (+,-)."""
    out = [SpringSlot(1, 2, "(+,+)"), SpringSlot(1, 2, "(-,-)")]
    out += [SpringSlot(1, j) for j in range(3, n + 1)]
    out += [SpringSlot(i, j, p) for i in range(2, n) for j in range(i + 1, n + 1)
            for p in ("(+,+)", "(-,-)", "(+,-)")]
    return out


def compare_rules_with_feasibility(chain: Chain, configurations, *, restarts: int = 4,
                                   progress: bool = False) -> list[tuple[tuple, bool, str]]:
    """For each configuration: (configuration, admissible by R1-R6, plain-criterion status).

    :param progress: show a progress bar (tqdm) on long sweeps
    """
    from tqdm import tqdm

    from springlab.configurations import is_admissible

    configurations = list(configurations)
    out = []
    for cfg in tqdm(configurations, disable=not progress, mininterval=2.0, desc="configurations"):
        out.append((tuple(cfg), is_admissible(chain.n, cfg),
                    feasibility(chain, cfg, restarts=restarts).status))
    return out


def tally_comparison(results) -> dict[str, int]:
    """Count the outcomes of :func:`compare_rules_with_feasibility` in five classes."""
    classes = {"admitted, solvable": (True, "feasible"), "rejected, no solution": (False, "infeasible"),
               "admitted, no solution": (True, "infeasible"), "rejected, solvable": (False, "feasible")}
    out = {name: sum(1 for _, ok, st in results if (ok, st) == key) for name, key in classes.items()}
    out["undecided"] = sum(1 for _, _, st in results if st == "unknown")
    return out


def design_for(chain: Chain, *, seed=0, restarts: int = 30):
    """Springs that balance ``chain``: the first configuration from the enumerator
    (rules R1-R6) that the plain criterion confirms, with a design found for it.

    :returns: (configuration, springs)
    :raises UnbalanceableError: when no enumerated configuration yields a design
    """
    from springlab.configurations import iter_configurations

    for cfg in iter_configurations(chain.n):
        if relaxation_margin(chain, cfg) <= 1e-9:
            continue
        try:
            return cfg, find_design(chain, cfg, seed=seed, restarts=restarts)
        except UnbalanceableError:
            continue
    raise UnbalanceableError(f"no configuration of the enumerator balances this {chain.n}-link arm")
