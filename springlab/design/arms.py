"""Springs for a real arm: the general model (:class:`~springlab.model.revolute.RevoluteChain`, read
from a URDF's own frames), its structure with proof, exact balance where the structure allows
it and the best springs elsewhere.

**Structure** (:func:`~springlab.design.structure.structure`, in :mod:`springlab.design.structure`):
which joints gravity loads, with proof, and whether the loaded joints form a **planar chain**.

**Exact balance of a planar chain** (:func:`~springlab.design.structure.planar_springs`): one
zero-free-length spring per pair of planar links at most, every one solvable
(:mod:`springlab.design.structure` derives it).

**Best springs elsewhere** (:func:`best_springs`): attachment points within each body's reach
and rates that minimise the largest holding torque over the workspace (a greedy choice of springs,
each set polished by sequential linear programmes on route 2's torques towards the smallest maximum).
The search compares to 9 significant digits and keeps its springs on a grid (:data:`END_GRID`), so
round-off, which differs from one CPU to another, decides none of its choices.

**Pseudobases** (``layout='belts'`` and ``'pseudobases'``, :mod:`springlab.design.layouts`,
:mod:`springlab.design.pseudobases`): paper 001's one spring per link's subsystem, its post on a frame a belt
or RSSR modules carry (001 Eqs. 5, 13-16).

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

import numpy as np

from springlab import _checks
from springlab.design.structure import (
    BRACKET,
    NEGLIGIBLE,
    Structure,
    attachment_boxes,
    planar_springs,
    structure,
)
from springlab.energy.geometry import gravity_torques, joint_torques
from springlab.errors import GeometryError, SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, check_point_springs
from springlab.model.springs import PointSpring
from springlab.rounding import significant
from springlab.tables import Table

MAX_STIFFNESS = 2000.0
"""N/m: the stiffest spring the best-springs search uses by default. Stocked music wire up to 6.5 mm
winds extension springs of a few kN/m with three body coils or more; a stiffer one (the search's
least-squares fit asks for 5-50 kN/m on a short lever when unbounded) is no spring a shop stocks."""






END_GRID = 1e-6
"""m: every point the search's polish steps to has its spring ends rounded to this grid (the boxes'
faces moved inwards onto it, ``_faces``), its rates to :data:`RATE_DIGITS` significant digits (a
shop works to tenths of a millimetre). Its later steps and
choices then see the same numbers on every CPU: each step is a linear programme's vertex, which
round-off of 1e-16 in the torques moves by far less than the grid."""

RATE_DIGITS = 7
"""Significant digits of a searched spring's rate (N/m)."""

PULL = 1e-5
"""The polish's L1 pull towards where it started, per unit of each variable's scale (the rate cap, the
box's half-size): it makes the minimum sharp, hence isolated, where moving an end changes no torque."""


def _sig(value, digits: int = 9) -> float:
    """``value`` to ``digits`` significant digits (:func:`springlab.rounding.significant`): a key that
    round-off (1e-16) does not move, so that the search's comparisons, and its ties, come out the same
    on every CPU."""
    return significant(value, digits)


def _on_grid(x, lo, hi) -> np.ndarray:
    """Springs packed as the search packs them (k, p_a, p_b per spring) rounded: rates to
    :data:`RATE_DIGITS` significant digits, ends to :data:`END_GRID`, kept within [lo, hi]."""
    x = np.array(x, dtype=float)
    for s in range(len(x) // 7):
        x[7 * s] = _sig(x[7 * s], RATE_DIGITS)
        x[7 * s + 1:7 * s + 7] = np.round(x[7 * s + 1:7 * s + 7] / END_GRID) * END_GRID
    return np.clip(x, lo, hi)


def _minimax(x, lo, hi, scale, residual, jacobian, iterations: int, rows: float = 0.7, groups=None,
             spread: float = 0.0) -> np.ndarray:
    """min over x in [lo, hi] of max_g m_g + ``spread`` mean_g m_g + :data:`PULL` |(x - x0) / scale|_1 from
    x0 = ``x``, m_g the largest |residual(x)| of group g (``groups``: each residual's group, its joint;
    None: one group), by sequential linear programming (HiGHS), at most ``iterations`` programmes, every
    point it steps to put on the grid (:func:`_on_grid`). ``jacobian(x, r)`` gives d residual / dx at x.

    The mean (``spread`` > 0) moves the search where the largest cannot move yet: each joint's own peak
    is its scale, so one spring lowers one joint's largest torque but not the largest of all.
    Each programme linearises the residuals within ``rows`` of their group's largest and bounds the step
    in a trust region of the scaled variables (x / scale), which grows after a step that did what it
    predicted and shrinks after one that did not. Its answers are vertices, points that round-off in the
    residuals hardly moves, and on the grid the next programme sees the same point, so the result is the
    same on every CPU; a group whose largest is round-off (below 1e-9 of the largest of all) has no
    rows, since which of them pass the threshold would be round-off's choice."""
    from springlab.design.highs import solve

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


def _scales(lo, hi, k_max, x) -> np.ndarray:
    """Each packed variable's scale for :func:`_minimax`: a rate's cap (else its size, at least 1 N/m),
    an end's box half-size."""
    scale = np.where(hi - lo > 0, 0.5 * (hi - lo), 1.0)
    for s in range(len(x) // 7):
        scale[7 * s] = k_max if np.isfinite(k_max) else max(abs(x[7 * s]), 1.0)
    return scale


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

    from springlab.energy.geometry import spring_lines

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
        if (ratio2 <= target, -len(which2) if ratio2 <= target else -_sig(ratio2)) > (False, -_sig(ratio)):
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
            if value <= target and (best is None or _sig(value) < _sig(best[0])):
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
            trial = np.concatenate([x, [_sig(min(gain[c] / norms[c], max_stiffness)), *pa, *pb]])
            trial, value = _polish(trial, which + [idx], F, g, N, n, centres, half, pairs, iterations, max_stiffness,
                                   spread)
            left = _residual(trial, which + [idx], F, g, N, n)  # the mean of the joints' largest, else the squares
            second = np.mean(np.max(np.abs(left), axis=0)) if spread > 0 else np.sum(left**2)
            trials.append((value, float(second), trial, idx))
        if not trials:
            break
        ratio, _, x, idx = min(trials, key=lambda t: (_sig(t[0]), _sig(t[1]), t[3]))  # ties to the lower pair index
        which = which + [idx]
        history.append(ratio)
        snapshots.append((ratio, x.copy(), list(which)))
    if snapshots:  # the fewest springs within the target, else the best step
        within = [snap for snap in snapshots if snap[0] <= target]
        ratio, x, which = within[0] if within else min(snapshots, key=lambda snap: _sig(snap[0]))
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
            lo[7 * s + off:7 * s + off + 3], hi[7 * s + off:7 * s + off + 3] = _faces(centres[body], half[body])
    return lo, hi


def _faces(centre, half) -> tuple[np.ndarray, np.ndarray]:
    """A box's lower and upper faces (m) moved inwards onto :data:`END_GRID`: an end the polish puts on a
    face is then on the grid too, whatever round-off the outline's coordinates carry."""
    return np.ceil((centre - half) / END_GRID) * END_GRID, np.floor((centre + half) / END_GRID) * END_GRID


def _polish(x, which, F, g, N, L, centres, half, pairs, iterations, k_max=np.inf, spread=0.0):
    """The largest torque (already divided by the joints' scales), plus ``spread`` times the mean of the
    joints' largest, brought down with every spring's rate and ends free in their boxes
    (:func:`_minimax`, the exact bilinear Jacobian :func:`_jacobian`), the springs on :data:`END_GRID`.
    Returns (x, the largest torque)."""

    def residual(v):
        return _residual(v, which, F, g, N, L).reshape(-1)

    if not which:
        return x, float(np.max(np.abs(residual(x))))
    lo, hi = _bounds(x, which, centres, half, pairs, k_max)
    x = np.clip(x, lo, hi)
    x = _minimax(x, lo, hi, _scales(lo, hi, k_max, x), residual, lambda v, r: _jacobian(v, which, F, N, L),
                 iterations, groups=np.tile(np.arange(L), N), spread=spread)
    return x, float(np.max(np.abs(residual(x))))


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
        poses, then the worst poses an independent denser sample found (:class:`Audit`)
    :ivar notes: what was assumed and found
    :ivar origins: per realised spring, the index of the ideal spring it realises (a spring too strong
        for one wire is realised by two or three side by side)
    :ivar changes: per realised spring, what the realisation changed of its ideal spring, and why
    :ivar audit: the independent sample the peaks were re-checked on (:class:`Audit`), or None
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
        mm = lambda p: "(" + ", ".join(f"{1e3 * v + 0.0:.1f}" for v in p) + ")"  # noqa: E731
        if which == "ideal":
            return Table(["spring", "link_a", "point_a (mm)", "link_b", "point_b (mm)", "k (N/m)"],
                         [(name, s.link_a, mm(s.point_a), s.link_b, mm(s.point_b), f"{s.k:.4g}")
                          for name, s in zip(self.names, self.ideal, strict=True)])
        rows = []
        for n, r, kind, (coil, *_) in zip(self.realised_names, self.realised, self.kinds, self.coils, strict=True):
            pulley = (f"{1e3 * r.pulley_radius:g}, lead ({', '.join(f'{v + 0.0:.2f}' for v in r.lead)})"
                      if r.pulley_radius > 0 else "")
            rows.append((n, r.link_a, mm(r.point_a), r.link_b, mm(r.point_b), f"{r.k:.4g}", kind, pulley,
                         f"{1e3 * coil.free_length:.1f}", f"{1e3 * coil.max_length:.1f}", f"{coil.initial_tension:.3g}",
                         f"{1e3 * coil.wire:.2g}"))
        return Table(["spring", "link_a", "point_a (mm)", "link_b", "point_b (mm)", "k (N/m)", "realised as",
                      "pulley (mm), lead", "coil free length (mm)", "coil longest (mm)", "initial tension (N)",
                      "wire (mm)"], rows)

    def sheet(self) -> Table:
        """The spec sheet a spring maker works from, one row per realised spring: where it goes (its ends,
        mm in their links' URDF frames), how it is realised, the coil
        (:data:`~springlab.design.buildable.COIL_COLUMNS`), the cable's offset L_0 - F_i / k, the pulley's
        radius and lead, and the maker's note (:func:`~springlab.design.buildable.maker_note`);
        :data:`~springlab.design.buildable.SHEET_NOTE` says what it is designed to."""
        from springlab.design.buildable import COIL_COLUMNS, coil_cells, maker_note

        mm = lambda p: "(" + ", ".join(f"{1e3 * v + 0.0:.1f}" for v in p) + ")"  # noqa: E731
        rows = []
        for n, r, kind, (coil, *_) in zip(self.realised_names, self.realised, self.kinds, self.coils, strict=True):
            cable = kind.startswith("cable")
            rows.append((n, f"{r.link_a} {mm(r.point_a)}", f"{r.link_b} {mm(r.point_b)}", kind, *coil_cells(coil),
                         f"{1e3 * (coil.free_length - r.free_length):.1f}" if cable else "",
                         f"{1e3 * r.pulley_radius:g}" if r.pulley_radius > 0 else "",
                         "(" + ", ".join(f"{v + 0.0:.2f}" for v in r.lead) + ")" if r.pulley_radius > 0 else "",
                         maker_note(coil)))
        return Table(["spring", "end A: link (mm)", "end B: link (mm)", "realisation", *COIL_COLUMNS,
                      "cable offset L0 - Fi/k (mm)", "pulley radius (mm)", "lead (link_a frame)", "maker's note"], rows)

    def built(self, *, tension: float = 1.0, free_length: float = 1.0, stiffness: float = 1.0) -> tuple:
        """The realised springs as wound, each coil's initial tension, free length and rate multiplied by
        the factors (1: as specified; :data:`~springlab.design.buildable.TOLERANCES`). A cable's length
        stays as cut: its offset c = L_0 - F_i / k is kept, so the force along its path is
        F_i' + k' (path + c - L_0'); over a pulley block of ratio n the coil moves path / n and the cable
        pulls (F_i' + k' (path / n + c - L_0')) / n, a spring of rate k' / n^2, initial tension F_i' / n and
        free length n (L_0' - c) along the path."""
        out = []
        for r, (coil, _, ratio, _) in zip(self.realised, self.coils, strict=True):
            offset = coil.free_length - r.free_length / ratio  # the cable's offset; 0 for a zero-length spring
            k = r.k * _checks.positive("stiffness", stiffness)
            L0 = ratio * (coil.free_length * _checks.positive("free_length", free_length) - offset)
            Fi = r.initial_tension * _checks.positive("tension", tension)
            fields = {"free_length": L0, "initial_tension": Fi} if L0 >= 0 else {"free_length": 0.0,
                                                                                  "initial_tension": Fi - k * L0}
            out.append(_with(r, k=k, **fields))
        return tuple(out)

    def tolerance_table(self, tolerances: dict | None = None) -> Table:
        """The balance the built springs leave (route 2, the design's poses): per loaded joint, the
        percentage of its peak gravity torque removed, by the ideal springs, the realised ones as
        specified, and with each of the maker's tolerances (default
        :data:`~springlab.design.buildable.TOLERANCES`; each at most 0.5) at its + and - limit on every
        spring at once."""
        from springlab.design.buildable import check_tolerances

        tolerances = check_tolerances(tolerances)
        loaded = list(self.structure.loaded)
        peak = np.max(np.abs(gravity_torques(self.model, self.q)), axis=0)[loaded]

        def removed(springs):
            left = np.max(np.abs(joint_torques(self.model, springs, self.q)), axis=0)[loaded]
            return [f"{100 * (1 - v / p):.1f}" for v, p in zip(left, peak, strict=True)]

        rows = [("as designed (ideal springs)", *removed(self.ideal)), ("as specified", *removed(self.built()))]
        for name, value in tolerances.items():
            for sign in (1, -1):
                rows.append((f"{name.replace('_', ' ')} {'+' if sign > 0 else '-'}{100 * value:g} %",
                             *removed(self.built(**{name: 1 + sign * value}))))
        return Table(["built", *(f"{self.model.joints[i]} removed (%)" for i in loaded)], rows)

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
        leaving no less than their negative control (every rate times ``factor``), or any joint left with
        more holding torque by the ideal or the realised springs than by gravity alone (above round-off:
        1e-9 of the arm's largest gravity torque), a spring with no line of action or whose cable's end
        crosses its lead, a spring that does not clear the links."""
        out = []
        designed, control = self.control(factor)
        if self.ideal and _sig(control) <= _sig(designed):
            out.append(f"the springs leave {designed:.3g} N m at worst, no less than their negative control (every rate "
                       f"x {factor:g}) leaves, {control:.3g} N m: they do not balance this arm")
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
            out.append(f"the realised spring {spring}'s {piece} {depth} (at {np.round(np.degrees(self.q[pose]), 1).tolist()} "
                       "deg): it cannot be mounted as drawn")
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
        included) past what it was wound for and past its wire's allowable stress; a cable spring with no stocked cable for its pull, a
        cable pulled past its working load, a pulley smaller than its cable's D/d asks for, a coil longer
        in service than its link has between its pulley and its joint (it would reach past the joint)."""
        from springlab.design.hardware import HOOK_GAP

        out = []
        R, o = body_frames(self.model, self.q)
        for name, r, kind, fit in zip(self.realised_names, self.realised, self.kinds, self.coils, strict=True):
            try:
                longest = length_range(self.model, r, R, o)[1]
            except GeometryError:
                longest = float(fit.span[1])  # no line of action at some pose: flagged by the balance checks
            stretched = float(fit.coil_length(longest)) if kind.startswith("cable") else longest
            stress = float(fit.coil.stress(fit.coil.force(max(stretched, fit.coil.free_length))))
            if longest > fit.span[1] and stress > fit.coil.allowable_stress:
                out.append(f"the realised spring {name}'s coil is stretched to {1e3 * stretched:.1f} mm at a pose of the "
                           f"check, beyond the {1e3 * fit.coil.max_length:.1f} mm it was wound for: {stress / 1e6:.0f} MPa, "
                           f"above its wire's allowable {fit.coil.allowable_stress / 1e6:.0f} MPa")
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
            behind = r.pulley_radius + HOOK_GAP + (2 * (r.pulley_radius + fit.cable.diameter) if fit.ratio > 1 else 0.0)
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
        from springlab.design.layouts import SHARE

        names = [self.model.joints[i] for i in self.structure.loaded]
        removed = self.removed_by(self.realised) if self.realised else np.zeros(len(names))
        peak = np.asarray(self.structure.peak)
        light = [self.model.joints[i] for i in self.structure.loaded if peak[i] < SHARE * float(np.max(peak))]
        missed = [n for n, v in zip(names, removed, strict=True) if not v >= 100 * share - 1e-9 and n not in light]
        return {"share": share, "reached": not missed,
                "removed_percent": {n: float(v) for n, v in zip(names, removed, strict=True)}, "missed": missed,
                "light": light}

    def trade_off(self) -> Table:
        """The spring count against the share removed: from all the realised springs, the one (with any beside
        it, side by side) whose leaving out costs least is left out, in turn; per count, the percentage of
        each loaded joint's peak the rest remove (on the arm carrying only their hardware)."""
        from springlab.design.hardware import with_spring_mass

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

    def parts_table(self) -> Table:
        """Every part of the realised springs' hardware (:func:`springlab.design.hardware.parts`): its kind,
        the link it rides on, its mass (g), sizes (mm) and the largest loads over :attr:`q`."""
        from springlab.design.hardware import parts

        rows = []
        for p in parts(self.model, self.realised, self.kinds, self.coils, self.realised_names, self.q):
            size = ", ".join(f"{k.replace('_', ' ')} {1e3 * v:.3g}" if isinstance(v, float) else f"{k.replace('_', ' ')} {v}"
                             for k, v in p.size.items() if not k.endswith("_kg"))
            loads = ", ".join(f"{k.rsplit('_', 1)[0].replace('_', ' ')} {v:.3g} {k.rsplit('_', 1)[1]}"
                              if isinstance(v, float) else str(v) for k, v in p.loads.items() if k != "breaking_load_N")
            rows.append((p.name, p.kind, p.link, f"{1e3 * p.mass:.0f}", size, loads))
        return Table(["part", "kind", "rides on", "mass (g)", "sizes (mm)", "largest loads"], rows)

    def control(self, factor: float = 0.9) -> tuple[float, float]:
        """The negative control: the largest holding torque (N m, over joints and the workspace poses)
        of the ideal springs as designed and with every rate times ``factor``. A check that cannot
        fail checks nothing: the scaled springs must leave more."""
        scaled = [s.scaled(factor) for s in self.ideal]
        arm = self.designed_for
        return (float(np.max(np.abs(joint_torques(arm, self.ideal, self.q)))),
                float(np.max(np.abs(joint_torques(arm, scaled, self.q)))))

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
        from springlab.design.hardware import coil_ends, parts

        ends = coil_ends(self.model, self.realised, self.kinds, self.coils, self.q) if self.realised else []
        hardware = [{"mass_kg": fit.coil.mass, "coil_outer_diameter": fit.coil.outer_diameter, "block_ratio": fit.ratio,
                     "cable": None if fit.cable is None else fit.cable.as_dict()} | end
                    | ({"clearance_m": near[n][4], "nearest_link": near[n][2], "nearest_piece": near[n][1],
                        "nearest_pose": self.q[near[n][3]].tolist()} if n in near else {})
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
                    "clears": not self.clearance.failing()},
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
    if kind.startswith("cable over a pulley"):
        out["cable_offset"] = coil.cable_offset
    return out


def realise_springs(model: RevoluteChain, springs, q, *, material: str = "music wire", pulley_radius: float = 0.0,
                    reach=None, fit=None, max_stiffness: float = MAX_STIFFNESS) -> tuple[tuple, tuple, tuple]:
    """Each ideal spring as a helical extension spring from stocked wire (:mod:`springlab.design.buildable`):
    a zero-length spring (F_i = k L_0) where one can be wound, else a spring mounted on link_a whose
    cable runs over a pulley at end A to end B, cut so that the force is k times the cable's path.
    Returns the realised springs (free length L_0 and initial tension F_i as wound; a cable spring's
    free length is the cable's equivalent, F_i / k), their kinds and coils.

    With ``pulley_radius`` (m) > 0 the pulley is modelled (route 2's cable path,
    :func:`springlab.energy.geometry.cable_geometry`): it adds a pose-dependent energy of about
    k L rho alpha that no ideal spring had. So the cable springs are re-balanced on the poses ``fit``
    (default: ``q``'s first 150): each spring's lead (the direction its cable arrives from) is chosen
    among its body's axes and the mean direction to B, and, where that leaves more than
    :data:`REBALANCE` of a joint's scale (its own peak gravity torque, or for a light joint ten times what
    the ideal springs leave on it), their rates and ends (within
    :func:`~springlab.design.structure.attachment_boxes` with ``reach``, rates at most ``max_stiffness``) are moved to bring the
    largest holding torque down again (sequential linear programmes, as the best springs are polished).
    The zero-length springs stay as designed.

    A re-balanced spring whose rate falls below :data:`DROP_RATE` of its designed rate carries next to
    nothing and is left out (its kind says so, as for a spring no wire realises).

    :raises SpringlabError: naming the spring when neither realisation fits
    """
    return _realise(model, springs, q, material=material, pulley_radius=pulley_radius, reach=reach, fit=fit,
                    max_stiffness=max_stiffness)[:3]


def _realise(model: RevoluteChain, springs, q, *, material, pulley_radius, reach, fit, max_stiffness):
    """:func:`realise_springs`, with a fourth tuple: per realised spring, the index of the ideal
    spring it realises."""
    from springlab.design.buildable import Fitted, cable_spring, zero_length_spring
    from springlab.design.layouts import cable_for, coil_for

    q = model.check_q(q)
    pulley_radius = _checks.positive("pulley_radius", pulley_radius, allow_zero=True, unit="m")
    springs = check_point_springs(model, springs)
    R, o = body_frames(model, q)
    kinds = []
    for s in springs:
        lengths = length_range(model, s, R, o)
        coil, why = zero_length_spring(s.k, lengths, material)
        kinds.append(("zero-length spring", coil, lengths) if coil is not None else ("cable", None, why))
    cable = [i for i, (kind, _, _) in enumerate(kinds) if kind == "cable"]
    built = list(springs)
    if pulley_radius > 0:  # a cable whose ends come within the pulley's radius cannot run over it
        fit = q[:150] if fit is None else model.check_q(fit)
        Rf, of = body_frames(model, fit)
        near = [i for i in cable if min(length_range(model, springs[i], R, o)[0],
                                        length_range(model, springs[i], Rf, of)[0]) <= 2 * pulley_radius]
        cable = [i for i in cable if i not in near]
    else:
        near = []
    if pulley_radius > 0 and cable:
        fit = q[:150] if fit is None else model.check_q(fit)
        scale = _realised_scales(model, springs, fit)
        led = _leads(model, built, cable, fit, pulley_radius, scale, clear_q=q)
        built = led
        if max(_worst(model, led, fit, scale), _worst(model, led, q, scale)) > REBALANCE:  # the leads leave too much
            built = _rebalance(model, led, cable, fit, reach, max_stiffness, scale)
        def windable(spring):  # None: its cable comes within the pulley's radius of A at a pose of ``q``
            try:  # a stocked wire carries it alone or up to MAX_PARALLEL side by side, as the realisation winds it
                span = length_range(model, spring, R, o)
                return any(cable_spring(spring.k / m, span, material)[0] is not None for m in range(1, MAX_PARALLEL + 1))
            except GeometryError:
                return None

        built = list(built)
        swapped = []
        dense = _dense(model, q)
        for i in cable:  # a re-balanced spring no stocked wire carries, whose cable meets its pulley at a pose
            fits = windable(built[i])  # the fit did not see, or whose end now crosses its lead's line, keeps its
            crosses = built[i] is not led[i] and _lead_tier(_lead_clearance(model, built[i], dense)) == 2
            if fits is None or (not fits and windable(led[i])) or crosses:  # designed rate and ends
                built[i] = led[i]
                swapped.append(i)
        rest = [i for i in cable if i not in swapped]
        if swapped and rest and _worst(model, built, q, scale) > REBALANCE:  # the others re-balanced around them
            again = _rebalance(model, led, rest, fit, reach, max_stiffness, scale)  # from the leads, as the first
            if all(windable(again[i]) and _lead_tier(_lead_clearance(model, again[i], dense)) < 2 for i in rest):
                built = list(again)
        if swapped and _sig(_worst(model, built, fit, scale)) > _sig(_worst(model, led, fit, scale)):
            built = list(led)  # the others were re-balanced around the springs put back: the leads alone do better
    out, names, coils, origins = [], [], [], []
    for i, s in enumerate(built):
        kind, coil, detail = kinds[i]
        origins.append(i)
        if kind == "zero-length spring":
            out.append(PointSpring(s.link_a, s.point_a, s.link_b, s.point_b, s.k, coil.free_length, s.k * coil.free_length))
            names.append(kind)
            coils.append(Fitted(coil, detail))
            continue
        if s.k < DROP_RATE * springs[i].k:
            names.append(f"not realised: spring S{i + 1} ({s.label}): the re-balance over the pulleys took its rate "
                         f"from {springs[i].k:.4g} to {s.k:.3g} N/m ({100 * s.k / springs[i].k:.2g} % of it), so it "
                         "carries next to nothing")
            out.append(None)
            coils.append(None)
            continue
        lengths = length_range(model, s, R, o)
        room, block = coil_room(model, s, lengths)
        found = coil_for(s.k, lengths, room, material, block=block)  # side by side where one wire is too weak, over
        # a block where the coil would reach past its joint
        coil, why_cable = (found[0], found[1]) if found[0] is None else (found[0], "")  # where too long for its link
        ratio, parallel = (found[1], found[2]) if coil is not None else (1, 1)
        if coil is None:
            names.append(f"not realised: spring S{i + 1} ({s.label}, k = {s.k:.4g} N/m): no zero-length spring "
                         f"({detail}) and no cable spring ({why_cable}), nor {MAX_PARALLEL} side by side")
            out.append(None)
            coils.append(None)
            continue
        k = s.k / parallel
        try:  # the stocked cable that carries its pull (the flags say when the pulley is too small for it)
            rope = cable_for(k * lengths[1], s.pulley_radius)
        except SpringlabError:
            rope = None
        tension = coil.initial_tension / ratio  # along the cable: a block divides the coil's pull
        single = parallel > 1 and coil_for(s.k, lengths, np.inf, material)[0] is not None
        for m in range(parallel):
            if m:
                origins.append(i)
            out.append(PointSpring(s.link_a, s.point_a, s.link_b, s.point_b, k, tension / k,
                                   tension, s.pulley_radius, s.lead))
            names.append("cable over a pulley" + (f", with a {ratio}:1 pulley block" if ratio > 1 else "")
                         + (f" ({m + 1} of {parallel} side by side" + (", so that each coil fit its link)" if single
                                                                      else ")") if parallel > 1 else "")
                         + (" (a point pulley: its ends come within twice the pulley's radius)" if i in near else ""))
            coils.append(Fitted(coil, lengths, ratio, rope))
    return tuple(out), tuple(names), tuple(coils), tuple(origins)


def _sized_pulley(model: RevoluteChain, springs, q) -> float:
    """The two-point springs' one pulley radius (m), sized to the cable of the largest pull (N) any of them
    pulls over the poses ``q`` (:mod:`springlab.design.cables`: the rope maker's D/d); the strongest
    cable's where none carries it (the flags then say so)."""
    from springlab.design.cables import CABLES, choose_cable

    R, o = body_frames(model, q)
    pull = max((s.k * length_range(model, s, R, o)[1] for s in springs), default=0.0)
    try:
        return choose_cable(pull).pulley_radius
    except SpringlabError:
        return CABLES[-1].pulley_radius

CARRY_ROUNDS = 2
"""How many times the belt layout is designed again for the arm carrying the springs it found (their masses
change a little with their rates)."""

REBALANCE = 0.1
"""Where the realised springs over their pulleys, leads chosen, leave more than this fraction of a
joint's scale (its own peak gravity torque, or for a light joint ten times what the ideal springs leave
on it) on the fitting poses, their rates and ends are re-balanced too."""

DROP_RATE = 0.01
"""A cable spring the re-balance leaves with less than this fraction of its designed rate carries next to
nothing: the realisation leaves it out (the Z1's S7 went from 5.2 to 0.007 N/m, a 0.1 mm wire 8 m long)."""

REBALANCE_STEPS = 40
"""The most linear programmes the re-balance of the cable springs takes (each on a finite-difference
Jacobian, 7 route-2 evaluations per cable spring)."""

MAX_PARALLEL = 3
"""The most springs a realised spring is split into, side by side on the same ends, when no stocked
wire carries its force alone."""


def length_range(model: RevoluteChain, spring, R, o) -> tuple[float, float]:
    """The shortest and longest length (m) of a spring (its cable's path over a pulley) at the poses."""
    from springlab.energy.geometry import spring_lengths

    length = spring_lengths(model, [spring], R, o)[0]
    return max(float(length.min()), 1e-6), max(float(length.max()), 1e-6)


def _worst(model: RevoluteChain, springs, q, scale) -> float:
    return float(np.max(np.abs(joint_torques(model, springs, q)) / scale))


def _with(s, **changes) -> PointSpring:
    fields = {"link_a": s.link_a, "point_a": s.point_a, "link_b": s.link_b, "point_b": s.point_b, "k": s.k,
              "free_length": s.free_length, "initial_tension": s.initial_tension, "pulley_radius": s.pulley_radius,
              "lead": s.lead}
    return PointSpring(**(fields | changes))


LEAD_CLEAR = 0.1
"""rad: a cable spring's lead is chosen, where one can be, so that at every pose of the design's check B
stays at least this far in angle from the lead's line through A (:func:`lead_angles`): where B crosses
that line a swivelling pulley must turn half a turn at once and the cable's pull jumps (over 5 mm
pulleys the UR5's S2 passed within 1e-6 rad of its line, its elbow torque jumping by 4 N m)."""


LEAD_AXES = 2
"""How many of the directions that B keeps furthest from (``_clearest_axes``) join a cable spring's
candidate leads."""


def _clearest_axes(model: RevoluteChain, spring, q, count: int = LEAD_AXES, directions: int = 400) -> np.ndarray:
    """The ``count`` lines through A (unit vectors in body a's frame, (count, 3)) that the direction from A
    to the spring's end B keeps furthest from, in angle, over the poses ``q``: the best of ``directions``
    spread evenly over a hemisphere (a line and its opposite are one)."""
    d = _span(model, spring, *body_frames(model, q))
    d /= np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
    k = np.arange(directions) + 0.5  # a Fibonacci lattice on the upper hemisphere
    z, phi = k / directions, np.pi * (1 + 5 ** 0.5) * k
    U = np.column_stack([np.sqrt(1 - z**2) * np.cos(phi), np.sqrt(1 - z**2) * np.sin(phi), z])
    nearest = np.min(np.arccos(np.clip(np.abs(d @ U.T), 0.0, 1.0)), axis=0)
    keys = [-_sig(v) for v in nearest]
    return U[np.argsort(keys, kind="stable")[:count]]


def _lead_tier(clearance: float) -> int:
    """0: B keeps :data:`LEAD_CLEAR` from the lead's line; 1: it comes nearer, but not within
    :data:`CROSSING`; 2: it does (the audit flags a third of that: a margin, since it searches other poses)."""
    return 0 if clearance >= LEAD_CLEAR else 1 if clearance >= CROSSING else 2


LEAD_SAMPLES = 20_000
"""Random poses of the workspace's box (their own seed) on which a candidate lead's clearance is measured
(``_lead_clearance``): as many as the audit's, so that the two find the same near crossings."""


def _dense(model: RevoluteChain, q):
    """:data:`LEAD_SAMPLES` random poses within the box of the poses ``q`` (their own seed), with their body
    frames, and the box: what the leads' clearances are measured on."""
    lo, hi = np.min(q, axis=0), np.max(q, axis=0)
    dense = np.random.default_rng([LEAD_SAMPLES, model.n]).uniform(lo, hi, (LEAD_SAMPLES, model.n))
    return dense, body_frames(model, dense), lo, hi


def _nearest_approach(model: RevoluteChain, spring, q, lo, hi, frames=None, enough: float = 0.0):
    """The pose (rad) and angle (rad) where B comes nearest a cable spring's lead line
    (:func:`lead_angles`): the nearest of the poses ``q`` (``frames``: their body frames, where already
    computed), refined by :func:`compass_search` within [lo, hi] until the angle is below ``enough``."""
    angle = lead_angles(model, spring, q, frames)
    start = q[int(np.argmin(angle))]
    if angle.min() < enough:  # already near enough: no need to refine
        return start, float(angle.min())
    pose, value = compass_search(lambda t: -lead_angles(model, spring, t), start, lo, hi, enough=-enough)
    return pose, -value


def _lead_clearance(model: RevoluteChain, spring, dense) -> float:
    """rad: how near B comes to a cable spring's lead line over the poses of ``dense`` (:func:`_dense`),
    refined towards it (:func:`_nearest_approach`) until it is taken to cross (:data:`CROSSING`)."""
    q, frames, lo, hi = dense
    return _sig(_nearest_approach(model, spring, q, lo, hi, frames, enough=CROSSING)[1])


def _leads(model: RevoluteChain, springs, cable, q, radius: float, scale, clear_q=None) -> list:
    """Each cable spring over a pulley of ``radius`` (m), its lead (in link_a's frame) chosen, one
    spring at a time and twice over, among +-x, +-y, +-z of link_a, the direction from its joint to A
    and the mean direction from A to B and its opposite: whichever leaves the smallest largest
    holding torque (relative to each joint's ``scale``, N m) at the poses ``q``, among the leads
    whose line B keeps :data:`LEAD_CLEAR` from (:func:`_lead_clearance` over the poses ``clear_q``,
    default ``q``) where any does, else among those it does not cross (:func:`_lead_tier`); the
    candidates include the lines B keeps furthest from (:func:`_clearest_axes`)."""

    clear_q = q if clear_q is None else clear_q
    R, o = body_frames(model, q)
    out = list(springs)
    candidates = {}
    for i in cable:
        s = springs[i]
        pa = model.locate(s.link_a, s.point_a)[1]
        towards = np.sum(_span(model, s, R, o), axis=0)  # summed over the poses, in body a's frame
        own = np.asarray(model.locate(s.link_a, (0.0, 0.0, 0.0))[1])  # link_a's origin in body a's frame
        found = [*np.eye(3), *-np.eye(3), towards, -towards, np.asarray(pa) - own]
        rotation = model.rotation(s.link_a)  # link_a -> body
        found += list(_clearest_axes(model, s, clear_q))
        candidates[i] = [tuple(rotation.T @ (u / np.linalg.norm(u))) for u in found if np.linalg.norm(u) > 1e-9]
        out[i] = _with(s, pulley_radius=radius, lead=candidates[i][-1 - LEAD_AXES])  # link_a's origin to A, or -towards
    dense = _dense(model, clear_q)
    crosses = {i: [_lead_tier(_lead_clearance(model, _with(out[i], lead=u), dense)) for u in candidates[i]]
               for i in cable}
    for _ in range(2):
        for i in cable:
            trials = [(crosses[i][c], out[:i] + [_with(out[i], lead=u)] + out[i + 1:]) for c, u in enumerate(candidates[i])]
            out = min(trials, key=lambda t: (t[0], _sig(_worst(model, t[1], q, scale))))[1]  # ties to the first lead
    return out


def _rebalance(model: RevoluteChain, springs, cable, q, reach, max_stiffness, scale) -> list:
    """Move the cable springs' rates and ends (within :func:`~springlab.design.structure.attachment_boxes`) to bring the largest
    holding torque at the poses ``q``, relative to each joint's ``scale`` (N m), down
    (:func:`_minimax`, at most :data:`REBALANCE_STEPS` programmes on a finite-difference Jacobian).
    Kept only where it lowers the largest torque."""
    centres, half = attachment_boxes(model, reach)
    ends = {i: (model.locate(springs[i].link_a, springs[i].point_a), model.locate(springs[i].link_b, springs[i].point_b))
            for i in cable}
    x0, lo, hi = [], [], []
    for i in cable:
        (a, pa), (b, pb) = ends[i]
        (lo_a, hi_a), (lo_b, hi_b) = _faces(centres[a], half[a]), _faces(centres[b], half[b])
        x0 += [springs[i].k, *pa, *pb]
        lo += [0.0, *lo_a, *lo_b]
        hi += [max_stiffness, *hi_a, *hi_b]
    x0, lo, hi = (np.array(v, dtype=float) for v in (x0, lo, hi))
    lo, hi = np.minimum(lo, x0), np.maximum(hi, x0)  # the designed springs stay reachable
    x0 = np.clip(x0, lo, hi)
    leads = {i: tuple(model.direction(springs[i].link_a, springs[i].lead)[1]) for i in cable}  # in the bodies' frames

    def build(x):
        out = list(springs)
        for m, i in enumerate(cable):
            (a, _), (b, _) = ends[i]
            v = x[7 * m:7 * m + 7]
            out[i] = PointSpring(model.bodies[a], tuple(v[1:4]), model.bodies[b], tuple(v[4:7]), max(v[0], 1e-9),
                                 pulley_radius=springs[i].pulley_radius, lead=leads[i])
        return out

    def residual(v):
        return (joint_torques(model, build(v), q) / scale).ravel()

    def jacobian(v, r):  # forward differences, a step of 1e-7 of each variable's scale, inward at a bound
        J = np.empty((len(r), len(v)))
        for c in range(len(v)):
            step = 1e-7 * var_scale[c] * (1 if v[c] + 1e-7 * var_scale[c] <= hi[c] else -1)
            w = v.copy()
            w[c] += step
            J[:, c] = (residual(w) - r) / step
        return J

    var_scale = _scales(lo, hi, max_stiffness, x0)
    x = _minimax(x0, lo, hi, var_scale, residual, jacobian, REBALANCE_STEPS, groups=np.tile(np.arange(model.n), len(q)),
                 spread=1.0)
    better = _sig(_worst(model, build(x), q, scale)) < _sig(_worst(model, build(x0), q, scale))
    return build(x if better else x0)


def _realised_scales(model: RevoluteChain, springs, q) -> np.ndarray:
    """Each joint's scale (N m) for the realised springs' leads and re-balance over the poses ``q``: its own
    peak gravity torque, or ten times what the ideal ``springs`` leave there where that is more (a light
    joint the ideal springs leave near its own peak does not take the pulleys' whole correction: held to
    its own peak, the Panda's joint 7, 0.03 N m, set the whole re-balance and cost a shoulder joint half
    its balance), a tenth of the arm's largest for a joint gravity leaves (nearly) alone."""
    peak = np.max(np.abs(gravity_torques(model, q)), axis=0)
    left = np.max(np.abs(joint_torques(model, springs, q)), axis=0)
    return np.where(peak > NEGLIGIBLE * np.max(peak), np.maximum(peak, left / REBALANCE), 0.1 * np.max(peak))


def _joint_scales(tau_g) -> np.ndarray:
    """Each joint's scale (N m) for the best springs' search, from the gravity torques ``tau_g`` (N, n):
    the larger of its own peak and a tenth of the arm's largest (a light joint, or one gravity leaves
    alone, is held to a tenth of the largest: the springs must not load it beyond that)."""
    peak = np.max(np.abs(tau_g), axis=0)
    return np.maximum(peak, 0.1 * np.max(peak))


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


AUDIT_SAMPLES = 20_000
"""Random poses of the workspace, drawn from their own seed, on which every design's peaks are re-checked
(:class:`Audit`): ten times the design's own check, independent of it."""

AUDIT_STARTS = 3
"""From how many of the independent sample's worst poses, per joint and case, the audit's compass search
starts (the worst it reaches joins the check)."""

AUDIT_STEPS = (0.05, 1e-5)
"""rad: the compass search's first and last step (``_climb``); the peaks it refines are then found to
about the square of the last step times the torque's curvature, below the tables' printed digits."""


@dataclass(frozen=True)
class Audit:
    """An independent re-check of a design's peak holding torques: :data:`AUDIT_SAMPLES` random poses of
    the workspace (their own seed), and from the worst of them, per joint and per case (gravity alone,
    ideal, realised springs), a compass search (``_climb``) that climbs to the nearby worst pose
    within the workspace. The worst poses found join the design's check poses, so every peak and
    share the design reports holds on them too.

    :ivar samples: how many random poses were drawn
    :ivar seed: their seed
    :ivar worst: the worst poses found, refined, (M, n) rad
    :ivar raised: per (case, joint name), the peak (N m) over the design's own check poses and over the
        audit's poses, where the audit found more (above the tables' 3 significant digits)
    :ivar undefined: per case whose springs have no line of action at some of the random poses (a cable's
        end within its pulley's radius of the pulley, a spring's ends coinciding), (case, how many, the
        first such pose (rad), the reason)
    :ivar crossings: per realised cable spring whose end B crosses its lead's line in the workspace
        (within :data:`CROSSING`), (its index, the angle (rad), the pose (rad))
    :ivar workspace: the drawn poses in collision were left out (an arm with collision geometry)
    """

    samples: int
    seed: int
    worst: np.ndarray
    raised: tuple
    undefined: tuple = ()
    crossings: tuple = ()
    workspace: bool = False

    @classmethod
    def of(cls, model: RevoluteChain, ranges, cases: dict, check, seed: int, samples: int = AUDIT_SAMPLES,
           sampler=None) -> Audit:
        """The audit of the springs ``cases`` (name -> springs; gravity alone is added) over the workspace
        ``ranges`` (n, 2) rad, beside the design's own ``check`` poses. With a ``sampler``
        (:class:`~springlab.design.collision.Sampler`) the drawn poses in collision are left out (each asked
        only when it matters: a start, an undefined pose, the nearest approach to a lead line, in order of
        how bad it is), and each climb moves through free poses only."""
        rng = np.random.default_rng([seed, samples])
        q = rng.uniform(ranges[:, 0], ranges[:, 1], (samples, model.n))
        known, free_at = np.zeros(samples, dtype=bool), np.ones(samples, dtype=bool)

        def first_free(order, count: int) -> np.ndarray:
            """The first ``count`` indices of ``order`` whose poses are in the workspace."""
            if sampler is None:
                return np.asarray(order[:count], dtype=int)
            out = []
            for at in range(0, len(order), 64):
                chunk = np.asarray(order[at:at + 64], dtype=int)
                todo = chunk[~known[chunk]]
                if len(todo):
                    free_at[todo], known[todo] = sampler.free(q[todo]), True
                out += chunk[free_at[chunk]].tolist()
                if len(out) >= count:
                    break
            return np.asarray(out[:count], dtype=int)

        lo, hi = ranges[:, 0], ranges[:, 1]
        worst, raised, undefined, largest = [], [], [], None
        for case, springs in ({"gravity alone": ()} | dict(cases)).items():
            tau, why = defined_torques(model, springs, q)
            bad = np.isnan(tau[:, 0])
            bad_free = first_free(np.flatnonzero(bad), samples) if np.any(bad) else np.zeros(0, dtype=int)
            if len(bad_free):
                undefined.append((case, len(bad_free), q[bad_free[0]].tolist(), why))
            tau = np.abs(np.where(bad[:, None], 0.0, tau))
            mine = np.abs(defined_torques(model, springs, check)[0])
            own = np.max(np.where(np.isnan(mine), 0.0, mine), axis=0)
            if largest is None:  # gravity's, the first case, over the workspace's poses
                largest = max(float(tau[first_free(np.argsort([-_sig(v) for v in tau[:, j]], kind="stable"), 1),
                                        j].max(initial=0.0)) for j in range(model.n))
            for j in range(model.n):
                if not np.max(tau[:, j]) > 0:
                    continue
                climbed = []
                for start in q[first_free(np.argsort([-_sig(v) for v in tau[:, j]], kind="stable"), AUDIT_STARTS)]:
                    pose, value, broken = _climb(model, springs, start, j, lo, hi,
                                                 None if sampler is None else sampler.free)
                    climbed.append((_sig(value), -len(climbed), pose, value))
                    if broken is not None and not any(u[0] == case for u in undefined):
                        undefined.append((case, 0, broken[0].tolist(), broken[1]))
                _, _, pose, value = max(climbed, key=lambda c: c[:2])
                worst.append(pose)
                if _sig(value, 3) > _sig(own[j], 3) and value > NEGLIGIBLE * largest:
                    raised.append((case, model.joints[j], float(own[j]), float(value)))
        crossings = []
        for m, spring in enumerate(dict(cases).get("realised", ())):
            if spring.pulley_radius > 0:
                if sampler is None:
                    pose, angle = _nearest_approach(model, spring, q, lo, hi)
                else:  # from the nearest free pose, through free poses
                    order = np.argsort([_sig(v) for v in lead_angles(model, spring, q)], kind="stable")
                    start = q[first_free(order, 1)[0]]
                    pose, value = compass_search(lambda t, s=spring: -lead_angles(model, s, t), start, lo, hi,
                                           allowed=sampler.free)
                    angle = -value
                if angle < CROSSING / 3:
                    crossings.append((m, float(angle), pose.tolist()))
        unique = np.unique(np.array(worst).reshape(-1, model.n), axis=0)
        keep = np.ones(len(unique), dtype=bool)  # a pose one case climbed to may leave another's spring undefined
        for case, springs in dict(cases).items():
            tau, why = defined_torques(model, springs, unique)
            bad = np.isnan(tau[:, 0]) if len(unique) else np.zeros(0, dtype=bool)
            if np.any(bad) and not any(u[0] == case for u in undefined):
                undefined.append((case, 0, unique[int(np.argmax(bad))].tolist(), why))
            keep &= ~bad
        return cls(samples, seed, unique[keep], tuple(raised), tuple(undefined), tuple(crossings), sampler is not None)

    def note(self, checked: int) -> str:
        """The sample, in words, for the design's output."""
        found = ("; it found more than the check at " + ", ".join(
            f"{joint} ({case}: {own:.3g} -> {value:.3g} N m)" for case, joint, own, value in self.raised)
                 if self.raised else "; it found no peak above the check's, to 3 digits")
        within = " (those in collision left out)" if self.workspace else ""
        return (f"checked by route 2 on {checked} random poses of the workspace, then re-checked on {self.samples:,} "
                f"independent ones{within} with a local search from the {AUDIT_STARTS} worst of them per joint and case (the {len(self.worst)} "
                f"worst poses found join the check, so every peak and share below holds on them){found}")

    def as_dict(self) -> dict:
        """For ``springlab design --json``."""
        return {"lead_crossings": [{"spring": m + 1, "angle_rad": angle, "pose_rad": pose}
                                   for m, angle, pose in self.crossings],
                "undefined": [{"case": case, "poses": count, "first_pose_rad": pose, "why": why}
                              for case, count, pose, why in self.undefined],
                "samples": self.samples, "workspace_only": self.workspace, "seed": list((self.seed, self.samples)),
                "worst_poses_rad": self.worst.tolist(),
                "raised": [{"case": case, "joint": joint, "check_peak_Nm": own, "audit_peak_Nm": value}
                           for case, joint, own, value in self.raised]}


def _climb(model: RevoluteChain, springs, start, j: int, lo, hi, allowed=None) -> tuple[np.ndarray, float, tuple | None]:
    """The largest |holding torque| (N m) of joint ``j`` near the pose ``start`` within the bounds [lo, hi]
    (rad), by :func:`compass_search` on route 2's torques, moving only to poses ``allowed`` (a function of poses
    (M, n) -> (M,) bool; None: all). Returns the pose, its |torque|, and the first trial pose where a
    spring had no line of action with the reason (None where every trial had one)."""
    broken = []

    def value(trials):
        tau, why = defined_torques(model, springs, trials)
        if why and not broken:
            broken.append((trials[int(np.argmax(np.isnan(tau[:, j])))], why))
        return np.abs(tau[:, j])  # nan where undefined: never chosen

    x, best = compass_search(value, start, lo, hi)
    if allowed is not None and not allowed(x[None])[0]:  # it climbed out of the workspace: again, within it
        x, best = compass_search(value, start, lo, hi, allowed=allowed)
    return x, best, broken[0] if broken else None


def compass_search(value, start, lo, hi, max_steps: int = 400, enough: float = np.inf,
                   allowed=None) -> tuple[np.ndarray, float]:
    """A compass search for the largest ``value`` (a function of poses (M, n) rad, nan where undefined)
    near the pose ``start`` within the bounds [lo, hi] (rad): each step tries +- the step on every joint
    (one call of 2n poses) and moves to the best trial where it beats the current pose (compared to 9
    significant digits, ties to the first, so that round-off decides nothing), else halves the step,
    from :data:`AUDIT_STEPS`' first to its last, or until the value reaches ``enough``. With ``allowed`` (a
    function of poses (M, n) -> (M,) bool) it moves to the best better trial that is allowed. Returns the
    pose and its value."""
    x = np.array(start, dtype=float)
    best = float(value(x[None])[0])
    step, n = AUDIT_STEPS[0], len(x)
    for _ in range(max_steps):
        if step < AUDIT_STEPS[1] or best >= enough:
            break
        trials = np.clip(np.repeat(x[None], 2 * n, axis=0) + step * np.vstack([np.eye(n), -np.eye(n)]), lo, hi)
        values = value(trials)
        keys = [_sig(v) if np.isfinite(v) else -np.inf for v in values]
        floor = _sig(best) if np.isfinite(best) else -np.inf
        better = [k for k in np.argsort([-v for v in keys], kind="stable") if keys[k] > floor]
        if allowed is not None:
            better = [next((k for k in better if allowed(trials[k][None])[0]), None)]
            better = [k for k in better if k is not None]
        if better:
            x, best = trials[better[0]], float(values[better[0]])
        else:
            step /= 2
    return x, best


def _span(model: RevoluteChain, spring, R, o) -> np.ndarray:
    """B - A (m), (N, 3), in body a's frame at the poses whose body frames are ``R``, ``o``."""
    from springlab.model.revolute import world_points

    a, pa = model.locate(spring.link_a, spring.point_a)
    B = world_points(R, o, *model.locate(spring.link_b, spring.point_b))
    return np.einsum("pji,pj->pi", R[:, a], B - world_points(R, o, a, pa))


def lead_angles(model: RevoluteChain, spring, q, frames=None) -> np.ndarray:
    """rad, (N,): at each pose ``q``, how far the direction from a cable spring's pulley (at A) to its
    end B lies from the line of its lead, either way: min(alpha, pi - alpha), alpha the angle between
    the lead and B - A. Where it is zero the pulley, which swivels about the lead to hold B in its plane,
    must turn half a turn at once, and the cable's line of action jumps (route 2's
    :func:`springlab.energy.geometry.cable_geometry` is discontinuous there). ``frames``: the poses'
    body frames (:func:`springlab.model.revolute.body_frames`), where already computed."""
    d = _span(model, spring, *(body_frames(model, q) if frames is None else frames))
    u = np.asarray(model.direction(spring.link_a, spring.lead)[1])
    along = np.abs(d @ u)
    across = np.linalg.norm(np.cross(d, u), axis=1)
    return np.arctan2(across, along)  # accurate near the line, where arccos of the cosine loses half the digits


CROSSING = 1e-3
"""rad: a lead whose line a cable spring's end B comes within this angle of (20,000 poses, then a compass
search towards the line) is taken to be crossed, and avoided; the audit flags a realised spring whose end
comes within a third of it (its own sample and search: a margin)."""


def defined_torques(model: RevoluteChain, springs, q) -> tuple[np.ndarray, str]:
    """Route 2's holding torques (N m, (N, n)) at the poses ``q``, nan at the poses where a spring has no
    line of action (route 2 raises GeometryError there: a cable's end within its pulley's radius, a
    spring's ends coinciding), found by halving the batch; and the first such reason ('' for none)."""
    try:
        return joint_torques(model, springs, q), ""
    except GeometryError as err:
        if len(q) == 1:
            m = next(m for m, s in enumerate(springs) if not _defined(model, s, q))  # which spring
            return (np.full((1, model.n), np.nan),
                    f"spring {m + 1} ({springs[m].label}): " + str(err).split(" at pose ")[0])
        half = len(q) // 2
        (first, why_1), (second, why_2) = defined_torques(model, springs, q[:half]), defined_torques(model, springs, q[half:])
        return np.vstack([first, second]), why_1 or why_2


def _defined(model: RevoluteChain, spring, q) -> bool:
    """Whether route 2 gives ``spring`` a line of action at the poses ``q``."""
    try:
        joint_torques(model, [spring], q)
    except GeometryError:
        return False
    return True


def coil_room(model: RevoluteChain, spring, lengths) -> tuple[float, float]:
    """The room (m) a cable spring's coil has on link_a, from behind its pulley to the link's joint in the
    plane the joint turns in (the base: unbounded), and what a pulley block's travelling sheave takes
    from it (m), for the rope that carries its largest pull over ``lengths`` (m)."""
    from springlab.design.hardware import HOOK_GAP
    from springlab.design.layouts import cable_for

    body, at = model.locate(spring.link_a, spring.point_a)
    rho = spring.pulley_radius
    try:
        d = cable_for(spring.k * float(lengths[1]), rho).diameter if rho > 0 else 0.0
    except SpringlabError:
        d = 0.0
    if not 0 < body <= model.n:
        return float("inf"), 2 * (rho + d)
    w = np.asarray(model.axes[body - 1], dtype=float)
    return float(np.linalg.norm(at - (at @ w) * w)) - rho - HOOK_GAP - d, 2 * (rho + d)


def _side_by_side(kind: str) -> str:
    """Why a realised spring is one of several side by side, from its kind
    (:func:`~springlab.design.layouts.coil_for`'s order: the fewest that a stocked wire carries and whose
    coil fits its link)."""
    return ("one coil would be longer than its link" if "fit its link" in kind else
            "no stocked wire carries its force alone")


def realisation_changes(model: RevoluteChain, ideal, realised, kinds, origins) -> tuple:
    """Per realised spring, what the realisation changed of the ideal spring it realises (``origins``:
    its index), and why, in words: the rate (N/m, and the share), each end's move (mm), the pulley and
    its lead, a pulley block, a split side by side; or that only its free length and initial tension
    were chosen."""
    out = []
    for r, kind, i in zip(realised, kinds, origins, strict=True):
        s = ideal[i]
        if kind == "zero-length spring":
            out.append("the designed rate and ends; wound with an initial tension equal to k times its free length")
            continue
        parts = []
        together = sum(x.k for x, o in zip(realised, origins, strict=True) if o == i)
        if f"{together:.4g}" != f"{s.k:.4g}":
            parts.append(f"rate {s.k:.4g} -> {together:.4g} N/m ({100 * (together / s.k - 1):+.1f} %)")
        moves = []
        for end, (link_i, p_i), (link_r, p_r) in (("A", (s.link_a, s.point_a), (r.link_a, r.point_a)),
                                                   ("B", (s.link_b, s.point_b), (r.link_b, r.point_b))):
            bi, pi = model.locate(link_i, p_i)
            br, pr = model.locate(link_r, p_r)
            d = float(np.linalg.norm(np.asarray(pr) - np.asarray(pi)))
            if bi != br or d >= 5e-5:
                moves.append(f"end {end} moved {1e3 * d:.1f} mm")
        parts += moves
        why = ("re-balanced for its pulley: the wrap adds about k rho times the change of the wrap angle, which the "
               "ideal springs did not have" if parts else "")
        how = (f"a cable over a {1e3 * r.pulley_radius:g} mm pulley at end A, its lead (the direction the cable arrives "
               "from) chosen for the least torque left" if r.pulley_radius > 0 else
               "a cable over a point pulley at end A (its coil on link A), the force k times |B - A|")
        text = how + ("; " + ", ".join(parts) + " (" + why + ")" if parts else "; the designed rate and ends")
        ratio = re.search(r"(\d):1 pulley block", kind)
        if ratio:
            text += (f"; over a {ratio.group(1)}:1 pulley block (its coil moves 1/{ratio.group(1)} of the cable's path "
                     f"at {ratio.group(1)} times its pull): a coil on the cable alone would be longer than its link")
        count = origins.count(i)
        if count > 1:
            text += f"; one of {count} side by side at k / {count} each: {_side_by_side(kind)}"
        out.append(text)
    return tuple(out)


def design_model(model: RevoluteChain, *, workspace=None, samples: int = 2000, fit_poses: int = 300, seed: int = 1,
                 target: float = 0.1, reach: float | None = None, max_springs: int = 8,
                 max_stiffness: float = MAX_STIFFNESS, material: str = "music wire",
                 pulley_radius: float | None = 0.0, tag: str = "S", margin: float | None = None,
                 collisions: bool = True, layout: str = "two-point", share: float | None = None,
                 cable=None) -> ArmDesign:
    """Springs for an arm of the general model over its workspace (:func:`workspace_ranges`): its
    structure (:func:`~springlab.design.structure.structure`); the exact planar springs where its loaded joints form a planar
    chain (:func:`~springlab.design.structure.planar_springs`), else the best springs (:func:`best_springs`, fitted on
    ``fit_poses`` poses); their realisation (:func:`realise_springs`); all checked by route 2 on
    ``samples`` other random poses of the workspace, then re-checked on an independent sample
    (:class:`Audit`). Its springs are named ``tag`` and a number (S1, S2, ...).

    An arm with collision geometry (a URDF read with its shapes) is designed over its free workspace
    (:class:`~springlab.design.collision.Sampler`: no two links in collision, none below the mounting
    plane; ``collisions=False``: the ranges' box), its realised springs' clearance from the links is
    measured against ``margin`` (m, default :data:`~springlab.design.collision.MARGIN`) on the check
    poses, and the arm carrying the springs' own mass is kept beside it
    (:mod:`springlab.design.hardware`).

    ``layout='auto'`` takes the belts where the loaded joints (the light ones left out) form a planar
    chain and the arm has collision geometry, else the two-point springs.
    ``layout='belts'`` (a planar loaded chain only): one spring per loaded link from a post on a level
    frame a 1:1 belt carries to the link's joint (:func:`springlab.design.layouts.belt_layout`), its coil
    along the link, the pulley compensated for; joints below ``share`` of the largest gravity peak
    (default :data:`springlab.design.layouts.SHARE`) get none; each cable is the stocked one that carries
    its pull (:mod:`springlab.design.cables`, or ``cable``), over a pulley sized to it
    (``pulley_radius=None``) or of ``pulley_radius`` (m). ``'two-point'`` (default): springs between two
    links' points, exact for a planar chain, else the best springs, their cables over pulleys of
    ``pulley_radius`` (None: sized to the cable of the largest pull)."""
    if layout not in ("two-point", "belts", "pseudobases", "auto"):
        raise SpringlabError(f"layout = {layout!r}: give 'two-point' (springs between two links), 'belts' (a level "
                             "reference carried by belts to each joint of a planar chain), 'pseudobases' (carried "
                             "by paper 001's RSSR modules, any arm) or 'auto' (belts, else pseudobases, where the "
                             "arm has link shapes to clear)")
    from springlab.design.collision import MARGIN, Sampler, has_geometry
    from springlab.design.hardware import spring_clearance, with_spring_mass

    margin = MARGIN if margin is None else _checks.positive("margin", margin, allow_zero=True, unit="m")
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    if not (isinstance(tag, str) and tag.isalpha() and tag.isupper()):
        raise SpringlabError(f"tag = {tag!r}: give capital letters, e.g. 'S' (springs S1, S2, ...) or 'P'")
    samples = _checks.count("samples", samples, least=1)
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
        from springlab.design.layouts import SHARE, without_light

        trimmed = without_light(model, found, SHARE if share is None else share, check)
        layout = ("two-point" if not has_geometry(model) else "belts" if trimmed.planar else "pseudobases")
        notes.append("layout: " + {"belts": "belts, the loaded joints (the light ones left out) forming a planar chain",
                                   "pseudobases": "pseudobases (paper 001's RSSR modules), the loaded joints not "
                                                  "forming a planar chain",
                                   "two-point": "two-point springs (no link shapes to clear)"}[layout])
    spatial = layout == "pseudobases"
    if spatial:
        layout = "belts"
    if layout == "belts":
        from springlab.design.layouts import SHARE, belt_layout, realise_layout
        from springlab.design.pseudobases import pseudobase_layout

        arrange = pseudobase_layout if spatial else belt_layout
        share = SHARE if share is None else share
        lay = arrange(model, found, share=share, q=check)
        realised, kinds, coils, origins = realise_layout(lay, check, material=material, cable=cable,
                                                         pulley_radius=None if sized else pulley_radius)
        bare = (model.mass, model.com, model.inertia)
        for _ in range(CARRY_ROUNDS):  # the springs' own steel rides on the links: designed for too
            arm = replace(lay.model, mass=bare[0], com=bare[1], inertia=bare[2])  # the arm alone, with the belts
            built = [m for m, r in enumerate(realised) if r is not None]
            realised, kinds, coils = ([v[m] for m in built] for v in (realised, kinds, coils))
            carried = replace(with_spring_mass(arm, realised, kinds, coils, check), belts=())
            widths = {}  # a pseudobase's C moves beside the links by half its coils' width too
            for r, fit in zip(realised, coils, strict=True):
                t = model.bodies.index(r.link_a) - 1
                widths[t] = widths.get(t, 0.0) + fit.coil.outer_diameter
            lay = arrange(carried, structure(carried, check), share=share, q=check,
                          **({"widths": widths} if spatial else {}))
            realised, kinds, coils, origins = realise_layout(lay, check, material=material, cable=cable,
                                                             pulley_radius=None if sized else pulley_radius)
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
        pulley_radius = _sized_pulley(model, ideal, check)
    if layout == "two-point":
        realised, kinds, coils, origins = _realise(
            model, ideal, check, material=material, pulley_radius=pulley_radius, reach=reach,
            fit=draw(min(150, fit_poses)), max_stiffness=max_stiffness)
    for kind in kinds:
        if kind.startswith("not realised"):
            notes.append(f"{kind}: the realised design leaves it out")
    left_out = tuple((origins[m], kinds[m].split("): ", 1)[-1]) for m, r in enumerate(realised) if r is None)
    kept = [m for m, r in enumerate(realised) if r is not None]
    realised, coils, kinds, origins = (tuple(v[m] for m in kept) for v in (realised, coils, kinds, origins))
    changes = realisation_changes(model, ideal, realised, kinds, origins)
    audit = Audit.of(model, ranges, {"ideal": ideal, "realised": realised}, check, seed, sampler=sampler)
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
    clearance = None
    if sampler is not None:
        clearance = spring_clearance(model, realised, kinds, coils, design.realised_names, check, margin=margin)
    massed = with_spring_mass(model, realised, kinds, coils, check)
    workspace = sampler.note() if sampler is not None else "the joint ranges' box (the arm has no collision geometry)"
    return replace(design, clearance=clearance, massed=massed, workspace=workspace, carried=layout == "belts")
