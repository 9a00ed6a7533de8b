"""Benchmark: paper 003's efficiency index (springlab.mechanisms.planar), one core.

* the index of Table 4's design at a 1-degree grid over Table 3's whole workspace,
  ends included: 201 x 281 x 281 = 15.9 million poses (target: under 5 s);
* Fig. 7a's sweep: the index at 21 x 21 settings of A_S(1,4), A_S(2,4), each a new
  design from Eqs. (27), on a 5-degree grid (target: under 30 s);
* the same index by Monte Carlo, 10 million poses, for comparison.

Memory stays bounded: the grid is walked one theta_2 slice (281 x 281 poses) at a time.

    make bench
    python benchmarks/bench_efficiency.py
"""

from __future__ import annotations

import resource
import time

import numpy as np

from springlab.mechanisms.planar import efficiency as ef
from springlab.mechanisms.planar import synthesis as plsyn
from springlab.papers import juang2022 as paper


def main() -> None:
    arm, ws = paper.ARM, paper.WORKSPACE
    springs = plsyn.design(arm, "Λ3-1", paper.FREE_CHOICES)
    ef.efficiency_index(arm, springs, ws, step=10)  # warm up (imports, caches)

    poses = ws.grid_size(1)
    t0 = time.perf_counter()
    index = ef.efficiency_index(arm, springs, ws, step=1)
    t_grid = time.perf_counter() - t0
    print(f"index at a 1 deg grid: {poses:,} poses in {t_grid:.2f} s ({poses / t_grid / 1e6:.1f} M poses/s), "
          f"index {index:.5f} (target < 5 s)")

    t0 = time.perf_counter()
    mc = ef.efficiency_index(arm, springs, ws, samples=10_000_000, seed=0)
    t_mc = time.perf_counter() - t0
    print(f"index by Monte Carlo: 10,000,000 poses in {t_mc:.2f} s ({10 / t_mc:.1f} M poses/s), index {mc:.5f}")

    axis = np.linspace(0.05, 1.0, 21)
    t0 = time.perf_counter()
    for a1 in axis:
        for a2 in axis:
            design = plsyn.design(arm, "Λ3-1", paper.FREE_CHOICES | {"A_S14": a1, "A_S24": a2})
            ef.efficiency_index(arm, design, ws, step=5)
    t_sweep = time.perf_counter() - t0
    print(f"Fig. 7a sweep: 21 x 21 designs at a 5 deg grid ({ws.grid_size(5):,} poses each) in {t_sweep:.1f} s "
          f"(target < 30 s)")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak resident memory of the whole run: {peak:.0f} MB")


if __name__ == "__main__":
    main()
