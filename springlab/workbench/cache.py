"""What an executed notebook depends on, and a cache keyed by it (under ``build/cache``).

A notebook is re-executed only when something it depends on changed. Its key is the
SHA-256 of the contents of:

* the notebook file and the parameters it runs with;
* every springlab module it imports, transitively, by the static import graph of
  grimp (the library import-linter uses; imports inside functions count), with the
  package ``__init__`` files on the way and the package's lazy exports
  (``springlab.design_arm`` -> ``springlab.design.rank``) resolved; if grimp is not
  installed, every springlab source file;
* the data the notebooks read (``notebooks/arms/``), the figure style
  (``springlab.mplstyle``) and the pinned environment (``pyproject.toml``,
  ``constraints.txt``), with the Python version.

So a change to one library module re-runs the notebooks that import it, and no other.
The cache holds only keys; the executed notebooks stay in ``build/notebooks`` and the
figures in ``figures/``: a key is reused only when they exist.
"""

from __future__ import annotations

import ast
import hashlib
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "springlab"
SHARED_INPUTS = ("pyproject.toml", "constraints.txt", "springlab/workbench/springlab.mplstyle")
DATA_DIRS = ("notebooks/arms",)


def _module_file(module: str) -> Path | None:
    base = ROOT.joinpath(*module.split("."))
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def imported_modules(notebook) -> set[str]:
    """The springlab modules a notebook's code cells name in their imports or as attributes
    (``springlab.geometry`` through the package's lazy exports)."""
    from springlab import LAZY_EXPORTS as lazy

    cells = json.loads(Path(notebook).read_text())["cells"]
    source = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
    code = "\n".join(line for line in source.splitlines() if not line.lstrip().startswith(("%", "!")))
    found = {"springlab"}
    try:
        tree = ast.parse(code)
    except SyntaxError:
        tree = None
    for node in ast.walk(tree) if tree else ():
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("springlab")}
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("springlab"):
            found.add(node.module)
            found |= {f"{node.module}.{a.name}" for a in node.names}
    found |= set(re.findall(r"\bspringlab(?:\.\w+)+", code))
    out = set()
    for name in found:
        parts = name.split(".")
        while parts and _module_file(".".join(parts)) is None:
            parts.pop()
        if parts:
            out.add(".".join(parts))
    # ``from springlab import design_arm``: a lazy export named at the top level
    out |= {lazy[n][0] for n in re.findall(r"\bspringlab\.(\w+)", code) + _top_level_names(tree) if n in lazy}
    return out


def _top_level_names(tree) -> list[str]:
    if tree is None:
        return []
    return [a.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.module == "springlab"
            for a in node.names]


def module_closure(modules) -> set[Path]:
    """The files of ``modules`` and of every springlab module they import, transitively,
    with the ``__init__`` of each package on the way."""
    try:
        import grimp
    except ImportError:  # no import graph: depend on the whole package
        return set(PACKAGE.rglob("*.py"))
    graph = grimp.build_graph("springlab", cache_dir=None)
    names = set()
    for module in modules:
        if module in graph.modules:
            names |= {module} | graph.find_upstream_modules(module)
    for name in list(names):
        parts = name.split(".")
        names |= {".".join(parts[:k]) for k in range(1, len(parts))}
    # the package's __init__ loads its lazy exports on demand: follow what it imports eagerly
    names |= {"springlab"} | graph.find_upstream_modules("springlab")
    return {f for f in map(_module_file, names) if f is not None}


def notebook_dependencies(notebook) -> list[Path]:
    """Every file a notebook's results depend on (module docstring), sorted."""
    files = {Path(notebook).resolve()} | module_closure(imported_modules(notebook))
    files |= {ROOT / p for p in SHARED_INPUTS if (ROOT / p).is_file()}
    for folder in DATA_DIRS:
        files |= {p for p in (ROOT / folder).rglob("*") if p.is_file()}
    return sorted(files)


def digest(files, extra=None) -> str:
    """SHA-256 of the files' paths (relative to the project) and contents, and of ``extra``
    (anything JSON can write), with the Python version."""
    h = hashlib.sha256()
    h.update(sys.version.encode())
    h.update(json.dumps(extra, sort_keys=True, default=str).encode())
    for path in sorted(Path(f).resolve() for f in files):
        name = path.relative_to(ROOT) if path.is_relative_to(ROOT) else path
        h.update(str(name).encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


class Cache:
    """Keys of finished work under ``folder`` (one small file each)."""

    def __init__(self, folder="build/cache"):
        self.folder = Path(folder)

    def fresh(self, name: str, key: str, outputs=()) -> bool:
        """True when ``name`` was last done with ``key`` and its outputs still exist."""
        stored = self.folder / f"{name}.key"
        return stored.is_file() and stored.read_text() == key and all(Path(p).exists() for p in outputs)

    def store(self, name: str, key: str) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)
        (self.folder / f"{name}.key").write_text(key)

    def forget(self, name: str) -> None:
        (self.folder / f"{name}.key").unlink(missing_ok=True)
