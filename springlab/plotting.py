"""One figure style, and figures saved so that their bytes repeat from run to run.

``save_figure`` writes ``<directory>/<name>.png`` and ``.svg``: the PNG without
the 'Software' metadata, the SVG with a fixed hash salt and no date, so that
re-running the notebooks on the pinned versions leaves ``git status`` clean.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib as mpl
import matplotlib.pyplot as plt

STYLE = Path(__file__).with_name("springlab.mplstyle")


def use_style() -> None:
    """Apply springlab's style file to the current matplotlib session."""
    plt.style.use(STYLE)


def save_figure(fig, name: str, directory) -> list[Path]:
    """Save ``fig`` as ``directory/name.png`` and ``directory/name.svg``; returns the paths."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    png, svg = directory / f"{name}.png", directory / f"{name}.svg"
    with mpl.rc_context({"svg.hashsalt": "springlab", "svg.fonttype": "path"}):
        fig.savefig(png, format="png", metadata={"Software": None})
        fig.savefig(svg, format="svg", metadata={"Date": None})
    return [png, svg]


def energy_figure(t, gravity, springs, total, *, title: str, reference=None, reference_label=None):
    """Gravity, spring and total energy over time, the look of 000 Figs. 16-17.

    :param t: time (s); the energies in J
    :param reference: optional second total-energy curve (e.g. with printed springs)
    """
    fig, ax = plt.subplots()
    ax.plot(t, gravity, label="gravitational energy $U_g$")
    ax.plot(t, springs, label=r"spring elastic energy $\sum U_S$")
    ax.plot(t, total, color="k", label="total energy")
    if reference is not None:
        ax.plot(t, reference, color="k", linestyle="--", linewidth=1.0, label=reference_label)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("energy (J)")
    ax.set_title(title)
    ax.set_xlim(t[0], t[-1])
    ax.legend(loc="best")
    return fig
