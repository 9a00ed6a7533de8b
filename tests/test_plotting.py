import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.colors import to_hex  # noqa: E402

from springlab.workbench.plotting import energy_figure, save_figure, use_style  # noqa: E402


def draw():
    use_style()
    t = np.linspace(0, 30, 50)
    return energy_figure(t, np.sin(t), 2 - np.sin(t), 2 + 0 * t, title="test",
                         reference=2 + 1e-3 * t, reference_label="rounded")


def test_saved_figures_are_byte_identical_and_undated(tmp_path):
    first = [p.read_bytes() for p in save_figure(draw(), "a", tmp_path / "1")]
    second = [p.read_bytes() for p in save_figure(draw(), "a", tmp_path / "2")]
    plt.close("all")
    assert first == second
    png, svg = first
    assert b"Software" not in png
    assert b"<dc:date>" not in svg


def test_in_a_notebook_the_saved_png_is_shown_and_the_figure_closed(tmp_path, monkeypatch):
    import IPython.display

    from springlab.workbench import plotting

    shown = []
    monkeypatch.setattr(IPython.display, "display", lambda obj: shown.append(obj))
    fig = draw()
    plotting.save_figure(fig, "b", tmp_path)
    assert not shown and plt.fignum_exists(fig.number)  # a script: nothing displayed, the figure stays open
    monkeypatch.setattr(plotting, "_in_kernel", lambda: True)
    png, _ = plotting.save_figure(fig, "b", tmp_path)
    assert len(shown) == 1 and shown[0].data == png.read_bytes()  # the file itself, not a new drawing
    assert shown[0].width == round(plt.imread(png).shape[1] * 110 / 150)  # the notebook's size (figure.dpi)
    assert not plt.fignum_exists(fig.number)  # plt.show() after it draws nothing more
    plt.close("all")


# --- legends cover no curve; a colour names one thing per figure ------------------------------
def covering(fig) -> list[str]:
    """The curves, over every panel of ``fig``, that run through their panel's legend."""
    from springlab.workbench.plotting import covered_lines

    fig.canvas.draw()
    return [name for ax in fig.axes for name in covered_lines(ax)]


def colour_meanings(fig) -> dict:
    """{colour: the labels of every labelled line drawn in it, over all panels}."""
    from matplotlib.colors import to_hex

    out = {}
    for ax in fig.axes:
        for line in ax.lines:
            if not line.get_label().startswith("_"):
                out.setdefault(to_hex(line.get_color()), set()).add(line.get_label())
    return out


@pytest.fixture(scope="module")
def paper_001():
    """Paper 001's Fig. 9 energies and fold margins along Eq. (26), route 2."""
    from springlab.mechanisms.pseudobase import geometry as pbgeo
    from springlab.mechanisms.pseudobase import model as pb
    from springlab.mechanisms.pseudobase import subsystems as subs
    from springlab.model.trajectories import PiecewiseCubic
    from springlab.papers import lin2010

    arm = lin2010.arm()
    t = np.linspace(0.0, lin2010.DURATION, 401)
    q = PiecewiseCubic(lin2010.TABLE4[:, :4]).angles(t)
    springs = subs.design_equilibrators(arm, lin2010.K, lin2010.L_CA)
    printed = subs.design_equilibrators(arm, lin2010.K, lin2010.L_CA, l_CB=lin2010.L_CB)
    return {"t": t, "E": pbgeo.energies(arm, springs, q), "printed": pbgeo.energies(arm, printed, q),
            "margin": pb.fold_margin(arm, q), "modules": arm.modules}


def fold_drawing(data):
    from springlab.workbench.plotting import fold_figure

    t = data["t"]
    noise = np.random.default_rng(0).uniform(1e-15, 1e-12, len(t))  # simulated tilts: small, ragged
    tilt = {"RSSR, Table 2's C_i": (t[t < 3.35], noise[t < 3.35]), "RSSR, C_2 turned": (t[t < 6.07], 3 * noise[t < 6.07])}
    return fold_figure(t, data["margin"], [f"module {i}" for i in data["modules"]], tilt=tilt, title="RSSR modules")


def test_the_legend_checks_can_fail():
    from springlab.workbench.plotting import covered_lines

    use_style()
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], label="diagonal")
    ax.plot([0, 1], [1, 1], label="top")
    ax.legend(loc="center")  # the diagonal runs through it, between its data points
    assert covered_lines(ax) == ["diagonal"] and covering(fig) == ["diagonal"]
    ax.plot([0, 1], [0.5, 0.5], color="C0", label="another")
    assert colour_meanings(fig)[to_hex("C0")] == {"diagonal", "another"}
    plt.close(fig)


def test_paper_001s_fig9_legend_covers_no_curve(paper_001):
    use_style()
    E, printed = paper_001["E"], paper_001["printed"]
    fig = energy_figure(paper_001["t"], E["gravity"], E["springs"], E["total"], title="Fig. 9",
                        reference=printed["total"], reference_label="total, Table 3's rounded $l_{CB}$")
    assert covering(fig) == []
    upper = fig.axes[0]  # the legend stays in its panel, whose curves keep their room
    inside = upper.get_window_extent()
    box = upper.get_legend().get_window_extent()
    assert inside.x0 <= box.x0 and box.x1 <= inside.x1 and inside.y0 <= box.y0 and box.y1 <= inside.y1
    upper.legend(loc="center right")  # where it was: the spring energy ran through "total energy"
    assert covering(fig) == [r"spring elastic energy $\sum U_S$"]
    plt.close(fig)


def test_energy_legends_cover_no_curve_with_markers():
    use_style()
    t = np.linspace(0, 30, 301)
    fig = energy_figure(t, np.cos(t / 5), 2 - np.cos(t / 5), 2 + 0 * t, title="markers",
                        markers={"gravity": np.cos(t / 5), "springs": 2 - np.cos(t / 5), "total": 2 + 0 * t})
    assert covering(fig) == []
    plt.close(fig)


def test_the_fold_figure_legends_cover_no_curve_and_colours_mean_one_thing(paper_001):
    use_style()
    fig = fold_drawing(paper_001)
    assert covering(fig) == []
    assert all(len(names) == 1 for names in colour_meanings(fig).values()), colour_meanings(fig)
    upper, lower = fig.axes
    upper.legend(loc="best", ncol=3, fontsize=7)  # the old placement: module 6's curve crossed its label
    assert "module 6" in covering(fig)
    plt.close(fig)


def test_a_legend_with_no_free_place_goes_beside_its_panel():
    from springlab.workbench.plotting import clear_legend, covered_lines

    use_style()
    fig, ax = plt.subplots()
    x = np.linspace(0, 1, 200)
    for k in range(40):  # curves everywhere
        ax.plot(x, np.sin(20 * x + k) + k / 10, label=f"curve {k}" if k < 6 else None)
    legend = clear_legend(ax)
    assert covered_lines(ax, legend) == []
    assert legend.get_window_extent().x0 >= ax.get_window_extent().x1  # to the right of the axes
    plt.close(fig)


def _png(fig) -> bytes:
    import io

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    plt.close(fig)
    return buffer.getvalue()


def test_the_fold_figure_shows_round_off_tilt_against_its_bound_and_a_real_tilt_as_itself(paper_001, tmp_path):
    """Round-off (below the floor) draws the same pixels whatever its digits; a tilt above the floor
    is drawn as itself (the negative control); the bound's colour means nothing else."""
    from springlab.workbench.images import same_pixels
    from springlab.workbench.plotting import fold_figure

    use_style()
    t, margin, labels = paper_001["t"], paper_001["margin"], [f"module {i}" for i in paper_001["modules"]]
    rng = np.random.default_rng(1)

    def drawn(scale):
        return fold_figure(t, margin, labels, tilt={"a": (t, scale * rng.uniform(1e-15, 1e-12, len(t)))}, bound=1e-6)

    fig = drawn(1.0)
    assert all(len(names) == 1 for names in colour_meanings(fig).values()), colour_meanings(fig)
    first = tmp_path / "one.png"
    first.write_bytes(_png(fig))
    assert same_pixels(first, _png(drawn(1.0)))  # other round-off, the same picture
    assert not same_pixels(first, _png(drawn(1e5)))  # up to 1e-7 rad: above the floor, drawn


def test_shown_values_do_not_carry_round_off():
    from springlab.workbench.plotting import shown

    values = np.array([0.0, 1.0 / 3.0, 18.215838752633520, 105.74228900330095])
    noisy = values * (1 + np.array([0.0, 3e-16, -4e-16, 1e-16]))
    assert np.array_equal(shown(values), shown(noisy))  # round-off (1e-16) draws no pixel
    assert not np.array_equal(shown(values), shown(values * (1 + 1e-6)))  # a change a figure can show stays
    assert np.max(np.abs(shown(values) - values)) <= 0.5e-6  # 9 digits of 105.7: to 1e-6
    assert np.array_equal(shown(np.zeros(3)), np.zeros(3))
