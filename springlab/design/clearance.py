"""Clearance between the springs and the links over the workspace (route 2's geometry).

Each spring is the segment between its ends A and B, thickened by its radius (half its
coil's outer diameter, or the cable's); each moving link t is the segment from joint
J_{t-1} to J_t, thickened by its radius (the arm file's ``radius`` per link, default
:data:`springlab.model.armfile.LINK_RADIUS`); the ground link is the base column, the segment from the base joint
down by the arm's reach. The clearance of a spring and a link is the smallest distance
between the two segments over the workspace poses, less both radii: negative means the
spring passes through the link somewhere in the workspace. A spring's own two links are
left out (it is attached to them), and each end of the spring's segment is trimmed by its own
link's radius (the spring leaves its bracket at the link's surface: an end at a joint does not
count as touching the next link there). Lengths in m.

Judge clearance over the poses the arm will take: random poses over every direction include
folded ones where the links themselves pass through each other.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.energy.geometry import attachment_points
from springlab.errors import SpringlabError
from springlab.model.armfile import LINK_RADIUS
from springlab.model.chain import UP, Chain, check_springs
from springlab.tables import Table


def segment_distance(P0, P1, Q0, Q1) -> np.ndarray:
    """Smallest distance (m) between segments P0-P1 and Q0-Q1, row by row: arrays (N, 3) -> (N,).

    The closest points minimise |P0 + s u - Q0 - t v| over s, t in [0, 1] (the clamped
    solution of the 2 x 2 normal equations, then each parameter re-clamped given the other).
    """
    P0, P1, Q0, Q1 = (_checks.real_array(name, v, shape=(None, 3)) for name, v in
                      (("P0", P0), ("P1", P1), ("Q0", Q0), ("Q1", Q1)))
    u, v, w = P1 - P0, Q1 - Q0, P0 - Q0
    a, b, c = (u * u).sum(1), (u * v).sum(1), (v * v).sum(1)
    d, e = (u * w).sum(1), (v * w).sum(1)
    den = a * c - b * b
    tiny = 1e-300
    s = np.where(den > 1e-14 * np.maximum(a * c, tiny), (b * e - c * d) / np.maximum(den, tiny), 0.0)
    s = np.clip(s, 0.0, 1.0)
    t = np.where(c > tiny, (b * s + e) / np.maximum(c, tiny), 0.0)
    t = np.clip(t, 0.0, 1.0)
    s = np.where(a > tiny, np.clip((b * t - d) / np.maximum(a, tiny), 0.0, 1.0), 0.0)
    return np.linalg.norm(w + s[:, None] * u - t[:, None] * v, axis=1)


@dataclass(frozen=True)
class Clearance:
    """Per (spring label, link): the smallest clearance (m) and the pose where it occurs."""

    pairs: list  # (spring label, link, clearance m, pose index)
    per_pose: dict  # spring label -> (N,) its smallest clearance from any other link at each pose (m)

    @property
    def crossing(self) -> list:
        """The pairs whose clearance is negative: the spring passes through the link."""
        return [p for p in self.pairs if p[2] < 0]

    def smallest(self) -> float:
        return min((p[2] for p in self.pairs), default=np.inf)

    def per_spring(self) -> dict:
        """{spring label: (smallest clearance m, its link)}."""
        out = {}
        for label, link, gap, _ in self.pairs:
            if label not in out or gap < out[label][0]:
                out[label] = (gap, link)
        return out

    def table(self) -> Table:
        return Table(["spring", "nearest link", "smallest clearance (mm)", "passes through it"],
                     [(label, link, f"{gap * 1e3:.1f}", "yes" if gap < 0 else "no")
                      for label, (gap, link) in self.per_spring().items()])


def clearance(chain: Chain, springs, X, *, link_radii=None, spring_radii=None,
              base_radius: float = LINK_RADIUS) -> Clearance:
    """The clearance of every spring from every other link over the poses X (N, n, 3).

    :param link_radii: m, one per moving link (n - 1 values) or one for all; None: :data:`springlab.model.armfile.LINK_RADIUS`
    :param spring_radii: m, one per spring; None: 0 (the spring's line)
    :param base_radius: m, the base column's
    """
    base_radius = _checks.positive("base_radius", base_radius, allow_zero=True, unit="m")
    springs = check_springs(chain, springs)
    X = chain.check_directions(X)
    n = chain.n
    if link_radii is None:
        radii = np.full(n - 1, LINK_RADIUS)
    else:
        radii = _checks.real_array("link_radii", link_radii)
        if radii.ndim == 0:
            radii = np.full(n - 1, float(radii))
        if radii.shape != (n - 1,) or np.any(radii < 0):
            raise SpringlabError(f"link_radii must be one radius >= 0 m per moving link ({n - 1}) or one for all, "
                                 f"got {radii.tolist()}")
    own = np.zeros(len(springs)) if spring_radii is None else _checks.real_array("spring_radii", spring_radii,
                                                                                  shape=(len(springs),))
    if np.any(own < 0):
        raise SpringlabError(f"spring_radii must be >= 0 m, got {np.min(own)}")
    joints = chain.joint_positions(X)  # joints[:, t - 1] = J_t
    reach = float(np.sum(chain.r))
    base = np.broadcast_to(np.asarray(UP, dtype=float) * -reach, joints[:, 0].shape)
    pairs, per_pose = [], {}
    for idx, s in enumerate(springs):
        A, B = attachment_points(chain, s, X)
        line = B - A
        length = np.linalg.norm(line, axis=1)
        trim_a = base_radius if s.i == 1 else float(radii[s.i - 2])
        trim_b = float(radii[s.j - 2])
        keep = length > trim_a + trim_b
        unit = line / np.where(length > 0, length, 1.0)[:, None]
        A = np.where(keep[:, None], A + trim_a * unit, A)
        B = np.where(keep[:, None], B - trim_b * unit, A)
        for t in range(1, n + 1):
            if t in (s.i, s.j):
                continue
            if t == 1:
                Q0, Q1, r = joints[:, 0] + base, joints[:, 0], base_radius
            else:
                Q0, Q1, r = joints[:, t - 2], joints[:, t - 1], float(radii[t - 2])
            gap = segment_distance(A, B, Q0, Q1) - r - own[idx]
            at = int(np.argmin(gap))
            label = f"{s.label}{s.pattern}"
            pairs.append((label, t, float(gap[at]), at))
            per_pose[label] = np.minimum(per_pose[label], gap) if label in per_pose else gap
    return Clearance(pairs, per_pose)
