"""Benchmark: configurations and designs for a user's arm (springlab.design.rules, design.rank, design.ground).

* every admissible configuration with necessary springs, with its sign patterns, for
  n = 3..6 (n = 5 target: under 10 s), and the count per n;
* best first: the first 10 configurations (fewest springs, then fewest spanned joints)
  for n = 3..8 (n = 8 target: under 10 s);
* design_arm on the two example arm files (verified designs, route 2): paper 000's
  configurations with and without the largest-force minimisation of the free choices, and
  the default search over every family, fewest springs first (6-link target: under 20 s);
* the n - 1 ground springs for n = 3..8, and the relaxation screen that proves n - 2
  impossible (n = 3..6);
* the rules against physics: every inclusion-minimal balanceable multiset of springs (000 Eqs. 39),
  each with a design or an exact certificate, on a random arm, n = 2..5 and every sign pattern at
  n = 4 (n = 5 target: under 15 s), n = 5 on three more arms, beside the rules' enumeration;
* the fewest springs, proved (a design, and every multiset of fewer springs refuted), n = 2..7;
  ``--fewest 8`` goes to n = 8 (about 25 minutes: 262,934 multisets of up to nine springs refuted).

    make bench
    python benchmarks/bench_design.py [--fewest 8]
"""

from __future__ import annotations

import argparse
import itertools
import time
from pathlib import Path

from springlab.design import feasibility, rulecheck
from springlab.design.ground import ground_spring_design, relaxation_screen
from springlab.design.rank import design_arm
from springlab.design.rules import best_first_configurations, iter_configurations
from springlab.model.chain import serial_chain

ARMS = Path(__file__).resolve().parents[1] / "notebooks" / "arms"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fewest", type=int, default=7, help="prove the fewest springs up to this n (default 7)")
    args = parser.parse_args()
    print("the rules against physics: every inclusion-minimal balanceable multiset (000 Eqs. 39), complete:")
    for n, signs in ((2, "paper"), (3, "paper"), (4, "paper"), (5, "paper"), (4, "all")):
        arm = feasibility.random_arm(n, 0)
        search = feasibility.minimal_balanceable(arm, signs=signs)
        t0 = time.perf_counter()
        rules = list(iter_configurations(n))
        print(f"  n = {n}, {signs} signs: {len(search.minimal):4d} minimal multisets, {search.nodes:5d} decided, "
              f"{len(search.undecided)} undecided, in {search.seconds:6.2f} s (target n = 5 paper: 15 s); "
              f"R1-R6 admit {len(rules):4d} in {time.perf_counter() - t0:5.2f} s")
    print("  n = 5 on three more arms (the list must be the same):")
    for seed in (1, 2, 3):
        search = feasibility.minimal_balanceable(feasibility.random_arm(5, seed))
        print(f"    arm {seed}: {len(search.minimal)} minimal, sizes {search.sizes()}, {search.nodes} decided, "
              f"{len(search.undecided)} undecided, {search.seconds:.2f} s")
    print("the fewest springs, proved (a design, and every multiset of fewer springs refuted):")
    for n in range(2, args.fewest + 1):
        fewest = rulecheck.fewest_springs(n, max_nodes=5_000_000)
        print(f"  n = {n}: {fewest.springs} spring{'s' if fewest.springs > 1 else ''} (R1-R6's fewest {fewest.rules_fewest}), "
              f"{len(fewest.search.refuted)} multisets of fewer springs refuted ({fewest.search.kinds()}), "
              f"route 2 {fewest.route_two:.1e}, {fewest.seconds:.1f} s")
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
    for name in ("paper000_arm.toml", "industrial_6link.toml"):
        for method, minimise in (("no auxiliary links", False), ("no auxiliary links", True), ("fewest springs", True)):
            t0 = time.perf_counter()
            report = design_arm(ARMS / name, method=method, max_designs=10, minimise_force=minimise)
            best = report.designs[0]
            print(f"design_arm({name}, method={method!r}, minimise_force={minimise}): {len(report.designs)} verified "
                  f"designs from {report.configurations_tried} configurations in {time.perf_counter() - t0:.1f} s; "
                  f"best: {best.spring_count} springs ({best.method}), largest force {best.max_force:.0f} N")
    lengths, masses = [0.30, 0.24, 0.20, 0.15, 0.12, 0.10, 0.08], [4.0, 3.2, 2.8, 1.5, 1.2, 1.0, 0.8]
    print("n - 1 ground springs (solved, force minimised, verified on 1000 poses), and n - 2 screened:")
    for n in range(3, 9):
        arm = serial_chain(r=lengths[:n - 1], d=[x / 2 for x in lengths[:n - 1]], m=masses[:n - 1], g=9.8)
        t0 = time.perf_counter()
        design = ground_spring_design(arm, max_extension=0.3, samples=1000, seed=n)
        dt = time.perf_counter() - t0
        line = f"  n = {n}: {design.spring_count} springs in {dt:5.2f} s, largest force {design.max_force:5.0f} N"
        if n <= 6:
            t0 = time.perf_counter()
            candidates, survivors = relaxation_screen(arm, n - 2)
            line += f"; {n - 2} springs: {candidates:,} sets, {survivors} pass, in {time.perf_counter() - t0:.1f} s"
        print(line)


if __name__ == "__main__":
    main()
