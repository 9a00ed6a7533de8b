r"""Route 1 for paper 003: the gravitational and elastic pseudo-stiffness terms
(003 Eqs. 5-7, 10-12) and the energy they sum to; the same terms in 000's spatial form.
Every pose-dependent energy term is a pseudo-stiffness (N/m) times r_u r_v (see
:mod:`~springlab.mechanisms.planar.model`). Route 2 (:mod:`~springlab.mechanisms.planar.geometry`) never uses them.

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

from dataclasses import dataclass

import numpy as np

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.mechanisms.planar.model import (
    PlanarArm,
    check_spring,
    check_springs,
    relative_angles,
    role_pattern,
)


# --- pseudo-stiffness terms (003 Eqs. 6-7, 11a-d) ----------------------------------------------
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
    """G_{1,u} = |G_{1,u}| cos(90 - Theta_{1,u}) (003 Eq. 6), u = 2..n; G: |G_12|..|G_1n| (N/m),
    numbers or sympy expressions."""
    if isinstance(G, str) or not hasattr(G, "__len__") or len(G) == 0:
        raise SpringlabError(f"G must be the non-empty sequence |G_12|..|G_1n| (N/m), got {G!r}")
    return [Term("G", 1, u, G[u - 2], 90.0, "gravity") for u in range(2, len(G) + 2)]


def spring_terms(i, j, k, A, B, alpha, beta, *, label=None, pattern=None) -> list[Term]:
    """The (j-i)(j-i+1)/2 pseudo-stiffnesses of S(i,j), 003 Eqs. (11a-d); k, A, B may be
    numbers or sympy expressions. ``pattern`` (see :func:`springlab.mechanisms.planar.model.role_pattern`) sets the roles;
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
    springs = check_springs(arm, springs)
    out = gravity_terms(arm.G)
    for sp in springs:
        check_spring(arm, sp, criteria=criteria)
        pattern = role_pattern(sp) if criteria else None
        out += spring_terms(sp.i, sp.j, sp.k, sp.A(arm), sp.B(arm), sp.alpha, sp.beta, label=sp.label, pattern=pattern)
    return out


def Theta(theta, u, v):
    """Theta_{u,v} = theta_{u+1} + ... + theta_v (003 Eq. 3); theta[:, 0] is theta_2."""
    theta = np.atleast_2d(_checks.real_array("theta (joint angles)", theta))
    u, v = _checks.count("u", u, least=1), _checks.count("v", v, least=1)
    if not u < v <= theta.shape[1] + 1:
        raise SpringlabError(f"need 1 <= u < v <= {theta.shape[1] + 1} (the links of theta), got u = {u}, v = {v}")
    return _theta(theta, u, v)


def _theta(theta, u, v):
    return theta[:, u - 1:v - 1].sum(axis=1)  # 003 Eq. (3), unchecked: the callers validated theta


def term_values(term_list, theta) -> np.ndarray:
    """Each term's value (N/m) at each pose, (N, T); theta (N, n-1) in rad."""
    theta = np.atleast_2d(_checks.real_array("theta (joint angles)", theta))
    if isinstance(term_list, str) or not hasattr(term_list, "__iter__"):
        raise SpringlabError(f"term_list must be a list of Term (see terms()), got {term_list!r}")
    return np.stack([float(t.amplitude) * np.cos(np.radians(t.phase) - _theta(theta, t.u, t.v))
                     for t in term_list], axis=1)


# --- energies: route 1 (pseudo-stiffness) and route 2 (geometry) ------------------------------
def _terms_at(arm: PlanarArm, springs, theta):
    """Every term's value (N/m) at each pose, its r_u r_v (m^2), and the springs' constant
    sum_S k (a^2 + b^2 + sum r_t^2) / 2 (J): the pieces of 003 Eqs. (5, 10)."""
    theta = relative_angles(theta, arm.n)
    tl = terms(arm, springs, criteria=False)
    scale = np.array([arm.r[t.u - 1] * arm.r[t.v - 1] for t in tl])
    const = sum(0.5 * sp.k * (sp.a**2 + sp.b**2 + np.sum(arm.r[sp.i:sp.j - 1] ** 2)) for sp in springs)
    return tl, term_values(tl, theta), scale, const


def quadratic_energy(arm: PlanarArm, springs, theta) -> np.ndarray:
    """Route 1: U = sum r_u r_v (pseudo-stiffness) + sum_S k (a^2 + b^2 + sum r_t^2) / 2
    (003 Eqs. 5, 10), in J, (N,). Heights from the base joint."""
    springs = check_springs(arm, springs)
    _, values, scale, const = _terms_at(arm, springs, theta)
    return values @ scale + const


def energies(arm: PlanarArm, springs, theta) -> dict:
    """Route 1 energies (J): {'gravity', 'springs', 'total'}, each (N,): gravity's terms
    (003 Eqs. 5-7), the springs' pseudo-stiffness terms and constants (003 Eqs. 10-12),
    and their sum, :func:`quadratic_energy`. Heights from the base joint."""
    springs = check_springs(arm, springs)
    tl, values, scale, const = _terms_at(arm, springs, theta)
    grav = np.array([t.source == "G" for t in tl])
    return {"gravity": values[:, grav] @ scale[grav], "springs": values[:, ~grav] @ scale[~grav] + const,
            "total": values @ scale + const}


def spatial_coefficients(arm: PlanarArm, springs) -> tuple[np.ndarray, np.ndarray]:
    """The planar energy's pose-dependent part as sum_{u<v} C_uv x_u . x_v + S_uv n . (x_u x x_v),
    in 000's frame (x_1 vertical), (n, n) upper-triangular arrays in J.

    Each term amplitude cos(phase - Theta_uv) r_u r_v splits into C = amplitude r_u r_v
    cos(phase - ref) and S = amplitude r_u r_v sin(phase - ref), ref = 90 deg on the
    ground row (000's x_1 is 003's ground link turned by 90 deg), 0 elsewhere. With C1/C2
    angles S = 0 and C equals 000's G + sum K_S off the diagonal (000 Eqs. 18, 23a-d)."""
    springs = check_springs(arm, springs)
    C, S = np.zeros((arm.n, arm.n)), np.zeros((arm.n, arm.n))
    for t in terms(arm, springs, criteria=False):
        ref = 90.0 if t.u == 1 else 0.0
        scale = float(t.amplitude) * arm.r[t.u - 1] * arm.r[t.v - 1]
        C[t.u - 1, t.v - 1] += scale * np.cos(np.radians(t.phase - ref))
        S[t.u - 1, t.v - 1] += scale * np.sin(np.radians(t.phase - ref))
    return C, S
