"""Benchmark: configurations and designs for a user's arm (springlab.configurations, arm_design).

* every admissible configuration with necessary springs, with its sign patterns, for
  n = 3..6 (n = 5 target: under 10 s), and the count per n;
* best first: the first 10 configurations (fewest springs, then fewest spanned joints)
  for n = 3..8 (n = 8 target: under 10 s);
* design_arm on the two example arm files (verified designs, route 2).

    make bench
    python benchmarks/bench_design.py
"""

from __future__ import annotations

import itertools
import time
from pathlib import Path

from springlab.arm_design import design_arm
from springlab.configurations import best_first_configurations, iter_configurations

ARMS = Path(__file__).resolve().parents[1] / "notebooks" / "arms"


def main() -> None:
    print("all configurations with necessary springs (rules R1-R6):")
    for n in (3, 4, 5, 6):
        t0 = time.perf_counter()
        configs = list(iter_configurations(n))
        dt = time.perf_counter() - t0
        fewest = min(len(c) for c in configs)
        print(f"  n = {n}: {len(configs):5d} configurations in {dt:6.2f} s (fewest springs {fewest})")
    print("best first, the first 10:")
    for n in range(3, 9):
        t0 = time.perf_counter()
        first = list(itertools.islice(best_first_configurations(n), 10))
        dt = time.perf_counter() - t0
        print(f"  n = {n}: {dt:6.2f} s, {first[0][0]} springs spanning {first[0][1]} joints first")
    for name, kw in (("paper000_arm.toml", {}), ("industrial_6link.toml", {"max_designs": 5})):
        t0 = time.perf_counter()
        report = design_arm(ARMS / name, **kw)
        print(f"design_arm({name}): {len(report.designs)} verified designs from {report.configurations_tried} "
              f"configurations in {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
