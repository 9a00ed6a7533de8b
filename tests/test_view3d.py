"""The real arms' interactive 3-D views (springlab.workbench.view3d): every link shape and spring piece
drawn at every pose, a close-up of each spring that frames it, plotly.js from the site's own folder; an arm
without shapes is refused. (That a view draws in Chromium, and that one fetching plotly.js from a network is
caught, is the browser check's test, in tests/test_book.py.)"""

import json

import numpy as np
import pytest

from springlab.design.hardware import spring_pieces
from springlab.errors import SpringlabError
from springlab.workbench import view3d


@pytest.fixture(scope="module")
def pendulum(pendulum_belts):
    return pendulum_belts  # the double pendulum's belt design (tests/conftest.py)


def test_the_view_draws_every_shape_and_piece_at_every_pose(pendulum):
    q = pendulum.q[:3]
    view = view3d.arm_view(pendulum, q, labels=["a", "b", "c"], element="dp")
    fig = view.figure
    solids = sum(len(s) for s in pendulum.model.solids)
    pieces = spring_pieces(pendulum.model, pendulum.realised, pendulum.kinds, pendulum.coils,
                           pendulum.realised_names, q)
    assert [t["type"] for t in fig["data"]] == ["mesh3d"] * solids + ["scatter3d"] * len(pieces)
    assert [f["name"] for f in fig["frames"]] == ["a", "b", "c"]
    assert all(len(f["data"]) == len(fig["data"]) for f in fig["frames"])
    for p in range(3):  # each piece at each pose, where the clearance check puts it (to the mm the view keeps)
        for piece, trace in zip(pieces, fig["frames"][p]["data"][solids:], strict=True):
            drawn = np.c_[trace["x"], trace["y"], trace["z"]]
            assert np.allclose(drawn, [piece.a[p], piece.b[p]], atol=6e-4)
    buttons = fig["layout"]["updatemenus"][0]["buttons"]
    assert [b["label"] for b in buttons] == ["whole arm", *(f"{n} close" for n in pendulum.realised_names)]
    for name, button in zip(pendulum.realised_names, buttons[1:], strict=True):  # the close-up frames its spring
        ranges = [button["args"][0][f"scene.{ax}axis.range"] for ax in "xyz"]  # at every pose of the slider
        ends = np.concatenate([np.concatenate([pc.a, pc.b]) for pc in pieces if pc.name.startswith(name + " ")])
        assert all(lo < ends[:, k].min() and ends[:, k].max() < hi for k, (lo, hi) in enumerate(ranges))
    for name, traces in fig["springs"].items():  # the page's close-up reads these traces at the pose shown
        assert [pieces[t - solids].name.split(" ")[0] for t in traces] == [name] * len(traces) and traces
    html = view.html()
    assert "plotly_buttonclicked" in html
    assert "_static/plotly.min.js" in html and "http" not in html.split("</div>", 1)[1]  # no network
    assert json.loads(html.split("var fig=", 1)[1].split(";function close", 1)[0])["frames"]


def test_an_arm_without_shapes_is_refused(pendulum):
    from dataclasses import replace

    bare = replace(pendulum, model=replace(pendulum.model, solids=()))
    with pytest.raises(SpringlabError, match="no link shapes"):
        view3d.arm_view(bare, pendulum.q[:1])


def test_plotly_js_is_the_packaged_file():
    path = view3d.plotly_js()
    assert path.name == view3d.PLOTLY_JS and path.stat().st_size > 1_000_000


def test_the_design_view_shows_where_each_spring_comes_nearest_a_link(pendulum):
    view = view3d.design_view(pendulum, title="double pendulum")
    labels = [f["name"] for f in view.figure["frames"]]
    ticks = [step["label"] for step in view.figure["layout"]["sliders"][0]["steps"]]
    assert ticks[0] == "workspace" and all(t == lab.split(" nearest")[0] + ": " + lab.split("(")[1].rstrip(")")
                                           for t, lab in zip(ticks[1:], labels[1:], strict=True))  # short ticks
    assert labels[0] == "a workspace pose" and view.element == "view-doublependulum" and len(labels) > 1
    nearest = {row[0]: row for row in pendulum.clearance.rows}
    for label in labels[1:]:  # each names a spring, the link it comes nearest and by how much
        spring = label.split(" ")[0]
        assert label == f"{spring} nearest {nearest[spring][2]} ({1e3 * nearest[spring][4]:.0f} mm)"
