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


def _interrupts_at_shutdown(manager_class, monkeypatch) -> int:
    import asyncio

    from jupyter_client.manager import AsyncKernelManager

    sent = []

    async def interrupt(self):
        sent.append(self)

    monkeypatch.setattr(AsyncKernelManager, "_async_interrupt_kernel", interrupt)

    async def start_and_stop():
        manager = manager_class(kernel_name="python3")
        await manager.start_kernel()
        await manager.shutdown_kernel()

    asyncio.run(start_and_stop())
    return len(sent)


def test_a_finished_kernel_is_shut_down_without_an_interrupt(monkeypatch):
    """jupyter_client sends SIGINT before each shutdown request; when it lands in a handler the
    kernel is closing, the kernel logs 'ERROR | KeyboardInterrupt caught in kernel.' (a race, seen
    on some runs). Our kernels are shut down by the request alone; the control is jupyter_client's
    own manager, which does send the interrupt."""
    from jupyter_client.manager import AsyncKernelManager

    from springlab.workbench.notebooks import _ipc_kernel_manager

    assert _interrupts_at_shutdown(_ipc_kernel_manager(), monkeypatch) == 0
    assert _interrupts_at_shutdown(AsyncKernelManager, monkeypatch) == 1
