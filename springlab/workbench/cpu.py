"""The same figures and claims on another CPU: ``python -m springlab.workbench.cpu``.

``make figures`` must leave ``git status`` clean on any machine, whatever its CPU. What moves with
the CPU is round-off: numpy dispatches its loops to the widest SIMD the CPU has (AVX-512, AVX2,
SSE), OpenBLAS picks its kernels by core type, numba compiles for the host CPU, and an optimiser
or a search can carry such a difference into its last digits or, near a tie, into its answer.

This module runs the notebooks twice with ``quick=True``: as usual, then on a narrowed CPU
(:func:`narrowed_environment`: numpy's SIMD dispatch off, OpenBLAS's kernels of an older core,
numba's generic target) over a copy of what the first run wrote, as a user's clone on another
machine starts from the committed files. What the second run leaves (claims, figures, animations)
must be byte for byte what the first wrote (:func:`differences`). The claims carry only the digits their tolerance gives them
(:mod:`springlab.workbench.claims`), and a figure is rewritten only when its pixels change
(:mod:`springlab.workbench.images`), so the two runs must write the same bytes.
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from springlab.errors import SpringlabError

COMPARED = ("*.json", "*.png", "*.svg", "*.gif", "*.md")
"""The files of a notebook's figures folder that are compared."""


def narrowed_environment(base: dict | None = None) -> dict:
    """``base`` (default: this process's environment) with the CPU narrowed for numpy, OpenBLAS
    and numba: ``NPY_DISABLE_CPU_FEATURES`` lists every SIMD target numpy would dispatch to on
    this CPU (its baseline is left, as on a CPU without them), ``OPENBLAS_CORETYPE`` names an
    older core (Sandybridge on x86-64: AVX without AVX2 or FMA; ARMv8 on arm64) and
    ``NUMBA_CPU_NAME=generic`` compiles numba's kernels for no particular CPU."""
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__

    env = dict(os.environ if base is None else base)
    on = [name for name in __cpu_dispatch__ if __cpu_features__.get(name)]
    if on:
        env["NPY_DISABLE_CPU_FEATURES"] = " ".join(on)
    machine = platform.machine().lower()
    if machine in ("x86_64", "amd64"):
        env["OPENBLAS_CORETYPE"] = "Sandybridge"
    elif machine in ("aarch64", "arm64"):
        env["OPENBLAS_CORETYPE"] = "ARMV8"
    env["NUMBA_CPU_NAME"] = "generic"
    return env


def differences(one, two) -> list[str]:
    """The files (matching :data:`COMPARED`) under folders ``one`` and ``two`` that differ in
    their bytes or exist in one only, as paths relative to the folders."""
    one, two = Path(one), Path(two)

    def files(root):
        return {p.relative_to(root) for pattern in COMPARED for p in root.rglob(pattern) if p.is_file()}

    a, b = files(one), files(two)
    out = [f"{p}: only in {one if p in a else two}" for p in sorted(a ^ b)]
    out += [str(p) for p in sorted(a & b) if (one / p).read_bytes() != (two / p).read_bytes()]
    return out


def run_notebooks(stems, figures, env: dict, jobs: int = 1) -> None:
    """Run notebooks ``stems`` with quick=True, their figures under ``figures/<stem>``, in
    subprocesses with environment ``env`` (``jobs`` at once)."""
    from concurrent.futures import ThreadPoolExecutor

    from springlab.workbench.notebooks import NOTEBOOK_DIR

    def one(stem):
        out = Path(figures).parent / "notebooks" / f"{stem}.ipynb"
        code = ("import sys; from springlab.workbench.notebooks import run_notebook; "
                "run_notebook(sys.argv[1], sys.argv[2], {'quick': True, 'figures_dir': sys.argv[3]})")
        done = subprocess.run([sys.executable, "-c", code, str(NOTEBOOK_DIR / f"{stem}.ipynb"), str(out),
                               str(Path(figures).resolve() / stem)], env=env, capture_output=True, text=True)
        if done.returncode:
            raise SpringlabError(f"notebook {stem} failed (quick run, its output in {out}):\n{done.stderr[-2000:]}")

    with ThreadPoolExecutor(max_workers=jobs) as pool:
        list(pool.map(one, stems))


def main(argv=None) -> int:
    from springlab.workbench.notebooks import notebook_paths

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("stems", nargs="*", help="notebooks to run (default: all)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="notebooks run at once")
    parser.add_argument("--keep", help="folder to keep both runs in (default: a temporary one)")
    parser.add_argument("--exclude", nargs="*", default=[], help="notebooks left out (say why where you call it)")
    args = parser.parse_args(argv)
    known = [p.stem for p in notebook_paths()]
    unknown = sorted((set(args.stems) | set(args.exclude)) - set(known))
    if unknown:
        parser.error(f"no notebook named {', '.join(unknown)} in notebooks/ (there are: {', '.join(known)})")
    if args.jobs < 1:
        parser.error(f"--jobs must be >= 1, got {args.jobs}")
    stems = [s for s in (args.stems or known) if s not in args.exclude]
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(args.keep or tmp)
        usual, narrowed = root / "usual" / "figures", root / "narrowed" / "figures"
        for folder in (usual, narrowed):
            (folder.parent / "notebooks").mkdir(parents=True, exist_ok=True)
        env = dict(os.environ)
        try:
            print(f"this CPU: {len(stems)} notebooks (quick) ...", flush=True)
            run_notebooks(stems, usual, env, args.jobs)
            shutil.copytree(usual, narrowed, dirs_exist_ok=True)  # as a clone starts from the committed files
            print("the narrowed CPU, over the first run's files ...", flush=True)
            run_notebooks(stems, narrowed, narrowed_environment(env), args.jobs)
        except SpringlabError as err:
            print(f"FAILED: {err}", file=sys.stderr)
            return 1
        found = differences(usual, narrowed)
    names = narrowed_environment({})
    print("narrowed CPU: " + ", ".join(f"{k}={v!r}" for k, v in sorted(names.items())))
    if found:
        print(f"{len(found)} files differ between the usual and the narrowed CPU:\n  " + "\n  ".join(found))
        return 1
    left = f" ({', '.join(args.exclude)} left out)" if args.exclude else ""
    print(f"the same bytes on both CPUs: {len(stems)} notebooks (quick), their claims and figures{left}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
