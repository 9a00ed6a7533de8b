"""An interactive 3-D view of a real arm with its springs, for the book: rotate, zoom, a slider over a few
poses, and a close-up of each spring.

The links are the URDF's own collision shapes (:attr:`~springlab.model.revolute.RevoluteChain.solids`:
meshes, boxes, cylinders, spheres, capsules), each mesh shown as its convex hull where it has more
triangles than :data:`MAX_FACES` (the hull of :data:`HULL_POINTS` of its vertices: the view is a picture;
the clearance check uses the meshes themselves).
The springs are the pieces the clearance check places (:func:`springlab.design.hardware.spring_pieces`):
each coil, cable and pulley at each pose.

It is drawn by plotly.js (plotly's ``Mesh3d`` and ``Scatter3d``), a well-kept library whose one
JavaScript file the book serves from its own ``_static`` folder (:func:`plotly_js`), so that the view
opens from ``build/site/`` with no network request; the page loads it once, when the first view needs it.
In Jupyter the output says where the view draws instead.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from springlab.design.hardware import spring_pieces
from springlab.model.revolute import body_frames

__all__ = ["MAX_FACES", "HULL_POINTS", "ArmView", "arm_view", "design_view", "plotly_js", "PLOTLY_JS"]

MAX_FACES = 800
"""A link mesh with more triangles than this is shown as its convex hull (a page stays light)."""

HULL_POINTS = 240
"""How many of a big mesh's vertices its hull is taken over."""

PLOTLY_JS = "plotly.min.js"
"""The file, in the book's ``_static`` folder, that draws the views."""

_LINK = "#b8c2cc"
_PART = {"coil": "#c0392b", "cable": "#2c3e50", "pulley": "#7f8c8d"}


def plotly_js() -> Path:
    """plotly.js as the plotly package ships it (``package_data/plotly.min.js``), found without importing
    plotly.

    :raises FileNotFoundError: when plotly is not installed
    """
    import importlib.util

    spec = importlib.util.find_spec("plotly")
    if spec is None or not spec.submodule_search_locations:
        raise FileNotFoundError("plotly is not installed: run `make` to build the environment")
    path = Path(list(spec.submodule_search_locations)[0]) / "package_data" / PLOTLY_JS
    if not path.exists():
        raise FileNotFoundError(f"{path}: plotly.js is missing from the plotly package")
    return path


def _primitive(kind: str, size: tuple):
    import trimesh

    if kind == "box":
        return trimesh.creation.box(extents=size)
    if kind == "cylinder":
        return trimesh.creation.cylinder(radius=size[0], height=size[1], sections=16)
    if kind == "sphere":
        return trimesh.creation.icosphere(subdivisions=1, radius=size[0])
    if kind == "capsule":
        return trimesh.creation.capsule(radius=size[0], height=size[1], count=[8, 8])
    return None


def _triangles(solid) -> tuple[np.ndarray, np.ndarray] | None:
    """A solid's vertices (its frame, m) and triangles, a big mesh by its hull."""
    import trimesh

    if solid.kind == "mesh":
        if not len(solid.faces):
            return None
        mesh = trimesh.Trimesh(solid.vertices, solid.faces, process=False)
        if len(solid.faces) > MAX_FACES:  # the hull of every k-th vertex (and each axis's extremes)
            v = np.asarray(solid.vertices, dtype=float)
            keep = np.r_[np.arange(0, len(v), max(1, len(v) // HULL_POINTS)), v.argmin(axis=0), v.argmax(axis=0)]
            mesh = trimesh.Trimesh(v[np.unique(keep)], process=False).convex_hull
    else:
        mesh = _primitive(solid.kind, solid.size)
        if mesh is None:
            return None
    return np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64)


@dataclass(frozen=True)
class ArmView:
    """The view's plotly figure (``data``, ``layout``, ``frames``: plotly.js's JSON) and its element id."""

    figure: dict
    element: str
    title: str

    def html(self) -> str:
        """The view as the book shows it: a div, and a script that loads ``_static/plotly.min.js`` once a
        page and draws into the div (the div says what it is until then)."""
        figure = json.dumps(self.figure, separators=(",", ":"))
        return (
            f'<div class="springlab-view3d" id="{self.element}" style="width:100%;height:560px" '
            f'aria-label="{self.title}">An interactive 3-D view draws here in the book '
            "(<code>make figures</code>, then <code>build/site/springlab_real_arms.html</code>).</div>"
            "<script>(function(){var el=document.getElementById(" + json.dumps(self.element) + ");"
            "var fig=" + figure + ";"
            "function close(e){var t=(fig.springs||{})[e.button.label.split(' ')[0]];if(!t)return;"
            "var lo=[1e9,1e9,1e9],hi=[-1e9,-1e9,-1e9];t.forEach(function(i){['x','y','z'].forEach(function(a,k){"
            "el.data[i][a].forEach(function(v){lo[k]=Math.min(lo[k],v);hi[k]=Math.max(hi[k],v);});});});"
            "var h=0.6*Math.max(hi[0]-lo[0],hi[1]-lo[1],hi[2]-lo[2])+0.03,u={};['x','y','z'].forEach(function(a,k){"
            "var c=(lo[k]+hi[k])/2;u['scene.'+a+'axis.range']=[c-h,c+h];});Plotly.relayout(el,u);}"
            "function draw(){el.textContent='';Plotly.newPlot(el,fig.data,fig.layout,fig.config)"
            ".then(function(){el.on('plotly_buttonclicked',close);return Plotly.addFrames(el,fig.frames);});}"
            "if(window.Plotly){draw();return;}"
            f"var src='_static/{PLOTLY_JS}';"
            "var all=window.__springlabViews=window.__springlabViews||{};var q=all[src]=all[src]||[];q.push(draw);"
            "if(q.length>1)return;var s=document.createElement('script');s.src=src;"
            "s.onload=function(){q.forEach(function(f){f();});};"
            "s.onerror=function(){document.querySelectorAll('.springlab-view3d').forEach(function(v){"
            "if(!v.querySelector('canvas'))v.dataset.failed='plotly.js did not load';});};"
            "document.head.appendChild(s);})();</script>")

    def _repr_html_(self) -> str:
        return self.html()


def _round(a) -> list:
    return np.round(np.asarray(a, dtype=float), 3).tolist()


def arm_view(design, q, *, labels=None, short_labels=None, title: str = "", element: str = "view") -> ArmView:
    """The 3-D view of ``design`` (:class:`~springlab.design.arms.ArmDesign` with link shapes) at the
    poses ``q`` (k, n) rad, a slider step each (``labels``: their names; ``short_labels``: what the slider
    prints for each, the names by default), with buttons for the whole arm and a close-up of each spring: in
    the page, the box of the spring at the pose the slider shows (its pieces' traces, ``springs`` of the
    figure); without the page's script, its box over every pose.

    :raises SpringlabError: when the arm has no link shapes or ``q`` is malformed
    """
    from springlab.errors import SpringlabError

    model = design.model
    if not model.solids or not any(len(s) for s in model.solids):
        raise SpringlabError(f"{model.name!r} has no link shapes to draw: a 3-D view needs the URDF's geometry")
    q = model.check_q(np.atleast_2d(q))
    labels = list(labels) if labels is not None else [f"pose {k + 1}" for k in range(len(q))]
    shorts = list(short_labels) if short_labels is not None else labels  # what the slider's ticks print
    R, o = body_frames(model, q)
    shapes = [(b, s.frame, *found) for b, solids in enumerate(model.solids) for s in solids
              if (found := _triangles(s)) is not None]
    pieces = spring_pieces(model, design.realised, design.kinds, design.coils, design.realised_names, q)

    def traces(p: int) -> list:
        out = []
        for b, frame, v, _ in shapes:
            w = (v @ frame[:3, :3].T + frame[:3, 3]) @ R[p, b].T + o[p, b]
            out.append({"x": _round(w[:, 0]), "y": _round(w[:, 1]), "z": _round(w[:, 2])})
        for piece in pieces:
            a, b = piece.a[p], piece.b[p]
            out.append({"x": _round([a[0], b[0]]), "y": _round([a[1], b[1]]), "z": _round([a[2], b[2]])})
        return out

    first = traces(0)
    data = []
    for (b, _, _, f), t in zip(shapes, first, strict=False):
        data.append({"type": "mesh3d", **t, "i": f[:, 0].tolist(), "j": f[:, 1].tolist(), "k": f[:, 2].tolist(),
                     "color": _LINK, "opacity": 0.55, "flatshading": True, "hoverinfo": "name",
                     "name": model.bodies[b], "showlegend": False})
    seen = set()
    for piece, t in zip(pieces, first[len(shapes):], strict=True):
        part = piece.name.split(" ")[-1]
        width = {"coil": 9, "cable": 3, "pulley": 3}[part]
        mode = "lines+markers" if part == "pulley" else "lines"
        data.append({"type": "scatter3d", "mode": mode, **t, "name": part, "legendgroup": part,
                     "showlegend": part not in seen, "hovertext": piece.name, "hoverinfo": "text",
                     "line": {"color": _PART[part], "width": width},
                     "marker": {"size": 5, "color": _PART[part]}})
        seen.add(part)
    frames = [{"name": label, "data": traces(p)} for p, label in enumerate(labels)]
    every = np.concatenate([np.c_[t["x"], t["y"], t["z"]] for f in frames for t in f["data"]])
    lo, hi = every.min(axis=0), every.max(axis=0)
    centre, half = (lo + hi) / 2, 0.55 * float(np.max(hi - lo))
    whole = {f"scene.{ax}axis.range": [float(centre[k] - half), float(centre[k] + half)]
             for k, ax in enumerate("xyz")}
    buttons = [{"label": "whole arm", "method": "relayout", "args": [whole]}]
    for name in design.realised_names:  # the box that holds the spring at every pose of the slider
        ends = np.concatenate([np.concatenate([piece.a, piece.b]) for piece in pieces
                               if piece.name.split(" ")[0] == name])
        c, h = (ends.min(axis=0) + ends.max(axis=0)) / 2, 0.6 * float(np.max(np.ptp(ends, axis=0))) + 0.03
        buttons.append({"label": f"{name} close", "method": "relayout",
                        "args": [{f"scene.{ax}axis.range": [float(c[k] - h), float(c[k] + h)]
                                  for k, ax in enumerate("xyz")}]})
    steps = [{"label": short, "method": "animate",
              "args": [[label], {"mode": "immediate", "frame": {"duration": 0, "redraw": True},
                                 "transition": {"duration": 0}}]} for label, short in zip(labels, shorts, strict=True)]
    axis = {"title": {"text": ""}, "showbackground": False}
    layout = {"title": {"text": title}, "margin": {"l": 0, "r": 0, "t": 40, "b": 0},
              "scene": {"aspectmode": "cube", "camera": {"eye": {"x": 1.1, "y": 1.1, "z": 0.7}}, **{f"{ax}axis": {**axis, "title": {"text": f"{ax} (m)"},
                                                               "range": whole[f"scene.{ax}axis.range"]}
                                                for ax in "xyz"}},
              "legend": {"x": 0, "y": 1},
              "updatemenus": [{"type": "buttons", "direction": "down", "x": 1.0, "xanchor": "right", "y": 1.0,
                               "buttons": buttons, "showactive": False}],
              "sliders": [{"steps": steps, "currentvalue": {"prefix": "pose: "}, "x": 0.05, "len": 0.9}]}
    config = {"displaylogo": False, "responsive": True, "modeBarButtonsToRemove": ["toImage"]}
    springs = {name: [len(shapes) + k for k, piece in enumerate(pieces) if piece.name.split(" ")[0] == name]
               for name in design.realised_names}  # each spring's traces: its close-up at the pose shown
    return ArmView({"data": data, "layout": layout, "frames": frames, "config": config, "springs": springs},
                   element, title)


def design_view(design, *, title: str = "", element: str | None = None, most: int = 9) -> ArmView:
    """:func:`arm_view` of ``design`` at the poses a reader wants to see: the first of its workspace, then the
    pose where each spring comes nearest a link (its clearance check's,
    :attr:`~springlab.design.arms.ArmDesign.clearance`), up to
    ``most`` poses, each labelled by what it shows."""
    q, labels, shorts = [design.q[0]], ["a workspace pose"], ["workspace"]
    for spring, _, link, pose, gap in (design.clearance.rows if design.clearance is not None else ()):
        if len(q) >= most:
            break
        if not any(np.allclose(design.q[pose], other) for other in q):
            q.append(design.q[pose])
            labels.append(f"{spring} nearest {link} ({1e3 * gap:.0f} mm)")
            shorts.append(f"{spring}: {1e3 * gap:.0f} mm")
    element = element or "view-" + "".join(ch for ch in (title or design.model.name) if ch.isalnum()).lower()
    return arm_view(design, np.asarray(q), labels=labels, short_labels=shorts, title=title, element=element)
