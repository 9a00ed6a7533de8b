"""The architecture, checked: import contracts (the routes stay independent, the layers
point down), no private names imported across modules, and the error classes."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import springlab
from springlab.errors import (
    AttachmentError,
    GeometryError,
    SolverError,
    SpringlabError,
    UnbalanceableError,
)

ROOT = Path(__file__).resolve().parents[1]
LINT = Path(sys.prefix) / "bin" / "lint-imports"


def lint_imports(root: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(root)}
    return subprocess.run([str(LINT), "--config", str(root / "pyproject.toml"), "--no-cache"], cwd=root,
                          capture_output=True, text=True, env=env)


needs_linter = pytest.mark.skipif(not LINT.exists(), reason="import-linter is not installed (dev extra)")


@needs_linter
def test_import_contracts_are_kept():
    result = lint_imports(ROOT)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Contracts: 6 kept, 0 broken." in result.stdout


@needs_linter
@pytest.mark.parametrize("module, line", [
    # route 2 reaching route 1 through a helper that imports it: a transitive import
    ("energy/geometry.py", "from springlab.design import solve as _solve  # noqa"),
    # route 3 of a mechanism importing its route 1 directly
    ("mechanisms/pseudobase/simulation.py", "from springlab.mechanisms.pseudobase import subsystems  # noqa"),
    # the model importing a layer above it
    ("model/chain.py", "from springlab.workbench import claims  # noqa"),
    # the circles the model and the design once had, hidden inside functions: each breaks a layer
    ("model/springs.py", "def _f():\n    from springlab.model.chain import Chain  # noqa"),
    ("model/urdf.py", "def _f():\n    from springlab.model.armfile import MAX_LINKS  # noqa"),
    ("design/screen.py", "def _f():\n    from springlab.design.rank import design_arm  # noqa"),
    ("design/layouts.py", "def _f():\n    from springlab.design.arms import ArmDesign  # noqa"),
    ("design/search.py", "def _f():\n    from springlab.design.realise import coil_for  # noqa"),
])
def test_a_forbidden_import_breaks_a_contract(tmp_path, module, line):
    """Negative control: the same check on a copy with one forbidden import must fail."""
    shutil.copytree(ROOT / "springlab", tmp_path / "springlab",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    path = tmp_path / "springlab" / module
    path.write_text(path.read_text() + "\n" + line + "\n")
    result = lint_imports(tmp_path)
    assert result.returncode != 0
    assert "BROKEN" in result.stdout


LAZY = re.compile(r"^[ \t]+(from springlab\S* import|import springlab)", re.M)


def function_level_imports(root: Path) -> list[str]:
    """The model's and the design's imports of springlab made inside a function or a class: each would
    hide an import circle from the contracts above (an optional dependency would say so; none is)."""
    return [f"{path.relative_to(root)}: {m.group(0).strip()}"
            for folder in ("model", "design") for path in sorted((root / folder).rglob("*.py"))
            for m in LAZY.finditer(path.read_text())]


def test_no_function_level_import_hides_a_circle(tmp_path):
    root = Path(springlab.__file__).parent
    assert function_level_imports(root) == []
    # negative control: one import moved into a function is found
    (tmp_path / "design").mkdir()
    (tmp_path / "design" / "late.py").write_text("def f():\n    from springlab.design.arms import ArmDesign\n")
    assert function_level_imports(tmp_path) == ["design/late.py: from springlab.design.arms import"]


def test_no_private_name_is_imported_across_modules():
    pattern = re.compile(r"^\s*from springlab[\w.]* import (.*)$", re.M)
    offenders = []
    for path in (ROOT / "springlab").rglob("*.py"):
        for names in pattern.findall(path.read_text()):
            for name in re.split(r"[,()\s]+", names):
                if name.startswith("_") and not name.startswith("__") and name != "_checks":
                    offenders.append(f"{path.relative_to(ROOT)}: {name}")
    assert not offenders, offenders


def test_error_classes():
    assert issubclass(SpringlabError, ValueError)
    assert issubclass(SolverError, SpringlabError) and issubclass(SolverError, RuntimeError)
    assert issubclass(AttachmentError, GeometryError) and issubclass(AttachmentError, UnbalanceableError)


def test_no_bare_builtin_errors_in_the_library():
    bare = re.compile(r"raise (ValueError|RuntimeError|TypeError|KeyError|AssertionError)\(")
    offenders = [f"{p.relative_to(ROOT)}:{i}" for p in (ROOT / "springlab").rglob("*.py")
                 for i, text in enumerate(p.read_text().splitlines(), 1) if bare.search(text)]
    assert not offenders, offenders


def test_the_package_exports_the_entry_points():
    for name in ("quadratic", "geometry", "simulation", "solve_design", "design_arm", "load_arm",
                 "serial_chain", "Spring", "SpringlabError"):
        assert hasattr(springlab, name), name


ROUTE_1 = ("springlab.energy.quadratic", "springlab.mechanisms.pseudobase.subsystems", "springlab.mechanisms.dyad.algebra",
           "springlab.mechanisms.planar.quadratic")
ROUTES_2_AND_3 = ("springlab.energy.geometry", "springlab.energy.simulation", "springlab.mechanisms.pseudobase.geometry",
                  "springlab.mechanisms.pseudobase.simulation", "springlab.mechanisms.dyad.geometry",
                  "springlab.mechanisms.dyad.simulation", "springlab.mechanisms.planar.geometry")


def loaded_after_import(module: str) -> set:
    """The springlab modules a fresh interpreter has loaded after importing ``module``."""
    code = f"import sys, {module}; print(' '.join(m for m in sys.modules if m.startswith('springlab')))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    return set(out.split())


@pytest.mark.parametrize("module", ROUTES_2_AND_3)
def test_a_route_2_or_3_module_loads_no_route_1_at_run_time(module):
    """The contract checks the import graph; this checks what actually runs, package
    __init__ files included (springlab's own exports are loaded lazily for this reason)."""
    assert not loaded_after_import(module) & set(ROUTE_1)


def test_the_run_time_check_can_fail():
    assert "springlab.energy.quadratic" in loaded_after_import("springlab.design.solve")
