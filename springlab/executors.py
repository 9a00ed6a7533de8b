"""Running independent tasks serially or on a :class:`concurrent.futures.Executor`.

The searches and studies that accept ``executor=`` (:func:`springlab.design.rank.design_arm`,
:func:`springlab.design.ground.relaxation_screen`, :func:`springlab.design.tolerance.tolerance_study`)
cut their work into tasks that carry their own inputs and seeds, and read the results in
submission order. So a run on a process pool or on a dask cluster
(``dask.distributed.Client(...).get_executor()``, the ``dask`` extra) returns exactly what the
serial run returns. ``None`` runs the tasks one after another in this process.
"""

from __future__ import annotations

from springlab.errors import SpringlabError


def check_executor(executor):
    """``executor`` if it is None or has ``submit`` (a concurrent.futures.Executor, or dask's)."""
    if isinstance(executor, type):  # the class has an (unbound) submit too
        raise SpringlabError(f"executor must be an executor instance, got the class {executor.__name__}: "
                             f"pass {executor.__name__}() (e.g. ThreadPoolExecutor(max_workers=2)), or None to run serially")
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise SpringlabError(f"executor must be a concurrent.futures.Executor (with submit), or None to run "
                             f"serially; got {type(executor).__name__}")
    return executor


def map_ordered(executor, fn, tasks) -> list:
    """``[fn(*task) for task in tasks]``, the tasks submitted to ``executor`` at once (None: run here);
    results in the tasks' order. ``fn`` must be a module-level function (picklable)."""
    tasks = list(tasks)
    if executor is None:
        return [fn(*task) for task in tasks]
    futures = [executor.submit(fn, *task) for task in tasks]
    return [f.result() for f in futures]
