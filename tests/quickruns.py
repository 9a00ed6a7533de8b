"""Each notebook run once per test run with quick=True, by whichever test needs it first.

The notebook tests (tests/test_notebooks.py) check every quick run, and the book test
(tests/test_book.py) builds the whole book from the same runs and opens it in Chromium. Under
pytest-xdist the two may sit on different workers: a file lock per notebook lets the first
caller run it and the others wait for it and read its output. A run is kept for the test run
that made it (xdist's run id) and made again in the next.

The same lock shares an expensive result other than a notebook (a real arm's design that several test
modules check): ``shared(name, build)`` builds it once per test run and the other workers read its
pickle."""

import fcntl
import os
import pickle
import shutil
from collections.abc import Callable
from pathlib import Path

from springlab.workbench.notebooks import notebook_paths, run_notebook

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build" / "test-notebooks"
FIGURES = OUT / "figures"
STEMS = tuple(p.stem for p in notebook_paths(ROOT / "notebooks"))


def _run_id() -> str:
    return os.environ.get("PYTEST_XDIST_TESTRUNUID", f"pid {os.getpid()}")


def once(folder: Path, name: str, make: Callable[[], None]) -> None:
    """``make()`` once in this test run, by whichever worker asks first: under the file lock
    ``folder/<name>.lock``, unless ``folder/<name>.run`` says this run (xdist's run id) made it already."""
    folder.mkdir(parents=True, exist_ok=True)
    done = folder / f"{name}.run"
    with open(folder / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (done.exists() and done.read_text() == _run_id()):
            done.unlink(missing_ok=True)
            make()
            done.write_text(_run_id())


def quick_run(stem: str) -> Path:
    """``build/test-notebooks/<stem>.ipynb``, notebook ``stem`` executed with quick=True in this
    test run (its figures and claims in ``build/test-notebooks/figures/<stem>``)."""
    executed = OUT / f"{stem}.ipynb"

    def make():
        executed.unlink(missing_ok=True)
        shutil.rmtree(FIGURES / stem, ignore_errors=True)
        run_notebook(ROOT / "notebooks" / f"{stem}.ipynb", executed,
                     {"quick": True, "figures_dir": str(FIGURES / stem)})

    once(OUT, stem, make)
    return executed


def shared(name: str, build: Callable[[], object]) -> object:
    """``build()``, called once in this test run by whichever worker asks first (:func:`once`); every
    caller reads its pickle (``build/test-notebooks/shared/<name>.pickle``)."""
    stored = OUT / "shared" / f"{name}.pickle"
    once(OUT / "shared", name, lambda: stored.write_bytes(pickle.dumps(build())))
    return pickle.loads(stored.read_bytes())
