"""Benchmark: `make figures` cold and warm, per notebook, beside the times before the speed-ups.

A fresh clone of the committed project (its HEAD) in a temporary folder, run with this
virtual environment's Python, as `make figures` runs it: every notebook executed with
papermill in parallel (one kernel per core), then the site. Cold: nothing cached (no
notebook keys, no compiled numba kernels). Warm: the same two commands again, nothing
changed. Then `git status` in the clone must be clean (the figures and claims it wrote
are the committed ones, byte for byte). Before that, an earlier commit (``--before``) is
cloned and run cold the same way, with the commands of its own Makefile, so that before
and after are measured on one machine on one day.

    make bench
    python benchmarks/bench_figures.py            # about 4 minutes on 2 cores
    python benchmarks/bench_figures.py --before ''  # without the earlier commit's run
    python benchmarks/bench_figures.py --skip     # print only the earlier figures
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

EARLIER = {  # s per notebook: (commit 0abe5ae, one after another, papermill's cell timings;
    #              commit 4d58831, in parallel on 2 cores, the runner's own lines), on the machine of their day
    "juang2022_spring_efficiency": (96, 121), "juang2023_spatial_balance": (21, 217),
    "lenzo2017_two_spring_arm": (4, 9), "lin2010_pseudobases": (60, 155),
    "springlab_design_your_arm": (205, 214), "zhang2023_dyad": (25, 43),
}
"""0abe5ae tested the rules against physics to n = 4 in the 000 notebook; from 4d58831 on, to n = 5."""
BEFORE = ""
"""No earlier commit by default: the last one before the book, cf00226 (52.6-57.4 s cold on this machine), builds
its site with jupyter-server-mathjax, which the pinned environment no longer holds. ``--before COMMIT`` runs a
commit that this environment runs, so that before and after share a machine and a day."""
TARGET_COLD, TARGET_WARM = 45, 2  # s: the targets of the issue on reproducible figures (a fresh clone, then nothing changed)
EARLIER_COLD = (430, 440)  # s, the whole of `make figures` from a fresh clone
EARLIER_WARM = (430, 0.6)  # s, again with nothing changed (0abe5ae had no cache: it ran everything again)


def figures_commands(clone: Path) -> list[list[str]]:
    """The commands of the clone's own ``make figures`` recipe, with this venv's Python: an
    earlier commit runs as it ran then."""
    lines = (clone / "Makefile").read_text().splitlines()
    start = lines.index(next(line for line in lines if line.startswith("figures:")))
    out = []
    for line in lines[start + 1:]:
        if not line.startswith("\t"):
            break
        out.append(line.strip().replace("$(BIN)/python", sys.executable).split()[1:])
    return out


def run_figures(clone: Path) -> tuple[float, dict[str, float], str]:
    env = dict(os.environ, PYTHONPATH=str(clone), OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
               MKL_NUM_THREADS="1", PYTHONDONTWRITEBYTECODE="")
    t0 = time.perf_counter()
    out = ""
    for args in figures_commands(clone):
        done = subprocess.run([sys.executable, *args], cwd=clone, env=env, capture_output=True, text=True)
        out += done.stdout + done.stderr
        if done.returncode:
            raise SystemExit(f"`{' '.join(args)}` failed in {clone}:\n{out[-4000:]}")
    wall = time.perf_counter() - t0
    per = {m.group(1): float(m.group(2)) for m in re.finditer(r"done notebooks/(\S+)\.ipynb in (\d+) s", out)}
    return wall, per, out


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--skip", action="store_true", help="do not run: print the earlier figures only")
    parser.add_argument("--before", default=BEFORE,
                        help=f"an earlier commit run cold in the same run, as its own Makefile ran it "
                             f"(default {BEFORE}; '' for none)")
    args = parser.parse_args(argv)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    print(f"make figures: a fresh clone of HEAD {head or '?'} on {os.cpu_count()} cores with this venv"
          + (f", and of {args.before} before it, in this run" if args.before and not args.skip else "")
          + "; beside two earlier commits measured on an earlier machine")
    cold = warm = before = None
    per: dict[str, float] = {}
    per_before: dict[str, float] = {}
    clean = "not run"
    if not args.skip:
        with tempfile.TemporaryDirectory(prefix="springlab-bench-") as tmp:
            if args.before:
                old = Path(tmp) / "before"
                subprocess.run(["git", "clone", "-q", str(ROOT), str(old)], check=True)
                subprocess.run(["git", "checkout", "-q", args.before], cwd=old, check=True)
                before, per_before, _ = run_figures(old)
            clone = Path(tmp) / "springlab"
            subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
            cold, per, _ = run_figures(clone)
            warm, _, warm_out = run_figures(clone)
            status = subprocess.run(["git", "status", "--porcelain"], cwd=clone, capture_output=True, text=True).stdout
            clean = "clean" if not status.strip() else f"NOT clean:\n{status}"
            if "running " in warm_out:
                clean += " (the warm run re-ran a notebook)"
    width = len("make figures, warm (nothing changed)")
    label = (args.before or "before")[:8]
    print(f"  {'notebook (s)':<{width}}  {'0abe5ae':>8}  {'4d58831':>8}  {label:>8}  {'now':>8}")
    fmt = lambda x: f"{x:8.1f}" if x is not None else f"{'-':>8}"  # noqa: E731
    for name in sorted(set(EARLIER) | set(per) | set(per_before)):  # a notebook newer than the earlier commits: '-'
        first, second = EARLIER.get(name, (None, None))
        print(f"  {name:<{width}}  {fmt(first)}  {fmt(second)}  {fmt(per_before.get(name))}  {fmt(per.get(name))}")
    print(f"  {'make figures, cold (fresh clone)':<{width}}  {EARLIER_COLD[0]:8.0f}  {EARLIER_COLD[1]:8.0f}  "
          f"{fmt(before)}  {fmt(cold)}   (target {TARGET_COLD:g})")
    print(f"  {'make figures, warm (nothing changed)':<{width}}  {EARLIER_WARM[0]:8.0f}  {EARLIER_WARM[1]:8.1f}  "
          f"{'':>8}  {fmt(warm)}   (target {TARGET_WARM:g})")
    print(f"  git status after both runs of HEAD: {clean}")


if __name__ == "__main__":
    main()
