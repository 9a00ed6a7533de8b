"""One figure style, and figures saved so that their bytes repeat from run to run.

``save_figure`` writes ``<directory>/<name>.png`` and ``.svg``: the PNG without
the 'Software' metadata, the SVG with a fixed hash salt and no date, so that
re-running the notebooks on the pinned versions leaves ``git status`` clean. In a
notebook it also shows the saved PNG as the cell's figure, so the reader sees the file
itself and the figure is drawn twice (PNG, SVG), not a third time for the notebook.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""

from __future__ import annotations

from pathlib import Path

import matplotlib as mpl
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import to_hex

from springlab import _checks
from springlab.workbench.images import save_png_and_svg

STYLE = Path(__file__).with_name("springlab.mplstyle")


def use_style() -> None:
    """Apply springlab's style file to the current matplotlib session."""
    plt.style.use(STYLE)


SHOWN_DIGITS = 9
"""Significant digits (of an array's largest value) a figure plots: far more than a figure can show,
far fewer than round-off moves. A coordinate that lands exactly on a rasteriser's sub-pixel boundary
(a payload of 1 kg at a round pixel) otherwise takes one grey level more or less from round-off
alone, so the same figure would differ between CPUs by a few pixels."""


def shown(values) -> np.ndarray:
    """``values`` rounded to :data:`SHOWN_DIGITS` significant digits of their largest magnitude,
    as a figure plots them (round-off, which differs between CPUs, then draws no pixel)."""
    values = np.asarray(values, dtype=float)
    top = float(np.max(np.abs(values[np.isfinite(values)]), initial=0.0))
    if top == 0.0:
        return values
    resolution = 10.0 ** (np.floor(np.log10(top)) - SHOWN_DIGITS + 1)
    return np.round(values / resolution) * resolution


def save_figure(fig, name: str, directory) -> list[Path]:
    """Save ``fig`` as ``directory/name.png`` and ``directory/name.svg``; returns the paths.
    The files are left as they are when the PNG already there has the same pixels
    (:mod:`springlab.workbench.images`): what the figure shows did not change.

    In a Jupyter kernel the PNG just written is displayed (at the size the notebook would
    draw the figure, ``figure.dpi``) and the figure closed, so a ``plt.show()`` after it
    draws nothing more."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    png, svg = directory / f"{name}.png", directory / f"{name}.svg"
    with mpl.rc_context({"svg.hashsalt": "springlab", "svg.fonttype": "path"}):  # rewritten only if the pixels changed
        save_png_and_svg(fig, png, svg, png_options={"metadata": {"Software": None}},
                         svg_options={"metadata": {"Date": None}})
    if _in_kernel():
        from IPython.display import Image, display
        from PIL import Image as PILImage

        saved_dpi = mpl.rcParams["savefig.dpi"]
        saved_dpi = fig.dpi if saved_dpi == "figure" else saved_dpi
        with PILImage.open(png) as im:
            width = round(im.width * mpl.rcParams["figure.dpi"] / saved_dpi)
        display(Image(data=png.read_bytes(), format="png", width=width, metadata={"alt": describe(fig)}))
        plt.close(fig)
    return [png, svg]


def describe(fig) -> str:
    """A figure's alt text, from what it says: its title (or its panels' titles), then each
    labelled panel's y label against its x label.

    >>> fig, ax = plt.subplots()
    >>> _ = ax.set(title="Fig. 16", xlabel="time t (s)", ylabel="energy (J)")
    >>> describe(fig)
    'Fig. 16: energy (J) against time t (s)'
    >>> plt.close(fig)
    """
    title = fig._suptitle.get_text() if getattr(fig, "_suptitle", None) else ""
    axes = [ax for ax in fig.axes if ax.get_visible() and (ax.get_xlabel() or ax.get_ylabel() or ax.get_title())]
    titles = [ax.get_title() for ax in axes if ax.get_title()]
    head = title or "; ".join(dict.fromkeys(titles))
    plots = [f"{ax.get_ylabel()} against {ax.get_xlabel()}" for ax in axes if ax.get_xlabel() and ax.get_ylabel()]
    body = "; ".join(dict.fromkeys(plots))
    return ": ".join(p for p in (head.replace("\n", " "), body) if p) or "figure"


def _in_kernel() -> bool:
    """True inside a Jupyter kernel (a notebook), False in a script or the tests."""
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    shell = get_ipython()
    return shell is not None and hasattr(shell, "kernel")


def covered_lines(ax, legend=None, *, pad: float = 5.0) -> list[str]:
    """The lines of ``ax`` (their labels, or "line k") that cross its legend's box, ``pad`` px
    around it, in display coordinates: every drawn segment (and marker) of each visible line,
    not only its data points.

    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0, 1], [0, 1], label="diagonal")
    >>> covered_lines(ax, ax.legend(loc="center"))
    ['diagonal']
    >>> plt.close(fig)
    """
    legend = legend or ax.get_legend()
    if legend is None:
        return []
    box = legend.get_window_extent(ax.figure.canvas.get_renderer()).padded(pad)
    out = []
    for k, line in enumerate(ax.lines):
        if not line.get_visible() or len(line.get_xdata()) == 0:
            continue
        path = line.get_transform().transform_path(line.get_path())
        if path.intersects_bbox(box, filled=False):
            label = line.get_label()
            out.append(label if not label.startswith("_") else f"line {k}")
    return out


def clear_legend(ax, *, fallback: str = "right", pad: float = 5.0, **legend_kw):
    """``ax``'s legend where it covers no line (:func:`covered_lines`): the first free place
    inside the axes, tried from the top down along the right edge, then the left, then the
    middle; if none is free, outside the axes: to their right (``fallback="right"``) or below
    them, under the x label (``"below"``). Call it once the axes have their final size (after
    ``tight_layout``). Returns the legend."""
    fig = ax.figure
    fig.draw_without_rendering()  # the axes' final boxes, without rasterising
    renderer = fig.canvas.get_renderer()
    inside = ax.get_window_extent(renderer)
    tops = np.linspace(1.0, 0.0, 41)
    for loc, x in (("upper right", 1.0), ("upper left", 0.0), ("upper center", 0.5)):
        for y in tops:
            legend = ax.legend(loc=loc, bbox_to_anchor=(x, y), **legend_kw)
            box = legend.get_window_extent(renderer)
            if box.y0 < inside.y0 or box.y1 > inside.y1:
                continue
            if not covered_lines(ax, legend, pad=pad):
                return legend
    if fallback == "below":
        below = ax.xaxis.get_tightbbox(renderer) or inside
        y = (below.y0 - inside.y0) / inside.height
        return ax.legend(loc="upper center", bbox_to_anchor=(0.5, y), **legend_kw)
    return ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), **legend_kw)


def energy_figure(t, gravity, springs, total, *, title: str, reference=None, reference_label=None,
                  markers=None, marker_every: int = 6, marker_label: str = "markers: exudyn; lines: route 2",
                  xlabel: str = "time t (s)"):
    """Gravity, spring and total energy over time, the look of 000 Figs. 16-17.

    With a ``reference`` total (e.g. with the paper's rounded springs) a lower
    panel shows both totals' deviation from their initial value in mJ, which
    the upper panel's scale cannot show.

    With ``markers`` ({'gravity', 'springs', 'total'} at the same times, e.g. another
    route's energies) every ``marker_every``-th value is drawn as an open circle over the lines.

    :param t: time (s), or another path parameter named by ``xlabel``; the energies in J
    """
    import numpy as np

    if reference is None:
        fig, ax = plt.subplots()
        axes = [ax]
    else:
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(6.4, 4.8),
                                 gridspec_kw={"height_ratios": [2.2, 1]})
        ax = axes[0]
    ax.plot(t, gravity, label="gravitational energy $U_g$")
    ax.plot(t, springs, label=r"spring elastic energy $\sum U_S$")
    ax.plot(t, total, color="k", label="total energy")
    ax.set_ylabel("energy (J)")
    ax.set_title(title)
    if markers is not None:
        for key, colour in (("gravity", "C0"), ("springs", "C1"), ("total", "k")):
            ax.plot(t[::marker_every], np.asarray(markers[key])[::marker_every], "o", color=colour, markersize=3,
                    markerfacecolor="none")
        ax.plot([], [], "o", color="gray", markerfacecolor="none", label=marker_label)
    if reference is not None:
        low = axes[1]
        low.plot(t, 1e3 * (np.asarray(total) - total[0]), color="k", label="total, exact springs")
        low.plot(t, 1e3 * (np.asarray(reference) - reference[0]), color="k", linestyle="--",
                 linewidth=1.0, label=reference_label)
        low.set_ylabel("total - initial (mJ)")
    axes[-1].set_xlabel(xlabel)
    axes[-1].set_xlim(t[0], t[-1])
    for panel in axes:  # once the limits are set: where no curve runs
        clear_legend(panel)
    return fig


def arm_figure(chain, springs, X_frames, tip_path=None, *, title: str = "", titles=None):
    """The arm at a few poses (at most 4), in front and side views at one scale: the ground
    column, links as thick segments with joints, springs as zigzags labelled S(i,j) with their
    attachment points (:func:`springlab.workbench.drawing.mechanism_figure`). One pose: its
    two views side by side; several: a row per pose, its two views side by side (so that the
    figure reads at the book's width, not shrunk), every panel's springs named in 8 pt labels
    at least 5 px apart (3 or else 12 px from their zigzags), the legend below.

    :param X_frames: poses (F, n, 3) to draw (link directions)
    :param tip_path: optional (T, 3) tip positions (m), drawn dashed
    :param titles: one title per pose (default "pose 1", ...)
    """
    from springlab.workbench.drawing import chain_scene, mechanism_figure

    scene = chain_scene(chain, springs, X_frames, tip_path)
    if scene.poses == 1:
        return mechanism_figure(scene, [0], titles=titles, title=title)
    return mechanism_figure(scene, range(scene.poses), titles=titles, title=title, rows="poses",
                            label_style={"fontsize": 8, "gap": 5.0, "clear": (3.0, 12.0)})


def real_arm_figure(design, pose=None, *, title: str = "", hardware: bool = False):
    """An arm of the general model with its springs at one pose (default the design's first
    workspace pose), in front, side and top views at one scale
    (:func:`springlab.workbench.drawing.revolute_scene`); ``hardware=True``: its realised springs as
    built, coils, cables and pulleys (:func:`springlab.workbench.drawing.hardware_scene`). The heading
    gives the pose: the joint angles (deg, to the nearest degree, within -180 to 180) from the base out."""
    from springlab.workbench.drawing import hardware_scene, mechanism_figure, revolute_scene

    q = design.q[:1] if pose is None else np.atleast_2d(pose)
    scene = hardware_scene(design, q) if hardware else revolute_scene(design.model, design.ideal, q)
    turned = np.degrees(np.angle(np.exp(1j * q[0])))  # (-180, 180]: 324 deg is drawn, and read, as -36
    angles = ", ".join(f"{v:.0f}" for v in np.round(turned) + 0.0)  # + 0.0: no "-0"
    return mechanism_figure(scene, [0], views=("front", "side", "top"), columns=2,
                            titles=[f"{design.model.name} at ({angles}) deg"], title=title,
                            label_style={"clear": ARM_LABEL_CLEAR})


ARM_LABEL_CLEAR = (3.0, 9.0, 16.0)
"""px: how far from its zigzag a spring's name is tried on a real arm's drawing, nearest first: a real arm's
springs run close together (the Panda's five in a 0.1 m wide side view), and a name that finds no place
clear of the other springs 3 px away takes one farther out before it sits on one."""


def moment_figure(phi, curves: dict, *, title: str, ylabel: str = "moment (N m)", styles: dict | None = None):
    """Moments against the link angle, the look of 002 Figs. 2-3.

    :param phi: angles (rad), plotted in degrees
    :param curves: {label: moments (N m)}
    """
    import numpy as np

    fig, ax = plt.subplots()
    for label, values in curves.items():
        ax.plot(np.degrees(phi), values, label=label, **(styles or {}).get(label, {}))
    ax.axhline(0.0, color="0.5", linewidth=0.6)
    ax.set_xlabel(r"link angle $\varphi$ (deg)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.set_xlim(np.degrees(phi[0]), np.degrees(phi[-1]))
    ax.legend(loc="best")
    return fig


def dyad_figure(comp, dyad, phis, *, title: str = ""):
    """The compensator drawn to scale, two panels at one scale with one legend below them:
    its parts at the middle of the link angles ``phis`` (rad), each named (link OS with its
    centre of mass S, crank OA, rod AB, slider B on the vertical guide through O, the spring
    from O's level to B beside its free length l0), and the link, dyad and slider at every
    angle of ``phis``, shaded light to dark, each angle written beyond its link's end."""
    import numpy as np

    from springlab.mechanisms.dyad.model import slider_height
    from springlab.workbench.drawing import tight, zigzag

    phis = np.atleast_1d(np.asarray(phis, dtype=float))
    fig, (parts, sweep) = plt.subplots(1, 2, figsize=(6.4, 5.6), sharex=True, sharey=True)

    def points(phi):
        S = comp.s * np.array([np.sin(phi), np.cos(phi)])
        A = dyad.r * np.array([np.sin(phi - dyad.beta), np.cos(phi - dyad.beta)])
        return S, A, np.array([0.0, float(slider_height(dyad, phi))])

    top = max(comp.l0, max(points(phi)[2][1] for phi in phis)) + 0.05
    for ax in (parts, sweep):
        ax.plot([0, 0], [-0.05, top], color="0.6", linewidth=1.0, linestyle="--", zorder=1,
                label="slider guide, vertical through O")
        ax.plot(0, -0.035, "k^", markersize=9, zorder=5, label="pivot O (frame)")
    phi = phis[len(phis) // 2]
    S, A, B = points(phi)
    parts.plot(*zigzag((0.0, 0.0), B, coils=7, width=0.035).T, color="tab:red", linewidth=1.3, zorder=3,
               label=f"spring O-B, k = {comp.k:g} N/m")
    parts.plot([0, 0], [B[1], comp.l0], color="tab:red", linestyle=":", linewidth=1.3, zorder=2,
               label=f"spring's free length l0 = {comp.l0:g} m")
    parts.plot([0, S[0]], [0, S[1]], color="0.25", linewidth=3.0, solid_capstyle="round", zorder=3, label="link OS")
    parts.plot(*S, "o", color="0.25", markersize=7, zorder=4, label=f"centre of mass S (G = {comp.G:g} N)")
    parts.plot([0, A[0]], [0, A[1]], color="tab:blue", linewidth=2.2, zorder=4, label=f"crank OA, r = {dyad.r:g} m")
    parts.plot([A[0], B[0]], [A[1], B[1]], color="tab:green", linewidth=2.2, zorder=4, label=f"rod AB, l = {dyad.l:g} m")
    parts.plot(*B, "s", markerfacecolor="white", markeredgecolor="k", markersize=8, zorder=5, label="slider B")
    for name, at, off, ha in (("O", (0, 0), (-7, -2), "right"), ("A", A, (3, -10), "left"), ("B", B, (-7, 0), "right"),
                              ("S", S, (4, 6), "left")):
        parts.annotate(name, at, textcoords="offset points", xytext=off, ha=ha, fontsize=8, fontweight="bold")
    parts.set_title(f"its parts, at {np.degrees(phi):.0f} deg", fontsize=9)
    for phi, shade in zip(phis, np.linspace(0.7, 0.0, len(phis)), strict=True):
        S, A, B = points(phi)
        sweep.plot([0, S[0]], [0, S[1]], color=(shade,) * 3, linewidth=2.4, solid_capstyle="round", zorder=3)
        sweep.plot(*S, "o", color=(shade,) * 3, markersize=6, zorder=4)
        sweep.plot([0, A[0]], [0, A[1]], color="tab:blue", alpha=1 - 0.7 * shade, linewidth=1.6, zorder=4)
        sweep.plot([A[0], B[0]], [A[1], B[1]], color="tab:green", alpha=1 - 0.7 * shade, linewidth=1.6, zorder=4)
        sweep.plot(*B, "s", markerfacecolor="white", markeredgecolor=(shade,) * 3, markersize=6, zorder=5)
        out = S / np.linalg.norm(S)  # the angle beyond the link's end, along it
        sweep.annotate(f"{np.degrees(phi):.0f} deg", S, textcoords="offset points", xytext=tuple(11 * out), fontsize=7,
                       ha="left" if out[0] > 0.3 else "center", va="bottom" if out[1] > 0.3 else "top" if out[1] < -0.3 else "center")
    sweep.set_title(f"{np.degrees(phis[0]):.0f}-{np.degrees(phis[-1]):.0f} deg, light to dark", fontsize=9)
    for ax in (parts, sweep):
        ax.set_aspect("equal")
        ax.set_xlabel("horizontal (m)")
    parts.set_xlim(-0.2, comp.s + 0.3)
    parts.set_ylim(-comp.s - 0.12, top + 0.05)
    parts.set_ylabel("vertical (m)")
    handles, names = parts.get_legend_handles_labels()
    legend = fig.legend(handles, names, loc="lower center", ncol=2, fontsize=7, frameon=False)
    if title:
        fig.suptitle(title, fontsize=10)
    below = legend.get_window_extent(fig.canvas.get_renderer()).height / fig.bbox.height  # the legend's share
    tight(fig, rect=(0, below + 0.01, 1, 1))
    return fig


def two_spring_layouts_figure(designs: dict, forearm_length: float, *, shoulder_deg: float = 50.0,
                              elbow_deg: float = 70.0):
    """Lenzo's layouts (004 Fig. 5) drawn to scale in the vertical plane, one panel per design
    {title: (arm, design)}, with the drawing of every arm in the book
    (:func:`springlab.workbench.drawing.scenes_figure`): the ground column, links and joints,
    brackets where a spring's end lies past a joint, springs S(1,3) (k2) and S(2,3) (k12) as
    zigzags, centres of mass. The upper arm at ``shoulder_deg`` from the vertical, the forearm
    bent by ``elbow_deg`` more."""
    import numpy as np

    from springlab.mechanisms.two_spring_arm import to_chain_springs
    from springlab.model.chain import UP
    from springlab.workbench.drawing import chain_scene, scenes_figure

    def unit(deg):  # in the vertical plane (x_1 up, y)
        return np.cos(np.radians(deg)) * UP + np.sin(np.radians(deg)) * np.array([0.0, 1.0, 0.0])

    X = np.array([[UP, unit(shoulder_deg), unit(shoulder_deg + elbow_deg)]])
    panels = {f"{title}\nk2 = {d.k2:.0f} N/m, k12 = {d.k12:.0f} N/m":
              (chain_scene(arm.chain(forearm_length), to_chain_springs(arm, d), X), 0)
              for title, (arm, d) in designs.items()}
    return scenes_figure(panels, view="front")


def planar_designs_figure(designs: dict, theta_deg, *, title: str = "", columns: int = 2):
    """Paper 003's planar arms with their springs, drawn to scale in their vertical plane, one
    panel per design {panel title: (PlanarArm, springs)}, every panel at one scale
    (:func:`springlab.workbench.drawing.scenes_figure`): the ground column, links and joints,
    springs S(i,j) as zigzags (one colour per spring name across the panels), centres of mass.

    :param theta_deg: 003's joint angles theta_2, theta_3, ... (deg); an arm of n links takes
        the first n - 1
    :raises SpringlabError: for a spring attached off the joint lines (it has no 000 form,
        :func:`springlab.mechanisms.planar.model.to_spatial`)
    """
    import numpy as np

    from springlab.mechanisms.planar import model as pl
    from springlab.workbench.drawing import chain_scene, scenes_figure

    panels = {}
    for name, (arm, springs) in designs.items():
        chain, spatial = pl.to_spatial(arm, springs)
        X = chain.directions(pl.spatial_angles(np.radians(np.asarray(theta_deg, dtype=float)[None, : arm.n - 1])))
        panels[name] = (chain_scene(chain, spatial, X), 0)
    return scenes_figure(panels, view="front", columns=columns, title=title)


def joint_angles_figure(t, angles, *, printed=None, title: str = "", events=None):
    """Joint angles against time, one colour per joint, the look of 001 Eq. (26)'s motion.

    :param t: (T,) s; angles: (T, n) rad, plotted in rad
    :param printed: optional (T, n) angles from a paper's printed coefficients, dashed
    :param events: optional {label: time (s)} marked by vertical lines
    """
    import numpy as np

    fig, ax = plt.subplots()
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j in range(np.shape(angles)[1]):
        colour = colours[j % len(colours)]
        ax.plot(t, angles[:, j], color=colour, label=rf"$\theta_{j + 1}$")
        if printed is not None and not np.allclose(printed[:, j], angles[:, j], atol=0.01):
            ax.plot(t, printed[:, j], color=colour, linestyle="--", linewidth=1.0,
                    label=rf"$\theta_{j + 1}$, printed coefficients")
    for label, when in (events or {}).items():
        ax.axvline(when, color="0.5", linewidth=0.8, linestyle=":")
        ax.text(when, ax.get_ylim()[1], label, fontsize=7, ha="center", va="bottom")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("joint angle (rad)")
    ax.set_xlim(t[0], t[-1])
    ax.set_title(title)
    ax.legend(loc="best", ncol=2, fontsize=7)
    return fig


def joint_torques_figure(t, balanced, unbalanced, *, title: str = "", hold=None):
    """Actuator torques (N m) against time with and without springs, two panels on
    their own scales; optional ``hold`` = (t_h, balanced_h, unbalanced_h) holding
    torques at rest, drawn as markers.

    :param t: (T,) s; balanced, unbalanced: (T, n) N m
    """
    import numpy as np

    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(6.4, 5.2))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, values, which, h in ((axes[0], unbalanced, "springs removed", 2), (axes[1], balanced, "balanced", 1)):
        for j in range(np.shape(values)[1]):
            ax.plot(t, values[:, j], color=colours[j % len(colours)], label=rf"$\tau_{j + 1}$")
            if hold is not None:
                ax.plot(hold[0], hold[h][:, j], "o", color=colours[j % len(colours)], markersize=3)
        ax.axhline(0.0, color="0.5", linewidth=0.6)
        ax.set_ylabel("torque (N m)")
        ax.set_title(f"{title}: {which}" if title else which, fontsize=9)
    axes[0].legend(loc="best", ncol=3, fontsize=7)
    axes[1].set_xlabel("time t (s)")
    axes[1].set_xlim(t[0], t[-1])
    fig.tight_layout()
    return fig


TILT_COLOURS = ("k", "tab:brown", "0.55", "tab:cyan")
"""The simulations' colours in :func:`fold_figure`'s lower panel: none of the modules' (the
style's first five), so that a colour names one thing in the figure."""


def fold_figure(t, margin, labels, *, tilt=None, title: str = "", floor: float = 1e-9, bound: float | None = None):
    """RSSR modules' fold margins against time (upper), and the largest pseudobase tilt
    from vertical in simulations on a log scale (lower, optional ``tilt`` =
    {label: (t, (T,) rad)}, in :data:`TILT_COLOURS`, colours the modules do not use). Each
    panel's legend where it covers no curve (:func:`clear_legend`), else to its right.

    The tilt is shown against its bound, not as its round-off: values below ``floor`` (rad) are
    drawn on it, a shaded band marks everything below it as the solver's round-off, and ``bound``
    (rad, the tolerance the tilt is checked against) is drawn dashed. A simulated tilt of 1e-13 rad
    is the Newton tolerance's noise, which moves with the CPU; drawn as itself it would redraw the
    figure on every machine."""
    import numpy as np

    panels = 2 if tilt else 1
    fig, axes = plt.subplots(panels, 1, sharex=True, figsize=(6.4, 2.6 * panels + 0.6), squeeze=False)
    ax = axes[0, 0]
    for k, label in enumerate(labels):
        ax.plot(t, margin[:, k], label=label)
    ax.axhline(0.0, color="k", linewidth=0.8)
    ax.set_ylabel("fold margin (-)")
    ax.set_title(title)
    if tilt:
        low = axes[1, 0]
        used = {to_hex(line.get_color()) for line in ax.lines if not line.get_label().startswith("_")}
        free = [c for c in TILT_COLOURS if to_hex(c) not in used]
        floor = _checks.positive("floor", floor, unit="rad")
        for k, (label, (tt, values)) in enumerate(tilt.items()):  # the first widest: curves on the floor all show
            low.semilogy(tt, np.maximum(values, floor), color=free[k % len(free)], label=label,
                         linewidth=1.5 + 2.0 * (len(tilt) - 1 - k))
        top = max([floor * 10, *(float(np.max(v)) * 3 for _, v in tilt.values())])
        if bound is not None:
            bound = _checks.positive("bound", bound, unit="rad")
            low.axhline(bound, color="tab:olive", linestyle="--", linewidth=1.0, label=f"bound checked, {bound:g} rad")
            top = max(top, bound * 10)
        low.axhspan(floor / 10, floor, color="0.85", zorder=0, label=f"round-off: below {floor:g} rad")
        low.set_ylim(floor / 10, top)
        low.set_ylabel("largest pseudobase tilt (rad)")
    axes[-1, 0].set_xlabel("time t (s)")
    axes[-1, 0].set_xlim(t[0], t[-1])
    fig.tight_layout()
    for panel in axes[:, 0]:
        clear_legend(panel, fontsize=7)
    fig.tight_layout()  # room for a legend put beside its panel
    return fig


def lines_figure(x, curves: dict, *, xlabel: str, ylabel: str, title: str = "", styles: dict | None = None,
                 references: dict | None = None, logx: bool = False):
    """Curves {label: y} against x, with optional horizontal ``references`` {label: y}
    (e.g. a paper's printed values) drawn dotted."""
    fig, ax = plt.subplots()
    for label, values in curves.items():
        ax.plot(x, values, label=label, **(styles or {}).get(label, {}))
    for label, value in (references or {}).items():
        ax.axhline(value, color="0.4", linestyle=":", linewidth=1.0)
        ax.text(ax.get_xlim()[1], value, f" {label}", fontsize=7, va="center", ha="left")
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(loc="best", fontsize=7)
    return fig


def index_resolution_figure(steps, diffs: dict, *, marked_step: float = 5.0):
    """The index minus the printed one (in 1e-4) against the grid step (deg), one curve per
    case {label: values}, the printed rounding (+-0.5e-4) shaded and ``marked_step`` marked."""
    fig = lines_figure(steps, diffs, xlabel="grid step (deg), both ends of each range included",
                       ylabel="ours - printed index ($10^{-4}$)", title="The index against grid resolution ('magnitudes' reading)",
                       logx=True, styles={k: {"marker": "o", "markersize": 3} for k in diffs})
    ax = fig.axes[0]
    ax.axhspan(-0.5, 0.5, color="0.85", zorder=0, label="within the printed rounding")
    ax.axvline(marked_step, color="0.4", linestyle=":", linewidth=1.0)
    ax.set_xticks(steps)
    ax.set_xticklabels([f"{x:g}" for x in steps])
    ax.minorticks_off()
    ax.invert_xaxis()
    ax.legend(loc="best", fontsize=7)
    return fig


def springs_per_n_figure(rows):
    """Springs needed per n: the rules' fewest, the n - 1 ground springs, and n - 2 where the
    relaxation proves it impossible (rows of :func:`springlab.design.ground.springs_per_n`)."""
    fig, ax = plt.subplots()
    ns = [r.n for r in rows]
    ax.plot(ns, [r.necessary for r in rows], "o-", label="rules R1-R6 (Juang et al. 2023): fewest springs")
    ax.plot(ns, [r.ground.spring_count for r in rows], "s-", label="any signs: n - 1 ground springs, verified")
    proved = [r.n for r in rows if r.screen is not None]
    ax.plot(proved, [n - 2 for n in proved], "x", color="C3", label="n - 2: impossible (linear relaxation)")
    ax.set_xlabel("n, links with the ground")
    ax.set_ylabel("springs")
    ax.set_title("Springs needed per n (0.3 m brackets)")
    ax.legend(fontsize=8)
    return fig


def configuration_counts_figure(result):
    """Configurations per n, counted and estimated (a :class:`springlab.design.rules.ConfigurationCounts`)."""
    fig, ax = plt.subplots()
    ax.semilogy(list(result.counts), list(result.counts.values()), "o-", label="counted")
    ax.semilogy(list(result.estimate), list(result.estimate.values()), "o--", color="0.5",
                label=f"estimated (x{result.ratio:.0f} per link)")
    ax.set_xlabel("n, links with the ground")
    ax.set_ylabel("configurations with necessary springs")
    ax.set_title("Admissible configurations (rules R1-R6) per n")
    ax.legend()
    return fig


def tolerance_figure(study, *, title: str):
    """Histograms of the largest holding torque (N m) of the built arms, one per error
    (a :class:`springlab.design.tolerance.ToleranceResult`)."""
    fig, ax = plt.subplots()
    for name, values in study.torques.items():
        ax.hist(values, bins=30, histtype="step", label=name)
    ax.set_xlabel("largest holding torque over the workspace (N m)")
    ax.set_ylabel("built arms")
    ax.set_title(title)
    ax.legend(fontsize=7)
    return fig


def clearance_figure(gaps, *, title: str):
    """Each spring's smallest clearance from the other links at every workspace pose (mm), as
    histograms (a :class:`springlab.design.clearance.Clearance`); below zero it passes through a link."""
    fig, ax = plt.subplots()
    for label, values in gaps.per_pose.items():
        ax.hist(1e3 * values, bins=40, histtype="step", label=label)
    ax.axvline(0.0, color="k", lw=0.8)
    ax.set_xlabel("smallest clearance from the other links (mm); < 0: through a link")
    ax.set_ylabel("workspace poses")
    ax.set_title(title)
    ax.legend(fontsize=7)
    return fig


def payload_figure(study, *, title: str, rated: float | None = None):
    """The peak holding torque (N m) of each loaded joint against the payload (kg), one panel a joint
    (a :class:`springlab.design.payload.PayloadStudy`): gravity alone, the realised springs as built and
    with the payload dial turned; the ideal springs with the dial turned sit at round-off, below
    what the axes show. The nominal payload is marked, and the rated one when given."""
    cases = {"gravity alone": dict(color="0.6", ls="-"), "realised": dict(color="C0", ls="--"),
             "realised, dial turned": dict(color="C1", ls="-", marker="o", ms=3)}
    loaded = list(study.loaded)
    fig, axes = plt.subplots(1, len(loaded), figsize=(3.2 * len(loaded), 3.2), squeeze=False)
    for ax, i in zip(axes[0], loaded, strict=True):
        for case, style in cases.items():
            ax.plot(study.masses, shown(study.peaks[case][:, i]), label=case.replace("realised", "built springs"),
                    **style)
        ax.axvline(study.nominal, color="k", lw=0.8, ls=":")
        ax.set_title(study.joints[i], fontsize=9)
        ax.set_xlabel("payload (kg)")
        ax.set_ylim(bottom=0)
    axes[0, 0].set_ylabel("peak holding torque (N m)")
    axes[0, 0].legend(fontsize=7, loc="upper left")
    fig.suptitle(title + f" (designed for {study.nominal:g} kg, dotted"
                 + (f"; rated {rated:g} kg" if rated is not None else "") + ")", fontsize=10)
    return fig


def pulley_loss_figure(radii, percent: dict, *, title: str):
    """The largest holding torque the built springs leave (% of gravity's) against the pulley's
    radius (m, plotted in mm), one curve per case ({case: values})."""
    import numpy as np

    fig, ax = plt.subplots()
    for case, values in percent.items():
        ax.plot(1e3 * np.asarray(radii), values, marker="o", ms=3, label=case)
    ax.set_xlabel("pulley radius (mm)")
    ax.set_ylabel("largest holding torque (% of gravity's)")
    ax.set_title(title)
    ax.legend(fontsize=7)
    return fig


def workspace_panels_figure(theta3, theta4, panels: dict, *, title: str, label: str, levels=None):
    """Values over (theta_3, theta_4) in degrees, one panel per theta_2 ({theta_2 deg:
    (len(theta3), len(theta4)) array}), a shared colour bar, the look of 003 Fig. 5."""
    import numpy as np

    keys = list(panels)
    cols = 2
    rows = (len(keys) + 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(6.4, 2.9 * rows), sharex=True, sharey=True, squeeze=False)
    vmin = min(float(np.min(v)) for v in panels.values())
    vmax = max(float(np.max(v)) for v in panels.values())
    levels = levels if levels is not None else np.linspace(vmin, vmax, 15)
    for ax, key in zip(axes.flat, keys, strict=False):
        cs = ax.contourf(theta4, theta3, panels[key], levels=levels, cmap="viridis")
        ax.set_title(rf"$\theta_2$ = {key:g} deg", fontsize=8)
    for ax in list(axes.flat)[len(keys):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel(r"$\theta_4$ (deg)")
    for ax in axes[:, 0]:
        ax.set_ylabel(r"$\theta_3$ (deg)")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.colorbar(cs, ax=axes.ravel().tolist(), label=label, shrink=0.9)
    return fig


def map_figure(x, y, Z, *, xlabel: str, ylabel: str, label: str, title: str = "", marks: dict | None = None):
    """A filled contour map Z (len(y), len(x)) with labelled points ``marks`` {label: (x, y)},
    the look of 003 Fig. 7."""
    fig, ax = plt.subplots()
    cs = ax.contourf(x, y, Z, levels=20, cmap="viridis")
    ax.contour(x, y, Z, levels=10, colors="k", linewidths=0.4)
    for text, (px, py) in (marks or {}).items():
        ax.plot(px, py, "o", color="w", markeredgecolor="k", markersize=5)
        ax.annotate(text, (px, py), textcoords="offset points", xytext=(5, 4), fontsize=7, color="w")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    fig.colorbar(cs, ax=ax, label=label)
    return fig
