"""Benchmark: `make figures` cold and warm, per notebook, beside the times before the speed-ups.

A fresh clone of the committed project (its HEAD) in a temporary folder, run with this
virtual environment's Python, as `make figures` runs it: every notebook executed with
papermill in parallel (one kernel per core), then the site. Cold: nothing cached (no
notebook keys, no compiled numba kernels). Warm: the same two commands again, nothing
changed. Then `git status` in the clone must be clean (the figures and claims it wrote
are the committed ones, byte for byte).

    make bench
    python benchmarks/bench_figures.py            # about 3 minutes on 2 cores
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
    #              commit 4d58831, in parallel on 2 cores, the runner's own lines), the same machine
    "juang2022_spring_efficiency": (96, 121), "juang2023_spatial_balance": (21, 217),
    "lenzo2017_two_spring_arm": (4, 9), "lin2010_pseudobases": (60, 155),
    "springlab_design_your_arm": (205, 214), "zhang2023_dyad": (25, 43),
}
"""0abe5ae tested the rules against physics to n = 4 in the 000 notebook; from 4d58831 on, to n = 5."""
EARLIER_COLD = (430, 440)  # s, the whole of `make figures` from a fresh clone
EARLIER_WARM = (430, 0.6)  # s, again with nothing changed (0abe5ae had no cache: it ran everything again)


def run_figures(clone: Path) -> tuple[float, dict[str, float], str]:
    env = dict(os.environ, PYTHONPATH=str(clone), OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
               MKL_NUM_THREADS="1", PYTHONDONTWRITEBYTECODE="")
    t0 = time.perf_counter()
    out = ""
    for args in (["-m", "springlab.workbench.notebooks", "--out", "build/notebooks", "--site", "build/site"],
                 ["-m", "springlab.workbench.site", "--notebooks", "build/notebooks", "--site", "build/site",
                  "--figures", "figures"]):
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
    args = parser.parse_args(argv)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    print(f"make figures: a fresh clone of HEAD {head or '?'} on {os.cpu_count()} cores with this venv, "
          "beside two earlier commits on the same machine")
    cold = warm = None
    per: dict[str, float] = {}
    clean = "not run"
    if not args.skip:
        with tempfile.TemporaryDirectory(prefix="springlab-bench-") as tmp:
            clone = Path(tmp) / "springlab"
            subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
            cold, per, _ = run_figures(clone)
            warm, _, warm_out = run_figures(clone)
            status = subprocess.run(["git", "status", "--porcelain"], cwd=clone, capture_output=True, text=True).stdout
            clean = "clean" if not status.strip() else f"NOT clean:\n{status}"
            if "running " in warm_out:
                clean += " (the warm run re-ran a notebook)"
    width = len("make figures, warm (nothing changed)")
    print(f"  {'notebook (s)':<{width}}  {'0abe5ae':>8}  {'4d58831':>8}  {'now':>8}")
    for name, (first, second) in EARLIER.items():
        now = f"{per[name]:8.0f}" if name in per else f"{'-':>8}"
        print(f"  {name:<{width}}  {first:8.0f}  {second:8.0f}  {now}")
    fmt = lambda x: f"{x:8.1f}" if x is not None else f"{'-':>8}"  # noqa: E731
    print(f"  {'make figures, cold (fresh clone)':<{width}}  {EARLIER_COLD[0]:8.0f}  {EARLIER_COLD[1]:8.0f}  "
          f"{fmt(cold)}   (target 60)")
    print(f"  {'make figures, warm (nothing changed)':<{width}}  {EARLIER_WARM[0]:8.0f}  {EARLIER_WARM[1]:8.1f}  "
          f"{fmt(warm)}   (target 5)")
    print(f"  git status after both runs: {clean}")


if __name__ == "__main__":
    main()
