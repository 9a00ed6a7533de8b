r"""Route 1 for paper 001: the rotational subsystems (001 Eqs. 5-8, 21-25) and the
equilibrator springs they call for (001 Eqs. 13-16).

The gravity energy of n serial links is a sum of n rotational subsystems
-mu_i g . sigma_i, each fixed in one link; this module computes them from the
arm's data, the energy they give, and one spring per module that balances each.
It never places a body in space (that is :mod:`~springlab.mechanisms.pseudobase.geometry`, route 2).

Only the product mu_i sigma_i is physical
-----------------------------------------
001 Eq. (5) fixes the vector mu_i sigma_i = m_i s_i - (sum_{j>=i} m_j) r_i (kg m),
the first moment of subsystem i. 001 Eq. (7)'s mu_i = m_i + sum_{j>=i} m_j (which
counts m_i twice) is a normalisation: any mu_i > 0 with sigma_i = (mu_i
sigma_i) / mu_i gives the same energy -mu_i g . sigma_i, and the same spring
through 001 Eq. (16), K l_CA l_CB = mu_i g |sigma_i|. :func:`subsystems` takes
``mu`` to show it:

>>> import numpy as np
>>> m, s, r = [2.0, 1.0], [[0.1, 0, 0], [0.2, 0, 0]], [[-0.3, 0, 0], [-0.4, 0, 0]]
>>> mu, sigma = subsystems(m, s, r)               # 001 Eq. (7)
>>> mu2, sigma2 = subsystems(m, s, r, mu=[1.0, 1.0])
>>> bool(np.allclose(mu[:, None] * sigma, mu2[:, None] * sigma2))
True

References
----------
Lin, P.-Y., Shieh, W.-B., Chen, D.-Z. (2010). Design of a gravity-balanced general
spatial serial-type manipulator. Journal of Mechanisms and Robotics 2(3), 031003.
doi:10.1115/1.4001816
"""

from __future__ import annotations

import numpy as np

from springlab import _checks
from springlab._checks import masses, vector_rows
from springlab.errors import SpringlabError, UnbalanceableError
from springlab.mechanisms.pseudobase.model import (
    Equilibrator,
    PseudobaseArm,
    check_arm,
)


# --- subsystems (001 Eqs. 5-8, 21-25) -------------------------------------------------
def subsystem_moments(m, s, r) -> np.ndarray:
    """mu_i sigma_i = m_i s_i - (sum_{j>=i} m_j) r_i, (n, 3) in kg m (001 Eq. 5): the
    physical content of a subsystem, in frame i."""
    m = _checks.real_array("m", m)
    if m.ndim != 1 or m.size == 0:
        raise SpringlabError(f"m must be n >= 1 masses (kg), got shape {m.shape}")
    s, r = _checks.real_array("s", s, shape=(m.size, 3)), _checks.real_array("r", r, shape=(m.size, 3))
    beyond = np.cumsum(m[::-1])[::-1]  # sum_{j>=i} m_j
    return m[:, None] * s - beyond[:, None] * r


def subsystems(m, s, r, mu=None):
    """(mu, sigma) of the n rotational subsystems (001 Eqs. 6-8).

    :param m: (n,) masses (kg); s: (n, 3) COMs from O_i; r: (n, 3) link vectors, frame i (m)
    :param mu: (n,) normalising masses (kg, > 0); None: 001 Eq. (7), mu_i = m_i + sum_{j>=i} m_j
    :returns: mu (n,) kg, sigma (n, 3) m with mu_i sigma_i = 001 Eq. (5)'s first moment
    """
    m = masses("m", m, len(np.atleast_1d(m)))
    n = m.size
    s, r = vector_rows("s", s, n), vector_rows("r", r, n)
    moment = subsystem_moments(m, s, r)
    if mu is None:
        mu = m + np.cumsum(m[::-1])[::-1]  # 001 Eq. (7)
    mu = np.asarray(mu, dtype=float)
    if mu.shape != (n,) or not np.all(np.isfinite(mu)) or np.any(mu <= 0):
        raise SpringlabError(f"mu must be {n} masses > 0 kg, got {mu!r}")
    return mu, moment / mu[:, None]  # 001 Eq. (8)


def combined_subsystems(arm: PseudobaseArm, mu=None):
    """Combined (mu~, sigma~) with the auxiliary links and pseudobases (001 Eqs. 24-25).

    Each body's mass is m_i + m^_i + m*_i; its first moment about O_i is
    m_i s_i + m^_i s^_i + m*_i c_i (frame i = frame î), and the mass beyond link i
    acts at -r_i (r^_i = r_i on the parallelogram branch). The constant height
    of the pseudobase's COM above C_i drops out (001 Eq. 23).
    """
    check_arm(arm)
    total = arm.m + arm.m_hat + arm.m_star
    first = arm.m[:, None] * arm.s + arm.m_hat[:, None] * arm.s_hat + arm.m_star[:, None] * arm.c
    beyond = np.cumsum(total[::-1])[::-1]
    moment = first - beyond[:, None] * arm.link_vectors()  # numerator of 001 Eq. (25)
    if mu is None:
        mu = total + beyond  # 001 Eq. (24)
    mu = np.asarray(mu, dtype=float)
    if mu.shape != (arm.n,) or np.any(~np.isfinite(mu)) or np.any(mu <= 0):
        raise SpringlabError(f"mu must be {arm.n} masses > 0 kg, got {mu!r}")
    return mu, moment / mu[:, None]


def subsystem_energy(arm: PseudobaseArm, q, mu, sigma) -> np.ndarray:
    """Route 1: sum_i -mu_i g . sigma_i = sum_i mu_i g up . (R_i sigma_i), (N,) J (001 Eq. 6).

    Equal to the direct-geometry gravity energy up to a constant."""
    check_arm(arm)
    R, _ = arm.dh.frames(arm.dh.check_angles(q))
    world = np.einsum("nkij,kj->nki", R[:, 1:], np.asarray(sigma, dtype=float))
    return arm.g * np.einsum("k,nk->n", np.asarray(mu, dtype=float), world @ arm.up)


def design_equilibrators(arm: PseudobaseArm, K, l_CA, *, max_l_CB: float | None = None,
                         l_CB=None) -> tuple[Equilibrator, ...]:
    """One spring per module from K_i and l_CA,i, with l_CB,i from 001 Eq. (16):
    K_i l_CA,i l_CB,i = mu~_i g |sigma~_i|, and B_i on the line through C_i along
    sigma~_i (001 Eq. 14).

    :param K: stiffnesses (N/m, > 0), one per module; l_CA: (m, > 0)
    :param max_l_CB: the longest distance C_i B_i link i allows (m); a spring that
        needs more cannot be attached and raises :class:`~springlab.errors.UnbalanceableError`
    :param l_CB: given lengths instead of 001 Eq. (16) (e.g. a paper's rounded ones),
        for measuring what they leave unbalanced
    """
    check_arm(arm)
    k = len(arm.modules)
    K, l_CA = _checks.real_array("K", K, finite_only=False), _checks.real_array("l_CA", l_CA, finite_only=False)
    max_l_CB = _checks.optional_positive("max_l_CB", max_l_CB, "m")
    for name, v in (("K", K), ("l_CA", l_CA)):
        if v.shape != (k,) or not np.all(np.isfinite(v)):
            raise SpringlabError(f"{name} must have {k} finite values (one per module), got {v!r}")
        bad = np.flatnonzero(v <= 0)
        if bad.size:
            unit = "N/m" if name == "K" else "m"
            raise SpringlabError(f"{name} of spring {arm.modules[bad[0]]} = {v[bad[0]]} {unit}: must be > 0")
    mu, sigma = combined_subsystems(arm)
    out = []
    for col, i in enumerate(arm.modules):
        length = float(np.linalg.norm(sigma[i - 1]))
        if length == 0.0:
            raise UnbalanceableError(f"subsystem {i} has no first moment (sigma~_{i} = 0): it needs no spring; "
                                     "remove its module")
        need = mu[i - 1] * arm.g * length / (K[col] * l_CA[col])  # 001 Eq. (16)
        if l_CB is not None:
            need = float(np.asarray(l_CB, dtype=float)[col])
        if max_l_CB is not None and need > max_l_CB:
            raise UnbalanceableError(
                f"spring {i} cannot be attached: 001 Eq. (16) needs l_CB = {need:.4g} m > max_l_CB = {max_l_CB} m; "
                f"raise K_{i} or l_CA,{i}")
        b = arm.c[i - 1] + need * sigma[i - 1] / length  # 001 Eq. (14)
        out.append(Equilibrator(i, float(K[col]), float(l_CA[col]), float(need), b, arm.c[i - 1].copy()))
    return tuple(out)


# --- the derivation of 001 Eqs. (4)-(8), in sympy ---------------------------------------------
def symbolic_subsystems(n: int) -> dict:
    """001 Eqs. (4)-(8) for n links in sympy, with the dot products g . s_i and g . r_i
    as symbols (the energy is linear in them).

    :returns: dict of sympy expressions: 'eq4' (the sum of 001 Eq. (4) over the links),
        'eq5', 'eq6' (with mu_i, sigma_i of 001 Eqs. (7)-(8)); each is the total gravity
        energy, and their differences expand to 0.

    >>> import sympy as sp
    >>> e = symbolic_subsystems(3)
    >>> sp.simplify(e["eq4"] - e["eq5"]), sp.simplify(e["eq5"] - e["eq6"])
    (0, 0)
    """
    import sympy as sp

    n = _checks.links(n, "n", least=1)
    m = sp.symbols(f"m1:{n + 1}", positive=True)
    gs = sp.symbols(f"gs1:{n + 1}", real=True)  # g . s_i
    gr = sp.symbols(f"gr1:{n + 1}", real=True)  # g . r_i
    eq4 = sum(-m[i] * (gs[i] - sum(gr[j] for j in range(i + 1))) for i in range(n))  # 001 Eqs. (3)-(4)
    eq5 = -sum(m[i] * gs[i] - sum(m[j] for j in range(i, n)) * gr[i] for i in range(n))  # 001 Eq. (5)
    mu = [m[i] + sum(m[j] for j in range(i, n)) for i in range(n)]  # 001 Eq. (7)
    g_sigma = [(m[i] * gs[i] - sum(m[j] for j in range(i, n)) * gr[i]) / mu[i] for i in range(n)]  # 001 Eq. (8)
    eq6 = -sum(mu[i] * g_sigma[i] for i in range(n))  # 001 Eq. (6)
    return {"eq4": eq4, "eq5": eq5, "eq6": eq6, "mu": mu, "g_sigma": g_sigma}
