"""Benchmark: springs an engineer can mount (springlab.design.layouts, springlab.design.collision).

The twelve arms of the real-robots work, then every other serial arm of example-robot-data, each
designed as ``springlab design`` does by default (``layout='auto'``: the belt layout where the loaded
joints, the light ones left out, form a planar chain, else paper 001's pseudobases), each cable a stocked
stainless rope over a pulley sized to it, with the springs' hardware (coils, ropes, pulleys, brackets,
posts, belts or RSSR modules) carried. Per arm: the layout, the
springs, the share of each loaded joint's peak removed by the realised springs carrying their hardware,
each spring's nearest approach to a link on the URDF's own meshes (coal), where it runs into one the
share of the workspace kept by the narrower ranges on which the same springs clear (springlab.design.narrowing,
re-measured on fresh poses), the longest coil over the
length it is held to (its link's; a coil on a bracket of the level frame: the longer link's at its
joint), the springs' and the hardware's mass beside the arm's, the design's status, and its seconds.

Targets (issue's): the UR5 and the UR10 >= 95 % of the shoulder's and the elbow's peaks, the UR3
>= 90 %, the SO-101 >= 90 % of shoulder_lift's and elbow_flex's, all with <= 3 springs; no spring,
cable or coil within 5 mm of a link; the longest coil no longer than its room; every serial arm of
example-robot-data clear of its links, each saying what share it reached; <= 60 s an arm.

    make bench
    python benchmarks/bench_layouts.py
"""

from __future__ import annotations

import time

import numpy as np

from springlab.design.arms import design_model
from springlab.design.hardware import coil_bound
from springlab.energy import geometry
from springlab.errors import SpringlabError
from springlab.model.robots import OTHER_ARMS, ROBOTS, load_robot
from springlab.workbench.real_arms import hardware_table


def _row(label: str):
    """The arm designed as ``springlab design`` does by default; its table row and the design (None if refused)."""
    model = load_robot(label)
    start = time.perf_counter()
    try:
        design = design_model(model, pulley_radius=None, layout="auto")
    except SpringlabError as err:  # a refusal is the finding here
        return (label, "REFUSED", 0, str(err), "", "", "", "", "refused", f"{time.perf_counter() - start:.1f}"), None
    seconds = time.perf_counter() - start
    if not design.realised:
        return (label, design.method, 0, "", "", "", "", "", "passed", f"{seconds:.1f}"), design
    peak = np.max(np.abs(geometry.gravity_torques(design.massed, design.q)), axis=0)
    left = np.max(np.abs(geometry.joint_torques(design.massed, design.realised, design.q)), axis=0)
    shares = ", ".join(f"{100 * (1 - left[i] / peak[i]):.1f}" for i in design.structure.loaded)
    gaps = [row[4] for row in design.clearance.rows] if design.clearance else []
    mass = sum(fit.coil.mass for fit in design.coils)
    hardware = float(np.sum(design.massed.mass) - np.sum(design.model.mass))
    bounds = [coil_bound(design.model, s, fit) for s, fit in zip(design.realised, design.coils, strict=True)]
    worst = max(fit.coil.max_length / bound if bound > 0 else np.inf  # a link of no length: no room at all
                for fit, bound in zip(design.coils, bounds, strict=True))
    status = "passed" if not design.flags() else f"flagged ({len(design.flags())})"
    best = max(design.narrowed, key=lambda n: n.kept, default=None)
    clear = ("the whole" if not (design.clearance and design.clearance.failing()) else "none found" if best is None
             else f"{100 * best.kept:.0f} % ({best.workspace(design.model)})")
    return (label, design.method.split(":")[0], len(design.realised), shares,
            f"{1e3 * min(gaps):.0f}" if gaps else "-", clear, f"{worst:.2f}",
            f"{mass:.2f} / {hardware:.2f} / {float(np.sum(model.mass[1:])):.1f}", status, f"{seconds:.1f}"), design


def _table(rows) -> None:
    print("| arm | layout | springs | loaded joints' peaks removed, hardware carried (%) | nearest link (mm) "
          "| workspace the springs clear (kept, narrowed) | longest coil / its room "
          "| springs' / hardware's / arm's mass (kg) | status | seconds |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        print("| " + " | ".join(str(v) for v in row) + " |")


def main() -> None:
    rows, belts = [], {}
    for label in ROBOTS:
        row, design = _row(label)
        rows.append(row)
        if design is not None and (design.model.belts or design.method.startswith("belts")):
            belts[label] = design
    _table(rows)
    if belts:
        print("\nthe belt layouts, spring by spring:")
        print(hardware_table(belts))
    others = [_row(label)[0] for label in OTHER_ARMS]
    passed = sum(row[8] == "passed" for row in others)  # the status column
    print(f"\nevery other serial arm of example-robot-data, designed the same way: {passed} of {len(others)} pass\n")
    _table(others)


if __name__ == "__main__":
    main()
