"""`make figures`' runner is quiet: a notebook run through it prints no WARNING or ERROR line (its kernel
on IPC sockets, so ipykernel has no unencrypted TCP to warn about)."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

RUN = """
from springlab.workbench.notebooks import run_notebook
run_notebook({nb!r}, {out!r}, {{"quick": True, "figures_dir": {figures!r}}})
"""


def _loud(text: str) -> list[str]:
    return [line for line in text.splitlines() if "WARNING" in line or "ERROR" in line]


def test_the_loud_line_check_can_fail():
    kernel = "[IPKernelApp] WARNING | Kernel is running over TCP without encryption."
    assert _loud(f"running\n{kernel}\ndone") == [kernel] and _loud("running\ndone") == []


def test_a_notebook_run_prints_no_warning_or_error(tmp_path):
    script = RUN.format(nb=str(ROOT / "notebooks" / "lenzo2017_two_spring_arm.ipynb"),
                        out=str(tmp_path / "out.ipynb"), figures=str(tmp_path / "figures"))
    run = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert _loud(run.stdout + run.stderr) == []
    assert not list(tmp_path.glob("kernel-*"))  # the IPC sockets live in Jupyter's runtime folder, not here


def test_kernels_side_by_side_have_sockets_of_their_own():
    from springlab.workbench.notebooks import _ipc_kernel_manager

    managers = [_ipc_kernel_manager()(kernel_name="python3") for _ in range(2)]
    assert {m.transport for m in managers} == {"ipc"}
    assert managers[0].ip != managers[1].ip  # jupyter_client's own default, 'kernel-ipc', is one path for all
    import asyncio

    for m in managers:  # the shutdown nbclient awaits removes each kernel's folder
        asyncio.run(m._async_cleanup_resources())
        assert not Path(m.ip).parent.exists()
