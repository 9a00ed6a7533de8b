"""The best springs where exact balance is out of reach: attachment points within each body's box and
rates that minimise the largest holding torque over the workspace (:func:`best_springs`: a greedy
choice of springs, each set polished by sequential linear programmes on route 2's torques towards the
smallest maximum, :func:`minimax`), and the compass search over poses (:func:`compass_search`) that
the audit and the layouts climb with.

Every comparison is made to 9 significant digits (:func:`sig`) and every step lands on a grid
(:data:`END_GRID`, :data:`RATE_DIGITS`), so round-off, which differs from one CPU to another, decides
none of the search's choices.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.design.highs import solve
from springlab.design.structure import Structure, attachment_boxes
from springlab.energy.geometry import gravity_torques, joint_torques
from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain
from springlab.model.springs import PointSpring
from springlab.rounding import significant

MAX_STIFFNESS = 2000.0
"""N/m: the stiffest spring the best-springs search uses by default. Stocked music wire up to 6.5 mm
winds extension springs of a few kN/m with three body coils or more; a stiffer one (the search's
least-squares fit asks for 5-50 kN/m on a short lever when unbounded) is no spring a shop stocks."""


END_GRID = 1e-6
"""m: every point the search's polish steps to has its spring ends rounded to this grid (the boxes'
faces moved inwards onto it, ``faces``), its rates to :data:`RATE_DIGITS` significant digits (a
shop works to tenths of a millimetre). Its later steps and
choices then see the same numbers on every CPU: each step is a linear programme's vertex, which
round-off of 1e-16 in the torques moves by far less than the grid."""


RATE_DIGITS = 7
"""Significant digits of a searched spring's rate (N/m)."""


PULL = 1e-5
"""The polish's L1 pull towards where it started, per unit of each variable's scale (the rate cap, the
box's half-size): it makes the minimum sharp, hence isolated, where moving an end changes no torque."""


def sig(value, digits: int = 9) -> float:
    """``value`` to ``digits`` significant digits (:func:`springlab.rounding.significant`): a key that
    round-off (1e-16) does not move, so that the search's comparisons, and its ties, come out the same
    on every CPU.

    :raises SpringlabError: for a value that is not a finite number
    """
    if type(value) not in _FLOATS:  # the search's own values are floats: checked the quick way
        value = _checks.finite("value", value)
    elif not math.isfinite(value):
        raise SpringlabError(f"value must be finite, got {value!r}")
    return significant(value, digits)


_FLOATS = (float, np.float64)


def _on_grid(x, lo, hi) -> np.ndarray:
    """Springs packed as the search packs them (k, p_a, p_b per spring) rounded: rates to
    :data:`RATE_DIGITS` significant digits, ends to :data:`END_GRID`, kept within [lo, hi]."""
    x = np.array(x, dtype=float)
    for s in range(len(x) // 7):
        x[7 * s] = sig(x[7 * s], RATE_DIGITS)
        x[7 * s + 1:7 * s + 7] = np.round(x[7 * s + 1:7 * s + 7] / END_GRID) * END_GRID
    return np.clip(x, lo, hi)


def minimax(x, lo, hi, scale, residual, jacobian, iterations: int, rows: float = 0.7, groups=None,
             spread: float = 0.0) -> np.ndarray:
    """min over x in [lo, hi] of max_g m_g + ``spread`` mean_g m_g + :data:`PULL` |(x - x0) / scale|_1 from
    x0 = ``x``, m_g the largest |residual(x)| of group g (``groups``: each residual's group, its joint;
    None: one group), by sequential linear programming (HiGHS), at most ``iterations`` programmes, every
    point it steps to put on the grid (``_on_grid``). ``jacobian(x, r)`` gives d residual / dx at x.

    The mean (``spread`` > 0) moves the search where the largest cannot move yet: each joint's own peak
    is its scale, so one spring lowers one joint's largest torque but not the largest of all.
    Each programme linearises the residuals within ``rows`` of their group's largest and bounds the step
    in a trust region of the scaled variables (x / scale), which grows after a step that did what it
    predicted and shrinks after one that did not. Its answers are vertices, points that round-off in the
    residuals hardly moves, and on the grid the next programme sees the same point, so the result is the
    same on every CPU; a group whose largest is round-off (below 1e-9 of the largest of all) has no
    rows, since which of them pass the threshold would be round-off's choice."""

    D = len(x)
    x0 = np.array(x, dtype=float)
    zlo, zhi = (lo - x0) / scale, (hi - x0) / scale
    r = residual(x0)
    groups = np.zeros(len(r), dtype=int) if groups is None else np.asarray(groups)
    G = int(groups.max()) + 1
    T = G if spread > 0 else 0  # the groups' own largest as columns, only where their mean counts
    cost = np.concatenate([np.full(2 * D, PULL), [1.0], np.full(T, spread / G)])

    def peaks(r):
        out = np.zeros(G)
        np.maximum.at(out, groups, np.abs(r))
        return out

    def merit(v, r):
        m = peaks(r)
        return float(np.max(m) + spread * np.mean(m)) + PULL * float(np.sum(np.abs((v - x0) / scale)))

    radius = 0.25
    x, f = x0, merit(x0, r)
    for _ in range(iterations):
        m = peaks(r)
        # a group whose largest is round-off (a vertical joint the springs do not load) has no rows: which
        # of its rows pass the threshold would be decided by round-off
        keep = (np.abs(r) >= rows * (m[groups] if spread > 0 else np.max(m))) & (m[groups] > 1e-9 * np.max(m))
        J = jacobian(x, r)[keep] * scale  # per scaled unit
        e = (x - x0) / scale
        Je, rk, M = J @ e, r[keep], int(np.count_nonzero(keep))
        # columns z+ (D), z- (D), t, t_g (T), with z = z+ - z- = (x_new - x0) / scale;
        # rows |r + J (z - e)| <= t_g (its group's), t_g <= t; without the groups' columns, <= t
        if T:
            own = np.zeros((M, T))
            own[np.arange(M), groups[keep]] = -1.0
            A = np.block([[J, -J, np.zeros((M, 1)), own], [-J, J, np.zeros((M, 1)), own],
                          [np.zeros((T, 2 * D)), -np.ones((T, 1)), np.eye(T)]])
        else:
            A = np.block([[J, -J, -np.ones((M, 1))], [-J, J, -np.ones((M, 1))]])
        zl, zh = np.maximum(e - radius, zlo), np.minimum(e + radius, zhi)
        col_lo = np.concatenate([np.where(zl >= 0, zl, 0.0), np.where(zh <= 0, -zh, 0.0), np.zeros(1 + T)])
        col_up = np.concatenate([np.where(zh <= 0, 0.0, zh), np.where(zl >= 0, 0.0, -zl), np.full(1 + T, np.inf)])
        out = solve(cost, A, np.full(2 * M + T, -np.inf), np.concatenate([Je - rk, rk - Je, np.zeros(T)]),
                    col_lo, col_up)
        if out is None:
            break
        z = out[0][:D] - out[0][D:2 * D]
        predicted = f - float(cost @ out[0])
        if predicted <= 1e-14 * max(f, 1e-300):
            break
        xn = _on_grid(x0 + scale * z, lo, hi)  # every point on the grid: round-off does not carry on
        if np.array_equal(xn, x):  # the step rounds to the point it left: nothing moves on the grid
            break
        try:
            rn = residual(xn)
        except SpringlabError:  # a step out of what the model allows (a cable through its pulley)
            rn = None
        fn = merit(xn, rn) if rn is not None else np.inf
        if f - fn >= 0.1 * predicted:
            if f - fn >= 0.75 * predicted and np.max(np.abs(z - e)) >= 0.99 * radius:
                radius = min(2 * radius, 1.0)
            x, f, r = xn, fn, rn
        else:
            radius *= 0.25
            if radius < 1e-12:
                break
    return _on_grid(x, lo, hi)


def variable_scales(lo, hi, k_max, x) -> np.ndarray:
    """Each packed variable's scale for :func:`minimax`: a rate's cap (else its size, at least 1 N/m),
    an end's box half-size."""
    scale = np.where(hi - lo > 0, 0.5 * (hi - lo), 1.0)
    for s in range(len(x) // 7):
        scale[7 * s] = k_max if np.isfinite(k_max) else max(abs(x[7 * s]), 1.0)
    return scale


def _features(model: RevoluteChain, pairs, q) -> np.ndarray:
    """Route 2's holding torques of a unit-rate zero-free-length spring on each pair of bodies, split
    by its attachment points: (pairs, 16, N, n) for [1, p_a (3), p_b (3), p_a p_b^T (9)]. The torque of
    k between p_a and p_b is exactly k (F0 + Fa p_a + Fb p_b + sum_ij p_a,i p_b,j Fab_ij): the
    spring's squared length is affine in each end and bilinear across, its |p|^2 terms constant."""
    e = np.eye(3)
    out = np.empty((len(pairs), 16) + q.shape)
    for idx, (a, b) in enumerate(pairs):
        def tau(pa, pb, a=a, b=b):
            return joint_torques(model, [PointSpring(model.bodies[a], pa, model.bodies[b], pb, 1.0)], q,
                                 gravity=False)
        F0 = tau(np.zeros(3), np.zeros(3))
        Ta = [tau(e[i], np.zeros(3)) for i in range(3)]
        Tb = [tau(np.zeros(3), e[j]) for j in range(3)]
        out[idx, 0] = F0
        for i in range(3):
            out[idx, 1 + i] = Ta[i] - F0
            out[idx, 4 + i] = Tb[i] - F0
            for j in range(3):
                out[idx, 7 + 3 * i + j] = tau(e[i], e[j]) - Ta[i] - Tb[j] + F0
    return out


@dataclass(frozen=True)
class BestSprings:
    """What :func:`best_springs` found.

    :ivar springs: the zero-free-length springs (m, N/m)
    :ivar ratio: the largest holding torque over the sample poses, per joint as a fraction of its scale
        (its own peak gravity torque, or a tenth of the arm's largest where that is more)
    :ivar target: the ratio asked for
    :ivar note: how the count was chosen
    """

    springs: tuple
    ratio: float
    target: float
    note: str


def _grid(centre, half) -> np.ndarray:
    """The candidate ends in a body's box (its centre and per-axis half-sizes): its centre and its
    eight corners, (9, 3) m."""
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    return np.vstack([centre, centre + half * corners])


def best_springs(model: RevoluteChain, found: Structure, q, *, target: float = 0.1, reach: float | None = None,
                 max_springs: int = 8, iterations: int = 200, candidates: int = 4,
                 max_stiffness: float = MAX_STIFFNESS) -> BestSprings:
    """The fewest zero-free-length springs, ends within each body's box (``attachment_boxes``), that bring the
    largest holding torque over the poses ``q`` within ``target`` of every joint's scale
    s_i = max(its peak gravity torque, a tenth of the largest), or as close as ``max_springs`` springs
    get: min over springs of max_{pose, joint} |tau| / s_i (a joint gravity leaves alone is held to a
    tenth of the largest too: the springs must not load it). Rates stay at most ``max_stiffness``
    (N/m; default :data:`MAX_STIFFNESS`, what stocked wire winds with room to spare).

    Greedy, then polished. Each step ranks the candidate springs (between grid points of two bodies'
    boxes, ``_grid``, any pair of bodies up to the last loaded one) by how much they reduce the
    remaining torques in a least-squares sense weighted towards the largest (an 8-norm's weights);
    adds, in turn, the best candidate of each of the ``candidates`` best pairs; moves every spring's
    ends within their boxes and changes the rates to lower the largest torque plus the mean of the
    joints' largest (``_polish``: at most ``iterations`` linear programmes, every point on
    :data:`END_GRID`); and keeps the best of those trials (the largest torque, then that mean). The
    mean moves the search while the largest cannot move yet: every heavy joint starts at its own
    scale, and one spring lowers one joint's peak, not all of them. Where that search misses the
    target, the search is run again polishing the largest torque alone, and the better of the two is
    kept (of the 42 arms of example-robot-data only the Z1 misses it, and there the first stays the
    better). Springs the target then does without are dropped (``_pruned``). Scores and trials are
    compared to 9 significant digits, ties going to the lower candidate or pair index, so that
    round-off (which differs from one CPU to another) decides nothing. ``q`` should hold several
    times more poses than the springs have parameters (7 each): the torques are fitted at those poses
    only.
    """
    from threadpoolctl import threadpool_limits

    q = model.check_q(q)
    target = _checks.positive("target", target)
    max_stiffness = _checks.positive("max_stiffness", max_stiffness, unit="N/m")
    with threadpool_limits(limits=1, user_api="blas"):  # small matrices: one thread is faster
        return _best_springs(model, found, q, target, reach, max_springs, iterations, candidates, max_stiffness)


def _best_springs(model, found, q, target, reach, max_springs, iterations, candidates, max_stiffness) -> BestSprings:
    max_springs = _checks.count("max_springs", max_springs, least=1)
    candidates = _checks.count("candidates", candidates, least=1)
    iterations = _checks.count("iterations", iterations, least=1)
    loaded = list(found.loaded)
    if not loaded:
        return BestSprings((), 0.0, target, "nothing to balance")
    last = max(loaded) + 1  # the last loaded joint's body
    first = min(loaded) + 1
    pairs = [(a, b) for b in range(first, last + 1) for a in range(0, b)]
    centres, half = attachment_boxes(model, reach)
    tau_g = gravity_torques(model, q)
    scale = _joint_scales(tau_g)
    F = _features(model, pairs, q) / scale  # (P, 16, N, n)
    g = tau_g / scale
    N, n = g.shape
    cols, ends = [], []
    for idx, (a, b) in enumerate(pairs):
        f = F[idx]
        for pa in _grid(centres[a], half[a]):
            for pb in _grid(centres[b], half[b]):
                cols.append(_unit_torque(f, pa, pb).reshape(-1))
                ends.append((idx, pa, pb))
    A = np.array(cols).T  # (N n, C): each candidate's torques at unit rate

    def greedy(spread):
        """The greedy search, each polish's objective the largest torque plus ``spread`` times the mean of
        the joints' largest: (the fewest springs within the target, else the best step) as (ratio, x,
        which), and the ratio after each step."""
        return _greedy(A, ends, F, g, N, n, target, max_springs, candidates, centres, half, pairs, iterations,
                       max_stiffness, spread)

    (ratio, x, which), history = greedy(1.0)
    how = "each polish lowering the largest torque and the mean of the joints' largest"
    if ratio > target:  # the other objective may find another path
        (ratio2, x2, which2), history2 = greedy(0.0)
        if (ratio2 <= target, -len(which2) if ratio2 <= target else -sig(ratio2)) > (False, -sig(ratio)):
            (ratio, x, which), history = (ratio2, x2, which2), history2
            how = "each polish lowering the largest torque alone, which went further than also lowering their mean"
    dropped = 0
    if ratio <= target and which:  # springs the target does without, added before the last ones: dropped
        ratio, x, which, dropped = _pruned(x, which, F, g, N, n, target)
    steps = ("after each spring the greedy search added, the share of the worst joint's scale removed: "
             + ", ".join(f"{k + 1} spring{'s' if k else ''} {100 * (1 - h):.1f} %" for k, h in enumerate(history)))
    if not history:
        note = f"no spring: gravity alone stays within {target:g} of every joint's scale"
    elif ratio <= target:
        note = (f"{len(which)} springs, the fewest the greedy search ({how}) needed to hold every joint within "
                f"{target:g} of its scale ({steps}"
                + (f"; {dropped} of the springs it added then dropped, the target holding without them)" if dropped
                   else ")"))
    else:
        note = (f"the target ({target:g} of each joint's scale) was not reached with max_springs = {max_springs} "
                f"springs ({steps}; {how}): the search stopped there; larger reaches (--reach) may do better, or "
                "more springs (the library's best_springs(max_springs=...))")
    out = tuple(PointSpring(model.bodies[pairs[p][0]], tuple(x[7 * s + 1:7 * s + 4]), model.bodies[pairs[p][1]],
                            tuple(x[7 * s + 4:7 * s + 7]), float(x[7 * s])) for s, p in enumerate(which) if x[7 * s] > 0)
    return BestSprings(out, float(ratio), target, note)


def _pruned(x, which, F, g, N, n, target):
    """Springs within ``target`` made fewer: while some spring can go with the largest torque staying within
    the target, the one whose removal leaves the least goes (a spring the greedy search added early can
    be one the later ones made idle). Returns (ratio, x, which, how many went)."""
    dropped = 0
    ratio = float(np.max(np.abs(_residual(x, which, F, g, N, n))))
    while which:
        best = None
        for s in range(len(which)):
            keep = [i for i in range(len(which)) if i != s]
            xs = np.concatenate([x[7 * i:7 * i + 7] for i in keep]) if keep else np.zeros(0)
            value = float(np.max(np.abs(_residual(xs, [which[i] for i in keep], F, g, N, n))))
            if value <= target and (best is None or sig(value) < sig(best[0])):
                best = (value, xs, [which[i] for i in keep])
        if best is None:
            break
        (ratio, x, which), dropped = best, dropped + 1
    return ratio, x, which, dropped


def _greedy(A, ends, F, g, N, n, target, max_springs, candidates, centres, half, pairs, iterations, max_stiffness,
            spread):
    """:func:`best_springs`'s greedy search from no springs (``A``: each candidate's torques at unit rate,
    ``ends``: its pair and ends): ((ratio, x, which) of the fewest springs within ``target``, else of
    the best step; the ratio after each step)."""
    x, which = np.zeros(0), []
    ratio = float(np.max(np.abs(g)))
    history, snapshots = [], []
    while len(which) < max_springs and ratio > target:
        r = _residual(x, which, F, g, N, n).reshape(-1)
        weight = (np.abs(r) / np.max(np.abs(r))) ** 6  # the worst poses and joints count most (an 8-norm's weights)
        gain = -(A.T @ (weight * r))
        norms = np.einsum("rc,r,rc->c", A, weight, A)
        score = np.where(gain > 0, gain**2 / np.maximum(norms, 1e-300), 0.0)
        tried, trials = set(), []
        top = float(np.max(score))
        key = np.round(score / top * 1e9) if top > 0 else np.zeros_like(score)
        order = np.lexsort((np.arange(len(score)), -key))  # by score to 1e-9 of the best, then by index
        for c in order:  # the best candidate of each of the `candidates` best pairs, each polished
            if score[c] <= 0 or len(tried) == candidates:
                break
            idx, pa, pb = ends[c]
            if idx in tried:
                continue
            tried.add(idx)
            trial = np.concatenate([x, [sig(min(gain[c] / norms[c], max_stiffness)), *pa, *pb]])
            trial, value = _polish(trial, which + [idx], F, g, N, n, centres, half, pairs, iterations, max_stiffness,
                                   spread)
            left = _residual(trial, which + [idx], F, g, N, n)  # the mean of the joints' largest, else the squares
            second = np.mean(np.max(np.abs(left), axis=0)) if spread > 0 else np.sum(left**2)
            trials.append((value, float(second), trial, idx))
        if not trials:
            break
        ratio, _, x, idx = min(trials, key=lambda t: (sig(t[0]), sig(t[1]), t[3]))  # ties to the lower pair index
        which = which + [idx]
        history.append(ratio)
        snapshots.append((ratio, x.copy(), list(which)))
    if snapshots:  # the fewest springs within the target, else the best step
        within = [snap for snap in snapshots if snap[0] <= target]
        ratio, x, which = within[0] if within else min(snapshots, key=lambda snap: sig(snap[0]))
    return (ratio, x, which), history


def _unit_torque(f, pa, pb) -> np.ndarray:
    """The torques of a unit-rate spring between ``pa`` and ``pb`` from its pair's features ``f``
    (:func:`_features`): F0 + Fa p_a + Fb p_b + sum_ij p_a,i p_b,j Fab_ij."""
    return (f[0] + np.tensordot(pa, f[1:4], 1) + np.tensordot(pb, f[4:7], 1)
            + np.tensordot(np.outer(pa, pb).reshape(-1), f[7:], 1))


def _spring_torque(x, s, which, F):
    k, pa, pb = x[7 * s], x[7 * s + 1:7 * s + 4], x[7 * s + 4:7 * s + 7]
    return k * _unit_torque(F[which[s]], pa, pb)


def _residual(x, which, F, g, N, L):
    total = g.reshape(N, L).copy()
    for s in range(len(which)):
        total += _spring_torque(x, s, which, F)
    return total


def _jacobian(x, which, F, N, L) -> np.ndarray:
    """d torques / d (k, p_a, p_b) of every spring, (N L, 7 S)."""
    S = len(which)
    J = np.empty((N * L, 7 * S))
    for s in range(S):
        k, pa, pb = x[7 * s], x[7 * s + 1:7 * s + 4], x[7 * s + 4:7 * s + 7]
        f = F[which[s]]
        fab = f[7:].reshape(3, 3, N, L)
        fa = f[1:4] + np.tensordot(pb, fab, axes=([0], [1]))  # d/d pa_i (per unit rate)
        fb = f[4:7] + np.tensordot(pa, fab, axes=([0], [0]))  # d/d pb_j
        J[:, 7 * s] = _unit_torque(f, pa, pb).reshape(-1)
        J[:, 7 * s + 1:7 * s + 4] = k * fa.reshape(3, -1).T
        J[:, 7 * s + 4:7 * s + 7] = k * fb.reshape(3, -1).T
    return J


def _bounds(x, which, centres, half, pairs, k_max=np.inf):
    """The packed springs' bounds: rates in [0, k_max], ends in their bodies' boxes, the faces on the grid."""
    lo, hi = np.empty_like(x), np.empty_like(x)
    for s in range(len(which)):
        a, b = pairs[which[s]]
        lo[7 * s], hi[7 * s] = 0.0, k_max
        for body, off in ((a, 1), (b, 4)):
            lo[7 * s + off:7 * s + off + 3], hi[7 * s + off:7 * s + off + 3] = faces(centres[body], half[body])
    return lo, hi


def faces(centre, half) -> tuple[np.ndarray, np.ndarray]:
    """A box's lower and upper faces (m) moved inwards onto :data:`END_GRID`: an end the polish puts on a
    face is then on the grid too, whatever round-off the outline's coordinates carry."""
    return np.ceil((centre - half) / END_GRID) * END_GRID, np.floor((centre + half) / END_GRID) * END_GRID


def _polish(x, which, F, g, N, L, centres, half, pairs, iterations, k_max=np.inf, spread=0.0):
    """The largest torque (already divided by the joints' scales), plus ``spread`` times the mean of the
    joints' largest, brought down with every spring's rate and ends free in their boxes
    (:func:`minimax`, the exact bilinear Jacobian :func:`_jacobian`), the springs on :data:`END_GRID`.
    Returns (x, the largest torque)."""

    def residual(v):
        return _residual(v, which, F, g, N, L).reshape(-1)

    if not which:
        return x, float(np.max(np.abs(residual(x))))
    lo, hi = _bounds(x, which, centres, half, pairs, k_max)
    x = np.clip(x, lo, hi)
    x = minimax(x, lo, hi, variable_scales(lo, hi, k_max, x), residual, lambda v, r: _jacobian(v, which, F, N, L),
                 iterations, groups=np.tile(np.arange(L), N), spread=spread)
    return x, float(np.max(np.abs(residual(x))))


def _joint_scales(tau_g) -> np.ndarray:
    """Each joint's scale (N m) for the best springs' search, from the gravity torques ``tau_g`` (N, n):
    the larger of its own peak and a tenth of the arm's largest (a light joint, or one gravity leaves
    alone, is held to a tenth of the largest: the springs must not load it beyond that)."""
    peak = np.max(np.abs(tau_g), axis=0)
    return np.maximum(peak, 0.1 * np.max(peak))


COMPASS_STEPS = (0.05, 1e-5)
"""rad: the compass search's first and last step (:class:`~springlab.design.audit.Audit`'s climb); the peaks it refines are then found to
about the square of the last step times the torque's curvature, below the tables' printed digits."""


def compass_searches(value, starts, lo, hi, max_steps: int = 400, enough: float = np.inf,
                     allowed=None) -> tuple[np.ndarray, np.ndarray]:
    """Several compass searches in lockstep, one from each pose of ``starts`` (S, n) rad, each exactly
    :func:`compass_search`'s: ``value`` is a function of trial poses (A, M, n) and of the indices (A,) of the
    searches they belong to, returning (A, M) values, so that one call evaluates a step of every search still
    running; ``allowed`` (a function of poses (M, n) -> (M,) bool) is asked once a step for every better trial
    of them all. Returns the poses (S, n) and their values (S,)."""
    X = np.array(starts, dtype=float)
    S, n = X.shape
    best = np.asarray(value(X[:, None, :], np.arange(S)), dtype=float)[:, 0].copy()
    step, taken = np.full(S, COMPASS_STEPS[0]), np.zeros(S, dtype=int)
    moves = np.vstack([np.eye(n), -np.eye(n)])
    while True:
        running = np.flatnonzero((taken < max_steps) & (step >= COMPASS_STEPS[1]) & ~(best >= enough))
        if not len(running):
            return X, best
        trials = np.clip(X[running][:, None, :] + step[running][:, None, None] * moves[None], lo, hi)
        values = np.asarray(value(trials, running), dtype=float)
        better = []
        for a, s in enumerate(running):  # the trials whose key beats the current one's, best first (ties: first)
            finite = np.isfinite(values[a])
            if np.isfinite(best[s]):  # sig is monotonic: only a trial above the current value can beat its key
                floor = sig(best[s])
                finite &= values[a] > best[s]
            else:
                floor = -np.inf
            near = np.flatnonzero(finite)
            keys = [sig(v) for v in values[a, near]]
            better.append([int(near[k]) for k in np.argsort([-v for v in keys], kind="stable") if keys[k] > floor])
        if allowed is not None:
            asked = [(a, k) for a, ks in enumerate(better) for k in ks]
            ok = dict(zip(asked, allowed(np.array([trials[a, k] for a, k in asked]).reshape(-1, n)) if asked else (),
                          strict=True))
            better = [[k for k in ks if ok[a, k]][:1] for a, ks in enumerate(better)]
        for a, s in enumerate(running):
            if better[a]:
                X[s], best[s] = trials[a, better[a][0]], float(values[a, better[a][0]])
            else:
                step[s] /= 2
            taken[s] += 1


def compass_search(value, start, lo, hi, max_steps: int = 400, enough: float = np.inf,
                   allowed=None) -> tuple[np.ndarray, float]:
    """A compass search for the largest ``value`` (a function of poses (M, n) rad, nan where undefined)
    near the pose ``start`` within the bounds [lo, hi] (rad): each step tries +- the step on every joint
    (one call of 2n poses) and moves to the best trial where it beats the current pose (compared to 9
    significant digits, ties to the first, so that round-off decides nothing), else halves the step,
    from :data:`COMPASS_STEPS`' first to its last, or until the value reaches ``enough``. With ``allowed`` (a
    function of poses (M, n) -> (M,) bool) it moves to the best better trial that is allowed. Returns the
    pose and its value. (:func:`compass_searches` runs several at once.)"""
    X, best = compass_searches(lambda trials, _: np.stack([value(t) for t in trials]), np.asarray(start)[None], lo,
                               hi, max_steps=max_steps, enough=enough, allowed=allowed)
    return X[0], float(best[0])
