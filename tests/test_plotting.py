import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

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
