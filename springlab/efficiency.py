r"""Spring efficiency of planar balanced arms: Juang, Jhuang and Chen (2022), paper 003.

A planar serial arm with revolute joints: link 1 is the ground (a horizontal
reference of length r_1, 1 m in the paper), links 2..n move; theta_j is link j's
angle to link j-1 and Theta_{u,v} = theta_{u+1} + ... + theta_v (Eq. 3), so
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
gravity's G_{1,u} = |G_{1,u}| cos(90 deg - Theta_{1,u}) (Eqs. 6-7) and the
spring's K^S_{u,v} = amplitude cos(phase - Theta_{u,v}) (Eqs. 11a-d)::

    K_{i,j} = k A B cos(alpha - beta + 180 - Theta_ij)     (11a)
    K_{i,v} = k A   cos(alpha + 180 - Theta_iv),  v < j     (11b)
    K_{u,j} = k B   cos(-beta - Theta_uj),        u > i     (11c)
    K_{u,v} = k     cos(-Theta_uv),               i < u < v < j   (11d)

with A = a / r_i, B = b / r_j (Eq. 12). A :class:`Term` holds one of them.

The planar form is the spatial one of paper 000 (:mod:`springlab.quadratic`)
restricted to a vertical plane. With 000's vertical x_1 in place of the
horizontal ground link, a term amplitude cos(phase - Theta_uv) r_u r_v is
C_uv x_u . x_v + S_uv (x_u x x_v) . n with C = amplitude r_u r_v cos(phase')
and S = amplitude r_u r_v sin(phase'). For the attachment angles that criteria
C1 and C2 allow ((90, 0) on the ground, (0, 0) or (180, 180) elsewhere), S = 0
and C is exactly 000's entry G_{1,u} or K_S(i,j)_{u,v} (Eqs. 18, 23a-d) for a
spring with signed distances on the joint lines: :func:`to_spatial` gives that
chain and those springs, and the tests check the entries equal. Other angles
need the S part, which 000's springs (attached on the link lines) never have.
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass

import numpy as np

from springlab.errors import SpringlabError, UnbalanceableError

__all__ = [
    "PlanarArm",
    "PlanarSpring",
    "Term",
    "Workspace",
    "CONFIGURATIONS",
    "gravity_terms",
    "spring_terms",
    "terms",
    "term_values",
    "relative_angles",
    "quadratic_energy",
    "direct_energy",
    "to_spatial",
    "spatial_angles",
    "spatial_coefficients",
    "spring_efficiency",
    "system_efficiency",
    "efficiency_index",
    "balance_equations",
    "solve_configuration",
    "design",
    "payload_adjustment",
    "READINGS",
    "com_distances",
    "optimise_index",
    "Optimum",
]

READINGS = ("magnitudes", "literal", "direct")


# --- the arm and its springs -------------------------------------------------------------
@dataclass(frozen=True)
class PlanarArm:
    """A planar arm; index 0 of each array is link 1, the ground.

    :ivar r: (n,) lengths r_1..r_n (m); r_1 is the ground's reference length
    :ivar s: (n,) COM distances from the proximal joint (m); s_1 unused
    :ivar m: (n,) masses (kg); m_1 unused
    :ivar g: gravitational acceleration (m/s^2)

    >>> arm = PlanarArm(r=[1.0, 0.36, 0.445, 0.3], s=[0, 0.18, 0.2225, 0.15], m=[0, 25, 26, 18], g=9.8)
    >>> arm.G.round(1).tolist()   # |G_12|, |G_13|, |G_14| (N/m), Eq. (7)
    [553.7, 303.8, 88.2]
    """

    r: np.ndarray
    s: np.ndarray
    m: np.ndarray
    g: float = 9.81

    def __post_init__(self):
        r, s, m = (np.atleast_1d(np.asarray(getattr(self, k), dtype=float)) for k in ("r", "s", "m"))
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
        if not (np.isfinite(self.g) and self.g > 0):
            raise SpringlabError(f"g must be > 0 m/s^2, got {self.g}")
        for k, v in (("r", r), ("s", s), ("m", m)):
            object.__setattr__(self, k, v)

    @property
    def n(self) -> int:
        return self.r.size

    @property
    def G(self) -> np.ndarray:
        """|G_{1,u}| for u = 2..n (N/m), Eq. (7)."""
        out = []
        for u in range(2, self.n + 1):
            beyond = self.m[u:].sum()  # m_{u+1} .. m_n
            out.append(self.m[u - 1] * self.g * self.s[u - 1] / (self.r[0] * self.r[u - 1]) + self.g * beyond / self.r[0])
        return np.array(out)

    def with_payload(self, mass: float) -> PlanarArm:
        """The arm with ``mass`` (kg) added at the end link's COM (Eq. 32)."""
        if not (np.isfinite(mass) and mass >= 0):
            raise SpringlabError(f"payload must be >= 0 kg, got {mass}")
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

    @property
    def label(self) -> str:
        return f"S({self.i},{self.j})"

    def A(self, arm: PlanarArm) -> float:
        return self.a / arm.r[self.i - 1]  # Eq. (12a)

    def B(self, arm: PlanarArm) -> float:
        return self.b / arm.r[self.j - 1]  # Eq. (12b)


def check_spring(arm: PlanarArm, sp: PlanarSpring, *, criteria: bool = True) -> None:
    """Raise unless S(i,j) fits the arm, k > 0, 0 < A, B <= 1 and (with ``criteria``)
    its angles obey C1 (ground springs) or C2 (the others)."""
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


def _angle(x: float) -> float:
    return float(np.mod(x, 360.0))


def role_pattern(sp: PlanarSpring) -> str:
    """Which of S(i,j)'s pseudo-stiffnesses balance, by criteria C1 and C2 (Section 3.2):
    'mono' (one joint spanned: its single term), 'ground' ((90, 0): the K_{1,v}),
    'proximal' ((0, 0): the K_{i,v}) or 'distal' ((180, 180): the K_{u,j})."""
    a, b = _angle(sp.alpha), _angle(sp.beta)
    if sp.j == sp.i + 1:
        want = 90.0 if sp.i == 1 else 0.0
        if np.isclose(_angle(a - b), want) or np.isclose(_angle(a - b), want + 360.0):
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


# --- pseudo-stiffness terms (Eqs. 6-7, 11a-d) ----------------------------------------------
@dataclass(frozen=True)
class Term:
    """One pseudo-stiffness amplitude cos(phase - Theta_{u,v}) (N/m; phase in deg).

    source: 'G' (gravity) or a spring's label; role: 'gravity', 'balancing' or 'balanced'."""

    source: str
    u: int
    v: int
    amplitude: object
    phase: float
    role: str


def gravity_terms(G) -> list[Term]:
    """G_{1,u} = |G_{1,u}| cos(90 - Theta_{1,u}) (Eq. 6), u = 2..n."""
    return [Term("G", 1, u, G[u - 2], 90.0, "gravity") for u in range(2, len(G) + 2)]


def spring_terms(i, j, k, A, B, alpha, beta, *, label=None, pattern=None) -> list[Term]:
    """The (j-i)(j-i+1)/2 pseudo-stiffnesses of S(i,j), Eqs. (11a-d); k, A, B may be
    numbers or sympy expressions. ``pattern`` (see :func:`role_pattern`) sets the roles;
    None leaves them 'balancing'."""
    label = label or f"S({i},{j})"
    out = [Term(label, i, j, k * A * B, alpha - beta + 180.0, "")]  # (11a)
    out += [Term(label, i, v, k * A, alpha + 180.0, "") for v in range(i + 1, j)]  # (11b)
    out += [Term(label, u, j, k * B, -beta, "") for u in range(i + 1, j)]  # (11c)
    out += [Term(label, u, v, k, 0.0, "") for u in range(i + 1, j) for v in range(u + 1, j)]  # (11d)

    def role(t):
        if pattern in (None, "mono"):
            return "balancing"
        if pattern in ("ground", "proximal"):
            return "balancing" if t.u == i else "balanced"
        return "balancing" if t.v == j else "balanced"  # distal

    return [Term(t.source, t.u, t.v, t.amplitude, t.phase, role(t)) for t in out]


def terms(arm: PlanarArm, springs, *, criteria: bool = True) -> list[Term]:
    """Gravity's and every spring's pseudo-stiffness terms, with their roles (C1, C2)."""
    out = gravity_terms(arm.G)
    for sp in springs:
        check_spring(arm, sp, criteria=criteria)
        pattern = role_pattern(sp) if criteria else None
        out += spring_terms(sp.i, sp.j, sp.k, sp.A(arm), sp.B(arm), sp.alpha, sp.beta, label=sp.label, pattern=pattern)
    return out


def relative_angles(theta, n: int) -> np.ndarray:
    """Joint angles theta_2..theta_n (rad) as an (N, n-1) array, validated."""
    theta = np.asarray(theta, dtype=float)
    if theta.ndim == 1:
        theta = theta[None]
    if theta.ndim != 2 or theta.shape[1] != n - 1 or not np.all(np.isfinite(theta)):
        raise SpringlabError(f"joint angles must be finite with shape (N, {n - 1}) in rad, got {theta.shape}")
    return theta


def _Theta(theta, u, v):
    """Theta_{u,v} = theta_{u+1} + ... + theta_v (Eq. 3); theta[:, 0] is theta_2."""
    return theta[:, u - 1:v - 1].sum(axis=1)


def term_values(term_list, theta) -> np.ndarray:
    """Each term's value (N/m) at each pose, (N, T)."""
    theta = np.asarray(theta, dtype=float)
    return np.stack([float(t.amplitude) * np.cos(np.radians(t.phase) - _Theta(theta, t.u, t.v))
                     for t in term_list], axis=1)


# --- energies: route 1 (pseudo-stiffness) and route 2 (geometry) ------------------------------
def quadratic_energy(arm: PlanarArm, springs, theta) -> np.ndarray:
    """Route 1: U = sum r_u r_v (pseudo-stiffness) + sum_S k (a^2 + b^2 + sum r_t^2) / 2
    (Eqs. 5, 10), in J, (N,). Heights from the base joint."""
    theta = relative_angles(theta, arm.n)
    tl = terms(arm, springs, criteria=False)
    values = term_values(tl, theta)
    scale = np.array([arm.r[t.u - 1] * arm.r[t.v - 1] for t in tl])
    const = sum(0.5 * sp.k * (sp.a**2 + sp.b**2 + np.sum(arm.r[sp.i:sp.j - 1] ** 2)) for sp in springs)
    return values @ scale + const


def _direction(angle):
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def direct_energy(arm: PlanarArm, springs, theta) -> dict:
    """Route 2: place the joints, COMs and attachment points in the plane and sum
    m g h and k |AB|^2 / 2. Returns {'gravity', 'springs', 'total'}, each (N,) in J."""
    theta = relative_angles(theta, arm.n)
    for sp in springs:
        check_spring(arm, sp, criteria=False)
    N = theta.shape[0]
    absolute = np.concatenate([np.zeros((N, 1)), np.cumsum(theta, axis=1)], axis=1)  # Theta_{1,j}, j = 1..n
    x = _direction(absolute)  # (N, n, 2) link directions; the ground's is horizontal
    joints = np.zeros((N, arm.n, 2))  # J_1 (base) .. J_n (distal end of link n)
    for j in range(2, arm.n + 1):
        joints[:, j - 1] = joints[:, j - 2] + arm.r[j - 1] * x[:, j - 1]
    gravity = np.zeros(N)
    for j in range(2, arm.n + 1):
        com = joints[:, j - 2] + arm.s[j - 1] * x[:, j - 1]
        gravity += arm.m[j - 1] * arm.g * com[:, 1]
    elastic = np.zeros(N)
    for sp in springs:
        A = joints[:, sp.i - 1] + sp.a * _direction(absolute[:, sp.i - 1] + np.radians(sp.alpha))
        B = joints[:, sp.j - 2] + sp.b * _direction(absolute[:, sp.j - 1] + np.radians(sp.beta))
        elastic += 0.5 * sp.k * np.sum((B - A) ** 2, axis=1)
    return {"gravity": gravity, "springs": elastic, "total": gravity + elastic}


def to_spatial(arm: PlanarArm, springs):
    """The same arm as a springlab :class:`~springlab.chain.Chain` (revolute joints about
    z, x_1 vertical) and its springs as 000 :class:`~springlab.springs.Spring` objects on
    the joint lines (signed a, b): possible when every spring obeys C1/C2."""
    from springlab.chain import serial_chain
    from springlab.springs import Spring

    chain = serial_chain(r=arm.r[1:], d=arm.s[1:], m=arm.m[1:], g=arm.g, joints=[(0.0, 0.0, 1.0)] * (arm.n - 1))
    out = []
    for sp in springs:
        check_spring(arm, sp)
        if sp.i == 1:  # 000 measures a ground attachment along the vertical x_1
            sa = {90.0: 1.0, 270.0: -1.0}.get(round(_angle(sp.alpha), 9))
        else:
            sa = {0.0: 1.0, 180.0: -1.0}.get(round(_angle(sp.alpha), 9))
        sb = {0.0: 1.0, 180.0: -1.0}.get(round(_angle(sp.beta), 9))
        if sa is None or sb is None:
            raise SpringlabError(f"{sp.label} ({sp.alpha:g}, {sp.beta:g}): only attachments on the joint lines map to 000")
        out.append(Spring(sp.i, sp.j, a=sa * sp.a, b=sb * sp.b, k=sp.k))
    return chain, out


def spatial_coefficients(arm: PlanarArm, springs) -> tuple[np.ndarray, np.ndarray]:
    """The planar energy's pose-dependent part as sum_{u<v} C_uv x_u . x_v + S_uv n . (x_u x x_v),
    in 000's frame (x_1 vertical), (n, n) upper-triangular arrays in J.

    Each term amplitude cos(phase - Theta_uv) r_u r_v splits into C = amplitude r_u r_v
    cos(phase - ref) and S = amplitude r_u r_v sin(phase - ref), ref = 90 deg on the
    ground row (000's x_1 is 003's ground link turned by 90 deg), 0 elsewhere. With C1/C2
    angles S = 0 and C equals 000's G + sum K_S off the diagonal (Eqs. 18, 23a-d)."""
    C, S = np.zeros((arm.n, arm.n)), np.zeros((arm.n, arm.n))
    for t in terms(arm, springs, criteria=False):
        ref = 90.0 if t.u == 1 else 0.0
        scale = float(t.amplitude) * arm.r[t.u - 1] * arm.r[t.v - 1]
        C[t.u - 1, t.v - 1] += scale * np.cos(np.radians(t.phase - ref))
        S[t.u - 1, t.v - 1] += scale * np.sin(np.radians(t.phase - ref))
    return C, S


def spatial_angles(theta) -> np.ndarray:
    """003 joint angles (N, n-1) as the revolute angles of :func:`to_spatial`'s chain,
    (N, n-1, 3): link 2 turns from the vertical x_1, so its angle is theta_2 - 90 deg."""
    theta = np.atleast_2d(np.asarray(theta, dtype=float))
    out = np.zeros(theta.shape + (3,))
    out[..., 0] = theta
    out[:, 0, 0] -= np.pi / 2
    return out


# --- efficiency (Eqs. 17-25) -------------------------------------------------------------------
def _balancing_groups(term_list):
    """For the 'literal' reading: each balanced term's group, the first spring with a
    balancing term on the same pair (u, v)."""
    owner = {}
    for t in term_list:
        if t.role == "balancing" and t.u > 1:
            owner.setdefault((t.u, t.v), t.source)
    groups = {}
    for col, t in enumerate(term_list):
        if t.role == "balanced":
            groups.setdefault(owner.get((t.u, t.v), f"unbalanced {t.u},{t.v}"), []).append(col)
    return list(groups.values())


def _e_sys(values, term_list, reading):
    roles = np.array([t.role for t in term_list])
    grav, bal, balancing = roles == "gravity", roles == "balanced", roles == "balancing"
    if reading == "magnitudes":  # the text: sums of magnitudes
        X = np.abs(values[:, grav]).sum(axis=1)
        Y = np.abs(values[:, bal]).sum(axis=1)
    elif reading == "literal":  # Eqs. (30a-b) as printed: |sum| per group
        X = np.abs(values[:, grav].sum(axis=1))
        Y = sum((np.abs(values[:, g].sum(axis=1)) for g in _balancing_groups(term_list)), np.zeros(len(values)))
    elif reading == "direct":  # Eq. (24) term by term
        num = np.abs(values[:, balancing]).sum(axis=1)
        return num / (num + np.abs(values[:, bal]).sum(axis=1))
    else:
        raise SpringlabError(f"reading must be one of {READINGS}, got {reading!r}")
    return (X + Y) / (X + 2 * Y)  # Eq. (25)


def system_efficiency(arm: PlanarArm, springs, theta, *, reading: str = "magnitudes") -> np.ndarray:
    """e_sys at each pose, (N,) in [0.5, 1] (Eq. 25, with X and Y read as ``reading``):

    * 'magnitudes': X, Y sums of the magnitudes of the balanced gravitational and
      elastic pseudo-stiffnesses, as Section 4.1 defines them;
    * 'literal': Eqs. (30a-b) as printed, the magnitude of each group's sum;
    * 'direct': Eq. (24) itself, balancing over all elastic pseudo-stiffnesses.
    """
    theta = relative_angles(theta, arm.n)
    tl = terms(arm, springs)
    return _e_sys(term_values(tl, theta), tl, reading)


def spring_efficiency(arm: PlanarArm, spring: PlanarSpring, theta) -> np.ndarray:
    """e = x / (x + y) (Eq. 18) at each pose, (N,): x, y the magnitudes of the spring's
    balancing and balanced pseudo-stiffnesses. 1 for a spring over one joint (Eq. 22)."""
    theta = relative_angles(theta, arm.n)
    tl = [t for t in terms(arm, [spring]) if t.role != "gravity"]
    v = np.abs(term_values(tl, theta))
    roles = np.array([t.role for t in tl])
    x, y = v[:, roles == "balancing"].sum(axis=1), v[:, roles == "balanced"].sum(axis=1)
    return x / (x + y)


# --- the workspace and the index ------------------------------------------------------------------
@dataclass(frozen=True)
class Workspace:
    """Joint ranges theta_2..theta_n in degrees, low <= high (Table 3)."""

    low: tuple
    high: tuple

    def __post_init__(self):
        lo, hi = np.atleast_1d(np.asarray(self.low, dtype=float)), np.atleast_1d(np.asarray(self.high, dtype=float))
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
        if not (np.isfinite(step) and step > 0):
            raise SpringlabError(f"grid step must be > 0 deg, got {step}")
        axes = []
        for a, b in zip(self.low, self.high, strict=True):
            count = int(np.floor((b - a) / step + 1e-9)) + 1
            axes.append(np.radians(a + step * np.arange(count)))
        return axes

    def grid_size(self, step: float) -> int:
        return int(np.prod([len(x) for x in self.grid(step)]))

    def sample(self, count: int, seed) -> np.ndarray:
        """``count`` poses uniform in the box (rad), (count, joints)."""
        if int(count) != count or count < 1:
            raise SpringlabError(f"sample count must be an integer >= 1, got {count}")
        rng = np.random.default_rng(seed)
        return np.radians(rng.uniform(self.low, self.high, (int(count), self.joints)))


def efficiency_index(arm: PlanarArm, springs, workspace: Workspace, *, step: float | None = None,
                     samples: int | None = None, seed=None, reading: str = "magnitudes",
                     chunk: int = 1 << 18, progress: bool = False) -> float:
    """The system spring efficiency index: the mean of e_sys over the workspace (Section 5).

    Sampling, stated by the arguments: ``step`` (deg), a grid with both ends included
    (:meth:`Workspace.grid`), every point weighted equally; or ``samples`` poses drawn
    uniformly with ``seed``. Memory stays bounded: the grid is walked a slice at a
    time over all but the last two joints, the samples ``chunk`` at a time.
    """
    if reading not in READINGS:
        raise SpringlabError(f"reading must be one of {READINGS}, got {reading!r}")
    if workspace.joints != arm.n - 1:
        raise SpringlabError(f"the workspace has {workspace.joints} joints, the arm {arm.n - 1}")
    if (step is None) == (samples is None):
        raise SpringlabError("give exactly one of step (a grid, deg) or samples (Monte Carlo, with seed)")
    tl = terms(arm, springs)
    from tqdm import tqdm

    if samples is not None:
        if int(samples) != samples or samples < 1:
            raise SpringlabError(f"samples must be an integer >= 1 (an empty sample has no mean), got {samples}")
        samples = int(samples)
        if seed is None:
            raise SpringlabError("Monte Carlo sampling needs a seed")
        total, done = 0.0, 0
        rng_seed = np.random.SeedSequence(seed)
        for child in tqdm(rng_seed.spawn(int(np.ceil(samples / chunk))), disable=not progress, desc="index"):
            count = min(chunk, samples - done)
            theta = workspace.sample(count, child)
            total += _e_sys(term_values(tl, theta), tl, reading).sum()
            done += count
        return total / samples
    axes = workspace.grid(step)
    split = max(0, len(axes) - 2)  # joints 2..split+1 walked, the last two vectorised
    outer, inner = axes[:split], axes[split:]
    mesh = np.meshgrid(*inner, indexing="ij")
    inner_theta = np.stack([m.ravel() for m in mesh], axis=1)  # (M, len(inner))

    def theta_in(t):
        cols = [c - split for c in range(t.u - 1, t.v - 1) if c >= split]  # theta index c <-> joint c+2
        return inner_theta[:, cols].sum(axis=1) if cols else np.zeros(len(inner_theta))

    phase = [np.radians(float(t.phase)) - theta_in(t) for t in tl]
    amp = np.array([float(t.amplitude) for t in tl])
    cos_in, sin_in = np.stack([np.cos(p) for p in phase], 1) * amp, np.stack([np.sin(p) for p in phase], 1) * amp
    outer_cols = [[c for c in range(t.u - 1, t.v - 1) if c < split] for t in tl]
    total, count = 0.0, 0
    for point in tqdm(itertools.product(*outer), total=int(np.prod([len(a) for a in outer])) if outer else 1,
                      disable=not progress, desc="index", mininterval=1.0):
        out = np.array([sum(point[c] for c in cols) for cols in outer_cols])  # Theta_out per term
        values = cos_in * np.cos(out) + sin_in * np.sin(out)  # amp cos(phase - Theta_in - Theta_out)
        e = _e_sys(values, tl, reading)
        total += e.sum()
        count += e.size
    return total / count


# --- balancing equations, configurations, design (Eqs. 16, 26-27, 32; Tables 1-2) ---------------
CONFIGURATIONS = {
    "Λ1": (((1, 2), (90.0, 0.0)),),
    "Λ2": (((1, 3), (90.0, 0.0)), ((2, 3), (0.0, 0.0))),
    "Λ3-1": (((1, 2), (90.0, 0.0)), ((1, 4), (90.0, 0.0)), ((2, 4), (0.0, 0.0)), ((3, 4), (180.0, 180.0))),
    "Λ3-2": (((1, 2), (90.0, 0.0)), ((1, 4), (90.0, 0.0)), ((2, 3), (0.0, 0.0)), ((2, 4), (180.0, 180.0))),
}
"""Table 1's efficient configurations: spring (i, j) and (alpha, beta) in degrees. Where
Table 1 gives only alpha - beta, (90, 0) or (0, 0) is used; Table 4 attaches S(3,4) at (180, 180)."""


def _configuration(config) -> tuple:
    """A configuration given by its Table 1 name ('Λ3-1', ...) or as ((i, j), (alpha, beta)) pairs."""
    if isinstance(config, str):
        if config not in CONFIGURATIONS:
            raise SpringlabError(f"unknown configuration {config!r}; Table 1's are {list(CONFIGURATIONS)}")
        return CONFIGURATIONS[config]
    return tuple(config)


def _symbols(config):
    import sympy as sp

    out = {}
    for (i, j), _ in config:
        out[(i, j)] = sp.symbols(f"k_S{i}{j} A_S{i}{j} B_S{i}{j}", positive=True)
    return out


def balance_equations(config, G=None) -> dict:
    """Eqs. (16a-b) for a configuration, in sympy: {(u, v): sum of the pair's pseudo-
    stiffness amplitudes, signed} = 0, with symbols k_Sij, A_Sij, B_Sij and |G_1u|
    (``G`` numbers instead of the symbols G_1u if given)."""
    import sympy as sp

    config = _configuration(config)
    n = max(j for (_, j), _ in config)
    syms = _symbols(config)
    Gs = [sp.Symbol(f"G_1{u}", positive=True) for u in range(2, n + 1)] if G is None else [sp.nsimplify(x) for x in G]
    eqs = {}
    all_terms = gravity_terms(Gs)
    for (i, j), (alpha, beta) in config:
        k, A, B = syms[(i, j)]
        all_terms += spring_terms(i, j, k, A, B, alpha, beta)
    for t in all_terms:
        ref = 90.0 if t.u == 1 else 0.0  # each pair's terms must be in phase or opposite
        d = _angle(t.phase - ref)
        if np.isclose(d, 0.0) or np.isclose(d, 360.0):
            sign = 1
        elif np.isclose(d, 180.0):
            sign = -1
        else:
            raise SpringlabError(f"a term of {t.source} on ({t.u},{t.v}) has phase {t.phase:g} deg: "
                                 "not an efficient attachment; Eqs. (16) need in-phase terms")
        eqs[(t.u, t.v)] = eqs.get((t.u, t.v), 0) + sign * t.amplitude
    return {key: sp.expand(v) for key, v in eqs.items()}


def solve_configuration(config, free, G=None, values=None) -> dict:
    """Solve Eqs. (16) for every parameter not in ``free`` (names like 'A_S14', or sympy
    symbols). With ``values`` ({name: number}) the free parameters are numbers, put in
    before solving. Returns {symbol: expression}; raises UnbalanceableError if no
    positive solution exists."""
    import sympy as sp

    eqs = balance_equations(config, G)
    names = {f if isinstance(f, str) else f.name for f in free}
    subs = {sp.Symbol(k, positive=True): sp.nsimplify(v) for k, v in (values or {}).items()}
    system = [e.subs(subs) for e in eqs.values()]
    params = sorted(set().union(*[e.free_symbols for e in eqs.values()]), key=lambda x: x.name)
    unknown = [x for x in params if x.name not in names and not x.name.startswith("G_")]
    sol = sp.solve([e for e in system if e != 0], unknown, dict=True)
    sol = [x for x in sol if all(v.is_positive is not False for v in x.values())]
    if not sol or any(e.subs(sol[0]).simplify() != 0 for e in system):
        raise UnbalanceableError(f"Eqs. (16) have no positive solution for {[x.name for x in unknown]} "
                                 f"with {sorted(names)} given")
    return sol[0]


@functools.lru_cache(maxsize=64)
def _symbolic_designer(cfg, names):
    """Eqs. (16) solved once, with the |G| and the chosen parameters as symbols, and
    compiled: (G values, chosen values) -> {parameter name: value}; None if sympy cannot
    solve it generally (e.g. when a chosen parameter is in fact forced)."""
    import sympy as sp

    try:
        sol = solve_configuration(cfg, list(names))
    except UnbalanceableError:
        return None
    n = max(j for (_, j), _ in cfg)
    args = [sp.Symbol(f"G_1{u}", positive=True) for u in range(2, n + 1)] + [sp.Symbol(x, positive=True) for x in names]
    if any(not expr.free_symbols <= set(args) for expr in sol.values()):
        return None
    keys = [x.name for x in sol]
    f = sp.lambdify(args, list(sol.values()), "math")
    return lambda G, values: dict(zip(keys, f(*G, *values), strict=True))


def design(arm: PlanarArm, config, choices: dict) -> list[PlanarSpring]:
    """Springs of ``config`` for the arm, from Eqs. (16) and the user's ``choices``
    ({'A_S14': 0.1, 'k_S12': 4998, ...}: enough of k, A, B to fix the rest).

    Raises :class:`UnbalanceableError` if the equations have no positive solution or
    leave a parameter undetermined, SpringlabError if an attachment falls off its link.
    """
    import sympy as sp

    cfg = _configuration(config)
    names = tuple(sorted(choices))
    fast = _symbolic_designer(cfg, names)
    if fast is not None:
        known = dict(choices) | fast(tuple(arm.G), tuple(float(choices[x]) for x in names))
    else:
        sol = solve_configuration(cfg, list(choices), G=arm.G, values=choices)
        known = dict(choices) | {x.name: (float(v) if not sp.sympify(v).free_symbols else None) for x, v in sol.items()}
    out = []
    for (i, j), (alpha, beta) in cfg:
        got = []
        for name in ("k", "A", "B"):
            value = known.get(f"{name}_S{i}{j}")
            if value is None:
                raise UnbalanceableError(f"S({i},{j}): {name}_S{i}{j} is not determined by Eqs. (16); choose it")
            if not (np.isfinite(value) and value > 0):
                raise UnbalanceableError(f"S({i},{j}): Eqs. (16) give {name}_S{i}{j} = {value:.6g}, not > 0")
            got.append(float(value))
        k, A, B = got
        spring = PlanarSpring(i, j, k, A * arm.r[i - 1], B * arm.r[j - 1], alpha, beta)
        check_spring(arm, spring)
        out.append(spring)
    return out


def payload_adjustment(arm: PlanarArm, springs, config, payload: float, *, keep: str = "stiffness",
                       mono: str = "A") -> list[PlanarSpring]:
    """Rebalance ``springs`` for a payload (kg) at the end link's COM (Eq. 32).

    :param keep: 'stiffness', Section 4.3's rule (Table 2): every k kept, the
        attachments moved; or 'attachments': every A kept (and B where Eqs. (16)
        leave it free), the stiffnesses (and the B that Eqs. 27a, c force) re-solved
    :param mono: under keep='stiffness', which of A, B moves on a spring over one
        joint, where Eqs. (16) fix only the product A B
    """
    if keep not in ("stiffness", "attachments"):
        raise SpringlabError(f"keep must be 'stiffness' or 'attachments', got {keep!r}")
    if mono not in ("A", "B"):
        raise SpringlabError(f"mono must be 'A' or 'B', got {mono!r}")
    loaded = arm.with_payload(payload)
    cfg = _configuration(config)
    if keep == "stiffness":
        choices = {}
        for sp in springs:
            tag = f"S{sp.i}{sp.j}"
            choices[f"k_{tag}"] = sp.k
            if sp.j == sp.i + 1:
                other = "B" if mono == "A" else "A"
                choices[f"{other}_{tag}"] = sp.B(arm) if other == "B" else sp.A(arm)
        return design(loaded, cfg, choices)
    # keep='attachments': every A and B kept, except the B that Eqs. (16) force (27a, 27c):
    # drop the fewest such B for a solution to exist
    base = {f"A_S{sp.i}{sp.j}": sp.A(arm) for sp in springs}
    Bs = {f"B_S{sp.i}{sp.j}": sp.B(arm) for sp in springs}
    multi = [f"B_S{sp.i}{sp.j}" for sp in springs if sp.j > sp.i + 1]
    for size in range(len(multi) + 1):
        for dropped in itertools.combinations(multi, size):
            try:
                return design(loaded, cfg, base | {k: v for k, v in Bs.items() if k not in dropped})
            except UnbalanceableError:
                continue
    raise UnbalanceableError(f"no design keeps the attachments of {config} under a payload of {payload} kg")


def com_distances(r, m, G, g: float) -> np.ndarray:
    """s_2..s_n (m) that give the printed |G_{1,u}| (N/m) by Eq. (7), for a given g:
    s_u = (|G_1u| r_1 / g - sum_{w>u} m_w) r_u / m_u.

    :param r: r_1..r_n (m); m: m_2..m_n (kg); G: |G_12|..|G_1n| (N/m)
    """
    r, m, G = (np.asarray(x, dtype=float) for x in (r, m, G))
    if not (r.size == m.size + 1 == G.size + 1):
        raise SpringlabError(f"need r_1..r_n, m_2..m_n, |G_12|..|G_1n|; got {r.size}, {m.size}, {G.size} values")
    beyond = np.r_[np.cumsum(m[::-1])[::-1][1:], 0.0]
    return (G * r[0] / g - beyond) * r[1:] / m


@dataclass(frozen=True)
class Optimum:
    """The best index found: ``choices`` (the free parameters), ``springs``, ``index``,
    and the bounds respected."""

    config: str
    choices: dict
    springs: list
    index: float
    bounds: dict
    k_max: float
    evaluations: int


def optimise_index(arm: PlanarArm, config: str, free: dict, fixed: dict, workspace: Workspace, *,
                   step: float = 5.0, k_max: float = 20000.0, start: dict | None = None) -> Optimum:
    """Maximise the efficiency index (grid ``step``, 'magnitudes' reading) over the
    parameters in ``free`` ({name: (low, high)}, e.g. {'A_S14': (0.05, 1)}), with the
    others in ``fixed``, every stiffness <= ``k_max`` (N/m) and every A, B in (0, 1]
    (scipy SLSQP from ``start``, default the middle of the bounds)."""
    from scipy.optimize import minimize

    names = list(free)
    lo = np.array([free[x][0] for x in names])
    hi = np.array([free[x][1] for x in names])
    if np.any(lo <= 0) or np.any(hi > 1 + 1e-12) or np.any(lo > hi):
        raise SpringlabError(f"bounds must satisfy 0 < low <= high <= 1, got {free}")
    x0 = np.array([(start or {}).get(x, 0.5 * (free[x][0] + free[x][1])) for x in names])
    count = [0]

    def springs_of(x):
        return design(arm, config, fixed | dict(zip(names, map(float, x), strict=True)))

    def objective(x):
        count[0] += 1
        try:
            return -efficiency_index(arm, springs_of(x), workspace, step=step)
        except SpringlabError:
            return 0.0

    def stiffness_margin(x):
        try:
            return np.array([k_max - s.k for s in springs_of(x)]) / k_max
        except SpringlabError:
            return -np.ones(len(_configuration(config)))

    res = minimize(objective, x0, method="SLSQP", bounds=list(zip(lo, hi, strict=True)),
                   constraints=[{"type": "ineq", "fun": stiffness_margin}], options={"ftol": 1e-9, "maxiter": 200})
    best = dict(zip(names, map(float, np.clip(res.x, lo, hi)), strict=True))
    springs = springs_of(list(best.values()))
    if max(s.k for s in springs) > k_max * (1 + 1e-6):
        raise UnbalanceableError(f"no design of {config} within k <= {k_max} N/m was found")
    return Optimum(config, best, springs, efficiency_index(arm, springs, workspace, step=step), dict(free), k_max, count[0])
