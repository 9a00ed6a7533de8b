"""Benchmark: route 3 (exudyn), CPU seconds per simulated second.

The paper-000 four-link example with Table 3's exact springs:

* hold test: released at rest at 20 random poses, 2 s each, step 1e-3 s, Newton
  tolerances 1e-12 relative / 1e-14 absolute (the control run at 1e-8 / 1e-10,
  ``simulation.CONTROL_TOLERANCES``: it only has to show motion);
* trajectory: Table 4's path over 30 s, rest to rest, step 1e-2 s, with the
  joints driven by Python offset functions.

    make bench
    python benchmarks/bench_sim.py
"""

from __future__ import annotations

import time

import numpy as np

from springlab import random_directions
from springlab.design.solve import SpringSpec, solve_design
from springlab.energy import simulation as sim
from springlab.model.trajectories import Sweep
from springlab.papers import juang2023 as paper


def main() -> None:
    arm = paper.example_arm()
    specs = [SpringSpec(s.i, s.j, s.pattern, **paper.FREE_CHOICES[(s.i, s.j)])
             for s in paper.EXAMPLE_CONFIGURATION]
    springs = solve_design(arm, specs).springs
    X = random_directions(arm.n, 20, np.random.default_rng(0))

    wall = time.perf_counter()
    hold = sim.hold_test(arm, springs, X, duration=2.0)
    hold_wall = time.perf_counter() - wall

    wall = time.perf_counter()
    torques = sim.holding_torques(arm, springs, X)
    torque_wall = time.perf_counter() - wall

    sweep = Sweep(paper.TABLE_4_INITIAL, paper.TABLE_4_ROTATION, paper.DURATION, law="quintic")
    wall = time.perf_counter()
    run = sim.follow(arm, springs, sweep, samples=301)
    follow_wall = time.perf_counter() - wall

    print("springlab exudyn benchmark: 000 four-link example, Table 3 exact springs")
    for label, r in (("balanced", hold.balanced), ("control, springs x 0.9", hold.control)):
        print(f"hold test, 20 poses x 2 s, {label}: {r.cpu_seconds / r.simulated_seconds:.4f} CPU s per "
              f"simulated s (solver only); max tip drift {r.max_tip_drift:.1e} m")
    print(f"hold test, both runs with model building: {hold_wall:.2f} s wall")
    print(f"holding torques, 20 static solves: {torque_wall:.2f} s wall; "
          f"max |route 3 - route 2| {torques.max_difference:.1e} N m")
    print(f"trajectory, 30 s: {run.cpu_seconds / paper.DURATION:.4f} CPU s per simulated s "
          f"({follow_wall:.2f} s wall); total energy varies {np.ptp(run.total):.1e} J")


if __name__ == "__main__":
    main()
