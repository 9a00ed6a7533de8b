r"""Spring and system efficiency (003 Eqs. 17-25) and the workspace index
(003 Section 5), read from the pseudo-stiffness terms of :mod:`~springlab.mechanisms.planar.quadratic`.

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.mechanisms.planar.model import (
    PlanarArm,
    PlanarSpring,
    Workspace,
    check_spring,
    check_springs,
    relative_angles,
)
from springlab.mechanisms.planar.quadratic import term_values, terms

READINGS = ("magnitudes", "literal", "direct")


# --- efficiency (003 Eqs. 17-25) -------------------------------------------------------------------
def _balancing_groups(term_list):
    """For the 'literal' reading: each balanced term's group, the first spring with a
    balancing term on the same pair (u, v)."""
    owner = {}
    for t in term_list:
        if t.role == "balancing" and t.u > 1:
            owner.setdefault((t.u, t.v), t.source)
    groups = {}
    for col, t in enumerate(term_list):
        if t.role == "balanced":
            groups.setdefault(owner.get((t.u, t.v), f"unbalanced {t.u},{t.v}"), []).append(col)
    return list(groups.values())


def _e_sys(values, term_list, reading):
    roles = np.array([t.role for t in term_list])
    grav, bal, balancing = roles == "gravity", roles == "balanced", roles == "balancing"
    if reading == "magnitudes":  # the text: sums of magnitudes
        X = np.abs(values[:, grav]).sum(axis=1)
        Y = np.abs(values[:, bal]).sum(axis=1)
    elif reading == "literal":  # 003 Eqs. (30a-b) as printed: |sum| per group
        X = np.abs(values[:, grav].sum(axis=1))
        Y = sum((np.abs(values[:, g].sum(axis=1)) for g in _balancing_groups(term_list)), np.zeros(len(values)))
    elif reading == "direct":  # 003 Eq. (24) term by term
        num = np.abs(values[:, balancing]).sum(axis=1)
        return num / (num + np.abs(values[:, bal]).sum(axis=1))
    else:
        raise SpringlabError(f"reading must be one of {READINGS}, got {reading!r}")
    return (X + Y) / (X + 2 * Y)  # 003 Eq. (25)


def system_efficiency(arm: PlanarArm, springs, theta, *, reading: str = "magnitudes") -> np.ndarray:
    """e_sys at each pose, (N,) in [0.5, 1] (003 Eq. 25, with X and Y read as ``reading``):

    * 'magnitudes': X, Y sums of the magnitudes of the balanced gravitational and
      elastic pseudo-stiffnesses, as Section 4.1 defines them;
    * 'literal': 003 Eqs. (30a-b) as printed, the magnitude of each group's sum;
    * 'direct': 003 Eq. (24) itself, balancing over all elastic pseudo-stiffnesses.
    """
    springs = check_springs(arm, springs)
    theta = relative_angles(theta, arm.n)
    tl = terms(arm, springs)
    return _e_sys(term_values(tl, theta), tl, reading)


def spring_efficiency(arm: PlanarArm, spring: PlanarSpring, theta) -> np.ndarray:
    """e = x / (x + y) (003 Eq. 18) at each pose, (N,): x, y the magnitudes of the spring's
    balancing and balanced pseudo-stiffnesses. 1 for a spring over one joint (003 Eq. 22)."""
    check_spring(arm, spring, criteria=False)
    theta = relative_angles(theta, arm.n)
    tl = [t for t in terms(arm, [spring]) if t.role != "gravity"]
    v = np.abs(term_values(tl, theta))
    roles = np.array([t.role for t in tl])
    x, y = v[:, roles == "balancing"].sum(axis=1), v[:, roles == "balanced"].sum(axis=1)
    return x / (x + y)


def spans(arm: PlanarArm, i: int, theta, *, k: float, A: float, B: float, alpha: float, beta: float) -> dict:
    """003 Eq. (23)'s comparison: the same spring (rate ``k`` N/m, attachment parameters ``A``, ``B`` (003 Eqs.
    12a-b), angles ``alpha``, ``beta`` deg) from link ``i`` to each later link j, its efficiency (003 Eq. 18) at
    the poses ``theta`` (N, n - 1) rad: {j: (N,) efficiencies}, j = i + 1 .. n."""
    out = {}
    for j in range(i + 1, arm.n + 1):
        spring = PlanarSpring(i, j, k, A * arm.r[i - 1], B * arm.r[j - 1], alpha, beta)  # 003 Eqs. (12a-b)
        out[j] = spring_efficiency(arm, spring, theta)  # 003 Eq. (18)
    return out


def span_rows(arm: PlanarArm, families: dict, theta) -> tuple[list, dict]:
    """For each family (label -> (i, dict of :func:`spans`' keywords)), each span's mean efficiency over the poses
    ``theta`` (rad) beside one joint fewer: the rows (label, spring, joints spanned, mean efficiency, the share
    of poses where it is lower, higher than one joint fewer), and per (family, i, j) the change of the mean from
    S(i, j - 1) to S(i, j) and the share of poses where S(i, j) is the more efficient."""
    rows, changes = [], {}
    for label, (i, kw) in families.items():
        eff = spans(arm, i, theta, **kw)
        for j, e in eff.items():
            fewer = eff.get(j - 1)
            lower = "" if fewer is None else f"{100 * np.mean(e < fewer - 1e-12):.1f}"
            higher = "" if fewer is None else f"{100 * np.mean(e > fewer + 1e-12):.1f}"
            rows.append((label, f"S({i},{j})", j - i, f"{e.mean():.4f}", lower, higher))
            if fewer is not None:
                changes[label, i, j] = (float(e.mean() - fewer.mean()), float(np.mean(e > fewer + 1e-12)))
    return rows, changes


RATE = 2e6
"""Poses per second the index evaluates by Monte Carlo on one core, about (for the refusal of
requests that would run for hours: :func:`springlab._checks.poses`)."""

GRID_RATE = 5e7
"""The same on a grid (the compiled kernel of :mod:`springlab.mechanisms.planar.kernels`)."""


def _check_workspace(arm: PlanarArm, workspace) -> None:
    _checks.instance("workspace", workspace, Workspace, "Workspace(low, high) in deg")
    if workspace.joints != arm.n - 1:
        raise SpringlabError(f"the workspace has {workspace.joints} joints, the arm {arm.n - 1}")


def efficiency_index(arm: PlanarArm, springs, workspace: Workspace, *, step: float | None = None,
                     samples: int | None = None, seed=None, reading: str = "magnitudes",
                     chunk: int = 1 << 18, progress: bool = False) -> float:
    """The system spring efficiency index: the mean of e_sys over the workspace (Section 5).

    Sampling, stated by the arguments: ``step`` (deg), a grid with both ends included
    (:meth:`~springlab.mechanisms.planar.model.Workspace.grid`), every point weighted equally; or ``samples`` poses drawn
    uniformly with ``seed``. Memory stays bounded: the grid is walked a slice at a
    time over all but the last two joints, the samples ``chunk`` at a time.
    """
    springs = check_springs(arm, springs)
    if reading not in READINGS:
        raise SpringlabError(f"reading must be one of {READINGS}, got {reading!r}")
    _check_workspace(arm, workspace)
    if (step is None) == (samples is None):
        raise SpringlabError("give exactly one of step (a grid, deg) or samples (Monte Carlo, with seed)")
    tl = terms(arm, springs)
    from tqdm import tqdm

    if samples is not None:
        samples = _checks.sample_count(samples, least=1, why=" (an empty sample has no mean)")
        _checks.poses(f"the index over samples = {samples}", samples, rate=RATE, hint="use fewer samples")
    else:
        points = workspace.grid_size(step)
        _checks.poses(f"the index over a grid of step = {step:g} deg", points, rate=GRID_RATE, hint="use a larger step")

    if samples is not None:
        if seed is None:
            raise SpringlabError("Monte Carlo sampling needs a seed")
        total, done = 0.0, 0
        rng_seed = np.random.SeedSequence(seed)
        for child in tqdm(rng_seed.spawn(int(np.ceil(samples / chunk))), disable=not progress, desc="index"):
            count = min(chunk, samples - done)
            theta = workspace.sample(count, child)
            total += _e_sys(term_values(tl, theta), tl, reading).sum()
            done += count
        return total / samples
    return _grid_means(workspace, step, [(tl, reading)], progress)[0]


def efficiency_indices(arm: PlanarArm, designs: dict, workspace: Workspace, *, step: float,
                       readings=("magnitudes",), also=(), progress: bool = False) -> dict[tuple[str, str], float]:
    """:func:`efficiency_index` on the grid of ``step`` (deg) for several designs and readings in one
    pass: {(design label, reading): index}. ``designs``: {label: springs}; every design under every
    one of ``readings``, and the further (label, reading) pairs of ``also`` (one design under
    another reading, without the others). Terms shared by the designs (gravity's, and those of
    springs two designs have in common) are evaluated once per pose; each design and reading is
    the same mean over the same grid as :func:`efficiency_index` gives, to the last bit."""
    _checks.instance("designs", designs, dict, "a dict {label: springs}")
    if not designs:
        raise SpringlabError("designs is empty: give at least one {label: springs}")
    readings = [_checks.choice("reading", r, READINGS) for r in readings]
    if not readings:
        raise SpringlabError("readings is empty: give at least one of " + ", ".join(READINGS))
    pairs = [(label, reading) for label in designs for reading in readings]
    for pair in also:
        if not (isinstance(pair, tuple) and len(pair) == 2 and pair[0] in designs):
            raise SpringlabError(f"also must hold (design label, reading) pairs with labels of designs "
                                 f"({', '.join(map(str, designs))}), got {pair!r}")
        pair = (pair[0], _checks.choice("reading", pair[1], READINGS))
        if pair not in pairs:
            pairs.append(pair)
    _check_workspace(arm, workspace)
    _checks.poses(f"the index over a grid of step = {step:g} deg", workspace.grid_size(step) * len(pairs),
                  rate=GRID_RATE, hint="use a larger step")
    springs_of = {label: check_springs(arm, springs) for label, springs in designs.items()}
    jobs = [(label, reading, terms(arm, springs_of[label])) for label, reading in pairs]
    means = _grid_means(workspace, step, [(tl, reading) for _, reading, tl in jobs], progress)
    return {(label, reading): mean for (label, reading, _), mean in zip(jobs, means, strict=True)}


def _groups(term_list, reading) -> list[tuple[int, list[int]]]:
    """e_sys as sums over groups of terms: (side, columns) with side 0 for X, 1 for Y; X = sum of
    |group sums| on side 0, Y on side 1 (for 'direct': the balancing and the balanced terms)."""
    roles = [t.role for t in term_list]
    one = [[c] for c in range(len(roles))]
    if reading == "magnitudes":
        return [(0, c) for c in one if roles[c[0]] == "gravity"] + [(1, c) for c in one if roles[c[0]] == "balanced"]
    if reading == "literal":
        return [(0, [c for c, r in enumerate(roles) if r == "gravity"])] + [(1, g) for g in _balancing_groups(term_list)]
    return [(0, c) for c in one if roles[c[0]] == "balancing"] + [(1, c) for c in one if roles[c[0]] == "balanced"]


def _grid_means(workspace: Workspace, step: float, jobs, progress: bool) -> list[float]:
    """The mean of e_sys over the grid of ``step`` for each (term list, reading) of ``jobs``.

    Each term is amp cos(phase - Theta_in - Theta_out), Theta_in the sum of the angles of the
    last two joints (the inner grid, held as amp cos and amp sin of phase - Theta_in), Theta_out
    of the others (one outer point at a time): amp cos(...) = C_in cos(Theta_out) + S_in sin(Theta_out).
    Terms equal across jobs (same amplitude, phase, u, v) are evaluated once, and a term with
    no outer joint in its Theta (and a group of such terms) once per inner point, not once per
    grid point. The sums run in a compiled kernel (numba, compiled once and cached on disk:
    :func:`springlab.mechanisms.planar.kernels.index_sums`), a block of inner points at a time."""
    from tqdm import tqdm

    from springlab.mechanisms.planar.kernels import index_sums

    axes = workspace.grid(step)
    split = max(0, len(axes) - 2)  # joints 2..split+1 walked, the last two vectorised
    def term_key(t):  # terms with these equal are the same function of the pose
        return float(t.amplitude), float(t.phase), t.u, t.v

    unique: dict[tuple, int] = {}
    for tl, _ in jobs:
        for t in tl:
            unique.setdefault(term_key(t), len(unique))
    _checks.memory(f"the index's inner grid with step = {step:g} deg",
                   math.prod(len(a) for a in axes[split:]) * (2 * len(unique) + 2 * len(jobs) + 3),
                   hint="use a larger step")
    outer, inner = axes[:split], axes[split:]
    mesh = np.meshgrid(*inner, indexing="ij")
    inner_theta = np.stack([m.ravel() for m in mesh], axis=1)  # (M, len(inner))
    keys = list(unique)

    def theta_in(u, v):
        cols = [c - split for c in range(u - 1, v - 1) if c >= split]  # theta index c <-> joint c+2
        return inner_theta[:, cols].sum(axis=1) if cols else np.zeros(len(inner_theta))

    phase = np.array([np.radians(ph) - theta_in(u, v) for _, ph, u, v in keys])  # (T, M)
    amp = np.array([a for a, _, _, _ in keys])[:, None]
    cos_in, sin_in = np.ascontiguousarray(np.cos(phase) * amp), np.ascontiguousarray(np.sin(phase) * amp)
    points = list(itertools.product(*outer)) if outer else [()]
    theta_out = np.array([[sum(point[c] for c in range(u - 1, v - 1) if c < split) for _, _, u, v in keys]
                          for point in points])  # (P, T): Theta_out per term
    sides, starts, members = [], [0], []
    per_job = []
    for tl, reading in jobs:
        groups = _groups(tl, reading)
        per_job.append(len(groups))
        for side, cols in groups:
            sides.append(side)
            members += [unique[term_key(tl[c])] for c in cols]
            starts.append(len(members))
    job_of_group = np.repeat(np.arange(len(jobs)), per_job)
    direct = np.array([reading == "direct" for _, reading in jobs])
    # a term whose Theta has no outer joint is the same at every outer point (its value is cos_in), and so is
    # a group of such terms: its |sum| is added once per inner point, before the walk over the outer points
    dynamic = np.array([any(c < split for c in range(u - 1, v - 1)) for _, _, u, v in keys])
    sides_a, starts_a, members_a = (np.array(v, dtype=np.int64) for v in (sides, starts, members))
    static_group = np.array([not dynamic[members_a[starts_a[g]:starts_a[g + 1]]].any() for g in range(len(sides))])
    base = np.zeros((2, len(jobs), cos_in.shape[1]))  # (X, Y) of the static groups, per job and inner point
    for g in np.flatnonzero(static_group):
        acc = np.zeros(cos_in.shape[1])
        for t in members_a[starts_a[g]:starts_a[g + 1]]:
            acc += cos_in[t]
        base[sides[g], job_of_group[g]] += np.abs(acc)
    totals = np.zeros(len(jobs))
    chunk = max(1, int(2e6 // max(1, cos_in.shape[1])))  # outer points per kernel call (the progress bar's steps)
    for lo in tqdm(range(0, len(points), chunk), disable=not progress, desc="index", mininterval=1.0):
        out = theta_out[lo:lo + chunk]
        totals += index_sums(cos_in, sin_in, np.cos(out), np.sin(out), dynamic, base[0], base[1],
                             sides_a, starts_a, members_a, job_of_group, static_group, direct)
    return list(totals / (len(points) * cos_in.shape[1]))
