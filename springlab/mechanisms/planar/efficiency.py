r"""Spring and system efficiency (003 Eqs. 17-25) and the workspace index
(003 Section 5), read from the pseudo-stiffness terms of :mod:`.quadratic`.

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


RATE = 1e7
"""Poses per second the index evaluates on one core, about (for the refusal of requests that
would run for hours: :func:`springlab._checks.poses`)."""


def efficiency_index(arm: PlanarArm, springs, workspace: Workspace, *, step: float | None = None,
                     samples: int | None = None, seed=None, reading: str = "magnitudes",
                     chunk: int = 1 << 18, progress: bool = False) -> float:
    """The system spring efficiency index: the mean of e_sys over the workspace (Section 5).

    Sampling, stated by the arguments: ``step`` (deg), a grid with both ends included
    (:meth:`Workspace.grid`), every point weighted equally; or ``samples`` poses drawn
    uniformly with ``seed``. Memory stays bounded: the grid is walked a slice at a
    time over all but the last two joints, the samples ``chunk`` at a time.
    """
    springs = check_springs(arm, springs)
    if reading not in READINGS:
        raise SpringlabError(f"reading must be one of {READINGS}, got {reading!r}")
    _checks.instance("workspace", workspace, Workspace, "Workspace(low, high) in deg")
    if workspace.joints != arm.n - 1:
        raise SpringlabError(f"the workspace has {workspace.joints} joints, the arm {arm.n - 1}")
    if (step is None) == (samples is None):
        raise SpringlabError("give exactly one of step (a grid, deg) or samples (Monte Carlo, with seed)")
    tl = terms(arm, springs)
    from tqdm import tqdm

    if samples is not None:
        samples = _checks.sample_count(samples, least=1, why=" (an empty sample has no mean)")
        _checks.poses(f"the index over samples = {samples}", samples, rate=RATE, hint="use fewer samples")
    else:
        points = workspace.grid_size(step)
        _checks.poses(f"the index over a grid of step = {step:g} deg", points, rate=RATE, hint="use a larger step")

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
    axes = workspace.grid(step)
    split = max(0, len(axes) - 2)  # joints 2..split+1 walked, the last two vectorised
    _checks.memory(f"the index's inner grid with step = {step:g} deg",
                   math.prod(len(a) for a in axes[split:]) * (2 * len(tl) + 3), hint="use a larger step")
    outer, inner = axes[:split], axes[split:]
    mesh = np.meshgrid(*inner, indexing="ij")
    inner_theta = np.stack([m.ravel() for m in mesh], axis=1)  # (M, len(inner))

    def theta_in(t):
        cols = [c - split for c in range(t.u - 1, t.v - 1) if c >= split]  # theta index c <-> joint c+2
        return inner_theta[:, cols].sum(axis=1) if cols else np.zeros(len(inner_theta))

    phase = [np.radians(float(t.phase)) - theta_in(t) for t in tl]
    amp = np.array([float(t.amplitude) for t in tl])
    cos_in, sin_in = np.stack([np.cos(p) for p in phase], 1) * amp, np.stack([np.sin(p) for p in phase], 1) * amp
    outer_cols = [[c for c in range(t.u - 1, t.v - 1) if c < split] for t in tl]
    total, count = 0.0, 0
    for point in tqdm(itertools.product(*outer), total=int(np.prod([len(a) for a in outer])) if outer else 1,
                      disable=not progress, desc="index", mininterval=1.0):
        out = np.array([sum(point[c] for c in cols) for cols in outer_cols])  # Theta_out per term
        values = cos_in * np.cos(out) + sin_in * np.sin(out)  # amp cos(phase - Theta_in - Theta_out)
        e = _e_sys(values, tl, reading)
        total += e.sum()
        count += e.size
    return total / count
