"""Another CPU writes the same claims (springlab.workbench.cpu, springlab.workbench.claims).

The whole check (every notebook run twice, on this CPU and on a narrowed one) runs in CI
(`.ci/run`: `python -m springlab.workbench.cpu`); here its parts, with the negative control:
a value written at full precision differs between the two CPUs, the same value stored as a claim
does not."""

import json
import subprocess
import sys

import pytest

from springlab.workbench import cpu

# a linear solve goes through OpenBLAS, whose kernels differ by core type in their last bits
PROGRAMME = """
import json, sys
import numpy as np
from springlab.workbench.claims import Claims
x = np.linalg.solve(*(lambda r: (r.normal(size=(200, 200)), r.normal(size=200)))(np.random.default_rng(7)))
value = float(x.sum())
claims = Claims("cpu")
claims.compare("sum of a solve", "here", 20.70284286, value, unit="-", tolerance=1e-8,
               tolerance_basis="a test")
claims.write(sys.argv[1])
with open(sys.argv[1] + "/full.json", "w") as f:
    json.dump({"value": value}, f)
"""


def _run(folder, env):
    folder.mkdir()
    subprocess.run([sys.executable, "-c", PROGRAMME, str(folder)], env=env, check=True)
    return json.loads((folder / "full.json").read_text())["value"]


def test_the_narrowed_cpu_moves_round_off_and_a_stored_claim_does_not(tmp_path):
    usual = _run(tmp_path / "usual", None)
    narrowed = _run(tmp_path / "narrowed", cpu.narrowed_environment())
    if usual == narrowed:
        pytest.skip("this CPU has nothing to narrow: OpenBLAS's Sandybridge kernels are its own")
    assert abs(usual - narrowed) < 1e-9 * abs(usual)  # round-off, not another answer
    # the negative control: written at full precision, the value differs between the CPUs
    assert cpu.differences(tmp_path / "usual", tmp_path / "narrowed") == ["full.json"]


def test_the_narrowed_environment_names_what_it_turns_off():
    env = cpu.narrowed_environment({"PATH": "/bin"})
    assert env["NUMBA_CPU_NAME"] == "generic" and env["PATH"] == "/bin"
    code = ("import numpy, os; from numpy._core._multiarray_umath import __cpu_features__ as f; "
            "off = os.environ.get('NPY_DISABLE_CPU_FEATURES', '').split(); print(all(not f[n] for n in off))")
    out = subprocess.run([sys.executable, "-c", code], env=cpu.narrowed_environment(), capture_output=True,
                         text=True, check=True)
    assert out.stdout.strip() == "True", out.stderr  # numpy starts, with those targets off


def test_differences_lists_changed_and_missing_files(tmp_path):
    one, two = tmp_path / "one", tmp_path / "two"
    for root in (one, two):
        (root / "nb").mkdir(parents=True)
        (root / "nb" / "claims.json").write_text("[1]\n")
        (root / "nb" / "notes.txt").write_text(str(root))  # not a compared kind of file
    assert cpu.differences(one, two) == []
    (two / "nb" / "claims.json").write_text("[2]\n")
    (one / "nb" / "fig.png").write_bytes(b"png")
    assert cpu.differences(one, two) == [f"nb/fig.png: only in {one}", "nb/claims.json"]


@pytest.mark.extended  # `make check-all` runs the check itself on every notebook
def test_the_check_runs_a_notebook_on_both_cpus_and_finds_the_same_bytes(monkeypatch, capsys):
    from pathlib import Path

    monkeypatch.chdir(Path(__file__).resolve().parents[1])
    assert cpu.main(["lenzo2017_two_spring_arm", "--jobs", "1"]) == 0
    assert "the same bytes on both CPUs: 1 notebooks" in capsys.readouterr().out


def test_the_check_refuses_a_notebook_it_does_not_know(monkeypatch, capsys):
    from pathlib import Path

    monkeypatch.chdir(Path(__file__).resolve().parents[1])
    with pytest.raises(SystemExit):
        cpu.main(["--exclude", "no_such_notebook"])
    assert "no notebook named no_such_notebook" in capsys.readouterr().err
