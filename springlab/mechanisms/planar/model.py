r"""The planar arm of Juang, Jhuang and Chen (2022), paper 003: links, springs with
attachment angles, the workspace, and the map onto paper 000's spatial form.

The model shared by :mod:`~springlab.mechanisms.planar.quadratic` (route 1, the pseudo-stiffness terms),
:mod:`~springlab.mechanisms.planar.geometry` (route 2), :mod:`~springlab.mechanisms.planar.efficiency` and :mod:`~springlab.mechanisms.planar.synthesis`.

A planar serial arm with revolute joints: link 1 is the ground (a horizontal
reference of length r_1, 1 m in the paper), links 2..n move; theta_j is link j's
angle to link j-1 and Theta_{u,v} = theta_{u+1} + ... + theta_v (003 Eq. 3), so
Theta_{1,j} is link j's angle above the horizontal. A zero-free-length spring
S(i,j) is attached at distance a (m) from link i's distal joint, turned by
alpha from link i, and at b (m) from link j's proximal joint, turned by beta::

                       B = J_{j-1} + b (cos(Theta_1j + beta), sin(Theta_1j + beta))
                      o
        spring S(i,j) |        link j
                      |   .---------------
          A           | beta
          o  alpha     J_{j-1}
      a  /
    ----o J_i ---- links i+1 .. j-1 ----
     link i

Every pose-dependent energy term is a *pseudo-stiffness* (N/m) times r_u r_v:
gravity's G_{1,u} = |G_{1,u}| cos(90 deg - Theta_{1,u}) (003 Eqs. 6-7) and the
spring's K^S_{u,v} = amplitude cos(phase - Theta_{u,v}) (003 Eqs. 11a-d)::

    K_{i,j} = k A B cos(alpha - beta + 180 - Theta_ij)     (11a)
    K_{i,v} = k A   cos(alpha + 180 - Theta_iv),  v < j     (11b)
    K_{u,j} = k B   cos(-beta - Theta_uj),        u > i     (11c)
    K_{u,v} = k     cos(-Theta_uv),               i < u < v < j   (11d)

with A = a / r_i, B = b / r_j (003 Eq. 12). A :class:`~springlab.mechanisms.planar.quadratic.Term` holds one of them.

The planar form is the spatial one of paper 000 (:mod:`springlab.energy.quadratic`)
restricted to a vertical plane. With 000's vertical x_1 in place of the
horizontal ground link, a term amplitude cos(phase - Theta_uv) r_u r_v is
C_uv x_u . x_v + S_uv (x_u x x_v) . n with C = amplitude r_u r_v cos(phase')
and S = amplitude r_u r_v sin(phase'). For the attachment angles that criteria
C1 and C2 allow ((90, 0) on the ground, (0, 0) or (180, 180) elsewhere), S = 0
and C is exactly 000's entry G_{1,u} or K_S(i,j)_{u,v} (000 Eqs. 18, 23a-d) for a
spring with signed distances on the joint lines: :func:`to_spatial` gives that
chain and those springs, and the tests check the entries equal. Other angles
need the S part, which 000's springs (attached on the link lines) never have.
"

References
----------
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2023). A novel spring gravity-balance method for
spatial articulated manipulators without auxiliary links. Mechanism and Machine Theory 191,
105497. doi:10.1016/j.mechmachtheory.2023.105497
Juang, C.-W., Jhuang, C.-S., Chen, D.-Z. (2022). Spring efficiency assessment and efficient
use of spring methods of statically balanced planar serial manipulators with revolute
joints only. Mechanical Sciences (2022).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError


# --- the arm and its springs -------------------------------------------------------------
@dataclass(frozen=True)
class PlanarArm:
    """A planar arm; index 0 of each array is link 1, the ground.

    :ivar r: (n,) lengths r_1..r_n (m); r_1 is the ground's reference length
    :ivar s: (n,) COM distances from the proximal joint (m); s_1 unused
    :ivar m: (n,) masses (kg); m_1 unused
    :ivar g: gravitational acceleration (m/s^2)

    >>> arm = PlanarArm(r=[1.0, 0.36, 0.445, 0.3], s=[0, 0.18, 0.2225, 0.15], m=[0, 25, 26, 18], g=9.8)
    >>> arm.G.round(1).tolist()   # |G_12|, |G_13|, |G_14| (N/m), 003 Eq. (7)
    [553.7, 303.8, 88.2]
    """

    r: np.ndarray
    s: np.ndarray
    m: np.ndarray
    g: float = 9.81

    def __post_init__(self):
        r, s, m = (np.atleast_1d(_checks.real_array(k, getattr(self, k), finite_only=False)) for k in ("r", "s", "m"))
        if not (r.shape == s.shape == m.shape) or r.ndim != 1 or r.size < 2:
            raise SpringlabError(f"r, s, m need one entry per link (ground included, n >= 2), got {r.shape}, {s.shape}, {m.shape}")
        for name, v in (("r", r), ("s", s), ("m", m)):
            if not np.all(np.isfinite(v)):
                raise SpringlabError(f"{name} must be finite, got {v.tolist()}")
        for j in range(1, r.size):
            if r[j] <= 0:
                raise SpringlabError(f"r_{j + 1} = {r[j]} m: link lengths must be > 0")
            if m[j] <= 0:
                raise SpringlabError(f"m_{j + 1} = {m[j]} kg: masses must be > 0")
            if not 0 <= s[j] <= r[j]:
                raise SpringlabError(f"s_{j + 1} = {s[j]} m puts the centre of mass off link {j + 1} (r = {r[j]} m)")
        if r[0] <= 0:
            raise SpringlabError(f"r_1 (the ground's reference length) = {r[0]} m must be > 0")
        g = _checks.number("g", self.g)
        if not (np.isfinite(g) and g > 0):
            raise SpringlabError(f"g must be > 0 m/s^2, got {self.g}")
        with np.errstate(over="ignore"):
            scale = m.sum() * g * r.sum() / r[0] * r.sum()
        if not np.isfinite(scale):
            raise SpringlabError("masses, lengths and g this large overflow the energies: give them in SI units "
                                 "(kg, m, m/s^2)")
        for k, v in (("r", r), ("s", s), ("m", m)):
            object.__setattr__(self, k, v)
        object.__setattr__(self, "g", g)

    @property
    def n(self) -> int:
        return self.r.size

    @property
    def G(self) -> np.ndarray:
        """|G_{1,u}| for u = 2..n (N/m), 003 Eq. (7)."""
        out = []
        for u in range(2, self.n + 1):
            beyond = self.m[u:].sum()  # m_{u+1} .. m_n
            out.append(self.m[u - 1] * self.g * self.s[u - 1] / (self.r[0] * self.r[u - 1]) + self.g * beyond / self.r[0])
        return np.array(out)

    def with_payload(self, mass: float) -> PlanarArm:
        """The arm with ``mass`` (kg) added at the end link's COM (003 Eq. 32)."""
        mass = _checks.positive("payload mass", mass, allow_zero=True, unit="kg")
        m = self.m.copy()
        m[-1] += mass
        return PlanarArm(self.r, self.s, m, self.g)


@dataclass(frozen=True)
class PlanarSpring:
    """Zero-free-length spring S(i,j), 1 <= i < j: stiffness k (N/m), distances a, b (m)
    (a from link i's distal joint, b from link j's proximal joint), angles alpha, beta (deg)."""

    i: int
    j: int
    k: float
    a: float
    b: float
    alpha: float
    beta: float

    def __post_init__(self):
        for name in ("i", "j"):
            object.__setattr__(self, name, _checks.count(
                f"spring link index {name}", getattr(self, name), least=1, why=" (S(i,j) needs 1 <= i < j)"))
        if not self.i < self.j:
            raise SpringlabError(f"a spring S(i,j) needs 1 <= i < j, got i={self.i}, j={self.j}")
        object.__setattr__(self, "k", _checks.positive(f"k of {self.label}", self.k, unit="N/m"))
        for name, unit in (("a", "m"), ("b", "m"), ("alpha", "deg"), ("beta", "deg")):
            object.__setattr__(self, name, _checks.finite(f"{name} of {self.label}", getattr(self, name), unit))

    @property
    def label(self) -> str:
        return f"S({self.i},{self.j})"

    def A(self, arm: PlanarArm) -> float:
        return self.a / arm.r[self.i - 1]  # 003 Eq. (12a)

    def B(self, arm: PlanarArm) -> float:
        return self.b / arm.r[self.j - 1]  # 003 Eq. (12b)


def check_arm(arm) -> PlanarArm:
    """``arm`` if it is a :class:`PlanarArm`."""
    return _checks.instance("arm", arm, PlanarArm, "PlanarArm(r, s, m, g)")


def check_springs(arm, springs, *, criteria: bool = False) -> tuple:
    """``springs`` as a tuple of :class:`PlanarSpring`, each fitting ``arm`` (:func:`check_spring`)."""
    check_arm(arm)
    if isinstance(springs, str | PlanarSpring) or not hasattr(springs, "__iter__"):
        raise SpringlabError(f"springs must be a sequence of PlanarSpring, got {springs!r}")
    springs = tuple(springs)
    for sp in springs:
        check_spring(arm, sp, criteria=criteria)
    return springs


def check_spring(arm: PlanarArm, sp: PlanarSpring, *, criteria: bool = True) -> None:
    """Raise unless S(i,j) fits the arm, k > 0, 0 < A, B <= 1 and (with ``criteria``)
    its angles obey C1 (ground springs) or C2 (the others)."""
    check_arm(arm)
    _checks.instance("spring", sp, PlanarSpring, "PlanarSpring(i, j, k, a, b, alpha, beta)")
    if not (1 <= sp.i < sp.j <= arm.n) or int(sp.i) != sp.i or int(sp.j) != sp.j:
        raise SpringlabError(f"{sp.label}: need integers 1 <= i < j <= {arm.n}")
    if not (np.isfinite(sp.k) and sp.k > 0):
        raise SpringlabError(f"{sp.label}: stiffness k = {sp.k} N/m must be > 0")
    for name, v in (("A", sp.A(arm)), ("B", sp.B(arm))):
        if not (np.isfinite(v) and 0 < v <= 1 + 1e-12):
            raise SpringlabError(f"{sp.label}: attachment ratio {name} = {v:.6g} must lie in (0, 1] "
                                 f"(a = {sp.a} m, b = {sp.b} m)")
    if criteria:
        role_pattern(sp)


def wrap_degrees(x: float) -> float:
    """``x`` (deg) in [0, 360)."""
    return float(np.mod(_checks.finite("x", x, "deg"), 360.0))


def role_pattern(sp: PlanarSpring) -> str:
    """Which of S(i,j)'s pseudo-stiffnesses balance, by criteria C1 and C2 (Section 3.2):
    'mono' (one joint spanned: its single term), 'ground' ((90, 0): the K_{1,v}),
    'proximal' ((0, 0): the K_{i,v}) or 'distal' ((180, 180): the K_{u,j})."""
    _checks.instance("spring", sp, PlanarSpring, "PlanarSpring(i, j, k, a, b, alpha, beta)")
    a, b = wrap_degrees(sp.alpha), wrap_degrees(sp.beta)
    if sp.j == sp.i + 1:
        want = 90.0 if sp.i == 1 else 0.0
        if np.isclose(wrap_degrees(a - b), want) or np.isclose(wrap_degrees(a - b), want + 360.0):
            return "mono"
        raise SpringlabError(f"{sp.label} ({sp.alpha:g}, {sp.beta:g}) breaks {'C1' if sp.i == 1 else 'C2'}: "
                             f"a spring over one joint needs alpha - beta = {want:g} deg")
    if sp.i == 1:
        if np.isclose(a, 90.0) and np.isclose(b, 0.0):
            return "ground"
        raise SpringlabError(f"{sp.label} ({sp.alpha:g}, {sp.beta:g}) breaks C1: a ground spring needs (90, 0) deg")
    if np.isclose(a, 0.0) and np.isclose(b, 0.0):
        return "proximal"
    if np.isclose(a, 180.0) and np.isclose(b, 180.0):
        return "distal"
    raise SpringlabError(f"{sp.label} ({sp.alpha:g}, {sp.beta:g}) breaks C2: a spring off the ground needs "
                         "(0, 0) or (180, 180) deg")


def relative_angles(theta, n: int) -> np.ndarray:
    """Joint angles theta_2..theta_n (rad) as an (N, n-1) array, validated."""
    n = _checks.links(n, "n")
    theta = _checks.real_array("theta (joint angles)", theta, finite_only=False)
    if theta.ndim == 1:
        theta = theta[None]
    if theta.ndim != 2 or theta.shape[1] != n - 1 or not np.all(np.isfinite(theta)):
        raise SpringlabError(f"theta (joint angles) must be finite with shape (N, {n - 1}) in rad, got {theta.shape}")
    if theta.shape[0] == 0:
        raise SpringlabError("theta (joint angles) holds no pose: give at least one")
    return theta


def to_spatial(arm: PlanarArm, springs):
    """The same arm as a springlab :class:`~springlab.model.chain.Chain` (revolute joints about
    z, x_1 vertical) and its springs as 000 :class:`~springlab.model.springs.Spring` objects on
    the joint lines (signed a, b): possible when every spring obeys C1/C2."""
    springs = check_springs(arm, springs)
    from springlab.model.chain import serial_chain
    from springlab.model.springs import Spring

    chain = serial_chain(r=arm.r[1:], d=arm.s[1:], m=arm.m[1:], g=arm.g, joints=[(0.0, 0.0, 1.0)] * (arm.n - 1))
    out = []
    for sp in springs:
        check_spring(arm, sp)
        if sp.i == 1:  # 000 measures a ground attachment along the vertical x_1
            sa = {90.0: 1.0, 270.0: -1.0}.get(round(wrap_degrees(sp.alpha), 9))
        else:
            sa = {0.0: 1.0, 180.0: -1.0}.get(round(wrap_degrees(sp.alpha), 9))
        sb = {0.0: 1.0, 180.0: -1.0}.get(round(wrap_degrees(sp.beta), 9))
        if sa is None or sb is None:
            raise SpringlabError(f"{sp.label} ({sp.alpha:g}, {sp.beta:g}): only attachments on the joint lines map to 000")
        out.append(Spring(sp.i, sp.j, a=sa * sp.a, b=sb * sp.b, k=sp.k))
    return chain, out


def spatial_angles(theta) -> np.ndarray:
    """003 joint angles (N, n-1) as the revolute angles of :func:`to_spatial`'s chain,
    (N, n-1, 3): link 2 turns from the vertical x_1, so its angle is theta_2 - 90 deg."""
    theta = np.atleast_2d(_checks.real_array("theta (joint angles)", theta))
    if theta.ndim != 2 or theta.size == 0:
        raise SpringlabError(f"theta (joint angles) must have shape (N, n-1) with N >= 1, got {theta.shape}")
    out = np.zeros(theta.shape + (3,))
    out[..., 0] = theta
    out[:, 0, 0] -= np.pi / 2
    return out


# --- the workspace and the index ------------------------------------------------------------------
@dataclass(frozen=True)
class Workspace:
    """Joint ranges theta_2..theta_n in degrees, low <= high (Table 3)."""

    low: tuple
    high: tuple

    def __post_init__(self):
        lo, hi = (np.atleast_1d(_checks.real_array(name, value, finite_only=False))
                  for name, value in (("low", self.low), ("high", self.high)))
        if lo.shape != hi.shape or lo.ndim != 1 or lo.size == 0:
            raise SpringlabError(f"low and high need one entry per joint, got {lo.shape} and {hi.shape}")
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            raise SpringlabError("joint ranges must be finite (deg)")
        for k, (a, b) in enumerate(zip(lo, hi, strict=True)):
            if a > b:
                raise SpringlabError(f"joint {k + 2}'s range is reversed: low {a:g} deg > high {b:g} deg")
        object.__setattr__(self, "low", tuple(lo.tolist()))
        object.__setattr__(self, "high", tuple(hi.tolist()))

    @property
    def joints(self) -> int:
        return len(self.low)

    def grid(self, step: float) -> list[np.ndarray]:
        """Each joint's grid (rad): low, low + step, ... up to high, both ends included
        when (high - low) is a multiple of the step; a zero-width range gives one value."""
        step = _checks.positive("step", step, unit="deg")
        counts = [int(np.floor((b - a) / step + 1e-9)) + 1 for a, b in zip(self.low, self.high, strict=True)]
        _checks.memory(f"a grid with step = {step:g} deg", sum(counts), hint="use a larger step")
        axes = []
        for a, b in zip(self.low, self.high, strict=True):
            count = int(np.floor((b - a) / step + 1e-9)) + 1
            axes.append(np.radians(a + step * np.arange(count)))
        return axes

    def grid_poses(self, step: float) -> np.ndarray:
        """Every pose of :meth:`grid` (rad), (points, joints), the last joint varying fastest."""
        return np.stack(np.meshgrid(*self.grid(step), indexing="ij"), -1).reshape(-1, self.joints)

    def grid_size(self, step: float) -> int:
        """Points of :meth:`grid`, counted without building it (exact, a Python int)."""
        step = _checks.positive("step", step, unit="deg")
        return math.prod(int(np.floor((b - a) / step + 1e-9)) + 1 for a, b in zip(self.low, self.high, strict=True))

    def sample(self, count: int, seed) -> np.ndarray:
        """``count`` poses uniform in the box (rad), (count, joints)."""
        count = _checks.sample_count(count, least=1, name="sample count")
        rng = np.random.default_rng(seed)
        return np.radians(rng.uniform(self.low, self.high, (int(count), self.joints)))
