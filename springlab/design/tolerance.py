"""How well a spring design holds up when it is built: a seeded Monte Carlo study.

Each sample builds the design with random errors and measures, by route 2
(:func:`springlab.energy.geometry.holding_torques`), the largest joint torque needed to
hold the arm over a set of workspace poses. A perfectly built balanced design
needs none; the study says how much each error costs. Errors (all optional):

* ``attachment`` (m): each end's distance a, b off by a normal error of this
  standard deviation, along the link line (000's springs sit on the joint lines);
* ``free_length`` (m): each spring's free length uniform in [0, this] instead of 0
  (a real spring is never quite zero-free-length);
* ``stiffness`` (relative): each k off by a normal error of this relative deviation;
* ``payload`` (kg): a payload uniform in [-payload, +payload] added at the end
  link's COM (a negative draw takes mass off, down to nothing).

The torque is the norm of the holding-torque vector at each joint (for a revolute
joint an upper bound on the actuator's share), maximised over joints and poses.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.energy.geometry import holding_torques
from springlab.errors import SpringlabError
from springlab.executors import check_executor, map_ordered
from springlab.model.chain import Chain, check_springs
from springlab.model.springs import Spring
from springlab.tables import Table

FACTORS = ("attachment", "free_length", "stiffness", "payload")


@dataclass(frozen=True)
class Tolerances:
    """Manufacturing and use tolerances (module docstring); 0 switches a factor off."""

    attachment: float = 0.0
    free_length: float = 0.0
    stiffness: float = 0.0
    payload: float = 0.0

    def __post_init__(self):
        for name in FACTORS:
            unit = {"attachment": "m", "free_length": "m", "stiffness": "(relative)", "payload": "kg"}[name]
            object.__setattr__(self, name, _checks.positive(f"tolerance {name}", getattr(self, name), allow_zero=True,
                                                            unit=unit))

    def only(self, factor: str) -> Tolerances:
        """The same tolerances with every other factor switched off."""
        if factor not in FACTORS:
            raise SpringlabError(f"factor must be one of {FACTORS}, got {factor!r}")
        return Tolerances(**{f: (getattr(self, f) if f == factor else 0.0) for f in FACTORS})


def perturbed(chain: Chain, springs, tol: Tolerances, rng) -> tuple[Chain, list[Spring]]:
    """One built arm: the chain (payload changed) and the springs with their errors."""
    springs = check_springs(chain, springs)
    _checks.instance("tol", tol, Tolerances)
    rng = _checks.rng("rng", rng)
    out = []
    for s in springs:
        a = s.a + rng.normal(0.0, tol.attachment) if tol.attachment else s.a
        b = s.b + rng.normal(0.0, tol.attachment) if tol.attachment else s.b
        k = s.k * max(1e-9, 1.0 + rng.normal(0.0, tol.stiffness)) if tol.stiffness else s.k
        l0 = s.free_length + (rng.uniform(0.0, tol.free_length) if tol.free_length else 0.0)
        out.append(Spring(s.i, s.j, a, b, k, free_length=l0, initial_tension=s.initial_tension))
    if tol.payload:
        dm = rng.uniform(-tol.payload, tol.payload)
        m = list(chain.m)
        m[-1] = max(1e-9, m[-1] + dm)
        chain = Chain(chain.r, chain.d, tuple(m), chain.g, chain.joints)
    return chain, out


@dataclass(frozen=True)
class ToleranceResult:
    """Per factor (and 'all' together): the largest holding torque of each sample (N m), (samples,)."""

    torques: dict
    samples: int
    seed: int

    def summary(self) -> list[tuple[str, float, float, float]]:
        """(factor, median, 95th percentile, max) of the largest holding torque, N m."""
        return [(name, float(np.median(v)), float(np.percentile(v, 95)), float(np.max(v)))
                for name, v in self.torques.items()]

    def table(self) -> Table:
        """:meth:`summary` as a table (shown as Markdown in a notebook)."""
        return Table(["error", "median (N m)", "95th percentile (N m)", "largest (N m)"],
                     [(n, f"{a:.3g}", f"{b:.3g}", f"{c:.3g}") for n, a, b, c in self.summary()])


def side_by_side(first: ToleranceResult, second: ToleranceResult, first_label: str, second_label: str) -> Table:
    """Two designs' tolerance studies, error by error: each one's median and 95th percentile of the
    largest holding torque (N m)."""
    rows = [(name, f"{a:.3g}", f"{b:.3g}", f"{c:.3g}", f"{d:.3g}")
            for (name, a, b, _), (_, c, d, _) in zip(first.summary(), second.summary(), strict=True)]
    return Table(["error", f"{first_label}: median", "95th pct", f"{second_label}: median", "95th pct"], rows)


def _study_factor(chain: Chain, springs, X, tol: Tolerances, seed_sequence, samples: int, step=None) -> np.ndarray:
    """One factor's built arms, seeded by its own SeedSequence: the largest holding torque of each (N m)."""
    rng = np.random.default_rng(seed_sequence)
    worst = np.zeros(samples)
    for k in range(samples):
        built_chain, built = perturbed(chain, springs, tol, rng)
        worst[k] = float(np.max(np.linalg.norm(holding_torques(built_chain, built, X), axis=-1)))
        if step is not None:
            step()
    return worst


def tolerance_study(chain: Chain, springs, X, tol: Tolerances, *, samples: int = 500, seed: int = 0,
                    progress: bool = True, executor=None) -> ToleranceResult:
    """Monte Carlo over built arms: each factor alone, then all together.

    :param X: workspace poses, link directions (N, n, 3)
    :param samples: built arms per factor; ``seed`` makes the study repeatable
    :param executor: a concurrent.futures.Executor to run the factors on (one task each, seeded by
        its own child of ``seed``: the same results as serially); None runs them here
    """
    from tqdm import tqdm

    springs = check_springs(chain, springs)
    X = chain.check_directions(X)
    _checks.instance("tol", tol, Tolerances)
    samples = _checks.sample_count(samples, least=1)
    seed = _checks.count("seed", seed)
    executor = check_executor(executor)
    active = [f for f in FACTORS if getattr(tol, f)]
    if not active:
        raise SpringlabError("every tolerance is 0: nothing to study")
    runs = {f: tol.only(f) for f in active} | ({"all": tol} if len(active) > 1 else {})
    seeds = np.random.SeedSequence(seed).spawn(len(runs))
    bar = tqdm(total=len(runs) * int(samples), disable=not progress, desc="tolerance study", mininterval=1.0)
    step = bar.update if executor is None else None  # a task on another process cannot move this bar
    tasks = [(chain, springs, X, t, ss, int(samples), step) for t, ss in zip(runs.values(), seeds, strict=True)]
    worst = map_ordered(executor, _study_factor, tasks)
    bar.update(bar.total - bar.n)
    bar.close()
    return ToleranceResult(dict(zip(runs, worst, strict=True)), int(samples), seed)
