"""Benchmark: springs made of stock parts (springlab.design.catalogue, --catalog).

The seconds the stock choice adds to ``springlab design``'s default design of the SO-101 (tip its gripper),
the UR5 and the double pendulum: each designed as the command does (belts, each rope over a pulley sized to it,
the hardware carried), without a catalogue and with one, and per realised spring the part chosen (or why
none), its working length and pull against its catalogue's limits, and the share of each loaded joint's peak
removed with the hardware carried (route 2 on the design's poses).

The catalogue is springlab's made-up series (springlab.design.catalogue.example_rows: 120 music-wire parts
from its own winding formulas), not a vendor's: springlab ships no vendor's stock table yet, so this measures
the choice's cost and what it reaches on such a series, not what any vendor's parts reach.

Target (issue's): choosing stock parts <= 10 s an arm.

    make bench
    python benchmarks/bench_catalogue.py
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from springlab.design.arms import design_model
from springlab.design.catalogue import example_rows, read_catalogue, write_catalogue
from springlab.energy import geometry
from springlab.model.robots import load_robot


def _shares(design) -> str:
    peak = np.max(np.abs(geometry.gravity_torques(design.massed, design.q)), axis=0)
    left = np.max(np.abs(geometry.joint_torques(design.massed, design.realised, design.q)), axis=0)
    return ", ".join(f"{100 * (1 - left[i] / peak[i]):.1f}" for i in design.structure.loaded if peak[i] > 0)


def main() -> None:
    with tempfile.TemporaryDirectory() as folder:
        catalogue = read_catalogue(write_catalogue(Path(folder) / "series.csv", example_rows()))
    print(f"catalogue: springlab's made-up series, {len(catalogue)} parts (not a vendor's)\n")
    print("| arm | custom coils (s) | stock parts (s) | added by the stock choice (s) | target (s) "
          "| loaded joints' peaks removed, custom / stock parts, hardware carried (%) |")
    print("|---|---|---|---|---|---|")
    details = []
    for label in ("SO-101", "UR5", "double pendulum"):
        model = load_robot(label)
        start = time.perf_counter()
        custom = design_model(model, pulley_radius=None, layout="auto")
        middle = time.perf_counter()
        stocked = design_model(model, pulley_radius=None, layout="auto", catalogue=catalogue)
        end = time.perf_counter()
        added = (end - middle) - (middle - start)
        print(f"| {label} | {middle - start:.1f} | {end - middle:.1f} | {added:.1f} | 10 | "
              f"{_shares(custom)} / {_shares(stocked)} |")
        details.append((label, stocked))
    for label, design in details:
        print(f"\n{label}: each spring's part")
        print(design.stock_table())


if __name__ == "__main__":
    main()
