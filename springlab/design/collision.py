"""What a spring must clear on a real arm, on the arm's own collision geometry, with coal.

coal (the collision library Pinocchio is built on, which the ``pin`` package brings) measures the
signed distance between a spring's pieces and each link's shapes as the URDF gives them
(:attr:`~springlab.model.revolute.RevoluteChain.solids`: boxes, cylinders, spheres, capsules and
meshes, not their bounding boxes), placed by the model's own frames
(:func:`~springlab.model.revolute.body_frames`). A spring's piece (its coil, its cable) is a capsule:
the segment between its ends thickened by its radius.

A mesh is measured twice: against its convex hull, which holds it (a piece farther than the margin
from the hull is clear of the mesh), and, where the hull is nearer, against its triangles (coal's
bounding-volume tree), which give the true distance outside the mesh. A piece inside the hull that
touches no triangle is either in a hollow of the mesh (clear, by the triangles' distance) or inside
the solid; the winding number of the mesh about the piece's middle decides (Jacobson et al., 2013),
and inside, the depth is the hull's. So a clearance is never larger than the truth, and a negative
one is a depth (m) the piece runs into the link.

The same geometry defines the arm's **workspace** (:class:`Sampler`): poses within the limits where
no two links collide but those that touch by construction, which an SRDF would disable as MoveIt's
setup assistant does (adjacent links; pairs in collision at the zero pose; pairs in collision at
nearly every pose), and no link passes below the mounting plane (the lowest point of the base's
geometry, across the up direction), bodies that sit on it by construction aside.

Lengths in m.

References
----------
Jacobson, A., Kavan, L., Sorkine-Hornung, O. Robust inside-outside segmentation using generalized
winding numbers. ACM Transactions on Graphics 32(4), 2013.
"""

from __future__ import annotations

import functools
import weakref
from dataclasses import dataclass

import numpy as np

from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames

MARGIN = 0.005
"""m: the clearance every spring, cable and hook keeps from every link by default."""

ALWAYS = 0.95
"""A pair of links (or a link and the mounting plane) in collision at more than this share of the
limits' poses touches by construction (a shell around a motor, a base on its plate) and is not checked,
as MoveIt's setup assistant disables 'always in collision' pairs."""

SLACK = 1e-6
"""m: a mesh's triangles are measured exactly wherever coal's collision test, with a security margin this much
beyond the one asked for, finds one within it: a margin of coal's own tolerance, so that a pose its distance
would put within the margin (or below the smallest clearance found) is never settled by a lower bound."""

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _coal():
    try:
        import coal
    except ImportError:
        raise SpringlabError("coal (the collision library the 'pin' package brings) is not installed: "
                             "pip install pin") from None
    return coal


@dataclass(frozen=True, eq=False)
class _Item:
    body: int
    link: str
    frame: np.ndarray  # (4, 4) in the body's frame
    convex: object  # coal geometry: the shape itself, or a mesh's hull
    mesh: object | None  # a mesh's triangles (coal BVH), else None
    triangles: np.ndarray | None  # a mesh's triangles' corners (t, 3, 3), for the winding number
    points: np.ndarray  # (k, 3) points in the item's frame: the item is their hull swollen by ``pad``
    pad: float = 0.0  # m: a sphere is its centre swollen by its radius, a capsule its axis' ends

    @functools.cached_property
    def capsule(self) -> tuple[np.ndarray, np.ndarray, float]:
        """A capsule that holds the item (its ends, in the item's frame, and radius): along the points'
        principal axis, from their least to their largest reach along it, swollen by the pad."""
        p = self.points
        c = p.mean(axis=0)
        axis = np.linalg.svd(p - c, full_matrices=False)[2][0] if len(p) > 1 else np.array([0.0, 0.0, 1.0])
        t = (p - c) @ axis
        r = float(np.max(np.linalg.norm((p - c) - np.outer(t, axis), axis=1))) if len(p) else 0.0
        return c + t.min() * axis, c + t.max() * axis, r + self.pad


def _items(model: RevoluteChain) -> tuple:
    """The model's solids as coal geometries, built once per model."""
    try:
        return _CACHE[model]
    except (KeyError, TypeError):
        pass
    coal = _coal()
    out = []
    for body, solids in enumerate(model.solids):
        for s in solids:
            if s.kind == "box":
                geom = coal.Box(*s.size)
            elif s.kind == "cylinder":
                geom = coal.Cylinder(*s.size)
            elif s.kind == "capsule":
                geom = coal.Capsule(*s.size)
            elif s.kind == "sphere":
                geom = coal.Sphere(s.size[0])
            else:
                out.append(_mesh_item(coal, body, s))
                continue
            out.append(_Item(body, s.link, np.asarray(s.frame), geom, None, None, *_outer_points(s.kind, s.size)))
    items = tuple(i for i in out if i is not None)
    try:
        _CACHE[model] = items
    except TypeError:
        pass
    return items


def _mesh_item(coal, body, s):
    v, f = np.asarray(s.vertices, dtype=float), np.asarray(s.faces, dtype=np.int64)
    if len(v) < 4 or len(f) == 0:
        return None
    hull, bvh, points = _mesh_geometry(np.ascontiguousarray(v).tobytes(), np.ascontiguousarray(f).tobytes())
    return _Item(body, s.link, np.asarray(s.frame), hull, bvh, v[f], points)


@functools.lru_cache(maxsize=256)
def _mesh_geometry(vertices: bytes, faces: bytes) -> tuple:
    """A mesh's coal hull and triangles and its hull's corners, from its vertices' (m, float64) and faces'
    (int64) bytes: built once per process, so that a robot loaded again (each ``load_robot``, each test)
    does not rebuild its meshes' bounding volumes (1.5 s for the SO-101's 17)."""
    coal = _coal()
    v, f = np.frombuffer(vertices).reshape(-1, 3), np.frombuffer(faces, dtype=np.int64).reshape(-1, 3)
    bvh = coal.BVHModelOBBRSS()
    bvh.beginModel(len(f), len(v))
    bvh.addVertices(v)
    bvh.addTriangles(f)
    bvh.endModel()
    from scipy.spatial import ConvexHull, QhullError

    try:
        points = v[ConvexHull(v).vertices]
    except (QhullError, ValueError):  # a flat mesh has no hull of volume: its triangles alone bound it
        return bvh, bvh, v
    corners = coal.StdVec_Vec3s()  # coal's hull of the hull's corners alone: the same solid, built from
    corners.extend(list(points))  # a few hundred points, not the mesh's (the SO-101's: 1.2 million)
    try:
        return coal.ConvexBase.convexHull(corners, False, "Qt"), bvh, points
    except RuntimeError:  # coal refuses a corner with more than 255 neighbours: its hull of the whole mesh, if it can
        try:
            bvh.buildConvexHull(False, "Qt")
            return bvh.convex, bvh, points
        except RuntimeError:  # else the triangles alone bound it
            return bvh, bvh, points


def _outer_points(kind: str, size) -> tuple[np.ndarray, float]:
    """A primitive as points in its own frame and a pad: the points' hull swollen by the pad holds it,
    exactly for a box, a sphere (its centre, padded by its radius) and a capsule (its axis' two ends), and
    a cylinder's rims by polygons that circumscribe them."""
    if kind == "box":
        h = np.asarray(size, dtype=float) / 2
        return np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * h, 0.0
    if kind == "sphere":
        return np.zeros((1, 3)), float(size[0])
    r, length = (float(v) for v in size)
    if kind == "capsule":
        return np.array([[0.0, 0.0, -length / 2], [0.0, 0.0, length / 2]]), r
    t = np.linspace(0.0, 2 * np.pi, 32, endpoint=False)
    ring = np.column_stack([np.cos(t), np.sin(t), np.zeros_like(t)]) / np.cos(np.pi / 32)
    return np.vstack([ring * r + [0, 0, -length / 2], ring * r + [0, 0, length / 2]]), 0.0


def has_geometry(model: RevoluteChain) -> bool:
    """True when the model carries collision shapes (a URDF read with its meshes)."""
    return bool(model.solids) and any(len(s) for s in model.solids)


def _transform(coal, R, t):
    return coal.Transform3s(np.ascontiguousarray(R, dtype=float), np.ascontiguousarray(t, dtype=float))


def _placed(R, o, item: _Item, p: int):
    """The item's rotation and translation in the base frame at pose p."""
    Rb, ob = R[p, item.body], o[p, item.body]
    return Rb @ item.frame[:3, :3], Rb @ item.frame[:3, 3] + ob


def _winding(triangles: np.ndarray, point: np.ndarray) -> float:
    """The generalised winding number of a triangle mesh about a point: 1 inside a closed mesh, 0
    outside (Jacobson et al. 2013, their equation 6: the sum of the triangles' solid angles over 4 pi)."""
    a, b, c = (triangles[:, k] - point for k in range(3))
    la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    div = la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", b, c) * la \
        + np.einsum("ij,ij->i", c, a) * lb
    return float(np.sum(2.0 * np.arctan2(det, div)) / (4.0 * np.pi))


def _segment_gap(P0, P1, Q0, Q1) -> np.ndarray:
    """The distance (m) between segments P0-P1 and Q0-Q1, row by row ((N, 3) each): the clamped solution
    of the 2 x 2 normal equations, each parameter re-clamped given the other (as
    :func:`springlab.design.clearance.segment_distance`, without its argument checks: a screen run
    thousands of times on arrays built here)."""
    u, v, w = P1 - P0, Q1 - Q0, P0 - Q0
    a, b, c = (u * u).sum(1), (u * v).sum(1), (v * v).sum(1)
    d, e = (u * w).sum(1), (v * w).sum(1)
    den = a * c - b * b
    tiny = 1e-300
    s = np.clip(np.where(den > 1e-14 * np.maximum(a * c, tiny), (b * e - c * d) / np.maximum(den, tiny), 0.0), 0.0, 1.0)
    t = np.clip(np.where(c > tiny, (b * s + e) / np.maximum(c, tiny), 0.0), 0.0, 1.0)
    s = np.where(a > tiny, np.clip((b * t - d) / np.maximum(a, tiny), 0.0, 1.0), 0.0)
    return np.linalg.norm(w + s[:, None] * u - t[:, None] * v, axis=1)


def _world_capsule(item, Ri, ti):
    a, b, r = item.capsule
    return np.einsum("pij,j->pi", Ri, a) + ti, np.einsum("pij,j->pi", Ri, b) + ti, r


def _capsules(coal, P0, P1, radius):
    """Capsules from P0 to P1 ((N, 3) each) of the radius: per row, its coal shape, rotation and centre."""
    d = P1 - P0
    length = np.linalg.norm(d, axis=1)
    z = np.where(length[:, None] >= 1e-9, d / np.maximum(length, 1e-12)[:, None], [[0.0, 0.0, 1.0]])  # a ball: any
    x = np.cross(z, np.where(np.abs(z[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]]))  # frame, a rotation
    x /= np.maximum(np.linalg.norm(x, axis=1), 1e-12)[:, None]
    frames = np.stack([x, np.cross(z, x), z], axis=2)
    centres = (P0 + P1) / 2
    r = max(radius, 1e-6)
    return [(coal.Capsule(r, float(L)) if L >= 1e-9 else coal.Sphere(r), frames[p], centres[p])
            for p, L in enumerate(length)]


def _discs(coal, centres, axes, radius, width) -> list:
    """Discs (coal cylinders) of the radius and width about ``axes`` at ``centres`` ((N, 3) each): per row,
    its coal shape, rotation and centre."""
    z = axes / np.maximum(np.linalg.norm(axes, axis=1), 1e-12)[:, None]
    x = np.cross(z, np.where(np.abs(z[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]]))
    x /= np.maximum(np.linalg.norm(x, axis=1), 1e-12)[:, None]
    frames = np.stack([x, np.cross(z, x), z], axis=2)
    return [(coal.Cylinder(max(radius, 1e-6), max(width, 1e-6)), frames[p], centres[p]) for p in range(len(centres))]


def _piece_capsules(coal, a, b, radius, trim=None) -> list:
    """A piece's capsules at each pose; ``trim`` (end 'a' or 'b', allowance m): without the allowance at
    that end (None at a pose where nothing is left)."""
    if trim is None:
        return _capsules(coal, a, b, radius)
    end, allowance = trim
    d = b - a
    length = np.linalg.norm(d, axis=1)
    u = d / np.maximum(length, 1e-12)[:, None]
    lo, hi = (a + allowance * u, b) if end == "a" else (a, b - allowance * u)
    return [None if length[i] <= allowance else c for i, c in enumerate(_capsules(coal, lo, hi, radius))]


def _signed(coal, item: _Item, Ti, shape, Ts, centre, margin: float) -> float:
    """The signed distance (m) from the shape to the item, never larger than the truth (see the module
    docstring); exact where it is below ``margin``. Above a finite ``margin``, a mesh whose triangles coal's
    collision test (its security margin ``margin`` + :data:`SLACK`) finds none within it returns a lower
    bound: the hull's distance, or that security margin if larger."""
    request = coal.DistanceRequest()
    hull = coal.distance(item.convex, Ti, shape, Ts, request, coal.DistanceResult())
    if item.mesh is None or hull >= margin:
        return float(hull)
    if np.isfinite(margin):  # whether any triangle comes within the margin (or touches) first: coal's collision
        near = coal.CollisionRequest()  # test with that security margin, 20 times quicker than their distance
        near.security_margin = max(float(margin), 0.0) + SLACK
        if not coal.collide(item.mesh, Ti, shape, Ts, near, coal.CollisionResult()):  # all farther than that
            if hull < 0.0 and _inside(coal, item, Ti, centre):
                return float(hull)  # inside the solid: its depth into the hull
            return max(float(hull), near.security_margin)  # outside it, or in a hollow: a lower bound
    tris = coal.distance(item.mesh, Ti, shape, Ts, request, coal.DistanceResult())
    if tris <= 0.0:  # it touches the mesh: its depth into the hull, at least as deep as into the mesh
        return float(min(hull, tris))
    if hull >= 0.0:  # outside the hull, where the triangles give the true distance
        return float(tris)
    return float(hull) if _inside(coal, item, Ti, centre) else float(tris)


def _inside(coal, item: _Item, Ti, centre) -> bool:
    """Whether the point ``centre`` (base frame) lies inside the mesh placed at ``Ti``: by its winding number."""
    R, t = Ti.getRotation(), Ti.getTranslation()
    return _winding(item.triangles, R.T @ (np.asarray(centre) - t)) > 0.5


@dataclass(frozen=True)
class Piece:
    """A part of a spring that must clear the links: a capsule from ``a`` to ``b`` (m, base frame,
    (N, 3) over the poses) of ``radius`` (m); or, with ``axis`` ((N, 3) unit vectors), a disc (a pulley)
    centred at ``a`` = ``b`` of ``radius`` and ``width`` (m) about that axis. ``bodies`` are the bodies it is
    fixed to, each with the length (m) at that end within which it may touch its own body (its hook and
    bracket): the piece is checked against its own body only beyond it (a disc: not at all)."""

    name: str
    a: np.ndarray
    b: np.ndarray
    radius: float
    bodies: tuple = ()  # ((body index, end 'a' or 'b', allowance m), ...)
    axis: np.ndarray | None = None
    width: float = 0.0


@dataclass(frozen=True)
class Clearances:
    """The clearance (m) of each piece from each body at each pose, and last from the mounting plane (the
    table or floor the base stands on), (pieces, N, n + 2); +inf where a body has no geometry or is not
    checked."""

    pieces: tuple
    gaps: np.ndarray
    links: tuple  # the bodies' names

    def worst(self, piece: int) -> tuple[float, int, int]:
        """A piece's smallest clearance (m), the body and the pose index where it occurs."""
        g = self.gaps[piece]
        p, b = np.unravel_index(int(np.argmin(g)), g.shape)
        return float(g[p, b]), int(b), int(p)

    def within(self, margin: float = MARGIN) -> np.ndarray:
        """Per pose, whether any piece comes nearer than ``margin`` (m) to a body or the mounting plane, (N,): exact
        where the clearances were measured with ``every`` and the same ``margin``, else it may also hold where only
        a lower bound was below it."""
        return np.any(self.gaps < margin, axis=(0, 2))

    def failures(self, margin: float = MARGIN) -> list[tuple[str, str, int, float]]:
        """(piece, link, pose index, clearance m) for each piece nearer than ``margin`` to a link."""
        out = []
        for i, piece in enumerate(self.pieces):
            gap, body, pose = self.worst(i)
            if gap < margin:
                out.append((piece.name, self.links[body], pose, gap))
        return out


def clearances(model: RevoluteChain, pieces, q, *, margin: float = MARGIN, every: bool = False) -> Clearances:
    """Each piece's clearance from each of the model's bodies at the poses ``q`` (N, n) rad: exact at each
    piece's nearest approach (:meth:`Clearances.worst`) and wherever coal found it below the ``margin``; elsewhere a lower
    bound (capsules that hold the piece and the shape screen the poses in numpy; coal measures the poses
    in the order of those bounds, until no pose left can come nearer than one measured, or than the
    ``margin``). With ``every``, coal measures every pose whose bound is below the ``margin`` and which no piece
    was yet found within the margin at: which poses some piece comes within the margin at is then exact
    (:meth:`Clearances.within`), each piece's nearest approach still exact."""
    coal = _coal()
    q = model.check_q(q)
    pieces = tuple(pieces)
    items = _items(model)
    R, o = body_frames(model, q)
    gaps = np.full((len(pieces), q.shape[0], model.n + 2), np.inf)
    hit = np.zeros(q.shape[0], dtype=bool)  # the poses found within the margin so far
    plane, up = mounting_plane(model), np.asarray(model.up, dtype=float)
    placed = []
    for item in items:
        Ri = R[:, item.body] @ item.frame[:3, :3]
        ti = np.einsum("pij,j->pi", R[:, item.body], item.frame[:3, 3]) + o[:, item.body]
        placed.append((Ri, ti))
    for k, piece in enumerate(pieces):
        own = {body: (end, allowance) for body, end, allowance in piece.bodies}
        a, b = np.asarray(piece.a, dtype=float), np.asarray(piece.b, dtype=float)
        shapes = {}  # (body or None) -> per pose its capsule, trimmed for its own bodies

        def exact(i, p, near, own=own, shapes=shapes, a=a, b=b, radius=piece.radius, piece=piece):
            key = items[i].body if items[i].body in own else None
            if key not in shapes and piece.axis is not None:  # a disc: not against its own bodies
                shapes[key] = ([None] * len(a) if key is not None else
                               _discs(coal, a, np.asarray(piece.axis, dtype=float), radius, piece.width))
            if key not in shapes:
                shapes[key] = _piece_capsules(coal, a, b, radius, own.get(key))
            found = shapes[key][p]
            if found is None:
                return np.inf
            solid, Rs, c = found
            Ri, ti = placed[i]
            return _signed(coal, items[i], _transform(coal, Ri[p], ti[p]), solid, _transform(coal, Rs, c), c, near)

        if piece.axis is None:  # a capsule's lowest point; a disc's: its rim's, tilted by its axis
            gaps[k, :, -1] = np.minimum(a @ up, b @ up) - piece.radius - plane
        else:
            tilt = np.sqrt(np.clip(1 - (np.asarray(piece.axis, dtype=float) @ up) ** 2, 0.0, 1.0))
            gaps[k, :, -1] = a @ up - piece.radius * tilt - 0.5 * piece.width * np.abs(piece.axis @ up) - plane
        hit |= gaps[k, :, -1] < margin
        G = np.empty((len(items), q.shape[0]))  # per shape and pose: exact below the margin, else a lower bound
        known = np.zeros(G.shape, dtype=bool)
        for i, (item, (Ri, ti)) in enumerate(zip(items, placed, strict=True)):
            Q0, Q1, r = _world_capsule(item, Ri, ti)
            G[i] = _segment_gap(a, b, Q0, Q1) - piece.radius - r
            best = np.inf  # the nearest approach to this shape, measured in the order of the screen's bounds
            for p in np.argsort(G[i], kind="stable"):
                if G[i, p] >= (margin if every else min(best, margin)):
                    break  # no pose left can come nearer than one measured, or than the margin
                if every and hit[p]:
                    continue  # a pose already within the margin: whether it is needs no more measuring
                G[i, p] = exact(i, p, margin)
                known[i, p] = G[i, p] < margin
                hit[p] |= known[i, p]
                best = min(best, G[i, p])
        lowest = float(np.min(G[known])) if known.any() else np.inf  # the smallest value known exactly
        while G.size:  # the smallest made exact: its value, link and pose are the piece's worst
            i, p = np.unravel_index(int(np.argmin(G)), G.shape)
            if known[i, p] or not np.isfinite(G[i, p]):
                break
            # exact up to the slack above the smallest known: beyond, a lower bound settles the pose (coal's distance
            # to a mesh's triangles takes a millisecond, whether they come within it a twentieth of that)
            G[i, p], known[i, p] = exact(i, p, lowest + SLACK), True
            lowest = min(lowest, float(G[i, p]))  # a lower bound lies above it by the slack at least
        for i, item in enumerate(items):
            gaps[k, :, item.body] = np.minimum(gaps[k, :, item.body], G[i])
    return Clearances(pieces, gaps, (*model.bodies, "the mounting plane"))


def _pairs(model: RevoluteChain) -> list[tuple[int, int]]:
    """The pairs of bodies checked against each other: all but adjacent ones (a joint between them)."""
    bodies = sorted({i.body for i in _items(model)})
    return [(a, b) for ai, a in enumerate(bodies) for b in bodies[ai + 1:] if b - a > 1]


_PLANES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def mounting_plane(model: RevoluteChain) -> float:
    """The height (m, along up, in the base frame) of the base's lowest point: its geometry's, or the
    base frame's origin when it has none."""
    if model in _PLANES:
        return _PLANES[model]
    base = [i for i in _items(model) if i.body == 0]
    _PLANES[model] = plane = min((float(np.min((i.points @ i.frame[:3, :3].T + i.frame[:3, 3]) @ model.up)) - i.pad
                                  for i in base), default=0.0)
    return plane


def collision_masks(model: RevoluteChain, q, *, pairs=None, below=None, first: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Per pose, whether each checked pair of bodies collides, (N, len(pairs)), and whether each body
    passes below the mounting plane, (N, n + 1) (the base never does). The poses are screened in
    numpy (each shape's lowest point; capsules that hold the shapes), coal decides the rest. With
    ``first``, a pose is left once it fails (below the plane, or one pair in collision): the masks then
    say only whether each pose is free."""
    coal = _coal()
    q = model.check_q(q)
    items = _items(model)
    pairs = _pairs(model) if pairs is None else list(pairs)
    R, o = body_frames(model, q)
    up = model.up
    plane = mounting_plane(model)
    N = q.shape[0]
    low = np.zeros((N, model.n + 1), dtype=bool)
    Rw, tw = [], []
    for item in items:
        Rw.append(R[:, item.body] @ item.frame[:3, :3])
        tw.append(np.einsum("pij,j->pi", R[:, item.body], item.frame[:3, 3]) + o[:, item.body])
    capsules = [_world_capsule(it, Rw[k], tw[k]) for k, it in enumerate(items)]
    for k, item in enumerate(items):
        if item.body and (below is None or item.body in below):
            Q0, Q1, r = capsules[k]
            maybe = np.flatnonzero(np.minimum(Q0 @ up, Q1 @ up) - r < plane)  # the capsule that holds it dips
            heights = np.einsum("pij,i->pj", Rw[k][maybe], up) @ item.points.T + (tw[k][maybe] @ up)[:, None] - item.pad
            low[maybe, item.body] |= heights.min(axis=1) < plane
    by_body: dict = {}
    for k, item in enumerate(items):
        by_body.setdefault(item.body, []).append(k)
    hit = np.zeros((N, len(pairs)), dtype=bool)
    combos = [(c, ka, kb) for c, (a, b) in enumerate(pairs) for ka in by_body.get(a, ()) for kb in by_body.get(b, ())]
    if not combos:
        return hit, low
    C, KA, KB = (np.array(v) for v in zip(*combos, strict=True))
    ends = [np.stack([cap[e] for cap in capsules], axis=1) for e in (0, 1)]  # (N, items, 3) each
    radius = np.array([cap[2] for cap in capsules])
    K = len(C)
    gap = _segment_gap(ends[0][:, KA].reshape(-1, 3), ends[1][:, KA].reshape(-1, 3),
                       ends[0][:, KB].reshape(-1, 3), ends[1][:, KB].reshape(-1, 3)).reshape(N, K)
    request = coal.CollisionRequest()
    dead = low.any(axis=1).tolist() if first else [False] * N  # poses already failed (with ``first``)
    found = set()  # (pose, pair) in collision
    C, KA, KB = C.tolist(), KA.tolist(), KB.tolist()
    near_p, near_k = np.nonzero(gap < radius[KA] + radius[KB])
    for p, kk in zip(near_p.tolist(), near_k.tolist(), strict=True):  # pose by pose, in order
        c = C[kk]
        if dead[p] or (p, c) in found:
            continue
        ka, kb = KA[kk], KB[kk]
        if _collide(coal, items[ka], _transform(coal, Rw[ka][p], tw[ka][p]),
                    items[kb], _transform(coal, Rw[kb][p], tw[kb][p]), request):
            found.add((p, c))
            dead[p] = first
    for p, c in found:
        hit[p, c] = True
    return hit, low


def _collide(coal, ia: _Item, Ta, ib: _Item, Tb, request) -> bool:
    """Whether two items overlap: their hulls first, then the meshes' triangles (a hollow's inside, where
    one mesh lies within the other without touching, is counted by the winding number)."""
    if not coal.collide(ia.convex, Ta, ib.convex, Tb, request, coal.CollisionResult()):
        return False
    if ia.mesh is None and ib.mesh is None:
        return True
    ga = ia.mesh if ia.mesh is not None else ia.convex
    gb = ib.mesh if ib.mesh is not None else ib.convex
    if coal.collide(ga, Ta, gb, Tb, request, coal.CollisionResult()):
        return True
    for inner, Ti, outer, To in ((ia, Ta, ib, Tb), (ib, Tb, ia, Ta)):  # one wholly inside the other
        if outer.triangles is None:
            continue
        point = Ti.getTranslation() if inner.triangles is None else \
            Ti.getRotation() @ inner.triangles[0, 0] + Ti.getTranslation()
        if coal.distance(outer.convex, To, coal.Sphere(1e-6), _transform(coal, np.eye(3), point),
                         coal.DistanceRequest(), coal.DistanceResult()) > 0:
            continue  # outside the outer mesh's hull, so outside the mesh
        local = To.getRotation().T @ (point - To.getTranslation())
        if _winding(outer.triangles, local) > 0.5:
            return True
    return False


def _default_pose(ranges: np.ndarray) -> np.ndarray:
    """The zero pose, each angle clipped into its range (the URDF's home, as far as the limits allow)."""
    return np.clip(0.0, ranges[:, 0], ranges[:, 1])


class Sampler:
    """Random poses of the arm's workspace (see the module docstring): within ``ranges`` ((n, 2) rad), no
    two links in collision but pairs that touch by construction (found on ``calibration`` poses of
    ``limits``, the joints' whole ranges, default ``ranges``, and named in its ``notes``: a narrowed
    workspace in which two links always touch does not make them touch by construction), no link below
    the mounting plane. An arm without collision geometry samples the ranges' box.

    :ivar notes: the pairs and links left unchecked because they touch by construction, a line each
    :ivar pairs: the pairs of bodies checked against each other (indices)
    :ivar below: the bodies checked against the mounting plane
    """

    def __init__(self, model: RevoluteChain, ranges, rng, *, calibration: int = 400, limits=None):
        self.model, self.ranges = model, np.asarray(ranges, dtype=float)
        limits = self.ranges if limits is None else np.asarray(limits, dtype=float)
        self.checked = has_geometry(model)
        self.drawn = self.kept = 0
        notes = []
        if not self.checked:
            notes.append("the arm has no collision geometry: the workspace is the joint ranges' box, unchecked for "
                         "self-collision")
            self.pairs, self.below, self.notes = [], set(), tuple(notes)
            return
        pairs, names = _pairs(model), model.bodies
        trial = np.vstack([_default_pose(limits), rng.uniform(limits[:, 0], limits[:, 1], (calibration, model.n))])
        hit, low = collision_masks(model, trial, pairs=pairs)
        self.pairs = []
        for k, (a, b) in enumerate(pairs):
            if hit[0, k] or hit[1:, k].mean() > ALWAYS:
                why = "at the zero pose" if hit[0, k] else f"at {100 * hit[1:, k].mean():.0f} % of the poses"
                notes.append(f"links {names[a]} and {names[b]} touch {why}: by construction, not checked")
            else:
                self.pairs.append((a, b))
        self.below = set()
        for b in range(1, model.n + 1):
            if low[1:, b].mean() > ALWAYS:
                notes.append(f"link {names[b]} reaches below the mounting plane at nearly every pose: it sits on the "
                             "mount by construction, not checked against it")
            else:
                self.below.add(b)
        self.notes = tuple(notes)

    @property
    def share(self) -> float:
        """The share of the ranges' poses found free so far."""
        return self.kept / self.drawn if self.drawn else 1.0

    def free(self, q) -> np.ndarray:
        """Whether each pose (N, n) rad is in the workspace, (N,) (limits aside)."""
        q = self.model.check_q(q)
        if not self.checked:
            return np.ones(q.shape[0], dtype=bool)
        hit, low = collision_masks(self.model, q, pairs=self.pairs, below=self.below, first=True)
        return ~hit.any(axis=1) & ~low.any(axis=1)

    def draw(self, count: int, rng) -> np.ndarray:
        """``count`` random poses of the workspace, (count, n) rad.

        :raises SpringlabError: when no pose of the ranges is free (every one collides)
        """
        out, found = [], 0
        while found < count:
            if self.drawn >= 50 * count and not self.kept:
                raise SpringlabError(f"no pose of the workspace is free: each of {self.drawn} random poses within the "
                                     "joint ranges has two links in collision or a link below the mounting plane; give "
                                     "a --workspace the arm can move in")
            size = max(64, int(1.2 * (count - found) / max(self.share, 0.05)))
            poses = self.ranges[:, 0] + (self.ranges[:, 1] - self.ranges[:, 0]) * rng.random((size, self.model.n))
            free = self.free(poses)
            out.append(poses[free])
            self.drawn += size
            self.kept += int(free.sum())
            found += int(free.sum())
        return np.vstack(out)[:count]

    def note(self) -> str:
        if not self.checked:
            return self.notes[0]
        return (f"the workspace: poses within the joint ranges where no two links collide and none passes below the "
                f"mounting plane, {100 * self.share:.0f} % of the ranges' poses ({self.drawn} drawn)")
