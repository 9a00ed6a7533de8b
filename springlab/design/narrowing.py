"""Where springs that run into a link do clear it: the workspace narrowed, one or two joints' ranges at a time.

A realised spring that clears every link at most poses of the workspace but runs into one at some (the Z1's
gripper folded back onto its upper arm, the Panda's forearm swung round its upper arm's roll) is a design for
a narrower workspace. :func:`narrowed` finds, among the design's own check poses, the ranges of one joint, or
of two together, that hold no pose at which a spring's coil, cable or pulley comes within the margin of a link
(coal, measured at every such pose: :func:`~springlab.design.collision.clearances` with ``every``) while
keeping the most of the other poses; it then draws fresh poses of that narrower workspace (the same
:class:`~springlab.design.collision.Sampler`: no two links in collision, none below the mounting plane) and
measures the same springs on them. Poses there that still collide join the pool and the ranges are found again,
at most :data:`ROUNDS` times. The springs are not re-designed: the balance on the narrower workspace is
measured on the fresh poses too, and the design itself is not changed.

A narrowing is offered only where it keeps at least a tenth of the workspace (:data:`LEAST_KEPT`); where the springs
come within the margin at nearly every pose (the Panda's pseudobase springs, at 99 %), a first look at
:data:`PROBE` poses says so, and none is sought.

Each range is bounded by the outermost clear pose inside it, rounded inwards to a whole degree: between it and the
nearest colliding pose the sample says nothing, so the bound stays on the side it has seen clear.

Angles in rad, lengths in m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab.design.collision import MARGIN, Sampler, clearances
from springlab.design.hardware import spring_pieces
from springlab.energy.geometry import gravity_torques, joint_torques
from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain

ROUNDS = 5
"""The most times fresh poses of a narrowed workspace are drawn and the ranges found again."""

LEAST_KEPT = 0.1
"""The least share of the workspace a narrowing must keep to be offered: where the springs come within the margin
at more than 1 - this share of the first :data:`PROBE` random check poses, none could, and none is sought."""

PROBE = 200
"""The random check poses measured first, to tell whether a narrowing could keep :data:`LEAST_KEPT` at all (where
nearly every pose collides, measuring them all costs as much as the design)."""

GRID = 12
"""Steps across the first joint's range among which a two-joint narrowing's first range is sought (then refined
on the poses themselves)."""


def _deg(angle: float) -> str:
    """An angle (rad) in whole degrees, without a negative zero."""
    return f"{float(np.round(np.degrees(angle))) + 0.0:.0f}"


@dataclass(frozen=True)
class Narrowing:
    """A narrower workspace on which the springs clear the links.

    :ivar ranges: the narrowed joint ranges (n, 2) rad
    :ivar joints: the indices of the joints narrowed
    :ivar kept: the share of the design's random check poses the narrowed ranges hold
    :ivar fresh: the fresh poses of the narrowed workspace the springs were measured on
    :ivar nearest: the smallest clearance (m) of any spring's piece from a link over those fresh poses, at least the
        margin
    :ivar link: the link it is nearest, and ``spring`` the spring
    :ivar removed: per loaded joint (name), the percentage of its peak the realised springs remove on the fresh
        poses (carrying their hardware)
    :ivar rounds: the rounds of fresh poses it took
    """

    ranges: np.ndarray
    joints: tuple
    kept: float
    fresh: int
    nearest: float
    link: str
    spring: str
    removed: dict
    rounds: int

    def workspace(self, model: RevoluteChain) -> str:
        """The narrowed joints as ``--workspace`` takes them: 'joint=low:high' in degrees."""
        return ",".join(f"{model.joints[i]}={_deg(self.ranges[i, 0])}:{_deg(self.ranges[i, 1])}"
                        for i in self.joints)

    def as_dict(self, model: RevoluteChain) -> dict:
        return {"workspace": {model.joints[i]: [round(float(np.degrees(v)), 6) + 0.0 for v in self.ranges[i]]
                              for i in self.joints},
                "workspace_argument": self.workspace(model), "kept_share": self.kept, "fresh_poses": self.fresh,
                "clearance_m": self.nearest, "nearest_link": self.link, "nearest_spring": self.spring,
                "removed_percent": self.removed}


def measured(model: RevoluteChain, realised, kinds, coils, names, q, *, margin: float = MARGIN):
    """The realised springs' pieces' clearances (:class:`~springlab.design.collision.Clearances`) at the poses
    ``q`` (N, n) rad, coal measuring every pose a piece comes within ``margin`` of a link or the mounting plane at:
    its ``within(margin)`` is exact."""
    pieces = spring_pieces(model, realised, kinds, coils, names, q)
    return clearances(model, pieces, q, margin=margin, every=True)


def colliding(model: RevoluteChain, realised, kinds, coils, names, q, *, margin: float = MARGIN) -> np.ndarray:
    """Per pose of ``q`` (N, n), whether any realised spring's piece comes within ``margin`` of a link or the
    mounting plane (coal at every such pose), (N,)."""
    return measured(model, realised, kinds, coils, names, q, margin=margin).within(margin)


def _interval(x: np.ndarray, bad: np.ndarray) -> tuple[int, float, float]:
    """The interval of the values ``x`` holding no ``bad`` one and the most others: (how many, its lowest and its
    highest value held), or (0, nan, nan)."""
    if not len(x):
        return 0, np.nan, np.nan
    order = np.argsort(x, kind="stable")
    xs, bs = x[order], bad[order]
    cuts = np.concatenate([[-1], np.flatnonzero(bs), [len(xs)]])
    counts = np.diff(cuts) - 1
    best = int(np.argmax(counts))
    if counts[best] <= 0:
        return 0, np.nan, np.nan
    return int(counts[best]), float(xs[cuts[best] + 1]), float(xs[cuts[best + 1] - 1])


def _inward(lo: float, hi: float) -> tuple[float, float]:
    """A range's bounds rounded inwards to whole degrees (rad)."""
    a, b = np.ceil(np.degrees(lo) - 1e-9), np.floor(np.degrees(hi) + 1e-9)
    return float(np.radians(a)), float(np.radians(b))


def _box(q: np.ndarray, bad: np.ndarray, ranges: np.ndarray, joints) -> np.ndarray | None:
    """The ranges of ``joints`` (one or two indices) holding none of the ``bad`` poses of ``q`` and the most of the
    others, their bounds on whole degrees within ``ranges``; None where none holds any."""
    out = ranges.copy()
    if len(joints) == 1:
        (j,) = joints
        count, lo, hi = _interval(q[:, j], bad)
        if not count:
            return None
        out[j] = _inward(lo, hi)
        return out if out[j, 0] < out[j, 1] else None
    i, j = joints
    edges = np.linspace(ranges[i, 0], ranges[i, 1], GRID + 1)
    best = (0, None)
    for a in range(GRID):
        for b in range(a + 1, GRID + 1):
            inside = (q[:, i] >= edges[a]) & (q[:, i] <= edges[b])
            count, lo, hi = _interval(q[inside, j], bad[inside])
            if count > best[0]:
                best = (count, (edges[a], edges[b], lo, hi))
    if best[1] is None:
        return None
    a, b, lo, hi = best[1]
    for _ in range(2):  # each range refined on the poses the other holds (the grid's range holds them all)
        inside = (q[:, j] >= lo) & (q[:, j] <= hi)
        count, a2, b2 = _interval(q[inside, i], bad[inside])
        inside = (q[:, i] >= a2) & (q[:, i] <= b2)
        count2, lo2, hi2 = _interval(q[inside, j], bad[inside])
        if not (count and count2):
            break
        a, b, lo, hi = a2, b2, lo2, hi2
    out[i], out[j] = _inward(a, b), _inward(lo, hi)
    return out if out[i, 0] < out[i, 1] and out[j, 0] < out[j, 1] else None


def _held(q: np.ndarray, ranges: np.ndarray) -> np.ndarray:
    return np.all((q >= ranges[:, 0] - 1e-12) & (q <= ranges[:, 1] + 1e-12), axis=1)


def narrowed(model: RevoluteChain, realised, kinds, coils, names, q, ranges, *, random: int | None = None,
             margin: float = MARGIN, fresh: int = 2000, seed: int = 1, massed: RevoluteChain | None = None,
             loaded=(), limits=None) -> tuple[Narrowing, ...]:
    """The narrower workspaces on which the realised springs clear the links (see the module docstring): the best
    narrowing of one joint's range, and, where it keeps less than half of the poses, the best of two joints'
    ranges, each kept only where it holds at least :data:`LEAST_KEPT` of the workspace's poses and ``fresh`` poses
    drawn within it all clear (within :data:`ROUNDS` rounds); empty when the springs clear every pose of ``q``
    (N, n) rad or no such narrowing was found. ``ranges``: the design's workspace (n, 2) rad; ``random``: how
    many of ``q``'s first poses are random draws of it (the share kept is counted on them; default all);
    ``massed``: the arm carrying the springs' hardware, on which ``loaded`` joints' shares are measured;
    ``limits``: the joints' whole ranges, for the :class:`~springlab.design.collision.Sampler`."""
    q = np.asarray(q, dtype=float)
    ranges = np.asarray(ranges, dtype=float)
    random = q.shape[0] if random is None else int(random)
    probe = colliding(model, realised, kinds, coils, names, q[:min(random, PROBE)], margin=margin)
    if np.mean(~probe) < LEAST_KEPT:
        return ()  # no narrowing could keep a tenth of the workspace
    rest = colliding(model, realised, kinds, coils, names, q[len(probe):], margin=margin) if len(q) > len(probe) else []
    bad = np.concatenate([probe, rest]).astype(bool)
    if not bad.any() or np.mean(~bad[:random]) < LEAST_KEPT:
        return ()  # nothing to narrow, or no narrowing could keep a tenth of the workspace
    found: list[Narrowing] = []
    singles = [(j,) for j in range(model.n)]
    pairs = [(i, j) for i in range(model.n) for j in range(model.n) if i != j]
    for size, family in enumerate((singles, pairs), start=1):
        pool, hit = q.copy(), bad.copy()
        rng = np.random.default_rng([seed, 29, size])  # each family its own poses: one's rounds move none of the other's
        for rounds in range(1, ROUNDS + 1):
            boxes = [(b, js) for js in family if (b := _box(pool, hit, ranges, js)) is not None]
            box, joints = max(boxes, key=lambda bj: (int(np.sum(_held(q[:random], bj[0]))), -sum(bj[1])),
                              default=(None, ()))
            if box is None or np.mean(_held(q[:random], box)) < LEAST_KEPT:
                break  # none left, or none that keeps a tenth of the workspace
            try:
                poses = Sampler(model, box, np.random.default_rng([seed, 31, size, rounds]), limits=limits).draw(fresh, rng)
            except SpringlabError:  # no pose of the narrowed ranges is free
                break
            gaps = measured(model, realised, kinds, coils, names, poses, margin=margin)
            near = gaps.within(margin)
            if near.any():  # the fresh poses found more: they join the pool, at most ROUNDS times
                pool, hit = np.vstack([pool, poses]), np.concatenate([hit, near])
                continue
            worst = min((gaps.worst(k) + (piece.name.partition(" ")[0],) for k, piece in enumerate(gaps.pieces)),
                        key=lambda r: r[0])  # (clearance, body, pose, spring)
            arm = model if massed is None else massed
            gravity = np.max(np.abs(gravity_torques(arm, poses)), axis=0)
            left = np.max(np.abs(joint_torques(arm, realised, poses)), axis=0)
            removed = {model.joints[i]: float(100 * (1 - left[i] / gravity[i])) for i in loaded if gravity[i] > 0}
            found.append(Narrowing(box, tuple(joints), float(np.mean(_held(q[:random], box))), poses.shape[0],
                                   float(worst[0]), gaps.links[worst[1]], worst[3], removed, rounds))
            break
        if found and found[-1].kept >= 0.5:
            break
    return tuple(found)
