"""Run the notebooks with papermill: ``python -m springlab.workbench.notebooks``.

Every notebook in ``notebooks/`` is executed in that folder (so its relative
paths, e.g. ``../figures/<stem>``, resolve) and the executed copy is written to
``--out``. Any failing notebook makes the command fail.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NOTEBOOK_DIR = Path("notebooks")


def notebook_paths(directory=NOTEBOOK_DIR) -> list[Path]:
    """The notebooks to run, sorted by name (checkpoints and drafts skipped)."""
    return sorted(p for p in Path(directory).glob("*.ipynb") if not p.name.startswith("_"))


def run_notebook(path, out_path, parameters: dict | None = None):
    """Execute one notebook with papermill in its own folder; returns the executed notebook."""
    import papermill as pm

    path = Path(path).resolve()
    out_path = Path(out_path).resolve()
    out_path.parent.mkdir(parents=True, exist_ok=True)
    return pm.execute_notebook(
        str(path), str(out_path), parameters=parameters or {}, cwd=str(path.parent),
        kernel_name="python3", progress_bar=False, log_output=False,
    )


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="build/notebooks", help="folder for the executed notebooks")
    parser.add_argument("--quick", action="store_true", help="run with quick=True (fewer samples)")
    args = parser.parse_args(argv)
    failures = []
    for nb in notebook_paths():
        print(f"running {nb} ...", flush=True)
        try:
            run_notebook(nb, Path(args.out) / nb.name, {"quick": True} if args.quick else None)
        except Exception as err:  # report every notebook, then fail
            failures.append((nb, err))
            print(f"FAILED {nb}: {type(err).__name__}: {str(err)[:2000]}", file=sys.stderr)
    if failures:
        return 1
    print(f"executed notebooks written to {args.out}/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
