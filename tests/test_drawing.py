"""Mechanism drawings and animations: the drawing shows route 2's points, every panel at one
scale with equal axes, the hold test's motion is the hold test, and a GIF is deterministic
and small enough to commit."""

from pathlib import Path

import matplotlib
import numpy as np
import pytest

from springlab.energy import simulation as sim
from springlab.energy.geometry import attachment_points
from springlab.errors import SpringlabError
from springlab.model.chain import random_directions
from springlab.workbench import drawing

matplotlib.use("Agg")
ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def poses():
    return random_directions(4, 3, np.random.default_rng(7))


def test_a_zigzag_runs_from_end_to_end_within_its_width():
    P, Q = np.array([0.0, 0.0]), np.array([1.0, 0.0])
    z = drawing.zigzag(P, Q, coils=5, width=0.05)
    assert np.allclose(z[0], P) and np.allclose(z[-1], Q)
    assert np.max(np.abs(z[:, 1])) == pytest.approx(0.05)
    assert np.all(np.diff(z[:, 0]) >= 0)  # it never turns back
    assert drawing.zigzag(P, P, width=0.05).shape == (1, 2)  # a spring seen end-on is a point
    assert np.max(np.abs(drawing.zigzag(P, [0.1, 0.0], width=0.05)[:, 1])) == pytest.approx(0.025)  # short: narrower


def test_the_scene_holds_route_2s_points(arm, exact_springs, poses):
    scene = drawing.chain_scene(arm, exact_springs, poses)
    assert np.allclose(scene.links[0], arm.joint_positions(poses))
    for s, (label, (A, B)) in zip(exact_springs, scene.springs.items(), strict=True):
        assert label.startswith(f"S({s.i},{s.j})")
        A2, B2 = attachment_points(arm, s, poses)
        assert np.array_equal(A, A2) and np.array_equal(B, B2)
    low, high = scene.column  # the ground column reaches every attachment on link 1
    assert all(low <= s.a <= high for s in exact_springs if s.i == 1)
    # the front view is (y, x up), the side view (z, x up), the top view (y, z)
    p = np.array([1.0, 2.0, 3.0])
    assert scene.project(p, "front").tolist() == [2.0, 1.0]
    assert scene.project(p, "side").tolist() == [3.0, 1.0]
    assert scene.project(p, "top").tolist() == [2.0, 3.0]
    with pytest.raises(SpringlabError, match="view must be one of"):
        scene.project(p, "oblique")


def test_every_panel_has_equal_axes_and_one_scale_per_view(arm, exact_springs, poses):
    import matplotlib.pyplot as plt

    fig = drawing.mechanism_figure(drawing.chain_scene(arm, exact_springs, poses), [0, 1, 2])
    axes = fig.axes
    assert len(axes) == 6 and all(ax.get_aspect() == 1.0 for ax in axes)
    for row in (axes[:3], axes[3:]):
        assert len({(ax.get_xlim(), ax.get_ylim()) for ax in row}) == 1
    labels = {t.get_text() for t in axes[0].texts}
    assert {f"S({s.i},{s.j})" for s in exact_springs} <= labels
    plt.close(fig)
    with pytest.raises(SpringlabError, match="poses must be 1 to 4"):
        drawing.mechanism_figure(drawing.chain_scene(arm, exact_springs, poses), [0, 1, 2, 0, 1])
    with pytest.raises(SpringlabError, match="coordinate axis"):
        drawing.Scene(np.array([0.6, 0.8, 0.0]), [np.zeros((1, 2, 3))], {}, (0, 0)).horizontal()


def test_the_hold_motion_is_the_hold_test(arm, exact_springs, poses):
    motion = sim.hold_motion(arm, exact_springs, poses[0], duration=1.0)
    test = sim.hold_test(arm, exact_springs, poses[:1], duration=1.0)
    tip = arm.tip_position(motion.balanced)
    falls = arm.tip_position(motion.control)
    assert np.max(np.linalg.norm(tip - tip[0], axis=1)) == pytest.approx(test.balanced.max_tip_drift, abs=1e-12)
    assert np.max(np.linalg.norm(falls - falls[0], axis=1)) == pytest.approx(test.control.max_tip_drift, rel=1e-9)
    assert test.balanced.max_tip_drift < 1e-9 and test.control.max_tip_drift > 1e-2  # still, and falling
    still, falls = motion.tip_travel(arm)
    assert still == pytest.approx(test.balanced.max_tip_drift, abs=1e-12)
    assert falls == pytest.approx(test.control.max_tip_drift, rel=1e-9)  # the control's Newton tolerance: 1e-8
    assert np.allclose(motion.balanced[0], poses[0])  # released where it was put
    short = motion.sampled(5)
    assert len(short.t) == 5 and short.t[0] == 0.0 and short.t[-1] == motion.t[-1]


def test_an_animation_is_deterministic_and_refuses_mismatched_scenes(arm, exact_springs, poses, tmp_path):
    from PIL import Image

    scene = drawing.chain_scene(arm, exact_springs, poses)
    one = drawing.animate({"a": (scene, "front"), "b": (scene, "side")}, tmp_path / "one.gif", times=[0, 1, 2])
    two = drawing.animate({"a": (scene, "front"), "b": (scene, "side")}, tmp_path / "two.gif", times=[0, 1, 2])
    assert Path(one).read_bytes() == Path(two).read_bytes()
    assert Image.open(one).n_frames == 3
    with pytest.raises(SpringlabError, match="common number of poses"):
        drawing.animate({"a": (scene, "front"), "b": (drawing.chain_scene(arm, exact_springs, poses[:2]), "front")},
                        tmp_path / "bad.gif")


@pytest.mark.parametrize("gif", sorted((ROOT / "figures").glob("*/*.gif")), ids=lambda p: p.parent.name)
def test_committed_animations_are_small(gif):
    from PIL import Image

    assert gif.stat().st_size < 2_000_000
    assert Image.open(gif).n_frames >= 10


def test_there_are_committed_animations():
    assert {p.parent.name for p in (ROOT / "figures").glob("*/*.gif")} >= {"juang2023_spatial_balance",
                                                                         "lin2010_pseudobases"}


def _distance_to_segment(p, a, b) -> float:
    ab = b - a
    t = np.clip(np.dot(p - a, ab) / max(np.dot(ab, ab), 1e-300), 0.0, 1.0)
    return float(np.linalg.norm(p - (a + t * ab)))


def floating(scene: drawing.Scene, pose: int = 0) -> list[str]:
    """The spring ends and centres of mass that lie on no link, bracket or the ground column."""
    joints = scene.links[0][pose]
    segments = [(joints[k], joints[k + 1]) for k in range(len(joints) - 1)]
    segments += [tuple(b) for b in (scene.brackets[pose] if scene.brackets is not None else [])]
    segments.append((scene.column[0] * scene.up, scene.column[1] * scene.up))
    points = {f"{label} {end}": P[pose] for label, (A, B) in scene.springs.items() for end, P in (("A", A), ("B", B))}
    points |= {f"centre of mass {k + 2}": c for k, c in enumerate(scene.masses[pose])}
    return [name for name, p in points.items() if min(_distance_to_segment(p, a, b) for a, b in segments) > 1e-12]


def test_no_spring_end_or_mass_floats(arm, exact_springs, poses):
    from springlab.mechanisms import two_spring_arm as an
    from springlab.papers import lenzo2017 as lenzo

    assert floating(drawing.chain_scene(arm, exact_springs, poses)) == []
    for layout, (a12, b12) in lenzo.FREE_CHOICES.items():  # c and d carry a countermass behind the elbow
        two = lenzo.ARM if layout in ("a", "b") else lenzo.ARM_COUNTERMASS
        d = an.solve(two, a2=lenzo.A2, a12=a12, b12=b12, layout=layout)
        chain = two.chain(lenzo.FOREARM_LENGTH)
        X = chain.directions(chain.random_angles(2, np.random.default_rng(1)))
        assert floating(drawing.chain_scene(chain, an.to_chain_springs(two, d), X)) == [], layout


def test_the_floating_check_can_fail(arm, exact_springs, poses):
    scene = drawing.chain_scene(arm, exact_springs, poses)
    bare = drawing.Scene(scene.up, scene.links, scene.springs, scene.column, masses=scene.masses)  # no brackets
    assert floating(bare) != []


def test_nothing_floats_on_paper_001s_arm():
    from springlab.mechanisms.pseudobase import subsystems as subs
    from springlab.papers import lin2010

    arm = lin2010.arm()
    springs = subs.design_equilibrators(arm, lin2010.K, lin2010.L_CA)
    q = np.random.default_rng(3).uniform(-np.pi, np.pi, (3, arm.n))
    scene = drawing.pseudobase_scene(arm, springs, q)
    assert len(scene.springs) == len(springs) and len(scene.extras) == len(arm.modules)
    for pose in range(3):
        assert floating(scene, pose) == []


# --- the drawings read at the book's width ----------------------------------------------------
BOOK_COLUMN = 750  # px: the book's text column; a figure is shown at its notebook size (figure.dpi), at most this wide
NOTEBOOK_DPI = 110  # springlab.mplstyle's figure.dpi: a saved PNG is shown at this many px per inch


def panel_widths_in_book(fig) -> list[float]:
    """The width (px) of each visible panel with data as the book shows the figure: at its
    notebook size, shrunk to the column when wider (the PNG is saved with bbox 'tight')."""
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    shown = fig.get_tightbbox(renderer).width * NOTEBOOK_DPI  # px, the tight bbox in inches
    shrink = min(1.0, BOOK_COLUMN / shown)
    return [ax.get_window_extent(renderer).width / fig.dpi * NOTEBOOK_DPI * shrink
            for ax in fig.axes if ax.get_visible() and ax.axison and ax.lines]


def overlapping_texts(fig) -> list[tuple[str, str]]:
    """Pairs of visible texts of the panels (spring labels, annotations, axis labels, titles)
    whose boxes overlap each other, or a legend."""
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    texts = [(t.get_text(), t.get_window_extent(renderer), ax) for ax in fig.axes
             for t in [*ax.texts, ax.xaxis.label, ax.yaxis.label, ax.title] if t.get_visible() and t.get_text()]
    legends = [lg.get_window_extent(renderer) for lg in [*fig.legends, *(ax.get_legend() for ax in fig.axes)] if lg]
    out = [(a, b) for k, (a, box_a, _) in enumerate(texts) for b, box_b, _ in texts[k + 1:] if box_a.overlaps(box_b)]
    out += [(a, "legend") for a, box, _ in texts for lg in legends if box.overlaps(lg)]
    return out


def outside_texts(fig) -> list[str]:
    """Spring labels (texts named S...) that leave their panel."""
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    out = []
    for ax in fig.axes:
        inside = ax.get_window_extent(renderer)
        for t in ax.texts:
            box = t.get_window_extent(renderer)
            if t.get_text().startswith("S") and not (inside.x0 <= box.x0 and box.x1 <= inside.x1
                                                     and inside.y0 <= box.y0 and box.y1 <= inside.y1):
                out.append(t.get_text())
    return out


@pytest.fixture
def styled():
    """The book's figure style (sizes, fonts, dpi), for the tests that measure figures."""
    import matplotlib.pyplot as plt

    from springlab.workbench.plotting import STYLE

    with plt.style.context(STYLE):
        yield


@pytest.fixture(scope="module")
def lin2010_scene():
    from springlab.mechanisms.pseudobase import subsystems as subs
    from springlab.model.trajectories import PiecewiseCubic
    from springlab.papers import lin2010

    arm = lin2010.arm()
    springs = subs.design_equilibrators(arm, lin2010.K, lin2010.L_CA)
    t = np.array([0.0, 0.5, 1.0]) * lin2010.DURATION
    return drawing.pseudobase_scene(arm, springs, PiecewiseCubic(lin2010.TABLE4[:, :4]).angles(t))


def test_the_overlap_checks_can_fail(styled):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.text(0.5, 0.5, "S2")
    ax.text(0.5, 0.5, "S3")  # on top of S2
    ax.text(1.5, 0.5, "S4")  # outside the axes
    assert overlapping_texts(fig) == [("S2", "S3")] and outside_texts(fig) == ["S4"]
    ax.plot([0, 1], [0, 1], label="a line")
    ax.legend(loc="center")  # over S2 and S3
    assert {b for _, b in overlapping_texts(fig)} == {"S3", "legend"}
    plt.close(fig)


def test_paper_001s_instants_read_at_the_books_width(lin2010_scene, styled):
    """One figure per instant, its three views two to a row: every panel at least 250 px wide in
    the book (the 3 x 3 grid it replaces: about 150 px), every spring named or in the legend,
    no two labels overlapping."""
    import matplotlib.pyplot as plt

    for pose in range(3):
        fig = drawing.mechanism_figure(lin2010_scene, [pose], views=drawing.VIEWS, columns=2, frame="shown")
        widths = panel_widths_in_book(fig)
        assert len(widths) == 3 and min(widths) >= 250, widths
        assert overlapping_texts(fig) == [] and outside_texts(fig) == []
        legend = {t.get_text() for t in fig.axes[3].get_legend().get_texts()}
        assert set(lin2010_scene.springs) <= legend  # every spring named by colour
        named = {t.get_text() for ax in fig.axes[:3] for t in ax.texts}
        assert len(named) >= 4  # most are named on the drawing as well
        plt.close(fig)
    grid = drawing.mechanism_figure(lin2010_scene, [0, 1, 2], views=drawing.VIEWS)  # the old 3 x 3: too small
    assert max(panel_widths_in_book(grid)) < 200
    plt.close(grid)


def test_one_scale_for_every_view_of_one_pose(lin2010_scene):
    import matplotlib.pyplot as plt

    fig = drawing.mechanism_figure(lin2010_scene, [1], views=drawing.VIEWS, columns=2, frame="shown")
    spans = {round(np.ptp(ax.get_xlim()), 12) for ax in fig.axes[:3]} | {round(np.ptp(ax.get_ylim()), 12) for ax in fig.axes[:3]}
    assert len(spans) == 1
    plt.close(fig)
    with pytest.raises(SpringlabError, match="frame must be"):
        drawing.mechanism_figure(lin2010_scene, [1], frame="tight")


def test_spring_labels_never_overlap_in_the_chain_figures(arm, exact_springs, poses, styled):
    import matplotlib.pyplot as plt

    fig = drawing.mechanism_figure(drawing.chain_scene(arm, exact_springs, poses), [0, 1, 2])
    assert overlapping_texts(fig) == [] and outside_texts(fig) == []
    plt.close(fig)


def test_paper_002s_drawing_has_a_legend_and_no_overlaps(styled):
    import matplotlib.pyplot as plt

    from springlab.papers import zhang2023
    from springlab.workbench.plotting import dyad_figure

    fig = dyad_figure(zhang2023.compensator(), zhang2023.printed_dyad("B"), np.radians([30, 60, 90, 120, 150]))
    names = [t.get_text() for lg in fig.legends for t in lg.get_texts()]
    assert len(names) >= 8 and any(n.startswith("spring") for n in names) and "slider B" in names
    assert overlapping_texts(fig) == []
    assert min(panel_widths_in_book(fig)) >= 200
    a, b = fig.axes
    assert a.get_xlim() == b.get_xlim() and a.get_ylim() == b.get_ylim()  # one scale
    plt.close(fig)


def test_paper_003s_configurations_are_drawn_to_scale(styled):
    import matplotlib.pyplot as plt

    from springlab.mechanisms.planar import model as pl
    from springlab.mechanisms.planar import synthesis as plsyn
    from springlab.papers import juang2022
    from springlab.workbench.plotting import planar_designs_figure

    arm = juang2022.ARM
    two = pl.PlanarArm(r=arm.r[:2], s=arm.s[:2], m=arm.m[:2], g=arm.g)
    designs = {"Λ1": (two, plsyn.design(two, "Λ1", {"A_S12": 0.1, "B_S12": 0.5})),
               "Λ3-1": (arm, plsyn.design(arm, "Λ3-1", juang2022.FREE_CHOICES))}
    fig = planar_designs_figure(designs, [60, -60, -45])
    one, full = fig.axes[:2]
    assert one.get_xlim()[1] - one.get_xlim()[0] == pytest.approx(full.get_xlim()[1] - full.get_xlim()[0])
    assert len(one.lines) < len(full.lines)  # one link and one spring, beside three links and four springs
    legend = {t.get_text() for t in fig.legends[0].get_texts()}
    assert {"S(1,2)", "S(1,4)", "S(2,4)", "S(3,4)"} <= legend
    assert overlapping_texts(fig) == [] and outside_texts(fig) == []
    assert min(panel_widths_in_book(fig)) >= 250
    plt.close(fig)
    chain, _ = pl.to_spatial(arm, designs["Λ3-1"][1])  # drawn at the angles given
    X = chain.directions(pl.spatial_angles(np.radians([[60, -60, -45]])))
    assert X[0, 1] @ X[0, 0] == pytest.approx(np.sin(np.radians(60)))  # link 2 at 60 deg above the horizontal


def arm_fill(scene: drawing.Scene, limits, view: str = "front") -> float:
    """The larger extent of the links and springs over every pose, over the panel's span."""
    pts = np.concatenate([link.reshape(-1, 3) for link in scene.links] + [np.vstack(ab) for ab in scene.springs.values()])
    return float(np.max(np.ptp(scene.project(pts, view), axis=0))) / limits[view][2]


def test_the_hold_animation_frames_the_arms_and_stops_at_the_floor(arm, exact_springs, poses, tmp_path):
    from PIL import Image

    motion = sim.hold_motion(arm, exact_springs, poses[0], duration=2.0)
    shown = drawing.hold_scenes(arm, exact_springs, motion, frames=9)
    for scene in (shown.balanced, shown.control):  # nothing drawn below the floor, the column stands on it
        assert np.all(drawing.lowest(scene) >= shown.floor) and scene.column[0] == shown.floor
    assert shown.stopped and 0 < shown.t[-1] < motion.t[-1]  # the control falls to the floor within 2 s
    limits = drawing.shared_limits({"a": (shown.balanced, "front"), "b": (shown.control, "front")})
    assert arm_fill(shown.balanced, limits) >= 0.6 and arm_fill(shown.control, limits) >= 0.6
    # negative controls: the whole run drawn on the column's own floor
    balanced = drawing.chain_scene(arm, exact_springs, motion.balanced)
    control = drawing.chain_scene(arm, [s.scaled(motion.control_scale) for s in exact_springs], motion.control)
    assert np.min(drawing.lowest(control)) < control.column[0]  # the control swings below that floor
    whole = drawing.shared_limits({"a": (balanced, "front"), "b": (control, "front")})
    assert arm_fill(balanced, whole) < 0.6  # and the still arm is lost in the frame of the fall
    gif = drawing.hold_animation(arm, exact_springs, motion, tmp_path / "hold.gif", frames=9)
    assert Image.open(gif).n_frames == len(shown.t) and Image.open(gif).size[0] >= 700  # the column's width


def smallest_label_gap(fig) -> float:
    """The smallest space (px) between two spring labels' texts in one panel (inf: none)."""
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    gaps = [np.inf]
    for ax in fig.axes:
        boxes = [t.get_window_extent(renderer) for t in ax.texts if t.get_text().startswith("S")]
        for k, a in enumerate(boxes):
            for b in boxes[k + 1:]:
                gaps.append(max(max(a.x0, b.x0) - min(a.x1, b.x1), max(a.y0, b.y0) - min(a.y1, b.y1)))
    return float(min(gaps))


def smallest_label_in_book(fig) -> float:
    """The height (px) of the smallest spring label's font as the book shows the figure (see
    :func:`panel_widths_in_book`)."""
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    shrink = min(1.0, BOOK_COLUMN / (fig.get_tightbbox(renderer).width * NOTEBOOK_DPI))
    return min(t.get_fontsize() for ax in fig.axes for t in ax.texts) * NOTEBOOK_DPI / 72 * shrink


@pytest.fixture(scope="module")
def fig15_poses(arm):
    """Paper 000's Fig. 15: the arm at the start, middle and end of Table 4's trajectory."""
    from springlab.model.trajectories import linear_sweep
    from springlab.papers import juang2023 as paper

    t, angles = linear_sweep(paper.TABLE_4_INITIAL, paper.TABLE_4_ROTATION, paper.DURATION, 301)
    X = arm.directions(angles)
    return t[[0, 150, 300]], X[[0, 150, 300]], arm.tip_position(X)


def test_paper_000s_fig15_reads_at_the_books_width(arm, exact_springs, fig15_poses, styled):
    """A row per instant, its two views side by side: every panel at least 280 px wide in the
    book and not shrunk, 8 pt labels (11 px), never closer than 4 px, every spring named by
    colour in the legend and on most panels."""
    import matplotlib.pyplot as plt

    from springlab.workbench.plotting import arm_figure

    t, X, tip = fig15_poses
    titles = [f"t = {s:.0f} s" for s in t]
    fig = arm_figure(arm, exact_springs, X, tip, titles=titles, title="Fig. 15")
    widths = panel_widths_in_book(fig)
    assert len(widths) == 6 and min(widths) >= 280, widths
    assert overlapping_texts(fig) == [] and outside_texts(fig) == []
    assert smallest_label_gap(fig) >= 4 and smallest_label_in_book(fig) >= 11
    labels = {f"S({s.i},{s.j})" for s in exact_springs}
    assert labels <= {t.get_text() for lg in fig.legends for t in lg.get_texts()}
    assert all(len({t.get_text() for t in ax.texts} & labels) >= 3 for ax in fig.axes)
    plt.close(fig)
    # the old drawing, poses side by side and a row per view: panels of about 170 px, labels of 9 px, touching
    old = drawing.mechanism_figure(drawing.chain_scene(arm, exact_springs, X, tip), [0, 1, 2], titles=titles,
                                   title="Fig. 15")
    assert max(panel_widths_in_book(old)) < 200 and smallest_label_gap(old) < 4 and smallest_label_in_book(old) < 10
    plt.close(old)


def mechanism_fill(scene: drawing.Scene, view: str, limits) -> float:
    """The share of a panel's frame (xlim, ylim, _) taken by the box round the mechanism over
    every pose (links, springs, pseudobases: not the column or its floor)."""
    pts = np.concatenate([link.reshape(-1, 3) for link in scene.links] + [np.vstack(ab) for ab in scene.springs.values()]
                         + [e.reshape(-1, 3) for e in scene.extras.values()])
    extent = np.ptp(scene.project(pts, view), axis=0)
    (x0, x1), (y0, y1), _ = limits
    return float(extent[0] * extent[1] / ((x1 - x0) * (y1 - y0)))


def test_paper_001s_animation_is_framed_on_the_mechanism_with_a_legend(lin2010_scene, styled, tmp_path):
    """The trajectory GIF: the column's width, each view framed on the mechanism over every pose
    (half its frame or more; the square frames it replaces: under a third), the arm at least
    400 px long, a legend naming every spring, labels that never overlap, its springs' own
    colours, the same bytes every time."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgb
    from PIL import Image

    panels = {f"{view} view": (lin2010_scene, view) for view in ("front", "side")}
    style = {k: v for k, v in drawing.TRAJECTORY_GIF.items() if k != "fps"}
    fig, frame, frames = drawing.animation_figure(panels, times=[0.0, 5.0, 10.0], title="Eq. (26)", **style)
    assert 700 <= fig.canvas.get_width_height()[0] <= 760
    assert set(lin2010_scene.springs) <= {t.get_text() for lg in fig.legends for t in lg.get_texts()}
    framed, square = drawing.framed_limits(panels), drawing.shared_limits(panels)
    for ax, (name, (scene, view)) in zip(fig.axes, panels.items(), strict=False):
        assert mechanism_fill(scene, view, framed[name]) >= 0.5, name
        assert mechanism_fill(scene, view, square[view]) < 0.35, name  # the old frames: the arm in a corner
        reach = float(np.ptp(scene.project(scene.links[0].reshape(-1, 3), view)[:, 0]))
        assert reach / framed[name][2] * ax.get_window_extent().width >= 400, name  # px
    for k in range(frames):
        frame(k)
        assert overlapping_texts(fig) == [] and outside_texts(fig) == []
    plt.close(fig)
    one = drawing.trajectory_animation(lin2010_scene, tmp_path / "one.gif", [0.0, 5.0, 10.0], title="Eq. (26)")
    two = drawing.trajectory_animation(lin2010_scene, tmp_path / "two.gif", [0.0, 5.0, 10.0], title="Eq. (26)")
    assert Path(one).read_bytes() == Path(two).read_bytes()
    with Image.open(one) as gif:
        assert gif.n_frames == 3 and 700 <= gif.size[0] <= 760
        colours = {c for _, c in gif.convert("RGB").getcolors(1 << 16)}
    drawn = [tuple(round(255 * v) for v in to_rgb(drawing._colour(label, k)))
             for k, label in enumerate(lin2010_scene.springs)]
    assert all(c in colours for c in drawn)  # each spring's colour kept exactly (legend, zigzag, label)


@pytest.mark.parametrize("gif", sorted((ROOT / "figures").glob("*/*.gif")), ids=lambda p: p.parent.name)
def test_committed_animations_fill_the_column(gif):
    """Shown at its own size in the book: about the text column's width (740 px), not less."""
    from PIL import Image

    with Image.open(gif) as im:
        assert 700 <= im.size[0] <= 760, im.size


def test_a_real_arms_spring_names_overlap_nothing_and_stay_in_their_panels(ur5_two_point, styled):
    """The UR5's six springs in three views: no name on another or on a legend, none out of its panel, every
    spring named in some view; its names tried farther from the zigzags than a paper's chain's."""
    import matplotlib.pyplot as plt

    from springlab.workbench.plotting import ARM_LABEL_CLEAR, real_arm_figure

    fig = real_arm_figure(ur5_two_point, title="UR5")
    assert overlapping_texts(fig) == [] and outside_texts(fig) == []
    named = {t.get_text() for ax in fig.axes for t in ax.texts}
    assert named == set(ur5_two_point.names) and len(named) == 6
    assert ARM_LABEL_CLEAR[0] == 3.0 and max(ARM_LABEL_CLEAR) > 3.0
    plt.close(fig)
