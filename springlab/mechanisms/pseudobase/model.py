r"""The pseudobase arm of Lin, Shieh and Chen (2010), paper 001: its kinematics and modules.

The model shared by the three routes (:mod:`~springlab.mechanisms.pseudobase.subsystems` route 1, :mod:`~springlab.mechanisms.pseudobase.geometry`
route 2, :mod:`~springlab.mechanisms.pseudobase.simulation` route 3): standard DH kinematics, the arm with its
RSSR modules, the equilibrator springs, fold margins, mobility and added inertia.

The gravity energy of n serial links is a sum of n *rotational subsystems*
(001 Eqs. 5-8): subsystem i is a point mass mu_i at sigma_i, a vector fixed
in link i, so its energy depends on link i's orientation only. Each one is
balanced like a single-link equilibrator (001 Eqs. 9-18) by one zero-free-length
spring from a point B_i of link i to a point A_i of a *pseudobase*, a body
that keeps the line C_i A_i vertical. A spatial parallelogram RSSR module per
link keeps the pseudobases vertical (Section 4); their own masses and those
of the auxiliary links fold into combined subsystems (001 Eqs. 21-25).

One module, link i, seen across the vertical parallelogram O_{i-1} C_i D_i Ô_{i-1}
(frames i and î stay parallel; Ô = O + h up everywhere)::

      Ô_{i-1} o- - - - - - - - - - -o D_i        auxiliary link î (revolute at Ô_{i-1},
        h |    auxiliary link î      |            spherical at D_i)
          |                     A_i  o  pseudobase i: C_i D_i stays vertical,
          |                          |\           A_i is l_CA above C_i
      O_{i-1} o--------------------- o C_i \ spring K_i (zero free length)
        joint i     link i            `----o B_i  l_CB from C_i along sigma_i

Conventions (stated, tested):

* standard DH (001 Table 1): ^{i-1}T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i);
  frame i is fixed on link i with origin O_i on the axis z_i of joint i+1;
  frame 0 is the ground's and the world frame; ``up`` is a unit vector in it
  (gravity acts along -up);
* link vectors r_i = O_{i-1} - O_i in frame i (001 Eq. 2): r_i = -(a_i, d_i sin alpha_i,
  d_i cos alpha_i);
* the auxiliary chain is the primary chain translated by the vertical vector
  ``aux_offset`` (the parallelogram branch of every RSSR module, Section 4.1),
  so vectors in frame î have the same coordinates as in frame i;
* links are numbered 1..n as in the paper (link 0 is the ground); arrays are
  0-based: ``m[i - 1]`` is m_i.

The subsystems and why only the product mu_i sigma_i is physical: :mod:`~springlab.mechanisms.pseudobase.subsystems`.

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general spatial
serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003. doi:10.1115/1.4001816
"""


from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from springlab import _checks
from springlab._checks import masses, vector_rows
from springlab.errors import SpringlabError
from springlab.tables import Table


# --- DH kinematics (001 Table 1) -------------------------------------------------
@dataclass(frozen=True)
class DH:
    """Standard Denavit-Hartenberg parameters of an all-revolute chain.

    :ivar d: (n,) offsets along z_{i-1} (m)
    :ivar a: (n,) lengths along x_i (m)
    :ivar alpha: (n,) twists about x_i (rad)

    >>> dh = DH(d=[0.0, 0.0], a=[0.4, 0.3], alpha=[0.0, 0.0])
    >>> R, org = dh.frames([0.0, 0.0])
    >>> org[-1].round(3).tolist()
    [0.7, 0.0, 0.0]
    >>> dh.link_vectors()[0].round(3).tolist()   # r_1 = O_0 - O_1 in frame 1
    [-0.4, -0.0, -0.0]
    """

    d: np.ndarray
    a: np.ndarray
    alpha: np.ndarray

    def __post_init__(self):
        arrays = [np.atleast_1d(_checks.real_array(f"DH parameter {k}", getattr(self, k), finite_only=False))
                  for k in ("d", "a", "alpha")]
        if len({x.shape for x in arrays}) != 1 or arrays[0].ndim != 1 or arrays[0].size == 0:
            raise SpringlabError(f"d, a, alpha must be 1-d arrays of one length, got shapes {[x.shape for x in arrays]}")
        for k, x in zip(("d", "a", "alpha"), arrays, strict=True):
            if not np.all(np.isfinite(x)):
                raise SpringlabError(f"DH parameter {k} must be finite, got {x.tolist()}")
            object.__setattr__(self, k, x)

    @property
    def n(self) -> int:
        return self.d.size

    def check_angles(self, q) -> np.ndarray:
        """Joint angles as an (N, n) array (rad); one pose (n,) becomes (1, n)."""
        q = _checks.real_array("joint angles q (poses)", q, finite_only=False)
        if q.ndim == 1:
            q = q[None]
        if q.ndim != 2 or q.shape[1] != self.n or not np.all(np.isfinite(q)):
            raise SpringlabError(f"joint angles must be finite with shape (N, {self.n}) in rad, got shape {q.shape}")
        if q.shape[0] == 0:
            raise SpringlabError("joint angles q (poses) hold no pose: give at least one")
        return q

    def frames(self, q):
        """Frames 0..n for joint angles q: rotations (..., n+1, 3, 3) and origins (..., n+1, 3),
        in frame 0 (m). One pose (n,) gives unbatched arrays."""
        single = np.ndim(q) == 1
        q = self.check_angles(q)
        N = q.shape[0]
        R = np.empty((N, self.n + 1, 3, 3))
        org = np.empty((N, self.n + 1, 3))
        R[:, 0], org[:, 0] = np.eye(3), 0.0
        ca, sa = np.cos(self.alpha), np.sin(self.alpha)
        for i in range(self.n):
            ct, st = np.cos(q[:, i]), np.sin(q[:, i])
            A = np.zeros((N, 3, 3))  # Rz(theta) Rx(alpha)
            A[:, 0, 0], A[:, 0, 1], A[:, 0, 2] = ct, -st * ca[i], st * sa[i]
            A[:, 1, 0], A[:, 1, 1], A[:, 1, 2] = st, ct * ca[i], -ct * sa[i]
            A[:, 2, 1], A[:, 2, 2] = sa[i], ca[i]
            p = np.stack([self.a[i] * ct, self.a[i] * st, np.full(N, self.d[i])], axis=1)
            R[:, i + 1] = R[:, i] @ A
            org[:, i + 1] = org[:, i] + np.einsum("nij,nj->ni", R[:, i], p)
        return (R[0], org[0]) if single else (R, org)

    def link_vectors(self) -> np.ndarray:
        """r_i = O_{i-1} - O_i in frame i (001 Eq. 2), (n, 3) in m."""
        return -np.stack([self.a, self.d * np.sin(self.alpha), self.d * np.cos(self.alpha)], axis=1)


# --- the arm with its modules -------------------------------------------------------
@dataclass(frozen=True)
class PseudobaseArm:
    """A serial arm with an RSSR module (auxiliary link + pseudobase) on some links.

    :ivar dh: the primary chain (:class:`DH`)
    :ivar m: (n,) link masses m_i (kg); 0 where a link's mass does not matter
    :ivar s: (n, 3) COM of link i from O_i, in frame i (m)
    :ivar modules: links (1-based) that carry a module and a spring, a range k..n
        with k = 1, or k = 2 when joint 1 is vertical (link 1's energy then never changes)
    :ivar m_hat, s_hat: auxiliary link masses (kg) and COMs from Ô_i in frame î (m)
    :ivar m_star: pseudobase masses (kg)
    :ivar c: (n, 3) spherical joint C_i from O_i in frame i (m)
    :ivar aux_offset: (3,) Ô_i - O_i in frame 0 (m); must be vertical (Section 4.2)
    :ivar star_height: pseudobase COM above C_i on the vertical line C_i D_i (m);
        None puts it half-way to D_i. It never changes the energy's variation.
    :ivar g: gravitational acceleration (m/s^2); up: (3,) unit vector, frame 0
    """

    dh: DH
    m: np.ndarray
    s: np.ndarray
    modules: tuple
    m_hat: np.ndarray
    s_hat: np.ndarray
    m_star: np.ndarray
    c: np.ndarray
    aux_offset: np.ndarray
    star_height: float | None = None
    g: float = 9.81
    up: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))

    def __post_init__(self):
        n = _checks.instance("dh", self.dh, DH, "DH (the primary chain's Denavit-Hartenberg parameters)").n
        set_ = lambda k, v: object.__setattr__(self, k, v)  # noqa: E731
        set_("m", masses("m", self.m, n))
        set_("m_hat", masses("m_hat", self.m_hat, n))
        set_("m_star", masses("m_star", self.m_star, n))
        for k in ("s", "s_hat", "c"):
            set_(k, vector_rows(k, getattr(self, k), n))
        if isinstance(self.modules, str) or not hasattr(self.modules, "__iter__"):
            raise SpringlabError(f"modules must be the links k..{n} with k = 1 or 2, got {self.modules!r}")
        modules = tuple(_checks.count("each of modules", i, least=1) for i in self.modules)
        if not modules or modules != tuple(range(modules[0], n + 1)) or modules[0] not in (1, 2):
            raise SpringlabError(f"modules must be the links k..{n} with k = 1 or 2, got {self.modules!r}")
        set_("modules", modules)
        set_("g", _checks.positive("g", self.g, unit="m/s^2"))
        up = _checks.real_array("up", self.up, finite_only=False)
        if up.shape != (3,) or not np.isclose(np.linalg.norm(up), 1.0, atol=1e-12):
            raise SpringlabError(f"up must be a unit 3-vector, got {self.up!r}")
        set_("up", up)
        offset = _checks.real_array("aux_offset", self.aux_offset, finite_only=False)
        if offset.shape != (3,) or not np.all(np.isfinite(offset)) or np.linalg.norm(offset) == 0:
            raise SpringlabError(f"aux_offset must be a non-zero finite 3-vector (m), got {self.aux_offset!r}")
        tilt = np.degrees(np.arccos(np.clip(abs(offset @ up) / np.linalg.norm(offset), -1.0, 1.0)))
        if tilt > 1e-6:
            raise SpringlabError(
                f"aux_offset {offset.tolist()} is {tilt:.3g} deg from vertical: the first joint pair "
                "(a joint and its auxiliary joint) must lie in one vertical plane with O Ô vertical "
                "(001 Section 4.2), or the pseudobases do not stay vertical")
        set_("aux_offset", offset)
        if modules[0] == 2:
            z0 = np.array([0.0, 0.0, 1.0])  # joint 1's axis in frame 0
            angle = np.degrees(np.arccos(np.clip(abs(z0 @ up), -1.0, 1.0)))
            if angle > 1e-6:
                raise SpringlabError(
                    f"joint 1's axis is {angle:.3g} deg from vertical, so link 1's subsystem energy "
                    "changes and the first joint pair is not vertical: give link 1 a module "
                    "(modules starting at 1)")
        free = [i for i in range(1, n + 1) if i not in modules and (self.m_hat[i - 1] or self.m_star[i - 1])]
        if free:
            raise SpringlabError(f"links {free} have no module but auxiliary or pseudobase masses")
        if self.star_height is None:
            set_("star_height", float(np.linalg.norm(offset)) / 2)
        else:
            set_("star_height", _checks.finite("star_height", self.star_height, "m"))

    @property
    def n(self) -> int:
        return self.dh.n

    @property
    def h(self) -> float:
        """Length of the vertical sides O_i Ô_i = C_i D_i of the parallelograms (m)."""
        return float(np.linalg.norm(self.aux_offset))

    def link_vectors(self) -> np.ndarray:
        return self.dh.link_vectors()


# --- equilibrator springs (001 Eqs. 13-16) ---------------------------------------------
@dataclass(frozen=True)
class Equilibrator:
    """Spring i between B_i on link i and A_i on pseudobase i, zero free length.

    :ivar link: i (1-based); K: stiffness (N/m); l_CA, l_CB: |C_i A_i|, |C_i B_i| (m)
    :ivar b: (3,) B_i from O_i in frame i (m), 001 Eq. (14); c: (3,) C_i from O_i in frame i (m)
    """

    link: int
    K: float
    l_CA: float
    l_CB: float
    b: np.ndarray
    c: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "link", _checks.count("link of an equilibrator", self.link, least=1))
        # K = 0 is the spring removed (a control), not an error
        object.__setattr__(self, "K", _checks.positive(f"K of spring {self.link}", self.K, allow_zero=True,
                                                       unit="N/m"))
        for name in ("l_CA", "l_CB"):
            object.__setattr__(self, name, _checks.positive(f"{name} of spring {self.link}", getattr(self, name),
                                                            allow_zero=True, unit="m"))
        for name in ("b", "c"):
            object.__setattr__(self, name, _checks.real_array(f"{name} of spring {self.link}", getattr(self, name),
                                                              shape=(3,)))

    def scaled(self, factor: float) -> Equilibrator:
        return Equilibrator(self.link, self.K * factor, self.l_CA, self.l_CB, self.b, self.c)


def check_arm(arm) -> PseudobaseArm:
    """``arm`` if it is a :class:`PseudobaseArm`."""
    return _checks.instance("arm", arm, PseudobaseArm, "PseudobaseArm (e.g. springlab.papers.lin2010.arm())")


def check_springs(arm, springs) -> tuple:
    """``springs`` as a tuple of :class:`Equilibrator`, each on a link of ``arm`` that has a module."""
    check_arm(arm)
    if isinstance(springs, str | Equilibrator) or not hasattr(springs, "__iter__"):
        raise SpringlabError(f"springs must be a sequence of Equilibrator, got {springs!r}")
    springs = tuple(springs)
    for sp in springs:
        _checks.instance("each of springs", sp, Equilibrator, "Equilibrator (design_equilibrators(arm, K, l_CA))")
        if sp.link not in arm.modules:
            raise SpringlabError(f"spring {sp.link} is on a link without a module (modules {arm.modules})")
    return springs


def attachment_a(arm: PseudobaseArm, springs, q) -> np.ndarray:
    """A_i from O_i in frame i at each pose, (N, k, 3) m (001 Eq. 13: a_i - c_i = l_CA up).

    A_i is fixed on the pseudobase, not on link i: its coordinates in frame i
    depend on the pose (001 Table 3 prints them at the initial pose)."""
    springs = check_springs(arm, springs)
    R, _ = arm.dh.frames(arm.dh.check_angles(q))
    out = []
    for sp in springs:
        up_local = R[:, sp.link].transpose(0, 2, 1) @ arm.up
        out.append(sp.c + sp.l_CA * up_local)
    return np.stack(out, axis=1)


# --- route 2: direct geometry ------------------------------------------------------------
def world_point(R, org, k, local):
    return org[:, k] + np.einsum("nij,j->ni", R[:, k], local)


def fold_margin(arm: PseudobaseArm, q) -> np.ndarray:
    """How far each RSSR module is from folding, (N, k), in [-1, 1].

    The vertical component of the unit direction in which C_i moves when joint i
    turns: up . (z_{i-1} x rho) / |rho|, rho the part of O_{i-1} C_i normal to the
    joint axis z_{i-1}. Zero when the crank O_{i-1} C_i is vertical (the parallelogram
    collapses onto its vertical side and can switch branch) or the axis is vertical.
    """
    check_arm(arm)
    R, org = arm.dh.frames(arm.dh.check_angles(q))
    return np.stack([_module_margin(R, org, i, arm.c[i - 1], arm.up) for i in arm.modules], axis=1)


def _module_margin(R, org, i, c_i, up) -> np.ndarray:
    """Module i's fold margin (N,) on the frames R, org, with C_i at c_i (m, frame i)."""
    z = R[:, i - 1, :, 2]
    rho = world_point(R, org, i, c_i) - org[:, i - 1]
    rho = rho - np.sum(rho * z, axis=-1, keepdims=True) * z
    norm = np.linalg.norm(rho, axis=-1)
    if np.any(norm == 0):
        raise SpringlabError(f"C_{i} lies on joint {i}'s axis: module {i} cannot turn its auxiliary link")
    return np.cross(z, rho) @ up / norm


# --- mobility (001 Eqs. 19-20) --------------------------------------------------------------
def mobility(links: int, joint_freedoms, lam: int = 6) -> int:
    """Gruebler-Kutzbach mobility F = lam (n - j - 1) + sum f_i (001 Eqs. 19-20).

    :param links: n, the number of links including the ground
    :param joint_freedoms: f_i of each of the j joints (1 revolute, 3 spherical)
    :param lam: 6 in space, 3 in the plane

    >>> mobility(4, [1, 3, 3, 1])   # one RSSR linkage, 001 Eq. (19): one active + one idle DOF
    2
    """
    if lam not in (3, 6):
        raise SpringlabError(f"lam must be 3 (planar) or 6 (spatial), got {lam}")
    if int(links) != links or links < 1:
        raise SpringlabError(f"links must be an integer >= 1 (ground included), got {links}")
    f = [int(x) for x in joint_freedoms]
    if any(x != y for x, y in zip(f, joint_freedoms, strict=True)) or any(x < 1 or x >= lam for x in f):
        raise SpringlabError(f"joint freedoms must be integers in 1..{lam - 1}, got {list(joint_freedoms)}")
    return lam * (int(links) - len(f) - 1) + sum(f)


def module_chain_mobility(n: int) -> int:
    """Mobility of n RSSR modules along n primary links (001 Eq. 20): 3n moving links
    plus the ground, 2n revolute and 2n spherical joints: F = 2n (n active, n idle spins)."""
    n = _checks.links(n, "n", least=1)
    return mobility(3 * n + 1, [1] * (2 * n) + [3] * (2 * n))


# --- added inertia ------------------------------------------------------------------------------
def joint_space_inertia(arm: PseudobaseArm, q, *, gyration: float = 0.05,
                        parts=("primary", "aux", "pseudobase")) -> np.ndarray:
    """The joint-space mass matrix M(q), (N, n, n) in kg m^2, of the chosen parts.

    Each primary and auxiliary link is its mass at its COM with an isotropic
    radius of gyration ``gyration`` (m) (the paper gives no inertia tensors);
    an auxiliary link moves as link i translated, a pseudobase translates with
    C_i (its idle spin is not driven). M = sum m (J_v^T J_v + rho^2 J_w^T J_w).
    """
    check_arm(arm)
    unknown = set(parts) - {"primary", "aux", "pseudobase"}
    if unknown:
        raise SpringlabError(f"parts must be among 'primary', 'aux', 'pseudobase', got {sorted(unknown)}")
    if not (np.isfinite(gyration) and gyration >= 0):
        raise SpringlabError(f"gyration must be >= 0 m, got {gyration}")
    q = arm.dh.check_angles(q)
    R, org = arm.dh.frames(q)
    N, n = q.shape
    M = np.zeros((N, n, n))
    bodies = []  # (link i, point in world, mass, rotates)
    for i in range(1, n + 1):
        if "primary" in parts:
            bodies.append((i, world_point(R, org, i, arm.s[i - 1]), arm.m[i - 1], True))
        if i in arm.modules and "aux" in parts:
            bodies.append((i, world_point(R, org, i, arm.s_hat[i - 1]), arm.m_hat[i - 1], True))
        if i in arm.modules and "pseudobase" in parts:
            bodies.append((i, world_point(R, org, i, arm.c[i - 1]), arm.m_star[i - 1], False))
    for i, p, mass, rotates in bodies:
        Jv = np.zeros((N, 3, n))
        Jw = np.zeros((N, 3, n))
        for j in range(i):  # joint j+1 turns about z_j through O_j
            z = R[:, j, :, 2]
            Jv[:, :, j] = np.cross(z, p - org[:, j])
            Jw[:, :, j] = z
        M += mass * np.einsum("nki,nkj->nij", Jv, Jv)
        if rotates:
            M += mass * gyration**2 * np.einsum("nki,nkj->nij", Jw, Jw)
    return M


def fold_crossings(t, margin, links) -> list[tuple[float, int]]:
    """Times (s) at which a module's fold margin changes sign along a sampled path,
    by linear interpolation: [(t, link), ...] in time order.

    :param t: (T,) s; margin: (T, k) from :func:`fold_margin`; links: the k module links
    """
    t, margin = np.asarray(t, dtype=float), np.asarray(margin, dtype=float)
    out = []
    for col, link in enumerate(links):
        y = margin[:, col]
        for k in np.flatnonzero(np.sign(y[:-1]) * np.sign(y[1:]) < 0):
            out.append((float(t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])), int(link)))
    return sorted(out)


# --- the auxiliary chain from its own DH table; moving a module clear of its folds ---------------
def aux_offset_from_dh(primary: DH, aux: DH, up=(0.0, 0.0, 1.0)) -> np.ndarray:
    """Ô_i - O_i (m, frame 0) from the two DH tables of 001 Table 1.

    The auxiliary chain must be the primary one lifted along the first joint's
    axis: equal tables except d^_1, and that axis vertical. Otherwise the first
    joint pair (joint 1 and its auxiliary joint) does not lie in one vertical
    plane with a vertical O_0 Ô_0 (001 Section 4.2), and the error says so.
    """
    if primary.n != aux.n:
        raise SpringlabError(f"the auxiliary DH table has {aux.n} rows, the primary {primary.n}")
    for name in ("d", "a", "alpha"):
        p, a = getattr(primary, name), getattr(aux, name)
        start = 1 if name == "d" else 0
        if not np.allclose(p[start:], a[start:], atol=1e-12):
            raise SpringlabError(f"auxiliary DH parameter {name} {a.tolist()} differs from the primary {p.tolist()}: "
                                 "the auxiliary chain must be the primary one translated (only d^_1 may differ)")
    up = np.asarray(up, dtype=float)
    angle = np.degrees(np.arccos(np.clip(abs(up[2]) / np.linalg.norm(up), -1.0, 1.0)))  # z_0 = (0, 0, 1)
    if angle > 1e-6:
        raise SpringlabError(f"the first joint pair is not vertical: joint 1's axis is {angle:.3g} deg from up, so "
                             "lifting the auxiliary chain by d^_1 along it does not keep the pseudobases vertical")
    return (aux.d[0] - primary.d[0]) * np.array([0.0, 0.0, 1.0])


def rotate_crank(arm: PseudobaseArm, link: int, angle: float) -> PseudobaseArm:
    """The arm with C_link turned by ``angle`` (rad) about joint ``link``'s axis (kept at
    its distance from the axis): 001 Section 4.1 leaves C_i free on link i, and where it
    sits decides the poses at which module ``link`` folds. The pseudobase's mass moves
    with it, so redesign the springs after."""
    check_arm(arm)
    link = _checks.count("link", link, least=1)
    angle = _checks.finite("angle", angle, "rad")
    import dataclasses

    if link not in arm.modules:
        raise SpringlabError(f"link {link} has no module (modules {arm.modules})")
    c = arm.c.copy()
    c[link - 1] = _turned_crank(arm, link, angle)
    return dataclasses.replace(arm, c=c)


def crank_margins(arm: PseudobaseArm, link: int, q, angles) -> np.ndarray:
    """Module ``link``'s fold margin (:func:`fold_margin`) at each pose of q with C_link turned by
    each of ``angles`` (rad, :func:`rotate_crank`): (N, A). The frames are computed once for all
    the turns (the turn moves C_link on its link, not the links); each turn's margins are
    :func:`fold_margin`'s, to the last bit."""
    check_arm(arm)
    link = _checks.count("link", link, least=1)
    if link not in arm.modules:
        raise SpringlabError(f"link {link} has no module (modules {arm.modules})")
    angles = np.atleast_1d(_checks.real_array("angles (rad)", angles))
    if angles.ndim != 1 or angles.size == 0:
        raise SpringlabError(f"angles must be a non-empty 1-D array of turns of C_{link} (rad), got shape {angles.shape}")
    R, org = arm.dh.frames(arm.dh.check_angles(q))
    return np.stack([_module_margin(R, org, link, _turned_crank(arm, link, a), arm.up) for a in angles], axis=1)


def _turned_crank(arm: PseudobaseArm, link: int, angle: float) -> np.ndarray:
    """C_link (m, frame link) turned by ``angle`` (rad) about joint ``link``'s axis (Rodrigues)."""
    alpha = arm.dh.alpha[link - 1]
    axis = np.array([0.0, np.sin(alpha), np.cos(alpha)])  # z_{i-1} in frame i
    r = arm.link_vectors()[link - 1]  # O_{i-1} in frame i
    v = arm.c[link - 1] - r
    turned = (v * np.cos(angle) + np.cross(axis, v) * np.sin(angle)
              + axis * (axis @ v) * (1 - np.cos(angle)))  # Rodrigues
    return r + turned


def clearest_crank(arm: PseudobaseArm, link: int, q, samples: int = 360) -> tuple[float, float]:
    """The turn of C_link about its joint axis (rad, in [-pi, pi)) that keeps module
    ``link`` furthest from folding over the poses q, and that smallest |fold margin|."""
    samples = _checks.count("samples", samples, least=1)
    angles = np.linspace(-np.pi, np.pi, int(samples), endpoint=False)  # crank_margins checks the arm and link
    worst = np.min(np.abs(crank_margins(arm, link, q, angles)), axis=0)
    best = int(np.argmax(worst))
    return float(angles[best]), float(worst[best])


def cost_table(arm: PseudobaseArm, springs, q) -> Table:
    """What the modules cost the arm: springs, mass of links 2..n (kg) with and without the
    auxiliary links and pseudobases, each joint's inertia (kg m^2, :func:`joint_space_inertia`)
    at the first pose of ``q`` and its largest increase along ``q``, and the sum of the stiffnesses."""
    springs = check_springs(arm, springs)
    bare_mass = float(arm.m[1:].sum())
    added = float(arm.m_hat.sum() + arm.m_star.sum())
    M_bare = joint_space_inertia(arm, q, parts=("primary",))
    M_all = joint_space_inertia(arm, q)
    ratio = np.diagonal(M_all, axis1=1, axis2=2) / np.diagonal(M_bare, axis1=1, axis2=2)
    rows = [("springs", "0", f"{len(springs)}", ""),
            (f"mass of links 2-{arm.n} (kg)", f"{bare_mass:.2f}", f"{bare_mass + added:.2f}", f"+{100 * added / bare_mass:.1f} %"),
            ("  of which auxiliary links / pseudobases (kg)", "", f"{arm.m_hat.sum():.2f} / {arm.m_star.sum():.2f}", "")]
    for j in range(1, arm.n):
        rows.append((f"inertia at joint {j + 1}, initial pose (kg m^2)", f"{M_bare[0, j, j]:.3f}", f"{M_all[0, j, j]:.3f}",
                     f"+{100 * (ratio[0, j] - 1):.0f} % (up to +{100 * (ratio[:, j].max() - 1):.0f} % along the path)"))
    rows.append(("sum of stiffnesses (kN/m)", "", f"{sum(s.K for s in springs) / 1e3:.0f}", ""))
    return Table(["", "bare arm", "with the modules", "change"], rows)
