"""Designing the springs: solve the balancing equations (000 Eqs. 39a-b of 000).

Three tools:

* :func:`solve_design`: the paper's way. For a configuration and the user's
  free choices (for example a and k of some springs), solve 000 Eqs. (39a-b)
  exactly (sympy, rational arithmetic) for the rest, or say why it cannot.
* :func:`find_design`: any balanced design of a configuration, found
  numerically (least squares on the logarithms of |a|, |b|, k, so the signs hold
  by construction). Used for random arms and for the plain feasibility check.
* :func:`feasibility`: the plain criterion, independent of rules R1-R6: do
  000 Eqs. (39) have a solution with k > 0 and the stated signs of a and b?

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import sympy as sp
from scipy.optimize import least_squares, linprog

from springlab import _checks
from springlab.design.rules import SpringSlot, as_slots, is_admissible, iter_configurations
from springlab.energy.quadratic import gravity_entries, spring_entries
from springlab.errors import (
    AttachmentError,
    SearchExhaustedError,
    SolverError,
    SpringlabError,
    UnbalanceableError,
)
from springlab.model.chain import Chain, check_attachments, check_springs
from springlab.model.springs import Spring, sign_char


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
        for name in ("i", "j"):
            object.__setattr__(self, name, _checks.count(
                f"spring link index {name}", getattr(self, name), least=1, why=" (S(i,j) needs 1 <= i < j)"))
        SpringSlot(self.i, self.j, self.pattern or "(+,+)")  # validates indices and pattern
        object.__setattr__(self, "k", _checks.optional_positive(f"k of S({self.i},{self.j})", self.k, "N/m"))
        for name in ("a", "b"):
            v = getattr(self, name)
            if v is not None:
                v = _checks.finite(f"{name} of S({self.i},{self.j})", v, "m")
                object.__setattr__(self, name, v)
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


def solve_design(chain: Chain, specs, *, max_extension: float | None = None) -> Design:
    """Solve 000 Eqs. (39a-b) for the unknown spring parameters, exactly.

    :param chain: the arm
    :param specs: :class:`SpringSpec` per spring; give each spring's pattern and
        fix as many of a, b, k as make the system determined
    :returns: :class:`Design` with floats in ``springs`` and exact values in ``exact``
    :raises UnbalanceableError: no solution, a negative stiffness, a sign that
        contradicts the pattern, or an attachment off the link
    :raises SpringlabError: the free choices leave unknowns undetermined
    """
    _checks.instance("chain", chain, Chain)
    max_extension = _checks.optional_positive("max_extension", max_extension, "m")
    if isinstance(specs, str) or not hasattr(specs, "__iter__"):
        raise SpringlabError(f"specs must be a list of SpringSpec, got {specs!r}")
    specs = list(specs)
    for s in specs:
        _checks.instance("each of specs", s, SpringSpec)
    if not specs:
        if balanced_core(chain) is None:
            return Design(())
        raise UnbalanceableError("no springs: gravity cannot be balanced without springs (G_1,j > 0, 000 Eq. 18)")
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
            raise UnbalanceableError(f"the fixed springs leave 000 Eqs. (39) unsatisfied at {sorted(bad)}")
        solutions = [{}]
    else:
        solutions = sp.solve(eqs, unknowns, dict=True)
    if not solutions:
        raise UnbalanceableError(
            "000 Eqs. (39a-b) have no solution with these free choices; the configuration cannot "
            "balance this arm, or the fixed values contradict each other")
    reasons, designs = [], []
    for sol in solutions:
        missing = [u for u in unknowns if u not in sol or sol[u].free_symbols]
        if missing:
            raise SpringlabError(
                "000 Eqs. (39a-b) leave " + ", ".join(str(u) for u in missing) +
                " undetermined: fix that many more of a, b, k")
        try:
            exact, springs = _springs_of_solution(chain, specs, params, sol, max_extension)
        except UnbalanceableError as err:
            reasons.append(str(err))
            continue
        designs.append(Design(springs, exact, equations))
    if not designs:
        raise UnbalanceableError("no admissible solution of 000 Eqs. (39a-b): " + "; ".join(reasons))
    return designs[0]


def _springs_of_solution(chain, specs, params, sol, max_extension):
    """The springs of one exact solution of 000 Eqs. (39), or UnbalanceableError saying
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


def linear_columns(chain: Chain, slots, *, exact: bool = False) -> list[dict[str, dict[tuple[int, int], float]]]:
    """Per spring, the entries of 000 Eqs. (39) that P = k a b, A = k a, B = k b and k
    carry (000 Eqs. 23a-d, written linearly): {'P': {(i, j): -1}, 'A': ..., 'B': ..., 'K': ...}.
    With ``exact`` the coefficients are rationals (``fractions.Fraction``), each link length read
    exactly as the rational its float is."""
    from fractions import Fraction

    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    slots = _slots_on(chain, slots)
    rr = {t: Fraction(chain.r[t - 2]) if exact else chain.r[t - 2] for t in range(2, chain.n + 1)}
    one = Fraction(1) if exact else 1.0
    out = []
    for s in as_slots(slots):
        inner = range(s.i + 1, s.j)
        out.append({"P": {(s.i, s.j): -one},  # 000 Eq. (23a)
                    "A": {(s.i, t): -rr[t] for t in inner},  # 000 Eq. (23b)
                    "B": {(t, s.j): rr[t] for t in inner},  # 000 Eq. (23d)
                    "K": {(t, v): rr[t] * rr[v] for t in inner for v in inner if t < v}})  # 000 Eq. (23c)
    return out


def _linear_system(chain: Chain, slots, keys) -> tuple[np.ndarray, np.ndarray]:
    """000 Eqs. (39) at the entries ``keys`` as M @ v + g = 0, v = (P, A, B, k) per spring (SI units)."""
    row = {key: idx for idx, key in enumerate(keys)}
    M = np.zeros((len(keys), 4 * len(as_slots(slots))))
    for idx, cols in enumerate(linear_columns(chain, slots)):
        for c, name in enumerate("PABK"):
            for key, coef in cols[name].items():
                M[row[key], 4 * idx + c] += coef
    G = gravity_entries(chain.r, chain.d, chain.m, chain.g)
    return M, np.array([G.get(key, 0.0) for key in keys])


def _scales(chain: Chain) -> tuple[float, float, float]:
    """(largest G_1,j in J, mean link length in m, their stiffness scale in N/m): the units
    the numeric searches work in."""
    G = np.array(list(gravity_entries(chain.r, chain.d, chain.m, chain.g).values()))
    scale_u = float(np.max(np.abs(G)))
    if scale_u <= 0:
        raise UnbalanceableError("the arm has no gravity moment to balance (all G_1,j = 0)")
    length = float(np.mean(chain.r))
    return scale_u, length, scale_u / length**2


def _end_limits(chain: Chain, slots, max_extension: float | None) -> tuple[np.ndarray, np.ndarray]:
    """Largest |a| and |b| (m) per slot: the link's length for an end on its link (a < 0 on
    link i >= 2, b > 0 on link j), else the bracket limit ``max_extension`` (default the
    longest link; see :func:`springlab.model.chain.check_attachments`)."""
    reach = max_extension if max_extension is not None else max(chain.r)
    lim_a = np.array([chain.length(s.i) if (s.i >= 2 and s.sa < 0) else reach for s in slots], dtype=float)
    lim_b = np.array([chain.length(s.j) if s.sb > 0 else reach for s in slots], dtype=float)
    return lim_a, lim_b


STALL_ITERATIONS = 300
"""A start of :func:`find_design` whose least-squares cost has not halved over this many
iterations is abandoned for the next start (it would run to its 2,000 evaluations without
converging: on the example arms and the family n = 3..8, 273 starts, every start that
converged did so with no such plateau, and the abandoned ones spend a third of the time)."""


def _stop_when_stalled():
    """A least-squares callback that stops a start whose cost has not halved over
    :data:`STALL_ITERATIONS` iterations (scipy passes ``intermediate_result`` by that name)."""
    costs: list[float] = []

    def stalled(intermediate_result):
        costs.append(intermediate_result.cost)
        if len(costs) > STALL_ITERATIONS and costs[-1] > 0.5 * costs[-1 - STALL_ITERATIONS]:
            raise StopIteration

    return stalled


def find_design(chain: Chain, slots, *, seed=0, restarts: int = 30, tol: float = 1e-13,
                within_links: bool = True, max_extension: float | None = None,
                max_stiffness: float | None = None, start=None, deadline: float | None = None) -> tuple[Spring, ...]:
    """A balanced design of the configuration ``slots``, found numerically.

    Least squares over (log k, log|a|, log|b|) of every spring, with the signs
    of the slots' patterns, from random starts. Succeeds when every entry of
    000 Eqs. (39) is below ``tol`` times the largest G_1,j.

    :param within_links: keep every end on its link (see :func:`springlab.model.chain.check_attachments`)
        and every bracket (an end beyond a joint) no longer than ``max_extension``
        (m; default the longest link). ``False`` asks for the signs only.
    :param max_stiffness: largest k (N/m), or None
    :param start: springs to start from (first), before the random starts
    :param deadline: a ``time.time()`` value (s; the wall clock, the same in every process of an
        executor) after which no further start begins; None: no limit
    :raises SearchExhaustedError: when no start converges (not a proof: more ``restarts``
        may find one; :func:`relaxation_margin` <= 0 is the proof that none exists)
    """
    _checks.instance("chain", chain, Chain)
    slots = _slots_on(chain, slots)
    restarts = _checks.count("restarts", restarts)
    tol = _checks.positive("tol", tol)
    max_extension = _checks.optional_positive("max_extension", max_extension, "m")
    max_stiffness = _checks.optional_positive("max_stiffness", max_stiffness, "N/m", allow_inf=True)
    rng = _checks.rng("seed", seed)
    scale_u, length, scale_k = _scales(chain)
    signs = np.array([(s.sa, s.sb) for s in slots], dtype=float)
    keys = _residual_entries(chain, slots)
    upper = np.full(3 * len(slots), 20.0)
    if max_stiffness is not None:
        upper[0::3] = np.log(max_stiffness / scale_k)
    if within_links:
        reach = max_extension if max_extension is not None else max(chain.r)
        lim_a, lim_b = _end_limits(chain, slots, reach)
        upper[1::3], upper[2::3] = np.log(lim_a / length), np.log(lim_b / length)
    lower = np.full_like(upper, -20.0)

    def springs_of(z):
        z = z.reshape(-1, 3)
        k = scale_k * np.exp(z[:, 0])
        a = signs[:, 0] * length * np.exp(z[:, 1])
        b = signs[:, 1] * length * np.exp(z[:, 2])
        return [Spring(s.i, s.j, float(ai), float(bi), float(ki)) for s, ai, bi, ki in zip(slots, a, b, k, strict=True)]

    M, g_keys = _linear_system(chain, slots, keys)
    M, g_keys = M / scale_u, g_keys / scale_u
    m = len(slots)

    def values(z):  # (P, A, B, k) per spring, SI units
        z = z.reshape(-1, 3)
        k = scale_k * np.exp(z[:, 0])
        A = signs[:, 0] * length * np.exp(z[:, 1]) * k
        B = signs[:, 1] * length * np.exp(z[:, 2]) * k
        P = signs[:, 0] * signs[:, 1] * length**2 * np.exp(z[:, 1] + z[:, 2]) * k
        return np.stack([P, A, B, k], axis=1).ravel()

    def residual(z):  # 000 Eqs. (39), linear in (P, A, B, k)
        with np.errstate(over="ignore", invalid="ignore"):  # a wild step: least squares backs off
            return M @ values(z) + g_keys

    # d v / d z: every value scales with k (z_0); P and A with |a| (z_1); P and B with |b| (z_2)
    uses = np.zeros((4 * m, 3 * m))
    for s_idx in range(m):
        base, col = 4 * s_idx, 3 * s_idx
        uses[base:base + 4, col] = 1.0
        uses[[base, base + 1], col + 1] = 1.0
        uses[[base, base + 2], col + 2] = 1.0

    def jacobian(z):
        with np.errstate(over="ignore", invalid="ignore"):
            return M @ (values(z)[:, None] * uses)

    best = None
    starts = []
    if start is not None:
        start = list(start)
        if len(start) != len(slots):
            raise SpringlabError(f"start has {len(start)} springs for {len(slots)} slots")
        z_start = np.array([[np.log(sp_.k / scale_k), np.log(abs(sp_.a) / length), np.log(abs(sp_.b) / length)]
                            for sp_ in start]).ravel()
        starts.append(np.clip(z_start, lower, upper))
    deadline = None if deadline is None else _checks.finite("deadline", deadline, "s")
    for idx in range(restarts + len(starts)):
        if deadline is not None and idx and time.time() > deadline:
            raise SearchExhaustedError(f"the time limit was reached after {idx} of {restarts + len(starts)} starts "
                                       f"for {' '.join(map(str, slots))}: give the search more time")
        z0 = starts[idx] if idx < len(starts) else np.minimum(rng.uniform(-1.5, 0.5, size=3 * len(slots)), upper - 0.05)
        try:
            with np.errstate(over="ignore", invalid="ignore"):  # a wild trial step: the method backs off
                sol = least_squares(residual, z0, jac=jacobian, method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                                    bounds=(lower, upper), max_nfev=2000, callback=_stop_when_stalled())
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
    best_text = f"best relative residual {best[0]:.3g}" if best else "no start could be evaluated"
    raise SearchExhaustedError(
        f"no balanced design found for {' '.join(map(str, slots))} after {restarts} random starts "
        f"({best_text}; limits: max_extension = {reach if within_links else 'none'} m, "
        f"max_stiffness = {max_stiffness if max_stiffness is not None else 'none'} N/m): "
        "raise restarts or the limits to search further")


def _slots_on(chain: Chain, slots) -> list[SpringSlot]:
    """``slots`` as a non-empty list of :class:`SpringSlot`, each within the chain."""
    if isinstance(slots, str | SpringSlot) or not hasattr(slots, "__iter__"):
        raise SpringlabError(f"slots must be a list of springs such as ['S(1,3)(+,+)'], got {slots!r}")
    slots = as_slots(slots)
    if not slots:
        raise SpringlabError("slots is empty: give the configuration's springs, e.g. ['S(1,2)(+,+)']")
    for s in slots:
        if s.j > chain.n:
            raise SpringlabError(f"{s} attaches to link {s.j}, but the chain has {chain.n} links")
    return slots


def longest_stretch(chain: Chain, spring: Spring) -> float:
    """The longest a spring can get over every pose of an arm whose links turn freely:
    |a| + sum_{i<t<j} r_t + |b| (m), all its segments in line (the ground link's x_1
    is fixed, the others can line up with it). ``k`` times this bounds its force."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    (spring,) = check_springs(chain, [spring])
    return abs(spring.a) + sum(chain.length(t) for t in range(spring.i + 1, spring.j)) + abs(spring.b)


def largest_force_bound(chain: Chain, springs) -> float:
    """The largest of the springs' force bounds k * :func:`longest_stretch` (N)."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    springs = check_springs(chain, springs)
    if not springs:
        return 0.0
    return max(s.k * longest_stretch(chain, s) for s in springs)


def minimise_largest_force(chain: Chain, slots, springs, *, max_extension: float | None = None,
                           max_stiffness: float | None = None, tol: float = 1e-12, rounds: int = 3) -> tuple[Spring, ...]:
    """Spend a configuration's free choices on the smallest largest spring force: up to
    ``rounds`` rounds of ``_force_round``, each from the last one's polished design,
    while a round gains more than 1 %. See ``_force_round`` for the formulation."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    slots = _slots_on(chain, slots)
    springs = check_springs(chain, springs)
    springs = tuple(springs)
    best = largest_force_bound(chain, springs)
    for _ in range(max(1, int(rounds))):
        out = _force_round(chain, slots, springs, max_extension=max_extension, max_stiffness=max_stiffness, tol=tol)
        force = largest_force_bound(chain, out)
        if not force < best:
            break
        gain, best, springs = 1 - force / best, force, out
        if gain < 0.01:
            break
    return springs


def _force_round(chain: Chain, slots, springs, *, max_extension: float | None = None,
                 max_stiffness: float | None = None, tol: float = 1e-12) -> tuple[Spring, ...]:
    """Spend a configuration's free choices on the smallest largest spring force.

    A spring's force over the workspace is at most k (|a| + R + |b|) =
    |A| + R k + |B| (N) with A = k a, B = k b (:func:`longest_stretch`), and 000 Eqs. (39)
    are linear in P = k a b, A, B and k: only P k = A B per spring is not. So the
    problem is a linear programme but for one bilinear equation per spring: minimise t
    subject to 000 Eqs. (39), |A| + R k + |B| <= t, the slots' signs, the attachment limits
    of :func:`find_design` (|A| <= reach k, linear too) and k <= ``max_stiffness``
    (N/m) if given, and P k = A B. Solved by scipy's SLSQP from the balanced design
    ``springs``, then polished by least squares until 000 Eqs. (39) hold to ``tol`` of the
    largest G_1,j. Returns the input unchanged when that does not improve on it.
    """
    from scipy.optimize import minimize

    slots = as_slots(slots)
    springs = tuple(springs)
    if len(springs) != len(slots):
        raise SpringlabError(f"{len(springs)} springs for {len(slots)} slots")
    scale_u, length, scale_k = _scales(chain)
    reach = max_extension if max_extension is not None else max(chain.r)
    keys = _residual_entries(chain, slots)
    m = len(slots)
    # unknowns, scaled: x = [P / scale_u, A / (scale_k L), B / (scale_k L), k / scale_k] per spring, then t
    M, g_keys = _linear_system(chain, slots, keys)
    units = np.tile([scale_u, scale_k * length, scale_k * length, scale_k], m)
    A_eq = np.hstack([M * units / scale_u, np.zeros((len(keys), 1))])
    b_eq = -g_keys / scale_u
    # 000 Eqs. (39) repeat themselves (springs spanning the same joints give proportional rows):
    # keep independent combinations, or SLSQP's subproblem is singular
    U, S, Vt = np.linalg.svd(A_eq, full_matrices=False)
    rank = int(np.sum(S > 1e-10 * S[0]))
    A_eq, b_eq = S[:rank, None] * Vt[:rank], U[:, :rank].T @ b_eq
    sa = np.array([s.sa for s in slots], dtype=float)
    sb = np.array([s.sb for s in slots], dtype=float)
    R = np.array([sum(chain.length(t) for t in range(s.i + 1, s.j)) for s in slots]) / length
    reach_a, reach_b = (lim / length for lim in _end_limits(chain, slots, reach))

    def parts(x):
        y = x[:-1].reshape(m, 4)
        return y[:, 0], y[:, 1], y[:, 2], y[:, 3]

    def inequalities(x):
        P, A, B, K = parts(x)
        return np.concatenate([x[-1] - (sa * A + R * K + sb * B),  # force <= t
                               reach_a * K - sa * A, reach_b * K - sb * B])  # |a| and |b| within reach

    def bilinear(x):
        P, A, B, K = parts(x)
        return P * K - A * B

    def bilinear_jac(x):
        P, A, B, K = parts(x)
        J = np.zeros((m, 4 * m + 1))
        idx = np.arange(m)
        J[idx, 4 * idx], J[idx, 4 * idx + 1], J[idx, 4 * idx + 2], J[idx, 4 * idx + 3] = K, -B, -A, P
        return J

    idx = np.arange(m)
    ineq_jac = np.zeros((3 * m, 4 * m + 1))  # constant: the inequalities are linear
    ineq_jac[idx, -1] = 1.0
    ineq_jac[idx, 4 * idx + 1], ineq_jac[idx, 4 * idx + 2], ineq_jac[idx, 4 * idx + 3] = -sa, -sb, -R
    ineq_jac[m + idx, 4 * idx + 3], ineq_jac[m + idx, 4 * idx + 1] = reach_a, -sa
    ineq_jac[2 * m + idx, 4 * idx + 3], ineq_jac[2 * m + idx, 4 * idx + 2] = reach_b, -sb

    x0 = np.concatenate([np.array([[s.k * s.a * s.b / scale_u, s.k * s.a / (scale_k * length),
                                    s.k * s.b / (scale_k * length), s.k / scale_k] for s in springs]).ravel(), [0.0]])
    x0[-1] = float(np.max(sa * x0[1:-1:4] + R * x0[3:-1:4] + sb * x0[2:-1:4]))
    start = x0[-1]
    tiny = 1e-9
    kmax = np.inf if max_stiffness is None else max_stiffness / scale_k
    bounds = []
    for a_sign, b_sign in zip(sa, sb, strict=True):
        bounds += [(tiny, None) if a_sign * b_sign > 0 else (None, -tiny),
                   (tiny, None) if a_sign > 0 else (None, -tiny),
                   (tiny, None) if b_sign > 0 else (None, -tiny), (tiny, kmax)]
    bounds.append((0.0, None))
    res = minimize(lambda x: x[-1], x0, method="SLSQP", jac=lambda x: np.r_[np.zeros(len(x) - 1), 1.0],
                   constraints=[{"type": "eq", "fun": lambda x: A_eq @ x - b_eq, "jac": lambda x: A_eq},
                                {"type": "eq", "fun": bilinear, "jac": bilinear_jac},
                                {"type": "ineq", "fun": inequalities, "jac": lambda x: ineq_jac}],
                   bounds=bounds, options={"maxiter": 500, "ftol": 1e-12})
    P, A, B, K = parts(res.x)
    if not (np.all(np.isfinite(res.x)) and np.all(K > 0) and res.x[-1] < start):
        return springs
    candidate = _springs_from_linear(slots, A, B, K, scale_k, length)
    # polish the balance (SLSQP meets its constraints to about 1e-8): Newton steps at the optimum first,
    # then, where they do not hold the limits, least squares in log(k), log|a|, log|b|
    out = _polish_newton(chain, slots, res.x[:-1], bounds[:-1], M * units / scale_u, g_keys / scale_u, scale_k,
                         length, reach, max_stiffness, tol, scale_u, (reach_a, reach_b, sa, sb))
    if out is None:
        try:
            out = find_design(chain, slots, start=candidate, restarts=0, tol=tol, max_extension=reach,
                              max_stiffness=max_stiffness)
        except (UnbalanceableError, SearchExhaustedError):
            out = None
    if out is None or largest_force_bound(chain, out) > 1.01 * largest_force_bound(chain, candidate):
        # the search in log(k), log|a|, log|b| can leave the optimum's neighbourhood (seen with one
        # BLAS thread): polish in the linear unknowns instead, from the optimum, in its sign boxes
        out = _polish_linear(chain, slots, res.x[:-1], bounds[:-1], M * units / scale_u, g_keys / scale_u,
                             scale_k, length, reach, max_stiffness, tol, scale_u)
        if out is None:
            return springs
    force = largest_force_bound(chain, out) / (scale_k * length)
    return out if force < start else springs


def _polish_newton(chain, slots, x0, bounds, M, g, scale_k, length, reach, max_stiffness, tol, scale_u, limits):
    """Newton steps from the force optimum x0 (scaled P, A, B, k per spring) onto 000 Eqs. (39)
    with P = A B / k, moving only the unknowns off their bounds and keeping the attachment limits
    active at x0 (|a| = reach there stays so): the minimum-norm step, a few times. Springs balanced
    to ``tol`` within the limits, or None (the caller then polishes by least squares)."""
    reach_a, reach_b, sa, sb = limits
    m = len(slots)
    y = np.array(x0, dtype=float).reshape(m, 4)
    lo = np.array([-np.inf if b[0] is None else b[0] for b in bounds]).reshape(m, 4)
    hi = np.array([np.inf if b[1] is None else b[1] for b in bounds]).reshape(m, 4)
    free = np.ones((m, 3), dtype=bool)  # A, B, k
    for c, col in enumerate((1, 2, 3)):
        gap = np.minimum(np.abs(y[:, col] - lo[:, col]), np.abs(hi[:, col] - y[:, col]))
        free[:, c] = gap > 1e-7 * np.maximum(1.0, np.abs(y[:, col]))
    at_reach = [(idx, r, s_, c) for idx in range(m) for r, s_, c in ((reach_a[idx], sa[idx], 1), (reach_b[idx], sb[idx], 2))
                if abs(r * y[idx, 3] - s_ * y[idx, c]) <= 1e-7 * max(1.0, abs(y[idx, 3]))]
    abk = y[:, 1:].copy()
    for _ in range(8):
        A, B, K = abk.T
        P = A * B / K
        v = np.stack([P, A, B, K], axis=1).ravel()
        rows = [M @ v + g] + [np.array([r * abk[idx, 2] - s_ * abk[idx, c - 1]]) for idx, r, s_, c in at_reach]
        F = np.concatenate(rows)
        if np.max(np.abs(F)) <= 0.01 * tol:
            break
        dv = np.zeros((4 * m, 3 * m))  # d(P, A, B, k) / d(A, B, k)
        for idx in range(m):
            dv[4 * idx, 3 * idx:3 * idx + 3] = B[idx] / K[idx], A[idx] / K[idx], -P[idx] / K[idx]
            dv[4 * idx + 1, 3 * idx] = dv[4 * idx + 2, 3 * idx + 1] = dv[4 * idx + 3, 3 * idx + 2] = 1.0
        J = [M @ dv]
        for idx, r, s_, c in at_reach:
            row = np.zeros(3 * m)
            row[3 * idx + 2], row[3 * idx + c - 1] = r, -s_
            J.append(row[None])
        J = np.vstack(J)[:, free.ravel()]
        step = np.zeros(3 * m)
        step[free.ravel()] = np.linalg.lstsq(J, -F, rcond=None)[0]
        abk = abk + step.reshape(m, 3)
    A, B, K = abk.T
    if not (np.all(np.isfinite(abk)) and np.all(K > 0) and np.all(np.sign(A) == sa) and np.all(np.sign(B) == sb)):
        return None
    springs = _springs_from_linear(slots, A, B, K, scale_k, length)
    return _balanced_within_limits(chain, springs, M, g, scale_u, scale_k, length, reach, max_stiffness, tol)


def _polish_linear(chain, slots, x0, bounds, M, g, scale_k, length, reach, max_stiffness, tol, scale_u):
    """Least squares on 000 Eqs. (39) (M x + g = 0, scaled) and P k = A B, from x0 within the sign
    boxes ``bounds``: springs balanced to ``tol`` of the largest G_1,j within the limits, or None."""
    from scipy.optimize import least_squares

    m = len(slots)
    lo = np.array([-np.inf if b[0] is None else b[0] for b in bounds])
    hi = np.array([np.inf if b[1] is None else b[1] for b in bounds])

    def residual(x):
        y = x.reshape(m, 4)
        return np.concatenate([M @ x + g, y[:, 0] * y[:, 3] - y[:, 1] * y[:, 2]])

    sol = least_squares(residual, np.clip(x0, lo, hi), bounds=(lo, hi), xtol=1e-15, ftol=1e-15, gtol=1e-15,
                        max_nfev=2000)
    y = sol.x.reshape(m, 4)
    springs = _springs_from_linear(slots, y[:, 1], y[:, 2], y[:, 3], scale_k, length)
    return _balanced_within_limits(chain, springs, M, g, scale_u, scale_k, length, reach, max_stiffness, tol)


def _balanced_within_limits(chain, springs, M, g, scale_u, scale_k, length, reach, max_stiffness, tol):
    """``springs`` if they satisfy 000 Eqs. (39) (M x + g = 0, scaled) to ``tol`` with k within
    ``max_stiffness`` and every end within its link or ``reach``, else None."""
    if np.max(np.abs(M @ _linear_values(springs, scale_u, scale_k, length) + g)) > tol:
        return None
    if max_stiffness is not None and max(s.k for s in springs) > max_stiffness * (1 + 1e-9):
        return None
    try:
        check_attachments(chain, springs, max_extension=reach * (1 + 1e-9))
    except SpringlabError:
        return None
    return springs


def _springs_from_linear(slots, A, B, K, scale_k, length) -> tuple[Spring, ...]:
    """Springs from the scaled A = k a, B = k b and k of ``_force_round``: a = A / k, b = B / k (m)."""
    k = np.asarray(K) * scale_k
    return tuple(Spring(s.i, s.j, float(a * scale_k * length / kk), float(b * scale_k * length / kk), float(kk))
                 for s, a, b, kk in zip(slots, A, B, k, strict=True))


def _linear_values(springs, scale_u, scale_k, length) -> np.ndarray:
    """(P, A, B, k) per spring in the scaled units of ``_force_round``."""
    return np.array([[s.k * s.a * s.b / scale_u, s.k * s.a / (scale_k * length), s.k * s.b / (scale_k * length),
                      s.k / scale_k] for s in springs]).ravel()


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
    """Largest margin t such that 000 Eqs. (39), written linearly in P = k a b,
    A = k a, B = k b and k of each spring, hold with every quantity carrying
    its pattern's sign by at least t (in units of max G). Drops only the
    coupling P k = A B, which binds only for springs spanning 3 or more links,
    so t <= 0 proves the configuration infeasible."""
    _checks.instance("chain", chain, Chain)
    slots = _slots_on(chain, slots)
    G = gravity_entries(chain.r, chain.d, chain.m, chain.g)
    scale = max(abs(v) for v in G.values())
    keys = _residual_entries(chain, slots)
    row = {key: idx for idx, key in enumerate(keys)}
    columns, col_signs = [], []
    for s, cols in zip(slots, linear_columns(chain, slots), strict=True):
        # A and B enter only for springs spanning 2 or more links, k for 3 or more
        for name, sign in (("P", s.sa * s.sb), ("A", s.sa), ("B", s.sb), ("K", 1)):
            if cols[name]:
                columns.append(cols[name])
                col_signs.append(sign)
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
        raise SolverError(f"linear programme failed: {res.message}")
    return float(res.x[-1])


def term_signs(chain: Chain, slots) -> tuple[list[tuple[int, int]], np.ndarray, np.ndarray]:
    """The signs of the terms each spring puts into the entries of 000 Eqs. (39), every quantity
    of its pattern's sign (P = k a b, A = k a, B = k b and k, 000 Eqs. 23a-d): (keys, pos, neg),
    keys every entry (u, v), u < v, in order, and pos, neg (len(slots), len(keys)) bool: the
    spring puts a positive (a negative) term there."""
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    slots = _slots_on(chain, slots)
    keys = [(u, v) for u in range(1, chain.n + 1) for v in range(u + 1, chain.n + 1)]
    column = {key: c for c, key in enumerate(keys)}
    pos = np.zeros((len(slots), len(keys)), dtype=bool)
    neg = np.zeros_like(pos)
    for row, (s, cols) in enumerate(zip(slots, linear_columns(chain, slots), strict=True)):
        for name, sign in (("P", s.sa * s.sb), ("A", s.sa), ("B", s.sb), ("K", 1)):
            for key, coef in cols[name].items():
                (pos if sign * coef > 0 else neg)[row, column[key]] = True
    return keys, pos, neg


def sign_consistent(chain: Chain, configurations) -> np.ndarray:
    """For each configuration (a sequence of slots), False when the signs alone refute the
    linear relaxation of 000 Eqs. (39): some entry (i, j) needs a term of a sign that no
    spring of the configuration brings. True says nothing (:func:`relaxation_margin` decides).

    With every quantity strictly of its pattern's sign (P = k a b, A = k a, B = k b and k,
    000 Eqs. 23a-d), each term an entry receives has a fixed sign. An entry (1, j) with
    G_1,j > 0 must receive a negative term (G + sum = 0, 000 Eqs. 39a); an entry with
    G = 0 that receives a term must receive terms of both signs (000 Eq. 39b). A False is
    therefore a proof, exact, with no solver tolerance; it costs a few array operations for
    thousands of configurations, where a linear programme costs about 1.5 ms each.

    :returns: (len(configurations),) bool
    """
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    configurations = [tuple(as_slots(cfg)) for cfg in configurations]
    if not configurations:
        return np.zeros(0, dtype=bool)
    kinds = sorted({s for cfg in configurations for s in cfg})
    index = {s: k for k, s in enumerate(kinds)}
    if kinds:
        keys, pos, neg = term_signs(chain, kinds)
    else:  # only empty configurations
        keys = [(u, v) for u in range(1, chain.n + 1) for v in range(u + 1, chain.n + 1)]
        pos = neg = np.zeros((0, len(keys)), dtype=bool)
    blank = np.zeros((1, len(keys)), dtype=bool)  # a last row for no spring, padding the shorter configurations
    pos, neg = np.vstack([pos, blank]), np.vstack([neg, blank])
    G = gravity_entries(chain.r, chain.d, chain.m, chain.g)
    b = np.array([-G.get(key, 0.0) for key in keys])  # 000 Eqs. (39a-b): the springs' sum must equal -G
    width = max(len(cfg) for cfg in configurations)
    idx = np.full((len(configurations), width), len(kinds))
    for row, cfg in enumerate(configurations):
        idx[row, :len(cfg)] = [index[s] for s in cfg]
    has_pos, has_neg = pos[idx].any(axis=1), neg[idx].any(axis=1)
    ok = np.where(b < 0, has_neg, np.where(b > 0, has_pos, has_pos == has_neg))
    return ok.all(axis=1)


def feasibility(chain: Chain, slots, *, seed=0, restarts: int = 30) -> Feasibility:
    """The plain criterion: do 000 Eqs. (39) have a solution with k > 0 and the signs
    of the slots' patterns, for this arm? See :class:`Feasibility`."""
    slots = as_slots(slots)
    margin = relaxation_margin(chain, slots)
    if margin <= 1e-9:
        return Feasibility("infeasible", margin)
    try:
        springs = find_design(chain, slots, seed=seed, restarts=restarts, within_links=False)
    except SearchExhaustedError:
        return Feasibility("unknown", margin)
    return Feasibility("feasible", margin, springs)


def candidate_slots(n: int) -> list[SpringSlot]:
    """Every spring slot the attachment criteria allow on an n-link arm: ground
    springs (+,+) (and S(1,2) (-,-)), non-ground springs (+,+), (-,-), (+,-)."""
    n = _checks.links(n, "n")
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


def balanced_core(chain: Chain, *, rel: float = 1e-13) -> Chain | None:
    """The chain the springs must balance.

    G_{1,j} (000 Eq. 18) is positive for every link j < n (masses are positive), but
    G_{1,n} = g m_n d_n vanishes when the end link's centre of mass is on its proximal
    joint (d_n = 0, or G_{1,n} below ``rel`` times the arm's energy scale g (sum m) (sum r)). Gravity then does not
    depend on x_n, and link n needs no spring: the core is the chain of links 2..n-1 with
    link n's mass moved to link n-1's distal joint, which has the same G_{1,j}, j < n. A
    design for the core, with no spring on link n, balances the whole arm (000 Eq. 39 has
    no (1, n) entry to offset). Returns ``chain`` itself when G_{1,n} > 0, and None for
    a one-link arm with d_2 = 0 (its centre of mass is on the base joint: balanced
    without springs).
    """
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")
    G = gravity_entries(chain.r, chain.d, chain.m, chain.g)  # 000 Eq. (18)
    if abs(G[(1, chain.n)]) > rel * chain.g * sum(chain.m) * sum(chain.r):  # vs the arm's energy scale (J)
        return chain
    if chain.n == 2:
        return None
    m_prev, m_end = chain.m[-2], chain.m[-1]
    merged = m_prev + m_end
    d_prev = (m_prev * chain.d[-2] + m_end * chain.r[-2]) / merged
    joints = chain.joints[:-1] if chain.joints else ()
    return Chain(chain.r[:-1], chain.d[:-2] + (d_prev,), chain.m[:-2] + (merged,), chain.g, joints)


def design_for(chain: Chain, *, seed=0, restarts: int = 30):
    """Springs that balance ``chain``: the first configuration from the enumerator
    (rules R1-R6) that the plain criterion confirms, with a design found for it. An end
    link whose centre of mass is on its proximal joint gets no spring (:func:`balanced_core`).

    :param restarts: random starts of :func:`find_design` per configuration (integer >= 0)
    :returns: (configuration, springs); both empty when the arm needs no spring
    :raises UnbalanceableError: when the linear relaxation refutes every enumerated
        configuration (a proof, for the configurations of 000's rules)
    :raises SearchExhaustedError: when some configuration was not refuted but its search
        found no design within ``restarts`` starts
    """
    _checks.instance("chain", chain, Chain, "springlab Chain (serial_chain(r, d, m))")

    restarts = _checks.count("restarts", restarts, least=0)
    core = balanced_core(chain)
    if core is None:
        return (), ()
    exhausted = 0
    for cfg in iter_configurations(core.n):
        if relaxation_margin(core, cfg) <= 1e-9:
            continue
        try:
            return cfg, find_design(core, cfg, seed=seed, restarts=restarts)
        except (SearchExhaustedError, AttachmentError):
            exhausted += 1
    if not exhausted:
        raise UnbalanceableError(
            f"no configuration of 000's rules R1-R6 balances this {chain.n}-link arm: the linear relaxation "
            "of 000 Eqs. (39) has no solution with the stated signs for any of them (a proof)")
    raise SearchExhaustedError(
        f"{exhausted} configuration(s) the linear relaxation allows, but no design found within "
        f"restarts = {restarts} random starts each (seed {seed}): raise restarts (this is not a proof "
        "that the arm cannot be balanced)")
