"""What gravity loads in an arm of the general model, with proof, and the exact springs of a planar chain.

**Structure** (:func:`structure`). A joint's gravity torque is a trigonometric polynomial of the
joint angles; one that vanishes at every pose of a random sample (round-off aside) vanishes
identically (a nonzero trigonometric polynomial is zero only on a set of measure zero). Such a
joint is *unloaded*: the energy does not depend on it (dV/dq_i = its gravity torque = 0). The
reason is named: a vertical axis (its own and every axis before it parallel to gravity, so it
stays vertical), or the mass beyond it centred on its axis. The *loaded* joints form a
**planar chain** when they are consecutive, their axes parallel, and every joint before them
turns about the vertical: then their axes stay horizontal at every pose, gravity acts in their
plane, and the energy is that of a planar chain whose links carry the bodies beyond (the
unloaded joints after them do not change it).

**Exact balance of a planar chain** (:func:`planar_springs`). In the plane (a complex coordinate
z = x + i y, y up), a point fixed to planar link k sits at
z = o + sum_{t<k} e^{i theta_t} l_t + e^{i theta_k} c, theta_t the link's absolute angle, l_t the
vector from joint t to joint t+1. Gravity's energy is g sum_k Re(conj(i) e^{i theta_k} G_k)
(G_k: the first moment of everything link k carries about its joint, the links beyond counted at
its next joint), and a zero-free-length spring S(j, k) of rate kappa, from c_j before joint j+1
to c_k beyond joint k, adds kappa Re(conj(c_s) c_t e^{i (theta_t - theta_s)}) for every pair
j <= s < t <= k of the links it spans (|B - A|^2 expanded). Balance: every pair's coefficient
vanishes. A spring's own pair (j, k) takes any complex value kappa conj(c_j) c_k; the pairs
inside its span take what its intermediate links give. So the springs are chosen from the
longest span to the shortest, each cancelling what its pair has collected: one spring per pair
at most (m (m + 1) / 2 for m planar links), every one solvable, hence **exact balance exists for
every planar chain**, centres of mass anywhere in or off the plane (an offset along the axes is
horizontal and costs nothing). Ends off the plane (along the axes) add a constant length only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.energy.geometry import gravity_torques
from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, joint_axes
from springlab.model.springs import PointSpring
from springlab.tables import Table

BRACKET = 0.03
"""m: how far beyond a body's outline (its URDF geometry's bounding box) a spring end may sit by
default: an eye bolt or a short bracket. Without it the stiffest exact spring of the UR10 (across its
elbow, whose forearm ends 6 cm behind the joint) needs 5957 N/m, which no stocked wire winds; with
it, 2692 N/m."""

MIN_SIZE = 2e-3
"""m: the smallest box side an end moves in (a flat outline, a base clipped at its mounting plane)."""

ROUND_OFF = 1e-10
"""A joint whose gravity torque stays below this fraction of the arm's largest over the sample
is unloaded (the torques are computed to about 1e-15 relative)."""

NEGLIGIBLE = 1e-5
"""A joint whose gravity torque stays below this fraction of the arm's largest (but above
:data:`ROUND_OFF`) is counted unloaded, the torque it leaves named: a URDF's rounded angles
(``rpy="0 0 3.14159"``) tilt a vertical axis by some 1e-6 rad."""

PARALLEL = 1e-5
"""|sin| of the angle (rad) below which two axes are parallel, and |cos| below which an axis is
horizontal (a URDF's rounded angles are good to about 1e-6)."""


@dataclass(frozen=True)
class Structure:
    """What gravity loads in an arm, with the reasons (:func:`structure`).

    :ivar model: the arm
    :ivar unloaded: joint indices (0-based) whose gravity torque vanishes identically
    :ivar reasons: joint index -> why it is unloaded
    :ivar loaded: the other joints
    :ivar planar: the loaded joints form a planar chain (exact balance exists: :func:`planar_springs`)
    :ivar why: why the loaded joints are (or are not) a planar chain
    :ivar peak: each joint's largest gravity torque over the sample (N m)
    """

    model: RevoluteChain
    unloaded: tuple
    reasons: dict
    loaded: tuple
    planar: bool
    why: str
    peak: tuple

    @property
    def exact(self) -> bool:
        """True when springlab balances the arm exactly (a planar loaded chain, or nothing loaded)."""
        return self.planar or not self.loaded

    def table(self) -> Table:
        rows = []
        for i, name in enumerate(self.model.joints):
            rows.append((name, "unloaded" if i in self.unloaded else "loaded", f"{self.peak[i]:.3g}",
                         self.reasons.get(i, "")))
        return Table(["joint", "gravity", "largest gravity torque (N m)", "why"], rows)

    def summary(self) -> str:
        names = ", ".join(self.model.joints[i] for i in self.loaded) or "none"
        return f"loaded joints: {names}. {self.why}"


def structure(model: RevoluteChain, q=None, *, samples: int = 512, rng=0) -> Structure:
    """The arm's structure (see the module docstring): which joints gravity loads, why the others
    carry nothing, and whether the loaded ones form a planar chain.

    :param q: the poses to sample (N, n) rad (default ``samples`` random poses within the limits,
        seeded by ``rng``: the proof needs random poses, not a grid that may hit a zero set)
    """
    _checks.instance("model", model, RevoluteChain, "springlab RevoluteChain")
    q = model.random_q(samples, rng) if q is None else model.check_q(q)
    tau = gravity_torques(model, q)
    peak = np.max(np.abs(tau), axis=0)
    scale = float(np.max(peak))
    R, _ = body_frames(model, q)
    w = joint_axes(model, R)  # (N, n, 3)
    up = model.up
    vertical = np.all(np.linalg.norm(np.cross(w, up), axis=-1) <= PARALLEL, axis=0)  # |sin| of the tilt
    unloaded, reasons = [], {}
    if scale == 0:
        return Structure(model, tuple(range(model.n)), dict.fromkeys(range(model.n), "no joint axis moves a mass "
                         "up or down (every gravity torque is zero)"), (), False, "nothing to balance", tuple(peak))
    all_vertical_before = True
    for i in range(model.n):
        if ROUND_OFF * scale < peak[i] <= NEGLIGIBLE * scale:
            unloaded.append(i)
            reasons[i] = (f"negligible: at most {peak[i]:.2g} N m ({peak[i] / scale:.1g} of the largest), left "
                          "unbalanced" + (" (its axis is off vertical by the file's rounding)" if vertical[i] else ""))
        elif peak[i] <= ROUND_OFF * scale:
            unloaded.append(i)
            if vertical[i] and all_vertical_before:
                reasons[i] = "vertical axis (it and every axis before it parallel to gravity)"
            else:
                reasons[i] = (f"the mass beyond it is centred on its axis: its gravity torque is below "
                              f"{ROUND_OFF:g} of the largest at {q.shape[0]} random poses, so it vanishes identically")
        all_vertical_before = all_vertical_before and bool(vertical[i])
    loaded = tuple(i for i in range(model.n) if i not in unloaded)
    planar, why = planar_chain(model, loaded, w, vertical, up)
    return Structure(model, tuple(unloaded), reasons, loaded, planar, why, tuple(float(p) for p in peak))


def planar_chain(model, loaded, w, vertical, up) -> tuple[bool, str]:
    """Whether the ``loaded`` joints (indices) form a planar chain (module docstring), and why: from their axes
    ``w`` (N, n, 3) over sample poses, which joints stay ``vertical`` (n,) and the ``up`` direction."""
    names = [model.joints[i] for i in loaded]
    if not loaded:
        return False, "gravity loads no joint: nothing to balance"
    first, last = loaded[0], loaded[-1]
    if list(loaded) != list(range(first, last + 1)):
        gap = [model.joints[i] for i in range(first, last + 1) if i not in loaded]
        return False, (f"the loaded joints are not consecutive (unloaded {', '.join(gap)} lies between them): "
                       "not a planar chain")
    tilted = [model.joints[i] for i in range(first) if not vertical[i]]
    if tilted:
        return False, (f"joint(s) {', '.join(tilted)} before the loaded ones turn about a non-vertical axis: the "
                       "loaded joints' plane tilts, so gravity leaves it")
    ref = w[:, first]
    for i in loaded[1:]:
        if np.max(np.linalg.norm(np.cross(w[:, i], ref), axis=1)) > PARALLEL:
            return False, (f"loaded joints {model.joints[first]} and {model.joints[i]} turn about axes that are not "
                           "parallel: not a planar chain")
    if np.max(np.abs(ref @ up)) > PARALLEL:
        return False, "the loaded joints' axes are not horizontal: gravity acts out of their plane"
    before = " after vertical ones" if first > 0 else ""
    return True, (f"{', '.join(names)} turn about parallel horizontal axes{before}: a planar chain, "
                  "balanced exactly by zero-free-length springs (one per pair of its links at most)")


def zero_pose(model):
    """Every body's frame at the zero pose: rotations (n+1, 3, 3) and origins (n+1, 3) (m)."""
    R, o = body_frames(model, np.zeros(model.n))
    return R[0], o[0]


def planar_moments(model: RevoluteChain, found: Structure) -> dict:
    """A planar loaded chain in its plane (module docstring), at the zero pose: the loaded axes' direction
    ``w`` (world), ``h`` and ``up`` (the plane's axes: a turn theta about w multiplies z = x h + y up by
    e^{i theta}), ``origin`` (the first loaded joint's), ``z`` (a point's complex coordinate), the planar
    links' bodies (``bodies``: 0 the ground, the body before the first loaded joint; ``m`` links), each
    link's joint (``joint_at``) and next joint (``next``, world points), the vectors between them
    (``vec``, complex) and ``G``: each link's first moment (kg m, complex) of what it carries about its
    joint, the links beyond counted at its next joint."""
    loaded = found.loaded
    first = loaded[0]
    R0, o0 = zero_pose(model)
    w = R0[first + 1] @ model.axes[first]  # the loaded axes' common direction (world, zero pose)
    up = model.up
    h = np.cross(up, w)  # (h, up, w) right-handed: a turn theta about w multiplies z by e^{i theta}
    origin = o0[first + 1]  # joint `first`'s origin

    def z(x):
        d = np.asarray(x) - origin
        return complex(d @ h, d @ up)

    # planar links: 0 = the ground (body `first`), k = 1..m the bodies of the loaded joints
    bodies = [first] + [i + 1 for i in loaded]
    m = len(loaded)
    joint_at = [origin] + [o0[i + 1] for i in loaded]  # joint k's origin (k >= 1); the ground's is joint 1's
    nxt = [joint_at[k + 1] if k < m else None for k in range(m + 1)]  # the next joint along the chain
    vec = [z(nxt[k]) - z(joint_at[k]) if k < m else 0j for k in range(m + 1)]
    vec[0] = 0j  # the ground reaches joint 1 at the plane's origin
    # G_k: the first moment (kg m) of what link k carries about its joint; bodies beyond the last
    # loaded joint ride on the last link (the unloaded joints after it do not change the energy)
    carrier = {b: None for b in range(model.n + 1)}
    for k, b in enumerate(bodies[1:], start=1):
        upto = bodies[k + 1] if k < m else model.n + 1
        for c in range(b, upto):
            carrier[c] = k
    G = [0j] * (m + 1)
    for b in range(model.n + 1):
        k = carrier[b]
        if k is None or model.mass[b] == 0:
            continue
        com = o0[b] + R0[b] @ model.com[b]
        for t in range(1, k):
            G[t] += model.mass[b] * vec[t]  # counted at joint t+1 on link t
        G[k] += model.mass[b] * (z(com) - z(joint_at[k]))
    return {"first": first, "bodies": bodies, "m": m, "joint_at": joint_at, "next": nxt, "vec": vec, "G": G,
            "origin": origin, "h": h, "up": up, "w": w, "R0": R0, "o0": o0, "z": z}


def planar_springs(model: RevoluteChain, found: Structure, *, reach: float | None = None) -> tuple[PointSpring, ...]:
    """Zero-free-length springs that balance a planar loaded chain exactly (module docstring): one
    per pair of its links (the link before the first loaded joint is the plane's ground) whose
    coefficient needs one, longest span first.

    Each spring's ends lie in their bodies' boxes (``attachment_boxes``: the body's outline from its URDF
    geometry, ``reach`` (m) beyond it; without an outline, the link and a bracket). Only the
    product conj(c_j) c_k of its two offsets is fixed, so the direction of c_k is free: it is
    chosen, over a 1-degree scan, to make the offsets' lengths' product (the lever) the largest the
    boxes allow, hence the rate the least. Along the axes each end sits at its box's middle (an
    offset along the axes adds a constant length only).
    """
    _checks.instance("found", found, Structure, "springlab Structure (structure(model))")
    if not found.planar:
        raise SpringlabError(f"the loaded joints of {model.name!r} are not a planar chain ({found.why}): "
                             "use best_springs")
    plane = planar_moments(model, found)
    first, bodies, m, joint_at, nxt, vec, G = (plane[k] for k in ("first", "bodies", "m", "joint_at", "next",
                                                                "vec", "G"))
    origin, h, up, w, R0, o0, z = (plane[k] for k in ("origin", "h", "up", "w", "R0", "o0", "z"))
    g = model.g
    need = {}
    for k in range(1, m + 1):
        need[(0, k)] = -g * np.conj(1j) * G[k]  # cancels g Re(conj(i) e^{i theta_k} G_k); an axis along -w
        # only turns its link the other way, which the balance (for every theta) does not mind
    centres, half = attachment_boxes(model, reach)
    frames = (origin, h, up, w, R0, o0)
    springs = []
    for span in range(m, 0, -1):
        for j in range(0, m - span + 1):
            k = j + span
            W = need.get((j, k), 0j)
            if abs(W) <= 1e-14 * max(1.0, max(abs(v) for v in need.values())):
                continue
            c_j, c_k = _offsets(W, (bodies[j], z(nxt[j])), (bodies[k], z(joint_at[k])), centres, half, frames)
            kappa = abs(W) / (abs(c_j) * abs(c_k))
            cs = {j: c_j, k: c_k}
            cs.update({t: vec[t] for t in range(j + 1, k)})
            for s in range(j, k + 1):
                for t in range(s + 1, k + 1):
                    if (s, t) != (j, k):
                        need[(s, t)] = need.get((s, t), 0j) - kappa * np.conj(cs[s]) * cs[t]
            need[(j, k)] = 0j
            A = z(nxt[j]) - c_j  # end A on link j, c_j before the next joint
            B = z(joint_at[k]) + c_k
            springs.append(PointSpring(model.bodies[bodies[j]], tuple(_local(bodies[j], A, centres, frames)),
                                       model.bodies[bodies[k]], tuple(_local(bodies[k], B, centres, frames)),
                                       float(kappa)))
    return tuple(springs)


def _local(body, zc, centres, frames) -> np.ndarray:
    """The point zc of the plane, at the middle of the body's box along the axes, in the body's frame."""
    origin, h, up, w, R0, o0 = frames
    middle = o0[body] + R0[body] @ centres[body]
    world = origin + zc.real * h + zc.imag * up + float((middle - origin) @ w) * w
    return R0[body].T @ (world - o0[body])


def _ray(body, anchor, direction, centres, half, frames) -> float:
    """How far (m) from ``anchor`` (a point of the plane) along ``direction`` (a unit complex number)
    an end can go and stay in the body's box: the far end of the ray's stretch inside it (0 when the
    ray misses it)."""
    origin, h, up, w, R0, o0 = frames
    p = _local(body, anchor, centres, frames)
    d = R0[body].T @ (direction.real * h + direction.imag * up)
    lo, hi = centres[body] - half[body], centres[body] + half[body]
    enter, leave = 0.0, np.inf
    for a in range(3):
        if abs(d[a]) < 1e-12:
            if not lo[a] - 1e-12 <= p[a] <= hi[a] + 1e-12:
                return 0.0
            continue
        t1, t2 = (lo[a] - p[a]) / d[a], (hi[a] - p[a]) / d[a]
        enter, leave = max(enter, min(t1, t2)), min(leave, max(t1, t2))
    return float(leave) if leave > enter else 0.0


def _offsets(W, end_j, end_k, centres, half, frames) -> tuple[complex, complex]:
    """The offsets c_j (end A = anchor_j - c_j on body j) and c_k (end B = anchor_k + c_k on body k)
    with conj(c_j) c_k along W (the rate makes up its size), both ends in their boxes, the product
    of their lengths the largest over a 1-degree scan of c_k's direction."""
    (body_j, anchor_j), (body_k, anchor_k) = end_j, end_k
    best = (0.0, 0j, 0j)
    for phi in np.radians(np.arange(360)):
        dk = complex(np.cos(phi), np.sin(phi))
        dj = np.conj(W / dk) / abs(W)  # conj(dj) dk = W / |W|
        rho_k = _ray(body_k, anchor_k, dk, centres, half, frames)
        rho_j = _ray(body_j, anchor_j, -dj, centres, half, frames)
        if rho_j * rho_k > best[0]:
            best = (rho_j * rho_k, rho_j * dj, rho_k * dk)
    if best[0] <= 1e-9:
        raise SpringlabError(f"no direction puts both ends of a spring between bodies {body_j} and {body_k} in "
                             "their boxes (each end's ray from its joint misses its body's outline): give a "
                             "reach beyond the outlines (--reach)")
    return best[1], best[2]


def attachment_boxes(model: RevoluteChain, reach=None) -> tuple[np.ndarray, np.ndarray]:
    """Per body, the centre (m, body frame) and half-sizes (m, per axis) of the box its spring ends may
    use, (n + 1, 3) each.

    Where the model knows the body's outline (a URDF's geometry, ``model.outline``), the box bounds
    that outline, ``reach`` (m, default :data:`BRACKET`) beyond it each way: a bracket that long.
    Elsewhere it is
    centred between the body's joint and the next (the last body: its centre of mass), half the
    distance plus ``reach`` each way (default 15 % of the arm's length, the sum of its joints'
    distances, at least 5 cm: a post or bracket of that size on any body). The base's box stops at
    its frame's horizontal plane (the mounting surface, when the base frame's up is one of its
    axes): nothing is attached under the table."""
    length = float(np.sum(np.linalg.norm(model.placements[:, :3, 3], axis=1)))
    given = None if reach is None else _checks.positive("reach", reach, allow_zero=True, unit="m") + 0.0
    if given is not None and given > max(length, 0.1):
        raise SpringlabError(f"reach = {given:g} m is longer than the arm itself ({length:.3g} m, the sum of its "
                             "joints' distances): a bracket beyond a link is a few centimetres, e.g. '3 cm'")
    margin = max(0.05, 0.15 * length) if given is None else given
    centres, half = np.zeros((model.n + 1, 3)), np.zeros((model.n + 1, 3))
    for b in range(model.n + 1):
        if model.outline and len(model.outline[b]):
            lo, hi = np.min(model.outline[b], axis=0), np.max(model.outline[b], axis=0)
            centres[b], half[b] = 0.5 * (lo + hi), 0.5 * (hi - lo) + (BRACKET if given is None else given)
            continue
        far = model.placements[b][:3, 3] if b < model.n else model.com[b]
        centres[b] = 0.5 * np.asarray(far)
        half[b] = 0.5 * float(np.linalg.norm(far)) + margin
    k = int(np.argmax(np.abs(model.up)))
    if abs(model.up[k]) > 1 - 1e-9:  # the base's box above (or, up = -axis, below) its frame's plane
        lo, hi = centres[0, k] - half[0, k], centres[0, k] + half[0, k]
        lo, hi = (max(lo, 0.0), max(hi, MIN_SIZE)) if model.up[k] > 0 else (min(lo, -MIN_SIZE), min(hi, 0.0))
        centres[0, k], half[0, k] = 0.5 * (lo + hi), 0.5 * (hi - lo)
    return centres, np.maximum(half, MIN_SIZE / 2)
