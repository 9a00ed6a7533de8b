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
