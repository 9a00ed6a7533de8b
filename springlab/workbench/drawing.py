"""Mechanisms drawn so a reader understands them at a glance, and animated.

A :class:`Scene` holds what a drawing shows at N poses, in world coordinates (m): the moving
links as polylines joint to joint, the springs' ends, the ground column and any extra bodies
(pseudobases). :func:`mechanism_figure` draws chosen poses side by side in orthographic
projection views (front, side, top) with equal axes and one scale for every panel, like a
paper's figure:

* the ground: a hatched floor and the base column, drawn up to its highest attachment;
* links as thick segments, joints as open circles;
* springs as zigzags between their attachment points (black dots), labelled S(i,j).

:func:`animate` writes the same drawing, frame by frame, as a GIF (Pillow,
headless, deterministic: the same scene gives the same bytes; each frame drawn once by Agg and
quantised by Pillow, to 64 colours or to the drawing's own :func:`palette`);
:func:`trajectory_animation` frames it on the mechanism at the book's column width, with a
legend. Builders: :func:`chain_scene`
(the serial chain of papers 000/003 and a user's arm), :func:`pseudobase_scene` (paper 001's
arm with its pseudobases).

Coordinates: a view's horizontal axis and the vertical ``up`` are named by the world axes
(the chain's up is x_1; paper 001's frame 0 has z up)::

        up                 front view: (h1, up)   side view: (h2, up)   top view: (h1, h2)
        |
        +--- h1            up = x -> (h1, h2) = (y, z); up = z -> (x, y); up = y -> (z, x)
       /
     h2
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from springlab.errors import SpringlabError
from springlab.workbench.images import unchanged_gif

VIEWS = ("front", "side", "top")
_AXES = "xyz"
SPRING_COLOURS = ("tab:red", "tab:orange", "tab:purple", "tab:brown", "tab:pink", "tab:olive", "tab:cyan",
                  "tab:green")
"""One colour per spring, in the order of the scene's springs (the legend names them)."""
LINK_COLOUR = "0.15"
COLUMN_COLOUR = "0.55"
SHELL_COLOUR = "0.88"
AUXILIARY_COLOUR = "0.6"


@dataclass(frozen=True)
class Scene:
    """What a drawing of a mechanism shows at N poses (world coordinates, m).

    :ivar up: (3,) the world's unit up vector (gravity along -up), a coordinate axis
    :ivar links: the moving links, each (N, k, 3): a polyline joint to joint
    :ivar springs: {label: (A (N, 3), B (N, 3))}: each spring's two attachment points
    :ivar column: (bottom, top) of the ground column along ``up`` at the origin (m)
    :ivar extras: {label: (N, k, 3)} other bodies drawn as thinner blue polylines (pseudobases)
    :ivar path: optional (T, 3) path of the end point
    :ivar brackets: (N, k, 2, 3) segments that carry a spring's end or a centre of mass off its
        link's segment (a link's extension past a joint): drawn grey, so that nothing floats
    :ivar masses: optional (N, m, 3) centres of mass
    :ivar ground: the legend's name of the base column
    :ivar shells: each body's outline, (N, k, 3) points whose hull is the body (a URDF's geometry):
        drawn as light grey silhouettes behind the links
    :ivar cables: {spring label: [(P (N, 3), Q (N, 3)), ...]}: a realised spring's cable runs, drawn as thin
        lines in its colour (its ``springs`` entry is then its coil)
    :ivar pulleys: {spring label: (centre (N, 3), radius m)}: its pulley, drawn as a circle of its radius
    :ivar auxiliary: polylines (N, k, 3) of links that carry no load of the arm's own but close a loop (paper
        001's auxiliary links of its RSSR modules, with the brackets to each pseudobase's end): drawn thinner
        and lighter than the links
    """

    up: np.ndarray
    links: list
    springs: dict
    column: tuple
    extras: dict = field(default_factory=dict)
    path: np.ndarray | None = None
    brackets: np.ndarray | None = None
    masses: np.ndarray | None = None
    ground: str = "ground (link 1)"
    shells: list = field(default_factory=list)
    cables: dict = field(default_factory=dict)
    pulleys: dict = field(default_factory=dict)
    auxiliary: list = field(default_factory=list)

    @property
    def poses(self) -> int:
        return int(self.links[0].shape[0])

    def horizontal(self) -> tuple[int, int]:
        """The world axes (indices) of the horizontal directions h1, h2."""
        k = int(np.argmax(np.abs(self.up)))
        if not np.isclose(abs(self.up[k]), 1.0):
            raise SpringlabError(f"Scene.up must be a coordinate axis, got {self.up}: rotate the scene first")
        return (k + 1) % 3, (k + 2) % 3

    def project(self, points, view: str) -> np.ndarray:
        """``points`` (..., 3) in ``view``'s plane (..., 2): (horizontal, up) or (h1, h2) for top."""
        if view not in VIEWS:
            raise SpringlabError(f"view must be one of {VIEWS}, got {view!r}")
        h1, h2 = self.horizontal()
        p = np.asarray(points, dtype=float)
        height = p @ self.up
        if view == "front":
            return np.stack([p[..., h1], height], axis=-1)
        if view == "side":
            return np.stack([p[..., h2], height], axis=-1)
        return np.stack([p[..., h1], p[..., h2]], axis=-1)

    def axis_labels(self, view: str) -> tuple[str, str]:
        h1, h2 = self.horizontal()
        up = f"{_AXES[int(np.argmax(np.abs(self.up)))]}, up (m)"
        return {"front": (f"{_AXES[h1]} (m)", up), "side": (f"{_AXES[h2]} (m)", up),
                "top": (f"{_AXES[h1]} (m)", f"{_AXES[h2]} (m)")}[view]

    def all_points(self) -> np.ndarray:
        parts = [link.reshape(-1, 3) for link in self.links]
        parts += [np.vstack(ab) for ab in self.springs.values()]
        parts += [np.vstack(run) for runs in self.cables.values() for run in runs]
        parts += [e.reshape(-1, 3) for e in self.extras.values()]
        parts += [b.reshape(-1, 3) for b in (self.brackets, self.masses) if b is not None]
        parts += [shell.reshape(-1, 3) for shell in self.shells]
        parts += [a.reshape(-1, 3) for a in self.auxiliary]
        parts.append(np.outer(self.column, self.up))
        if self.path is not None:
            parts.append(np.asarray(self.path).reshape(-1, 3))
        return np.vstack(parts)


def chain_scene(chain, springs, X, tip_path=None) -> Scene:
    """The serial chain (:class:`springlab.model.chain.Chain`) at poses X (N, n, 3): links 2..n
    from joint to joint, the ground column from the lowest to the highest point on link 1
    (the base joint, its springs' ends), the springs S(i,j) (route 2's attachment points)."""
    from springlab.energy.geometry import attachment_points

    X = chain.check_directions(X)
    joints = chain.joint_positions(X)
    up = X[0, 0]
    ends, brackets = {}, []
    for s in springs:
        A, B = attachment_points(chain, s, X)
        label = f"S({s.i},{s.j})"
        while label in ends:
            label += "'"
        ends[label] = (A, B)
        # A = J_i + a x_i lies on link i's segment J_(i-1) J_i for -r_i <= a <= 0; B = J_(j-1) + b x_j
        # on link j's for 0 <= b <= r_j; past either end it sits on a bracket from the nearer joint
        if s.i > 1 and s.a > 0:
            brackets.append((joints[:, s.i - 1], A))
        elif s.i > 1 and s.a < -chain.r[s.i - 2]:
            brackets.append((joints[:, s.i - 2], A))
        if s.b < 0:
            brackets.append((joints[:, s.j - 2], B))
        elif s.b > chain.r[s.j - 2]:
            brackets.append((joints[:, s.j - 1], B))
    coms = chain.com_positions(X)
    for j, (d, r) in enumerate(zip(chain.d, chain.r, strict=True)):  # a countermass past a joint
        if d < 0:
            brackets.append((joints[:, j], coms[:, j]))
        elif d > r:
            brackets.append((joints[:, j + 1], coms[:, j]))
    on_ground = [0.0] + [s.a for s in springs if s.i == 1]
    column = (min(min(on_ground), -0.08 * sum(chain.r)), max(on_ground))
    bracket = np.stack([np.stack(b, axis=1) for b in brackets], axis=1) if brackets else None
    return Scene(np.asarray(up, dtype=float), [joints], ends, column, path=tip_path, brackets=bracket,
                 masses=coms)


def revolute_scene(model, springs, q) -> Scene:
    """An arm of the general model (:class:`springlab.model.revolute.RevoluteChain`) at joint angles q
    (N, n): the chain through its joints' origins to the last body's farthest fixed frame (a flange),
    its centres of mass, the springs between their points (route 2's placement), each spring end
    and centre of mass on a grey bracket from its body's joint, the base column under the first
    joint, and each body's outline (its URDF geometry, where known). Springs are named S1, S2, ... in
    their order."""
    from springlab.model.revolute import body_frames, centres_of_mass, world_points

    q = model.check_q(q)
    R, o = body_frames(model, q)
    ends = [o[:, b] for b in range(1, model.n + 1)]
    far = [(name, T) for name, (b, T) in model.fixed.items() if b == model.n]
    if far:  # the farthest frame fixed to the last body (a flange, a tool0) closes the chain
        name, T = max(far, key=lambda item: float(np.linalg.norm(item[1][:3, 3])))
        ends.append(world_points(R, o, model.n, T[:3, 3]))
    joints = np.stack([np.zeros_like(ends[0])] + ends, axis=1) if np.any(o[0, 1]) else np.stack(ends, axis=1)
    springs_at, brackets = {}, []
    for k, s in enumerate(springs, start=1):
        (ia, pa), (ib, pb) = model.locate(s.link_a, s.point_a), model.locate(s.link_b, s.point_b)
        A, B = world_points(R, o, ia, pa), world_points(R, o, ib, pb)
        springs_at[f"S{k}"] = (A, B)
        brackets += [np.stack([o[:, ia], A], axis=1), np.stack([o[:, ib], B], axis=1)]
    coms = centres_of_mass(model, R, o)[:, 1:]
    brackets += [np.stack([o[:, b], coms[:, b - 1]], axis=1) for b in range(1, model.n + 1)]
    up = model.up
    heights = [0.0] + [float(np.min(A @ up)) for A, _ in springs_at.values()]
    column = (min(min(heights), -0.05), float(o[0, 1] @ up))
    shells = [o[:, b, None] + np.einsum("pab,kb->pka", R[:, b], points)
              for b, points in enumerate(model.outline) if len(points) >= 3]
    return Scene(np.asarray(up, dtype=float), [joints], springs_at, column,
                 brackets=np.stack(brackets, axis=1) if brackets else None, masses=coms,
                 ground=f"base ({model.bodies[0]})", shells=shells)


def hardware_scene(design, q) -> Scene:
    """A URDF arm's design (:class:`springlab.design.arms.ArmDesign`) at joint angles ``q`` (N, n) rad with
    its realised springs as built (:func:`springlab.design.hardware.spring_pieces`): each coil between its
    hooks (drawn as the spring), its cable runs, and its pulley; named as the design names them."""
    from dataclasses import replace

    from springlab.design.hardware import spring_pieces

    q = design.model.check_q(q)
    scene = revolute_scene(design.model, design.realised, q)
    pieces = spring_pieces(design.model, design.realised, design.kinds, design.coils, design.realised_names, q)
    springs, cables, pulleys = {}, {}, {}
    for piece in pieces:
        name, _, part = piece.name.partition(" ")
        if part == "coil":
            springs[name] = (piece.a, piece.b)
        elif part == "cable":
            cables.setdefault(name, []).append((piece.a, piece.b))
        elif part == "pulley":
            pulleys[name] = (piece.a, piece.radius)
    return replace(scene, springs=springs, cables=cables, pulleys=pulleys)


def pseudobase_scene(arm, springs, q) -> Scene:
    """Paper 001's arm at joint angles q (N, n): the primary links through the frame origins, the
    auxiliary links through their own (the primary frames' origins moved by the auxiliary chain's offset,
    001 Section 4) with a bracket from each module's auxiliary link to D_i and from its primary link to
    C_i (so each RSSR loop is closed in the drawing), each module's pseudobase as the segment C_i D_i (it
    keeps its direction at every pose),
    the equilibrator springs A B with their brackets (A_i on the pseudobase's line, B_i fixed to
    link i at O_i) and the primary links' centres of mass (each fixed in its frame, at O_i)
    (route 2's positions)."""
    from springlab.mechanisms.pseudobase.geometry import positions

    p = positions(arm, springs, q)
    springs = list(springs)
    ends = {f"S{sp.link}": (p["A"][:, k], p["B"][:, k]) for k, sp in enumerate(springs)}
    extras = {f"pseudobase {i}": np.stack([p["C"][:, k], p["D"][:, k]], axis=1) for k, i in enumerate(arm.modules)}
    origins = p["O"]
    hat = origins + np.asarray(arm.aux_offset, dtype=float)  # the auxiliary chain's frame origins
    first = arm.modules[0] - 1  # the body the first module's auxiliary link is jointed to, at Ô_first
    auxiliary = [hat[:, [first, *arm.modules]], np.stack([origins[:, first], hat[:, first]], axis=1)]
    auxiliary += [np.stack([hat[:, i], p["D"][:, k]], axis=1) for k, i in enumerate(arm.modules)]
    auxiliary += [np.stack([origins[:, i], p["C"][:, k]], axis=1) for k, i in enumerate(arm.modules)]
    column_k = {i: k for k, i in enumerate(arm.modules)}
    # A_i sits on the pseudobase's line, l_CA from C_i; B_i on a bracket fixed to link i at O_i
    brackets = [np.stack([p["C"][:, column_k[sp.link]], p["A"][:, k]], axis=1) for k, sp in enumerate(springs)]
    brackets += [np.stack([origins[:, sp.link], p["B"][:, k]], axis=1) for k, sp in enumerate(springs)]
    brackets += [np.stack([origins[:, i], p["com"][:, i - 1]], axis=1) for i in range(1, arm.n + 1)]  # in frame i
    base = np.asarray(arm.up, dtype=float)
    low = min(0.0, float(np.min(origins @ base)))
    column = (low - 0.05 * float(np.ptp(origins @ base) + 1e-9), float(np.max(origins[:, :2] @ base)))
    return Scene(base, [origins], ends, column, extras,
                 brackets=np.stack(brackets, axis=1) if brackets else None, masses=p["com"], auxiliary=auxiliary)


def zigzag(P, Q, *, coils: int = 6, width: float) -> np.ndarray:
    """A spring drawn from P to Q (2-D points): straight leads of 15 % at each end and
    ``coils`` zigzags of half-width ``width`` (m) between. (M, 2) points; P alone when P = Q."""
    P, Q = np.asarray(P, dtype=float), np.asarray(Q, dtype=float)
    d = Q - P
    length = float(np.hypot(*d))
    if length < 1e-12:
        return P[None, :]
    u = d / length
    n = np.array([-u[1], u[0]])
    w = min(width, 0.25 * length)
    s = np.linspace(0.15, 0.85, 2 * coils + 1)
    offsets = np.zeros_like(s)
    offsets[1:-1] = w * np.where(np.arange(1, 2 * coils) % 2 == 1, 1.0, -1.0)
    body = P + np.outer(s * length, u) + np.outer(offsets, n)
    return np.vstack([P, body, Q])


def _limits(scene: Scene, view: str, margin: float = 0.08):
    pts = scene.project(scene.all_points(), view)
    low, high = pts.min(axis=0), pts.max(axis=0)
    span = float(max(high - low)) * (1 + 2 * margin) or 1.0
    centre = (low + high) / 2
    return (centre[0] - span / 2, centre[0] + span / 2), (centre[1] - span / 2, centre[1] + span / 2), span


def draw(ax, scene: Scene, pose: int, view: str, *, labels: bool = True, limits=None, colours=None,
         label_style: dict | None = None) -> list:
    """Draw ``scene`` at ``pose`` in ``view`` on ``ax``; returns the artists (for animation).
    ``colours``: {spring label: colour}, by default :data:`SPRING_COLOURS` in the scene's order;
    ``label_style``: :func:`label_springs`'s keywords (fontsize, gap, clear)."""
    xlim, ylim, span = limits or _limits(scene, view)
    artists = []
    if view != "top":  # the floor and the base column, seen from the side
        bottom, top = scene.column
        floor = np.array([[-0.12 * span, bottom], [0.12 * span, bottom]])
        artists += ax.plot(*floor.T, color="k", linewidth=1.2)
        for x in np.linspace(-0.12 * span, 0.1 * span, 8):
            artists += ax.plot([x, x + 0.025 * span], [bottom - 0.025 * span, bottom], color="k", linewidth=0.6)
        artists += ax.plot([0, 0], [bottom, top], color=COLUMN_COLOUR, linewidth=7, solid_capstyle="butt",
                           label=scene.ground, zorder=1)
    else:
        artists += ax.plot([0], [0], "s", color=COLUMN_COLOUR, markersize=9, label=scene.ground, zorder=1)
    for k, shell in enumerate(scene.shells):
        outline = _hull(scene.project(shell[pose], view))
        artists += ax.fill(*outline.T, facecolor=SHELL_COLOUR, edgecolor="0.6", linewidth=0.5, zorder=0.5,
                           label="links' outlines (URDF geometry)" if k == 0 else None)
    for k, chain in enumerate(scene.auxiliary):
        pts = scene.project(chain[pose], view)
        artists += ax.plot(*pts.T, color=AUXILIARY_COLOUR, linewidth=1.8, solid_capstyle="round", zorder=2,
                           marker="o", markersize=3, label="auxiliary links" if k == 0 else None)
    for name, body in scene.extras.items():
        pts = scene.project(body[pose], view)
        artists += ax.plot(*pts.T, color="tab:blue", linewidth=2.4, solid_capstyle="round", zorder=2,
                           label="pseudobase" if name == next(iter(scene.extras)) else None)
    if scene.brackets is not None:
        for k, segment in enumerate(scene.brackets[pose]):
            artists += ax.plot(*scene.project(segment, view).T, color=COLUMN_COLOUR, linewidth=2.6,
                               solid_capstyle="round", zorder=2, label="brackets" if k == 0 else None)
    for link in scene.links:
        pts = scene.project(link[pose], view)
        artists += ax.plot(*pts.T, color=LINK_COLOUR, linewidth=4.5, solid_capstyle="round", zorder=3,
                           label="links" if link is scene.links[0] else None)
        artists += ax.plot(*pts.T, "o", markersize=6, markerfacecolor="white", markeredgecolor="k",
                           markeredgewidth=1.2, zorder=5)
    if scene.masses is not None:
        artists += ax.plot(*scene.project(scene.masses[pose], view).T, "o", color="tab:blue", markersize=4.5,
                           zorder=6, label="centres of mass")
    for k, (label, (A, B)) in enumerate(scene.springs.items()):
        P, Q = scene.project(A[pose], view), scene.project(B[pose], view)
        colour = _colour(label, k, colours)
        coils = int(np.clip(round(30 * float(np.hypot(*(Q - P))) / span), 2, 6))  # a short spring: fewer coils
        pts = zigzag(P, Q, coils=coils, width=0.018 * span)
        artists += ax.plot(*pts.T, color=colour, linewidth=1.5, zorder=4, label=label)
        artists += ax.plot(*np.array([P, Q]).T, "o", color="k", markersize=3.2, zorder=6,
                           label="attachment points" if k == 0 else None)
    for k, (label, runs) in enumerate(scene.cables.items()):
        colour = _colour(label, list(scene.springs).index(label) if label in scene.springs else k, colours)
        for m, (P, Q) in enumerate(runs):
            artists += ax.plot(*scene.project(np.array([P[pose], Q[pose]]), view).T, color=colour, linewidth=0.8,
                               zorder=4, label="cables" if k == 0 and m == 0 else None)
    for k, (label, (centre, radius)) in enumerate(scene.pulleys.items()):
        colour = _colour(label, list(scene.springs).index(label) if label in scene.springs else k, colours)
        turn = np.linspace(0.0, 2 * np.pi, 41)
        circle = scene.project(centre[pose], view) + radius * np.stack([np.cos(turn), np.sin(turn)], axis=1)
        artists += ax.plot(*circle.T, color=colour, linewidth=0.9, zorder=4,
                           label="pulleys (circles of their radius)" if k == 0 else None)
    if scene.path is not None:
        artists += ax.plot(*scene.project(scene.path, view).T, color="tab:blue", linewidth=0.9,
                           linestyle="--", label="end-point path", zorder=2)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal")
    xl, yl = scene.axis_labels(view)
    ax.set_xlabel(xl)
    ax.set_ylabel(yl)
    if labels:
        artists += label_springs(ax, scene, pose, view, colours=colours, **(label_style or {}))
    return artists


def _hull(points) -> np.ndarray:
    """The convex hull of 2-D points, as a closed polygon (its points when they are degenerate)."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        return points[ConvexHull(points).vertices]
    except (QhullError, ValueError):
        return points


def _colour(label: str, k: int, colours=None):
    return (colours or {}).get(label, SPRING_COLOURS[k % len(SPRING_COLOURS)])


def label_springs(ax, scene: Scene, pose: int, view: str, *, colours=None, fontsize: float = 7,
                  gap: float = 2.0, clear=(3.0,)) -> list:
    """Name each spring S(i,j) beside its zigzag, where the name overlaps no other and stays in
    the axes; returns the texts. ``fontsize`` (pt); ``gap``: the least space (px) between two
    labels' texts (their white backgrounds reach about 1 px past the text, so a gap of 2 px
    lets them touch); ``clear``: the distances (px) from the zigzag tried, nearest first.

    Each label tries places along its spring (its middle first, then towards the ends), on
    either side, ``clear`` px from the zigzag, in the axes' current pixels (so call it once the
    figure is laid out): first a place clear of every spring too, then one clear of the other
    labels only. A label that finds no free place is left out: the legend names every spring
    by its colour."""
    from matplotlib.transforms import Bbox

    ax.apply_aspect()  # the box equal axes will have once drawn
    renderer = ax.figure.canvas.get_renderer()
    inside = ax.get_window_extent(renderer)
    to_pixels = ax.transData.transform
    span = abs(np.subtract(*ax.get_xlim()))  # m: the panel's width, as draw's limits
    scale = abs(np.subtract(*to_pixels([[0.0, 0.0], [span, 0.0]])[:, 0])) / span  # px per m
    ends = [(to_pixels(scene.project(A[pose], view)), to_pixels(scene.project(B[pose], view)))
            for A, B in scene.springs.values()]
    widths = [min(0.018 * span, 0.25 * float(np.hypot(*(Q - P))) / scale) * scale for P, Q in ends]  # see draw
    springs = [Bbox([np.minimum(P, Q), np.maximum(P, Q)]).padded(w) for (P, Q), w in zip(ends, widths, strict=True)]
    placed, texts = [], []
    for k, (label, (P, Q), w) in enumerate(zip(scene.springs, ends, widths, strict=True)):
        d = Q - P
        length = float(np.hypot(*d))
        u = d / length if length > 1e-9 else np.array([1.0, 0.0])
        normal = np.array([-u[1], u[0]])
        colour = _colour(label, k, colours)
        places = [(t, side, c) for c in clear for t in (0.5, 0.3, 0.7, 0.1, 0.9) for side in (1.0, -1.0)]
        for avoid_springs, (t, side, c) in [(a, place) for a in (True, False) for place in places]:
            off = side * normal
            at = ax.transData.inverted().transform(P + t * d + (w + c) * off)  # c px clear of the zigzag
            text = ax.text(*at, label, color=colour, fontsize=fontsize, zorder=7,
                           ha="left" if off[0] > 0.35 else "right" if off[0] < -0.35 else "center",
                           va="bottom" if off[1] > 0.35 else "top" if off[1] < -0.35 else "center",
                           bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.75, "pad": 0.4})
            box = text.get_window_extent(renderer).padded(gap / 2)
            blocked = placed + ([b for j, b in enumerate(springs) if j != k] if avoid_springs else [])
            if (inside.x0 <= box.x0 and box.x1 <= inside.x1 and inside.y0 <= box.y0 and box.y1 <= inside.y1
                    and not any(box.overlaps(other) for other in blocked)):
                placed.append(box)
                texts.append(text)
                break
            text.remove()
    return texts


def mechanism_figure(scene: Scene, poses, *, views=("front", "side"), titles=None, title: str = "",
                     columns: int | None = None, frame: str = "all", rows: str = "views",
                     label_style: dict | None = None):
    """``scene`` at ``poses`` (indices, at most 4) side by side, one row per view, every panel
    at one scale. Returns the matplotlib figure.

    One pose: its views side by side, ``columns`` to a row (default all); the legend takes
    the first free panel, if any, else goes below. ``frame``: "all" frames the panels on
    every pose of the scene (so that drawings of its poses share their limits), "shown" on
    the poses drawn (a larger drawing).

    ``rows="poses"``: one row per pose instead, its views side by side (two views: two panels
    to a row, each about 330 px wide at the book's width, every panel at one scale and its
    springs named on it), the legend below. ``label_style``: :func:`label_springs`'s keywords
    (fontsize, gap, clear)."""
    import matplotlib.pyplot as plt

    poses = [int(p) for p in np.atleast_1d(poses)]
    if not poses or len(poses) > 4 or any(not 0 <= p < scene.poses for p in poses):
        raise SpringlabError(f"poses must be 1 to 4 indices in 0..{scene.poses - 1}, got {poses}")
    if frame not in ("all", "shown"):
        raise SpringlabError(f"frame must be 'all' or 'shown', got {frame!r}")
    if rows not in ("views", "poses"):
        raise SpringlabError(f"rows must be 'views' or 'poses', got {rows!r}")
    views = tuple(views)
    named = titles is not None
    titles = list(titles) if named else [f"pose {p + 1}" for p in poses]
    framed = scene if frame == "all" else _at(scene, poses)
    spans = [_limits(framed, v) for v in views]
    label_style = label_style or {}
    if rows == "poses":
        return _poses_in_rows(scene, poses, views, spans, titles, title, label_style)
    across = len(poses) == 1  # one pose: its views side by side
    if across:  # one scale for every view: the largest span, each view about its own centre
        span = max(b[2] for b in spans)
        spans = [(_about(xlim, span), _about(ylim, span), span) for xlim, ylim, _ in spans]
        cols = min(columns or len(views), len(views))
        n_rows = -(-len(views) // cols)
        size = (3.2 * cols + 0.4, 3.2 * n_rows + 0.4)
    else:
        n_rows, cols = len(views), len(poses)
        size = (2.7 * cols + 0.6, 2.8 * n_rows + 0.5)
    fig, axes = plt.subplots(n_rows, cols, figsize=size, squeeze=False)
    panels = []
    for r, view in enumerate(views):
        for c, pose in enumerate(poses):
            ax = axes.flat[r] if across else axes[r][c]
            draw(ax, scene, pose, view, labels=False, limits=spans[r])
            ax.set_title(f"{titles[c]}, {view} view" if r == 0 and not across else f"{view} view", fontsize=8)
            if c:
                ax.set_ylabel("")
            if c == 0 or across:
                panels.append((ax, pose, view))
    spare = list(axes.flat)[len(views):] if across else []
    for ax in spare:
        ax.set_axis_off()
    if across and named and titles[0] not in title:  # one pose: named once, under the figure's title
        title = f"{title}\n{titles[0]}" if title else titles[0]
    fig = _legend_and_title(fig, [axes.flat[0]], title, into=spare[0] if spare else None)
    for ax, pose, view in panels:  # once laid out: the labels' places are in pixels
        label_springs(ax, scene, pose, view, **label_style)
    return fig


def _poses_in_rows(scene: Scene, poses, views, spans, titles, title: str, label_style: dict):
    """:func:`mechanism_figure`'s ``rows="poses"``: a row per pose, its views side by side at
    one scale (the largest span, each view about its own centre), the legend below, every
    panel's springs named."""
    import matplotlib.pyplot as plt

    span = max(b[2] for b in spans)
    spans = [(_about(xlim, span), _about(ylim, span), span) for xlim, ylim, _ in spans]
    cols = len(views)
    fig, axes = plt.subplots(len(poses), cols, figsize=(3.2 * cols + 0.4, 3.5 * len(poses) + 0.9), squeeze=False)
    for r, pose in enumerate(poses):
        for c, view in enumerate(views):
            ax = axes[r][c]
            draw(ax, scene, pose, view, labels=False, limits=spans[c])
            ax.set_title(f"{titles[r]}, {view} view", fontsize=9)
            if c and scene.axis_labels(views[c - 1])[1] == scene.axis_labels(view)[1]:  # one scale, one label
                ax.set_ylabel("")
    fig = _legend_and_title(fig, [axes[0][0]], title, fontsize=8)
    for r, pose in enumerate(poses):  # once laid out: the labels' places are in pixels
        for c, view in enumerate(views):
            label_springs(axes[r][c], scene, pose, view, **label_style)
    return fig


def _about(limits, span: float) -> tuple[float, float]:
    centre = sum(limits) / 2
    return centre - span / 2, centre + span / 2


def _at(scene: Scene, poses) -> Scene:
    """``scene`` at ``poses`` alone (the same column and path)."""
    k = list(poses)
    pick = lambda a: None if a is None else a[k]  # noqa: E731
    return replace(scene, links=[link[k] for link in scene.links],
                   springs={n: (A[k], B[k]) for n, (A, B) in scene.springs.items()},
                   extras={n: e[k] for n, e in scene.extras.items()}, brackets=pick(scene.brackets),
                   masses=pick(scene.masses), shells=[shell[k] for shell in scene.shells],
                   auxiliary=[a[k] for a in scene.auxiliary])


def _legend_and_title(fig, axes, title: str, into=None, fontsize: float = 7):
    """The figure's legend (every name drawn on ``axes``, once; in the empty axes ``into``, else
    below the panels, in ``fontsize`` pt) and title, then its layout."""
    legend = {}
    for ax in axes:
        for handle, name in zip(*ax.get_legend_handles_labels(), strict=True):
            legend.setdefault(name, handle)
    handles, names = list(legend.values()), list(legend)
    if into is not None:
        into.legend(handles, names, loc="center", ncol=1 + len(names) // 9, fontsize=8, frameon=False)
        rect = (0, 0, 1, 1)
    else:
        legend = fig.legend(handles, names, loc="lower center", ncol=min(4, len(names)), fontsize=fontsize,
                            frameon=False)
        below = legend.get_window_extent(fig.canvas.get_renderer()).height / fig.bbox.height  # the legend's share
        rect = (0, below + 0.01, 1, 1)
    if title:
        fig.suptitle(title, fontsize=10)
    tight(fig, rect=rect, h_pad=2.0)
    return fig


def tight(fig, **layout) -> None:
    """``fig.tight_layout(**layout)`` twice: equal axes change their boxes once laid out, which
    the first pass cannot see (its labels may then reach a legend below the panels)."""
    for _ in range(2):
        fig.tight_layout(**layout)
        fig.draw_without_rendering()  # the boxes settle at a draw; no pixels are needed for it


def scenes_figure(panels: dict, *, view: str = "front", columns: int = 2, title: str = ""):
    """Several scenes side by side, each at one pose: {panel title: (Scene, pose)} in ``view``,
    every panel at one scale (the union of their extents). Returns the matplotlib figure."""
    import matplotlib.pyplot as plt

    if not panels:
        raise SpringlabError("scenes_figure needs at least one panel")
    boxes = [_limits(scene, view) for scene, _ in panels.values()]
    span = max(b[2] for b in boxes)
    rows = -(-len(panels) // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(3.1 * columns, 3.0 * rows + 0.5), squeeze=False)
    names = list(dict.fromkeys(label for scene, _ in panels.values() for label in scene.springs))
    colours = {label: SPRING_COLOURS[k % len(SPRING_COLOURS)] for k, label in enumerate(names)}  # one per name
    drawn = []
    for ax, (name, (scene, pose)), (xlim, ylim, _) in zip(axes.flat, panels.items(), boxes, strict=False):
        cx, cy = sum(xlim) / 2, sum(ylim) / 2
        draw(ax, scene, pose, view, labels=False, colours=colours,
             limits=((cx - span / 2, cx + span / 2), (cy - span / 2, cy + span / 2), span))
        ax.set_title(name, fontsize=8)
        drawn.append((ax, scene, pose))
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    fig = _legend_and_title(fig, [ax for ax, _, _ in drawn], title)
    for ax, scene, pose in drawn:  # once laid out: the labels' places are in pixels
        label_springs(ax, scene, pose, view, colours=colours)
    return fig


def animate(panels: dict, path, *, fps: int = 10, dpi: int = 90, title: str = "", times=None, note: str = "",
            layout: str = "row", label_style: dict | None = None):
    """Write a GIF of scenes side by side, one frame per pose: ``panels`` is {panel title:
    (Scene, view)}, the scenes with one common number of poses. Panels of the same view share
    one scale (:func:`shared_limits`). ``times`` (s), one per pose, is shown in the title, and
    ``note`` on a second line under it. Returns the GIF's path; a GIF already there with the same
    pixels in every frame is left as it is (:func:`~springlab.workbench.images.unchanged_gif`).

    ``layout="column"``: the panels one above the other instead, each framed on its mechanism
    over every pose (:func:`framed_limits`, not a square), all at one scale, with the legend
    below them, the GIF about 740 px wide (the book's column) at ``dpi`` 110
    (:func:`animation_figure`), its colours those drawn (:func:`palette`: a spring's label and
    legend entry keep its colour). ``label_style``: :func:`label_springs`'s keywords.

    :raises SpringlabError: when the scenes have different numbers of poses, or none
    """
    import matplotlib.pyplot as plt
    from PIL import Image

    fig, frame, frames = animation_figure(panels, dpi=dpi, title=title, times=times, note=note, layout=layout,
                                          label_style=label_style)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    images, colours = [], palette() if layout == "column" else None
    # what does not move (axes, ticks, panel titles, legend) is drawn once; each frame restores it and
    # draws only the mechanism and the title over it (blitting: a full draw per frame took twice as long)
    canvas = fig.canvas
    for artist in frame.moving():
        artist.set_visible(False)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    for k in range(frames):
        frame(k)
        canvas.restore_region(background)
        for artist in sorted(frame.moving(), key=lambda a: a.get_zorder()):
            artist.set_visible(True)
            fig.draw_artist(artist)
        rgb = Image.fromarray(np.asarray(canvas.buffer_rgba())[..., :3])
        if colours is not None:  # each pixel to the nearest drawn colour or its tint
            images.append(rgb.quantize(palette=colours, dither=Image.Dither.NONE))
        else:
            images.append(rgb.quantize(colors=64, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE))
    plt.close(fig)
    if not unchanged_gif(path, images, round(1000 / fps)):  # rewritten only when a frame's pixels changed
        images[0].save(path, save_all=True, append_images=images[1:], duration=round(1000 / fps), loop=0)
    return str(path)


def animation_figure(panels: dict, *, dpi: int = 90, title: str = "", times=None, note: str = "",
                     layout: str = "row", label_style: dict | None = None, width: float = 6.7):
    """The figure :func:`animate` draws its frames on, laid out with its first frame: returns
    (figure, frame(k) that draws pose k, number of poses). ``frame.moving()`` lists the artists
    that change from frame to frame (the mechanism, its labels and the title), the rest being
    drawn once.

    ``layout="row"``: the panels side by side, square, each view's panels on one frame
    (:func:`shared_limits`), laid out once with the first frame's labels. ``layout="column"``:
    one above the other, ``width`` inches wide, each framed on its mechanism over every pose
    (:func:`framed_limits`) at one scale for all, the legend (every name drawn, once) below.
    """
    import matplotlib.pyplot as plt

    scenes = [(name, scene, view) for name, (scene, view) in panels.items()]
    counts = {s.poses for _, s, _ in scenes}
    if not scenes or len(counts) != 1:
        raise SpringlabError(f"animate needs scenes with one common number of poses, got {sorted(counts)}")
    if layout not in ("row", "column"):
        raise SpringlabError(f"layout must be 'row' or 'column', got {layout!r}")
    frames = counts.pop()
    stacked = layout == "column"
    if stacked:
        limits = framed_limits(panels)
        heights = [float(np.ptp(limits[name][1])) for name, _, _ in scenes]
        span = limits[scenes[0][0]][2]
        panel = (width - 0.9) / span  # in per m: the panels' width (less the axis labels) over their span
        size = (width, sum(panel * h + 0.75 for h in heights) + 0.55 + 0.2 * (3 + len(scenes[0][1].springs) // 4))
        fig, axes = plt.subplots(len(scenes), 1, figsize=size, squeeze=False, gridspec_kw={"height_ratios": heights})
        axes = axes[:, 0]
    else:
        limits = shared_limits(panels)
        fig, axes = plt.subplots(1, len(scenes), figsize=(3.4 * len(scenes), 3.9), squeeze=False)
        axes = axes[0]
    drawn = [[] for _ in scenes]

    def frame(k):
        for i, (ax, (name, scene, view)) in enumerate(zip(axes, scenes, strict=True)):
            for artist in drawn[i]:  # the axes stay; the last frame's mechanism goes
                artist.remove()
            drawn[i] = draw(ax, scene, k, view, labels=True, limits=limits[name if stacked else view],
                            label_style=label_style)
            ax.set_title(name, fontsize=9 if stacked else 8)
            if not stacked and i and scenes[i - 1][2] == view:  # one scale, one axis label
                ax.set_ylabel("")
        stamp = f" (t = {times[k]:.2f} s)" if times is not None else ""
        fig.suptitle(f"{title}{stamp}" + (f"\n{note}" if note else ""), fontsize=10 if stacked else 9)
        return []

    frame.moving = lambda: [artist for artists in drawn for artist in artists] + [fig._suptitle]

    fig.set_dpi(dpi)
    frame(0)
    if stacked:  # the legend below the panels, then the layout
        _legend_and_title(fig, [axes[0]], "", fontsize=8)
    else:
        fig.tight_layout()  # laid out once, with the first frame's labels
    return fig, frame, frames


def palette():
    """A fixed GIF palette (a Pillow "P" image) of the colours :func:`draw` uses: each spring's,
    the pseudobases' and centres' blue, each with three tints towards white (antialiased edges,
    labels' backgrounds), and 16 greys from black to white (links, column, text, grid). Unlike a
    palette fitted to each frame, it keeps a small spring's colour exactly."""
    from matplotlib.colors import to_rgb
    from PIL import Image

    rgb = []
    for colour in (*SPRING_COLOURS, "tab:blue"):
        c = np.array(to_rgb(colour))
        rgb += [c * (1 - f) + f for f in (0.0, 0.3, 0.55, 0.8)]
    rgb += [np.full(3, g) for g in np.linspace(0.0, 1.0, 16)]
    flat = [int(round(255 * v)) for c in rgb for v in c]
    image = Image.new("P", (1, 1))
    image.putpalette(flat + flat[-3:] * (256 - len(rgb)))
    return image


def framed_limits(panels: dict) -> dict:
    """{panel title: (xlim, ylim, span)} for ``panels`` {title: (Scene, view)}: each panel framed
    on its mechanism over all its poses (its floor and column too), 5 % of the larger extent
    clear, not a square; every panel as wide as the widest (about its own centre, one scale for
    all when they are drawn equally wide); ``span`` the common width (m)."""
    boxes = {}
    for name, (scene, view) in panels.items():
        pts = scene.project(scene.all_points(), view)
        low, high = pts.min(axis=0), pts.max(axis=0)
        extent = float(max(high - low)) or 1.0
        pad = 0.05 * extent
        if view != "top":  # the floor's hatching, below the column (see draw)
            low[1] = min(low[1], scene.column[0] - 0.04 * extent)
        boxes[name] = ((low[0] - pad, high[0] + pad), (low[1] - pad, high[1] + pad))
    span = max(x1 - x0 for (x0, x1), _ in boxes.values())
    return {name: (_about(xlim, span), ylim, span) for name, (xlim, ylim) in boxes.items()}


def shared_limits(panels: dict) -> dict:
    """{view: (xlim, ylim, span)} for ``panels`` {title: (Scene, view)}: one square frame per
    view, the union of its panels' extents over all their poses (m)."""
    limits = {}
    for scene, view in panels.values():
        xlim, ylim, span = _limits(scene, view)
        if view in limits:
            (x0, x1), (y0, y1), old = limits[view]
            xlim, ylim = (min(x0, xlim[0]), max(x1, xlim[1])), (min(y0, ylim[0]), max(y1, ylim[1]))
            span = max(xlim[1] - xlim[0], ylim[1] - ylim[0])
            xlim, ylim = _about(xlim, span), _about(ylim, span)
        limits[view] = (xlim, ylim, span)
    return limits


def lowest(scene: Scene) -> np.ndarray:
    """(N,) the height (m, along ``up``) of the lowest drawn point of the mechanism at each pose:
    links, springs' ends, pseudobases, brackets and centres of mass (not the ground column)."""
    parts = [link.reshape(scene.poses, -1, 3) for link in scene.links]
    parts += [np.stack(ab, axis=1) for ab in scene.springs.values()]
    parts += [e.reshape(scene.poses, -1, 3) for e in scene.extras.values()]
    parts += [b.reshape(scene.poses, -1, 3) for b in (scene.brackets, scene.masses) if b is not None]
    parts += [a.reshape(scene.poses, -1, 3) for a in scene.auxiliary]
    return np.min(np.concatenate(parts, axis=1) @ scene.up, axis=1)


@dataclass(frozen=True)
class HoldScenes:
    """What :func:`hold_animation` draws: the balanced arm and the control at the same times.

    :ivar balanced, control: the two scenes, their ground column standing on the drawn floor
    :ivar t: (F,) the frames' times (s)
    :ivar floor: the drawn floor's height (m along up; no floor is simulated)
    :ivar duration: the simulated time (s); ``t[-1] < duration`` when the control reached the floor
    """

    balanced: Scene
    control: Scene
    t: np.ndarray
    floor: float
    duration: float

    @property
    def stopped(self) -> bool:
        return bool(self.t[-1] < self.duration)


def hold_scenes(chain, springs, motion, *, frames: int = 21, clearance: float | None = None) -> HoldScenes:
    """The hold test's motion (:func:`springlab.energy.simulation.hold_motion`) made drawable.

    The simulation has no floor: the floor is drawn ``clearance`` (m; default 0.15 of the arm's
    reach, the sum of its link lengths) below the lowest point of the released arm (or of its
    column), and the motion is shown up to the last stored step at which no point of the
    control lies below it (the whole run when it never gets there), at ``frames`` evenly
    spaced stored steps."""
    scale = motion.control_scale
    balanced = chain_scene(chain, springs, motion.balanced)
    control = chain_scene(chain, [s.scaled(scale) for s in springs], motion.control)
    clearance = 0.15 * float(np.sum(chain.r)) if clearance is None else float(clearance)
    floor = min(balanced.column[0], float(lowest(balanced)[0]), float(lowest(control)[0])) - clearance
    below = np.flatnonzero((lowest(control) < floor) | (lowest(balanced) < floor))
    last = int(below[0]) - 1 if below.size else len(motion.t) - 1
    k = np.unique(np.linspace(0, last, frames).round().astype(int))
    return HoldScenes(replace(_at(balanced, k), column=(floor, balanced.column[1])),
                      replace(_at(control, k), column=(floor, control.column[1])), np.asarray(motion.t)[k], floor,
                      float(motion.t[-1]))


def hold_animation(chain, springs, motion, path, *, title: str = "exudyn hold test", frames: int = 21,
                   clearance: float | None = None, dpi: int = 110) -> str:
    """The hold test's motion (:func:`springlab.energy.simulation.hold_motion`) as a GIF: the
    balanced arm beside the control, one scale framed on the arms, in the front view, up to
    where the control reaches the drawn floor (:func:`hold_scenes`; the second title line says
    so)."""
    shown = hold_scenes(chain, springs, motion, frames=frames, clearance=clearance)
    panels = {"balanced": (shown.balanced, "front"),
              f"springs x {motion.control_scale:g} (control)": (shown.control, "front")}
    if shown.stopped:
        note = (f"shown to t = {shown.t[-1]:.2f} s of {shown.duration:g} s, where the control reaches the floor "
                "drawn below the arm (none is simulated)")
    else:
        note = f"the whole {shown.duration:g} s run"
    return animate(panels, path, times=shown.t, title=title, note=note, dpi=dpi)


TRAJECTORY_GIF = {"fps": 8, "dpi": 110, "layout": "column",
                  "label_style": {"fontsize": 8, "gap": 4.0, "clear": (3.0, 10.0)}}
"""How :func:`trajectory_animation` calls :func:`animate`: about 740 px wide (the book's
column), the views one above the other, framed on the mechanism, the legend below, 8 pt
spring labels at least 4 px apart."""


def trajectory_animation(scene: Scene, path, times, *, views=("front", "side"), title: str = "") -> str:
    """``scene`` along its poses (one per entry of ``times``, s) as a GIF about 740 px wide (the
    book's column), one panel per view, one above the other, each framed on the mechanism over
    every pose at one scale, the legend below and the springs named in 8 pt labels
    (:data:`TRAJECTORY_GIF`)."""
    return animate({f"{view} view": (scene, view) for view in views}, path, times=times, title=title,
                   **TRAJECTORY_GIF)
