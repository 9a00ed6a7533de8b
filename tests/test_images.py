"""A figure file is rewritten only when what it shows changed (springlab.workbench.images)."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

from springlab.workbench import images  # noqa: E402
from springlab.workbench.plotting import save_figure  # noqa: E402


def _figure(y):
    fig, ax = plt.subplots(figsize=(3, 2), dpi=50)
    ax.plot(np.linspace(0, 1, len(y)), y)
    ax.set(xlabel="time t (s)", ylabel="energy (J)", ylim=(-1.5, 1.5))
    return fig


def test_a_figure_whose_data_moved_below_a_pixel_is_not_rewritten(tmp_path):
    y = np.sin(np.linspace(0, 6, 50))
    png, svg = save_figure(_figure(y), "f", tmp_path)
    before = (png.read_bytes(), svg.read_bytes())
    png.write_bytes(png.read_bytes())  # same bytes, new mtime: nothing to tell from the time
    save_figure(_figure(y * (1 + 1e-12)), "f", tmp_path)  # round-off: the same pixels
    assert (png.read_bytes(), svg.read_bytes()) == before


def test_a_figure_that_shows_something_else_is_rewritten(tmp_path):
    """The negative control: a visible change must reach the files."""
    y = np.sin(np.linspace(0, 6, 50))
    png, svg = save_figure(_figure(y), "f", tmp_path)
    before = (png.read_bytes(), svg.read_bytes())
    save_figure(_figure(y * 0.8), "f", tmp_path)
    after = (png.read_bytes(), svg.read_bytes())
    assert after[0] != before[0] and after[1] != before[1]


def test_a_missing_svg_or_an_unreadable_png_is_written(tmp_path):
    matplotlib.rcdefaults()  # the size below is matplotlib's default saving, whatever style an earlier test set
    y = np.sin(np.linspace(0, 6, 50))
    png, svg = save_figure(_figure(y), "f", tmp_path)
    svg.unlink()
    save_figure(_figure(y), "f", tmp_path)
    assert svg.is_file()
    png.write_bytes(b"not a png")
    save_figure(_figure(y), "f", tmp_path)
    assert Image.open(png).size == (150, 100)


def test_same_pixels_compares_pixels_not_bytes(tmp_path):
    rgb = np.zeros((4, 5, 3), dtype=np.uint8)
    rgb[1, 2] = 255
    path = tmp_path / "a.png"
    Image.fromarray(rgb).save(path, compress_level=1)
    other = tmp_path / "b.png"
    Image.fromarray(rgb).save(other, compress_level=9)  # other bytes, same pixels
    assert images.same_pixels(path, other.read_bytes())
    rgb[0, 0] = 1
    Image.fromarray(rgb).save(other)
    assert not images.same_pixels(path, other.read_bytes())
    assert not images.same_pixels(tmp_path / "none.png", other.read_bytes())


def test_an_unchanged_animation_is_recognised_and_a_changed_one_is_not(tmp_path):
    frames = [Image.fromarray(np.full((6, 8, 3), k * 40, dtype=np.uint8)).quantize(colors=8) for k in range(3)]
    path = tmp_path / "a.gif"
    frames[0].save(path, save_all=True, append_images=frames[1:], duration=100, loop=0)
    assert images.unchanged_gif(path, frames, 100)
    assert not images.unchanged_gif(path, frames, 125)  # another frame rate
    assert not images.unchanged_gif(path, frames[:2], 100)  # a frame fewer
    changed = frames[:2] + [Image.fromarray(np.full((6, 8, 3), 7, dtype=np.uint8)).quantize(colors=8)]
    assert not images.unchanged_gif(path, changed, 100)
    assert not images.unchanged_gif(tmp_path / "none.gif", frames, 100)
