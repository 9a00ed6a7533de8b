"""Springs for a real arm: the general model (:class:`~springlab.model.revolute.RevoluteChain`, read
from a URDF's own frames), its structure with proof, exact balance where the structure allows
it and the best springs elsewhere.

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

**Best springs elsewhere** (:func:`best_springs`): attachment points within each body's reach
and rates that minimise the largest holding torque over the workspace (sequential linear
programming on route 2's torques, HiGHS).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.energy.geometry import gravity_torques, joint_torques
from springlab.errors import SpringlabError
from springlab.model.revolute import RevoluteChain, body_frames, joint_axes
from springlab.model.springs import PointSpring
from springlab.tables import Table

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
    planar, why = _planar(model, loaded, w, vertical, up)
    return Structure(model, tuple(unloaded), reasons, loaded, planar, why, tuple(float(p) for p in peak))


def _planar(model, loaded, w, vertical, up) -> tuple[bool, str]:
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
    return True, (f"{', '.join(names)} turn about parallel horizontal axes after vertical ones: a planar chain, "
                  "balanced exactly by zero-free-length springs (one per pair of its links at most)")


def _zero_pose(model):
    R, o = body_frames(model, np.zeros(model.n))
    return R[0], o[0]


def planar_springs(model: RevoluteChain, found: Structure, *, reach=None) -> tuple[PointSpring, ...]:
    """Zero-free-length springs that balance a planar loaded chain exactly (module docstring): one
    per pair of its links (the link before the first loaded joint is the plane's ground) whose
    coefficient needs one, longest span first.

    :param reach: per body, the distance (m) an end may lie from its joint, (n + 1,) (default: half
        the distance to the next joint, at least 5 cm); it sets each spring's end offsets, the rate
        follows
    """
    _checks.instance("found", found, Structure, "springlab Structure (structure(model))")
    if not found.planar:
        raise SpringlabError(f"the loaded joints of {model.name!r} are not a planar chain ({found.why}): "
                             "use best_springs")
    loaded = found.loaded
    first, last = loaded[0], loaded[-1]
    R0, o0 = _zero_pose(model)
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
    signs = [1.0] + [float(np.sign(R0[i + 1] @ model.axes[i] @ w)) for i in loaded]
    joint_at = [origin] + [o0[i + 1] for i in loaded]  # joint k's origin (k >= 1); the ground's is joint 1's
    nxt = [joint_at[k + 1] if k < m else None for k in range(m + 1)]  # the next joint along the chain
    l = [z(nxt[k]) - z(joint_at[k]) if k < m else 0j for k in range(m + 1)]
    l[0] = 0j  # the ground reaches joint 1 at the plane's origin
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
            G[t] += model.mass[b] * l[t]  # counted at joint t+1 on link t
        G[k] += model.mass[b] * (z(com) - z(joint_at[k]))
    g = model.g
    need = {}
    for k in range(1, m + 1):
        need[(0, k)] = -g * np.conj(1j) * G[k] * signs[k] ** 0  # cancels g Re(conj(i) e^{i theta_k} G_k)
    reach = _reach(model, reach)
    springs = []
    for span in range(m, 0, -1):
        for j in range(0, m - span + 1):
            k = j + span
            W = need.get((j, k), 0j)
            if abs(W) <= 1e-14 * max(1.0, max(abs(v) for v in need.values())):
                continue
            rho_j, rho_k = reach[bodies[j]], reach[bodies[k]]
            direction = l[k] if abs(l[k]) > 1e-9 else (G[k] if abs(G[k]) > 1e-12 else 1.0 + 0j)
            c_k = rho_k * direction / abs(direction)
            kappa = abs(W) / (rho_j * rho_k)
            c_j = np.conj(W / (kappa * c_k))  # kappa conj(c_j) c_k = W
            cs = {j: c_j, k: c_k}
            cs.update({t: l[t] for t in range(j + 1, k)})
            for s in range(j, k + 1):
                for t in range(s + 1, k + 1):
                    if (s, t) != (j, k):
                        need[(s, t)] = need.get((s, t), 0j) - kappa * np.conj(cs[s]) * cs[t]
            need[(j, k)] = 0j
            A = z(nxt[j]) - c_j  # end A on link j, c_j before the next joint
            B = z(joint_at[k]) + c_k
            axial = float((o0[bodies[k]] - origin) @ w)  # both ends in one plane normal to the axes
            springs.append(_spring(model, bodies[j], A, bodies[k], B, kappa, origin, h, up, w, axial, R0, o0))
    return tuple(springs)


def _spring(model, body_a, A, body_b, B, k, origin, h, up, w, axial, R0, o0) -> PointSpring:
    def local(body, zc):
        world = origin + zc.real * h + zc.imag * up + axial * w
        return R0[body].T @ (world - o0[body])

    return PointSpring(model.bodies[body_a], tuple(local(body_a, A)), model.bodies[body_b], tuple(local(body_b, B)),
                       float(k))


def _reach(model: RevoluteChain, reach) -> np.ndarray:
    if reach is not None:
        reach = _checks.real_array("reach", reach, shape=(model.n + 1,))
        if not np.all(reach > 0):
            raise SpringlabError(f"reach must be positive distances (m), one per body, got {reach.tolist()}")
        return reach
    out = np.full(model.n + 1, 0.05)
    for b in range(model.n):
        out[b] = max(0.05, 0.5 * float(np.linalg.norm(model.placements[b][:3, 3])))
    out[model.n] = max(0.05, float(np.linalg.norm(model.com[model.n])))
    return out


def torque_table(model: RevoluteChain, q, cases: dict) -> Table:
    """Per loaded joint: peak and RMS gravity torque (N m), the same with each set of springs in
    ``cases`` (name -> springs), and the percentage of the peak each removes."""
    q = model.check_q(q)
    gravity = gravity_torques(model, q)
    rows = []
    with_springs = {name: joint_torques(model, springs, q) for name, springs in cases.items()}
    for i, name in enumerate(model.joints):
        peak, rms = np.max(np.abs(gravity[:, i])), np.sqrt(np.mean(gravity[:, i] ** 2))
        row = [name, f"{peak:.4g}", f"{rms:.4g}"]
        for tau in with_springs.values():
            p = np.max(np.abs(tau[:, i]))
            row += [f"{p:.3g}", f"{np.sqrt(np.mean(tau[:, i] ** 2)):.3g}",
                    f"{100 * (1 - p / peak):.2f}" if peak > 0 else ""]
        rows.append(row)
    headers = ["joint", "gravity peak (N m)", "gravity RMS (N m)"]
    for case in cases:
        headers += [f"{case} peak (N m)", f"{case} RMS (N m)", f"{case}: peak removed (%)"]
    return Table(headers, rows)
