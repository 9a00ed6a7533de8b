"""`make bench`: every benchmark in turn, its output shown as it runs and written to
``benchmarks/RESULTS.md``, the book's Performance page (with the date, the commit and the machine).

Each benchmark is its own script (run one alone with ``python benchmarks/bench_energy.py``); this
runner only collects what they print. Tables they print stay Markdown tables; every other line is
kept as printed, in a text block. A benchmark that fails stops the run, and RESULTS.md is left as
it was.
"""

from __future__ import annotations

import datetime
import os
import platform
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
BENCHES = ("bench_energy", "bench_sim", "bench_efficiency", "bench_design", "bench_figures", "bench_real_arms",
           "bench_layouts", "bench_catalogue")
"""In the order they run: the routes first, then the searches, `make figures`, and the real arms."""


def _title(script: Path) -> str:
    """The first line of a benchmark's docstring, without its 'Benchmark: ', as a heading (capitalised)."""
    import ast

    doc = ast.get_docstring(ast.parse(script.read_text())) or script.stem
    title = doc.splitlines()[0].removeprefix("Benchmark: ").rstrip(".")
    return title[:1].upper() + title[1:]


def as_markdown(lines: list[str]) -> list[str]:
    """A benchmark's printed lines as Markdown: runs of table rows ('|' first) as they are, every other
    run in a text block (so that nothing printed is read as Markdown it was not meant to be)."""
    out, text = [], []

    def flush():
        while text and not text[-1].strip():
            text.pop()
        if text:
            out.extend(["```text", *text, "```", ""])
        text.clear()

    table = False
    for line in lines:
        if line.startswith("|"):
            if not table:
                flush()
            out.append(line)
            table = True
            continue
        if table:
            out.append("")
            table = False
        if line.strip() or text:
            text.append(line)
    if table:
        out.append("")
    flush()
    return out


def _machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}"


def main(argv=None) -> int:
    names = list(argv if argv is not None else sys.argv[1:]) or list(BENCHES)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                            cwd=HERE.parent).stdout.strip() or "unknown"
    started = datetime.datetime.now(datetime.timezone.utc)
    page = ["# Performance", "",
            f"`make bench` on {started:%Y-%m-%d} (UTC), commit {commit}, on {_machine()}; BLAS on one thread. "
            "Each section is one script of `benchmarks/`, its output as printed; timings vary by 5-10 % from "
            "run to run. This page is written by `make bench` (benchmarks/run_all.py), never by hand.", ""]
    for name in names:
        script = HERE / f"{name}.py"
        print(f"== {name}", flush=True)
        lines = []
        with subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True,
                              cwd=HERE.parent) as run:
            for line in run.stdout:
                print(line, end="", flush=True)
                lines.append(line.rstrip("\n"))
        if run.returncode != 0:
            print(f"run_all: {name} failed (exit {run.returncode}); RESULTS.md left as it was", file=sys.stderr)
            return run.returncode
        page += [f"## {_title(script)}", "", f"`python benchmarks/{name}.py`", "", *as_markdown(lines)]
    if names == list(BENCHES):  # a subset prints, and leaves the page as it was
        (HERE / "RESULTS.md").write_text("\n".join(page).rstrip() + "\n")
        print(f"wrote {HERE / 'RESULTS.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
