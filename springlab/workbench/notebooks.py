"""Run the notebooks with papermill: ``python -m springlab.workbench.notebooks``.

Every notebook in ``notebooks/`` is executed in that folder (so its relative
paths, e.g. ``../figures/<stem>``, resolve) and the executed copy is written to
``--out``. Any failing notebook makes the command fail.

The notebooks run in parallel, one kernel per core (``--jobs``), the longest first
(:func:`expected_seconds`). A notebook whose
inputs have not changed since its last successful run is not run again: its key
(:mod:`springlab.workbench.cache`: the notebook, its parameters, the springlab modules
it imports, the arm files, the style and the environment) is kept under
``build/cache``; ``--no-cache`` runs everything.

The book (:mod:`springlab.workbench.site`) is built from the executed copies afterwards.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
"""Set to 1 for the kernels unless already set: with a kernel per core, a BLAS that starts a
thread per core in every kernel oversubscribes the cores (the six-link design search took
20.3 s with the default threads, 18.4 s with one, alone on 2 cores)."""

NOTEBOOK_DIR = Path("notebooks")
FIGURES_DIR = Path("figures")


def notebook_paths(directory=NOTEBOOK_DIR) -> list[Path]:
    """The notebooks to run, sorted by name (checkpoints and drafts skipped)."""
    return sorted(p for p in Path(directory).glob("*.ipynb") if not p.name.startswith("_"))


def skip_unused_format_checker() -> None:
    """Keep jsonschema from importing ``rfc3987_syntax``. nbformat validates notebooks with
    jsonschema, which loads that package, when installed (Jupyter Server's dependencies bring
    it), to check strings of the 'iri' format; its import compiles a grammar, 0.9 s in every
    process that reads a notebook (the runner's workers, the page renderer, the site step).
    The notebook schema has no such string, so validation is unchanged."""
    sys.modules.setdefault("rfc3987_syntax", None)  # None: 'import rfc3987_syntax' raises ImportError


def _ipc_kernel_manager():
    """jupyter_client's kernel manager with the kernel's sockets on local IPC files instead of TCP ports:
    nothing listens on the network, and the kernel has no reason to warn that its TCP traffic is
    unencrypted. Each kernel's sockets get a folder of their own (jupyter_client's default path,
    'kernel-ipc-N', is shared by kernels started side by side, whose messages then cross), removed
    with the kernel. A kernel is shut down by request alone, without jupyter_client's SIGINT first."""
    import shutil
    import tempfile

    from jupyter_client.manager import AsyncKernelManager
    from traitlets import default

    class IPCKernelManager(AsyncKernelManager):
        @default("transport")
        def _transport_default(self):
            return "ipc"

        @default("ip")
        def _ip_default(self):
            self._ipc_folder = tempfile.mkdtemp(prefix="springlab-kernel-")
            return str(Path(self._ipc_folder) / "kernel")

        async def _async_interrupt_kernel(self) -> None:
            # jupyter_client sends SIGINT before every shutdown request, for a kernel still busy. nbclient
            # shuts a kernel down only once its cells have finished (a timed-out cell is interrupted
            # on its own, before), so here the signal can only land in whatever handler the kernel is
            # closing, which then logs 'ERROR | KeyboardInterrupt caught in kernel.' on a good run.
            if not self.shutting_down:
                await super()._async_interrupt_kernel()

        async def _async_cleanup_resources(self, restart: bool = False) -> None:
            await super()._async_cleanup_resources(restart=restart)
            if not restart and getattr(self, "_ipc_folder", None):
                shutil.rmtree(self._ipc_folder, ignore_errors=True)

    return IPCKernelManager


def run_notebook(path, out_path, parameters: dict | None = None):
    """Execute one notebook with papermill in its own folder, its kernel on IPC sockets
    (``_ipc_kernel_manager``); returns the executed notebook."""
    skip_unused_format_checker()
    import papermill as pm

    path = Path(path).resolve()
    out_path = Path(out_path).resolve()
    out_path.parent.mkdir(parents=True, exist_ok=True)
    return pm.execute_notebook(
        str(path), str(out_path), parameters=parameters or {}, cwd=str(path.parent),
        kernel_name="python3", progress_bar=False, log_output=False,
        kernel_manager_class=_ipc_kernel_manager(),
    )


def _durations(cache_folder) -> dict:
    """The recorded run times {notebook stem: s} in ``cache_folder/durations.json`` ({} if none or unreadable)."""
    import json

    try:
        known = json.loads((Path(cache_folder) / "durations.json").read_text())
    except (OSError, ValueError):
        return {}
    return known if isinstance(known, dict) else {}


def expected_seconds(nb: Path, cache_folder) -> float:
    """How long the notebook is expected to run (s): its last full run's time, recorded in
    ``cache_folder/durations.json``, else the ``springlab.expected_seconds`` of its metadata
    (measured on 2 cores and kept with the notebook), else 0."""
    import json

    seconds = _durations(cache_folder).get(nb.stem)
    if isinstance(seconds, int | float):
        return float(seconds)
    try:
        hint = json.loads(nb.read_text()).get("metadata", {}).get("springlab", {}).get("expected_seconds", 0)
    except (ValueError, AttributeError, OSError):
        return 0.0
    return float(hint) if isinstance(hint, int | float) else 0.0


def _record_seconds(cache_folder, stem: str, seconds: float) -> None:
    import json

    known = _durations(cache_folder) | {stem: round(seconds, 1)}
    record = Path(cache_folder) / "durations.json"
    record.parent.mkdir(parents=True, exist_ok=True)
    record.write_text(json.dumps(known, indent=1, sort_keys=True) + "\n")


def _run(nb: Path, out: Path, parameters: dict | None) -> float:
    t0 = time.perf_counter()
    run_notebook(nb, out, parameters)
    return time.perf_counter() - t0


def main(argv=None) -> int:
    from springlab.workbench.cache import Cache, digest, notebook_dependencies

    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="build/notebooks", help="folder for the executed notebooks")
    parser.add_argument("--quick", action="store_true", help="run with quick=True (fewer samples)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="notebooks run at once (default: the cores)")
    parser.add_argument("--no-cache", action="store_true", help="run every notebook, changed or not")
    parser.add_argument("--cache", default="build/cache", help="folder for the keys of finished runs")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error(f"--jobs must be >= 1, got {args.jobs}")
    parameters = {"quick": True} if args.quick else None
    for name in THREAD_VARIABLES:  # one kernel per core: a kernel's BLAS and OpenMP keep to it
        os.environ.setdefault(name, "1")
    cache = Cache(args.cache)
    todo, keys = [], {}
    for nb in notebook_paths():
        out = Path(args.out) / nb.name
        keys[nb] = digest(notebook_dependencies(nb), {"parameters": parameters, "out": str(out)})
        if not args.no_cache and cache.fresh(nb.stem, keys[nb], [out, FIGURES_DIR / nb.stem]):
            print(f"unchanged {nb}: reusing {out}", flush=True)
        else:
            todo.append(nb)
    # longest first (the longest-processing-time rule): the last notebook to start is a short one,
    # so the cores finish together instead of one waiting on a long notebook started last
    todo.sort(key=lambda nb: -expected_seconds(nb, args.cache))
    failures = []
    with ProcessPoolExecutor(max_workers=min(args.jobs, max(1, len(todo)))) as pool:
        running = {}
        for nb in todo:
            print(f"running {nb} ...", flush=True)
            cache.forget(nb.stem)
            running[pool.submit(_run, nb, Path(args.out) / nb.name, parameters)] = nb
        for done in as_completed(running):
            nb = running[done]
            try:
                seconds = done.result()
            except Exception as err:  # report every notebook, then fail
                failures.append((nb, err))
                print(f"FAILED {nb}: {type(err).__name__}: {str(err)[:2000]}", file=sys.stderr)
                continue
            cache.store(nb.stem, keys[nb])
            if not args.quick:
                _record_seconds(args.cache, nb.stem, seconds)
            print(f"done {nb} in {seconds:.0f} s", flush=True)
    if failures:
        return 1
    print(f"executed notebooks written to {args.out}/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
